/* wrinkle/mesher.h — garment pattern → one optimally resolved simulation mesh (Style3D Sec. 4.2–4.3):
 * the pattern's sizing map (sizing.h), seam pairing, per panel boundary and constraint
 * discretisation, variable-radius Poisson sampling (poisson.h) and a constrained Delaunay
 * triangulation (triangulate.h); one wr_mesh with panel ids, per-vertex sizing, a seam table and a
 * quality report.
 * wrinkle v0.1.0 — MIT licence (see LICENSE). Needs only libc and libm (and core.h, mesh.h,
 * resolution.h, transition.h, sizing.h, poisson.h, triangulate.h).
 *
 * API (create/free pair: wr_mesher_run → wr_mesher_free)
 *   wr_mesher_run(pattern, desc, result, diag)      sizing → seam pairing → per panel {discretise →
 *                                                   Poisson fill → CDT} → assemble/sew → report
 *   wr_mesher_free(result)                          free and zero (safe on a zeroed result)
 *   wr_mesher_eval_sizing(result, panel, x, y)      the panel's sizing map at a pattern point [m]
 *   wr_mesher_panel_resolution(fabric, model, &r_warp, &r_weft, diag)   = wr_sizing_fabric_resolution
 *
 * EXAMPLE
 *     double sq[8] = {0,0, 0.25,0, 0.25,0.25, 0,0.25}, line[6] = {0.03,0.1, 0.125,0.14, 0.22,0.1};
 *     wr_pattern_panel pn; wr_pattern_shirring sh; wr_pattern pat; wr_mesher_result res; wr_diag d;
 *     memset(&pn, 0, sizeof pn); memset(&sh, 0, sizeof sh); memset(&pat, 0, sizeof pat);
 *     pn.outer.xy = sq; pn.outer.n = 4; pn.fabric.B = 2.6e-6; pn.fabric.E = 2.0e6;   // Table 1 Green
 *     sh.panel = 0; sh.xy = line; sh.n = 3; sh.E_sh = 2.0e6; sh.rho = 0.5;
 *     pat.panels = &pn; pat.n_panels = 1; pat.shirrings = &sh; pat.n_shirrings = 1;
 *     if (wr_mesher_run(&pat, NULL, &res, &d) != WR_OK) { puts(d.message); return 1; }
 *     printf("%d vertices, min angle %.1f deg\n", res.mesh.nv, res.report.min_angle_deg);
 *     wr_mesher_free(&res);
 *
 * ON UNITS
 *   Metres, N·m (B), N/m² (E, E_sh), radians (grain_angle), degrees only where the paper uses them
 *   (fold angle Δθ). The pattern-file driver (drivers/lib/pattern.h) converts millimetres.
 *
 * ON THE PIPELINE (wr_mesher_run; one stage per step of the paper)
 *   sizing        (4.1–4.2)  wr_sizing_map_build: per-panel metric and technique sources (sizing.h
 *                            documents every source); the map stays in result.map.
 *   budget                   wr_sizing_map_vertex_estimate per panel (area and perimeter at the map's
 *                            cap): WR_ERR_BUDGET before any work that grows faster than the output.
 *   seam pairing  (4.2.4)    each side a range of its panel's OUTER loop from `from` to `to`, walked
 *                            in the loop's input order (reverse = 1: against it); pairing from↔from,
 *                            to↔to. Seam ends are inserted into the loop; overlapping sides and sides
 *                            passing a corner (turn > WR_MESHER_CORNER_DEG: split the seam there) are
 *                            refused. Both sides get N = max of their own counts segments.
 *   per panel     (4.3)      discretise → curve budget → Poisson fill → CDT input → CDT → append.
 *   assemble                 the seam table, the wr_mesh (sewn with desc.sew), the quality report.
 *
 * ON THE CONSTRAINTS (what each technique adds to the mesh besides its sizing source)
 *   shirring, quilt stitches: the polyline is a constraint. Ends may lie on the outer loop: the
 *             constraint copy is then trimmed by WR_MESHER_TRIM_FACTOR × local sizing at that end (the
 *             sampler needs constraint lines strictly inside); the sizing source keeps the full line.
 *   fold:     the fold line and two parallels at ±offset (default WR_MESHER_DEFAULT_FOLD_OFFSET,
 *             mitred at vertices); the fold line must lie strictly inside its panel.
 *   seam:     its range of the outer loop carries exactly N segments on both sides.
 *
 * ON ANISOTROPY (Sec. 4.1.2, Fig. 6)
 *   Each panel is meshed in its metric's stretched space (sizing.h, ON THE PANEL METRIC): sampling
 *   and the CDT run on T(panel) with the isotropic size h(T⁻¹ X) and the points are mapped back with
 *   T⁻¹ (det T > 0, so faces stay CCW). Edges then have length ≈ h r_warp/r0 along the warp and
 *   h r_weft/r0 along the weft.
 *
 * ON SAMPLING AND TRIANGULATION (Sec. 4.3)
 *   Per panel, in stretched coordinates: the outer loop (with seam ends inserted), holes and
 *   constraint lines are discretised here, once, at ∫ ds/h (break points: corners turning >
 *   WR_MESHER_CORNER_DEG, seam ends; a seam range gets the count N shared with its partner side).
 *   poisson.h's wr_poisson_fill takes these curves as given: our points are its fixed points (in our
 *   order), our curve edges its segments, and its samples keep its clearance (0.35 h) from exactly
 *   those segments, inside exactly that polygon (its calibrated radius factor unless
 *   desc.radius_factor). The CDT (triangulate.h, no refinement, so no Steiner points and seam counts
 *   stay exact) gets the sampler's points and segments as they are and one seed per hole.
 *   Sampler failures on the curves (crossings, a line outside its panel) name the pattern items
 *   behind the sampler's curves from its structured location; diag->part = the panel, diag->curve /
 *   other_curve = the sampler's curves (0 outer, 1 + i hole i, 1 + n_holes + j constraint line j in
 *   the order shirrings, quilt lines, folds with their two parallels). Measurements:
 *   docs/notes-mesher.md.
 *
 * ON THE OUTPUT
 *   Vertices are numbered panel by panel (panels[p].v_begin..v_end), faces too (f_begin..f_end).
 *   Within a panel the curve points come first, in the order the sampler's domain lists them (outer
 *   loop from its first break, holes, constraint lines: shirrings, quilt lines, folds), then the
 *   interior samples: with desc.vertex_order = WR_MESHER_ORDER_SAMPLED (the default) in the
 *   sampler's order and the faces in the CDT's; with WR_MESHER_ORDER_SPATIAL along a Hilbert curve
 *   over the panel, and the panel's faces sorted by their largest corner id, so that nearby vertices
 *   and faces have nearby ids (every later pass over the mesh reads memory in order: 15-35 % less
 *   CPU in the passes measured, bench/RESULTS.md). The two orders give the same triangles (same
 *   corners in the same rotation) over the same positions, sizings, seam pairs and constraint
 *   segments: only the ids differ. Why the sampled order stays the default: a dynamic drape is
 *   chaotic in round-off, and the summation order a numbering implies moves it (the quick skirt's
 *   drape distance D1 2.6 -> 3.9 mm from the numbering alone), so switching the default means
 *   re-running every mesh-dependent validation; new callers may prefer SPATIAL. rest = pattern position, pos = (rest, 0).
 *   face_panel set.
 *   Seam sides are NOT merged (seam_pairs lists the vertices to sew, in order along the seam) unless
 *   desc.sew: then side b's vertices are merged into side a's, rest is NULL and corner_rest carries
 *   each corner's own pattern position (a sewn vertex has two). sizing[v] = target edge length [m]
 *   (the fine direction for anisotropic panels), sizing_warp/_weft per direction. result.map is the
 *   sizing map (sizing.h: evaluate, draw). Quality: angles in pattern space and in the metric
 *   (stretched) space; edge ratio = |T e| / mean of the two end sizings (metric length over target,
 *   1 is ideal), histogram of WR_MESHER_HIST_BINS bins on [0, 2).
 *
 * ON PROGRESS
 *   desc.progress (optional) is called from the calling thread after the sizing stage (stage
 *   "sizing", panel = -1), after each panel ("panel") and at the end ("done"); it only observes.
 *
 * ON ERRORS (status + message naming the item; diag->item = its index)
 *   Pattern and sizing errors as in sizing.h (WR_ERR_INVALID_ARG, WR_ERR_DOMAIN, WR_ERR_GEOMETRY);
 *   here also WR_ERR_GEOMETRY for overlapping seams, a seam across a corner or of zero length, and
 *   self-intersections reported by poisson.h (message names the technique behind the sampler's
 *   curves; diag->part / curve / other_curve as in ON SAMPLING AND TRIANGULATION); WR_ERR_BUDGET
 *   when desc.max_vertices would be exceeded: by the area/perimeter estimate before any panel is
 *   discretised, by a panel's curve points before sampling, by the sampler's own estimate, and by
 *   the CDT output (item = the panel). On failure the result is zeroed.
 *
 * ON THREADS: no global state; one call is single-threaded. Deterministic for a fixed desc.seed.
 */
#ifndef WRINKLE_MESHER_H
#define WRINKLE_MESHER_H

#include "core.h"
#include "mesh.h"
#include "resolution.h"
#include "transition.h"
#include "sizing.h"
#include "poisson.h"
#include "triangulate.h"

#ifdef __cplusplus
extern "C" {
#endif

#define WR_MESHER_DEFAULT_FOLD_OFFSET 0.5e-3 /* m, Sec. 4.2.3 "e.g., 0.5 mm" */
#define WR_MESHER_DEFAULT_MAX_VERTICES 20000000
#define WR_MESHER_CORNER_DEG 30.0 /* turning angle above which a boundary vertex is kept exactly */
#define WR_MESHER_TRIM_FACTOR 0.5 /* constraint trim at a line end lying on the boundary (× sizing) */
#define WR_MESHER_HIST_BINS 20    /* edge-ratio histogram bins on [0, 2) */
#define WR_MESHER_ORDER_SAMPLED 0 /* desc.vertex_order: interior vertices in the sampler's order (default) */
#define WR_MESHER_ORDER_SPATIAL 1 /* desc.vertex_order: interior vertices along a Hilbert curve */

/* What wr_mesher_run reports to desc.progress. */
typedef struct wr_mesher_progress {
    const char *stage;      /* "sizing", "panel", "done" */
    int32_t panel;          /* the panel just meshed (stage "panel"), else -1 */
    int32_t n_panels;
    const char *panel_name; /* "" when unnamed or no panel */
    int32_t n_vertices;     /* vertices so far (before sewing) */
    double seconds;         /* wall time since wr_mesher_run started */
} wr_mesher_progress;
typedef void (*wr_mesher_progress_fn)(void *user, const wr_mesher_progress *p);

/* Options; zero means default:
 *   model               Eq. 4 constants; c1 == c2 == 0 → wr_resolution_model_paper()
 *   uniform_resolution  > 0: ignore fabrics and techniques, mesh every panel at this size [m]
 *                       (seams still get equal counts) — the "uniform fine" comparison
 *   radius_factor       Poisson radius / sizing; 0 → poisson.h's calibrated default
 *   seed                sampling seed (0 is used as given)
 *   max_vertices        0 → WR_MESHER_DEFAULT_MAX_VERTICES
 *   sew                 1: merge seam pairs into one vertex (corner_rest output)
 *   vertex_order        WR_MESHER_ORDER_SAMPLED (0) or WR_MESHER_ORDER_SPATIAL: the numbering within a
 *                       panel (ON THE OUTPUT); the same triangles over the same positions either way
 *   progress            NULL: no reports; else called with progress_user (see ON PROGRESS) */
typedef struct wr_mesher_desc {
    wr_resolution_model model;
    double uniform_resolution;
    double radius_factor;
    uint64_t seed;
    int32_t max_vertices;
    int sew;
    wr_mesher_progress_fn progress;
    void *progress_user;
    int vertex_order;
} wr_mesher_desc;

typedef struct wr_mesher_panel_info {
    double r_warp, r_weft;  /* base resolution per direction [m] (equal for isotropic panels) */
    double r0;              /* min(r_warp, r_weft): the stretched-space sizing */
    double T[4], Tinv[4];   /* row-major pattern → stretched map and its inverse */
    int32_t v_begin, v_end; /* vertex range (before sewing) */
    int32_t f_begin, f_end; /* face range */
    double area;            /* pattern area [m²] */
    int32_t n_sources;      /* sizing sources of this panel */
} wr_mesher_panel_info;

typedef struct wr_mesher_report {
    int32_t n_vertices, n_triangles, n_seam_pairs, n_constraint_segments;
    double min_angle_deg, max_angle_deg, mean_min_angle_deg; /* pattern space */
    double min_angle_metric_deg, mean_min_angle_metric_deg;  /* in each panel's metric (stretched) space;
                                                                equal to the above for isotropic panels */
    double ratio_mean, ratio_interior_mean, ratio_min, ratio_max; /* edge metric length / sizing */
    int32_t ratio_hist[WR_MESHER_HIST_BINS];                      /* bins on [0, 2) */
    int32_t n_inverted, n_zero_area;
    double t_sizing, t_discretise, t_poisson, t_cdt, t_assemble, t_total; /* seconds */
} wr_mesher_report;

typedef struct wr_mesher_result {
    wr_mesh mesh;
    double *sizing;                    /* nv target edge length [m] (fine direction) */
    double *sizing_warp, *sizing_weft; /* nv per-direction target lengths [m] */
    int32_t *seam_pairs;               /* n_seam_pairs × 2 vertex ids (side a, side b), in order along each seam */
    int32_t *seam_pair_seam;           /* n_seam_pairs: seam index */
    int32_t n_seam_pairs;
    int32_t *constraint_segments;      /* n_constraint_segments × 2: boundary + constraint-line edges */
    int32_t n_constraint_segments;
    wr_mesher_panel_info *panels;      /* n_panels */
    int32_t n_panels;
    wr_sizing_map map;                 /* the sizing map the mesh follows (sizing.h) */
    wr_mesher_report report;
} wr_mesher_result;

WRDEF wr_status wr_mesher_run(const wr_pattern *pat, const wr_mesher_desc *desc, wr_mesher_result *res,
                              wr_diag *diag);
WRDEF void wr_mesher_free(wr_mesher_result *res);
/* Sizing [m] (fine direction) of panel p's map at pattern point (x, y); NaN for a bad panel index.
 * Same as wr_sizing_map_eval(&res->map, panel, x, y). */
WRDEF double wr_mesher_eval_sizing(const wr_mesher_result *res, int32_t panel, double x, double y);
/* Eq. 4 per direction for one fabric: wr_sizing_fabric_resolution under its older name. */
WRDEF wr_status wr_mesher_panel_resolution(const wr_pattern_fabric *fab, const wr_resolution_model *model,
                                           double *r_warp, double *r_weft, wr_diag *diag);

#ifdef __cplusplus
}
#endif
#endif /* WRINKLE_MESHER_H */

/* ============================================================================================ */
#ifdef WRINKLE_IMPLEMENTATION
#ifndef WRINKLE_MESHER_IMPLEMENTATION_DONE
#define WRINKLE_MESHER_IMPLEMENTATION_DONE

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#ifdef __cplusplus
extern "C" {
#endif

/* ---- growable arrays ------------------------------------------------------------------------- */
typedef struct wr__msh_dbuf {
    double *v;
    int32_t n, cap;
} wr__msh_dbuf;
typedef struct wr__msh_ibuf {
    int32_t *v;
    int32_t n, cap;
} wr__msh_ibuf;

static int wr__msh_dpush(wr__msh_dbuf *b, double x) {
    if (b->n == b->cap) {
        int32_t nc = b->cap ? 2 * b->cap : 64;
        double *nv = (double *)wr_realloc_array(b->v, (size_t)nc, sizeof(double));
        if (!nv) return 0;
        b->v = nv;
        b->cap = nc;
    }
    b->v[b->n++] = x;
    return 1;
}
static int wr__msh_dpush2(wr__msh_dbuf *b, double x, double y) { return wr__msh_dpush(b, x) && wr__msh_dpush(b, y); }
static int wr__msh_dbuf_reserve(wr__msh_dbuf *b, int32_t n) {
    if (n > b->cap) {
        double *nv = (double *)wr_realloc_array(b->v, (size_t)n, sizeof(double));
        if (!nv) return 0;
        b->v = nv;
        b->cap = n;
    }
    return 1;
}
static int wr__msh_ipush(wr__msh_ibuf *b, int32_t x) {
    if (b->n == b->cap) {
        int32_t nc = b->cap ? 2 * b->cap : 64;
        int32_t *nv = (int32_t *)wr_realloc_array(b->v, (size_t)nc, sizeof(int32_t));
        if (!nv) return 0;
        b->v = nv;
        b->cap = nc;
    }
    b->v[b->n++] = x;
    return 1;
}
static int wr__msh_ipush2(wr__msh_ibuf *b, int32_t x, int32_t y) { return wr__msh_ipush(b, x) && wr__msh_ipush(b, y); }

/* ---- the state of one run ------------------------------------------------------------------------ */
/* A panel's outer loop with the seam ends inserted (pattern coordinates). */
typedef struct wr__msh_loop {
    double *xy;
    int32_t n;
    int *brk;              /* break flags: corners and seam ends are kept exactly */
    int32_t *side_of_edge; /* loop edge → the seam side walking over it, -1 */
    int32_t *forced;       /* per break vertex: forced segment count of the piece starting there */
} wr__msh_loop;

/* One seam side resolved on its panel's loop. */
typedef struct wr__msh_side {
    int32_t seam, which; /* which: 0 = a, 1 = b */
    int32_t panel;
    int32_t v_from, v_to; /* vertices of the panel's loop */
    int reverse;
    int32_t N;       /* segments (equal on both sides) */
    int32_t *global; /* N+1 global vertex ids in walk order from → to */
} wr__msh_side;

/* What lives across stages: the inputs, the seam layout and the growing output arrays. */
typedef struct wr__msh_ctx {
    const wr_pattern *pat;
    wr_mesher_desc desc;
    wr_mesher_result *res;
    wr_diag *diag;
    double t_start;
    wr__msh_loop *loops; /* n_panels */
    wr__msh_side *sides; /* 2 per seam: a, b */
    int32_t n_sides;
    wr__msh_dbuf rest, sizing, sizing_warp, sizing_weft; /* per output vertex (before sewing) */
    wr__msh_ibuf faces, face_panel, segments, seam_pairs, seam_pair_seam;
} wr__msh_ctx;

/* One panel's curves, samples and triangulation, all in its stretched coordinates. */
typedef struct wr__msh_panel_run {
    double *loop;                                 /* the refined outer loop */
    int32_t *index_of;                            /* loop vertex → index in outer */
    wr__msh_dbuf outer, holes, lines;             /* discretised curves */
    wr__msh_ibuf hole_n, line_n, line_lab;        /* counts; line_lab: 2 per line (kind, technique index) */
    wr_poisson_curve *hole_curves, *line_curves;  /* views of holes / lines for the sampler */
    wr_poisson_result samples;                    /* our curve points, then the fill; our curve edges */
    double *hole_seeds;
    wr_cdt_result tri;
} wr__msh_panel_run;

static void wr__msh_panel_run_free(wr__msh_panel_run *r) {
    wr_free(r->loop);
    wr_free(r->index_of);
    wr_free(r->outer.v);
    wr_free(r->holes.v);
    wr_free(r->lines.v);
    wr_free(r->hole_n.v);
    wr_free(r->line_n.v);
    wr_free(r->line_lab.v);
    wr_free(r->hole_curves);
    wr_free(r->line_curves);
    wr_poisson_free(&r->samples);
    wr_free(r->hole_seeds);
    wr_cdt_free(&r->tri);
    memset(r, 0, sizeof *r);
}

static const wr_sizing_panel *wr__msh_map(const wr__msh_ctx *c, int32_t p) { return &c->res->map.panels[p]; }
static const char *wr__msh_pname(const wr__msh_ctx *c, int32_t p) { return wr_pattern_panel_name(c->pat, p); }
static wr_status wr__msh_nomem(wr__msh_ctx *c, int32_t p) {
    if (p < 0) return wr_fail(c->diag, WR_ERR_NOMEM, -1, "out of memory");
    return wr_fail(c->diag, WR_ERR_NOMEM, p, "out of memory meshing panels[%d]", (int)p);
}
/* The sampler's sizing callback: the panel's map at a stretched point. */
static double wr__msh_size_cb(void *user, double x, double y) {
    return wr_sizing_panel_eval_stretched((const wr_sizing_panel *)user, x, y);
}

/* ---- small geometry ------------------------------------------------------------------------ */
/* Turning angle [deg] at vertex i of a closed loop. */
static double wr__msh_turn(const double *xy, int32_t n, int32_t i) {
    const double *a = xy + 2 * ((i + n - 1) % n), *b = xy + 2 * i, *c = xy + 2 * ((i + 1) % n);
    double ux = b[0] - a[0], uy = b[1] - a[1], vx = c[0] - b[0], vy = c[1] - b[1];
    return fabs(atan2(ux * vy - uy * vx, ux * vx + uy * vy)) * 57.29577951308232;
}

static int32_t wr__msh_step(int32_t v, int32_t n, int reverse) { return reverse ? (v + n - 1) % n : (v + 1) % n; }

/* ---- discretisation of one piece of a curve at ∫ ds / h -------------------------------------- */
/* Piece = points P[0..np) (stretched coords). Appends interior points (not P[0], not P[np-1]) for N
 * segments at equal ∫ ds/h fractions, N = forced > 0 or max(1, round(∫)) with the guard that keeps
 * every piece's ∫ below 1.4 (the sampler then keeps the points as they are). Returns N, or -1 on
 * allocation failure. With out == NULL only returns the natural count. */
static int32_t wr__msh_piece(const double *P, int32_t np, const wr_sizing_panel *m, int32_t forced, wr__msh_dbuf *out) {
    wr__msh_dbuf cum, pts;
    double total = 0.0;
    int32_t i, N, k, j;
    memset(&cum, 0, sizeof cum);
    memset(&pts, 0, sizeof pts);
    /* fine table: sub-steps of WR_POISSON_WALK_STEP × local sizing, trapezoid rule on 1/h */
    if (!wr__msh_dpush(&cum, 0.0) || !wr__msh_dpush2(&pts, P[0], P[1])) goto nomem;
    for (i = 0; i + 1 < np; ++i) {
        const double *a = P + 2 * i, *b = P + 2 * i + 2;
        double dx = b[0] - a[0], dy = b[1] - a[1], L = sqrt(dx * dx + dy * dy);
        double h0 = wr_sizing_panel_eval_stretched(m, a[0], a[1]);
        /* clamp in double before the cast: a huge or NaN ratio must not overflow int32 (fuzzer finding) */
        double nsd = ceil(L / (WR_POISSON_WALK_STEP * h0));
        int32_t ns;
        double hp = h0;
        if (!(nsd >= 1.0)) nsd = 1.0;
        if (nsd > 100000.0) nsd = 100000.0;
        ns = (int32_t)nsd;
        for (k = 1; k <= ns; ++k) {
            double t = (double)k / ns, x = a[0] + t * dx, y = a[1] + t * dy;
            double hk = wr_sizing_panel_eval_stretched(m, x, y);
            total += 0.5 * (1.0 / hp + 1.0 / hk) * (L / ns);
            hp = hk;
            if (!wr__msh_dpush(&cum, total) || !wr__msh_dpush2(&pts, x, y)) goto nomem;
        }
    }
    /* More than 1e7 segments on one curve piece is no cloth pattern; refuse before the int32 cast
     * (reported by the callers as an allocation failure). */
    if (!(total < 1e7)) goto nomem;
    N = (int32_t)floor(total + 0.5);
    if (N < 1) N = 1;
    if (total / N > 1.4) ++N;
    if (out && forced > 0) N = forced;
    for (k = 1, j = 0; out && k < N; ++k) {
        double target = total * k / N, f;
        while (j + 1 < cum.n && cum.v[j + 1] < target) ++j;
        if (j + 1 >= cum.n) j = cum.n - 2;
        f = (cum.v[j + 1] > cum.v[j]) ? (target - cum.v[j]) / (cum.v[j + 1] - cum.v[j]) : 0.0;
        if (!wr__msh_dpush2(out, pts.v[2 * j] + f * (pts.v[2 * j + 2] - pts.v[2 * j]),
                            pts.v[2 * j + 1] + f * (pts.v[2 * j + 3] - pts.v[2 * j + 1])))
            goto nomem;
    }
    wr_free(cum.v);
    wr_free(pts.v);
    return N;
nomem:
    wr_free(cum.v);
    wr_free(pts.v);
    return -1;
}

/* Discretise a closed loop (stretched coords L[2n]) with break flags brk[n] (at least one set), and
 * forced segment counts per piece (forced_of_start[v] for the piece starting at break v, 0 = natural).
 * Output points in loop order starting at the first break; index_of[v] = output index of break v.
 * Returns 0 on success, -1 on allocation failure. */
static int wr__msh_loop_discretise(const double *L, int32_t n, const int *brk, const int32_t *forced_of_start,
                                   const wr_sizing_panel *m, wr__msh_dbuf *out, int32_t *index_of) {
    int32_t first = -1, v;
    wr__msh_dbuf piece;
    memset(&piece, 0, sizeof piece);
    for (v = 0; v < n && first < 0; ++v)
        if (brk[v]) first = v;
    if (first < 0) return 0;
    v = first;
    do {
        int32_t w = (v + 1) % n;
        piece.n = 0;
        if (!wr__msh_dpush2(&piece, L[2 * v], L[2 * v + 1])) goto nomem;
        while (!brk[w]) {
            if (!wr__msh_dpush2(&piece, L[2 * w], L[2 * w + 1])) goto nomem;
            w = (w + 1) % n;
        }
        if (!wr__msh_dpush2(&piece, L[2 * w], L[2 * w + 1])) goto nomem;
        index_of[v] = out->n / 2;
        if (!wr__msh_dpush2(out, L[2 * v], L[2 * v + 1])) goto nomem;
        if (wr__msh_piece(piece.v, piece.n / 2, m, forced_of_start ? forced_of_start[v] : 0, out) < 0) goto nomem;
        v = w;
    } while (v != first);
    wr_free(piece.v);
    return 0;
nomem:
    wr_free(piece.v);
    return -1;
}

/* ---- stage: set-up ------------------------------------------------------------------------------ */
static wr_status wr__msh_begin(wr__msh_ctx *c, const wr_pattern *pat, const wr_mesher_desc *desc, wr_mesher_result *res,
                               wr_diag *diag) {
    memset(c, 0, sizeof *c);
    c->t_start = wr_time_seconds();
    c->pat = pat;
    c->res = res;
    c->diag = diag;
    if (!res) return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "NULL result");
    memset(res, 0, sizeof *res);
    if (!pat) return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "NULL pattern");
    if (desc) c->desc = *desc;
    if (c->desc.model.c1 == 0.0 && c->desc.model.c2 == 0.0) c->desc.model = wr_resolution_model_paper();
    if (c->desc.max_vertices <= 0) c->desc.max_vertices = WR_MESHER_DEFAULT_MAX_VERTICES;
    if (c->desc.radius_factor < 0.0 || !isfinite(c->desc.radius_factor) || c->desc.uniform_resolution < 0.0 ||
        !isfinite(c->desc.uniform_resolution))
        return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "desc: negative or non-finite radius_factor/uniform_resolution");
    if (c->desc.vertex_order != WR_MESHER_ORDER_SPATIAL && c->desc.vertex_order != WR_MESHER_ORDER_SAMPLED)
        return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "desc: vertex_order %d is neither WR_MESHER_ORDER_SAMPLED (0) nor "
                       "WR_MESHER_ORDER_SPATIAL (1)", c->desc.vertex_order);
    return WR_OK;
}

static void wr__msh_progress(const wr__msh_ctx *c, const char *stage, int32_t panel) {
    wr_mesher_progress pr;
    if (!c->desc.progress) return;
    pr.stage = stage;
    pr.panel = panel;
    pr.n_panels = c->pat->n_panels;
    pr.panel_name = panel >= 0 ? wr__msh_pname(c, panel) : "";
    pr.n_vertices = c->rest.n / 2;
    pr.seconds = wr_time_seconds() - c->t_start;
    c->desc.progress(c->desc.progress_user, &pr);
}

/* ---- stage: the sizing map (Sec. 4.1–4.2) -------------------------------------------------------- */
static wr_status wr__msh_sizing(wr__msh_ctx *c) {
    wr_sizing_map_desc sd;
    wr_status st;
    int32_t p, np;
    double t0 = wr_time_seconds();
    memset(&sd, 0, sizeof sd);
    sd.model = c->desc.model;
    sd.uniform_resolution = c->desc.uniform_resolution;
    if ((st = wr_sizing_map_build(c->pat, &sd, &c->res->map, c->diag)) != WR_OK) return st;
    np = c->pat->n_panels;
    c->res->panels = (wr_mesher_panel_info *)wr_calloc_array((size_t)np, sizeof(wr_mesher_panel_info));
    c->loops = (wr__msh_loop *)wr_calloc_array((size_t)np, sizeof(wr__msh_loop));
    c->sides = (wr__msh_side *)wr_calloc_array((size_t)(2 * c->pat->n_seams), sizeof(wr__msh_side));
    if (!c->res->panels || !c->loops || !c->sides) return wr__msh_nomem(c, -1);
    c->res->n_panels = np;
    for (p = 0; p < np; ++p) {
        const wr_sizing_panel *m = wr__msh_map(c, p);
        wr_mesher_panel_info *pi = &c->res->panels[p];
        pi->r_warp = m->r_warp;
        pi->r_weft = m->r_weft;
        pi->r0 = m->r0;
        memcpy(pi->T, m->T, sizeof pi->T);
        memcpy(pi->Tinv, m->Tinv, sizeof pi->Tinv);
        pi->area = m->area;
        pi->n_sources = m->n_sources;
    }
    c->res->report.t_sizing = wr_time_seconds() - t0;
    return WR_OK;
}

/* ---- stage: the vertex budget from area and perimeter, before any work that grows with the output */
static wr_status wr__msh_budget(wr__msh_ctx *c) {
    double total = 0.0, spacing = c->desc.radius_factor > 0.0 ? c->desc.radius_factor / WR_POISSON_DEFAULT_RADIUS_FACTOR : 1.0;
    int32_t p;
    for (p = 0; p < c->pat->n_panels; ++p) {
        const wr_sizing_panel *m = wr__msh_map(c, p);
        double need = wr_sizing_map_vertex_estimate(&c->res->map, p, spacing);
        total += need;
        if (total > (double)c->desc.max_vertices)
            return wr_fail(c->diag, WR_ERR_BUDGET, p,
                           "vertex budget of %d exceeded at panels[%d] '%s': its area %.4g m^2 and perimeter %.4g m "
                           "need at least %.3g vertices at a %.3g mm size (%.3g with the panels before it)",
                           (int)c->desc.max_vertices, (int)p, wr__msh_pname(c, p), m->area, m->perimeter, need,
                           1e3 * m->r0, total);
    }
    return WR_OK;
}

/* ---- stage: seam pairing (Sec. 4.2.4) ------------------------------------------------------------- */
typedef struct wr__msh_insert {
    int32_t edge;
    double t;
    int32_t tag; /* 2*side_id + (0 from, 1 to) */
} wr__msh_insert;

static int wr__msh_insert_cmp(const void *a, const void *b) {
    const wr__msh_insert *x = (const wr__msh_insert *)a, *y = (const wr__msh_insert *)b;
    if (x->edge != y->edge) return x->edge < y->edge ? -1 : 1;
    if (x->t != y->t) return x->t < y->t ? -1 : 1;
    return x->tag < y->tag ? -1 : (x->tag > y->tag);
}

/* Both ends of every side on their panels' outer loops, sorted along the loops. */
static wr_status wr__msh_locate_seam_ends(wr__msh_ctx *c, wr__msh_insert *ins) {
    int32_t i, k, n = 0;
    wr_status st;
    for (i = 0; i < c->pat->n_seams; ++i)
        for (k = 0; k < 2; ++k) {
            const wr_pattern_seam_side *sd = k ? &c->pat->seams[i].b : &c->pat->seams[i].a;
            wr__msh_side *S = &c->sides[2 * i + k];
            char what[64];
            S->seam = i;
            S->which = k;
            S->panel = sd->panel;
            S->reverse = sd->reverse != 0;
            snprintf(what, sizeof what, "seams[%d].%c.from", (int)i, k ? 'b' : 'a');
            st = wr_pattern_locate_on_outer(c->pat, sd->panel, sd->from, &ins[n].edge, &ins[n].t, what, i, c->diag);
            if (st != WR_OK) return st;
            ins[n++].tag = 2 * (2 * i + k);
            snprintf(what, sizeof what, "seams[%d].%c.to", (int)i, k ? 'b' : 'a');
            st = wr_pattern_locate_on_outer(c->pat, sd->panel, sd->to, &ins[n].edge, &ins[n].t, what, i, c->diag);
            if (st != WR_OK) return st;
            ins[n++].tag = 2 * (2 * i + k) + 1;
        }
    c->n_sides = 2 * c->pat->n_seams;
    qsort(ins, (size_t)n, sizeof *ins, wr__msh_insert_cmp);
    return WR_OK;
}

/* Panel p's outer loop with the seam ends strictly inside edges inserted (deduplicated), the sides'
 * end vertices, and break flags at corners. */
static wr_status wr__msh_refine_loop(wr__msh_ctx *c, int32_t p, const wr__msh_insert *ins, int32_t n_ins) {
    const wr_pattern_curve *O = &c->pat->panels[p].outer;
    wr__msh_loop *w = &c->loops[p];
    wr__msh_dbuf L;
    int32_t j, q;
    memset(&L, 0, sizeof L);
    for (j = 0; j < O->n; ++j) {
        int32_t vj = L.n / 2;
        if (!wr__msh_dpush2(&L, O->xy[2 * j], O->xy[2 * j + 1])) goto nomem;
        for (q = 0; q < n_ins; ++q) {
            wr__msh_side *sd = &c->sides[ins[q].tag / 2];
            int32_t *end = (ins[q].tag & 1) ? &sd->v_to : &sd->v_from;
            if (sd->panel != p || ins[q].edge != j) continue;
            if (ins[q].t > 0.0) {
                const double *a = O->xy + 2 * j, *b = O->xy + 2 * ((j + 1) % O->n);
                double x = a[0] + ins[q].t * (b[0] - a[0]), y = a[1] + ins[q].t * (b[1] - a[1]);
                int32_t last = L.n / 2 - 1;
                if (!(L.v[2 * last] == x && L.v[2 * last + 1] == y) && !wr__msh_dpush2(&L, x, y)) goto nomem;
                *end = L.n / 2 - 1;
            } else {
                *end = vj;
            }
        }
    }
    w->xy = L.v;
    w->n = L.n / 2;
    w->brk = (int *)wr_calloc_array((size_t)w->n, sizeof(int));
    w->side_of_edge = (int32_t *)wr_alloc_array((size_t)w->n, sizeof(int32_t));
    w->forced = (int32_t *)wr_calloc_array((size_t)w->n, sizeof(int32_t));
    if (!w->brk || !w->side_of_edge || !w->forced) return wr__msh_nomem(c, -1);
    for (j = 0; j < w->n; ++j) {
        w->side_of_edge[j] = -1;
        if (wr__msh_turn(w->xy, w->n, j) > WR_MESHER_CORNER_DEG) w->brk[j] = 1;
    }
    return WR_OK;
nomem:
    wr_free(L.v);
    return wr__msh_nomem(c, -1);
}

/* Walk side k over its loop: mark the edges it covers, refuse overlaps and corners inside the range. */
static wr_status wr__msh_walk_side(wr__msh_ctx *c, int32_t k) {
    wr__msh_side *sd = &c->sides[k];
    wr__msh_loop *w = &c->loops[sd->panel];
    int32_t v = sd->v_from, steps = 0;
    if (sd->v_from == sd->v_to)
        return wr_fail(c->diag, WR_ERR_GEOMETRY, sd->seam, "seams[%d].%c: from and to coincide (zero length)",
                       (int)sd->seam, sd->which ? 'b' : 'a');
    while (v != sd->v_to) {
        int32_t e = sd->reverse ? (v + w->n - 1) % w->n : v; /* edge walked */
        int32_t nv = wr__msh_step(v, w->n, sd->reverse);
        if (w->side_of_edge[e] >= 0) {
            const wr__msh_side *o = &c->sides[w->side_of_edge[e]];
            return wr_fail(c->diag, WR_ERR_GEOMETRY, sd->seam, "seams[%d].%c overlaps seams[%d].%c on panel %d '%s'",
                           (int)sd->seam, sd->which ? 'b' : 'a', (int)o->seam, o->which ? 'b' : 'a', (int)sd->panel,
                           wr__msh_pname(c, sd->panel));
        }
        w->side_of_edge[e] = k;
        if (nv != sd->v_to && w->brk[nv])
            return wr_fail(c->diag, WR_ERR_GEOMETRY, sd->seam,
                           "seams[%d].%c passes a corner of panel %d '%s' (turn > %g deg); split the seam there",
                           (int)sd->seam, sd->which ? 'b' : 'a', (int)sd->panel, wr__msh_pname(c, sd->panel),
                           WR_MESHER_CORNER_DEG);
        v = nv;
        if (++steps > w->n) break;
    }
    w->brk[sd->v_from] = 1;
    w->brk[sd->v_to] = 1;
    return WR_OK;
}

static wr_status wr__msh_pair_seams(wr__msh_ctx *c) {
    wr__msh_insert *ins = (wr__msh_insert *)wr_alloc_array((size_t)(4 * c->pat->n_seams + 1), sizeof(wr__msh_insert));
    wr_status st;
    int32_t p, k;
    double t0 = wr_time_seconds();
    if (!ins) return wr__msh_nomem(c, -1);
    st = wr__msh_locate_seam_ends(c, ins);
    for (p = 0; p < c->pat->n_panels && st == WR_OK; ++p) st = wr__msh_refine_loop(c, p, ins, 4 * c->pat->n_seams);
    for (k = 0; k < c->n_sides && st == WR_OK; ++k) st = wr__msh_walk_side(c, k);
    wr_free(ins);
    c->res->report.t_sizing += wr_time_seconds() - t0;
    return st;
}

/* Segment count N of seam pair (k, k+1) when one of its sides is on panel p: max of the two sides'
 * natural counts, each measured on its own panel's map in its own stretched space. */
static wr_status wr__msh_seam_counts(wr__msh_ctx *c, int32_t p) {
    int32_t k, s2;
    for (k = 0; k < c->n_sides; k += 2) {
        wr__msh_side *sa = &c->sides[k], *sb = &c->sides[k + 1];
        if ((sa->panel != p && sb->panel != p) || sa->N != 0) continue;
        for (s2 = 0; s2 < 2; ++s2) {
            const wr__msh_side *sd = &c->sides[k + s2];
            const wr__msh_loop *w = &c->loops[sd->panel];
            const wr_sizing_panel *m = wr__msh_map(c, sd->panel);
            wr__msh_dbuf pc;
            int32_t v = sd->v_from, cnt;
            memset(&pc, 0, sizeof pc);
            for (;;) {
                double q[2];
                wr_sizing_panel_to_stretched(m, w->xy + 2 * v, q);
                if (!wr__msh_dpush2(&pc, q[0], q[1])) {
                    wr_free(pc.v);
                    return wr__msh_nomem(c, p);
                }
                if (v == sd->v_to) break;
                v = wr__msh_step(v, w->n, sd->reverse);
            }
            cnt = wr__msh_piece(pc.v, pc.n / 2, m, 0, NULL);
            wr_free(pc.v);
            if (cnt < 0) return wr__msh_nomem(c, p);
            if (cnt > sa->N) sa->N = cnt;
        }
        sb->N = sa->N;
    }
    for (k = 0; k < c->n_sides; ++k) {
        const wr__msh_side *sd = &c->sides[k];
        /* the piece in loop order starts at from (forward walk) or at to (reverse walk) */
        if (sd->panel == p) c->loops[p].forced[sd->reverse ? sd->v_to : sd->v_from] = sd->N;
    }
    return WR_OK;
}

/* ---- per panel: discretise the curves at ∫ ds/h (Sec. 4.3) ----------------------------------------- */
/* The refined outer loop: pieces between breaks (corners, seam ends), seam pieces at their count N. */
static wr_status wr__msh_discretise_outer(wr__msh_ctx *c, int32_t p, wr__msh_panel_run *r) {
    wr__msh_loop *w = &c->loops[p];
    const wr_sizing_panel *m = wr__msh_map(c, p);
    int32_t j, anybrk = 0;
    r->loop = (double *)wr_alloc_array((size_t)w->n, 2 * sizeof(double));
    r->index_of = (int32_t *)wr_alloc_array((size_t)w->n, sizeof(int32_t));
    if (!r->loop || !r->index_of) return wr__msh_nomem(c, p);
    for (j = 0; j < w->n; ++j) wr_sizing_panel_to_stretched(m, w->xy + 2 * j, r->loop + 2 * j);
    for (j = 0; j < w->n; ++j) anybrk |= w->brk[j];
    if (!anybrk) w->brk[0] = 1;
    if (wr__msh_loop_discretise(r->loop, w->n, w->brk, w->forced, m, &r->outer, r->index_of) < 0)
        return wr__msh_nomem(c, p);
    return WR_OK;
}

/* Holes: natural counts, breaks at corners and at vertex 0. */
static wr_status wr__msh_discretise_holes(wr__msh_ctx *c, int32_t p, wr__msh_panel_run *r) {
    const wr_pattern_panel *pn = &c->pat->panels[p];
    const wr_sizing_panel *m = wr__msh_map(c, p);
    int32_t j, k;
    for (j = 0; j < pn->n_holes; ++j) {
        const wr_pattern_curve *hcv = &pn->holes[j];
        double *hs = (double *)wr_alloc_array((size_t)hcv->n, 2 * sizeof(double));
        int *hb = (int *)wr_calloc_array((size_t)hcv->n, sizeof(int));
        int32_t *hi = (int32_t *)wr_alloc_array((size_t)hcv->n, sizeof(int32_t));
        int32_t before = r->holes.n, ok = -1;
        if (hs && hb && hi) {
            for (k = 0; k < hcv->n; ++k) {
                wr_sizing_panel_to_stretched(m, hcv->xy + 2 * k, hs + 2 * k);
                hb[k] = wr__msh_turn(hcv->xy, hcv->n, k) > WR_MESHER_CORNER_DEG;
            }
            hb[0] = 1;
            ok = wr__msh_loop_discretise(hs, hcv->n, hb, NULL, m, &r->holes, hi);
        }
        wr_free(hs);
        wr_free(hb);
        wr_free(hi);
        if (ok < 0 || !wr__msh_ipush(&r->hole_n, (r->holes.n - before) / 2)) return wr__msh_nomem(c, p);
    }
    return WR_OK;
}

/* Point k of a polyline moved by `off` along the mitred normal (average of the adjacent segment
 * normals, scaled by 1/cos of the half angle, capped at 4×). */
static void wr__msh_offset_point(const double *xy, int32_t n, int32_t k, double off, double *q) {
    double nx = 0.0, ny = 0.0, sx, sy, sl, dotn = 1.0;
    int32_t a2;
    q[0] = xy[2 * k];
    q[1] = xy[2 * k + 1];
    if (off == 0.0) return;
    for (a2 = k - 1; a2 <= k; ++a2) {
        if (a2 < 0 || a2 + 1 >= n) continue;
        sx = xy[2 * a2 + 2] - xy[2 * a2];
        sy = xy[2 * a2 + 3] - xy[2 * a2 + 1];
        sl = sqrt(sx * sx + sy * sy);
        if (sl > 0.0) {
            nx += -sy / sl;
            ny += sx / sl;
        }
    }
    sl = sqrt(nx * nx + ny * ny);
    if (sl > 0.0) {
        nx /= sl;
        ny /= sl;
    }
    if (k > 0) {
        sx = xy[2 * k] - xy[2 * k - 2];
        sy = xy[2 * k + 1] - xy[2 * k - 1];
        sl = sqrt(sx * sx + sy * sy);
        if (sl > 0.0) dotn = (-sy / sl) * nx + (sx / sl) * ny;
    }
    if (dotn < 0.25) dotn = 0.25;
    q[0] += off * nx / dotn;
    q[1] += off * ny / dotn;
}

/* Move a line end lying on the boundary inwards by WR_MESHER_TRIM_FACTOR × local sizing (at most 0.45
 * of its segment): the sampler needs constraint lines strictly inside. end = 0 first, 1 last point. */
static void wr__msh_trim_end(const wr_sizing_panel *m, double *poly, int32_t n, int end) {
    double *e0 = end ? poly + 2 * (n - 1) : poly, *e1 = end ? poly + 2 * (n - 2) : poly + 2;
    double dx = e1[0] - e0[0], dy = e1[1] - e0[1], L = sqrt(dx * dx + dy * dy);
    double cut = WR_MESHER_TRIM_FACTOR * wr_sizing_panel_eval_stretched(m, e0[0], e0[1]);
    if (cut > 0.45 * L) cut = 0.45 * L;
    if (L > 0.0) {
        e0[0] += dx / L * cut;
        e0[1] += dy / L * cut;
    }
}

/* One constraint line (kind 0 shirring, 1 quilt stitch, 2 fold or fold parallel at `off`): offset,
 * map to stretched space, trim ends on the boundary, discretise with a break at every input vertex. */
static wr_status wr__msh_constraint_line(wr__msh_ctx *c, int32_t p, wr__msh_panel_run *r, const double *xy, int32_t n,
                                         double off, int32_t kind, int32_t idx) {
    const wr_sizing_panel *m = wr__msh_map(c, p);
    int32_t k, before = r->lines.n;
    int on0 = 0, on1 = 0;
    double *poly;
    if (kind != 2 && wr_pattern_check_line(c->pat, p, xy, n, "lines", idx, 1, &on0, &on1, NULL) != WR_OK) on0 = on1 = 0;
    poly = (double *)wr_alloc_array((size_t)n, 2 * sizeof(double));
    if (!poly) return wr__msh_nomem(c, p);
    for (k = 0; k < n; ++k) {
        double q[2];
        wr__msh_offset_point(xy, n, k, off, q);
        wr_sizing_panel_to_stretched(m, q, poly + 2 * k);
    }
    if (on0 && n >= 2) wr__msh_trim_end(m, poly, n, 0);
    if (on1 && n >= 2) wr__msh_trim_end(m, poly, n, 1);
    if (!wr__msh_dpush2(&r->lines, poly[0], poly[1])) goto nomem;
    for (k = 0; k + 1 < n; ++k)
        if (wr__msh_piece(poly + 2 * k, 2, m, 0, &r->lines) < 0 ||
            !wr__msh_dpush2(&r->lines, poly[2 * k + 2], poly[2 * k + 3]))
            goto nomem;
    wr_free(poly);
    if (!wr__msh_ipush(&r->line_n, (r->lines.n - before) / 2) || !wr__msh_ipush2(&r->line_lab, kind, idx))
        return wr__msh_nomem(c, p);
    return WR_OK;
nomem:
    wr_free(poly);
    return wr__msh_nomem(c, p);
}

/* Constraint lines of panel p, in this order: shirrings, quilt stitches, folds (line, +offset, −offset). */
static wr_status wr__msh_discretise_lines(wr__msh_ctx *c, int32_t p, wr__msh_panel_run *r) {
    const wr_pattern *pat = c->pat;
    int32_t i, u;
    wr_status st = WR_OK;
    for (i = 0; i < pat->n_shirrings && st == WR_OK; ++i)
        if (pat->shirrings[i].panel == p)
            st = wr__msh_constraint_line(c, p, r, pat->shirrings[i].xy, pat->shirrings[i].n, 0.0, 0, i);
    for (i = 0; i < pat->n_quilts && st == WR_OK; ++i)
        for (u = 0; u < pat->quilts[i].n_lines && st == WR_OK && pat->quilts[i].panel == p; ++u)
            st = wr__msh_constraint_line(c, p, r, pat->quilts[i].lines[u].xy, pat->quilts[i].lines[u].n, 0.0, 1, i);
    for (i = 0; i < pat->n_folds && st == WR_OK; ++i) {
        const wr_pattern_fold *fd = &pat->folds[i];
        double off = fd->offset > 0.0 ? fd->offset : WR_MESHER_DEFAULT_FOLD_OFFSET;
        for (u = 0; u < 3 && st == WR_OK && fd->panel == p; ++u)
            st = wr__msh_constraint_line(c, p, r, fd->xy, fd->n, off * (u == 0 ? 0.0 : u == 1 ? 1.0 : -1.0), 2, i);
    }
    return st;
}

static wr_status wr__msh_discretise(wr__msh_ctx *c, int32_t p, wr__msh_panel_run *r) {
    double t0 = wr_time_seconds();
    wr_status st = wr__msh_discretise_outer(c, p, r);
    if (st == WR_OK) st = wr__msh_discretise_holes(c, p, r);
    if (st == WR_OK) st = wr__msh_discretise_lines(c, p, r);
    c->res->report.t_discretise += wr_time_seconds() - t0;
    if (st != WR_OK) return st;
    /* The curve points become mesh vertices: when they alone exceed the budget, refuse now, before
     * the sampler's crossing checks over them. */
    if ((double)c->rest.n / 2 + (double)(r->outer.n + r->holes.n + r->lines.n) / 2 > (double)c->desc.max_vertices)
        return wr_fail(c->diag, WR_ERR_BUDGET, p,
                       "vertex budget of %d exceeded at panels[%d] '%s': its curves alone need %.0f points at the sizing",
                       (int)c->desc.max_vertices, (int)p, wr__msh_pname(c, p),
                       (double)(r->outer.n + r->holes.n + r->lines.n) / 2);
    return WR_OK;
}

/* ---- per panel: Poisson fill in stretched space (Sec. 4.3) --------------------------------------- */
/* The pattern item behind the sampler's curve c (its numbering: 0 outer, 1 + i hole i, 1 + n_holes + j
 * line j in our order: shirrings, quilt lines, folds with their two parallels). */
static void wr__msh_curve_name(const wr__msh_panel_run *r, int32_t c, char *buf, size_t len) {
    static const char *const kinds[3] = {"shirrings", "quilts", "folds"};
    int32_t j = c - 1 - r->hole_n.n;
    if (c == 0)
        snprintf(buf, len, "outer loop = the panel's outline");
    else if (c >= 1 && c <= r->hole_n.n)
        snprintf(buf, len, "hole %d = holes[%d]", (int)(c - 1), (int)(c - 1));
    else if (j >= 0 && j < r->line_n.n)
        snprintf(buf, len, "polyline %d = %s[%d]%s", (int)j, kinds[r->line_lab.v[2 * j]], (int)r->line_lab.v[2 * j + 1],
                 r->line_lab.v[2 * j] == 2 ? " (the fold line or a parallel)" : "");
    else
        snprintf(buf, len, "curve %d", (int)c);
}

/* The sampler's failure, named for the pattern: budget errors name the panel and the budget; curve
 * errors name the techniques behind the curves from the sampler's structured location (diag->curve,
 * diag->other_curve), and diag->part = the panel. */
static wr_status wr__msh_sampling_failure(wr__msh_ctx *c, int32_t p, const wr__msh_panel_run *r, wr_status st) {
    char msg[WR_DIAG_MESSAGE_LEN], n1[96], n2[96];
    int32_t cu = c->diag ? c->diag->curve : -1, oc = c->diag ? c->diag->other_curve : -1;
    wr_status out;
    snprintf(msg, sizeof msg, "%s", c->diag ? c->diag->message : "");
    if (st == WR_ERR_BUDGET)
        return wr_fail(c->diag, st, p, "vertex budget of %d exceeded at panels[%d] '%s' (%s)", (int)c->desc.max_vertices,
                       (int)p, wr__msh_pname(c, p), msg);
    n1[0] = n2[0] = 0;
    if (cu >= 0) wr__msh_curve_name(r, cu, n1, sizeof n1);
    if (oc >= 0 && oc != cu) wr__msh_curve_name(r, oc, n2, sizeof n2);
    out = wr_fail(c->diag, st, p, "panels[%d] '%s': %.300s%s%s%s%s%s", (int)p, wr__msh_pname(c, p), msg,
                  cu >= 0 ? " [" : "", n1, n2[0] ? "; " : "", n2, cu >= 0 ? "]" : "");
    if (c->diag) { /* wr_fail reset the location: restore the sampler's, with the panel */
        c->diag->part = p;
        c->diag->curve = cu;
        c->diag->other_curve = oc;
    }
    return out;
}

/* Our curves as the sampler's domain: every curve point is kept as given and every curve edge is a
 * constraint (wr_poisson_fill), so the samples keep their clearance from exactly the segments the
 * CDT receives and the first n_fixed points are ours, in our order. */
static wr_status wr__msh_sample(wr__msh_ctx *c, int32_t p, wr__msh_panel_run *r) {
    wr_poisson_domain dom;
    wr_poisson_desc pd;
    int32_t j, off;
    wr_status st;
    r->hole_curves = (wr_poisson_curve *)wr_calloc_array((size_t)r->hole_n.n + 1, sizeof(wr_poisson_curve));
    r->line_curves = (wr_poisson_curve *)wr_calloc_array((size_t)r->line_n.n + 1, sizeof(wr_poisson_curve));
    if (!r->hole_curves || !r->line_curves) return wr__msh_nomem(c, p);
    for (j = 0, off = 0; j < r->hole_n.n; off += r->hole_n.v[j++]) {
        r->hole_curves[j].xy = r->holes.v + 2 * off;
        r->hole_curves[j].n = r->hole_n.v[j];
    }
    for (j = 0, off = 0; j < r->line_n.n; off += r->line_n.v[j++]) {
        r->line_curves[j].xy = r->lines.v + 2 * off;
        r->line_curves[j].n = r->line_n.v[j];
    }
    memset(&dom, 0, sizeof dom);
    dom.outer.xy = r->outer.v;
    dom.outer.n = r->outer.n / 2;
    dom.outer.closed = 1;
    dom.holes = r->hole_curves;
    dom.n_holes = r->hole_n.n;
    dom.lines = r->line_curves;
    dom.n_lines = r->line_n.n;
    memset(&pd, 0, sizeof pd);
    pd.seed = c->desc.seed + (uint64_t)p * 0x9E3779B97F4A7C15ULL;
    pd.radius_factor = c->desc.radius_factor;
    pd.max_points = c->desc.max_vertices - c->rest.n / 2;
    if (pd.max_points < 3) pd.max_points = 3;
    st = wr_poisson_fill(&dom, wr__msh_size_cb, (void *)wr__msh_map(c, p), &pd, &r->samples, c->diag);
    return st == WR_OK ? WR_OK : wr__msh_sampling_failure(c, p, r, st);
}

/* ---- per panel: the constrained Delaunay triangulation ---------------------------------------------- */
/* One seed strictly inside each hole: an edge midpoint nudged into the hole (checked). */
static wr_status wr__msh_hole_seeds(wr__msh_ctx *c, int32_t p, wr__msh_panel_run *r) {
    int32_t k;
    if (r->hole_n.n == 0) return WR_OK;
    r->hole_seeds = (double *)wr_alloc_array((size_t)r->hole_n.n, 2 * sizeof(double));
    if (!r->hole_seeds) return wr__msh_nomem(c, p);
    for (k = 0; k < r->hole_n.n; ++k) {
        const double *H = r->hole_curves[k].xy;
        int32_t nh = r->hole_curves[k].n, e2, found = 0;
        double sgn = wr_polygon_area(H, nh) > 0.0 ? 1.0 : -1.0; /* CCW hole: interior on the left */
        for (e2 = 0; e2 < nh && !found; ++e2) {
            const double *a = H + 2 * e2, *b = H + 2 * ((e2 + 1) % nh);
            double dx = b[0] - a[0], dy = b[1] - a[1], L = sqrt(dx * dx + dy * dy), f2;
            if (!(L > 0.0)) continue;
            for (f2 = 1e-2; f2 >= 1e-6 && !found; f2 *= 0.1) {
                double x = 0.5 * (a[0] + b[0]) - sgn * dy * f2, y = 0.5 * (a[1] + b[1]) + sgn * dx * f2;
                if (wr_point_in_polygon(H, nh, x, y)) {
                    r->hole_seeds[2 * k] = x;
                    r->hole_seeds[2 * k + 1] = y;
                    found = 1;
                }
            }
        }
        if (!found)
            return wr_fail(c->diag, WR_ERR_GEOMETRY, p, "panels[%d] '%s': hole %d is too thin to seed", (int)p,
                           wr__msh_pname(c, p), (int)k);
    }
    return WR_OK;
}

/* No refinement: no Steiner points, so the seam counts stay exact. */
static wr_status wr__msh_triangulate(wr__msh_ctx *c, int32_t p, wr__msh_panel_run *r) {
    wr_cdt_input ci;
    wr_cdt_desc cd;
    wr_status st = wr__msh_hole_seeds(c, p, r);
    if (st != WR_OK) return st;
    memset(&ci, 0, sizeof ci);
    ci.holes = r->hole_seeds;
    ci.n_holes = r->hole_n.n;
    ci.points = r->samples.points; /* our curve points, then the interior samples */
    ci.n_points = r->samples.n_points;
    ci.segments = r->samples.segments; /* our curve edges */
    ci.n_segments = r->samples.n_segments;
    memset(&cd, 0, sizeof cd);
    cd.seed = c->desc.seed + 1;
    st = wr_cdt_triangulate(&ci, &cd, &r->tri, c->diag);
    if (st != WR_OK) {
        char msg[WR_DIAG_MESSAGE_LEN];
        snprintf(msg, sizeof msg, "%s", c->diag ? c->diag->message : "");
        return wr_fail(c->diag, st, p, "panels[%d] '%s': triangulation: %s", (int)p, wr__msh_pname(c, p), msg);
    }
    return WR_OK;
}

/* Room for nv more output vertices and nf more faces (amortised doubling). */
static int wr__msh_ireserve(wr__msh_ibuf *b, int32_t more) {
    int64_t need = (int64_t)b->n + more, nc = b->cap ? b->cap : 64;
    int32_t *nv;
    if (need <= b->cap) return 1;
    while (nc < need) nc *= 2;
    if (nc > INT32_MAX) return 0;
    nv = (int32_t *)wr_realloc_array(b->v, (size_t)nc, sizeof(int32_t));
    if (!nv) return 0;
    b->v = nv;
    b->cap = (int32_t)nc;
    return 1;
}
static int wr__msh_dreserve(wr__msh_dbuf *b, int32_t more) {
    int64_t need = (int64_t)b->n + more, nc = b->cap ? b->cap : 64;
    if (need <= b->cap) return 1;
    while (nc < need) nc *= 2;
    return nc <= INT32_MAX && wr__msh_dbuf_reserve(b, (int32_t)nc);
}
static int wr__msh_reserve(wr__msh_ctx *c, int32_t nv, int32_t nf) {
    return nv < INT32_MAX / 3 && nf < INT32_MAX / 3 && wr__msh_dreserve(&c->rest, 2 * nv) &&
           wr__msh_dreserve(&c->sizing, nv) && wr__msh_dreserve(&c->sizing_warp, nv) &&
           wr__msh_dreserve(&c->sizing_weft, nv) && wr__msh_ireserve(&c->faces, 3 * nf) &&
           wr__msh_ireserve(&c->face_panel, nf);
}

/* ---- per panel: the output numbering (ON THE OUTPUT) ------------------------------------------------ */
/* newid[v] = the panel-local output id of CDT vertex v: the vertices of the sampler's first n_fixed
 * points (our curve points; a prefix of the CDT's numbering, which keeps input order) as they are,
 * then the others in the order wr_cdt_hilbert_order gives (WR_MESHER_ORDER_SPATIAL) or as the CDT
 * numbers them. */
static wr_status wr__msh_panel_order(wr__msh_ctx *c, int32_t p, const wr__msh_panel_run *r, int32_t *newid) {
    const wr_cdt_result *cr = &r->tri;
    int32_t nv = cr->n_points, j, k, n_curve = 0, n_rest = 0, *rest_ids;
    wr_status st;
    for (j = 0; j < nv; ++j) newid[j] = -1;
    for (j = 0; j < r->samples.n_fixed && j < cr->n_map; ++j)
        if (newid[cr->point_map[j]] < 0) newid[cr->point_map[j]] = 0;
    for (j = 0; j < nv; ++j)
        if (newid[j] == 0) newid[j] = n_curve++ - nv - 1; /* marked: -nv-1 .. -2, apart from -1 */
    if (c->desc.vertex_order == WR_MESHER_ORDER_SAMPLED) {
        for (j = 0, k = n_curve; j < nv; ++j) newid[j] = newid[j] < -1 ? newid[j] + nv + 1 : k++;
        return WR_OK;
    }
    rest_ids = (int32_t *)wr_alloc_array((size_t)(nv + 1), sizeof(int32_t));
    if (!rest_ids) return wr__msh_nomem(c, p);
    for (j = 0; j < nv; ++j)
        if (newid[j] == -1) rest_ids[n_rest++] = j;
    st = wr_cdt_hilbert_order(cr->points, rest_ids, n_rest, rest_ids, c->diag);
    if (st == WR_OK) {
        for (j = 0; j < nv; ++j)
            if (newid[j] < -1) newid[j] += nv + 1;
        for (k = 0; k < n_rest; ++k) newid[rest_ids[k]] = n_curve + k;
    }
    wr_free(rest_ids);
    return st == WR_OK ? WR_OK : wr__msh_nomem(c, p);
}

/* The panel's faces appended in output numbering: the CDT's triangles renumbered in place by newid
 * (their corners keep their rotation), then WR_MESHER_ORDER_SPATIAL: sorted by their largest corner
 * id (a counting sort, CDT order among equals, written straight to the output), else in the CDT's
 * order. */
static wr_status wr__msh_append_faces(wr__msh_ctx *c, int32_t p, wr__msh_panel_run *r, const int32_t *newid) {
    int32_t *T = r->tri.triangles, nf = r->tri.n_triangles, nv = r->tri.n_points, vbase = c->rest.n / 2, j, k, *cnt;
    int32_t *out = c->faces.v + c->faces.n;
    for (j = 0; j < 3 * nf; ++j) T[j] = vbase + newid[T[j]];
    c->faces.n += 3 * nf;
    if (c->desc.vertex_order == WR_MESHER_ORDER_SAMPLED) {
        memcpy(out, T, sizeof(int32_t) * 3 * (size_t)nf);
        return WR_OK;
    }
    cnt = (int32_t *)wr_calloc_array((size_t)(nv + 2), sizeof(int32_t));
    if (!cnt) return wr__msh_nomem(c, p);
    for (j = 0; j < nf; ++j) {
        int32_t a = T[3 * j] > T[3 * j + 1] ? T[3 * j] : T[3 * j + 1];
        ++cnt[(a > T[3 * j + 2] ? a : T[3 * j + 2]) - vbase + 2];
    }
    for (j = 0; j < nv; ++j) cnt[j + 2] += cnt[j + 1];
    for (j = 0; j < nf; ++j) {
        int32_t a = T[3 * j] > T[3 * j + 1] ? T[3 * j] : T[3 * j + 1], *o;
        o = out + 3 * cnt[(a > T[3 * j + 2] ? a : T[3 * j + 2]) - vbase + 1]++;
        for (k = 0; k < 3; ++k) o[k] = T[3 * j + k];
    }
    wr_free(cnt);
    return WR_OK;
}

/* ---- per panel: append to the output -------------------------------------------------------------- */
/* Vertices mapped back to the pattern with their sizing, faces, constraint segments, and the global
 * vertex ids of this panel's seam sides in walk order; numbered by wr__msh_panel_order. */
static wr_status wr__msh_append(wr__msh_ctx *c, int32_t p, wr__msh_panel_run *r) {
    const wr_cdt_result *cr = &r->tri;
    const wr_sizing_panel *m = wr__msh_map(c, p);
    wr_mesher_panel_info *pi = &c->res->panels[p];
    int32_t j, k, vbase = c->rest.n / 2, n_out = r->outer.n / 2, *newid;
    double *h_cdt;
    wr_status st;
    if (vbase + cr->n_points > c->desc.max_vertices)
        return wr_fail(c->diag, WR_ERR_BUDGET, p, "vertex budget of %d exceeded at panels[%d] '%s'",
                       (int)c->desc.max_vertices, (int)p, wr__msh_pname(c, p));
    if (!cr->exterior_carved)
        return wr_fail(c->diag, WR_ERR_GEOMETRY, p, "panels[%d] '%s': triangulation did not carve the exterior", (int)p,
                       wr__msh_pname(c, p));
    if (!wr__msh_reserve(c, cr->n_points, cr->n_triangles)) return wr__msh_nomem(c, p);
    newid = (int32_t *)wr_alloc_array((size_t)(cr->n_points + 1), sizeof(int32_t));
    h_cdt = (double *)wr_alloc_array((size_t)(cr->n_points + 1), sizeof(double));
    st = newid && h_cdt ? wr__msh_panel_order(c, p, r, newid) : wr__msh_nomem(c, p);
    if (st != WR_OK) goto done;
    /* the sizing the sampler evaluated at each point (input i → CDT vertex point_map[i]; no Steiner
     * points), then every vertex written once to its output slot */
    for (j = 0; j < cr->n_map && j < r->samples.n_points; ++j) h_cdt[cr->point_map[j]] = r->samples.sizing[j];
    for (j = 0; j < cr->n_points; ++j) {
        int32_t v = vbase + newid[j];
        double h = h_cdt[j];
        wr_sizing_panel_to_pattern(m, cr->points + 2 * j, c->rest.v + 2 * v);
        c->sizing.v[v] = h;
        c->sizing_warp.v[v] = h * pi->r_warp / pi->r0;
        c->sizing_weft.v[v] = h * pi->r_weft / pi->r0;
    }
    pi->f_begin = c->faces.n / 3;
    if ((st = wr__msh_append_faces(c, p, r, newid)) != WR_OK) goto done;
    c->rest.n += 2 * cr->n_points;
    c->sizing.n += cr->n_points;
    c->sizing_warp.n += cr->n_points;
    c->sizing_weft.n += cr->n_points;
    for (j = 0; j < cr->n_triangles; ++j) c->face_panel.v[c->face_panel.n++] = p;
    pi->f_end = c->faces.n / 3;
    pi->v_begin = vbase;
    pi->v_end = c->rest.n / 2;
    for (j = 0; j < r->samples.n_segments && st == WR_OK; ++j)
        if (!wr__msh_ipush2(&c->segments, vbase + newid[cr->point_map[r->samples.segments[2 * j]]],
                            vbase + newid[cr->point_map[r->samples.segments[2 * j + 1]]]))
            st = wr__msh_nomem(c, p);
    for (k = 0; k < c->n_sides && st == WR_OK; ++k) {
        wr__msh_side *sd = &c->sides[k];
        int32_t a5, c5;
        if (sd->panel != p) continue;
        a5 = r->index_of[sd->reverse ? sd->v_to : sd->v_from];
        sd->global = (int32_t *)wr_alloc_array((size_t)(sd->N + 1), sizeof(int32_t));
        if (!sd->global) {
            st = wr__msh_nomem(c, p);
            break;
        }
        for (c5 = 0; c5 <= sd->N; ++c5)
            sd->global[sd->reverse ? sd->N - c5 : c5] = vbase + newid[cr->point_map[(a5 + c5) % n_out]];
    }
done:
    wr_free(newid);
    wr_free(h_cdt);
    return st;
}

/* Sec. 4.3 for one panel: discretise → Poisson fill → CDT → append. */
static wr_status wr__msh_mesh_panel(wr__msh_ctx *c, int32_t p) {
    wr__msh_panel_run r;
    wr_status st;
    double t0;
    memset(&r, 0, sizeof r);
    st = wr__msh_seam_counts(c, p);
    if (st == WR_OK) st = wr__msh_discretise(c, p, &r);
    t0 = wr_time_seconds();
    if (st == WR_OK) st = wr__msh_sample(c, p, &r);
    c->res->report.t_poisson += wr_time_seconds() - t0;
    t0 = wr_time_seconds();
    if (st == WR_OK) st = wr__msh_triangulate(c, p, &r);
    c->res->report.t_cdt += wr_time_seconds() - t0;
    t0 = wr_time_seconds();
    if (st == WR_OK) st = wr__msh_append(c, p, &r);
    c->res->report.t_assemble += wr_time_seconds() - t0;
    wr__msh_panel_run_free(&r);
    if (st == WR_OK) wr__msh_progress(c, "panel", p);
    return st;
}

/* ---- assemble: the seam table, the mesh, sewing ---------------------------------------------------- */
static wr_status wr__msh_seam_table(wr__msh_ctx *c) {
    int32_t i, j;
    for (i = 0; i < c->pat->n_seams; ++i) {
        const wr__msh_side *a = &c->sides[2 * i], *b = &c->sides[2 * i + 1];
        for (j = 0; j <= a->N; ++j)
            if (!wr__msh_ipush2(&c->seam_pairs, a->global[j], b->global[j]) || !wr__msh_ipush(&c->seam_pair_seam, i))
                return wr__msh_nomem(c, -1);
    }
    return WR_OK;
}

/* Union-find over the seam pairs (chains of seams collapse consistently); rep[v] = the smallest vertex
 * of v's class, newid[rep] = its id in the sewn mesh. Returns the number of sewn vertices. */
static int32_t wr__msh_sew_classes(const wr__msh_ctx *c, int32_t nv, int32_t *rep, int32_t *newid) {
    int32_t j, nn = 0;
    for (j = 0; j < nv; ++j) rep[j] = j;
    for (j = 0; j < c->seam_pairs.n / 2; ++j) {
        int32_t x = c->seam_pairs.v[2 * j], y = c->seam_pairs.v[2 * j + 1];
        while (rep[x] != x) x = rep[x] = rep[rep[x]];
        while (rep[y] != y) y = rep[y] = rep[rep[y]];
        if (x != y) {
            if (x < y)
                rep[y] = x;
            else
                rep[x] = y;
        }
    }
    for (j = 0; j < nv; ++j) {
        int32_t x = j;
        while (rep[x] != x) x = rep[x];
        rep[j] = x;
    }
    for (j = 0; j < nv; ++j) newid[j] = (rep[j] == j) ? nn++ : -1;
    return nn;
}

/* Merge side b into side a: one vertex per class at its representative's rest position, corner rest
 * positions per face corner, the per-vertex arrays and the index lists renumbered. */
static wr_status wr__msh_sew(wr__msh_ctx *c, double *pos3) {
    int32_t nv = c->rest.n / 2, nf = c->faces.n / 3, nn, j;
    int32_t *rep = (int32_t *)wr_alloc_array((size_t)nv, sizeof(int32_t));
    int32_t *newid = (int32_t *)wr_alloc_array((size_t)nv, sizeof(int32_t));
    int32_t *F2 = (int32_t *)wr_alloc_array((size_t)(3 * nf), sizeof(int32_t));
    double *corner = (double *)wr_alloc_array((size_t)(6 * nf), sizeof(double));
    const double *V = c->rest.v;
    wr_status st = WR_ERR_NOMEM;
    if (!rep || !newid || !F2 || !corner) goto done;
    nn = wr__msh_sew_classes(c, nv, rep, newid);
    for (j = 0; j < nv; ++j) {
        int32_t r = newid[rep[j]];
        pos3[3 * r] = V[2 * rep[j]];
        pos3[3 * r + 1] = V[2 * rep[j] + 1];
        pos3[3 * r + 2] = 0.0;
    }
    for (j = 0; j < 3 * nf; ++j) {
        F2[j] = newid[rep[c->faces.v[j]]];
        corner[2 * j] = V[2 * c->faces.v[j]];
        corner[2 * j + 1] = V[2 * c->faces.v[j] + 1];
    }
    st = wr_mesh_create(&c->res->mesh, nn, pos3, NULL, nf, F2, c->diag);
    if (st == WR_OK) st = wr_mesh_set_corner_rest(&c->res->mesh, corner, c->diag);
    if (st != WR_OK) {
        char msg[WR_DIAG_MESSAGE_LEN];
        snprintf(msg, sizeof msg, "%s", c->diag ? c->diag->message : "");
        st = wr_fail(c->diag, st, -1, "sewing the seams: %s (a seam pairing with the same traversal "
                                      "direction on both sides makes the sewn mesh non-orientable)", msg);
        goto done;
    }
    /* per-vertex arrays follow the representative */
    for (j = 0; j < nv; ++j)
        if (newid[j] >= 0) {
            c->sizing.v[newid[j]] = c->sizing.v[j];
            c->sizing_warp.v[newid[j]] = c->sizing_warp.v[j];
            c->sizing_weft.v[newid[j]] = c->sizing_weft.v[j];
        }
    c->sizing.n = c->sizing_warp.n = c->sizing_weft.n = nn;
    for (j = 0; j < c->seam_pairs.n; ++j) c->seam_pairs.v[j] = newid[rep[c->seam_pairs.v[j]]];
    for (j = 0; j < c->segments.n; ++j) c->segments.v[j] = newid[rep[c->segments.v[j]]];
done:
    if (st == WR_ERR_NOMEM) st = wr__msh_nomem(c, -1);
    wr_free(rep);
    wr_free(newid);
    wr_free(F2);
    wr_free(corner);
    return st;
}

/* The wr_mesh (sewn or not) and the per-vertex arrays, handed to the result. */
static wr_status wr__msh_assemble(wr__msh_ctx *c) {
    wr_mesher_result *res = c->res;
    int32_t nv = c->rest.n / 2, nf = c->faces.n / 3;
    double *pos3;
    wr_status st;
    if (nf < 1) return wr_fail(c->diag, WR_ERR_GEOMETRY, -1, "pattern produced no triangles");
    if (!c->desc.sew) { /* pos = (rest, 0), made by wr_mesh_create itself (no copy of our own) */
        st = wr_mesh_create(&res->mesh, nv, NULL, c->rest.v, nf, c->faces.v, c->diag);
    } else {
        pos3 = (double *)wr_alloc_array((size_t)(3 * (nv > 0 ? nv : 1)), sizeof(double));
        if (!pos3) return wr__msh_nomem(c, -1);
        st = wr__msh_sew(c, pos3);
        wr_free(pos3);
    }
    if (st == WR_OK) st = wr_mesh_set_face_panel(&res->mesh, c->face_panel.v, c->diag);
    if (st != WR_OK) return st;
    res->sizing = c->sizing.v;
    res->sizing_warp = c->sizing_warp.v;
    res->sizing_weft = c->sizing_weft.v;
    c->sizing.v = c->sizing_warp.v = c->sizing_weft.v = NULL;
    res->seam_pairs = c->seam_pairs.v;
    res->seam_pair_seam = c->seam_pair_seam.v;
    res->n_seam_pairs = c->seam_pair_seam.n;
    c->seam_pairs.v = c->seam_pair_seam.v = NULL;
    res->constraint_segments = c->segments.v;
    res->n_constraint_segments = c->segments.n / 2;
    c->segments.v = NULL;
    return WR_OK;
}

/* ---- report: quality in pattern and metric space, edge ratios ---------------------------------------- */
/* A triangle's edges, computed once for its angles, area test and edge ratios: e[2k..2k+1] = the
 * edge opposite corner k, from corner (k+1)%3 to corner (k+2)%3 (as wr_mesh's face_edges), L[k] its
 * squared length. */
typedef struct wr__msh_tri {
    double e[6], L[3];
} wr__msh_tri;

static void wr__msh_tri_edges(const double *w, wr__msh_tri *t) {
    t->e[0] = w[4] - w[2], t->e[1] = w[5] - w[3]; /* corner 1 → 2 */
    t->e[2] = w[0] - w[4], t->e[3] = w[1] - w[5]; /* corner 2 → 0 */
    t->e[4] = w[2] - w[0], t->e[5] = w[3] - w[1]; /* corner 0 → 1 */
    t->L[0] = t->e[0] * t->e[0] + t->e[1] * t->e[1];
    t->L[1] = t->e[2] * t->e[2] + t->e[3] * t->e[3];
    t->L[2] = t->e[4] * t->e[4] + t->e[5] * t->e[5];
}

/* atan2(y, x) [rad] for y >= 0, to a few ulp: a smallest angle (<= 60 deg) by tan(a - k 15 deg) =
 * (t - tan k 15)/(1 + t tan k 15), |.| <= tan 7.5 deg, and the arctangent's Taylor series to
 * degree 19 (the first term left out < 1e-17 relative); libm's atan2 beyond 67.5 deg. The report
 * takes one smallest angle per face for the mean, and libm's atan2 was a third of its time. */
static double wr__msh_atan2_small(double y, double x) {
    static const double tk[5] = {0.0, 0.26794919243112270, 0.57735026918962573, 1.0, 1.7320508075688772};
    static const double ak[5] = {0.0, 0.26179938779914941, 0.52359877559829887, 0.78539816339744831,
                                 1.0471975511965976}; /* k pi / 12 */
    double t = y / x, u, s;
    int k;
    if (!(x > 0.0 && t < 2.4142135623730950)) return atan2(y, x); /* also NaN, 0/0 */
    k = t < 0.13165249758739585 ? 0 : t < 0.41421356237309505 ? 1 : t < 0.76732698797895960 ? 2 : t < 1.3032253728412058 ? 3 : 4;
    u = k ? (t - tk[k]) / (1.0 + t * tk[k]) : t;
    s = u * u;
    return ak[k] + (u + u * s * (-1.0 / 3 + s * (1.0 / 5 + s * (-1.0 / 7 + s * (1.0 / 9 + s * (-1.0 / 11 + s * (1.0 / 13 +
                    s * (-1.0 / 15 + s * (1.0 / 17 + s * (-1.0 / 19))))))))));
}

/* Smallest and largest angle [deg] of the triangle t: at the corners opposite its shortest and its
 * longest edge, each one atan2(|u × v|, u · v) with u, v the edges leaving that corner (exact at
 * any shape, unlike acos of the cosine rule near 0 and 180 deg). The largest only feeds a running
 * maximum: where its cosine exceeds cos_skip (the running maximum's cosine plus a margin far above
 * rounding) it cannot raise it, and *amax = 0 without the atan2. */
static void wr__msh_tri_angles(const wr__msh_tri *t, double cos_skip, double *amin, double *amax) {
    const double *L = t->L;
    int s = L[1] < L[0] ? 1 : 0, g = L[1] > L[0] ? 1 : 0, pass;
    if (L[2] < L[s]) s = 2;
    if (L[2] > L[g]) g = 2;
    for (pass = 0; pass < (amax ? 2 : 1); ++pass) { /* amax == NULL: the smallest only */
        int q = pass ? g : s, qa = q == 0 ? 2 : q - 1, qb = q == 2 ? 0 : q + 1;
        /* the edges leaving corner q: u = e[(q+2)%3] (q → q+1), v = −e[(q+1)%3] (q → q+2) */
        double ux = t->e[2 * qa], uy = t->e[2 * qa + 1], vx = -t->e[2 * qb], vy = -t->e[2 * qb + 1], ang;
        if (pass && ux * vx + uy * vy > cos_skip * sqrt(L[qa] * L[qb])) {
            *amax = 0.0;
            continue;
        }
        ang = fabs(ux * vy - uy * vx);
        if (pass)
            *amax = atan2(ang, ux * vx + uy * vy) * 57.29577951308232;
        else
            *amin = wr__msh_atan2_small(ang, ux * vx + uy * vy) * 57.29577951308232;
    }
}

/* Running sums of the report's one pass over the faces. */
typedef struct wr__msh_quality {
    double sum_min, sum_min_metric, sum_ratio, sum_ratio_int;
    int32_t n_ratio, n_ratio_int;
} wr__msh_quality;

/* Edge metric length |T e| over the mean of its two end sizings, for the edges face f owns (the face
 * edge_faces lists first): sums, extremes, histogram; interior = no boundary or constraint vertex.
 * Face f owns its edge k when it traverses it with sign +1 (edge_faces[2e] = f), or with sign -1 on
 * a boundary edge (edge_faces[2e] = -1); only an edge with both ends in bnd can be one, so the
 * per-edge arrays (edge order: a cache miss per edge) are read for those few alone, and the ends
 * (edges[2e] < edges[2e+1]) come from the face's own corners. */
static void wr__msh_face_ratios(wr_mesher_result *res, int32_t f, const wr__msh_tri *t, const double *T,
                                const char *bnd, wr__msh_quality *qa) {
    const wr_mesh *M = &res->mesh;
    const int32_t *F = M->faces + 3 * f;
    wr_mesher_report *rp = &res->report;
    int k;
    for (k = 0; k < 3; ++k) {
        int32_t p = F[k == 2 ? 0 : k + 1], q = F[k == 0 ? 2 : k - 1]; /* corners (k+1)%3, (k+2)%3 */
        int32_t a = p < q ? p : q, b = p < q ? q : p;
        double dx = t->e[2 * k], dy = t->e[2 * k + 1], mx, my, ratio, bin;
        if (M->face_edge_sign[3 * f + k] < 0 && !(bnd[a] && bnd[b] && M->edge_faces[2 * M->face_edges[3 * f + k]] < 0))
            continue;
        mx = T[0] * dx + T[1] * dy;
        my = T[2] * dx + T[3] * dy;
        ratio = sqrt(mx * mx + my * my) / (0.5 * (res->sizing[a] + res->sizing[b]));
        qa->sum_ratio += ratio;
        ++qa->n_ratio;
        if (!bnd[a] && !bnd[b]) {
            qa->sum_ratio_int += ratio;
            ++qa->n_ratio_int;
        }
        if (ratio < rp->ratio_min) rp->ratio_min = ratio;
        if (ratio > rp->ratio_max) rp->ratio_max = ratio;
        bin = ratio / 2.0 * WR_MESHER_HIST_BINS; /* clamped first, so the cast is the floor */
        if (!(bin >= 0)) bin = 0;
        if (bin > WR_MESHER_HIST_BINS - 1) bin = WR_MESHER_HIST_BINS - 1;
        rp->ratio_hist[(int)bin]++;
    }
}

/* The smallest angle [deg] of face f in its panel's metric (stretched) space: amin itself on an
 * isotropic panel (a similarity keeps angles), else that of the mapped triangle T uv. */
static double wr__msh_metric_min_angle(const double *T, const double *uv, double amin) {
    double w[6], am;
    wr__msh_tri t;
    int k;
    if (T[1] == 0.0 && T[2] == 0.0 && T[0] == T[3]) return amin;
    for (k = 0; k < 3; ++k) {
        w[2 * k] = T[0] * uv[2 * k] + T[1] * uv[2 * k + 1];
        w[2 * k + 1] = T[2] * uv[2 * k] + T[3] * uv[2 * k + 1];
    }
    wr__msh_tri_edges(w, &t);
    wr__msh_tri_angles(&t, 2.0, &am, NULL);
    return am;
}

/* In the sampler's order (WR_MESHER_ORDER_SAMPLED) a face's corners are ~1700 ids apart, so the
 * report's reads of rest and sizing miss the cache at every face; GCC/Clang builds prefetch them this
 * many faces ahead (in the spatial order the lines are mostly in cache already). */
#define WR__MSH_AHEAD 16

/* One pass over the faces: angles in pattern space and in each panel's metric (stretched) space,
 * inverted / zero-area faces (WR_MESH_ZERO_AREA_REL, as wr_mesh_quality counts them), edge ratios. */
static wr_status wr__msh_report(wr__msh_ctx *c) {
    wr_mesher_result *res = c->res;
    wr_mesher_report *rp = &res->report;
    const wr_mesh *M = &res->mesh;
    wr__msh_quality qa;
    int32_t f, j, k;
    double cos_skip = 2.0; /* see wr__msh_tri_angles; 2: no face skipped before the first maximum */
    char *bnd = (char *)wr_calloc_array((size_t)M->nv, 1);
    if (!bnd) return wr__msh_nomem(c, -1);
    for (j = 0; j < M->n_loops; ++j)
        for (k = M->loop_start[j]; k < M->loop_start[j + 1]; ++k) bnd[M->loop_verts[k]] = 1;
    for (j = 0; j < 2 * res->n_constraint_segments; ++j) bnd[res->constraint_segments[j]] = 1;
    memset(&qa, 0, sizeof qa);
    rp->min_angle_deg = rp->min_angle_metric_deg = 180.0;
    rp->max_angle_deg = 0.0;
    rp->ratio_min = HUGE_VAL;
    rp->ratio_max = 0.0;
    for (f = 0; f < M->nf; ++f) {
        const double *T = res->panels[M->face_panel[f]].T;
#if defined(__GNUC__)
        if (f + WR__MSH_AHEAD < M->nf && !M->corner_rest && M->rest) /* see WR__MSH_AHEAD */
            for (k = 0; k < 3; ++k) {
                int32_t v = M->faces[3 * (f + WR__MSH_AHEAD) + k];
                __builtin_prefetch(M->rest + 2 * v);
                __builtin_prefetch(res->sizing + v);
            }
#endif
        double uv[6], amin, amax, amin_m, area, lmax;
        wr__msh_tri t;
        wr_mesh_face_rest(M, f, uv);
        wr__msh_tri_edges(uv, &t);
        wr__msh_tri_angles(&t, cos_skip, &amin, &amax);
        amin_m = wr__msh_metric_min_angle(T, uv, amin);
        if (amin < rp->min_angle_deg) rp->min_angle_deg = amin;
        if (amax > rp->max_angle_deg) {
            rp->max_angle_deg = amax;
            cos_skip = cos(amax / 57.29577951308232) + 1e-9;
        }
        if (amin_m < rp->min_angle_metric_deg) rp->min_angle_metric_deg = amin_m;
        qa.sum_min += amin;
        qa.sum_min_metric += amin_m;
        area = 0.5 * ((uv[2] - uv[0]) * (uv[5] - uv[1]) - (uv[3] - uv[1]) * (uv[4] - uv[0]));
        lmax = t.L[0] > t.L[1] ? t.L[0] : t.L[1];
        lmax = t.L[2] > lmax ? t.L[2] : lmax;
        if (fabs(area) <= WR_MESH_ZERO_AREA_REL * lmax)
            ++rp->n_zero_area;
        else if (area < 0.0)
            ++rp->n_inverted;
        wr__msh_face_ratios(res, f, &t, T, bnd, &qa);
    }
    wr_free(bnd);
    rp->n_vertices = M->nv;
    rp->n_triangles = M->nf;
    rp->n_seam_pairs = res->n_seam_pairs;
    rp->n_constraint_segments = res->n_constraint_segments;
    rp->mean_min_angle_deg = M->nf ? qa.sum_min / M->nf : 0.0;
    rp->mean_min_angle_metric_deg = M->nf ? qa.sum_min_metric / M->nf : 0.0;
    rp->ratio_mean = qa.n_ratio ? qa.sum_ratio / qa.n_ratio : 0.0;
    rp->ratio_interior_mean = qa.n_ratio_int ? qa.sum_ratio_int / qa.n_ratio_int : NAN;
    return WR_OK;
}

/* ---- the one cleanup path --------------------------------------------------------------------------- */
static wr_status wr__msh_end(wr__msh_ctx *c, wr_status st) {
    int32_t k, p;
    if (c->sides)
        for (k = 0; k < 2 * c->pat->n_seams; ++k) wr_free(c->sides[k].global);
    wr_free(c->sides);
    if (c->loops)
        for (p = 0; p < c->pat->n_panels; ++p) {
            wr_free(c->loops[p].xy);
            wr_free(c->loops[p].brk);
            wr_free(c->loops[p].side_of_edge);
            wr_free(c->loops[p].forced);
        }
    wr_free(c->loops);
    wr_free(c->rest.v);
    wr_free(c->sizing.v);
    wr_free(c->sizing_warp.v);
    wr_free(c->sizing_weft.v);
    wr_free(c->faces.v);
    wr_free(c->face_panel.v);
    wr_free(c->segments.v);
    wr_free(c->seam_pairs.v);
    wr_free(c->seam_pair_seam.v);
    if (st != WR_OK && c->res) {
        wr_mesher_free(c->res);
        /* panel names are user text: keep the message one line */
        if (c->diag) {
            char *ch;
            for (ch = c->diag->message; *ch; ++ch)
                if (*ch == '\n' || *ch == '\r') *ch = ' ';
        }
    }
    return st;
}

/* ---- the pipeline --------------------------------------------------------------------------------- */
WRDEF wr_status wr_mesher_run(const wr_pattern *pat, const wr_mesher_desc *desc, wr_mesher_result *res, wr_diag *diag) {
    wr__msh_ctx c;
    int32_t p;
    double t0;
    wr_status st = wr__msh_begin(&c, pat, desc, res, diag);
    if (st != WR_OK) return st; /* nothing allocated yet; res (if any) is zeroed */
    st = wr__msh_sizing(&c);                       /* Sec. 4.1–4.2: the sizing map */
    if (st == WR_OK) st = wr__msh_pair_seams(&c);  /* Sec. 4.2.4: seam ends on the loops, sides walked */
    if (st == WR_OK) st = wr__msh_budget(&c);      /* area/perimeter estimate before any growing work */
    if (st == WR_OK) wr__msh_progress(&c, "sizing", -1);
    for (p = 0; st == WR_OK && p < pat->n_panels; ++p) st = wr__msh_mesh_panel(&c, p); /* Sec. 4.3 */
    t0 = wr_time_seconds();
    if (st == WR_OK) st = wr__msh_seam_table(&c);
    if (st == WR_OK) st = wr__msh_assemble(&c);
    if (st == WR_OK) st = wr__msh_report(&c);
    if (st == WR_OK) {
        res->report.t_assemble += wr_time_seconds() - t0;
        res->report.t_total = wr_time_seconds() - c.t_start;
        wr__msh_progress(&c, "done", -1);
    }
    return wr__msh_end(&c, st);
}

WRDEF void wr_mesher_free(wr_mesher_result *res) {
    if (!res) return;
    wr_mesh_free(&res->mesh);
    wr_free(res->sizing);
    wr_free(res->sizing_warp);
    wr_free(res->sizing_weft);
    wr_free(res->seam_pairs);
    wr_free(res->seam_pair_seam);
    wr_free(res->constraint_segments);
    wr_free(res->panels);
    wr_sizing_map_free(&res->map);
    memset(res, 0, sizeof *res);
}

WRDEF double wr_mesher_eval_sizing(const wr_mesher_result *res, int32_t panel, double x, double y) {
    return res ? wr_sizing_map_eval(&res->map, panel, x, y) : NAN;
}

WRDEF wr_status wr_mesher_panel_resolution(const wr_pattern_fabric *fab, const wr_resolution_model *model,
                                           double *r_warp, double *r_weft, wr_diag *diag) {
    return wr_sizing_fabric_resolution(fab, model, r_warp, r_weft, diag);
}

#ifdef __cplusplus
}
#endif
#endif /* WRINKLE_MESHER_IMPLEMENTATION_DONE */
#endif /* WRINKLE_IMPLEMENTATION */
