/* cli.h - what the subcommands share: option parsing, one-line errors, the memory budget, and
 * the checks made before any work.  Subcommand NAME is cmd_NAME(argc, argv) in cmd_NAME.c,
 * given the arguments after its name.  It returns the exit status: 0 done, 1 an error (one
 * line `envtex: FILE:LINE: what`, nothing written), 2 a comparison that failed.
 */
#ifndef ENVTEX_CLI_H
#define ENVTEX_CLI_H

#include "envtex/core/budget.h"
#include "envtex/core/error.h"

int cmd_render(int argc, char **argv);
int cmd_compare(int argc, char **argv);
int cmd_tonemap(int argc, char **argv);
int cmd_convert(int argc, char **argv);
int cmd_gen_env(int argc, char **argv);
int cmd_noise(int argc, char **argv);
int cmd_prefilter(int argc, char **argv);
int cmd_strata(int argc, char **argv);

/* Print *err as one line and return 1. */
int cli_fail(const error *err);

/* Print `envtex: WHAT (envtex --help for usage)`, WHAT printf'd; return 1. */
int cli_usage_error(const char *fmt, ...) __attribute__((format(printf, 1, 2)));

/* The word of the NULL-terminated `known` that `word` is a near miss of (nearmiss.h), or NULL. */
const char *cli_closest(const char *word, const char *const *known);

/* `envtex: unknown KIND 'WORD'`, with " (did you mean 'X'?)" when X of the NULL-terminated
 * `known` is a near miss of it (nearmiss.h), as cli_usage_error prints it; returns 1. */
int cli_unknown(const char *kind, const char *word, const char *const *known);

/* The whole token s as a finite double / as a long in [lo, hi]: 0, or -1 (nothing stored). */
int cli_parse_double(const char *s, double *out);
int cli_parse_long(const char *s, long lo, long hi, long *out);

/* The value after option argv[*i] (*i moved onto it), or NULL with the usage line printed. */
const char *cli_opt_value(int argc, char **argv, int *i);

/* --memory-budget SIZE at argv[*i]: budget_parse's or "none" (*limit = 0).  0, or 1 with the
 * usage line printed. */
int cli_memory_budget_option(int argc, char **argv, int *i, double *limit);

/* The run's budget of `limit` bytes in *b, or NULL for limit 0. */
budget *cli_run_budget(budget *b, double limit);

/* 1 if a and b name the same existing file (infile.h). */
int cli_same_file(const char *a, const char *b);

/* 0 if `path` has a known image extension and a temporary file can be made beside it (tried
 * now, before the work), else -1 with *err. */
int cli_check_output(const char *path, error *err);
/* The same for a PNG whatever its name (a scene's `output scene2`). */
int cli_check_output_any_name(const char *path, error *err);

/* -1 with *err if `out` is one of the n `inputs` (NULL skipped) by name or identity (`tonemap
 * a.png a.png`), else 0. */
int cli_check_not_replacing(const char *out, const char *const *inputs, int n, error *err);

#endif
