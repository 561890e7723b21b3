/* Regression tests for fuzzer findings (tests/regressions/README.md): each fixed finding's input is
 * replayed through the same entry point the harness used and the contract it broke is asserted. */
#include <criterion/criterion.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "pattern.h"
#include "scene.h"
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

/* fuzz_poly: a 129-byte .poly whose header declares 200000000 vertices made wr_cdt_poly_parse
 * allocate 3.2 GB before reading a vertex (libFuzzer out-of-memory). The section counts are now
 * checked against the lines left first. Byte 0 of the file is the harness's mode (1 = .poly only). */
Test(regressions, poly_huge_vertex_count) {
    size_t len;
    char *raw = read_regression("poly_huge_vertex_count.fuzz_poly", &len);
    wr_cdt_poly p;
    wr_diag d;
    wr_status s;
    cr_assert(len > 1 && raw[0] == 1);
    memset(&d, 0, sizeof d);
    s = wr_cdt_poly_parse(raw + 1, NULL, "fuzz.poly", &p, &d);
    cr_assert_eq(s, WR_ERR_PARSE, "status %s: %s", wr_status_string(s), d.message);
    cr_assert(strstr(d.message, "declares 200000000 vertices but fewer lines follow") != NULL, "[%s]", d.message);
    cr_assert_eq(p.points, NULL); /* nothing allocated, output zeroed */
    wr_cdt_poly_free(&p);
    free(raw);
}

/* The same early check for the segment and hole sections, and its boundary: a count equal to the
 * lines left still parses (the last line may lack its newline). */
Test(regressions, poly_section_counts_vs_lines_left) {
    static const char *const bad_seg = "3 2 0 0\n1 0 0\n2 1 0\n3 0 1\n100000000 0\n1 1 2\n";
    static const char *const bad_holes = "3 2 0 0\n1 0 0\n2 1 0\n3 0 1\n1 0\n1 1 2\n99999999\n1 0.2 0.2\n";
    static const char *const exact = "3 2 0 0\n1 0 0\n2 1 0\n3 0 1\n3 0\n1 1 2\n2 2 3\n3 3 1\n1\n1 0.2 0.2";
    static const char *const crlf = "3 2 0 0\r\n1 0 0\r\n2 1 0\r\n3 0 1\r\n0 0\r\n";
    wr_cdt_poly p;
    wr_diag d;
    cr_assert_eq(wr_cdt_poly_parse(bad_seg, NULL, "s.poly", &p, &d), WR_ERR_PARSE);
    cr_assert(strstr(d.message, "declares 100000000 segments") != NULL, "[%s]", d.message);
    wr_cdt_poly_free(&p);
    cr_assert_eq(wr_cdt_poly_parse(bad_holes, NULL, "h.poly", &p, &d), WR_ERR_PARSE);
    cr_assert(strstr(d.message, "declares 99999999 holes") != NULL, "[%s]", d.message);
    wr_cdt_poly_free(&p);
    cr_assert_eq(wr_cdt_poly_parse(exact, NULL, "e.poly", &p, &d), WR_OK, "%s", d.message);
    cr_assert_eq(p.n_points, 3);
    cr_assert_eq(p.n_segments, 3);
    cr_assert_eq(p.n_holes, 1);
    wr_cdt_poly_free(&p);
    cr_assert_eq(wr_cdt_poly_parse(crlf, NULL, "c.poly", &p, &d), WR_OK, "%s", d.message);
    cr_assert_eq(p.n_points, 3);
    wr_cdt_poly_free(&p);
}

/* fuzz_scene: a key holding a newline ("m\n  esh") was echoed into a two-line message. Control
 * characters are now shown as \xHH; the message still names the JSON path. */
Test(regressions, scene_newline_in_key) {
    size_t len;
    char *text = read_regression("scene_newline_in_key.fuzz_scene", &len);
    wr_scene sc;
    wr_diag d;
    wr_status s;
    memset(&d, 0, sizeof d);
    s = wr_scene_parse(&sc, text, len, ".", &d);
    cr_assert_eq(s, WR_ERR_PARSE, "status %s: %s", wr_status_string(s), d.message);
    cr_assert(strchr(d.message, '\n') == NULL, "multi-line message: [%s]", d.message);
    cr_assert_str_eq(d.message, "$.m\\x0a  esh: unknown key");
    wr_scene_free(&sc);
    free(text);
}
