/* fileio.h - the file operations every writer and reader shares: atomic writes (a temporary
 * file beside the target, renamed over it only when complete, so a failure never leaves a
 * partial file and an existing target stays byte-identical) and whole-file reads charged to a
 * memory budget.
 *
 *     char tmp[ERROR_FILE_MAX];
 *     FILE *f = fileio_tmp_fopen("out.pfm", tmp, &err);
 *     if (!f) return -1;
 *     ... write; if (fclose(f) != 0) { fileio_tmp_abandon(tmp); return -1; }
 *     return fileio_tmp_commit(tmp, "out.pfm", &err);
 */
#ifndef ENVTEX_FILEIO_H
#define ENVTEX_FILEIO_H

#include <stddef.h>
#include <stdio.h>

#include "envtex/core/budget.h"
#include "envtex/core/error.h"

/* Atomic-write helpers shared by the format modules: open a temporary file beside `path`
 * (its name goes to tmp_path, at least ERROR_FILE_MAX bytes; mode 0666 less the umask), and
 * commit (fsync-free rename) or abandon it (unlink).  The caller closes the descriptor (and
 * checks close / fclose) BEFORE commit.  A failed commit unlinks the temporary file itself.
 * Any output file may use them. */
int fileio_tmp_open(const char *path, char *tmp_path, error *err); /* returns an fd or -1 */
/* fileio_tmp_open as a stdio stream ("wb"); NULL on failure (nothing left behind). */
FILE *fileio_tmp_fopen(const char *path, char *tmp_path, error *err);
int fileio_tmp_commit(const char *tmp_path, const char *path, error *err);
void fileio_tmp_abandon(const char *tmp_path);

/* Read a whole regular file into *data (malloc'd, one extra 0 byte after the *size bytes; free()
 * it), its size + 1 charged to `mem` first (the caller releases it when it frees the data).
 * Errors: "cannot open: ..." (missing, a folder, not a regular file: infile_open), the budget,
 * read errors. */
int fileio_read_all(const char *path, unsigned char **data, size_t *size, budget *mem, error *err);

#endif
