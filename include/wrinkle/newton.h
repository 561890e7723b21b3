/* wrinkle/newton.h — one Newton method for every energy of the kit: the shell statics (statics.h),
 * the TFW Sec. 4.1 TFT base surface (tfw.h through statics.h) and backward-Euler incremental
 * potentials of a dynamic simulation. The energy comes in as callbacks; the method is projected
 * Newton with a diagonal shift, a linear solve through spd.h's wr_spd solvers and a backtracking
 * Armijo line search that starts from the largest safe step a caller hook allows (continuous
 * collision detection plugs in there), as the TFW authors' newtonSolver(objective, x0, …, findMaxStep)
 * separates the energy from the method. wrinkle v0.1.0 — MIT licence (see LICENSE).
 * Needs core.h, sparse.h, spd.h (CHOLMOD with WR_USE_CHOLMOD=1, see spd.h); otherwise libc and libm.
 *
 * Minimises E(x) over the free DOFs of x (n = block · n_blocks, blocks of 3 DOFs — vertices — or 1).
 * Each step: the problem streams its element Hessians (wr_newton_add_element), each made positive
 * semidefinite on its own (ON PROJECTION) or kept exact (ON EXACT PHASE), into a matrix whose pattern
 * is built once (sparse.h ON ASSEMBLY CACHE); K + μI Δx = −∇E is solved with the fixed DOFs held
 * (ON SHIFT); the step is cut to max_step(x, Δx) and halved until Armijo holds (ON LINE SEARCH).
 *
 * API
 *   wr_newton_solve(problem, x, desc, stats, diag)   x: n initial guess in, minimiser out
 *   in the problem's hessian callback:
 *     wr_newton_add_element(H, k, blocks, Ke)        one element, projected per the step's mode
 *     wr_newton_add_element_psd(H, k, blocks, Ke)    one element known PSD (never projected)
 *     wr_newton_sink_add(H, k, blocks, Ke)           the same as a shell.h wr_hess_sink .add
 *     wr_newton_add_diagonal(H, v, B)                a block on the diagonal (contact, mass)
 *     wr_newton_constant_begin(H) / _end(H)          elements whose values never change (added once)
 *     wr_newton_hessian_exact(H)                     1 when this step assembles exact blocks
 *   wr_newton_desc_check(desc, diag)                 the option checks alone (before touching input)
 *   wr_newton_project_spd(n, A, floor)               fast PSD projection of one dense block
 *   wr_newton_stop_name(stop)                        "gradient", "step", …
 *
 * EXAMPLE (4 springs of 10 N/m in series, one DOF per vertex, held at 0, unit load at the end)
 *     static wr_status ex_energy(void *u, const double *x, double *E, double *g, double *sc, wr_diag *d) { int i; (void)u; (void)sc; (void)d; *E = -x[4]; if (g) { memset(g, 0, 5 * sizeof *g); g[4] = -1.0; } for (i = 0; i < 4; ++i) { double t = x[i + 1] - x[i]; *E += 5.0 * t * t; if (g) { g[i + 1] += 10.0 * t; g[i] -= 10.0 * t; } } return WR_OK; }
 *     static wr_status ex_hessian(void *u, const double *x, wr_newton_hessian *H, wr_diag *d) { double K[4] = {10, -10, -10, 10}; int32_t v[2], i; wr_status s; (void)u; (void)x; (void)d; for (i = 0; i < 4; ++i) { v[0] = i; v[1] = i + 1; if ((s = wr_newton_add_element_psd(H, 2, v, K)) != WR_OK) return s; } return WR_OK; }
 *     wr_newton_problem p;  wr_newton_desc nd;  wr_newton_stats st;  wr_diag d;
 *     double x[5] = {0};  uint8_t fixed[5] = {1, 0, 0, 0, 0};
 *     memset(&p, 0, sizeof p);  memset(&nd, 0, sizeof nd);   // zero = defaults
 *     p.n_blocks = 5;  p.block = 1;  p.energy = ex_energy;  p.hessian = ex_hessian;
 *     nd.fixed = fixed;
 *     if (wr_newton_solve(&p, x, &nd, &st, &d) != WR_OK) { puts(d.message); return 1; }
 *     printf("end at %.3f m after %d step(s), stop: %s\n", x[4], (int)st.iterations, wr_newton_stop_name(st.stop));
 *   (0.400 m, one step plus a second removing the 1e-8 relative error of the default shift μ)
 *
 * ON CALLBACKS (wr_newton_problem; the user pointer is passed to each)
 *   energy(x, E, grad, scale)   E(x) [J]; grad (n) overwritten when non-NULL; scale, when non-NULL,
 *       receives Σ|terms| of E (the magnitude round-off acts on, ON STOPPING; |E| when left alone).
 *       A status other than WR_OK means x is outside the energy's domain: an error at x0, +∞ in the
 *       line search. grad entries of fixed DOFs are ignored (zeroed by Newton).
 *   hessian(x, H)   streams the Hessian at x: elements through wr_newton_add_element* (dense
 *       (block·k)² row-major over blocks[0..k), negative entries dropped), vertex-diagonal blocks
 *       through wr_newton_add_diagonal. The stream should be the same elements in the same order
 *       each time (then no search: sparse.h ON ASSEMBLY CACHE); a new block outside the pattern (a new
 *       contact pair) makes Newton assemble again with a rebuilt pattern (stats.pattern_builds).
 *   max_step(x, dx)   NULL = 1; else the largest α in (0, 1] such that x + α dx is safe (CCD).
 *   update(x, iteration, changed)   NULL = none; called before every step (iteration 0 first) for
 *       lagged quantities (friction's normal forces, contact sets); *changed = 1 when E changed, then
 *       E and ∇E are evaluated again and the best iterate restarts there.
 *   progress(stats)   NULL = none; after every accepted step.
 *
 * ON STOPPING
 *   GRADIENT: ‖∇E_free‖ <= grad_tol · reference, reference = stop.grad_ref when > 0, else
 *   max(‖∇E_free(x0)‖, stop.grad_ref_min). STEP: a full step (α = 1, neither backtracked nor cut by
 *   max_step) with max|Δx| <= stop.step_tol (absolute, in x's units; 0 = off) after which ‖∇E_free‖ <=
 *   WR_NEWTON_STEP_GRAD_MAX (1e3) · reference: a tiny full step that leaves the gradient orders of
 *   magnitude above the start's landed on a jump of E (a mid-edge hinge folded flat), not on a
 *   minimum, and the solve goes on (to MAX_ITER or LINE_SEARCH if nothing better is found); a state
 *   at rest, whose start gradient is round-off, may still end with a few times that. DECREMENT (opt-in,
 *   stop.decrement_tol > 0): the Newton decrement λ² = −∇E·Δx of the step just solved satisfies
 *   λ²/2 <= decrement_tol · scale; for a convex E with the exact Hessian λ²/2 estimates E(x) − E*
 *   (Boyd & Vandenberghe 2004, Sec. 9.5), so this stops on the energy error instead of the gradient,
 *   which converges slowly where E is flat (the TFW TFT base). x is left before that last step.
 *   ROUNDOFF (WR_OK): E is a sum of many terms and cannot resolve a change below
 *   WR_NEWTON_ENERGY_NOISE (1e-12) · scale. Near convergence the line search accepts a step whose
 *   predicted decrease is below that noise when ‖∇E‖ drops instead; the solve stops after
 *   WR_NEWTON_ROUNDOFF_HITS (3) consecutive steps whose decrement is below the noise and after
 *   which ‖∇E‖ is not below 0.9 × its smallest value so far, with ‖∇E‖ <= √grad_tol · reference (a
 *   flat start at a saddle never qualifies); also when a line search fails with such a decrement.
 *   MAX_ITER and LINE_SEARCH (no decrease in WR_NEWTON_MAX_HALVINGS halvings) return
 *   WR_ERR_NOT_CONVERGED with the lowest-energy iterate in x.
 *
 * ON SHIFT
 *   K + μI with μ = shift.rel · mean |diag K| at first; μ ×100 (from at least that value) while the
 *   linear solve reports a non-SPD matrix or gives no descent direction (WR_NEWTON_MAX_SHIFT_RAISES,
 *   then steepest descent); μ ×0.1 after every full step down to WR_NEWTON_SHIFT_MIN_REL (1e-14) ·
 *   mean diagonal, the factorisation's round-off level. A fixed μ = 1e-8 · mean diagonal is not small
 *   for a slender structure whose softest mode is orders below the membrane stiffness: Newton then
 *   converges only linearly (docs/notes-statics.md). Opt-in shift.raise = r > 1: after a step the
 *   line search had to shorten, μ ×r (Levenberg–Marquardt style) up to WR_NEWTON_SHIFT_RAISE_CAP (1e6)
 *   · shift.rel · mean diagonal.
 *
 * ON PROJECTION AND THE EXACT PHASE
 *   hessian.projection = WR_PROJECT_FAST (default) makes each element block PSD with
 *   wr_newton_project_spd (a Cholesky test, then Householder + implicit QL and inverse iteration for
 *   the negative eigenpairs only), WR_PROJECT_JACOBI with core.h's cyclic Jacobi (kept to measure
 *   against), WR_PROJECT_NONE keeps exact blocks. Projection keeps Newton a descent method far from
 *   the minimum but discards real negative curvature, and near a minimum it converges only linearly.
 *   So once a full step was accepted and ‖∇E‖ <= WR_NEWTON_EXACT_SWITCH (1e-3) × reference, steps
 *   use the exact Hessian; the first time its solve reports a non-SPD matrix (or no descent) that step
 *   continues with μ raised and the rest of the solve is projected (stats.exact_steps counts exact
 *   steps). Opt-in hessian.exact_retry = q in (0, 1): after a failed exact step the exact Hessian is
 *   tried again once ‖∇E‖ <= q × its value at that failure.
 *
 * ON LINE SEARCH
 *   From α0 = max_step(x, Δx) (1 without the hook), α halves (at most WR_NEWTON_MAX_HALVINGS times)
 *   until E(x + αΔx) <= E(x) + c α ∇E·Δx, c = WR_NEWTON_ARMIJO (1e-4, Nocedal & Wright's usual
 *   value); a trial outside the domain counts as +∞. With linear.forcing = η_max > 0 each PCG solve
 *   stops at the relative residual min(η_max, max(tol, √(‖∇E‖ / reference))) (inexact Newton,
 *   Eisenstat & Walker 1996); CHOLMOD solves exactly.
 *
 * ON OWNERSHIP AND THREADS
 *   Newton allocates its work arrays, the matrix and the solver per call and frees them before it
 *   returns. No global state; callbacks run on the calling thread.
 */
#ifndef WRINKLE_NEWTON_H
#define WRINKLE_NEWTON_H

#include "core.h"
#include "sparse.h"
#include "spd.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef enum wr_newton_stop {
    WR_NEWTON_STOP_NONE = 0,
    WR_NEWTON_STOP_GRADIENT,    /* relative gradient norm below grad_tol */
    WR_NEWTON_STOP_STEP,        /* full step below step_tol */
    WR_NEWTON_STOP_MAX_ITER,    /* WR_ERR_NOT_CONVERGED */
    WR_NEWTON_STOP_LINE_SEARCH, /* no decrease found (WR_ERR_NOT_CONVERGED) */
    WR_NEWTON_STOP_ROUNDOFF,    /* Newton decrement below E's round-off (WR_OK) */
    WR_NEWTON_STOP_DECREMENT    /* Newton decrement below decrement_tol (WR_OK) */
} wr_newton_stop;

typedef enum wr_projection {
    WR_PROJECT_FAST = 0,   /* PSD test, then Householder + QL (ON PROJECTION) */
    WR_PROJECT_JACOBI = 1, /* wr_dense_project_spd (cyclic Jacobi) on every block */
    WR_PROJECT_NONE = 2    /* exact element Hessians */
} wr_projection;

typedef struct wr_newton_stats {
    int32_t iterations;        /* Newton steps taken */
    int32_t linear_iterations; /* summed over steps */
    int32_t line_search_evals; /* energy evaluations in line searches */
    int32_t exact_steps;       /* steps with the exact Hessian in a projected solve */
    int32_t elements_projected, elements_assembled; /* blocks changed by the projection / seen, summed */
    int32_t pattern_builds;    /* Hessian patterns built (1 unless the stencils changed) */
    double energy;             /* E at the returned x [J] */
    double grad_norm, grad_norm0, grad_ref; /* ‖∇E_free‖ now, at x0, the ON STOPPING reference */
    double decrement;          /* −∇E·Δx of the last solved step */
    double last_step;          /* max |αΔx| of the last accepted step */
    double shift;              /* last diagonal shift μ */
    double max_step_min;       /* smallest max_step cut over the solve (1 = never cut) */
    wr_newton_stop stop;
    double t_assembly, t_projection, t_linear, t_line_search, t_total; /* seconds (wall) */
} wr_newton_stats;

/* Assembly state of one Newton step, handed to the hessian callback (fields are Newton's). */
typedef struct wr_newton_hessian {
    wr_assembly *assembly;
    wr_projection proj;        /* this step's treatment of wr_newton_add_element blocks */
    int32_t block;
    int32_t n_proj, n_elem, const_mark, const_elem;
    double t_proj;
} wr_newton_hessian;

typedef struct wr_newton_problem {
    int32_t n_blocks; /* vertices (blocks of `block` DOFs) */
    int32_t block;    /* DOFs per block: 0 → 3, or 1 */
    void *user;
    wr_status (*energy)(void *user, const double *x, double *E, double *grad, double *scale, wr_diag *diag);
    wr_status (*hessian)(void *user, const double *x, wr_newton_hessian *H, wr_diag *diag);
    double (*max_step)(void *user, const double *x, const double *dx);
    wr_status (*update)(void *user, const double *x, int32_t iteration, int *changed, wr_diag *diag);
    void (*progress)(void *user, const wr_newton_stats *stats);
} wr_newton_problem;

/* Defaults (zero means default), ON STOPPING: grad_tol 1e-8 (relative); grad_ref 0 = measured at x0,
 * grad_ref_min 0 (floor of the measured reference, e.g. the external load's norm); step_tol 0 = off
 * (absolute [x units]); decrement_tol 0 = off (relative to the energy scale). */
typedef struct wr_newton_stop_desc {
    double grad_tol, grad_ref, grad_ref_min, step_tol, decrement_tol;
} wr_newton_stop_desc;

/* projection WR_PROJECT_FAST; exact_retry 0 = off, else q in (0, 1) (ON PROJECTION AND THE EXACT PHASE) */
typedef struct wr_newton_hessian_desc {
    wr_projection projection;
    double exact_retry;
} wr_newton_hessian_desc;

/* rel 1e-8 (μ relative to the mean diagonal); raise 0 = off, else r > 1 (ON SHIFT) */
typedef struct wr_newton_shift_desc {
    double rel, raise;
} wr_newton_shift_desc;

/* solver: spd.h options (its fixed is set by Newton from desc.fixed); forcing 0 = every solve to
 * solver.rel_tol, else η_max in (0, 1) (ON LINE SEARCH) */
typedef struct wr_newton_linear_desc {
    wr_spd_desc solver;
    double forcing;
} wr_newton_linear_desc;

/* max_iter 200; fixed NULL = none, else n flags (nonzero = DOF held at its input value); name NULL =
 * "newton" (prefix of diag messages). */
typedef struct wr_newton_desc {
    int32_t max_iter;
    const uint8_t *fixed;
    wr_newton_stop_desc stop;
    wr_newton_hessian_desc hessian;
    wr_newton_shift_desc shift;
    wr_newton_linear_desc linear;
    const char *name;
} wr_newton_desc;

/* WR_OK on GRADIENT / STEP / ROUNDOFF / DECREMENT; WR_ERR_NOT_CONVERGED (best iterate in x) on
 * MAX_ITER / LINE_SEARCH; WR_ERR_INVALID_ARG on bad options; a callback's error otherwise. */
WRDEF wr_status wr_newton_solve(const wr_newton_problem *p, double *x, const wr_newton_desc *desc,
                                wr_newton_stats *stats, wr_diag *diag);
/* The option checks of wr_newton_solve alone (defaults applied to a copy): WR_ERR_INVALID_ARG naming
 * the field, for callers that validate everything before touching their input. */
WRDEF wr_status wr_newton_desc_check(const wr_newton_desc *desc, wr_diag *diag);
/* Ke (block·k)² row-major; overwritten by its projection when 3k <= WR_DENSE_MAX and the step projects
 * (larger stencils are added unprojected: they must be PSD by construction). */
WRDEF wr_status wr_newton_add_element(wr_newton_hessian *H, int32_t k, const int32_t *blocks, double *Ke);
WRDEF wr_status wr_newton_add_element_psd(wr_newton_hessian *H, int32_t k, const int32_t *blocks, const double *Ke);
/* wr_hess_sink-compatible (shell.h): user = the wr_newton_hessian; Ke copied, then as add_element */
WRDEF wr_status wr_newton_sink_add(void *H, int32_t k, const int32_t *blocks, const double *Ke);
/* B: block×block row-major, added unprojected at diagonal block v */
WRDEF wr_status wr_newton_add_diagonal(wr_newton_hessian *H, int32_t v, const double *B);
/* 1: stream the constant elements now (first assembly), then call _end; 0: their sum was added */
WRDEF int wr_newton_constant_begin(wr_newton_hessian *H);
WRDEF void wr_newton_constant_end(wr_newton_hessian *H);
WRDEF int wr_newton_hessian_exact(const wr_newton_hessian *H);
/* In-place PSD projection of symmetric A (n×n, n <= WR_DENSE_MAX): eigenvalues below floor − τ are
 * raised to floor (τ = WR_NEWTON_PSD_TEST_REL · max|A_ii|); a block passing the Cholesky test
 * (floor = 0 only) is kept unchanged. Returns the number of raised eigenvalues (0 = A unchanged). */
WRDEF int wr_newton_project_spd(int n, double *A, double floor);
WRDEF const char *wr_newton_stop_name(wr_newton_stop stop);

#define WR_NEWTON_ARMIJO 1e-4 /* sufficient-decrease constant (Nocedal & Wright's usual value) */
#define WR_NEWTON_MAX_HALVINGS 40
#define WR_NEWTON_MAX_SHIFT_RAISES 8
/* PSD test shift relative to the largest |diagonal| of an element block: a passing block has no
 * eigenvalue below −1e-12·max|Ke_ii|, four orders under the default global shift (1e-8) */
#define WR_NEWTON_PSD_TEST_REL 1e-12
/* E is a sum of O(n) terms; a change below this fraction of Σ|terms| is not resolvable in double
 * precision (√n·ε for n up to 1e6 is ~2e-13) */
#define WR_NEWTON_ENERGY_NOISE 1e-12
/* STEP needs ‖∇E‖ <= this × the reference (ON STOPPING): a full tiny step after which the gradient is
 * that far above the start's was not taken at a minimum of a smooth E (a jump: docs/issue13-folds.md) */
#define WR_NEWTON_STEP_GRAD_MAX 1e3
#define WR_NEWTON_ROUNDOFF_HITS 3 /* consecutive round-off-level decrements that end the solve */
/* relative gradient below which a projected solve tries the exact Hessian after a full step; the
 * scene driver's hybrid Newton measured 1e-3 as past the saddle-escape phase */
#define WR_NEWTON_EXACT_SWITCH 1e-3
/* smallest μ relative to the mean diagonal: the factorisation's round-off level (ON SHIFT) */
#define WR_NEWTON_SHIFT_MIN_REL 1e-14
/* ceiling of the opt-in raise relative to shift.rel · mean diagonal: 1e-2 of the stiffness at the
 * default rel, still far below it so stiff modes keep the Newton direction */
#define WR_NEWTON_SHIFT_RAISE_CAP 1e6

#ifdef __cplusplus
}
#endif
#endif /* WRINKLE_NEWTON_H */

/* ============================================================================================ */
#ifdef WRINKLE_IMPLEMENTATION
#ifndef WRINKLE_NEWTON_IMPLEMENTATION_DONE
#define WRINKLE_NEWTON_IMPLEMENTATION_DONE

#include <float.h>
#include <math.h>
#include <string.h>

#ifdef __cplusplus
extern "C" {
#endif

#define WR__NEWTON_QL_ITERS 60 /* implicit-QL iterations per eigenvalue before falling back to Jacobi */

WRDEF const char *wr_newton_stop_name(wr_newton_stop stop) {
    switch (stop) {
    case WR_NEWTON_STOP_NONE: return "none";
    case WR_NEWTON_STOP_GRADIENT: return "gradient";
    case WR_NEWTON_STOP_STEP: return "step";
    case WR_NEWTON_STOP_MAX_ITER: return "max_iter";
    case WR_NEWTON_STOP_LINE_SEARCH: return "line_search";
    case WR_NEWTON_STOP_ROUNDOFF: return "roundoff";
    case WR_NEWTON_STOP_DECREMENT: return "decrement";
    }
    return "unknown";
}

/* ---- dense PSD projection (ON PROJECTION AND THE EXACT PHASE) ------------------------------------ */

/* Cholesky of A + τI; 1 when every pivot is positive (A has no eigenvalue below −τ). */
static int wr__newton_psd_test(int n, const double *A) {
    double L[WR_DENSE_MAX * WR_DENSE_MAX], dmax = 0.0, tau;
    int i, j, k;
    for (i = 0; i < n; ++i) dmax = fmax(dmax, fabs(A[i * n + i]));
    if (!(dmax > 0.0)) return 0;
    tau = WR_NEWTON_PSD_TEST_REL * dmax;
    for (j = 0; j < n; ++j) {
        double s = A[j * n + j] + tau;
        for (k = 0; k < j; ++k) s -= L[j * n + k] * L[j * n + k];
        if (!(s > 0.0)) return 0;
        s = sqrt(s);
        L[j * n + j] = s;
        for (i = j + 1; i < n; ++i) {
            double t = 0.5 * (A[i * n + j] + A[j * n + i]);
            for (k = 0; k < j; ++k) t -= L[i * n + k] * L[j * n + k];
            L[i * n + j] = t / s;
        }
    }
    return 1;
}
/* Householder reduction of symmetric a (destroyed) to tridiagonal T = Qᵀ a Q with Q = H_0 H_1 ⋯,
 * H_k = I − β_k v_k v_kᵀ: d diagonal, e[i] = T(i, i+1) (e[n−1] = 0); v_k stored in row k of V
 * (entries k+1..n−1), β_k in beta[k] (0 = no reflection). */
static void wr__newton_tridiag(int n, double *a, double *V, double *beta, double *d, double *e) {
    double p[WR_DENSE_MAX];
    int i, j, k;
    for (k = 0; k < n; ++k) beta[k] = 0.0;
    for (k = 0; k + 2 < n; ++k) {
        double xn = 0.0, alpha, vv = 0.0, bk, K = 0.0, *v = V + k * n;
        for (i = k + 1; i < n; ++i) xn += a[i * n + k] * a[i * n + k];
        xn = sqrt(xn);
        if (xn == 0.0) continue;
        /* reflect x = a[k+1.., k] onto alpha·e1 with the sign that avoids cancellation */
        alpha = a[(k + 1) * n + k] > 0.0 ? -xn : xn;
        for (i = k + 1; i < n; ++i) v[i] = a[i * n + k];
        v[k + 1] -= alpha;
        for (i = k + 1; i < n; ++i) vv += v[i] * v[i];
        if (vv == 0.0) continue;
        bk = beta[k] = 2.0 / vv;
        /* H A H = A − v wᵀ − w vᵀ with p = βAv, w = p − (β vᵀp / 2) v, on the trailing block */
        for (i = k + 1; i < n; ++i) {
            double sum = 0.0;
            for (j = k + 1; j < n; ++j) sum += a[i * n + j] * v[j];
            p[i] = bk * sum;
            K += v[i] * p[i];
        }
        K *= 0.5 * bk;
        for (i = k + 1; i < n; ++i) p[i] -= K * v[i];
        for (i = k + 1; i < n; ++i)
            for (j = k + 1; j < n; ++j) a[i * n + j] -= v[i] * p[j] + p[i] * v[j];
        a[(k + 1) * n + k] = a[k * n + k + 1] = alpha;
        for (i = k + 2; i < n; ++i) a[i * n + k] = a[k * n + i] = 0.0;
    }
    for (i = 0; i < n; ++i) {
        d[i] = a[i * n + i];
        e[i] = i + 1 < n ? a[(i + 1) * n + i] : 0.0;
    }
}

/* Eigenvalues of the tridiagonal (d, e) by implicit QL with Wilkinson shifts (d overwritten, e
 * destroyed). Returns 0, or −1 when an eigenvalue needs more than WR__NEWTON_QL_ITERS sweeps. */
static int wr__newton_ql(int n, double *d, double *e) {
    int l, m, i;
    for (l = 0; l < n; ++l) {
        int iter = 0;
        for (;;) {
            double g, r, s, c, pp;
            for (m = l; m + 1 < n; ++m)
                if (fabs(e[m]) <= DBL_EPSILON * (fabs(d[m]) + fabs(d[m + 1]))) break;
            if (m == l) break;
            if (++iter > WR__NEWTON_QL_ITERS) return -1;
            /* shift: the eigenvalue of the leading 2×2 of the unreduced block closer to d[l] */
            g = (d[l + 1] - d[l]) / (2.0 * e[l]);
            r = sqrt(g * g + 1.0);
            g = d[m] - d[l] + e[l] / (g + (g >= 0.0 ? r : -r));
            s = c = 1.0;
            pp = 0.0;
            r = 1.0;
            for (i = m - 1; i >= l; --i) {
                double f = s * e[i], b = c * e[i];
                r = sqrt(f * f + g * g);
                e[i + 1] = r;
                if (r == 0.0) { /* split: the bulge vanished, deflate */
                    d[i + 1] -= pp;
                    e[m] = 0.0;
                    break;
                }
                s = f / r;
                c = g / r;
                g = d[i + 1] - pp;
                r = (d[i] - g) * s + 2.0 * c * b;
                pp = s * r;
                d[i + 1] = g + pp;
                g = c * r - b;
            }
            if (r == 0.0 && i >= l) continue;
            d[l] -= pp;
            e[l] = g;
            e[m] = 0.0;
        }
    }
    return 0;
}

/* b ← (T − σI)⁻¹ b for the tridiagonal (d, e): Gaussian elimination with partial pivoting (row
 * swaps give a second superdiagonal); a zero pivot is replaced by `tiny`, as inverse iteration
 * wants (T − σI is singular to working precision when σ is an eigenvalue). */
static void wr__newton_tri_solve(int n, const double *d, const double *e, double sigma, double tiny, double *b) {
    double u0[WR_DENSE_MAX], u1[WR_DENSE_MAX], u2[WR_DENSE_MAX], l[WR_DENSE_MAX], a, bb, cc;
    int piv[WR_DENSE_MAX], i;
    a = d[0] - sigma;
    bb = n > 1 ? e[0] : 0.0;
    cc = 0.0;
    for (i = 0; i + 1 < n; ++i) {
        double na = e[i], nb = d[i + 1] - sigma, nc = i + 2 < n ? e[i + 1] : 0.0, m;
        if (fabs(a) >= fabs(na)) {
            if (a == 0.0) a = tiny;
            m = na / a;
            u0[i] = a, u1[i] = bb, u2[i] = cc, piv[i] = 0, l[i] = m;
            a = nb - m * bb;
            bb = nc - m * cc;
        } else {
            m = a / na;
            u0[i] = na, u1[i] = nb, u2[i] = nc, piv[i] = 1, l[i] = m;
            a = bb - m * nb;
            bb = cc - m * nc;
        }
        cc = 0.0;
    }
    u0[n - 1] = a == 0.0 ? tiny : a;
    for (i = 0; i + 1 < n; ++i) {
        if (piv[i]) {
            double t = b[i];
            b[i] = b[i + 1];
            b[i + 1] = t;
        }
        b[i + 1] -= l[i] * b[i];
    }
    for (i = n - 1; i >= 0; --i) {
        double t = b[i];
        if (i + 1 < n) t -= u1[i] * b[i + 1];
        if (i + 2 < n) t -= u2[i] * b[i + 2];
        b[i] = t / u0[i];
    }
}

WRDEF int wr_newton_project_spd(int n, double *A, double floor) {
    double a[WR_DENSE_MAX * WR_DENSE_MAX], V[WR_DENSE_MAX * WR_DENSE_MAX], Y[WR_DENSE_MAX * WR_DENSE_MAX];
    double lam[WR_DENSE_MAX], d[WR_DENSE_MAX], e[WR_DENSE_MAX], e2[WR_DENSE_MAX], beta[WR_DENSE_MAX], tn = 0.0;
    double dmax = 0.0, tau;
    int i, j, k, it, raised = 0;
    WR_ASSERT(n > 0 && n <= WR_DENSE_MAX);
    if (floor == 0.0 && wr__newton_psd_test(n, A)) return 0;
    for (i = 0; i < n; ++i)
        for (j = 0; j < n; ++j) a[i * n + j] = 0.5 * (A[i * n + j] + A[j * n + i]);
    wr__newton_tridiag(n, a, V, beta, d, e);
    memcpy(lam, d, sizeof(double) * (size_t)n);
    memcpy(e2, e, sizeof(double) * (size_t)n);
    if (wr__newton_ql(n, lam, e2) != 0) return wr_dense_project_spd(n, A, floor);
    for (i = 0; i < n; ++i) {
        tn = fmax(tn, fabs(d[i]) + 2.0 * fabs(e[i]));
        dmax = fmax(dmax, fabs(A[i * n + i]));
    }
    /* eigenvalues within τ below the floor are left alone, as in the Cholesky test */
    tau = WR_NEWTON_PSD_TEST_REL * dmax;
    for (k = 0; k < n; ++k) {
        double *y = Y + raised * n, nrm;
        if (!(lam[k] < floor - tau)) continue;
        /* eigenvector of T by inverse iteration at the computed eigenvalue (converges in 1–2 solves
         * since σ is accurate to ε‖T‖), re-orthogonalised against the eigenvectors already found so
         * a cluster of negative eigenvalues yields an orthonormal set */
        for (i = 0; i < n; ++i) y[i] = 1.0 + 0.1 * (double)((i * 7 + k * 3) % 11);
        for (it = 0; it < 3; ++it) {
            int q;
            wr__newton_tri_solve(n, d, e, lam[k], DBL_EPSILON * (tn > 0.0 ? tn : 1.0), y);
            for (q = 0; q < raised; ++q) {
                double dot = 0.0;
                for (i = 0; i < n; ++i) dot += Y[q * n + i] * y[i];
                for (i = 0; i < n; ++i) y[i] -= dot * Y[q * n + i];
            }
            nrm = 0.0;
            for (i = 0; i < n; ++i) nrm += y[i] * y[i];
            nrm = sqrt(nrm);
            if (!(nrm > 0.0) || nrm - nrm != 0.0) return wr_dense_project_spd(n, A, floor);
            for (i = 0; i < n; ++i) y[i] /= nrm;
        }
        lam[raised] = lam[k];
        ++raised;
    }
    if (!raised) return 0;
    for (i = 0; i < n; ++i)
        for (j = 0; j < i; ++j) A[i * n + j] = A[j * n + i] = 0.5 * (A[i * n + j] + A[j * n + i]);
    for (k = 0; k < raised; ++k) {
        double *y = Y + k * n, z[WR_DENSE_MAX], c = lam[k] - floor;
        int q;
        /* back to A's basis: z = Q y = H_0 (H_1 (⋯ H_{n−3} y)) */
        memcpy(z, y, sizeof(double) * (size_t)n);
        for (q = n - 3; q >= 0; --q) {
            double dot = 0.0;
            if (beta[q] == 0.0) continue;
            for (i = q + 1; i < n; ++i) dot += V[q * n + i] * z[i];
            dot *= beta[q];
            for (i = q + 1; i < n; ++i) z[i] -= dot * V[q * n + i];
        }
        /* remove the offending eigenpair: A ← A − (λ − floor) z zᵀ */
        for (i = 0; i < n; ++i) {
            double zi = c * z[i];
            for (j = 0; j < n; ++j) A[i * n + j] -= zi * z[j];
        }
    }
    return raised;
}

/* ---- element assembly (called from the problem's hessian callback) ------------------------------ */

WRDEF wr_status wr_newton_add_element(wr_newton_hessian *H, int32_t k, const int32_t *blocks, double *Ke) {
    int32_t n = H->block * k;
    if (n > 0 && n <= WR_DENSE_MAX) {
        H->n_elem++;
        if (H->proj != WR_PROJECT_NONE) {
            double t0 = wr_time_seconds();
            int r = H->proj == WR_PROJECT_JACOBI ? wr_dense_project_spd(n, Ke, 0.0) : wr_newton_project_spd(n, Ke, 0.0);
            if (r) H->n_proj++;
            H->t_proj += wr_time_seconds() - t0;
        }
    }
    /* larger stencils (quadratic bending at high valence) must be PSD by construction: added as given */
    return wr_assembly_add(H->assembly, k, blocks, Ke, NULL);
}

WRDEF wr_status wr_newton_add_element_psd(wr_newton_hessian *H, int32_t k, const int32_t *blocks, const double *Ke) {
    return wr_assembly_add(H->assembly, k, blocks, Ke, NULL);
}

WRDEF wr_status wr_newton_sink_add(void *user, int32_t k, const int32_t *blocks, const double *Ke) {
    wr_newton_hessian *H = (wr_newton_hessian *)user;
    double buf[WR_DENSE_MAX * WR_DENSE_MAX];
    int32_t n = H->block * k;
    if (n <= 0 || n > WR_DENSE_MAX) return wr_newton_add_element_psd(H, k, blocks, Ke);
    memcpy(buf, Ke, sizeof(double) * (size_t)(n * n));
    return wr_newton_add_element(H, k, blocks, buf);
}

WRDEF wr_status wr_newton_add_diagonal(wr_newton_hessian *H, int32_t v, const double *B) {
    return wr_assembly_add_diagonal(H->assembly, v, B, NULL);
}

WRDEF int wr_newton_constant_begin(wr_newton_hessian *H) {
    int r = wr_assembly_constant_begin(H->assembly);
    H->const_mark = H->n_elem;
    if (!r) H->n_elem += H->const_elem; /* counted as if streamed */
    return r;
}

WRDEF void wr_newton_constant_end(wr_newton_hessian *H) {
    H->const_elem = H->n_elem - H->const_mark;
    wr_assembly_constant_end(H->assembly);
}

WRDEF int wr_newton_hessian_exact(const wr_newton_hessian *H) { return H->proj == WR_PROJECT_NONE; }

/* ---- the method ---------------------------------------------------------------------------------- */

typedef struct wr__newton {
    const wr_newton_problem *p;
    wr_newton_desc d;
    const char *name;
    int32_t n;
    double *g, *dx, *xt, *xbest, *gt, *diagv;
    int32_t *dpos;
    int32_t builds_seen;
    wr_assembly A;
    wr_newton_hessian H;
    wr_spd_solver S;
    int have_S;
    double lin_tol;
    /* iteration state */
    double Pi, Pibest, Pscale, gref, gbest, shift, mean_diag, exact_retry_g;
    int exact_ok, last_full, use_exact;
    int32_t roundoff_hits;
    wr_newton_stats st;
} wr__newton;

static double wr__newton_norm(const double *v, int32_t n) {
    double s = 0.0;
    int32_t i;
    for (i = 0; i < n; ++i) s += v[i] * v[i];
    return sqrt(s);
}

static wr_status wr__newton_defaults(wr_newton_desc *d, const wr_newton_desc *desc, wr_diag *diag) {
    if (desc)
        *d = *desc;
    else
        memset(d, 0, sizeof *d);
    if (!d->name) d->name = "newton";
    if (d->max_iter == 0) d->max_iter = 200;
    if (d->stop.grad_tol == 0.0) d->stop.grad_tol = 1e-8;
    if (d->shift.rel == 0.0) d->shift.rel = 1e-8;
    if (d->max_iter < 0 || !(d->stop.grad_tol > 0.0) || !(d->shift.rel > 0.0) || !(d->stop.step_tol >= 0.0) ||
        !(d->stop.grad_ref >= 0.0) || !(d->stop.grad_ref_min >= 0.0) || !(d->stop.decrement_tol >= 0.0))
        return wr_fail(diag, WR_ERR_INVALID_ARG, -1,
                       "%s: max_iter %d, grad_tol %g, shift rel %g must be positive; step_tol %g, grad_ref %g, "
                       "grad_ref_min %g, decrement_tol %g non-negative",
                       d->name, (int)d->max_iter, d->stop.grad_tol, d->shift.rel, d->stop.step_tol, d->stop.grad_ref,
                       d->stop.grad_ref_min, d->stop.decrement_tol);
    if (!(d->linear.forcing >= 0.0 && d->linear.forcing < 1.0))
        return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "%s: linear forcing %g must be in [0, 1)", d->name, d->linear.forcing);
    if (!(d->shift.raise == 0.0 || (d->shift.raise > 1.0 && d->shift.raise - d->shift.raise == 0.0)))
        return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "%s: shift_raise %g must be 0 (off) or > 1", d->name, d->shift.raise);
    if (!(d->hessian.exact_retry == 0.0 || (d->hessian.exact_retry > 0.0 && d->hessian.exact_retry < 1.0)))
        return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "%s: exact_retry %g must be 0 (off) or in (0, 1)", d->name,
                       d->hessian.exact_retry);
    if ((int)d->hessian.projection < 0 || (int)d->hessian.projection > (int)WR_PROJECT_NONE)
        return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "%s: unknown projection %d", d->name, (int)d->hessian.projection);
    return WR_OK;
}

WRDEF wr_status wr_newton_desc_check(const wr_newton_desc *desc, wr_diag *diag) {
    wr_newton_desc d;
    return wr__newton_defaults(&d, desc, diag);
}

/* E (and ∇E with fixed DOFs zeroed, and the round-off scale) at x; non-OK = outside the domain */
static wr_status wr__newton_eval(wr__newton *c, const double *x, double *E, double *g, double *scale, wr_diag *diag) {
    double sc = -1.0;
    int32_t i;
    wr_status rs = c->p->energy(c->p->user, x, E, g, scale ? &sc : NULL, diag);
    if (rs != WR_OK) return rs;
    if (!(*E - *E == 0.0)) return wr_fail(diag, WR_ERR_DOMAIN, -1, "%s: energy is not finite", c->name);
    if (g && c->d.fixed)
        for (i = 0; i < c->n; ++i)
            if (c->d.fixed[i]) g[i] = 0.0;
    if (scale) *scale = sc >= 0.0 ? sc : fabs(*E);
    return WR_OK;
}

static wr_status wr__newton_setup(wr__newton *c, const wr_newton_problem *p, double *x, wr_diag *diag) {
    int32_t i, n;
    wr_status rs;
    c->p = p;
    c->name = c->d.name;
    c->st.max_step_min = 1.0;
    if (!p || !x || !p->energy || !p->hessian || p->n_blocks < 0 || (p->block != 0 && p->block != 1 && p->block != 3))
        return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "%s: NULL problem, x or callback, or block %d not 1 or 3", c->name,
                       p ? (int)p->block : 0);
    c->H.block = p->block ? p->block : 3;
    if ((rs = wr_assembly_init(&c->A, p->n_blocks, c->H.block, diag)) != WR_OK) return rs;
    c->H.assembly = &c->A;
    c->n = n = c->H.block * p->n_blocks;
    c->g = (double *)wr_alloc_array((size_t)n + 1, sizeof(double));
    c->dx = (double *)wr_alloc_array((size_t)n + 1, sizeof(double));
    c->xt = (double *)wr_alloc_array((size_t)n + 1, sizeof(double));
    c->xbest = (double *)wr_alloc_array((size_t)n + 1, sizeof(double));
    c->gt = (double *)wr_alloc_array((size_t)n + 1, sizeof(double));
    c->diagv = (double *)wr_alloc_array((size_t)n + 1, sizeof(double));
    if (!c->g || !c->dx || !c->xt || !c->xbest || !c->gt || !c->diagv)
        return wr_fail(diag, WR_ERR_NOMEM, -1, "%s: out of memory (%d DOFs)", c->name, (int)n);
    for (i = 0; i < n; ++i)
        if (!(x[i] - x[i] == 0.0))
            return wr_fail(diag, WR_ERR_DOMAIN, i / c->H.block, "%s: DOF %d is not finite", c->name, (int)i);
    c->d.linear.solver.fixed = c->d.fixed;
    c->exact_ok = 1;
    c->exact_retry_g = -1.0;
    c->gbest = HUGE_VAL;
    if ((rs = wr__newton_eval(c, x, &c->Pi, c->g, &c->Pscale, diag)) != WR_OK) return rs;
    memcpy(c->xbest, x, sizeof(double) * (size_t)n);
    c->Pibest = c->Pi;
    c->st.grad_norm0 = c->st.grad_norm = wr__newton_norm(c->g, n);
    c->gbest = c->st.grad_norm0;
    c->gref = c->d.stop.grad_ref > 0.0 ? c->d.stop.grad_ref : fmax(c->st.grad_norm0, c->d.stop.grad_ref_min);
    c->st.grad_ref = c->gref;
    c->st.energy = c->Pi;
    return WR_OK;
}

static void wr__newton_free(wr__newton *c) {
    if (c->have_S) wr_spd_solver_free(&c->S);
    wr_assembly_free(&c->A);
    wr_free(c->g);
    wr_free(c->dx);
    wr_free(c->xt);
    wr_free(c->xbest);
    wr_free(c->gt);
    wr_free(c->diagv);
    wr_free(c->dpos);
}

/* One Hessian at x into c->A (again with a new pattern when the stencils changed); a new pattern
 * also means new diagonal positions and a new linear solver (symbolic work on the pattern). */
static wr_status wr__newton_assemble(wr__newton *c, const double *x, wr_diag *diag) {
    double t0 = wr_time_seconds();
    int pass;
    wr_status rs = WR_OK;
    int32_t i;
    c->H.proj = c->use_exact ? WR_PROJECT_NONE : c->d.hessian.projection;
    c->H.n_proj = c->H.n_elem = 0;
    c->H.t_proj = 0.0;
    for (pass = 0; pass < 2; ++pass) {
        wr_assembly_begin(&c->A);
        if ((rs = c->p->hessian(c->p->user, x, &c->H, diag)) != WR_OK) return rs;
        if ((rs = wr_assembly_end(&c->A, diag)) != WR_OK) return rs;
        if (!c->A.stale) break;
        c->H.n_proj = c->H.n_elem = 0; /* stencils changed: the second pass records the new pattern */
    }
    if (c->A.stale)
        return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "%s: the Hessian stream changed between two passes at one x", c->name);
    if (c->A.builds != c->builds_seen) {
        c->builds_seen = c->A.builds;
        wr_free(c->dpos);
        c->dpos = (int32_t *)wr_alloc_array((size_t)c->n + 1, sizeof(int32_t));
        if (!c->dpos) return wr_fail(diag, WR_ERR_NOMEM, -1, "%s: out of memory (%d DOFs)", c->name, (int)c->n);
        for (i = 0; i < c->n; ++i) c->dpos[i] = wr_csr_find(&c->A.A, i, i);
        if (c->have_S) wr_spd_solver_free(&c->S);
        c->have_S = 0;
    }
    c->st.pattern_builds = c->A.builds;
    c->st.elements_projected += c->H.n_proj;
    c->st.elements_assembled += c->H.n_elem;
    c->st.t_projection += c->H.t_proj;
    c->st.t_assembly += wr_time_seconds() - t0 - c->H.t_proj;
    return WR_OK;
}

/* (K + μI) Δx = −∇E, raising μ while the matrix is not SPD or the direction not a descent (ON SHIFT);
 * steepest descent when nothing works. Returns ∇E·Δx in *gdx and whether the solver gave Δx. */
static wr_status wr__newton_direction(wr__newton *c, double *gdx, int *from_solver, wr_diag *diag) {
    wr_csr *K = &c->A.A;
    int32_t i, n = c->n, raises;
    double t0, sum = 0.0;
    wr_status rs = WR_OK;
    wr_spd_stats ls;
    wr_csr_diagonal(K, c->diagv);
    for (i = 0; i < n; ++i) sum += fabs(c->diagv[i]);
    c->mean_diag = sum / n;
    if (!(c->mean_diag > 0.0)) c->mean_diag = 1.0;
    if (c->shift == 0.0) c->shift = c->d.shift.rel * c->mean_diag;
    t0 = wr_time_seconds();
    *gdx = 0.0;
    for (raises = 0;; ++raises) {
        for (i = 0; i < n; ++i) {
            K->val[c->dpos[i]] = c->diagv[i] + c->shift;
            c->dx[i] = 0.0;
            c->xt[i] = -c->g[i];
        }
        if (!c->have_S) {
            if ((rs = wr_spd_solver_create(&c->S, K, &c->d.linear.solver, diag)) != WR_OK) return rs;
            c->have_S = 1;
            c->lin_tol = c->S.rel_tol;
        }
        if (c->d.linear.forcing > 0.0 && c->S.method != WR_SOLVER_CHOLMOD) /* inexact Newton (ON LINE SEARCH) */
            c->S.rel_tol = fmin(c->d.linear.forcing, fmax(c->lin_tol, sqrt(c->st.grad_norm / c->gref)));
        rs = wr_spd_solver_factor(&c->S, K, diag);
        if (rs == WR_OK) rs = wr_spd_solver_solve(&c->S, K, c->xt, c->dx, &ls, diag);
        if (rs == WR_OK || rs == WR_ERR_NOT_CONVERGED) {
            c->st.linear_iterations += ls.iterations;
            *gdx = 0.0;
            for (i = 0; i < n; ++i) *gdx += c->g[i] * c->dx[i];
            if (*gdx < 0.0) break;
        }
        /* the exact Hessian is indefinite here: shift this step, project from the next one on */
        if (c->use_exact) {
            c->exact_ok = 0;
            if (c->d.hessian.exact_retry > 0.0) c->exact_retry_g = c->d.hessian.exact_retry * c->st.grad_norm;
        }
        if ((rs != WR_OK && rs != WR_ERR_NOT_SPD && rs != WR_ERR_NOT_CONVERGED) || raises == WR_NEWTON_MAX_SHIFT_RAISES)
            break;
        /* from a decayed μ straight back to at least the initial shift */
        c->shift = fmax(c->shift * 100.0, c->d.shift.rel * c->mean_diag);
    }
    c->st.t_linear += wr_time_seconds() - t0;
    c->st.shift = c->shift;
    if (rs != WR_OK && rs != WR_ERR_NOT_CONVERGED && rs != WR_ERR_NOT_SPD) return rs;
    *gdx = 0.0;
    for (i = 0; i < n; ++i) *gdx += c->g[i] * c->dx[i];
    *from_solver = *gdx < 0.0;
    if (!(*gdx < 0.0)) {
        double sc = 1.0 / c->mean_diag;
        for (i = 0; i < n; ++i) c->dx[i] = -sc * c->g[i];
        *gdx = 0.0;
        for (i = 0; i < n; ++i) *gdx += c->g[i] * c->dx[i];
    }
    return WR_OK;
}

/* Backtracking Armijo from α0 (ON LINE SEARCH); the accepted trial is left in c->xt. 0 = failed. */
static int wr__newton_line_search(wr__newton *c, const double *x, double alpha0, double gdx, double *alpha) {
    int32_t i, n = c->n;
    int h;
    double Pit = 0.0;
    *alpha = alpha0;
    for (h = 0; h < WR_NEWTON_MAX_HALVINGS; ++h, *alpha *= 0.5) {
        for (i = 0; i < n; ++i) c->xt[i] = x[i] + *alpha * c->dx[i];
        c->st.line_search_evals++;
        if (wr__newton_eval(c, c->xt, &Pit, NULL, NULL, NULL) != WR_OK) continue;
        if (Pit <= c->Pi + WR_NEWTON_ARMIJO * *alpha * gdx) return 1;
        if (-*alpha * gdx <= WR_NEWTON_ENERGY_NOISE * c->Pscale && Pit <= c->Pi + WR_NEWTON_ENERGY_NOISE * c->Pscale) {
            /* round-off regime: E cannot resolve the decrease; accept when the gradient drops */
            if (wr__newton_eval(c, c->xt, &Pit, c->gt, NULL, NULL) == WR_OK &&
                wr__newton_norm(c->gt, n) < c->st.grad_norm)
                return 1;
        }
    }
    return 0;
}

/* x ← the accepted trial; μ, the exact phase, the round-off counter and the stats follow it */
static wr_status wr__newton_accept(wr__newton *c, double *x, double alpha, double alpha0, double gdx, wr_diag *diag) {
    int32_t i, n = c->n;
    double maxstep = 0.0, Pscale0 = c->Pscale, gn;
    wr_status rs;
    for (i = 0; i < n; ++i) maxstep = fmax(maxstep, fabs(alpha * c->dx[i]));
    memcpy(x, c->xt, sizeof(double) * (size_t)n);
    if ((rs = wr__newton_eval(c, x, &c->Pi, c->g, &c->Pscale, diag)) != WR_OK) return rs;
    /* full steps relax μ towards the factorisation's round-off; opt-in: backtracked ones raise it */
    if (alpha == 1.0)
        c->shift = fmax(c->shift * 0.1, WR_NEWTON_SHIFT_MIN_REL * c->mean_diag);
    else if (c->d.shift.raise > 0.0 && alpha < alpha0)
        c->shift = fmax(c->shift, fmin(c->shift * c->d.shift.raise, WR_NEWTON_SHIFT_RAISE_CAP * c->d.shift.rel * c->mean_diag));
    c->last_full = alpha == 1.0;
    if (c->use_exact) c->st.exact_steps++;
    /* round-off (ON STOPPING): decrement below what E resolves AND no new 10 % low of the gradient */
    gn = wr__newton_norm(c->g, n);
    if (-gdx <= WR_NEWTON_ENERGY_NOISE * Pscale0 && gn <= sqrt(c->d.stop.grad_tol) * c->gref && gn > 0.9 * c->gbest)
        c->roundoff_hits++;
    else
        c->roundoff_hits = 0;
    c->gbest = fmin(c->gbest, gn);
    c->st.iterations++;
    c->st.energy = c->Pi;
    c->st.grad_norm = gn;
    c->st.last_step = maxstep;
    if (c->Pi <= c->Pibest) {
        c->Pibest = c->Pi;
        memcpy(c->xbest, x, sizeof(double) * (size_t)n);
    }
    return WR_OK;
}

/* the update hook (lagged quantities): E may have changed, so everything measured at x is renewed */
static wr_status wr__newton_update(wr__newton *c, double *x, int32_t it, int *changed, wr_diag *diag) {
    wr_status rs;
    *changed = 0;
    if (!c->p->update) return WR_OK;
    if ((rs = c->p->update(c->p->user, x, it, changed, diag)) != WR_OK || !*changed) return rs;
    if ((rs = wr__newton_eval(c, x, &c->Pi, c->g, &c->Pscale, diag)) != WR_OK) return rs;
    c->st.grad_norm = c->gbest = wr__newton_norm(c->g, c->n);
    c->st.energy = c->Pibest = c->Pi;
    memcpy(c->xbest, x, sizeof(double) * (size_t)c->n);
    c->roundoff_hits = 0;
    return WR_OK;
}

/* one Newton step: assemble, solve, search, accept; sets c->st.stop when the solve ends here */
static wr_status wr__newton_step(wr__newton *c, double *x, double t_start, wr_diag *diag) {
    double gdx, alpha, alpha0, t0, gtol = c->d.stop.grad_tol * c->gref;
    int from_solver = 0;
    wr_status rs;
    /* ON PROJECTION AND THE EXACT PHASE: near a minimum after a full step, try the exact Hessian */
    c->use_exact = c->d.hessian.projection != WR_PROJECT_NONE && (c->exact_ok || c->st.grad_norm <= c->exact_retry_g) &&
                   c->last_full && c->st.grad_norm <= WR_NEWTON_EXACT_SWITCH * c->gref;
    if ((rs = wr__newton_assemble(c, x, diag)) != WR_OK) return rs;
    if ((rs = wr__newton_direction(c, &gdx, &from_solver, diag)) != WR_OK) return rs;
    c->st.decrement = -gdx;
    if (c->d.stop.decrement_tol > 0.0 && from_solver && -0.5 * gdx <= c->d.stop.decrement_tol * c->Pscale) {
        c->st.stop = WR_NEWTON_STOP_DECREMENT;
        return WR_OK;
    }
    t0 = wr_time_seconds();
    alpha0 = c->p->max_step ? c->p->max_step(c->p->user, x, c->dx) : 1.0;
    if (!(alpha0 <= 1.0)) alpha0 = 1.0;
    c->st.max_step_min = fmin(c->st.max_step_min, alpha0);
    if (!wr__newton_line_search(c, x, alpha0, gdx, &alpha)) {
        c->st.t_line_search += wr_time_seconds() - t0;
        /* no decrease E can resolve with the decrement at round-off: as converged as double allows */
        c->st.stop = (-gdx <= WR_NEWTON_ENERGY_NOISE * c->Pscale && c->st.grad_norm <= sqrt(c->d.stop.grad_tol) * c->gref)
                         ? WR_NEWTON_STOP_ROUNDOFF
                         : WR_NEWTON_STOP_LINE_SEARCH;
        return WR_OK;
    }
    c->st.t_line_search += wr_time_seconds() - t0;
    if ((rs = wr__newton_accept(c, x, alpha, alpha0, gdx, diag)) != WR_OK) return rs;
    c->st.t_total = wr_time_seconds() - t_start;
    if (c->p->progress) c->p->progress(c->p->user, &c->st);
    if (c->st.grad_norm <= gtol)
        c->st.stop = WR_NEWTON_STOP_GRADIENT;
    /* only a full step is small because the minimum is near; a cut one may just be stalled */
    else if (c->d.stop.step_tol > 0.0 && c->st.last_step <= c->d.stop.step_tol && alpha == 1.0 &&
             c->st.grad_norm <= WR_NEWTON_STEP_GRAD_MAX * c->gref)
        c->st.stop = WR_NEWTON_STOP_STEP;
    else if (c->roundoff_hits >= WR_NEWTON_ROUNDOFF_HITS)
        c->st.stop = WR_NEWTON_STOP_ROUNDOFF;
    return WR_OK;
}

WRDEF wr_status wr_newton_solve(const wr_newton_problem *p, double *x, const wr_newton_desc *desc,
                                wr_newton_stats *stats, wr_diag *diag) {
    wr__newton c;
    double t_start = wr_time_seconds();
    int32_t it;
    int changed = 0, updated = 0;
    wr_status rs;
    memset(&c, 0, sizeof c);
    if (stats) {
        memset(stats, 0, sizeof *stats);
        stats->max_step_min = 1.0;
    }
    if ((rs = wr__newton_defaults(&c.d, desc, diag)) != WR_OK) return rs;
    if ((rs = wr__newton_setup(&c, p, x, diag)) != WR_OK) goto done;
    for (it = 0; it < c.d.max_iter && c.st.stop == WR_NEWTON_STOP_NONE; ++it) {
        if (!updated && (rs = wr__newton_update(&c, x, it, &changed, diag)) != WR_OK) goto done;
        updated = 0;
        if (c.st.grad_norm <= c.d.stop.grad_tol * c.gref || c.gref == 0.0) {
            c.st.stop = WR_NEWTON_STOP_GRADIENT;
            break;
        }
        if ((rs = wr__newton_step(&c, x, t_start, diag)) != WR_OK) goto done;
        if (c.st.stop == WR_NEWTON_STOP_GRADIENT && c.p->update) {
            /* converged for the lagged quantities of this step: renew them before believing it */
            if ((rs = wr__newton_update(&c, x, it + 1, &changed, diag)) != WR_OK) goto done;
            updated = 1;
            if (changed) c.st.stop = WR_NEWTON_STOP_NONE;
        }
    }
    if (c.st.stop == WR_NEWTON_STOP_NONE) c.st.stop = WR_NEWTON_STOP_MAX_ITER;
    if (c.st.stop == WR_NEWTON_STOP_MAX_ITER || c.st.stop == WR_NEWTON_STOP_LINE_SEARCH) {
        if (c.Pibest < c.Pi) {
            memcpy(x, c.xbest, sizeof(double) * (size_t)c.n);
            wr__newton_eval(&c, x, &c.Pi, c.g, NULL, NULL);
            c.st.energy = c.Pi;
            c.st.grad_norm = wr__newton_norm(c.g, c.n);
        }
        rs = wr_fail(diag, WR_ERR_NOT_CONVERGED, c.st.iterations, "%s: %s after %d Newton steps, |grad| %.3e (target %.3e)",
                     c.name, c.st.stop == WR_NEWTON_STOP_MAX_ITER ? "max_iter reached" : "line search failed",
                     (int)c.st.iterations, c.st.grad_norm, c.d.stop.grad_tol * c.gref);
    }
done:
    c.st.t_total = wr_time_seconds() - t_start;
    if (stats) *stats = c.st;
    wr__newton_free(&c);
    return rs;
}

#ifdef __cplusplus
}
#endif
#endif /* WRINKLE_NEWTON_IMPLEMENTATION_DONE */
#endif /* WRINKLE_IMPLEMENTATION */
