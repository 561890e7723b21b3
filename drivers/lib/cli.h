/* cli.h — small command-line helpers shared by the wrinkle drivers (driver-side, not a public
 * wrinkle header; compiled once as drivers/lib/cli.c and linked into every program).
 *
 * Conventions the helpers enforce, so every driver behaves alike:
 *   - numbers are parsed strictly: the whole argument must be one finite decimal/exponent number
 *     ("1e-6", "2.5", "-3"); empty strings, trailing junk ("1e-6x", "3 "), leading blanks, "nan" and
 *     "inf" are rejected;
 *   - options take their value as "--name VALUE" or "--name=VALUE";
 *   - invalid input is reported as ONE line "<program>: <reason>" on stderr and the driver exits
 *     with WR_CLI_EXIT_USAGE (2).
 *
 * API
 *   wr_cli_set_program(argv[0])             name used as the prefix of error lines (basename)
 *   wr_cli_error(fmt, ...)                  print "<program>: <message>\n" (newlines in the message
 *                                           become spaces, so the reason is always one line)
 *   wr_cli_parse_double(s, &x)              1 on success, 0 on malformed/non-finite input
 *   wr_cli_parse_long(s, &n)                1 on success, 0 on malformed/out-of-range input
 *   wr_cli_is_flag(arg, "--json")           1 when arg is exactly that boolean flag
 *   wr_cli_value(argc, argv, &i, "--x", &v) 1: argv[i] is --x, *v is its value (i advanced past it);
 *                                           0: not this option; -1: value missing (error printed)
 *   wr_cli_double(argc, argv, &i, "--x", &d) as wr_cli_value, then strict number parsing
 *                                           (-1 with the error printed when malformed)
 *   wr_cli_integer(argc, argv, &i, "--x", lo, hi, &d)  as wr_cli_double, and the number must be a
 *                                           whole number in [lo, hi] (else -1 with "--x must be an
 *                                           integer in [lo, hi]" printed); *d holds it as a double
 *   wr_cli_scene_arg(argc, argv, &i, &scene, &out)  the LAST branch of a scene driver's option loop
 *                                           (wrinkle-statics, wrinkle-tfw): -o/--output DIR, else an
 *                                           unknown option (error), else the one positional
 *                                           SCENE.json (a second one is an error). 1: taken; -1: bad
 *                                           input (error printed)
 *   wr_cli_cpu_seconds()                    this process's CPU time [s] (timings of long validation
 *                                           and bench runs on a shared machine, where wall time is not
 *                                           the work)
 *   wr_cli_load1()                          the 1-minute load average (/proc/loadavg), NAN where absent
 *   wr_cli_scene_args_ok(scene, out)        after the loop: 1 when both were given, else 0 with
 *                                           "need SCENE.json and -o DIR (see --help)" printed
 *
 * The shared argument loop (every driver's options as one table):
 *   wr_cli_parse(argc, argv, opts, n, pos, max_pos, &n_pos, usage)
 *       walks argv once: -h/--help prints usage(stdout) and returns 0 (exit 0); each wr_cli_opt
 *       matches "--name", "--name=V" or its alias; numbers are strict and range-checked, integers
 *       whole; other words are positionals (at most max_pos, "-" counts as one); anything else is
 *       one error line and -1 (exit WR_CLI_EXIT_USAGE). 1 when parsed.
 * Cleanup shared by every exit path:
 *   wr_cli_defer(fn, p)                     run fn(p) at wr_cli_exit (last registered runs first;
 *                                           up to WR_CLI_MAX_DEFER)
 *   wr_cli_exit(code)                       run the deferred cleanups, flush stdout (a failed flush
 *                                           is reported and turns code 0 or 1 into WR_CLI_EXIT_FAILURE);
 *                                           returns the code for `return wr_cli_exit(rc);`
 * Progress, warnings, results:
 *   wr_cli_progress(fmt, ...)               progress on stderr: on a terminal one line redrawn with
 *                                           '\r'; redirected (a log, a pipe) one plain line each
 *   wr_cli_progress_end()                   ends a terminal progress line ('\n'), no-op otherwise
 *                                           (wr_cli_error and wr_cli_warn call it first)
 *   wr_cli_progress_tty()                   1 when progress goes to a terminal (a driver that thins
 *                                           its redirected progress asks this, not isatty)
 *   wr_cli_warn(fmt, ...)                   "<program>: warning: <message>" (one line, stderr)
 *                                           (the plausibility warnings of issue 19 are plausible.h's)
 *   wr_cli_num(buf, n, fmt, x)              x printed with fmt, or "n/a" when not finite (no "inf"
 *                                           or "nan" is ever printed as a result)
 *   wr_cli_stdout_ok()                      flush stdout: 1 ok, else 0 with "writing standard output
 *                                           failed" printed (a full disk, a closed pipe)
 * Outputs:
 *   wr_cli_output_ok(out, inputs, n)        0 (error printed) when the output path resolves to one of
 *                                           the n input files (same device and inode: links and
 *                                           "./x" included), or exists and is neither a regular file
 *                                           nor a directory (a device such as /dev/full would be
 *                                           replaced by the temp-and-rename writer); else 1
 *   wr_cli_dir_outputs_ok(dir, names, inputs, n)  the same for DIR itself and each DIR/name; 0 (error
 *                                           printed) also when DIR exists and is not a directory
 *
 * EXIT STATUS (every driver): 0 done; 1 done with a caveat the driver names (not converged, a
 * validation miss, a budget reached); WR_CLI_EXIT_USAGE 2 bad input — the command line or an input
 * file; WR_CLI_EXIT_FAILURE 3 the input was fine but the run could not finish or write its outputs.
 *
 * EXAMPLE
 *     wr_cli_set_program(argv[0]);
 *     for (i = 1; i < argc; ++i) {
 *         int k;
 *         if ((k = wr_cli_double(argc, argv, &i, "--young", &E)) != 0) { if (k < 0) return 2; continue; }
 *         if (wr_cli_is_flag(argv[i], "--json")) { json = 1; continue; }
 *         wr_cli_error("unknown option '%s' (see --help)", argv[i]);
 *         return WR_CLI_EXIT_USAGE;
 *     }
 */
#ifndef WRINKLE_CLI_H
#define WRINKLE_CLI_H

#include <stddef.h>
#include <stdio.h>

#define WR_CLI_EXIT_USAGE 2
#define WR_CLI_EXIT_FAILURE 3
#define WR_CLI_MAX_DEFER 16

typedef enum wr_cli_kind {
    WR_CLI_FLAG = 0, /* out: int*, set to 1 */
    WR_CLI_NUMBER,   /* out: double*, strict, in [lo, hi] unless lo > hi */
    WR_CLI_INTEGER,  /* out: double*, whole, in [lo, hi] */
    WR_CLI_STRING    /* out: const char**, non-empty */
} wr_cli_kind;

typedef struct wr_cli_opt {
    const char *name;  /* "--levels" */
    const char *alias; /* "-q" or NULL */
    wr_cli_kind kind;
    void *out;
    double lo, hi;
    int *given; /* optional: set to 1 when the option appears */
} wr_cli_opt;

#if defined(__GNUC__) || defined(__clang__)
#define WR_CLI_PRINTF(a, b) __attribute__((format(printf, a, b)))
#else
#define WR_CLI_PRINTF(a, b)
#endif

void wr_cli_set_program(const char *argv0);
const char *wr_cli_program(void);
void wr_cli_error(const char *fmt, ...)
#if defined(__GNUC__) || defined(__clang__)
    __attribute__((format(printf, 1, 2)))
#endif
    ;
int wr_cli_parse_double(const char *s, double *out);
int wr_cli_parse_long(const char *s, long *out);
int wr_cli_is_flag(const char *arg, const char *name);
int wr_cli_value(int argc, char **argv, int *i, const char *name, const char **value);
int wr_cli_double(int argc, char **argv, int *i, const char *name, double *out);
int wr_cli_integer(int argc, char **argv, int *i, const char *name, double lo, double hi, double *out);
int wr_cli_scene_arg(int argc, char **argv, int *i, const char **scene_path, const char **out);
int wr_cli_scene_args_ok(const char *scene_path, const char *out);
double wr_cli_cpu_seconds(void);
double wr_cli_load1(void);
int wr_cli_parse(int argc, char **argv, const wr_cli_opt *opts, int n_opts, const char **pos, int max_pos, int *n_pos,
                 void (*usage)(FILE *));
void wr_cli_defer(void (*fn)(void *), void *p);
int wr_cli_exit(int code);
void wr_cli_progress(const char *fmt, ...) WR_CLI_PRINTF(1, 2);
void wr_cli_progress_end(void);
int wr_cli_progress_tty(void);
void wr_cli_warn(const char *fmt, ...) WR_CLI_PRINTF(1, 2);
const char *wr_cli_num(char *buf, size_t n, const char *fmt, double x);
int wr_cli_stdout_ok(void);
int wr_cli_output_ok(const char *out, const char *const *inputs, int n_inputs);
int wr_cli_dir_outputs_ok(const char *dir, const char *const *names, int n_names, const char *const *inputs,
                          int n_inputs);

#endif
