/* wrinkle/poisson.h — variable-radius Poisson-disk sampling of polygons with holes, with fixed
 * boundary and constraint-line points, driven by a sizing callback (target edge length [m]).
 * wrinkle v0.1.0 — MIT licence (see LICENSE). Needs only libc and libm (and core.h).
 *
 * Style3D ("Physics-inspired Estimation of Optimal Cloth Mesh Resolution", Sec. 4.3): "we first
 * sample the sizing map using the fast Poisson disk sampling algorithm [Bridson 2007], ensuring that
 * the average vertex spacing locally aligns with the sizing values. The resulting point cloud, along
 * with boundary constraints, is then input into triangulation tools". This header is that first
 * step: boundary loops and interior constraint polylines (shirring lines, seams, fold lines) are
 * discretised at the local sizing and kept fixed; the interior is filled by Bridson's active-list
 * algorithm generalised to a radius that varies in space; the constraint segments come back as
 * index pairs for the triangulator (triangulate.h).
 *
 * API (create/free pair: wr_poisson_sample → wr_poisson_free)
 *   wr_poisson_sample(dom, sizing, user, desc, res, diag)   validate, discretise, sample
 *   wr_poisson_free(res)                                    free and zero (safe on a zeroed result)
 *
 * EXAMPLE
 *     static double size_fn(void *u, double x, double y) { (void)u; (void)y; return 0.01 + 0.02 * x; }
 *     double sq[8] = {0,0, 1,0, 1,1, 0,1};
 *     wr_poisson_domain dom; wr_poisson_desc desc; wr_poisson_result res; wr_diag d;
 *     memset(&dom, 0, sizeof dom); memset(&desc, 0, sizeof desc);
 *     dom.outer.xy = sq; dom.outer.n = 4;
 *     desc.seed = 7;
 *     if (wr_poisson_sample(&dom, size_fn, NULL, &desc, &res, &d) != WR_OK) { puts(d.message); return 1; }
 *     // res.points[0 .. 2*res.n_fixed) are the boundary points, then the interior samples;
 *     // res.segments (res.n_segments pairs) are the boundary edges to hand to the CDT.
 *     printf("%d points (%d on the boundary), %d segments\n", res.n_points, res.n_fixed, res.n_segments);
 *     wr_poisson_free(&res);
 *
 * ON THE SIZING → RADIUS RELATION
 *   The sizing h(x) is the target mesh edge length. Each sample p carries the disk radius
 *   r(p) = radius_factor · h(p). Boundary/constraint points are spaced ≈ h along their curves (one
 *   edge per unit of ∫ ds / h). The default radius_factor WR_POISSON_DEFAULT_RADIUS_FACTOR was
 *   calibrated so that the Delaunay mesh of the output has mean edge length / local sizing ≈ 1:
 *   measured by tests/test_poisson.c (own Bowyer–Watson, interior edges, constant h on a unit square
 *   with h = 0.02 and on a 20×-graded field): see the constant's comment for the numbers.
 *
 * ON THE CONFLICT RULE (varying radius)
 *   Two samples p, q conflict when |p − q| < (r(p) + r(q)) / 2 (the symmetric "mean" rule; it is
 *   well defined, independent of insertion order, and equals the classical rule for constant r).
 *   Every pair in which at least one point is an interior sample satisfies |p − q| >= (r(p)+r(q))/2.
 *   Fixed points are not tested against each other (they are the caller's geometry).
 *   Candidates are drawn uniformly (by area) in the annulus [r(p), 2 r(p)] around an active sample p,
 *   k per activation (Bridson 2007); a sample is retired after k consecutive failures.
 *
 * ON COVERAGE (what is, and is not, guaranteed)
 *   Bridson's k-candidate algorithm is not exactly maximal: the only hard guarantee is the minimum
 *   distance above. Gaps are rare: tests/test_poisson.c checks, on a probe lattice, that every probe x
 *   strictly inside the domain has a sample within 2 r(x) (2 = the annulus' outer radius) and reports
 *   the largest empty-disk ratio it saw.
 *
 * ON THE ACCELERATION GRID (why it stays O(n) when the radius varies 20×)
 *   Radii are bucketed into octave levels: level l holds samples with r in [s·2^l, s·2^(l+1)),
 *   s = bbox size / 2^28. Each level is a hashed grid (open addressing, key = level + cell) with cell
 *   size 2·s·2^l >= every radius of that level, so a same-level query touches <= 3×3 cells. A dense
 *   "presence" grid with cells of ≈ 2·r_max keeps, per cell, a 64-bit mask of the levels present in
 *   it; a query probes only the levels present around the candidate. For a sizing that is smooth on
 *   the scale of r_max (any graded sizing map), only 1–2 levels are present around a point, so the
 *   work per candidate is bounded independently of n and of the global ratio r_max/r_min, and memory
 *   is O(n) (hash ~ 2n entries; presence cells <= max(4096, 4n_est)). The dense single grid at the
 *   minimum radius that Bridson uses would hold (r_max/r_min)^2 more cells than samples where the
 *   radius is large. bench/bench_poisson.c measures samples/s at constant and 20×-graded radius.
 *   Where the sizing jumps by several octaves within r_max, coarse candidates near the jump probe
 *   the fine level's cells ((r_q / r_fine)^2 cells) — still correct, only slower there.
 *
 * ON VALIDATION (all WR_ERR_GEOMETRY unless said otherwise; diag->item as stated)
 *   Loops need >= 3 points, polylines >= 2 (closed polylines >= 3); non-finite coordinate (item = the
 *   point); an input extent that overflows a double; zero-length segment; loop with |area| <=
 *   WR_POISSON_REL_TOL·bbox²; any two segments of the input (same or different curves, adjacent ones
 *   only when they fold back) that touch or cross — the
 *   message names both (curve and segment index; item = the first segment's index in its curve);
 *   a hole not inside the outer loop; a hole inside another hole; a polyline not inside the domain.
 *   Checked on a uniform bucket grid (O(n) for evenly spaced input). After discretisation the same
 *   check runs on the discretised segments (chords can cross where a feature is thinner than the
 *   sizing). The sizing callback returning a value that is not a positive finite number →
 *   WR_ERR_DOMAIN naming the point. Estimated point count κ·∫ dA / r² + n_fixed > max_points →
 *   WR_ERR_BUDGET before any per-sample memory is allocated (and again if sampling itself would
 *   exceed it). NULL arguments → WR_ERR_INVALID_ARG.
 *
 * ON OUTPUT ORDER AND OWNERS
 *   Fixed points: outer loop, then holes in order, then polylines in order; each curve starts at its
 *   input vertex 0 and follows the input direction (any orientation is accepted and kept). Input
 *   vertices whose turning angle exceeds desc.corner_angle are kept exactly ("corners"), unless they
 *   lie closer than h/2 (arc length) to the previous kept vertex or to the curve's end; vertex 0
 *   and open-polyline endpoints are always kept. Between kept vertices points follow ∫ ds/h with the segment count
 *   N = max(1, round(∫ ds/h)) and the points redistributed so every piece has ∫ ds/h = total/N
 *   (so endpoints are hit exactly and no last step is tiny). Hence every constraint segment has
 *   ∫ ds/h in [0.5, 1.5] measured along the input curve (up to the trapezoid error of the walk;
 *   the chord is shorter where the input curves), except where a closed curve needs more segments
 *   to reach its minimum of 3.
 *   segment_owner: 0 = outer loop, 1 + i = hole i, 1 + n_holes + j = polyline j.
 *   The inside test (crossing number, boundary points count as outside) uses the DISCRETISED loops,
 *   i.e. exactly the polygon the triangulator receives.
 *
 * ON NUMERICS
 *   Orientation tests here are plain double arithmetic (not exact predicates): inputs that are
 *   degenerate to within rounding may be classified either way. Build without -ffast-math.
 *
 * ON DETERMINISM AND THREADS
 *   Randomness only from wr_rng seeded with desc.seed: the same inputs, seed and sizing give the same
 *   output bit for bit. No global state; the callback is called from the calling thread only.
 */
#ifndef WRINKLE_POISSON_H
#define WRINKLE_POISSON_H

#include "core.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Target edge length h(x, y) [m] at a point of the domain; must be positive and finite. */
typedef double (*wr_poisson_sizing_fn)(void *user, double x, double y);

/* r = radius_factor · h. Calibrated by test_poisson.c "calibration" (own Bowyer–Watson Delaunay of
 * the output, mean length of edges not touching the boundary, divided by the mean of the two end
 * points' sizing): see the report line printed by that test. */
#define WR_POISSON_DEFAULT_RADIUS_FACTOR 0.705
#define WR_POISSON_DEFAULT_K 30
#define WR_POISSON_DEFAULT_MAX_POINTS 50000000
#define WR_POISSON_DEFAULT_CORNER_ANGLE 0.5235987755982988 /* 30° [rad] */
/* Samples per r² of area for this sampler (mean rule, k = 30): N ≈ κ ∫ dA / r². Measured in
 * test_poisson.c "density" (constant and graded sizing); used only for the budget estimate. */
#define WR_POISSON_DENSITY 0.61
/* Relative tolerance (× bbox size) for "on a boundary segment" and (× bbox size²) for zero area. */
#define WR_POISSON_REL_TOL 1e-12
/* Arc-length walking step along curves, as a fraction of the local sizing (trapezoid rule on 1/h). */
#define WR_POISSON_WALK_STEP 0.25
/* Probe lattice (per axis) over the bounding box for the ∫ dA / r² budget estimate. */
#define WR_POISSON_BUDGET_PROBES 128

/* A curve: n points, row-major xy[2n] [m]. Loops (outer, holes) are always closed; for polylines
 * `closed` != 0 joins the last point to the first. */
typedef struct wr_poisson_curve {
    const double *xy;
    int32_t n;
    int32_t closed;
} wr_poisson_curve;

typedef struct wr_poisson_domain {
    wr_poisson_curve outer;        /* the panel boundary */
    const wr_poisson_curve *holes; /* n_holes hole loops, each strictly inside outer, disjoint */
    int32_t n_holes;
    const wr_poisson_curve *lines; /* n_lines constraint polylines strictly inside the domain */
    int32_t n_lines;
} wr_poisson_domain;

/* Options; zero means default:
 *   seed          0 is a valid seed and is used as given (no default substitution)
 *   k             WR_POISSON_DEFAULT_K candidates per activation
 *   radius_factor WR_POISSON_DEFAULT_RADIUS_FACTOR (r = radius_factor · h)
 *   max_points    WR_POISSON_DEFAULT_MAX_POINTS (fixed + interior)
 *   corner_angle  WR_POISSON_DEFAULT_CORNER_ANGLE [rad]; a tiny positive value keeps every vertex */
typedef struct wr_poisson_desc {
    uint64_t seed;
    int32_t k;
    double radius_factor;
    int32_t max_points;
    double corner_angle;
} wr_poisson_desc;

typedef struct wr_poisson_result {
    double *points;         /* n_points×2 [m]; the first n_fixed are boundary/constraint points */
    double *sizing;         /* n_points: h at each point [m] */
    int32_t n_points;
    int32_t n_fixed;
    int32_t *segments;      /* n_segments×2 indices into points (constraint edges for the CDT) */
    int32_t *segment_owner; /* n_segments: 0 outer, 1+i hole i, 1+n_holes+j polyline j */
    int32_t n_segments;
    int32_t n_estimated;    /* budget estimate n_fixed + κ ∫ dA / r² */
    int64_t n_candidates;   /* candidates generated in the interior phase */
    double seconds;         /* wall time of wr_poisson_sample */
} wr_poisson_result;

WRDEF wr_status wr_poisson_sample(const wr_poisson_domain *dom, wr_poisson_sizing_fn sizing, void *user,
                                  const wr_poisson_desc *desc, wr_poisson_result *res, wr_diag *diag);
WRDEF void wr_poisson_free(wr_poisson_result *res);

#ifdef __cplusplus
}
#endif
#endif /* WRINKLE_POISSON_H */

/* ============================================================================================ */
#ifdef WRINKLE_IMPLEMENTATION
#ifndef WRINKLE_POISSON_IMPLEMENTATION_DONE
#define WRINKLE_POISSON_IMPLEMENTATION_DONE

#include <math.h>
#include <string.h>

#ifdef __cplusplus
extern "C" {
#endif

/* ---------------------------------------------------------------------------------------------- */
/* curve set: all curves' points in one array; curve c = points [off[c], off[c]+cnt[c]) */
typedef struct wr__pz_curves {
    double *xy;
    int32_t *off, *cnt, *closed;
    int32_t nc, n_holes, np;
} wr__pz_curves;

static void wr__pz_curves_free(wr__pz_curves *cv) {
    wr_free(cv->xy);
    wr_free(cv->off);
    wr_free(cv->cnt);
    wr_free(cv->closed);
    memset(cv, 0, sizeof *cv);
}

static void wr__pz_curve_name(const wr__pz_curves *cv, int32_t c, char *buf, size_t len) {
    if (c == 0)
        snprintf(buf, len, "outer loop");
    else if (c <= cv->n_holes)
        snprintf(buf, len, "hole %d", (int)(c - 1));
    else
        snprintf(buf, len, "polyline %d", (int)(c - 1 - cv->n_holes));
}

static int32_t wr__pz_nseg(const wr__pz_curves *cv, int32_t c) { return cv->closed[c] ? cv->cnt[c] : cv->cnt[c] - 1; }

static double wr__pz_orient(const double *a, const double *b, const double *c) {
    return (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
}

/* c collinear with [a,b]: is it within the segment's box? */
static int wr__pz_on_seg(const double *a, const double *b, const double *c) {
    return c[0] >= fmin(a[0], b[0]) && c[0] <= fmax(a[0], b[0]) && c[1] >= fmin(a[1], b[1]) &&
           c[1] <= fmax(a[1], b[1]);
}

static int wr__pz_sgn(double v) { return v > 0.0 ? 1 : (v < 0.0 ? -1 : 0); }

/* Closed segments [a,b] and [c,d] share at least one point. */
static int wr__pz_seg_hit(const double *a, const double *b, const double *c, const double *d) {
    int o1 = wr__pz_sgn(wr__pz_orient(a, b, c)), o2 = wr__pz_sgn(wr__pz_orient(a, b, d));
    int o3 = wr__pz_sgn(wr__pz_orient(c, d, a)), o4 = wr__pz_sgn(wr__pz_orient(c, d, b));
    if (o1 * o2 < 0 && o3 * o4 < 0) return 1;
    if (o1 == 0 && wr__pz_on_seg(a, b, c)) return 1;
    if (o2 == 0 && wr__pz_on_seg(a, b, d)) return 1;
    if (o3 == 0 && wr__pz_on_seg(c, d, a)) return 1;
    if (o4 == 0 && wr__pz_on_seg(c, d, b)) return 1;
    return 0;
}

/* Adjacent segments [a,s] and [s,d] sharing s: they intersect elsewhere only by folding back. */
static int wr__pz_fold(const double *a, const double *s, const double *d) {
    return wr__pz_orient(a, s, d) == 0.0 && (d[0] - s[0]) * (a[0] - s[0]) + (d[1] - s[1]) * (a[1] - s[1]) > 0.0;
}

/* Every pair of segments of the curve set that touch or cross, except adjacent segments of one curve
 * meeting at their shared vertex, is an error naming both. Uniform bucket grid over the bbox. */
static wr_status wr__pz_check_crossings(const wr__pz_curves *cv, const char *what, wr_diag *diag) {
    int32_t c, i, ns = 0, *seg_c = NULL, *seg_i = NULL, *cstart = NULL, *clist = NULL, *fill = NULL;
    double x0 = HUGE_VAL, y0 = HUGE_VAL, x1 = -HUGE_VAL, y1 = -HUGE_VAL, g, W, H;
    int64_t nx, ny, ncell, nreg = 0, cell;
    wr_status st = WR_OK;
    for (c = 0; c < cv->nc; ++c) ns += wr__pz_nseg(cv, c);
    for (i = 0; i < cv->np; ++i) {
        x0 = fmin(x0, cv->xy[2 * i]);
        x1 = fmax(x1, cv->xy[2 * i]);
        y0 = fmin(y0, cv->xy[2 * i + 1]);
        y1 = fmax(y1, cv->xy[2 * i + 1]);
    }
    W = x1 - x0;
    H = y1 - y0;
    /* Finite points can still span more than DBL_MAX; the bucket count would be NaN then. */
    if (!isfinite(W) || !isfinite(H))
        return wr_fail(diag, WR_ERR_GEOMETRY, -1, "%s extent [%g, %g] x [%g, %g] m overflows a double", what, x0, x1,
                       y0, y1);
    /* About two segments per cell, and at most ~2 ns + 16 cells along the longer side (so the cell
     * count stays O(ns) for any aspect ratio). The former floor of 1/2048 of the longer side put a
     * 0.25 m x 33 km panel's millions of segments into one column of 2048 cells, thousands per cell,
     * and the pair test went quadratic (fuzzer finding pattern_giant_panel_budget). */
    g = sqrt(fmax(W * H, 1e-300) / (2.0 * (double)(ns > 0 ? ns : 1)));
    g = fmax(g, fmax(W, H) / (2.0 * (double)ns + 16.0));
    if (!(g > 0.0)) g = 1.0;
    nx = (int64_t)(W / g) + 1;
    ny = (int64_t)(H / g) + 1;
    ncell = nx * ny;
    seg_c = (int32_t *)wr_alloc_array((size_t)ns, sizeof(int32_t));
    seg_i = (int32_t *)wr_alloc_array((size_t)ns, sizeof(int32_t));
    cstart = (int32_t *)wr_calloc_array((size_t)ncell + 1, sizeof(int32_t));
    if (!seg_c || !seg_i || !cstart) {
        st = wr_fail(diag, WR_ERR_NOMEM, -1, "crossing check: out of memory");
        goto done;
    }
    ns = 0;
    for (c = 0; c < cv->nc; ++c)
        for (i = 0; i < wr__pz_nseg(cv, c); ++i) {
            seg_c[ns] = c;
            seg_i[ns++] = i;
        }
    /* two passes over each segment's cell box: count, then fill (CSR) */
    {
        int pass;
        for (pass = 0; pass < 2; ++pass) {
            int32_t s;
            for (s = 0; s < ns; ++s) {
                const double *a = cv->xy + 2 * (cv->off[seg_c[s]] + seg_i[s]);
                const double *b = cv->xy + 2 * (cv->off[seg_c[s]] + (seg_i[s] + 1) % cv->cnt[seg_c[s]]);
                int64_t ix0 = (int64_t)((fmin(a[0], b[0]) - x0) / g), ix1 = (int64_t)((fmax(a[0], b[0]) - x0) / g);
                int64_t iy0 = (int64_t)((fmin(a[1], b[1]) - y0) / g), iy1 = (int64_t)((fmax(a[1], b[1]) - y0) / g);
                int64_t ix, iy;
                if (ix1 >= nx) ix1 = nx - 1;
                if (iy1 >= ny) iy1 = ny - 1;
                for (iy = iy0; iy <= iy1; ++iy)
                    for (ix = ix0; ix <= ix1; ++ix) {
                        cell = iy * nx + ix;
                        if (pass == 0) {
                            if (nreg >= INT32_MAX - 1) {
                                st = wr_fail(diag, WR_ERR_BUDGET, -1, "crossing check: too many grid registrations");
                                goto done;
                            }
                            ++cstart[cell + 1];
                            ++nreg;
                        } else {
                            clist[fill[cell]++] = s;
                        }
                    }
            }
            if (pass == 0) {
                for (cell = 0; cell < ncell; ++cell) cstart[cell + 1] += cstart[cell];
                clist = (int32_t *)wr_alloc_array((size_t)nreg, sizeof(int32_t));
                fill = (int32_t *)wr_alloc_array((size_t)ncell, sizeof(int32_t));
                if (!clist || !fill) {
                    st = wr_fail(diag, WR_ERR_NOMEM, -1, "crossing check: out of memory");
                    goto done;
                }
                memcpy(fill, cstart, sizeof(int32_t) * (size_t)ncell);
            }
        }
    }
    for (cell = 0; cell < ncell; ++cell) {
        int32_t p, q;
        for (p = cstart[cell]; p < cstart[cell + 1]; ++p)
            for (q = p + 1; q < cstart[cell + 1]; ++q) {
                int32_t s = clist[p], t = clist[q], cs = seg_c[s], ct = seg_c[t], is = seg_i[s], it = seg_i[t];
                int32_t n = cv->cnt[cs];
                const double *a = cv->xy + 2 * (cv->off[cs] + is), *b = cv->xy + 2 * (cv->off[cs] + (is + 1) % n);
                const double *d = cv->xy + 2 * (cv->off[ct] + it);
                const double *e = cv->xy + 2 * (cv->off[ct] + (it + 1) % cv->cnt[ct]);
                int hit;
                if (cs == ct && (it == is + 1 || is == it + 1)) {
                    hit = it == is + 1 ? wr__pz_fold(a, b, e) : wr__pz_fold(d, e, b);
                } else if (cs == ct && cv->closed[cs] && ((is == 0 && it == n - 1) || (it == 0 && is == n - 1))) {
                    hit = is == 0 ? wr__pz_fold(d, e, b) : wr__pz_fold(a, b, e);
                } else {
                    hit = wr__pz_seg_hit(a, b, d, e);
                }
                if (hit) {
                    char na[32], nb[32];
                    int32_t fs = s < t ? s : t, ls = s < t ? t : s;
                    wr__pz_curve_name(cv, seg_c[fs], na, sizeof na);
                    wr__pz_curve_name(cv, seg_c[ls], nb, sizeof nb);
                    st = wr_fail(diag, WR_ERR_GEOMETRY, seg_i[fs],
                                 "%s: %s segment %d (points %d-%d) intersects %s segment %d (points %d-%d)", what, na,
                                 (int)seg_i[fs], (int)seg_i[fs], (int)((seg_i[fs] + 1) % cv->cnt[seg_c[fs]]), nb,
                                 (int)seg_i[ls], (int)seg_i[ls], (int)((seg_i[ls] + 1) % cv->cnt[seg_c[ls]]));
                    goto done;
                }
            }
    }
done:
    wr_free(seg_c);
    wr_free(seg_i);
    wr_free(cstart);
    wr_free(clist);
    wr_free(fill);
    return st;
}

/* Brute-force crossing-number test of point p against curve c (used for containment validation). */
static int wr__pz_in_curve(const wr__pz_curves *cv, int32_t c, const double *p) {
    return wr_point_in_polygon(cv->xy + 2 * cv->off[c], cv->cnt[c], p[0], p[1]);
}

/* ---------------------------------------------------------------------------------------------- */
/* Inside test over the discretised loops: bucket grid; edge-free cells carry their in/out status
 * (computed by a right-to-left sweep per row), other cells cast two rays in lockstep, +x along
 * y = q.y and +y along x = q.x, each ending at its first edge-free cell (status ^ parity) or at the
 * grid's end (outside); the ray that ends first answers. Crossings use the half-open rule
 * ((y1 > y) != (y2 > y) for the +x ray) and count only in the cell that contains the crossing, so
 * edges spanning several cells count once. Why two rays: in a domain thinner than a cell every
 * cell of its rows holds both long boundaries, so a +x ray alone walks the whole row (O(nx) per
 * query, quadratic sampling: 20k vertices of a 216 m x 0.1 mm strip took 5 s); the +y ray leaves
 * such a strip within two cells, and a strip along y is the +x ray's easy case. */
typedef struct wr__pz_inside {
    double x0, y0, g, inv_g, tol;
    int32_t nx, ny;
    int32_t *cstart, *clist;
    unsigned char *status;
    double *seg; /* ne×4: x1 y1 x2 y2 */
    int32_t ne;
} wr__pz_inside;

static void wr__pz_inside_free(wr__pz_inside *t) {
    wr_free(t->cstart);
    wr_free(t->clist);
    wr_free(t->status);
    wr_free(t->seg);
    memset(t, 0, sizeof *t);
}

/* Cell index along axis 0 (x) or 1 (y), clamped to [-1, n]. */
static int32_t wr__pz_cell(const wr__pz_inside *t, int axis, double v) {
    double f = (v - (axis ? t->y0 : t->x0)) * t->inv_g;
    int32_t n = axis ? t->ny : t->nx;
    if (f < 0.0) return -1;
    if (f >= (double)n) return n;
    return (int32_t)f;
}

static int32_t wr__pz_cell_x(const wr__pz_inside *t, double x) { return wr__pz_cell(t, 0, x); }

/* Parity of the crossings, inside `cell` (index k along the ray), of the ray from q along +x (axis 0)
 * or +y (axis 1); half-open rule across the other axis, counted only where the crossing lies. */
static int wr__pz_ray_cell(const wr__pz_inside *t, int32_t cell, int axis, const double q[2], int32_t k) {
    int32_t p, a = axis, b = 1 - axis;
    int par = 0;
    for (p = t->cstart[cell]; p < t->cstart[cell + 1]; ++p) {
        const double *s = t->seg + 4 * t->clist[p];
        if ((s[b] > q[b]) != (s[2 + b] > q[b])) {
            double c = s[a] + (q[b] - s[b]) * (s[2 + a] - s[a]) / (s[2 + b] - s[b]);
            if (c > q[a] && wr__pz_cell(t, axis, c) == k) par ^= 1;
        }
    }
    return par;
}

static int wr__pz_inside_at(const wr__pz_inside *t, double qx, double qy) {
    int32_t ix = wr__pz_cell_x(t, qx), iy, i, j;
    int parx = 0, pary = 0;
    double fy = (qy - t->y0) * t->inv_g, q[2];
    if (ix < 0 || ix >= t->nx || !(fy >= 0.0) || fy >= (double)t->ny) return 0;
    iy = (int32_t)fy;
    q[0] = qx;
    q[1] = qy;
    {
        int32_t cell = iy * t->nx + ix, p;
        if (t->cstart[cell] == t->cstart[cell + 1]) return t->status[cell];
        /* boundary points count as outside */
        for (p = t->cstart[cell]; p < t->cstart[cell + 1]; ++p) {
            const double *s = t->seg + 4 * t->clist[p];
            double ex = s[2] - s[0], ey = s[3] - s[1], l2 = ex * ex + ey * ey;
            double u = l2 > 0.0 ? ((qx - s[0]) * ex + (qy - s[1]) * ey) / l2 : 0.0;
            double dx, dy;
            u = u < 0.0 ? 0.0 : (u > 1.0 ? 1.0 : u);
            dx = s[0] + u * ex - qx;
            dy = s[1] + u * ey - qy;
            if (dx * dx + dy * dy <= t->tol * t->tol) return 0;
        }
    }
    for (i = ix, j = iy;; ++i, ++j) {
        int32_t cell;
        if (i >= t->nx) return parx;
        cell = iy * t->nx + i;
        if (i > ix && t->cstart[cell] == t->cstart[cell + 1]) return t->status[cell] ^ parx;
        parx ^= wr__pz_ray_cell(t, cell, 0, q, i);
        if (j >= t->ny) return pary;
        cell = j * t->nx + ix;
        if (j > iy && t->cstart[cell] == t->cstart[cell + 1]) return t->status[cell] ^ pary;
        pary ^= wr__pz_ray_cell(t, cell, 1, q, j);
    }
}

/* Build from the loops (curves 0..n_holes) of a curve set. */
static wr_status wr__pz_inside_build(wr__pz_inside *t, const wr__pz_curves *cv, double x0, double y0, double W,
                                     double H, double tol, wr_diag *diag) {
    int32_t c, i, e = 0, pass;
    int64_t ncell, nreg = 0, cell;
    int32_t *fill = NULL;
    memset(t, 0, sizeof *t);
    for (c = 0; c <= cv->n_holes; ++c) t->ne += cv->cnt[c];
    t->g = sqrt(W * H / (4.0 * (double)t->ne));
    t->g = fmax(t->g, fmax(W, H) / 4096.0);
    t->inv_g = 1.0 / t->g;
    /* one spare cell on each side so the grid strictly contains the loops */
    t->x0 = x0 - t->g;
    t->y0 = y0 - t->g;
    t->nx = (int32_t)(W / t->g) + 3;
    t->ny = (int32_t)(H / t->g) + 3;
    t->tol = tol;
    ncell = (int64_t)t->nx * t->ny;
    t->seg = (double *)wr_alloc_array((size_t)t->ne, 4 * sizeof(double));
    t->cstart = (int32_t *)wr_calloc_array((size_t)ncell + 1, sizeof(int32_t));
    t->status = (unsigned char *)wr_calloc_array((size_t)ncell, 1);
    if (!t->seg || !t->cstart || !t->status) goto nomem;
    for (c = 0; c <= cv->n_holes; ++c)
        for (i = 0; i < cv->cnt[c]; ++i, ++e) {
            const double *a = cv->xy + 2 * (cv->off[c] + i), *b = cv->xy + 2 * (cv->off[c] + (i + 1) % cv->cnt[c]);
            t->seg[4 * e] = a[0];
            t->seg[4 * e + 1] = a[1];
            t->seg[4 * e + 2] = b[0];
            t->seg[4 * e + 3] = b[1];
        }
    for (pass = 0; pass < 2; ++pass) {
        for (e = 0; e < t->ne; ++e) {
            const double *s = t->seg + 4 * e;
            int32_t ix0 = wr__pz_cell_x(t, fmin(s[0], s[2])), ix1 = wr__pz_cell_x(t, fmax(s[0], s[2]));
            int32_t iy0 = (int32_t)((fmin(s[1], s[3]) - t->y0) * t->inv_g);
            int32_t iy1 = (int32_t)((fmax(s[1], s[3]) - t->y0) * t->inv_g), ix, iy;
            for (iy = iy0; iy <= iy1; ++iy)
                for (ix = ix0; ix <= ix1; ++ix) {
                    cell = (int64_t)iy * t->nx + ix;
                    if (pass == 0) {
                        ++t->cstart[cell + 1];
                        if (++nreg >= INT32_MAX) return wr_fail(diag, WR_ERR_BUDGET, -1, "inside grid too large");
                    } else {
                        t->clist[fill[cell]++] = e;
                    }
                }
        }
        if (pass == 0) {
            for (cell = 0; cell < ncell; ++cell) t->cstart[cell + 1] += t->cstart[cell];
            t->clist = (int32_t *)wr_alloc_array((size_t)nreg, sizeof(int32_t));
            fill = (int32_t *)wr_alloc_array((size_t)ncell, sizeof(int32_t));
            if (!t->clist || !fill) goto nomem;
            memcpy(fill, t->cstart, sizeof(int32_t) * (size_t)ncell);
        }
    }
    wr_free(fill);
    /* status sweep: along y = row centre, from outside (right) to the left */
    for (i = 0; i < t->ny; ++i) {
        double yc = t->y0 + ((double)i + 0.5) * t->g;
        int32_t ix, s = 0;
        for (ix = t->nx - 1; ix >= 0; --ix) {
            int32_t cl = i * t->nx + ix, p;
            t->status[cl] = (unsigned char)s;
            for (p = t->cstart[cl]; p < t->cstart[cl + 1]; ++p) {
                const double *sg = t->seg + 4 * t->clist[p];
                if ((sg[1] > yc) != (sg[3] > yc)) {
                    double xi = sg[0] + (yc - sg[1]) * (sg[2] - sg[0]) / (sg[3] - sg[1]);
                    if (wr__pz_cell_x(t, xi) == ix) s ^= 1;
                }
            }
        }
    }
    return WR_OK;
nomem:
    wr_free(fill);
    return wr_fail(diag, WR_ERR_NOMEM, -1, "inside grid: out of memory");
}

/* ---------------------------------------------------------------------------------------------- */
/* One sample in the acceleration structure (32 bytes: one cache line holds two). */
typedef struct wr__pz_s {
    double x, y, r;
    int32_t next; /* next sample in the same cell, -1 at the end */
    int32_t lvl;
} wr__pz_s;

/* Hash slot: a 4×4 tile of cells of one level (spatially adjacent cells share a slot, so a 3×3 cell
 * query touches 1–4 slots instead of 9 random ones). */
#define WR__PZ_TILE 4
typedef struct wr__pz_tile {
    uint64_t key;
    int32_t head[WR__PZ_TILE * WR__PZ_TILE];
} wr__pz_tile;

/* Sampler state. */
typedef struct wr__pz {
    wr_poisson_sizing_fn fn;
    void *user;
    wr_diag *diag;
    double c;           /* radius factor */
    int32_t max_points; /* budget */
    /* samples */
    wr__pz_s *sm;
    double *h;
    int32_t n, cap;
    /* level hash of tiles */
    wr__pz_tile *tiles;
    size_t hcap, hcount;
    int hbits;
    double x0, y0, W, H, s_base;
    double cs[64], inv_cs[64], rmax[64], rmax_all;
    /* presence grid */
    uint64_t *mask;
    int32_t mx, my;
    double mg, inv_mg;
    /* walking table */
    double *tx, *ty, *tI;
    int32_t tn, tcap;
} wr__pz;

static wr_status wr__pz_size(wr__pz *z, double x, double y, double *h) {
    double v = z->fn(z->user, x, y);
    *h = v;
    if (!(v > 0.0) || !(v < HUGE_VAL))
        return wr_fail(z->diag, WR_ERR_DOMAIN, -1, "sizing(%.9g, %.9g) = %g: must be a positive finite length [m]", x, y,
                       v);
    return WR_OK;
}

static wr_status wr__pz_table_push(wr__pz *z, double x, double y, double I) {
    if (z->tn == z->tcap) {
        int32_t nc = z->tcap ? z->tcap * 2 : 256;
        double *a = (double *)wr_realloc_array(z->tx, (size_t)nc, sizeof(double));
        if (!a) return wr_fail(z->diag, WR_ERR_NOMEM, -1, "curve walk: out of memory");
        z->tx = a;
        a = (double *)wr_realloc_array(z->ty, (size_t)nc, sizeof(double));
        if (!a) return wr_fail(z->diag, WR_ERR_NOMEM, -1, "curve walk: out of memory");
        z->ty = a;
        a = (double *)wr_realloc_array(z->tI, (size_t)nc, sizeof(double));
        if (!a) return wr_fail(z->diag, WR_ERR_NOMEM, -1, "curve walk: out of memory");
        z->tI = a;
        z->tcap = nc;
    }
    z->tx[z->tn] = x;
    z->ty[z->tn] = y;
    z->tI[z->tn++] = I;
    return WR_OK;
}

/* growable output point list for the fixed points */
typedef struct wr__pz_pts {
    double *xy;
    int32_t n, cap;
} wr__pz_pts;

static wr_status wr__pz_pts_push(wr__pz *z, wr__pz_pts *p, double x, double y) {
    if (p->n >= z->max_points)
        return wr_fail(z->diag, WR_ERR_BUDGET, -1,
                       "boundary/constraint discretisation alone needs more than max_points=%d points",
                       (int)z->max_points);
    if (p->n == p->cap) {
        int32_t nc = p->cap ? (p->cap > INT32_MAX / 2 ? INT32_MAX : p->cap * 2) : 256;
        double *a = (double *)wr_realloc_array(p->xy, (size_t)nc, 2 * sizeof(double));
        if (!a) return wr_fail(z->diag, WR_ERR_NOMEM, -1, "discretisation: out of memory");
        p->xy = a;
        p->cap = nc;
    }
    p->xy[2 * p->n] = x;
    p->xy[2 * p->n + 1] = y;
    ++p->n;
    return WR_OK;
}

/* Walk the input polyline through vertices v[idx[0..m-1]] (m >= 2) integrating ∫ ds / h with the
 * trapezoid rule at steps of WR_POISSON_WALK_STEP·h, then emit N-1 interior points at equal
 * increments of the integral, N = max(min_seg, round(∫ ds / h)). The start vertex is emitted by the
 * caller; the end vertex belongs to the next piece. */
static wr_status wr__pz_walk_piece(wr__pz *z, const double *v, int32_t n, int32_t start, int32_t m, int32_t min_seg,
                                   wr__pz_pts *out) {
    int32_t j, k, N, e;
    double I = 0.0, ha, hb;
    int64_t steps = 0;
    int64_t step_limit = 8 * (int64_t)z->max_points + 1000000;
    wr_status st;
    const double *A0 = v + 2 * start;
    z->tn = 0;
    if ((st = wr__pz_size(z, A0[0], A0[1], &ha)) != WR_OK) return st;
    if ((st = wr__pz_table_push(z, A0[0], A0[1], 0.0)) != WR_OK) return st;
    for (j = 0; j + 1 < m; ++j) {
        const double *A = v + 2 * ((start + j) % n), *B = v + 2 * ((start + j + 1) % n);
        double L = hypot(B[0] - A[0], B[1] - A[1]), t = 0.0;
        while (t < L) {
            double dt = WR_POISSON_WALK_STEP * ha, px, py;
            int last = t + dt >= L;
            if (last) {
                dt = L - t;
                px = B[0];
                py = B[1];
            } else {
                px = A[0] + (B[0] - A[0]) * ((t + dt) / L);
                py = A[1] + (B[1] - A[1]) * ((t + dt) / L);
            }
            if ((st = wr__pz_size(z, px, py, &hb)) != WR_OK) return st;
            I += dt * 0.5 * (1.0 / ha + 1.0 / hb);
            if ((st = wr__pz_table_push(z, px, py, I)) != WR_OK) return st;
            ha = hb;
            t = last ? L : t + dt;
            if (++steps > step_limit || I > (double)z->max_points)
                return wr_fail(z->diag, WR_ERR_BUDGET, -1,
                               "curve discretisation near (%.6g, %.6g): sizing too small for max_points=%d", px, py,
                               (int)z->max_points);
        }
    }
    N = (int32_t)floor(I + 0.5);
    if (N < min_seg) N = min_seg;
    if (N < 1) N = 1;
    e = 0;
    for (k = 1; k < N; ++k) {
        double target = I * (double)k / (double)N, f;
        while (e + 2 < z->tn && z->tI[e + 1] < target) ++e;
        f = z->tI[e + 1] > z->tI[e] ? (target - z->tI[e]) / (z->tI[e + 1] - z->tI[e]) : 0.0;
        f = f < 0.0 ? 0.0 : (f > 1.0 ? 1.0 : f);
        if ((st = wr__pz_pts_push(z, out, z->tx[e] + f * (z->tx[e + 1] - z->tx[e]),
                                  z->ty[e] + f * (z->ty[e + 1] - z->ty[e]))) != WR_OK)
            return st;
    }
    return WR_OK;
}

/* Discretise every curve of `in`; write the curve set `outc` (points of each curve, same closed flags). */
static wr_status wr__pz_discretise(wr__pz *z, const wr__pz_curves *in, double corner, wr__pz_curves *outc) {
    wr__pz_pts pts;
    int32_t c;
    int32_t *brk = NULL;
    wr_status st = WR_OK;
    memset(&pts, 0, sizeof pts);
    memset(outc, 0, sizeof *outc);
    outc->nc = in->nc;
    outc->n_holes = in->n_holes;
    outc->off = (int32_t *)wr_alloc_array((size_t)in->nc, sizeof(int32_t));
    outc->cnt = (int32_t *)wr_alloc_array((size_t)in->nc, sizeof(int32_t));
    outc->closed = (int32_t *)wr_alloc_array((size_t)in->nc, sizeof(int32_t));
    brk = (int32_t *)wr_alloc_array((size_t)in->np + 1, sizeof(int32_t));
    if (!outc->off || !outc->cnt || !outc->closed || !brk) {
        st = wr_fail(z->diag, WR_ERR_NOMEM, -1, "discretisation: out of memory");
        goto done;
    }
    for (c = 0; c < in->nc; ++c) {
        const double *v = in->xy + 2 * in->off[c];
        int32_t n = in->cnt[c], closed = in->closed[c], nb = 0, i, k, min_seg;
        double since = 0.0, total = 0.0, cum = 0.0; /* arc length since the last kept break; curve length */
        for (i = 0; i < (closed ? n : n - 1); ++i)
            total += hypot(v[2 * ((i + 1) % n)] - v[2 * i], v[2 * ((i + 1) % n) + 1] - v[2 * i + 1]);
        outc->off[c] = pts.n;
        outc->closed[c] = closed;
        for (i = 0; i < n; ++i) {
            int keep = i == 0 || (!closed && i == n - 1);
            if (i > 0) {
                double l = hypot(v[2 * i] - v[2 * i - 2], v[2 * i + 1] - v[2 * i - 1]);
                since += l;
                cum += l;
            }
            if (!keep) {
                const double *a = v + 2 * (i - 1), *b = v + 2 * i, *d = v + 2 * ((i + 1) % n);
                double ux = b[0] - a[0], uy = b[1] - a[1], wx = d[0] - b[0], wy = d[1] - b[1];
                double ang = atan2(fabs(ux * wy - uy * wx), ux * wx + uy * wy), hb;
                if (ang > corner) {
                    /* a corner closer (in arc length) than half the local sizing to the previous
                     * break or to the curve's end (vertex 0 again when closed) is dropped: it would
                     * force a segment with ∫ds/h < 0.5 (finely sampled wiggles below the sizing) */
                    if ((st = wr__pz_size(z, b[0], b[1], &hb)) != WR_OK) goto done;
                    keep = since >= 0.5 * hb && total - cum >= 0.5 * hb;
                }
            }
            if (keep) {
                brk[nb++] = i;
                since = 0.0;
            }
        }
        /* closed curves: >= 3 segments in total */
        min_seg = closed && nb < 3 ? (3 + nb - 1) / nb : 1;
        for (k = 0; k < (closed ? nb : nb - 1); ++k) {
            int32_t s = brk[k], e = k + 1 < nb ? brk[k + 1] : brk[0] + n;
            if ((st = wr__pz_pts_push(z, &pts, v[2 * s], v[2 * s + 1])) != WR_OK) goto done;
            if ((st = wr__pz_walk_piece(z, v, n, s, e - s + 1, min_seg, &pts)) != WR_OK) goto done;
        }
        if (!closed && (st = wr__pz_pts_push(z, &pts, v[2 * (n - 1)], v[2 * (n - 1) + 1])) != WR_OK) goto done;
        outc->cnt[c] = pts.n - outc->off[c];
    }
    outc->np = pts.n;
    outc->xy = pts.xy;
    pts.xy = NULL;
done:
    wr_free(pts.xy);
    wr_free(brk);
    return st;
}

/* ---- level hash ------------------------------------------------------------------------------ */
#define WR__PZ_CMAX ((1 << 29) - 2)

static uint64_t wr__pz_key(int l, int64_t tx, int64_t ty) {
    return (((uint64_t)l << 58) | ((uint64_t)tx << 29) | (uint64_t)ty) + 1u; /* 0 = empty slot */
}

static size_t wr__pz_slot(const wr__pz *z, uint64_t key) {
    size_t m = z->hcap - 1, s = (size_t)((key * 0x9E3779B97F4A7C15ULL) >> (64 - z->hbits)) & m;
    while (z->tiles[s].key != 0 && z->tiles[s].key != key) s = (s + 1) & m;
    return s;
}

static wr_status wr__pz_hash_alloc(wr__pz *z) {
    size_t i;
    z->hcap = (size_t)1 << z->hbits;
    z->tiles = (wr__pz_tile *)wr_alloc_array(z->hcap, sizeof(wr__pz_tile));
    if (!z->tiles) return wr_fail(z->diag, WR_ERR_NOMEM, -1, "sampling grid: out of memory");
    for (i = 0; i < z->hcap; ++i) z->tiles[i].key = 0;
    return WR_OK;
}

static wr_status wr__pz_hash_init(wr__pz *z, size_t expect_tiles) {
    z->hbits = 8;
    while (((size_t)1 << z->hbits) < 2 * expect_tiles && z->hbits < 40) ++z->hbits;
    z->hcount = 0;
    return wr__pz_hash_alloc(z);
}

static wr_status wr__pz_hash_grow(wr__pz *z) {
    wr__pz_tile *old = z->tiles;
    size_t oc = z->hcap, i;
    wr_status st;
    z->hbits += 1;
    if ((st = wr__pz_hash_alloc(z)) != WR_OK) {
        wr_free(old);
        return st;
    }
    for (i = 0; i < oc; ++i)
        if (old[i].key) z->tiles[wr__pz_slot(z, old[i].key)] = old[i];
    wr_free(old);
    return WR_OK;
}

static int wr__pz_level(const wr__pz *z, double r) {
    int e;
    (void)frexp(r / z->s_base, &e);
    return e - 1; /* r/s in [2^(e-1), 2^e) */
}

/* Mean rule: does (qx,qy) with radius rq conflict with any stored sample? */
static int wr__pz_conflict(const wr__pz *z, double qx, double qy, double rq) {
    double R = 0.5 * (rq + z->rmax_all);
    int64_t ax0 = (int64_t)floor((qx - R - z->x0) * z->inv_mg), ax1 = (int64_t)floor((qx + R - z->x0) * z->inv_mg);
    int64_t ay0 = (int64_t)floor((qy - R - z->y0) * z->inv_mg), ay1 = (int64_t)floor((qy + R - z->y0) * z->inv_mg);
    int64_t ix, iy;
    uint64_t mask = 0;
    if (ax0 < 0) ax0 = 0;
    if (ay0 < 0) ay0 = 0;
    if (ax1 >= z->mx) ax1 = z->mx - 1;
    if (ay1 >= z->my) ay1 = z->my - 1;
    for (iy = ay0; iy <= ay1; ++iy)
        for (ix = ax0; ix <= ax1; ++ix) mask |= z->mask[iy * z->mx + ix];
    while (mask) {
        int l = 0;
        uint64_t low = mask & (~mask + 1u);
        while (((uint64_t)1 << l) != low) ++l;
        mask ^= low;
        {
            double Rl = 0.5 * (rq + z->rmax[l]), ic = z->inv_cs[l];
            int64_t cx0 = (int64_t)floor((qx - Rl - z->x0) * ic), cx1 = (int64_t)floor((qx + Rl - z->x0) * ic);
            int64_t cy0 = (int64_t)floor((qy - Rl - z->y0) * ic), cy1 = (int64_t)floor((qy + Rl - z->y0) * ic);
            if (cx0 < 0) cx0 = 0;
            if (cy0 < 0) cy0 = 0;
            if (cx1 > (int64_t)(z->W * ic) + 1) cx1 = (int64_t)(z->W * ic) + 1;
            if (cy1 > (int64_t)(z->H * ic) + 1) cy1 = (int64_t)(z->H * ic) + 1;
            int64_t tx, ty;
            /* walk the tiles covering the cell box, then the cells of each tile inside the box */
            for (ty = cy0 / WR__PZ_TILE; ty <= cy1 / WR__PZ_TILE; ++ty)
                for (tx = cx0 / WR__PZ_TILE; tx <= cx1 / WR__PZ_TILE; ++tx) {
                    size_t sl = wr__pz_slot(z, wr__pz_key(l, tx, ty));
                    const wr__pz_tile *T = &z->tiles[sl];
                    int64_t jx0, jx1, jy0, jy1;
                    if (T->key == 0) continue;
                    jx0 = cx0 > tx * WR__PZ_TILE ? cx0 - tx * WR__PZ_TILE : 0;
                    jy0 = cy0 > ty * WR__PZ_TILE ? cy0 - ty * WR__PZ_TILE : 0;
                    jx1 = cx1 < tx * WR__PZ_TILE + WR__PZ_TILE - 1 ? cx1 - tx * WR__PZ_TILE : WR__PZ_TILE - 1;
                    jy1 = cy1 < ty * WR__PZ_TILE + WR__PZ_TILE - 1 ? cy1 - ty * WR__PZ_TILE : WR__PZ_TILE - 1;
                    for (iy = jy0; iy <= jy1; ++iy)
                        for (ix = jx0; ix <= jx1; ++ix) {
                            int32_t p = T->head[iy * WR__PZ_TILE + ix];
                            for (; p >= 0; p = z->sm[p].next) {
                                const wr__pz_s *S = &z->sm[p];
                                double dx = S->x - qx, dy = S->y - qy, md = 0.5 * (rq + S->r);
                                if (dx * dx + dy * dy < md * md) return 1;
                            }
                        }
                }
        }
    }
    return 0;
}

static wr_status wr__pz_insert(wr__pz *z, double x, double y, double h) {
    double r = z->c * h;
    int l = wr__pz_level(z, r);
    int64_t cx, cy;
    uint64_t key;
    size_t s;
    int32_t i, j;
    if (l < 0 || l > 62)
        return wr_fail(z->diag, WR_ERR_DOMAIN, -1,
                       "sizing %g at (%.9g, %.9g) is outside the representable range relative to the domain size", h,
                       x, y);
    cx = (int64_t)floor((x - z->x0) * z->inv_cs[l]);
    cy = (int64_t)floor((y - z->y0) * z->inv_cs[l]);
    if (cx < 0 || cy < 0 || cx > WR__PZ_CMAX || cy > WR__PZ_CMAX)
        return wr_fail(z->diag, WR_ERR_DOMAIN, -1, "point (%.9g, %.9g) outside the sampling grid", x, y);
    if (z->n == z->cap) {
        int32_t nc;
        void *a;
        if (z->cap >= z->max_points)
            return wr_fail(z->diag, WR_ERR_BUDGET, -1, "sampling exceeded max_points=%d", (int)z->max_points);
        nc = z->cap > z->max_points / 2 ? z->max_points : z->cap * 2;
        if (nc < 16) nc = 16;
        if ((a = wr_realloc_array(z->sm, (size_t)nc, sizeof(wr__pz_s))) == NULL) goto nomem;
        z->sm = (wr__pz_s *)a;
        if ((a = wr_realloc_array(z->h, (size_t)nc, sizeof(double))) == NULL) goto nomem;
        z->h = (double *)a;
        z->cap = nc;
    }
    if (2 * (z->hcount + 1) > z->hcap) {
        wr_status st = wr__pz_hash_grow(z);
        if (st != WR_OK) return st;
    }
    i = z->n++;
    z->sm[i].x = x;
    z->sm[i].y = y;
    z->sm[i].r = r;
    z->sm[i].lvl = l;
    z->h[i] = h;
    key = wr__pz_key(l, cx / WR__PZ_TILE, cy / WR__PZ_TILE);
    s = wr__pz_slot(z, key);
    if (z->tiles[s].key != key) {
        z->tiles[s].key = key;
        for (j = 0; j < WR__PZ_TILE * WR__PZ_TILE; ++j) z->tiles[s].head[j] = -1;
        ++z->hcount;
    }
    j = (int32_t)((cy % WR__PZ_TILE) * WR__PZ_TILE + cx % WR__PZ_TILE);
    z->sm[i].next = z->tiles[s].head[j];
    z->tiles[s].head[j] = i;
    if (r > z->rmax[l]) z->rmax[l] = r;
    if (r > z->rmax_all) z->rmax_all = r;
    {
        int64_t mx = (int64_t)floor((x - z->x0) * z->inv_mg), my = (int64_t)floor((y - z->y0) * z->inv_mg);
        if (mx >= z->mx) mx = z->mx - 1;
        if (my >= z->my) my = z->my - 1;
        if (mx < 0) mx = 0;
        if (my < 0) my = 0;
        z->mask[my * z->mx + mx] |= (uint64_t)1 << l;
    }
    return WR_OK;
nomem:
    return wr_fail(z->diag, WR_ERR_NOMEM, -1, "samples: out of memory");
}

static void wr__pz_free(wr__pz *z) {
    wr_free(z->sm);
    wr_free(z->h);
    wr_free(z->tiles);
    wr_free(z->mask);
    wr_free(z->tx);
    wr_free(z->ty);
    wr_free(z->tI);
}

WRDEF void wr_poisson_free(wr_poisson_result *res) {
    if (!res) return;
    wr_free(res->points);
    wr_free(res->sizing);
    wr_free(res->segments);
    wr_free(res->segment_owner);
    memset(res, 0, sizeof *res);
}

/* Copy and validate the input curves (counts, finiteness, zero-length segments, zero area). */
static wr_status wr__pz_gather(const wr_poisson_domain *dom, wr__pz_curves *cv, wr_diag *diag) {
    int32_t c, i, nc = 1 + dom->n_holes + dom->n_lines, np = 0;
    char name[32];
    memset(cv, 0, sizeof *cv);
    cv->nc = nc;
    cv->n_holes = dom->n_holes;
    cv->off = (int32_t *)wr_alloc_array((size_t)nc, sizeof(int32_t));
    cv->cnt = (int32_t *)wr_alloc_array((size_t)nc, sizeof(int32_t));
    cv->closed = (int32_t *)wr_alloc_array((size_t)nc, sizeof(int32_t));
    if (!cv->off || !cv->cnt || !cv->closed) return wr_fail(diag, WR_ERR_NOMEM, -1, "out of memory");
    for (c = 0; c < nc; ++c) {
        const wr_poisson_curve *k = c == 0 ? &dom->outer : (c <= dom->n_holes ? &dom->holes[c - 1] : &dom->lines[c - 1 - dom->n_holes]);
        int is_loop = c <= dom->n_holes;
        int32_t need = is_loop || k->closed ? 3 : 2;
        wr__pz_curve_name(cv, c, name, sizeof name);
        if (k->n < need || !k->xy)
            return wr_fail(diag, WR_ERR_GEOMETRY, c, "%s has %d points (at least %d needed)", name, (int)k->n, (int)need);
        if (np > INT32_MAX - k->n) return wr_fail(diag, WR_ERR_OVERFLOW, c, "too many input points");
        cv->off[c] = np;
        cv->cnt[c] = k->n;
        cv->closed[c] = is_loop || k->closed;
        np += k->n;
    }
    cv->np = np;
    cv->xy = (double *)wr_alloc_array((size_t)np, 2 * sizeof(double));
    if (!cv->xy) return wr_fail(diag, WR_ERR_NOMEM, -1, "out of memory");
    for (c = 0; c < nc; ++c) {
        const wr_poisson_curve *k = c == 0 ? &dom->outer : (c <= dom->n_holes ? &dom->holes[c - 1] : &dom->lines[c - 1 - dom->n_holes]);
        wr__pz_curve_name(cv, c, name, sizeof name);
        for (i = 0; i < k->n; ++i) {
            double x = k->xy[2 * i], y = k->xy[2 * i + 1];
            if (!isfinite(x) || !isfinite(y))
                return wr_fail(diag, WR_ERR_GEOMETRY, i, "%s point %d is not finite (%g, %g)", name, (int)i, x, y);
            cv->xy[2 * (cv->off[c] + i)] = x;
            cv->xy[2 * (cv->off[c] + i) + 1] = y;
        }
    }
    return WR_OK;
}

WRDEF wr_status wr_poisson_sample(const wr_poisson_domain *dom, wr_poisson_sizing_fn sizing, void *user,
                                  const wr_poisson_desc *desc_in, wr_poisson_result *res, wr_diag *diag) {
    wr_poisson_desc desc;
    wr__pz z;
    wr__pz_curves in, dc;
    wr__pz_inside ins;
    wr_status st = WR_OK;
    int32_t c, i, k;
    int32_t *active = NULL;
    double t0 = wr_time_seconds(), x0, y0, x1, y1, W, H, maxdim, tol;
    char name[32], name2[32];
    memset(&z, 0, sizeof z);
    memset(&in, 0, sizeof in);
    memset(&dc, 0, sizeof dc);
    memset(&ins, 0, sizeof ins);
    if (res) memset(res, 0, sizeof *res);
    if (!dom || !sizing || !res) return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "wr_poisson_sample: NULL argument");
    if (dom->n_holes < 0 || dom->n_lines < 0 || (dom->n_holes > 0 && !dom->holes) || (dom->n_lines > 0 && !dom->lines))
        return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "wr_poisson_sample: bad hole/line arrays");
    /* defaults (the one place) */
    if (desc_in)
        desc = *desc_in;
    else
        memset(&desc, 0, sizeof desc);
    if (desc.k == 0) desc.k = WR_POISSON_DEFAULT_K;
    if (desc.radius_factor == 0.0) desc.radius_factor = WR_POISSON_DEFAULT_RADIUS_FACTOR;
    if (desc.max_points == 0) desc.max_points = WR_POISSON_DEFAULT_MAX_POINTS;
    if (desc.corner_angle == 0.0) desc.corner_angle = WR_POISSON_DEFAULT_CORNER_ANGLE;
    if (desc.k < 1 || !(desc.radius_factor > 0.0) || !isfinite(desc.radius_factor) || desc.max_points < 1 ||
        !(desc.corner_angle > 0.0))
        return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "wr_poisson_desc: k=%d radius_factor=%g max_points=%d corner_angle=%g",
                       (int)desc.k, desc.radius_factor, (int)desc.max_points, desc.corner_angle);
    z.fn = sizing;
    z.user = user;
    z.diag = diag;
    z.c = desc.radius_factor;
    z.max_points = desc.max_points;

    /* 1. input validation */
    if ((st = wr__pz_gather(dom, &in, diag)) != WR_OK) goto done;
    x0 = y0 = HUGE_VAL;
    x1 = y1 = -HUGE_VAL;
    for (i = 0; i < in.cnt[0]; ++i) {
        x0 = fmin(x0, in.xy[2 * i]);
        x1 = fmax(x1, in.xy[2 * i]);
        y0 = fmin(y0, in.xy[2 * i + 1]);
        y1 = fmax(y1, in.xy[2 * i + 1]);
    }
    W = x1 - x0;
    H = y1 - y0;
    maxdim = fmax(W, H);
    tol = WR_POISSON_REL_TOL * maxdim;
    for (c = 0; c < in.nc; ++c) {
        const double *v = in.xy + 2 * in.off[c];
        int32_t n = in.cnt[c];
        wr__pz_curve_name(&in, c, name, sizeof name);
        for (i = 0; i < wr__pz_nseg(&in, c); ++i) {
            const double *a = v + 2 * i, *b = v + 2 * ((i + 1) % n);
            if (a[0] == b[0] && a[1] == b[1]) {
                st = wr_fail(diag, WR_ERR_GEOMETRY, i, "%s segment %d has zero length (points %d and %d coincide)", name,
                             (int)i, (int)i, (int)((i + 1) % n));
                goto done;
            }
        }
    }
    /* crossings before areas: a self-intersecting loop can have any signed area (a symmetric bow-tie
     * has 0), and the crossing is the more useful message */
    if ((st = wr__pz_check_crossings(&in, "input", diag)) != WR_OK) goto done;
    for (c = 0; c <= in.n_holes; ++c) {
        const double *v = in.xy + 2 * in.off[c];
        int32_t n = in.cnt[c];
        /* about the first vertex (core.h): an origin-based shoelace cancels a small far loop away */
        double area = wr_polygon_area(v, n);
        wr__pz_curve_name(&in, c, name, sizeof name);
        if (!(fabs(area) > WR_POISSON_REL_TOL * maxdim * maxdim)) {
            st = wr_fail(diag, WR_ERR_GEOMETRY, c, "%s has zero area (%g m^2)", name, area);
            goto done;
        }
    }
    /* no crossings: one vertex decides each containment relation */
    for (c = 1; c < in.nc; ++c) {
        const double *p = in.xy + 2 * in.off[c];
        wr__pz_curve_name(&in, c, name, sizeof name);
        if (!wr__pz_in_curve(&in, 0, p)) {
            st = wr_fail(diag, WR_ERR_GEOMETRY, c, "%s lies outside the outer loop", name);
            goto done;
        }
        for (k = 1; k <= in.n_holes; ++k) {
            if (k == c) continue;
            if (wr__pz_in_curve(&in, k, p) || (c <= in.n_holes && wr__pz_in_curve(&in, c, in.xy + 2 * in.off[k]))) {
                wr__pz_curve_name(&in, k, name2, sizeof name2);
                st = wr_fail(diag, WR_ERR_GEOMETRY, c, "%s %s %s", name, c <= in.n_holes ? "overlaps" : "lies inside",
                             name2);
                goto done;
            }
        }
    }

    /* 2. fixed points along every curve at the local sizing */
    if ((st = wr__pz_discretise(&z, &in, desc.corner_angle, &dc)) != WR_OK) goto done;
    if ((st = wr__pz_check_crossings(&dc, "discretised at the sizing (feature thinner than the sizing?)", diag)) !=
        WR_OK)
        goto done;
    if ((st = wr__pz_inside_build(&ins, &dc, x0, y0, W, H, tol, diag)) != WR_OK) goto done;

    /* 3. budget: n_fixed + κ ∫ dA / r² on a probe lattice, before any per-sample allocation */
    {
        int32_t M = WR_POISSON_BUDGET_PROBES, a, b;
        double dA = (W / M) * (H / M), integ = 0.0, rmax = 0.0, est;
        for (b = 0; b < M; ++b)
            for (a = 0; a < M; ++a) {
                double px = x0 + (a + 0.5) * W / M, py = y0 + (b + 0.5) * H / M, h, r;
                if (!wr__pz_inside_at(&ins, px, py)) continue;
                if ((st = wr__pz_size(&z, px, py, &h)) != WR_OK) goto done;
                r = z.c * h;
                integ += dA / (r * r);
                rmax = fmax(rmax, r);
            }
        for (i = 0; i < dc.np; ++i) {
            double h;
            if ((st = wr__pz_size(&z, dc.xy[2 * i], dc.xy[2 * i + 1], &h)) != WR_OK) goto done;
            rmax = fmax(rmax, z.c * h);
        }
        est = (double)dc.np + WR_POISSON_DENSITY * integ;
        res->n_estimated = est < (double)INT32_MAX ? (int32_t)est : INT32_MAX;
        if (est > (double)desc.max_points) {
            st = wr_fail(diag, WR_ERR_BUDGET, -1,
                         "estimated %.0f points (%d fixed + %.3g * integral dA/r^2) exceed max_points=%d", est,
                         (int)dc.np, WR_POISSON_DENSITY, (int)desc.max_points);
            goto done;
        }
        /* grids */
        z.x0 = x0;
        z.y0 = y0;
        z.W = W;
        z.H = H;
        z.s_base = ldexp(fmax(maxdim, 1e-300), -28);
        for (i = 0; i < 64; ++i) {
            z.cs[i] = ldexp(z.s_base, i + 1);
            z.inv_cs[i] = 1.0 / z.cs[i];
            z.rmax[i] = 0.0;
        }
        z.mg = 2.0 * rmax;
        {
            double cells_cap = fmax(4096.0, 4.0 * est);
            while ((W / z.mg + 1.0) * (H / z.mg + 1.0) > cells_cap) z.mg *= 1.5;
        }
        z.inv_mg = 1.0 / z.mg;
        z.mx = (int32_t)(W * z.inv_mg) + 1;
        z.my = (int32_t)(H * z.inv_mg) + 1;
        z.mask = (uint64_t *)wr_calloc_array((size_t)z.mx * (size_t)z.my, sizeof(uint64_t));
        if (!z.mask) {
            st = wr_fail(diag, WR_ERR_NOMEM, -1, "presence grid: out of memory");
            goto done;
        }
        /* tiles hold 16 cells of >= 2 r: ~ one tile per 16·(2r)²·κ/r² ≈ 40 samples; be generous */
        if ((st = wr__pz_hash_init(&z, (size_t)(est / 16.0) + 16)) != WR_OK) goto done;
        {
            /* initial sample capacity from the estimate (+10%), never above the budget */
            double want = fmin(1.1 * est + 64.0, (double)desc.max_points);
            int32_t nc = (int32_t)want;
            if (nc < 16) nc = 16;
            z.sm = (wr__pz_s *)wr_alloc_array((size_t)nc, sizeof(wr__pz_s));
            z.h = (double *)wr_alloc_array((size_t)nc, sizeof(double));
            active = (int32_t *)wr_alloc_array((size_t)nc, sizeof(int32_t));
            if (!z.sm || !z.h || !active) {
                st = wr_fail(diag, WR_ERR_NOMEM, -1, "samples: out of memory");
                goto done;
            }
            z.cap = nc;
        }
    }

    /* 4. fixed points first, all active */
    for (i = 0; i < dc.np; ++i) {
        double h;
        if ((st = wr__pz_size(&z, dc.xy[2 * i], dc.xy[2 * i + 1], &h)) != WR_OK) goto done;
        if ((st = wr__pz_insert(&z, dc.xy[2 * i], dc.xy[2 * i + 1], h)) != WR_OK) goto done;
    }

    /* 5. Bridson's active list with the mean conflict rule */
    {
        wr_rng rng;
        int32_t n_active = 0, acap = z.cap;
        int64_t ncand = 0;
        wr_rng_seed(&rng, desc.seed);
        for (i = 0; i < z.n; ++i) active[n_active++] = i;
        while (n_active > 0) {
            int32_t ai = (int32_t)wr_rng_below(&rng, (uint32_t)n_active), p = active[ai];
            double px = z.sm[p].x, py = z.sm[p].y, rp = z.sm[p].r;
            int found = 0;
            for (k = 0; k < desc.k; ++k) {
                double ux, uy, d2, qx, qy, hq;
                /* uniform by area in the annulus r <= |d| < 2r: rejection from the square [-2,2]²
                 * (acceptance 3π/16 ≈ 0.59; cheaper than sincos, which was 22% of the run time) */
                do {
                    ux = 4.0 * wr_rng_uniform(&rng) - 2.0;
                    uy = 4.0 * wr_rng_uniform(&rng) - 2.0;
                    d2 = ux * ux + uy * uy;
                } while (d2 < 1.0 || d2 >= 4.0);
                qx = px + rp * ux;
                qy = py + rp * uy;
                ++ncand;
                if (!wr__pz_inside_at(&ins, qx, qy)) continue;
                if ((st = wr__pz_size(&z, qx, qy, &hq)) != WR_OK) goto done;
                if (wr__pz_conflict(&z, qx, qy, z.c * hq)) continue;
                if ((st = wr__pz_insert(&z, qx, qy, hq)) != WR_OK) goto done;
                if (n_active == acap) {
                    int32_t *a2;
                    acap = z.cap;
                    a2 = (int32_t *)wr_realloc_array(active, (size_t)acap, sizeof(int32_t));
                    if (!a2) {
                        st = wr_fail(diag, WR_ERR_NOMEM, -1, "active list: out of memory");
                        goto done;
                    }
                    active = a2;
                }
                active[n_active++] = z.n - 1;
                found = 1;
                break;
            }
            if (!found) active[ai] = active[--n_active];
        }
        res->n_candidates = ncand;
    }

    /* 6. output */
    {
        int32_t ns = 0, s = 0;
        for (c = 0; c < dc.nc; ++c) ns += wr__pz_nseg(&dc, c);
        res->points = (double *)wr_alloc_array((size_t)z.n, 2 * sizeof(double));
        res->sizing = (double *)wr_alloc_array((size_t)z.n, sizeof(double));
        res->segments = (int32_t *)wr_alloc_array((size_t)ns, 2 * sizeof(int32_t));
        res->segment_owner = (int32_t *)wr_alloc_array((size_t)ns, sizeof(int32_t));
        if (!res->points || !res->sizing || !res->segments || !res->segment_owner) {
            st = wr_fail(diag, WR_ERR_NOMEM, -1, "result: out of memory");
            goto done;
        }
        for (i = 0; i < z.n; ++i) {
            res->points[2 * i] = z.sm[i].x;
            res->points[2 * i + 1] = z.sm[i].y;
        }
        memcpy(res->sizing, z.h, sizeof(double) * (size_t)z.n);
        for (c = 0; c < dc.nc; ++c)
            for (i = 0; i < wr__pz_nseg(&dc, c); ++i, ++s) {
                res->segments[2 * s] = dc.off[c] + i;
                res->segments[2 * s + 1] = dc.off[c] + (i + 1) % dc.cnt[c];
                res->segment_owner[s] = c;
            }
        res->n_points = z.n;
        res->n_fixed = dc.np;
        res->n_segments = ns;
    }
done:
    if (st != WR_OK && res) {
        int32_t est = res->n_estimated;
        wr_poisson_free(res);
        res->n_estimated = est;
    }
    if (res) res->seconds = wr_time_seconds() - t0;
    wr_free(active);
    wr__pz_free(&z);
    wr__pz_curves_free(&in);
    wr__pz_curves_free(&dc);
    wr__pz_inside_free(&ins);
    return st;
}

#ifdef __cplusplus
}
#endif
#endif /* WRINKLE_POISSON_IMPLEMENTATION_DONE */
#endif /* WRINKLE_IMPLEMENTATION */
