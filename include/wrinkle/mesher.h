/* wrinkle/mesher.h — garment pattern → one optimally resolved simulation mesh (Style3D Sec. 4.1.2,
 * 4.2.1–4.2.6, 4.3): per-panel sizing maps from fabrics and garment-making techniques, boundary and
 * constraint discretisation, variable-radius Poisson sampling, constrained Delaunay triangulation,
 * one wr_mesh with panel ids, per-vertex sizing, a seam table and a quality report.
 * wrinkle v0.1.0 — MIT licence (see LICENSE). Needs only libc and libm (and core.h, mesh.h,
 * resolution.h, transition.h, poisson.h, triangulate.h).
 *
 * API (create/free pair: wr_mesher_run → wr_mesher_free)
 *   wr_mesher_run(pattern, desc, result, diag)      validate, build sizing maps, sample, triangulate
 *   wr_mesher_free(result)                          free and zero (safe on a zeroed result)
 *   wr_mesher_eval_sizing(result, panel, x, y)      the panel's sizing map at a pattern point [m]
 *   wr_mesher_panel_resolution(fabric, model, &r_warp, &r_weft, diag)   Eq. 4 per direction
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
 * ON THE SIZING MAP (Sec. 4.2.1, 4.3)
 *   Per panel: r_f from Eq. 4 (resolution.h; clamped onto the model's branch so a pipeline always has
 *   a size); sources r_i with transitions r_i(x) = r_i (1 + (x/L_w)^m) (transition.h, = r_i + x^m in
 *   mm); r_v = min(r_f, min_i r_i(x_i)). L_w of a source: the technique's explicit transition_length
 *   if > 0, else the compression form of Sec. 4.2.1 with unit prefactor,
 *       L_w = r_src^{3/2} (δ / h²)^{1/4},   δ = 1 − ρ (ρ the technique's resolution factor),
 *       h = (12 (1 − ν²) B/E)^{1/3}          (Kirchhoff–Love thickness of the fabric, ν = 0.3),
 *   reading λ ≈ r_src (the paper absorbs r/λ into m). δ is floored at WR_MESHER_MIN_STRAIN. When
 *   the paper's m is undefined (r or L_w ≤ 1 mm) transition.h's scale-free fallback is used.
 *
 * ON THE TECHNIQUES (each refers to a panel by index)
 *   shirring  (4.2.2): r_sh = ρ_sh^n r(B/(E+E_sh)) · r_f / r(B/E) (the last factor is 1 unless the
 *             panel overrides its base resolution r_f; B, E of the fine direction for anisotropic
 *             fabrics); source = the polyline; it is also a mesh
 *             constraint. Endpoints may lie on the panel boundary: the constraint copy is then
 *             trimmed by WR_MESHER_TRIM_FACTOR × local sizing at that end (the sampler needs
 *             constraint lines strictly inside), the sizing source keeps the full line.
 *   fold      (4.2.3): constraints = the fold line and two parallel lines at ±offset (default
 *             0.5 mm); the fold line itself carries the base resolution (no source). At both
 *             endpoints and at high-curvature vertices (local radius of curvature < curvature_radius,
 *             local maxima only): ρ_fd = Δθ/360, r_fd = ρ_fd r_ng (r_ng = the map's value there
 *             before fold points are added) with a DIRECTIONAL transition (forward half-space only):
 *             endpoints along the fold direction pointing INTO the fold (our reading of "follows the
 *             direction of the folding edge": the tip of a fold compresses the fabric along the fold),
 *             curvature points along the normal pointing to the centre of curvature (the compressed
 *             side). The fold line must lie strictly inside its panel ("leaves its panel" otherwise).
 *   seam      (4.2.4): side a ↔ side b, each a range of a panel's OUTER loop from point `from` to
 *             point `to` (both must lie on that loop), walked in the loop's input order (reverse = 1:
 *             against it). Pairing is from↔from, to↔to. Both sides get the same number of vertices
 *             (N = max of the two sides' own counts), listed pairwise in result.seam_pairs. When the
 *             lengths differ, ρ_s = l_s/l_l is the source factor of the LONGER side only
 *             (r = ρ_s r_f of that panel, source = that boundary range, transition on that side).
 *             A seam range may not pass a corner (turn > WR_MESHER_CORNER_DEG): split it there.
 *   quilt     (4.2.5, down-filling): stitch polylines with shrinkage ρ and optional E_sh treated as
 *             shirring lines; pressure p ≥ 0 gives m' = 2^p m, L_w' = L_w^{2^{-p}} (mm).
 *   collision (4.2.6): a user-labelled polygon or disk with compression δ ∈ (0, 1): inside,
 *             r = (1 − δ) r_f; outside, a transition from its boundary.
 *
 * ON ANISOTROPY (Sec. 4.1.2, Fig. 6)
 *   A panel with fabric.anisotropic gets r_warp, r_weft (Eq. 4 per direction) and a constant metric
 *   M = R diag(1/r_warp², 1/r_weft²) Rᵀ. We mesh in the metric's stretched space: the affine map
 *   T = r0 diag(1/r_warp, 1/r_weft) Rᵀ, r0 = min(r_warp, r_weft), turns M into the isotropic
 *   r0⁻² I; sampling and the CDT run on T(panel) with sizing r0 and the points are mapped back with
 *   T⁻¹ (det T > 0, so faces stay CCW). Edges then have length ≈ r_warp along the warp and r_weft
 *   along the weft. Technique sources refine in stretched space (both directions scaled by
 *   s/r0, keeping the fabric's aspect) — an approximation of transition.h's min(r_dir, s) metric
 *   that keeps the map affine-constant per panel; distances x for transitions are pattern-space.
 *
 * ON SAMPLING AND TRIANGULATION (Sec. 4.3)
 *   Per panel, in stretched coordinates: the outer loop (with seam ends inserted), holes and
 *   constraint lines (shirring, quilt stitches, folds and their parallels) are discretised here at
 *   ∫ ds/h (break points: corners turning > WR_MESHER_CORNER_DEG, seam ends; a seam range gets the
 *   count N shared with its partner side). poisson.h fills the interior (its calibrated radius
 *   factor unless desc.radius_factor); it re-discretises the curves it is given, so only its
 *   INTERIOR samples are used: each is dropped when closer than WR_MESHER_SAMPLE_CLEARANCE × h to
 *   one of our constraint segments or (near the boundary) outside our polygon. The CDT
 *   (triangulate.h, no refinement, so no Steiner points and seam counts stay exact) gets our curve
 *   points + the kept samples, our segments and one seed per hole. Measured: mean edge length /
 *   sizing 0.99–1.01 on the Table 1 squares (validation/validate_meshing.c).
 *
 * ON THE OUTPUT
 *   Vertices are numbered panel by panel. rest = pattern position, pos = (rest, 0). face_panel set.
 *   Seam sides are NOT merged (seam_pairs lists the vertices to sew, in order along the seam) unless
 *   desc.sew: then side b's vertices are merged into side a's, rest is NULL and corner_rest carries
 *   each corner's own pattern position (a sewn vertex has two). sizing[v] = target edge length [m]
 *   (the fine direction for anisotropic panels), sizing_warp/_weft per direction.
 *   Quality: angles in pattern space and in the metric (stretched) space; edge ratio = |T e| / mean of the two end sizings (metric
 *   length over target, 1 is ideal), histogram of WR_MESHER_HIST_BINS bins on [0, 2).
 *
 * ON ERRORS (status + message naming the item; diag->item = its index)
 *   WR_ERR_INVALID_ARG  NULL arguments, no panels, technique on a missing panel ("shirrings[2]: panel
 *                       5 does not exist"), ρ outside (0, 1], negative pressure / E_sh, fold angle
 *                       outside (0, 360], non-positive offset / radius / transition length.
 *   WR_ERR_DOMAIN       non-positive or non-finite stiffness ("panels[1] 'back': B = -1").
 *   WR_ERR_GEOMETRY     loops with < 3 points or zero area, non-finite coordinates, seam ends not on
 *                       the panel boundary, overlapping seams, seam across a corner, fold/shirring
 *                       line leaving its panel; self-intersections reported by poisson.h.
 *   WR_ERR_BUDGET       desc.max_vertices would be exceeded (checked before sampling each panel).
 *   On failure the result is zeroed.
 *
 * ON THREADS: no global state; one call is single-threaded. Deterministic for a fixed desc.seed.
 */
#ifndef WRINKLE_MESHER_H
#define WRINKLE_MESHER_H

#include "core.h"
#include "mesh.h"
#include "resolution.h"
#include "transition.h"
#include "poisson.h"
#include "triangulate.h"

#ifdef __cplusplus
extern "C" {
#endif

#define WR_MESHER_DEFAULT_FOLD_OFFSET 0.5e-3     /* m, Sec. 4.2.3 "e.g., 0.5 mm" */
#define WR_MESHER_DEFAULT_FOLD_ANGLE 180.0       /* deg: a flat fold (hem) */
#define WR_MESHER_DEFAULT_CURVATURE_RADIUS 20e-3 /* m: fold vertices curving tighter are "high curvature" */
#define WR_MESHER_DEFAULT_MAX_VERTICES 20000000
#define WR_MESHER_KL_POISSON 0.3      /* ν for the Kirchhoff–Love thickness h = (12(1-ν²) B/E)^{1/3} */
#define WR_MESHER_MIN_STRAIN 1e-3     /* floor of δ in the compression law (δ = 0 gives L_w = 0) */
#define WR_MESHER_FALLBACK_THICKNESS_RATIO 0.1 /* h / r when a panel has no stiffness (override only) */
#define WR_MESHER_CORNER_DEG 30.0     /* turning angle above which a boundary vertex is kept exactly */
#define WR_MESHER_TRIM_FACTOR 0.5     /* constraint trim at a line end lying on the boundary (× sizing) */
#define WR_MESHER_HIST_BINS 20
/* Interior samples closer than this × local sizing to one of our constraint segments are dropped
 * (the sampler keeps ≈ 0.7 h from its own curve points; half of that marks a sample squeezed
 * against our slightly different discretisation, which would only make a sliver). */
#define WR_MESHER_SAMPLE_CLEARANCE 0.35        /* edge-ratio histogram bins on [0, 2) */
/* Tolerance for "lies on the boundary" (seam ends, line ends): absolute [m] plus relative to the
 * panel's bounding-box size. 1 µm is far below any cloth feature and above JSON mm round-off. */
#define WR_MESHER_ON_BOUNDARY_ABS 1e-6
#define WR_MESHER_ON_BOUNDARY_REL 1e-9

/* A polyline or loop: n points xy[2n] [m] (row-major). */
typedef struct wr_pattern_curve {
    const double *xy;
    int32_t n;
} wr_pattern_curve;

/* Fabric of a panel. Isotropic: B [N·m], E [N/m²]. anisotropic != 0: (B_warp, E_warp), (B_weft, E_weft)
 * and the warp direction grain_angle [rad] in the pattern frame. Overrides (> 0) replace Eq. 4:
 * resolution (isotropic), resolution_warp / resolution_weft (anisotropic) [m]; the stiffness is then
 * still used for the transition thickness when given, else h = r · WR_MESHER_FALLBACK_THICKNESS_RATIO. */
typedef struct wr_pattern_fabric {
    double B, E;
    int anisotropic;
    double B_warp, E_warp, B_weft, E_weft;
    double grain_angle;
    double resolution;
    double resolution_warp, resolution_weft;
} wr_pattern_fabric;

typedef struct wr_pattern_panel {
    const char *name; /* may be NULL; used in messages */
    wr_pattern_curve outer;
    const wr_pattern_curve *holes;
    int32_t n_holes;
    wr_pattern_fabric fabric;
} wr_pattern_panel;

/* Sec. 4.2.2. rho in (0, 1]; n_exp 0 → 1; E_sh >= 0; transition_length 0 → compression law. */
typedef struct wr_pattern_shirring {
    int32_t panel;
    const double *xy;
    int32_t n;
    double E_sh, rho, n_exp, transition_length;
} wr_pattern_shirring;

/* Sec. 4.2.3. angle_deg Δθ in (0, 360], 0 → 180; offset 0 → 0.5 mm; curvature_radius 0 → 20 mm. */
typedef struct wr_pattern_fold {
    int32_t panel;
    const double *xy;
    int32_t n;
    double angle_deg, offset, curvature_radius, transition_length;
} wr_pattern_fold;

typedef struct wr_pattern_seam_side {
    int32_t panel;
    double from[2], to[2]; /* points on the panel's outer loop [m] */
    int reverse;           /* 0: walk in the loop's input order from → to; 1: against it */
} wr_pattern_seam_side;

/* Sec. 4.2.4. transition_length 0 → compression law with δ = 1 − ρ_s. */
typedef struct wr_pattern_seam {
    wr_pattern_seam_side a, b;
    double transition_length;
} wr_pattern_seam;

/* Sec. 4.2.5: a quilted (down-filled) panel's stitch lines. rho in (0, 1], E_sh >= 0, pressure >= 0. */
typedef struct wr_pattern_quilt {
    int32_t panel;
    const wr_pattern_curve *lines;
    int32_t n_lines;
    double rho, E_sh, pressure, transition_length;
} wr_pattern_quilt;

/* Sec. 4.2.6: polygon (n >= 3) or, when n == 0, the disk (center, radius). compression δ in (0, 1). */
typedef struct wr_pattern_collision {
    int32_t panel;
    const double *xy;
    int32_t n;
    double center[2], radius;
    double compression, transition_length;
} wr_pattern_collision;

/* A garment pattern: a view of caller-owned arrays (nothing is copied or freed by the mesher). */
typedef struct wr_pattern {
    const wr_pattern_panel *panels;
    int32_t n_panels;
    const wr_pattern_shirring *shirrings;
    int32_t n_shirrings;
    const wr_pattern_fold *folds;
    int32_t n_folds;
    const wr_pattern_seam *seams;
    int32_t n_seams;
    const wr_pattern_quilt *quilts;
    int32_t n_quilts;
    const wr_pattern_collision *collisions;
    int32_t n_collisions;
} wr_pattern;

/* Options; zero means default:
 *   model               Eq. 4 constants; c1 == c2 == 0 → wr_resolution_model_paper()
 *   uniform_resolution  > 0: ignore fabrics and techniques, mesh every panel at this size [m]
 *                       (seams still get equal counts) — the "uniform fine" comparison
 *   radius_factor       Poisson radius / sizing; 0 → poisson.h's calibrated default
 *   seed                sampling seed (0 is used as given)
 *   max_vertices        0 → WR_MESHER_DEFAULT_MAX_VERTICES
 *   sew                 1: merge seam pairs into one vertex (corner_rest output) */
typedef struct wr_mesher_desc {
    wr_resolution_model model;
    double uniform_resolution;
    double radius_factor;
    uint64_t seed;
    int32_t max_vertices;
    int sew;
} wr_mesher_desc;

typedef struct wr_mesher_panel_info {
    double r_warp, r_weft; /* base resolution per direction [m] (equal for isotropic panels) */
    double r0;             /* min(r_warp, r_weft): the stretched-space sizing */
    double T[4], Tinv[4];  /* row-major pattern → stretched map and its inverse */
    int32_t v_begin, v_end;  /* vertex range (before sewing) */
    int32_t f_begin, f_end;  /* face range */
    double area;           /* pattern area [m²] */
    int32_t n_sources;     /* sizing sources of this panel */
    void *map_;            /* private: the sizing map (wr_sizing) and collision regions */
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
    double *sizing;               /* nv target edge length [m] (fine direction) */
    double *sizing_warp, *sizing_weft; /* nv per-direction target lengths [m] */
    int32_t *seam_pairs;          /* n_seam_pairs × 2 vertex ids (side a, side b), in order along each seam */
    int32_t *seam_pair_seam;      /* n_seam_pairs: seam index */
    int32_t n_seam_pairs;
    int32_t *constraint_segments; /* n_constraint_segments × 2: boundary + constraint-line edges */
    int32_t n_constraint_segments;
    wr_mesher_panel_info *panels; /* n_panels */
    int32_t n_panels;
    wr_mesher_report report;
} wr_mesher_result;

WRDEF wr_status wr_mesher_run(const wr_pattern *pat, const wr_mesher_desc *desc, wr_mesher_result *res,
                              wr_diag *diag);
WRDEF void wr_mesher_free(wr_mesher_result *res);
/* Sizing [m] (fine direction) of panel p's map at pattern point (x, y); NaN for a bad panel index. */
WRDEF double wr_mesher_eval_sizing(const wr_mesher_result *res, int32_t panel, double x, double y);
/* Eq. 4 per direction for one fabric (overrides honoured). model NULL → paper model. */
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
#include <stdlib.h>
#include <string.h>

#ifdef __cplusplus
extern "C" {
#endif

/* ---- small geometry ------------------------------------------------------------------------ */

/* Closest edge of a closed loop to p: returns the distance, the edge index and its parameter. */
static double wr__msh_loop_closest(const double *xy, int32_t n, const double *p, int32_t *edge, double *t) {
    double best = HUGE_VAL;
    int32_t i;
    for (i = 0; i < n; ++i) {
        double tt, d = wr_segment_distance(p, xy + 2 * i, xy + 2 * ((i + 1) % n), &tt);
        if (d < best) {
            best = d;
            *edge = i;
            *t = tt;
        }
    }
    return best;
}

/* Do closed segments ab and cd intersect (touching counts)? Exact predicates from triangulate.h. */
static int wr__msh_seg_cross(const double *a, const double *b, const double *c, const double *d) {
    double o1 = wr_orient2d(a, b, c), o2 = wr_orient2d(a, b, d), o3 = wr_orient2d(c, d, a),
           o4 = wr_orient2d(c, d, b);
    if (((o1 > 0 && o2 < 0) || (o1 < 0 && o2 > 0)) && ((o3 > 0 && o4 < 0) || (o3 < 0 && o4 > 0))) return 1;
#define WR__MSH_ONSEG(p, q, r) \
    (fmin(p[0], q[0]) <= r[0] && r[0] <= fmax(p[0], q[0]) && fmin(p[1], q[1]) <= r[1] && r[1] <= fmax(p[1], q[1]))
    if (o1 == 0 && WR__MSH_ONSEG(a, b, c)) return 1;
    if (o2 == 0 && WR__MSH_ONSEG(a, b, d)) return 1;
    if (o3 == 0 && WR__MSH_ONSEG(c, d, a)) return 1;
    if (o4 == 0 && WR__MSH_ONSEG(c, d, b)) return 1;
#undef WR__MSH_ONSEG
    return 0;
}

static int wr__msh_finite_curve(const double *xy, int32_t n) {
    int32_t i;
    for (i = 0; i < 2 * n; ++i)
        if (!isfinite(xy[i])) return 0;
    return 1;
}

static void wr__msh_apply(const double *T, const double *p, double *q) {
    double x = p[0], y = p[1];
    q[0] = T[0] * x + T[1] * y;
    q[1] = T[2] * x + T[3] * y;
}

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

/* ---- per-panel sizing context ---------------------------------------------------------------- */
typedef struct wr__msh_region {
    const double *xy; /* polygon (n >= 3) or NULL for a disk */
    int32_t n;
    double cx, cy, R;
    double r; /* resolution inside [m] */
} wr__msh_region;

typedef struct wr__msh_map {
    wr_sizing *s;
    wr__msh_region *regions;
    int32_t n_regions;
    double r0;      /* cap */
    double Tinv[4]; /* stretched → pattern */
    double uniform; /* > 0: constant sizing */
} wr__msh_map;

static double wr__msh_map_eval(const wr__msh_map *m, double x, double y) {
    double s;
    int32_t i;
    if (m->uniform > 0.0) return m->uniform;
    s = m->s ? wr_sizing_eval(m->s, x, y) : m->r0;
    for (i = 0; i < m->n_regions; ++i) {
        const wr__msh_region *g = &m->regions[i];
        int in = g->xy ? wr_point_in_polygon(g->xy, g->n, x, y)
                       : ((x - g->cx) * (x - g->cx) + (y - g->cy) * (y - g->cy) <= g->R * g->R);
        if (in && g->r < s) s = g->r;
    }
    return s;
}

/* Sizing callback in stretched coordinates: map back to the pattern and evaluate there. */
static double wr__msh_stretched_size(void *user, double x, double y) {
    const wr__msh_map *m = (const wr__msh_map *)user;
    double p[2], q[2];
    p[0] = x;
    p[1] = y;
    wr__msh_apply(m->Tinv, p, q);
    return wr__msh_map_eval(m, q[0], q[1]);
}

static void wr__msh_map_free(wr__msh_map *m) {
    if (!m) return;
    wr_sizing_free(m->s);
    wr_free(m->regions);
    wr_free(m);
}

/* ---- resolutions ----------------------------------------------------------------------------- */
static const char *wr__msh_pname(const wr_pattern *pat, int32_t p) {
    const char *n = pat->panels[p].name;
    return n ? n : "";
}

WRDEF wr_status wr_mesher_panel_resolution(const wr_pattern_fabric *fab, const wr_resolution_model *model,
                                           double *r_warp, double *r_weft, wr_diag *diag) {
    wr_resolution_model mdl;
    wr_resolution_desc rd;
    wr_status st;
    if (!fab || !r_warp || !r_weft) return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "NULL argument");
    mdl = (model && (model->c1 != 0.0 || model->c2 != 0.0)) ? *model : wr_resolution_model_paper();
    memset(&rd, 0, sizeof rd);
    rd.clamp = 1; /* a pipeline must always produce a size; Eq. 4's branch edge is the limit */
    if (!fab->anisotropic) {
        if (fab->resolution > 0.0) {
            if (!isfinite(fab->resolution))
                return wr_fail(diag, WR_ERR_DOMAIN, -1, "resolution = %g is not finite", fab->resolution);
            *r_warp = *r_weft = fab->resolution;
            return WR_OK;
        }
        if (!(fab->B > 0.0) || !isfinite(fab->B))
            return wr_fail(diag, WR_ERR_DOMAIN, -1, "bending stiffness B = %g must be positive", fab->B);
        if (!(fab->E > 0.0) || !isfinite(fab->E))
            return wr_fail(diag, WR_ERR_DOMAIN, -1, "Young's modulus E = %g must be positive", fab->E);
        st = wr_resolution_from_BE(&mdl, fab->B, fab->E, &rd, r_warp, diag);
        if (st != WR_OK) return st;
        *r_weft = *r_warp;
        return WR_OK;
    }
    if (fab->resolution_warp > 0.0 && fab->resolution_weft > 0.0) {
        if (!isfinite(fab->resolution_warp) || !isfinite(fab->resolution_weft))
            return wr_fail(diag, WR_ERR_DOMAIN, -1, "warp/weft resolution not finite");
        *r_warp = fab->resolution_warp;
        *r_weft = fab->resolution_weft;
        return WR_OK;
    }
    if (!(fab->B_warp > 0.0) || !isfinite(fab->B_warp) || !(fab->E_warp > 0.0) || !isfinite(fab->E_warp))
        return wr_fail(diag, WR_ERR_DOMAIN, 0, "warp stiffness B = %g, E = %g must be positive", fab->B_warp,
                       fab->E_warp);
    if (!(fab->B_weft > 0.0) || !isfinite(fab->B_weft) || !(fab->E_weft > 0.0) || !isfinite(fab->E_weft))
        return wr_fail(diag, WR_ERR_DOMAIN, 1, "weft stiffness B = %g, E = %g must be positive", fab->B_weft,
                       fab->E_weft);
    if (!isfinite(fab->grain_angle)) return wr_fail(diag, WR_ERR_DOMAIN, -1, "grain angle not finite");
    return wr_resolution_orthotropic(&mdl, fab->B_warp, fab->E_warp, fab->B_weft, fab->E_weft, &rd, r_warp,
                                     r_weft, diag);
}

/* Kirchhoff–Love thickness of the panel's fabric for the compression law (see ON THE SIZING MAP).
 * Uses the smallest y = B/E (the fine direction). With a resolution override and no stiffness there
 * is no thickness to compute; h = r0/10 is then used (WR_MESHER_FALLBACK_THICKNESS_RATIO): for the
 * Table 1 fabrics h/r runs from 0.011 (Rose) over 0.04 (Green) to 0.13 (Dark Blue). */
static double wr__msh_thickness(const wr_pattern_fabric *f, double r0) {
    double y = HUGE_VAL;
    if (!f->anisotropic) {
        if (f->B > 0.0 && f->E > 0.0) y = f->B / f->E;
    } else {
        if (f->B_warp > 0.0 && f->E_warp > 0.0) y = f->B_warp / f->E_warp;
        if (f->B_weft > 0.0 && f->E_weft > 0.0 && f->B_weft / f->E_weft < y) y = f->B_weft / f->E_weft;
    }
    if (!(y < HUGE_VAL) || !isfinite(y)) return r0 * WR_MESHER_FALLBACK_THICKNESS_RATIO;
    return cbrt(12.0 * (1.0 - WR_MESHER_KL_POISSON * WR_MESHER_KL_POISSON) * y);
}

/* The (B, E) pair of the fabric's fine direction (smallest y = B/E); zeros when not given. */
static void wr__msh_fine_pair(const wr_pattern_fabric *f, double *B, double *E) {
    *B = *E = 0.0;
    if (!f->anisotropic) {
        *B = f->B;
        *E = f->E;
    } else if (f->B_warp > 0.0 && f->E_warp > 0.0 && f->B_weft > 0.0 && f->E_weft > 0.0) {
        int warp_fine = f->B_warp / f->E_warp <= f->B_weft / f->E_weft;
        *B = warp_fine ? f->B_warp : f->B_weft;
        *E = warp_fine ? f->E_warp : f->E_weft;
    }
}

/* Transition for a source of resolution r with resolution factor rho (δ = 1 − ρ) or explicit L_w. */
static wr_status wr__msh_transition(double r, double rho, double h, double L_explicit, double pressure,
                                    wr_transition *t, wr_diag *diag) {
    double L = L_explicit, delta = 1.0 - rho;
    wr_status st;
    if (!(L > 0.0)) {
        if (delta < WR_MESHER_MIN_STRAIN) delta = WR_MESHER_MIN_STRAIN;
        st = wr_wrinklon_size_compression(r, delta, h, &L, diag);
        if (st != WR_OK) return st;
    }
    st = wr_transition_make(r, L, NULL, t, diag);
    if (st != WR_OK) return st;
    if (pressure > 0.0) {
        wr_transition u;
        st = wr_transition_downfill(t, pressure, &u, diag);
        if (st != WR_OK) return st;
        *t = u;
    }
    return WR_OK;
}

/* ---- loop with inserted seam points ----------------------------------------------------------- */
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

/* One seam side resolved on a panel's loop. */
typedef struct wr__msh_side {
    int32_t seam, which; /* which: 0 = a, 1 = b */
    int32_t panel;
    int32_t v_from, v_to; /* vertices of the panel's refined loop */
    int reverse;
    double length;        /* pattern length [m] */
    int32_t N;            /* segments (equal on both sides) */
    int32_t *fixed;       /* N+1 poisson fixed indices in walk order from → to */
    int32_t *global;      /* N+1 global vertex ids */
} wr__msh_side;

/* ---- discretisation of one piece of a curve at ∫ ds / h -------------------------------------- */
/* Piece = points P[0..np) (stretched coords). Appends interior points (not P[0], not P[np-1]) for N
 * segments at equal ∫ ds/h fractions, N = forced > 0 or max(1, round(∫)) with the guard that keeps
 * every piece's ∫ below 1.4 (the sampler then keeps the points as they are). Returns N, or -1 on
 * allocation failure. With measure_only, only returns the natural count and stores the integral. */
static int32_t wr__msh_piece(const double *P, int32_t np, wr__msh_map *m, int32_t forced, wr__msh_dbuf *out,
                             int measure_only, double *integral_out) {
    wr__msh_dbuf cum, pts;
    double total = 0.0;
    int32_t i, N, k, j;
    memset(&cum, 0, sizeof cum);
    memset(&pts, 0, sizeof pts);
    /* fine table: sub-steps of WR_POISSON_WALK_STEP × local sizing, trapezoid rule on 1/h */
    if (!wr__msh_dpush(&cum, 0.0) || !wr__msh_dpush(&pts, P[0]) || !wr__msh_dpush(&pts, P[1])) goto nomem;
    for (i = 0; i + 1 < np; ++i) {
        const double *a = P + 2 * i, *b = P + 2 * i + 2;
        double dx = b[0] - a[0], dy = b[1] - a[1], L = sqrt(dx * dx + dy * dy);
        double h0 = wr__msh_stretched_size(m, a[0], a[1]);
        /* clamp in double before the cast: a huge or NaN ratio must not overflow int32 (fuzzer finding) */
        double nsd = ceil(L / (WR_POISSON_WALK_STEP * h0));
        int32_t ns;
        double hp = h0;
        if (!(nsd >= 1.0)) nsd = 1.0;
        if (nsd > 100000.0) nsd = 100000.0;
        ns = (int32_t)nsd;
        for (k = 1; k <= ns; ++k) {
            double t = (double)k / ns, x = a[0] + t * dx, y = a[1] + t * dy;
            double hk = wr__msh_stretched_size(m, x, y);
            total += 0.5 * (1.0 / hp + 1.0 / hk) * (L / ns);
            hp = hk;
            if (!wr__msh_dpush(&cum, total) || !wr__msh_dpush(&pts, x) || !wr__msh_dpush(&pts, y)) goto nomem;
        }
    }
    if (integral_out) *integral_out = total;
    /* More than 1e7 segments on one curve piece is no cloth pattern; refuse before the int32 cast
     * (reported by the callers as an allocation failure). */
    if (!(total < 1e7)) goto nomem;
    N = (int32_t)floor(total + 0.5);
    if (N < 1) N = 1;
    if (total / N > 1.4) ++N;
    if (measure_only) {
        wr_free(cum.v);
        wr_free(pts.v);
        return N;
    }
    if (forced > 0) N = forced;
    j = 0;
    for (k = 1; k < N; ++k) {
        double target = total * k / N, f;
        while (j + 1 < cum.n && cum.v[j + 1] < target) ++j;
        if (j + 1 >= cum.n) j = cum.n - 2;
        f = (cum.v[j + 1] > cum.v[j]) ? (target - cum.v[j]) / (cum.v[j + 1] - cum.v[j]) : 0.0;
        if (!wr__msh_dpush(out, pts.v[2 * j] + f * (pts.v[2 * j + 2] - pts.v[2 * j])) ||
            !wr__msh_dpush(out, pts.v[2 * j + 1] + f * (pts.v[2 * j + 3] - pts.v[2 * j + 1])))
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

/* Turning angle [deg] at vertex i of a closed loop. */
static double wr__msh_turn(const double *xy, int32_t n, int32_t i) {
    const double *a = xy + 2 * ((i + n - 1) % n), *b = xy + 2 * i, *c = xy + 2 * ((i + 1) % n);
    double ux = b[0] - a[0], uy = b[1] - a[1], vx = c[0] - b[0], vy = c[1] - b[1];
    return fabs(atan2(ux * vy - uy * vx, ux * vx + uy * vy)) * 57.29577951308232;
}

/* Discretise a closed loop (stretched coords L[2n]) with break flags brk[n] (at least one set), and
 * forced segment counts per piece (forced_of_start[v] for the piece starting at break v, 0 = natural).
 * Output points in loop order starting at the first break; index_of[v] = output index of break v. */
static int wr__msh_loop_discretise(const double *L, int32_t n, const int *brk, const int32_t *forced_of_start,
                                   wr__msh_map *m, wr__msh_dbuf *out, int32_t *index_of) {
    int32_t first = -1, v, s;
    wr__msh_dbuf piece;
    memset(&piece, 0, sizeof piece);
    for (v = 0; v < n; ++v)
        if (brk[v]) {
            first = v;
            break;
        }
    if (first < 0) return 0;
    v = first;
    do {
        int32_t w = (v + 1) % n;
        piece.n = 0;
        if (!wr__msh_dpush(&piece, L[2 * v]) || !wr__msh_dpush(&piece, L[2 * v + 1])) goto nomem;
        while (!brk[w]) {
            if (!wr__msh_dpush(&piece, L[2 * w]) || !wr__msh_dpush(&piece, L[2 * w + 1])) goto nomem;
            w = (w + 1) % n;
        }
        if (!wr__msh_dpush(&piece, L[2 * w]) || !wr__msh_dpush(&piece, L[2 * w + 1])) goto nomem;
        index_of[v] = out->n / 2;
        if (!wr__msh_dpush(out, L[2 * v]) || !wr__msh_dpush(out, L[2 * v + 1])) goto nomem;
        s = wr__msh_piece(piece.v, piece.n / 2, m, forced_of_start ? forced_of_start[v] : 0, out, 0, NULL);
        if (s < 0) goto nomem;
        v = w;
    } while (v != first);
    wr_free(piece.v);
    return 1;
nomem:
    wr_free(piece.v);
    return -1;
}

/* ---- the pipeline ----------------------------------------------------------------------------- */
static void wr__msh_m2(double a, double b, double c, double d, double *M) {
    M[0] = a;
    M[1] = b;
    M[2] = c;
    M[3] = d;
}

WRDEF void wr_mesher_free(wr_mesher_result *res) {
    int32_t p;
    if (!res) return;
    wr_mesh_free(&res->mesh);
    wr_free(res->sizing);
    wr_free(res->sizing_warp);
    wr_free(res->sizing_weft);
    wr_free(res->seam_pairs);
    wr_free(res->seam_pair_seam);
    wr_free(res->constraint_segments);
    if (res->panels)
        for (p = 0; p < res->n_panels; ++p) wr__msh_map_free((wr__msh_map *)res->panels[p].map_);
    wr_free(res->panels);
    memset(res, 0, sizeof *res);
}

WRDEF double wr_mesher_eval_sizing(const wr_mesher_result *res, int32_t panel, double x, double y) {
    if (!res || panel < 0 || panel >= res->n_panels || !res->panels[panel].map_) return NAN;
    return wr__msh_map_eval((const wr__msh_map *)res->panels[panel].map_, x, y);
}

/* Checks a technique polyline: n >= 2, finite, every vertex inside the panel (outer, not in holes),
 * no segment crossing a panel loop. Ends within tol of the outer loop are allowed when allow_end_on
 * (flags in on_start/on_end). */
static wr_status wr__msh_check_line(const wr_pattern *pat, int32_t p, const double *xy, int32_t n,
                                    const char *what, int32_t idx, int allow_end_on, int *on_start, int *on_end,
                                    wr_diag *diag) {
    const wr_pattern_panel *pn = &pat->panels[p];
    double tol, bb = 0.0;
    int32_t i, j, h, e;
    double t;
    if (on_start) *on_start = 0;
    if (on_end) *on_end = 0;
    if (!xy || n < 2) return wr_fail(diag, WR_ERR_GEOMETRY, idx, "%s[%d]: fewer than 2 points", what, (int)idx);
    if (!wr__msh_finite_curve(xy, n))
        return wr_fail(diag, WR_ERR_GEOMETRY, idx, "%s[%d]: non-finite coordinate", what, (int)idx);
    for (i = 0; i < pn->outer.n; ++i) bb = fmax(bb, fmax(fabs(pn->outer.xy[2 * i]), fabs(pn->outer.xy[2 * i + 1])));
    tol = WR_MESHER_ON_BOUNDARY_ABS + WR_MESHER_ON_BOUNDARY_REL * bb;
    for (i = 0; i < n; ++i) {
        const double *q = xy + 2 * i;
        double d = wr__msh_loop_closest(pn->outer.xy, pn->outer.n, q, &e, &t);
        int endpt = (i == 0 || i == n - 1);
        if (d <= tol) {
            if (allow_end_on && endpt) {
                if (i == 0 && on_start) *on_start = 1;
                if (i == n - 1 && on_end) *on_end = 1;
                continue;
            }
            return wr_fail(diag, WR_ERR_GEOMETRY, idx, "%s[%d]: point %d touches the boundary of panel %d '%s'",
                           what, (int)idx, (int)i, (int)p, wr__msh_pname(pat, p));
        }
        if (!wr_point_in_polygon(pn->outer.xy, pn->outer.n, q[0], q[1]))
            return wr_fail(diag, WR_ERR_GEOMETRY, idx, "%s[%d]: point %d (%g, %g) m leaves panel %d '%s'", what,
                           (int)idx, (int)i, q[0], q[1], (int)p, wr__msh_pname(pat, p));
        for (h = 0; h < pn->n_holes; ++h)
            if (wr_point_in_polygon(pn->holes[h].xy, pn->holes[h].n, q[0], q[1]))
                return wr_fail(diag, WR_ERR_GEOMETRY, idx, "%s[%d]: point %d lies in hole %d of panel %d '%s'", what,
                               (int)idx, (int)i, (int)h, (int)p, wr__msh_pname(pat, p));
    }
    for (i = 0; i + 1 < n; ++i) {
        const double *a = xy + 2 * i, *b = xy + 2 * i + 2;
        for (h = -1; h < pn->n_holes; ++h) {
            const wr_pattern_curve *c = h < 0 ? &pn->outer : &pn->holes[h];
            for (j = 0; j < c->n; ++j) {
                const double *u = c->xy + 2 * j, *w = c->xy + 2 * ((j + 1) % c->n);
                if (h < 0 && ((i == 0 && on_start && *on_start) || (i == n - 2 && on_end && *on_end))) {
                    /* a segment ending on the boundary touches it there: only a proper crossing counts */
                    double o1 = wr_orient2d(a, b, u), o2 = wr_orient2d(a, b, w), o3 = wr_orient2d(u, w, a),
                           o4 = wr_orient2d(u, w, b);
                    if (((o1 > 0 && o2 < 0) || (o1 < 0 && o2 > 0)) && ((o3 > 0 && o4 < 0) || (o3 < 0 && o4 > 0))) {
                        double da = wr_segment_distance(a, u, w, NULL), db = wr_segment_distance(b, u, w, NULL);
                        if (da > tol && db > tol)
                            return wr_fail(diag, WR_ERR_GEOMETRY, idx, "%s[%d]: segment %d leaves panel %d '%s'",
                                           what, (int)idx, (int)i, (int)p, wr__msh_pname(pat, p));
                    }
                    continue;
                }
                if (wr__msh_seg_cross(a, b, u, w))
                    return wr_fail(diag, WR_ERR_GEOMETRY, idx, "%s[%d]: segment %d leaves panel %d '%s'", what,
                                   (int)idx, (int)i, (int)p, wr__msh_pname(pat, p));
            }
        }
    }
    return WR_OK;
}

static wr_status wr__msh_check_panel_ref(const wr_pattern *pat, int32_t panel, const char *what, int32_t idx,
                                         wr_diag *diag) {
    if (panel < 0 || panel >= pat->n_panels)
        return wr_fail(diag, WR_ERR_INVALID_ARG, idx, "%s[%d]: panel %d does not exist (%d panels)", what, (int)idx,
                       (int)panel, (int)pat->n_panels);
    return WR_OK;
}

static wr_status wr__msh_check_rho(double rho, const char *what, int32_t idx, wr_diag *diag) {
    if (!(rho > 0.0 && rho <= 1.0))
        return wr_fail(diag, WR_ERR_INVALID_ARG, idx, "%s[%d]: rho = %g outside (0, 1]", what, (int)idx, rho);
    return WR_OK;
}

static wr_status wr__msh_check_nonneg(double v, const char *what, int32_t idx, const char *field, wr_diag *diag) {
    if (!(v >= 0.0) || !isfinite(v))
        return wr_fail(diag, WR_ERR_INVALID_ARG, idx, "%s[%d]: %s = %g must be >= 0", what, (int)idx, field, v);
    return WR_OK;
}

/* Validation of everything that does not need the sizing maps. */
static wr_status wr__msh_validate(const wr_pattern *pat, wr_diag *diag) {
    int32_t p, i, h, k;
    wr_status st;
    if (pat->n_panels < 1 || !pat->panels) return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "pattern has no panels");
    if ((pat->n_shirrings > 0 && !pat->shirrings) || (pat->n_folds > 0 && !pat->folds) ||
        (pat->n_seams > 0 && !pat->seams) || (pat->n_quilts > 0 && !pat->quilts) ||
        (pat->n_collisions > 0 && !pat->collisions) || pat->n_shirrings < 0 || pat->n_folds < 0 ||
        pat->n_seams < 0 || pat->n_quilts < 0 || pat->n_collisions < 0)
        return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "pattern technique arrays inconsistent with their counts");
    for (p = 0; p < pat->n_panels; ++p) {
        const wr_pattern_panel *pn = &pat->panels[p];
        if (!pn->outer.xy || pn->outer.n < 3)
            return wr_fail(diag, WR_ERR_GEOMETRY, p, "panels[%d] '%s': outer loop has fewer than 3 points", (int)p,
                           wr__msh_pname(pat, p));
        if (!wr__msh_finite_curve(pn->outer.xy, pn->outer.n))
            return wr_fail(diag, WR_ERR_GEOMETRY, p, "panels[%d] '%s': non-finite coordinate", (int)p,
                           wr__msh_pname(pat, p));
        if (wr_polygon_area(pn->outer.xy, pn->outer.n) == 0.0)
            return wr_fail(diag, WR_ERR_GEOMETRY, p, "panels[%d] '%s': zero area", (int)p, wr__msh_pname(pat, p));
        if (pn->n_holes < 0 || (pn->n_holes > 0 && !pn->holes))
            return wr_fail(diag, WR_ERR_INVALID_ARG, p, "panels[%d] '%s': holes inconsistent", (int)p,
                           wr__msh_pname(pat, p));
        for (h = 0; h < pn->n_holes; ++h) {
            if (!pn->holes[h].xy || pn->holes[h].n < 3)
                return wr_fail(diag, WR_ERR_GEOMETRY, p, "panels[%d] '%s': hole %d has fewer than 3 points", (int)p,
                               wr__msh_pname(pat, p), (int)h);
            if (!wr__msh_finite_curve(pn->holes[h].xy, pn->holes[h].n))
                return wr_fail(diag, WR_ERR_GEOMETRY, p, "panels[%d] '%s': hole %d has a non-finite coordinate",
                               (int)p, wr__msh_pname(pat, p), (int)h);
        }
    }
    for (i = 0; i < pat->n_shirrings; ++i) {
        const wr_pattern_shirring *s = &pat->shirrings[i];
        if ((st = wr__msh_check_panel_ref(pat, s->panel, "shirrings", i, diag)) != WR_OK) return st;
        if ((st = wr__msh_check_rho(s->rho, "shirrings", i, diag)) != WR_OK) return st;
        if ((st = wr__msh_check_nonneg(s->E_sh, "shirrings", i, "E_sh", diag)) != WR_OK) return st;
        if ((st = wr__msh_check_nonneg(s->n_exp, "shirrings", i, "n", diag)) != WR_OK) return st;
        if ((st = wr__msh_check_nonneg(s->transition_length, "shirrings", i, "transition_length", diag)) != WR_OK)
            return st;
    }
    for (i = 0; i < pat->n_folds; ++i) {
        const wr_pattern_fold *f = &pat->folds[i];
        if ((st = wr__msh_check_panel_ref(pat, f->panel, "folds", i, diag)) != WR_OK) return st;
        if (!(f->angle_deg >= 0.0 && f->angle_deg <= 360.0))
            return wr_fail(diag, WR_ERR_INVALID_ARG, i, "folds[%d]: fold angle %g deg outside (0, 360]", (int)i,
                           f->angle_deg);
        if ((st = wr__msh_check_nonneg(f->offset, "folds", i, "offset", diag)) != WR_OK) return st;
        if ((st = wr__msh_check_nonneg(f->curvature_radius, "folds", i, "curvature_radius", diag)) != WR_OK)
            return st;
        if ((st = wr__msh_check_nonneg(f->transition_length, "folds", i, "transition_length", diag)) != WR_OK)
            return st;
    }
    for (i = 0; i < pat->n_seams; ++i) {
        const wr_pattern_seam *s = &pat->seams[i];
        if ((st = wr__msh_check_panel_ref(pat, s->a.panel, "seams", i, diag)) != WR_OK) return st;
        if ((st = wr__msh_check_panel_ref(pat, s->b.panel, "seams", i, diag)) != WR_OK) return st;
        if (!isfinite(s->a.from[0]) || !isfinite(s->a.from[1]) || !isfinite(s->a.to[0]) || !isfinite(s->a.to[1]) ||
            !isfinite(s->b.from[0]) || !isfinite(s->b.from[1]) || !isfinite(s->b.to[0]) || !isfinite(s->b.to[1]))
            return wr_fail(diag, WR_ERR_GEOMETRY, i, "seams[%d]: non-finite end point", (int)i);
        if ((st = wr__msh_check_nonneg(s->transition_length, "seams", i, "transition_length", diag)) != WR_OK)
            return st;
    }
    for (i = 0; i < pat->n_quilts; ++i) {
        const wr_pattern_quilt *q = &pat->quilts[i];
        if ((st = wr__msh_check_panel_ref(pat, q->panel, "quilts", i, diag)) != WR_OK) return st;
        if ((st = wr__msh_check_rho(q->rho, "quilts", i, diag)) != WR_OK) return st;
        if ((st = wr__msh_check_nonneg(q->E_sh, "quilts", i, "E_sh", diag)) != WR_OK) return st;
        if (!(q->pressure >= 0.0) || !isfinite(q->pressure))
            return wr_fail(diag, WR_ERR_INVALID_ARG, i, "quilts[%d]: pressure = %g must be >= 0", (int)i, q->pressure);
        if ((st = wr__msh_check_nonneg(q->transition_length, "quilts", i, "transition_length", diag)) != WR_OK)
            return st;
        if (q->n_lines < 1 || !q->lines)
            return wr_fail(diag, WR_ERR_INVALID_ARG, i, "quilts[%d]: no stitch lines", (int)i);
    }
    for (i = 0; i < pat->n_collisions; ++i) {
        const wr_pattern_collision *c = &pat->collisions[i];
        if ((st = wr__msh_check_panel_ref(pat, c->panel, "collisions", i, diag)) != WR_OK) return st;
        if (!(c->compression > 0.0 && c->compression < 1.0))
            return wr_fail(diag, WR_ERR_INVALID_ARG, i, "collisions[%d]: compression = %g outside (0, 1)", (int)i,
                           c->compression);
        if (c->n == 0) {
            if (!(c->radius > 0.0) || !isfinite(c->radius) || !isfinite(c->center[0]) || !isfinite(c->center[1]))
                return wr_fail(diag, WR_ERR_GEOMETRY, i, "collisions[%d]: disk needs a finite centre and radius > 0",
                               (int)i);
        } else {
            if (c->n < 3 || !c->xy)
                return wr_fail(diag, WR_ERR_GEOMETRY, i, "collisions[%d]: polygon has fewer than 3 points", (int)i);
            if (!wr__msh_finite_curve(c->xy, c->n))
                return wr_fail(diag, WR_ERR_GEOMETRY, i, "collisions[%d]: non-finite coordinate", (int)i);
            if (wr_polygon_area(c->xy, c->n) == 0.0)
                return wr_fail(diag, WR_ERR_GEOMETRY, i, "collisions[%d]: zero-area polygon", (int)i);
        }
        if ((st = wr__msh_check_nonneg(c->transition_length, "collisions", i, "transition_length", diag)) != WR_OK)
            return st;
    }
    (void)k;
    return WR_OK;
}

/* Everything the pipeline keeps per panel while it runs. */
typedef struct wr__msh_panel_work {
    double *loop;      /* refined outer loop, pattern coords (seam points inserted) */
    int32_t n_loop;
    int *brk;          /* break flags on the refined loop */
    int32_t *side_of_edge; /* refined loop edge → seam side id walking over it, -1 */
    int32_t *forced;   /* per break vertex: forced segment count of the piece starting there */
    double h_thick;    /* compression-law thickness */
} wr__msh_panel_work;

static wr_status wr__msh_locate_on_loop(const wr_pattern *pat, int32_t p, const double *pt, int32_t *edge, double *t,
                                        const char *what, int32_t idx, wr_diag *diag) {
    const wr_pattern_panel *pn = &pat->panels[p];
    double bb = 0.0, tol, d;
    int32_t i;
    for (i = 0; i < pn->outer.n; ++i) bb = fmax(bb, fmax(fabs(pn->outer.xy[2 * i]), fabs(pn->outer.xy[2 * i + 1])));
    tol = WR_MESHER_ON_BOUNDARY_ABS + WR_MESHER_ON_BOUNDARY_REL * bb;
    d = wr__msh_loop_closest(pn->outer.xy, pn->outer.n, pt, edge, t);
    if (d > tol)
        return wr_fail(diag, WR_ERR_GEOMETRY, idx,
                       "%s: end point (%g, %g) m does not lie on the boundary of panel %d '%s' (%.3g m away)", what,
                       pt[0], pt[1], (int)p, wr__msh_pname(pat, p), d);
    /* snap to a vertex when within tolerance of one */
    {
        const double *a = pn->outer.xy + 2 * *edge, *b = pn->outer.xy + 2 * ((*edge + 1) % pn->outer.n);
        double L = sqrt((b[0] - a[0]) * (b[0] - a[0]) + (b[1] - a[1]) * (b[1] - a[1]));
        if (*t * L <= tol) *t = 0.0;
        if ((1.0 - *t) * L <= tol) {
            *edge = (*edge + 1) % pn->outer.n;
            *t = 0.0;
        }
    }
    return WR_OK;
}

WRDEF wr_status wr_mesher_run(const wr_pattern *pat, const wr_mesher_desc *desc_in, wr_mesher_result *res,
                              wr_diag *diag) {
    wr_mesher_desc desc;
    wr_status st = WR_OK;
    int32_t np, p, i, j, k, n_sides = 0, max_v;
    wr__msh_panel_work *work = NULL;
    wr__msh_side *sides = NULL;
    wr__msh_dbuf V, S, SW, SF;   /* global vertices (pattern), sizing, warp, weft */
    wr__msh_ibuf F, FP, SEG, SP, SPS;
    double t_start = wr_time_seconds(), t0;
    wr_poisson_result pr;
    wr_cdt_result cr;
    double *stretched = NULL;
    memset(&V, 0, sizeof V);
    memset(&S, 0, sizeof S);
    memset(&SW, 0, sizeof SW);
    memset(&SF, 0, sizeof SF);
    memset(&F, 0, sizeof F);
    memset(&FP, 0, sizeof FP);
    memset(&SEG, 0, sizeof SEG);
    memset(&SP, 0, sizeof SP);
    memset(&SPS, 0, sizeof SPS);
    memset(&pr, 0, sizeof pr);
    memset(&cr, 0, sizeof cr);
    if (!res) return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "NULL result");
    memset(res, 0, sizeof *res);
    if (!pat) return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "NULL pattern");
    if (desc_in)
        desc = *desc_in;
    else
        memset(&desc, 0, sizeof desc);
    if (desc.model.c1 == 0.0 && desc.model.c2 == 0.0) desc.model = wr_resolution_model_paper();
    if (desc.max_vertices <= 0) desc.max_vertices = WR_MESHER_DEFAULT_MAX_VERTICES;
    if (desc.radius_factor < 0.0 || !isfinite(desc.radius_factor) || desc.uniform_resolution < 0.0 ||
        !isfinite(desc.uniform_resolution))
        return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "desc: negative or non-finite radius_factor/uniform_resolution");
    if ((st = wr__msh_validate(pat, diag)) != WR_OK) return st;
    np = pat->n_panels;
    max_v = desc.max_vertices;

    res->panels = (wr_mesher_panel_info *)wr_calloc_array((size_t)np, sizeof(wr_mesher_panel_info));
    work = (wr__msh_panel_work *)wr_calloc_array((size_t)np, sizeof(wr__msh_panel_work));
    sides = (wr__msh_side *)wr_calloc_array((size_t)(2 * pat->n_seams), sizeof(wr__msh_side));
    if (!res->panels || !work || !sides) goto nomem;
    res->n_panels = np;

    /* ---- stage 1: resolutions, affine maps, sizing maps (Sec. 4.1, 4.2) ---- */
    t0 = wr_time_seconds();
    for (p = 0; p < np; ++p) {
        const wr_pattern_panel *pn = &pat->panels[p];
        wr_mesher_panel_info *pi = &res->panels[p];
        wr__msh_map *m;
        double rw, rf, c, s;
        if (desc.uniform_resolution > 0.0) {
            rw = rf = desc.uniform_resolution;
        } else {
            st = wr_mesher_panel_resolution(&pn->fabric, &desc.model, &rw, &rf, diag);
            if (st != WR_OK) {
                char msg[WR_DIAG_MESSAGE_LEN];
                snprintf(msg, sizeof msg, "%s", diag ? diag->message : "");
                st = wr_fail(diag, st, p, "panels[%d] '%s': %s", (int)p, wr__msh_pname(pat, p), msg);
                goto fail;
            }
        }
        pi->r_warp = rw;
        pi->r_weft = rf;
        pi->r0 = rw < rf ? rw : rf;
        c = cos(pn->fabric.anisotropic ? pn->fabric.grain_angle : 0.0);
        s = sin(pn->fabric.anisotropic ? pn->fabric.grain_angle : 0.0);
        /* T = r0 diag(1/rw, 1/rf) Rᵀ, Rᵀ = [[c, s], [-s, c]] */
        wr__msh_m2(pi->r0 / rw * c, pi->r0 / rw * s, -pi->r0 / rf * s, pi->r0 / rf * c, pi->T);
        /* T⁻¹ = R diag(rw, rf)/r0 */
        wr__msh_m2(c * rw / pi->r0, -s * rf / pi->r0, s * rw / pi->r0, c * rf / pi->r0, pi->Tinv);
        pi->area = fabs(wr_polygon_area(pn->outer.xy, pn->outer.n));
        for (i = 0; i < pn->n_holes; ++i) pi->area -= fabs(wr_polygon_area(pn->holes[i].xy, pn->holes[i].n));
        m = (wr__msh_map *)wr_calloc_array(1, sizeof(wr__msh_map));
        if (!m) goto nomem;
        pi->map_ = m;
        m->r0 = pi->r0;
        memcpy(m->Tinv, pi->Tinv, sizeof m->Tinv);
        if (desc.uniform_resolution > 0.0) m->uniform = desc.uniform_resolution;
        if ((st = wr_sizing_create(pi->r0, NULL, &m->s, diag)) != WR_OK) goto fail;
        work[p].h_thick = wr__msh_thickness(&pn->fabric, pi->r0);
    }
    /* technique sources (not in uniform mode) */
    if (!(desc.uniform_resolution > 0.0)) {
        int on0, on1;
        for (i = 0; i < pat->n_shirrings; ++i) {
            const wr_pattern_shirring *sh = &pat->shirrings[i];
            const wr_pattern_fabric *fb = &pat->panels[sh->panel].fabric;
            wr__msh_map *m = (wr__msh_map *)res->panels[sh->panel].map_;
            wr_transition tr;
            wr_resolution_desc rd;
            double r_y, E, B, n_exp = sh->n_exp > 0.0 ? sh->n_exp : 1.0;
            if ((st = wr__msh_check_line(pat, sh->panel, sh->xy, sh->n, "shirrings", i, 1, &on0, &on1, diag)) != WR_OK)
                goto fail;
            memset(&rd, 0, sizeof rd);
            rd.clamp = 1;
            wr__msh_fine_pair(fb, &B, &E);
            if (B > 0.0 && E > 0.0) {
                /* Sec. 4.2.2: y_sh = B/(E+E_sh), r_sh = ρ^n r(y_sh); scaled by r_f / r(B/E), which is 1
                 * unless the panel overrides its base resolution (the override then carries over) */
                double r_b;
                if ((st = wr_source_shirring(&desc.model, B, E, sh->E_sh, sh->rho, n_exp, &rd, &r_y, diag)) != WR_OK)
                    goto fail;
                if ((st = wr_resolution_from_BE(&desc.model, B, E, &rd, &r_b, diag)) != WR_OK) goto fail;
                r_y *= m->r0 / r_b;
            } else {
                r_y = pow(sh->rho, n_exp) * m->r0; /* resolution override without stiffness: E_sh unweighable */
            }
            if ((st = wr__msh_transition(r_y, sh->rho, work[sh->panel].h_thick, sh->transition_length, 0.0, &tr,
                                         diag)) != WR_OK)
                goto fail;
            if ((st = wr_sizing_add_polyline(m->s, sh->xy, sh->n, &tr, diag)) != WR_OK) goto fail;
            res->panels[sh->panel].n_sources++;
        }
        for (i = 0; i < pat->n_quilts; ++i) {
            const wr_pattern_quilt *q = &pat->quilts[i];
            const wr_pattern_fabric *fb = &pat->panels[q->panel].fabric;
            wr__msh_map *m = (wr__msh_map *)res->panels[q->panel].map_;
            wr_transition tr;
            wr_resolution_desc rd;
            double r_y, B, E;
            memset(&rd, 0, sizeof rd);
            rd.clamp = 1;
            wr__msh_fine_pair(fb, &B, &E);
            /* Sec. 4.2.5: stitch lines as shirring lines (n = 1), scaled as for shirring */
            if (B > 0.0 && E > 0.0) {
                double r_b;
                if ((st = wr_source_shirring(&desc.model, B, E, q->E_sh, q->rho, 1.0, &rd, &r_y, diag)) != WR_OK)
                    goto fail;
                if ((st = wr_resolution_from_BE(&desc.model, B, E, &rd, &r_b, diag)) != WR_OK) goto fail;
                r_y *= m->r0 / r_b;
            } else {
                r_y = q->rho * m->r0;
            }
            if ((st = wr__msh_transition(r_y, q->rho, work[q->panel].h_thick, q->transition_length, q->pressure, &tr,
                                         diag)) != WR_OK)
                goto fail;
            for (j = 0; j < q->n_lines; ++j) {
                if ((st = wr__msh_check_line(pat, q->panel, q->lines[j].xy, q->lines[j].n, "quilts", i, 1, &on0, &on1,
                                             diag)) != WR_OK)
                    goto fail;
                if ((st = wr_sizing_add_polyline(m->s, q->lines[j].xy, q->lines[j].n, &tr, diag)) != WR_OK) goto fail;
                res->panels[q->panel].n_sources++;
            }
        }
        for (i = 0; i < pat->n_collisions; ++i) {
            const wr_pattern_collision *c = &pat->collisions[i];
            wr__msh_map *m = (wr__msh_map *)res->panels[c->panel].map_;
            wr__msh_region *nr;
            wr_transition tr;
            double r = (1.0 - c->compression) * m->r0; /* Sec. 4.2.6: compression → local resolution */
            if ((st = wr__msh_transition(r, 1.0 - c->compression, work[c->panel].h_thick, c->transition_length, 0.0,
                                         &tr, diag)) != WR_OK)
                goto fail;
            nr = (wr__msh_region *)wr_realloc_array(m->regions, (size_t)(m->n_regions + 1), sizeof(wr__msh_region));
            if (!nr) goto nomem;
            m->regions = nr;
            nr = &m->regions[m->n_regions++];
            nr->xy = c->n ? c->xy : NULL;
            nr->n = c->n;
            nr->cx = c->center[0];
            nr->cy = c->center[1];
            nr->R = c->radius;
            nr->r = r;
            if (c->n) {
                double *ring = (double *)wr_alloc_array((size_t)(2 * (c->n + 1)), sizeof(double));
                if (!ring) goto nomem;
                memcpy(ring, c->xy, sizeof(double) * 2 * (size_t)c->n);
                ring[2 * c->n] = c->xy[0];
                ring[2 * c->n + 1] = c->xy[1];
                st = wr_sizing_add_polyline(m->s, ring, c->n + 1, &tr, diag);
                wr_free(ring);
                if (st != WR_OK) goto fail;
            } else {
                /* disk: the boundary as a 64-gon polyline source (its chord error is < 0.12% of R) */
                double ring[2 * 65];
                for (j = 0; j <= 64; ++j) {
                    ring[2 * j] = c->center[0] + c->radius * cos(6.283185307179586 * j / 64);
                    ring[2 * j + 1] = c->center[1] + c->radius * sin(6.283185307179586 * j / 64);
                }
                if ((st = wr_sizing_add_polyline(m->s, ring, 65, &tr, diag)) != WR_OK) goto fail;
            }
            res->panels[c->panel].n_sources++;
        }
    }

    /* ---- seams: locate ends, refine loops, overlap checks, long-short sources (Sec. 4.2.4) ---- */
    {
        wr__msh_insert *ins = NULL;
        int32_t n_ins = 0;
        ins = (wr__msh_insert *)wr_alloc_array((size_t)(4 * pat->n_seams + 1), sizeof(wr__msh_insert));
        if (!ins) goto nomem;
        for (i = 0; i < pat->n_seams; ++i) {
            for (k = 0; k < 2; ++k) {
                const wr_pattern_seam_side *sd = k ? &pat->seams[i].b : &pat->seams[i].a;
                char what[64];
                int32_t e;
                double t;
                wr__msh_side *S2 = &sides[2 * i + k];
                S2->seam = i;
                S2->which = k;
                S2->panel = sd->panel;
                S2->reverse = sd->reverse != 0;
                snprintf(what, sizeof what, "seams[%d].%c.from", (int)i, k ? 'b' : 'a');
                if ((st = wr__msh_locate_on_loop(pat, sd->panel, sd->from, &e, &t, what, i, diag)) != WR_OK) {
                    wr_free(ins);
                    goto fail;
                }
                ins[n_ins].edge = e;
                ins[n_ins].t = t;
                ins[n_ins].tag = 2 * (2 * i + k);
                ++n_ins;
                snprintf(what, sizeof what, "seams[%d].%c.to", (int)i, k ? 'b' : 'a');
                if ((st = wr__msh_locate_on_loop(pat, sd->panel, sd->to, &e, &t, what, i, diag)) != WR_OK) {
                    wr_free(ins);
                    goto fail;
                }
                ins[n_ins].edge = e;
                ins[n_ins].t = t;
                ins[n_ins].tag = 2 * (2 * i + k) + 1;
                ++n_ins;
            }
        }
        n_sides = 2 * pat->n_seams;
        qsort(ins, (size_t)n_ins, sizeof *ins, wr__msh_insert_cmp);
        for (p = 0; p < np; ++p) {
            const wr_pattern_panel *pn = &pat->panels[p];
            wr__msh_dbuf L;
            int32_t q = 0, cnt;
            memset(&L, 0, sizeof L);
            /* refined loop: original vertices plus seam points strictly inside edges (deduplicated) */
            for (j = 0; j < pn->outer.n; ++j) {
                int32_t vj = L.n / 2;
                if (!wr__msh_dpush(&L, pn->outer.xy[2 * j]) || !wr__msh_dpush(&L, pn->outer.xy[2 * j + 1])) {
                    wr_free(L.v);
                    wr_free(ins);
                    goto nomem;
                }
                for (q = 0; q < n_ins; ++q) {
                    wr__msh_side *sd = &sides[ins[q].tag / 2];
                    if (sd->panel != p || ins[q].edge != j) continue;
                    if (ins[q].t > 0.0) {
                        const double *a = pn->outer.xy + 2 * j, *b = pn->outer.xy + 2 * ((j + 1) % pn->outer.n);
                        double x = a[0] + ins[q].t * (b[0] - a[0]), y = a[1] + ins[q].t * (b[1] - a[1]);
                        int32_t last = L.n / 2 - 1;
                        if (!(L.v[2 * last] == x && L.v[2 * last + 1] == y)) {
                            if (!wr__msh_dpush(&L, x) || !wr__msh_dpush(&L, y)) {
                                wr_free(L.v);
                                wr_free(ins);
                                goto nomem;
                            }
                        }
                        if (ins[q].tag & 1)
                            sd->v_to = L.n / 2 - 1;
                        else
                            sd->v_from = L.n / 2 - 1;
                    } else {
                        if (ins[q].tag & 1)
                            sd->v_to = vj;
                        else
                            sd->v_from = vj;
                    }
                }
            }
            cnt = L.n / 2;
            work[p].loop = L.v;
            work[p].n_loop = cnt;
            work[p].brk = (int *)wr_calloc_array((size_t)cnt, sizeof(int));
            work[p].side_of_edge = (int32_t *)wr_alloc_array((size_t)cnt, sizeof(int32_t));
            work[p].forced = (int32_t *)wr_calloc_array((size_t)cnt, sizeof(int32_t));
            if (!work[p].brk || !work[p].side_of_edge || !work[p].forced) {
                wr_free(ins);
                goto nomem;
            }
            for (j = 0; j < cnt; ++j) {
                work[p].side_of_edge[j] = -1;
                if (wr__msh_turn(L.v, cnt, j) > WR_MESHER_CORNER_DEG) work[p].brk[j] = 1;
            }
        }
        wr_free(ins);
        /* walk every side, mark edges, detect overlaps and corners inside a range */
        for (k = 0; k < n_sides; ++k) {
            wr__msh_side *sd = &sides[k];
            wr__msh_panel_work *w = &work[sd->panel];
            int32_t v = sd->v_from, steps = 0;
            if (sd->v_from == sd->v_to) {
                st = wr_fail(diag, WR_ERR_GEOMETRY, sd->seam, "seams[%d].%c: from and to coincide (zero length)",
                             (int)sd->seam, sd->which ? 'b' : 'a');
                goto fail;
            }
            sd->length = 0.0;
            while (v != sd->v_to) {
                int32_t e = sd->reverse ? (v + w->n_loop - 1) % w->n_loop : v; /* edge walked */
                int32_t nv = sd->reverse ? (v + w->n_loop - 1) % w->n_loop : (v + 1) % w->n_loop;
                if (w->side_of_edge[e] >= 0) {
                    const wr__msh_side *o = &sides[w->side_of_edge[e]];
                    st = wr_fail(diag, WR_ERR_GEOMETRY, sd->seam, "seams[%d].%c overlaps seams[%d].%c on panel %d '%s'",
                                 (int)sd->seam, sd->which ? 'b' : 'a', (int)o->seam, o->which ? 'b' : 'a',
                                 (int)sd->panel, wr__msh_pname(pat, sd->panel));
                    goto fail;
                }
                w->side_of_edge[e] = k;
                sd->length += sqrt((w->loop[2 * nv] - w->loop[2 * v]) * (w->loop[2 * nv] - w->loop[2 * v]) +
                                   (w->loop[2 * nv + 1] - w->loop[2 * v + 1]) * (w->loop[2 * nv + 1] - w->loop[2 * v + 1]));
                if (nv != sd->v_to && w->brk[nv]) {
                    st = wr_fail(diag, WR_ERR_GEOMETRY, sd->seam,
                                 "seams[%d].%c passes a corner of panel %d '%s' (turn > %g deg); split the seam there",
                                 (int)sd->seam, sd->which ? 'b' : 'a', (int)sd->panel, wr__msh_pname(pat, sd->panel),
                                 WR_MESHER_CORNER_DEG);
                    goto fail;
                }
                v = nv;
                if (++steps > w->n_loop) break;
            }
            w->brk[sd->v_from] = 1;
            w->brk[sd->v_to] = 1;
        }
        /* long-to-short seams: source on the longer side (Sec. 4.2.4) */
        if (!(desc.uniform_resolution > 0.0))
            for (i = 0; i < pat->n_seams; ++i) {
                wr__msh_side *a = &sides[2 * i], *b = &sides[2 * i + 1], *lng;
                double rho;
                wr__msh_map *m;
                wr__msh_panel_work *w;
                wr__msh_dbuf pl;
                wr_transition tr;
                int32_t v;
                if (a->length <= 0.0 || b->length <= 0.0) continue;
                lng = a->length >= b->length ? a : b;
                if ((st = wr_source_stitch_ratio(fmin(a->length, b->length), fmax(a->length, b->length), &rho, diag)) !=
                    WR_OK)
                    goto fail;
                if (rho >= 1.0 - 1e-9) continue; /* equal lengths: no compression */
                m = (wr__msh_map *)res->panels[lng->panel].map_;
                w = &work[lng->panel];
                if ((st = wr__msh_transition(rho * m->r0, rho, w->h_thick, pat->seams[i].transition_length, 0.0, &tr,
                                             diag)) != WR_OK)
                    goto fail;
                memset(&pl, 0, sizeof pl);
                v = lng->v_from;
                for (;;) {
                    if (!wr__msh_dpush(&pl, w->loop[2 * v]) || !wr__msh_dpush(&pl, w->loop[2 * v + 1])) {
                        wr_free(pl.v);
                        goto nomem;
                    }
                    if (v == lng->v_to) break;
                    v = lng->reverse ? (v + w->n_loop - 1) % w->n_loop : (v + 1) % w->n_loop;
                }
                st = wr_sizing_add_polyline(m->s, pl.v, pl.n / 2, &tr, diag);
                wr_free(pl.v);
                if (st != WR_OK) goto fail;
                res->panels[lng->panel].n_sources++;
            }
    }
    /* folds, pass 1 (check) — their points need r_ng from the map without them (Sec. 4.2.3) */
    for (p = 0; p < np; ++p) {
        wr__msh_map *m = (wr__msh_map *)res->panels[p].map_;
        if ((st = wr_sizing_build(m->s, diag)) != WR_OK) goto fail;
    }
    for (i = 0; i < pat->n_folds; ++i) {
        const wr_pattern_fold *fd = &pat->folds[i];
        if ((st = wr__msh_check_line(pat, fd->panel, fd->xy, fd->n, "folds", i, 0, NULL, NULL, diag)) != WR_OK)
            goto fail;
    }
    if (!(desc.uniform_resolution > 0.0) && pat->n_folds > 0) {
        /* fold points: collect first (r_ng from the map without fold points), then add */
        typedef struct {
            int32_t panel;
            double x, y, dx, dy;
            wr_transition t;
        } wr__msh_fpt;
        wr__msh_fpt *fp = NULL;
        int32_t nfp = 0, cap = 0;
        for (i = 0; i < pat->n_folds && st == WR_OK; ++i) {
            const wr_pattern_fold *fd = &pat->folds[i];
            wr__msh_map *m = (wr__msh_map *)res->panels[fd->panel].map_;
            double ang = fd->angle_deg > 0.0 ? fd->angle_deg : WR_MESHER_DEFAULT_FOLD_ANGLE;
            double rho = ang / 360.0; /* ρ_fd = Δθ/360 */
            double Rc = fd->curvature_radius > 0.0 ? fd->curvature_radius : WR_MESHER_DEFAULT_CURVATURE_RADIUS;
            double *kap = (double *)wr_calloc_array((size_t)fd->n, sizeof(double));
            if (!kap) {
                wr_free(fp);
                goto nomem;
            }
            for (j = 1; j + 1 < fd->n; ++j) {
                const double *a = fd->xy + 2 * (j - 1), *b = fd->xy + 2 * j, *c = fd->xy + 2 * (j + 1);
                double ux = b[0] - a[0], uy = b[1] - a[1], vx = c[0] - b[0], vy = c[1] - b[1];
                double la = sqrt(ux * ux + uy * uy), lb = sqrt(vx * vx + vy * vy);
                double turn = fabs(atan2(ux * vy - uy * vx, ux * vx + uy * vy));
                kap[j] = (la + lb > 0.0) ? turn / (0.5 * (la + lb)) : 0.0;
            }
            for (j = 0; j < fd->n; ++j) {
                double dx, dy, nrm, rng, rfd;
                int take = 0;
                if (j == 0 || j == fd->n - 1) {
                    /* endpoint: direction into the fold */
                    const double *a = fd->xy + 2 * j, *b = fd->xy + 2 * (j == 0 ? 1 : fd->n - 2);
                    dx = b[0] - a[0];
                    dy = b[1] - a[1];
                    take = 1;
                } else if (kap[j] >= 1.0 / Rc && kap[j] >= kap[j - 1] && kap[j] >= kap[j + 1]) {
                    /* high-curvature point: normal towards the centre of curvature */
                    const double *a = fd->xy + 2 * (j - 1), *b = fd->xy + 2 * j, *c = fd->xy + 2 * (j + 1);
                    double ux = b[0] - a[0], uy = b[1] - a[1], vx = c[0] - b[0], vy = c[1] - b[1];
                    double cr2 = ux * vy - uy * vx, tx = ux / (sqrt(ux * ux + uy * uy)) + vx / sqrt(vx * vx + vy * vy),
                           ty = uy / (sqrt(ux * ux + uy * uy)) + vy / sqrt(vx * vx + vy * vy);
                    /* left normal of the tangent for a left turn (cr2 > 0), right normal otherwise */
                    dx = cr2 > 0 ? -ty : ty;
                    dy = cr2 > 0 ? tx : -tx;
                    take = 1;
                }
                if (!take) continue;
                nrm = sqrt(dx * dx + dy * dy);
                if (!(nrm > 0.0)) continue;
                rng = wr__msh_map_eval(m, fd->xy[2 * j], fd->xy[2 * j + 1]);
                /* Sec. 4.2.3: r_fd = (Δθ/360°) r_ng */
                if ((st = wr_source_folding(ang * 0.017453292519943295, rng, &rfd, diag)) != WR_OK) break;
                if (nfp == cap) {
                    int32_t nc = cap ? 2 * cap : 16;
                    wr__msh_fpt *nf = (wr__msh_fpt *)wr_realloc_array(fp, (size_t)nc, sizeof(wr__msh_fpt));
                    if (!nf) {
                        wr_free(kap);
                        wr_free(fp);
                        goto nomem;
                    }
                    fp = nf;
                    cap = nc;
                }
                fp[nfp].panel = fd->panel;
                fp[nfp].x = fd->xy[2 * j];
                fp[nfp].y = fd->xy[2 * j + 1];
                fp[nfp].dx = dx / nrm;
                fp[nfp].dy = dy / nrm;
                st = wr__msh_transition(rfd, rho, work[fd->panel].h_thick, fd->transition_length, 0.0, &fp[nfp].t,
                                        diag);
                ++nfp;
                if (st != WR_OK) break;
            }
            wr_free(kap);
        }
        for (j = 0; j < nfp && st == WR_OK; ++j) {
            wr__msh_map *m = (wr__msh_map *)res->panels[fp[j].panel].map_;
            st = wr_sizing_add_point_directional(m->s, fp[j].x, fp[j].y, fp[j].dx, fp[j].dy, &fp[j].t, diag);
            res->panels[fp[j].panel].n_sources++;
        }
        wr_free(fp);
        if (st != WR_OK) goto fail;
        for (p = 0; p < np; ++p)
            if ((st = wr_sizing_build(((wr__msh_map *)res->panels[p].map_)->s, diag)) != WR_OK) goto fail;
    }
    res->report.t_sizing = wr_time_seconds() - t0;

    /* ---- per panel: discretise, sample, triangulate, append ---- */
    for (p = 0; p < np; ++p) {
        const wr_pattern_panel *pn = &pat->panels[p];
        wr_mesher_panel_info *pi = &res->panels[p];
        wr__msh_panel_work *w = &work[p];
        wr__msh_map *m = (wr__msh_map *)pi->map_;
        wr__msh_dbuf outer, holes, lines;
        wr__msh_ibuf hole_n, line_n, line_lab; /* line_lab: 2 per line (kind 0/1/2, technique index) */
        int32_t *idx_of = NULL, nL = w->n_loop, vbase = V.n / 2;
        double *hseeds = NULL;
        wr__msh_dbuf cpts;
        wr__msh_ibuf csegs;
        wr_poisson_curve *hc = NULL, *lc = NULL;
        wr_poisson_domain dom;
        wr_poisson_desc pd;
        wr_cdt_input ci;
        wr_cdt_desc cd;
        int anybrk = 0;
        memset(&outer, 0, sizeof outer);
        memset(&holes, 0, sizeof holes);
        memset(&lines, 0, sizeof lines);
        memset(&hole_n, 0, sizeof hole_n);
        memset(&line_n, 0, sizeof line_n);
        memset(&line_lab, 0, sizeof line_lab);
        memset(&cpts, 0, sizeof cpts);
        memset(&csegs, 0, sizeof csegs);
        t0 = wr_time_seconds();
        /* stretched loop */
        stretched = (double *)wr_alloc_array((size_t)(2 * nL), sizeof(double));
        idx_of = (int32_t *)wr_alloc_array((size_t)nL, sizeof(int32_t));
        if (!stretched || !idx_of) goto panel_nomem;
        for (j = 0; j < nL; ++j) wr__msh_apply(pi->T, w->loop + 2 * j, stretched + 2 * j);
        for (j = 0; j < nL; ++j) anybrk |= w->brk[j];
        if (!anybrk) w->brk[0] = 1;
        /* forced counts for seam pieces: N = max of both sides' natural counts */
        for (k = 0; k < n_sides; k += 2) {
            wr__msh_side *sa = &sides[k], *sb = &sides[k + 1];
            if (sa->panel != p && sb->panel != p) continue;
            if (sa->N == 0) {
                int32_t s2;
                for (s2 = 0; s2 < 2; ++s2) {
                    wr__msh_side *sd = &sides[k + s2];
                    wr__msh_panel_work *ww = &work[sd->panel];
                    wr_mesher_panel_info *pp = &res->panels[sd->panel];
                    wr__msh_dbuf pc;
                    int32_t v = sd->v_from, cnt;
                    double q2[2];
                    memset(&pc, 0, sizeof pc);
                    for (;;) {
                        wr__msh_apply(pp->T, ww->loop + 2 * v, q2);
                        if (!wr__msh_dpush(&pc, q2[0]) || !wr__msh_dpush(&pc, q2[1])) {
                            wr_free(pc.v);
                            goto panel_nomem;
                        }
                        if (v == sd->v_to) break;
                        v = sd->reverse ? (v + ww->n_loop - 1) % ww->n_loop : (v + 1) % ww->n_loop;
                    }
                    cnt = wr__msh_piece(pc.v, pc.n / 2, (wr__msh_map *)pp->map_, 0, NULL, 1, NULL);
                    wr_free(pc.v);
                    if (cnt < 0) goto panel_nomem;
                    if (cnt > sa->N) sa->N = cnt;
                }
                sb->N = sa->N;
            }
        }
        for (k = 0; k < n_sides; ++k) {
            wr__msh_side *sd = &sides[k];
            if (sd->panel != p) continue;
            /* the piece in loop order starts at from (forward walk) or at to (reverse walk) */
            w->forced[sd->reverse ? sd->v_to : sd->v_from] = sd->N;
        }
        if (wr__msh_loop_discretise(stretched, nL, w->brk, w->forced, m, &outer, idx_of) < 0) goto panel_nomem;
        /* holes: natural discretisation, break at corners (or vertex 0) */
        for (j = 0; j < pn->n_holes; ++j) {
            const wr_pattern_curve *hcv = &pn->holes[j];
            double *hs = (double *)wr_alloc_array((size_t)(2 * hcv->n), sizeof(double));
            int *hb = (int *)wr_calloc_array((size_t)hcv->n, sizeof(int));
            int32_t *hi = (int32_t *)wr_alloc_array((size_t)hcv->n, sizeof(int32_t));
            int32_t before = holes.n, ok;
            if (!hs || !hb || !hi) {
                wr_free(hs);
                wr_free(hb);
                wr_free(hi);
                goto panel_nomem;
            }
            for (k = 0; k < hcv->n; ++k) {
                wr__msh_apply(pi->T, hcv->xy + 2 * k, hs + 2 * k);
                hb[k] = wr__msh_turn(hcv->xy, hcv->n, k) > WR_MESHER_CORNER_DEG;
            }
            hb[0] = 1;
            ok = wr__msh_loop_discretise(hs, hcv->n, hb, NULL, m, &holes, hi);
            wr_free(hs);
            wr_free(hb);
            wr_free(hi);
            if (ok < 0 || !wr__msh_ipush(&hole_n, (holes.n - before) / 2)) goto panel_nomem;
        }
        /* constraint lines: shirring, quilt stitches, folds (+ parallels); pattern → stretched */
        {
            int32_t t2;
            for (t2 = 0; t2 < 3; ++t2) {
                int32_t count = t2 == 0 ? pat->n_shirrings : t2 == 1 ? pat->n_quilts : pat->n_folds;
                for (i = 0; i < count; ++i) {
                    int32_t nsub = t2 == 1 ? pat->quilts[i].n_lines : t2 == 2 ? 3 : 1, u;
                    int32_t owner = t2 == 0 ? pat->shirrings[i].panel : t2 == 1 ? pat->quilts[i].panel : pat->folds[i].panel;
                    if (owner != p) continue;
                    for (u = 0; u < nsub; ++u) {
                        const double *xy;
                        int32_t n, before = lines.n, s3;
                        double *poly, off = 0.0;
                        int on0 = 0, on1 = 0;
                        if (t2 == 0) {
                            xy = pat->shirrings[i].xy;
                            n = pat->shirrings[i].n;
                        } else if (t2 == 1) {
                            xy = pat->quilts[i].lines[u].xy;
                            n = pat->quilts[i].lines[u].n;
                        } else {
                            xy = pat->folds[i].xy;
                            n = pat->folds[i].n;
                            off = (pat->folds[i].offset > 0.0 ? pat->folds[i].offset : WR_MESHER_DEFAULT_FOLD_OFFSET) *
                                  (u == 0 ? 0.0 : u == 1 ? 1.0 : -1.0);
                        }
                        if (t2 != 2 &&
                            wr__msh_check_line(pat, p, xy, n, "lines", i, 1, &on0, &on1, NULL) != WR_OK)
                            on0 = on1 = 0;
                        poly = (double *)wr_alloc_array((size_t)(2 * n), sizeof(double));
                        if (!poly) goto panel_nomem;
                        for (k = 0; k < n; ++k) {
                            double q[2];
                            q[0] = xy[2 * k];
                            q[1] = xy[2 * k + 1];
                            if (off != 0.0) {
                                /* mitred offset: average of adjacent segment normals, scaled by 1/cos */
                                double nx = 0.0, ny = 0.0, sx, sy, sl, dotn;
                                int32_t a2;
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
                                /* 1/cos of the half angle between the mitre and a segment normal */
                                dotn = 1.0;
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
                            wr__msh_apply(pi->T, q, poly + 2 * k);
                        }
                        /* trim ends that lie on the boundary (the sampler needs strictly inside lines) */
                        for (s3 = 0; s3 < 2; ++s3) {
                            int on = s3 ? on1 : on0;
                            double *e0, *e1, dx, dy, L, h, cut;
                            if (!on || n < 2) continue;
                            e0 = s3 ? poly + 2 * (n - 1) : poly;
                            e1 = s3 ? poly + 2 * (n - 2) : poly + 2;
                            dx = e1[0] - e0[0];
                            dy = e1[1] - e0[1];
                            L = sqrt(dx * dx + dy * dy);
                            h = wr__msh_stretched_size(m, e0[0], e0[1]);
                            cut = WR_MESHER_TRIM_FACTOR * h;
                            if (cut > 0.45 * L) cut = 0.45 * L;
                            if (L > 0.0) {
                                e0[0] += dx / L * cut;
                                e0[1] += dy / L * cut;
                            }
                        }
                        /* discretise: break at every input vertex, natural counts */
                        {
                            int32_t a3;
                            int32_t s4;
                            if (!wr__msh_dpush(&lines, poly[0]) || !wr__msh_dpush(&lines, poly[1])) {
                                wr_free(poly);
                                goto panel_nomem;
                            }
                            for (a3 = 0; a3 + 1 < n; ++a3) {
                                s4 = wr__msh_piece(poly + 2 * a3, 2, m, 0, &lines, 0, NULL);
                                if (s4 < 0 || !wr__msh_dpush(&lines, poly[2 * a3 + 2]) ||
                                    !wr__msh_dpush(&lines, poly[2 * a3 + 3])) {
                                    wr_free(poly);
                                    goto panel_nomem;
                                }
                            }
                        }
                        wr_free(poly);
                        if (!wr__msh_ipush(&line_n, (lines.n - before) / 2) || !wr__msh_ipush(&line_lab, t2) ||
                            !wr__msh_ipush(&line_lab, i))
                            goto panel_nomem;
                    }
                }
            }
        }
        res->report.t_discretise += wr_time_seconds() - t0;
        /* The curve points become mesh vertices: when they alone exceed the budget, refuse now, before
         * the sampler's crossing checks over them (fuzzer finding pattern_giant_panel_budget: a 33 km
         * panel edge at the sizing gave ~1.1e7 boundary points against a budget of 2000, and minutes
         * of checks before the sampler's own budget test). */
        if ((double)V.n / 2 + (double)(outer.n + holes.n + lines.n) / 2 > (double)max_v) {
            st = wr_fail(diag, WR_ERR_BUDGET, p,
                         "vertex budget of %d exceeded at panels[%d] '%s': its curves alone need %.0f points at the sizing",
                         (int)max_v, (int)p, wr__msh_pname(pat, p), (double)(outer.n + holes.n + lines.n) / 2);
            goto panel_fail;
        }
        /* ---- Poisson sampling in stretched space (Sec. 4.3, Bridson) ---- */
        t0 = wr_time_seconds();
        hc = (wr_poisson_curve *)wr_calloc_array((size_t)hole_n.n, sizeof(wr_poisson_curve));
        lc = (wr_poisson_curve *)wr_calloc_array((size_t)line_n.n, sizeof(wr_poisson_curve));
        if (!hc || !lc) goto panel_nomem;
        {
            int32_t off2 = 0;
            for (j = 0; j < hole_n.n; ++j) {
                hc[j].xy = holes.v + 2 * off2;
                hc[j].n = hole_n.v[j];
                off2 += hole_n.v[j];
            }
            off2 = 0;
            for (j = 0; j < line_n.n; ++j) {
                lc[j].xy = lines.v + 2 * off2;
                lc[j].n = line_n.v[j];
                off2 += line_n.v[j];
            }
        }
        memset(&dom, 0, sizeof dom);
        dom.outer.xy = outer.v;
        dom.outer.n = outer.n / 2;
        dom.outer.closed = 1;
        dom.holes = hc;
        dom.n_holes = hole_n.n;
        dom.lines = lc;
        dom.n_lines = line_n.n;
        memset(&pd, 0, sizeof pd);
        pd.seed = desc.seed + (uint64_t)p * 0x9E3779B97F4A7C15ULL;
        pd.radius_factor = desc.radius_factor;
        pd.corner_angle = 1e-9; /* keep our points where it can, so its curve points match ours closely */
        pd.max_points = max_v - V.n / 2;
        if (pd.max_points < 3) pd.max_points = 3;
        st = wr_poisson_sample(&dom, wr__msh_stretched_size, m, &pd, &pr, diag);
        if (st != WR_OK) {
            char msg[WR_DIAG_MESSAGE_LEN];
            snprintf(msg, sizeof msg, "%s", diag ? diag->message : "");
            if (st == WR_ERR_BUDGET)
                st = wr_fail(diag, st, p, "vertex budget of %d exceeded at panels[%d] '%s' (%s)", (int)max_v, (int)p,
                             wr__msh_pname(pat, p), msg);
            else {
                /* name the techniques behind the sampler's "polyline j" (its constraint-line numbering) */
                char legend[160];
                const char *q = msg;
                size_t ll = 0;
                int seen = 0;
                static const char *const kinds[3] = {"shirrings", "quilts", "folds"};
                legend[0] = 0;
                while ((q = strstr(q, "polyline ")) != NULL && seen < 3) {
                    int lj = atoi(q + 9);
                    if (lj >= 0 && lj < line_n.n && ll < sizeof legend - 40) {
                        ll += (size_t)snprintf(legend + ll, sizeof legend - ll, "%s polyline %d = %s[%d]",
                                               seen ? ";" : " [", lj, kinds[line_lab.v[2 * lj]],
                                               (int)line_lab.v[2 * lj + 1]);
                        ++seen;
                    }
                    q += 9;
                }
                if (seen && ll < sizeof legend - 2) snprintf(legend + ll, sizeof legend - ll, "]");
                st = wr_fail(diag, st, p, "panels[%d] '%s': %.300s%s", (int)p, wr__msh_pname(pat, p), msg, legend);
            }
            goto panel_fail;
        }
        /* CDT input: OUR fixed points (outer, holes, lines — so seam counts are exactly ours) plus
         * the sampler's interior samples, minus any sample that falls outside our polygon or closer
         * than WR_MESHER_SAMPLE_CLEARANCE × h to one of our constraint segments (the sampler's own
         * re-discretisation of the curves can differ slightly from ours). */
        {
            int32_t n_out = outer.n / 2, n_hol = holes.n / 2, n_lin = line_n.n ? lines.n / 2 : 0;
            int32_t nfix = n_out + n_hol + n_lin, off3, c7, ns = 0;
            double hmax = 0.0, bx0 = HUGE_VAL, by0 = HUGE_VAL, bx1 = -HUGE_VAL, by1 = -HUGE_VAL, cell;
            int32_t gx, gy, *gstart = NULL, *gitem = NULL;
            if (!wr__msh_dbuf_reserve(&cpts, 2 * (nfix + pr.n_points - pr.n_fixed))) goto panel_nomem;
            for (j = 0; j < outer.n; ++j) cpts.v[cpts.n++] = outer.v[j];
            for (j = 0; j < holes.n; ++j) cpts.v[cpts.n++] = holes.v[j];
            for (j = 0; j < 2 * n_lin; ++j) cpts.v[cpts.n++] = lines.v[j];
            /* segments: closed outer, closed holes, open lines */
            for (j = 0; j < n_out; ++j)
                if (!wr__msh_ipush(&csegs, j) || !wr__msh_ipush(&csegs, (j + 1) % n_out)) goto panel_nomem;
            off3 = n_out;
            for (k = 0; k < hole_n.n; ++k) {
                for (j = 0; j < hole_n.v[k]; ++j)
                    if (!wr__msh_ipush(&csegs, off3 + j) || !wr__msh_ipush(&csegs, off3 + (j + 1) % hole_n.v[k]))
                        goto panel_nomem;
                off3 += hole_n.v[k];
            }
            for (k = 0; k < line_n.n; ++k) {
                for (j = 0; j + 1 < line_n.v[k]; ++j)
                    if (!wr__msh_ipush(&csegs, off3 + j) || !wr__msh_ipush(&csegs, off3 + j + 1)) goto panel_nomem;
                off3 += line_n.v[k];
            }
            /* bucket grid over the segments, cell = largest sizing among the samples and fixed points */
            for (j = 0; j < pr.n_points; ++j) {
                if (pr.sizing[j] > hmax) hmax = pr.sizing[j];
                bx0 = fmin(bx0, pr.points[2 * j]);
                by0 = fmin(by0, pr.points[2 * j + 1]);
                bx1 = fmax(bx1, pr.points[2 * j]);
                by1 = fmax(by1, pr.points[2 * j + 1]);
            }
            for (j = 0; j < nfix; ++j) {
                bx0 = fmin(bx0, cpts.v[2 * j]);
                by0 = fmin(by0, cpts.v[2 * j + 1]);
                bx1 = fmax(bx1, cpts.v[2 * j]);
                by1 = fmax(by1, cpts.v[2 * j + 1]);
            }
            cell = hmax > 0.0 ? hmax : 1.0;
            if ((bx1 - bx0) / cell > 2048.0 || (by1 - by0) / cell > 2048.0)
                cell = fmax(bx1 - bx0, by1 - by0) / 2048.0;
            gx = (int32_t)((bx1 - bx0) / cell) + 1;
            gy = (int32_t)((by1 - by0) / cell) + 1;
            gstart = (int32_t *)wr_calloc_array((size_t)gx * (size_t)gy + 1, sizeof(int32_t));
            if (!gstart) goto panel_nomem;
            for (c7 = 0; c7 < 2; ++c7) { /* pass 0 counts, pass 1 fills (CSR) */
                int32_t sidx;
                if (c7 == 1) {
                    int32_t acc = 0, cc;
                    for (cc = 0; cc < gx * gy; ++cc) {
                        int32_t t4 = gstart[cc];
                        gstart[cc] = acc;
                        acc += t4;
                    }
                    gstart[gx * gy] = acc;
                    gitem = (int32_t *)wr_alloc_array((size_t)acc + 1, sizeof(int32_t));
                    if (!gitem) {
                        wr_free(gstart);
                        goto panel_nomem;
                    }
                }
                for (sidx = 0; sidx < csegs.n / 2; ++sidx) {
                    const double *a = cpts.v + 2 * csegs.v[2 * sidx], *b = cpts.v + 2 * csegs.v[2 * sidx + 1];
                    int32_t x0 = (int32_t)((fmin(a[0], b[0]) - bx0) / cell), x1 = (int32_t)((fmax(a[0], b[0]) - bx0) / cell);
                    int32_t y0 = (int32_t)((fmin(a[1], b[1]) - by0) / cell), y1 = (int32_t)((fmax(a[1], b[1]) - by0) / cell);
                    int32_t xx, yy;
                    if (x1 >= gx) x1 = gx - 1;
                    if (y1 >= gy) y1 = gy - 1;
                    for (yy = y0; yy <= y1; ++yy)
                        for (xx = x0; xx <= x1; ++xx) {
                            if (c7 == 0)
                                gstart[yy * gx + xx]++;
                            else
                                gitem[gstart[yy * gx + xx]++] = sidx;
                        }
                }
                if (c7 == 1) { /* restore starts */
                    int32_t cc;
                    for (cc = gx * gy; cc > 0; --cc) gstart[cc] = gstart[cc - 1];
                    gstart[0] = 0;
                }
            }
            for (j = pr.n_fixed; j < pr.n_points; ++j) {
                const double *q = pr.points + 2 * j;
                double h = pr.sizing[j], dmin = HUGE_VAL;
                int32_t cx = (int32_t)((q[0] - bx0) / cell), cy = (int32_t)((q[1] - by0) / cell), xx, yy, it;
                int keep = 1;
                for (yy = cy - 1; yy <= cy + 1; ++yy)
                    for (xx = cx - 1; xx <= cx + 1; ++xx) {
                        if (xx < 0 || yy < 0 || xx >= gx || yy >= gy) continue;
                        for (it = gstart[yy * gx + xx]; it < gstart[yy * gx + xx + 1]; ++it) {
                            int32_t sg = gitem[it];
                            double d = wr_segment_distance(q, cpts.v + 2 * csegs.v[2 * sg], cpts.v + 2 * csegs.v[2 * sg + 1],
                                                        NULL);
                            if (d < dmin) dmin = d;
                        }
                    }
                if (dmin < WR_MESHER_SAMPLE_CLEARANCE * h) keep = 0;
                if (keep && dmin < 2.0 * h) {
                    /* near our boundary: exact-ish containment against our own polygon */
                    if (!wr_point_in_polygon(outer.v, n_out, q[0], q[1])) keep = 0;
                    for (k = 0; k < hole_n.n && keep; ++k)
                        if (wr_point_in_polygon(hc[k].xy, hc[k].n, q[0], q[1])) keep = 0;
                }
                if (!keep) continue;
                cpts.v[cpts.n++] = q[0];
                cpts.v[cpts.n++] = q[1];
                ++ns;
            }
            wr_free(gstart);
            wr_free(gitem);
            (void)ns;
        }
        res->report.t_poisson += wr_time_seconds() - t0; /* sampling + filtering against our curves */
        /* ---- CDT ---- */
        t0 = wr_time_seconds();
        /* one seed strictly inside each hole: an edge midpoint nudged into the hole (checked) */
        if (hole_n.n > 0) {
            hseeds = (double *)wr_alloc_array((size_t)(2 * hole_n.n), sizeof(double));
            if (!hseeds) goto panel_nomem;
            for (k = 0; k < hole_n.n; ++k) {
                const double *H = hc[k].xy;
                int32_t nh = hc[k].n, e2, found = 0;
                double sgn = wr_polygon_area(H, nh) > 0.0 ? 1.0 : -1.0; /* CCW hole: interior on the left */
                for (e2 = 0; e2 < nh && !found; ++e2) {
                    const double *a = H + 2 * e2, *b = H + 2 * ((e2 + 1) % nh);
                    double dx = b[0] - a[0], dy = b[1] - a[1], L = sqrt(dx * dx + dy * dy), f2;
                    if (!(L > 0.0)) continue;
                    for (f2 = 1e-2; f2 >= 1e-6 && !found; f2 *= 0.1) {
                        double x = 0.5 * (a[0] + b[0]) - sgn * dy * f2, y = 0.5 * (a[1] + b[1]) + sgn * dx * f2;
                        if (wr_point_in_polygon(H, nh, x, y)) {
                            hseeds[2 * k] = x;
                            hseeds[2 * k + 1] = y;
                            found = 1;
                        }
                    }
                }
                if (!found) {
                    st = wr_fail(diag, WR_ERR_GEOMETRY, p, "panels[%d] '%s': hole %d is too thin to seed", (int)p,
                                 wr__msh_pname(pat, p), (int)k);
                    goto panel_fail;
                }
            }
        }
        memset(&ci, 0, sizeof ci);
        ci.holes = hseeds;
        ci.n_holes = hole_n.n;
        ci.points = cpts.v;
        ci.n_points = cpts.n / 2;
        ci.segments = csegs.v;
        ci.n_segments = csegs.n / 2;
        memset(&cd, 0, sizeof cd);
        cd.seed = desc.seed + 1;
        st = wr_cdt_triangulate(&ci, &cd, &cr, diag);
        if (st != WR_OK) {
            char msg[WR_DIAG_MESSAGE_LEN];
            snprintf(msg, sizeof msg, "%s", diag ? diag->message : "");
            st = wr_fail(diag, st, p, "panels[%d] '%s': triangulation: %s", (int)p, wr__msh_pname(pat, p), msg);
            goto panel_fail;
        }
        res->report.t_cdt += wr_time_seconds() - t0;
        t0 = wr_time_seconds();
        if (V.n / 2 + cr.n_points > max_v) {
            st = wr_fail(diag, WR_ERR_BUDGET, p, "vertex budget of %d exceeded at panels[%d] '%s'", (int)max_v, (int)p,
                         wr__msh_pname(pat, p));
            goto panel_fail;
        }
        /* vertices: map back to the pattern; sizing from the map */
        for (j = 0; j < cr.n_points; ++j) {
            double q[2], h;
            wr__msh_apply(pi->Tinv, cr.points + 2 * j, q);
            h = wr__msh_stretched_size(m, cr.points[2 * j], cr.points[2 * j + 1]);
            if (!wr__msh_dpush(&V, q[0]) || !wr__msh_dpush(&V, q[1]) || !wr__msh_dpush(&S, h) ||
                !wr__msh_dpush(&SW, h * pi->r_warp / pi->r0) || !wr__msh_dpush(&SF, h * pi->r_weft / pi->r0))
                goto panel_nomem;
        }
        /* faces: the CDT carved the exterior (outer loop) and the holes (seeds) */
        if (!cr.exterior_carved) {
            st = wr_fail(diag, WR_ERR_GEOMETRY, p, "panels[%d] '%s': triangulation did not carve the exterior",
                         (int)p, wr__msh_pname(pat, p));
            goto panel_fail;
        }
        pi->f_begin = F.n / 3;
        for (j = 0; j < cr.n_triangles; ++j) {
            const int32_t *t3 = cr.triangles + 3 * j;
            if (!wr__msh_ipush(&F, vbase + t3[0]) || !wr__msh_ipush(&F, vbase + t3[1]) ||
                !wr__msh_ipush(&F, vbase + t3[2]) || !wr__msh_ipush(&FP, p))
                goto panel_nomem;
        }
        pi->f_end = F.n / 3;
        pi->v_begin = vbase;
        pi->v_end = V.n / 2;
        for (j = 0; j < csegs.n / 2; ++j)
            if (!wr__msh_ipush(&SEG, vbase + cr.point_map[csegs.v[2 * j]]) ||
                !wr__msh_ipush(&SEG, vbase + cr.point_map[csegs.v[2 * j + 1]]))
                goto panel_nomem;
        /* seam sides of this panel: vertex ids in walk order */
        for (k = 0; k < n_sides; ++k) {
            wr__msh_side *sd = &sides[k];
            int32_t a5, c5;
            if (sd->panel != p) continue;
            a5 = idx_of[sd->reverse ? sd->v_to : sd->v_from];
            sd->global = (int32_t *)wr_alloc_array((size_t)(sd->N + 1), sizeof(int32_t));
            if (!sd->global) goto panel_nomem;
            for (c5 = 0; c5 <= sd->N; ++c5) {
                int32_t oi = (a5 + c5) % (outer.n / 2);
                sd->global[sd->reverse ? sd->N - c5 : c5] = vbase + cr.point_map[oi];
            }
        }
        res->report.t_assemble += wr_time_seconds() - t0;
        wr_poisson_free(&pr);
        wr_cdt_free(&cr);
        wr_free(stretched);
        stretched = NULL;
        wr_free(idx_of);
        wr_free(cpts.v);
        wr_free(csegs.v);
        wr_free(hc);
        wr_free(lc);
        wr_free(outer.v);
        wr_free(holes.v);
        wr_free(lines.v);
        wr_free(hole_n.v);
        wr_free(line_n.v);
        wr_free(line_lab.v);
        wr_free(hseeds);
        continue;
    panel_nomem:
        st = wr_fail(diag, WR_ERR_NOMEM, p, "out of memory meshing panels[%d]", (int)p);
    panel_fail:
        wr_free(idx_of);
        wr_free(cpts.v);
        wr_free(csegs.v);
        wr_free(hc);
        wr_free(lc);
        wr_free(outer.v);
        wr_free(holes.v);
        wr_free(lines.v);
        wr_free(hole_n.v);
        wr_free(line_n.v);
        wr_free(line_lab.v);
        wr_free(hseeds);
        goto fail;
    }

    /* ---- seam table ---- */
    t0 = wr_time_seconds();
    for (i = 0; i < pat->n_seams; ++i) {
        wr__msh_side *a = &sides[2 * i], *b = &sides[2 * i + 1];
        for (j = 0; j <= a->N; ++j)
            if (!wr__msh_ipush(&SP, a->global[j]) || !wr__msh_ipush(&SP, b->global[j]) || !wr__msh_ipush(&SPS, i))
                goto nomem;
    }
    /* ---- the mesh ---- */
    {
        int32_t nv = V.n / 2, nf = F.n / 3;
        double *pos3 = (double *)wr_alloc_array((size_t)(3 * (nv > 0 ? nv : 1)), sizeof(double));
        if (!pos3) goto nomem;
        if (nf < 1) {
            wr_free(pos3);
            st = wr_fail(diag, WR_ERR_GEOMETRY, -1, "pattern produced no triangles");
            goto fail;
        }
        if (!desc.sew) {
            for (j = 0; j < nv; ++j) {
                pos3[3 * j] = V.v[2 * j];
                pos3[3 * j + 1] = V.v[2 * j + 1];
                pos3[3 * j + 2] = 0.0;
            }
            st = wr_mesh_create(&res->mesh, nv, pos3, V.v, nf, F.v, diag);
            wr_free(pos3);
            if (st != WR_OK) goto fail;
        } else {
            /* merge side b into side a (union-find so chains of seams collapse consistently) */
            int32_t *par = (int32_t *)wr_alloc_array((size_t)nv, sizeof(int32_t));
            int32_t *newid = (int32_t *)wr_alloc_array((size_t)nv, sizeof(int32_t));
            int32_t *F2 = (int32_t *)wr_alloc_array((size_t)(3 * nf), sizeof(int32_t));
            double *cr6 = (double *)wr_alloc_array((size_t)(6 * nf), sizeof(double));
            int32_t nn = 0;
            if (!par || !newid || !F2 || !cr6) {
                wr_free(par);
                wr_free(newid);
                wr_free(F2);
                wr_free(cr6);
                wr_free(pos3);
                goto nomem;
            }
            for (j = 0; j < nv; ++j) par[j] = j;
            for (j = 0; j < SP.n / 2; ++j) {
                int32_t x = SP.v[2 * j], y = SP.v[2 * j + 1];
                while (par[x] != x) x = par[x] = par[par[x]];
                while (par[y] != y) y = par[y] = par[par[y]];
                if (x != y) {
                    if (x < y)
                        par[y] = x;
                    else
                        par[x] = y;
                }
            }
            for (j = 0; j < nv; ++j) {
                int32_t x = j;
                while (par[x] != x) x = par[x];
                par[j] = x;
            }
            for (j = 0; j < nv; ++j) newid[j] = (par[j] == j) ? nn++ : -1;
            for (j = 0; j < nv; ++j) {
                int32_t r = newid[par[j]];
                pos3[3 * r] = V.v[2 * par[j]];
                pos3[3 * r + 1] = V.v[2 * par[j] + 1];
                pos3[3 * r + 2] = 0.0;
            }
            for (j = 0; j < 3 * nf; ++j) {
                F2[j] = newid[par[F.v[j]]];
                cr6[2 * j] = V.v[2 * F.v[j]];
                cr6[2 * j + 1] = V.v[2 * F.v[j] + 1];
            }
            st = wr_mesh_create(&res->mesh, nn, pos3, NULL, nf, F2, diag);
            if (st == WR_OK) st = wr_mesh_set_corner_rest(&res->mesh, cr6, diag);
            if (st == WR_OK) {
                /* per-vertex arrays follow the representative */
                for (j = 0; j < nv; ++j)
                    if (newid[j] >= 0) {
                        S.v[newid[j]] = S.v[j];
                        SW.v[newid[j]] = SW.v[j];
                        SF.v[newid[j]] = SF.v[j];
                    }
                S.n = SW.n = SF.n = nn;
                for (j = 0; j < SP.n; ++j) SP.v[j] = newid[par[SP.v[j]]];
                for (j = 0; j < SEG.n; ++j) SEG.v[j] = newid[par[SEG.v[j]]];
            } else {
                char msg[WR_DIAG_MESSAGE_LEN];
                snprintf(msg, sizeof msg, "%s", diag ? diag->message : "");
                st = wr_fail(diag, st, -1, "sewing the seams: %s (a seam pairing with the same traversal "
                                           "direction on both sides makes the sewn mesh non-orientable)", msg);
            }
            wr_free(par);
            wr_free(newid);
            wr_free(F2);
            wr_free(cr6);
            wr_free(pos3);
            if (st != WR_OK) goto fail;
        }
        if ((st = wr_mesh_set_face_panel(&res->mesh, FP.v, diag)) != WR_OK) goto fail;
    }
    res->sizing = S.v;
    res->sizing_warp = SW.v;
    res->sizing_weft = SF.v;
    S.v = SW.v = SF.v = NULL;
    res->seam_pairs = SP.v;
    res->seam_pair_seam = SPS.v;
    res->n_seam_pairs = SPS.n;
    SP.v = SPS.v = NULL;
    res->constraint_segments = SEG.v;
    res->n_constraint_segments = SEG.n / 2;
    SEG.v = NULL;
    /* ---- quality report ---- */
    {
        wr_mesh_quality_stats q;
        wr_mesher_report *rp = &res->report;
        const wr_mesh *M = &res->mesh;
        double sum = 0.0, sumi = 0.0;
        int32_t ni = 0, e;
        char *bnd = (char *)wr_calloc_array((size_t)M->nv, 1);
        if (!bnd) goto nomem;
        for (j = 0; j < M->n_loops; ++j)
            for (k = M->loop_start[j]; k < M->loop_start[j + 1]; ++k) bnd[M->loop_verts[k]] = 1;
        for (j = 0; j < res->n_constraint_segments; ++j) {
            bnd[res->constraint_segments[2 * j]] = 1;
            bnd[res->constraint_segments[2 * j + 1]] = 1;
        }
        wr_mesh_quality(M, 1, &q);
        rp->n_vertices = M->nv;
        rp->n_triangles = M->nf;
        rp->n_seam_pairs = res->n_seam_pairs;
        rp->n_constraint_segments = res->n_constraint_segments;
        rp->min_angle_deg = q.min_angle_deg;
        rp->max_angle_deg = q.max_angle_deg;
        rp->mean_min_angle_deg = q.mean_min_angle_deg;
        /* angles where the mesher actually worked: in each panel's stretched space */
        {
            double amin = 180.0, asum = 0.0;
            int32_t ff;
            for (ff = 0; ff < M->nf; ++ff) {
                const wr_mesher_panel_info *pi = &res->panels[M->face_panel[ff]];
                double uv[6], w[6], fmin_a = 180.0;
                int c8;
                wr_mesh_face_rest(M, ff, uv);
                for (c8 = 0; c8 < 3; ++c8) wr__msh_apply(pi->T, uv + 2 * c8, w + 2 * c8);
                for (c8 = 0; c8 < 3; ++c8) {
                    const double *a = w + 2 * c8, *b = w + 2 * ((c8 + 1) % 3), *c = w + 2 * ((c8 + 2) % 3);
                    double ux = b[0] - a[0], uy = b[1] - a[1], vx = c[0] - a[0], vy = c[1] - a[1];
                    double ang = fabs(atan2(ux * vy - uy * vx, ux * vx + uy * vy)) * 57.29577951308232;
                    if (ang < fmin_a) fmin_a = ang;
                }
                if (fmin_a < amin) amin = fmin_a;
                asum += fmin_a;
            }
            rp->min_angle_metric_deg = amin;
            rp->mean_min_angle_metric_deg = M->nf ? asum / M->nf : 0.0;
        }
        rp->n_inverted = q.n_inverted;
        rp->n_zero_area = q.n_zero_area;
        rp->ratio_min = HUGE_VAL;
        rp->ratio_max = 0.0;
        for (e = 0; e < M->ne; ++e) {
            int32_t a = M->edges[2 * e], b = M->edges[2 * e + 1];
            int32_t f = M->edge_faces[2 * e] >= 0 ? M->edge_faces[2 * e] : M->edge_faces[2 * e + 1];
            const wr_mesher_panel_info *pi = &res->panels[M->face_panel[f]];
            double uv[6], d[2], l, ratio, bin;
            int32_t ka = -1, kb = -1, c6;
            wr_mesh_face_rest(M, f, uv);
            for (c6 = 0; c6 < 3; ++c6) {
                if (M->faces[3 * f + c6] == a) ka = c6;
                if (M->faces[3 * f + c6] == b) kb = c6;
            }
            d[0] = uv[2 * kb] - uv[2 * ka];
            d[1] = uv[2 * kb + 1] - uv[2 * ka + 1];
            wr__msh_apply(pi->T, d, d);
            l = sqrt(d[0] * d[0] + d[1] * d[1]);
            ratio = l / (0.5 * (res->sizing[a] + res->sizing[b]));
            sum += ratio;
            if (!bnd[a] && !bnd[b]) {
                sumi += ratio;
                ++ni;
            }
            if (ratio < rp->ratio_min) rp->ratio_min = ratio;
            if (ratio > rp->ratio_max) rp->ratio_max = ratio;
            bin = floor(ratio / 2.0 * WR_MESHER_HIST_BINS);
            if (bin < 0) bin = 0;
            if (bin > WR_MESHER_HIST_BINS - 1) bin = WR_MESHER_HIST_BINS - 1;
            rp->ratio_hist[(int)bin]++;
        }
        rp->ratio_mean = M->ne ? sum / M->ne : 0.0;
        rp->ratio_interior_mean = ni ? sumi / ni : NAN;
        wr_free(bnd);
    }
    res->report.t_assemble += wr_time_seconds() - t0;
    res->report.t_total = wr_time_seconds() - t_start;
    for (k = 0; k < n_sides; ++k) {
        wr_free(sides[k].fixed);
        wr_free(sides[k].global);
    }
    wr_free(sides);
    for (p = 0; p < np; ++p) {
        wr_free(work[p].loop);
        wr_free(work[p].brk);
        wr_free(work[p].side_of_edge);
        wr_free(work[p].forced);
    }
    wr_free(work);
    wr_free(V.v);
    wr_free(F.v);
    wr_free(FP.v);
    return WR_OK;

nomem:
    st = wr_fail(diag, WR_ERR_NOMEM, -1, "out of memory");
fail:
    wr_poisson_free(&pr);
    wr_cdt_free(&cr);
    wr_free(stretched);
    if (sides)
        for (k = 0; k < 2 * pat->n_seams; ++k) {
            wr_free(sides[k].fixed);
            wr_free(sides[k].global);
        }
    wr_free(sides);
    if (work)
        for (p = 0; p < np; ++p) {
            wr_free(work[p].loop);
            wr_free(work[p].brk);
            wr_free(work[p].side_of_edge);
            wr_free(work[p].forced);
        }
    wr_free(work);
    wr_free(V.v);
    wr_free(S.v);
    wr_free(SW.v);
    wr_free(SF.v);
    wr_free(F.v);
    wr_free(FP.v);
    wr_free(SEG.v);
    wr_free(SP.v);
    wr_free(SPS.v);
    wr_mesher_free(res);
    /* panel names are user text: keep the message one line */
    if (diag) {
        char *c;
        for (c = diag->message; *c; ++c)
            if (*c == '\n' || *c == '\r') *c = ' ';
    }
    return st;
}

#ifdef __cplusplus
}
#endif
#endif /* WRINKLE_MESHER_IMPLEMENTATION_DONE */
#endif /* WRINKLE_IMPLEMENTATION */
