/* fuzz_file.h — for the targets whose parser reads a file rather than a
 * buffer: the fuzzer's input written to a file of this process. */
#ifndef TESTS_FUZZ_FUZZ_FILE_H
#define TESTS_FUZZ_FUZZ_FILE_H

#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <unistd.h>

/* Writes data to /tmp/dm-fuzz-NAME-PID.EXT (the same file on every call of
 * the process) and returns its path; aborts when it cannot, as the input
 * would otherwise go untested. */
static const char *fuzz_file(const uint8_t *data, size_t size, const char *name, const char *ext)
{
    static char path[96];
    if (!path[0])
        snprintf(path, sizeof path, "/tmp/dm-fuzz-%s-%ld.%s", name, (long)getpid(), ext);
    FILE *f = fopen(path, "wb");
    if (!f || fwrite(data, 1, size, f) != size || fclose(f) != 0)
        abort();
    return path;
}

#endif
