/* nearmiss.h - the known word closest to a mistyped one, for "did you mean ...?": a scene's
 * `sphre 0 0 0 1`, `envtex rendr`, `--sppp 4`.
 *
 *     nearmiss m;
 *     nearmiss_start(&m, "sphre");
 *     for (...) nearmiss_offer(&m, name);          // every known word
 *     const char *best = nearmiss_best(&m);        // "sphere", or NULL when none is close
 *
 * Close means an edit distance (insertions, deletions, substitutions and swaps of two neighbours,
 * each 1) of at most 1 for a word of up to 5 characters and 2 for a longer one, and never 0 (the
 * word itself is not a near miss); a word of 2 characters or fewer, or over NEARMISS_MAX_LEN, has
 * none.  Of equally close words the first offered wins.  No allocation; the strings are borrowed.
 */
#ifndef ENVTEX_NEARMISS_H
#define ENVTEX_NEARMISS_H

#define NEARMISS_MAX_LEN 64

typedef struct nearmiss {
    const char *word; /* the mistyped word */
    const char *best; /* the closest offered so far, or NULL */
    int best_dist;
} nearmiss;

void nearmiss_start(nearmiss *m, const char *word);
void nearmiss_offer(nearmiss *m, const char *candidate);
const char *nearmiss_best(const nearmiss *m);

/* The edit distance of a and b as above, or NEARMISS_MAX_LEN + 1 when either is longer. */
int nearmiss_distance(const char *a, const char *b);

#endif
