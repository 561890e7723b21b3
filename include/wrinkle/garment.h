/* wrinkle/garment.h — a garment on a body: the mesher's flat pattern mesh placed panel by panel in
 * 3D (a rigid transform, or a wrap onto a cylinder around a body part), its seams pulled shut by
 * the dynamic simulator's sewing springs over the first frames, then welded into one mesh on which
 * the simulation continues; shirring lines and quilt stitches gathered by elastic threads.
 * wrinkle v0.1.0 — MIT licence (see LICENSE). Needs core.h, mesh.h, shell.h, dynamics.h and
 * collision.h; otherwise libc and libm.
 *
 * Style3D's figures (Sec. 5, Figs. 15 and 19) are garments worn by a body; a garment is sewn the
 * way pattern-based simulators do it — flat panels placed around the
 * body, seams drawn together by springs, the sewn seams then treated as ordinary cloth.
 *
 * API (create/free pair: wr_garment_sim_create → wr_garment_sim_free)
 *   wr_garment_place_point(pl, u, v, x)           one pattern point (u, v) [m] → 3D point x [m]
 *   wr_garment_placement_check(pl, index, diag)   finite values, radius > 0, a known kind
 *   wr_garment_place(mesh, pl, n_pl, diag)        every vertex of the unsewn pattern mesh placed by
 *                                                 its panel's placement (mesh.pos overwritten)
 *   wr_garment_sewing_pairs(mesh, pairs, seam, n, out, out_seam, n_out, diag)  the mesher's seam
 *                                                 pairs → the dynamics' sewing pairs (checked,
 *                                                 duplicates dropped; caller frees with wr_free)
 *   wr_garment_line_chain(mesh, segs, n_segs, xy, n, out, n_out, diag)   the mesh vertices on a
 *                                                 pattern polyline (a shirring line, a quilt
 *                                                 stitch), in order along it, from the mesher's
 *                                                 constraint segments (caller frees with wr_free)
 *   wr_garment_line_split(xy, n, s, out, n_out, diag)   the polyline with a vertex at every stitch
 *                                                 of stitch length s (ON GATHERING; mesh the
 *                                                 split line so the stitches are mesh vertices)
 *   wr_garment_sim_create(gs, garment, shell, dyn, desc, diag)   place, pair, shell, simulator
 *   wr_garment_sim_step(gs, stats, diag)          one frame: sewing, gathering and gravity
 *                                                 schedules, step, seam gap, weld
 *   wr_garment_gravity_scale(desc, t)             the gravity schedule's factor at time t (ON HOLDING)
 *   wr_garment_sim_thread_length(gs, line, &now, &rest)   a gathered line's current length and its
 *                                                 thread's final rest length ρ·l [m]
 *   wr_garment_sim_weld(gs, diag)                 weld now (called by _step once the gap is small)
 *   wr_garment_sim_seam_gap(gs, seam)             largest gap of the seam's pairs (−1: all) [m]
 *   wr_garment_sim_unsewn_positions(gs, out)      current positions on the pattern mesh's vertices
 *   wr_garment_sim_free(gs)                       free and zero (safe on a zeroed gs)
 *
 * EXAMPLE (a tube of two 0.3 × 0.2 m panels wrapped onto a 0.1 m cylinder, sewn shut, welded)
 *     wr_mesh a, b, m;  wr_garment_placement pl[2];  wr_garment gm;  wr_garment_sim gs;
 *     wr_shell_desc sd;  wr_dyn_desc dd;  wr_garment_desc gd;  wr_dyn_stats fs;  wr_diag d;
 *     int32_t pairs[2 * 14], i, f;  double w = 0.3;
 *     if (wr_mesh_rectangle(&a, w, 0.2, 10, 6, &d) != WR_OK) { puts(d.message); return 1; }
 *     if (wr_mesh_rectangle(&b, w, 0.2, 10, 6, &d) != WR_OK) { puts(d.message); return 1; }
 *     if (wr_garment_example_join(&m, &a, &b, &d) != WR_OK) { puts(d.message); return 1; }  // panel 0, 1
 *     for (i = 0; i <= 6; ++i) {                          // a's right edge to b's left, b's right to a's left
 *         pairs[4 * i] = i * 11 + 10;  pairs[4 * i + 1] = a.nv + i * 11;
 *         pairs[4 * i + 2] = a.nv + i * 11 + 10;  pairs[4 * i + 3] = i * 11;
 *     }
 *     memset(pl, 0, sizeof pl);  memset(&gm, 0, sizeof gm);
 *     memset(&sd, 0, sizeof sd);  memset(&dd, 0, sizeof dd);  memset(&gd, 0, sizeof gd);
 *     for (i = 0; i < 2; ++i) {                           // each panel half way round, 4 cm gaps
 *         pl[i].kind = WR_GARMENT_CYLINDER;  pl[i].origin[0] = w / 2;
 *         pl[i].cylinder.radius = (2 * w + 0.08) / (2 * 3.141592653589793);
 *         pl[i].cylinder.angle = i * 3.141592653589793;
 *     }
 *     gm.pattern = &m;  gm.seam_pairs = pairs;  gm.n_seam_pairs = 14;  gm.placements = pl;  gm.n_placements = 2;
 *     sd.young = 1e5;  sd.poisson = 0.3;  sd.thickness = 5e-4;  sd.density = 300;
 *     if (wr_garment_sim_create(&gs, &gm, &sd, &dd, &gd, &d) != WR_OK) { puts(d.message); return 1; }
 *     for (f = 0; f < 12 && !gs.welded; ++f)
 *         if (wr_garment_sim_step(&gs, &fs, &d) != WR_OK) { puts(d.message); return 1; }
 *     printf("welded %d at frame %d: %d -> %d vertices\n", gs.welded, gs.weld_frame, gs.nv0, gs.mesh.nv);
 *     wr_garment_sim_free(&gs);  wr_mesh_free(&a);  wr_mesh_free(&b);  wr_mesh_free(&m);
 *
 * ON PLACEMENT
 *   A placement maps the panel's pattern coordinates (u, v) [m] (the mesher's rest positions) to
 *   3D; (u0, v0) = origin is the pattern point that goes to the anchor.
 *   RIGID:    x = R(axis, angle) (u − u0, v − v0, 0) + translate (Rodrigues; zero axis: R = I).
 *             An isometry of the whole plane: every length and angle is kept.
 *   CYLINDER: θ = angle + (u − u0)/r,  x = point + (v − v0) â + r (cos θ ê1 + sin θ ê2), with
 *             â = axis/|axis| (zero: +z), ê1 = the part of ref orthogonal to â, normalised (zero or
 *             parallel to â: the world axis least aligned with â), ê2 = â × ê1. The pattern's u runs
 *             round the cylinder (counter-clockwise seen from +â), v along it. The map is the
 *             developable unrolling of the cylinder, an isometry onto its image: a u-line keeps its
 *             length as arc length (its chords are 2r sin(Δu/2r)), a v-line stays straight, every
 *             point is at distance r from the axis. A counter-clockwise (mesher) face keeps its
 *             normal pointing away from the axis (ê_θ × â = radial), so panels wrapped round a body
 *             face outwards and sewn panels are consistently oriented. For the mannequin (body.h)
 *             wr_body_parts gives each limb's and the torso's axis (p → q): point = p, axis = q − p.
 *
 * ON SEWING (the schedule, and why)
 *   The seams are the dynamics' zero-rest-length sewing springs k/2 ‖x_a − x_b‖² (dynamics.h) on
 *   the mesher's seam pairs. The stiffness doubles every frame, from k_0 = WR_DYN_SEW_FACTOR m̄/dt²
 *   (dynamics.h's default: against inertia alone an isolated pair closes within a frame) up to
 *   k_full = WR_GARMENT_SEW_MEMBRANE_FACTOR · E h/(1 − ν²) (the shell's membrane stiffness [N/m]):
 *     - starting at k_full snaps the seam shut in one frame and the panel recoils (the frame
 *       after the snap needs many Newton iterations and can halve its step); doubling from k_0
 *       closes the gaps over several frames without a halving and with less edge strain. The
 *       doubling is the default because it is the robust one; start_stiffness = stiffness is the
 *       fast one (both measured on the A-line skirt: docs/garments.md, "What was tried");
 *     - k_full in units of the membrane's own stiffness makes the residual gap of a seam under a
 *       membrane tension T = ε E h (spread over pair spacing s) T s/k = ε s/100: below 0.01 mm for
 *       10 % strain at 1 cm spacing, far below the weld tolerance, whatever the mesh resolution.
 *   desc.stiffness and desc.start_stiffness override the two ends.
 *   Cloth self-contact stays ON while the seams are open (as the dynamics desc asks). A seam
 *   pair's two vertices are distinct primitives, so the IPC barrier between them and the triangles
 *   next to them resists the last millimetre (d < d̂), but the barrier's force κ d̂²/d (small d)
 *   balances the spring's k d only at d ≈ d̂ √(κ/k), microns once k has grown to k_full ≫ κ, so
 *   the gap closes below d̂/2 within a few frames of growth (docs/garments.md, seam gap per frame).
 *   Switching self-contact off until the weld (desc.no_self_while_sewing = 1) closes the gap
 *   faster but lets the panels pass through each other where they meet edge on, and the weld then
 *   refuses the crossed mesh (docs/garments.md, "What was tried").
 *
 * ON WELDING (when, and what is carried over)
 *   At the end of the first frame whose largest seam gap is below desc.weld_tol (default
 *   WR_GARMENT_WELD_FRACTION · d̂ = 0.5 mm at the default d̂ = 1 mm) the pattern mesh is welded
 *   (mesh.h wr_mesh_weld: each face keeps its own pattern corners, so every panel keeps its flat
 *   rest shape). Why that tolerance: merging a pair moves each of its vertices by at most half the
 *   gap, d̂/4, a small part of the barrier's margin to a body, while a tighter default would sit
 *   below what the Newton stop resolves — a step is accepted once no vertex moves more than h ·
 *   velocity_tol (0.33 mm at the defaults), so gaps much below that stall (docs/garments.md, "What
 *   was tried"). A merged vertex gets the mass-weighted mean position and velocity of its class
 *   (mass and momentum are kept), pins are OR-ed, the shell and the simulator are rebuilt on the
 *   welded mesh (same materials and contact settings, no sewing springs), bodies keep their current
 *   positions, and time goes on. The midpoint is not always feasible: sewing springs at full
 *   stiffness press a seam line onto the body far inside d̂, and on a small faceted body (the 0.25
 *   mannequin of validate_sim_garments, d̂ = 0.25 mm) a body ridge within half the gap of the seam
 *   line put midpoint-welded faces through it (weld_mid_hits reports how many body triangle pairs a
 *   plain midpoint merge would meet). So the merge is done as a motion and certified the way a
 *   Newton step is (collision.h ON CCD): the copies of each seam vertex move along straight lines
 *   from their own positions, which the simulator keeps intersection-free, to one common point, in
 *   one collision mesh of the unwelded cloth and the bodies whose vertex classes are the welded
 *   vertices (collision.h ON PAIRS: the copies are meant to meet, so the pairs that become adjacent
 *   are not contacts). A move that CCD cuts short is not made. First every class moves to its
 *   midpoint m at once; when CCD stops that, class by class, in up to WR_GARMENT_WELD_SWEEPS
 *   sweeps, to the first of m, m + t (x_u − m) (x_u a copy's own position, t = 1/2, then 1) whose
 *   move completes (weld_moved counts those left off m; momentum is kept, the position is no longer
 *   the mass mean there). CCD checks every vertex–triangle and edge–edge pair, cloth against body
 *   and, when the welded sim has self-contact, cloth against cloth, so no merge move sweeps a face
 *   through the body or the garment: a triangle pair can only start to intersect through such a
 *   contact. Each move is certified locally (collision.h ON LOCAL CCD: every position a copy can
 *   take lies in the box of its class's start positions and m, so the collision mesh is bound to
 *   those boxes once and a move costs the CCD of the primitives round its copies: the same alpha as
 *   a whole-mesh wr_collision_max_step, at a cost that does not grow with the garment). What CCD
 *   cannot see is a pair that shares a merged vertex (two faces folding over each other at the
 *   seam), so the welded mesh is then checked exactly against every body and, with self-contact,
 *   against itself. A class no move can merge (weld_blocked) or an intersection found (weld_left,
 *   triangle pairs) is WR_ERR_GEOMETRY from wr_garment_sim_weld (the barriers would lock it in) and
 *   the sim is left unwelded; wr_garment_sim_step then defers the weld (weld_deferred counts it,
 *   sewing goes on, the gap keeps closing) and retries next frame, so a weld never introduces an
 *   intersection. After desc.max_time (default WR_GARMENT_MAX_SEW_TIME) the step is
 *   WR_ERR_NOT_CONVERGED: naming the widest seam and its gap (item = seam) when a seam is still
 *   open, or (item = -1) saying that every seam is closed to the tolerance but the weld is still
 *   refused, with the last refusal's weld_blocked and weld_left. desc.no_weld = 1 keeps the springs
 *   for the whole run instead.
 *
 * ON GATHERING (shirring Style3D Sec. 4.2.2, quilt stitches Sec. 4.2.5; the paper only meshes them)
 *   A gathered line (wr_garment_line: the pattern-mesh vertices along it, wr_garment_line_chain)
 *   is an elastic thread stitched to every desc.stitch_edges-th vertex of the chain (default
 *   WR_GARMENT_STITCH_EDGES = 2): one dynamics.h thread segment per stitch, tension only, final
 *   rest length ρ × the pattern length of the chain between its two stitches, axial stiffness
 *   EA = E_sh · A; the thread does not slide through its stitches, as shirring elastic is
 *   stitched down. Why not a stitch at every vertex: the thread segment and the fabric's own mesh
 *   edge would then join the same two vertices, so the edge could only shorten by crushing the
 *   triangles beside it in their plane (the thread against the membrane E h, a 1D balance that
 *   tests/test_garment.c checks in closed form: at the Table 1 stiffnesses the line stays within
 *   a few % of its length). With a stitch every other vertex, the vertex between two stitches
 *   folds out of the plane and the line gathers as a pucker at the mesh's finest scale; the
 *   fabric beside the line is gathered with it and wrinkles at the wavelength its bending
 *   selects.
 *   E_sh [Pa]: the paper adds it to E (y_sh = B/(E + E_sh) in Eq. 4), so it is a modulus of the
 *   same kind as E, N/m² (docs/pattern-format.md). We read it as the thread's Young's modulus and
 *   give the thread the cross-section A = h² (desc.thread_area overrides): a thread as thick as
 *   the fabric it gathers (0.25–0.4 mm for the Table 1 fabrics, the size of a sewing thread). Why
 *   h²: the pattern gives no thread size, h is the only length at the line that belongs to the
 *   material rather than to the mesh, so the thread is the same at 9 mm and at 2.5 mm (a
 *   cross-section tied to the edge length would make the gathering depend on the resolution it
 *   is meant to test). line.modulus 0 (the down coat's E_sh = 0: a quilt stitch is a plain,
 *   not an elastic, thread) takes the fabric's E instead.
 *   Schedule: the rest length ramps linearly from the pattern length to ρ times it over the first
 *   desc.gather_time seconds (default WR_GARMENT_GATHER_TIME; the rest at frame k uses the frame's
 *   end time), like the sewing stiffness doubling: a thread at ρ from the start loads the flat
 *   fabric with its full compression in one step (docs/garments.md: the Newton iterations and
 *   halvings measured both ways). desc.gather_immediate = 1 starts at ρ.
 *   Quilts: the stitch lines are gathered the same way (E_sh, ρ of the quilt). The down pressure p
 *   is NOT modelled as a load: the paper's p is a dimensionless exponent of its transition rule
 *   (m' = 2^p m, L_w' = L_w^(2^-p)), not a pressure in Pa, and a single quilted layer encloses no
 *   volume, so a normal pressure on it would be a net force blowing the panel like a sail rather
 *   than puffing its packs (that needs the two layers and the down between them).
 *   At the weld the threads are carried over to the welded vertices (a segment whose two ends
 *   merge is dropped).
 *   Stitch length (line.stitch_length s [m] > 0, a length of the pattern, not of the mesh): the
 *   stitches are the points at arc length k·s along the line's pattern polyline (line.xy),
 *   k = 1, 2, ... while k·s <= l − s/2 (l its length), plus the chain's two ends, so the last
 *   stitch interval is in [s/2, 3s/2). The thread segment between two stitches then has the
 *   pattern length s (the last one its remainder) and rest ρ·s on every mesh, and the pucker a
 *   stitch interval makes is the same length of fabric at every resolution. The stitch points
 *   must be mesh vertices: wr_garment_line_split inserts them into the polyline, and the mesher
 *   keeps every input vertex of a constraint line as a mesh vertex (mesher.h: "a break at every
 *   input vertex"), so meshing the split line puts a vertex exactly there whatever the sizing;
 *   a stitch point with no chain vertex within WR_GARMENT_LINE_TOL is WR_ERR_GEOMETRY (item =
 *   line). A line end the mesher trimmed off the boundary (mesher.h ON THE CONSTRAINTS) keeps
 *   its chain end as the first / last stitch, so only that end interval depends on the sizing.
 *   Why s = 0 keeps the mesh-edge stitches (desc.stitch_edges) rather than a default length:
 *   the pattern gives no stitch length, any default would be a guess at a garment scale, and
 *   every gathered result measured so far (the dress, the coat, Fig. 14) was made with the
 *   edge rule. A stitch interval needs at least two mesh edges (one free vertex to fold out,
 *   see above), so s should be at least twice the line's coarsest edge on every mesh compared.
 *
 * ON HOLDING (gravity held off while the garment is sewn and gathered)
 *   A garment whose waist must be gathered onto the body before it can hang there (a shirred
 *   skirt: its ungathered waist is wider than the body by 1/ρ) falls off the body if gravity acts
 *   during the gathering: in the default 1/3 s ramp it would drop ~0.5 m. desc.gravity_delay [s]
 *   holds gravity off until then and desc.gravity_ramp [s] brings it in linearly after that: the
 *   dynamics' gravity for the frame ending at t is g · wr_garment_gravity_scale(desc, t), the
 *   scale 0 for t <= delay, (t − delay)/ramp up to 1 after it (1 at once for ramp 0). This is
 *   how pattern-based tools dress a body (sew and gather with gravity off, then let it hang); the
 *   body contact, sewing and threads act throughout. Both 0 (the default): full gravity from the
 *   first frame, unchanged behaviour. The barrier stiffness is set from the full g at create (and
 *   at the weld's rebuild), so the schedule does not change the contact model.
 *
 * ON ERRORS (wr_status + wr_diag, item = the offending index)
 *   WR_ERR_INVALID_ARG: a placement that is not finite, a radius <= 0, an unknown kind (item =
 *   placement); fewer placements than panels (item = first panel without one); a pattern mesh
 *   without rest coordinates or with a vertex in two panels (item = vertex: pass the UNSEWN mesh,
 *   mesher desc.sew = 0); a seam pair outside the mesh or joining a vertex to itself (item = pair).
 *   WR_ERR_GEOMETRY: a placed panel that intersects a body (item = panel), a weld that would
 *   intersect. WR_ERR_NOT_CONVERGED: see ON WELDING. Errors of wr_shell_create and wr_dyn_create
 *   pass through.
 *
 * ON OWNERSHIP AND UNITS
 *   wr_garment is a view: the pattern mesh and the arrays are the caller's and only read during
 *   create. The shell and dynamics descs are copied, but the arrays they point to (dynamics:
 *   bodies, analytic obstacles; fixed is copied) must stay valid until wr_garment_sim_free, since
 *   the simulator is rebuilt from them at the weld. The garment sim owns its mesh, shell, state
 *   (x, v) and simulator. SI units: m, s, N/m, kg/m³.
 *
 * ON THREADS
 *   A garment sim is used by one thread at a time; several may run concurrently.
 */
#ifndef WRINKLE_GARMENT_H
#define WRINKLE_GARMENT_H

#include "core.h"
#include "mesh.h"
#include "shell.h"
#include "dynamics.h"
#include "collision.h"

#ifdef __cplusplus
extern "C" {
#endif

/* sewing stiffness at full strength, × the membrane stiffness E h/(1 − ν²) [N/m] (ON SEWING) */
#define WR_GARMENT_SEW_MEMBRANE_FACTOR 100.0
/* the stiffness grows by this factor per frame from start_stiffness to stiffness (ON SEWING) */
#define WR_GARMENT_SEW_GROWTH 2.0
/* weld when every seam pair is closer than this fraction of the barrier thickness d̂ (ON WELDING) */
#define WR_GARMENT_WELD_FRACTION 0.5
/* sweeps of the feasible merge over the merged vertices whose faces meet a body (ON WELDING) */
#define WR_GARMENT_WELD_SWEEPS 4
/* give up sewing after this simulated time [s]: 30 frames at 1/30 s (the skirt examples weld
 * after 7–12 frames, docs/garments.md) */
#define WR_GARMENT_MAX_SEW_TIME 1.0
/* gathering threads reach their rest length ρ·l after this time [s] (ON GATHERING): 10 frames */
#define WR_GARMENT_GATHER_TIME (1.0 / 3.0)
/* mesh edges of a gathered line per thread stitch (ON GATHERING) */
#define WR_GARMENT_STITCH_EDGES 2
/* a mesh vertex lies on a pattern polyline when within this distance of it [m]: the mesher maps
 * its constraint points back from the stretched space, exact to rounding (1e-16 m here) */
#define WR_GARMENT_LINE_TOL 1e-9

typedef enum wr_garment_wrap {
    WR_GARMENT_RIGID = 0,   /* ON PLACEMENT */
    WR_GARMENT_CYLINDER = 1 /* ON PLACEMENT */
} wr_garment_wrap;

typedef struct wr_garment_rigid {
    double axis[3];      /* rotation axis (zero: no rotation) */
    double angle;        /* [rad] */
    double translate[3]; /* [m] */
} wr_garment_rigid;

typedef struct wr_garment_cylinder {
    double point[3]; /* a point on the axis: where the origin's height v0 goes [m] */
    double axis[3];  /* axis direction (zero: +z) */
    double ref[3];   /* direction of θ = 0 (zero: the world axis least aligned with the axis) */
    double radius;   /* [m], > 0 */
    double angle;    /* θ of the origin [rad] */
} wr_garment_cylinder;

typedef struct wr_garment_placement {
    wr_garment_wrap kind;
    double origin[2]; /* the pattern point (u0, v0) that goes to the anchor [m] */
    wr_garment_rigid rigid;
    wr_garment_cylinder cylinder;
} wr_garment_placement;

/* The garment to simulate (a view; see ON OWNERSHIP). pattern: the mesher's UNSEWN mesh (rest per
 * vertex, face_panel; face_panel may be NULL with one placement). seam_pairs: n_seam_pairs × 2
 * vertex ids (mesher result.seam_pairs); seam_pair_seam: the seam of each pair (may be NULL: all
 * seam 0). placements: one per panel. */
/* A gathered line (ON GATHERING): vertices (n_vertices >= 2) of the pattern mesh in order along
 * it (wr_garment_line_chain), rho in (0, 1], modulus E_sh [Pa] (0: the shell's Young's modulus).
 * stitch_length [m] >= 0 (0: a stitch every desc.stitch_edges mesh edges); when > 0, xy (n_xy >= 2
 * points [m]) is the line's pattern polyline, split by wr_garment_line_split before meshing. */
typedef struct wr_garment_line {
    const int32_t *vertices;
    int32_t n_vertices;
    double rho;
    double modulus;
    double stitch_length;
    const double *xy;
    int32_t n_xy;
} wr_garment_line;

typedef struct wr_garment {
    const wr_mesh *pattern;
    const int32_t *seam_pairs;
    const int32_t *seam_pair_seam;
    int32_t n_seam_pairs;
    const wr_garment_placement *placements;
    int32_t n_placements;
    const wr_garment_line *lines; /* gathered lines (may be NULL / 0) */
    int32_t n_lines;
} wr_garment;

/* Defaults (zero means default): stiffness → WR_GARMENT_SEW_MEMBRANE_FACTOR · E h/(1 − ν²);
 * start_stiffness → WR_DYN_SEW_FACTOR · m̄/dt² (capped at stiffness); weld_tol →
 * WR_GARMENT_WELD_FRACTION · d̂; max_time → WR_GARMENT_MAX_SEW_TIME; no_weld 0;
 * no_self_while_sewing 0; thread_area → h² (the shell's thickness squared); gather_time →
 * WR_GARMENT_GATHER_TIME; gather_immediate 0; stitch_edges → WR_GARMENT_STITCH_EDGES (ON GATHERING);
 * gravity_delay 0, gravity_ramp 0: full gravity from the start (ON HOLDING; negative or not finite is
 * WR_ERR_INVALID_ARG). */
typedef struct wr_garment_desc {
    double stiffness;       /* [N/m] */
    double start_stiffness; /* [N/m] */
    double weld_tol;        /* [m] */
    double max_time;        /* [s] */
    int32_t no_weld;
    int32_t no_self_while_sewing; /* 1: cloth self-contact off until the weld (ON SEWING) */
    double thread_area;     /* gathering thread cross-section [m²] */
    double gather_time;     /* [s] */
    int32_t gather_immediate; /* 1: threads at ρ·l from the first frame */
    int32_t stitch_edges;   /* mesh edges per stitch, >= 1 (lines without a stitch_length) */
    double gravity_delay;   /* [s] gravity off until this time (ON HOLDING; 0: from the start) */
    double gravity_ramp;    /* [s] then ramped in over this time (ON HOLDING; 0: at once) */
} wr_garment_desc;

typedef struct wr_garment_sim {
    wr_mesh mesh;        /* the simulated mesh: the placed pattern mesh, then the welded one */
    wr_shell shell;
    wr_dyn dyn;
    wr_dyn_state state;  /* state.x, state.v point at x, v below */
    double *x, *v;       /* mesh.nv*3, owned [m], [m/s] */
    int32_t nv0;         /* vertices of the pattern (unsewn) mesh */
    int32_t *vmap;       /* nv0: pattern vertex → vertex of `mesh` (identity before the weld) */
    int32_t *pairs, *pair_seam; /* the sewing pairs (pattern vertex ids) and their seams */
    int32_t n_pairs, n_seams;
    int32_t welded, weld_frame; /* 1 once welded, and the frame after which it happened */
    double weld_gap;     /* the largest seam gap when welded [m] */
    int32_t weld_mid_hits; /* last weld: body triangle pairs a midpoint merge would meet (ON WELDING) */
    int32_t weld_moved;  /* last weld: merged vertices moved off the midpoint to stay feasible */
    int32_t weld_blocked; /* last weld attempt: merged vertices no CCD-safe move could merge */
    int32_t weld_left;   /* last weld attempt: triangle pairs (body + self) its merge left intersecting */
    int32_t weld_deferred; /* frames whose weld was refused as intersecting and deferred */
    double gap;          /* the largest seam gap at the end of the last frame [m] (0 after the weld) */
    double sew_k;        /* the sewing stiffness of the last frame [N/m] */
    double k_start, k_full;
    int32_t frame;       /* frames done */
    wr_shell_desc shell_desc; /* copies the rebuild uses */
    wr_dyn_desc dyn_desc;
    wr_garment_desc desc;
    uint8_t *fixed0;     /* nv0 pins of the pattern mesh (copy), or NULL */
    /* gathering threads (ON GATHERING): segments over pattern vertices, their pattern lengths,
     * ρ, EA [N], their line, and their index in dyn's thread list (-1: dropped at the weld) */
    int32_t *thr_seg, *thr_line, *thr_dyn;
    double *thr_len, *thr_rho, *thr_axial;
    int32_t n_thr, n_lines;
    double gather;       /* the schedule's fraction of 1 − ρ applied in the last frame */
    double gravity_scale; /* the gravity schedule's factor in the last frame (ON HOLDING) */
} wr_garment_sim;

WRDEF void wr_garment_place_point(const wr_garment_placement *pl, double u, double v, double x[3]);
WRDEF wr_status wr_garment_placement_check(const wr_garment_placement *pl, int32_t index, wr_diag *diag);
WRDEF wr_status wr_garment_place(wr_mesh *m, const wr_garment_placement *pl, int32_t n_pl, wr_diag *diag);
WRDEF wr_status wr_garment_sewing_pairs(const wr_mesh *m, const int32_t *pairs, const int32_t *seam, int32_t n,
                                        int32_t **out, int32_t **out_seam, int32_t *n_out, wr_diag *diag);
/* The vertices of mesh m (rest coordinates) along the pattern polyline xy (n points [m]): the
 * segments among segs (n_segs × 2, the mesher's constraint_segments) whose two ends and midpoint
 * lie within WR_GARMENT_LINE_TOL of the polyline, chained from the end nearest xy's first point.
 * *out (wr_free) gets *n_out >= 2 vertices. WR_ERR_GEOMETRY (item = -1) when fewer than one
 * segment lies on the line or the segments on it do not form one open chain. */
WRDEF wr_status wr_garment_line_chain(const wr_mesh *m, const int32_t *segs, int32_t n_segs, const double *xy, int32_t n,
                                      int32_t **out, int32_t *n_out, wr_diag *diag);
/* The polyline xy (n >= 2 points [m]) with a point inserted at arc length k·s for k = 1, 2, ...
 * while k·s <= l − s/2 (ON GATHERING: the stitch points of stitch length s > 0 [m]; a point within
 * WR_GARMENT_LINE_TOL of an input vertex is that vertex). *out (wr_free) gets *n_out points, the
 * input vertices kept. WR_ERR_INVALID_ARG: s not finite or <= 0, n < 2, a point not finite. */
WRDEF wr_status wr_garment_line_split(const double *xy, int32_t n, double s, double **out, int32_t *n_out, wr_diag *diag);
/* Joins two meshes into one with face_panel 0 (a's faces) and 1 (b's), b's vertices after a's;
 * rest coordinates kept (a helper for hand-made two-panel garments and the EXAMPLE). */
WRDEF wr_status wr_garment_example_join(wr_mesh *out, const wr_mesh *a, const wr_mesh *b, wr_diag *diag);
WRDEF wr_status wr_garment_sim_create(wr_garment_sim *gs, const wr_garment *g, const wr_shell_desc *shell,
                                      const wr_dyn_desc *dyn, const wr_garment_desc *desc, wr_diag *diag);
WRDEF wr_status wr_garment_sim_step(wr_garment_sim *gs, wr_dyn_stats *stats, wr_diag *diag);
WRDEF wr_status wr_garment_sim_weld(wr_garment_sim *gs, wr_diag *diag);
WRDEF double wr_garment_sim_seam_gap(const wr_garment_sim *gs, int32_t seam);
/* Line `line`'s current length along its thread (*now) and the thread's final rest length ρ·l
 * (*rest) [m]; both 0 for a line index out of range. */
WRDEF void wr_garment_sim_thread_length(const wr_garment_sim *gs, int32_t line, double *now, double *rest);
/* ON HOLDING: 0 for t <= desc->gravity_delay, then (t − delay)/gravity_ramp capped at 1 (1 after
 * the delay when the ramp is 0); 1 for a NULL desc. */
WRDEF double wr_garment_gravity_scale(const wr_garment_desc *desc, double t);
WRDEF void wr_garment_sim_unsewn_positions(const wr_garment_sim *gs, double *out);
WRDEF void wr_garment_sim_free(wr_garment_sim *gs);

#ifdef __cplusplus
}
#endif
#endif /* WRINKLE_GARMENT_H */

/* ============================================================================================ */
#ifdef WRINKLE_IMPLEMENTATION
#ifndef WRINKLE_GARMENT_IMPLEMENTATION_DONE
#define WRINKLE_GARMENT_IMPLEMENTATION_DONE

#include <math.h>
#include <string.h>

#ifdef __cplusplus
extern "C" {
#endif

/* ---- placement (ON PLACEMENT) ---------------------------------------------------------------- */

static void wr__gar_unit(const double a[3], const double fallback[3], double out[3]) {
    double l = sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
    int i;
    for (i = 0; i < 3; ++i) out[i] = l > 0.0 ? a[i] / l : fallback[i];
}

/* ê1, ê2 of a cylinder with unit axis ax (ON PLACEMENT) */
static void wr__gar_frame(const double ax[3], const double ref[3], double e1[3], double e2[3]) {
    double r[3], d, l;
    int i, k = 0;
    for (i = 0; i < 3; ++i) r[i] = ref[i];
    d = r[0] * ax[0] + r[1] * ax[1] + r[2] * ax[2];
    for (i = 0; i < 3; ++i) r[i] -= d * ax[i];
    l = sqrt(r[0] * r[0] + r[1] * r[1] + r[2] * r[2]);
    if (!(l > 1e-12 * (1.0 + fabs(d)))) { /* no usable ref: the world axis least aligned with ax */
        for (i = 1; i < 3; ++i)
            if (fabs(ax[i]) < fabs(ax[k])) k = i;
        for (i = 0; i < 3; ++i) r[i] = (i == k ? 1.0 : 0.0) - ax[k] * ax[i];
        l = sqrt(r[0] * r[0] + r[1] * r[1] + r[2] * r[2]);
    }
    for (i = 0; i < 3; ++i) e1[i] = r[i] / l;
    e2[0] = ax[1] * e1[2] - ax[2] * e1[1];
    e2[1] = ax[2] * e1[0] - ax[0] * e1[2];
    e2[2] = ax[0] * e1[1] - ax[1] * e1[0];
}

WRDEF void wr_garment_place_point(const wr_garment_placement *pl, double u, double v, double x[3]) {
    static const double z[3] = {0.0, 0.0, 1.0};
    double du = u - pl->origin[0], dv = v - pl->origin[1];
    int i;
    if (pl->kind == WR_GARMENT_CYLINDER) {
        const wr_garment_cylinder *c = &pl->cylinder;
        double ax[3], e1[3], e2[3], th = c->angle + du / c->radius, cs = cos(th), sn = sin(th);
        wr__gar_unit(c->axis, z, ax);
        wr__gar_frame(ax, c->ref, e1, e2);
        for (i = 0; i < 3; ++i) x[i] = c->point[i] + dv * ax[i] + c->radius * (cs * e1[i] + sn * e2[i]);
    } else {
        const wr_garment_rigid *r = &pl->rigid;
        double l = sqrt(r->axis[0] * r->axis[0] + r->axis[1] * r->axis[1] + r->axis[2] * r->axis[2]);
        double p[3], a[3], cs, sn, kp[3], kd;
        p[0] = du, p[1] = dv, p[2] = 0.0;
        if (l > 0.0 && r->angle != 0.0) { /* Rodrigues: p cosφ + (k×p) sinφ + k (k·p)(1 − cosφ) */
            for (i = 0; i < 3; ++i) a[i] = r->axis[i] / l;
            cs = cos(r->angle);
            sn = sin(r->angle);
            kp[0] = a[1] * p[2] - a[2] * p[1];
            kp[1] = a[2] * p[0] - a[0] * p[2];
            kp[2] = a[0] * p[1] - a[1] * p[0];
            kd = a[0] * p[0] + a[1] * p[1] + a[2] * p[2];
            for (i = 0; i < 3; ++i) x[i] = p[i] * cs + kp[i] * sn + a[i] * kd * (1.0 - cs) + r->translate[i];
        } else {
            for (i = 0; i < 3; ++i) x[i] = p[i] + r->translate[i];
        }
    }
}

WRDEF wr_status wr_garment_placement_check(const wr_garment_placement *pl, int32_t index, wr_diag *diag) {
    double s = pl ? pl->origin[0] + pl->origin[1] : 0.0;
    int i;
    if (!pl) return wr_fail(diag, WR_ERR_INVALID_ARG, index, "garment: placement %d is NULL", (int)index);
    for (i = 0; i < 3; ++i)
        s += pl->rigid.axis[i] + pl->rigid.translate[i] + pl->cylinder.point[i] + pl->cylinder.axis[i] + pl->cylinder.ref[i];
    s += pl->rigid.angle + pl->cylinder.angle + pl->cylinder.radius;
    if (s - s != 0.0) return wr_fail(diag, WR_ERR_INVALID_ARG, index, "garment: placement %d is not finite", (int)index);
    if ((int)pl->kind != WR_GARMENT_RIGID && (int)pl->kind != WR_GARMENT_CYLINDER)
        return wr_fail(diag, WR_ERR_INVALID_ARG, index, "garment: placement %d has unknown kind %d", (int)index, (int)pl->kind);
    if (pl->kind == WR_GARMENT_CYLINDER && !(pl->cylinder.radius > 0.0))
        return wr_fail(diag, WR_ERR_INVALID_ARG, index, "garment: placement %d: cylinder radius %g must be > 0", (int)index,
                       pl->cylinder.radius);
    return WR_OK;
}

/* Panel of every vertex (from face_panel); WR_ERR_INVALID_ARG for a vertex in two panels. */
static wr_status wr__gar_vertex_panels(const wr_mesh *m, int32_t *vp, wr_diag *diag) {
    int32_t f, k, v;
    for (v = 0; v < m->nv; ++v) vp[v] = -1;
    for (f = 0; f < m->nf; ++f)
        for (k = 0; k < 3; ++k) {
            int32_t p = m->face_panel ? m->face_panel[f] : 0, *q = vp + m->faces[3 * f + k];
            if (*q >= 0 && *q != p)
                return wr_fail(diag, WR_ERR_INVALID_ARG, m->faces[3 * f + k],
                               "garment: vertex %d lies in panels %d and %d: place the unsewn pattern mesh (mesher sew = 0)",
                               (int)m->faces[3 * f + k], (int)*q, (int)p);
            *q = p;
        }
    return WR_OK;
}

WRDEF wr_status wr_garment_place(wr_mesh *m, const wr_garment_placement *pl, int32_t n_pl, wr_diag *diag) {
    int32_t *vp, v, f;
    wr_status st = WR_OK;
    if (!m || !m->faces || !pl || n_pl < 1) return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "garment: NULL mesh or no placement");
    if (!m->rest)
        return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "garment: the pattern mesh has no rest (pattern) coordinates; "
                                                     "place the unsewn mesh (mesher sew = 0)");
    for (f = 0; f < n_pl; ++f)
        if ((st = wr_garment_placement_check(pl + f, f, diag)) != WR_OK) return st;
    for (f = 0; f < m->nf; ++f) {
        int32_t p = m->face_panel ? m->face_panel[f] : 0;
        if (p < 0 || p >= n_pl)
            return wr_fail(diag, WR_ERR_INVALID_ARG, p < 0 ? f : p, "garment: panel %d has no placement (%d given)", (int)p,
                           (int)n_pl);
    }
    vp = (int32_t *)wr_alloc_array((size_t)m->nv, sizeof(int32_t));
    if (!vp) return wr_fail(diag, WR_ERR_NOMEM, -1, "garment: out of memory");
    st = wr__gar_vertex_panels(m, vp, diag);
    for (v = 0; v < m->nv && st == WR_OK; ++v)
        if (vp[v] >= 0) wr_garment_place_point(pl + vp[v], m->rest[2 * v], m->rest[2 * v + 1], m->pos + 3 * v);
    wr_free(vp);
    return st;
}

WRDEF wr_status wr_garment_sewing_pairs(const wr_mesh *m, const int32_t *pairs, const int32_t *seam, int32_t n,
                                        int32_t **out, int32_t **out_seam, int32_t *n_out, wr_diag *diag) {
    int32_t k, j, no = 0, *o, *os;
    *out = *out_seam = NULL;
    *n_out = 0;
    if (n < 0 || (n > 0 && !pairs)) return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "garment: %d seam pairs, NULL array", (int)n);
    o = (int32_t *)wr_alloc_array(2 * (size_t)n + 2, sizeof(int32_t));
    os = (int32_t *)wr_alloc_array((size_t)n + 1, sizeof(int32_t));
    if (!o || !os) {
        wr_free(o);
        wr_free(os);
        return wr_fail(diag, WR_ERR_NOMEM, -1, "garment: out of memory");
    }
    for (k = 0; k < n; ++k) {
        int32_t a = pairs[2 * k], b = pairs[2 * k + 1], dup = 0;
        if (a < 0 || a >= m->nv || b < 0 || b >= m->nv || a == b) {
            wr_free(o);
            wr_free(os);
            return wr_fail(diag, WR_ERR_INVALID_ARG, k, "garment: seam pair %d (%d, %d) is outside [0, %d) or joins a vertex to itself",
                           (int)k, (int)a, (int)b, (int)m->nv);
        }
        /* a vertex where two seams meet is listed by both: one spring per unordered pair. Pairs of
         * one seam run along it, so a duplicate is among the recent ones only at seam junctions;
         * the quadratic scan is over the few thousand pairs of a garment at most. */
        for (j = 0; j < no && !dup; ++j)
            dup = (o[2 * j] == a && o[2 * j + 1] == b) || (o[2 * j] == b && o[2 * j + 1] == a);
        if (dup) continue;
        o[2 * no] = a;
        o[2 * no + 1] = b;
        os[no++] = seam ? seam[k] : 0;
    }
    *out = o;
    *out_seam = os;
    *n_out = no;
    return WR_OK;
}

WRDEF wr_status wr_garment_example_join(wr_mesh *out, const wr_mesh *a, const wr_mesh *b, wr_diag *diag) {
    int32_t nv = a->nv + b->nv, nf = a->nf + b->nf, i, *F = NULL, *fp = NULL;
    double *P = NULL, *R = NULL;
    wr_status st;
    memset(out, 0, sizeof *out);
    if (!a->rest || !b->rest) return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "garment: join needs rest coordinates");
    F = (int32_t *)wr_alloc_array(3 * (size_t)nf, sizeof(int32_t));
    fp = (int32_t *)wr_alloc_array((size_t)nf, sizeof(int32_t));
    P = (double *)wr_alloc_array(3 * (size_t)nv, sizeof(double));
    R = (double *)wr_alloc_array(2 * (size_t)nv, sizeof(double));
    if (!F || !fp || !P || !R) {
        st = wr_fail(diag, WR_ERR_NOMEM, -1, "garment: out of memory");
        goto done;
    }
    memcpy(P, a->pos, sizeof(double) * 3 * (size_t)a->nv);
    memcpy(P + 3 * a->nv, b->pos, sizeof(double) * 3 * (size_t)b->nv);
    memcpy(R, a->rest, sizeof(double) * 2 * (size_t)a->nv);
    memcpy(R + 2 * a->nv, b->rest, sizeof(double) * 2 * (size_t)b->nv);
    for (i = 0; i < 3 * a->nf; ++i) F[i] = a->faces[i];
    for (i = 0; i < 3 * b->nf; ++i) F[3 * a->nf + i] = b->faces[i] + a->nv;
    for (i = 0; i < nf; ++i) fp[i] = i < a->nf ? 0 : 1;
    st = wr_mesh_create(out, nv, P, R, nf, F, diag);
    if (st == WR_OK && (st = wr_mesh_set_face_panel(out, fp, diag)) != WR_OK) wr_mesh_free(out);
done:
    wr_free(F);
    wr_free(fp);
    wr_free(P);
    wr_free(R);
    return st;
}

/* ---- gathered lines (ON GATHERING) --------------------------------------------------------- */

/* distance from point p to the polyline xy (n points) */
static double wr__gar_poly_dist(const double *xy, int32_t n, const double p[2]) {
    double best = HUGE_VAL;
    int32_t i;
    for (i = 0; i + 1 < n; ++i) {
        const double *a = xy + 2 * i, *b = a + 2;
        double ux = b[0] - a[0], uy = b[1] - a[1], l2 = ux * ux + uy * uy, t = 0.0, dx, dy;
        if (l2 > 0.0) t = fmin(1.0, fmax(0.0, ((p[0] - a[0]) * ux + (p[1] - a[1]) * uy) / l2));
        dx = a[0] + t * ux - p[0];
        dy = a[1] + t * uy - p[1];
        best = fmin(best, sqrt(dx * dx + dy * dy));
    }
    return best;
}

WRDEF wr_status wr_garment_line_chain(const wr_mesh *m, const int32_t *segs, int32_t n_segs, const double *xy, int32_t n,
                                      int32_t **out, int32_t *n_out, wr_diag *diag) {
    int32_t *adj = NULL, *deg = NULL, *o = NULL, k, v, ends[2], n_ends = 0, n_on = 0, prev, cur, len = 0;
    wr_status st = WR_OK;
    *out = NULL;
    *n_out = 0;
    if (!m || !m->rest || !xy || n < 2 || (n_segs > 0 && !segs))
        return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "garment: line chain needs a mesh with rest coordinates and >= 2 points");
    adj = (int32_t *)wr_alloc_array(2 * (size_t)m->nv, sizeof(int32_t));
    deg = (int32_t *)wr_calloc_array((size_t)m->nv, sizeof(int32_t));
    o = (int32_t *)wr_alloc_array((size_t)m->nv, sizeof(int32_t));
    if (!adj || !deg || !o) {
        st = wr_fail(diag, WR_ERR_NOMEM, -1, "garment: out of memory");
        goto done;
    }
    for (k = 0; k < n_segs; ++k) {
        int32_t a = segs[2 * k], b = segs[2 * k + 1];
        double mid[2];
        if (a < 0 || b < 0 || a >= m->nv || b >= m->nv || a == b) continue;
        mid[0] = 0.5 * (m->rest[2 * a] + m->rest[2 * b]);
        mid[1] = 0.5 * (m->rest[2 * a + 1] + m->rest[2 * b + 1]);
        if (wr__gar_poly_dist(xy, n, m->rest + 2 * a) > WR_GARMENT_LINE_TOL ||
            wr__gar_poly_dist(xy, n, m->rest + 2 * b) > WR_GARMENT_LINE_TOL || wr__gar_poly_dist(xy, n, mid) > WR_GARMENT_LINE_TOL)
            continue;
        if (deg[a] >= 2 || deg[b] >= 2) {
            st = wr_fail(diag, WR_ERR_GEOMETRY, -1, "garment: the mesh segments on the line branch at vertex %d",
                         (int)(deg[a] >= 2 ? a : b));
            goto done;
        }
        adj[2 * a + deg[a]++] = b;
        adj[2 * b + deg[b]++] = a;
        n_on++;
    }
    for (v = 0; v < m->nv; ++v)
        if (deg[v] == 1) {
            if (n_ends == 2) {
                st = wr_fail(diag, WR_ERR_GEOMETRY, -1, "garment: the mesh segments on the line form more than one piece");
                goto done;
            }
            ends[n_ends++] = v;
        }
    if (n_on < 1 || n_ends != 2) {
        st = wr_fail(diag, WR_ERR_GEOMETRY, -1, "garment: %d mesh segments on the line, not one open chain (is it a mesher constraint?)",
                     (int)n_on);
        goto done;
    }
    {   /* start from the end nearer the polyline's first point */
        double d0 = hypot(m->rest[2 * ends[0]] - xy[0], m->rest[2 * ends[0] + 1] - xy[1]);
        double d1 = hypot(m->rest[2 * ends[1]] - xy[0], m->rest[2 * ends[1] + 1] - xy[1]);
        cur = d1 < d0 ? ends[1] : ends[0];
    }
    prev = -1;
    while (cur >= 0) {
        int32_t next = -1;
        o[len++] = cur;
        for (k = 0; k < deg[cur]; ++k)
            if (adj[2 * cur + k] != prev) next = adj[2 * cur + k];
        prev = cur;
        cur = next;
    }
    if (len != n_on + 1) {
        st = wr_fail(diag, WR_ERR_GEOMETRY, -1, "garment: the mesh segments on the line form more than one piece");
        goto done;
    }
    *out = o;
    *n_out = len;
    o = NULL;
done:
    wr_free(adj);
    wr_free(deg);
    wr_free(o);
    return st;
}

/* the polyline xy's length (n points) */
static double wr__gar_poly_len(const double *xy, int32_t n) {
    double l = 0.0;
    int32_t i;
    for (i = 0; i + 1 < n; ++i) l += hypot(xy[2 * i + 2] - xy[2 * i], xy[2 * i + 3] - xy[2 * i + 1]);
    return l;
}

/* the point p at arc length t along the polyline xy (n >= 2 points), clamped to its ends */
static void wr__gar_poly_at(const double *xy, int32_t n, double t, double p[2]) {
    int32_t i;
    for (i = 0; i + 1 < n; ++i) {
        const double *a = xy + 2 * i, *b = a + 2;
        double l = hypot(b[0] - a[0], b[1] - a[1]), f;
        if (t > l && i + 2 < n) {
            t -= l;
            continue;
        }
        f = l > 0.0 ? fmin(1.0, fmax(0.0, t / l)) : 0.0;
        p[0] = a[0] + f * (b[0] - a[0]);
        p[1] = a[1] + f * (b[1] - a[1]);
        return;
    }
    p[0] = xy[0];
    p[1] = xy[1];
}

/* interior stitch points of stitch length s on a line of length l: k = 1..K with k·s <= l − s/2 */
static int32_t wr__gar_n_stitch(double l, double s) {
    double k = floor(l / s - 0.5 + 1e-9);
    return k > 0.0 ? (int32_t)fmin(k, 2e9) : 0;
}

WRDEF wr_status wr_garment_line_split(const double *xy, int32_t n, double s, double **out, int32_t *n_out, wr_diag *diag) {
    double l, acc = 0.0, *o;
    int32_t i, K, k = 1, m = 0;
    if (out) *out = NULL;
    if (n_out) *n_out = 0;
    if (!xy || !out || !n_out || n < 2 || !(s > 0.0) || !isfinite(s))
        return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "garment: line split needs >= 2 points and a finite stitch length > 0 (%d, %g m)",
                       (int)n, s);
    for (i = 0; i < 2 * n; ++i)
        if (!isfinite(xy[i])) return wr_fail(diag, WR_ERR_INVALID_ARG, i / 2, "garment: line point %d is not finite", (int)(i / 2));
    l = wr__gar_poly_len(xy, n);
    if (l / s > 1e6) return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "garment: stitch length %g m on a %g m line: over 1e6 stitches", s, l);
    K = wr__gar_n_stitch(l, s);
    o = (double *)wr_alloc_array((size_t)(n + K), 2 * sizeof(double));
    if (!o) return wr_fail(diag, WR_ERR_NOMEM, -1, "garment: out of memory");
    o[m++] = xy[0];
    o[m++] = xy[1];
    for (i = 0; i + 1 < n; ++i) {
        double end = acc + hypot(xy[2 * i + 2] - xy[2 * i], xy[2 * i + 3] - xy[2 * i + 1]);
        for (; k <= K && k * s < end - WR_GARMENT_LINE_TOL; ++k)
            if (k * s > acc + WR_GARMENT_LINE_TOL) {
                wr__gar_poly_at(xy, n, k * s, o + m);
                m += 2;
            }
        while (k <= K && k * s <= end + WR_GARMENT_LINE_TOL) ++k; /* the stitch is vertex i + 1 */
        o[m++] = xy[2 * i + 2];
        o[m++] = xy[2 * i + 3];
        acc = end;
    }
    *out = o;
    *n_out = m / 2;
    return WR_OK;
}

/* Chain indices idx (*n_idx of them, room for n_vertices) of line L's stitches (ON GATHERING):
 * every se-th vertex and the last, or with a stitch length the chain vertices at k·s along ln->xy
 * and the chain's two ends. */
static wr_status wr__gar_line_stitches(const wr_mesh *m, const wr_garment_line *ln, int32_t L, int32_t se, int32_t *idx,
                                       int32_t *n_idx, wr_diag *diag) {
    int32_t i, k, K, c = 1, n = 0;
    if (!(ln->stitch_length > 0.0)) {
        for (i = 0; i + 1 < ln->n_vertices; i += se) idx[n++] = i;
        idx[n++] = ln->n_vertices - 1;
        *n_idx = n;
        return WR_OK;
    }
    K = wr__gar_n_stitch(wr__gar_poly_len(ln->xy, ln->n_xy), ln->stitch_length);
    idx[n++] = 0;
    for (k = 1; k <= K; ++k) {
        double p[2];
        wr__gar_poly_at(ln->xy, ln->n_xy, k * ln->stitch_length, p);
        while (c < ln->n_vertices &&
               hypot(m->rest[2 * ln->vertices[c]] - p[0], m->rest[2 * ln->vertices[c] + 1] - p[1]) > WR_GARMENT_LINE_TOL)
            ++c;
        if (c >= ln->n_vertices)
            return wr_fail(diag, WR_ERR_GEOMETRY, L,
                           "garment: line %d has no mesh vertex at its stitch %d (%g m along it): mesh the line split at its "
                           "stitches (wr_garment_line_split)",
                           (int)L, (int)k, k * ln->stitch_length);
        if (c < ln->n_vertices - 1) idx[n++] = c++;
    }
    idx[n++] = ln->n_vertices - 1;
    *n_idx = n;
    return WR_OK;
}

/* Line L of the garment checked against the pattern mesh m (ON GATHERING). */
static wr_status wr__gar_line_check(const wr_mesh *m, const wr_garment_line *ln, int32_t L, wr_diag *diag) {
    int32_t i;
    if (ln->n_vertices < 2 || !ln->vertices || !(ln->rho > 0.0 && ln->rho <= 1.0) || !(ln->modulus >= 0.0) ||
        ln->modulus - ln->modulus != 0.0)
        return wr_fail(diag, WR_ERR_INVALID_ARG, L, "garment: line %d (%d vertices, rho %g, modulus %g) is invalid", (int)L,
                       (int)ln->n_vertices, ln->rho, ln->modulus);
    if (!(ln->stitch_length >= 0.0) || !isfinite(ln->stitch_length) || (ln->stitch_length > 0.0 && (!ln->xy || ln->n_xy < 2)))
        return wr_fail(diag, WR_ERR_INVALID_ARG, L,
                       "garment: line %d stitch length %g m is invalid (finite, >= 0; > 0 needs the line's polyline xy)", (int)L,
                       ln->stitch_length);
    for (i = 0; i < ln->n_vertices; ++i)
        if (ln->vertices[i] < 0 || ln->vertices[i] >= m->nv || (i > 0 && ln->vertices[i] == ln->vertices[i - 1]))
            return wr_fail(diag, WR_ERR_INVALID_ARG, L, "garment: line %d vertex %d (%d) is invalid", (int)L, (int)i,
                           (int)ln->vertices[i]);
    return WR_OK;
}

/* The threads of the garment's lines (ON GATHERING), checked against the pattern mesh. */
static wr_status wr__gar_threads(wr_garment_sim *gs, const wr_garment *g, wr_diag *diag) {
    const wr_mesh *m = g->pattern;
    double area = gs->desc.thread_area > 0.0 ? gs->desc.thread_area : gs->shell.thickness * gs->shell.thickness;
    int32_t L, i, n = 0, nmax = 0, n_idx = 0, *idx, se = gs->desc.stitch_edges > 0 ? gs->desc.stitch_edges : WR_GARMENT_STITCH_EDGES;
    wr_status st;
    if (g->n_lines > 0 && !g->lines) return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "garment: %d lines with a NULL array", (int)g->n_lines);
    for (L = 0; L < g->n_lines; ++L) {
        if ((st = wr__gar_line_check(m, g->lines + L, L, diag)) != WR_OK) return st;
        n += g->lines[L].n_vertices - 1; /* at most one segment per chain edge */
        if (g->lines[L].n_vertices > nmax) nmax = g->lines[L].n_vertices;
    }
    gs->n_lines = g->n_lines;
    if (n == 0) return WR_OK;
    gs->thr_seg = (int32_t *)wr_alloc_array(2 * (size_t)n, sizeof(int32_t));
    gs->thr_line = (int32_t *)wr_alloc_array((size_t)n, sizeof(int32_t));
    gs->thr_dyn = (int32_t *)wr_alloc_array((size_t)n, sizeof(int32_t));
    gs->thr_len = (double *)wr_alloc_array((size_t)n, sizeof(double));
    gs->thr_rho = (double *)wr_alloc_array((size_t)n, sizeof(double));
    gs->thr_axial = (double *)wr_alloc_array((size_t)n, sizeof(double));
    if (!gs->thr_seg || !gs->thr_line || !gs->thr_dyn || !gs->thr_len || !gs->thr_rho || !gs->thr_axial)
        return wr_fail(diag, WR_ERR_NOMEM, -1, "garment: out of memory (%d thread segments)", (int)n);
    idx = (int32_t *)wr_alloc_array((size_t)nmax, sizeof(int32_t));
    if (!idx) return wr_fail(diag, WR_ERR_NOMEM, -1, "garment: out of memory");
    for (L = 0, st = WR_OK; L < g->n_lines && st == WR_OK; ++L) {
        const wr_garment_line *ln = g->lines + L;
        double E = ln->modulus > 0.0 ? ln->modulus : gs->shell.young > 0.0 ? gs->shell.young : gs->shell_desc.young_warp;
        if ((st = wr__gar_line_stitches(m, ln, L, se, idx, &n_idx, diag)) != WR_OK) break;
        for (i = 0; i + 1 < n_idx; ++i) {
            int32_t j, e = idx[i + 1], a = ln->vertices[idx[i]], b = ln->vertices[e];
            int32_t s = gs->n_thr++;
            gs->thr_seg[2 * s] = a;
            gs->thr_seg[2 * s + 1] = b;
            gs->thr_line[s] = L;
            gs->thr_len[s] = 0.0; /* the pattern length of the chain between the two stitches */
            for (j = idx[i]; j < e; ++j) {
                const double *p = m->rest + 2 * ln->vertices[j], *q = m->rest + 2 * ln->vertices[j + 1];
                gs->thr_len[s] += hypot(p[0] - q[0], p[1] - q[1]);
            }
            gs->thr_rho[s] = ln->rho;
            gs->thr_axial[s] = E * area;
            if (!(gs->thr_len[s] > 0.0)) {
                st = wr_fail(diag, WR_ERR_INVALID_ARG, L, "garment: line %d has a zero-length edge at vertex %d", (int)L, (int)a);
                break;
            }
        }
    }
    wr_free(idx);
    return st;
}

/* rest length of thread segment s under the schedule's fraction gather (ON GATHERING) */
static double wr__gar_thread_rest(const wr_garment_sim *gs, int32_t s, double gather) {
    return gs->thr_len[s] * (1.0 - gather * (1.0 - gs->thr_rho[s]));
}

/* ---- the simulation (ON SEWING, ON WELDING) -------------------------------------------------- */

static void wr__gar_desc_defaults(wr_garment_desc *d) {
    if (!(d->max_time > 0.0)) d->max_time = WR_GARMENT_MAX_SEW_TIME;
}

/* Exact check of cloth positions x on mesh m against every body of the sim, faces restricted to
 * panel `panel` when >= 0; *hit = number of intersecting triangle pairs. */
static wr_status wr__gar_body_hits(const wr_dyn *sim, const wr_mesh *m, const double *x, int32_t panel, int32_t *hit,
                                   wr_diag *diag) {
    int32_t *F = NULL, nf = 0, f, k;
    wr_status st;
    *hit = 0;
    if (sim->nbf < 1) return WR_OK;
    F = (int32_t *)wr_alloc_array(3 * (size_t)m->nf, sizeof(int32_t));
    if (!F) return wr_fail(diag, WR_ERR_NOMEM, -1, "garment: out of memory");
    for (f = 0; f < m->nf; ++f) {
        if (panel >= 0 && (m->face_panel ? m->face_panel[f] : 0) != panel) continue;
        for (k = 0; k < 3; ++k) F[3 * nf + k] = m->faces[3 * f + k];
        nf++;
    }
    st = nf ? wr_collision_meshes_intersect(m->nv, x, nf, F, sim->nb, sim->body_x, sim->nbf, sim->body_faces, hit, diag)
            : WR_OK;
    wr_free(F);
    return st;
}

/* The simulator on gs->mesh/shell (sewing on before the weld, self-contact off then), with the
 * threads on the vertices vmap gives their pattern vertices (NULL: identity). */
static wr_status wr__gar_build(wr_garment_sim *gs, const uint8_t *fixed, const int32_t *vmap, wr_diag *diag) {
    wr_dyn_desc dd = gs->dyn_desc;
    int32_t *seg = NULL, s, n = 0;
    double *rest = NULL, *ax = NULL;
    wr_status st;
    dd.fixed = fixed;
    if (!gs->welded && gs->desc.no_self_while_sewing) dd.contact.no_self = 1;
    if (!gs->welded) {
        dd.sewing.pairs = gs->pairs;
        dd.sewing.n_pairs = gs->n_pairs;
        dd.sewing.duration = 0.0;
        dd.sewing.stiffness = gs->k_start > 0.0 ? gs->k_start : 0.0;
    } else {
        memset(&dd.sewing, 0, sizeof dd.sewing);
    }
    memset(&dd.threads, 0, sizeof dd.threads);
    if (gs->n_thr > 0) {
        seg = (int32_t *)wr_alloc_array(2 * (size_t)gs->n_thr, sizeof(int32_t));
        rest = (double *)wr_alloc_array((size_t)gs->n_thr, sizeof(double));
        ax = (double *)wr_alloc_array((size_t)gs->n_thr, sizeof(double));
        if (!seg || !rest || !ax) {
            st = wr_fail(diag, WR_ERR_NOMEM, -1, "garment: out of memory (%d thread segments)", (int)gs->n_thr);
            goto done;
        }
        for (s = 0; s < gs->n_thr; ++s) {
            int32_t a = gs->thr_seg[2 * s], b = gs->thr_seg[2 * s + 1];
            if (vmap) a = vmap[a], b = vmap[b];
            gs->thr_dyn[s] = a == b ? -1 : n; /* both ends welded into one vertex: nothing to gather */
            if (a == b) continue;
            seg[2 * n] = a;
            seg[2 * n + 1] = b;
            rest[n] = wr__gar_thread_rest(gs, s, gs->gather);
            ax[n++] = gs->thr_axial[s];
        }
        dd.threads.segments = seg;
        dd.threads.rest = rest;
        dd.threads.axial = ax;
        dd.threads.n_segments = n;
    }
    st = wr_dyn_create(&gs->dyn, &gs->shell, &dd, diag);
done:
    wr_free(seg);
    wr_free(rest);
    wr_free(ax);
    return st;
}

WRDEF void wr_garment_sim_free(wr_garment_sim *gs) {
    if (!gs) return;
    wr_dyn_free(&gs->dyn);
    wr_shell_free(&gs->shell);
    wr_mesh_free(&gs->mesh);
    wr_free(gs->x);
    wr_free(gs->v);
    wr_free(gs->vmap);
    wr_free(gs->pairs);
    wr_free(gs->pair_seam);
    wr_free(gs->fixed0);
    wr_free(gs->thr_seg);
    wr_free(gs->thr_line);
    wr_free(gs->thr_dyn);
    wr_free(gs->thr_len);
    wr_free(gs->thr_rho);
    wr_free(gs->thr_axial);
    memset(gs, 0, sizeof *gs);
}

/* k_full and k_start (ON SEWING) once the simulator knows m̄ and h */
static void wr__gar_stiffness(wr_garment_sim *gs) {
    const wr_shell *s = &gs->shell;
    double h = gs->dyn.desc.time.dt / gs->dyn.desc.time.substeps;
    double kmem = s->young * s->thickness / (1.0 - s->poisson * s->poisson);
    gs->k_full = gs->desc.stiffness > 0.0 ? gs->desc.stiffness : WR_GARMENT_SEW_MEMBRANE_FACTOR * kmem;
    gs->k_start = gs->desc.start_stiffness > 0.0 ? gs->desc.start_stiffness : WR_DYN_SEW_FACTOR * gs->dyn.mean_mass / (h * h);
    if (gs->k_start > gs->k_full) gs->k_start = gs->k_full;
    gs->sew_k = gs->k_start;
}

WRDEF wr_status wr_garment_sim_create(wr_garment_sim *gs, const wr_garment *g, const wr_shell_desc *shell,
                                      const wr_dyn_desc *dyn, const wr_garment_desc *desc, wr_diag *diag) {
    wr_status st;
    int32_t v, p, n_panels = 1, hit;
    if (!gs) return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "garment: NULL sim");
    memset(gs, 0, sizeof *gs);
    if (!g || !g->pattern || !g->pattern->faces || !shell || !g->placements)
        return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "garment: NULL garment, pattern mesh, placements or shell desc");
    if (g->pattern->face_panel)
        for (v = 0; v < g->pattern->nf; ++v)
            if (g->pattern->face_panel[v] + 1 > n_panels) n_panels = g->pattern->face_panel[v] + 1;
    if (g->n_placements < n_panels)
        return wr_fail(diag, WR_ERR_INVALID_ARG, g->n_placements, "garment: panel %d has no placement (%d given for %d panels)",
                       (int)g->n_placements, (int)g->n_placements, (int)n_panels);
    gs->shell_desc = *shell;
    if (dyn) gs->dyn_desc = *dyn;
    if (desc) gs->desc = *desc;
    if (!(gs->desc.gravity_delay >= 0.0 && gs->desc.gravity_ramp >= 0.0) || gs->desc.gravity_delay - gs->desc.gravity_delay != 0.0 ||
        gs->desc.gravity_ramp - gs->desc.gravity_ramp != 0.0)
        return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "garment: gravity_delay %g s, gravity_ramp %g s must be finite and >= 0",
                       gs->desc.gravity_delay, gs->desc.gravity_ramp);
    wr__gar_desc_defaults(&gs->desc);
    gs->nv0 = g->pattern->nv;
    if ((st = wr_mesh_copy(&gs->mesh, g->pattern, diag)) != WR_OK) goto fail;
    if ((st = wr_garment_place(&gs->mesh, g->placements, g->n_placements, diag)) != WR_OK) goto fail;
    if ((st = wr_garment_sewing_pairs(&gs->mesh, g->seam_pairs, g->seam_pair_seam, g->n_seam_pairs, &gs->pairs, &gs->pair_seam,
                                      &gs->n_pairs, diag)) != WR_OK)
        goto fail;
    for (p = 0; p < gs->n_pairs; ++p)
        if (gs->pair_seam[p] + 1 > gs->n_seams) gs->n_seams = gs->pair_seam[p] + 1;
    gs->x = (double *)wr_alloc_array(3 * (size_t)gs->nv0, sizeof(double));
    gs->v = (double *)wr_calloc_array(3 * (size_t)gs->nv0, sizeof(double));
    gs->vmap = (int32_t *)wr_alloc_array((size_t)gs->nv0, sizeof(int32_t));
    if (dyn && dyn->fixed) gs->fixed0 = (uint8_t *)wr_alloc_array((size_t)gs->nv0, 1);
    if (!gs->x || !gs->v || !gs->vmap || (dyn && dyn->fixed && !gs->fixed0)) {
        st = wr_fail(diag, WR_ERR_NOMEM, -1, "garment: out of memory (%d vertices)", (int)gs->nv0);
        goto fail;
    }
    if (gs->fixed0) memcpy(gs->fixed0, dyn->fixed, (size_t)gs->nv0);
    for (v = 0; v < gs->nv0; ++v) gs->vmap[v] = v;
    memcpy(gs->x, gs->mesh.pos, sizeof(double) * 3 * (size_t)gs->nv0);
    if ((st = wr_shell_create(&gs->shell, &gs->mesh, &gs->shell_desc, diag)) != WR_OK) goto fail;
    if ((st = wr__gar_threads(gs, g, diag)) != WR_OK) goto fail;
    if ((st = wr__gar_build(gs, gs->fixed0, NULL, diag)) != WR_OK) goto fail;
    wr__gar_stiffness(gs);
    gs->dyn.sew_k = gs->sew_k;
    if (!(gs->desc.weld_tol > 0.0)) gs->desc.weld_tol = WR_GARMENT_WELD_FRACTION * gs->dyn.dhat;
    /* a panel placed into a body would be locked there by the barrier: refuse it, naming the panel */
    for (p = 0; p < n_panels; ++p) {
        if ((st = wr__gar_body_hits(&gs->dyn, &gs->mesh, gs->x, p, &hit, diag)) != WR_OK) goto fail;
        if (hit) {
            st = wr_fail(diag, WR_ERR_GEOMETRY, p, "garment: panel %d as placed intersects a body (%d triangle pairs)", (int)p,
                         (int)hit);
            goto fail;
        }
    }
    wr_dyn_state_init(&gs->dyn, &gs->state, gs->x, gs->v);
    gs->gap = wr_dyn_sew_gap(&gs->dyn, gs->x);
    gs->weld_frame = -1;
    return WR_OK;
fail:
    wr_garment_sim_free(gs);
    return st;
}

WRDEF double wr_garment_sim_seam_gap(const wr_garment_sim *gs, int32_t seam) {
    double g = 0.0;
    int32_t p, i;
    for (p = 0; p < gs->n_pairs; ++p) {
        const double *a = gs->x + 3 * gs->vmap[gs->pairs[2 * p]], *b = gs->x + 3 * gs->vmap[gs->pairs[2 * p + 1]];
        double d = 0.0;
        if (seam >= 0 && gs->pair_seam[p] != seam) continue;
        for (i = 0; i < 3; ++i) d += (a[i] - b[i]) * (a[i] - b[i]);
        if (d > g * g) g = sqrt(d);
    }
    return g;
}

WRDEF void wr_garment_sim_unsewn_positions(const wr_garment_sim *gs, double *out) {
    int32_t v;
    for (v = 0; v < gs->nv0; ++v) memcpy(out + 3 * v, gs->x + 3 * gs->vmap[v], sizeof(double) * 3);
}

/* After wr_mesh_weld: mass-weighted positions and velocities per welded vertex, pins OR-ed. */
static void wr__gar_remap(const wr_garment_sim *gs, const int32_t *vmap, int32_t nn, double *x, double *v, double *msum,
                          uint8_t *fixed) {
    int32_t u, i;
    memset(x, 0, sizeof(double) * 3 * (size_t)nn);
    memset(v, 0, sizeof(double) * 3 * (size_t)nn);
    memset(msum, 0, sizeof(double) * (size_t)nn);
    for (u = 0; u < gs->nv0; ++u) {
        int32_t j = vmap[u];
        double m = gs->dyn.mass[u];
        for (i = 0; i < 3; ++i) {
            x[3 * j + i] += m * gs->x[3 * u + i];
            v[3 * j + i] += m * gs->v[3 * u + i];
        }
        msum[j] += m;
        if (fixed) fixed[j] = (uint8_t)(fixed[j] | (gs->fixed0[u] != 0));
    }
    for (u = 0; u < nn; ++u)
        for (i = 0; i < 3; ++i) {
            x[3 * u + i] /= msum[u];
            v[3 * u + i] /= msum[u];
        }
}

/* ON WELDING, the midpoint diagnostic: body triangles (tree bt over the body faces) that the faces
 * of welded vertex j meet at x, exact tri–tri on the box query's candidates. */
typedef struct wr__gar_hitq {
    const wr_dyn *sim;
    double ta[9];
    int32_t n;
} wr__gar_hitq;

static wr_status wr__gar_hit_fn(void *user, int32_t b) {
    wr__gar_hitq *q = (wr__gar_hitq *)user;
    double tb[9];
    int32_t k, i;
    for (k = 0; k < 3; ++k)
        for (i = 0; i < 3; ++i) tb[3 * k + i] = q->sim->body_x[3 * q->sim->body_faces[3 * b + k] + i];
    q->n += wr_collision_triangle_triangle_intersect(q->ta, tb);
    return WR_OK;
}

static int32_t wr__gar_vertex_hits(const wr_dyn *sim, const wr_bvh *bt, const wr_mesh *wm, const double *x, int32_t j) {
    wr__gar_hitq q;
    int32_t c, k, i, n = 0;
    q.sim = sim;
    for (c = wm->vf_start[j]; c < wm->vf_start[j + 1]; ++c) {
        double box[6];
        for (k = 0; k < 3; ++k)
            for (i = 0; i < 3; ++i) q.ta[3 * k + i] = x[3 * wm->faces[3 * wm->vf[c] + k] + i];
        for (i = 0; i < 3; ++i) {
            box[i] = fmin(q.ta[i], fmin(q.ta[3 + i], q.ta[6 + i]));
            box[3 + i] = fmax(q.ta[i], fmax(q.ta[3 + i], q.ta[6 + i]));
        }
        q.n = 0;
        (void)wr_bvh_box_query(bt, box, wr__gar_hit_fn, &q, NULL); /* the callback never stops it */
        n += q.n;
    }
    return n;
}

/* Body triangle pairs that the faces of the merged vertices meet with every pair at its midpoint
 * x (wm's positions): reported as weld_mid_hits, what a plain midpoint weld would do. */
static wr_status wr__gar_mid_hits(const wr_dyn *sim, const wr_mesh *wm, const int32_t *start, const double *x, int32_t *hits,
                                  wr_diag *diag) {
    double *bb;
    wr_bvh bt;
    int32_t k, i, j;
    wr_status st;
    *hits = 0;
    if (sim->nbf < 1) return WR_OK;
    if (!(bb = (double *)wr_alloc_array(6 * (size_t)sim->nbf, sizeof(double))))
        return wr_fail(diag, WR_ERR_NOMEM, -1, "garment: out of memory");
    for (k = 0; k < sim->nbf; ++k)
        for (i = 0; i < 3; ++i) {
            const double *p0 = sim->body_x + 3 * sim->body_faces[3 * k], *p1 = sim->body_x + 3 * sim->body_faces[3 * k + 1],
                         *p2 = sim->body_x + 3 * sim->body_faces[3 * k + 2];
            bb[6 * k + i] = fmin(p0[i], fmin(p1[i], p2[i]));
            bb[6 * k + 3 + i] = fmax(p0[i], fmax(p1[i], p2[i]));
        }
    st = wr_bvh_build(&bt, sim->nbf, bb, diag);
    wr_free(bb);
    if (st != WR_OK) return st;
    for (j = 0; j < wm->nv; ++j)
        if (start[j + 1] - start[j] > 1) *hits += wr__gar_vertex_hits(sim, &bt, wm, x, j);
    wr_bvh_free(&bt);
    return WR_OK;
}

/* ON WELDING, the merge as a motion: the unwelded cloth and the bodies in one collision mesh whose
 * vertex classes are the welded vertices (collision.h ON PAIRS: the copies of a seam vertex are
 * meant to meet), so CCD certifies each move of a class's members. Every position a member takes
 * (m, m + t (x_u − m)) lies in the box of its class's start positions and m, so the mesh is bound
 * to those boxes once (collision.h ON LOCAL CCD) and each move costs the CCD of the primitives
 * round the moving copies, not of the whole cloth and body (wr_collision_max_step_local: the same
 * alpha as wr_collision_max_step). */
typedef struct wr__gar_merge {
    wr_collision_mesh cm;
    double *X, *dX;       /* (nv0 + nb)*3: the members as they move, a trial motion (0 elsewhere) */
    int32_t *start, *mem; /* members of welded vertex j: mem[start[j] .. start[j + 1]) */
    int32_t *mv;          /* nv0: the moving members of one move */
} wr__gar_merge;

static void wr__gar_merge_free(wr__gar_merge *M) {
    wr_collision_mesh_free(&M->cm);
    wr_free(M->X), wr_free(M->dX), wr_free(M->start), wr_free(M->mem), wr_free(M->mv);
}

/* The bound boxes of ON WELDING's merge (n = nv0 + nb vertices): a class's members get the box of
 * their start positions and its mean m (x), grown by 1e-9 (1 + max |coordinate|) m, far above the
 * rounding of m + t (x_u − m) and of X + (p − X), far below any cloth length; the rest are points. */
static wr_status wr__gar_merge_bound(wr__gar_merge *M, int32_t n, int32_t nn, const double *x, wr_diag *diag) {
    double *vb = (double *)wr_alloc_array(6 * (size_t)n, sizeof(double));
    int32_t u, j, c, i;
    wr_status st;
    if (!vb) return wr_fail(diag, WR_ERR_NOMEM, -1, "garment: out of memory");
    for (u = 0; u < n; ++u)
        for (i = 0; i < 3; ++i) vb[6 * u + i] = vb[6 * u + 3 + i] = M->X[3 * u + i];
    for (j = 0; j < nn; ++j) {
        double lo[3], hi[3], big = 0.0;
        if (M->start[j + 1] - M->start[j] < 2) continue;
        for (i = 0; i < 3; ++i) lo[i] = hi[i] = x[3 * j + i];
        for (c = M->start[j]; c < M->start[j + 1]; ++c)
            for (i = 0; i < 3; ++i) {
                lo[i] = fmin(lo[i], M->X[3 * M->mem[c] + i]);
                hi[i] = fmax(hi[i], M->X[3 * M->mem[c] + i]);
            }
        for (i = 0; i < 3; ++i) big = fmax(big, fmax(fabs(lo[i]), fabs(hi[i])));
        for (c = M->start[j]; c < M->start[j + 1]; ++c)
            for (i = 0; i < 3; ++i) {
                vb[6 * M->mem[c] + i] = lo[i] - 1e-9 * (1.0 + big);
                vb[6 * M->mem[c] + 3 + i] = hi[i] + 1e-9 * (1.0 + big);
            }
    }
    st = wr_collision_mesh_bound(&M->cm, M->X, vb, diag);
    wr_free(vb);
    return st;
}

static wr_status wr__gar_merge_init(wr__gar_merge *M, const wr_garment_sim *gs, const int32_t *vmap, int32_t nn,
                                    const double *x, wr_diag *diag) {
    const wr_dyn *sim = &gs->dyn;
    int32_t n = gs->nv0 + sim->nb, nf = gs->mesh.nf + sim->nbf, *F, *cls, u, j, i;
    uint8_t *ob;
    wr_collision_desc cd;
    wr_status st;
    memset(M, 0, sizeof *M);
    F = (int32_t *)wr_alloc_array(3 * (size_t)nf, sizeof(int32_t));
    cls = (int32_t *)wr_alloc_array((size_t)n, sizeof(int32_t));
    ob = (uint8_t *)wr_calloc_array((size_t)n, 1);
    M->X = (double *)wr_alloc_array(3 * (size_t)n, sizeof(double));
    M->dX = (double *)wr_calloc_array(3 * (size_t)n, sizeof(double));
    M->start = (int32_t *)wr_calloc_array((size_t)nn + 1, sizeof(int32_t));
    M->mem = (int32_t *)wr_alloc_array((size_t)gs->nv0, sizeof(int32_t));
    M->mv = (int32_t *)wr_alloc_array((size_t)gs->nv0, sizeof(int32_t));
    if (!F || !cls || !ob || !M->X || !M->dX || !M->start || !M->mem || !M->mv) {
        st = wr_fail(diag, WR_ERR_NOMEM, -1, "garment: out of memory");
        goto done;
    }
    memcpy(F, gs->mesh.faces, sizeof(int32_t) * 3 * (size_t)gs->mesh.nf);
    for (i = 0; i < 3 * sim->nbf; ++i) F[3 * gs->mesh.nf + i] = sim->body_faces[i] + gs->nv0;
    for (u = 0; u < n; ++u) cls[u] = u < gs->nv0 ? vmap[u] : nn + u, ob[u] = u >= gs->nv0;
    memcpy(M->X, gs->x, sizeof(double) * 3 * (size_t)gs->nv0);
    if (sim->nb) memcpy(M->X + 3 * gs->nv0, sim->body_x, sizeof(double) * 3 * (size_t)sim->nb);
    for (u = 0; u < gs->nv0; ++u) M->start[vmap[u] + 1]++; /* CSR */
    for (j = 0; j < nn; ++j) M->start[j + 1] += M->start[j];
    for (u = 0; u < gs->nv0; ++u) M->mem[M->start[vmap[u]]++] = u;
    for (j = nn; j > 0; --j) M->start[j] = M->start[j - 1];
    M->start[0] = 0;
    memset(&cd, 0, sizeof cd);
    cd.no_self = gs->dyn_desc.contact.no_self; /* the welded sim's self-contact */
    cd.vertex_class = cls;
    st = wr_collision_mesh_create(&M->cm, n, nf, F, ob, &cd, diag);
    if (st == WR_OK) st = wr__gar_merge_bound(M, n, nn, x, diag);
done:
    wr_free(F), wr_free(cls), wr_free(ob);
    if (st != WR_OK) wr__gar_merge_free(M);
    return st;
}

/* Move the members of welded vertex j (all of them when j < 0) to p (p + 3k for vertex k when
 * j < 0) if CCD lets the straight motion complete (*ok = 1); else leave them (*ok = 0). */
static wr_status wr__gar_merge_move(wr__gar_merge *M, int32_t nn, int32_t j, const double *p, int32_t *ok, wr_diag *diag) {
    int32_t k0 = j < 0 ? 0 : j, k1 = j < 0 ? nn : j + 1, k, c, i, nm = 0;
    double alpha;
    wr_status st;
    for (k = k0; k < k1; ++k)
        for (c = M->start[k]; c < M->start[k + 1] && M->start[k + 1] - M->start[k] > 1; ++c) {
            for (i = 0; i < 3; ++i) M->dX[3 * M->mem[c] + i] = p[3 * (j < 0 ? k : 0) + i] - M->X[3 * M->mem[c] + i];
            M->mv[nm++] = M->mem[c];
        }
    st = wr_collision_max_step_local(&M->cm, M->X, M->dX, nm, M->mv, &alpha, NULL, diag);
    *ok = st == WR_OK && alpha >= 1.0;
    for (k = k0; k < k1; ++k)
        for (c = M->start[k]; c < M->start[k + 1]; ++c)
            for (i = 0; i < 3; ++i) {
                int32_t q = 3 * M->mem[c] + i;
                if (*ok && M->dX[q] != 0.0) M->X[q] = p[3 * (j < 0 ? k : 0) + i];
                M->dX[q] = 0.0;
            }
    return st;
}

/* ON WELDING, the CCD-limited merge: the members of every merged vertex move along straight lines
 * from their own (intersection-free) positions to a common point, each move certified by CCD, so
 * no merge move can sweep a face through a body or through the cloth. First all classes at once
 * to their midpoints m (x on entry); when CCD stops that, class by class in up to
 * WR_GARMENT_WELD_SWEEPS sweeps, to the first of m, m + t (x_u − m) (u a member, t = 1/2, then 1)
 * whose move completes. x gets the merged positions (blocked classes stay at m); *moved counts the
 * classes left off m, *blocked those that no candidate could reach. */
static wr_status wr__gar_weld_feasible(const wr_garment_sim *gs, const wr_mesh *wm, const int32_t *vmap, double *x,
                                       int32_t *mid_hits, int32_t *moved, int32_t *blocked, wr_diag *diag) {
    wr__gar_merge M;
    int32_t nn = wm->nv, j, k, i, t, ok, sweep, progress = 1;
    uint8_t *done;
    wr_status st;
    *mid_hits = *moved = *blocked = 0;
    if ((st = wr__gar_merge_init(&M, gs, vmap, nn, x, diag)) != WR_OK) return st;
    if (!(done = (uint8_t *)wr_calloc_array((size_t)nn, 1))) {
        wr__gar_merge_free(&M);
        return wr_fail(diag, WR_ERR_NOMEM, -1, "garment: out of memory");
    }
    if ((st = wr__gar_mid_hits(&gs->dyn, wm, M.start, x, mid_hits, diag)) != WR_OK) goto out;
    if ((st = wr__gar_merge_move(&M, nn, -1, x, &ok, diag)) != WR_OK) goto out;
    for (j = 0; j < nn; ++j) done[j] = ok || M.start[j + 1] - M.start[j] < 2;
    for (sweep = 0; sweep < WR_GARMENT_WELD_SWEEPS && progress; ++sweep) {
        progress = 0;
        for (j = 0; j < nn; ++j)
            for (t = 0; t <= 2 && !done[j]; ++t) /* t/2 toward copy k; t = 0 is m itself, tried once */
                for (k = t ? M.start[j] : M.start[j + 1] - 1; k < M.start[j + 1] && !done[j]; ++k) {
                    double c[3];
                    for (i = 0; i < 3; ++i) c[i] = x[3 * j + i] + 0.5 * t * (gs->x[3 * M.mem[k] + i] - x[3 * j + i]);
                    if ((st = wr__gar_merge_move(&M, nn, j, c, &ok, diag)) != WR_OK) goto out;
                    if (ok) done[j] = 1, progress = 1, *moved += t > 0;
                }
    }
    for (j = 0; j < nn; ++j) {
        if (!done[j]) (*blocked)++;
        else if (M.start[j + 1] - M.start[j] > 1) memcpy(x + 3 * j, M.X + 3 * M.mem[M.start[j]], 3 * sizeof(double));
    }
out:
    wr_free(done);
    wr__gar_merge_free(&M);
    return st;
}

/* The exact check of the welded state (ON WELDING): triangle pairs meeting a body, and (self-contact
 * on) pairs of the welded mesh meeting each other, into *left. */
static wr_status wr__gar_weld_check(const wr_garment_sim *gs, const wr_mesh *wm, const double *x, int32_t *left, wr_diag *diag) {
    int32_t hit = 0, self = 0;
    wr_status st = wr__gar_body_hits(&gs->dyn, wm, x, -1, &hit, diag);
    *left = 0;
    if (st != WR_OK) return st;
    if (!gs->dyn_desc.contact.no_self) {
        wr_collision_mesh cm;
        if ((st = wr_collision_mesh_create(&cm, wm->nv, wm->nf, wm->faces, NULL, NULL, diag)) != WR_OK) return st;
        st = wr_collision_mesh_self_intersects(&cm, x, &self, NULL, diag);
        wr_collision_mesh_free(&cm);
        if (st != WR_OK) return st;
    }
    *left = hit + self;
    return WR_OK;
}

WRDEF wr_status wr_garment_sim_weld(wr_garment_sim *gs, wr_diag *diag) {
    wr_mesh placed, wm;
    wr_shell sh;
    wr_dyn old;
    int32_t *vmap = NULL, nn, v;
    double *x = NULL, *vel = NULL, *msum = NULL, t = gs->state.t;
    uint8_t *fixed = NULL;
    wr_status st;
    if (gs->welded) return WR_OK;
    memset(&wm, 0, sizeof wm);
    placed = gs->mesh; /* a shallow view with the current positions */
    placed.pos = gs->x;
    vmap = (int32_t *)wr_alloc_array((size_t)gs->nv0, sizeof(int32_t));
    if (!vmap) return wr_fail(diag, WR_ERR_NOMEM, -1, "garment: out of memory");
    if ((st = wr_mesh_weld(&wm, &placed, gs->n_pairs, gs->pairs, vmap, diag)) != WR_OK) goto fail;
    nn = wm.nv;
    x = (double *)wr_alloc_array(3 * (size_t)nn, sizeof(double));
    vel = (double *)wr_alloc_array(3 * (size_t)nn, sizeof(double));
    msum = (double *)wr_alloc_array((size_t)nn, sizeof(double));
    if (gs->fixed0) fixed = (uint8_t *)wr_calloc_array((size_t)nn, 1);
    if (!x || !vel || !msum || (gs->fixed0 && !fixed)) {
        st = wr_fail(diag, WR_ERR_NOMEM, -1, "garment: out of memory");
        goto fail;
    }
    wr__gar_remap(gs, vmap, nn, x, vel, msum, fixed);
    st = wr__gar_weld_feasible(gs, &wm, vmap, x, &gs->weld_mid_hits, &gs->weld_moved, &gs->weld_blocked, diag);
    if (st != WR_OK) goto fail;
    memcpy(wm.pos, x, sizeof(double) * 3 * (size_t)nn);
    if ((st = wr__gar_weld_check(gs, &wm, x, &gs->weld_left, diag)) != WR_OK) goto fail;
    if (gs->weld_blocked || gs->weld_left) { /* the barriers would lock an intersection in */
        st = wr_fail(diag, WR_ERR_GEOMETRY, -1,
                     "garment: the weld is refused: %d merged vertices cannot reach a common point without crossing, "
                     "%d triangle pairs of the welded mesh intersect",
                     (int)gs->weld_blocked, (int)gs->weld_left);
        goto fail;
    }
    if ((st = wr_shell_create(&sh, &wm, &gs->shell_desc, diag)) != WR_OK) goto fail;
    /* swap in the welded mesh and rebuild the simulator on it; the old one is kept until it works */
    old = gs->dyn;
    {
        wr_shell old_shell = gs->shell;
        wr_mesh old_mesh = gs->mesh;
        gs->shell = sh;
        gs->mesh = wm;
        gs->welded = 1;
        st = wr__gar_build(gs, fixed, vmap, diag);
        if (st != WR_OK) {
            wr_shell_free(&gs->shell);
            wr_mesh_free(&gs->mesh);
            gs->shell = old_shell;
            gs->mesh = old_mesh;
            gs->dyn = old;
            gs->welded = 0;
            memset(&wm, 0, sizeof wm);
            goto fail;
        }
        if (old.nb) memcpy(gs->dyn.body_x, old.body_x, sizeof(double) * 3 * (size_t)old.nb); /* bodies where they are */
        wr_dyn_free(&old);
        wr_shell_free(&old_shell);
        wr_mesh_free(&old_mesh);
    }
    wr_free(gs->x);
    wr_free(gs->v);
    gs->x = x;
    gs->v = vel;
    for (v = 0; v < gs->nv0; ++v) gs->vmap[v] = vmap[v];
    wr_dyn_state_init(&gs->dyn, &gs->state, gs->x, gs->v);
    gs->state.t = t;
    gs->weld_gap = gs->gap;
    gs->weld_frame = gs->frame;
    gs->gap = 0.0;
    wr_free(vmap);
    wr_free(msum);
    wr_free(fixed);
    return WR_OK;
fail:
    wr_mesh_free(&wm);
    wr_free(vmap);
    wr_free(x);
    wr_free(vel);
    wr_free(msum);
    wr_free(fixed);
    return st;
}

WRDEF void wr_garment_sim_thread_length(const wr_garment_sim *gs, int32_t line, double *now, double *rest) {
    int32_t s, i;
    *now = *rest = 0.0;
    for (s = 0; s < gs->n_thr; ++s) {
        const double *a = gs->x + 3 * gs->vmap[gs->thr_seg[2 * s]], *b = gs->x + 3 * gs->vmap[gs->thr_seg[2 * s + 1]];
        double d = 0.0;
        if (gs->thr_line[s] != line) continue;
        for (i = 0; i < 3; ++i) d += (a[i] - b[i]) * (a[i] - b[i]);
        *now += sqrt(d);
        *rest += gs->thr_rho[s] * gs->thr_len[s];
    }
}

/* ON GATHERING: the rest lengths for the frame ending at t + dt */
static void wr__gar_gather_schedule(wr_garment_sim *gs) {
    double T = gs->desc.gather_time > 0.0 ? gs->desc.gather_time : WR_GARMENT_GATHER_TIME;
    int32_t s;
    gs->gather = gs->desc.gather_immediate ? 1.0 : fmin(1.0, (gs->state.t + gs->dyn.desc.time.dt) / T);
    for (s = 0; s < gs->n_thr; ++s)
        if (gs->thr_dyn[s] >= 0) gs->dyn.thread_rest[gs->thr_dyn[s]] = wr__gar_thread_rest(gs, s, gs->gather);
}

WRDEF double wr_garment_gravity_scale(const wr_garment_desc *desc, double t) {
    if (!desc || t > desc->gravity_delay + desc->gravity_ramp) return 1.0;
    if (t <= desc->gravity_delay) return 0.0;
    return (t - desc->gravity_delay) / desc->gravity_ramp;
}

WRDEF wr_status wr_garment_sim_step(wr_garment_sim *gs, wr_dyn_stats *stats, wr_diag *diag) {
    wr_status st;
    int i;
    wr__gar_gather_schedule(gs);
    /* ON HOLDING: the gravity of the frame ending at t + dt */
    gs->gravity_scale = wr_garment_gravity_scale(&gs->desc, gs->state.t + gs->dyn.desc.time.dt);
    for (i = 0; i < 3; ++i) gs->dyn.desc.gravity[i] = gs->gravity_scale * gs->dyn_desc.gravity[i];
    if (!gs->welded && gs->n_pairs > 0) {
        /* ON SEWING: the stiffness doubles per frame from k_start to k_full */
        gs->dyn.sew_k = gs->sew_k;
    }
    if ((st = wr_dyn_step(&gs->dyn, &gs->state, stats, diag)) != WR_OK) return st;
    gs->frame++;
    if (gs->welded || gs->n_pairs == 0) return WR_OK;
    gs->gap = wr_garment_sim_seam_gap(gs, -1);
    gs->sew_k = fmin(gs->k_full, gs->sew_k * WR_GARMENT_SEW_GROWTH);
    if (gs->desc.no_weld) return WR_OK;
    if (gs->gap < gs->desc.weld_tol) {
        /* a weld that would intersect is deferred (ON WELDING): sewing goes on, the gap keeps closing */
        st = wr_garment_sim_weld(gs, diag);
        if (st != WR_ERR_GEOMETRY) return st;
        gs->weld_deferred++;
        if (gs->state.t >= gs->desc.max_time - 1e-9 * gs->dyn.desc.time.dt)
            /* closed to the tolerance but never weldable: say so, not "still open" */
            return wr_fail(diag, WR_ERR_NOT_CONVERGED, -1,
                           "garment: every seam is closed to %.3g mm (weld tolerance %.3g mm) but the weld was refused in %d "
                           "frames up to %.3g s (last: %d merged vertices blocked, %d triangle pairs intersecting)",
                           1e3 * gs->gap, 1e3 * gs->desc.weld_tol, (int)gs->weld_deferred, gs->state.t, (int)gs->weld_blocked,
                           (int)gs->weld_left);
    }
    if (gs->state.t >= gs->desc.max_time - 1e-9 * gs->dyn.desc.time.dt) {
        int32_t s, worst = 0;
        double gw = -1.0;
        for (s = 0; s < gs->n_seams; ++s) {
            double g = wr_garment_sim_seam_gap(gs, s);
            if (g > gw) gw = g, worst = s;
        }
        return wr_fail(diag, WR_ERR_NOT_CONVERGED, worst,
                       "garment: seam %d still open by %.3g mm after %.3g s (weld tolerance %.3g mm, %d welds refused)", (int)worst,
                       1e3 * gw, gs->state.t, 1e3 * gs->desc.weld_tol, (int)gs->weld_deferred);
    }
    return WR_OK;
}

#ifdef __cplusplus
}
#endif
#endif /* WRINKLE_GARMENT_IMPLEMENTATION_DONE */
#endif /* WRINKLE_IMPLEMENTATION */
