/* Regression tests for fuzzer findings (tests/regressions/README.md): each fixed finding's input is
 * replayed through the same entry point the harness used and the contract it broke is asserted. */
#include <criterion/criterion.h>
#include <math.h>
#include <stdint.h>
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

/* Decodes a fuzz_cdt input exactly as tests/fuzz/fuzz_cdt.c does (byte layout documented there),
 * runs wr_cdt_triangulate and returns its status; *r holds the result. */
static double cdt_coord(const unsigned char *p, size_t n, size_t *at, int mode) {
#define RD8() (*at < n ? p[(*at)++] : 0)
    if (mode == 3) mode = RD8() % 3;
    if (mode == 0) return (double)((int)(RD8() % 16) - 8);
    if (mode == 1) {
        double base = (double)((int)(RD8() % 16) - 8);
        int k = (int)(signed char)RD8();
        return base + ldexp((double)k, -48);
    } else {
        uint64_t u = 0;
        double x;
        int i;
        for (i = 0; i < 8; ++i) u |= (uint64_t)RD8() << (8 * i);
        memcpy(&x, &u, sizeof x);
        if (!isfinite(x) || fabs(x) > 1e30 || (x != 0.0 && fabs(x) < 1e-30)) x = 0.0;
        return x;
    }
#undef RD8
}

static wr_status replay_cdt_bytes_diag(const unsigned char *p, size_t n, int32_t max_vertices, wr_cdt_result *r,
                                      wr_diag *dg);
static wr_status replay_cdt_bytes(const unsigned char *p, size_t n, int32_t max_vertices, wr_cdt_result *r) {
    wr_diag d;
    return replay_cdt_bytes_diag(p, n, max_vertices, r, &d);
}

/* replay_cdt_ok (below) on bytes in memory: as found (quick = 0) or with refinement switched off
 * (quick = 1: recovery alone; flag bit 0 cleared in p); free r after. */
static void replay_cdt_bytes_ok(unsigned char *p, size_t n, int quick, wr_cdt_result *r) {
    wr_diag dc;
    wr_status s;
    if (quick) p[0] &= (unsigned char)~1u;
    s = replay_cdt_bytes(p, n, 2000, r);
    cr_assert_eq(s, WR_OK, "status %s", wr_status_string(s));
    cr_assert_eq(wr_cdt_check(r, -1, NULL, &dc), WR_OK, "quality %d: %s", !quick, dc.message);
}

/* Decodes fuzz_cdt bytes as the harness does and triangulates them; the diagnostics go to *dg. */
static wr_status replay_cdt_bytes_diag(const unsigned char *p, size_t n, int32_t max_vertices, wr_cdt_result *r,
                                      wr_diag *dg) {
    size_t at = 0;
    double pts[2 * 32], holes[2 * 2];
    int32_t seg[2 * 24], np, ns, nh, i;
    unsigned char flags;
    int mode;
    wr_cdt_input in;
    wr_cdt_desc cd;
    wr_status s;
#define RD8() (at < n ? p[at++] : 0)
    flags = RD8();
    np = RD8() % 33;
    ns = RD8() % 25;
    nh = RD8() % 3;
    memset(&cd, 0, sizeof cd);
    cd.quality = flags & 1;
    cd.split_intersections = (flags >> 1) & 1;
    cd.keep_convex_hull = (flags >> 2) & 1;
    cd.off_center = (flags >> 3) & 1;
    mode = (flags >> 4) & 3;
    cd.min_angle_deg = 5.0 + (double)(RD8() % 30);
    if (flags & 64) cd.merge_tolerance = 1e-9;
    if (flags & 128) cd.max_area = 0.5;
    cd.max_vertices = max_vertices;
    for (i = 0; i < np; ++i) {
        pts[2 * i] = cdt_coord(p, n, &at, mode);
        pts[2 * i + 1] = cdt_coord(p, n, &at, mode);
    }
    if (np == 0) ns = 0;
    for (i = 0; i < ns; ++i) {
        seg[2 * i] = RD8() % np;
        seg[2 * i + 1] = RD8() % np;
    }
    for (i = 0; i < nh; ++i) {
        holes[2 * i] = cdt_coord(p, n, &at, mode);
        holes[2 * i + 1] = cdt_coord(p, n, &at, mode);
    }
#undef RD8
    memset(&in, 0, sizeof in);
    in.points = pts;
    in.n_points = np;
    in.segments = ns ? seg : NULL;
    in.n_segments = ns;
    in.holes = nh ? holes : NULL;
    in.n_holes = nh;
    s = wr_cdt_triangulate(&in, &cd, r, dg);
    return s;
}

static wr_status replay_cdt(const char *name, int32_t max_vertices, wr_cdt_result *r) {
    size_t n;
    unsigned char *p = (unsigned char *)read_regression(name, &n);
    wr_status s = replay_cdt_bytes(p, n, max_vertices, r);
    free(p);
    return s;
}

/* fuzz_cdt: segment 0-3 given twice, quality refinement: WR_OK but wr_cdt_check said "input segment 2
 * (0-3) is not a chain of subsegments" (the refined chain carries the first occurrence's id and its
 * split points are rounded off the line). The checker now accepts the first identical segment's id,
 * as documented for segment_id. */
Test(regressions, cdt_duplicate_segment_refine) {
    wr_cdt_result r;
    wr_diag dc;
    wr_status s = replay_cdt("cdt_duplicate_segment_refine.fuzz_cdt", 2000, &r), c;
    cr_assert(s == WR_OK || s == WR_ERR_BUDGET, "%s", wr_status_string(s));
    cr_assert_eq(r.n_input_segments, 3);
    cr_assert_gt(r.n_steiner, 0);
    c = wr_cdt_check(&r, -1, NULL, &dc);
    cr_assert_eq(c, WR_OK, "%s", dc.message);
    wr_cdt_free(&r);
}

/* fuzz_cdt: refinement toward a sharp corner / a 5e-10 feature pushed Steiner coordinates down to
 * ~1e-78 and ~1e-316, where the exact predicates' products underflow; WR_ERR_BUDGET then returned a
 * non-Delaunay edge or a zero-area triangle. Checked at every budget around the old failures. */
Test(regressions, cdt_budget_underflow) {
    static const char *const names[] = {"cdt_budget_not_delaunay.fuzz_cdt", "cdt_budget_degenerate_triangle.fuzz_cdt"};
    int k;
    int32_t mv;
    for (k = 0; k < 2; ++k)
        for (mv = 1040; mv <= 1160; mv += 3) {
            wr_cdt_result r;
            wr_diag dc;
            wr_status s = replay_cdt(names[k], mv, &r), c;
            cr_assert(s == WR_OK || s == WR_ERR_BUDGET, "%s", wr_status_string(s));
            c = wr_cdt_check(&r, -1, NULL, &dc);
            cr_assert_eq(c, WR_OK, "%s at max_vertices %d: %s", names[k], mv, dc.message);
            wr_cdt_free(&r);
        }
    {
        wr_cdt_result r;
        wr_diag dc;
        cr_assert_eq(replay_cdt(names[0], 2000, &r), WR_OK); /* ends since the precision floor */
        cr_assert_eq(wr_cdt_check(&r, -1, NULL, &dc), WR_OK, "%s", dc.message);
        wr_cdt_free(&r);
        /* since the hull edges count as segments for the small-angle rule (cdt_tiny_edge_refine_cubic)
         * the 5e-10 feature's own angle is left alone and refinement ends within the budget */
        cr_assert_eq(replay_cdt(names[1], 2000, &r), WR_OK);
        cr_assert_eq(wr_cdt_check(&r, -1, NULL, &dc), WR_OK, "%s", dc.message);
        wr_cdt_free(&r);
    }
}

/* Replays a fuzz_cdt input and asserts the harness contract: WR_OK (refinement ended within the
 * harness's vertex budget of 2000) and a result wr_cdt_check accepts. */
static void replay_cdt_ok(const char *name, wr_cdt_result *r) {
    wr_diag dc;
    wr_status s = replay_cdt(name, 2000, r), c;
    cr_assert_eq(s, WR_OK, "%s: status %s", name, wr_status_string(s));
    c = wr_cdt_check(r, -1, NULL, &dc);
    cr_assert_eq(c, WR_OK, "%s: %s", name, dc.message);
}

/* fuzz_cdt: a needle (3 points, widths 4e-14 / 1.5e-13 over 8 units), hull kept, 16° with
 * off-centers: WR_OK but "edge (4, 2) between triangles 6 and 11 is not locally Delaunay". A hull
 * split point rounded a few ulps outside the hull made Lawson flip the edge between two ghosts,
 * burying two hull edges (marked constrained, reported unconstrained) inside the mesh. During
 * refinement the boundary is now fixed: no flips between ghosts. */
Test(regressions, cdt_needle_hull_not_delaunay) {
    wr_cdt_result r;
    replay_cdt_ok("cdt_needle_hull_not_delaunay.fuzz_cdt", &r);
    cr_assert_eq(r.n_input_points, 3);
    cr_assert_gt(r.n_steiner, 0);
    wr_cdt_free(&r);
}

/* fuzz_cdt: three points with a 1.4e-14 edge, 7°, max_area 0.5: refinement never met the angle bound
 * and ran to the budget with ~n³ cost (walks ending in ghosts after unconstrained hull edges
 * appeared; 31 s for 2000 vertices under the fuzzer's sanitizers). Now hull edges are segments for
 * refinement, including the small-input-angle rule: it ends with WR_OK and few vertices. With
 * the default budget (65k vertices) the old code would have run for hours. */
Test(regressions, cdt_tiny_edge_refine_cubic) {
    wr_cdt_result r;
    /* the vertex counts are the guard (the old code ran to the harness budget); no wall-clock
     * assertion here: performance lives in bench/, never in tests */
    replay_cdt_ok("cdt_tiny_edge_refine_cubic.fuzz_cdt", &r);
    cr_assert_eq(r.n_input_points, 3);
    cr_assert_lt(r.n_points, 1000, "%d vertices for a 3-point input", r.n_points);
    wr_cdt_free(&r);
    cr_assert_eq(replay_cdt("cdt_tiny_edge_refine_cubic.fuzz_cdt", 0, &r), WR_OK); /* default budget */
    cr_assert_lt(r.n_points, 1000, "%d vertices", r.n_points);
    wr_cdt_free(&r);
}

/* fuzz_cdt: segment 7-0 passes through point 6 and so overlaps segments 0-6 / 6-0; the shared piece
 * carries segment 0's id, and refinement split it at points rounded off the line (a
 * concentric-shell point). WR_OK but "input segment 2 (7-0) is not a chain of subsegments": the
 * checker required the piece's own end points to be exactly collinear with 7-0. The contract
 * (segment_id, wr_cdt_check) is now: shared pieces carry the lowest id, and a piece counts for an
 * input segment when its id names an input segment lying exactly on the same line. */
Test(regressions, cdt_overlapping_segments_refine) {
    /* a square with segment (-3,-7)-(3,7) through (0,0) and segment (0,0)-(3,7) on top of its half */
    static const double pts[] = {-10, -10, 10, -10, 10, 10, -10, 10, 0, 0, 3, 7, -3, -7};
    static const int32_t seg[] = {0, 1, 1, 2, 2, 3, 3, 0, 6, 5, 4, 5};
    wr_cdt_result r;
    wr_cdt_input in;
    wr_cdt_desc cd;
    wr_diag d;
    int32_t k, off_line = 0;
    const double *a, *b;
    replay_cdt_ok("cdt_overlapping_segments_refine.fuzz_cdt", &r);
    cr_assert_eq(r.n_input_segments, 4);
    wr_cdt_free(&r);
    /* Since the precision floor the fuzzer's input splits the shared piece only at its exact
     * midpoint; this one still rounds split points of the shared piece off the line (the case the
     * old checker rejected: "input segment 5 (4-5) is not a chain of subsegments"). */
    memset(&in, 0, sizeof in);
    memset(&cd, 0, sizeof cd);
    in.points = pts;
    in.n_points = 7;
    in.segments = seg;
    in.n_segments = 6;
    cd.quality = 1;
    cd.min_angle_deg = 30.0;
    cd.max_area = 2.0;
    cr_assert_eq(wr_cdt_triangulate(&in, &cd, &r, &d), WR_OK, "%s", d.message);
    cr_assert_eq(wr_cdt_check(&r, 0, NULL, &d), WR_OK, "%s", d.message);
    a = r.points + 2 * r.input_segments[10];
    b = r.points + 2 * r.input_segments[11];
    for (k = 0; k < r.n_segments; ++k) {
        cr_assert_neq(r.segment_id[k], 5, "the shared piece carries the lower id 4");
        if (r.segment_id[k] == 4 && (wr_orient2d(a, b, r.points + 2 * r.segments[2 * k]) != 0.0 ||
                                     wr_orient2d(a, b, r.points + 2 * r.segments[2 * k + 1]) != 0.0))
            ++off_line;
    }
    cr_assert_gt(off_line, 0);
    wr_cdt_free(&r);
}

/* fuzz_cdt: an early artifact (quadrilateral with a 1e-9 step, 30°, off-centers). It replays clean
 * through the harness before and after the fixes above, but the old code returned WR_OK with a
 * 0° minimum angle: slivers along the hull segment 1-2, made by the ghost flips that
 * cdt_needle_hull_not_delaunay fixed (live triangles just outside the segment). Now no triangle is
 * below the bound. */
Test(regressions, cdt_early_finding) {
    wr_cdt_result r;
    replay_cdt_ok("cdt_early_finding.fuzz_cdt", &r);
    cr_assert(r.exterior_carved);
    cr_assert_geq(r.min_angle_deg, 30.0 - 1e-9, "min angle %g", r.min_angle_deg);
    wr_cdt_free(&r);
}

/* fuzz_cdt (found by the 10-minute fuzz run after the fixes above): segments (0,0)-(0.001,0) and
 * (0,0)-(8e-25,0.5), each twice, hull kept, a hull vertex (0,0.25) 4e-25 beside the second
 * segment: a sliver domain 1e-25 wide. Refinement ran into the vertex budget with ~n^2.5 cost
 * (2000 vertices 0.06 s, 8000 1.1 s, 32000 36 s; out of memory at 128000) through two cascades:
 * concentric-shell vertices of the segment and the hull edge, misaligned by rounding, encroaching
 * each other's subsegments (a vertex on a segment meeting at < 60° no longer counts as encroaching),
 * and circumcenters of ulp-scale slivers rounding back onto the sliver (triangles and subsegments
 * below the relative precision floor 2^-36 are left alone). Each rule alone does not end it. */
Test(regressions, cdt_sliver_cascade) {
    wr_cdt_result r;
    int32_t nv;
    replay_cdt_ok("cdt_sliver_cascade.fuzz_cdt", &r);
    nv = r.n_points;
    wr_cdt_free(&r);
    /* with the default budget (65k vertices) it ends at the same mesh: refinement stopped by itself */
    cr_assert_eq(replay_cdt("cdt_sliver_cascade.fuzz_cdt", 0, &r), WR_OK);
    cr_assert_eq(r.n_points, nv);
    wr_cdt_free(&r);
}

/* fuzz_cdt (found by a later fuzz run; the code before this session fails it too, also without
 * refinement): split_intersections, segment 5-8 given twice, crossing segment 9-0 and others near
 * one point. Recovering the duplicate again crossed the first copy's rounded junction 1.3e-15
 * away, split segment 9-0 there too, and the sliver piece between the two junctions ended up in
 * the duplicate's chain with its id: "input segment 0 (8-0) is not a chain of subsegments". A
 * segment given again is now recovered once. */
Test(regressions, cdt_duplicate_crossing_split) {
    wr_cdt_result r;
    replay_cdt_ok("cdt_duplicate_crossing_split.fuzz_cdt", &r);
    cr_assert_eq(r.n_input_segments, 6);
    cr_assert_gt(r.n_steiner, 0);
    wr_cdt_free(&r);
}

/* fuzz_cdt (later fuzz run; the code before this session fails it too, also without refinement):
 * a hole seed exactly on hull vertex (7,7) removed the triangles inside hull subsegment (7,7)-(7,6),
 * whose other side is outside the hull: the subsegment rightly stays in the list (it bounded removed
 * triangles, as `segments` documents) but wr_cdt_check only allowed that when the exterior was
 * carved: "subsegment (8, 9) of segment 0 is not a constrained mesh edge". The result now records
 * holes_carved and the checker applies the same rule to holes. */
Test(regressions, cdt_hole_seed_on_hull_vertex) {
    wr_cdt_result r;
    replay_cdt_ok("cdt_hole_seed_on_hull_vertex.fuzz_cdt", &r);
    cr_assert(r.holes_carved);
    cr_assert(!r.exterior_carved);
    wr_cdt_free(&r);
}

/* fuzz_cdt (last fuzz run of that session; the code before it fails too, also without refinement):
 * split_intersections, 20 small-integer points, 19 crossing segments. Segment 12 (7,-8)-(-8,4)
 * passes exactly through (-3,0), the end of segments 3 and 15, and segment 15 exactly through
 * (0,-3), the end of segment 8; but the pieces being recovered start at rounded junctions, so they
 * crossed those segments' last edges and junctions were computed at (-3,-2.2e-16),
 * (-3,-7.7e-17), ...: segment 3's chain overshot its end and came back, and "input segment 15
 * (1-17) is not a chain of subsegments". A crossing is now first resolved exactly on the input
 * segments (an end of one strictly inside the other is the junction), and a computed point within
 * rounding distance of an end vertex of either piece snaps to it. */
Test(regressions, cdt_crossing_chain_split) {
    wr_cdt_result r;
    int32_t i, k;
    replay_cdt_ok("cdt_crossing_chain_split.fuzz_cdt", &r);
    cr_assert_eq(r.n_input_segments, 19);
    cr_assert_gt(r.n_steiner, 0);
    /* no junction a rounding error away from an input point: those points are the junctions */
    for (i = r.n_input_points; i < r.n_points; ++i)
        for (k = 0; k < r.n_input_points; ++k) {
            double dx = r.points[2 * i] - r.points[2 * k], dy = r.points[2 * i + 1] - r.points[2 * k + 1];
            cr_assert(fabs(dx) > 1e-12 || fabs(dy) > 1e-12, "Steiner point %d (%.17g, %.17g) next to input point %d",
                      i, r.points[2 * i], r.points[2 * i + 1], k);
        }
    wr_cdt_free(&r);
}

/* Found by the fuzz run on the first version of that fix (also seed
 * tests/fuzz/corpus/fuzz_cdt/regr_crossing_snap_not_delaunay; fine with the code before it):
 * split_intersections, a piece of segment 12 again crossing an edge at the end (-3,0) of segment 3
 * that segment 12 passes exactly through. The junction is now that vertex, so no point is inserted
 * there, and an edge that an earlier rounded junction's insertion had left non-Delaunay (waiting for
 * that insertion's legalization) stayed so: "edge (10, 32) between triangles 1 and 36 is not locally
 * Delaunay". After recovering the segments, one Lawson pass now covers every unconstrained edge. */
Test(regressions, cdt_crossing_vertex_junction_delaunay) {
    static const unsigned char bytes[] = {
        0x03, 0x14, 0x77, 0x08, 0x05, 0x7e, 0xff, 0xbd, 0x00, 0x2e, 0x02, 0x04, 0x00, 0x08, 0x04, 0x08,
        0xfc, 0xf7, 0xff, 0x0c, 0xff, 0xff, 0xff, 0xff, 0xff, 0xff, 0x00, 0x00, 0xf6, 0x61, 0x40, 0x30,
        0x05, 0x00, 0x44, 0x00, 0x1c, 0x0b, 0x08, 0x08, 0x0b, 0x05, 0x08, 0x08, 0x05, 0x5b, 0x0a, 0x0a,
        0x06, 0x0a, 0x06, 0x06, 0x12, 0x00, 0xff, 0x7e, 0xff, 0xbd, 0x00, 0x2e, 0xf8, 0x03, 0x00, 0x08,
        0x05, 0xf8, 0x03, 0x08, 0x0c, 0x0a, 0xff, 0xff, 0xfe, 0x01, 0x00, 0x00, 0x2e, 0xe8, 0x0b, 0x2e,
        0x11, 0x0b, 0x05, 0xff, 0x1b, 0x00,
    };
    wr_cdt_result r;
    int q;
    for (q = 0; q < 2; ++q) { /* as found (quality on) and without refinement: recovery alone */
        unsigned char b[sizeof bytes];
        memcpy(b, bytes, sizeof b);
        replay_cdt_bytes_ok(b, sizeof b, q, &r);
        wr_cdt_free(&r);
    }
}

/* fuzz_cdt (CI fuzz smoke after the snap fix above, 29k runs): split_intersections; segments 1-2
 * (0.001,0)-(0,1e-9) and 2-4 (0,1e-9)-(1,0) meet at their shared end at 1e-6 rad and both cross
 * segment 0-3 (slope 1/2) near (2e-9, 1e-9), 4e-15 apart. The second crossing snapped onto the
 * first junction, so both chains ran through the edge from that junction to (0,1e-9), which carries
 * one id: WR_OK but "input segment 3 (2-4) is not a chain of subsegments". A snap that would make a
 * split half an edge another segment owns is refused; the computed point becomes its own vertex. */
Test(regressions, cdt_chain_after_crossing_fix) {
    size_t n;
    unsigned char *p = (unsigned char *)read_regression("cdt_chain_after_crossing_fix.fuzz_cdt", &n);
    int q;
    cr_assert(n > 0);
    for (q = 0; q < 2; ++q) { /* as found (quality on) and without refinement: recovery alone */
        wr_cdt_result r;
        int32_t i, own3 = 0, own2 = 0;
        replay_cdt_bytes_ok(p, n, q, &r);
        cr_assert_eq(r.n_input_segments, 4);
        cr_assert_eq(r.input_segments[2 * 3], 2); /* output numbering = input numbering here */
        /* both segments ending at input point 2 keep a piece of their own there */
        for (i = 0; i < r.n_segments; ++i)
            if (r.segments[2 * i] == 2 || r.segments[2 * i + 1] == 2) {
                own2 += r.segment_id[i] == 2;
                own3 += r.segment_id[i] == 3;
            }
        cr_assert_eq(own2, 1);
        cr_assert_eq(own3, 1);
        wr_cdt_free(&r);
    }
    free(p);
}

/* Found by the fuzz run on the first version of that fix (fine with the code before it):
 * split_intersections; segments 4 (0,-2)-(-7,-7) and 10 (-7,-7)-(7,3) are collinear and overlap,
 * and segment 0 (-5,0)-(7,-8) crosses both at (-28/29, -78/29). Refusing every snap onto an edge of
 * another segment also refused the snap onto the pieces segments 4 and 10 share by contract, so
 * three vertices an ulp apart were made there and "input segment 0 (11-10) is not a chain of
 * subsegments". An edge of a collinear overlapping segment does not block the snap. */
Test(regressions, cdt_collinear_overlap_snap) {
    size_t n;
    unsigned char *p = (unsigned char *)read_regression("cdt_collinear_overlap_snap.fuzz_cdt", &n);
    int q;
    cr_assert(n > 0);
    for (q = 0; q < 2; ++q) { /* as found (quality on) and without refinement */
        wr_cdt_result r;
        int32_t i, k, near = 0;
        replay_cdt_bytes_ok(p, n, q, &r);
        /* one junction at the triple crossing, not several an ulp apart */
        for (i = 0; i < r.n_points; ++i)
            for (k = i + 1; k < r.n_points; ++k)
                near += fabs(r.points[2 * i] - r.points[2 * k]) < 1e-12 &&
                        fabs(r.points[2 * i + 1] - r.points[2 * k + 1]) < 1e-12;
        cr_assert_eq(near, 0, "quality %d: %d vertex pairs closer than 1e-12", !q, near);
        wr_cdt_free(&r);
    }
    free(p);
}

/* fuzz_cdt (fails with the code of the whole previous session too): split_intersections; points
 * (1.08e-19,0) (0,0.001) (0,0) (0.5,0.25) (1,0.5), segments 0-1 1-2 2-4 4-0. Segment 2-4 crosses
 * 0-1 at (1.08e-19, 5.4e-20), 5.4e-20 from point 0; the snap radius was 64 ulps of the largest end
 * point (|(1,0.5)| = 1, so 7e-15) and the crossing snapped onto point 0, making 2-4's chain run
 * 2-0-4 through the edge of segment 4-0 (not yet recovered): "input segment 3 (4-0) is not a chain
 * of subsegments". The radius now follows the computed point's own error (a few ulps of the point,
 * of its distance from the piece's start, and of the pieces' computed end points), with the
 * orientations evaluated to a few ulps. */
Test(regressions, cdt_crossing_near_tiny_feature) {
    size_t n;
    unsigned char *p = (unsigned char *)read_regression("cdt_crossing_near_tiny_feature.fuzz_cdt", &n);
    int q;
    cr_assert(n > 0);
    for (q = 0; q < 2; ++q) { /* as found (quality on) and without refinement */
        wr_cdt_result r;
        int32_t i, junction = -1;
        replay_cdt_bytes_ok(p, n, q, &r);
        /* the crossing is its own vertex, a few ulps from the exact (1.0843e-19, 5.4215e-20) */
        for (i = r.n_input_points; i < r.n_points; ++i)
            if (fabs(r.points[2 * i] - 1.0843018218998615e-19) < 1e-33 && fabs(r.points[2 * i + 1] - 0.5 * 1.0843018218998615e-19) < 1e-33)
                junction = i;
        cr_assert_geq(junction, 0, "quality %d: no junction at the crossing", !q);
        wr_cdt_free(&r);
    }
    free(p);
}

/* fuzz_cdt (fails with the code of the whole previous session too): split_intersections, near-integer
 * points; segments 0 (6,4)-(-8,7-1.8e-13) and 8 (-8,7+4.5e-13)-(6,4) share the end (6,4) and meet
 * there at 4.5e-14 rad; both cross segments 3 and 4, and those crossings round to the same
 * junctions, so pieces of segment 0 were reused by segment 8 under segment 0's id: WR_OK but "input
 * segment 8 (6-5) is not a chain of subsegments". One piece cannot belong to two segments off one
 * line in the result, so this input is now refused with WR_ERR_GEOMETRY naming both segments. */
Test(regressions, cdt_hairline_segments_share_piece) {
    size_t n;
    unsigned char *p = (unsigned char *)read_regression("cdt_hairline_segments_share_piece.fuzz_cdt", &n);
    int q;
    cr_assert(n > 0);
    for (q = 0; q < 2; ++q) { /* as found (quality on) and without refinement */
        wr_cdt_result r;
        wr_diag d;
        wr_status s;
        if (q) p[0] &= (unsigned char)~1u;
        memset(&r, 0, sizeof r);
        s = replay_cdt_bytes_diag(p, n, 2000, &r, &d);
        if (s == WR_OK) {
            wr_diag dc;
            cr_assert_eq(wr_cdt_check(&r, -1, NULL, &dc), WR_OK, "quality %d: WR_OK but %s", !q, dc.message);
            wr_cdt_free(&r);
            continue;
        }
        cr_assert_eq(s, WR_ERR_GEOMETRY, "quality %d: %s", !q, wr_status_string(s));
        cr_assert(strstr(d.message, "segments 0 and 8 cannot be kept apart") != NULL, "message: %s", d.message);
        cr_assert(strchr(d.message, '\n') == NULL);
        cr_assert_eq(r.n_triangles, 0); /* nothing handed out on failure */
        cr_assert(r.triangles == NULL && r.points == NULL);
    }
    free(p);
}

/* fuzz_cdt (libFuzzer timeout, 26 s on the loaded box; fails the same way on the code of the whole
 * previous session): points spanning 1e-3 to 1e28, segments 1-2 and 2-4 forming a wedge 1e-3 wide
 * and 1e26 long, 30° with off-centers. Refinement candidates near the wedge had cavities of n/6
 * triangles (huge skinny circumcircles), each rejected candidate costing that many exact in-circle
 * tests: ~n^2, 10 s to the harness budget of 2000 vertices. The cavity search now stops at 256
 * triangles. Guarded by the result: with the default budget refinement ends (WR_OK) with a valid
 * mesh of fewer than 20000 vertices (8509 measured, 0.5 s; the old code needs minutes for it). */
Test(regressions, cdt_wedge_cavity_quadratic) {
    int32_t budgets[2] = {2000, 0}, k;
    for (k = 0; k < 2; ++k) {
        wr_cdt_result r;
        wr_diag dc;
        wr_status s = replay_cdt("cdt_wedge_cavity_quadratic.fuzz_cdt", budgets[k], &r);
        cr_assert(s == WR_OK || s == WR_ERR_BUDGET, "budget %d: %s", (int)budgets[k], wr_status_string(s));
        if (budgets[k] == 0) {
            cr_assert_eq(s, WR_OK, "default budget: refinement must end");
            cr_assert_lt(r.n_points, 20000);
        }
        cr_assert_eq(wr_cdt_check(&r, -1, NULL, &dc), WR_OK, "budget %d: %s", (int)budgets[k], dc.message);
        wr_cdt_free(&r);
    }
}

/* fuzz_cdt (CI fuzz smoke, 52 s for one input under ASan; pre-existing): points (0,2) (0.00098,0)
 * (1,-1.17e26) (-2.5e24,-1.35e28) (0,0.94), segments 0-3 1-2 2-4 4-0, 30° with off-centers. A fan of
 * ~860 slivers around one vertex that refinement cannot fix (Steiner point not finite, or beyond a
 * subsegment whose split would fold a sliver): every insertion beside the fan queued all of them
 * again and walked to each Steiner point again — 388k queue entries, 34M exact walk steps for 1,750
 * vertices. Now a triangle is queued once and a give-up is recorded until the triangle (or the
 * blocking subsegment's neighbourhood) changes. Guarded by the work count, not by time: at most 4
 * queue entries examined per output vertex (2.7 measured; 10 without the give-up record, 222
 * without the one-entry rule), at both budgets, with a valid mesh and the give-ups reported. */
Test(regressions, cdt_fan_giveup) {
    int32_t budgets[2] = {2000, 0}, k;
    for (k = 0; k < 2; ++k) {
        wr_cdt_result r;
        wr_diag dc;
        wr_status s = replay_cdt("cdt_fan_giveup.fuzz_cdt", budgets[k], &r);
        cr_assert_eq(s, WR_OK, "budget %d: %s", (int)budgets[k], wr_status_string(s));
        cr_assert_eq(wr_cdt_check(&r, -1, NULL, &dc), WR_OK, "budget %d: %s", (int)budgets[k], dc.message);
        cr_assert_gt(r.n_left_alone, 0, "the input must exercise the give-up record");
        cr_assert_leq(r.n_refine_tries, (int64_t)4 * r.n_points, "budget %d: %lld queue entries for %d vertices",
                      (int)budgets[k], (long long)r.n_refine_tries, (int)r.n_points);
        wr_cdt_free(&r);
    }
}

/* fuzz_poly: a .poly with coordinates up to 1e118: the in-circle determinant overflowed, flips went
 * wrong, and the segment-recovery walk reached the vertex at infinity and read coordinates at index
 * -1 (UBSan: unsigned offset overflow). Policy: |coordinates| beyond WR_CDT_MAX_COORD (1e70) are
 * WR_ERR_GEOMETRY naming the point; the walk never reads the ghost vertex. */
Test(regressions, poly_segment_walk_ghost_ub) {
    size_t len;
    char *raw = read_regression("poly_segment_walk_ghost_ub.fuzz_poly", &len);
    wr_cdt_poly p;
    wr_cdt_input in;
    wr_cdt_desc cd;
    wr_cdt_result r;
    wr_diag d;
    wr_status s;
    cr_assert(len > 1 && raw[0] == 1); /* harness mode 1: .poly only */
    s = wr_cdt_poly_parse(raw + 1, NULL, "fuzz.poly", &p, &d);
    cr_assert_eq(s, WR_OK, "%s", d.message);
    memset(&in, 0, sizeof in);
    memset(&cd, 0, sizeof cd);
    in.points = p.points;
    in.n_points = p.n_points;
    in.segments = p.segments;
    in.n_segments = p.n_segments;
    in.holes = p.holes;
    in.n_holes = p.n_holes;
    cd.max_vertices = 4096;
    s = wr_cdt_triangulate(&in, &cd, &r, &d);
    cr_assert_eq(s, WR_ERR_GEOMETRY, "status %s: %s", wr_status_string(s), d.message);
    cr_assert(strstr(d.message, "point 7 (1e+118, 2)") != NULL && strstr(d.message, "beyond") != NULL, "[%s]", d.message);
    cr_assert_eq(r.triangles, NULL);
    wr_cdt_free(&r);
    wr_cdt_poly_free(&p);
    free(raw);
}

/* The bound itself: WR_CDT_MAX_COORD is accepted (and triangulated exactly), the next double above
 * it is refused, for points and for hole seeds. */
Test(regressions, cdt_coordinate_bound) {
    double pts[8], hole[2];
    int32_t seg[8] = {0, 1, 1, 2, 2, 3, 3, 0};
    wr_cdt_input in;
    wr_cdt_result r;
    wr_diag d;
    const double M = WR_CDT_MAX_COORD, above = nextafter(WR_CDT_MAX_COORD, HUGE_VAL);
    pts[0] = -M; pts[1] = -M; pts[2] = M; pts[3] = -M; pts[4] = M; pts[5] = M; pts[6] = -M; pts[7] = M;
    memset(&in, 0, sizeof in);
    in.points = pts;
    in.n_points = 4;
    in.segments = seg;
    in.n_segments = 4;
    cr_assert_eq(wr_cdt_triangulate(&in, NULL, &r, &d), WR_OK, "%s", d.message);
    cr_assert_eq(r.n_triangles, 2);
    cr_assert_eq(wr_cdt_check(&r, 0, NULL, &d), WR_OK, "%s", d.message);
    wr_cdt_free(&r);
    pts[5] = above;
    cr_assert_eq(wr_cdt_triangulate(&in, NULL, &r, &d), WR_ERR_GEOMETRY);
    cr_assert(strstr(d.message, "point 2 ") != NULL, "[%s]", d.message);
    wr_cdt_free(&r);
    pts[5] = M;
    hole[0] = -above;
    hole[1] = 0.0;
    in.holes = hole;
    in.n_holes = 1;
    cr_assert_eq(wr_cdt_triangulate(&in, NULL, &r, &d), WR_ERR_GEOMETRY);
    cr_assert(strstr(d.message, "hole 0 ") != NULL, "[%s]", d.message);
    wr_cdt_free(&r);
}

/* fuzz_pattern (libFuzzer timeout in the CI smoke, 28 s under load): the Fig. 14 square with one
 * corner moved to y = 33333250 mm, a 33 km panel edge. At the sizing its curves need ~1.1e7 points
 * against the harness budget of 2000, but the mesher handed them to the sampler, whose crossing check
 * binned them into a grid floored at 1/2048 of the long side (thousands of segments per cell,
 * quadratic pair tests) before its own budget test. The mesher now refuses a panel whose curve
 * points alone exceed the vertex budget, and the crossing grid keeps O(segments) cells for any
 * aspect ratio. */
Test(regressions, pattern_giant_panel_budget) {
    size_t len;
    char *text = read_regression("pattern_giant_panel_budget.fuzz_pattern", &len);
    wr_pattern_file pf;
    wr_mesher_desc md;
    wr_mesher_result res;
    wr_diag d;
    wr_status s;
    memset(&d, 0, sizeof d);
    cr_assert_eq(wr_pattern_parse(text, len, "fuzz.json", &pf, &d), WR_OK, "%s", d.message);
    md = pf.desc;
    md.max_vertices = 2000;
    s = wr_mesher_run(&pf.pattern, &md, &res, &d);
    cr_assert_eq(s, WR_ERR_BUDGET, "status %s: %s", wr_status_string(s), d.message);
    cr_assert(strstr(d.message, "vertex budget of 2000 exceeded at panels[0]") != NULL, "message: %s", d.message);
    cr_assert(strchr(d.message, '\n') == NULL);
    wr_mesher_free(&res);
    wr_pattern_file_free(&pf);
    free(text);
}

/* fuzz_pattern: a curve piece needing ~5.5e127 discretisation steps overflowed the int32 cast in
 * mesher.h's curve walk (UBSan, found by the CI fuzz smoke run). The counts are now clamped in double
 * and absurd pieces refused: the run must end with a status, never undefined behaviour (this binary
 * runs under UBSan with -fno-sanitize-recover, so the old code aborts here). */
Test(regressions, pattern_piece_count_overflow) {
    size_t len;
    char *text = read_regression("pattern_piece_count_overflow.fuzz_pattern", &len);
    wr_pattern_file pf;
    wr_diag d;
    wr_status s;
    memset(&d, 0, sizeof d);
    s = wr_pattern_parse(text, len, "fuzz.json", &pf, &d);
    if (s == WR_OK) {
        wr_mesher_desc md = pf.desc;
        wr_mesher_result res;
        md.max_vertices = 2000;
        s = wr_mesher_run(&pf.pattern, &md, &res, &d);
        cr_assert(s != WR_OK || res.mesh.nv <= 2000, "status %s", wr_status_string(s));
        if (s == WR_OK) wr_mesher_free(&res);
        else cr_assert(strchr(d.message, '\n') == NULL);
    }
    wr_pattern_file_free(&pf);
    free(text);
}
