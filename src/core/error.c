/* error.c - errors as values (see include/envtex/core/error.h). */
#include "envtex/core/error.h"

#include <stdarg.h>
#include <string.h>

static void one_line(char *s)
{
    for (; *s; s++)
        if (*s == '\n' || *s == '\r') *s = ' ';
}

int error_set(error *err, const char *file, int line, const char *fmt, ...)
{
    if (!err) return -1;
    snprintf(err->file, sizeof err->file, "%s", file ? file : "");
    one_line(err->file); /* a file name may hold a newline too */
    err->line = line;
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(err->msg, sizeof err->msg, fmt, ap);
    va_end(ap);
    one_line(err->msg);
    return -1;
}

int error_prefix(error *err, const char *fmt, ...)
{
    if (!err) return -1;
    char head[ERROR_MSG_MAX], old[ERROR_MSG_MAX];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(head, sizeof head, fmt, ap);
    va_end(ap);
    memcpy(old, err->msg, sizeof old);
    /* build "head: old" by hand so an over-long message is cut, not a warning */
    size_t n = strlen(head);
    if (n > sizeof err->msg - 3) n = sizeof err->msg - 3;
    memcpy(err->msg, head, n);
    memcpy(err->msg + n, ": ", 2);
    size_t room = sizeof err->msg - n - 3, m = strlen(old);
    if (m > room) m = room;
    memcpy(err->msg + n + 2, old, m);
    err->msg[n + 2 + m] = '\0';
    one_line(err->msg);
    return -1;
}

void error_print(const error *err, FILE *out)
{
    fputs("envtex: ", out);
    if (err->file[0]) {
        fputs(err->file, out);
        if (err->line > 0) fprintf(out, ":%d", err->line);
        fputs(": ", out);
    }
    fprintf(out, "%s\n", err->msg[0] ? err->msg : "unknown error");
}
