/* wrinkle/statics.h — static equilibrium of a shell (shell.h): gravity, prescribed vertices and
 * prescribed motions (stretch, shear, twist) with load increments, uniform pressure on closed or
 * sewn surfaces, frictionless contact with analytic obstacles (plane, sphere, capsule); projected
 * Newton with backtracking line search, linear solves through pcg.h.
 * wrinkle v0.1.0 — MIT licence (see LICENSE). Needs core.h, sparse.h, pcg.h (CHOLMOD when built
 * with WR_USE_CHOLMOD=1, see pcg.h), mesh.h, tft.h, shell.h; otherwise only libc and libm.
 *
 * Minimises Π(x) = E_shell(x) − Σ_v m_v g·x_v − p·V(x) + Σ_{free v, obstacles o} κ·b(d_o(x_v))
 * over the free vertices: the TFW Sec. 4.1 base surface (TFT membrane + quadratic bending), and the
 * StVK reference statics (StVK membrane + mid-edge bending) that both papers compare against. Each
 * Newton step assembles the element Hessians, projects each to PSD (as TFW App. E does for its SQP),
 * adds a diagonal shift μ·I (μ = shift_rel · mean diagonal at first, raised ×100 while the linear
 * solve reports a non-SPD matrix, divided by 10 after every full step down to WR_STATICS_SHIFT_MIN_REL
 * · mean diagonal, see ON SHIFT), solves K Δx = −∇Π with the prescribed DOFs held, limits the step so no
 * vertex can reach an obstacle (CCD), and backtracks (Armijo, c = 1e-4, halving) on Π. A trial state
 * where Π is undefined (degenerate face, vertex on or through an obstacle) counts as +∞.
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
 *   wr_statics_project_spd(n, A, floor)              fast per-element PSD projection (see ON PROJECTION)
 *   wr_mesh_weld(out, in, n_pairs, pairs, vmap, diag)   sew: merge vertex pairs, keep each face's rest
 *   wr_mesh_pillow(out, panel, lift, diag)           two copies of a flat panel sewn along the boundary
 *   (weld and pillow fill a wr_mesh: free it with wr_mesh_free; on failure it is left zeroed)
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
 *     sd.gravity[2] = -9.81; sd.fixed = pin;                         // sags onto the ball
 *     sd.obstacles = &ball; sd.n_obstacles = 1;                      // default d̂ and κ
 *     if (wr_statics_solve(&shell, x, &sd, &st, &d) != WR_OK) { puts(d.message); return 1; }
 *     printf("%d Newton steps, |g| %.2e N, gap %.2e m\n", st.iterations, st.grad_norm, st.min_distance);
 *     wr_free(x);  wr_free(pin);  wr_shell_free(&shell);  wr_mesh_free(&m);
 *
 * ON STOPPING ("solve to tolerance")
 *   Converged when ‖∇Π_free‖ <= grad_tol · max(‖∇Π_free(x0)‖, ‖f_ext,free‖) (stop GRADIENT), or when
 *   a full (α = 1, not backtracked, not cut by CCD) step has max|Δx| <= step_tol · (bounding-box
 *   diagonal of x0) (stop STEP; a backtracked tiny step means a stall, not convergence). max_iter
 *   reached, or a line search that cannot decrease Π in 40 halvings, returns WR_ERR_NOT_CONVERGED
 *   with the best (lowest-Π) iterate in x. ∇Π includes pressure and contact forces, so a converged
 *   state is an equilibrium of all of them. The perturbation is applied before x0 is measured.
 *   Near convergence Π stops resolving the decrease (it is a sum of O(n) terms): when the predicted
 *   decrease −α∇Π·Δx is below WR_STATICS_ENERGY_NOISE (1e-12) × Σ|terms| and Π did not rise by more
 *   than that, the step is accepted if ‖∇Π‖ drops (otherwise plain Armijo).
 *   When the tolerance asks for a gradient below what double precision resolves (the gradient's
 *   round-off floor grows like √n·ε·(largest internal force)), the solve stops with WR_OK and stop
 *   ROUNDOFF: WR__STATICS_ROUNDOFF_HITS (3) consecutive Newton steps whose Newton decrement −∇Π·Δx
 *   is below WR_STATICS_ENERGY_NOISE × Σ|terms of Π| (nothing left that Π can resolve) and after
 *   which ‖∇Π‖ is not below 0.9 × its smallest value so far (a gradient that still falls is still
 *   converging), with ‖∇Π‖ <= √grad_tol · reference (so a flat start at a saddle never qualifies).
 *
 * ON SHIFT
 *   A fixed shift μ = 1e-8 · mean diagonal is not small for a slender structure: the mean diagonal is
 *   the membrane stiffness (Eh ~ 300 N/m for fabric) while the softest global mode of a hanging
 *   strip is orders lower, so Newton with K + μI converged only linearly near the solution (measured
 *   on the L = 100 mm cantilever at 20 mm: error ratio 0.42 per step, 25 extra steps per load step).
 *   μ therefore decays ×0.1 after every full (α = 1) step, down to WR_STATICS_SHIFT_MIN_REL (1e-14)
 *   · mean diagonal — the factorisation's own round-off level, kept so that an exactly singular PSD
 *   matrix still factors — and is raised again (to shift_rel · mean diagonal, then ×100) only when
 *   the linear solve reports a non-SPD matrix or gives no descent direction.
 *   Opt-in (desc.shift_raise = r > 1, 0 = off): after a step the line search had to shorten (α below
 *   the CCD-safe step), μ is also multiplied by r (Levenberg–Marquardt style), capped at
 *   WR_STATICS_SHIFT_RAISE_CAP (1e6) · shift_rel · mean diagonal (a μ already above the cap from a
 *   non-SPD raise is left alone), and decays ×0.1 again after full steps. Why: on the TFW sheared
 *   rectangle base (TFT, 1789 of 1836 elements wrinkled, 34 slack) full Newton steps push slack
 *   elements back into tension and the line search halved up to 9 times per step, along directions
 *   held only by bending (~1e-6 of the membrane stiffness); a larger μ shortens exactly those
 *   directions. Measured there (bench_tfw --shift-raise=R, one increment): 313 Newton steps → 175
 *   (R = 10) or 126 (R = 100). μ only changes the path, not the minimiser, but where Π is that flat
 *   the solve stops elsewhere in the valley: that base differs by up to 1.5e-4 m (Π higher by 4e-10 J
 *   of 0.245 J), so it is off by default (0 keeps every caller on its previous iterates).
 *   Why that base crawls (measured with the exact Hessian, one increment; not fixed): in the tail no
 *   element changes TFT regime between accepted iterates (none over steps ~150–296), yet the full
 *   Newton step raises Π by up to ~2300× the quadratic model's predicted decrease (step 150: +1.1e-7 J
 *   against −4.8e-11 J), falling like α^3.6 over the halvings: the step is large along directions held
 *   only by bending, whose stretching is second order in the step, so its membrane energy is quartic
 *   (the geometric nonlinearity of ON MEMBRANE CONTINUATION) and Armijo cuts α to 1/4–1/32. Tried
 *   without gain there: the wrinkled-side Hessian for near-slack elements (272–497 steps), the taut
 *   Hessian for near-taut wrinkled ones (241–386), membrane continuation s0 = 1e-2 / 1e-4 (299 / 458),
 *   a ‖∇Π‖-merit line search near the end (stalls). The returned base is only as determined as that
 *   valley: round-off-level changes (summation order of the assembly, -O2 vs -O3) give 296–358 steps
 *   and bases up to 3.6e-5 m apart with Π equal to 1.4e-10 J.
 *
 * ON MEMBRANE CONTINUATION (desc.membrane_ramp)
 *   A displacement-based thin shell under large rotation converges slowly with Newton: a step that
 *   rotates a part of length ℓ by θ is linear in the positions, so it stretches it by θ²/2, and the
 *   membrane energy of that stretch grows like Eh·θ⁴ while the load's gain grows like θ. Full steps
 *   are limited to d ~ (4 ρ_A g ℓ⁴ / (Eh))^{1/3} (measured 1–2 mm per Newton step on the L = 100 mm
 *   fabric cantilever, whose tip travels 80 mm: 259 steps at 20 mm, 593 at 2.5 mm, 991 at 1.25 mm,
 *   whatever the load stepping — 100 gravity increments still took 45 steps for the first 1 %).
 *   With membrane_ramp = s0 in (0, 1) the solve first finds the equilibrium of the same shell with
 *   its membrane stiffness (StVK C_mem, TFT Y) scaled by s0, then by s0·f, s0·f², … (f =
 *   membrane_ramp_factor, default 1e3), each stage warm-started from the last and solved to the
 *   relative tolerance WR_STATICS_RAMP_TOL (1e-6), and finally solves the real shell to grad_tol.
 *   The soft stages take full steps s0^{-1/3} times longer and the soft equilibrium is already
 *   nearly inextensible (strain ~ load / (s0·Eh)), so the last stage starts close to the solution.
 *   Measured (L = 100 mm cantilever, mirror clamp, exact Hessian, CHOLMOD): at 20 mm, s0 = 1e-3 and
 *   full gravity in one solve 28 Newton steps, against 110 without (219 with 5 gravity increments),
 *   same tip to 1e-5 mm; validate_cantilever (s0 = 8.8e-4) 29–38 steps from 20 to 1.25 mm, all WR_OK
 *   (1.25 mm: 38 steps, 7.6 s on the 2-core box, was 991 steps, 369 s, NOT_CONVERGED).
 *   Bending is not scaled (it drives the shape). It is an
 *   option, off by default: for a buckling problem (a stretched sheet that wrinkles) a softer
 *   membrane changes the wrinkle pattern the path selects, so callers opt in for smooth large-
 *   deflection problems. Choose s0 so that the soft stage's membrane strain stays small (s0 ≳ 100 ×
 *   load per width / (Eh), strain ≲ 1 %): with s0 = 1e-3 on a heavier 25 mm strip (load / (Eh) =
 *   1.3e-4, soft strain ~13 %) the soft path folded the strip at its clamp and the real shell
 *   converged (WR_OK) to that folded equilibrium, tip = L. When the last stage ends
 *   WR_ERR_NOT_CONVERGED the solve restarts from the initial x without continuation
 *   (stats.ramp_fallback = 1, the discarded steps counted in ramp_iterations). The perturbation is applied in the first stage only; stats report the whole
 *   solve (iterations and times summed over stages, ramp_stages/ramp_iterations for the soft ones).
 *
 * ON INEXACT NEWTON (desc.linear_forcing)
 *   Far from the solution a Newton direction needs no 1e-8 linear accuracy. With linear_forcing =
 *   η_max > 0 each PCG solve stops at the relative residual η_k = min(η_max, max(tol, √(‖∇Π‖ /
 *   reference))) (tol = linear.rel_tol or pcg.h's default): the forcing sequence η_k → 0 with the
 *   gradient keeps Newton's local convergence superlinear (Dembo, Eisenstat & Steihaug 1982;
 *   Eisenstat & Walker 1996 use the same √ scaling). The direction is still checked for descent
 *   (CG from x = 0 on an SPD matrix always gives one). CHOLMOD solves exactly whatever η_k.
 *
 * ON PRESSURE (Skouras et al. 2014; TFW Sec. 6 inflatables)
 *   desc.pressure p [Pa] (> 0 inflates) adds −p·V with V = (1/6) Σ_f (x_a−o)·((x_b−o)×(x_c−o)) over
 *   faces (a, b, c), o = the centroid of the initial x (held fixed during the solve). V > 0 when the
 *   faces are oriented with outward normals ((x_b−x_a)×(x_c−x_a) pointing out); an inward-oriented
 *   closed mesh has V < 0 and pressure then deflates it. On a closed surface V does not depend on o.
 *   On an open surface it does, through the boundary only, so pressure needs a closed (sewn) surface
 *   or an open one whose boundary vertices are all prescribed; otherwise WR_ERR_UNSUPPORTED (item =
 *   a free boundary vertex). Hessian: ∂²V_f/∂x_a∂x_b = −(1/6)[x_c−o]× for (a, b, c) cyclic: zero
 *   diagonal blocks, hence indefinite. We add each face's −p·∇²V_f to the same face's elastic block
 *   BEFORE that block's PSD projection: the membrane stiffness absorbs the indefinite part where it
 *   can, so Newton keeps the pressure stiffness where it is consistent (fast convergence near the
 *   inflated equilibrium) and only the net non-convex part is discarded. Faces whose elastic block
 *   is absent (no membrane and no mid-edge bending) get the pressure block projected on its own.
 *   (The folding relies on shell.h streaming one block per face, in face order, corners first — its
 *   ON ELEMENT HESSIANS contract; a block that does not match is not folded, and the leftover faces
 *   are added on their own, so each face's pressure term enters exactly once either way.)
 *   Measured (not asserted): two sewn disks of radius a (12 rings, 866 vertices, TFT membrane,
 *   Y = 10 MPa, h = 0.1 mm, p = 200 Pa) inflate to radius 0.779 a and thickness/diameter 0.608,
 *   against Paulsen's inextensible Mylar balloon 0.7627 a and 0.599.
 *
 * ON CONTACT
 *   Frictionless, vertex against analytic obstacle, one-sided (the obstacle is where d < 0): an
 *   IPC-style log barrier (Li et al. 2020) b(d) = −(d − d̂)² ln(d/d̂) for 0 < d < d̂, 0 for d >= d̂
 *   (C², so Newton sees a smooth energy), scaled by κ [N/m]. Only free vertices feel it; a free
 *   vertex with d <= 0 at the start (after the perturbation) is WR_ERR_GEOMETRY (item = vertex).
 *   Every Newton step is cut, before the line search, to the largest α <= 1 such that no free vertex
 *   gets closer than WR_STATICS_CCD_KEEP (0.2) of its current distance to any obstacle: conservative
 *   advancement along the straight path, exact for the plane and safe for the sphere and capsule
 *   because d is 1-Lipschitz. So no iterate ever penetrates, whatever κ. The barrier Hessian is
 *   κ[b''(d) ∇d∇dᵀ + b'(d) ∇²d]; the second term is negative semidefinite on a convex obstacle
 *   (b' < 0, ∇²d >= 0, orthogonal to ∇d), so its PSD projection is exactly κ b''(d) ∇d∇dᵀ, which is
 *   what we assemble. Defaults: d̂ = 1e-3 × bounding-box diagonal of x0; κ = 10 f_ref / d̂ with
 *   f_ref = the largest per-vertex external load (gravity m_v|g| plus p × vertex area), or, with no
 *   external load, 1e-3 · h·Y · (typical rest edge). κ only decides how close to the surface a
 *   loaded vertex rests (within d̂), never whether it passes. Contact is vertex-only: a face between
 *   vertices outside a curved obstacle can cut into it by its sagitta (≈ l²/(8R) for edge length l,
 *   radius R); min_distance in the stats is measured at the vertices.
 *
 * ON MOTIONS AND INCREMENTS
 *   A wr_motion moves a vertex set rigidly or by a simple deformation of its reference positions
 *   (the x given to the incremental solve): translate, stretch (uniaxial, or isotropic scale when
 *   axis = 0), simple shear, or twist (rotation about an axis line by an angle, so heights along the
 *   axis are kept). wr_statics_solve_incremental applies fraction t = k/n_inc of every motion for
 *   k = 1..n_inc and solves each increment to tolerance, warm-started from the previous equilibrium
 *   (free vertices start where the last increment left them, prescribed ones at their new targets).
 *   inc_predictor = 1 uses a secant predictor instead: from the second increment on, free vertices
 *   start at 2·x_{k−1} − x_{k−2} (x_0 = the reference), restarting from x_{k−1} when that prediction
 *   is infeasible (degenerate face, vertex in an obstacle). It is not the default because on a
 *   buckling path it did not pay: the twisted cylinder (16×6, 4° in 4 / 8 increments) took 333 / 644
 *   Newton steps with it against 306 / 571 without. Intermediate increments use
 *   inc_grad_tol (default grad_tol); an intermediate WR_ERR_NOT_CONVERGED is tolerated (its best
 *   iterate warm-starts the next increment, counted in stats.increments_failed); the status of the
 *   last increment is returned. The perturbation is applied in the first increment only.
 *
 * ON PROJECTION
 *   Element Hessians are made PSD one by one. projection = WR_PROJECT_FAST (default) first tries a
 *   Cholesky factorisation of Ke + τI, τ = WR_STATICS_PSD_TEST_REL · max|diag(Ke)| (1e-12): when it
 *   succeeds every eigenvalue is >= −τ, four orders below the global shift μ (1e-8 of the mean
 *   diagonal), and the block is used as is. Otherwise: Householder tridiagonalisation (reflectors
 *   kept, Q not formed), eigenvalues only by implicit QL with Wilkinson shifts, and for each
 *   eigenvalue below floor − τ its eigenvector by inverse iteration on the tridiagonal (3 solves,
 *   re-orthogonalised against the ones already found so repeated eigenvalues give an orthonormal
 *   set), mapped back through the reflectors; then A ← A − Σ (λ − floor) z zᵀ. Element blocks of
 *   the shell typically have 0–5 such eigenvalues out of 18, so this avoids both Jacobi's sweeps
 *   and the O(n³) eigenvector accumulation. (A dense eigen-solver of this kind could move to
 *   core.h.) Measured on 4000 mid-edge 18×18 blocks of a wrinkling sheet: 8.8 µs per block
 *   against 66 µs for wr_dense_project_spd (7.5×), same result to 8e-13 relative. Eigenvalues in
 *   [floor − τ, floor) are left as they are. WR_PROJECT_JACOBI is the former path (core.h's cyclic
 *   Jacobi, every block), kept to measure against; WR_PROJECT_NONE assembles the exact Hessian
 *   (no_projection = 1 means the same, for compatibility).
 *   Exact phase: projection keeps Newton a descent method far from equilibrium but discards real
 *   negative curvature (membrane compression, bending of a tensioned sheet), and near a minimum it
 *   then converges only linearly (measured: hanging 6×6 sheet, error ratio 0.82 per step, 29 steps
 *   to 1e-7). So once a full step was accepted and ‖∇Π‖ <= WR_STATICS_EXACT_SWITCH (1e-3) ×
 *   reference, the next steps use the exact Hessian (at a strict minimum it is SPD: quadratic
 *   convergence); the first time its factorisation reports a non-SPD matrix (or no descent), that
 *   step continues with the shift raised and the rest of the solve is projected again
 *   (stats.exact_steps counts the exact steps).
 *   Opt-in (desc.exact_retry = q in (0, 1), 0 = off): after a failed exact step the exact Hessian is
 *   tried again once ‖∇Π‖ <= q × its value at that failure (and again after each further failure).
 *   Why: the first exact attempt comes at ‖∇Π‖ = 1e-3 × reference, often still on the way down where
 *   the exact Hessian is indefinite; without a retry the rest of the solve is projected, and along a
 *   nearly flat mode the projected Hessian is far stiffer than the exact one, so Newton crawls.
 *   Measured on the StVK twisted cylinder 56×44 (2520 vertices, 10° in 4 increments, max_iter 300,
 *   validate_tfw_crosscheck): first increment without retry NOT_CONVERGED after 300 steps at
 *   ‖∇Π‖ = 4–6e-8 × reference (target 1e-8), full projected steps of ~5e-6 m, Π falling ~5e-11 J per
 *   step, largest dihedral 34° (no folded faces); with q = 0.1, 261 steps, WR_OK.
 *
 * ON ASSEMBLY CACHE
 *   The Hessian pattern does not change between Newton steps, so each solve (each continuation stage
 *   and load increment) records the element stencils of its first assembly, builds the pattern from
 *   them (sparse.h wr_csr_from_stencils: every 3×3 vertex block of each stencil, plus all diagonal
 *   blocks for the shift and contact), and keeps each element's block offsets (wr_csr_block_offsets);
 *   later assemblies add every element block without any search (wr_csr_add_element_blocks). An
 *   element that does not match the record (never seen with shell.h, which streams the same elements
 *   in the same order) falls back to the searched add. The quadratic-bending blocks (TFW Eq. 28) do
 *   not depend on x and are PSD, so the FAST projection and the exact Hessian keep them unchanged:
 *   they are assembled once into a value array added to each later assembly (shell.h
 *   wr_shell_hessian_elements_part streams the face blocks alone); with WR_PROJECT_JACOBI they are
 *   streamed every time as before. Measured on the TFW bench bases (bench_tfw --base-only, CPU, this
 *   2-core box): the searched scatter wr_csr_add_element was 20–29 % of the whole TFT base solve and
 *   the triplet pattern build (allocation, page clearing, sort) another ~10 % on short solves;
 *   assembly time per stretched-sheet solve 0.084 → 0.019 s. Same bases as the searched, triplet-
 *   built assembly (bench_tfw settings, max vertex distance): stretched sheet 7e-17 m, twisted
 *   cylinder 2e-15 m (same 9 and 14 Newton steps), teabag 2.3e-6 m (same 11 steps, both at ‖∇Π‖ =
 *   5e-11 of the reference: the slack TFT regions of the pillow leave a soft direction), sheared
 *   rectangle 3.6e-5 m (296 against 313 steps: the flat valley of ON SHIFT).
 *
 * ON SEWING
 *   wr_mesh_weld merges the vertices of each pair (transitively), averages their positions and gives
 *   every face its own rest corners (corner_rest) from the input, so each panel keeps its flat
 *   pattern shape (TFW: two annuli → torus, two disks → Mylar balloon, two rectangles → teabag).
 *   wr_mesh_pillow builds that two-panel case from one flat panel: the top copy keeps the panel's
 *   orientation and is lifted by +lift·s(v), the bottom copy is mirrored in the rest domain (u → −u,
 *   corners 1 and 2 swapped, so it is CCW in its own pattern and faces outward below) and lowered by
 *   −lift·s(v); s = hop distance to the boundary / the largest such distance (0 on the seam, 1 at the
 *   middle), a tent that keeps the seam faces non-degenerate. The closed result has outward normals,
 *   so V > 0 and p > 0 inflates. (These two could move to mesh.h.)
 *
 * ON THREADS
 *   No global state; the progress callback runs on the calling thread.
 */
#ifndef WRINKLE_STATICS_H
#define WRINKLE_STATICS_H

#include "core.h"
#include "sparse.h"
#include "pcg.h"
#include "newton.h"
#include "shell.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef enum wr_statics_stop {
    WR_STATICS_STOP_NONE = 0,
    WR_STATICS_STOP_GRADIENT,   /* relative gradient norm below grad_tol */
    WR_STATICS_STOP_STEP,       /* accepted step below step_tol */
    WR_STATICS_STOP_MAX_ITER,   /* WR_ERR_NOT_CONVERGED */
    WR_STATICS_STOP_LINE_SEARCH, /* no decrease found (WR_ERR_NOT_CONVERGED) */
    WR_STATICS_STOP_ROUNDOFF     /* Newton decrement below Π's round-off (WR_OK, see ON STOPPING) */
} wr_statics_stop;

typedef struct wr_statics_stats {
    int32_t iterations;         /* Newton steps taken (this solve; last increment for incremental) */
    int32_t linear_iterations;  /* summed over steps */
    int32_t line_search_evals;  /* energy evaluations in line searches */
    double energy;              /* Π at the returned x [J] */
    double grad_norm, grad_norm0, grad_ref; /* ‖∇Π_free‖ now, at x0, and the reference of ON STOPPING [N] */
    double last_step;           /* max |αΔx| of the last accepted step [m] */
    double shift;               /* last diagonal shift μ used */
    wr_statics_stop stop;
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
} wr_statics_stats;

typedef wr_projection wr_statics_projection; /* newton.h (kept for compatibility) */

typedef enum wr_obstacle_kind {
    WR_OBSTACLE_PLANE = 0,  /* half-space n·(x − p) < 0 is solid */
    WR_OBSTACLE_SPHERE = 1, /* |x − p| < radius is solid */
    WR_OBSTACLE_CAPSULE = 2 /* distance to segment [p, q] < radius is solid */
} wr_obstacle_kind;

typedef struct wr_obstacle {
    wr_obstacle_kind kind;
    double p[3];      /* plane: a point on it; sphere: centre; capsule: axis end [m] */
    double q[3];      /* capsule: other axis end [m] (p == q is a sphere) */
    double normal[3]; /* plane: normal towards the free side (any length > 0) */
    double radius;    /* sphere, capsule [m] > 0 */
} wr_obstacle;

/* Defaults (zero means default):
 *   max_iter 200; grad_tol 1e-8 (relative, see ON STOPPING); step_tol 1e-13 (relative to the
 *   bounding-box diagonal); gravity (0,0,0) m/s² (needs shell density > 0 to matter);
 *   fixed NULL = none, else nv flags (nonzero = vertex prescribed); target NULL = prescribed vertices
 *   keep their input position, else nv*3 positions whose fixed rows are used;
 *   perturb 0 = none, else the standard deviation [m] of a seeded normal displacement of the free
 *   vertices along their area-weighted vertex normal (breaks the symmetry of flat starts), seed used
 *   as given (0 is a valid seed); shift_rel 1e-8 (diagonal shift relative to the mean diagonal);
 *   no_projection 0 = project element Hessians to PSD; linear: pcg.h options (fixed is set here);
 *   progress NULL, else called after every Newton step;
 *   pressure 0 Pa = none (ON PRESSURE); obstacles NULL / n_obstacles 0 = none, contact_dhat 0 →
 *   1e-3 × bbox diagonal [m], contact_stiffness 0 → ON CONTACT default [N/m];
 *   projection WR_PROJECT_FAST (ON PROJECTION); inc_grad_tol 0 → grad_tol (incremental solve);
 *   inc_predictor 0 = each increment starts from the last equilibrium, 1 = secant predictor
 *   (ON MOTIONS AND INCREMENTS);
 *   membrane_ramp 0 = off, else the first stage's membrane scale s0 in (0, 1), membrane_ramp_factor
 *   0 → 1e3 (> 1) (ON MEMBRANE CONTINUATION);
 *   linear_forcing 0 = every PCG solve to linear.rel_tol, else η_max in (0, 1) of the inexact Newton
 *   forcing (ON INEXACT NEWTON; no effect with CHOLMOD);
 *   shift_raise 0 = off, else the factor r > 1 applied to μ after a backtracked step (ON SHIFT);
 *   r in (0, 1], negative or not finite is WR_ERR_INVALID_ARG;
 *   exact_retry 0 = off (one failed exact step ends the exact phase), else the factor q in (0, 1):
 *   after a failed exact step the exact Hessian is tried again once ‖∇Π‖ <= q × its value at the
 *   failure (ON PROJECTION); outside (0, 1) or not finite is WR_ERR_INVALID_ARG. */
typedef struct wr_statics_desc {
    int32_t max_iter;
    double grad_tol;
    double step_tol;
    double gravity[3];
    const uint8_t *fixed;
    const double *target;
    double perturb;
    uint64_t seed;
    double shift_rel;
    int32_t no_projection;
    wr_spd_desc linear;
    void (*progress)(void *user, const wr_statics_stats *stats);
    void *progress_user;
    /* added fields (zero = previous behaviour) */
    double pressure;
    const wr_obstacle *obstacles;
    int32_t n_obstacles;
    double contact_dhat;
    double contact_stiffness;
    wr_statics_projection projection;
    double inc_grad_tol;
    int32_t inc_predictor;
    double membrane_ramp;
    double membrane_ramp_factor;
    double linear_forcing;
    double shift_raise;
    double exact_retry;
} wr_statics_desc;

typedef enum wr_motion_kind {
    WR_MOTION_HOLD = 0,      /* prescribed at the reference position */
    WR_MOTION_TRANSLATE = 1, /* x = X + t·vec */
    WR_MOTION_STRETCH = 2,   /* x = X + t·amount·((X−origin)·â) â; axis = 0: x = origin + (1 + t·amount)(X−origin) */
    WR_MOTION_SHEAR = 3,     /* x = X + t·amount·((X−origin)·n̂) â  (simple shear γ = amount) */
    WR_MOTION_TWIST = 4      /* X rotated by t·amount [rad] about the line (origin, â), right-handed */
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
} wr_motion;

WRDEF wr_status wr_statics_solve(const wr_shell *s, double *x, const wr_statics_desc *desc, wr_statics_stats *stats,
                                 wr_diag *diag);
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
/* In-place PSD projection of symmetric A (n×n, n <= WR_DENSE_MAX): eigenvalues below floor − τ are
 * raised to floor (τ = 1e-12 max|A_ii|, ON PROJECTION); a block passing the Cholesky test (floor = 0
 * only) is kept unchanged. Returns the number of raised eigenvalues (0 = A unchanged). */
WRDEF int wr_statics_project_spd(int n, double *A, double floor);
/* Sewing (ON SEWING). pairs: n_pairs × 2 vertex indices of `in`; vmap (in->nv) receives the new index
 * of every input vertex when non-NULL. out gets corner_rest (and face_panel copied). Free with
 * wr_mesh_free. Errors: WR_ERR_INVALID_ARG (index outside [0, nv), item = pair), WR_ERR_TOPOLOGY from
 * wr_mesh_create (a face with two merged corners, an edge in more than two faces, inconsistent
 * orientation across a seam). */
WRDEF wr_status wr_mesh_weld(wr_mesh *out, const wr_mesh *in, int32_t n_pairs, const int32_t *pairs, int32_t *vmap,
                             wr_diag *diag);
/* Two copies of a flat panel (pos z = 0, at least one boundary loop) sewn along all its boundary
 * loops; lift > 0 [m]. Top copy vertices keep their indices 0..nv−1 (face_panel 0, faces 0..nf−1),
 * the bottom's interior vertices follow (face_panel 1). WR_ERR_INVALID_ARG for lift <= 0 or a panel
 * without boundary. */
WRDEF wr_status wr_mesh_pillow(wr_mesh *out, const wr_mesh *panel, double lift, wr_diag *diag);

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
#include <string.h>

#ifdef __cplusplus
extern "C" {
#endif

#define WR__STATICS_ARMIJO 1e-4   /* sufficient-decrease constant (Nocedal & Wright's usual value) */
#define WR__STATICS_MAX_HALVINGS 40
#define WR__STATICS_MAX_SHIFT_RAISES 8
/* PSD test shift relative to the largest |diagonal| entry of the element block: a block that passes
 * has no eigenvalue below −1e-12·max|Ke_ii|, four orders under the global shift (shift_rel 1e-8). */
#define WR_STATICS_PSD_TEST_REL 1e-12
/* CCD keeps a vertex at >= this fraction of its current obstacle distance per Newton step (IPC uses
 * a similar safety fraction, 0.1–0.2, so iterates approach contact geometrically, never touching). */
#define WR_STATICS_CCD_KEEP 0.2
#define WR__STATICS_CCD_ITERS 64 /* conservative-advancement iterations; the result is safe at any count */
#define WR__STATICS_DHAT_REL 1e-3
/* Π is a sum of O(n) terms; a change below this fraction of the sum of their magnitudes is not
 * resolvable in double precision (√n·ε for n up to 1e6 is ~2e-13), so near convergence the line
 * search accepts a step whose predicted decrease is below it when ‖∇Π‖ drops instead. */
#define WR_STATICS_ENERGY_NOISE 1e-12
/* consecutive Newton steps with a decrement below the energy noise that end the solve (ON STOPPING) */
#define WR__STATICS_ROUNDOFF_HITS 3
/* relative gradient (ON STOPPING reference) below which a projected solve tries the exact Hessian
 * after a full step; the scene driver's hybrid Newton measured 1e-3 as past the saddle-escape phase */
#define WR_STATICS_EXACT_SWITCH 1e-3
/* smallest diagonal shift, relative to the mean diagonal: the round-off level of the factorisation
 * (ON SHIFT); below it μ no longer changes K + μI in double precision for the stiff DOFs */
#define WR_STATICS_SHIFT_MIN_REL 1e-14
/* ceiling of the opt-in raise after backtracked steps (desc.shift_raise), relative to shift_rel ·
 * mean diagonal: 1e6 · 1e-8 = 1e-2 of the membrane stiffness at the default shift_rel, still far
 * below it so a step keeps the Newton direction in the stiff modes (ON SHIFT) */
#define WR_STATICS_SHIFT_RAISE_CAP 1e6
/* relative gradient tolerance of the soft stages of the membrane continuation: they only have to
 * bring the shape near the final one (ON MEMBRANE CONTINUATION) */
#define WR_STATICS_RAMP_TOL 1e-6
#define WR__STATICS_RAMP_FACTOR 1e3

/* the per-element projection lives in newton.h (ON PROJECTION AND THE EXACT PHASE there) */
WRDEF int wr_statics_project_spd(int n, double *A, double floor) { return wr_newton_project_spd(n, A, floor); }

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

WRDEF double wr_statics_barrier(double d, double dhat, double kappa, double *b1, double *b2) {
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

/* ---- the solver ---------------------------------------------------------------------------- */

typedef struct wr__statics_ctx {
    const wr_shell *s;
    const double *fext;
    const uint8_t *fixv; /* per vertex, may be NULL */
    double p, origin[3];
    const wr_obstacle *obs;
    int32_t nobs;
    double dhat, kappa;
} wr__statics_ctx;

/* ON ASSEMBLY CACHE: the element stencils of the first assembly, their block offsets in the fixed
 * pattern, and the constant quadratic-bending part of K. */
typedef struct wr__statics_cache {
    int32_t n_el, cap_el;  /* elements recorded in the first assembly */
    int32_t *vstart;       /* n_el + 1: element e has verts[vstart[e] .. vstart[e+1]) */
    int32_t *verts;
    int64_t vcap;
    int64_t *ostart;       /* n_el + 1: its block offsets off[ostart[e] ..), k² of them */
    int32_t *off;
    double *rec;           /* first assembly only: the element blocks, (3k)² each, in order */
    int64_t rn, rcap;
    int32_t face_end;      /* elements [0, face_end) are face blocks, [face_end, qb_end) quadratic stencils */
    int32_t qb_end, qb_small; /* qb_small: quadratic stencils with 3k <= WR_DENSE_MAX (counted as elements) */
    double *Kq;            /* nnz: the assembled quadratic-bending blocks, NULL when not cached */
    int32_t misses;        /* elements of later assemblies that did not match the record (added by search) */
} wr__statics_cache;

typedef struct wr__statics_sink {
    wr_csr *A;      /* the fixed pattern (NULL while recording) */
    wr__statics_cache *cache;
    int32_t e;      /* next recorded element expected */
    wr_statics_projection proj;
    double t_proj;
    int32_t n_proj, n_elem;
    const wr__statics_ctx *c; /* pressure folded into face blocks */
    const double *x;
    int32_t face;             /* next face whose block is expected */
} wr__statics_sink;

static void wr__statics_cache_free(wr__statics_cache *C) {
    wr_free(C->vstart);
    wr_free(C->verts);
    wr_free(C->ostart);
    wr_free(C->off);
    wr_free(C->rec);
    wr_free(C->Kq);
    memset(C, 0, sizeof *C);
}

/* first assembly: append the element's stencil and (3k)² block to the record */
static wr_status wr__statics_record(wr__statics_cache *C, int32_t k, const int32_t *verts, const double *K) {
    int64_t nn = 9 * (int64_t)k * k;
    if (C->n_el + 1 >= C->cap_el) {
        int32_t cap = C->cap_el ? 2 * C->cap_el : 1024;
        int32_t *vs = (int32_t *)wr_realloc_array(C->vstart, (size_t)cap + 1, sizeof(int32_t));
        if (!vs) return WR_ERR_NOMEM;
        C->vstart = vs;
        C->cap_el = cap;
        if (C->n_el == 0) C->vstart[0] = 0;
    }
    if (C->vstart[C->n_el] + k > C->vcap) {
        int64_t cap = 2 * C->vcap + 4 * (int64_t)k + 4096;
        int32_t *v = (int32_t *)wr_realloc_array(C->verts, (size_t)cap, sizeof(int32_t));
        if (!v) return WR_ERR_NOMEM;
        C->verts = v;
        C->vcap = cap;
    }
    if (C->rn + nn > C->rcap) {
        int64_t cap = 2 * C->rcap + 4 * nn + 65536;
        double *r = (double *)wr_realloc_array(C->rec, (size_t)cap, sizeof(double));
        if (!r) return WR_ERR_NOMEM;
        C->rec = r;
        C->rcap = cap;
    }
    memcpy(C->verts + C->vstart[C->n_el], verts, sizeof(int32_t) * (size_t)k);
    memcpy(C->rec + C->rn, K, sizeof(double) * (size_t)nn);
    C->rn += nn;
    C->vstart[C->n_el + 1] = C->vstart[C->n_el] + k;
    C->n_el++;
    return WR_OK;
}

/* later assemblies: the recorded element e through its cached offsets when the stream still matches
 * the record (shell.h streams the same elements in the same order every time), else by search */
static wr_status wr__statics_scatter(wr__statics_sink *S, int32_t k, const int32_t *verts, const double *K) {
    wr__statics_cache *C = S->cache;
    int32_t e = S->e;
    if (!S->A) return wr__statics_record(C, k, verts, K);
    if (e < C->n_el && C->vstart[e + 1] - C->vstart[e] == k &&
        !memcmp(C->verts + C->vstart[e], verts, sizeof(int32_t) * (size_t)k)) {
        S->e = e + 1;
        wr_csr_add_element_blocks(S->A, k, verts, C->off + C->ostart[e], K);
        return WR_OK;
    }
    {
        int32_t a, b, i, j, n = 3 * k;
        C->misses++;
        for (a = 0; a < k; ++a)
            for (b = 0; b < k; ++b) {
                double B[9];
                wr_status st;
                for (i = 0; i < 3; ++i)
                    for (j = 0; j < 3; ++j) B[3 * i + j] = K[(3 * a + i) * n + 3 * b + j];
                if ((st = wr_csr_add_block3(S->A, verts[a], verts[b], B, NULL)) != WR_OK) return st;
            }
        return WR_OK;
    }
}

static wr_status wr__statics_put(wr__statics_sink *S, int32_t k, const int32_t *verts, double *K) {
    int32_t n = 3 * k;
    S->n_elem++;
    if (S->proj != WR_PROJECT_NONE) {
        double t0 = wr_time_seconds();
        int r = S->proj == WR_PROJECT_JACOBI ? wr_dense_project_spd(n, K, 0.0) : wr_statics_project_spd(n, K, 0.0);
        if (r) S->n_proj++;
        S->t_proj += wr_time_seconds() - t0;
    }
    return wr__statics_scatter(S, k, verts, K);
}

static wr_status wr__statics_add(void *user, int32_t k, const int32_t *verts, const double *Ke) {
    wr__statics_sink *S = (wr__statics_sink *)user;
    double buf[WR_DENSE_MAX * WR_DENSE_MAX];
    int32_t a, i, n = 3 * k;
    if (n <= WR_DENSE_MAX) {
        const wr_shell *s = S->c->s;
        memcpy(buf, Ke, sizeof(double) * (size_t)(n * n));
        /* shell.h streams one block per face, in face order, corners first (ON ELEMENT HESSIANS):
         * fold that face's pressure Hessian in before the projection (ON PRESSURE) */
        if (S->c->p != 0.0 && k >= 3 && S->face < s->nf && verts[0] == s->faces[3 * S->face] &&
            verts[1] == s->faces[3 * S->face + 1] && verts[2] == s->faces[3 * S->face + 2]) {
            double x9[9], H9[81];
            int j, b;
            for (a = 0; a < 3; ++a)
                for (i = 0; i < 3; ++i) x9[3 * a + i] = S->x[3 * verts[a] + i];
            wr_statics_pressure_element(x9, S->c->origin, S->c->p, NULL, H9);
            for (a = 0; a < 3; ++a)
                for (b = 0; b < 3; ++b)
                    for (i = 0; i < 3; ++i)
                        for (j = 0; j < 3; ++j) buf[(3 * a + i) * n + 3 * b + j] += H9[(3 * a + i) * 9 + 3 * b + j];
            S->face++;
        }
        return wr__statics_put(S, k, verts, buf);
    }
    /* large stencils (quadratic bending at high valence) are PSD by construction: added unprojected */
    return wr__statics_scatter(S, k, verts, Ke);
}

/* Π and ∇Π (gradient zeroed on fixed DOFs when g != NULL). WR_ERR_GEOMETRY (item = vertex) when a
 * free vertex is on or inside an obstacle. */
static wr_status wr__statics_energy(const wr__statics_ctx *c, const double *x, double *Pi, double *g, double *scale,
                                    wr_diag *diag) {
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
            double gd[3], b1, d;
            if (c->fixv && c->fixv[v]) continue;
            d = wr_obstacle_distance(c->obs + o, x + 3 * v, gd);
            if (!(d > 0.0))
                return wr_fail(diag, WR_ERR_GEOMETRY, v, "statics: vertex %d is %.3e m inside obstacle %d", (int)v, -d,
                               (int)o);
            if (d >= c->dhat) continue;
            {
                double eb = wr_statics_barrier(d, c->dhat, c->kappa, &b1, NULL);
                E += eb;
                sc += eb;
            }
            if (g)
                for (i = 0; i < 3; ++i) g[3 * v + i] += b1 * gd[i];
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

/* Largest α in (0, 1] keeping every free vertex at >= WR_STATICS_CCD_KEEP of its current distance
 * to every obstacle along x + αΔx (conservative advancement: d is 1-Lipschitz, so advancing by
 * (d − target)/|Δx| can never overshoot the target distance). */
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

static double wr__statics_ccd(const wr__statics_ctx *c, const double *x, const double *dx) {
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

/* Vertex-diagonal contact blocks κ b''(d) ∇d∇dᵀ (ON CONTACT) */
static wr_status wr__statics_contact_hessian(const wr__statics_ctx *c, const double *x, wr__statics_sink *S) {
    int32_t o, v, i, j;
    for (o = 0; o < c->nobs; ++o)
        for (v = 0; v < c->s->nv; ++v) {
            double gd[3], b2, d, B[9];
            wr_status st;
            if (c->fixv && c->fixv[v]) continue;
            d = wr_obstacle_distance(c->obs + o, x + 3 * v, gd);
            if (!(d < c->dhat) || !(d > 0.0)) continue;
            wr_statics_barrier(d, c->dhat, c->kappa, NULL, &b2);
            for (i = 0; i < 3; ++i)
                for (j = 0; j < 3; ++j) B[3 * i + j] = b2 * gd[i] * gd[j];
            st = wr_csr_add_block3(S->A, v, v, B, NULL);
            if (st != WR_OK) return st;
        }
    return WR_OK;
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
        } else if (b->kind == WR_OBSTACLE_SPHERE || b->kind == WR_OBSTACLE_CAPSULE) {
            if (!(b->radius > 0.0))
                return wr_fail(diag, WR_ERR_INVALID_ARG, o, "statics: obstacle %d radius %g must be > 0", (int)o, b->radius);
        } else {
            return wr_fail(diag, WR_ERR_INVALID_ARG, o, "statics: obstacle %d has unknown kind %d", (int)o, (int)b->kind);
        }
    }
    return WR_OK;
}

/* gref_fixed > 0: use it as the reference of ON STOPPING instead of the one measured at x0; ref_only:
 * stop after measuring the reference (stats->grad_ref), no Newton step. */
static wr_status wr__statics_solve_one(const wr_shell *s, double *x, const wr_statics_desc *desc,
                                       wr_statics_stats *stats, wr_diag *diag, double gref_fixed, int ref_only) {
    wr_statics_desc d;
    wr_statics_stats st;
    wr__statics_ctx ctx;
    int32_t n, i, it;
    double *fext = NULL, *g = NULL, *dx = NULL, *xt = NULL, *xbest = NULL, *mass = NULL, *diagv = NULL;
    int32_t *dpos = NULL, roundoff_hits = 0;
    int exact_ok = 1, last_full = 0;
    double exact_retry_g = -1.0; /* desc.exact_retry: gradient below which the exact phase is tried again */
    double lin_tol = 0.0;
    double gbest = HUGE_VAL;
    uint8_t *fixd = NULL;
    wr__statics_cache cache;
    wr_csr A;
    wr_spd_solver S;
    int have_A = 0, have_S = 0;
    wr_status rs = WR_OK;
    double Pi, Pibest, Pscale = 0.0, gref, bbox, t_start = wr_time_seconds(), shift;
    memset(&st, 0, sizeof st);
    memset(&cache, 0, sizeof cache);
    memset(&A, 0, sizeof A);
    memset(&S, 0, sizeof S);
    memset(&ctx, 0, sizeof ctx);
    st.ccd_alpha_min = 1.0;
    if (stats) *stats = st;
    if (!s || !x || !s->faces) return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "statics: NULL shell or x");
    if (desc)
        d = *desc;
    else
        memset(&d, 0, sizeof d);
    if (d.max_iter == 0) d.max_iter = 200;
    if (d.grad_tol == 0.0) d.grad_tol = 1e-8;
    if (d.step_tol == 0.0) d.step_tol = 1e-13;
    if (d.shift_rel == 0.0) d.shift_rel = 1e-8;
    if (d.no_projection) d.projection = WR_PROJECT_NONE;
    if (d.max_iter < 0 || !(d.grad_tol > 0.0) || !(d.step_tol > 0.0) || !(d.shift_rel > 0.0) || !(d.perturb >= 0.0))
        return wr_fail(diag, WR_ERR_INVALID_ARG, -1,
                       "statics: max_iter %d, grad_tol %g, step_tol %g, shift_rel %g, perturb %g must be positive",
                       (int)d.max_iter, d.grad_tol, d.step_tol, d.shift_rel, d.perturb);
    if (!(d.pressure - d.pressure == 0.0) || !(d.contact_dhat >= 0.0) || !(d.contact_stiffness >= 0.0) ||
        d.contact_dhat - d.contact_dhat != 0.0 || d.contact_stiffness - d.contact_stiffness != 0.0)
        return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "statics: pressure %g, contact_dhat %g, contact_stiffness %g invalid",
                       d.pressure, d.contact_dhat, d.contact_stiffness);
    if (!(d.linear_forcing >= 0.0 && d.linear_forcing < 1.0))
        return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "statics: linear_forcing %g must be in [0, 1)", d.linear_forcing);
    if (!(d.shift_raise == 0.0 || (d.shift_raise > 1.0 && d.shift_raise - d.shift_raise == 0.0)))
        return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "statics: shift_raise %g must be 0 (off) or > 1", d.shift_raise);
    if (!(d.exact_retry == 0.0 || (d.exact_retry > 0.0 && d.exact_retry < 1.0)))
        return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "statics: exact_retry %g must be 0 (off) or in (0, 1)", d.exact_retry);
    if ((int)d.projection < 0 || (int)d.projection > (int)WR_PROJECT_NONE)
        return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "statics: unknown projection %d", (int)d.projection);
    rs = wr__statics_check_obstacles(d.obstacles, d.n_obstacles, diag);
    if (rs != WR_OK) return rs;
    n = 3 * s->nv;
    fext = (double *)wr_calloc_array((size_t)n, sizeof(double));
    g = (double *)wr_alloc_array((size_t)n, sizeof(double));
    dx = (double *)wr_alloc_array((size_t)n, sizeof(double));
    xt = (double *)wr_alloc_array((size_t)n, sizeof(double));
    xbest = (double *)wr_alloc_array((size_t)n, sizeof(double));
    mass = (double *)wr_alloc_array((size_t)s->nv, sizeof(double));
    diagv = (double *)wr_alloc_array((size_t)n, sizeof(double));
    fixd = (uint8_t *)wr_calloc_array((size_t)n, 1);
    if (!fext || !g || !dx || !xt || !xbest || !mass || !diagv || !fixd) {
        rs = wr_fail(diag, WR_ERR_NOMEM, -1, "statics: out of memory (%d DOFs)", (int)n);
        goto done;
    }
    /* external load: lumped gravity m_v g */
    wr_shell_vertex_masses(s, mass);
    for (i = 0; i < n; ++i) fext[i] = mass[i / 3] * d.gravity[i % 3];
    if (d.fixed)
        for (i = 0; i < n; ++i) {
            fixd[i] = d.fixed[i / 3] != 0;
            if (fixd[i] && d.target) x[i] = d.target[i];
        }
    for (i = 0; i < n; ++i)
        if (!(x[i] == x[i]) || x[i] - x[i] != 0.0) {
            rs = wr_fail(diag, WR_ERR_DOMAIN, i / 3, "statics: vertex %d has a non-finite coordinate", (int)(i / 3));
            goto done;
        }
    if (d.pressure != 0.0) {
        /* V depends on the origin through an open boundary unless that boundary is prescribed */
        int32_t f, k;
        for (f = 0; f < s->nf; ++f)
            for (k = 0; k < 3; ++k)
                if (s->opp[3 * f + k] < 0) {
                    int32_t va = s->faces[3 * f + (k + 1) % 3], vb = s->faces[3 * f + (k + 2) % 3];
                    int32_t bad = !fixd[3 * va] ? va : (!fixd[3 * vb] ? vb : -1);
                    if (bad >= 0) {
                        rs = wr_fail(diag, WR_ERR_UNSUPPORTED, bad,
                                     "statics: pressure on an open surface with free boundary vertex %d (sew it closed "
                                     "or prescribe the boundary)",
                                     (int)bad);
                        goto done;
                    }
                }
    }
    if (d.perturb > 0.0) {
        /* seeded kick along area-weighted vertex normals (flat starts are saddle points of buckling) */
        wr_rng rng;
        double *nrm = diagv;
        int32_t f, k;
        memset(nrm, 0, sizeof(double) * (size_t)n);
        for (f = 0; f < s->nf; ++f) {
            const int32_t *t = s->faces + 3 * f;
            wr_vec3 e1 = wr_v3_sub(wr_v3_load(x + 3 * t[1]), wr_v3_load(x + 3 * t[0]));
            wr_vec3 e2 = wr_v3_sub(wr_v3_load(x + 3 * t[2]), wr_v3_load(x + 3 * t[0]));
            wr_vec3 c = wr_v3_cross(e1, e2);
            for (k = 0; k < 3; ++k) {
                nrm[3 * t[k]] += c.x;
                nrm[3 * t[k] + 1] += c.y;
                nrm[3 * t[k] + 2] += c.z;
            }
        }
        wr_rng_seed(&rng, d.seed);
        for (i = 0; i < s->nv; ++i) {
            wr_vec3 nv = wr_v3_normalized(wr_v3_load(nrm + 3 * i));
            double a = d.perturb * wr_rng_normal(&rng);
            if (fixd[3 * i]) continue;
            x[3 * i] += a * nv.x;
            x[3 * i + 1] += a * nv.y;
            x[3 * i + 2] += a * nv.z;
        }
    }
    {
        double lo[3] = {1e300, 1e300, 1e300}, hi[3] = {-1e300, -1e300, -1e300};
        for (i = 0; i < n; ++i) {
            lo[i % 3] = fmin(lo[i % 3], x[i]);
            hi[i % 3] = fmax(hi[i % 3], x[i]);
            ctx.origin[i % 3] += x[i] / s->nv;
        }
        bbox = sqrt((hi[0] - lo[0]) * (hi[0] - lo[0]) + (hi[1] - lo[1]) * (hi[1] - lo[1]) +
                    (hi[2] - lo[2]) * (hi[2] - lo[2]));
    }
    ctx.s = s;
    ctx.fext = fext;
    ctx.fixv = d.fixed;
    ctx.p = d.pressure;
    ctx.obs = d.obstacles;
    ctx.nobs = d.n_obstacles;
    if (ctx.nobs > 0) {
        /* ON CONTACT defaults */
        double fref = 0.0, *av = xt;
        int32_t f, k;
        ctx.dhat = d.contact_dhat > 0.0 ? d.contact_dhat : WR__STATICS_DHAT_REL * bbox;
        if (!(ctx.dhat > 0.0)) ctx.dhat = WR__STATICS_DHAT_REL;
        memset(av, 0, sizeof(double) * (size_t)s->nv);
        for (f = 0; f < s->nf; ++f)
            for (k = 0; k < 3; ++k) av[s->faces[3 * f + k]] += s->area[f] / 3.0;
        for (i = 0; i < s->nv; ++i)
            fref = fmax(fref, mass[i] * sqrt(d.gravity[0] * d.gravity[0] + d.gravity[1] * d.gravity[1] +
                                             d.gravity[2] * d.gravity[2]) +
                                  fabs(d.pressure) * av[i]);
        if (!(fref > 0.0)) fref = 1e-3 * fabs(s->C_mem[0]) * sqrt(2.0 * s->total_area / s->nf);
        if (!(fref > 0.0)) fref = 1e-3 * s->bending_stiffness / sqrt(2.0 * s->total_area / s->nf);
        ctx.kappa = d.contact_stiffness > 0.0 ? d.contact_stiffness : 10.0 * fref / ctx.dhat;
        if (!(ctx.kappa > 0.0)) ctx.kappa = 1.0;
        st.contact_dhat = ctx.dhat;
        st.contact_stiffness = ctx.kappa;
    }
    rs = wr__statics_energy(&ctx, x, &Pi, g, &Pscale, diag);
    if (rs != WR_OK) goto done;
    memcpy(xbest, x, sizeof(double) * (size_t)n);
    Pibest = Pi;
    st.grad_norm0 = st.grad_norm = wr__statics_norm(g, n);
    gbest = st.grad_norm0;
    {
        double fe = 0.0;
        for (i = 0; i < n; ++i)
            if (!fixd[i]) fe += fext[i] * fext[i];
        gref = gref_fixed > 0.0 ? gref_fixed : fmax(st.grad_norm0, sqrt(fe));
    }
    st.grad_ref = gref;
    if (ref_only) goto done;
    st.energy = Pi;
    shift = 0.0;
    d.linear.fixed = fixd;
    for (it = 0; it < d.max_iter; ++it) {
        wr__statics_sink sk;
        wr_hess_sink hs;
        wr_spd_stats ls;
        double t0, gdx, alpha, alpha0, mean_diag = 0.0, maxstep, Pscale0;
        int use_exact;
        int raises;
        if (st.grad_norm <= d.grad_tol * gref || gref == 0.0) {
            st.stop = WR_STATICS_STOP_GRADIENT;
            break;
        }
        /* assemble */
        t0 = wr_time_seconds();
        memset(&sk, 0, sizeof sk);
        /* ON PROJECTION, exact phase: near a minimum after a full step, try the exact Hessian */
        use_exact = d.projection != WR_PROJECT_NONE && (exact_ok || st.grad_norm <= exact_retry_g) && last_full &&
                    st.grad_norm <= WR_STATICS_EXACT_SWITCH * gref;
        sk.proj = use_exact ? WR_PROJECT_NONE : d.projection;
        sk.c = &ctx;
        sk.x = x;
        sk.cache = &cache;
        hs.user = &sk;
        hs.add = wr__statics_add;
        if (have_A) {
            /* ON ASSEMBLY CACHE: same pattern, values through the recorded offsets */
            wr_csr_zero_values(&A);
            sk.A = &A;
            if (cache.Kq) {
                rs = wr_shell_hessian_elements_part(s, x, 0, WR_SHELL_HESS_FACES, &hs, diag);
                if (rs != WR_OK) goto done;
                /* the constant quadratic-bending part, added where the stream would have added it */
                for (i = 0; i < A.nnz; ++i) A.val[i] += cache.Kq[i];
                sk.e = cache.qb_end;
                sk.n_elem += cache.qb_small;
            } else {
                rs = wr_shell_hessian_elements(s, x, 0, &hs, diag);
                if (rs != WR_OK) goto done;
            }
        } else {
            /* first assembly: record the stencils and blocks (faces, then quadratic bending) */
            rs = wr_shell_hessian_elements_part(s, x, 0, WR_SHELL_HESS_FACES, &hs, diag);
            if (rs == WR_OK) {
                cache.face_end = cache.n_el;
                rs = wr_shell_hessian_elements_part(s, x, 0, WR_SHELL_HESS_QUADRATIC, &hs, diag);
                cache.qb_end = cache.n_el;
            }
            if (rs != WR_OK) goto done;
        }
        if (ctx.p != 0.0)
            for (; sk.face < s->nf; ++sk.face) {
                /* faces without an elastic block: the pressure block projected on its own */
                double x9[9], H9[81];
                int32_t a, k;
                for (a = 0; a < 3; ++a)
                    for (k = 0; k < 3; ++k) x9[3 * a + k] = x[3 * s->faces[3 * sk.face + a] + k];
                wr_statics_pressure_element(x9, ctx.origin, ctx.p, NULL, H9);
                if ((rs = wr__statics_put(&sk, 3, s->faces + 3 * sk.face, H9)) != WR_OK) {
                    rs = wr_fail(diag, rs, sk.face, "statics: pressure block of face %d rejected", (int)sk.face);
                    goto done;
                }
            }
        if (!have_A) {
            /* the pattern of the recorded stencils (plus every diagonal block: the shift and any contact
             * block go there), each element's block offsets, then the recorded values in stream order */
            int32_t e;
            int64_t r = 0;
            rs = wr_csr_from_stencils(&A, s->nv, cache.n_el, cache.vstart, cache.verts, diag);
            if (rs != WR_OK) goto done;
            have_A = 1;
            cache.ostart = (int64_t *)wr_alloc_array((size_t)cache.n_el + 1, sizeof(int64_t));
            dpos = (int32_t *)wr_alloc_array((size_t)n, sizeof(int32_t));
            if (!cache.ostart || !dpos) {
                rs = wr_fail(diag, WR_ERR_NOMEM, -1, "statics: out of memory (%d DOFs)", (int)n);
                goto done;
            }
            cache.ostart[0] = 0;
            for (e = 0; e < cache.n_el; ++e) {
                int64_t k = cache.vstart[e + 1] - cache.vstart[e];
                cache.ostart[e + 1] = cache.ostart[e] + k * k;
            }
            cache.off = (int32_t *)wr_alloc_array((size_t)cache.ostart[cache.n_el] + 1, sizeof(int32_t));
            /* the quadratic-bending blocks are constant and left unchanged by the FAST projection (PSD) */
            if (cache.qb_end > cache.face_end && d.projection != WR_PROJECT_JACOBI)
                cache.Kq = (double *)wr_calloc_array((size_t)A.nnz + 1, sizeof(double));
            if (!cache.off || (cache.qb_end > cache.face_end && d.projection != WR_PROJECT_JACOBI && !cache.Kq)) {
                rs = wr_fail(diag, WR_ERR_NOMEM, -1, "statics: out of memory (%d DOFs)", (int)n);
                goto done;
            }
            for (e = 0; e < cache.n_el; ++e) {
                int32_t k = cache.vstart[e + 1] - cache.vstart[e];
                const int32_t *ev = cache.verts + cache.vstart[e];
                int32_t *off = cache.off + cache.ostart[e];
                if ((rs = wr_csr_block_offsets(&A, k, ev, off, diag)) != WR_OK) goto done;
                wr_csr_add_element_blocks(&A, k, ev, off, cache.rec + r);
                if (cache.Kq && e >= cache.face_end && e < cache.qb_end) {
                    wr_csr kq = A;
                    kq.val = cache.Kq;
                    wr_csr_add_element_blocks(&kq, k, ev, off, cache.rec + r);
                    if (3 * k <= WR_DENSE_MAX) cache.qb_small++;
                }
                r += 9 * (int64_t)k * k;
            }
            wr_free(cache.rec);
            cache.rec = NULL;
            cache.rcap = cache.rn = 0;
            for (i = 0; i < n; ++i) dpos[i] = wr_csr_find(&A, i, i);
            sk.A = &A; /* the contact blocks below go straight into A */
        }
        if (ctx.nobs > 0 && (rs = wr__statics_contact_hessian(&ctx, x, &sk)) != WR_OK) {
            rs = wr_fail(diag, rs, -1, "statics: contact block rejected");
            goto done;
        }
        st.elements_projected += sk.n_proj;
        st.elements_assembled += sk.n_elem;
        st.t_projection += sk.t_proj;
        st.t_assembly += wr_time_seconds() - t0 - sk.t_proj;
        wr_csr_diagonal(&A, diagv);
        for (i = 0; i < n; ++i) mean_diag += fabs(diagv[i]);
        mean_diag = mean_diag / n;
        if (!(mean_diag > 0.0)) mean_diag = 1.0;
        if (shift == 0.0) shift = d.shift_rel * mean_diag;
        /* solve (K + μI) Δx = −g, raising μ while the matrix is not SPD */
        t0 = wr_time_seconds();
        for (raises = 0;; ++raises) {
            for (i = 0; i < n; ++i) {
                A.val[dpos[i]] = diagv[i] + shift;
                dx[i] = 0.0;
                xt[i] = -g[i];
            }
            if (!have_S) {
                rs = wr_spd_solver_create(&S, &A, &d.linear, diag);
                if (rs != WR_OK) goto done;
                have_S = 1;
                lin_tol = S.rel_tol;
            }
            if (d.linear_forcing > 0.0 && S.method != WR_SOLVER_CHOLMOD) /* ON INEXACT NEWTON */
                S.rel_tol = fmin(d.linear_forcing, fmax(lin_tol, sqrt(st.grad_norm / gref)));
            rs = wr_spd_solver_factor(&S, &A, diag);
            if (rs == WR_OK) rs = wr_spd_solver_solve(&S, &A, xt, dx, &ls, diag);
            if (rs == WR_OK || rs == WR_ERR_NOT_CONVERGED) {
                st.linear_iterations += ls.iterations;
                gdx = 0.0;
                for (i = 0; i < n; ++i) gdx += g[i] * dx[i];
                if (gdx < 0.0) break;
            }
            /* the exact Hessian is indefinite here: shift this step, project from the next one on */
            if (use_exact) {
                exact_ok = 0;
                /* opt-in (desc.exact_retry): try again once the gradient has fallen by that factor */
                if (d.exact_retry > 0.0) exact_retry_g = d.exact_retry * st.grad_norm;
            }
            if ((rs != WR_OK && rs != WR_ERR_NOT_SPD && rs != WR_ERR_NOT_CONVERGED) ||
                raises == WR__STATICS_MAX_SHIFT_RAISES)
                break;
            /* from a decayed μ (ON SHIFT) straight back to at least the initial shift */
            shift = fmax(shift * 100.0, d.shift_rel * mean_diag);
        }
        st.t_linear += wr_time_seconds() - t0;
        st.shift = shift;
        if (rs != WR_OK && rs != WR_ERR_NOT_CONVERGED && rs != WR_ERR_NOT_SPD) goto done;
        gdx = 0.0;
        for (i = 0; i < n; ++i) gdx += g[i] * dx[i];
        if (!(gdx < 0.0)) {
            /* no descent direction from the linear solver: fall back to steepest descent */
            double sc = 1.0 / mean_diag;
            for (i = 0; i < n; ++i) dx[i] = -sc * g[i];
            gdx = 0.0;
            for (i = 0; i < n; ++i) gdx += g[i] * dx[i];
        }
        rs = WR_OK;
        /* backtracking line search on Π, from the CCD-safe step */
        t0 = wr_time_seconds();
        alpha0 = ctx.nobs > 0 ? wr__statics_ccd(&ctx, x, dx) : 1.0;
        st.ccd_alpha_min = fmin(st.ccd_alpha_min, alpha0);
        alpha = alpha0;
        {
            int h, ok = 0;
            double Pit = 0.0;
            for (h = 0; h < WR__STATICS_MAX_HALVINGS; ++h, alpha *= 0.5) {
                for (i = 0; i < n; ++i) xt[i] = x[i] + alpha * dx[i];
                st.line_search_evals++;
                if (wr__statics_energy(&ctx, xt, &Pit, NULL, NULL, NULL) != WR_OK) continue;
                if (Pit <= Pi + WR__STATICS_ARMIJO * alpha * gdx) {
                    ok = 1;
                    break;
                }
                if (-alpha * gdx <= WR_STATICS_ENERGY_NOISE * Pscale && Pit <= Pi + WR_STATICS_ENERGY_NOISE * Pscale) {
                    /* roundoff regime: Π cannot resolve the decrease; accept when the gradient drops */
                    double *gt = diagv;
                    if (wr__statics_energy(&ctx, xt, &Pit, gt, NULL, NULL) == WR_OK &&
                        wr__statics_norm(gt, n) < st.grad_norm) {
                        ok = 1;
                        break;
                    }
                }
            }
            st.t_line_search += wr_time_seconds() - t0;
            if (!ok) {
                /* no decrease Π can resolve, with the Newton decrement at round-off: as converged as
                 * double precision allows (ON STOPPING) */
                st.stop = (-gdx <= WR_STATICS_ENERGY_NOISE * Pscale && st.grad_norm <= sqrt(d.grad_tol) * gref)
                              ? WR_STATICS_STOP_ROUNDOFF
                              : WR_STATICS_STOP_LINE_SEARCH;
                break;
            }
        }
        maxstep = 0.0;
        for (i = 0; i < n; ++i) maxstep = fmax(maxstep, fabs(alpha * dx[i]));
        memcpy(x, xt, sizeof(double) * (size_t)n);
        Pscale0 = Pscale;
        rs = wr__statics_energy(&ctx, x, &Pi, g, &Pscale, diag);
        if (rs != WR_OK) goto done;
        /* successful full steps relax the shift towards the factorisation's round-off (ON SHIFT) */
        if (alpha == 1.0) shift = fmax(shift * 0.1, WR_STATICS_SHIFT_MIN_REL * mean_diag);
        /* opt-in: a backtracked step raises it (ON SHIFT, desc.shift_raise), up to the cap */
        else if (d.shift_raise > 0.0 && alpha < alpha0)
            shift = fmax(shift, fmin(shift * d.shift_raise, WR_STATICS_SHIFT_RAISE_CAP * d.shift_rel * mean_diag));
        last_full = alpha == 1.0;
        if (use_exact) st.exact_steps++;
        /* round-off (ON STOPPING): the Newton decrement −∇Π·Δx is below what Π resolves AND the
         * gradient makes no new 10 % low; a gradient that still falls is still converging */
        {
            double gn = wr__statics_norm(g, n);
            if (-gdx <= WR_STATICS_ENERGY_NOISE * Pscale0 && gn <= sqrt(d.grad_tol) * gref && gn > 0.9 * gbest)
                roundoff_hits++;
            else
                roundoff_hits = 0;
            gbest = fmin(gbest, gn);
        }
        st.iterations = it + 1;
        st.energy = Pi;
        st.grad_norm = wr__statics_norm(g, n);
        st.last_step = maxstep;
        if (Pi <= Pibest) {
            Pibest = Pi;
            memcpy(xbest, x, sizeof(double) * (size_t)n);
        }
        st.t_total = wr_time_seconds() - t_start;
        if (d.progress) d.progress(d.progress_user, &st);
        if (st.grad_norm <= d.grad_tol * gref) {
            st.stop = WR_STATICS_STOP_GRADIENT;
            break;
        }
        /* only a full Newton step is small because the solution is near; a backtracked or CCD-cut
         * one may just be stalled (reported as such when the iterations run out) */
        if (maxstep <= d.step_tol * bbox && alpha == 1.0) {
            st.stop = WR_STATICS_STOP_STEP;
            break;
        }
        if (roundoff_hits >= WR__STATICS_ROUNDOFF_HITS) {
            st.stop = WR_STATICS_STOP_ROUNDOFF;
            break;
        }
    }
    if (st.stop == WR_STATICS_STOP_NONE) st.stop = WR_STATICS_STOP_MAX_ITER;
    if (st.stop == WR_STATICS_STOP_MAX_ITER || st.stop == WR_STATICS_STOP_LINE_SEARCH) {
        if (Pibest < Pi) {
            memcpy(x, xbest, sizeof(double) * (size_t)n);
            wr__statics_energy(&ctx, x, &Pi, g, NULL, NULL);
            st.energy = Pi;
            st.grad_norm = wr__statics_norm(g, n);
        }
        rs = wr_fail(diag, WR_ERR_NOT_CONVERGED, st.iterations,
                     "statics: %s after %d Newton steps, |grad| %.3e (target %.3e)",
                     st.stop == WR_STATICS_STOP_MAX_ITER ? "max_iter reached" : "line search failed",
                     (int)st.iterations, st.grad_norm, d.grad_tol * gref);
    }
    if (ctx.p != 0.0) st.volume = wr_statics_volume(s, x, ctx.origin, NULL);
    if (ctx.nobs > 0) {
        int32_t o, v;
        st.min_distance = HUGE_VAL;
        for (o = 0; o < ctx.nobs; ++o)
            for (v = 0; v < s->nv; ++v) {
                double dd = wr_obstacle_distance(ctx.obs + o, x + 3 * v, NULL);
                if (ctx.fixv && ctx.fixv[v]) continue;
                st.min_distance = fmin(st.min_distance, dd);
                if (dd < ctx.dhat) st.n_contacts++;
            }
    }
done:
    st.t_total = wr_time_seconds() - t_start;
    if (stats) *stats = st;
    if (have_S) wr_spd_solver_free(&S);
    if (have_A) wr_csr_free(&A);
    wr__statics_cache_free(&cache);
    wr_free(fext);
    wr_free(g);
    wr_free(dx);
    wr_free(xt);
    wr_free(xbest);
    wr_free(mass);
    wr_free(diagv);
    wr_free(dpos);
    wr_free(fixd);
    return rs;
}

/* ON MEMBRANE CONTINUATION: soft-membrane stages, then the real shell */
WRDEF wr_status wr_statics_solve(const wr_shell *s, double *x, const wr_statics_desc *desc, wr_statics_stats *stats,
                                 wr_diag *diag) {
    wr_statics_desc dk;
    wr_statics_stats sk, acc;
    double m, f, t0 = wr_time_seconds();
    wr_status rs;
    int32_t k;
    double gref, *x0;
    if (!desc || desc->membrane_ramp == 0.0) return wr__statics_solve_one(s, x, desc, stats, diag, 0.0, 0);
    memset(&acc, 0, sizeof acc);
    if (stats) *stats = acc;
    m = desc->membrane_ramp;
    f = desc->membrane_ramp_factor == 0.0 ? WR__STATICS_RAMP_FACTOR : desc->membrane_ramp_factor;
    if (!(m > 0.0 && m < 1.0) || !(f > 1.0) || f - f != 0.0)
        return wr_fail(diag, WR_ERR_INVALID_ARG, -1,
                       "statics: membrane_ramp %g must be in (0, 1) and membrane_ramp_factor %g > 1", m, f);
    if (!s || !x || !s->faces) return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "statics: NULL shell or x");
    dk = *desc;
    dk.membrane_ramp = 0.0;
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
    for (; m < 1.0; m *= f) {
        /* a shallow copy: only the membrane constants differ, the arrays are shared read-only */
        wr_shell soft = *s;
        for (k = 0; k < 9; ++k) soft.C_mem[k] *= m;
        soft.young *= m;
        dk.grad_tol = WR_STATICS_RAMP_TOL;
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
        dk.perturb = 0.0;
        acc.ramp_stages++;
        acc.ramp_iterations += sk.iterations;
        wr__statics_work_add(&acc, &sk);
        acc.ccd_alpha_min = acc.ramp_stages == 1 ? sk.ccd_alpha_min : fmin(acc.ccd_alpha_min, sk.ccd_alpha_min);
    }
    dk.grad_tol = desc->grad_tol;
    rs = wr__statics_solve_one(s, x, &dk, &sk, diag, gref, 0);
    if (rs == WR_ERR_NOT_CONVERGED) {
        /* the soft path led somewhere the real shell cannot converge from: plain solve from the start */
        acc.ramp_iterations += sk.iterations;
        wr__statics_work_add(&acc, &sk);
        memcpy(x, x0, sizeof(double) * 3 * (size_t)s->nv);
        dk.perturb = desc->perturb;
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
    if ((int)m->kind < 0 || (int)m->kind > (int)WR_MOTION_TWIST)
        return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "motion: unknown kind %d", (int)m->kind);
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
        default:
            break;
        }
        for (i = 0; i < 3; ++i) target[3 * v + i] = y[i];
        if (fixed) fixed[v] = 1;
    }
    return WR_OK;
}

WRDEF wr_status wr_statics_solve_incremental(const wr_shell *s, double *x, const wr_statics_desc *desc,
                                             const wr_motion *motions, int32_t n_motions, int32_t n_inc,
                                             wr_statics_stats *stats, wr_diag *diag) {
    wr_statics_desc dk;
    wr_statics_stats sk, acc;
    double *X = NULL, *target = NULL, *xprev = NULL, *xsave = NULL;
    uint8_t *fixed = NULL;
    int32_t k, j, n;
    wr_status rs = WR_OK;
    double t0 = wr_time_seconds();
    memset(&acc, 0, sizeof acc);
    if (stats) *stats = acc;
    if (!s || !x || !s->faces) return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "statics: NULL shell or x");
    if (n_inc < 1 || n_motions < 0 || (n_motions > 0 && !motions))
        return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "statics: n_inc %d must be >= 1, n_motions %d >= 0 with motions",
                       (int)n_inc, (int)n_motions);
    if (desc)
        dk = *desc;
    else
        memset(&dk, 0, sizeof dk);
    n = 3 * s->nv;
    X = (double *)wr_alloc_array((size_t)n, sizeof(double));
    target = (double *)wr_alloc_array((size_t)n, sizeof(double));
    fixed = (uint8_t *)wr_calloc_array((size_t)s->nv, 1);
    xprev = (double *)wr_alloc_array((size_t)n, sizeof(double));
    xsave = (double *)wr_alloc_array((size_t)n, sizeof(double));
    if (!X || !target || !fixed || !xprev || !xsave) {
        rs = wr_fail(diag, WR_ERR_NOMEM, -1, "statics: out of memory (%d DOFs)", (int)n);
        goto done;
    }
    memcpy(X, x, sizeof(double) * (size_t)n);
    memcpy(xprev, x, sizeof(double) * (size_t)n);
    memcpy(target, desc && desc->target ? desc->target : x, sizeof(double) * (size_t)n);
    if (desc && desc->fixed)
        for (j = 0; j < s->nv; ++j) fixed[j] = desc->fixed[j] != 0;
    for (j = 0; j < n_motions; ++j) /* validate everything before the first solve */
        if ((rs = wr_motion_apply(motions + j, s->nv, X, 0.0, target, fixed, diag)) != WR_OK) goto done;
    dk.fixed = fixed;
    dk.target = target;
    for (k = 1; k <= n_inc; ++k) {
        double t = (double)k / (double)n_inc;
        for (j = 0; j < n_motions; ++j)
            if ((rs = wr_motion_apply(motions + j, s->nv, X, t, target, fixed, diag)) != WR_OK) goto done;
        if (k > 1) dk.perturb = 0.0;
        dk.grad_tol = (k < n_inc && desc && desc->inc_grad_tol > 0.0) ? desc->inc_grad_tol : (desc ? desc->grad_tol : 0.0);
        memcpy(xsave, x, sizeof(double) * (size_t)n);
        if (k > 1 && dk.inc_predictor) {
            /* secant predictor: free vertices continue along the path of the last increment */
            for (j = 0; j < n; ++j)
                if (!fixed[j / 3]) x[j] = 2.0 * x[j] - xprev[j];
        }
        rs = wr_statics_solve(s, x, &dk, &sk, diag);
        if (k > 1 && dk.inc_predictor && (rs == WR_ERR_GEOMETRY || rs == WR_ERR_DOMAIN) && sk.iterations == 0) {
            /* the prediction folded a face or entered an obstacle: start from the last equilibrium */
            memcpy(x, xsave, sizeof(double) * (size_t)n);
            rs = wr_statics_solve(s, x, &dk, &sk, diag);
        }
        memcpy(xprev, xsave, sizeof(double) * (size_t)n);
        acc.total_iterations += sk.iterations;
        wr__statics_work_add(&acc, &sk);
        acc.increments = k;
        if (rs == WR_ERR_NOT_CONVERGED && k < n_inc) {
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
        out.t_total = wr_time_seconds() - t0;
        acc = out;
    }
done:
    if (stats) *stats = acc;
    wr_free(X);
    wr_free(target);
    wr_free(fixed);
    wr_free(xprev);
    wr_free(xsave);
    return rs;
}

/* ---- sewing ------------------------------------------------------------------------------------ */

static int32_t wr__statics_find(int32_t *par, int32_t v) {
    while (par[v] != v) {
        par[v] = par[par[v]];
        v = par[v];
    }
    return v;
}

WRDEF wr_status wr_mesh_weld(wr_mesh *out, const wr_mesh *in, int32_t n_pairs, const int32_t *pairs, int32_t *vmap,
                             wr_diag *diag) {
    int32_t *par = NULL, *nid = NULL, *faces = NULL, *cnt = NULL, nn = 0, v, f, k, i;
    double *pos = NULL, *cr = NULL;
    wr_status rs = WR_OK;
    if (out) memset(out, 0, sizeof *out);
    if (!out || !in || !in->faces || n_pairs < 0 || (n_pairs > 0 && !pairs))
        return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "weld: NULL mesh or pairs, or n_pairs %d < 0", (int)n_pairs);
    par = (int32_t *)wr_alloc_array((size_t)in->nv, sizeof(int32_t));
    nid = (int32_t *)wr_alloc_array((size_t)in->nv, sizeof(int32_t));
    cnt = (int32_t *)wr_calloc_array((size_t)in->nv, sizeof(int32_t));
    faces = (int32_t *)wr_alloc_array((size_t)in->nf * 3, sizeof(int32_t));
    pos = (double *)wr_calloc_array((size_t)in->nv * 3, sizeof(double));
    cr = (double *)wr_alloc_array((size_t)in->nf * 6, sizeof(double));
    if (!par || !nid || !cnt || !faces || !pos || !cr) {
        rs = wr_fail(diag, WR_ERR_NOMEM, -1, "weld: out of memory");
        goto done;
    }
    for (v = 0; v < in->nv; ++v) par[v] = v;
    for (k = 0; k < n_pairs; ++k) {
        int32_t a = pairs[2 * k], b = pairs[2 * k + 1];
        if (a < 0 || a >= in->nv || b < 0 || b >= in->nv) {
            rs = wr_fail(diag, WR_ERR_INVALID_ARG, k, "weld: pair %d (%d, %d) outside [0, %d)", (int)k, (int)a, (int)b,
                         (int)in->nv);
            goto done;
        }
        a = wr__statics_find(par, a);
        b = wr__statics_find(par, b);
        /* the smaller index is the root, so an unpaired prefix keeps its numbering */
        if (a < b)
            par[b] = a;
        else
            par[a] = b;
    }
    for (v = 0; v < in->nv; ++v) {
        int32_t r = wr__statics_find(par, v);
        if (r == v) nid[v] = nn++;
    }
    for (v = 0; v < in->nv; ++v) {
        int32_t j = nid[wr__statics_find(par, v)];
        if (vmap) vmap[v] = j;
        for (i = 0; i < 3; ++i) pos[3 * j + i] += in->pos[3 * v + i];
        cnt[j]++;
    }
    for (v = 0; v < nn; ++v)
        for (i = 0; i < 3; ++i) pos[3 * v + i] /= cnt[v];
    for (f = 0; f < in->nf; ++f) {
        for (k = 0; k < 3; ++k) faces[3 * f + k] = nid[wr__statics_find(par, in->faces[3 * f + k])];
        wr_mesh_face_rest(in, f, cr + 6 * f);
    }
    rs = wr_mesh_create(out, nn, pos, NULL, in->nf, faces, diag);
    if (rs != WR_OK) goto done;
    rs = wr_mesh_set_corner_rest(out, cr, diag);
    if (rs == WR_OK && in->face_panel) rs = wr_mesh_set_face_panel(out, in->face_panel, diag);
    if (rs != WR_OK) wr_mesh_free(out);
done:
    wr_free(par);
    wr_free(nid);
    wr_free(cnt);
    wr_free(faces);
    wr_free(pos);
    wr_free(cr);
    return rs;
}

WRDEF wr_status wr_mesh_pillow(wr_mesh *out, const wr_mesh *panel, double lift, wr_diag *diag) {
    int32_t nv, nf, *faces = NULL, *hop = NULL, *pairs = NULL, *fp = NULL, np = 0, v, f, k, e, maxhop = 0, changed;
    double *pos = NULL, *cr = NULL;
    wr_mesh two;
    wr_status rs = WR_OK;
    memset(&two, 0, sizeof two);
    if (out) memset(out, 0, sizeof *out);
    if (!out || !panel || !panel->faces || !(lift > 0.0) || lift - lift != 0.0)
        return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "pillow: NULL mesh or lift %g not > 0", lift);
    if (panel->n_loops < 1)
        return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "pillow: the panel has no boundary to sew");
    nv = panel->nv;
    nf = panel->nf;
    faces = (int32_t *)wr_alloc_array((size_t)nf * 6, sizeof(int32_t));
    fp = (int32_t *)wr_alloc_array((size_t)nf * 2, sizeof(int32_t));
    hop = (int32_t *)wr_alloc_array((size_t)nv, sizeof(int32_t));
    pairs = (int32_t *)wr_alloc_array((size_t)panel->loop_start[panel->n_loops] * 2, sizeof(int32_t));
    pos = (double *)wr_alloc_array((size_t)nv * 6, sizeof(double));
    cr = (double *)wr_alloc_array((size_t)nf * 12, sizeof(double));
    if (!faces || !fp || !hop || !pairs || !pos || !cr) {
        rs = wr_fail(diag, WR_ERR_NOMEM, -1, "pillow: out of memory");
        goto done;
    }
    /* hop distance to the boundary (Bellman–Ford sweeps over the edges; O(ne · depth)) */
    for (v = 0; v < nv; ++v) hop[v] = INT32_MAX;
    for (k = 0; k < panel->loop_start[panel->n_loops]; ++k) {
        hop[panel->loop_verts[k]] = 0;
        pairs[2 * np] = panel->loop_verts[k];
        pairs[2 * np + 1] = nv + panel->loop_verts[k];
        np++;
    }
    do {
        changed = 0;
        for (e = 0; e < panel->ne; ++e) {
            int32_t a = panel->edges[2 * e], b = panel->edges[2 * e + 1];
            if (hop[a] != INT32_MAX && hop[a] + 1 < hop[b]) hop[b] = hop[a] + 1, changed = 1;
            if (hop[b] != INT32_MAX && hop[b] + 1 < hop[a]) hop[a] = hop[b] + 1, changed = 1;
        }
    } while (changed);
    for (v = 0; v < nv; ++v) {
        if (hop[v] == INT32_MAX) hop[v] = 0; /* a component without boundary stays flat */
        if (hop[v] > maxhop) maxhop = hop[v];
    }
    for (v = 0; v < nv; ++v) {
        double z = maxhop > 0 ? lift * (double)hop[v] / (double)maxhop : 0.0;
        pos[3 * v] = pos[3 * (nv + v)] = panel->pos[3 * v];
        pos[3 * v + 1] = pos[3 * (nv + v) + 1] = panel->pos[3 * v + 1];
        pos[3 * v + 2] = panel->pos[3 * v + 2] + z;
        pos[3 * (nv + v) + 2] = panel->pos[3 * v + 2] - z;
    }
    for (f = 0; f < nf; ++f) {
        double uv[6], *b = cr + 6 * (nf + f);
        const int32_t *t = panel->faces + 3 * f;
        wr_mesh_face_rest(panel, f, uv);
        memcpy(cr + 6 * f, uv, sizeof uv);
        faces[3 * f] = t[0];
        faces[3 * f + 1] = t[1];
        faces[3 * f + 2] = t[2];
        /* bottom: mirrored pattern u → −u with corners 1 and 2 swapped (CCW again, normal flipped) */
        faces[3 * (nf + f)] = nv + t[0];
        faces[3 * (nf + f) + 1] = nv + t[2];
        faces[3 * (nf + f) + 2] = nv + t[1];
        b[0] = -uv[0], b[1] = uv[1];
        b[2] = -uv[4], b[3] = uv[5];
        b[4] = -uv[2], b[5] = uv[3];
        fp[f] = 0;
        fp[nf + f] = 1;
    }
    rs = wr_mesh_create(&two, 2 * nv, pos, NULL, 2 * nf, faces, diag);
    if (rs == WR_OK) rs = wr_mesh_set_corner_rest(&two, cr, diag);
    if (rs == WR_OK) rs = wr_mesh_set_face_panel(&two, fp, diag);
    if (rs == WR_OK) rs = wr_mesh_weld(out, &two, np, pairs, NULL, diag);
done:
    wr_mesh_free(&two);
    wr_free(faces);
    wr_free(fp);
    wr_free(hop);
    wr_free(pairs);
    wr_free(pos);
    wr_free(cr);
    return rs;
}

#ifdef __cplusplus
}
#endif
#endif /* WRINKLE_STATICS_IMPLEMENTATION_DONE */
#endif /* WRINKLE_IMPLEMENTATION */
