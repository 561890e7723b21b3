/* wrinkle/statics.h — static equilibrium of a shell (shell.h): gravity, prescribed vertices and
 * prescribed motions (stretch, shear, twist) with load increments, uniform pressure on closed or
 * sewn surfaces, frictionless contact with analytic obstacles (plane, sphere, capsule) and static
 * triangle meshes (a body: ON MESH OBSTACLES), solved by
 * newton.h's projected Newton with linear solves through spd.h.
 * wrinkle v0.1.0 — MIT licence (see LICENSE). Needs core.h, sparse.h, spd.h (CHOLMOD when built
 * with WR_USE_CHOLMOD=1, see spd.h), newton.h, mesh.h, tft.h, shell.h, eigen.h (the opt-in
 * stability test needs its ARPACK, WR_USE_ARPACK=1, -larpack); otherwise only libc and libm.
 *
 * Minimises Π(x) = E_shell(x) − Σ_v m_v g·x_v − p·V(x) + Σ_{free v, obstacles o} κ·b(d_o(x_v))
 * over the free vertices: the TFW Sec. 4.1 base surface (TFT membrane + quadratic bending), and the
 * StVK reference statics (StVK membrane + mid-edge bending) that both papers compare against. Π is
 * handed to wr_newton_solve (newton.h: per-element PSD projection as TFW App. E does for its SQP,
 * diagonal shift, exact phase near the minimum, Armijo backtracking); statics adds the energy terms,
 * their Hessian stream, the contact step limit (CCD, the max-step hook), the stop reference, and
 * the paths to the solution (membrane continuation, load increments). A trial state where Π is
 * undefined (degenerate face, vertex on or through an obstacle) counts as +∞. Measurements behind
 * the defaults: docs/notes-statics.md.
 *
 * API
 *   wr_statics_solve(shell, x, desc, stats, diag)    x: nv*3 initial guess in, equilibrium out
 *   wr_statics_solve_incremental(shell, x, desc, motions, n_motions, n_inc, stats, diag)
 *                                                    prescribed motions applied in n_inc increments
 *   wr_motion_apply(motion, nv, x_ref, t, target, fixed, diag)   targets of a motion at fraction t
 *   wr_statics_volume(shell, x, origin, grad)        enclosed volume (1/6)Σ_f (x_a−o)·((x_b−o)×(x_c−o))
 *   wr_statics_pressure_element(x9, origin, p, g, H) one face's −p·V_f, gradient and Hessian
 *   wr_obstacle_distance(obstacle, x, grad)          signed distance [m] and its gradient
 *   wr_statics_barrier(d, dhat, kappa, b1, b2)       contact barrier κ·b(d) and its d-derivatives
 *   wr_obstacle_barrier(o, x, dhat, kappa, d, g, H)  one vertex's contact term, ∇ and PSD Hessian
 *   wr_obstacle_mesh_create(m, V, nv, F, nf, diag)   a triangle-mesh obstacle (BVH, pseudonormals);
 *   wr_obstacle_mesh_free(m)                         released by the caller after the solves
 *   wr_obstacle_mesh_closest(m, x, c, grad, face)    signed distance to it, closest point, ∇d
 *   desc.stability                                   test each equilibrium with the true Hessian's
 *                                                    lowest eigenpairs, escape along negative modes
 *   wr_statics_stability_test(shell, x, desc, stats, diag)   that test alone, at a given x
 *   (sewing — wr_mesh_weld, wr_mesh_pillow — is in mesh.h; the element projection is newton.h's
 *   wr_newton_project_spd)
 *
 * EXAMPLE
 *     wr_mesh m;  wr_shell shell;  wr_shell_desc sh;  wr_statics_desc sd;  wr_statics_stats st;
 *     wr_obstacle ball;  wr_diag d;  double *x;  uint8_t *pin;  int32_t i;
 *     if (wr_mesh_rectangle(&m, 0.3, 0.3, 8, 8, &d) != WR_OK) { puts(d.message); return 1; }
 *     memset(&sh, 0, sizeof sh);  memset(&sd, 0, sizeof sd);  memset(&ball, 0, sizeof ball);
 *     sh.young = 1e6; sh.poisson = 0.3; sh.thickness = 1e-3; sh.density = 200;   // SI: Pa, -, m, kg/m³
 *     if (wr_shell_create(&shell, &m, &sh, &d) != WR_OK) { puts(d.message); return 1; }
 *     x = (double *)wr_alloc_array(3 * (size_t)m.nv, sizeof(double));
 *     pin = (uint8_t *)wr_calloc_array((size_t)m.nv, 1);
 *     for (i = 0; i < 3 * m.nv; ++i) x[i] = m.pos[i] - (i % 3 == 2 ? -0.11 : 0.15);  // centred, 1 cm above
 *     pin[0] = pin[8] = pin[72] = pin[80] = 1;                      // the four corners are held
 *     ball.kind = WR_OBSTACLE_SPHERE; ball.radius = 0.1;             // centred at the origin
 *     sd.loads.gravity[2] = -9.81; sd.loads.fixed = pin;             // sags onto the ball
 *     sd.contact.obstacles = &ball; sd.contact.n_obstacles = 1;      // default d̂ and κ
 *     if (wr_statics_solve(&shell, x, &sd, &st, &d) != WR_OK) { puts(d.message); return 1; }
 *     printf("%d Newton steps, |g| %.2e N, gap %.2e m\n", st.iterations, st.grad_norm, st.min_distance);
 *     wr_free(x);  wr_free(pin);  wr_shell_free(&shell);  wr_mesh_free(&m);
 *
 * ON STOPPING ("solve to tolerance")
 *   Converged when ‖∇Π_free‖ <= stop.grad_tol · max(‖∇Π_free(x0)‖, ‖f_ext,free‖) (stop GRADIENT),
 *   or when a full (α = 1, not backtracked, not cut by CCD) step has max|Δx| <= stop.step_tol ·
 *   (bounding-box diagonal of x0) (stop STEP; a backtracked tiny step means a stall, not
 *   convergence, and so does one that leaves ‖∇Π‖ above 1e3 × the reference: newton.h), or on Π's round-off (ROUNDOFF) or the opt-in Newton decrement (DECREMENT), both as
 *   newton.h ON STOPPING says. stop.max_iter reached, or a line search that cannot decrease Π,
 *   returns WR_ERR_NOT_CONVERGED with the best (lowest-Π) iterate in x. ∇Π includes pressure and
 *   contact forces, so a converged state is an equilibrium of all of them. The perturbation
 *   (start.perturb) is applied before x0 is measured.
 *
 * ON SHIFT, PROJECTION AND THE EXACT PHASE
 *   newton.h's (ON SHIFT, ON PROJECTION AND THE EXACT PHASE): μ = shift.rel · mean diagonal,
 *   raised ×100 while the solve reports a non-SPD matrix, ×0.1 after full steps; per-element PSD
 *   projection (hessian.projection), the exact Hessian near the minimum, hessian.exact_retry.
 *   shift.raise (> 1) multiplies μ after backtracked steps: it changes the path, not the minimiser,
 *   and can save many steps where full steps keep being cut, but where Π is flat the solve then
 *   stops elsewhere in the valley, so it is opt-in (docs/notes-statics.md, "Shift").
 *
 * ON MEMBRANE CONTINUATION (continuation.membrane_ramp)
 *   A displacement-based thin shell under large rotation converges slowly with Newton: a step that
 *   rotates a part of length ℓ by θ is linear in the positions, so it stretches it by θ²/2, and the
 *   membrane energy of that stretch grows like Eh·θ⁴ while the load's gain grows like θ. With
 *   membrane_ramp = s0 in (0, 1) the solve first finds the equilibrium of the same shell with its
 *   membrane stiffness (StVK C_mem, TFT Y) scaled by s0, then by s0·f, s0·f², … (f =
 *   continuation.factor, default 1e3), each stage warm-started from the last and solved to the
 *   relative tolerance WR_STATICS_RAMP_TOL (1e-6), and finally solves the real shell to grad_tol.
 *   The soft stages take full steps s0^{-1/3} times longer and the soft equilibrium is already
 *   nearly inextensible, so the last stage starts close to the solution (several times fewer Newton
 *   steps on a fabric cantilever: docs/notes-statics.md). Bending is not scaled (it drives the
 *   shape). Off by default: for a buckling problem a softer membrane changes the wrinkle pattern the
 *   path selects.
 *   Choose s0 so that the soft stage's membrane strain stays small (s0 ≳ 100 × load per width /
 *   (Eh), strain ≲ 1 %). When the last stage ends WR_ERR_NOT_CONVERGED the solve restarts from the
 *   initial x without continuation (stats.ramp_fallback = 1, the discarded steps counted in
 *   ramp_iterations). The perturbation is applied in the first stage only; stats report the whole
 *   solve (iterations and times summed over stages, ramp_stages/ramp_iterations for the soft ones).
 *
 * ON INEXACT NEWTON (linear.forcing)
 *   Far from the solution a Newton direction needs no 1e-8 linear accuracy. With linear.forcing =
 *   η_max > 0 each PCG solve stops at the relative residual η_k = min(η_max, max(tol, √(‖∇Π‖ /
 *   reference))) (tol = linear.solver.rel_tol or spd.h's default): the forcing sequence η_k → 0 with
 *   the gradient keeps Newton's local convergence superlinear (Dembo, Eisenstat & Steihaug 1982;
 *   Eisenstat & Walker 1996 use the same √ scaling). CHOLMOD solves exactly whatever η_k.
 *
 * ON PRESSURE (Skouras et al. 2014; TFW Sec. 6 inflatables)
 *   loads.pressure p [Pa] (> 0 inflates) adds −p·V with V = (1/6) Σ_f (x_a−o)·((x_b−o)×(x_c−o))
 *   over faces (a, b, c), o = the centroid of the initial x (held fixed during the solve). V > 0 when
 *   the faces are oriented with outward normals; an inward-oriented closed mesh has V < 0 and
 *   pressure then deflates it. On a closed surface V does not depend on o. On an open surface it
 *   does, through the boundary only, so pressure needs a closed (sewn) surface or an open one whose
 *   boundary vertices are all prescribed; otherwise WR_ERR_UNSUPPORTED (item = a free boundary
 *   vertex). Hessian: ∂²V_f/∂x_a∂x_b = −(1/6)[x_c−o]× for (a, b, c) cyclic: zero diagonal blocks,
 *   hence indefinite. Each face's −p·∇²V_f is added to the same face's elastic block BEFORE that
 *   block's PSD projection: the membrane stiffness absorbs the indefinite part where it can, so
 *   Newton keeps the pressure stiffness where it is consistent and only the net non-convex part is
 *   discarded. Faces whose elastic block is absent (no membrane and no mid-edge bending) get the
 *   pressure block projected on its own. (The folding relies on shell.h streaming one block per
 *   face, in face order, corners first — its ON ELEMENT HESSIANS contract; a block that does not
 *   match is not folded, and the leftover faces are added on their own, so each face's pressure
 *   term enters exactly once either way.)
 *
 * ON CONTACT
 *   Frictionless, vertex against obstacle, one-sided (the obstacle is where d < 0): an
 *   IPC-style log barrier (Li et al. 2020) b(d) = −(d − d̂)² ln(d/d̂) for 0 < d < d̂, 0 for d >= d̂
 *   (wr_collision_barrier of collision.h; wr_statics_barrier is the same function)
 *   (C², so Newton sees a smooth energy), scaled by κ [N/m]. Only free vertices feel it; a free
 *   vertex with d <= 0 at the start (after the perturbation) is WR_ERR_GEOMETRY (item = vertex).
 *   Every Newton step is cut, before the line search, to the largest α <= 1 such that no free vertex
 *   gets closer than WR_STATICS_CCD_KEEP (0.2) of its current distance to any obstacle (newton.h's
 *   max_step hook): conservative advancement along the straight path, exact for the plane and safe
 *   for the sphere and capsule because d is 1-Lipschitz. So no iterate ever penetrates, whatever κ.
 *   The barrier Hessian is κ[b''(d) ∇d∇dᵀ + b'(d) ∇²d]; the second term is negative semidefinite on
 *   a convex obstacle (b' < 0, ∇²d >= 0, orthogonal to ∇d), so its PSD projection is exactly
 *   κ b''(d) ∇d∇dᵀ, which is what we assemble. Defaults: d̂ = 1e-3 × bounding-box diagonal of x0;
 *   κ = 10 f_ref / d̂ with f_ref = the largest per-vertex external load (gravity m_v|g| plus p ×
 *   vertex area), or, with no external load, 1e-3 · h·Y · (typical rest edge). κ only decides how
 *   close to the surface a loaded vertex rests (within d̂), never whether it passes. Contact is
 *   vertex-only: a face between vertices outside a curved obstacle can cut into it by its sagitta
 *   (≈ l²/(8R) for edge length l, radius R); min_distance in the stats is measured at the vertices.
 *   One function, wr_obstacle_barrier, gives every kind's term, gradient and Hessian.
 *
 * ON MESH OBSTACLES (WR_OBSTACLE_MESH: a body, a mannequin, any closed triangle mesh)
 *   d(x) = ±|x − c|, c the closest point of the mesh, found exactly by collision.h's BVH over the
 *   face boxes (wr_bvh_nearest: a node is skipped only when its box is farther than the best face
 *   so far) and its point–triangle distance. The sign is that of (x − c)·n with n the angle-
 *   weighted pseudonormal of the closest feature (Bærentzen & Aanæs 2005): the face normal when c
 *   is inside a face, the normalised sum of the two face normals on an edge, Σ corner angle × face
 *   normal at a vertex. On a closed, consistently oriented (outward, counter-clockwise) 2-manifold
 *   mesh this is exactly inside (< 0) / outside (> 0), so d is the true signed distance, 1-Lipschitz,
 *   and the CCD of ON CONTACT is as safe as for the analytic kinds: no vertex crosses to d <= 0 or
 *   gets closer than WR_STATICS_CCD_KEEP of its distance in one step. On an open mesh
 *   (n_open_edges > 0) the sign flips behind the boundary, where |d| > 0: d jumps there and the CCD
 *   is not guaranteed; use closed meshes. ∇d = sign·(x − c)/|x − c|.
 *   The signed d decides "inside" (WR_ERR_GEOMETRY at the start), the CCD, min_distance and the
 *   contact count. The barrier itself is IPC's (Li et al. 2020): for 0 < d < d̂, Σ_f κ b(d_f) over
 *   every face f with unsigned point–triangle distance d_f < d̂ (a box query of the BVH). Not κ b(d)
 *   of the closest face alone: d is only C⁰ in its gradient where the closest face changes inside a
 *   concave crease (the medial axis), and a vertex resting in such a crease — everywhere on a
 *   marching-tetrahedra body — stalls Newton (a 64-vertex sheet on the mannequin's head: |∇Π|
 *   stuck at 0.77 of its start after 1000 steps, converged in 133 with the sum). Each d_f is C¹
 *   off its triangle, so the sum is; the price is that a vertex near an edge or mesh vertex feels
 *   every face there (multiplicity 2 to ~6), so it rests somewhat farther off within (0, d̂) than
 *   against one smooth surface — never outside d̂, never inside. The curvature term κ b'(d_f) ∇²d_f
 *   is dropped per face as for the analytic kinds: d_f is the distance to a convex set, ∇²d_f is
 *   PSD with ∇²d_f ∇d_f = 0, so with b' < 0 that term is negative semidefinite on the complement of
 *   ∇d_f and the exact PSD projection of each face's term is κ b''(d_f) ∇d_f∇d_fᵀ; their sum is
 *   assembled. Contact stays vertex-only: a cloth face can cut through a convex mesh
 *   edge or vertex by its sagitta, and a sharp mesh feature can poke between cloth vertices (the
 *   cloth edge length should be below the body's feature size). Ownership: wr_obstacle.mesh is
 *   borrowed; the caller keeps the wr_obstacle_mesh alive through every solve that uses it and frees
 *   it with wr_obstacle_mesh_free. Cost: one nearest-face query per free vertex per energy, gradient,
 *   Hessian and CCD evaluation, O(log nf) each on a well-shaped body. A skirt hung on the mannequin
 *   and its TFW wrinkles: docs/notes-tfw-dress.md.
 *
 * ON MOTIONS AND INCREMENTS
 *   A wr_motion moves a vertex set rigidly or by a simple deformation of its reference positions
 *   (the x given to the incremental solve): translate, stretch (uniaxial, or isotropic scale when
 *   axis = 0), simple shear, or twist (rotation about an axis line by an angle, so heights along
 *   the axis are kept). wr_statics_solve_incremental applies fraction t = k/n_inc of every motion
 *   for k = 1..n_inc and solves each increment to tolerance, warm-started from the previous
 *   equilibrium (free vertices start where the last increment left them, prescribed ones at their
 *   new targets). increments.predictor = 1 uses a secant predictor instead: from the second
 *   increment on, free vertices start at 2·x_{k−1} − x_{k−2} (x_0 = the reference), restarting from
 *   x_{k−1} when that prediction is infeasible (degenerate face, vertex in an obstacle); off by
 *   default (on a buckling path it cost more Newton steps than it saved: docs/notes-statics.md,
 *   "Increments"). Intermediate increments use increments.grad_tol (default stop.grad_tol); an
 *   intermediate WR_ERR_NOT_CONVERGED is tolerated (its best iterate warm-starts the next
 *   increment, counted in stats.increments_failed); the status of the last increment is returned.
 *   The perturbation is applied in the first increment only. increments.hybrid_switch = s > 0
 *   solves each increment with the given projection to s/grad_tol times the tolerance, then with
 *   the exact Hessian to the tolerance; both phases stop relative to the projected phase's
 *   reference (ON STOPPING, at the increment's start), so the exact phase ends where a plain solve
 *   would.
 *
 * ON STABILITY (stability.check = 1; needs eigen.h's ARPACK + CHOLMOD)
 *   Newton stops at any stationary point, and a flat start under compression is one: every
 *   out-of-plane force vanishes by symmetry, so an unstable flat state can be carried to full load.
 *   With the option, after each increment of wr_statics_solve_incremental (and at the end of
 *   wr_statics_solve) the equilibrium is tested with the TRUE Hessian K of Π (exact element blocks,
 *   pressure and contact terms included, free DOFs only): eigen.h's LDLᵀ of K − σ0A gives the
 *   number of eigenvalues below σ0 = −neg_tol · scale (the inertia; scale = mean diag K / mean A)
 *   and shift-invert Lanczos the n_modes lowest pairs of K v = λ A v, A = the lumped rest vertex
 *   areas (so λ is an energy per area and displacement², [Pa/m], comparable across meshes). When
 *   an eigenvalue is below σ0 the lowest mode v is scaled to a largest vertex displacement of
 *   `amplitude` (default: the thickness h, the scale of a wrinkle's amplitude, much larger than
 *   round-off and much smaller than the mesh), x ± amplitude·v̂ are both re-solved (same options,
 *   no perturbation) and the lower Π is kept if it is below Π(x); then the test repeats (at most
 *   max_rounds escapes per increment). The stats report the eigenvalues at the returned x, the
 *   negative count and lowest eigenvalue before the first escape, the modes found, the escapes and
 *   the energy drop. check = 2 tests and reports without escaping. perturb_each = 1 also applies start.perturb at every increment (seed + k − 1),
 *   not only the first. Checked against Euler's strip in tests/test_statics.c (λ₁ within 0.1 %,
 *   the buckled amplitude within 1 %); cost and figures: docs/notes-statics.md.
 *
 * ON ASSEMBLY CACHE
 *   Each solve (each continuation stage and load increment) assembles through sparse.h's
 *   wr_assembly (inside newton.h): the pattern of the first assembly is kept and every later one adds
 *   each element through cached block offsets. The quadratic-bending blocks (TFW Eq. 28) do not
 *   depend on x and are PSD, so the FAST projection and the exact Hessian keep them unchanged: they
 *   are streamed once as the constant segment (shell.h wr_shell_hessian_elements_part) and their sum
 *   is added to each later assembly; with WR_PROJECT_JACOBI they are streamed every time.
 *
 * ON THREADS
 *   No global state; the progress callback runs on the calling thread.
 */
#ifndef WRINKLE_STATICS_H
#define WRINKLE_STATICS_H

#include "core.h"
#include "sparse.h"
#include "spd.h"
#include "newton.h"
#include "shell.h"
#include "collision.h" /* wr_collision_barrier */
#include "eigen.h"     /* the stability test (ON STABILITY) */

#ifdef __cplusplus
extern "C" {
#endif

#define WR_STATICS_STABILITY_EIGS 8 /* eigenvalues kept in the stats */

typedef struct wr_statics_stats {
    int32_t iterations;         /* Newton steps taken (this solve; last increment for incremental) */
    int32_t linear_iterations;  /* summed over steps */
    int32_t line_search_evals;  /* energy evaluations in line searches */
    double energy;              /* Π at the returned x [J] */
    double grad_norm, grad_norm0, grad_ref; /* ‖∇Π_free‖ now, at x0, and the reference of ON STOPPING [N] */
    double last_step;           /* max |αΔx| of the last accepted step [m] */
    double shift;               /* last diagonal shift μ used */
    wr_newton_stop stop;        /* newton.h: GRADIENT, STEP, ROUNDOFF, DECREMENT (WR_OK) or MAX_ITER, LINE_SEARCH */
    double t_assembly, t_projection, t_linear, t_line_search, t_total; /* seconds */
    /* added with pressure / contact / increments (zero when unused) */
    double volume;              /* enclosed volume V at the returned x [m³] (pressure != 0) */
    double min_distance;        /* smallest signed vertex–obstacle distance at x [m] (obstacles) */
    double contact_dhat, contact_stiffness; /* d̂ [m] and κ [N/m] actually used */
    int32_t n_contacts;         /* free vertices within d̂ of an obstacle at x */
    int32_t elements_projected; /* element blocks changed by the projection, summed over steps */
    int32_t elements_assembled; /* element blocks seen, summed over steps */
    double ccd_alpha_min;       /* smallest CCD step cut over the solve (1 = never cut) */
    int32_t increments, increments_failed, total_iterations; /* incremental solve only */
    int32_t ramp_stages, ramp_iterations; /* membrane continuation: soft stages and their Newton steps */
    int32_t exact_steps;        /* Newton steps taken with the exact Hessian in a projected solve (ON PROJECTION) */
    int32_t ramp_fallback;      /* 1: the continuation's last stage did not converge, solved again without it */
    int32_t increment;          /* incremental solve: the increment being solved (1-based; progress callbacks) */
    /* stability (ON STABILITY; zero when stability.check is off). Eigenvalues λ of K v = λ A v, K the
     * true Hessian of Π on the free DOFs, A the lumped rest vertex areas: [J/m⁴ = Pa/m] */
    int32_t stability_checks;   /* eigen-analyses (summed over increments) */
    int32_t stability_modes;    /* negative eigenpairs found (summed over analyses) */
    int32_t stability_escapes;  /* steps along a mode that lowered Π and were kept (summed) */
    int32_t stability_iterations; /* Newton steps of the re-solves from the mode steps (summed) */
    double stability_energy_drop; /* Π lowered by the kept escapes, summed [J] */
    double t_stability;         /* seconds in the analyses and re-solves */
    int32_t stability_negative_first; /* last increment: # negative eigenvalues before any escape */
    double stability_lambda_first;    /* last increment: lowest eigenvalue before any escape */
    int32_t stability_negative; /* # negative eigenvalues (below −neg_tol·scale) at the returned x */
    int32_t stability_n_eigs;   /* eigenvalues in stability_eigs: the lowest at the returned x, ascending */
    double stability_eigs[WR_STATICS_STABILITY_EIGS];
} wr_statics_stats;


typedef enum wr_obstacle_kind {
    WR_OBSTACLE_PLANE = 0,   /* half-space n·(x − p) < 0 is solid */
    WR_OBSTACLE_SPHERE = 1,  /* |x − p| < radius is solid */
    WR_OBSTACLE_CAPSULE = 2, /* distance to segment [p, q] < radius is solid */
    WR_OBSTACLE_MESH = 3     /* inside a closed triangle mesh is solid (ON MESH OBSTACLES) */
} wr_obstacle_kind;

/* A static triangle-mesh obstacle (ON MESH OBSTACLES): copies of the positions and faces, unit face
 * normals, the angle-weighted pseudonormals of its edges and vertices, and a BVH over the face
 * boxes (collision.h). Made by wr_obstacle_mesh_create, released by wr_obstacle_mesh_free. */
typedef struct wr_obstacle_mesh {
    int32_t nv, nf;
    double *pos;    /* nv*3 [m] */
    int32_t *faces; /* nf*3, counter-clockwise seen from outside */
    double *fn;     /* nf*3 unit face normals */
    double *en;     /* nf*9: unit pseudonormal of edge k = (faces[3f+k], faces[3f+(k+1)%3]) of face f */
    double *vn;     /* nv*3 unit angle-weighted vertex pseudonormals */
    int32_t n_open_edges; /* edges with one face (0 for a closed mesh: the sign is then exact) */
    wr_bvh bvh;     /* over the nf face boxes */
} wr_obstacle_mesh;

typedef struct wr_obstacle {
    wr_obstacle_kind kind;
    double p[3];      /* plane: a point on it; sphere: centre; capsule: axis end [m] */
    double q[3];      /* capsule: other axis end [m] (p == q is a sphere) */
    double normal[3]; /* plane: normal towards the free side (any length > 0) */
    double radius;    /* sphere, capsule [m] > 0 */
    const wr_obstacle_mesh *mesh; /* WR_OBSTACLE_MESH: borrowed, kept alive by the caller */
} wr_obstacle;

/* Options grouped by concern; zero means default everywhere, filled in by one private function:
 *   stop          max_iter 200; grad_tol 1e-8 (relative, ON STOPPING); step_tol 1e-13 (relative to the
 *                 bounding-box diagonal of x0); decrement_tol 0 = off (newton.h ON STOPPING: λ²/2 <=
 *                 decrement_tol · Σ|terms of Π|, for the convex TFT base)
 *   loads         gravity (0,0,0) m/s² (needs shell density > 0); pressure 0 Pa (ON PRESSURE); fixed
 *                 NULL = none, else nv flags (nonzero = vertex prescribed); target NULL = prescribed
 *                 vertices keep their input position, else nv*3 positions whose fixed rows are used
 *   start         perturb 0 = none, else the standard deviation [m] of a seeded normal displacement of
 *                 the free vertices along their area-weighted vertex normal (breaks the symmetry of
 *                 flat starts); seed used as given (0 is a valid seed)
 *   contact       obstacles NULL / n_obstacles 0 = none; dhat 0 → 1e-3 × bbox diagonal [m]; stiffness
 *                 0 → the ON CONTACT default [N/m]
 *   hessian       newton.h: projection WR_PROJECT_FAST (WR_PROJECT_NONE = exact Hessians);
 *                 exact_retry 0 = off, else q in (0, 1) (ON PROJECTION)
 *   shift         newton.h: rel 1e-8 (μ relative to the mean diagonal); raise 0 = off, else r > 1
 *                 applied after a backtracked step (ON SHIFT)
 *   linear        newton.h: solver = spd.h options (its fixed is set here); forcing 0 = every PCG
 *                 solve to solver.rel_tol, else η_max in (0, 1) (ON INEXACT NEWTON; not for CHOLMOD)
 *   continuation  membrane_ramp 0 = off, else the first stage's membrane scale s0 in (0, 1); factor
 *                 0 → 1e3 (> 1) (ON MEMBRANE CONTINUATION)
 *   increments    grad_tol 0 → stop.grad_tol, for the intermediate increments; predictor 0 = each
 *                 increment starts from the last equilibrium, 1 = secant predictor (ON MOTIONS AND
 *                 INCREMENTS)
 *   stability     check 0 = off, 1 = test the equilibrium and escape along negative modes, 2 = test
 *                 and report only (ON STABILITY; needs WR_USE_ARPACK and WR_USE_CHOLMOD, else
 *                 WR_ERR_UNSUPPORTED); n_modes
 *                 0 → 4 eigenpairs (<= 64); neg_tol 0 → WR_EIGEN_NEG_REL (eigen.h); amplitude 0 → the
 *                 shell thickness [m] (largest vertex displacement of a mode step); max_rounds 0 → 4
 *                 escapes per test; perturb_each 1 = start.perturb at every increment (seed + k − 1)
 *   progress      NULL, else called with progress_user after every Newton step.
 * Out-of-range values (negative tolerances, factors outside their intervals, non-finite numbers)
 * are WR_ERR_INVALID_ARG naming the field. */
typedef struct wr_statics_stop_desc {
    int32_t max_iter;
    double grad_tol, step_tol, decrement_tol;
} wr_statics_stop_desc;

typedef struct wr_statics_loads_desc {
    double gravity[3]; /* [m/s²] */
    double pressure;   /* [Pa], > 0 inflates */
    const uint8_t *fixed;
    const double *target;
} wr_statics_loads_desc;

typedef struct wr_statics_start_desc {
    double perturb; /* [m] */
    uint64_t seed;
} wr_statics_start_desc;

typedef struct wr_statics_contact_desc {
    const wr_obstacle *obstacles;
    int32_t n_obstacles;
    double dhat;      /* [m] */
    double stiffness; /* κ [N/m] */
} wr_statics_contact_desc;

typedef struct wr_statics_continuation_desc {
    double membrane_ramp, factor;
} wr_statics_continuation_desc;

typedef enum wr_statics_predictor {
    WR_STATICS_PREDICT_LAST = 0,   /* free vertices start at the last equilibrium */
    WR_STATICS_PREDICT_SECANT = 1, /* 2·x_{k−1} − x_{k−2} */
    WR_STATICS_PREDICT_AFFINE = 2  /* the least-squares affine map of the prescribed vertices' move */
} wr_statics_predictor;

typedef struct wr_statics_increments_desc {
    double grad_tol;
    wr_statics_predictor predictor;
    int32_t ramp_gravity;       /* 1: loads.gravity scaled by k/n_inc as well */
    int32_t absolute_reference; /* 1: one force scale for every increment (ON MOTIONS AND INCREMENTS) */
    double hybrid_switch;       /* 0 = off; > 0: each increment projected to hybrid_switch, then exact */
    /* NULL, else called after every increment with progress_user, its status, stats and diag */
    void (*done)(void *user, int32_t k, int32_t n_inc, wr_status status, const wr_statics_stats *stats,
                 const wr_diag *diag);
} wr_statics_increments_desc;

typedef struct wr_statics_stability_desc {
    int32_t check, n_modes, max_rounds, perturb_each;
    double neg_tol, amplitude;
} wr_statics_stability_desc;

typedef struct wr_statics_desc {
    wr_statics_stop_desc stop;
    wr_statics_loads_desc loads;
    wr_statics_start_desc start;
    wr_statics_contact_desc contact;
    wr_newton_hessian_desc hessian;
    wr_newton_shift_desc shift;
    wr_newton_linear_desc linear;
    wr_statics_continuation_desc continuation;
    wr_statics_increments_desc increments;
    wr_statics_stability_desc stability;
    void (*progress)(void *user, const wr_statics_stats *stats);
    void *progress_user;
} wr_statics_desc;

typedef enum wr_motion_kind {
    WR_MOTION_HOLD = 0,      /* prescribed at the reference position */
    WR_MOTION_TRANSLATE = 1, /* x = X + t·vec */
    WR_MOTION_STRETCH = 2,   /* x = X + t·amount·((X−origin)·â) â; axis = 0: x = origin + (1 + t·amount)(X−origin) */
    WR_MOTION_SHEAR = 3,     /* x = X + t·amount·((X−origin)·n̂) â  (simple shear γ = amount) */
    WR_MOTION_TWIST = 4,     /* X rotated by t·amount [rad] about the line (origin, â), right-handed */
    WR_MOTION_AFFINE = 5     /* x = o + R(t·amount about â)·(I + t·grad)·(X − o) + t·vec + t·wave(X) (the scene format's) */
} wr_motion_kind;

/* A prescribed motion of the vertex set verts[0..n_verts) (their reference positions X are the x
 * passed in). amount: stretch = engineering strain (0.1278 = +12.78%), shear = γ, twist = angle [rad]. */
typedef struct wr_motion {
    wr_motion_kind kind;
    const int32_t *verts;
    int32_t n_verts;
    double origin[3]; /* [m] */
    double axis[3];   /* stretch / twist axis, shear displacement direction (normalised here) */
    double normal[3]; /* shear: the direction whose coordinate scales the displacement */
    double vec[3];    /* translate [m] */
    double amount;
    /* WR_MOTION_AFFINE only: grad = F − I at t = 1 (row-major 3×3; F = the deformation about origin);
     * the twist is amount [rad] about axis (none when amount = 0); wave(X) = wave_amplitude ·
     * sin(2π (X·wave_along) / wave_length + wave_phase) · unit(wave_dir) [m], off when the amplitude is 0
     * (a sinusoidal gather, e.g. a curtain's top edge) */
    double grad[9];
    double wave_amplitude, wave_length, wave_phase, wave_along[3], wave_dir[3];
} wr_motion;

WRDEF wr_status wr_statics_solve(const wr_shell *s, double *x, const wr_statics_desc *desc, wr_statics_stats *stats,
                                 wr_diag *diag);
/* ON STABILITY without a solve: the lowest eigenpairs of Π's true Hessian at x (desc's loads, contact,
 * pressure; desc.stability's n_modes and neg_tol; its check is ignored) into stats' stability fields
 * (stability_eigs, stability_negative, …); x is not changed. Needs WR_USE_ARPACK and WR_USE_CHOLMOD. */
WRDEF wr_status wr_statics_stability_test(const wr_shell *s, const double *x, const wr_statics_desc *desc,
                                          wr_statics_stats *stats, wr_diag *diag);
/* x: nv*3 reference positions in (the motions' X and the first warm start), final equilibrium out.
 * desc->fixed / desc->target still prescribe other vertices (held at their target). n_inc >= 1. */
WRDEF wr_status wr_statics_solve_incremental(const wr_shell *s, double *x, const wr_statics_desc *desc,
                                             const wr_motion *motions, int32_t n_motions, int32_t n_inc,
                                             wr_statics_stats *stats, wr_diag *diag);
/* Writes target rows (nv*3 array, only the motion's vertices) at fraction t from reference x_ref and
 * sets fixed[v] = 1 for them (fixed may be NULL). WR_ERR_INVALID_ARG on a vertex index outside
 * [0, nv) (item = index position), a zero axis for twist/shear/… that needs one, non-finite data. */
WRDEF wr_status wr_motion_apply(const wr_motion *m, int32_t nv, const double *x_ref, double t, double *target,
                                uint8_t *fixed, wr_diag *diag);
/* V = (1/6) Σ_f (x_a−o)·((x_b−o)×(x_c−o)) [m³], o = origin (NULL = 0). grad (nv*3) overwritten if non-NULL. */
WRDEF double wr_statics_volume(const wr_shell *s, const double *x, const double origin[3], double *grad);
/* One face: returns −p·V_f; g (9) and H (81, row-major) of −p·V_f when non-NULL. origin NULL = 0. */
WRDEF double wr_statics_pressure_element(const double x9[9], const double origin[3], double p, double *g, double *H);
/* Signed distance [m] from x to the obstacle surface (> 0 outside); grad (3) = ∇d, unit. */
WRDEF double wr_obstacle_distance(const wr_obstacle *o, const double x[3], double grad[3]);
/* κ·b(d) with b(d) = −(d−d̂)² ln(d/d̂) on (0, d̂), 0 for d >= d̂, +∞ for d <= 0; b1 = κ b'(d),
 * b2 = κ b''(d) when non-NULL. */
WRDEF double wr_statics_barrier(double d, double dhat, double kappa, double *b1, double *b2);
/* The contact term of one vertex x against obstacle o: returns κ b(d(x)) (+∞ when d <= 0); g (3) =
 * κ b'(d) ∇d and H (9, row-major) = κ b''(d) ∇d∇dᵀ (the PSD Hessian of ON CONTACT) when non-NULL,
 * zero beyond d̂; *dist (may be NULL) = d(x) [m], signed. For a mesh, when 0 < d < d̂: the sum of
 * those terms over the faces within d̂, on their unsigned distances (ON MESH OBSTACLES). Every
 * obstacle kind, one function. */
WRDEF double wr_obstacle_barrier(const wr_obstacle *o, const double x[3], double dhat, double kappa, double *dist,
                                 double g[3], double H[9]);
/* Builds the mesh obstacle from nv vertices V (nv*3 [m]) and nf faces F (nf*3, outward counter-
 * clockwise); V and F are copied. WR_ERR_INVALID_ARG for NULL arrays, nv < 3 or nf < 1, an index
 * outside [0, nv) (item = face); WR_ERR_DOMAIN for a non-finite coordinate (item = vertex);
 * WR_ERR_GEOMETRY for a degenerate face (repeated corner or zero area, item = face); WR_ERR_NOMEM.
 * On failure m is left zeroed (safe to free). */
WRDEF wr_status wr_obstacle_mesh_create(wr_obstacle_mesh *m, const double *V, int32_t nv, const int32_t *F, int32_t nf,
                                        wr_diag *diag);
WRDEF void wr_obstacle_mesh_free(wr_obstacle_mesh *m);
/* Signed distance [m] from x to the mesh (> 0 outside, ON MESH OBSTACLES); closest (3) = the nearest
 * surface point and grad (3) = ∇d = ±(x − closest)/|x − closest| (unit; the feature's pseudonormal
 * on the surface) when non-NULL; *face (may be NULL) = the nearest face. */
WRDEF double wr_obstacle_mesh_closest(const wr_obstacle_mesh *m, const double x[3], double closest[3], double grad[3],
                                      int32_t *face);

#ifdef __cplusplus
}
#endif
#endif /* WRINKLE_STATICS_H */

/* ============================================================================================ */
#ifdef WRINKLE_IMPLEMENTATION
#ifndef WRINKLE_STATICS_IMPLEMENTATION_DONE
#define WRINKLE_STATICS_IMPLEMENTATION_DONE

#include <float.h>
#include <math.h>
#include <stdlib.h> /* qsort */
#include <string.h>

#ifdef __cplusplus
extern "C" {
#endif

/* The Newton method's constants (Armijo, halvings, shift floor and cap, round-off and exact-phase
 * thresholds) are newton.h's WR_NEWTON_*. */
/* CCD keeps a vertex at >= this fraction of its current obstacle distance per Newton step (IPC uses
 * a similar safety fraction, 0.1–0.2, so iterates approach contact geometrically, never touching). */
#define WR_STATICS_CCD_KEEP 0.2
#define WR__STATICS_CCD_ITERS 64 /* conservative-advancement iterations; the result is safe at any count */
#define WR__STATICS_DHAT_REL 1e-3
/* relative gradient tolerance of the soft stages of the membrane continuation: they only have to
 * bring the shape near the final one (ON MEMBRANE CONTINUATION) */
#define WR_STATICS_RAMP_TOL 1e-6
#define WR__STATICS_RAMP_FACTOR 1e3
/* regularisation of the affine predictor towards the identity, relative to the prescribed vertices'
 * spread: small enough not to bias a well-posed fit, large enough for collinear or coplanar sets */
#define WR_STATICS_AFFINE_REG 1e-6

/* ---- pressure, obstacles, barrier --------------------------------------------------------------- */

static void wr__statics_skew(const double u[3], double S[9]) {
    S[0] = 0.0, S[1] = -u[2], S[2] = u[1];
    S[3] = u[2], S[4] = 0.0, S[5] = -u[0];
    S[6] = -u[1], S[7] = u[0], S[8] = 0.0;
}

WRDEF double wr_statics_pressure_element(const double x9[9], const double origin[3], double p, double *g, double *H) {
    double r[9], V;
    int a, i, j;
    for (a = 0; a < 3; ++a)
        for (i = 0; i < 3; ++i) r[3 * a + i] = x9[3 * a + i] - (origin ? origin[i] : 0.0);
    V = (r[0] * (r[4] * r[8] - r[5] * r[7]) + r[1] * (r[5] * r[6] - r[3] * r[8]) + r[2] * (r[3] * r[7] - r[4] * r[6])) /
        6.0;
    if (g)
        for (a = 0; a < 3; ++a) {
            /* ∂V/∂x_a = (1/6) r_b × r_c, (a, b, c) cyclic */
            const double *rb = r + 3 * ((a + 1) % 3), *rc = r + 3 * ((a + 2) % 3);
            g[3 * a] = -p * (rb[1] * rc[2] - rb[2] * rc[1]) / 6.0;
            g[3 * a + 1] = -p * (rb[2] * rc[0] - rb[0] * rc[2]) / 6.0;
            g[3 * a + 2] = -p * (rb[0] * rc[1] - rb[1] * rc[0]) / 6.0;
        }
    if (H) {
        memset(H, 0, sizeof(double) * 81);
        for (a = 0; a < 3; ++a) {
            /* ∂²V/∂x_a∂x_b = −(1/6)[r_c]×, (a, b, c) cyclic; the (b, a) block is its transpose */
            int b = (a + 1) % 3, c = (a + 2) % 3;
            double S[9];
            wr__statics_skew(r + 3 * c, S);
            for (i = 0; i < 3; ++i)
                for (j = 0; j < 3; ++j) {
                    H[(3 * a + i) * 9 + 3 * b + j] = p * S[3 * i + j] / 6.0;
                    H[(3 * b + j) * 9 + 3 * a + i] = p * S[3 * i + j] / 6.0;
                }
        }
    }
    return -p * V;
}

WRDEF double wr_statics_volume(const wr_shell *s, const double *x, const double origin[3], double *grad) {
    double V = 0.0, x9[9], g9[9];
    int32_t f, a, i;
    if (grad) memset(grad, 0, sizeof(double) * 3 * (size_t)s->nv);
    for (f = 0; f < s->nf; ++f) {
        for (a = 0; a < 3; ++a)
            for (i = 0; i < 3; ++i) x9[3 * a + i] = x[3 * s->faces[3 * f + a] + i];
        /* −p·V_f with p = −1 is V_f */
        V += wr_statics_pressure_element(x9, origin, -1.0, grad ? g9 : NULL, NULL);
        if (grad)
            for (a = 0; a < 3; ++a)
                for (i = 0; i < 3; ++i) grad[3 * s->faces[3 * f + a] + i] += g9[3 * a + i];
    }
    return V;
}

WRDEF double wr_obstacle_distance(const wr_obstacle *o, const double x[3], double grad[3]) {
    double r[3], n, dd;
    int i;
    if (o->kind == WR_OBSTACLE_MESH) return wr_obstacle_mesh_closest(o->mesh, x, NULL, grad, NULL);
    if (o->kind == WR_OBSTACLE_PLANE) {
        n = sqrt(o->normal[0] * o->normal[0] + o->normal[1] * o->normal[1] + o->normal[2] * o->normal[2]);
        dd = 0.0;
        for (i = 0; i < 3; ++i) {
            double u = n > 0.0 ? o->normal[i] / n : (i == 2 ? 1.0 : 0.0);
            dd += u * (x[i] - o->p[i]);
            if (grad) grad[i] = u;
        }
        return dd;
    }
    if (o->kind == WR_OBSTACLE_CAPSULE) {
        double ab[3], t = 0.0, l2 = 0.0;
        for (i = 0; i < 3; ++i) {
            ab[i] = o->q[i] - o->p[i];
            l2 += ab[i] * ab[i];
            t += ab[i] * (x[i] - o->p[i]);
        }
        t = l2 > 0.0 ? fmin(1.0, fmax(0.0, t / l2)) : 0.0;
        for (i = 0; i < 3; ++i) r[i] = x[i] - (o->p[i] + t * ab[i]);
    } else {
        for (i = 0; i < 3; ++i) r[i] = x[i] - o->p[i];
    }
    n = sqrt(r[0] * r[0] + r[1] * r[1] + r[2] * r[2]);
    if (grad)
        for (i = 0; i < 3; ++i) grad[i] = n > 0.0 ? r[i] / n : (i == 2 ? 1.0 : 0.0);
    return n - o->radius;
}

/* the IPC barrier lives in collision.h (one concept, one place); kept here under its old name */
WRDEF double wr_statics_barrier(double d, double dhat, double kappa, double *b1, double *b2) {
    return wr_collision_barrier(d, dhat, kappa, b1, b2);
}

/* ---- mesh obstacles (ON MESH OBSTACLES) ---------------------------------------------------------- */

WRDEF void wr_obstacle_mesh_free(wr_obstacle_mesh *m) {
    if (!m) return;
    wr_free(m->pos);
    wr_free(m->faces);
    wr_free(m->fn);
    wr_free(m->en);
    wr_free(m->vn);
    wr_bvh_free(&m->bvh);
    memset(m, 0, sizeof *m);
}

static void wr__obsmesh_unit(double *v) {
    double n = sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    if (n > 0.0) v[0] /= n, v[1] /= n, v[2] /= n;
}

/* unit face normals, angle-weighted vertex pseudonormals, face boxes (nf*6); WR_ERR_GEOMETRY on a
 * degenerate face */
static wr_status wr__obsmesh_faces(wr_obstacle_mesh *m, double *boxes, wr_diag *diag) {
    int32_t f, k, i;
    memset(m->vn, 0, sizeof(double) * 3 * (size_t)m->nv);
    for (f = 0; f < m->nf; ++f) {
        const int32_t *t = m->faces + 3 * f;
        const double *P[3];
        double e1[3], e2[3], *n = m->fn + 3 * f, area2, scale = 0.0;
        for (k = 0; k < 3; ++k) P[k] = m->pos + 3 * t[k];
        for (i = 0; i < 3; ++i) e1[i] = P[1][i] - P[0][i], e2[i] = P[2][i] - P[0][i];
        n[0] = e1[1] * e2[2] - e1[2] * e2[1];
        n[1] = e1[2] * e2[0] - e1[0] * e2[2];
        n[2] = e1[0] * e2[1] - e1[1] * e2[0];
        area2 = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
        for (i = 0; i < 3; ++i) scale += e1[i] * e1[i] + e2[i] * e2[i];
        if (t[0] == t[1] || t[1] == t[2] || t[2] == t[0] || !(area2 > 1e-12 * scale))
            return wr_fail(diag, WR_ERR_GEOMETRY, f, "obstacle mesh: face %d is degenerate (zero area)", (int)f);
        wr__obsmesh_unit(n);
        for (k = 0; k < 3; ++k) { /* corner angle at P[k] weights the vertex pseudonormal */
            const double *a = P[k], *b = P[(k + 1) % 3], *c = P[(k + 2) % 3];
            double u[3], w[3], cr[3], ang;
            for (i = 0; i < 3; ++i) u[i] = b[i] - a[i], w[i] = c[i] - a[i];
            cr[0] = u[1] * w[2] - u[2] * w[1], cr[1] = u[2] * w[0] - u[0] * w[2], cr[2] = u[0] * w[1] - u[1] * w[0];
            ang = atan2(sqrt(cr[0] * cr[0] + cr[1] * cr[1] + cr[2] * cr[2]), u[0] * w[0] + u[1] * w[1] + u[2] * w[2]);
            for (i = 0; i < 3; ++i) m->vn[3 * t[k] + i] += ang * n[i];
        }
        for (i = 0; i < 3; ++i) {
            boxes[6 * f + i] = fmin(P[0][i], fmin(P[1][i], P[2][i]));
            boxes[6 * f + 3 + i] = fmax(P[0][i], fmax(P[1][i], P[2][i]));
        }
    }
    for (i = 0; i < m->nv; ++i) wr__obsmesh_unit(m->vn + 3 * i);
    return WR_OK;
}

typedef struct wr__obsmesh_he {
    uint64_t key; /* (min vertex, max vertex) */
    int32_t he;   /* 3f + k */
} wr__obsmesh_he;

static int wr__obsmesh_he_cmp(const void *a, const void *b) {
    const wr__obsmesh_he *x = (const wr__obsmesh_he *)a, *y = (const wr__obsmesh_he *)b;
    return x->key < y->key ? -1 : (x->key > y->key ? 1 : (x->he > y->he) - (x->he < y->he));
}

/* edge pseudonormals: the normalised sum of the unit normals of the faces sharing the edge */
static wr_status wr__obsmesh_edges(wr_obstacle_mesh *m, wr_diag *diag) {
    int32_t n = 3 * m->nf, i, j, k;
    wr__obsmesh_he *h = (wr__obsmesh_he *)wr_alloc_array((size_t)n, sizeof(wr__obsmesh_he));
    if (!h) return wr_fail(diag, WR_ERR_NOMEM, -1, "obstacle mesh: out of memory (%d faces)", (int)m->nf);
    for (i = 0; i < n; ++i) {
        uint64_t a = (uint64_t)m->faces[i], b = (uint64_t)m->faces[3 * (i / 3) + (i % 3 + 1) % 3];
        h[i].key = a < b ? (a << 32 | b) : (b << 32 | a);
        h[i].he = i;
    }
    qsort(h, (size_t)n, sizeof *h, wr__obsmesh_he_cmp);
    m->n_open_edges = 0;
    for (i = 0; i < n; i = j) {
        double s[3] = {0.0, 0.0, 0.0};
        for (j = i; j < n && h[j].key == h[i].key; ++j)
            for (k = 0; k < 3; ++k) s[k] += m->fn[3 * (h[j].he / 3) + k];
        if (j - i == 1) m->n_open_edges++;
        wr__obsmesh_unit(s);
        for (k = i; k < j; ++k) memcpy(m->en + 3 * h[k].he, s, sizeof s);
    }
    wr_free(h);
    return WR_OK;
}

WRDEF wr_status wr_obstacle_mesh_create(wr_obstacle_mesh *m, const double *V, int32_t nv, const int32_t *F, int32_t nf,
                                        wr_diag *diag) {
    double *boxes;
    int32_t i;
    wr_status rs;
    if (!m) return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "obstacle mesh: NULL mesh");
    memset(m, 0, sizeof *m);
    if (!V || !F || nv < 3 || nf < 1)
        return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "obstacle mesh: %d vertices, %d faces (needs >= 3 and >= 1)", (int)nv,
                       (int)nf);
    for (i = 0; i < 3 * nv; ++i)
        if (!(V[i] - V[i] == 0.0))
            return wr_fail(diag, WR_ERR_DOMAIN, i / 3, "obstacle mesh: vertex %d is not finite", (int)(i / 3));
    for (i = 0; i < 3 * nf; ++i)
        if (F[i] < 0 || F[i] >= nv)
            return wr_fail(diag, WR_ERR_INVALID_ARG, i / 3, "obstacle mesh: face %d has vertex %d outside [0, %d)",
                           (int)(i / 3), (int)F[i], (int)nv);
    m->nv = nv, m->nf = nf;
    m->pos = (double *)wr_alloc_array(3 * (size_t)nv, sizeof(double));
    m->faces = (int32_t *)wr_alloc_array(3 * (size_t)nf, sizeof(int32_t));
    m->fn = (double *)wr_alloc_array(3 * (size_t)nf, sizeof(double));
    m->en = (double *)wr_alloc_array(9 * (size_t)nf, sizeof(double));
    m->vn = (double *)wr_alloc_array(3 * (size_t)nv, sizeof(double));
    boxes = (double *)wr_alloc_array(6 * (size_t)nf, sizeof(double));
    if (!m->pos || !m->faces || !m->fn || !m->en || !m->vn || !boxes) {
        rs = wr_fail(diag, WR_ERR_NOMEM, -1, "obstacle mesh: out of memory (%d faces)", (int)nf);
        goto done;
    }
    memcpy(m->pos, V, sizeof(double) * 3 * (size_t)nv);
    memcpy(m->faces, F, sizeof(int32_t) * 3 * (size_t)nf);
    if ((rs = wr__obsmesh_faces(m, boxes, diag)) == WR_OK && (rs = wr__obsmesh_edges(m, diag)) == WR_OK)
        rs = wr_bvh_build(&m->bvh, nf, boxes, diag);
done:
    wr_free(boxes);
    if (rs != WR_OK) wr_obstacle_mesh_free(m);
    return rs;
}

typedef struct wr__obsmesh_q {
    const wr_obstacle_mesh *m;
    const double *x;
} wr__obsmesh_q;

static double wr__obsmesh_dist2(void *user, int32_t f) {
    const wr__obsmesh_q *q = (const wr__obsmesh_q *)user;
    const int32_t *t = q->m->faces + 3 * f;
    const double *P = q->m->pos;
    return wr_collision_point_triangle_dist2(q->x, P + 3 * t[0], P + 3 * t[1], P + 3 * t[2], NULL, NULL, NULL, NULL);
}

WRDEF double wr_obstacle_mesh_closest(const wr_obstacle_mesh *m, const double x[3], double closest[3], double grad[3],
                                      int32_t *face) {
    wr__obsmesh_q q;
    const double *P, *pn;
    const int32_t *t;
    double w[4], c[3], r[3], rr, side;
    int32_t f, i, nz = 0, last = 0, first = -1;
    q.m = m, q.x = x;
    wr_bvh_nearest(&m->bvh, x, wr__obsmesh_dist2, &q, &f);
    if (face) *face = f;
    if (f < 0) return HUGE_VAL;
    t = m->faces + 3 * f, P = m->pos;
    wr_collision_point_triangle_dist2(x, P + 3 * t[0], P + 3 * t[1], P + 3 * t[2], NULL, NULL, w, NULL);
    for (i = 0; i < 3; ++i) {
        c[i] = -(w[1] * P[3 * t[0] + i] + w[2] * P[3 * t[1] + i] + w[3] * P[3 * t[2] + i]);
        r[i] = x[i] - c[i];
    }
    /* the closest feature from the barycentric weights (exact zeros off it): face, edge or vertex */
    for (i = 0; i < 3; ++i)
        if (w[1 + i] != 0.0) {
            if (first < 0) first = i;
            last = i, ++nz;
        }
    if (nz == 3)
        pn = m->fn + 3 * f;
    else if (nz == 2) /* edge (first, last): index first unless it is the edge (2, 0) */
        pn = m->en + 9 * f + 3 * (first == 0 && last == 2 ? 2 : first);
    else
        pn = m->vn + 3 * t[first < 0 ? 0 : first];
    rr = sqrt(r[0] * r[0] + r[1] * r[1] + r[2] * r[2]);
    side = r[0] * pn[0] + r[1] * pn[1] + r[2] * pn[2] < 0.0 ? -1.0 : 1.0;
    if (closest) memcpy(closest, c, sizeof c);
    if (grad)
        for (i = 0; i < 3; ++i) grad[i] = rr > 0.0 ? side * r[i] / rr : pn[i];
    return side * rr;
}

/* the IPC sum of ON MESH OBSTACLES over the faces within d̂ of one point */
typedef struct wr__obsmesh_sum {
    const wr_obstacle_mesh *m;
    const double *x;
    double dhat, kappa, E, g[3], H[9];
} wr__obsmesh_sum;

static wr_status wr__obsmesh_sum_face(void *user, int32_t f) {
    wr__obsmesh_sum *q = (wr__obsmesh_sum *)user;
    const int32_t *t = q->m->faces + 3 * f;
    const double *P = q->m->pos;
    double gs[12], s = wr_collision_point_triangle_dist2(q->x, P + 3 * t[0], P + 3 * t[1], P + 3 * t[2], gs, NULL, NULL, NULL);
    double d = sqrt(s), b1, b2, gd[3];
    int i, j;
    if (!(d < q->dhat)) return WR_OK;
    q->E += wr_statics_barrier(d, q->dhat, q->kappa, &b1, &b2);
    if (!(d > 0.0)) return WR_OK;
    for (i = 0; i < 3; ++i) gd[i] = gs[i] / (2.0 * d);
    for (i = 0; i < 3; ++i) {
        q->g[i] += b1 * gd[i];
        for (j = 0; j < 3; ++j) q->H[3 * i + j] += b2 * gd[i] * gd[j];
    }
    return WR_OK;
}

static double wr__obsmesh_barrier(const wr_obstacle_mesh *m, const double x[3], double dhat, double kappa, double g[3],
                                  double H[9]) {
    wr__obsmesh_sum q;
    double box[6];
    int i;
    memset(&q, 0, sizeof q);
    q.m = m, q.x = x, q.dhat = dhat, q.kappa = kappa;
    for (i = 0; i < 3; ++i) box[i] = x[i] - dhat, box[3 + i] = x[i] + dhat;
    wr_bvh_box_query(&m->bvh, box, wr__obsmesh_sum_face, &q, NULL);
    if (g) memcpy(g, q.g, sizeof q.g);
    if (H) memcpy(H, q.H, sizeof q.H);
    return q.E;
}

WRDEF double wr_obstacle_barrier(const wr_obstacle *o, const double x[3], double dhat, double kappa, double *dist,
                                 double g[3], double H[9]) {
    double gd[3], b1 = 0.0, b2 = 0.0, d = wr_obstacle_distance(o, x, gd), E;
    int i, j;
    if (dist) *dist = d;
    if (o->kind == WR_OBSTACLE_MESH && d > 0.0 && d < dhat) return wr__obsmesh_barrier(o->mesh, x, dhat, kappa, g, H);
    E = d < dhat ? wr_statics_barrier(d, dhat, kappa, &b1, &b2) : 0.0;
    if (!(d > 0.0)) b1 = b2 = 0.0;
    if (g)
        for (i = 0; i < 3; ++i) g[i] = b1 * gd[i];
    if (H)
        for (i = 0; i < 3; ++i)
            for (j = 0; j < 3; ++j) H[3 * i + j] = b2 * gd[i] * gd[j];
    return E;
}

/* ---- the solver: Π as a newton.h problem ----------------------------------------------------- */

typedef struct wr__statics_ctx {
    const wr_shell *s;
    const wr_statics_desc *d; /* with defaults */
    double *fext, *mass;      /* nv*3 external load [N], nv lumped masses [kg] (owned) */
    uint8_t *fixd;            /* nv*3 fixed DOFs (owned) */
    const uint8_t *fixv;      /* per vertex, may be NULL */
    double p, origin[3], bbox;
    const wr_obstacle *obs;
    int32_t nobs;
    double dhat, kappa;
    /* the Hessian stream of one Newton step (wr__statics_hessian) */
    wr_newton_hessian *H;
    const double *x;
    int32_t face; /* next face whose block is expected (pressure folded into it) */
    /* progress: the figures newton.h does not know */
    wr_statics_stats *st;
    double t_start;
} wr__statics_ctx;

/* Π and ∇Π (gradient zeroed on fixed DOFs when g != NULL); scale = Σ|terms of Π| (newton.h ON
 * STOPPING). WR_ERR_GEOMETRY (item = vertex) when a free vertex is on or inside an obstacle. */
static wr_status wr__statics_energy(void *user, const double *x, double *Pi, double *g, double *scale, wr_diag *diag) {
    const wr__statics_ctx *c = (const wr__statics_ctx *)user;
    const wr_shell *s = c->s;
    double E, sc = 0.0;
    int32_t i, n = 3 * s->nv, v, o;
    wr_status st = wr_shell_energy(s, x, &E, g, diag);
    if (st != WR_OK) return st;
    sc = fabs(E);
    if (c->p != 0.0) {
        int32_t f, a;
        for (f = 0; f < s->nf; ++f) {
            double x9[9], g9[9];
            for (a = 0; a < 3; ++a)
                for (i = 0; i < 3; ++i) x9[3 * a + i] = x[3 * s->faces[3 * f + a] + i];
            double ef = wr_statics_pressure_element(x9, c->origin, c->p, g ? g9 : NULL, NULL);
            E += ef;
            sc += fabs(ef);
            if (g)
                for (a = 0; a < 3; ++a)
                    for (i = 0; i < 3; ++i) g[3 * s->faces[3 * f + a] + i] += g9[3 * a + i];
        }
    }
    for (o = 0; o < c->nobs; ++o)
        for (v = 0; v < s->nv; ++v) {
            double gb[3], d, eb;
            if (c->fixv && c->fixv[v]) continue;
            eb = wr_obstacle_barrier(c->obs + o, x + 3 * v, c->dhat, c->kappa, &d, g ? gb : NULL, NULL);
            if (!(d > 0.0))
                return wr_fail(diag, WR_ERR_GEOMETRY, v, "statics: vertex %d is %.3e m inside obstacle %d", (int)v, -d,
                               (int)o);
            if (d >= c->dhat) continue;
            E += eb;
            sc += eb;
            if (g)
                for (i = 0; i < 3; ++i) g[3 * v + i] += gb[i];
        }
    for (i = 0; i < n; ++i) {
        E -= c->fext[i] * x[i];
        sc += fabs(c->fext[i] * x[i]);
        if (g) g[i] = (c->fixv && c->fixv[i / 3]) ? 0.0 : g[i] - c->fext[i];
    }
    if (!(E - E == 0.0)) return wr_fail(diag, WR_ERR_DOMAIN, -1, "statics: potential is not finite");
    *Pi = E;
    if (scale) *scale = sc;
    return WR_OK;
}

/* Adds one solve's work counters and timings to a running total (continuation stages, load increments);
 * iteration counts are kept by the callers because each totals them differently. */
static void wr__statics_work_add(wr_statics_stats *to, const wr_statics_stats *from) {
    to->linear_iterations += from->linear_iterations;
    to->line_search_evals += from->line_search_evals;
    to->t_assembly += from->t_assembly;
    to->t_projection += from->t_projection;
    to->t_linear += from->t_linear;
    to->t_line_search += from->t_line_search;
    to->elements_projected += from->elements_projected;
    to->elements_assembled += from->elements_assembled;
}

/* newton.h max_step: the largest α in (0, 1] keeping every free vertex at >= WR_STATICS_CCD_KEEP of
 * its current distance to every obstacle along x + αΔx (conservative advancement: d is 1-Lipschitz,
 * so advancing by (d − target)/|Δx| can never overshoot the target distance). */
static double wr__statics_ccd(void *user, const double *x, const double *dx) {
    const wr__statics_ctx *c = (const wr__statics_ctx *)user;
    double alpha = 1.0;
    int32_t v, o, it, i;
    for (o = 0; o < c->nobs; ++o)
        for (v = 0; v < c->s->nv; ++v) {
            double d0, speed, target, t = 0.0, p[3];
            if (c->fixv && c->fixv[v]) continue;
            speed = sqrt(dx[3 * v] * dx[3 * v] + dx[3 * v + 1] * dx[3 * v + 1] + dx[3 * v + 2] * dx[3 * v + 2]);
            if (speed == 0.0) continue;
            d0 = wr_obstacle_distance(c->obs + o, x + 3 * v, NULL);
            if (speed <= (1.0 - WR_STATICS_CCD_KEEP) * d0) continue; /* cannot reach the target at α = 1 */
            target = WR_STATICS_CCD_KEEP * d0;
            for (it = 0; it < WR__STATICS_CCD_ITERS && t < alpha; ++it) {
                double gap;
                for (i = 0; i < 3; ++i) p[i] = x[3 * v + i] + t * dx[3 * v + i];
                gap = wr_obstacle_distance(c->obs + o, p, NULL) - target;
                if (gap <= 1e-6 * d0) break; /* at the target distance (to 1e-6 of the start distance) */
                t += gap / speed;
            }
            if (t < alpha) alpha = t;
        }
    return alpha;
}

/* shell.h element stream → newton.h: each face's pressure Hessian folded into its elastic block before
 * the projection (ON PRESSURE); shell.h streams one block per face, in face order, corners first (its
 * ON ELEMENT HESSIANS). Large stencils (quadratic bending at high valence) are PSD by construction. */
static wr_status wr__statics_sink_add(void *user, int32_t k, const int32_t *verts, const double *Ke) {
    wr__statics_ctx *c = (wr__statics_ctx *)user;
    const wr_shell *s = c->s;
    double buf[WR_DENSE_MAX * WR_DENSE_MAX];
    int32_t a, i, n = 3 * k;
    if (n > WR_DENSE_MAX) return wr_newton_add_element_psd(c->H, k, verts, Ke);
    memcpy(buf, Ke, sizeof(double) * (size_t)(n * n));
    if (c->p != 0.0 && k >= 3 && c->face < s->nf && verts[0] == s->faces[3 * c->face] &&
        verts[1] == s->faces[3 * c->face + 1] && verts[2] == s->faces[3 * c->face + 2]) {
        double x9[9], H9[81];
        int j, b;
        for (a = 0; a < 3; ++a)
            for (i = 0; i < 3; ++i) x9[3 * a + i] = c->x[3 * verts[a] + i];
        wr_statics_pressure_element(x9, c->origin, c->p, NULL, H9);
        for (a = 0; a < 3; ++a)
            for (b = 0; b < 3; ++b)
                for (i = 0; i < 3; ++i)
                    for (j = 0; j < 3; ++j) buf[(3 * a + i) * n + 3 * b + j] += H9[(3 * a + i) * 9 + 3 * b + j];
        c->face++;
    }
    return wr_newton_add_element(c->H, k, verts, buf);
}

/* faces without an elastic block: their pressure block projected on its own (ON PRESSURE) */
static wr_status wr__statics_pressure_rest(wr__statics_ctx *c, const double *x, wr_diag *diag) {
    const wr_shell *s = c->s;
    for (; c->face < s->nf; ++c->face) {
        double x9[9], H9[81];
        int32_t a, k;
        wr_status rs;
        for (a = 0; a < 3; ++a)
            for (k = 0; k < 3; ++k) x9[3 * a + k] = x[3 * s->faces[3 * c->face + a] + k];
        wr_statics_pressure_element(x9, c->origin, c->p, NULL, H9);
        if ((rs = wr_newton_add_element(c->H, 3, s->faces + 3 * c->face, H9)) != WR_OK)
            return wr_fail(diag, rs, c->face, "statics: pressure block of face %d rejected", (int)c->face);
    }
    return WR_OK;
}

/* Vertex-diagonal contact blocks κ b''(d) ∇d∇dᵀ (ON CONTACT) */
static wr_status wr__statics_contact_hessian(const wr__statics_ctx *c, const double *x, wr_diag *diag) {
    int32_t o, v;
    for (o = 0; o < c->nobs; ++o)
        for (v = 0; v < c->s->nv; ++v) {
            double d, B[9];
            if (c->fixv && c->fixv[v]) continue;
            wr_obstacle_barrier(c->obs + o, x + 3 * v, c->dhat, c->kappa, &d, NULL, B);
            if (!(d < c->dhat) || !(d > 0.0)) continue;
            if (wr_newton_add_diagonal(c->H, v, B) != WR_OK)
                return wr_fail(diag, WR_ERR_INVALID_ARG, v, "statics: contact block of vertex %d rejected", (int)v);
        }
    return WR_OK;
}

/* newton.h hessian: faces, the constant quadratic bending, leftover pressure faces, contact */
static wr_status wr__statics_hessian(void *user, const double *x, wr_newton_hessian *H, wr_diag *diag) {
    wr__statics_ctx *c = (wr__statics_ctx *)user;
    wr_hess_sink hs;
    wr_status rs;
    c->H = H;
    c->x = x;
    c->face = 0;
    hs.user = c;
    hs.add = wr__statics_sink_add;
    /* the sink projects blocks up to WR_DENSE_MAX per Newton's mode; larger ones (the Loop element)
     * the shell projects in its own point space when Newton projects (shell.h ON THE LOOP ELEMENT) */
    if ((rs = wr_shell_hessian_elements_part(c->s, x, wr_newton_hessian_exact(H) ? 0 : WR_SHELL_PROJECT_LARGE,
                                             WR_SHELL_HESS_FACES, &hs, diag)) != WR_OK)
        return rs;
    /* ON ASSEMBLY CACHE: the quadratic-bending blocks (TFW Eq. 28) do not depend on x and are PSD, so
     * the FAST projection and the exact Hessian keep them: summed once. Jacobi rounds them each time. */
    if (c->d->hessian.projection == WR_PROJECT_JACOBI) {
        rs = wr_shell_hessian_elements_part(c->s, x, 0, WR_SHELL_HESS_QUADRATIC, &hs, diag);
    } else {
        if (wr_newton_constant_begin(H)) rs = wr_shell_hessian_elements_part(c->s, x, 0, WR_SHELL_HESS_QUADRATIC, &hs, diag);
        wr_newton_constant_end(H);
    }
    if (rs != WR_OK) return rs;
    if (c->p != 0.0 && (rs = wr__statics_pressure_rest(c, x, diag)) != WR_OK) return rs;
    return wr__statics_contact_hessian(c, x, diag);
}

static double wr__statics_norm(const double *v, int32_t n) {
    double s = 0.0;
    int32_t i;
    for (i = 0; i < n; ++i) s += v[i] * v[i];
    return sqrt(s);
}

static wr_status wr__statics_check_obstacles(const wr_obstacle *obs, int32_t n, wr_diag *diag) {
    int32_t o, i;
    if (n < 0 || (n > 0 && !obs))
        return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "statics: %d obstacles with a NULL array", (int)n);
    for (o = 0; o < n; ++o) {
        const wr_obstacle *b = obs + o;
        double nn = 0.0, fin = b->radius;
        for (i = 0; i < 3; ++i) {
            nn += b->normal[i] * b->normal[i];
            fin += b->p[i] + b->q[i] + b->normal[i];
        }
        if (!(fin - fin == 0.0)) return wr_fail(diag, WR_ERR_INVALID_ARG, o, "statics: obstacle %d has non-finite data", (int)o);
        if (b->kind == WR_OBSTACLE_PLANE) {
            if (!(nn > 0.0)) return wr_fail(diag, WR_ERR_INVALID_ARG, o, "statics: plane obstacle %d has a zero normal", (int)o);
        } else if (b->kind == WR_OBSTACLE_MESH) {
            if (!b->mesh || b->mesh->nf < 1 || b->mesh->bvh.n != b->mesh->nf)
                return wr_fail(diag, WR_ERR_INVALID_ARG, o, "statics: mesh obstacle %d has no mesh (wr_obstacle_mesh_create)",
                               (int)o);
        } else if (b->kind == WR_OBSTACLE_SPHERE || b->kind == WR_OBSTACLE_CAPSULE) {
            if (!(b->radius > 0.0))
                return wr_fail(diag, WR_ERR_INVALID_ARG, o, "statics: obstacle %d radius %g must be > 0", (int)o, b->radius);
        } else {
            return wr_fail(diag, WR_ERR_INVALID_ARG, o, "statics: obstacle %d has unknown kind %d", (int)o, (int)b->kind);
        }
    }
    return WR_OK;
}

/* The defaults of wr_statics_desc (the comment above it), and its validation. */
static wr_status wr__statics_defaults(wr_statics_desc *d, const wr_statics_desc *desc, wr_diag *diag) {
    if (desc)
        *d = *desc;
    else
        memset(d, 0, sizeof *d);
    if (d->stop.max_iter == 0) d->stop.max_iter = 200;
    if (d->stop.grad_tol == 0.0) d->stop.grad_tol = 1e-8;
    if (d->stop.step_tol == 0.0) d->stop.step_tol = 1e-13;
    if (d->shift.rel == 0.0) d->shift.rel = 1e-8;
    if (d->continuation.factor == 0.0) d->continuation.factor = WR__STATICS_RAMP_FACTOR;
    if (d->increments.grad_tol == 0.0) d->increments.grad_tol = d->stop.grad_tol;
    if (d->stop.max_iter < 0 || !(d->stop.grad_tol > 0.0) || !(d->stop.step_tol > 0.0) || !(d->shift.rel > 0.0) ||
        !(d->start.perturb >= 0.0) || !(d->increments.grad_tol > 0.0) || !(d->stop.decrement_tol >= 0.0))
        return wr_fail(diag, WR_ERR_INVALID_ARG, -1,
                       "statics: stop.max_iter %d, stop.grad_tol %g, stop.step_tol %g, shift.rel %g, "
                       "increments.grad_tol %g must be positive, start.perturb %g and stop.decrement_tol %g >= 0",
                       (int)d->stop.max_iter, d->stop.grad_tol, d->stop.step_tol, d->shift.rel, d->increments.grad_tol,
                       d->start.perturb, d->stop.decrement_tol);
    if (!(d->loads.pressure - d->loads.pressure == 0.0) || !(d->contact.dhat >= 0.0) || !(d->contact.stiffness >= 0.0) ||
        d->contact.dhat - d->contact.dhat != 0.0 || d->contact.stiffness - d->contact.stiffness != 0.0)
        return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "statics: loads.pressure %g, contact.dhat %g, contact.stiffness %g invalid",
                       d->loads.pressure, d->contact.dhat, d->contact.stiffness);
    if (d->continuation.membrane_ramp != 0.0 &&
        (!(d->continuation.membrane_ramp > 0.0 && d->continuation.membrane_ramp < 1.0) ||
         !(d->continuation.factor > 1.0) || d->continuation.factor - d->continuation.factor != 0.0))
        return wr_fail(diag, WR_ERR_INVALID_ARG, -1,
                       "statics: continuation.membrane_ramp %g must be in (0, 1) and continuation.factor %g > 1",
                       d->continuation.membrane_ramp, d->continuation.factor);
    {
        /* the Newton options (hessian, shift, linear) by newton.h's own check, before anything is touched */
        wr_newton_desc nd;
        wr_status rs;
        memset(&nd, 0, sizeof nd);
        nd.hessian = d->hessian;
        nd.shift = d->shift;
        nd.linear = d->linear;
        nd.name = "statics";
        if ((rs = wr_newton_desc_check(&nd, diag)) != WR_OK) return rs;
    }
    if (d->stability.check != 0 &&
        (d->stability.check < 0 || d->stability.check > 2 || d->stability.n_modes < 0 || d->stability.n_modes > 64 || d->stability.max_rounds < 0 ||
         !(d->stability.neg_tol >= 0.0) || !(d->stability.amplitude >= 0.0) || d->stability.amplitude - d->stability.amplitude != 0.0))
        return wr_fail(diag, WR_ERR_INVALID_ARG, -1,
                       "statics: stability.check %d (0, 1 or 2), n_modes %d (0..64), max_rounds %d, neg_tol %g, amplitude %g invalid",
                       (int)d->stability.check, (int)d->stability.n_modes, (int)d->stability.max_rounds, d->stability.neg_tol,
                       d->stability.amplitude);
#if !(defined(WR_USE_ARPACK) && WR_USE_ARPACK && defined(WR_USE_CHOLMOD) && WR_USE_CHOLMOD)
    if (d->stability.check)
        return wr_fail(diag, WR_ERR_UNSUPPORTED, -1,
                       "statics: stability.check needs eigen.h's ARPACK and CHOLMOD (WR_USE_ARPACK=1, WR_USE_CHOLMOD=1)");
#endif
    return wr__statics_check_obstacles(d->contact.obstacles, d->contact.n_obstacles, diag);
}

/* external load (lumped gravity m_v g), prescribed DOFs at their targets, finite start, and the
 * pressure's closed-surface condition (ON PRESSURE) */
static wr_status wr__statics_loads(wr__statics_ctx *c, double *x, wr_diag *diag) {
    const wr_shell *s = c->s;
    const wr_statics_loads_desc *L = &c->d->loads;
    int32_t i, n = 3 * s->nv, f, k;
    c->fext = (double *)wr_calloc_array((size_t)n, sizeof(double));
    c->mass = (double *)wr_alloc_array((size_t)s->nv, sizeof(double));
    c->fixd = (uint8_t *)wr_calloc_array((size_t)n, 1);
    if (!c->fext || !c->mass || !c->fixd) return wr_fail(diag, WR_ERR_NOMEM, -1, "statics: out of memory (%d DOFs)", (int)n);
    wr_shell_vertex_masses(s, c->mass);
    for (i = 0; i < n; ++i) c->fext[i] = c->mass[i / 3] * L->gravity[i % 3];
    if (L->fixed)
        for (i = 0; i < n; ++i) {
            c->fixd[i] = L->fixed[i / 3] != 0;
            if (c->fixd[i] && L->target) x[i] = L->target[i];
        }
    for (i = 0; i < n; ++i)
        if (!(x[i] == x[i]) || x[i] - x[i] != 0.0)
            return wr_fail(diag, WR_ERR_DOMAIN, i / 3, "statics: vertex %d has a non-finite coordinate", (int)(i / 3));
    if (L->pressure == 0.0) return WR_OK;
    /* V depends on the origin through an open boundary unless that boundary is prescribed */
    for (f = 0; f < s->nf; ++f)
        for (k = 0; k < 3; ++k)
            if (s->opp[3 * f + k] < 0) {
                int32_t va = s->faces[3 * f + (k + 1) % 3], vb = s->faces[3 * f + (k + 2) % 3];
                int32_t bad = !c->fixd[3 * va] ? va : (!c->fixd[3 * vb] ? vb : -1);
                if (bad >= 0)
                    return wr_fail(diag, WR_ERR_UNSUPPORTED, bad,
                                   "statics: pressure on an open surface with free boundary vertex %d (sew it closed "
                                   "or prescribe the boundary)",
                                   (int)bad);
            }
    return WR_OK;
}

/* seeded kick along area-weighted vertex normals (flat starts are saddle points of buckling) */
static wr_status wr__statics_perturb(const wr__statics_ctx *c, double *x, wr_diag *diag) {
    const wr_shell *s = c->s;
    double *nrm;
    wr_rng rng;
    int32_t f, k, i;
    if (!(c->d->start.perturb > 0.0)) return WR_OK;
    nrm = (double *)wr_calloc_array(3 * (size_t)s->nv, sizeof(double));
    if (!nrm) return wr_fail(diag, WR_ERR_NOMEM, -1, "statics: out of memory (%d vertices)", (int)s->nv);
    for (f = 0; f < s->nf; ++f) {
        const int32_t *t = s->faces + 3 * f;
        wr_vec3 e1 = wr_v3_sub(wr_v3_load(x + 3 * t[1]), wr_v3_load(x + 3 * t[0]));
        wr_vec3 e2 = wr_v3_sub(wr_v3_load(x + 3 * t[2]), wr_v3_load(x + 3 * t[0]));
        wr_vec3 cr = wr_v3_cross(e1, e2);
        for (k = 0; k < 3; ++k) {
            nrm[3 * t[k]] += cr.x;
            nrm[3 * t[k] + 1] += cr.y;
            nrm[3 * t[k] + 2] += cr.z;
        }
    }
    wr_rng_seed(&rng, c->d->start.seed);
    for (i = 0; i < s->nv; ++i) {
        wr_vec3 nv = wr_v3_normalized(wr_v3_load(nrm + 3 * i));
        double a = c->d->start.perturb * wr_rng_normal(&rng);
        if (c->fixd[3 * i]) continue;
        x[3 * i] += a * nv.x;
        x[3 * i + 1] += a * nv.y;
        x[3 * i + 2] += a * nv.z;
    }
    wr_free(nrm);
    return WR_OK;
}

/* the pressure origin (centroid of x0), the bounding-box diagonal, and the ON CONTACT defaults */
static wr_status wr__statics_frame(wr__statics_ctx *c, const double *x, wr_diag *diag) {
    const wr_shell *s = c->s;
    const wr_statics_desc *d = c->d;
    double lo[3] = {1e300, 1e300, 1e300}, hi[3] = {-1e300, -1e300, -1e300}, fref = 0.0, *av, gn;
    int32_t i, f, k, n = 3 * s->nv;
    for (i = 0; i < n; ++i) {
        lo[i % 3] = fmin(lo[i % 3], x[i]);
        hi[i % 3] = fmax(hi[i % 3], x[i]);
        c->origin[i % 3] += x[i] / s->nv;
    }
    c->bbox = sqrt((hi[0] - lo[0]) * (hi[0] - lo[0]) + (hi[1] - lo[1]) * (hi[1] - lo[1]) + (hi[2] - lo[2]) * (hi[2] - lo[2]));
    if (c->nobs == 0) return WR_OK;
    c->dhat = d->contact.dhat > 0.0 ? d->contact.dhat : WR__STATICS_DHAT_REL * c->bbox;
    if (!(c->dhat > 0.0)) c->dhat = WR__STATICS_DHAT_REL;
    av = (double *)wr_calloc_array((size_t)s->nv, sizeof(double));
    if (!av) return wr_fail(diag, WR_ERR_NOMEM, -1, "statics: out of memory (%d vertices)", (int)s->nv);
    for (f = 0; f < s->nf; ++f)
        for (k = 0; k < 3; ++k) av[s->faces[3 * f + k]] += s->area[f] / 3.0;
    gn = sqrt(d->loads.gravity[0] * d->loads.gravity[0] + d->loads.gravity[1] * d->loads.gravity[1] +
              d->loads.gravity[2] * d->loads.gravity[2]);
    for (i = 0; i < s->nv; ++i) fref = fmax(fref, c->mass[i] * gn + fabs(d->loads.pressure) * av[i]);
    wr_free(av);
    if (!(fref > 0.0)) fref = 1e-3 * fabs(s->C_mem[0]) * sqrt(2.0 * s->total_area / s->nf);
    if (!(fref > 0.0)) fref = 1e-3 * s->bending_stiffness / sqrt(2.0 * s->total_area / s->nf);
    c->kappa = d->contact.stiffness > 0.0 ? d->contact.stiffness : 10.0 * fref / c->dhat;
    if (!(c->kappa > 0.0)) c->kappa = 1.0;
    return WR_OK;
}

/* newton.h progress → the caller's, with the statics figures */
static void wr__statics_from_newton(wr_statics_stats *st, const wr_newton_stats *ns) {
    st->iterations = ns->iterations;
    st->linear_iterations = ns->linear_iterations;
    st->line_search_evals = ns->line_search_evals;
    st->energy = ns->energy;
    st->grad_norm = ns->grad_norm;
    st->grad_norm0 = ns->grad_norm0;
    st->grad_ref = ns->grad_ref;
    st->last_step = ns->last_step;
    st->shift = ns->shift;
    st->stop = ns->stop;
    st->t_assembly = ns->t_assembly;
    st->t_projection = ns->t_projection;
    st->t_linear = ns->t_linear;
    st->t_line_search = ns->t_line_search;
    st->elements_projected = ns->elements_projected;
    st->elements_assembled = ns->elements_assembled;
    st->ccd_alpha_min = ns->max_step_min;
    st->exact_steps = ns->exact_steps;
}

static void wr__statics_progress(void *user, const wr_newton_stats *ns) {
    const wr__statics_ctx *c = (const wr__statics_ctx *)user;
    wr_statics_stats st = *c->st;
    wr__statics_from_newton(&st, ns);
    st.t_total = wr_time_seconds() - c->t_start;
    c->d->progress(c->d->progress_user, &st);
}

/* Newton on Π (newton.h) from the prepared x; the reference of ON STOPPING is gref_fixed when > 0,
 * else max(‖∇Π(x0)‖, ‖f_ext,free‖) */
static wr_status wr__statics_newton(wr__statics_ctx *c, double *x, double gref_fixed, wr_statics_stats *st,
                                    wr_diag *diag) {
    wr_newton_problem p;
    wr_newton_desc nd;
    wr_newton_stats ns;
    double fe = 0.0;
    int32_t i;
    wr_status rs;
    for (i = 0; i < 3 * c->s->nv; ++i)
        if (!c->fixd[i]) fe += c->fext[i] * c->fext[i];
    memset(&p, 0, sizeof p);
    p.n_blocks = c->s->nv;
    p.block = 3;
    p.user = c;
    p.energy = wr__statics_energy;
    p.hessian = wr__statics_hessian;
    p.max_step = c->nobs > 0 ? wr__statics_ccd : NULL;
    p.progress = c->d->progress ? wr__statics_progress : NULL;
    memset(&nd, 0, sizeof nd);
    nd.max_iter = c->d->stop.max_iter;
    nd.fixed = c->fixd;
    nd.stop.grad_tol = c->d->stop.grad_tol;
    nd.stop.grad_ref = gref_fixed > 0.0 ? gref_fixed : 0.0;
    nd.stop.grad_ref_min = sqrt(fe);
    nd.stop.step_tol = c->d->stop.step_tol * c->bbox;
    nd.stop.decrement_tol = c->d->stop.decrement_tol;
    nd.hessian = c->d->hessian;
    nd.shift = c->d->shift;
    nd.linear = c->d->linear;
    nd.name = "statics";
    c->st = st;
    rs = wr_newton_solve(&p, x, &nd, &ns, diag);
    wr__statics_from_newton(st, &ns);
    return rs;
}

/* volume and contact figures at the returned x */
static void wr__statics_report(const wr__statics_ctx *c, const double *x, wr_statics_stats *st) {
    int32_t o, v;
    if (c->p != 0.0) st->volume = wr_statics_volume(c->s, x, c->origin, NULL);
    if (c->nobs == 0) return;
    st->min_distance = HUGE_VAL;
    for (o = 0; o < c->nobs; ++o)
        for (v = 0; v < c->s->nv; ++v) {
            double dd = wr_obstacle_distance(c->obs + o, x + 3 * v, NULL);
            if (c->fixv && c->fixv[v]) continue;
            st->min_distance = fmin(st->min_distance, dd);
            if (dd < c->dhat) st->n_contacts++;
        }
}

/* One solve of Π: loads and targets, the perturbation, the frame (origin, bbox, contact defaults),
 * then Newton. gref_fixed > 0: the ON STOPPING reference instead of the one measured at x0;
 * ref_only: stop after measuring the reference (stats->grad_ref), no Newton step. */
static wr_status wr__statics_solve_one(const wr_shell *s, double *x, const wr_statics_desc *desc,
                                       wr_statics_stats *stats, wr_diag *diag, double gref_fixed, int ref_only) {
    wr_statics_desc d;
    wr_statics_stats st;
    wr__statics_ctx c;
    wr_status rs;
    memset(&st, 0, sizeof st);
    memset(&c, 0, sizeof c);
    st.ccd_alpha_min = 1.0;
    c.t_start = wr_time_seconds();
    if (stats) *stats = st;
    if (!s || !x || !s->faces) return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "statics: NULL shell or x");
    if ((rs = wr__statics_defaults(&d, desc, diag)) != WR_OK) return rs;
    c.s = s;
    c.d = &d;
    c.fixv = d.loads.fixed;
    c.p = d.loads.pressure;
    c.obs = d.contact.obstacles;
    c.nobs = d.contact.n_obstacles;
    if ((rs = wr__statics_loads(&c, x, diag)) != WR_OK || (rs = wr__statics_perturb(&c, x, diag)) != WR_OK ||
        (rs = wr__statics_frame(&c, x, diag)) != WR_OK)
        goto done;
    st.contact_dhat = c.dhat;
    st.contact_stiffness = c.kappa;
    if (ref_only) {
        double Pi, fe = 0.0, *g = (double *)wr_alloc_array(3 * (size_t)s->nv, sizeof(double));
        int32_t i;
        if (!g) {
            rs = wr_fail(diag, WR_ERR_NOMEM, -1, "statics: out of memory (%d vertices)", (int)s->nv);
            goto done;
        }
        rs = wr__statics_energy(&c, x, &Pi, g, NULL, diag);
        for (i = 0; i < 3 * s->nv; ++i)
            if (!c.fixd[i]) fe += c.fext[i] * c.fext[i];
        st.grad_norm0 = st.grad_norm = wr__statics_norm(g, 3 * s->nv);
        st.grad_ref = fmax(st.grad_norm0, sqrt(fe));
        st.energy = Pi;
        wr_free(g);
        goto done;
    }
    rs = wr__statics_newton(&c, x, gref_fixed, &st, diag);
    if (rs == WR_OK || rs == WR_ERR_NOT_CONVERGED) wr__statics_report(&c, x, &st);
done:
    st.t_total = wr_time_seconds() - c.t_start;
    if (stats) *stats = st;
    wr_free(c.fext);
    wr_free(c.mass);
    wr_free(c.fixd);
    return rs;
}

/* ---- stability of an equilibrium (ON STABILITY) ------------------------------------------------ */

/* Π at x (loads and targets of d, no perturbation), through the reference-only solve */
static wr_status wr__statics_energy_at(const wr_shell *s, double *x, const wr_statics_desc *d, double *Pi) {
    wr_statics_desc d2 = *d;
    wr_statics_stats st;
    wr_status rs;
    d2.start.perturb = 0.0;
    d2.stability.check = 0;
    rs = wr__statics_solve_one(s, x, &d2, &st, NULL, 0.0, 1);
    *Pi = st.energy;
    return rs;
}

/* The true (unprojected) Hessian of Π at x into A (every term of wr__statics_hessian, exact element
 * blocks), the fixed DOFs (nv*3) and the DOF metric: lumped rest vertex areas (ON STABILITY). */
static wr_status wr__statics_true_hessian(const wr_shell *s, const double *x, const wr_statics_desc *d, wr_assembly *A,
                                          uint8_t *fixd, double *metric, wr_diag *diag) {
    wr__statics_ctx c;
    wr_newton_hessian H;
    int32_t f, k, i, n = 3 * s->nv, pass;
    double *xc = (double *)wr_alloc_array((size_t)n, sizeof(double));
    wr_status rs;
    memset(&c, 0, sizeof c);
    memset(&H, 0, sizeof H);
    if (!xc) return wr_fail(diag, WR_ERR_NOMEM, -1, "statics: out of memory (%d DOFs)", (int)n);
    memcpy(xc, x, sizeof(double) * (size_t)n);
    c.s = s, c.d = d, c.fixv = d->loads.fixed, c.p = d->loads.pressure;
    c.obs = d->contact.obstacles, c.nobs = d->contact.n_obstacles;
    rs = wr__statics_loads(&c, xc, diag);
    if (rs == WR_OK) rs = wr__statics_frame(&c, xc, diag);
    if (rs == WR_OK) memcpy(fixd, c.fixd, (size_t)n);
    H.assembly = A, H.proj = WR_PROJECT_NONE, H.block = 3;
    for (pass = 0; pass < 2 && rs == WR_OK; ++pass) {
        wr_assembly_begin(A);
        if ((rs = wr__statics_hessian(&c, x, &H, diag)) != WR_OK || (rs = wr_assembly_end(A, diag)) != WR_OK || !A->stale)
            break;
    }
    memset(metric, 0, sizeof(double) * (size_t)n);
    for (f = 0; f < s->nf; ++f)
        for (k = 0; k < 3; ++k)
            for (i = 0; i < 3; ++i) metric[3 * s->faces[3 * f + k] + i] += s->area[f] / 3.0;
    wr_free(c.fext), wr_free(c.mass), wr_free(c.fixd), wr_free(xc);
    return rs;
}

/* The lowest eigenpairs of the true Hessian at x (eigen.h, K v = λ A v on the free DOFs). */
static wr_status wr__statics_eigen(const wr_shell *s, const double *x, const wr_statics_desc *d,
                                   const wr_statics_stability_desc *sd, uint64_t seed, wr_eigen_result *er, wr_diag *diag) {
    wr_assembly A;
    wr_eigen_desc ed;
    int32_t n = 3 * s->nv, i, nfree = 0;
    uint8_t *fixd = (uint8_t *)wr_alloc_array((size_t)n, 1);
    double *metric = (double *)wr_alloc_array((size_t)n, sizeof(double));
    wr_status rs = wr_assembly_init(&A, s->nv, 3, diag);
    memset(er, 0, sizeof *er);
    if (rs == WR_OK && (!fixd || !metric)) rs = wr_fail(diag, WR_ERR_NOMEM, -1, "statics: out of memory (%d DOFs)", (int)n);
    if (rs == WR_OK) rs = wr__statics_true_hessian(s, x, d, &A, fixd, metric, diag);
    for (i = 0; fixd && i < n; ++i) nfree += !fixd[i];
    memset(&ed, 0, sizeof ed);
    ed.nev = sd->n_modes < nfree - 1 ? sd->n_modes : nfree - 1;
    ed.neg_rel = sd->neg_tol;
    ed.fixed = fixd, ed.metric = metric, ed.seed = seed;
    if (rs == WR_OK && ed.nev < 1) rs = wr_fail(diag, WR_ERR_INVALID_ARG, -1, "statics: %d free DOFs, no stability test", (int)nfree);
    if (rs == WR_OK) rs = wr_eigen_lowest(&A.A, &ed, er, diag);
    wr_assembly_free(&A), wr_free(fixd), wr_free(metric);
    return rs;
}

/* the analysis into the stats: eigenvalues at x, negative count; first = before any escape */
static void wr__statics_stab_record(const wr_eigen_result *er, int first, wr_statics_stats *st) {
    int32_t k;
    st->stability_checks++;
    st->stability_negative = er->n_negative;
    st->stability_n_eigs = er->nev < WR_STATICS_STABILITY_EIGS ? er->nev : WR_STATICS_STABILITY_EIGS;
    for (k = 0; k < st->stability_n_eigs; ++k) st->stability_eigs[k] = er->values[k];
    if (first) {
        st->stability_negative_first = er->n_negative;
        st->stability_lambda_first = er->nev > 0 ? er->values[0] : 0.0;
    }
    for (k = 0; k < er->nev; ++k) st->stability_modes += er->values[k] < er->sigma0;
}

/* re-solve from a trial state (the caller's solve: one increment, or the plain solve) */
typedef wr_status (*wr__statics_resolve_fn)(void *user, double *x, wr_statics_stats *st, wr_diag *diag);

/* ON STABILITY: step along the lowest negative mode, both signs, re-solve each; the lower Π is kept when
 * it is below Π(x). *best_st receives the kept solve's stats. Returns 1 when x moved. */
static int wr__statics_escape(const wr_shell *s, double *x, const double *mode, double amp, double Pi0,
                              wr__statics_resolve_fn fn, void *user, double *xt, wr_statics_stats *st,
                              wr_statics_stats *best_st) {
    int32_t n = 3 * s->nv, i, v, sgn, moved = 0;
    double vmax = 0.0, best = Pi0 - WR_NEWTON_ENERGY_NOISE * fmax(fabs(Pi0), 1e-300);
    double *xb = xt + n;
    for (v = 0; v < s->nv; ++v)
        vmax = fmax(vmax, sqrt(mode[3 * v] * mode[3 * v] + mode[3 * v + 1] * mode[3 * v + 1] + mode[3 * v + 2] * mode[3 * v + 2]));
    if (!(vmax > 0.0)) return 0;
    for (sgn = -1; sgn <= 1; sgn += 2) {
        wr_statics_stats s2;
        wr_diag d2;
        wr_status rs;
        for (i = 0; i < n; ++i) xt[i] = x[i] + sgn * amp / vmax * mode[i];
        rs = fn(user, xt, &s2, &d2);
        st->stability_iterations += s2.iterations;
        if (rs == WR_OK && s2.energy < best) {
            best = s2.energy;
            memcpy(xb, xt, sizeof(double) * (size_t)n);
            *best_st = s2;
            moved = 1;
        }
    }
    if (moved) memcpy(x, xb, sizeof(double) * (size_t)n);
    return moved;
}

/* ON STABILITY: analyse, escape while a negative mode lowers Π (at most max_rounds times), analyse the
 * result. st holds the solve's stats at x on entry and at the returned x on exit (stability counters
 * added). d: the solve's options (loads of this increment). */
static wr_status wr__statics_stability(const wr_shell *s, double *x, const wr_statics_desc *d,
                                       const wr_statics_stability_desc *user_sd, uint64_t seed, wr__statics_resolve_fn fn,
                                       void *user, wr_statics_stats *st, wr_diag *diag) {
    wr_statics_stability_desc sd = *user_sd;
    wr_eigen_result er;
    double t0 = wr_time_seconds(), amp, *xt;
    int32_t round;
    wr_status rs = WR_OK;
    if (sd.n_modes == 0) sd.n_modes = 4;
    if (sd.max_rounds == 0) sd.max_rounds = 4;
    if (sd.neg_tol == 0.0) sd.neg_tol = WR_EIGEN_NEG_REL;
    amp = sd.amplitude > 0.0 ? sd.amplitude : s->thickness;
    if (!(amp > 0.0)) amp = 1e-2 * sqrt(2.0 * s->total_area / s->nf); /* no thickness: 1 % of the typical edge */
    xt = (double *)wr_alloc_array(6 * (size_t)s->nv, sizeof(double));
    if (!xt) return wr_fail(diag, WR_ERR_NOMEM, -1, "statics: out of memory (%d vertices)", (int)s->nv);
    for (round = 0;; ++round) {
        wr_statics_stats kept, saved;
        if ((rs = wr__statics_eigen(s, x, d, &sd, seed, &er, diag)) != WR_OK) break;
        wr__statics_stab_record(&er, round == 0, st);
        if (er.n_negative == 0 || er.nev == 0 || round == sd.max_rounds || sd.check == 2 ||
            !wr__statics_escape(s, x, er.vectors, amp, st->energy, fn, user, xt, st, &kept)) {
            wr_eigen_result_free(&er);
            break;
        }
        wr_eigen_result_free(&er);
        /* x moved: the kept solve's figures, with the stability counters carried over */
        saved = *st;
        *st = kept;
        st->stability_energy_drop = saved.stability_energy_drop + (saved.energy - kept.energy);
        st->stability_escapes = saved.stability_escapes + 1;
        st->stability_checks = saved.stability_checks, st->stability_modes = saved.stability_modes;
        st->stability_iterations = saved.stability_iterations;
        st->stability_negative_first = saved.stability_negative_first;
        st->stability_lambda_first = saved.stability_lambda_first;
    }
    wr_eigen_result_free(&er);
    wr_free(xt);
    st->t_stability += wr_time_seconds() - t0;
    return rs;
}

/* the plain solve's re-solve (stability off, no perturbation) */
typedef struct wr__statics_plain {
    const wr_shell *s;
    wr_statics_desc d;
} wr__statics_plain;

static wr_status wr__statics_resolve_plain(void *user, double *x, wr_statics_stats *st, wr_diag *diag) {
    const wr__statics_plain *p = (const wr__statics_plain *)user;
    return wr_statics_solve(p->s, x, &p->d, st, diag);
}

WRDEF wr_status wr_statics_stability_test(const wr_shell *s, const double *x, const wr_statics_desc *desc,
                                          wr_statics_stats *stats, wr_diag *diag) {
    wr_statics_desc dk;
    wr_statics_stats st;
    wr_status rs;
    double *xc;
    memset(&st, 0, sizeof st);
    if (stats) *stats = st;
    if (!s || !x || !s->faces) return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "statics: NULL shell or x");
    if ((rs = wr__statics_defaults(&dk, desc, diag)) != WR_OK) return rs;
    dk.stability.check = 2; /* report only: no re-solve, x unchanged */
#if !(defined(WR_USE_ARPACK) && WR_USE_ARPACK && defined(WR_USE_CHOLMOD) && WR_USE_CHOLMOD)
    return wr_fail(diag, WR_ERR_UNSUPPORTED, -1, "statics: the stability test needs WR_USE_ARPACK=1 and WR_USE_CHOLMOD=1");
#endif
    xc = (double *)wr_alloc_array(3 * (size_t)s->nv, sizeof(double));
    if (!xc) return wr_fail(diag, WR_ERR_NOMEM, -1, "statics: out of memory (%d vertices)", (int)s->nv);
    memcpy(xc, x, sizeof(double) * 3 * (size_t)s->nv);
    if (wr__statics_energy_at(s, xc, &dk, &st.energy) != WR_OK) st.energy = NAN;
    rs = wr__statics_stability(s, xc, &dk, &dk.stability, dk.start.seed, NULL, NULL, &st, diag);
    wr_free(xc);
    if (stats) *stats = st;
    return rs;
}

/* ON MEMBRANE CONTINUATION: soft-membrane stages, then the real shell */
WRDEF wr_status wr_statics_solve(const wr_shell *s, double *x, const wr_statics_desc *desc, wr_statics_stats *stats,
                                 wr_diag *diag) {
    wr_statics_desc dk;
    wr_statics_stats sk, acc;
    double m, t0 = wr_time_seconds();
    wr_status rs;
    int32_t k;
    double gref, *x0;
    if (desc && desc->stability.check) {
        /* ON STABILITY: the solve, then the test of its equilibrium and the escapes */
        wr__statics_plain pl;
        wr_statics_stats st0;
        if ((rs = wr__statics_defaults(&dk, desc, diag)) != WR_OK) return rs;
        pl.s = s, pl.d = *desc;
        pl.d.stability.check = 0;
        rs = wr_statics_solve(s, x, &pl.d, &st0, diag);
        if (rs == WR_OK || rs == WR_ERR_NOT_CONVERGED) {
            wr_status r2;
            pl.d.start.perturb = 0.0;
            r2 = wr__statics_stability(s, x, &pl.d, &desc->stability, desc->start.seed, wr__statics_resolve_plain, &pl, &st0, diag);
            if (r2 != WR_OK) rs = r2;
            else if (st0.stability_escapes > 0) rs = WR_OK; /* the kept re-solve converged */
        }
        st0.t_total = wr_time_seconds() - t0;
        if (stats) *stats = st0;
        return rs;
    }
    if (!desc || desc->continuation.membrane_ramp == 0.0) return wr__statics_solve_one(s, x, desc, stats, diag, 0.0, 0);
    memset(&acc, 0, sizeof acc);
    if (stats) *stats = acc;
    if (!s || !x || !s->faces) return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "statics: NULL shell or x");
    if ((rs = wr__statics_defaults(&dk, desc, diag)) != WR_OK) return rs;
    m = dk.continuation.membrane_ramp;
    dk.continuation.membrane_ramp = 0.0;
    /* every stage stops relative to the REAL shell's reference at the initial x (after the
     * perturbation), as a solve without continuation would: a later stage's own start (the soft
     * equilibrium, out of balance by the membrane's stiffening) would loosen the final tolerance */
    x0 = (double *)wr_alloc_array((size_t)s->nv * 3, sizeof(double));
    if (!x0) return wr_fail(diag, WR_ERR_NOMEM, -1, "statics: out of memory (%d vertices)", (int)s->nv);
    memcpy(x0, x, sizeof(double) * 3 * (size_t)s->nv);
    rs = wr__statics_solve_one(s, x0, &dk, &sk, diag, 0.0, 1);
    if (rs != WR_OK) {
        wr_free(x0);
        if (stats) *stats = sk;
        return rs;
    }
    memcpy(x0, x, sizeof(double) * 3 * (size_t)s->nv); /* the start, for the fallback */
    gref = sk.grad_ref;
    for (; m < 1.0; m *= dk.continuation.factor) {
        /* a shallow copy: only the membrane constants differ, the arrays are shared read-only */
        wr_shell soft = *s;
        for (k = 0; k < 9; ++k) soft.C_mem[k] *= m;
        soft.young *= m;
        dk.stop.grad_tol = WR_STATICS_RAMP_TOL;
        rs = wr__statics_solve_one(&soft, x, &dk, &sk, diag, gref, 0);
        if (rs != WR_OK && rs != WR_ERR_NOT_CONVERGED) { /* best iterate of a stage is a fine warm start */
            wr_free(x0);
            if (stats) {
                sk.ramp_stages = acc.ramp_stages;
                sk.ramp_iterations = acc.ramp_iterations;
                *stats = sk;
            }
            return rs;
        }
        dk.start.perturb = 0.0;
        acc.ramp_stages++;
        acc.ramp_iterations += sk.iterations;
        wr__statics_work_add(&acc, &sk);
        acc.ccd_alpha_min = acc.ramp_stages == 1 ? sk.ccd_alpha_min : fmin(acc.ccd_alpha_min, sk.ccd_alpha_min);
    }
    dk.stop.grad_tol = desc->stop.grad_tol;
    rs = wr__statics_solve_one(s, x, &dk, &sk, diag, gref, 0);
    if (rs == WR_ERR_NOT_CONVERGED) {
        /* the soft path led somewhere the real shell cannot converge from: plain solve from the start */
        acc.ramp_iterations += sk.iterations;
        wr__statics_work_add(&acc, &sk);
        memcpy(x, x0, sizeof(double) * 3 * (size_t)s->nv);
        dk.start.perturb = desc->start.perturb;
        rs = wr__statics_solve_one(s, x, &dk, &sk, diag, 0.0, 0);
        acc.ramp_fallback = 1;
    }
    wr_free(x0);
    /* the final stage's state, with the work of the whole solve */
    sk.iterations += acc.ramp_iterations;
    wr__statics_work_add(&sk, &acc);
    sk.ccd_alpha_min = fmin(sk.ccd_alpha_min, acc.ccd_alpha_min);
    sk.ramp_stages = acc.ramp_stages;
    sk.ramp_iterations = acc.ramp_iterations;
    sk.ramp_fallback = acc.ramp_fallback;
    sk.t_total = wr_time_seconds() - t0;
    if (stats) *stats = sk;
    return rs;
}

/* ---- prescribed motions and load increments ---------------------------------------------------- */

static int wr__statics_unit(const double a[3], double u[3]) {
    double n = sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
    int i;
    if (!(n > 0.0) || n - n != 0.0) return 0;
    for (i = 0; i < 3; ++i) u[i] = a[i] / n;
    return 1;
}

/* WR_MOTION_AFFINE at fraction t: o + R(t·θ)·(I + t·grad)·(X − o) + t·vec + t·wave(X) */
static void wr__motion_affine(const wr_motion *m, const double *X, double t, double *out) {
    double d[3], q[3], F[9];
    int k;
    for (k = 0; k < 9; ++k) F[k] = (k % 4 == 0 ? 1.0 : 0.0) + t * m->grad[k];
    for (k = 0; k < 3; ++k) d[k] = X[k] - m->origin[k];
    for (k = 0; k < 3; ++k) q[k] = F[3 * k] * d[0] + F[3 * k + 1] * d[1] + F[3 * k + 2] * d[2];
    if (m->amount != 0.0) { /* Rodrigues rotation by t·θ about the unit axis */
        wr_vec3 a = wr_v3_normalized(wr_v3_load(m->axis)), v = wr_v3_load(q);
        double th = t * m->amount, c = cos(th), sn = sin(th);
        wr_vec3 r = wr_v3_add(wr_v3_add(wr_v3_scale(v, c), wr_v3_scale(wr_v3_cross(a, v), sn)),
                              wr_v3_scale(a, wr_v3_dot(a, v) * (1.0 - c)));
        wr_v3_store(r, q);
    }
    for (k = 0; k < 3; ++k) out[k] = m->origin[k] + q[k] + t * m->vec[k];
    if (m->wave_amplitude != 0.0) {
        double ph = 2.0 * 3.14159265358979323846 *
                        (X[0] * m->wave_along[0] + X[1] * m->wave_along[1] + X[2] * m->wave_along[2]) / m->wave_length +
                    m->wave_phase;
        wr_vec3 dir = wr_v3_normalized(wr_v3_load(m->wave_dir));
        double a = t * m->wave_amplitude * sin(ph);
        out[0] += a * dir.x, out[1] += a * dir.y, out[2] += a * dir.z;
    }
}

/* the affine kind's own parameters: finite, a twist axis when it twists, a wave with a length */
static wr_status wr__motion_affine_check(const wr_motion *m, wr_diag *diag) {
    double fin = m->wave_amplitude + m->wave_length + m->wave_phase, nd = 0.0;
    int k;
    for (k = 0; k < 9; ++k) fin += m->grad[k];
    for (k = 0; k < 3; ++k) {
        fin += m->wave_along[k] + m->wave_dir[k];
        nd += m->wave_dir[k] * m->wave_dir[k];
    }
    if (fin - fin != 0.0) return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "motion: non-finite affine parameter");
    if (m->amount != 0.0 && !(m->axis[0] * m->axis[0] + m->axis[1] * m->axis[1] + m->axis[2] * m->axis[2] > 0.0))
        return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "motion: an affine twist needs a nonzero axis");
    if (m->wave_amplitude != 0.0 && (!(m->wave_length > 0.0) || !(nd > 0.0)))
        return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "motion: a wave needs wave_length > 0 and a nonzero wave_dir");
    return WR_OK;
}

WRDEF wr_status wr_motion_apply(const wr_motion *m, int32_t nv, const double *x_ref, double t, double *target,
                                uint8_t *fixed, wr_diag *diag) {
    double ax[3] = {0.0, 0.0, 0.0}, nr[3] = {0.0, 0.0, 0.0}, fin;
    int32_t k, i;
    int has_axis;
    if (!m || !x_ref || !target || m->n_verts < 0 || (m->n_verts > 0 && !m->verts))
        return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "motion: NULL argument or negative vertex count");
    fin = t + m->amount;
    for (i = 0; i < 3; ++i) fin += m->origin[i] + m->axis[i] + m->normal[i] + m->vec[i];
    if (fin - fin != 0.0) return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "motion: non-finite parameter or t");
    has_axis = wr__statics_unit(m->axis, ax);
    if ((m->kind == WR_MOTION_TWIST || m->kind == WR_MOTION_SHEAR) && !has_axis)
        return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "motion: kind %d needs a nonzero axis", (int)m->kind);
    if (m->kind == WR_MOTION_SHEAR && !wr__statics_unit(m->normal, nr))
        return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "motion: shear needs a nonzero normal");
    if ((int)m->kind < 0 || (int)m->kind > (int)WR_MOTION_AFFINE)
        return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "motion: unknown kind %d", (int)m->kind);
    if (m->kind == WR_MOTION_AFFINE && wr__motion_affine_check(m, diag) != WR_OK) return WR_ERR_INVALID_ARG;
    for (k = 0; k < m->n_verts; ++k) {
        int32_t v = m->verts[k];
        double X[3], r[3], y[3];
        if (v < 0 || v >= nv)
            return wr_fail(diag, WR_ERR_INVALID_ARG, k, "motion: vertex %d at position %d outside [0, %d)", (int)v,
                           (int)k, (int)nv);
        for (i = 0; i < 3; ++i) {
            X[i] = x_ref[3 * v + i];
            r[i] = X[i] - m->origin[i];
            y[i] = X[i];
        }
        switch (m->kind) {
        case WR_MOTION_TRANSLATE:
            for (i = 0; i < 3; ++i) y[i] = X[i] + t * m->vec[i];
            break;
        case WR_MOTION_STRETCH:
            if (has_axis) {
                double c = r[0] * ax[0] + r[1] * ax[1] + r[2] * ax[2];
                for (i = 0; i < 3; ++i) y[i] = X[i] + t * m->amount * c * ax[i];
            } else {
                for (i = 0; i < 3; ++i) y[i] = m->origin[i] + (1.0 + t * m->amount) * r[i];
            }
            break;
        case WR_MOTION_SHEAR: {
            double c = r[0] * nr[0] + r[1] * nr[1] + r[2] * nr[2];
            for (i = 0; i < 3; ++i) y[i] = X[i] + t * m->amount * c * ax[i];
            break;
        }
        case WR_MOTION_TWIST: {
            /* Rodrigues: r cosθ + (â×r) sinθ + â(â·r)(1 − cosθ); the axial coordinate â·r is kept */
            double th = t * m->amount, cs = cos(th), sn = sin(th), ar = r[0] * ax[0] + r[1] * ax[1] + r[2] * ax[2];
            double cr[3];
            cr[0] = ax[1] * r[2] - ax[2] * r[1];
            cr[1] = ax[2] * r[0] - ax[0] * r[2];
            cr[2] = ax[0] * r[1] - ax[1] * r[0];
            for (i = 0; i < 3; ++i) y[i] = m->origin[i] + r[i] * cs + cr[i] * sn + ax[i] * ar * (1.0 - cs);
            break;
        }
        case WR_MOTION_AFFINE:
            wr__motion_affine(m, X, t, y);
            break;
        default:
            break;
        }
        for (i = 0; i < 3; ++i) target[3 * v + i] = y[i];
        if (fixed) fixed[v] = 1;
    }
    return WR_OK;
}

/* The state of an incremental solve across its increments. */
typedef struct wr__statics_inc {
    const wr_shell *s;
    const wr_statics_desc *user_desc;
    wr_statics_desc dk;      /* with defaults; fixed / target / gravity / grad_tol / perturb per increment */
    double *X, *target, *xprev, *xsave, *work, *work2, *mass;
    uint8_t *fixed;
    double grad_tol, G;      /* the final tolerance; the absolute force scale (increments.absolute_reference) */
    int32_t k, n_inc;
    wr_statics_stability_desc stab; /* the user's (ON STABILITY); dk.stability.check is 0 */
} wr__statics_inc;

static void wr__statics_inc_free(wr__statics_inc *I) {
    wr_free(I->X);
    wr_free(I->target);
    wr_free(I->xprev);
    wr_free(I->xsave);
    wr_free(I->work);
    wr_free(I->work2);
    wr_free(I->mass);
    wr_free(I->fixed);
}

/* Gaussian elimination with partial pivoting on a 4×4 system in place; 0 when singular. */
static int wr__statics_solve4(double M[16], double r[4]) {
    int i, j, k;
    for (k = 0; k < 4; ++k) {
        int p = k;
        for (i = k + 1; i < 4; ++i)
            if (fabs(M[4 * i + k]) > fabs(M[4 * p + k])) p = i;
        if (!(fabs(M[4 * p + k]) > 0.0)) return 0;
        if (p != k) {
            double t;
            for (j = 0; j < 4; ++j) t = M[4 * k + j], M[4 * k + j] = M[4 * p + j], M[4 * p + j] = t;
            t = r[k], r[k] = r[p], r[p] = t;
        }
        for (i = k + 1; i < 4; ++i) {
            double f = M[4 * i + k] / M[4 * k + k];
            for (j = k; j < 4; ++j) M[4 * i + j] -= f * M[4 * k + j];
            r[i] -= f * r[k];
        }
    }
    for (k = 3; k >= 0; --k) {
        for (j = k + 1; j < 4; ++j) r[k] -= M[4 * k + j] * r[j];
        r[k] /= M[4 * k + k];
    }
    return 1;
}

/* WR_STATICS_PREDICT_AFFINE: the least-squares affine map taking the prescribed vertices' current
 * positions to their new targets (regularised towards the identity by WR_STATICS_AFFINE_REG times
 * their spread), applied to the free vertices. A uniform stretch is then exact for the free interior,
 * so Newton starts close instead of propagating a boundary jump through the whole mesh. */
static void wr__statics_affine_predict(const wr__statics_inc *I, double *x) {
    int32_t i, nv = I->s->nv, k;
    double M[16], rhs[3][4], spread = 0.0, mean[3] = {0, 0, 0}, cnt = 0.0;
    for (i = 0; i < nv; ++i)
        if (I->fixed[i]) {
            for (k = 0; k < 3; ++k) mean[k] += x[3 * i + k];
            cnt += 1.0;
        }
    if (cnt < 1.0) return;
    for (k = 0; k < 3; ++k) mean[k] /= cnt;
    for (i = 0; i < nv; ++i)
        if (I->fixed[i])
            for (k = 0; k < 3; ++k) spread += (x[3 * i + k] - mean[k]) * (x[3 * i + k] - mean[k]);
    spread = fmax(spread, 1e-300);
    for (k = 0; k < 3; ++k) {
        int a, b;
        memset(M, 0, sizeof M);
        memset(rhs[k], 0, sizeof rhs[k]);
        for (i = 0; i < nv; ++i)
            if (I->fixed[i]) {
                double z[4];
                z[0] = x[3 * i] - mean[0], z[1] = x[3 * i + 1] - mean[1], z[2] = x[3 * i + 2] - mean[2];
                z[3] = 1.0;
                for (a = 0; a < 4; ++a) {
                    for (b = 0; b < 4; ++b) M[4 * a + b] += z[a] * z[b];
                    rhs[k][a] += z[a] * (I->target[3 * i + k] - mean[k]);
                }
            }
        for (a = 0; a < 3; ++a) {
            M[4 * a + a] += WR_STATICS_AFFINE_REG * spread;
            rhs[k][a] += WR_STATICS_AFFINE_REG * spread * (a == k ? 1.0 : 0.0);
        }
        if (!wr__statics_solve4(M, rhs[k])) return;
    }
    for (i = 0; i < nv; ++i)
        if (!I->fixed[i]) {
            double z[3], y[3];
            for (k = 0; k < 3; ++k) z[k] = x[3 * i + k] - mean[k];
            for (k = 0; k < 3; ++k) y[k] = mean[k] + rhs[k][0] * z[0] + rhs[k][1] * z[1] + rhs[k][2] * z[2] + rhs[k][3];
            for (k = 0; k < 3; ++k) x[3 * i + k] = y[k];
        }
}

/* increments.absolute_reference: at the increment's start (prescribed rows at their targets, before
 * the perturbation) ref = max(‖(∇E_shell − f)_free‖, ‖f_free‖); at the first increment G = max(ref,
 * ‖∇E_shell‖ on the prescribed DOFs), the elastic reaction (the start residual alone can be tiny after
 * the affine prediction). The solve's relative tolerance is rescaled so that it stops at
 * ‖∇Π_free‖ <= grad_tol · G: a later increment's own start, after a good prediction, would ask for a
 * gradient below round-off (the 2.5 mm stretch test hit max_iter at |g| 7e-9 N against 7e-14 N). */
static double wr__statics_inc_tolerance(wr__statics_inc *I, const double *x, double gtol) {
    const wr_shell *s = I->s;
    double E, gs = 0.0, f2 = 0.0, r2 = 0.0, ref, *g = I->work, *mass = I->mass;
    int32_t i, nv = s->nv;
    memcpy(I->work2, x, sizeof(double) * 3 * (size_t)nv);
    for (i = 0; i < nv; ++i)
        if (I->fixed[i]) memcpy(I->work2 + 3 * i, I->target + 3 * i, sizeof(double) * 3);
    if (wr_shell_energy(s, I->work2, &E, g, NULL) != WR_OK) {
        ref = 0.0;
    } else {
        wr_shell_vertex_masses(s, mass);
        for (i = 0; i < 3 * nv; ++i)
            if (!I->fixed[i / 3]) {
                double f = mass[i / 3] * I->dk.loads.gravity[i % 3];
                gs += (g[i] - f) * (g[i] - f);
                f2 += f * f;
            } else
                r2 += g[i] * g[i];
        ref = fmax(sqrt(gs), sqrt(f2));
    }
    if (I->k == 1) I->G = fmax(ref, sqrt(r2));
    return (ref > 0.0 && I->G > 0.0) ? fmin(1.0, gtol * I->G / ref) : gtol;
}

/* the increment's progress: the user's callback with the increment number */
static void wr__statics_inc_progress(void *user, const wr_statics_stats *st) {
    const wr__statics_inc *I = (const wr__statics_inc *)user;
    wr_statics_stats s2 = *st;
    s2.increment = I->k;
    I->user_desc->progress(I->user_desc->progress_user, &s2);
}

/* One increment's solve: increments.hybrid_switch > 0 first runs the given projection to the loose
 * tolerance min(1, max(tol, tol · hybrid_switch / grad_tol)) (robust descent away from a flat saddle),
 * then the exact Hessian to tol; the stats are the exact phase's with the work of both. Both phases
 * stop relative to the projected phase's reference (its ‖∇Π(x0)‖, x0 the increment's start): the
 * exact phase's own start is already within ~hybrid_switch of equilibrium, and tol relative to it
 * asks ~hybrid_switch times less, below the gradient's round-off on a large sheet. */
static wr_status wr__statics_inc_solve(wr__statics_inc *I, double *x, wr_statics_stats *sk, wr_diag *diag) {
    wr_statics_desc d1 = I->dk;
    wr_statics_stats s1;
    wr_status rs;
    if (!(I->dk.increments.hybrid_switch > 0.0)) return wr_statics_solve(I->s, x, &I->dk, sk, diag);
    d1.stop.grad_tol = fmin(1.0, fmax(I->dk.stop.grad_tol, I->dk.stop.grad_tol * I->dk.increments.hybrid_switch / I->grad_tol));
    memset(&s1, 0, sizeof s1);
    wr_statics_solve(I->s, x, &d1, &s1, diag); /* its status is the exact phase's to decide */
    I->dk.start.perturb = 0.0;
    I->dk.hessian.projection = WR_PROJECT_NONE;
    /* no second membrane continuation: the projected phase ended on the real shell */
    rs = wr__statics_solve_one(I->s, x, &I->dk, sk, diag, s1.grad_ref, 0);
    I->dk.hessian.projection = d1.hessian.projection;
    sk->iterations += s1.iterations;
    sk->linear_iterations += s1.linear_iterations;
    sk->line_search_evals += s1.line_search_evals;
    sk->t_assembly += s1.t_assembly, sk->t_projection += s1.t_projection;
    sk->t_linear += s1.t_linear, sk->t_line_search += s1.t_line_search, sk->t_total += s1.t_total;
    return rs;
}

/* reference positions, targets and prescribed flags; every motion validated before the first solve */
static wr_status wr__statics_inc_setup(wr__statics_inc *I, const double *x, const wr_motion *motions, int32_t n_motions,
                                       wr_diag *diag) {
    int32_t j, n = 3 * I->s->nv;
    I->X = (double *)wr_alloc_array((size_t)n, sizeof(double));
    I->target = (double *)wr_alloc_array((size_t)n, sizeof(double));
    I->fixed = (uint8_t *)wr_calloc_array((size_t)I->s->nv, 1);
    I->xprev = (double *)wr_alloc_array((size_t)n, sizeof(double));
    I->xsave = (double *)wr_alloc_array((size_t)n, sizeof(double));
    I->work = (double *)wr_alloc_array((size_t)n, sizeof(double));
    I->work2 = (double *)wr_alloc_array((size_t)n, sizeof(double));
    I->mass = (double *)wr_alloc_array((size_t)I->s->nv, sizeof(double));
    if (!I->X || !I->target || !I->fixed || !I->xprev || !I->xsave || !I->work || !I->work2 || !I->mass)
        return wr_fail(diag, WR_ERR_NOMEM, -1, "statics: out of memory (%d DOFs)", (int)n);
    memcpy(I->X, x, sizeof(double) * (size_t)n);
    memcpy(I->xprev, x, sizeof(double) * (size_t)n);
    memcpy(I->target, I->dk.loads.target ? I->dk.loads.target : x, sizeof(double) * (size_t)n);
    if (I->dk.loads.fixed)
        for (j = 0; j < I->s->nv; ++j) I->fixed[j] = I->dk.loads.fixed[j] != 0;
    for (j = 0; j < n_motions; ++j) {
        wr_status rs = wr_motion_apply(motions + j, I->s->nv, I->X, 0.0, I->target, I->fixed, diag);
        if (rs != WR_OK) return rs;
    }
    I->dk.loads.fixed = I->fixed;
    I->dk.loads.target = I->target;
    if (I->user_desc && I->user_desc->progress) {
        I->dk.progress = wr__statics_inc_progress;
        I->dk.progress_user = I;
    }
    return WR_OK;
}

/* increment k: motions at t = k/n_inc, loads, prediction, tolerance, solve (ON MOTIONS AND INCREMENTS) */
static wr_status wr__statics_inc_step(wr__statics_inc *I, double *x, const wr_motion *motions, int32_t n_motions,
                                      wr_statics_stats *sk, wr_diag *diag) {
    const wr_statics_desc *ud = I->user_desc;
    double t = (double)I->k / (double)I->n_inc, gtol;
    int32_t j, n = 3 * I->s->nv;
    wr_status rs;
    for (j = 0; j < n_motions; ++j)
        if ((rs = wr_motion_apply(motions + j, I->s->nv, I->X, t, I->target, I->fixed, diag)) != WR_OK) return rs;
    if (I->k > 1) {
        /* the perturbation at the first increment only, or at every one (stability.perturb_each) */
        I->dk.start.perturb = (I->stab.perturb_each && ud) ? ud->start.perturb : 0.0;
        I->dk.start.seed = (ud ? ud->start.seed : 0) + (uint64_t)(I->k - 1);
    }
    if (I->dk.increments.ramp_gravity)
        for (j = 0; j < 3; ++j) I->dk.loads.gravity[j] = ud->loads.gravity[j] * t;
    gtol = I->k < I->n_inc ? I->dk.increments.grad_tol : I->grad_tol;
    I->dk.stop.grad_tol = gtol;
    memcpy(I->xsave, x, sizeof(double) * (size_t)n);
    if (I->dk.increments.predictor == WR_STATICS_PREDICT_AFFINE) wr__statics_affine_predict(I, x);
    if (I->dk.increments.absolute_reference) I->dk.stop.grad_tol = wr__statics_inc_tolerance(I, x, gtol);
    if (I->k > 1 && I->dk.increments.predictor == WR_STATICS_PREDICT_SECANT) {
        /* secant predictor: free vertices continue along the path of the last increment */
        for (j = 0; j < n; ++j)
            if (!I->fixed[j / 3]) x[j] = 2.0 * x[j] - I->xprev[j];
    }
    rs = wr__statics_inc_solve(I, x, sk, diag);
    if (I->k > 1 && I->dk.increments.predictor == WR_STATICS_PREDICT_SECANT && (rs == WR_ERR_GEOMETRY || rs == WR_ERR_DOMAIN) &&
        sk->iterations == 0) {
        /* the prediction folded a face or entered an obstacle: start from the last equilibrium */
        memcpy(x, I->xsave, sizeof(double) * (size_t)n);
        rs = wr__statics_inc_solve(I, x, sk, diag);
    }
    memcpy(I->xprev, I->xsave, sizeof(double) * (size_t)n);
    return rs;
}

/* an increment's re-solve from a mode step (ON STABILITY): the same solve, without the perturbation */
static wr_status wr__statics_inc_resolve(void *user, double *x, wr_statics_stats *st, wr_diag *diag) {
    wr__statics_inc *I = (wr__statics_inc *)user;
    double p = I->dk.start.perturb;
    wr_status rs;
    I->dk.start.perturb = 0.0;
    rs = wr__statics_inc_solve(I, x, st, diag);
    I->dk.start.perturb = p;
    return rs;
}

/* the stability counters of one increment into the running total */
static void wr__statics_stab_add(wr_statics_stats *to, const wr_statics_stats *from) {
    to->stability_checks += from->stability_checks;
    to->stability_modes += from->stability_modes;
    to->stability_escapes += from->stability_escapes;
    to->stability_iterations += from->stability_iterations;
    to->stability_energy_drop += from->stability_energy_drop;
    to->t_stability += from->t_stability;
}

WRDEF wr_status wr_statics_solve_incremental(const wr_shell *s, double *x, const wr_statics_desc *desc,
                                             const wr_motion *motions, int32_t n_motions, int32_t n_inc,
                                             wr_statics_stats *stats, wr_diag *diag) {
    wr__statics_inc I;
    wr_statics_stats sk, acc;
    wr_status rs = WR_OK;
    double t0 = wr_time_seconds();
    memset(&acc, 0, sizeof acc);
    memset(&sk, 0, sizeof sk);
    memset(&I, 0, sizeof I);
    if (stats) *stats = acc;
    if (!s || !x || !s->faces) return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "statics: NULL shell or x");
    if (n_inc < 1 || n_motions < 0 || (n_motions > 0 && !motions))
        return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "statics: n_inc %d must be >= 1, n_motions %d >= 0 with motions",
                       (int)n_inc, (int)n_motions);
    if ((rs = wr__statics_defaults(&I.dk, desc, diag)) != WR_OK) return rs;
    if ((int)I.dk.increments.predictor < 0 || (int)I.dk.increments.predictor > (int)WR_STATICS_PREDICT_AFFINE ||
        !(I.dk.increments.hybrid_switch >= 0.0))
        return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "statics: increments.predictor %d or hybrid_switch %g invalid",
                       (int)I.dk.increments.predictor, I.dk.increments.hybrid_switch);
    I.s = s;
    I.user_desc = desc;
    I.n_inc = n_inc;
    I.grad_tol = I.dk.stop.grad_tol;
    I.stab = I.dk.stability;
    I.dk.stability.check = 0;
    if ((rs = wr__statics_inc_setup(&I, x, motions, n_motions, diag)) != WR_OK) goto done;
    for (I.k = 1; I.k <= n_inc; ++I.k) {
        rs = wr__statics_inc_step(&I, x, motions, n_motions, &sk, diag);
        if (I.stab.check && (rs == WR_OK || rs == WR_ERR_NOT_CONVERGED)) {
            /* ON STABILITY: test this increment's equilibrium, escape along its negative modes */
            wr_status r2 = wr__statics_stability(s, x, &I.dk, &I.stab, I.dk.start.seed, wr__statics_inc_resolve, &I, &sk, diag);
            if (r2 != WR_OK) rs = r2;
            else if (sk.stability_escapes > 0) rs = WR_OK; /* the kept re-solve converged */
        }
        wr__statics_stab_add(&acc, &sk);
        sk.increment = I.k;
        acc.total_iterations += sk.iterations;
        wr__statics_work_add(&acc, &sk);
        acc.increments = I.k;
        if (I.dk.increments.done) I.dk.increments.done(desc->progress_user, I.k, n_inc, rs, &sk, diag);
        if (rs == WR_ERR_NOT_CONVERGED && I.k < n_inc) {
            acc.increments_failed++; /* best iterate warm-starts the next increment */
            rs = WR_OK;
            continue;
        }
        if (rs != WR_OK) break;
    }
    {
        /* the last increment's figures, with the sums over all increments */
        wr_statics_stats out = sk;
        out.total_iterations = acc.total_iterations;
        out.linear_iterations = acc.linear_iterations;
        out.line_search_evals = acc.line_search_evals;
        out.t_assembly = acc.t_assembly;
        out.t_projection = acc.t_projection;
        out.t_linear = acc.t_linear;
        out.t_line_search = acc.t_line_search;
        out.elements_projected = acc.elements_projected;
        out.elements_assembled = acc.elements_assembled;
        out.increments = acc.increments;
        out.increments_failed = acc.increments_failed;
        out.stability_checks = acc.stability_checks;
        out.stability_modes = acc.stability_modes;
        out.stability_escapes = acc.stability_escapes;
        out.stability_iterations = acc.stability_iterations;
        out.stability_energy_drop = acc.stability_energy_drop;
        out.t_stability = acc.t_stability;
        out.t_total = wr_time_seconds() - t0;
        acc = out;
    }
done:
    if (stats) *stats = acc;
    wr__statics_inc_free(&I);
    return rs;
}

#ifdef __cplusplus
}
#endif
#endif /* WRINKLE_STATICS_IMPLEMENTATION_DONE */
#endif /* WRINKLE_IMPLEMENTATION */
