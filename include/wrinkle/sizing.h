/* wrinkle/sizing.h — the Style3D sizing map of a garment pattern: per-panel metric, technique sources,
 * collision regions and uniform overrides, built from a pattern by one call, evaluable at a point and
 * drawable on a grid without meshing.
 * wrinkle v0.1.0 — MIT licence (see LICENSE). Needs only libc and libm (and core.h, resolution.h,
 * transition.h, triangulate.h).
 *
 * Implements Sec. 4.1.2 and 4.2 of "Physics-inspired Estimation of Optimal Cloth Mesh Resolution"
 * (Style3D, SIGGRAPH 2025): the target edge length at a point of a panel is
 *     r_v(p) = min(r_f, min_i r_i(x_i(p)), r_region(p)),     r_i(x) = r_i (1 + (x/L_w)^m)
 * (transition.h holds the formulas: L_w, m, r + x^m, down-filling, the technique resolutions), with
 * r_f from the fabric (Eq. 4 per direction, resolution.h) and one source per garment-making technique.
 * This header holds the pattern description (panels, fabrics, techniques: what docs/pattern-format.md
 * reads into), its validation, the source field of one panel (wr_sizing) and the map of the whole
 * pattern (wr_sizing_map). mesher.h meshes what this map says.
 *
 * API (create/free pairs: wr_sizing_map_build → wr_sizing_map_free, wr_sizing_create → wr_sizing_free)
 *   wr_sizing_map_build(pat, desc, &map, diag)       validate the pattern, build every panel's map
 *   wr_sizing_map_free(&map)                         free and zero (safe on a zeroed map)
 *   wr_sizing_map_eval(&map, panel, x, y)            target edge length [m] (fine direction)
 *   wr_sizing_map_eval_metric(&map, panel, x, y)     2×2 metric M: an edge e is on target when eᵀMe = 1
 *   wr_sizing_map_raster(&map, panel, box, nx, ny, out, diag)   the map on a grid (NaN outside the panel)
 *   wr_sizing_map_vertex_estimate(&map, panel, radius_factor)   vertices a mesh of the panel needs, low side
 *   wr_sizing_panel_eval(pn, x, y) / _eval_stretched(pn, X, Y)   one panel, pattern / stretched coordinates
 *   wr_sizing_panel_to_stretched(pn, p, q) / _to_pattern(pn, q, p)   the panel's affine metric map T, T⁻¹
 *   wr_sizing_fabric_resolution(fabric, model, &r_warp, &r_weft, diag)   Eq. 4 per direction
 *   wr_pattern_validate(pat, diag)                   every check that needs no sizing
 *   wr_pattern_check_line(pat, panel, xy, n, what, idx, allow_end_on, &on0, &on1, diag)   a technique line
 *   wr_pattern_locate_on_outer(pat, panel, pt, &edge, &t, what, idx, diag)   a seam end on the outer loop
 *   wr_pattern_panel_name(pat, panel)                "" when unnamed
 *   wr_sizing_create(r_f, desc, &s, diag) / wr_sizing_free(s)     one panel's source field
 *   wr_sizing_add_point / _add_point_directional / _add_polyline   sources with a transition
 *   wr_sizing_build(s, diag)                         grid index (optional; eval works without)
 *   wr_sizing_eval(s, x, y) / _eval_brute / _eval_gradient / _eval_metric / _set_region_fn
 *
 * EXAMPLE
 *     double sq[8] = {0,0, 0.25,0, 0.25,0.25, 0,0.25}, line[4] = {0.03,0.125, 0.22,0.125}, box[4], img[16];
 *     wr_pattern_panel pn; wr_pattern_shirring sh; wr_pattern pat; wr_sizing_map map; wr_diag d;
 *     memset(&pn, 0, sizeof pn); memset(&sh, 0, sizeof sh); memset(&pat, 0, sizeof pat);
 *     pn.outer.xy = sq; pn.outer.n = 4; pn.fabric.B = 2.6e-6; pn.fabric.E = 2.0e6;   // Table 1 Green
 *     sh.panel = 0; sh.xy = line; sh.n = 2; sh.E_sh = 2.0e6; sh.rho = 0.5;
 *     pat.panels = &pn; pat.n_panels = 1; pat.shirrings = &sh; pat.n_shirrings = 1;
 *     if (wr_sizing_map_build(&pat, NULL, &map, &d) != WR_OK) { puts(d.message); return 1; }
 *     printf("r_f %.2f mm, on the line %.2f mm\n", 1e3 * map.panels[0].r0,
 *            1e3 * wr_sizing_map_eval(&map, 0, 0.1, 0.125));
 *     box[0] = 0; box[1] = 0; box[2] = 0.25; box[3] = 0.25;      // x0 y0 x1 y1 [m]
 *     if (wr_sizing_map_raster(&map, 0, box, 4, 4, img, &d) != WR_OK) { puts(d.message); return 1; }
 *     printf("cell (1, 1): %.2f mm\n", 1e3 * img[4 * 1 + 1]);   // 4×4 cell centres, row-major
 *     wr_sizing_map_free(&map);
 *
 * ON UNITS
 *   Metres, N·m (B), N/m² (E, E_sh), radians (grain_angle), degrees only where the paper uses them
 *   (fold angle Δθ). The pattern-file reader (drivers/lib/pattern.h) converts millimetres.
 *
 * ON THE PANEL METRIC (Sec. 4.1.2, Fig. 6)
 *   r_warp, r_weft from Eq. 4 per direction (clamped onto the model's branch so a pipeline always has a
 *   size; a fabric's resolution override wins). The constant metric M = R diag(1/r_warp², 1/r_weft²) Rᵀ
 *   (R the grain rotation) is turned isotropic by the affine map T = r0 diag(1/r_warp, 1/r_weft) Rᵀ,
 *   r0 = min(r_warp, r_weft): |T e| = r0 for an edge on target. The map itself is evaluated in
 *   pattern space and gives the fine-direction length h ≤ r0; in stretched space (T p) the target is
 *   h in every direction, so eval_metric returns M = Tᵀ T / h². Technique sources refine both
 *   directions by h / r0 (keeping the fabric's aspect) — an approximation of min(r_dir, r_source)
 *   that keeps the map affine-constant per panel; transition distances x are pattern-space.
 *
 * ON THE SOURCES (one builder per technique; each refers to a panel by index)
 *   L_w of a source: the technique's explicit transition_length if > 0, else the compression form of
 *   Sec. 4.2.1 with unit prefactor, L_w = λ_src^{3/2} (δ / h²)^{1/4}, δ = 1 − ρ (ρ the technique's
 *   resolution factor, floored at WR_SIZING_MIN_STRAIN), h = (12 (1 − ν²) B/E)^{1/3} the Kirchhoff–Love
 *   thickness of the fabric (ν = 0.3, fine direction), and λ_src the source's WAVELENGTH: Sec. 4.1.1's
 *   r = sqrt(λ²/16 + A²) (Fig. 4) with A = (√2/π) λ √δ (Sec. 3.1) inverted, λ_src = r_src / c(δ),
 *   c = sqrt(1/16 + 2δ/π²) (λ = 2.47 r_src at δ = 0.5). The paper's m = log r / log L_w then carries
 *   the r/λ factor ("incorporating the scaling factor between r and λ into m", Sec. 4.2.1).
 *   When the paper's m is undefined (r or L_w ≤ 1 mm) transition.h's scale-free fallback is used.
 *   shirring  (4.2.2): r_sh = ρ_sh^n r(B/(E+E_sh)) · r_f / r(B/E) (the last factor is 1 unless the
 *             panel overrides r_f); source = the polyline (ends may touch the outer loop).
 *   quilt     (4.2.5): stitch lines as shirring lines (n = 1); pressure p: m' = 2^p m, L_w' = L_w^{2^-p}.
 *   collision (4.2.6): polygon or disk with compression δ ∈ (0, 1): inside r = (1 − δ) r_f (a region);
 *             outside, a transition from its boundary (a disk as a 64-gon, chord error < 0.12 % of R).
 *   seam      (4.2.4): when the two sides' lengths differ, ρ_s = l_s / l_l is the source factor of the
 *             LONGER side (r = ρ_s r_f, source = that side's range of the outer loop).
 *   fold      (4.2.3): at both endpoints and at high-curvature vertices (radius below
 *             curvature_radius, local maxima only): r_fd = (Δθ/360) r_ng, r_ng = the map there before
 *             fold points are added, with a DIRECTIONAL transition (forward half-space): endpoints
 *             along the fold pointing into it (the tip of a fold compresses the fabric along the fold),
 *             curvature points along the normal towards the centre of curvature. The fold line
 *             itself carries the base resolution (mesher.h makes it a constraint).
 *   uniform   desc.uniform_resolution > 0: every panel at that size, no sources (the "uniform fine"
 *             comparison); the pattern is still validated and seam ends located.
 *
 * ON THE SOURCE FIELD (wr_sizing, one per panel)
 *   r_v(p) = min(r_f, min_i r_i(dist(p, source_i))); a source whose r_i ≥ r_f can never win and is
 *   dropped. wr_sizing_build stores each segment in the cells of a uniform grid its bounding box
 *   overlaps; a query visits rings of cells and stops when a lower bound of every unvisited term
 *   exceeds the running minimum (terms grow with distance). The grid and the brute-force scan run the
 *   same routine, so they agree bit for bit. Directional points act only on (p − s)·dir ≥ 0. NaN
 *   coordinates give NaN. eval is const and thread-safe; add and build are not. The region callback
 *   (set_region_fn) gives wr_sizing_eval_metric a per-region warp/weft size and grain angle:
 *   M = R diag(1/min(r_warp, r_v)², 1/min(r_weft, r_v)²) Rᵀ. Speed: docs/notes-sizing.md.
 *
 * ON ERRORS (status + message naming the item; diag->item = its index)
 *   WR_ERR_INVALID_ARG  NULL arguments, no panels, technique on a missing panel ("shirrings[2]: panel
 *                       5 does not exist"), ρ outside (0, 1], negative pressure / E_sh, fold angle
 *                       outside (0, 360], non-positive offset / radius / transition length.
 *   WR_ERR_DOMAIN       non-positive or non-finite stiffness ("panels[1] 'back': B = -1").
 *   WR_ERR_GEOMETRY     loops with < 3 points or zero area, non-finite coordinates, seam ends not on
 *                       the outer loop, fold/shirring line leaving its panel.
 *   On failure the map is zeroed.
 *
 * MEMORY: wr_sizing_map_build fills a caller-owned wr_sizing_map (collision polygons are copied: the
 *   pattern need not outlive it); wr_sizing_map_free releases it. wr_sizing_create allocates a field,
 *   wr_sizing_free releases it (NULL is fine). THREADS: no global state; evaluation is const.
 */
#ifndef WRINKLE_SIZING_H
#define WRINKLE_SIZING_H

#include "core.h"
#include "resolution.h"
#include "transition.h"
#include "triangulate.h" /* wr_orient2d: exact crossing tests of technique lines */

#ifdef __cplusplus
extern "C" {
#endif

#define WR_SIZING_DEFAULT_FOLD_ANGLE 180.0       /* deg: a flat fold (hem) */
#define WR_SIZING_DEFAULT_CURVATURE_RADIUS 20e-3 /* m: fold vertices curving tighter are "high curvature" */
#define WR_SIZING_KL_POISSON 0.3      /* ν for the Kirchhoff–Love thickness h = (12(1-ν²) B/E)^{1/3} */
#define WR_SIZING_MIN_STRAIN 1e-3     /* floor of δ in the compression law (δ = 0 gives L_w = 0) */
#define WR_SIZING_FALLBACK_THICKNESS_RATIO 0.1 /* h / r when a panel has no stiffness (override only) */
/* Tolerance for "lies on the boundary" (seam ends, line ends): absolute [m] plus relative to the
 * panel's bounding-box size. 1 µm is far below any cloth feature and above JSON mm round-off. */
#define WR_SIZING_ON_BOUNDARY_ABS 1e-6
#define WR_SIZING_ON_BOUNDARY_REL 1e-9
/* Sides of the regular polygon standing for a collision disk's boundary (chord error < 0.12 % of R). */
#define WR_SIZING_DISK_SIDES 64

/* ---- the pattern: panels, fabrics, techniques ------------------------------------------------ */
/* A polyline or loop: n points xy[2n] [m] (row-major). */
typedef struct wr_pattern_curve {
    const double *xy;
    int32_t n;
} wr_pattern_curve;

/* Fabric of a panel. Isotropic: B [N·m], E [N/m²]. anisotropic != 0: (B_warp, E_warp), (B_weft, E_weft)
 * and the warp direction grain_angle [rad] in the pattern frame. Overrides (> 0) replace Eq. 4:
 * resolution (isotropic), resolution_warp / resolution_weft (anisotropic) [m]; the stiffness is then
 * still used for the transition thickness when given, else h = r · WR_SIZING_FALLBACK_THICKNESS_RATIO. */
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

/* Sec. 4.2.2. rho in (0, 1]; n_exp 0 → 1; E_sh >= 0; transition_length 0 → compression law.
 * stitch_length [m] >= 0: the gathering thread's stitch length (garment.h ON GATHERING; 0: a stitch
 * every few mesh edges); not used by the sizing; xy must then carry a vertex at every stitch
 * (wr_garment_line_split; the pattern reader splits the line it reads). */
typedef struct wr_pattern_shirring {
    int32_t panel;
    const double *xy;
    int32_t n;
    double E_sh, rho, n_exp, transition_length;
    double stitch_length;
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

/* Sec. 4.2.5: a quilted (down-filled) panel's stitch lines. rho in (0, 1], E_sh >= 0, pressure >= 0;
 * stitch_length [m] >= 0 of every line as for a shirring. */
typedef struct wr_pattern_quilt {
    int32_t panel;
    const wr_pattern_curve *lines;
    int32_t n_lines;
    double rho, E_sh, pressure, transition_length;
    double stitch_length;
} wr_pattern_quilt;

/* Sec. 4.2.6: polygon (n >= 3) or, when n == 0, the disk (center, radius). compression δ in (0, 1). */
typedef struct wr_pattern_collision {
    int32_t panel;
    const double *xy;
    int32_t n;
    double center[2], radius;
    double compression, transition_length;
} wr_pattern_collision;

/* A garment pattern: a view of caller-owned arrays (nothing is copied or freed by the sizing map or the mesher). */
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

/* ---- one panel's source field ---------------------------------------------------------------- */
typedef struct wr_sizing wr_sizing;

/* Options for wr_sizing_build. Zero means default:
 *   cell_size   grid cell edge [m]; 0 → automatic (about one segment per cell)
 *   max_cells   cap on nx·ny and on stored cell entries; 0 → 1 << 22 */
typedef struct wr_sizing_desc {
    double cell_size;
    int32_t max_cells;
} wr_sizing_desc;

/* Region callback for the metric hook: return nonzero and fill the three outputs when (x, y) lies in
 * an anisotropic region (r_warp, r_weft [m] > 0, grain angle [rad] of the warp direction). */
typedef int (*wr_sizing_region_fn)(void *user, double x, double y, double *r_warp, double *r_weft,
                                   double *grain_angle);

/* r_f [m] finite and > 0: the fabric resolution, the field's upper bound. desc may be NULL. */
WRDEF wr_status wr_sizing_create(double r_f, const wr_sizing_desc *desc, wr_sizing **out, wr_diag *diag);
WRDEF void wr_sizing_free(wr_sizing *s);
WRDEF wr_status wr_sizing_add_point(wr_sizing *s, double x, double y, const wr_transition *t, wr_diag *diag);
/* Only points p with (p - (x, y))·(dir_x, dir_y) ≥ 0 see this source; dir must be nonzero. */
WRDEF wr_status wr_sizing_add_point_directional(wr_sizing *s, double x, double y, double dir_x, double dir_y,
                                                const wr_transition *t, wr_diag *diag);
/* xy[2n] = x0 y0 x1 y1 ...; n ≥ 1 (n = 1 is a point). diag->item names a bad coordinate's point
 * (WR_ERR_INVALID_ARG), or a segment whose squared length overflows a double (WR_ERR_DOMAIN). */
WRDEF wr_status wr_sizing_add_polyline(wr_sizing *s, const double *xy, int32_t n, const wr_transition *t,
                                       wr_diag *diag);
/* Build (or rebuild) the grid index. Adding sources afterwards invalidates it until the next build;
 * eval then scans every source. Errors leave the field unbuilt but usable (eval scans every source):
 * more active segments than desc.max_cells (WR_ERR_BUDGET: each needs one cell entry), a source
 * extent that overflows a double (WR_ERR_DOMAIN), WR_ERR_NOMEM. */
WRDEF wr_status wr_sizing_build(wr_sizing *s, wr_diag *diag);
WRDEF double wr_sizing_eval(const wr_sizing *s, double x, double y);
WRDEF double wr_sizing_eval_brute(const wr_sizing *s, double x, double y);
/* Gradient of the active term (zero where r_f is active or on a source itself, where it is undefined). */
WRDEF void wr_sizing_eval_gradient(const wr_sizing *s, double x, double y, double *r, double grad[2]);
WRDEF void wr_sizing_set_region_fn(wr_sizing *s, wr_sizing_region_fn fn, void *user);
WRDEF wr_mat2 wr_sizing_eval_metric(const wr_sizing *s, double x, double y);
/* Counts: stored segments (points count as one) and whether the index is current. */
WRDEF int32_t wr_sizing_segment_count(const wr_sizing *s);
WRDEF int wr_sizing_is_built(const wr_sizing *s);

/* ---- the sizing map of a pattern --------------------------------------------------------------- */
/* A collision area (Sec. 4.2.6): polygon xy[2n] (n >= 3, owned copy) or the disk (center, radius)
 * when n == 0; r [m] is the resolution inside. */
typedef struct wr_sizing_region {
    double *xy;
    int32_t n;
    double center[2], radius;
    double r;
} wr_sizing_region;

/* One panel's map (read-only for the caller; owned by the wr_sizing_map). */
typedef struct wr_sizing_panel {
    double r_warp, r_weft;  /* base resolution per direction [m] (equal for isotropic panels) */
    double r0;              /* min(r_warp, r_weft): the cap of the map, the stretched-space size */
    double grain_angle;     /* warp direction [rad] (0 for isotropic panels) */
    double T[4], Tinv[4];   /* row-major pattern → stretched map and its inverse */
    double area;            /* outer minus holes [m²] */
    double perimeter;       /* outer plus holes [m] */
    double thickness;       /* h of the compression law [m] */
    double uniform;         /* > 0: constant sizing (desc.uniform_resolution), no sources */
    int32_t n_sources;      /* technique sources of this panel */
    wr_sizing *field;       /* the technique sources */
    wr_sizing_region *regions;
    int32_t n_regions;
    double *outline;        /* copy of the outer loop then the holes, for the raster's inside test */
    int32_t n_outline;      /* points of the outer loop */
    int32_t *hole_start;    /* n_hole_loops + 1 offsets (in points, after the outer loop) */
    int32_t n_hole_loops;
} wr_sizing_panel;

typedef struct wr_sizing_map {
    wr_sizing_panel *panels;
    int32_t n_panels;
} wr_sizing_map;

/* Options; zero means default:
 *   model               Eq. 4 constants; c1 == c2 == 0 → wr_resolution_model_paper()
 *   uniform_resolution  > 0: ignore fabrics and techniques, every panel at this size [m] */
typedef struct wr_sizing_map_desc {
    wr_resolution_model model;
    double uniform_resolution;
} wr_sizing_map_desc;

/* Validates the pattern (wr_pattern_validate plus the checks of technique lines and seam ends) and
 * builds every panel's map. desc may be NULL. On failure *map is zeroed. */
WRDEF wr_status wr_sizing_map_build(const wr_pattern *pat, const wr_sizing_map_desc *desc, wr_sizing_map *map,
                                    wr_diag *diag);
WRDEF void wr_sizing_map_free(wr_sizing_map *map);
/* Target edge length [m] (fine direction) of panel p at pattern point (x, y); NaN for a bad panel. */
WRDEF double wr_sizing_map_eval(const wr_sizing_map *map, int32_t panel, double x, double y);
/* M = Tᵀ T / h², h the stretched-space size at (x, y): an edge e [m] is on target when eᵀ M e = 1.
 * Eigenvalues 1/(h r_warp/r0)² along the warp, 1/(h r_weft/r0)² across. NaNs for a bad panel. */
WRDEF wr_mat2 wr_sizing_map_eval_metric(const wr_sizing_map *map, int32_t panel, double x, double y);
/* The map of panel p at the centres of an nx × ny grid over box = {x0, y0, x1, y1} [m]:
 * out[j nx + i] at (x0 + (i + ½)(x1 − x0)/nx, y0 + (j + ½)(y1 − y0)/ny), NaN outside the panel (outside
 * its outer loop or inside a hole). Ready for an image (row j = 0 at y0). */
WRDEF wr_status wr_sizing_map_raster(const wr_sizing_map *map, int32_t panel, const double box[4], int32_t nx,
                                     int32_t ny, double *out, wr_diag *diag);
/* Vertices a mesh of panel p needs at least, from its area A and perimeter P at the map's cap (the
 * map is never coarser than r_warp × r_weft): A / (r_warp r_weft s²) + P / (2 max(r_warp, r_weft)),
 * s = spacing / target edge length (0 → 1; the mesher passes radius_factor over poisson.h's
 * calibrated default). O(1): refuse a budget with it before any work that grows with the output. */
WRDEF double wr_sizing_map_vertex_estimate(const wr_sizing_map *map, int32_t panel, double spacing);
/* One panel: target edge length at pattern point (x, y), and at stretched point (X, Y) = T (x, y). */
WRDEF double wr_sizing_panel_eval(const wr_sizing_panel *pn, double x, double y);
WRDEF double wr_sizing_panel_eval_stretched(const wr_sizing_panel *pn, double X, double Y);
WRDEF void wr_sizing_panel_to_stretched(const wr_sizing_panel *pn, const double p[2], double q[2]);
WRDEF void wr_sizing_panel_to_pattern(const wr_sizing_panel *pn, const double q[2], double p[2]);

/* Eq. 4 per direction for one fabric (overrides honoured, clamped onto the model's branch).
 * model NULL → paper model. */
WRDEF wr_status wr_sizing_fabric_resolution(const wr_pattern_fabric *fab, const wr_resolution_model *model,
                                            double *r_warp, double *r_weft, wr_diag *diag);

/* ---- pattern checks ----------------------------------------------------------------------------- */
/* Everything that needs no sizing: counts and arrays, loops (>= 3 points, finite, nonzero area),
 * technique parameters and panel references. */
WRDEF wr_status wr_pattern_validate(const wr_pattern *pat, wr_diag *diag);
/* A technique polyline of panel p: n >= 2, finite, every vertex inside the panel (outer, not in
 * holes), no segment crossing a panel loop. With allow_end_on, ends within the boundary tolerance of
 * the outer loop are allowed and flagged in *on_start / *on_end (either may be NULL). Messages name
 * "what[idx]". */
WRDEF wr_status wr_pattern_check_line(const wr_pattern *pat, int32_t p, const double *xy, int32_t n,
                                      const char *what, int32_t idx, int allow_end_on, int *on_start, int *on_end,
                                      wr_diag *diag);
/* A point on panel p's outer loop: the closest edge and its parameter t ∈ [0, 1), snapped to the
 * edge's start vertex (t = 0) within the boundary tolerance. WR_ERR_GEOMETRY when farther away;
 * the message starts with `what` and diag->item = idx. */
WRDEF wr_status wr_pattern_locate_on_outer(const wr_pattern *pat, int32_t p, const double pt[2], int32_t *edge,
                                           double *t, const char *what, int32_t idx, wr_diag *diag);
WRDEF const char *wr_pattern_panel_name(const wr_pattern *pat, int32_t p);

#ifdef __cplusplus
}
#endif
#endif /* WRINKLE_SIZING_H */

/* ============================================================================================ */
#ifdef WRINKLE_IMPLEMENTATION
#ifndef WRINKLE_SIZING_IMPLEMENTATION_DONE
#define WRINKLE_SIZING_IMPLEMENTATION_DONE

#include <math.h>
#include <stdio.h>
#include <string.h>

#ifdef __cplusplus
extern "C" {
#endif

/* Relative safety margin of the grid's early-out bounds: a bound must exceed the running minimum by
 * this much before cells are skipped, so rounding in pow() can never drop a winning term. */
#define WR__SZ_BOUND_MARGIN 1e-12
/* A source's reach (distance where its term reaches r_f) is widened by this relative margin [1] so
 * that the pow() round-off of the reach formula never drops a term the scan would keep. */
#define WR__SZ_REACH_MARGIN 1e-9
/* Up to this many source groups the ring lower bound is evaluated per group (exact); above it a
 * conservative O(1) bound from the extreme parameters is used. */
#define WR__SZ_EXACT_LB_GROUPS 32
#define WR__SZ_DEFAULT_MAX_CELLS (1 << 22)
/* Budget (transition evaluations) for the per-ring lower-bound table built by wr_sizing_build. */
#define WR__SZ_LB_TABLE_WORK (1 << 22)

static int wr__sz_pos(double v) { return isfinite(v) && v > 0.0; }

/* ---- sizing map ------------------------------------------------------------------------- */

typedef struct wr__sz_group {
    wr_transition t;
    double reach; /* distance beyond which this group's terms are >= r_f (with margin) */
} wr__sz_group;

typedef struct wr__sz_seg {
    double ax, ay, bx, by;
    double dx, dy;        /* direction of a directional point source; (0,0) otherwise */
    double inv_ee, inv_len; /* 1/|b-a|² and 1/|b-a| (0 for a point): no divisions per query */
    int32_t group;
} wr__sz_seg;

struct wr_sizing {
    double r_f;
    wr_sizing_desc desc;
    wr__sz_group *groups;
    int32_t n_groups, cap_groups;
    wr__sz_seg *segs;
    int32_t n_segs, cap_segs;
    /* grid index over the segments of active groups (r < r_f) */
    int built;
    double x0, y0, h;
    int32_t nx, ny;
    int32_t *cell_start; /* nx*ny + 1 */
    int32_t *cell_items; /* segment indices */
    int32_t n_active_groups;
    double lb_r_min, lb_L_max, lb_m_min, lb_m_max, reach_max;
    double *lb_table; /* lb_table[j] = min over active sources of r_g(j h), j < n_lb: ring bounds */
    int32_t n_lb;
    wr_sizing_region_fn region_fn;
    void *region_user;
};

WRDEF wr_status wr_sizing_create(double r_f, const wr_sizing_desc *desc, wr_sizing **out, wr_diag *diag) {
    wr_sizing *s;
    if (!out) return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "sizing: NULL output");
    *out = NULL;
    if (!wr__sz_pos(r_f))
        return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "sizing: fabric resolution r_f=%g m must be finite and > 0", r_f);
    if (desc && (!(desc->cell_size >= 0.0) || !isfinite(desc->cell_size) || desc->max_cells < 0))
        return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "sizing: bad desc (cell_size=%g, max_cells=%d)", desc->cell_size,
                       (int)desc->max_cells);
    s = (wr_sizing *)wr_calloc_array(1, sizeof(wr_sizing));
    if (!s) return wr_fail(diag, WR_ERR_NOMEM, -1, "sizing: out of memory");
    s->r_f = r_f;
    if (desc) s->desc = *desc;
    if (s->desc.max_cells == 0) s->desc.max_cells = WR__SZ_DEFAULT_MAX_CELLS;
    *out = s;
    return WR_OK;
}

static void wr__sz_drop_index(wr_sizing *s) {
    wr_free(s->cell_start);
    wr_free(s->cell_items);
    wr_free(s->lb_table);
    s->cell_start = s->cell_items = NULL;
    s->lb_table = NULL;
    s->n_lb = 0;
    s->built = 0;
}

WRDEF void wr_sizing_free(wr_sizing *s) {
    if (!s) return;
    wr__sz_drop_index(s);
    wr_free(s->groups);
    wr_free(s->segs);
    wr_free(s);
}

static wr_status wr__sz_check_transition(const wr_transition *t, wr_diag *diag) {
    if (!t) return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "sizing: NULL transition");
    if (!wr__sz_pos(t->r) || !wr__sz_pos(t->L_w) || !wr__sz_pos(t->m))
        return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "sizing: invalid transition (r=%g m, L_w=%g m, m=%g)", t->r,
                       t->L_w, t->m);
    return WR_OK;
}

static wr_status wr__sz_add_group(wr_sizing *s, const wr_transition *t, int32_t extra_segs, wr_diag *diag) {
    if (s->n_groups == s->cap_groups) {
        int32_t nc = s->cap_groups ? 2 * s->cap_groups : 8;
        wr__sz_group *g = (wr__sz_group *)wr_realloc_array(s->groups, (size_t)nc, sizeof(wr__sz_group));
        if (!g || nc < 0) return wr_fail(diag, WR_ERR_NOMEM, -1, "sizing: out of memory (groups)");
        s->groups = g;
        s->cap_groups = nc;
    }
    if (extra_segs > INT32_MAX - s->n_segs) return wr_fail(diag, WR_ERR_OVERFLOW, -1, "sizing: too many segments");
    if (s->n_segs + extra_segs > s->cap_segs) {
        int32_t nc = s->cap_segs ? s->cap_segs : 16;
        wr__sz_seg *g;
        while (nc < s->n_segs + extra_segs) nc = nc > INT32_MAX / 2 ? INT32_MAX : 2 * nc;
        g = (wr__sz_seg *)wr_realloc_array(s->segs, (size_t)nc, sizeof(wr__sz_seg));
        if (!g) return wr_fail(diag, WR_ERR_NOMEM, -1, "sizing: out of memory (segments)");
        s->segs = g;
        s->cap_segs = nc;
    }
    s->groups[s->n_groups].t = *t;
    /* r (1 + (x/L)^m) >= r_f  ⇔  x >= L ((r_f - r)/r)^{1/m}; widened by the margin. */
    if (t->r >= s->r_f)
        s->groups[s->n_groups].reach = -1.0; /* never active */
    else
        s->groups[s->n_groups].reach =
            t->L_w * pow((s->r_f - t->r) / t->r, 1.0 / t->m) * (1.0 + WR__SZ_REACH_MARGIN) + 1e-300;
    s->n_groups++;
    wr__sz_drop_index(s);
    return WR_OK;
}

static void wr__sz_push_seg(wr_sizing *s, double ax, double ay, double bx, double by, double dx, double dy) {
    wr__sz_seg *g = &s->segs[s->n_segs++];
    g->ax = ax;
    g->ay = ay;
    g->bx = bx;
    g->by = by;
    g->dx = dx;
    g->dy = dy;
    {
        double ee = (bx - ax) * (bx - ax) + (by - ay) * (by - ay);
        g->inv_ee = ee > 0.0 ? 1.0 / ee : 0.0;
        g->inv_len = ee > 0.0 ? 1.0 / sqrt(ee) : 0.0;
    }
    g->group = s->n_groups - 1;
}

WRDEF wr_status wr_sizing_add_point(wr_sizing *s, double x, double y, const wr_transition *t, wr_diag *diag) {
    wr_status st;
    if (!s) return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "sizing: NULL object");
    if (!isfinite(x) || !isfinite(y))
        return wr_fail(diag, WR_ERR_INVALID_ARG, 0, "sizing: point (%g, %g) not finite", x, y);
    st = wr__sz_check_transition(t, diag);
    if (st != WR_OK) return st;
    st = wr__sz_add_group(s, t, 1, diag);
    if (st != WR_OK) return st;
    wr__sz_push_seg(s, x, y, x, y, 0.0, 0.0);
    return WR_OK;
}

WRDEF wr_status wr_sizing_add_point_directional(wr_sizing *s, double x, double y, double dir_x, double dir_y,
                                                const wr_transition *t, wr_diag *diag) {
    wr_status st;
    if (!s) return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "sizing: NULL object");
    if (!isfinite(x) || !isfinite(y))
        return wr_fail(diag, WR_ERR_INVALID_ARG, 0, "sizing: point (%g, %g) not finite", x, y);
    if (!isfinite(dir_x) || !isfinite(dir_y) || (dir_x == 0.0 && dir_y == 0.0))
        return wr_fail(diag, WR_ERR_INVALID_ARG, 0, "sizing: direction (%g, %g) must be finite and nonzero", dir_x,
                       dir_y);
    st = wr__sz_check_transition(t, diag);
    if (st != WR_OK) return st;
    st = wr__sz_add_group(s, t, 1, diag);
    if (st != WR_OK) return st;
    wr__sz_push_seg(s, x, y, x, y, dir_x, dir_y);
    return WR_OK;
}

WRDEF wr_status wr_sizing_add_polyline(wr_sizing *s, const double *xy, int32_t n, const wr_transition *t,
                                       wr_diag *diag) {
    wr_status st;
    int32_t i;
    if (!s || !xy) return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "sizing: NULL argument");
    if (n < 1) return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "sizing: polyline needs >= 1 point, got %d", (int)n);
    for (i = 0; i < n; ++i)
        if (!isfinite(xy[2 * i]) || !isfinite(xy[2 * i + 1]))
            return wr_fail(diag, WR_ERR_INVALID_ARG, i, "sizing: polyline point %d (%g, %g) not finite", (int)i,
                           xy[2 * i], xy[2 * i + 1]);
    /* |b - a|² must be finite or the projection in wr__sz_seg_dist degenerates (inv_ee = 0). */
    for (i = 0; i + 1 < n; ++i) {
        double ex = xy[2 * i + 2] - xy[2 * i], ey = xy[2 * i + 3] - xy[2 * i + 1];
        if (!isfinite(ex * ex + ey * ey))
            return wr_fail(diag, WR_ERR_DOMAIN, i, "sizing: polyline segment %d is too long (%g, %g) m to measure",
                           (int)i, ex, ey);
    }
    st = wr__sz_check_transition(t, diag);
    if (st != WR_OK) return st;
    st = wr__sz_add_group(s, t, n > 1 ? n - 1 : 1, diag);
    if (st != WR_OK) return st;
    if (n == 1)
        wr__sz_push_seg(s, xy[0], xy[1], xy[0], xy[1], 0.0, 0.0);
    else
        for (i = 0; i + 1 < n; ++i) wr__sz_push_seg(s, xy[2 * i], xy[2 * i + 1], xy[2 * i + 2], xy[2 * i + 3], 0.0, 0.0);
    return WR_OK;
}

/* Distance from p to segment g, and the closest point. */
static double wr__sz_seg_dist(const wr__sz_seg *g, double px, double py, double *cx, double *cy) {
    double ex = g->bx - g->ax, ey = g->by - g->ay;
    double tt = 0.0, qx, qy;
    if (g->inv_ee > 0.0) {
        tt = ((px - g->ax) * ex + (py - g->ay) * ey) * g->inv_ee;
        tt = tt < 0.0 ? 0.0 : (tt > 1.0 ? 1.0 : tt);
    }
    qx = g->ax + tt * ex;
    qy = g->ay + tt * ey;
    if (cx) *cx = qx;
    if (cy) *cy = qy;
    /* Interior projection: the cross-product form is exact (0) for points on the segment's line,
     * which matters because x^m with m < 1 amplifies a 1e-17 distance error to ~1e-5 relative. */
    if (tt > 0.0 && tt < 1.0) return fabs(ex * (py - g->ay) - ey * (px - g->ax)) * g->inv_len;
    /* sqrt rather than hypot: coordinates are metres, far from overflow, and hypot is ~5x slower */
    return sqrt((px - qx) * (px - qx) + (py - qy) * (py - qy));
}

/* Scan segments (items[0..n) in increasing index order, or 0..n-1 when items is NULL) and lower *best
 * with their terms. Segments of one source are contiguous, so the scan keeps the smallest distance
 * per run of one source and evaluates the transition (the pow) once per run: terms increase with
 * distance, so r_g(min d) = min r_g(d). Both the brute-force and the grid path use exactly this
 * routine, so they agree bit for bit. Directional points skip p behind them; distances beyond a
 * source's reach cannot beat r_f and are dropped. */
static void wr__sz_flush(const wr_sizing *s, int32_t g, double dmin, int32_t darg, double *best, int32_t *arg) {
    double v;
    if (g < 0 || darg < 0 || dmin > s->groups[g].reach) return;
    v = wr_transition_eval(&s->groups[g].t, dmin);
    if (v < *best) {
        *best = v;
        *arg = darg;
    }
}

static void wr__sz_scan(const wr_sizing *s, const int32_t *items, int32_t n, double px, double py, double *best,
                        int32_t *arg) {
    int32_t k, cur = -1, darg = -1;
    double dmin = INFINITY;
    for (k = 0; k < n; ++k) {
        int32_t i = items ? items[k] : k;
        const wr__sz_seg *g = &s->segs[i];
        double d;
        if (g->group != cur) {
            wr__sz_flush(s, cur, dmin, darg, best, arg);
            cur = g->group;
            dmin = INFINITY;
            darg = -1;
        }
        if (s->groups[cur].reach < 0.0) continue;
        if ((g->dx != 0.0 || g->dy != 0.0) && (px - g->ax) * g->dx + (py - g->ay) * g->dy < 0.0) continue;
        d = wr__sz_seg_dist(g, px, py, NULL, NULL);
        if (d < dmin) {
            dmin = d;
            darg = i;
        }
    }
    wr__sz_flush(s, cur, dmin, darg, best, arg);
}

static double wr__sz_brute(const wr_sizing *s, double px, double py, int32_t *arg) {
    double best = s->r_f;
    *arg = -1;
    wr__sz_scan(s, NULL, s->n_segs, px, py, &best, arg);
    return best;
}

WRDEF wr_status wr_sizing_build(wr_sizing *s, wr_diag *diag) {
    double xmin = INFINITY, ymin = INFINITY, xmax = -INFINITY, ymax = -INFINITY, W, H, h;
    int32_t i, n_act = 0, nx = 1, ny = 1;
    size_t total = 0;
    int32_t *start = NULL, *items = NULL, *fill = NULL;
    if (!s) return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "sizing: NULL object");
    wr__sz_drop_index(s);
    s->n_active_groups = 0;
    s->lb_r_min = INFINITY;
    s->lb_L_max = 0.0;
    s->lb_m_min = INFINITY;
    s->lb_m_max = 0.0;
    s->reach_max = 0.0;
    for (i = 0; i < s->n_groups; ++i) {
        const wr__sz_group *g = &s->groups[i];
        if (g->reach < 0.0) continue;
        s->n_active_groups++;
        s->lb_r_min = fmin(s->lb_r_min, g->t.r);
        s->lb_L_max = fmax(s->lb_L_max, g->t.L_w);
        s->lb_m_min = fmin(s->lb_m_min, g->t.m);
        s->lb_m_max = fmax(s->lb_m_max, g->t.m);
        s->reach_max = fmax(s->reach_max, g->reach);
    }
    for (i = 0; i < s->n_segs; ++i) {
        const wr__sz_seg *g = &s->segs[i];
        if (s->groups[g->group].reach < 0.0) continue;
        n_act++;
        xmin = fmin(xmin, fmin(g->ax, g->bx));
        xmax = fmax(xmax, fmax(g->ax, g->bx));
        ymin = fmin(ymin, fmin(g->ay, g->by));
        ymax = fmax(ymax, fmax(g->ay, g->by));
    }
    if (n_act == 0) { /* nothing can refine r_f: an empty 1×1 grid */
        xmin = ymin = 0.0;
        xmax = ymax = 1.0;
    }
    W = xmax - xmin;
    H = ymax - ymin;
    /* Finite coordinates can still span more than DBL_MAX; no cell size would be finite then. */
    if (!isfinite(W) || !isfinite(H))
        return wr_fail(diag, WR_ERR_DOMAIN, -1, "sizing: source extent [%g, %g] x [%g, %g] m overflows a double", xmin,
                       xmax, ymin, ymax);
    /* Every active segment takes at least one cell entry, so no cell size can fit a smaller cap. */
    if (n_act > s->desc.max_cells)
        return wr_fail(diag, WR_ERR_BUDGET, -1, "sizing: %d active segments exceed max_cells = %d (raise the cap)",
                       (int)n_act, (int)s->desc.max_cells);
    if (s->desc.cell_size > 0.0)
        h = s->desc.cell_size;
    else if (W > 0.0 && H > 0.0)
        h = sqrt(W * H / (double)(n_act > 0 ? n_act : 1));
    else if (W > 0.0 || H > 0.0)
        h = fmax(W, H) / (double)(n_act > 0 ? n_act : 1);
    else
        h = s->reach_max > 0.0 ? s->reach_max : 1.0;
    if (!(h > 0.0) || !isfinite(h)) h = fmax(fmax(W, H), 1e-6);
    /* Grow h until both the cell count and the stored entries fit the cap. */
    for (;;) {
        double fnx = floor(W / h) + 1.0, fny = floor(H / h) + 1.0;
        if (fnx * fny <= (double)s->desc.max_cells) {
            nx = (int32_t)fnx;
            ny = (int32_t)fny;
            total = 0;
            for (i = 0; i < s->n_segs; ++i) {
                const wr__sz_seg *g = &s->segs[i];
                double cx0, cx1, cy0, cy1;
                if (s->groups[g->group].reach < 0.0) continue;
                cx0 = floor((fmin(g->ax, g->bx) - xmin) / h);
                cx1 = floor((fmax(g->ax, g->bx) - xmin) / h);
                cy0 = floor((fmin(g->ay, g->by) - ymin) / h);
                cy1 = floor((fmax(g->ay, g->by) - ymin) / h);
                total += (size_t)((cx1 - cx0 + 1.0) * (cy1 - cy0 + 1.0));
                if (total > (size_t)s->desc.max_cells) break;
            }
            if (total <= (size_t)s->desc.max_cells) break;
        }
        h *= 2.0;
    }
    start = (int32_t *)wr_calloc_array((size_t)nx * (size_t)ny + 1, sizeof(int32_t));
    fill = (int32_t *)wr_calloc_array((size_t)nx * (size_t)ny, sizeof(int32_t));
    items = (int32_t *)wr_alloc_array(total, sizeof(int32_t));
    if (!start || !fill || !items) {
        wr_free(start);
        wr_free(fill);
        wr_free(items);
        return wr_fail(diag, WR_ERR_NOMEM, -1, "sizing: out of memory for a %dx%d grid", (int)nx, (int)ny);
    }
    /* Two passes: count per cell, prefix sum, then fill (CSR layout). */
    {
        int pass;
        for (pass = 0; pass < 2; ++pass) {
            for (i = 0; i < s->n_segs; ++i) {
                const wr__sz_seg *g = &s->segs[i];
                int32_t x0, x1, y0, y1, a, b;
                if (s->groups[g->group].reach < 0.0) continue;
                x0 = (int32_t)floor((fmin(g->ax, g->bx) - xmin) / h);
                x1 = (int32_t)floor((fmax(g->ax, g->bx) - xmin) / h);
                y0 = (int32_t)floor((fmin(g->ay, g->by) - ymin) / h);
                y1 = (int32_t)floor((fmax(g->ay, g->by) - ymin) / h);
                if (x1 > nx - 1) x1 = nx - 1;
                if (y1 > ny - 1) y1 = ny - 1;
                for (b = y0; b <= y1; ++b)
                    for (a = x0; a <= x1; ++a) {
                        size_t c = (size_t)b * (size_t)nx + (size_t)a;
                        if (pass == 0)
                            start[c + 1]++;
                        else
                            items[start[c] + fill[c]++] = i;
                    }
            }
            if (pass == 0) {
                size_t c;
                for (c = 0; c < (size_t)nx * (size_t)ny; ++c) start[c + 1] += start[c];
            }
        }
    }
    wr_free(fill);
    s->x0 = xmin;
    s->y0 = ymin;
    s->h = h;
    s->nx = nx;
    s->ny = ny;
    s->cell_start = start;
    s->cell_items = items;
    /* Ring lower-bound table: LB(D) >= lb_table[floor(D/h)] because every term grows with distance.
     * Costs n_active_groups pows per entry; capped so huge point sets fall back to the O(1) bound. */
    {
        int32_t nlb = (nx > ny ? nx : ny) + 2, j;
        if (s->n_active_groups > 0 && (double)nlb * (double)s->n_active_groups <= (double)WR__SZ_LB_TABLE_WORK) {
            s->lb_table = (double *)wr_alloc_array((size_t)nlb, sizeof(double));
            if (s->lb_table) {
                for (j = 0; j < nlb; ++j) {
                    double lb = INFINITY, D = (double)j * h;
                    for (i = 0; i < s->n_groups; ++i)
                        if (s->groups[i].reach >= 0.0) lb = fmin(lb, wr_transition_eval(&s->groups[i].t, D));
                    s->lb_table[j] = lb;
                }
                s->n_lb = nlb;
            } /* allocation failure only loses the speed-up */
        }
    }
    s->built = 1;
    return WR_OK;
}

/* Lower bound of every term at distance >= D. */
static double wr__sz_lower_bound(const wr_sizing *s, double D) {
    double j = floor(D / s->h);
    if (j < (double)s->n_lb) return s->lb_table[(int32_t)j];
    if (s->n_active_groups <= WR__SZ_EXACT_LB_GROUPS) {
        double lb = INFINITY;
        int32_t i;
        for (i = 0; i < s->n_groups; ++i)
            if (s->groups[i].reach >= 0.0) lb = fmin(lb, wr_transition_eval(&s->groups[i].t, D));
        return lb;
    } else {
        /* r_g >= r_min, L_g <= L_max ⇒ (D/L_g)^{m_g} >= q^{m} with q = D/L_max and the exponent that
         * makes q^m smallest (the largest when q < 1, the smallest when q >= 1). */
        double q = D / s->lb_L_max;
        return s->lb_r_min * (1.0 + pow(q, q < 1.0 ? s->lb_m_max : s->lb_m_min));
    }
}

static void wr__sz_visit_cell(const wr_sizing *s, int32_t a, int32_t b, double px, double py, double *best,
                              int32_t *arg) {
    size_t c = (size_t)b * (size_t)s->nx + (size_t)a;
    /* cell lists are filled in increasing segment order, as wr__sz_scan needs */
    wr__sz_scan(s, s->cell_items + s->cell_start[c], s->cell_start[c + 1] - s->cell_start[c], px, py, best, arg);
}

static double wr__sz_query(const wr_sizing *s, double px, double py, int32_t *arg) {
    double best = s->r_f, fx, fy;
    int32_t cx, cy, k, k0, kmax, nx, ny;
    *arg = -1;
    if (isnan(px) || isnan(py)) return NAN;
    if (!s->built) return wr__sz_brute(s, px, py, arg);
    if (s->n_active_groups == 0) return best;
    nx = s->nx;
    ny = s->ny;
    /* Cell of p, clamped far outside the grid so the int conversion is defined. */
    fx = floor((px - s->x0) / s->h);
    fy = floor((py - s->y0) / s->h);
    fx = fmax(-1e9, fmin(1e9, fx));
    fy = fmax(-1e9, fmin(1e9, fy));
    cx = (int32_t)fx;
    cy = (int32_t)fy;
    /* Rings before k0 lie entirely outside the grid; after kmax every cell has been seen. */
    k0 = 0;
    if (cx - (nx - 1) > k0) k0 = cx - (nx - 1);
    if (-cx > k0) k0 = -cx;
    if (cy - (ny - 1) > k0) k0 = cy - (ny - 1);
    if (-cy > k0) k0 = -cy;
    kmax = cx;
    if (nx - 1 - cx > kmax) kmax = nx - 1 - cx;
    if (cy > kmax) kmax = cy;
    if (ny - 1 - cy > kmax) kmax = ny - 1 - cy;
    for (k = k0; k <= kmax; ++k) {
        int32_t a, b, a0, a1, b0, b1;
        if (k > 0) {
            /* Unvisited segments lie outside the block of rings < k: distance >= D from p. */
            double xlo = s->x0 + (double)(cx - k + 1) * s->h, xhi = s->x0 + (double)(cx + k) * s->h;
            double ylo = s->y0 + (double)(cy - k + 1) * s->h, yhi = s->y0 + (double)(cy + k) * s->h;
            double D = fmin(fmin(px - xlo, xhi - px), fmin(py - ylo, yhi - py));
            if (D > 0.0) {
                if (D > s->reach_max) break; /* every remaining term >= r_f >= best */
                if (wr__sz_lower_bound(s, D) > best * (1.0 + WR__SZ_BOUND_MARGIN)) break;
            }
        }
        a0 = cx - k < 0 ? 0 : cx - k;
        a1 = cx + k > nx - 1 ? nx - 1 : cx + k;
        b0 = cy - k < 0 ? 0 : cy - k;
        b1 = cy + k > ny - 1 ? ny - 1 : cy + k;
        if (k == 0) {
            if (cx >= 0 && cx < nx && cy >= 0 && cy < ny) wr__sz_visit_cell(s, cx, cy, px, py, &best, arg);
            continue;
        }
        if (cy - k >= 0)
            for (a = a0; a <= a1; ++a) wr__sz_visit_cell(s, a, cy - k, px, py, &best, arg);
        if (cy + k <= ny - 1)
            for (a = a0; a <= a1; ++a) wr__sz_visit_cell(s, a, cy + k, px, py, &best, arg);
        if (b0 < cy - k + 1) b0 = cy - k + 1;
        if (b1 > cy + k - 1) b1 = cy + k - 1;
        if (cx - k >= 0)
            for (b = b0; b <= b1; ++b) wr__sz_visit_cell(s, cx - k, b, px, py, &best, arg);
        if (cx + k <= nx - 1)
            for (b = b0; b <= b1; ++b) wr__sz_visit_cell(s, cx + k, b, px, py, &best, arg);
    }
    return best;
}

WRDEF double wr_sizing_eval(const wr_sizing *s, double x, double y) {
    int32_t arg;
    return wr__sz_query(s, x, y, &arg);
}

WRDEF double wr_sizing_eval_brute(const wr_sizing *s, double x, double y) {
    int32_t arg;
    if (isnan(x) || isnan(y)) return NAN;
    return wr__sz_brute(s, x, y, &arg);
}

WRDEF void wr_sizing_eval_gradient(const wr_sizing *s, double x, double y, double *r, double grad[2]) {
    int32_t arg;
    double v = wr__sz_query(s, x, y, &arg);
    if (r) *r = v;
    grad[0] = grad[1] = 0.0;
    if (arg >= 0) {
        double qx, qy, d = wr__sz_seg_dist(&s->segs[arg], x, y, &qx, &qy);
        if (d > 0.0) {
            double sl = wr_transition_slope(&s->groups[s->segs[arg].group].t, d);
            grad[0] = sl * (x - qx) / d;
            grad[1] = sl * (y - qy) / d;
        }
    }
}

WRDEF void wr_sizing_set_region_fn(wr_sizing *s, wr_sizing_region_fn fn, void *user) {
    s->region_fn = fn;
    s->region_user = user;
}

WRDEF wr_mat2 wr_sizing_eval_metric(const wr_sizing *s, double x, double y) {
    double rv = wr_sizing_eval(s, x, y), rw = s->r_f, rf = s->r_f, ang = 0.0;
    if (s->region_fn) {
        double a, b, g;
        if (s->region_fn(s->region_user, x, y, &a, &b, &g)) {
            rw = a;
            rf = b;
            ang = g;
        }
    }
    return wr_resolution_metric(fmin(rw, rv), fmin(rf, rv), ang);
}

WRDEF int32_t wr_sizing_segment_count(const wr_sizing *s) { return s->n_segs; }
WRDEF int wr_sizing_is_built(const wr_sizing *s) { return s->built; }


/* ---- the pattern: checks and the panel's fabric ---------------------------------------------- */
/* ---- small geometry ------------------------------------------------------------------------ */

/* Closest edge of a closed loop to p: returns the distance, the edge index and its parameter. */
static double wr__sz_loop_closest(const double *xy, int32_t n, const double *p, int32_t *edge, double *t) {
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
static int wr__sz_seg_cross(const double *a, const double *b, const double *c, const double *d) {
    double o1 = wr_orient2d(a, b, c), o2 = wr_orient2d(a, b, d), o3 = wr_orient2d(c, d, a),
           o4 = wr_orient2d(c, d, b);
    if (((o1 > 0 && o2 < 0) || (o1 < 0 && o2 > 0)) && ((o3 > 0 && o4 < 0) || (o3 < 0 && o4 > 0))) return 1;
#define WR__SZ_ONSEG(p, q, r) \
    (fmin(p[0], q[0]) <= r[0] && r[0] <= fmax(p[0], q[0]) && fmin(p[1], q[1]) <= r[1] && r[1] <= fmax(p[1], q[1]))
    if (o1 == 0 && WR__SZ_ONSEG(a, b, c)) return 1;
    if (o2 == 0 && WR__SZ_ONSEG(a, b, d)) return 1;
    if (o3 == 0 && WR__SZ_ONSEG(c, d, a)) return 1;
    if (o4 == 0 && WR__SZ_ONSEG(c, d, b)) return 1;
#undef WR__SZ_ONSEG
    return 0;
}

static int wr__sz_finite_curve(const double *xy, int32_t n) {
    int32_t i;
    for (i = 0; i < 2 * n; ++i)
        if (!isfinite(xy[i])) return 0;
    return 1;
}
/* ---- resolutions ----------------------------------------------------------------------------- */
WRDEF const char *wr_pattern_panel_name(const wr_pattern *pat, int32_t p) {
    const char *n = pat->panels[p].name;
    return n ? n : "";
}

WRDEF wr_status wr_sizing_fabric_resolution(const wr_pattern_fabric *fab, const wr_resolution_model *model,
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

/* Kirchhoff–Love thickness of the panel's fabric for the compression law (see ON THE SOURCES).
 * Uses the smallest y = B/E (the fine direction). With a resolution override and no stiffness there
 * is no thickness to compute; h = r0/10 is then used (WR_SIZING_FALLBACK_THICKNESS_RATIO): for the
 * Table 1 fabrics h/r runs from 0.011 (Rose) over 0.04 (Green) to 0.13 (Dark Blue). */
static double wr__sz_thickness(const wr_pattern_fabric *f, double r0) {
    double y = HUGE_VAL;
    if (!f->anisotropic) {
        if (f->B > 0.0 && f->E > 0.0) y = f->B / f->E;
    } else {
        if (f->B_warp > 0.0 && f->E_warp > 0.0) y = f->B_warp / f->E_warp;
        if (f->B_weft > 0.0 && f->E_weft > 0.0 && f->B_weft / f->E_weft < y) y = f->B_weft / f->E_weft;
    }
    if (!(y < HUGE_VAL) || !isfinite(y)) return r0 * WR_SIZING_FALLBACK_THICKNESS_RATIO;
    return cbrt(12.0 * (1.0 - WR_SIZING_KL_POISSON * WR_SIZING_KL_POISSON) * y);
}

/* The (B, E) pair of the fabric's fine direction (smallest y = B/E); zeros when not given. */
static void wr__sz_fine_pair(const wr_pattern_fabric *f, double *B, double *E) {
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

/* The source wavelength of a source resolution r under compression δ: Sec. 4.1.1 (Fig. 4) sets
 * r = sqrt(λ²/16 + A²) with Sec. 3.1's A = (√2/π) λ √δ, so r = c(δ) λ, c = sqrt(1/16 + 2δ/π²)
 * (0.405 at δ = 0.5: λ = 2.47 r). Sec. 4.2.1's wrinklon size L_w(λ) takes this λ, not r. */
static wr_status wr__sz_source_wavelength(double r, double delta, double *lambda, wr_diag *diag) {
    double A1;
    wr_status st = wr_cm_amplitude(1.0, delta, &A1, diag); /* A per unit wavelength */
    if (st != WR_OK) return st;
    *lambda = r / wr_cm_optimal_resolution(1.0, A1);
    return WR_OK;
}

/* Transition for a source of resolution r with resolution factor rho (δ = 1 − ρ) or explicit L_w. */
static wr_status wr__sz_source_transition(double r, double rho, double h, double L_explicit, double pressure,
                                    wr_transition *t, wr_diag *diag) {
    double L = L_explicit, delta = 1.0 - rho, lambda;
    wr_status st;
    if (!(L > 0.0)) {
        if (delta < WR_SIZING_MIN_STRAIN) delta = WR_SIZING_MIN_STRAIN;
        if ((st = wr__sz_source_wavelength(r, delta, &lambda, diag)) != WR_OK) return st;
        st = wr_wrinklon_size_compression(lambda, delta, h, &L, diag);
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
WRDEF wr_status wr_pattern_check_line(const wr_pattern *pat, int32_t p, const double *xy, int32_t n,
                                    const char *what, int32_t idx, int allow_end_on, int *on_start, int *on_end,
                                    wr_diag *diag) {
    const wr_pattern_panel *pn = &pat->panels[p];
    double tol, bb = 0.0;
    int32_t i, j, h, e;
    double t;
    int start_on = 0, end_on = 0;
    if (!on_start) on_start = &start_on; /* the crossing test below needs the flags either way */
    if (!on_end) on_end = &end_on;
    *on_start = 0;
    *on_end = 0;
    if (!xy || n < 2) return wr_fail(diag, WR_ERR_GEOMETRY, idx, "%s[%d]: fewer than 2 points", what, (int)idx);
    if (!wr__sz_finite_curve(xy, n))
        return wr_fail(diag, WR_ERR_GEOMETRY, idx, "%s[%d]: non-finite coordinate", what, (int)idx);
    for (i = 0; i < pn->outer.n; ++i) bb = fmax(bb, fmax(fabs(pn->outer.xy[2 * i]), fabs(pn->outer.xy[2 * i + 1])));
    tol = WR_SIZING_ON_BOUNDARY_ABS + WR_SIZING_ON_BOUNDARY_REL * bb;
    for (i = 0; i < n; ++i) {
        const double *q = xy + 2 * i;
        double d = wr__sz_loop_closest(pn->outer.xy, pn->outer.n, q, &e, &t);
        int endpt = (i == 0 || i == n - 1);
        if (d <= tol) {
            if (allow_end_on && endpt) {
                if (i == 0 && on_start) *on_start = 1;
                if (i == n - 1 && on_end) *on_end = 1;
                continue;
            }
            return wr_fail(diag, WR_ERR_GEOMETRY, idx, "%s[%d]: point %d touches the boundary of panel %d '%s'",
                           what, (int)idx, (int)i, (int)p, wr_pattern_panel_name(pat, p));
        }
        if (!wr_point_in_polygon(pn->outer.xy, pn->outer.n, q[0], q[1]))
            return wr_fail(diag, WR_ERR_GEOMETRY, idx, "%s[%d]: point %d (%g, %g) m leaves panel %d '%s'", what,
                           (int)idx, (int)i, q[0], q[1], (int)p, wr_pattern_panel_name(pat, p));
        for (h = 0; h < pn->n_holes; ++h)
            if (wr_point_in_polygon(pn->holes[h].xy, pn->holes[h].n, q[0], q[1]))
                return wr_fail(diag, WR_ERR_GEOMETRY, idx, "%s[%d]: point %d lies in hole %d of panel %d '%s'", what,
                               (int)idx, (int)i, (int)h, (int)p, wr_pattern_panel_name(pat, p));
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
                                           what, (int)idx, (int)i, (int)p, wr_pattern_panel_name(pat, p));
                    }
                    continue;
                }
                if (wr__sz_seg_cross(a, b, u, w))
                    return wr_fail(diag, WR_ERR_GEOMETRY, idx, "%s[%d]: segment %d leaves panel %d '%s'", what,
                                   (int)idx, (int)i, (int)p, wr_pattern_panel_name(pat, p));
            }
        }
    }
    return WR_OK;
}

static wr_status wr__sz_check_panel_ref(const wr_pattern *pat, int32_t panel, const char *what, int32_t idx,
                                         wr_diag *diag) {
    if (panel < 0 || panel >= pat->n_panels)
        return wr_fail(diag, WR_ERR_INVALID_ARG, idx, "%s[%d]: panel %d does not exist (%d panels)", what, (int)idx,
                       (int)panel, (int)pat->n_panels);
    return WR_OK;
}

static wr_status wr__sz_check_rho(double rho, const char *what, int32_t idx, wr_diag *diag) {
    if (!(rho > 0.0 && rho <= 1.0))
        return wr_fail(diag, WR_ERR_INVALID_ARG, idx, "%s[%d]: rho = %g outside (0, 1]", what, (int)idx, rho);
    return WR_OK;
}

static wr_status wr__sz_check_nonneg(double v, const char *what, int32_t idx, const char *field, wr_diag *diag) {
    if (!(v >= 0.0) || !isfinite(v))
        return wr_fail(diag, WR_ERR_INVALID_ARG, idx, "%s[%d]: %s = %g must be >= 0", what, (int)idx, field, v);
    return WR_OK;
}

/* Validation of everything that does not need the sizing maps. */
WRDEF wr_status wr_pattern_validate(const wr_pattern *pat, wr_diag *diag) {
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
                           wr_pattern_panel_name(pat, p));
        if (!wr__sz_finite_curve(pn->outer.xy, pn->outer.n))
            return wr_fail(diag, WR_ERR_GEOMETRY, p, "panels[%d] '%s': non-finite coordinate", (int)p,
                           wr_pattern_panel_name(pat, p));
        if (wr_polygon_area(pn->outer.xy, pn->outer.n) == 0.0)
            return wr_fail(diag, WR_ERR_GEOMETRY, p, "panels[%d] '%s': zero area", (int)p, wr_pattern_panel_name(pat, p));
        if (pn->n_holes < 0 || (pn->n_holes > 0 && !pn->holes))
            return wr_fail(diag, WR_ERR_INVALID_ARG, p, "panels[%d] '%s': holes inconsistent", (int)p,
                           wr_pattern_panel_name(pat, p));
        for (h = 0; h < pn->n_holes; ++h) {
            if (!pn->holes[h].xy || pn->holes[h].n < 3)
                return wr_fail(diag, WR_ERR_GEOMETRY, p, "panels[%d] '%s': hole %d has fewer than 3 points", (int)p,
                               wr_pattern_panel_name(pat, p), (int)h);
            if (!wr__sz_finite_curve(pn->holes[h].xy, pn->holes[h].n))
                return wr_fail(diag, WR_ERR_GEOMETRY, p, "panels[%d] '%s': hole %d has a non-finite coordinate",
                               (int)p, wr_pattern_panel_name(pat, p), (int)h);
        }
    }
    for (i = 0; i < pat->n_shirrings; ++i) {
        const wr_pattern_shirring *s = &pat->shirrings[i];
        if ((st = wr__sz_check_panel_ref(pat, s->panel, "shirrings", i, diag)) != WR_OK) return st;
        if ((st = wr__sz_check_rho(s->rho, "shirrings", i, diag)) != WR_OK) return st;
        if ((st = wr__sz_check_nonneg(s->E_sh, "shirrings", i, "E_sh", diag)) != WR_OK) return st;
        if ((st = wr__sz_check_nonneg(s->n_exp, "shirrings", i, "n", diag)) != WR_OK) return st;
        if ((st = wr__sz_check_nonneg(s->transition_length, "shirrings", i, "transition_length", diag)) != WR_OK)
            return st;
        if ((st = wr__sz_check_nonneg(s->stitch_length, "shirrings", i, "stitch_length", diag)) != WR_OK) return st;
    }
    for (i = 0; i < pat->n_folds; ++i) {
        const wr_pattern_fold *f = &pat->folds[i];
        if ((st = wr__sz_check_panel_ref(pat, f->panel, "folds", i, diag)) != WR_OK) return st;
        if (!(f->angle_deg >= 0.0 && f->angle_deg <= 360.0))
            return wr_fail(diag, WR_ERR_INVALID_ARG, i, "folds[%d]: fold angle %g deg outside (0, 360]", (int)i,
                           f->angle_deg);
        if ((st = wr__sz_check_nonneg(f->offset, "folds", i, "offset", diag)) != WR_OK) return st;
        if ((st = wr__sz_check_nonneg(f->curvature_radius, "folds", i, "curvature_radius", diag)) != WR_OK)
            return st;
        if ((st = wr__sz_check_nonneg(f->transition_length, "folds", i, "transition_length", diag)) != WR_OK)
            return st;
    }
    for (i = 0; i < pat->n_seams; ++i) {
        const wr_pattern_seam *s = &pat->seams[i];
        if ((st = wr__sz_check_panel_ref(pat, s->a.panel, "seams", i, diag)) != WR_OK) return st;
        if ((st = wr__sz_check_panel_ref(pat, s->b.panel, "seams", i, diag)) != WR_OK) return st;
        if (!isfinite(s->a.from[0]) || !isfinite(s->a.from[1]) || !isfinite(s->a.to[0]) || !isfinite(s->a.to[1]) ||
            !isfinite(s->b.from[0]) || !isfinite(s->b.from[1]) || !isfinite(s->b.to[0]) || !isfinite(s->b.to[1]))
            return wr_fail(diag, WR_ERR_GEOMETRY, i, "seams[%d]: non-finite end point", (int)i);
        if ((st = wr__sz_check_nonneg(s->transition_length, "seams", i, "transition_length", diag)) != WR_OK)
            return st;
    }
    for (i = 0; i < pat->n_quilts; ++i) {
        const wr_pattern_quilt *q = &pat->quilts[i];
        if ((st = wr__sz_check_panel_ref(pat, q->panel, "quilts", i, diag)) != WR_OK) return st;
        if ((st = wr__sz_check_rho(q->rho, "quilts", i, diag)) != WR_OK) return st;
        if ((st = wr__sz_check_nonneg(q->E_sh, "quilts", i, "E_sh", diag)) != WR_OK) return st;
        if (!(q->pressure >= 0.0) || !isfinite(q->pressure))
            return wr_fail(diag, WR_ERR_INVALID_ARG, i, "quilts[%d]: pressure = %g must be >= 0", (int)i, q->pressure);
        if ((st = wr__sz_check_nonneg(q->transition_length, "quilts", i, "transition_length", diag)) != WR_OK)
            return st;
        if ((st = wr__sz_check_nonneg(q->stitch_length, "quilts", i, "stitch_length", diag)) != WR_OK) return st;
        if (q->n_lines < 1 || !q->lines)
            return wr_fail(diag, WR_ERR_INVALID_ARG, i, "quilts[%d]: no stitch lines", (int)i);
    }
    for (i = 0; i < pat->n_collisions; ++i) {
        const wr_pattern_collision *c = &pat->collisions[i];
        if ((st = wr__sz_check_panel_ref(pat, c->panel, "collisions", i, diag)) != WR_OK) return st;
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
            if (!wr__sz_finite_curve(c->xy, c->n))
                return wr_fail(diag, WR_ERR_GEOMETRY, i, "collisions[%d]: non-finite coordinate", (int)i);
            if (wr_polygon_area(c->xy, c->n) == 0.0)
                return wr_fail(diag, WR_ERR_GEOMETRY, i, "collisions[%d]: zero-area polygon", (int)i);
        }
        if ((st = wr__sz_check_nonneg(c->transition_length, "collisions", i, "transition_length", diag)) != WR_OK)
            return st;
    }
    (void)k;
    return WR_OK;
}

WRDEF wr_status wr_pattern_locate_on_outer(const wr_pattern *pat, int32_t p, const double pt[2], int32_t *edge, double *t,
                                        const char *what, int32_t idx, wr_diag *diag) {
    const wr_pattern_panel *pn = &pat->panels[p];
    double bb = 0.0, tol, d;
    int32_t i;
    for (i = 0; i < pn->outer.n; ++i) bb = fmax(bb, fmax(fabs(pn->outer.xy[2 * i]), fabs(pn->outer.xy[2 * i + 1])));
    tol = WR_SIZING_ON_BOUNDARY_ABS + WR_SIZING_ON_BOUNDARY_REL * bb;
    d = wr__sz_loop_closest(pn->outer.xy, pn->outer.n, pt, edge, t);
    if (d > tol)
        return wr_fail(diag, WR_ERR_GEOMETRY, idx,
                       "%s: end point (%g, %g) m does not lie on the boundary of panel %d '%s' (%.3g m away)", what,
                       pt[0], pt[1], (int)p, wr_pattern_panel_name(pat, p), d);
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

/* ---- the map of one panel ------------------------------------------------------------------------ */
static void wr__sz_apply(const double *T, const double *p, double *q) {
    double x = p[0], y = p[1];
    q[0] = T[0] * x + T[1] * y;
    q[1] = T[2] * x + T[3] * y;
}

WRDEF void wr_sizing_panel_to_stretched(const wr_sizing_panel *pn, const double p[2], double q[2]) {
    wr__sz_apply(pn->T, p, q);
}
WRDEF void wr_sizing_panel_to_pattern(const wr_sizing_panel *pn, const double q[2], double p[2]) {
    wr__sz_apply(pn->Tinv, q, p);
}

static int wr__sz_region_contains(const wr_sizing_region *g, double x, double y) {
    if (g->n > 0) return wr_point_in_polygon(g->xy, g->n, x, y);
    return (x - g->center[0]) * (x - g->center[0]) + (y - g->center[1]) * (y - g->center[1]) <= g->radius * g->radius;
}

WRDEF double wr_sizing_panel_eval(const wr_sizing_panel *pn, double x, double y) {
    double s;
    int32_t i;
    if (pn->uniform > 0.0) return pn->uniform;
    s = pn->field ? wr_sizing_eval(pn->field, x, y) : pn->r0;
    for (i = 0; i < pn->n_regions; ++i)
        if (pn->regions[i].r < s && wr__sz_region_contains(&pn->regions[i], x, y)) s = pn->regions[i].r;
    return s;
}

WRDEF double wr_sizing_panel_eval_stretched(const wr_sizing_panel *pn, double X, double Y) {
    double q[2], p[2];
    q[0] = X;
    q[1] = Y;
    wr__sz_apply(pn->Tinv, q, p);
    return wr_sizing_panel_eval(pn, p[0], p[1]);
}

WRDEF double wr_sizing_map_eval(const wr_sizing_map *map, int32_t panel, double x, double y) {
    if (!map || panel < 0 || panel >= map->n_panels) return NAN;
    return wr_sizing_panel_eval(&map->panels[panel], x, y);
}

WRDEF wr_mat2 wr_sizing_map_eval_metric(const wr_sizing_map *map, int32_t panel, double x, double y) {
    const wr_sizing_panel *pn;
    wr_mat2 T;
    double h;
    if (!map || panel < 0 || panel >= map->n_panels) return wr_m2(NAN, NAN, NAN, NAN);
    pn = &map->panels[panel];
    h = wr_sizing_panel_eval(pn, x, y);
    T = wr_m2(pn->T[0], pn->T[1], pn->T[2], pn->T[3]);
    /* stretched space is isotropic with target h: |T e| = h ⇔ eᵀ (Tᵀ T / h²) e = 1 */
    return wr_m2_scale(wr_m2_mul(wr_m2_transpose(T), T), 1.0 / (h * h));
}

WRDEF wr_status wr_sizing_map_raster(const wr_sizing_map *map, int32_t panel, const double box[4], int32_t nx,
                                     int32_t ny, double *out, wr_diag *diag) {
    const wr_sizing_panel *pn;
    int32_t i, j;
    if (!map || !box || !out) return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "sizing raster: NULL argument");
    if (panel < 0 || panel >= map->n_panels)
        return wr_fail(diag, WR_ERR_INVALID_ARG, panel, "sizing raster: panel %d does not exist (%d panels)",
                       (int)panel, (int)map->n_panels);
    if (nx < 1 || ny < 1) return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "sizing raster: %d x %d grid", (int)nx, (int)ny);
    for (i = 0; i < 4; ++i)
        if (!isfinite(box[i])) return wr_fail(diag, WR_ERR_INVALID_ARG, i, "sizing raster: box[%d] not finite", (int)i);
    pn = &map->panels[panel];
    for (j = 0; j < ny; ++j)
        for (i = 0; i < nx; ++i) {
            double x = box[0] + (i + 0.5) * (box[2] - box[0]) / nx, y = box[1] + (j + 0.5) * (box[3] - box[1]) / ny;
            int32_t h, in = wr_point_in_polygon(pn->outline, pn->n_outline, x, y);
            for (h = 0; in && h < pn->n_hole_loops; ++h)
                if (wr_point_in_polygon(pn->outline + 2 * (pn->n_outline + pn->hole_start[h]), pn->hole_start[h + 1] - pn->hole_start[h],
                                        x, y))
                    in = 0;
            out[(size_t)j * (size_t)nx + (size_t)i] = in ? wr_sizing_panel_eval(pn, x, y) : NAN;
        }
    return WR_OK;
}

WRDEF double wr_sizing_map_vertex_estimate(const wr_sizing_map *map, int32_t panel, double spacing) {
    const wr_sizing_panel *pn;
    double q;
    if (!map || panel < 0 || panel >= map->n_panels) return NAN;
    pn = &map->panels[panel];
    q = spacing > 0.0 ? 1.0 / spacing : 1.0;
    /* Interior: an equilateral mesh at edge h has 2/√3 A / h² vertices; 1 · A / h² stays below it.
     * Boundary: ∫ ds / h ≥ P / h_max points, half of them counted by the area term already. */
    return pn->area / (pn->r_warp * pn->r_weft) * q * q + pn->perimeter / (2.0 * fmax(pn->r_warp, pn->r_weft));
}

/* ---- building: the panel bases (Sec. 4.1) ---------------------------------------------------------- */
static double wr__sz_loop_length(const double *xy, int32_t n) {
    double L = 0.0;
    int32_t i;
    for (i = 0; i < n; ++i) {
        const double *a = xy + 2 * i, *b = xy + 2 * ((i + 1) % n);
        L += sqrt((b[0] - a[0]) * (b[0] - a[0]) + (b[1] - a[1]) * (b[1] - a[1]));
    }
    return L;
}

/* r_warp, r_weft, the affine maps, area, perimeter, thickness, an empty source field, and a copy of the
 * panel's loops for the raster's inside test. */
static wr_status wr__sz_panel_base(const wr_pattern *pat, int32_t p, const wr_sizing_map_desc *desc,
                                   wr_sizing_panel *pi, wr_diag *diag) {
    const wr_pattern_panel *pn = &pat->panels[p];
    double rw, rf, c, s;
    int32_t i, n_pts;
    wr_status st;
    if (desc->uniform_resolution > 0.0) {
        rw = rf = desc->uniform_resolution;
    } else {
        st = wr_sizing_fabric_resolution(&pn->fabric, &desc->model, &rw, &rf, diag);
        if (st != WR_OK) {
            char msg[WR_DIAG_MESSAGE_LEN];
            snprintf(msg, sizeof msg, "%s", diag ? diag->message : "");
            return wr_fail(diag, st, p, "panels[%d] '%s': %s", (int)p, wr_pattern_panel_name(pat, p), msg);
        }
    }
    pi->r_warp = rw;
    pi->r_weft = rf;
    pi->r0 = rw < rf ? rw : rf;
    pi->grain_angle = pn->fabric.anisotropic ? pn->fabric.grain_angle : 0.0;
    c = cos(pi->grain_angle);
    s = sin(pi->grain_angle);
    /* T = r0 diag(1/rw, 1/rf) Rᵀ, Rᵀ = [[c, s], [-s, c]];  T⁻¹ = R diag(rw, rf)/r0 */
    pi->T[0] = pi->r0 / rw * c;
    pi->T[1] = pi->r0 / rw * s;
    pi->T[2] = -pi->r0 / rf * s;
    pi->T[3] = pi->r0 / rf * c;
    pi->Tinv[0] = c * rw / pi->r0;
    pi->Tinv[1] = -s * rf / pi->r0;
    pi->Tinv[2] = s * rw / pi->r0;
    pi->Tinv[3] = c * rf / pi->r0;
    pi->area = fabs(wr_polygon_area(pn->outer.xy, pn->outer.n));
    pi->perimeter = wr__sz_loop_length(pn->outer.xy, pn->outer.n);
    n_pts = pn->outer.n;
    for (i = 0; i < pn->n_holes; ++i) {
        pi->area -= fabs(wr_polygon_area(pn->holes[i].xy, pn->holes[i].n));
        pi->perimeter += wr__sz_loop_length(pn->holes[i].xy, pn->holes[i].n);
        n_pts += pn->holes[i].n;
    }
    if (desc->uniform_resolution > 0.0) pi->uniform = desc->uniform_resolution;
    pi->thickness = wr__sz_thickness(&pn->fabric, pi->r0);
    pi->outline = (double *)wr_alloc_array((size_t)n_pts, 2 * sizeof(double));
    pi->hole_start = (int32_t *)wr_alloc_array((size_t)pn->n_holes + 1, sizeof(int32_t));
    if (!pi->outline || !pi->hole_start) return wr_fail(diag, WR_ERR_NOMEM, p, "sizing: out of memory");
    memcpy(pi->outline, pn->outer.xy, sizeof(double) * 2 * (size_t)pn->outer.n);
    pi->n_outline = pn->outer.n;
    pi->n_hole_loops = pn->n_holes;
    pi->hole_start[0] = 0;
    for (i = 0, n_pts = pn->outer.n; i < pn->n_holes; ++i) {
        memcpy(pi->outline + 2 * n_pts, pn->holes[i].xy, sizeof(double) * 2 * (size_t)pn->holes[i].n);
        n_pts += pn->holes[i].n;
        pi->hole_start[i + 1] = n_pts - pn->outer.n;
    }
    return wr_sizing_create(pi->r0, NULL, &pi->field, diag);
}

/* ---- building: one source builder per technique (Sec. 4.2) ---------------------------------------- */
/* Source resolution of a shirring-like line (Sec. 4.2.2: y_sh = B/(E+E_sh), r_sh = ρ^n r(y_sh)), scaled
 * by r_f / r(B/E), which is 1 unless the panel overrides its base resolution (the override then
 * carries over). Without stiffness (override only) E_sh cannot be weighed: r = ρ^n r_f. */
static wr_status wr__sz_shirring_resolution(const wr_sizing_map_desc *desc, const wr_pattern_fabric *fb, double r0,
                                            double E_sh, double rho, double n_exp, double *r, wr_diag *diag) {
    wr_resolution_desc rd;
    double B, E, r_b;
    wr_status st;
    memset(&rd, 0, sizeof rd);
    rd.clamp = 1;
    wr__sz_fine_pair(fb, &B, &E);
    if (!(B > 0.0 && E > 0.0)) {
        *r = pow(rho, n_exp) * r0;
        return WR_OK;
    }
    if ((st = wr_source_shirring(&desc->model, B, E, E_sh, rho, n_exp, &rd, r, diag)) != WR_OK) return st;
    if ((st = wr_resolution_from_BE(&desc->model, B, E, &rd, &r_b, diag)) != WR_OK) return st;
    *r *= r0 / r_b;
    return WR_OK;
}

static wr_status wr__sz_add_shirrings(const wr_pattern *pat, const wr_sizing_map_desc *desc, wr_sizing_map *map,
                                      wr_diag *diag) {
    int32_t i;
    wr_status st;
    for (i = 0; i < pat->n_shirrings; ++i) {
        const wr_pattern_shirring *sh = &pat->shirrings[i];
        wr_sizing_panel *pn = &map->panels[sh->panel];
        wr_transition tr;
        double r, n_exp = sh->n_exp > 0.0 ? sh->n_exp : 1.0;
        if ((st = wr_pattern_check_line(pat, sh->panel, sh->xy, sh->n, "shirrings", i, 1, NULL, NULL, diag)) != WR_OK)
            return st;
        if ((st = wr__sz_shirring_resolution(desc, &pat->panels[sh->panel].fabric, pn->r0, sh->E_sh, sh->rho, n_exp,
                                             &r, diag)) != WR_OK)
            return st;
        if ((st = wr__sz_source_transition(r, sh->rho, pn->thickness, sh->transition_length, 0.0, &tr, diag)) != WR_OK)
            return st;
        if ((st = wr_sizing_add_polyline(pn->field, sh->xy, sh->n, &tr, diag)) != WR_OK) return st;
        pn->n_sources++;
    }
    return WR_OK;
}

/* Sec. 4.2.5: a quilt's stitch lines are shirring lines (n = 1) whose transition the pressure steepens. */
static wr_status wr__sz_add_quilts(const wr_pattern *pat, const wr_sizing_map_desc *desc, wr_sizing_map *map,
                                   wr_diag *diag) {
    int32_t i, j;
    wr_status st;
    for (i = 0; i < pat->n_quilts; ++i) {
        const wr_pattern_quilt *q = &pat->quilts[i];
        wr_sizing_panel *pn = &map->panels[q->panel];
        wr_transition tr;
        double r;
        if ((st = wr__sz_shirring_resolution(desc, &pat->panels[q->panel].fabric, pn->r0, q->E_sh, q->rho, 1.0, &r,
                                             diag)) != WR_OK)
            return st;
        if ((st = wr__sz_source_transition(r, q->rho, pn->thickness, q->transition_length, q->pressure, &tr, diag)) !=
            WR_OK)
            return st;
        for (j = 0; j < q->n_lines; ++j) {
            if ((st = wr_pattern_check_line(pat, q->panel, q->lines[j].xy, q->lines[j].n, "quilts", i, 1, NULL, NULL,
                                            diag)) != WR_OK)
                return st;
            if ((st = wr_sizing_add_polyline(pn->field, q->lines[j].xy, q->lines[j].n, &tr, diag)) != WR_OK) return st;
            pn->n_sources++;
        }
    }
    return WR_OK;
}

/* Sec. 4.2.6: inside the area r = (1 − δ) r_f (a region); outside, a transition from its boundary. */
static wr_status wr__sz_add_collisions(const wr_pattern *pat, wr_sizing_map *map, wr_diag *diag) {
    int32_t i, j;
    wr_status st;
    for (i = 0; i < pat->n_collisions; ++i) {
        const wr_pattern_collision *c = &pat->collisions[i];
        wr_sizing_panel *pn = &map->panels[c->panel];
        wr_sizing_region *g;
        wr_transition tr;
        double r = (1.0 - c->compression) * pn->r0, *ring;
        int32_t nr = c->n ? c->n + 1 : WR_SIZING_DISK_SIDES + 1;
        if ((st = wr__sz_source_transition(r, 1.0 - c->compression, pn->thickness, c->transition_length, 0.0, &tr,
                                           diag)) != WR_OK)
            return st;
        g = (wr_sizing_region *)wr_realloc_array(pn->regions, (size_t)(pn->n_regions + 1), sizeof(wr_sizing_region));
        if (!g) return wr_fail(diag, WR_ERR_NOMEM, i, "sizing: out of memory (collisions[%d])", (int)i);
        pn->regions = g;
        g = &pn->regions[pn->n_regions++];
        memset(g, 0, sizeof *g);
        g->n = c->n;
        g->center[0] = c->center[0];
        g->center[1] = c->center[1];
        g->radius = c->radius;
        g->r = r;
        /* the source: the closed boundary as a polyline (first point repeated) */
        ring = (double *)wr_alloc_array((size_t)nr, 2 * sizeof(double));
        if (!ring) return wr_fail(diag, WR_ERR_NOMEM, i, "sizing: out of memory (collisions[%d])", (int)i);
        if (c->n) {
            g->xy = (double *)wr_alloc_array((size_t)c->n, 2 * sizeof(double));
            if (!g->xy) {
                wr_free(ring);
                return wr_fail(diag, WR_ERR_NOMEM, i, "sizing: out of memory (collisions[%d])", (int)i);
            }
            memcpy(g->xy, c->xy, sizeof(double) * 2 * (size_t)c->n);
            memcpy(ring, c->xy, sizeof(double) * 2 * (size_t)c->n);
            ring[2 * c->n] = c->xy[0];
            ring[2 * c->n + 1] = c->xy[1];
        } else {
            for (j = 0; j < nr; ++j) {
                ring[2 * j] = c->center[0] + c->radius * cos(6.283185307179586 * j / WR_SIZING_DISK_SIDES);
                ring[2 * j + 1] = c->center[1] + c->radius * sin(6.283185307179586 * j / WR_SIZING_DISK_SIDES);
            }
        }
        st = wr_sizing_add_polyline(pn->field, ring, nr, &tr, diag);
        wr_free(ring);
        if (st != WR_OK) return st;
        pn->n_sources++;
    }
    return WR_OK;
}

/* Loop position of a seam end: (edge, t) with t ∈ [0, 1); vertices have t = 0. */
typedef struct wr__sz_loop_pos {
    int32_t edge;
    double t;
} wr__sz_loop_pos;

static int wr__sz_pos_cmp(wr__sz_loop_pos a, wr__sz_loop_pos b) {
    if (a.edge != b.edge) return a.edge < b.edge ? -1 : 1;
    return a.t < b.t ? -1 : (a.t > b.t);
}

static void wr__sz_pos_point(const wr_pattern_curve *L, wr__sz_loop_pos q, double *xy) {
    const double *a = L->xy + 2 * q.edge, *b = L->xy + 2 * ((q.edge + 1) % L->n);
    if (q.t > 0.0) {
        xy[0] = a[0] + q.t * (b[0] - a[0]);
        xy[1] = a[1] + q.t * (b[1] - a[1]);
    } else {
        xy[0] = a[0];
        xy[1] = a[1];
    }
}

/* Does loop position x come before y on the walk that starts at f (forward: increasing keys, cyclic;
 * reverse: decreasing)? f itself comes first. */
static int wr__sz_walk_before(wr__sz_loop_pos f, wr__sz_loop_pos x, wr__sz_loop_pos y, int reverse) {
    int cx = wr__sz_pos_cmp(x, f), cy = wr__sz_pos_cmp(y, f), rx, ry, c;
    if (reverse) {
        cx = -cx;
        cy = -cy;
    }
    rx = cx >= 0 ? 0 : 1;
    ry = cy >= 0 ? 0 : 1;
    if (rx != ry) return rx < ry;
    c = wr__sz_pos_cmp(x, y);
    return reverse ? c > 0 : c < 0;
}

/* The path of one seam side along its panel's outer loop, in walk order from `from` to `to`: the two
 * end points and the loop vertices strictly between (the points mesher.h walks on its refined loop,
 * in the same order). *xy is allocated (≤ n_outer + 2 points); *length is the path length [m], 0 when
 * from and to coincide. */
static wr_status wr__sz_seam_side_path(const wr_pattern *pat, int32_t seam, int which, double **xy, int32_t *n,
                                       double *length, wr_diag *diag) {
    const wr_pattern_seam_side *sd = which ? &pat->seams[seam].b : &pat->seams[seam].a;
    const wr_pattern_curve *L = &pat->panels[sd->panel].outer;
    wr__sz_loop_pos f, t, q;
    char what[64];
    double *P;
    int32_t k, v, i;
    wr_status st;
    *xy = NULL;
    *n = 0;
    *length = 0.0;
    snprintf(what, sizeof what, "seams[%d].%c.from", (int)seam, which ? 'b' : 'a');
    if ((st = wr_pattern_locate_on_outer(pat, sd->panel, sd->from, &f.edge, &f.t, what, seam, diag)) != WR_OK) return st;
    snprintf(what, sizeof what, "seams[%d].%c.to", (int)seam, which ? 'b' : 'a');
    if ((st = wr_pattern_locate_on_outer(pat, sd->panel, sd->to, &t.edge, &t.t, what, seam, diag)) != WR_OK) return st;
    P = (double *)wr_alloc_array((size_t)L->n + 2, 2 * sizeof(double));
    if (!P) return wr_fail(diag, WR_ERR_NOMEM, seam, "sizing: out of memory (seams[%d])", (int)seam);
    wr__sz_pos_point(L, f, P);
    k = 1;
    if (wr__sz_pos_cmp(f, t) != 0) {
        /* the first vertex after f in walk order, then one vertex per step */
        v = sd->reverse ? (f.t > 0.0 ? f.edge : (f.edge + L->n - 1) % L->n) : (f.edge + 1) % L->n;
        q.t = 0.0;
        for (i = 0; i < L->n; ++i, v = sd->reverse ? (v + L->n - 1) % L->n : (v + 1) % L->n) {
            q.edge = v;
            if (wr__sz_pos_cmp(q, f) == 0) continue;
            if (!wr__sz_walk_before(f, q, t, sd->reverse)) break;
            P[2 * k] = L->xy[2 * v];
            P[2 * k + 1] = L->xy[2 * v + 1];
            ++k;
        }
        wr__sz_pos_point(L, t, P + 2 * k);
        ++k;
    }
    for (i = 0; i + 1 < k; ++i)
        *length += sqrt((P[2 * i + 2] - P[2 * i]) * (P[2 * i + 2] - P[2 * i]) +
                        (P[2 * i + 3] - P[2 * i + 1]) * (P[2 * i + 3] - P[2 * i + 1]));
    *xy = P;
    *n = k;
    return WR_OK;
}

/* Sec. 4.2.4: of two seam sides of different lengths, the LONGER one gathers: ρ_s = l_s / l_l is its
 * source factor (r = ρ_s r_f of its panel, source = its range of the outer loop). Seam ends are located
 * (and reported) in every mode; sources only when add_sources. */
static wr_status wr__sz_add_seams(const wr_pattern *pat, wr_sizing_map *map, int add_sources, wr_diag *diag) {
    int32_t i;
    wr_status st = WR_OK;
    for (i = 0; i < pat->n_seams && st == WR_OK; ++i) {
        double *xy[2] = {NULL, NULL}, len[2], rho;
        int32_t n[2], lng;
        wr_sizing_panel *pn;
        wr_transition tr;
        if ((st = wr__sz_seam_side_path(pat, i, 0, &xy[0], &n[0], &len[0], diag)) == WR_OK &&
            (st = wr__sz_seam_side_path(pat, i, 1, &xy[1], &n[1], &len[1], diag)) == WR_OK && add_sources &&
            len[0] > 0.0 && len[1] > 0.0) {
            lng = len[0] >= len[1] ? 0 : 1;
            pn = &map->panels[lng ? pat->seams[i].b.panel : pat->seams[i].a.panel];
            st = wr_source_stitch_ratio(fmin(len[0], len[1]), fmax(len[0], len[1]), &rho, diag);
            if (st == WR_OK && rho < 1.0 - 1e-9) { /* equal lengths: no compression */
                st = wr__sz_source_transition(rho * pn->r0, rho, pn->thickness, pat->seams[i].transition_length, 0.0,
                                              &tr, diag);
                if (st == WR_OK) st = wr_sizing_add_polyline(pn->field, xy[lng], n[lng], &tr, diag);
                if (st == WR_OK) pn->n_sources++;
            }
        }
        wr_free(xy[0]);
        wr_free(xy[1]);
    }
    return st;
}

/* A fold point source (Sec. 4.2.3), collected before any is added: r_ng is the map without them. */
typedef struct wr__sz_fold_point {
    int32_t panel;
    double x, y, dx, dy;
    wr_transition t;
} wr__sz_fold_point;

/* Discrete curvature at the interior vertices of a polyline: turning angle / mean adjacent length. */
static void wr__sz_polyline_curvature(const double *xy, int32_t n, double *kap) {
    int32_t j;
    kap[0] = kap[n - 1] = 0.0;
    for (j = 1; j + 1 < n; ++j) {
        const double *a = xy + 2 * (j - 1), *b = xy + 2 * j, *c = xy + 2 * (j + 1);
        double ux = b[0] - a[0], uy = b[1] - a[1], vx = c[0] - b[0], vy = c[1] - b[1];
        double la = sqrt(ux * ux + uy * uy), lb = sqrt(vx * vx + vy * vy);
        double turn = fabs(atan2(ux * vy - uy * vx, ux * vx + uy * vy));
        kap[j] = (la + lb > 0.0) ? turn / (0.5 * (la + lb)) : 0.0;
    }
}

/* Direction of fold point j, or 0 when j is not a fold point: endpoints along the fold into it,
 * high-curvature vertices (local maxima above 1/R_c) along the normal towards the centre of curvature. */
static int wr__sz_fold_point_dir(const double *xy, int32_t n, const double *kap, double Rc, int32_t j, double *dx,
                                 double *dy) {
    double nrm;
    if (j == 0 || j == n - 1) {
        const double *a = xy + 2 * j, *b = xy + 2 * (j == 0 ? 1 : n - 2);
        *dx = b[0] - a[0];
        *dy = b[1] - a[1];
    } else if (kap[j] >= 1.0 / Rc && kap[j] >= kap[j - 1] && kap[j] >= kap[j + 1]) {
        const double *a = xy + 2 * (j - 1), *b = xy + 2 * j, *c = xy + 2 * (j + 1);
        double ux = b[0] - a[0], uy = b[1] - a[1], vx = c[0] - b[0], vy = c[1] - b[1];
        double cr2 = ux * vy - uy * vx, tx = ux / (sqrt(ux * ux + uy * uy)) + vx / sqrt(vx * vx + vy * vy),
               ty = uy / (sqrt(ux * ux + uy * uy)) + vy / sqrt(vx * vx + vy * vy);
        /* left normal of the tangent for a left turn (cr2 > 0), right normal otherwise */
        *dx = cr2 > 0 ? -ty : ty;
        *dy = cr2 > 0 ? tx : -tx;
    } else {
        return 0;
    }
    nrm = sqrt(*dx * *dx + *dy * *dy);
    if (!(nrm > 0.0)) return 0;
    *dx /= nrm;
    *dy /= nrm;
    return 1;
}

/* The fold points of folds[i], appended to *fp (r_fd = (Δθ/360°) r_ng, directional transitions). */
static wr_status wr__sz_collect_fold_points(const wr_pattern *pat, const wr_sizing_map *map, int32_t i,
                                            wr__sz_fold_point **fp, int32_t *nfp, int32_t *cap, wr_diag *diag) {
    const wr_pattern_fold *fd = &pat->folds[i];
    const wr_sizing_panel *pn = &map->panels[fd->panel];
    double ang = fd->angle_deg > 0.0 ? fd->angle_deg : WR_SIZING_DEFAULT_FOLD_ANGLE;
    double rho = ang / 360.0; /* ρ_fd = Δθ/360 */
    double Rc = fd->curvature_radius > 0.0 ? fd->curvature_radius : WR_SIZING_DEFAULT_CURVATURE_RADIUS;
    double *kap = (double *)wr_calloc_array((size_t)fd->n, sizeof(double));
    int32_t j;
    wr_status st = WR_OK;
    if (!kap) return wr_fail(diag, WR_ERR_NOMEM, i, "sizing: out of memory (folds[%d])", (int)i);
    wr__sz_polyline_curvature(fd->xy, fd->n, kap);
    for (j = 0; j < fd->n && st == WR_OK; ++j) {
        double dx, dy, rfd;
        wr__sz_fold_point *q;
        if (!wr__sz_fold_point_dir(fd->xy, fd->n, kap, Rc, j, &dx, &dy)) continue;
        /* Sec. 4.2.3: r_fd = (Δθ/360°) r_ng */
        st = wr_source_folding(ang * 0.017453292519943295, wr_sizing_panel_eval(pn, fd->xy[2 * j], fd->xy[2 * j + 1]),
                               &rfd, diag);
        if (st != WR_OK) break;
        if (*nfp == *cap) {
            int32_t nc = *cap ? 2 * *cap : 16;
            wr__sz_fold_point *nf = (wr__sz_fold_point *)wr_realloc_array(*fp, (size_t)nc, sizeof(wr__sz_fold_point));
            if (!nf) {
                st = wr_fail(diag, WR_ERR_NOMEM, i, "sizing: out of memory (folds[%d])", (int)i);
                break;
            }
            *fp = nf;
            *cap = nc;
        }
        q = &(*fp)[(*nfp)++];
        q->panel = fd->panel;
        q->x = fd->xy[2 * j];
        q->y = fd->xy[2 * j + 1];
        q->dx = dx;
        q->dy = dy;
        st = wr__sz_source_transition(rfd, rho, pn->thickness, fd->transition_length, 0.0, &q->t, diag);
    }
    wr_free(kap);
    return st;
}

static wr_status wr__sz_build_fields(wr_sizing_map *map, wr_diag *diag) {
    int32_t p;
    wr_status st;
    for (p = 0; p < map->n_panels; ++p)
        if ((st = wr_sizing_build(map->panels[p].field, diag)) != WR_OK) return st;
    return WR_OK;
}

/* Fold lines are checked in every mode; their points need r_ng from the map without them, so all are
 * collected first, then added, then the fields rebuilt. */
static wr_status wr__sz_add_folds(const wr_pattern *pat, wr_sizing_map *map, int add_sources, wr_diag *diag) {
    wr__sz_fold_point *fp = NULL;
    int32_t i, nfp = 0, cap = 0;
    wr_status st = WR_OK;
    for (i = 0; i < pat->n_folds; ++i) {
        const wr_pattern_fold *fd = &pat->folds[i];
        if ((st = wr_pattern_check_line(pat, fd->panel, fd->xy, fd->n, "folds", i, 0, NULL, NULL, diag)) != WR_OK)
            return st;
    }
    if (!add_sources || pat->n_folds == 0) return WR_OK;
    for (i = 0; i < pat->n_folds && st == WR_OK; ++i) st = wr__sz_collect_fold_points(pat, map, i, &fp, &nfp, &cap, diag);
    for (i = 0; i < nfp && st == WR_OK; ++i) {
        wr_sizing_panel *pn = &map->panels[fp[i].panel];
        st = wr_sizing_add_point_directional(pn->field, fp[i].x, fp[i].y, fp[i].dx, fp[i].dy, &fp[i].t, diag);
        pn->n_sources++;
    }
    wr_free(fp);
    if (st != WR_OK) return st;
    return wr__sz_build_fields(map, diag);
}

WRDEF void wr_sizing_map_free(wr_sizing_map *map) {
    int32_t p, i;
    if (!map) return;
    if (map->panels)
        for (p = 0; p < map->n_panels; ++p) {
            wr_sizing_panel *pn = &map->panels[p];
            wr_sizing_free(pn->field);
            for (i = 0; i < pn->n_regions; ++i) wr_free(pn->regions[i].xy);
            wr_free(pn->regions);
            wr_free(pn->outline);
            wr_free(pn->hole_start);
        }
    wr_free(map->panels);
    memset(map, 0, sizeof *map);
}

/* The map in the paper's order: fabric bases (4.1), shirring (4.2.2), down-filling (4.2.5), collision
 * areas (4.2.6), long-short seams (4.2.4), then fold points (4.2.3), which read the map built so far. */
WRDEF wr_status wr_sizing_map_build(const wr_pattern *pat, const wr_sizing_map_desc *desc_in, wr_sizing_map *map,
                                    wr_diag *diag) {
    wr_sizing_map_desc desc;
    int32_t p;
    int sources;
    wr_status st;
    if (!map) return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "NULL sizing map");
    memset(map, 0, sizeof *map);
    if (!pat) return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "NULL pattern");
    if (desc_in)
        desc = *desc_in;
    else
        memset(&desc, 0, sizeof desc);
    if (desc.model.c1 == 0.0 && desc.model.c2 == 0.0) desc.model = wr_resolution_model_paper();
    if (desc.uniform_resolution < 0.0 || !isfinite(desc.uniform_resolution))
        return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "desc: uniform_resolution = %g must be >= 0 and finite",
                       desc.uniform_resolution);
    if ((st = wr_pattern_validate(pat, diag)) != WR_OK) return st;
    sources = !(desc.uniform_resolution > 0.0);
    map->panels = (wr_sizing_panel *)wr_calloc_array((size_t)pat->n_panels, sizeof(wr_sizing_panel));
    if (!map->panels) return wr_fail(diag, WR_ERR_NOMEM, -1, "sizing: out of memory");
    map->n_panels = pat->n_panels;
    for (p = 0; p < pat->n_panels && st == WR_OK; ++p) st = wr__sz_panel_base(pat, p, &desc, &map->panels[p], diag);
    if (st == WR_OK && sources) st = wr__sz_add_shirrings(pat, &desc, map, diag);
    if (st == WR_OK && sources) st = wr__sz_add_quilts(pat, &desc, map, diag);
    if (st == WR_OK && sources) st = wr__sz_add_collisions(pat, map, diag);
    if (st == WR_OK) st = wr__sz_add_seams(pat, map, sources, diag);
    if (st == WR_OK) st = wr__sz_build_fields(map, diag);
    if (st == WR_OK) st = wr__sz_add_folds(pat, map, sources, diag);
    if (st != WR_OK) wr_sizing_map_free(map);
    return st;
}

#ifdef __cplusplus
}
#endif
#endif /* WRINKLE_SIZING_IMPLEMENTATION_DONE */
#endif /* WRINKLE_IMPLEMENTATION */
