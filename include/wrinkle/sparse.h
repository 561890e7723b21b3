/* wrinkle/sparse.h — triplet assembly and compressed-sparse-row matrices for the Newton and SQP
 * systems of wrinkle (shell statics, TFW Sec. 5; Style3D Sec. 5 PCG).
 * wrinkle v0.1.0 — MIT licence (see LICENSE). Needs only libc and libm.
 *
 * HOW TO USE
 *   #define WRINKLE_IMPLEMENTATION in exactly one .c/.cpp file before including this header.
 *
 * API (create/free pairs: wr_triplets_create/wr_triplets_free, wr_csr_from_triplets/wr_csr_free,
 *      wr_csr_copy/wr_csr_free)
 *   wr_triplets_create(t, n, reserve, diag)      empty n×n triplet list (grows on demand)
 *   wr_triplets_free(t) / wr_triplets_clear(t)   release / forget entries but keep the memory
 *   wr_triplets_add(t, i, j, v, diag)            append one entry (duplicates are summed later)
 *   wr_triplets_add_block3(t, I, J, B, diag)     append the dense 3×3 block B at rows 3I.., cols 3J..
 *   wr_triplets_add_element(t, k, idx, Ke, diag) scatter a dense k×k element matrix through idx
 *   wr_csr_from_triplets(A, t, diag)             sorted, duplicate-summed CSR (diagonal always present)
 *   wr_csr_copy(dst, src, diag) / wr_csr_free(A)
 *   wr_csr_zero_values(A)                        keep the pattern, zero the values (Newton reassembly)
 *   wr_csr_find(A, i, j)                         position of (i, j) in col/val, or -1 (binary search)
 *   wr_csr_add(A, i, j, v, diag)                 A(i,j) += v, (i,j) must be in the pattern
 *   wr_csr_add_element(A, k, idx, Ke, diag)      scatter-add a k×k element matrix into the pattern
 *   wr_csr_add_block3(A, I, J, B, diag)          add a dense 3×3 block
 *   wr_csr_from_stencils(A, nb, ns, start, verts, diag)  3-DOF pattern of vertex stencils, zero values
 *   wr_csr_block_offsets(A, k, verts, off, diag) cache where an element's 3×3 blocks sit (ON CACHED ASSEMBLY)
 *   wr_csr_add_element_blocks(A, k, verts, off, Ke)  add a 3k×3k element through cached offsets
 *   wr_csr_block3(A, I, J, B)                    read the 3×3 block (I, J) (absent entries read 0)
 *   wr_csr_block3_diagonal(A, D)                 all n/3 diagonal 3×3 blocks, row-major, 9 per block
 *   wr_csr_spmv(A, x, y)                         y = A x (x and y must not overlap)
 *   wr_csr_diagonal(A, d)                        d[i] = A(i,i)
 *   wr_csr_asymmetry(A)                          max |A(i,j) - A(j,i)| / max |A(i,j)| (0 = symmetric)
 *
 * EXAMPLE (Newton: build the pattern once, reassemble values every iteration)
 *     wr_triplets t;  wr_csr K;  wr_diag d;  int32_t e, idx[2];
 *     double Ke[4] = {1.0, -1.0, -1.0, 1.0}, x[5] = {0, 1, 2, 3, 4}, y[5];   // a chain of 4 unit springs
 *     wr_triplets_create(&t, 5, 16, &d);                 // build the pattern once ...
 *     for (e = 0; e < 4; ++e) { idx[0] = e; idx[1] = e + 1; wr_triplets_add_element(&t, 2, idx, Ke, &d); }
 *     if (wr_csr_from_triplets(&K, &t, &d) != WR_OK) puts(d.message);
 *     wr_triplets_free(&t);
 *     wr_csr_zero_values(&K);                            // ... and reassemble values every Newton step
 *     for (e = 0; e < 4; ++e) { idx[0] = e; idx[1] = e + 1; wr_csr_add_element(&K, 2, idx, Ke, &d); }
 *     wr_csr_spmv(&K, x, y);                             // K x = (-1, 0, 0, 0, 1)
 *     printf("nnz = %d, y[0] = %g, y[4] = %g\n", K.nnz, y[0], y[4]);   // 13, -1, 1
 *     wr_csr_free(&K);
 *
 * ON STORAGE
 *   wr_csr keeps exactly the entries it was given, summed: for a symmetric matrix store BOTH
 *   triangles (full symmetric storage; dense element matrices already do this). Columns are sorted
 *   ascending inside each row, no duplicates, and every diagonal entry (i, i) is in the pattern
 *   (value 0 when never given) because the preconditioners and the Dirichlet masking in pcg.h need
 *   it. Explicit zeros are kept, so a pattern assembled from zero element matrices stays valid for
 *   later value updates. Indices are int32_t; nnz must fit in int32_t (WR_ERR_OVERFLOW otherwise),
 *   which holds for 3-DOF triangle meshes far beyond 10^7 vertices.
 *   In wr_triplets_add_element / wr_csr_add_element a negative idx[a] drops row a and column a of
 *   the element matrix (an eliminated DOF), anything >= n is WR_ERR_INVALID_ARG.
 *
 * ON CACHED ASSEMBLY (Newton loops whose pattern does not change)
 *   wr_csr_add_element finds every entry by binary search: (3k)² searches per element, which was
 *   20–29 % of a whole TFT base solve (perf, statics.h on the TFW bench cases). For 3-DOF problems
 *   whose pattern is made of full 3×3 vertex blocks (every shell / membrane Hessian here), the three
 *   scalar rows of a vertex have the same columns, so one offset per vertex pair locates a block in
 *   all three rows: entry (3a+i, 3b+j) of the element sits at rowptr[3·verts[a]+i] + off[a·k+b] + j.
 *   wr_csr_block_offsets computes off (k² ints per element, kept by the caller across iterations)
 *   and fails with WR_ERR_INVALID_ARG when a block is missing or not contiguous in the pattern (then
 *   the caller keeps wr_csr_add_element); wr_csr_add_element_blocks then adds without any search.
 *   A negative verts[a] drops that vertex (off entries −1). wr_csr_from_stencils builds such a
 *   pattern directly from the vertex stencils (vertex sets of the elements, CSR-like start/verts
 *   arrays), without a triplet list of every scalar entry: the union of the full 3×3 blocks of all
 *   vertex pairs in each stencil, plus every diagonal block, all values 0.
 *
 * ON THREADS
 *   No global state. wr_csr_spmv reads A only, so several threads may multiply with one matrix.
 */
#ifndef WRINKLE_SPARSE_H
#define WRINKLE_SPARSE_H

#include "core.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct wr_triplets {
    int32_t n;       /* rows = columns */
    int64_t count;   /* entries stored */
    int64_t cap;     /* entries allocated */
    int32_t *row, *col;
    double *val;
} wr_triplets;

typedef struct wr_csr {
    int32_t n;       /* rows = columns */
    int32_t nnz;     /* stored entries = rowptr[n] */
    int32_t *rowptr; /* n+1 */
    int32_t *col;    /* nnz, ascending within each row */
    double *val;     /* nnz */
} wr_csr;

WRDEF wr_status wr_triplets_create(wr_triplets *t, int32_t n, int64_t reserve, wr_diag *diag);
WRDEF void wr_triplets_free(wr_triplets *t);
WRDEF void wr_triplets_clear(wr_triplets *t);
WRDEF wr_status wr_triplets_add(wr_triplets *t, int32_t i, int32_t j, double v, wr_diag *diag);
/* B row-major: B[3a+b] goes to (3I+a, 3J+b). */
WRDEF wr_status wr_triplets_add_block3(wr_triplets *t, int32_t I, int32_t J, const double B[9], wr_diag *diag);
/* Ke row-major k×k: Ke[a*k+b] goes to (idx[a], idx[b]); negative idx entries are skipped. */
WRDEF wr_status wr_triplets_add_element(wr_triplets *t, int32_t k, const int32_t *idx, const double *Ke,
                                        wr_diag *diag);

/* On failure *A is zeroed (safe to wr_csr_free). */
WRDEF wr_status wr_csr_from_triplets(wr_csr *A, const wr_triplets *t, wr_diag *diag);
WRDEF wr_status wr_csr_copy(wr_csr *dst, const wr_csr *src, wr_diag *diag);
WRDEF void wr_csr_free(wr_csr *A);
WRDEF void wr_csr_zero_values(wr_csr *A);
WRDEF int32_t wr_csr_find(const wr_csr *A, int32_t i, int32_t j);
WRDEF wr_status wr_csr_add(wr_csr *A, int32_t i, int32_t j, double v, wr_diag *diag);
WRDEF wr_status wr_csr_add_element(wr_csr *A, int32_t k, const int32_t *idx, const double *Ke, wr_diag *diag);
WRDEF wr_status wr_csr_add_block3(wr_csr *A, int32_t I, int32_t J, const double B[9], wr_diag *diag);
/* ON CACHED ASSEMBLY. n = 3·nb; stencil t has the vertices verts[start[t] .. start[t+1]) (entries in
 * [0, nb), negative entries skipped). On failure *A is zeroed. */
WRDEF wr_status wr_csr_from_stencils(wr_csr *A, int32_t nb, int32_t n_stencils, const int32_t *start,
                                     const int32_t *verts, wr_diag *diag);
/* off (k·k) receives the block offsets of the element with vertices verts[0..k) (ON CACHED ASSEMBLY). */
WRDEF wr_status wr_csr_block_offsets(const wr_csr *A, int32_t k, const int32_t *verts, int32_t *off, wr_diag *diag);
/* A += Ke (3k×3k row-major, dof order (v0x, v0y, v0z, v1x, …)) through offsets from wr_csr_block_offsets. */
WRDEF void wr_csr_add_element_blocks(wr_csr *A, int32_t k, const int32_t *verts, const int32_t *off, const double *Ke);
/* Returns how many of the 9 entries are in the pattern (missing ones read as 0). */
WRDEF int wr_csr_block3(const wr_csr *A, int32_t I, int32_t J, double B[9]);
/* D has 9*(n/3) doubles; n must be a multiple of 3 (WR_ASSERT). */
WRDEF void wr_csr_block3_diagonal(const wr_csr *A, double *D);
/* y = A x. y is written row by row while x is still read, so x and y must not overlap. */
WRDEF void wr_csr_spmv(const wr_csr *A, const double *x, double *y);
WRDEF void wr_csr_diagonal(const wr_csr *A, double *d);
WRDEF double wr_csr_asymmetry(const wr_csr *A);

#ifdef __cplusplus
}
#endif
#endif /* WRINKLE_SPARSE_H */

/* ============================================================================================ */
#ifdef WRINKLE_IMPLEMENTATION
#ifndef WRINKLE_SPARSE_IMPLEMENTATION_DONE
#define WRINKLE_SPARSE_IMPLEMENTATION_DONE

#include <math.h>
#include <string.h>

#ifdef __cplusplus
extern "C" {
#endif

WRDEF wr_status wr_triplets_create(wr_triplets *t, int32_t n, int64_t reserve, wr_diag *diag) {
    if (!t) return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "triplets: NULL output");
    memset(t, 0, sizeof *t);
    if (n < 0) return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "triplets: n = %d < 0", (int)n);
    if (reserve < 16) reserve = 16;
    if ((uint64_t)reserve > (uint64_t)(SIZE_MAX / sizeof(double)))
        return wr_fail(diag, WR_ERR_OVERFLOW, -1, "triplets: reserve %lld too large", (long long)reserve);
    t->row = (int32_t *)wr_alloc_array((size_t)reserve, sizeof(int32_t));
    t->col = (int32_t *)wr_alloc_array((size_t)reserve, sizeof(int32_t));
    t->val = (double *)wr_alloc_array((size_t)reserve, sizeof(double));
    if (!t->row || !t->col || !t->val) {
        wr_triplets_free(t);
        return wr_fail(diag, WR_ERR_NOMEM, -1, "triplets: cannot reserve %lld entries", (long long)reserve);
    }
    t->n = n;
    t->cap = reserve;
    return WR_OK;
}

WRDEF void wr_triplets_free(wr_triplets *t) {
    if (!t) return;
    wr_free(t->row);
    wr_free(t->col);
    wr_free(t->val);
    memset(t, 0, sizeof *t);
}

WRDEF void wr_triplets_clear(wr_triplets *t) {
    if (t) t->count = 0;
}

/* Make room for `extra` more entries (geometric growth, overflow-checked). */
static wr_status wr__triplets_reserve(wr_triplets *t, int64_t extra, wr_diag *diag) {
    int64_t need, cap;
    int32_t *r, *c;
    double *v;
    if (t->count > INT64_MAX - extra) return wr_fail(diag, WR_ERR_OVERFLOW, -1, "triplets: count overflow");
    need = t->count + extra;
    if (need <= t->cap) return WR_OK;
    cap = t->cap < 16 ? 16 : t->cap;
    while (cap < need) {
        if (cap > INT64_MAX / 2) return wr_fail(diag, WR_ERR_OVERFLOW, -1, "triplets: capacity overflow");
        cap *= 2;
    }
    if ((uint64_t)cap > (uint64_t)(SIZE_MAX / sizeof(double)))
        return wr_fail(diag, WR_ERR_OVERFLOW, -1, "triplets: %lld entries exceed the address space", (long long)cap);
    /* Each realloc result is stored at once so that a later failure leaves t freeable and intact. */
    r = (int32_t *)wr_realloc_array(t->row, (size_t)cap, sizeof(int32_t));
    if (!r) return wr_fail(diag, WR_ERR_NOMEM, -1, "triplets: cannot grow to %lld entries", (long long)cap);
    t->row = r;
    c = (int32_t *)wr_realloc_array(t->col, (size_t)cap, sizeof(int32_t));
    if (!c) return wr_fail(diag, WR_ERR_NOMEM, -1, "triplets: cannot grow to %lld entries", (long long)cap);
    t->col = c;
    v = (double *)wr_realloc_array(t->val, (size_t)cap, sizeof(double));
    if (!v) return wr_fail(diag, WR_ERR_NOMEM, -1, "triplets: cannot grow to %lld entries", (long long)cap);
    t->val = v;
    t->cap = cap;
    return WR_OK;
}

WRDEF wr_status wr_triplets_add(wr_triplets *t, int32_t i, int32_t j, double v, wr_diag *diag) {
    wr_status s;
    if (!t) return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "triplets: NULL");
    if (i < 0 || i >= t->n || j < 0 || j >= t->n)
        return wr_fail(diag, WR_ERR_INVALID_ARG, i, "triplets: entry (%d, %d) outside %d x %d", (int)i, (int)j,
                       (int)t->n, (int)t->n);
    if ((s = wr__triplets_reserve(t, 1, diag)) != WR_OK) return s;
    t->row[t->count] = i;
    t->col[t->count] = j;
    t->val[t->count] = v;
    t->count++;
    return WR_OK;
}

WRDEF wr_status wr_triplets_add_block3(wr_triplets *t, int32_t I, int32_t J, const double B[9], wr_diag *diag) {
    int32_t idx[6];
    int a, b;
    wr_status s;
    if (!t || !B) return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "triplets_add_block3: NULL argument");
    if (I < 0 || J < 0 || I > (t->n - 3) / 3 || J > (t->n - 3) / 3 || t->n < 3)
        return wr_fail(diag, WR_ERR_INVALID_ARG, I, "triplets_add_block3: block (%d, %d) outside n = %d", (int)I,
                       (int)J, (int)t->n);
    for (a = 0; a < 3; ++a) {
        idx[a] = 3 * I + a;
        idx[3 + a] = 3 * J + a;
    }
    if ((s = wr__triplets_reserve(t, 9, diag)) != WR_OK) return s;
    for (a = 0; a < 3; ++a)
        for (b = 0; b < 3; ++b) {
            t->row[t->count] = idx[a];
            t->col[t->count] = idx[3 + b];
            t->val[t->count] = B[3 * a + b];
            t->count++;
        }
    return WR_OK;
}

static wr_status wr__check_element(int32_t n, int32_t k, const int32_t *idx, const double *Ke, wr_diag *diag) {
    int32_t a;
    if (!idx || !Ke) return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "element: NULL idx or Ke");
    if (k < 0) return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "element: k = %d < 0", (int)k);
    for (a = 0; a < k; ++a)
        if (idx[a] >= n)
            return wr_fail(diag, WR_ERR_INVALID_ARG, a, "element: idx[%d] = %d >= n = %d", (int)a, (int)idx[a],
                           (int)n);
    return WR_OK;
}

WRDEF wr_status wr_triplets_add_element(wr_triplets *t, int32_t k, const int32_t *idx, const double *Ke,
                                        wr_diag *diag) {
    int32_t a, b;
    wr_status s;
    if (!t) return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "triplets_add_element: NULL triplets");
    if ((s = wr__check_element(t->n, k, idx, Ke, diag)) != WR_OK) return s;
    if ((s = wr__triplets_reserve(t, (int64_t)k * k, diag)) != WR_OK) return s;
    for (a = 0; a < k; ++a) {
        if (idx[a] < 0) continue;
        for (b = 0; b < k; ++b) {
            if (idx[b] < 0) continue;
            t->row[t->count] = idx[a];
            t->col[t->count] = idx[b];
            t->val[t->count] = Ke[(size_t)a * (size_t)k + (size_t)b];
            t->count++;
        }
    }
    return WR_OK;
}

WRDEF void wr_csr_free(wr_csr *A) {
    if (!A) return;
    wr_free(A->rowptr);
    wr_free(A->col);
    wr_free(A->val);
    memset(A, 0, sizeof *A);
}

WRDEF wr_status wr_csr_from_triplets(wr_csr *A, const wr_triplets *t, wr_diag *diag) {
    /* Two stable counting sorts (by column into a scratch CSC, then by row) leave every row's
     * columns ascending in O(count + n) without comparisons; duplicates then sit next to each
     * other and are summed in one sweep. The n diagonal entries are appended as explicit zeros. */
    int64_t total, k;
    int32_t n, i;
    int32_t *cptr = NULL, *tmp_row = NULL, *rptr = NULL, *srt_col = NULL;
    double *tmp_val = NULL, *srt_val = NULL;
    wr_status st = WR_OK;
    if (!A) return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "csr_from_triplets: NULL output");
    memset(A, 0, sizeof *A);
    if (!t) return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "csr_from_triplets: NULL triplets");
    n = t->n;
    if (t->count > INT64_MAX - n) return wr_fail(diag, WR_ERR_OVERFLOW, -1, "csr_from_triplets: count overflow");
    total = t->count + n;
    /* Counts below live in int32_t; more triplets than that are refused (duplicates are not rescued). */
    if (total > INT32_MAX)
        return wr_fail(diag, WR_ERR_OVERFLOW, -1, "csr_from_triplets: %lld triplets exceed int32 counts",
                       (long long)total);
    cptr = (int32_t *)wr_calloc_array((size_t)n + 2, sizeof(int32_t));
    rptr = (int32_t *)wr_calloc_array((size_t)n + 2, sizeof(int32_t));
    tmp_row = (int32_t *)wr_alloc_array((size_t)total, sizeof(int32_t));
    tmp_val = (double *)wr_alloc_array((size_t)total, sizeof(double));
    srt_col = (int32_t *)wr_alloc_array((size_t)total, sizeof(int32_t));
    srt_val = (double *)wr_alloc_array((size_t)total, sizeof(double));
    if (!cptr || !rptr || !tmp_row || !tmp_val || !srt_col || !srt_val) {
        st = wr_fail(diag, WR_ERR_NOMEM, -1, "csr_from_triplets: out of memory for %lld entries", (long long)total);
        goto done;
    }
    for (k = 0; k < t->count; ++k) {
        int32_t r = t->row[k], c = t->col[k];
        if (r < 0 || r >= n || c < 0 || c >= n) {
            st = wr_fail(diag, WR_ERR_INVALID_ARG, (int32_t)k, "csr_from_triplets: triplet %lld = (%d, %d) outside n = %d",
                         (long long)k, (int)r, (int)c, (int)n);
            goto done;
        }
        cptr[c + 2]++;
    }
    for (i = 0; i < n; ++i) cptr[i + 2]++; /* diagonal */
    for (i = 0; i < n; ++i) cptr[i + 2] += cptr[i + 1];
    /* scatter by column: position cptr[c+1]++ */
    for (k = 0; k < t->count; ++k) {
        int32_t p = cptr[t->col[k] + 1]++;
        tmp_row[p] = t->row[k];
        tmp_val[p] = t->val[k];
    }
    for (i = 0; i < n; ++i) {
        int32_t p = cptr[i + 1]++;
        tmp_row[p] = i;
        tmp_val[p] = 0.0;
    }
    /* now cptr[c] .. cptr[c+1] is column c; stable scatter by row keeps columns ascending */
    for (k = 0; k < total; ++k) rptr[tmp_row[k] + 2]++;
    for (i = 0; i < n; ++i) rptr[i + 2] += rptr[i + 1];
    {
        int32_t c;
        for (c = 0; c < n; ++c) {
            int32_t p;
            for (p = cptr[c]; p < cptr[c + 1]; ++p) {
                int32_t q = rptr[tmp_row[p] + 1]++;
                srt_col[q] = c;
                srt_val[q] = tmp_val[p];
            }
        }
    }
    /* rows are rptr[i] .. rptr[i+1]; compact duplicates in place */
    {
        int32_t out = 0, start = 0;
        for (i = 0; i < n; ++i) {
            int32_t p, end = rptr[i + 1];
            rptr[i] = out;
            for (p = start; p < end; ++p) {
                if (out > rptr[i] && srt_col[out - 1] == srt_col[p]) {
                    srt_val[out - 1] += srt_val[p];
                } else {
                    srt_col[out] = srt_col[p];
                    srt_val[out] = srt_val[p];
                    out++;
                }
            }
            start = end;
        }
        rptr[n] = out;
        A->n = n;
        A->nnz = out;
        A->rowptr = (int32_t *)wr_alloc_array((size_t)n + 1, sizeof(int32_t));
        A->col = (int32_t *)wr_alloc_array((size_t)out, sizeof(int32_t));
        A->val = (double *)wr_alloc_array((size_t)out, sizeof(double));
        if (!A->rowptr || !A->col || !A->val) {
            wr_csr_free(A);
            st = wr_fail(diag, WR_ERR_NOMEM, -1, "csr_from_triplets: out of memory for %d entries", (int)out);
            goto done;
        }
        memcpy(A->rowptr, rptr, sizeof(int32_t) * ((size_t)n + 1));
        memcpy(A->col, srt_col, sizeof(int32_t) * (size_t)out);
        memcpy(A->val, srt_val, sizeof(double) * (size_t)out);
    }
done:
    wr_free(cptr);
    wr_free(rptr);
    wr_free(tmp_row);
    wr_free(tmp_val);
    wr_free(srt_col);
    wr_free(srt_val);
    return st;
}

WRDEF wr_status wr_csr_copy(wr_csr *dst, const wr_csr *src, wr_diag *diag) {
    if (!dst) return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "csr_copy: NULL output");
    memset(dst, 0, sizeof *dst);
    if (!src || !src->rowptr) return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "csr_copy: NULL or empty source");
    dst->rowptr = (int32_t *)wr_alloc_array((size_t)src->n + 1, sizeof(int32_t));
    dst->col = (int32_t *)wr_alloc_array((size_t)src->nnz, sizeof(int32_t));
    dst->val = (double *)wr_alloc_array((size_t)src->nnz, sizeof(double));
    if (!dst->rowptr || !dst->col || !dst->val) {
        wr_csr_free(dst);
        return wr_fail(diag, WR_ERR_NOMEM, -1, "csr_copy: out of memory (%d entries)", (int)src->nnz);
    }
    dst->n = src->n;
    dst->nnz = src->nnz;
    memcpy(dst->rowptr, src->rowptr, sizeof(int32_t) * ((size_t)src->n + 1));
    memcpy(dst->col, src->col, sizeof(int32_t) * (size_t)src->nnz);
    memcpy(dst->val, src->val, sizeof(double) * (size_t)src->nnz);
    return WR_OK;
}

WRDEF void wr_csr_zero_values(wr_csr *A) {
    if (A && A->val) memset(A->val, 0, sizeof(double) * (size_t)A->nnz);
}

WRDEF int32_t wr_csr_find(const wr_csr *A, int32_t i, int32_t j) {
    int32_t lo, hi;
    if (!A || i < 0 || i >= A->n) return -1;
    lo = A->rowptr[i];
    hi = A->rowptr[i + 1] - 1;
    while (lo <= hi) {
        int32_t mid = lo + (hi - lo) / 2, c = A->col[mid];
        if (c == j) return mid;
        if (c < j)
            lo = mid + 1;
        else
            hi = mid - 1;
    }
    return -1;
}

WRDEF wr_status wr_csr_add(wr_csr *A, int32_t i, int32_t j, double v, wr_diag *diag) {
    int32_t p;
    if (!A || !A->rowptr) return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "csr_add: NULL matrix");
    p = wr_csr_find(A, i, j);
    if (p < 0) return wr_fail(diag, WR_ERR_INVALID_ARG, i, "csr_add: entry (%d, %d) not in the pattern", (int)i, (int)j);
    A->val[p] += v;
    return WR_OK;
}

WRDEF wr_status wr_csr_add_element(wr_csr *A, int32_t k, const int32_t *idx, const double *Ke, wr_diag *diag) {
    int32_t a, b;
    wr_status s;
    if (!A || !A->rowptr) return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "csr_add_element: NULL matrix");
    if ((s = wr__check_element(A->n, k, idx, Ke, diag)) != WR_OK) return s;
    /* Check the whole pattern first so a failure leaves A unchanged. */
    for (a = 0; a < k; ++a) {
        if (idx[a] < 0) continue;
        for (b = 0; b < k; ++b)
            if (idx[b] >= 0 && wr_csr_find(A, idx[a], idx[b]) < 0)
                return wr_fail(diag, WR_ERR_INVALID_ARG, idx[a], "csr_add_element: entry (%d, %d) not in the pattern",
                               (int)idx[a], (int)idx[b]);
    }
    for (a = 0; a < k; ++a) {
        if (idx[a] < 0) continue;
        for (b = 0; b < k; ++b)
            if (idx[b] >= 0) A->val[wr_csr_find(A, idx[a], idx[b])] += Ke[(size_t)a * (size_t)k + (size_t)b];
    }
    return WR_OK;
}

WRDEF wr_status wr_csr_add_block3(wr_csr *A, int32_t I, int32_t J, const double B[9], wr_diag *diag) {
    int32_t idx[3], jdx[3];
    int a, b;
    if (!A || !A->rowptr || !B) return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "csr_add_block3: NULL argument");
    if (A->n < 3 || I < 0 || J < 0 || I > (A->n - 3) / 3 || J > (A->n - 3) / 3)
        return wr_fail(diag, WR_ERR_INVALID_ARG, I, "csr_add_block3: block (%d, %d) outside n = %d", (int)I, (int)J,
                       (int)A->n);
    for (a = 0; a < 3; ++a) {
        idx[a] = 3 * I + a;
        jdx[a] = 3 * J + a;
    }
    for (a = 0; a < 3; ++a)
        for (b = 0; b < 3; ++b)
            if (wr_csr_find(A, idx[a], jdx[b]) < 0)
                return wr_fail(diag, WR_ERR_INVALID_ARG, idx[a], "csr_add_block3: entry (%d, %d) not in the pattern",
                               (int)idx[a], (int)jdx[b]);
    for (a = 0; a < 3; ++a)
        for (b = 0; b < 3; ++b) A->val[wr_csr_find(A, idx[a], jdx[b])] += B[3 * a + b];
    return WR_OK;
}

static int wr__sparse_cmp_i32(const void *a, const void *b) {
    int32_t x = *(const int32_t *)a, y = *(const int32_t *)b;
    return x < y ? -1 : x > y;
}

WRDEF wr_status wr_csr_from_stencils(wr_csr *A, int32_t nb, int32_t n_stencils, const int32_t *start,
                                     const int32_t *verts, wr_diag *diag) {
    int64_t *cnt = NULL, total = 0, nnz;
    int32_t *adj = NULL, *fill = NULL, *deg = NULL, t, v, a, b, i;
    wr_status rs = WR_OK;
    if (!A) return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "csr_from_stencils: NULL output");
    memset(A, 0, sizeof *A);
    if (nb < 0 || nb > (INT32_MAX - 3) / 3 || n_stencils < 0 || (n_stencils > 0 && (!start || !verts)))
        return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "csr_from_stencils: nb = %d, %d stencils", (int)nb, (int)n_stencils);
    for (t = 0; t < n_stencils; ++t) {
        if (start[t + 1] < start[t] || start[t] < 0)
            return wr_fail(diag, WR_ERR_INVALID_ARG, t, "csr_from_stencils: stencil %d has start %d > end %d", (int)t,
                           (int)start[t], (int)start[t + 1]);
        for (a = start[t]; a < start[t + 1]; ++a)
            if (verts[a] >= nb)
                return wr_fail(diag, WR_ERR_INVALID_ARG, t, "csr_from_stencils: stencil %d has vertex %d >= %d", (int)t,
                               (int)verts[a], (int)nb);
    }
    /* per vertex: every stencil neighbour (with repeats) plus itself, then sorted and made unique */
    cnt = (int64_t *)wr_calloc_array((size_t)nb + 1, sizeof(int64_t));
    deg = (int32_t *)wr_alloc_array((size_t)nb + 1, sizeof(int32_t));
    if (!cnt || !deg) {
        rs = wr_fail(diag, WR_ERR_NOMEM, -1, "csr_from_stencils: out of memory (%d vertices)", (int)nb);
        goto done;
    }
    for (v = 0; v < nb; ++v) cnt[v + 1] = 1;
    for (t = 0; t < n_stencils; ++t) {
        int64_t k = 0;
        for (a = start[t]; a < start[t + 1]; ++a) k += verts[a] >= 0;
        for (a = start[t]; a < start[t + 1]; ++a)
            if (verts[a] >= 0) cnt[verts[a] + 1] += k;
    }
    for (v = 0; v < nb; ++v) cnt[v + 1] += cnt[v];
    total = cnt[nb];
    adj = (int32_t *)wr_alloc_array((size_t)total, sizeof(int32_t));
    fill = (int32_t *)wr_calloc_array((size_t)nb + 1, sizeof(int32_t));
    if (!adj || !fill) {
        rs = wr_fail(diag, WR_ERR_NOMEM, -1, "csr_from_stencils: out of memory (%lld pairs)", (long long)total);
        goto done;
    }
    for (v = 0; v < nb; ++v) adj[cnt[v] + fill[v]++] = v;
    for (t = 0; t < n_stencils; ++t)
        for (a = start[t]; a < start[t + 1]; ++a)
            if (verts[a] >= 0)
                for (b = start[t]; b < start[t + 1]; ++b)
                    if (verts[b] >= 0) adj[cnt[verts[a]] + fill[verts[a]]++] = verts[b];
    nnz = 0;
    for (v = 0; v < nb; ++v) {
        int32_t *r = adj + cnt[v], m = fill[v], u = 0;
        qsort(r, (size_t)m, sizeof(int32_t), wr__sparse_cmp_i32);
        for (i = 0; i < m; ++i)
            if (u == 0 || r[i] != r[u - 1]) r[u++] = r[i];
        deg[v] = u;
        nnz += 9 * (int64_t)u;
    }
    if (nnz > INT32_MAX) {
        rs = wr_fail(diag, WR_ERR_OVERFLOW, -1, "csr_from_stencils: %lld entries exceed int32", (long long)nnz);
        goto done;
    }
    A->n = 3 * nb;
    A->nnz = (int32_t)nnz;
    A->rowptr = (int32_t *)wr_alloc_array((size_t)A->n + 1, sizeof(int32_t));
    A->col = (int32_t *)wr_alloc_array(nnz > 0 ? (size_t)nnz : 1, sizeof(int32_t));
    A->val = (double *)wr_calloc_array(nnz > 0 ? (size_t)nnz : 1, sizeof(double));
    if (!A->rowptr || !A->col || !A->val) {
        wr_csr_free(A);
        rs = wr_fail(diag, WR_ERR_NOMEM, -1, "csr_from_stencils: out of memory (%lld entries)", (long long)nnz);
        goto done;
    }
    A->rowptr[0] = 0;
    for (v = 0; v < nb; ++v)
        for (i = 0; i < 3; ++i) {
            int32_t p = A->rowptr[3 * v + i], q;
            for (q = 0; q < deg[v]; ++q) {
                int32_t c = 3 * adj[cnt[v] + q];
                A->col[p++] = c;
                A->col[p++] = c + 1;
                A->col[p++] = c + 2;
            }
            A->rowptr[3 * v + i + 1] = p;
        }
done:
    wr_free(cnt);
    wr_free(adj);
    wr_free(fill);
    wr_free(deg);
    return rs;
}

WRDEF wr_status wr_csr_block_offsets(const wr_csr *A, int32_t k, const int32_t *verts, int32_t *off, wr_diag *diag) {
    int32_t a, b, i, j;
    if (!A || !A->rowptr || k < 0 || (k > 0 && (!verts || !off)) || A->n % 3 != 0)
        return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "csr_block_offsets: NULL argument, k = %d or n not 3-DOF", (int)k);
    for (a = 0; a < k; ++a)
        for (b = 0; b < k; ++b) {
            int32_t va = verts[a], vb = verts[b], p;
            off[a * k + b] = -1;
            if (va < 0 || vb < 0) continue;
            if (3 * va >= A->n || 3 * vb >= A->n)
                return wr_fail(diag, WR_ERR_INVALID_ARG, a, "csr_block_offsets: vertex %d outside n = %d",
                               (int)(3 * va >= A->n ? va : vb), (int)A->n);
            p = wr_csr_find(A, 3 * va, 3 * vb);
            if (p < 0)
                return wr_fail(diag, WR_ERR_INVALID_ARG, a, "csr_block_offsets: block (%d, %d) not in the pattern", (int)va,
                               (int)vb);
            p -= A->rowptr[3 * va];
            /* the same offset must address the whole block in all three rows (ON CACHED ASSEMBLY) */
            for (i = 0; i < 3; ++i)
                for (j = 0; j < 3; ++j) {
                    int32_t q = A->rowptr[3 * va + i] + p + j;
                    if (q >= A->rowptr[3 * va + i + 1] || A->col[q] != 3 * vb + j)
                        return wr_fail(diag, WR_ERR_INVALID_ARG, a,
                                       "csr_block_offsets: block (%d, %d) is not a contiguous 3x3 block of the pattern",
                                       (int)va, (int)vb);
                }
            off[a * k + b] = p;
        }
    return WR_OK;
}

WRDEF void wr_csr_add_element_blocks(wr_csr *A, int32_t k, const int32_t *verts, const int32_t *off, const double *Ke) {
    int32_t a, b, i, n = 3 * k;
    for (a = 0; a < k; ++a) {
        if (verts[a] < 0) continue;
        for (i = 0; i < 3; ++i) {
            double *row = A->val + A->rowptr[3 * verts[a] + i];
            const double *ke = Ke + (size_t)(3 * a + i) * (size_t)n;
            for (b = 0; b < k; ++b) {
                int32_t p = off[a * k + b];
                if (p < 0) continue;
                row[p] += ke[3 * b];
                row[p + 1] += ke[3 * b + 1];
                row[p + 2] += ke[3 * b + 2];
            }
        }
    }
}

WRDEF int wr_csr_block3(const wr_csr *A, int32_t I, int32_t J, double B[9]) {
    int a, b, found = 0;
    for (a = 0; a < 3; ++a)
        for (b = 0; b < 3; ++b) {
            int32_t p = wr_csr_find(A, 3 * I + a, 3 * J + b);
            B[3 * a + b] = p >= 0 ? A->val[p] : 0.0;
            found += p >= 0;
        }
    return found;
}

WRDEF void wr_csr_block3_diagonal(const wr_csr *A, double *D) {
    int32_t I, nb;
    WR_ASSERT(A && A->n % 3 == 0 && "wr_csr_block3_diagonal needs n divisible by 3");
    nb = A->n / 3;
    for (I = 0; I < nb; ++I) {
        int a;
        for (a = 0; a < 3; ++a) {
            int32_t i = 3 * I + a, p;
            D[9 * I + 3 * a + 0] = D[9 * I + 3 * a + 1] = D[9 * I + 3 * a + 2] = 0.0;
            /* The columns are sorted, so one linear scan of the row picks the block's entries. */
            for (p = A->rowptr[i]; p < A->rowptr[i + 1]; ++p) {
                int32_t c = A->col[p];
                if (c >= 3 * I && c < 3 * I + 3) D[9 * I + 3 * a + (c - 3 * I)] = A->val[p];
            }
        }
    }
}

WRDEF void wr_csr_spmv(const wr_csr *A, const double *x, double *y) {
    int32_t i;
    for (i = 0; i < A->n; ++i) {
        double s = 0.0;
        int32_t p;
        for (p = A->rowptr[i]; p < A->rowptr[i + 1]; ++p) s += A->val[p] * x[A->col[p]];
        y[i] = s;
    }
}

WRDEF void wr_csr_diagonal(const wr_csr *A, double *d) {
    int32_t i;
    for (i = 0; i < A->n; ++i) {
        int32_t p = wr_csr_find(A, i, i);
        d[i] = p >= 0 ? A->val[p] : 0.0;
    }
}

WRDEF double wr_csr_asymmetry(const wr_csr *A) {
    double worst = 0.0, amax = 0.0;
    int32_t i, p;
    for (i = 0; i < A->n; ++i)
        for (p = A->rowptr[i]; p < A->rowptr[i + 1]; ++p) {
            int32_t q = wr_csr_find(A, A->col[p], i);
            double other = q >= 0 ? A->val[q] : 0.0;
            double dv = fabs(A->val[p] - other);
            if (dv > worst) worst = dv;
            if (fabs(A->val[p]) > amax) amax = fabs(A->val[p]);
        }
    return amax > 0.0 ? worst / amax : 0.0;
}

#ifdef __cplusplus
}
#endif
#endif /* WRINKLE_SPARSE_IMPLEMENTATION_DONE */
#endif /* WRINKLE_IMPLEMENTATION */
