/* Unit tests for wrinkle/core.h: status strings, diagnostics, allocation, RNG, atomic files and the
 * small linear algebra (closed-form 2×2 eigen, Jacobi eigen-solver, SPD projection). */
#include <criterion/criterion.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "wrinkle/core.h"

Test(core, status_strings_cover_every_code) {
    int s;
    cr_assert_eq(WR_OK, 0);
    for (s = 0; s < WR_STATUS_COUNT; ++s) {
        cr_assert(strncmp(wr_status_string((wr_status)s), "WR_", 3) == 0);
        cr_assert(strlen(wr_status_text((wr_status)s)) > 0);
        cr_assert(strcmp(wr_status_string((wr_status)s), "WR_STATUS_UNKNOWN") != 0);
    }
    cr_assert_str_eq(wr_status_string(WR_ERR_PARSE), "WR_ERR_PARSE");
    cr_assert_str_eq(wr_status_string((wr_status)999), "WR_STATUS_UNKNOWN");
}

Test(core, fail_fills_diag_and_tolerates_null) {
    wr_diag d;
    memset(&d, 0, sizeof d);
    cr_assert_eq(wr_fail(&d, WR_ERR_DOMAIN, 7, "B=%g out of range", 2.5), WR_ERR_DOMAIN);
    cr_assert_eq(d.status, WR_ERR_DOMAIN);
    cr_assert_eq(d.item, 7);
    cr_assert_str_eq(d.message, "B=2.5 out of range");
    cr_assert_eq(wr_fail(NULL, WR_ERR_IO, -1, "x"), WR_ERR_IO);
}

Test(core, fail_truncates_long_messages) {
    wr_diag d;
    char big[2000];
    memset(big, 'a', sizeof big - 1);
    big[sizeof big - 1] = 0;
    wr_fail(&d, WR_ERR_PARSE, -1, "%s", big);
    cr_assert_eq(strlen(d.message), WR_DIAG_MESSAGE_LEN - 1);
}

Test(core, alloc_rejects_overflow_and_accepts_zero) {
    void *p = wr_alloc_array(SIZE_MAX / 2, 4);
    cr_assert_null(p);
    cr_assert_null(wr_realloc_array(NULL, SIZE_MAX / 8 + 1, 16));
    p = wr_alloc_array(0, 8);
    cr_assert_not_null(p);
    wr_free(p);
    p = wr_calloc_array(10, sizeof(double));
    cr_assert_not_null(p);
    cr_assert_eq(((double *)p)[9], 0.0);
    wr_free(p);
    wr_free(NULL);
}

Test(core, rng_is_deterministic_and_seed_dependent) {
    wr_rng a, b, c;
    int i, same = 1, differ = 0;
    wr_rng_seed(&a, 42);
    wr_rng_seed(&b, 42);
    wr_rng_seed(&c, 43);
    for (i = 0; i < 1000; ++i) {
        uint64_t x = wr_rng_u64(&a), y = wr_rng_u64(&b), z = wr_rng_u64(&c);
        same &= x == y;
        differ |= x != z;
    }
    cr_assert(same);
    cr_assert(differ);
}

Test(core, rng_uniform_moments_and_range) {
    wr_rng r;
    double s = 0, s2 = 0, n = 200000, lo = 1, hi = 0;
    int i;
    wr_rng_seed(&r, 7);
    for (i = 0; i < (int)n; ++i) {
        double u = wr_rng_uniform(&r);
        s += u;
        s2 += u * u;
        lo = fmin(lo, u);
        hi = fmax(hi, u);
    }
    cr_assert(lo >= 0.0 && hi < 1.0);
    /* mean 1/2, variance 1/12; 5-sigma bands for n = 2e5 */
    cr_assert(fabs(s / n - 0.5) < 5 * sqrt(1.0 / 12.0 / n));
    cr_assert(fabs(s2 / n - s * s / n / n - 1.0 / 12.0) < 2e-3);
}

Test(core, rng_normal_moments) {
    wr_rng r;
    double s = 0, s2 = 0, n = 200000;
    int i;
    wr_rng_seed(&r, 11);
    for (i = 0; i < (int)n; ++i) {
        double g = wr_rng_normal(&r);
        s += g;
        s2 += g * g;
    }
    cr_assert(fabs(s / n) < 5.0 / sqrt(n));
    cr_assert(fabs(s2 / n - 1.0) < 0.02);
}

Test(core, rng_below_is_in_range_and_uniform) {
    wr_rng r;
    int counts[7] = {0}, i;
    wr_rng_seed(&r, 3);
    for (i = 0; i < 70000; ++i) {
        uint32_t k = wr_rng_below(&r, 7);
        cr_assert(k < 7);
        counts[k]++;
    }
    for (i = 0; i < 7; ++i) cr_assert(abs(counts[i] - 10000) < 500, "bucket %d: %d", i, counts[i]);
}

Test(core, afile_commit_replaces_atomically) {
    const char *path = "build/test/afile_probe.txt";
    wr_afile f;
    wr_diag d;
    FILE *in;
    char buf[64] = {0};
    cr_assert_eq(wr_afile_open(&f, path, &d), WR_OK, "%s", d.message);
    fputs("first\n", f.fp);
    cr_assert_eq(wr_afile_commit(&f, &d), WR_OK);
    /* an aborted second write leaves the first file whole and no temporary behind */
    cr_assert_eq(wr_afile_open(&f, path, &d), WR_OK);
    fputs("second, never committed\n", f.fp);
    {
        char tmp[sizeof f.tmp];
        memcpy(tmp, f.tmp, sizeof tmp);
        wr_afile_abort(&f);
        cr_assert_null(fopen(tmp, "r"));
    }
    in = fopen(path, "r");
    cr_assert_not_null(in);
    cr_assert_not_null(fgets(buf, sizeof buf, in));
    fclose(in);
    cr_assert_str_eq(buf, "first\n");
    remove(path);
}

Test(core, afile_reports_unwritable_directory) {
    wr_afile f;
    wr_diag d;
    cr_assert_eq(wr_afile_open(&f, "no/such/dir/out.txt", &d), WR_ERR_IO);
    cr_assert(strstr(d.message, "no/such/dir/out.txt") != NULL);
    cr_assert_eq(wr_afile_open(&f, "", &d), WR_ERR_INVALID_ARG);
}

Test(core, vec_and_mat_basics) {
    wr_vec3 a = wr_v3(1, 2, 3), b = wr_v3(-2, 0.5, 4);
    wr_vec3 c = wr_v3_cross(a, b);
    wr_mat3 M, Mi, I;
    int i, j;
    cr_assert_float_eq(wr_v3_dot(c, a), 0.0, 1e-12);
    cr_assert_float_eq(wr_v3_dot(c, b), 0.0, 1e-12);
    cr_assert_float_eq(wr_v3_norm(wr_v3_normalized(b)), 1.0, 1e-15);
    cr_assert_eq(wr_v3_norm(wr_v3_normalized(wr_v3(0, 0, 0))), 0.0);
    M = wr_m3_identity();
    M.m[0][1] = 2;
    M.m[2][0] = -1;
    M.m[1][2] = 0.25; /* det = 0.5 */
    cr_assert(wr_m3_inverse(M, &Mi));
    I = wr_m3_mul(M, Mi);
    for (i = 0; i < 3; ++i)
        for (j = 0; j < 3; ++j) cr_assert_float_eq(I.m[i][j], i == j ? 1.0 : 0.0, 1e-14);
    M.m[0][0] = M.m[0][1] = M.m[0][2] = 0;
    cr_assert_not(wr_m3_inverse(M, &Mi));
}

Test(core, m2_inverse_and_singular) {
    wr_mat2 A = wr_m2(4, 1, 2, 3), Ai, P;
    cr_assert(wr_m2_inverse(A, &Ai));
    P = wr_m2_mul(A, Ai);
    cr_assert_float_eq(P.m[0][0], 1, 1e-15);
    cr_assert_float_eq(P.m[0][1], 0, 1e-15);
    cr_assert_float_eq(P.m[1][0], 0, 1e-15);
    cr_assert_float_eq(P.m[1][1], 1, 1e-15);
    cr_assert_not(wr_m2_inverse(wr_m2(1, 2, 2, 4), &Ai));
}

static void check_sym_eig(wr_mat2 A) {
    double lam[2];
    wr_vec2 v[2];
    int k;
    wr_m2_sym_eig(A, lam, v);
    cr_assert(lam[0] <= lam[1]);
    for (k = 0; k < 2; ++k) {
        wr_vec2 Av = wr_m2_mulv(A, v[k]);
        double scale = 1.0 + fabs(lam[0]) + fabs(lam[1]);
        cr_assert_float_eq(wr_v2_norm(v[k]), 1.0, 1e-14);
        cr_assert(fabs(Av.x - lam[k] * v[k].x) < 1e-13 * scale);
        cr_assert(fabs(Av.y - lam[k] * v[k].y) < 1e-13 * scale);
    }
    /* right-handed pair */
    cr_assert_float_eq(wr_v2_cross(v[0], v[1]), 1.0, 1e-14);
}

Test(core, m2_sym_eig_random_and_degenerate) {
    wr_rng r;
    int i;
    wr_rng_seed(&r, 5);
    for (i = 0; i < 1000; ++i) {
        double off = wr_rng_normal(&r);
        check_sym_eig(wr_m2(wr_rng_normal(&r), off, off, wr_rng_normal(&r)));
    }
    check_sym_eig(wr_m2(2, 0, 0, 2));     /* repeated eigenvalue */
    check_sym_eig(wr_m2(1, 1e-17, 1e-17, 1)); /* nearly repeated */
    check_sym_eig(wr_m2(-3, 0, 0, 5));
    check_sym_eig(wr_m2(5, 0, 0, -3)); /* diagonal, descending */
    check_sym_eig(wr_m2(0, 0, 0, 0));
}

Test(core, dense_sym_eig_reconstructs) {
    wr_rng r;
    int n, t;
    wr_rng_seed(&r, 9);
    for (t = 0; t < 20; ++t)
        for (n = 1; n <= 18; n += (n < 4 ? 1 : 7)) {
            double A[18 * 18], V[18 * 18], lam[18];
            int i, j, k;
            for (i = 0; i < n; ++i)
                for (j = 0; j <= i; ++j) A[i * n + j] = A[j * n + i] = wr_rng_normal(&r);
            wr_dense_sym_eig(n, A, lam, V);
            for (k = 1; k < n; ++k) cr_assert(lam[k - 1] <= lam[k]);
            for (i = 0; i < n; ++i)
                for (j = 0; j < n; ++j) {
                    double s = 0, o = 0;
                    for (k = 0; k < n; ++k) {
                        s += V[i * n + k] * lam[k] * V[j * n + k];
                        o += V[k * n + i] * V[k * n + j];
                    }
                    cr_assert(fabs(s - A[i * n + j]) < 1e-12 * n, "reconstruction n=%d", n);
                    cr_assert(fabs(o - (i == j)) < 1e-12 * n, "orthonormality n=%d", n);
                }
        }
}

Test(core, project_spd_clamps_negative_eigenvalues_only) {
    double A[9] = {1, 2, 0, 2, 1, 0, 0, 0, 3}; /* eigenvalues -1, 3, 3 */
    double B[9], lam[3];
    int raised;
    memcpy(B, A, sizeof A);
    raised = wr_dense_project_spd(3, B, 0.0);
    cr_assert_eq(raised, 1);
    wr_dense_sym_eig(3, B, lam, NULL);
    cr_assert_float_eq(lam[0], 0.0, 1e-13);
    cr_assert_float_eq(lam[1], 3.0, 1e-13);
    cr_assert_float_eq(lam[2], 3.0, 1e-13);
    /* an SPD matrix is left bit-for-bit alone */
    {
        double S[4] = {2, 1, 1, 2}, S0[4];
        memcpy(S0, S, sizeof S);
        cr_assert_eq(wr_dense_project_spd(2, S, 1e-12), 0);
        cr_assert_eq(memcmp(S, S0, sizeof S), 0);
    }
}

Test(core, time_is_monotone_enough) {
    double t0 = wr_time_seconds(), t1 = wr_time_seconds();
    cr_assert(t1 >= t0);
    cr_assert(t0 > 1.6e9); /* seconds since the epoch: after 2020 */
}

Test(core, polygon_area_sign_and_far_from_origin) {
    const double sq[8] = {0, 0, 2, 0, 2, 1, 0, 1}, cw[8] = {0, 0, 0, 1, 2, 1, 2, 0};
    const double tri[6] = {1, 1, 4, 1, 1, 5};
    const double o = 1e7, s = 1e-3;
    double far[8], sx;
    cr_expect_eq(wr_polygon_area(sq, 4), 2.0);
    cr_expect_eq(wr_polygon_area(cw, 4), -2.0);
    cr_expect_eq(wr_polygon_area(tri, 3), 6.0);
    cr_expect_eq(wr_polygon_area(sq, 2), 0.0);
    cr_expect_eq(wr_polygon_area(sq, 0), 0.0);
    /* a 1 mm square 1e7 m away: the origin-based shoelace cancels to garbage (terms ~1e14 m²);
     * about the first vertex the result is the exact square of the representable side */
    far[0] = o, far[1] = o, far[2] = o + s, far[3] = o, far[4] = o + s, far[5] = o + s, far[6] = o, far[7] = o + s;
    sx = (o + s) - o;
    cr_expect_eq(wr_polygon_area(far, 4), sx * sx);
}

Test(core, point_in_polygon_nonconvex_and_degenerate) {
    /* L shape: [0,2]x[0,1] plus [0,1]x[1,2], counter-clockwise */
    const double L[12] = {0, 0, 2, 0, 2, 1, 1, 1, 1, 2, 0, 2};
    cr_expect_eq(wr_point_in_polygon(L, 6, 0.5, 0.5), 1);
    cr_expect_eq(wr_point_in_polygon(L, 6, 1.5, 0.5), 1);
    cr_expect_eq(wr_point_in_polygon(L, 6, 0.5, 1.5), 1);
    cr_expect_eq(wr_point_in_polygon(L, 6, 1.5, 1.5), 0); /* the notch */
    cr_expect_eq(wr_point_in_polygon(L, 6, -0.5, 0.5), 0);
    cr_expect_eq(wr_point_in_polygon(L, 6, 0.5, 1.0), 1);  /* level with a vertex: half-open rule */
    cr_expect_eq(wr_point_in_polygon(L, 6, 2.5, 1.0), 0);
    cr_expect_eq(wr_point_in_polygon(L, 2, 0.5, 0.5), 0);
}

Test(core, segment_distance_known_values) {
    const double a[2] = {0, 0}, b[2] = {4, 0}, c[2] = {1, 1};
    double p[2], t;
    p[0] = 1, p[1] = 3;
    cr_expect_eq(wr_segment_distance(p, a, b, &t), 3.0);
    cr_expect_eq(t, 0.25);
    p[0] = -3, p[1] = 4;
    cr_expect_eq(wr_segment_distance(p, a, b, &t), 5.0); /* beyond a: distance to the end point */
    cr_expect_eq(t, 0.0);
    p[0] = 7, p[1] = -4;
    cr_expect_eq(wr_segment_distance(p, a, b, &t), 5.0);
    cr_expect_eq(t, 1.0);
    p[0] = 4, p[1] = 5;
    cr_expect_eq(wr_segment_distance(p, c, c, &t), 5.0); /* zero-length segment = point */
    cr_expect_eq(t, 0.0);
    p[0] = 2, p[1] = 2;
    cr_expect_eq(wr_segment_distance(p, a, c, NULL), sqrt(2.0));
    /* on the line y = x/2 through a skew segment (every coordinate exactly on it: halving is exact):
     * the projected-point form leaves 5e-16 m here, the cross-product form gives exactly 0 */
    {
        double s0[2], s1[2];
        s0[0] = 0.1 * 7.0, s0[1] = 0.5 * s0[0];
        s1[0] = s0[0] + 3.0, s1[1] = 0.5 * s1[0];
        p[0] = s0[0] + 1.1, p[1] = 0.5 * p[0];
        cr_assert_eq((s1[0] - s0[0]) * (p[1] - s0[1]) - (s1[1] - s0[1]) * (p[0] - s0[0]), 0.0);
        cr_expect_eq(wr_segment_distance(p, s0, s1, &t), 0.0);
        cr_expect(t > 0.0 && t < 1.0);
    }
}

/* Whole-file read: contents and length exact past the first 64 KiB chunk, NUL appended, embedded
 * NUL kept, empty file, and the error paths naming the path. */
Test(core, file_read_round_trip_and_errors) {
    const char *path = "build/test/file_read_probe.bin";
    const size_t n = 200003; /* three buffer doublings */
    wr_afile f;
    wr_diag d;
    char *text = NULL;
    size_t len = 7, i;
    cr_assert_eq(wr_afile_open(&f, path, &d), WR_OK, "%s", d.message);
    for (i = 0; i < n; ++i) fputc(i == 1000 ? 0 : (int)('a' + i % 26), f.fp);
    cr_assert_eq(wr_afile_commit(&f, &d), WR_OK);
    cr_assert_eq(wr_file_read(path, &text, &len, &d), WR_OK, "%s", d.message);
    cr_assert_eq(len, n);
    cr_expect_eq(text[n], 0);
    cr_expect_eq(text[1000], 0);
    cr_expect_eq(strlen(text), 1000u); /* how a caller detects a binary file */
    for (i = 0; i < n; ++i)
        if (i != 1000 && text[i] != (char)('a' + i % 26)) break;
    cr_expect_eq(i, n, "first mismatch at byte %zu", i);
    wr_free(text);
    cr_assert_eq(wr_afile_open(&f, path, &d), WR_OK);
    cr_assert_eq(wr_afile_commit(&f, &d), WR_OK);
    cr_assert_eq(wr_file_read(path, &text, NULL, &d), WR_OK);
    cr_expect_str_eq(text, "");
    wr_free(text);
    remove(path);
    text = (char *)&len;
    cr_expect_eq(wr_file_read("no/such/file.txt", &text, &len, &d), WR_ERR_IO);
    cr_expect_null(text);
    cr_expect_eq(len, 0u);
    cr_expect(strstr(d.message, "no/such/file.txt") != NULL, "%s", d.message);
    cr_expect_eq(wr_file_read(NULL, &text, &len, &d), WR_ERR_INVALID_ARG);
    cr_expect_eq(wr_file_read(path, NULL, &len, &d), WR_ERR_INVALID_ARG);
}
