/* stepcheck.c - the failure side of the step checks (see include/envtex/core/stepcheck.h). */
#include "envtex/core/stepcheck.h"

#include <stdio.h>
#include <stdlib.h>

static stepcheck_handler handler;

void stepcheck_set_handler(stepcheck_handler h) { handler = h; }

static _Noreturn void stop(const char *msg)
{
    if (handler) handler(msg);
    fprintf(stderr, "envtex: %s\n", msg); /* the default, and a handler that returned */
    fflush(stderr);
    exit(1);
}

void stepcheck_index_fail(const char *func, const char *what, long long i, long long n,
                          const char *step)
{
    char msg[256];
    snprintf(msg, sizeof msg, "%s: %s %lld is outside [0, %lld]: the %s step's code made it", func,
             what, i, n - 1, step);
    stop(msg);
}

void stepcheck_coord_fail(const char *func, const char *what, double x, double lo, double hi,
                          const char *step)
{
    char msg[256];
    snprintf(msg, sizeof msg, "%s: %s = %.9g is outside [%g, %g]: the %s step's code made it", func,
             what, x, lo, hi, step);
    stop(msg);
}
