/* bench_collision: the collision.h broad phase against primitive count, 1e3 to 1e6 triangles, on a
 * sheet folded onto itself (two layers 2 edge lengths apart, so the self query reports the pairs a
 * cloth simulator sees). Per size: BVH build, refit (after a small deformation), self-pair query of
 * the face boxes grown by d̂ = h/2 (h the edge length), and, as the same-run peer, a uniform
 * spatial hash (cell = the mean box extent, pairs deduplicated by their lowest shared cell) doing
 * the same query; both must report the same pair count. Then the whole contact detection
 * (wr_collision_contacts: PT + EE, narrow phase included) and one CCD step (wr_collision_max_step)
 * up to 1e5 triangles. CPU seconds (clock()), median of 5 runs (3 at 1e6). Single-threaded. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "wrinkle/collision.h"

static double cpu(void) { return (double)clock() / CLOCKS_PER_SEC; }

static int cmp_d(const void *a, const void *b) {
    double x = *(const double *)a, y = *(const double *)b;
    return x < y ? -1 : x > y;
}

static double median(double *v, int n) {
    qsort(v, (size_t)n, sizeof(double), cmp_d);
    return v[n / 2];
}

/* folded sheet: (u, v) in [0,1]², x = 0.5 − |u − 0.5|, z rises by 2h across the fold */
static void sheet(int32_t N, double phase, double **x, int32_t **f, int32_t *nv, int32_t *nf) {
    int32_t i, j, q = 0;
    double h = 1.0 / N;
    *nv = (N + 1) * (N + 1);
    *nf = 2 * N * N;
    *x = (double *)malloc(sizeof(double) * 3 * (size_t)*nv);
    *f = (int32_t *)malloc(sizeof(int32_t) * 3 * (size_t)*nf);
    for (j = 0; j <= N; ++j)
        for (i = 0; i <= N; ++i) {
            double u = (double)i / N, v = (double)j / N, *p = *x + 3 * (j * (N + 1) + i);
            p[0] = 0.5 - fabs(u - 0.5);
            p[1] = v;
            p[2] = 2.0 * h * (0.5 + 0.5 * tanh((u - 0.5) / (2.0 * h))) + 0.1 * h * sin(7.0 * v + phase);
        }
    for (j = 0; j < N; ++j)
        for (i = 0; i < N; ++i) {
            int32_t a = j * (N + 1) + i, t[6] = {a, a + 1, a + N + 2, a, a + N + 2, a + N + 1};
            memcpy(*f + 3 * q, t, sizeof t);
            q += 2;
        }
}

static void face_boxes(const double *x, const int32_t *f, int32_t nf, double pad, double *bx) {
    int32_t i;
    int k, a;
    for (i = 0; i < nf; ++i) {
        double *b = bx + 6 * i;
        for (a = 0; a < 3; ++a) {
            b[a] = HUGE_VAL;
            b[3 + a] = -HUGE_VAL;
        }
        for (k = 0; k < 3; ++k)
            for (a = 0; a < 3; ++a) {
                double c = x[3 * f[3 * i + k] + a];
                if (c - pad < b[a]) b[a] = c - pad;
                if (c + pad > b[3 + a]) b[3 + a] = c + pad;
            }
    }
}

static wr_status count_pair(void *u, int32_t i, int32_t j) {
    (void)i;
    (void)j;
    ++*(long *)u;
    return WR_OK;
}

/* ---- the peer: a uniform spatial hash (bench-only) ---- */
typedef struct hash_entry {
    int64_t cell;
    int32_t prim;
} hash_entry;

static int cmp_entry(const void *a, const void *b) {
    const hash_entry *x = (const hash_entry *)a, *y = (const hash_entry *)b;
    return x->cell < y->cell ? -1 : (x->cell > y->cell ? 1 : (x->prim - y->prim));
}

static int64_t cell_key(int64_t i, int64_t j, int64_t k) { return (i << 42) ^ (j << 21) ^ k; }

static int ov(const double *a, const double *b) {
    return a[0] <= b[3] && b[0] <= a[3] && a[1] <= b[4] && b[1] <= a[4] && a[2] <= b[5] && b[2] <= a[5];
}

/* Sort-based hash (a sorted cell list is a perfect hash): every box goes into each cell it covers;
 * within a cell all overlapping pairs are reported once, by the lowest cell both boxes cover. */
static long hash_pairs(int32_t n, const double *bx, double *seconds) {
    double t0 = cpu(), ext = 0.0, cs, lo[3] = {HUGE_VAL, HUGE_VAL, HUGE_VAL};
    int32_t i, ne = 0, cap = 8 * n, s, e, a;
    hash_entry *E = (hash_entry *)malloc(sizeof(hash_entry) * (size_t)cap);
    long pairs = 0;
    for (i = 0; i < n; ++i)
        for (a = 0; a < 3; ++a) {
            ext += bx[6 * i + 3 + a] - bx[6 * i + a];
            if (bx[6 * i + a] < lo[a]) lo[a] = bx[6 * i + a];
        }
    cs = ext / (3.0 * n);
    for (i = 0; i < n; ++i) {
        int64_t c0[3], c1[3], p, q, r;
        for (a = 0; a < 3; ++a) {
            c0[a] = (int64_t)floor((bx[6 * i + a] - lo[a]) / cs);
            c1[a] = (int64_t)floor((bx[6 * i + 3 + a] - lo[a]) / cs);
        }
        for (p = c0[0]; p <= c1[0]; ++p)
            for (q = c0[1]; q <= c1[1]; ++q)
                for (r = c0[2]; r <= c1[2]; ++r) {
                    if (ne == cap) {
                        cap *= 2;
                        E = (hash_entry *)realloc(E, sizeof(hash_entry) * (size_t)cap);
                    }
                    E[ne].cell = cell_key(p, q, r);
                    E[ne].prim = i;
                    ++ne;
                }
    }
    qsort(E, (size_t)ne, sizeof(hash_entry), cmp_entry);
    for (s = 0; s < ne; s = e) {
        int32_t u, v;
        for (e = s; e < ne && E[e].cell == E[s].cell; ++e) {
        }
        for (u = s; u < e; ++u)
            for (v = u + 1; v < e; ++v) {
                const double *A = bx + 6 * E[u].prim, *B = bx + 6 * E[v].prim;
                double m[3];
                int64_t lc[3];
                if (!ov(A, B)) continue;
                /* report only in the lowest cell of the overlap box */
                for (a = 0; a < 3; ++a) {
                    m[a] = A[a] > B[a] ? A[a] : B[a];
                    lc[a] = (int64_t)floor((m[a] - lo[a]) / cs);
                }
                if (cell_key(lc[0], lc[1], lc[2]) == E[s].cell) ++pairs;
            }
    }
    free(E);
    *seconds = cpu() - t0;
    return pairs;
}

int main(void) {
    static const int32_t Ns[4] = {22, 71, 224, 707};
    int s;
    printf("bench_collision: folded sheet, d-hat = h/2; CPU s, median of 5 (3 at 1e6); single thread\n");
    printf("%9s %9s | %8s %8s %8s %9s | %8s %9s %6s | %8s %8s %8s\n", "faces", "pairs", "build", "refit", "query",
           "b+q", "hash", "hash/bvh", "same", "contacts", "n_cont", "ccd");
    for (s = 0; s < 4; ++s) {
        int32_t N = Ns[s], nv, nf, r, runs = N > 500 ? 3 : 5, i;
        double *x, *x2, *bx, tb[5], tr[5], tq[5], th[5], tc[5], tk[5], h = 1.0 / N;
        int32_t *f, *f2;
        long pairs = 0, hp = 0;
        int same;
        wr_bvh t;
        sheet(N, 0.0, &x, &f, &nv, &nf);
        sheet(N, 0.3, &x2, &f2, &nv, &nf);
        bx = (double *)malloc(sizeof(double) * 6 * (size_t)nf);
        for (r = 0; r < runs; ++r) {
            double t0;
            face_boxes(x, f, nf, 0.25 * h, bx);
            t0 = cpu();
            if (wr_bvh_build(&t, nf, bx, NULL) != WR_OK) return 1;
            tb[r] = cpu() - t0;
            face_boxes(x2, f, nf, 0.25 * h, bx);
            t0 = cpu();
            wr_bvh_refit(&t, bx);
            tr[r] = cpu() - t0;
            pairs = 0;
            t0 = cpu();
            if (wr_bvh_self_pairs(&t, count_pair, &pairs, NULL) != WR_OK) return 1;
            tq[r] = cpu() - t0;
            wr_bvh_free(&t);
            hp = hash_pairs(nf, bx, &th[r]);
        }
        same = hp == pairs;
        {
            double mb = median(tb, runs), mr = median(tr, runs), mq = median(tq, runs), mh = median(th, runs);
            double mc = 0.0, mk = 0.0;
            int32_t ncont = 0;
            if (nf <= 200000) {
                wr_collision_mesh cm;
                wr_contact_set cs;
                double *dx = (double *)calloc(3 * (size_t)nv, sizeof(double)), alpha;
                memset(&cs, 0, sizeof cs);
                if (wr_collision_mesh_create(&cm, nv, nf, f, NULL, NULL, NULL) != WR_OK) return 1;
                for (i = 0; i < nv; ++i) dx[3 * i + 2] = x2[3 * i + 2] - x[3 * i + 2];
                for (r = 0; r < runs; ++r) {
                    double t0 = cpu();
                    if (wr_collision_contacts(&cm, x, 0.5 * h, &cs, NULL) != WR_OK) return 1;
                    tc[r] = cpu() - t0;
                    t0 = cpu();
                    if (wr_collision_max_step(&cm, x, dx, &alpha, NULL, NULL) != WR_OK) return 1;
                    tk[r] = cpu() - t0;
                }
                ncont = cs.n;
                mc = median(tc, runs);
                mk = median(tk, runs);
                wr_contact_set_free(&cs);
                wr_collision_mesh_free(&cm);
                free(dx);
            }
            printf("%9d %9ld | %8.4f %8.4f %8.4f %9.4f | %8.4f %9.2f %6s | %8.4f %8d %8.4f\n", (int)nf, pairs, mb, mr,
                   mq, mb + mq, mh, mh / (mb + mq), same ? "yes" : "NO", mc, (int)ncont, mk);
        }
        free(x);
        free(x2);
        free(f);
        free(f2);
        free(bx);
        if (!same) return 1;
    }
    return 0;
}
