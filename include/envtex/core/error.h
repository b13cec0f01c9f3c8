/* error.h - errors as values.
 *
 * Every library function that can fail returns 0 on success and -1 on failure, and fills an
 * `error` the caller owns.  The library never prints and never exits: src/cli/main.c prints the one
 * line `envtex: FILE:LINE: what is wrong` (or `envtex: FILE: what is wrong` when no line applies).
 *
 *     error err = {0};
 *     if (imageio_read("sky.exr", &img, NULL, &err)) { error_print(&err, stderr); return 1; }
 */
#ifndef ENVTEX_ERROR_H
#define ENVTEX_ERROR_H

#include <stdio.h>

#define ERROR_FILE_MAX 1024
#define ERROR_MSG_MAX 1024

typedef struct error {
    char file[ERROR_FILE_MAX]; /* file the problem is in; "" when none */
    int line;                  /* 1-based line in that file; 0 when no line applies */
    char msg[ERROR_MSG_MAX];   /* what is wrong, one line, no trailing newline */
} error;

/* Fill `err` (if not NULL) with file, line and a printf-style message; always returns -1 so a
 * caller can write `return error_set(err, path, 0, "truncated");`.  Newlines (and carriage
 * returns) in the message and in the file name are replaced by spaces so the report stays one
 * line. */
int error_set(error *err, const char *file, int line, const char *fmt, ...)
    __attribute__((format(printf, 4, 5)));

/* Prefix an existing message: "PREFIX: old message" (keeps file and line). Returns -1. */
int error_prefix(error *err, const char *fmt, ...) __attribute__((format(printf, 2, 3)));

/* Print `envtex: FILE:LINE: msg\n` (parts that are empty are left out). */
void error_print(const error *err, FILE *out);

#endif
