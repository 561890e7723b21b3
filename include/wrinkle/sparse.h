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
 *   wr_assembly_init(a, nb, bs, diag) / wr_assembly_free(a)   assembly cache for nb blocks of bs DOFs
 *   wr_assembly_begin(a) … wr_assembly_add(a, k, blocks, Ke, diag) / _add_diagonal(a, v, B, diag)
 *       … wr_assembly_end(a, diag)                one assembly into a.A (ON ASSEMBLY CACHE)
 *   wr_assembly_constant_begin(a) / _end(a)       elements whose values never change, summed once
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
 *   (value 0 when never given) because the preconditioners and the Dirichlet masking in spd.h need
 *   it. Explicit zeros are kept, so a pattern assembled from zero element matrices stays valid for
 *   later value updates. Indices are int32_t; nnz must fit in int32_t (WR_ERR_OVERFLOW otherwise),
 *   which holds for 3-DOF triangle meshes far beyond 10^7 vertices.
 *   In wr_triplets_add_element / wr_csr_add_element a negative idx[a] drops row a and column a of
 *   the element matrix (an eliminated DOF), anything >= n is WR_ERR_INVALID_ARG.
 *
 * ON CACHED ASSEMBLY (Newton loops whose pattern does not change)
 *   wr_csr_add_element finds every entry by binary search: (3k)² searches per element, a large
 *   share of a Newton solve's time (docs/notes-statics.md, "Assembly cache"). For 3-DOF problems
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
 * ON ASSEMBLY CACHE (wr_assembly: the Newton and SQP loops)
 *   One object does the above for a caller that streams the same elements every iteration: the first
 *   assembly (between wr_assembly_begin and wr_assembly_end) records each element's blocks and values,
 *   _end builds the pattern from the recorded stencils (wr_csr_from_stencils; scalar blocks with
 *   bs = 1 too), caches every element's block offsets and adds the recorded values in stream order;
 *   later assemblies zero the values and add element e through its offsets while the stream matches
 *   the record (same block list at the same position), by search otherwise (a.misses). A block the
 *   pattern lacks (a new contact pair) sets a.stale: that assembly is incomplete, and the next
 *   wr_assembly_begin records a new pattern (a.builds counts them), so the caller assembles again.
 *   Diagonal blocks (wr_assembly_add_diagonal) are always in the pattern and never recorded.
 *   Elements between wr_assembly_constant_begin and _end (x-independent ones: the TFW Eq. 28
 *   quadratic bending) are summed once into a separate value array; later constant_begin calls add
 *   that sum and return 0, so the caller skips streaming them. Floating-point sums follow the stream
 *   order, so repeated assemblies of the same values give bit-identical matrices. Memory: the record
 *   ((bs·k)² doubles per element) lives only until the first _end; afterwards k² ints per element.
 *   Ownership: a.A belongs to the cache (wr_assembly_free).
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

/* ON ASSEMBLY CACHE. One Newton (or SQP) matrix assembled again and again from the same elements:
 * the first assembly records the element stencils and values and builds the pattern from them, later
 * ones add each element through its cached block offsets. Fields above "private" may be read. */
typedef struct wr_assembly {
    wr_csr A;        /* the matrix: pattern of the recorded elements (+ every diagonal block), last values */
    int32_t nb, bs;  /* blocks (vertices) and DOFs per block (1 or 3): A is (bs·nb) × (bs·nb) */
    int32_t builds;  /* patterns built so far (a rebuild follows an element outside the pattern) */
    int32_t misses;  /* elements of the last assembly that did not match the record (added by search) */
    int32_t stale;   /* 1: the last assembly met a block outside the pattern; assemble again */
    /* private */
    int32_t rec_mode, n_el, cap_el, e, c_begin, c_end, n_pend, cap_pend;
    int32_t *vstart, *verts, *off, *doff, *pend_v;
    int64_t vcap, rn, rcap, *ostart;
    double *rec, *Kc, *pend_B;
} wr_assembly;

/* Empty cache for nb blocks of bs (1 or 3) DOFs; nothing allocated until the first assembly. */
WRDEF wr_status wr_assembly_init(wr_assembly *a, int32_t nb, int32_t bs, wr_diag *diag);
WRDEF void wr_assembly_free(wr_assembly *a);
/* Start an assembly: values zeroed (the first one, or after a stale one, records a new pattern). */
WRDEF void wr_assembly_begin(wr_assembly *a);
/* Add a dense (bs·k)² row-major element over blocks[0..k) (negative entries dropped). */
WRDEF wr_status wr_assembly_add(wr_assembly *a, int32_t k, const int32_t *blocks, const double *Ke, wr_diag *diag);
/* Add a bs×bs block at diagonal block v (always in the pattern: contact, mass, shift terms). */
WRDEF wr_status wr_assembly_add_diagonal(wr_assembly *a, int32_t v, const double *B, wr_diag *diag);
/* Constant elements (same values every assembly): returns 1 when the caller must add them now (first
 * assembly, between this call and wr_assembly_constant_end), 0 when their cached sum was added. */
WRDEF int wr_assembly_constant_begin(wr_assembly *a);
WRDEF void wr_assembly_constant_end(wr_assembly *a);
/* Finish an assembly (after a recording one: builds the pattern and adds the recorded values). */
WRDEF wr_status wr_assembly_end(wr_assembly *a, wr_diag *diag);

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

/* the pattern of ON CACHED ASSEMBLY for blocks of bs (1 or 3) DOFs */
static wr_status wr__csr_from_stencils_bs(wr_csr *A, int32_t nb, int32_t bs, int32_t n_stencils, const int32_t *start,
                                          const int32_t *verts, wr_diag *diag) {
    int64_t *cnt = NULL, total = 0, nnz;
    int32_t *adj = NULL, *fill = NULL, *deg = NULL, t, v, a, b, i, j;
    wr_status rs = WR_OK;
    if (!A) return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "csr_from_stencils: NULL output");
    memset(A, 0, sizeof *A);
    if (bs < 1 || nb < 0 || nb > (INT32_MAX - 3) / 3 || n_stencils < 0 || (n_stencils > 0 && (!start || !verts)))
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
        nnz += (int64_t)bs * bs * u;
    }
    if (nnz > INT32_MAX) {
        rs = wr_fail(diag, WR_ERR_OVERFLOW, -1, "csr_from_stencils: %lld entries exceed int32", (long long)nnz);
        goto done;
    }
    A->n = bs * nb;
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
        for (i = 0; i < bs; ++i) {
            int32_t p = A->rowptr[bs * v + i], q;
            for (q = 0; q < deg[v]; ++q) {
                int32_t c = bs * adj[cnt[v] + q];
                for (j = 0; j < bs; ++j) A->col[p++] = c + j;
            }
            A->rowptr[bs * v + i + 1] = p;
        }
done:
    wr_free(cnt);
    wr_free(adj);
    wr_free(fill);
    wr_free(deg);
    return rs;
}

WRDEF wr_status wr_csr_from_stencils(wr_csr *A, int32_t nb, int32_t n_stencils, const int32_t *start,
                                     const int32_t *verts, wr_diag *diag) {
    return wr__csr_from_stencils_bs(A, nb, 3, n_stencils, start, verts, diag);
}

static wr_status wr__csr_block_offsets_bs(const wr_csr *A, int32_t bs, int32_t k, const int32_t *verts, int32_t *off,
                                          wr_diag *diag) {
    int32_t a, b, i, j;
    if (!A || !A->rowptr || bs < 1 || k < 0 || (k > 0 && (!verts || !off)) || A->n % bs != 0)
        return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "csr_block_offsets: NULL argument, k = %d or n not %d-DOF", (int)k,
                       (int)bs);
    for (a = 0; a < k; ++a)
        for (b = 0; b < k; ++b) {
            int32_t va = verts[a], vb = verts[b], p;
            off[a * k + b] = -1;
            if (va < 0 || vb < 0) continue;
            if (bs * va >= A->n || bs * vb >= A->n)
                return wr_fail(diag, WR_ERR_INVALID_ARG, a, "csr_block_offsets: vertex %d outside n = %d",
                               (int)(bs * va >= A->n ? va : vb), (int)A->n);
            p = wr_csr_find(A, bs * va, bs * vb);
            if (p < 0)
                return wr_fail(diag, WR_ERR_INVALID_ARG, a, "csr_block_offsets: block (%d, %d) not in the pattern", (int)va,
                               (int)vb);
            p -= A->rowptr[bs * va];
            /* the same offset must address the whole block in all its rows (ON CACHED ASSEMBLY) */
            for (i = 0; i < bs; ++i)
                for (j = 0; j < bs; ++j) {
                    int32_t q = A->rowptr[bs * va + i] + p + j;
                    if (q >= A->rowptr[bs * va + i + 1] || A->col[q] != bs * vb + j)
                        return wr_fail(diag, WR_ERR_INVALID_ARG, a,
                                       "csr_block_offsets: block (%d, %d) is not a contiguous %dx%d block of the pattern",
                                       (int)va, (int)vb, (int)bs, (int)bs);
                }
            off[a * k + b] = p;
        }
    return WR_OK;
}

WRDEF wr_status wr_csr_block_offsets(const wr_csr *A, int32_t k, const int32_t *verts, int32_t *off, wr_diag *diag) {
    return wr__csr_block_offsets_bs(A, 3, k, verts, off, diag);
}

/* Ke added into A's blocks; inline so that the call with bs = 3 below gets the block size as a constant
 * (the shells' vertex blocks: the inner loop unrolled, the same additions in the same order). */
static inline void wr__csr_add_blocks_loop(wr_csr *A, int32_t bs, int32_t k, const int32_t *verts, const int32_t *off,
                                           const double *Ke) {
    int32_t a, b, i, j, n = bs * k;
    for (a = 0; a < k; ++a) {
        if (verts[a] < 0) continue;
        for (i = 0; i < bs; ++i) {
            double *row = A->val + A->rowptr[bs * verts[a] + i];
            const double *ke = Ke + (size_t)(bs * a + i) * (size_t)n;
            for (b = 0; b < k; ++b) {
                int32_t p = off[a * k + b];
                if (p < 0) continue;
                for (j = 0; j < bs; ++j) row[p + j] += ke[bs * b + j];
            }
        }
    }
}

static void wr__csr_add_element_blocks_bs(wr_csr *A, int32_t bs, int32_t k, const int32_t *verts, const int32_t *off,
                                          const double *Ke) {
    if (bs == 3)
        wr__csr_add_blocks_loop(A, 3, k, verts, off, Ke);
    else
        wr__csr_add_blocks_loop(A, bs, k, verts, off, Ke);
}

WRDEF void wr_csr_add_element_blocks(wr_csr *A, int32_t k, const int32_t *verts, const int32_t *off, const double *Ke) {
    wr__csr_add_element_blocks_bs(A, 3, k, verts, off, Ke);
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

/* ---- assembly cache (ON ASSEMBLY CACHE) ------------------------------------------------------- */

WRDEF wr_status wr_assembly_init(wr_assembly *a, int32_t nb, int32_t bs, wr_diag *diag) {
    if (!a) return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "assembly: NULL cache");
    memset(a, 0, sizeof *a);
    if (nb < 0 || (bs != 1 && bs != 3) || nb > (INT32_MAX - 3) / 3)
        return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "assembly: %d blocks of %d DOFs (block size must be 1 or 3)",
                       (int)nb, (int)bs);
    a->nb = nb;
    a->bs = bs;
    a->c_begin = a->c_end = -1;
    return WR_OK;
}

static void wr__assembly_drop_record(wr_assembly *a) {
    wr_free(a->rec);
    a->rec = NULL;
    a->rn = a->rcap = 0;
    a->n_pend = 0;
}

WRDEF void wr_assembly_free(wr_assembly *a) {
    if (!a) return;
    wr_csr_free(&a->A);
    wr_free(a->vstart);
    wr_free(a->verts);
    wr_free(a->off);
    wr_free(a->doff);
    wr_free(a->pend_v);
    wr_free(a->ostart);
    wr_free(a->rec);
    wr_free(a->Kc);
    wr_free(a->pend_B);
    {
        int32_t nb = a->nb, bs = a->bs, builds = a->builds;
        memset(a, 0, sizeof *a);
        a->nb = nb;
        a->bs = bs;
        a->builds = builds;
        a->c_begin = a->c_end = -1;
    }
}

WRDEF void wr_assembly_begin(wr_assembly *a) {
    a->e = 0;
    a->misses = 0;
    if (!a->A.rowptr || a->stale) {
        wr_assembly_free(a); /* keeps nb, bs, builds */
        a->rec_mode = 1;
        return;
    }
    a->rec_mode = 0;
    wr_csr_zero_values(&a->A);
}

static wr_status wr__assembly_grow(void **p, int64_t *cap, int64_t need, size_t size, int64_t minimum) {
    void *q;
    int64_t c;
    if (need <= *cap) return WR_OK;
    c = 2 * *cap + need + minimum;
    q = wr_realloc_array(*p, (size_t)c, size);
    if (!q) return WR_ERR_NOMEM;
    *p = q;
    *cap = c;
    return WR_OK;
}

/* first assembly: append the element's stencil and its (bs·k)² block to the record */
static wr_status wr__assembly_record(wr_assembly *a, int32_t k, const int32_t *blocks, const double *Ke) {
    int64_t nn = (int64_t)a->bs * a->bs * k * k, cap_el = a->cap_el;
    if (a->n_el + 1 >= a->cap_el) {
        if (wr__assembly_grow((void **)&a->vstart, &cap_el, (int64_t)a->n_el + 2, sizeof(int32_t), 1024) != WR_OK)
            return WR_ERR_NOMEM;
        if (cap_el > INT32_MAX - 1) return WR_ERR_OVERFLOW;
        a->cap_el = (int32_t)cap_el;
        if (a->n_el == 0) a->vstart[0] = 0;
    }
    if (wr__assembly_grow((void **)&a->verts, &a->vcap, (int64_t)a->vstart[a->n_el] + k, sizeof(int32_t), 4096) != WR_OK ||
        wr__assembly_grow((void **)&a->rec, &a->rcap, a->rn + nn, sizeof(double), 65536) != WR_OK)
        return WR_ERR_NOMEM;
    memcpy(a->verts + a->vstart[a->n_el], blocks, sizeof(int32_t) * (size_t)k);
    memcpy(a->rec + a->rn, Ke, sizeof(double) * (size_t)nn);
    a->rn += nn;
    a->vstart[a->n_el + 1] = a->vstart[a->n_el] + k;
    a->n_el++;
    return WR_OK;
}

/* an element that does not match the record: its offsets by search; a block outside the pattern
 * makes the assembly stale (the caller assembles again, recording a new pattern) */
static wr_status wr__assembly_search_add(wr_assembly *a, int32_t k, const int32_t *blocks, const double *Ke,
                                         wr_diag *diag) {
    int32_t *off = (int32_t *)wr_alloc_array((size_t)k * (size_t)k + 1, sizeof(int32_t)), b;
    a->misses++;
    if (!off) return wr_fail(diag, WR_ERR_NOMEM, -1, "assembly: out of memory (element of %d blocks)", (int)k);
    for (b = 0; b < k; ++b)
        if (blocks[b] >= a->nb) {
            wr_free(off);
            return wr_fail(diag, WR_ERR_INVALID_ARG, blocks[b], "assembly: block %d outside [0, %d)", (int)blocks[b],
                           (int)a->nb);
        }
    if (wr__csr_block_offsets_bs(&a->A, a->bs, k, blocks, off, NULL) == WR_OK)
        wr__csr_add_element_blocks_bs(&a->A, a->bs, k, blocks, off, Ke);
    else
        a->stale = 1;
    wr_free(off);
    return WR_OK;
}

WRDEF wr_status wr_assembly_add(wr_assembly *a, int32_t k, const int32_t *blocks, const double *Ke, wr_diag *diag) {
    int32_t e = a->e;
    if (k < 0 || (k > 0 && (!blocks || !Ke))) return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "assembly: element of %d blocks", (int)k);
    if (a->rec_mode) {
        int32_t b;
        for (b = 0; b < k; ++b)
            if (blocks[b] >= a->nb)
                return wr_fail(diag, WR_ERR_INVALID_ARG, blocks[b], "assembly: block %d outside [0, %d)",
                               (int)blocks[b], (int)a->nb);
        if (wr__assembly_record(a, k, blocks, Ke) != WR_OK)
            return wr_fail(diag, WR_ERR_NOMEM, -1, "assembly: out of memory (%d elements recorded)", (int)a->n_el);
        return WR_OK;
    }
    /* later assemblies: the recorded element e when the stream still matches the record */
    if (e < a->n_el && a->vstart[e + 1] - a->vstart[e] == k &&
        !memcmp(a->verts + a->vstart[e], blocks, sizeof(int32_t) * (size_t)k)) {
        a->e = e + 1;
        wr__csr_add_element_blocks_bs(&a->A, a->bs, k, blocks, a->off + a->ostart[e], Ke);
        return WR_OK;
    }
    return wr__assembly_search_add(a, k, blocks, Ke, diag);
}

static void wr__assembly_diag_add(wr_assembly *a, int32_t v, const double *B) {
    int32_t i, j, bs = a->bs;
    for (i = 0; i < bs; ++i) {
        double *row = a->A.val + a->A.rowptr[bs * v + i] + a->doff[v];
        for (j = 0; j < bs; ++j) row[j] += B[bs * i + j];
    }
}

WRDEF wr_status wr_assembly_add_diagonal(wr_assembly *a, int32_t v, const double *B, wr_diag *diag) {
    int32_t bb = a->bs * a->bs;
    if (v < 0 || v >= a->nb || !B) return wr_fail(diag, WR_ERR_INVALID_ARG, v, "assembly: diagonal block %d outside [0, %d)", (int)v, (int)a->nb);
    if (!a->rec_mode) {
        wr__assembly_diag_add(a, v, B);
        return WR_OK;
    }
    /* recording: kept until the pattern exists, then added in the order given */
    if (a->n_pend >= a->cap_pend) {
        int32_t cap = a->cap_pend ? 2 * a->cap_pend : 256;
        int32_t *pv = (int32_t *)wr_realloc_array(a->pend_v, (size_t)cap, sizeof(int32_t));
        double *pb;
        if (!pv) return wr_fail(diag, WR_ERR_NOMEM, -1, "assembly: out of memory (%d diagonal blocks)", (int)cap);
        a->pend_v = pv;
        pb = (double *)wr_realloc_array(a->pend_B, (size_t)cap * (size_t)bb, sizeof(double));
        if (!pb) return wr_fail(diag, WR_ERR_NOMEM, -1, "assembly: out of memory (%d diagonal blocks)", (int)cap);
        a->pend_B = pb;
        a->cap_pend = cap;
    }
    a->pend_v[a->n_pend] = v;
    memcpy(a->pend_B + (size_t)a->n_pend * (size_t)bb, B, sizeof(double) * (size_t)bb);
    a->n_pend++;
    return WR_OK;
}

WRDEF int wr_assembly_constant_begin(wr_assembly *a) {
    int32_t i;
    if (a->rec_mode) {
        a->c_begin = a->n_el;
        return 1;
    }
    if (a->c_begin < 0) return 1; /* none recorded: streamed like the rest */
    if (a->Kc)
        for (i = 0; i < a->A.nnz; ++i) a->A.val[i] += a->Kc[i];
    a->e = a->c_end;
    return 0;
}

WRDEF void wr_assembly_constant_end(wr_assembly *a) {
    if (a->rec_mode) a->c_end = a->n_el;
}

/* after the recording assembly: the pattern, each element's block offsets, the recorded values in
 * stream order (and the constant segment's sum apart), then the diagonal blocks given meanwhile */
static wr_status wr__assembly_build(wr_assembly *a, wr_diag *diag) {
    int32_t e, v, bs = a->bs, zero = 0;
    int64_t r = 0;
    wr_status rs;
    if ((rs = wr__csr_from_stencils_bs(&a->A, a->nb, bs, a->n_el, a->n_el ? a->vstart : &zero, a->verts, diag)) != WR_OK)
        return rs;
    a->builds++;
    a->ostart = (int64_t *)wr_alloc_array((size_t)a->n_el + 1, sizeof(int64_t));
    a->doff = (int32_t *)wr_alloc_array((size_t)a->nb + 1, sizeof(int32_t));
    if (!a->ostart || !a->doff) return wr_fail(diag, WR_ERR_NOMEM, -1, "assembly: out of memory (%d elements)", (int)a->n_el);
    a->ostart[0] = 0;
    for (e = 0; e < a->n_el; ++e) {
        int64_t k = a->vstart[e + 1] - a->vstart[e];
        a->ostart[e + 1] = a->ostart[e] + k * k;
    }
    a->off = (int32_t *)wr_alloc_array((size_t)a->ostart[a->n_el] + 1, sizeof(int32_t));
    if (a->c_end > a->c_begin && a->c_begin >= 0) a->Kc = (double *)wr_calloc_array((size_t)a->A.nnz + 1, sizeof(double));
    if (!a->off || (a->c_end > a->c_begin && a->c_begin >= 0 && !a->Kc))
        return wr_fail(diag, WR_ERR_NOMEM, -1, "assembly: out of memory (%d elements)", (int)a->n_el);
    for (e = 0; e < a->n_el; ++e) {
        int32_t k = a->vstart[e + 1] - a->vstart[e];
        const int32_t *ev = a->verts + a->vstart[e];
        int32_t *off = a->off + a->ostart[e];
        if ((rs = wr__csr_block_offsets_bs(&a->A, bs, k, ev, off, diag)) != WR_OK) return rs;
        wr__csr_add_element_blocks_bs(&a->A, bs, k, ev, off, a->rec + r);
        if (a->Kc && e >= a->c_begin && e < a->c_end) {
            wr_csr kc = a->A;
            kc.val = a->Kc;
            wr__csr_add_element_blocks_bs(&kc, bs, k, ev, off, a->rec + r);
        }
        r += (int64_t)bs * bs * k * k;
    }
    for (v = 0; v < a->nb; ++v) a->doff[v] = wr_csr_find(&a->A, bs * v, bs * v) - a->A.rowptr[bs * v];
    for (e = 0; e < a->n_pend; ++e) wr__assembly_diag_add(a, a->pend_v[e], a->pend_B + (size_t)e * (size_t)(bs * bs));
    return WR_OK;
}

WRDEF wr_status wr_assembly_end(wr_assembly *a, wr_diag *diag) {
    wr_status rs = WR_OK;
    if (a->rec_mode) {
        rs = wr__assembly_build(a, diag);
        wr__assembly_drop_record(a);
        a->rec_mode = 0;
        a->stale = 0;
        if (rs != WR_OK) wr_assembly_free(a);
    }
    return rs;
}

#ifdef __cplusplus
}
#endif
#endif /* WRINKLE_SPARSE_IMPLEMENTATION_DONE */
#endif /* WRINKLE_IMPLEMENTATION */
