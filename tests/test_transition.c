/* Tests for transition.h: wrinklon sizes, transition power, paper vs scale-free forms, down-filling,
 * sizing map (min-composition vs brute force, grid == brute), directional sources, metric hook. */
#include <criterion/criterion.h>
#include <math.h>
#include <string.h>

#include "wrinkle/transition.h"

static double rel(double a, double b) { return fabs(a - b) / fabs(b); }

Test(transition, wrinklon_sizes) {
    double L, L2;
    /* λ = 1 cm, T/B = 1e4 m^-2 -> L = 1e-4 * 100 = 1 cm */
    cr_assert_eq(wr_wrinklon_size_tension(1e-2, 1.0, 1e-4, &L, NULL), WR_OK);
    cr_expect(rel(L, 1e-2) < 1e-15);
    /* λ² scaling */
    cr_assert_eq(wr_wrinklon_size_tension(2e-2, 1.0, 1e-4, &L2, NULL), WR_OK);
    cr_expect(rel(L2, 4.0 * L) < 1e-15);
    /* λ^{3/2} (δ/h²)^{1/4}: λ = 4 mm, δ = 0.01, h = 1e-4 m -> 2.53e-4 * (1e6)^{1/4} = 8e-3 m */
    cr_assert_eq(wr_wrinklon_size_compression(4e-3, 0.01, 1e-4, &L, NULL), WR_OK);
    cr_expect(rel(L, pow(4e-3, 1.5) * pow(0.01 / 1e-8, 0.25)) < 1e-14, "%g", L);
    cr_assert_eq(wr_wrinklon_size_compression(4e-3 * 4.0, 0.01, 1e-4, &L2, NULL), WR_OK);
    cr_expect(rel(L2, 8.0 * L) < 1e-14);
    cr_expect_eq(wr_wrinklon_size_tension(0.0, 1.0, 1e-4, &L, NULL), WR_ERR_INVALID_ARG);
    cr_expect_eq(wr_wrinklon_size_tension(1e-2, -1.0, 1e-4, &L, NULL), WR_ERR_INVALID_ARG);
    cr_expect_eq(wr_wrinklon_size_tension(1e-2, 1.0, NAN, &L, NULL), WR_ERR_INVALID_ARG);
    cr_expect_eq(wr_wrinklon_size_tension(1e-2, 1.0, 1e-4, NULL, NULL), WR_ERR_INVALID_ARG);
    cr_expect_eq(wr_wrinklon_size_compression(1e-2, 0.0, 1e-4, &L, NULL), WR_ERR_INVALID_ARG);
    cr_expect_eq(wr_wrinklon_size_compression(1e-2, 0.1, 0.0, &L, NULL), WR_ERR_INVALID_ARG);
    cr_expect_eq(wr_wrinklon_size_compression(INFINITY, 0.1, 1e-4, &L, NULL), WR_ERR_INVALID_ARG);
    cr_expect_eq(wr_wrinklon_size_compression(1e-2, 0.1, 1e-4, NULL, NULL), WR_ERR_INVALID_ARG);
}

/* m = log r / log L_w in millimetres; continuity r(0) = r and r(L_w) = 2r by construction. */
Test(transition, power_and_endpoints) {
    double m;
    wr_transition t;
    cr_assert_eq(wr_transition_power(5e-3, 26.7e-3, &m, NULL), WR_OK);
    cr_expect(rel(m, log(5.0) / log(26.7)) < 1e-15, "m=%g", m);
    cr_assert_eq(wr_transition_make(5e-3, 26.7e-3, NULL, &t, NULL), WR_OK);
    cr_expect_eq(t.scale_free, 0);
    cr_expect_eq(t.m, m);
    cr_expect_eq(wr_transition_eval(&t, 0.0), 5e-3);
    cr_expect(rel(wr_transition_eval(&t, 26.7e-3), 10e-3) < 1e-15);
    /* the paper's literal form in mm: r + L_w^m = 2r */
    cr_expect(rel(wr_transition_paper_eval(5e-3, m, 26.7e-3), 10e-3) < 1e-13);
    cr_expect_eq(wr_transition_paper_eval(5e-3, m, 0.0), 5e-3);
}

/* The scale-free evaluation equals the paper's r + x^m (mm) wherever the paper's m is defined. */
Test(transition, scale_free_equals_paper_form) {
    const double rs[] = {1.5e-3, 3e-3, 9e-3, 20e-3};
    const double Ls[] = {1.2e-3, 4e-3, 25e-3, 300e-3};
    size_t i, j;
    for (i = 0; i < 4; ++i)
        for (j = 0; j < 4; ++j) {
            wr_transition t;
            double x;
            cr_assert_eq(wr_transition_make(rs[i], Ls[j], NULL, &t, NULL), WR_OK);
            cr_assert_eq(t.scale_free, 0);
            for (x = 0.0; x < 0.5; x += 0.0137) {
                double a = wr_transition_eval(&t, x), b = wr_transition_paper_eval(t.r, t.m, x);
                cr_expect(rel(a, b) < 1e-12, "r=%g L=%g x=%g: %.17g vs %.17g", rs[i], Ls[j], x, a, b);
            }
        }
}

/* r or L_w at or below 1 mm: the strict power is a domain error; make() falls back, no NaN, keeps
 * the endpoints and monotone growth. */
Test(transition, below_one_millimetre) {
    const double cases[][2] = {{0.5e-3, 20e-3}, {5e-3, 0.8e-3}, {0.5e-3, 0.7e-3}, {1e-3, 10e-3}, {5e-3, 1e-3}};
    size_t i;
    double m;
    wr_diag d;
    for (i = 0; i < sizeof cases / sizeof cases[0]; ++i) {
        wr_transition t;
        wr_transition_desc desc;
        double r = cases[i][0], L = cases[i][1], x, prev = 0.0;
        cr_expect_eq(wr_transition_power(r, L, &m, &d), WR_ERR_DOMAIN, "r=%g L=%g", r, L);
        cr_expect(strstr(d.message, "1 mm") != NULL, "%s", d.message);
        cr_assert_eq(wr_transition_make(r, L, NULL, &t, NULL), WR_OK);
        cr_expect_eq(t.scale_free, 1);
        cr_expect_eq(t.m, WR_TRANSITION_DEFAULT_FALLBACK_POWER);
        cr_expect_eq(wr_transition_eval(&t, 0.0), r);
        cr_expect(rel(wr_transition_eval(&t, L), 2.0 * r) < 1e-15);
        for (x = 0.0; x < 0.1; x += 1e-4) {
            double v = wr_transition_eval(&t, x);
            cr_assert(isfinite(v) && v >= prev, "x=%g v=%g", x, v);
            prev = v;
        }
        memset(&desc, 0, sizeof desc);
        desc.fallback_power = 2.0 / 3.0;
        cr_assert_eq(wr_transition_make(r, L, &desc, &t, NULL), WR_OK);
        cr_expect_eq(t.m, 2.0 / 3.0);
        desc.strict = 1;
        cr_expect_eq(wr_transition_make(r, L, &desc, &t, NULL), WR_ERR_DOMAIN);
    }
}

Test(transition, from_power_and_errors) {
    wr_transition t;
    double m;
    cr_assert_eq(wr_transition_from_power(4e-3, 0.5, &t, NULL), WR_OK);
    cr_expect(rel(t.L_w, 16e-3) < 1e-14, "L=%g", t.L_w);
    cr_expect(rel(wr_transition_eval(&t, 0.009), wr_transition_paper_eval(4e-3, 0.5, 0.009)) < 1e-14);
    /* r below 1 mm with the paper's form: L_w < 1 mm, still r(L_w) = 2r */
    cr_assert_eq(wr_transition_from_power(0.5e-3, 0.5, &t, NULL), WR_OK);
    cr_expect(rel(wr_transition_eval(&t, t.L_w), 1e-3) < 1e-14);
    cr_expect(rel(wr_transition_paper_eval(0.5e-3, 0.5, t.L_w), 1e-3) < 1e-13);
    /* absurdly slow transition: L_w overflows */
    cr_expect_eq(wr_transition_from_power(10e-3, 1e-3, &t, NULL), WR_ERR_DOMAIN);
    cr_expect_eq(wr_transition_from_power(0.0, 0.5, &t, NULL), WR_ERR_INVALID_ARG);
    cr_expect_eq(wr_transition_from_power(1e-3, -0.5, &t, NULL), WR_ERR_INVALID_ARG);
    cr_expect_eq(wr_transition_from_power(1e-3, 0.5, NULL, NULL), WR_ERR_INVALID_ARG);
    cr_expect_eq(wr_transition_power(0.0, 1e-2, &m, NULL), WR_ERR_INVALID_ARG);
    cr_expect_eq(wr_transition_power(2e-3, NAN, &m, NULL), WR_ERR_INVALID_ARG);
    cr_expect_eq(wr_transition_power(2e-3, 2e-2, NULL, NULL), WR_ERR_INVALID_ARG);
    cr_expect_eq(wr_transition_make(2e-3, 2e-2, NULL, NULL, NULL), WR_ERR_INVALID_ARG);
    cr_expect_eq(wr_transition_make(-2e-3, 2e-2, NULL, &t, NULL), WR_ERR_INVALID_ARG);
    {
        wr_transition_desc desc;
        memset(&desc, 0, sizeof desc);
        desc.fallback_power = -1.0;
        cr_expect_eq(wr_transition_make(2e-3, 2e-2, &desc, &t, NULL), WR_ERR_INVALID_ARG);
    }
}

Test(transition, slope_matches_finite_difference) {
    wr_transition t;
    double x;
    cr_assert_eq(wr_transition_make(3e-3, 20e-3, NULL, &t, NULL), WR_OK);
    for (x = 1e-3; x < 0.1; x *= 1.7) {
        double h = 1e-7 * x;
        double fd = (wr_transition_eval(&t, x + h) - wr_transition_eval(&t, x - h)) / (2.0 * h);
        cr_expect(rel(wr_transition_slope(&t, x), fd) < 1e-6, "x=%g", x);
    }
    cr_expect(isinf(wr_transition_slope(&t, 0.0))); /* m = ln 3 / ln 20 < 1 */
}

/* Sec. 4.2.5: m' = 2^p m, L' = L^{2^-p} (mm); r(L') = 2r is kept; p = 0 is the identity. */
Test(transition, downfill) {
    wr_transition t, u;
    cr_assert_eq(wr_transition_make(3e-3, 30e-3, NULL, &t, NULL), WR_OK);
    cr_assert_eq(wr_transition_downfill(&t, 0.0, &u, NULL), WR_OK);
    cr_expect(rel(u.m, t.m) < 1e-15 && rel(u.L_w, t.L_w) < 1e-14);
    cr_assert_eq(wr_transition_downfill(&t, 1.0, &u, NULL), WR_OK);
    cr_expect(rel(u.m, 2.0 * t.m) < 1e-15);
    cr_expect(rel(u.L_w, sqrt(30.0) * 1e-3) < 1e-14, "L'=%g", u.L_w);
    cr_expect(u.L_w < t.L_w); /* pressure shortens the transition */
    cr_expect(rel(wr_transition_eval(&u, u.L_w), 6e-3) < 1e-14);
    /* and it is still the paper's r + x^{m'} */
    cr_expect(rel(wr_transition_eval(&u, 0.011), wr_transition_paper_eval(3e-3, u.m, 0.011)) < 1e-12);
    cr_expect_eq(wr_transition_downfill(&t, -1.0, &u, NULL), WR_ERR_INVALID_ARG);
    cr_expect_eq(wr_transition_downfill(&t, NAN, &u, NULL), WR_ERR_INVALID_ARG);
    cr_expect_eq(wr_transition_downfill(&t, 1e6, &u, NULL), WR_ERR_DOMAIN);
    cr_expect_eq(wr_transition_downfill(NULL, 1.0, &u, NULL), WR_ERR_INVALID_ARG);
    t.m = 0.0;
    cr_expect_eq(wr_transition_downfill(&t, 1.0, &u, NULL), WR_ERR_INVALID_ARG);
}

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

Test(transition, technique_sources) {
    wr_resolution_model m = wr_resolution_model_paper();
    double r, r0, rho;
    wr_diag d;
    /* E_sh = 0, rho = 1: the fabric's own resolution */
    cr_assert_eq(wr_resolution_from_BE(&m, 2e-6, 3e5, NULL, &r0, NULL), WR_OK);
    cr_assert_eq(wr_source_shirring(&m, 2e-6, 3e5, 0.0, 1.0, 1.0, NULL, &r, NULL), WR_OK);
    cr_expect_eq(r, r0);
    /* shirring stiffness lowers y and the resolution; the shrinkage ratio scales it (n = 1) */
    cr_assert_eq(wr_source_shirring(&m, 2e-6, 3e5, 3e5, 0.5, 1.0, NULL, &r, NULL), WR_OK);
    cr_assert_eq(wr_resolution_from_y(&m, 2e-6 / 6e5, NULL, &r0, NULL), WR_OK);
    cr_expect(rel(r, 0.5 * r0) < 1e-15);
    cr_assert_eq(wr_source_shirring(&m, 2e-6, 3e5, 3e5, 0.5, 2.0, NULL, &r, NULL), WR_OK);
    cr_expect(rel(r, 0.25 * r0) < 1e-15);
    cr_expect_eq(wr_source_shirring(&m, 2e-6, 3e5, -1.0, 0.5, 1.0, NULL, &r, NULL), WR_ERR_INVALID_ARG);
    cr_expect_eq(wr_source_shirring(&m, 2e-6, 3e5, 0.0, 1.5, 1.0, NULL, &r, &d), WR_ERR_INVALID_ARG);
    cr_expect(strstr(d.message, "rho") != NULL, "%s", d.message);
    cr_expect_eq(wr_source_shirring(&m, 2e-6, 3e5, 0.0, 0.0, 1.0, NULL, &r, NULL), WR_ERR_INVALID_ARG);
    cr_expect_eq(wr_source_shirring(&m, 2e-6, 3e5, 0.0, 0.5, -1.0, NULL, &r, NULL), WR_ERR_INVALID_ARG);
    cr_expect_eq(wr_source_shirring(&m, 0.0, 3e5, 0.0, 0.5, 1.0, NULL, &r, NULL), WR_ERR_INVALID_ARG);
    cr_expect_eq(wr_source_shirring(&m, 2e-6, NAN, 0.0, 0.5, 1.0, NULL, &r, NULL), WR_ERR_INVALID_ARG);
    cr_expect_eq(wr_source_shirring(&m, 2e-6, 3e5, 0.0, 0.5, 1.0, NULL, NULL, NULL), WR_ERR_INVALID_ARG);
    /* folding: a 90° fold is a quarter of the neighbourhood resolution */
    cr_assert_eq(wr_source_folding(0.5 * 3.14159265358979323846, 8e-3, &r, NULL), WR_OK);
    cr_expect(rel(r, 2e-3) < 1e-15);
    cr_expect_eq(wr_source_folding(0.0, 8e-3, &r, NULL), WR_ERR_INVALID_ARG);
    cr_expect_eq(wr_source_folding(7.0, 8e-3, &r, NULL), WR_ERR_INVALID_ARG);
    cr_expect_eq(wr_source_folding(1.0, -8e-3, &r, NULL), WR_ERR_INVALID_ARG);
    cr_expect_eq(wr_source_folding(1.0, 8e-3, NULL, NULL), WR_ERR_INVALID_ARG);
    /* stitching ratio */
    cr_assert_eq(wr_source_stitch_ratio(0.3, 0.4, &rho, NULL), WR_OK);
    cr_expect(rel(rho, 0.75) < 1e-15);
    cr_expect_eq(wr_source_stitch_ratio(0.5, 0.4, &rho, NULL), WR_ERR_INVALID_ARG);
    cr_expect_eq(wr_source_stitch_ratio(0.0, 0.4, &rho, NULL), WR_ERR_INVALID_ARG);
    cr_expect_eq(wr_source_stitch_ratio(0.3, 0.4, NULL, NULL), WR_ERR_INVALID_ARG);
}

/* Regression: wr_sizing_build looped forever (doubling h to infinity) when the active segments
 * could never fit the max_cells cap on stored entries — each segment needs at least one entry.
 * Now a budget error; the map stays usable through the brute-force path. */
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
