/* Tests for resolution.h: Style3D Eq. 4 calibration, root solve, inverse, domain, helpers. */
#include <criterion/criterion.h>
#include <math.h>
#include <string.h>

#include "wrinkle/resolution.h"

static double rel(double a, double b) { return fabs(a - b) / fabs(b); }

/* Paper, Sec. 4.1.1: c1 = 32.08 m^-3, c2 = -1.876e-4 m^-1 (printed to 4 significant digits). */
Test(resolution, paper_constants) {
    wr_resolution_model m = wr_resolution_model_paper();
    cr_expect(rel(m.c1, 32.08) < 5e-4, "c1 = %.6g", m.c1);
    cr_expect(rel(m.c2, -1.876e-4) < 5e-4, "c2 = %.6g", m.c2);
    /* the closed form reproduces both design points exactly (to rounding) */
    cr_expect(rel(m.c1 * pow(50e-3, 6) + m.c2 * pow(50e-3, 4), 1e-3 / 2e3) < 1e-12);
    cr_expect(rel(m.c1 * pow(2.5e-3, 6) + m.c2 * pow(2.5e-3, 4), 1e-9 / 2e6) < 1e-12);
}

/* The paper's matrix form, written out literally, agrees with our rearranged closed form. */
Test(resolution, calibration_matches_paper_matrix_form) {
    double rmin = 3e-3, rmax = 40e-3, ymin = 2e-16, ymax = 7e-7;
    double det = pow(rmax, 4) * pow(rmin, 4) * (rmax + rmin) * (rmax - rmin);
    double c1 = (pow(rmin, 4) * ymax - pow(rmax, 4) * ymin) / det;
    double c2 = (-pow(rmin, 6) * ymax + pow(rmax, 6) * ymin) / det;
    wr_resolution_model m;
    cr_assert_eq(wr_resolution_calibrate_y(ymin, ymax, rmin, rmax, &m, NULL), WR_OK);
    cr_expect(rel(m.c1, c1) < 1e-12);
    cr_expect(rel(m.c2, c2) < 1e-12);
}

typedef struct row {
    const char *name;
    double B, E, r_mm;
} row;
/* Table 1 (all rows, resolution in mm) and the cantilever of Fig. 18 (6.45 mm). */
static const row table1[] = {
    {"Wine Style", 2.0e-6, 3.0e5, 7.83},  {"Pinkish Puff", 2.0e-6, 8.0e5, 6.69}, {"Mint Melody", 7.8e-7, 6.6e4, 8.58},
    {"Golden Grace", 2.0e-6, 1.1e5, 9.21}, {"Blue Ballet", 2.5e-6, 1.1e5, 9.55}, {"Dark Blue", 1.6e-4, 1.3e5, 18.5},
    {"Khaki", 2.0e-5, 5.0e5, 10.5},        {"Green", 2.6e-6, 2.0e6, 6.00},       {"Light Blue", 3.2e-7, 8.2e6, 3.61},
    {"Rose", 4.0e-8, 1.6e7, 2.70},         {"cantilever", 2.0e-6, 1.0e6, 6.45}};

Test(resolution, table1_rows_within_1_percent) {
    wr_resolution_model m = wr_resolution_model_paper();
    size_t i;
    for (i = 0; i < sizeof table1 / sizeof table1[0]; ++i) {
        double r;
        wr_diag d;
        cr_assert_eq(wr_resolution_from_BE(&m, table1[i].B, table1[i].E, NULL, &r, &d), WR_OK, "%s", d.message);
        cr_expect(rel(1e3 * r, table1[i].r_mm) < 0.01, "%s: ours %.4f mm, paper %.2f mm", table1[i].name, 1e3 * r,
                  table1[i].r_mm);
    }
}

Test(resolution, monotone_in_B_and_E) {
    wr_resolution_model m = wr_resolution_model_paper();
    double prev = 0.0, B, E;
    for (B = 1e-9; B <= 1e-3; B *= 1.5) {
        double r;
        cr_assert_eq(wr_resolution_from_BE(&m, B, 1e5, NULL, &r, NULL), WR_OK);
        cr_expect(r > prev, "r must grow with B (B=%g)", B);
        prev = r;
    }
    prev = INFINITY;
    for (E = 2e3; E <= 2e7; E *= 1.5) {
        double r;
        cr_assert_eq(wr_resolution_from_BE(&m, 1e-6, E, NULL, &r, NULL), WR_OK);
        cr_expect(r < prev, "r must shrink with E (E=%g)", E);
        prev = r;
    }
}

Test(resolution, round_trips) {
    wr_resolution_model m = wr_resolution_model_paper();
    double y, r, r2, y2;
    /* y -> r -> y over 20 decades */
    for (y = 1e-22; y < 1e-2; y *= 7.3) {
        cr_assert_eq(wr_resolution_from_y(&m, y, NULL, &r, NULL), WR_OK);
        cr_assert_eq(wr_resolution_y(&m, r, &y2, NULL), WR_OK);
        /* near r0 the map y -> r is very flat, so compare r after the second pass instead */
        cr_assert_eq(wr_resolution_from_y(&m, y2, NULL, &r2, NULL), WR_OK);
        cr_expect(rel(r2, r) < 1e-13, "y=%g r=%.17g r2=%.17g", y, r, r2);
        if (y > 1e-15) cr_expect(rel(y2, y) < 1e-10, "y=%g y2=%g", y, y2);
    }
    /* r -> y -> r */
    for (r = 2.43e-3; r < 1.0; r *= 1.21) {
        cr_assert_eq(wr_resolution_y(&m, r, &y, NULL), WR_OK);
        cr_assert_eq(wr_resolution_from_y(&m, y, NULL, &r2, NULL), WR_OK);
        cr_expect(rel(r2, r) < 1e-12, "r=%g r2=%g", r, r2);
    }
}

/* The paper's model is negative below r0 = sqrt(-c2/c1) ≈ 2.42 mm: tiny y approaches r0 from above,
 * and y(r) at or below r0 is out of the model's domain. */
Test(resolution, domain_edge_near_2_42_mm) {
    wr_resolution_model m = wr_resolution_model_paper();
    wr_resolution_domain_info dom;
    double r, y;
    wr_diag d;
    cr_assert_eq(wr_resolution_domain(&m, &dom, NULL), WR_OK);
    cr_expect(fabs(dom.r_zero - 2.4189e-3) < 1e-7, "r0 = %.6g", dom.r_zero);
    cr_expect(fabs(dom.r_extremum - sqrt(2.0 / 3.0) * dom.r_zero) < 1e-15);
    cr_expect_eq(dom.r_lo, dom.r_zero);
    cr_expect(isinf(dom.r_hi) && isinf(dom.y_hi));
    cr_assert_eq(wr_resolution_from_y(&m, 1e-30, NULL, &r, NULL), WR_OK);
    cr_expect(r > dom.r_zero && rel(r, dom.r_zero) < 1e-9, "r=%.17g r0=%.17g", r, dom.r_zero);
    cr_expect_eq(wr_resolution_y(&m, 2.0e-3, &y, &d), WR_ERR_DOMAIN);
    cr_expect(strstr(d.message, "branch") != NULL, "%s", d.message);
    /* the unbounded side is said in words, never as "inf" (issue 19: the text reaches the drivers) */
    cr_expect(strstr(d.message, "inf") == NULL && strstr(d.message, "r > 0.00241") != NULL, "%s", d.message);
    cr_expect_eq(wr_resolution_y(&m, dom.r_zero, &y, NULL), WR_ERR_DOMAIN);
    cr_expect_eq(wr_resolution_y(&m, dom.r_zero * (1 + 1e-9), &y, NULL), WR_OK);
    cr_expect(y > 0.0);
}

Test(resolution, design_band_error_and_clamp) {
    wr_resolution_model m = wr_resolution_model_paper();
    wr_resolution_desc desc;
    double r;
    wr_diag d;
    memset(&desc, 0, sizeof desc);
    desc.r_lo = 2.5e-3;
    desc.r_hi = 50e-3;
    /* y below the design minimum gives r in (2.42, 2.5) mm */
    cr_expect_eq(wr_resolution_from_y(&m, 1e-17, &desc, &r, &d), WR_ERR_DOMAIN);
    cr_expect(strstr(d.message, "below") != NULL, "%s", d.message);
    cr_expect_eq(wr_resolution_from_y(&m, 1e-3, &desc, &r, &d), WR_ERR_DOMAIN);
    cr_expect(strstr(d.message, "above") != NULL, "%s", d.message);
    desc.clamp = 1;
    cr_expect_eq(wr_resolution_from_y(&m, 1e-17, &desc, &r, NULL), WR_OK);
    cr_expect_eq(r, 2.5e-3);
    cr_expect_eq(wr_resolution_from_y(&m, 1e-3, &desc, &r, NULL), WR_OK);
    cr_expect_eq(r, 50e-3);
    desc.r_lo = 3e-3;
    desc.r_hi = 2e-3;
    cr_expect_eq(wr_resolution_from_y(&m, 1e-10, &desc, &r, NULL), WR_ERR_INVALID_ARG);
}

/* A peaked model (c1 < 0 < c2): y above the peak is out of the domain, or clamped to r_peak. */
Test(resolution, peaked_model_domain) {
    wr_resolution_model m;
    wr_resolution_domain_info dom;
    wr_resolution_desc desc;
    double r, y;
    m.c1 = -1.0;
    m.c2 = 3e-4;
    cr_assert_eq(wr_resolution_domain(&m, &dom, NULL), WR_OK);
    cr_expect(rel(dom.r_hi, sqrt(2e-4)) < 1e-14);
    cr_expect(rel(dom.y_hi, 4e-8 * (-2e-4 + 3e-4)) < 1e-12);
    cr_expect_eq(wr_resolution_from_y(&m, 2.0 * dom.y_hi, NULL, &r, NULL), WR_ERR_DOMAIN);
    memset(&desc, 0, sizeof desc);
    desc.clamp = 1;
    cr_expect_eq(wr_resolution_from_y(&m, 2.0 * dom.y_hi, &desc, &r, NULL), WR_OK);
    cr_expect(rel(r, dom.r_hi) < 1e-14);
    cr_assert_eq(wr_resolution_from_y(&m, 0.5 * dom.y_hi, NULL, &r, NULL), WR_OK);
    cr_assert_eq(wr_resolution_y(&m, r, &y, NULL), WR_OK);
    cr_expect(rel(y, 0.5 * dom.y_hi) < 1e-12);
    cr_expect_eq(wr_resolution_y(&m, 1.5 * dom.r_hi, &y, NULL), WR_ERR_DOMAIN);
    /* c1 = 0: pure quartic */
    m.c1 = 0.0;
    m.c2 = 2.0;
    cr_assert_eq(wr_resolution_from_y(&m, 32.0, NULL, &r, NULL), WR_OK);
    cr_expect(rel(r, 2.0) < 1e-15);
    /* c1 > 0, c2 > 0 */
    m.c1 = 1.0;
    m.c2 = 1.0;
    cr_assert_eq(wr_resolution_from_y(&m, 2.0, NULL, &r, NULL), WR_OK);
    cr_expect(rel(r, 1.0) < 1e-14);
}

Test(resolution, error_paths) {
    wr_resolution_model m = wr_resolution_model_paper(), bad;
    wr_resolution_domain_info dom;
    double r, y, a, b;
    wr_diag d;
    cr_expect_eq(wr_resolution_from_BE(&m, 0.0, 1e5, NULL, &r, &d), WR_ERR_INVALID_ARG);
    cr_expect(strstr(d.message, "B=") != NULL, "%s", d.message);
    cr_expect_eq(wr_resolution_from_BE(&m, -1e-6, 1e5, NULL, &r, NULL), WR_ERR_INVALID_ARG);
    cr_expect_eq(wr_resolution_from_BE(&m, NAN, 1e5, NULL, &r, NULL), WR_ERR_INVALID_ARG);
    cr_expect_eq(wr_resolution_from_BE(&m, 1e-6, 0.0, NULL, &r, &d), WR_ERR_INVALID_ARG);
    cr_expect(strstr(d.message, "E=") != NULL, "%s", d.message);
    cr_expect_eq(wr_resolution_from_BE(&m, 1e-6, INFINITY, NULL, &r, NULL), WR_ERR_INVALID_ARG);
    cr_expect_eq(wr_resolution_from_y(&m, 0.0, NULL, &r, NULL), WR_ERR_INVALID_ARG);
    cr_expect_eq(wr_resolution_from_y(&m, NAN, NULL, &r, NULL), WR_ERR_INVALID_ARG);
    cr_expect_eq(wr_resolution_from_y(&m, 1e-10, NULL, NULL, NULL), WR_ERR_INVALID_ARG);
    cr_expect_eq(wr_resolution_y(&m, -1.0, &y, NULL), WR_ERR_INVALID_ARG);
    cr_expect_eq(wr_resolution_y(&m, 1e-2, NULL, NULL), WR_ERR_INVALID_ARG);
    bad.c1 = -1.0;
    bad.c2 = -1.0;
    cr_expect_eq(wr_resolution_domain(&bad, &dom, &d), WR_ERR_DOMAIN);
    cr_expect(strstr(d.message, "no increasing") != NULL, "%s", d.message);
    cr_expect_eq(wr_resolution_from_y(&bad, 1e-10, NULL, &r, NULL), WR_ERR_DOMAIN);
    bad.c1 = 0.0;
    bad.c2 = 0.0;
    cr_expect_eq(wr_resolution_from_y(&bad, 1e-10, NULL, &r, NULL), WR_ERR_DOMAIN);
    bad.c1 = NAN;
    cr_expect_eq(wr_resolution_domain(&bad, &dom, NULL), WR_ERR_INVALID_ARG);
    cr_expect_eq(wr_resolution_domain(NULL, &dom, NULL), WR_ERR_INVALID_ARG);
    /* calibration errors */
    cr_expect_eq(wr_resolution_calibrate(2e6, 2e3, 1e-9, 1e-3, 2.5e-3, 50e-3, &bad, &d), WR_ERR_INVALID_ARG);
    cr_expect(strstr(d.message, "inverted E") != NULL, "%s", d.message);
    cr_expect_eq(wr_resolution_calibrate(2e3, 2e6, 1e-3, 1e-9, 2.5e-3, 50e-3, &bad, &d), WR_ERR_INVALID_ARG);
    cr_expect(strstr(d.message, "inverted B") != NULL, "%s", d.message);
    cr_expect_eq(wr_resolution_calibrate(2e3, 2e6, 1e-9, 1e-3, 50e-3, 2.5e-3, &bad, &d), WR_ERR_INVALID_ARG);
    cr_expect(strstr(d.message, "inverted r") != NULL, "%s", d.message);
    cr_expect_eq(wr_resolution_calibrate(0.0, 2e6, 1e-9, 1e-3, 2.5e-3, 50e-3, &bad, NULL), WR_ERR_INVALID_ARG);
    cr_expect_eq(wr_resolution_calibrate(2e3, 2e6, NAN, 1e-3, 2.5e-3, 50e-3, &bad, NULL), WR_ERR_INVALID_ARG);
    cr_expect_eq(wr_resolution_calibrate(2e3, 2e6, 1e-9, 1e-3, -1.0, 50e-3, &bad, NULL), WR_ERR_INVALID_ARG);
    cr_expect_eq(wr_resolution_calibrate_y(1e-10, 1e-10, 1e-3, 2e-3, &bad, NULL), WR_ERR_INVALID_ARG);
    cr_expect_eq(wr_resolution_calibrate_y(1e-10, 1e-9, 1e-3, 2e-3, NULL, NULL), WR_ERR_INVALID_ARG);
    /* y ratio 2 over r ratio 10: no increasing model through both points */
    cr_expect_eq(wr_resolution_calibrate_y(1e-10, 2e-10, 1e-3, 1e-2, &bad, &d), WR_ERR_DOMAIN);
    cr_expect(strstr(d.message, "not increasing") != NULL, "%s", d.message);
    /* orthotropic reports which pair failed */
    cr_expect_eq(wr_resolution_orthotropic(&m, 1e-6, 1e5, -1.0, 1e5, NULL, &a, &b, &d), WR_ERR_INVALID_ARG);
    cr_expect_eq(d.item, 1);
    cr_expect_eq(wr_resolution_orthotropic(&m, 1e-6, 0.0, 1e-6, 1e5, NULL, &a, &b, &d), WR_ERR_INVALID_ARG);
    cr_expect_eq(d.item, 0);
    cr_expect_eq(wr_resolution_orthotropic(&m, 1e-6, 1e5, 1e-6, 1e5, NULL, NULL, &b, NULL), WR_ERR_INVALID_ARG);
}

/* A calibrated peaked model must still be increasing on [r_min, r_max] and reproduce both ends. */
Test(resolution, calibrate_custom_ranges) {
    wr_resolution_model m;
    double r;
    cr_assert_eq(wr_resolution_calibrate(1e4, 1e6, 1e-8, 1e-4, 3e-3, 30e-3, &m, NULL), WR_OK);
    cr_assert_eq(wr_resolution_from_y(&m, 1e-4 / 1e4, NULL, &r, NULL), WR_OK);
    cr_expect(rel(r, 30e-3) < 1e-12, "%.17g", r);
    cr_assert_eq(wr_resolution_from_y(&m, 1e-8 / 1e6, NULL, &r, NULL), WR_OK);
    cr_expect(rel(r, 3e-3) < 1e-12, "%.17g", r);
    /* c1 < 0 case through both points */
    cr_assert_eq(wr_resolution_calibrate_y(1e-10, 4e-8, 1e-3, 5e-3, &m, NULL), WR_OK);
    cr_expect(m.c1 < 0.0 && m.c2 > 0.0, "c1=%g c2=%g", m.c1, m.c2);
    cr_assert_eq(wr_resolution_from_y(&m, 4e-8, NULL, &r, NULL), WR_OK);
    cr_expect(rel(r, 5e-3) < 1e-11, "%.17g", r);
    cr_assert_eq(wr_resolution_from_y(&m, 1e-10, NULL, &r, NULL), WR_OK);
    cr_expect(rel(r, 1e-3) < 1e-11, "%.17g", r);
}

Test(resolution, orthotropic_and_metric) {
    wr_resolution_model m = wr_resolution_model_paper();
    double rw, rf, rw1, rf1;
    wr_mat2 M;
    wr_vec2 warp, weft;
    const double ang = 0.3;
    /* stiff warp, soft weft -> fine weft, coarse warp (Fig. 6) */
    cr_assert_eq(wr_resolution_orthotropic(&m, 2e-5, 5e5, 2e-6, 1e6, NULL, &rw, &rf, NULL), WR_OK);
    cr_assert_eq(wr_resolution_from_BE(&m, 2e-5, 5e5, NULL, &rw1, NULL), WR_OK);
    cr_assert_eq(wr_resolution_from_BE(&m, 2e-6, 1e6, NULL, &rf1, NULL), WR_OK);
    cr_expect_eq(rw, rw1);
    cr_expect_eq(rf, rf1);
    cr_expect(rf < rw);
    M = wr_resolution_metric(rw, rf, ang);
    /* a warp-direction vector of length r_warp has unit metric length; same for weft */
    warp = wr_v2(rw * cos(ang), rw * sin(ang));
    weft = wr_v2(-rf * sin(ang), rf * cos(ang));
    cr_expect(fabs(wr_v2_dot(warp, wr_m2_mulv(M, warp)) - 1.0) < 1e-12);
    cr_expect(fabs(wr_v2_dot(weft, wr_m2_mulv(M, weft)) - 1.0) < 1e-12);
    cr_expect(fabs(wr_v2_dot(warp, wr_m2_mulv(M, weft))) < 1e-12);
    cr_expect_eq(M.m[0][1], M.m[1][0]);
}

Test(resolution, kirchhoff_love) {
    double y, B, r, rB;
    wr_resolution_model m = wr_resolution_model_paper();
    cr_assert_eq(wr_kl_y(1e-3, 0.3, &y, NULL), WR_OK);
    cr_expect(rel(y, 1e-9 / (12.0 * 0.91)) < 1e-15);
    cr_assert_eq(wr_kl_bending(1e5, 1e-3, 0.3, &B, NULL), WR_OK);
    cr_expect(rel(B, 1e5 * y) < 1e-15);
    /* through B or through y: same resolution */
    cr_assert_eq(wr_resolution_from_y(&m, y, NULL, &r, NULL), WR_OK);
    cr_assert_eq(wr_resolution_from_BE(&m, B, 1e5, NULL, &rB, NULL), WR_OK);
    cr_expect(rel(r, rB) < 1e-13);
    /* thicker -> coarser */
    cr_assert_eq(wr_kl_y(2e-3, 0.3, &y, NULL), WR_OK);
    cr_assert_eq(wr_resolution_from_y(&m, y, NULL, &rB, NULL), WR_OK);
    cr_expect(rB > r);
    cr_expect_eq(wr_kl_y(0.0, 0.3, &y, NULL), WR_ERR_INVALID_ARG);
    cr_expect_eq(wr_kl_y(1e-3, 0.6, &y, NULL), WR_ERR_INVALID_ARG);
    cr_expect_eq(wr_kl_y(1e-3, -1.0, &y, NULL), WR_ERR_INVALID_ARG);
    cr_expect_eq(wr_kl_y(1e-3, NAN, &y, NULL), WR_ERR_INVALID_ARG);
    cr_expect_eq(wr_kl_y(1e-3, 0.3, NULL, NULL), WR_ERR_INVALID_ARG);
    cr_expect_eq(wr_kl_bending(-1.0, 1e-3, 0.3, &B, NULL), WR_ERR_INVALID_ARG);
    cr_expect_eq(wr_kl_bending(1e5, 1e-3, 0.7, &B, NULL), WR_ERR_INVALID_ARG);
    cr_expect_eq(wr_kl_bending(1e5, 1e-3, 0.3, NULL, NULL), WR_ERR_INVALID_ARG);
}

Test(resolution, cerda_mahadevan) {
    double lam, A, r;
    const double pi = 3.14159265358979323846;
    /* B L^2 / T = 1e-8 m^4 -> (.)^{1/4} = 1e-2 m */
    cr_assert_eq(wr_cm_wavelength(1e-6, 1.0, 0.1, &lam, NULL), WR_OK);
    cr_expect(rel(lam, 2.0 * sqrt(pi) * 1e-2) < 1e-14);
    cr_assert_eq(wr_cm_amplitude(lam, 0.02, &A, NULL), WR_OK);
    cr_expect(rel(A, sqrt(2.0) / pi * lam * sqrt(0.02)) < 1e-14);
    r = wr_cm_optimal_resolution(lam, A);
    cr_expect(rel(r * r, lam * lam / 16.0 + A * A) < 1e-14);
    cr_expect_eq(wr_cm_optimal_resolution(0.04, 0.0), 0.01);
    /* scaling: 16x stiffer -> 2x wavelength */
    {
        double l2;
        cr_assert_eq(wr_cm_wavelength(16e-6, 1.0, 0.1, &l2, NULL), WR_OK);
        cr_expect(rel(l2, 2.0 * lam) < 1e-14);
    }
    cr_expect_eq(wr_cm_wavelength(0.0, 1.0, 0.1, &lam, NULL), WR_ERR_INVALID_ARG);
    cr_expect_eq(wr_cm_wavelength(1e-6, -1.0, 0.1, &lam, NULL), WR_ERR_INVALID_ARG);
    cr_expect_eq(wr_cm_wavelength(1e-6, 1.0, NAN, &lam, NULL), WR_ERR_INVALID_ARG);
    cr_expect_eq(wr_cm_wavelength(1e-6, 1.0, 0.1, NULL, NULL), WR_ERR_INVALID_ARG);
    cr_expect_eq(wr_cm_amplitude(0.0, 0.1, &A, NULL), WR_ERR_INVALID_ARG);
    cr_expect_eq(wr_cm_amplitude(0.01, -0.1, &A, NULL), WR_ERR_INVALID_ARG);
    cr_expect_eq(wr_cm_amplitude(0.01, 0.1, NULL, NULL), WR_ERR_INVALID_ARG);
    cr_assert_eq(wr_cm_amplitude(0.01, 0.0, &A, NULL), WR_OK);
    cr_expect_eq(A, 0.0);
}

/* Regression: tiny y on a peaked model used to need > 200 Newton steps (Newton only halves toward a
 * root at u ~ 1e-150 from the [0, u_peak] bracket); extreme y on the paper's model stays finite. */
Test(resolution, extreme_y) {
    wr_resolution_model m = wr_resolution_model_paper();
    double r, y;
    cr_assert_eq(wr_resolution_from_y(&m, 1e-300, NULL, &r, NULL), WR_OK);
    cr_expect(r > 2.41e-3 && r < 2.43e-3);
    cr_assert_eq(wr_resolution_from_y(&m, 1e300, NULL, &r, NULL), WR_OK);
    cr_expect(rel(r, pow(1e300 / m.c1, 1.0 / 6.0)) < 1e-12, "%g", r);
    m.c1 = -1.0;
    m.c2 = 3e-4;
    for (y = 1e-300; y < 1e-9; y *= 1e7) {
        double y2;
        cr_assert_eq(wr_resolution_from_y(&m, y, NULL, &r, NULL), WR_OK, "y=%g", y);
        cr_assert_eq(wr_resolution_y(&m, r, &y2, NULL), WR_OK);
        cr_expect(rel(y2, y) < 1e-12, "y=%g y2=%g", y, y2);
    }
}
