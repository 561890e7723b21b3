/* wrinkle/eigen.h — the lowest eigenpairs and the inertia of a sparse symmetric matrix K (the
 * unprojected Hessian of an energy at an equilibrium), with fixed (Dirichlet) DOFs removed and an
 * optional diagonal metric M: K v = λ M v. What statics.h's stability test (ON STABILITY) asks:
 * is the equilibrium a minimum (no λ < 0), and along which modes does it lose stability.
 * wrinkle v0.1.0 — MIT licence (see LICENSE).
 *
 * DEPENDENCIES
 *   sparse.h, core.h. The inertia needs CHOLMOD (WR_USE_CHOLMOD=1, as spd.h: libsuitesparse-dev,
 *   -I/usr/include/suitesparse, -lcholmod); the eigenpairs need CHOLMOD and ARPACK-ng
 *   (WR_USE_ARPACK=1: Debian libarpack2-dev, <arpack/arpack.h>, -larpack; BSD-3 licence). Without
 *   them the functions return WR_ERR_UNSUPPORTED. Why these: CHOLMOD's simplicial LDLᵀ factors an
 *   indefinite matrix without pivoting, so its D gives the inertia (Sylvester's law) and the same
 *   factor applies (K − σM)⁻¹ for ARPACK's implicitly restarted Lanczos in shift-invert mode
 *   (Lehoucq, Sorensen & Yang, ARPACK Users' Guide, 1998, Sec. 3.2 mode 3), the standard way to
 *   the eigenvalues nearest a shift of a large sparse pencil. A home-made Lanczos would need its
 *   own reorthogonalisation and restarts; ARPACK is the well-kept one.
 *
 * API (create/free pair: wr_eigen_lowest fills a result, wr_eigen_result_free releases it)
 *   wr_eigen_inertia(K, fixed, metric, sigma, n_below, n_zero, diag)   # eigenvalues of the pencil
 *                                                    (K_ff, M_ff) below σ (LDLᵀ of K_ff − σM_ff)
 *   wr_eigen_lowest(K, desc, result, diag)           the nev lowest eigenpairs, ascending
 *   wr_eigen_result_free(result)
 *
 * EXAMPLE (the 1D Dirichlet Laplacian, n = 50: λ_k = 2 − 2cos(kπ/51))
 *     wr_triplets t;  wr_csr K;  wr_eigen_desc ed;  wr_eigen_result er;  wr_diag d;  int32_t i;
 *     if (wr_triplets_create(&t, 50, 150, &d) != WR_OK) { puts(d.message); return 1; }
 *     for (i = 0; i < 50; ++i) {
 *         wr_triplets_add(&t, i, i, 2.0, &d);
 *         if (i + 1 < 50) { wr_triplets_add(&t, i, i + 1, -1.0, &d);  wr_triplets_add(&t, i + 1, i, -1.0, &d); }
 *     }
 *     if (wr_csr_from_triplets(&K, &t, &d) != WR_OK) { puts(d.message); return 1; }
 *     wr_triplets_free(&t);
 *     memset(&ed, 0, sizeof ed);  ed.nev = 3;                       // zero = defaults
 *     if (wr_eigen_lowest(&K, &ed, &er, &d) != WR_OK) { puts(d.message); return 1; }
 *     printf("lowest %.6f (exact %.6f), %d negative\n", er.values[0], 2.0 - 2.0 * cos(3.14159265358979 / 51), (int)er.n_negative);
 *     wr_eigen_result_free(&er);  wr_csr_free(&K);
 *
 * ON THE PENCIL AND THE METRIC
 *   Only the free DOFs count: K_ff v = λ M_ff v with M = diag(metric) (NULL = I). A metric of
 *   lumped vertex areas makes λ an energy per unit area and displacement² [Pa/m for a shell],
 *   nearly independent of the mesh, so the lowest eigenvalue of one state can be compared across
 *   meshes (statics.h uses it). Returned vectors are M-orthonormal (vᵀMv = 1) and zero on fixed DOFs.
 *
 * ON THE SEARCH (wr_eigen_lowest)
 *   1. LDLᵀ of K_ff − σ0 M_ff at σ0 = desc.sigma (default −neg_rel · scale, scale =
 *      mean diag(K_ff) / mean(M_ff)): n_negative = # λ < σ0 (so n_negative counts eigenvalues
 *      "negative beyond the stated tolerance"; a zero pivot moves σ0 down by scale·1e-6 and retries).
 *   2. ARPACK dsaupd/dseupd in shift-invert mode about σ, which = "LM": the nev eigenvalues nearest σ.
 *   3. The set is the nev lowest once it holds every eigenvalue below σ (n_below from the LDLᵀ
 *      at σ); otherwise σ moves below the lowest found by twice the found spread and 2–3 repeat, at
 *      most WR_EIGEN_MAX_SHIFTS times (result.complete = 0 if that did not suffice).
 *   Each pair's residual ‖Kv − λMv‖ / (‖Kv‖ + |λ|‖Mv‖) is checked (result.residual, the largest).
 *
 * ON THREADS AND MEMORY
 *   No global state. CHOLMOD and ARPACK allocate with malloc (not WR_MALLOC); ARPACK-ng's debug
 *   and timing commons are global in the Fortran library but untouched here (no debug output).
 */
#ifndef WRINKLE_EIGEN_H
#define WRINKLE_EIGEN_H

#include "core.h"
#include "sparse.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Defaults (zero means default):
 *   nev 4 pairs; ncv 0 → max(2·nev + 1, 24) Lanczos vectors (at most the free DOFs); tol 0 → 1e-10
 *   (ARPACK's relative accuracy of the Ritz values); max_iter 0 → 500 restarts; has_sigma 0 →
 *   σ0 = −neg_rel · scale (ON THE SEARCH; neg_rel 0 → WR_EIGEN_NEG_REL), else sigma [λ units]; fixed NULL = none, else n
 *   flags; metric NULL = I, else n weights > 0 (only the free ones are read); seed for the start vector. */
typedef struct wr_eigen_desc {
    int32_t nev, ncv, max_iter;
    double tol;
    int32_t has_sigma;
    double sigma, neg_rel;
    const uint8_t *fixed;
    const double *metric;
    uint64_t seed;
} wr_eigen_desc;

typedef struct wr_eigen_result {
    int32_t n;          /* DOFs of K */
    int32_t nev;        /* pairs returned (ascending λ) */
    double *values;     /* nev eigenvalues */
    double *vectors;    /* nev × n, row k = mode k (M-normalised, 0 on fixed DOFs) */
    int32_t n_negative; /* # eigenvalues below σ0 (the inertia's negative count) */
    int32_t complete;   /* 1: every eigenvalue below the final σ was found (the set is the lowest) */
    double sigma0, sigma, scale; /* first and final shift, the scale of ON THE SEARCH */
    double residual;    /* largest relative residual of the returned pairs */
    int32_t restarts, op_applies, factorizations;
    double t_factor, t_lanczos; /* seconds */
} wr_eigen_result;

/* # eigenvalues of (K_ff, M_ff) below sigma and # zero pivots of the LDLᵀ of K_ff − σM_ff
 * (Sylvester). WR_ERR_UNSUPPORTED without CHOLMOD; WR_ERR_INVALID_ARG on a bad metric (item = DOF). */
WRDEF wr_status wr_eigen_inertia(const wr_csr *K, const uint8_t *fixed, const double *metric, double sigma,
                                 int32_t *n_below, int32_t *n_zero, wr_diag *diag);
/* The nev lowest eigenpairs (ON THE SEARCH). WR_ERR_UNSUPPORTED without ARPACK and CHOLMOD;
 * WR_ERR_INVALID_ARG (nev outside [1, n_free − 1], bad metric or options); WR_ERR_NOT_CONVERGED when
 * ARPACK converged fewer than nev pairs (those it found are returned, result.nev says how many);
 * WR_ERR_BACKEND on another ARPACK or CHOLMOD failure. The result is freeable on every return. */
WRDEF wr_status wr_eigen_lowest(const wr_csr *K, const wr_eigen_desc *desc, wr_eigen_result *result, wr_diag *diag);
WRDEF void wr_eigen_result_free(wr_eigen_result *result);

/* negative-eigenvalue tolerance relative to scale = mean diag(K_ff) / mean(M_ff): an eigenvalue above
 * −1e-9·scale is not resolved as negative. The LDLᵀ's backward error is ~1e-16·‖K‖ and ‖K‖/scale is
 * O(10–100) for shell Hessians, so 1e-9 sits five orders above round-off and far below buckling
 * eigenvalues (the stretched sheet's are ~1e-4·scale, validate_statics_stability). */
#define WR_EIGEN_NEG_REL 1e-9
#define WR_EIGEN_MAX_SHIFTS 4 /* shift moves of ON THE SEARCH step 3 */

#ifdef __cplusplus
}
#endif
#endif /* WRINKLE_EIGEN_H */

/* ============================================================================================ */
#ifdef WRINKLE_IMPLEMENTATION
#ifndef WRINKLE_EIGEN_IMPLEMENTATION_DONE
#define WRINKLE_EIGEN_IMPLEMENTATION_DONE

#include <math.h>
#include <string.h>
#if defined(WR_USE_CHOLMOD) && WR_USE_CHOLMOD
#include <cholmod.h>
#endif
#if defined(WR_USE_ARPACK) && WR_USE_ARPACK && defined(WR_USE_CHOLMOD) && WR_USE_CHOLMOD
#include <arpack/arpack.h>
#endif

#ifdef __cplusplus
extern "C" {
#endif

WRDEF void wr_eigen_result_free(wr_eigen_result *r) {
    if (!r) return;
    wr_free(r->values);
    wr_free(r->vectors);
    memset(r, 0, sizeof *r);
}

#if defined(WR_USE_CHOLMOD) && WR_USE_CHOLMOD
/* K_ff (lower triangle, CSC) and its LDLᵀ factor; the reduced numbering of the free DOFs */
typedef struct wr__eig_ldl {
    cholmod_common cc;
    int started;
    cholmod_sparse *A;
    cholmod_factor *L;
    int32_t nf, *free_of, *src, *dpos; /* dpos[k]: entry of A holding the diagonal of reduced column k */
    double *m;                          /* nf metric weights */
} wr__eig_ldl;

static void wr__eig_ldl_free(wr__eig_ldl *F) {
    if (F->started) {
        if (F->L) cholmod_l_free_factor(&F->L, &F->cc);
        if (F->A) cholmod_l_free_sparse(&F->A, &F->cc);
        cholmod_l_finish(&F->cc);
    }
    wr_free(F->free_of);
    wr_free(F->src);
    wr_free(F->dpos);
    wr_free(F->m);
    memset(F, 0, sizeof *F);
}

/* the reduced lower triangle of K (every diagonal present) and a simplicial LDLᵀ analysis */
static wr_status wr__eig_ldl_create(wr__eig_ldl *F, const wr_csr *K, const uint8_t *fixed, const double *metric,
                                    wr_diag *diag) {
    int32_t i, p, *red, nz = 0;
    SuiteSparse_long *Ap, *Ai;
    memset(F, 0, sizeof *F);
    red = (int32_t *)wr_alloc_array((size_t)K->n + 1, sizeof(int32_t));
    F->free_of = (int32_t *)wr_alloc_array((size_t)K->n + 1, sizeof(int32_t));
    F->m = (double *)wr_alloc_array((size_t)K->n + 1, sizeof(double));
    F->dpos = (int32_t *)wr_alloc_array((size_t)K->n + 1, sizeof(int32_t));
    F->src = (int32_t *)wr_alloc_array((size_t)K->nnz + (size_t)K->n + 1, sizeof(int32_t));
    if (!red || !F->free_of || !F->m || !F->dpos || !F->src) {
        wr_free(red);
        return wr_fail(diag, WR_ERR_NOMEM, -1, "eigen: out of memory (%d DOFs)", (int)K->n);
    }
    for (i = 0; i < K->n; ++i) {
        red[i] = -1;
        if (fixed && fixed[i]) continue;
        if (metric && !(metric[i] > 0.0 && metric[i] - metric[i] == 0.0)) {
            wr_free(red);
            return wr_fail(diag, WR_ERR_INVALID_ARG, i, "eigen: metric[%d] = %g must be finite and > 0", (int)i, metric[i]);
        }
        F->m[F->nf] = metric ? metric[i] : 1.0;
        F->free_of[F->nf] = i;
        red[i] = F->nf++;
    }
    if (!cholmod_l_start(&F->cc)) {
        wr_free(red);
        return wr_fail(diag, WR_ERR_BACKEND, -1, "eigen: CHOLMOD start failed");
    }
    F->started = 1;
    F->cc.print = 0;
    F->cc.supernodal = CHOLMOD_SIMPLICIAL; /* LDLᵀ, no square roots: indefinite matrices factor too */
    F->cc.final_ll = 0;
    F->A = cholmod_l_allocate_sparse((size_t)F->nf, (size_t)F->nf, (size_t)K->nnz + (size_t)K->n, 1, 1, -1,
                                     CHOLMOD_REAL, &F->cc);
    if (!F->A) {
        wr_free(red);
        return wr_fail(diag, WR_ERR_NOMEM, -1, "eigen: CHOLMOD allocate_sparse failed");
    }
    Ap = (SuiteSparse_long *)F->A->p;
    Ai = (SuiteSparse_long *)F->A->i;
    for (i = 0; i < K->n; ++i) {
        int have_diag = 0;
        if (red[i] < 0) continue;
        Ap[red[i]] = nz;
        for (p = K->rowptr[i]; p < K->rowptr[i + 1]; ++p) {
            int32_t j = K->col[p];
            if (j < i || red[j] < 0) continue;
            if (j > i && !have_diag) { /* a structurally missing diagonal: a zero entry, for the shift */
                F->dpos[red[i]] = nz, F->src[nz] = -1, Ai[nz++] = red[i];
                have_diag = 1;
            }
            if (j == i) F->dpos[red[i]] = nz, have_diag = 1;
            F->src[nz] = p;
            Ai[nz++] = red[j];
        }
        if (!have_diag) F->dpos[red[i]] = nz, F->src[nz] = -1, Ai[nz++] = red[i];
    }
    Ap[F->nf] = nz;
    wr_free(red);
    F->L = cholmod_l_analyze(F->A, &F->cc);
    if (!F->L || F->cc.status < CHOLMOD_OK) return wr_fail(diag, WR_ERR_BACKEND, -1, "eigen: CHOLMOD analyze failed");
    return WR_OK;
}

/* LDLᵀ of K_ff − σM_ff; n_below = # negative D, n_zero = # zero D (Sylvester's law of inertia) */
static wr_status wr__eig_ldl_factor(wr__eig_ldl *F, const wr_csr *K, double sigma, int32_t *n_below, int32_t *n_zero,
                                    wr_diag *diag) {
    double *x = (double *)F->A->x;
    SuiteSparse_long *Lp;
    double *Lx;
    int32_t k, nneg = 0, nzero = 0;
    size_t q, nz = (size_t)((SuiteSparse_long *)F->A->p)[F->nf];
    for (q = 0; q < nz; ++q) x[q] = F->src[q] >= 0 ? K->val[F->src[q]] : 0.0;
    for (k = 0; k < F->nf; ++k) x[F->dpos[k]] -= sigma * F->m[k];
    /* a zero pivot stops CHOLMOD at L->minor with status NOT_POSDEF; negative pivots pass (LDLᵀ) */
    if (!cholmod_l_factorize(F->A, F->L, &F->cc) || F->cc.status < CHOLMOD_OK)
        return wr_fail(diag, F->cc.status == CHOLMOD_OUT_OF_MEMORY ? WR_ERR_NOMEM : WR_ERR_BACKEND, -1,
                       "eigen: CHOLMOD factorize failed (status %d)", (int)F->cc.status);
    if (F->L->is_super || F->L->is_ll)
        return wr_fail(diag, WR_ERR_BACKEND, -1, "eigen: CHOLMOD did not return a simplicial LDL' factor");
    Lp = (SuiteSparse_long *)F->L->p;
    Lx = (double *)F->L->x;
    for (k = 0; k < (int32_t)F->L->minor && k < F->nf; ++k) {
        double dk = Lx[Lp[k]]; /* simplicial LDLᵀ keeps D on L's diagonal */
        nneg += dk < 0.0;
        nzero += dk == 0.0;
    }
    if ((int32_t)F->L->minor < F->nf) nzero++;
    if (n_below) *n_below = nneg;
    if (n_zero) *n_zero = nzero;
    return WR_OK;
}
#endif

WRDEF wr_status wr_eigen_inertia(const wr_csr *K, const uint8_t *fixed, const double *metric, double sigma,
                                 int32_t *n_below, int32_t *n_zero, wr_diag *diag) {
#if defined(WR_USE_CHOLMOD) && WR_USE_CHOLMOD
    wr__eig_ldl F;
    wr_status rs;
    if (!K || !K->rowptr || K->n < 1 || !(sigma - sigma == 0.0))
        return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "eigen: NULL or empty matrix, or non-finite sigma %g", sigma);
    rs = wr__eig_ldl_create(&F, K, fixed, metric, diag);
    if (rs == WR_OK) rs = wr__eig_ldl_factor(&F, K, sigma, n_below, n_zero, diag);
    wr__eig_ldl_free(&F);
    return rs;
#else
    (void)K, (void)fixed, (void)metric, (void)sigma, (void)n_below, (void)n_zero;
    return wr_fail(diag, WR_ERR_UNSUPPORTED, -1, "eigen: the inertia needs CHOLMOD (define WR_USE_CHOLMOD=1)");
#endif
}

#if defined(WR_USE_ARPACK) && WR_USE_ARPACK && defined(WR_USE_CHOLMOD) && WR_USE_CHOLMOD
/* one shift-invert Lanczos run: the state of ARPACK's reverse communication */
typedef struct wr__eig_run {
    wr__eig_ldl *F;
    int32_t nf, nev, ncv, lworkl;
    double *resid, *v, *workd, *workl, *d, *z;
    a_int *select;
    a_int iparam[11], ipntr[14];
    cholmod_dense *b;
} wr__eig_run;

static void wr__eig_run_free(wr__eig_run *R) {
    wr_free(R->resid), wr_free(R->v), wr_free(R->workd), wr_free(R->workl), wr_free(R->d), wr_free(R->z);
    wr_free(R->select);
    if (R->b) cholmod_l_free_dense(&R->b, &R->F->cc);
}

/* y = (K − σM)⁻¹ u (reduced numbering) through the LDLᵀ factor */
static wr_status wr__eig_apply(wr__eig_run *R, const double *u, double *y, wr_diag *diag) {
    cholmod_dense *X;
    int32_t k;
    memcpy(R->b->x, u, sizeof(double) * (size_t)R->nf);
    X = cholmod_l_solve(CHOLMOD_A, R->F->L, R->b, &R->F->cc);
    if (!X) return wr_fail(diag, WR_ERR_BACKEND, -1, "eigen: CHOLMOD solve failed (status %d)", (int)R->F->cc.status);
    for (k = 0; k < R->nf; ++k) y[k] = ((double *)X->x)[k];
    cholmod_l_free_dense(&X, &R->F->cc);
    return WR_OK;
}

/* ARPACK mode 3: OP = (K − σM)⁻¹M, B = M (bmat "G"), or (K − σI)⁻¹ (bmat "I"); which = "LM" */
static wr_status wr__eig_lanczos(wr__eig_run *R, int generalized, double tol, int32_t max_iter, double sigma,
                                 wr_eigen_result *res, wr_diag *diag) {
    a_int ido = 0, info = 1, k;
    const char *bmat = generalized ? "G" : "I";
    wr_status rs;
    memset(R->iparam, 0, sizeof R->iparam);
    R->iparam[0] = 1; /* exact shifts */
    R->iparam[2] = max_iter;
    R->iparam[6] = 3; /* shift-invert */
    for (;;) {
        dsaupd_c(&ido, bmat, R->nf, "LM", R->nev, tol, R->resid, R->ncv, R->v, R->nf, R->iparam, R->ipntr, R->workd,
                 R->workl, R->lworkl, &info);
        if (ido == -1 || ido == 1) {
            double *x = R->workd + R->ipntr[0] - 1, *y = R->workd + R->ipntr[1] - 1, *u = R->z;
            if (generalized) {
                const double *bx = (ido == 1) ? R->workd + R->ipntr[2] - 1 : NULL;
                for (k = 0; k < R->nf; ++k) u[k] = bx ? bx[k] : R->F->m[k] * x[k];
            } else {
                memcpy(u, x, sizeof(double) * (size_t)R->nf);
            }
            if ((rs = wr__eig_apply(R, u, y, diag)) != WR_OK) return rs;
            res->op_applies++;
        } else if (ido == 2) {
            double *x = R->workd + R->ipntr[0] - 1, *y = R->workd + R->ipntr[1] - 1;
            for (k = 0; k < R->nf; ++k) y[k] = R->F->m[k] * x[k];
        } else {
            break;
        }
    }
    res->restarts += R->iparam[2];
    if (info < 0) return wr_fail(diag, WR_ERR_BACKEND, (int32_t)info, "eigen: ARPACK dsaupd failed (info %d)", (int)info);
    dseupd_c(1, "A", R->select, R->d, R->z, R->nf, sigma, bmat, R->nf, "LM", R->nev, tol, R->resid, R->ncv, R->v, R->nf,
             R->iparam, R->ipntr, R->workd, R->workl, R->lworkl, &info);
    if (info != 0) return wr_fail(diag, WR_ERR_BACKEND, (int32_t)info, "eigen: ARPACK dseupd failed (info %d)", (int)info);
    return WR_OK;
}

static wr_status wr__eig_run_alloc(wr__eig_run *R, wr__eig_ldl *F, int32_t nev, int32_t ncv, uint64_t seed,
                                   wr_diag *diag) {
    wr_rng rng;
    int32_t k;
    memset(R, 0, sizeof *R);
    R->F = F;
    R->nf = F->nf;
    R->nev = nev;
    R->ncv = ncv;
    R->lworkl = ncv * (ncv + 8);
    R->resid = (double *)wr_alloc_array((size_t)R->nf, sizeof(double));
    R->v = (double *)wr_alloc_array((size_t)R->nf * (size_t)ncv, sizeof(double));
    R->workd = (double *)wr_alloc_array(3 * (size_t)R->nf, sizeof(double));
    R->workl = (double *)wr_alloc_array((size_t)R->lworkl, sizeof(double));
    R->d = (double *)wr_alloc_array((size_t)ncv, sizeof(double));
    R->z = (double *)wr_alloc_array((size_t)R->nf * (size_t)(nev + 1), sizeof(double));
    R->select = (a_int *)wr_calloc_array((size_t)ncv, sizeof(a_int));
    R->b = cholmod_l_allocate_dense((size_t)R->nf, 1, (size_t)R->nf, CHOLMOD_REAL, &F->cc);
    if (!R->resid || !R->v || !R->workd || !R->workl || !R->d || !R->z || !R->select || !R->b)
        return wr_fail(diag, WR_ERR_NOMEM, -1, "eigen: out of memory (%d DOFs, %d Lanczos vectors)", (int)R->nf, (int)ncv);
    /* a seeded start vector (ARPACK's own would be its fixed internal LAPACK seed) */
    wr_rng_seed(&rng, seed);
    for (k = 0; k < R->nf; ++k) R->resid[k] = wr_rng_uniform(&rng) - 0.5;
    return WR_OK;
}

/* pairs sorted ascending into the result, mapped back to the full numbering; relative residuals */
static void wr__eig_collect(const wr__eig_run *R, const wr_csr *K, int32_t nconv, double *work, wr_eigen_result *res) {
    int32_t a, b, k, i;
    int32_t order[64];
    double *full = work, *Kv = work + K->n;
    for (a = 0; a < nconv; ++a) order[a] = a;
    for (a = 1; a < nconv; ++a)
        for (b = a; b > 0 && R->d[order[b]] < R->d[order[b - 1]]; --b) k = order[b], order[b] = order[b - 1], order[b - 1] = k;
    res->nev = nconv;
    res->residual = 0.0;
    for (a = 0; a < nconv; ++a) {
        const double *zz = R->z + (size_t)order[a] * (size_t)R->nf;
        double lam = R->d[order[a]], num = 0.0, kn = 0.0, mn = 0.0, *out = res->vectors + (size_t)a * (size_t)K->n;
        memset(full, 0, sizeof(double) * (size_t)K->n);
        for (k = 0; k < R->nf; ++k) full[R->F->free_of[k]] = zz[k];
        wr_csr_spmv(K, full, Kv);
        for (k = 0; k < R->nf; ++k) {
            i = R->F->free_of[k];
            num += (Kv[i] - lam * R->F->m[k] * zz[k]) * (Kv[i] - lam * R->F->m[k] * zz[k]);
            kn += Kv[i] * Kv[i];
            mn += R->F->m[k] * zz[k] * R->F->m[k] * zz[k];
        }
        res->residual = fmax(res->residual, sqrt(num) / (sqrt(kn) + fabs(lam) * sqrt(mn) + 1e-300));
        res->values[a] = lam;
        memcpy(out, full, sizeof(double) * (size_t)K->n);
    }
}

/* one round of ON THE SEARCH at σ: factor, count, Lanczos, collect */
static wr_status wr__eig_round(wr__eig_ldl *F, const wr_csr *K, const wr_eigen_desc *d, int32_t nev, int32_t ncv,
                               double sigma, double *work, wr_eigen_result *res, int32_t *n_below, wr_diag *diag) {
    wr__eig_run R;
    int32_t nz = 0;
    double t0 = wr_time_seconds();
    wr_status rs = wr__eig_ldl_factor(F, K, sigma, n_below, &nz, diag);
    res->factorizations++;
    res->t_factor += wr_time_seconds() - t0;
    if (rs != WR_OK) return rs;
    if (nz > 0) return WR_ERR_NOT_SPD; /* σ is an eigenvalue to working precision: the caller moves it */
    t0 = wr_time_seconds();
    rs = wr__eig_run_alloc(&R, F, nev, ncv, d->seed, diag);
    if (rs == WR_OK) rs = wr__eig_lanczos(&R, d->metric != NULL, d->tol, d->max_iter, sigma, res, diag);
    if (rs == WR_OK) {
        int32_t nconv = (int32_t)R.iparam[4];
        if (nconv > nev) nconv = nev;
        wr__eig_collect(&R, K, nconv, work, res);
        if (nconv < nev)
            rs = wr_fail(diag, WR_ERR_NOT_CONVERGED, nconv, "eigen: ARPACK converged %d of %d eigenpairs in %d restarts",
                         (int)nconv, (int)nev, (int)R.iparam[2]);
    }
    wr__eig_run_free(&R);
    res->t_lanczos += wr_time_seconds() - t0;
    return rs;
}
#endif

#if defined(WR_USE_ARPACK) && WR_USE_ARPACK && defined(WR_USE_CHOLMOD) && WR_USE_CHOLMOD
/* the shift loop of ON THE SEARCH on an analysed factor */
static wr_status wr__eig_search(wr__eig_ldl *F, const wr_csr *K, const wr_eigen_desc *d, wr_eigen_result *res,
                                double *work, wr_diag *diag) {
    int32_t nev = d->nev, ncv = d->ncv, round, nb = 0, k, first = 1;
    double sigma, dsum = 0.0, msum = 0.0;
    wr_status rs = WR_OK;
    if (ncv == 0) ncv = 2 * nev + 1 > 24 ? 2 * nev + 1 : 24;
    if (ncv > F->nf) ncv = F->nf;
    if (ncv <= nev) return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "eigen: ncv %d must exceed nev %d (free DOFs %d)", (int)ncv, (int)nev, (int)F->nf);
    for (k = 0; k < F->nf; ++k) {
        int32_t i = F->free_of[k], p = wr_csr_find(K, i, i);
        dsum += p >= 0 ? fabs(K->val[p]) : 0.0;
        msum += F->m[k];
    }
    res->scale = (dsum > 0.0 ? dsum : 1.0) / msum;
    sigma = d->has_sigma ? d->sigma : -d->neg_rel * res->scale;
    for (round = 0; round <= WR_EIGEN_MAX_SHIFTS; ++round) {
        int32_t found = 0;
        rs = wr__eig_round(F, K, d, nev, ncv, sigma, work, res, &nb, diag);
        if (rs == WR_ERR_NOT_SPD) { /* zero pivot: σ on an eigenvalue, step below it */
            sigma -= 1e-6 * res->scale;
            continue;
        }
        if (first) res->n_negative = nb, res->sigma0 = sigma, first = 0;
        res->sigma = sigma;
        if (rs != WR_OK) return rs;
        for (k = 0; k < res->nev; ++k) found += res->values[k] < sigma;
        if (found >= nb) {
            res->complete = 1;
            return WR_OK;
        }
        /* some eigenvalue below σ was missed: move σ below the lowest found by twice the spread */
        sigma = fmin(sigma, res->values[0]) - 2.0 * fmax(res->values[res->nev - 1] - res->values[0], 1e-6 * res->scale);
    }
    return rs;
}
#endif

WRDEF wr_status wr_eigen_lowest(const wr_csr *K, const wr_eigen_desc *desc, wr_eigen_result *res, wr_diag *diag) {
    wr_eigen_desc d;
    if (res) memset(res, 0, sizeof *res);
    if (!K || !K->rowptr || K->n < 2 || !res) return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "eigen: NULL or too small matrix or result");
    if (desc) d = *desc;
    else memset(&d, 0, sizeof d);
    if (d.nev == 0) d.nev = 4;
    if (d.tol == 0.0) d.tol = 1e-10;
    if (d.max_iter == 0) d.max_iter = 500;
    if (d.neg_rel == 0.0) d.neg_rel = WR_EIGEN_NEG_REL;
    if (d.nev < 1 || d.nev > 64 || d.ncv < 0 || !(d.tol > 0.0) || d.max_iter < 0 || !(d.sigma - d.sigma == 0.0) ||
        !(d.neg_rel > 0.0))
        return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "eigen: nev %d (1..64), ncv %d, tol %g, max_iter %d or sigma %g invalid",
                       (int)d.nev, (int)d.ncv, d.tol, (int)d.max_iter, d.sigma);
    res->n = K->n;
#if defined(WR_USE_ARPACK) && WR_USE_ARPACK && defined(WR_USE_CHOLMOD) && WR_USE_CHOLMOD
    {
        wr__eig_ldl F;
        double *work = NULL;
        wr_status rs = wr__eig_ldl_create(&F, K, d.fixed, d.metric, diag);
        if (rs == WR_OK && d.nev >= F.nf)
            rs = wr_fail(diag, WR_ERR_INVALID_ARG, -1, "eigen: nev %d must be below the %d free DOFs", (int)d.nev, (int)F.nf);
        if (rs == WR_OK) {
            res->values = (double *)wr_alloc_array((size_t)d.nev, sizeof(double));
            res->vectors = (double *)wr_calloc_array((size_t)d.nev * (size_t)K->n, sizeof(double));
            work = (double *)wr_alloc_array(2 * (size_t)K->n, sizeof(double));
            if (!res->values || !res->vectors || !work) rs = wr_fail(diag, WR_ERR_NOMEM, -1, "eigen: out of memory");
        }
        if (rs == WR_OK) rs = wr__eig_search(&F, K, &d, res, work, diag);
        wr_free(work);
        wr__eig_ldl_free(&F);
        return rs;
    }
#else
    return wr_fail(diag, WR_ERR_UNSUPPORTED, -1, "eigen: the eigensolver needs ARPACK and CHOLMOD (define WR_USE_ARPACK=1 and WR_USE_CHOLMOD=1)");
#endif
}

#ifdef __cplusplus
}
#endif
#endif /* WRINKLE_EIGEN_IMPLEMENTATION_DONE */
#endif /* WRINKLE_IMPLEMENTATION */
