/* replay.c - replay driver: a plain main() for a fuzz target built without libFuzzer.
 *
 *     build/fuzz/fuzz_scene tests/fuzz/corpus/scene/a.test tests/fuzz/regressions/scene/crash-1
 *
 * Calls LLVMFuzzerTestOneInput once per file named on the command line (folders are not
 * walked: the shell expands the globs).  Exits 0 when every input returned, 1 when a file could
 * not be read; a crash is a crash (and a sanitizer report under `make asan`).
 */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

static int replay(const char *path)
{
    FILE *f = fopen(path, "rb");
    if (!f) {
        perror(path);
        return -1;
    }
    size_t cap = 4096, n = 0;
    uint8_t *buf = malloc(cap);
    for (;;) {
        if (!buf) break;
        n += fread(buf + n, 1, cap - n, f);
        if (n < cap) break;
        uint8_t *more = realloc(buf, cap * 2);
        if (!more) {
            free(buf);
            buf = NULL;
            break;
        }
        buf = more;
        cap *= 2;
    }
    int bad = ferror(f) || !buf;
    fclose(f);
    if (bad) {
        fprintf(stderr, "%s: cannot read\n", path);
        free(buf);
        return -1;
    }
    /* an exact-size copy, as libFuzzer passes it, so a read one byte past the end is caught */
    uint8_t *exact = malloc(n ? n : 1);
    if (exact) {
        for (size_t i = 0; i < n; i++) exact[i] = buf[i];
        LLVMFuzzerTestOneInput(exact, n);
    }
    free(exact);
    free(buf);
    return exact ? 0 : -1;
}

int main(int argc, char **argv)
{
    int status = 0;
    for (int i = 1; i < argc; i++)
        if (replay(argv[i])) status = 1;
    return status;
}
