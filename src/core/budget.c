/* budget.c - the memory budget of one run (see include/envtex/core/budget.h). */
#include "envtex/core/budget.h"

#include <ctype.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

void budget_init(budget *b, double limit)
{
    b->limit = limit;
    b->used = 0;
    b->peak = 0;
}

int budget_charge(budget *b, double bytes, const char *file, int line, error *err,
                  const char *claim_fmt, ...)
{
    if (!b) return 0;
    if (isfinite(bytes) && bytes >= 0 && b->used + bytes <= b->limit) {
        b->used += bytes;
        if (b->used > b->peak) b->peak = b->used;
        return 0;
    }
    char claim[ERROR_MSG_MAX / 2], size[32], limit[32], used[32];
    va_list ap;
    va_start(ap, claim_fmt);
    vsnprintf(claim, sizeof claim, claim_fmt, ap);
    va_end(ap);
    budget_format(bytes, size, sizeof size);
    budget_format(b->limit, limit, sizeof limit);
    budget_format(b->used, used, sizeof used);
    if (b->used > 0)
        return error_set(err, file, line,
                         "%s = %s, beyond the memory budget of %s (%s of it in "
                         "use; envtex --memory-budget SIZE sets it)",
                         claim, size, limit, used);
    return error_set(err, file, line,
                     "%s = %s, beyond the memory budget of %s (envtex "
                     "--memory-budget SIZE sets it)",
                     claim, size, limit);
}

void budget_release(budget *b, double bytes)
{
    if (!b) return;
    b->used = b->used > bytes ? b->used - bytes : 0;
}

void budget_format(double bytes, char *buf, size_t size)
{
    static const char *const unit[] = {"KiB", "MiB", "GiB", "TiB", "PiB", "EiB"};
    if (!isfinite(bytes)) {
        snprintf(buf, size, "%g bytes", bytes);
        return;
    }
    if (bytes < 1024) {
        snprintf(buf, size, "%.0f bytes", bytes);
        return;
    }
    int u = 0;
    double v = bytes / 1024;
    while (v >= 1024 && u < 5) {
        v /= 1024;
        u++;
    }
    /* three significant digits, no trailing zeros: 3.75 GiB, 12 KiB, 512 MiB */
    int decimals = v < 10 ? 2 : v < 100 ? 1 : 0;
    snprintf(buf, size, "%.*f", decimals, v);
    char *dot = strchr(buf, '.');
    if (dot) {
        char *end = buf + strlen(buf);
        while (end > dot + 1 && end[-1] == '0') *--end = '\0';
        if (end == dot + 1) *dot = '\0';
    }
    size_t n = strlen(buf);
    snprintf(buf + n, size > n ? size - n : 0, " %s", unit[u]);
}

int budget_parse(const char *text, double *bytes)
{
    if (!text) return -1;
    size_t n = strspn(text, "0123456789."); /* a plain decimal number: no sign, exponent or hex */
    if (n == 0 || n > 30) return -1;
    char num[32];
    memcpy(num, text, n);
    num[n] = '\0';
    char *end;
    double v = strtod(num, &end);
    if (*end || !(v > 0)) return -1;
    const char *rest = text + n, *suffixes = "KMGT", *at = NULL;
    double scale = 1;
    if (*rest && (at = strchr(suffixes, toupper((unsigned char)*rest)))) {
        for (const char *s = suffixes; s <= at; s++) scale *= 1024;
        rest++;
    }
    int bytes_word = !strcmp(rest, "") || !strcmp(rest, "B") || !strcmp(rest, "b");
    if (!bytes_word && (!at || strcasecmp(rest, "iB"))) return -1;
    if (!isfinite(v * scale) || v * scale < 1) return -1;
    *bytes = floor(v * scale);
    return 0;
}
