/* Tests for the driver-side CLI helpers drivers/lib/cli.{h,c}. */
#include <criterion/criterion.h>
#include <math.h>
#include <string.h>

#include "cli.h"

Test(cli, strict_double) {
    double x = 0.0;
    cr_expect(wr_cli_parse_double("1e-6", &x) && x == 1e-6);
    cr_expect(wr_cli_parse_double("-2.5", &x) && x == -2.5);
    cr_expect(wr_cli_parse_double("3", &x) && x == 3.0);
    cr_expect(wr_cli_parse_double(".5E+2", &x) && x == 50.0);
    x = 7.0;
    cr_expect(!wr_cli_parse_double("", &x));
    cr_expect(!wr_cli_parse_double(NULL, &x));
    cr_expect(!wr_cli_parse_double("1e-6x", &x));
    cr_expect(!wr_cli_parse_double(" 1", &x));
    cr_expect(!wr_cli_parse_double("1 ", &x));
    cr_expect(!wr_cli_parse_double("nan", &x));
    cr_expect(!wr_cli_parse_double("inf", &x));
    cr_expect(!wr_cli_parse_double("0x10", &x));
    cr_expect(!wr_cli_parse_double("1e999", &x));
    cr_expect(!wr_cli_parse_double("e", &x));
    cr_expect(!wr_cli_parse_double("1..2", &x));
    cr_expect_eq(x, 7.0); /* failures leave the output alone */
}

Test(cli, strict_long) {
    long n = 0;
    cr_expect(wr_cli_parse_long("42", &n) && n == 42);
    cr_expect(wr_cli_parse_long("-3", &n) && n == -3);
    cr_expect(!wr_cli_parse_long("4.2", &n));
    cr_expect(!wr_cli_parse_long("12a", &n));
    cr_expect(!wr_cli_parse_long("", &n));
    cr_expect(!wr_cli_parse_long("99999999999999999999999", &n));
    cr_expect(!wr_cli_parse_long("1-", &n));
}

Test(cli, option_values) {
    char *argv[] = {"prog", "--young", "1e5", "--young=2e5", "--youngest", "3", "--bending", "abc", "--json",
                    "--young"};
    int argc = 10, i;
    double x = 0.0;
    const char *v;
    i = 1;
    cr_expect_eq(wr_cli_double(argc, argv, &i, "--young", &x), 1);
    cr_expect(x == 1e5 && i == 2);
    i = 3;
    cr_expect_eq(wr_cli_double(argc, argv, &i, "--young", &x), 1);
    cr_expect(x == 2e5 && i == 3);
    i = 4; /* a longer option sharing the prefix is not a match */
    cr_expect_eq(wr_cli_value(argc, argv, &i, "--young", &v), 0);
    cr_expect_eq(i, 4);
    i = 6;
    cr_expect_eq(wr_cli_double(argc, argv, &i, "--bending", &x), -1); /* malformed */
    i = 9;
    cr_expect_eq(wr_cli_value(argc, argv, &i, "--young", &v), -1); /* missing value */
    cr_expect(wr_cli_is_flag(argv[8], "--json"));
    cr_expect(!wr_cli_is_flag(argv[8], "--jso"));
    wr_cli_set_program("/usr/bin/some-tool");
    cr_expect_str_eq(wr_cli_program(), "some-tool");
}

/* The shared tail of the scene drivers' option loops (wrinkle-statics, wrinkle-tfw). */
Test(cli, scene_args) {
    char *argv[] = {"prog", "scene.json", "-o", "out", "--output=o2", "-", "--bogus", "-o"};
    int argc = 8, i;
    const char *scene = NULL, *out = NULL;
    wr_cli_set_program("prog");
    i = 1;
    cr_expect_eq(wr_cli_scene_arg(argc, argv, &i, &scene, &out), 1);
    cr_expect(scene == argv[1] && i == 1);
    i = 2;
    cr_expect_eq(wr_cli_scene_arg(argc, argv, &i, &scene, &out), 1);
    cr_expect(out == argv[3] && i == 3, "-o takes the next argument");
    i = 4;
    cr_expect_eq(wr_cli_scene_arg(argc, argv, &i, &scene, &out), 1);
    cr_expect_str_eq(out, "o2");
    i = 5; /* a second positional ("-" is a file name, not an option) */
    cr_expect_eq(wr_cli_scene_arg(argc, argv, &i, &scene, &out), -1);
    cr_expect(scene == argv[1], "the first scene is kept");
    i = 6;
    cr_expect_eq(wr_cli_scene_arg(argc, argv, &i, &scene, &out), -1); /* unknown option */
    i = 7;
    cr_expect_eq(wr_cli_scene_arg(argc, argv, &i, &scene, &out), -1); /* -o without a value */
    cr_expect_eq(wr_cli_scene_args_ok(scene, out), 1);
    cr_expect_eq(wr_cli_scene_args_ok(NULL, out), 0);
    cr_expect_eq(wr_cli_scene_args_ok(scene, NULL), 0);
    scene = NULL;
    i = 5; /* "-" alone is taken as the scene file */
    cr_expect_eq(wr_cli_scene_arg(argc, argv, &i, &scene, &out), 1);
    cr_expect_str_eq(scene, "-");
}

Test(cli, integer_option) {
    char *argv[] = {"prog", "--levels", "3", "--levels=1e1", "--levels", "2.5", "--levels", "-1", "--levels=x"};
    int argc = 9, i;
    double x = -7.0;
    wr_cli_set_program("prog");
    i = 1;
    cr_expect_eq(wr_cli_integer(argc, argv, &i, "--levels", 0.0, 5.0, &x), 1);
    cr_expect(x == 3.0 && i == 2);
    i = 3; /* 10 is whole but above the range */
    cr_expect_eq(wr_cli_integer(argc, argv, &i, "--levels", 0.0, 5.0, &x), -1);
    cr_expect_eq(wr_cli_integer(argc, argv, &i, "--levels", 0.0, 10.0, &x), 1);
    cr_expect_eq(x, 10.0);
    i = 4; /* not whole */
    cr_expect_eq(wr_cli_integer(argc, argv, &i, "--levels", 0.0, 5.0, &x), -1);
    i = 6; /* below the range */
    cr_expect_eq(wr_cli_integer(argc, argv, &i, "--levels", 0.0, 5.0, &x), -1);
    i = 8; /* malformed */
    cr_expect_eq(wr_cli_integer(argc, argv, &i, "--levels", 0.0, 5.0, &x), -1);
    cr_expect_eq(x, 10.0, "failures leave the output alone");
    i = 1; /* another option */
    cr_expect_eq(wr_cli_integer(argc, argv, &i, "--steps", 0.0, 5.0, &x), 0);
}

/* The shared argument loop the drivers and the validators use (issue 18: validators read options with
 * atoi/atof, so "--seeds x" became 0 and a run rewrote its result file). A validator-like table:
 * every bad value is refused (-1, the caller exits WR_CLI_EXIT_USAGE) and leaves the outputs alone;
 * --help anywhere returns 0 before anything is parsed. */
static int parse_usage_calls;
static void parse_usage(FILE *f) {
    (void)f;
    ++parse_usage_calls;
}

static int parse_run(int argc, char **argv, double *seeds, double *seconds, int *quick, const char **only) {
    const wr_cli_opt opts[] = {
        {"--quick", NULL, WR_CLI_FLAG, quick, 0.0, 0.0, NULL},
        {"--seeds", NULL, WR_CLI_INTEGER, seeds, 1.0, 8.0, NULL},
        {"--seconds", NULL, WR_CLI_NUMBER, seconds, 1e-9, 1e4, NULL},
        {"--garment", NULL, WR_CLI_STRING, (void *)only, 0.0, 0.0, NULL},
    };
    return wr_cli_parse(argc, argv, opts, 4, NULL, 0, NULL, parse_usage); /* errors: one line on stderr */
}

Test(cli, parse_table) {
    char *good[] = {"prog", "--seeds", "5", "--seconds=0.4", "--quick", "--garment", "skirt"};
    char *bad[][3] = {{"prog", "--seeds", "x"},       {"prog", "--seeds", "0"},     {"prog", "--seeds", "2.5"},
                      {"prog", "--seeds", "9"},       {"prog", "--seconds", "-1"},  {"prog", "--seconds", "1e-6x"},
                      {"prog", "--seconds", "nan"},   {"prog", "--garment", ""},    {"prog", "--bogus", "1"},
                      {"prog", "stray", "--quick"}};
    char *help[] = {"prog", "--seeds", "x", "--help"};
    char *missing[] = {"prog", "--seeds"};
    double seeds = 3.0, seconds = 2.0;
    int quick = 0, k;
    const char *only = NULL;
    wr_cli_set_program("prog");
    cr_expect_eq(parse_run(7, good, &seeds, &seconds, &quick, &only), 1);
    cr_expect(seeds == 5.0 && seconds == 0.4 && quick == 1 && only && strcmp(only, "skirt") == 0);
    for (k = 0; k < (int)(sizeof bad / sizeof bad[0]); ++k) {
        seeds = 3.0, seconds = 2.0;
        cr_expect_eq(parse_run(3, bad[k], &seeds, &seconds, &quick, &only), -1, "'%s %s' must be refused", bad[k][1],
                     bad[k][2]);
        cr_expect(seeds == 3.0 && seconds == 2.0, "'%s %s': a refused value leaves the output alone", bad[k][1], bad[k][2]);
    }
    cr_expect_eq(parse_run(2, missing, &seeds, &seconds, &quick, &only), -1, "an option without its value");
    parse_usage_calls = 0;
    cr_expect_eq(parse_run(4, help, &seeds, &seconds, &quick, &only), 0, "--help wins over a bad value before it");
    cr_expect_eq(parse_usage_calls, 1);
    cr_expect_eq(seeds, 3.0, "--help parses nothing");
}
