/* stepcheck.h - an index or coordinate that a lecture step's code produced, checked where a lookup
 * uses it: a texel's column and row, a CDF bin, a mip level, a cube face, a map's (u, v).
 *
 *     STEPCHECK_INDEX(c, el->w, "latlong", "column");     // c in [0, el->w)
 *     STEPCHECK_COORD(uv.u, 0.0, 1.0, "latlong", "u");    // uv.u in [0, 1], not NaN
 *
 * In a starter kit a student's step can hand a lookup a value out of its range (a phi not wrapped
 * to [0, 2 pi) makes a negative column): unchecked, a bare segmentation fault or a silent wrong
 * image.  Checked, the run stops with one line that names the function, the value, the valid
 * range and the step:
 *
 *     envtex: world_to_texel: column -3 is outside [0, 255]: the latlong step's code made it
 *
 * It is an assertion that stays on in every build (one branch, predicted not taken): a value out
 * of range here is a programmer error, never bad input, which is refused earlier with an error
 * value.  As assert does, it stops the process: the message on stderr, exit status 1 (nothing is
 * written: outputs are written after a render).  A test program can take the message instead
 * (stepcheck_set_handler), so that the failing test case reports it.
 */
#ifndef ENVTEX_STEPCHECK_H
#define ENVTEX_STEPCHECK_H

/* What runs on a failed check, given the whole message (no "envtex: ", no newline).  It must not
 * return.  NULL restores the default: print `envtex: MESSAGE` to stderr and exit(1). */
typedef void (*stepcheck_handler)(const char *msg);
void stepcheck_set_handler(stepcheck_handler h);

/* The failure paths of the macros below: build the message and call the handler. */
_Noreturn void stepcheck_index_fail(const char *func, const char *what, long long i, long long n,
                                    const char *step);
_Noreturn void stepcheck_coord_fail(const char *func, const char *what, double x, double lo,
                                    double hi, const char *step);

/* i must be in [0, n): one unsigned comparison */
#define STEPCHECK_INDEX(i, n, step, what)                                                          \
    do {                                                                                           \
        if (__builtin_expect((unsigned long long)(long long)(i) >=                                 \
                                 (unsigned long long)(long long)(n),                               \
                             0))                                                                   \
            stepcheck_index_fail(__func__, what, (long long)(i), (long long)(n), step);           \
    } while (0)

/* x must be in [lo, hi] (NaN fails) */
#define STEPCHECK_COORD(x, lo, hi, step, what)                                                     \
    do {                                                                                           \
        if (__builtin_expect(!((x) >= (lo) && (x) <= (hi)), 0))                                    \
            stepcheck_coord_fail(__func__, what, x, lo, hi, step);                                 \
    } while (0)

#endif
