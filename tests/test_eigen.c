/* tests/test_eigen.c — eigen.h: the lowest eigenpairs of sparse symmetric pencils against closed
 * forms (1D and 2D Dirichlet Laplacians, shifted ones with known negative eigenvalues, a diagonal
 * metric, fixed DOFs), the LDLᵀ inertia (and its zero pivot on an eigenvalue), and the error
 * paths. Built with WR_USE_ARPACK and WR_USE_CHOLMOD (the Makefile's test binary).
 * Tolerances: ARPACK's tol is 1e-10 relative on the Ritz values of (K − σM)⁻¹; the eigenvalues
 * here are O(1e-3–1), so 1e-9 absolute leaves an order of margin over what it guarantees. */
#include <criterion/criterion.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "wrinkle/eigen.h"

#define EG_PI 3.14159265358979323846
#define EG_TOL 1e-9

/* 1D Laplacian tridiag(−1, 2 − c, −1), scaled symmetrically by D (K = D L D) when w != NULL */
static void eg_laplace1d(wr_csr *K, int32_t n, double c, const double *w) {
    wr_triplets t;
    int32_t i;
    cr_assert_eq(wr_triplets_create(&t, n, 3 * (int64_t)n, NULL), WR_OK);
    for (i = 0; i < n; ++i) {
        double di = w ? sqrt(w[i]) : 1.0;
        wr_triplets_add(&t, i, i, (2.0 - c) * di * di, NULL);
        if (i + 1 < n) {
            double dj = w ? sqrt(w[i + 1]) : 1.0;
            wr_triplets_add(&t, i, i + 1, -di * dj, NULL);
            wr_triplets_add(&t, i + 1, i, -di * dj, NULL);
        }
    }
    cr_assert_eq(wr_csr_from_triplets(K, &t, NULL), WR_OK);
    wr_triplets_free(&t);
}

static double eg_exact1d(int32_t n, double c, int32_t k) { return 2.0 - c - 2.0 * cos((double)k * EG_PI / (double)(n + 1)); }

static int eg_cmp(const void *a, const void *b) {
    double x = *(const double *)a, y = *(const double *)b;
    return x < y ? -1 : x > y;
}

Test(eigen, laplacian_1d_lowest_and_modes) {
    wr_csr K;
    wr_eigen_desc ed;
    wr_eigen_result er;
    wr_diag d;
    int32_t n = 60, k, i;
    eg_laplace1d(&K, n, 0.0, NULL);
    memset(&ed, 0, sizeof ed);
    ed.nev = 5;
    cr_assert_eq(wr_eigen_lowest(&K, &ed, &er, &d), WR_OK, "%s", d.message);
    cr_assert_eq(er.nev, 5);
    cr_assert_eq(er.n_negative, 0);
    cr_assert(er.complete);
    cr_assert(er.residual < 1e-8, "residual %g", er.residual);
    for (k = 0; k < 5; ++k) {
        double dot = 0.0, nn = 0.0;
        cr_assert_float_eq(er.values[k], eg_exact1d(n, 0.0, k + 1), EG_TOL, "λ_%d = %.12g", (int)k, er.values[k]);
        /* mode k+1 is sin((k+1)π i/(n+1)): unit vector up to sign */
        for (i = 0; i < n; ++i) {
            double s = sin((double)(k + 1) * EG_PI * (double)(i + 1) / (double)(n + 1));
            dot += s * er.vectors[(size_t)k * n + i];
            nn += s * s;
        }
        cr_assert_float_eq(fabs(dot) / sqrt(nn), 1.0, 1e-8, "mode %d overlap %.12g", (int)k, fabs(dot) / sqrt(nn));
    }
    wr_eigen_result_free(&er);
    wr_csr_free(&K);
}

Test(eigen, laplacian_2d_closed_form) {
    /* 5-point Dirichlet Laplacian on an nx × ny interior grid: λ = 4 − 2cos(iπ/(nx+1)) − 2cos(jπ/(ny+1)) */
    wr_triplets t;
    wr_csr K;
    wr_eigen_desc ed;
    wr_eigen_result er;
    wr_diag d;
    int32_t nx = 12, ny = 9, n = nx * ny, i, j, k;
    double all[108];
    cr_assert_eq(wr_triplets_create(&t, n, 5 * (int64_t)n, NULL), WR_OK);
    for (j = 0; j < ny; ++j)
        for (i = 0; i < nx; ++i) {
            int32_t p = j * nx + i;
            wr_triplets_add(&t, p, p, 4.0, NULL);
            if (i + 1 < nx) wr_triplets_add(&t, p, p + 1, -1.0, NULL), wr_triplets_add(&t, p + 1, p, -1.0, NULL);
            if (j + 1 < ny) wr_triplets_add(&t, p, p + nx, -1.0, NULL), wr_triplets_add(&t, p + nx, p, -1.0, NULL);
            all[p] = 4.0 - 2.0 * cos((i + 1) * EG_PI / (nx + 1)) - 2.0 * cos((j + 1) * EG_PI / (ny + 1));
        }
    cr_assert_eq(wr_csr_from_triplets(&K, &t, NULL), WR_OK);
    wr_triplets_free(&t);
    qsort(all, (size_t)n, sizeof *all, eg_cmp);
    memset(&ed, 0, sizeof ed);
    ed.nev = 6;
    cr_assert_eq(wr_eigen_lowest(&K, &ed, &er, &d), WR_OK, "%s", d.message);
    for (k = 0; k < 6; ++k) cr_assert_float_eq(er.values[k], all[k], EG_TOL, "λ_%d = %.12g vs %.12g", (int)k, er.values[k], all[k]);
    wr_eigen_result_free(&er);
    wr_csr_free(&K);
}

Test(eigen, negative_eigenvalues_and_inertia) {
    /* L − cI, c = 0.05, n = 50: exactly three eigenvalues below 0 (2 − 2cos(3π/51) = 0.0341 < c) */
    wr_csr K;
    wr_eigen_desc ed;
    wr_eigen_result er;
    wr_diag d;
    int32_t n = 50, k, nb = -1, nz = -1, expect;
    double c = 0.05, sig;
    eg_laplace1d(&K, n, c, NULL);
    memset(&ed, 0, sizeof ed);
    ed.nev = 5;
    cr_assert_eq(wr_eigen_lowest(&K, &ed, &er, &d), WR_OK, "%s", d.message);
    cr_assert_eq(er.n_negative, 3);
    for (k = 0; k < 5; ++k) cr_assert_float_eq(er.values[k], eg_exact1d(n, c, k + 1), EG_TOL);
    wr_eigen_result_free(&er);
    /* the inertia below several shifts: the count of closed-form eigenvalues below σ */
    for (sig = -0.06; sig < 0.3; sig += 0.0137) {
        for (expect = 0, k = 1; k <= n; ++k) expect += eg_exact1d(n, c, k) < sig;
        cr_assert_eq(wr_eigen_inertia(&K, NULL, NULL, sig, &nb, &nz, &d), WR_OK, "%s", d.message);
        cr_assert_eq(nb, expect, "σ = %g: %d below, expected %d", sig, (int)nb, (int)expect);
        cr_assert_eq(nz, 0);
    }
    wr_csr_free(&K);
}

Test(eigen, many_negatives_need_the_shift_loop) {
    /* n = 200, c = 0.01: six eigenvalues below 0 packed within 0.006, so the three nearest σ0 ≈ 0 are
     * the least negative; ON THE SEARCH step 3 must move σ to return the three lowest */
    wr_csr K;
    wr_eigen_desc ed;
    wr_eigen_result er;
    wr_diag d;
    int32_t n = 200, k;
    eg_laplace1d(&K, n, 0.01, NULL);
    memset(&ed, 0, sizeof ed);
    ed.nev = 3;
    cr_assert_eq(wr_eigen_lowest(&K, &ed, &er, &d), WR_OK, "%s", d.message);
    cr_assert_eq(er.n_negative, 6);
    cr_assert(er.complete);
    cr_assert(er.factorizations >= 2, "%d factorizations", (int)er.factorizations);
    for (k = 0; k < 3; ++k) cr_assert_float_eq(er.values[k], eg_exact1d(n, 0.01, k + 1), EG_TOL, "λ_%d = %.12g", (int)k, er.values[k]);
    wr_eigen_result_free(&er);
    wr_csr_free(&K);
}

Test(eigen, diagonal_metric_and_fixed_dofs) {
    /* K = D L D, M = D²: K v = λ M v has L's eigenvalues (D v = L's mode), M-orthonormal vectors */
    wr_csr K;
    wr_eigen_desc ed;
    wr_eigen_result er;
    wr_diag d;
    int32_t n = 61, i, k, q;
    double w[61];
    uint8_t fixed[61];
    for (i = 0; i < n; ++i) w[i] = 0.5 + 0.37 * (double)((i * 7) % 5);
    eg_laplace1d(&K, n, 0.0, w);
    memset(&ed, 0, sizeof ed);
    ed.nev = 4;
    ed.metric = w;
    cr_assert_eq(wr_eigen_lowest(&K, &ed, &er, &d), WR_OK, "%s", d.message);
    for (k = 0; k < 4; ++k) cr_assert_float_eq(er.values[k], eg_exact1d(n, 0.0, k + 1), EG_TOL, "λ_%d = %.12g", (int)k, er.values[k]);
    for (k = 0; k < 4; ++k)
        for (q = 0; q < 4; ++q) {
            double g = 0.0;
            for (i = 0; i < n; ++i) g += er.vectors[(size_t)k * n + i] * w[i] * er.vectors[(size_t)q * n + i];
            cr_assert_float_eq(g, k == q ? 1.0 : 0.0, 1e-8, "vᵀMv (%d, %d) = %g", (int)k, (int)q, g);
        }
    wr_eigen_result_free(&er);
    wr_csr_free(&K);
    /* DOF 30 held: two Dirichlet chains of 30, every eigenvalue 2 − 2cos(kπ/31) twice */
    eg_laplace1d(&K, n, 0.0, NULL);
    memset(fixed, 0, sizeof fixed);
    fixed[30] = 1;
    memset(&ed, 0, sizeof ed);
    ed.nev = 4;
    ed.fixed = fixed;
    cr_assert_eq(wr_eigen_lowest(&K, &ed, &er, &d), WR_OK, "%s", d.message);
    for (k = 0; k < 4; ++k) cr_assert_float_eq(er.values[k], eg_exact1d(30, 0.0, k / 2 + 1), EG_TOL, "λ_%d = %.12g", (int)k, er.values[k]);
    for (k = 0; k < 4; ++k) cr_assert_eq(er.vectors[(size_t)k * n + 30], 0.0);
    wr_eigen_result_free(&er);
    wr_csr_free(&K);
}

Test(eigen, error_paths) {
    wr_csr K;
    wr_eigen_desc ed;
    wr_eigen_result er;
    wr_diag d;
    double w[10];
    int32_t i, nb;
    eg_laplace1d(&K, 10, 0.0, NULL);
    memset(&ed, 0, sizeof ed);
    ed.nev = 10; /* as many as the free DOFs: ARPACK needs nev < n */
    cr_assert_eq(wr_eigen_lowest(&K, &ed, &er, &d), WR_ERR_INVALID_ARG);
    wr_eigen_result_free(&er);
    for (i = 0; i < 10; ++i) w[i] = 1.0;
    w[7] = 0.0;
    ed.nev = 2;
    ed.metric = w;
    cr_assert_eq(wr_eigen_lowest(&K, &ed, &er, &d), WR_ERR_INVALID_ARG);
    cr_assert_eq(d.item, 7);
    wr_eigen_result_free(&er);
    cr_assert_eq(wr_eigen_inertia(&K, NULL, w, 0.0, &nb, NULL, &d), WR_ERR_INVALID_ARG);
    ed.metric = NULL;
    ed.tol = -1.0;
    cr_assert_eq(wr_eigen_lowest(&K, &ed, &er, &d), WR_ERR_INVALID_ARG);
    wr_eigen_result_free(&er);
    wr_csr_free(&K);
}

/* A shift exactly on an eigenvalue: the 1D Laplacian of n = 3 has λ = 2 − √2, 2, 2 + √2, and
 * L − 2I (every diagonal entry exactly 0) is singular in exact arithmetic, whatever the ordering:
 * the first pivot is 0, so the inertia must report a zero pivot (it is what the search tests to
 * move σ off an eigenvalue). Off the eigenvalue (σ = 2 ± 1e-3) no zero pivot, and the counts of
 * the closed form. */
Test(eigen, inertia_reports_a_zero_pivot_on_an_eigenvalue) {
    wr_csr K;
    wr_diag d;
    int32_t nb = -1, nz = -1;
    eg_laplace1d(&K, 3, 0.0, NULL);
    cr_assert_eq(wr_eigen_inertia(&K, NULL, NULL, 2.0, &nb, &nz, &d), WR_OK, "%s", d.message);
    cr_assert_geq(nz, 1, "σ = 2 = λ_2: %d zero pivots", (int)nz);
    cr_assert_eq(wr_eigen_inertia(&K, NULL, NULL, 2.0 - 1e-3, &nb, &nz, &d), WR_OK, "%s", d.message);
    cr_assert_eq(nz, 0);
    cr_assert_eq(nb, 1);
    cr_assert_eq(wr_eigen_inertia(&K, NULL, NULL, 2.0 + 1e-3, &nb, &nz, &d), WR_OK, "%s", d.message);
    cr_assert_eq(nz, 0);
    cr_assert_eq(nb, 2);
    wr_csr_free(&K);
}
