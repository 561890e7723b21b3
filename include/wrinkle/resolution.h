/* wrinkle/resolution.h — optimal cloth mesh resolution from material stiffness (Style3D scaling law).
 * wrinkle v0.1.0 — MIT licence (see LICENSE). Needs only libc and libm (and core.h).
 *
 * Implements Sec. 3.1 and 4.1 of "Physics-inspired Estimation of Optimal Cloth Mesh Resolution"
 * (Style3D, SIGGRAPH 2025):
 *   Eq. 1    λ ~ (B/K)^{1/4}, A ~ λ √δ                  (Cerda–Mahadevan scaling law)
 *   Sec. 3.1 λ = 2√π (B L²/T)^{1/4}, A = (√2/π) λ √δ     (stretched sheet, exact prefactors)
 *   4.1.1    r_opt = sqrt(λ²/16 + A²)                    (Fig. 4, Pythagoras)
 *   Eq. 4    c1 r⁶ + c2 r⁴ = y,  y = B/E                 (the resolution model)
 *   4.1.1    2×2 calibration of (c1, c2) from designer ranges of E, B and r
 *   4.1.2    orthotropic fabrics: separate warp and weft resolutions
 *
 * HOW TO USE: see core.h (one translation unit defines WRINKLE_IMPLEMENTATION).
 *
 * API
 *   wr_resolution_calibrate(E_min,E_max,B_min,B_max,r_min,r_max,&model,diag)  Eq. 4 2×2 system
 *   wr_resolution_calibrate_y(y_min,y_max,r_min,r_max,&model,diag)           same, from y directly
 *   wr_resolution_model_paper()              c1, c2 calibrated from the paper's design ranges
 *   wr_resolution_domain(&model,&dom,diag)   the increasing positive branch of Eq. 4 (r and y bounds)
 *   wr_resolution_from_y(&model,y,desc,&r,diag)     solve Eq. 4 for r on that branch
 *   wr_resolution_from_BE(&model,B,E,desc,&r,diag)  same with y = B/E
 *   wr_resolution_y(&model,r,&y,diag)        the inverse: y(r) = c1 r⁶ + c2 r⁴ (r on the branch)
 *   wr_resolution_orthotropic(&model,B_warp,E_warp,B_weft,E_weft,desc,&r_warp,&r_weft,diag)
 *   wr_resolution_metric(r_warp,r_weft,grain_angle)  M = R diag(1/r_warp², 1/r_weft²) Rᵀ
 *   wr_kl_y(h,nu,&y,diag) / wr_kl_bending(E,h,nu,&B,diag)   Kirchhoff–Love y = h³/(12(1-ν²)), B = E y
 *   wr_cm_wavelength(B,T,L,&lambda,diag)     λ = 2√π (B L²/T)^{1/4}
 *   wr_cm_amplitude(lambda,delta,&A,diag)    A = (√2/π) λ √δ
 *   wr_cm_optimal_resolution(lambda,A)       r_opt = sqrt(λ²/16 + A²)
 *
 * EXAMPLE
 *     wr_resolution_model mdl = wr_resolution_model_paper();   // c1 ≈ 32.08 m⁻³, c2 ≈ -1.876e-4 m⁻¹
 *     double r;  wr_diag d;
 *     if (wr_resolution_from_BE(&mdl, 2.0e-6, 1.0e6, NULL, &r, &d) != WR_OK) { puts(d.message); return 1; }
 *     printf("%.2f mm\n", 1e3 * r);                            // 6.46 mm (paper Fig. 18: 6.45 mm)
 *
 * ON UNITS
 *   SI throughout: r in metres, E in N/m², B in N·m, y = B/E in m³, c1 in m⁻³, c2 in m⁻¹,
 *   tension T (Cerda–Mahadevan) in N/m, lengths in m, δ dimensionless.
 *
 * ON THE DOMAIN OF EQ. 4
 *   f(r) = c1 r⁶ + c2 r⁴ is used only on its "increasing positive branch": the r > 0 where f(r) > 0 and
 *   f'(r) = 2r³(3 c1 r² + 2 c2) > 0, on which f is a bijection onto its y range. Cases:
 *     c1 > 0, c2 < 0 (the paper's): f < 0 for r < r0 = sqrt(-c2/c1) (≈ 2.42 mm for the paper's
 *        constants; f has its minimum at sqrt(-2c2/(3c1)) ≈ 1.98 mm). The branch is r > r0, y ∈ (0, ∞):
 *        every y > 0 has exactly one root, and r(y) → r0 as y → 0+. Hence resolutions below r0 are
 *        unreachable; wr_resolution_y(r ≤ r0) is WR_ERR_DOMAIN.
 *     c1 > 0, c2 ≥ 0, or c1 = 0 < c2: branch r > 0, y ∈ (0, ∞).
 *     c1 < 0 < c2: f rises to a peak at r_peak = sqrt(-2c2/(3c1)) and falls; branch r ∈ (0, r_peak),
 *        y ∈ (0, y_peak). y ≥ y_peak is WR_ERR_DOMAIN, or r_peak with desc.clamp.
 *     otherwise (c1 ≤ 0 and c2 ≤ 0): no positive branch; every solve is WR_ERR_DOMAIN.
 *   y ≤ 0, NaN or ∞ is WR_ERR_INVALID_ARG (never clamped: it is not a material).
 *   A desc may add a design band [r_lo, r_hi] (e.g. the paper's 2.5–50 mm); a root outside it is
 *   WR_ERR_DOMAIN, or clamped to the band with desc.clamp. Clamping is for meshing pipelines that must
 *   always produce a size; a validation or CLI wants the error.
 *
 * ON ANISOTROPY (Sec. 4.1.2, Fig. 6)
 *   The paper gives no cross-coupling; we take the direct per-direction reading: r_warp = r(B_warp /
 *   E_warp) is the target edge length measured ALONG the warp (grain) direction and resolves wrinkles
 *   whose wave vector lies along the warp; r_weft likewise along the weft. In Fig. 6 the weft is the
 *   soft direction, giving "fine weft, coarse warp". wr_resolution_metric turns the pair into the 2×2
 *   sizing metric (unit metric length ⇔ target edge length in every direction).
 *
 * MEMORY: nothing is allocated. THREADS: no global state; everything is a pure function of its
 * arguments.
 */
#ifndef WRINKLE_RESOLUTION_H
#define WRINKLE_RESOLUTION_H

#include "core.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Eq. 4 parameters: c1 r⁶ + c2 r⁴ = y. c1 [m⁻³], c2 [m⁻¹]. */
typedef struct wr_resolution_model {
    double c1;
    double c2;
} wr_resolution_model;

/* The increasing positive branch of Eq. 4 (see "ON THE DOMAIN"): r ∈ (r_lo, r_hi), y ∈ (0, y_hi).
 * r_hi and y_hi are +INFINITY when unbounded. r_zero = sqrt(-c2/c1) when c1 > 0 > c2, else 0.
 * r_extremum = sqrt(-2c2/(3c1)) where f' changes sign (0 when it never does). */
typedef struct wr_resolution_domain_info {
    double r_lo, r_hi;
    double y_hi;
    double r_zero;
    double r_extremum;
} wr_resolution_domain_info;

/* Options for the root solve. Defaults (all zero): no design band, out-of-domain is an error.
 *   clamp   0: y or r outside the branch / band → WR_ERR_DOMAIN.  1: clamp to the nearest edge.
 *   r_lo, r_hi   optional design band [m]; 0 = no bound on that side.
 *   rel_tol      relative tolerance on r² of the safeguarded Newton iteration; 0 → 1e-14
 *                (a few ulps above double precision: the solve is cheap, so converge fully).
 *   max_iter     0 → 200 (bisection alone needs ~60 halvings from the analytic bracket). */
typedef struct wr_resolution_desc {
    int clamp;
    double r_lo, r_hi;
    double rel_tol;
    int32_t max_iter;
} wr_resolution_desc;

/* Paper's design ranges (Sec. 4.1.1), SI. */
#define WR_RESOLUTION_PAPER_E_MIN 2.0e3  /* N/m² */
#define WR_RESOLUTION_PAPER_E_MAX 2.0e6  /* N/m² */
#define WR_RESOLUTION_PAPER_B_MIN 1.0e-9 /* N·m */
#define WR_RESOLUTION_PAPER_B_MAX 1.0e-3 /* N·m */
#define WR_RESOLUTION_PAPER_R_MIN 2.5e-3 /* m */
#define WR_RESOLUTION_PAPER_R_MAX 50.0e-3 /* m */

/* Calibrate Eq. 4 so that the coarsest r_max pairs with y_max = B_max/E_min and the finest r_min with
 * y_min = B_min/E_max (Sec. 4.1.1). All inputs finite and > 0, E_min < E_max, B_min < B_max,
 * r_min < r_max, else WR_ERR_INVALID_ARG. WR_ERR_DOMAIN when the resulting model is not increasing on
 * [r_min, r_max] (the two design points would lie on different branches). */
WRDEF wr_status wr_resolution_calibrate(double E_min, double E_max, double B_min, double B_max, double r_min,
                                        double r_max, wr_resolution_model *out, wr_diag *diag);
/* Same from the y range directly: y_min < y_max, r_min < r_max, all > 0. */
WRDEF wr_status wr_resolution_calibrate_y(double y_min, double y_max, double r_min, double r_max,
                                          wr_resolution_model *out, wr_diag *diag);
/* The paper's model, calibrated from WR_RESOLUTION_PAPER_* (c1 = 32.075 m⁻³, c2 = -1.8767e-4 m⁻¹). */
WRDEF wr_resolution_model wr_resolution_model_paper(void);

/* Branch of the model; WR_ERR_DOMAIN when it has none, WR_ERR_INVALID_ARG for non-finite c1, c2. */
WRDEF wr_status wr_resolution_domain(const wr_resolution_model *m, wr_resolution_domain_info *out, wr_diag *diag);

/* Solve Eq. 4 for r [m] on the increasing positive branch. desc may be NULL. */
WRDEF wr_status wr_resolution_from_y(const wr_resolution_model *m, double y, const wr_resolution_desc *desc,
                                     double *r, wr_diag *diag);
/* y = B/E; B [N·m] and E [N/m²] finite and > 0. */
WRDEF wr_status wr_resolution_from_BE(const wr_resolution_model *m, double B, double E,
                                      const wr_resolution_desc *desc, double *r, wr_diag *diag);
/* The inverse y(r) = c1 r⁶ + c2 r⁴ [m³]; r must lie on the branch (else WR_ERR_DOMAIN). */
WRDEF wr_status wr_resolution_y(const wr_resolution_model *m, double r, double *y, wr_diag *diag);

/* Sec. 4.1.2: r_warp from (B_warp, E_warp), r_weft from (B_weft, E_weft); see "ON ANISOTROPY".
 * diag->item is 0 when the warp pair failed, 1 for the weft pair. */
WRDEF wr_status wr_resolution_orthotropic(const wr_resolution_model *m, double B_warp, double E_warp,
                                          double B_weft, double E_weft, const wr_resolution_desc *desc,
                                          double *r_warp, double *r_weft, wr_diag *diag);

/* Sizing metric M = R diag(1/r_warp², 1/r_weft²) Rᵀ, R the rotation by grain_angle [rad] (the warp
 * direction is (cos a, sin a) in the 2D pattern frame). sqrt(vᵀ M v) = 1 for a vector v of the target
 * edge length in its direction. Caller guarantees r_warp, r_weft > 0. */
WRDEF wr_mat2 wr_resolution_metric(double r_warp, double r_weft, double grain_angle);

/* Kirchhoff–Love (Sec. 4.1.1): y = h³ / (12 (1 - ν²)) [m³]; h > 0 [m], ν ∈ (-1, 0.5]. */
WRDEF wr_status wr_kl_y(double h, double nu, double *y, wr_diag *diag);
/* B = E h³ / (12 (1 - ν²)) [N·m], E [N/m²] > 0. */
WRDEF wr_status wr_kl_bending(double E, double h, double nu, double *B, wr_diag *diag);

/* Cerda–Mahadevan (Sec. 3.1): λ = 2√π (B L² / T)^{1/4} [m]; B [N·m], T [N/m], L [m], all > 0. */
WRDEF wr_status wr_cm_wavelength(double B, double T, double L, double *lambda, wr_diag *diag);
/* A = (√2/π) λ √δ [m]; λ > 0, δ ≥ 0 (compressive strain Δ/W). */
WRDEF wr_status wr_cm_amplitude(double lambda, double delta, double *A, wr_diag *diag);
/* Sec. 4.1.1, Fig. 4: r_opt = sqrt(λ²/16 + A²) [m]. */
WRDEF double wr_cm_optimal_resolution(double lambda, double A);

#ifdef __cplusplus
}
#endif
#endif /* WRINKLE_RESOLUTION_H */

/* ============================================================================================ */
#ifdef WRINKLE_IMPLEMENTATION
#ifndef WRINKLE_RESOLUTION_IMPLEMENTATION_DONE
#define WRINKLE_RESOLUTION_IMPLEMENTATION_DONE

#include <math.h>

#ifdef __cplusplus
extern "C" {
#endif

/* Default Newton tolerance on u = r² (relative): converge to near machine precision. */
#define WR__RES_DEFAULT_REL_TOL 1e-14
#define WR__RES_DEFAULT_MAX_ITER 200
/* Relative step [1] by which an analytic bracket end that misses the root by round-off is widened. */
#define WR__RES_BRACKET_GROW 1e-12

static int wr__res_pos(double v) { return isfinite(v) && v > 0.0; }

WRDEF wr_status wr_resolution_calibrate_y(double y_min, double y_max, double r_min, double r_max,
                                          wr_resolution_model *out, wr_diag *diag) {
    double a, b, den, c1, c2;
    if (!out) return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "calibrate: NULL output");
    if (!wr__res_pos(y_min) || !wr__res_pos(y_max))
        return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "calibrate: y range [%g, %g] m^3 must be finite and > 0",
                       y_min, y_max);
    if (!wr__res_pos(r_min) || !wr__res_pos(r_max))
        return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "calibrate: r range [%g, %g] m must be finite and > 0",
                       r_min, r_max);
    if (!(y_min < y_max))
        return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "calibrate: inverted y range: y_min=%g >= y_max=%g", y_min,
                       y_max);
    if (!(r_min < r_max))
        return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "calibrate: inverted r range: r_min=%g >= r_max=%g m", r_min,
                       r_max);
    /* Sec. 4.1.1: [c1 c2]ᵀ = det⁻¹ [[r_min⁴, -r_max⁴], [-r_min⁶, r_max⁶]] [y_max y_min]ᵀ with
     * det = r_max⁴ r_min⁴ (r_max + r_min)(r_max - r_min). Dividing the r⁴ factors into the y's first
     * is the same algebra without forming the ~1e-22 product r_max⁴ r_min⁴:
     *   c1 = (y_max/r_max⁴ - y_min/r_min⁴) / (r_max² - r_min²)
     *   c2 = (y_min r_max²/r_min⁴ - y_max r_min²/r_max⁴) / (r_max² - r_min²). */
    a = y_max / (r_max * r_max * r_max * r_max);
    b = y_min / (r_min * r_min * r_min * r_min);
    den = (r_max - r_min) * (r_max + r_min);
    c1 = (a - b) / den;
    c2 = (b * r_max * r_max - a * r_min * r_min) / den;
    if (!isfinite(c1) || !isfinite(c2))
        return wr_fail(diag, WR_ERR_DOMAIN, -1, "calibrate: c1=%g, c2=%g not finite (ranges too extreme)", c1, c2);
    /* f'(r) has the sign of 3 c1 r² + 2 c2, linear in r²: positive at both ends ⇔ on the whole range. */
    if (!(3.0 * c1 * r_min * r_min + 2.0 * c2 > 0.0) || !(3.0 * c1 * r_max * r_max + 2.0 * c2 > 0.0))
        return wr_fail(diag, WR_ERR_DOMAIN, -1,
                       "calibrate: c1=%g, c2=%g is not increasing on [%g, %g] m (y ratio %g too small for r "
                       "ratio %g)",
                       c1, c2, r_min, r_max, y_max / y_min, r_max / r_min);
    out->c1 = c1;
    out->c2 = c2;
    return WR_OK;
}

WRDEF wr_status wr_resolution_calibrate(double E_min, double E_max, double B_min, double B_max, double r_min,
                                        double r_max, wr_resolution_model *out, wr_diag *diag) {
    if (!wr__res_pos(E_min) || !wr__res_pos(E_max))
        return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "calibrate: E range [%g, %g] N/m^2 must be finite and > 0",
                       E_min, E_max);
    if (!wr__res_pos(B_min) || !wr__res_pos(B_max))
        return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "calibrate: B range [%g, %g] N*m must be finite and > 0",
                       B_min, B_max);
    if (!(E_min < E_max))
        return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "calibrate: inverted E range: E_min=%g >= E_max=%g", E_min,
                       E_max);
    if (!(B_min < B_max))
        return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "calibrate: inverted B range: B_min=%g >= B_max=%g", B_min,
                       B_max);
    /* Sec. 4.1.1: the coarsest resolution pairs with the highest B and smallest E, the finest with the
     * lowest B and largest E. */
    return wr_resolution_calibrate_y(B_min / E_max, B_max / E_min, r_min, r_max, out, diag);
}

WRDEF wr_resolution_model wr_resolution_model_paper(void) {
    wr_resolution_model m;
    m.c1 = m.c2 = 0.0;
    /* The paper's ranges are valid inputs, so this cannot fail; the WR_ASSERT guards edits. */
    if (wr_resolution_calibrate(WR_RESOLUTION_PAPER_E_MIN, WR_RESOLUTION_PAPER_E_MAX, WR_RESOLUTION_PAPER_B_MIN,
                                WR_RESOLUTION_PAPER_B_MAX, WR_RESOLUTION_PAPER_R_MIN, WR_RESOLUTION_PAPER_R_MAX, &m,
                                NULL) != WR_OK)
        WR_ASSERT(0 && "paper design ranges must calibrate");
    return m;
}

WRDEF wr_status wr_resolution_domain(const wr_resolution_model *m, wr_resolution_domain_info *out, wr_diag *diag) {
    double c1, c2;
    if (!m || !out) return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "resolution domain: NULL argument");
    c1 = m->c1;
    c2 = m->c2;
    if (!isfinite(c1) || !isfinite(c2))
        return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "resolution model: c1=%g, c2=%g not finite", c1, c2);
    out->r_zero = 0.0;
    out->r_extremum = 0.0;
    out->y_hi = INFINITY;
    out->r_hi = INFINITY;
    out->r_lo = 0.0;
    if (c1 > 0.0) {
        if (c2 < 0.0) {
            out->r_zero = sqrt(-c2 / c1);
            out->r_extremum = sqrt(-2.0 * c2 / (3.0 * c1));
            out->r_lo = out->r_zero;
        }
        return WR_OK;
    }
    if (c1 == 0.0) {
        if (c2 > 0.0) return WR_OK;
    } else if (c2 > 0.0) { /* c1 < 0 < c2: peak */
        double u = -2.0 * c2 / (3.0 * c1);
        out->r_extremum = sqrt(u);
        out->r_zero = sqrt(-c2 / c1);
        out->r_hi = out->r_extremum;
        out->y_hi = u * u * (c1 * u + c2);
        return WR_OK;
    }
    return wr_fail(diag, WR_ERR_DOMAIN, -1,
                   "resolution model c1=%g m^-3, c2=%g m^-1 has no increasing positive branch", c1, c2);
}

/* g(u) = u²(c1 u + c2) - y with u = r²; the factored form loses nothing near the root r0. */
static double wr__res_f(double c1, double c2, double u) { return u * u * (c1 * u + c2); }

WRDEF wr_status wr_resolution_from_y(const wr_resolution_model *m, double y, const wr_resolution_desc *desc,
                                     double *r, wr_diag *diag) {
    wr_resolution_domain_info dom;
    wr_resolution_desc d;
    wr_status st;
    double c1, c2, lo, hi, u;
    int32_t it;
    if (!r) return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "resolution: NULL output");
    if (!isfinite(y) || !(y > 0.0))
        return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "resolution: y = B/E = %g m^3 must be finite and > 0", y);
    st = wr_resolution_domain(m, &dom, diag);
    if (st != WR_OK) return st;
    /* defaults */
    if (desc)
        d = *desc;
    else {
        d.clamp = 0;
        d.r_lo = d.r_hi = 0.0;
        d.rel_tol = 0.0;
        d.max_iter = 0;
    }
    if (d.rel_tol <= 0.0) d.rel_tol = WR__RES_DEFAULT_REL_TOL;
    if (d.max_iter <= 0) d.max_iter = WR__RES_DEFAULT_MAX_ITER;
    if (!(d.r_lo >= 0.0) || !(d.r_hi >= 0.0) || (d.r_hi > 0.0 && d.r_lo > d.r_hi))
        return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "resolution: bad design band [%g, %g] m", d.r_lo, d.r_hi);
    c1 = m->c1;
    c2 = m->c2;
    if (y >= dom.y_hi) {
        if (!d.clamp)
            return wr_fail(diag, WR_ERR_DOMAIN, -1,
                           "resolution: y=%g m^3 is above the model's maximum %g m^3 (reached at r=%g m)", y,
                           dom.y_hi, dom.r_hi);
        u = dom.r_hi * dom.r_hi;
    } else if (c1 == 0.0) {
        u = sqrt(y / c2); /* c2 r⁴ = y */
    } else {
        /* Analytic bracket [lo, hi] on u = r² with g(lo) < 0 <= g(hi). */
        if (c1 > 0.0 && c2 < 0.0) {
            /* u = u0 + t, u0 = -c2/c1: y = c1 u² t >= c1 t max(u0², t²) ⇒ t <= min(y/(c1 u0²), (y/c1)^{1/3}). */
            double u0 = -c2 / c1;
            double t = fmin(y / (c1 * u0 * u0), cbrt(y / c1));
            lo = u0;
            hi = u0 + t;
        } else if (c1 > 0.0) {
            /* both terms >= 0: u <= (y/c1)^{1/3} and u <= sqrt(y/c2). */
            lo = 0.0;
            hi = cbrt(y / c1);
            if (c2 > 0.0) hi = fmin(hi, sqrt(y / c2));
        } else {
            /* c1 < 0 < c2, u < u_peak: y = u²(c2 + c1 u) lies between u² c2/3 (c1 u > c1 u_peak = -2c2/3)
             * and u² c2, so sqrt(y/c2) <= u <= sqrt(3y/c2): a bracket of ratio √3 at every scale (from
             * [0, u_peak] Newton would only halve per step toward a tiny root). */
            lo = sqrt(y / c2);
            hi = fmin(dom.r_hi * dom.r_hi, sqrt(3.0 * y / c2));
            if (lo > hi) lo = hi;
            while (wr__res_f(c1, c2, lo) - y > 0.0 && lo > 0.0) lo *= 0.5; /* rounding guard */
        }
        /* The bracket bound can be tight to the last ulp; widen until it truly brackets. */
        while (!(wr__res_f(c1, c2, hi) - y >= 0.0) && isfinite(hi)) hi = hi * (1.0 + WR__RES_BRACKET_GROW) + 1e-300;
        u = 0.5 * (lo + hi);
        for (it = 0; it < d.max_iter; ++it) {
            double g = wr__res_f(c1, c2, u) - y;
            double dg = u * (3.0 * c1 * u + 2.0 * c2); /* dg/du */
            double un;
            if (g < 0.0)
                lo = u;
            else
                hi = u;
            if (g == 0.0) break;
            un = u - g / dg;
            /* Safeguard: fall back to bisection when Newton leaves the bracket. */
            if (!(dg > 0.0) || !(un > lo && un < hi)) un = 0.5 * (lo + hi);
            if (fabs(un - u) <= d.rel_tol * u || hi - lo <= d.rel_tol * hi) {
                u = un;
                break;
            }
            u = un;
        }
        if (it == d.max_iter)
            return wr_fail(diag, WR_ERR_NOT_CONVERGED, -1, "resolution: root solve for y=%g did not converge", y);
    }
    {
        double rr = sqrt(u);
        if (d.r_lo > 0.0 && rr < d.r_lo) {
            if (!d.clamp)
                return wr_fail(diag, WR_ERR_DOMAIN, -1,
                               "resolution: r=%g m for y=%g m^3 is below the design band minimum %g m", rr, y, d.r_lo);
            rr = d.r_lo;
        }
        if (d.r_hi > 0.0 && rr > d.r_hi) {
            if (!d.clamp)
                return wr_fail(diag, WR_ERR_DOMAIN, -1,
                               "resolution: r=%g m for y=%g m^3 is above the design band maximum %g m", rr, y, d.r_hi);
            rr = d.r_hi;
        }
        *r = rr;
    }
    return WR_OK;
}

WRDEF wr_status wr_resolution_from_BE(const wr_resolution_model *m, double B, double E,
                                      const wr_resolution_desc *desc, double *r, wr_diag *diag) {
    if (!wr__res_pos(B))
        return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "resolution: bending stiffness B=%g N*m must be finite and > 0",
                       B);
    if (!wr__res_pos(E))
        return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "resolution: Young's modulus E=%g N/m^2 must be finite and > 0",
                       E);
    return wr_resolution_from_y(m, B / E, desc, r, diag);
}

WRDEF wr_status wr_resolution_y(const wr_resolution_model *m, double r, double *y, wr_diag *diag) {
    wr_resolution_domain_info dom;
    wr_status st;
    if (!y) return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "resolution y(r): NULL output");
    if (!wr__res_pos(r))
        return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "resolution y(r): r=%g m must be finite and > 0", r);
    st = wr_resolution_domain(m, &dom, diag);
    if (st != WR_OK) return st;
    if (!(r > dom.r_lo) || !(r < dom.r_hi)) {
        /* An unbounded branch (r_hi = +INFINITY) is said in words: the text reaches users through the
         * drivers, and "inf" in an error reads like a bug. */
        if (isinf(dom.r_hi))
            return wr_fail(diag, WR_ERR_DOMAIN, -1,
                           "resolution y(r): r=%g m is outside the model's increasing positive branch r > %g m", r,
                           dom.r_lo);
        return wr_fail(diag, WR_ERR_DOMAIN, -1,
                       "resolution y(r): r=%g m is outside the model's increasing positive branch (%g, %g) m", r,
                       dom.r_lo, dom.r_hi);
    }
    *y = wr__res_f(m->c1, m->c2, r * r);
    return WR_OK;
}

WRDEF wr_status wr_resolution_orthotropic(const wr_resolution_model *m, double B_warp, double E_warp,
                                          double B_weft, double E_weft, const wr_resolution_desc *desc,
                                          double *r_warp, double *r_weft, wr_diag *diag) {
    wr_status st;
    double a, b;
    if (!r_warp || !r_weft) return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "orthotropic: NULL output");
    st = wr_resolution_from_BE(m, B_warp, E_warp, desc, &a, diag);
    if (st != WR_OK) {
        if (diag) diag->item = 0;
        return st;
    }
    st = wr_resolution_from_BE(m, B_weft, E_weft, desc, &b, diag);
    if (st != WR_OK) {
        if (diag) diag->item = 1;
        return st;
    }
    *r_warp = a;
    *r_weft = b;
    return WR_OK;
}

WRDEF wr_mat2 wr_resolution_metric(double r_warp, double r_weft, double grain_angle) {
    double c = cos(grain_angle), s = sin(grain_angle);
    double a = 1.0 / (r_warp * r_warp), b = 1.0 / (r_weft * r_weft);
    /* R = [[c, -s], [s, c]]; M = R diag(a, b) Rᵀ. */
    return wr_m2(a * c * c + b * s * s, (a - b) * c * s, (a - b) * c * s, a * s * s + b * c * c);
}

WRDEF wr_status wr_kl_y(double h, double nu, double *y, wr_diag *diag) {
    if (!y) return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "kl: NULL output");
    if (!wr__res_pos(h)) return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "kl: thickness h=%g m must be finite and > 0", h);
    /* ν ≤ 0.5 for an isotropic elastic solid (incompressible limit); > -1 keeps 1 - ν² > 0. */
    if (!isfinite(nu) || !(nu > -1.0) || !(nu <= 0.5))
        return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "kl: Poisson ratio nu=%g must lie in (-1, 0.5]", nu);
    *y = h * h * h / (12.0 * (1.0 - nu * nu));
    return WR_OK;
}

WRDEF wr_status wr_kl_bending(double E, double h, double nu, double *B, wr_diag *diag) {
    double y;
    wr_status st;
    if (!B) return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "kl: NULL output");
    if (!wr__res_pos(E))
        return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "kl: Young's modulus E=%g N/m^2 must be finite and > 0", E);
    st = wr_kl_y(h, nu, &y, diag);
    if (st != WR_OK) return st;
    *B = E * y;
    return WR_OK;
}

WRDEF wr_status wr_cm_wavelength(double B, double T, double L, double *lambda, wr_diag *diag) {
    if (!lambda) return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "cm: NULL output");
    if (!wr__res_pos(B)) return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "cm: B=%g N*m must be finite and > 0", B);
    if (!wr__res_pos(T)) return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "cm: tension T=%g N/m must be finite and > 0", T);
    if (!wr__res_pos(L)) return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "cm: length L=%g m must be finite and > 0", L);
    /* Sec. 3.1: λ = 2√π (B / (T/L²))^{1/4}; K = T/L² is the effective foundation stiffness. */
    *lambda = 2.0 * sqrt(3.14159265358979323846) * sqrt(sqrt(B * L * L / T));
    return WR_OK;
}

WRDEF wr_status wr_cm_amplitude(double lambda, double delta, double *A, wr_diag *diag) {
    if (!A) return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "cm: NULL output");
    if (!wr__res_pos(lambda))
        return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "cm: wavelength %g m must be finite and > 0", lambda);
    if (!isfinite(delta) || !(delta >= 0.0))
        return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "cm: compressive strain delta=%g must be finite and >= 0", delta);
    /* Sec. 3.1: A = (√2/π) λ √δ. */
    *A = sqrt(2.0) / 3.14159265358979323846 * lambda * sqrt(delta);
    return WR_OK;
}

WRDEF double wr_cm_optimal_resolution(double lambda, double A) {
    /* Sec. 4.1.1, Fig. 4: one edge spans a quarter wavelength (crest to node, λ/4) horizontally and the
     * amplitude A vertically; Pythagoras gives its length. */
    return sqrt(lambda * lambda / 16.0 + A * A);
}

#ifdef __cplusplus
}
#endif
#endif /* WRINKLE_RESOLUTION_IMPLEMENTATION_DONE */
#endif /* WRINKLE_IMPLEMENTATION */
