/* wrinkle/transition.h — wrinklon transitions and the Style3D sizing map.
 * wrinkle v0.1.0 — MIT licence (see LICENSE). Needs only libc and libm (and core.h, resolution.h).
 *
 * Implements Sec. 3.2 and 4.2 of "Physics-inspired Estimation of Optimal Cloth Mesh Resolution"
 * (Style3D, SIGGRAPH 2025):
 *   4.2.1  wrinklon size  L_w ~ λ² sqrt(T/B)             (fabric under tension T)
 *                         L_w ~ λ^{3/2} (δ h⁻²)^{1/4}     (compression ratio δ, thickness h)
 *          transition power  m = log r / log L_w          (r, L_w in MILLIMETRES)
 *          resolution at distance x from a source  r(x) = r + x^m   (x in mm)
 *          sizing map  r_v = min(r_f, r_0 + x_0^{m_0}, ..., r_n + x_n^{m_n})
 *   4.2.3  directional transitions at folding endpoints (only the forward half-space is affected)
 *   4.2.5  down-filling  m' = 2^p m,  L_w' = L_w^{2^{-p}}
 *   4.1.2  anisotropic metric hook M = R diag(1/r_warp², 1/r_weft²) Rᵀ (see resolution.h)
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
 *   wr_sizing_create(r_f,desc,&s,diag) / wr_sizing_free(s)     the sizing map object
 *   wr_sizing_add_point(s,x,y,&t,diag)        point source
 *   wr_sizing_add_point_directional(s,x,y,dx,dy,&t,diag)   forward half-space only (Sec. 4.2.3)
 *   wr_sizing_add_polyline(s,xy,n,&t,diag)    distance to an open polyline of n points
 *   wr_sizing_build(s,diag)                   uniform-grid index (optional; eval works without)
 *   wr_sizing_eval(s,x,y)                     r_v [m]
 *   wr_sizing_eval_brute(s,x,y)               the same by scanning every source (reference)
 *   wr_sizing_eval_gradient(s,x,y,&r,grad)    r_v and ∇r_v of the active term
 *   wr_sizing_set_region_fn(s,fn,user)        per-region warp/weft resolution and grain angle
 *   wr_sizing_eval_metric(s,x,y)              2×2 sizing metric combining both
 *
 * EXAMPLE
 *     wr_transition t;  wr_sizing *s;  wr_diag d;
 *     double line[4] = {0.0, 0.0, 0.3, 0.0};                 // a 30 cm shirring line
 *     if (wr_transition_make(3.0e-3, 25.0e-3, NULL, &t, &d) != WR_OK) { puts(d.message); return 1; }
 *     if (wr_sizing_create(9.0e-3, NULL, &s, &d) != WR_OK) { puts(d.message); return 1; }  // r_f = 9 mm
 *     wr_sizing_add_polyline(s, line, 2, &t, &d);            // r = 3 mm on the line, doubling over 25 mm
 *     if (wr_sizing_build(s, &d) != WR_OK) { puts(d.message); return 1; }
 *     printf("%.1f mm\n", 1e3 * wr_sizing_eval(s, 0.1, 0.025));   // 6 mm: 25 mm away the size has doubled
 *     wr_sizing_free(s);
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
 * ON THE SIZING MAP
 *   r_v(p) = min(r_f, min_i r_i(dist(p, source_i))). A source whose r_i ≥ r_f can never win and is
 *   dropped. The grid index stores each polyline segment (a point is a zero-length segment) in every
 *   cell of a uniform grid its bounding box overlaps, then visits rings of cells around the query
 *   and stops when a lower bound of every unvisited term exceeds the current minimum (terms increase
 *   with distance; the bound per ring comes from a table built once per build). Within a scan the
 *   transition is evaluated once per run of one source's segments, at their smallest distance. Both
 *   paths run the same scan routine, so the grid gives the brute-force value exactly (tested with ==).
 *   Speed-up depends on the physics: with steep transitions (m ≥ 1, reach of a few mm) a 2000-segment
 *   map answers ~80x faster than the scan; with the slow transitions the paper's m = log r / log L_w
 *   gives for typical r and L_w (m ≈ 0.2–0.5, a source still refines r_f a metre away) most of the
 *   panel is in reach and the grid gains only ~2x. eval is const and thread-safe; the add and build
 *   calls are not.
 *   Directional points (Sec. 4.2.3) act only on p with (p − s)·dir ≥ 0.
 *   Queries with a NaN coordinate return NaN.
 *
 * ON THE METRIC HOOK (Sec. 4.1.2)
 *   eval_metric returns R diag(1/min(r_warp, r_v)², 1/min(r_weft, r_v)²) Rᵀ where (r_warp, r_weft,
 *   grain angle) come from the region callback (or r_f, r_f, 0 without one) and r_v is the scalar map:
 *   isotropic sources refine both directions, and r_f caps everything (set it to the coarsest
 *   direction's resolution). The anisotropic sampling itself lives elsewhere.
 *
 * MEMORY: wr_sizing_create allocates; wr_sizing_free releases (NULL is fine).
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
 * on the light side: validation/validate_curtain finds 4x T lengthening the transition by 0-5 %, not
 * 2x, and even a tension-dominated one (42x T) only 1.6x, not 6.5x. Style3D writes both forms with
 * "~" and gives no O(1) prefactor. */
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

/* ---- sizing map ------------------------------------------------------------------------- */
typedef struct wr_sizing wr_sizing;

/* Options for wr_sizing_build. Zero means default:
 *   cell_size   grid cell edge [m]; 0 → automatic (about one segment per cell)
 *   max_cells   cap on nx·ny and on stored cell entries; 0 → 1 << 22 */
typedef struct wr_sizing_desc {
    double cell_size;
    int32_t max_cells;
} wr_sizing_desc;

/* Region callback for the metric hook: return nonzero and fill the three outputs when (x, y) lies in
 * an anisotropic region (r_warp, r_weft [m] > 0, grain angle [rad] of the warp direction). */
typedef int (*wr_sizing_region_fn)(void *user, double x, double y, double *r_warp, double *r_weft,
                                   double *grain_angle);

/* r_f [m] finite and > 0: the fabric resolution, the map's upper bound. desc may be NULL. */
WRDEF wr_status wr_sizing_create(double r_f, const wr_sizing_desc *desc, wr_sizing **out, wr_diag *diag);
WRDEF void wr_sizing_free(wr_sizing *s);
WRDEF wr_status wr_sizing_add_point(wr_sizing *s, double x, double y, const wr_transition *t, wr_diag *diag);
/* Only points p with (p - (x, y))·(dir_x, dir_y) ≥ 0 see this source; dir must be nonzero. */
WRDEF wr_status wr_sizing_add_point_directional(wr_sizing *s, double x, double y, double dir_x, double dir_y,
                                                const wr_transition *t, wr_diag *diag);
/* xy[2n] = x0 y0 x1 y1 ...; n ≥ 1 (n = 1 is a point). diag->item names a bad coordinate's point
 * (WR_ERR_INVALID_ARG), or a segment whose squared length overflows a double (WR_ERR_DOMAIN). */
WRDEF wr_status wr_sizing_add_polyline(wr_sizing *s, const double *xy, int32_t n, const wr_transition *t,
                                       wr_diag *diag);
/* Build (or rebuild) the grid index. Adding sources afterwards invalidates it until the next build;
 * eval then scans every source. Errors leave the map unbuilt but usable (eval scans every source):
 * more active segments than desc.max_cells (WR_ERR_BUDGET: each needs one cell entry), a source
 * extent that overflows a double (WR_ERR_DOMAIN), WR_ERR_NOMEM. */
WRDEF wr_status wr_sizing_build(wr_sizing *s, wr_diag *diag);
WRDEF double wr_sizing_eval(const wr_sizing *s, double x, double y);
WRDEF double wr_sizing_eval_brute(const wr_sizing *s, double x, double y);
/* Gradient of the active term (zero where r_f is active or on a source itself, where it is undefined). */
WRDEF void wr_sizing_eval_gradient(const wr_sizing *s, double x, double y, double *r, double grad[2]);
WRDEF void wr_sizing_set_region_fn(wr_sizing *s, wr_sizing_region_fn fn, void *user);
WRDEF wr_mat2 wr_sizing_eval_metric(const wr_sizing *s, double x, double y);
/* Counts: stored segments (points count as one) and whether the index is current. */
WRDEF int32_t wr_sizing_segment_count(const wr_sizing *s);
WRDEF int wr_sizing_is_built(const wr_sizing *s);

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

/* Relative safety margin of the grid's early-out bounds: a bound must exceed the running minimum by
 * this much before cells are skipped, so rounding in pow() can never drop a winning term. */
#define WR__SZ_BOUND_MARGIN 1e-12
/* A source's reach (distance where its term reaches r_f) is widened by this relative margin [1] so
 * that the pow() round-off of the reach formula never drops a term the scan would keep. */
#define WR__SZ_REACH_MARGIN 1e-9
/* Up to this many source groups the ring lower bound is evaluated per group (exact); above it a
 * conservative O(1) bound from the extreme parameters is used. */
#define WR__SZ_EXACT_LB_GROUPS 32
#define WR__SZ_DEFAULT_MAX_CELLS (1 << 22)
/* Budget (transition evaluations) for the per-ring lower-bound table built by wr_sizing_build. */
#define WR__SZ_LB_TABLE_WORK (1 << 22)

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

/* ---- sizing map ------------------------------------------------------------------------- */

typedef struct wr__sz_group {
    wr_transition t;
    double reach; /* distance beyond which this group's terms are >= r_f (with margin) */
} wr__sz_group;

typedef struct wr__sz_seg {
    double ax, ay, bx, by;
    double dx, dy;        /* direction of a directional point source; (0,0) otherwise */
    double inv_ee, inv_len; /* 1/|b-a|² and 1/|b-a| (0 for a point): no divisions per query */
    int32_t group;
} wr__sz_seg;

struct wr_sizing {
    double r_f;
    wr_sizing_desc desc;
    wr__sz_group *groups;
    int32_t n_groups, cap_groups;
    wr__sz_seg *segs;
    int32_t n_segs, cap_segs;
    /* grid index over the segments of active groups (r < r_f) */
    int built;
    double x0, y0, h;
    int32_t nx, ny;
    int32_t *cell_start; /* nx*ny + 1 */
    int32_t *cell_items; /* segment indices */
    int32_t n_active_groups;
    double lb_r_min, lb_L_max, lb_m_min, lb_m_max, reach_max;
    double *lb_table; /* lb_table[j] = min over active sources of r_g(j h), j < n_lb: ring bounds */
    int32_t n_lb;
    wr_sizing_region_fn region_fn;
    void *region_user;
};

WRDEF wr_status wr_sizing_create(double r_f, const wr_sizing_desc *desc, wr_sizing **out, wr_diag *diag) {
    wr_sizing *s;
    if (!out) return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "sizing: NULL output");
    *out = NULL;
    if (!wr__tr_pos(r_f))
        return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "sizing: fabric resolution r_f=%g m must be finite and > 0", r_f);
    if (desc && (!(desc->cell_size >= 0.0) || !isfinite(desc->cell_size) || desc->max_cells < 0))
        return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "sizing: bad desc (cell_size=%g, max_cells=%d)", desc->cell_size,
                       (int)desc->max_cells);
    s = (wr_sizing *)wr_calloc_array(1, sizeof(wr_sizing));
    if (!s) return wr_fail(diag, WR_ERR_NOMEM, -1, "sizing: out of memory");
    s->r_f = r_f;
    if (desc) s->desc = *desc;
    if (s->desc.max_cells == 0) s->desc.max_cells = WR__SZ_DEFAULT_MAX_CELLS;
    *out = s;
    return WR_OK;
}

static void wr__sz_drop_index(wr_sizing *s) {
    wr_free(s->cell_start);
    wr_free(s->cell_items);
    wr_free(s->lb_table);
    s->cell_start = s->cell_items = NULL;
    s->lb_table = NULL;
    s->n_lb = 0;
    s->built = 0;
}

WRDEF void wr_sizing_free(wr_sizing *s) {
    if (!s) return;
    wr__sz_drop_index(s);
    wr_free(s->groups);
    wr_free(s->segs);
    wr_free(s);
}

static wr_status wr__sz_check_transition(const wr_transition *t, wr_diag *diag) {
    if (!t) return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "sizing: NULL transition");
    if (!wr__tr_pos(t->r) || !wr__tr_pos(t->L_w) || !wr__tr_pos(t->m))
        return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "sizing: invalid transition (r=%g m, L_w=%g m, m=%g)", t->r,
                       t->L_w, t->m);
    return WR_OK;
}

static wr_status wr__sz_add_group(wr_sizing *s, const wr_transition *t, int32_t extra_segs, wr_diag *diag) {
    if (s->n_groups == s->cap_groups) {
        int32_t nc = s->cap_groups ? 2 * s->cap_groups : 8;
        wr__sz_group *g = (wr__sz_group *)wr_realloc_array(s->groups, (size_t)nc, sizeof(wr__sz_group));
        if (!g || nc < 0) return wr_fail(diag, WR_ERR_NOMEM, -1, "sizing: out of memory (groups)");
        s->groups = g;
        s->cap_groups = nc;
    }
    if (extra_segs > INT32_MAX - s->n_segs) return wr_fail(diag, WR_ERR_OVERFLOW, -1, "sizing: too many segments");
    if (s->n_segs + extra_segs > s->cap_segs) {
        int32_t nc = s->cap_segs ? s->cap_segs : 16;
        wr__sz_seg *g;
        while (nc < s->n_segs + extra_segs) nc = nc > INT32_MAX / 2 ? INT32_MAX : 2 * nc;
        g = (wr__sz_seg *)wr_realloc_array(s->segs, (size_t)nc, sizeof(wr__sz_seg));
        if (!g) return wr_fail(diag, WR_ERR_NOMEM, -1, "sizing: out of memory (segments)");
        s->segs = g;
        s->cap_segs = nc;
    }
    s->groups[s->n_groups].t = *t;
    /* r (1 + (x/L)^m) >= r_f  ⇔  x >= L ((r_f - r)/r)^{1/m}; widened by the margin. */
    if (t->r >= s->r_f)
        s->groups[s->n_groups].reach = -1.0; /* never active */
    else
        s->groups[s->n_groups].reach =
            t->L_w * pow((s->r_f - t->r) / t->r, 1.0 / t->m) * (1.0 + WR__SZ_REACH_MARGIN) + 1e-300;
    s->n_groups++;
    wr__sz_drop_index(s);
    return WR_OK;
}

static void wr__sz_push_seg(wr_sizing *s, double ax, double ay, double bx, double by, double dx, double dy) {
    wr__sz_seg *g = &s->segs[s->n_segs++];
    g->ax = ax;
    g->ay = ay;
    g->bx = bx;
    g->by = by;
    g->dx = dx;
    g->dy = dy;
    {
        double ee = (bx - ax) * (bx - ax) + (by - ay) * (by - ay);
        g->inv_ee = ee > 0.0 ? 1.0 / ee : 0.0;
        g->inv_len = ee > 0.0 ? 1.0 / sqrt(ee) : 0.0;
    }
    g->group = s->n_groups - 1;
}

WRDEF wr_status wr_sizing_add_point(wr_sizing *s, double x, double y, const wr_transition *t, wr_diag *diag) {
    wr_status st;
    if (!s) return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "sizing: NULL object");
    if (!isfinite(x) || !isfinite(y))
        return wr_fail(diag, WR_ERR_INVALID_ARG, 0, "sizing: point (%g, %g) not finite", x, y);
    st = wr__sz_check_transition(t, diag);
    if (st != WR_OK) return st;
    st = wr__sz_add_group(s, t, 1, diag);
    if (st != WR_OK) return st;
    wr__sz_push_seg(s, x, y, x, y, 0.0, 0.0);
    return WR_OK;
}

WRDEF wr_status wr_sizing_add_point_directional(wr_sizing *s, double x, double y, double dir_x, double dir_y,
                                                const wr_transition *t, wr_diag *diag) {
    wr_status st;
    if (!s) return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "sizing: NULL object");
    if (!isfinite(x) || !isfinite(y))
        return wr_fail(diag, WR_ERR_INVALID_ARG, 0, "sizing: point (%g, %g) not finite", x, y);
    if (!isfinite(dir_x) || !isfinite(dir_y) || (dir_x == 0.0 && dir_y == 0.0))
        return wr_fail(diag, WR_ERR_INVALID_ARG, 0, "sizing: direction (%g, %g) must be finite and nonzero", dir_x,
                       dir_y);
    st = wr__sz_check_transition(t, diag);
    if (st != WR_OK) return st;
    st = wr__sz_add_group(s, t, 1, diag);
    if (st != WR_OK) return st;
    wr__sz_push_seg(s, x, y, x, y, dir_x, dir_y);
    return WR_OK;
}

WRDEF wr_status wr_sizing_add_polyline(wr_sizing *s, const double *xy, int32_t n, const wr_transition *t,
                                       wr_diag *diag) {
    wr_status st;
    int32_t i;
    if (!s || !xy) return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "sizing: NULL argument");
    if (n < 1) return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "sizing: polyline needs >= 1 point, got %d", (int)n);
    for (i = 0; i < n; ++i)
        if (!isfinite(xy[2 * i]) || !isfinite(xy[2 * i + 1]))
            return wr_fail(diag, WR_ERR_INVALID_ARG, i, "sizing: polyline point %d (%g, %g) not finite", (int)i,
                           xy[2 * i], xy[2 * i + 1]);
    /* |b - a|² must be finite or the projection in wr__sz_seg_dist degenerates (inv_ee = 0). */
    for (i = 0; i + 1 < n; ++i) {
        double ex = xy[2 * i + 2] - xy[2 * i], ey = xy[2 * i + 3] - xy[2 * i + 1];
        if (!isfinite(ex * ex + ey * ey))
            return wr_fail(diag, WR_ERR_DOMAIN, i, "sizing: polyline segment %d is too long (%g, %g) m to measure",
                           (int)i, ex, ey);
    }
    st = wr__sz_check_transition(t, diag);
    if (st != WR_OK) return st;
    st = wr__sz_add_group(s, t, n > 1 ? n - 1 : 1, diag);
    if (st != WR_OK) return st;
    if (n == 1)
        wr__sz_push_seg(s, xy[0], xy[1], xy[0], xy[1], 0.0, 0.0);
    else
        for (i = 0; i + 1 < n; ++i) wr__sz_push_seg(s, xy[2 * i], xy[2 * i + 1], xy[2 * i + 2], xy[2 * i + 3], 0.0, 0.0);
    return WR_OK;
}

/* Distance from p to segment g, and the closest point. */
static double wr__sz_seg_dist(const wr__sz_seg *g, double px, double py, double *cx, double *cy) {
    double ex = g->bx - g->ax, ey = g->by - g->ay;
    double tt = 0.0, qx, qy;
    if (g->inv_ee > 0.0) {
        tt = ((px - g->ax) * ex + (py - g->ay) * ey) * g->inv_ee;
        tt = tt < 0.0 ? 0.0 : (tt > 1.0 ? 1.0 : tt);
    }
    qx = g->ax + tt * ex;
    qy = g->ay + tt * ey;
    if (cx) *cx = qx;
    if (cy) *cy = qy;
    /* Interior projection: the cross-product form is exact (0) for points on the segment's line,
     * which matters because x^m with m < 1 amplifies a 1e-17 distance error to ~1e-5 relative. */
    if (tt > 0.0 && tt < 1.0) return fabs(ex * (py - g->ay) - ey * (px - g->ax)) * g->inv_len;
    /* sqrt rather than hypot: coordinates are metres, far from overflow, and hypot is ~5x slower */
    return sqrt((px - qx) * (px - qx) + (py - qy) * (py - qy));
}

/* Scan segments (items[0..n) in increasing index order, or 0..n-1 when items is NULL) and lower *best
 * with their terms. Segments of one source are contiguous, so the scan keeps the smallest distance
 * per run of one source and evaluates the transition (the pow) once per run: terms increase with
 * distance, so r_g(min d) = min r_g(d). Both the brute-force and the grid path use exactly this
 * routine, so they agree bit for bit. Directional points skip p behind them; distances beyond a
 * source's reach cannot beat r_f and are dropped. */
static void wr__sz_flush(const wr_sizing *s, int32_t g, double dmin, int32_t darg, double *best, int32_t *arg) {
    double v;
    if (g < 0 || darg < 0 || dmin > s->groups[g].reach) return;
    v = wr_transition_eval(&s->groups[g].t, dmin);
    if (v < *best) {
        *best = v;
        *arg = darg;
    }
}

static void wr__sz_scan(const wr_sizing *s, const int32_t *items, int32_t n, double px, double py, double *best,
                        int32_t *arg) {
    int32_t k, cur = -1, darg = -1;
    double dmin = INFINITY;
    for (k = 0; k < n; ++k) {
        int32_t i = items ? items[k] : k;
        const wr__sz_seg *g = &s->segs[i];
        double d;
        if (g->group != cur) {
            wr__sz_flush(s, cur, dmin, darg, best, arg);
            cur = g->group;
            dmin = INFINITY;
            darg = -1;
        }
        if (s->groups[cur].reach < 0.0) continue;
        if ((g->dx != 0.0 || g->dy != 0.0) && (px - g->ax) * g->dx + (py - g->ay) * g->dy < 0.0) continue;
        d = wr__sz_seg_dist(g, px, py, NULL, NULL);
        if (d < dmin) {
            dmin = d;
            darg = i;
        }
    }
    wr__sz_flush(s, cur, dmin, darg, best, arg);
}

static double wr__sz_brute(const wr_sizing *s, double px, double py, int32_t *arg) {
    double best = s->r_f;
    *arg = -1;
    wr__sz_scan(s, NULL, s->n_segs, px, py, &best, arg);
    return best;
}

WRDEF wr_status wr_sizing_build(wr_sizing *s, wr_diag *diag) {
    double xmin = INFINITY, ymin = INFINITY, xmax = -INFINITY, ymax = -INFINITY, W, H, h;
    int32_t i, n_act = 0, nx = 1, ny = 1;
    size_t total = 0;
    int32_t *start = NULL, *items = NULL, *fill = NULL;
    if (!s) return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "sizing: NULL object");
    wr__sz_drop_index(s);
    s->n_active_groups = 0;
    s->lb_r_min = INFINITY;
    s->lb_L_max = 0.0;
    s->lb_m_min = INFINITY;
    s->lb_m_max = 0.0;
    s->reach_max = 0.0;
    for (i = 0; i < s->n_groups; ++i) {
        const wr__sz_group *g = &s->groups[i];
        if (g->reach < 0.0) continue;
        s->n_active_groups++;
        s->lb_r_min = fmin(s->lb_r_min, g->t.r);
        s->lb_L_max = fmax(s->lb_L_max, g->t.L_w);
        s->lb_m_min = fmin(s->lb_m_min, g->t.m);
        s->lb_m_max = fmax(s->lb_m_max, g->t.m);
        s->reach_max = fmax(s->reach_max, g->reach);
    }
    for (i = 0; i < s->n_segs; ++i) {
        const wr__sz_seg *g = &s->segs[i];
        if (s->groups[g->group].reach < 0.0) continue;
        n_act++;
        xmin = fmin(xmin, fmin(g->ax, g->bx));
        xmax = fmax(xmax, fmax(g->ax, g->bx));
        ymin = fmin(ymin, fmin(g->ay, g->by));
        ymax = fmax(ymax, fmax(g->ay, g->by));
    }
    if (n_act == 0) { /* nothing can refine r_f: an empty 1×1 grid */
        xmin = ymin = 0.0;
        xmax = ymax = 1.0;
    }
    W = xmax - xmin;
    H = ymax - ymin;
    /* Finite coordinates can still span more than DBL_MAX; no cell size would be finite then. */
    if (!isfinite(W) || !isfinite(H))
        return wr_fail(diag, WR_ERR_DOMAIN, -1, "sizing: source extent [%g, %g] x [%g, %g] m overflows a double", xmin,
                       xmax, ymin, ymax);
    /* Every active segment takes at least one cell entry, so no cell size can fit a smaller cap. */
    if (n_act > s->desc.max_cells)
        return wr_fail(diag, WR_ERR_BUDGET, -1, "sizing: %d active segments exceed max_cells = %d (raise the cap)",
                       (int)n_act, (int)s->desc.max_cells);
    if (s->desc.cell_size > 0.0)
        h = s->desc.cell_size;
    else if (W > 0.0 && H > 0.0)
        h = sqrt(W * H / (double)(n_act > 0 ? n_act : 1));
    else if (W > 0.0 || H > 0.0)
        h = fmax(W, H) / (double)(n_act > 0 ? n_act : 1);
    else
        h = s->reach_max > 0.0 ? s->reach_max : 1.0;
    if (!(h > 0.0) || !isfinite(h)) h = fmax(fmax(W, H), 1e-6);
    /* Grow h until both the cell count and the stored entries fit the cap. */
    for (;;) {
        double fnx = floor(W / h) + 1.0, fny = floor(H / h) + 1.0;
        if (fnx * fny <= (double)s->desc.max_cells) {
            nx = (int32_t)fnx;
            ny = (int32_t)fny;
            total = 0;
            for (i = 0; i < s->n_segs; ++i) {
                const wr__sz_seg *g = &s->segs[i];
                double cx0, cx1, cy0, cy1;
                if (s->groups[g->group].reach < 0.0) continue;
                cx0 = floor((fmin(g->ax, g->bx) - xmin) / h);
                cx1 = floor((fmax(g->ax, g->bx) - xmin) / h);
                cy0 = floor((fmin(g->ay, g->by) - ymin) / h);
                cy1 = floor((fmax(g->ay, g->by) - ymin) / h);
                total += (size_t)((cx1 - cx0 + 1.0) * (cy1 - cy0 + 1.0));
                if (total > (size_t)s->desc.max_cells) break;
            }
            if (total <= (size_t)s->desc.max_cells) break;
        }
        h *= 2.0;
    }
    start = (int32_t *)wr_calloc_array((size_t)nx * (size_t)ny + 1, sizeof(int32_t));
    fill = (int32_t *)wr_calloc_array((size_t)nx * (size_t)ny, sizeof(int32_t));
    items = (int32_t *)wr_alloc_array(total, sizeof(int32_t));
    if (!start || !fill || !items) {
        wr_free(start);
        wr_free(fill);
        wr_free(items);
        return wr_fail(diag, WR_ERR_NOMEM, -1, "sizing: out of memory for a %dx%d grid", (int)nx, (int)ny);
    }
    /* Two passes: count per cell, prefix sum, then fill (CSR layout). */
    {
        int pass;
        for (pass = 0; pass < 2; ++pass) {
            for (i = 0; i < s->n_segs; ++i) {
                const wr__sz_seg *g = &s->segs[i];
                int32_t x0, x1, y0, y1, a, b;
                if (s->groups[g->group].reach < 0.0) continue;
                x0 = (int32_t)floor((fmin(g->ax, g->bx) - xmin) / h);
                x1 = (int32_t)floor((fmax(g->ax, g->bx) - xmin) / h);
                y0 = (int32_t)floor((fmin(g->ay, g->by) - ymin) / h);
                y1 = (int32_t)floor((fmax(g->ay, g->by) - ymin) / h);
                if (x1 > nx - 1) x1 = nx - 1;
                if (y1 > ny - 1) y1 = ny - 1;
                for (b = y0; b <= y1; ++b)
                    for (a = x0; a <= x1; ++a) {
                        size_t c = (size_t)b * (size_t)nx + (size_t)a;
                        if (pass == 0)
                            start[c + 1]++;
                        else
                            items[start[c] + fill[c]++] = i;
                    }
            }
            if (pass == 0) {
                size_t c;
                for (c = 0; c < (size_t)nx * (size_t)ny; ++c) start[c + 1] += start[c];
            }
        }
    }
    wr_free(fill);
    s->x0 = xmin;
    s->y0 = ymin;
    s->h = h;
    s->nx = nx;
    s->ny = ny;
    s->cell_start = start;
    s->cell_items = items;
    /* Ring lower-bound table: LB(D) >= lb_table[floor(D/h)] because every term grows with distance.
     * Costs n_active_groups pows per entry; capped so huge point sets fall back to the O(1) bound. */
    {
        int32_t nlb = (nx > ny ? nx : ny) + 2, j;
        if (s->n_active_groups > 0 && (double)nlb * (double)s->n_active_groups <= (double)WR__SZ_LB_TABLE_WORK) {
            s->lb_table = (double *)wr_alloc_array((size_t)nlb, sizeof(double));
            if (s->lb_table) {
                for (j = 0; j < nlb; ++j) {
                    double lb = INFINITY, D = (double)j * h;
                    for (i = 0; i < s->n_groups; ++i)
                        if (s->groups[i].reach >= 0.0) lb = fmin(lb, wr_transition_eval(&s->groups[i].t, D));
                    s->lb_table[j] = lb;
                }
                s->n_lb = nlb;
            } /* allocation failure only loses the speed-up */
        }
    }
    s->built = 1;
    return WR_OK;
}

/* Lower bound of every term at distance >= D. */
static double wr__sz_lower_bound(const wr_sizing *s, double D) {
    double j = floor(D / s->h);
    if (j < (double)s->n_lb) return s->lb_table[(int32_t)j];
    if (s->n_active_groups <= WR__SZ_EXACT_LB_GROUPS) {
        double lb = INFINITY;
        int32_t i;
        for (i = 0; i < s->n_groups; ++i)
            if (s->groups[i].reach >= 0.0) lb = fmin(lb, wr_transition_eval(&s->groups[i].t, D));
        return lb;
    } else {
        /* r_g >= r_min, L_g <= L_max ⇒ (D/L_g)^{m_g} >= q^{m} with q = D/L_max and the exponent that
         * makes q^m smallest (the largest when q < 1, the smallest when q >= 1). */
        double q = D / s->lb_L_max;
        return s->lb_r_min * (1.0 + pow(q, q < 1.0 ? s->lb_m_max : s->lb_m_min));
    }
}

static void wr__sz_visit_cell(const wr_sizing *s, int32_t a, int32_t b, double px, double py, double *best,
                              int32_t *arg) {
    size_t c = (size_t)b * (size_t)s->nx + (size_t)a;
    /* cell lists are filled in increasing segment order, as wr__sz_scan needs */
    wr__sz_scan(s, s->cell_items + s->cell_start[c], s->cell_start[c + 1] - s->cell_start[c], px, py, best, arg);
}

static double wr__sz_query(const wr_sizing *s, double px, double py, int32_t *arg) {
    double best = s->r_f, fx, fy;
    int32_t cx, cy, k, k0, kmax, nx, ny;
    *arg = -1;
    if (isnan(px) || isnan(py)) return NAN;
    if (!s->built) return wr__sz_brute(s, px, py, arg);
    if (s->n_active_groups == 0) return best;
    nx = s->nx;
    ny = s->ny;
    /* Cell of p, clamped far outside the grid so the int conversion is defined. */
    fx = floor((px - s->x0) / s->h);
    fy = floor((py - s->y0) / s->h);
    fx = fmax(-1e9, fmin(1e9, fx));
    fy = fmax(-1e9, fmin(1e9, fy));
    cx = (int32_t)fx;
    cy = (int32_t)fy;
    /* Rings before k0 lie entirely outside the grid; after kmax every cell has been seen. */
    k0 = 0;
    if (cx - (nx - 1) > k0) k0 = cx - (nx - 1);
    if (-cx > k0) k0 = -cx;
    if (cy - (ny - 1) > k0) k0 = cy - (ny - 1);
    if (-cy > k0) k0 = -cy;
    kmax = cx;
    if (nx - 1 - cx > kmax) kmax = nx - 1 - cx;
    if (cy > kmax) kmax = cy;
    if (ny - 1 - cy > kmax) kmax = ny - 1 - cy;
    for (k = k0; k <= kmax; ++k) {
        int32_t a, b, a0, a1, b0, b1;
        if (k > 0) {
            /* Unvisited segments lie outside the block of rings < k: distance >= D from p. */
            double xlo = s->x0 + (double)(cx - k + 1) * s->h, xhi = s->x0 + (double)(cx + k) * s->h;
            double ylo = s->y0 + (double)(cy - k + 1) * s->h, yhi = s->y0 + (double)(cy + k) * s->h;
            double D = fmin(fmin(px - xlo, xhi - px), fmin(py - ylo, yhi - py));
            if (D > 0.0) {
                if (D > s->reach_max) break; /* every remaining term >= r_f >= best */
                if (wr__sz_lower_bound(s, D) > best * (1.0 + WR__SZ_BOUND_MARGIN)) break;
            }
        }
        a0 = cx - k < 0 ? 0 : cx - k;
        a1 = cx + k > nx - 1 ? nx - 1 : cx + k;
        b0 = cy - k < 0 ? 0 : cy - k;
        b1 = cy + k > ny - 1 ? ny - 1 : cy + k;
        if (k == 0) {
            if (cx >= 0 && cx < nx && cy >= 0 && cy < ny) wr__sz_visit_cell(s, cx, cy, px, py, &best, arg);
            continue;
        }
        if (cy - k >= 0)
            for (a = a0; a <= a1; ++a) wr__sz_visit_cell(s, a, cy - k, px, py, &best, arg);
        if (cy + k <= ny - 1)
            for (a = a0; a <= a1; ++a) wr__sz_visit_cell(s, a, cy + k, px, py, &best, arg);
        if (b0 < cy - k + 1) b0 = cy - k + 1;
        if (b1 > cy + k - 1) b1 = cy + k - 1;
        if (cx - k >= 0)
            for (b = b0; b <= b1; ++b) wr__sz_visit_cell(s, cx - k, b, px, py, &best, arg);
        if (cx + k <= nx - 1)
            for (b = b0; b <= b1; ++b) wr__sz_visit_cell(s, cx + k, b, px, py, &best, arg);
    }
    return best;
}

WRDEF double wr_sizing_eval(const wr_sizing *s, double x, double y) {
    int32_t arg;
    return wr__sz_query(s, x, y, &arg);
}

WRDEF double wr_sizing_eval_brute(const wr_sizing *s, double x, double y) {
    int32_t arg;
    if (isnan(x) || isnan(y)) return NAN;
    return wr__sz_brute(s, x, y, &arg);
}

WRDEF void wr_sizing_eval_gradient(const wr_sizing *s, double x, double y, double *r, double grad[2]) {
    int32_t arg;
    double v = wr__sz_query(s, x, y, &arg);
    if (r) *r = v;
    grad[0] = grad[1] = 0.0;
    if (arg >= 0) {
        double qx, qy, d = wr__sz_seg_dist(&s->segs[arg], x, y, &qx, &qy);
        if (d > 0.0) {
            double sl = wr_transition_slope(&s->groups[s->segs[arg].group].t, d);
            grad[0] = sl * (x - qx) / d;
            grad[1] = sl * (y - qy) / d;
        }
    }
}

WRDEF void wr_sizing_set_region_fn(wr_sizing *s, wr_sizing_region_fn fn, void *user) {
    s->region_fn = fn;
    s->region_user = user;
}

WRDEF wr_mat2 wr_sizing_eval_metric(const wr_sizing *s, double x, double y) {
    double rv = wr_sizing_eval(s, x, y), rw = s->r_f, rf = s->r_f, ang = 0.0;
    if (s->region_fn) {
        double a, b, g;
        if (s->region_fn(s->region_user, x, y, &a, &b, &g)) {
            rw = a;
            rf = b;
            ang = g;
        }
    }
    return wr_resolution_metric(fmin(rw, rv), fmin(rf, rv), ang);
}

WRDEF int32_t wr_sizing_segment_count(const wr_sizing *s) { return s->n_segs; }
WRDEF int wr_sizing_is_built(const wr_sizing *s) { return s->built; }

#ifdef __cplusplus
}
#endif
#endif /* WRINKLE_TRANSITION_IMPLEMENTATION_DONE */
#endif /* WRINKLE_IMPLEMENTATION */
