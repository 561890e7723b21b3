/* sizing.h: the source field (wr_sizing: min composition, grid == brute force, directional points,
 * gradient, metric hook, errors) and the pattern's sizing map (wr_sizing_map: closed-form transition
 * profile, anisotropic metric eigenvalues, collision regions, long-short seams, uniform override,
 * raster, vertex estimate, errors). */
#include <criterion/criterion.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "wrinkle/sizing.h"

static double rel(double a, double b) { return fabs(a - b) / fabs(b); }
/* ---- sizing map --------------------------------------------------------------------------- */

static double seg_dist(double px, double py, double ax, double ay, double bx, double by) {
    double ex = bx - ax, ey = by - ay, ee = ex * ex + ey * ey, t = 0.0;
    if (ee > 0.0) t = fmax(0.0, fmin(1.0, ((px - ax) * ex + (py - ay) * ey) / ee));
    return hypot(px - ax - t * ex, py - ay - t * ey);
}

Test(sizing, single_polyline_known_values) {
    wr_sizing *s;
    wr_transition t;
    double line[6] = {0.0, 0.0, 0.3, 0.0, 0.3, 0.2};
    cr_assert_eq(wr_transition_make(3e-3, 25e-3, NULL, &t, NULL), WR_OK);
    cr_assert_eq(wr_sizing_create(9e-3, NULL, &s, NULL), WR_OK);
    cr_assert_eq(wr_sizing_add_polyline(s, line, 3, &t, NULL), WR_OK);
    cr_expect_eq(wr_sizing_segment_count(s), 2);
    cr_expect_eq(wr_sizing_eval(s, 0.1, 0.0), 3e-3);         /* on the line: r_source */
    cr_expect(rel(wr_sizing_eval(s, 0.1, 0.025), 6e-3) < 1e-14); /* L_w away: doubled */
    cr_expect(rel(wr_sizing_eval(s, 0.1, -0.025), 6e-3) < 1e-14);
    cr_expect(rel(wr_sizing_eval(s, 0.325, 0.1), 6e-3) < 1e-14); /* second segment */
    cr_expect_eq(wr_sizing_eval(s, 0.1, 0.5), 9e-3);          /* far away: r_f */
    cr_assert_eq(wr_sizing_build(s, NULL), WR_OK);
    cr_expect(wr_sizing_is_built(s));
    cr_expect(rel(wr_sizing_eval(s, 0.1, 0.025), 6e-3) < 1e-14);
    cr_expect_eq(wr_sizing_eval(s, 0.1, 0.5), 9e-3);
    cr_expect_eq(wr_sizing_eval(s, 1e30, -1e30), 9e-3);
    cr_expect(isnan(wr_sizing_eval(s, NAN, 0.0)));
    cr_expect(isnan(wr_sizing_eval_brute(s, 0.0, NAN)));
    wr_sizing_free(s);
    wr_sizing_free(NULL);
}

/* Random sources (seeded): the map equals the min-composition formula written out here, and the grid
 * index returns bit-identical values to brute force, for several cell sizes. */
Test(sizing, random_min_composition_and_grid) {
    wr_rng rng;
    int trial;
    wr_rng_seed(&rng, 20250731);
    for (trial = 0; trial < 6; ++trial) {
        wr_sizing *s;
        wr_sizing_desc desc;
        enum { NSRC = 60, NPTS_MAX = 6 };
        double src_xy[NSRC][2 * NPTS_MAX];
        int src_n[NSRC];
        wr_transition src_t[NSRC];
        const double r_f = 10e-3;
        int i, q, mismatches = 0;
        memset(&desc, 0, sizeof desc);
        desc.cell_size = trial < 2 ? 0.0 : 0.01 * (double)trial; /* auto and explicit cells */
        cr_assert_eq(wr_sizing_create(r_f, &desc, &s, NULL), WR_OK);
        for (i = 0; i < NSRC; ++i) {
            int k;
            double r = 1.5e-3 + 10e-3 * wr_rng_uniform(&rng); /* some above r_f: inactive */
            double L = 5e-3 + 60e-3 * wr_rng_uniform(&rng);
            double x = wr_rng_uniform(&rng), y = 0.6 * wr_rng_uniform(&rng);
            cr_assert_eq(wr_transition_make(r, L, NULL, &src_t[i], NULL), WR_OK);
            src_n[i] = 1 + (int)wr_rng_below(&rng, NPTS_MAX);
            for (k = 0; k < src_n[i]; ++k) {
                src_xy[i][2 * k] = x;
                src_xy[i][2 * k + 1] = y;
                x += 0.1 * (wr_rng_uniform(&rng) - 0.5);
                y += 0.1 * (wr_rng_uniform(&rng) - 0.5);
            }
            cr_assert_eq(wr_sizing_add_polyline(s, src_xy[i], src_n[i], &src_t[i], NULL), WR_OK);
        }
        cr_assert_eq(wr_sizing_build(s, NULL), WR_OK);
        for (q = 0; q < 1500; ++q) {
            double px = -0.3 + 1.6 * wr_rng_uniform(&rng), py = -0.3 + 1.2 * wr_rng_uniform(&rng);
            double want = r_f, brute, grid;
            for (i = 0; i < NSRC; ++i) {
                double d = INFINITY;
                int k;
                if (src_n[i] == 1)
                    d = hypot(px - src_xy[i][0], py - src_xy[i][1]);
                else
                    for (k = 0; k + 1 < src_n[i]; ++k)
                        d = fmin(d, seg_dist(px, py, src_xy[i][2 * k], src_xy[i][2 * k + 1], src_xy[i][2 * k + 2],
                                             src_xy[i][2 * k + 3]));
                want = fmin(want, src_t[i].r * (1.0 + pow(d / src_t[i].L_w, src_t[i].m)));
            }
            brute = wr_sizing_eval_brute(s, px, py);
            grid = wr_sizing_eval(s, px, py);
            cr_expect(rel(brute, want) < 1e-14, "brute %.17g want %.17g", brute, want);
            if (grid != brute) ++mismatches;
        }
        cr_expect_eq(mismatches, 0, "trial %d: %d grid/brute mismatches", trial, mismatches);
        wr_sizing_free(s);
    }
}

/* Many point sources (> the exact-bound group count) exercise the conservative ring bound. */
Test(sizing, many_points_grid_equals_brute) {
    wr_rng rng;
    wr_sizing *s;
    int i, q, mismatches = 0;
    wr_rng_seed(&rng, 7);
    cr_assert_eq(wr_sizing_create(8e-3, NULL, &s, NULL), WR_OK);
    for (i = 0; i < 400; ++i) {
        wr_transition t;
        cr_assert_eq(wr_transition_make(1e-3 + 6e-3 * wr_rng_uniform(&rng), 2e-3 + 30e-3 * wr_rng_uniform(&rng),
                                        NULL, &t, NULL),
                     WR_OK);
        if (i % 3 == 0)
            cr_assert_eq(wr_sizing_add_point_directional(s, wr_rng_uniform(&rng), wr_rng_uniform(&rng),
                                                         wr_rng_normal(&rng), wr_rng_normal(&rng), &t, NULL),
                         WR_OK);
        else
            cr_assert_eq(wr_sizing_add_point(s, wr_rng_uniform(&rng), wr_rng_uniform(&rng), &t, NULL), WR_OK);
    }
    /* before build: eval scans */
    cr_expect(!wr_sizing_is_built(s));
    cr_expect_eq(wr_sizing_eval(s, 0.5, 0.5), wr_sizing_eval_brute(s, 0.5, 0.5));
    cr_assert_eq(wr_sizing_build(s, NULL), WR_OK);
    for (q = 0; q < 3000; ++q) {
        double px = -0.2 + 1.4 * wr_rng_uniform(&rng), py = -0.2 + 1.4 * wr_rng_uniform(&rng);
        if (wr_sizing_eval(s, px, py) != wr_sizing_eval_brute(s, px, py)) ++mismatches;
    }
    cr_expect_eq(mismatches, 0);
    /* adding a source invalidates the index; eval stays correct */
    {
        wr_transition t;
        cr_assert_eq(wr_transition_make(1.2e-3, 5e-3, NULL, &t, NULL), WR_OK);
        cr_assert_eq(wr_sizing_add_point(s, 0.123, 0.456, &t, NULL), WR_OK);
        cr_expect(!wr_sizing_is_built(s));
        cr_expect_eq(wr_sizing_eval(s, 0.123, 0.456), 1.2e-3);
    }
    wr_sizing_free(s);
}

/* Sec. 4.2.3: a directional folding endpoint only affects the forward half-space. */
Test(sizing, directional_half_space) {
    wr_sizing *s;
    wr_transition t;
    cr_assert_eq(wr_transition_make(2e-3, 20e-3, NULL, &t, NULL), WR_OK);
    cr_assert_eq(wr_sizing_create(9e-3, NULL, &s, NULL), WR_OK);
    cr_assert_eq(wr_sizing_add_point_directional(s, 0.0, 0.0, 1.0, 0.0, &t, NULL), WR_OK);
    cr_assert_eq(wr_sizing_build(s, NULL), WR_OK);
    cr_expect(rel(wr_sizing_eval(s, 0.02, 0.0), 4e-3) < 1e-14);
    cr_expect(rel(wr_sizing_eval(s, 0.0, 0.02), 4e-3) < 1e-14); /* on the boundary line: included */
    cr_expect_eq(wr_sizing_eval(s, -0.001, 0.0), 9e-3);
    cr_expect_eq(wr_sizing_eval(s, -0.02, 0.01), 9e-3);
    cr_expect_eq(wr_sizing_eval(s, 0.0, 0.0), 2e-3);
    wr_sizing_free(s);
}

Test(sizing, gradient_matches_finite_difference) {
    wr_sizing *s;
    wr_transition t;
    double line[4] = {0.0, 0.0, 0.2, 0.05};
    double r, g[2];
    int i;
    cr_assert_eq(wr_transition_make(3e-3, 25e-3, NULL, &t, NULL), WR_OK);
    cr_assert_eq(wr_sizing_create(9e-3, NULL, &s, NULL), WR_OK);
    cr_assert_eq(wr_sizing_add_polyline(s, line, 2, &t, NULL), WR_OK);
    cr_assert_eq(wr_sizing_build(s, NULL), WR_OK);
    {
        const double pts[][2] = {{0.1, 0.04}, {0.05, -0.01}, {0.21, 0.06}, {-0.01, 0.005}};
        for (i = 0; i < 4; ++i) {
            const double h = 1e-7, x = pts[i][0], y = pts[i][1];
            double fx = (wr_sizing_eval(s, x + h, y) - wr_sizing_eval(s, x - h, y)) / (2 * h);
            double fy = (wr_sizing_eval(s, x, y + h) - wr_sizing_eval(s, x, y - h)) / (2 * h);
            wr_sizing_eval_gradient(s, x, y, &r, g);
            cr_expect_eq(r, wr_sizing_eval(s, x, y));
            cr_expect(fabs(g[0] - fx) < 1e-6 * (fabs(fx) + fabs(fy)) + 1e-12, "pt %d gx %g fd %g", i, g[0], fx);
            cr_expect(fabs(g[1] - fy) < 1e-6 * (fabs(fx) + fabs(fy)) + 1e-12, "pt %d gy %g fd %g", i, g[1], fy);
        }
    }
    wr_sizing_eval_gradient(s, 0.1, 0.5, &r, g); /* r_f active */
    cr_expect(r == 9e-3 && g[0] == 0.0 && g[1] == 0.0);
    wr_sizing_free(s);
}

static int region_left_half(void *user, double x, double y, double *rw, double *rf, double *ang) {
    (void)user;
    (void)y;
    if (x >= 0.5) return 0;
    *rw = 8e-3;
    *rf = 4e-3;
    *ang = 0.25;
    return 1;
}

Test(sizing, metric_hook) {
    wr_sizing *s;
    wr_transition t;
    wr_mat2 M, W;
    /* paper form r + x^1 (mm): 2 mm at the source, 8 mm (= r_f) 6 mm away */
    cr_assert_eq(wr_transition_from_power(2e-3, 1.0, &t, NULL), WR_OK);
    cr_assert_eq(wr_sizing_create(8e-3, NULL, &s, NULL), WR_OK);
    cr_assert_eq(wr_sizing_add_point(s, 0.2, 0.2, &t, NULL), WR_OK);
    cr_assert_eq(wr_sizing_build(s, NULL), WR_OK);
    /* no region: isotropic 1/r_v² */
    M = wr_sizing_eval_metric(s, 0.9, 0.9);
    cr_expect(rel(M.m[0][0], 1.0 / (8e-3 * 8e-3)) < 1e-14 && M.m[0][1] == 0.0);
    wr_sizing_set_region_fn(s, region_left_half, NULL);
    M = wr_sizing_eval_metric(s, 0.1, 0.9); /* region, far from the source */
    W = wr_resolution_metric(8e-3, 4e-3, 0.25);
    cr_expect(rel(M.m[0][0], W.m[0][0]) < 1e-14 && rel(M.m[0][1], W.m[0][1]) < 1e-14 &&
              rel(M.m[1][1], W.m[1][1]) < 1e-14);
    /* on the source: both directions refined to 2 mm */
    M = wr_sizing_eval_metric(s, 0.2, 0.2);
    cr_expect(rel(M.m[0][0], 1.0 / 4e-6) < 1e-12 && rel(M.m[1][1], 1.0 / 4e-6) < 1e-12);
    cr_expect(fabs(M.m[0][1]) < 1e-6 * M.m[0][0]);
    /* 4 mm away r_v = 6 mm: it refines only the 8 mm warp direction */
    {
        double d = t.L_w * pow(2.0, 1.0 / t.m), rv = wr_sizing_eval(s, 0.2 + d, 0.2);
        cr_expect(rel(rv, 6e-3) < 1e-12, "rv=%g", rv);
        M = wr_sizing_eval_metric(s, 0.2 + d, 0.2);
        W = wr_resolution_metric(rv, 4e-3, 0.25);
        cr_expect(rel(M.m[0][0], W.m[0][0]) < 1e-12 && rel(M.m[1][1], W.m[1][1]) < 1e-12);
    }
    wr_sizing_free(s);
}

Test(sizing, error_paths) {
    wr_sizing *s = NULL;
    wr_transition t, bad;
    wr_sizing_desc desc;
    wr_diag d;
    double pts[4] = {0.0, 0.0, NAN, 1.0};
    cr_expect_eq(wr_sizing_create(0.0, NULL, &s, &d), WR_ERR_INVALID_ARG);
    cr_expect(s == NULL);
    cr_expect_eq(wr_sizing_create(INFINITY, NULL, &s, NULL), WR_ERR_INVALID_ARG);
    cr_expect_eq(wr_sizing_create(1e-3, NULL, NULL, NULL), WR_ERR_INVALID_ARG);
    memset(&desc, 0, sizeof desc);
    desc.cell_size = -1.0;
    cr_expect_eq(wr_sizing_create(1e-2, &desc, &s, NULL), WR_ERR_INVALID_ARG);
    desc.cell_size = 0.0;
    desc.max_cells = -5;
    cr_expect_eq(wr_sizing_create(1e-2, &desc, &s, NULL), WR_ERR_INVALID_ARG);
    cr_assert_eq(wr_sizing_create(1e-2, NULL, &s, NULL), WR_OK);
    cr_assert_eq(wr_transition_make(2e-3, 20e-3, NULL, &t, NULL), WR_OK);
    bad = t;
    bad.L_w = 0.0;
    cr_expect_eq(wr_sizing_add_point(s, 0.0, 0.0, &bad, &d), WR_ERR_INVALID_ARG);
    cr_expect(strstr(d.message, "L_w") != NULL, "%s", d.message);
    cr_expect_eq(wr_sizing_add_point(s, 0.0, 0.0, NULL, NULL), WR_ERR_INVALID_ARG);
    cr_expect_eq(wr_sizing_add_point(s, INFINITY, 0.0, &t, NULL), WR_ERR_INVALID_ARG);
    cr_expect_eq(wr_sizing_add_point(NULL, 0.0, 0.0, &t, NULL), WR_ERR_INVALID_ARG);
    cr_expect_eq(wr_sizing_add_point_directional(s, 0.0, 0.0, 0.0, 0.0, &t, NULL), WR_ERR_INVALID_ARG);
    cr_expect_eq(wr_sizing_add_point_directional(s, NAN, 0.0, 1.0, 0.0, &t, NULL), WR_ERR_INVALID_ARG);
    cr_expect_eq(wr_sizing_add_polyline(s, pts, 2, &t, &d), WR_ERR_INVALID_ARG);
    cr_expect_eq(d.item, 1);
    cr_expect_eq(wr_sizing_add_polyline(s, pts, 0, &t, NULL), WR_ERR_INVALID_ARG);
    cr_expect_eq(wr_sizing_add_polyline(s, NULL, 2, &t, NULL), WR_ERR_INVALID_ARG);
    cr_expect_eq(wr_sizing_segment_count(s), 0); /* failed adds leave nothing behind */
    cr_expect_eq(wr_sizing_build(NULL, NULL), WR_ERR_INVALID_ARG);
    /* a built map without active sources is r_f everywhere; a source coarser than r_f is inert */
    t.r = 2e-2;
    cr_assert_eq(wr_sizing_add_point(s, 0.0, 0.0, &t, NULL), WR_OK);
    cr_assert_eq(wr_sizing_build(s, NULL), WR_OK);
    cr_expect_eq(wr_sizing_eval(s, 0.0, 0.0), 1e-2);
    wr_sizing_free(s);
}

/* Fine grid cells and a query between sources: the ring search must keep going until the reach of
 * the source (where its term meets r_f), not stop at the first empty rings. */
Test(sizing, ring_search_reaches_far_sources) {
    wr_sizing *s;
    wr_sizing_desc desc;
    wr_transition t;
    double x;
    memset(&desc, 0, sizeof desc);
    desc.cell_size = 0.5e-3;
    cr_assert_eq(wr_transition_from_power(2e-3, 1.0, &t, NULL), WR_OK); /* r + x (mm): reach 8 mm */
    cr_assert_eq(wr_sizing_create(10e-3, &desc, &s, NULL), WR_OK);
    cr_assert_eq(wr_sizing_add_point(s, 0.0, 0.0, &t, NULL), WR_OK);
    cr_assert_eq(wr_sizing_add_point(s, 0.05, 0.05, &t, NULL), WR_OK);
    cr_assert_eq(wr_sizing_build(s, NULL), WR_OK);
    for (x = 0.0; x <= 12e-3; x += 0.25e-3) {
        double want = fmin(10e-3, 2e-3 + x);
        cr_expect(fabs(wr_sizing_eval(s, x, 0.0) - want) < 1e-15, "x=%g: %.17g want %.17g", x,
                  wr_sizing_eval(s, x, 0.0), want);
        cr_expect(fabs(wr_sizing_eval(s, 0.05 - 0.6 * x, 0.05 - 0.8 * x) - want) < 1e-15);
        cr_expect_eq(wr_sizing_eval(s, x, 0.0), wr_sizing_eval_brute(s, x, 0.0));
    }
    wr_sizing_free(s);
}

Test(sizing, build_cap_below_segment_count_is_budget_error) {
    wr_transition t;
    wr_sizing *s;
    wr_sizing_desc sd;
    wr_diag d;
    double line[6] = {0.0, 0.0, 0.1, 0.0, 0.2, 0.05};
    memset(&sd, 0, sizeof sd);
    sd.max_cells = 1;
    cr_assert_eq(wr_transition_make(3.0e-3, 25.0e-3, NULL, &t, NULL), WR_OK);
    cr_assert_eq(wr_sizing_create(9.0e-3, &sd, &s, NULL), WR_OK);
    cr_assert_eq(wr_sizing_add_polyline(s, line, 3, &t, NULL), WR_OK);
    cr_expect_eq(wr_sizing_build(s, &d), WR_ERR_BUDGET);
    cr_expect(strstr(d.message, "max_cells") != NULL, "%s", d.message);
    cr_expect_eq(wr_sizing_is_built(s), 0);
    cr_expect_eq(wr_sizing_eval(s, 0.05, 0.025), wr_sizing_eval_brute(s, 0.05, 0.025));
    cr_expect(rel(wr_sizing_eval(s, 0.05, 0.025), 6.0e-3) < 1e-12); /* 25 mm from the first segment */
    wr_sizing_free(s);
}

/* Regression: finite sources whose extent overflows a double (xmax - xmin = inf) made the grid
 * size NaN and wr_sizing_build looped forever. Now WR_ERR_DOMAIN naming the extent; a polyline
 * segment whose squared length overflows (distances to it would be wrong) is refused when added. */
Test(sizing, build_extent_overflow_is_domain_error) {
    wr_transition t;
    wr_sizing *s;
    wr_diag d;
    double far[4] = {-1e308, 0.0, 1e308, 0.0}, ok[4] = {0.0, 0.0, 1.0, 0.0};
    cr_assert_eq(wr_transition_make(3.0e-3, 25.0e-3, NULL, &t, NULL), WR_OK);
    cr_assert_eq(wr_sizing_create(9.0e-3, NULL, &s, NULL), WR_OK);
    cr_expect_eq(wr_sizing_add_polyline(s, far, 2, &t, &d), WR_ERR_DOMAIN);
    cr_expect_eq(d.item, 0);
    cr_expect(strstr(d.message, "segment 0") != NULL, "%s", d.message);
    cr_expect_eq(wr_sizing_segment_count(s), 0);
    cr_assert_eq(wr_sizing_add_point(s, -1e308, 0.0, &t, NULL), WR_OK);
    cr_assert_eq(wr_sizing_add_point(s, 1e308, 0.0, &t, NULL), WR_OK);
    cr_assert_eq(wr_sizing_add_polyline(s, ok, 2, &t, NULL), WR_OK);
    cr_expect_eq(wr_sizing_build(s, &d), WR_ERR_DOMAIN);
    cr_expect(strstr(d.message, "extent") != NULL, "%s", d.message);
    cr_expect_eq(wr_sizing_is_built(s), 0);
    cr_expect(rel(wr_sizing_eval(s, 0.5, 0.025), 6.0e-3) < 1e-12);
    wr_sizing_free(s);
}

/* ---- the pattern's sizing map ------------------------------------------------------------------ */
static double sq300[8] = {0, 0, 0.3, 0, 0.3, 0.3, 0, 0.3};

static void one_panel(wr_pattern *pat, wr_pattern_panel *pn, double r_override) {
    memset(pat, 0, sizeof *pat);
    memset(pn, 0, sizeof *pn);
    pn->outer.xy = sq300;
    pn->outer.n = 4;
    pn->fabric.resolution = r_override;
    pat->panels = pn;
    pat->n_panels = 1;
}

/* Style3D Sec. 4.2.1: r(x) = r + x^m (mm) with m = ln r / ln L_w, evaluated in the paper's literal form
 * at known distances from a shirring line. r_f = 10 mm (override, no stiffness: r_sh = ρ r_f = 5 mm),
 * L_w = 20 mm given. Tolerance 1e-12 relative: the map's scale-free form r (1 + (x/L)^m) equals r + x^m
 * in exact arithmetic when r = L^m; the two differ by a few ulps of pow. */
Test(sizing_map, transition_profile_closed_form) {
    wr_pattern pat;
    wr_pattern_panel pn;
    wr_pattern_shirring sh;
    wr_sizing_map map;
    wr_diag d;
    double line[4] = {0.05, 0.15, 0.25, 0.15}, x_mm[5] = {0.0, 1.0, 5.0, 12.5, 19.0};
    double m = log(5.0) / log(20.0);
    int k;
    one_panel(&pat, &pn, 10e-3);
    memset(&sh, 0, sizeof sh);
    sh.xy = line;
    sh.n = 2;
    sh.rho = 0.5;
    sh.transition_length = 20e-3;
    pat.shirrings = &sh;
    pat.n_shirrings = 1;
    cr_assert_eq(wr_sizing_map_build(&pat, NULL, &map, &d), WR_OK, "%s", d.message);
    cr_expect_eq(map.panels[0].n_sources, 1);
    for (k = 0; k < 5; ++k) {
        double want = 1e-3 * (5.0 + pow(x_mm[k], m)), got = wr_sizing_map_eval(&map, 0, 0.15, 0.15 + 1e-3 * x_mm[k]);
        cr_expect(rel(got, want) < 1e-12, "x = %g mm: %.15g vs %.15g", x_mm[k], got, want);
    }
    /* r + L_w^m = 2r = r_f at x = L_w: beyond it the fabric resolution caps the map */
    cr_expect_eq(wr_sizing_map_eval(&map, 0, 0.15, 0.15 + 25e-3), 10e-3);
    /* beyond the line's end the distance is to the end point: 5 mm past (0.25, 0.15) along x */
    cr_expect(rel(wr_sizing_map_eval(&map, 0, 0.255, 0.15), 1e-3 * (5.0 + pow(5.0, m))) < 1e-12);
    cr_expect(isnan(wr_sizing_map_eval(&map, 1, 0.1, 0.1)));
    wr_sizing_map_free(&map);
    cr_expect_null(map.panels);
}

/* Sec. 4.2.1 with the compression law: the wrinklon size of a shirring line is L_w(λ) of the source
 * WAVELENGTH λ = r_sh / c, c = sqrt(1/16 + 2δ/π²) (Fig. 4's r = sqrt(λ²/16 + A²), A = (√2/π) λ √δ),
 * L_w = λ^{3/2} (δ/h²)^{1/4}, not L_w(r_sh). The Fig. 14 line: Table 1 Green (B = 2.6e-6 N m,
 * E = 2 MPa, r_f = 6.03 mm), ρ = 0.5, E_sh = E: r_sh = 2.71 mm, λ = 6.69 mm, L_w = 29.6 mm, m = 0.294,
 * so r(20 mm) = 5.12 mm and r(L_w) = 2 r_sh = 5.42 mm; with L_w(r_sh) = 7.6 mm the map reached r_f
 * 11.6 mm from the line (the Fig. 15 miss, docs/garments.md). Tolerance 1e-9 relative: pow/log
 * round-off of an independent evaluation in the paper's literal mm form r + x^m. */
Test(sizing_map, shirring_transition_from_the_source_wavelength) {
    wr_pattern pat;
    wr_pattern_panel pn;
    wr_pattern_shirring sh;
    wr_sizing_map map;
    wr_diag d;
    const double B = 2.6e-6, E = 2.0e6, delta = 0.5, pi = 3.14159265358979323846;
    double line[4] = {0.03, 0.125, 0.22, 0.125}, r_sh, h, lambda, L_mm, m, x_mm[3] = {5.0, 20.0, 0.0};
    int k;
    one_panel(&pat, &pn, 0.0);
    pn.fabric.B = B, pn.fabric.E = E;
    memset(&sh, 0, sizeof sh);
    sh.xy = line, sh.n = 2, sh.rho = 0.5, sh.E_sh = E;
    pat.shirrings = &sh, pat.n_shirrings = 1;
    cr_assert_eq(wr_sizing_map_build(&pat, NULL, &map, &d), WR_OK, "%s", d.message);
    r_sh = wr_sizing_map_eval(&map, 0, 0.1, 0.125); /* Sec. 4.2.2's value, tested in test_transition.c */
    cr_expect(fabs(1e3 * r_sh - 2.709) < 1e-3 && fabs(1e3 * map.panels[0].r0 - 6.034) < 1e-3, "r_sh %g, r_f %g", r_sh,
              map.panels[0].r0);
    h = cbrt(12.0 * (1.0 - 0.3 * 0.3) * B / E);
    lambda = r_sh / sqrt(1.0 / 16.0 + 2.0 * delta / (pi * pi));
    L_mm = 1e3 * pow(lambda, 1.5) * pow(delta / (h * h), 0.25);
    m = log(1e3 * r_sh) / log(L_mm);
    cr_expect(fabs(L_mm - 29.59) < 0.01 && fabs(m - 0.294) < 1e-3, "L_w %g mm, m %g", L_mm, m);
    x_mm[2] = L_mm;
    for (k = 0; k < 3; ++k) {
        double want = r_sh + 1e-3 * pow(x_mm[k], m), got = wr_sizing_map_eval(&map, 0, 0.1, 0.125 + 1e-3 * x_mm[k]);
        cr_expect(rel(got, want) < 1e-9, "x = %g mm: %.12g vs %.12g m", x_mm[k], got, want);
    }
    cr_expect(rel(wr_sizing_map_eval(&map, 0, 0.1, 0.125 + 1e-3 * L_mm), 2.0 * r_sh) < 1e-9);
    wr_sizing_map_free(&map);
}

/* Sec. 4.1.2: M = R diag(1/r_warp², 1/r_weft²) Rᵀ with no sources; eigenvalues 1/64 and 1/16 mm⁻²,
 * the smaller along the grain (30°). Tolerance 1e-12 relative: a handful of roundings in T, Tᵀ T. */
Test(sizing_map, anisotropic_metric_eigenvalues) {
    wr_pattern pat;
    wr_pattern_panel pn;
    wr_sizing_map map;
    wr_diag d;
    wr_mat2 M;
    wr_vec2 vec[2];
    double lam[2], a = 30.0 * 3.14159265358979323846 / 180.0, lo, hi, p[2] = {0.1, 0.2}, q[2], back[2];
    int ilo;
    one_panel(&pat, &pn, 0.0);
    pn.fabric.anisotropic = 1;
    pn.fabric.resolution_warp = 8e-3;
    pn.fabric.resolution_weft = 4e-3;
    pn.fabric.grain_angle = a;
    cr_assert_eq(wr_sizing_map_build(&pat, NULL, &map, &d), WR_OK, "%s", d.message);
    cr_expect_eq(map.panels[0].r0, 4e-3);
    cr_expect_eq(wr_sizing_map_eval(&map, 0, 0.1, 0.1), 4e-3);
    M = wr_sizing_map_eval_metric(&map, 0, 0.1, 0.1);
    wr_m2_sym_eig(M, lam, vec);
    ilo = lam[0] < lam[1] ? 0 : 1;
    lo = lam[ilo];
    hi = lam[1 - ilo];
    cr_expect(rel(lo, 1.0 / (8e-3 * 8e-3)) < 1e-12, "%.15g", lo);
    cr_expect(rel(hi, 1.0 / (4e-3 * 4e-3)) < 1e-12, "%.15g", hi);
    cr_expect(fabs(fabs(vec[ilo].x * cos(a) + vec[ilo].y * sin(a)) - 1.0) < 1e-12, "warp eigenvector");
    /* T maps an on-target warp edge to length r0, and T⁻¹ undoes T */
    {
        double e[2] = {8e-3 * cos(a), 8e-3 * sin(a)}, te[2];
        wr_sizing_panel_to_stretched(&map.panels[0], e, te);
        cr_expect(rel(sqrt(te[0] * te[0] + te[1] * te[1]), 4e-3) < 1e-12);
    }
    wr_sizing_panel_to_stretched(&map.panels[0], p, q);
    wr_sizing_panel_to_pattern(&map.panels[0], q, back);
    cr_expect(fabs(back[0] - p[0]) < 1e-15 && fabs(back[1] - p[1]) < 1e-15);
    wr_sizing_map_free(&map);
}

/* Sec. 4.2.6: inside a collision disk of compression δ = 0.4 the map is (1 − δ) r_f exactly; it grows
 * outside; Sec. 4.2.4: a 0.3 m side sewn to a 0.24 m side gathers: ρ_s = 0.8, r = 0.8 r_f on it. */
Test(sizing_map, collision_region_and_long_short_seam) {
    wr_pattern pat;
    wr_pattern_panel pn[2];
    wr_pattern_collision col;
    wr_pattern_seam se;
    wr_sizing_map map;
    wr_diag d;
    double sq240[8] = {0.4, 0, 0.64, 0, 0.64, 0.24, 0.4, 0.24};
    one_panel(&pat, &pn[0], 10e-3);
    pn[1] = pn[0];
    pn[1].outer.xy = sq240;
    pat.panels = pn;
    pat.n_panels = 2;
    memset(&col, 0, sizeof col);
    col.center[0] = 0.15;
    col.center[1] = 0.2;
    col.radius = 0.03;
    col.compression = 0.4;
    pat.collisions = &col;
    pat.n_collisions = 1;
    memset(&se, 0, sizeof se);
    se.a.panel = 0; /* the bottom edge of the 0.3 m panel */
    se.a.to[0] = 0.3;
    se.b.panel = 1; /* the bottom edge of the 0.24 m panel */
    se.b.from[0] = 0.4;
    se.b.to[0] = 0.64;
    pat.seams = &se;
    pat.n_seams = 1;
    cr_assert_eq(wr_sizing_map_build(&pat, NULL, &map, &d), WR_OK, "%s", d.message);
    cr_expect_eq(map.panels[0].n_regions, 1);
    cr_expect_eq(map.panels[0].n_sources, 2); /* the disk's boundary and the long seam side */
    cr_expect_eq(map.panels[1].n_sources, 0);
    cr_expect(rel(wr_sizing_map_eval(&map, 0, 0.15, 0.2), 6e-3) < 1e-14); /* (1 - 0.4) 10 mm: two roundings */
    cr_expect(rel(wr_sizing_map_eval(&map, 0, 0.165, 0.21), 6e-3) < 1e-14);
    cr_expect_gt(wr_sizing_map_eval(&map, 0, 0.15, 0.235), 6e-3);
    cr_expect(rel(wr_sizing_map_eval(&map, 0, 0.1, 0.0), 0.8 * 10e-3) < 1e-12);
    cr_expect_eq(wr_sizing_map_eval(&map, 1, 0.5, 0.0), 10e-3); /* the short side is not refined */
    wr_sizing_map_free(&map);
}

/* The raster is the map at the cell centres, NaN outside the outer loop and inside holes. */
Test(sizing_map, raster_matches_eval_and_masks_holes) {
    wr_pattern pat;
    wr_pattern_panel pn;
    wr_pattern_curve hole;
    wr_pattern_shirring sh;
    wr_sizing_map map;
    wr_diag d;
    double hxy[8] = {0.2, 0.2, 0.28, 0.2, 0.28, 0.28, 0.2, 0.28}, line[4] = {0.05, 0.1, 0.25, 0.1};
    double box[4] = {-0.1, -0.1, 0.4, 0.4}, img[50 * 40];
    int i, j, n_nan = 0;
    one_panel(&pat, &pn, 10e-3);
    hole.xy = hxy;
    hole.n = 4;
    pn.holes = &hole;
    pn.n_holes = 1;
    memset(&sh, 0, sizeof sh);
    sh.xy = line;
    sh.n = 2;
    sh.rho = 0.5;
    pat.shirrings = &sh;
    pat.n_shirrings = 1;
    cr_assert_eq(wr_sizing_map_build(&pat, NULL, &map, &d), WR_OK, "%s", d.message);
    cr_assert_eq(wr_sizing_map_raster(&map, 0, box, 50, 40, img, &d), WR_OK, "%s", d.message);
    for (j = 0; j < 40; ++j)
        for (i = 0; i < 50; ++i) {
            double x = -0.1 + (i + 0.5) * 0.5 / 50, y = -0.1 + (j + 0.5) * 0.5 / 40, v = img[j * 50 + i];
            int inside = x > 0 && x < 0.3 && y > 0 && y < 0.3 && !(x > 0.2 && x < 0.28 && y > 0.2 && y < 0.28);
            if (inside)
                cr_expect_eq(v, wr_sizing_map_eval(&map, 0, x, y), "(%d, %d)", i, j);
            else
                cr_expect(isnan(v), "(%d, %d) outside: %g", i, j, v);
            n_nan += isnan(v);
        }
    cr_expect_gt(n_nan, 0);
    cr_expect_eq(wr_sizing_map_raster(&map, 1, box, 50, 40, img, &d), WR_ERR_INVALID_ARG);
    cr_expect_eq(wr_sizing_map_raster(&map, 0, box, 0, 40, img, &d), WR_ERR_INVALID_ARG);
    wr_sizing_map_free(&map);
}

/* Uniform override: one size everywhere, no sources, seam ends still located; the estimate is
 * A / r² + P / (2r) = 0.09 / 25e-6 + 1.2 / 10e-3 = 3720 exactly at 5 mm, a quarter of the area term
 * at spacing 2. */
Test(sizing_map, uniform_override_and_vertex_estimate) {
    wr_pattern pat;
    wr_pattern_panel pn;
    wr_pattern_shirring sh;
    wr_sizing_map map;
    wr_sizing_map_desc sd;
    wr_diag d;
    double line[4] = {0.05, 0.1, 0.25, 0.1};
    one_panel(&pat, &pn, 10e-3);
    memset(&sh, 0, sizeof sh);
    sh.xy = line;
    sh.n = 2;
    sh.rho = 0.5;
    pat.shirrings = &sh;
    pat.n_shirrings = 1;
    memset(&sd, 0, sizeof sd);
    sd.uniform_resolution = 5e-3;
    cr_assert_eq(wr_sizing_map_build(&pat, &sd, &map, &d), WR_OK, "%s", d.message);
    cr_expect_eq(map.panels[0].n_sources, 0);
    cr_expect_eq(wr_sizing_map_eval(&map, 0, 0.1, 0.1), 5e-3);
    cr_expect_eq(wr_sizing_map_eval(&map, 0, 0.15, 0.1), 5e-3);
    cr_expect(rel(wr_sizing_map_vertex_estimate(&map, 0, 0.0), 3720.0) < 1e-12);
    cr_expect(rel(wr_sizing_map_vertex_estimate(&map, 0, 2.0), 900.0 + 120.0) < 1e-12);
    wr_sizing_map_free(&map);
}

/* Errors name the item and leave the map zeroed. */
Test(sizing_map, errors) {
    wr_pattern pat;
    wr_pattern_panel pn;
    wr_pattern_shirring sh;
    wr_pattern_seam se;
    wr_sizing_map map;
    wr_diag d;
    double leave[4] = {0.05, 0.1, 0.4, 0.1};
    one_panel(&pat, &pn, 10e-3);
    memset(&sh, 0, sizeof sh);
    sh.xy = leave;
    sh.n = 2;
    sh.rho = 0.5;
    pat.shirrings = &sh;
    pat.n_shirrings = 1;
    cr_expect_eq(wr_sizing_map_build(&pat, NULL, &map, &d), WR_ERR_GEOMETRY);
    cr_expect(strstr(d.message, "shirrings[0]") != NULL, "%s", d.message);
    cr_expect_null(map.panels);
    sh.panel = 3;
    cr_expect_eq(wr_sizing_map_build(&pat, NULL, &map, &d), WR_ERR_INVALID_ARG);
    cr_expect(strstr(d.message, "shirrings[0]: panel 3 does not exist") != NULL, "%s", d.message);
    pat.n_shirrings = 0;
    memset(&se, 0, sizeof se);
    se.a.to[0] = 0.3;
    se.b.from[0] = 0.3;
    se.b.from[1] = 0.1; /* not on the loop of panel 0 at (0.3, 0.1)? it is: the right edge */
    se.b.to[0] = 0.15;
    se.b.to[1] = 0.15; /* the middle of the panel */
    pat.seams = &se;
    pat.n_seams = 1;
    cr_expect_eq(wr_sizing_map_build(&pat, NULL, &map, &d), WR_ERR_GEOMETRY);
    cr_expect(strstr(d.message, "seams[0].b.to") != NULL, "%s", d.message);
    cr_expect_eq(d.item, 0);
    pn.fabric.resolution = 0.0; /* no stiffness either */
    pat.n_seams = 0;
    cr_expect_eq(wr_sizing_map_build(&pat, NULL, &map, &d), WR_ERR_DOMAIN);
    cr_expect(strstr(d.message, "panels[0]") != NULL, "%s", d.message);
    cr_expect_eq(wr_sizing_map_build(NULL, NULL, &map, &d), WR_ERR_INVALID_ARG);
    cr_expect_eq(wr_sizing_map_build(&pat, NULL, NULL, &d), WR_ERR_INVALID_ARG);
}

/* A seam side walked against the loop order through a loop vertex: the long side's source follows the
 * loop (through the vertex), not the chord between its ends. The bent bottom edge is 2 mm below the
 * chord at x = 0.15; on the vertex the map is ρ_s r_f, ρ_s = 0.24 / (length of the bent side). */
Test(sizing_map, reverse_seam_side_follows_the_loop) {
    wr_pattern pat;
    wr_pattern_panel pn[2];
    wr_pattern_seam se;
    wr_sizing_map map;
    wr_diag d;
    double bent[10] = {0, 0, 0.15, -0.002, 0.3, 0, 0.3, 0.3, 0, 0.3};
    double sq240[8] = {0.4, 0, 0.64, 0, 0.64, 0.24, 0.4, 0.24};
    double l_long = 2.0 * sqrt(0.15 * 0.15 + 0.002 * 0.002);
    one_panel(&pat, &pn[0], 10e-3);
    pn[0].outer.xy = bent;
    pn[0].outer.n = 5;
    pn[1] = pn[0];
    pn[1].outer.xy = sq240;
    pn[1].outer.n = 4;
    pat.panels = pn;
    pat.n_panels = 2;
    memset(&se, 0, sizeof se);
    se.a.panel = 0;
    se.a.from[0] = 0.3; /* vertex 2, backwards over vertex 1 to vertex 0 */
    se.a.reverse = 1;
    se.b.panel = 1;
    se.b.from[0] = 0.64;
    se.b.to[0] = 0.4;
    se.b.reverse = 1;
    pat.seams = &se;
    pat.n_seams = 1;
    cr_assert_eq(wr_sizing_map_build(&pat, NULL, &map, &d), WR_OK, "%s", d.message);
    cr_expect_eq(map.panels[0].n_sources, 1);
    cr_expect(rel(wr_sizing_map_eval(&map, 0, 0.15, -0.002), 0.24 / l_long * 10e-3) < 1e-12, "%.15g",
              wr_sizing_map_eval(&map, 0, 0.15, -0.002));
    cr_expect(rel(wr_sizing_map_eval(&map, 0, 0.075, -0.001), 0.24 / l_long * 10e-3) < 1e-12);
    wr_sizing_map_free(&map);
}
