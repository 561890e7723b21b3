/* validation/elastica_ref.h — reference solution of the planar heavy elastica for the cantilever
 * validation of the resolution paper (Style3D Fig. 18a–c: a fabric strip clamped horizontally at one
 * end, sagging under its own weight; the converged drape shape and tip deflection are the "ground
 * truth" the mesh-resolution sweep is compared with).
 *
 * NOT part of the wrinkle library: GSL stays out of include/wrinkle/. Every function here is static
 * and meant for the validation drivers (and tests/test_elastica_ref.c) only.
 * Needs GSL: -lgsl -lgslcblas (Debian: libgsl-dev). elastica_ref_solve calls gsl_set_error_handler_off()
 * (GSL's default handler aborts the process) and checks every GSL status; note that this changes a
 * process-wide GSL setting. Not thread-safe for the same reason.
 *
 * MODEL
 *   Inextensible, unshearable strip of length L [m], width b [m], clamped horizontally at s = 0, free
 *   at s = L, under its weight q = ρ_A·g·b [N/m] (ρ_A areal density [kg/m²]) and optionally a vertical
 *   tip load P [N]. Bending stiffness per unit width B [N·m] (Style3D's B), so the strip's flexural
 *   rigidity is D = B·b [N·m²]. φ(s) is the angle of the tangent BELOW the horizontal. Moment balance
 *   of the part beyond s about the point s, differentiated once:
 *       D φ''(s) + (q·(L − s) + P)·cos φ(s) = 0,   φ(0) = 0 (clamp),   φ'(L) = 0 (free end, no moment)
 *       x'(s) = cos φ,  y'(s) = −sin φ        (y up; the tip deflection is δ = −y(L) > 0)
 *   Per unit width (divide by b): B φ'' + (ρ_A g (L − s) + P/b) cos φ = 0 — the equation of the brief.
 *   Dimensionless: σ = s/L, κ = q L³/D = ρ_A g L³/B (self-weight), β = P L²/D (tip load):
 *       φ'' = −(κ (1 − σ) + β) cos φ.
 *   Small loads: φ ≈ κ(σ − σ² + σ³/3)/2 + β(σ − σ²/2) gives the beam formulas δ = qL⁴/(8D) + PL³/(3D).
 *
 * METHOD
 *   Shooting on a = φ'(0) (dimensionless): integrate (φ, φ', X, Y) over σ ∈ [0, 1] with GSL's
 *   gsl_odeiv2 rk8pd (Prince–Dormand 8(9)), abs/rel tolerance ELASTICA_ODE_TOL, and solve
 *   R(a) = φ'(1; a) = 0 with gsl_root_fsolver_brent. Bracket: since |cos φ| <= 1,
 *   R(κ/2 + β) >= 0; the lower end is found by scanning [0, κ/2 + β] (R(0) < 0 for every load that
 *   keeps φ < π/2, which the horizontal clamp does). The converged shape is checked: φ must stay in
 *   [0, π/2] (the physical branch).
 *
 * API
 *   elastica_ref_solve(L, D, q, P, n, x, y, phi, &res, err, errlen)
 *       x, y, phi: n >= 2 samples at s_i = L·i/(n−1) (each may be NULL). Returns 0 on success, −1 on
 *       bad input or non-convergence with a message in err.
 *   elastica_ref_result: tip x/y, tip deflection δ, tip angle, clamp curvature φ'(0) [1/m],
 *       κ, β, shooting iterations, final residual.
 */
#ifndef WRINKLE_VALIDATION_ELASTICA_REF_H
#define WRINKLE_VALIDATION_ELASTICA_REF_H

#include <gsl/gsl_errno.h>
#include <gsl/gsl_odeiv2.h>
#include <gsl/gsl_roots.h>
#include <math.h>
#include <stdio.h>

/* rk8pd absolute and relative tolerance on (φ, φ', X, Y), dimensionless. 1e-12 leaves the shooting
 * residual, not the ODE, as the accuracy limit while costing < 1 ms per integration. */
#define ELASTICA_ODE_TOL 1e-12
/* Brent stops when the bracket on a = φ'(0) is below this (absolute, dimensionless) + 1e-14·|a|. */
#define ELASTICA_SHOOT_TOL 1e-13
#define ELASTICA_MAX_ITER 200
/* Sub-intervals used to scan for the lower end of the bracket. */
#define ELASTICA_SCAN 32
#define ELASTICA_PI 3.14159265358979323846

typedef struct elastica_ref_result {
    double tip_x, tip_y;    /* tip position [m], clamp at the origin, y up */
    double tip_deflection;  /* δ = −tip_y [m] */
    double tip_angle;       /* φ(L) [rad] below the horizontal */
    double clamp_curvature; /* φ'(0) [1/m] */
    double kappa, beta;     /* q L³/D and P L²/D */
    int iterations;         /* Brent iterations */
    double residual;        /* |φ'(1)| at the solution (dimensionless) */
} elastica_ref_result;

typedef struct elastica__params {
    double kappa, beta;
} elastica__params;

static int elastica__rhs(double t, const double z[], double dz[], void *vp) {
    const elastica__params *p = (const elastica__params *)vp;
    dz[0] = z[1];
    dz[1] = -(p->kappa * (1.0 - t) + p->beta) * cos(z[0]);
    dz[2] = cos(z[0]);
    dz[3] = sin(z[0]); /* downward deflection, positive */
    return GSL_SUCCESS;
}

/* Integrate from σ = 0 with φ'(0) = a. If n >= 2 and out arrays are given, store the samples at
 * σ_i = i/(n−1). z_end receives the state at σ = 1. Returns a GSL status. */
static int elastica__shoot(const elastica__params *p, double a, int n, double *phi_out, double *X_out, double *Y_out,
                           double z_end[4]) {
    gsl_odeiv2_system sys;
    gsl_odeiv2_driver *drv;
    double z[4], t = 0.0;
    int i, st = GSL_SUCCESS, m = n >= 2 ? n : 2;
    sys.function = elastica__rhs;
    sys.jacobian = NULL;
    sys.dimension = 4;
    sys.params = (void *)p;
    drv = gsl_odeiv2_driver_alloc_y_new(&sys, gsl_odeiv2_step_rk8pd, 1e-3, ELASTICA_ODE_TOL, ELASTICA_ODE_TOL);
    if (!drv) return GSL_ENOMEM;
    z[0] = 0.0;
    z[1] = a;
    z[2] = 0.0;
    z[3] = 0.0;
    if (phi_out) phi_out[0] = 0.0;
    if (X_out) X_out[0] = 0.0;
    if (Y_out) Y_out[0] = 0.0;
    for (i = 1; i < m && st == GSL_SUCCESS; ++i) {
        double ti = (double)i / (double)(m - 1);
        st = gsl_odeiv2_driver_apply(drv, &t, ti, z);
        if (n >= 2) {
            if (phi_out) phi_out[i] = z[0];
            if (X_out) X_out[i] = z[2];
            if (Y_out) Y_out[i] = z[3];
        }
    }
    gsl_odeiv2_driver_free(drv);
    for (i = 0; i < 4; ++i) z_end[i] = z[i];
    return st;
}

typedef struct elastica__root_ctx {
    elastica__params p;
    int failed;
} elastica__root_ctx;

static double elastica__residual(double a, void *vp) {
    elastica__root_ctx *c = (elastica__root_ctx *)vp;
    double z[4];
    if (elastica__shoot(&c->p, a, 0, NULL, NULL, NULL, z) != GSL_SUCCESS) {
        c->failed = 1;
        return GSL_NAN;
    }
    return z[1];
}

static int elastica_ref_solve(double L, double D, double q, double P, int n, double *x, double *y, double *phi,
                              elastica_ref_result *res, char *err, size_t errlen) {
    elastica__root_ctx ctx;
    gsl_function F;
    gsl_root_fsolver *solver;
    double lo, hi, flo, fhi, a = 0.0, z[4];
    int it = 0, st, i;
    gsl_set_error_handler_off();
    if (!(L > 0.0) || !(D > 0.0) || !(q >= 0.0) || !(P >= 0.0) || !isfinite(L) || !isfinite(D) || !isfinite(q) ||
        !isfinite(P) || (q == 0.0 && P == 0.0)) {
        snprintf(err, errlen, "elastica: need L>0, D>0, q>=0, P>=0, not both zero (L=%g D=%g q=%g P=%g)", L, D, q, P);
        return -1;
    }
    if (n < 0 || n == 1) {
        snprintf(err, errlen, "elastica: n=%d samples (0 or >= 2)", n);
        return -1;
    }
    ctx.p.kappa = q * L * L * L / D;
    ctx.p.beta = P * L * L / D;
    ctx.failed = 0;
    F.function = elastica__residual;
    F.params = &ctx;
    hi = 0.5 * ctx.p.kappa + ctx.p.beta;
    fhi = elastica__residual(hi, &ctx);
    lo = 0.0;
    flo = elastica__residual(lo, &ctx);
    if (ctx.failed) {
        snprintf(err, errlen, "elastica: ODE integration failed (kappa=%g beta=%g)", ctx.p.kappa, ctx.p.beta);
        return -1;
    }
    if (fhi == 0.0) {
        lo = hi; /* exact hit: the root is hi */
    } else if (!(flo < 0.0)) {
        /* scan down from hi for a sign change */
        int k;
        double prev = hi, fprev = fhi;
        for (k = ELASTICA_SCAN - 1; k >= 0; --k) {
            double ak = hi * (double)k / ELASTICA_SCAN, fk = elastica__residual(ak, &ctx);
            if (fk < 0.0) {
                lo = ak;
                flo = fk;
                hi = prev;
                fhi = fprev;
                break;
            }
            prev = ak;
            fprev = fk;
        }
        if (!(flo < 0.0)) {
            snprintf(err, errlen, "elastica: no bracket for phi'(0) (kappa=%g beta=%g)", ctx.p.kappa, ctx.p.beta);
            return -1;
        }
    }
    if (lo != hi) {
        solver = gsl_root_fsolver_alloc(gsl_root_fsolver_brent);
        if (!solver) {
            snprintf(err, errlen, "elastica: out of memory");
            return -1;
        }
        st = gsl_root_fsolver_set(solver, &F, lo, hi);
        while (st == GSL_SUCCESS && it < ELASTICA_MAX_ITER) {
            ++it;
            st = gsl_root_fsolver_iterate(solver);
            if (st != GSL_SUCCESS || ctx.failed) break;
            a = gsl_root_fsolver_root(solver);
            lo = gsl_root_fsolver_x_lower(solver);
            hi = gsl_root_fsolver_x_upper(solver);
            if (gsl_root_test_interval(lo, hi, ELASTICA_SHOOT_TOL, 1e-14) == GSL_SUCCESS) break;
        }
        gsl_root_fsolver_free(solver);
        if (st != GSL_SUCCESS || ctx.failed || it >= ELASTICA_MAX_ITER) {
            snprintf(err, errlen, "elastica: shooting did not converge (status %d, %d iterations)", st, it);
            return -1;
        }
    } else {
        a = hi;
    }
    /* final pass: samples and tip */
    {
        st = elastica__shoot(&ctx.p, a, n, phi, x, y, z);
        if (st != GSL_SUCCESS) {
            snprintf(err, errlen, "elastica: final integration failed (status %d)", st);
            return -1;
        }
        for (i = 0; i < n; ++i) {
            if (x) x[i] *= L;
            if (y) y[i] *= -L; /* downward deflection -> y up */
            if (phi && !(phi[i] >= -1e-12 && phi[i] <= 0.5 * ELASTICA_PI + 1e-12)) {
                snprintf(err, errlen, "elastica: solution left the physical branch (phi=%g at sample %d)", phi[i], i);
                return -1;
            }
        }
    }
    if (!(z[0] >= -1e-12 && z[0] <= 0.5 * ELASTICA_PI + 1e-12)) {
        snprintf(err, errlen, "elastica: tip angle %g outside [0, pi/2]", z[0]);
        return -1;
    }
    res->tip_x = L * z[2];
    res->tip_y = -L * z[3];
    res->tip_deflection = L * z[3];
    res->tip_angle = z[0];
    res->clamp_curvature = a / L;
    res->kappa = ctx.p.kappa;
    res->beta = ctx.p.beta;
    res->iterations = it;
    res->residual = fabs(z[1]);
    return 0;
}

#endif /* WRINKLE_VALIDATION_ELASTICA_REF_H */
