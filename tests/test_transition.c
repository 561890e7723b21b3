/* Tests for transition.h: wrinklon sizes, transition power, paper vs scale-free forms, down-filling,
 * technique source resolutions. The sizing field and map are tested in test_sizing.c. */
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
