/* tests/test_newton.c — newton.h: closed-form minimisers (a quadratic in one step, a hanging chain of
 * nonlinear springs, a barrier problem whose max-step hook must keep every trial in the domain), each
 * stop reason reached, fixed DOFs held, the update hook, a Hessian pattern that changes, bad options. */
#include <criterion/criterion.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "wrinkle/newton.h"

/* ---- a chain of N nonlinear springs hanging from vertex 0 under gravity ------------------------- */
/* E = Σ_i ½ k (|x_{i+1} − x_i| − L)² + Σ_v m g z_v. Spring i (from the top) carries the weight of the
 * N − i masses below it, so at equilibrium it is vertical with length L + (N − i) m g / k. */
#define CH_N 6
typedef struct chain {
    double k, L, mg;
    int coupled_late; /* pattern test: the springs below vertex 3 are streamed as diagonal blocks at first */
    int calls;
    double lie; /* != 0: the gradient is scaled by this (a wrong gradient for the line-search test) */
} chain;

static double ch_len(const double *x, int i, double u[3]) {
    double l = 0.0;
    int a;
    for (a = 0; a < 3; ++a) {
        u[a] = x[3 * i + 3 + a] - x[3 * i + a];
        l += u[a] * u[a];
    }
    l = sqrt(l);
    for (a = 0; a < 3; ++a) u[a] /= l;
    return l;
}

static wr_status ch_energy(void *user, const double *x, double *E, double *g, double *scale, wr_diag *d) {
    chain *c = (chain *)user;
    int i, a;
    double e = 0.0, sc = 0.0;
    (void)d;
    if (g) memset(g, 0, sizeof(double) * 3 * (CH_N + 1));
    for (i = 0; i < CH_N; ++i) {
        double u[3], l = ch_len(x, i, u), t = l - c->L;
        if (!(l > 0.0)) return WR_ERR_GEOMETRY;
        e += 0.5 * c->k * t * t;
        sc += 0.5 * c->k * t * t;
        if (g)
            for (a = 0; a < 3; ++a) {
                g[3 * i + 3 + a] += c->k * t * u[a];
                g[3 * i + a] -= c->k * t * u[a];
            }
    }
    for (i = 0; i <= CH_N; ++i) {
        e += c->mg * x[3 * i + 2];
        sc += fabs(c->mg * x[3 * i + 2]);
        if (g) g[3 * i + 2] += c->mg;
    }
    if (g && c->lie != 0.0)
        for (i = 0; i < 3 * (CH_N + 1); ++i) g[i] *= c->lie;
    *E = e;
    if (scale) *scale = sc;
    return WR_OK;
}

/* exact spring Hessian: k[(1 − L/l)(I − uuᵀ) + uuᵀ] in the ±± blocks (indefinite when l < L) */
static wr_status ch_hessian(void *user, const double *x, wr_newton_hessian *H, wr_diag *d) {
    chain *c = (chain *)user;
    int i, a, b;
    (void)d;
    c->calls++;
    for (i = 0; i < CH_N; ++i) {
        double u[3], l = ch_len(x, i, u), B[9], K[36];
        int32_t v[2];
        wr_status s;
        for (a = 0; a < 3; ++a)
            for (b = 0; b < 3; ++b)
                B[3 * a + b] = c->k * ((1.0 - c->L / l) * ((a == b) - u[a] * u[b]) + u[a] * u[b]);
        v[0] = i;
        v[1] = i + 1;
        if (c->coupled_late && i >= 3 && c->calls == 1) {
            /* a diagonal stand-in at first (still SPD after the shift): the coupling arrives later */
            double D[9];
            for (a = 0; a < 9; ++a) D[a] = fabs(B[a]) * (a % 4 == 0);
            if ((s = wr_newton_add_diagonal(H, i, D)) != WR_OK || (s = wr_newton_add_diagonal(H, i + 1, D)) != WR_OK)
                return s;
            continue;
        }
        for (a = 0; a < 3; ++a)
            for (b = 0; b < 3; ++b) {
                K[6 * a + b] = K[6 * (a + 3) + b + 3] = B[3 * a + b];
                K[6 * a + b + 3] = K[6 * (a + 3) + b] = -B[3 * a + b];
            }
        if ((s = wr_newton_add_element(H, 2, v, K)) != WR_OK) return s;
    }
    return WR_OK;
}

static void ch_setup(chain *c, wr_newton_problem *p, wr_newton_desc *nd, double *x, uint8_t *fixed) {
    int i;
    memset(c, 0, sizeof *c);
    c->k = 50.0;
    c->L = 0.1;
    c->mg = 0.5;
    memset(p, 0, sizeof *p);
    p->n_blocks = CH_N + 1;
    p->user = c;
    p->energy = ch_energy;
    p->hessian = ch_hessian;
    memset(nd, 0, sizeof *nd);
    memset(fixed, 0, 3 * (CH_N + 1));
    fixed[0] = fixed[1] = fixed[2] = 1;
    nd->fixed = fixed;
    /* a start off the vertical line, springs compressed (0.07 < L) and stretched: the exact Hessian is
     * indefinite there, so the projection matters */
    for (i = 0; i <= CH_N; ++i) {
        x[3 * i] = 0.03 * sin(1.3 * i);
        x[3 * i + 1] = 0.02 * cos(0.7 * i) - 0.02;
        x[3 * i + 2] = -0.07 * i * (1.0 + 0.5 * (i % 2));
    }
}

/* max deviation from the closed-form hanging chain (vertical below vertex 0) */
static double ch_error(const chain *c, const double *x) {
    double z = x[2], err = 0.0;
    int i;
    for (i = 0; i < CH_N; ++i) {
        z -= c->L + (CH_N - i) * c->mg / c->k;
        err = fmax(err, fabs(x[3 * i + 3] - x[0]));
        err = fmax(err, fabs(x[3 * i + 4] - x[1]));
        err = fmax(err, fabs(x[3 * i + 5] - z));
    }
    return err;
}

Test(newton, hanging_chain_closed_form) {
    chain c;
    wr_newton_problem p;
    wr_newton_desc nd;
    wr_newton_stats st;
    wr_diag d;
    double x[3 * (CH_N + 1)], x0[3];
    uint8_t fixed[3 * (CH_N + 1)];
    ch_setup(&c, &p, &nd, x, fixed);
    memcpy(x0, x, sizeof x0);
    cr_assert_eq(wr_newton_solve(&p, x, &nd, &st, &d), WR_OK, "%s", d.message);
    cr_expect_eq(st.stop, WR_NEWTON_STOP_GRADIENT, "stop %s", wr_newton_stop_name(st.stop));
    /* |∇E| <= 1e-8 × |∇E(x0)| (~1 N) over springs of k = 50 N/m: position error ~1e-8/50 m; 1e-9 m
     * leaves a factor ~5 */
    cr_expect_lt(ch_error(&c, x), 1e-9, "error %.3e m", ch_error(&c, x));
    cr_expect(x[0] == x0[0] && x[1] == x0[1] && x[2] == x0[2], "the held vertex moved: %g %g %g -> %g %g %g", x0[0], x0[1], x0[2], x[0], x[1], x[2]);
    cr_expect_gt(st.elements_projected, 0, "the compressed start should need the projection");
    cr_expect_gt(st.exact_steps, 0, "the exact phase should be reached near the minimum");
    cr_expect_eq(st.pattern_builds, 1);
    cr_expect_lt(st.iterations, 40, "%d iterations", (int)st.iterations);
}

/* ---- a quadratic: E = ½ xᵀKx − fᵀx over a linear spring chain along x, one Newton step -------- */
static wr_status q_energy(void *user, const double *x, double *E, double *g, double *scale, wr_diag *d) {
    int i;
    (void)user;
    (void)d;
    (void)scale;
    *E = 0.0;
    if (g) memset(g, 0, sizeof(double) * 15);
    for (i = 0; i < 4; ++i) {
        double t = x[3 * i + 3] - x[3 * i];
        *E += 5.0 * t * t;
        if (g) {
            g[3 * i + 3] += 10.0 * t;
            g[3 * i] -= 10.0 * t;
        }
    }
    /* the transverse DOFs: unit springs to the origin, so the Hessian is SPD with nothing held there */
    for (i = 0; i < 5; ++i) {
        *E += 0.5 * (x[3 * i + 1] * x[3 * i + 1] + x[3 * i + 2] * x[3 * i + 2]) - 0.1 * x[3 * i + 1];
        if (g) {
            g[3 * i + 1] += x[3 * i + 1] - 0.1;
            g[3 * i + 2] += x[3 * i + 2];
        }
    }
    *E -= x[12];
    if (g) g[12] -= 1.0;
    return WR_OK;
}

static wr_status q_hessian(void *user, const double *x, wr_newton_hessian *H, wr_diag *d) {
    double K[36] = {0}, D[9] = {0, 0, 0, 0, 1, 0, 0, 0, 1};
    int32_t v[2], i;
    wr_status s;
    (void)user;
    (void)x;
    (void)d;
    K[0] = K[21] = 10.0;
    K[3] = K[18] = -10.0;
    for (i = 0; i < 4; ++i) {
        v[0] = i;
        v[1] = i + 1;
        if ((s = wr_newton_add_element(H, 2, v, K)) != WR_OK) return s;
    }
    for (i = 0; i < 5; ++i)
        if ((s = wr_newton_add_diagonal(H, i, D)) != WR_OK) return s;
    return WR_OK;
}

static void q_setup(wr_newton_problem *p, wr_newton_desc *nd, uint8_t *fixed) {
    memset(p, 0, sizeof *p);
    p->n_blocks = 5;
    p->energy = q_energy;
    p->hessian = q_hessian;
    memset(nd, 0, sizeof *nd);
    memset(fixed, 0, 15);
    fixed[0] = 1;
    nd->fixed = fixed;
    /* μ = 1e-15 · mean diagonal: the shifted solution differs from K⁻¹f by ~1e-15 relative, below
     * grad_tol 1e-12, so exactly one step must do */
    nd->shift.rel = 1e-15;
    nd->stop.grad_tol = 1e-12;
}

Test(newton, quadratic_in_one_step) {
    wr_newton_problem p;
    wr_newton_desc nd;
    wr_newton_stats st;
    wr_diag d;
    double x[15] = {0};
    uint8_t fixed[15];
    int i;
    q_setup(&p, &nd, fixed);
    cr_assert_eq(wr_newton_solve(&p, x, &nd, &st, &d), WR_OK, "%s", d.message);
    cr_expect_eq(st.iterations, 1, "%d iterations", (int)st.iterations);
    cr_expect_eq(st.stop, WR_NEWTON_STOP_GRADIENT);
    for (i = 0; i < 5; ++i) {
        cr_expect_float_eq(x[3 * i], 0.1 * i, 1e-12, "x[%d] = %.15g (springs in series: i·F/k)", i, x[3 * i]);
        cr_expect_float_eq(x[3 * i + 1], 0.1, 1e-12);
        cr_expect_float_eq(x[3 * i + 2], 0.0, 1e-12);
    }
    /* E* = −½ fᵀK⁻¹f: −½ (1 · 0.4) − 5 · ½ · 0.01 */
    cr_expect_float_eq(st.energy, -0.2 - 0.025, 1e-13, "E %.15g", st.energy);
    cr_expect_eq(st.elements_projected, 0, "PSD blocks must pass the projection unchanged");
}

/* the same quadratic through every linear solver of pcg.h */
Test(newton, quadratic_every_linear_solver) {
    wr_solver_method m[] = {WR_SOLVER_PCG_JACOBI, WR_SOLVER_PCG_BLOCK3, WR_SOLVER_PCG_IC0, WR_SOLVER_PCG_AMG,
                            WR_SOLVER_CHOLMOD};
    int k, i;
    for (k = 0; k < 5; ++k) {
        wr_newton_problem p;
        wr_newton_desc nd;
        wr_newton_stats st;
        wr_diag d;
        double x[15] = {0};
        uint8_t fixed[15];
        q_setup(&p, &nd, fixed);
        nd.linear.solver.method = m[k];
        nd.linear.solver.rel_tol = 1e-14;
        cr_assert_eq(wr_newton_solve(&p, x, &nd, &st, &d), WR_OK, "%s: %s", wr_solver_method_name(m[k]), d.message);
        cr_expect_leq(st.iterations, 2, "%s: %d", wr_solver_method_name(m[k]), (int)st.iterations);
        for (i = 0; i < 5; ++i) cr_expect_float_eq(x[3 * i], 0.1 * i, 1e-11, "%s", wr_solver_method_name(m[k]));
    }
}

/* ---- the max-step hook: E = ½(x − 2)² − μ ln(1 − x), domain x < 1 -------------------------------- */
typedef struct barrier {
    double mu;
    int outside; /* energy calls at x >= 1 */
    int use_hook;
} barrier;

static wr_status b_energy(void *user, const double *x, double *E, double *g, double *scale, wr_diag *d) {
    barrier *b = (barrier *)user;
    (void)scale;
    (void)d;
    if (!(x[0] < 1.0)) {
        b->outside++;
        return WR_ERR_DOMAIN;
    }
    *E = 0.5 * (x[0] - 2.0) * (x[0] - 2.0) - b->mu * log(1.0 - x[0]);
    if (g) g[0] = (x[0] - 2.0) + b->mu / (1.0 - x[0]);
    return WR_OK;
}

static wr_status b_hessian(void *user, const double *x, wr_newton_hessian *H, wr_diag *d) {
    barrier *b = (barrier *)user;
    double h = 1.0 + b->mu / ((1.0 - x[0]) * (1.0 - x[0]));
    int32_t v = 0;
    (void)d;
    return wr_newton_add_element(H, 1, &v, &h);
}

/* conservative advancement: at most 80 % of the way to the wall */
static double b_max_step(void *user, const double *x, const double *dx) {
    (void)user;
    return dx[0] > 0.0 ? fmin(1.0, 0.8 * (1.0 - x[0]) / dx[0]) : 1.0;
}

Test(newton, max_step_hook_honoured) {
    barrier b;
    wr_newton_problem p;
    wr_newton_desc nd;
    wr_newton_stats st;
    wr_diag d;
    double x = 0.0, xs;
    memset(&b, 0, sizeof b);
    b.mu = 0.01;
    memset(&p, 0, sizeof p);
    p.n_blocks = 1;
    p.block = 1;
    p.user = &b;
    p.energy = b_energy;
    p.hessian = b_hessian;
    p.max_step = b_max_step;
    memset(&nd, 0, sizeof nd);
    nd.stop.grad_tol = 1e-12;
    cr_assert_eq(wr_newton_solve(&p, &x, &nd, &st, &d), WR_OK, "%s", d.message);
    xs = (3.0 - sqrt(1.0 + 4.0 * b.mu)) / 2.0; /* (x − 2)(1 − x) + μ = 0, the root below 1 */
    cr_expect_float_eq(x, xs, 1e-12, "x %.15g vs %.15g", x, xs);
    cr_expect_eq(b.outside, 0, "%d trials outside the domain: the hook was not honoured", b.outside);
    cr_expect_lt(st.max_step_min, 0.5, "max_step_min %g", st.max_step_min);
    /* without the hook the first full step (≈ 2) leaves the domain: the line search meets it */
    p.max_step = NULL;
    x = 0.0;
    cr_assert_eq(wr_newton_solve(&p, &x, &nd, &st, &d), WR_OK, "%s", d.message);
    cr_expect_gt(b.outside, 0, "the test problem must need the hook");
    cr_expect_float_eq(x, xs, 1e-12);
}

/* ---- stop reasons --------------------------------------------------------------------------------- */
Test(newton, stop_reasons) {
    chain c;
    wr_newton_problem p;
    wr_newton_desc nd;
    wr_newton_stats st, ref;
    wr_diag d;
    double x[3 * (CH_N + 1)], xr[3 * (CH_N + 1)];
    uint8_t fixed[3 * (CH_N + 1)];
    /* reference minimum at the default tolerance */
    ch_setup(&c, &p, &nd, xr, fixed);
    cr_assert_eq(wr_newton_solve(&p, xr, &nd, &ref, &d), WR_OK, "%s", d.message);
    /* MAX_ITER: NOT_CONVERGED, best iterate kept (energy not above the start's) */
    ch_setup(&c, &p, &nd, x, fixed);
    nd.max_iter = 2;
    cr_expect_eq(wr_newton_solve(&p, x, &nd, &st, &d), WR_ERR_NOT_CONVERGED);
    cr_expect_eq(st.stop, WR_NEWTON_STOP_MAX_ITER);
    cr_expect_eq(st.iterations, 2);
    /* STEP: a gradient tolerance no solve reaches, a step tolerance of 1e-9 m */
    ch_setup(&c, &p, &nd, x, fixed);
    nd.stop.grad_tol = 1e-300;
    nd.stop.step_tol = 1e-9;
    cr_expect_eq(wr_newton_solve(&p, x, &nd, &st, &d), WR_OK, "%s", d.message);
    cr_expect_eq(st.stop, WR_NEWTON_STOP_STEP, "stop %s", wr_newton_stop_name(st.stop));
    cr_expect_lt(ch_error(&c, x), 1e-9);
    /* ROUNDOFF: the same unreachable gradient, no step test: the solve ends on E's round-off, WR_OK */
    ch_setup(&c, &p, &nd, x, fixed);
    nd.stop.grad_tol = 1e-24;
    cr_expect_eq(wr_newton_solve(&p, x, &nd, &st, &d), WR_OK, "%s", d.message);
    cr_expect_eq(st.stop, WR_NEWTON_STOP_ROUNDOFF, "stop %s", wr_newton_stop_name(st.stop));
    cr_expect_lt(ch_error(&c, x), 1e-12, "round-off stop should be at the minimum: %.3e", ch_error(&c, x));
    /* DECREMENT: λ²/2 <= 1e-10 · scale stops before the gradient test (grad_tol 1e-14) would */
    ch_setup(&c, &p, &nd, x, fixed);
    nd.stop.grad_tol = 1e-14;
    nd.stop.decrement_tol = 1e-10;
    cr_expect_eq(wr_newton_solve(&p, x, &nd, &st, &d), WR_OK, "%s", d.message);
    cr_expect_eq(st.stop, WR_NEWTON_STOP_DECREMENT, "stop %s", wr_newton_stop_name(st.stop));
    /* near the minimum E − E* ≈ λ²/2 (Boyd Sec. 9.5.1): within the tolerance, with a factor 2 for the
     * quadratic model's error; the scale Σ|terms| is < 3 J here */
    cr_expect_leq(st.energy - ref.energy, 2.0 * 1e-10 * 3.0, "E − E* = %.3e", st.energy - ref.energy);
    cr_expect_lt(st.iterations, ref.iterations + 1);
    /* LINE_SEARCH: a gradient of the wrong sign, so no step along −K⁻¹g decreases E */
    ch_setup(&c, &p, &nd, x, fixed);
    c.lie = -1.0;
    cr_expect_eq(wr_newton_solve(&p, x, &nd, &st, &d), WR_ERR_NOT_CONVERGED);
    cr_expect_eq(st.stop, WR_NEWTON_STOP_LINE_SEARCH, "stop %s", wr_newton_stop_name(st.stop));
    cr_expect(strstr(d.message, "line search") != NULL, "%s", d.message);
}

/* a Hessian stream that gains couplings after the first assembly: the pattern is rebuilt */
Test(newton, pattern_rebuilt_when_stencils_change) {
    chain c;
    wr_newton_problem p;
    wr_newton_desc nd;
    wr_newton_stats st;
    wr_diag d;
    double x[3 * (CH_N + 1)];
    uint8_t fixed[3 * (CH_N + 1)];
    ch_setup(&c, &p, &nd, x, fixed);
    c.coupled_late = 1;
    cr_assert_eq(wr_newton_solve(&p, x, &nd, &st, &d), WR_OK, "%s", d.message);
    cr_expect_eq(st.pattern_builds, 2, "%d pattern builds", (int)st.pattern_builds);
    cr_expect_lt(ch_error(&c, x), 1e-9);
}

/* ---- the update hook: E = ½ (x − c)², the hook lags c = x/2 + 1 (fixed point x = c = 2) --------- */
typedef struct lagged {
    double c;
    int updates;
} lagged;

static wr_status l_energy(void *user, const double *x, double *E, double *g, double *scale, wr_diag *d) {
    lagged *l = (lagged *)user;
    (void)scale;
    (void)d;
    *E = 0.5 * (x[0] - l->c) * (x[0] - l->c);
    if (g) g[0] = x[0] - l->c;
    return WR_OK;
}

static wr_status l_hessian(void *user, const double *x, wr_newton_hessian *H, wr_diag *d) {
    double h = 1.0;
    int32_t v = 0;
    (void)user;
    (void)x;
    (void)d;
    return wr_newton_add_element(H, 1, &v, &h);
}

static wr_status l_update(void *user, const double *x, int32_t it, int *changed, wr_diag *d) {
    lagged *l = (lagged *)user;
    double c = 0.5 * x[0] + 1.0;
    (void)it;
    (void)d;
    l->updates++;
    *changed = c != l->c;
    l->c = c;
    return WR_OK;
}

Test(newton, update_hook_lagged_quantity) {
    lagged l;
    wr_newton_problem p;
    wr_newton_desc nd;
    wr_newton_stats st;
    wr_diag d;
    double x = 0.0;
    memset(&l, 0, sizeof l);
    memset(&p, 0, sizeof p);
    p.n_blocks = 1;
    p.block = 1;
    p.user = &l;
    p.energy = l_energy;
    p.hessian = l_hessian;
    p.update = l_update;
    memset(&nd, 0, sizeof nd);
    nd.stop.grad_ref = 1.0; /* absolute: |x − c| <= 1e-8 */
    cr_assert_eq(wr_newton_solve(&p, &x, &nd, &st, &d), WR_OK, "%s", d.message);
    /* each step solves exactly for the lagged c; the residual |x − c| halves per update */
    cr_expect_float_eq(x, 2.0, 3e-8, "x %.15g", x);
    cr_expect_gt(l.updates, 20, "%d updates", l.updates);
}

Test(newton, bad_options_and_failing_start) {
    chain c;
    wr_newton_problem p;
    wr_newton_desc nd;
    wr_diag d;
    double x[3 * (CH_N + 1)];
    uint8_t fixed[3 * (CH_N + 1)];
    ch_setup(&c, &p, &nd, x, fixed);
    nd.stop.grad_tol = -1.0;
    cr_expect_eq(wr_newton_solve(&p, x, &nd, NULL, &d), WR_ERR_INVALID_ARG);
    ch_setup(&c, &p, &nd, x, fixed);
    nd.hessian.exact_retry = 1.5;
    cr_expect_eq(wr_newton_solve(&p, x, &nd, NULL, &d), WR_ERR_INVALID_ARG);
    ch_setup(&c, &p, &nd, x, fixed);
    nd.shift.raise = 0.5;
    cr_expect_eq(wr_newton_solve(&p, x, &nd, NULL, &d), WR_ERR_INVALID_ARG);
    ch_setup(&c, &p, &nd, x, fixed);
    p.block = 2;
    cr_expect_eq(wr_newton_solve(&p, x, &nd, NULL, &d), WR_ERR_INVALID_ARG);
    /* a start outside the energy's domain (two coincident vertices) is the energy's error */
    ch_setup(&c, &p, &nd, x, fixed);
    memcpy(x + 3, x, 3 * sizeof(double));
    cr_expect_eq(wr_newton_solve(&p, x, &nd, NULL, &d), WR_ERR_GEOMETRY);
    ch_setup(&c, &p, &nd, x, fixed);
    x[4] = NAN;
    cr_expect_eq(wr_newton_solve(&p, x, &nd, NULL, &d), WR_ERR_DOMAIN);
}

/* ---- the Armijo test: a full Newton step that does not decrease E must be cut ---------------------
 * E(x) = sqrt(1 + x²) (one DOF, convex, E'' > 0 everywhere): the Newton step from x is −x(1 + x²), so
 * from x0 = 1 the full step lands on x = −1 with exactly the same energy. Armijo (sufficient decrease
 * c·α·∇E·Δx < 0) rejects it and the halved step lands on the minimiser x = 0; a line search that
 * accepted non-decreasing steps would bounce between ±1 until max_iter. */
static wr_status sq_energy(void *user, const double *x, double *E, double *g, double *scale, wr_diag *d) {
    (void)user;
    (void)d;
    *E = sqrt(1.0 + x[0] * x[0]);
    if (g) g[0] = x[0] / *E;
    if (scale) *scale = *E;
    return WR_OK;
}
static wr_status sq_hessian(void *user, const double *x, wr_newton_hessian *H, wr_diag *d) {
    double B = pow(1.0 + x[0] * x[0], -1.5);
    (void)user;
    (void)d;
    return wr_newton_add_diagonal(H, 0, &B);
}

Test(newton, armijo_rejects_a_step_without_decrease) {
    wr_newton_problem p;
    wr_newton_desc nd;
    wr_newton_stats st;
    wr_diag d;
    double x[1] = {1.0};
    memset(&p, 0, sizeof p);
    p.n_blocks = 1;
    p.block = 1;
    p.energy = sq_energy;
    p.hessian = sq_hessian;
    memset(&nd, 0, sizeof nd);
    nd.shift.rel = 1e-15; /* the exact Newton step (the default shift would shorten it below |x| = 1) */
    nd.max_iter = 50;
    cr_assert_eq(wr_newton_solve(&p, x, &nd, &st, &d), WR_OK, "%s", d.message);
    cr_expect(fabs(x[0]) < 1e-8, "x = %g, want the minimiser 0", x[0]);
    cr_expect(st.iterations <= 3, "%d iterations (one halved step reaches x = 0 exactly)", (int)st.iterations);
    cr_expect(st.line_search_evals >= 2, "the full step must have been tried and cut");
}

/* ---- STEP at a jump (issue 13, docs/issue13-folds.md): a tiny full step onto a discontinuity ------
 * E(x) = ½K(x − a)² on x <= 0 and ½K(x − a)² + G x − J on x > 0 (J > 0: E jumps down across 0, and
 * the right branch's gradient is G more than the left's). From x0 = −1e-9 the Newton step of the
 * left branch lands at a = 1e-15, just across the jump: a full step of 1e-9 m that lowers E, after
 * which ‖∇E‖ = G. The dynamics' frame 11 of docs/issue13-folds.md was such a stop (a 2.8e-10 m full
 * step at 5.4e4 × the start gradient, on the mid-edge bending's jump at a 180° fold). */
typedef struct jump_problem {
    double K, a, G, J;
} jump_problem;
static wr_status jp_energy(void *user, const double *x, double *E, double *g, double *scale, wr_diag *d) {
    const jump_problem *q = (const jump_problem *)user;
    double t = x[0] - q->a, right = x[0] > 0.0;
    (void)d;
    *E = 0.5 * q->K * t * t + (right ? q->G * x[0] - q->J : 0.0);
    if (g) g[0] = q->K * t + (right ? q->G : 0.0);
    if (scale) *scale = 0.5 * q->K * t * t + (right ? fabs(q->G * x[0]) + q->J : 0.0);
    return WR_OK;
}
static wr_status jp_hessian(void *user, const double *x, wr_newton_hessian *H, wr_diag *d) {
    const jump_problem *q = (const jump_problem *)user;
    (void)x;
    (void)d;
    return wr_newton_add_diagonal(H, 0, &q->K);
}
static wr_status jp_solve(jump_problem *q, double G, wr_newton_stats *st) {
    wr_newton_problem p;
    wr_newton_desc nd;
    double x[1] = {-1e-9};
    q->K = 1e12;
    q->a = 1e-15;
    q->G = G;
    q->J = 1e-3;
    memset(&p, 0, sizeof p);
    p.n_blocks = 1;
    p.block = 1;
    p.user = q;
    p.energy = jp_energy;
    p.hessian = jp_hessian;
    memset(&nd, 0, sizeof nd);
    nd.stop.step_tol = 1e-6;
    nd.max_iter = 20;
    return wr_newton_solve(&p, x, &nd, st, NULL);
}

Test(newton, step_stop_refuses_a_tiny_step_onto_a_jump) {
    jump_problem q;
    wr_newton_stats st;
    wr_status s;
    /* ‖∇E‖ after the step 1e7 N, 1e4 × the start's 1e3 N: not a minimum, whatever the step length */
    s = jp_solve(&q, 1e7, &st);
    cr_expect_neq(st.stop, WR_NEWTON_STOP_STEP, "stop %s at |grad| %.3e (start %.3e)", wr_newton_stop_name(st.stop),
                  st.grad_norm, st.grad_norm0);
    cr_expect_eq(s, WR_ERR_NOT_CONVERGED, "status %s", wr_status_string(s));
    /* a gradient 4 × the start's after a tiny full step is still a stop (a rest state's gradient is
     * round-off, and one step can raise it a few times: the flap at rest, residual_rel up to 4.6) */
    s = jp_solve(&q, 4e3, &st);
    cr_expect_eq(s, WR_OK, "status %s", wr_status_string(s));
    cr_expect_eq(st.stop, WR_NEWTON_STOP_STEP, "stop %s", wr_newton_stop_name(st.stop));
    cr_expect_eq(st.iterations, 1);
}
