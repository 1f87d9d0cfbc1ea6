/* fuzz_file.h — for the targets whose parser reads a file rather than a
 * buffer: the fuzzer's input written to a file of this process. */
#ifndef TESTS_FUZZ_FUZZ_FILE_H
#define TESTS_FUZZ_FUZZ_FILE_H

#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <unistd.h>

static char fuzz_file__path[96];

static void fuzz_file__remove(void)
{
    unlink(fuzz_file__path);
}

/* Writes data to /tmp/dm-fuzz-NAME-PID.EXT (the same file on every call of
 * the process, removed when it exits) and returns its path; aborts when it
 * cannot, as the input would otherwise go untested. */
static const char *fuzz_file(const uint8_t *data, size_t size, const char *name, const char *ext)
{
    char *path = fuzz_file__path;
    if (!path[0]) {
        snprintf(path, sizeof fuzz_file__path, "/tmp/dm-fuzz-%s-%ld.%s", name, (long)getpid(), ext);
        atexit(fuzz_file__remove);
    }
    FILE *f = fopen(path, "wb");
    if (!f || fwrite(data, 1, size, f) != size || fclose(f) != 0)
        abort();
    return path;
}

#endif
