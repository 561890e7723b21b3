/* wrinkle/poisson.h — variable-radius Poisson-disk sampling of polygons with holes and constraint
 * lines, driven by a sizing callback (target edge length [m]).
 * wrinkle v0.1.0 — MIT licence (see LICENSE). Needs only libc and libm (and core.h).
 *
 * Style3D ("Physics-inspired Estimation of Optimal Cloth Mesh Resolution", Sec. 4.3): "we first
 * sample the sizing map using the fast Poisson disk sampling algorithm [Bridson 2007], ensuring that
 * the average vertex spacing locally aligns with the sizing values. The resulting point cloud, along
 * with boundary constraints, is then input into triangulation tools". This header is that step.
 * The curves (outer loop, hole loops, constraint polylines: shirring lines, seams, fold lines) are
 * either taken as given (wr_poisson_fill: the caller — the mesher — has discretised them already)
 * or discretised here at the local sizing (wr_poisson_sample); their points are kept fixed and their
 * edges come back as constraint segments for the triangulator (triangulate.h). The interior is filled
 * by an advancing front of Poisson-disk samples (see ON THE ALGORITHM).
 *
 * API (create/free pair: wr_poisson_fill or wr_poisson_sample → wr_poisson_free)
 *   wr_poisson_fill(dom, sizing, user, desc, res, diag)       curves as given → fixed points, fill
 *   wr_poisson_sample(dom, sizing, user, desc, res, diag)     discretise the curves at the sizing, fill
 *   wr_poisson_estimate(dom, sizing, user, desc, &bud, diag)  the budget estimate alone (cheap)
 *   wr_poisson_free(res)                                      free and zero (safe on a zeroed result)
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
 *     // curves already discretised (here the 4 corners only): they are kept exactly as given
 *     if (wr_poisson_fill(&dom, size_fn, NULL, &desc, &res, &d) != WR_OK) { puts(d.message); return 1; }
 *     printf("fill: %d points, the first %d are the input's\n", res.n_points, res.n_fixed);
 *     wr_poisson_free(&res);
 *
 * ON THE ALGORITHM
 *   Every point, fixed points first and then the samples in order of creation (first in, first
 *   out), takes one front step (Dunbar & Humphreys 2006, "A spatial data structure for fast
 *   Poisson-disk sample generation": boundary sampling, here with a radius that varies in space):
 *   new samples are placed on the circle of radius r(p) around p, in directions drawn uniformly
 *   from the arcs still free, until no direction is left. The neighbours' blocked arcs are cut all
 *   at once before the first draw (lens ends by rotation, no trigonometric call per neighbour;
 *   merged in a pseudo-angle and only the merged ends converted), so a draw is never wasted on a
 *   neighbour and the sizing is evaluated once per accepted sample at constant sizing (the law of
 *   the draws is that of drawing over the whole circle and redrawing on a conflict: uniform over
 *   the free directions). Where the sizing differs from r(p) the candidate sits at the mean-rule
 *   distance ρ = (r(p) + r(ρ))/2 along its direction: placed there at once from a sizing gradient
 *   estimate that every evaluation corrects and every new sample inherits (so about one evaluation
 *   per candidate on a graded map), else reached by a fixed-point iteration (up to 3 moves, each
 *   one more evaluation; counts per sample: docs/notes-mesher.md), so the front also crosses steep
 *   transitions in either direction. The domain's segments near p cut the arcs
 *   outside the domain and within the clearance of a segment before any candidate is drawn. Work
 *   per sample is bounded (one neighbour query, a few arc cuts), so the fill is O(n) and the sizing
 *   is evaluated a bounded number of times per sample (no dart throwing with a failure count). The
 *   result is maximal up to the failed-candidate arcs: every point of the domain is within about r
 *   of a sample.
 *
 * ON THE SIZING → RADIUS RELATION
 *   The sizing h(x) is the target mesh edge length. Each sample p carries the disk radius
 *   r(p) = radius_factor · h(p). Where the value comes from: a sampler of density κ samples per r²
 *   whose Delaunay triangulation has mean edge length β / sqrt(density) gives a mean edge of
 *   β r / sqrt(κ); setting it to h gives radius_factor = sqrt(κ) / β. For the hexagonal lattice
 *   β = sqrt(2/√3) = 1.0746 (edge a, density 2/(√3 a²)), for a Poisson process β = 32/(9π) =
 *   1.1318. This sampler: κ = 0.885 (WR_POISSON_DENSITY) and β = 1.100, measured on the unit square
 *   (tests/test_poisson.c "density" and "calibration"), so radius_factor = sqrt(0.885)/1.100 = 0.855.
 *   The front's mean-rule packing sits nearer the lattice than random dart throwing (higher κ), which
 *   is why more of the radius is needed for the same edge length (figures: docs/notes-mesher.md).
 *
 * ON THE CONFLICT RULE (varying radius) AND THE CLEARANCE
 *   Two points p, q conflict when |p − q| < (r(p) + r(q)) / 2 (the symmetric "mean" rule; it is
 *   well defined, independent of insertion order, and equals the classical rule for constant r).
 *   Every pair in which at least one point is an interior sample satisfies |p − q| >= (r(p)+r(q))/2,
 *   with r = c h for samples and line points and r = (2 D − c) h for loop points (ON THE FIRST RING).
 *   Fixed points are not tested against each other (they are the caller's geometry). Every sample is
 *   at least desc.clearance · h from every constraint segment (default 0.35: a triangle on a segment
 *   of length h with its apex 0.35 h away keeps angles >= 35°; between fixed points h apart the mean
 *   rule alone keeps samples sqrt(0.855² − 0.5²) h = 0.69 h away from a line, sqrt(0.93² − 0.5²) h =
 *   0.78 h from a loop, so the clearance acts only where a segment is longer than about 1.6 h).
 *
 * ON THE FIRST RING (samples next to the outer loop and the holes)
 *   Style3D Sec. 4.3 asks that "the average vertex spacing locally aligns with the sizing values";
 *   the radius factor does that for the interior, where the disks of radius r = 0.855 h pack
 *   irregularly and their mean Delaunay edge is h. Next to a loop the curve points are a regular row
 *   h apart, and the front places samples on the circle of the mean-rule distance around them: at
 *   0.855 h from two points h apart a sample sits 0.69 h above the curve (mean ring height 0.77 h,
 *   the equilateral apex is at 0.866 h) and its edges to the curve average 0.93 h. So a sample and
 *   a loop point f conflict below (r_f + r_q)/2 with r_f = (2 D − c) h_f: the distance is D h at
 *   equal sizing, and D (desc.fixed_distance) is calibrated like the radius factor, to the same
 *   target: the mean Delaunay edge from loop points to samples = h (D = 0.93: mean ring height
 *   0.85 h). Points of constraint lines keep the interior rule (r_f = c h): around shirring lines
 *   the sizing grows steeply and their edges to the samples are already at h, and a fold's three
 *   lines 0.5 mm apart would add up their exclusions (measurements: docs/notes-mesher.md). Fixed
 *   points are still not tested against each other.
 *
 * ON COVERAGE (what is, and is not, guaranteed)
 *   The front stops at a point when no free direction is left, so gaps are closed up to the
 *   angular resolution of failed candidates (WR__PZ_FAIL_ARC) and the desc.k cap on failures per
 *   point. tests/test_poisson.c checks, on a probe lattice, that every probe x strictly inside the
 *   domain has a sample within 1.5 r(x) (constant, graded, holes and lines, steep transitions) and
 *   prints the largest empty-disk ratio it saw (0.9–1.0 r).
 *
 * ON THE ACCELERATION GRID (why it stays O(n) when the radius varies 20×)
 *   Radii are bucketed into octave levels: level l holds samples with r in [s·2^l, s·2^(l+1)),
 *   s = bbox size / 2^28. Each level is a hashed grid (open addressing, key = level + 8×8 tile of
 *   cells, with a 64-bit mask of the tile's occupied cells) with cell size 2·s·2^l >= every radius
 *   of that level, so a same-level query touches few cells and skips the empty ones. A dense "presence" grid with cells of ≈ 2·r_max keeps, per cell, a 64-bit mask of the
 *   levels present in it (filled once a second level is in use: with one level, every query probes
 *   that one); a query probes only the levels present around the point. For a sizing
 *   that is smooth on the scale of r_max, only 1–2 levels are present around a point, so the work
 *   per sample is bounded independently of n and of r_max/r_min; memory is O(n). The segments sit in
 *   a bucket grid with O(segments) cells for any aspect ratio (inside test and clearance).
 *
 * ON THE BUDGET (bounded time on every input)
 *   Before anything that grows faster than the input, the point count is estimated from area and
 *   perimeter: n_curves (the given points, or ∫ ds / h by Simpson's rule per input segment) plus
 *   κ · area · mean(1/r²) over a 128×128-probe lattice (aspect ratio of the bounding box; inside test
 *   by a scanline over the loops, O(input + probes)). Over desc.max_points → WR_ERR_BUDGET, message
 *   "... > max_points=N: raise max_points or coarsen the sizing" with the numbers behind it. The
 *   sampling itself stops with WR_ERR_BUDGET if it would exceed max_points all the same.
 *
 * ON VALIDATION (all WR_ERR_GEOMETRY unless said otherwise)
 *   Loops need >= 3 points, polylines >= 2 (closed polylines >= 3); non-finite coordinate; an input
 *   extent that overflows a double; zero-length segment; loop with |area| <= WR_POISSON_REL_TOL·bbox²;
 *   any two segments (same or different curves, adjacent ones only when they fold back) that touch
 *   or cross — the message names both; a hole not inside the outer loop; a hole inside another hole;
 *   a polyline not inside the domain. Checked on a uniform bucket grid (O(n) for evenly spaced
 *   input). wr_poisson_sample runs the crossing check again on the discretised segments (chords can
 *   cross where a feature is thinner than the sizing). The sizing callback returning a value that is
 *   not a positive finite number → WR_ERR_DOMAIN naming the point. NULL arguments →
 *   WR_ERR_INVALID_ARG. Structured location (no need to parse the message): diag->curve (0 outer,
 *   1 + i hole i, 1 + n_holes + j line j), diag->item (point or segment index within that curve),
 *   diag->other_curve / other_item for the second segment of a crossing or the other curve of a
 *   containment failure; -1 where not applicable. diag->part is left for the caller (the panel).
 *
 * ON OUTPUT ORDER AND OWNERS
 *   Fixed points: outer loop, then holes in order, then polylines in order. wr_poisson_fill keeps
 *   the input points exactly (res.points[0 .. 2 n_fixed) is the concatenation of the curves' xy, so
 *   the caller's indices stay valid) and its segments are the curves' edges. wr_poisson_sample:
 *   each curve starts at its input vertex 0 and follows the input direction (any orientation is
 *   accepted and kept). Input vertices whose turning angle exceeds desc.corner_angle are kept exactly
 *   ("corners"), unless they lie closer than h/2 (arc length) to the previous kept vertex or to the
 *   curve's end; vertex 0 and open-polyline endpoints are always kept. Between kept vertices points
 *   follow ∫ ds/h with the segment count N = max(1, round(∫ ds/h)) and the points redistributed so
 *   every piece has ∫ ds/h = total/N (so endpoints are hit exactly and no last step is tiny). Hence
 *   every constraint segment has ∫ ds/h in [0.5, 1.5] measured along the input curve (up to the
 *   trapezoid error of the walk), except where a closed curve needs more segments to reach its
 *   minimum of 3. segment_owner: 0 = outer loop, 1 + i = hole i, 1 + n_holes + j = polyline j.
 *   The inside test (crossing number, boundary points count as outside) uses the segments returned,
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

/* r = radius_factor · h = sqrt(κ)/β · h (ON THE SIZING → RADIUS RELATION): the mean Delaunay edge
 * between interior samples over the mean of their two sizings is 0.995–1.004 with this value
 * (tests/test_poisson.c "calibration", constant and 20×-graded h; band ±2 %). */
#define WR_POISSON_DEFAULT_RADIUS_FACTOR 0.855
/* Failed candidates allowed per front step before the point is retired. */
#define WR_POISSON_DEFAULT_K 30
#define WR_POISSON_DEFAULT_MAX_POINTS 50000000
#define WR_POISSON_DEFAULT_CORNER_ANGLE 0.5235987755982988 /* 30° [rad] */
/* Minimum distance sample → constraint segment, in units of the sample's sizing h (see ON THE
 * CONFLICT RULE AND THE CLEARANCE for the 35° reading of 0.35). */
#define WR_POISSON_DEFAULT_CLEARANCE 0.35
/* D: a sample keeps (r_f + r)/2 = D h from a point of the outer loop or a hole (ON THE FIRST RING);
 * 0.93 makes the mean Delaunay edge between such points and the first ring = the sizing (±2 %,
 * tests/test_poisson.c "first_ring_calibration"), the interior's calibration target. */
#define WR_POISSON_DEFAULT_FIXED_DISTANCE 0.93
/* κ: samples per r² of area for this sampler, N ≈ κ ∫ dA / r²: 0.885 measured in test_poisson.c
 * "density" (unit square, h = 0.01; 0.883 at h = 0.002); used for the budget estimate. */
#define WR_POISSON_DENSITY 0.885
/* Relative tolerance (× bbox size) for "on a boundary segment" and (× bbox size²) for zero area. */
#define WR_POISSON_REL_TOL 1e-12
/* Arc-length walking step along curves, as a fraction of the local sizing (trapezoid rule on 1/h). */
#define WR_POISSON_WALK_STEP 0.25
/* Probe lattice (per axis, for a square box) for the ∫ dA / r² budget estimate. */
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
 *   k             WR_POISSON_DEFAULT_K failed candidates per front step
 *   radius_factor WR_POISSON_DEFAULT_RADIUS_FACTOR (r = radius_factor · h)
 *   max_points    WR_POISSON_DEFAULT_MAX_POINTS (fixed + interior)
 *   corner_angle  WR_POISSON_DEFAULT_CORNER_ANGLE [rad] (wr_poisson_sample only); a tiny positive
 *                 value keeps every vertex
 *   clearance     WR_POISSON_DEFAULT_CLEARANCE (× h); must stay below radius_factor / 2
 *   fixed_distance WR_POISSON_DEFAULT_FIXED_DISTANCE (× h): sample to loop point; in
 *                 (radius_factor / 2, 4); radius_factor itself gives the interior rule there too */
typedef struct wr_poisson_desc {
    uint64_t seed;
    int32_t k;
    double radius_factor;
    int32_t max_points;
    double corner_angle;
    double clearance;
    double fixed_distance;
} wr_poisson_desc;

typedef struct wr_poisson_result {
    double *points;         /* n_points×2 [m]; the first n_fixed are boundary/constraint points */
    double *sizing;         /* n_points: h at each point [m] */
    int32_t n_points;
    int32_t n_fixed;
    int32_t *segments;      /* n_segments×2 indices into points (constraint edges for the CDT) */
    int32_t *segment_owner; /* n_segments: 0 outer, 1+i hole i, 1+n_holes+j polyline j */
    int32_t n_segments;
    int32_t n_estimated;    /* budget estimate: curve points + κ ∫ dA / r² (kept on failure) */
    int64_t n_candidates;   /* sizing evaluations of the fill (candidates that survived the neighbours) */
    double seconds;         /* wall time of the call */
} wr_poisson_result;

/* The budget estimate (ON THE BUDGET); all counts are expected values, not bounds. */
typedef struct wr_poisson_budget {
    double area;          /* |outer| − Σ |holes| [m²] */
    double perimeter;     /* total length of all curves [m] */
    double n_given;       /* curve points as given (what wr_poisson_fill keeps) */
    double n_discretised; /* Σ ∫ ds / h over the curves (about what wr_poisson_sample puts on them) */
    double n_interior;    /* κ · area · mean(1/r²) over the inside probes */
    double h_min, h_max;  /* smallest / largest sizing seen [m] */
    int32_t n_probes;     /* probes inside the domain */
} wr_poisson_budget;

WRDEF wr_status wr_poisson_fill(const wr_poisson_domain *dom, wr_poisson_sizing_fn sizing, void *user,
                                const wr_poisson_desc *desc, wr_poisson_result *res, wr_diag *diag);
WRDEF wr_status wr_poisson_sample(const wr_poisson_domain *dom, wr_poisson_sizing_fn sizing, void *user,
                                  const wr_poisson_desc *desc, wr_poisson_result *res, wr_diag *diag);
WRDEF wr_status wr_poisson_estimate(const wr_poisson_domain *dom, wr_poisson_sizing_fn sizing, void *user,
                                    const wr_poisson_desc *desc, wr_poisson_budget *bud, wr_diag *diag);
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
#include <stdlib.h>
#include <string.h>

#ifdef __cplusplus
extern "C" {
#endif

/* Front-step constants (ON THE ALGORITHM). Dimensionless unless said otherwise. */
/* Placement radius ρ = r_p (1 + GAP): just beyond the mean-rule distance, so rounding cannot make
 * a new sample conflict with the point it was placed from. */
#define WR__PZ_GAP 1e-9
/* A candidate moved to the mean-rule distance goes that much further (the sizing at the new spot
 * may be a little larger again: 1e-3 absorbs a 0.1 % change over the move). */
#define WR__PZ_MOVE_GAP 1e-3
/* Moves (extra sizing evaluations) allowed per candidate: 3 reach the fixed point of
 * ρ = (r_p + r(ρ))/2 to < 1 % across a transition that halves the sizing within one h. */
#define WR__PZ_MOVES 3
/* The neighbour list of a step is complete for candidates with r <= RBOUND · r_p (larger ones ask
 * the grid); 1.1 covers a 10 % sizing change over one radius (steeper than a graded map). */
#define WR__PZ_RBOUND 1.1
/* A candidate whose mean-rule distance to p differs from ρ by more than this fraction moves there
 * and is evaluated again (2 %: well below the calibration band, rarely triggered by smooth maps). */
#define WR__PZ_REPLACE 0.02
/* The predicted placement (wr__pz_activate) only where it moves the candidate by less than this
 * relative share of its radius, |c ∇h·u| / 2 < 0.25 (a 20× ramp: 0.3–4 % per step); a steeper
 * estimate — a jump of the sizing seen from one side — is left to the moves, as without one. */
#define WR__PZ_PREDICT_MAX 0.25
/* Arc cut around a failed candidate [rad]: bounds the candidates per step (π/48 ≈ 3.75°). */
#define WR__PZ_FAIL_ARC 0.06544984694978735
/* Arc cut around a direction already settled [rad] (guards rounding at arc ends). */
#define WR__PZ_TINY_ARC 1e-9
/* The skipped neighbour test of a front step (wr__pz_activate): a drawn direction at least
 * WR__PZ_INNER [rad] inside its free arc is that far outside every neighbour's lens up to the
 * lens ends' error (~1e-7 rad: the polynomial atan2/acos), so its distance to the neighbour
 * exceeds the mean-rule distance by >= ~ρ d·WR__PZ_INNER²/2 ≈ 5e-9 r² even for a lens that just
 * touches the circle; a neighbour whose lens test is within a relative WR__PZ_TANGENT of touching
 * (cut or not) sends the step back to the full test. WR__PZ_SCALE: coordinates at most this many
 * radii from the origin round at <= 2.2e-11 r, far below those margins. */
#define WR__PZ_INNER 1e-4
#define WR__PZ_TANGENT 1e-9
#define WR__PZ_SCALE 1e5

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

/* The structured location of a failure (core.h wr_diag: curve, item, other_curve, other_item). */
static wr_status wr__pz_where(wr_diag *diag, wr_status st, int32_t curve, int32_t item, int32_t other_curve,
                              int32_t other_item) {
    if (diag) {
        diag->curve = curve;
        diag->item = item;
        diag->other_curve = other_curve;
        diag->other_item = other_item;
    }
    return st;
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
                    wr__pz_where(diag, st, seg_c[fs], seg_i[fs], seg_c[ls], seg_i[ls]);
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
/* Segment grid: every constraint segment (loops and lines) in a bucket grid. It answers the two
 * questions the sampler asks of the curves: is a point inside the domain (loop segments only), and
 * is it at least a clearance away from every segment (all of them).
 * Inside test: edge-free cells carry their in/out status (computed by a right-to-left sweep per
 * row), other cells cast two rays in lockstep, +x along y = q.y and +y along x = q.x, each ending at
 * its first edge-free cell (status ^ parity) or at the grid's end (outside); the ray that ends first
 * answers. Crossings use the half-open rule ((y1 > y) != (y2 > y) for the +x ray) and count only in
 * the cell that contains the crossing, so edges spanning several cells count once. Why two rays: in
 * a domain thinner than a cell every cell of its rows holds both long boundaries, so a +x ray alone
 * walks the whole row (O(nx) per query); the +y ray leaves such a strip within two cells, and a
 * strip along y is the +x ray's easy case. */
#define WR__PZ_DBLOCK 8
typedef struct wr__pz_segs {
    double x0, y0, g, inv_g, tol;
    int32_t nx, ny;
    int32_t *cstart, *clist;
    unsigned char *status;
    unsigned char *dist; /* chessboard distance [cells] to the nearest cell holding a segment, <= 255 */
    unsigned char *bdist; /* the least dist of each block of WR__PZ_DBLOCK × WR__PZ_DBLOCK cells */
    int32_t nbx;          /* blocks per row */
    double *seg;         /* ne×4: x1 y1 x2 y2 */
    unsigned char *loop; /* ne: 1 = loop edge (counts for the inside parity), 0 = constraint line */
    int32_t ne;
} wr__pz_segs;

static void wr__pz_segs_free(wr__pz_segs *t) {
    wr_free(t->cstart);
    wr_free(t->clist);
    wr_free(t->status);
    wr_free(t->dist);
    wr_free(t->bdist);
    wr_free(t->seg);
    wr_free(t->loop);
    memset(t, 0, sizeof *t);
}

/* Cell index along axis 0 (x) or 1 (y), clamped to [-1, n]. */
static int32_t wr__pz_cell(const wr__pz_segs *t, int axis, double v) {
    double f = (v - (axis ? t->y0 : t->x0)) * t->inv_g;
    int32_t n = axis ? t->ny : t->nx;
    if (!(f >= 0.0)) return -1;
    if (f >= (double)n) return n;
    return (int32_t)f;
}

/* Parity of the loop crossings, inside `cell` (index k along the ray), of the ray from q along +x
 * (axis 0) or +y (axis 1); half-open rule across the other axis, counted only where it lies. */
static int wr__pz_ray_cell(const wr__pz_segs *t, int32_t cell, int axis, const double q[2], int32_t k) {
    int32_t p, a = axis, b = 1 - axis;
    int par = 0;
    for (p = t->cstart[cell]; p < t->cstart[cell + 1]; ++p) {
        const double *s = t->seg + 4 * t->clist[p];
        if (!t->loop[t->clist[p]]) continue;
        if ((s[b] > q[b]) != (s[2 + b] > q[b])) {
            double c = s[a] + (q[b] - s[b]) * (s[2 + a] - s[a]) / (s[2 + b] - s[b]);
            if (c > q[a] && wr__pz_cell(t, axis, c) == k) par ^= 1;
        }
    }
    return par;
}

static double wr__pz_seg_d2(const double *s, double qx, double qy) {
    double ex = s[2] - s[0], ey = s[3] - s[1], l2 = ex * ex + ey * ey;
    double u = l2 > 0.0 ? ((qx - s[0]) * ex + (qy - s[1]) * ey) / l2 : 0.0, dx, dy;
    u = u < 0.0 ? 0.0 : (u > 1.0 ? 1.0 : u);
    dx = s[0] + u * ex - qx;
    dy = s[1] + u * ey - qy;
    return dx * dx + dy * dy;
}

/* Strictly inside the loops (points within tol of a loop edge count as outside). */
static int wr__pz_inside_at(const wr__pz_segs *t, double qx, double qy) {
    int32_t ix = wr__pz_cell(t, 0, qx), iy = wr__pz_cell(t, 1, qy), i, j, cell, p;
    int parx = 0, pary = 0;
    double q[2];
    if (ix < 0 || ix >= t->nx || iy < 0 || iy >= t->ny) return 0;
    q[0] = qx;
    q[1] = qy;
    cell = iy * t->nx + ix;
    if (t->cstart[cell] == t->cstart[cell + 1]) return t->status[cell];
    for (p = t->cstart[cell]; p < t->cstart[cell + 1]; ++p)
        if (t->loop[t->clist[p]] && wr__pz_seg_d2(t->seg + 4 * t->clist[p], qx, qy) <= t->tol * t->tol) return 0;
    for (i = ix, j = iy;; ++i, ++j) {
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

/* No segment (loop or line) closer than d to q? */
static int wr__pz_clear_of_segments(const wr__pz_segs *t, double qx, double qy, double d) {
    int32_t ix0 = wr__pz_cell(t, 0, qx - d), ix1 = wr__pz_cell(t, 0, qx + d), ix, iy, p;
    int32_t iy0 = wr__pz_cell(t, 1, qy - d), iy1 = wr__pz_cell(t, 1, qy + d);
    ix0 = ix0 < 0 ? 0 : ix0;
    iy0 = iy0 < 0 ? 0 : iy0;
    ix1 = ix1 >= t->nx ? t->nx - 1 : ix1;
    iy1 = iy1 >= t->ny ? t->ny - 1 : iy1;
    for (iy = iy0; iy <= iy1; ++iy)
        for (ix = ix0; ix <= ix1; ++ix) {
            int32_t cell = iy * t->nx + ix;
            for (p = t->cstart[cell]; p < t->cstart[cell + 1]; ++p)
                if (wr__pz_seg_d2(t->seg + 4 * t->clist[p], qx, qy) < d * d) return 0;
        }
    return 1;
}

/* Register segment e's cell box (pass 0 counts, pass 1 fills). */
static wr_status wr__pz_segs_register(wr__pz_segs *t, int32_t e, int pass, int32_t *fill, int64_t *nreg,
                                      wr_diag *diag) {
    const double *s = t->seg + 4 * e;
    int32_t ix0 = wr__pz_cell(t, 0, fmin(s[0], s[2])), ix1 = wr__pz_cell(t, 0, fmax(s[0], s[2]));
    int32_t iy0 = wr__pz_cell(t, 1, fmin(s[1], s[3])), iy1 = wr__pz_cell(t, 1, fmax(s[1], s[3])), ix, iy;
    for (iy = iy0; iy <= iy1; ++iy)
        for (ix = ix0; ix <= ix1; ++ix) {
            int64_t cell = (int64_t)iy * t->nx + ix;
            if (pass == 0) {
                ++t->cstart[cell + 1];
                if (++*nreg >= INT32_MAX) return wr_fail(diag, WR_ERR_BUDGET, -1, "segment grid too large");
            } else {
                t->clist[fill[cell]++] = e;
            }
        }
    return WR_OK;
}

/* t->dist: the chessboard distance of every cell to the nearest cell holding a segment (two
 * raster passes over the 8-neighbourhood, exact for this metric), so a front step far from every
 * curve skips its scan of the segment cells (wr__pz_arcs_cut_curves) after one lookup. */
static void wr__pz_segs_dist(wr__pz_segs *t) {
    int32_t nx = t->nx, ny = t->ny, ix, iy;
    unsigned char *d = t->dist;
    for (iy = 0; iy < ny; ++iy)
        for (ix = 0; ix < nx; ++ix) {
            int32_t c = iy * nx + ix, v = t->cstart[c] < t->cstart[c + 1] ? 0 : 255;
            if (v && ix > 0 && d[c - 1] + 1 < v) v = d[c - 1] + 1;
            if (v && iy > 0) {
                const unsigned char *u = d + c - nx;
                if (u[0] + 1 < v) v = u[0] + 1;
                if (ix > 0 && u[-1] + 1 < v) v = u[-1] + 1;
                if (ix + 1 < nx && u[1] + 1 < v) v = u[1] + 1;
            }
            d[c] = (unsigned char)v;
        }
    for (iy = ny - 1; iy >= 0; --iy)
        for (ix = nx - 1; ix >= 0; --ix) {
            int32_t c = iy * nx + ix, v = d[c];
            if (v && ix + 1 < nx && d[c + 1] + 1 < v) v = d[c + 1] + 1;
            if (v && iy + 1 < ny) {
                const unsigned char *u = d + c + nx;
                if (u[0] + 1 < v) v = u[0] + 1;
                if (ix > 0 && u[-1] + 1 < v) v = u[-1] + 1;
                if (ix + 1 < nx && u[1] + 1 < v) v = u[1] + 1;
            }
            d[c] = (unsigned char)v;
        }
    /* the block minima: a lookup that stays in cache (dist has about one cell per sample, too
     * large for it: its lookup was the front step's most frequent cache miss) */
    memset(t->bdist, 255, (size_t)t->nbx * (size_t)((ny + WR__PZ_DBLOCK - 1) / WR__PZ_DBLOCK));
    for (iy = 0; iy < ny; ++iy)
        for (ix = 0; ix < nx; ++ix) {
            unsigned char *b = t->bdist + (iy / WR__PZ_DBLOCK) * t->nbx + ix / WR__PZ_DBLOCK;
            if (d[iy * nx + ix] < *b) *b = d[iy * nx + ix];
        }
}

/* Build from every curve of a curve set (loops: curves 0..n_holes). */
static wr_status wr__pz_segs_build(wr__pz_segs *t, const wr__pz_curves *cv, double x0, double y0, double W,
                                   double H, double tol, double n_est, wr_diag *diag) {
    int32_t c, i, e = 0, pass;
    int64_t ncell, nreg = 0, cell;
    int32_t *fill = NULL;
    wr_status st = WR_OK;
    memset(t, 0, sizeof *t);
    for (c = 0; c < cv->nc; ++c) t->ne += wr__pz_nseg(cv, c);
    /* ~4 cells per segment by area, and at most ~2 ne + 16 cells along the longer side, so the cell
     * count stays O(ne) for any aspect ratio */
    t->g = sqrt(fmax(W * H, 1e-300) / (4.0 * (double)t->ne));
    {
        /* cells about as large as the segments where the point count allows it (one cell per
         * expected point): the sampler's steps near a curve scan the segments of the cells within
         * ~2 r, and cells much larger than r put whole bands of samples beside the curves */
        double len = 0.0;
        for (c = 0; c < cv->nc; ++c)
            for (i = 0; i < wr__pz_nseg(cv, c); ++i) {
                const double *a = cv->xy + 2 * (cv->off[c] + i), *b = cv->xy + 2 * (cv->off[c] + (i + 1) % cv->cnt[c]);
                len += hypot(b[0] - a[0], b[1] - a[1]);
            }
        len /= (double)t->ne;
        if (len < t->g) t->g = fmax(len, sqrt(fmax(W * H, 1e-300) / fmax(4.0 * (double)t->ne, n_est)));
    }
    t->g = fmax(t->g, fmax(W, H) / (2.0 * (double)t->ne + 16.0));
    t->inv_g = 1.0 / t->g;
    /* one spare cell on each side so the grid strictly contains the curves */
    t->x0 = x0 - t->g;
    t->y0 = y0 - t->g;
    t->nx = (int32_t)(W / t->g) + 3;
    t->ny = (int32_t)(H / t->g) + 3;
    t->tol = tol;
    ncell = (int64_t)t->nx * t->ny;
    t->seg = (double *)wr_alloc_array((size_t)t->ne, 4 * sizeof(double));
    t->loop = (unsigned char *)wr_alloc_array((size_t)t->ne, 1);
    t->cstart = (int32_t *)wr_calloc_array((size_t)ncell + 1, sizeof(int32_t));
    t->status = (unsigned char *)wr_calloc_array((size_t)ncell, 1);
    if (!t->seg || !t->loop || !t->cstart || !t->status) goto nomem;
    for (c = 0; c < cv->nc; ++c)
        for (i = 0; i < wr__pz_nseg(cv, c); ++i, ++e) {
            const double *a = cv->xy + 2 * (cv->off[c] + i), *b = cv->xy + 2 * (cv->off[c] + (i + 1) % cv->cnt[c]);
            memcpy(t->seg + 4 * e, a, 2 * sizeof(double));
            memcpy(t->seg + 4 * e + 2, b, 2 * sizeof(double));
            t->loop[e] = (unsigned char)(c <= cv->n_holes);
        }
    for (pass = 0; pass < 2; ++pass) {
        for (e = 0; e < t->ne; ++e)
            if ((st = wr__pz_segs_register(t, e, pass, fill, &nreg, diag)) != WR_OK) goto fail;
        if (pass == 0) {
            for (cell = 0; cell < ncell; ++cell) t->cstart[cell + 1] += t->cstart[cell];
            t->clist = (int32_t *)wr_alloc_array((size_t)nreg, sizeof(int32_t));
            fill = (int32_t *)wr_alloc_array((size_t)ncell, sizeof(int32_t));
            if (!t->clist || !fill) goto nomem;
            memcpy(fill, t->cstart, sizeof(int32_t) * (size_t)ncell);
        }
    }
    wr_free(fill);
    /* status sweep: along y = row centre, from outside (right) to the left, loop edges only */
    for (i = 0; i < t->ny; ++i) {
        double yc = t->y0 + ((double)i + 0.5) * t->g;
        int32_t ix, s = 0;
        for (ix = t->nx - 1; ix >= 0; --ix) {
            int32_t cl = i * t->nx + ix, p;
            t->status[cl] = (unsigned char)s;
            for (p = t->cstart[cl]; p < t->cstart[cl + 1]; ++p) {
                const double *sg = t->seg + 4 * t->clist[p];
                if (t->loop[t->clist[p]] && (sg[1] > yc) != (sg[3] > yc)) {
                    double xi = sg[0] + (yc - sg[1]) * (sg[2] - sg[0]) / (sg[3] - sg[1]);
                    if (wr__pz_cell(t, 0, xi) == ix) s ^= 1;
                }
            }
        }
    }
    if ((t->dist = (unsigned char *)wr_alloc_array((size_t)ncell, 1)) == NULL) goto nomem;
    t->nbx = (t->nx + WR__PZ_DBLOCK - 1) / WR__PZ_DBLOCK;
    t->bdist = (unsigned char *)wr_alloc_array((size_t)t->nbx * (size_t)((t->ny + WR__PZ_DBLOCK - 1) / WR__PZ_DBLOCK), 1);
    if (!t->bdist) goto nomem;
    wr__pz_segs_dist(t);
    return WR_OK;
nomem:
    st = wr_fail(diag, WR_ERR_NOMEM, -1, "segment grid: out of memory");
fail:
    wr_free(fill);
    return st;
}
typedef struct wr__pz_s {
    double x, y, r;
    int32_t next; /* next sample in the same cell, -1 at the end */
    int32_t lvl;
} wr__pz_s;

/* Hash slot: an 8×8 tile of cells of one level (spatially adjacent cells share a slot, so a front
 * step's query of ~4×4 cells touches 1–4 slots, ~1.9 on average, instead of 16 random ones; 4×4
 * tiles needed ~3.2 lookups per query). The slot's key and occupancy are 16 bytes in z->tiles; its
 * 64 cell heads are in z->heads (64 per slot, valid only where the occupancy bit is set), so the
 * probing walks four slots per cache line instead of one slot per five lines (the probe's key
 * load was the front step's first cache miss) and a new tile needs no initialisation of heads. */
#define WR__PZ_TILE 8
typedef struct wr__pz_tile {
    uint64_t key;
    uint64_t occ; /* bit iy·8 + ix: cell (ix, iy) holds a sample (a query visits only those) */
} wr__pz_tile;

/* A neighbour of the current front step: position and radius copied next to each other. */
typedef struct wr__pz_nbr {
    double x, y, r;
    int32_t id; /* sample index */
} wr__pz_nbr;

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
    float *g; /* 2 per sample: the sizing gradient estimate [1] carried along the front (wr__pz_activate) */
    int32_t n, cap;
    /* level hash of tiles */
    wr__pz_tile *tiles;
    int32_t *heads; /* 64 per slot: the first sample of each cell (list through wr__pz_s.next) */
    int32_t *tcnt;  /* per slot: the samples in the tile, a bound on a query's visits there */
    size_t hcap, hcount;
    int hbits;
    double x0, y0, W, H, s_base, xmag; /* xmag: the largest |coordinate| of the box */
    double cs[64], inv_cs[64], rmax[64], rmax_all;
    int64_t lim_x[64], lim_y[64]; /* the last cell column / row of each level (wr__pz_cell_box) */
    uint64_t tw[64], th[64]; /* tiles per row and rows at each level (home slot of a tile) */
    uint64_t rowstep[64];    /* tw, or 0 where the level's rows start at hashed slots */
    /* presence grid */
    uint64_t *mask, levels; /* levels: every level in use */
    int32_t mx, my;
    double mg, inv_mg;
    /* walking table */
    double *tx, *ty, *tI;
    int32_t tn, tcap;
    /* front sampler: options, the domain's segments, the current point's neighbours */
    const wr__pz_segs *segs;
    wr_rng rng;
    double clearance; /* minimum sample-to-segment distance / h */
    double fixed_d;   /* D: sample-to-loop-point distance / h (ON THE FIRST RING) */
    int32_t k;        /* placement attempts per point */
    wr__pz_nbr *nb; /* neighbours of the point being processed (copies: scanned for every candidate) */
    int32_t nb_n, nb_cap;
    int64_t n_candidates;
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

/* floor() as an integer without the libm call (x86-64 has no SSE4.1 round by default); |v| < 2^62 */
static int64_t wr__pz_ifloor(double v) {
    int64_t i = (int64_t)v;
    return i - (v < (double)i);
}

/* ---- level hash ------------------------------------------------------------------------------ */
#define WR__PZ_CMAX ((1 << 29) - 2)

static uint64_t wr__pz_key(int l, int64_t tx, int64_t ty) {
    return (((uint64_t)l << 58) | ((uint64_t)tx << 29) | (uint64_t)ty) + 1u; /* 0 = empty slot */
}

/* Home slot = the tile's row-major index in its level's tile grid (plus a per-level offset), so
 * tiles that are neighbours along x are neighbours in memory and a single level covering the domain
 * fills the table without collisions; linear probing resolves the rest. (A multiplicative hash made
 * every tile lookup a cache miss: 17 % of a step's time.) A level whose tile grid is larger than the
 * table (the fine levels of a graded sizing, which fill only a band of the box) would wrap its rows
 * onto each other and into long probe runs: its rows start at hashed slots instead (20×-graded
 * square: 65 → 43 instructions per lookup). */
static inline size_t wr__pz_slot_of(const wr__pz *z, uint64_t l, uint64_t tx, uint64_t ty, uint64_t key) {
    /* z->rowstep[l]: tw[l] when the level's tile grid fits the table, 0 for hashed rows (set with
     * the table: wr__pz_hash_alloc) */
    uint64_t row = z->rowstep[l] ? ty * z->rowstep[l] : (ty + 1u) * 0x9E3779B97F4A7C15u >> 20;
    size_t m = z->hcap - 1, s = (size_t)(tx + row + l * 0x9E3779B1u) & m;
    while (z->tiles[s].key != 0 && z->tiles[s].key != key) s = (s + 1) & m;
    return s;
}

static size_t wr__pz_slot(const wr__pz *z, uint64_t key) {
    uint64_t k = key - 1u;
    return wr__pz_slot_of(z, k >> 58, (k >> 29) & (uint64_t)0x1FFFFFFF, k & (uint64_t)0x1FFFFFFF, key);
}

static wr_status wr__pz_hash_alloc(wr__pz *z) {
    size_t i;
    z->hcap = (size_t)1 << z->hbits;
    for (i = 0; i < 64; ++i) z->rowstep[i] = z->tw[i] * z->th[i] <= z->hcap ? z->tw[i] : 0u;
    z->tiles = (wr__pz_tile *)wr_alloc_array(z->hcap, sizeof(wr__pz_tile));
    z->heads = (int32_t *)wr_alloc_array(z->hcap, WR__PZ_TILE * WR__PZ_TILE * sizeof(int32_t));
    z->tcnt = (int32_t *)wr_alloc_array(z->hcap, sizeof(int32_t));
    if (!z->tiles || !z->heads || !z->tcnt) return wr_fail(z->diag, WR_ERR_NOMEM, -1, "sampling grid: out of memory");
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
    int32_t *oldh = z->heads, *oldc = z->tcnt;
    size_t oc = z->hcap, i, s;
    wr_status st;
    z->hbits += 1;
    if ((st = wr__pz_hash_alloc(z)) != WR_OK) {
        wr_free(old);
        wr_free(oldh);
        wr_free(oldc);
        return st;
    }
    for (i = 0; i < oc; ++i)
        if (old[i].key) {
            s = wr__pz_slot(z, old[i].key);
            z->tiles[s] = old[i];
            z->tcnt[s] = oldc[i];
            memcpy(z->heads + s * WR__PZ_TILE * WR__PZ_TILE, oldh + i * WR__PZ_TILE * WR__PZ_TILE,
                   WR__PZ_TILE * WR__PZ_TILE * sizeof(int32_t));
        }
    wr_free(old);
    wr_free(oldh);
    wr_free(oldc);
    return WR_OK;
}

static int wr__pz_level(const wr__pz *z, double r) {
    /* the binary exponent of r/s (r/s in [2^e, 2^(e+1))) from its bits: frexp's, without the call
     * (zero, subnormal, infinite and NaN ratios give e < 0 or e > 62, refused by the caller) */
    double v = r / z->s_base;
    uint64_t bits;
    memcpy(&bits, &v, sizeof bits);
    return (int)((bits >> 52) & 0x7FFu) - 1023;
}

/* Mean rule: does (qx,qy) with radius rq conflict with any stored sample? */

/* Grow the neighbour list (out of the hot path of wr__pz_nb_push). */
static wr_status wr__pz_nb_grow(wr__pz *z) {
    int32_t nc = z->nb_cap ? 2 * z->nb_cap : 64;
    wr__pz_nbr *a = (wr__pz_nbr *)wr_realloc_array(z->nb, (size_t)nc, sizeof(wr__pz_nbr));
    if (!a) return wr_fail(z->diag, WR_ERR_NOMEM, -1, "neighbour list: out of memory");
    z->nb = a;
    z->nb_cap = nc;
    return WR_OK;
}

/* Room for `need` entries in the neighbour list (its first z->nb_n kept). */
static wr_status wr__pz_nb_reserve(wr__pz *z, int64_t need) {
    while (z->nb_cap < need)
        if (wr__pz_nb_grow(z) != WR_OK) return WR_ERR_NOMEM;
    return WR_OK;
}

/* Append sample i to the neighbour list. */
static inline wr_status wr__pz_nb_push(wr__pz *z, int32_t i) {
    wr__pz_nbr *e;
    if (z->nb_n == z->nb_cap && wr__pz_nb_grow(z) != WR_OK) return WR_ERR_NOMEM;
    e = &z->nb[z->nb_n++];
    e->x = z->sm[i].x;
    e->y = z->sm[i].y;
    e->r = z->sm[i].r;
    e->id = i;
    return WR_OK;
}

/* Angles for the free-arc bookkeeping by polynomial: Abramowitz & Stegun 4.4.49 (arctan on [0, 1],
 * |error| <= 2e-8 rad) and 4.4.46 (arccos, <= 2e-8 rad); sin and cos by their Taylor series to
 * degree 11 and 12 on [-π/4, π/4] (< 1e-11). libm's atan2, acos and sincos took 20 % of a front
 * step; the arcs only steer where candidates are drawn and every candidate is checked exactly, so
 * 1e-7 rad is ample. */
#define WR__PZ_HALF_PI 1.5707963267948966
static inline double wr__pz_atan2(double y, double x) {
    double ax = fabs(x), ay = fabs(y), a, s, r;
    if (ax == 0.0 && ay == 0.0) return 0.0;
    a = ax >= ay ? ay / ax : ax / ay;
    s = a * a;
    r = a * (1.0 + s * (-0.3333314528 + s * (0.1999355085 + s * (-0.1420889944 + s * (0.1065626393 +
        s * (-0.0752896400 + s * (0.0429096138 + s * (-0.0161657367 + s * 0.0028662257))))))));
    if (ay > ax) r = WR__PZ_HALF_PI - r;
    if (x < 0.0) r = 2.0 * WR__PZ_HALF_PI - r;
    return y < 0.0 ? -r : r;
}

static double wr__pz_acos(double x) { /* |x| <= 1 */
    double ax = fabs(x);
    double r = sqrt(1.0 - ax) * (1.5707963050 + ax * (-0.2145988016 + ax * (0.0889789874 + ax * (-0.0501743046 +
               ax * (0.0308918810 + ax * (-0.0170881256 + ax * (0.0066700901 + ax * -0.0012624911)))))));
    return x < 0.0 ? 2.0 * WR__PZ_HALF_PI - r : r;
}

static void wr__pz_sincos(double t, double *sn, double *cs) {
    int64_t q = wr__pz_ifloor(t / WR__PZ_HALF_PI + 0.5);
    double u = t - (double)q * WR__PZ_HALF_PI, u2 = u * u, sv, cv;
    sv = u * (1.0 + u2 * (-1.0 / 6 + u2 * (1.0 / 120 + u2 * (-1.0 / 5040 + u2 * (1.0 / 362880 + u2 * (-1.0 / 39916800))))));
    cv = 1.0 + u2 * (-0.5 + u2 * (1.0 / 24 + u2 * (-1.0 / 720 + u2 * (1.0 / 40320 + u2 * (-1.0 / 3628800 +
         u2 * (1.0 / 479001600))))));
    switch ((int)(q & 3)) {
    case 0: *sn = sv; *cs = cv; break;
    case 1: *sn = cv; *cs = -sv; break;
    case 2: *sn = -sv; *cs = -cv; break;
    default: *sn = -cv; *cs = sv; break;
    }
}

/* ---- free arcs: the directions around a point still open for a new sample -------------------- */
#define WR__PZ_ARCS 32
#define WR__PZ_TWO_PI 6.283185307179586
typedef struct wr__pz_arcs {
    double lo[WR__PZ_ARCS], hi[WR__PZ_ARCS]; /* disjoint, ascending, within [0, 2π] */
    int32_t n;
} wr__pz_arcs;

/* Remove [a, b] (0 <= a < b <= 2π), in place. A split beyond the capacity keeps the longer side. */
static inline void wr__pz_arcs_cut1(wr__pz_arcs *A, double a, double b) {
    int32_t i;
    for (i = 0; i < A->n; ++i) {
        double l = A->lo[i], h = A->hi[i];
        if (b <= l) return; /* ascending: nothing further overlaps */
        if (a >= h) continue;
        if (a > l && b < h) { /* strictly inside: split */
            if (A->n < WR__PZ_ARCS) {
                int32_t j;
                for (j = A->n; j > i; --j) { /* a few arcs: a loop beats two memmove calls */
                    A->lo[j] = A->lo[j - 1];
                    A->hi[j] = A->hi[j - 1];
                }
                A->hi[i] = a;
                A->lo[i + 1] = b;
                ++A->n;
            } else if (a - l >= h - b) {
                A->hi[i] = a;
            } else {
                A->lo[i] = b;
            }
            return;
        }
        if (a > l) {
            A->hi[i] = a; /* the top goes */
        } else if (b < h) {
            A->lo[i] = b; /* the bottom goes */
            return;
        } else { /* covered */
            int32_t j;
            for (j = i; j + 1 < A->n; ++j) {
                A->lo[j] = A->lo[j + 1];
                A->hi[j] = A->hi[j + 1];
            }
            --A->n;
            --i;
        }
    }
}

/* Remove the directions within `half` of angle `c` (any real c). */
static void wr__pz_arcs_cut(wr__pz_arcs *A, double c, double half) {
    double a, b;
    if (half >= 0.5 * WR__PZ_TWO_PI) {
        A->n = 0;
        return;
    }
    if (!(half > 0.0)) return;
    c -= WR__PZ_TWO_PI * (double)wr__pz_ifloor(c / WR__PZ_TWO_PI);
    a = c - half;
    b = c + half;
    if (a < 0.0) {
        wr__pz_arcs_cut1(A, a + WR__PZ_TWO_PI, WR__PZ_TWO_PI);
        wr__pz_arcs_cut1(A, 0.0, b);
    } else if (b > WR__PZ_TWO_PI) {
        wr__pz_arcs_cut1(A, a, WR__PZ_TWO_PI);
        wr__pz_arcs_cut1(A, 0.0, b - WR__PZ_TWO_PI);
    } else {
        wr__pz_arcs_cut1(A, a, b);
    }
}

/* wr__pz_arcs_cut(A, th, WR__PZ_TINY_ARC) for a drawn direction th in [0, 2π): the same cut, but
 * without the wrap arithmetic, and nothing at all when no free arc is within the tiny arc (the
 * usual case: th was just removed with a neighbour's or a new sample's lens). */
static void wr__pz_arcs_cut_tiny(wr__pz_arcs *A, double th) {
    double a = th - WR__PZ_TINY_ARC, b = th + WR__PZ_TINY_ARC;
    int32_t i;
    if (a < 0.0 || b > WR__PZ_TWO_PI) {
        wr__pz_arcs_cut(A, th, WR__PZ_TINY_ARC);
        return;
    }
    for (i = 0; i < A->n; ++i) {
        if (b <= A->lo[i]) return;
        if (a < A->hi[i]) {
            wr__pz_arcs_cut1(A, a, b);
            return;
        }
    }
}

/* A direction uniform over the free arcs (u uniform in [0, 1)); *inner = it lies at least
 * WR__PZ_INNER from both ends of its arc. */
static double wr__pz_arcs_pick(const wr__pz_arcs *A, double u, int *inner) {
    double total = 0.0, t;
    int32_t i;
    for (i = 0; i < A->n; ++i) total += A->hi[i] - A->lo[i];
    t = u * total;
    for (i = 0; i + 1 < A->n && t >= A->hi[i] - A->lo[i]; ++i) t -= A->hi[i] - A->lo[i];
    t += A->lo[i];
    t = t < A->hi[i] ? t : A->lo[i];
    *inner = t - A->lo[i] >= WR__PZ_INNER && A->hi[i] - t >= WR__PZ_INNER;
    return t;
}

/* Cut the directions θ for which p + ρ(cos θ, sin θ) lies closer than D to q = p + d (cos φ, sin φ)
 * (the lens of two circles: law of cosines); *tiny |= q within rounding of touching the circle
 * (WR__PZ_TANGENT). q is a sample just placed from p, so its direction φ and distance d are known:
 * no atan2 and no square root. */
static void wr__pz_arcs_cut_disk(wr__pz_arcs *A, double rho, double phi, double d, double D, int *tiny) {
    double cs;
    if (d >= rho + D) {
        *tiny |= d < (rho + D) * (1.0 + WR__PZ_TANGENT);
        return;
    }
    if (d <= D - rho || d == 0.0) {
        A->n = 0;
        return;
    }
    cs = (rho * rho + d * d - D * D) / (2.0 * rho * d);
    if (cs <= -1.0) {
        A->n = 0;
        return;
    }
    *tiny |= cs >= 1.0 - WR__PZ_TANGENT;
    if (cs < 1.0) wr__pz_arcs_cut(A, phi, wr__pz_acos(cs));
}

/* The curves near p: cut the directions in which the circle of radius ρ around p comes within the
 * clearance of a segment (around each crossing) and the arcs between crossings that lie outside
 * the domain (one inside test at each arc's middle). Returns 0 when no segment is within `reach`
 * (then every candidate up to that distance is inside and clear, p being inside). */
static int wr__pz_arcs_cut_curves(const wr__pz *z, wr__pz_arcs *A, double px, double py, double rho, double clr,
                                  double reach) {
    const wr__pz_segs *t = z->segs;
    double cross[2 * WR__PZ_ARCS];
    int32_t ix0, ix1, iy0, iy1, ix, iy, p, nc = 0, i, j;
    int32_t cx = wr__pz_cell(t, 0, px), cy = wr__pz_cell(t, 1, py);
    int any = 0;
    /* the box of cells within reach is within k = floor(reach / g) + 1 cells (chessboard) of p's
     * cell: when p's cell is farther than that from every segment cell, nothing to scan */
    if (cx >= 0 && cx < t->nx && cy >= 0 && cy < t->ny && reach * t->inv_g < 254.0) {
        int32_t k = (int32_t)(reach * t->inv_g) + 1; /* the block's least distance first: in cache */
        if (t->bdist[(cy / WR__PZ_DBLOCK) * t->nbx + cx / WR__PZ_DBLOCK] > k || t->dist[cy * t->nx + cx] > k) return 0;
    }
    ix0 = wr__pz_cell(t, 0, px - reach);
    ix1 = wr__pz_cell(t, 0, px + reach);
    iy0 = wr__pz_cell(t, 1, py - reach);
    iy1 = wr__pz_cell(t, 1, py + reach);
    ix0 = ix0 < 0 ? 0 : ix0;
    iy0 = iy0 < 0 ? 0 : iy0;
    ix1 = ix1 >= t->nx ? t->nx - 1 : ix1;
    iy1 = iy1 >= t->ny ? t->ny - 1 : iy1;
    for (iy = iy0; iy <= iy1; ++iy)
        for (ix = ix0; ix <= ix1; ++ix) {
            int32_t cell = iy * t->nx + ix;
            for (p = t->cstart[cell]; p < t->cstart[cell + 1]; ++p) {
                /* |a + s e − p|² = ρ²: s² |e|² + 2 s e·(a−p) + |a−p|² − ρ² = 0 */
                const double *sg = t->seg + 4 * t->clist[p];
                double ex = sg[2] - sg[0], ey = sg[3] - sg[1], fx = sg[0] - px, fy = sg[1] - py;
                double A2 = ex * ex + ey * ey, B = ex * fx + ey * fy, C = fx * fx + fy * fy - rho * rho, disc, sq;
                double len, nx, ny, dl, phin, ahi, alo;
                int r;
                if (wr__pz_seg_d2(sg, px, py) >= reach * reach) continue;
                any = 1;
                disc = B * B - A2 * C;
                if (!(disc >= 0.0) || !(A2 > 0.0)) continue;
                sq = sqrt(disc);
                len = sqrt(A2);
                /* the clearance band |δ + ρ cos(φ − φn)| < clr of the segment's line (n its unit
                 * normal, δ = n·(p − a)) meets the circle in two arcs symmetric about φn, at
                 * angular distance in (acos(hi), acos(lo)) from it */
                nx = -ey / len;
                ny = ex / len;
                dl = -(nx * fx + ny * fy);
                phin = wr__pz_atan2(ny, nx);
                ahi = wr__pz_acos(fmax(-1.0, fmin(1.0, (clr - dl) / rho)));
                alo = wr__pz_acos(fmax(-1.0, fmin(1.0, (-clr - dl) / rho)));
                for (r = 0; r < 2; ++r) {
                    double s = (-B + (r ? sq : -sq)) / A2, th, psi;
                    if (s < 0.0 || s > 1.0) continue;
                    th = wr__pz_atan2(fy + s * ey, fx + s * ex);
                    psi = th - phin;
                    psi -= WR__PZ_TWO_PI * (double)wr__pz_ifloor(psi / WR__PZ_TWO_PI + 0.5); /* (−π, π] */
                    wr__pz_arcs_cut(A, phin + (psi >= 0.0 ? 0.5 : -0.5) * (ahi + alo), 0.5 * (alo - ahi));
                    if (t->loop[t->clist[p]] && nc < 2 * WR__PZ_ARCS) cross[nc++] = th < 0.0 ? th + WR__PZ_TWO_PI : th;
                }
            }
        }
    if (!any) return 0;
    /* sort the loop crossings (few), then test each arc between consecutive ones */
    for (i = 1; i < nc; ++i)
        for (j = i; j > 0 && cross[j - 1] > cross[j]; --j) {
            double tmp = cross[j];
            cross[j] = cross[j - 1];
            cross[j - 1] = tmp;
        }
    if (nc == 0) {
        if (!wr__pz_inside_at(t, px + rho, py)) A->n = 0;
        return 1;
    }
    for (i = 0; i < nc; ++i) {
        double a = cross[i], b = i + 1 < nc ? cross[i + 1] : cross[0] + WR__PZ_TWO_PI, m = 0.5 * (a + b), sm, cm;
        wr__pz_sincos(m, &sm, &cm);
        if (b - a > 1e-12 && !wr__pz_inside_at(t, px + rho * cm, py + rho * sm))
            wr__pz_arcs_cut(A, m, 0.5 * (b - a));
    }
    return 1;
}

/* Does (qx, qy) with radius rq conflict with a neighbour of the current step (mean rule)? */
static int wr__pz_nb_conflict(const wr__pz *z, double qx, double qy, double rq) {
    int32_t i;
    for (i = 0; i < z->nb_n; ++i) {
        const wr__pz_nbr *S = &z->nb[i];
        double dx = S->x - qx, dy = S->y - qy, md = 0.5 * (rq + S->r);
        if (dx * dx + dy * dy < md * md) return 1;
    }
    return 0;
}

/* Pseudo-angle of the direction (x, y) ≠ 0: monotone in the polar angle on [0, 2π) ↦ [0, 4), one
 * division (the "diamond angle": the position along the unit L1 circle). Ordering and merging arcs
 * needs only this; true angles are needed only at the ends of the merged arcs. */
static inline double wr__pz_pseudo(double x, double y) {
    /* r = |y| / (|x| + |y|) folded by quadrant: r, 2 − r, 2 + r, 4 − r. The quadrant indexes a
     * table, not branches: lens ends point in random directions, and the four-way
     * branch mispredicted about every other call (11 % of a front step's time) */
    static const double off[4] = {0.0, 2.0, 4.0, 2.0}, sg[4] = {1.0, -1.0, -1.0, 1.0};
    double ax = fabs(x), ay = fabs(y), r = ay / (ax + ay);
    uint64_t bx, by;
    size_t q;
    memcpy(&bx, &x, sizeof bx);
    memcpy(&by, &y, sizeof by);
    /* quadrant from the sign bits: 0 (+,+), 1 (−,+), 2 (+,−), 3 (−,−); a signed zero only moves
     * direction 0 to 4 (the same direction: a lens end there cuts the same arcs) */
    q = (size_t)(bx >> 63) | (size_t)(by >> 63) << 1;
    return off[q] + sg[q] * r;
}

/* The polar angle in [0, 2π] of pseudo-angle t in [0, 4] (the ends map exactly to 0 and 2π). */
static inline double wr__pz_pseudo_angle(double t) {
    double th;
    if (t <= 0.0) return 0.0;
    if (t >= 4.0) return WR__PZ_TWO_PI;
    th = t < 1.0 ? wr__pz_atan2(t, 1.0 - t)
       : t < 2.0 ? wr__pz_atan2(2.0 - t, 1.0 - t)
       : t < 3.0 ? wr__pz_atan2(2.0 - t, t - 3.0)
                 : wr__pz_atan2(t - 4.0, t - 3.0);
    return th < 0.0 ? th + WR__PZ_TWO_PI : th;
}

/* The lens cutting of a front step (wr__pz_neighbours): the directions θ in which
 * p + ρ(cos θ, sin θ) would conflict with a neighbour (radius rc assumed for the new sample: the
 * lens of wr__pz_arcs_cut_disk) are cut, all at once and before the first draw, from F, the free
 * directions in pseudo-angle (wr__pz_pseudo, monotone in the angle). The lens ends are rotations
 * of the direction to the neighbour by ±acos(cs), so with cos and sin of the half-width from the
 * law of cosines no trigonometric call is needed per neighbour; the gathering stops once F is
 * empty, and only the ends of what is left are converted to angles (wr__pz_arcs_take_free).
 * Uniform draws over the result have the law of drawing over all free directions and redrawing on
 * a conflict (ON THE ALGORITHM). */
typedef struct wr__pz_cut {
    wr__pz_arcs F;  /* the directions free of every neighbour so far, pseudo-angle in [0, 4] */
    double rho, rc; /* the circle's radius, the new sample's assumed radius */
    double inv_2rho;
    int32_t ip;     /* p itself: no lens */
    int tiny;       /* a neighbour is within rounding of touching the circle (WR__PZ_TANGENT) */
} wr__pz_cut;

/* Remove [a, b] (a < b) from arcs kept in no particular order (C->F while the lenses are cut: no
 * shifting on a split, the new piece goes to the end; wr__pz_arcs_sort before use). A split beyond
 * the capacity keeps the longer side, as wr__pz_arcs_cut1 does. */
static inline void wr__pz_arcs_cut_any(wr__pz_arcs *A, double a, double b) {
    int32_t i = 0;
    while (i < A->n) {
        double l = A->lo[i], h = A->hi[i];
        if (b <= l || a >= h) {
            ++i;
        } else if (a > l) {
            if (b < h) { /* strictly inside one arc: no other arc meets [a, b] */
                if (A->n < WR__PZ_ARCS) {
                    A->hi[i] = a;
                    A->lo[A->n] = b;
                    A->hi[A->n++] = h;
                } else if (a - l >= h - b) {
                    A->hi[i] = a;
                } else {
                    A->lo[i] = b;
                }
                return;
            }
            A->hi[i++] = a; /* the top goes */
        } else if (b < h) {
            A->lo[i++] = b; /* the bottom goes */
        } else { /* covered: the last arc takes its place */
            --A->n;
            A->lo[i] = A->lo[A->n];
            A->hi[i] = A->hi[A->n];
        }
    }
}

/* Sort disjoint arcs into ascending order (insertion sort: a few arcs). */
static void wr__pz_arcs_sort(wr__pz_arcs *A) {
    int32_t i, j;
    for (i = 1; i < A->n; ++i) {
        double l = A->lo[i], h = A->hi[i];
        for (j = i; j > 0 && A->lo[j - 1] > l; --j) {
            A->lo[j] = A->lo[j - 1];
            A->hi[j] = A->hi[j - 1];
        }
        A->lo[j] = l;
        A->hi[j] = h;
    }
}

/* Cut the lens of neighbour S at offset (dx, dy) from p (d2 = dx² + dy²), radius rs; 1 when
 * nothing is left. The lens ends are the direction to S rotated by ±acos(cs), cs = e / d with
 * e = (ρ² + d² − D²) / (2ρ) (law of cosines); scaled by d² they are (dx e ∓ dy f, dy e ± dx f) with
 * f = d sin = sqrt(d² − e²), and the pseudo-angle ignores the scale, so neither d nor cs is formed:
 * one square root and no division per neighbour. cs <= −1 (the circle inside S's disk, also
 * d <= D − ρ) is e <= −d, cs >= 1 − WR__PZ_TANGENT is e >= d (1 − WR__PZ_TANGENT). */
static inline int wr__pz_lens(wr__pz_cut *C, double dx, double dy, double d2, double rs) {
    double rho = C->rho, D = 0.5 * (C->rc + rs), e, e2, f, a, b;
    if (d2 >= (rho + D) * (rho + D)) {
        if (d2 < (rho + D) * (rho + D) * (1.0 + WR__PZ_TANGENT)) C->tiny = 1;
        return 0;
    }
    e = (rho * rho + d2 - D * D) * C->inv_2rho;
    e2 = e * e;
    if (e2 >= d2 * ((1.0 - WR__PZ_TANGENT) * (1.0 - WR__PZ_TANGENT)) || d2 == 0.0) { /* rare: one test */
        if (d2 == 0.0 || (e <= 0.0 && e2 >= d2)) {
            C->F.n = 0;
            return 1;
        }
        if (e > 0.0) {
            C->tiny = 1;
            if (e2 >= d2) return 0;
        }
    }
    f = sqrt(d2 - e2); /* e² < d² here */
    a = wr__pz_pseudo(dx * e + dy * f, dy * e - dx * f); /* direction rotated by −acos(cs) */
    b = wr__pz_pseudo(dx * e - dy * f, dy * e + dx * f); /* and by +acos(cs) */
    if (a < b) {
        wr__pz_arcs_cut_any(&C->F, a, b);
    } else if (a > b) { /* through direction 0 */
        wr__pz_arcs_cut_any(&C->F, a, 4.0);
        wr__pz_arcs_cut_any(&C->F, 0.0, b);
    }
    return C->F.n == 0;
}

/* A ∩= F (F in pseudo-angle, converted at its ends only; F is sorted here). */
static void wr__pz_arcs_take_free(wr__pz_arcs *A, wr__pz_arcs *F) {
    int32_t i;
    if (F->n == 0) {
        A->n = 0;
        return;
    }
    wr__pz_arcs_sort(F);
    if (A->n == 1 && A->lo[0] == 0.0 && A->hi[0] == WR__PZ_TWO_PI) { /* no curve near: A = F */
        int32_t k = 0;
        for (i = 0; i < F->n; ++i) {
            double ta = wr__pz_pseudo_angle(F->lo[i]), tb = wr__pz_pseudo_angle(F->hi[i]);
            if (tb > ta) {
                A->lo[k] = ta;
                A->hi[k++] = tb;
            }
        }
        A->n = k;
        return;
    }
    for (i = 0; i <= F->n && A->n > 0; ++i) { /* otherwise cut the gaps of F from A */
        double ga = i == 0 ? 0.0 : F->hi[i - 1], gb = i == F->n ? 4.0 : F->lo[i], ta, tb;
        if (!(gb > ga)) continue;
        ta = wr__pz_pseudo_angle(ga);
        tb = wr__pz_pseudo_angle(gb);
        if (tb > ta) wr__pz_arcs_cut1(A, ta, tb);
    }
}

/* The levels present in the presence-grid cells within R of q. */
static uint64_t wr__pz_levels_near(const wr__pz *z, double qx, double qy, double R) {
    int64_t ax0, ax1, ay0, ay1, ix, iy;
    uint64_t mask = 0;
    if ((z->levels & (z->levels - 1u)) == 0u) return z->levels; /* one level in use (constant sizing) */
    ax0 = wr__pz_ifloor((qx - R - z->x0) * z->inv_mg);
    ax1 = wr__pz_ifloor((qx + R - z->x0) * z->inv_mg);
    ay0 = wr__pz_ifloor((qy - R - z->y0) * z->inv_mg);
    ay1 = wr__pz_ifloor((qy + R - z->y0) * z->inv_mg);
    ax0 = ax0 < 0 ? 0 : ax0;
    ay0 = ay0 < 0 ? 0 : ay0;
    ax1 = ax1 >= z->mx ? z->mx - 1 : ax1;
    ay1 = ay1 >= z->my ? z->my - 1 : ay1;
    for (iy = ay0; iy <= ay1; ++iy)
        for (ix = ax0; ix <= ax1; ++ix) mask |= z->mask[iy * z->mx + ix];
    return mask;
}

/* Lowest level in mask (mask != 0). */
static inline int wr__pz_ctz(uint64_t mask) {
#if defined(__GNUC__) || defined(__clang__)
    return __builtin_ctzll(mask);
#else
    int l = 0;
    while (!((mask >> l) & 1u)) ++l;
    return l;
#endif
}

/* Level l's cells within Rl of q: b = {cx0, cx1, cy0, cy1}, clamped to the level's grid. */
static inline void wr__pz_cell_box(const wr__pz *z, int l, double qx, double qy, double Rl, int64_t b[4]) {
    double ic = z->inv_cs[l];
    const int64_t lim_x = z->lim_x[l], lim_y = z->lim_y[l];
    b[0] = wr__pz_ifloor((qx - Rl - z->x0) * ic);
    b[1] = wr__pz_ifloor((qx + Rl - z->x0) * ic);
    b[2] = wr__pz_ifloor((qy - Rl - z->y0) * ic);
    b[3] = wr__pz_ifloor((qy + Rl - z->y0) * ic);
    b[0] = b[0] < 0 ? 0 : b[0];
    b[2] = b[2] < 0 ? 0 : b[2];
    b[1] = b[1] > lim_x ? lim_x : b[1];
    b[3] = b[3] > lim_y ? lim_y : b[3];
}

/* Tile (tx, ty) of level l's cell box b: the occupied cells of the tile inside b, as a mask of
 * bits iy·8 + ix (ascending bits = row by row), and the tile's cell heads in *H. */
#if WR__PZ_TILE != 8
#error "wr__pz_box_tile's cell masks assume 8x8 tiles"
#endif
static inline uint64_t wr__pz_box_tile(const wr__pz *z, int l, int64_t tx, int64_t ty, const int64_t b[4],
                                       const int32_t **H) {
    size_t s = wr__pz_slot_of(z, (uint64_t)l, (uint64_t)tx, (uint64_t)ty, wr__pz_key(l, tx, ty));
    const wr__pz_tile *t = &z->tiles[s];
    int64_t ox = tx * WR__PZ_TILE, oy = ty * WR__PZ_TILE;
    uint32_t jx0, jx1, jy0, jy1;
    uint64_t cols, rows;
    *H = z->heads + s * WR__PZ_TILE * WR__PZ_TILE;
    if (t->key == 0) return 0;
    jx0 = (uint32_t)(b[0] > ox ? b[0] - ox : 0);
    jx1 = (uint32_t)(b[1] < ox + WR__PZ_TILE - 1 ? b[1] - ox : WR__PZ_TILE - 1);
    jy0 = (uint32_t)(b[2] > oy ? b[2] - oy : 0);
    jy1 = (uint32_t)(b[3] < oy + WR__PZ_TILE - 1 ? b[3] - oy : WR__PZ_TILE - 1);
    cols = (uint64_t)((2u << jx1) - (1u << jx0)) * 0x0101010101010101u; /* columns jx0..jx1, every row */
    rows = (~(uint64_t)0 >> (56u - 8u * jy1)) & (~(uint64_t)0 << (8u * jy0)); /* rows jy0..jy1 */
    return t->occ & cols & rows;
}

/* Does a stored sample S lie within R0 + (rq + r_S)/2 of q (level by level, only the levels
 * present around q)? With R0 = 0 this is the mean-rule conflict test. */
static int wr__pz_near(const wr__pz *z, double qx, double qy, double R0, double rq) {
    uint64_t mask = wr__pz_levels_near(z, qx, qy, R0 + 0.5 * (rq + z->rmax_all));
    const wr__pz_s *sm = z->sm;
    while (mask) {
        int l = wr__pz_ctz(mask);
        int64_t b[4], tx, ty;
        mask &= mask - 1u;
        wr__pz_cell_box(z, l, qx, qy, R0 + 0.5 * (rq + z->rmax[l]), b);
        for (ty = b[2] / WR__PZ_TILE; ty <= b[3] / WR__PZ_TILE; ++ty)
            for (tx = b[0] / WR__PZ_TILE; tx <= b[1] / WR__PZ_TILE; ++tx) {
                const int32_t *T;
                uint64_t cells = wr__pz_box_tile(z, l, tx, ty, b, &T);
                int32_t p;
                for (; cells; cells &= cells - 1u)
                        for (p = T[wr__pz_ctz(cells)]; p >= 0; p = sm[p].next) {
                            double dx = sm[p].x - qx, dy = sm[p].y - qy, md = R0 + 0.5 * (rq + sm[p].r);
                            if (dx * dx + dy * dy < md * md) return 1;
                        }
            }
    }
    return 0;
}

/* The second pass of wr__pz_neighbours: each neighbour's lens but p's own (index ip) cut from C->F,
 * stopping once nothing is left. Kept out of line (GCC and Clang): inlined into the fill, GCC
 * judged the lens's square root cold and called libm's sqrt for it (its errno path) instead of
 * using the instruction. */
#if defined(__GNUC__)
#define WR__PZ_NOINLINE __attribute__((noinline))
#else
#define WR__PZ_NOINLINE
#endif
static WR__PZ_NOINLINE void wr__pz_cut_lenses(const wr__pz_nbr *nb, int32_t nn, double px, double py, int32_t ip,
                                              wr__pz_cut *C) {
    int32_t i;
    for (i = 0; i < nn; ++i) {
        double dx = nb[i].x - px, dy = nb[i].y - py;
        if (nb[i].id != ip && wr__pz_lens(C, dx, dy, dx * dx + dy * dy, nb[i].r)) return;
    }
}

/* The front step's neighbours: the stored samples S within R0 + (rq + r_S)/2 of p = (px, py) go to
 * z->nb (level by level, only the levels present around p), then each one's lens (but p's own,
 * index C->ip) is cut from C->F, stopping as soon as nothing is left of C->F. Two passes, not one:
 * the gathering appends every visited sample and advances the count by the comparison, without a
 * branch (half the visited samples are kept, in no predictable pattern: the branch mispredicted
 * about every other visit, and each miss discarded the loads of the next cells already under
 * way); the list is then complete even when no direction is left. The hot loop keeps the arrays
 * in locals: stores to the neighbour list would otherwise reload them (they may alias). Returns
 * -1 when out of memory (diag filled). */
static int wr__pz_neighbours(wr__pz *z, double px, double py, double R0, double rq, wr__pz_cut *C) {
    uint64_t mask = wr__pz_levels_near(z, px, py, R0 + 0.5 * (rq + z->rmax_all));
    const wr__pz_s *sm = z->sm;
    const double base = R0 + 0.5 * rq;
    const int32_t ip = C->ip;
    wr__pz_nbr *nb = z->nb;
    int32_t nn = 0, cap = z->nb_cap;
    while (mask) {
        int l = wr__pz_ctz(mask);
        int64_t b[4], tx, ty;
        mask &= mask - 1u;
        wr__pz_cell_box(z, l, px, py, base + 0.5 * z->rmax[l], b);
        for (ty = b[2] / WR__PZ_TILE; ty <= b[3] / WR__PZ_TILE; ++ty)
            for (tx = b[0] / WR__PZ_TILE; tx <= b[1] / WR__PZ_TILE; ++tx) {
                const int32_t *T;
                uint64_t cells = wr__pz_box_tile(z, l, tx, ty, b, &T);
                int32_t p;
                /* room for every visit in this tile (the append below is unconditional): at most the
                 * tile's sample count, tcnt of its slot (T is that slot's heads) */
                if (cells) {
                    const int64_t need = nn + (int64_t)z->tcnt[(size_t)(T - z->heads) / (WR__PZ_TILE * WR__PZ_TILE)];
                    if (need > cap) {
                        z->nb_n = nn;
                        if (wr__pz_nb_reserve(z, need) != WR_OK) return -1;
                        nb = z->nb;
                        cap = z->nb_cap;
                    }
                }
                for (; cells; cells &= cells - 1u)
                    for (p = T[wr__pz_ctz(cells)]; p >= 0; p = sm[p].next) {
                        const double sx = sm[p].x, sy = sm[p].y, sr = sm[p].r;
                        double dx = sx - px, dy = sy - py, md = base + 0.5 * sr;
                        nb[nn].x = sx;
                        nb[nn].y = sy;
                        nb[nn].r = sr;
                        nb[nn].id = p;
                        nn += dx * dx + dy * dy < md * md;
                    }
            }
    }
    z->nb_n = nn;
    wr__pz_cut_lenses(nb, nn, px, py, ip, C);
    return 0;
}

/* Level l present in the presence-grid cell of (x, y). */
static void wr__pz_mark(wr__pz *z, double x, double y, int l) {
    int64_t mx = wr__pz_ifloor((x - z->x0) * z->inv_mg), my = wr__pz_ifloor((y - z->y0) * z->inv_mg);
    if (mx >= z->mx) mx = z->mx - 1;
    if (my >= z->my) my = z->my - 1;
    if (mx < 0) mx = 0;
    if (my < 0) my = 0;
    z->mask[my * z->mx + mx] |= (uint64_t)1 << l;
}

/* Store a point of sizing h with conflict radius r (samples: r = c h; fixed points: see
 * wr__pz_fixed_radius). The level is that of c h in both cases, so a constant sizing stays one
 * level; the level's rmax covers r, so the queries still reach every conflict. */
static wr_status wr__pz_insert(wr__pz *z, double x, double y, double h, double r) {
    int l = wr__pz_level(z, z->c * h);
    int64_t cx, cy;
    uint64_t key;
    size_t s;
    int32_t i, j;
    if (l < 0 || l > 62)
        return wr_fail(z->diag, WR_ERR_DOMAIN, -1,
                       "sizing %g at (%.9g, %.9g) is outside the representable range relative to the domain size", h,
                       x, y);
    cx = wr__pz_ifloor((x - z->x0) * z->inv_cs[l]);
    cy = wr__pz_ifloor((y - z->y0) * z->inv_cs[l]);
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
        if ((a = wr_realloc_array(z->g, (size_t)nc, 2 * sizeof(float))) == NULL) goto nomem;
        z->g = (float *)a;
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
    z->g[2 * i] = z->g[2 * i + 1] = 0.0f;
    key = wr__pz_key(l, cx / WR__PZ_TILE, cy / WR__PZ_TILE);
    s = wr__pz_slot(z, key);
    if (z->tiles[s].key != key) { /* a new tile: its heads are read only under occupied bits */
        z->tiles[s].key = key;
        z->tiles[s].occ = 0;
        z->tcnt[s] = 0;
        ++z->hcount;
    }
    j = (int32_t)((cy % WR__PZ_TILE) * WR__PZ_TILE + cx % WR__PZ_TILE);
    z->sm[i].next = z->tiles[s].occ >> j & 1u ? z->heads[s * WR__PZ_TILE * WR__PZ_TILE + (size_t)j] : -1;
    z->tiles[s].occ |= (uint64_t)1 << j;
    ++z->tcnt[s];
    z->heads[s * WR__PZ_TILE * WR__PZ_TILE + (size_t)j] = i;
    if (r > z->rmax[l]) z->rmax[l] = r;
    if (r > z->rmax_all) z->rmax_all = r;
    /* the presence grid is read only once two levels are in use (wr__pz_levels_near): until then
     * it is left empty, and the sample that brings the second level marks every sample so far */
    if (!(z->levels >> l & 1u)) { /* a new level */
        if (z->levels && !(z->levels & (z->levels - 1u)))
            for (j = 0; j < i; ++j) wr__pz_mark(z, z->sm[j].x, z->sm[j].y, z->sm[j].lvl);
        z->levels |= (uint64_t)1 << l;
    }
    if (z->levels & (z->levels - 1u)) wr__pz_mark(z, x, y, l);
    return WR_OK;
nomem:
    return wr_fail(z->diag, WR_ERR_NOMEM, -1, "samples: out of memory");
}


/* Conflict radius of a fixed point of the outer loop or a hole, sizing h: (2 D − c) h, so that the
 * mean-rule distance to a sample of the same sizing, (r_f + c h)/2, is D h (ON THE FIRST RING). */
static double wr__pz_fixed_radius(const wr__pz *z, double h) { return (2.0 * z->fixed_d - z->c) * h; }

/* The sizing gradient estimate g of a front step made consistent with the directional difference
 * s = (h(x) − h_p) / ρ just observed along the unit direction u (a projection onto that one
 * observation, as in Kaczmarz's method: exact for a linear sizing after two directions). It only
 * steers where candidates are placed (the band check decides), so float storage and a stale
 * estimate cost at most an evaluation. */
static inline void wr__pz_grad_update(double *gx, double *gy, double ux, double uy, double s) {
    double corr = s - (*gx * ux + *gy * uy);
    *gx += corr * ux;
    *gy += corr * uy;
}

/* One step of the front (Dunbar & Humphreys 2006, boundary sampling, generalised to a varying
 * radius): place new samples on the circle of radius ρ = r_p around point p until no direction is
 * left. The free directions are kept as arcs; the curves' and the neighbours' arcs (the directions
 * in which a sample would conflict with them, assuming the new radius ≈ r_p) are cut before the
 * first draw. A drawn direction is checked exactly: inside the domain, sizing evaluated (once,
 * at the mean-rule distance predicted by the gradient estimate; once more only when the radius
 * there is off that distance by more than WR__PZ_REPLACE and the point moves to it), clearance
 * from the segments, mean rule against every neighbour. */
static wr_status wr__pz_activate(wr__pz *z, int32_t ip) {
    /* rp: p's conflict radius; rc: the radius a new sample here would have (c h_p; = rp for a
     * sample, smaller for a fixed point) — the arcs are cut for candidates of radius rc */
    const double px = z->sm[ip].x, py = z->sm[ip].y, rp = z->sm[ip].r, hp = z->h[ip], rc = z->c * hp;
    const double rho0 = 0.5 * (rp + rc) * (1.0 + WR__PZ_GAP), rb = WR__PZ_RBOUND * rc, rho_max = 0.5 * (rp + rb);
    double gx = z->g[2 * ip], gy = z->g[2 * ip + 1]; /* ∇h estimate at p */
    wr__pz_arcs A;
    int32_t fails = 0, moves;
    int curves, far, inner, placed, tiny = 1;
    wr_status st;
    A.n = 1;
    A.lo[0] = 0.0;
    A.hi[0] = WR__PZ_TWO_PI;
    curves = wr__pz_arcs_cut_curves(z, &A, px, py, rho0, z->clearance * z->h[ip],
                                    rho_max + z->clearance * rb / z->c);
    z->nb_n = 0;
    if (A.n > 0) {
        wr__pz_cut C;
        C.F.n = 1;
        C.F.lo[0] = 0.0;
        C.F.hi[0] = 4.0;
        C.rho = rho0;
        C.inv_2rho = 0.5 / rho0;
        C.rc = rc;
        C.ip = ip;
        C.tiny = 0;
        if (wr__pz_neighbours(z, px, py, rho_max, rb, &C) < 0)
            return wr_fail(z->diag, WR_ERR_NOMEM, -1, "neighbours: out of memory");
        wr__pz_arcs_take_free(&A, &C.F);
        /* coordinates up to WR__PZ_SCALE radii: their rounding is far below the margins that
         * make the neighbour test conclusive (below) */
        tiny = C.tiny || !(rc * WR__PZ_SCALE >= z->xmag);
    }
    while (A.n > 0 && fails < z->k) {
        double th = wr__pz_arcs_pick(&A, wr_rng_uniform(&z->rng), &inner), ux, uy, rho = rho0, x, y, hx, rx, gu, m0;
        wr__pz_sincos(th, &uy, &ux);
        /* where the gradient estimate predicts that rho0 is out of the accepted band (below),
         * place the candidate at the predicted fixed point ρ = (r_p + c (h_p + ρ ∇h·u)) / 2 at once,
         * so the sizing is evaluated once per candidate on a graded map (a 20× ramp: 1.74 → ~1.0
         * evaluations per sample); the band check below still decides, and moves on if needed */
        gu = gx * ux + gy * uy;
        m0 = 0.5 * (rp + rc + z->c * rho0 * gu);
        placed = 0;
        if ((m0 > rho0 || rho0 - m0 > WR__PZ_REPLACE * rho0) && fabs(0.5 * z->c * gu) < WR__PZ_PREDICT_MAX) {
            rho = 0.5 * (rp + rc) / (1.0 - 0.5 * z->c * gu) * (1.0 + WR__PZ_MOVE_GAP);
            placed = 1;
        }
        x = px + rho * ux;
        y = py + rho * uy;
        if ((curves || rho > rho_max) && !wr__pz_inside_at(z->segs, x, y)) goto failed;
        if ((st = wr__pz_size(z, x, y, &hx)) != WR_OK) return st;
        ++z->n_candidates;
        wr__pz_grad_update(&gx, &gy, ux, uy, (hx - hp) / rho);
        rx = z->c * hx;
        /* where the sizing changed, move along the direction to the mean-rule distance: the
         * fixed point of ρ = (r_p + r(ρ)) / 2, iterated (it contracts wherever |∇r| < 2); beyond
         * ρ_max too, so a jump to a coarser region is crossed (checked against the grid below) */
        for (moves = 0; 0.5 * (rp + rx) > rho || rho - 0.5 * (rp + rx) > WR__PZ_REPLACE * rho; ++moves) {
            if (moves == WR__PZ_MOVES) {
                if (0.5 * (rp + rx) > rho) goto failed;
                break; /* a little slack is fine; too close is not */
            }
            rho = 0.5 * (rp + rx) * (1.0 + WR__PZ_MOVE_GAP);
            x = px + rho * ux;
            y = py + rho * uy;
            if ((curves || rho > rho_max) && !wr__pz_inside_at(z->segs, x, y)) goto failed;
            if ((st = wr__pz_size(z, x, y, &hx)) != WR_OK) return st;
            ++z->n_candidates;
            wr__pz_grad_update(&gx, &gy, ux, uy, (hx - hp) / rho);
            rx = z->c * hx;
        }
        far = rho > rho_max || rx > rb; /* beyond what the neighbour list and `curves` cover */
        if ((curves || far) && !wr__pz_clear_of_segments(z->segs, x, y, z->clearance * hx)) goto failed;
        if (!far) {
            /* the arcs assumed radius rc; the candidate's own rx decides (a neighbour's arc is
             * already cut, so a conflict here is a failed direction). Not needed when the
             * candidate is on the circle the lenses were cut for, no larger than rc, and
             * WR__PZ_INNER inside its free arc: every neighbour is then farther than its mean-rule
             * distance by a margin far above the rounding of the lens ends and of the coordinates
             * (no neighbour touching the circle within rounding: `tiny`) */
            if ((moves || placed || rx > rc || !inner || tiny) && wr__pz_nb_conflict(z, x, y, rx)) goto failed;
        } else {
            if (wr__pz_near(z, x, y, 0.0, rx)) goto failed; /* the grid decides */
        }
        if ((st = wr__pz_insert(z, x, y, hx, rx)) != WR_OK) return st;
        z->g[2 * (z->n - 1)] = (float)gx; /* the new sample inherits the estimate */
        z->g[2 * (z->n - 1) + 1] = (float)gy;
        if ((st = wr__pz_nb_push(z, z->n - 1)) != WR_OK) return st;
        wr__pz_arcs_cut_disk(&A, rho0, th, rho, 0.5 * (rc + rx), &tiny);
        wr__pz_arcs_cut_tiny(&A, th);
        continue;
    failed:
        ++fails;
        wr__pz_arcs_cut(&A, th, WR__PZ_FAIL_ARC);
    }
    return WR_OK;
}

/* Grids and sample storage sized from the estimate (est points, radii up to rmax). */
static wr_status wr__pz_grids_init(wr__pz *z, double x0, double y0, double W, double H, double est, double rmax) {
    int32_t i, nc;
    double cells_cap = fmax(4096.0, 4.0 * est), want = fmin(1.1 * est + 64.0, (double)z->max_points);
    z->x0 = x0;
    z->y0 = y0;
    z->W = W;
    z->H = H;
    z->xmag = fmax(fmax(fabs(x0), fabs(x0 + W)), fmax(fabs(y0), fabs(y0 + H)));
    z->s_base = ldexp(fmax(fmax(W, H), 1e-300), -28);
    for (i = 0; i < 64; ++i) {
        z->cs[i] = ldexp(z->s_base, i + 1);
        z->inv_cs[i] = 1.0 / z->cs[i];
        z->lim_x[i] = (int64_t)(W * z->inv_cs[i]) + 1;
        z->lim_y[i] = (int64_t)(H * z->inv_cs[i]) + 1;
        z->rmax[i] = 0.0;
        z->tw[i] = (uint64_t)fmin(W * z->inv_cs[i] / WR__PZ_TILE, 1e9) + 2u;
        z->th[i] = (uint64_t)fmin(H * z->inv_cs[i] / WR__PZ_TILE, 1e9) + 2u;
    }
    z->mg = 2.0 * rmax;
    while ((W / z->mg + 1.0) * (H / z->mg + 1.0) > cells_cap) z->mg *= 1.5;
    z->inv_mg = 1.0 / z->mg;
    z->mx = (int32_t)(W * z->inv_mg) + 1;
    z->my = (int32_t)(H * z->inv_mg) + 1;
    z->mask = (uint64_t *)wr_calloc_array((size_t)z->mx * (size_t)z->my, sizeof(uint64_t));
    if (!z->mask) return wr_fail(z->diag, WR_ERR_NOMEM, -1, "presence grid: out of memory");
    /* tiles hold 64 cells of side r..2r: ~ one tile per 64·r²·κ/r² ≈ 57 samples or more */
    if (wr__pz_hash_init(z, (size_t)(est / 56.0) + 16) != WR_OK) return WR_ERR_NOMEM;
    nc = want < 16.0 ? 16 : (int32_t)want;
    z->sm = (wr__pz_s *)wr_alloc_array((size_t)nc, sizeof(wr__pz_s));
    z->h = (double *)wr_alloc_array((size_t)nc, sizeof(double));
    z->g = (float *)wr_alloc_array((size_t)nc, 2 * sizeof(float));
    if (!z->sm || !z->h || !z->g) return wr_fail(z->diag, WR_ERR_NOMEM, -1, "samples: out of memory");
    z->cap = nc;
    return WR_OK;
}

/* The fill over curve set dc (its points are the fixed points, its edges the segments): fixed
 * points first, then every point in order of creation is a front step (first in, first out: the
 * front advances from the curves inwards, and consecutive steps touch nearby memory). */
static wr_status wr__pz_fill(wr__pz *z, const wr__pz_curves *dc, const double *hfix, wr_poisson_result *res) {
    int32_t i, c, s = 0, ns = 0, n_loop;
    wr_status st;
    /* loop points (curves 0..n_holes come first) keep the first ring at D h; the points of
     * constraint lines keep the interior rule (ON THE FIRST RING) */
    n_loop = dc->nc > dc->n_holes + 1 ? dc->off[dc->n_holes + 1] : dc->np;
    for (i = 0; i < dc->np; ++i) {
        double r = i < n_loop ? wr__pz_fixed_radius(z, hfix[i]) : z->c * hfix[i];
        if ((st = wr__pz_insert(z, dc->xy[2 * i], dc->xy[2 * i + 1], hfix[i], r)) != WR_OK) return st;
    }
    for (i = 0; i < z->n; ++i)
        if ((st = wr__pz_activate(z, i)) != WR_OK) return st;
    for (c = 0; c < dc->nc; ++c) ns += wr__pz_nseg(dc, c);
    res->points = (double *)wr_alloc_array((size_t)z->n, 2 * sizeof(double));
    res->sizing = (double *)wr_alloc_array((size_t)z->n, sizeof(double));
    res->segments = (int32_t *)wr_alloc_array((size_t)ns, 2 * sizeof(int32_t));
    res->segment_owner = (int32_t *)wr_alloc_array((size_t)ns, sizeof(int32_t));
    if (!res->points || !res->sizing || !res->segments || !res->segment_owner)
        return wr_fail(z->diag, WR_ERR_NOMEM, -1, "result: out of memory");
    for (i = 0; i < z->n; ++i) {
        res->points[2 * i] = z->sm[i].x;
        res->points[2 * i + 1] = z->sm[i].y;
    }
    memcpy(res->sizing, z->h, sizeof(double) * (size_t)z->n);
    for (c = 0; c < dc->nc; ++c)
        for (i = 0; i < wr__pz_nseg(dc, c); ++i, ++s) {
            res->segments[2 * s] = dc->off[c] + i;
            res->segments[2 * s + 1] = dc->off[c] + (i + 1) % dc->cnt[c];
            res->segment_owner[s] = c;
        }
    res->n_points = z->n;
    res->n_fixed = dc->np;
    res->n_segments = ns;
    res->n_candidates = z->n_candidates;
    return WR_OK;
}

static void wr__pz_free(wr__pz *z) {
    wr_free(z->sm);
    wr_free(z->h);
    wr_free(z->g);
    wr_free(z->tiles);
    wr_free(z->heads);
    wr_free(z->tcnt);
    wr_free(z->mask);
    wr_free(z->tx);
    wr_free(z->ty);
    wr_free(z->tI);
    wr_free(z->nb);
}

WRDEF void wr_poisson_free(wr_poisson_result *res) {
    if (!res) return;
    wr_free(res->points);
    wr_free(res->sizing);
    wr_free(res->segments);
    wr_free(res->segment_owner);
    memset(res, 0, sizeof *res);
}

static const wr_poisson_curve *wr__pz_dom_curve(const wr_poisson_domain *dom, int32_t c) {
    return c == 0 ? &dom->outer : (c <= dom->n_holes ? &dom->holes[c - 1] : &dom->lines[c - 1 - dom->n_holes]);
}

/* Copy the input curves; check counts and finiteness. */
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
        const wr_poisson_curve *k = wr__pz_dom_curve(dom, c);
        int is_loop = c <= dom->n_holes;
        int32_t need = is_loop || k->closed ? 3 : 2;
        wr__pz_curve_name(cv, c, name, sizeof name);
        if (k->n < need || !k->xy)
            return wr__pz_where(diag, wr_fail(diag, WR_ERR_GEOMETRY, c, "%s has %d points (at least %d needed)", name,
                                              (int)k->n, (int)need),
                                c, -1, -1, -1);
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
        const wr_poisson_curve *k = wr__pz_dom_curve(dom, c);
        for (i = 0; i < k->n; ++i) {
            double x = k->xy[2 * i], y = k->xy[2 * i + 1];
            if (!isfinite(x) || !isfinite(y)) {
                wr__pz_curve_name(cv, c, name, sizeof name);
                return wr__pz_where(diag, wr_fail(diag, WR_ERR_GEOMETRY, i, "%s point %d is not finite (%g, %g)", name,
                                                  (int)i, x, y),
                                    c, i, -1, -1);
            }
            cv->xy[2 * (cv->off[c] + i)] = x;
            cv->xy[2 * (cv->off[c] + i) + 1] = y;
        }
    }
    return WR_OK;
}

/* Bounding box of the outer loop; its extent must be a finite double. Zero-length segments. */
static wr_status wr__pz_check_extent(const wr__pz_curves *in, double box[4], wr_diag *diag) {
    int32_t c, i;
    char name[32];
    box[0] = box[1] = HUGE_VAL;
    box[2] = box[3] = -HUGE_VAL;
    for (i = 0; i < in->np; ++i) {
        box[0] = fmin(box[0], in->xy[2 * i]);
        box[2] = fmax(box[2], in->xy[2 * i]);
        box[1] = fmin(box[1], in->xy[2 * i + 1]);
        box[3] = fmax(box[3], in->xy[2 * i + 1]);
    }
    if (!isfinite(box[2] - box[0]) || !isfinite(box[3] - box[1]))
        return wr_fail(diag, WR_ERR_GEOMETRY, -1, "input extent [%g, %g] x [%g, %g] m overflows a double", box[0],
                       box[2], box[1], box[3]);
    for (c = 0; c < in->nc; ++c)
        for (i = 0; i < wr__pz_nseg(in, c); ++i) {
            const double *a = in->xy + 2 * (in->off[c] + i), *b = in->xy + 2 * (in->off[c] + (i + 1) % in->cnt[c]);
            if (a[0] == b[0] && a[1] == b[1]) {
                wr__pz_curve_name(in, c, name, sizeof name);
                return wr__pz_where(diag, wr_fail(diag, WR_ERR_GEOMETRY, i,
                                                  "%s segment %d has zero length (points %d and %d coincide)", name,
                                                  (int)i, (int)i, (int)((i + 1) % in->cnt[c])),
                                    c, i, -1, -1);
            }
        }
    return WR_OK;
}

/* Crossings, zero area, containment (the curves form a valid domain). */
static wr_status wr__pz_validate(const wr__pz_curves *in, double maxdim, const char *what, wr_diag *diag) {
    int32_t c, k;
    char name[32], name2[32];
    wr_status st;
    /* crossings before areas: a self-intersecting loop can have any signed area (a symmetric bow-tie
     * has 0), and the crossing is the more useful message */
    if ((st = wr__pz_check_crossings(in, what, diag)) != WR_OK) return st;
    for (c = 0; c <= in->n_holes; ++c) {
        /* about the first vertex (core.h): an origin-based shoelace cancels a small far loop away */
        double area = wr_polygon_area(in->xy + 2 * in->off[c], in->cnt[c]);
        wr__pz_curve_name(in, c, name, sizeof name);
        if (!(fabs(area) > WR_POISSON_REL_TOL * maxdim * maxdim))
            return wr__pz_where(diag, wr_fail(diag, WR_ERR_GEOMETRY, c, "%s has zero area (%g m^2)", name, area), c, -1,
                                -1, -1);
    }
    /* no crossings: one vertex decides each containment relation */
    for (c = 1; c < in->nc; ++c) {
        const double *p = in->xy + 2 * in->off[c];
        wr__pz_curve_name(in, c, name, sizeof name);
        if (!wr__pz_in_curve(in, 0, p))
            return wr__pz_where(diag, wr_fail(diag, WR_ERR_GEOMETRY, c, "%s lies outside the outer loop", name), c, -1,
                                0, -1);
        for (k = 1; k <= in->n_holes; ++k) {
            if (k == c) continue;
            if (wr__pz_in_curve(in, k, p) || (c <= in->n_holes && wr__pz_in_curve(in, c, in->xy + 2 * in->off[k]))) {
                wr__pz_curve_name(in, k, name2, sizeof name2);
                return wr__pz_where(diag, wr_fail(diag, WR_ERR_GEOMETRY, c, "%s %s %s", name,
                                                  c <= in->n_holes ? "overlaps" : "lies inside", name2),
                                    c, -1, k, -1);
            }
        }
    }
    return WR_OK;
}

static int wr__pz_cmp_double(const void *a, const void *b) {
    double x = *(const double *)a, y = *(const double *)b;
    return x < y ? -1 : (x > y);
}

/* x-crossings of the loops with the probe rows y_j = y0 + (j + ½) dy (half-open rule), as CSR:
 * row j's crossings are xs[start[j] .. start[j+1]), sorted. Returns the row count actually used
 * (halved until the crossings fit in 8 per segment + 64 per row, so a zigzag loop cannot blow it up). */
static int32_t wr__pz_probe_rows(const wr__pz_curves *cv, double y0, double H, int32_t rows, int32_t **start_out,
                                 double **xs_out) {
    for (;; rows = rows > 1 ? rows / 2 : 1) {
        double dy = H / rows;
        int64_t total = 0, cap;
        int32_t c, i, j, ns = 0, *start;
        int pass;
        double *xs = NULL;
        for (c = 0; c <= cv->n_holes; ++c) ns += cv->cnt[c];
        cap = 8 * (int64_t)ns + 64 * (int64_t)rows;
        start = (int32_t *)wr_calloc_array((size_t)rows + 2, sizeof(int32_t));
        if (!start) return -1;
        for (pass = 0; pass < 2 && total <= cap; ++pass) {
            if (pass == 1) {
                for (j = 0; j < rows; ++j) start[j + 1] += start[j];
                xs = (double *)wr_alloc_array((size_t)total, sizeof(double));
                if (!xs) {
                    wr_free(start);
                    return -1;
                }
            }
            for (c = 0; c <= cv->n_holes; ++c)
                for (i = 0; i < cv->cnt[c]; ++i) {
                    const double *a = cv->xy + 2 * (cv->off[c] + i), *b = cv->xy + 2 * (cv->off[c] + (i + 1) % cv->cnt[c]);
                    double lo = fmin(a[1], b[1]), hi = fmax(a[1], b[1]);
                    int32_t j0 = (int32_t)fmax(0.0, floor((lo - y0) / dy - 0.5)), j1 = (int32_t)fmin(rows - 1.0, ceil((hi - y0) / dy));
                    for (j = j0; j <= j1; ++j) {
                        double y = y0 + (j + 0.5) * dy;
                        if ((a[1] > y) == (b[1] > y)) continue;
                        if (pass == 0) {
                            ++start[j + 1];
                            ++total;
                        } else {
                            xs[start[j]++] = a[0] + (y - a[1]) * (b[0] - a[0]) / (b[1] - a[1]);
                        }
                    }
                }
            if (pass == 1) {
                for (j = rows; j > 0; --j) start[j] = start[j - 1];
                start[0] = 0;
                for (j = 0; j < rows; ++j)
                    qsort(xs + start[j], (size_t)(start[j + 1] - start[j]), sizeof(double), wr__pz_cmp_double);
                *start_out = start;
                *xs_out = xs;
                return rows;
            }
        }
        wr_free(start);
        if (rows == 1) return -1;
    }
}

/* The budget estimate (see wr_poisson_budget): O(input + probes), nothing that grows with the
 * output. want_discretised = 0 skips ∫ ds / h (the fill keeps the given points). */
static wr_status wr__pz_estimate(wr__pz *z, const wr__pz_curves *in, const double box[4], int want_discretised,
                                 wr_poisson_budget *b) {
    double W = box[2] - box[0], H = box[3] - box[1], dx, dy, sum_inv_r2 = 0.0, *xs = NULL;
    int32_t P = WR_POISSON_BUDGET_PROBES * WR_POISSON_BUDGET_PROBES, mx, my, c, i, j, *start = NULL;
    wr_status st = WR_OK;
    memset(b, 0, sizeof *b);
    b->h_min = HUGE_VAL;
    b->n_given = (double)in->np;
    for (c = 0; c <= in->n_holes; ++c) b->area += (c ? -1.0 : 1.0) * fabs(wr_polygon_area(in->xy + 2 * in->off[c], in->cnt[c]));
    for (c = 0; c < in->nc; ++c)
        for (i = 0; i < wr__pz_nseg(in, c); ++i) {
            /* Simpson's rule on 1/h along the segment (endpoints and middle) */
            const double *a = in->xy + 2 * (in->off[c] + i), *e = in->xy + 2 * (in->off[c] + (i + 1) % in->cnt[c]);
            double L = hypot(e[0] - a[0], e[1] - a[1]), ha, hm, he;
            b->perimeter += L;
            if (!want_discretised) continue;
            if ((st = wr__pz_size(z, a[0], a[1], &ha)) != WR_OK) return st;
            if ((st = wr__pz_size(z, 0.5 * (a[0] + e[0]), 0.5 * (a[1] + e[1]), &hm)) != WR_OK) return st;
            if ((st = wr__pz_size(z, e[0], e[1], &he)) != WR_OK) return st;
            b->n_discretised += L * (1.0 / ha + 4.0 / hm + 1.0 / he) / 6.0 + (i == 0 && !in->closed[c]);
            b->h_min = fmin(b->h_min, fmin(ha, fmin(hm, he)));
            b->h_max = fmax(b->h_max, fmax(ha, fmax(hm, he)));
        }
    /* probe lattice with the box's aspect ratio, inside test by scanline over the loops */
    my = (int32_t)fmin((double)P, fmax(1.0, floor(sqrt((double)P * H / fmax(W, 1e-300)) + 0.5)));
    mx = (int32_t)fmax(1.0, (double)(P / my));
    if ((my = wr__pz_probe_rows(in, box[1], H, my, &start, &xs)) < 0)
        return wr_fail(z->diag, WR_ERR_NOMEM, -1, "budget probes: out of memory");
    dx = W / mx;
    dy = H / my;
    for (j = 0; j < my; ++j) {
        int32_t k = start[j];
        for (i = 0; i < mx; ++i) {
            double x = box[0] + (i + 0.5) * dx, y = box[1] + (j + 0.5) * dy, h;
            while (k < start[j + 1] && xs[k] < x) ++k;
            if (((k - start[j]) & 1) == 0) continue; /* even number of crossings to the left: outside */
            if ((st = wr__pz_size(z, x, y, &h)) != WR_OK) goto done;
            sum_inv_r2 += 1.0 / (z->c * h * z->c * h);
            b->h_min = fmin(b->h_min, h);
            b->h_max = fmax(b->h_max, h);
            ++b->n_probes;
        }
    }
    if (b->n_probes == 0) /* a domain thinner than the probe spacing: its curve vertices stand in */
        for (c = 0; c <= in->n_holes; ++c)
            for (i = 0; i < in->cnt[c]; i += 1 + in->cnt[c] / 64) {
                double h;
                if ((st = wr__pz_size(z, in->xy[2 * (in->off[c] + i)], in->xy[2 * (in->off[c] + i) + 1], &h)) != WR_OK)
                    goto done;
                sum_inv_r2 += 1.0 / (z->c * h * z->c * h);
                b->h_min = fmin(b->h_min, h);
                b->h_max = fmax(b->h_max, h);
                ++b->n_probes;
            }
    b->n_interior = WR_POISSON_DENSITY * fmax(b->area, 0.0) * sum_inv_r2 / b->n_probes;
done:
    wr_free(start);
    wr_free(xs);
    return st;
}

/* Defaults (the one place) and argument checks. */
static wr_status wr__pz_setup(wr__pz *z, const wr_poisson_domain *dom, wr_poisson_sizing_fn sizing, void *user,
                              const wr_poisson_desc *desc_in, wr_poisson_desc *desc, wr_diag *diag) {
    memset(z, 0, sizeof *z);
    if (!dom || !sizing) return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "wr_poisson: NULL domain or sizing");
    if (dom->n_holes < 0 || dom->n_lines < 0 || (dom->n_holes > 0 && !dom->holes) || (dom->n_lines > 0 && !dom->lines))
        return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "wr_poisson: bad hole/line arrays");
    if (desc_in)
        *desc = *desc_in;
    else
        memset(desc, 0, sizeof *desc);
    if (desc->k == 0) desc->k = WR_POISSON_DEFAULT_K;
    if (desc->radius_factor == 0.0) desc->radius_factor = WR_POISSON_DEFAULT_RADIUS_FACTOR;
    if (desc->max_points == 0) desc->max_points = WR_POISSON_DEFAULT_MAX_POINTS;
    if (desc->corner_angle == 0.0) desc->corner_angle = WR_POISSON_DEFAULT_CORNER_ANGLE;
    if (desc->clearance == 0.0) desc->clearance = WR_POISSON_DEFAULT_CLEARANCE;
    if (desc->fixed_distance == 0.0) desc->fixed_distance = WR_POISSON_DEFAULT_FIXED_DISTANCE;
    if (desc->k < 1 || !(desc->radius_factor > 0.0) || !isfinite(desc->radius_factor) || desc->max_points < 1 ||
        !(desc->corner_angle > 0.0) || !(desc->clearance >= 0.0) || !(desc->clearance < 0.5 * desc->radius_factor) ||
        !(desc->fixed_distance > 0.5 * desc->radius_factor) || !(desc->fixed_distance < 4.0))
        return wr_fail(diag, WR_ERR_INVALID_ARG, -1,
                       "wr_poisson_desc: k=%d radius_factor=%g max_points=%d corner_angle=%g clearance=%g "
                       "fixed_distance=%g",
                       (int)desc->k, desc->radius_factor, (int)desc->max_points, desc->corner_angle, desc->clearance,
                       desc->fixed_distance);
    z->fn = sizing;
    z->user = user;
    z->diag = diag;
    z->c = desc->radius_factor;
    z->max_points = desc->max_points;
    z->k = desc->k;
    z->clearance = desc->clearance;
    z->fixed_d = desc->fixed_distance;
    wr_rng_seed(&z->rng, desc->seed);
    return WR_OK;
}

/* Refuse, naming what to change, when the estimate exceeds the budget. */
static wr_status wr__pz_check_budget(const wr__pz *z, const wr_poisson_budget *b, double n_curve, int32_t *n_est) {
    double est = n_curve + b->n_interior;
    *n_est = est < (double)INT32_MAX ? (int32_t)est : INT32_MAX;
    if (n_curve > (double)z->max_points)
        return wr_fail(z->diag, WR_ERR_BUDGET, -1,
                       "the curves alone need %.0f points (%.4g m of curves at sizing down to %.3g m) > max_points=%d: "
                       "raise max_points or coarsen the sizing",
                       n_curve, b->perimeter, b->h_min, (int)z->max_points);
    if (est > (double)z->max_points)
        return wr_fail(z->diag, WR_ERR_BUDGET, -1,
                       "estimated %.0f points (%.0f on the curves + %.0f inside: %.4g m^2 at sizing %.3g..%.3g m) > "
                       "max_points=%d: raise max_points or coarsen the sizing",
                       est, n_curve, b->n_interior, b->area, b->h_min, b->h_max, (int)z->max_points);
    return WR_OK;
}

/* The shared pipeline of wr_poisson_sample (discretise = 1) and wr_poisson_fill (0). */
static wr_status wr__pz_run(const wr_poisson_domain *dom, wr_poisson_sizing_fn sizing, void *user,
                            const wr_poisson_desc *desc_in, int discretise, wr_poisson_result *res, wr_diag *diag) {
    wr_poisson_desc desc;
    wr_poisson_budget bud;
    wr__pz z;
    wr__pz_curves in, dc;
    wr__pz_segs segs;
    const wr__pz_curves *curves = &in;
    double t0 = wr_time_seconds(), box[4], maxdim, rmax, *hfix = NULL;
    int32_t i;
    wr_status st;
    memset(&in, 0, sizeof in);
    memset(&dc, 0, sizeof dc);
    memset(&segs, 0, sizeof segs);
    if (!res) return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "wr_poisson: NULL result");
    memset(res, 0, sizeof *res);
    if ((st = wr__pz_setup(&z, dom, sizing, user, desc_in, &desc, diag)) != WR_OK) return st;
    /* 1. cheap O(n) checks, then the budget from area and perimeter before anything larger */
    if ((st = wr__pz_gather(dom, &in, diag)) != WR_OK) goto done;
    if ((st = wr__pz_check_extent(&in, box, diag)) != WR_OK) goto done;
    maxdim = fmax(box[2] - box[0], box[3] - box[1]);
    if ((st = wr__pz_estimate(&z, &in, box, discretise, &bud)) != WR_OK) goto done;
    if ((st = wr__pz_check_budget(&z, &bud, discretise ? bud.n_discretised : bud.n_given, &res->n_estimated)) != WR_OK)
        goto done;
    /* 2. the curves form a valid domain; 3. (sample) discretised at the sizing, still valid */
    if ((st = wr__pz_validate(&in, maxdim, "input", diag)) != WR_OK) goto done;
    if (discretise) {
        if ((st = wr__pz_discretise(&z, &in, desc.corner_angle, &dc)) != WR_OK) goto done;
        if ((st = wr__pz_check_crossings(&dc, "discretised at the sizing (feature thinner than the sizing?)", diag)) !=
            WR_OK)
            goto done;
        curves = &dc;
    }
    /* 4. sizing at the fixed points, grids, the fill */
    hfix = (double *)wr_alloc_array((size_t)curves->np, sizeof(double));
    if (!hfix) {
        st = wr_fail(diag, WR_ERR_NOMEM, -1, "out of memory");
        goto done;
    }
    rmax = z.c * bud.h_max;
    for (i = 0; i < curves->np; ++i) {
        if ((st = wr__pz_size(&z, curves->xy[2 * i], curves->xy[2 * i + 1], &hfix[i])) != WR_OK) goto done;
        rmax = fmax(rmax, z.c * hfix[i]);
    }
    if ((st = wr__pz_segs_build(&segs, curves, box[0], box[1], box[2] - box[0], box[3] - box[1],
                                WR_POISSON_REL_TOL * maxdim, (double)curves->np + bud.n_interior, diag)) != WR_OK)
        goto done;
    z.segs = &segs;
    if ((st = wr__pz_grids_init(&z, box[0], box[1], box[2] - box[0], box[3] - box[1],
                                (double)curves->np + bud.n_interior, rmax)) != WR_OK)
        goto done;
    st = wr__pz_fill(&z, curves, hfix, res);
done:
    if (st != WR_OK) {
        int32_t est = res->n_estimated;
        wr_poisson_free(res);
        res->n_estimated = est;
    }
    res->seconds = wr_time_seconds() - t0;
    wr_free(hfix);
    wr__pz_free(&z);
    wr__pz_curves_free(&in);
    wr__pz_curves_free(&dc);
    wr__pz_segs_free(&segs);
    return st;
}

WRDEF wr_status wr_poisson_sample(const wr_poisson_domain *dom, wr_poisson_sizing_fn sizing, void *user,
                                  const wr_poisson_desc *desc, wr_poisson_result *res, wr_diag *diag) {
    return wr__pz_run(dom, sizing, user, desc, 1, res, diag);
}

WRDEF wr_status wr_poisson_fill(const wr_poisson_domain *dom, wr_poisson_sizing_fn sizing, void *user,
                                const wr_poisson_desc *desc, wr_poisson_result *res, wr_diag *diag) {
    return wr__pz_run(dom, sizing, user, desc, 0, res, diag);
}

WRDEF wr_status wr_poisson_estimate(const wr_poisson_domain *dom, wr_poisson_sizing_fn sizing, void *user,
                                    const wr_poisson_desc *desc_in, wr_poisson_budget *out, wr_diag *diag) {
    wr_poisson_desc desc;
    wr__pz z;
    wr__pz_curves in;
    double box[4];
    wr_status st;
    memset(&in, 0, sizeof in);
    if (!out) return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "wr_poisson_estimate: NULL output");
    memset(out, 0, sizeof *out);
    if ((st = wr__pz_setup(&z, dom, sizing, user, desc_in, &desc, diag)) != WR_OK) return st;
    if ((st = wr__pz_gather(dom, &in, diag)) == WR_OK && (st = wr__pz_check_extent(&in, box, diag)) == WR_OK)
        st = wr__pz_estimate(&z, &in, box, 1, out);
    wr__pz_curves_free(&in);
    return st;
}

#ifdef __cplusplus
}
#endif
#endif /* WRINKLE_POISSON_IMPLEMENTATION_DONE */
#endif /* WRINKLE_IMPLEMENTATION */
