/* Tests for wrinkle/sparse.h: triplet assembly, CSR construction, pattern reuse, SpMV, blocks. */
#include <criterion/criterion.h>
#include <math.h>
#include <string.h>

#include "wrinkle/sparse.h"

/* Random sparse n×n matrix as triplets with many duplicates, plus the same sum in a dense array. */
static void random_triplets(wr_triplets *t, double *dense, int32_t n, int64_t m, wr_rng *rng) {
    int64_t k;
    memset(dense, 0, sizeof(double) * (size_t)n * (size_t)n);
    for (k = 0; k < m; ++k) {
        int32_t i = (int32_t)wr_rng_below(rng, (uint32_t)n), j = (int32_t)wr_rng_below(rng, (uint32_t)n);
        double v = wr_rng_normal(rng);
        cr_assert_eq(wr_triplets_add(t, i, j, v, NULL), WR_OK);
        dense[(size_t)i * n + j] += v;
    }
}

Test(sparse, triplets_sum_duplicates_and_sort) {
    wr_triplets t;
    wr_csr A;
    wr_diag d;
    cr_assert_eq(wr_triplets_create(&t, 4, 0, &d), WR_OK);
    cr_assert_eq(wr_triplets_add(&t, 2, 3, 1.5, &d), WR_OK);
    cr_assert_eq(wr_triplets_add(&t, 2, 0, -1.0, &d), WR_OK);
    cr_assert_eq(wr_triplets_add(&t, 2, 3, 2.25, &d), WR_OK);
    cr_assert_eq(wr_triplets_add(&t, 1, 1, 7.0, &d), WR_OK);
    cr_assert_eq(wr_triplets_add(&t, 2, 0, 0.5, &d), WR_OK);
    cr_assert_eq(wr_csr_from_triplets(&A, &t, &d), WR_OK);
    /* row 2: (2,0) -0.5, (2,2) explicit diagonal 0, (2,3) 3.75; rows 0,1,3 only their diagonal */
    cr_assert_eq(A.n, 4);
    cr_assert_eq(A.nnz, 6);
    cr_assert_eq(A.rowptr[2], 2);
    cr_assert_eq(A.rowptr[3], 5);
    cr_assert_eq(A.col[2], 0);
    cr_assert_eq(A.col[3], 2);
    cr_assert_eq(A.col[4], 3);
    cr_assert_eq(A.val[2], -0.5);
    cr_assert_eq(A.val[3], 0.0);
    cr_assert_eq(A.val[4], 3.75);
    cr_assert_eq(A.val[wr_csr_find(&A, 1, 1)], 7.0);
    cr_assert_eq(wr_csr_find(&A, 0, 3), -1);
    wr_csr_free(&A);
    wr_triplets_free(&t);
}

Test(sparse, random_matches_dense_spmv_and_growth) {
    enum { N = 37 };
    static double dense[N * N];
    double x[N], y[N], yd[N], diagv[N];
    wr_triplets t;
    wr_csr A;
    wr_rng rng;
    int32_t i, j, p;
    wr_rng_seed(&rng, 7);
    cr_assert_eq(wr_triplets_create(&t, N, 1, NULL), WR_OK); /* forces many regrowths */
    random_triplets(&t, dense, N, 3000, &rng);
    cr_assert_eq(t.count, 3000);
    cr_assert_eq(wr_csr_from_triplets(&A, &t, NULL), WR_OK);
    for (i = 0; i < N; ++i) {
        for (p = A.rowptr[i]; p + 1 < A.rowptr[i + 1]; ++p) cr_assert_lt(A.col[p], A.col[p + 1]);
        cr_assert_geq(wr_csr_find(&A, i, i), 0);
        x[i] = wr_rng_normal(&rng);
    }
    wr_csr_spmv(&A, x, y);
    for (i = 0; i < N; ++i) {
        yd[i] = 0.0;
        for (j = 0; j < N; ++j) {
            yd[i] += dense[i * N + j] * x[j];
            p = wr_csr_find(&A, i, j);
            if (p >= 0) cr_assert_float_eq(A.val[p], dense[i * N + j], 1e-12);
            else cr_assert_eq(dense[i * N + j], 0.0);
        }
        cr_assert_float_eq(y[i], yd[i], 1e-11 * (1.0 + fabs(yd[i])));
    }
    wr_csr_diagonal(&A, diagv);
    for (i = 0; i < N; ++i) cr_assert_float_eq(diagv[i], dense[i * N + i], 1e-12);
    wr_csr_free(&A);
    wr_triplets_free(&t);
}

/* Newton-style reuse: pattern from zero element matrices, then values via wr_csr_add_element must
 * equal a fresh triplet assembly of the same element matrices. */
Test(sparse, pattern_reuse_equals_fresh_assembly) {
    enum { NV = 5, NE = 4 };
    const int32_t tri[NE][3] = {{0, 1, 2}, {1, 3, 2}, {2, 3, 4}, {0, 2, 4}};
    static double Ke[NE][81], zeros[81];
    int32_t idx[NE][9];
    wr_triplets t, t2;
    wr_csr K, K2;
    wr_rng rng;
    int e, a, b, round;
    wr_rng_seed(&rng, 11);
    for (e = 0; e < NE; ++e)
        for (a = 0; a < 3; ++a)
            for (b = 0; b < 3; ++b) idx[e][3 * a + b] = 3 * tri[e][a] + b;
    cr_assert_eq(wr_triplets_create(&t, 3 * NV, 0, NULL), WR_OK);
    for (e = 0; e < NE; ++e) cr_assert_eq(wr_triplets_add_element(&t, 9, idx[e], zeros, NULL), WR_OK);
    cr_assert_eq(wr_csr_from_triplets(&K, &t, NULL), WR_OK);
    for (round = 0; round < 3; ++round) {
        int32_t p;
        for (e = 0; e < NE; ++e)
            for (a = 0; a < 81; ++a) Ke[e][a] = wr_rng_normal(&rng);
        wr_csr_zero_values(&K);
        for (e = 0; e < NE; ++e) cr_assert_eq(wr_csr_add_element(&K, 9, idx[e], Ke[e], NULL), WR_OK);
        cr_assert_eq(wr_triplets_create(&t2, 3 * NV, 0, NULL), WR_OK);
        for (e = 0; e < NE; ++e) cr_assert_eq(wr_triplets_add_element(&t2, 9, idx[e], Ke[e], NULL), WR_OK);
        cr_assert_eq(wr_csr_from_triplets(&K2, &t2, NULL), WR_OK);
        cr_assert_eq(K.nnz, K2.nnz);
        for (p = 0; p < K.nnz; ++p) {
            cr_assert_eq(K.col[p], K2.col[p]);
            cr_assert_float_eq(K.val[p], K2.val[p], 1e-13);
        }
        wr_csr_free(&K2);
        wr_triplets_free(&t2);
    }
    /* vertices 1 and 4 share no triangle: that block is outside the pattern */
    {
        double B[9];
        wr_diag d;
        int32_t bad[2] = {3, 12};
        double K4[4] = {1, 2, 3, 4};
        cr_assert_eq(wr_csr_block3(&K, 1, 4, B), 0);
        cr_assert_eq(wr_csr_block3(&K, 1, 2, B), 9);
        cr_assert_eq(wr_csr_add(&K, 3, 12, 1.0, &d), WR_ERR_INVALID_ARG);
        cr_assert_eq(d.item, 3);
        cr_assert_eq(wr_csr_add_element(&K, 2, bad, K4, &d), WR_ERR_INVALID_ARG);
    }
    wr_csr_free(&K);
    wr_triplets_free(&t);
}

Test(sparse, block3_helpers_and_negative_index_skip) {
    double B[9] = {1, 2, 3, 4, 5, 6, 7, 8, 9}, R[9], D[18];
    double Ke[4] = {10, 20, 30, 40};
    int32_t idx[2] = {-1, 4};
    wr_triplets t;
    wr_csr A;
    wr_diag d;
    int a;
    cr_assert_eq(wr_triplets_create(&t, 6, 0, NULL), WR_OK);
    cr_assert_eq(wr_triplets_add_block3(&t, 1, 0, B, NULL), WR_OK);
    cr_assert_eq(wr_triplets_add_block3(&t, 1, 1, B, NULL), WR_OK);
    cr_assert_eq(wr_triplets_add_element(&t, 2, idx, Ke, NULL), WR_OK); /* only (4,4) += 40 */
    cr_assert_eq(t.count, 19);
    cr_assert_eq(wr_triplets_add_block3(&t, 2, 0, B, &d), WR_ERR_INVALID_ARG);
    cr_assert_eq(wr_csr_from_triplets(&A, &t, NULL), WR_OK);
    cr_assert_eq(wr_csr_block3(&A, 1, 0, R), 9);
    for (a = 0; a < 9; ++a) cr_assert_eq(R[a], B[a]);
    cr_assert_eq(wr_csr_add_block3(&A, 1, 0, B, NULL), WR_OK);
    wr_csr_block3(&A, 1, 0, R);
    for (a = 0; a < 9; ++a) cr_assert_eq(R[a], 2 * B[a]);
    cr_assert_eq(wr_csr_add_block3(&A, 0, 1, B, &d), WR_ERR_INVALID_ARG); /* (0..2, 3..5) not stored */
    wr_csr_block3_diagonal(&A, D);
    for (a = 0; a < 9; ++a) cr_assert_eq(D[9 + a], B[a] + (a == 4 ? 40.0 : 0.0));
    cr_assert_eq(D[0], 0.0); /* explicit diagonal zero of block 0 */
    cr_assert_float_eq(wr_csr_asymmetry(&A), 18.0 / 45.0, 1e-15); /* 2*9 missing from the transpose, max |a| = 5+40 */
    wr_csr_free(&A);
    wr_triplets_free(&t);
}

Test(sparse, symmetric_assembly_has_zero_asymmetry_and_copy) {
    double Ke[9] = {2, -1, 0.5, -1, 3, 0.25, 0.5, 0.25, 4};
    int32_t idx[3] = {0, 2, 3};
    wr_triplets t;
    wr_csr A, C;
    int32_t p;
    cr_assert_eq(wr_triplets_create(&t, 4, 0, NULL), WR_OK);
    cr_assert_eq(wr_triplets_add_element(&t, 3, idx, Ke, NULL), WR_OK);
    cr_assert_eq(wr_csr_from_triplets(&A, &t, NULL), WR_OK);
    cr_assert_eq(wr_csr_asymmetry(&A), 0.0);
    cr_assert_eq(wr_csr_copy(&C, &A, NULL), WR_OK);
    cr_assert_eq(C.nnz, A.nnz);
    for (p = 0; p < A.nnz; ++p) cr_assert_eq(C.val[p], A.val[p]);
    C.val[0] = 99.0;
    cr_assert_neq(A.val[0], 99.0);
    wr_csr_free(&C);
    wr_csr_free(&A);
    wr_csr_free(&A); /* free is idempotent on a zeroed matrix */
    wr_triplets_free(&t);
}

Test(sparse, error_paths) {
    wr_triplets t;
    wr_csr A;
    wr_diag d;
    double Ke[1] = {1.0};
    int32_t idx[1] = {5};
    cr_assert_eq(wr_triplets_create(NULL, 3, 0, &d), WR_ERR_INVALID_ARG);
    cr_assert_eq(wr_triplets_create(&t, -1, 0, &d), WR_ERR_INVALID_ARG);
    cr_assert_eq(wr_triplets_create(&t, 3, 0, &d), WR_OK);
    cr_assert_eq(wr_triplets_add(&t, 3, 0, 1.0, &d), WR_ERR_INVALID_ARG);
    cr_assert_eq(d.item, 3);
    cr_assert_eq(wr_triplets_add(&t, 0, -1, 1.0, &d), WR_ERR_INVALID_ARG);
    cr_assert_eq(wr_triplets_add(NULL, 0, 0, 1.0, &d), WR_ERR_INVALID_ARG);
    cr_assert_eq(wr_triplets_add_element(&t, 1, idx, Ke, &d), WR_ERR_INVALID_ARG);
    cr_assert_eq(wr_triplets_add_element(&t, 1, NULL, Ke, &d), WR_ERR_INVALID_ARG);
    cr_assert_eq(wr_triplets_add_element(&t, -2, idx, Ke, &d), WR_ERR_INVALID_ARG);
    cr_assert_eq(t.count, 0);
    cr_assert_eq(wr_csr_from_triplets(NULL, &t, &d), WR_ERR_INVALID_ARG);
    cr_assert_eq(wr_csr_from_triplets(&A, NULL, &d), WR_ERR_INVALID_ARG);
    /* a corrupted triplet (user wrote past the API) is caught, A stays freeable */
    cr_assert_eq(wr_triplets_add(&t, 1, 1, 1.0, &d), WR_OK);
    t.col[0] = 9;
    cr_assert_eq(wr_csr_from_triplets(&A, &t, &d), WR_ERR_INVALID_ARG);
    cr_assert_eq(A.rowptr, NULL);
    wr_csr_free(&A);
    cr_assert_eq(wr_csr_copy(&A, NULL, &d), WR_ERR_INVALID_ARG);
    cr_assert_eq(wr_csr_add(NULL, 0, 0, 1.0, &d), WR_ERR_INVALID_ARG);
    cr_assert_eq(wr_csr_find(NULL, 0, 0), -1);
    wr_triplets_free(&t);
    /* empty matrix: n = 0 is legal */
    cr_assert_eq(wr_triplets_create(&t, 0, 0, &d), WR_OK);
    cr_assert_eq(wr_csr_from_triplets(&A, &t, &d), WR_OK);
    cr_assert_eq(A.nnz, 0);
    wr_csr_free(&A);
    wr_triplets_free(&t);
}

/* ON CACHED ASSEMBLY: the stencil pattern equals the triplet pattern of the same blocks, and adding
 * through cached block offsets gives the same values as the searched wr_csr_add_element. */
Test(sparse, stencil_pattern_and_cached_block_offsets) {
    /* 6 vertices, stencils of 3, 4 and 2 vertices (one repeated pair, vertex 5 only on the diagonal),
     * one negative (dropped) entry */
    static const int32_t start[4] = {0, 3, 7, 10};
    static const int32_t verts[10] = {0, 1, 2, 3, 1, 2, 4, 4, -1, 0};
    wr_triplets t;
    wr_csr A, B;
    wr_diag d;
    wr_rng rng;
    int32_t e, p, off[16], badoff[4];
    double Ke[144];
    wr_rng_seed(&rng, 7);
    cr_assert_eq(wr_csr_from_stencils(&A, 6, 3, start, verts, &d), WR_OK);
    cr_assert_eq(wr_triplets_create(&t, 18, 0, &d), WR_OK);
    for (e = 0; e < 3; ++e) {
        int32_t k = start[e + 1] - start[e], idx[12], a, i;
        for (a = 0; a < k; ++a)
            for (i = 0; i < 3; ++i) idx[3 * a + i] = verts[start[e] + a] < 0 ? -1 : 3 * verts[start[e] + a] + i;
        for (a = 0; a < 9 * k * k; ++a) Ke[a] = wr_rng_normal(&rng);
        cr_assert_eq(wr_triplets_add_element(&t, 3 * k, idx, Ke, &d), WR_OK);
    }
    for (e = 0; e < 6; ++e) {
        static const double Z[9] = {0, 0, 0, 0, 0, 0, 0, 0, 0};
        cr_assert_eq(wr_triplets_add_block3(&t, e, e, Z, &d), WR_OK);
    }
    cr_assert_eq(wr_csr_from_triplets(&B, &t, &d), WR_OK);
    wr_triplets_free(&t);
    /* same pattern: 18 rows; vertex 0 couples 0,1,2,4 → 12 columns per row */
    cr_assert_eq(A.n, 18);
    cr_assert_eq(A.nnz, B.nnz);
    for (p = 0; p <= A.n; ++p) cr_assert_eq(A.rowptr[p], B.rowptr[p]);
    for (p = 0; p < A.nnz; ++p) {
        cr_assert_eq(A.col[p], B.col[p]);
        cr_assert_eq(A.val[p], 0.0);
    }
    cr_assert_eq(A.rowptr[1] - A.rowptr[0], 12);
    cr_assert_eq(A.rowptr[16] - A.rowptr[15], 3); /* vertex 5: its diagonal block only */
    /* random element values: cached offsets against the binary-search path */
    wr_csr_zero_values(&B);
    for (e = 0; e < 3; ++e) {
        int32_t k = start[e + 1] - start[e], idx[12], a, i;
        for (a = 0; a < k; ++a)
            for (i = 0; i < 3; ++i) idx[3 * a + i] = verts[start[e] + a] < 0 ? -1 : 3 * verts[start[e] + a] + i;
        for (a = 0; a < 9 * k * k; ++a) Ke[a] = wr_rng_normal(&rng);
        cr_assert_eq(wr_csr_block_offsets(&A, k, verts + start[e], off, &d), WR_OK);
        if (e == 2) cr_expect_eq(off[1], -1); /* the dropped vertex */
        wr_csr_add_element_blocks(&A, k, verts + start[e], off, Ke);
        cr_assert_eq(wr_csr_add_element(&B, 3 * k, idx, Ke, &d), WR_OK);
    }
    for (p = 0; p < A.nnz; ++p) cr_expect_eq(A.val[p], B.val[p], "entry %d: %g vs %g", (int)p, A.val[p], B.val[p]);
    /* errors: a block outside the pattern, a vertex outside n, a pattern without whole 3×3 blocks */
    {
        int32_t v2[2] = {0, 3}, v3[2] = {0, 6};
        cr_expect_eq(wr_csr_block_offsets(&A, 2, v2, badoff, &d), WR_ERR_INVALID_ARG);
        cr_expect_eq(wr_csr_block_offsets(&A, 2, v3, badoff, &d), WR_ERR_INVALID_ARG);
    }
    wr_csr_free(&B);
    cr_assert_eq(wr_triplets_create(&t, 6, 0, &d), WR_OK);
    cr_assert_eq(wr_triplets_add(&t, 0, 3, 1.0, &d), WR_OK); /* only (0,3) of block (0,1) */
    cr_assert_eq(wr_csr_from_triplets(&B, &t, &d), WR_OK);
    {
        int32_t v01[2] = {0, 1};
        cr_expect_eq(wr_csr_block_offsets(&B, 2, v01, badoff, &d), WR_ERR_INVALID_ARG);
    }
    {
        static const int32_t bad_start[2] = {0, 2}, bad_verts[2] = {0, 9};
        wr_csr C;
        cr_expect_eq(wr_csr_from_stencils(&C, 6, 1, bad_start, bad_verts, &d), WR_ERR_INVALID_ARG);
        cr_expect_null(C.rowptr);
        cr_expect_eq(wr_csr_from_stencils(&C, 0, 0, NULL, NULL, &d), WR_OK); /* empty */
        cr_expect_eq(C.n, 0);
        wr_csr_free(&C);
    }
    wr_triplets_free(&t);
    wr_csr_free(&B);
    wr_csr_free(&A);
}

/* ---- the assembly cache (ON ASSEMBLY CACHE) ---------------------------------------------------- */

/* element e of a small made-up stream: k blocks, values depending on (e, scale) */
static void asm_element(int32_t e, int32_t bs, double scale, int32_t *k, int32_t *blocks, double *Ke) {
    static const int32_t conn[4][3] = {{0, 1, 2}, {2, 3, -1}, {3, 4, 1}, {4, 0, -1}};
    int32_t i, j, n;
    *k = conn[e][2] < 0 ? 2 : 3;
    for (i = 0; i < *k; ++i) blocks[i] = conn[e][i];
    n = bs * *k;
    for (i = 0; i < n; ++i)
        for (j = 0; j < n; ++j) Ke[i * n + j] = scale * (1.0 + e + 0.1 * i + 0.01 * j);
}

/* the same stream through triplets: the reference matrix */
static void asm_reference(wr_csr *R, int32_t bs, double scale, double scale_const, int extra) {
    wr_triplets t;
    int32_t e, k, blocks[3], idx[9], a, i;
    double Ke[81], D[9];
    cr_assert_eq(wr_triplets_create(&t, 5 * bs, 64, NULL), WR_OK);
    for (e = 0; e < 4 + (extra != 0); ++e) {
        asm_element(e < 4 ? e : 3, bs, e == 1 ? scale_const : scale, &k, blocks, Ke);
        if (e == 4) blocks[1] = 2; /* the extra element couples 4 with 2: outside the first pattern */
        for (a = 0; a < k; ++a)
            for (i = 0; i < bs; ++i) idx[bs * a + i] = bs * blocks[a] + i;
        cr_assert_eq(wr_triplets_add_element(&t, bs * k, idx, Ke, NULL), WR_OK);
    }
    for (i = 0; i < bs * bs; ++i) D[i] = scale * (i + 1);
    for (i = 0; i < bs; ++i)
        for (a = 0; a < bs; ++a) cr_assert_eq(wr_triplets_add(&t, 3 * bs + i, 3 * bs + a, D[bs * i + a], NULL), WR_OK);
    cr_assert_eq(wr_csr_from_triplets(R, &t, NULL), WR_OK);
    wr_triplets_free(&t);
}

static void asm_run(wr_assembly *A, int32_t bs, double scale, int extra) {
    int32_t e, k, blocks[3];
    double Ke[81], D[9];
    int i;
    wr_assembly_begin(A);
    for (e = 0; e < 4; ++e) {
        if (e == 1) {
            /* element 1 is the constant segment: streamed only when asked */
            if (wr_assembly_constant_begin(A)) {
                asm_element(1, bs, 1.0, &k, blocks, Ke);
                cr_assert_eq(wr_assembly_add(A, k, blocks, Ke, NULL), WR_OK);
            }
            wr_assembly_constant_end(A);
            continue;
        }
        asm_element(e, bs, scale, &k, blocks, Ke);
        cr_assert_eq(wr_assembly_add(A, k, blocks, Ke, NULL), WR_OK);
    }
    if (extra) {
        asm_element(3, bs, scale, &k, blocks, Ke);
        blocks[1] = 2;
        cr_assert_eq(wr_assembly_add(A, k, blocks, Ke, NULL), WR_OK);
    }
    for (i = 0; i < bs * bs; ++i) D[i] = scale * (i + 1);
    cr_assert_eq(wr_assembly_add_diagonal(A, 3, D, NULL), WR_OK);
    cr_assert_eq(wr_assembly_end(A, NULL), WR_OK);
}

/* every entry of R equals A's (absent entries of A must be zero in R) */
static void asm_expect_equal(const wr_csr *A, const wr_csr *R, const char *what) {
    int32_t i, p;
    cr_assert_eq(A->n, R->n, "%s", what);
    for (i = 0; i < R->n; ++i)
        for (p = R->rowptr[i]; p < R->rowptr[i + 1]; ++p) {
            int32_t q = wr_csr_find(A, i, R->col[p]);
            double v = q >= 0 ? A->val[q] : 0.0;
            /* same additions, possibly in another order: a few ulps of the entry */
            cr_expect_float_eq(v, R->val[p], 1e-14 * fmax(1.0, fabs(R->val[p])), "%s: (%d, %d) %g vs %g", what, (int)i,
                               (int)R->col[p], v, R->val[p]);
        }
}

Test(sparse, assembly_cache_blocks_of_3_and_1) {
    int32_t bs;
    for (bs = 1; bs <= 3; bs += 2) {
        wr_assembly A;
        wr_csr R;
        cr_assert_eq(wr_assembly_init(&A, 5, bs, NULL), WR_OK);
        asm_run(&A, bs, 1.0, 0); /* records, builds the pattern */
        asm_reference(&R, bs, 1.0, 1.0, 0);
        asm_expect_equal(&A.A, &R, "first assembly");
        wr_csr_free(&R);
        cr_expect_eq(A.builds, 1);
        asm_run(&A, bs, 2.5, 0); /* cached offsets; the constant element from its cached sum */
        asm_reference(&R, bs, 2.5, 1.0, 0);
        asm_expect_equal(&A.A, &R, "cached assembly");
        wr_csr_free(&R);
        cr_expect_eq(A.misses, 0);
        cr_expect_eq(A.builds, 1);
        cr_expect_eq(A.stale, 0);
        /* an element coupling two blocks the pattern does not couple: stale, then a new pattern */
        asm_run(&A, bs, 3.0, 1);
        cr_expect_eq(A.stale, 1, "bs %d: the new coupling must make the assembly stale", (int)bs);
        asm_run(&A, bs, 3.0, 1);
        cr_expect_eq(A.stale, 0);
        cr_expect_eq(A.builds, 2);
        asm_reference(&R, bs, 3.0, 1.0, 1);
        asm_expect_equal(&A.A, &R, "rebuilt pattern");
        wr_csr_free(&R);
        wr_assembly_free(&A);
    }
    {
        wr_assembly A;
        cr_expect_eq(wr_assembly_init(&A, 5, 2, NULL), WR_ERR_INVALID_ARG);
    }
}
