/* technique.c — lookups over the registry in technique_list.c. */
#include "techniques/technique.h"

#include <pthread.h>
#include <string.h>

#include "techniques/axes.h"
#include "techniques/user_technique.h"

extern const technique_desc technique__list[];
extern const size_t technique__list_count;

#define TECHNIQUE__MAX 64
static const char *technique__names[TECHNIQUE__MAX + 1];
static pthread_once_t technique__once = PTHREAD_ONCE_INIT;

size_t technique_count(void) { return technique__list_count + user_technique_count(); }

const technique_desc *technique_at(size_t i)
{
    return i < technique__list_count ? &technique__list[i]
                                     : user_technique_at(i - technique__list_count);
}

const technique_desc *technique_find(const char *name)
{
    for (size_t i = 0; name && i < technique_count(); i++)
        if (strcmp(technique_at(i)->name, name) == 0)
            return technique_at(i);
    return NULL;
}

static void technique__init_names(void)
{
    size_t n = 0;
    for (size_t i = 0; i < technique_count() && n < TECHNIQUE__MAX; i++)
        if (!technique_at(i)->test_only)
            technique__names[n++] = technique_at(i)->name;
    technique__names[n] = NULL;
}

/* Called by user_technique.c after it registers one: the names array (the
 * technique axis's choices point at it) gets the new name in place. */
void technique__names_changed(void);
void technique__names_changed(void)
{
    pthread_once(&technique__once, technique__init_names);
    technique__init_names();
}

const char *const *technique_names(void)
{
    pthread_once(&technique__once, technique__init_names);
    return technique__names;
}

int technique_reads_axis(const technique_desc *t, const char *name)
{
    const axis_info *a = axes_find(name);
    if (!t || !a)
        return 0;
    if (a->scene)
        return 1;
    for (size_t i = 0; t->axes && t->axes[i]; i++)
        if (strcmp(t->axes[i], name) == 0)
            return 1;
    return 0;
}
