/* wrinkle/statics.h — static equilibrium of a shell (shell.h) under gravity and prescribed vertices:
 * projected Newton with backtracking line search, linear solves through pcg.h.
 * wrinkle v0.1.0 — MIT licence (see LICENSE). Needs core.h, sparse.h, pcg.h (CHOLMOD when built
 * with WR_USE_CHOLMOD=1, see pcg.h), mesh.h, tft.h, shell.h.
 *
 * Minimises Π(x) = E_shell(x) − Σ_v m_v g·x_v over the free vertices (TFW Sec. 4.1 base surface with
 * the TFT membrane; the StVK reference statics with the mid-edge membrane+bending). Each Newton step
 * assembles the element Hessians, projects each to its nearest PSD matrix (wr_dense_project_spd, as
 * TFW App. E does for its SQP), adds a diagonal shift μ·I (μ = shift_rel · mean diagonal, raised ×100
 * while the linear solve reports a non-SPD matrix), solves K Δx = −∇Π with the prescribed DOFs held,
 * and backtracks (Armijo, c = 1e-4, halving) on Π. A trial state where the energy is undefined
 * (degenerate face) counts as +∞.
 *
 * API
 *   wr_statics_solve(shell, x, desc, stats, diag)   x: nv*3 initial guess in, equilibrium out
 *
 * EXAMPLE
 *     wr_statics_desc sd; wr_statics_stats st;
 *     memset(&sd, 0, sizeof sd);
 *     sd.gravity[2] = -9.81; sd.fixed = pinned; sd.perturb = 1e-4; // seeded out-of-plane kick
 *     if (wr_statics_solve(&shell, x, &sd, &st, &d) != WR_OK) puts(d.message);
 *     printf("%d Newton steps, |g| %.2e\n", st.iterations, st.grad_norm);
 *
 * ON STOPPING
 *   Converged when ‖∇Π_free‖ <= grad_tol · max(‖∇Π_free(x0)‖, ‖f_ext,free‖) (stop GRADIENT), or when
 *   the accepted step max|αΔx| <= step_tol · (bounding-box diagonal) (stop STEP). max_iter reached,
 *   or a line search that cannot decrease Π in 40 halvings, returns WR_ERR_NOT_CONVERGED with the best
 *   (lowest-Π) iterate in x.
 *
 * ON THREADS
 *   No global state; the progress callback runs on the calling thread.
 */
#ifndef WRINKLE_STATICS_H
#define WRINKLE_STATICS_H

#include "core.h"
#include "sparse.h"
#include "pcg.h"
#include "shell.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef enum wr_statics_stop {
    WR_STATICS_STOP_NONE = 0,
    WR_STATICS_STOP_GRADIENT,   /* relative gradient norm below grad_tol */
    WR_STATICS_STOP_STEP,       /* accepted step below step_tol */
    WR_STATICS_STOP_MAX_ITER,   /* WR_ERR_NOT_CONVERGED */
    WR_STATICS_STOP_LINE_SEARCH /* no decrease found (WR_ERR_NOT_CONVERGED) */
} wr_statics_stop;

typedef struct wr_statics_stats {
    int32_t iterations;         /* Newton steps taken */
    int32_t linear_iterations;  /* summed over steps */
    int32_t line_search_evals;  /* energy evaluations in line searches */
    double energy;              /* Π at the returned x [J] */
    double grad_norm, grad_norm0, grad_ref; /* ‖∇Π_free‖ now, at x0, and the reference of ON STOPPING [N] */
    double last_step;           /* max |αΔx| of the last accepted step [m] */
    double shift;               /* last diagonal shift μ used */
    wr_statics_stop stop;
    double t_assembly, t_projection, t_linear, t_line_search, t_total; /* seconds */
} wr_statics_stats;

/* Defaults (zero means default):
 *   max_iter 200; grad_tol 1e-8 (relative, see ON STOPPING); step_tol 1e-13 (relative to the
 *   bounding-box diagonal); gravity (0,0,0) m/s² (needs shell density > 0 to matter);
 *   fixed NULL = none, else nv flags (nonzero = vertex prescribed); target NULL = prescribed vertices
 *   keep their input position, else nv*3 positions whose fixed rows are used;
 *   perturb 0 = none, else the standard deviation [m] of a seeded normal displacement of the free
 *   vertices along their area-weighted vertex normal (breaks the symmetry of flat starts), seed used
 *   as given (0 is a valid seed); shift_rel 1e-8 (diagonal shift relative to the mean diagonal);
 *   no_projection 0 = project element Hessians to PSD; linear: pcg.h options (fixed is set here);
 *   progress NULL, else called after every Newton step. */
typedef struct wr_statics_desc {
    int32_t max_iter;
    double grad_tol;
    double step_tol;
    double gravity[3];
    const uint8_t *fixed;
    const double *target;
    double perturb;
    uint64_t seed;
    double shift_rel;
    int32_t no_projection;
    wr_spd_desc linear;
    void (*progress)(void *user, const wr_statics_stats *stats);
    void *progress_user;
} wr_statics_desc;

WRDEF wr_status wr_statics_solve(const wr_shell *s, double *x, const wr_statics_desc *desc, wr_statics_stats *stats,
                                 wr_diag *diag);

#ifdef __cplusplus
}
#endif
#endif /* WRINKLE_STATICS_H */

/* ============================================================================================ */
#ifdef WRINKLE_IMPLEMENTATION
#ifndef WRINKLE_STATICS_IMPLEMENTATION_DONE
#define WRINKLE_STATICS_IMPLEMENTATION_DONE

#include <math.h>
#include <string.h>

#ifdef __cplusplus
extern "C" {
#endif

#define WR__STATICS_ARMIJO 1e-4   /* sufficient-decrease constant (Nocedal & Wright's usual value) */
#define WR__STATICS_MAX_HALVINGS 40
#define WR__STATICS_MAX_SHIFT_RAISES 8

typedef struct wr__statics_sink {
    wr_triplets *t; /* first assembly: collect the pattern */
    wr_csr *A;      /* later: add into the fixed pattern */
    int project;
    double t_proj;
    wr_status st;
} wr__statics_sink;

static wr_status wr__statics_add(void *user, int32_t k, const int32_t *verts, const double *Ke) {
    wr__statics_sink *S = (wr__statics_sink *)user;
    double buf[WR_DENSE_MAX * WR_DENSE_MAX];
    int32_t idx[WR_DENSE_MAX], a, i, n = 3 * k;
    const double *K = Ke;
    if (n <= WR_DENSE_MAX) {
        for (a = 0; a < k; ++a)
            for (i = 0; i < 3; ++i) idx[3 * a + i] = 3 * verts[a] + i;
        if (S->project) {
            double t0 = wr_time_seconds();
            memcpy(buf, Ke, sizeof(double) * (size_t)(n * n));
            wr_dense_project_spd(n, buf, 0.0);
            S->t_proj += wr_time_seconds() - t0;
            K = buf;
        }
        return S->t ? wr_triplets_add_element(S->t, n, idx, K, NULL) : wr_csr_add_element(S->A, n, idx, K, NULL);
    }
    /* large stencils (quadratic bending at high valence) are PSD by construction: add 3×3 blocks */
    for (a = 0; a < k; ++a) {
        int32_t b;
        for (b = 0; b < k; ++b) {
            double B[9];
            int j;
            wr_status st;
            for (i = 0; i < 3; ++i)
                for (j = 0; j < 3; ++j) B[3 * i + j] = Ke[(3 * a + i) * n + 3 * b + j];
            st = S->t ? wr_triplets_add_block3(S->t, verts[a], verts[b], B, NULL)
                      : wr_csr_add_block3(S->A, verts[a], verts[b], B, NULL);
            if (st != WR_OK) return st;
        }
    }
    return WR_OK;
}

/* Π and ∇Π (gradient zeroed on fixed DOFs when g != NULL). */
static wr_status wr__statics_energy(const wr_shell *s, const double *x, const double *fext, const uint8_t *fixv,
                                    double *Pi, double *g, wr_diag *diag) {
    double E;
    int32_t i, n = 3 * s->nv;
    wr_status st = wr_shell_energy(s, x, &E, g, diag);
    if (st != WR_OK) return st;
    for (i = 0; i < n; ++i) {
        E -= fext[i] * x[i];
        if (g) g[i] = (fixv && fixv[i / 3]) ? 0.0 : g[i] - fext[i];
    }
    *Pi = E;
    return WR_OK;
}

static double wr__statics_norm(const double *v, int32_t n) {
    double s = 0.0;
    int32_t i;
    for (i = 0; i < n; ++i) s += v[i] * v[i];
    return sqrt(s);
}

WRDEF wr_status wr_statics_solve(const wr_shell *s, double *x, const wr_statics_desc *desc, wr_statics_stats *stats,
                                 wr_diag *diag) {
    wr_statics_desc d;
    wr_statics_stats st;
    int32_t n, i, it;
    double *fext = NULL, *g = NULL, *dx = NULL, *xt = NULL, *xbest = NULL, *mass = NULL, *diagv = NULL;
    uint8_t *fixd = NULL;
    wr_triplets T;
    wr_csr A;
    wr_spd_solver S;
    int have_A = 0, have_S = 0;
    wr_status rs = WR_OK;
    double Pi, Pibest, gref, bbox, t_start = wr_time_seconds(), shift;
    memset(&st, 0, sizeof st);
    memset(&T, 0, sizeof T);
    memset(&A, 0, sizeof A);
    memset(&S, 0, sizeof S);
    if (stats) *stats = st;
    if (!s || !x || !s->faces) return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "statics: NULL shell or x");
    if (desc)
        d = *desc;
    else
        memset(&d, 0, sizeof d);
    if (d.max_iter == 0) d.max_iter = 200;
    if (d.grad_tol == 0.0) d.grad_tol = 1e-8;
    if (d.step_tol == 0.0) d.step_tol = 1e-13;
    if (d.shift_rel == 0.0) d.shift_rel = 1e-8;
    if (d.max_iter < 0 || !(d.grad_tol > 0.0) || !(d.step_tol > 0.0) || !(d.shift_rel > 0.0) || !(d.perturb >= 0.0))
        return wr_fail(diag, WR_ERR_INVALID_ARG, -1,
                       "statics: max_iter %d, grad_tol %g, step_tol %g, shift_rel %g, perturb %g must be positive",
                       (int)d.max_iter, d.grad_tol, d.step_tol, d.shift_rel, d.perturb);
    n = 3 * s->nv;
    fext = (double *)wr_calloc_array((size_t)n, sizeof(double));
    g = (double *)wr_alloc_array((size_t)n, sizeof(double));
    dx = (double *)wr_alloc_array((size_t)n, sizeof(double));
    xt = (double *)wr_alloc_array((size_t)n, sizeof(double));
    xbest = (double *)wr_alloc_array((size_t)n, sizeof(double));
    mass = (double *)wr_alloc_array((size_t)s->nv, sizeof(double));
    diagv = (double *)wr_alloc_array((size_t)n, sizeof(double));
    fixd = (uint8_t *)wr_calloc_array((size_t)n, 1);
    if (!fext || !g || !dx || !xt || !xbest || !mass || !diagv || !fixd) {
        rs = wr_fail(diag, WR_ERR_NOMEM, -1, "statics: out of memory (%d DOFs)", (int)n);
        goto done;
    }
    /* external load: lumped gravity m_v g */
    wr_shell_vertex_masses(s, mass);
    for (i = 0; i < n; ++i) fext[i] = mass[i / 3] * d.gravity[i % 3];
    if (d.fixed)
        for (i = 0; i < n; ++i) {
            fixd[i] = d.fixed[i / 3] != 0;
            if (fixd[i] && d.target) x[i] = d.target[i];
        }
    for (i = 0; i < n; ++i)
        if (!(x[i] == x[i]) || x[i] - x[i] != 0.0) {
            rs = wr_fail(diag, WR_ERR_DOMAIN, i / 3, "statics: vertex %d has a non-finite coordinate", (int)(i / 3));
            goto done;
        }
    if (d.perturb > 0.0) {
        /* seeded kick along area-weighted vertex normals (flat starts are saddle points of buckling) */
        wr_rng rng;
        double *nrm = diagv;
        int32_t f, k;
        memset(nrm, 0, sizeof(double) * (size_t)n);
        for (f = 0; f < s->nf; ++f) {
            const int32_t *t = s->faces + 3 * f;
            wr_vec3 e1 = wr_v3_sub(wr_v3_load(x + 3 * t[1]), wr_v3_load(x + 3 * t[0]));
            wr_vec3 e2 = wr_v3_sub(wr_v3_load(x + 3 * t[2]), wr_v3_load(x + 3 * t[0]));
            wr_vec3 c = wr_v3_cross(e1, e2);
            for (k = 0; k < 3; ++k) {
                nrm[3 * t[k]] += c.x;
                nrm[3 * t[k] + 1] += c.y;
                nrm[3 * t[k] + 2] += c.z;
            }
        }
        wr_rng_seed(&rng, d.seed);
        for (i = 0; i < s->nv; ++i) {
            wr_vec3 nv = wr_v3_normalized(wr_v3_load(nrm + 3 * i));
            double a = d.perturb * wr_rng_normal(&rng);
            if (fixd[3 * i]) continue;
            x[3 * i] += a * nv.x;
            x[3 * i + 1] += a * nv.y;
            x[3 * i + 2] += a * nv.z;
        }
    }
    {
        double lo[3] = {1e300, 1e300, 1e300}, hi[3] = {-1e300, -1e300, -1e300};
        for (i = 0; i < n; ++i) {
            lo[i % 3] = fmin(lo[i % 3], x[i]);
            hi[i % 3] = fmax(hi[i % 3], x[i]);
        }
        bbox = sqrt((hi[0] - lo[0]) * (hi[0] - lo[0]) + (hi[1] - lo[1]) * (hi[1] - lo[1]) +
                    (hi[2] - lo[2]) * (hi[2] - lo[2]));
    }
    rs = wr__statics_energy(s, x, fext, d.fixed, &Pi, g, diag);
    if (rs != WR_OK) goto done;
    memcpy(xbest, x, sizeof(double) * (size_t)n);
    Pibest = Pi;
    st.grad_norm0 = st.grad_norm = wr__statics_norm(g, n);
    {
        double fe = 0.0;
        for (i = 0; i < n; ++i)
            if (!fixd[i]) fe += fext[i] * fext[i];
        gref = fmax(st.grad_norm0, sqrt(fe));
    }
    st.grad_ref = gref;
    st.energy = Pi;
    shift = 0.0;
    d.linear.fixed = fixd;
    for (it = 0; it < d.max_iter; ++it) {
        wr__statics_sink sk;
        wr_hess_sink hs;
        wr_spd_stats ls;
        double t0, gdx, alpha, mean_diag = 0.0, maxstep;
        int raises;
        if (st.grad_norm <= d.grad_tol * gref || gref == 0.0) {
            st.stop = WR_STATICS_STOP_GRADIENT;
            break;
        }
        /* assemble */
        t0 = wr_time_seconds();
        memset(&sk, 0, sizeof sk);
        sk.project = !d.no_projection;
        if (!have_A) {
            rs = wr_triplets_create(&T, n, (int64_t)s->nf * 324, diag);
            if (rs != WR_OK) goto done;
            sk.t = &T;
        } else {
            wr_csr_zero_values(&A);
            sk.A = &A;
        }
        hs.user = &sk;
        hs.add = wr__statics_add;
        rs = wr_shell_hessian_elements(s, x, 0, &hs, diag);
        if (rs != WR_OK) goto done;
        if (!have_A) {
            /* identity diagonal entries so the pattern holds the shift even on isolated DOFs */
            for (i = 0; i < n; ++i)
                if ((rs = wr_triplets_add(&T, i, i, 0.0, diag)) != WR_OK) goto done;
            rs = wr_csr_from_triplets(&A, &T, diag);
            wr_triplets_free(&T);
            if (rs != WR_OK) goto done;
            have_A = 1;
        }
        st.t_projection += sk.t_proj;
        st.t_assembly += wr_time_seconds() - t0 - sk.t_proj;
        wr_csr_diagonal(&A, diagv);
        for (i = 0; i < n; ++i) mean_diag += fabs(diagv[i]);
        mean_diag = mean_diag / n;
        if (!(mean_diag > 0.0)) mean_diag = 1.0;
        if (shift == 0.0) shift = d.shift_rel * mean_diag;
        /* solve (K + μI) Δx = −g, raising μ while the matrix is not SPD */
        t0 = wr_time_seconds();
        for (raises = 0;; ++raises) {
            for (i = 0; i < n; ++i) {
                int32_t p = wr_csr_find(&A, i, i);
                A.val[p] = diagv[i] + shift;
                dx[i] = 0.0;
                xt[i] = -g[i];
            }
            if (!have_S) {
                rs = wr_spd_solver_create(&S, &A, &d.linear, diag);
                if (rs != WR_OK) goto done;
                have_S = 1;
            }
            rs = wr_spd_solver_factor(&S, &A, diag);
            if (rs == WR_OK) rs = wr_spd_solver_solve(&S, &A, xt, dx, &ls, diag);
            if (rs == WR_OK || rs == WR_ERR_NOT_CONVERGED) {
                st.linear_iterations += ls.iterations;
                gdx = 0.0;
                for (i = 0; i < n; ++i) gdx += g[i] * dx[i];
                if (gdx < 0.0) break;
            }
            if ((rs != WR_OK && rs != WR_ERR_NOT_SPD && rs != WR_ERR_NOT_CONVERGED) ||
                raises == WR__STATICS_MAX_SHIFT_RAISES)
                break;
            shift *= 100.0;
        }
        st.t_linear += wr_time_seconds() - t0;
        st.shift = shift;
        if (rs != WR_OK && rs != WR_ERR_NOT_CONVERGED && rs != WR_ERR_NOT_SPD) goto done;
        gdx = 0.0;
        for (i = 0; i < n; ++i) gdx += g[i] * dx[i];
        if (!(gdx < 0.0)) {
            /* no descent direction from the linear solver: fall back to steepest descent */
            double sc = 1.0 / mean_diag;
            for (i = 0; i < n; ++i) dx[i] = -sc * g[i];
            gdx = 0.0;
            for (i = 0; i < n; ++i) gdx += g[i] * dx[i];
        }
        rs = WR_OK;
        /* backtracking line search on Π */
        t0 = wr_time_seconds();
        alpha = 1.0;
        {
            int h, ok = 0;
            double Pit = 0.0;
            for (h = 0; h < WR__STATICS_MAX_HALVINGS; ++h, alpha *= 0.5) {
                for (i = 0; i < n; ++i) xt[i] = x[i] + alpha * dx[i];
                st.line_search_evals++;
                if (wr__statics_energy(s, xt, fext, d.fixed, &Pit, NULL, NULL) != WR_OK) continue;
                if (Pit <= Pi + WR__STATICS_ARMIJO * alpha * gdx) {
                    ok = 1;
                    break;
                }
            }
            st.t_line_search += wr_time_seconds() - t0;
            if (!ok) {
                st.stop = WR_STATICS_STOP_LINE_SEARCH;
                break;
            }
        }
        maxstep = 0.0;
        for (i = 0; i < n; ++i) maxstep = fmax(maxstep, fabs(alpha * dx[i]));
        memcpy(x, xt, sizeof(double) * (size_t)n);
        rs = wr__statics_energy(s, x, fext, d.fixed, &Pi, g, diag);
        if (rs != WR_OK) goto done;
        /* successful full steps relax the shift back towards its floor */
        if (alpha == 1.0) shift = fmax(shift * 0.1, d.shift_rel * mean_diag);
        st.iterations = it + 1;
        st.energy = Pi;
        st.grad_norm = wr__statics_norm(g, n);
        st.last_step = maxstep;
        if (Pi <= Pibest) {
            Pibest = Pi;
            memcpy(xbest, x, sizeof(double) * (size_t)n);
        }
        st.t_total = wr_time_seconds() - t_start;
        if (d.progress) d.progress(d.progress_user, &st);
        if (st.grad_norm <= d.grad_tol * gref) {
            st.stop = WR_STATICS_STOP_GRADIENT;
            break;
        }
        if (maxstep <= d.step_tol * bbox) {
            st.stop = WR_STATICS_STOP_STEP;
            break;
        }
    }
    if (st.stop == WR_STATICS_STOP_NONE) st.stop = WR_STATICS_STOP_MAX_ITER;
    if (st.stop == WR_STATICS_STOP_MAX_ITER || st.stop == WR_STATICS_STOP_LINE_SEARCH) {
        if (Pibest < Pi) {
            memcpy(x, xbest, sizeof(double) * (size_t)n);
            wr__statics_energy(s, x, fext, d.fixed, &Pi, g, NULL);
            st.energy = Pi;
            st.grad_norm = wr__statics_norm(g, n);
        }
        rs = wr_fail(diag, WR_ERR_NOT_CONVERGED, st.iterations,
                     "statics: %s after %d Newton steps, |grad| %.3e (target %.3e)",
                     st.stop == WR_STATICS_STOP_MAX_ITER ? "max_iter reached" : "line search failed",
                     (int)st.iterations, st.grad_norm, d.grad_tol * gref);
    }
done:
    st.t_total = wr_time_seconds() - t_start;
    if (stats) *stats = st;
    if (have_S) wr_spd_solver_free(&S);
    if (have_A) wr_csr_free(&A);
    wr_triplets_free(&T);
    wr_free(fext);
    wr_free(g);
    wr_free(dx);
    wr_free(xt);
    wr_free(xbest);
    wr_free(mass);
    wr_free(diagv);
    wr_free(fixd);
    return rs;
}

#ifdef __cplusplus
}
#endif
#endif /* WRINKLE_STATICS_IMPLEMENTATION_DONE */
#endif /* WRINKLE_IMPLEMENTATION */
