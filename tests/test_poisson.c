/* Tests for poisson.h: minimum-distance rule (brute force), coverage on a probe lattice, determinism,
 * fixed points and constraint segments, holes and polylines, every error path, and the calibration
 * of radius_factor against the mean edge length of a Delaunay triangulation of the output (a small
 * Bowyer–Watson written here, test-only). */
#include <criterion/criterion.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "wrinkle/poisson.h"

#define WRT_PI 3.14159265358979323846

static double size_const(void *u, double x, double y) {
    (void)x;
    (void)y;
    return *(const double *)u;
}
/* 20× graded along x on [0, 1]: h = h0 (1 + 19 x) */
static double size_ramp(void *u, double x, double y) {
    (void)y;
    return *(const double *)u * (1.0 + 19.0 * x);
}

static const double SQUARE[8] = {0, 0, 1, 0, 1, 1, 0, 1};

static void dom_square(wr_poisson_domain *dom) {
    memset(dom, 0, sizeof *dom);
    dom->outer.xy = SQUARE;
    dom->outer.n = 4;
}

static double r_of(const wr_poisson_result *res, int32_t i) { return WR_POISSON_DEFAULT_RADIUS_FACTOR * res->sizing[i]; }

/* Every pair with at least one interior sample satisfies |p-q| >= (r_p + r_q)/2; returns min ratio. */
static double min_distance_ratio(const wr_poisson_result *res) {
    double worst = HUGE_VAL;
    int32_t i, j;
    for (i = 0; i < res->n_points; ++i)
        for (j = (i + 1 > res->n_fixed ? i + 1 : res->n_fixed); j < res->n_points; ++j) {
            double dx = res->points[2 * i] - res->points[2 * j], dy = res->points[2 * i + 1] - res->points[2 * j + 1];
            double q = sqrt(dx * dx + dy * dy) / (0.5 * (r_of(res, i) + r_of(res, j)));
            if (q < worst) worst = q;
        }
    return worst;
}

/* crossing-number test against the loops (owners 0..n_holes) of the result's segments */
static int inside_loops(const wr_poisson_result *res, int32_t n_holes, double x, double y) {
    int32_t s, in = 0;
    for (s = 0; s < res->n_segments; ++s) {
        const double *a, *b;
        if (res->segment_owner[s] > n_holes) continue;
        a = res->points + 2 * res->segments[2 * s];
        b = res->points + 2 * res->segments[2 * s + 1];
        if ((a[1] > y) != (b[1] > y) && a[0] + (y - a[1]) * (b[0] - a[0]) / (b[1] - a[1]) > x) in ^= 1;
    }
    return in;
}

/* Largest (distance to nearest sample) / r(probe) over an m×m probe lattice inside the domain. */
static double coverage_ratio(const wr_poisson_result *res, int32_t n_holes, wr_poisson_sizing_fn fn, void *user,
                             double x0, double y0, double W, double H, int m) {
    double worst = 0.0;
    int a, b;
    int32_t i;
    for (b = 0; b < m; ++b)
        for (a = 0; a < m; ++a) {
            double x = x0 + (a + 0.5) * W / m, y = y0 + (b + 0.5) * H / m, best = HUGE_VAL;
            if (!inside_loops(res, n_holes, x, y)) continue;
            for (i = 0; i < res->n_points; ++i) {
                double dx = res->points[2 * i] - x, dy = res->points[2 * i + 1] - y, d = dx * dx + dy * dy;
                if (d < best) best = d;
            }
            best = sqrt(best) / (WR_POISSON_DEFAULT_RADIUS_FACTOR * fn(user, x, y));
            if (best > worst) worst = best;
        }
    return worst;
}

/* ---- test-only Bowyer–Watson (naive O(n²)) ------------------------------------------------- */
typedef struct bw_tri {
    int32_t v[3];
    double cx, cy, r2;
    int alive;
} bw_tri;

static void bw_circ(bw_tri *t, const double *P) {
    const double *a = P + 2 * t->v[0], *b = P + 2 * t->v[1], *c = P + 2 * t->v[2];
    double bx = b[0] - a[0], by = b[1] - a[1], cx = c[0] - a[0], cy = c[1] - a[1];
    double d = 2.0 * (bx * cy - by * cx), ux, uy;
    ux = (cy * (bx * bx + by * by) - by * (cx * cx + cy * cy)) / d;
    uy = (bx * (cx * cx + cy * cy) - cx * (bx * bx + by * by)) / d;
    t->cx = a[0] + ux;
    t->cy = a[1] + uy;
    t->r2 = ux * ux + uy * uy;
}

static int cmp_edge(const void *a, const void *b) {
    const int32_t *x = (const int32_t *)a, *y = (const int32_t *)b;
    if (x[0] != y[0]) return x[0] < y[0] ? -1 : 1;
    return x[1] < y[1] ? -1 : (x[1] > y[1]);
}

/* Delaunay edges of pts (n×2); returns edge count, *edges (m×2, i<j) malloc'd. */
static int32_t bw_edges(const double *pts, int32_t n, int32_t **edges_out) {
    double *P = (double *)malloc(sizeof(double) * 2 * (size_t)(n + 3));
    int32_t cap = 4 * n + 16, nt = 0, i, j, k, *bad = (int32_t *)malloc(sizeof(int32_t) * (size_t)cap);
    int32_t *poly = (int32_t *)malloc(sizeof(int32_t) * 2 * (size_t)cap), ne = 0, *E;
    bw_tri *T = (bw_tri *)malloc(sizeof(bw_tri) * (size_t)(2 * n + 16));
    double x0 = HUGE_VAL, y0 = HUGE_VAL, x1 = -HUGE_VAL, y1 = -HUGE_VAL, D;
    memcpy(P, pts, sizeof(double) * 2 * (size_t)n);
    for (i = 0; i < n; ++i) {
        x0 = fmin(x0, P[2 * i]);
        x1 = fmax(x1, P[2 * i]);
        y0 = fmin(y0, P[2 * i + 1]);
        y1 = fmax(y1, P[2 * i + 1]);
    }
    D = 20.0 * fmax(x1 - x0, y1 - y0);
    P[2 * n] = x0 - D;
    P[2 * n + 1] = y0 - D;
    P[2 * n + 2] = x0 + 3 * D;
    P[2 * n + 3] = y0 - D;
    P[2 * n + 4] = x0 - D;
    P[2 * n + 5] = y0 + 3 * D;
    T[0].v[0] = n;
    T[0].v[1] = n + 1;
    T[0].v[2] = n + 2;
    T[0].alive = 1;
    bw_circ(&T[0], P);
    nt = 1;
    for (i = 0; i < n; ++i) {
        double x = P[2 * i], y = P[2 * i + 1];
        int32_t nb = 0, np = 0;
        for (j = 0; j < nt; ++j)
            if (T[j].alive) {
                double dx = x - T[j].cx, dy = y - T[j].cy;
                if (dx * dx + dy * dy < T[j].r2) bad[nb++] = j;
            }
        for (j = 0; j < nb; ++j)
            for (k = 0; k < 3; ++k) {
                int32_t a = T[bad[j]].v[k], b = T[bad[j]].v[(k + 1) % 3], shared = 0, jj, kk;
                for (jj = 0; jj < nb && !shared; ++jj)
                    if (jj != j)
                        for (kk = 0; kk < 3; ++kk)
                            if (T[bad[jj]].v[kk] == b && T[bad[jj]].v[(kk + 1) % 3] == a) shared = 1;
                if (!shared) {
                    poly[2 * np] = a;
                    poly[2 * np + 1] = b;
                    ++np;
                }
            }
        for (j = 0; j < nb; ++j) T[bad[j]].alive = 0;
        /* reuse dead slots first */
        for (j = 0, k = 0; j < np; ++j) {
            while (k < nt && T[k].alive) ++k;
            {
                int32_t slot = k < nt ? k : nt++;
                T[slot].v[0] = poly[2 * j];
                T[slot].v[1] = poly[2 * j + 1];
                T[slot].v[2] = i;
                T[slot].alive = 1;
                bw_circ(&T[slot], P);
            }
        }
    }
    E = (int32_t *)malloc(sizeof(int32_t) * 6 * (size_t)nt);
    for (j = 0; j < nt; ++j)
        if (T[j].alive && T[j].v[0] < n && T[j].v[1] < n && T[j].v[2] < n)
            for (k = 0; k < 3; ++k) {
                int32_t a = T[j].v[k], b = T[j].v[(k + 1) % 3];
                E[2 * ne] = a < b ? a : b;
                E[2 * ne + 1] = a < b ? b : a;
                ++ne;
            }
    qsort(E, (size_t)ne, 2 * sizeof(int32_t), cmp_edge);
    for (i = 0, k = 0; i < ne; ++i)
        if (k == 0 || E[2 * i] != E[2 * k - 2] || E[2 * i + 1] != E[2 * k - 1]) {
            E[2 * k] = E[2 * i];
            E[2 * k + 1] = E[2 * i + 1];
            ++k;
        }
    free(P);
    free(bad);
    free(poly);
    free(T);
    *edges_out = E;
    return k;
}

/* mean over Delaunay edges with both ends interior of |e| / ((h_i + h_j)/2) */
static double mean_edge_ratio(const wr_poisson_result *res, int32_t *n_used) {
    int32_t *E, ne = bw_edges(res->points, res->n_points, &E), e, used = 0;
    double sum = 0.0;
    for (e = 0; e < ne; ++e) {
        int32_t i = E[2 * e], j = E[2 * e + 1];
        double dx, dy;
        if (i < res->n_fixed || j < res->n_fixed) continue;
        dx = res->points[2 * i] - res->points[2 * j];
        dy = res->points[2 * i + 1] - res->points[2 * j + 1];
        sum += sqrt(dx * dx + dy * dy) / (0.5 * (res->sizing[i] + res->sizing[j]));
        ++used;
    }
    free(E);
    *n_used = used;
    return sum / used;
}

/* ---------------------------------------------------------------------------------------------- */
Test(poisson, constant_radius_min_distance_and_coverage) {
    wr_poisson_domain dom;
    wr_poisson_desc desc;
    wr_poisson_result res;
    wr_diag d;
    double h = 0.02, md, cov;
    dom_square(&dom);
    memset(&desc, 0, sizeof desc);
    desc.seed = 11;
    cr_assert_eq(wr_poisson_sample(&dom, size_const, &h, &desc, &res, &d), WR_OK, "%s", d.message);
    cr_assert_eq(res.n_fixed, 200, "4 sides of length 1 at h = 0.02 -> 200 boundary points, got %d", res.n_fixed);
    cr_assert_eq(res.n_segments, 200);
    md = min_distance_ratio(&res);
    cr_assert(md >= 1.0, "min distance ratio %.9f < 1", md);
    cov = coverage_ratio(&res, 0, size_const, &h, 0, 0, 1, 1, 100);
    /* maximal up to the failed-candidate arcs: no probe farther than r from every sample (a gap
     * left by a failed direction is narrower than r; 1.5 r leaves room for the boundary layer,
     * where the clearance keeps samples 0.35 h off the curves) */
    cr_assert(cov < 1.5, "largest empty disk %.3f r (bound 1.5 r)", cov);
    printf("[poisson] constant h=%.3g: n=%d (fixed %d), est=%d, min dist ratio %.6f, max empty/r %.3f\n", h,
           res.n_points, res.n_fixed, res.n_estimated, md, cov);
    wr_poisson_free(&res);
}

Test(poisson, graded_20x_min_distance_and_coverage) {
    wr_poisson_domain dom;
    wr_poisson_desc desc;
    wr_poisson_result res;
    wr_diag d;
    double h0 = 0.004, md, cov, hmin = HUGE_VAL, hmax = 0.0;
    int32_t i;
    dom_square(&dom);
    memset(&desc, 0, sizeof desc);
    desc.seed = 5;
    cr_assert_eq(wr_poisson_sample(&dom, size_ramp, &h0, &desc, &res, &d), WR_OK, "%s", d.message);
    for (i = 0; i < res.n_points; ++i) {
        cr_assert_float_eq(res.sizing[i], size_ramp(&h0, res.points[2 * i], res.points[2 * i + 1]), 1e-15);
        hmin = fmin(hmin, res.sizing[i]);
        hmax = fmax(hmax, res.sizing[i]);
    }
    cr_assert(hmax / hmin > 18.0, "sizing range %g", hmax / hmin);
    md = min_distance_ratio(&res);
    cr_assert(md >= 1.0, "min distance ratio %.9f < 1", md);
    cov = coverage_ratio(&res, 0, size_ramp, &h0, 0, 0, 1, 1, 120);
    cr_assert(cov < 1.5, "largest empty disk %.3f r (bound 1.5 r, see the constant-radius test)", cov);
    printf("[poisson] graded 20x: n=%d (fixed %d), est=%d, min dist ratio %.6f, max empty/r %.3f\n", res.n_points,
           res.n_fixed, res.n_estimated, md, cov);
    wr_poisson_free(&res);
}

/* Density constant κ (samples per r² of area) behind the budget estimate, and the estimate itself. */
Test(poisson, density_and_estimate) {
    wr_poisson_domain dom;
    wr_poisson_desc desc;
    wr_poisson_result res;
    wr_diag d;
    double h = 0.01, r = WR_POISSON_DEFAULT_RADIUS_FACTOR * h, kappa;
    dom_square(&dom);
    memset(&desc, 0, sizeof desc);
    desc.seed = 3;
    cr_assert_eq(wr_poisson_sample(&dom, size_const, &h, &desc, &res, &d), WR_OK, "%s", d.message);
    kappa = (double)(res.n_points - res.n_fixed) / (1.0 / (r * r));
    printf("[poisson] density kappa = %.4f samples per r^2 (constant h=%.3g, n=%d); estimate %d vs actual %d\n", kappa, h,
           res.n_points, res.n_estimated, res.n_points);
    /* 1 %: seed-to-seed spread of κ at this size is < 0.2 % */
    cr_assert(fabs(kappa - WR_POISSON_DENSITY) < 0.01 * WR_POISSON_DENSITY, "kappa %.4f vs constant %.4f", kappa,
              WR_POISSON_DENSITY);
    cr_assert(fabs((double)res.n_estimated / res.n_points - 1.0) < 0.1, "estimate %d vs %d", res.n_estimated,
              res.n_points);
    wr_poisson_free(&res);
}

/* The front cuts every neighbour's arc before its first draw (poisson.h, ON THE ALGORITHM), so at
 * constant sizing no candidate is wasted on a neighbour: every sizing evaluation of the fill is an
 * accepted sample (0.2 % allowed for rounding at arc ends and the clearance near the outline).
 * Measured: as many evaluations as samples (h = 0.01, seed 3); an arc left uncut (mutant
 * poisson-lens-wrap-uncut in tests/mutants.txt) costs 5.4 evaluations per sample. */
Test(poisson, constant_sizing_every_candidate_is_a_sample) {
    wr_poisson_domain dom;
    wr_poisson_desc desc;
    wr_poisson_result res;
    wr_diag d;
    double h = 0.01, per;
    dom_square(&dom);
    memset(&desc, 0, sizeof desc);
    desc.seed = 3;
    cr_assert_eq(wr_poisson_sample(&dom, size_const, &h, &desc, &res, &d), WR_OK, "%s", d.message);
    per = (double)res.n_candidates / (res.n_points - res.n_fixed);
    printf("[poisson] constant h=%.3g: %lld sizing evaluations for %d samples (%.4f per sample)\n", h,
           (long long)res.n_candidates, res.n_points - res.n_fixed, per);
    cr_assert(per <= 1.002, "%.4f sizing evaluations per sample at constant sizing", per);
    wr_poisson_free(&res);
}

/* On a graded sizing a candidate is placed at the mean-rule distance predicted from a sizing
 * gradient estimate carried along the front (poisson.h, wr__pz_activate), so the sizing is evaluated
 * about once per candidate instead of once more for every candidate that heads into coarser sizing.
 * Measured (20x ramp, h0 = 0.001, seed 3, ~60k samples): 1.09 evaluations per sample (the rest:
 * candidates refused by the full neighbour test, and the estimate's start at the outline, where it
 * is zero); 1.80 with the prediction disabled (mutant poisson-no-radius-prediction). */
Test(poisson, graded_sizing_about_one_evaluation_per_sample) {
    wr_poisson_domain dom;
    wr_poisson_desc desc;
    wr_poisson_result res;
    wr_diag d;
    double h0 = 0.001, per;
    dom_square(&dom);
    memset(&desc, 0, sizeof desc);
    desc.seed = 3;
    cr_assert_eq(wr_poisson_sample(&dom, size_ramp, &h0, &desc, &res, &d), WR_OK, "%s", d.message);
    per = (double)res.n_candidates / (res.n_points - res.n_fixed);
    printf("[poisson] 20x graded h0=%.3g: %lld sizing evaluations for %d samples (%.4f per sample)\n", h0,
           (long long)res.n_candidates, res.n_points - res.n_fixed, per);
    cr_assert(per <= 1.15, "%.4f sizing evaluations per sample on the 20x ramp", per);
    wr_poisson_free(&res);
}

/* radius_factor calibration: the mean Delaunay edge length / sizing within ±2 % of 1 (issue 20: a
 * band that sees a few-percent error; the mutant radius_factor × 1.078 gives +4.8 % / +8.5 %, see
 * bench/RESULTS.md), constant and 20×-graded sizing, over the Delaunay edges between interior
 * samples. Measured centre with 3 seeds: 0.9945 (constant h = 0.01) and 1.0016 (graded h0 =
 * 0.0025); seed-to-seed spread < 0.3 %, so ±2 % is the band of the requirement, not a fit. */
Test(poisson, calibration_mean_edge_matches_sizing) {
    wr_poisson_domain dom;
    wr_poisson_desc desc;
    wr_poisson_result res;
    wr_diag d;
    double h = 0.01, h0 = 0.0025, q1, q2;
    int32_t u1, u2;
    dom_square(&dom);
    memset(&desc, 0, sizeof desc);
    desc.seed = 21;
    cr_assert_eq(wr_poisson_sample(&dom, size_const, &h, &desc, &res, &d), WR_OK, "%s", d.message);
    q1 = mean_edge_ratio(&res, &u1);
    wr_poisson_free(&res);
    cr_assert_eq(wr_poisson_sample(&dom, size_ramp, &h0, &desc, &res, &d), WR_OK, "%s", d.message);
    q2 = mean_edge_ratio(&res, &u2);
    wr_poisson_free(&res);
    printf("[poisson] calibration radius_factor=%.3f: mean Delaunay edge / sizing = %.4f (constant, %d edges), "
           "%.4f (20x graded, %d edges)\n",
           WR_POISSON_DEFAULT_RADIUS_FACTOR, q1, u1, q2, u2);
    cr_assert(fabs(q1 - 1.0) <= 0.02, "constant: mean edge / sizing = %.4f", q1);
    cr_assert(fabs(q2 - 1.0) <= 0.02, "graded: mean edge / sizing = %.4f", q2);
}

/* mean over Delaunay edges joining a fixed point to a sample of |e| / ((h_i + h_j)/2), and the mean
 * height of those samples (the first ring) above the unit square's outline / own sizing */
static double first_ring_ratio(const wr_poisson_result *res, double *height, int32_t *n_used) {
    int32_t *E, ne = bw_edges(res->points, res->n_points, &E), e, i, used = 0, nr = 0;
    char *ring = (char *)calloc((size_t)res->n_points, 1);
    double sum = 0.0, hs = 0.0;
    for (e = 0; e < ne; ++e) {
        int32_t a = E[2 * e], b = E[2 * e + 1];
        if ((a < res->n_fixed) == (b < res->n_fixed)) continue;
        sum += hypot(res->points[2 * a] - res->points[2 * b], res->points[2 * a + 1] - res->points[2 * b + 1]) /
               (0.5 * (res->sizing[a] + res->sizing[b]));
        ++used;
        ring[a < res->n_fixed ? b : a] = 1;
    }
    for (i = res->n_fixed; i < res->n_points; ++i)
        if (ring[i]) {
            double x = res->points[2 * i], y = res->points[2 * i + 1];
            hs += fmin(fmin(x, 1.0 - x), fmin(y, 1.0 - y)) / res->sizing[i];
            ++nr;
        }
    free(E);
    free(ring);
    *height = hs / nr;
    *n_used = used;
    return sum / used;
}

/* fixed_distance calibration (header: ON THE FIRST RING): the mean Delaunay edge between the outline's
 * points and the first ring of samples / sizing within ±2 % of 1, the interior's target and band
 * (issue 20), constant and 20x-graded sizing. Measured with 3 seeds at D = 0.93: 0.995-1.001
 * (constant), 0.986 (graded); the interior rule there (D = c = 0.855) gives 0.93 / 0.92 and D = 1
 * about 1.07, both outside. The ring's mean height (0.85 h; 0.77 h under the interior rule) is
 * printed. */
Test(poisson, first_ring_calibration) {
    wr_poisson_domain dom;
    wr_poisson_desc desc;
    wr_poisson_result res;
    wr_diag d;
    double h = 0.01, h0 = 0.0025, q1, q2, t1, t2;
    int32_t u1, u2;
    dom_square(&dom);
    memset(&desc, 0, sizeof desc);
    desc.seed = 21;
    cr_assert_eq(wr_poisson_sample(&dom, size_const, &h, &desc, &res, &d), WR_OK, "%s", d.message);
    q1 = first_ring_ratio(&res, &t1, &u1);
    wr_poisson_free(&res);
    cr_assert_eq(wr_poisson_sample(&dom, size_ramp, &h0, &desc, &res, &d), WR_OK, "%s", d.message);
    q2 = first_ring_ratio(&res, &t2, &u2);
    wr_poisson_free(&res);
    printf("[poisson] first ring fixed_distance=%.3f: mean edge outline-sample / sizing = %.4f (constant, %d edges, "
           "ring height %.3f h), %.4f (20x graded, %d edges, ring height %.3f h)\n",
           WR_POISSON_DEFAULT_FIXED_DISTANCE, q1, u1, t1, q2, u2, t2);
    cr_assert(fabs(q1 - 1.0) <= 0.02, "constant: first-ring edge / sizing = %.4f", q1);
    cr_assert(fabs(q2 - 1.0) <= 0.02, "graded: first-ring edge / sizing = %.4f", q2);
}

Test(poisson, deterministic_for_seed) {
    wr_poisson_domain dom;
    wr_poisson_desc desc;
    wr_poisson_result a, b, c;
    wr_diag d;
    double h0 = 0.01;
    dom_square(&dom);
    memset(&desc, 0, sizeof desc);
    desc.seed = 99;
    cr_assert_eq(wr_poisson_sample(&dom, size_ramp, &h0, &desc, &a, &d), WR_OK, "%s", d.message);
    cr_assert_eq(wr_poisson_sample(&dom, size_ramp, &h0, &desc, &b, &d), WR_OK, "%s", d.message);
    desc.seed = 100;
    cr_assert_eq(wr_poisson_sample(&dom, size_ramp, &h0, &desc, &c, &d), WR_OK, "%s", d.message);
    cr_assert_eq(a.n_points, b.n_points);
    cr_assert(memcmp(a.points, b.points, sizeof(double) * 2 * (size_t)a.n_points) == 0, "same seed, different points");
    cr_assert(memcmp(a.sizing, b.sizing, sizeof(double) * (size_t)a.n_points) == 0);
    /* the fixed points do not depend on the seed; the interior does */
    cr_assert_eq(a.n_fixed, c.n_fixed);
    cr_assert(memcmp(a.points, c.points, sizeof(double) * 2 * (size_t)a.n_fixed) == 0);
    cr_assert(a.n_points != c.n_points ||
                  memcmp(a.points, c.points, sizeof(double) * 2 * (size_t)a.n_points) != 0,
              "different seeds gave identical samples");
    wr_poisson_free(&a);
    wr_poisson_free(&b);
    wr_poisson_free(&c);
}

/* point-to-segment distance */
static double seg_dist(const double *p, const double *a, const double *b) {
    double ex = b[0] - a[0], ey = b[1] - a[1], u = ((p[0] - a[0]) * ex + (p[1] - a[1]) * ey) / (ex * ex + ey * ey);
    double dx, dy;
    u = u < 0 ? 0 : (u > 1 ? 1 : u);
    dx = a[0] + u * ex - p[0];
    dy = a[1] + u * ey - p[1];
    return sqrt(dx * dx + dy * dy);
}

/* Pentagon panel 1.0 × 0.9 with a square hole and a 24-gon hole; an open wavy shirring line and a closed
 * circular seam; 4× graded sizing. Checks fixed points (order, exact corners/endpoints, on the input
 * curves, spacing ≈ h), segments and owners, interior samples inside the domain and off the holes. */
/* A strip thinner than the inside grid's cell rows (every cell of its boundary rows holds a long
 * edge): the inside test must answer from the short ray. Both orientations, brute-force inside check
 * of every interior sample and the largest empty disk over a probe lattice (a wrong inside test
 * either admits outside samples or starves the strip). Before the two-ray walk this strip's queries
 * walked whole rows (20k vertices of a 216 m x 0.1 mm strip: 5 s, now 0.1 s). */
Test(poisson, thin_strip_both_orientations) {
    double strip[8], h = 0.004, md, cov;
    wr_poisson_domain dom;
    wr_poisson_desc desc;
    wr_poisson_result res;
    wr_diag d;
    int32_t i, axis, n_in;
    for (axis = 0; axis < 2; ++axis) {
        double L = 3.0, w = 0.01;
        double xy[8] = {0, 0, L, 0, L, w, 0, w};
        for (i = 0; i < 4; ++i) {
            strip[2 * i + axis] = xy[2 * i];
            strip[2 * i + 1 - axis] = xy[2 * i + 1];
        }
        memset(&dom, 0, sizeof dom);
        dom.outer.xy = strip;
        dom.outer.n = 4;
        memset(&desc, 0, sizeof desc);
        desc.seed = 5;
        cr_assert_eq(wr_poisson_sample(&dom, size_const, &h, &desc, &res, &d), WR_OK, "%s", d.message);
        n_in = 0;
        for (i = res.n_fixed; i < res.n_points; ++i) {
            cr_assert(inside_loops(&res, 0, res.points[2 * i], res.points[2 * i + 1]), "axis %d: sample %d (%g, %g) outside",
                      axis, i, res.points[2 * i], res.points[2 * i + 1]);
            ++n_in;
        }
        cr_assert(n_in > 0, "axis %d: no interior samples", axis);
        cov = coverage_ratio(&res, 0, size_const, &h, 0, 0, axis ? w : L, axis ? L : w, 100);
        cr_assert(cov < 2.0, "axis %d: largest empty disk %.3f r (bound 2 r)", axis, cov);
        md = min_distance_ratio(&res);
        cr_assert(md >= 1.0, "axis %d: min distance ratio %.9f < 1", axis, md);
        wr_poisson_free(&res);
    }
}

Test(poisson, holes_and_polylines) {
    static double outer[10] = {0, 0, 1.0, 0, 1.0, 0.6, 0.5, 0.9, 0, 0.6}; /* pentagon, CCW, all corners > 30° */
    static double hole1[8] = {0.1, 0.1, 0.1, 0.25, 0.25, 0.25, 0.25, 0.1}; /* CW on purpose */
    double hole2[48], wave[2 * 41], seam[2 * 32];
    wr_poisson_curve holes[2], lines[2];
    wr_poisson_domain dom;
    wr_poisson_desc desc;
    wr_poisson_result res;
    wr_diag d;
    double h0 = 0.008, md;
    int32_t i, s, c, curve_first[5], curve_n[5];
    for (i = 0; i < 24; ++i) {
        hole2[2 * i] = 0.75 + 0.1 * cos(2 * WRT_PI * i / 24);
        hole2[2 * i + 1] = 0.2 + 0.1 * sin(2 * WRT_PI * i / 24);
    }
    for (i = 0; i < 41; ++i) {
        wave[2 * i] = 0.1 + 0.6 * i / 40.0;
        wave[2 * i + 1] = 0.45 + 0.03 * sin(8 * WRT_PI * i / 40.0);
    }
    for (i = 0; i < 32; ++i) {
        seam[2 * i] = 0.5 + 0.06 * cos(2 * WRT_PI * i / 32);
        seam[2 * i + 1] = 0.2 + 0.06 * sin(2 * WRT_PI * i / 32);
    }
    holes[0].xy = hole1;
    holes[0].n = 4;
    holes[0].closed = 0; /* ignored for loops */
    holes[1].xy = hole2;
    holes[1].n = 24;
    holes[1].closed = 0;
    lines[0].xy = wave;
    lines[0].n = 41;
    lines[0].closed = 0;
    lines[1].xy = seam;
    lines[1].n = 32;
    lines[1].closed = 1;
    memset(&dom, 0, sizeof dom);
    dom.outer.xy = outer;
    dom.outer.n = 5;
    dom.holes = holes;
    dom.n_holes = 2;
    dom.lines = lines;
    dom.n_lines = 2;
    memset(&desc, 0, sizeof desc);
    desc.seed = 8;
    cr_assert_eq(wr_poisson_sample(&dom, size_ramp, &h0, &desc, &res, &d), WR_OK, "%s", d.message);

    /* segments: per owner a consecutive chain over consecutive fixed indices */
    for (c = 0; c < 5; ++c) curve_n[c] = 0;
    for (s = 0; s < res.n_segments; ++s) {
        int32_t o = res.segment_owner[s];
        cr_assert(o >= 0 && o < 5);
        if (curve_n[o] == 0) curve_first[o] = res.segments[2 * s];
        cr_assert_eq(res.segments[2 * s], curve_first[o] + curve_n[o], "segment %d not consecutive", s);
        ++curve_n[o];
        cr_assert(res.segments[2 * s + 1] < res.n_fixed);
        if (o != 3) /* loops and the closed seam (owner 4): the last segment closes the chain */
            cr_assert(res.segments[2 * s + 1] == curve_first[o] + curve_n[o] || res.segments[2 * s + 1] == curve_first[o]);
        else
            cr_assert_eq(res.segments[2 * s + 1], curve_first[o] + curve_n[o]);
    }
    /* owner order: outer, holes, lines; the open wave has n-1 segments for n points */
    cr_assert_eq(curve_first[0], 0);
    for (c = 1; c < 5; ++c) cr_assert_eq(curve_first[c], curve_first[c - 1] + curve_n[c - 1] + (c - 1 == 3 ? 1 : 0));
    cr_assert_eq(curve_first[4] + curve_n[4], res.n_fixed, "closed seam is the last curve");
    /* corners and endpoints exact, at the curve's start in input order */
    cr_assert(res.points[0] == 0.0 && res.points[1] == 0.0);
    cr_assert(res.points[2 * curve_first[1]] == 0.1 && res.points[2 * curve_first[1] + 1] == 0.1);
    cr_assert(res.points[2 * curve_first[3]] == wave[0] && res.points[2 * curve_first[3] + 1] == wave[1]);
    cr_assert(res.points[2 * (curve_first[3] + curve_n[3])] == wave[80]);
    for (c = 0; c < 5 * 2; c += 2) {
        int found = 0;
        for (i = 0; i < curve_n[0]; ++i)
            if (res.points[2 * i] == outer[c] && res.points[2 * i + 1] == outer[c + 1]) found = 1;
        cr_assert(found, "outer corner %d kept exactly", c / 2);
    }
    /* hole 1 keeps its input (clockwise) direction: second corner (0.1, 0.25) comes after (0.1, 0.1) */
    cr_assert(res.points[2 * (curve_first[1] + 1)] == 0.1 && res.points[2 * (curve_first[1] + 1) + 1] > 0.1);
    /* every constraint segment has ∫ ds/h in [0.5, 1.5] (the header's guarantee; N = round(∫ds/h)
     * per piece, corners closer than h/2 dropped). h is linear along a straight segment, so
     * ∫ ds/h = L ln(h_b/h_a)/(h_b − h_a) exactly; 1e-3 allows the walk's trapezoid error. */
    for (s = 0; s < res.n_segments; ++s) {
        const double *a = res.points + 2 * res.segments[2 * s], *b = res.points + 2 * res.segments[2 * s + 1];
        double L = hypot(b[0] - a[0], b[1] - a[1]), ha = size_ramp(&h0, a[0], a[1]), hb = size_ramp(&h0, b[0], b[1]);
        double I = fabs(hb - ha) > 1e-12 * ha ? L * log(hb / ha) / (hb - ha) : L / ha;
        /* the bound holds along the input curve; on the curved owners (24-gon hole 1, wave 3,
         * seam 4) the chord is up to ~10% shorter than the arc it replaces */
        double lo = res.segment_owner[s] == 0 || res.segment_owner[s] == 1 ? 0.5 : 0.45;
        cr_assert(I >= lo - 1e-3 && I <= 1.5 + 1e-3, "segment %d (owner %d): integral ds/h = %.4f", s,
                  res.segment_owner[s], I);
    }
    /* interior samples inside the domain, outside the holes, and off the constraint lines */
    md = min_distance_ratio(&res);
    cr_assert(md >= 1.0, "min distance ratio %.9f", md);
    /* the first ring (header: ON THE FIRST RING): samples keep (r_f + r)/2, r_f = (2 D - c) h_f, from
     * every loop point (outer, holes); line points keep the interior rule, so some sample is nearer
     * to a line point than the loop rule would allow */
    {
        const double c = WR_POISSON_DEFAULT_RADIUS_FACTOR, D = WR_POISSON_DEFAULT_FIXED_DISTANCE;
        double loop_min = HUGE_VAL, line_min = HUGE_VAL;
        int32_t f;
        for (f = 0; f < res.n_fixed; ++f)
            for (i = res.n_fixed; i < res.n_points; ++i) {
                double dd = hypot(res.points[2 * f] - res.points[2 * i], res.points[2 * f + 1] - res.points[2 * i + 1]);
                double q = dd / (0.5 * ((2.0 * D - c) * res.sizing[f] + c * res.sizing[i]));
                if (f < curve_first[3])
                    loop_min = fmin(loop_min, q);
                else
                    line_min = fmin(line_min, q);
            }
        cr_assert(loop_min >= 1.0 - 1e-12, "a sample at %.6f of the loop-point distance", loop_min);
        cr_assert(line_min < 0.97, "line points: closest sample at %.4f of the loop rule (interior rule expected)",
                  line_min);
    }
    for (i = res.n_fixed; i < res.n_points; ++i) {
        const double *p = res.points + 2 * i;
        cr_assert(inside_loops(&res, 2, p[0], p[1]), "sample %d at (%g, %g) outside the domain", i, p[0], p[1]);
        for (s = 0; s < res.n_segments; ++s) {
            double dd = seg_dist(p, res.points + 2 * res.segments[2 * s], res.points + 2 * res.segments[2 * s + 1]);
            /* the clearance (header: ON THE CONFLICT RULE AND THE CLEARANCE) */
            cr_assert(dd >= WR_POISSON_DEFAULT_CLEARANCE * res.sizing[i] * (1.0 - 1e-12),
                      "sample %d at %.4g h from segment %d", i, dd / res.sizing[i], s);
        }
    }
    printf("[poisson] holes+lines: n=%d fixed=%d segments=%d coverage %.3f\n", res.n_points, res.n_fixed,
           res.n_segments, coverage_ratio(&res, 2, size_ramp, &h0, 0, 0, 1.0, 0.9, 70));
    cr_assert(coverage_ratio(&res, 2, size_ramp, &h0, 0, 0, 1.0, 0.9, 70) < 1.5);
    wr_poisson_free(&res);
}

/* ---- error paths ------------------------------------------------------------------------------ */
static wr_status run_outer(const double *xy, int32_t n, double h, wr_diag *d) {
    wr_poisson_domain dom;
    wr_poisson_result res;
    wr_status st;
    memset(&dom, 0, sizeof dom);
    dom.outer.xy = xy;
    dom.outer.n = n;
    st = wr_poisson_sample(&dom, size_const, &h, NULL, &res, d);
    wr_poisson_free(&res);
    return st;
}

Test(poisson, error_self_intersecting_names_segments) {
    static const double bow[8] = {0, 0, 1, 1, 1, 0, 0, 1}; /* segments 0 and 2 cross */
    wr_diag d;
    cr_assert_eq(run_outer(bow, 4, 0.1, &d), WR_ERR_GEOMETRY);
    cr_assert(strstr(d.message, "outer loop segment 0") && strstr(d.message, "outer loop segment 2"), "%s", d.message);
}

Test(poisson, error_fold_back_and_touching) {
    static const double fold[10] = {0, 0, 1, 0, 0.5, 0, 0.5, 1, 0, 1}; /* segment 1 runs back over 0 */
    static const double touch[12] = {0, 0, 2, 0, 2, 2, 1, 0, 0.5, 2, 0, 2}; /* vertex 3 lies on segment 0 */
    wr_diag d;
    cr_assert_eq(run_outer(fold, 5, 0.1, &d), WR_ERR_GEOMETRY);
    cr_assert(strstr(d.message, "segment 0") && strstr(d.message, "segment 1"), "%s", d.message);
    cr_assert_eq(run_outer(touch, 6, 0.1, &d), WR_ERR_GEOMETRY);
    cr_assert(strstr(d.message, "intersects"), "%s", d.message);
}

Test(poisson, error_counts_area_nan_duplicates) {
    static const double line3[6] = {0, 0, 1, 1, 2, 2};
    static const double dup[8] = {0, 0, 1, 0, 1, 0, 0, 1};
    double nanp[8] = {0, 0, 1, 0, 1, 1, 0, 1};
    wr_diag d;
    cr_assert_eq(run_outer(SQUARE, 2, 0.1, &d), WR_ERR_GEOMETRY);
    cr_assert(strstr(d.message, "at least 3"), "%s", d.message);
    cr_assert_eq(run_outer(line3, 3, 0.1, &d), WR_ERR_GEOMETRY); /* collinear: segment 2 folds back over 0 and 1 */
    cr_assert(strstr(d.message, "intersects"), "%s", d.message);
    cr_assert_eq(run_outer(dup, 4, 0.1, &d), WR_ERR_GEOMETRY);
    cr_assert(strstr(d.message, "zero length"), "%s", d.message);
    nanp[5] = NAN;
    cr_assert_eq(run_outer(nanp, 4, 0.1, &d), WR_ERR_GEOMETRY);
    cr_assert(strstr(d.message, "point 2") && strstr(d.message, "not finite"), "%s", d.message);
    cr_assert_eq(d.item, 2);
}

Test(poisson, error_zero_area_loop) {
    /* a simple (non-crossing) triangle whose area 5e-15 m² is below WR_POISSON_REL_TOL·bbox² */
    static const double flat[6] = {0, 0, 1, 0, 0.5, 1e-14};
    /* collinear back-and-forth loop: folds back on itself (segment 1 runs over segment 0) */
    static const double back[8] = {0, 0, 1, 0, 2, 0, 1, 0};
    wr_diag d;
    cr_assert_eq(run_outer(flat, 3, 0.1, &d), WR_ERR_GEOMETRY);
    cr_assert(strstr(d.message, "outer loop has zero area"), "%s", d.message);
    cr_assert_eq(run_outer(back, 4, 0.1, &d), WR_ERR_GEOMETRY);
    cr_assert(strstr(d.message, "intersects"), "%s", d.message);
}

Test(poisson, error_holes_and_lines) {
    static const double out_hole[8] = {2, 2, 3, 2, 3, 3, 2, 3};
    static const double ha[8] = {0.2, 0.2, 0.5, 0.2, 0.5, 0.5, 0.2, 0.5};
    static const double hb[8] = {0.3, 0.3, 0.4, 0.3, 0.4, 0.4, 0.3, 0.4}; /* inside ha */
    static const double hc[8] = {0.4, 0.4, 0.7, 0.4, 0.7, 0.7, 0.4, 0.7}; /* crosses ha */
    static const double line_out[4] = {0.7, 0.7, 1.5, 0.7};                /* leaves the panel */
    static const double line_in_hole[4] = {0.3, 0.3, 0.4, 0.4};
    wr_poisson_curve holes[2], line;
    wr_poisson_domain dom;
    wr_poisson_result res;
    wr_diag d;
    double h = 0.05;
    memset(holes, 0, sizeof holes);
    memset(&line, 0, sizeof line);
    dom_square(&dom);
    dom.holes = holes;
    holes[0].xy = out_hole;
    holes[0].n = 4;
    dom.n_holes = 1;
    cr_assert_eq(wr_poisson_sample(&dom, size_const, &h, NULL, &res, &d), WR_ERR_GEOMETRY);
    cr_assert(strstr(d.message, "hole 0 lies outside the outer loop"), "%s", d.message);
    holes[0].xy = ha;
    holes[1].xy = hb;
    holes[1].n = 4;
    dom.n_holes = 2;
    cr_assert_eq(wr_poisson_sample(&dom, size_const, &h, NULL, &res, &d), WR_ERR_GEOMETRY);
    cr_assert(strstr(d.message, "hole 0 overlaps hole 1"), "%s", d.message);
    holes[1].xy = hc;
    cr_assert_eq(wr_poisson_sample(&dom, size_const, &h, NULL, &res, &d), WR_ERR_GEOMETRY);
    cr_assert(strstr(d.message, "hole 0 segment") && strstr(d.message, "hole 1 segment"), "%s", d.message);
    dom.n_holes = 1;
    dom.lines = &line;
    dom.n_lines = 1;
    line.xy = line_out;
    line.n = 2;
    cr_assert_eq(wr_poisson_sample(&dom, size_const, &h, NULL, &res, &d), WR_ERR_GEOMETRY);
    cr_assert(strstr(d.message, "polyline 0 segment 0") && strstr(d.message, "outer loop segment 1"), "%s", d.message);
    line.xy = line_in_hole;
    cr_assert_eq(wr_poisson_sample(&dom, size_const, &h, NULL, &res, &d), WR_ERR_GEOMETRY);
    cr_assert(strstr(d.message, "polyline 0 lies inside hole 0"), "%s", d.message);
    line.n = 1;
    cr_assert_eq(wr_poisson_sample(&dom, size_const, &h, NULL, &res, &d), WR_ERR_GEOMETRY);
    cr_assert(strstr(d.message, "polyline 0 has 1 points"), "%s", d.message);
    cr_assert_eq(res.n_points, 0);
    cr_assert_null(res.points);
}

static double size_bad(void *u, double x, double y) {
    (void)y;
    (void)u;
    return x > 0.6 ? -0.01 : 0.05; /* non-positive in part of the interior */
}
/* NaN on an interior disk (centre (0.5, 0.5), radius 0.2) only: found by the budget probes */
static double size_nan(void *u, double x, double y) {
    (void)u;
    return (x - 0.5) * (x - 0.5) + (y - 0.5) * (y - 0.5) < 0.04 ? NAN : 0.05;
}

Test(poisson, error_bad_sizing_names_location) {
    wr_poisson_domain dom;
    wr_poisson_result res;
    wr_diag d;
    dom_square(&dom);
    cr_assert_eq(wr_poisson_sample(&dom, size_bad, NULL, NULL, &res, &d), WR_ERR_DOMAIN);
    cr_assert(strstr(d.message, "sizing(") && strstr(d.message, "= -0.01"), "%s", d.message);
    cr_assert_eq(wr_poisson_sample(&dom, size_nan, NULL, NULL, &res, &d), WR_ERR_DOMAIN);
    cr_assert(strstr(d.message, "nan"), "%s", d.message);
    {   /* the reported location really is where the callback is bad */
        double x, y;
        cr_assert_eq(sscanf(strstr(d.message, "sizing("), "sizing(%lf, %lf)", &x, &y), 2);
        cr_assert((x - 0.5) * (x - 0.5) + (y - 0.5) * (y - 0.5) < 0.04 + 1e-6, "%s", d.message);
    }
}

Test(poisson, error_budget_before_sampling) {
    wr_poisson_domain dom;
    wr_poisson_desc desc;
    wr_poisson_result res;
    wr_diag d;
    double h = 0.001; /* ≈ 1.1e6 points on the unit square */
    dom_square(&dom);
    memset(&desc, 0, sizeof desc);
    desc.max_points = 100000;
    cr_assert_eq(wr_poisson_sample(&dom, size_const, &h, &desc, &res, &d), WR_ERR_BUDGET);
    cr_assert(strstr(d.message, "max_points=100000"), "%s", d.message);
    cr_assert(res.n_estimated > 1000000 && res.n_estimated < 1300000, "estimate %d", res.n_estimated);
    cr_assert_null(res.points);
    /* boundary alone over budget */
    desc.max_points = 1000;
    cr_assert_eq(wr_poisson_sample(&dom, size_const, &h, &desc, &res, &d), WR_ERR_BUDGET);
}

Test(poisson, error_invalid_args) {
    wr_poisson_domain dom;
    wr_poisson_desc desc;
    wr_poisson_result res;
    wr_diag d;
    double h = 0.1;
    dom_square(&dom);
    cr_assert_eq(wr_poisson_sample(NULL, size_const, &h, NULL, &res, &d), WR_ERR_INVALID_ARG);
    cr_assert_eq(wr_poisson_sample(&dom, NULL, &h, NULL, &res, &d), WR_ERR_INVALID_ARG);
    cr_assert_eq(wr_poisson_sample(&dom, size_const, &h, NULL, NULL, &d), WR_ERR_INVALID_ARG);
    memset(&desc, 0, sizeof desc);
    desc.k = -1;
    cr_assert_eq(wr_poisson_sample(&dom, size_const, &h, &desc, &res, &d), WR_ERR_INVALID_ARG);
    desc.k = 0;
    desc.fixed_distance = 0.4; /* below radius_factor / 2: a loop point's radius would be negative */
    cr_assert_eq(wr_poisson_sample(&dom, size_const, &h, &desc, &res, &d), WR_ERR_INVALID_ARG);
    cr_assert(strstr(d.message, "fixed_distance=0.4") != NULL, "%s", d.message);
    dom.n_holes = 1; /* holes == NULL */
    cr_assert_eq(wr_poisson_sample(&dom, size_const, &h, NULL, &res, &d), WR_ERR_INVALID_ARG);
}

Test(poisson, narrow_feature_detected_after_discretisation) {
    /* an open arc (radius 0.108) wrapped around a circular hole (radius 0.1): at h = 0.1 the arc's
     * chords cut 0.1²/(8·0.108) ≈ 0.012 inwards, more than the 0.008 gap, and cross the hole's
     * discretised boundary; at h = 0.01 the sagitta is 1.2e-4 and the input is fine */
    double hole[128], arc[128];
    wr_poisson_curve hl, ln;
    wr_poisson_domain dom;
    wr_poisson_result res;
    wr_diag d;
    double h = 0.1;
    int i;
    for (i = 0; i < 64; ++i) {
        hole[2 * i] = 0.5 + 0.1 * cos(2 * WRT_PI * i / 64);
        hole[2 * i + 1] = 0.5 + 0.1 * sin(2 * WRT_PI * i / 64);
        /* the arc spans 30°..210° so its discretised points fall between the hole's (0°, 60°, …) */
        arc[2 * i] = 0.5 + 0.108 * cos(WRT_PI * (i / 63.0 + 1.0 / 6.0));
        arc[2 * i + 1] = 0.5 + 0.108 * sin(WRT_PI * (i / 63.0 + 1.0 / 6.0));
    }
    memset(&hl, 0, sizeof hl);
    memset(&ln, 0, sizeof ln);
    hl.xy = hole;
    hl.n = 64;
    ln.xy = arc;
    ln.n = 64;
    dom_square(&dom);
    dom.holes = &hl;
    dom.n_holes = 1;
    dom.lines = &ln;
    dom.n_lines = 1;
    cr_assert_eq(wr_poisson_sample(&dom, size_const, &h, NULL, &res, &d), WR_ERR_GEOMETRY);
    cr_assert(strstr(d.message, "discretised") && strstr(d.message, "hole 0") && strstr(d.message, "polyline 0"), "%s",
              d.message);
    h = 0.01;
    cr_assert_eq(wr_poisson_sample(&dom, size_const, &h, NULL, &res, &d), WR_OK, "%s", d.message);
    wr_poisson_free(&res);
}

/* Regression: finite input whose extent overflows a double (W = inf) turned the crossing check's
 * bucket count into NaN → int64 conversion and a signed overflow (UBSan). Now WR_ERR_GEOMETRY. */
Test(poisson, error_extent_overflow_is_geometry_error) {
    double sq[8] = {-1e308, -1e308, 1e308, -1e308, 1e308, 1e308, -1e308, 1e308}, h = 1e307;
    wr_poisson_domain dom;
    wr_poisson_result res;
    wr_diag d;
    memset(&dom, 0, sizeof dom);
    dom.outer.xy = sq;
    dom.outer.n = 4;
    cr_expect_eq(wr_poisson_sample(&dom, size_const, &h, NULL, &res, &d), WR_ERR_GEOMETRY);
    cr_expect(strstr(d.message, "extent") != NULL, "%s", d.message);
    wr_poisson_free(&res);
}

/* Regression: the zero-area test summed x_i y_j - x_j y_i about the origin, so a 1 mm square placed
 * 1e7 m away lost its whole area to cancellation (terms ~1e14 m², area 1e-6 m²) and was rejected
 * as "zero area". The shoelace sum now runs about the loop's first vertex. */
Test(poisson, far_from_origin_loop_keeps_its_area) {
    const double o = 1e7, s = 1e-3;
    double sq[8] = {o, o, o + s, o, o + s, o + s, o, o + s}, h = 1e-4;
    wr_poisson_domain dom;
    wr_poisson_result res;
    wr_diag d;
    memset(&dom, 0, sizeof dom);
    dom.outer.xy = sq;
    dom.outer.n = 4;
    cr_assert_eq(wr_poisson_sample(&dom, size_const, &h, NULL, &res, &d), WR_OK, "%s", d.message);
    cr_expect_gt(res.n_points, res.n_fixed);
    wr_poisson_free(&res);
}

/* ---- wr_poisson_fill: the curves as given ----------------------------------------------------- */
/* A square outer loop given at 41 points per side, a hole and an open line given at their own
 * spacing: the first n_fixed output points are exactly the input points (concatenated in curve
 * order), the segments exactly the input edges, and every sample keeps the mean rule, the
 * clearance and the inside. */
Test(poisson, fill_keeps_given_curves_exactly) {
    double outer[2 * 160], hole[2 * 40], line[2 * 25], h = 0.02;
    wr_poisson_curve hl, ln;
    wr_poisson_domain dom;
    wr_poisson_desc desc;
    wr_poisson_result res;
    wr_diag d;
    int32_t i, s, k = 0, n_exp;
    for (i = 0; i < 160; ++i) { /* CCW around the unit square, 40 steps of 0.025 per side */
        int side = i / 40;
        double t = (i % 40) / 40.0;
        outer[2 * i] = side == 0 ? t : side == 1 ? 1.0 : side == 2 ? 1.0 - t : 0.0;
        outer[2 * i + 1] = side == 0 ? 0.0 : side == 1 ? t : side == 2 ? 1.0 : 1.0 - t;
    }
    for (i = 0; i < 40; ++i) {
        hole[2 * i] = 0.3 + 0.1 * cos(2 * WRT_PI * i / 40);
        hole[2 * i + 1] = 0.3 + 0.1 * sin(2 * WRT_PI * i / 40);
    }
    for (i = 0; i < 25; ++i) {
        line[2 * i] = 0.55 + 0.3 * i / 24.0;
        line[2 * i + 1] = 0.7;
    }
    memset(&hl, 0, sizeof hl);
    memset(&ln, 0, sizeof ln);
    hl.xy = hole;
    hl.n = 40;
    ln.xy = line;
    ln.n = 25;
    memset(&dom, 0, sizeof dom);
    dom.outer.xy = outer;
    dom.outer.n = 160;
    dom.holes = &hl;
    dom.n_holes = 1;
    dom.lines = &ln;
    dom.n_lines = 1;
    memset(&desc, 0, sizeof desc);
    desc.seed = 4;
    cr_assert_eq(wr_poisson_fill(&dom, size_const, &h, &desc, &res, &d), WR_OK, "%s", d.message);
    cr_assert_eq(res.n_fixed, 160 + 40 + 25);
    for (i = 0; i < 160; ++i, ++k) cr_assert(res.points[2 * k] == outer[2 * i] && res.points[2 * k + 1] == outer[2 * i + 1]);
    for (i = 0; i < 40; ++i, ++k) cr_assert(res.points[2 * k] == hole[2 * i] && res.points[2 * k + 1] == hole[2 * i + 1]);
    for (i = 0; i < 25; ++i, ++k) cr_assert(res.points[2 * k] == line[2 * i] && res.points[2 * k + 1] == line[2 * i + 1]);
    n_exp = 160 + 40 + 24;
    cr_assert_eq(res.n_segments, n_exp);
    for (s = 0; s < 160; ++s) cr_assert(res.segments[2 * s] == s && res.segments[2 * s + 1] == (s + 1) % 160);
    for (s = 0; s < 40; ++s)
        cr_assert(res.segments[2 * (160 + s)] == 160 + s && res.segments[2 * (160 + s) + 1] == 160 + (s + 1) % 40);
    for (s = 0; s < 24; ++s) {
        cr_assert(res.segments[2 * (200 + s)] == 200 + s && res.segments[2 * (200 + s) + 1] == 201 + s);
        cr_assert_eq(res.segment_owner[200 + s], 2);
    }
    cr_assert(min_distance_ratio(&res) >= 1.0);
    for (i = res.n_fixed; i < res.n_points; ++i) {
        const double *p = res.points + 2 * i;
        cr_assert(inside_loops(&res, 1, p[0], p[1]), "sample %d outside", i);
        for (s = 0; s < res.n_segments; ++s)
            cr_assert(seg_dist(p, res.points + 2 * res.segments[2 * s], res.points + 2 * res.segments[2 * s + 1]) >=
                          WR_POISSON_DEFAULT_CLEARANCE * h * (1.0 - 1e-12),
                      "sample %d within the clearance of segment %d", i, s);
    }
    cr_assert(coverage_ratio(&res, 1, size_const, &h, 0, 0, 1, 1, 80) < 1.5);
    wr_poisson_free(&res);
}

/* The structured location in wr_diag (no message parsing): a line crossing hole 0. */
Test(poisson, failure_location_is_structured) {
    static const double hole[8] = {0.2, 0.2, 0.5, 0.2, 0.5, 0.5, 0.2, 0.5};
    static const double line[6] = {0.1, 0.6, 0.35, 0.6, 0.35, 0.3}; /* segment 1 enters the hole */
    static const double dup[8] = {0, 0, 1, 0, 1, 0, 0, 1};
    wr_poisson_curve hl, ln;
    wr_poisson_domain dom;
    wr_poisson_result res;
    wr_diag d;
    double h = 0.05;
    memset(&hl, 0, sizeof hl);
    memset(&ln, 0, sizeof ln);
    hl.xy = hole;
    hl.n = 4;
    ln.xy = line;
    ln.n = 3;
    dom_square(&dom);
    dom.holes = &hl;
    dom.n_holes = 1;
    dom.lines = &ln;
    dom.n_lines = 1;
    cr_assert_eq(wr_poisson_fill(&dom, size_const, &h, NULL, &res, &d), WR_ERR_GEOMETRY);
    /* hole 0 (curve 1) segment 2 = (0.5,0.5)-(0.2,0.5) is crossed by line 0 (curve 2) segment 1 */
    cr_assert(d.curve == 1 && d.item == 2 && d.other_curve == 2 && d.other_item == 1,
              "curve %d item %d other %d/%d: %s", d.curve, d.item, d.other_curve, d.other_item, d.message);
    cr_assert_eq(d.part, -1);
    dom.n_holes = 0;
    dom.n_lines = 0;
    dom.outer.xy = dup;
    cr_assert_eq(wr_poisson_fill(&dom, size_const, &h, NULL, &res, &d), WR_ERR_GEOMETRY);
    cr_assert(d.curve == 0 && d.item == 1, "zero-length segment: curve %d item %d", d.curve, d.item);
}

/* wr_poisson_estimate against closed forms: a 2 x 1 rectangle with a 0.5 x 0.5 hole at constant
 * h: area 1.75, perimeter 6 + 2, ∫ ds / h = 8 / h (Simpson is exact for constant h), interior
 * κ · 1.75 / r² up to the probe lattice's area error (the hole's edges fall between probes: the
 * mean of 1/r² is exact for constant h, so only the area enters, and that is the shoelace). */
Test(poisson, estimate_closed_forms) {
    static const double rect[8] = {0, 0, 2, 0, 2, 1, 0, 1};
    static const double hole[8] = {0.5, 0.25, 0.5, 0.75, 1.0, 0.75, 1.0, 0.25};
    wr_poisson_curve hl;
    wr_poisson_domain dom;
    wr_poisson_budget b;
    wr_diag d;
    double h = 0.01, r = WR_POISSON_DEFAULT_RADIUS_FACTOR * h;
    memset(&hl, 0, sizeof hl);
    hl.xy = hole;
    hl.n = 4;
    memset(&dom, 0, sizeof dom);
    dom.outer.xy = rect;
    dom.outer.n = 4;
    dom.holes = &hl;
    dom.n_holes = 1;
    cr_assert_eq(wr_poisson_estimate(&dom, size_const, &h, NULL, &b, &d), WR_OK, "%s", d.message);
    cr_assert_float_eq(b.area, 1.75, 1e-12);
    cr_assert_float_eq(b.perimeter, 8.0, 1e-12);
    cr_assert_float_eq(b.n_given, 8.0, 0.0);
    cr_assert_float_eq(b.n_discretised, 800.0, 1e-9);
    cr_assert_float_eq(b.n_interior, WR_POISSON_DENSITY * 1.75 / (r * r), 1e-9 * b.n_interior);
    cr_assert(b.n_probes > 10000 && b.h_min == h && b.h_max == h);
}

/* Issue 17's bounded-time inputs end with WR_ERR_BUDGET from the estimate, before any work that
 * grows with the output (no timing assert: the estimate's cost is O(input + 128² probes) by
 * construction; bench/RESULTS.md has the seconds). A 10 km square panel at 5 mm (4e12 points) and
 * a 1 m panel at 1 µm (1.2e12 points), default max_points; the message names what to change. */
Test(poisson, budget_refuses_huge_inputs_early) {
    double big[8] = {0, 0, 1e4, 0, 1e4, 1e4, 0, 1e4}, h = 5e-3, hu = 1e-6;
    wr_poisson_domain dom;
    wr_poisson_desc desc;
    wr_poisson_result res;
    wr_diag d;
    memset(&dom, 0, sizeof dom);
    dom.outer.xy = big;
    dom.outer.n = 4;
    cr_assert_eq(wr_poisson_sample(&dom, size_const, &h, NULL, &res, &d), WR_ERR_BUDGET);
    cr_assert(strstr(d.message, "max_points=50000000") && strstr(d.message, "raise max_points or coarsen the sizing"),
              "%s", d.message);
    cr_assert_eq(res.n_points, 0);
    cr_assert_eq(wr_poisson_fill(&dom, size_const, &h, NULL, &res, &d), WR_ERR_BUDGET);
    dom_square(&dom);
    cr_assert_eq(wr_poisson_sample(&dom, size_const, &hu, NULL, &res, &d), WR_ERR_BUDGET);
    cr_assert(strstr(d.message, "inside") && strstr(d.message, "max_points=50000000"), "%s", d.message);
    cr_assert(res.n_estimated == INT32_MAX, "estimate %d", res.n_estimated);
    cr_assert_eq(wr_poisson_fill(&dom, size_const, &hu, NULL, &res, &d), WR_ERR_BUDGET);
    memset(&desc, 0, sizeof desc);
    desc.max_points = 1000000; /* the 4e6 boundary points alone exceed it */
    cr_assert_eq(wr_poisson_sample(&dom, size_const, &hu, &desc, &res, &d), WR_ERR_BUDGET);
    cr_assert(strstr(d.message, "the curves alone need 4000000 points"), "%s", d.message);
}

/* Regression (found on examples/fig13_elbow.json: the collision disk stayed empty): a sizing that
 * halves within one h, as the mesher's collision transition does. A candidate moved inwards to the
 * mean-rule distance landed where the sizing was larger again and was refused, so no front entered
 * the finer disk. Now the move iterates ρ = (r_p + r(ρ))/2; checked by coverage (every probe
 * within 1.5 r of a sample, as the constant-radius test) and by the mean rule. Also the reverse
 * (a coarser disk: candidates beyond the neighbour list's reach, decided by the grid). */
static double size_disk_step(void *u, double x, double y) {
    double f = *(const double *)u, dx = x - 0.5, dy = y - 0.5, d = sqrt(dx * dx + dy * dy), h = 0.02;
    double t = d < 0.2 ? 0.0 : (d - 0.2) / 0.02; /* transition over one h */
    return h * (t >= 1.0 ? 1.0 : f + (1.0 - f) * t);
}

Test(poisson, steep_transition_into_finer_or_coarser_disk_is_filled) {
    wr_poisson_domain dom;
    wr_poisson_desc desc;
    wr_poisson_result res;
    wr_diag d;
    double f[2] = {0.5, 2.0};
    int k;
    dom_square(&dom);
    memset(&desc, 0, sizeof desc);
    desc.seed = 13;
    for (k = 0; k < 2; ++k) {
        double cov;
        cr_assert_eq(wr_poisson_sample(&dom, size_disk_step, &f[k], &desc, &res, &d), WR_OK, "%s", d.message);
        cr_assert(min_distance_ratio(&res) >= 1.0);
        cov = coverage_ratio(&res, 0, size_disk_step, &f[k], 0, 0, 1, 1, 90);
        cr_assert(cov < 1.5, "disk sizing x%.1f: largest empty disk %.3f r", f[k], cov);
        wr_poisson_free(&res);
    }
}
