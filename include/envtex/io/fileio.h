/* fileio.h - atomic writes (a temporary file beside the target, renamed over it when complete:
 * never a partial file) and whole-file reads charged to a budget, for every reader and writer.
 *
 *     FILE *f = fileio_tmp_fopen("out.pfm", tmp, &err);   // char tmp[ERROR_FILE_MAX]
 *     ... write; if (fclose(f) != 0) { fileio_tmp_abandon(tmp); return -1; }
 *     return fileio_tmp_commit(tmp, "out.pfm", &err);
 */
#ifndef ENVTEX_FILEIO_H
#define ENVTEX_FILEIO_H

#include <stddef.h>
#include <stdio.h>

#include "envtex/core/budget.h"
#include "envtex/core/error.h"

/* A temporary file beside `path` (name in tmp_path, >= ERROR_FILE_MAX bytes; mode 0666 less
 * the umask); commit renames it over `path`, abandon unlinks it.  Close it, checked, BEFORE
 * commit; a failed commit unlinks it. */
int fileio_tmp_open(const char *path, char *tmp_path, error *err); /* returns an fd or -1 */
/* The same as a "wb" stream; NULL on failure, nothing left. */
FILE *fileio_tmp_fopen(const char *path, char *tmp_path, error *err);
int fileio_tmp_commit(const char *tmp_path, const char *path, error *err);
void fileio_tmp_abandon(const char *tmp_path);

/* A regular file into *data (malloc'd, 0 after the *size bytes; free() it), size + 1 charged
 * to `mem` first (released by the caller with the data).  Fails as infile_open, on the
 * budget, on a read error. */
int fileio_read_all(const char *path, unsigned char **data, size_t *size, budget *mem, error *err);

#endif
