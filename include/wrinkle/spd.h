/* wrinkle/spd.h — one entry point for symmetric positive definite sparse systems A x = b:
 * preconditioned conjugate gradients (Jacobi, 3×3 block-Jacobi, incomplete Cholesky IC(0),
 * smoothed-aggregation algebraic multigrid) or CHOLMOD's supernodal Cholesky, with Dirichlet
 * (fixed) DOFs, for the shell statics Newton solver and the TFW SQP (TFW Sec. 5) and the Style3D
 * Sec. 5 "PCG with 3×3 block diagonal preconditioning".
 * wrinkle v0.1.0 — MIT licence (see LICENSE).
 *
 * (Formerly pcg.h, after its first backend; pcg.h remains as a compatibility include.)
 *
 * WHICH METHOD
 *   CHOLMOD is the robust default for the shell Newton systems up to ~1e5 vertices. For PCG:
 *   smoothed-aggregation AMG for smooth, stiff operators (a membrane with mass: iterations nearly
 *   independent of n), IC(0) with the blocked kernels for the buckling shell Hessians (where AMG's
 *   coarse spaces miss the non-smooth modes), 3×3 block-Jacobi as the Style3D paper's setting.
 *   Measured figures and their machine: docs/notes-statics.md (linear solvers) and bench/RESULTS.md.
 *
 * DEPENDENCIES
 *   sparse.h, core.h (libc/libm). The CHOLMOD backend is compiled only when WR_USE_CHOLMOD is
 *   defined to 1: then this header includes <cholmod.h> (Debian: libsuitesparse-dev, add
 *   -I/usr/include/suitesparse) and the program links -lcholmod. Without it WR_SOLVER_CHOLMOD
 *   returns WR_ERR_UNSUPPORTED and WR_SOLVER_AUTO means WR_SOLVER_PCG_IC0.
 *   CHOLMOD allocates its own workspace and factor with malloc: WR_MALLOC cannot reach that memory
 *   (only wrinkle's own arrays go through the hooks).
 *
 * API (create/free pair: wr_spd_solver_create / wr_spd_solver_free)
 *   wr_spd_solve(A, b, x, desc, stats, diag)         one-shot: setup + solve
 *   wr_spd_solver_create(S, A, desc, diag)           symbolic work on A's pattern (CHOLMOD analyze,
 *                                                    IC pattern), copies desc->fixed
 *   wr_spd_solver_factor(S, A, diag)                 numeric setup with A's current values
 *   wr_spd_solver_solve(S, A, b, x, stats, diag)     solve with the last factored values
 *   wr_spd_solver_free(S)
 *   wr_solver_method_name(m)                         "pcg-ic0", "pcg-amg", "cholmod", ...
 *   (the AMG hierarchy is value dependent, so for WR_SOLVER_PCG_AMG all setup happens in factor)
 *
 * EXAMPLE (one-shot solve; see the note after it for a Newton loop)
 *     wr_triplets t;  wr_csr K;  wr_spd_desc sd;  wr_spd_stats st;  wr_diag d;  int32_t e;
 *     uint8_t fixed[5] = {1, 0, 0, 0, 0};                // DOF 0 clamped (Dirichlet)
 *     double b[5] = {0, 0, 0, 0, 1.0}, x[5] = {0};       // unit force on the free end; x[0] stays 0
 *     if (wr_triplets_create(&t, 5, 16, &d) != WR_OK) { puts(d.message); return 1; }   // 4 unit springs
 *     for (e = 0; e < 4; ++e) {
 *         wr_triplets_add(&t, e, e, 1.0, &d);  wr_triplets_add(&t, e + 1, e + 1, 1.0, &d);
 *         wr_triplets_add(&t, e, e + 1, -1.0, &d);  wr_triplets_add(&t, e + 1, e, -1.0, &d);
 *     }
 *     if (wr_csr_from_triplets(&K, &t, &d) != WR_OK) { puts(d.message); return 1; }
 *     wr_triplets_free(&t);
 *     memset(&sd, 0, sizeof sd);  sd.fixed = fixed;      // zero = defaults (AUTO, rel_tol 1e-10)
 *     if (wr_spd_solve(&K, b, x, &sd, &st, &d) != WR_OK) { puts(d.message); return 1; }
 *     printf("x[4] = %g m by %s\n", x[4], wr_solver_method_name(st.method));   // 4 (springs in series)
 *     wr_csr_free(&K);
 *   In a Newton loop keep one solver so the symbolic analysis is done once: wr_spd_solver_create(&S,
 *   &K, &sd, &d) before the loop; per iteration reassemble K's values (sparse.h), then
 *   wr_spd_solver_factor(&S, &K, &d) and wr_spd_solver_solve(&S, &K, g, dx, &st, &d) with dx = 0 on
 *   the fixed DOFs; wr_spd_solver_free(&S) after it.
 *
 * ON FIXED DOFS
 *   desc->fixed[i] != 0 marks DOF i as Dirichlet: x[i] keeps its input value and row i of the
 *   equations is dropped; the coupling A(free, fixed) x(fixed) moves to the right-hand side. The
 *   matrix is never rebuilt by the caller. PCG works on a masked copy of the values (rows and
 *   columns of fixed DOFs replaced by the identity; residual and search direction are zero on fixed
 *   DOFs), so the preconditioners see the reduced matrix A_ff exactly (AMG also leaves fixed DOFs
 *   out of its coarse spaces). CHOLMOD factors the reduced
 *   system A_ff (eliminated, no penalty): its pattern is extracted once in create.
 *
 * ON ACCURACY AND STOPPING
 *   Relative residual = ||(b - A x)_free|| / ||(b - A x0)_free|| where x0 is the input x with the
 *   free entries set to 0 (= ||b - A x|| / ||b|| without fixed DOFs). PCG stops when the recursive
 *   residual passes rel_tol, then recomputes the true residual; if that misses it replaces the
 *   residual and continues (at most WR_SPD_MAX_REPLACEMENTS times). stats->rel_residual is always
 *   the true residual of the returned x. CHOLMOD's solution gets up to WR_SPD_MAX_REFINEMENTS
 *   steps of iterative refinement when its residual misses rel_tol. A zero right-hand side gives
 *   x_free = 0 at once. When max_iter is reached the status is WR_ERR_NOT_CONVERGED and x holds the
 *   last iterate, which is the best one in the A-norm of the error (CG minimises that norm over the
 *   growing Krylov space); its residual is reported. p^T A p <= 0 (or a non-positive diagonal /
 *   3×3 block / CHOLMOD pivot) returns WR_ERR_NOT_SPD with the last valid iterate in x.
 *
 * ON BLOCKED KERNELS
 *   When n is a multiple of 3 and A's pattern consists of full 3×3 blocks with a symmetric block
 *   pattern (sparse.h's block/element assembly of 3-DOF vertices gives that), PCG multiplies with the
 *   upper block triangle only (BCSR, double) and IC(0) applies its factor from single-precision 3×3
 *   blocks (factorised in double, then rounded; sweeps accumulate in double): same iterations, less
 *   memory traffic. M = L~ L~^T with the rounded L~ is still SPD, so CG's guarantees hold. Other
 *   patterns run the scalar CSR paths. wr_spd_solver.nb > 0 tells which (see the code note).
 *
 * ON THREADS
 *   No global state; one solver object per thread. CHOLMOD calls its BLAS, which may start threads.
 */
#ifndef WRINKLE_SPD_H
#define WRINKLE_SPD_H

#include "core.h"
#include "sparse.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef enum wr_solver_method {
    WR_SOLVER_AUTO = 0,    /* CHOLMOD when built with WR_USE_CHOLMOD, else WR_SOLVER_PCG_IC0 */
    WR_SOLVER_PCG_JACOBI,  /* PCG, diagonal preconditioner */
    WR_SOLVER_PCG_BLOCK3,  /* PCG, 3×3 block-Jacobi (Style3D Sec. 5); n must be a multiple of 3 */
    WR_SOLVER_PCG_IC0,     /* PCG, incomplete Cholesky IC(0) with Manteuffel diagonal-shift retries */
    WR_SOLVER_CHOLMOD,     /* CHOLMOD supernodal Cholesky of the reduced system */
    WR_SOLVER_PCG_AMG,     /* PCG, smoothed-aggregation algebraic multigrid V(1,1) cycle (3-DOF nodes) */
    WR_SOLVER_METHOD_COUNT
} wr_solver_method;

typedef enum wr_spd_stop {
    WR_SPD_STOP_NONE = 0,
    WR_SPD_STOP_CONVERGED,  /* true relative residual <= rel_tol */
    WR_SPD_STOP_ZERO_RHS,   /* effective right-hand side is zero: x_free = 0 */
    WR_SPD_STOP_MAX_ITER,   /* max_iter reached (WR_ERR_NOT_CONVERGED) */
    WR_SPD_STOP_NOT_SPD,    /* p^T A p <= 0, bad pivot or block (WR_ERR_NOT_SPD) */
    WR_SPD_STOP_NONFINITE,  /* NaN/Inf appeared (WR_ERR_DOMAIN) */
    WR_SPD_STOP_DIRECT_INACCURATE /* CHOLMOD + refinement could not reach rel_tol (WR_ERR_NOT_CONVERGED) */
} wr_spd_stop;

/* Defaults (zero means default):
 *   method   WR_SOLVER_AUTO
 *   rel_tol  1e-10 relative residual (see ON ACCURACY)
 *   max_iter 10 * n PCG iterations
 *   fixed    NULL = no Dirichlet DOFs; else n flags, nonzero = fixed (copied by create) */
typedef struct wr_spd_desc {
    wr_solver_method method;
    double rel_tol;
    int32_t max_iter;
    const uint8_t *fixed;
} wr_spd_desc;

typedef struct wr_spd_stats {
    wr_solver_method method; /* the method actually used (AUTO resolved) */
    int32_t iterations;      /* PCG iterations (refinement steps for CHOLMOD) */
    double rel_residual;     /* true relative residual of the returned x */
    double setup_seconds;    /* symbolic (create) + numeric (last factor) setup */
    double analyze_seconds;  /* the symbolic part alone */
    double solve_seconds;    /* this solve */
    wr_spd_stop stop;
    double ic_shift;         /* IC0: Manteuffel shift alpha used (A_ii scaled by 1+alpha), 0 if none */
    int32_t n_free;          /* DOFs not fixed */
} wr_spd_stats;

struct wr__spd_backend;
struct wr__spd_amg;
typedef struct wr_spd_solver {
    int32_t n, nnz;             /* pattern the solver was created for */
    wr_solver_method method;    /* resolved */
    double rel_tol;
    int32_t max_iter;
    uint8_t *fixed;             /* n flags (own copy) or NULL */
    int32_t n_free;
    int factored;
    double analyze_seconds, factor_seconds;
    double *mval;               /* masked values (fixed rows/cols -> identity), or NULL if none fixed */
    double *prec;               /* Jacobi: n inverse diagonals; block3: 9*(n/3) inverse blocks */
    int32_t *lrow, *lcol, *lsrc;/* IC0: lower-triangular CSR of L and the A index of each entry */
    double *lval;
    double ic_shift;
    struct wr__spd_backend *backend; /* CHOLMOD state, NULL otherwise */
    struct wr__spd_amg *amg;         /* AMG hierarchy, NULL otherwise */
    /* 3×3-blocked kernels (ON BLOCKED KERNELS), used when A's pattern is made of full 3×3 blocks
     * and symmetric; nb = 0 means the scalar CSR paths above. */
    int32_t nb;                 /* block rows (n / 3) */
    int32_t *abrow, *abcol;     /* operator: upper block triangle (J >= I) of the masked A, BCSR */
    int32_t *apack;             /* per A entry: index into abval, or -1 (lower triangle) */
    double *abval;              /* 9 per block, row-major */
    int32_t *lbrow, *lbcol;     /* IC0 factor: strictly lower blocks of L, BCSR */
    int32_t *lpack;             /* per L entry: index into lboff (>= 0) or -(1 + index into lbdia) */
    float *lboff, *lbdia;       /* off-diagonal blocks (9 each); diagonal lower triangles (6 each:
                                   1/l00, l10, 1/l11, l20, l21, 1/l22) */
} wr_spd_solver;

WRDEF const char *wr_solver_method_name(wr_solver_method m);
WRDEF wr_status wr_spd_solve(const wr_csr *A, const double *b, double *x, const wr_spd_desc *desc,
                             wr_spd_stats *stats, wr_diag *diag);
WRDEF wr_status wr_spd_solver_create(wr_spd_solver *S, const wr_csr *A, const wr_spd_desc *desc, wr_diag *diag);
WRDEF wr_status wr_spd_solver_factor(wr_spd_solver *S, const wr_csr *A, wr_diag *diag);
/* A must be the matrix given to the last wr_spd_solver_factor, values unchanged. */
WRDEF wr_status wr_spd_solver_solve(wr_spd_solver *S, const wr_csr *A, const double *b, double *x,
                                    wr_spd_stats *stats, wr_diag *diag);
WRDEF void wr_spd_solver_free(wr_spd_solver *S);

#ifdef __cplusplus
}
#endif
#endif /* WRINKLE_SPD_H */

/* ============================================================================================ */
#ifdef WRINKLE_IMPLEMENTATION
#ifndef WRINKLE_SPD_IMPLEMENTATION_DONE
#define WRINKLE_SPD_IMPLEMENTATION_DONE

#include <math.h>
#include <string.h>
#if defined(WR_USE_CHOLMOD) && WR_USE_CHOLMOD
#include <cholmod.h>
#endif

#ifdef __cplusplus
extern "C" {
#endif

/* Defaults and limits, each with its reason. */
#define WR_SPD_DEFAULT_REL_TOL 1e-10  /* brief: 1e-10 relative residual for Newton/SQP steps */
#define WR_SPD_DEFAULT_ITER_FACTOR 10 /* max_iter = 10 n: CG is exact after n steps in exact arithmetic */
#define WR_SPD_MAX_REPLACEMENTS 5     /* true-residual restarts before accepting the drift as final */
#define WR_SPD_MAX_REFINEMENTS 3      /* CHOLMOD iterative-refinement steps */
/* Manteuffel (1980) shifted IC: factor D(1+alpha) + offdiag. Start small so a matrix that only
 * barely breaks down keeps most of IC(0)'s strength, double until the pivots stay positive. */
#define WR_IC_SHIFT_START 1e-3
#define WR_IC_SHIFT_MAX 1e3
/* A pivot is a breakdown when it falls below this fraction of the original diagonal: a tiny pivot
 * makes L^-1 huge and the preconditioner useless even if it is technically positive. */
#define WR_IC_PIVOT_REL 1e-12

WRDEF const char *wr_solver_method_name(wr_solver_method m) {
    switch (m) {
    case WR_SOLVER_AUTO: return "auto";
    case WR_SOLVER_PCG_JACOBI: return "pcg-jacobi";
    case WR_SOLVER_PCG_BLOCK3: return "pcg-block3";
    case WR_SOLVER_PCG_IC0: return "pcg-ic0";
    case WR_SOLVER_CHOLMOD: return "cholmod";
    case WR_SOLVER_PCG_AMG: return "pcg-amg";
    default: return "unknown";
    }
}

/* ---------------------------------------------------------------- CHOLMOD backend ---------- */
#if defined(WR_USE_CHOLMOD) && WR_USE_CHOLMOD
struct wr__spd_backend {
    cholmod_common cc;
    int started;
    cholmod_sparse *Ar;   /* reduced lower triangle, CSC (stype -1) */
    cholmod_factor *L;
    int32_t *src;         /* for each entry of Ar: index into A.val */
    int32_t *free_of;     /* reduced index -> original DOF */
};

static void wr__chol_free(struct wr__spd_backend *B) {
    if (!B) return;
    if (B->started) {
        if (B->L) cholmod_l_free_factor(&B->L, &B->cc);
        if (B->Ar) cholmod_l_free_sparse(&B->Ar, &B->cc);
        cholmod_l_finish(&B->cc);
    }
    wr_free(B->src);
    wr_free(B->free_of);
    wr_free(B);
}

static wr_status wr__chol_fail(wr_diag *diag, struct wr__spd_backend *B, const char *what) {
    /* CHOLMOD reports exhaustion of its own (malloc'd) workspace as a status, not a NULL we see */
    int oom = B && B->started && B->cc.status == CHOLMOD_OUT_OF_MEMORY;
    wr_status s = wr_fail(diag, oom ? WR_ERR_NOMEM : WR_ERR_BACKEND, -1, "CHOLMOD %s failed (status %d)", what,
                          B ? B->cc.status : 0);
    if (diag && B) diag->backend_code = B->cc.status;
    return s;
}

static wr_status wr__chol_create(wr_spd_solver *S, const wr_csr *A, wr_diag *diag) {
    struct wr__spd_backend *B;
    int32_t *red = NULL, i, p, nf = 0;
    int64_t nz = 0;
    SuiteSparse_long *Ap, *Ai;
    B = (struct wr__spd_backend *)wr_calloc_array(1, sizeof *B);
    if (!B) return wr_fail(diag, WR_ERR_NOMEM, -1, "CHOLMOD backend: out of memory");
    S->backend = B;
    red = (int32_t *)wr_alloc_array((size_t)A->n, sizeof(int32_t));
    B->free_of = (int32_t *)wr_alloc_array((size_t)A->n, sizeof(int32_t));
    if (!red || !B->free_of) {
        wr_free(red);
        return wr_fail(diag, WR_ERR_NOMEM, -1, "CHOLMOD backend: out of memory");
    }
    for (i = 0; i < A->n; ++i) {
        if (S->fixed && S->fixed[i]) {
            red[i] = -1;
        } else {
            B->free_of[nf] = i;
            red[i] = nf++;
        }
    }
    /* Row i of the full symmetric CSR is column i; keep its entries j >= i between free DOFs: the
     * lower triangle of A_ff in CSC, rows ascending because CSR columns are sorted. */
    for (i = 0; i < A->n; ++i)
        if (red[i] >= 0)
            for (p = A->rowptr[i]; p < A->rowptr[i + 1]; ++p)
                if (A->col[p] >= i && red[A->col[p]] >= 0) nz++;
    B->src = (int32_t *)wr_alloc_array((size_t)nz, sizeof(int32_t));
    if (!B->src) {
        wr_free(red);
        return wr_fail(diag, WR_ERR_NOMEM, -1, "CHOLMOD backend: out of memory");
    }
    if (!cholmod_l_start(&B->cc)) {
        wr_free(red);
        return wr__chol_fail(diag, B, "start");
    }
    B->started = 1;
    B->cc.print = 0; /* library code never prints */
    B->cc.supernodal = CHOLMOD_SUPERNODAL;
    B->Ar = cholmod_l_allocate_sparse((size_t)nf, (size_t)nf, (size_t)nz, 1, 1, -1, CHOLMOD_REAL, &B->cc);
    if (!B->Ar) {
        wr_free(red);
        return wr__chol_fail(diag, B, "allocate_sparse");
    }
    Ap = (SuiteSparse_long *)B->Ar->p;
    Ai = (SuiteSparse_long *)B->Ar->i;
    nz = 0;
    for (i = 0; i < A->n; ++i) {
        if (red[i] < 0) continue;
        Ap[red[i]] = (SuiteSparse_long)nz;
        for (p = A->rowptr[i]; p < A->rowptr[i + 1]; ++p)
            if (A->col[p] >= i && red[A->col[p]] >= 0) {
                Ai[nz] = red[A->col[p]];
                B->src[nz] = p;
                ((double *)B->Ar->x)[nz] = 0.0;
                nz++;
            }
    }
    Ap[nf] = (SuiteSparse_long)nz;
    wr_free(red);
    B->L = cholmod_l_analyze(B->Ar, &B->cc);
    if (!B->L || B->cc.status < CHOLMOD_OK) return wr__chol_fail(diag, B, "analyze");
    return WR_OK;
}

static wr_status wr__chol_factor(wr_spd_solver *S, const wr_csr *A, wr_diag *diag) {
    struct wr__spd_backend *B = S->backend;
    double *x = (double *)B->Ar->x;
    size_t k, nz = (size_t)((SuiteSparse_long *)B->Ar->p)[B->Ar->ncol];
    for (k = 0; k < nz; ++k) x[k] = A->val[B->src[k]];
    if (!cholmod_l_factorize(B->Ar, B->L, &B->cc) || B->cc.status < CHOLMOD_OK)
        return wr__chol_fail(diag, B, "factorize");
    if (B->cc.status == CHOLMOD_NOT_POSDEF || B->L->minor < B->L->n) {
        wr_status s;
        int32_t col = B->L->minor < B->L->n ? B->free_of[B->L->minor] : -1;
        s = wr_fail(diag, WR_ERR_NOT_SPD, col, "CHOLMOD: matrix not positive definite (pivot at DOF %d)", (int)col);
        if (diag) diag->backend_code = B->cc.status;
        return s;
    }
    return WR_OK;
}

/* x_f = A_ff^{-1} rhs_f on the reduced numbering; rhs and out are full-length (free entries used). */
static wr_status wr__chol_solve(wr_spd_solver *S, const double *rhs, double *out, wr_diag *diag) {
    struct wr__spd_backend *B = S->backend;
    cholmod_dense *Bd, *X;
    size_t k, nf = B->Ar->nrow;
    Bd = cholmod_l_allocate_dense(nf, 1, nf, CHOLMOD_REAL, &B->cc);
    if (!Bd) return wr__chol_fail(diag, B, "allocate_dense");
    for (k = 0; k < nf; ++k) ((double *)Bd->x)[k] = rhs[B->free_of[k]];
    X = cholmod_l_solve(CHOLMOD_A, B->L, Bd, &B->cc);
    cholmod_l_free_dense(&Bd, &B->cc);
    if (!X || B->cc.status < CHOLMOD_OK) {
        if (X) cholmod_l_free_dense(&X, &B->cc);
        return wr__chol_fail(diag, B, "solve");
    }
    for (k = 0; k < nf; ++k) out[B->free_of[k]] = ((double *)X->x)[k];
    cholmod_l_free_dense(&X, &B->cc);
    return WR_OK;
}
#else
struct wr__spd_backend {
    int unused;
};
static void wr__chol_free(struct wr__spd_backend *B) { wr_free(B); }
#endif

/* ---------------------------------------------------------------- helpers ------------------ */
static double wr__dot(int32_t n, const double *a, const double *b) {
    double s = 0.0;
    int32_t i;
    for (i = 0; i < n; ++i) s += a[i] * b[i];
    return s;
}

/* y = A x with the masked values when some DOFs are fixed (then fixed rows give y_c = x_c and
 * fixed columns do not couple). */
static void wr__spmv_vals(const wr_csr *A, const double *val, const double *x, double *y) {
    int32_t i;
    for (i = 0; i < A->n; ++i) {
        double s = 0.0;
        int32_t p;
        for (p = A->rowptr[i]; p < A->rowptr[i + 1]; ++p) s += val[p] * x[A->col[p]];
        y[i] = s;
    }
}

/* r = b - A x on free DOFs, 0 on fixed DOFs; returns ||r||. */
static double wr__residual(const wr_spd_solver *S, const wr_csr *A, const double *b, const double *x, double *r) {
    int32_t i;
    double s = 0.0;
    wr_csr_spmv(A, x, r);
    for (i = 0; i < A->n; ++i) {
        r[i] = (S->fixed && S->fixed[i]) ? 0.0 : b[i] - r[i];
        s += r[i] * r[i];
    }
    return sqrt(s);
}

static void wr__solver_resolve(wr_spd_solver *S, const wr_spd_desc *desc) {
    S->method = desc ? desc->method : WR_SOLVER_AUTO;
    if (S->method == WR_SOLVER_AUTO) {
#if defined(WR_USE_CHOLMOD) && WR_USE_CHOLMOD
        S->method = WR_SOLVER_CHOLMOD;
#else
        S->method = WR_SOLVER_PCG_IC0;
#endif
    }
    S->rel_tol = (desc && desc->rel_tol > 0.0) ? desc->rel_tol : WR_SPD_DEFAULT_REL_TOL;
    if (desc && desc->max_iter > 0)
        S->max_iter = desc->max_iter;
    else
        S->max_iter = S->n > INT32_MAX / WR_SPD_DEFAULT_ITER_FACTOR ? INT32_MAX : WR_SPD_DEFAULT_ITER_FACTOR * S->n;
}

static wr_status wr__check_matrix(const wr_csr *A, const char *who, wr_diag *diag) {
    if (!A || !A->rowptr || !A->col || !A->val || A->n < 0)
        return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "%s: NULL or empty matrix", who);
    return WR_OK;
}

/* ---------------------------------------------------------------- solver object ------------ */
static void wr__amg_clear(struct wr__spd_amg *M);
WRDEF void wr_spd_solver_free(wr_spd_solver *S) {
    if (!S) return;
    wr_free(S->fixed);
    wr_free(S->mval);
    wr_free(S->prec);
    wr_free(S->lrow);
    wr_free(S->lcol);
    wr_free(S->lsrc);
    wr_free(S->lval);
    wr_free(S->abrow);
    wr_free(S->abcol);
    wr_free(S->apack);
    wr_free(S->abval);
    wr_free(S->lbrow);
    wr_free(S->lbcol);
    wr_free(S->lpack);
    wr_free(S->lboff);
    wr_free(S->lbdia);
    if (S->backend) wr__chol_free(S->backend);
    if (S->amg) {
        wr__amg_clear(S->amg);
        wr_free(S->amg);
    }
    memset(S, 0, sizeof *S);
}

/* IC(0) symbolic part: the lower triangle (diagonal last in each row) of A's pattern, restricted
 * to free DOFs; a fixed DOF keeps only its diagonal (value 1 in the masked matrix). */
static wr_status wr__ic_create(wr_spd_solver *S, const wr_csr *A, wr_diag *diag) {
    int32_t i, p, nz = 0;
    for (i = 0; i < A->n; ++i)
        for (p = A->rowptr[i]; p < A->rowptr[i + 1] && A->col[p] <= i; ++p) nz++;
    S->lrow = (int32_t *)wr_alloc_array((size_t)A->n + 1, sizeof(int32_t));
    S->lcol = (int32_t *)wr_alloc_array((size_t)nz, sizeof(int32_t));
    S->lsrc = (int32_t *)wr_alloc_array((size_t)nz, sizeof(int32_t));
    S->lval = (double *)wr_alloc_array((size_t)nz, sizeof(double));
    if (!S->lrow || !S->lcol || !S->lsrc || !S->lval)
        return wr_fail(diag, WR_ERR_NOMEM, -1, "IC(0): out of memory for %d entries", (int)nz);
    nz = 0;
    for (i = 0; i < A->n; ++i) {
        S->lrow[i] = nz;
        for (p = A->rowptr[i]; p < A->rowptr[i + 1] && A->col[p] <= i; ++p) {
            S->lcol[nz] = A->col[p];
            S->lsrc[nz] = p;
            nz++;
        }
        /* wr_csr always stores the diagonal, so the row ends with (i, i). */
        if (nz == S->lrow[i] || S->lcol[nz - 1] != i)
            return wr_fail(diag, WR_ERR_INVALID_ARG, i, "IC(0): row %d has no diagonal entry", (int)i);
    }
    S->lrow[A->n] = nz;
    return WR_OK;
}

/* IC(0) numeric part with Manteuffel shifts: L L^T ~= offdiag(A) + (1+alpha) diag(A).
 * Row-oriented: L_ij = (a_ij - sum_{m<j} L_im L_jm) / L_jj over the fixed pattern, using a scatter
 * map of row i so each row j of L is read once. */
static wr_status wr__ic_factor(wr_spd_solver *S, const double *val, wr_diag *diag) {
    int32_t n = S->n, i, p, q, attempt;
    int32_t *pos = (int32_t *)wr_alloc_array((size_t)n, sizeof(int32_t));
    double alpha = 0.0;
    if (!pos) return wr_fail(diag, WR_ERR_NOMEM, -1, "IC(0): out of memory");
    for (i = 0; i < n; ++i) pos[i] = -1;
    for (i = 0; i < n; ++i) {
        double d = val[S->lsrc[S->lrow[i + 1] - 1]];
        if (!(d > 0.0)) {
            wr_free(pos);
            return wr_fail(diag, WR_ERR_NOT_SPD, i, "IC(0): diagonal A(%d,%d) = %g is not positive", (int)i, (int)i, d);
        }
    }
    for (attempt = 0;; ++attempt) {
        int broke = 0;
        for (i = 0; i < n && !broke; ++i) {
            int32_t b = S->lrow[i], e = S->lrow[i + 1] - 1; /* e = diagonal */
            double dsum;
            for (p = b; p < e; ++p) pos[S->lcol[p]] = p;
            for (p = b; p < e; ++p) {
                int32_t j = S->lcol[p];
                double s = val[S->lsrc[p]];
                for (q = S->lrow[j]; q < S->lrow[j + 1] - 1; ++q) {
                    int32_t m = S->lcol[q];
                    if (pos[m] >= 0) s -= S->lval[pos[m]] * S->lval[q];
                }
                S->lval[p] = s / S->lval[S->lrow[j + 1] - 1];
            }
            dsum = (1.0 + alpha) * val[S->lsrc[e]];
            for (p = b; p < e; ++p) {
                dsum -= S->lval[p] * S->lval[p];
                pos[S->lcol[p]] = -1;
            }
            if (!(dsum > WR_IC_PIVOT_REL * val[S->lsrc[e]])) {
                broke = 1;
                break;
            }
            S->lval[e] = sqrt(dsum);
        }
        if (!broke) break;
        for (p = S->lrow[i]; p < S->lrow[i + 1]; ++p) pos[S->lcol[p]] = -1;
        alpha = alpha == 0.0 ? WR_IC_SHIFT_START : 2.0 * alpha;
        if (alpha > WR_IC_SHIFT_MAX) {
            wr_free(pos);
            return wr_fail(diag, WR_ERR_NOT_SPD, i, "IC(0): breakdown at row %d even with shift %g", (int)i,
                           alpha / 2.0);
        }
    }
    S->ic_shift = alpha;
    wr_free(pos);
    return WR_OK;
}

/* z = (L L^T)^{-1} r: forward with the rows of L, backward with the rows of L read as columns of L^T. */
static void wr__ic_apply(const wr_spd_solver *S, const double *r, double *z) {
    int32_t n = S->n, i, p;
    for (i = 0; i < n; ++i) {
        int32_t e = S->lrow[i + 1] - 1;
        double s = r[i];
        for (p = S->lrow[i]; p < e; ++p) s -= S->lval[p] * z[S->lcol[p]];
        z[i] = s / S->lval[e];
    }
    for (i = n - 1; i >= 0; --i) {
        int32_t e = S->lrow[i + 1] - 1;
        double zi = z[i] / S->lval[e];
        z[i] = zi;
        for (p = S->lrow[i]; p < e; ++p) z[S->lcol[p]] -= S->lval[p] * zi;
    }
}

/* ---------------------------------------------------------------- 3×3-blocked kernels ------ */
/* ON BLOCKED KERNELS (why): a PCG iteration on the shell Hessians (3 DOFs per vertex, ~56 entries
 * per row) is bound by memory traffic, not arithmetic: scalar CSR moves 12 bytes per entry (value
 * + column) for the SpMV and again for each IC(0) sweep. The blocked paths store one column index
 * per 3×3 block, the operator only as its upper block triangle (the matrix is symmetric: each block
 * is read once and used for y_I and y_J), and the IC(0) factor in single precision for the two
 * triangular sweeps (accumulated in double). The factor is still computed in double by
 * wr__ic_factor and only rounded when packed: the preconditioner is then M = L~ L~^T with L~ the
 * rounded factor, still symmetric positive definite (positive diagonal), so PCG's convergence
 * theory is untouched; L~ differs from L by ~6e-8 relative, far below IC(0)'s own dropping error.
 * The operator (SpMV) stays in double: it defines the system being solved. Used when n is a
 * multiple of 3 and A's pattern consists of full 3×3 blocks with a symmetric block pattern (what
 * sparse.h's block assembly gives); otherwise the scalar paths run unchanged. */

/* 1 when A's pattern is made of complete 3×3 blocks (rows 3I..3I+2 list the same columns, in full
 * aligned triples, diagonal block present) and the block pattern is symmetric. */
static int wr__pattern_blocked(const wr_csr *A) {
    int32_t nb, I, J, a, p, k, len;
    if (A->n <= 0 || A->n % 3 != 0) return 0;
    nb = A->n / 3;
    for (I = 0; I < nb; ++I) {
        int diag = 0;
        len = A->rowptr[3 * I + 1] - A->rowptr[3 * I];
        if (len % 3 != 0) return 0;
        for (a = 1; a < 3; ++a)
            if (A->rowptr[3 * I + a + 1] - A->rowptr[3 * I + a] != len) return 0;
        for (k = 0; k < len; k += 3) {
            int32_t c = A->col[A->rowptr[3 * I] + k];
            if (c % 3 != 0) return 0;
            for (a = 0; a < 3; ++a) {
                const int32_t *cc = A->col + A->rowptr[3 * I + a] + k;
                if (cc[0] != c || cc[1] != c + 1 || cc[2] != c + 2) return 0;
            }
            if (c == 3 * I) diag = 1;
        }
        if (!diag) return 0;
    }
    /* block pattern symmetry: every (I, J) has its (J, I) (binary search in block row J) */
    for (I = 0; I < nb; ++I)
        for (p = A->rowptr[3 * I]; p < A->rowptr[3 * I + 1]; p += 3) {
            int32_t lo, hi, found = 0;
            J = A->col[p] / 3;
            lo = A->rowptr[3 * J];
            hi = A->rowptr[3 * J + 1] - 1;
            while (lo <= hi) {
                int32_t mid = lo + (hi - lo) / 2, cm = A->col[mid] / 3;
                if (cm == I) {
                    found = 1;
                    break;
                }
                if (cm < I) lo = mid + 1;
                else hi = mid - 1;
            }
            if (!found) return 0;
        }
    return 1;
}

/* Symbolic part of the blocked kernels: operator upper block triangle and, for IC0 (after
 * wr__ic_create), the block structure of L and where each scalar L entry goes. Leaves S->nb = 0
 * (scalar paths) when the pattern does not qualify. */
static wr_status wr__block_create(wr_spd_solver *S, const wr_csr *A, wr_diag *diag) {
    int32_t nb, I, a, p, k, nu = 0, nl = 0;
    if (!wr__pattern_blocked(A)) return WR_OK;
    nb = A->n / 3;
    for (I = 0; I < nb; ++I)
        for (p = A->rowptr[3 * I]; p < A->rowptr[3 * I + 1]; p += 3) {
            if (A->col[p] / 3 >= I) nu++;
            else nl++;
        }
    S->abrow = (int32_t *)wr_alloc_array((size_t)nb + 1, sizeof(int32_t));
    S->abcol = (int32_t *)wr_alloc_array((size_t)nu, sizeof(int32_t));
    S->apack = (int32_t *)wr_alloc_array((size_t)A->nnz, sizeof(int32_t));
    S->abval = (double *)wr_alloc_array((size_t)nu, 9 * sizeof(double));
    if (!S->abrow || !S->abcol || !S->apack || !S->abval)
        return wr_fail(diag, WR_ERR_NOMEM, -1, "pcg blocked kernels: out of memory for %d blocks", (int)nu);
    nu = 0;
    for (I = 0; I < nb; ++I) {
        int32_t first = nu;
        S->abrow[I] = nu;
        for (p = A->rowptr[3 * I]; p < A->rowptr[3 * I + 1]; p += 3)
            if (A->col[p] / 3 >= I) S->abcol[nu++] = A->col[p] / 3; /* diagonal block first (sorted) */
        for (a = 0; a < 3; ++a) {
            k = first;
            for (p = A->rowptr[3 * I + a]; p < A->rowptr[3 * I + a + 1]; ++p) {
                int32_t J = A->col[p] / 3, b = A->col[p] % 3;
                if (J < I) {
                    S->apack[p] = -1;
                    continue;
                }
                S->apack[p] = 9 * k + 3 * a + b;
                if (b == 2) k++;
            }
        }
    }
    S->abrow[nb] = nu;
    if (S->method == WR_SOLVER_PCG_IC0) {
        S->lbrow = (int32_t *)wr_alloc_array((size_t)nb + 1, sizeof(int32_t));
        S->lbcol = (int32_t *)wr_alloc_array((size_t)nl + 1, sizeof(int32_t));
        S->lpack = (int32_t *)wr_alloc_array((size_t)S->lrow[A->n], sizeof(int32_t));
        S->lboff = (float *)wr_alloc_array((size_t)nl + 1, 9 * sizeof(float));
        S->lbdia = (float *)wr_alloc_array((size_t)nb, 6 * sizeof(float));
        if (!S->lbrow || !S->lbcol || !S->lpack || !S->lboff || !S->lbdia)
            return wr_fail(diag, WR_ERR_NOMEM, -1, "pcg-ic0 blocked factor: out of memory for %d blocks", (int)nl);
        nl = 0;
        for (I = 0; I < nb; ++I) {
            int32_t first = nl;
            S->lbrow[I] = nl;
            for (p = A->rowptr[3 * I]; p < A->rowptr[3 * I + 1]; p += 3)
                if (A->col[p] / 3 < I) S->lbcol[nl++] = A->col[p] / 3;
            /* L row 3I+a holds A's columns <= 3I+a in order: the lower blocks, then the diagonal
             * block's columns 3I..3I+a (wr__ic_create keeps A's order) */
            for (a = 0; a < 3; ++a) {
                k = first;
                for (p = S->lrow[3 * I + a]; p < S->lrow[3 * I + a + 1]; ++p) {
                    int32_t J = S->lcol[p] / 3, b = S->lcol[p] % 3;
                    if (J < I) {
                        S->lpack[p] = 9 * k + 3 * a + b;
                        if (b == 2) k++;
                    } else {
                        S->lpack[p] = -(1 + 6 * I + a * (a + 1) / 2 + b);
                    }
                }
            }
        }
        S->lbrow[nb] = nl;
    }
    S->nb = nb;
    return WR_OK;
}

/* Numeric: the operator's upper blocks from the (masked) values. */
static void wr__block_fill_op(wr_spd_solver *S, const double *val) {
    int32_t p;
    for (p = 0; p < S->nnz; ++p)
        if (S->apack[p] >= 0) S->abval[S->apack[p]] = val[p];
}

/* Round the double IC(0) factor into the single-precision blocks; diagonal pivots as reciprocals so
 * the sweeps multiply (the same rounded numbers serve L~ and L~^T: M stays symmetric). */
static void wr__ic_pack(wr_spd_solver *S) {
    int32_t p, nz = S->lrow[S->n];
    for (p = 0; p < nz; ++p) {
        int32_t d = S->lpack[p];
        if (d >= 0) {
            S->lboff[d] = (float)S->lval[p];
        } else {
            int32_t t = -d - 1, u = t % 6;
            S->lbdia[t] = (u == 0 || u == 2 || u == 5) ? (float)(1.0 / S->lval[p]) : (float)S->lval[p];
        }
    }
}

/* y = A x with the symmetric upper block triangle: block (I, J), J > I, serves y_I += B x_J and
 * y_J += B^T x_I. Returns x^T y (PCG's p^T A p), summed as each y_I becomes final (rows after I
 * only add to y_J, J > I), which saves CG a separate pass over two vectors. */
static double wr__bspmv(const wr_spd_solver *S, const double *x, double *y) {
    int32_t I, k, nb = S->nb;
    double xy = 0.0;
    memset(y, 0, sizeof(double) * 3 * (size_t)nb);
    for (I = 0; I < nb; ++I) {
        const double *B = S->abval + 9 * (size_t)S->abrow[I];
        double x0 = x[3 * I], x1 = x[3 * I + 1], x2 = x[3 * I + 2];
        double s0 = y[3 * I] + B[0] * x0 + B[1] * x1 + B[2] * x2;
        double s1 = y[3 * I + 1] + B[3] * x0 + B[4] * x1 + B[5] * x2;
        double s2 = y[3 * I + 2] + B[6] * x0 + B[7] * x1 + B[8] * x2;
        for (k = S->abrow[I] + 1; k < S->abrow[I + 1]; ++k) {
            const double *xj;
            double *yj;
            B += 9;
            xj = x + 3 * (size_t)S->abcol[k];
            yj = y + 3 * (size_t)S->abcol[k];
            s0 += B[0] * xj[0] + B[1] * xj[1] + B[2] * xj[2];
            s1 += B[3] * xj[0] + B[4] * xj[1] + B[5] * xj[2];
            s2 += B[6] * xj[0] + B[7] * xj[1] + B[8] * xj[2];
            yj[0] += B[0] * x0 + B[3] * x1 + B[6] * x2;
            yj[1] += B[1] * x0 + B[4] * x1 + B[7] * x2;
            yj[2] += B[2] * x0 + B[5] * x1 + B[8] * x2;
        }
        y[3 * I] = s0;
        y[3 * I + 1] = s1;
        y[3 * I + 2] = s2;
        xy += x0 * s0 + x1 * s1 + x2 * s2;
    }
    return xy;
}

/* z = (L~ L~^T)^{-1} r by block rows: forward with the lower blocks and the diagonal triangle,
 * backward with the same blocks transposed (the scalar wr__ic_apply, grouped by 3). Returns r^T z
 * (PCG's rho), summed in the backward sweep where each z_I becomes final. */
static double wr__ic_apply_blocked(const wr_spd_solver *S, const double *r, double *z) {
    int32_t I, k, nb = S->nb;
    double rz = 0.0;
    for (I = 0; I < nb; ++I) {
        const float *d = S->lbdia + 6 * (size_t)I;
        double s0 = r[3 * I], s1 = r[3 * I + 1], s2 = r[3 * I + 2], z0, z1;
        for (k = S->lbrow[I]; k < S->lbrow[I + 1]; ++k) {
            const float *B = S->lboff + 9 * (size_t)k;
            const double *zj = z + 3 * (size_t)S->lbcol[k];
            s0 -= (double)B[0] * zj[0] + (double)B[1] * zj[1] + (double)B[2] * zj[2];
            s1 -= (double)B[3] * zj[0] + (double)B[4] * zj[1] + (double)B[5] * zj[2];
            s2 -= (double)B[6] * zj[0] + (double)B[7] * zj[1] + (double)B[8] * zj[2];
        }
        z0 = s0 * (double)d[0];
        z1 = (s1 - (double)d[1] * z0) * (double)d[2];
        z[3 * I] = z0;
        z[3 * I + 1] = z1;
        z[3 * I + 2] = (s2 - (double)d[3] * z0 - (double)d[4] * z1) * (double)d[5];
    }
    for (I = nb - 1; I >= 0; --I) {
        const float *d = S->lbdia + 6 * (size_t)I;
        double t2 = z[3 * I + 2] * (double)d[5], t1, t0;
        t1 = (z[3 * I + 1] - (double)d[4] * t2) * (double)d[2];
        t0 = (z[3 * I] - (double)d[1] * t1 - (double)d[3] * t2) * (double)d[0];
        z[3 * I] = t0;
        z[3 * I + 1] = t1;
        z[3 * I + 2] = t2;
        rz += r[3 * I] * t0 + r[3 * I + 1] * t1 + r[3 * I + 2] * t2;
        for (k = S->lbrow[I]; k < S->lbrow[I + 1]; ++k) {
            const float *B = S->lboff + 9 * (size_t)k;
            double *zj = z + 3 * (size_t)S->lbcol[k];
            zj[0] -= (double)B[0] * t0 + (double)B[3] * t1 + (double)B[6] * t2;
            zj[1] -= (double)B[1] * t0 + (double)B[4] * t1 + (double)B[7] * t2;
            zj[2] -= (double)B[2] * t0 + (double)B[5] * t1 + (double)B[8] * t2;
        }
    }
    return rz;
}

/* ---------------------------------------------------------------- smoothed aggregation AMG - */
/* Smoothed-aggregation algebraic multigrid (Vanek, Mandel & Brezina 1996) used as a PCG
 * preconditioner: one symmetric V(1,1) cycle (forward Gauss-Seidel before, backward after, so the
 * preconditioner is symmetric positive definite) per PCG iteration. Nodes are groups of WR_AMG_BS
 * DOFs when n is a multiple of 3 (the 3 displacement components of a vertex; coarse DOFs keep that
 * grouping), else single DOFs. Near-null space = the per-component constants (translations) only:
 * the matrix carries no geometry, so rotations are not available. Everything is rebuilt by
 * wr_spd_solver_factor because aggregation depends on the values. */
#define WR_AMG_MAX_LEVELS 12
#define WR_AMG_COARSE_MAX 600  /* DOFs: below this the level is solved by dense Cholesky */
#define WR_AMG_THETA 0.08      /* strength threshold on the finest level (Vanek et al. use 0.08, halved per level) */
#define WR_AMG_POWER_ITERS 12  /* power iterations for rho(D^-1 A) in the prolongator smoother */

typedef struct wr__amg_level {
    int32_t n, nc, own;
    int32_t *rp, *ci; /* level matrix (level 0: A's pattern, not owned) */
    double *v;
    double *dinv;
    int32_t *prp, *pci; /* prolongator P: n x nc */
    double *pv;
    double *x, *b, *r;
} wr__amg_level;

struct wr__spd_amg {
    int32_t nlev, bs;
    wr__amg_level lev[WR_AMG_MAX_LEVELS];
    double *dense; /* coarsest level: Cholesky factor, row-major lower */
    int32_t nd;
};

static void wr__amg_clear(struct wr__spd_amg *M) {
    int32_t l;
    if (!M) return;
    for (l = 0; l < M->nlev; ++l) {
        wr__amg_level *L = &M->lev[l];
        if (L->own) {
            wr_free(L->rp);
            wr_free(L->ci);
            wr_free(L->v);
        }
        wr_free(L->dinv);
        wr_free(L->prp);
        wr_free(L->pci);
        wr_free(L->pv);
        wr_free(L->x);
        wr_free(L->b);
        wr_free(L->r);
    }
    wr_free(M->dense);
    memset(M->lev, 0, sizeof M->lev);
    M->dense = NULL;
    M->nlev = 0;
    M->nd = 0;
}

/* C = A B for CSR A (n x m) and B (m x k); columns of C unsorted. Two passes with a marker. */
static int wr__spgemm(int32_t n, int32_t k, const int32_t *arp, const int32_t *aci, const double *av,
                      const int32_t *brp, const int32_t *bci, const double *bv, int32_t **crp, int32_t **cci,
                      double **cv) {
    int32_t *mark = (int32_t *)wr_alloc_array((size_t)k, sizeof(int32_t));
    int32_t *rp = (int32_t *)wr_alloc_array((size_t)n + 1, sizeof(int32_t)), *ci = NULL;
    double *v = NULL;
    int64_t nz = 0;
    int32_t i, p, q;
    if (!mark || !rp) goto fail;
    for (i = 0; i < k; ++i) mark[i] = -1;
    for (i = 0; i < n; ++i) {
        rp[i] = (int32_t)nz;
        for (p = arp[i]; p < arp[i + 1]; ++p)
            for (q = brp[aci[p]]; q < brp[aci[p] + 1]; ++q)
                if (mark[bci[q]] != i) {
                    mark[bci[q]] = i;
                    nz++;
                }
        if (nz > INT32_MAX) goto fail;
    }
    rp[n] = (int32_t)nz;
    ci = (int32_t *)wr_alloc_array((size_t)nz, sizeof(int32_t));
    v = (double *)wr_alloc_array((size_t)nz, sizeof(double));
    if (!ci || !v) goto fail;
    for (i = 0; i < k; ++i) mark[i] = -1;
    for (i = 0; i < n; ++i) {
        int32_t start = rp[i], end = rp[i];
        for (p = arp[i]; p < arp[i + 1]; ++p)
            for (q = brp[aci[p]]; q < brp[aci[p] + 1]; ++q) {
                int32_t c = bci[q];
                if (mark[c] < start) {
                    mark[c] = end;
                    ci[end] = c;
                    v[end] = av[p] * bv[q];
                    end++;
                } else {
                    v[mark[c]] += av[p] * bv[q];
                }
            }
    }
    wr_free(mark);
    *crp = rp;
    *cci = ci;
    *cv = v;
    return 1;
fail:
    wr_free(mark);
    wr_free(rp);
    wr_free(ci);
    wr_free(v);
    return 0;
}

/* Transpose of a CSR n x k matrix. */
static int wr__transpose(int32_t n, int32_t k, const int32_t *rp, const int32_t *ci, const double *v, int32_t **trp,
                         int32_t **tci, double **tv) {
    int32_t *r = (int32_t *)wr_calloc_array((size_t)k + 2, sizeof(int32_t));
    int32_t *c = (int32_t *)wr_alloc_array((size_t)rp[n], sizeof(int32_t));
    double *w = (double *)wr_alloc_array((size_t)rp[n], sizeof(double));
    int32_t i, p;
    if (!r || !c || !w) {
        wr_free(r);
        wr_free(c);
        wr_free(w);
        return 0;
    }
    for (p = 0; p < rp[n]; ++p) r[ci[p] + 2]++;
    for (i = 0; i < k; ++i) r[i + 2] += r[i + 1];
    for (i = 0; i < n; ++i)
        for (p = rp[i]; p < rp[i + 1]; ++p) {
            int32_t q = r[ci[p] + 1]++;
            c[q] = i;
            w[q] = v[p];
        }
    *trp = r;
    *tci = c;
    *tv = w;
    return 1;
}

/* Aggregate the nodes of level L; fills agg[node] (-1: left out of the coarse space). Returns the
 * number of aggregates, or -1 on allocation failure. */
static int32_t wr__amg_aggregate(const wr__amg_level *L, int32_t bs, double theta, int32_t *agg) {
    int32_t nn = L->n / bs, I, J, a = -1, na = 0, p, q;
    double *acc = (double *)wr_calloc_array((size_t)nn, sizeof(double));
    double *dn = (double *)wr_alloc_array((size_t)nn, sizeof(double));
    int32_t *list = (int32_t *)wr_alloc_array((size_t)nn, sizeof(int32_t));
    int32_t *srp = (int32_t *)wr_alloc_array((size_t)nn + 1, sizeof(int32_t));
    int32_t *sci = NULL, *snap = NULL;
    int64_t cap = (int64_t)L->rp[L->n] + 1, ns = 0; /* distinct neighbours <= stored entries */
    if (!acc || !dn || !list || !srp) goto done;
    sci = (int32_t *)wr_alloc_array((size_t)cap, sizeof(int32_t));
    snap = (int32_t *)wr_alloc_array((size_t)nn, sizeof(int32_t));
    if (!sci || !snap) goto done;
    /* Frobenius norms of the node blocks: diagonal first, then strong neighbours
     * ||A_IJ|| >= theta sqrt(||A_II|| ||A_JJ||). */
    for (I = 0; I < nn; ++I) {
        double s = 0.0;
        int32_t r;
        for (r = bs * I; r < bs * I + bs; ++r)
            for (p = L->rp[r]; p < L->rp[r + 1]; ++p)
                if (L->ci[p] / bs == I) s += L->v[p] * L->v[p];
        dn[I] = sqrt(s);
    }
    for (I = 0; I < nn; ++I) {
        int32_t r, cnt = 0;
        srp[I] = (int32_t)ns;
        for (r = bs * I; r < bs * I + bs; ++r)
            for (p = L->rp[r]; p < L->rp[r + 1]; ++p) {
                J = L->ci[p] / bs;
                if (J == I) continue;
                if (acc[J] == 0.0) list[cnt++] = J;
                acc[J] += L->v[p] * L->v[p] + 1e-300; /* the tiny term marks J as listed */
            }
        for (q = 0; q < cnt; ++q) {
            J = list[q];
            if (sqrt(acc[J]) >= theta * sqrt(dn[I] * dn[J])) sci[ns++] = J;
            acc[J] = 0.0;
        }
    }
    srp[nn] = (int32_t)ns;
    for (I = 0; I < nn; ++I) agg[I] = srp[I + 1] > srp[I] ? -1 : -2; /* -2: isolated, stays out */
    /* phase 1: a node whose strong neighbours are all free seeds an aggregate with them */
    for (I = 0; I < nn; ++I) {
        int ok = agg[I] == -1;
        for (p = srp[I]; p < srp[I + 1] && ok; ++p) ok = agg[sci[p]] == -1;
        if (!ok) continue;
        agg[I] = na;
        for (p = srp[I]; p < srp[I + 1]; ++p) agg[sci[p]] = na;
        na++;
    }
    /* phase 2: join a neighbouring phase-1 aggregate (snapshot so aggregates do not creep) */
    memcpy(snap, agg, sizeof(int32_t) * (size_t)nn);
    for (I = 0; I < nn; ++I) {
        if (snap[I] != -1) continue;
        for (p = srp[I]; p < srp[I + 1]; ++p)
            if (snap[sci[p]] >= 0) {
                agg[I] = snap[sci[p]];
                break;
            }
    }
    /* phase 3: leftovers group with their still-free strong neighbours */
    for (I = 0; I < nn; ++I) {
        if (agg[I] != -1) continue;
        agg[I] = na;
        for (p = srp[I]; p < srp[I + 1]; ++p)
            if (agg[sci[p]] == -1) agg[sci[p]] = na;
        na++;
    }
    for (I = 0; I < nn; ++I)
        if (agg[I] < -1) agg[I] = -1;
    a = na;
done: /* one exit: a stays -1 when an allocation failed */
    wr_free(acc);
    wr_free(dn);
    wr_free(list);
    wr_free(srp);
    wr_free(sci);
    wr_free(snap);
    return a;
}

/* rho(D^-1 A) by power iteration from a fixed deterministic start (no RNG state needed). */
static double wr__amg_rho(const wr__amg_level *L, double *u, double *w) {
    int32_t i, it, p;
    double lam = 1.0, nrm;
    uint64_t h = 0x9E3779B97F4A7C15ULL;
    for (i = 0; i < L->n; ++i) {
        h ^= h >> 33;
        h *= 0xFF51AFD7ED558CCDULL;
        h ^= h >> 29;
        u[i] = (double)(h >> 11) * (1.0 / 9007199254740992.0) - 0.5;
    }
    for (it = 0; it < WR_AMG_POWER_ITERS; ++it) {
        nrm = 0.0;
        for (i = 0; i < L->n; ++i) {
            double s = 0.0;
            for (p = L->rp[i]; p < L->rp[i + 1]; ++p) s += L->v[p] * u[L->ci[p]];
            w[i] = s * L->dinv[i];
            nrm += w[i] * w[i];
        }
        nrm = sqrt(nrm);
        if (!(nrm > 0.0)) return 1.0;
        lam = 0.0;
        for (i = 0; i < L->n; ++i) lam += u[i] * w[i];
        {
            double un = 0.0;
            for (i = 0; i < L->n; ++i) un += u[i] * u[i];
            lam /= un;
        }
        for (i = 0; i < L->n; ++i) u[i] = w[i] / nrm;
    }
    return lam > 0.0 ? lam : 1.0;
}

/* a level's work vectors and inverse diagonal (a non-positive diagonal is WR_ERR_NOT_SPD) */
static wr_status wr__amg_level_init(wr__amg_level *L, int32_t l, wr_diag *diag) {
    int32_t i, p;
    L->dinv = (double *)wr_alloc_array((size_t)L->n, sizeof(double));
    L->x = (double *)wr_alloc_array((size_t)L->n, sizeof(double));
    L->b = (double *)wr_alloc_array((size_t)L->n, sizeof(double));
    L->r = (double *)wr_alloc_array((size_t)L->n, sizeof(double));
    if (!L->dinv || !L->x || !L->b || !L->r) return wr_fail(diag, WR_ERR_NOMEM, -1, "pcg-amg: out of memory");
    for (i = 0; i < L->n; ++i) {
        double d = 0.0;
        for (p = L->rp[i]; p < L->rp[i + 1]; ++p)
            if (L->ci[p] == i) d += L->v[p];
        if (!(d > 0.0))
            return wr_fail(diag, WR_ERR_NOT_SPD, l == 0 ? i : -1, "pcg-amg: level %d diagonal %d = %g <= 0", (int)l,
                           (int)i, d);
        L->dinv[i] = 1.0 / d;
    }
    return WR_OK;
}

/* smoothed prolongator P = (I - omega D^-1 A) P_tent, P_tent(bs*I+c, bs*agg(I)+c) = 1 (agg is freed) */
static wr_status wr__amg_prolongator(const wr_spd_solver *S, wr__amg_level *L, int32_t l, int32_t bs, int32_t *agg,
                                     double omega, wr_diag *diag) {
    int32_t *map = (int32_t *)wr_alloc_array((size_t)L->n, sizeof(int32_t));
    int32_t *mark = (int32_t *)wr_alloc_array((size_t)L->nc, sizeof(int32_t));
    int64_t nz = 0;
    int32_t i, p;
    if (!map || !mark) {
        wr_free(map);
        wr_free(mark);
        wr_free(agg);
        return wr_fail(diag, WR_ERR_NOMEM, -1, "pcg-amg: out of memory");
    }
    for (i = 0; i < L->n; ++i) {
        int32_t I = i / bs;
        map[i] = (agg[I] >= 0 && !(l == 0 && S->fixed && S->fixed[i])) ? bs * agg[I] + i % bs : -1;
    }
    wr_free(agg);
    for (i = 0; i < L->nc; ++i) mark[i] = -1;
    for (i = 0; i < L->n; ++i) {
        if (map[i] >= 0 && mark[map[i]] != i) {
            mark[map[i]] = i;
            nz++;
        }
        for (p = L->rp[i]; p < L->rp[i + 1]; ++p) {
            int32_t c = map[L->ci[p]];
            if (c >= 0 && mark[c] != i) {
                mark[c] = i;
                nz++;
            }
        }
    }
    L->prp = (int32_t *)wr_alloc_array((size_t)L->n + 1, sizeof(int32_t));
    L->pci = (int32_t *)wr_alloc_array((size_t)nz, sizeof(int32_t));
    L->pv = (double *)wr_alloc_array((size_t)nz, sizeof(double));
    if (nz > INT32_MAX || !L->prp || !L->pci || !L->pv) {
        wr_free(map);
        wr_free(mark);
        return wr_fail(diag, WR_ERR_NOMEM, -1, "pcg-amg: out of memory");
    }
    for (i = 0; i < L->nc; ++i) mark[i] = -1;
    nz = 0;
    for (i = 0; i < L->n; ++i) {
        int32_t start = (int32_t)nz;
        double s = -omega * L->dinv[i];
        L->prp[i] = start;
        if (map[i] >= 0) {
            mark[map[i]] = (int32_t)nz;
            L->pci[nz] = map[i];
            L->pv[nz] = 1.0;
            nz++;
        }
        for (p = L->rp[i]; p < L->rp[i + 1]; ++p) {
            int32_t c = map[L->ci[p]];
            if (c < 0) continue;
            if (mark[c] < start) {
                mark[c] = (int32_t)nz;
                L->pci[nz] = c;
                L->pv[nz] = s * L->v[p];
                nz++;
            } else {
                L->pv[mark[c]] += s * L->v[p];
            }
        }
    }
    L->prp[L->n] = (int32_t)nz;
    wr_free(map);
    wr_free(mark);
    return WR_OK;
}

/* Galerkin coarse operator A_c = P^T (A P) into level l + 1 */
static wr_status wr__amg_galerkin(struct wr__spd_amg *M, int32_t l, wr_diag *diag) {
    wr__amg_level *L = &M->lev[l], *C = &M->lev[l + 1];
    int32_t *trp = NULL, *tci = NULL, *aprp, *apci;
    double *tv = NULL, *apv;
    int okc;
    if (!wr__spgemm(L->n, L->nc, L->rp, L->ci, L->v, L->prp, L->pci, L->pv, &aprp, &apci, &apv))
        return wr_fail(diag, WR_ERR_NOMEM, -1, "pcg-amg: out of memory (A P)");
    if (!wr__transpose(L->n, L->nc, L->prp, L->pci, L->pv, &trp, &tci, &tv)) {
        wr_free(aprp);
        wr_free(apci);
        wr_free(apv);
        return wr_fail(diag, WR_ERR_NOMEM, -1, "pcg-amg: out of memory (P^T)");
    }
    okc = wr__spgemm(L->nc, L->nc, trp, tci, tv, aprp, apci, apv, &C->rp, &C->ci, &C->v);
    wr_free(trp);
    wr_free(tci);
    wr_free(tv);
    wr_free(aprp);
    wr_free(apci);
    wr_free(apv);
    C->own = 1;
    C->n = L->nc;
    M->nlev = l + 2;
    if (!okc) return wr_fail(diag, WR_ERR_NOMEM, -1, "pcg-amg: out of memory (P^T A P)");
    return WR_OK;
}

/* coarsest level: dense Cholesky */
static wr_status wr__amg_coarsest(struct wr__spd_amg *M, wr_diag *diag) {
    wr__amg_level *L = &M->lev[M->nlev - 1];
    int32_t nd = L->n, i, j, k, p;
    double *D;
    if ((int64_t)nd * nd > 4000000) /* 2000^2: only when coarsening stalled on a huge level */
        return wr_fail(diag, WR_ERR_UNSUPPORTED, -1, "pcg-amg: coarsening stalled at %d DOFs", (int)nd);
    D = M->dense = (double *)wr_calloc_array((size_t)nd * (size_t)nd, sizeof(double));
    if (!D) return wr_fail(diag, WR_ERR_NOMEM, -1, "pcg-amg: out of memory");
    M->nd = nd;
    for (i = 0; i < nd; ++i)
        for (p = L->rp[i]; p < L->rp[i + 1]; ++p) D[(size_t)i * nd + L->ci[p]] += L->v[p];
    for (j = 0; j < nd; ++j) {
        double d = D[(size_t)j * nd + j];
        for (k = 0; k < j; ++k) d -= D[(size_t)j * nd + k] * D[(size_t)j * nd + k];
        if (!(d > 0.0))
            return wr_fail(diag, WR_ERR_NOT_SPD, -1, "pcg-amg: coarsest matrix not positive definite (pivot %d)", (int)j);
        d = sqrt(d);
        D[(size_t)j * nd + j] = d;
        for (i = j + 1; i < nd; ++i) {
            double s = D[(size_t)i * nd + j];
            for (k = 0; k < j; ++k) s -= D[(size_t)i * nd + k] * D[(size_t)j * nd + k];
            D[(size_t)i * nd + j] = s / d;
        }
    }
    return WR_OK;
}

/* The hierarchy: per level the diagonal, aggregation, smoothed prolongator and Galerkin operator,
 * until the level is small (WR_AMG_COARSE_MAX) or coarsening stalls; then the dense coarsest factor. */
static wr_status wr__amg_setup(wr_spd_solver *S, const wr_csr *A, const double *val, wr_diag *diag) {
    struct wr__spd_amg *M = S->amg;
    int32_t l;
    double theta = WR_AMG_THETA;
    wr_status rs;
    wr__amg_clear(M);
    M->bs = (A->n % 3 == 0) ? 3 : 1;
    M->lev[0].n = A->n;
    M->lev[0].rp = A->rowptr;
    M->lev[0].ci = A->col;
    M->lev[0].v = (double *)val;
    M->lev[0].own = 0;
    M->nlev = 1;
    for (l = 0;; ++l) {
        wr__amg_level *L = &M->lev[l];
        int32_t *agg, na, nn, bs = M->bs;
        double omega;
        if ((rs = wr__amg_level_init(L, l, diag)) != WR_OK) return rs;
        if (L->n <= WR_AMG_COARSE_MAX || l + 1 >= WR_AMG_MAX_LEVELS) break;
        nn = L->n / bs;
        agg = (int32_t *)wr_alloc_array((size_t)nn, sizeof(int32_t));
        if (!agg) return wr_fail(diag, WR_ERR_NOMEM, -1, "pcg-amg: out of memory");
        na = wr__amg_aggregate(L, bs, theta, agg);
        if (na < 0) {
            wr_free(agg);
            return wr_fail(diag, WR_ERR_NOMEM, -1, "pcg-amg: out of memory");
        }
        if (na == 0 || (int64_t)na * bs * 10 > (int64_t)L->n * 9) { /* coarsening stalled */
            wr_free(agg);
            break;
        }
        L->nc = na * bs;
        omega = 4.0 / (3.0 * 1.05 * wr__amg_rho(L, L->x, L->r));
        if ((rs = wr__amg_prolongator(S, L, l, bs, agg, omega, diag)) != WR_OK) return rs;
        if ((rs = wr__amg_galerkin(M, l, diag)) != WR_OK) return rs;
        theta *= 0.5;
    }
    return wr__amg_coarsest(M, diag);
}

/* One symmetric V(1,1) cycle for A_l x = b_l from x = 0 (x, b in the level's work vectors). */
static void wr__amg_vcycle(struct wr__spd_amg *M, int32_t l) {
    wr__amg_level *L = &M->lev[l];
    int32_t i, p, n = L->n;
    if (l == M->nlev - 1) {
        const double *D = M->dense;
        int32_t nd = M->nd, k;
        for (i = 0; i < nd; ++i) {
            double s = L->b[i];
            for (k = 0; k < i; ++k) s -= D[(size_t)i * nd + k] * L->x[k];
            L->x[i] = s / D[(size_t)i * nd + i];
        }
        for (i = nd - 1; i >= 0; --i) {
            double s = L->x[i];
            for (k = i + 1; k < nd; ++k) s -= D[(size_t)k * nd + i] * L->x[k];
            L->x[i] = s / D[(size_t)i * nd + i];
        }
        return;
    }
    /* forward Gauss-Seidel from x = 0 */
    for (i = 0; i < n; ++i) {
        double s = L->b[i];
        for (p = L->rp[i]; p < L->rp[i + 1]; ++p)
            if (L->ci[p] < i) s -= L->v[p] * L->x[L->ci[p]];
        L->x[i] = s * L->dinv[i];
    }
    {
        wr__amg_level *C = &M->lev[l + 1];
        for (i = 0; i < C->n; ++i) C->b[i] = 0.0;
        for (i = 0; i < n; ++i) {
            double s = L->b[i];
            for (p = L->rp[i]; p < L->rp[i + 1]; ++p) s -= L->v[p] * L->x[L->ci[p]];
            for (p = L->prp[i]; p < L->prp[i + 1]; ++p) C->b[L->pci[p]] += L->pv[p] * s; /* b_c = P^T r */
        }
        wr__amg_vcycle(M, l + 1);
        for (i = 0; i < n; ++i) {
            double s = 0.0;
            for (p = L->prp[i]; p < L->prp[i + 1]; ++p) s += L->pv[p] * C->x[L->pci[p]];
            L->x[i] += s;
        }
    }
    /* backward Gauss-Seidel */
    for (i = n - 1; i >= 0; --i) {
        double s = L->b[i];
        for (p = L->rp[i]; p < L->rp[i + 1]; ++p) s -= L->v[p] * L->x[L->ci[p]];
        L->x[i] += s * L->dinv[i];
    }
}

static void wr__amg_apply(struct wr__spd_amg *M, const double *r, double *z) {
    wr__amg_level *L = &M->lev[0];
    memcpy(L->b, r, sizeof(double) * (size_t)L->n);
    wr__amg_vcycle(M, 0);
    memcpy(z, L->x, sizeof(double) * (size_t)L->n);
}

WRDEF wr_status wr_spd_solver_create(wr_spd_solver *S, const wr_csr *A, const wr_spd_desc *desc, wr_diag *diag) {
    wr_status st;
    double t0 = wr_time_seconds();
    int32_t i;
    if (!S) return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "spd_solver_create: NULL solver");
    memset(S, 0, sizeof *S);
    if ((st = wr__check_matrix(A, "spd_solver_create", diag)) != WR_OK) return st;
    if (desc && (desc->method < WR_SOLVER_AUTO || desc->method >= WR_SOLVER_METHOD_COUNT))
        return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "spd_solver_create: unknown method %d", (int)desc->method);
    if (desc && (desc->rel_tol < 0.0 || desc->rel_tol != desc->rel_tol || desc->max_iter < 0))
        return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "spd_solver_create: rel_tol = %g, max_iter = %d", desc->rel_tol,
                       (int)desc->max_iter);
    S->n = A->n;
    S->nnz = A->nnz;
    wr__solver_resolve(S, desc);
    if (S->method == WR_SOLVER_PCG_BLOCK3 && A->n % 3 != 0)
        return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "pcg-block3: n = %d is not a multiple of 3", (int)A->n);
#if !(defined(WR_USE_CHOLMOD) && WR_USE_CHOLMOD)
    if (S->method == WR_SOLVER_CHOLMOD)
        return wr_fail(diag, WR_ERR_UNSUPPORTED, -1, "CHOLMOD backend not compiled in (define WR_USE_CHOLMOD=1)");
#endif
    S->n_free = A->n;
    if (desc && desc->fixed) {
        S->fixed = (uint8_t *)wr_alloc_array((size_t)A->n, 1);
        if (!S->fixed) return wr_fail(diag, WR_ERR_NOMEM, -1, "spd_solver_create: out of memory");
        for (i = 0; i < A->n; ++i) {
            S->fixed[i] = desc->fixed[i] ? 1 : 0;
            S->n_free -= S->fixed[i];
        }
    }
    st = WR_OK;
    switch (S->method) {
    case WR_SOLVER_PCG_JACOBI:
        S->prec = (double *)wr_alloc_array((size_t)A->n, sizeof(double));
        if (!S->prec) st = wr_fail(diag, WR_ERR_NOMEM, -1, "pcg-jacobi: out of memory");
        break;
    case WR_SOLVER_PCG_BLOCK3:
        S->prec = (double *)wr_alloc_array((size_t)A->n / 3, 9 * sizeof(double));
        if (!S->prec) st = wr_fail(diag, WR_ERR_NOMEM, -1, "pcg-block3: out of memory");
        break;
    case WR_SOLVER_PCG_IC0:
        st = wr__ic_create(S, A, diag);
        break;
    case WR_SOLVER_CHOLMOD:
#if defined(WR_USE_CHOLMOD) && WR_USE_CHOLMOD
        st = wr__chol_create(S, A, diag);
#endif
        break;
    case WR_SOLVER_PCG_AMG:
        S->amg = (struct wr__spd_amg *)wr_calloc_array(1, sizeof(struct wr__spd_amg));
        if (!S->amg) st = wr_fail(diag, WR_ERR_NOMEM, -1, "pcg-amg: out of memory");
        break;
    default:
        st = wr_fail(diag, WR_ERR_INVALID_ARG, -1, "spd_solver_create: bad method");
    }
    if (st == WR_OK && S->method != WR_SOLVER_CHOLMOD) st = wr__block_create(S, A, diag);
    if (st == WR_OK && S->fixed && S->method != WR_SOLVER_CHOLMOD) {
        S->mval = (double *)wr_alloc_array((size_t)A->nnz, sizeof(double));
        if (!S->mval) st = wr_fail(diag, WR_ERR_NOMEM, -1, "spd_solver_create: out of memory");
    }
    if (st != WR_OK) {
        wr_spd_solver_free(S);
        return st;
    }
    S->analyze_seconds = wr_time_seconds() - t0;
    return WR_OK;
}

/* A 3×3 block's Cholesky pivot must exceed this fraction of its trace (|trace| sum) [1]: below it the
 * block is singular to rounding (≈ 45 ulps), and block-Jacobi would amplify noise. */
#define WR__BLOCK3_PIVOT_REL 1e-14

/* Cholesky of a 3×3 SPD block, then its inverse (row-major). 0 when not positive definite. */
static int wr__block3_inverse(const double *M, double *inv) {
    double l00, l10, l20, l11, l21, l22, i00, i10, i20, i11, i21, i22;
    double s = fabs(M[0]) + fabs(M[4]) + fabs(M[8]);
    if (!(M[0] > WR__BLOCK3_PIVOT_REL * s)) return 0;
    l00 = sqrt(M[0]);
    l10 = M[3] / l00;
    l20 = M[6] / l00;
    if (!(M[4] - l10 * l10 > WR__BLOCK3_PIVOT_REL * s)) return 0;
    l11 = sqrt(M[4] - l10 * l10);
    l21 = (M[7] - l20 * l10) / l11;
    if (!(M[8] - l20 * l20 - l21 * l21 > WR__BLOCK3_PIVOT_REL * s)) return 0;
    l22 = sqrt(M[8] - l20 * l20 - l21 * l21);
    /* inverse of L (lower), then inv = L^-T L^-1 */
    i00 = 1.0 / l00;
    i11 = 1.0 / l11;
    i22 = 1.0 / l22;
    i10 = -l10 * i00 * i11;
    i21 = -l21 * i11 * i22;
    i20 = -(l20 * i00 + l21 * i10) * i22;
    inv[0] = i00 * i00 + i10 * i10 + i20 * i20;
    inv[1] = inv[3] = i10 * i11 + i20 * i21;
    inv[2] = inv[6] = i20 * i22;
    inv[4] = i11 * i11 + i21 * i21;
    inv[5] = inv[7] = i21 * i22;
    inv[8] = i22 * i22;
    return 1;
}

WRDEF wr_status wr_spd_solver_factor(wr_spd_solver *S, const wr_csr *A, wr_diag *diag) {
    wr_status st;
    const double *val;
    double t0 = wr_time_seconds();
    int32_t i, p;
    if (!S || (!S->prec && !S->lval && !S->backend && !S->amg))
        return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "spd_solver_factor: solver not created");
    if ((st = wr__check_matrix(A, "spd_solver_factor", diag)) != WR_OK) return st;
    if (A->n != S->n || A->nnz != S->nnz)
        return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "spd_solver_factor: matrix n = %d, nnz = %d but solver has %d, %d",
                       (int)A->n, (int)A->nnz, (int)S->n, (int)S->nnz);
    S->factored = 0;
    val = A->val;
    if (S->mval) {
        /* Masked copy: fixed rows and columns become identity rows/columns. */
        for (i = 0; i < A->n; ++i)
            for (p = A->rowptr[i]; p < A->rowptr[i + 1]; ++p) {
                int32_t j = A->col[p];
                if (S->fixed[i] || S->fixed[j])
                    S->mval[p] = i == j ? 1.0 : 0.0;
                else
                    S->mval[p] = A->val[p];
            }
        val = S->mval;
    }
    for (p = 0; p < A->nnz; ++p)
        if (!isfinite(val[p])) return wr_fail(diag, WR_ERR_DOMAIN, p, "spd_solver_factor: non-finite value at entry %d", (int)p);
    switch (S->method) {
    case WR_SOLVER_PCG_JACOBI:
        for (i = 0; i < A->n; ++i) {
            int32_t q = wr_csr_find(A, i, i);
            double d = q >= 0 ? val[q] : 0.0;
            if (!(d > 0.0)) return wr_fail(diag, WR_ERR_NOT_SPD, i, "pcg-jacobi: diagonal A(%d,%d) = %g <= 0", (int)i, (int)i, d);
            S->prec[i] = 1.0 / d;
        }
        break;
    case WR_SOLVER_PCG_BLOCK3: {
        int32_t I, nb = A->n / 3;
        for (I = 0; I < nb; ++I) {
            double M[9];
            int a;
            for (a = 0; a < 9; ++a) M[a] = 0.0;
            for (a = 0; a < 3; ++a)
                for (p = A->rowptr[3 * I + a]; p < A->rowptr[3 * I + a + 1]; ++p) {
                    int32_t c = A->col[p] - 3 * I;
                    if (c >= 0 && c < 3) M[3 * a + c] = val[p];
                }
            /* symmetrise the block: the caller's A is symmetric up to round-off */
            M[1] = M[3] = 0.5 * (M[1] + M[3]);
            M[2] = M[6] = 0.5 * (M[2] + M[6]);
            M[5] = M[7] = 0.5 * (M[5] + M[7]);
            if (!wr__block3_inverse(M, S->prec + 9 * (size_t)I))
                return wr_fail(diag, WR_ERR_NOT_SPD, I, "pcg-block3: diagonal block %d is not positive definite", (int)I);
        }
        break;
    }
    case WR_SOLVER_PCG_IC0:
        if ((st = wr__ic_factor(S, val, diag)) != WR_OK) return st;
        if (S->nb > 0) wr__ic_pack(S);
        break;
    case WR_SOLVER_CHOLMOD:
#if defined(WR_USE_CHOLMOD) && WR_USE_CHOLMOD
        if ((st = wr__chol_factor(S, A, diag)) != WR_OK) return st;
#endif
        break;
    case WR_SOLVER_PCG_AMG:
        if ((st = wr__amg_setup(S, A, val, diag)) != WR_OK) return st;
        break;
    default:
        return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "spd_solver_factor: bad method");
    }
    if (S->nb > 0) wr__block_fill_op(S, val);
    S->factored = 1;
    S->factor_seconds = wr_time_seconds() - t0;
    return WR_OK;
}

/* z = M^{-1} r (zero on fixed DOFs); returns r^T z. */
static double wr__prec_apply(wr_spd_solver *S, const double *r, double *z) {
    int32_t i, n = S->n;
    if (S->method == WR_SOLVER_PCG_IC0 && S->nb > 0) {
        /* the masked rows are identity and r is 0 there, so z is exactly 0 on fixed DOFs already
         * (row i of L is e_i, and L_ki = 0 below it because A_ki = 0 and L_i,<i = 0) */
        return wr__ic_apply_blocked(S, r, z);
    }
    switch (S->method) {
    case WR_SOLVER_PCG_JACOBI:
        for (i = 0; i < n; ++i) z[i] = S->prec[i] * r[i];
        break;
    case WR_SOLVER_PCG_BLOCK3:
        for (i = 0; i < n; i += 3) {
            const double *M = S->prec + 3 * (size_t)i;
            double a = r[i], b = r[i + 1], c = r[i + 2];
            z[i] = M[0] * a + M[1] * b + M[2] * c;
            z[i + 1] = M[3] * a + M[4] * b + M[5] * c;
            z[i + 2] = M[6] * a + M[7] * b + M[8] * c;
        }
        break;
    case WR_SOLVER_PCG_IC0:
        wr__ic_apply(S, r, z);
        break;
    case WR_SOLVER_PCG_AMG:
        wr__amg_apply(S->amg, r, z);
        break;
    default:
        for (i = 0; i < n; ++i) z[i] = r[i];
    }
    if (S->fixed)
        for (i = 0; i < n; ++i)
            if (S->fixed[i]) z[i] = 0.0;
    return wr__dot(n, r, z);
}

static void wr__fill_stats(wr_spd_stats *st, const wr_spd_solver *S, int32_t it, double rel, double t0, wr_spd_stop stop) {
    if (!st) return;
    st->method = S->method;
    st->iterations = it;
    st->rel_residual = rel;
    st->analyze_seconds = S->analyze_seconds;
    st->setup_seconds = S->analyze_seconds + S->factor_seconds;
    st->solve_seconds = wr_time_seconds() - t0;
    st->stop = stop;
    st->ic_shift = S->ic_shift;
    st->n_free = S->n_free;
}

WRDEF wr_status wr_spd_solver_solve(wr_spd_solver *S, const wr_csr *A, const double *b, double *x,
                                    wr_spd_stats *stats, wr_diag *diag) {
    double t0 = wr_time_seconds(), bnorm, rnorm, tol_abs, rz;
    double *r = NULL, *z = NULL, *pv = NULL, *q = NULL;
    const double *val;
    int32_t n, i, it = 0, replacements = 0;
    wr_status st = WR_OK;
    wr_spd_stop stop = WR_SPD_STOP_NONE;
    if (stats) memset(stats, 0, sizeof *stats);
    if (!S || !S->factored) return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "spd_solver_solve: solver not factored");
    if ((st = wr__check_matrix(A, "spd_solver_solve", diag)) != WR_OK) return st;
    if (A->n != S->n || A->nnz != S->nnz)
        return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "spd_solver_solve: matrix n = %d, nnz = %d but solver has %d, %d",
                       (int)A->n, (int)A->nnz, (int)S->n, (int)S->nnz);
    if (!b || !x) return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "spd_solver_solve: NULL b or x");
    n = S->n;
    for (i = 0; i < n; ++i)
        if (!isfinite(b[i]) || !isfinite(x[i]))
            return wr_fail(diag, WR_ERR_DOMAIN, i, "spd_solver_solve: b[%d] = %g, x[%d] = %g", (int)i, b[i], (int)i, x[i]);
    r = (double *)wr_alloc_array((size_t)n, sizeof(double));
    z = (double *)wr_alloc_array((size_t)n, sizeof(double));
    pv = (double *)wr_calloc_array((size_t)n, sizeof(double));
    q = (double *)wr_alloc_array((size_t)n, sizeof(double));
    if (!r || !z || !pv || !q) {
        st = wr_fail(diag, WR_ERR_NOMEM, -1, "spd_solver_solve: out of memory (n = %d)", (int)n);
        goto done;
    }
    /* Effective right-hand side (b - A x_fixed) on free DOFs: the scale of the relative residual. */
    for (i = 0; i < n; ++i) pv[i] = (S->fixed && S->fixed[i]) ? x[i] : 0.0;
    bnorm = wr__residual(S, A, b, pv, r);
    if (bnorm == 0.0) {
        for (i = 0; i < n; ++i) x[i] = pv[i];
        wr__fill_stats(stats, S, 0, 0.0, t0, WR_SPD_STOP_ZERO_RHS);
        goto done;
    }
    tol_abs = S->rel_tol * bnorm;
    if (S->method == WR_SOLVER_CHOLMOD) {
#if defined(WR_USE_CHOLMOD) && WR_USE_CHOLMOD
        /* x_f = A_ff^-1 (b - A_fc x_c); r currently holds exactly that right-hand side. */
        if ((st = wr__chol_solve(S, r, x, diag)) != WR_OK) goto done;
        rnorm = wr__residual(S, A, b, x, r);
        while (rnorm > tol_abs && it < WR_SPD_MAX_REFINEMENTS) {
            /* iterative refinement: x += A_ff^-1 r */
            for (i = 0; i < n; ++i) z[i] = 0.0;
            if ((st = wr__chol_solve(S, r, z, diag)) != WR_OK) goto done;
            for (i = 0; i < n; ++i) x[i] += z[i];
            rnorm = wr__residual(S, A, b, x, r);
            it++;
        }
        stop = rnorm <= tol_abs ? WR_SPD_STOP_CONVERGED : WR_SPD_STOP_DIRECT_INACCURATE;
        wr__fill_stats(stats, S, it, rnorm / bnorm, t0, stop);
        if (stop != WR_SPD_STOP_CONVERGED)
            st = wr_fail(diag, WR_ERR_NOT_CONVERGED, -1, "cholmod: relative residual %g > %g after %d refinements",
                         rnorm / bnorm, S->rel_tol, (int)it);
#endif
        goto done;
    }
    /* ---- PCG on the masked operator (Hestenes–Stiefel with residual replacement) ---- */
    val = S->mval ? S->mval : A->val;
    rnorm = wr__residual(S, A, b, x, r);
    if (rnorm <= tol_abs) {
        stop = WR_SPD_STOP_CONVERGED;
    } else {
        rz = wr__prec_apply(S, r, z);
        memcpy(pv, z, sizeof(double) * (size_t)n);
        while (stop == WR_SPD_STOP_NONE) {
            double pq, alpha, beta, rz_new, rr = 0.0;
            if (it >= S->max_iter) {
                stop = WR_SPD_STOP_MAX_ITER;
                break;
            }
            if (S->nb > 0) {
                pq = wr__bspmv(S, pv, q);
            } else {
                wr__spmv_vals(A, val, pv, q);
                pq = wr__dot(n, pv, q);
            }
            if (!isfinite(pq) || !isfinite(rz)) {
                stop = WR_SPD_STOP_NONFINITE;
                break;
            }
            if (!(pq > 0.0)) {
                stop = WR_SPD_STOP_NOT_SPD;
                break;
            }
            alpha = rz / pq;
            for (i = 0; i < n; ++i) {
                x[i] += alpha * pv[i];
                r[i] -= alpha * q[i];
                rr += r[i] * r[i];
            }
            it++;
            if (sqrt(rr) <= tol_abs) {
                /* recursive residual says done: check the true one */
                rnorm = wr__residual(S, A, b, x, r);
                if (rnorm <= tol_abs) {
                    stop = WR_SPD_STOP_CONVERGED;
                    break;
                }
                if (replacements >= WR_SPD_MAX_REPLACEMENTS) {
                    stop = WR_SPD_STOP_MAX_ITER;
                    break;
                }
                replacements++;
                rz = wr__prec_apply(S, r, z);
                memcpy(pv, z, sizeof(double) * (size_t)n);
                continue;
            }
            rz_new = wr__prec_apply(S, r, z);
            beta = rz_new / rz;
            rz = rz_new;
            for (i = 0; i < n; ++i) pv[i] = z[i] + beta * pv[i];
        }
    }
    rnorm = wr__residual(S, A, b, x, r);
    if (stop == WR_SPD_STOP_CONVERGED && !(rnorm <= tol_abs)) stop = WR_SPD_STOP_MAX_ITER;
    wr__fill_stats(stats, S, it, rnorm / bnorm, t0, stop);
    switch (stop) {
    case WR_SPD_STOP_CONVERGED: st = WR_OK; break;
    case WR_SPD_STOP_NOT_SPD:
        st = wr_fail(diag, WR_ERR_NOT_SPD, it, "%s: p^T A p <= 0 at iteration %d (matrix not SPD)",
                     wr_solver_method_name(S->method), (int)it);
        break;
    case WR_SPD_STOP_NONFINITE:
        st = wr_fail(diag, WR_ERR_DOMAIN, it, "%s: non-finite value at iteration %d", wr_solver_method_name(S->method),
                     (int)it);
        break;
    default:
        st = wr_fail(diag, WR_ERR_NOT_CONVERGED, it, "%s: relative residual %g > %g after %d iterations",
                     wr_solver_method_name(S->method), rnorm / bnorm, S->rel_tol, (int)it);
    }
done:
    wr_free(r);
    wr_free(z);
    wr_free(pv);
    wr_free(q);
    return st;
}

WRDEF wr_status wr_spd_solve(const wr_csr *A, const double *b, double *x, const wr_spd_desc *desc,
                             wr_spd_stats *stats, wr_diag *diag) {
    wr_spd_solver S;
    wr_status st;
    if (stats) memset(stats, 0, sizeof *stats);
    if ((st = wr_spd_solver_create(&S, A, desc, diag)) != WR_OK) return st;
    if ((st = wr_spd_solver_factor(&S, A, diag)) != WR_OK) {
        if (stats) {
            stats->method = S.method;
            stats->stop = st == WR_ERR_NOT_SPD ? WR_SPD_STOP_NOT_SPD : WR_SPD_STOP_NONE;
        }
        wr_spd_solver_free(&S);
        return st;
    }
    st = wr_spd_solver_solve(&S, A, b, x, stats, diag);
    wr_spd_solver_free(&S);
    return st;
}

#ifdef __cplusplus
}
#endif
#endif /* WRINKLE_SPD_IMPLEMENTATION_DONE */
#endif /* WRINKLE_IMPLEMENTATION */
