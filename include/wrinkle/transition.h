/* wrinkle/transition.h — wrinklon transitions and the source resolutions of garment-making techniques:
 * the formulas of the Style3D sizing map (the map itself is sizing.h).
 * wrinkle v0.1.0 — MIT licence (see LICENSE). Needs only libc and libm (and core.h, resolution.h).
 *
 * Implements Sec. 3.2 and 4.2 of "Physics-inspired Estimation of Optimal Cloth Mesh Resolution"
 * (Style3D, SIGGRAPH 2025):
 *   4.2.1  wrinklon size  L_w ~ λ² sqrt(T/B)             (fabric under tension T)
 *                         L_w ~ λ^{3/2} (δ h⁻²)^{1/4}     (compression ratio δ, thickness h)
 *          transition power  m = log r / log L_w          (r, L_w in MILLIMETRES)
 *          resolution at distance x from a source  r(x) = r + x^m   (x in mm)
 *   4.2.2  shirring source  r_sh = ρ^n r(B/(E+E_sh))
 *   4.2.3  folding source  r_fd = (Δθ/360°) r_ng
 *   4.2.4  long-short stitching  ρ_s = l_s / l_l
 *   4.2.5  down-filling  m' = 2^p m,  L_w' = L_w^{2^{-p}}
 *
 * API
 *   wr_wrinklon_size_tension(lambda,T,B,&L_w,diag)        L_w = λ² sqrt(T/B)   (unit prefactor)
 *   wr_wrinklon_size_compression(lambda,delta,h,&L_w,diag) L_w = λ^{3/2} (δ/h²)^{1/4}
 *   wr_transition_power(r,L_w,&m,diag)        the paper's m = ln r_mm / ln L_mm (strict)
 *   wr_transition_make(r,L_w,desc,&t,diag)    transition {r, L_w, m}; scale-free fallback when the
 *                                             paper's m is undefined (r or L_w ≤ 1 mm)
 *   wr_transition_from_power(r,m,&t,diag)     a paper-style (r, m) pair as a transition
 *   wr_transition_eval(&t,x)                  r(x) = r (1 + (x/L_w)^m) [m]   (== r + x^m in mm)
 *   wr_transition_slope(&t,x)                 dr/dx [m/m]
 *   wr_transition_paper_eval(r,m,x)           the literal paper form r + x^m, mm inside, m outside
 *   wr_transition_downfill(&t,p,&out,diag)    m' = 2^p m, L_w' = L_w^{2^{-p}} (mm)
 *   wr_source_shirring(&model,B,E,E_sh,rho,n,desc,&r,diag)  r_sh = ρ^n r(B/(E+E_sh))   (Sec. 4.2.2)
 *   wr_source_folding(dtheta,r_ng,&r,diag)    r_fd = (Δθ/2π) r_ng   (Sec. 4.2.3, Δθ in radians)
 *   wr_source_stitch_ratio(l_short,l_long,&rho,diag)  ρ_s = l_s/l_l   (Sec. 4.2.4)
 *
 * EXAMPLE
 *     wr_transition t, u;  wr_diag d;
 *     if (wr_transition_make(3.0e-3, 25.0e-3, NULL, &t, &d) != WR_OK) { puts(d.message); return 1; }
 *     printf("m = %.3f, r(25 mm) = %.1f mm\n", t.m, 1e3 * wr_transition_eval(&t, 25.0e-3));   // 6 mm
 *     if (wr_transition_downfill(&t, 1.0, &u, &d) != WR_OK) { puts(d.message); return 1; }   // p = 1
 *     printf("down-filled: m' = %.3f, L_w' = %.2f mm\n", u.m, 1e3 * u.L_w);                 // 2m, 5 mm
 *
 * ON UNITS AND THE MILLIMETRE POWER LAW
 *   The API is SI (metres). The paper's power law r + x^m is NOT dimensionless: r, x and L_w are in
 *   millimetres there (m = log r / log L_w makes r + L_w^m = 2r only in the unit they were measured
 *   in). The conversion happens in exactly one place, wr__tr_mm() in the implementation; everything
 *   else is metres. We evaluate every transition in the equivalent scale-free form
 *       r(x) = r (1 + (x / L_w)^m),
 *   which equals r + x^m in mm whenever r_mm = L_mm^m (the paper's definition of m), so the two forms
 *   agree to rounding (tested). Its endpoints r(0) = r and r(L_w) = 2r hold for any m > 0.
 *
 * ON r OR L_w AT OR BELOW 1 mm (the paper's m is undefined there)
 *   ln r_mm ≤ 0 or ln L_mm ≤ 0 makes m ≤ 0, infinite or of the wrong sign: x^m would then decrease
 *   with distance or blow up at x → 0. wr_transition_power reports WR_ERR_DOMAIN there. The builder
 *   wr_transition_make instead switches to the scale-free form with m = desc.fallback_power (default
 *   1/2, Vandeparre et al.'s heavy-curtain exponent λ ∝ x^{1/2}, Sec. 3.2) and sets t.scale_free = 1:
 *   it keeps r(0) = r, r(L_w) = 2r, monotone growth, and never produces NaN.
 *
 * MEMORY: nothing is allocated. THREADS: every function is pure.
 */
#ifndef WRINKLE_TRANSITION_H
#define WRINKLE_TRANSITION_H

#include "core.h"
#include "resolution.h" /* wr_resolution_metric for the anisotropic hook */

#ifdef __cplusplus
extern "C" {
#endif

/* One resolution transition away from a source: r(x) = r (1 + (x/L_w)^m). */
typedef struct wr_transition {
    double r;       /* source resolution [m] */
    double L_w;     /* transition distance over which r doubles [m] */
    double m;       /* transition power (dimensionless, > 0) */
    int scale_free; /* 1: m is desc.fallback_power because the paper's m was undefined */
} wr_transition;

/* Options for wr_transition_make. Zero means default:
 *   fallback_power   exponent used when the paper's m is undefined; 0 → 0.5 (Vandeparre et al.
 *                    2011 heavy curtain, λ ∝ x^{1/2}; Sec. 3.2). Must be > 0 and finite if set.
 *   strict           1: no fallback, return WR_ERR_DOMAIN like wr_transition_power. */
typedef struct wr_transition_desc {
    double fallback_power;
    int strict;
} wr_transition_desc;

#define WR_TRANSITION_DEFAULT_FALLBACK_POWER 0.5

/* Sec. 4.2.1, tension form: L_w = λ² sqrt(T/B) (scaling law, prefactor 1 — multiply by your own).
 * λ [m], T [N/m], B [N·m], all finite and > 0.
 * Which form applies (Vandeparre et al. 2011's energy balance, which Style3D cites; re-derived: a
 * wrinklon of amplitude A ~ λ sqrt(δ) and length L pays bending B A²/λ⁴ against stretching T (A/L)²
 * (heavy, this form) or E h (A/L)⁴ (light, the compression form below)): this form holds only when
 * T/(E h) ≫ (A/L)². A fabric-like sheet (E h ~ 300 N/m) gathered at cm scale under its own weight is
 * on the light side (measured by validation/validate_curtain: docs/notes-sizing.md). Style3D writes
 * both forms with "~" and gives no O(1) prefactor. */
WRDEF wr_status wr_wrinklon_size_tension(double lambda, double T, double B, double *L_w, wr_diag *diag);
/* Sec. 4.2.1, compression form: L_w = λ^{3/2} (δ h⁻²)^{1/4} (prefactor 1). λ, h [m] > 0, δ > 0. */
WRDEF wr_status wr_wrinklon_size_compression(double lambda, double delta, double h, double *L_w, wr_diag *diag);

/* Sec. 4.2.1: m = ln(r/1 mm) / ln(L_w/1 mm). WR_ERR_DOMAIN when r ≤ 1 mm or L_w ≤ 1 mm. */
WRDEF wr_status wr_transition_power(double r, double L_w, double *m, wr_diag *diag);
/* Build a transition from a source resolution r [m] and a wrinklon size L_w [m]; desc may be NULL. */
WRDEF wr_status wr_transition_make(double r, double L_w, const wr_transition_desc *desc, wr_transition *out,
                                   wr_diag *diag);
/* From the paper's (r, m): L_w = 1 mm · r_mm^{1/m}. WR_ERR_DOMAIN if that L_w is not representable. */
WRDEF wr_status wr_transition_from_power(double r, double m, wr_transition *out, wr_diag *diag);
/* r(x) = r (1 + (x/L_w)^m) [m] for distance x ≥ 0 [m]. */
WRDEF double wr_transition_eval(const wr_transition *t, double x);
/* dr/dx [m/m]; +INFINITY at x = 0 when m < 1, 0 at x = 0 when m > 1. */
WRDEF double wr_transition_slope(const wr_transition *t, double x);
/* The literal paper form r + x^m with r, x in metres converted to mm inside; result in metres. */
WRDEF double wr_transition_paper_eval(double r, double m, double x);
/* Sec. 4.2.5: down-filling pressure p ≥ 0: m' = 2^p m, L_w' = (L_w in mm)^{2^{-p}} mm. Keeps r. */
WRDEF wr_status wr_transition_downfill(const wr_transition *t, double p, wr_transition *out, wr_diag *diag);

/* ---- source resolutions of garment-making techniques (Sec. 4.2.2-4.2.4) -------------------- */
/* Shirring (Sec. 4.2.2): y_sh = B / (E + E_sh), r_sh = ρ_sh^n r(y_sh) with Eq. 4 (model, desc as in
 * resolution.h). E_sh ≥ 0 [N/m²] extra shirring stiffness, ρ_sh ∈ (0, 1] shrinkage ratio, n ≥ 0
 * (the paper uses n = 1). Stitching with a compressive ratio (Sec. 4.2.4) is the same call with
 * ρ = wr_source_stitch_ratio(...). */
WRDEF wr_status wr_source_shirring(const wr_resolution_model *model, double B, double E, double E_sh, double rho,
                                   double n, const wr_resolution_desc *desc, double *r, wr_diag *diag);
/* Folding endpoints / high-curvature points (Sec. 4.2.3): ρ_fd = Δθ/360° — here Δθ in radians, so
 * ρ_fd = Δθ / 2π, Δθ ∈ (0, 2π] — and r_fd = ρ_fd r_ng, r_ng [m] > 0 the neighbourhood resolution. */
WRDEF wr_status wr_source_folding(double dtheta, double r_ng, double *r, wr_diag *diag);
/* Long-short stitching (Sec. 4.2.4): ρ_s = l_short / l_long ∈ (0, 1]; lengths [m] > 0. */
WRDEF wr_status wr_source_stitch_ratio(double l_short, double l_long, double *rho, wr_diag *diag);

#ifdef __cplusplus
}
#endif
#endif /* WRINKLE_TRANSITION_H */

/* ============================================================================================ */
#ifdef WRINKLE_IMPLEMENTATION
#ifndef WRINKLE_TRANSITION_IMPLEMENTATION_DONE
#define WRINKLE_TRANSITION_IMPLEMENTATION_DONE

#include "core.h"
#include "resolution.h"
#include <math.h>
#include <string.h>

#ifdef __cplusplus
extern "C" {
#endif

/* THE one place where the paper's millimetre power law meets SI metres (Sec. 4.2.1). */
static double wr__tr_mm(double metres) { return metres * 1e3; }

static int wr__tr_pos(double v) { return isfinite(v) && v > 0.0; }

WRDEF wr_status wr_wrinklon_size_tension(double lambda, double T, double B, double *L_w, wr_diag *diag) {
    if (!L_w) return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "wrinklon: NULL output");
    if (!wr__tr_pos(lambda))
        return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "wrinklon: wavelength %g m must be finite and > 0", lambda);
    if (!wr__tr_pos(T)) return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "wrinklon: tension T=%g N/m must be > 0", T);
    if (!wr__tr_pos(B)) return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "wrinklon: B=%g N*m must be > 0", B);
    /* Sec. 4.2.1: L_w ~ λ² sqrt(T/B); [m² · sqrt((N/m)/(N·m))] = [m]. */
    *L_w = lambda * lambda * sqrt(T / B);
    return WR_OK;
}

WRDEF wr_status wr_wrinklon_size_compression(double lambda, double delta, double h, double *L_w, wr_diag *diag) {
    if (!L_w) return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "wrinklon: NULL output");
    if (!wr__tr_pos(lambda))
        return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "wrinklon: wavelength %g m must be finite and > 0", lambda);
    if (!wr__tr_pos(delta))
        return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "wrinklon: compression ratio delta=%g must be > 0", delta);
    if (!wr__tr_pos(h)) return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "wrinklon: thickness h=%g m must be > 0", h);
    /* Sec. 4.2.1: L_w ~ λ^{3/2} (δ h⁻²)^{1/4} = λ^{3/2} δ^{1/4} h^{-1/2}; [m^{3/2} m^{-1/2}] = [m]. */
    *L_w = lambda * sqrt(lambda) * sqrt(sqrt(delta)) / sqrt(h);
    return WR_OK;
}

WRDEF wr_status wr_transition_power(double r, double L_w, double *m, wr_diag *diag) {
    double lr, ll;
    if (!m) return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "transition: NULL output");
    if (!wr__tr_pos(r))
        return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "transition: source resolution r=%g m must be > 0", r);
    if (!wr__tr_pos(L_w))
        return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "transition: wrinklon size L_w=%g m must be > 0", L_w);
    lr = log(wr__tr_mm(r));
    ll = log(wr__tr_mm(L_w));
    if (!(lr > 0.0) || !(ll > 0.0))
        return wr_fail(diag, WR_ERR_DOMAIN, -1,
                       "transition: m = log r / log L_w needs r and L_w above 1 mm (r=%g mm, L_w=%g mm)",
                       wr__tr_mm(r), wr__tr_mm(L_w));
    *m = lr / ll;
    return WR_OK;
}

WRDEF wr_status wr_transition_make(double r, double L_w, const wr_transition_desc *desc, wr_transition *out,
                                   wr_diag *diag) {
    double m, fb = WR_TRANSITION_DEFAULT_FALLBACK_POWER;
    int strict = 0;
    wr_status st;
    if (!out) return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "transition: NULL output");
    if (desc) {
        if (desc->fallback_power != 0.0) {
            if (!wr__tr_pos(desc->fallback_power))
                return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "transition: fallback_power=%g must be finite and > 0",
                               desc->fallback_power);
            fb = desc->fallback_power;
        }
        strict = desc->strict;
    }
    st = wr_transition_power(r, L_w, &m, diag);
    if (st == WR_ERR_DOMAIN && !strict) {
        m = fb;
        out->scale_free = 1;
    } else if (st != WR_OK) {
        return st;
    } else {
        out->scale_free = 0;
    }
    out->r = r;
    out->L_w = L_w;
    out->m = m;
    return WR_OK;
}

WRDEF wr_status wr_transition_from_power(double r, double m, wr_transition *out, wr_diag *diag) {
    double L_mm;
    if (!out) return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "transition: NULL output");
    if (!wr__tr_pos(r))
        return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "transition: source resolution r=%g m must be > 0", r);
    if (!wr__tr_pos(m)) return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "transition: power m=%g must be > 0", m);
    /* r_mm + L_mm^m = 2 r_mm ⇔ L_mm = r_mm^{1/m}. */
    L_mm = pow(wr__tr_mm(r), 1.0 / m);
    if (!wr__tr_pos(L_mm))
        return wr_fail(diag, WR_ERR_DOMAIN, -1, "transition: r=%g mm with m=%g gives L_w=%g mm (not representable)",
                       wr__tr_mm(r), m, L_mm);
    out->r = r;
    out->m = m;
    out->L_w = L_mm / wr__tr_mm(1.0);
    out->scale_free = 0;
    return WR_OK;
}

WRDEF double wr_transition_eval(const wr_transition *t, double x) {
    /* Scale-free form of r + x^m (see "ON UNITS"); pow(0, m > 0) = 0 gives r(0) = r exactly. */
    return t->r * (1.0 + pow(x / t->L_w, t->m));
}

WRDEF double wr_transition_slope(const wr_transition *t, double x) {
    double q = x / t->L_w;
    if (q == 0.0) return t->m < 1.0 ? INFINITY : (t->m == 1.0 ? t->r / t->L_w : 0.0);
    return t->r * t->m * pow(q, t->m - 1.0) / t->L_w;
}

WRDEF double wr_transition_paper_eval(double r, double m, double x) {
    /* Sec. 4.2.1 literally: r + x^m with x in mm, result converted back to metres. */
    return r + pow(wr__tr_mm(x), m) / wr__tr_mm(1.0);
}

WRDEF wr_status wr_transition_downfill(const wr_transition *t, double p, wr_transition *out, wr_diag *diag) {
    double L_mm, s;
    if (!t || !out) return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "downfill: NULL argument");
    if (!isfinite(p) || !(p >= 0.0))
        return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "downfill: pressure p=%g must be finite and >= 0", p);
    if (!wr__tr_pos(t->r) || !wr__tr_pos(t->L_w) || !wr__tr_pos(t->m))
        return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "downfill: invalid transition (r=%g, L_w=%g, m=%g)", t->r,
                       t->L_w, t->m);
    /* Sec. 4.2.5: m' = 2^p m and L_w' = L_w^{2^{-p}} (mm). Then L_w'^{m'} = L_w^m, so r(L_w') = 2r is kept.
     * For L_w < 1 mm the mm power moves L_w' up toward 1 mm — a property of the paper's formula. */
    s = pow(2.0, p);
    L_mm = pow(wr__tr_mm(t->L_w), 1.0 / s);
    if (!wr__tr_pos(s * t->m) || !wr__tr_pos(L_mm))
        return wr_fail(diag, WR_ERR_DOMAIN, -1, "downfill: p=%g overflows the transition power", p);
    out->r = t->r;
    out->m = s * t->m;
    out->L_w = L_mm / wr__tr_mm(1.0);
    out->scale_free = t->scale_free;
    return WR_OK;
}

WRDEF wr_status wr_source_shirring(const wr_resolution_model *model, double B, double E, double E_sh, double rho,
                                   double n, const wr_resolution_desc *desc, double *r, wr_diag *diag) {
    double rr;
    wr_status st;
    if (!r) return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "shirring: NULL output");
    if (!isfinite(E_sh) || !(E_sh >= 0.0))
        return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "shirring: E_sh=%g N/m^2 must be finite and >= 0", E_sh);
    if (!isfinite(rho) || !(rho > 0.0) || !(rho <= 1.0))
        return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "shirring: shrinkage ratio rho=%g must lie in (0, 1]", rho);
    if (!isfinite(n) || !(n >= 0.0))
        return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "shirring: exponent n=%g must be finite and >= 0", n);
    if (!wr__tr_pos(B)) return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "shirring: B=%g N*m must be > 0", B);
    if (!wr__tr_pos(E)) return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "shirring: E=%g N/m^2 must be > 0", E);
    /* Sec. 4.2.2: y_sh = B / (E + E_sh), r_sh = ρ^n r(y_sh). */
    st = wr_resolution_from_y(model, B / (E + E_sh), desc, &rr, diag);
    if (st != WR_OK) return st;
    *r = pow(rho, n) * rr;
    return WR_OK;
}

WRDEF wr_status wr_source_folding(double dtheta, double r_ng, double *r, wr_diag *diag) {
    const double two_pi = 6.283185307179586;
    if (!r) return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "folding: NULL output");
    if (!isfinite(dtheta) || !(dtheta > 0.0) || !(dtheta <= two_pi))
        return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "folding: angle %g rad must lie in (0, 2*pi]", dtheta);
    if (!wr__tr_pos(r_ng))
        return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "folding: neighbourhood resolution %g m must be > 0", r_ng);
    /* Sec. 4.2.3: ρ_fd = Δθ/360 (degrees) = Δθ/2π (radians); r_fd = ρ_fd r_ng. */
    *r = dtheta / two_pi * r_ng;
    return WR_OK;
}

WRDEF wr_status wr_source_stitch_ratio(double l_short, double l_long, double *rho, wr_diag *diag) {
    if (!rho) return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "stitching: NULL output");
    if (!wr__tr_pos(l_short) || !wr__tr_pos(l_long))
        return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "stitching: lengths %g, %g m must be finite and > 0", l_short,
                       l_long);
    if (l_short > l_long)
        return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "stitching: short line %g m is longer than the long line %g m",
                       l_short, l_long);
    /* Sec. 4.2.4: ρ_s = l_s / l_l sets the source resolution of the longer line. */
    *rho = l_short / l_long;
    return WR_OK;
}

#ifdef __cplusplus
}
#endif
#endif /* WRINKLE_TRANSITION_IMPLEMENTATION_DONE */
#endif /* WRINKLE_IMPLEMENTATION */
