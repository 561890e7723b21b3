/* wrinkle/triangulate.h — a constrained Delaunay triangulator with optional Delaunay quality
 * refinement (Ruppert/Shewchuk, Üngör off-centers), on the exact predicates of predicates.h.
 * File I/O: polyfile.h.
 * wrinkle v0.1.0 — MIT licence (see LICENSE). Needs core.h, predicates.h; libc and libm.
 *
 * Style3D Sec. 4.3: "the resulting point cloud [Poisson samples of the sizing map], along with
 * boundary constraints, is then input into triangulation tools such as the Triangle library to
 * produce a triangular cloth mesh adhering to Delaunay triangulation rules." This header is that
 * step, written from the published ideas (Shewchuk 1997 exact predicates, in predicates.h;
 * Lawson flips, Sloan's flip-based edge recovery, BRIO/Hilbert insertion order, Ruppert 1995 and
 * Shewchuk 2002 Delaunay refinement with concentric-shell segment splitting, Üngör off-centers).
 *
 * API
 *   (wr_orient2d, wr_incircle and their _fast versions: predicates.h, included by this header)
 *   wr_cdt_triangulate(in, desc, out, diag)   CDT (+ carving, + refinement) -> wr_cdt_result
 *   wr_cdt_free(out)              release a result (also after a failed call)
 *   wr_cdt_check(res, expected_holes, info, diag)  exact verification of a result
 *   wr_cdt_hilbert_order(xy, ids, n, order, diag)  points sorted along a Hilbert curve (numbering)
 *   (Triangle's .node/.poly files: wrinkle/polyfile.h)
 *
 * EXAMPLE
 *     double pts[] = {0,0, 1,0, 1,1, 0,1, 0.5,0.5};
 *     int32_t seg[] = {0,1, 1,2, 2,3, 3,0};
 *     wr_cdt_input in; wr_cdt_desc d; wr_cdt_result r; wr_diag dg;
 *     memset(&in, 0, sizeof in); memset(&d, 0, sizeof d);
 *     in.points = pts; in.n_points = 5; in.segments = seg; in.n_segments = 4;
 *     d.quality = 1; d.min_angle_deg = 30.0;            // Ruppert refinement, 30° minimum angle
 *     if (wr_cdt_triangulate(&in, &d, &r, &dg) != WR_OK) { puts(dg.message); return 1; }
 *     // r.points (r.n_points×2), r.triangles (r.n_triangles×3, CCW), r.neighbors, r.edge_segment
 *     if (wr_cdt_check(&r, 0, NULL, &dg) != WR_OK) { puts(dg.message); return 1; }   // CCW, CDT, Euler
 *     printf("%d points, %d triangles\n", r.n_points, r.n_triangles);
 *     wr_cdt_free(&r);
 *
 * ON PREDICATES (the flags they need)
 *   Every orientation and in-circle decision is exact (predicates.h: an error-bounded floating-point
 *   filter, expansion arithmetic when it cannot decide). Hence the build needs what predicates.h
 *   needs: no -ffast-math / -Ofast, -ffp-contract=off, SSE2 arithmetic on 32-bit x86; the sign of
 *   every test is exact for coordinates within [1e-50, 1e50] (WR_CDT_MAX_COORD below refuses more).
 *   Degenerate input stays cheap: on grid-like input the exact stage keeps each coordinate
 *   difference as one component (predicates.h), so a lattice whose every in-circle test is
 *   cocircular costs a small constant factor over random points (figure: bench/RESULTS.md,
 *   "bench_cdt").
 *
 * ON THE TRIANGULATION
 *   Input: points (n×2), segments (m×2 point indices, 0-based), hole seeds (h×2). Exact duplicate
 *   points are merged (or points closer than desc.merge_tolerance [same unit as coordinates]);
 *   result.point_map[i] gives the output vertex of input point i. Output vertices: the distinct input
 *   points first, in input order (so without duplicates output vertex i == input point i), then
 *   Steiner points. Triangles are counter-clockwise; neighbors[3t+k] is the triangle across the edge
 *   opposite corner k (joining corners (k+1)%3 -> (k+2)%3), or -1 on the boundary; edge_segment[3t+k]
 *   is the input segment that edge is part of, or -1. Segments crossing each other are rejected with
 *   WR_ERR_GEOMETRY naming both (a garment panel boundary must not self-intersect) unless
 *   desc.split_intersections is set, in which case they are split at a computed Steiner point
 *   (junctions are rounded to doubles; two segments meeting at an angle so small that their pieces
 *   round onto the same edges cannot be represented — one id per piece — and are refused with
 *   WR_ERR_GEOMETRY naming both). Points lying exactly on a segment split it. With segments given and keep_convex_hull unset,
 *   triangles reachable from the convex hull without crossing a segment are removed (when that
 *   would remove everything, i.e. the segments enclose nothing, the hull is kept), and so are those
 *   reachable from each hole seed. Refinement (desc.quality or desc.max_area > 0) then inserts
 *   circumcenters (or off-centers) of bad triangles and splits encroached subsegments, treating the
 *   convex hull edges as segments when the hull is kept (the domain boundary never moves during
 *   refinement: no flips between ghost triangles, so a split point rounded a few ulps outside the
 *   hull cannot bury a hull edge). Subsegments are split at their midpoint, or at a power
 *   of two from an input vertex or a segment junction (concentric shells). Left alone: triangles
 *   whose shortest edge joins points on two segments (or hull edges) meeting at less than 60° (the
 *   input's own small angle; a vertex on one of them does not count as encroaching the other's
 *   subsegments), slivers with all corners on one segment (split points are rounded a few ulps off
 *   the segment's line; the output stays an exact CDT of the vertices produced), and triangles and
 *   subsegments shorter than 2^-36 of their coordinates' magnitude (rounding scale, where a computed
 *   Steiner point is no longer where it should be). With an angle bound, refinement ends with a
 *   clean-up: a free Steiner point (not on a segment) is deleted, or two adjacent ones are merged at
 *   their midpoint, wherever every new triangle still meets the angle and size bounds and the mesh
 *   stays an exact CDT (see "Steiner-point removal" below; figures in bench/RESULTS.md,
 *   bench_triangle). A vertex budget stops everything else:
 *   WR_ERR_BUDGET is returned with the valid mesh reached so far in *out.
 *   Coordinates beyond ±WR_CDT_MAX_COORD (1e70) are refused with WR_ERR_GEOMETRY (the predicates
 *   would overflow). Input segments that overlap on one line share their common subsegments, which
 *   carry the lowest of their ids (segment_id); wr_cdt_check accepts such pieces in each chain.
 *   Always call wr_cdt_free on the result, also after an error.
 *   Cost: O(n log n) expected for the Delaunay part (BRIO order, walks of O(1) expected length),
 *   linear for the clean-up. Timings against CGAL's and Triangle's triangulators: bench/RESULTS.md
 *   ("bench_cdt", "bench_triangle") and bench/bench_cdt.cpp's header.
 *
 * ON THREADS
 *   No global state; distinct calls may run concurrently.
 */
#ifndef WRINKLE_TRIANGULATE_H
#define WRINKLE_TRIANGULATE_H

#include "core.h"
#include "predicates.h" /* wr_orient2d, wr_incircle (exact), also for this header's users */

#ifdef __cplusplus
extern "C" {
#endif

/* ---- constrained Delaunay triangulation ---- */
/* Largest |coordinate| wr_cdt_triangulate accepts (points and hole seeds; larger ones are
 * WR_ERR_GEOMETRY). The in-circle determinant is a sum of products of four coordinate differences,
 * at most 192·c⁴ for |coordinates| <= c; it and the circumcenter arithmetic of refinement stay far
 * below DBL_MAX (1.8e308) up to c = 1e70, while at ~3e76 the fast stage overflows to inf/NaN and the
 * signs (and with them the mesh topology) become meaningless. */
#define WR_CDT_MAX_COORD 1e70

typedef struct wr_cdt_input {
    const double *points;    /* n_points × 2 coordinates, row-major */
    int32_t n_points;
    const int32_t *segments; /* n_segments × 2 indices into points (0-based), may be NULL */
    int32_t n_segments;
    const double *holes;     /* n_holes × 2 seed points inside holes, may be NULL */
    int32_t n_holes;
    /* optional, all may be NULL / 0: */
    const double *regions;   /* n_regions × 4: seed x, y, attribute, maximum area (<= 0: none). Each
                              * seed's region (triangles reachable without crossing a segment) gets
                              * the index in result.triangle_region and that area bound */
    int32_t n_regions;
    const double *attributes; /* n_points × n_attributes values per point; Steiner points get them
                               * interpolated (linearly along a segment, affinely over the triangle
                               * whose Steiner point they are) in result.attributes */
    int32_t n_attributes;
    const int32_t *triangles; /* n_triangles × 3: a previous mesh of these points to refine; its
                               * boundary edges bound the domain (added as segments n_segments.. when
                               * not already segments) and everything outside them is removed */
    int32_t n_triangles;
    const double *triangle_area; /* n_triangles: maximum area inherited by the refinement of each
                                  * previous triangle (<= 0: none); may be NULL */
} wr_cdt_input;

/* User refinement test (Triangle's -u): nonzero when triangle (a, b, c), counter-clockwise, of the
 * given area, must be split. Called often: keep it cheap and pure. */
typedef int (*wr_cdt_unsuitable_fn)(const double *a, const double *b, const double *c, double area, void *user);

/* Options; zero means default:
 *   quality            0: no angle refinement; nonzero: refine to min_angle_deg (Steiner points at
 *                      off-centers, shortest edges first, diametral lenses: see ON REFINEMENT)
 *   min_angle_deg      20° when quality is set; accepted range (0, 34] (Ruppert/Shewchuk's analysis
 *                      guarantees termination up to 20.7°; up to ~33.8° works in practice)
 *   max_area           0: none; > 0: triangles larger than this [coordinate unit²] are split
 *   max_vertices       0: 16·(n_points + n_segments) + 65536 once refinement is on, else unlimited;
 *                      otherwise the total number of output vertices allowed (WR_ERR_BUDGET beyond)
 *   merge_tolerance    0: only exactly equal points are merged; > 0: points closer than this are
 *   keep_convex_hull   0: carve exterior and holes when segments enclose something; 1: keep hull
 *   split_intersections 0: crossing segments -> WR_ERR_GEOMETRY; 1: split them at a Steiner point
 *   off_center         0 or 1: Üngör off-centers (the point on the shortest edge's bisector seeing
 *                      it under a little more than the angle bound, when nearer than the
 *                      circumcenter); -1: plain circumcenters (Ruppert/Chew)
 *   conforming         0: a constrained Delaunay mesh; 1: conforming Delaunay (Triangle's -D):
 *                      subsegments are split until no vertex lies in one's diametral circle
 *                      (then every edge is Delaunay), also without quality or area
 *   no_segment_steiner 0: refinement may split segments; 1: not those bounding the domain
 *                      (Triangle's -Y); 2: no segment (-YY). Triangles it cannot fix stay bad.
 *   unsuitable, user   user test (-u), see wr_cdt_unsuitable_fn; NULL: none
 *   seed               BRIO shuffle seed (0 -> fixed constant); results are deterministic per seed */
typedef struct wr_cdt_desc {
    int quality;
    double min_angle_deg;
    double max_area;
    int32_t max_vertices;
    double merge_tolerance;
    int keep_convex_hull;
    int split_intersections;
    int off_center;
    int conforming;
    int no_segment_steiner;
    wr_cdt_unsuitable_fn unsuitable;
    void *user;
    uint64_t seed;
} wr_cdt_desc;

typedef struct wr_cdt_result {
    double *points;          /* n_points × 2: distinct input points (input order), then Steiner points */
    int32_t n_points;
    int32_t n_input_points;  /* distinct input points (a prefix of points) */
    int32_t *point_map;      /* n_map entries: input point i -> output vertex */
    int32_t n_map;
    int32_t *point_segment;  /* n_points: input segment a Steiner point lies on, else -1 */
    int32_t *triangles;      /* n_triangles × 3, counter-clockwise */
    int32_t n_triangles;
    int32_t *neighbors;      /* n_triangles × 3: triangle across edge opposite corner k, or -1 */
    int32_t *edge_segment;   /* n_triangles × 3: input segment containing that edge, or -1 */
    int32_t *segments;       /* n_segments × 2: subsegments (pieces of input segments), including
                              * pieces that only bounded removed triangles (exterior or holes) */
    int32_t *segment_id;     /* n_segments: which input segment each subsegment belongs to; where
                              * input segments overlap on one line (one given twice, also via merged
                              * points, or one passing through another's end point) their common
                              * pieces carry the lowest of their ids */
    int32_t n_segments;
    int32_t *input_segments; /* n_input_segments × 2: the input segments in output vertex numbers */
    int32_t n_input_segments;
    int exterior_carved;     /* 1 when triangles outside the segments were removed */
    int holes_carved;        /* 1 when hole seeds removed triangles */
    int32_t n_steiner;       /* Steiner points inserted (intersections + refinement) */
    int64_t n_refine_tries;  /* bad-triangle queue entries refinement examined: its cost, a small
                              * multiple of the points inserted on any input */
    int32_t n_left_alone;    /* bad triangles refinement left alone because their Steiner point is
                              * not finite (area rounding to zero); they stay bad */
    int32_t n_duplicates;    /* input points merged into an earlier one */
    double *attributes;      /* n_points × n_attributes (NULL without input attributes) */
    int32_t n_attributes;
    int32_t *triangle_region; /* n_triangles: the region (index into in->regions) the triangle lies
                               * in; n_regions + j when it descends from previous triangle j (and no
                               * region seed reached it); -1 otherwise. NULL without regions and
                               * previous triangles */
    double min_angle_deg;    /* smallest angle over the output triangles */
    double seconds;          /* wall time of wr_cdt_triangulate */
} wr_cdt_result;

WRDEF wr_status wr_cdt_triangulate(const wr_cdt_input *in, const wr_cdt_desc *desc, wr_cdt_result *out,
                                   wr_diag *diag);
WRDEF void wr_cdt_free(wr_cdt_result *r);

/* Spatially coherent order of points: order[0..n) := ids[0..n) (NULL: 0..n-1) sorted along a Hilbert
 * curve over their bounding box (a grid of about 4n..16n cells, at most 2^16 per side; points in one
 * cell keep their order in ids). The curve wr_cdt_triangulate's BRIO rounds follow; for numbering a
 * mesh so that nearby vertices get nearby ids (mesher.h). xy holds every point ids names (×2); order
 * may be ids itself. O(n) (one radix sort), 12 bytes of scratch per point. WR_ERR_INVALID_ARG (n < 0,
 * NULL arrays), WR_ERR_NOMEM. */
WRDEF wr_status wr_cdt_hilbert_order(const double *xy, const int32_t *ids, int32_t n, int32_t *order, wr_diag *diag);

/* What wr_cdt_check measured. */
typedef struct wr_cdt_check_info {
    int32_t n_vertices_used; /* vertices referenced by triangles */
    int32_t n_edges;
    int32_t n_components;     /* edge-connected components of triangles */
    int32_t n_boundary_loops; /* boundary cycles (holes = loops - components) */
    int32_t n_pinched;        /* vertices with more than one boundary fan (Euler test skipped then) */
    int32_t euler;            /* V - E + F */
    double min_angle_deg;
} wr_cdt_check_info;

/* Verifies with exact predicates: indices in range, every triangle strictly CCW, neighbor symmetry
 * (and equal edge_segment on both sides), every unconstrained interior edge locally Delaunay
 * (incircle <= 0), every input segment present as a chain of subsegments (each carrying its id, or
 * the id of an input segment lying exactly on its line: shared pieces, see segment_id), every constrained mesh
 * edge listed as a subsegment and — unless the exterior or holes were carved (a subsegment may then
 * bound removed triangles only) — every subsegment between used vertices present as a constrained mesh edge, Euler characteristic
 * V - E + F == 2·components - boundary_loops, and, when expected_holes >= 0, that the number of
 * holes (boundary_loops - components) equals it. info may be NULL. WR_ERR_TOPOLOGY /
 * WR_ERR_GEOMETRY name the first failing triangle or segment. */
WRDEF wr_status wr_cdt_check(const wr_cdt_result *r, int32_t expected_holes, wr_cdt_check_info *info,
                             wr_diag *diag);

#ifdef __cplusplus
}
#endif
#endif /* WRINKLE_TRIANGULATE_H */

/* ============================================================================================ */
#ifdef WRINKLE_IMPLEMENTATION
#ifndef WRINKLE_TRIANGULATE_IMPLEMENTATION_DONE
#define WRINKLE_TRIANGULATE_IMPLEMENTATION_DONE

#include <math.h>
#include <stdlib.h>
#include <string.h>

#ifdef __cplusplus
extern "C" {
#endif

/* ---- triangulation data structure ----
 * Triangles are vertex triples tv[3t..3t+2] in CCW order; tn[3t+k] is the half-edge (3u+j) of the
 * neighbor across the edge opposite corner k (that edge runs tv[3t+(k+1)%3] -> tv[3t+(k+2)%3]).
 * The convex hull is closed by "ghost" triangles holding the vertex at infinity (index -1), so every
 * half-edge has a twin and every vertex star is a full cycle. cm[3t+k] is the segment id of a
 * constrained edge: >= 0 an input segment, -1 none, <= -2 convex-hull edge k = -2 - cm, treated as a
 * segment ("pseudo-segment" n_segments + k) while refinement keeps the hull as the domain boundary. */
#define WR__INF (-1)
#define WR__HULL_MARK(k) (-2 - (k)) /* cm of hull edge k (and k = -2 - cm) */
#define WR__F_OUT 1 /* triangle removed by carving (outside or in a hole) */

static const int wr__n1[3] = {1, 2, 0};
static const int wr__n2[3] = {2, 0, 1};

typedef struct wr__cdt {
    double *xy;     /* 2·capv */
    int32_t *vtri;  /* capv: some triangle incident to each vertex, -1 if not inserted */
    int32_t *vseg;  /* capv: segment a Steiner point lies on (-1 none) */
    int32_t nv, capv, n_input;
    int32_t *tv, *tn, *cm; /* 3·capt each (cm NULL until constraints exist) */
    unsigned char *tf;     /* capt flags */
    int32_t nt, capt;
    int32_t *stk; /* scratch stack of ints */
    int32_t nstk, capstk;
    int32_t last;  /* triangle to start the next walk from */
    uint32_t walk_rng;
    int32_t max_vertices;
    int track_vtri; /* vtri is kept current only after bulk insertion (rebuilt once, saves stores) */
    int fixed_boundary; /* refinement: the domain boundary may not move (no flips between ghosts) */
    int32_t *treg;      /* capt: region of each triangle (-1 none), NULL without regions */
    double *attr;       /* capv × na vertex attributes, NULL without them */
    int32_t na;
    /* Refinement: the in-conflict answers of the last cavity search (wr__cavity_encroached), reused by
     * wr__legalize when that cavity's point is inserted. ktag[t] = (kid << 1) | answer for the triangles
     * the search tested; kon while the insertion runs. The triangles legalize tests are those across the
     * new point's star, never modified since the search (a flip or split only changes triangles that
     * then hold the new point), so the answer is the one it would compute. */
    uint32_t *ktag;
    int32_t kcap;
    uint32_t kid;
    int kon;
} wr__cdt;

static int wr__push(wr__cdt *S, int32_t x) {
    if (S->nstk == S->capstk) {
        int32_t nc = S->capstk ? 2 * S->capstk : 256;
        int32_t *p = (int32_t *)wr_realloc_array(S->stk, (size_t)nc, sizeof(int32_t));
        if (!p) return 0;
        S->stk = p;
        S->capstk = nc;
    }
    S->stk[S->nstk++] = x;
    return 1;
}

/* growable int32 vector used for queues and lists */
typedef struct wr__ivec {
    int32_t *a;
    int32_t n, cap;
} wr__ivec;
static int wr__ivec_push(wr__ivec *v, int32_t x) {
    if (v->n == v->cap) {
        int32_t nc = v->cap ? 2 * v->cap : 64;
        int32_t *p = (int32_t *)wr_realloc_array(v->a, (size_t)nc, sizeof(int32_t));
        if (!p) return 0;
        v->a = p;
        v->cap = nc;
    }
    v->a[v->n++] = x;
    return 1;
}

static int wr__reserve_tris(wr__cdt *S, int32_t extra) {
    if (S->nt + extra > S->capt) {
        int64_t want = (int64_t)S->capt + S->capt / 2 + extra + 64;
        int32_t nc;
        int32_t *tv, *tn;
        unsigned char *tf;
        if (want > INT32_MAX / 3) want = INT32_MAX / 3;
        if (S->nt + (int64_t)extra > want) return 0;
        nc = (int32_t)want;
        tv = (int32_t *)wr_realloc_array(S->tv, (size_t)nc * 3, sizeof(int32_t));
        if (!tv) return 0;
        S->tv = tv;
        tn = (int32_t *)wr_realloc_array(S->tn, (size_t)nc * 3, sizeof(int32_t));
        if (!tn) return 0;
        S->tn = tn;
        tf = (unsigned char *)wr_realloc_array(S->tf, (size_t)nc, 1);
        if (!tf) return 0;
        S->tf = tf;
        if (S->cm) {
            int32_t *cm = (int32_t *)wr_realloc_array(S->cm, (size_t)nc * 3, sizeof(int32_t));
            if (!cm) return 0;
            S->cm = cm;
        }
        if (S->treg) {
            int32_t *tr = (int32_t *)wr_realloc_array(S->treg, (size_t)nc, sizeof(int32_t));
            if (!tr) return 0;
            S->treg = tr;
        }
        S->capt = nc;
    }
    return 1;
}

static int wr__ensure_cm(wr__cdt *S) {
    int32_t i;
    if (S->cm) return 1;
    S->cm = (int32_t *)wr_alloc_array((size_t)S->capt * 3, sizeof(int32_t));
    if (!S->cm) return 0;
    for (i = 0; i < 3 * S->capt; ++i) S->cm[i] = -1;
    return 1;
}

static int wr__reserve_verts(wr__cdt *S, int32_t extra) {
    if (S->nv + extra > S->capv) {
        int64_t want = (int64_t)S->capv + S->capv / 2 + extra + 16;
        int32_t nc;
        double *xy;
        int32_t *a;
        if (want > INT32_MAX / 4) want = INT32_MAX / 4;
        if (S->nv + (int64_t)extra > want) return 0;
        nc = (int32_t)want;
        xy = (double *)wr_realloc_array(S->xy, (size_t)nc * 2, sizeof(double));
        if (!xy) return 0;
        S->xy = xy;
        a = (int32_t *)wr_realloc_array(S->vtri, (size_t)nc, sizeof(int32_t));
        if (!a) return 0;
        S->vtri = a;
        a = (int32_t *)wr_realloc_array(S->vseg, (size_t)nc, sizeof(int32_t));
        if (!a) return 0;
        S->vseg = a;
        if (S->na > 0) {
            double *at = (double *)wr_realloc_array(S->attr, (size_t)nc * (size_t)S->na, sizeof(double));
            if (!at) return 0;
            S->attr = at;
        }
        S->capv = nc;
    }
    return 1;
}

#define WR__P(S, v) ((S)->xy + 2 * (size_t)(v))
#define WR__GHOSTLY(S, t) ((S)->tv[3 * (t)] < 0 || (S)->tv[3 * (t) + 1] < 0 || (S)->tv[3 * (t) + 2] < 0)

static void wr__link(wr__cdt *S, int32_t h1, int32_t h2) {
    S->tn[h1] = h2;
    S->tn[h2] = h1;
}
static int32_t wr__cmark(const wr__cdt *S, int32_t h) { return S->cm ? S->cm[h] : -1; }
static void wr__setv(wr__cdt *S, int32_t t, int32_t a, int32_t b, int32_t c) {
    S->tv[3 * t] = a;
    S->tv[3 * t + 1] = b;
    S->tv[3 * t + 2] = c;
    if (!S->track_vtri) return;
    if (a >= 0) S->vtri[a] = t;
    if (b >= 0) S->vtri[b] = t;
    if (c >= 0) S->vtri[c] = t;
}

/* Attributes of a new vertex q: linear along x-y at fraction f (a split point or a junction), or
 * the affine interpolation over triangle (a, b, c) at q's position (Triangle's rule for a
 * circumcenter: extrapolated when q lies outside that triangle). */
static void wr__attr_lerp(wr__cdt *S, int32_t q, int32_t x, int32_t y, double f) {
    int32_t i, na = S->na;
    for (i = 0; i < na; ++i)
        S->attr[(size_t)q * na + i] = S->attr[(size_t)x * na + i] + f * (S->attr[(size_t)y * na + i] - S->attr[(size_t)x * na + i]);
}
static void wr__attr_bary(wr__cdt *S, int32_t q, int32_t a, int32_t b, int32_t c) {
    const double *pa = S->xy + 2 * (size_t)a, *pb = S->xy + 2 * (size_t)b, *pc = S->xy + 2 * (size_t)c,
                 *pq = S->xy + 2 * (size_t)q;
    double bx = pb[0] - pa[0], by = pb[1] - pa[1], cx = pc[0] - pa[0], cy = pc[1] - pa[1];
    double qx = pq[0] - pa[0], qy = pq[1] - pa[1], D = bx * cy - by * cx, xi, eta;
    int32_t i, na = S->na;
    if (na == 0 || D == 0.0) return;
    xi = (qx * cy - qy * cx) / D;
    eta = (bx * qy - by * qx) / D;
    for (i = 0; i < na; ++i) {
        double va = S->attr[(size_t)a * na + i];
        S->attr[(size_t)q * na + i] =
            va + xi * (S->attr[(size_t)b * na + i] - va) + eta * (S->attr[(size_t)c * na + i] - va);
    }
}

/* Is point p in conflict with triangle u: strictly inside its circumcircle, or for a ghost strictly
 * beyond its hull edge (the circle through a hull edge and infinity is that half-plane). */
static int wr__conflict(const wr__cdt *S, int32_t u, const double *p) {
    const int32_t *v = S->tv + 3 * u;
    int g;
    if (v[0] >= 0 && v[1] >= 0 && v[2] >= 0) return wr__incircle_in(WR__P(S, v[0]), WR__P(S, v[1]), WR__P(S, v[2]), p) > 0.0;
    g = v[0] < 0 ? 0 : v[1] < 0 ? 1 : 2;
    return wr__orient2d_in(WR__P(S, v[wr__n1[g]]), WR__P(S, v[wr__n2[g]]), p) > 0.0;
}

/* Flip the edge half-edge he = (t, k) across to its twin: (a,b,c)+(d,c,b) -> (a,b,d)+(d,c,a). a ends
 * at corner 0 of t and corner 2 of u. */
static void wr__flip(wr__cdt *S, int32_t he, int32_t *to, int32_t *uo) {
    int32_t t = he / 3, k = he % 3, tw = S->tn[he], u = tw / 3, j = tw % 3;
    int32_t a = S->tv[he], b = S->tv[3 * t + wr__n1[k]], c = S->tv[3 * t + wr__n2[k]], d = S->tv[tw];
    int32_t Nca = S->tn[3 * t + wr__n1[k]], Nab = S->tn[3 * t + wr__n2[k]];
    int32_t Nbd = S->tn[3 * u + wr__n1[j]], Ndc = S->tn[3 * u + wr__n2[j]];
    wr__setv(S, t, a, b, d);
    wr__setv(S, u, d, c, a);
    if (S->cm) {
        int32_t Mca = S->cm[3 * t + wr__n1[k]], Mab = S->cm[3 * t + wr__n2[k]];
        int32_t Mbd = S->cm[3 * u + wr__n1[j]], Mdc = S->cm[3 * u + wr__n2[j]];
        S->cm[3 * t] = Mbd;
        S->cm[3 * t + 1] = -1;
        S->cm[3 * t + 2] = Mab;
        S->cm[3 * u] = Mca;
        S->cm[3 * u + 1] = -1;
        S->cm[3 * u + 2] = Mdc;
    }
    wr__link(S, 3 * t, Nbd);
    wr__link(S, 3 * t + 1, 3 * u + 1);
    wr__link(S, 3 * t + 2, Nab);
    wr__link(S, 3 * u, Nca);
    wr__link(S, 3 * u + 2, Ndc);
    *to = t;
    *uo = u;
}

/* Lawson: the stack holds half-edges whose corner is the new vertex p; flip while p is in conflict
 * with the triangle across (never across a constrained edge). */
static void wr__legalize(wr__cdt *S, int32_t p) {
    const double *pp = WR__P(S, p);
    while (S->nstk) {
        int32_t he = S->stk[--S->nstk], t, u;
        if (S->cm && S->cm[he] != -1) continue;
        /* he's corner is the real vertex p, so its triangle is a ghost exactly when the edge joins a
         * hull vertex to infinity. Flipping it would fill the notch at that hull vertex with a new
         * real triangle and bury its two hull edges. During refinement the boundary is fixed (its
         * edges are constraints): a split point rounded a few ulps outside the hull must not
         * enlarge the domain (fuzzer findings cdt_needle_hull_not_delaunay, cdt_tiny_edge_refine_cubic:
         * the buried hull edges were non-Delaunay and the new hull edge unconstrained). */
        if (S->fixed_boundary && WR__GHOSTLY(S, he / 3)) continue;
        u = S->tn[he] / 3;
        if (S->kon && u < S->kcap && S->ktag[u] >> 1 == S->kid ? !(S->ktag[u] & 1u) : !wr__conflict(S, u, pp)) continue;
        wr__flip(S, he, &t, &u);
        S->stk[S->nstk++] = 3 * t; /* room: two pushes replace one pop, reserved by callers */
        S->stk[S->nstk++] = 3 * u + 2;
        if (S->nstk + 4 > S->capstk) {
            int32_t nc = 2 * S->capstk;
            int32_t *q = (int32_t *)wr_realloc_array(S->stk, (size_t)nc, sizeof(int32_t));
            if (!q) { /* out of memory mid-legalization: the mesh stays valid, only less Delaunay */
                S->nstk = 0;
                return;
            }
            S->stk = q;
            S->capstk = nc;
        }
    }
}

/* Split triangle t at new vertex p (strictly inside t, or strictly beyond a ghost's hull edge). */
static int wr__split_tri(wr__cdt *S, int32_t t, int32_t p) {
    int32_t a, b, c, Na, Nb, Nc, Ma, Mb, Mc, t1, t2;
    if (!wr__reserve_tris(S, 2)) return 0;
    a = S->tv[3 * t];
    b = S->tv[3 * t + 1];
    c = S->tv[3 * t + 2];
    Na = S->tn[3 * t];
    Nb = S->tn[3 * t + 1];
    Nc = S->tn[3 * t + 2];
    Ma = wr__cmark(S, 3 * t);
    Mb = wr__cmark(S, 3 * t + 1);
    Mc = wr__cmark(S, 3 * t + 2);
    t1 = S->nt++;
    t2 = S->nt++;
    S->tf[t1] = S->tf[t2] = S->tf[t];
    if (S->treg) S->treg[t1] = S->treg[t2] = S->treg[t];
    wr__setv(S, t1, p, c, a);
    wr__setv(S, t2, p, a, b);
    wr__setv(S, t, p, b, c);
    wr__link(S, 3 * t, Na);
    wr__link(S, 3 * t1, Nb);
    wr__link(S, 3 * t2, Nc);
    wr__link(S, 3 * t + 1, 3 * t1 + 2);
    wr__link(S, 3 * t + 2, 3 * t2 + 1);
    wr__link(S, 3 * t1 + 1, 3 * t2 + 2);
    if (S->cm) {
        S->cm[3 * t] = Ma;
        S->cm[3 * t1] = Mb;
        S->cm[3 * t2] = Mc;
        S->cm[3 * t + 1] = S->cm[3 * t + 2] = S->cm[3 * t1 + 1] = S->cm[3 * t1 + 2] = -1;
        S->cm[3 * t2 + 1] = S->cm[3 * t2 + 2] = -1;
    }
    S->nstk = 0;
    if (S->capstk < 64 && !wr__push(S, 0)) return 0;
    S->nstk = 0;
    S->stk[S->nstk++] = 3 * t;
    S->stk[S->nstk++] = 3 * t1;
    S->stk[S->nstk++] = 3 * t2;
    wr__legalize(S, p);
    S->last = t;
    return 1;
}

/* Split the edge of half-edge he at new vertex p lying on it; a constrained edge stays constrained
 * in both halves. */
static int wr__split_edge(wr__cdt *S, int32_t he, int32_t p) {
    int32_t t, k, tw, u, j, a, b, c, d, Nab, Nca, Nbd, Ndc, Mab, Mca, Mbd, Mdc, M, T2, U2;
    if (!wr__reserve_tris(S, 2)) return 0;
    t = he / 3;
    k = he % 3;
    tw = S->tn[he];
    u = tw / 3;
    j = tw % 3;
    a = S->tv[he];
    b = S->tv[3 * t + wr__n1[k]];
    c = S->tv[3 * t + wr__n2[k]];
    d = S->tv[tw];
    Nab = S->tn[3 * t + wr__n2[k]];
    Nca = S->tn[3 * t + wr__n1[k]];
    Nbd = S->tn[3 * u + wr__n1[j]];
    Ndc = S->tn[3 * u + wr__n2[j]];
    Mab = wr__cmark(S, 3 * t + wr__n2[k]);
    Mca = wr__cmark(S, 3 * t + wr__n1[k]);
    Mbd = wr__cmark(S, 3 * u + wr__n1[j]);
    Mdc = wr__cmark(S, 3 * u + wr__n2[j]);
    M = wr__cmark(S, he);
    T2 = S->nt++;
    U2 = S->nt++;
    S->tf[T2] = S->tf[t];
    S->tf[U2] = S->tf[u];
    if (S->treg) {
        S->treg[T2] = S->treg[t];
        S->treg[U2] = S->treg[u];
    }
    wr__setv(S, T2, a, p, c);
    wr__setv(S, U2, d, p, b);
    wr__setv(S, u, d, c, p);
    wr__setv(S, t, a, b, p);
    wr__link(S, 3 * t, 3 * U2);
    wr__link(S, 3 * t + 1, 3 * T2 + 2);
    wr__link(S, 3 * t + 2, Nab);
    wr__link(S, 3 * T2, 3 * u);
    wr__link(S, 3 * T2 + 1, Nca);
    wr__link(S, 3 * u + 1, 3 * U2 + 2);
    wr__link(S, 3 * u + 2, Ndc);
    wr__link(S, 3 * U2 + 1, Nbd);
    if (S->cm) {
        S->cm[3 * t] = S->cm[3 * U2] = M;
        S->cm[3 * T2] = S->cm[3 * u] = M;
        S->cm[3 * t + 1] = S->cm[3 * T2 + 2] = -1;
        S->cm[3 * u + 1] = S->cm[3 * U2 + 2] = -1;
        S->cm[3 * t + 2] = Mab;
        S->cm[3 * T2 + 1] = Mca;
        S->cm[3 * u + 2] = Mdc;
        S->cm[3 * U2 + 1] = Mbd;
    }
    if (M != -1) S->vseg[p] = M >= 0 ? M : S->vseg[p];
    S->nstk = 0;
    if (S->capstk < 64 && !wr__push(S, 0)) return 0;
    S->nstk = 0;
    S->stk[S->nstk++] = 3 * t + 2;
    S->stk[S->nstk++] = 3 * T2 + 1;
    S->stk[S->nstk++] = 3 * u + 2;
    S->stk[S->nstk++] = 3 * U2 + 1;
    wr__legalize(S, p);
    S->last = t;
    return 1;
}

#define WR__LOC_TRI 0
#define WR__LOC_EDGE 1
#define WR__LOC_VERT 2
#define WR__LOC_BLOCKED 3
#define WR__LOC_LOST 4

/* Visibility walk from triangle `start` to point p. Returns WR__LOC_TRI (*res = triangle containing
 * p strictly, or a ghost whose hull edge p lies strictly beyond), WR__LOC_EDGE (*res = half-edge whose
 * open edge contains p), WR__LOC_VERT (*res = vertex equal to p). With `blocking`, crossing a
 * constrained edge returns WR__LOC_BLOCKED (*res = that half-edge, seen from the near side). The
 * starting edge is chosen pseudo-randomly (stochastic walk), so walking cannot cycle forever;
 * WR__LOC_LOST after max_steps is a safety net only. */
static int wr__locate(wr__cdt *S, const double *p, int32_t start, int blocking, int64_t max_steps, int32_t *res) {
    int32_t t = start, came = -1;
    int64_t steps;
    for (steps = 0; steps < max_steps; ++steps) {
        const int32_t *v = S->tv + 3 * t;
        if (v[0] < 0 || v[1] < 0 || v[2] < 0) {
            int g = v[0] < 0 ? 0 : v[1] < 0 ? 1 : 2;
            int32_t x = v[wr__n1[g]], y = v[wr__n2[g]];
            const double *px = WR__P(S, x), *py = WR__P(S, y);
            double o = wr__orient2d_in(px, py, p);
            if (o > 0.0) {
                *res = t;
                return WR__LOC_TRI;
            }
            if (o < 0.0) {
                if (blocking && wr__cmark(S, 3 * t + g) != -1) {
                    *res = S->tn[3 * t + g];
                    return WR__LOC_BLOCKED;
                }
                came = S->tn[3 * t + g];
                t = came / 3;
                continue;
            }
            if (p[0] == px[0] && p[1] == px[1]) {
                *res = x;
                return WR__LOC_VERT;
            }
            if (p[0] == py[0] && p[1] == py[1]) {
                *res = y;
                return WR__LOC_VERT;
            }
            {
                double dx = py[0] - px[0], dy = py[1] - px[1];
                double sx = (p[0] - px[0]) * dx + (p[1] - px[1]) * dy; /* > 0: past x toward y */
                double sy = (p[0] - py[0]) * dx + (p[1] - py[1]) * dy; /* > 0: past y */
                if (sx > 0.0 && sy < 0.0) {
                    *res = 3 * t + g;
                    return WR__LOC_EDGE;
                }
                came = -1;
                t = S->tn[3 * t + (sy >= 0.0 ? wr__n1[g] : wr__n2[g])] / 3;
            }
            continue;
        } else {
            double o[3];
            int i, k0, nz = 0, zk = -1, moved = 0;
            S->walk_rng = S->walk_rng * 1664525u + 1013904223u;
            k0 = (int)((S->walk_rng >> 16) % 3u);
            for (i = 0; i < 3; ++i) {
                int k = (k0 + i) % 3;
                int32_t he = 3 * t + k;
                if (S->tn[he] == came) {
                    o[k] = 1.0;
                    continue;
                }
                o[k] = wr__orient2d_in(WR__P(S, v[wr__n1[k]]), WR__P(S, v[wr__n2[k]]), p);
                if (o[k] < 0.0) {
                    if (blocking && wr__cmark(S, he) != -1) {
                        *res = he;
                        return WR__LOC_BLOCKED;
                    }
                    came = he;
                    t = S->tn[he] / 3;
                    moved = 1;
                    break;
                }
            }
            if (moved) continue;
            for (i = 0; i < 3; ++i)
                if (o[i] == 0.0) {
                    ++nz;
                    zk = i;
                }
            if (nz == 0) {
                *res = t;
                return WR__LOC_TRI;
            }
            if (nz == 1) {
                *res = 3 * t + zk;
                return WR__LOC_EDGE;
            }
            for (i = 0; i < 3; ++i)
                if (o[i] != 0.0) {
                    *res = v[i];
                    return WR__LOC_VERT;
                }
            *res = t; /* three zeros: impossible for a CCW triangle */
            return WR__LOC_LOST;
        }
    }
    *res = t;
    return WR__LOC_LOST;
}

/* Insert vertex p (coordinates already in xy) starting the walk at `start`. *vout = p, or the
 * existing vertex p coincides with. Returns 0 on out-of-memory or a lost walk. */
static int wr__insert(wr__cdt *S, int32_t p, int32_t start, int32_t *vout) {
    int32_t r;
    int loc = wr__locate(S, WR__P(S, p), start, 0, (int64_t)4 * S->nt + 64, &r);
    if (loc == WR__LOC_VERT) {
        *vout = r;
        return 1;
    }
    *vout = p;
    if (loc == WR__LOC_TRI) return wr__split_tri(S, r, p);
    if (loc == WR__LOC_EDGE) return wr__split_edge(S, r, p);
    return 0;
}

/* The half-edge u -> v, or -1. Rotates around u through its full star. */
static int32_t wr__find_edge(const wr__cdt *S, int32_t u, int32_t v) {
    int32_t t0 = S->vtri[u], t = t0, guard = 0;
    if (t0 < 0) return -1;
    do {
        const int32_t *tv = S->tv + 3 * t;
        int i = tv[0] == u ? 0 : tv[1] == u ? 1 : 2;
        if (tv[wr__n1[i]] == v) return 3 * t + wr__n2[i];
        t = S->tn[3 * t + wr__n1[i]] / 3;
    } while (t != t0 && ++guard < 1 << 24);
    return -1;
}

/* ---- insertion order: BRIO rounds (Amenta–Choi–Rote), each round in Hilbert-curve order ----
 * A point joins the last round with probability 1/2, the one before with 1/4, ... (the randomness
 * that bounds the expected work); within a round points follow a Hilbert curve on a grid of about
 * 4n..16n cells (short walks). One radix sort on (round, curve index) does both. */
/* Hilbert-curve index of cell (x, y) on a 2^levels grid, most significant level first. The frame
 * of the remaining levels is tracked as a state (swap, flip) instead of rewriting x and y. One level:
 * state and the cell's bits (bx, by) give the quadrant digit and the next state. */
static uint32_t wr__hilbert_step(uint32_t *sw, uint32_t *fl, uint32_t bx, uint32_t by) {
    uint32_t tx = ((*sw ? by : bx) ^ *fl), ty = ((*sw ? bx : by) ^ *fl), z = ty ^ 1u;
    *fl ^= z & tx; /* lower-left/right quadrants turn the frame */
    *sw ^= z;
    return (3u * tx) ^ ty; /* quadrant digit in curve order */
}
/* The same machine two levels per step: tab[16·state + 4·(2 x bits) + (2 y bits)] holds the two
 * digits (bits 2..5) and the next state (bits 0..1), state = 2·swap + flip. Built per call (64
 * entries), it halves the key cost, which was ~4% of a 1e6-point triangulation. */
static void wr__hilbert_table(unsigned char *tab) {
    uint32_t st, xb, yb;
    for (st = 0; st < 4; ++st)
        for (xb = 0; xb < 4; ++xb)
            for (yb = 0; yb < 4; ++yb) {
                uint32_t sw = st >> 1, fl = st & 1u, d;
                d = wr__hilbert_step(&sw, &fl, xb >> 1, yb >> 1) << 2;
                d |= wr__hilbert_step(&sw, &fl, xb & 1u, yb & 1u);
                tab[16 * st + 4 * xb + yb] = (unsigned char)((d << 2) | (sw << 1) | fl);
            }
}
static uint32_t wr__hilbert_key(const unsigned char *tab, uint32_t x, uint32_t y, int levels) {
    uint32_t d = 0, st = 0;
    int l = levels;
    if (l & 1) { /* odd level count: the top level alone */
        uint32_t sw = 0, fl = 0;
        --l;
        d = wr__hilbert_step(&sw, &fl, (x >> l) & 1u, (y >> l) & 1u);
        st = (sw << 1) | fl;
    }
    while (l > 0) {
        uint32_t e;
        l -= 2;
        e = tab[16 * st + 4 * ((x >> l) & 3u) + ((y >> l) & 3u)];
        d = (d << 4) | (e >> 2);
        st = e & 3u;
    }
    return d;
}

/* Stable LSD radix sort of idx[0..n) by key[i] (parallel arrays), `bits` significant bits. */
static void wr__radix_sort(uint32_t *key, int32_t *idx, uint32_t *tkey, int32_t *tidx, int32_t n, int bits) {
    int sh;
    for (sh = 0; sh < bits; sh += 8) {
        int32_t cnt[257], i;
        uint32_t *sk;
        int32_t *si;
        memset(cnt, 0, sizeof cnt);
        for (i = 0; i < n; ++i) ++cnt[((key[i] >> sh) & 255u) + 1];
        for (i = 0; i < 256; ++i) cnt[i + 1] += cnt[i];
        for (i = 0; i < n; ++i) {
            int32_t at = cnt[(key[i] >> sh) & 255u]++;
            tkey[at] = key[i];
            tidx[at] = idx[i];
        }
        sk = key; /* swap buffers */
        key = tkey;
        tkey = sk;
        si = idx;
        idx = tidx;
        tidx = si;
    }
    if (((bits + 7) / 8) % 2 == 1) { /* odd pass count: result sits in the scratch arrays */
        memcpy(tkey, key, sizeof(uint32_t) * (size_t)n);
        memcpy(tidx, idx, sizeof(int32_t) * (size_t)n);
    }
}

/* key[i] := Hilbert index of point ids[i] (NULL: i) on a 2^levels grid over the points' bounding box;
 * order[i] := that point. */
static void wr__hilbert_keys(const double *xy, const int32_t *ids, int32_t n, int levels, uint32_t *key, int32_t *order) {
    uint32_t side = 1u << levels;
    int32_t i;
    double lo[2] = {HUGE_VAL, HUGE_VAL}, hi[2] = {-HUGE_VAL, -HUGE_VAL}, sc[2], lim = (double)(side - 1);
    unsigned char htab[64];
    wr__hilbert_table(htab);
    for (i = 0; i < n; ++i) {
        const double *p = xy + 2 * (size_t)(ids ? ids[i] : i);
        if (p[0] < lo[0]) lo[0] = p[0];
        if (p[1] < lo[1]) lo[1] = p[1];
        if (p[0] > hi[0]) hi[0] = p[0];
        if (p[1] > hi[1]) hi[1] = p[1];
    }
    for (i = 0; i < 2; ++i) sc[i] = hi[i] > lo[i] ? lim / (hi[i] - lo[i]) : 0.0;
    for (i = 0; i < n; ++i) {
        const double *p = xy + 2 * (size_t)(ids ? ids[i] : i);
        double fx = (p[0] - lo[0]) * sc[0], fy = (p[1] - lo[1]) * sc[1];
        uint32_t qx = (uint32_t)(fx < 0.0 ? 0.0 : fx > lim ? lim : fx);
        uint32_t qy = (uint32_t)(fy < 0.0 ? 0.0 : fy > lim ? lim : fy);
        key[i] = wr__hilbert_key(htab, qx, qy, levels);
        order[i] = ids ? ids[i] : i;
    }
}

/* Grid levels for n points: the smallest with 4n cells or more, in [4, max_levels]. */
static int wr__hilbert_levels(int32_t n, int max_levels) {
    int levels = 4;
    while (levels < max_levels && ((int64_t)1 << (2 * levels)) < 4 * (int64_t)n) ++levels;
    return levels;
}

/* order[0..n) := BRIO order of the points listed in ids. */
static int wr__brio(const double *xy, const int32_t *ids, int32_t n, wr_rng *rng, int32_t *order) {
    uint32_t *key, *tkey;
    int32_t *tidx, i, nr = 0;
    int levels = wr__hilbert_levels(n, 14);
    if (n <= 0) return 1;
    key = (uint32_t *)wr_alloc_array((size_t)n, sizeof(uint32_t));
    tkey = (uint32_t *)wr_alloc_array((size_t)n, sizeof(uint32_t));
    tidx = (int32_t *)wr_alloc_array((size_t)n, sizeof(int32_t));
    if (!key || !tkey || !tidx) {
        wr_free(key);
        wr_free(tkey);
        wr_free(tidx);
        return 0;
    }
    while (nr < 15 && (n >> (nr + 1)) >= 4096) ++nr; /* rounds 0..nr; the first holds >= ~4096 */
    wr__hilbert_keys(xy, ids, n, levels, key, order);
    for (i = 0; i < n; ++i) {
        uint64_t u = wr_rng_u64(rng);
        int32_t tz = 0, round;
        while (tz < nr && !(u & 1u)) { /* geometric: P(tz = j) = 2^-(j+1) */
            u >>= 1;
            ++tz;
        }
        round = nr - tz;
        key[i] |= (uint32_t)round << (2 * levels);
    }
    wr__radix_sort(key, order, tkey, tidx, n, 2 * levels + 4);
    wr_free(key);
    wr_free(tkey);
    wr_free(tidx);
    return 1;
}

WRDEF wr_status wr_cdt_hilbert_order(const double *xy, const int32_t *ids, int32_t n, int32_t *order, wr_diag *diag) {
    uint32_t *key, *tkey;
    int32_t *tidx;
    int levels = wr__hilbert_levels(n, 16), ok;
    if (n < 0 || (n > 0 && (!xy || !order)))
        return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "wr_cdt_hilbert_order: n < 0 or NULL arrays");
    if (n == 0) return WR_OK;
    key = (uint32_t *)wr_alloc_array((size_t)n, sizeof(uint32_t));
    tkey = (uint32_t *)wr_alloc_array((size_t)n, sizeof(uint32_t));
    tidx = (int32_t *)wr_alloc_array((size_t)n, sizeof(int32_t));
    ok = key && tkey && tidx;
    if (ok) {
        wr__hilbert_keys(xy, ids, n, levels, key, order);
        wr__radix_sort(key, order, tkey, tidx, n, 2 * levels);
    }
    wr_free(key);
    wr_free(tkey);
    wr_free(tidx);
    return ok ? WR_OK : wr_fail(diag, WR_ERR_NOMEM, -1, "wr_cdt_hilbert_order: out of memory (%d points)", (int)n);
}

/* merge points closer than tol (greedy, input order) with a hash grid of cell size tol. */
static int wr__merge_close(const double *xy, int32_t n, double tol, int32_t *rep) {
    int32_t *head, *next, i, nb = 1;
    size_t hb;
    while (nb < 2 * n && nb < (1 << 28)) nb *= 2;
    hb = (size_t)nb;
    head = (int32_t *)wr_alloc_array(hb, sizeof(int32_t));
    next = (int32_t *)wr_alloc_array((size_t)n, sizeof(int32_t));
    if (!head || !next) {
        wr_free(head);
        wr_free(next);
        return 0;
    }
    for (i = 0; i < nb; ++i) head[i] = -1;
    for (i = 0; i < n; ++i) {
        /* clamped so the integer conversion below stays defined for any finite ratio */
        double cx = fmax(-4e18, fmin(4e18, floor(xy[2 * i] / tol)));
        double cy = fmax(-4e18, fmin(4e18, floor(xy[2 * i + 1] / tol)));
        int dx, dy, found = -1;
        rep[i] = i;
        for (dx = -1; dx <= 1 && found < 0; ++dx)
            for (dy = -1; dy <= 1 && found < 0; ++dy) {
                uint64_t h = ((uint64_t)(int64_t)(cx + dx) * 73856093u) ^ ((uint64_t)(int64_t)(cy + dy) * 19349663u);
                int32_t j;
                for (j = head[h & (hb - 1)]; j >= 0; j = next[j]) {
                    double ex = xy[2 * j] - xy[2 * i], ey = xy[2 * j + 1] - xy[2 * i + 1];
                    if (ex * ex + ey * ey < tol * tol) {
                        found = j;
                        break;
                    }
                }
            }
        if (found >= 0) {
            rep[i] = found;
            next[i] = -1;
        } else {
            uint64_t h = ((uint64_t)(int64_t)cx * 73856093u) ^ ((uint64_t)(int64_t)cy * 19349663u);
            next[i] = head[h & (hb - 1)];
            head[h & (hb - 1)] = i;
        }
    }
    wr_free(head);
    wr_free(next);
    return 1;
}

/* The first triangle (i0, i1, i2 CCW) and its three ghosts. */
static void wr__init_tri(wr__cdt *S, int32_t i0, int32_t i1, int32_t i2) {
    int32_t v[3], k;
    v[0] = i0;
    v[1] = i1;
    v[2] = i2;
    S->nt = 4;
    memset(S->tf, 0, 4);
    wr__setv(S, 0, v[0], v[1], v[2]);
    for (k = 0; k < 3; ++k) {
        int32_t g = 1 + k;
        wr__setv(S, g, v[wr__n2[k]], v[wr__n1[k]], WR__INF);
        wr__link(S, 3 * 0 + k, 3 * g + 2);
    }
    for (k = 0; k < 3; ++k) wr__link(S, 3 * (1 + k) + 0, 3 * (1 + wr__n2[k]) + 1);
    S->last = 0;
}

/* ---- constraint recovery ---- */
typedef struct wr__segctx {
    wr__ivec pieces; /* triples (a, b, segment) still to recover */
    wr__ivec cross;  /* queue of vertex pairs: edges crossing the current piece */
    wr__ivec fresh;  /* vertex pairs: edges made by flips, to re-check for the CDT property */
    int split;       /* desc.split_intersections */
    int32_t n_steiner;
    const int32_t *seg;    /* input segments (input point ids), for the exact junction tests */
    const int32_t *in2int; /* input point -> internal vertex */
} wr__segctx;

static void wr__mark_both(wr__cdt *S, int32_t he, int32_t s) {
    if (S->cm[he] == -1) S->cm[he] = s; /* overlapping collinear segments keep the first id */
    if (S->cm[S->tn[he]] == -1) S->cm[S->tn[he]] = s;
}

static double wr__dot3(const double *a, const double *b, const double *c) { /* (b-a)·(c-a) */
    return (b[0] - a[0]) * (c[0] - a[0]) + (b[1] - a[1]) * (c[1] - a[1]);
}

/* Lawson flips over the vertex pairs in C->fresh until every unconstrained one is locally Delaunay. */
static int wr__restore_delaunay(wr__cdt *S, wr__ivec *fresh) {
    while (fresh->n >= 2) {
        int32_t y = fresh->a[--fresh->n], x = fresh->a[--fresh->n], he, t, u, p, d;
        const int32_t *v;
        he = wr__find_edge(S, x, y);
        if (he < 0 || S->cm[he] != -1) continue;
        t = he / 3;
        u = S->tn[he] / 3;
        if (WR__GHOSTLY(S, t) || WR__GHOSTLY(S, u)) continue;
        v = S->tv + 3 * t;
        p = S->tv[he];
        d = S->tv[S->tn[he]];
        if (wr__incircle_in(WR__P(S, v[0]), WR__P(S, v[1]), WR__P(S, v[2]), WR__P(S, d)) <= 0.0) continue;
        wr__flip(S, he, &t, &u);
        if (!wr__ivec_push(fresh, x) || !wr__ivec_push(fresh, d) || !wr__ivec_push(fresh, d) ||
            !wr__ivec_push(fresh, y) || !wr__ivec_push(fresh, y) || !wr__ivec_push(fresh, p) ||
            !wr__ivec_push(fresh, p) || !wr__ivec_push(fresh, x))
            return 0;
    }
    return 1;
}

static int wr__push3(wr__ivec *v, int32_t a, int32_t b, int32_t c) {
    return wr__ivec_push(v, a) && wr__ivec_push(v, b) && wr__ivec_push(v, c);
}

/* A computed crossing point within this many units of its coordinates' magnitude (L-inf) of an end
 * vertex of either crossing piece is that vertex. The point is a + t(b - a) with t = oa/(oa - ob)
 * from two orientations: a few rounding errors of 2^-53 relative to the coordinates, so 64·2^-53
 * (7.1e-15) covers them with margin while staying far below any feature the predicates resolve
 * as distinct in practice. (Fuzzer finding cdt_crossing_chain_split: junctions 1e-16..1e-15 from a
 * segment's end vertex made that segment's chain overshoot its end.) */
#define WR__CROSS_SNAP (64.0 * WR_PRED_EPS)

/* x lies exactly on segment p-q strictly between its ends (exact orientation; for collinear points
 * the sign of (p-x)·(q-x) is exact: both terms are <= 0, each a correctly rounded product). */
static int wr__strictly_on(const double *p, const double *q, const double *x) {
    return wr__orient2d_in(p, q, x) == 0.0 && wr__dot3(x, p, q) < 0.0;
}

/* Input segment o lies on input segment s's line (exact orientation of its input end points):
 * collinear overlapping segments share their common pieces by contract (see segment_id). */
static int wr__same_line(const wr__cdt *S, const wr__segctx *C, int32_t s, int32_t o) {
    const double *p, *q;
    if (s < 0 || o < 0 || !C->seg) return 0;
    p = WR__P(S, C->in2int[C->seg[2 * s]]);
    q = WR__P(S, C->in2int[C->seg[2 * s + 1]]);
    return wr__orient2d_in(p, q, WR__P(S, C->in2int[C->seg[2 * o]])) == 0.0 &&
           wr__orient2d_in(p, q, WR__P(S, C->in2int[C->seg[2 * o + 1]])) == 0.0;
}

/* u-v is an edge constrained by an input segment other than s and not on its line. */
static int wr__owned_by_other(const wr__cdt *S, const wr__segctx *C, int32_t u, int32_t v, int32_t s) {
    int32_t he = wr__find_edge(S, u, v), o;
    if (he < 0 || S->cm[he] == -1 || S->cm[he] == s) return 0;
    o = S->cm[he];
    return !wr__same_line(S, C, s, o);
}

/* Mark the existing edge u-v (half-edge he) as a piece of segment s. An edge that already is a piece
 * of a segment off s's line means the two segments could not be kept apart in double precision:
 * they meet at an angle below its resolution (fuzzer finding cdt_hairline_segments_share_piece: 4.5e-14
 * rad at a shared end) and their crossings with a third segment rounded to the same junctions, so
 * one piece would have to belong to both — which the result cannot represent (one id per piece).
 * That input is refused with a clear error rather than returned with a broken chain. */
static wr_status wr__claim(wr__cdt *S, const wr__segctx *C, int32_t he, int32_t u, int32_t v, int32_t s,
                           int32_t sid, wr_diag *diag) {
    int32_t o = S->cm[he];
    if (o != -1 && o != s && s >= 0 && o >= 0 && !wr__same_line(S, C, s, o)) {
        const double *pu = WR__P(S, u), *pv = WR__P(S, v);
        return wr_fail(diag, WR_ERR_GEOMETRY, sid,
                       "segments %d and %d cannot be kept apart in double precision: after splitting at their "
                       "crossings both run through the piece (%.17g, %.17g)-(%.17g, %.17g) (they meet at an "
                       "angle below its resolution)",
                       (int)(o < s ? o : s), (int)(o < s ? s : o), pu[0], pu[1], pv[0], pv[1]);
    }
    wr__mark_both(S, he, s);
    return WR_OK;
}

/* The piece a-b of segment s crosses the constrained edge xr-yl of segment s2 (strictly, by the
 * walk's predicates). Before a floating crossing point is computed, the junction is looked for among
 * the existing vertices: *v gets that vertex (or -1) and *on_s says whether it splits the piece a-b
 * (v is xr or yl) or the crossed edge (v is a or b).
 * 1. Exact degeneracies of the input segments (exact orientation): an end of s2 that lies strictly
 *    inside input segment s is the only common point of the two segments (they are not collinear:
 *    s2's other end is off s, or they would not cross), so when that end is xr or yl the junction is
 *    it; likewise an end of s strictly inside s2 when it is a or b. The pieces' own end points may be
 *    rounded junctions slightly off their segment's line, which is how a piece can cross an edge at
 *    an end vertex that its input segment passes exactly through.
 * 2. Otherwise the crossing point a + tt(b - a) is computed (*ppx, *ppy; only in this case) and
 *    snaps to an end vertex of either piece within WR__CROSS_SNAP of it, relative to the size of
 *    the point's own possible error (below).
 * Either way the vertex must project strictly inside the piece it splits, so a chain never runs
 * past an end and back. */
static void wr__cross_vertex(const wr__cdt *S, const wr__segctx *C, int32_t s, int32_t s2, int32_t a, int32_t b,
                             int32_t xr, int32_t yl, double tt, double *ppx, double *ppy, int32_t *v, int *on_s) {
    const double *pa = WR__P(S, a), *pb = WR__P(S, b), *px_ = WR__P(S, xr), *py_ = WR__P(S, yl);
    int32_t e[4], c[4];
    double scale = 0.0, best = 0.0, px, py;
    int k;
    *v = -1;
    *on_s = 0;
    e[0] = e[1] = e[2] = e[3] = -1; /* (recovery only meets input segment ids; hull marks come later) */
    if (s >= 0 && s2 >= 0) {
        e[0] = C->in2int[C->seg[2 * s]];
        e[1] = C->in2int[C->seg[2 * s + 1]];
        e[2] = C->in2int[C->seg[2 * s2]];
        e[3] = C->in2int[C->seg[2 * s2 + 1]];
    }
    for (k = 2; k < 4 && e[k] >= 0; ++k) /* an end of s2 inside s, at the crossed edge */
        if ((e[k] == xr || e[k] == yl) && wr__strictly_on(WR__P(S, e[0]), WR__P(S, e[1]), WR__P(S, e[k])) &&
            wr__dot3(WR__P(S, e[k]), pa, pb) < 0.0) {
            *v = e[k];
            *on_s = 1;
            return;
        }
    for (k = 0; k < 2 && e[k] >= 0; ++k) /* an end of s inside s2, at the current piece */
        if ((e[k] == a || e[k] == b) && wr__strictly_on(WR__P(S, e[2]), WR__P(S, e[3]), WR__P(S, e[k])) &&
            wr__dot3(WR__P(S, e[k]), px_, py_) < 0.0) {
            *v = e[k];
            *on_s = 0;
            return;
        }
    px = *ppx = pa[0] + tt * (pb[0] - pa[0]);
    py = *ppy = pa[1] + tt * (pb[1] - pa[1]);
    c[0] = a;
    c[1] = b;
    c[2] = xr;
    c[3] = yl;
    /* What the computed point may be off by: the arithmetic, a few ulps of |p| and |p - a| (the
     * orientations are accurate to a few ulps), and the rounding of the pieces' end points that are
     * themselves computed junctions (input points are exact). The magnitude of a far input end
     * point does not enter (fuzzer finding cdt_crossing_near_tiny_feature: a crossing 5e-20 from an
     * input point at 1e-19 snapped onto it because the pieces reached coordinates ~1). */
    scale = fabs(px) > fabs(py) ? fabs(px) : fabs(py);
    if (fabs(px - pa[0]) > scale) scale = fabs(px - pa[0]);
    if (fabs(py - pa[1]) > scale) scale = fabs(py - pa[1]);
    for (k = 0; k < 4; ++k) {
        const double *q = WR__P(S, c[k]);
        double m = fabs(q[0]) > fabs(q[1]) ? fabs(q[0]) : fabs(q[1]);
        if (c[k] >= S->n_input && m > scale) scale = m;
    }
    for (k = 0; k < 4; ++k) {
        const double *q = WR__P(S, c[k]);
        double dx = fabs(px - q[0]), dy = fabs(py - q[1]), dist = dx > dy ? dx : dy;
        if (dist > WR__CROSS_SNAP * scale || (*v >= 0 && dist >= best)) continue;
        /* A snap must not make the split piece's half an edge another segment already owns: two
         * segments meeting at a hair-thin angle (fuzzer finding cdt_chain_after_crossing_fix: 1e-6
         * rad at a shared end) cross a third one 4e-15 apart, and snapping the second crossing onto
         * the first junction made both chains run through one edge, which carries one id. The
         * computed point is a distinct vertex then. */
        if (k < 2 ? wr__owned_by_other(S, C, xr, c[k], s2) || wr__owned_by_other(S, C, c[k], yl, s2)
                  : wr__owned_by_other(S, C, a, c[k], s) || wr__owned_by_other(S, C, c[k], b, s))
            continue;
        if (k < 2 ? wr__dot3(q, px_, py_) < 0.0 : wr__dot3(q, pa, pb) < 0.0) {
            *v = c[k];
            *on_s = k >= 2;
            best = dist;
        }
    }
}

/* One piece a -> b of segment s being recovered (sid: the input segment, for messages), and where
 * the walk along it is: the crossed half-edge he with its right and left vertices xr, yl. */
typedef struct wr__rcpiece {
    int32_t a, b, s, sid;
    int32_t he, xr, yl;
} wr__rcpiece;

/* How the piece leaves a's star: *how = 1 through the wedge whose far edge it crosses (P->he, xr,
 * yl set), 2 along a star edge to a vertex lying on it (that edge claimed, the rest pushed as a new
 * piece), 0 when no wedge of the star faces b. */
static wr_status wr__rc_leave_star(wr__cdt *S, wr__segctx *C, wr__rcpiece *P, int *how, wr_diag *diag) {
    const double *pa = WR__P(S, P->a), *pb = WR__P(S, P->b);
    int32_t t0, t, i;
    *how = 0;
    t0 = t = S->vtri[P->a];
    do {
        const int32_t *v = S->tv + 3 * t;
        int32_t x, y;
        i = v[0] == P->a ? 0 : v[1] == P->a ? 1 : 2;
        x = v[wr__n1[i]];
        y = v[wr__n2[i]];
        if (x >= 0 && y >= 0) {
            double ox = wr__orient2d_in(pa, pb, WR__P(S, x)), oy = wr__orient2d_in(pa, pb, WR__P(S, y));
            int32_t on = -1, hon = -1;
            if (ox == 0.0 && wr__dot3(pa, WR__P(S, x), pb) > 0.0)
                on = x, hon = 3 * t + wr__n2[i];
            else if (oy == 0.0 && wr__dot3(pa, WR__P(S, y), pb) > 0.0)
                on = y, hon = 3 * t + wr__n1[i];
            if (on >= 0) {
                wr_status cs = wr__claim(S, C, hon, P->a, on, P->s, P->sid, diag);
                if (cs != WR_OK) return cs;
                if (!wr__push3(&C->pieces, on, P->b, P->s)) return wr_fail(diag, WR_ERR_NOMEM, P->sid, "out of memory");
                *how = 2;
                return WR_OK;
            }
            if (ox < 0.0 && oy > 0.0) {
                P->he = 3 * t + i;
                P->xr = x;
                P->yl = y;
                *how = 1;
                return WR_OK;
            }
        }
        t = S->tn[3 * t + wr__n1[i]] / 3;
    } while (t != t0);
    return WR_OK;
}

/* The walk met the constrained edge P->he of another segment s2: the two cross. Split at the
 * junction -- an existing vertex within snapping distance (wr__cross_vertex) or a new vertex -- and
 * push the pieces of both to recover. Needs split_intersections; without it this is an error. */
static wr_status wr__rc_cross_constraint(wr__cdt *S, wr__segctx *C, const wr__rcpiece *P, wr_diag *diag) {
    const int32_t he = P->he, xr = P->xr, yl = P->yl, a = P->a, b = P->b, s = P->s, sid = P->sid, s2 = S->cm[he];
    const double *pa = WR__P(S, a), *pb = WR__P(S, b);
    double oa, ob, tt, px = 0.0, py = 0.0;
    int32_t q, vq;
    int on_s;
    if (!C->split)
        return wr_fail(diag, WR_ERR_GEOMETRY, sid,
                       "segments %d and %d cross (self-intersecting boundary); set split_intersections to split them",
                       sid, s2);
    oa = wr_orient2d_value(WR__P(S, xr), WR__P(S, yl), pa);
    ob = wr_orient2d_value(WR__P(S, xr), WR__P(S, yl), pb);
    tt = oa / (oa - ob); /* oa, ob have strictly opposite signs here */
    wr__cross_vertex(S, C, s, s2, a, b, xr, yl, tt, &px, &py, &vq, &on_s);
    if (vq >= 0 && on_s) { /* the junction is an end of the crossed edge: split the piece */
        if (!wr__push3(&C->pieces, a, vq, s) || !wr__push3(&C->pieces, vq, b, s))
            return wr_fail(diag, WR_ERR_NOMEM, sid, "out of memory");
        return WR_OK;
    }
    if (vq >= 0) { /* the junction is an end of the piece: split the crossed edge there */
        /* The edge is no longer a constraint: make it locally Delaunay now (a constrained
         * edge need not be, and if the next walk stops at another crossing first, nothing
         * else would look at it). */
        S->cm[he] = S->cm[S->tn[he]] = -1;
        C->fresh.n = 0;
        if (!wr__ivec_push(&C->fresh, xr) || !wr__ivec_push(&C->fresh, yl) || !wr__restore_delaunay(S, &C->fresh))
            return wr_fail(diag, WR_ERR_NOMEM, sid, "out of memory");
        if (!wr__push3(&C->pieces, xr, vq, s2) || !wr__push3(&C->pieces, vq, yl, s2) || !wr__push3(&C->pieces, a, b, s))
            return wr_fail(diag, WR_ERR_NOMEM, sid, "out of memory");
        return WR_OK;
    }
    if (S->nv >= S->max_vertices)
        return wr_fail(diag, WR_ERR_BUDGET, sid, "vertex budget %d reached while splitting crossing segments",
                       S->max_vertices);
    if (!wr__reserve_verts(S, 1)) return wr_fail(diag, WR_ERR_NOMEM, sid, "out of memory");
    pa = WR__P(S, a); /* xy may have moved */
    pb = WR__P(S, b);
    q = S->nv++;
    S->xy[2 * q] = px;
    S->xy[2 * q + 1] = py;
    S->vtri[q] = -1;
    S->vseg[q] = -3 - sid; /* a junction of two segments: an apex for concentric shells */
    if (S->na > 0) {
        double ex = pb[0] - pa[0], ey = pb[1] - pa[1], l2 = ex * ex + ey * ey;
        wr__attr_lerp(S, q, a, b, l2 > 0.0 ? ((px - pa[0]) * ex + (py - pa[1]) * ey) / l2 : 0.5);
    }
    S->cm[he] = S->cm[S->tn[he]] = -1;
    if (!wr__insert(S, q, he / 3, &vq)) return wr_fail(diag, WR_ERR_NOMEM, sid, "out of memory");
    if (vq != q)
        S->nv--;
    else
        C->n_steiner++;
    if (!wr__push3(&C->pieces, xr, vq, s2) || !wr__push3(&C->pieces, vq, yl, s2) || !wr__push3(&C->pieces, a, vq, s) ||
        !wr__push3(&C->pieces, vq, b, s))
        return wr_fail(diag, WR_ERR_NOMEM, sid, "out of memory");
    return WR_OK;
}

/* Walks from a's wedge along the piece, collecting the crossed edges as (right, left) vertex pairs
 * in C->cross. *bend is where the walk ended: b; a vertex d lying on the piece (the rest d -> b
 * pushed, recovered later); or -1 when it met a constrained edge (the split's pieces pushed). */
static wr_status wr__rc_walk(wr__cdt *S, wr__segctx *C, wr__rcpiece *P, int32_t *bend, wr_diag *diag) {
    const double *pa = WR__P(S, P->a), *pb = WR__P(S, P->b);
    *bend = P->b;
    C->cross.n = 0;
    for (;;) {
        int32_t tw, u, j, d;
        double o;
        if (S->cm[P->he] != -1) { /* the segment crosses a constrained edge */
            *bend = -1;
            return wr__rc_cross_constraint(S, C, P, diag);
        }
        if (!wr__ivec_push(&C->cross, P->xr) || !wr__ivec_push(&C->cross, P->yl))
            return wr_fail(diag, WR_ERR_NOMEM, P->sid, "out of memory");
        tw = S->tn[P->he];
        u = tw / 3;
        j = tw % 3;
        d = S->tv[tw];
        if (d == P->b) return WR_OK;
        /* The segment joins two vertices of a convex triangulation, so with exact predicates the
         * walk stays inside the hull; reaching the vertex at infinity means the predicates were
         * wrong (overflow), and its coordinates must not be read. */
        if (d < 0)
            return wr_fail(diag, WR_ERR_GEOMETRY, P->sid, "segment %d: the walk along it left the triangulation", P->sid);
        o = wr__orient2d_in(pa, pb, WR__P(S, d));
        if (o == 0.0) { /* d lies on the segment: recover a-d now, d-b later */
            *bend = d;
            if (!wr__push3(&C->pieces, d, P->b, P->s)) return wr_fail(diag, WR_ERR_NOMEM, P->sid, "out of memory");
            return WR_OK;
        }
        if (o < 0.0) {
            P->he = 3 * u + wr__n2[j];
            P->xr = d;
        } else {
            P->he = 3 * u + wr__n1[j];
            P->yl = d;
        }
    }
}

/* Flips the crossed edges of C->cross away until a-bend is an edge (Sloan 1993: an edge whose quad
 * is convex is flipped; one still crossing goes back in the queue), marks it as segment s and
 * restores the Delaunay property around the new edges by Lawson flips. */
static wr_status wr__rc_flip_away(wr__cdt *S, wr__segctx *C, int32_t a, int32_t bend, int32_t s, int32_t sid,
                                  wr_diag *diag) {
    const double *pa = WR__P(S, a), *pb = WR__P(S, bend);
    int32_t head = 0, he;
    int64_t iter, cap = (int64_t)64 * (C->cross.n + 2) * (C->cross.n + 2) + 4096;
    C->fresh.n = 0;
    for (iter = 0; head < C->cross.n; ++iter) {
        int32_t ex = C->cross.a[head], ey = C->cross.a[head + 1], p, q;
        double o1, o2;
        head += 2;
        if (iter > cap) return wr_fail(diag, WR_ERR_GEOMETRY, sid, "segment %d: edge recovery did not finish", sid);
        if (head > 4096 && head > C->cross.n / 2) {
            memmove(C->cross.a, C->cross.a + head, sizeof(int32_t) * (size_t)(C->cross.n - head));
            C->cross.n -= head;
            head = 0;
        }
        he = wr__find_edge(S, ex, ey);
        if (he < 0) return wr_fail(diag, WR_ERR_GEOMETRY, sid, "segment %d: lost a crossing edge", sid);
        p = S->tv[he];
        q = S->tv[S->tn[he]];
        o1 = wr__orient2d_in(WR__P(S, p), WR__P(S, q), WR__P(S, ex));
        o2 = wr__orient2d_in(WR__P(S, p), WR__P(S, q), WR__P(S, ey));
        if ((o1 > 0.0 && o2 < 0.0) || (o1 < 0.0 && o2 > 0.0)) {
            int32_t t1, t2;
            double op, oq;
            wr__flip(S, he, &t1, &t2);
            op = wr__orient2d_in(pa, pb, WR__P(S, p));
            oq = wr__orient2d_in(pa, pb, WR__P(S, q));
            if ((op > 0.0 && oq < 0.0) || (op < 0.0 && oq > 0.0)) {
                if (!wr__ivec_push(&C->cross, p) || !wr__ivec_push(&C->cross, q))
                    return wr_fail(diag, WR_ERR_NOMEM, sid, "out of memory");
            } else if (!wr__ivec_push(&C->fresh, p) || !wr__ivec_push(&C->fresh, q)) {
                return wr_fail(diag, WR_ERR_NOMEM, sid, "out of memory");
            }
        } else if (!wr__ivec_push(&C->cross, ex) || !wr__ivec_push(&C->cross, ey)) {
            return wr_fail(diag, WR_ERR_NOMEM, sid, "out of memory");
        }
    }
    he = wr__find_edge(S, a, bend);
    if (he < 0) return wr_fail(diag, WR_ERR_GEOMETRY, sid, "segment %d: recovery failed", sid);
    wr__mark_both(S, he, s);
    if (!wr__restore_delaunay(S, &C->fresh)) return wr_fail(diag, WR_ERR_NOMEM, sid, "out of memory");
    return WR_OK;
}

/* Make segment (a0, b0) a chain of constrained edges: split it at vertices lying exactly on it,
 * collect the edges it crosses, flip them away (Sloan 1993: a convex quad's diagonal can always be
 * flipped, and some crossing edge always has a convex quad), then restore the CDT by Lawson flips.
 * The pieces still to recover are a stack; splitting (at vertices on the segment, or where it
 * crosses another segment) pushes the parts. */
static wr_status wr__recover(wr__cdt *S, wr__segctx *C, int32_t a0, int32_t b0, int32_t sid, wr_diag *diag) {
    C->pieces.n = 0;
    if (!wr__push3(&C->pieces, a0, b0, sid)) return wr_fail(diag, WR_ERR_NOMEM, sid, "out of memory");
    while (C->pieces.n >= 3) {
        wr__rcpiece P;
        int32_t he, bend;
        int how;
        wr_status st;
        P.s = C->pieces.a[--C->pieces.n];
        P.b = C->pieces.a[--C->pieces.n];
        P.a = C->pieces.a[--C->pieces.n];
        P.sid = sid;
        if (P.a == P.b) continue;
        he = wr__find_edge(S, P.a, P.b);
        if (he >= 0) { /* already an edge: claim it for s */
            if ((st = wr__claim(S, C, he, P.a, P.b, P.s, sid, diag)) != WR_OK) return st;
            continue;
        }
        if ((st = wr__rc_leave_star(S, C, &P, &how, diag)) != WR_OK) return st;
        if (how == 2) continue;
        if (how == 0)
            return wr_fail(diag, WR_ERR_GEOMETRY, sid, "segment %d: no triangle around vertex %d faces vertex %d", sid, P.a,
                           P.b);
        if ((st = wr__rc_walk(S, C, &P, &bend, diag)) != WR_OK) return st;
        if (bend < 0) continue;
        if ((st = wr__rc_flip_away(S, C, P.a, bend, P.s, sid, diag)) != WR_OK) return st;
    }
    return WR_OK;
}

/* ---- carving: flood fill across unconstrained edges ---- */
static int wr__flood(wr__cdt *S, int32_t seed, int64_t *removed) {
    S->nstk = 0;
    if (S->tf[seed] & WR__F_OUT) return 1;
    S->tf[seed] |= WR__F_OUT;
    ++*removed;
    if (!wr__push(S, seed)) return 0;
    while (S->nstk) {
        int32_t t = S->stk[--S->nstk], k;
        for (k = 0; k < 3; ++k) {
            int32_t he = 3 * t + k, u = S->tn[he] / 3;
            if (wr__cmark(S, he) != -1 || (S->tf[u] & WR__F_OUT) || WR__GHOSTLY(S, u)) continue;
            S->tf[u] |= WR__F_OUT;
            ++*removed;
            if (!wr__push(S, u)) return 0;
        }
    }
    return 1;
}

/* ---- Delaunay refinement (Ruppert 1995; Shewchuk 2002) ---- */
/* A queued bad triangle: its corners (to tell whether it still exists), its priority bucket (the
 * shortest edge, see wr__bad_key) and an arrival number (first in, first out within a bucket). */
typedef struct wr__bad {
    int32_t t, a, b, c, key;
    int64_t seq;
} wr__bad;
typedef struct wr__badheap {
    wr__bad *h;
    int32_t n, cap;
    int64_t seq;
} wr__badheap;

typedef struct wr__ref {
    double sin2;      /* sin²(min angle); a triangle is bad when sin² of its smallest angle is below */
    double max_area;  /* 0: none */
    double off;       /* off-center distance from the shortest edge's midpoint, in edge lengths (0: none) */
    double lens_c2;   /* cos²(2θ): diametral-lens encroachment (apex angle >= 180° - 2θ); 0: circle */
    int nobisect;     /* 1: hull/exterior subsegments are never split; 2: no subsegment is */
    double tiny;      /* smallest nonzero |coordinate| a Steiner point may have (see wr__coord_ok) */
    const int32_t *seg; /* segments in internal vertex ids (for the small-angle rule): the n_seg_in
                         * input segments, then the hull edges when the hull bounds the domain */
    int32_t n_seg_in;
    const double *region_area; /* per region (S->treg): maximum area, <= 0 none; may be NULL */
    wr_cdt_unsuitable_fn unsuitable; /* user test, may be NULL */
    void *user;
    wr__ivec segq;      /* vertex pairs of possibly encroached subsegments */
    wr__badheap badq;   /* possibly bad triangles, smallest shortest edge first */
    wr__ivec cav;       /* cavity scratch */
    wr__ivec slot;      /* per triangle slot: queue and give-up records (see wr__slot) */
    int32_t n_steiner, n_left;
    int64_t n_tries;
} wr__ref;

static inline int wr__is_live(const wr__cdt *S, int32_t t) { return !WR__GHOSTLY(S, t) && !(S->tf[t] & WR__F_OUT); }

/* The predicates are exact only while no product underflows (nonzero |coordinates| >= 1e-50, or as
 * small as the input's own). Refinement toward a sharp corner or a tiny feature halves coordinates
 * without end; once they reach ~1e-78 the incircle terms (|d|^4) underflow and a flip or split made
 * on a wrong sign leaves a zero-area triangle or a non-Delaunay edge (fuzzer findings). A Steiner
 * point below that floor is therefore not inserted: the triangle or subsegment stays as it is. */
static int wr__coord_ok(const wr__ref *R, const double *p) {
    double ax = fabs(p[0]), ay = fabs(p[1]);
    return (ax == 0.0 || ax >= R->tiny) && (ay == 0.0 || ay >= R->tiny);
}

/* Relative precision floor of refinement: an edge shorter than this times the largest |coordinate|
 * of its end points is at the scale of rounding (2^-36 is 2^16 ulps). A Steiner point computed for
 * a triangle (or subsegment) at that scale carries a rounding error of a sizeable fraction of the
 * triangle itself — a circumcenter of a 1e-25-wide sliver at y = 0.25 rounds onto the sliver's
 * base — so inserting it does not improve anything and, repeated, makes new slivers without end
 * (fuzzer finding cdt_sliver_cascade: exponential growth to the vertex budget, ~n^2.5 time).
 * Such triangles are left alone like the input's small angles, such subsegments are not split.
 * Cloth panels in metres need features above ~1e-11 of their coordinates' size: far above. */
#define WR__REFINE_REL_FLOOR 1.4551915228366852e-11 /* 2^-36 */
static int wr__below_floor(const double *p, const double *q, double len2) {
    double m = fmax(fmax(fabs(p[0]), fabs(p[1])), fmax(fabs(q[0]), fabs(q[1]))) * WR__REFINE_REL_FLOOR;
    return len2 < m * m;
}

/* input segment a Steiner vertex lies on (junctions of crossing segments are stored as -3 - id) */
static int32_t wr__seg_of(const wr__cdt *S, int32_t v) {
    int32_t s = S->vseg[v];
    return s >= 0 ? s : s <= -3 ? -3 - s : -1;
}
static int wr__on_seg(const wr__cdt *S, const wr__ref *R, int32_t v, int32_t s) {
    return wr__seg_of(S, v) == s || R->seg[2 * s] == v || R->seg[2 * s + 1] == v;
}

/* Do input segments s1, s2 meet (shared end point or crossing) at an angle below 60°? Then a
 * skinny triangle between them is the input's own small angle and is left alone. */
static int wr__segs_meet_sharply(const wr__cdt *S, const wr__ref *R, int32_t s1, int32_t s2) {
    const int32_t *A = R->seg + 2 * s1, *B = R->seg + 2 * s2;
    const double *a0 = WR__P(S, A[0]), *a1 = WR__P(S, A[1]), *b0 = WR__P(S, B[0]), *b1 = WR__P(S, B[1]);
    double ux = a1[0] - a0[0], uy = a1[1] - a0[1], vx = b1[0] - b0[0], vy = b1[1] - b0[1];
    double c = ux * vx + uy * vy, nn = (ux * ux + uy * uy) * (vx * vx + vy * vy);
    int meet = A[0] == B[0] || A[0] == B[1] || A[1] == B[0] || A[1] == B[1];
    if (!meet) {
        double o1 = wr__orient2d_in(a0, a1, b0), o2 = wr__orient2d_in(a0, a1, b1), o3 = wr__orient2d_in(b0, b1, a0),
               o4 = wr__orient2d_in(b0, b1, a1);
        meet = ((o1 > 0 && o2 < 0) || (o1 < 0 && o2 > 0)) && ((o3 > 0 && o4 < 0) || (o3 < 0 && o4 > 0));
        if (!meet) return 0;
        return c * c > 0.25 * nn; /* crossing lines: the acute angle between them */
    }
    /* shared end point z: angle between the directions away from z */
    if (A[0] == B[1] || A[1] == B[0]) c = -c;
    return c > 0.0 && c * c > 0.25 * nn;
}

/* Bad: larger than an area bound (max_area, the region's, the user's test), or smallest angle below
 * the bound — except when the shortest edge joins two Steiner points on different segments meeting
 * at a small angle (the small angle is the input's own and splitting there would never end), and
 * rounding-scale triangles. *key: priority bucket of the shortest edge (see wr__bad_key). */
static int32_t wr__bad_key(double len2) { /* buckets of a factor sqrt(2) in squared length */
    int ex;
    double mant;
    uint64_t bits;
    memcpy(&bits, &len2, sizeof bits);
    if (len2 > 0.0 && (bits >> 52) - 1u < 0x7feu) /* normal: frexp's exponent and mantissa from the bits */
        return 2 * ((int)(bits >> 52) - 1022) + ((bits & 0xfffffffffffffull) >= 0x6a09e667f3bcdull);
    mant = frexp(len2, &ex);
    return 2 * ex + (mant >= 0.70710678118654752);
}
static int wr__is_bad_v(const wr__cdt *S, const wr__ref *R, const int32_t *v, int32_t reg, int32_t *key) {
    const double *p0 = WR__P(S, v[0]), *p1 = WR__P(S, v[1]), *p2 = WR__P(S, v[2]), *P3[3];
    double e[3], a2, l1, l2;
    int k, m = 0;
    P3[0] = p0;
    P3[1] = p1;
    P3[2] = p2;
    e[0] = (p1[0] - p2[0]) * (p1[0] - p2[0]) + (p1[1] - p2[1]) * (p1[1] - p2[1]);
    e[1] = (p2[0] - p0[0]) * (p2[0] - p0[0]) + (p2[1] - p0[1]) * (p2[1] - p0[1]);
    e[2] = (p0[0] - p1[0]) * (p0[0] - p1[0]) + (p0[1] - p1[1]) * (p0[1] - p1[1]);
    for (k = 1; k < 3; ++k)
        if (e[k] < e[m]) m = k;
    a2 = wr_orient2d_fast(p0, p1, p2); /* twice the area */
    if (R->max_area > 0.0 && 0.5 * a2 > R->max_area) goto bad;
    if (R->region_area && reg >= 0 && R->region_area[reg] > 0.0 && 0.5 * a2 > R->region_area[reg]) goto bad;
    if (R->unsuitable && R->unsuitable(p0, p1, p2, 0.5 * a2, R->user)) goto bad;
    if (R->sin2 <= 0.0) return 0;
    l1 = e[wr__n1[m]];
    l2 = e[wr__n2[m]];
    if (!(a2 * a2 < R->sin2 * l1 * l2)) return 0;
    if (wr__below_floor(P3[wr__n1[m]], P3[wr__n2[m]], e[m])) return 0; /* rounding scale: see the floor */
    if (R->seg) {
        int32_t u = v[wr__n1[m]], w = v[wr__n2[m]], su = wr__seg_of(S, u), sw = wr__seg_of(S, w);
        if (su >= 0 && sw >= 0 && su != sw && wr__segs_meet_sharply(S, R, su, sw)) return 0;
        /* a sliver whose three corners lie on one segment comes from split points rounded off the
         * segment's line: no interior point can improve it */
        if (su >= 0 && wr__on_seg(S, R, v[0], su) && wr__on_seg(S, R, v[1], su) && wr__on_seg(S, R, v[2], su))
            return 0;
    }
bad: /* the key only for a bad triangle (key NULL: not wanted, the clean-up's tests) */
    if (key) *key = wr__bad_key(e[m]);
    return 1;
}

static int wr__is_bad(const wr__cdt *S, const wr__ref *R, int32_t t, int32_t *key) {
    return wr__is_bad_v(S, R, S->tv + 3 * t, S->treg ? S->treg[t] : -1, key);
}

/* The bad-triangle queue is a binary heap on (bucket, arrival): the triangle with the shortest
 * shortest edge first (Shewchuk's Triangle orders its queue so: small features are resolved before
 * the large triangles around them are split, whose Steiner points would otherwise land where a
 * later small-feature point makes them redundant), first in first out within a bucket. */
static int wr__bad_before(const wr__bad *x, const wr__bad *y) {
    return x->key < y->key || (x->key == y->key && x->seq < y->seq);
}
static int wr__bad_push(wr__badheap *H, int32_t t, int32_t a, int32_t b, int32_t c, int32_t key) {
    wr__bad x;
    int32_t i;
    if (H->n == H->cap) {
        int32_t nc = H->cap ? 2 * H->cap : 256;
        wr__bad *p = (wr__bad *)wr_realloc_array(H->h, (size_t)nc, sizeof(wr__bad));
        if (!p) return 0;
        H->h = p;
        H->cap = nc;
    }
    x.t = t;
    x.a = a;
    x.b = b;
    x.c = c;
    x.key = key;
    x.seq = H->seq++;
    for (i = H->n++; i > 0 && wr__bad_before(&x, &H->h[(i - 1) / 2]); i = (i - 1) / 2) H->h[i] = H->h[(i - 1) / 2];
    H->h[i] = x;
    return 1;
}
static wr__bad wr__bad_pop(wr__badheap *H) {
    wr__bad top = H->h[0], x = H->h[--H->n];
    int32_t i = 0;
    for (;;) {
        int32_t c = 2 * i + 1;
        if (c >= H->n) break;
        if (c + 1 < H->n && wr__bad_before(&H->h[c + 1], &H->h[c])) ++c;
        if (!wr__bad_before(&H->h[c], &x)) break;
        H->h[i] = H->h[c];
        i = c;
    }
    if (H->n > 0) H->h[i] = x;
    return top;
}
/* Per triangle slot, two records, each keyed by the slot's vertex triple (a slot reused by another
 * triangle matches neither):
 *   [0..2] the triangle waiting in the queue: a triangle is queued once, not once per insertion
 *          near it (scan_star visits a fan vertex's whole star at every insertion beside it);
 *   [3..5] a bad triangle whose Steiner point is not finite (a sliver whose area rounds to zero):
 *          a property of the triangle alone, so it is left alone while it exists, like the input's
 *          small angles.
 * Without them every insertion beside a fan of n unfixable slivers queued all of them again and
 * walked to their Steiner points again: O(n^2) walks and queue entries (fuzzer finding
 * cdt_fan_giveup: 5 points spanning 1e-3 to 1e28, 388k queue entries and 34M exact walk steps for
 * 1,750 vertices, 9 s). Returns the record, or NULL past 2^27 triangles (not recorded: the
 * behaviour without records) or when out of memory (*oom = 1). */
#define WR__SLOT_W 6
static int32_t *wr__slot(wr__ref *R, int32_t t, int *oom) {
    if ((int64_t)WR__SLOT_W * (t + 1) > INT32_MAX / 2) return NULL;
    while (R->slot.n < WR__SLOT_W * (t + 1))
        if (!wr__ivec_push(&R->slot, -1)) {
            *oom = 1;
            return NULL;
        }
    return R->slot.a + WR__SLOT_W * t;
}
static const int32_t *wr__slot_if(const wr__ref *R, int32_t t) {
    return (int64_t)WR__SLOT_W * (t + 1) > R->slot.n ? NULL : R->slot.a + WR__SLOT_W * t;
}
static int wr__triple_is(const int32_t *l, const int32_t *v) { return l[0] == v[0] && l[1] == v[1] && l[2] == v[2]; }

static int wr__leave(const wr__cdt *S, wr__ref *R, int32_t t) {
    int oom = 0;
    int32_t *l = wr__slot(R, t, &oom);
    if (!l) return !oom;
    R->n_left++;
    memcpy(l + 3, S->tv + 3 * t, 3 * sizeof(int32_t));
    return 1;
}
static int wr__left_alone(const wr__cdt *S, const wr__ref *R, int32_t t) {
    const int32_t *l = wr__slot_if(R, t);
    return l && wr__triple_is(l + 3, S->tv + 3 * t);
}

/* Queue bad triangle t (key: wr__is_bad's) unless it is queued already. 0 out of memory. */
static int wr__queue_tri(const wr__cdt *S, wr__ref *R, int32_t t, int32_t key) {
    const int32_t *v = S->tv + 3 * t;
    int oom = 0;
    int32_t *l = wr__slot(R, t, &oom);
    if (oom) return 0;
    if (l) {
        if (wr__triple_is(l, v)) return 1;
        memcpy(l, v, 3 * sizeof(int32_t));
    }
    return wr__bad_push(&R->badq, t, v[0], v[1], v[2], key);
}
/* Queue entry bt's triangle again after a subsegment split for it, if it still exists (else the
 * entry would be stale: nothing to do). 0 out of memory. */
static int wr__requeue(const wr__cdt *S, wr__ref *R, const wr__bad *bt, int32_t key) {
    int32_t v[3];
    v[0] = bt->a;
    v[1] = bt->b;
    v[2] = bt->c;
    return !wr__triple_is(S->tv + 3 * bt->t, v) || wr__queue_tri(S, R, bt->t, key);
}
/* Entry bt left the queue: its slot may be queued again. */
static void wr__unqueue(wr__ref *R, const wr__bad *bt) {
    int32_t *l, v[3];
    if (!wr__slot_if(R, bt->t)) return;
    l = R->slot.a + WR__SLOT_W * bt->t;
    v[0] = bt->a;
    v[1] = bt->b;
    v[2] = bt->c;
    if (wr__triple_is(l, v)) l[0] = l[1] = l[2] = -1;
}

static int wr__queue_if_bad(const wr__cdt *S, wr__ref *R, int32_t t) {
    int32_t key;
    if (wr__left_alone(S, R, t) || !wr__is_bad(S, R, t, &key)) return 1;
    return wr__queue_tri(S, R, t, key);
}

/* Does vertex w encroach subsegment x-y? Ruppert: w inside its diametral circle (angle x-w-y above
 * 90°), kept for conforming Delaunay meshes. Otherwise Shewchuk's diametral lens (Shewchuk 2002,
 * "Delaunay refinement algorithms for triangular mesh generation", Sec. 3): the angle at w at least
 * 180° - 2θ for the bound θ — a vertex outside the lens cannot make a triangle on x-y worse than θ
 * at that edge, and the lens is thinner than the circle, so fewer subsegments are split (and the
 * analysis still bounds the mesh size): cos² of the angle against cos²(2θ). */
static int wr__encroaches(const wr__cdt *S, const wr__ref *R, int32_t x, int32_t y, const double *w) {
    const double *px = WR__P(S, x), *py = WR__P(S, y);
    double ax = px[0] - w[0], ay = px[1] - w[1], bx = py[0] - w[0], by = py[1] - w[1], dot = ax * bx + ay * by;
    if (!(dot < 0.0)) return 0;
    return R->lens_c2 <= 0.0 || dot * dot >= R->lens_c2 * (ax * ax + ay * ay) * (bx * bx + by * by);
}

/* After inserting vertex p: queue the bad triangles around it and the subsegments its star
 * encroaches (apex test on both sides of each constrained edge). */
static int wr__scan_star(wr__cdt *S, wr__ref *R, int32_t p) {
    int32_t t0 = S->vtri[p], t = t0, guard = 0;
    do {
        const int32_t *v = S->tv + 3 * t;
        int i = v[0] == p ? 0 : v[1] == p ? 1 : 2, k;
        if (wr__is_live(S, t)) {
            if (!wr__queue_if_bad(S, R, t)) return 0;
            for (k = 0; k < 3; ++k) {
                int32_t x = v[wr__n1[k]], y = v[wr__n2[k]];
                if (S->cm[3 * t + k] != -1 && wr__encroaches(S, R, x, y, WR__P(S, v[k])))
                    if (!wr__ivec_push(&R->segq, x) || !wr__ivec_push(&R->segq, y)) return 0;
            }
        }
        t = S->tn[3 * t + wr__n1[i]] / 3;
    } while (t != t0 && ++guard < 1 << 20);
    return 1;
}

/* May subsegment he be split? Not with nobisect 2 (no Steiner point on any segment), nor with
 * nobisect 1 when it bounds the domain (a removed or ghost triangle on one side). */
static int wr__may_split(const wr__cdt *S, const wr__ref *R, int32_t he) {
    if (R->nobisect >= 2) return 0;
    if (R->nobisect == 1) return wr__is_live(S, he / 3) && wr__is_live(S, S->tn[he] / 3);
    return 1;
}

/* Does a segment continue through input vertex (or junction) x beyond the subsegment y-x: another
 * constrained edge at x on the same line, on the other side? */
static int wr__continues(const wr__cdt *S, int32_t x, int32_t y) {
    int32_t t0 = S->vtri[x], t = t0, guard = 0;
    if (t0 < 0 || !(x < S->n_input || S->vseg[x] <= -3)) return 0;
    do {
        const int32_t *v = S->tv + 3 * t;
        int i = v[0] == x ? 0 : v[1] == x ? 1 : 2;
        int32_t w = v[wr__n1[i]];
        if (w >= 0 && w != y && S->cm[3 * t + wr__n2[i]] != -1 &&
            wr__orient2d_in(WR__P(S, x), WR__P(S, y), WR__P(S, w)) == 0.0 && wr__dot3(WR__P(S, x), WR__P(S, y), WR__P(S, w)) < 0.0)
            return 1;
        t = S->tn[3 * t + wr__n1[i]] / 3;
    } while (t != t0 && ++guard < 1 << 20);
    return 0;
}

/* Where to split subsegment he, as a fraction from its first end x toward y: the midpoint, unless an
 * end is shared with another subsegment in a triangle beside it (Triangle's test) or a segment
 * continues through it — then at the power of two nearest half its length from that end
 * (concentric shells, Ruppert 1995 / Shewchuk 2002):
 * segments meeting at a small angle are split at matching radii and stop encroaching each other. */
static double wr__split_fraction(const wr__cdt *S, int32_t he, double len) {
    int32_t t = he / 3, k = he % 3, tw = S->tn[he], u = tw / 3, j = tw % 3;
    int acute_x = 0, acute_y = 0;
    double p;
    if (wr__is_live(S, t)) {
        acute_x |= S->cm[3 * t + wr__n2[k]] != -1;
        acute_y |= S->cm[3 * t + wr__n1[k]] != -1;
    }
    if (wr__is_live(S, u)) { /* u sees the edge as y -> x */
        acute_x |= S->cm[3 * u + wr__n1[j]] != -1;
        acute_y |= S->cm[3 * u + wr__n2[j]] != -1;
    }
    if (!(acute_x || acute_y)) {
        int32_t x = S->tv[3 * t + wr__n1[k]], y = S->tv[3 * t + wr__n2[k]];
        acute_x = wr__continues(S, x, y);
        acute_y = wr__continues(S, y, x);
    }
    if (!(acute_x || acute_y) || !(len > 0.0)) return 0.5;
    p = ldexp(1.0, (int)floor(log2(0.5 * len) + 0.5)); /* nearest power of two to len/2 */
    return acute_y ? 1.0 - p / len : p / len;
}

/* Re-check the whole star of a new split point q with general flips: it is the rounded split point,
 * a few ulps off the segment's line, and the edges at q may then violate the (exact) CDT property,
 * which Lawson's test around q alone does not see. */
static int wr__restore_star(wr__cdt *S, wr__ref *R, int32_t q) {
    int32_t t0 = S->vtri[q], tt = t0, guard = 0;
    R->cav.n = 0;
    do {
        const int32_t *vv = S->tv + 3 * tt;
        int i = vv[0] == q ? 0 : vv[1] == q ? 1 : 2;
        if (vv[wr__n1[i]] >= 0 && vv[wr__n2[i]] >= 0)
            if (!wr__ivec_push(&R->cav, q) || !wr__ivec_push(&R->cav, vv[wr__n1[i]]) ||
                !wr__ivec_push(&R->cav, vv[wr__n1[i]]) || !wr__ivec_push(&R->cav, vv[wr__n2[i]]))
                return 0;
        tt = S->tn[3 * tt + wr__n1[i]] / 3;
    } while (tt != t0 && ++guard < 1 << 20);
    return wr__restore_delaunay(S, &R->cav);
}

/* Split the constrained edge he at wr__split_fraction. Returns 1 split, 0 not splittable (nobisect,
 * or the result would invert a triangle: ulp-short edge), -1 budget, -2 out of memory. */
static int wr__split_segment(wr__cdt *S, wr__ref *R, int32_t he) {
    int32_t t = he / 3, k = he % 3, tw = S->tn[he], x = S->tv[3 * t + wr__n1[k]], y = S->tv[3 * t + wr__n2[k]];
    int32_t a = S->tv[he], d = S->tv[tw], q, m = S->cm[he];
    const double *px = WR__P(S, x), *py = WR__P(S, y);
    double len = hypot(py[0] - px[0], py[1] - px[1]), f, p[2];
    if (!wr__may_split(S, R, he) || wr__below_floor(px, py, len * len)) return 0;
    f = wr__split_fraction(S, he, len);
    if (f == 0.5) {
        p[0] = 0.5 * (px[0] + py[0]);
        p[1] = 0.5 * (px[1] + py[1]);
    } else {
        p[0] = px[0] + f * (py[0] - px[0]);
        p[1] = px[1] + f * (py[1] - px[1]);
    }
    if (!wr__coord_ok(R, p)) return 0;
    if (a >= 0 && !(wr__orient2d_in(WR__P(S, a), px, p) > 0.0 && wr__orient2d_in(WR__P(S, a), p, py) > 0.0)) return 0;
    if (d >= 0 && !(wr__orient2d_in(WR__P(S, d), py, p) > 0.0 && wr__orient2d_in(WR__P(S, d), p, px) > 0.0)) return 0;
    if (S->nv >= S->max_vertices) return -1;
    if (!wr__reserve_verts(S, 1)) return -2;
    q = S->nv++;
    S->xy[2 * q] = p[0];
    S->xy[2 * q + 1] = p[1];
    S->vtri[q] = -1;
    S->vseg[q] = m >= 0 ? m : R->n_seg_in + (-2 - m); /* hull edge k: pseudo-segment n_seg_in + k */
    wr__attr_lerp(S, q, x, y, f);
    if (!wr__split_edge(S, he, q)) return -2;
    R->n_steiner++;
    if (!wr__restore_star(S, R, q)) return -2;
    /* flips may have reshaped the stars of the four vertices around q too */
    if (!wr__scan_star(S, R, q) || !wr__scan_star(S, R, x) || !wr__scan_star(S, R, y)) return -2;
    if ((a >= 0 && !wr__scan_star(S, R, a)) || (d >= 0 && !wr__scan_star(S, R, d))) return -2;
    return 1;
}

/* Is apex w of a triangle on subsegment he (segment id sg in R->seg numbering) an encroachment that
 * splitting can resolve? Not when w lies on another segment meeting sg at less than 60°: near such
 * an input angle the two segments' vertices are close because the segments are (the skinny
 * triangles between them are left alone by wr__is_bad). Concentric shells would make the vertices
 * of both pair up in exact arithmetic, but split points are rounded: a few ulps of misalignment
 * between two segments 1e-25 apart made each one's vertices encroach the other's subsegments
 * without end (fuzzer finding cdt_sliver_cascade: ~n^2.5 cost, out of memory). */
static int wr__encroach_counts(const wr__cdt *S, const wr__ref *R, int32_t sg, int32_t w) {
    int32_t sw = wr__seg_of(S, w);
    return !(sg >= 0 && sw >= 0 && sw != sg && wr__segs_meet_sharply(S, R, sg, sw));
}

static int wr__seg_encroached(const wr__cdt *S, const wr__ref *R, int32_t he) {
    int32_t t = he / 3, k = he % 3, tw = S->tn[he], x = S->tv[3 * t + wr__n1[k]], y = S->tv[3 * t + wr__n2[k]];
    int32_t m = S->cm[he], sg = m >= 0 ? m : m <= -2 ? R->n_seg_in + (-2 - m) : -1;
    if (wr__is_live(S, t) && wr__encroaches(S, R, x, y, WR__P(S, S->tv[he])) &&
        wr__encroach_counts(S, R, sg, S->tv[he]))
        return 1;
    if (wr__is_live(S, tw / 3) && wr__encroaches(S, R, x, y, WR__P(S, S->tv[tw])) &&
        wr__encroach_counts(S, R, sg, S->tv[tw]))
        return 1;
    return 0;
}

/* Steiner point of bad triangle t: its circumcenter, or Üngör's off-center (Üngör 2004, "Off-centers:
 * a new type of Steiner points for computing size-optimal quality-guaranteed Delaunay
 * triangulations") when nearer: the point on the shortest edge's perpendicular bisector at R->off
 * edge lengths from its midpoint, toward the circumcenter. At 0.5·cot(θ/2) the new triangle on the
 * shortest edge has exactly the bound θ at its apex; Triangle takes 0.95 of that (Shewchuk's
 * 0.475·cot(θ/2)), leaving a margin so that triangle is not bad again after rounding. */
static void wr__steiner_point(const wr__cdt *S, const wr__ref *R, int32_t t, int off_ok, double *c) {
    const int32_t *v = S->tv + 3 * t;
    const double *P[3];
    double bx, by, cx, cy, bb, c2, D, e[3], mx, my, dx, dy, dc, h;
    int k, m = 0;
    P[0] = WR__P(S, v[0]);
    P[1] = WR__P(S, v[1]);
    P[2] = WR__P(S, v[2]);
    bx = P[1][0] - P[0][0];
    by = P[1][1] - P[0][1];
    cx = P[2][0] - P[0][0];
    cy = P[2][1] - P[0][1];
    bb = bx * bx + by * by;
    c2 = cx * cx + cy * cy;
    D = 2.0 * (bx * cy - by * cx);
    c[0] = P[0][0] + (cy * bb - by * c2) / D;
    c[1] = P[0][1] + (bx * c2 - cx * bb) / D;
    if (!(R->off > 0.0) || !off_ok) return;
    for (k = 0; k < 3; ++k) {
        const double *p = P[wr__n1[k]], *q = P[wr__n2[k]];
        e[k] = (p[0] - q[0]) * (p[0] - q[0]) + (p[1] - q[1]) * (p[1] - q[1]);
    }
    for (k = 1; k < 3; ++k)
        if (e[k] < e[m]) m = k;
    mx = 0.5 * (P[wr__n1[m]][0] + P[wr__n2[m]][0]);
    my = 0.5 * (P[wr__n1[m]][1] + P[wr__n2[m]][1]);
    dx = c[0] - mx;
    dy = c[1] - my;
    dc = hypot(dx, dy);
    h = sqrt(e[m]) * R->off;
    if (dc > h && dc > 0.0) {
        c[0] = mx + dx * (h / dc);
        c[1] = my + dy * (h / dc);
    }
}

/* Ruppert: a new vertex cp that would encroach a subsegment is rejected and the subsegments it would
 * encroach are split instead. Collects (on S->stk, as vertex pairs) the splittable constrained edges
 * of cp's cavity (the live triangles in conflict with it, grown from tt) that cp encroaches. */
static int wr__cavity_encroached(wr__cdt *S, wr__ref *R, int32_t tt, int loc, int32_t r, const double *cp) {
    int32_t i, k;
    R->cav.n = 0;
    S->nstk = 0;
    if (S->kcap < S->nt) { /* room for every triangle's answer (without it, legalize computes its own) */
        uint32_t *kt = (uint32_t *)wr_realloc_array(S->ktag, (size_t)S->capt, sizeof(uint32_t));
        if (kt) {
            memset(kt + S->kcap, 0, sizeof(uint32_t) * (size_t)(S->capt - S->kcap));
            S->ktag = kt;
            S->kcap = S->capt;
        }
    }
    if (++S->kid >= 1u << 31) { /* the tags wrap: none is current */
        if (S->ktag) memset(S->ktag, 0, sizeof(uint32_t) * (size_t)S->kcap);
        S->kid = 1;
    }
    if (!wr__ivec_push(&R->cav, tt)) return 0;
    if (loc == WR__LOC_EDGE && S->cm[r] == -1 && wr__is_live(S, S->tn[r] / 3))
        if (!wr__ivec_push(&R->cav, S->tn[r] / 3)) return 0;
    for (i = 0; i < R->cav.n; ++i) {
        int32_t ct = R->cav.a[i];
        for (k = 0; k < 3; ++k) {
            int32_t ch = 3 * ct + k, u = S->tn[ch] / 3, x = S->tv[3 * ct + wr__n1[k]], y = S->tv[3 * ct + wr__n2[k]];
            int j, seen = 0;
            if (S->cm[ch] != -1) {
                if (!(loc == WR__LOC_EDGE && (ch == r || ch == S->tn[r])) && wr__encroaches(S, R, x, y, cp) &&
                    wr__may_split(S, R, ch))
                    if (!wr__push(S, x) || !wr__push(S, y)) return 0;
                continue;
            }
            if (!wr__is_live(S, u)) continue;
            for (j = 0; j < R->cav.n && !seen; ++j) seen = R->cav.a[j] == u;
            if (seen) continue;
            j = wr__conflict(S, u, cp);
            if (u < S->kcap) S->ktag[u] = S->kid << 1 | (uint32_t)j;
            if (!j) continue;
            if (!wr__ivec_push(&R->cav, u)) return 0;
        }
        /* A candidate's cavity is a handful of triangles in a graded mesh. Hundreds mean huge,
         * skinny circumcircles (fuzzer finding cdt_wedge_cavity_quadratic: a 1e-3-wide wedge
         * 1e26 long, where the cavity grew as n/6 and each rejected candidate cost that many
         * exact in-circle tests, ~n^2 overall). The encroachment check over the cavity is a
         * heuristic past that size anyway, so the search stops at 256; no input of the fuzz corpus
         * changes its result (timings before and after: commit b84b16d). */
        if (R->cav.n > 256) break;
    }
    return 1;
}

/* Split the subsegments listed as vertex pairs in pairs[0..np). Returns 1 when any was split, 0 when
 * none could be, -1 budget, -2 out of memory. */
static int wr__split_listed(wr__cdt *S, wr__ref *R, const int32_t *pairs, int32_t np) {
    int32_t j;
    int any = 0;
    for (j = 0; j + 1 < np; j += 2) {
        int32_t he = wr__find_edge(S, pairs[j], pairs[j + 1]);
        int rc;
        if (he < 0 || S->cm[he] == -1) continue;
        rc = wr__split_segment(S, R, he);
        if (rc < 0) return rc;
        any |= rc == 1;
    }
    return any;
}

/* Split the queued encroached subsegments until none is left. 1 ok, -1 budget, -2 out of memory. */
static int wr__drain_segq(wr__cdt *S, wr__ref *R) {
    while (R->segq.n >= 2) {
        int32_t y = R->segq.a[--R->segq.n], x = R->segq.a[--R->segq.n], he = wr__find_edge(S, x, y);
        int rc;
        if (he < 0 || S->cm[he] == -1 || !wr__seg_encroached(S, R, he)) continue;
        rc = wr__split_segment(S, R, he);
        if (rc < 0) return rc;
    }
    return 1;
}

/* Insert Steiner point cp (located: loc, r) as a free vertex interpolating attributes over bad
 * triangle (a, b, c). 1 ok, 0 not inserted, -1 budget, -2 out of memory. */
static int wr__insert_free(wr__cdt *S, wr__ref *R, int loc, int32_t r, const double *cp, const wr__bad *bt) {
    int32_t q;
    int i;
    /* checked here, not before the walk: a point outside the domain is not inserted anyway (the
     * segment it lies beyond is split instead) */
    if (!wr__coord_ok(R, cp)) return 0;
    if (S->nv >= S->max_vertices) return -1;
    if (!wr__reserve_verts(S, 1)) return -2;
    q = S->nv++;
    S->xy[2 * q] = cp[0];
    S->xy[2 * q + 1] = cp[1];
    S->vtri[q] = -1;
    S->vseg[q] = -1;
    wr__attr_bary(S, q, bt->a, bt->b, bt->c);
    S->kon = 1; /* the cavity of cp was searched just before (wr__fix_bad) */
    i = loc == WR__LOC_TRI ? wr__split_tri(S, r, q) : wr__split_edge(S, r, q);
    S->kon = 0;
    if (!i) return -2;
    R->n_steiner++;
    return wr__scan_star(S, R, q) ? 1 : -2;
}

/* One bad triangle: its Steiner point is inserted, or — when that point lies beyond a segment or
 * encroaches subsegments — those are split and the triangle is queued again. 1 ok, -1 budget,
 * -2 out of memory. */
static int wr__fix_bad(wr__cdt *S, wr__ref *R, const wr__bad *bt) {
    int32_t t = bt->t, r, tt, key, np, *pairs;
    int loc, rc;
    double cp[2];
    R->n_tries++;
    wr__unqueue(R, bt);
    if (t >= S->nt || S->tv[3 * t] != bt->a || S->tv[3 * t + 1] != bt->b || S->tv[3 * t + 2] != bt->c) return 1;
    if (!wr__is_live(S, t) || wr__left_alone(S, R, t) || !wr__is_bad(S, R, t, &key)) return 1;
    wr__steiner_point(S, R, t, 1, cp);
    /* an off-center below the coordinate floor (wr__coord_ok: between a tiny feature and the
     * boundary) falls back to the circumcenter, which lies beyond it or splits the subsegment */
    if (!wr__coord_ok(R, cp)) wr__steiner_point(S, R, t, 0, cp);
    if (!isfinite(cp[0]) || !isfinite(cp[1])) return wr__leave(S, R, t) ? 1 : -2;
    if (!wr__coord_ok(R, cp)) { /* still below the floor: split a subsegment of t whose diametral
                                 * circle holds cp (its split point lies on the segment's line) */
        int k;
        for (k = 0; k < 3; ++k) {
            int32_t he = 3 * t + k, x = S->tv[3 * t + wr__n1[k]], y = S->tv[3 * t + wr__n2[k]];
            const double *px = WR__P(S, x), *py = WR__P(S, y);
            if (S->cm[he] == -1 || !((px[0] - cp[0]) * (py[0] - cp[0]) + (px[1] - cp[1]) * (py[1] - cp[1]) < 0.0))
                continue;
            rc = wr__split_segment(S, R, he);
            if (rc < 0) return rc;
            return rc == 0 || wr__requeue(S, R, bt, key) ? 1 : -2;
        }
        return 1;
    }
    loc = wr__locate(S, cp, t, 1, (int64_t)4 * S->nt + 64, &r);
    if (loc == WR__LOC_VERT || loc == WR__LOC_LOST) return 1;
    if (loc == WR__LOC_BLOCKED) { /* the point lies beyond a segment: split that segment instead */
        rc = wr__split_segment(S, R, r);
        if (rc < 0) return rc;
        return rc == 0 || wr__requeue(S, R, bt, key) ? 1 : -2;
    }
    tt = loc == WR__LOC_EDGE ? r / 3 : r;
    if (!wr__is_live(S, tt)) return 1;
    if (!wr__cavity_encroached(S, R, tt, loc, r, cp)) return -2;
    if (S->nstk == 0) return (rc = wr__insert_free(S, R, loc, r, cp, bt)) < 0 ? rc : 1;
    np = S->nstk;
    pairs = (int32_t *)wr_alloc_array((size_t)np, sizeof(int32_t));
    if (!pairs) return -2;
    memcpy(pairs, S->stk, sizeof(int32_t) * (size_t)np);
    rc = wr__split_listed(S, R, pairs, np);
    wr_free(pairs);
    if (rc < 0) return rc;
    return rc == 0 || wr__requeue(S, R, bt, key) ? 1 : -2;
}

/* ---- Steiner-point removal and edge collapse ----
 * Delaunay refinement inserts every point for a triangle that was bad when it was queued; points
 * inserted later nearby often make an earlier one unnecessary. Two local operations on free
 * Steiner vertices (not on a segment) undo such points:
 *   removal   the vertex's star is re-triangulated by Delaunay ears (Devillers 1999, "On deletion
 *             in Delaunay triangulations": an ear whose circumcircle holds no other polygon vertex)
 *   collapse  two adjacent free vertices are replaced by one at their midpoint: the union of their
 *             stars is fanned from it and made Delaunay by Lawson flips inside the polygon.
 * Both build a wr__plan (the region's triangles, its boundary ring, the new triangles), and
 * wr__plan_valid accepts it only when it tiles the ring (counter-clockwise triangles, every ring
 * edge used once, every inner edge twice), every unconstrained edge inside (by construction) and on
 * the ring is locally Delaunay (so the whole mesh stays a CDT: Delaunay's lemma) and every new triangle meets
 * the angle and size bounds (wr__tri_ok).
 * Cost: rings of at most WR__RING_CAP vertices, O(cap^2) work per plan, each free vertex tried once
 * per pass, at most WR__REMOVE_PASSES passes: linear in the mesh size. Each accepted operation
 * lowers the vertex count and inserts nothing, so the passes end. */
#define WR__RING_CAP 24
#define WR__REMOVE_PASSES 8
typedef struct wr__plan {
    int32_t ring[WR__RING_CAP], out[WR__RING_CAP], ocm[WR__RING_CAP]; /* ring CCW; across edge i -> i+1:
                                                                        * outer half-edge, its mark */
    int32_t slot[WR__RING_CAP], tri[3 * WR__RING_CAP];                /* region triangles; new ones */
    int32_t nbr[3 * WR__RING_CAP]; /* across new corner 3i+e: the new corner 3j+f facing the same edge,
                                    * or -1 - k for ring edge k (kept as the plan is built) */
    uint32_t known_ok; /* bit i: new triangle i passed wr__tri_ok as it stands (wr__plan_valid skips it) */
    int n, ns, nt;
} wr__plan;

/* Move triangle `from` into slot `to` (overwriting it), relinking its neighbours. */
static void wr__move_tri(wr__cdt *S, int32_t from, int32_t to) {
    int k;
    if (from == to) return;
    for (k = 0; k < 3; ++k) {
        S->tv[3 * to + k] = S->tv[3 * from + k];
        S->cm[3 * to + k] = S->cm[3 * from + k];
        wr__link(S, 3 * to + k, S->tn[3 * from + k]);
        if (S->tv[3 * to + k] >= 0) S->vtri[S->tv[3 * to + k]] = to;
    }
    S->tf[to] = S->tf[from];
    if (S->treg) S->treg[to] = S->treg[from];
}

/* Move vertex `from` (the last one) into slot `to` (a removed vertex), renaming it in its star. */
static void wr__move_vert(wr__cdt *S, int32_t from, int32_t to) {
    int32_t t0 = S->vtri[from], t = t0, guard = 0;
    if (from == to) return;
    do {
        int32_t *v = S->tv + 3 * t;
        int i = v[0] == from ? 0 : v[1] == from ? 1 : 2;
        v[i] = to;
        t = S->tn[3 * t + wr__n1[i]] / 3;
    } while (t != t0 && ++guard < 1 << 20);
    S->xy[2 * to] = S->xy[2 * from];
    S->xy[2 * to + 1] = S->xy[2 * from + 1];
    S->vseg[to] = S->vseg[from];
    S->vtri[to] = t0;
    if (S->na > 0) memcpy(S->attr + (size_t)to * S->na, S->attr + (size_t)from * S->na, sizeof(double) * (size_t)S->na);
}

/* After refinement: fill the slots of removed vertices with the last live ones. */
static void wr__compact_verts(wr__cdt *S) {
    int32_t v;
    for (v = S->nv - 1; v >= S->n_input; --v)
        if (S->vtri[v] < 0) wr__move_vert(S, --S->nv, v);
}

/* May triangle (a, b, c) replace part of the mesh: at least the angle bound even where wr__is_bad
 * would excuse it (the clean-up must never lower the minimum angle), and not bad. The angle test
 * comes first: it rejects nearly every candidate (9 in 10 plans fail on a triangle's angle). */
static int wr__tri_ok(const wr__cdt *S, const wr__ref *R, const int32_t *v, int32_t reg) {
    const double *p = WR__P(S, v[0]), *q = WR__P(S, v[1]), *r = WR__P(S, v[2]);
    double a2 = wr_orient2d_fast(p, q, r), e0, e1, e2, lo;
    e0 = (q[0] - r[0]) * (q[0] - r[0]) + (q[1] - r[1]) * (q[1] - r[1]);
    e1 = (r[0] - p[0]) * (r[0] - p[0]) + (r[1] - p[1]) * (r[1] - p[1]);
    e2 = (p[0] - q[0]) * (p[0] - q[0]) + (p[1] - q[1]) * (p[1] - q[1]);
    lo = e1 < e2 ? e1 : e2;
    lo = e0 < lo ? e0 : lo; /* sin² of the smallest angle = a2² / (product of the two longer edges²) */
    if (!(a2 * a2 >= R->sin2 * (e0 * e1 * e2 / lo))) return 0;
    if (!R->max_area && !R->region_area && !R->unsuitable) {
        /* no size bound: wr__is_bad_v could only find the angle bad, by its own rounding of this test
         * (the same sums; the two longer edges by its choice of the shortest) */
        double e[3];
        int m = 0;
        e[0] = e0;
        e[1] = e1;
        e[2] = e2;
        if (e1 < e0) m = 1;
        if (e2 < e[m]) m = 2;
        if (!(a2 * a2 < R->sin2 * e[wr__n1[m]] * e[wr__n2[m]])) return 1;
    }
    return !wr__is_bad_v(S, R, v, reg, NULL);
}

/* Can triangle (a, b, c) pass wr__tri_ok's angle test, in any vertex order? The same test with the
 * bound lowered by 1e-12 (the rounding of sin² near the bound is ~1e-14 whatever the order). */
static int wr__angle_may_pass(const wr__cdt *S, const wr__ref *R, int32_t a, int32_t b, int32_t c) {
    const double *p = WR__P(S, a), *q = WR__P(S, b), *r = WR__P(S, c);
    double a2 = wr_orient2d_fast(p, q, r), e0, e1, e2, lo;
    e0 = (q[0] - r[0]) * (q[0] - r[0]) + (q[1] - r[1]) * (q[1] - r[1]);
    e1 = (r[0] - p[0]) * (r[0] - p[0]) + (r[1] - p[1]) * (r[1] - p[1]);
    e2 = (p[0] - q[0]) * (p[0] - q[0]) + (p[1] - q[1]) * (p[1] - q[1]);
    lo = e1 < e2 ? e1 : e2;
    lo = e0 < lo ? e0 : lo;
    return !(a2 * a2 < (R->sin2 - 1e-12) * (e0 * e1 * e2 / lo));
}

/* Ring position j (from 0) outward from both ends of a run of excluded positions of a ring of n:
 * fwd, back, fwd+1, back-1, ... (fwd: the first after the run, back: the last before it). An
 * incircle test of a triangle on the run meets the nearest vertices first. */
static inline int wr__ring_out(int fwd, int back, int j, int n) {
    return (j & 1) ? (back + n - j / 2) % n : (fwd + j / 2) % n;
}

/* Corner c of a new triangle faces h (a new corner, or -1 - k for ring edge k); both sides. */
static void wr__plan_nbr(wr__plan *P, int32_t c, int32_t h) {
    P->nbr[c] = h;
    if (h >= 0) P->nbr[h] = c;
}

/* See the section comment. The tiling is read from nbr (symmetric, each ring edge used once). The
 * inner edges are locally Delaunay by construction: a collapse's when its flips end; a removal's
 * because each ear's circumcircle held none of the vertices left when it was cut, so the apex across
 * its cut edge (cut later) is outside it (the exact incircle sign is the same seen from either side). */
static int wr__plan_valid(const wr__cdt *S, const wr__ref *R, const wr__plan *P, int32_t reg) {
    int i, e, open = 0;
    uint32_t used = 0;
    for (i = 0; i < P->nt; ++i) /* the same test on the same vertex triple: the same answer */
        if (!(P->known_ok >> i & 1u) && !wr__tri_ok(S, R, P->tri + 3 * i, reg)) return 0;
    for (i = 0; i < P->nt; ++i) {
        const int32_t *v = P->tri + 3 * i;
        const double *a = WR__P(S, v[0]), *b = WR__P(S, v[1]), *c = WR__P(S, v[2]);
        if (!(wr__orient2d_in(a, b, c) > 0.0)) return 0;
        for (e = 0; e < 3; ++e) {
            int32_t h = P->nbr[3 * i + e], x = v[wr__n1[e]], y = v[wr__n2[e]], d;
            if (h >= 0) { /* inner edge x -> y: the other triangle holds y -> x */
                const int32_t *o = P->tri + 3 * (h / 3);
                if (P->nbr[h] != 3 * i + e || o[wr__n1[h % 3]] != y || o[wr__n2[h % 3]] != x) return 0;
                continue;
            }
            h = -1 - h; /* ring edge h, to be used once */
            if (h >= P->n || (used >> h & 1u) || P->ring[h] != x || P->ring[(h + 1) % P->n] != y) return 0;
            used |= 1u << h;
            ++open;
            d = S->tv[P->out[h]];
            if (P->ocm[h] == -1 && d >= 0 && wr__incircle_in(a, b, c, WR__P(S, d)) > 0.0) return 0;
        }
    }
    return open == P->n;
}

/* Write the plan into the mesh: new triangles in slot[0..nt), the other slots dropped. */
static void wr__plan_apply(wr__cdt *S, wr__plan *P) {
    int i, e, j;
    unsigned char tf = S->tf[P->slot[0]];
    int32_t reg = S->treg ? S->treg[P->slot[0]] : -1;
    for (i = 0; i < P->nt; ++i) {
        int32_t t = P->slot[i];
        wr__setv(S, t, P->tri[3 * i], P->tri[3 * i + 1], P->tri[3 * i + 2]);
        S->tf[t] = tf;
        if (S->treg) S->treg[t] = reg;
        for (e = 0; e < 3; ++e) S->vtri[P->tri[3 * i + e]] = t;
    }
    for (i = 0; i < P->nt; ++i)
        for (e = 0; e < 3; ++e) {
            int32_t h = P->nbr[3 * i + e], c = 3 * P->slot[i] + e;
            if (h >= 0) {
                S->tn[c] = 3 * P->slot[h / 3] + h % 3;
                S->cm[c] = -1;
            } else {
                wr__link(S, c, P->out[-1 - h]);
                S->cm[c] = P->ocm[-1 - h];
            }
        }
    while (P->ns > P->nt) { /* drop the highest slot first: the moved last triangle is never dropped */
        int hi = P->nt;
        int32_t from;
        for (j = P->nt + 1; j < P->ns; ++j)
            if (P->slot[j] > P->slot[hi]) hi = j;
        from = --S->nt;
        wr__move_tri(S, from, P->slot[hi]);
        for (j = 0; j < P->nt; ++j)
            if (P->slot[j] == from) P->slot[j] = P->slot[hi];
        P->slot[hi] = P->slot[--P->ns];
    }
    S->last = P->slot[0];
}

/* Star of free vertex v into ring/slots (triangle i = (v, ring i, ring i+1)); 0 when too large or not
 * all live. Also the outer half-edges. */
static int wr__plan_star(const wr__cdt *S, int32_t v, wr__plan *P, int cap) {
    int32_t t0 = S->vtri[v], t = t0;
    int n = 0; /* the counts in locals: the int32_t stores below may alias P->n for the compiler */
    P->nt = 0;
    do {
        const int32_t *tv = S->tv + 3 * t;
        int i = tv[0] == v ? 0 : tv[1] == v ? 1 : 2, i1 = wr__n1[i];
        int32_t r = tv[i1];
        /* wr__is_live(S, t) with v >= 0 known: a ghost holds -1 at one of the other two corners */
        if (n == cap || r < 0 || tv[wr__n2[i]] < 0 || (S->tf[t] & WR__F_OUT)) {
            P->n = P->ns = n;
            return 0;
        }
        P->slot[n] = t;
        P->out[n] = S->tn[3 * t + i];
        P->ocm[n] = S->cm[3 * t + i];
        P->ring[n++] = r;
        t = S->tn[3 * t + i1] / 3;
    } while (t != t0);
    P->n = P->ns = n;
    return n >= 3;
}

/* Removal plan on the star in *P (from wr__plan_star, kept): ear clipping of the ring, Delaunay ears
 * first, each ear held to the bounds as it is cut (a failing plan mostly fails at its first ear);
 * lab[i] names what lies across the polygon edge idx[i] -> idx[i+1] (a ring edge or a cut ear). */
static int wr__plan_removal(const wr__cdt *S, const wr__ref *R, wr__plan *P, int32_t reg) {
    int32_t idx[WR__RING_CAP], lab[WR__RING_CAP], *t;
    int n, i, j, ears = 0;
    P->known_ok = 0;
    /* every triangulation of a polygon of four or more vertices has two ears (r_i-1, r_i, r_i+1):
     * fewer than two corners whose ear meets the angle bound, and the plan fails */
    for (i = 0; i < P->n && ears < 2 && P->n > 3; ++i)
        ears += wr__angle_may_pass(S, R, P->ring[(i + P->n - 1) % P->n], P->ring[i], P->ring[(i + 1) % P->n]);
    if (P->n > 3 && ears < 2) return 0;
    for (i = 0; i < P->n; ++i) {
        idx[i] = P->ring[i];
        lab[i] = -1 - i;
    }
    P->nt = 0;
    for (n = P->n; n > 3; --n) {
        int found = -1, prev;
        int32_t c = 3 * P->nt;
        for (i = 0; i < n && found < 0; ++i) {
            int32_t a = idx[(i + n - 1) % n], b = idx[i], cc = idx[(i + 1) % n];
            const double *pa = WR__P(S, a), *pb = WR__P(S, b), *pc = WR__P(S, cc);
            int ok = wr__orient2d_in(pa, pb, pc) > 0.0;
            wr__icfix F;
            if (ok) wr__icfix_set(&F, pa, pb, pc);
            for (j = 0; j < n - 3 && ok; ++j) /* the ear's edge a -> c is ring edge i-1 -> i+1 of n-1 */
                if (wr__incircle_fixed(&F, WR__P(S, idx[wr__ring_out((i + 2) % n, (i + n - 2) % n, j, n)])) > 0.0) ok = 0;
            if (ok) found = i;
        }
        if (found < 0) return 0;
        prev = (found + n - 1) % n;
        t = P->tri + c;
        t[0] = idx[prev];
        t[1] = idx[found];
        t[2] = idx[(found + 1) % n];
        if (!wr__tri_ok(S, R, t, reg)) return 0;
        P->known_ok |= 1u << P->nt; /* only the last triangle is left to wr__plan_valid's angle test */
        wr__plan_nbr(P, c, lab[found]);    /* corner a faces b -> c */
        wr__plan_nbr(P, c + 2, lab[prev]); /* corner c faces a -> b */
        lab[prev] = c + 1;                 /* the cut a -> c faces corner b */
        ++P->nt;
        for (j = found; j + 1 < n; ++j) {
            idx[j] = idx[j + 1];
            lab[j] = lab[j + 1];
        }
    }
    t = P->tri + 3 * P->nt;
    t[0] = idx[0];
    t[1] = idx[1];
    t[2] = idx[2];
    wr__plan_nbr(P, 3 * P->nt, lab[1]);
    wr__plan_nbr(P, 3 * P->nt + 1, lab[2]);
    wr__plan_nbr(P, 3 * P->nt + 2, lab[0]);
    ++P->nt;
    return 1;
}

/* Remove free Steiner vertex v (its star in *P) when its plan is valid; 1 removed, 0 kept. The slot
 * of v stays dead (vtri -1) until wr__compact_verts. */
static int wr__try_remove(wr__cdt *S, wr__ref *R, int32_t v, wr__plan *P) {
    int32_t reg = S->treg ? S->treg[S->vtri[v]] : -1;
    if (!wr__plan_removal(S, R, P, reg) || !wr__plan_valid(S, R, P, reg)) return 0;
    wr__plan_apply(S, P);
    S->vtri[v] = -1;
    R->n_steiner--;
    return 1;
}

/* Collapse plan for the edge u-w (both free; U: u's star) into *P: the union of the two stars,
 * fanned from u moved to the midpoint (S->xy[u] already holds it), then Lawson flips on the inner
 * edges. 1: a plan; 0: none; -1: none, decided from the merged ring and the midpoint alone (the
 * same for the edge w-u while neither star changes: see wr__cmemo). */
static int wr__plan_collapse(const wr__cdt *S, const wr__ref *R, int32_t u, int32_t w, const wr__plan *U, wr__plan *P,
                             int32_t reg) {
    wr__plan Q;
    wr__icfix F;
    int32_t *nbr = P->nbr;
    int iu, iw, i, j, e, n = 0, flips = 0, again = 1;
    P->known_ok = 0;
    if (!wr__plan_star(S, w, &Q, WR__RING_CAP / 2)) return 0;
    for (iu = 0; iu < U->n && U->ring[iu] != w; ++iu) {}
    for (iw = 0; iw < Q.n && Q.ring[iw] != u; ++iw) {}
    if (iu == U->n || iw == Q.n) return 0;
    /* ring: u's ring after w up to two before w, then w's ring from after u up to before u's next
     * (the vertex before w in u's ring is the one after u in w's) */
    for (i = 1; i + 1 < U->n; ++i) P->ring[n++] = U->ring[(iu + i) % U->n];
    for (i = 1; i + 1 < Q.n; ++i) P->ring[n++] = Q.ring[(iw + i) % Q.n];
    P->n = n;
    /* The cheap rejection first, from the ring alone: a fan triangle (u, ring i, ring i+1) whose
     * circumcircle holds no other vertex of the polygon (strictly: incircle < 0) has three strongly
     * Delaunay edges: it is in every CDT of the polygon and u, so it is never flipped and ends in the
     * plan as it is. One such that fails the bounds fails the plan, found here without building the
     * fan or flipping (9 in 10 failing plans in the bench inputs). Every test of a plan only rejects,
     * so their order does not change which plans pass. */
    for (i = 0; i < n; ++i) {
        int32_t f[3];
        const double *pa = WR__P(S, u), *pb = WR__P(S, P->ring[i]), *pc = WR__P(S, P->ring[(i + 1) % n]);
        int empty = 1;
        f[0] = u;
        f[1] = P->ring[i];
        f[2] = P->ring[(i + 1) % n];
        if (wr__tri_ok(S, R, f, reg)) { /* fan triangle i as it will be built; cleared if flipped */
            P->known_ok |= 1u << i;
            continue;
        }
        wr__icfix_set(&F, pa, pb, pc);
        for (j = 0; j < n - 2 && empty; ++j) /* nearest ring vertices first: i+2, i-1, i+3, i-2, ... */
            if (!(wr__incircle_fixed(&F, WR__P(S, P->ring[wr__ring_out((i + 2) % n, (i + n - 1) % n, j, n)])) < 0.0))
                empty = 0;
        if (empty) return -1;
    }
    /* each part is a piece of one vertex's link (no repeats): the union is a simple polygon unless
     * the parts share a vertex */
    for (i = 0; i < U->n - 2; ++i)
        for (j = U->n - 2; j < n; ++j)
            if (P->ring[i] == P->ring[j]) return -1;
    for (i = 1, n = 0; i + 1 < U->n; ++i, ++n) {
        P->out[n] = U->out[(iu + i) % U->n];
        P->ocm[n] = U->ocm[(iu + i) % U->n];
    }
    for (i = 1; i + 1 < Q.n; ++i, ++n) {
        P->out[n] = Q.out[(iw + i) % Q.n];
        P->ocm[n] = Q.ocm[(iw + i) % Q.n];
    }
    P->ns = 0;
    for (i = 0; i < U->ns; ++i) P->slot[P->ns++] = U->slot[i];
    for (i = 0; i < Q.ns; ++i)
        if (Q.slot[i] != U->slot[iu] && Q.slot[i] != U->slot[(iu + U->n - 1) % U->n]) P->slot[P->ns++] = Q.slot[i];
    for (i = 0; i < n; ++i) {
        int i1 = i + 1 < n ? i + 1 : 0;
        P->tri[3 * i] = u;
        P->tri[3 * i + 1] = P->ring[i];
        P->tri[3 * i + 2] = P->ring[i1];
        nbr[3 * i] = -1 - i; /* ring edge i */
        nbr[3 * i + 1] = 3 * i1 + 2;
        nbr[3 * i1 + 2] = 3 * i + 1;
    }
    P->nt = n;
    for (i = 0; i < n; ++i) /* u in the kernel of the polygon: the fan is a triangulation */
        if (!(wr__orient2d_in(WR__P(S, u), WR__P(S, P->ring[i]), WR__P(S, P->ring[i + 1 < n ? i + 1 : 0])) > 0.0)) return -1;
    while (again && flips < 4 * WR__RING_CAP) { /* Lawson within the polygon (ring edges stay) */
        again = 0;
        for (i = 0; i < n; ++i)
            for (e = 0; e < 3; ++e) {
                int32_t *v = P->tri + 3 * i, x, y, a, d;
                int h = nbr[3 * i + e], f, Nya, Nax, Nxd, Ndy;
                if (h < 3 * i + 3) continue; /* a ring edge, or an inner edge seen from its lower triangle */
                if (!(wr__incircle_in(WR__P(S, v[0]), WR__P(S, v[1]), WR__P(S, v[2]), WR__P(S, P->tri[h])) > 0.0))
                    continue; /* each inner edge once per sweep, from its lower triangle */
                x = v[wr__n1[e]];
                y = v[wr__n2[e]];
                a = v[e];
                /* (a, x, y) + (d, y, x) -> (a, x, d) + (d, y, a), relinking the four outer edges */
                j = h / 3;
                f = h % 3;
                d = P->tri[h];
                Nya = nbr[3 * i + wr__n1[e]];
                Nax = nbr[3 * i + wr__n2[e]];
                Nxd = nbr[3 * j + wr__n1[f]];
                Ndy = nbr[3 * j + wr__n2[f]];
                v[0] = a, v[1] = x, v[2] = d;
                P->tri[3 * j] = d, P->tri[3 * j + 1] = y, P->tri[3 * j + 2] = a;
                nbr[3 * i] = Nxd, nbr[3 * i + 1] = 3 * j + 1, nbr[3 * i + 2] = Nax;
                nbr[3 * j] = Nya, nbr[3 * j + 1] = 3 * i + 1, nbr[3 * j + 2] = Ndy;
                if (Nxd >= 0) nbr[Nxd] = 3 * i;
                if (Nax >= 0) nbr[Nax] = 3 * i + 2;
                if (Nya >= 0) nbr[Nya] = 3 * j;
                if (Ndy >= 0) nbr[Ndy] = 3 * j + 2;
                P->known_ok &= ~((1u << i) | (1u << j));
                again = 1;
                ++flips;
            }
    }
    return !again;
}
/* Does the moved vertex u encroach a subsegment on the ring? Refinement ended with none encroached
 * (where splitting could help); a collapse must not make one (nor, with conforming, break the
 * empty diametral circles). Removal cannot: it adds no vertex. */
static int wr__plan_encroaches(const wr__cdt *S, const wr__ref *R, const wr__plan *P, int32_t u) {
    int i;
    for (i = 0; i < P->n; ++i)
        if (P->ocm[i] != -1 && wr__encroaches(S, R, P->ring[i], P->ring[(i + 1) % P->n], WR__P(S, u))) return 1;
    return 0;
}

/* Try collapsing free vertex u (its star in *U) with one of its WR__COLLAPSE_TRIES nearest free
 * neighbours (nearest first: close pairs are the redundant ones; further tries cost more than they
 * find); 1 done (the plan applied in *P). */
#define WR__COLLAPSE_TRIES 2
/* Failed collapses remembered, so that a pair is not planned again while the answer cannot have
 * changed: a plan of u-w that failed from the merged ring and the midpoint alone fails for w-u too
 * (the same polygon, the same midpoint bits, the same fan triangles, the same region: u and w share
 * two triangles across an unconstrained edge) and for u-w again, until an applied plan changes the
 * star of u or w (then u or w is on its ring). now counts the applied plans; stamp[v]: the count
 * when v's star last changed; fw/ft[2v + k]: v's k-th failed partner and the count then (-1: none;
 * a try answered from the memo keeps the record it was answered from). */
typedef struct wr__cmemo {
    int32_t now, *stamp, *fw, *ft;
} wr__cmemo;
static int wr__cmemo_fails(const wr__cmemo *M, int32_t u, int32_t w) {
    int k, s;
    for (s = 0; M && s < 2; ++s) {
        int32_t a = s ? w : u, b = s ? u : w;
        for (k = 0; k < WR__COLLAPSE_TRIES; ++k)
            if (M->fw[WR__COLLAPSE_TRIES * a + k] == b && M->ft[WR__COLLAPSE_TRIES * a + k] >= M->stamp[u] &&
                M->ft[WR__COLLAPSE_TRIES * a + k] >= M->stamp[w])
                return 1;
    }
    return 0;
}
static int wr__try_collapse(wr__cdt *S, wr__ref *R, int32_t u, const wr__plan *U, wr__plan *P, wr__cmemo *M) {
    int32_t nb[WR__RING_CAP], reg = S->treg ? S->treg[S->vtri[u]] : -1;
    double keep[2], d2[WR__RING_CAP];
    int i, j, n = 0;
    keep[0] = S->xy[2 * u];
    keep[1] = S->xy[2 * u + 1];
    for (i = 0; i < U->n; ++i) { /* free neighbours by distance (insertion sort: at most 12) */
        int32_t w = U->ring[i];
        double dx = S->xy[2 * w] - keep[0], dy = S->xy[2 * w + 1] - keep[1], dd = dx * dx + dy * dy;
        if (w < S->n_input || S->vseg[w] != -1) continue;
        for (j = n++; j > 0 && d2[j - 1] > dd; --j) {
            nb[j] = nb[j - 1];
            d2[j] = d2[j - 1];
        }
        nb[j] = w;
        d2[j] = dd;
    }
    if (n > WR__COLLAPSE_TRIES) n = WR__COLLAPSE_TRIES;
    for (i = 0; i < n; ++i) {
        int32_t w = nb[i];
        int pc;
        if (wr__cmemo_fails(M, u, w)) continue;
        if (M) M->fw[WR__COLLAPSE_TRIES * u + i] = -1;
        S->xy[2 * u] = 0.5 * (keep[0] + S->xy[2 * w]);
        S->xy[2 * u + 1] = 0.5 * (keep[1] + S->xy[2 * w + 1]);
        pc = wr__plan_collapse(S, R, u, w, U, P, reg);
        if (pc < 0 && M) {
            M->fw[WR__COLLAPSE_TRIES * u + i] = w;
            M->ft[WR__COLLAPSE_TRIES * u + i] = M->now;
        }
        if (pc > 0 && !wr__plan_encroaches(S, R, P, u) && wr__plan_valid(S, R, P, reg)) {
            if (S->na > 0) wr__attr_lerp(S, u, u, w, 0.5);
            wr__plan_apply(S, P);
            S->vtri[w] = -1;
            R->n_steiner--;
            return 1;
        }
    }
    S->xy[2 * u] = keep[0];
    S->xy[2 * u + 1] = keep[1];
    return 0;
}

/* Up to WR__REMOVE_PASSES passes over the free Steiner vertices, newest first: removal, else
 * collapse with a free neighbour (both start from the vertex's star, read once). After the first
 * pass only vertices next to a change are tried again (nothing else can have become removable);
 * without memory for those marks, one pass. */
static void wr__remove_steiner(wr__cdt *S, wr__ref *R) {
    int pass, any = 1, i;
    wr__plan U, P;
    wr__cmemo memo, *M = &memo;
    unsigned char *mark = (unsigned char *)wr_alloc_array((size_t)S->nv, 1);
    if (mark) memset(mark, 1, (size_t)S->nv);
    memo.now = 0;
    memo.stamp = (int32_t *)wr_alloc_array((size_t)S->nv, sizeof(int32_t));
    memo.fw = (int32_t *)wr_alloc_array((size_t)S->nv * WR__COLLAPSE_TRIES, sizeof(int32_t));
    memo.ft = (int32_t *)wr_alloc_array((size_t)S->nv * WR__COLLAPSE_TRIES, sizeof(int32_t));
    if (memo.stamp && memo.fw && memo.ft) {
        memset(memo.stamp, 0, sizeof(int32_t) * (size_t)S->nv);
        for (i = 0; i < S->nv * WR__COLLAPSE_TRIES; ++i) memo.fw[i] = -1;
    } else {
        M = NULL; /* without memory: every plan computed */
    }
    for (pass = 0; pass < WR__REMOVE_PASSES && any && (pass == 0 || mark); ++pass) {
        int32_t v;
        any = 0;
        for (v = S->nv - 1; v >= S->n_input; --v) {
            const wr__plan *ch;
            if (S->vseg[v] != -1 || S->vtri[v] < 0 || (mark && !(mark[v] & 1))) continue;
            if (mark) mark[v] = 0;
            if (!wr__plan_star(S, v, &U, WR__RING_CAP / 2)) continue;
            if (wr__try_remove(S, R, v, &U))
                ch = &U;
            else if (wr__try_collapse(S, R, v, &U, &P, M))
                ch = &P;
            else
                continue;
            any = 1;
            if (M) { /* the stars changed: the ring's and the survivor's */
                M->stamp[v] = ++M->now;
                for (i = 0; i < ch->n; ++i) M->stamp[ch->ring[i]] = M->now;
            }
            /* a vertex's plan reads its star and the apexes across it: what may have changed for the
             * vertices of the changed region's ring and their neighbours */
            for (i = 0; mark && i < ch->n; ++i) {
                int32_t r = ch->ring[i], t0 = S->vtri[r], t = t0;
                do {
                    const int32_t *tv = S->tv + 3 * t;
                    int c = tv[0] == r ? 0 : tv[1] == r ? 1 : 2;
                    if (tv[wr__n1[c]] >= 0) mark[tv[wr__n1[c]]] |= 3;
                    t = S->tn[3 * t + wr__n1[c]] / 3;
                } while (t != t0);
                mark[r] |= 3;
            }
        }
        if (mark)
            for (v = 0; v < S->nv; ++v) mark[v] >>= 1; /* marks made in this pass count in the next */
    }
    wr_free(mark);
    wr_free(memo.stamp);
    wr_free(memo.fw);
    wr_free(memo.ft);
}

/* Delaunay refinement: encroached subsegments first, then bad triangles by priority (each may
 * encroach subsegments, which are split before the next triangle is looked at). */
static wr_status wr__refine(wr__cdt *S, wr__ref *R, wr_diag *diag) {
    int32_t t, k;
    int rc = 1;
    for (t = 0; t < S->nt; ++t) {
        const int32_t *v = S->tv + 3 * t;
        if (!wr__is_live(S, t)) continue;
        if (!wr__queue_if_bad(S, R, t)) return wr_fail(diag, WR_ERR_NOMEM, -1, "out of memory");
        for (k = 0; k < 3; ++k)
            if (S->cm[3 * t + k] != -1 && wr__encroaches(S, R, v[wr__n1[k]], v[wr__n2[k]], WR__P(S, v[k])))
                if (!wr__ivec_push(&R->segq, v[wr__n1[k]]) || !wr__ivec_push(&R->segq, v[wr__n2[k]]))
                    return wr_fail(diag, WR_ERR_NOMEM, -1, "out of memory");
    }
    while (rc > 0) {
        wr__bad bt;
        rc = wr__drain_segq(S, R);
        if (rc < 0 || R->badq.n == 0) break;
        bt = wr__bad_pop(&R->badq);
        rc = wr__fix_bad(S, R, &bt);
    }
    if (rc > 0 && R->sin2 > 0.0) wr__remove_steiner(S, R);
    wr__compact_verts(S);
    if (rc == -2) return wr_fail(diag, WR_ERR_NOMEM, -1, "out of memory");
    if (rc == -1)
        return wr_fail(diag, WR_ERR_BUDGET, -1,
                       "refinement stopped at the vertex budget of %d vertices (%d Steiner points inserted); the "
                       "mesh reached is returned; raise max_vertices or lower min_angle_deg",
                       S->max_vertices, R->n_steiner);
    return WR_OK;
}

/* ---- public entry ---- */
#define WR__DEFAULT_MIN_ANGLE 20.0 /* degrees; Triangle's -q default, inside Ruppert's proven 20.7° */
#define WR__MAX_MIN_ANGLE 34.0     /* degrees; beyond ~33.8° Delaunay refinement is known not to end */
#define WR__DEFAULT_SEED 0x5EEDC0DEull

static void wr__cdt_defaults(const wr_cdt_desc *in, wr_cdt_desc *d) {
    if (in)
        *d = *in;
    else
        memset(d, 0, sizeof *d);
    if (d->quality && d->min_angle_deg == 0.0) d->min_angle_deg = WR__DEFAULT_MIN_ANGLE;
    if (!d->quality) d->min_angle_deg = 0.0;
    if (d->seed == 0) d->seed = WR__DEFAULT_SEED;
}

static void wr__cdt_release(wr__cdt *S) {
    wr_free(S->xy);
    wr_free(S->vtri);
    wr_free(S->vseg);
    wr_free(S->tv);
    wr_free(S->tn);
    wr_free(S->cm);
    wr_free(S->tf);
    wr_free(S->stk);
    wr_free(S->treg);
    wr_free(S->attr);
    wr_free(S->ktag);
    memset(S, 0, sizeof *S);
}

WRDEF void wr_cdt_free(wr_cdt_result *r) {
    if (!r) return;
    wr_free(r->points);
    wr_free(r->point_map);
    wr_free(r->point_segment);
    wr_free(r->triangles);
    wr_free(r->neighbors);
    wr_free(r->edge_segment);
    wr_free(r->segments);
    wr_free(r->segment_id);
    wr_free(r->input_segments);
    wr_free(r->attributes);
    wr_free(r->triangle_region);
    memset(r, 0, sizeof *r);
}

/* sin² of a triangle's smallest angle (opposite its shortest edge): (2·area)² / (L1²·L2²) with L1, L2
 * the two longer edges. Monotone in the angle on [0°, 60°], so minima can be taken on it and
 * converted to degrees once. */
static double wr__tri_sin2_min(const double *a, const double *b, const double *c) {
    double e0 = (b[0] - c[0]) * (b[0] - c[0]) + (b[1] - c[1]) * (b[1] - c[1]);
    double e1 = (c[0] - a[0]) * (c[0] - a[0]) + (c[1] - a[1]) * (c[1] - a[1]);
    double e2 = (a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]);
    double a2 = wr_orient2d_fast(a, b, c), l1l2;
    if (e0 <= e1 && e0 <= e2)
        l1l2 = e1 * e2;
    else if (e1 <= e2)
        l1l2 = e0 * e2;
    else
        l1l2 = e0 * e1;
    return l1l2 > 0.0 ? fmin(1.0, a2 * a2 / l1l2) : 0.0;
}
static double wr__sin2_to_deg(double s2) { return asin(sqrt(fmax(0.0, fmin(1.0, s2)))) * (180.0 / 3.14159265358979323846); }

/* Output numbering: distinct input points in input order, then Steiner points. Internal vertex k < nid
 * is input point pos^-1(k) (BRIO order); in2int maps every input point to its internal vertex. */
static wr_status wr__cdt_output(wr__cdt *S, const int32_t *rep, const int32_t *pos, const int32_t *dupof,
                                const int32_t *in2int, int32_t nid, const wr_cdt_input *in, wr_cdt_result *out,
                                wr_diag *diag) {
    int32_t *outv = NULL, *outt = NULL, i, t, k, nvo = 0, nto = 0, nso = 0, n = in->n_points;
    double minang = 1.0; /* sin² of the smallest angle seen */
    outv = (int32_t *)wr_alloc_array((size_t)S->nv, sizeof(int32_t));
    outt = (int32_t *)wr_alloc_array((size_t)S->nt, sizeof(int32_t));
    if (!outv || !outt) goto nomem;
    for (i = 0; i < S->nv; ++i) outv[i] = -1;
    for (i = 0; i < n; ++i)
        if (rep[i] == i && dupof[pos[i]] == pos[i]) outv[pos[i]] = nvo++;
    out->n_input_points = nvo;
    for (i = nid; i < S->nv; ++i) outv[i] = nvo++;
    for (t = 0; t < S->nt; ++t) outt[t] = wr__is_live(S, t) ? nto++ : -1;
    out->points = (double *)wr_alloc_array((size_t)nvo * 2, sizeof(double));
    out->point_segment = (int32_t *)wr_alloc_array((size_t)nvo, sizeof(int32_t));
    out->point_map = (int32_t *)wr_alloc_array((size_t)n, sizeof(int32_t));
    if (!S->cm) { /* no constraints: all -1 (else S->cm is compacted and handed over below) */
        out->edge_segment = (int32_t *)wr_alloc_array((size_t)nto * 3, sizeof(int32_t));
        if (out->edge_segment) memset(out->edge_segment, 0xff, sizeof(int32_t) * 3 * (size_t)nto);
    }
    out->input_segments = (int32_t *)wr_alloc_array((size_t)in->n_segments * 2, sizeof(int32_t));
    if (!out->points || !out->point_segment || !out->point_map || (!S->cm && !out->edge_segment) ||
        !out->input_segments)
        goto nomem;
    out->n_points = nvo;
    out->n_map = n;
    out->n_input_segments = in->n_segments;
    for (i = 0; i < S->nv; ++i)
        if (outv[i] >= 0) {
            int32_t sg = i >= nid ? wr__seg_of(S, i) : -1;
            out->points[2 * outv[i]] = S->xy[2 * i];
            out->points[2 * outv[i] + 1] = S->xy[2 * i + 1];
            out->point_segment[outv[i]] = sg < in->n_segments ? sg : -1; /* hull pseudo-segments: -1 */
        }
    for (i = 0; i < n; ++i) out->point_map[i] = outv[in2int[i]];
    if (S->na > 0) {
        out->attributes = (double *)wr_alloc_array((size_t)nvo * (size_t)S->na, sizeof(double));
        if (!out->attributes) goto nomem;
        out->n_attributes = S->na;
        for (i = 0; i < S->nv; ++i)
            if (outv[i] >= 0)
                memcpy(out->attributes + (size_t)outv[i] * S->na, S->attr + (size_t)i * S->na, sizeof(double) * (size_t)S->na);
    }
    if (S->treg) {
        out->triangle_region = (int32_t *)wr_alloc_array((size_t)(nto > 0 ? nto : 1), sizeof(int32_t));
        if (!out->triangle_region) goto nomem;
        for (t = 0; t < S->nt; ++t)
            if (outt[t] >= 0) out->triangle_region[outt[t]] = S->treg[t];
    }
    for (i = 0; i < in->n_segments; ++i) {
        out->input_segments[2 * i] = outv[in2int[in->segments[2 * i]]];
        out->input_segments[2 * i + 1] = outv[in2int[in->segments[2 * i + 1]]];
    }
    /* every subsegment, also those bounding only removed triangles (so input segments stay complete
     * chains in this list); each edge once, from the lower-numbered internal triangle. Done before
     * the triangle arrays are compacted below. */
    for (i = 0; i < 2; ++i) {
        for (t = 0; S->cm && t < S->nt; ++t)
            for (k = 0; k < 3; ++k) {
                int32_t m = S->cm[3 * t + k], a, b;
                if (m < 0 || S->tn[3 * t + k] / 3 < t) continue; /* most edges: unconstrained */
                a = S->tv[3 * t + wr__n1[k]];
                b = S->tv[3 * t + wr__n2[k]];
                if (a < 0 || b < 0) continue;
                if (i == 0) {
                    ++nso;
                    continue;
                }
                out->segments[2 * out->n_segments] = outv[a];
                out->segments[2 * out->n_segments + 1] = outv[b];
                out->segment_id[out->n_segments++] = m;
            }
        if (i == 0) {
            out->segments = (int32_t *)wr_alloc_array((size_t)nso * 2, sizeof(int32_t));
            out->segment_id = (int32_t *)wr_alloc_array((size_t)nso, sizeof(int32_t));
            if (!out->segments || !out->segment_id) goto nomem;
        }
    }
    /* Triangles, neighbors and edge marks are compacted in place into the working arrays S->tv / S->tn
     * / S->cm, which are then handed over: live triangle t goes to slot outt[t] <= t, so every write lands at or before
     * the slot being read (the three entries are read first). This saves writing 24 bytes per
     * triangle into freshly allocated pages (page faults were ~10% of a 1e6-point run). The smallest
     * angle is tracked as sin² = (2·area)²/(L1²·L2²) compared by multiplication: one division per
     * new minimum instead of one per triangle. */
    for (t = 0; t < S->nt; ++t) {
        int32_t o = outt[t], v0, v1, v2, n0, n1, n2;
        if (o < 0) continue;
        v0 = S->tv[3 * t];
        v1 = S->tv[3 * t + 1];
        v2 = S->tv[3 * t + 2];
        n0 = outt[S->tn[3 * t] / 3];
        n1 = outt[S->tn[3 * t + 1] / 3];
        n2 = outt[S->tn[3 * t + 2] / 3];
        if (S->cm)
            for (k = 0; k < 3; ++k) {
                int32_t m = S->cm[3 * t + k];
                S->cm[3 * o + k] = m >= 0 ? m : -1; /* hull marks are not input segments */
            }
        {
            const double *a = WR__P(S, v0), *b = WR__P(S, v1), *c = WR__P(S, v2);
            double e0 = (b[0] - c[0]) * (b[0] - c[0]) + (b[1] - c[1]) * (b[1] - c[1]);
            double e1 = (c[0] - a[0]) * (c[0] - a[0]) + (c[1] - a[1]) * (c[1] - a[1]);
            double e2 = (a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]);
            double a2 = wr_orient2d_fast(a, b, c), l1l2, num;
            l1l2 = fmax(e1 * e2, fmax(e0 * e2, e0 * e1)); /* the two longer edges: largest product */
            num = a2 * a2;
            if (num < minang * l1l2) minang = num / l1l2;
        }
        S->tv[3 * o] = outv[v0];
        S->tv[3 * o + 1] = outv[v1];
        S->tv[3 * o + 2] = outv[v2];
        S->tn[3 * o] = n0;
        S->tn[3 * o + 1] = n1;
        S->tn[3 * o + 2] = n2;
    }
    out->triangles = S->tv;
    out->neighbors = S->tn;
    if (S->cm) out->edge_segment = S->cm;
    S->tv = S->tn = S->cm = NULL;
    S->capt = S->nt = 0;
    out->n_triangles = nto;
    if (nto > 0) { /* give back the unused tail; keep the larger block if shrinking fails */
        int32_t *p = (int32_t *)wr_realloc_array(out->triangles, (size_t)nto * 3, sizeof(int32_t));
        if (p) out->triangles = p;
        p = (int32_t *)wr_realloc_array(out->neighbors, (size_t)nto * 3, sizeof(int32_t));
        if (p) out->neighbors = p;
        p = (int32_t *)wr_realloc_array(out->edge_segment, (size_t)nto * 3, sizeof(int32_t));
        if (p) out->edge_segment = p;
    }
    out->min_angle_deg = nto ? wr__sin2_to_deg(minang) : 0.0;
    wr_free(outv);
    wr_free(outt);
    return WR_OK;
nomem:
    wr_free(outv);
    wr_free(outt);
    return wr_fail(diag, WR_ERR_NOMEM, -1, "out of memory while writing the result");
}

/* State of one wr_cdt_triangulate call, passed through its stages. */
typedef struct wr__tctx {
    const wr_cdt_input *in; /* the caller's input, or &in2 when a previous mesh adds segments */
    wr_cdt_input in2;
    wr_cdt_desc d;
    wr__cdt S;
    wr__segctx C;
    wr__ref R;
    wr_rng rng;
    int32_t *rep, *ids, *order, *in2int, *pos, *dupof, *allseg, *prev_bnd;
    double *tag_area;
    int32_t n, m, nid, n_prev_bnd;
    int refine, carved, holes_carved;
    int64_t n_real, n_live;
} wr__tctx;

static wr_status wr__cdt_validate(const wr_cdt_input *in, const wr_cdt_desc *d, wr_diag *diag) {
    int32_t i, n = in->n_points, m = in->n_segments;
    if (n < 0 || m < 0 || in->n_holes < 0 || in->n_regions < 0 || in->n_attributes < 0 || in->n_triangles < 0)
        return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "negative count (points %d, segments %d, holes %d)", n, m,
                       in->n_holes);
    if ((n > 0 && !in->points) || (m > 0 && !in->segments) || (in->n_holes > 0 && !in->holes) ||
        (in->n_regions > 0 && !in->regions) || (in->n_attributes > 0 && n > 0 && !in->attributes) ||
        (in->n_triangles > 0 && !in->triangles))
        return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "a non-empty input array is NULL");
    if (n > INT32_MAX / 8) return wr_fail(diag, WR_ERR_OVERFLOW, -1, "%d points is too many", n);
    if (in->n_attributes > 64) return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "%d attributes (at most 64)", in->n_attributes);
    if (d->min_angle_deg < 0.0 || !(d->min_angle_deg <= WR__MAX_MIN_ANGLE))
        return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "min_angle_deg %g outside (0, %g]", d->min_angle_deg,
                       WR__MAX_MIN_ANGLE);
    if (!(d->max_area >= 0.0) || !isfinite(d->max_area))
        return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "max_area %g must be finite and >= 0", d->max_area);
    if (!(d->merge_tolerance >= 0.0) || !isfinite(d->merge_tolerance))
        return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "merge_tolerance %g must be finite and >= 0", d->merge_tolerance);
    if (d->max_vertices < 0) return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "max_vertices %d < 0", d->max_vertices);
    for (i = 0; i < n; ++i) {
        double x = in->points[2 * i], y = in->points[2 * i + 1];
        if (!isfinite(x) || !isfinite(y))
            return wr_fail(diag, WR_ERR_INVALID_ARG, i, "point %d has a non-finite coordinate (%g, %g)", i, x, y);
        if (fabs(x) > WR_CDT_MAX_COORD || fabs(y) > WR_CDT_MAX_COORD)
            return wr_fail(diag, WR_ERR_GEOMETRY, i,
                           "point %d (%g, %g) has a coordinate beyond +-%g, where the exact predicates would "
                           "overflow; scale the input",
                           i, x, y, WR_CDT_MAX_COORD);
    }
    for (i = 0; i < m; ++i) {
        int32_t a = in->segments[2 * i], b = in->segments[2 * i + 1];
        if (a < 0 || a >= n || b < 0 || b >= n)
            return wr_fail(diag, WR_ERR_INVALID_ARG, i, "segment %d references point %d, outside [0, %d)", i,
                           (a < 0 || a >= n) ? a : b, n);
        if (a == b) return wr_fail(diag, WR_ERR_GEOMETRY, i, "segment %d has zero length (both ends are point %d)", i, a);
    }
    for (i = 0; i < 3 * in->n_triangles; ++i)
        if (in->triangles[i] < 0 || in->triangles[i] >= n)
            return wr_fail(diag, WR_ERR_INVALID_ARG, i / 3, "triangle %d references point %d, outside [0, %d)", i / 3,
                           in->triangles[i], n);
    for (i = 0; i < in->n_holes + in->n_regions; ++i) {
        const double *h = i < in->n_holes ? in->holes + 2 * i : in->regions + 4 * (i - in->n_holes);
        const char *what = i < in->n_holes ? "hole" : "region";
        int32_t j = i < in->n_holes ? i : i - in->n_holes;
        if (!isfinite(h[0]) || !isfinite(h[1]))
            return wr_fail(diag, WR_ERR_INVALID_ARG, j, "%s %d has a non-finite coordinate", what, j);
        if (fabs(h[0]) > WR_CDT_MAX_COORD || fabs(h[1]) > WR_CDT_MAX_COORD)
            return wr_fail(diag, WR_ERR_GEOMETRY, j, "%s %d (%g, %g) has a coordinate beyond +-%g", what, j, h[0], h[1],
                           WR_CDT_MAX_COORD);
    }
    return WR_OK;
}

/* Previous mesh: its boundary edges (directed with the mesh on their left) are those whose reverse
 * is no edge of it; they are added as segments after the input's (0 ok, -1 out of memory, -2 a
 * triangle with repeated corners). */
static int wr__edge_cmp(const void *x, const void *y) {
    const int32_t *a = (const int32_t *)x, *b = (const int32_t *)y;
    return a[0] != b[0] ? (a[0] < b[0] ? -1 : 1) : a[1] != b[1] ? (a[1] < b[1] ? -1 : 1) : 0;
}
static int wr__prev_boundary(wr__tctx *X) {
    const wr_cdt_input *in = X->in;
    int32_t nt = in->n_triangles, i, k, nb = 0, *e = (int32_t *)wr_alloc_array((size_t)nt * 3, 2 * sizeof(int32_t));
    if (!e) return -1;
    for (i = 0; i < nt; ++i) {
        const int32_t *v = in->triangles + 3 * i;
        int ccw = wr__orient2d_in(in->points + 2 * v[0], in->points + 2 * v[1], in->points + 2 * v[2]) > 0.0;
        for (k = 0; k < 3; ++k) {
            int32_t a = v[wr__n1[k]], b = v[wr__n2[k]];
            e[6 * i + 2 * k] = ccw ? a : b;
            e[6 * i + 2 * k + 1] = ccw ? b : a;
        }
    }
    qsort(e, (size_t)nt * 3, 2 * sizeof(int32_t), wr__edge_cmp);
    X->prev_bnd = (int32_t *)wr_alloc_array((size_t)nt * 3, 2 * sizeof(int32_t));
    X->allseg = (int32_t *)wr_alloc_array((size_t)in->n_segments + 3 * (size_t)nt, 2 * sizeof(int32_t));
    if (!X->prev_bnd || !X->allseg) {
        wr_free(e);
        return -1;
    }
    for (i = 0; i < 3 * nt; ++i) {
        int32_t r[2];
        r[0] = e[2 * i + 1];
        r[1] = e[2 * i];
        if (bsearch(r, e, (size_t)nt * 3, 2 * sizeof(int32_t), wr__edge_cmp)) continue;
        X->prev_bnd[2 * nb] = e[2 * i];
        X->prev_bnd[2 * nb + 1] = e[2 * i + 1];
        ++nb;
    }
    wr_free(e);
    X->n_prev_bnd = nb;
    if (in->n_segments > 0) memcpy(X->allseg, in->segments, sizeof(int32_t) * 2 * (size_t)in->n_segments);
    memcpy(X->allseg + 2 * in->n_segments, X->prev_bnd, sizeof(int32_t) * 2 * (size_t)nb);
    X->in2 = *in;
    X->in2.segments = X->allseg;
    X->in2.n_segments = in->n_segments + nb;
    X->in = &X->in2;
    X->m = X->in2.n_segments;
    return 0;
}

/* Delaunay triangulation of the distinct points in BRIO order (merging duplicates). */
static wr_status wr__cdt_delaunay(wr__tctx *X, wr_diag *diag) {
    wr__cdt *S = &X->S;
    const wr_cdt_input *in = X->in;
    int32_t i, n = X->n, i0 = 0, i1 = -1, i2 = -1, nid = 0;
    if (!wr__reserve_verts(S, n + 16)) return wr_fail(diag, WR_ERR_NOMEM, -1, "out of memory (%d points)", n);
    for (i = 0; i < S->capv; ++i) S->vseg[i] = -1; /* vtri: set when first needed, below */
    X->rep = (int32_t *)wr_alloc_array((size_t)n, sizeof(int32_t));
    X->ids = (int32_t *)wr_alloc_array((size_t)n, sizeof(int32_t));
    X->order = (int32_t *)wr_alloc_array((size_t)n, sizeof(int32_t));
    X->in2int = (int32_t *)wr_alloc_array((size_t)n, sizeof(int32_t));
    if (!X->rep || !X->ids || !X->order || !X->in2int) return wr_fail(diag, WR_ERR_NOMEM, -1, "out of memory (%d points)", n);
    if (X->d.merge_tolerance > 0.0) {
        if (!wr__merge_close(in->points, n, X->d.merge_tolerance, X->rep)) return wr_fail(diag, WR_ERR_NOMEM, -1, "out of memory");
    } else {
        for (i = 0; i < n; ++i) X->rep[i] = i;
    }
    for (i = 0; i < n; ++i)
        if (X->rep[i] == i) X->ids[nid++] = i;
    if (!wr__brio(in->points, X->ids, nid, &X->rng, X->order)) return wr_fail(diag, WR_ERR_NOMEM, -1, "out of memory");
    if (nid == 0) return wr_fail(diag, WR_ERR_GEOMETRY, -1, "no points to triangulate");
    /* Renumber: internal vertex k is input point order[k]. Consecutive insertions then touch nearby
     * memory (the walk and the predicates read coordinates of spatial neighbours). */
    for (i = 0; i < nid; ++i) {
        S->xy[2 * i] = in->points[2 * (size_t)X->order[i]];
        S->xy[2 * i + 1] = in->points[2 * (size_t)X->order[i] + 1];
        if (S->na > 0)
            memcpy(S->attr + (size_t)i * S->na, in->attributes + (size_t)X->order[i] * S->na, sizeof(double) * (size_t)S->na);
    }
    S->nv = S->n_input = X->nid = nid;
    X->pos = X->ids; /* reuse: pos[input] = internal slot of a representative */
    for (i = 0; i < nid; ++i) X->pos[X->order[i]] = i;
    X->dupof = X->order; /* reuse: dupof[k] = k, or the earlier vertex k coincides with */
    for (i = 0; i < nid; ++i) X->dupof[i] = i;
    for (i = 1; i < nid && i1 < 0; ++i)
        if (S->xy[2 * i] != S->xy[0] || S->xy[2 * i + 1] != S->xy[1]) i1 = i;
    for (i = 1; i < nid && i1 >= 0 && i2 < 0; ++i)
        if (wr__orient2d_in(WR__P(S, i0), WR__P(S, i1), WR__P(S, i)) != 0.0) i2 = i;
    if (i1 < 0) return wr_fail(diag, WR_ERR_GEOMETRY, -1, "fewer than 3 distinct points (%d given, all coincide)", n);
    if (i2 < 0) return wr_fail(diag, WR_ERR_GEOMETRY, -1, "all %d distinct points are collinear: no triangle exists", nid);
    if (!wr__reserve_tris(S, 2 * nid + 16)) return wr_fail(diag, WR_ERR_NOMEM, -1, "out of memory (%d points)", n);
    if (wr__orient2d_in(WR__P(S, i0), WR__P(S, i1), WR__P(S, i2)) > 0.0)
        wr__init_tri(S, i0, i1, i2);
    else
        wr__init_tri(S, i0, i2, i1);
    for (i = 0; i < nid; ++i) {
        int32_t vq;
        if (i == i0 || i == i1 || i == i2) continue;
        if (!wr__insert(S, i, S->last, &vq)) return wr_fail(diag, WR_ERR_NOMEM, -1, "out of memory (%d points)", n);
        X->dupof[i] = vq; /* vq != i: exact duplicate of an inserted vertex */
    }
    if (X->m > 0 || X->refine || in->n_holes > 0 || in->n_regions > 0) { /* vertex stars are needed from here on */
        for (i = 0; i < S->capv; ++i) S->vtri[i] = -1; /* -1: not in the mesh (a merged duplicate) */
        for (i = 0; i < S->nt; ++i) {
            int k;
            for (k = 0; k < 3; ++k)
                if (S->tv[3 * i + k] >= 0) S->vtri[S->tv[3 * i + k]] = i;
        }
        S->track_vtri = 1;
    }
    for (i = 0; i < S->nt; ++i) X->n_real += !WR__GHOSTLY(S, i);
    X->n_live = X->n_real;
    return WR_OK;
}

/* Segment recovery (each distinct segment once), then one Lawson pass when crossings were split. */
static wr_status wr__cdt_constrain(wr__tctx *X, wr_diag *diag) {
    wr__cdt *S = &X->S;
    const wr_cdt_input *in = X->in;
    int32_t *shead, *slink, i, t, m = X->m;
    wr_status st = WR_OK;
    if (!wr__ensure_cm(S)) return wr_fail(diag, WR_ERR_NOMEM, -1, "out of memory");
    X->C.split = X->d.split_intersections;
    X->C.seg = in->segments;
    X->C.in2int = X->in2int;
    /* A segment given again (same end points, also through merged duplicates) is recovered once:
     * its chain is the first one's (pieces carry the lowest id, see segment_id). Recovering it
     * again with split_intersections made it cross the first one's rounded junctions a few ulps
     * away, and the two chains then shared a sliver of a third segment (fuzzer finding
     * cdt_duplicate_crossing_split). shead/slink: per lower end, earlier segments. */
    shead = (int32_t *)wr_alloc_array((size_t)X->nid, sizeof(int32_t));
    slink = (int32_t *)wr_alloc_array((size_t)m, sizeof(int32_t));
    if (!shead || !slink) {
        wr_free(shead);
        wr_free(slink);
        return wr_fail(diag, WR_ERR_NOMEM, -1, "out of memory");
    }
    for (i = 0; i < X->nid; ++i) shead[i] = -1;
    for (i = 0; i < m && st == WR_OK; ++i) {
        int32_t a = X->in2int[in->segments[2 * i]], b = X->in2int[in->segments[2 * i + 1]], lo, hi, j;
        if (a == b) {
            st = wr_fail(diag, WR_ERR_GEOMETRY, i, "segment %d has zero length: its end points %d and %d were merged as duplicates",
                         i, in->segments[2 * i], in->segments[2 * i + 1]);
            break;
        }
        lo = a < b ? a : b;
        hi = a < b ? b : a;
        for (j = shead[lo]; j >= 0; j = slink[j]) {
            int32_t a2 = X->in2int[in->segments[2 * j]], b2 = X->in2int[in->segments[2 * j + 1]];
            if ((a2 < b2 ? b2 : a2) == hi) break;
        }
        if (j >= 0) continue; /* same as segment j */
        slink[i] = shead[lo];
        shead[lo] = i;
        st = wr__recover(S, &X->C, a, b, i, diag);
    }
    wr_free(shead);
    wr_free(slink);
    if (st != WR_OK || !X->C.split) return st;
    /* A crossing unconstrains the crossed edge and inserts its junction; an edge the insertion could
     * not legalize (the rounded junction fell beside it) is left to later pieces, and when a junction
     * is an existing vertex (wr__cross_vertex) no insertion happens at all. One Lawson pass over
     * every unconstrained edge restores the CDT property for the final constraints (fuzzer finding
     * after cdt_crossing_chain_split). */
    X->C.fresh.n = 0;
    for (t = 0; t < S->nt; ++t) {
        int k;
        if (WR__GHOSTLY(S, t)) continue;
        for (k = 0; k < 3; ++k) {
            int32_t he = 3 * t + k;
            if (S->cm[he] != -1 || S->tn[he] < he) continue;
            if (!wr__ivec_push(&X->C.fresh, S->tv[3 * t + wr__n1[k]]) || !wr__ivec_push(&X->C.fresh, S->tv[3 * t + wr__n2[k]]))
                return wr_fail(diag, WR_ERR_NOMEM, -1, "out of memory");
        }
    }
    return wr__restore_delaunay(S, &X->C.fresh) ? WR_OK : wr_fail(diag, WR_ERR_NOMEM, -1, "out of memory");
}

/* Remove the triangles outside the segments (unless the hull is kept), outside a previous mesh's
 * boundary, and in holes. */
static wr_status wr__cdt_carve(wr__tctx *X, wr_diag *diag) {
    wr__cdt *S = &X->S;
    const wr_cdt_input *in = X->in;
    int32_t i, t;
    int64_t removed = 0;
    if (X->m > 0 && !X->d.keep_convex_hull) {
        for (t = 0; t < S->nt; ++t)
            if (WR__GHOSTLY(S, t)) {
                const int32_t *v = S->tv + 3 * t;
                int g = v[0] < 0 ? 0 : v[1] < 0 ? 1 : 2;
                if (S->cm[3 * t + g] == -1 && !wr__flood(S, S->tn[3 * t + g] / 3, &removed))
                    return wr_fail(diag, WR_ERR_NOMEM, -1, "out of memory");
            }
        /* a previous mesh's boundary: the triangle right of each boundary edge is outside it */
        for (i = 0; i < X->n_prev_bnd; ++i) {
            int32_t he = wr__find_edge(S, X->in2int[X->prev_bnd[2 * i + 1]], X->in2int[X->prev_bnd[2 * i]]);
            if (he >= 0 && !WR__GHOSTLY(S, he / 3) && !wr__flood(S, he / 3, &removed))
                return wr_fail(diag, WR_ERR_NOMEM, -1, "out of memory");
        }
        if (removed == X->n_real) /* the segments enclose nothing: keep the hull */
            memset(S->tf, 0, (size_t)S->nt);
        else
            X->carved = 1;
        X->n_live = X->n_real - (X->carved ? removed : 0);
    }
    for (i = 0; i < in->n_holes; ++i) {
        int32_t r;
        int loc = wr__locate(S, in->holes + 2 * i, S->last, 0, (int64_t)4 * S->nt + 64, &r);
        removed = 0;
        if (loc == WR__LOC_LOST) continue;
        t = loc == WR__LOC_TRI ? r : loc == WR__LOC_EDGE ? r / 3 : S->vtri[r];
        if (WR__GHOSTLY(S, t)) continue; /* seed outside the convex hull */
        if (!wr__flood(S, t, &removed)) return wr_fail(diag, WR_ERR_NOMEM, -1, "out of memory");
        X->n_live -= removed;
        X->holes_carved |= removed > 0;
        if (X->n_live == 0)
            return wr_fail(diag, WR_ERR_GEOMETRY, i,
                           "hole %d at (%g, %g) removed every remaining triangle: the boundary around it is not closed",
                           i, in->holes[2 * i], in->holes[2 * i + 1]);
    }
    return WR_OK;
}

/* Triangle tags (S->treg): n_regions + j for a triangle that is triangle j of a previous mesh, then
 * region r for the triangles a flood from region seed r reaches (regions win). tag_area: the area
 * bound per tag. */
static int wr__tri_cmp3(const void *x, const void *y) {
    const int32_t *a = (const int32_t *)x, *b = (const int32_t *)y;
    int k;
    for (k = 0; k < 3; ++k)
        if (a[k] != b[k]) return a[k] < b[k] ? -1 : 1;
    return 0;
}
static void wr__sort3(int32_t *v) {
    int32_t t;
    if (v[0] > v[1]) t = v[0], v[0] = v[1], v[1] = t;
    if (v[1] > v[2]) t = v[1], v[1] = v[2], v[2] = t;
    if (v[0] > v[1]) t = v[0], v[0] = v[1], v[1] = t;
}
static wr_status wr__cdt_tags(wr__tctx *X, wr_diag *diag) {
    wr__cdt *S = &X->S;
    const wr_cdt_input *in = X->in;
    int32_t nr = in->n_regions, np = in->n_triangles, i, t, *key = NULL;
    if (nr == 0 && np == 0) return WR_OK;
    S->treg = (int32_t *)wr_alloc_array((size_t)S->capt, sizeof(int32_t));
    X->tag_area = (double *)wr_alloc_array((size_t)nr + (size_t)np, sizeof(double));
    if (np > 0) key = (int32_t *)wr_alloc_array((size_t)np, 4 * sizeof(int32_t));
    if (!S->treg || !X->tag_area || (np > 0 && !key)) {
        wr_free(key);
        return wr_fail(diag, WR_ERR_NOMEM, -1, "out of memory");
    }
    for (t = 0; t < S->capt; ++t) S->treg[t] = -1;
    for (i = 0; i < nr; ++i) X->tag_area[i] = in->regions[4 * i + 3];
    for (i = 0; i < np; ++i) {
        int k;
        X->tag_area[nr + i] = in->triangle_area ? in->triangle_area[i] : 0.0;
        for (k = 0; k < 3; ++k) key[4 * i + k] = X->in2int[in->triangles[3 * i + k]];
        wr__sort3(key + 4 * i);
        key[4 * i + 3] = i;
    }
    if (np > 0) {
        qsort(key, (size_t)np, 4 * sizeof(int32_t), wr__tri_cmp3);
        for (t = 0; t < S->nt; ++t) {
            int32_t v[3], *hit;
            if (!wr__is_live(S, t)) continue;
            memcpy(v, S->tv + 3 * t, sizeof v);
            wr__sort3(v);
            hit = (int32_t *)bsearch(v, key, (size_t)np, 4 * sizeof(int32_t), wr__tri_cmp3);
            if (hit) S->treg[t] = nr + hit[3];
        }
        wr_free(key);
    }
    for (i = 0; i < nr; ++i) {
        int32_t r, t0;
        int loc = wr__locate(S, in->regions + 4 * i, S->last, 0, (int64_t)4 * S->nt + 64, &r);
        if (loc == WR__LOC_LOST) continue;
        t0 = loc == WR__LOC_TRI ? r : loc == WR__LOC_EDGE ? r / 3 : S->vtri[r];
        if (!wr__is_live(S, t0) || S->treg[t0] == i) continue;
        S->nstk = 0;
        S->treg[t0] = i;
        if (!wr__push(S, t0)) return wr_fail(diag, WR_ERR_NOMEM, -1, "out of memory");
        while (S->nstk) {
            int32_t u = S->stk[--S->nstk], k;
            for (k = 0; k < 3; ++k) {
                int32_t w = S->tn[3 * u + k] / 3;
                if (S->cm[3 * u + k] != -1 || !wr__is_live(S, w) || S->treg[w] == i) continue;
                S->treg[w] = i;
                if (!wr__push(S, w)) return wr_fail(diag, WR_ERR_NOMEM, -1, "out of memory");
            }
        }
    }
    return WR_OK;
}

/* Refinement set-up (the hull becomes segments when it bounds the domain) and run. */
static wr_status wr__cdt_refine(wr__tctx *X, wr_diag *diag) {
    wr__cdt *S = &X->S;
    wr__ref *R = &X->R;
    const wr_cdt_input *in = X->in;
    int32_t t, i, n_ghost = 0, n_hull = 0, *sg, m = X->m;
    wr_status st;
    if (!wr__ensure_cm(S)) return wr_fail(diag, WR_ERR_NOMEM, -1, "out of memory");
    for (t = 0; t < S->nt; ++t) n_ghost += WR__GHOSTLY(S, t);
    sg = (int32_t *)wr_alloc_array(2 * ((size_t)m + (size_t)n_ghost), sizeof(int32_t));
    if (!sg) return wr_fail(diag, WR_ERR_NOMEM, -1, "out of memory");
    for (i = 0; i < 2 * m; ++i) sg[i] = X->in2int[in->segments[i]];
    /* When the hull bounds the domain, its edges not already on a segment become segments for
     * refinement (Ruppert treats the boundary of the domain as segments): they are split when
     * encroached, never flipped, concentric shells apply at hull vertices, and the small-angle
     * rule covers two hull edges (a needle-thin input triangle) or a hull edge and a segment
     * meeting at a small angle; each hull edge k is pseudo-segment m + k of R->seg. */
    if (!X->carved)
        for (t = 0; t < S->nt; ++t)
            if (WR__GHOSTLY(S, t)) {
                const int32_t *v = S->tv + 3 * t;
                int g = v[0] < 0 ? 0 : v[1] < 0 ? 1 : 2;
                if (S->cm[3 * t + g] != -1) continue;
                S->cm[3 * t + g] = S->cm[S->tn[3 * t + g]] = WR__HULL_MARK(n_hull);
                sg[2 * (m + n_hull)] = v[wr__n1[g]];
                sg[2 * (m + n_hull) + 1] = v[wr__n2[g]];
                ++n_hull;
            }
    S->fixed_boundary = 1;
    R->seg = sg;
    R->n_seg_in = m;
    if (X->d.quality) {
        double th = X->d.min_angle_deg * (3.14159265358979323846 / 180.0), s = sin(th), c2 = cos(2.0 * th);
        R->sin2 = s * s;
        /* Üngör's off-center at 0.95 of the distance (|pq|/2)·cot(θ/2) where the apex angle is θ */
        if (X->d.off_center >= 0) R->off = 0.475 / tan(0.5 * th);
        R->lens_c2 = X->d.conforming ? 0.0 : c2 * c2;
    } else {
        /* no angle bound: the lens of θ = 0 is the segment itself; Steiner points beyond a segment
         * still split it (see wr__fix_bad) */
        R->lens_c2 = X->d.conforming ? 0.0 : 1.0;
    }
    R->nobisect = X->d.no_segment_steiner;
    R->max_area = X->d.max_area;
    R->region_area = X->tag_area;
    R->unsuitable = X->d.unsuitable;
    R->user = X->d.user;
    R->tiny = 1e-50;
    for (i = 0; i < 2 * X->nid; ++i)
        if (S->xy[i] != 0.0 && fabs(S->xy[i]) < R->tiny) R->tiny = fabs(S->xy[i]);
    st = wr__refine(S, R, diag);
    wr_free(sg);
    R->seg = NULL;
    return st;
}

WRDEF wr_status wr_cdt_triangulate(const wr_cdt_input *in, const wr_cdt_desc *desc_in, wr_cdt_result *out,
                                   wr_diag *diag) {
    wr__tctx X;
    wr_status st, st_late = WR_OK;
    double t_start = wr_time_seconds();
    int64_t budget;
    int32_t i;
    memset(&X, 0, sizeof X);
    if (!out) return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "out is NULL");
    memset(out, 0, sizeof *out);
    if (!in) return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "input is NULL");
    wr__cdt_defaults(desc_in, &X.d);
    if ((st = wr__cdt_validate(in, &X.d, diag)) != WR_OK) return st;
    X.in = in;
    X.n = in->n_points;
    X.m = in->n_segments;
    X.refine = X.d.quality || X.d.max_area > 0.0 || X.d.conforming || X.d.unsuitable ||
               (in->n_triangles > 0 && in->triangle_area);
    for (i = 0; i < in->n_regions; ++i) X.refine |= in->regions[4 * i + 3] > 0.0;
    if (in->n_triangles > 0 && wr__prev_boundary(&X) < 0) {
        st = wr_fail(diag, WR_ERR_NOMEM, -1, "out of memory");
        goto done;
    }
    budget = X.d.max_vertices > 0 ? (int64_t)X.d.max_vertices
             : X.refine           ? 16 * ((int64_t)X.n + X.m) + 65536
                                  : (int64_t)INT32_MAX / 4;
    if (budget > INT32_MAX / 4) budget = INT32_MAX / 4;
    X.S.max_vertices = budget < X.n ? X.n : (int32_t)budget;
    X.S.n_input = X.n;
    X.S.walk_rng = 12345u;
    X.S.na = in->n_attributes;
    wr_rng_seed(&X.rng, X.d.seed);
    if ((st = wr__cdt_delaunay(&X, diag)) != WR_OK) goto done;
    for (i = 0; i < X.n; ++i) {
        X.in2int[i] = X.dupof[X.pos[X.rep[i]]];
        out->n_duplicates += X.rep[i] != i || X.in2int[i] != X.pos[i];
    }
    if (X.m > 0 && (st = wr__cdt_constrain(&X, diag)) != WR_OK) goto done;
    if ((st = wr__cdt_carve(&X, diag)) != WR_OK) goto done;
    if ((X.refine || in->n_regions > 0 || in->n_triangles > 0) && !wr__ensure_cm(&X.S)) {
        st = wr_fail(diag, WR_ERR_NOMEM, -1, "out of memory");
        goto done;
    }
    if ((st = wr__cdt_tags(&X, diag)) != WR_OK) goto done;
    if (X.refine) {
        st_late = wr__cdt_refine(&X, diag);
        if (st_late != WR_OK && st_late != WR_ERR_BUDGET) {
            st = st_late;
            goto done;
        }
    }
    st = wr__cdt_output(&X.S, X.rep, X.pos, X.dupof, X.in2int, X.nid, X.in, out, diag);
    if (st != WR_OK) goto done;
    out->exterior_carved = X.carved;
    out->holes_carved = X.holes_carved;
    out->n_steiner = X.C.n_steiner + X.R.n_steiner;
    out->n_refine_tries = X.R.n_tries;
    out->n_left_alone = X.R.n_left;
    st = st_late;
done:
    if (st != WR_OK && st != WR_ERR_BUDGET) wr_cdt_free(out);
    out->seconds = wr_time_seconds() - t_start;
    wr__cdt_release(&X.S);
    wr_free(X.C.pieces.a);
    wr_free(X.C.cross.a);
    wr_free(X.C.fresh.a);
    wr_free(X.R.segq.a);
    wr_free(X.R.badq.h);
    wr_free(X.R.cav.a);
    wr_free(X.R.slot.a);
    wr_free(X.rep);
    wr_free(X.ids);
    wr_free(X.order);
    wr_free(X.in2int);
    wr_free(X.allseg);
    wr_free(X.prev_bnd);
    wr_free(X.tag_area);
    return st;
}

/* ---- verification ---- */
static int32_t wr__uf_find(int32_t *p, int32_t x) {
    while (p[x] != x) {
        p[x] = p[p[x]];
        x = p[x];
    }
    return x;
}

/* The checker's state: the result, its counts (V used vertices, E edges, C components, B boundary
 * loops, pinched boundary vertices), per-vertex boundary successor, union-find over triangles, and
 * the two adjacency lists of the subsegment checks. */
typedef struct wr__cdtchk {
    const wr_cdt_result *r;
    int32_t nT, nP, V, E, C, B, pinched;
    double minang; /* sin² of the smallest angle seen */
    int32_t *bout, *bnext, *used, *uf, *stamp;
    /* CSR 1 (cstart, adj[0..nhe)): every mesh half-edge a -> b with its mark; CSR 2 (sstart,
     * adj[nhe..)): subsegments, both directions */
    int32_t nhe, *cstart, *sstart, *adj, *mk, *dfs;
} wr__cdtchk;

/* Every triangle's vertices in range and counter-clockwise; the smallest angle; the used vertices. */
static wr_status wr__chk_triangles(wr__cdtchk *K, wr_diag *diag) {
    const wr_cdt_result *r = K->r;
    int32_t t, k;
    for (t = 0; t < K->nT; ++t) {
        const int32_t *v = r->triangles + 3 * t;
        double a, s2;
        K->uf[t] = t;
        for (k = 0; k < 3; ++k)
            if (v[k] < 0 || v[k] >= K->nP)
                return wr_fail(diag, WR_ERR_TOPOLOGY, t, "triangle %d: vertex %d out of range [0, %d)", t, v[k], K->nP);
        a = wr__orient2d_in(r->points + 2 * v[0], r->points + 2 * v[1], r->points + 2 * v[2]);
        if (!(a > 0.0))
            return wr_fail(diag, WR_ERR_GEOMETRY, t, "triangle %d (%d, %d, %d) is %s", t, v[0], v[1], v[2],
                           a == 0.0 ? "degenerate (zero area)" : "clockwise (inverted)");
        s2 = wr__tri_sin2_min(r->points + 2 * v[0], r->points + 2 * v[1], r->points + 2 * v[2]);
        if (s2 < K->minang) K->minang = s2;
        for (k = 0; k < 3; ++k) K->used[v[k]] = 1;
    }
    return WR_OK;
}

/* Neighbours are mutual across the same edge with the same segment mark; every unconstrained
 * interior edge is locally Delaunay; counts edges, joins components, records the boundary edges. */
static wr_status wr__chk_adjacency(wr__cdtchk *K, wr_diag *diag) {
    const wr_cdt_result *r = K->r;
    int32_t t, k;
    for (t = 0; t < K->nT; ++t) {
        const int32_t *v = r->triangles + 3 * t;
        for (k = 0; k < 3; ++k) {
            int32_t nb = r->neighbors[3 * t + k], a = v[wr__n1[k]], b = v[wr__n2[k]], k2, m = r->edge_segment[3 * t + k];
            const int32_t *w;
            if (nb < -1 || nb >= K->nT) return wr_fail(diag, WR_ERR_TOPOLOGY, t, "triangle %d: neighbor %d out of range", t, nb);
            if (nb < 0) {
                ++K->E;
                if (K->bout[a]++) ++K->pinched;
                K->bnext[a] = b;
                continue;
            }
            w = r->triangles + 3 * nb;
            for (k2 = 0; k2 < 3; ++k2)
                if (w[wr__n1[k2]] == b && w[wr__n2[k2]] == a) break;
            if (k2 == 3 || r->neighbors[3 * nb + k2] != t || r->edge_segment[3 * nb + k2] != m)
                return wr_fail(diag, WR_ERR_TOPOLOGY, t, "triangles %d and %d are not mutual neighbors across edge (%d, %d)",
                               t, nb, a, b);
            if (t >= nb) continue; /* each interior edge once, from its lower triangle */
            ++K->E;
            K->uf[wr__uf_find(K->uf, t)] = wr__uf_find(K->uf, nb);
            if (m < 0 && wr__incircle_in(r->points + 2 * v[0], r->points + 2 * v[1], r->points + 2 * v[2],
                                      r->points + 2 * w[k2]) > 0.0)
                return wr_fail(diag, WR_ERR_GEOMETRY, t, "edge (%d, %d) between triangles %d and %d is not locally Delaunay",
                               a, b, t, nb);
        }
    }
    return WR_OK;
}

/* Components, used vertices, and (when no boundary vertex is pinched, so each vertex has at most one
 * outgoing boundary edge) the boundary cycles, the Euler characteristic and the hole count. */
static wr_status wr__chk_euler(wr__cdtchk *K, int32_t expected_holes, wr_diag *diag) {
    int32_t t, s;
    for (t = 0; t < K->nT; ++t) K->C += wr__uf_find(K->uf, t) == t;
    for (s = 0; s < K->nP; ++s) K->V += K->used[s];
    if (K->pinched) return WR_OK;
    for (s = 0; s < K->nP; ++s) K->stamp[s] = 0;
    for (s = 0; s < K->nP; ++s) {
        int32_t x = s, len = 0;
        if (!K->bout[s] || K->stamp[s]) continue;
        do {
            K->stamp[x] = 1;
            if (!K->bout[x]) return wr_fail(diag, WR_ERR_TOPOLOGY, x, "boundary is not closed at vertex %d", x);
            x = K->bnext[x];
        } while (!K->stamp[x] && ++len <= K->nP);
        if (x != s) return wr_fail(diag, WR_ERR_TOPOLOGY, s, "boundary through vertex %d is not a simple cycle", s);
        ++K->B;
    }
    if (K->V - K->E + K->nT != 2 * K->C - K->B)
        return wr_fail(diag, WR_ERR_TOPOLOGY, -1, "Euler characteristic V-E+F = %d, expected 2*components-loops = %d",
                       K->V - K->E + K->nT, 2 * K->C - K->B);
    if (expected_holes >= 0 && K->B - K->C != expected_holes)
        return wr_fail(diag, WR_ERR_TOPOLOGY, -1, "%d holes found (boundary loops %d, components %d), expected %d",
                       K->B - K->C, K->B, K->C, expected_holes);
    return WR_OK;
}

/* Checks the subsegment arrays and builds the two adjacency lists (half-edges, subsegments). */
static wr_status wr__chk_build_lists(wr__cdtchk *K, wr_diag *diag) {
    const wr_cdt_result *r = K->r;
    const int32_t nP = K->nP, ns = r->n_segments;
    int32_t s, t, k;
    if (ns < 0 || (ns > 0 && (!r->segments || !r->segment_id)))
        return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "subsegment arrays missing");
    for (s = 0; s < 2 * ns; ++s)
        if (r->segments[s] < 0 || r->segments[s] >= nP)
            return wr_fail(diag, WR_ERR_TOPOLOGY, s / 2, "subsegment %d has an out-of-range end", s / 2);
    K->nhe = 3 * K->nT;
    K->adj = (int32_t *)wr_alloc_array((size_t)K->nhe + 2 * (size_t)ns, sizeof(int32_t));
    K->mk = (int32_t *)wr_alloc_array((size_t)K->nhe + 2 * (size_t)ns, sizeof(int32_t));
    K->dfs = (int32_t *)wr_alloc_array((size_t)nP, sizeof(int32_t));
    K->sstart = (int32_t *)wr_calloc_array((size_t)nP + 1, sizeof(int32_t));
    if (!K->adj || !K->mk || !K->dfs || !K->sstart) return wr_fail(diag, WR_ERR_NOMEM, -1, "out of memory");
    for (t = 0; t < K->nT; ++t)
        for (k = 0; k < 3; ++k) K->cstart[r->triangles[3 * t + wr__n1[k]] + 1]++;
    for (s = 0; s < ns; ++s) {
        K->sstart[r->segments[2 * s] + 1]++;
        K->sstart[r->segments[2 * s + 1] + 1]++;
    }
    for (s = 0; s < nP; ++s) {
        K->cstart[s + 1] += K->cstart[s];
        K->sstart[s + 1] += K->sstart[s];
    }
    for (s = 0; s < nP; ++s) K->stamp[s] = K->cstart[s];
    for (t = 0; t < K->nT; ++t)
        for (k = 0; k < 3; ++k) {
            int32_t a = r->triangles[3 * t + wr__n1[k]], b = r->triangles[3 * t + wr__n2[k]];
            K->adj[K->stamp[a]] = b;
            K->mk[K->stamp[a]++] = r->edge_segment[3 * t + k];
        }
    for (s = 0; s < nP; ++s) K->stamp[s] = K->nhe + K->sstart[s];
    for (s = 0; s < ns; ++s) {
        int32_t a = r->segments[2 * s], b = r->segments[2 * s + 1], m = r->segment_id[s];
        K->adj[K->stamp[a]] = b;
        K->mk[K->stamp[a]++] = m;
        K->adj[K->stamp[b]] = a;
        K->mk[K->stamp[b]++] = m;
    }
    return WR_OK;
}

/* (1) constrained triangle edges and subsegments list each other, with the same segment id (a
 * subsegment that is no mesh edge at all is allowed only where triangles were removed). */
static wr_status wr__chk_subsegments(const wr__cdtchk *K, wr_diag *diag) {
    const wr_cdt_result *r = K->r;
    const int32_t *adj = K->adj, *mk = K->mk, *cs = K->cstart, o = K->nhe;
    int32_t s, j, j2;
    for (s = 0; s < K->nP; ++s) {
        for (j = cs[s]; j < cs[s + 1]; ++j) { /* constrained mesh edge -> listed subsegment */
            if (mk[j] < 0) continue;
            for (j2 = o + K->sstart[s]; j2 < o + K->sstart[s + 1]; ++j2)
                if (adj[j2] == adj[j] && mk[j2] == mk[j]) break;
            if (j2 == o + K->sstart[s + 1])
                return wr_fail(diag, WR_ERR_TOPOLOGY, mk[j], "constrained edge (%d, %d) of segment %d is not in the subsegment list",
                               s, adj[j], mk[j]);
        }
        for (j2 = o + K->sstart[s]; j2 < o + K->sstart[s + 1]; ++j2) { /* subsegment -> constrained edge */
            int32_t y = adj[j2], found = 0;
            for (j = cs[s]; j < cs[s + 1] && !found; ++j)
                if (adj[j] == y) found = mk[j] == mk[j2] ? 1 : -1;
            for (j = cs[y]; j < cs[y + 1] && !found; ++j)
                if (adj[j] == s) found = mk[j] == mk[j2] ? 1 : -1;
            if (found < 0 || (found == 0 && !r->exterior_carved && !r->holes_carved && K->used[s] && K->used[y]))
                return wr_fail(diag, WR_ERR_GEOMETRY, mk[j2], "subsegment (%d, %d) of segment %d is not a constrained mesh edge",
                               s, y, mk[j2]);
        }
    }
    return WR_OK;
}

/* (2) every input segment is a chain of subsegments (a DFS from one end to the other over pieces
 * that count for it). Input segments overlapping on one line (a segment given twice, also through
 * merged duplicate points, or one passing through another's end point) share their common pieces,
 * which carry the lowest id among them (see segment_id). A piece therefore counts for input segment
 * s when its id is s or names an input segment whose two end points lie exactly on s's line (exact
 * orient of the input end points, not of the piece's own end points, which refinement rounds a few
 * ulps off the line: fuzzer finding cdt_overlapping_segments_refine). */
static wr_status wr__chk_input_chains(wr__cdtchk *K, wr_diag *diag) {
    const wr_cdt_result *r = K->r;
    const double *P = r->points;
    int32_t s;
    for (s = 0; s < r->n_input_segments; ++s) {
        int32_t a = r->input_segments[2 * s], b = r->input_segments[2 * s + 1];
        if (a < 0 || a >= K->nP || b < 0 || b >= K->nP)
            return wr_fail(diag, WR_ERR_TOPOLOGY, s, "input segment %d has an out-of-range end", s);
    }
    for (s = 0; s < K->nP; ++s) K->stamp[s] = -1;
    for (s = 0; s < r->n_input_segments; ++s) {
        int32_t a = r->input_segments[2 * s], b = r->input_segments[2 * s + 1], nd = 0, ok = 0;
        K->dfs[nd++] = a;
        K->stamp[a] = s;
        while (nd && !ok) {
            int32_t x = K->dfs[--nd], j;
            for (j = K->nhe + K->sstart[x]; j < K->nhe + K->sstart[x + 1]; ++j) {
                int32_t y = K->adj[j], o = K->mk[j];
                if (K->stamp[y] == s) continue;
                if (o != s) {
                    const int32_t *e;
                    if (o < 0 || o >= r->n_input_segments) continue;
                    e = r->input_segments + 2 * o;
                    if (!(wr__orient2d_in(P + 2 * a, P + 2 * b, P + 2 * e[0]) == 0.0 &&
                          wr__orient2d_in(P + 2 * a, P + 2 * b, P + 2 * e[1]) == 0.0))
                        continue;
                }
                if (y == b) {
                    ok = 1;
                    break;
                }
                K->stamp[y] = s;
                K->dfs[nd++] = y;
            }
        }
        if (!ok) return wr_fail(diag, WR_ERR_GEOMETRY, s, "input segment %d (%d-%d) is not a chain of subsegments", s, a, b);
    }
    return WR_OK;
}

WRDEF wr_status wr_cdt_check(const wr_cdt_result *r, int32_t expected_holes, wr_cdt_check_info *info, wr_diag *diag) {
    wr__cdtchk K;
    wr_status st;
    wr_cdt_check_info loc;
    if (!info) info = &loc;
    memset(info, 0, sizeof *info);
    if (!r) return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "result is NULL");
    memset(&K, 0, sizeof K);
    K.r = r;
    K.nT = r->n_triangles;
    K.nP = r->n_points;
    K.minang = 1.0;
    if (K.nT < 0 || K.nP < 0 || (K.nT > 0 && (!r->triangles || !r->neighbors || !r->edge_segment)) ||
        (K.nP > 0 && !r->points))
        return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "result arrays missing");
    K.bout = (int32_t *)wr_calloc_array((size_t)K.nP, sizeof(int32_t));
    K.bnext = (int32_t *)wr_alloc_array((size_t)K.nP, sizeof(int32_t));
    K.used = (int32_t *)wr_calloc_array((size_t)K.nP, sizeof(int32_t));
    K.uf = (int32_t *)wr_alloc_array((size_t)K.nT, sizeof(int32_t));
    K.cstart = (int32_t *)wr_calloc_array((size_t)K.nP + 1, sizeof(int32_t));
    K.stamp = (int32_t *)wr_calloc_array((size_t)K.nP, sizeof(int32_t));
    if (!K.bout || !K.bnext || !K.used || !K.uf || !K.cstart || !K.stamp)
        st = wr_fail(diag, WR_ERR_NOMEM, -1, "out of memory");
    else if ((st = wr__chk_triangles(&K, diag)) == WR_OK && (st = wr__chk_adjacency(&K, diag)) == WR_OK &&
             (st = wr__chk_euler(&K, expected_holes, diag)) == WR_OK && (st = wr__chk_build_lists(&K, diag)) == WR_OK &&
             (st = wr__chk_subsegments(&K, diag)) == WR_OK)
        st = wr__chk_input_chains(&K, diag);
    info->n_vertices_used = K.V;
    info->n_edges = K.E;
    info->n_components = K.C;
    info->n_boundary_loops = K.B;
    info->n_pinched = K.pinched;
    info->euler = K.V - K.E + K.nT;
    info->min_angle_deg = K.nT ? wr__sin2_to_deg(K.minang) : 0.0;
    wr_free(K.bout);
    wr_free(K.bnext);
    wr_free(K.uf);
    wr_free(K.used);
    wr_free(K.cstart);
    wr_free(K.adj);
    wr_free(K.mk);
    wr_free(K.stamp);
    wr_free(K.dfs);
    wr_free(K.sstart);
    return st;
}

#ifdef __cplusplus
}
#endif
#endif /* WRINKLE_TRIANGULATE_IMPLEMENTATION_DONE */
#endif /* WRINKLE_IMPLEMENTATION */
