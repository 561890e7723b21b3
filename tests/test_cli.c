/* Tests for the driver-side CLI helpers drivers/lib/cli.{h,c}. */
#include <criterion/criterion.h>
#include <math.h>

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
