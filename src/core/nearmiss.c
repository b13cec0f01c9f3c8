/* nearmiss.c - "did you mean" (see include/envtex/core/nearmiss.h). */
#include "envtex/core/nearmiss.h"

#include <string.h>

static int min3(int a, int b, int c) { return a < b ? (a < c ? a : c) : (b < c ? b : c); }

/* Optimal string alignment: Levenshtein's table plus a swap of neighbours, three rows kept. */
int nearmiss_distance(const char *a, const char *b)
{
    int n = (int)strnlen(a, NEARMISS_MAX_LEN + 1), m = (int)strnlen(b, NEARMISS_MAX_LEN + 1);
    if (n > NEARMISS_MAX_LEN || m > NEARMISS_MAX_LEN) return NEARMISS_MAX_LEN + 1;
    int rows[3][NEARMISS_MAX_LEN + 1];
    int *prev2 = rows[0], *prev = rows[1], *cur = rows[2];
    for (int j = 0; j <= m; j++) prev[j] = j; /* d(0, j) = j insertions */
    for (int i = 1; i <= n; i++) {
        cur[0] = i;
        for (int j = 1; j <= m; j++) {
            int cost = a[i - 1] != b[j - 1];
            cur[j] = min3(prev[j] + 1, cur[j - 1] + 1, prev[j - 1] + cost);
            if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1] &&
                prev2[j - 2] + 1 < cur[j])
                cur[j] = prev2[j - 2] + 1; /* "ab" -> "ba" */
        }
        int *t = prev2;
        prev2 = prev;
        prev = cur;
        cur = t;
    }
    return prev[m];
}

void nearmiss_start(nearmiss *m, const char *word)
{
    m->word = word;
    m->best = NULL;
    m->best_dist = NEARMISS_MAX_LEN + 1;
}

void nearmiss_offer(nearmiss *m, const char *candidate)
{
    size_t len = strnlen(m->word, NEARMISS_MAX_LEN + 1);
    if (len <= 2 || len > NEARMISS_MAX_LEN) return;
    int limit = len <= 5 ? 1 : 2;
    int d = nearmiss_distance(m->word, candidate);
    if (d > 0 && d <= limit && d < m->best_dist) {
        m->best = candidate;
        m->best_dist = d;
    }
}

const char *nearmiss_best(const nearmiss *m) { return m->best; }
