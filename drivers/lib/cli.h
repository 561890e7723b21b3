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
 *   wr_cli_scene_args_ok(scene, out)        after the loop: 1 when both were given, else 0 with
 *                                           "need SCENE.json and -o DIR (see --help)" printed
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

#define WR_CLI_EXIT_USAGE 2

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

#endif
