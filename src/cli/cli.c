/* cli.c - what the subcommands share (see include/envtex/cli/cli.h). */
#include "envtex/cli/cli.h"

#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "envtex/core/nearmiss.h"
#include "envtex/io/fileio.h"
#include "envtex/io/imageio.h"
#include "envtex/io/infile.h"

int cli_fail(const error *err)
{
    error_print(err, stderr);
    return 1;
}

int cli_usage_error(const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    fprintf(stderr, "envtex: ");
    vfprintf(stderr, fmt, ap);
    fprintf(stderr, " (envtex --help for usage)\n");
    va_end(ap);
    return 1;
}

const char *cli_closest(const char *word, const char *const *known)
{
    nearmiss m;
    nearmiss_start(&m, word);
    for (; *known; known++) nearmiss_offer(&m, *known);
    return nearmiss_best(&m);
}

int cli_unknown(const char *kind, const char *word, const char *const *known)
{
    const char *best = cli_closest(word, known);
    if (best) return cli_usage_error("unknown %s '%s' (did you mean '%s'?)", kind, word, best);
    return cli_usage_error("unknown %s '%s'", kind, word);
}

int cli_parse_double(const char *s, double *out)
{
    char *end;
    errno = 0;
    double v = strtod(s, &end);
    if (end == s || *end || errno == ERANGE || !isfinite(v)) return -1;
    *out = v;
    return 0;
}

int cli_parse_long(const char *s, long lo, long hi, long *out)
{
    char *end;
    errno = 0;
    long v = strtol(s, &end, 10);
    if (end == s || *end || errno == ERANGE || v < lo || v > hi) return -1;
    *out = v;
    return 0;
}

const char *cli_opt_value(int argc, char **argv, int *i)
{
    if (*i + 1 >= argc) {
        cli_usage_error("option '%s' needs a value", argv[*i]);
        return NULL;
    }
    return argv[++*i];
}

int cli_memory_budget_option(int argc, char **argv, int *i, double *limit)
{
    const char *v = cli_opt_value(argc, argv, i);
    if (!v) return 1;
    if (!strcmp(v, "none")) {
        *limit = 0;
        return 0;
    }
    if (budget_parse(v, limit))
        return cli_usage_error(
            "--memory-budget needs a size such as 512M or 4G (or 'none'), got '%s'", v);
    return 0;
}

budget *cli_run_budget(budget *b, double limit)
{
    if (limit <= 0) return NULL;
    budget_init(b, limit);
    return b;
}

int cli_same_file(const char *a, const char *b)
{
    infile_id ia, ib;
    return infile_identify(a, &ia) == 0 && infile_identify(b, &ib) == 0 && infile_same(ia, ib);
}

/* the temporary file beside path can be made (then it is removed again) */
static int check_writable(const char *path, error *err)
{
    if (!path[0]) return error_set(err, NULL, 0, "the output file name is empty");
    char tmp[ERROR_FILE_MAX];
    int fd = fileio_tmp_open(path, tmp, err);
    if (fd < 0) return -1;
    close(fd);
    fileio_tmp_abandon(tmp);
    return 0;
}

int cli_check_output(const char *path, error *err)
{
    if (path[0] && !imageio_can_write(path))
        return error_set(err, path, 0, "cannot write this format: use .exr, .png, .pfm or .hdr");
    return check_writable(path, err);
}

int cli_check_output_any_name(const char *path, error *err) { return check_writable(path, err); }

int cli_check_not_replacing(const char *out, const char *const *inputs, int n, error *err)
{
    for (int k = 0; k < n; k++)
        if (inputs[k] && (!strcmp(out, inputs[k]) || cli_same_file(out, inputs[k])))
            return error_set(err, out, 0, "the output would replace the input image %s", inputs[k]);
    return 0;
}
