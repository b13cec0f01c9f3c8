/* fuzz.h - what every fuzz target shares (see tests/fuzz/README.md).
 *
 * A target is one file tests/fuzz/fuzz_NAME.c that defines
 *
 *     int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
 *
 * and nothing else.  It is built twice:
 *   - by `make fuzz` with clang -fsanitize=fuzzer,address,undefined (libFuzzer's own main), and
 *   - by `make test` with the project's compiler, linked with replay.c, a plain main() that
 *     replays the files named on its command line (the regression inputs and the seed corpora).
 * A target must: never print, never exit, free everything it allocated, and treat a failed read
 * (-1 with an error) as the normal outcome.  It may abort() when it finds a broken contract
 * (fuzz_check), which both builds report as a crash.
 *
 * The image readers take a path, not a buffer, so fuzz_tmpfile() puts the bytes in an anonymous
 * in-memory file (memfd_create) and returns a path to it (/proc/self/fd/N).
 */
#ifndef ENVTEX_FUZZ_H
#define ENVTEX_FUZZ_H

#include <stddef.h>
#include <stdint.h>

/* The memory budget every target passes its loader (budget.h): far below make fuzz's
 * -malloc_limit_mb and -rss_limit_mb, so a header that claims more is refused by the budget, as
 * the contract says, and one that escapes the budget (a loader that allocates before it
 * charges) fails the fuzzer as an out-of-memory or a timeout instead of passing slowly. */
#define FUZZ_MEMORY_BUDGET (64.0 * 1024 * 1024)

/* Put `data` into an in-memory file (created once, truncated and rewritten on every call) and
 * return its path, valid until the next call.  NULL if the file could not be made (the target
 * then skips the input). */
const char *fuzz_tmpfile(const uint8_t *data, size_t size);

/* abort() with a message on stderr when `ok` is 0: a contract the library broke. */
void fuzz_check(int ok, const char *what);

#endif
