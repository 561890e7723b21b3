/* wrinkle/predicates.h — exact geometric predicates: 2D orientation, 2D in-circle and 3D orientation,
 * adaptive (a floating-point evaluation with a forward error bound; exact expansion arithmetic only
 * when the bound cannot certify the sign). Used by triangulate.h (CDT) and collision.h (intersection
 * checks).
 * wrinkle v0.1.0 — MIT licence (see LICENSE). Needs core.h, libc and libm.
 *
 * Reference: J. R. Shewchuk, "Adaptive Precision Floating-Point Arithmetic and Fast Robust Geometric
 * Predicates", Discrete & Computational Geometry 18(3):305–363, 1997. Taken from it (facts, written
 * here from the paper, not from its code): the expansion representation (a sum of nonoverlapping
 * doubles sorted by increasing magnitude, whose sign is that of its largest component; Sec. 2),
 * TWO-SUM, FAST-TWO-SUM, SPLIT (multiplier 2^27 + 1) and TWO-PRODUCT, the FAST-EXPANSION-SUM and
 * SCALE-EXPANSION algorithms (Sec. 2), and the error bounds of the first, floating-point stage of
 * each predicate (Sec. 4): ccwerrboundA = (3 + 16ε)ε, iccerrboundA = (10 + 96ε)ε, o3derrboundA =
 * (7 + 56ε)ε, times the permanent (the determinant with every term's absolute value), ε = 2^-53.
 * Two stages here instead of the paper's four: the bound-A filter, then the whole determinant
 * exactly (its intermediate stages B and C, which reuse the filter's rounded products, are not
 * implemented); the exact stage keeps a coordinate difference as one component when the subtraction
 * was exact (lattice and grid input, the common case of the CDT's degenerate tests: several times
 * cheaper).
 *
 * API (points are double[2] or double[3]; no allocation, no state)
 *   wr_orient2d(a, b, c)          exact sign of det[a−c; b−c]: > 0 when a, b, c are counter-clockwise,
 *                                 < 0 clockwise, exactly 0 iff collinear (twice the signed area)
 *   wr_orient2d_value(a, b, c)    the same determinant's value to a few ulps (the exact expansion,
 *                                 summed): for intersection points computed from two orientations
 *   wr_incircle(a, b, c, d)       exact sign of the lifted 3×3 determinant (rows x−d, y−d, |p−d|²
 *                                 for p = a, b, c): for CCW a, b, c > 0 iff d is strictly inside
 *                                 their circumcircle, 0 iff cocircular
 *   wr_orient3d(a, b, c, d)       exact sign of det[b−a; c−a; d−a] = ((b−a)×(c−a))·(d−a): > 0 when d
 *                                 lies on the side the normal of (a, b, c) points to, 0 iff coplanar
 *                                 (the opposite sign of the paper's orient3d)
 *   wr_orient2d_fast / wr_incircle_fast   plain floating point (not robust), for comparison
 *   WR_PRED_EPS                   ε = 2^-53, the relative rounding error of one operation
 *   (internal, for triangulate.h's loops: wr__orient2d_in, wr__incircle_in, wr__incircle_fixed — the
 *   same signs with the filter inline; see their comment below)
 *   The magnitudes returned by the exact predicates are approximations; only the signs are exact
 *   (wr_orient2d_value is the one that returns an accurate value).
 *
 * EXAMPLE
 *     double p[2], q[2] = {12.0, 12.0}, r[2] = {24.0, 24.0};
 *     double a[2] = {0.0, 0.0}, b[2] = {1.0, 0.0}, c[2] = {1.0, 1.0}, d[2] = {0.0, 1.0};
 *     double A[3] = {0, 0, 0}, B[3] = {1, 0, 0}, C[3] = {0, 1, 0}, D[3] = {0.3, 0.3, 0.0}, E[3] = {0.3, 0.3, 1e-30};
 *     p[0] = 0.5;  p[1] = nextafter(0.5, 1.0);          // one ulp above the line y = x through q and r
 *     printf("orient2d: exact %+g, plain floating point %+g\n", wr_orient2d(p, q, r), wr_orient2d_fast(p, q, r));
 *     if (!(wr_orient2d(p, q, r) > 0.0)) return 1;       // p, q, r turn counter-clockwise
 *     if (wr_incircle(a, b, c, d) != 0.0) return 1;      // the unit square's corners are cocircular
 *     if (wr_orient3d(A, B, C, D) != 0.0 || !(wr_orient3d(A, B, C, E) > 0.0)) return 1;
 *
 * ON FLAGS AND RANGE
 *   The signs are exact for all finite inputs provided no intermediate overflows or underflows:
 *   every nonzero |coordinate| within [1e-50, 1e50] is safe (the smallest expansion component of
 *   incircle is about |coordinate·ε|⁴·ε²; tests run at 1e-60 and 1e60). Needs strict IEEE-754 binary64
 *   round-to-nearest: compile WITHOUT -ffast-math / -Ofast / -funsafe-math-optimizations, WITH
 *   -ffp-contract=off (FMA contraction would break TWO-PRODUCT and the error bounds), and on 32-bit
 *   x86 with -msse2 -mfpmath=sse (no x87 extended precision).
 *
 * ON THREADS
 *   No global state; every function is reentrant.
 */
#ifndef WRINKLE_PREDICATES_H
#define WRINKLE_PREDICATES_H

#include <math.h> /* fabs: the inline filters below */

#include "core.h"

#ifdef __cplusplus
extern "C" {
#endif

#define WR_PRED_EPS 1.1102230246251565e-16 /* 2^-53, half an ulp of 1 (Shewchuk's ε) */

WRDEF double wr_orient2d(const double *a, const double *b, const double *c);
/* det[a−c; b−c] to a few ulps (the filter's value may be off by a large relative amount when it only
 * certifies the sign): where a crossing point is computed from two of them, its rounding error is
 * then a few ulps of its own coordinates. */
WRDEF double wr_orient2d_value(const double *a, const double *b, const double *c);
WRDEF double wr_incircle(const double *a, const double *b, const double *c, const double *d);
WRDEF double wr_orient3d(const double a[3], const double b[3], const double c[3], const double d[3]);
WRDEF double wr_orient2d_fast(const double *a, const double *b, const double *c);
WRDEF double wr_incircle_fast(const double *a, const double *b, const double *c, const double *d);

/* ---- internal: the filters inline (triangulate.h's hot loops; issue 17) ----
 * wr__orient2d_in / wr__incircle_in: the same sign as wr_orient2d / wr_incircle, the filter evaluated
 * in place (its rounded values and bound are those of the public predicate) and the public predicate
 * called only when the filter cannot decide. wr__incircle_fixed: incircle(a, b, c, x) for one triangle
 * and many x, through the filter of incircle(b, c, x, a), whose sign is the opposite one (the lifted
 * 4x4 determinant of (b, c, x, a) is that of (a, b, c, x) with its rows shifted cyclically: an odd
 * permutation); the terms without x are computed once (wr__icfix_set), each rounded value the one that
 * filter computes, in the same order, so its error bound holds; undecided: wr_incircle(a, b, c, x). */
#define WR__CCW_BOUND ((3.0 + 16.0 * WR_PRED_EPS) * WR_PRED_EPS)  /* Shewchuk's ccwerrboundA */
#define WR__ICC_BOUND ((10.0 + 96.0 * WR_PRED_EPS) * WR_PRED_EPS) /* Shewchuk's iccerrboundA */
/* The two filters (Shewchuk 1997, error bound A), the one place both the public predicates and the
 * inline calls evaluate them: 1 with *det when the rounded determinant's sign is certain, else 0
 * (incircle's *perm, the permanent, is what the slower stages of wr_incircle reuse). */
static inline int wr__orient2d_filter(const double *a, const double *b, const double *c, double *det) {
    double l = (a[0] - c[0]) * (b[1] - c[1]), r = (a[1] - c[1]) * (b[0] - c[0]), sum;
    *det = l - r;
    if (l > 0.0) {
        if (r <= 0.0) return 1;
        sum = l + r;
    } else if (l < 0.0) {
        if (r >= 0.0) return 1;
        sum = -l - r;
    } else {
        return 1;
    }
    sum *= WR__CCW_BOUND;
    return *det >= sum || -*det >= sum;
}
static inline int wr__incircle_filter(const double *a, const double *b, const double *c, const double *d, double *det,
                                      double *perm) {
    double adx = a[0] - d[0], ady = a[1] - d[1], bdx = b[0] - d[0], bdy = b[1] - d[1];
    double cdx = c[0] - d[0], cdy = c[1] - d[1];
    double bc1 = bdx * cdy, bc2 = cdx * bdy, ca1 = cdx * ady, ca2 = adx * cdy, ab1 = adx * bdy, ab2 = bdx * ady;
    double al = adx * adx + ady * ady, bl = bdx * bdx + bdy * bdy, cl = cdx * cdx + cdy * cdy, eb;
    *det = al * (bc1 - bc2) + bl * (ca1 - ca2) + cl * (ab1 - ab2);
    *perm = (fabs(bc1) + fabs(bc2)) * al + (fabs(ca1) + fabs(ca2)) * bl + (fabs(ab1) + fabs(ab2)) * cl;
    eb = WR__ICC_BOUND * *perm;
    return *det > eb || -*det > eb;
}
static inline double wr__orient2d_in(const double *a, const double *b, const double *c) {
    double det;
    return wr__orient2d_filter(a, b, c, &det) ? det : wr_orient2d(a, b, c);
}
static inline double wr__incircle_in(const double *a, const double *b, const double *c, const double *d) {
    double det, perm;
    return wr__incircle_filter(a, b, c, d, &det, &perm) ? det : wr_incircle(a, b, c, d);
}
typedef struct wr__icfix {
    const double *a, *b, *c;
    double pdx, pdy, qdx, qdy, pl, ql, pq, pqa; /* b - a, c - a, their lifts, cross product, permanent */
} wr__icfix;
static inline void wr__icfix_set(wr__icfix *F, const double *a, const double *b, const double *c) {
    double pq1, pq2;
    F->a = a;
    F->b = b;
    F->c = c;
    F->pdx = b[0] - a[0];
    F->pdy = b[1] - a[1];
    F->qdx = c[0] - a[0];
    F->qdy = c[1] - a[1];
    pq1 = F->pdx * F->qdy;
    pq2 = F->qdx * F->pdy;
    F->pl = F->pdx * F->pdx + F->pdy * F->pdy;
    F->ql = F->qdx * F->qdx + F->qdy * F->qdy;
    F->pq = pq1 - pq2;
    F->pqa = fabs(pq1) + fabs(pq2);
}
static inline double wr__incircle_fixed(const wr__icfix *F, const double *x) {
    double rdx = x[0] - F->a[0], rdy = x[1] - F->a[1];
    double qr1 = F->qdx * rdy, qr2 = rdx * F->qdy, rp1 = rdx * F->pdy, rp2 = F->pdx * rdy;
    double rl = rdx * rdx + rdy * rdy;
    double det = F->pl * (qr1 - qr2) + F->ql * (rp1 - rp2) + rl * F->pq;
    double perm = (fabs(qr1) + fabs(qr2)) * F->pl + (fabs(rp1) + fabs(rp2)) * F->ql + F->pqa * rl;
    double fixed_bound = WR__ICC_BOUND * perm;
    if (det > fixed_bound || -det > fixed_bound) return -det;
    return wr_incircle(F->a, F->b, F->c, x);
}

#ifdef __cplusplus
}
#endif
#endif /* WRINKLE_PREDICATES_H */

/* ============================================================================================ */
#ifdef WRINKLE_IMPLEMENTATION
#ifndef WRINKLE_PREDICATES_IMPLEMENTATION_DONE
#define WRINKLE_PREDICATES_IMPLEMENTATION_DONE

#include <math.h>
#include <string.h>

#ifdef __cplusplus
extern "C" {
#endif

/* ---- expansion arithmetic (Shewchuk 1997, Sec. 2) ----
 * An expansion is an array of doubles, increasing magnitude, nonoverlapping, whose exact sum is the
 * value; its sign is the sign of its last (largest) component. */
#define WR__SPLITTER 134217729.0                               /* 2^27 + 1: Dekker's split into 26+26 bits */
#define WR__O3D_BOUND ((7.0 + 56.0 * WR_PRED_EPS) * WR_PRED_EPS)  /* Shewchuk's o3derrboundA */

static void wr__two_sum(double a, double b, double *x, double *y) {
    double s = a + b, bv = s - a, av = s - bv;
    *x = s;
    *y = (a - av) + (b - bv);
}
static void wr__fast_two_sum(double a, double b, double *x, double *y) { /* needs |a| >= |b| */
    double s = a + b;
    *x = s;
    *y = b - (s - a);
}
static void wr__two_diff(double a, double b, double *x, double *y) {
    double s = a - b, bv = a - s, av = s + bv;
    *x = s;
    *y = (a - av) + (bv - b);
}
static void wr__split(double a, double *hi, double *lo) {
    double c = WR__SPLITTER * a, big = c - a;
    *hi = c - big;
    *lo = a - *hi;
}
static void wr__two_prod(double a, double b, double *x, double *y) {
    double p = a * b, ah, al, bh, bl, e1, e2, e3;
    wr__split(a, &ah, &al);
    wr__split(b, &bh, &bl);
    e1 = p - ah * bh;
    e2 = e1 - al * bh;
    e3 = e2 - ah * bl;
    *x = p;
    *y = al * bl - e3;
}
/* h = e + f; merge by magnitude then one running two-sum (FAST-EXPANSION-SUM), zeros dropped. */
static int wr__exp_sum(int ne, const double *e, int nf, const double *f, double *h) {
    double q, qn, hh, g;
    int i = 0, j = 0, k = 0;
    if (ne == 0 && nf == 0) return 0;
    if (j >= nf || (i < ne && fabs(e[i]) < fabs(f[j])))
        q = e[i++];
    else
        q = f[j++];
    while (i < ne || j < nf) {
        if (j >= nf || (i < ne && fabs(e[i]) < fabs(f[j])))
            g = e[i++];
        else
            g = f[j++];
        wr__two_sum(q, g, &qn, &hh);
        q = qn;
        if (hh != 0.0) h[k++] = hh;
    }
    if (q != 0.0 || k == 0) h[k++] = q;
    return k;
}
/* h = e * b (SCALE-EXPANSION), zeros dropped. h has room for 2·ne. */
static int wr__exp_scale(int ne, const double *e, double b, double *h) {
    double q, hh, p1, p0, s, t;
    int i, k = 0;
    if (ne == 0) return 0;
    wr__two_prod(e[0], b, &q, &hh);
    if (hh != 0.0) h[k++] = hh;
    for (i = 1; i < ne; ++i) {
        wr__two_prod(e[i], b, &p1, &p0);
        wr__two_sum(q, p0, &s, &hh);
        if (hh != 0.0) h[k++] = hh;
        wr__fast_two_sum(p1, s, &q, &t);
        if (t != 0.0) h[k++] = t;
    }
    if (q != 0.0 || k == 0) h[k++] = q;
    return k;
}
/* h = e * f with e, f short; h has room for 2·ne·nf (<= 512 here). */
#define WR__EXP_MAX 512
static int wr__exp_mul(int ne, const double *e, int nf, const double *f, double *h) {
    double sc[64], acc[WR__EXP_MAX];
    int j, ns, nh = 0;
    for (j = 0; j < nf; ++j) {
        ns = wr__exp_scale(ne, e, f[j], sc);
        nh = wr__exp_sum(nh, h, ns, sc, acc);
        memcpy(h, acc, sizeof(double) * (size_t)nh);
    }
    if (nh == 0) h[nh++] = 0.0;
    return nh;
}
static void wr__exp_neg(int n, double *e) {
    int i;
    for (i = 0; i < n; ++i) e[i] = -e[i];
}

/* a - b as an expansion of 1 or 2 components (1 when the difference is exact, which is the common
 * case for lattice-like input: the exact stage then costs a fraction of the general one) */
static int wr__diff_exp(double a, double b, double *e) {
    double hi, lo;
    wr__two_diff(a, b, &hi, &lo);
    if (lo == 0.0) {
        e[0] = hi;
        return 1;
    }
    e[0] = lo;
    e[1] = hi;
    return 2;
}

/* The orientation determinant as an exact expansion s[0..n) (components by increasing magnitude). */
static int wr__orient_expansion(const double *a, const double *b, const double *c, double *s) {
    double acx[2], acy[2], bcx[2], bcy[2], l[8], r[8];
    int nl, nr, n1, n2, n3, n4;
    n1 = wr__diff_exp(a[0], c[0], acx);
    n2 = wr__diff_exp(a[1], c[1], acy);
    n3 = wr__diff_exp(b[0], c[0], bcx);
    n4 = wr__diff_exp(b[1], c[1], bcy);
    nl = wr__exp_mul(n1, acx, n4, bcy, l);
    nr = wr__exp_mul(n2, acy, n3, bcx, r);
    wr__exp_neg(nr, r);
    return wr__exp_sum(nl, l, nr, r, s);
}

static double wr__orient_exact(const double *a, const double *b, const double *c) {
    double s[16];
    int ns = wr__orient_expansion(a, b, c, s);
    return s[ns - 1]; /* the sign (all callers need) is the largest component's */
}


static double wr__incircle_exact(const double *a, const double *b, const double *c, const double *d) {
    double dx[3][2], dy[3][2], t1[8], t2[8], lift[16], c1[16], c2[16], cr[32], term[3][WR__EXP_MAX],
        s01[2 * WR__EXP_MAX], tot[3 * WR__EXP_MAX];
    const double *p[3];
    int nterm[3], nx[3], ny[3], i, n1, n2, nl, ncr, n01, ntot;
    p[0] = a;
    p[1] = b;
    p[2] = c;
    for (i = 0; i < 3; ++i) {
        nx[i] = wr__diff_exp(p[i][0], d[0], dx[i]);
        ny[i] = wr__diff_exp(p[i][1], d[1], dy[i]);
    }
    for (i = 0; i < 3; ++i) {
        int j = (i + 1) % 3, k = (i + 2) % 3;
        /* lift_i · (dx_j dy_k - dy_j dx_k): cofactor expansion along the lifted column */
        n1 = wr__exp_mul(nx[i], dx[i], nx[i], dx[i], t1);
        n2 = wr__exp_mul(ny[i], dy[i], ny[i], dy[i], t2);
        nl = wr__exp_sum(n1, t1, n2, t2, lift);
        n1 = wr__exp_mul(nx[j], dx[j], ny[k], dy[k], c1);
        n2 = wr__exp_mul(ny[j], dy[j], nx[k], dx[k], c2);
        wr__exp_neg(n2, c2);
        ncr = wr__exp_sum(n1, c1, n2, c2, cr);
        nterm[i] = wr__exp_mul(nl, lift, ncr, cr, term[i]);
    }
    n01 = wr__exp_sum(nterm[0], term[0], nterm[1], term[1], s01);
    ntot = wr__exp_sum(n01, s01, nterm[2], term[2], tot);
    return tot[ntot - 1];
}

/* Double-double arithmetic (a value hi + lo, |lo| <= ulp(hi)/2): products split exactly by
 * two_prod, sums by two_sum, only the low-order cross terms rounded. */
static inline void wr__dd_add(double ah, double al, double bh, double bl, double *h, double *l) {
    double s, e;
    wr__two_sum(ah, bh, &s, &e);
    wr__two_sum(s, e + (al + bl), h, l);
}
static inline void wr__dd_mul(double ah, double al, double bh, double bl, double *h, double *l) {
    double p, e;
    wr__two_prod(ah, bh, &p, &e);
    wr__two_sum(p, e + (ah * bl + al * bh), h, l);
}

/* The incircle determinant in double-double: the differences exact (two_diff), every product and sum
 * of the cofactor expansion within a few eps^2 of the magnitudes it combines, so the result is within
 * ~33 eps^2 * perm of the determinant (perm: the filter's permanent). Decided when beyond 1024 eps^2
 * * perm (near-cocircular points that the filter leaves, at a fifth of the cost of the expansions);
 * otherwise, and outside 1e-250 < perm < 1e250 (no underflow of the products' error terms, no
 * overflow), the exact expansion. */
#if defined(__GNUC__)
#define WR__COLD __attribute__((noinline)) /* keeps the filter's fast path small (it is inlined) */
#else
#define WR__COLD
#endif
static WR__COLD double wr__incircle_slow(const double *a, const double *b, const double *c, const double *d,
                                         double perm) {
    const double *p[3];
    double xh[3], xl[3], yh[3], yl[3], th[3], tl[3], h, l, h2, l2, bound;
    int i;
    if (!(perm > 1e-250 && perm < 1e250)) return wr__incircle_exact(a, b, c, d);
    p[0] = a;
    p[1] = b;
    p[2] = c;
    for (i = 0; i < 3; ++i) {
        wr__two_diff(p[i][0], d[0], &xh[i], &xl[i]);
        wr__two_diff(p[i][1], d[1], &yh[i], &yl[i]);
    }
    for (i = 0; i < 3; ++i) {
        int j = (i + 1) % 3, k = (i + 2) % 3;
        double lh, ll, ch, cl;
        wr__dd_mul(xh[i], xl[i], xh[i], xl[i], &h, &l); /* lift: x^2 + y^2 */
        wr__dd_mul(yh[i], yl[i], yh[i], yl[i], &h2, &l2);
        wr__dd_add(h, l, h2, l2, &lh, &ll);
        wr__dd_mul(xh[j], xl[j], yh[k], yl[k], &h, &l); /* cross: x_j y_k - y_j x_k */
        wr__dd_mul(yh[j], yl[j], xh[k], xl[k], &h2, &l2);
        wr__dd_add(h, l, -h2, -l2, &ch, &cl);
        wr__dd_mul(lh, ll, ch, cl, &th[i], &tl[i]);
    }
    wr__dd_add(th[0], tl[0], th[1], tl[1], &h, &l);
    wr__dd_add(h, l, th[2], tl[2], &h2, &l2);
    bound = 1024.0 * WR_PRED_EPS * WR_PRED_EPS * perm;
    if (h2 > bound || -h2 > bound) return h2;
    return wr__incircle_exact(a, b, c, d);
}

WRDEF double wr_orient2d_value(const double *a, const double *b, const double *c) {
    double s[16], v = 0.0;
    int ns = wr__orient_expansion(a, b, c, s), i;
    for (i = 0; i < ns; ++i) v += s[i];
    return v;
}

/* ---- the adaptive predicates: filter with error bound A (Shewchuk 1997, Sec. 4), else exact ---- */
WRDEF double wr_orient2d(const double *a, const double *b, const double *c) {
    double det;
    if (wr__orient2d_filter(a, b, c, &det)) return det;
    return wr__orient_exact(a, b, c);
}

WRDEF double wr_incircle(const double *a, const double *b, const double *c, const double *d) {
    double det, perm;
    if (wr__incircle_filter(a, b, c, d, &det, &perm)) return det;
    return wr__incircle_slow(a, b, c, d, perm);
}

/* det[b−a, c−a, d−a] exactly, cofactor expansion along the first row (expansions by magnitude). */
static double wr__orient3d_exact(const double *a, const double *b, const double *c, const double *d) {
    double e[3][3][2], m1[8], m2[8], cof[16], term[3][64], s01[128], tot[192];
    int ne[3][3], n1, n2, nc, nt[3], n01, ntot, r, k;
    const double *P[3];
    P[0] = b;
    P[1] = c;
    P[2] = d;
    for (r = 0; r < 3; ++r)
        for (k = 0; k < 3; ++k) ne[r][k] = wr__diff_exp(P[r][k], a[k], e[r][k]);
    for (k = 0; k < 3; ++k) {
        int k1 = (k + 1) % 3, k2 = (k + 2) % 3;
        /* row 0 entry k times the minor of rows 1, 2 and columns k1, k2 */
        n1 = wr__exp_mul(ne[1][k1], e[1][k1], ne[2][k2], e[2][k2], m1);
        n2 = wr__exp_mul(ne[1][k2], e[1][k2], ne[2][k1], e[2][k1], m2);
        wr__exp_neg(n2, m2);
        nc = wr__exp_sum(n1, m1, n2, m2, cof);
        nt[k] = wr__exp_mul(nc, cof, ne[0][k], e[0][k], term[k]);
    }
    n01 = wr__exp_sum(nt[0], term[0], nt[1], term[1], s01);
    ntot = wr__exp_sum(n01, s01, nt[2], term[2], tot);
    return tot[ntot - 1];
}

WRDEF double wr_orient3d(const double a[3], const double b[3], const double c[3], const double d[3]) {
    double bx = b[0] - a[0], by = b[1] - a[1], bz = b[2] - a[2];
    double cx = c[0] - a[0], cy = c[1] - a[1], cz = c[2] - a[2];
    double dx = d[0] - a[0], dy = d[1] - a[1], dz = d[2] - a[2];
    double m0a = cy * dz, m0b = cz * dy, m1a = cz * dx, m1b = cx * dz, m2a = cx * dy, m2b = cy * dx;
    double det = bx * (m0a - m0b) + by * (m1a - m1b) + bz * (m2a - m2b);
    double perm = fabs(bx) * (fabs(m0a) + fabs(m0b)) + fabs(by) * (fabs(m1a) + fabs(m1b)) +
                  fabs(bz) * (fabs(m2a) + fabs(m2b));
    double eb = WR__O3D_BOUND * perm;
    if (det > eb || -det > eb) return det;
    return wr__orient3d_exact(a, b, c, d);
}

WRDEF double wr_orient2d_fast(const double *a, const double *b, const double *c) {
    return (a[0] - c[0]) * (b[1] - c[1]) - (a[1] - c[1]) * (b[0] - c[0]);
}
WRDEF double wr_incircle_fast(const double *a, const double *b, const double *c, const double *d) {
    double adx = a[0] - d[0], ady = a[1] - d[1], bdx = b[0] - d[0], bdy = b[1] - d[1];
    double cdx = c[0] - d[0], cdy = c[1] - d[1];
    return (adx * adx + ady * ady) * (bdx * cdy - cdx * bdy) + (bdx * bdx + bdy * bdy) * (cdx * ady - adx * cdy) +
           (cdx * cdx + cdy * cdy) * (adx * bdy - bdx * ady);
}

#ifdef __cplusplus
}
#endif
#endif /* WRINKLE_PREDICATES_IMPLEMENTATION_DONE */
#endif /* WRINKLE_IMPLEMENTATION */
