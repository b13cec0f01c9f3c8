/* error.h - errors as values: a library function that can fail returns 0 or -1 and fills an
 * `error` the caller owns; it never prints or exits.  The command line prints
 * `envtex: FILE:LINE: what is wrong`.
 *
 *     if (imageio_read("sky.exr", &img, NULL, &err)) { error_print(&err, stderr); return 1; }
 */
#ifndef ENVTEX_ERROR_H
#define ENVTEX_ERROR_H

#include <stdio.h>

#define ERROR_FILE_MAX 1024
#define ERROR_MSG_MAX  1024

typedef struct error {
    char file[ERROR_FILE_MAX]; /* file the problem is in; "" when none */
    int line;                  /* 1-based line in that file; 0 when no line applies */
    char msg[ERROR_MSG_MAX];   /* what is wrong, one line, no trailing newline */
} error;

/* Fill `err` (if not NULL) with file, line and a printf message (line breaks made spaces);
 * returns -1: `return error_set(err, path, 0, "truncated");`. */
int error_set(error *err, const char *file, int line, const char *fmt, ...)
    __attribute__((format(printf, 4, 5)));

/* "PREFIX: old message", keeping file and line; returns -1. */
int error_prefix(error *err, const char *fmt, ...) __attribute__((format(printf, 2, 3)));

/* Print `envtex: FILE:LINE: msg\n`, empty parts left out. */
void error_print(const error *err, FILE *out);

#endif
