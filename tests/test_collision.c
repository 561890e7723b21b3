/* tests/test_collision.c — collision.h: closed-form point–triangle and edge–edge distances in every
 * region, finite-difference gradients and Hessians, the barrier, ACCD times of impact against
 * closed forms (and never past the true contact), exact segment/triangle intersection cases, BVH
 * candidate sets equal to brute force on random soups, contact sets and CCD on meshes, whole-mesh
 * intersection checks. */
#include <criterion/criterion.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "wrinkle/collision.h"

/* Distances here are O(1) sums of a few products: rounding ~1e-16; 1e-12 leaves 4 orders. */
#define CO_TOL 1e-12
/* Central differences, step 1e-6 on O(1) coordinates: truncation ~1e-12, round-off ~1e-10. */
#define CO_FD_STEP 1e-6
#define CO_FD_TOL 1e-6

static void co_set(double *p, double x, double y, double z) {
    p[0] = x;
    p[1] = y;
    p[2] = z;
}

/* ---- point–triangle regions (triangle (0,0,0), (1,0,0), (0,1,0)) ---- */
Test(collision, point_triangle_regions_closed_form) {
    double t0[3] = {0, 0, 0}, t1[3] = {1, 0, 0}, t2[3] = {0, 1, 0}, p[3], w[4];
    int32_t piece;
    /* face interior: distance = height */
    co_set(p, 0.2, 0.3, 0.7);
    cr_expect_float_eq(wr_collision_point_triangle_dist2(p, t0, t1, t2, NULL, NULL, w, &piece), 0.49, CO_TOL);
    cr_expect_eq(piece, WR_DIST_PF);
    cr_expect_float_eq(w[2], -0.2, CO_TOL); /* r = p − (0.2, 0.3, 0) */
    cr_expect_float_eq(w[3], -0.3, CO_TOL);
    /* below the plane: same unsigned distance */
    co_set(p, 0.2, 0.3, -0.7);
    cr_expect_float_eq(wr_collision_point_triangle_dist2(p, t0, t1, t2, NULL, NULL, NULL, &piece), 0.49, CO_TOL);
    /* edge region of the hypotenuse x + y = 1: distance to the line */
    co_set(p, 1.0, 1.0, 0.5);
    cr_expect_float_eq(wr_collision_point_triangle_dist2(p, t0, t1, t2, NULL, NULL, NULL, &piece), 0.5 + 0.25, CO_TOL);
    cr_expect_eq(piece, WR_DIST_PE);
    /* edge region of the x axis edge */
    co_set(p, 0.5, -2.0, 1.0);
    cr_expect_float_eq(wr_collision_point_triangle_dist2(p, t0, t1, t2, NULL, NULL, NULL, &piece), 5.0, CO_TOL);
    cr_expect_eq(piece, WR_DIST_PE);
    /* vertex regions */
    co_set(p, -1.0, -2.0, 2.0);
    cr_expect_float_eq(wr_collision_point_triangle_dist2(p, t0, t1, t2, NULL, NULL, NULL, &piece), 9.0, CO_TOL);
    cr_expect_eq(piece, WR_DIST_PP);
    co_set(p, 3.0, -1.0, 0.0);
    cr_expect_float_eq(wr_collision_point_triangle_dist2(p, t0, t1, t2, NULL, NULL, NULL, &piece), 5.0, CO_TOL);
    co_set(p, -0.5, 2.0, 0.0);
    cr_expect_float_eq(wr_collision_point_triangle_dist2(p, t0, t1, t2, NULL, NULL, NULL, &piece), 1.25, CO_TOL);
}

Test(collision, edge_edge_crossing_and_parallel) {
    double a0[3], a1[3], b0[3], b1[3], w[4];
    int32_t piece;
    /* crossing skew edges: x axis segment and a y-parallel segment 0.3 above at x = 0.4 */
    co_set(a0, 0, 0, 0);
    co_set(a1, 1, 0, 0);
    co_set(b0, 0.4, -1, 0.3);
    co_set(b1, 0.4, 1, 0.3);
    cr_expect_float_eq(wr_collision_edge_edge_dist2(a0, a1, b0, b1, NULL, NULL, w, &piece), 0.09, CO_TOL);
    cr_expect_eq(piece, WR_DIST_EE);
    cr_expect_float_eq(w[1], 0.4, CO_TOL);
    cr_expect_float_eq(w[3], -0.5, CO_TOL);
    /* parallel overlapping: distance between the lines, attained at an end point */
    co_set(b0, 0.5, 0.2, 0.0);
    co_set(b1, 1.5, 0.2, 0.0);
    cr_expect_float_eq(wr_collision_edge_edge_dist2(a0, a1, b0, b1, NULL, NULL, NULL, &piece), 0.04, CO_TOL);
    cr_expect_eq(piece, WR_DIST_PE);
    /* parallel disjoint along the line: end point to end point */
    co_set(b0, 2.0, 0.0, 0.0);
    co_set(b1, 3.0, 0.0, 0.0);
    cr_expect_float_eq(wr_collision_edge_edge_dist2(a0, a1, b0, b1, NULL, NULL, NULL, &piece), 1.0, CO_TOL);
    cr_expect_eq(piece, WR_DIST_PP);
    /* lines cross outside one segment: end of b to the interior of a */
    co_set(b0, 0.4, 0.5, 0.0);
    co_set(b1, 0.4, 2.0, 0.0);
    cr_expect_float_eq(wr_collision_edge_edge_dist2(a0, a1, b0, b1, NULL, NULL, NULL, &piece), 0.25, CO_TOL);
    cr_expect_eq(piece, WR_DIST_PE);
    /* intersecting: distance 0 */
    co_set(b0, 0.4, -1, 0.0);
    co_set(b1, 0.4, 1, 0.0);
    cr_expect_float_eq(wr_collision_edge_edge_dist2(a0, a1, b0, b1, NULL, NULL, NULL, NULL), 0.0, CO_TOL);
}

/* FD check of gradient and Hessian of d² at x (12), for the pair kind. Returns max relative error. */
static void co_fd_check(int kind, const double *x0) {
    double x[12], g[12], H[144], gp[12], gm[12], sp, sm, s, scale = 0.0, herr = 0.0, gerr = 0.0, hs = 0.0;
    int32_t piece, pp, pm;
    int i, j;
    memcpy(x, x0, sizeof x);
    s = kind == 0 ? wr_collision_point_triangle_dist2(x, x + 3, x + 6, x + 9, g, H, NULL, &piece)
                  : wr_collision_edge_edge_dist2(x, x + 3, x + 6, x + 9, g, H, NULL, &piece);
    (void)s;
    for (i = 0; i < 12; ++i) scale = fmax(scale, fabs(g[i]));
    for (i = 0; i < 144; ++i) hs = fmax(hs, fabs(H[i]));
    for (i = 0; i < 12; ++i) {
        x[i] = x0[i] + CO_FD_STEP;
        sp = kind == 0 ? wr_collision_point_triangle_dist2(x, x + 3, x + 6, x + 9, gp, NULL, NULL, &pp)
                       : wr_collision_edge_edge_dist2(x, x + 3, x + 6, x + 9, gp, NULL, NULL, &pp);
        x[i] = x0[i] - CO_FD_STEP;
        sm = kind == 0 ? wr_collision_point_triangle_dist2(x, x + 3, x + 6, x + 9, gm, NULL, NULL, &pm)
                       : wr_collision_edge_edge_dist2(x, x + 3, x + 6, x + 9, gm, NULL, NULL, &pm);
        x[i] = x0[i];
        cr_assert(pp == piece && pm == piece, "FD step crossed a piece boundary; pick another point");
        gerr = fmax(gerr, fabs((sp - sm) / (2 * CO_FD_STEP) - g[i]));
        for (j = 0; j < 12; ++j) herr = fmax(herr, fabs((gp[j] - gm[j]) / (2 * CO_FD_STEP) - H[12 * j + i]));
    }
    cr_expect(gerr <= CO_FD_TOL * fmax(scale, 1.0), "kind %d piece %d: gradient FD error %g (scale %g)", kind, piece,
              gerr, scale);
    cr_expect(herr <= CO_FD_TOL * fmax(hs, 1.0), "kind %d piece %d: Hessian FD error %g (scale %g)", kind, piece, herr,
              hs);
}

Test(collision, distance_derivatives_fd_every_piece) {
    /* point–triangle: face, edge, vertex pieces; edge–edge: line–line, point–edge, point–point */
    double pf[12] = {0.2, 0.3, 0.7, 0.1, -0.05, 0.02, 1.1, 0.1, -0.1, 0.05, 0.9, 0.1};
    double pe[12] = {1.0, 1.0, 0.5, 0.1, -0.05, 0.02, 1.1, 0.1, -0.1, 0.05, 0.9, 0.1};
    double pv[12] = {-1.0, -2.0, 2.0, 0.1, -0.05, 0.02, 1.1, 0.1, -0.1, 0.05, 0.9, 0.1};
    double ee[12] = {0, 0, 0, 1, 0.1, 0.05, 0.4, -1, 0.3, 0.45, 1, 0.35};
    double eep[12] = {0, 0, 0, 1, 0.1, 0.05, 0.4, 0.6, 0.3, 0.45, 2, 0.35};
    double eev[12] = {0, 0, 0, 1, 0.1, 0.05, 2.0, 1.0, 0.3, 3.0, 2.0, 0.35};
    int32_t piece;
    co_fd_check(0, pf);
    co_fd_check(0, pe);
    co_fd_check(0, pv);
    co_fd_check(1, ee);
    co_fd_check(1, eep);
    co_fd_check(1, eev);
    wr_collision_point_triangle_dist2(pf, pf + 3, pf + 6, pf + 9, NULL, NULL, NULL, &piece);
    cr_expect_eq(piece, WR_DIST_PF);
    wr_collision_point_triangle_dist2(pe, pe + 3, pe + 6, pe + 9, NULL, NULL, NULL, &piece);
    cr_expect_eq(piece, WR_DIST_PE);
    wr_collision_point_triangle_dist2(pv, pv + 3, pv + 6, pv + 9, NULL, NULL, NULL, &piece);
    cr_expect_eq(piece, WR_DIST_PP);
    wr_collision_edge_edge_dist2(ee, ee + 3, ee + 6, ee + 9, NULL, NULL, NULL, &piece);
    cr_expect_eq(piece, WR_DIST_EE);
    wr_collision_edge_edge_dist2(eep, eep + 3, eep + 6, eep + 9, NULL, NULL, NULL, &piece);
    cr_expect_eq(piece, WR_DIST_PE);
    wr_collision_edge_edge_dist2(eev, eev + 3, eev + 6, eev + 9, NULL, NULL, NULL, &piece);
    cr_expect_eq(piece, WR_DIST_PP);
}

Test(collision, barrier_matches_statics_form_and_derivatives) {
    double d, b1, b2, bp1, bm1, h = 1e-9;
    for (d = 1e-4; d < 1e-3; d += 1.7e-4) {
        double bp = wr_collision_barrier(d + h, 1e-3, 50.0, &bp1, NULL), bm = wr_collision_barrier(d - h, 1e-3, 50.0, &bm1, NULL);
        double b = wr_collision_barrier(d, 1e-3, 50.0, &b1, &b2);
        cr_expect_float_eq(b, -50.0 * (d - 1e-3) * (d - 1e-3) * log(d / 1e-3), 1e-15);
        cr_expect(fabs((bp - bm) / (2 * h) - b1) <= 1e-6 * fabs(b1));
        cr_expect(fabs((bp1 - bm1) / (2 * h) - b2) <= 1e-5 * fabs(b2));
    }
    cr_expect(isinf(wr_collision_barrier(0.0, 1e-3, 1.0, NULL, NULL)));
    cr_expect_eq(wr_collision_barrier(2e-3, 1e-3, 1.0, NULL, NULL), 0.0);
}

/* ---- CCD ---- */
Test(collision, accd_point_towards_plane_triangle) {
    /* point at height z0 moving down at speed v through the triangle's interior: true impact
     * t* = z0/v; ACCD must stop in [ (1 − keep)·t*·(1 − 1e-12), t* ) and keep d >= keep·z0 */
    double x[12] = {0.2, 0.2, 0.5, 0, 0, 0, 1, 0, 0, 0, 1, 0}, dx[12] = {0};
    double toi, z0 = 0.5;
    int32_t hit;
    dx[2] = -1.0; /* impact at t* = 0.5 */
    hit = wr_collision_accd(WR_CONTACT_PT, x, dx, 0.1, 1.0, 0, &toi);
    cr_expect_eq(hit, 1);
    cr_expect(toi < 0.5 && toi >= 0.9 * 0.5 * (1 - 1e-12), "toi %g", toi);
    cr_expect(z0 - toi >= 0.1 * z0 * (1 - 1e-12));
    /* moving away: no impact */
    dx[2] = 1.0;
    cr_expect_eq(wr_collision_accd(WR_CONTACT_PT, x, dx, 0.1, 1.0, 0, &toi), 0);
    cr_expect_eq(toi, 1.0);
    /* the triangle moving up instead (same relative motion): same TOI bound */
    dx[2] = 0.0;
    dx[5] = dx[8] = dx[11] = 1.0;
    hit = wr_collision_accd(WR_CONTACT_PT, x, dx, 0.1, 1.0, 0, &toi);
    cr_expect(hit == 1 && toi < 0.5 && toi >= 0.45 * (1 - 1e-12), "toi %g", toi);
    /* impact beyond t_max = 0.4: not reported */
    dx[5] = dx[8] = dx[11] = 0.0;
    dx[2] = -1.0;
    cr_expect_eq(wr_collision_accd(WR_CONTACT_PT, x, dx, 0.1, 0.4, 0, &toi), 0);
}

Test(collision, accd_edge_edge_crossing_never_passes_impact) {
    /* b moves down through a: true impact at t* = 0.3/0.9; random extra tangential motions */
    wr_rng rng;
    int trial;
    wr_rng_seed(&rng, 7);
    for (trial = 0; trial < 200; ++trial) {
        double x[12] = {0, 0, 0, 1, 0, 0, 0.4, -1, 0.3, 0.4, 1, 0.3}, dx[12] = {0}, toi, xt[12], s;
        double tx = 0.2 * (wr_rng_uniform(&rng) - 0.5);
        int i, k;
        for (k = 2; k < 4; ++k) {
            dx[3 * k] = tx;
            dx[3 * k + 2] = -0.9;
        }
        cr_assert_eq(wr_collision_accd(WR_CONTACT_EE, x, dx, 0.1, 1.0, 0, &toi), 1);
        cr_expect(toi < 0.3 / 0.9, "toi %g past the impact", toi);
        for (i = 0; i < 12; ++i) xt[i] = x[i] + toi * dx[i];
        s = wr_collision_edge_edge_dist2(xt, xt + 3, xt + 6, xt + 9, NULL, NULL, NULL, NULL);
        cr_expect(sqrt(s) >= 0.1 * 0.3 * (1 - 1e-12), "distance %g at toi", sqrt(s));
    }
    /* parallel overlapping edges sliding along each other at a constant gap: never a hit (ACCD
     * only stops below keep·d(0), and d stays d(0)) */
    {
        double x[12] = {0, 0, 0, 1, 0, 0, 0.5, 0.1, 0, 1.5, 0.1, 0}, dx[12] = {0}, toi;
        dx[6] = dx[9] = 0.3;
        cr_expect_eq(wr_collision_accd(WR_CONTACT_EE, x, dx, 0.1, 1.0, 0, &toi), 0);
    }
}

/* ---- exact predicates ---- */
Test(collision, orient3d_exact_on_near_degenerate_input) {
    double a[3] = {0, 0, 0}, b[3] = {1, 0, 0}, c[3] = {0, 1, 0}, d[3] = {0.3, 0.3, 1e-300};
    cr_expect(wr_orient3d(a, b, c, d) > 0.0);
    d[2] = -1e-300;
    cr_expect(wr_orient3d(a, b, c, d) < 0.0);
    d[2] = 0.0;
    cr_expect_eq(wr_orient3d(a, b, c, d), 0.0);
    { /* four points on the plane z = 0.75x + y (dyadic coordinates, so exactly coplanar) where the
       * plain floating-point determinant is 1.4e-17, not 0: only the exact stage answers 0 */
        double P[4][3] = {{1.1906375885009766, 0.89058017730712891, 1.7835583686828613},
                          {0.71826171875, 0.78396129608154297, 1.322657585144043},
                          {0.92459487915039062, 0.64950752258300781, 1.3429536819458008},
                          {0.71016693115234375, 0.96557426452636719, 1.498199462890625}};
        double bx = P[1][0] - P[0][0], by = P[1][1] - P[0][1], bz = P[1][2] - P[0][2];
        double cx = P[2][0] - P[0][0], cy = P[2][1] - P[0][1], cz = P[2][2] - P[0][2];
        double dx = P[3][0] - P[0][0], dy = P[3][1] - P[0][1], dz = P[3][2] - P[0][2];
        double naive = bx * (cy * dz - cz * dy) + by * (cz * dx - cx * dz) + bz * (cx * dy - cy * dx);
        cr_expect_neq(naive, 0.0); /* the case exercises the exact stage */
        cr_expect_eq(wr_orient3d(P[0], P[1], P[2], P[3]), 0.0);
        P[3][2] = nextafter(P[3][2], 2.0); /* one ulp off the plane */
        cr_expect_neq(wr_orient3d(P[0], P[1], P[2], P[3]), 0.0);
        P[3][2] = nextafter(nextafter(P[3][2], 0.0), 0.0); /* one ulp below: the opposite sign */
        {
            double below = wr_orient3d(P[0], P[1], P[2], P[3]);
            P[3][2] = nextafter(nextafter(P[3][2], 2.0), 2.0);
            cr_expect(below * wr_orient3d(P[0], P[1], P[2], P[3]) < 0.0);
        }
    }
}

Test(collision, segment_and_triangle_intersection_cases) {
    double a[3] = {0, 0, 0}, b[3] = {1, 0, 0}, c[3] = {0, 1, 0}, p[3], q[3];
    double A[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0}, B[9];
    co_set(p, 0.2, 0.2, -1);
    co_set(q, 0.2, 0.2, 1);
    cr_expect(wr_collision_segment_triangle_intersect(p, q, a, b, c));
    co_set(q, 0.2, 0.2, -0.5); /* stops short */
    cr_expect(!wr_collision_segment_triangle_intersect(p, q, a, b, c));
    co_set(q, 0.2, 0.2, 0.0); /* touches the face */
    cr_expect(wr_collision_segment_triangle_intersect(p, q, a, b, c));
    co_set(p, 0.5, 0.5, -1); /* through the hypotenuse exactly (closed) */
    co_set(q, 0.5, 0.5, 1);
    cr_expect(wr_collision_segment_triangle_intersect(p, q, a, b, c));
    co_set(p, nextafter(0.5, 1.0), 0.5, -1); /* one ulp outside */
    co_set(q, nextafter(0.5, 1.0), 0.5, 1);
    cr_expect(!wr_collision_segment_triangle_intersect(p, q, a, b, c));
    co_set(p, -1, 0.25, 0); /* coplanar, crossing */
    co_set(q, 2, 0.25, 0);
    cr_expect(wr_collision_segment_triangle_intersect(p, q, a, b, c));
    co_set(p, -1, 2.5, 0); /* coplanar, outside */
    co_set(q, 2, 2.5, 0);
    cr_expect(!wr_collision_segment_triangle_intersect(p, q, a, b, c));
    /* triangle–triangle: piercing, separated, coplanar overlapping, coplanar disjoint */
    double Bp[9] = {0.2, 0.2, -1, 0.3, 0.2, 1, 0.25, 0.3, 1};
    memcpy(B, Bp, sizeof B);
    cr_expect(wr_collision_triangle_triangle_intersect(A, B));
    B[2] = 0.1; /* now the whole of B is above: z in [0.1, 1] */
    cr_expect(!wr_collision_triangle_triangle_intersect(A, B));
    double Bc[9] = {0.2, 0.2, 0, 2, 0.2, 0, 0.2, 2, 0};
    cr_expect(wr_collision_triangle_triangle_intersect(A, Bc));
    double Bd[9] = {2, 2, 0, 3, 2, 0, 2, 3, 0};
    cr_expect(!wr_collision_triangle_triangle_intersect(A, Bd));
    /* a triangle whose edges all miss A but whose interior is pierced by an edge of A */
    double Bq[9] = {0.5, -1, -1, 0.5, -1, 1, 0.5, 3, 0};
    cr_expect(wr_collision_triangle_triangle_intersect(A, Bq));
}

/* ---- BVH vs brute force ---- */
typedef struct co_pairs {
    int32_t n, cap;
    int64_t *k;
} co_pairs;

static wr_status co_collect(void *u, int32_t i, int32_t j) {
    co_pairs *p = (co_pairs *)u;
    if (p->n == p->cap) {
        p->cap = p->cap ? 2 * p->cap : 1024;
        p->k = (int64_t *)realloc(p->k, sizeof(int64_t) * (size_t)p->cap);
    }
    p->k[p->n++] = ((int64_t)i << 32) | j;
    return WR_OK;
}

static int co_cmp(const void *a, const void *b) {
    int64_t x = *(const int64_t *)a, y = *(const int64_t *)b;
    return x < y ? -1 : x > y;
}

static int co_ov(const double *a, const double *b) {
    return a[0] <= b[3] && b[0] <= a[3] && a[1] <= b[4] && b[1] <= a[4] && a[2] <= b[5] && b[2] <= a[5];
}

static void co_soup(wr_rng *rng, int32_t n, double size, double *bx) {
    int32_t i;
    int a;
    for (i = 0; i < n; ++i)
        for (a = 0; a < 3; ++a) {
            double c = wr_rng_uniform(rng), h = size * wr_rng_uniform(rng);
            bx[6 * i + a] = c - h;
            bx[6 * i + 3 + a] = c + h;
        }
}

/* move every box coordinate by amp·sin(freq·i), then swap min and max where they crossed */
static void co_jiggle(double *bx, int32_t n, double amp, double freq) {
    int32_t i, j;
    for (i = 0; i < 6 * n; ++i) bx[i] += amp * sin(freq * (double)i);
    for (i = 0; i < n; ++i)
        for (j = 0; j < 3; ++j)
            if (bx[6 * i + j] > bx[6 * i + 3 + j]) {
                double t = bx[6 * i + j];
                bx[6 * i + j] = bx[6 * i + 3 + j];
                bx[6 * i + 3 + j] = t;
            }
}

Test(collision, bvh_candidates_equal_brute_force) {
    wr_rng rng;
    int round;
    wr_rng_seed(&rng, 11);
    for (round = 0; round < 4; ++round) {
        int32_t n = 300 + 200 * round, m = 250, i, j;
        double *bx = (double *)malloc(sizeof(double) * 6 * (size_t)n), *by = (double *)malloc(sizeof(double) * 6 * (size_t)m);
        wr_bvh ta, tb;
        co_pairs got = {0, 0, NULL}, ref = {0, 0, NULL};
        co_soup(&rng, n, 0.03, bx);
        co_soup(&rng, m, 0.05, by);
        /* duplicated boxes (equal keys) in the first tree stress the median split */
        for (i = 0; i < 30; ++i) memcpy(bx + 6 * (n - 1 - i), bx, 6 * sizeof(double));
        cr_assert_eq(wr_bvh_build(&ta, n, bx, NULL), WR_OK);
        cr_assert_eq(wr_bvh_build(&tb, m, by, NULL), WR_OK);
        /* self pairs */
        cr_assert_eq(wr_bvh_self_pairs(&ta, co_collect, &got, NULL), WR_OK);
        for (i = 0; i < n; ++i)
            for (j = i + 1; j < n; ++j)
                if (co_ov(bx + 6 * i, bx + 6 * j)) co_collect(&ref, i, j);
        qsort(got.k, (size_t)got.n, sizeof(int64_t), co_cmp);
        cr_assert_eq(got.n, ref.n, "self pairs: BVH %d, brute force %d", got.n, ref.n);
        cr_expect(got.n == 0 || memcmp(got.k, ref.k, sizeof(int64_t) * (size_t)got.n) == 0);
        /* cross pairs, after moving every box (refit) */
        co_jiggle(bx, n, 0.01, 1.0);
        wr_bvh_refit(&ta, bx);
        got.n = ref.n = 0;
        cr_assert_eq(wr_bvh_pairs(&ta, &tb, co_collect, &got, NULL), WR_OK);
        for (i = 0; i < n; ++i)
            for (j = 0; j < m; ++j)
                if (co_ov(bx + 6 * i, by + 6 * j)) co_collect(&ref, i, j);
        qsort(got.k, (size_t)got.n, sizeof(int64_t), co_cmp);
        cr_assert_eq(got.n, ref.n, "cross pairs: BVH %d, brute force %d", got.n, ref.n);
        cr_expect(got.n == 0 || memcmp(got.k, ref.k, sizeof(int64_t) * (size_t)got.n) == 0);
        wr_bvh_free(&ta);
        wr_bvh_free(&tb);
        free(got.k);
        free(ref.k);
        free(bx);
        free(by);
    }
}

/* ---- the single-box query against brute force ---- */
static wr_status co_collect_prim(void *u, int32_t i) { return co_collect(u, 0, i); }
static wr_status co_stop_prim(void *u, int32_t i) {
    (void)i;
    ++*(int32_t *)u;
    return WR_ERR_BUDGET;
}

/* every id whose box overlaps q, in increasing order, from the tree (sorted) and by brute force */
static void co_query_check(const wr_bvh *t, const double *bx, int32_t n, const double *q, const char *what) {
    co_pairs got = {0, 0, NULL}, ref = {0, 0, NULL};
    int32_t i;
    cr_assert_eq(wr_bvh_box_query(t, q, co_collect_prim, &got, NULL), WR_OK);
    for (i = 0; i < n; ++i)
        if (co_ov(bx + 6 * i, q)) co_collect(&ref, 0, i);
    if (got.n) qsort(got.k, (size_t)got.n, sizeof(int64_t), co_cmp);
    cr_assert_eq(got.n, ref.n, "%s (n = %d): BVH %d boxes, brute force %d", what, (int)n, (int)got.n, (int)ref.n);
    cr_assert(got.n == 0 || memcmp(got.k, ref.k, sizeof(int64_t) * (size_t)got.n) == 0, "%s: different ids", what);
    free(got.k);
    free(ref.k);
}

/* Random soups (n = 0 .. 2000, so leaves, one split and deep trees) and random query boxes of every
 * size, plus queries that only touch a primitive's box face or are a single corner point (closed
 * boxes: touching counts), before and after a refit: the query returns exactly the brute-force set,
 * so a traversal that prunes a subtree it should enter (or reports one it should not) fails here.
 * A callback's non-OK status stops the query at once and is returned; a NaN box meets nothing. */
Test(collision, bvh_box_query_equals_brute_force) {
    static const int32_t sizes[] = {0, 1, 4, 5, 9, 37, 600, 2000};
    wr_rng rng;
    size_t r;
    wr_rng_seed(&rng, 29);
    for (r = 0; r < sizeof sizes / sizeof sizes[0]; ++r) {
        int32_t n = sizes[r], i, k, calls = 0;
        double *bx = (double *)malloc(sizeof(double) * 6 * (size_t)(n > 0 ? n : 1)), q[6];
        wr_bvh t;
        co_soup(&rng, n, 0.02, bx);
        for (i = 0; i + 1 < n && i < 10; ++i) memcpy(bx + 6 * (n - 1 - i), bx, 6 * sizeof(double)); /* equal keys */
        cr_assert_eq(wr_bvh_build(&t, n, bx, NULL), WR_OK);
        for (k = 0; k < 300; ++k) {
            co_soup(&rng, 1, k % 3 == 0 ? 0.3 : (k % 3 == 1 ? 0.05 : 0.0), q);
            co_query_check(&t, bx, n, q, "random box");
        }
        for (i = 0; i < n && i < 50; ++i) {
            int a = (int)(i % 3);
            memcpy(q, bx + 6 * i, sizeof q); /* a box whose min face touches box i's max face */
            q[a] = q[3 + a];
            q[3 + a] = q[a] + 0.01;
            co_query_check(&t, bx, n, q, "touching box");
            memcpy(q, bx + 6 * i, 3 * sizeof(double)); /* box i's min corner, a point */
            memcpy(q + 3, bx + 6 * i, 3 * sizeof(double));
            co_query_check(&t, bx, n, q, "corner point");
        }
        co_jiggle(bx, n, 0.05, 3.0);
        wr_bvh_refit(&t, bx);
        for (k = 0; k < 300; ++k) {
            co_soup(&rng, 1, k % 2 ? 0.2 : 0.01, q);
            co_query_check(&t, bx, n, q, "after refit");
        }
        q[0] = q[1] = q[2] = -1.0, q[3] = q[4] = q[5] = 2.0; /* everything: the callback stops at the first */
        cr_expect_eq(wr_bvh_box_query(&t, q, co_stop_prim, &calls, NULL), n > 0 ? WR_ERR_BUDGET : WR_OK);
        cr_expect_eq(calls, n > 0 ? 1 : 0);
        q[0] = NAN;
        calls = 0;
        cr_expect_eq(wr_bvh_box_query(&t, q, co_stop_prim, &calls, NULL), WR_OK);
        cr_expect_eq(calls, 0);
        cr_expect_eq(wr_bvh_box_query(&t, NULL, co_stop_prim, &calls, NULL), WR_ERR_INVALID_ARG);
        wr_bvh_free(&t);
        free(bx);
    }
}

Test(collision, bvh_rejects_bad_boxes) {
    double bx[6] = {0, 0, 0, 1, -1, 1};
    wr_bvh t;
    wr_diag dg;
    cr_expect_eq(wr_bvh_build(&t, 1, bx, &dg), WR_ERR_DOMAIN);
    cr_expect_eq(dg.item, 0);
    bx[4] = NAN;
    cr_expect_eq(wr_bvh_build(&t, 1, bx, &dg), WR_ERR_DOMAIN);
    cr_expect_eq(wr_bvh_build(&t, 0, NULL, &dg), WR_OK);
    wr_bvh_free(&t);
}

/* ---- mesh level ---- */
/* two n×n grids of the unit square: A at z = 0 (obstacle), B at height z (cloth), B shifted by half
 * a cell so its vertices sit over A's face interiors */
static void co_two_sheets(int32_t n, double z, double **x, int32_t **f, int32_t *nv, int32_t *nf, uint8_t **obst) {
    int32_t i, j, s, k = 0, q = 0, nn = (n + 1) * (n + 1);
    *nv = 2 * nn;
    *nf = 4 * n * n;
    *x = (double *)malloc(sizeof(double) * 3 * (size_t)*nv);
    *f = (int32_t *)malloc(sizeof(int32_t) * 3 * (size_t)*nf);
    *obst = (uint8_t *)calloc((size_t)*nv, 1);
    for (s = 0; s < 2; ++s)
        for (j = 0; j <= n; ++j)
            for (i = 0; i <= n; ++i) {
                (*x)[3 * k] = (double)i / n + (s ? 0.37 / n : 0.0);
                (*x)[3 * k + 1] = (double)j / n + (s ? 0.29 / n : 0.0);
                (*x)[3 * k + 2] = s ? z : 0.0;
                (*obst)[k] = s == 0;
                ++k;
            }
    for (s = 0; s < 2; ++s)
        for (j = 0; j < n; ++j)
            for (i = 0; i < n; ++i) {
                int32_t v = s * nn + j * (n + 1) + i;
                int32_t t[6] = {v, v + 1, v + n + 2, v, v + n + 2, v + n + 1};
                memcpy(*f + 3 * q, t, sizeof t);
                q += 2;
            }
}

Test(collision, contacts_and_ccd_between_sheets) {
    double *x, *dx;
    int32_t *f, nv, nf, n = 6, i;
    uint8_t *ob;
    wr_collision_mesh cm;
    wr_contact_set cs;
    wr_collision_ccd_stats st;
    double alpha, E, *g;
    co_two_sheets(n, 1e-3, &x, &f, &nv, &nf, &ob);
    memset(&cs, 0, sizeof cs);
    cr_assert_eq(wr_collision_mesh_create(&cm, nv, nf, f, ob, NULL, NULL), WR_OK);
    cr_expect_eq(cm.ne, 2 * (3 * n * n + 2 * n));
    /* d̂ = 2 mm > 1 mm gap: every cloth vertex over A's interior (all (n+1)² of B, B's shifted
     * square still overlaps A except on the far rows, which sit past A's edge) has a PT contact */
    cr_assert_eq(wr_collision_contacts(&cm, x, 2e-3, &cs, NULL), WR_OK);
    cr_expect(cs.n > 0);
    cr_expect_float_eq(cs.min_distance, 1e-3, 1e-15);
    for (i = 0; i < cs.n; ++i) {
        double r[3] = {0, 0, 0};
        int k, q;
        cr_expect(cs.c[i].d < 2e-3);
        /* the stored closest-point coefficients reproduce the distance */
        for (k = 0; k < 4; ++k)
            for (q = 0; q < 3; ++q) r[q] += cs.c[i].w[k] * x[3 * cs.c[i].v[k] + q];
        cr_expect(fabs(sqrt(r[0] * r[0] + r[1] * r[1] + r[2] * r[2]) - cs.c[i].d) < 1e-15, "contact %d", i);
        /* no obstacle–obstacle and (both sheets flat, 1 mm apart) no cloth–cloth pair */
        if (cs.c[i].kind == WR_CONTACT_PT) cr_expect(!ob[cs.c[i].v[0]] || !ob[cs.c[i].v[1]]);
    }
    /* d̂ below the gap: none */
    cr_assert_eq(wr_collision_contacts(&cm, x, 0.9e-3, &cs, NULL), WR_OK);
    cr_expect_eq(cs.n, 0);
    /* energy and its gradient against FD along a vertical move of one cloth vertex */
    cr_assert_eq(wr_collision_contacts(&cm, x, 2e-3, &cs, NULL), WR_OK);
    g = (double *)calloc(3 * (size_t)nv, sizeof(double));
    cr_assert_eq(wr_collision_contact_energy(&cs, x, 2e-3, 1.0, 1, &E, g, NULL, NULL), WR_OK);
    cr_expect(E > 0.0);
    {
        int32_t v = nv / 2 + (n + 1) + 1; /* an interior vertex of B */
        double h = 1e-8, Ep, Em;
        x[3 * v + 2] += h;
        wr_collision_contact_energy(&cs, x, 2e-3, 1.0, 1, &Ep, NULL, NULL, NULL);
        x[3 * v + 2] -= 2 * h;
        wr_collision_contact_energy(&cs, x, 2e-3, 1.0, 1, &Em, NULL, NULL, NULL);
        x[3 * v + 2] += h;
        cr_expect(fabs((Ep - Em) / (2 * h) - g[3 * v + 2]) <= 1e-5 * fabs(g[3 * v + 2]), "dE/dz %g vs %g",
                  (Ep - Em) / (2 * h), g[3 * v + 2]);
        cr_expect(g[3 * v + 2] < 0.0); /* the barrier pushes the cloth up */
    }
    /* CCD: the cloth moves down by 3 mm (through A): alpha < 1/3 and the end state intersection-free */
    dx = (double *)calloc(3 * (size_t)nv, sizeof(double));
    for (i = nv / 2; i < nv; ++i) dx[3 * i + 2] = -3e-3;
    cr_assert_eq(wr_collision_max_step(&cm, x, dx, &alpha, &st, NULL), WR_OK);
    cr_expect(alpha < 1.0 / 3.0 && alpha >= 0.9 / 3.0 * (1 - 1e-9), "alpha %g", alpha);
    cr_expect(st.hits > 0 && st.candidates >= st.hits);
    {
        double *xe = (double *)malloc(sizeof(double) * 3 * (size_t)nv);
        int32_t cnt = -1;
        for (i = 0; i < 3 * nv; ++i) xe[i] = x[i] + alpha * dx[i];
        cr_assert_eq(wr_collision_mesh_self_intersects(&cm, xe, &cnt, NULL, NULL), WR_OK);
        cr_expect_eq(cnt, 0);
        /* a tilting motion that ends with B cutting through A: the full step intersects, the
         * CCD-limited one does not */
        for (i = nv / 2; i < nv; ++i) dx[3 * i + 2] = -3e-3 * x[3 * i];
        for (i = 0; i < 3 * nv; ++i) xe[i] = x[i] + dx[i];
        cr_assert_eq(wr_collision_mesh_self_intersects(&cm, xe, &cnt, NULL, NULL), WR_OK);
        cr_expect(cnt > 0);
        cr_assert_eq(wr_collision_max_step(&cm, x, dx, &alpha, &st, NULL), WR_OK);
        cr_expect(alpha < 1.0);
        for (i = 0; i < 3 * nv; ++i) xe[i] = x[i] + alpha * dx[i];
        cr_assert_eq(wr_collision_mesh_self_intersects(&cm, xe, &cnt, NULL, NULL), WR_OK);
        cr_expect_eq(cnt, 0);
        free(xe);
    }
    /* tangential motion only: nothing limits it */
    for (i = nv / 2; i < nv; ++i) {
        dx[3 * i] = 0.3;
        dx[3 * i + 2] = 0.0;
    }
    cr_assert_eq(wr_collision_max_step(&cm, x, dx, &alpha, NULL, NULL), WR_OK);
    cr_expect_eq(alpha, 1.0);
    wr_contact_set_free(&cs);
    wr_collision_mesh_free(&cm);
    free(x);
    free(dx);
    free(f);
    free(ob);
    free(g);
}

Test(collision, self_contacts_only_when_asked) {
    double *x;
    int32_t *f, nv, nf;
    uint8_t *ob;
    wr_collision_mesh cm;
    wr_collision_desc d;
    wr_contact_set cs;
    co_two_sheets(4, 1e-3, &x, &f, &nv, &nf, &ob);
    memset(ob, 0, (size_t)nv); /* both sheets are cloth */
    memset(&cs, 0, sizeof cs);
    memset(&d, 0, sizeof d);
    cr_assert_eq(wr_collision_mesh_create(&cm, nv, nf, f, ob, &d, NULL), WR_OK);
    cr_assert_eq(wr_collision_contacts(&cm, x, 2e-3, &cs, NULL), WR_OK);
    cr_expect(cs.n > 0);
    wr_collision_mesh_free(&cm);
    d.no_self = 1;
    cr_assert_eq(wr_collision_mesh_create(&cm, nv, nf, f, ob, &d, NULL), WR_OK);
    cr_assert_eq(wr_collision_contacts(&cm, x, 2e-3, &cs, NULL), WR_OK);
    cr_expect_eq(cs.n, 0);
    wr_contact_set_free(&cs);
    wr_collision_mesh_free(&cm);
    free(x);
    free(f);
    free(ob);
}

/* desc.vertex_class: a cloth triangle B 1 mm above cloth triangle A, B's corner 3 a copy of A's
 * corner 0 (one class) moving onto it, as garment.h's weld merges seam copies. Without classes the
 * pair (3, A) reaches distance 0 and CCD stops the move before it; with them the pairs of 3 against
 * A's faces, edges at 0 are skipped (they become adjacent at the merge), the move completes, and the
 * merged state has no zero-distance contact. */
Test(collision, vertex_class_lets_copies_meet) {
    double x[18] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0.01, 0.01, 1e-3, 1.01, 0.01, 1e-3, 0.01, 1.01, 1e-3}, dx[18] = {0}, xe[18];
    int32_t f[6] = {0, 1, 2, 3, 4, 5}, cls[6] = {0, 1, 2, 0, 4, 5}, i;
    wr_collision_mesh cm;
    wr_collision_desc d;
    wr_contact_set cs;
    double alpha;
    for (i = 0; i < 3; ++i) dx[9 + i] = x[i] - x[9 + i];
    for (i = 0; i < 18; ++i) xe[i] = x[i] + dx[i];
    memset(&d, 0, sizeof d);
    memset(&cs, 0, sizeof cs);
    cr_assert_eq(wr_collision_mesh_create(&cm, 6, 2, f, NULL, &d, NULL), WR_OK);
    cr_assert_eq(wr_collision_max_step(&cm, x, dx, &alpha, NULL, NULL), WR_OK);
    cr_expect(alpha < 1.0, "alpha %g without classes", alpha);
    cr_expect_eq(wr_collision_contacts(&cm, xe, 2e-3, &cs, NULL), WR_ERR_GEOMETRY); /* 3 touches A */
    wr_collision_mesh_free(&cm);
    d.vertex_class = cls;
    cr_assert_eq(wr_collision_mesh_create(&cm, 6, 2, f, NULL, &d, NULL), WR_OK);
    cls[3] = 3; /* copied at create */
    cr_assert_eq(wr_collision_max_step(&cm, x, dx, &alpha, NULL, NULL), WR_OK);
    cr_expect_eq(alpha, 1.0);
    cr_assert_eq(wr_collision_contacts(&cm, xe, 2e-3, &cs, NULL), WR_OK);
    for (i = 0; i < cs.n; ++i) cr_expect(cs.c[i].d > 0.0);
    wr_contact_set_free(&cs);
    wr_collision_mesh_free(&cm);
}

/* ON THE BROAD PHASE, the kept obstacle boxes: contacts (padding d̂/2) and CCD (no padding)
 * alternating on one collision mesh with a still obstacle swap the other padding's boxes back in
 * instead of refitting; every answer must still be the one of a freshly built mesh: the contact
 * count and minimum distance, and alpha. The cloth sheet 2.7 mm over the obstacle: d̂ = 3 mm finds
 * every pair over it only with both paddings 1.5 mm (unpadded or 1 mm obstacle boxes miss them),
 * d̂ = 2 mm finds none; the obstacle is shifted along x between rounds (the kept boxes must go),
 * which changes how many cloth vertices are over it. */
Test(collision, kept_obstacle_boxes_answer_as_a_fresh_mesh) {
    static const double dh[6] = {3e-3, 0.0, 2e-3, 3e-3, 0.0, 3e-3}; /* 0: a CCD query */
    double *x, *dx;
    int32_t *f, nv, nf, n = 8, i, r, q, found = 0;
    uint8_t *ob;
    wr_collision_mesh cm, fresh;
    wr_contact_set a, b;
    co_two_sheets(n, 2.7e-3, &x, &f, &nv, &nf, &ob);
    memset(&a, 0, sizeof a);
    memset(&b, 0, sizeof b);
    dx = (double *)calloc(3 * (size_t)nv, sizeof(double));
    for (i = nv / 2; i < nv; ++i) dx[3 * i + 2] = -4e-3, dx[3 * i] = 1e-3 * i / nv; /* through the obstacle */
    cr_assert_eq(wr_collision_mesh_create(&cm, nv, nf, f, ob, NULL, NULL), WR_OK);
    for (r = 0; r < 4; ++r) {
        for (i = 0; i < nv / 2; ++i) x[3 * i] = (double)(i % (n + 1)) / n + 0.2 * r; /* obstacle shifted */
        for (q = 0; q < 12; ++q) {
            double d = dh[q % 6];
            cr_assert_eq(wr_collision_mesh_create(&fresh, nv, nf, f, ob, NULL, NULL), WR_OK);
            if (d > 0.0) {
                cr_assert_eq(wr_collision_contacts(&cm, x, d, &a, NULL), WR_OK);
                cr_assert_eq(wr_collision_contacts(&fresh, x, d, &b, NULL), WR_OK);
                cr_expect_eq(a.n, b.n, "round %d query %d (d̂ %g): %d contacts, fresh mesh %d", (int)r, (int)q, d, (int)a.n,
                             (int)b.n);
                cr_expect_eq(a.min_distance, b.min_distance);
                if (d == 3e-3) found += b.n > 0;
                else cr_expect_eq(b.n, 0);
            } else {
                double al, bl;
                cr_assert_eq(wr_collision_max_step(&cm, x, dx, &al, NULL, NULL), WR_OK);
                cr_assert_eq(wr_collision_max_step(&fresh, x, dx, &bl, NULL, NULL), WR_OK);
                cr_expect_eq(al, bl, "round %d query %d: alpha %.17g, fresh %.17g", (int)r, (int)q, al, bl);
                cr_expect_lt(bl, 1.0);
            }
            wr_collision_mesh_free(&fresh);
        }
    }
    cr_expect_eq(found, 4 * 6, "every d̂ = 3 mm query finds contacts (%d)", (int)found);
    wr_contact_set_free(&a);
    wr_contact_set_free(&b);
    wr_collision_mesh_free(&cm);
    free(x);
    free(dx);
    free(f);
    free(ob);
}

static void co_expect_same_set(const wr_contact_set *a, const wr_contact_set *b, int32_t step, int32_t call) {
    int32_t i, k;
    cr_expect_eq(a->n, b->n, "step %d call %d: %d contacts, no-record mesh %d", (int)step, (int)call, (int)a->n, (int)b->n);
    cr_expect_eq(a->min_distance, b->min_distance, "step %d call %d: min distance %.17g vs %.17g", (int)step, (int)call,
                 a->min_distance, b->min_distance);
    for (i = 0; i < a->n && i < b->n; ++i) {
        const wr_contact *p = a->c + i, *q = b->c + i;
        int same = p->kind == q->kind && p->piece == q->piece && p->d == q->d;
        for (k = 0; k < 4; ++k) same = same && p->v[k] == q->v[k] && p->w[k] == q->w[k];
        if (!same) {
            cr_expect(same, "step %d call %d: contact %d differs (in order, bit for bit)", (int)step, (int)call, (int)i);
            return;
        }
    }
}

/* ON REPEATED QUERIES: a mesh answering repeated wr_collision_contacts calls from its record gives,
 * at every call, the set (same pairs, same order, same bits) of a mesh that queries every time (its
 * record dropped before each call, so both follow one rebuild schedule), over 150 steps of a wavy
 * cloth sheet sliding over an obstacle sheet that shifts too (self-contact on): each step asks at
 * x twice, every third step a CCD query comes between, every fifth step another d̂ does, so the
 * record must be refused there; the cloth trees are rebuilt twice, each time on a repeated call
 * (where the record must be refused too), and the obstacle trees' rebuild schedule runs on the
 * CCD / contact paddings. A repeated call does answer from the record (a mark left in the set
 * survives it), and one after the caller emptied the set queries again. */
Test(collision, repeated_contact_queries_answer_as_a_fresh_mesh) {
    const double dhat = 4e-3;
    double *x, *dx;
    int32_t *f, nv, nf, n = 8, i, step, call;
    uint8_t *ob;
    wr_collision_mesh cm, ref;
    wr_contact_set a, b;
    co_two_sheets(n, 3e-3, &x, &f, &nv, &nf, &ob);
    memset(&a, 0, sizeof a);
    memset(&b, 0, sizeof b);
    dx = (double *)calloc(3 * (size_t)nv, sizeof(double));
    for (i = nv / 2; i < nv; ++i) dx[3 * i + 2] = -2e-3;
    cr_assert_eq(wr_collision_mesh_create(&cm, nv, nf, f, ob, NULL, NULL), WR_OK);
    cr_assert_eq(wr_collision_mesh_create(&ref, nv, nf, f, ob, NULL, NULL), WR_OK);
    /* one query first, so the rebuilds (every 64th query) fall on repeated calls (4 per step) */
    cr_assert_eq(wr_collision_contacts(&cm, x, 0.5 * dhat, &a, NULL), WR_OK);
    cr_assert_eq(wr_collision_contacts(&ref, x, 0.5 * dhat, &b, NULL), WR_OK);
    for (step = 0; step < 150; ++step) {
        for (i = 0; i < nv / 2; ++i) x[3 * i + 1] = (double)(i / (n + 1)) / n + 1e-3 * (step % 7); /* obstacle moves */
        for (i = nv / 2; i < nv; ++i) { /* the cloth: slid along x, waved in z (some pairs within d̂) */
            double u = (double)((i - nv / 2) % (n + 1)) / n, v = (double)((i - nv / 2) / (n + 1)) / n;
            x[3 * i] = u + 0.37 / n + 0.013 * (step % 40);
            x[3 * i + 2] = 3e-3 + 2.5e-3 * sin(6.0 * u + 4.0 * v + 0.21 * step);
        }
        for (call = 0; call < 4; ++call) {
            double d = call == 2 && step % 5 == 0 ? 0.5 * dhat : dhat;
            if (call == 2 && step % 3 == 0) {
                double al, bl;
                cr_assert_eq(wr_collision_max_step(&cm, x, dx, &al, NULL, NULL), WR_OK);
                cr_assert_eq(wr_collision_max_step(&ref, x, dx, &bl, NULL, NULL), WR_OK);
                cr_expect_eq(al, bl, "step %d: CCD alpha %.17g, no-record mesh %.17g", (int)step, al, bl);
                continue;
            }
            ref.cvalid = 0; /* the reference queries every time */
            cr_assert_eq(wr_collision_contacts(&cm, x, d, &a, NULL), WR_OK);
            cr_assert_eq(wr_collision_contacts(&ref, x, d, &b, NULL), WR_OK);
            co_expect_same_set(&a, &b, step, call);
        }
        cr_expect_eq(cm.queries, ref.queries, "step %d: %d queries, no-record mesh %d", (int)step, (int)cm.queries,
                     (int)ref.queries);
    }
    /* the last call at x was answered: a repeat is answered from the record (the mark stays), and
     * after the caller emptied the set, by a query again */
    cr_assert(a.n > 0, "the last step has contacts (%d)", (int)a.n);
    if (cm.queries % 64 == 0) { /* a rebuild due (collision.h's WR__COLL_REBUILD): two queries on */
        cr_assert_eq(wr_collision_contacts(&cm, x, 0.5 * dhat, &a, NULL), WR_OK);
        cr_assert_eq(wr_collision_contacts(&cm, x, dhat, &a, NULL), WR_OK);
    }
    a.min_distance = -1.0;
    cr_assert_eq(wr_collision_contacts(&cm, x, dhat, &a, NULL), WR_OK);
    cr_expect_eq(a.min_distance, -1.0, "a repeated call queried again");
    a.n = 0;
    cr_assert_eq(wr_collision_contacts(&cm, x, dhat, &a, NULL), WR_OK);
    cr_expect_eq(a.n, b.n, "after the set was emptied: %d contacts, expected %d", (int)a.n, (int)b.n);
    wr_contact_set_free(&a);
    wr_contact_set_free(&b);
    wr_collision_mesh_free(&cm);
    wr_collision_mesh_free(&ref);
    free(x);
    free(dx);
    free(f);
    free(ob);
}

/* ON LOCAL CCD: wr_collision_max_step_local returns wr_collision_max_step's alpha bit for bit, and
 * the same limiting pair, on 600 random moves of 1-4 neighbouring vertices of a cloth sheet (z
 * jittered by ±0.3 mm round 1 mm, self-contact on) over an obstacle sheet, one move in eight of
 * obstacle vertices. Targets are uniform in each vertex's start position ± R (R = half a cell: the
 * moving faces sweep over their neighbours and through the obstacle), the boxes the local trees are
 * bound to; each move is applied at its alpha, so later trials start from changed states. (Two
 * pairs can tie, e.g. a vertex passing a face's edge: PT and EE then give one time, and either may
 * be reported: the local one's own ACCD time must then be alpha.) Both
 * pair kinds limit some trials and some trials run free (else the case tests little). Then the
 * refusals: not bound, a vertex listed twice, a target outside its box, an unlisted vertex moving. */
Test(collision, max_step_local_equals_full) {
    const int32_t n = 12, off[4] = {0, 1, 13, 14}; /* a vertex, its +x, +y, +xy neighbours (n + 1 = 13) */
    const double R = 0.5 / 12;
    int32_t nv, nf, *f, trial, hits = 0, clear = 0, same = 0, kinds[2] = {0, 0}, i, k, mv[4];
    double *x, *dx, *vb, aloc, afull;
    uint8_t *ob;
    wr_collision_mesh cm;
    wr_collision_ccd_stats sf, sl;
    wr_diag dg;
    wr_rng rng;
    co_two_sheets(n, 1e-3, &x, &f, &nv, &nf, &ob);
    wr_rng_seed(&rng, 31);
    for (i = nv / 2; i < nv; ++i) x[3 * i + 2] += 3e-4 * (2.0 * wr_rng_uniform(&rng) - 1.0);
    dx = (double *)calloc(3 * (size_t)nv, sizeof(double));
    vb = (double *)malloc(sizeof(double) * 6 * (size_t)nv);
    for (i = 0; i < nv; ++i)
        for (k = 0; k < 3; ++k) { /* ± 1e-9 m: x + alpha dx may round past a target on the box face */
            vb[6 * i + k] = x[3 * i + k] - R - 1e-9;
            vb[6 * i + 3 + k] = x[3 * i + k] + R + 1e-9;
        }
    cr_assert_eq(wr_collision_mesh_create(&cm, nv, nf, f, ob, NULL, NULL), WR_OK);
    cr_expect_eq(wr_collision_max_step_local(&cm, x, dx, 0, mv, &aloc, NULL, &dg), WR_ERR_INVALID_ARG, "not bound yet");
    cr_assert_eq(wr_collision_mesh_bound(&cm, x, vb, &dg), WR_OK, "%s", dg.message);
    for (trial = 0; trial < 600; ++trial) {
        int32_t nm = 1 + trial % 4, sheet = trial % 8 == 7 ? 0 : 1, base = (n + 1) * (n + 1);
        int32_t i0 = (int32_t)wr_rng_below(&rng, (uint32_t)n), j0 = (int32_t)wr_rng_below(&rng, (uint32_t)n);
        for (k = 0; k < nm; ++k) {
            int32_t v = sheet * base + j0 * (n + 1) + i0 + off[k];
            mv[k] = v;
            for (i = 0; i < 3; ++i) {
                double c = 0.5 * (vb[6 * v + i] + vb[6 * v + 3 + i]);
                dx[3 * v + i] = c + R * (2.0 * wr_rng_uniform(&rng) - 1.0) - x[3 * v + i];
            }
        }
        cr_assert_eq(wr_collision_max_step(&cm, x, dx, &afull, &sf, &dg), WR_OK, "%s", dg.message);
        cr_assert_eq(wr_collision_max_step_local(&cm, x, dx, nm, mv, &aloc, &sl, &dg), WR_OK, "trial %d: %s", (int)trial,
                     dg.message);
        cr_expect_eq(aloc, afull, "trial %d: local alpha %.17g, full %.17g", (int)trial, aloc, afull);
        if (afull < 1.0) { /* the same limiting pair, or (a tie) one whose own time of impact is alpha */
            double x12[12], d12[12], toi = 2.0;
            same += sl.worst_kind == sf.worst_kind && !memcmp(sl.worst_v, sf.worst_v, sizeof sl.worst_v);
            cr_assert(sl.worst_kind >= 0, "trial %d: no limiting pair", (int)trial);
            for (k = 0; k < 4; ++k)
                for (i = 0; i < 3; ++i) x12[3 * k + i] = x[3 * sl.worst_v[k] + i], d12[3 * k + i] = dx[3 * sl.worst_v[k] + i];
            cr_expect(wr_collision_accd((wr_contact_kind)sl.worst_kind, x12, d12, WR_COLLISION_CCD_KEEP, 1.0, 0, &toi));
            cr_expect_eq(toi, afull, "trial %d: the local limiting pair's own time %.17g", (int)trial, toi);
        }
        cr_expect_leq(sl.candidates, sf.candidates);
        if (afull < 1.0) hits++, kinds[sf.worst_kind]++;
        else clear++;
        for (k = 0; k < nm; ++k)
            for (i = 0; i < 3; ++i) {
                x[3 * mv[k] + i] += afull * dx[3 * mv[k] + i];
                dx[3 * mv[k] + i] = 0.0;
            }
    }
    cr_log_info("local CCD: %d of 600 moves limited (%d PT, %d EE; the same limiting pair in %d), %d free", (int)hits,
                (int)kinds[0], (int)kinds[1], (int)same, (int)clear);
    cr_expect(kinds[0] > 20 && kinds[1] > 20 && clear > 20, "PT %d, EE %d, free %d", (int)kinds[0], (int)kinds[1],
              (int)clear);
    mv[0] = mv[1] = nv / 2 + 20;
    cr_expect_eq(wr_collision_max_step_local(&cm, x, dx, 2, mv, &aloc, NULL, &dg), WR_ERR_INVALID_ARG, "listed twice");
    dx[3 * mv[0]] = 2.0 * R;
    cr_expect_eq(wr_collision_max_step_local(&cm, x, dx, 1, mv, &aloc, NULL, &dg), WR_ERR_DOMAIN, "out of its box");
    cr_expect_eq(dg.item, mv[0]);
    dx[3 * mv[0]] = 0.0;
    dx[3 * (mv[0] + 1) + 2] = -1e-3; /* a neighbour moves unlisted: its own faces meet it */
    cr_expect_eq(wr_collision_max_step_local(&cm, x, dx, 1, mv, &aloc, NULL, &dg), WR_ERR_INVALID_ARG, "unlisted");
    cr_expect_eq(dg.item, mv[0] + 1);
    cr_expect_eq(wr_collision_max_step_local(&cm, x, dx, 1, mv, &aloc, NULL, &dg), WR_ERR_INVALID_ARG, "marks cleared");
    wr_collision_mesh_free(&cm);
    free(x);
    free(dx);
    free(vb);
    free(f);
    free(ob);
}

Test(collision, mesh_self_intersection_exact) {
    /* a strip of two triangles folded about their shared edge: fine at any angle but 0 (flat onto
     * each other, exact) and a far triangle pierced by the strip */
    double x[18] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0, 0.3, 0.3, -1, 0.3, 0.4, 1};
    int32_t f[9] = {0, 1, 2, 1, 3, 2, 4, 5, 0}, cnt, first[2];
    wr_collision_mesh cm;
    cr_assert_eq(wr_collision_mesh_create(&cm, 6, 2, f, NULL, NULL, NULL), WR_OK);
    cr_assert_eq(wr_collision_mesh_self_intersects(&cm, x, &cnt, first, NULL), WR_OK);
    cr_expect_eq(cnt, 0); /* flat strip: neighbours share an edge only */
    co_set(x + 9, 0, 0, 0);  /* fold vertex 3 exactly onto vertex 0: triangles coincide beyond the edge */
    cr_assert_eq(wr_collision_mesh_self_intersects(&cm, x, &cnt, first, NULL), WR_OK);
    cr_expect_eq(cnt, 1);
    co_set(x + 9, 0.1, 0.1, 1e-9); /* almost folded: no intersection */
    cr_assert_eq(wr_collision_mesh_self_intersects(&cm, x, &cnt, first, NULL), WR_OK);
    cr_expect_eq(cnt, 0);
    wr_collision_mesh_free(&cm);
    /* third triangle (4, 5, 0) shares vertex 0 with the first and pierces it */
    co_set(x + 9, 1, 1, 0);
    cr_assert_eq(wr_collision_mesh_create(&cm, 6, 3, f, NULL, NULL, NULL), WR_OK);
    cr_assert_eq(wr_collision_mesh_self_intersects(&cm, x, &cnt, first, NULL), WR_OK);
    cr_expect_eq(cnt, 1);
    cr_expect(first[0] == 0 && first[1] == 2);
    x[14] = 0.5; /* 4 now above the plane too: (4,5,0) touches the strip only at vertex 0 */
    x[17] = 1.0;
    cr_assert_eq(wr_collision_mesh_self_intersects(&cm, x, &cnt, first, NULL), WR_OK);
    cr_expect_eq(cnt, 0);
    wr_collision_mesh_free(&cm);
}

Test(collision, meshes_intersect_and_bad_input) {
    double xa[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0}, xb[9] = {0.2, 0.2, -1, 0.3, 0.2, 1, 0.25, 0.3, 1};
    int32_t fa[3] = {0, 1, 2}, cnt, bad[3] = {0, 1, 5}, rep[3] = {0, 1, 1};
    wr_collision_mesh cm;
    wr_diag dg;
    cr_assert_eq(wr_collision_meshes_intersect(3, xa, 1, fa, 3, xb, 1, fa, &cnt, NULL), WR_OK);
    cr_expect_eq(cnt, 1);
    xb[2] = 0.5;
    cr_assert_eq(wr_collision_meshes_intersect(3, xa, 1, fa, 3, xb, 1, fa, &cnt, NULL), WR_OK);
    cr_expect_eq(cnt, 0);
    cr_expect_eq(wr_collision_mesh_create(&cm, 3, 1, bad, NULL, NULL, &dg), WR_ERR_TOPOLOGY);
    cr_expect_eq(dg.item, 0);
    cr_expect_eq(wr_collision_mesh_create(&cm, 3, 1, rep, NULL, NULL, &dg), WR_ERR_TOPOLOGY);
    cr_assert_eq(wr_collision_mesh_create(&cm, 3, 1, fa, NULL, NULL, NULL), WR_OK);
    xa[4] = NAN;
    cr_expect_eq(wr_collision_contacts(&cm, xa, 1e-3, NULL, &dg), WR_ERR_INVALID_ARG);
    {
        wr_contact_set cs;
        memset(&cs, 0, sizeof cs);
        cr_expect_eq(wr_collision_contacts(&cm, xa, 1e-3, &cs, &dg), WR_ERR_DOMAIN);
        cr_expect_eq(dg.item, 1);
        xa[4] = 0.0;
        cr_expect_eq(wr_collision_contacts(&cm, xa, 0.0, &cs, &dg), WR_ERR_DOMAIN);
        wr_contact_set_free(&cs);
    }
    wr_collision_mesh_free(&cm);
}
