/* Regression tests for fuzzer findings (tests/regressions/README.md): each fixed finding's input is
 * replayed through the same entry point the harness used and the contract it broke is asserted. */
#include <criterion/criterion.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "pattern.h"
#include "wrinkle/wrinkle.h"

/* Reads tests/regressions/<name> (tests run from the repository root). */
static char *read_regression(const char *name, size_t *len) {
    char path[512];
    FILE *f;
    char *buf;
    long n;
    snprintf(path, sizeof path, "tests/regressions/%s", name);
    f = fopen(path, "rb");
    cr_assert_not_null(f, "cannot open %s (run from the repository root)", path);
    fseek(f, 0, SEEK_END);
    n = ftell(f);
    fseek(f, 0, SEEK_SET);
    buf = (char *)malloc((size_t)n + 1);
    cr_assert_not_null(buf);
    cr_assert_eq(fread(buf, 1, (size_t)n, f), (size_t)n);
    fclose(f);
    buf[n] = 0;
    *len = (size_t)n;
    return buf;
}

/* fuzz_pattern: a top-level key containing a newline ("ba\n f rics") was echoed verbatim, giving a
 * two-line message (core.h: "one line, no trailing newline"). Fixed in 2a9b27c. */
Test(regressions, pattern_newline_in_key) {
    size_t len;
    char *text = read_regression("pattern_newline_in_key.fuzz_pattern", &len);
    wr_pattern_file pf;
    wr_diag d;
    wr_status s;
    memset(&d, 0, sizeof d);
    cr_assert(memchr(text, '\n', len) != NULL);
    s = wr_pattern_parse(text, len, "fuzz.json", &pf, &d);
    cr_assert_eq(s, WR_ERR_PARSE, "status %s: %s", wr_status_string(s), d.message);
    cr_assert_eq(d.status, s);
    cr_assert(strchr(d.message, '\n') == NULL, "multi-line message: [%s]", d.message);
    cr_assert(strstr(d.message, "unknown key") != NULL, "message does not name the problem: [%s]", d.message);
    wr_pattern_file_free(&pf);
    free(text);
}
