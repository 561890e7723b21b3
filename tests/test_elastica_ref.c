/* tests/test_elastica_ref.c — the GSL heavy-elastica reference used by the cantilever validation
 * (validation/elastica_ref.h): small-load beam formulas, the tip-load elastica against its elliptic-
 * integral closed form and against published tip deflections, the heavy elastica against an
 * independent fixed-point solver, the clamp moment balance, and the error paths. */
#include <criterion/criterion.h>
#include <gsl/gsl_errno.h>
#include <gsl/gsl_roots.h>
#include <gsl/gsl_sf_ellint.h>
#include <math.h>
#include <stdlib.h>

#include "../validation/elastica_ref.h"

/* Small-load bound asked for by the validation plan: linear beam theory within 0.5 %. */
#define LINEAR_TOL 0.005

Test(elastica_ref, small_self_weight_matches_qL4_over_8D) {
    /* Style3D Fig. 18 material: B = 2e-6 N·m per unit width; a 0.2 m strip of 0.05 m width and a
     * tiny areal density so that κ = ρ_A g L³/B = 1e-4 (linear regime). */
    double L = 0.2, bw = 0.05, B = 2e-6, D = B * bw, kappa = 1e-4, q = kappa * D / (L * L * L);
    double x[11], y[11], phi[11], err_max = 0.0;
    char err[256];
    elastica_ref_result r;
    int i;
    cr_assert_eq(elastica_ref_solve(L, D, q, 0.0, 11, x, y, phi, &r, err, sizeof err), 0, "%s", err);
    cr_assert_lt(fabs(r.tip_deflection / (q * L * L * L * L / (8.0 * D)) - 1.0), LINEAR_TOL);
    for (i = 1; i < 11; ++i) {
        double s = L * i / 10.0, w = q * s * s * (6 * L * L - 4 * L * s + s * s) / (24.0 * D);
        err_max = fmax(err_max, fabs(-y[i] / w - 1.0));
        cr_assert_float_eq(x[i], s, 1e-6 * L);
    }
    cr_assert_lt(err_max, LINEAR_TOL, "shape vs beam theory: %g", err_max);
    cr_assert_lt(r.residual, 1e-9);
    cr_log_info("kappa=1e-4: tip deflection / (qL^4/8D) - 1 = %.3g, worst shape deviation %.3g",
                r.tip_deflection / (q * L * L * L * L / (8.0 * D)) - 1.0, err_max);
}

Test(elastica_ref, small_tip_load_matches_PL3_over_3D) {
    double L = 1.0, D = 2.0, P = 1e-4 * D / (L * L);
    char err[256];
    elastica_ref_result r;
    cr_assert_eq(elastica_ref_solve(L, D, 0.0, P, 0, NULL, NULL, NULL, &r, err, sizeof err), 0, "%s", err);
    cr_assert_lt(fabs(r.tip_deflection / (P * L * L * L / (3.0 * D)) - 1.0), LINEAR_TOL);
}

/* Tip-load elastica in closed form (derived in validation/elastica_ref.h's notation): with
 * k² = (1 + sin φ_L)/2 and sin ψ0 = 1/(k√2),  α = L√(P/D) = K(k) − F(ψ0, k),
 * δ/L = 1 − 2 (E(k) − E(ψ0, k))/α,  x_L/L = √(2 sin φ_L)/α. Solved for φ_L by Brent. */
typedef struct {
    double alpha;
} tip_ctx;
static double tip_alpha_residual(double phiL, void *vp) {
    double k = sqrt(0.5 * (1.0 + sin(phiL))), psi0 = asin(fmin(1.0, 1.0 / (k * sqrt(2.0))));
    return gsl_sf_ellint_Kcomp(k, GSL_PREC_DOUBLE) - gsl_sf_ellint_F(psi0, k, GSL_PREC_DOUBLE) -
           ((tip_ctx *)vp)->alpha;
}
static void tip_closed_form(double alpha, double *delta_over_L, double *x_over_L, double *phiL_out) {
    tip_ctx c;
    gsl_function F;
    gsl_root_fsolver *s = gsl_root_fsolver_alloc(gsl_root_fsolver_brent);
    double lo = 1e-9, hi = 0.5 * ELASTICA_PI - 1e-6, phiL = 0.0, k, psi0; /* K(k) at hi ≈ 15.9 > α */
    int it;
    c.alpha = alpha;
    F.function = tip_alpha_residual;
    F.params = &c;
    gsl_set_error_handler_off();
    cr_assert_eq(gsl_root_fsolver_set(s, &F, lo, hi), GSL_SUCCESS);
    for (it = 0; it < 200; ++it) {
        cr_assert_eq(gsl_root_fsolver_iterate(s), GSL_SUCCESS);
        phiL = gsl_root_fsolver_root(s);
        if (gsl_root_test_interval(gsl_root_fsolver_x_lower(s), gsl_root_fsolver_x_upper(s), 1e-15, 1e-15) ==
            GSL_SUCCESS)
            break;
    }
    gsl_root_fsolver_free(s);
    k = sqrt(0.5 * (1.0 + sin(phiL)));
    psi0 = asin(fmin(1.0, 1.0 / (k * sqrt(2.0))));
    *delta_over_L =
        1.0 - 2.0 * (gsl_sf_ellint_Ecomp(k, GSL_PREC_DOUBLE) - gsl_sf_ellint_E(psi0, k, GSL_PREC_DOUBLE)) / alpha;
    *x_over_L = sqrt(2.0 * sin(phiL)) / alpha;
    *phiL_out = phiL;
}

Test(elastica_ref, tip_load_matches_elliptic_closed_form_and_published_values) {
    /* Published large-deflection tip deflections δ/L of an end-loaded cantilever for PL²/EI = 1, 2,
     * 5, 10: 0.30172, 0.49346, 0.71379, 0.81061 (elliptic-integral solution of Bisshopp & Drucker,
     * "Large deflection of cantilever beams", Q. Appl. Math. 3(3):272–275, 1945, as tabulated to five
     * digits by Mattiasson, "Numerical results from large deflection beam and frame problems analysed
     * by means of elliptic integrals", IJNME 17:145–153, 1981). Five digits: tolerance 1e-5. */
    static const double loads[4] = {1.0, 2.0, 5.0, 10.0};
    static const double published[4] = {0.30172, 0.49346, 0.71379, 0.81061};
    int i;
    for (i = 0; i < 4; ++i) {
        double L = 0.3, D = 4e-3, P = loads[i] * D / (L * L), dl, xl, phiL;
        char err[256];
        elastica_ref_result r;
        cr_assert_eq(elastica_ref_solve(L, D, 0.0, P, 0, NULL, NULL, NULL, &r, err, sizeof err), 0, "%s", err);
        tip_closed_form(sqrt(loads[i]), &dl, &xl, &phiL); /* α = L√(P/D) */
        cr_assert_float_eq(r.tip_deflection / L, dl, 1e-9, "PL2/D=%g: shooting %.12f closed form %.12f", loads[i],
                           r.tip_deflection / L, dl);
        cr_assert_float_eq(r.tip_x / L, xl, 1e-9);
        cr_assert_float_eq(r.tip_angle, phiL, 1e-9);
        cr_assert_float_eq(r.tip_deflection / L, published[i], 1e-5, "PL2/D=%g: %.6f vs published %.5f", loads[i],
                           r.tip_deflection / L, published[i]);
        cr_log_info("PL^2/D=%g: delta/L shooting %.8f, elliptic %.8f, published %.5f", loads[i], r.tip_deflection / L,
                    dl, published[i]);
    }
}

/* Independent heavy-elastica solver: Picard iteration on the integrated moment balance
 *   φ'(σ) = κ ∫_σ^1 (X(ξ) − X(σ)) dξ + β (X(1) − X(σ)),  X(σ) = ∫_0^σ cos φ,  φ(σ) = ∫_0^σ φ',
 * trapezoid rule on M intervals, under-relaxed; no ODE integrator, no shooting. Returns δ/L. */
static double picard_tip(double kappa, double beta, int M) {
    double *phi = (double *)calloc((size_t)M + 1, sizeof(double)), *X = (double *)calloc((size_t)M + 1, sizeof(double));
    double *C = (double *)calloc((size_t)M + 1, sizeof(double)), *dp = (double *)calloc((size_t)M + 1, sizeof(double));
    double h = 1.0 / M, omega = 0.5, delta = 0.0;
    int it, i;
    cr_assert(phi && X && C && dp);
    for (it = 0; it < 20000; ++it) {
        double change = 0.0, acc = 0.0, newphi;
        X[0] = 0.0;
        for (i = 1; i <= M; ++i) X[i] = X[i - 1] + 0.5 * h * (cos(phi[i - 1]) + cos(phi[i]));
        C[M] = 0.0;
        for (i = M - 1; i >= 0; --i) C[i] = C[i + 1] + 0.5 * h * (X[i] + X[i + 1]);
        for (i = 0; i <= M; ++i) dp[i] = kappa * (C[i] - X[i] * (1.0 - (double)i * h)) + beta * (X[M] - X[i]);
        for (i = 1; i <= M; ++i) {
            acc += 0.5 * h * (dp[i - 1] + dp[i]);
            newphi = (1.0 - omega) * phi[i] + omega * acc;
            change = fmax(change, fabs(newphi - phi[i]));
            phi[i] = newphi;
        }
        if (change < 1e-14) break;
    }
    cr_assert_lt(it, 20000, "Picard did not converge for kappa=%g", kappa);
    for (i = 1; i <= M; ++i) delta += 0.5 * h * (sin(phi[i - 1]) + sin(phi[i]));
    free(phi);
    free(X);
    free(C);
    free(dp);
    return delta;
}

Test(elastica_ref, heavy_large_deflection_matches_independent_solver) {
    static const double kappas[3] = {1.0, 4.0, 8.0};
    int i;
    for (i = 0; i < 3; ++i) {
        double L = 0.15, D = 1e-7, q = kappas[i] * D / (L * L * L);
        /* Richardson on the O(h²) trapezoid error */
        double d1 = picard_tip(kappas[i], 0.0, 400), d2 = picard_tip(kappas[i], 0.0, 800);
        double ref = (4.0 * d2 - d1) / 3.0;
        char err[256];
        elastica_ref_result r;
        cr_assert_eq(elastica_ref_solve(L, D, q, 0.0, 0, NULL, NULL, NULL, &r, err, sizeof err), 0, "%s", err);
        cr_assert_float_eq(r.tip_deflection / L, ref, 1e-6, "kappa=%g: shooting %.10f picard %.10f", kappas[i],
                           r.tip_deflection / L, ref);
        /* well past the linear regime: beam theory overestimates */
        cr_assert_lt(r.tip_deflection / L, kappas[i] / 8.0);
        cr_log_info("kappa=%g: delta/L shooting %.8f, Picard+Richardson %.8f, linear %.4f", kappas[i],
                    r.tip_deflection / L, ref, kappas[i] / 8.0);
    }
}

Test(elastica_ref, clamp_and_free_end_shooting_agree) {
    /* within the clamp shooting's range (κ/2 + β <= 50); tip load P = ratio·qL */
    static const double kappas[4] = {1e-3, 1.0, 8.0, 100.0}, ratio[4] = {0.3, 0.3, 0.3, 0.0};
    int i;
    for (i = 0; i < 4; ++i) {
        double L = 0.2, D = 1e-7, q = kappas[i] * D / (L * L * L), P = ratio[i] * q * L;
        elastica_ref_result a, b;
        char err[256];
        cr_assert_eq(elastica_ref_solve_method(L, D, q, P, 0, NULL, NULL, NULL, &a, err, sizeof err, 1), 0, "%s", err);
        cr_assert_eq(elastica_ref_solve_method(L, D, q, P, 0, NULL, NULL, NULL, &b, err, sizeof err, 2), 0, "%s", err);
        cr_assert_float_eq(a.tip_deflection / L, b.tip_deflection / L, 1e-9, "kappa=%g: %.12f vs %.12f", kappas[i],
                           a.tip_deflection / L, b.tip_deflection / L);
        cr_assert_float_eq(a.tip_x / L, b.tip_x / L, 1e-9);
        cr_assert_float_eq(a.clamp_curvature * L, b.clamp_curvature * L, 1e-7 * (1.0 + a.clamp_curvature * L));
    }
}

/* Heavy strips (the fabric regime) hang almost vertically below a clamp boundary layer. There the
 * tension is T ≈ qL, and D φ'' = −T cos φ integrates once to (D/2) φ'² = T (1 − sin φ). So the
 * layer's horizontal reach is ∫cos φ ds = √(2D/T), and its "lost" height is
 * ∫(1 − sin φ) ds = (2√2 − 2)·√(D/2T). In units of L:
 *     x_tip/L → √(2/κ),   1 − δ/L → (2√2 − 2)/√(2κ),   relative corrections O(κ^−½)
 * (the tension is not constant across the layer). The test checks both limits to within 1/√κ. */
Test(elastica_ref, heavy_strip_boundary_layer_asymptotics) {
    static const double kappas[3] = {1e3, 1e4, 1e5};
    double prev_dev = 0.0;
    int i;
    for (i = 0; i < 3; ++i) {
        double L = 0.15, D = 2e-6 * 0.05, q = kappas[i] * D / (L * L * L), k = kappas[i];
        double reach, drop;
        char err[256];
        elastica_ref_result r;
        cr_assert_eq(elastica_ref_solve(L, D, q, 0.0, 0, NULL, NULL, NULL, &r, err, sizeof err), 0, "%s", err);
        reach = r.tip_x / L / sqrt(2.0 / k) - 1.0;
        drop = (1.0 - r.tip_deflection / L) / ((2.0 * sqrt(2.0) - 2.0) / sqrt(2.0 * k)) - 1.0;
        cr_assert(reach > 0.0 && reach < 1.0 / sqrt(k), "kappa=%g: reach deviation %g", k, reach);
        cr_assert(fabs(drop) < 1.0 / sqrt(k), "kappa=%g: drop deviation %g", k, drop);
        /* the deviation shrinks like κ^−½: a factor ≈ √10 per decade */
        if (i > 0) cr_assert(prev_dev / reach > 2.5 && prev_dev / reach < 4.0, "ratio %g", prev_dev / reach);
        prev_dev = reach;
        cr_log_info("kappa=%g: x_tip/L = %.8f (sqrt(2/kappa) x (1%+.5f)), delta/L = %.8f (drop ratio 1%+.5f)", k,
                    r.tip_x / L, reach, r.tip_deflection / L, drop);
    }
}

Test(elastica_ref, fabric_cantilever_stays_on_the_physical_branch) {
    /* Style3D Fig. 18 fabric: B = 2e-6 N·m; with ρ_A = 0.2 kg/m², g = 9.81 m/s², L = 0.15 m, b = 0.05 m:
     * κ = ρ_A g L³ / B ≈ 3311. Clamp shooting alone converges to a looping equilibrium there. */
    enum { N = 4001 };
    static double x[N], y[N], phi[N];
    double L = 0.15, bw = 0.05, B = 2e-6, D = B * bw, q = 0.2 * 9.81 * bw, integral = 0.0, h = L / (N - 1);
    char err[256];
    elastica_ref_result r;
    int i;
    cr_assert_eq(elastica_ref_solve(L, D, q, 0.0, N, x, y, phi, &r, err, sizeof err), 0, "%s", err);
    cr_assert_float_eq(r.kappa, 0.2 * 9.81 * L * L * L / B, 1e-9 * r.kappa);
    for (i = 1; i < N; ++i) {
        cr_assert_geq(phi[i], phi[i - 1] - 1e-12);
        cr_assert_leq(phi[i], 0.5 * ELASTICA_PI + 1e-9);
        integral += 0.5 * h * (x[i - 1] + x[i]);
    }
    /* the moment check's own trapezoid error on the ~L/√κ clamp layer dominates: 1e-5 */
    cr_assert_float_eq(D * r.clamp_curvature, q * integral, 1e-5 * D * r.clamp_curvature);
    cr_assert_neq(elastica_ref_solve_method(L, D, q, 0.0, 0, NULL, NULL, NULL, &r, err, sizeof err, 1), 0,
                  "clamp shooting is expected to lose the branch at kappa ~ 3300");
    cr_log_info("fabric strip (kappa=%.0f): tip deflection %.3f mm of L = %.0f mm, tip x %.3f mm", r.kappa,
                1e3 * r.tip_deflection, 1e3 * L, 1e3 * r.tip_x);
}

Test(elastica_ref, clamp_moment_balance) {
    /* D φ'(0) = q ∫_0^L x ds + P x(L): the clamp carries the moment of all the loads. */
    enum { N = 2001 };
    static double x[N], y[N], phi[N];
    double L = 0.25, D = 3e-4, q = 6.0 * D / (L * L * L), P = 1.5 * D / (L * L), integral = 0.0, h = L / (N - 1);
    char err[256];
    elastica_ref_result r;
    int i;
    cr_assert_eq(elastica_ref_solve(L, D, q, P, N, x, y, phi, &r, err, sizeof err), 0, "%s", err);
    for (i = 1; i < N; ++i) integral += 0.5 * h * (x[i - 1] + x[i]);
    cr_assert_float_eq(D * r.clamp_curvature, q * integral + P * x[N - 1], 1e-7 * D * r.clamp_curvature);
    cr_assert_float_eq(x[N - 1], r.tip_x, 1e-15);
    cr_assert_float_eq(y[N - 1], r.tip_y, 1e-15);
    for (i = 1; i < N; ++i) cr_assert_geq(phi[i], phi[i - 1] - 1e-12, "phi must increase along the strip");
}

Test(elastica_ref, error_paths) {
    char err[256];
    elastica_ref_result r;
    cr_assert_eq(elastica_ref_solve(0.0, 1.0, 1.0, 0.0, 0, NULL, NULL, NULL, &r, err, sizeof err), -1);
    cr_assert_eq(elastica_ref_solve(1.0, 0.0, 1.0, 0.0, 0, NULL, NULL, NULL, &r, err, sizeof err), -1);
    cr_assert_eq(elastica_ref_solve(1.0, 1.0, -1.0, 0.0, 0, NULL, NULL, NULL, &r, err, sizeof err), -1);
    cr_assert_eq(elastica_ref_solve(1.0, 1.0, 0.0, 0.0, 0, NULL, NULL, NULL, &r, err, sizeof err), -1);
    cr_assert_eq(elastica_ref_solve(1.0, 1.0, NAN, 0.0, 0, NULL, NULL, NULL, &r, err, sizeof err), -1);
    cr_assert_eq(elastica_ref_solve(1.0, 1.0, 1.0, 0.0, 1, NULL, NULL, NULL, &r, err, sizeof err), -1);
    cr_assert_eq(elastica_ref_solve_method(1.0, 1.0, 1.0, 0.0, 0, NULL, NULL, NULL, &r, err, sizeof err, 7), -1);
}
