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
 *   Two shootings, both with GSL's gsl_odeiv2 rk8pd (Prince–Dormand 8(9)) at tolerance ELASTICA_ODE_TOL
 *   and gsl_root_fsolver_brent on the mismatch:
 *   - from the clamp (light loads, κ/2 + β <= 50): unknown a = φ'(0), mismatch φ'(1). Since
 *     |cos φ| <= 1, R(κ/2 + β) >= 0; the lower end of the bracket comes from a scan.
 *   - from the free end (heavy loads, the fabric regime: κ ≈ 3000 for B = 2e-6 N·m, ρ_A = 0.2 kg/m²,
 *     L = 0.15 m): with ψ = π/2 − φ and τ = 1 − σ, ψ'' = (κτ + β) sin ψ, ψ(0) = ψ_L, ψ'(0) = 0;
 *     unknown u = log ψ_L, mismatch ψ(τ=1) − π/2. Shooting from the clamp cannot work there: the
 *     hanging strip amplifies errors like exp(⅔√κ), and the clamp shooting converges to looping
 *     equilibria instead (measured at κ = 300 and above). The physical solution is the smallest root
 *     in u, which the upward scan finds first.
 *   Automatic mode tries the preferred one and falls back to the other. Every solution is checked
 *   to lie on the physical branch 0 <= φ <= π/2 (up to ELASTICA_BRANCH_TOL).
 *   Works to κ = 1e6 (measured); far beyond that ψ_L would underflow (below e^−690).
 *
 * API
 *   elastica_ref_solve(L, D, q, P, n, x, y, phi, &res, err, errlen)
 *       x, y, phi: n >= 2 samples at s_i = L·i/(n−1) (each may be NULL). Returns 0 on success, −1 on
 *       bad input or non-convergence with a message in err.
 *   elastica_ref_solve_method(..., method): same, method 0 = automatic, 1 = shoot from the clamp,
 *       2 = shoot from the free end (tests use it to compare the two).
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
#include <stdlib.h>

/* rk8pd absolute and relative tolerance on (φ, φ', X, Y), dimensionless. 1e-12 leaves the shooting
 * residual, not the ODE, as the accuracy limit while costing < 1 ms per integration. */
#define ELASTICA_ODE_TOL 1e-12
/* Brent stops when the bracket on a = φ'(0) is below this (absolute, dimensionless) + 1e-14·|a|. */
#define ELASTICA_SHOOT_TOL 1e-13
#define ELASTICA_MAX_ITER 200
/* Sub-intervals used to scan for the lower end of the bracket. */
#define ELASTICA_SCAN 32
#define ELASTICA_PI 3.14159265358979323846
/* Drivers usually call only one of the two entry points; keep -Wunused-function quiet. */
#if defined(__GNUC__) || defined(__clang__)
#define ELASTICA_MAYBE_UNUSED __attribute__((unused))
#else
#define ELASTICA_MAYBE_UNUSED
#endif
/* Slack [rad] on the physical-branch check 0 <= φ <= π/2: the clamp angle of a tip-shot solution is
 * off by the shooting residual (~1e-12); loops violate the check by O(1e-3) or more. */
#define ELASTICA_BRANCH_TOL 1e-9
/* Samples on which the branch is checked when the caller asks for none. */
#define ELASTICA_CHECK_SAMPLES 513

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

static int elastica__solve_clamp(double L, double D, double q, double P, int n, double *x, double *y, double *phi,
                                 elastica_ref_result *res, char *err, size_t errlen) {
    elastica__root_ctx ctx;
    gsl_function F;
    gsl_root_fsolver *solver;
    double lo, hi, flo, fhi, a = 0.0, z[4];
    int it = 0, st, i;
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
    /* final pass: samples and tip; the branch is always checked on at least ELASTICA_CHECK_SAMPLES
     * samples (a looping equilibrium can end with a tip angle inside [0, π/2]) */
    {
        int m = n >= 2 ? n : ELASTICA_CHECK_SAMPLES;
        double *buf = (double *)malloc(sizeof(double) * 3u * (size_t)m);
        if (!buf) {
            snprintf(err, errlen, "elastica: out of memory");
            return -1;
        }
        st = elastica__shoot(&ctx.p, a, m, buf, buf + m, buf + 2 * m, z);
        if (st != GSL_SUCCESS) {
            free(buf);
            snprintf(err, errlen, "elastica: final integration failed (status %d)", st);
            return -1;
        }
        for (i = 0; i < m; ++i)
            if (!(buf[i] >= -ELASTICA_BRANCH_TOL && buf[i] <= 0.5 * ELASTICA_PI + ELASTICA_BRANCH_TOL)) {
                snprintf(err, errlen, "elastica: solution left the physical branch (phi=%g at s/L=%g)", buf[i],
                         (double)i / (m - 1));
                free(buf);
                return -1;
            }
        for (i = 0; i < n; ++i) {
            if (phi) phi[i] = buf[i];
            if (x) x[i] = L * buf[m + i];
            if (y) y[i] = -L * buf[2 * m + i]; /* downward deflection -> y up */
        }
        free(buf);
    }
    if (!(z[0] >= -ELASTICA_BRANCH_TOL && z[0] <= 0.5 * ELASTICA_PI + ELASTICA_BRANCH_TOL)) {
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

/* ---- shooting from the free end, for heavy loads ----
 * With ψ = π/2 − φ (angle from the downward vertical) and τ = 1 − σ (distance from the tip):
 *     d²ψ/dτ² = (κ τ + β) sin ψ,   ψ(0) = ψ_L,  dψ/dτ(0) = 0,   and the clamp needs ψ(τ = 1) = π/2.
 * For large κ the strip hangs almost vertically and ψ grows from the tip like an Airy function,
 * ψ(1) ~ ψ_L·exp(⅔√κ) (√κ ≈ 89 for a fabric strip, κ ≈ 8000): from the clamp, φ'(0) would have to be
 * hit to ~exp(−⅔√κ) relative accuracy, which double precision cannot do (measured: clamp shooting
 * loses the physical branch from κ ≈ 300). From the tip the unknown is u = log ψ_L, and ψ(1) depends
 * smoothly on it. ψ and ψ' get purely relative ODE tolerance (they start at ~1e-90 for κ = 1e5);
 * the positions (X, Y measured from the tip) get absolute tolerance. */
typedef struct elastica__tip_ctx {
    elastica__params p;
    int failed;
} elastica__tip_ctx;

static int elastica__rhs_tip(double t, const double z[], double dz[], void *vp) {
    const elastica__params *p = (const elastica__params *)vp;
    dz[0] = z[1];
    dz[1] = (p->kappa * t + p->beta) * sin(z[0]);
    dz[2] = -sin(z[0]); /* dx/dτ = −cos φ = −sin ψ */
    dz[3] = -cos(z[0]); /* d(deflection)/dτ = −sin φ = −cos ψ */
    return GSL_SUCCESS;
}

/* Integrate τ from 0 to 1 from ψ_L = exp(u); samples at τ_j = j/(n−1) when n >= 2. */
static int elastica__shoot_tip(const elastica__params *p, double u, int n, double *psi_out, double *X_out,
                               double *Y_out, double z_end[4]) {
    static const double scale_abs[4] = {0.0, 0.0, 1.0, 1.0};
    gsl_odeiv2_system sys;
    gsl_odeiv2_driver *drv;
    double z[4], t = 0.0;
    int i, st = GSL_SUCCESS, m = n >= 2 ? n : 2;
    sys.function = elastica__rhs_tip;
    sys.jacobian = NULL;
    sys.dimension = 4;
    sys.params = (void *)p;
    drv = gsl_odeiv2_driver_alloc_scaled_new(&sys, gsl_odeiv2_step_rk8pd, 1e-4, ELASTICA_ODE_TOL, ELASTICA_ODE_TOL,
                                             1.0, 0.0, scale_abs);
    if (!drv) return GSL_ENOMEM;
    z[0] = exp(u);
    z[1] = 0.0;
    z[2] = 0.0;
    z[3] = 0.0;
    if (psi_out) psi_out[0] = z[0];
    if (X_out) X_out[0] = 0.0;
    if (Y_out) Y_out[0] = 0.0;
    for (i = 1; i < m && st == GSL_SUCCESS; ++i) {
        st = gsl_odeiv2_driver_apply(drv, &t, (double)i / (double)(m - 1), z);
        if (n >= 2) {
            if (psi_out) psi_out[i] = z[0];
            if (X_out) X_out[i] = z[2];
            if (Y_out) Y_out[i] = z[3];
        }
    }
    gsl_odeiv2_driver_free(drv);
    for (i = 0; i < 4; ++i) z_end[i] = z[i];
    return st;
}

static double elastica__residual_tip(double u, void *vp) {
    elastica__tip_ctx *c = (elastica__tip_ctx *)vp;
    double z[4];
    if (elastica__shoot_tip(&c->p, u, 0, NULL, NULL, NULL, z) != GSL_SUCCESS) {
        c->failed = 1;
        return GSL_NAN;
    }
    return z[0] - 0.5 * ELASTICA_PI;
}

/* The physical solution is the SMALLEST root in u = log ψ_L: below it ψ(1) < π/2; above it, larger
 * ψ_L make ψ overshoot π/2 inside the strip and swing like a pendulum, and R(u) has further roots —
 * looping equilibria (measured at κ = 300, 1000: clamp shooting converges to such loops). So the scan
 * runs upward from ψ_L = e^−690 ≈ 1e−300, coarse steps first, then fine steps inside the first coarse
 * interval where R changes sign. */
#define ELASTICA_TIP_U_MIN (-690.0)
#define ELASTICA_TIP_U_COARSE 8.0
#define ELASTICA_TIP_U_FINE 0.25

static int elastica__solve_tip(double L, double D, double q, double P, int n, double *x, double *y, double *phi,
                               elastica_ref_result *res, char *err, size_t errlen) {
    elastica__tip_ctx ctx;
    gsl_function F;
    gsl_root_fsolver *solver;
    double top = log(0.5 * ELASTICA_PI), lo = ELASTICA_TIP_U_MIN, hi, fhi, u = top, z[4], step;
    double *psi = NULL, *X = NULL, *Y = NULL;
    int it = 0, st, i, pass, m;
    ctx.p.kappa = q * L * L * L / D;
    ctx.p.beta = P * L * L / D;
    ctx.failed = 0;
    F.function = elastica__residual_tip;
    F.params = &ctx;
    if (!(elastica__residual_tip(lo, &ctx) < 0.0) || ctx.failed) {
        snprintf(err, errlen, "elastica(tip): load too large (kappa=%g beta=%g): psi_L below 1e-300", ctx.p.kappa,
                 ctx.p.beta);
        return -1;
    }
    /* R(top) > 0: at ψ_L = π/2, ψ only grows. Two passes: coarse, then fine from the coarse lower end. */
    hi = top;
    for (pass = 0; pass < 2; ++pass) {
        double end = pass == 0 ? top : hi;
        step = pass == 0 ? ELASTICA_TIP_U_COARSE : ELASTICA_TIP_U_FINE;
        hi = end;
        for (u = lo + step; u < end; u += step) {
            fhi = elastica__residual_tip(u, &ctx);
            if (ctx.failed) {
                snprintf(err, errlen, "elastica(tip): ODE integration failed (kappa=%g beta=%g)", ctx.p.kappa,
                         ctx.p.beta);
                return -1;
            }
            if (fhi >= 0.0) {
                hi = u;
                break;
            }
            lo = u;
        }
    }
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
        u = gsl_root_fsolver_root(solver);
        /* u = log ψ_L: an absolute tolerance on u is a relative one on ψ_L */
        if (gsl_root_test_interval(gsl_root_fsolver_x_lower(solver), gsl_root_fsolver_x_upper(solver),
                                   ELASTICA_SHOOT_TOL, 1e-14) == GSL_SUCCESS)
            break;
    }
    gsl_root_fsolver_free(solver);
    if (st != GSL_SUCCESS || ctx.failed || it >= ELASTICA_MAX_ITER) {
        snprintf(err, errlen, "elastica(tip): shooting did not converge (status %d, %d iterations)", st, it);
        return -1;
    }
    m = n >= 2 ? n : ELASTICA_CHECK_SAMPLES;
    psi = (double *)malloc(sizeof(double) * 3u * (size_t)m);
    if (!psi) {
        snprintf(err, errlen, "elastica: out of memory");
        return -1;
    }
    X = psi + m;
    Y = psi + 2 * m;
    st = elastica__shoot_tip(&ctx.p, u, m, psi, X, Y, z);
    if (st != GSL_SUCCESS) {
        free(psi);
        snprintf(err, errlen, "elastica(tip): final integration failed (status %d)", st);
        return -1;
    }
    /* τ_j ↔ σ_i with i = n−1−j; positions relative to the clamp: x(σ) = X(τ) − X(1), same for the
     * deflection, whose clamp value is Y(1). */
    for (i = 0; i < m; ++i) {
        double ph = 0.5 * ELASTICA_PI - psi[i];
        if (!(ph >= -ELASTICA_BRANCH_TOL && ph <= 0.5 * ELASTICA_PI + ELASTICA_BRANCH_TOL)) {
            free(psi);
            snprintf(err, errlen, "elastica(tip): solution left the physical branch (phi=%g at s/L=%g)", ph,
                     1.0 - (double)i / (m - 1));
            return -1;
        }
    }
    for (i = 0; i < n; ++i) {
        int j = n - 1 - i;
        double ph = 0.5 * ELASTICA_PI - psi[j];
        if (phi) phi[i] = ph;
        if (x) x[i] = L * (X[j] - z[2]);
        if (y) y[i] = -L * (Y[j] - z[3]);
    }
    free(psi);
    res->tip_x = -L * z[2];
    res->tip_y = L * z[3];
    res->tip_deflection = -L * z[3];
    res->tip_angle = 0.5 * ELASTICA_PI - exp(u);
    res->clamp_curvature = z[1] / L; /* dφ/dσ = dψ/dτ */
    res->kappa = ctx.p.kappa;
    res->beta = ctx.p.beta;
    res->iterations = it;
    res->residual = fabs(z[0] - 0.5 * ELASTICA_PI);
    return 0;
}

/* Loads up to this κ/2 + β are shot from the clamp (verified to κ = 100), heavier ones from the tip. */
#define ELASTICA_CLAMP_MAX_LOAD 50.0

/* method: 0 = automatic, 1 = shoot from the clamp, 2 = shoot from the free end. */
ELASTICA_MAYBE_UNUSED static int elastica_ref_solve_method(double L, double D, double q, double P, int n, double *x, double *y, double *phi,
                                     elastica_ref_result *res, char *err, size_t errlen, int method) {
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
    if (method == 0) {
        /* clamp shooting for light loads (more accurate there), the free-end shooting otherwise; each
         * falls back to the other when it fails */
        int first = 0.5 * q * L * L * L / D + P * L * L / D <= ELASTICA_CLAMP_MAX_LOAD ? 1 : 2;
        if (first == 1 && elastica__solve_clamp(L, D, q, P, n, x, y, phi, res, err, errlen) == 0) return 0;
        if (elastica__solve_tip(L, D, q, P, n, x, y, phi, res, err, errlen) == 0) return 0;
        if (first == 2) return elastica__solve_clamp(L, D, q, P, n, x, y, phi, res, err, errlen);
        return -1;
    }
    if (method == 1) return elastica__solve_clamp(L, D, q, P, n, x, y, phi, res, err, errlen);
    if (method == 2) return elastica__solve_tip(L, D, q, P, n, x, y, phi, res, err, errlen);
    snprintf(err, errlen, "elastica: unknown method %d", method);
    return -1;
}

ELASTICA_MAYBE_UNUSED static int elastica_ref_solve(double L, double D, double q, double P, int n, double *x, double *y, double *phi,
                              elastica_ref_result *res, char *err, size_t errlen) {
    return elastica_ref_solve_method(L, D, q, P, n, x, y, phi, res, err, errlen, 0);
}

#endif /* WRINKLE_VALIDATION_ELASTICA_REF_H */
