/* sweep_docs.c — docs/sweep-files.md's key reference (sweep_keys_markdown,
 * sweep.h), written from the parser's key table through sweep_keys_at(), so
 * the reference and the parser cannot drift apart. */
#include "sweep/sweep.h"

#include <stdio.h>
#include <string.h>

/* A Markdown table cell: '|' escaped, so a type such as "a | b" stays one cell. */
static void sweep_docs__cell(dm_str *out, const char *text)
{
    dm_str_cat(out, " ");
    for (const char *p = text; *p; p++)
        dm_str_cat(out, *p == '|' ? "\\|" : (char[2]){ *p, 0 });
    dm_str_cat(out, " |");
}

void sweep_keys_markdown(dm_str *out)
{
    const char *section = NULL;
    for (size_t i = 0; i < sweep_keys_count(); i++) {
        const sweep_key *row = sweep_keys_at(i);
        if (!section || strcmp(section, row->section) != 0) {
            section = row->section;
            dm_str_printf(out, "%s### %s%s%s\n\n| key | value | default | meaning |\n|---|---|---|---|\n",
                          i ? "\n" : "", *section ? "`" : "", *section ? section : "Top level",
                          *section ? "`" : "");
        }
        char key[64];
        if (strcmp(row->name, "*") == 0)
            snprintf(key, sizeof key, "*AXIS*");
        else
            snprintf(key, sizeof key, "`%s`", row->name);
        dm_str_cat(out, "|");
        sweep_docs__cell(out, key);
        sweep_docs__cell(out, row->type);
        sweep_docs__cell(out, row->deflt);
        dm_str doc = {0};
        dm_str_cat(&doc, row->doc);
        if (row->example && strcmp(row->name, "*") == 0)
            dm_str_printf(&doc, "; e.g. `%s`", row->example);
        else if (row->example)
            dm_str_printf(&doc, "; e.g. `%s: %s`", row->name, row->example);
        sweep_docs__cell(out, dm_str_get(&doc));
        dm_str_free(&doc);
        dm_str_cat(out, "\n");
    }
}
