/* wrinkle/dynamics.h — dynamic cloth: backward Euler as an incremental potential minimised by the
 * shared Newton (newton.h), with gravity, Rayleigh damping, sewing springs, IPC-style contact
 * barriers against analytic obstacles, triangle-mesh bodies (static or moving) and the cloth
 * itself, lagged Coulomb friction, and continuous collision detection as Newton's max-step hook.
 * wrinkle v0.1.0 — MIT licence (see LICENSE). Needs core.h, sparse.h, spd.h, mesh.h, shell.h,
 * statics.h (analytic obstacles, barrier), newton.h and collision.h; otherwise libc and libm.
 *
 * The Style3D paper's simulator (Sec. 5): "Newton's method with a 1/30 s time step for implicit
 * integration", PCG with 3×3 block-diagonal preconditioning stopped at an L2 residual of 1e-5,
 * Baraff–Witkin membrane, stable discrete bending, adaptive stepping for collisions. One step of
 * size h from (x_n, v_n) minimises (Martin et al. 2011, "Example-based elastic materials"; IPC, Li
 * et al. 2020, Eq. 3)
 *     Φ(x) = 1/(2h²) ‖x − x̃‖²_M + E_el(x) − Σ_v m_v g·x_v + α/(2h) ‖x − x_n‖²_M
 *            + β/(2h) (x − x_n)ᵀ K_n (x − x_n) + E_sew(x) + E_thr(x) + B(x) + D(x),  x̃ = x_n + h v_n,
 * then v_{n+1} = (x − x_n)/h. ∇Φ = 0 is exactly backward Euler M(v_{n+1} − v_n)/h = f(x_{n+1}) −
 * αM v_{n+1} − βK_n v_{n+1}: Rayleigh damping with mass coefficient α [1/s] and stiffness
 * coefficient β [s], K_n the PSD-projected elastic Hessian at x_n (lagged over the step, so the
 * damping term is an exact quadratic). B is the contact barrier, D the lagged friction potential.
 *
 * API (create/free pair: wr_dyn_create → wr_dyn_free)
 *   wr_dyn_create(sim, shell, desc, diag)          masses, Hessian pattern, solver, contact set-up
 *   wr_dyn_free(sim)                               free and zero (safe on a zeroed sim)
 *   wr_dyn_state_init(sim, state, x, v)            point a state at caller arrays (x, v: nv*3), t = 0
 *   wr_dyn_step(sim, state, stats, diag)           advance one frame (desc.time.dt) in place
 *   wr_dyn_run(sim, state, t_end, progress, user, total, diag)   frames until t_end, callback per frame
 *   wr_dyn_energy(sim, state, kinetic, potential)  ½vᵀMv and E_el + E_thr − Σ m g·x [J]
 *   wr_dyn_min_distance(sim, x)                    smallest contact distance at x [m]
 *   wr_dyn_sew_gap(sim, x)                         largest distance between sewn vertex pairs [m]
 *   wr_dyn_thread_segment(xa, xb, rest, axial, g, H)   one gathering-thread segment: energy,
 *                                                  gradient (6), PSD Hessian (36) (ON GATHERING)
 *
 * EXAMPLE (a sheet dropped on a ball)
 *     wr_mesh m;  wr_shell sh;  wr_shell_desc sd;  wr_dyn_desc dd;  wr_dyn sim;  wr_dyn_state st;
 *     wr_dyn_stats fs;  wr_obstacle ball;  wr_diag d;  double *x, *v;  int32_t i, f;
 *     if (wr_mesh_rectangle(&m, 0.4, 0.4, 8, 8, &d) != WR_OK) { puts(d.message); return 1; }
 *     memset(&sd, 0, sizeof sd);  memset(&dd, 0, sizeof dd);  memset(&ball, 0, sizeof ball);
 *     sd.young = 1e5; sd.poisson = 0.3; sd.thickness = 5e-4; sd.density = 300;   // Pa, -, m, kg/m³
 *     if (wr_shell_create(&sh, &m, &sd, &d) != WR_OK) { puts(d.message); return 1; }
 *     ball.kind = WR_OBSTACLE_SPHERE; ball.radius = 0.1;              // centred at the origin
 *     dd.gravity[2] = -9.81; dd.contact.analytic = &ball; dd.contact.n_analytic = 1;
 *     if (wr_dyn_create(&sim, &sh, &dd, &d) != WR_OK) { puts(d.message); return 1; }
 *     x = (double *)wr_alloc_array(3 * (size_t)m.nv, sizeof(double));
 *     v = (double *)wr_calloc_array(3 * (size_t)m.nv, sizeof(double));
 *     for (i = 0; i < 3 * m.nv; ++i) x[i] = m.pos[i] - (i % 3 == 2 ? -0.12 : 0.2);   // 2 cm above
 *     wr_dyn_state_init(&sim, &st, x, v);
 *     for (f = 0; f < 10; ++f)
 *         if (wr_dyn_step(&sim, &st, &fs, &d) != WR_OK) { puts(d.message); return 1; }
 *     printf("t %.3f s, gap %.2e m, %d Newton\n", st.t, fs.min_distance, fs.newton_iterations);
 *     wr_dyn_free(&sim);  wr_shell_free(&sh);  wr_mesh_free(&m);  wr_free(x);  wr_free(v);
 *
 * ON TIME STEPPING
 *   wr_dyn_step advances one frame of desc.time.dt (default 1/30 s, the paper's step) in
 *   desc.time.substeps equal steps h. When a step's Newton solve does not converge (max_iter, or a
 *   line search that cannot decrease Φ) the step is restarted from its start with h/2, and so on up
 *   to desc.time.max_halvings times; the rest of the frame then continues with the reduced h (the
 *   next frame starts again at the full substep). stats.halvings counts the reductions; a step that
 *   fails at the smallest h returns WR_ERR_NOT_CONVERGED with the state at the last good step.
 *   Newton stops when a full (uncut) step moves no vertex by more than h·velocity_tol (IPC's
 *   velocity criterion, Li et al. 2020 Sec. 4.3: the step is then below velocity_tol in the
 *   velocities it sets), or when ‖∇Φ‖ has fallen below grad_tol of its value at the start.
 *
 * ON CONTACT
 *   IPC barrier (Li et al. 2020): κ b(d) with b(d) = −(d − d̂)² ln(d/d̂) on 0 < d < d̂ (statics.h
 *   wr_statics_barrier), d the distance from a cloth vertex to an analytic obstacle (statics.h
 *   wr_obstacle), or the unsigned point–triangle / edge–edge distance to a body mesh or between
 *   cloth primitives (collision.h). Every Newton step is cut before its line search so that no
 *   primitive comes closer than WR_DYN_CCD_KEEP of its current distance (max-step hook), so no
 *   iterate ever penetrates. Defaults: d̂ = 1 mm; κ = WR_DYN_KAPPA_FACTOR · m̄ · max(|g|, d̂/h²) / d̂
 *   (m̄ the mean vertex mass): the barrier holds 10× a vertex's weight, or 10× the force that stops
 *   it within d̂ in one step, at |b'| = d̂ (d ≈ d̂/2).
 *   Friction (lagged, IPC Sec. 5): at the start of each step every active contact k records its
 *   normal force λ_k = κ|b'(d_k)|, tangent basis T_k and stencil weights; over the step
 *   D = Σ_k μ λ_k f0(‖T_kᵀ Σ_i w_i (x_i − x_n,i)‖) with IPC's smoothed f0 (ε = ε_v h, ε_v =
 *   friction_eps_v): Coulomb's law μλ above the sliding speed ε_v, a stiff viscous stick below.
 *
 * ON FOLDS (cloth self-contact off)
 *   The shell's mid-edge bending (shell.h) is undefined where two neighbouring faces lie folded flat
 *   onto each other (hinge angle π: the average of their normals vanishes) and jumps there (the
 *   normalised average flips, so a hinge passing the fold changes b discontinuously). Self-contact
 *   keeps every hinge off that fold, since the vertex across a hinge and the neighbouring face (or
 *   their edges) are contact pairs. With no_self those pairs are kept alone: for each interior
 *   edge (a, b) between faces (c, a, b) and (q, b, a), the point–triangle pairs (c; a, b, q),
 *   (q; b, a, c) and the edge–edge pairs (a, c | b, q), (b, c | a, q), with the same barrier and
 *   CCD as any contact pair (no friction) but their own thickness d̂_h = min(d̂, ¼ of the mesh's
 *   smallest rest altitude): a flat hinge's pairs are about an altitude apart, so on a fine mesh
 *   (altitudes near d̂) a flat or gently bent sheet never feels them; they act only on a hinge
 *   folded to within ~15° of lying flat on itself. Two coplanar faces on one side of their shared
 *   edge overlap, so one of these distances is 0 at the fold: the barrier and CCD keep every hinge
 *   short of it, as self-contact does. Without them Newton walked the drape_ball scene without
 *   self-contact onto a fold (frame 11 of 30: ‖∇Φ‖ 5.4e4 × its start, accepted by the step test;
 *   Φ jumped by 1.1e-6 J for a move of 1e-13 m, so every later line search failed). Other pairs of
 *   the cloth still pass through each other.
 *
 * ON PROJECTION
 *   Newton (newton.h) makes each element block PSD. The shell's face blocks (membrane + bending over
 *   the face and the vertices across its edges) carry their share of the inertia when projected:
 *   each vertex's lumped mass is split evenly over the blocks that hold it, so block e is
 *   K_e + (1/h² + α/h) M_e and the blocks still sum to K_el + (1/h² + α/h) M. Projecting K_e alone
 *   would discard compression curvature that the inertia outweighs; with its share a block whose
 *   negative curvature is below m/h² passes the projection's Cholesky test unchanged, and the
 *   projected matrix is closer to the true Hessian.
 *
 * ON MOVING BODIES
 *   Body vertices are unknowns of Newton's vector after the cloth's (z = (x, body)) when some body
 *   moves; bodies without keys are then fixed DOFs. When no body moves they are not unknowns at all
 *   (Newton and its linear solves see the cloth only; contacts drop the body rows of their blocks
 *   after projection, a principal submatrix of a PSD block being PSD). A keyframed body's vertices start each step where they are and are
 *   pulled to their positions at the step's end by springs k/2 ‖z_b − target(t + h)‖² (k =
 *   kinematic_stiffness, default WR_DYN_KINEMATIC_FACTOR · m̄/h²), so the body's motion goes
 *   through the same CCD-limited line search as the cloth's and can never push through it; a body
 *   vertex ends within (cloth force)/k of its key.
 *
 * ON TIMING (the paper's Table 1 split)
 *   NS (numerical solving): elastic/inertia/sewing energy, gradient and Hessian assembly, the PSD
 *   projection, and the linear solves. CH (collision handling): contact detection (broad and narrow
 *   phase), CCD step limits, and the contact barrier and friction terms' values, gradients and
 *   Hessian blocks. Both are wall-clock sums over the frame's Newton iterations.
 *
 * ON GATHERING (threads: Style3D Sec. 4.2.2 shirring, 4.2.5 quilt stitches)
 *   desc.threads lists elastic thread segments between stitched vertex pairs (garment.h ON
 *   GATHERING: stitches along a shirring line's chain of mesh edges): segment s with rest length
 *   L_s [m] and axial stiffness EA_s [N] stores E_thr = EA_s/(2 L_s) · max(0, ℓ − L_s)²,
 *   ℓ = ‖x_a − x_b‖. Tension only: a thread shorter than its rest length is slack (a thread
 *   buckles at no load). Gradient k (ℓ − L)₊ u, k = EA/L, u = (x_a − x_b)/ℓ; Hessian block
 *   k [u uᵀ + (1 − L/ℓ)(I − u uᵀ)] for ℓ > L (both eigenvalues ≥ 0: PSD as it stands, never
 *   projected), 0 when slack. The rest lengths are copied into sim->thread_rest, which the
 *   caller may change between steps (a gathering schedule ramps them from the pattern length to
 *   ρ times it).
 *
 * ON THE LINEAR SOLVE
 *   desc.linear.method picks Newton's linear solver (spd.h); zero means WR_SOLVER_PCG_BLOCK3, the
 *   paper's 3×3 block-Jacobi PCG, and rel_tol zero means its 1e-5, so the paper's setup is the
 *   default. WR_SOLVER_PCG_IC0 (incomplete Cholesky on the 3×3-block pattern, spd.h ON BLOCKED
 *   KERNELS) and WR_SOLVER_CHOLMOD (a fresh factorisation per Newton step) are the alternatives,
 *   also as "linear" in the scene's solver object. Why block-Jacobi stays the default: IC(0) needs
 *   far fewer PCG iterations, but the linear solves are a minor part of NS on small meshes
 *   (assembly and projection dominate) and its factorisation loses on easy steps, so it pays only
 *   where the solves dominate, from about 2e4 vertices; the option for those meshes. Figures:
 *   bench/RESULTS.md, "Preconditioner".
 *   wr_dyn_stats.t_linear reports the solves' share of t_ns.
 *   Opt-in inexact Newton, desc.newton.forcing = η_max in (0, 1): each PCG solve of a time step stops
 *   at the relative residual η_k = min(η_max, max(rel_tol, √(‖∇Φ_k‖ / ‖∇Φ_0‖))), ∇Φ_0 the gradient
 *   at the step's start (newton.h's linear.forcing; η_k → rel_tol as the step converges, which keeps
 *   Newton's local convergence superlinear: Dembo, Eisenstat & Steihaug 1982; Eisenstat & Walker
 *   1996). The stopping tests are unchanged. 0 (the default) solves every system to rel_tol. It
 *   cuts PCG iterations 4-8x but moves the trajectory of a contact-rich drape by more than halving
 *   velocity_tol does (measured: bench/RESULTS.md, "bench_dynamics", inexact Newton).
 *
 * ON UNITS
 *   SI: m, s, kg (shell density), N/m (κ, sewing), N (thread EA), 1/s (α), s (β), m/s (tolerances).
 *
 * ON THREADS
 *   A created sim is used by one thread at a time; several sims may run concurrently. Built with
 *   OpenMP (-fopenmp), each Hessian's face blocks are computed and projected in parallel, 1024 faces
 *   at a time, into a buffer that is then added to the matrix in face order: every sum happens in
 *   the same order for any thread count, so results are bit-identical with 1, 2, … threads and
 *   without OpenMP (bench/bench_dynamics.c checks this). Energies, gradients, contact detection and
 *   the linear solves are serial.
 */
#ifndef WRINKLE_DYNAMICS_H
#define WRINKLE_DYNAMICS_H

#include "core.h"
#include "sparse.h"
#include "spd.h"
#include "mesh.h"
#include "shell.h"
#include "statics.h"
#include "newton.h"
#include "collision.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Defaults: dt 1/30 s; substeps 1; max_halvings 6 (h down to dt/64). */
typedef struct wr_dyn_time_desc {
    double dt;            /* frame length [s] */
    int32_t substeps;     /* steps per frame */
    int32_t max_halvings; /* step reductions allowed after a failed step; has_max_halvings: 0 is meaningful */
    int32_t has_max_halvings;
} wr_dyn_time_desc;

/* Rayleigh damping C = αM + βK_n; both default 0 (only backward Euler's own numerical damping). */
typedef struct wr_dyn_damping_desc {
    double mass;      /* α [1/s] */
    double stiffness; /* β [s] */
} wr_dyn_damping_desc;

/* A triangle-mesh obstacle (a body): nf faces over nv vertices at pos (nv*3 [m]); n_keys >= 2 makes
 * it move: key_pos (n_keys × nv × 3) at increasing key_time [s], linearly interpolated, held before
 * the first key and after the last (an OBJ sequence is such keys at frame times). Copied. */
typedef struct wr_dyn_body {
    int32_t nv, nf;
    const int32_t *faces;
    const double *pos;
    int32_t n_keys;
    const double *key_time;
    const double *key_pos;
} wr_dyn_body;

/* Defaults: dhat 1e-3 m; stiffness 0 → ON CONTACT; friction μ 0; friction_eps_v 1e-3 m/s;
 * analytic NULL / 0 obstacles (statics.h wr_obstacle, copied); bodies NULL / 0 (copied);
 * no_self 0 = cloth self-contact on (1: off, but hinges still kept off their fold: ON FOLDS);
 * kinematic_stiffness 0 → ON MOVING BODIES. */
typedef struct wr_dyn_contact_desc {
    double dhat;      /* barrier thickness d̂ [m] */
    double stiffness; /* κ [N/m] */
    double friction;  /* Coulomb coefficient μ >= 0 */
    double friction_eps_v; /* sliding-speed threshold ε_v [m/s] */
    const wr_obstacle *analytic;
    int32_t n_analytic;
    const wr_dyn_body *bodies;
    int32_t n_bodies;
    int32_t no_self;
    double kinematic_stiffness; /* [N/m] per body vertex */
} wr_dyn_contact_desc;

/* sewing stiffness default, × m̄/dt² (garment.h starts its sewing there too): the spring's period
 * 2π/√(k/m) is dt·2π/√k_rel ≈ 0.6 dt, so a seam closes within a few frames and backward Euler damps
 * the oscillation (ratio 1/(1+100) per step) */
#define WR_DYN_SEW_FACTOR 100.0

/* Zero-rest-length springs k/2 ‖x_a − x_b‖² between vertex pairs, active while t < duration
 * (duration 0 → always). Defaults: stiffness 0 → WR_DYN_SEW_FACTOR · m̄/dt² (pulls a seam shut
 * over a few frames against inertia). pairs: n_pairs × 2 vertex indices, copied. */
typedef struct wr_dyn_sewing_desc {
    const int32_t *pairs;
    int32_t n_pairs;
    double stiffness; /* [N/m] */
    double duration;  /* [s] */
} wr_dyn_sewing_desc;

/* Gathering threads (ON GATHERING): n_segments × 2 vertex ids, a rest length [m] (> 0) and an
 * axial stiffness EA [N] (>= 0) per segment; copied. */
typedef struct wr_dyn_thread_desc {
    const int32_t *segments;
    const double *rest;
    const double *axial;
    int32_t n_segments;
} wr_dyn_thread_desc;

/* Defaults: max_iter 50; velocity_tol 1e-2 m/s; grad_tol 1e-9 (relative to ‖∇Φ‖ at the step's
 * start); projection WR_PROJECT_FAST (newton.h: per-element PSD projection, exact near the end);
 * forcing 0 = every PCG solve to linear.rel_tol, else η_max in (0, 1) (ON THE LINEAR SOLVE). */
typedef struct wr_dyn_newton_desc {
    int32_t max_iter;
    double velocity_tol;
    double grad_tol;
    wr_projection projection;
    double forcing;
} wr_dyn_newton_desc;

/* Zero means default everywhere (see each group). gravity [m/s²] default 0; fixed NULL = none, else
 * nv flags (nonzero: the vertex keeps its position; its velocity is set to 0); linear: spd.h options
 * with method default WR_SOLVER_PCG_BLOCK3 and rel_tol default 1e-5 (the paper's setting); its
 * `fixed` is set by the simulator. */
typedef struct wr_dyn_desc {
    wr_dyn_time_desc time;
    double gravity[3];
    const uint8_t *fixed;
    wr_dyn_damping_desc damping;
    wr_dyn_contact_desc contact;
    wr_dyn_sewing_desc sewing;
    wr_dyn_newton_desc newton;
    wr_spd_desc linear;
    wr_dyn_thread_desc threads; /* none by default */
} wr_dyn_desc;

/* Caller-owned state: x, v point at nv*3 arrays [m], [m/s] that the caller allocates and frees. */
typedef struct wr_dyn_state {
    double *x;
    double *v;
    double t; /* [s] */
} wr_dyn_state;

/* One frame (wr_dyn_step) or, summed, a run (wr_dyn_run; min_distance the smallest, the last
 * solve's residual/stop). Times are wall-clock seconds. */
typedef struct wr_dyn_stats {
    int32_t frames, steps, halvings;   /* frames done, time steps taken, step reductions */
    int32_t newton_iterations, linear_iterations, line_search_evals;
    double residual;      /* last solve: ‖∇Φ‖ at its end [N] */
    double residual_rel;  /* ... relative to ‖∇Φ‖ at its start */
    wr_newton_stop stop;  /* why the last solve stopped (newton.h; STEP is the velocity criterion) */
    double t_ns, t_ch, t_total; /* ON TIMING */
    double t_linear;      /* the linear solves alone (factor + PCG; part of t_ns) */
    int32_t n_contacts;   /* active contacts (d < d̂) at the end of the frame */
    double min_distance;  /* smallest contact distance at the end of the frame [m] (HUGE_VAL: none) */
    double ccd_alpha_min; /* smallest CCD step cut (1 = never cut) */
    double h_min;         /* smallest time step used [s] */
    int32_t pattern_builds; /* Hessian patterns built (newton.h: one per solve, more when contacts appear) */
    int32_t elements_projected; /* element blocks the PSD projection changed (newton.h), summed */
} wr_dyn_stats;

/* Called after every frame of wr_dyn_run; a nonzero return stops the run (WR_OK). */
typedef int (*wr_dyn_progress_fn)(void *user, const wr_dyn_state *state, const wr_dyn_stats *frame);

struct wr__dyn_work;
struct wr__dyn_body;
typedef struct wr_dyn {
    const wr_shell *shell; /* borrowed, must outlive the sim */
    int32_t nv;            /* cloth vertices */
    wr_dyn_desc desc;      /* resolved defaults; pointer fields point at the copies below */
    double *mass;          /* nv lumped masses [kg]; may be changed between steps (e.g. a weighted hem) */
    uint8_t *fixed;        /* nv */
    int32_t *sew_pairs;    /* copy */
    wr_obstacle *analytic; /* copy */
    int32_t nb;            /* body vertices, all bodies (DOFs after the cloth's in Newton's vector) */
    double *body_x;        /* nb*3 current body positions [m] (the sim's state of the bodies) */
    int32_t *body_faces;   /* all bodies' faces, indices into body_x */
    int32_t nbf;
    struct wr__dyn_body *bodies; /* copies */
    double kappa, dhat, sew_k, mean_mass, kin_k;
    struct wr__dyn_work *w; /* private work state */
    int32_t *thread_seg;    /* copy of desc.threads.segments */
    double *thread_rest;    /* rest lengths [m]; may be changed between steps (ON GATHERING) */
    double *thread_axial;   /* EA [N] */
} wr_dyn;

WRDEF wr_status wr_dyn_create(wr_dyn *sim, const wr_shell *shell, const wr_dyn_desc *desc, wr_diag *diag);
WRDEF void wr_dyn_free(wr_dyn *sim);
WRDEF void wr_dyn_state_init(const wr_dyn *sim, wr_dyn_state *state, double *x, double *v);
/* One frame. WR_ERR_GEOMETRY (item = vertex) when a vertex starts inside an obstacle;
 * WR_ERR_NOT_CONVERGED when a step failed at the smallest h (state at the last good step). */
WRDEF wr_status wr_dyn_step(wr_dyn *sim, wr_dyn_state *state, wr_dyn_stats *stats, wr_diag *diag);
/* Frames until state->t >= t_end (to 1e-9 dt). total (may be NULL) receives the sums. */
WRDEF wr_status wr_dyn_run(wr_dyn *sim, wr_dyn_state *state, double t_end, wr_dyn_progress_fn progress, void *user,
                           wr_dyn_stats *total, wr_diag *diag);
WRDEF wr_status wr_dyn_energy(const wr_dyn *sim, const wr_dyn_state *state, double *kinetic, double *potential,
                              wr_diag *diag);
/* Smallest contact distance at cloth positions x (bodies where they are now) [m]; HUGE_VAL when
 * nothing is within d̂ of anything (and no analytic obstacle exists). */
WRDEF double wr_dyn_min_distance(wr_dyn *sim, const double *x);
WRDEF double wr_dyn_sew_gap(const wr_dyn *sim, const double *x);
/* One thread segment (ON GATHERING) between xa and xb: returns its energy [J]; g (6, may be
 * NULL) receives the gradient w.r.t. (xa, xb), H (36 row-major, may be NULL) the PSD Hessian. */
WRDEF double wr_dyn_thread_segment(const double xa[3], const double xb[3], double rest, double axial, double g[6],
                                   double H[36]);

#ifdef __cplusplus
}
#endif
#endif /* WRINKLE_DYNAMICS_H */

/* ============================================================================================ */
#ifdef WRINKLE_IMPLEMENTATION
#ifndef WRINKLE_DYNAMICS_IMPLEMENTATION_DONE
#define WRINKLE_DYNAMICS_IMPLEMENTATION_DONE

#include <float.h>
#include <math.h>
#include <string.h>

#ifdef __cplusplus
extern "C" {
#endif

#define WR_DYN_DEFAULT_DT (1.0 / 30.0) /* Style3D Sec. 5: "a 1/30s time step" */
#define WR_DYN_DEFAULT_HALVINGS 6      /* h down to dt/64 before a step is given up */
#define WR_DYN_DEFAULT_DHAT 1e-3       /* 1 mm barrier: below the 2.5 mm finest mesh of Table 1 */
#define WR_DYN_DEFAULT_EPS_V 1e-3      /* IPC's default sliding threshold, 1 mm/s */
#define WR_DYN_DEFAULT_VEL_TOL 1e-2    /* 1 cm/s (IPC: 1e-2 × bbox diagonal per second): positions to h·1e-2 = 0.33 mm at 1/30 s */
#define WR_DYN_DEFAULT_GRAD_TOL 1e-9
#define WR_DYN_DEFAULT_MAX_ITER 50
#define WR_DYN_DEFAULT_LINEAR_TOL 1e-5 /* Style3D Sec. 5: PCG "terminating when the L2 residual norm falls below 1e-5" */
/* κ default (ON CONTACT): the barrier force κ|b'| at |b'| = d̂ is this many times the larger of a
 * vertex's weight and the force that stops it within d̂ in one step (statics.h uses the same 10). */
#define WR_DYN_KAPPA_FACTOR 10.0
/* moving-body spring default, × m̄/h²: a body vertex held like a particle 1e4 times heavier than a
 * cloth vertex, so cloth pushing on it moves it by ~1e-4 of what it would move the cloth */
#define WR_DYN_KINEMATIC_FACTOR 1e4
/* CCD keeps every contact at >= this fraction of its current distance per Newton step (statics.h
 * WR_STATICS_CCD_KEEP, IPC's 0.1–0.2 safety fraction) */
#define WR_DYN_CCD_KEEP 0.2
#define WR__DYN_CCD_ITERS 64
/* face blocks computed together before they are added (2.6 MB of 18×18 blocks: cache-sized work
 * per thread, and enough faces per chunk for two threads) */
#define WR__DYN_CHUNK 1024

/* one lagged friction contact (ON CONTACT): vertex v against analytic obstacle, normal force lam,
 * tangent basis T (two orthonormal rows) frozen at the step's start */
/* one lagged friction contact (ON CONTACT): the relative displacement of the contact is
 * Σ_i w[i] (x_v[i] − x_n,v[i]) over k stencil vertices (k = 1 against an analytic obstacle, 4 for a
 * point–triangle or edge–edge pair), normal force lam and tangent basis T (two orthonormal rows),
 * all frozen at the step's start */
typedef struct wr__dyn_fric {
    int32_t k, v[4];
    double w[4];
    double lam;
    double T[6];
} wr__dyn_fric;

/* a copied body */
typedef struct wr__dyn_body {
    int32_t nv, nf, off, n_keys; /* off: its first vertex in body_x */
    double *pos, *key_time, *key_pos;
} wr__dyn_body;

typedef struct wr__dyn_work {
    int32_t n;          /* 3 (nv + nb): cloth and body vertices, the collision mesh's vector */
    int32_t nn;         /* Newton's DOFs: n with a moving body, else 3 nv (held bodies are no unknowns) */
    double *zc, *dzc, *gc; /* n: Newton's iterate, step and contact gradient over cloth + held bodies */
    double h;           /* current step [s] */
    double *xn, *xt;    /* step start x_n, inertial target x̃ = x_n + h v_n */
    double *z;          /* Newton's iterate (a copy of x: the state stays put when a step fails) */
    double *s1, *s2;    /* scratch of the stiffness-damping term */
    uint8_t *fixd;      /* n DOF flags */
    wr_assembly Kd;     /* the lagged K_n of stiffness damping (ON TIME STEPPING), its own pattern */
    int damp_stiff;     /* β > 0 */
    wr__dyn_fric *fr;
    int32_t n_fr, cap_fr;
    int sew_on;
    double t_ch;        /* contact work timed by the callbacks this frame (ON TIMING) */
    int have_cm, moving;       /* a collision mesh (bodies or self-contact); a body moves */
    wr_collision_mesh cm;      /* cloth faces + body faces over Newton's vector */
    wr_contact_set cs;         /* the contact set at the last evaluated point */
    double *target;            /* nb*3 body positions at the step's end (moving bodies) */
    double *mshare, *mdiag;    /* nv: 1/(face blocks holding v), 1 where none does (mass on the diagonal) */
    int face_blocks;           /* the shell has face blocks (membrane, mid-edge or dihedral bending) */
    double *kbuf;              /* WR__DYN_CHUNK face blocks (18×18 each) of one chunk */
    int32_t *kvert;            /* per block: k, then k vertices (7 ints) */
    int8_t *kstat, *kproj;     /* per block: failed, changed by the projection */
    int32_t n_hinge, *hinge;   /* ON FOLDS: n_hinge pairs of 5 ints (kind, 4 cloth vertices) */
    double dhat_h;             /* their barrier thickness: min(d̂, ¼ of the smallest rest altitude) */
    wr_contact_set hs;         /* the hinge pairs within d̂ at the last evaluated point (cap n_hinge) */
} wr__dyn_work;

static double wr__dyn_now(void) { return wr_time_seconds(); }

/* ---- IPC friction mollifier (Li et al. 2020 Eq. 15) ---------------------------------------- */

/* f0(y) with f0' = f1: −y³/(3ε²) + y²/ε + ε/3 below ε, y above. */
static double wr__dyn_f0(double y, double eps) {
    return y >= eps ? y : -y * y * y / (3.0 * eps * eps) + y * y / eps + eps / 3.0;
}
/* f1(y)/y (finite at 0: 2/ε) */
static double wr__dyn_f1_over_y(double y, double eps) { return y >= eps ? 1.0 / y : 2.0 / eps - y / (eps * eps); }

static void wr__dyn_tangent_basis(const double n[3], double T[6]) {
    double a[3] = {1.0, 0.0, 0.0}, t1[3], t2[3], l;
    int i;
    if (fabs(n[0]) > 0.8) a[0] = 0.0, a[1] = 1.0;
    t1[0] = n[1] * a[2] - n[2] * a[1];
    t1[1] = n[2] * a[0] - n[0] * a[2];
    t1[2] = n[0] * a[1] - n[1] * a[0];
    l = sqrt(t1[0] * t1[0] + t1[1] * t1[1] + t1[2] * t1[2]);
    for (i = 0; i < 3; ++i) t1[i] /= l;
    t2[0] = n[1] * t1[2] - n[2] * t1[1];
    t2[1] = n[2] * t1[0] - n[0] * t1[2];
    t2[2] = n[0] * t1[1] - n[1] * t1[0];
    for (i = 0; i < 3; ++i) T[i] = t1[i], T[3 + i] = t2[i];
}

/* ---- the lagged K_n of stiffness damping (file top block) ------------------------------------- */

/* shell.h sink into the sim's own assembly: each element block projected (wr_newton_project_spd) */
static wr_status wr__dyn_kd_add(void *user, int32_t k, const int32_t *verts, const double *Ke) {
    wr_assembly *a = (wr_assembly *)user;
    double buf[WR_DENSE_MAX * WR_DENSE_MAX];
    int32_t n = 3 * k;
    if (n > WR_DENSE_MAX) return wr_assembly_add(a, k, verts, Ke, NULL); /* quadratic bending: PSD */
    memcpy(buf, Ke, sizeof(double) * (size_t)(n * n));
    wr_newton_project_spd(n, buf, 0.0);
    return wr_assembly_add(a, k, verts, buf, NULL);
}

/* K_n: the projected elastic Hessian at x_n, assembled once per step (the pattern once per sim). */
static wr_status wr__dyn_lag_stiffness(wr_dyn *sim, const double *xn, wr_diag *diag) {
    wr__dyn_work *w = sim->w;
    wr_hess_sink hs;
    wr_status st;
    hs.user = &w->Kd;
    hs.add = wr__dyn_kd_add;
    do {
        wr_assembly_begin(&w->Kd);
        st = wr_shell_hessian_elements(sim->shell, xn, 0, &hs, diag);
        if (st == WR_OK) st = wr_assembly_end(&w->Kd, diag);
    } while (st == WR_OK && w->Kd.stale);
    return st;
}

/* β/h K_n into Newton's matrix: diagonal blocks as diagonal blocks, each off-diagonal pair (I < J) as
 * a two-vertex element [[0, B], [Bᵀ, 0]] (not PSD on its own, so added unprojected: the sum is the
 * PSD K_n) */
static wr_status wr__dyn_stream_stiffness(const wr_dyn *sim, wr_newton_hessian *H) {
    const wr_csr *K = &sim->w->Kd.A;
    double c = sim->desc.damping.stiffness / sim->w->h, B[9], E[36];
    int32_t I, J, p, i, j, v[2];
    wr_status st;
    for (I = 0; I < K->n / 3; ++I)
        for (p = K->rowptr[3 * I]; p < K->rowptr[3 * I + 1]; p += 3) {
            J = K->col[p] / 3;
            if (J < I) continue;
            for (i = 0; i < 3; ++i)
                for (j = 0; j < 3; ++j) B[3 * i + j] = c * K->val[K->rowptr[3 * I + i] + (p - K->rowptr[3 * I]) + j];
            if (J == I) {
                if ((st = wr_newton_add_diagonal(H, I, B)) != WR_OK) return st;
                continue;
            }
            memset(E, 0, sizeof E);
            for (i = 0; i < 3; ++i)
                for (j = 0; j < 3; ++j) E[6 * i + 3 + j] = E[6 * (3 + j) + i] = B[3 * i + j];
            v[0] = I;
            v[1] = J;
            if ((st = wr_newton_add_element_psd(H, 2, v, E)) != WR_OK) return st;
        }
    return WR_OK;
}

/* ---- the incremental potential Φ (file top block) -------------------------------------------- */

/* Gathering threads (ON GATHERING): their energy, gradient added to g (may be NULL). */
static double wr__dyn_threads(const wr_dyn *sim, const double *z, double *g) {
    double e = 0.0, gs[6];
    int32_t s, i;
    for (s = 0; s < sim->desc.threads.n_segments; ++s) {
        int32_t a = sim->thread_seg[2 * s], b = sim->thread_seg[2 * s + 1];
        e += wr_dyn_thread_segment(z + 3 * a, z + 3 * b, sim->thread_rest[s], sim->thread_axial[s], g ? gs : NULL, NULL);
        if (g)
            for (i = 0; i < 3; ++i) {
                g[3 * a + i] += gs[i];
                g[3 * b + i] += gs[3 + i];
            }
    }
    return e;
}

/* Inertia, mass damping, gravity, stiffness damping, sewing, threads: value added to *E, gradient to g. */
static void wr__dyn_smooth_terms(const wr_dyn *sim, const double *z, double *E, double *g) {
    const wr__dyn_work *w = sim->w;
    double h = w->h, ci = 1.0 / (2.0 * h * h), cd = sim->desc.damping.mass / (2.0 * h), e = 0.0;
    int32_t v, i, p;
    for (v = 0; v < sim->nv; ++v) {
        double m = sim->mass[v];
        for (i = 0; i < 3; ++i) {
            int32_t k = 3 * v + i;
            double a = z[k] - w->xt[k], b = z[k] - w->xn[k];
            e += m * (ci * a * a + cd * b * b - sim->desc.gravity[i] * z[k]);
            if (g) g[k] += m * (2.0 * ci * a + 2.0 * cd * b - sim->desc.gravity[i]);
        }
    }
    if (w->damp_stiff) { /* β/(2h) Δᵀ K_n Δ, Δ = z − x_n */
        double *d = w->s1, *Kdd = w->s2, q = 0.0, c = sim->desc.damping.stiffness / h;
        for (i = 0; i < 3 * sim->nv; ++i) d[i] = z[i] - w->xn[i];
        wr_csr_spmv(&w->Kd.A, d, Kdd);
        for (i = 0; i < 3 * sim->nv; ++i) { /* K_n is over the cloth alone */
            q += d[i] * Kdd[i];
            if (g) g[i] += c * Kdd[i];
        }
        e += 0.5 * c * q;
    }
    if (w->moving) /* moving bodies: stiff springs to their keyframed positions (ON MOVING BODIES) */
        for (i = 0; i < 3 * sim->nb; ++i) {
            double d = z[3 * sim->nv + i] - w->target[i];
            e += 0.5 * sim->kin_k * d * d;
            if (g) g[3 * sim->nv + i] += sim->kin_k * d;
        }
    if (w->sew_on)
        for (p = 0; p < sim->desc.sewing.n_pairs; ++p) {
            int32_t a = sim->sew_pairs[2 * p], b = sim->sew_pairs[2 * p + 1];
            for (i = 0; i < 3; ++i) {
                double d = z[3 * a + i] - z[3 * b + i];
                e += 0.5 * sim->sew_k * d * d;
                if (g) {
                    g[3 * a + i] += sim->sew_k * d;
                    g[3 * b + i] -= sim->sew_k * d;
                }
            }
        }
    e += wr__dyn_threads(sim, z, g);
    *E += e;
}

/* Friction potential of one lagged contact at z: y = |Tᵀ Σ w_i (z_i − x_n,i)|; value μλ f0(y);
 * gradient (when g) added per stencil vertex; u (2) returned for the Hessian. */
static double wr__dyn_fric_eval(const wr__dyn_fric *f, const double *z, const double *xn, double mu, double eps,
                                double *g, double u[2], double *y) {
    double r[3] = {0, 0, 0}, c;
    int32_t a, i;
    for (a = 0; a < f->k; ++a)
        for (i = 0; i < 3; ++i) r[i] += f->w[a] * (z[3 * f->v[a] + i] - xn[3 * f->v[a] + i]);
    u[0] = f->T[0] * r[0] + f->T[1] * r[1] + f->T[2] * r[2];
    u[1] = f->T[3] * r[0] + f->T[4] * r[1] + f->T[5] * r[2];
    *y = sqrt(u[0] * u[0] + u[1] * u[1]);
    if (g) {
        c = mu * f->lam * wr__dyn_f1_over_y(*y, eps);
        for (a = 0; a < f->k; ++a)
            for (i = 0; i < 3; ++i) g[3 * f->v[a] + i] += f->w[a] * c * (f->T[i] * u[0] + f->T[3 + i] * u[1]);
    }
    return mu * f->lam * wr__dyn_f0(*y, eps);
}

/* The hinge pairs (ON FOLDS) within d̂ at z into w->hs; WR_ERR_GEOMETRY when one touches (a fold). */
static wr_status wr__dyn_hinge_contacts(wr_dyn *sim, const double *z, wr_diag *diag) {
    wr__dyn_work *w = sim->w;
    int32_t p, a, i;
    w->hs.n = 0;
    w->hs.min_distance = HUGE_VAL;
    for (p = 0; p < w->n_hinge; ++p) {
        const int32_t *hp = w->hinge + 5 * p;
        double x12[12], s2, d;
        for (a = 0; a < 4; ++a)
            for (i = 0; i < 3; ++i) x12[3 * a + i] = z[3 * hp[1 + a] + i];
        s2 = hp[0] == WR_CONTACT_PT ? wr_collision_point_triangle_dist2(x12, x12 + 3, x12 + 6, x12 + 9, NULL, NULL, NULL, NULL)
                                    : wr_collision_edge_edge_dist2(x12, x12 + 3, x12 + 6, x12 + 9, NULL, NULL, NULL, NULL);
        if (!(s2 > 0.0))
            return wr_fail(diag, WR_ERR_GEOMETRY, hp[1], "dynamics: the faces at the hinge of vertices %d %d %d %d are folded flat",
                           (int)hp[1], (int)hp[2], (int)hp[3], (int)hp[4]);
        d = sqrt(s2);
        if (d < w->hs.min_distance) w->hs.min_distance = d;
        if (d >= w->dhat_h) continue;
        {
            wr_contact *ct = w->hs.c + w->hs.n++;
            memset(ct, 0, sizeof *ct);
            ct->kind = hp[0];
            for (a = 0; a < 4; ++a) ct->v[a] = hp[1 + a];
            ct->d = d;
        }
    }
    return WR_OK;
}

/* Barriers (analytic obstacles; body and self pairs through collision.h) and lagged friction
 * (ON CONTACT): value added to *E, gradient to g; the mesh contact set at z is left in w->cs.
 * WR_ERR_GEOMETRY when a vertex is on or inside an obstacle, or a pair touches (Φ = +∞ there). */
static wr_status wr__dyn_contact_terms(wr_dyn *sim, const double *z, double *E, double *g, double *dmin,
                                       int32_t *n_active, wr_diag *diag) {
    wr__dyn_work *w = sim->w;
    double e = 0.0, dm = HUGE_VAL, mu = sim->desc.contact.friction, eps = sim->desc.contact.friction_eps_v * w->h, u[2], y;
    int32_t o, v, i, k, na = 0;
    wr_status st;
    for (o = 0; o < sim->desc.contact.n_analytic; ++o)
        for (v = 0; v < sim->nv; ++v) {
            double gd[3], d, b1;
            if (sim->fixed[v]) continue;
            d = wr_obstacle_distance(sim->analytic + o, z + 3 * v, gd);
            if (d < dm) dm = d;
            if (!(d > 0.0))
                return wr_fail(diag, WR_ERR_GEOMETRY, v, "dynamics: vertex %d is %.3e m inside obstacle %d", (int)v, -d,
                               (int)o);
            if (d >= sim->dhat) continue;
            na++;
            e += wr_statics_barrier(d, sim->dhat, sim->kappa, &b1, NULL);
            if (g)
                for (i = 0; i < 3; ++i) g[3 * v + i] += b1 * gd[i];
        }
    if (w->have_cm) {
        double Ec = 0.0;
        if ((st = wr_collision_contacts(&w->cm, z, sim->dhat, &w->cs, diag)) != WR_OK) return st;
        if ((st = wr_collision_contact_energy(&w->cs, z, sim->dhat, sim->kappa, 0, &Ec, g, NULL, diag)) != WR_OK) return st;
        e += Ec;
        na += w->cs.n;
        if (w->cs.min_distance < dm) dm = w->cs.min_distance;
    }
    if (w->n_hinge) {
        double Eh = 0.0;
        if ((st = wr__dyn_hinge_contacts(sim, z, diag)) != WR_OK) return st;
        if ((st = wr_collision_contact_energy(&w->hs, z, w->dhat_h, sim->kappa, 0, &Eh, g, NULL, diag)) != WR_OK) return st;
        e += Eh;
        na += w->hs.n;
        if (w->hs.min_distance < dm) dm = w->hs.min_distance;
    }
    for (k = 0; k < w->n_fr && mu > 0.0; ++k) e += wr__dyn_fric_eval(w->fr + k, z, w->xn, mu, eps, g, u, &y);
    *E += e;
    if (dmin) *dmin = dm;
    if (n_active) *n_active = na;
    return WR_OK;
}

/* Newton's vector z (nn) as the collision mesh's (n): z, then the held bodies (set per step). */
static const double *wr__dyn_full(wr__dyn_work *w, const double *z, double *buf) {
    if (w->nn == w->n) return z;
    memcpy(buf, z, sizeof(double) * (size_t)w->nn);
    return buf;
}

/* Contact elements into Newton's matrix with held-body vertices (not unknowns) dropped: the block
 * is made PSD over all its vertices first (when the step projects), so its cloth part, a principal
 * submatrix, stays PSD. */
typedef struct wr__dyn_csink {
    wr_newton_hessian *H;
    int32_t nblk; /* Newton's blocks: vertices >= nblk are held body vertices */
    int psd;      /* the elements are PSD by construction (friction) */
} wr__dyn_csink;

static wr_status wr__dyn_csink_add(void *user, int32_t k, const int32_t *verts, const double *Ke) {
    wr__dyn_csink *cs = (wr__dyn_csink *)user;
    double buf[WR_DENSE_MAX * WR_DENSE_MAX];
    int32_t vv[WR_DENSE_MAX / 3], a, n = 3 * k, drop = 0;
    if (k > WR_DENSE_MAX / 3) return WR_ERR_INVALID_ARG;
    for (a = 0; a < k; ++a) {
        vv[a] = verts[a] < cs->nblk ? verts[a] : -1;
        drop |= vv[a] < 0;
    }
    if (!drop) return cs->psd ? wr_newton_add_element_psd(cs->H, k, verts, Ke) : wr_newton_sink_add(cs->H, k, verts, Ke);
    if (cs->psd) return wr_newton_add_element_psd(cs->H, k, vv, Ke);
    memcpy(buf, Ke, sizeof(double) * (size_t)(n * n));
    /* projected over the whole stencil (newton.h's per-step mode), then added with the rows dropped */
    if (!wr_newton_hessian_exact(cs->H)) {
        cs->H->n_elem++;
        cs->H->n_proj += (cs->H->proj == WR_PROJECT_JACOBI ? wr_dense_project_spd(n, buf, 0.0)
                                                           : wr_newton_project_spd(n, buf, 0.0)) != 0;
    }
    return wr_newton_add_element_psd(cs->H, k, vv, buf);
}

/* Newton's energy callback: Φ(z), ∇Φ; scale = Σ|parts| (newton.h ON STOPPING). A penetrating
 * vertex or a degenerate face is outside Φ's domain (an error status). */
static wr_status wr__dyn_energy_cb(void *user, const double *z, double *Phi, double *g, double *scale, wr_diag *diag) {
    wr_dyn *sim = (wr_dyn *)user;
    wr__dyn_work *w = sim->w;
    double E = 0.0, Es = 0.0, Ec = 0.0, t0;
    wr_status st = wr_shell_energy(sim->shell, z, &E, g, diag);
    if (st != WR_OK) return st;
    if (g && w->nn > 3 * sim->nv) memset(g + 3 * sim->nv, 0, sizeof(double) * (size_t)(w->nn - 3 * sim->nv));
    wr__dyn_smooth_terms(sim, z, &Es, g);
    t0 = wr__dyn_now();
    if (w->nn == w->n) {
        st = wr__dyn_contact_terms(sim, z, &Ec, g, NULL, NULL, diag);
    } else { /* held bodies: contact terms over (z, body), their body rows dropped */
        int32_t i;
        if (g) memset(w->gc, 0, sizeof(double) * (size_t)w->n);
        st = wr__dyn_contact_terms(sim, wr__dyn_full(w, z, w->zc), &Ec, g ? w->gc : NULL, NULL, NULL, diag);
        if (g)
            for (i = 0; i < w->nn; ++i) g[i] += w->gc[i];
    }
    w->t_ch += wr__dyn_now() - t0;
    if (st != WR_OK) return st;
    *Phi = E + Es + Ec;
    if (scale) *scale = fabs(E) + fabs(Es) + fabs(Ec);
    if (!(*Phi - *Phi == 0.0)) return wr_fail(diag, WR_ERR_DOMAIN, -1, "dynamics: incremental potential is not finite");
    return WR_OK;
}

/* One friction contact's Hessian μλ ∇²f0 as a k-vertex element: in the tangent plane
 * f1/y I + (f1' y − f1)/y³ u uᵀ; below ε that is (2/ε − y/ε²) I − u uᵀ/(ε² y), PSD (eigenvalue
 * 2(1 − y/ε)/ε along u); above ε it is (I − ûûᵀ)/y, PSD (IPC Sec. 5.2); block (a, b) = w_a w_b T H2 Tᵀ. */
static wr_status wr__dyn_fric_hessian(const wr__dyn_fric *f, const double *z, const double *xn, double mu, double eps,
                                      wr__dyn_csink *H) {
    double u[2], y, a, c, H2[4], TH[6], B[9], K[144];
    int32_t i, j, p, q;
    wr__dyn_fric_eval(f, z, xn, mu, eps, NULL, u, &y);
    c = mu * f->lam;
    a = wr__dyn_f1_over_y(y, eps);
    for (i = 0; i < 2; ++i)
        for (j = 0; j < 2; ++j) {
            double uu = y > 0.0 ? u[i] * u[j] : 0.0;
            H2[2 * i + j] = c * ((i == j ? a : 0.0) - (y >= eps ? uu / (y * y * y) : (y > 0.0 ? uu / (eps * eps * y) : 0.0)));
        }
    for (i = 0; i < 3; ++i)
        for (j = 0; j < 2; ++j) TH[2 * i + j] = f->T[i] * H2[j] + f->T[3 + i] * H2[2 + j];
    for (i = 0; i < 3; ++i)
        for (j = 0; j < 3; ++j) B[3 * i + j] = TH[2 * i] * f->T[j] + TH[2 * i + 1] * f->T[3 + j];
    if (f->k == 1) return wr_newton_add_diagonal(H->H, f->v[0], B);
    for (p = 0; p < f->k; ++p)
        for (q = 0; q < f->k; ++q)
            for (i = 0; i < 3; ++i)
                for (j = 0; j < 3; ++j) K[(3 * p + i) * 3 * f->k + 3 * q + j] = f->w[p] * f->w[q] * B[3 * i + j];
    return wr__dyn_csink_add(H, f->k, f->v, K);
}

/* Contact and friction Hessian blocks: analytic obstacles vertex-diagonal, mesh pairs 4-vertex
 * elements (projected or exact by Newton's phase, like the elastic ones), friction elements PSD. */
static wr_status wr__dyn_contact_hessian(wr_dyn *sim, const double *zn, wr_newton_hessian *H, wr_diag *diag) {
    wr__dyn_work *w = sim->w;
    double mu = sim->desc.contact.friction, eps = sim->desc.contact.friction_eps_v * w->h, B[9];
    const double *z = wr__dyn_full(w, zn, w->zc);
    int32_t o, v, i, j, k;
    wr__dyn_csink cs, fs;
    wr_status st;
    cs.H = fs.H = H;
    cs.nblk = fs.nblk = w->nn / 3;
    cs.psd = 0;
    fs.psd = 1;
    for (o = 0; o < sim->desc.contact.n_analytic; ++o)
        for (v = 0; v < sim->nv; ++v) {
            double gd[3], d, b2;
            if (sim->fixed[v]) continue;
            d = wr_obstacle_distance(sim->analytic + o, z + 3 * v, gd);
            if (!(d > 0.0) || d >= sim->dhat) continue;
            /* κ[b'' ∇d∇dᵀ + b' ∇²d]: the second term is NSD on a convex obstacle (b' < 0, ∇²d >= 0),
             * so its PSD projection is the first alone (statics.h ON CONTACT) */
            wr_statics_barrier(d, sim->dhat, sim->kappa, NULL, &b2);
            for (i = 0; i < 3; ++i)
                for (j = 0; j < 3; ++j) B[3 * i + j] = b2 * gd[i] * gd[j];
            if ((st = wr_newton_add_diagonal(H, v, B)) != WR_OK) return st;
        }
    if (w->have_cm) {
        wr_hess_sink hs;
        double Ec = 0.0;
        hs.user = &cs;
        hs.add = wr__dyn_csink_add;
        if ((st = wr_collision_contacts(&w->cm, z, sim->dhat, &w->cs, diag)) != WR_OK) return st;
        if ((st = wr_collision_contact_energy(&w->cs, z, sim->dhat, sim->kappa, 0, &Ec, NULL, &hs, diag)) != WR_OK)
            return st;
    }
    if (w->n_hinge) { /* ON FOLDS: projected or exact by Newton's phase, as the mesh pairs */
        wr_hess_sink hh;
        double Eh = 0.0;
        hh.user = &cs;
        hh.add = wr__dyn_csink_add;
        if ((st = wr__dyn_hinge_contacts(sim, z, diag)) != WR_OK) return st;
        if ((st = wr_collision_contact_energy(&w->hs, z, w->dhat_h, sim->kappa, 0, &Eh, NULL, &hh, diag)) != WR_OK) return st;
    }
    for (k = 0; k < w->n_fr && mu > 0.0; ++k)
        if ((st = wr__dyn_fric_hessian(w->fr + k, z, w->xn, mu, eps, &fs)) != WR_OK) return st;
    return WR_OK;
}

/* ---- the elastic Hessian: face blocks computed in chunks, added in face order (ON THREADS) ----- */

/* One face block of the shell (shell.h ON ELEMENT HESSIANS: membrane + mid-edge or dihedral bending
 * over the face's corners and the vertices across its edges) plus its share of the inertia: each
 * vertex's lumped mass is split evenly over the blocks whose stencil holds it (w->mshare), so every
 * DOF of a block carries c·m_v/count_v on its diagonal (c = 1/h² + α/h) before the block is made
 * PSD; the blocks sum to K_el + cM exactly as before, but a block whose negative curvature the
 * inertia outweighs passes the projection's Cholesky test untouched (ON PROJECTION). Ke: (3k)²
 * row-major, verts: k vertices; returns WR_OK or WR_ERR_GEOMETRY (an undefined normal). */
static wr_status wr__dyn_face_block(const wr_dyn *sim, const double *z, int32_t f, double c, int32_t *k, int32_t verts[6],
                                    double *Ke) {
    const double *ms = sim->w->mshare;
    int32_t a, i, kk;
    wr_status st = wr_shell_face_block(sim->shell, f, z, k, verts, Ke);
    if (st != WR_OK) return st;
    kk = 3 * *k;
    for (a = 0; a < *k; ++a)
        for (i = 0; i < 3; ++i) Ke[(3 * a + i) * kk + 3 * a + i] += c * ms[verts[a]] * sim->mass[verts[a]];
    return WR_OK;
}

/* The face blocks into Newton's matrix: WR__DYN_CHUNK faces at a time are computed and projected
 * (per Newton's mode for this step, newton.h ON PROJECTION) independently — in parallel with
 * OpenMP — into w->kbuf, then added one by one in face order, so the matrix is bit-identical for
 * any thread count. Newton's element counters and projection time are kept as its own sink would
 * (the time as the chunk's wall time share). */
static wr_status wr__dyn_face_blocks(wr_dyn *sim, const double *z, double c, wr_newton_hessian *H, wr_diag *diag) {
    wr__dyn_work *w = sim->w;
    int32_t nf = sim->shell->nf, f0, i;
    int proj = H->proj;
    for (f0 = 0; f0 < nf; f0 += WR__DYN_CHUNK) {
        int32_t nb = nf - f0 < WR__DYN_CHUNK ? nf - f0 : WR__DYN_CHUNK;
        double t0 = wr__dyn_now(), tp = 0.0;
#ifdef _OPENMP
#pragma omp parallel for schedule(static) reduction(+ : tp) if (nb >= 64)
#endif
        for (i = 0; i < nb; ++i) {
            double *Ke = w->kbuf + (size_t)324 * i, t1;
            int32_t *kv = w->kvert + 7 * i, k = 0;
            w->kstat[i] = (int8_t)(wr__dyn_face_block(sim, z, f0 + i, c, &k, kv + 1, Ke) != WR_OK);
            kv[0] = k;
            w->kproj[i] = 0;
            if (w->kstat[i] || proj == WR_PROJECT_NONE) continue;
            t1 = wr__dyn_now();
            w->kproj[i] = (int8_t)((proj == WR_PROJECT_JACOBI ? wr_dense_project_spd(3 * k, Ke, 0.0)
                                                              : wr_newton_project_spd(3 * k, Ke, 0.0)) != 0);
            tp += wr__dyn_now() - t1;
        }
        for (i = 0; i < nb; ++i) {
            wr_status st;
            if (w->kstat[i])
                return wr_fail(diag, WR_ERR_GEOMETRY, f0 + i, "dynamics: face %d has an undefined normal", (int)(f0 + i));
            H->n_elem++;
            H->n_proj += w->kproj[i];
            if ((st = wr_newton_add_element_psd(H, w->kvert[7 * i], w->kvert + 7 * i + 1, w->kbuf + (size_t)324 * i)) != WR_OK)
                return wr_fail(diag, st, f0 + i, "dynamics: face %d not assembled", (int)(f0 + i));
        }
        /* the projections' summed time, capped by the chunk's wall time when threads overlap */
        H->t_proj += fmin(tp, wr__dyn_now() - t0);
    }
    return WR_OK;
}

/* Which shell face blocks hold which vertex (shell.h ON ELEMENT HESSIANS: the face's corners, and
 * the vertices across its edges with mid-edge or dihedral bending): the inertia shares above. */
static void wr__dyn_mass_shares(wr_dyn *sim) {
    const wr_shell *s = sim->shell;
    wr__dyn_work *w = sim->w;
    int32_t f, a, v, vs[6];
    int faces = s->membrane != WR_MEMBRANE_NONE || s->bending == WR_BENDING_MIDEDGE || s->bending == WR_BENDING_DIHEDRAL;
    int opp = s->bending == WR_BENDING_MIDEDGE || s->bending == WR_BENDING_DIHEDRAL;
    w->face_blocks = faces;
    for (v = 0; v < sim->nv; ++v) w->mshare[v] = 0.0;
    for (f = 0; faces && f < s->nf; ++f) {
        wr_shell_face_stencil(s, f, vs);
        for (a = 0; a < 6; ++a)
            if (vs[a] >= 0 && (a < 3 || opp)) w->mshare[vs[a]] += 1.0;
    }
    /* fractions, not masses: sim->mass may be changed after wr_dyn_create (a weighted hem), and the
     * Hessian's inertia must stay the energy's */
    for (v = 0; v < sim->nv; ++v) {
        w->mdiag[v] = w->mshare[v] > 0.0 ? 0.0 : 1.0;
        w->mshare[v] = w->mshare[v] > 0.0 ? 1.0 / w->mshare[v] : 0.0;
    }
}

/* Newton's Hessian callback: K_el + M(1/h² + α/h) (face blocks with their inertia share, projected
 * by Newton per its phase) + β/h K_n + sewing + moving-body springs + contact and friction. */
static wr_status wr__dyn_hessian_cb(void *user, const double *z, wr_newton_hessian *H, wr_diag *diag) {
    wr_dyn *sim = (wr_dyn *)user;
    wr__dyn_work *w = sim->w;
    double c = 1.0 / (w->h * w->h) + sim->desc.damping.mass / w->h, B[9], S[36], t0;
    int32_t v, p, i, j, vv[2];
    wr_hess_sink hs;
    wr_status st;
    hs.user = H;
    hs.add = wr_newton_sink_add;
    if (w->face_blocks && (st = wr__dyn_face_blocks(sim, z, c, H, diag)) != WR_OK) return st;
    /* quadratic bending stencils (x-independent, PSD): the shell streams them */
    if (sim->shell->bending == WR_BENDING_QUADRATIC &&
        (st = wr_shell_hessian_elements_part(sim->shell, z, 0, WR_SHELL_HESS_QUADRATIC, &hs, diag)) != WR_OK)
        return st;
    if (w->damp_stiff && (st = wr__dyn_stream_stiffness(sim, H)) != WR_OK) return st;
    memset(B, 0, sizeof B);
    for (v = 0; v < sim->nv; ++v)
        if (w->mdiag[v] > 0.0) {
            B[0] = B[4] = B[8] = c * w->mdiag[v] * sim->mass[v];
            if ((st = wr_newton_add_diagonal(H, v, B)) != WR_OK) return st;
        }
    if (w->moving)
        for (v = 0; v < sim->nb; ++v) {
            B[0] = B[4] = B[8] = sim->kin_k;
            if ((st = wr_newton_add_diagonal(H, sim->nv + v, B)) != WR_OK) return st;
        }
    if (w->sew_on) {
        memset(S, 0, sizeof S);
        for (i = 0; i < 6; ++i)
            for (j = 0; j < 6; ++j)
                if (i % 3 == j % 3) S[6 * i + j] = (i / 3 == j / 3 ? 1.0 : -1.0) * sim->sew_k;
        for (p = 0; p < sim->desc.sewing.n_pairs; ++p) {
            vv[0] = sim->sew_pairs[2 * p];
            vv[1] = sim->sew_pairs[2 * p + 1];
            if ((st = wr_newton_add_element_psd(H, 2, vv, S)) != WR_OK) return st;
        }
    }
    for (p = 0; p < sim->desc.threads.n_segments; ++p) { /* ON GATHERING: PSD as computed */
        double T[36];
        vv[0] = sim->thread_seg[2 * p];
        vv[1] = sim->thread_seg[2 * p + 1];
        wr_dyn_thread_segment(z + 3 * vv[0], z + 3 * vv[1], sim->thread_rest[p], sim->thread_axial[p], NULL, T);
        if ((st = wr_newton_add_element_psd(H, 2, vv, T)) != WR_OK) return st;
    }
    t0 = wr__dyn_now();
    st = wr__dyn_contact_hessian(sim, z, H, diag);
    w->t_ch += wr__dyn_now() - t0;
    return st;
}

/* Max-step hook (CCD): the largest α in (0, 1] keeping every free vertex at >= WR_DYN_CCD_KEEP of
 * its current distance to every analytic obstacle along z + αΔz, and every mesh pair
 * intersection-free (collision.h's additive CCD, keep 0.1). The analytic obstacles are convex
 * solids, so the distance d(t) along the straight path is convex in t: its tangent lies below it,
 * and Newton's iteration t += (d(t) − target)/(−d'(t)) from t = 0 climbs to the first crossing of
 * the target from below (every iterate is safe); d' >= 0 means no crossing at all. (Advancing by
 * (d − target)/|Δz|, the 1-Lipschitz bound, also stays below but crawls when a vertex slides
 * tangentially at a small gap: 64 of its steps covered only 64·0.8·d0 of the path, so a sliding
 * cloth had its Newton steps cut to a fraction for no approach at all.) */
static double wr__dyn_max_step_cb(void *user, const double *zn, const double *dzn) {
    wr_dyn *sim = (wr_dyn *)user;
    double alpha = 1.0, t0 = wr__dyn_now();
    const double *z = wr__dyn_full(sim->w, zn, sim->w->zc), *dz = wr__dyn_full(sim->w, dzn, sim->w->dzc);
    int32_t o, v, it, i;
    for (o = 0; o < sim->desc.contact.n_analytic; ++o)
        for (v = 0; v < sim->nv; ++v) {
            double d0, speed, target, t = 0.0, p[3];
            if (sim->fixed[v]) continue;
            speed = sqrt(dz[3 * v] * dz[3 * v] + dz[3 * v + 1] * dz[3 * v + 1] + dz[3 * v + 2] * dz[3 * v + 2]);
            if (speed == 0.0) continue;
            d0 = wr_obstacle_distance(sim->analytic + o, z + 3 * v, NULL);
            if (speed <= (1.0 - WR_DYN_CCD_KEEP) * d0) continue;
            target = WR_DYN_CCD_KEEP * d0;
            /* Newton on the convex d(t): every iterate stays below the first crossing of target */
            for (it = 0; it < WR__DYN_CCD_ITERS && t < alpha; ++it) {
                double gap, gd[3], slope;
                for (i = 0; i < 3; ++i) p[i] = z[3 * v + i] + t * dz[3 * v + i];
                gap = wr_obstacle_distance(sim->analytic + o, p, gd) - target;
                if (gap <= 1e-6 * d0) break;
                slope = gd[0] * dz[3 * v] + gd[1] * dz[3 * v + 1] + gd[2] * dz[3 * v + 2];
                if (!(slope < 0.0)) { /* d no longer decreases, and a convex d never turns down again */
                    t = alpha;
                    break;
                }
                t += gap / -slope;
            }
            if (t < alpha) alpha = t;
        }
    if (sim->w->have_cm) {
        double a = 1.0;
        /* a failure here (out of memory) can only be reported as "no safe step" */
        if (wr_collision_max_step(&sim->w->cm, z, dz, &a, NULL, NULL) != WR_OK) a = 0.0;
        if (a < alpha) alpha = a;
    }
    for (o = 0; o < sim->w->n_hinge; ++o) { /* ON FOLDS: the hinge pairs' additive CCD */
        const int32_t *hp = sim->w->hinge + 5 * o;
        double x12[12], d12[12], toi, moved = 0.0;
        for (v = 0; v < 4; ++v)
            for (i = 0; i < 3; ++i) {
                x12[3 * v + i] = z[3 * hp[1 + v] + i];
                d12[3 * v + i] = dz[3 * hp[1 + v] + i];
                moved += fabs(d12[3 * v + i]);
            }
        if (moved > 0.0 && wr_collision_accd((wr_contact_kind)hp[0], x12, d12, WR_COLLISION_CCD_KEEP, alpha, 0, &toi) &&
            toi < alpha)
            alpha = toi;
    }
    sim->w->t_ch += wr__dyn_now() - t0;
    return alpha;
}

static wr_status wr__dyn_fric_push(wr__dyn_work *w, wr__dyn_fric **f, wr_diag *diag) {
    if (w->n_fr == w->cap_fr) {
        int32_t cap = w->cap_fr ? 2 * w->cap_fr : 256;
        wr__dyn_fric *nf = (wr__dyn_fric *)wr_realloc_array(w->fr, (size_t)cap, sizeof(wr__dyn_fric));
        if (!nf) return wr_fail(diag, WR_ERR_NOMEM, -1, "dynamics: out of memory (%d friction contacts)", (int)cap);
        w->fr = nf;
        w->cap_fr = cap;
    }
    *f = w->fr + w->n_fr++;
    return WR_OK;
}

/* Lagged friction (ON CONTACT): contacts active at the step's start x_n, with their normal forces
 * λ = κ|b'(d)|, their normals and stencil weights (collision.h's closest-point coefficients). */
static wr_status wr__dyn_lag_friction(wr_dyn *sim, wr_diag *diag) {
    wr__dyn_work *w = sim->w;
    int32_t o, v, c, a;
    wr__dyn_fric *f;
    wr_status st;
    w->n_fr = 0;
    if (!(sim->desc.contact.friction > 0.0)) return WR_OK;
    for (o = 0; o < sim->desc.contact.n_analytic; ++o)
        for (v = 0; v < sim->nv; ++v) {
            double gd[3], d, b1;
            if (sim->fixed[v]) continue;
            d = wr_obstacle_distance(sim->analytic + o, w->xn + 3 * v, gd);
            if (!(d > 0.0) || d >= sim->dhat) continue;
            wr_statics_barrier(d, sim->dhat, sim->kappa, &b1, NULL);
            if ((st = wr__dyn_fric_push(w, &f, diag)) != WR_OK) return st;
            f->k = 1;
            f->v[0] = v;
            f->w[0] = 1.0;
            f->lam = fabs(b1);
            wr__dyn_tangent_basis(gd, f->T);
        }
    if (!w->have_cm) return WR_OK;
    if ((st = wr_collision_contacts(&w->cm, w->xn, sim->dhat, &w->cs, diag)) != WR_OK) return st;
    for (c = 0; c < w->cs.n; ++c) {
        const wr_contact *ct = w->cs.c + c;
        const double *p0 = w->xn + 3 * ct->v[0], *p1 = w->xn + 3 * ct->v[1], *p2 = w->xn + 3 * ct->v[2],
                     *p3 = w->xn + 3 * ct->v[3];
        double wt[4], r[3] = {0, 0, 0}, d, b1, nrm[3];
        int i;
        if (ct->kind == WR_CONTACT_PT)
            wr_collision_point_triangle_dist2(p0, p1, p2, p3, NULL, NULL, wt, NULL);
        else
            wr_collision_edge_edge_dist2(p0, p1, p2, p3, NULL, NULL, wt, NULL);
        for (a = 0; a < 4; ++a)
            for (i = 0; i < 3; ++i) r[i] += wt[a] * w->xn[3 * ct->v[a] + i];
        d = sqrt(r[0] * r[0] + r[1] * r[1] + r[2] * r[2]);
        if (!(d > 0.0) || d >= sim->dhat) continue;
        wr_collision_barrier(d, sim->dhat, sim->kappa, &b1, NULL);
        if ((st = wr__dyn_fric_push(w, &f, diag)) != WR_OK) return st;
        f->k = 4;
        for (a = 0; a < 4; ++a) f->v[a] = ct->v[a], f->w[a] = wt[a];
        f->lam = fabs(b1);
        for (i = 0; i < 3; ++i) nrm[i] = r[i] / d;
        wr__dyn_tangent_basis(nrm, f->T);
    }
    return WR_OK;
}

/* Body positions at time t (keyframes linearly interpolated, held outside their range). */
static void wr__dyn_body_at(const wr_dyn *sim, double t, double *out) {
    int32_t b, k, i;
    for (b = 0; b < sim->desc.contact.n_bodies; ++b) {
        const wr__dyn_body *bd = sim->bodies + b;
        double *o = out + 3 * (size_t)bd->off;
        if (bd->n_keys < 2) {
            memcpy(o, bd->pos, sizeof(double) * 3 * (size_t)bd->nv);
            continue;
        }
        for (k = 0; k + 2 < bd->n_keys && t > bd->key_time[k + 1]; ++k) {
        }
        {
            double t0 = bd->key_time[k], t1 = bd->key_time[k + 1], s = (t - t0) / (t1 - t0);
            const double *a = bd->key_pos + 3 * (size_t)bd->nv * k, *c = a + 3 * (size_t)bd->nv;
            s = fmin(1.0, fmax(0.0, s));
            for (i = 0; i < 3 * bd->nv; ++i) o[i] = (1.0 - s) * a[i] + s * c[i];
        }
    }
}

/* ---- one time step ------------------------------------------------------------------------ */

/* One backward Euler step of size h from state (in place): Φ minimised by the shared Newton over
 * z = (cloth x, body vertices) from z_n. On failure the state is unchanged. */
static wr_status wr__dyn_one_step(wr_dyn *sim, wr_dyn_state *state, double h, wr_newton_stats *ns, wr_diag *diag) {
    wr__dyn_work *w = sim->w;
    wr_newton_problem pb;
    wr_newton_desc nd;
    int32_t i, n = w->n, nc = 3 * sim->nv;
    wr_status st;
    double *x = state->x, *v = state->v, t0;
    memset(ns, 0, sizeof *ns);
    w->h = h;
    w->sew_on = sim->desc.sewing.n_pairs > 0 && (sim->desc.sewing.duration == 0.0 || state->t < sim->desc.sewing.duration);
    for (i = 0; i < nc; ++i) {
        w->xn[i] = x[i];
        w->xt[i] = w->fixd[i] ? x[i] : x[i] + h * v[i];
    }
    for (i = nc; i < n; ++i) w->xn[i] = w->xt[i] = sim->body_x[i - nc];
    if (w->moving) wr__dyn_body_at(sim, state->t + h, w->target);
    if (w->damp_stiff && (st = wr__dyn_lag_stiffness(sim, w->xn, diag)) != WR_OK) return st;
    t0 = wr__dyn_now();
    st = wr__dyn_lag_friction(sim, diag);
    w->t_ch += wr__dyn_now() - t0;
    if (st != WR_OK) return st;
    memset(&pb, 0, sizeof pb);
    pb.n_blocks = w->nn / 3;
    pb.block = 3;
    pb.user = sim;
    pb.energy = wr__dyn_energy_cb;
    pb.hessian = wr__dyn_hessian_cb;
    pb.max_step = wr__dyn_max_step_cb;
    memset(&nd, 0, sizeof nd);
    nd.max_iter = sim->desc.newton.max_iter;
    nd.fixed = w->fixd;
    nd.stop.grad_tol = sim->desc.newton.grad_tol;
    nd.stop.step_tol = h * sim->desc.newton.velocity_tol; /* ON TIME STEPPING: IPC's velocity criterion */
    nd.hessian.projection = sim->desc.newton.projection;
    nd.linear.solver = sim->desc.linear;
    nd.linear.forcing = sim->desc.newton.forcing;
    nd.name = "dynamics";
    /* Newton keeps the lowest-Φ iterate in its x on failure: work on a copy so the state stays */
    memcpy(w->z, w->xn, sizeof(double) * (size_t)n);
    /* held bodies: their part of the full vectors is x_n's, the step's is zero (ON MOVING BODIES) */
    memcpy(w->zc, w->xn, sizeof(double) * (size_t)n);
    memset(w->dzc, 0, sizeof(double) * (size_t)n);
    st = wr_newton_solve(&pb, w->z, &nd, ns, diag);
    if (st != WR_OK) return st;
    memcpy(x, w->z, sizeof(double) * (size_t)nc);
    if (w->nn == n && sim->nb) memcpy(sim->body_x, w->z + nc, sizeof(double) * 3 * (size_t)sim->nb);
    for (i = 0; i < nc; ++i) v[i] = w->fixd[i] ? 0.0 : (x[i] - w->xn[i]) / h;
    state->t += h;
    return WR_OK;
}

/* ---- public API ----------------------------------------------------------------------------- */

static wr_status wr__dyn_check_desc(const wr_dyn_desc *d, int32_t nv, wr_diag *diag) {
    int32_t i, o;
    double gsum = d->gravity[0] + d->gravity[1] + d->gravity[2];
    if (!(d->time.dt > 0.0) || d->time.dt - d->time.dt != 0.0)
        return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "dynamics: time.dt %g must be > 0 and finite", d->time.dt);
    if (d->time.substeps < 1 || d->time.max_halvings < 0 || d->time.max_halvings > 30)
        return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "dynamics: time.substeps %d must be >= 1, max_halvings %d in [0, 30]",
                       (int)d->time.substeps, (int)d->time.max_halvings);
    if (gsum - gsum != 0.0) return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "dynamics: gravity is not finite");
    if (!(d->damping.mass >= 0.0) || !(d->damping.stiffness >= 0.0) || d->damping.mass - d->damping.mass != 0.0 ||
        d->damping.stiffness - d->damping.stiffness != 0.0)
        return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "dynamics: damping mass %g, stiffness %g must be >= 0 and finite",
                       d->damping.mass, d->damping.stiffness);
    if (!(d->contact.dhat > 0.0) || !(d->contact.stiffness >= 0.0) || !(d->contact.friction >= 0.0) ||
        !(d->contact.friction_eps_v > 0.0) || d->contact.dhat - d->contact.dhat != 0.0 ||
        d->contact.stiffness - d->contact.stiffness != 0.0 || d->contact.friction - d->contact.friction != 0.0)
        return wr_fail(diag, WR_ERR_INVALID_ARG, -1,
                       "dynamics: contact dhat %g, stiffness %g, friction %g, friction_eps_v %g out of range", d->contact.dhat,
                       d->contact.stiffness, d->contact.friction, d->contact.friction_eps_v);
    if (d->contact.n_analytic < 0 || (d->contact.n_analytic > 0 && !d->contact.analytic))
        return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "dynamics: %d analytic obstacles with a NULL array",
                       (int)d->contact.n_analytic);
    for (o = 0; o < d->contact.n_analytic; ++o) {
        const wr_obstacle *b = d->contact.analytic + o;
        double nn = b->normal[0] * b->normal[0] + b->normal[1] * b->normal[1] + b->normal[2] * b->normal[2], fin = b->radius;
        for (i = 0; i < 3; ++i) fin += b->p[i] + b->q[i] + b->normal[i];
        if (fin - fin != 0.0 || (int)b->kind < 0 || (int)b->kind > (int)WR_OBSTACLE_CAPSULE ||
            (b->kind == WR_OBSTACLE_PLANE && !(nn > 0.0)) || (b->kind != WR_OBSTACLE_PLANE && !(b->radius > 0.0)))
            return wr_fail(diag, WR_ERR_INVALID_ARG, o, "dynamics: analytic obstacle %d is invalid (kind %d, radius %g)",
                           (int)o, (int)b->kind, b->radius);
    }
    if (d->contact.n_bodies < 0 || (d->contact.n_bodies > 0 && !d->contact.bodies) || !(d->contact.kinematic_stiffness >= 0.0))
        return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "dynamics: %d bodies with a NULL array, or kinematic_stiffness %g < 0",
                       (int)d->contact.n_bodies, d->contact.kinematic_stiffness);
    for (o = 0; o < d->contact.n_bodies; ++o) {
        const wr_dyn_body *b = d->contact.bodies + o;
        int32_t k;
        if (b->nv < 3 || b->nf < 1 || !b->faces || !b->pos || b->n_keys < 0 || (b->n_keys >= 2 && (!b->key_time || !b->key_pos)))
            return wr_fail(diag, WR_ERR_INVALID_ARG, o, "dynamics: body %d is invalid (%d vertices, %d faces, %d keys)",
                           (int)o, (int)b->nv, (int)b->nf, (int)b->n_keys);
        for (i = 0; i < 3 * b->nf; ++i)
            if (b->faces[i] < 0 || b->faces[i] >= b->nv)
                return wr_fail(diag, WR_ERR_INVALID_ARG, o, "dynamics: body %d face %d has vertex %d outside [0, %d)", (int)o,
                               (int)(i / 3), (int)b->faces[i], (int)b->nv);
        for (i = 0; i < 3 * b->nv; ++i)
            if (b->pos[i] - b->pos[i] != 0.0)
                return wr_fail(diag, WR_ERR_INVALID_ARG, o, "dynamics: body %d vertex %d is not finite", (int)o, (int)(i / 3));
        for (k = 1; k < b->n_keys; ++k)
            if (!(b->key_time[k] > b->key_time[k - 1]))
                return wr_fail(diag, WR_ERR_INVALID_ARG, o, "dynamics: body %d key times must increase (key %d)", (int)o, (int)k);
    }
    if (d->sewing.n_pairs < 0 || (d->sewing.n_pairs > 0 && !d->sewing.pairs) || !(d->sewing.stiffness >= 0.0) ||
        !(d->sewing.duration >= 0.0) || d->sewing.stiffness - d->sewing.stiffness != 0.0)
        return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "dynamics: sewing (%d pairs, stiffness %g, duration %g) is invalid",
                       (int)d->sewing.n_pairs, d->sewing.stiffness, d->sewing.duration);
    for (i = 0; i < 2 * d->sewing.n_pairs; ++i)
        if (d->sewing.pairs[i] < 0 || d->sewing.pairs[i] >= nv || (i % 2 && d->sewing.pairs[i] == d->sewing.pairs[i - 1]))
            return wr_fail(diag, WR_ERR_INVALID_ARG, i / 2, "dynamics: sewing pair %d (%d, %d) is invalid", (int)(i / 2),
                           (int)d->sewing.pairs[i - i % 2], (int)d->sewing.pairs[i - i % 2 + 1]);
    if (d->threads.n_segments < 0 || (d->threads.n_segments > 0 && (!d->threads.segments || !d->threads.rest || !d->threads.axial)))
        return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "dynamics: %d thread segments with a NULL array", (int)d->threads.n_segments);
    for (i = 0; i < d->threads.n_segments; ++i) {
        int32_t a = d->threads.segments[2 * i], b = d->threads.segments[2 * i + 1];
        double L = d->threads.rest[i], k = d->threads.axial[i];
        if (a < 0 || a >= nv || b < 0 || b >= nv || a == b || !(L > 0.0) || !(k >= 0.0) || L - L != 0.0 || k - k != 0.0)
            return wr_fail(diag, WR_ERR_INVALID_ARG, i, "dynamics: thread segment %d (%d, %d, rest %g m, EA %g N) is invalid",
                           (int)i, (int)a, (int)b, L, k);
    }
    if (d->newton.max_iter < 1 || !(d->newton.velocity_tol > 0.0) || !(d->newton.grad_tol > 0.0) ||
        (int)d->newton.projection < 0 || (int)d->newton.projection > (int)WR_PROJECT_NONE)
        return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "dynamics: newton max_iter %d, velocity_tol %g, grad_tol %g invalid",
                       (int)d->newton.max_iter, d->newton.velocity_tol, d->newton.grad_tol);
    if (!(d->linear.rel_tol > 0.0 && d->linear.rel_tol < 1.0))
        return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "dynamics: linear.rel_tol %g must be in (0, 1)", d->linear.rel_tol);
    if (!(d->newton.forcing >= 0.0 && d->newton.forcing < 1.0))
        return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "dynamics: newton.forcing %g must be in [0, 1)", d->newton.forcing);
    return WR_OK;
}

static void wr__dyn_defaults(wr_dyn_desc *d) {
    if (d->time.dt == 0.0) d->time.dt = WR_DYN_DEFAULT_DT;
    if (d->time.substeps == 0) d->time.substeps = 1;
    if (!d->time.has_max_halvings && d->time.max_halvings == 0) d->time.max_halvings = WR_DYN_DEFAULT_HALVINGS;
    if (d->contact.dhat == 0.0) d->contact.dhat = WR_DYN_DEFAULT_DHAT;
    if (d->contact.friction_eps_v == 0.0) d->contact.friction_eps_v = WR_DYN_DEFAULT_EPS_V;
    if (d->newton.max_iter == 0) d->newton.max_iter = WR_DYN_DEFAULT_MAX_ITER;
    if (d->newton.velocity_tol == 0.0) d->newton.velocity_tol = WR_DYN_DEFAULT_VEL_TOL;
    if (d->newton.grad_tol == 0.0) d->newton.grad_tol = WR_DYN_DEFAULT_GRAD_TOL;
    if (d->linear.method == WR_SOLVER_AUTO) d->linear.method = WR_SOLVER_PCG_BLOCK3;
    if (d->linear.rel_tol == 0.0) d->linear.rel_tol = WR_DYN_DEFAULT_LINEAR_TOL;
}

WRDEF void wr_dyn_free(wr_dyn *sim) {
    wr__dyn_work *w;
    if (!sim) return;
    w = sim->w;
    if (w) {
        wr_free(w->xn);
        wr_free(w->xt);
        wr_free(w->z);
        wr_free(w->s1);
        wr_free(w->s2);
        wr_free(w->fixd);
        wr_assembly_free(&w->Kd);
        if (w->have_cm) wr_collision_mesh_free(&w->cm);
        wr_contact_set_free(&w->cs);
        wr_free(w->target);
        wr_free(w->zc);
        wr_free(w->dzc);
        wr_free(w->gc);
        wr_free(w->mshare);
        wr_free(w->mdiag);
        wr_free(w->kbuf);
        wr_free(w->kvert);
        wr_free(w->kstat);
        wr_free(w->kproj);
        wr_free(w->fr);
        wr_free(w->hinge);
        wr_contact_set_free(&w->hs);
        wr_free(w);
    }
    wr_free(sim->mass);
    wr_free(sim->fixed);
    wr_free(sim->sew_pairs);
    wr_free(sim->thread_seg);
    wr_free(sim->thread_rest);
    wr_free(sim->thread_axial);
    wr_free(sim->analytic);
    if (sim->bodies) {
        int32_t b;
        for (b = 0; b < sim->desc.contact.n_bodies; ++b) {
            wr_free(sim->bodies[b].pos);
            wr_free(sim->bodies[b].key_time);
            wr_free(sim->bodies[b].key_pos);
        }
    }
    wr_free(sim->bodies);
    wr_free(sim->body_x);
    wr_free(sim->body_faces);
    memset(sim, 0, sizeof *sim);
}

/* Copies of the bodies, their vertices in one array after each other (sim->body_x at t = 0). */
static wr_status wr__dyn_copy_bodies(wr_dyn *sim, const wr_dyn_desc *d, wr_diag *diag) {
    int32_t b, nb = 0, nbf = 0, i;
    for (b = 0; b < d->contact.n_bodies; ++b) nb += d->contact.bodies[b].nv, nbf += d->contact.bodies[b].nf;
    sim->bodies = (wr__dyn_body *)wr_calloc_array((size_t)d->contact.n_bodies + 1, sizeof(wr__dyn_body));
    sim->body_x = (double *)wr_alloc_array(3 * (size_t)nb + 1, sizeof(double));
    sim->body_faces = (int32_t *)wr_alloc_array(3 * (size_t)nbf + 1, sizeof(int32_t));
    if (!sim->bodies || !sim->body_x || !sim->body_faces)
        return wr_fail(diag, WR_ERR_NOMEM, -1, "dynamics: out of memory (%d body vertices)", (int)nb);
    sim->nb = 0;
    sim->nbf = 0;
    for (b = 0; b < d->contact.n_bodies; ++b) {
        const wr_dyn_body *in = d->contact.bodies + b;
        wr__dyn_body *bd = sim->bodies + b;
        int32_t nk = in->n_keys >= 2 ? in->n_keys : 0;
        bd->nv = in->nv;
        bd->nf = in->nf;
        bd->off = sim->nb;
        bd->n_keys = nk;
        bd->pos = (double *)wr_alloc_array(3 * (size_t)in->nv, sizeof(double));
        bd->key_time = (double *)wr_alloc_array((size_t)nk + 1, sizeof(double));
        bd->key_pos = (double *)wr_alloc_array(3 * (size_t)in->nv * (size_t)nk + 1, sizeof(double));
        if (!bd->pos || !bd->key_time || !bd->key_pos)
            return wr_fail(diag, WR_ERR_NOMEM, b, "dynamics: out of memory (body %d)", (int)b);
        memcpy(bd->pos, in->pos, sizeof(double) * 3 * (size_t)in->nv);
        if (nk) {
            memcpy(bd->key_time, in->key_time, sizeof(double) * (size_t)nk);
            memcpy(bd->key_pos, in->key_pos, sizeof(double) * 3 * (size_t)in->nv * (size_t)nk);
        }
        for (i = 0; i < 3 * in->nf; ++i) sim->body_faces[3 * sim->nbf + i] = in->faces[i] + bd->off;
        sim->nb += in->nv;
        sim->nbf += in->nf;
    }
    wr__dyn_body_at(sim, 0.0, sim->body_x);
    return WR_OK;
}

/* The collision mesh over Newton's vector: cloth faces, then body faces (offset past the cloth),
 * body vertices flagged as obstacle (collision.h ON PAIRS). */
static wr_status wr__dyn_collision_setup(wr_dyn *sim, wr_diag *diag) {
    wr__dyn_work *w = sim->w;
    int32_t nf = sim->shell->nf + sim->nbf, i;
    int32_t *faces = (int32_t *)wr_alloc_array(3 * (size_t)nf, sizeof(int32_t));
    uint8_t *obst = (uint8_t *)wr_calloc_array((size_t)(sim->nv + sim->nb), 1);
    wr_collision_desc cd;
    wr_status st;
    if (!faces || !obst) {
        wr_free(faces);
        wr_free(obst);
        return wr_fail(diag, WR_ERR_NOMEM, -1, "dynamics: out of memory (%d contact faces)", (int)nf);
    }
    memcpy(faces, sim->shell->faces, sizeof(int32_t) * 3 * (size_t)sim->shell->nf);
    for (i = 0; i < 3 * sim->nbf; ++i) faces[3 * sim->shell->nf + i] = sim->body_faces[i] + sim->nv;
    for (i = sim->nv; i < sim->nv + sim->nb; ++i) obst[i] = 1;
    memset(&cd, 0, sizeof cd);
    cd.no_self = sim->desc.contact.no_self;
    st = wr_collision_mesh_create(&w->cm, sim->nv + sim->nb, nf, faces, obst, &cd, diag);
    wr_free(faces);
    wr_free(obst);
    if (st == WR_OK) w->have_cm = 1;
    return st;
}

/* The hinge pairs of ON FOLDS: per face f and edge k with a face across (vertex q), the vertex c of
 * f opposite the edge (a, b) against the face across, and once per edge (c < q) the two edge pairs. */
static wr_status wr__dyn_hinge_setup(wr_dyn *sim, wr_diag *diag) {
    wr__dyn_work *w = sim->w;
    const wr_shell *s = sim->shell;
    int32_t f, k, vs[6], *h, n = 0;
    double amin = HUGE_VAL;
    w->hinge = (int32_t *)wr_alloc_array(5 * 9 * (size_t)s->nf + 1, sizeof(int32_t));
    w->hs.c = (wr_contact *)wr_alloc_array(9 * (size_t)s->nf + 1, sizeof(wr_contact));
    if (!w->hinge || !w->hs.c) return wr_fail(diag, WR_ERR_NOMEM, -1, "dynamics: out of memory (%d hinges)", (int)(3 * s->nf));
    w->hs.cap = 9 * s->nf + 1;
    for (f = 0; f < s->nf; ++f) {
        /* rest edges: the columns of dinv's inverse; the smallest altitude is 2A / the longest edge */
        const double *D = s->dinv + 4 * f;
        double det = D[0] * D[3] - D[1] * D[2], e1[2], e2[2], lmax;
        e1[0] = D[3] / det, e1[1] = -D[2] / det, e2[0] = -D[1] / det, e2[1] = D[0] / det;
        lmax = fmax(fmax(hypot(e1[0], e1[1]), hypot(e2[0], e2[1])), hypot(e2[0] - e1[0], e2[1] - e1[1]));
        if (lmax > 0.0) amin = fmin(amin, 2.0 * s->area[f] / lmax);
        wr_shell_face_stencil(s, f, vs);
        for (k = 0; k < 3; ++k) {
            int32_t c = vs[k], a = vs[(k + 1) % 3], b = vs[(k + 2) % 3], q = vs[3 + k];
            if (q < 0) continue;
            h = w->hinge + 5 * n++;
            h[0] = WR_CONTACT_PT, h[1] = c, h[2] = a, h[3] = b, h[4] = q;
            if (c > q) continue;
            h = w->hinge + 5 * n++;
            h[0] = WR_CONTACT_EE, h[1] = a, h[2] = c, h[3] = b, h[4] = q;
            h = w->hinge + 5 * n++;
            h[0] = WR_CONTACT_EE, h[1] = b, h[2] = c, h[3] = a, h[4] = q;
        }
    }
    w->n_hinge = n;
    w->dhat_h = fmin(sim->dhat, 0.25 * amin);
    return WR_OK;
}

WRDEF wr_status wr_dyn_create(wr_dyn *sim, const wr_shell *shell, const wr_dyn_desc *desc, wr_diag *diag) {
    wr_dyn_desc d;
    wr__dyn_work *w;
    int32_t v, i, n, b;
    double msum = 0.0, gmag, h;
    wr_status st;
    if (!sim) return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "dynamics: NULL sim");
    memset(sim, 0, sizeof *sim);
    if (!shell || !shell->faces || shell->nv < 1) return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "dynamics: NULL or empty shell");
    if (!(shell->density > 0.0))
        return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "dynamics: the shell has no mass (density %g)", shell->density);
    if (desc)
        d = *desc;
    else
        memset(&d, 0, sizeof d);
    wr__dyn_defaults(&d);
    if ((st = wr__dyn_check_desc(&d, shell->nv, diag)) != WR_OK) return st;
    sim->shell = shell;
    sim->nv = shell->nv;
    sim->desc = d; /* pointer fields redirected to the copies below */
    sim->mass = (double *)wr_alloc_array((size_t)shell->nv, sizeof(double));
    sim->fixed = (uint8_t *)wr_calloc_array((size_t)shell->nv, 1);
    sim->sew_pairs = (int32_t *)wr_alloc_array(2 * (size_t)d.sewing.n_pairs + 1, sizeof(int32_t));
    sim->analytic = (wr_obstacle *)wr_alloc_array((size_t)d.contact.n_analytic + 1, sizeof(wr_obstacle));
    sim->thread_seg = (int32_t *)wr_alloc_array(2 * (size_t)d.threads.n_segments + 1, sizeof(int32_t));
    sim->thread_rest = (double *)wr_alloc_array((size_t)d.threads.n_segments + 1, sizeof(double));
    sim->thread_axial = (double *)wr_alloc_array((size_t)d.threads.n_segments + 1, sizeof(double));
    w = (wr__dyn_work *)wr_calloc_array(1, sizeof(wr__dyn_work));
    sim->w = w;
    if (!sim->mass || !sim->fixed || !sim->sew_pairs || !sim->analytic || !sim->thread_seg || !sim->thread_rest ||
        !sim->thread_axial || !w)
        goto nomem;
    if ((st = wr__dyn_copy_bodies(sim, &d, diag)) != WR_OK) goto fail;
    n = 3 * (shell->nv + sim->nb);
    w->n = n;
    w->zc = (double *)wr_alloc_array((size_t)n, sizeof(double));
    w->dzc = (double *)wr_alloc_array((size_t)n, sizeof(double));
    w->gc = (double *)wr_alloc_array((size_t)n, sizeof(double));
    if (!w->zc || !w->dzc || !w->gc) goto nomem;
    w->xn = (double *)wr_alloc_array((size_t)n, sizeof(double));
    w->xt = (double *)wr_alloc_array((size_t)n, sizeof(double));
    w->z = (double *)wr_alloc_array((size_t)n, sizeof(double));
    w->s1 = (double *)wr_alloc_array((size_t)n, sizeof(double));
    w->s2 = (double *)wr_alloc_array((size_t)n, sizeof(double));
    w->fixd = (uint8_t *)wr_calloc_array((size_t)n, 1);
    w->target = (double *)wr_alloc_array(3 * (size_t)sim->nb + 1, sizeof(double));
    w->mshare = (double *)wr_alloc_array((size_t)shell->nv, sizeof(double));
    w->mdiag = (double *)wr_alloc_array((size_t)shell->nv, sizeof(double));
    w->kbuf = (double *)wr_alloc_array((size_t)324 * WR__DYN_CHUNK, sizeof(double));
    w->kvert = (int32_t *)wr_alloc_array((size_t)7 * WR__DYN_CHUNK, sizeof(int32_t));
    w->kstat = (int8_t *)wr_alloc_array(WR__DYN_CHUNK, 1);
    w->kproj = (int8_t *)wr_alloc_array(WR__DYN_CHUNK, 1);
    if (!w->xn || !w->xt || !w->z || !w->s1 || !w->s2 || !w->fixd || !w->target || !w->mshare || !w->mdiag || !w->kbuf ||
        !w->kvert || !w->kstat || !w->kproj)
        goto nomem;
    wr_shell_vertex_masses(shell, sim->mass);
    wr__dyn_mass_shares(sim);
    for (v = 0; v < shell->nv; ++v) {
        sim->fixed[v] = d.fixed ? d.fixed[v] != 0 : 0;
        for (i = 0; i < 3; ++i) w->fixd[3 * v + i] = sim->fixed[v];
        msum += sim->mass[v];
    }
    /* a body that never moves is held (Dirichlet); moving ones follow their keys through springs */
    for (b = 0; b < d.contact.n_bodies; ++b) {
        const wr__dyn_body *bd = sim->bodies + b;
        if (bd->n_keys >= 2) w->moving = 1;
        for (i = 0; i < 3 * bd->nv; ++i) w->fixd[3 * (shell->nv + bd->off) + i] = bd->n_keys < 2;
    }
    w->nn = w->moving ? n : 3 * shell->nv; /* held bodies stay out of Newton's vector (and its PCG) */
    if (d.sewing.n_pairs) memcpy(sim->sew_pairs, d.sewing.pairs, sizeof(int32_t) * 2 * (size_t)d.sewing.n_pairs);
    if (d.contact.n_analytic) memcpy(sim->analytic, d.contact.analytic, sizeof(wr_obstacle) * (size_t)d.contact.n_analytic);
    if (d.threads.n_segments) {
        memcpy(sim->thread_seg, d.threads.segments, sizeof(int32_t) * 2 * (size_t)d.threads.n_segments);
        memcpy(sim->thread_rest, d.threads.rest, sizeof(double) * (size_t)d.threads.n_segments);
        memcpy(sim->thread_axial, d.threads.axial, sizeof(double) * (size_t)d.threads.n_segments);
    }
    sim->desc.threads.segments = sim->thread_seg;
    sim->desc.threads.rest = sim->thread_rest;
    sim->desc.threads.axial = sim->thread_axial;
    sim->desc.fixed = sim->fixed;
    sim->desc.sewing.pairs = sim->sew_pairs;
    sim->desc.contact.analytic = sim->analytic;
    sim->desc.contact.bodies = NULL; /* copied into sim->bodies */
    sim->mean_mass = msum / shell->nv;
    sim->dhat = d.contact.dhat;
    h = d.time.dt / d.time.substeps;
    gmag = sqrt(d.gravity[0] * d.gravity[0] + d.gravity[1] * d.gravity[1] + d.gravity[2] * d.gravity[2]);
    sim->kappa = d.contact.stiffness > 0.0 ? d.contact.stiffness
                                           : WR_DYN_KAPPA_FACTOR * sim->mean_mass * fmax(gmag, sim->dhat / (h * h)) / sim->dhat;
    sim->sew_k = d.sewing.stiffness > 0.0 ? d.sewing.stiffness : WR_DYN_SEW_FACTOR * sim->mean_mass / (h * h);
    sim->kin_k = d.contact.kinematic_stiffness > 0.0 ? d.contact.kinematic_stiffness
                                                     : WR_DYN_KINEMATIC_FACTOR * sim->mean_mass / (h * h);
    w->damp_stiff = d.damping.stiffness > 0.0;
    if (w->damp_stiff && (st = wr_assembly_init(&w->Kd, shell->nv, 3, diag)) != WR_OK) goto fail;
    if ((d.contact.n_bodies > 0 || !d.contact.no_self) && (st = wr__dyn_collision_setup(sim, diag)) != WR_OK) goto fail;
    if (d.contact.no_self && (st = wr__dyn_hinge_setup(sim, diag)) != WR_OK) goto fail;
    return WR_OK;
nomem:
    st = wr_fail(diag, WR_ERR_NOMEM, -1, "dynamics: out of memory (%d vertices)", (int)shell->nv);
fail:
    wr_dyn_free(sim);
    return st;
}

WRDEF void wr_dyn_state_init(const wr_dyn *sim, wr_dyn_state *state, double *x, double *v) {
    (void)sim;
    state->x = x;
    state->v = v;
    state->t = 0.0;
}

/* Smallest contact distance and the number of active contacts at cloth positions x, bodies where
 * they are (friction left out: only the barriers' distances are wanted). */
static double wr__dyn_gap(wr_dyn *sim, const double *x, int32_t *n_active) {
    wr__dyn_work *w = sim->w;
    double dm = HUGE_VAL, E = 0.0;
    int32_t nfr = w->n_fr;
    memcpy(w->z, x, sizeof(double) * 3 * (size_t)sim->nv);
    if (sim->nb) memcpy(w->z + 3 * sim->nv, sim->body_x, sizeof(double) * 3 * (size_t)sim->nb);
    w->n_fr = 0;
    if (wr__dyn_contact_terms(sim, w->z, &E, NULL, &dm, n_active, NULL) != WR_OK) dm = 0.0;
    w->n_fr = nfr;
    return dm;
}

/* One solve's counters into the frame's record. NS is Newton's wall time less the contact work the
 * callbacks timed as CH (ON TIMING). */
static void wr__dyn_stats_add(wr_dyn_stats *to, const wr_newton_stats *ns) {
    to->newton_iterations += ns->iterations;
    to->linear_iterations += ns->linear_iterations;
    to->line_search_evals += ns->line_search_evals;
    to->residual = ns->grad_norm;
    to->residual_rel = ns->grad_norm0 > 0.0 ? ns->grad_norm / ns->grad_norm0 : 0.0;
    to->stop = ns->stop;
    to->t_ns += ns->t_total;
    to->t_linear += ns->t_linear;
    to->pattern_builds += ns->pattern_builds;
    to->elements_projected += ns->elements_projected;
    if (ns->iterations > 0 && ns->max_step_min < to->ccd_alpha_min) to->ccd_alpha_min = ns->max_step_min;
}

WRDEF wr_status wr_dyn_step(wr_dyn *sim, wr_dyn_state *state, wr_dyn_stats *stats, wr_diag *diag) {
    wr__dyn_work *w;
    wr_dyn_stats fs;
    double t_end, h, t_start = wr__dyn_now();
    int32_t i;
    wr_status st = WR_OK;
    memset(&fs, 0, sizeof fs);
    fs.min_distance = HUGE_VAL;
    fs.ccd_alpha_min = 1.0;
    if (stats) *stats = fs;
    if (!sim || !sim->w || !state || !state->x || !state->v)
        return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "dynamics: NULL sim or state");
    w = sim->w;
    for (i = 0; i < 3 * sim->nv; ++i)
        if (state->x[i] - state->x[i] != 0.0 || state->v[i] - state->v[i] != 0.0)
            return wr_fail(diag, WR_ERR_DOMAIN, i / 3, "dynamics: vertex %d has a non-finite position or velocity", (int)(i / 3));
    w->t_ch = 0.0;
    t_end = state->t + sim->desc.time.dt;
    h = sim->desc.time.dt / sim->desc.time.substeps;
    fs.h_min = h;
    while (state->t < t_end - 1e-9 * sim->desc.time.dt) {
        wr_newton_stats ns;
        double hs = fmin(h, t_end - state->t);
        st = wr__dyn_one_step(sim, state, hs, &ns, diag);
        wr__dyn_stats_add(&fs, &ns);
        if (st == WR_ERR_NOT_CONVERGED && fs.halvings < sim->desc.time.max_halvings) {
            h *= 0.5; /* adaptive step reduction (ON TIME STEPPING) */
            fs.halvings++;
            if (h < fs.h_min) fs.h_min = h;
            continue;
        }
        if (st != WR_OK) break;
        fs.steps++;
    }
    fs.frames = st == WR_OK ? 1 : 0;
    {
        double t0 = wr__dyn_now();
        fs.min_distance = wr__dyn_gap(sim, state->x, &fs.n_contacts);
        w->t_ch += wr__dyn_now() - t0;
    }
    fs.t_ch = w->t_ch;
    fs.t_ns = fmax(0.0, fs.t_ns - w->t_ch);
    fs.t_total = wr__dyn_now() - t_start;
    if (stats) *stats = fs;
    return st;
}

WRDEF wr_status wr_dyn_run(wr_dyn *sim, wr_dyn_state *state, double t_end, wr_dyn_progress_fn progress, void *user,
                           wr_dyn_stats *total, wr_diag *diag) {
    wr_dyn_stats tot, fs;
    wr_status st = WR_OK;
    memset(&tot, 0, sizeof tot);
    tot.min_distance = HUGE_VAL;
    tot.ccd_alpha_min = 1.0;
    tot.h_min = HUGE_VAL;
    if (total) *total = tot;
    if (!sim || !sim->w || !state) return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "dynamics: NULL sim or state");
    if (!(t_end - t_end == 0.0)) return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "dynamics: t_end is not finite");
    while (state->t < t_end - 1e-9 * sim->desc.time.dt) {
        st = wr_dyn_step(sim, state, &fs, diag);
        tot.frames += fs.frames;
        tot.steps += fs.steps;
        tot.halvings += fs.halvings;
        tot.newton_iterations += fs.newton_iterations;
        tot.linear_iterations += fs.linear_iterations;
        tot.line_search_evals += fs.line_search_evals;
        tot.residual = fs.residual;
        tot.residual_rel = fs.residual_rel;
        tot.stop = fs.stop;
        tot.t_ns += fs.t_ns;
        tot.t_linear += fs.t_linear;
        tot.t_ch += fs.t_ch;
        tot.t_total += fs.t_total;
        tot.n_contacts = fs.n_contacts;
        tot.min_distance = fmin(tot.min_distance, fs.min_distance);
        tot.ccd_alpha_min = fmin(tot.ccd_alpha_min, fs.ccd_alpha_min);
        tot.h_min = fmin(tot.h_min, fs.h_min);
        tot.pattern_builds += fs.pattern_builds;
        tot.elements_projected += fs.elements_projected;
        if (st != WR_OK) break;
        if (progress && progress(user, state, &fs)) break;
    }
    if (total) *total = tot;
    return st;
}

WRDEF wr_status wr_dyn_energy(const wr_dyn *sim, const wr_dyn_state *state, double *kinetic, double *potential,
                              wr_diag *diag) {
    double K = 0.0, E = 0.0;
    int32_t v, i;
    wr_status st;
    if (!sim || !sim->w || !state || !state->x || !state->v)
        return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "dynamics: NULL sim or state");
    if ((st = wr_shell_energy(sim->shell, state->x, &E, NULL, diag)) != WR_OK) return st;
    E += wr__dyn_threads(sim, state->x, NULL);
    for (v = 0; v < sim->nv; ++v)
        for (i = 0; i < 3; ++i) {
            K += 0.5 * sim->mass[v] * state->v[3 * v + i] * state->v[3 * v + i];
            E -= sim->mass[v] * sim->desc.gravity[i] * state->x[3 * v + i];
        }
    if (kinetic) *kinetic = K;
    if (potential) *potential = E;
    return WR_OK;
}

WRDEF double wr_dyn_min_distance(wr_dyn *sim, const double *x) {
    if (!sim || !sim->w || !x) return HUGE_VAL;
    return wr__dyn_gap(sim, x, NULL);
}

WRDEF double wr_dyn_thread_segment(const double xa[3], const double xb[3], double rest, double axial, double g[6],
                                   double H[36]) {
    double d[3], l = 0.0, k = axial / rest, s, c;
    int32_t i, j;
    for (i = 0; i < 3; ++i) {
        d[i] = xa[i] - xb[i];
        l += d[i] * d[i];
    }
    l = sqrt(l);
    s = l - rest;
    if (g) memset(g, 0, sizeof(double) * 6);
    if (H) memset(H, 0, sizeof(double) * 36);
    if (!(s > 0.0)) return 0.0; /* slack (ON GATHERING) */
    for (i = 0; i < 3; ++i) d[i] /= l;
    if (g)
        for (i = 0; i < 3; ++i) {
            g[i] = k * s * d[i];
            g[3 + i] = -g[i];
        }
    c = 1.0 - rest / l; /* > 0: the transverse eigenvalue k(1 − L/ℓ) */
    if (H)
        for (i = 0; i < 3; ++i)
            for (j = 0; j < 3; ++j) {
                double b = k * (d[i] * d[j] + c * ((i == j ? 1.0 : 0.0) - d[i] * d[j]));
                H[6 * i + j] = H[6 * (3 + i) + 3 + j] = b;
                H[6 * i + 3 + j] = H[6 * (3 + i) + j] = -b;
            }
    return 0.5 * k * s * s;
}

WRDEF double wr_dyn_sew_gap(const wr_dyn *sim, const double *x) {
    double gmax = 0.0;
    int32_t p, i;
    if (!sim || !x) return 0.0;
    for (p = 0; p < sim->desc.sewing.n_pairs; ++p) {
        double s = 0.0;
        for (i = 0; i < 3; ++i) {
            double d = x[3 * sim->sew_pairs[2 * p] + i] - x[3 * sim->sew_pairs[2 * p + 1] + i];
            s += d * d;
        }
        gmax = fmax(gmax, sqrt(s));
    }
    return gmax;
}

#ifdef __cplusplus
}
#endif
#endif /* WRINKLE_DYNAMICS_IMPLEMENTATION_DONE */
#endif /* WRINKLE_IMPLEMENTATION */
