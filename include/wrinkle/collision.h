/* wrinkle/collision.h — contact between triangle meshes: a BVH broad phase with refit, vertex–
 * triangle and edge–edge distances with gradients and Hessians, the IPC log barrier on them,
 * additive continuous collision detection (a conservative time of impact), and exact intersection
 * tests (segment–triangle, triangle–triangle, whole meshes) to certify "no penetration".
 * wrinkle v0.1.0 — MIT licence (see LICENSE). Needs only libc and libm (and core.h, shell.h for the
 * Hessian sink, predicates.h for the exact orientation tests).
 *
 * Models: Li et al. 2020, "Incremental Potential Contact" (IPC): contact as a barrier on the unsigned
 * distance between a vertex and a triangle and between two edges, active below d̂, with every
 * Newton step limited by continuous collision detection so no iterate ever intersects. Li et al.
 * 2021, "Codimensional Incremental Potential Contact" (C-IPC), Alg. 1: additive CCD (ACCD). The
 * Style3D paper (Sec. 5) uses "adaptive-step collision handling" in the same spirit.
 *
 * API (create/free pairs: wr_bvh_build → wr_bvh_free, wr_collision_mesh_create → _free,
 *      wr_contact_set is zero-initialised by the caller and released with wr_contact_set_free)
 *   wr_bvh_build(b, n, boxes, diag)              binary BVH over n axis-aligned boxes (n*6: min, max)
 *   wr_bvh_refit(b, boxes)                       same tree, new boxes (O(n), no rebuild)
 *   wr_bvh_self_pairs(b, fn, user, diag)         every pair i < j whose boxes overlap
 *   wr_bvh_pairs(a, b, fn, user, diag)           every (i in a, j in b) whose boxes overlap
 *   wr_bvh_box_query(b, box, fn, user, diag)     every i whose box overlaps one query box (no allocation)
 *   wr_bvh_nearest(b, p, fn, user, best)         the primitive nearest a point (fn: its squared distance)
 *   wr_bvh_free(b)
 *   wr_collision_point_triangle_dist2(p, t0, t1, t2, g, H, w)  squared distance, ∇ (12), ∇² (144)
 *   wr_collision_edge_edge_dist2(a0, a1, b0, b1, g, H, w)      the same for two segments
 *   wr_collision_distance_from_dist2(n, s, gs, Hs, gd, Hd)     d = √s and its derivatives
 *   wr_collision_barrier(d, dhat, kappa, b1, b2)               κ·b(d), b = −(d − d̂)² ln(d/d̂)
 *   wr_collision_accd(kind, x, dx, keep, t_max, max_iter, toi) additive CCD of one pair
 *   (wr_orient3d(a, b, c, d), exact sign of (b−a)×(c−a)·(d−a): predicates.h, included by this header)
 *   wr_collision_segment_triangle_intersect(p, q, a, b, c)     exact, closed sets
 *   wr_collision_triangle_triangle_intersect(a, b)             exact, closed sets
 *   wr_collision_mesh_create(cm, nv, nf, faces, obstacle, desc, diag)  faces + edges + BVHs
 *   wr_collision_mesh_free(cm)
 *   wr_collision_contacts(cm, x, dhat, set, diag)              every PT/EE pair with d < d̂
 *   wr_collision_contact_energy(set, x, dhat, kappa, project, E, grad, sink, diag)  barrier sum
 *   wr_collision_max_step(cm, x, dx, alpha, stats, diag)       CCD: largest safe α <= 1
 *   wr_collision_mesh_bound(cm, x, vbox, diag)                 fit the local trees to vertex boxes
 *   wr_collision_max_step_local(cm, x, dx, nm, moving, alpha, stats, diag)  the same α, few moving
 *   wr_collision_mesh_self_intersects(cm, x, count, first, diag)  exact whole-mesh check
 *   wr_collision_meshes_intersect(nva, xa, nfa, fa, nvb, xb, nfb, fb, count, diag)
 *   wr_contact_set_free(set)
 *
 * EXAMPLE (a cloth vertex 1 mm above an obstacle triangle: one contact, a safe step)
 *     double x[12] = {0,0,0, 1,0,0, 0,1,0,  0.2,0.2,1e-3};
 *     double dx[12] = {0,0,0, 0,0,0, 0,0,0, 0,0,-2e-3};
 *     int32_t tri[3] = {0, 1, 2};  uint8_t obst[4] = {1, 1, 1, 0};
 *     wr_collision_mesh cm;  wr_collision_desc cd;  wr_contact_set cs;  wr_diag dg;  double alpha, E;
 *     memset(&cd, 0, sizeof cd);  memset(&cs, 0, sizeof cs);
 *     if (wr_collision_mesh_create(&cm, 4, 1, tri, obst, &cd, &dg) != WR_OK) { puts(dg.message); return 1; }
 *     if (wr_collision_contacts(&cm, x, 2e-3, &cs, &dg) != WR_OK) { puts(dg.message); return 1; }
 *     if (wr_collision_contact_energy(&cs, x, 2e-3, 1.0, 1, &E, NULL, NULL, &dg) != WR_OK) return 1;
 *     if (wr_collision_max_step(&cm, x, dx, &alpha, NULL, &dg) != WR_OK) { puts(dg.message); return 1; }
 *     printf("%d contact(s), d = %g m, E = %g J, alpha = %g\n", (int)cs.n, cs.c[0].d, E, alpha);
 *     wr_contact_set_free(&cs);  wr_collision_mesh_free(&cm);
 *
 * ON THE BROAD PHASE (why a BVH)
 *   A binary bounding-volume hierarchy of axis-aligned boxes, built top-down by median split of the
 *   box centres along the longest axis of their bounds (leaves of at most WR_BVH_LEAF primitives),
 *   refitted bottom-up when positions change (the topology of cloth and body never changes, and a
 *   refitted tree stays good while the motion per step is small against the mesh). Chosen over a
 *   uniform spatial hash because a body's triangles and a cloth's are of very different sizes (a
 *   hash needs one cell size; a BVH adapts), swept boxes of fast vertices stay one box, and there is
 *   no table size to tune. The build is O(n log n) (quickselect per level), a refit O(n), a self
 *   query O(n + pairs) on cloth-like input. Measured in bench/bench_collision.c (bench/RESULTS.md).
 *   Obstacle trees are refitted only when an obstacle moves or the padding changes (contacts pad
 *   by d̂/2, CCD by 0); the previous padding's boxes are kept, so queries alternating the two on a
 *   still body swap boxes instead of refitting (the same boxes, the same rebuild schedule).
 *   Traversal is iterative (a growable stack of node pairs), deterministic, single-threaded.
 *   A single-box query (wr_bvh_box_query: what a caller needs for "which triangles near this one")
 *   walks the tree depth first with a fixed stack on the C stack, so it allocates nothing and can
 *   sit in an inner loop: the median split halves every node (children of ⌊m/2⌋ and ⌈m/2⌉
 *   primitives), so the depth is at most ⌈log2 n⌉ <= 31 and the stack holds at most one pending
 *   sibling per level (WR__BVH_QUERY_STACK = 64 covers every int32_t n).
 *
 * ON REPEATED QUERIES
 *   A Newton solve asks wr_collision_contacts the same question several times (the line search's
 *   trial, the accepted point's gradient, its Hessian: one x). The mesh keeps a copy of the last
 *   call's x; a call with the same x (bit for bit), d̂ and set (its size and buffer untouched),
 *   with no other query on the mesh in between and no rebuild due, returns the set as it stands
 *   and only advances the rebuild schedule: what the query would give, bit for bit (a refit at the
 *   same x and padding gives the same boxes, and the obstacle trees are left as they are).
 *
 * ON DISTANCES
 *   Point–triangle (p; t0, t1, t2) and edge–edge (a0, a1; b0, b1) squared unsigned distances with
 *   their gradient and Hessian w.r.t. the 12 coordinates (order as the arguments). The closest pair
 *   of points is found exactly by region (face interior, else the closest of the three point–edge
 *   distances; edge interiors, else the closest of the four point–edge distances; point–edge,
 *   else point–point). In the active region, d² = min over the free parameters λ (0, 1 or 2 of
 *   them) of |r(x, λ)|² with r bilinear in (x, λ); by the envelope theorem ∇d² = 2 c_k r per point
 *   (c_k the closest point's barycentric coefficient, r = closest difference) and, by implicit
 *   differentiation, ∇²d² = f_xx − f_xλ f_λλ⁻¹ f_λx — one formula for the point–point, point–edge,
 *   point–plane and line–line pieces of IPC's piecewise distance (Li et al. 2020, Sec. 4.2), exact
 *   inside each piece. Across pieces d² is C¹. Edge–edge for (nearly) parallel edges: the line–
 *   line piece is used whenever |u×v|² > WR_COLLISION_PARALLEL·|u|²|v|² (u, v the edge vectors),
 *   otherwise the four point–edge distances, which are exact for parallel edges. Its Hessian grows
 *   like 1/sin²θ as the edges turn parallel; IPC's edge–edge mollifier (Sec. 4.3), which makes the
 *   barrier C¹ through the parallel switch, is NOT applied here (PSD projection keeps Newton's
 *   matrix usable; the energy is continuous). w[4] (optional) returns the closest point's
 *   coefficients: r = Σ w_k x_k (w = (1, −β0, −β1, −β2) point–triangle, (1−s, s, −(1−t), −t) edge–edge).
 *
 * ON THE BARRIER
 *   b(d) = −(d − d̂)² ln(d/d̂) for 0 < d < d̂, 0 beyond (C², Li et al. 2020 Eq. 6 written on d rather
 *   than d²), times κ [J/m²·m⁻⁰: κ b has units of energy when κ is in J/m²]. The same function as
 *   the analytic-obstacle barrier of statics.h. contact_energy sums κ b(d) over a contact set: the
 *   pair Hessian κ[b″∇d∇dᵀ + b′∇²d] is 12×12, projected to PSD per pair when project != 0.
 *
 * ON CCD (which method, why it is conservative)
 *   Additive CCD (Li et al. 2021, Alg. 1): subtract the pair's mean displacement, bound the relative
 *   speed by l_p = |Δp| + max |Δt_i| (PT) or max |Δa_i| + max |Δb_j| (EE), and advance along the
 *   straight path by steps of 0.9·d(t)/l_p (the first one (1 − keep)·d(0)/l_p). Distance is 1-Lipschitz
 *   in each point, so no step can cross zero; the loop stops at the last time whose distance is still
 *   >= keep·d(0), which is returned as the time of impact (keep = WR_COLLISION_CCD_KEEP, 0.1 by
 *   default). So the returned TOI t has d > 0 on all of [0, t] and d(t) >= keep·d(0): a step limited
 *   to t never introduces an intersection, and floating-point error in d (a few ulps of the
 *   coordinates) is covered by the margin as long as keep·d(0) exceeds it. No pair is missed: a pair
 *   whose swept boxes overlap is tested; one whose swept boxes do not overlap cannot meet. After
 *   max_iter steps (a pair sliding tangentially at a tiny gap) the current t is returned, still safe
 *   but pessimistic; the mesh-level stats count such pairs.
 *
 * ON LOCAL CCD (a step that moves few vertices)
 *   wr_collision_max_step refits every tree and traverses every pair: O(n) per call however few
 *   vertices move. A caller that certifies many small motions of a few vertices each (garment.h's
 *   seam weld: one call per merged vertex) first fits a second set of trees once
 *   (wr_collision_mesh_bound) to per-vertex boxes that hold every position each vertex will take in
 *   those calls; wr_collision_max_step_local then visits only the primitives incident to the moving
 *   vertices, asks the bound trees for the primitives whose boxes meet each one's swept box, and
 *   applies to those exactly the filters and the ACCD of wr_collision_max_step (the same swept boxes
 *   with no padding, the same pair rules, the same vertex order within a pair). Every pair that
 *   contains a moving vertex is then tested once, and a pair without one has no relative motion
 *   (ACCD returns no impact for it unless it already touches), so alpha is the same number as
 *   wr_collision_max_step's: the minimum of the same per-pair times of impact (ACCD's time does not
 *   depend on its t_max while below it, so the visiting order does not matter). The one difference:
 *   a pair of two still primitives that already touch (distance 0, an intersection that the step
 *   did not make) gives alpha = 0 there and is not looked at here; stats count only pairs with a
 *   moving vertex. Cost: O(k log n + candidates) for k moving vertices.
 *
 * ON EXACT INTERSECTION TESTS
 *   Built on predicates.h's wr_orient3d and wr_orient2d (exact signs for coordinates within
 *   [1e-50, 1e50]; the compiler flags predicates.h names: no -ffast-math, -ffp-contract=off).
 *   Segment–triangle and triangle–triangle tests treat both as CLOSED sets (touching counts as
 *   intersecting) and are exact for non-degenerate triangles (coplanar cases go to 2D with the exact wr_orient2d on the dominant-axis projection).
 *   Whole-mesh checks skip pairs of triangles that share a vertex or an edge unless they overlap
 *   beyond what they share (a fold that lays two neighbours exactly onto each other counts).
 *
 * ON PAIRS AND OBSTACLES
 *   wr_collision_mesh holds ONE vertex array (cloth and obstacles together, e.g. cloth vertices
 *   first, body after); obstacle[v] = 1 marks obstacle vertices. A primitive (vertex, edge, face) is
 *   an obstacle primitive when all its vertices are. Pairs of two obstacle primitives are never
 *   reported; pairs of two cloth primitives only with desc.self != 0 (default on); pairs that share
 *   a vertex are never reported (IPC's rule for the barrier). desc.vertex_class widens "share a
 *   vertex" to "share a class": for a mesh holding several copies of a vertex that are about to be
 *   merged (garment.h's seam weld moves the copies of each seam vertex together under CCD), the
 *   pairs that become adjacent at the merge are meant to meet and are not contacts. It applies to
 *   wr_collision_contacts and wr_collision_max_step; the exact intersection checks use the ids.
 *
 * ON UNITS AND THREADS
 *   Positions [m], distances [m], d̂ [m], κ [J/m²], energies [J]. A wr_collision_mesh keeps its BVHs
 *   inside and refits them on every query: do not share one across threads; distinct meshes are
 *   independent. The pair-level functions are pure.
 */
#ifndef WRINKLE_COLLISION_H
#define WRINKLE_COLLISION_H

#include "core.h"
#include "predicates.h" /* wr_orient2d, wr_orient3d (exact) */
#include "shell.h"

#ifdef __cplusplus
extern "C" {
#endif

/* ---- broad phase -------------------------------------------------------------------------------- */
#define WR_BVH_LEAF 4 /* primitives per leaf: 4 measured best of {1, 2, 4, 8} in bench_collision */

typedef struct wr_bvh {
    int32_t n;      /* primitives */
    int32_t nnodes; /* nodes; children of node i are left[i] and left[i] + 1 (> i), leaf: left[i] = -1 */
    int32_t *left;  /* nnodes */
    int32_t *lo, *hi; /* nnodes: node i covers prim[lo[i] .. hi[i]) */
    int32_t *prim;  /* n: primitive ids in tree order */
    double *box;    /* nnodes*6: min xyz, max xyz */
    double *pbox;   /* n*6: primitive boxes in tree order (pbox[6i] is prim[i]'s) */
} wr_bvh;

/* Pair callback: return WR_OK to continue; anything else stops the traversal and is returned. */
typedef wr_status (*wr_bvh_pair_fn)(void *user, int32_t i, int32_t j);
/* Primitive callback of a box query, the same contract. */
typedef wr_status (*wr_bvh_prim_fn)(void *user, int32_t i);

/* boxes: n*6 [min x, min y, min z, max x, max y, max z]; n >= 0 (n = 0 gives an empty tree).
 * WR_ERR_DOMAIN (item = box) for a non-finite or inverted box. */
WRDEF wr_status wr_bvh_build(wr_bvh *b, int32_t n, const double *boxes, wr_diag *diag);
/* Same primitives, new boxes (n*6 as above). No checks: boxes must be finite. */
WRDEF void wr_bvh_refit(wr_bvh *b, const double *boxes);
WRDEF wr_status wr_bvh_self_pairs(const wr_bvh *b, wr_bvh_pair_fn fn, void *user, wr_diag *diag);
WRDEF wr_status wr_bvh_pairs(const wr_bvh *a, const wr_bvh *b, wr_bvh_pair_fn fn, void *user, wr_diag *diag);
/* fn(user, i) for every primitive i whose box overlaps the closed box q (6: min xyz, max xyz;
 * touching counts, as in the pair queries), in tree order; after a refit, the refitted boxes.
 * Allocates nothing (ON THE BROAD PHASE). A q with a NaN meets nothing. WR_ERR_INVALID_ARG for a
 * NULL tree, box or callback. */
WRDEF wr_status wr_bvh_box_query(const wr_bvh *b, const double q[6], wr_bvh_prim_fn fn, void *user, wr_diag *diag);
/* Squared distance [m²] from the query point to primitive i (the nearest-primitive query). */
typedef double (*wr_bvh_dist2_fn)(void *user, int32_t i);
/* The primitive nearest point p: depth first, the nearer child first, skipping every node whose box
 * is farther from p than the best primitive so far (the box distance is a lower bound of its
 * primitives', so the answer is exact: the smallest fn over all primitives, ties to the first found).
 * Returns that squared distance and *best = its id; HUGE_VAL and *best = -1 for an empty tree.
 * Allocates nothing (the fixed stack of wr_bvh_box_query). */
WRDEF double wr_bvh_nearest(const wr_bvh *b, const double p[3], wr_bvh_dist2_fn fn, void *user, int32_t *best);
WRDEF void wr_bvh_free(wr_bvh *b);

/* ---- pair distances, barrier, CCD ------------------------------------------------------------- */
typedef enum wr_contact_kind {
    WR_CONTACT_PT = 0, /* vertex v[0] against triangle (v[1], v[2], v[3]) */
    WR_CONTACT_EE = 1  /* edge (v[0], v[1]) against edge (v[2], v[3]) */
} wr_contact_kind;

/* Which piece of the distance is active (returned by the dist2 functions). */
typedef enum wr_dist_piece {
    WR_DIST_PP = 0, /* point–point */
    WR_DIST_PE = 1, /* point–edge (line) */
    WR_DIST_PF = 2, /* point–plane (face interior) */
    WR_DIST_EE = 3  /* line–line (edge interiors) */
} wr_dist_piece;

#define WR_COLLISION_PARALLEL 1e-12 /* sin²θ below which two edges are treated as parallel: well above
                                       the ~1e-16 relative rounding of |u×v|², far below any angle
                                       at which the line–line piece differs from the endpoint one */
#define WR_COLLISION_CCD_KEEP 0.1   /* fraction of the start distance ACCD keeps (Li et al. 2021 s) */
#define WR_COLLISION_ACCD_MAX_ITER 10000
#define WR__ACCD_STEP 0.9 /* later ACCD steps advance 0.9·d/l_p (C-IPC Alg. 1 line 15's factor) */

/* Squared distance [m²]; g (12) and H (144, row-major) may be NULL, w (4) may be NULL. piece (may be
 * NULL) receives a wr_dist_piece. Degenerate (zero-area) triangles are measured by their edges. */
WRDEF double wr_collision_point_triangle_dist2(const double p[3], const double t0[3], const double t1[3],
                                               const double t2[3], double *g, double *H, double *w, int32_t *piece);
WRDEF double wr_collision_edge_edge_dist2(const double a0[3], const double a1[3], const double b0[3],
                                          const double b1[3], double *g, double *H, double *w, int32_t *piece);
/* d = √s with gd = ∇s/(2d), Hd = ∇²s/(2d) − ∇s∇sᵀ/(4d³) over n coordinates (n <= 12); gd/Hd may be
 * NULL (Hd needs Hs, gd needs gs). s must be > 0. */
WRDEF double wr_collision_distance_from_dist2(int32_t n, double s, const double *gs, const double *Hs, double *gd,
                                              double *Hd);
/* κ b(d) with b1 = κ b′(d), b2 = κ b″(d) (either may be NULL). +∞ for d <= 0, 0 for d >= d̂. */
WRDEF double wr_collision_barrier(double d, double dhat, double kappa, double *b1, double *b2);
/* Additive CCD of one pair: x (12) at t = 0, moving along dx (12) to x + dx at t = 1. Returns 1 and
 * *toi in [0, t_max] when the pair may come within keep·d(0) before t_max, else 0 (*toi = t_max).
 * keep 0 → WR_COLLISION_CCD_KEEP; max_iter 0 → WR_COLLISION_ACCD_MAX_ITER. *toi is conservative
 * (ON CCD). d(0) == 0 gives 1 and *toi = 0. */
WRDEF int32_t wr_collision_accd(wr_contact_kind kind, const double x[12], const double dx[12], double keep,
                                double t_max, int32_t max_iter, double *toi);

/* ---- exact tests ------------------------------------------------------------------------------- */
/* wr_orient3d (predicates.h): sign of det[b−a, c−a, d−a] = ((b−a)×(c−a))·(d−a). */
/* Closed segment pq against closed triangle abc: 1 if they share a point. Exact. */
WRDEF int32_t wr_collision_segment_triangle_intersect(const double p[3], const double q[3], const double a[3],
                                                      const double b[3], const double c[3]);
/* Closed triangles ta (9: three corners) and tb: 1 if they share a point. Exact. */
WRDEF int32_t wr_collision_triangle_triangle_intersect(const double ta[9], const double tb[9]);

/* ---- mesh level ------------------------------------------------------------------------------- */
/* Defaults (zero means default): self 0 → cloth self-contact ON (set no_self = 1 to switch it off). */
typedef struct wr_collision_desc {
    int32_t no_self; /* 1: skip cloth–cloth pairs (cloth against obstacles only) */
    /* nv or NULL (each vertex its own class): pairs in which a vertex of one primitive and a vertex
     * of the other share a class are skipped (ON PAIRS), copied at create */
    const int32_t *vertex_class;
} wr_collision_desc;

typedef struct wr_collision_mesh {
    int32_t nv, nf, ne;
    int32_t *faces;   /* nf*3 copy */
    int32_t *edges;   /* ne*2 unique edges (i < j) */
    uint8_t *obst_v;  /* nv: 1 = obstacle vertex */
    uint8_t *obst_e, *obst_f; /* ne, nf: 1 = all vertices obstacle */
    int32_t *vclass;  /* nv copy of desc.vertex_class, or NULL */
    int32_t self;
    int32_t queries;  /* cloth trees are rebuilt every 64th query and refitted in between */
    /* ON THE BROAD PHASE: trees over cloth vertices, edges, faces (0–2) and obstacle vertices,
     * edges, faces (3–5); ids[t][i] is the mesh-wide id of tree t's primitive i */
    wr_bvh tree[6];
    int32_t *ids[6], nids[6];
    double *ox;       /* nv*3: positions the obstacle trees were fitted at (obstacle rows) */
    double opad;      /* box padding of the obstacle trees [m] */
    int32_t ofit, orefits; /* obstacle trees fitted (0/1), refits since their last build */
    /* the obstacle trees' node and primitive boxes at the other padding of the same fit (ON THE
     * BROAD PHASE: contacts and CCD alternate paddings), valid when oalt = 1 */
    double *oalt_box[3], *oalt_pbox[3], oalt_pad;
    int32_t oalt;
    double *boxes;    /* scratch: max(nv, ne, nf)*6 */
    /* ON LOCAL CCD (empty until wr_collision_mesh_bound): trees over the primitives of ids[] fitted
     * to the vertex boxes lbox, incidence inc[inc_start[v] .. inc_start[v + 1]) (an edge e as e, a
     * face f as ne + f), a per-vertex mark (0 between calls) */
    wr_bvh ltree[6];
    double *lbox;     /* nv*6 */
    int32_t *inc_start, *inc;
    uint8_t *lmark;
    /* ON REPEATED QUERIES: the last wr_collision_contacts call (x copy, d̂, set, its size and
     * buffer, the query count after it), valid when cvalid = 1 */
    double *cx, cdhat;
    const void *cset, *cbuf;
    int32_t cn, cqueries, cvalid;
} wr_collision_mesh;

typedef struct wr_contact {
    int32_t kind;  /* wr_contact_kind */
    int32_t v[4];  /* vertex ids, layout of the kind */
    int32_t piece; /* wr_dist_piece active at detection */
    double d;      /* distance at detection [m] */
    double w[4];   /* closest-point coefficients at detection, r = Σ w_k x_k (ON DISTANCES): the lagged
                      contact point and normal r/d a friction model needs */
} wr_contact;

typedef struct wr_contact_set {
    int32_t n, cap;
    wr_contact *c;
    double min_distance; /* over the set (+∞ when empty) [m] */
} wr_contact_set;

typedef struct wr_collision_ccd_stats {
    int32_t candidates;  /* pairs whose swept boxes overlapped */
    int32_t hits;        /* pairs that limited the step below 1 */
    int32_t capped;      /* pairs that hit max_iter (TOI pessimistic) */
    int32_t worst_kind;  /* kind of the pair that set alpha (-1 when alpha = 1) */
    int32_t worst_v[4];
} wr_collision_ccd_stats;

/* faces nf*3 (indices in [0, nv)); obstacle nv flags or NULL (all cloth). Copies what it needs.
 * WR_ERR_TOPOLOGY (item = face) for an index out of range or a repeated corner. */
WRDEF wr_status wr_collision_mesh_create(wr_collision_mesh *cm, int32_t nv, int32_t nf, const int32_t *faces,
                                         const uint8_t *obstacle, const wr_collision_desc *desc, wr_diag *diag);
WRDEF void wr_collision_mesh_free(wr_collision_mesh *cm);
/* Replaces set's content by every vertex–face and edge–edge pair (ON PAIRS) with distance < dhat
 * at x (nv*3 [m]). dhat > 0. WR_ERR_GEOMETRY (item = first vertex) when a pair's distance is 0.
 * A repeat of the last call (same x, d̂ and untouched set) is answered from a record (ON REPEATED
 * QUERIES). */
WRDEF wr_status wr_collision_contacts(wr_collision_mesh *cm, const double *x, double dhat, wr_contact_set *set,
                                      wr_diag *diag);
/* E = Σ κ b(d) over the set at x; grad (nv*3, ADDED to, may be NULL); sink gets one 4-vertex block
 * per active pair (may be NULL). WR_ERR_GEOMETRY (item = contact index) when a pair has d <= 0. */
WRDEF wr_status wr_collision_contact_energy(const wr_contact_set *set, const double *x, double dhat, double kappa,
                                            int32_t project_spd, double *E, double *grad, const wr_hess_sink *sink,
                                            wr_diag *diag);
/* Largest alpha in [0, 1] such that the straight motion x → x + alpha·dx stays intersection-free for
 * every pair (ACCD with keep = WR_COLLISION_CCD_KEEP). stats may be NULL. */
WRDEF wr_status wr_collision_max_step(wr_collision_mesh *cm, const double *x, const double *dx, double *alpha,
                                      wr_collision_ccd_stats *stats, wr_diag *diag);
/* ON LOCAL CCD: fits the local trees to vbox (nv*6: min xyz, max xyz per vertex), which must hold
 * every position each vertex takes (x, x + dx) in the wr_collision_max_step_local calls until the
 * next bound; x (nv*3) is checked to lie in them. WR_ERR_DOMAIN (item = vertex) for a non-finite
 * or inverted box or a vertex outside its box. */
WRDEF wr_status wr_collision_mesh_bound(wr_collision_mesh *cm, const double *x, const double *vbox, wr_diag *diag);
/* wr_collision_max_step's alpha (ON LOCAL CCD) for a dx that is 0 except at the nm distinct
 * vertices moving[]; positions outside moving[] must not change between calls. Needs
 * wr_collision_mesh_bound first (WR_ERR_INVALID_ARG without). WR_ERR_DOMAIN (item = vertex) for a
 * moving vertex with a non-finite x or dx or outside its box at x or x + dx; WR_ERR_INVALID_ARG
 * for a vertex listed twice or out of range, or (item = vertex) a nonzero dx off the list met on
 * the way. stats (may be NULL) count pairs with a moving vertex only. */
WRDEF wr_status wr_collision_max_step_local(wr_collision_mesh *cm, const double *x, const double *dx, int32_t nm,
                                            const int32_t *moving, double *alpha, wr_collision_ccd_stats *stats,
                                            wr_diag *diag);
/* Exact: number of intersecting non-adjacent triangle pairs at x (ON EXACT INTERSECTION TESTS);
 * first (2, may be NULL) gets the first pair found (or -1, -1). */
WRDEF wr_status wr_collision_mesh_self_intersects(wr_collision_mesh *cm, const double *x, int32_t *count,
                                                  int32_t first[2], wr_diag *diag);
/* Exact: number of intersecting pairs (triangle of A, triangle of B) between two separate meshes. */
WRDEF wr_status wr_collision_meshes_intersect(int32_t nva, const double *xa, int32_t nfa, const int32_t *fa,
                                              int32_t nvb, const double *xb, int32_t nfb, const int32_t *fb,
                                              int32_t *count, wr_diag *diag);
WRDEF void wr_contact_set_free(wr_contact_set *set);

#ifdef __cplusplus
}
#endif
#endif /* WRINKLE_COLLISION_H */

/* ============================================================================================ */
#ifdef WRINKLE_IMPLEMENTATION
#ifndef WRINKLE_COLLISION_IMPLEMENTATION_DONE
#define WRINKLE_COLLISION_IMPLEMENTATION_DONE


#include <math.h>
#include <string.h>

#ifdef __cplusplus
extern "C" {
#endif

/* ==== BVH ====================================================================================== */

static int wr__bvh_finite(double v) { return v == v && v - v == 0.0; }

static double wr__bvh_key(const double *boxes, int32_t p, int axis) {
    return boxes[6 * p + axis] + boxes[6 * p + 3 + axis];
}

/* Quickselect: rearrange prim[lo..hi) so prim[k] has the k-th smallest key, smaller keys before it.
 * Median-of-three pivots, Hoare partition (equal keys split evenly). */
static void wr__bvh_select(int32_t *prim, int32_t lo, int32_t hi, int32_t k, const double *boxes, int axis) {
    --hi; /* inclusive */
    while (hi > lo) {
        int32_t i = lo, j = hi, mid = lo + (hi - lo) / 2;
        double a = wr__bvh_key(boxes, prim[lo], axis), b = wr__bvh_key(boxes, prim[mid], axis),
               c = wr__bvh_key(boxes, prim[hi], axis), piv;
        piv = a < b ? (b < c ? b : (a < c ? c : a)) : (a < c ? a : (b < c ? c : b));
        while (i <= j) {
            while (wr__bvh_key(boxes, prim[i], axis) < piv) ++i;
            while (wr__bvh_key(boxes, prim[j], axis) > piv) --j;
            if (i <= j) {
                int32_t t = prim[i];
                prim[i] = prim[j];
                prim[j] = t;
                ++i;
                --j;
            }
        }
        if (k <= j)
            hi = j;
        else if (k >= i)
            lo = i;
        else
            return;
    }
}

static void wr__bvh_node_box(wr_bvh *b, int32_t nd) {
    double *bx = b->box + 6 * nd;
    int32_t i;
    int a;
    if (b->left[nd] >= 0) {
        const double *l = b->box + 6 * b->left[nd], *r = l + 6;
        for (a = 0; a < 3; ++a) {
            bx[a] = l[a] < r[a] ? l[a] : r[a];
            bx[3 + a] = l[3 + a] > r[3 + a] ? l[3 + a] : r[3 + a];
        }
        return;
    }
    for (a = 0; a < 3; ++a) {
        bx[a] = HUGE_VAL;
        bx[3 + a] = -HUGE_VAL;
    }
    for (i = b->lo[nd]; i < b->hi[nd]; ++i) {
        const double *pb = b->pbox + 6 * i;
        for (a = 0; a < 3; ++a) {
            if (pb[a] < bx[a]) bx[a] = pb[a];
            if (pb[3 + a] > bx[3 + a]) bx[3 + a] = pb[3 + a];
        }
    }
}

WRDEF void wr_bvh_free(wr_bvh *b) {
    if (!b) return;
    wr_free(b->left);
    wr_free(b->lo);
    wr_free(b->hi);
    wr_free(b->prim);
    wr_free(b->box);
    wr_free(b->pbox);
    memset(b, 0, sizeof *b);
}

WRDEF wr_status wr_bvh_build(wr_bvh *b, int32_t n, const double *boxes, wr_diag *diag) {
    int32_t i, maxn, nd;
    if (!b) return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "bvh: NULL tree");
    memset(b, 0, sizeof *b);
    if (n < 0 || (n > 0 && !boxes)) return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "bvh: n = %d, boxes %p", (int)n,
                                                   (const void *)boxes);
    for (i = 0; i < n; ++i) {
        int a;
        for (a = 0; a < 3; ++a)
            if (!wr__bvh_finite(boxes[6 * i + a]) || !wr__bvh_finite(boxes[6 * i + 3 + a]) ||
                boxes[6 * i + a] > boxes[6 * i + 3 + a])
                return wr_fail(diag, WR_ERR_DOMAIN, i, "bvh: box %d is not finite or inverted on axis %d", (int)i, a);
    }
    maxn = n > 0 ? 2 * n - 1 : 1;
    b->n = n;
    b->left = (int32_t *)wr_alloc_array((size_t)maxn, sizeof(int32_t));
    b->lo = (int32_t *)wr_alloc_array((size_t)maxn, sizeof(int32_t));
    b->hi = (int32_t *)wr_alloc_array((size_t)maxn, sizeof(int32_t));
    b->prim = (int32_t *)wr_alloc_array((size_t)(n > 0 ? n : 1), sizeof(int32_t));
    b->box = (double *)wr_alloc_array((size_t)maxn * 6, sizeof(double));
    b->pbox = (double *)wr_alloc_array((size_t)(n > 0 ? n : 1) * 6, sizeof(double));
    if (!b->left || !b->lo || !b->hi || !b->prim || !b->box || !b->pbox) {
        wr_bvh_free(b);
        return wr_fail(diag, WR_ERR_NOMEM, -1, "bvh: out of memory (%d boxes)", (int)n);
    }
    if (n == 0) return WR_OK;
    for (i = 0; i < n; ++i) b->prim[i] = i;
    /* Nodes are created in breadth order by a worklist that is the node array itself: node nd is
     * split when reached, its children appended. Children always follow their parent. */
    b->nnodes = 1;
    b->lo[0] = 0;
    b->hi[0] = n;
    for (nd = 0; nd < b->nnodes; ++nd) {
        int32_t lo = b->lo[nd], hi = b->hi[nd], mid, c;
        double cmin[3] = {HUGE_VAL, HUGE_VAL, HUGE_VAL}, cmax[3] = {-HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
        int a, axis = 0;
        b->left[nd] = -1;
        if (hi - lo <= WR_BVH_LEAF) continue;
        for (i = lo; i < hi; ++i)
            for (a = 0; a < 3; ++a) {
                double k = wr__bvh_key(boxes, b->prim[i], a);
                if (k < cmin[a]) cmin[a] = k;
                if (k > cmax[a]) cmax[a] = k;
            }
        for (a = 1; a < 3; ++a)
            if (cmax[a] - cmin[a] > cmax[axis] - cmin[axis]) axis = a;
        mid = lo + (hi - lo) / 2;
        wr__bvh_select(b->prim, lo, hi, mid, boxes, axis);
        c = b->nnodes;
        b->nnodes += 2;
        b->left[nd] = c;
        b->lo[c] = lo;
        b->hi[c] = mid;
        b->lo[c + 1] = mid;
        b->hi[c + 1] = hi;
    }
    wr_bvh_refit(b, boxes);
    return WR_OK;
}

WRDEF void wr_bvh_refit(wr_bvh *b, const double *boxes) {
    int32_t nd, i;
    for (i = 0; i < b->n; ++i) memcpy(b->pbox + 6 * i, boxes + 6 * b->prim[i], 6 * sizeof(double));
    for (nd = b->nnodes - 1; nd >= 0; --nd) wr__bvh_node_box(b, nd);
}

static int wr__bvh_overlap(const double *a, const double *b) {
    return a[0] <= b[3] && b[0] <= a[3] && a[1] <= b[4] && b[1] <= a[4] && a[2] <= b[5] && b[2] <= a[5];
}

typedef struct wr__bvh_stack {
    int32_t *s;
    int32_t n, cap;
} wr__bvh_stack;

static int wr__bvh_push(wr__bvh_stack *st, int32_t a, int32_t b) {
    if (st->n + 2 > st->cap) {
        int32_t nc = st->cap ? 2 * st->cap : 256;
        int32_t *ns = (int32_t *)wr_realloc_array(st->s, (size_t)nc, sizeof(int32_t));
        if (!ns) return 0;
        st->s = ns;
        st->cap = nc;
    }
    st->s[st->n++] = a;
    st->s[st->n++] = b;
    return 1;
}

/* Pairs between node subtrees of ta and tb; self = (ta == tb), where (x, x) means "within x" and
 * cross pairs are only visited once (x < y). */
static wr_status wr__bvh_traverse(const wr_bvh *ta, const wr_bvh *tb, int self, wr_bvh_pair_fn fn, void *user,
                                  wr_diag *diag) {
    wr__bvh_stack st;
    wr_status rs = WR_OK;
    if (ta->n == 0 || tb->n == 0) return WR_OK;
    memset(&st, 0, sizeof st);
    if (!wr__bvh_push(&st, 0, 0)) return wr_fail(diag, WR_ERR_NOMEM, -1, "bvh: out of memory (stack)");
    while (st.n > 0 && rs == WR_OK) {
        int32_t nb = st.s[--st.n], na = st.s[--st.n];
        int la = ta->left[na] < 0, lb = tb->left[nb] < 0, ok = 1;
        if (self && na == nb) {
            if (la) {
                int32_t i, j;
                for (i = ta->lo[na]; i < ta->hi[na] && rs == WR_OK; ++i)
                    for (j = i + 1; j < ta->hi[na] && rs == WR_OK; ++j) {
                        int32_t p = ta->prim[i], q = ta->prim[j];
                        if (!wr__bvh_overlap(ta->pbox + 6 * i, ta->pbox + 6 * j)) continue;
                        rs = fn(user, p < q ? p : q, p < q ? q : p);
                    }
            } else {
                int32_t c = ta->left[na];
                ok = wr__bvh_push(&st, c, c) && wr__bvh_push(&st, c + 1, c + 1) && wr__bvh_push(&st, c, c + 1);
            }
        } else {
            if (!wr__bvh_overlap(ta->box + 6 * na, tb->box + 6 * nb)) continue;
            if (la && lb) {
                int32_t i, j;
                for (i = ta->lo[na]; i < ta->hi[na] && rs == WR_OK; ++i)
                    for (j = tb->lo[nb]; j < tb->hi[nb] && rs == WR_OK; ++j) {
                        int32_t p = ta->prim[i], q = tb->prim[j];
                        if (!wr__bvh_overlap(ta->pbox + 6 * i, tb->pbox + 6 * j)) continue;
                        if (self) {
                            if (p == q) continue;
                            rs = fn(user, p < q ? p : q, p < q ? q : p);
                        } else {
                            rs = fn(user, p, q);
                        }
                    }
            } else if (lb || (!la && (ta->hi[na] - ta->lo[na]) >= (tb->hi[nb] - tb->lo[nb]))) {
                int32_t c = ta->left[na];
                ok = wr__bvh_push(&st, c, nb) && wr__bvh_push(&st, c + 1, nb);
            } else {
                int32_t c = tb->left[nb];
                ok = wr__bvh_push(&st, na, c) && wr__bvh_push(&st, na, c + 1);
            }
        }
        if (!ok) {
            wr_free(st.s);
            return wr_fail(diag, WR_ERR_NOMEM, -1, "bvh: out of memory (stack)");
        }
    }
    wr_free(st.s);
    return rs;
}

WRDEF wr_status wr_bvh_self_pairs(const wr_bvh *b, wr_bvh_pair_fn fn, void *user, wr_diag *diag) {
    if (!b || !fn) return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "bvh: NULL tree or callback");
    return wr__bvh_traverse(b, b, 1, fn, user, diag);
}

WRDEF wr_status wr_bvh_pairs(const wr_bvh *a, const wr_bvh *b, wr_bvh_pair_fn fn, void *user, wr_diag *diag) {
    if (!a || !b || !fn) return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "bvh: NULL tree or callback");
    return wr__bvh_traverse(a, b, 0, fn, user, diag);
}

#define WR__BVH_QUERY_STACK 64 /* >= depth + 2 for any int32_t n (ON THE BROAD PHASE) */

WRDEF wr_status wr_bvh_box_query(const wr_bvh *b, const double q[6], wr_bvh_prim_fn fn, void *user, wr_diag *diag) {
    int32_t st[WR__BVH_QUERY_STACK], n = 0;
    wr_status rs = WR_OK;
    if (!b || !q || !fn) return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "bvh: NULL tree, box or callback");
    if (b->n == 0) return WR_OK;
    st[n++] = 0;
    while (n > 0 && rs == WR_OK) {
        int32_t nd = st[--n], i;
        if (!wr__bvh_overlap(b->box + 6 * nd, q)) continue;
        if (b->left[nd] >= 0) {
            if (n + 2 > WR__BVH_QUERY_STACK) return wr_fail(diag, WR_ERR_OVERFLOW, nd, "bvh: query deeper than its stack");
            st[n++] = b->left[nd] + 1;
            st[n++] = b->left[nd];
            continue;
        }
        for (i = b->lo[nd]; i < b->hi[nd] && rs == WR_OK; ++i)
            if (wr__bvh_overlap(b->pbox + 6 * i, q)) rs = fn(user, b->prim[i]);
    }
    return rs;
}

/* squared distance from point p to the closed box bx (0 inside) */
static double wr__bvh_box_dist2(const double *bx, const double p[3]) {
    double s = 0.0;
    int a;
    for (a = 0; a < 3; ++a) {
        double e = p[a] < bx[a] ? bx[a] - p[a] : (p[a] > bx[3 + a] ? p[a] - bx[3 + a] : 0.0);
        s += e * e;
    }
    return s;
}

WRDEF double wr_bvh_nearest(const wr_bvh *b, const double p[3], wr_bvh_dist2_fn fn, void *user, int32_t *best) {
    int32_t st[WR__BVH_QUERY_STACK], n = 0, id = -1;
    double bd = HUGE_VAL;
    if (b && b->n > 0) st[n++] = 0;
    while (n > 0) {
        int32_t nd = st[--n], i, l;
        if (!(wr__bvh_box_dist2(b->box + 6 * nd, p) < bd)) continue;
        if ((l = b->left[nd]) >= 0) {
            int near = wr__bvh_box_dist2(b->box + 6 * (l + 1), p) < wr__bvh_box_dist2(b->box + 6 * l, p);
            if (n + 2 > WR__BVH_QUERY_STACK) break; /* cannot happen (ON THE BROAD PHASE: depth <= 31) */
            st[n++] = near ? l : l + 1;             /* the farther child waits */
            st[n++] = near ? l + 1 : l;
            continue;
        }
        for (i = b->lo[nd]; i < b->hi[nd]; ++i) {
            double s;
            if (!(wr__bvh_box_dist2(b->pbox + 6 * i, p) < bd)) continue;
            s = fn(user, b->prim[i]);
            if (s < bd) bd = s, id = b->prim[i];
        }
    }
    if (best) *best = id;
    return bd;
}

/* ==== pair distances ============================================================================ */

/* One active piece of a squared distance over four points X[0..3]: r = Σ_k c_k X_k with
 * c = c0 + Σ_a λ_a D[a] (D[a] 4 coefficients per free parameter a < m), λ the minimiser. */
typedef struct wr__piece {
    double c[4];
    double D[2][4];
    int m;
    int kind; /* wr_dist_piece */
} wr__piece;

static double wr__dot3c(const double *a, const double *b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

static double wr__piece_r(const double *const X[4], const wr__piece *pc, double r[3]) {
    int k, i;
    for (i = 0; i < 3; ++i) {
        r[i] = 0.0;
        for (k = 0; k < 4; ++k) r[i] += pc->c[k] * X[k][i];
    }
    return wr__dot3c(r, r);
}

/* Gradient 2 c_k r and Hessian f_xx − f_xλ f_λλ⁻¹ f_λx of d² in the active piece (ON DISTANCES). */
static void wr__piece_derivs(const double *const X[4], const wr__piece *pc, const double r[3], double *g, double *H) {
    double u[2][3], M[4], Mi[4], B[12][2];
    int k, l, i, j, a, b;
    if (g)
        for (k = 0; k < 4; ++k)
            for (i = 0; i < 3; ++i) g[3 * k + i] = 2.0 * pc->c[k] * r[i];
    if (!H) return;
    for (k = 0; k < 4; ++k)
        for (l = 0; l < 4; ++l)
            for (i = 0; i < 3; ++i)
                for (j = 0; j < 3; ++j) H[(3 * k + i) * 12 + 3 * l + j] = i == j ? 2.0 * pc->c[k] * pc->c[l] : 0.0;
    if (pc->m == 0) return;
    for (a = 0; a < pc->m; ++a)
        for (i = 0; i < 3; ++i) {
            u[a][i] = 0.0;
            for (k = 0; k < 4; ++k) u[a][i] += pc->D[a][k] * X[k][i];
        }
    for (a = 0; a < pc->m; ++a)
        for (b = 0; b < pc->m; ++b) M[2 * a + b] = 2.0 * wr__dot3c(u[a], u[b]);
    if (pc->m == 1) {
        Mi[0] = 1.0 / M[0];
    } else {
        double det = M[0] * M[3] - M[1] * M[2];
        Mi[0] = M[3] / det;
        Mi[1] = -M[1] / det;
        Mi[2] = -M[2] / det;
        Mi[3] = M[0] / det;
    }
    for (k = 0; k < 4; ++k)
        for (i = 0; i < 3; ++i)
            for (a = 0; a < pc->m; ++a) B[3 * k + i][a] = 2.0 * (pc->D[a][k] * r[i] + pc->c[k] * u[a][i]);
    for (i = 0; i < 12; ++i)
        for (j = 0; j < 12; ++j) {
            double t = 0.0;
            for (a = 0; a < pc->m; ++a)
                for (b = 0; b < pc->m; ++b) t += B[i][a] * Mi[pc->m * a + b] * B[j][b];
            H[i * 12 + j] -= t;
        }
}

/* Point X[ip] against segment X[ia]–X[ib]: the point–edge piece, or point–point at a clamped end. */
static double wr__piece_point_segment(const double *const X[4], int ip, int ia, int ib, wr__piece *pc) {
    double e[3], w[3], ee, t, r[3];
    int i;
    memset(pc, 0, sizeof *pc);
    for (i = 0; i < 3; ++i) {
        e[i] = X[ib][i] - X[ia][i];
        w[i] = X[ip][i] - X[ia][i];
    }
    ee = wr__dot3c(e, e);
    t = ee > 0.0 ? wr__dot3c(w, e) / ee : 0.0;
    pc->c[ip] = 1.0;
    if (t <= 0.0) {
        pc->c[ia] = -1.0;
        pc->kind = WR_DIST_PP;
    } else if (t >= 1.0) {
        pc->c[ib] = -1.0;
        pc->kind = WR_DIST_PP;
    } else {
        pc->c[ia] = -(1.0 - t);
        pc->c[ib] = -t;
        pc->D[0][ia] = 1.0;
        pc->D[0][ib] = -1.0;
        pc->m = 1;
        pc->kind = WR_DIST_PE;
    }
    return wr__piece_r(X, pc, r);
}

static double wr__piece_finish(const double *const X[4], const wr__piece *pc, double *g, double *H, double *w,
                               int32_t *piece) {
    double r[3], s = wr__piece_r(X, pc, r);
    wr__piece_derivs(X, pc, r, g, H);
    if (w) memcpy(w, pc->c, sizeof pc->c);
    if (piece) *piece = pc->kind;
    return s;
}

WRDEF double wr_collision_point_triangle_dist2(const double p[3], const double t0[3], const double t1[3],
                                               const double t2[3], double *g, double *H, double *w, int32_t *piece) {
    const double *X[4];
    double e1[3], e2[3], q[3], a, b, c, d1, d2, det;
    wr__piece best, pc;
    double sb;
    int i, k;
    X[0] = p;
    X[1] = t0;
    X[2] = t1;
    X[3] = t2;
    for (i = 0; i < 3; ++i) {
        e1[i] = t1[i] - t0[i];
        e2[i] = t2[i] - t0[i];
        q[i] = p[i] - t0[i];
    }
    a = wr__dot3c(e1, e1);
    b = wr__dot3c(e1, e2);
    c = wr__dot3c(e2, e2);
    d1 = wr__dot3c(e1, q);
    d2 = wr__dot3c(e2, q);
    det = a * c - b * b;
    if (det > 1e-14 * a * c) { /* non-degenerate triangle: try the face interior */
        double b1 = (c * d1 - b * d2) / det, b2 = (a * d2 - b * d1) / det;
        if (b1 > 0.0 && b2 > 0.0 && b1 + b2 < 1.0) {
            memset(&pc, 0, sizeof pc);
            pc.c[0] = 1.0;
            pc.c[1] = -1.0 + b1 + b2;
            pc.c[2] = -b1;
            pc.c[3] = -b2;
            pc.D[0][1] = 1.0;
            pc.D[0][2] = -1.0;
            pc.D[1][1] = 1.0;
            pc.D[1][3] = -1.0;
            pc.m = 2;
            pc.kind = WR_DIST_PF;
            return wr__piece_finish(X, &pc, g, H, w, piece);
        }
    }
    sb = wr__piece_point_segment(X, 0, 1, 2, &best);
    for (k = 1; k < 3; ++k) {
        double s = wr__piece_point_segment(X, 0, 1 + k, 1 + (k + 1) % 3, &pc);
        if (s < sb) {
            sb = s;
            best = pc;
        }
    }
    return wr__piece_finish(X, &best, g, H, w, piece);
}

WRDEF double wr_collision_edge_edge_dist2(const double a0[3], const double a1[3], const double b0[3],
                                          const double b1[3], double *g, double *H, double *w, int32_t *piece) {
    const double *X[4];
    double u[3], v[3], q[3], uu, uv, vv, uq, vq, det;
    wr__piece best, pc;
    double sb;
    int i, k;
    X[0] = a0;
    X[1] = a1;
    X[2] = b0;
    X[3] = b1;
    for (i = 0; i < 3; ++i) {
        u[i] = a1[i] - a0[i];
        v[i] = b1[i] - b0[i];
        q[i] = a0[i] - b0[i];
    }
    uu = wr__dot3c(u, u);
    uv = wr__dot3c(u, v);
    vv = wr__dot3c(v, v);
    uq = wr__dot3c(u, q);
    vq = wr__dot3c(v, q);
    det = uu * vv - uv * uv; /* |u×v|² */
    if (det > WR_COLLISION_PARALLEL * uu * vv) {
        /* minimise |q + s u − t v|²: [uu, −uv; −uv, vv] (s, t) = (−uq, vq) */
        double s = (-uq * vv + uv * vq) / det, t = (uu * vq - uv * uq) / det;
        if (s > 0.0 && s < 1.0 && t > 0.0 && t < 1.0) {
            memset(&pc, 0, sizeof pc);
            pc.c[0] = 1.0 - s;
            pc.c[1] = s;
            pc.c[2] = -(1.0 - t);
            pc.c[3] = -t;
            pc.D[0][0] = -1.0;
            pc.D[0][1] = 1.0;
            pc.D[1][2] = 1.0;
            pc.D[1][3] = -1.0;
            pc.m = 2;
            pc.kind = WR_DIST_EE;
            return wr__piece_finish(X, &pc, g, H, w, piece);
        }
    }
    /* the minimum over the parameter square lies on its boundary: an end point against the other
     * segment (point_segment puts +1 on the point; d² does not depend on the sign of r) */
    sb = wr__piece_point_segment(X, 0, 2, 3, &best);
    for (k = 1; k < 4; ++k) {
        double s = k < 2 ? wr__piece_point_segment(X, k, 2, 3, &pc) : wr__piece_point_segment(X, k, 0, 1, &pc);
        if (s < sb) {
            sb = s;
            best = pc;
        }
    }
    if (best.c[0] + best.c[1] < 0.0) /* keep the documented sign of w: a-side positive */
        for (k = 0; k < 4; ++k) {
            best.c[k] = -best.c[k];
            best.D[0][k] = -best.D[0][k];
        }
    return wr__piece_finish(X, &best, g, H, w, piece);
}

WRDEF double wr_collision_distance_from_dist2(int32_t n, double s, const double *gs, const double *Hs, double *gd,
                                              double *Hd) {
    double d = sqrt(s);
    int32_t i, j;
    if (gd && gs)
        for (i = 0; i < n; ++i) gd[i] = gs[i] / (2.0 * d);
    if (Hd && Hs && gs)
        for (i = 0; i < n; ++i)
            for (j = 0; j < n; ++j) Hd[i * n + j] = Hs[i * n + j] / (2.0 * d) - gs[i] * gs[j] / (4.0 * d * d * d);
    return d;
}

WRDEF double wr_collision_barrier(double d, double dhat, double kappa, double *b1, double *b2) {
    double t, L;
    if (b1) *b1 = 0.0;
    if (b2) *b2 = 0.0;
    if (!(d > 0.0)) return HUGE_VAL;
    if (d >= dhat) return 0.0;
    t = d - dhat;
    L = log(d / dhat);
    if (b1) *b1 = kappa * (-2.0 * t * L - t * t / d);
    if (b2) *b2 = kappa * (-2.0 * L - 4.0 * t / d + t * t / (d * d));
    return -kappa * t * t * L;
}

static double wr__pair_dist2(wr_contact_kind kind, const double x[12]) {
    return kind == WR_CONTACT_PT ? wr_collision_point_triangle_dist2(x, x + 3, x + 6, x + 9, NULL, NULL, NULL, NULL)
                                 : wr_collision_edge_edge_dist2(x, x + 3, x + 6, x + 9, NULL, NULL, NULL, NULL);
}

WRDEF int32_t wr_collision_accd(wr_contact_kind kind, const double x[12], const double dx[12], double keep,
                                double t_max, int32_t max_iter, double *toi) {
    double p[12], xt[12], mean[3] = {0.0, 0.0, 0.0}, lp, d, gap, t = 0.0, tl, len[4];
    int32_t k, i, it;
    if (!(keep > 0.0 && keep < 1.0)) keep = WR_COLLISION_CCD_KEEP;
    if (max_iter <= 0) max_iter = WR_COLLISION_ACCD_MAX_ITER;
    *toi = t_max;
    /* C-IPC Alg. 1 lines 2-4: remove the common translation, bound the relative speed */
    for (k = 0; k < 4; ++k)
        for (i = 0; i < 3; ++i) mean[i] += 0.25 * dx[3 * k + i];
    for (k = 0; k < 4; ++k) {
        for (i = 0; i < 3; ++i) p[3 * k + i] = dx[3 * k + i] - mean[i];
        len[k] = sqrt(wr__dot3c(p + 3 * k, p + 3 * k));
    }
    if (kind == WR_CONTACT_PT) {
        double m = len[1] > len[2] ? len[1] : len[2];
        lp = len[0] + (m > len[3] ? m : len[3]);
    } else {
        lp = (len[0] > len[1] ? len[0] : len[1]) + (len[2] > len[3] ? len[2] : len[3]);
    }
    d = sqrt(wr__pair_dist2(kind, x));
    if (!(d > 0.0)) {
        *toi = 0.0;
        return 1;
    }
    if (!(lp > 0.0)) return 0;
    gap = keep * d;
    memcpy(xt, x, sizeof xt);
    tl = (1.0 - keep) * d / lp;
    for (it = 0; it < max_iter; ++it) {
        for (i = 0; i < 12; ++i) xt[i] = x[i] + (t + tl) * p[i];
        d = sqrt(wr__pair_dist2(kind, xt));
        /* the first step needs no check: by the Lipschitz bound d >= keep·d(0) after it */
        if (it > 0 && d < gap) {
            *toi = t;
            return 1;
        }
        t += tl;
        if (t > t_max) return 0;
        tl = WR__ACCD_STEP * d / lp;
    }
    *toi = t < t_max ? t : t_max; /* capped: still safe (ON CCD), pessimistic */
    return 1;
}

/* ==== exact intersection tests (predicates.h) ==================================================== */

/* Dominant-axis projection of a plane through a, b, c: drop the axis whose projected triangle is
 * exactly non-degenerate (tried z, y, x). Returns the dropped axis, or -1 if abc is collinear. */
static int wr__proj_axis(const double *a, const double *b, const double *c) {
    int drop;
    for (drop = 2; drop >= 0; --drop) {
        double pa[2], pb[2], pc[2];
        int i0 = drop == 0 ? 1 : 0, i1 = drop == 2 ? 1 : 2;
        pa[0] = a[i0];
        pa[1] = a[i1];
        pb[0] = b[i0];
        pb[1] = b[i1];
        pc[0] = c[i0];
        pc[1] = c[i1];
        if (wr_orient2d(pa, pb, pc) != 0.0) return drop;
    }
    return -1;
}

static void wr__proj(const double *p, int drop, double *q) {
    q[0] = p[drop == 0 ? 1 : 0];
    q[1] = p[drop == 2 ? 1 : 2];
}

static int wr__sgn(double v) { return v > 0.0 ? 1 : (v < 0.0 ? -1 : 0); }

/* 2D closed segments pq and rs share a point (exact). */
static int wr__seg_seg_2d(const double *p, const double *q, const double *r, const double *s) {
    int o1 = wr__sgn(wr_orient2d(p, q, r)), o2 = wr__sgn(wr_orient2d(p, q, s));
    int o3 = wr__sgn(wr_orient2d(r, s, p)), o4 = wr__sgn(wr_orient2d(r, s, q));
    if (o1 * o2 > 0 || o3 * o4 > 0) return 0;
    if (o1 != 0 || o2 != 0 || o3 != 0 || o4 != 0) return 1;
    { /* collinear: overlap of the projections on a non-degenerate axis (exact comparisons) */
        int ax = p[0] != q[0] || r[0] != s[0] ? 0 : 1;
        double a0 = p[ax] < q[ax] ? p[ax] : q[ax], a1 = p[ax] < q[ax] ? q[ax] : p[ax];
        double b0 = r[ax] < s[ax] ? r[ax] : s[ax], b1 = r[ax] < s[ax] ? s[ax] : r[ax];
        if (p[0] == q[0] && p[1] == q[1] && r[0] == s[0] && r[1] == s[1]) return p[0] == r[0] && p[1] == r[1];
        return a0 <= b1 && b0 <= a1;
    }
}

/* 2D point p in closed triangle abc (any orientation, non-degenerate). */
static int wr__pt_in_tri_2d(const double *p, const double *a, const double *b, const double *c) {
    int o1 = wr__sgn(wr_orient2d(a, b, p)), o2 = wr__sgn(wr_orient2d(b, c, p)), o3 = wr__sgn(wr_orient2d(c, a, p));
    return !((o1 < 0 || o2 < 0 || o3 < 0) && (o1 > 0 || o2 > 0 || o3 > 0));
}

static int wr__seg_tri_2d(const double *p, const double *q, const double *a, const double *b, const double *c) {
    return wr__pt_in_tri_2d(p, a, b, c) || wr__pt_in_tri_2d(q, a, b, c) || wr__seg_seg_2d(p, q, a, b) ||
           wr__seg_seg_2d(p, q, b, c) || wr__seg_seg_2d(p, q, c, a);
}

WRDEF int32_t wr_collision_segment_triangle_intersect(const double p[3], const double q[3], const double a[3],
                                                      const double b[3], const double c[3]) {
    int sp = wr__sgn(wr_orient3d(a, b, c, p)), sq = wr__sgn(wr_orient3d(a, b, c, q)), s1, s2, s3;
    if (sp * sq > 0) return 0;
    if (sp == 0 && sq == 0) { /* coplanar */
        double P[2], Q[2], A[2], B[2], C[2];
        int drop = wr__proj_axis(a, b, c);
        if (drop < 0) return 0; /* degenerate triangle: outside the contract */
        wr__proj(p, drop, P);
        wr__proj(q, drop, Q);
        wr__proj(a, drop, A);
        wr__proj(b, drop, B);
        wr__proj(c, drop, C);
        return wr__seg_tri_2d(P, Q, A, B, C);
    }
    /* the segment meets the plane in one point: it is in the triangle iff the line pq passes on the
     * same side of (or through) all three edges */
    s1 = wr__sgn(wr_orient3d(p, q, a, b));
    s2 = wr__sgn(wr_orient3d(p, q, b, c));
    s3 = wr__sgn(wr_orient3d(p, q, c, a));
    return !((s1 < 0 || s2 < 0 || s3 < 0) && (s1 > 0 || s2 > 0 || s3 > 0));
}

static int wr__tri_tri_coplanar(const double *ta, const double *tb) {
    double A[3][2], B[3][2];
    int drop = wr__proj_axis(ta, ta + 3, ta + 6), i, j;
    if (drop < 0) return 0;
    for (i = 0; i < 3; ++i) {
        wr__proj(ta + 3 * i, drop, A[i]);
        wr__proj(tb + 3 * i, drop, B[i]);
    }
    for (i = 0; i < 3; ++i) {
        if (wr__pt_in_tri_2d(A[i], B[0], B[1], B[2]) || wr__pt_in_tri_2d(B[i], A[0], A[1], A[2])) return 1;
        for (j = 0; j < 3; ++j)
            if (wr__seg_seg_2d(A[i], A[(i + 1) % 3], B[j], B[(j + 1) % 3])) return 1;
    }
    return 0;
}

WRDEF int32_t wr_collision_triangle_triangle_intersect(const double ta[9], const double tb[9]) {
    int s[3], k, all0 = 1;
    for (k = 0; k < 3; ++k) {
        s[k] = wr__sgn(wr_orient3d(ta, ta + 3, ta + 6, tb + 3 * k));
        if (s[k] != 0) all0 = 0;
    }
    if (all0) return wr__tri_tri_coplanar(ta, tb);
    if ((s[0] > 0 && s[1] > 0 && s[2] > 0) || (s[0] < 0 && s[1] < 0 && s[2] < 0)) return 0;
    /* non-coplanar: the intersection segment's ends lie on edges of one triangle or the other */
    for (k = 0; k < 3; ++k) {
        if (wr_collision_segment_triangle_intersect(ta + 3 * k, ta + 3 * ((k + 1) % 3), tb, tb + 3, tb + 6)) return 1;
        if (wr_collision_segment_triangle_intersect(tb + 3 * k, tb + 3 * ((k + 1) % 3), ta, ta + 3, ta + 6)) return 1;
    }
    return 0;
}

/* Two mesh triangles that share 1 or 2 vertices: do they meet beyond what they share? ta/tb are
 * rotated so the shared vertices come first (ta[0] == tb[0], and ta[1] == tb[1] when ns == 2 —
 * as points; the caller arranges the order). */
static int wr__tri_tri_adjacent(const double *ta, const double *tb, int ns) {
    if (ns == 2) {
        /* shared edge v w, opposite corners a (ta[2]) and b (tb[2]): they overlap beyond the edge
         * only when coplanar with a and b on the same side of the edge */
        double V[2], W[2], A2[2], B2[2];
        int drop;
        if (wr_orient3d(ta, ta + 3, ta + 6, tb + 6) != 0.0) return 0;
        drop = wr__proj_axis(ta, ta + 3, ta + 6);
        if (drop < 0) return 0;
        wr__proj(ta, drop, V);
        wr__proj(ta + 3, drop, W);
        wr__proj(ta + 6, drop, A2);
        wr__proj(tb + 6, drop, B2);
        return wr__sgn(wr_orient2d(V, W, A2)) * wr__sgn(wr_orient2d(V, W, B2)) > 0;
    }
    /* shared vertex v: non-coplanar → the far edge of one meets the other triangle; coplanar → the
     * two angular wedges at v overlap (one contains a ray of the other) */
    if (wr_orient3d(ta, ta + 3, ta + 6, tb + 3) != 0.0 || wr_orient3d(ta, ta + 3, ta + 6, tb + 6) != 0.0)
        return wr_collision_segment_triangle_intersect(ta + 3, ta + 6, tb, tb + 3, tb + 6) ||
               wr_collision_segment_triangle_intersect(tb + 3, tb + 6, ta, ta + 3, ta + 6);
    {
        double V[2], A1[2], A2[2], B1[2], B2[2];
        int drop = wr__proj_axis(ta, ta + 3, ta + 6), k;
        const double *ray[2];
        if (drop < 0) return 0;
        wr__proj(ta, drop, V);
        wr__proj(ta + 3, drop, A1);
        wr__proj(ta + 6, drop, A2);
        wr__proj(tb + 3, drop, B1);
        wr__proj(tb + 6, drop, B2);
        if (wr_orient2d(V, A1, A2) < 0.0) { /* make each wedge counter-clockwise */
            double t0 = A1[0], t1 = A1[1];
            A1[0] = A2[0]; A1[1] = A2[1]; A2[0] = t0; A2[1] = t1;
        }
        if (wr_orient2d(V, B1, B2) < 0.0) {
            double t0 = B1[0], t1 = B1[1];
            B1[0] = B2[0]; B1[1] = B2[1]; B2[0] = t0; B2[1] = t1;
        }
        ray[0] = B1;
        ray[1] = B2;
        for (k = 0; k < 2; ++k)
            if (wr_orient2d(V, A1, ray[k]) >= 0.0 && wr_orient2d(V, ray[k], A2) >= 0.0) return 1;
        ray[0] = A1;
        ray[1] = A2;
        for (k = 0; k < 2; ++k)
            if (wr_orient2d(V, B1, ray[k]) >= 0.0 && wr_orient2d(V, ray[k], B2) >= 0.0) return 1;
        return 0;
    }
}

/* ==== mesh level ================================================================================ */

#define WR__COLL_REBUILD 64 /* queries between full BVH rebuilds (refits in between) */

static int wr__coll_cmp64(const void *a, const void *b) {
    int64_t x = *(const int64_t *)a, y = *(const int64_t *)b;
    return x < y ? -1 : (x > y ? 1 : 0);
}

WRDEF void wr_collision_mesh_free(wr_collision_mesh *cm) {
    if (!cm) return;
    wr_free(cm->faces);
    wr_free(cm->edges);
    wr_free(cm->obst_v);
    wr_free(cm->obst_e);
    wr_free(cm->obst_f);
    wr_free(cm->vclass);
    wr_free(cm->boxes);
    wr_free(cm->ox);
    wr_free(cm->lbox);
    {
        int t;
        for (t = 0; t < 3; ++t) wr_free(cm->oalt_box[t]), wr_free(cm->oalt_pbox[t]);
    }
    wr_free(cm->inc_start);
    wr_free(cm->inc);
    wr_free(cm->lmark);
    wr_free(cm->cx);
    {
        int t;
        for (t = 0; t < 6; ++t) {
            wr_bvh_free(&cm->ltree[t]);
            wr_bvh_free(&cm->tree[t]);
            wr_free(cm->ids[t]);
        }
    }
    memset(cm, 0, sizeof *cm);
}

WRDEF wr_status wr_collision_mesh_create(wr_collision_mesh *cm, int32_t nv, int32_t nf, const int32_t *faces,
                                         const uint8_t *obstacle, const wr_collision_desc *desc, wr_diag *diag) {
    int64_t *keys = NULL;
    int32_t f, k, i, ne = 0, nmax;
    if (!cm) return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "collision mesh: NULL output");
    memset(cm, 0, sizeof *cm);
    if (nv < 1 || nf < 0 || (nf > 0 && !faces))
        return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "collision mesh: nv = %d, nf = %d, faces %p", (int)nv, (int)nf,
                       (const void *)faces);
    for (f = 0; f < nf; ++f) {
        const int32_t *t = faces + 3 * f;
        for (k = 0; k < 3; ++k)
            if (t[k] < 0 || t[k] >= nv)
                return wr_fail(diag, WR_ERR_TOPOLOGY, f, "collision mesh: face %d corner %d = %d outside [0, %d)", (int)f,
                               k, (int)t[k], (int)nv);
        if (t[0] == t[1] || t[1] == t[2] || t[0] == t[2])
            return wr_fail(diag, WR_ERR_TOPOLOGY, f, "collision mesh: face %d repeats a corner", (int)f);
    }
    cm->nv = nv;
    cm->nf = nf;
    cm->self = !(desc && desc->no_self);
    keys = (int64_t *)wr_alloc_array((size_t)3 * (size_t)(nf > 0 ? nf : 1), sizeof(int64_t));
    cm->faces = (int32_t *)wr_alloc_array((size_t)3 * (size_t)(nf > 0 ? nf : 1), sizeof(int32_t));
    cm->obst_v = (uint8_t *)wr_calloc_array((size_t)nv, 1);
    cm->obst_f = (uint8_t *)wr_calloc_array((size_t)(nf > 0 ? nf : 1), 1);
    if (!keys || !cm->faces || !cm->obst_v || !cm->obst_f) goto nomem;
    if (desc && desc->vertex_class) {
        if (!(cm->vclass = (int32_t *)wr_alloc_array((size_t)nv, sizeof(int32_t)))) goto nomem;
        memcpy(cm->vclass, desc->vertex_class, sizeof(int32_t) * (size_t)nv);
    }
    if (nf > 0) memcpy(cm->faces, faces, sizeof(int32_t) * 3 * (size_t)nf);
    if (obstacle)
        for (i = 0; i < nv; ++i) cm->obst_v[i] = obstacle[i] != 0;
    for (f = 0; f < nf; ++f) {
        const int32_t *t = faces + 3 * f;
        cm->obst_f[f] = cm->obst_v[t[0]] && cm->obst_v[t[1]] && cm->obst_v[t[2]];
        for (k = 0; k < 3; ++k) {
            int32_t a = t[k], b = t[(k + 1) % 3];
            keys[3 * f + k] = a < b ? ((int64_t)a << 32) | b : ((int64_t)b << 32) | a;
        }
    }
    qsort(keys, (size_t)3 * (size_t)nf, sizeof(int64_t), wr__coll_cmp64);
    for (i = 0; i < 3 * nf; ++i)
        if (i == 0 || keys[i] != keys[i - 1]) keys[ne++] = keys[i];
    cm->ne = ne;
    cm->edges = (int32_t *)wr_alloc_array((size_t)2 * (size_t)(ne > 0 ? ne : 1), sizeof(int32_t));
    cm->obst_e = (uint8_t *)wr_calloc_array((size_t)(ne > 0 ? ne : 1), 1);
    nmax = nv > ne ? nv : ne;
    if (nf > nmax) nmax = nf;
    cm->boxes = (double *)wr_alloc_array((size_t)6 * (size_t)nmax, sizeof(double));
    if (!cm->edges || !cm->obst_e || !cm->boxes) goto nomem;
    for (i = 0; i < ne; ++i) {
        cm->edges[2 * i] = (int32_t)(keys[i] >> 32);
        cm->edges[2 * i + 1] = (int32_t)(keys[i] & 0xffffffff);
        cm->obst_e[i] = cm->obst_v[cm->edges[2 * i]] && cm->obst_v[cm->edges[2 * i + 1]];
    }
    wr_free(keys);
    keys = NULL;
    cm->ox = (double *)wr_alloc_array((size_t)3 * (size_t)nv, sizeof(double));
    if (!cm->ox) goto nomem;
    {   /* the six primitive lists of ON THE BROAD PHASE, in increasing id order */
        int t;
        for (t = 0; t < 6; ++t) {
            int32_t n = t % 3 == 0 ? nv : (t % 3 == 1 ? ne : nf), m = 0;
            const uint8_t *ob = t % 3 == 0 ? cm->obst_v : (t % 3 == 1 ? cm->obst_e : cm->obst_f);
            cm->ids[t] = (int32_t *)wr_alloc_array((size_t)(n > 0 ? n : 1), sizeof(int32_t));
            if (!cm->ids[t]) goto nomem;
            for (i = 0; i < n; ++i)
                if ((ob[i] != 0) == (t >= 3)) cm->ids[t][m++] = i;
            cm->nids[t] = m;
        }
    }
    return WR_OK;
nomem:
    wr_free(keys);
    wr_collision_mesh_free(cm);
    return wr_fail(diag, WR_ERR_NOMEM, -1, "collision mesh: out of memory (%d vertices, %d faces)", (int)nv, (int)nf);
}

/* Box of the vertices vs[0..n) at x and (when dx != NULL) at x + dx, grown by pad on every side. */
static void wr__coll_box(const double *x, const double *dx, const int32_t *vs, int n, double pad, double *bx) {
    int k, a;
    for (a = 0; a < 3; ++a) {
        bx[a] = HUGE_VAL;
        bx[3 + a] = -HUGE_VAL;
    }
    for (k = 0; k < n; ++k)
        for (a = 0; a < 3; ++a) {
            double p = x[3 * vs[k] + a], q = dx ? p + dx[3 * vs[k] + a] : p;
            double lo = p < q ? p : q, hi = p < q ? q : p;
            if (lo < bx[a]) bx[a] = lo;
            if (hi > bx[3 + a]) bx[3 + a] = hi;
        }
    for (a = 0; a < 3; ++a) {
        bx[a] -= pad;
        bx[3 + a] += pad;
    }
}

static int wr__coll_finite(double v) { return v == v && v - v == 0.0; }

/* Boxes of tree t's primitives (ON THE BROAD PHASE) into cm->boxes; refit or (re)build the tree. */
static wr_status wr__coll_tree(wr_collision_mesh *cm, int t, const double *x, const double *dx, double pad, int rebuild,
                               wr_diag *diag) {
    wr_bvh *b = &cm->tree[t];
    int32_t n = cm->nids[t], i, which = t % 3;
    for (i = 0; i < n; ++i) {
        int32_t g = cm->ids[t][i];
        const int32_t *vs = which == 0 ? &cm->ids[t][i] : (which == 1 ? cm->edges + 2 * g : cm->faces + 3 * g);
        wr__coll_box(x, dx, vs, which + 1, pad, cm->boxes + 6 * i);
    }
    if (rebuild || b->n != n || !b->left) {
        wr_bvh_free(b);
        return wr_bvh_build(b, n, cm->boxes, diag);
    }
    wr_bvh_refit(b, cm->boxes);
    return WR_OK;
}

/* Swap the obstacle trees' box arrays with the kept ones of the other padding. */
static void wr__coll_swap_alt(wr_collision_mesh *cm) {
    int t;
    for (t = 0; t < 3; ++t) {
        double *b = cm->tree[3 + t].box, *p = cm->tree[3 + t].pbox;
        cm->tree[3 + t].box = cm->oalt_box[t], cm->tree[3 + t].pbox = cm->oalt_pbox[t];
        cm->oalt_box[t] = b, cm->oalt_pbox[t] = p;
    }
}

/* Room for the kept boxes (the sizes wr_bvh_build allocates); 0 when out of memory (then nothing is
 * kept: a cache, not needed for correctness). */
static int wr__coll_alt_alloc(wr_collision_mesh *cm) {
    int t;
    for (t = 0; t < 3; ++t) {
        size_t n = (size_t)(cm->tree[3 + t].n > 0 ? cm->tree[3 + t].n : 1), m = cm->tree[3 + t].n > 0 ? 2 * n - 1 : 1;
        if (!cm->oalt_box[t]) cm->oalt_box[t] = (double *)wr_alloc_array(6 * m, sizeof(double));
        if (!cm->oalt_pbox[t]) cm->oalt_pbox[t] = (double *)wr_alloc_array(6 * n, sizeof(double));
        if (!cm->oalt_box[t] || !cm->oalt_pbox[t]) return 0;
    }
    return 1;
}

/* The obstacle trees are fitted again only when an obstacle vertex moved (or moves along dx) or the
 * padding changed (contacts pad by d̂/2, CCD by 0: a padded tree would hand CCD extra candidates,
 * whose additive CCD is conservative for tangential motion): a body held still costs its box
 * refit per query at most, and never the traversal of its own pairs. A refit that only changes
 * the padding keeps the previous padding's boxes, and the next query at that padding swaps them
 * back in: the same boxes a refit would compute, bit for bit, on the same tree (the swap counts as
 * a refit for the rebuild schedule), so contacts and CCD alternating on a still body refit it at
 * most once per WR__COLL_REBUILD queries instead of every query. */
static wr_status wr__coll_obstacle_trees(wr_collision_mesh *cm, const double *x, const double *dx, double pad,
                                         wr_diag *diag) {
    int32_t k, i, moving = 0, still = cm->ofit; /* still: fitted at these positions */
    wr_status st;
    int t, rebuild, keep;
    for (k = 0; k < cm->nids[3]; ++k) {
        int32_t v = cm->ids[3][k];
        for (i = 0; i < 3; ++i) {
            if (dx && dx[3 * v + i] != 0.0) moving = 1;
            if (x[3 * v + i] != cm->ox[3 * v + i]) still = 0;
        }
    }
    if (still && !moving && pad == cm->opad) return WR_OK;
    rebuild = !cm->ofit || cm->orefits >= WR__COLL_REBUILD;
    keep = still && !moving && !rebuild;
    if (keep && cm->oalt && pad == cm->oalt_pad) {
        wr__coll_swap_alt(cm);
        cm->oalt_pad = cm->opad;
        cm->opad = pad;
        cm->orefits++;
        return WR_OK;
    }
    cm->oalt = 0;
    keep = keep && wr__coll_alt_alloc(cm);
    if (keep) wr__coll_swap_alt(cm); /* the fitted boxes kept; the refit below overwrites every entry of the others */
    for (t = 3; t < 6; ++t)
        if ((st = wr__coll_tree(cm, t, x, dx, pad, rebuild, diag)) != WR_OK) {
            cm->ofit = 0;
            return st;
        }
    if (keep) cm->oalt = 1, cm->oalt_pad = cm->opad;
    cm->orefits = rebuild ? 0 : cm->orefits + 1;
    /* boxes swept along a moving obstacle's dx are not reused */
    cm->ofit = !moving;
    cm->opad = pad;
    for (k = 0; k < cm->nids[3]; ++k)
        for (i = 0; i < 3; ++i) cm->ox[3 * cm->ids[3][k] + i] = x[3 * cm->ids[3][k] + i];
    return WR_OK;
}

static wr_status wr__coll_trees(wr_collision_mesh *cm, const double *x, const double *dx, double pad, wr_diag *diag) {
    int rebuild = (cm->queries++ % WR__COLL_REBUILD) == 0, t;
    wr_status st;
    int32_t i;
    for (i = 0; i < 3 * cm->nv; ++i)
        if (!wr__coll_finite(x[i]) || (dx && !wr__coll_finite(dx[i])))
            return wr_fail(diag, WR_ERR_DOMAIN, i / 3, "collision: vertex %d has a non-finite coordinate%s", (int)(i / 3),
                           dx && wr__coll_finite(x[i]) ? " step" : "");
    for (t = 0; t < 3; ++t)
        if ((st = wr__coll_tree(cm, t, x, dx, pad, rebuild, diag)) != WR_OK) return st;
    return wr__coll_obstacle_trees(cm, x, dx, pad, diag);
}

/* ON PAIRS: 1 when the pair (primitive obstacle flags oa, ob) is to be considered */
static int wr__coll_keep(const wr_collision_mesh *cm, int oa, int ob) {
    if (oa && ob) return 0;
    if (!oa && !ob && !cm->self) return 0;
    return 1;
}

static void wr__coll_gather(const double *x, const int32_t v[4], double x12[12]) {
    int k, i;
    for (k = 0; k < 4; ++k)
        for (i = 0; i < 3; ++i) x12[3 * k + i] = x[3 * v[k] + i];
}

typedef struct wr__coll_ctx {
    wr_collision_mesh *cm;
    const int32_t *ma, *mb; /* tree-local → mesh-wide ids of the two trees being traversed */
    const double *x, *dx;
    double dhat;
    wr_contact_set *set;
    wr_diag *diag;
    double alpha;
    wr_collision_ccd_stats *stats;
} wr__coll_ctx;

/* ON PAIRS: the class of vertex v (itself without vertex_class); pairs sharing a class are skipped */
static int32_t wr__coll_cls(const int32_t *cls, int32_t v) { return cls ? cls[v] : v; }

/* The pair (PT: vertex i, face j; EE: edge i, edge j) as 4 vertex ids, or 0 when it is skipped. */
static int wr__coll_pair(const wr_collision_mesh *cm, int kind, int32_t i, int32_t j, int32_t v[4]) {
    const int32_t *c = cm->vclass;
    if (kind == WR_CONTACT_PT) {
        const int32_t *t = cm->faces + 3 * j;
        int32_t p = wr__coll_cls(c, i);
        if (p == wr__coll_cls(c, t[0]) || p == wr__coll_cls(c, t[1]) || p == wr__coll_cls(c, t[2])) return 0;
        if (!wr__coll_keep(cm, cm->obst_v[i], cm->obst_f[j])) return 0;
        v[0] = i;
        v[1] = t[0];
        v[2] = t[1];
        v[3] = t[2];
    } else {
        const int32_t *a = cm->edges + 2 * i, *b = cm->edges + 2 * j;
        int32_t a0 = wr__coll_cls(c, a[0]), a1 = wr__coll_cls(c, a[1]), b0 = wr__coll_cls(c, b[0]), b1 = wr__coll_cls(c, b[1]);
        if (a0 == b0 || a0 == b1 || a1 == b0 || a1 == b1) return 0;
        if (!wr__coll_keep(cm, cm->obst_e[i], cm->obst_e[j])) return 0;
        v[0] = a[0];
        v[1] = a[1];
        v[2] = b[0];
        v[3] = b[1];
    }
    return 1;
}

static wr_status wr__coll_add_contact(wr__coll_ctx *c, int kind, int32_t i, int32_t j) {
    int32_t v[4], piece = 0;
    double x12[12], d, w[4];
    wr_contact_set *s = c->set;
    if (!wr__coll_pair(c->cm, kind, c->ma[i], c->mb[j], v)) return WR_OK;
    wr__coll_gather(c->x, v, x12);
    d = sqrt(kind == WR_CONTACT_PT
                 ? wr_collision_point_triangle_dist2(x12, x12 + 3, x12 + 6, x12 + 9, NULL, NULL, w, &piece)
                 : wr_collision_edge_edge_dist2(x12, x12 + 3, x12 + 6, x12 + 9, NULL, NULL, w, &piece));
    if (!(d < c->dhat)) return WR_OK;
    if (!(d > 0.0))
        return wr_fail(c->diag, WR_ERR_GEOMETRY, v[0], "collision: %s pair (%d %d %d %d) touches (distance 0)",
                       kind == WR_CONTACT_PT ? "vertex-triangle" : "edge-edge", (int)v[0], (int)v[1], (int)v[2],
                       (int)v[3]);
    if (s->n == s->cap) {
        int32_t nc = s->cap ? 2 * s->cap : 64;
        wr_contact *nn = (wr_contact *)wr_realloc_array(s->c, (size_t)nc, sizeof(wr_contact));
        if (!nn) return wr_fail(c->diag, WR_ERR_NOMEM, -1, "collision: out of memory (%d contacts)", (int)s->n);
        s->c = nn;
        s->cap = nc;
    }
    s->c[s->n].kind = kind;
    memcpy(s->c[s->n].v, v, sizeof v);
    memcpy(s->c[s->n].w, w, sizeof w);
    s->c[s->n].piece = piece;
    s->c[s->n].d = d;
    s->n++;
    if (d < s->min_distance) s->min_distance = d;
    return WR_OK;
}

static wr_status wr__coll_pt_contact(void *u, int32_t i, int32_t j) {
    return wr__coll_add_contact((wr__coll_ctx *)u, WR_CONTACT_PT, i, j);
}
static wr_status wr__coll_ee_contact(void *u, int32_t i, int32_t j) {
    return wr__coll_add_contact((wr__coll_ctx *)u, WR_CONTACT_EE, i, j);
}

/* Every candidate pair of ON PAIRS from the six trees (ON THE BROAD PHASE): cloth vertices against
 * cloth faces (self) and obstacle faces, obstacle vertices against cloth faces, cloth edges among
 * themselves (self) and against obstacle edges. Obstacle–obstacle pairs are never visited. */
static wr_status wr__coll_query(wr_collision_mesh *cm, wr__coll_ctx *c, wr_bvh_pair_fn pt, wr_bvh_pair_fn ee,
                                wr_diag *diag) {
    static const int pairs[5][3] = {{0, 2, 0}, {0, 5, 0}, {3, 2, 0}, {1, 1, 1}, {1, 4, 1}};
    int q;
    wr_status st;
    for (q = 0; q < 5; ++q) {
        int a = pairs[q][0], b = pairs[q][1];
        if (!cm->self && a < 3 && b < 3) continue; /* a cloth–cloth pair */
        c->ma = cm->ids[a];
        c->mb = cm->ids[b];
        st = a == b ? wr_bvh_self_pairs(&cm->tree[a], ee, c, diag)
                    : wr_bvh_pairs(&cm->tree[a], &cm->tree[b], pairs[q][2] ? ee : pt, c, diag);
        if (st != WR_OK) return st;
    }
    return WR_OK;
}

WRDEF void wr_contact_set_free(wr_contact_set *set) {
    if (!set) return;
    wr_free(set->c);
    memset(set, 0, sizeof *set);
}

WRDEF wr_status wr_collision_contacts(wr_collision_mesh *cm, const double *x, double dhat, wr_contact_set *set,
                                      wr_diag *diag) {
    wr__coll_ctx c;
    wr_status st;
    if (!cm || !x || !set || !cm->obst_v) return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "collision: NULL argument");
    if (!(dhat > 0.0) || !wr__coll_finite(dhat))
        return wr_fail(diag, WR_ERR_DOMAIN, -1, "collision: dhat %g m must be > 0", dhat);
    /* ON REPEATED QUERIES: the same question again, nothing in between, no rebuild due */
    if (cm->cvalid && set == cm->cset && set->c == cm->cbuf && set->n == cm->cn && dhat == cm->cdhat &&
        cm->queries == cm->cqueries && cm->queries % WR__COLL_REBUILD != 0 &&
        !memcmp(x, cm->cx, sizeof(double) * 3 * (size_t)cm->nv)) {
        cm->cqueries = ++cm->queries;
        return WR_OK;
    }
    cm->cvalid = 0;
    set->n = 0;
    set->min_distance = HUGE_VAL;
    /* boxes grown by d̂/2 each: two primitives closer than d̂ have overlapping boxes */
    if ((st = wr__coll_trees(cm, x, NULL, 0.5 * dhat, diag)) != WR_OK) return st;
    memset(&c, 0, sizeof c);
    c.cm = cm;
    c.x = x;
    c.dhat = dhat;
    c.set = set;
    c.diag = diag;
    if ((st = wr__coll_query(cm, &c, wr__coll_pt_contact, wr__coll_ee_contact, diag)) != WR_OK) return st;
    if (!cm->cx) cm->cx = (double *)wr_alloc_array(3 * (size_t)(cm->nv > 0 ? cm->nv : 1), sizeof(double));
    if (cm->cx) { /* out of memory: no record, every call queries (a cache, not needed for correctness) */
        memcpy(cm->cx, x, sizeof(double) * 3 * (size_t)cm->nv);
        cm->cdhat = dhat;
        cm->cset = set;
        cm->cbuf = set->c;
        cm->cn = set->n;
        cm->cqueries = cm->queries;
        cm->cvalid = 1;
    }
    return WR_OK;
}

WRDEF wr_status wr_collision_contact_energy(const wr_contact_set *set, const double *x, double dhat, double kappa,
                                            int32_t project_spd, double *E, double *grad, const wr_hess_sink *sink,
                                            wr_diag *diag) {
    int32_t q, i, j;
    double sum = 0.0;
    if (!set || !x) return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "contact energy: NULL set or x");
    if (!(dhat > 0.0) || !(kappa >= 0.0) || !wr__coll_finite(dhat + kappa))
        return wr_fail(diag, WR_ERR_DOMAIN, -1, "contact energy: dhat %g m must be > 0, kappa %g >= 0", dhat, kappa);
    for (q = 0; q < set->n; ++q) {
        const wr_contact *ct = set->c + q;
        double x12[12], gs[12], Hs[144], gd[12], Hd[144], s, d, b1, b2, e;
        wr__coll_gather(x, ct->v, x12);
        s = ct->kind == WR_CONTACT_PT
                ? wr_collision_point_triangle_dist2(x12, x12 + 3, x12 + 6, x12 + 9, gs, sink ? Hs : NULL, NULL, NULL)
                : wr_collision_edge_edge_dist2(x12, x12 + 3, x12 + 6, x12 + 9, gs, sink ? Hs : NULL, NULL, NULL);
        if (!(s > 0.0))
            return wr_fail(diag, WR_ERR_GEOMETRY, q, "contact energy: contact %d (vertices %d %d %d %d) has distance 0",
                           (int)q, (int)ct->v[0], (int)ct->v[1], (int)ct->v[2], (int)ct->v[3]);
        d = wr_collision_distance_from_dist2(12, s, gs, sink ? Hs : NULL, gd, sink ? Hd : NULL);
        e = wr_collision_barrier(d, dhat, kappa, &b1, &b2);
        if (e == 0.0 && b1 == 0.0) continue; /* d >= d̂ since detection */
        sum += e;
        if (grad)
            for (i = 0; i < 4; ++i)
                for (j = 0; j < 3; ++j) grad[3 * ct->v[i] + j] += b1 * gd[3 * i + j];
        if (sink) {
            double K[144];
            wr_status rs;
            for (i = 0; i < 12; ++i)
                for (j = 0; j < 12; ++j) K[12 * i + j] = b2 * gd[i] * gd[j] + b1 * Hd[12 * i + j];
            if (project_spd) wr_dense_project_spd(12, K, 0.0);
            rs = sink->add(sink->user, 4, ct->v, K);
            if (rs != WR_OK) return wr_fail(diag, rs, q, "contact energy: sink rejected contact %d", (int)q);
        }
    }
    if (E) *E = sum;
    return WR_OK;
}

/* ACCD of the pair (PT: vertex i, face j; EE: edge i, edge j; mesh-wide ids) if ON PAIRS keeps it */
static wr_status wr__coll_ccd_ids(wr__coll_ctx *c, int kind, int32_t i, int32_t j) {
    int32_t v[4];
    double x12[12], d12[12], toi;
    if (!wr__coll_pair(c->cm, kind, i, j, v)) return WR_OK;
    wr__coll_gather(c->x, v, x12);
    wr__coll_gather(c->dx, v, d12);
    if (c->stats) c->stats->candidates++;
    if (wr_collision_accd((wr_contact_kind)kind, x12, d12, WR_COLLISION_CCD_KEEP, c->alpha, 0, &toi) &&
        toi < c->alpha) {
        c->alpha = toi;
        if (c->stats) {
            c->stats->hits++;
            c->stats->worst_kind = kind;
            memcpy(c->stats->worst_v, v, sizeof v);
        }
    }
    return WR_OK;
}

static wr_status wr__coll_ccd(wr__coll_ctx *c, int kind, int32_t i, int32_t j) {
    return wr__coll_ccd_ids(c, kind, c->ma[i], c->mb[j]);
}

static wr_status wr__coll_pt_ccd(void *u, int32_t i, int32_t j) { return wr__coll_ccd((wr__coll_ctx *)u, 0, i, j); }
static wr_status wr__coll_ee_ccd(void *u, int32_t i, int32_t j) { return wr__coll_ccd((wr__coll_ctx *)u, 1, i, j); }

static void wr__coll_stats_init(wr_collision_ccd_stats *stats) {
    if (!stats) return;
    memset(stats, 0, sizeof *stats);
    stats->worst_kind = -1;
    stats->worst_v[0] = stats->worst_v[1] = stats->worst_v[2] = stats->worst_v[3] = -1;
}

WRDEF wr_status wr_collision_max_step(wr_collision_mesh *cm, const double *x, const double *dx, double *alpha,
                                      wr_collision_ccd_stats *stats, wr_diag *diag) {
    wr__coll_ctx c;
    wr_status st;
    if (!cm || !x || !dx || !alpha || !cm->obst_v)
        return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "collision step: NULL argument");
    *alpha = 1.0;
    wr__coll_stats_init(stats);
    if ((st = wr__coll_trees(cm, x, dx, 0.0, diag)) != WR_OK) return st;
    memset(&c, 0, sizeof c);
    c.cm = cm;
    c.x = x;
    c.dx = dx;
    c.diag = diag;
    c.alpha = 1.0;
    c.stats = stats;
    if ((st = wr__coll_query(cm, &c, wr__coll_pt_ccd, wr__coll_ee_ccd, diag)) != WR_OK) return st;
    *alpha = c.alpha;
    return WR_OK;
}

/* ---- local CCD (ON LOCAL CCD) ---- */

/* Vertex → incident edges and faces (CSR; edge e as e, face f as ne + f), built once per mesh. */
static wr_status wr__coll_incidence(wr_collision_mesh *cm, wr_diag *diag) {
    int32_t v, i, k, n = 2 * cm->ne + 3 * cm->nf;
    if (cm->inc_start) return WR_OK;
    cm->inc_start = (int32_t *)wr_calloc_array((size_t)cm->nv + 1, sizeof(int32_t));
    cm->inc = (int32_t *)wr_alloc_array((size_t)(n > 0 ? n : 1), sizeof(int32_t));
    if (!cm->inc_start || !cm->inc) {
        wr_free(cm->inc_start), wr_free(cm->inc);
        cm->inc_start = cm->inc = NULL;
        return wr_fail(diag, WR_ERR_NOMEM, -1, "collision: out of memory (incidence of %d vertices)", (int)cm->nv);
    }
    for (i = 0; i < 2 * cm->ne; ++i) cm->inc_start[cm->edges[i] + 1]++;
    for (i = 0; i < 3 * cm->nf; ++i) cm->inc_start[cm->faces[i] + 1]++;
    for (v = 0; v < cm->nv; ++v) cm->inc_start[v + 1] += cm->inc_start[v];
    for (i = 0; i < cm->ne; ++i)
        for (k = 0; k < 2; ++k) cm->inc[cm->inc_start[cm->edges[2 * i + k]]++] = i;
    for (i = 0; i < cm->nf; ++i)
        for (k = 0; k < 3; ++k) cm->inc[cm->inc_start[cm->faces[3 * i + k]]++] = cm->ne + i;
    for (v = cm->nv; v > 0; --v) cm->inc_start[v] = cm->inc_start[v - 1]; /* the fill moved each start to its end */
    cm->inc_start[0] = 0;
    return WR_OK;
}

WRDEF wr_status wr_collision_mesh_bound(wr_collision_mesh *cm, const double *x, const double *vbox, wr_diag *diag) {
    int32_t v, i, k;
    int t;
    wr_status st;
    if (!cm || !x || !vbox || !cm->obst_v) return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "collision bound: NULL argument");
    for (v = 0; v < cm->nv; ++v)
        for (i = 0; i < 3; ++i) {
            double lo = vbox[6 * v + i], hi = vbox[6 * v + 3 + i], p = x[3 * v + i];
            if (!wr__coll_finite(lo) || !wr__coll_finite(hi) || !(lo <= p && p <= hi))
                return wr_fail(diag, WR_ERR_DOMAIN, v, "collision bound: vertex %d: %g outside its box [%g, %g] (axis %d)",
                               (int)v, p, lo, hi, (int)i);
        }
    if ((st = wr__coll_incidence(cm, diag)) != WR_OK) return st;
    wr_free(cm->lbox); /* unbound until every tree is built */
    cm->lbox = NULL;
    if (!cm->lmark) cm->lmark = (uint8_t *)wr_calloc_array((size_t)cm->nv, 1);
    if (!cm->lmark) return wr_fail(diag, WR_ERR_NOMEM, -1, "collision bound: out of memory");
    for (t = 0; t < 6; ++t) {
        int32_t n = cm->nids[t], which = t % 3;
        for (i = 0; i < n; ++i) { /* a primitive's box: the union of its vertices' boxes */
            int32_t g = cm->ids[t][i], a;
            const int32_t *vs = which == 0 ? &cm->ids[t][i] : (which == 1 ? cm->edges + 2 * g : cm->faces + 3 * g);
            double *bx = cm->boxes + 6 * i;
            memcpy(bx, vbox + 6 * vs[0], 6 * sizeof(double));
            for (k = 1; k <= which; ++k)
                for (a = 0; a < 3; ++a) {
                    bx[a] = fmin(bx[a], vbox[6 * vs[k] + a]);
                    bx[3 + a] = fmax(bx[3 + a], vbox[6 * vs[k] + 3 + a]);
                }
        }
        wr_bvh_free(&cm->ltree[t]);
        if ((st = wr_bvh_build(&cm->ltree[t], n, cm->boxes, diag)) != WR_OK) return st;
    }
    if (!(cm->lbox = (double *)wr_alloc_array(6 * (size_t)cm->nv, sizeof(double))))
        return wr_fail(diag, WR_ERR_NOMEM, -1, "collision bound: out of memory");
    memcpy(cm->lbox, vbox, 6 * sizeof(double) * (size_t)cm->nv);
    return WR_OK;
}

/* One moving primitive a (kind 0 vertex, 1 edge, 2 face) and its swept box, against tree t. */
typedef struct wr__coll_local {
    wr__coll_ctx c;
    int32_t a;
    int kind, t;
    double abox[6];
} wr__coll_local;

/* A bound-tree candidate b of the moving primitive: skipped when another visit owns the pair (a
 * moving vertex's own visit owns its PT pairs, the smaller id a pair of moving edges), else
 * wr_collision_max_step's own test: swept boxes without padding, then the pair's ACCD. */
static wr_status wr__coll_local_fn(void *u, int32_t i) {
    wr__coll_local *L = (wr__coll_local *)u;
    wr_collision_mesh *cm = L->c.cm;
    int which = L->t % 3, k, moving = 0;
    int32_t b = cm->ids[L->t][i];
    const int32_t *vs = which == 0 ? &cm->ids[L->t][i] : (which == 1 ? cm->edges + 2 * b : cm->faces + 3 * b);
    double bb[6];
    for (k = 0; k <= which; ++k) {
        if (cm->lmark[vs[k]]) moving = 1;
        else if (L->c.dx[3 * vs[k]] != 0.0 || L->c.dx[3 * vs[k] + 1] != 0.0 || L->c.dx[3 * vs[k] + 2] != 0.0)
            return wr_fail(L->c.diag, WR_ERR_INVALID_ARG, vs[k], "collision step: vertex %d moves but is not listed",
                           (int)vs[k]);
    }
    if ((L->kind == 2 && moving) || (L->kind == 1 && (b == L->a || (moving && b < L->a)))) return WR_OK;
    wr__coll_box(L->c.x, L->c.dx, vs, which + 1, 0.0, bb);
    if (!wr__bvh_overlap(L->abox, bb)) return WR_OK;
    if (L->kind == 0) return wr__coll_ccd_ids(&L->c, WR_CONTACT_PT, L->a, b);
    if (L->kind == 2) return wr__coll_ccd_ids(&L->c, WR_CONTACT_PT, b, L->a);
    /* the order of wr__coll_query: the cloth edge first, two cloth edges by id */
    if (cm->obst_e[L->a] == cm->obst_e[b])
        return wr__coll_ccd_ids(&L->c, WR_CONTACT_EE, L->a < b ? L->a : b, L->a < b ? b : L->a);
    return cm->obst_e[L->a] ? wr__coll_ccd_ids(&L->c, WR_CONTACT_EE, b, L->a)
                            : wr__coll_ccd_ids(&L->c, WR_CONTACT_EE, L->a, b);
}

/* The moving primitive (kind, id a, vertices vs[0..n)) against the trees of its partners: vertices
 * against faces, edges against edges, faces against vertices (cloth and obstacle trees, as ON PAIRS
 * allows). */
static wr_status wr__coll_local_query(wr__coll_local *L, int kind, int32_t a, const int32_t *vs, int n, wr_diag *diag) {
    static const int partner[3][2] = {{2, 5}, {1, 4}, {0, 3}};
    wr_collision_mesh *cm = L->c.cm;
    int oa = kind == 0 ? cm->obst_v[a] : (kind == 1 ? cm->obst_e[a] : cm->obst_f[a]), s;
    wr_status st;
    wr__coll_box(L->c.x, L->c.dx, vs, n, 0.0, L->abox);
    L->a = a;
    L->kind = kind;
    for (s = 0; s < 2; ++s) {
        L->t = partner[kind][s];
        if (!wr__coll_keep(cm, oa, L->t >= 3)) continue;
        if ((st = wr_bvh_box_query(&cm->ltree[L->t], L->abox, wr__coll_local_fn, L, diag)) != WR_OK) return st;
    }
    return WR_OK;
}

/* Moving vertex u and the incident edges and faces whose first moving corner it is. */
static wr_status wr__coll_local_vertex(wr__coll_local *L, int32_t u, wr_diag *diag) {
    wr_collision_mesh *cm = L->c.cm;
    int32_t c, k;
    wr_status st = wr__coll_local_query(L, 0, u, &u, 1, diag);
    for (c = cm->inc_start[u]; c < cm->inc_start[u + 1] && st == WR_OK; ++c) {
        int32_t id = cm->inc[c], edge = id < cm->ne, a = edge ? id : id - cm->ne, n = edge ? 2 : 3;
        const int32_t *vs = edge ? cm->edges + 2 * a : cm->faces + 3 * a;
        for (k = 0; !cm->lmark[vs[k]]; ++k) continue; /* u itself is marked: the loop ends */
        if (vs[k] == u) st = wr__coll_local_query(L, edge ? 1 : 2, a, vs, n, diag);
    }
    return st;
}

/* Marks moving[0..nm) in cm->lmark, checking each (ON LOCAL CCD); *nmarked gets how many were marked. */
static wr_status wr__coll_local_mark(wr_collision_mesh *cm, const double *x, const double *dx, int32_t nm,
                                     const int32_t *moving, int32_t *nmarked, wr_diag *diag) {
    int32_t k, i;
    for (*nmarked = 0, k = 0; k < nm; ++k) {
        int32_t v = moving[k];
        if (v < 0 || v >= cm->nv || cm->lmark[v])
            return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "collision step: moving[%d] = %d %s", (int)k, (int)v,
                           v < 0 || v >= cm->nv ? "out of range" : "listed twice");
        for (i = 0; i < 3; ++i) {
            double p = x[3 * v + i], q = p + dx[3 * v + i], lo = cm->lbox[6 * v + i], hi = cm->lbox[6 * v + 3 + i];
            if (!wr__coll_finite(p) || !wr__coll_finite(q) || !(lo <= p && p <= hi && lo <= q && q <= hi))
                return wr_fail(diag, WR_ERR_DOMAIN, v, "collision step: vertex %d leaves its bound box (axis %d)", (int)v,
                               (int)i);
        }
        cm->lmark[v] = 1;
        (*nmarked)++;
    }
    return WR_OK;
}

WRDEF wr_status wr_collision_max_step_local(wr_collision_mesh *cm, const double *x, const double *dx, int32_t nm,
                                            const int32_t *moving, double *alpha, wr_collision_ccd_stats *stats,
                                            wr_diag *diag) {
    wr__coll_local L;
    int32_t k, marked;
    wr_status st;
    if (!cm || !x || !dx || !alpha || !cm->obst_v || nm < 0 || (nm > 0 && !moving))
        return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "collision step: NULL or negative argument");
    if (!cm->lbox) return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "collision step: local trees not bound (wr_collision_mesh_bound)");
    *alpha = 1.0;
    wr__coll_stats_init(stats);
    memset(&L, 0, sizeof L);
    L.c.cm = cm;
    L.c.x = x;
    L.c.dx = dx;
    L.c.diag = diag;
    L.c.alpha = 1.0;
    L.c.stats = stats;
    st = wr__coll_local_mark(cm, x, dx, nm, moving, &marked, diag);
    for (k = 0; k < nm && st == WR_OK; ++k) st = wr__coll_local_vertex(&L, moving[k], diag);
    for (k = 0; k < marked; ++k) cm->lmark[moving[k]] = 0;
    if (st == WR_OK) *alpha = L.c.alpha;
    return st;
}

/* ---- exact whole-mesh checks ---- */
typedef struct wr__coll_isect {
    const int32_t *fa, *fb;
    const double *xa, *xb;
    int32_t count, first[2];
} wr__coll_isect;

static void wr__coll_tri(const double *x, const int32_t *t, double *T) {
    int k;
    for (k = 0; k < 3; ++k) memcpy(T + 3 * k, x + 3 * t[k], 3 * sizeof(double));
}

static void wr__coll_isect_hit(wr__coll_isect *c, int32_t i, int32_t j) {
    if (c->count == 0) {
        c->first[0] = i;
        c->first[1] = j;
    }
    c->count++;
}

static wr_status wr__coll_self_isect(void *u, int32_t i, int32_t j) {
    wr__coll_isect *c = (wr__coll_isect *)u;
    const int32_t *ta = c->fa + 3 * i, *tb = c->fa + 3 * j;
    int32_t ra[3], rb[3], ns = 0, ka[3], kb[3], k, l, n;
    double A[9], B[9];
    for (k = 0; k < 3; ++k)
        for (l = 0; l < 3; ++l)
            if (ta[k] == tb[l]) {
                ka[ns] = k;
                kb[ns] = l;
                ++ns;
            }
    if (ns == 0) {
        wr__coll_tri(c->xa, ta, A);
        wr__coll_tri(c->xa, tb, B);
        if (wr_collision_triangle_triangle_intersect(A, B)) wr__coll_isect_hit(c, i, j);
        return WR_OK;
    }
    if (ns == 3) { /* duplicate face: coincident triangles */
        wr__coll_isect_hit(c, i, j);
        return WR_OK;
    }
    /* shared vertices first, in the same order in both, then the rest */
    for (k = 0; k < ns; ++k) {
        ra[k] = ta[ka[k]];
        rb[k] = tb[kb[k]];
    }
    n = ns;
    for (k = 0; k < 3; ++k)
        if (k != ka[0] && (ns < 2 || k != ka[1])) ra[n++] = ta[k];
    n = ns;
    for (k = 0; k < 3; ++k)
        if (k != kb[0] && (ns < 2 || k != kb[1])) rb[n++] = tb[k];
    wr__coll_tri(c->xa, ra, A);
    wr__coll_tri(c->xa, rb, B);
    if (wr__tri_tri_adjacent(A, B, ns)) wr__coll_isect_hit(c, i, j);
    return WR_OK;
}

static wr_status wr__coll_pair_isect(void *u, int32_t i, int32_t j) {
    wr__coll_isect *c = (wr__coll_isect *)u;
    double A[9], B[9];
    wr__coll_tri(c->xa, c->fa + 3 * i, A);
    wr__coll_tri(c->xb, c->fb + 3 * j, B);
    if (wr_collision_triangle_triangle_intersect(A, B)) wr__coll_isect_hit(c, i, j);
    return WR_OK;
}

static wr_status wr__coll_face_tree(wr_bvh *t, int32_t nv, const double *x, int32_t nf, const int32_t *f,
                                    wr_diag *diag);

WRDEF wr_status wr_collision_mesh_self_intersects(wr_collision_mesh *cm, const double *x, int32_t *count,
                                                  int32_t first[2], wr_diag *diag) {
    wr__coll_isect c;
    wr_status st;
    int32_t i;
    if (!cm || !x || !count || !cm->faces) return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "self-intersection: NULL argument");
    for (i = 0; i < 3 * cm->nv; ++i)
        if (!wr__coll_finite(x[i]))
            return wr_fail(diag, WR_ERR_DOMAIN, i / 3, "self-intersection: vertex %d is not finite", (int)(i / 3));
    {   /* every face pair, obstacle ones included: a tree of its own */
        wr_bvh t;
        memset(&t, 0, sizeof t);
        if ((st = wr__coll_face_tree(&t, cm->nv, x, cm->nf, cm->faces, diag)) != WR_OK) return st;
        memset(&c, 0, sizeof c);
        c.fa = cm->faces;
        c.xa = x;
        c.first[0] = c.first[1] = -1;
        st = wr_bvh_self_pairs(&t, wr__coll_self_isect, &c, diag);
        wr_bvh_free(&t);
        if (st != WR_OK) return st;
    }
    *count = c.count;
    if (first) {
        first[0] = c.first[0];
        first[1] = c.first[1];
    }
    return WR_OK;
}

static wr_status wr__coll_face_tree(wr_bvh *t, int32_t nv, const double *x, int32_t nf, const int32_t *f,
                                    wr_diag *diag) {
    double *bx = (double *)wr_alloc_array((size_t)6 * (size_t)(nf > 0 ? nf : 1), sizeof(double));
    wr_status st;
    int32_t i, k;
    if (!bx) return wr_fail(diag, WR_ERR_NOMEM, -1, "mesh intersection: out of memory");
    for (i = 0; i < nf; ++i)
        for (k = 0; k < 3; ++k)
            if (f[3 * i + k] < 0 || f[3 * i + k] >= nv) {
                wr_free(bx);
                return wr_fail(diag, WR_ERR_TOPOLOGY, i, "mesh intersection: face %d corner %d out of range", (int)i, k);
            }
    for (i = 0; i < 3 * nv; ++i)
        if (!wr__coll_finite(x[i])) {
            wr_free(bx);
            return wr_fail(diag, WR_ERR_DOMAIN, i / 3, "mesh intersection: vertex %d is not finite", (int)(i / 3));
        }
    for (i = 0; i < nf; ++i) wr__coll_box(x, NULL, f + 3 * i, 3, 0.0, bx + 6 * i);
    st = wr_bvh_build(t, nf, bx, diag);
    wr_free(bx);
    return st;
}

WRDEF wr_status wr_collision_meshes_intersect(int32_t nva, const double *xa, int32_t nfa, const int32_t *fa,
                                              int32_t nvb, const double *xb, int32_t nfb, const int32_t *fb,
                                              int32_t *count, wr_diag *diag) {
    wr_bvh ta, tb;
    wr__coll_isect c;
    wr_status st;
    if (!xa || !xb || !count || (nfa > 0 && !fa) || (nfb > 0 && !fb) || nfa < 0 || nfb < 0)
        return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "mesh intersection: NULL or negative argument");
    memset(&ta, 0, sizeof ta);
    memset(&tb, 0, sizeof tb);
    if ((st = wr__coll_face_tree(&ta, nva, xa, nfa, fa, diag)) != WR_OK) return st;
    if ((st = wr__coll_face_tree(&tb, nvb, xb, nfb, fb, diag)) != WR_OK) {
        wr_bvh_free(&ta);
        return st;
    }
    memset(&c, 0, sizeof c);
    c.fa = fa;
    c.fb = fb;
    c.xa = xa;
    c.xb = xb;
    st = wr_bvh_pairs(&ta, &tb, wr__coll_pair_isect, &c, diag);
    wr_bvh_free(&ta);
    wr_bvh_free(&tb);
    if (st == WR_OK) *count = c.count;
    return st;
}

#ifdef __cplusplus
}
#endif
#endif /* WRINKLE_COLLISION_IMPLEMENTATION_DONE */
#endif /* WRINKLE_IMPLEMENTATION */
