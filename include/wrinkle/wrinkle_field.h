/* wrinkle/wrinkle_field.h — TFW wrinkle fields on a coarse base surface: the wrinkle-field energy,
 * the wrinkle-free face set, initialisation, an SQP solver for amplitude and frequency, phase
 * extraction and Loop upsampling to a wrinkled surface.
 * wrinkle v0.1.0 — MIT licence (see LICENSE). Needs core.h, mesh.h, sparse.h, spd.h; otherwise
 * libc and libm. Linear solves go through spd.h (CHOLMOD when built with -DWR_USE_CHOLMOD=1, else
 * PCG with IC(0)).
 *
 * Paper: Chen, Chen, Kaufman, Skouras, Vouga, "Fine Wrinkling on Coarsely Meshed Thin Shells"
 * (TFW, TOG 2021): Sec. 3 (Eq. 19–27), Sec. 4.2 (Eq. 29, 30), Sec. 5 (W set, Sec. 5.1),
 * App. A (discrete fundamental forms), App. E.2–E.5.
 *
 * HOW TO USE
 *   #define WRINKLE_IMPLEMENTATION in exactly one .c/.cpp file before including this header.
 *
 * API (create/free pairs: wr_wf_create → wr_wf_free; wr_wf_upsample → wr_mesh_free + wr_free;
 *      wr_wf_upsample_fields → wr_mesh_free + wr_wf_fine_fields_free)
 *   wr_wf_create(wf, mesh, base_pos, material, diag)   per-face I_u, I_b, II_b, Eq. 29 eigen-data
 *   wr_wf_free(wf)
 *   wr_wf_classify(wf, desc)                          W by the rule of Sec. 5.1; returns |W|
 *   wr_wf_set_wrinkle_free(wf, flags)                 set W explicitly (NULL = empty)
 *   wr_wf_set_amplitude_zero(wf, vflags)              hold a = 0 on vertices (clamped edges)
 *   wr_wf_energy(wf, a, omega, E, grad, face_hess, terms, diag)   E_wf (Eq. 20–27, 37), ∇, per-face ∇²
 *   wr_wf_face_dofs(wf, f, idx[6], sign[6])           global indices of a face's local DOFs
 *   wr_wf_curl(mesh, omega, curl)                     dω per face (mesh.h sign convention)
 *   wr_wf_project_closed(wf, omega, diag)             least-squares nearest ω with dω = 0 off W
 *   wr_wf_init(wf, desc, a, omega, diag)              App. E.2 initial guess (projected to dω = 0)
 *   wr_wf_solve(wf, desc, a, omega, stats, diag)      App. E.3 SQP: a >= 0, dω = 0 off W
 *   wr_wf_count_folds(wf, a, omega)                   edges where dφ reverses between wrinkled faces
 *   wr_wf_unfold(wf, a, omega, diag)                  re-orient dφ consistently, project to dω = 0
 *   wr_wf_phase(wf, omega, phi, stats, diag)          App. E.4: per-corner φ, 2π-integer jumps
 *   wr_wf_loop_step(m, ncomp, vals, desc, fine_faces, fine_vals, diag)  one Loop step, any fields
 *   wr_wf_loop_corner_rest(nf, corner_rest, fine)     one step of per-corner rest (ON SEWN BASES)
 *   wr_wf_upsample(wf, a, phi, desc, out, out_a, diag)  App. E.5: Loop n levels + Eq. 19 (v2 term)
 *   wr_wf_upsample_fields(wf, a, phi, desc, out, fields, diag)  the same, with the fine level's a,
 *                                                     phase and wrinkle-free flag per vertex (viewers)
 *   wr_wf_fine_fields_free(fields)
 *
 * EXAMPLE
 *     wr_mesh m, fine;  wr_wf wf;  wr_wf_material mat;  wr_wf_solve_stats ss;  wr_wf_upsample_desc ud;  wr_diag d;
 *     double *x, *a, *omega, *phi;  int32_t i;  wr_status st;
 *     if (wr_mesh_rectangle(&m, 0.25, 0.10, 12, 5, &d) != WR_OK) { puts(d.message); return 1; }
 *     x = (double *)wr_alloc_array(3 * (size_t)m.nv, sizeof(double));       // base_pos: nv*3 (TFT solve)
 *     a = (double *)wr_alloc_array((size_t)m.nv, sizeof(double));            // amplitude per vertex [m]
 *     omega = (double *)wr_alloc_array((size_t)m.ne, sizeof(double));        // frequency one-form [rad]
 *     phi = (double *)wr_alloc_array(3 * (size_t)m.nf, sizeof(double));      // phase per corner [rad]
 *     for (i = 0; i < m.nv; ++i) {                      // 10 % stretch, width pulled in mid-span
 *         double u = m.pos[3 * i], v = m.pos[3 * i + 1] - 0.05;
 *         x[3 * i] = 1.1 * u;  x[3 * i + 1] = 0.05 + v * (1.0 - 0.1 * sin(3.14159265 * u / 0.25));  x[3 * i + 2] = 0.0;
 *     }
 *     mat.young = 1e6; mat.poisson = 0.5; mat.thickness = 1e-4;     // E [Pa], ν, h [m]
 *     if (wr_wf_create(&wf, &m, x, &mat, &d) != WR_OK) { puts(d.message); return 1; }
 *     wr_wf_classify(&wf, NULL);                                     // W (Sec. 5.1)
 *     if (wr_wf_init(&wf, NULL, a, omega, &d) != WR_OK) { puts(d.message); return 1; }   // App. E.2
 *     st = wr_wf_solve(&wf, NULL, a, omega, &ss, &d);                // App. E.3 (SQP)
 *     if (st != WR_OK && st != WR_ERR_NOT_CONVERGED) { puts(d.message); return 1; }   // best iterate kept
 *     if (wr_wf_phase(&wf, omega, phi, NULL, &d) != WR_OK) { puts(d.message); return 1; }  // App. E.4
 *     memset(&ud, 0, sizeof ud);  ud.levels = 2;
 *     if (wr_wf_upsample(&wf, a, phi, &ud, &fine, NULL, &d) != WR_OK) { puts(d.message); return 1; }  // Eq. 19
 *     printf("SQP %d iterations; wrinkled mesh %d vertices\n", ss.iterations, fine.nv);
 *     wr_mesh_free(&fine);  wr_wf_free(&wf);  wr_mesh_free(&m);
 *     wr_free(x);  wr_free(a);  wr_free(omega);  wr_free(phi);
 *
 * ON CHARTS AND UNITS
 *   Every face works in its own barycentric chart (s, t): r = r0 + s (r1 - r0) + t (r2 - r0), as in
 *   TFW App. A. I_u is built from the rest corners (wr_mesh_face_rest), I_b from base_pos [m].
 *   a [m] lives on vertices (piecewise linear); omega [rad] on edges: omega[e] is the phase change
 *   from edges[2e] to edges[2e+1] (docs/CONVENTIONS.md). In a chart, dφ = (ω_01, ω_02) and
 *   da = (a1 - a0, a2 - a0). The global unknown vector of wr_wf_energy is x = (a[0..nv), ω[0..ne)).
 *   Material: young E [Pa], poisson ν, thickness h [m]; Lamé α = Eν/(1-ν²), β = E/(2(1+ν)) (Eq. 33).
 *
 * ON READINGS OF THE PAPER (the text extraction is garbled in places)
 *   - Prefactors: Eq. 20 and 26 (h/4 and h³/12 without the 1/2 of Eq. 1 and 37). With
 *     ||M||²_SV = α/2 tr²M + β tr M² and M = I_u⁻¹I - id = 2ε this is the usual StVK plate energy
 *     h(α/2 tr²ε + β tr ε²); the extra 1/2 would halve E_wf and not move its minimiser.
 *   - W_s^2 (Eq. 22) = 4 a² κ⊥² β(α+β)/(α+2β) ((w⊥ᵀI_b w⊥)/(w⊥ᵀI_u w⊥))², κ⊥ = w⊥ᵀII_b w⊥ / w⊥ᵀI_b w⊥;
 *     w from Eq. 29 (most negative generalised eigenvalue), w⊥ its I_u-orthogonal partner (= the
 *     other generalised eigenvector). W_s^2 = 0 where neither eigenvalue is negative (Sec. 4.2).
 *     κ⊥ uses the App. A mid-edge-normal II_b, constant per face, by default; the paper's quadric
 *     fitting (Panozzo et al. 2010), as the authors' release builds it, is wr_wf_set_kappa(wf,
 *     WR_WF_KAPPA_VERTEX_FIT) (docs/notes-tfw-release.md has the comparison); either is fixed during
 *     the solve as in App. E.3. The other places where the release departs from the printed text
 *     are options too: its W rule (wr_wf_classify_desc.rule) and its start's scale
 *     (wr_wf_init_desc.rule); every other term is the release's (docs/notes-tfw-authors.md).
 *   - W_b^1 = ||I_u⁻¹ II_b||²_SV (rest-flat: II_u = 0) is a constant of the base; it is included in
 *     E and in terms[] but has no gradient.
 *   - dφ per face: the face average of the Whitney interpolant of ω, dφ = Σ_ij ω_ij (dλ_j - dλ_i)/3.
 *     It is symmetric in the three edges, linear in ω and equals the exact dφ when dω_f = 0 (where
 *     the paper uses "the first two equations"); so the energy stays well defined off the
 *     constraint set (W faces are excluded from E anyway, Eq. 37).
 *   - Quadrature: the symmetric three-point rule with barycentric points (2/3,1/6,1/6) and
 *     permutations, weights area/3 (exact for quadratics); a is linear, dφ and da constant per face.
 *   - Faces in W contribute nothing (Eq. 37). Their vertices have a = 0 ("force a = 0 on W", Sec.
 *     5.1), and edges touching no face outside W carry no energy and are left untouched.
 *
 * ON THE SQP SOLVER (App. E.3)
 *   Unknowns after eliminating dω = 0: y = (free a, z), ω = Z z. Per iteration one sparse Cholesky of
 *   (PᵀH P + μ M) restricted to the free set, H the per-face Hessians (SPD-projected or true, see
 *   wr_wf_hessian; AUTO = the paper's switch, at a relative KKT of 1e-2 instead of its ΔE < 1e-8),
 *   M = max(|diag|, 1e-2 · block mean), μ adapted from ρ = actual/predicted decrease (Nielsen's rule)
 *   instead of a Moré–Thuente line search; bounds by a projected-Newton ε-active set (ε = 1e-3 a_ref).
 *   KKT residual: see wr__wf_kkt — nondimensional (a / a_ref, E / E_ref), so its relative tolerance
 *   means the same on every case.
 *   a = 0 is a KKT point wherever it holds (E is even in a): before stopping on KKT the solver tries
 *   a second-order escape along the amplitudes whose faces see compression (wr__wf_escape); this is
 *   what lets wrinkles reappear after the E.2 guess collapses to 0 (the paper's video notes describe
 *   the same), and what lets a flat stop on an unstructured base wrinkle.
 *   Cost per iteration: per face the energy is 3 α0 + α2 M2 + α4 M4 (coefficients in da, dφ; M2, M4
 *   the quadrature moments of a; see wr__wf_face_eval_fast), Q of Eq. 4 is cached per face
 *   (wf->qf); the reduced Hessian is assembled through sparse.h's assembly cache (wr_assembly: the
 *   pattern and each face block's offsets recorded once per solve) and its symbolic Cholesky is
 *   built once per solve; a face block that passes a 6×6 Cholesky skips the eigen-projection (it is
 *   its own projection).
 *   Termination vs App. E.3: the paper stops on (1) |ΔE| < 1e-10, (2) stationarity < 1e-6, (3) update
 *   < 1e-10, (4) 1000 iterations, absolute numbers in its (SI) units. Rule 1 here is relative,
 *   |ΔE| <= 1e-10 |E_wf| on a step with ρ > 1/2, never looser than the absolute reading on the
 *   kit's cases (docs/notes-tfw-solver.md has the comparison). Below round-off (predicted decrease
 *   <= 1e-14 |E|) E - Et is noise, so such a step is taken iff it lowers the KKT residual, else
 *   rule 1 stops.
 *   omega_reg (default 0 = the paper's energy) adds a tiny Tikhonov term on ω; it is not needed for
 *   convergence and changes the solution, so it is off unless asked for.
 *   negative_curvature (default 0 = off) replaces the μ raise after a failed factorisation of the
 *   true Hessian by a Moré–Sorensen-type step along a direction of negative curvature (see ON
 *   NEGATIVE CURVATURE at wr__wf_sqp_negcurv; its figures: docs/notes-tfw-solver.md).
 *
 * ON CLAMPED EDGES AND PHASE FOLDS
 *   wr_wf_set_amplitude_zero holds a = 0 on given vertices: a clamp keeps the sheet in the base
 *   surface, so Eq. 19's a cos φ n̂ must vanish there. The paper states no such condition; without it
 *   a clamped edge under TFT compression keeps a finite amplitude along the whole wrinkle, nothing
 *   opposes W_b^2 but W_s^3/W_s^4, and the wavelength grows (figures: docs/notes-tfw-solver.md,
 *   "Clamps and phase folds"). With it, the crest-tension part of W_s^1 (½ daᵀda along the
 *   tension) against W_b^2 reproduces Cerda & Mahadevan's k⁴ = T∫a'²/(D∫a²) to 0.2 % (tests).
 *   E_wf is even in dφ face by face, so a curl-free ω may zig-zag (dφ reversing between neighbouring
 *   faces) at no cost; near 2 edges per wavelength the SQP does end in such states (same notes).
 *   wr_wf_count_folds finds them, wr_wf_unfold re-orients dφ (breadth-first from the largest
 *   amplitude) and projects to dω = 0; tfw.h then solves again from there.
 *
 * ON SEWN BASES (corner_rest and face_panel through the upsampling)
 *   A welded multi-panel base (mesh.h ON SEWING) has rest coordinates per face corner only: a seam
 *   vertex has one pattern position in each panel, and the panels' charts may overlap in the rest
 *   plane (a skirt's front and back over the same rectangle). wr_wf_upsample carries both to the
 *   wrinkled mesh, so rest-domain probes (spectrum.h, with a panel mask) can sample it:
 *   - face_panel: a child face is its parent's panel (after L levels fine face F descends from
 *     coarse face F >> 2L).
 *   - corner_rest: a child corner that is a parent corner keeps the parent's rest corner, one on a
 *     parent edge gets the midpoint of that edge's two rest corners IN THE PARENT'S CHART. This is
 *     the linear (midpoint) rule, not Loop's: the rest map of a face is affine (TFW App. A charts),
 *     so the midpoint is exact for it, and a per-face rule never averages corners of two panels
 *     across a seam, which Loop's stencils (neighbouring faces, other charts) would. Per-vertex rest
 *     (when present) is still Loop-subdivided as before; with corner_rest present that one wins for
 *     the rest metric (mesh.h). The fine positions are Loop's, so a rest point maps to a fine 3D
 *     point that differs from the linear image by the Loop smoothing, O(h²) of the base's faces.
 *
 * ON THREADS
 *   No global state; a wr_wf is read-only after classify/set, so concurrent energy calls are fine.
 */
#ifndef WRINKLE_WRINKLE_FIELD_H
#define WRINKLE_WRINKLE_FIELD_H

#include "core.h"
#include "mesh.h"
#include "sparse.h"
#include "spd.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct wr_wf_material {
    double young;     /* E [Pa] > 0 */
    double poisson;   /* ν in [0, 0.5] for the plane-stress Lamé formulas of Eq. 33 (< 1 required) */
    double thickness; /* h [m] > 0 */
} wr_wf_material;

/* Indices into the terms[] breakdown of wr_wf_energy (each already multiplied by its h/4 or h³/12
 * prefactor and integrated). */
enum { WR_WF_TERM_S1 = 0, WR_WF_TERM_S2, WR_WF_TERM_S3, WR_WF_TERM_S4, WR_WF_TERM_B1, WR_WF_TERM_B2, WR_WF_NTERMS };

typedef struct wr_wf {
    const wr_mesh *mesh;     /* borrowed; must outlive the wr_wf */
    int32_t nv, ne, nf;
    double alpha, beta, h;   /* Lamé parameters [Pa] (Eq. 33), thickness [m] */
    double *base;            /* nv*3 copy of the base positions [m] */
    double *iu, *iu_inv;     /* nf*3: (00, 01, 11) of I_u and I_u⁻¹ in the face chart */
    double *ib, *iib;        /* nf*3: I_b and II_b (App. A, mid-edge normals) in the face chart */
    double *area;            /* nf rest areas [m²] */
    double *lambda;          /* nf*2 ascending eigenvalues of (I_b - I_u) w = λ I_u w (Eq. 29) */
    double *wdir;            /* nf*2 chart vector w of lambda[0], ||w||_{I_u} = 1 */
    double *wperp;           /* nf*2 chart vector w⊥ of lambda[1], ||w⊥||_{I_u} = 1 */
    double *kperp;           /* nf κ⊥ [1/m] */
    double *c2;              /* nf: W_s^2 = c2 a² (0 where lambda[0] >= 0) [1/m²] */
    double *wb1;             /* nf: W_b^1 density ||I_u⁻¹ II_b||²_SV [Pa/m²] */
    double *qf;              /* nf*9: Q of ||I_u⁻¹ S||²_SV = sᵀQs (Eq. 4), a constant of the rest face */
    uint8_t *wfree;          /* nf: 1 = face in the wrinkle-free set W */
    uint8_t *azero;          /* nv: 1 = amplitude held at 0 (clamped boundary, see wr_wf_set_amplitude_zero) */
    int reference_eval;      /* nonzero: wr_wf_energy uses the generic monomial evaluator (the slow, literal
                              * transcription of Eq. 20–27 that the hand-expanded default is tested against) */
} wr_wf;

WRDEF wr_status wr_wf_create(wr_wf *wf, const wr_mesh *m, const double *base_pos, const wr_wf_material *mat,
                             wr_diag *diag);
WRDEF void wr_wf_free(wr_wf *wf);

/* The default compress_tol below (tfw.h counts strain states with the same threshold). */
#define WR_WF_COMPRESS_TOL_DEFAULT 1e-10
/* How W is chosen (wr_wf_classify).
 *   WR_WF_WSET_PAPER (default): Sec. 5.1 as printed: each face's most negative Eq. 29 eigenvalue
 *     averaged with its (up to three) edge neighbours', non-negative average -> W; then one
 *     simultaneous filter pass: a W face none of whose neighbours is in W leaves W; a non-W face all
 *     of whose neighbours (at least one) are in W joins W.
 *   WR_WF_WSET_RELEASE: the authors' release: a face is in W when its own most negative eigenvalue is
 *     non-negative (no averaging); then one pass in which a face outside W whose three vertices all
 *     lie on W faces joins W (it fills one-face holes; nothing leaves W). */
typedef enum wr_wf_wset_rule { WR_WF_WSET_PAPER = 0, WR_WF_WSET_RELEASE = 1 } wr_wf_wset_rule;
/* Defaults: compress_tol = 1e-10 (strain; a face counts as compressed when its (smoothed) most
 * negative Eq. 29 eigenvalue is < -compress_tol, so round-off on an unstrained sheet is "tension");
 * rule = WR_WF_WSET_PAPER. */
typedef struct wr_wf_classify_desc {
    double compress_tol;
    int no_outlier_filter; /* nonzero: skip the Sec. 5.1 outlier filter (for tests; PAPER rule only) */
    wr_wf_wset_rule rule;
} wr_wf_classify_desc;
/* Sets wf->wfree by desc->rule (above) and returns |W|, or -1 for an unknown rule (wfree then
 * untouched). desc may be NULL. */
WRDEF int32_t wr_wf_classify(wr_wf *wf, const wr_wf_classify_desc *desc);
WRDEF void wr_wf_set_wrinkle_free(wr_wf *wf, const uint8_t *flags /* nf or NULL */);
/* Hold a = 0 on the flagged vertices (nv flags, NULL = none) in init, solve and upsampling: the
 * boundary condition of a clamped edge, where the out-of-plane displacement a cos φ of Eq. 19 must
 * vanish (the clamp holds the sheet in the base surface). Faces keep their energy and curl constraint. */
WRDEF void wr_wf_set_amplitude_zero(wr_wf *wf, const uint8_t *vflags);

/* κ⊥ of Eq. 22 (ON READINGS OF THE PAPER): which curvature of the base along the crests w⊥.
 *   WR_WF_KAPPA_MIDEDGE (default): w⊥ᵀ II_b w⊥ / w⊥ᵀ I_b w⊥ with the App. A mid-edge II_b, constant
 *     per face; W_s^2 wherever the face is compressed (λ0 < 0).
 *   WR_WF_KAPPA_VERTEX_FIT: the normal curvature along w⊥ from per-vertex principal curvatures of a
 *     quadric fit over 5-rings (Panozzo et al. 2010, which the paper cites; wr_mesh_vertex_curvature),
 *     by Euler's formula at each corner, averaged over the three corners; W_s^2 only on faces in mixed
 *     tension/compression (λ0 <= 0 <= λ1). This is how the authors' release builds the term. */
typedef enum wr_wf_kappa { WR_WF_KAPPA_MIDEDGE = 0, WR_WF_KAPPA_VERTEX_FIT = 1 } wr_wf_kappa;
/* Recompute κ⊥ and the W_s^2 coefficient of every face with the given reading. WR_ERR_INVALID_ARG
 * for an unknown reading, WR_ERR_NOMEM. */
WRDEF wr_status wr_wf_set_kappa(wr_wf *wf, wr_wf_kappa reading, wr_diag *diag);

/* E_wf of Eq. 20, 22–24, 26 summed over faces outside W (Eq. 37). a: nv [m], omega: ne [rad].
 * grad (nv+ne, or NULL): dE/dx for x = (a, ω). face_hess (nf*36, or NULL): per face the 6×6 Hessian
 * in the local order of wr_wf_face_dofs (zero for W faces). terms (WR_WF_NTERMS, or NULL).
 * WR_ERR_DOMAIN if a value is non-finite. */
WRDEF wr_status wr_wf_energy(const wr_wf *wf, const double *a, const double *omega, double *energy, double *grad,
                             double *face_hess, double *terms, wr_diag *diag);
/* Local DOFs of face f: (a at corners 0,1,2, ω of face edges 0,1,2) -> global index in x and sign
 * (+1 for a; face_edge_sign for ω, the local unknown is sign·ω = phase change along the face). */
WRDEF void wr_wf_face_dofs(const wr_wf *wf, int32_t f, int32_t idx[6], double sign[6]);
WRDEF void wr_wf_curl(const wr_mesh *m, const double *omega, double *curl /* nf */);

/* Replace omega by the nearest (least squares over edges of faces outside W) one-form with dω = 0 on
 * every face outside W; edges touching only W faces are unchanged. */
WRDEF wr_status wr_wf_project_closed(const wr_wf *wf, double *omega, wr_diag *diag);

/* App. E.2. Defaults: k = min(0.01 m, 0.1 · base bounding-box diagonal) (the paper's constant).
 * a_v = mean over incident faces of k·sqrt(2 ε_w) with ε_w = -lambda[0] (0 where lambda[0] >= 0, and
 * 0 on W vertices); per face outside W with ε_w > 0 the target dφ has direction I_u w and
 * ||dφ||_{I_u⁻¹} = 1/k (Eq. 8 with a = k sqrt(2ε)); the edge target is the mean of its faces' targets
 * (w oriented consistently by a breadth-first sweep over the dual graph), then projected to dω = 0.
 * rule = WR_WF_INIT_RELEASE scales as the authors' release does instead (when k is 0): the largest
 * face amplitude is A0 = min(0.01 · (largest - smallest base coordinate over x, y and z together),
 * 0.1 · largest bounding-box side), i.e. k = A0 / (max_f sqrt(2 ε_w) + 1e-6), and the vertex
 * amplitudes are then smoothed twice (every vertex with a > 0 takes the mean of its edge
 * neighbours' a; vertices at a = 0 stay). */
typedef enum wr_wf_init_rule { WR_WF_INIT_PAPER = 0, WR_WF_INIT_RELEASE = 1 } wr_wf_init_rule;
typedef struct wr_wf_init_desc {
    double k; /* [m] */
    wr_wf_init_rule rule;
} wr_wf_init_desc;
WRDEF wr_status wr_wf_init(const wr_wf *wf, const wr_wf_init_desc *desc, double *a, double *omega, wr_diag *diag);

typedef enum wr_wf_stop {
    WR_WF_STOP_NONE = 0,
    WR_WF_STOP_ENERGY,     /* rule 1: |ΔE| <= tol_energy · |E| on a well-modelled step (ρ > 1/2) */
    WR_WF_STOP_KKT,        /* rule 2: scaled stationarity residual <= tol_kkt · initial residual */
    WR_WF_STOP_STEP,       /* rule 3: step <= tol_step · |x| (per block: a and ω), ρ > 1/2 */
    WR_WF_STOP_MAX_ITER,   /* rule 4 (WR_ERR_NOT_CONVERGED) */
    WR_WF_STOP_LINE_SEARCH /* no acceptable step even with damping μ > 1e12 (WR_ERR_NOT_CONVERGED) */
} wr_wf_stop;

/* App. E.3 Hessian strategy. PROJECTED: per-face SPD projection throughout (robust far from the
 * solution, but only linearly convergent where the true Hessian has negative face blocks that the
 * global Hessian does not); TRUE: exact Hessian throughout, indefiniteness handled by the damping;
 * AUTO: projected until the relative KKT residual drops below hessian_switch, then true. */
typedef enum wr_wf_hessian {
    WR_WF_HESSIAN_AUTO = 0,
    WR_WF_HESSIAN_PROJECTED,
    WR_WF_HESSIAN_TRUE
} wr_wf_hessian;

typedef struct wr_wf_iter_info {
    int32_t iteration;
    double energy;   /* after the step [J] */
    double kkt;      /* scaled stationarity residual before the step (see wr_wf_solve_stats) */
    double step;     /* max |Δa|/a_ref, |Δz| [rad] */
    double alpha_ls; /* ρ = actual / predicted decrease of the accepted step */
    double shift;    /* Marquardt damping μ after the step (relative to |diag K|) */
    int32_t n_active;   /* amplitudes held at the bound a = 0 */
    int32_t n_rejected; /* trial steps rejected in this iteration */
    int32_t true_hessian;
    /* negative_curvature option (ON NEGATIVE CURVATURE): 1 when the accepted step holds a direction
     * of negative curvature p; curvature = pᵀKp / pᵀMp (< 0) of that p, nc_gain = the step's model
     * decrease minus that of the same step with p reversed (≥ 0: the sign the model prefers) */
    int32_t negcurv;
    double curvature, nc_gain;
} wr_wf_iter_info;

/* Defaults (App. E.3, applied relative where the paper's absolute numbers have no units):
 *   max_iter 1000, tol_energy 1e-10, tol_kkt 1e-8, tol_step 1e-10, hessian AUTO with
 *   hessian_switch 1e-2, solver: WR_SOLVER_AUTO (spd.h), negative_curvature 0 (off: a failed
 *   factorisation raises μ), progress: none. */
typedef struct wr_wf_solve_desc {
    int32_t max_iter;
    double tol_energy, tol_kkt, tol_step;
    wr_solver_method solver;
    wr_wf_hessian hessian;
    double hessian_switch; /* relative KKT below which AUTO switches to the true Hessian */
    double omega_reg;      /* ≥ 0: adds (γ/2) Σ ω_e², γ = omega_reg · E_ref / #edges (see ON THE SQP SOLVER) */
    int32_t negative_curvature; /* 0: off; 1: Moré–Sorensen-type step on an indefinite true Hessian (ON NEGATIVE CURVATURE) */
    void (*progress)(const wr_wf_iter_info *info, void *user); /* called once per accepted step */
    void *user;
} wr_wf_solve_desc;

typedef struct wr_wf_solve_stats {
    int32_t iterations;     /* accepted steps */
    int32_t n_rejected;     /* rejected trial steps (each cost one energy and, but for a Δ_nc cut of the
                             * negative_curvature option, one factorisation) */
    int32_t n_factorizations;
    int32_t n_escapes;      /* second-order escapes from stationary a = 0 (see wr__wf_escape) */
    int32_t n_negcurv;      /* accepted steps along a direction of negative curvature (negative_curvature option) */
    int32_t switch_iteration; /* first iteration with the true Hessian, -1 if never */
    int32_t n_vars;         /* reduced unknowns: free amplitudes + closed-form coordinates */
    int32_t n_generators;   /* cohomology generators of the complex outside W */
    double energy0, energy; /* objective (E_wf + regulariser) at the start and at the end [J] */
    double energy_reg;      /* the regulariser's share of energy at the end [J] (0 without omega_reg) */
    double kkt0, kkt;       /* kkt0: at the start, or after an escape from a = 0 if larger; ||ŷ - P(ŷ - ĝ)||_∞, ŷ = y/s, ĝ = s ∇E / E_ref (stationarity of Eq. 39) */
    double a_ref, e_ref;    /* scales used: a_ref = max a at the start [m], E_ref = |E| at the start [J] */
    double seconds, seconds_assembly, seconds_solve;
    wr_wf_stop stop;
} wr_wf_solve_stats;

/* App. E.3: min E_wf s.t. a >= 0, dω = 0 on faces outside W. omega is first projected to dω = 0 and a
 * clipped to >= 0 (a = 0 on W vertices). The curl constraints are eliminated exactly by a null-space
 * parametrisation ω = d0 ψ + Σ c_g h_g (tree–cotree over the complex outside W), the bounds by a
 * projected-Newton ε-active set; each iteration solves (K + μ M) d = -g (one sparse Cholesky), with
 * K the reduced Hessian (per-face SPD projection or true, see wr_wf_hessian), M = max(|diag K|,
 * floor) and μ adapted from the ratio of actual to predicted decrease (Levenberg–Marquardt trust
 * region), so every iterate is feasible and the step turns into full Newton near the solution.
 * See ON THE SQP SOLVER. */
WRDEF wr_status wr_wf_solve(const wr_wf *wf, const wr_wf_solve_desc *desc, double *a, double *omega,
                            wr_wf_solve_stats *stats, wr_diag *diag);

/* Phase folds. E_wf depends on dφ only through dφᵀdφ and (dφᵀda + daᵀdφ)² (Eq. 21–26): flipping the
 * sign of dφ on a patch of faces costs nothing but the mismatch on the patch border, and at ~2 base
 * edges per wavelength a curl-free ω that zig-zags (φ = 0, 2.9, 0, 2.9, ... along the wave vector)
 * has the same discrete energy as the monotone one. The continuum model forbids it (dφ is a slow
 * variable, Sec. 3.3), and the visualised surface (Loop-smoothed φ, Eq. 19) is wrong where it happens.
 * A fold edge: interior edge whose two faces (outside W) both have mean a >= 0.2 max a and whose dφ
 * (pushed to the base surface) point in opposite directions (dot < 0). Returns the count. */
WRDEF int32_t wr_wf_count_folds(const wr_wf *wf, const double *a, const double *omega);
/* Orient dφ consistently: per face outside W the Whitney dφ; a breadth-first sweep over the dual graph
 * (outside W) from the face of largest amplitude, visiting through the edge between faces, flips a
 * face's dφ when it points against its parent's; edge targets = mean of the adjacent faces' oriented
 * phase changes; then the least-squares projection to dω = 0 (wr_wf_project_closed). |dφ| per face is
 * kept where the faces agreed; the result is a start for another wr_wf_solve. */
WRDEF wr_status wr_wf_unfold(const wr_wf *wf, const double *a, double *omega, wr_diag *diag);

typedef struct wr_wf_phase_stats {
    int32_t n_cut_edges;      /* interior edges (outside W) across which the corner phases jump */
    int32_t n_nonzero_jumps;  /* of those, jumps by a nonzero multiple of 2π */
    int32_t n_conflicts;      /* rounded jumps inconsistent around a loop (left open: singular) */
    double max_residual;      /* max over face edges |φ_end - φ_start - ω| after the solve [rad] */
} wr_wf_phase_stats;
/* App. E.4. phi: nf*3 per-face-corner phase [rad] (W faces get 0). Algorithm: integrate ω along a
 * spanning tree of the dual graph outside W (cut to a disk per component), round every jump across
 * the remaining interior edges to a multiple of 2π, glue corners with those jumps (weighted
 * union-find), and solve min Σ (φ_end - φ_start - ω)² over the glued corner classes. stats may be NULL. */
WRDEF wr_status wr_wf_phase(const wr_wf *wf, const double *omega, double *phi, wr_wf_phase_stats *stats,
                            wr_diag *diag);

/* Loop subdivision. Default boundary: WR_WF_LOOP_BOUNDARY_FIXED keeps the boundary polygon (even
 * boundary vertices stay, odd ones at edge midpoints), so clamped outlines do not shrink;
 * WR_WF_LOOP_BOUNDARY_SPLINE uses Loop's cubic B-spline boundary rule (1/8, 3/4, 1/8). */
enum { WR_WF_LOOP_BOUNDARY_FIXED = 0, WR_WF_LOOP_BOUNDARY_SPLINE = 1 };
typedef struct wr_wf_loop_desc {
    int boundary;
} wr_wf_loop_desc;
/* One Loop step of ncomp per-vertex fields vals (nv*ncomp). Fine vertex v < nv is coarse vertex v
 * (even), nv + e the point on coarse edge e (odd); fine face 4f+c (c < 3) is the corner-c child of f,
 * 4f+3 the middle child. *fine_faces (4nf*3) and *fine_vals ((nv+ne)*ncomp) are allocated here; free
 * with wr_free. Interior even weight β = (1/n)(5/8 - (3/8 + cos(2π/n)/4)²) (Loop 1987). */
WRDEF wr_status wr_wf_loop_step(const wr_mesh *m, int32_t ncomp, const double *vals, const wr_wf_loop_desc *desc,
                                int32_t **fine_faces, double **fine_vals, wr_diag *diag);
/* One Loop step of per-corner rest coordinates (mesh.h corner_rest, nf*6 [m]) into fine (4nf*6),
 * child faces numbered and cornered as wr_wf_loop_step's (ON SEWN BASES): a child's corners are its
 * parent's corners and the midpoints of the parent's edges, taken in the parent's own chart. */
WRDEF void wr_wf_loop_corner_rest(int32_t nf, const double *corner_rest, double *fine);

/* Defaults: levels = 2, boundary FIXED, no_inplane = 0 (the v2 term of Eq. 19 is on). */
typedef struct wr_wf_upsample_desc {
    int32_t levels;
    int boundary;
    int no_inplane; /* nonzero: normal displacement only (TFW Fig. 5 ablation) */
} wr_wf_upsample_desc;
/* App. E.5: Loop-subdivide the base mesh, a and the per-corner phase (differences taken inside one
 * sheet, so 2π jumps never enter a stencil; faces in W keep a = 0 at vertices touching only W), then
 * displace by Eq. 19 without the v1 term: r = r_b + a cos φ n̂_b + (a²/8) sin 2φ ∇_b φ. out: the
 * wrinkled mesh (rest = subdivided rest when the input has rest coordinates; corner_rest = the base's
 * corner_rest split by wr_wf_loop_corner_rest at every level when the input has one; face_panel =
 * the coarse face's panel when the input has one: ON SEWN BASES). out_a (or NULL): *out_a = fine
 * amplitudes (out->nv), free with wr_free. */
WRDEF wr_status wr_wf_upsample(const wr_wf *wf, const double *a, const double *phi, const wr_wf_upsample_desc *desc,
                               wr_mesh *out, double **out_a, wr_diag *diag);

/* The fine level's fields, one value per vertex of the wrinkled mesh (out->nv), for viewers and
 * probes: a [m] the amplitude used in Eq. 19, phase [rad] the φ used there wrapped to (-π, π] (on the
 * fine mesh φ is per face corner and multivalued by 2π; the displacement needs only cos φ and sin 2φ,
 * so one wrapped value per vertex is exact for it), wfree 1 on vertices touching only faces of W
 * (there a = 0 and phase = 0). So r = r_b + a cos(phase) n̂_b (+ the in-plane term) vertex by vertex. */
typedef struct wr_wf_fine_fields {
    int32_t nv;
    double *a, *phase;
    uint8_t *wfree;
} wr_wf_fine_fields;
/* wr_wf_upsample, with the fine fields in *fields (allocated here; free with wr_wf_fine_fields_free,
 * which also accepts a zeroed struct). On failure *fields is zeroed. */
WRDEF wr_status wr_wf_upsample_fields(const wr_wf *wf, const double *a, const double *phi,
                                      const wr_wf_upsample_desc *desc, wr_mesh *out, wr_wf_fine_fields *fields,
                                      wr_diag *diag);
WRDEF void wr_wf_fine_fields_free(wr_wf_fine_fields *fields);

#ifdef __cplusplus
}
#endif
#endif /* WRINKLE_WRINKLE_FIELD_H */

/* ============================================================================================ */
#ifdef WRINKLE_IMPLEMENTATION
#ifndef WRINKLE_WRINKLE_FIELD_IMPLEMENTATION_DONE
#define WRINKLE_WRINKLE_FIELD_IMPLEMENTATION_DONE

#include <math.h>
#include <string.h>

#ifdef __cplusplus
extern "C" {
#endif

#define WR__WF_PI 3.14159265358979323846
/* Default tolerances (see the desc comments for their source). */
#define WR__WF_COMPRESS_TOL WR_WF_COMPRESS_TOL_DEFAULT
#define WR__WF_K_MAX 0.01         /* [m] App. E.2: k = min(0.01, 0.1 bbox) */
#define WR__WF_MAX_ITER 1000      /* App. E.3 rule 4 */
#define WR__WF_TOL_ENERGY 1e-10   /* App. E.3 rule 1 */
#define WR__WF_TOL_KKT 1e-8       /* App. E.3 rule 2 (relative to the initial residual) */
#define WR__WF_TOL_STEP 1e-10     /* App. E.3 rule 3 */
#define WR__WF_HESSIAN_SWITCH 1e-2 /* AUTO: true Hessian once KKT <= 1e-2 · KKT0 (App. E.3 "near convergence") */
#define WR__WF_MU0 1e-4           /* initial Marquardt damping μ (relative to |diag K|) */
#define WR__WF_MU_MIN 1e-12       /* μ floor: keeps K + μM nonsingular in directions E does not see */
#define WR__WF_MU_MAX 1e12        /* μ beyond which the step is negligible: stop (line-search rule) */
#define WR__WF_MU_UP 10.0         /* μ growth after a failed (non-SPD) factorisation */
#define WR__WF_RHO_ACCEPT 1e-4    /* accept a step when actual/predicted decrease > this */
/* Damping diagonal floor, relative to the block's mean |diag K|. It is the trust radius of the
 * directions E_wf barely sees (ω on faces where a ~ 0): with 1e-6 those coordinates jumped by 20+ rad
 * per step and spoiled the next model (stretched sheet, 522 vertices: 134 accepted + 67 rejected steps
 * to the same energy that 1e-2 reaches in 46 + 28; unit-test cases unchanged). */
#ifndef WR__WF_DAMP_FLOOR
#define WR__WF_DAMP_FLOOR 1e-2
#endif
#define WR__WF_EPS_ACTIVE 1e-3    /* ε of the ε-active set, in units of a_ref: a <= ε a_ref with ∂E/∂a > 0 is put on the bound */
#define WR__WF_ROUNDOFF 1e-14     /* predicted decrease below this × |E| is below double round-off of E */
#define WR__WF_ROUNDOFF_FLOOR 1e-6 /* ... of at least 1e-6 |E_wf(start)| (excess energy can be ~0) */
#define WR__WF_MAX_ESCAPES 50     /* second-order escapes from a = 0 per solve */
#define WR__WF_AREF_FALLBACK 1e-3 /* a_ref = 1e-3 × bbox diagonal when the start has a = 0 everywhere */
#define WR__WF_NC_LANCZOS 20      /* shift-invert Lanczos steps for the negative-curvature direction */
#define WR__WF_NC_SEED 0x5eedULL  /* their (fixed) random start */
#define WR__WF_NC_CUTS 4          /* Δ_nc cuts per iteration before the trial counts as rejected */
#define WR__WF_NC_FLOOR 1e-2      /* Δ_nc >= this × ‖s(σ)‖_M (ON NEGATIVE CURVATURE) */

/* Barycentric quadrature points (λ0, λ1, λ2), weight 1/3 each: symmetric degree-2 rule. */
static const double wr__wf_qp[3][3] = {
    {2.0 / 3.0, 1.0 / 6.0, 1.0 / 6.0}, {1.0 / 6.0, 2.0 / 3.0, 1.0 / 6.0}, {1.0 / 6.0, 1.0 / 6.0, 2.0 / 3.0}};

/* ---- small symmetric 2×2 helpers: s = (s00, s01, s11) ---- */
static void wr__wf_sym_to_m2(const double s[3], double M[2][2]) {
    M[0][0] = s[0];
    M[0][1] = M[1][0] = s[1];
    M[1][1] = s[2];
}

/* Q (3×3, row-major) such that ||I_u⁻¹ S||²_SV = sᵀ Q s for S = sym(s), Eq. 4:
 * ||M||²_SV = α/2 tr²(M) + β tr(M²). Built by polarisation on the basis E00, E01 + E10, E11. */
static void wr__wf_qform(const double binv[3], double alpha, double beta, double Q[9]) {
    double E[3][2][2], BE[3][2][2], B[2][2], tr[3];
    int a, b, i, j, k;
    wr__wf_sym_to_m2(binv, B);
    memset(E, 0, sizeof E);
    E[0][0][0] = 1.0;
    E[1][0][1] = E[1][1][0] = 1.0;
    E[2][1][1] = 1.0;
    for (a = 0; a < 3; ++a) {
        for (i = 0; i < 2; ++i)
            for (j = 0; j < 2; ++j) {
                double s = 0.0;
                for (k = 0; k < 2; ++k) s += B[i][k] * E[a][k][j];
                BE[a][i][j] = s;
            }
        tr[a] = BE[a][0][0] + BE[a][1][1];
    }
    for (a = 0; a < 3; ++a)
        for (b = 0; b < 3; ++b) {
            double t2 = 0.0;
            for (i = 0; i < 2; ++i)
                for (k = 0; k < 2; ++k) t2 += BE[a][i][k] * BE[b][k][i];
            Q[3 * a + b] = 0.5 * alpha * tr[a] * tr[b] + beta * t2;
        }
}

/* Monomial coef·Π y[ix[k]] (n <= 4 factors, repeats allowed): adds value, gradient (5) and Hessian
 * (5×5) by the product rule. */
static void wr__wf_mono(double coef, int n, const int *ix, const double *y, double *v, double *g, double *H) {
    int k, l, m;
    double p = coef;
    for (k = 0; k < n; ++k) p *= y[ix[k]];
    *v += p;
    for (k = 0; k < n; ++k) {
        double q = coef;
        for (m = 0; m < n; ++m)
            if (m != k) q *= y[ix[m]];
        g[ix[k]] += q;
        for (l = 0; l < n; ++l) {
            double r = coef;
            if (l == k) continue;
            for (m = 0; m < n; ++m)
                if (m != k && m != l) r *= y[ix[m]];
            H[5 * ix[k] + ix[l]] += r;
        }
    }
}

/* y = (a, g0, g1, p0, p1): amplitude at the point, da and dφ in the chart. */
enum { WR__Y_A = 0, WR__Y_G0, WR__Y_G1, WR__Y_P0, WR__Y_P1 };

/* Accumulate w·N(s(y)) with N(s) = sᵀQs where each component of s is given by up to `nm` monomials.
 * s value/gradient/Hessian are built first, then the chain rule. */
typedef struct wr__wf_sfun {
    double v[3], g[3][5], H[3][25];
} wr__wf_sfun;

static void wr__wf_sfun_zero(wr__wf_sfun *s) { memset(s, 0, sizeof *s); }

/* off (or NULL): a constant added to s whose own N(off) is left out of the value (so the value is
 * N(off + s) - N(off) = 2 offᵀQs + sᵀQs, computed without cancellation); derivatives are those of
 * N(off + s). */
static void wr__wf_norm_acc(const wr__wf_sfun *s, const double *off, const double Q[9], double w, double *val,
                            double *g, double *H) {
    double Qs[3], Qo[3], QJ[3][5];
    int c, d, i, j;
    for (c = 0; c < 3; ++c) {
        Qs[c] = Qo[c] = 0.0;
        for (d = 0; d < 3; ++d) {
            Qs[c] += Q[3 * c + d] * s->v[d];
            if (off) Qo[c] += Q[3 * c + d] * off[d];
        }
    }
    *val += w * (s->v[0] * (Qs[0] + 2.0 * Qo[0]) + s->v[1] * (Qs[1] + 2.0 * Qo[1]) + s->v[2] * (Qs[2] + 2.0 * Qo[2]));
    for (c = 0; c < 3; ++c) Qs[c] += Qo[c]; /* Q (off + s) for the derivatives */
    if (!g) return;
    for (i = 0; i < 5; ++i) {
        double t = 0.0;
        for (c = 0; c < 3; ++c) t += s->g[c][i] * Qs[c];
        g[i] += 2.0 * w * t;
    }
    if (!H) return;
    for (c = 0; c < 3; ++c)
        for (i = 0; i < 5; ++i) {
            QJ[c][i] = 0.0;
            for (d = 0; d < 3; ++d) QJ[c][i] += Q[3 * c + d] * s->g[d][i];
        }
    for (i = 0; i < 5; ++i)
        for (j = 0; j < 5; ++j) {
            double t = 0.0;
            for (c = 0; c < 3; ++c) t += s->g[c][i] * QJ[c][j] + Qs[c] * s->H[c][5 * i + j];
            H[5 * i + j] += 2.0 * w * t;
        }
}

static void wr__wf_sfun_mono(wr__wf_sfun *s, int comp, double coef, int n, const int *ix, const double *y) {
    wr__wf_mono(coef, n, ix, y, &s->v[comp], s->g[comp], s->H[comp]);
}

/* Face energy in local DOFs xl = (a0, a1, a2, ω̃0, ω̃1, ω̃2), ω̃k = phase change along face edge k in the
 * face's traversal (corner (k+1)%3 -> (k+2)%3). Adds into e, g[6], H[36], terms[6] (each may be NULL
 * except e). */
static void wr__wf_face_eval(const wr_wf *wf, int32_t f, const double xl[6], int excess, double *e, double *g6,
                             double *H36, double *terms) {
    /* dφ (Whitney face average, see ON READINGS): p = (2ω̃2 - ω̃0 - ω̃1, ω̃2 + ω̃0 - 2ω̃1)/3. */
    static const double JP[2][3] = {{-1.0 / 3.0, -1.0 / 3.0, 2.0 / 3.0}, {1.0 / 3.0, -2.0 / 3.0, 1.0 / 3.0}};
    static const int ix_g00[2] = {WR__Y_G0, WR__Y_G0}, ix_g01[2] = {WR__Y_G0, WR__Y_G1},
                     ix_g11[2] = {WR__Y_G1, WR__Y_G1};
    static const int ix_aapp00[4] = {WR__Y_A, WR__Y_A, WR__Y_P0, WR__Y_P0},
                     ix_aapp01[4] = {WR__Y_A, WR__Y_A, WR__Y_P0, WR__Y_P1},
                     ix_aapp11[4] = {WR__Y_A, WR__Y_A, WR__Y_P1, WR__Y_P1};
    static const int ix_apg00[3] = {WR__Y_A, WR__Y_P0, WR__Y_G0}, ix_apg01a[3] = {WR__Y_A, WR__Y_P0, WR__Y_G1},
                     ix_apg01b[3] = {WR__Y_A, WR__Y_P1, WR__Y_G0}, ix_apg11[3] = {WR__Y_A, WR__Y_P1, WR__Y_G1};
    static const int ix_app00[3] = {WR__Y_A, WR__Y_P0, WR__Y_P0}, ix_app01[3] = {WR__Y_A, WR__Y_P0, WR__Y_P1},
                     ix_app11[3] = {WR__Y_A, WR__Y_P1, WR__Y_P1};
    static const int ix_aa[2] = {WR__Y_A, WR__Y_A};
    double Q[9], y[5], J[5][6], gy[5], Hy[25];
    double ws, wb, c[3];
    double inv32 = 1.0 / sqrt(32.0), inv8 = 1.0 / sqrt(8.0), inv2 = 1.0 / sqrt(2.0);
    int q, i, j, k, t;
    wr__wf_qform(wf->iu_inv + 3 * f, wf->alpha, wf->beta, Q);
    ws = wf->h / 4.0 * wf->area[f] / 3.0;                /* Eq. 20 prefactor × quadrature weight */
    wb = wf->h * wf->h * wf->h / 12.0 * wf->area[f] / 3.0; /* Eq. 26 */
    for (k = 0; k < 3; ++k) c[k] = wf->ib[3 * f + k] - wf->iu[3 * f + k];
    y[WR__Y_G0] = xl[1] - xl[0];
    y[WR__Y_G1] = xl[2] - xl[0];
    y[WR__Y_P0] = JP[0][0] * xl[3] + JP[0][1] * xl[4] + JP[0][2] * xl[5];
    y[WR__Y_P1] = JP[1][0] * xl[3] + JP[1][1] * xl[4] + JP[1][2] * xl[5];
    memset(J, 0, sizeof J);
    J[WR__Y_G0][0] = -1.0;
    J[WR__Y_G0][1] = 1.0;
    J[WR__Y_G1][0] = -1.0;
    J[WR__Y_G1][2] = 1.0;
    for (k = 0; k < 3; ++k) {
        J[WR__Y_P0][3 + k] = JP[0][k];
        J[WR__Y_P1][3 + k] = JP[1][k];
    }
    /* W_b^1: constant of the base (no a, ω dependence); left out of the excess energy. */
    if (!excess) {
        *e += 3.0 * wb * wf->wb1[f];
        if (terms) terms[WR_WF_TERM_B1] += 3.0 * wb * wf->wb1[f];
    }
    for (q = 0; q < 3; ++q) {
        wr__wf_sfun s;
        double vt;
        y[WR__Y_A] = wr__wf_qp[q][0] * xl[0] + wr__wf_qp[q][1] * xl[1] + wr__wf_qp[q][2] * xl[2];
        for (k = 0; k < 3; ++k) J[WR__Y_A][k] = wr__wf_qp[q][k];
        memset(gy, 0, sizeof gy);
        memset(Hy, 0, sizeof Hy);
        for (t = 0; t < 5; ++t) {
            vt = 0.0;
            wr__wf_sfun_zero(&s);
            switch (t) {
            case 0: /* W_s^1, Eq. 21: I_u⁻¹(I_b - I_u + ½ daᵀda + ½ a² dφᵀdφ) */
                if (!excess) {
                    s.v[0] = c[0];
                    s.v[1] = c[1];
                    s.v[2] = c[2];
                }
                wr__wf_sfun_mono(&s, 0, 0.5, 2, ix_g00, y);
                wr__wf_sfun_mono(&s, 1, 0.5, 2, ix_g01, y);
                wr__wf_sfun_mono(&s, 2, 0.5, 2, ix_g11, y);
                wr__wf_sfun_mono(&s, 0, 0.5, 4, ix_aapp00, y);
                wr__wf_sfun_mono(&s, 1, 0.5, 4, ix_aapp01, y);
                wr__wf_sfun_mono(&s, 2, 0.5, 4, ix_aapp11, y);
                wr__wf_norm_acc(&s, excess ? c : NULL, Q, ws, &vt, g6 ? gy : NULL, H36 ? Hy : NULL);
                break;
            case 1: /* W_s^3, Eq. 23: (a²/32)||I_u⁻¹(dφᵀda + daᵀdφ)||² = N((a/√32)(pᵀg + gᵀp)) */
                wr__wf_sfun_mono(&s, 0, 2.0 * inv32, 3, ix_apg00, y);
                wr__wf_sfun_mono(&s, 1, inv32, 3, ix_apg01a, y);
                wr__wf_sfun_mono(&s, 1, inv32, 3, ix_apg01b, y);
                wr__wf_sfun_mono(&s, 2, 2.0 * inv32, 3, ix_apg11, y);
                wr__wf_norm_acc(&s, NULL, Q, ws, &vt, g6 ? gy : NULL, H36 ? Hy : NULL);
                break;
            case 2: /* W_s^4, Eq. 24: (1/8)||I_u⁻¹ daᵀda||² */
                wr__wf_sfun_mono(&s, 0, inv8, 2, ix_g00, y);
                wr__wf_sfun_mono(&s, 1, inv8, 2, ix_g01, y);
                wr__wf_sfun_mono(&s, 2, inv8, 2, ix_g11, y);
                wr__wf_norm_acc(&s, NULL, Q, ws, &vt, g6 ? gy : NULL, H36 ? Hy : NULL);
                break;
            case 3: /* W_b^2, Eq. 26: (a²/2)||I_u⁻¹ dφᵀdφ||² */
                wr__wf_sfun_mono(&s, 0, inv2, 3, ix_app00, y);
                wr__wf_sfun_mono(&s, 1, inv2, 3, ix_app01, y);
                wr__wf_sfun_mono(&s, 2, inv2, 3, ix_app11, y);
                wr__wf_norm_acc(&s, NULL, Q, wb, &vt, g6 ? gy : NULL, H36 ? Hy : NULL);
                break;
            default: { /* W_s^2, Eq. 22: c2 a² */
                double dummy[5], dH[25];
                double v2 = 0.0;
                memset(dummy, 0, sizeof dummy);
                memset(dH, 0, sizeof dH);
                wr__wf_mono(ws * wf->c2[f], 2, ix_aa, y, &v2, dummy, dH);
                vt = v2;
                for (i = 0; i < 5; ++i) gy[i] += dummy[i];
                for (i = 0; i < 25; ++i) Hy[i] += dH[i];
            } break;
            }
            *e += vt;
            if (terms) {
                static const int slot[5] = {WR_WF_TERM_S1, WR_WF_TERM_S3, WR_WF_TERM_S4, WR_WF_TERM_B2, WR_WF_TERM_S2};
                terms[slot[t]] += vt;
            }
        }
        if (g6)
            for (i = 0; i < 6; ++i) {
                double s2 = 0.0;
                for (k = 0; k < 5; ++k) s2 += J[k][i] * gy[k];
                g6[i] += s2;
            }
        if (H36)
            for (i = 0; i < 6; ++i)
                for (j = 0; j < 6; ++j) {
                    double s2 = 0.0;
                    int l;
                    for (k = 0; k < 5; ++k) {
                        if (J[k][i] == 0.0) continue;
                        for (l = 0; l < 5; ++l) s2 += J[k][i] * Hy[5 * k + l] * J[l][j];
                    }
                    H36[6 * i + j] += s2;
                }
    }
}

WRDEF void wr_wf_free(wr_wf *wf) {
    if (!wf) return;
    wr_free(wf->base);
    wr_free(wf->iu);
    wr_free(wf->iu_inv);
    wr_free(wf->ib);
    wr_free(wf->iib);
    wr_free(wf->area);
    wr_free(wf->lambda);
    wr_free(wf->wdir);
    wr_free(wf->wperp);
    wr_free(wf->kperp);
    wr_free(wf->c2);
    wr_free(wf->wb1);
    wr_free(wf->qf);
    wr_free(wf->wfree);
    wr_free(wf->azero);
    memset(wf, 0, sizeof *wf);
}

/* W_s^2 coefficient of Eq. 22 from κ⊥ and the face's Eq. 29 data (ratio = w⊥ᵀI_b w⊥ / w⊥ᵀI_u w⊥). */
static double wr__wf_c2(const wr_wf *wf, double kperp, double ratio) {
    return 4.0 * kperp * kperp * wf->beta * (wf->alpha + wf->beta) / (wf->alpha + 2.0 * wf->beta) * ratio * ratio;
}

static wr_vec3 wr__wf_face_normal(const double *P, const int32_t *fv) {
    wr_vec3 p0 = wr_v3_load(P + 3 * fv[0]), p1 = wr_v3_load(P + 3 * fv[1]), p2 = wr_v3_load(P + 3 * fv[2]);
    return wr_v3_cross(wr_v3_sub(p1, p0), wr_v3_sub(p2, p0));
}

/* w⊥ᵀ S w⊥ for a symmetric chart tensor S = (s00, s01, s11) of face f. */
static double wr__wf_perp_form(const wr_wf *wf, int32_t f, const double *S) {
    double px = wf->wperp[2 * f], py = wf->wperp[2 * f + 1];
    return S[0] * px * px + 2.0 * S[1] * px * py + S[2] * py * py;
}

/* The mid-edge reading of κ⊥ on face f (curvature of the base across the wrinkles, w⊥ᵀ II_b w⊥ /
 * w⊥ᵀ I_b w⊥) and the Eq. 22 W_s^2 coefficient it gives (ignored in pure tension, Sec. 4.2). */
static void wr__wf_kappa_midedge_face(wr_wf *wf, int32_t f) {
    double wIbw = wr__wf_perp_form(wf, f, wf->ib + 3 * f), wIuw = wr__wf_perp_form(wf, f, wf->iu + 3 * f);
    wf->kperp[f] = wIbw > 0.0 ? wr__wf_perp_form(wf, f, wf->iib + 3 * f) / wIbw : 0.0;
    wf->c2[f] = wf->lambda[2 * f] < 0.0 ? wr__wf_c2(wf, wf->kperp[f], wIbw / wIuw) : 0.0;
}

static wr_status wr__wf_check_material(const wr_wf_material *mat, wr_diag *diag) {
    const double E = mat->young, nu = mat->poisson, h = mat->thickness;
    if (!(E > 0.0) || !isfinite(E))
        return wr_fail(diag, WR_ERR_DOMAIN, -1, "wrinkle field: Young's modulus %g Pa must be > 0", E);
    if (!(nu > -1.0 && nu < 1.0))
        return wr_fail(diag, WR_ERR_DOMAIN, -1, "wrinkle field: Poisson ratio %g outside (-1, 1)", nu);
    if (!(h > 0.0) || !isfinite(h)) return wr_fail(diag, WR_ERR_DOMAIN, -1, "wrinkle field: thickness %g m must be > 0", h);
    return WR_OK;
}

/* The per-vertex and per-face arrays of wf (nv, nf set); 0 when out of memory. */
static int wr__wf_alloc(wr_wf *wf) {
    const size_t nv = (size_t)wf->nv, nf = (size_t)wf->nf;
    wf->base = (double *)wr_alloc_array(nv * 3, sizeof(double));
    wf->iu = (double *)wr_alloc_array(nf * 3, sizeof(double));
    wf->iu_inv = (double *)wr_alloc_array(nf * 3, sizeof(double));
    wf->ib = (double *)wr_alloc_array(nf * 3, sizeof(double));
    wf->iib = (double *)wr_alloc_array(nf * 3, sizeof(double));
    wf->area = (double *)wr_alloc_array(nf, sizeof(double));
    wf->lambda = (double *)wr_alloc_array(nf * 2, sizeof(double));
    wf->wdir = (double *)wr_alloc_array(nf * 2, sizeof(double));
    wf->wperp = (double *)wr_alloc_array(nf * 2, sizeof(double));
    wf->kperp = (double *)wr_alloc_array(nf, sizeof(double));
    wf->c2 = (double *)wr_alloc_array(nf, sizeof(double));
    wf->wb1 = (double *)wr_alloc_array(nf, sizeof(double));
    wf->qf = (double *)wr_alloc_array(nf * 9, sizeof(double));
    wf->wfree = (uint8_t *)wr_calloc_array(nf, sizeof(uint8_t));
    wf->azero = (uint8_t *)wr_calloc_array(nv, sizeof(uint8_t));
    return wf->base && wf->iu && wf->iu_inv && wf->ib && wf->iib && wf->area && wf->lambda && wf->wdir && wf->wperp &&
           wf->kperp && wf->c2 && wf->wb1 && wf->qf && wf->wfree && wf->azero;
}

/* The first fundamental forms of face f: I_u (rest chart, with its inverse and the rest area) and
 * I_b (base surface); a degenerate rest or base triangle is an error naming the face. */
static wr_status wr__wf_face_forms(wr_wf *wf, int32_t f, wr_diag *diag) {
    const wr_mesh *m = wf->mesh;
    const int32_t *fv = m->faces + 3 * f;
    double uv[6], e1[2], e2[2], det, *Iu = wf->iu + 3 * f, *Ib = wf->ib + 3 * f;
    wr_vec3 P0, E1, E2;
    wr_mesh_face_rest(m, f, uv);
    e1[0] = uv[2] - uv[0];
    e1[1] = uv[3] - uv[1];
    e2[0] = uv[4] - uv[0];
    e2[1] = uv[5] - uv[1];
    Iu[0] = e1[0] * e1[0] + e1[1] * e1[1];
    Iu[1] = e1[0] * e2[0] + e1[1] * e2[1];
    Iu[2] = e2[0] * e2[0] + e2[1] * e2[1];
    det = Iu[0] * Iu[2] - Iu[1] * Iu[1];
    if (!(det > 1e-24 * Iu[0] * Iu[2]) || !(Iu[0] > 0.0))
        return wr_fail(diag, WR_ERR_GEOMETRY, f, "wrinkle field: face %d has a degenerate rest triangle", (int)f);
    wf->area[f] = 0.5 * sqrt(det);
    wf->iu_inv[3 * f + 0] = Iu[2] / det;
    wf->iu_inv[3 * f + 1] = -Iu[1] / det;
    wf->iu_inv[3 * f + 2] = Iu[0] / det;
    P0 = wr_v3_load(wf->base + 3 * fv[0]);
    E1 = wr_v3_sub(wr_v3_load(wf->base + 3 * fv[1]), P0);
    E2 = wr_v3_sub(wr_v3_load(wf->base + 3 * fv[2]), P0);
    Ib[0] = wr_v3_dot(E1, E1);
    Ib[1] = wr_v3_dot(E1, E2);
    Ib[2] = wr_v3_dot(E2, E2);
    if (!(wr_v3_norm(wr__wf_face_normal(wf->base, fv)) > 1e-12 * (Ib[0] + Ib[2])))
        return wr_fail(diag, WR_ERR_GEOMETRY, f, "wrinkle field: face %d is degenerate on the base surface", (int)f);
    return WR_OK;
}

/* App. A: the second fundamental form of face f from mid-edge normals, n̂_k on the edge opposite
 * corner k: the face normal on boundary edges, the normalised average of the two face normals
 * otherwise; II_b = 2 [(v1-v0)·(n1-n0), (v2-v0)·(n1-n0); ·, (v2-v0)·(n2-n0)] (off-diagonal
 * symmetrised). Its sign convention only enters squared (W_s^2, W_b^1). */
static void wr__wf_face_iib(wr_wf *wf, int32_t f) {
    const wr_mesh *m = wf->mesh;
    const int32_t *fv = m->faces + 3 * f;
    const wr_vec3 P0 = wr_v3_load(wf->base + 3 * fv[0]);
    const wr_vec3 E1 = wr_v3_sub(wr_v3_load(wf->base + 3 * fv[1]), P0), E2 = wr_v3_sub(wr_v3_load(wf->base + 3 * fv[2]), P0);
    const wr_vec3 nf0 = wr_v3_normalized(wr__wf_face_normal(wf->base, fv));
    wr_vec3 nhat[3];
    double *II = wf->iib + 3 * f;
    int k;
    for (k = 0; k < 3; ++k) {
        int32_t e = m->face_edges[3 * f + k];
        int32_t g = m->edge_faces[2 * e] == f ? m->edge_faces[2 * e + 1] : m->edge_faces[2 * e];
        nhat[k] = nf0;
        if (g >= 0) {
            wr_vec3 ng = wr_v3_normalized(wr__wf_face_normal(wf->base, m->faces + 3 * g));
            wr_vec3 avg = wr_v3_add(nf0, ng);
            if (wr_v3_norm(avg) > 1e-12) nhat[k] = wr_v3_normalized(avg);
        }
    }
    II[0] = 2.0 * wr_v3_dot(E1, wr_v3_sub(nhat[1], nhat[0]));
    II[1] = wr_v3_dot(E2, wr_v3_sub(nhat[1], nhat[0])) + wr_v3_dot(E1, wr_v3_sub(nhat[2], nhat[0]));
    II[2] = 2.0 * wr_v3_dot(E2, wr_v3_sub(nhat[2], nhat[0]));
}

/* Eq. 29 on face f: the principal strains λ and directions of I_b - I_u relative to I_u, through
 * I_u = L Lᵀ: L⁻¹(I_b - I_u)L⁻ᵀ y = λ y, w = L⁻ᵀ y (so ||w||_{I_u} = ||y|| = 1); wdir belongs to
 * the smaller λ (the most compressed direction), wperp to the other. */
static void wr__wf_face_strain_eig(wr_wf *wf, int32_t f) {
    const double *Iu = wf->iu + 3 * f, *Ib = wf->ib + 3 * f;
    const double l00 = sqrt(Iu[0]), l10 = Iu[1] / l00, l11 = sqrt(Iu[2] - l10 * l10);
    const double C00 = Ib[0] - Iu[0], C01 = Ib[1] - Iu[1], C11 = Ib[2] - Iu[2];
    /* A = L⁻¹ C L⁻ᵀ with L⁻¹ = [1/l00, 0; -l10/(l00 l11), 1/l11] */
    const double i00 = 1.0 / l00, i10 = -l10 / (l00 * l11), i11 = 1.0 / l11;
    const double t00 = i00 * C00, t01 = i00 * C01;                         /* (L⁻¹C) row 0 */
    const double t10 = i10 * C00 + i11 * C01, t11 = i10 * C01 + i11 * C11; /* row 1 */
    const double a00 = t00 * i00, a01 = t00 * i10 + t01 * i11, a11 = t10 * i10 + t11 * i11;
    double lam[2];
    wr_vec2 evec[2];
    wr_m2_sym_eig(wr_m2(a00, a01, a01, a11), lam, evec);
    wf->lambda[2 * f] = lam[0];
    wf->lambda[2 * f + 1] = lam[1];
    /* w = L⁻ᵀ y: L⁻ᵀ = [1/l00, -l10/(l00 l11); 0, 1/l11] */
    wf->wdir[2 * f] = evec[0].x / l00 - l10 / (l00 * l11) * evec[0].y;
    wf->wdir[2 * f + 1] = evec[0].y / l11;
    wf->wperp[2 * f] = evec[1].x / l00 - l10 / (l00 * l11) * evec[1].y;
    wf->wperp[2 * f + 1] = evec[1].y / l11;
}

/* Face f's constant bending data: the quadratic form of I_u⁻¹ (reused by the SQP at every
 * evaluation) and W_b^1 = ||I_u⁻¹ II_b||²_SV (II_u = 0, rest-flat). */
static void wr__wf_face_bending(wr_wf *wf, int32_t f) {
    const double *II = wf->iib + 3 * f;
    double *Qm = wf->qf + 9 * (size_t)f, s = 0.0;
    int c, d;
    wr__wf_qform(wf->iu_inv + 3 * f, wf->alpha, wf->beta, Qm);
    for (c = 0; c < 3; ++c)
        for (d = 0; d < 3; ++d) s += II[c] * Qm[3 * c + d] * II[d];
    wf->wb1[f] = s;
}

WRDEF wr_status wr_wf_create(wr_wf *wf, const wr_mesh *m, const double *base_pos, const wr_wf_material *mat,
                             wr_diag *diag) {
    int32_t f, v;
    double E, nu;
    wr_status st;
    if (!wf) return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "wrinkle field: NULL output");
    memset(wf, 0, sizeof *wf);
    if (!m || !mat || !m->faces || m->nf < 1 || m->nv < 1)
        return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "wrinkle field: NULL or empty mesh/material");
    if ((st = wr__wf_check_material(mat, diag)) != WR_OK) return st;
    if (!base_pos) base_pos = m->pos;
    E = mat->young;
    nu = mat->poisson;
    wf->mesh = m;
    wf->nv = m->nv;
    wf->ne = m->ne;
    wf->nf = m->nf;
    wf->alpha = E * nu / (1.0 - nu * nu); /* Eq. 33 */
    wf->beta = E / (2.0 * (1.0 + nu));
    wf->h = mat->thickness;
    if (!wr__wf_alloc(wf)) {
        wr_wf_free(wf);
        return wr_fail(diag, WR_ERR_NOMEM, -1, "wrinkle field: out of memory for %d faces", (int)m->nf);
    }
    for (v = 0; v < 3 * m->nv; ++v) {
        if (!isfinite(base_pos[v])) {
            wr_wf_free(wf);
            return wr_fail(diag, WR_ERR_DOMAIN, v / 3, "wrinkle field: non-finite base position at vertex %d",
                           (int)(v / 3));
        }
        wf->base[v] = base_pos[v];
    }
    for (f = 0; f < m->nf; ++f) { /* per face: the two forms, II_b, Eq. 29, κ⊥ and Eq. 22, bending */
        if ((st = wr__wf_face_forms(wf, f, diag)) != WR_OK) {
            wr_wf_free(wf);
            return st;
        }
        wr__wf_face_iib(wf, f);
        wr__wf_face_strain_eig(wf, f);
        wr__wf_kappa_midedge_face(wf, f);
        wr__wf_face_bending(wf, f);
    }
    return WR_OK;
}

WRDEF wr_status wr_wf_set_kappa(wr_wf *wf, wr_wf_kappa reading, wr_diag *diag) {
    const wr_mesh *m = wf->mesh;
    double *k1, *k2, *d1;
    int32_t f;
    wr_status st;
    if (reading == WR_WF_KAPPA_MIDEDGE) {
        for (f = 0; f < wf->nf; ++f) wr__wf_kappa_midedge_face(wf, f);
        return WR_OK;
    }
    if (reading != WR_WF_KAPPA_VERTEX_FIT)
        return wr_fail(diag, WR_ERR_INVALID_ARG, (int32_t)reading, "wf kappa: unknown reading %d", (int)reading);
    k1 = (double *)wr_alloc_array((size_t)wf->nv, sizeof(double));
    k2 = (double *)wr_alloc_array((size_t)wf->nv, sizeof(double));
    d1 = (double *)wr_alloc_array((size_t)wf->nv * 3, sizeof(double));
    st = (k1 && k2 && d1) ? wr_mesh_vertex_curvature(m, wf->base, 5, k1, k2, d1, diag)
                          : wr_fail(diag, WR_ERR_NOMEM, -1, "wf kappa: out of memory");
    for (f = 0; f < wf->nf && !st; ++f) {
        const int32_t *fv = m->faces + 3 * f;
        wr_vec3 P0 = wr_v3_load(wf->base + 3 * fv[0]), E1 = wr_v3_sub(wr_v3_load(wf->base + 3 * fv[1]), P0),
                E2 = wr_v3_sub(wr_v3_load(wf->base + 3 * fv[2]), P0);
        wr_vec3 n = wr_v3_normalized(wr_v3_cross(E1, E2));
        wr_vec3 t = wr_v3_normalized(wr_v3_add(wr_v3_scale(E1, wf->wperp[2 * f]), wr_v3_scale(E2, wf->wperp[2 * f + 1])));
        double wIbw = wr__wf_perp_form(wf, f, wf->ib + 3 * f), wIuw = wr__wf_perp_form(wf, f, wf->iu + 3 * f), kap = 0.0;
        int c;
        for (c = 0; c < 3; ++c) {
            /* Euler: κ(t) = k1 cos²θ + k2 sin²θ, θ from the k1 direction projected on the face plane */
            wr_vec3 dv = wr_v3_load(d1 + 3 * fv[c]);
            double cs = wr_v3_dot(wr_v3_sub(dv, wr_v3_scale(n, wr_v3_dot(dv, n))), t);
            kap += k1[fv[c]] * cs * cs + k2[fv[c]] * (1.0 - cs * cs);
        }
        wf->kperp[f] = kap / 3.0;
        wf->c2[f] = wf->lambda[2 * f] <= 0.0 && wf->lambda[2 * f + 1] >= 0.0 ? wr__wf_c2(wf, wf->kperp[f], wIbw / wIuw)
                                                                                : 0.0;
    }
    wr_free(k1);
    wr_free(k2);
    wr_free(d1);
    return st;
}

WRDEF void wr_wf_set_wrinkle_free(wr_wf *wf, const uint8_t *flags) {
    int32_t f;
    for (f = 0; f < wf->nf; ++f) wf->wfree[f] = (uint8_t)(flags && flags[f] ? 1 : 0);
}

WRDEF void wr_wf_set_amplitude_zero(wr_wf *wf, const uint8_t *vflags) {
    int32_t v;
    for (v = 0; v < wf->nv; ++v) wf->azero[v] = (uint8_t)(vflags && vflags[v] ? 1 : 0);
}

static int32_t wr__wf_face_neighbor(const wr_mesh *m, int32_t f, int k) {
    int32_t e = m->face_edges[3 * f + k];
    return m->edge_faces[2 * e] == f ? m->edge_faces[2 * e + 1] : m->edge_faces[2 * e];
}

/* WR_WF_WSET_RELEASE: own eigenvalue, then the one-pass hole fill through vertices (see the
 * declaration). The release tests λ0 >= 0 exactly; -tol keeps round-off on an unstrained face from
 * deciding, as in the paper rule. Out of memory: the unfilled rule. */
static void wr__wf_classify_release(wr_wf *wf, double tol) {
    const wr_mesh *m = wf->mesh;
    uint8_t *vin = (uint8_t *)wr_calloc_array((size_t)wf->nv, sizeof(uint8_t));
    int32_t f;
    int c;
    for (f = 0; f < wf->nf; ++f) wf->wfree[f] = (uint8_t)(wf->lambda[2 * f] >= -tol ? 1 : 0);
    if (!vin) return;
    for (f = 0; f < wf->nf; ++f)
        if (wf->wfree[f])
            for (c = 0; c < 3; ++c) vin[m->faces[3 * f + c]] = 1;
    for (f = 0; f < wf->nf; ++f) {
        const int32_t *fv = m->faces + 3 * f;
        if (!wf->wfree[f] && vin[fv[0]] && vin[fv[1]] && vin[fv[2]]) wf->wfree[f] = 1;
    }
    wr_free(vin);
}

WRDEF int32_t wr_wf_classify(wr_wf *wf, const wr_wf_classify_desc *desc) {
    const wr_mesh *m = wf->mesh;
    double tol = desc && desc->compress_tol > 0.0 ? desc->compress_tol : WR__WF_COMPRESS_TOL;
    int filter = !(desc && desc->no_outlier_filter);
    int32_t f, count = 0;
    uint8_t *w0;
    if (desc && desc->rule != WR_WF_WSET_PAPER) {
        if (desc->rule != WR_WF_WSET_RELEASE) return -1;
        wr__wf_classify_release(wf, tol);
        for (f = 0; f < wf->nf; ++f) count += wf->wfree[f];
        return count;
    }
    w0 = (uint8_t *)wr_alloc_array((size_t)wf->nf, sizeof(uint8_t));
    if (!w0) { /* fall back to the unfiltered rule written straight into wfree */
        filter = 0;
    }
    for (f = 0; f < wf->nf; ++f) {
        /* Sec. 5.1: average of the face's most negative eigenvalue with its neighbours'. */
        double s = wf->lambda[2 * f];
        int n = 1, k;
        for (k = 0; k < 3; ++k) {
            int32_t g = wr__wf_face_neighbor(m, f, k);
            if (g >= 0) {
                s += wf->lambda[2 * g];
                ++n;
            }
        }
        wf->wfree[f] = (uint8_t)(s / n >= -tol ? 1 : 0);
    }
    if (filter) {
        memcpy(w0, wf->wfree, (size_t)wf->nf);
        for (f = 0; f < wf->nf; ++f) {
            int nn = 0, nin = 0, k;
            for (k = 0; k < 3; ++k) {
                int32_t g = wr__wf_face_neighbor(m, f, k);
                if (g >= 0) {
                    ++nn;
                    nin += w0[g];
                }
            }
            if (w0[f] && nn > 0 && nin == 0) wf->wfree[f] = 0;
            if (!w0[f] && nn > 0 && nin == nn) wf->wfree[f] = 1;
        }
    }
    wr_free(w0);
    for (f = 0; f < wf->nf; ++f) count += wf->wfree[f];
    return count;
}

/* ---- hand-expanded face evaluation (the default; wr__wf_face_eval above is the literal reference) ----
 * With g = da and p = dφ constant on the face (see ON READINGS) only a varies between quadrature
 * points, and every term of Eq. 21–26 is a polynomial in a² whose coefficients depend on
 * u = (g0, g1, p0, p1) alone. Per point, h/4 (W_s^1 + W_s^2 + W_s^3 + W_s^4) + h³/12 W_b^2 (times the
 * point's weight) = α0(u) + α2(u) a² + α4(u) a⁴ with
 *   α0 = ws [cᵀQc + cᵀQG + ⅜ GᵀQG]                      (W_s^1 at a = 0; W_s^4 = GᵀQG/8)
 *   α2 = ws [cᵀQP + ½ GᵀQP + XᵀQX/32 + c2] + wb PᵀQP/2  (W_s^1 cross term, W_s^3, W_s^2, W_b^2)
 *   α4 = ws PᵀQP/4                                      (W_s^1)
 * where Q is the face's Eq. 4 form (wf->qf), c = I_b - I_u, and G = gᵀg, P = pᵀp, X = pᵀg + gᵀp are
 * 3-vectors (00, 01, 11). So E_f = 3 α0 + α2 M2 + α4 M4 with the quadrature moments M2 = Σ_q a_q²,
 * M4 = Σ_q a_q⁴; gradient and Hessian follow from those of the α's (bilinear forms sᵀQt of G, P, X)
 * and of the moments. excess drops cᵀQc (and W_b^1), as in wr__wf_face_eval. */
enum { WR__WF_VC = 0, WR__WF_VG, WR__WF_VP, WR__WF_VX };

/* Adds w Σ_c lam_c ∇²v_c to the 4×4 H (u = (g0, g1, p0, p1)) for v = G, P or X; c is constant. */
static void wr__wf_d2(int kind, const double *lam, double w, double *H) {
    if (kind == WR__WF_VG || kind == WR__WF_VP) { /* G = (g0², g0 g1, g1²), P alike on (p0, p1) */
        int o = kind == WR__WF_VP ? 2 : 0;
        H[5 * o] += 2.0 * w * lam[0];
        H[5 * o + 1] += w * lam[1];
        H[5 * o + 4] += w * lam[1];
        H[5 * o + 5] += 2.0 * w * lam[2];
    } else if (kind == WR__WF_VX) { /* X = (2 p0 g0, p0 g1 + p1 g0, 2 p1 g1) */
        H[2] += 2.0 * w * lam[0], H[8] += 2.0 * w * lam[0];
        H[3] += w * lam[1], H[12] += w * lam[1];
        H[6] += w * lam[1], H[9] += w * lam[1];
        H[7] += 2.0 * w * lam[2], H[13] += 2.0 * w * lam[2];
    }
}

/* sᵀQt for s, t among (c, G, P, X) (v, Qv: 3 per kind, Qv = Q v); when grad is given, adds
 * w ∇_u(sᵀQt) = w (J_s Qt + J_t Qs) to grad and, when H is given, w ∇²_u(sᵀQt) =
 * w (J_s Q J_tᵀ + J_t Q J_sᵀ + ∇²s·Qt + ∇²t·Qs) to H (J: 12 per kind, 4 rows of 3; QJ = rows of Q J). */
static double wr__wf_bil(const double *v, const double *Qv, const double *J, const double *QJ, int ks, int kt, double w,
                         double *grad, double *H) {
    const double *s = v + 3 * ks, *Qs = Qv + 3 * ks, *Qt = Qv + 3 * kt, *Js = J + 12 * ks, *Jt = J + 12 * kt;
    const double *QJs = QJ + 12 * ks, *QJt = QJ + 12 * kt;
    int i, j;
    if (grad)
        for (i = 0; i < 4; ++i) {
            const double *a = Js + 3 * i, *b = Jt + 3 * i;
            grad[i] += w * (a[0] * Qt[0] + a[1] * Qt[1] + a[2] * Qt[2] + b[0] * Qs[0] + b[1] * Qs[1] + b[2] * Qs[2]);
        }
    if (H) {
        for (i = 0; i < 4; ++i)
            for (j = 0; j < 4; ++j) {
                const double *a = Js + 3 * i, *b = Jt + 3 * i, *qa = QJs + 3 * j, *qb = QJt + 3 * j;
                H[4 * i + j] += w * (a[0] * qb[0] + a[1] * qb[1] + a[2] * qb[2] + b[0] * qa[0] + b[1] * qa[1] + b[2] * qa[2]);
            }
        wr__wf_d2(ks, Qt, w, H);
        wr__wf_d2(kt, Qs, w, H);
    }
    return s[0] * Qt[0] + s[1] * Qt[1] + s[2] * Qt[2];
}

static void wr__wf_face_eval_fast(const wr_wf *wf, int32_t f, const double xl[6], int excess, double *e, double *g6,
                                  double *H36, double *terms) {
    /* dφ (Whitney face average, see ON READINGS): p = JP ω̃, as in wr__wf_face_eval */
    static const double JP[2][3] = {{-1.0 / 3.0, -1.0 / 3.0, 2.0 / 3.0}, {1.0 / 3.0, -2.0 / 3.0, 1.0 / 3.0}};
    const double *Q = wf->qf + 9 * (size_t)f;
    const double ws = wf->h / 4.0 * wf->area[f] / 3.0;                  /* Eq. 20 prefactor × quadrature weight */
    const double wb = wf->h * wf->h * wf->h / 12.0 * wf->area[f] / 3.0; /* Eq. 26 */
    const double c2 = wf->c2[f];
    const int deriv = g6 != NULL || H36 != NULL;
    double v[12], Qv[12], J[48], QJ[48];
    double d0[4], d2[4], dP[4], H0[16], H2[16], HP[16], *pd0 = NULL, *pd2 = NULL, *pdP = NULL, *pH0 = NULL, *pH2 = NULL,
                                                         *pHP = NULL;
    double g0, g1, p0, p1, aq[3], M2 = 0.0, M4 = 0.0;
    double cQc, cQG, GQG, cQP, GQP, XQX, PQP, al0, al2, al4;
    int i, j, k, q;
    for (k = 0; k < 3; ++k) v[k] = wf->ib[3 * f + k] - wf->iu[3 * f + k];
    g0 = xl[1] - xl[0];
    g1 = xl[2] - xl[0];
    p0 = JP[0][0] * xl[3] + JP[0][1] * xl[4] + JP[0][2] * xl[5];
    p1 = JP[1][0] * xl[3] + JP[1][1] * xl[4] + JP[1][2] * xl[5];
    v[3] = g0 * g0, v[4] = g0 * g1, v[5] = g1 * g1;
    v[6] = p0 * p0, v[7] = p0 * p1, v[8] = p1 * p1;
    v[9] = 2.0 * p0 * g0, v[10] = p0 * g1 + p1 * g0, v[11] = 2.0 * p1 * g1;
    for (k = 0; k < 4; ++k)
        for (i = 0; i < 3; ++i) Qv[3 * k + i] = Q[3 * i] * v[3 * k] + Q[3 * i + 1] * v[3 * k + 1] + Q[3 * i + 2] * v[3 * k + 2];
    if (deriv) {
        memset(J, 0, sizeof J); /* J + 12 kind: row i = ∂v/∂u_i, u = (g0, g1, p0, p1) */
        J[12 * WR__WF_VG + 0] = 2.0 * g0, J[12 * WR__WF_VG + 1] = g1;
        J[12 * WR__WF_VG + 4] = g0, J[12 * WR__WF_VG + 5] = 2.0 * g1;
        J[12 * WR__WF_VP + 6] = 2.0 * p0, J[12 * WR__WF_VP + 7] = p1;
        J[12 * WR__WF_VP + 10] = p0, J[12 * WR__WF_VP + 11] = 2.0 * p1;
        J[12 * WR__WF_VX + 0] = 2.0 * p0, J[12 * WR__WF_VX + 1] = p1;
        J[12 * WR__WF_VX + 4] = p0, J[12 * WR__WF_VX + 5] = 2.0 * p1;
        J[12 * WR__WF_VX + 6] = 2.0 * g0, J[12 * WR__WF_VX + 7] = g1;
        J[12 * WR__WF_VX + 10] = g0, J[12 * WR__WF_VX + 11] = 2.0 * g1;
        memset(d0, 0, sizeof d0);
        memset(d2, 0, sizeof d2);
        memset(dP, 0, sizeof dP);
        pd0 = d0, pd2 = d2, pdP = dP;
        if (H36) {
            for (k = 0; k < 16; ++k) /* 4 kinds × 4 rows */
                for (i = 0; i < 3; ++i)
                    QJ[3 * k + i] = Q[3 * i] * J[3 * k] + Q[3 * i + 1] * J[3 * k + 1] + Q[3 * i + 2] * J[3 * k + 2];
            memset(H0, 0, sizeof H0);
            memset(H2, 0, sizeof H2);
            memset(HP, 0, sizeof HP);
            pH0 = H0, pH2 = H2, pHP = HP;
        }
    }
    /* each bilinear form once; its derivatives weighted into the α it feeds (PᵀQP feeds α2 and α4) */
    cQc = excess ? 0.0 : v[0] * Qv[0] + v[1] * Qv[1] + v[2] * Qv[2];
    cQG = wr__wf_bil(v, Qv, J, QJ, WR__WF_VC, WR__WF_VG, ws, pd0, pH0);
    GQG = wr__wf_bil(v, Qv, J, QJ, WR__WF_VG, WR__WF_VG, 0.375 * ws, pd0, pH0);
    cQP = wr__wf_bil(v, Qv, J, QJ, WR__WF_VC, WR__WF_VP, ws, pd2, pH2);
    GQP = wr__wf_bil(v, Qv, J, QJ, WR__WF_VG, WR__WF_VP, 0.5 * ws, pd2, pH2);
    XQX = wr__wf_bil(v, Qv, J, QJ, WR__WF_VX, WR__WF_VX, ws / 32.0, pd2, pH2);
    PQP = wr__wf_bil(v, Qv, J, QJ, WR__WF_VP, WR__WF_VP, 1.0, pdP, pHP);
    al0 = ws * (cQc + cQG + 0.375 * GQG);
    al2 = ws * (cQP + 0.5 * GQP + XQX / 32.0 + c2) + 0.5 * wb * PQP;
    al4 = 0.25 * ws * PQP;
    /* quadrature moments of a (three-point rule, see ON READINGS) */
    for (q = 0; q < 3; ++q) {
        aq[q] = wr__wf_qp[q][0] * xl[0] + wr__wf_qp[q][1] * xl[1] + wr__wf_qp[q][2] * xl[2];
        M2 += aq[q] * aq[q];
        M4 += aq[q] * aq[q] * aq[q] * aq[q];
    }
    /* W_b^1: constant of the base (no a, ω dependence); left out of the excess energy. */
    if (!excess) {
        *e += 3.0 * wb * wf->wb1[f];
        if (terms) terms[WR_WF_TERM_B1] += 3.0 * wb * wf->wb1[f];
    }
    *e += 3.0 * al0 + al2 * M2 + al4 * M4;
    if (terms) {
        terms[WR_WF_TERM_S1] += 3.0 * ws * (cQc + cQG + 0.25 * GQG) + M2 * ws * (cQP + 0.5 * GQP) + M4 * al4;
        terms[WR_WF_TERM_S4] += 3.0 * ws * 0.125 * GQG;
        terms[WR_WF_TERM_S3] += M2 * ws * XQX / 32.0;
        terms[WR_WF_TERM_S2] += M2 * ws * c2;
        terms[WR_WF_TERM_B2] += M2 * 0.5 * wb * PQP;
    }
    if (!deriv) return;
    {
        /* x = (a0, a1, a2, ω̃0, ω̃1, ω̃2) -> u = R x; E = 3 α0(u) + α2(u) M2(a) + α4(u) M4(a) */
        double R[4][6], gu[4], gRa2[6], gRa4[6], dM2[3] = {0.0, 0.0, 0.0}, dM4[3] = {0.0, 0.0, 0.0};
        memset(R, 0, sizeof R);
        R[0][0] = -1.0, R[0][1] = 1.0;
        R[1][0] = -1.0, R[1][2] = 1.0;
        for (k = 0; k < 3; ++k) R[2][3 + k] = JP[0][k], R[3][3 + k] = JP[1][k];
        for (q = 0; q < 3; ++q)
            for (k = 0; k < 3; ++k) {
                dM2[k] += 2.0 * aq[q] * wr__wf_qp[q][k];
                dM4[k] += 4.0 * aq[q] * aq[q] * aq[q] * wr__wf_qp[q][k];
            }
        for (i = 0; i < 4; ++i) {
            d2[i] += 0.5 * wb * dP[i];       /* ∇α2 */
            gu[i] = 3.0 * d0[i] + M2 * d2[i] + M4 * 0.25 * ws * dP[i];
        }
        for (j = 0; j < 6; ++j) {
            double s2 = 0.0, s4 = 0.0;
            for (i = 0; i < 4; ++i) s2 += d2[i] * R[i][j], s4 += 0.25 * ws * dP[i] * R[i][j];
            gRa2[j] = s2; /* ∇_x α2 */
            gRa4[j] = s4; /* ∇_x α4 */
        }
        if (g6)
            for (j = 0; j < 6; ++j) {
                double s = j < 3 ? al2 * dM2[j] + al4 * dM4[j] : 0.0;
                for (i = 0; i < 4; ++i) s += gu[i] * R[i][j];
                g6[j] += s;
            }
        if (H36) {
            double Hu[16], HR[4][6];
            for (k = 0; k < 16; ++k) Hu[k] = 3.0 * H0[k] + M2 * (H2[k] + 0.5 * wb * HP[k]) + M4 * 0.25 * ws * HP[k];
            for (i = 0; i < 4; ++i)
                for (j = 0; j < 6; ++j) {
                    double s = 0.0;
                    int l;
                    for (l = 0; l < 4; ++l) s += Hu[4 * i + l] * R[l][j];
                    HR[i][j] = s;
                }
            for (i = 0; i < 6; ++i)
                for (j = i; j < 6; ++j) {
                    double s = 0.0;
                    int l;
                    for (l = 0; l < 4; ++l) s += R[l][i] * HR[l][j];
                    if (i < 3) s += dM2[i] * gRa2[j] + dM4[i] * gRa4[j];
                    if (j < 3) s += dM2[j] * gRa2[i] + dM4[j] * gRa4[i];
                    if (i < 3 && j < 3) {
                        /* ∇²M2 = 2 Σ λλᵀ, ∇²M4 = 12 Σ a² λλᵀ */
                        double m2 = 0.0, m4 = 0.0;
                        for (q = 0; q < 3; ++q) {
                            double ll = wr__wf_qp[q][i] * wr__wf_qp[q][j];
                            m2 += 2.0 * ll;
                            m4 += 12.0 * aq[q] * aq[q] * ll;
                        }
                        s += al2 * m2 + al4 * m4;
                    }
                    H36[6 * i + j] += s;
                    if (j != i) H36[6 * j + i] += s;
                }
        }
    }
}

WRDEF void wr_wf_face_dofs(const wr_wf *wf, int32_t f, int32_t idx[6], double sign[6]) {
    const wr_mesh *m = wf->mesh;
    int k;
    for (k = 0; k < 3; ++k) {
        idx[k] = m->faces[3 * f + k];
        sign[k] = 1.0;
        idx[3 + k] = wf->nv + m->face_edges[3 * f + k];
        sign[3 + k] = (double)m->face_edge_sign[3 * f + k];
    }
}

WRDEF void wr_wf_curl(const wr_mesh *m, const double *omega, double *curl) {
    int32_t f;
    for (f = 0; f < m->nf; ++f) {
        double s = 0.0;
        int k;
        for (k = 0; k < 3; ++k) s += m->face_edge_sign[3 * f + k] * omega[m->face_edges[3 * f + k]];
        curl[f] = s;
    }
}

/* excess != 0: E minus its a- and ω-independent part (the base's own stretching N(I_u⁻¹(I_b - I_u))
 * and W_b^1), computed without cancellation. The SQP compares energies through it: on a stretched
 * sheet the wrinkle part is ~3e-4 of E_wf, so differences of the full E hit round-off 1e4 times
 * too early. */
static wr_status wr__wf_energy_impl(const wr_wf *wf, const double *a, const double *omega, int excess, double *energy,
                                    double *grad, double *face_hess, double *terms, wr_diag *diag) {
    int32_t f, i;
    double E = 0.0;
    if (!wf || !a || !omega || !energy) return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "wf energy: NULL argument");
    for (i = 0; i < wf->nv; ++i)
        if (!isfinite(a[i])) return wr_fail(diag, WR_ERR_DOMAIN, i, "wf energy: non-finite a at vertex %d", (int)i);
    for (i = 0; i < wf->ne; ++i)
        if (!isfinite(omega[i]))
            return wr_fail(diag, WR_ERR_DOMAIN, i, "wf energy: non-finite omega at edge %d", (int)i);
    if (grad) memset(grad, 0, sizeof(double) * (size_t)(wf->nv + wf->ne));
    if (face_hess) memset(face_hess, 0, sizeof(double) * 36 * (size_t)wf->nf);
    if (terms) memset(terms, 0, sizeof(double) * WR_WF_NTERMS);
    for (f = 0; f < wf->nf; ++f) {
        int32_t idx[6];
        double sg[6], xl[6], g6[6];
        int k;
        if (wf->wfree[f]) continue; /* Eq. 37: sum over faces not in W */
        wr_wf_face_dofs(wf, f, idx, sg);
        for (k = 0; k < 3; ++k) {
            xl[k] = a[idx[k]];
            xl[3 + k] = sg[3 + k] * omega[idx[3 + k] - wf->nv];
        }
        memset(g6, 0, sizeof g6);
        if (wf->reference_eval)
            wr__wf_face_eval(wf, f, xl, excess, &E, grad ? g6 : NULL, face_hess ? face_hess + 36 * (size_t)f : NULL, terms);
        else
            wr__wf_face_eval_fast(wf, f, xl, excess, &E, grad ? g6 : NULL, face_hess ? face_hess + 36 * (size_t)f : NULL,
                                  terms);
        if (grad)
            for (k = 0; k < 6; ++k) grad[idx[k]] += sg[k] * g6[k];
        if (face_hess) {
            double *H = face_hess + 36 * (size_t)f;
            int r, c;
            for (r = 0; r < 6; ++r)
                for (c = 0; c < 6; ++c) H[6 * r + c] *= sg[r] * sg[c];
        }
    }
    *energy = E;
    return WR_OK;
}

WRDEF wr_status wr_wf_energy(const wr_wf *wf, const double *a, const double *omega, double *energy, double *grad,
                             double *face_hess, double *terms, wr_diag *diag) {
    return wr__wf_energy_impl(wf, a, omega, 0, energy, grad, face_hess, terms, diag);
}

/* ---- null-space basis of {ω : dω_f = 0 for every face f outside W} (tree–cotree) ----
 * ω = d0 ψ + Σ_g c_g h_g on the "active" edges (edges of at least one face outside W). ψ lives on
 * active vertices minus one root per primal component; h_g is 1 on generator edge g, 0 on the other
 * generators and on primal-tree edges, and fixed on dual-tree (cotree) edges by peeling the dual tree
 * from its leaves (each face's curl equation solved for its parent edge). The dual tree is rooted at a
 * virtual "outside" node reached through boundary edges of the complex, so the root needs no
 * equation; closed components get a real root face whose equation follows from the others.
 * Z is stored row-wise per edge (CSR over edges). */
typedef struct wr__wf_basis {
    int32_t ne, ncol, npsi, ngen;
    int32_t *zstart; /* ne+1 */
    int32_t *zcol;
    double *zval;
    int32_t *vcol;   /* nv: ψ column of vertex, or -1 (root or inactive) */
    uint8_t *eact;   /* ne: edge of some face outside W */
} wr__wf_basis;

static void wr__wf_basis_free(wr__wf_basis *B) {
    wr_free(B->zstart);
    wr_free(B->zcol);
    wr_free(B->zval);
    wr_free(B->vcol);
    wr_free(B->eact);
    memset(B, 0, sizeof *B);
}

/* Scratch of the tree–cotree construction (wr__wf_basis_build's stages). */
typedef struct wr__wf_tc {
    int32_t *vadj_s, *vadj;   /* vertex → active edges (CSR) */
    int32_t *queue, *fpar;    /* BFS queue; dual-tree parent edge per face (-1: root) */
    int32_t *order, nord;     /* faces in dual-BFS order */
    int32_t *gcol;            /* per edge: generator column, or -1 */
    uint8_t *intree, *cotree, *vvis, *fvis;
    /* generator rows h(e) per edge: hcol/hval[hstart[e] .. + hlen[e]) (hstart -1: empty) */
    int32_t *hstart, *hlen, *hcol, hcount, cap;
    double *hval;
    int32_t *mark, *touched;  /* sparse accumulator over generators */
    double *acc;
} wr__wf_tc;

static void wr__wf_tc_free(wr__wf_tc *T) {
    wr_free(T->vadj_s);
    wr_free(T->vadj);
    wr_free(T->queue);
    wr_free(T->fpar);
    wr_free(T->order);
    wr_free(T->gcol);
    wr_free(T->intree);
    wr_free(T->cotree);
    wr_free(T->vvis);
    wr_free(T->fvis);
    wr_free(T->hstart);
    wr_free(T->hlen);
    wr_free(T->hcol);
    wr_free(T->hval);
    wr_free(T->mark);
    wr_free(T->touched);
    wr_free(T->acc);
}

/* Active edges (edges of some face outside W) and the vertex → active-edge adjacency. */
static wr_status wr__wf_tc_adjacency(const wr_wf *wf, wr__wf_basis *B, wr__wf_tc *T, wr_diag *diag) {
    const wr_mesh *m = wf->mesh;
    int32_t nv = m->nv, ne = m->ne, nf = m->nf, f, e, v, i, *fill;
    B->zstart = (int32_t *)wr_calloc_array((size_t)ne + 1, sizeof(int32_t));
    B->vcol = (int32_t *)wr_alloc_array((size_t)nv, sizeof(int32_t));
    B->eact = (uint8_t *)wr_calloc_array((size_t)ne, sizeof(uint8_t));
    T->queue = (int32_t *)wr_alloc_array((size_t)(nv > nf ? nv : nf) + 1, sizeof(int32_t));
    T->fpar = (int32_t *)wr_alloc_array((size_t)nf, sizeof(int32_t));
    T->order = (int32_t *)wr_alloc_array((size_t)nf, sizeof(int32_t));
    T->vadj_s = (int32_t *)wr_calloc_array((size_t)nv + 1, sizeof(int32_t));
    T->vadj = (int32_t *)wr_alloc_array((size_t)ne * 2, sizeof(int32_t));
    T->gcol = (int32_t *)wr_alloc_array((size_t)ne, sizeof(int32_t));
    T->intree = (uint8_t *)wr_calloc_array((size_t)ne, sizeof(uint8_t));
    T->cotree = (uint8_t *)wr_calloc_array((size_t)ne, sizeof(uint8_t));
    T->vvis = (uint8_t *)wr_calloc_array((size_t)nv, sizeof(uint8_t));
    T->fvis = (uint8_t *)wr_calloc_array((size_t)nf, sizeof(uint8_t));
    fill = (int32_t *)wr_alloc_array((size_t)nv, sizeof(int32_t));
    if (!B->zstart || !B->vcol || !B->eact || !T->queue || !T->fpar || !T->order || !T->vadj_s || !T->vadj ||
        !T->gcol || !T->intree || !T->cotree || !T->vvis || !T->fvis || !fill) {
        wr_free(fill);
        return wr_fail(diag, WR_ERR_NOMEM, -1, "wf basis: out of memory");
    }
    for (f = 0; f < nf; ++f)
        if (!wf->wfree[f])
            for (i = 0; i < 3; ++i) B->eact[m->face_edges[3 * f + i]] = 1;
    for (e = 0; e < ne; ++e)
        if (B->eact[e]) {
            T->vadj_s[m->edges[2 * e] + 1]++;
            T->vadj_s[m->edges[2 * e + 1] + 1]++;
        }
    for (v = 0; v < nv; ++v) T->vadj_s[v + 1] += T->vadj_s[v];
    for (v = 0; v < nv; ++v) fill[v] = T->vadj_s[v];
    for (e = 0; e < ne; ++e)
        if (B->eact[e]) {
            T->vadj[fill[m->edges[2 * e]]++] = e;
            T->vadj[fill[m->edges[2 * e + 1]]++] = e;
        }
    wr_free(fill);
    return WR_OK;
}

/* Primal BFS forest over active edges: every non-root vertex gets a ψ column (roots fix the gauge). */
static void wr__wf_tc_primal(const wr_mesh *m, wr__wf_basis *B, wr__wf_tc *T) {
    int32_t v, qh, qt;
    for (v = 0; v < m->nv; ++v) B->vcol[v] = -1;
    B->npsi = 0;
    for (v = 0; v < m->nv; ++v) {
        int32_t r = v;
        if (T->vvis[r] || T->vadj_s[r] == T->vadj_s[r + 1]) continue;
        T->vvis[r] = 1; /* root: no ψ column (gauge) */
        qh = qt = 0;
        T->queue[qt++] = r;
        while (qh < qt) {
            int32_t u = T->queue[qh++], k;
            for (k = T->vadj_s[u]; k < T->vadj_s[u + 1]; ++k) {
                int32_t ee = T->vadj[k], w = m->edges[2 * ee] == u ? m->edges[2 * ee + 1] : m->edges[2 * ee];
                if (T->vvis[w]) continue;
                T->vvis[w] = 1;
                T->intree[ee] = 1;
                B->vcol[w] = B->npsi++;
                T->queue[qt++] = w;
            }
        }
    }
}

/* Dual BFS: from the virtual outside node through boundary edges of the complex (not in the primal
 * tree), then through interior edges not in the primal tree; closed components get a real root. */
static void wr__wf_tc_dual(const wr_wf *wf, const wr__wf_basis *B, wr__wf_tc *T) {
    const wr_mesh *m = wf->mesh;
    int32_t f, e, qh = 0, qt = 0;
    for (f = 0; f < m->nf; ++f) T->fpar[f] = -1;
    for (e = 0; e < m->ne; ++e) {
        int32_t f0 = m->edge_faces[2 * e], f1 = m->edge_faces[2 * e + 1], fin;
        int n_in = (f0 >= 0 && !wf->wfree[f0]) + (f1 >= 0 && !wf->wfree[f1]);
        if (!B->eact[e] || n_in != 1 || T->intree[e]) continue;
        fin = (f0 >= 0 && !wf->wfree[f0]) ? f0 : f1;
        if (T->fvis[fin]) continue;
        T->fvis[fin] = 1;
        T->fpar[fin] = e;
        T->cotree[e] = 1;
        T->queue[qt++] = fin;
    }
    T->nord = 0;
    for (f = -1; f < m->nf; ++f) {
        if (f >= 0) {
            if (T->fvis[f] || wf->wfree[f]) continue;
            T->fvis[f] = 1; /* closed component: a real root face */
            T->queue[qt++] = f;
        }
        while (qh < qt) {
            int32_t g = T->queue[qh++], k;
            T->order[T->nord++] = g;
            for (k = 0; k < 3; ++k) {
                int32_t ee = m->face_edges[3 * g + k], h2 = wr__wf_face_neighbor(m, g, k);
                if (h2 < 0 || wf->wfree[h2] || T->fvis[h2] || T->intree[ee]) continue;
                T->fvis[h2] = 1;
                T->fpar[h2] = ee;
                T->cotree[ee] = 1;
                T->queue[qt++] = h2;
            }
        }
    }
}

/* Generators (active edges in neither tree) and their unit rows h(e) = e_g. */
static wr_status wr__wf_tc_generators(const wr_mesh *m, wr__wf_basis *B, wr__wf_tc *T, wr_diag *diag) {
    int32_t e, ne = m->ne, ng1;
    B->ngen = 0;
    for (e = 0; e < ne; ++e) {
        T->gcol[e] = -1;
        if (B->eact[e] && !T->intree[e] && !T->cotree[e]) T->gcol[e] = B->npsi + B->ngen++;
    }
    B->ncol = B->npsi + B->ngen;
    ng1 = B->ngen > 0 ? B->ngen : 1;
    T->cap = ne + 16;
    T->hstart = (int32_t *)wr_alloc_array((size_t)ne, sizeof(int32_t));
    T->hlen = (int32_t *)wr_calloc_array((size_t)ne, sizeof(int32_t));
    T->hcol = (int32_t *)wr_alloc_array((size_t)T->cap, sizeof(int32_t));
    T->hval = (double *)wr_alloc_array((size_t)T->cap, sizeof(double));
    T->mark = (int32_t *)wr_calloc_array((size_t)ng1, sizeof(int32_t));
    T->touched = (int32_t *)wr_alloc_array((size_t)ng1, sizeof(int32_t));
    T->acc = (double *)wr_calloc_array((size_t)ng1, sizeof(double));
    if (!T->hstart || !T->hlen || !T->hcol || !T->hval || !T->mark || !T->touched || !T->acc)
        return wr_fail(diag, WR_ERR_NOMEM, -1, "wf basis: out of memory");
    T->hcount = 0;
    for (e = 0; e < ne; ++e) {
        T->hstart[e] = -1;
        if (T->gcol[e] >= 0) {
            T->hstart[e] = T->hcount;
            T->hlen[e] = 1;
            T->hcol[T->hcount] = T->gcol[e] - B->npsi;
            T->hval[T->hcount++] = 1.0;
        }
    }
    return WR_OK;
}

/* Room for nt more generator entries in hcol/hval. */
static wr_status wr__wf_tc_reserve(wr__wf_tc *T, int32_t nt, wr_diag *diag) {
    int32_t ncap, *nc;
    double *nvv;
    if (T->hcount + nt <= T->cap) return WR_OK;
    ncap = 2 * (T->hcount + nt) + 16;
    nc = (int32_t *)wr_realloc_array(T->hcol, (size_t)ncap, sizeof(int32_t));
    if (!nc) return wr_fail(diag, WR_ERR_NOMEM, -1, "wf basis: out of memory");
    T->hcol = nc;
    nvv = (double *)wr_realloc_array(T->hval, (size_t)ncap, sizeof(double));
    if (!nvv) return wr_fail(diag, WR_ERR_NOMEM, -1, "wf basis: out of memory");
    T->hval = nvv;
    T->cap = ncap;
    return WR_OK;
}

/* Generator rows of the cotree edges, peeling the dual tree from its leaves: face g's curl equation
 * ps·h(pe) + Σ_other s·h = 0 gives its parent edge pe's row. A real root's equation must already
 * hold (WR_ERR_TOPOLOGY otherwise). */
static wr_status wr__wf_tc_peel(const wr_mesh *m, const wr__wf_basis *B, wr__wf_tc *T, wr_diag *diag) {
    int32_t i;
    for (i = T->nord - 1; i >= 0; --i) {
        int32_t g = T->order[i], pe = T->fpar[g], k, nt = 0, ps = 0;
        wr_status st;
        if (pe < 0) {
            for (k = 0; k < 3; ++k) {
                int32_t ee = m->face_edges[3 * g + k], t;
                for (t = 0; T->hstart[ee] >= 0 && t < T->hlen[ee]; ++t)
                    T->acc[T->hcol[T->hstart[ee] + t]] += m->face_edge_sign[3 * g + k] * T->hval[T->hstart[ee] + t];
            }
            for (k = 0; k < B->ngen; ++k) {
                if (fabs(T->acc[k]) > 1e-9)
                    return wr_fail(diag, WR_ERR_TOPOLOGY, g,
                                   "wf basis: dual tree root face %d cannot close its curl equation", (int)g);
                T->acc[k] = 0.0;
            }
            continue;
        }
        for (k = 0; k < 3; ++k) {
            int32_t ee = m->face_edges[3 * g + k], t;
            if (ee == pe) {
                ps = m->face_edge_sign[3 * g + k];
                continue;
            }
            for (t = 0; T->hstart[ee] >= 0 && t < T->hlen[ee]; ++t) {
                int32_t c = T->hcol[T->hstart[ee] + t];
                if (!T->mark[c]) {
                    T->mark[c] = 1;
                    T->touched[nt++] = c;
                }
                T->acc[c] += m->face_edge_sign[3 * g + k] * T->hval[T->hstart[ee] + t];
            }
        }
        st = wr__wf_tc_reserve(T, nt, diag);
        if (st) return st;
        T->hstart[pe] = T->hcount;
        T->hlen[pe] = 0;
        for (k = 0; k < nt; ++k) {
            int32_t c = T->touched[k];
            if (T->acc[c] != 0.0) {
                T->hcol[T->hcount] = c;
                T->hval[T->hcount++] = -ps * T->acc[c];
                T->hlen[pe]++;
            }
            T->acc[c] = 0.0;
            T->mark[c] = 0;
        }
    }
    return WR_OK;
}

/* Z rows: the d0 part (ψ_hi − ψ_lo) plus the generator part h(e). */
static wr_status wr__wf_tc_assemble(const wr_mesh *m, wr__wf_basis *B, const wr__wf_tc *T, wr_diag *diag) {
    int32_t e, nnz = 0;
    for (e = 0; e < m->ne; ++e) nnz += B->eact[e] ? 2 + (T->hstart[e] >= 0 ? T->hlen[e] : 0) : 0;
    B->zcol = (int32_t *)wr_alloc_array((size_t)nnz + 1, sizeof(int32_t));
    B->zval = (double *)wr_alloc_array((size_t)nnz + 1, sizeof(double));
    if (!B->zcol || !B->zval) return wr_fail(diag, WR_ERR_NOMEM, -1, "wf basis: out of memory");
    nnz = 0;
    for (e = 0; e < m->ne; ++e) {
        B->zstart[e] = nnz;
        if (B->eact[e]) {
            int32_t lo = B->vcol[m->edges[2 * e]], hi = B->vcol[m->edges[2 * e + 1]], t;
            if (hi >= 0) {
                B->zcol[nnz] = hi;
                B->zval[nnz++] = 1.0;
            }
            if (lo >= 0) {
                B->zcol[nnz] = lo;
                B->zval[nnz++] = -1.0;
            }
            for (t = 0; T->hstart[e] >= 0 && t < T->hlen[e]; ++t) {
                B->zcol[nnz] = B->npsi + T->hcol[T->hstart[e] + t];
                B->zval[nnz++] = T->hval[T->hstart[e] + t];
            }
        }
    }
    B->zstart[m->ne] = nnz;
    return WR_OK;
}

/* The null-space basis Z of dω = 0 outside W by tree–cotree: ψ on a primal spanning forest, the
 * dual forest's edges determined by the faces' curl equations, the remaining edges generators. */
static wr_status wr__wf_basis_build(const wr_wf *wf, wr__wf_basis *B, wr_diag *diag) {
    const wr_mesh *m = wf->mesh;
    wr__wf_tc T;
    wr_status st;
    memset(B, 0, sizeof *B);
    memset(&T, 0, sizeof T);
    B->ne = m->ne;
    st = wr__wf_tc_adjacency(wf, B, &T, diag);
    if (!st) {
        wr__wf_tc_primal(m, B, &T);
        wr__wf_tc_dual(wf, B, &T);
        st = wr__wf_tc_generators(m, B, &T, diag);
    }
    if (!st) st = wr__wf_tc_peel(m, B, &T, diag);
    if (!st) st = wr__wf_tc_assemble(m, B, &T, diag);
    wr__wf_tc_free(&T);
    if (st != WR_OK) wr__wf_basis_free(B);
    return st;
}

/* ω_e = (Z z)_e on active edges; other edges untouched. */
static void wr__wf_z_apply(const wr__wf_basis *B, const double *z, double *omega) {
    int32_t e, t;
    for (e = 0; e < B->ne; ++e) {
        double s = 0.0;
        if (!B->eact[e]) continue;
        for (t = B->zstart[e]; t < B->zstart[e + 1]; ++t) s += B->zval[t] * z[B->zcol[t]];
        omega[e] = s;
    }
}

/* gz = Zᵀ gω (gz has ncol entries, overwritten). */
static void wr__wf_z_applyT(const wr__wf_basis *B, const double *gomega, double *gz) {
    int32_t e, t;
    memset(gz, 0, sizeof(double) * (size_t)(B->ncol > 0 ? B->ncol : 0));
    for (e = 0; e < B->ne; ++e)
        if (B->eact[e])
            for (t = B->zstart[e]; t < B->zstart[e + 1]; ++t) gz[B->zcol[t]] += B->zval[t] * gomega[e];
}

/* Solve the least-squares problem min ||Z z - t||² over active edges: (ZᵀZ) z = Zᵀ t. */
static wr_status wr__wf_lsq_closed(const wr__wf_basis *B, const double *target, double *z, wr_solver_method method,
                                   wr_diag *diag) {
    wr_triplets T;
    wr_csr A;
    wr_spd_desc sd;
    wr_spd_stats ss;
    double *rhs = NULL;
    int32_t e;
    wr_status st;
    memset(&A, 0, sizeof A);
    if (B->ncol == 0) return WR_OK;
    st = wr_triplets_create(&T, B->ncol, (int64_t)B->zstart[B->ne] * 4 + 16, diag);
    if (st) return st;
    for (e = 0; e < B->ne && !st; ++e) {
        int32_t s0 = B->zstart[e], n = B->zstart[e + 1] - s0, r, c;
        if (!B->eact[e]) continue;
        for (r = 0; r < n && !st; ++r)
            for (c = 0; c < n && !st; ++c)
                st = wr_triplets_add(&T, B->zcol[s0 + r], B->zcol[s0 + c], B->zval[s0 + r] * B->zval[s0 + c], diag);
    }
    if (!st) st = wr_csr_from_triplets(&A, &T, diag);
    wr_triplets_free(&T);
    rhs = (double *)wr_alloc_array((size_t)B->ncol, sizeof(double));
    if (!st && !rhs) st = wr_fail(diag, WR_ERR_NOMEM, -1, "wf lsq: out of memory");
    if (!st) {
        int32_t i;
        wr__wf_z_applyT(B, target, rhs);
        for (i = 0; i < B->ncol; ++i) z[i] = 0.0;
        memset(&sd, 0, sizeof sd);
        sd.method = method;
        st = wr_spd_solve(&A, rhs, z, &sd, &ss, diag);
    }
    wr_free(rhs);
    wr_csr_free(&A);
    return st;
}

WRDEF wr_status wr_wf_project_closed(const wr_wf *wf, double *omega, wr_diag *diag) {
    wr__wf_basis B;
    double *z;
    wr_status st;
    if (!wf || !omega) return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "wf project: NULL argument");
    st = wr__wf_basis_build(wf, &B, diag);
    if (st) return st;
    z = (double *)wr_calloc_array((size_t)(B.ncol > 0 ? B.ncol : 1), sizeof(double));
    if (!z) {
        wr__wf_basis_free(&B);
        return wr_fail(diag, WR_ERR_NOMEM, -1, "wf project: out of memory");
    }
    st = wr__wf_lsq_closed(&B, omega, z, WR_SOLVER_AUTO, diag);
    if (!st) wr__wf_z_apply(&B, z, omega);
    wr_free(z);
    wr__wf_basis_free(&B);
    return st;
}

/* Vertices with a forced to 0: every vertex of a W face, and vertices in no face outside W. */
static void wr__wf_zero_vertices(const wr_wf *wf, uint8_t *zero) {
    const wr_mesh *m = wf->mesh;
    int32_t f, v;
    for (v = 0; v < wf->nv; ++v) zero[v] = 1;
    for (f = 0; f < wf->nf; ++f)
        if (!wf->wfree[f])
            for (v = 0; v < 3; ++v) zero[m->faces[3 * f + v]] = 0;
    for (f = 0; f < wf->nf; ++f)
        if (wf->wfree[f])
            for (v = 0; v < 3; ++v) zero[m->faces[3 * f + v]] = 1;
    if (wf->azero)
        for (v = 0; v < wf->nv; ++v)
            if (wf->azero[v]) zero[v] = 1;
}

/* WR_WF_INIT_RELEASE's k (see wr_wf_init_desc): the largest face amplitude k·sqrt(2 ε_w) is A0. */
static double wr__wf_init_k_release(const wr_wf *wf, const double lo[3], const double hi[3]) {
    double cmin = fmin(lo[0], fmin(lo[1], lo[2])), cmax = fmax(hi[0], fmax(hi[1], hi[2]));
    double side = fmax(hi[0] - lo[0], fmax(hi[1] - lo[1], hi[2] - lo[2])), smax = 0.0;
    int32_t f;
    for (f = 0; f < wf->nf; ++f)
        if (!wf->wfree[f] && wf->lambda[2 * f] < 0.0) smax = fmax(smax, sqrt(-2.0 * wf->lambda[2 * f]));
    return fmin(0.01 * (cmax - cmin), 0.1 * side) / (smax + 1e-6);
}

/* WR_WF_INIT_RELEASE's two smoothing passes: a vertex with a > 0 before the first pass takes the
 * mean of its edge neighbours' a (itself excluded), the others keep theirs. */
static wr_status wr__wf_init_smooth(const wr_wf *wf, double *a, wr_diag *diag) {
    const wr_mesh *m = wf->mesh;
    double *sum = (double *)wr_alloc_array((size_t)wf->nv, sizeof(double));
    double *deg = (double *)wr_calloc_array((size_t)wf->nv, sizeof(double));
    uint8_t *pos = (uint8_t *)wr_alloc_array((size_t)wf->nv, sizeof(uint8_t));
    int32_t v, e, pass;
    if (!sum || !deg || !pos) {
        wr_free(sum);
        wr_free(deg);
        wr_free(pos);
        return wr_fail(diag, WR_ERR_NOMEM, -1, "wf init: out of memory");
    }
    for (v = 0; v < wf->nv; ++v) pos[v] = (uint8_t)(a[v] > 0.0);
    for (e = 0; e < m->ne; ++e) {
        deg[m->edges[2 * e]] += 1.0;
        deg[m->edges[2 * e + 1]] += 1.0;
    }
    for (pass = 0; pass < 2; ++pass) {
        for (v = 0; v < wf->nv; ++v) sum[v] = 0.0;
        for (e = 0; e < m->ne; ++e) {
            sum[m->edges[2 * e]] += a[m->edges[2 * e + 1]];
            sum[m->edges[2 * e + 1]] += a[m->edges[2 * e]];
        }
        for (v = 0; v < wf->nv; ++v)
            if (pos[v] && deg[v] > 0.0) a[v] = sum[v] / deg[v];
    }
    wr_free(sum);
    wr_free(deg);
    wr_free(pos);
    return WR_OK;
}

WRDEF wr_status wr_wf_init(const wr_wf *wf, const wr_wf_init_desc *desc, double *a, double *omega, wr_diag *diag) {
    const wr_mesh *m;
    double k, lo[3], hi[3], diam;
    int32_t f, v, e, i;
    double *cnt = NULL, *tsum = NULL, *tcnt = NULL, *wd = NULL;
    uint8_t *zero = NULL, *vis = NULL;
    int32_t *queue = NULL;
    wr_status st = WR_OK;
    if (!wf || !a || !omega) return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "wf init: NULL argument");
    m = wf->mesh;
    for (i = 0; i < 3; ++i) lo[i] = hi[i] = wf->base[i];
    for (v = 0; v < wf->nv; ++v)
        for (i = 0; i < 3; ++i) {
            lo[i] = fmin(lo[i], wf->base[3 * v + i]);
            hi[i] = fmax(hi[i], wf->base[3 * v + i]);
        }
    diam = sqrt((hi[0] - lo[0]) * (hi[0] - lo[0]) + (hi[1] - lo[1]) * (hi[1] - lo[1]) + (hi[2] - lo[2]) * (hi[2] - lo[2]));
    if (desc && desc->rule != WR_WF_INIT_PAPER && desc->rule != WR_WF_INIT_RELEASE)
        return wr_fail(diag, WR_ERR_INVALID_ARG, (int32_t)desc->rule, "wf init: unknown rule %d", (int)desc->rule);
    if (desc && desc->k > 0.0)
        k = desc->k;
    else
        k = desc && desc->rule == WR_WF_INIT_RELEASE ? wr__wf_init_k_release(wf, lo, hi) : fmin(WR__WF_K_MAX, 0.1 * diam);
    if (!(k > 0.0)) return wr_fail(diag, WR_ERR_GEOMETRY, -1, "wf init: base surface has zero extent");
    cnt = (double *)wr_calloc_array((size_t)wf->nv, sizeof(double));
    tsum = (double *)wr_calloc_array((size_t)wf->ne, sizeof(double));
    tcnt = (double *)wr_calloc_array((size_t)wf->ne, sizeof(double));
    wd = (double *)wr_alloc_array((size_t)wf->nf * 2, sizeof(double));
    zero = (uint8_t *)wr_alloc_array((size_t)wf->nv, sizeof(uint8_t));
    vis = (uint8_t *)wr_calloc_array((size_t)wf->nf, sizeof(uint8_t));
    queue = (int32_t *)wr_alloc_array((size_t)wf->nf, sizeof(int32_t));
    if (!cnt || !tsum || !tcnt || !wd || !zero || !vis || !queue) {
        st = wr_fail(diag, WR_ERR_NOMEM, -1, "wf init: out of memory");
        goto done;
    }
    /* Orient the line field w consistently: BFS over compressed faces outside W, flipping w of a new
     * face when its pushforward dr_b w points against its parent's. */
    memcpy(wd, wf->wdir, sizeof(double) * 2 * (size_t)wf->nf);
    for (f = 0; f < wf->nf; ++f) {
        int32_t qh = 0, qt = 0;
        if (vis[f] || wf->wfree[f] || !(wf->lambda[2 * f] < 0.0)) continue;
        vis[f] = 1;
        queue[qt++] = f;
        while (qh < qt) {
            int32_t g = queue[qh++], c;
            const int32_t *gv = m->faces + 3 * g;
            wr_vec3 pg = wr_v3_add(wr_v3_scale(wr_v3_sub(wr_v3_load(wf->base + 3 * gv[1]), wr_v3_load(wf->base + 3 * gv[0])), wd[2 * g]),
                                   wr_v3_scale(wr_v3_sub(wr_v3_load(wf->base + 3 * gv[2]), wr_v3_load(wf->base + 3 * gv[0])), wd[2 * g + 1]));
            for (c = 0; c < 3; ++c) {
                int32_t h2 = wr__wf_face_neighbor(m, g, c);
                const int32_t *hv;
                wr_vec3 ph;
                if (h2 < 0 || vis[h2] || wf->wfree[h2] || !(wf->lambda[2 * h2] < 0.0)) continue;
                hv = m->faces + 3 * h2;
                ph = wr_v3_add(wr_v3_scale(wr_v3_sub(wr_v3_load(wf->base + 3 * hv[1]), wr_v3_load(wf->base + 3 * hv[0])), wd[2 * h2]),
                               wr_v3_scale(wr_v3_sub(wr_v3_load(wf->base + 3 * hv[2]), wr_v3_load(wf->base + 3 * hv[0])), wd[2 * h2 + 1]));
                if (wr_v3_dot(pg, ph) < 0.0) {
                    wd[2 * h2] = -wd[2 * h2];
                    wd[2 * h2 + 1] = -wd[2 * h2 + 1];
                }
                vis[h2] = 1;
                queue[qt++] = h2;
            }
        }
    }
    for (v = 0; v < wf->nv; ++v) a[v] = 0.0;
    for (f = 0; f < wf->nf; ++f) {
        double eps = -wf->lambda[2 * f], amp = 0.0;
        const double *iu = wf->iu + 3 * f;
        double p[2] = {0.0, 0.0};
        int c;
        if (!wf->wfree[f] && eps > 0.0) {
            /* App. E.2: a = k sqrt(2 ε_w); dφ ∝ (I_u w)ᵀ with ||dφ||_{I_u⁻¹} = 1/k (||w||_{I_u} = 1). */
            amp = k * sqrt(2.0 * eps);
            p[0] = (iu[0] * wd[2 * f] + iu[1] * wd[2 * f + 1]) / k;
            p[1] = (iu[1] * wd[2 * f] + iu[2] * wd[2 * f + 1]) / k;
        }
        for (c = 0; c < 3; ++c) {
            int32_t vv = m->faces[3 * f + c];
            a[vv] += amp;
            cnt[vv] += 1.0;
        }
        if (wf->wfree[f]) continue;
        /* edge targets in the face traversal: edge k goes corner (k+1)%3 -> (k+2)%3; chart vectors of
         * the three traversals: 1->2 = (-1, 1), 2->0 = (0, -1), 0->1 = (1, 0). */
        {
            static const double ev[3][2] = {{-1.0, 1.0}, {0.0, -1.0}, {1.0, 0.0}};
            for (c = 0; c < 3; ++c) {
                int32_t ee = m->face_edges[3 * f + c];
                double tloc = p[0] * ev[c][0] + p[1] * ev[c][1];
                tsum[ee] += m->face_edge_sign[3 * f + c] * tloc;
                tcnt[ee] += 1.0;
            }
        }
    }
    wr__wf_zero_vertices(wf, zero);
    for (v = 0; v < wf->nv; ++v) a[v] = (cnt[v] > 0.0 && !zero[v]) ? a[v] / cnt[v] : 0.0;
    if (desc && desc->rule == WR_WF_INIT_RELEASE && (st = wr__wf_init_smooth(wf, a, diag)) != WR_OK) goto done;
    for (e = 0; e < wf->ne; ++e) omega[e] = tcnt[e] > 0.0 ? tsum[e] / tcnt[e] : 0.0;
    st = wr_wf_project_closed(wf, omega, diag); /* App. E.2: least-squares curl-free projection */
done:
    wr_free(cnt);
    wr_free(tsum);
    wr_free(tcnt);
    wr_free(wd);
    wr_free(zero);
    wr_free(vis);
    wr_free(queue);
    return st;
}

/* ---- phase folds (see wr_wf_count_folds) ---- */
#define WR__WF_FOLD_AMP 0.2 /* faces below this fraction of max mean amplitude do not count (visible wrinkles only) */

/* Face f's dφ as a vector on the base surface (dr_b I_b⁻¹ dφᵀ) and as chart components p. */
static wr_vec3 wr__wf_dphi_vec(const wr_wf *wf, const double *omega, int32_t f, double p[2]) {
    const wr_mesh *m = wf->mesh;
    const int32_t *fv = m->faces + 3 * f;
    const double *ib = wf->ib + 3 * f;
    double w[3], det, c0, c1;
    int k;
    for (k = 0; k < 3; ++k) w[k] = m->face_edge_sign[3 * f + k] * omega[m->face_edges[3 * f + k]];
    /* Whitney face average, as in wr__wf_face_eval */
    p[0] = (-w[0] - w[1] + 2.0 * w[2]) / 3.0;
    p[1] = (w[0] - 2.0 * w[1] + w[2]) / 3.0;
    det = ib[0] * ib[2] - ib[1] * ib[1];
    if (!(det > 0.0)) det = 1.0;
    c0 = (ib[2] * p[0] - ib[1] * p[1]) / det;
    c1 = (-ib[1] * p[0] + ib[0] * p[1]) / det;
    return wr_v3_add(wr_v3_scale(wr_v3_sub(wr_v3_load(wf->base + 3 * fv[1]), wr_v3_load(wf->base + 3 * fv[0])), c0),
                     wr_v3_scale(wr_v3_sub(wr_v3_load(wf->base + 3 * fv[2]), wr_v3_load(wf->base + 3 * fv[0])), c1));
}

WRDEF int32_t wr_wf_count_folds(const wr_wf *wf, const double *a, const double *omega) {
    const wr_mesh *m;
    double amax = 0.0;
    int32_t f, e, n = 0;
    if (!wf || !a || !omega) return 0;
    m = wf->mesh;
    for (f = 0; f < wf->nf; ++f) {
        const int32_t *fv = m->faces + 3 * f;
        if (!wf->wfree[f]) amax = fmax(amax, (a[fv[0]] + a[fv[1]] + a[fv[2]]) / 3.0);
    }
    if (!(amax > 0.0)) return 0;
    for (e = 0; e < wf->ne; ++e) {
        int32_t f0 = m->edge_faces[2 * e], f1 = m->edge_faces[2 * e + 1];
        const int32_t *v0, *v1;
        double p[2];
        if (f0 < 0 || f1 < 0 || wf->wfree[f0] || wf->wfree[f1]) continue;
        v0 = m->faces + 3 * f0;
        v1 = m->faces + 3 * f1;
        if ((a[v0[0]] + a[v0[1]] + a[v0[2]]) / 3.0 < WR__WF_FOLD_AMP * amax) continue;
        if ((a[v1[0]] + a[v1[1]] + a[v1[2]]) / 3.0 < WR__WF_FOLD_AMP * amax) continue;
        if (wr_v3_dot(wr__wf_dphi_vec(wf, omega, f0, p), wr__wf_dphi_vec(wf, omega, f1, p)) < 0.0) ++n;
    }
    return n;
}

WRDEF wr_status wr_wf_unfold(const wr_wf *wf, const double *a, double *omega, wr_diag *diag) {
    const wr_mesh *m;
    double *sgn = NULL, *tsum = NULL, *tcnt = NULL, best = -1.0;
    int32_t *queue = NULL, f, e, seed;
    wr_status st = WR_OK;
    if (!wf || !a || !omega) return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "wf unfold: NULL argument");
    m = wf->mesh;
    sgn = (double *)wr_calloc_array((size_t)wf->nf, sizeof(double));
    tsum = (double *)wr_calloc_array((size_t)wf->ne, sizeof(double));
    tcnt = (double *)wr_calloc_array((size_t)wf->ne, sizeof(double));
    queue = (int32_t *)wr_alloc_array((size_t)wf->nf, sizeof(int32_t));
    if (!sgn || !tsum || !tcnt || !queue) {
        st = wr_fail(diag, WR_ERR_NOMEM, -1, "wf unfold: out of memory");
        goto done;
    }
    /* one sweep per connected component outside W, seeded at its largest-amplitude face */
    for (;;) {
        int32_t qh = 0, qt = 0;
        seed = -1;
        best = -1.0;
        for (f = 0; f < wf->nf; ++f) {
            const int32_t *fv = m->faces + 3 * f;
            double am = (a[fv[0]] + a[fv[1]] + a[fv[2]]) / 3.0;
            if (wf->wfree[f] || sgn[f] != 0.0) continue;
            if (am > best) {
                best = am;
                seed = f;
            }
        }
        if (seed < 0) break;
        sgn[seed] = 1.0;
        queue[qt++] = seed;
        while (qh < qt) {
            int32_t g = queue[qh++], c;
            double p[2];
            wr_vec3 vg = wr_v3_scale(wr__wf_dphi_vec(wf, omega, g, p), sgn[g]);
            for (c = 0; c < 3; ++c) {
                int32_t ee = m->face_edges[3 * g + c];
                int32_t h2 = m->edge_faces[2 * ee] == g ? m->edge_faces[2 * ee + 1] : m->edge_faces[2 * ee];
                if (h2 < 0 || wf->wfree[h2] || sgn[h2] != 0.0) continue;
                sgn[h2] = wr_v3_dot(vg, wr__wf_dphi_vec(wf, omega, h2, p)) < 0.0 ? -1.0 : 1.0;
                queue[qt++] = h2;
            }
        }
    }
    /* edge targets: the oriented faces' phase change along the edge (chart vectors of the three
     * traversals as in wr_wf_init: 1->2 = (-1, 1), 2->0 = (0, -1), 0->1 = (1, 0)) */
    for (f = 0; f < wf->nf; ++f) {
        static const double ev[3][2] = {{-1.0, 1.0}, {0.0, -1.0}, {1.0, 0.0}};
        double p[2];
        int c;
        if (wf->wfree[f]) continue;
        (void)wr__wf_dphi_vec(wf, omega, f, p);
        for (c = 0; c < 3; ++c) {
            int32_t ee = m->face_edges[3 * f + c];
            tsum[ee] += m->face_edge_sign[3 * f + c] * sgn[f] * (p[0] * ev[c][0] + p[1] * ev[c][1]);
            tcnt[ee] += 1.0;
        }
    }
    for (e = 0; e < wf->ne; ++e)
        if (tcnt[e] > 0.0) omega[e] = tsum[e] / tcnt[e];
    st = wr_wf_project_closed(wf, omega, diag);
done:
    wr_free(sgn);
    wr_free(tsum);
    wr_free(tcnt);
    wr_free(queue);
    return st;
}

/* ---- phase extraction (App. E.4) ---- */

/* Weighted union-find over face corners: off[x] = φ_x - φ_parent(x). */
static int32_t wr__wf_uf_find(int32_t *par, double *off, int32_t x) {
    int32_t r = x, y;
    double acc = 0.0, t;
    while (par[r] != r) r = par[r];
    /* path compression with offsets: walk again, making every node point to r */
    y = x;
    acc = 0.0;
    {
        int32_t z = x;
        while (par[z] != z) {
            acc += off[z];
            z = par[z];
        }
    }
    while (par[y] != y) {
        int32_t nxt = par[y];
        t = off[y];
        off[y] = acc;
        par[y] = r;
        acc -= t;
        y = nxt;
    }
    return r;
}

/* State of the phase reconstruction (wr_wf_phase's stages). Corners are indexed 3f + c. */
typedef struct wr__wf_ph {
    const wr_wf *wf;
    const double *omega;
    int32_t *par, *cls, *croot, ncls; /* union–find over corners; class of each root; root of each class */
    double *off, *phi0;               /* φ(corner) − φ(root) of the union–find; tree-integrated φ */
    double *rhs, *sol;
    uint8_t *fixed;
    wr_triplets T;
    wr_csr A;
    wr_wf_phase_stats ps;
} wr__wf_ph;

static void wr__wf_ph_free(wr__wf_ph *P) {
    wr_triplets_free(&P->T);
    wr_csr_free(&P->A);
    wr_free(P->par);
    wr_free(P->cls);
    wr_free(P->croot);
    wr_free(P->off);
    wr_free(P->phi0);
    wr_free(P->rhs);
    wr_free(P->sol);
    wr_free(P->fixed);
}

/* 1. Integrate ω along a BFS tree of the dual graph outside W (one disk per component). */
static wr_status wr__wf_ph_integrate(wr__wf_ph *P, wr_diag *diag) {
    const wr_mesh *m = P->wf->mesh;
    const uint8_t *wfree = P->wf->wfree;
    const double *omega = P->omega;
    int32_t nf = m->nf, f, qh, qt;
    int32_t *queue = (int32_t *)wr_alloc_array((size_t)nf, sizeof(int32_t));
    uint8_t *vis = (uint8_t *)wr_calloc_array((size_t)nf, sizeof(uint8_t));
    if (!queue || !vis) {
        wr_free(queue);
        wr_free(vis);
        return wr_fail(diag, WR_ERR_NOMEM, -1, "wf phase: out of memory");
    }
    for (f = 0; f < nf; ++f) {
        if (vis[f] || wfree[f]) continue;
        vis[f] = 1;
        qh = qt = 0;
        queue[qt++] = f;
        /* root: φ(corner 0) = 0, then along edge 2 (0->1) and edge 1 (2->0) */
        P->phi0[3 * f] = 0.0;
        P->phi0[3 * f + 1] = m->face_edge_sign[3 * f + 2] * omega[m->face_edges[3 * f + 2]];
        P->phi0[3 * f + 2] = -m->face_edge_sign[3 * f + 1] * omega[m->face_edges[3 * f + 1]];
        while (qh < qt) {
            int32_t g = queue[qh++], k;
            for (k = 0; k < 3; ++k) {
                int32_t h2 = wr__wf_face_neighbor(m, g, k), c, d, shared = 0, third = -1;
                if (h2 < 0 || vis[h2] || wfree[h2]) continue;
                vis[h2] = 1;
                queue[qt++] = h2;
                /* copy the two shared corners, integrate to the third along an edge of h2 */
                for (c = 0; c < 3; ++c) {
                    int32_t vh = m->faces[3 * h2 + c], found = 0;
                    for (d = 0; d < 3; ++d)
                        if (m->faces[3 * g + d] == vh) {
                            P->phi0[3 * h2 + c] = P->phi0[3 * g + d];
                            found = 1;
                        }
                    if (found)
                        ++shared;
                    else
                        third = c;
                }
                if (shared == 2 && third >= 0) {
                    /* the edge opposite corner (third+1)%3 runs from corner (third+2)%3 to corner third */
                    int32_t kk = (third + 1) % 3, from = (third + 2) % 3;
                    P->phi0[3 * h2 + third] =
                        P->phi0[3 * h2 + from] + m->face_edge_sign[3 * h2 + kk] * omega[m->face_edges[3 * h2 + kk]];
                }
            }
        }
    }
    wr_free(queue);
    wr_free(vis);
    return WR_OK;
}

/* 2. Glue corners across every interior edge outside W with the rounded jump (a multiple of 2π). */
static void wr__wf_ph_glue(wr__wf_ph *P) {
    const wr_mesh *m = P->wf->mesh;
    const uint8_t *wfree = P->wf->wfree;
    int32_t i, e;
    for (i = 0; i < m->nf * 3; ++i) P->par[i] = i;
    for (e = 0; e < m->ne; ++e) {
        int32_t f0 = m->edge_faces[2 * e], f1 = m->edge_faces[2 * e + 1], end;
        double J = 0.0, n;
        int32_t c0[2], c1[2];
        if (f0 < 0 || f1 < 0 || wfree[f0] || wfree[f1]) continue;
        for (end = 0; end < 2; ++end) {
            int32_t vtx = m->edges[2 * e + end], c;
            for (c = 0; c < 3; ++c) {
                if (m->faces[3 * f0 + c] == vtx) c0[end] = 3 * f0 + c;
                if (m->faces[3 * f1 + c] == vtx) c1[end] = 3 * f1 + c;
            }
            J += 0.5 * (P->phi0[c1[end]] - P->phi0[c0[end]]);
        }
        n = floor(J / (2.0 * WR__WF_PI) + 0.5);
        if (fabs(J) > 1e-9 * (1.0 + fabs(P->phi0[c0[0]]))) P->ps.n_cut_edges++;
        if (n != 0.0) P->ps.n_nonzero_jumps++;
        for (end = 0; end < 2; ++end) {
            int32_t ra = wr__wf_uf_find(P->par, P->off, c0[end]), rb = wr__wf_uf_find(P->par, P->off, c1[end]);
            double d = 2.0 * WR__WF_PI * n; /* φ(c1) - φ(c0) */
            if (ra == rb) {
                if (fabs(P->off[c1[end]] - P->off[c0[end]] - d) > 1e-6) P->ps.n_conflicts++;
                continue;
            }
            /* φ_rb = φ_c1 - off_c1 = φ_c0 + d - off_c1 = φ_ra + off_c0 + d - off_c1 */
            P->par[rb] = ra;
            P->off[rb] = P->off[c0[end]] + d - P->off[c1[end]];
        }
    }
}

/* 3a. Number the corner classes (union–find roots) of faces outside W. */
static void wr__wf_ph_classes(wr__wf_ph *P) {
    const wr_mesh *m = P->wf->mesh;
    int32_t i, f;
    for (i = 0; i < m->nf * 3; ++i) P->cls[i] = -1;
    for (f = 0; f < m->nf; ++f) {
        int c;
        if (P->wf->wfree[f]) continue;
        for (c = 0; c < 3; ++c) {
            int32_t r = wr__wf_uf_find(P->par, P->off, 3 * f + c);
            if (P->cls[r] < 0) {
                P->cls[r] = P->ncls;
                P->croot[P->ncls++] = r;
            }
        }
    }
}

/* 3b. Least squares over the classes: Σ_faces Σ_edges (φ_to − φ_from − ω̃)², a graph Laplacian. */
static wr_status wr__wf_ph_system(wr__wf_ph *P, wr_diag *diag) {
    const wr_mesh *m = P->wf->mesh;
    const double *omega = P->omega;
    int32_t f;
    wr_status st;
    P->rhs = (double *)wr_calloc_array((size_t)P->ncls, sizeof(double));
    P->sol = (double *)wr_calloc_array((size_t)P->ncls, sizeof(double));
    P->fixed = (uint8_t *)wr_calloc_array((size_t)P->ncls, sizeof(uint8_t));
    if (!P->rhs || !P->sol || !P->fixed) return wr_fail(diag, WR_ERR_NOMEM, -1, "wf phase: out of memory");
    st = wr_triplets_create(&P->T, P->ncls, (int64_t)m->nf * 12, diag);
    for (f = 0; f < m->nf && !st; ++f) {
        int k;
        if (P->wf->wfree[f]) continue;
        for (k = 0; k < 3 && !st; ++k) {
            int32_t ca = 3 * f + (k + 1) % 3, cb = 3 * f + (k + 2) % 3;
            int32_t ia = P->cls[wr__wf_uf_find(P->par, P->off, ca)], ib = P->cls[wr__wf_uf_find(P->par, P->off, cb)];
            /* residual: (x_b + off_b) - (x_a + off_a) - ω̃ */
            double r0 = P->off[cb] - P->off[ca] - m->face_edge_sign[3 * f + k] * omega[m->face_edges[3 * f + k]];
            if (ia == ib) continue; /* constant residual (a conflict or a degenerate loop) */
            st = wr_triplets_add(&P->T, ia, ia, 1.0, diag);
            if (!st) st = wr_triplets_add(&P->T, ib, ib, 1.0, diag);
            if (!st) st = wr_triplets_add(&P->T, ia, ib, -1.0, diag);
            if (!st) st = wr_triplets_add(&P->T, ib, ia, -1.0, diag);
            P->rhs[ia] += r0;
            P->rhs[ib] -= r0;
        }
    }
    if (!st) st = wr_csr_from_triplets(&P->A, &P->T, diag);
    return st;
}

/* 3c. Gauge: one fixed class per connected component of the class graph, at its tree-integrated
 * value; then solve the Laplacian (isolated classes get a unit diagonal). */
static wr_status wr__wf_ph_solve(wr__wf_ph *P, wr_diag *diag) {
    wr_csr *A = &P->A;
    wr_spd_desc sd;
    wr_spd_stats ss;
    int32_t s;
    int32_t *q2 = (int32_t *)wr_alloc_array((size_t)P->ncls, sizeof(int32_t));
    uint8_t *seen = (uint8_t *)wr_calloc_array((size_t)P->ncls, sizeof(uint8_t));
    if (!q2 || !seen) {
        wr_free(q2);
        wr_free(seen);
        return wr_fail(diag, WR_ERR_NOMEM, -1, "wf phase: out of memory");
    }
    for (s = 0; s < P->ncls; ++s) {
        int32_t h0 = 0, t0 = 0;
        if (seen[s]) continue;
        seen[s] = 1;
        P->fixed[s] = 1;
        P->sol[s] = P->phi0[P->croot[s]];
        q2[t0++] = s;
        while (h0 < t0) {
            int32_t u = q2[h0++], t;
            for (t = A->rowptr[u]; t < A->rowptr[u + 1]; ++t)
                if (A->col[t] != u && A->val[t] != 0.0 && !seen[A->col[t]]) {
                    seen[A->col[t]] = 1;
                    q2[t0++] = A->col[t];
                }
        }
    }
    wr_free(q2);
    wr_free(seen);
    memset(&sd, 0, sizeof sd);
    sd.fixed = P->fixed;
    for (s = 0; s < P->ncls; ++s) {
        int32_t p = wr_csr_find(A, s, s);
        if (p >= 0 && A->val[p] == 0.0) A->val[p] = 1.0;
    }
    return wr_spd_solve(A, P->rhs, P->sol, &sd, &ss, diag);
}

/* Corner phases from the class solution, and the largest residual |φ_to − φ_from − ω̃| left. */
static void wr__wf_ph_write(wr__wf_ph *P, double *phi) {
    const wr_mesh *m = P->wf->mesh;
    int32_t f;
    for (f = 0; f < m->nf; ++f) {
        int c, k;
        if (P->wf->wfree[f]) continue;
        for (c = 0; c < 3; ++c) {
            int32_t r = wr__wf_uf_find(P->par, P->off, 3 * f + c);
            phi[3 * f + c] = P->sol[P->cls[r]] + P->off[3 * f + c];
        }
        for (k = 0; k < 3; ++k) {
            double r = phi[3 * f + (k + 2) % 3] - phi[3 * f + (k + 1) % 3] -
                       m->face_edge_sign[3 * f + k] * P->omega[m->face_edges[3 * f + k]];
            P->ps.max_residual = fmax(P->ps.max_residual, fabs(r));
        }
    }
}

WRDEF wr_status wr_wf_phase(const wr_wf *wf, const double *omega, double *phi, wr_wf_phase_stats *stats,
                            wr_diag *diag) {
    wr__wf_ph P;
    int32_t i, nf;
    wr_status st;
    memset(&P, 0, sizeof P);
    if (!wf || !omega || !phi) return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "wf phase: NULL argument");
    P.wf = wf;
    P.omega = omega;
    nf = wf->mesh->nf;
    P.par = (int32_t *)wr_alloc_array((size_t)nf * 3, sizeof(int32_t));
    P.cls = (int32_t *)wr_alloc_array((size_t)nf * 3, sizeof(int32_t));
    P.croot = (int32_t *)wr_alloc_array((size_t)nf * 3, sizeof(int32_t));
    P.off = (double *)wr_calloc_array((size_t)nf * 3, sizeof(double));
    P.phi0 = (double *)wr_calloc_array((size_t)nf * 3, sizeof(double));
    if (!P.par || !P.cls || !P.croot || !P.off || !P.phi0) {
        st = wr_fail(diag, WR_ERR_NOMEM, -1, "wf phase: out of memory");
    } else {
        for (i = 0; i < nf * 3; ++i) phi[i] = 0.0;
        st = wr__wf_ph_integrate(&P, diag);
        if (!st) {
            wr__wf_ph_glue(&P);
            wr__wf_ph_classes(&P);
        }
        if (!st && P.ncls > 0) {
            st = wr__wf_ph_system(&P, diag);
            if (!st) st = wr__wf_ph_solve(&P, diag);
            if (!st) wr__wf_ph_write(&P, phi);
        }
    }
    if (stats) *stats = P.ps;
    wr__wf_ph_free(&P);
    return st;
}

/* ---- Loop subdivision and upsampling (App. E.5) ---- */

/* Loop's interior even weight β(n) (Loop 1987). */
static double wr__wf_loop_beta(int32_t n) {
    double c = 0.375 + 0.25 * cos(2.0 * WR__WF_PI / (double)n);
    return (0.625 - c * c) / (double)n;
}

static int32_t wr__wf_opposite(const wr_mesh *m, int32_t f, int32_t e) {
    int k;
    for (k = 0; k < 3; ++k)
        if (m->face_edges[3 * f + k] == e) return m->faces[3 * f + k];
    return -1;
}

/* Per-vertex Loop stencil data: nb = valence, nbnd = boundary edges, bnb = the two boundary neighbours. */
typedef struct wr__wf_vstencil {
    int32_t *n, *nbnd, *bnb;
} wr__wf_vstencil;

static wr_status wr__wf_vstencil_build(const wr_mesh *m, wr__wf_vstencil *S, wr_diag *diag) {
    int32_t e, v;
    S->n = (int32_t *)wr_calloc_array((size_t)m->nv, sizeof(int32_t));
    S->nbnd = (int32_t *)wr_calloc_array((size_t)m->nv, sizeof(int32_t));
    S->bnb = (int32_t *)wr_alloc_array((size_t)m->nv * 2, sizeof(int32_t));
    if (!S->n || !S->nbnd || !S->bnb) {
        wr_free(S->n);
        wr_free(S->nbnd);
        wr_free(S->bnb);
        return wr_fail(diag, WR_ERR_NOMEM, -1, "loop: out of memory");
    }
    for (v = 0; v < 2 * m->nv; ++v) S->bnb[v] = -1;
    for (e = 0; e < m->ne; ++e) {
        int32_t i = m->edges[2 * e], j = m->edges[2 * e + 1];
        int bnd = m->edge_faces[2 * e] < 0 || m->edge_faces[2 * e + 1] < 0;
        S->n[i]++;
        S->n[j]++;
        if (bnd) {
            if (S->nbnd[i] < 2) S->bnb[2 * i + S->nbnd[i]] = j;
            if (S->nbnd[j] < 2) S->bnb[2 * j + S->nbnd[j]] = i;
            S->nbnd[i]++;
            S->nbnd[j]++;
        }
    }
    return WR_OK;
}

static void wr__wf_vstencil_free(wr__wf_vstencil *S) {
    wr_free(S->n);
    wr_free(S->nbnd);
    wr_free(S->bnb);
}

/* Weight of neighbour u in the even rule of v: kind 0 = interior (β), 1 = boundary neighbour, -1 =
 * not in the stencil. Returns the weight applied to (x_u - x_v). */
static double wr__wf_even_weight(const wr__wf_vstencil *S, int32_t v, int32_t u, int bnd_edge, int mode) {
    if (S->nbnd[v] == 0) return wr__wf_loop_beta(S->n[v]);
    if (S->nbnd[v] == 2 && mode == WR_WF_LOOP_BOUNDARY_SPLINE && bnd_edge) return 0.125;
    (void)u;
    return 0.0; /* FIXED boundary, corner or non-manifold: the vertex stays */
}

WRDEF wr_status wr_wf_loop_step(const wr_mesh *m, int32_t ncomp, const double *vals, const wr_wf_loop_desc *desc,
                                int32_t **fine_faces, double **fine_vals, wr_diag *diag) {
    int mode = desc ? desc->boundary : WR_WF_LOOP_BOUNDARY_FIXED;
    int32_t nv, ne, nf, e, f, v, c;
    double *out;
    int32_t *ff;
    wr__wf_vstencil S;
    wr_status st;
    if (!m || !vals || !fine_faces || !fine_vals || ncomp < 1)
        return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "loop: NULL argument or ncomp < 1");
    if (mode != WR_WF_LOOP_BOUNDARY_FIXED && mode != WR_WF_LOOP_BOUNDARY_SPLINE)
        return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "loop: unknown boundary mode %d", mode);
    *fine_faces = NULL;
    *fine_vals = NULL;
    nv = m->nv;
    ne = m->ne;
    nf = m->nf;
    if ((int64_t)nv + ne > INT32_MAX / 2 || (int64_t)nf * 4 > INT32_MAX / 4)
        return wr_fail(diag, WR_ERR_OVERFLOW, -1, "loop: subdivided mesh too large");
    st = wr__wf_vstencil_build(m, &S, diag);
    if (st) return st;
    out = (double *)wr_alloc_array((size_t)(nv + ne) * (size_t)ncomp, sizeof(double));
    ff = (int32_t *)wr_alloc_array((size_t)nf * 12, sizeof(int32_t));
    if (!out || !ff) {
        wr_free(out);
        wr_free(ff);
        wr__wf_vstencil_free(&S);
        return wr_fail(diag, WR_ERR_NOMEM, -1, "loop: out of memory");
    }
    /* even vertices: x_v + Σ w (x_u - x_v) (the affine form of the Loop masks) */
    for (v = 0; v < nv; ++v)
        for (c = 0; c < ncomp; ++c) out[(size_t)v * ncomp + c] = vals[(size_t)v * ncomp + c];
    for (e = 0; e < ne; ++e) {
        int32_t i = m->edges[2 * e], j = m->edges[2 * e + 1];
        int bnd = m->edge_faces[2 * e] < 0 || m->edge_faces[2 * e + 1] < 0;
        double wi = wr__wf_even_weight(&S, i, j, bnd, mode), wj = wr__wf_even_weight(&S, j, i, bnd, mode);
        for (c = 0; c < ncomp; ++c) {
            double d = vals[(size_t)j * ncomp + c] - vals[(size_t)i * ncomp + c];
            out[(size_t)i * ncomp + c] += wi * d;
            out[(size_t)j * ncomp + c] -= wj * d;
        }
    }
    /* odd vertices */
    for (e = 0; e < ne; ++e) {
        int32_t i = m->edges[2 * e], j = m->edges[2 * e + 1], f0 = m->edge_faces[2 * e], f1 = m->edge_faces[2 * e + 1];
        double *o = out + (size_t)(nv + e) * ncomp;
        if (f0 >= 0 && f1 >= 0) {
            int32_t p = wr__wf_opposite(m, f0, e), q = wr__wf_opposite(m, f1, e);
            for (c = 0; c < ncomp; ++c)
                o[c] = 0.375 * (vals[(size_t)i * ncomp + c] + vals[(size_t)j * ncomp + c]) +
                       0.125 * (vals[(size_t)p * ncomp + c] + vals[(size_t)q * ncomp + c]);
        } else {
            for (c = 0; c < ncomp; ++c) o[c] = 0.5 * (vals[(size_t)i * ncomp + c] + vals[(size_t)j * ncomp + c]);
        }
    }
    for (f = 0; f < nf; ++f) {
        const int32_t *fv = m->faces + 3 * f;
        int32_t m0 = nv + m->face_edges[3 * f], m1 = nv + m->face_edges[3 * f + 1], m2 = nv + m->face_edges[3 * f + 2];
        int32_t *o = ff + 12 * (size_t)f;
        o[0] = fv[0], o[1] = m2, o[2] = m1;
        o[3] = fv[1], o[4] = m0, o[5] = m2;
        o[6] = fv[2], o[7] = m1, o[8] = m0;
        o[9] = m0, o[10] = m1, o[11] = m2;
    }
    wr__wf_vstencil_free(&S);
    *fine_faces = ff;
    *fine_vals = out;
    return WR_OK;
}

WRDEF void wr_wf_loop_corner_rest(int32_t nf, const double *corner_rest, double *fine) {
    int32_t f, c, k;
    for (f = 0; f < nf; ++f) {
        const double *p = corner_rest + 6 * (size_t)f;
        double q[12], *o = fine + 24 * (size_t)f; /* corners 0..2, then midpoints m0..m2 */
        /* children as in wr_wf_loop_step: (c0, m2, m1), (c1, m0, m2), (c2, m1, m0), (m0, m1, m2) */
        static const int child[12] = {0, 5, 4, 1, 3, 5, 2, 4, 3, 3, 4, 5};
        for (c = 0; c < 6; ++c) q[c] = p[c];
        for (k = 0; k < 3; ++k) { /* m_k: the midpoint of the edge opposite corner k */
            int32_t a = (k + 1) % 3, b = (k + 2) % 3;
            q[6 + 2 * k] = 0.5 * (p[2 * a] + p[2 * b]);
            q[7 + 2 * k] = 0.5 * (p[2 * a + 1] + p[2 * b + 1]);
        }
        for (c = 0; c < 12; ++c) {
            int32_t j = child[c] < 3 ? 2 * child[c] : 6 + 2 * (child[c] - 3);
            o[2 * c] = q[j];
            o[2 * c + 1] = q[j + 1];
        }
    }
}

/* One Loop step of the per-corner phase (nf*3) outside W: every stencil is written as the corner's
 * own value plus weighted differences along edges, and a difference along an edge is taken inside a
 * face outside W containing it (0 when there is none), so 2π jumps between sheets never mix. */
static wr_status wr__wf_loop_phase(const wr_mesh *m, const uint8_t *wfree, const double *phi, int mode,
                                   double *fine_phi /* 4nf*3 */, wr_diag *diag) {
    int32_t e, f, k;
    double *ed = NULL, *delta = NULL;
    wr__wf_vstencil S;
    wr_status st = wr__wf_vstencil_build(m, &S, diag);
    if (st) return st;
    ed = (double *)wr_calloc_array((size_t)m->ne, sizeof(double));
    delta = (double *)wr_calloc_array((size_t)m->nv, sizeof(double));
    if (!ed || !delta) {
        wr_free(ed);
        wr_free(delta);
        wr__wf_vstencil_free(&S);
        return wr_fail(diag, WR_ERR_NOMEM, -1, "loop phase: out of memory");
    }
    /* ed[e] = φ(hi) - φ(lo) inside some face outside W */
    for (f = 0; f < m->nf; ++f) {
        if (wfree[f]) continue;
        for (k = 0; k < 3; ++k) {
            int32_t ee = m->face_edges[3 * f + k];
            double d = phi[3 * f + (k + 2) % 3] - phi[3 * f + (k + 1) % 3];
            ed[ee] = m->face_edge_sign[3 * f + k] * d;
        }
    }
    for (e = 0; e < m->ne; ++e) {
        int32_t i = m->edges[2 * e], j = m->edges[2 * e + 1];
        int bnd = m->edge_faces[2 * e] < 0 || m->edge_faces[2 * e + 1] < 0;
        delta[i] += wr__wf_even_weight(&S, i, j, bnd, mode) * ed[e];
        delta[j] -= wr__wf_even_weight(&S, j, i, bnd, mode) * ed[e];
    }
    for (f = 0; f < m->nf; ++f) {
        double val[6]; /* corners 0..2, then odd points on edges 0..2 */
        int c;
        if (wfree[f]) {
            for (c = 0; c < 12; ++c) fine_phi[12 * (size_t)f + c] = 0.0;
            continue;
        }
        for (c = 0; c < 3; ++c) val[c] = phi[3 * f + c] + delta[m->faces[3 * f + c]];
        for (k = 0; k < 3; ++k) {
            int32_t ee = m->face_edges[3 * f + k], p = (k + 1) % 3, q = (k + 2) % 3;
            int32_t f0 = m->edge_faces[2 * ee], f1 = m->edge_faces[2 * ee + 1];
            double base = phi[3 * f + p], dq = phi[3 * f + q] - base, dr = phi[3 * f + k] - base;
            if (f0 >= 0 && f1 >= 0) {
                int32_t g = f0 == f ? f1 : f0, s = wr__wf_opposite(m, g, ee), vp = m->faces[3 * f + p], t;
                double ds = 0.0;
                /* difference p -> s along edge (p, s) of g */
                for (t = 0; t < 3; ++t) {
                    int32_t e2 = m->face_edges[3 * g + t];
                    if ((m->edges[2 * e2] == vp && m->edges[2 * e2 + 1] == s) ||
                        (m->edges[2 * e2] == s && m->edges[2 * e2 + 1] == vp))
                        ds = m->edges[2 * e2] == vp ? ed[e2] : -ed[e2];
                }
                val[3 + k] = base + 0.375 * dq + 0.125 * dr + 0.125 * ds;
            } else {
                val[3 + k] = base + 0.5 * dq;
            }
        }
        /* children as in wr_wf_loop_step: (c0, m2, m1), (c1, m0, m2), (c2, m1, m0), (m0, m1, m2) */
        {
            double *o = fine_phi + 12 * (size_t)f;
            o[0] = val[0], o[1] = val[5], o[2] = val[4];
            o[3] = val[1], o[4] = val[3], o[5] = val[5];
            o[6] = val[2], o[7] = val[4], o[8] = val[3];
            o[9] = val[3], o[10] = val[4], o[11] = val[5];
        }
    }
    wr_free(ed);
    wr_free(delta);
    wr__wf_vstencil_free(&S);
    return WR_OK;
}

/* The upsampling's current level: mesh (base positions, rest), amplitude per vertex, phase per
 * corner (3 per face), wrinkle-free flag per face. */
typedef struct wr__wf_up {
    wr_mesh cur;
    double *ca, *cphi;
    uint8_t *cw;
    int32_t ncomp; /* components Loop-subdivided per vertex: position (3), rest (2, if any), a */
    int has_rest, mode;
} wr__wf_up;

/* The subdivided level's mesh from the Loop-averaged vertex values (nvf vertices, nf4 faces) and
 * its amplitudes, zero on vertices touching only W faces. */
static wr_status wr__wf_up_fine_mesh(wr__wf_up *U, int32_t nvf, const double *fvals, const int32_t *ffaces,
                                     const uint8_t *fw, wr_mesh *fine, double **fine_a, wr_diag *diag) {
    int32_t v, ncomp = U->ncomp;
    double *p3 = (double *)wr_alloc_array((size_t)nvf * 3, sizeof(double));
    double *r2 = U->has_rest ? (double *)wr_alloc_array((size_t)nvf * 2, sizeof(double)) : NULL;
    double *na = (double *)wr_alloc_array((size_t)nvf, sizeof(double));
    wr_status st;
    if (!p3 || (U->has_rest && !r2) || !na) {
        wr_free(p3);
        wr_free(r2);
        wr_free(na);
        return wr_fail(diag, WR_ERR_NOMEM, -1, "wf upsample: out of memory");
    }
    for (v = 0; v < nvf; ++v) {
        const double *iv = fvals + (size_t)v * ncomp;
        p3[3 * v] = iv[0];
        p3[3 * v + 1] = iv[1];
        p3[3 * v + 2] = iv[2];
        if (U->has_rest) {
            r2[2 * v] = iv[3];
            r2[2 * v + 1] = iv[4];
        }
        na[v] = iv[ncomp - 1];
    }
    st = wr_mesh_create(fine, nvf, p3, r2, 4 * U->cur.nf, ffaces, diag);
    wr_free(p3);
    wr_free(r2);
    if (st) {
        wr_free(na);
        return st;
    }
    for (v = 0; v < nvf; ++v) {
        int32_t t, anyk = 0;
        for (t = fine->vf_start[v]; t < fine->vf_start[v + 1]; ++t) anyk |= !fw[fine->vf[t]];
        if (!anyk) na[v] = 0.0;
    }
    *fine_a = na;
    return WR_OK;
}

/* One Loop level (App. E.5): positions, rest coordinates and amplitude by Loop's rules, the corner
 * phases by wr__wf_loop_phase (the phase is multivalued: it is subdivided per face), W inherited
 * by the four children of each face. */
static wr_status wr__wf_up_level(wr__wf_up *U, wr_diag *diag) {
    wr_mesh *cur = &U->cur, fine;
    wr_wf_loop_desc ld;
    double *vals, *fvals = NULL, *fphi = NULL, *fine_a = NULL;
    uint8_t *fw = NULL;
    int32_t *ffaces = NULL, v, f, c, ncomp = U->ncomp;
    wr_status st;
    ld.boundary = U->mode;
    vals = (double *)wr_alloc_array((size_t)cur->nv * (size_t)ncomp, sizeof(double));
    if (!vals) return wr_fail(diag, WR_ERR_NOMEM, -1, "wf upsample: out of memory");
    for (v = 0; v < cur->nv; ++v) {
        double *o = vals + (size_t)v * ncomp;
        o[0] = cur->pos[3 * v];
        o[1] = cur->pos[3 * v + 1];
        o[2] = cur->pos[3 * v + 2];
        if (U->has_rest) {
            o[3] = cur->rest[2 * v];
            o[4] = cur->rest[2 * v + 1];
        }
        o[ncomp - 1] = U->ca[v];
    }
    st = wr_wf_loop_step(cur, ncomp, vals, &ld, &ffaces, &fvals, diag);
    wr_free(vals);
    if (!st) {
        fphi = (double *)wr_alloc_array((size_t)cur->nf * 12, sizeof(double));
        fw = (uint8_t *)wr_alloc_array((size_t)cur->nf * 4, sizeof(uint8_t));
        if (!fphi || !fw) st = wr_fail(diag, WR_ERR_NOMEM, -1, "wf upsample: out of memory");
    }
    if (!st) st = wr__wf_loop_phase(cur, U->cw, U->cphi, U->mode, fphi, diag);
    if (!st) {
        for (f = 0; f < cur->nf; ++f)
            for (c = 0; c < 4; ++c) fw[4 * f + c] = U->cw[f];
        st = wr__wf_up_fine_mesh(U, cur->nv + cur->ne, fvals, ffaces, fw, &fine, &fine_a, diag);
    }
    wr_free(fvals);
    wr_free(ffaces);
    if (st) {
        wr_free(fphi);
        wr_free(fw);
        return st;
    }
    wr_free(U->ca);
    U->ca = fine_a;
    wr_free(U->cphi);
    U->cphi = fphi;
    wr_free(U->cw);
    U->cw = fw;
    wr_mesh_free(cur);
    *cur = fine;
    return WR_OK;
}

/* Eq. 19 without v1 (App. E.5): r = r_b + a cos φ n̂_b + (a²/8) sin 2φ ∇_b φ on the finest level,
 * n̂_b the area-weighted vertex normal, ∇_b φ the area-weighted average of the faces' gradients. */
/* vphi, vwr (nv each, zeroed by the caller): out, per vertex the φ of one incident wrinkled face's
 * corner (any sheet will do: only cos φ and sin 2φ enter) and 1 when the vertex touches a face not
 * in W. */
static wr_status wr__wf_up_displace(const wr__wf_up *U, int inplane, double *disp, double *vphi, uint8_t *vwr,
                                    wr_diag *diag) {
    const wr_mesh *cur = &U->cur;
    const double *cphi = U->cphi;
    int32_t f, v, c;
    double *grad = (double *)wr_calloc_array((size_t)cur->nv * 3, sizeof(double));
    double *wsum = (double *)wr_calloc_array((size_t)cur->nv, sizeof(double));
    double *nrm = (double *)wr_calloc_array((size_t)cur->nv * 3, sizeof(double));
    wr_status st = WR_OK;
    if (!grad || !wsum || !nrm) {
        st = wr_fail(diag, WR_ERR_NOMEM, -1, "wf upsample: out of memory");
        goto done;
    }
    for (f = 0; f < cur->nf; ++f) {
        const int32_t *fv = cur->faces + 3 * f;
        wr_vec3 P0 = wr_v3_load(cur->pos + 3 * fv[0]), P1 = wr_v3_load(cur->pos + 3 * fv[1]),
                P2 = wr_v3_load(cur->pos + 3 * fv[2]);
        wr_vec3 N = wr_v3_cross(wr_v3_sub(P1, P0), wr_v3_sub(P2, P0)), g0, g1, g2, gp;
        double N2 = wr_v3_dot(N, N), A = 0.5 * sqrt(N2);
        for (c = 0; c < 3; ++c) {
            nrm[3 * fv[c]] += N.x;
            nrm[3 * fv[c] + 1] += N.y;
            nrm[3 * fv[c] + 2] += N.z;
        }
        if (U->cw[f] || !(N2 > 0.0)) continue;
        /* ∇λ_i = N × e_i / |N|², e_i the edge opposite corner i (CCW) */
        g0 = wr_v3_scale(wr_v3_cross(N, wr_v3_sub(P2, P1)), 1.0 / N2);
        g1 = wr_v3_scale(wr_v3_cross(N, wr_v3_sub(P0, P2)), 1.0 / N2);
        g2 = wr_v3_scale(wr_v3_cross(N, wr_v3_sub(P1, P0)), 1.0 / N2);
        gp = wr_v3_add(wr_v3_add(wr_v3_scale(g0, cphi[3 * f]), wr_v3_scale(g1, cphi[3 * f + 1])),
                       wr_v3_scale(g2, cphi[3 * f + 2]));
        for (c = 0; c < 3; ++c) {
            grad[3 * fv[c]] += A * gp.x;
            grad[3 * fv[c] + 1] += A * gp.y;
            grad[3 * fv[c] + 2] += A * gp.z;
            wsum[fv[c]] += A;
            if (!vwr[fv[c]]) {
                vwr[fv[c]] = 1;
                vphi[fv[c]] = cphi[3 * f + c]; /* any sheet: only cos φ, sin 2φ are used */
            }
        }
    }
    for (v = 0; v < cur->nv; ++v) {
        wr_vec3 n = wr_v3_normalized(wr_v3_load(nrm + 3 * v)), g = wr_v3(0.0, 0.0, 0.0), d;
        double av = vwr[v] ? U->ca[v] : 0.0, ph = vphi[v];
        if (wsum[v] > 0.0) g = wr_v3_scale(wr_v3_load(grad + 3 * v), 1.0 / wsum[v]);
        d = wr_v3_scale(n, av * cos(ph));
        if (inplane) d = wr_v3_add(d, wr_v3_scale(g, av * av / 8.0 * sin(2.0 * ph)));
        disp[3 * v] = cur->pos[3 * v] + d.x;
        disp[3 * v + 1] = cur->pos[3 * v + 1] + d.y;
        disp[3 * v + 2] = cur->pos[3 * v + 2] + d.z;
    }
done:
    wr_free(grad);
    wr_free(wsum);
    wr_free(nrm);
    return st;
}

/* The fine fields from the finest level: a (zero where no wrinkled face touches), the phase
 * wrapped to (-π, π] (0 off the wrinkled faces), the wrinkle-free flag. Takes vphi and vwr. */
static void wr__wf_up_fields(wr__wf_up *U, double *vphi, uint8_t *vwr, wr_wf_fine_fields *F) {
    int32_t v;
    for (v = 0; v < U->cur.nv; ++v) {
        double p = vwr[v] ? vphi[v] - 2.0 * WR__WF_PI * floor(vphi[v] / (2.0 * WR__WF_PI)) : 0.0; /* [0, 2π) */
        if (p > WR__WF_PI) p -= 2.0 * WR__WF_PI;
        vphi[v] = p;
        if (!vwr[v]) U->ca[v] = 0.0;
    }
    F->nv = U->cur.nv;
    F->a = U->ca;
    U->ca = NULL;
    F->phase = vphi;
    for (v = 0; v < U->cur.nv; ++v) vwr[v] = !vwr[v]; /* touches a wrinkled face -> wrinkle-free flag */
    F->wfree = vwr;
}

WRDEF void wr_wf_fine_fields_free(wr_wf_fine_fields *fields) {
    if (!fields) return;
    wr_free(fields->a);
    wr_free(fields->phase);
    wr_free(fields->wfree);
    memset(fields, 0, sizeof *fields);
}

/* The coarse faces' panels on the fine mesh: every Loop step puts the children of face f at 4f..4f+3
 * (wr_wf_loop_step), so after L steps fine face F descends from coarse face F >> 2L. A viewer then
 * shows the wrinkled surface grouped by the base's panels (OBJ g names, mesh.h wr_obj_desc). */
static wr_status wr__wf_up_panels(const wr_mesh *src, int32_t levels, wr_mesh *out, wr_diag *diag) {
    int32_t *fp = (int32_t *)wr_alloc_array((size_t)out->nf, sizeof(int32_t)), F;
    wr_status st;
    if (!fp) return wr_fail(diag, WR_ERR_NOMEM, -1, "wf upsample: out of memory");
    for (F = 0; F < out->nf; ++F) fp[F] = src->face_panel[F >> (2 * levels)];
    st = wr_mesh_set_face_panel(out, fp, diag);
    wr_free(fp);
    return st;
}

/* The base's corner_rest on the fine mesh: wr_wf_loop_corner_rest once per level (ON SEWN BASES). */
static wr_status wr__wf_up_corner_rest(const wr_mesh *src, int32_t levels, wr_mesh *out, wr_diag *diag) {
    double *cur = (double *)wr_alloc_array((size_t)out->nf * 6, sizeof(double));
    double *nxt = (double *)wr_alloc_array((size_t)out->nf * 6, sizeof(double)), *t;
    int32_t nf = src->nf, lvl;
    wr_status st;
    if (!cur || !nxt) {
        wr_free(cur);
        wr_free(nxt);
        return wr_fail(diag, WR_ERR_NOMEM, -1, "wf upsample: out of memory");
    }
    memcpy(cur, src->corner_rest, sizeof(double) * 6 * (size_t)nf);
    for (lvl = 0; lvl < levels; ++lvl, nf *= 4) {
        wr_wf_loop_corner_rest(nf, cur, nxt);
        t = cur, cur = nxt, nxt = t;
    }
    st = wr_mesh_set_corner_rest(out, cur, diag);
    wr_free(cur);
    wr_free(nxt);
    return st;
}

WRDEF wr_status wr_wf_upsample_fields(const wr_wf *wf, const double *a, const double *phi,
                                      const wr_wf_upsample_desc *desc, wr_mesh *out, wr_wf_fine_fields *fields,
                                      wr_diag *diag) {
    int32_t levels = desc && desc->levels > 0 ? desc->levels : 2, lvl;
    int inplane = !(desc && desc->no_inplane);
    const wr_mesh *src;
    double *disp = NULL, *vphi = NULL;
    uint8_t *vwr = NULL;
    wr__wf_up U;
    wr_status st;
    if (out) memset(out, 0, sizeof *out);
    if (fields) memset(fields, 0, sizeof *fields);
    if (!wf || !a || !phi || !out || !fields) return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "wf upsample: NULL argument");
    memset(&U, 0, sizeof U);
    U.mode = desc ? desc->boundary : WR_WF_LOOP_BOUNDARY_FIXED;
    if (levels > 8)
        return wr_fail(diag, WR_ERR_BUDGET, -1, "wf upsample: %d levels (> 8) would need 4^%d faces", (int)levels,
                       (int)levels);
    if (U.mode != WR_WF_LOOP_BOUNDARY_FIXED && U.mode != WR_WF_LOOP_BOUNDARY_SPLINE)
        return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "wf upsample: unknown boundary mode %d", U.mode);
    src = wf->mesh;
    U.has_rest = src->rest != NULL;
    U.ncomp = 3 + (U.has_rest ? 2 : 0) + 1;
    /* level 0: the coarse mesh with the base positions */
    st = wr_mesh_create(&U.cur, src->nv, wf->base, src->rest, src->nf, src->faces, diag);
    if (st) return st;
    U.ca = (double *)wr_alloc_array((size_t)src->nv, sizeof(double));
    U.cphi = (double *)wr_alloc_array((size_t)src->nf * 3, sizeof(double));
    U.cw = (uint8_t *)wr_alloc_array((size_t)src->nf, sizeof(uint8_t));
    if (!U.ca || !U.cphi || !U.cw) {
        st = wr_fail(diag, WR_ERR_NOMEM, -1, "wf upsample: out of memory");
    } else {
        memcpy(U.ca, a, sizeof(double) * (size_t)src->nv);
        memcpy(U.cphi, phi, sizeof(double) * 3 * (size_t)src->nf);
        memcpy(U.cw, wf->wfree, (size_t)src->nf);
    }
    for (lvl = 0; lvl < levels && !st; ++lvl) st = wr__wf_up_level(&U, diag);
    if (!st) {
        disp = (double *)wr_alloc_array((size_t)U.cur.nv * 3, sizeof(double));
        vphi = (double *)wr_calloc_array((size_t)U.cur.nv, sizeof(double));
        vwr = (uint8_t *)wr_calloc_array((size_t)U.cur.nv, sizeof(uint8_t));
        if (!disp || !vphi || !vwr) st = wr_fail(diag, WR_ERR_NOMEM, -1, "wf upsample: out of memory");
    }
    if (!st) st = wr__wf_up_displace(&U, inplane, disp, vphi, vwr, diag);
    if (!st) st = wr_mesh_create(out, U.cur.nv, disp, U.cur.rest, U.cur.nf, U.cur.faces, diag);
    if (!st && src->face_panel) st = wr__wf_up_panels(src, levels, out, diag);
    if (!st && src->corner_rest) st = wr__wf_up_corner_rest(src, levels, out, diag);
    if (!st) {
        wr__wf_up_fields(&U, vphi, vwr, fields);
        vphi = NULL;
        vwr = NULL;
    }
    wr_free(disp);
    wr_free(vphi);
    wr_free(vwr);
    wr_mesh_free(&U.cur);
    wr_free(U.ca);
    wr_free(U.cphi);
    wr_free(U.cw);
    return st;
}

/* The amplitude alone: the fine fields' a, the rest freed. The fine amplitude is zero on vertices
 * that touch only W faces either way (wr__wf_up_fine_mesh zeroes them on every level). */
WRDEF wr_status wr_wf_upsample(const wr_wf *wf, const double *a, const double *phi, const wr_wf_upsample_desc *desc,
                               wr_mesh *out, double **out_a, wr_diag *diag) {
    wr_wf_fine_fields F;
    wr_status st;
    if (out_a) *out_a = NULL;
    st = wr_wf_upsample_fields(wf, a, phi, desc, out, &F, diag);
    if (st) return st;
    if (out_a) {
        *out_a = F.a;
        F.a = NULL;
    }
    wr_wf_fine_fields_free(&F);
    return WR_OK;
}

/* ---- SQP (App. E.3) ---- */

/* Pivot floor of the positive-definiteness test below, relative to the largest diagonal entry [1]:
 * a block that is positive definite only by less than this goes through the eigen-decomposition, so
 * nearly singular blocks (ω rows of faces with a ≈ 0) are projected exactly as before. */
#define WR__WF_SPD_PIVOT_REL 1e-10

/* 1 when the symmetric 6×6 A passes a Cholesky factorisation with every pivot above
 * WR__WF_SPD_PIVOT_REL · max diag: then every eigenvalue is positive and the projection to the PSD
 * cone (wr_dense_project_spd with floor 0) would return A unchanged. */
static int wr__wf_spd6(const double A[36]) {
    double L[36], dmax = 0.0;
    int i, j, k;
    for (i = 0; i < 6; ++i) dmax = fmax(dmax, A[7 * i]);
    if (!(dmax > 0.0)) return 0;
    for (j = 0; j < 6; ++j) {
        double d = A[7 * j];
        for (k = 0; k < j; ++k) d -= L[6 * j + k] * L[6 * j + k];
        if (!(d > WR__WF_SPD_PIVOT_REL * dmax)) return 0;
        d = sqrt(d);
        L[7 * j] = d;
        for (i = j + 1; i < 6; ++i) {
            double t = A[6 * i + j];
            for (k = 0; k < j; ++k) t -= L[6 * i + k] * L[6 * j + k];
            L[6 * i + j] = t / d;
        }
    }
    return 1;
}

static void wr__wf_sqp_tox(const wr_wf *wf, const wr__wf_basis *B, const int32_t *avar, const double *y, int32_t na,
                           double *a, double *omega) {
    int32_t v;
    for (v = 0; v < wf->nv; ++v) a[v] = avar[v] >= 0 ? y[avar[v]] : 0.0;
    wr__wf_z_apply(B, y + na, omega);
}

/* Second-order escape from amplitudes stuck at the bound with zero gradient (TFW App. F notes for
 * the stretched sheet: "amplitude first vanishes globally over the sheet, and then wrinkles emerge at
 * the center"). E is even in a, so a = 0 with any ω is a KKT point; whether it is a minimum is a
 * second-order question about SMOOTH amplitude modes: a single vertex's curvature is dominated by
 * its own |da|² term. Per face, 1ᵀ H_aa 1 (true Hessian, a uniform on the face so da = 0) is the
 * curvature of the a²|dφ|² terms alone: negative where the base stress is compressive along dφ
 * (Eq. 21). Vertices at 0 whose incident faces average a negative value form the escape profile
 * p_v = -avg / max(-avg); trial points a = s·a_ref·p_v for s = 0.1, 0.01, ..., 1e-6 (ω unchanged),
 * the first that lowers E is taken. "At 0" is a <= abound (0: exactly at the bound; the flat-stop
 * test of wr__wf_sqp_flat passes ε a_ref). hd: scratch of na. Returns 1 with the point in yt, E in
 * *Enew. */
static int wr__wf_escape(const wr_wf *wf, const wr__wf_basis *B, const int32_t *avar, int32_t na, const double *y,
                         const double *H, double aref, double abound, double E, double *yt, double *xa, double *xo,
                         double *hd, double *cnt, double *Enew) {
    int32_t f, i, v, n = na + B->ncol;
    double pmax = 0.0, s;
    for (i = 0; i < na; ++i) hd[i] = cnt[i] = 0.0;
    for (f = 0; f < wf->nf; ++f) {
        const double *He = H + 36 * (size_t)f;
        double c = 0.0;
        int k, l;
        if (wf->wfree[f]) continue;
        for (k = 0; k < 3; ++k)
            for (l = 0; l < 3; ++l) c += He[6 * k + l];
        for (k = 0; k < 3; ++k) {
            int32_t col = avar[wf->mesh->faces[3 * f + k]];
            if (col < 0) continue;
            hd[col] += c;
            cnt[col] += 1.0;
        }
    }
    for (i = 0; i < na; ++i) {
        hd[i] = (y[i] <= abound && cnt[i] > 0.0 && hd[i] < 0.0) ? -hd[i] / cnt[i] : 0.0;
        pmax = fmax(pmax, hd[i]);
    }
    if (!(pmax > 0.0)) return 0;
    for (s = 1e-1; s >= 1e-6; s *= 0.1) {
        double Et = 0.0;
        for (i = 0; i < n; ++i) yt[i] = y[i];
        for (i = 0; i < na; ++i)
            if (hd[i] > 0.0) yt[i] = s * aref * hd[i] / pmax;
        for (v = 0; v < wf->nv; ++v) xa[v] = avar[v] >= 0 ? yt[avar[v]] : 0.0;
        wr__wf_z_apply(B, yt + na, xo);
        if (wr__wf_energy_impl(wf, xa, xo, 1, &Et, NULL, NULL, NULL, NULL) == WR_OK && Et < E - WR__WF_ROUNDOFF * fabs(E)) {
            *Enew = Et;
            return 1;
        }
    }
    return 0;
}

/* Stationarity of Eq. 39 in nondimensional variables ŷ = y / s (s = a_ref for amplitudes, 1 rad for
 * the closed-form coordinates) and ĝ = s g / E_ref: ||ŷ - P(ŷ - ĝ)||_∞, P = projection onto a >= 0.
 * For a free amplitude and for every z coordinate this is |ĝ| (reduced gradient in the null space of
 * dω = 0); at the bound it is min(ŷ, ĝ) (complementarity). */
/* Frequency regulariser (γ/2) Σ_active ω_e² (see wr_wf_solve_desc.omega_reg); adds γω to gomega. */
static double wr__wf_reg(const wr__wf_basis *B, double gamma, const double *omega, double *gomega) {
    double r = 0.0;
    int32_t e;
    if (!(gamma > 0.0)) return 0.0;
    for (e = 0; e < B->ne; ++e)
        if (B->eact[e]) {
            r += 0.5 * gamma * omega[e] * omega[e];
            if (gomega) gomega[e] += gamma * omega[e];
        }
    return r;
}

static double wr__wf_kkt(const double *y, const double *g, int32_t n, int32_t na, double aref, double eref) {
    double kkt = 0.0;
    int32_t i;
    for (i = 0; i < n; ++i) {
        double r;
        if (i < na) {
            double yh = y[i] / aref, gh = g[i] * aref / eref;
            r = yh - fmax(0.0, yh - gh);
        } else {
            r = g[i] / eref;
        }
        kkt = fmax(kkt, fabs(r));
    }
    return kkt;
}

/* The SQP's state, alive across its stages (wr_wf_solve below reads as App. E.3's loop over them).
 * Unknowns y = (free amplitudes, closed-form coordinates z): y[0..na) are the amplitudes of the
 * vertices with avar[v] >= 0, y[na..n) the coordinates of the null-space basis B (ω = Z z). */
typedef struct wr__wf_sqp {
    const wr_wf *wf;
    wr_wf_solve_desc D;
    wr_wf_solve_stats S;
    wr__wf_basis B;
    int32_t *avar, na, n;
    uint8_t *zero, *active;
    double *y, *yt, *d, *g, *rhs;   /* n each: iterate, trial, step, reduced gradient, right-hand side */
    double *xa, *xo, *gx, *H;       /* full space: a (nv), ω (ne), ∇E (nv + ne), face Hessians (nf × 36) */
    /* per-face reduction ω-local DOFs → reduced unknowns: face f's columns fcols[fstart[f] ..], the
     * first fused[f] of them used, P (6 × used) column-major in Pm; the reduced Hessian K = KA.A is
     * assembled through sparse.h's assembly cache (its pattern is fixed for the whole solve) */
    int32_t *fstart, *fcols, *fused;
    double *Pm;
    wr_assembly KA;
    wr_spd_solver SV;
    int have_solver;
    double *kmodel, *mdiag, *ks, *ainit; /* undamped model values (nnz), damping diagonal, K·s, scratch */
    double aref, eref, greg, ebase;      /* scales (ON THE SQP SOLVER), regulariser weight, constant part of E */
    double mu, nu_up;                    /* Marquardt damping and its growth factor (Nielsen 1999) */
    double E;                            /* objective at y (E_wf without its constant part + regulariser) */
    double *pnc, *wnc, *dnc, *lz;        /* negative_curvature option: direction p, s(σ), raw step (n each), Lanczos basis */
    double nc_radius, nc_floor;          /* its Δ_nc (ON NEGATIVE CURVATURE), 0 until the first such step; floor */
    int hess_true;
} wr__wf_sqp;

/* One Levenberg–Marquardt trial sequence's outcome. */
typedef struct wr__wf_trial {
    int accepted, roundoff, negcurv;
    int32_t nact, nfail;
    double Et, rho, curv, gain; /* curv, gain: see wr_wf_iter_info */
} wr__wf_trial;

static void wr__wf_sqp_free(wr__wf_sqp *Q) {
    if (Q->have_solver) wr_spd_solver_free(&Q->SV);
    wr_assembly_free(&Q->KA);
    wr__wf_basis_free(&Q->B);
    wr_free(Q->avar);
    wr_free(Q->zero);
    wr_free(Q->fstart);
    wr_free(Q->fcols);
    wr_free(Q->fused);
    wr_free(Q->Pm);
    wr_free(Q->y);
    wr_free(Q->yt);
    wr_free(Q->d);
    wr_free(Q->g);
    wr_free(Q->gx);
    wr_free(Q->H);
    wr_free(Q->xa);
    wr_free(Q->xo);
    wr_free(Q->rhs);
    wr_free(Q->active);
    wr_free(Q->kmodel);
    wr_free(Q->mdiag);
    wr_free(Q->ks);
    wr_free(Q->ainit);
    wr_free(Q->pnc);
    wr_free(Q->wnc);
    wr_free(Q->dnc);
    wr_free(Q->lz);
}

/* Defaults of wr_wf_solve_desc (the comment above the struct lists them). */
static wr_status wr__wf_sqp_defaults(wr_wf_solve_desc *D, const wr_wf_solve_desc *desc, wr_diag *diag) {
    if (desc)
        *D = *desc;
    else
        memset(D, 0, sizeof *D);
    if (D->max_iter <= 0) D->max_iter = WR__WF_MAX_ITER;
    if (!(D->tol_energy > 0.0)) D->tol_energy = WR__WF_TOL_ENERGY;
    if (!(D->tol_kkt > 0.0)) D->tol_kkt = WR__WF_TOL_KKT;
    if (!(D->tol_step > 0.0)) D->tol_step = WR__WF_TOL_STEP;
    if (!(D->hessian_switch > 0.0)) D->hessian_switch = WR__WF_HESSIAN_SWITCH;
    if ((int)D->hessian < 0 || (int)D->hessian > (int)WR_WF_HESSIAN_TRUE)
        return wr_fail(diag, WR_ERR_INVALID_ARG, (int32_t)D->hessian, "wf solve: unknown Hessian strategy %d",
                       (int)D->hessian);
    if (D->negative_curvature != 0 && D->negative_curvature != 1)
        return wr_fail(diag, WR_ERR_INVALID_ARG, D->negative_curvature, "wf solve: negative_curvature %d (0 or 1)",
                       (int)D->negative_curvature);
    return WR_OK;
}

/* Unknowns and the feasible start: a clipped to >= 0 (0 on W vertices and clamps), ω projected to
 * dω = 0 (least squares in the closed-form coordinates). */
static wr_status wr__wf_sqp_start(wr__wf_sqp *Q, const double *a, const double *omega, wr_diag *diag) {
    const wr_wf *wf = Q->wf;
    wr_status st = wr__wf_basis_build(wf, &Q->B, diag);
    int32_t v, n;
    if (st) return st;
    Q->avar = (int32_t *)wr_alloc_array((size_t)wf->nv, sizeof(int32_t));
    Q->zero = (uint8_t *)wr_alloc_array((size_t)wf->nv, sizeof(uint8_t));
    Q->fstart = (int32_t *)wr_calloc_array((size_t)wf->nf + 1, sizeof(int32_t));
    Q->xa = (double *)wr_alloc_array((size_t)wf->nv, sizeof(double));
    Q->xo = (double *)wr_alloc_array((size_t)wf->ne, sizeof(double));
    Q->gx = (double *)wr_alloc_array((size_t)(wf->nv + wf->ne), sizeof(double));
    Q->H = (double *)wr_alloc_array((size_t)wf->nf * 36, sizeof(double));
    if (!Q->avar || !Q->zero || !Q->fstart || !Q->xa || !Q->xo || !Q->gx || !Q->H)
        return wr_fail(diag, WR_ERR_NOMEM, -1, "wf solve: out of memory");
    wr__wf_zero_vertices(wf, Q->zero);
    for (v = 0; v < wf->nv; ++v) Q->avar[v] = Q->zero[v] ? -1 : Q->na++;
    n = Q->n = Q->na + Q->B.ncol;
    Q->S.n_vars = n;
    Q->S.n_generators = Q->B.ngen;
    Q->y = (double *)wr_calloc_array((size_t)n + 1, sizeof(double));
    Q->yt = (double *)wr_calloc_array((size_t)n + 1, sizeof(double));
    Q->d = (double *)wr_calloc_array((size_t)n + 1, sizeof(double));
    Q->g = (double *)wr_calloc_array((size_t)n + 1, sizeof(double));
    Q->rhs = (double *)wr_calloc_array((size_t)n + 1, sizeof(double));
    Q->active = (uint8_t *)wr_calloc_array((size_t)n + 1, sizeof(uint8_t));
    if (!Q->y || !Q->yt || !Q->d || !Q->g || !Q->rhs || !Q->active)
        return wr_fail(diag, WR_ERR_NOMEM, -1, "wf solve: out of memory");
    for (v = 0; v < wf->nv; ++v)
        if (Q->avar[v] >= 0) Q->y[Q->avar[v]] = a[v] > 0.0 && isfinite(a[v]) ? a[v] : 0.0;
    for (v = 0; v < wf->ne; ++v) Q->xo[v] = omega[v];
    return wr__wf_lsq_closed(&Q->B, omega, Q->y + Q->na, Q->D.solver, diag);
}

/* Per face, the map P (6 local DOFs: 3 amplitudes, 3 edge ω → the face's reduced unknowns), with
 * the face's unique columns in fcols; unused tail slots are marked -1 (fstart stays monotone). */
static wr_status wr__wf_sqp_face_maps(wr__wf_sqp *Q, wr_diag *diag) {
    const wr_wf *wf = Q->wf;
    const wr__wf_basis *B = &Q->B;
    int32_t total = 0, cap, f;
    for (f = 0; f < wf->nf; ++f) {
        int k;
        Q->fstart[f] = total;
        if (wf->wfree[f]) continue;
        for (k = 0; k < 3; ++k) {
            int32_t e = wf->mesh->face_edges[3 * f + k];
            total += 1 + (B->zstart[e + 1] - B->zstart[e]);
        }
    }
    Q->fstart[wf->nf] = total;
    cap = total > 0 ? total : 1;
    Q->fcols = (int32_t *)wr_alloc_array((size_t)cap, sizeof(int32_t));
    Q->Pm = (double *)wr_calloc_array((size_t)cap * 6, sizeof(double));
    if (!Q->fcols || !Q->Pm) return wr_fail(diag, WR_ERR_NOMEM, -1, "wf solve: out of memory");
    for (f = 0; f < wf->nf; ++f) {
        int32_t idx[6], mcount = 0, s0 = Q->fstart[f], t;
        double sg[6];
        int k;
        if (wf->wfree[f]) {
            Q->fstart[f + 1] = Q->fstart[f] > Q->fstart[f + 1] ? Q->fstart[f] : Q->fstart[f + 1];
            continue;
        }
        wr_wf_face_dofs(wf, f, idx, sg);
        /* unique columns: linear search is fine, m_f is small */
        for (k = 0; k < 6; ++k) {
            int32_t cstart = k < 3 ? 0 : B->zstart[idx[k] - wf->nv], cend = k < 3 ? 1 : B->zstart[idx[k] - wf->nv + 1];
            for (t = cstart; t < cend; ++t) {
                int32_t col = k < 3 ? Q->avar[idx[k]] : Q->na + B->zcol[t], q;
                /* face_hess is already in global ω orientation (wr_wf_energy applies the
                 * face_edge_sign), so P maps straight to global ω: no sign here. */
                double val = k < 3 ? 1.0 : B->zval[t];
                if (col < 0) continue;
                for (q = 0; q < mcount; ++q)
                    if (Q->fcols[s0 + q] == col) break;
                if (q == mcount) Q->fcols[s0 + mcount++] = col;
                Q->Pm[6 * (size_t)s0 + 6 * (size_t)q + k] += val; /* column-major per face: P[q][k] */
            }
        }
        for (t = mcount; t < Q->fstart[f + 1] - s0; ++t) Q->fcols[s0 + t] = -1;
    }
    return WR_OK;
}

/* Face f's reduced block Pᵀ He P (u × u, row-major, u = fused[f]), He its true or SPD-projected
 * 6×6 Hessian block (App. E.3). */
static void wr__wf_sqp_face_block(const wr__wf_sqp *Q, int32_t f, double *Ke) {
    int32_t s0 = Q->fstart[f], u = Q->fused[f], r, c, k, l;
    double He[36], HP[6 * WR_DENSE_MAX];
    memcpy(He, Q->H + 36 * (size_t)f, sizeof He);
    /* App. E.3 per-face projection; a positive definite block is its own projection, and a
     * Cholesky attempt settles that far cheaper than the eigen-decomposition */
    if (!Q->hess_true && !wr__wf_spd6(He)) wr_dense_project_spd(6, He, 0.0);
    /* HP = He P first (6 × u), then the upper triangle of Pᵀ HP, mirrored */
    for (c = 0; c < u; ++c) {
        const double *pc = Q->Pm + 6 * (size_t)(s0 + c);
        for (k = 0; k < 6; ++k) {
            double t = 0.0;
            for (l = 0; l < 6; ++l) t += He[6 * k + l] * pc[l];
            HP[6 * c + k] = t;
        }
    }
    for (r = 0; r < u; ++r) {
        const double *pr = Q->Pm + 6 * (size_t)(s0 + r);
        for (c = r; c < u; ++c) {
            const double *hc = HP + 6 * c;
            double t = pr[0] * hc[0] + pr[1] * hc[1] + pr[2] * hc[2] + pr[3] * hc[3] + pr[4] * hc[4] + pr[5] * hc[5];
            Ke[r * u + c] = Ke[c * u + r] = t;
        }
    }
}

/* The reduced Hessian's element stream, shared by the pattern and every assembly: per face the
 * reduced block Pᵀ He P over its used columns (He the face's true or SPD-projected 6×6 block, App.
 * E.3), then the regulariser's γ ZᵀZ per active edge. values = 0 streams zero blocks (the recording
 * pass that fixes the pattern before any Hessian exists). */
static wr_status wr__wf_sqp_stream(wr__wf_sqp *Q, int values, wr_diag *diag) {
    const wr_wf *wf = Q->wf;
    double Ke[WR_DENSE_MAX * WR_DENSE_MAX];
    int32_t f, e;
    wr_status st;
    for (f = 0; f < wf->nf; ++f) {
        int32_t s0 = Q->fstart[f], u = Q->fused[f];
        if (wf->wfree[f]) continue;
        if (values) wr__wf_sqp_face_block(Q, f, Ke);
        else memset(Ke, 0, sizeof(double) * (size_t)u * (size_t)u);
        if ((st = wr_assembly_add(&Q->KA, u, Q->fcols + s0, Ke, diag)) != WR_OK) return st;
    }
    if (Q->greg > 0.0 || !values)
        for (e = 0; e < wf->ne; ++e) {
            int32_t s0 = Q->B.zstart[e], nz = Q->B.zstart[e + 1] - s0, r, c, cols[WR_DENSE_MAX];
            if (!Q->B.eact[e] || nz == 0) continue;
            if (nz > WR_DENSE_MAX)
                return wr_fail(diag, WR_ERR_BUDGET, e, "wf solve: edge %d couples %d unknowns (> %d)", (int)e, (int)nz,
                               WR_DENSE_MAX);
            for (r = 0; r < nz; ++r) {
                cols[r] = Q->na + Q->B.zcol[s0 + r];
                for (c = 0; c < nz; ++c)
                    Ke[r * nz + c] = values ? Q->greg * Q->B.zval[s0 + r] * Q->B.zval[s0 + c] : 0.0;
            }
            if ((st = wr_assembly_add(&Q->KA, nz, cols, Ke, diag)) != WR_OK) return st;
        }
    return WR_OK;
}

/* The reduced Hessian's sparsity pattern (every face block, the regulariser's edge blocks and the
 * diagonal: one recording assembly of zero blocks through the assembly cache) and its solver, so
 * the symbolic analysis is done once and each later assembly adds through cached offsets. */
static wr_status wr__wf_sqp_pattern(wr__wf_sqp *Q, wr_diag *diag) {
    const wr_wf *wf = Q->wf;
    wr_spd_desc sd;
    int32_t f, n = Q->n;
    wr_status st;
    Q->fused = (int32_t *)wr_calloc_array((size_t)wf->nf + 1, sizeof(int32_t));
    if (!Q->fused) return wr_fail(diag, WR_ERR_NOMEM, -1, "wf solve: out of memory");
    for (f = 0; f < wf->nf; ++f) {
        int32_t s0 = Q->fstart[f], m = Q->fstart[f + 1] - s0, u = 0;
        if (wf->wfree[f]) continue;
        while (u < m && Q->fcols[s0 + u] >= 0) ++u; /* used columns come first (wr__wf_sqp_face_maps) */
        if (u > WR_DENSE_MAX)
            return wr_fail(diag, WR_ERR_BUDGET, f, "wf solve: face %d couples %d unknowns (> %d)", (int)f, (int)u,
                           WR_DENSE_MAX);
        Q->fused[f] = u;
    }
    st = wr_assembly_init(&Q->KA, n, 1, diag);
    if (!st) {
        wr_assembly_begin(&Q->KA);
        st = wr__wf_sqp_stream(Q, 0, diag);
        if (!st) st = wr_assembly_end(&Q->KA, diag);
    }
    if (st) return st;
    memset(&sd, 0, sizeof sd);
    sd.method = Q->D.solver;
    st = wr_spd_solver_create(&Q->SV, &Q->KA.A, &sd, diag);
    if (st) return st;
    Q->have_solver = 1;
    Q->kmodel = (double *)wr_alloc_array((size_t)(Q->KA.A.nnz > 0 ? Q->KA.A.nnz : 1), sizeof(double));
    Q->mdiag = (double *)wr_alloc_array((size_t)n + 1, sizeof(double));
    Q->ks = (double *)wr_alloc_array((size_t)n + 1, sizeof(double));
    if (!Q->kmodel || !Q->mdiag || !Q->ks) return wr_fail(diag, WR_ERR_NOMEM, -1, "wf solve: out of memory");
    if (Q->D.negative_curvature) {
        Q->pnc = (double *)wr_calloc_array((size_t)n + 1, sizeof(double));
        Q->wnc = (double *)wr_calloc_array((size_t)n + 1, sizeof(double));
        Q->dnc = (double *)wr_calloc_array((size_t)n + 1, sizeof(double));
        Q->lz = (double *)wr_alloc_array((size_t)WR__WF_NC_LANCZOS * ((size_t)n + 1), sizeof(double));
        if (!Q->pnc || !Q->wnc || !Q->dnc || !Q->lz) return wr_fail(diag, WR_ERR_NOMEM, -1, "wf solve: out of memory");
    }
    return WR_OK;
}

/* Nondimensionalisation (ON THE SQP SOLVER): amplitudes in units of a_ref = max a at the start (or
 * a fraction of the bounding-box diagonal when the start is flat). */
static wr_status wr__wf_sqp_scales(wr__wf_sqp *Q, wr_diag *diag) {
    const wr_wf *wf = Q->wf;
    double amax = 0.0, lo[3], hi[3], diam2 = 0.0;
    int32_t i, v;
    for (i = 0; i < Q->na; ++i) amax = fmax(amax, Q->y[i]);
    for (i = 0; i < 3; ++i) lo[i] = hi[i] = wf->base[i];
    for (v = 0; v < wf->nv; ++v)
        for (i = 0; i < 3; ++i) {
            lo[i] = fmin(lo[i], wf->base[3 * v + i]);
            hi[i] = fmax(hi[i], wf->base[3 * v + i]);
        }
    for (i = 0; i < 3; ++i) diam2 += (hi[i] - lo[i]) * (hi[i] - lo[i]);
    Q->aref = amax > 0.0 ? amax : WR__WF_AREF_FALLBACK * sqrt(diam2);
    Q->ainit = (double *)wr_alloc_array((size_t)Q->na + 1, sizeof(double));
    if (!Q->ainit) return wr_fail(diag, WR_ERR_NOMEM, -1, "wf solve: out of memory");
    return WR_OK;
}

/* Reduced gradient g = (∂E/∂a on free amplitudes, Zᵀ ∂E/∂ω) from the full-space gradient gx. */
static void wr__wf_sqp_reduce(const wr__wf_sqp *Q, const double *gx, double *g) {
    int32_t v;
    for (v = 0; v < Q->wf->nv; ++v)
        if (Q->avar[v] >= 0) g[Q->avar[v]] = gx[v];
    wr__wf_z_applyT(&Q->B, gx + Q->wf->nv, g + Q->na);
}

/* E, g and the face Hessians at y. The first evaluation also fixes E_ref (|E_wf| at the start), the
 * constant part of E_wf (reported, not minimised) and the regulariser weight γ. */
static wr_status wr__wf_sqp_evaluate(wr__wf_sqp *Q, int first, wr_diag *diag) {
    const wr_wf *wf = Q->wf;
    wr_status st;
    wr__wf_sqp_tox(wf, &Q->B, Q->avar, Q->y, Q->na, Q->xa, Q->xo);
    st = wr__wf_energy_impl(wf, Q->xa, Q->xo, 1, &Q->E, Q->gx, Q->H, NULL, diag);
    if (st) return st;
    if (first) {
        int32_t i, nact_e = 0;
        double Efull = 0.0;
        st = wr_wf_energy(wf, Q->xa, Q->xo, &Efull, NULL, NULL, NULL, diag);
        if (st) return st;
        Q->ebase = Efull - Q->E;
        Q->eref = fabs(Efull) > 0.0 ? fabs(Efull) : 1.0;
        for (i = 0; i < wf->ne; ++i) nact_e += Q->B.eact[i];
        Q->greg = Q->D.omega_reg > 0.0 && nact_e > 0 ? Q->D.omega_reg * Q->eref / nact_e : 0.0;
    }
    Q->E += wr__wf_reg(&Q->B, Q->greg, Q->xo, Q->gx + wf->nv);
    wr__wf_sqp_reduce(Q, Q->gx, Q->g);
    return WR_OK;
}

/* The model Hessian K = Σ_f Pᵀ He P (+ the regulariser's γ ZᵀZ), kept undamped in kmodel. */
static wr_status wr__wf_sqp_assemble(wr__wf_sqp *Q, wr_diag *diag) {
    wr_status st;
    wr_assembly_begin(&Q->KA);
    st = wr__wf_sqp_stream(Q, 1, diag);
    if (!st) st = wr_assembly_end(&Q->KA, diag);
    if (st) return st;
    /* the stream is the recorded one, so the pattern never goes stale within a solve */
    WR_ASSERT(!Q->KA.stale && Q->KA.misses == 0);
    memcpy(Q->kmodel, Q->KA.A.val, sizeof(double) * (size_t)Q->KA.A.nnz);
    return WR_OK;
}

/* Marquardt damping matrix: |diag| of the model Hessian, floored per block (a, z) so that directions
 * the energy does not see (ω where a = 0) still get a finite, tiny step. */
static void wr__wf_sqp_damping(wr__wf_sqp *Q) {
    double mblock[2] = {0.0, 0.0}, mcount[2] = {0.0, 0.0};
    int32_t i, na = Q->na;
    for (i = 0; i < Q->n; ++i) {
        int32_t p = wr_csr_find(&Q->KA.A, i, i);
        Q->mdiag[i] = p >= 0 ? fabs(Q->kmodel[p]) : 0.0;
        mblock[i < na ? 0 : 1] += Q->mdiag[i];
        mcount[i < na ? 0 : 1] += 1.0;
    }
    for (i = 0; i < 2; ++i) mblock[i] = mcount[i] > 0.0 && mblock[i] > 0.0 ? mblock[i] / mcount[i] : 1.0;
    for (i = 0; i < Q->n; ++i) Q->mdiag[i] = fmax(Q->mdiag[i], WR__WF_DAMP_FLOOR * mblock[i < na ? 0 : 1]);
}

/* Solve (K + μ M) d = -g on the free set of the ε-active set (Bertsekas 1982 projected Newton:
 * amplitudes within ε of the bound whose scaled gradient pushes them down are held and moved onto
 * it); d is 0 on the held set (wr__wf_sqp_project moves those onto the bound). Returns the
 * factor/solve status; K's values stay the factored K + μ M. */
static wr_status wr__wf_sqp_damped_solve(wr__wf_sqp *Q, double epsact, int32_t *nact) {
    wr_csr *K = &Q->KA.A;
    wr_spd_stats ss;
    wr_status fs;
    double t1 = wr_time_seconds();
    int32_t i, n = Q->n;
    *nact = 0;
    for (i = 0; i < n; ++i) {
        Q->active[i] = (uint8_t)(i < Q->na && (Q->y[i] <= 0.0 || Q->y[i] / Q->aref <= epsact) && Q->g[i] > 0.0);
        *nact += Q->active[i];
    }
    memcpy(K->val, Q->kmodel, sizeof(double) * (size_t)K->nnz);
    for (i = 0; i < n; ++i) {
        int32_t t;
        for (t = K->rowptr[i]; t < K->rowptr[i + 1]; ++t) {
            if (Q->active[i] || Q->active[K->col[t]])
                K->val[t] = (K->col[t] == i) ? 1.0 : 0.0;
            else if (K->col[t] == i)
                K->val[t] += Q->mu * Q->mdiag[i];
        }
        Q->rhs[i] = Q->active[i] ? 0.0 : -Q->g[i];
        Q->d[i] = 0.0;
    }
    fs = wr_spd_solver_factor(&Q->SV, K, NULL);
    if (!fs) fs = wr_spd_solver_solve(&Q->SV, K, Q->rhs, Q->d, &ss, NULL);
    Q->S.n_factorizations++;
    Q->S.seconds_solve += wr_time_seconds() - t1;
    return fs;
}

/* The raw step dr (0 on the held set) as the projected step: held amplitudes onto the bound, yt =
 * max(y + dr, 0) on the amplitudes, d = yt - y. dr may be Q->d. */
static void wr__wf_sqp_project(wr__wf_sqp *Q, const double *dr) {
    int32_t i;
    for (i = 0; i < Q->n; ++i) {
        double di = Q->active[i] ? -Q->y[i] : dr[i]; /* onto the bound */
        Q->yt[i] = Q->y[i] + di;
        if (i < Q->na && Q->yt[i] < 0.0) Q->yt[i] = 0.0;
        Q->d[i] = Q->yt[i] - Q->y[i]; /* the projected step s */
    }
}

/* Model decrease of the projected step s = d: -(gᵀs + ½ sᵀ K s) with the undamped model K. */
static double wr__wf_sqp_predicted(wr__wf_sqp *Q) {
    const wr_csr *K = &Q->KA.A;
    double pred = 0.0;
    int32_t i;
    for (i = 0; i < Q->n; ++i) {
        int32_t t;
        double r = 0.0;
        for (t = K->rowptr[i]; t < K->rowptr[i + 1]; ++t) r += Q->kmodel[t] * Q->d[K->col[t]];
        Q->ks[i] = r;
        pred -= Q->d[i] * (Q->g[i] + 0.5 * r);
    }
    return pred;
}

/* uᵀ K u with the undamped model (kmodel) on the free set, u = a - b (b NULL: u = a); *um = uᵀ M u
 * on the free set when um is given. The curvature the negative-curvature step is judged by. */
static double wr__wf_sqp_curv(const wr__wf_sqp *Q, const double *a, const double *b, double *um) {
    const wr_csr *K = &Q->KA.A;
    double uk = 0.0, m = 0.0;
    int32_t i, t;
    for (i = 0; i < Q->n; ++i) {
        double r = 0.0, ui = b ? a[i] - b[i] : a[i];
        if (Q->active[i]) continue;
        for (t = K->rowptr[i]; t < K->rowptr[i + 1]; ++t)
            if (!Q->active[K->col[t]]) r += Q->kmodel[t] * (b ? a[K->col[t]] - b[K->col[t]] : a[K->col[t]]);
        uk += ui * r;
        m += Q->mdiag[i] * ui * ui;
    }
    if (um) *um = m;
    return uk;
}

/* ON NEGATIVE CURVATURE (wr_wf_solve_desc.negative_curvature). The factorisation of K + μ M failed at
 * the trust region's μ and succeeded at σ = 10^k μ: the true Hessian has a direction of curvature
 * below -μ in the M metric, and the default takes s(σ) = -(K + σ M)⁻¹ g with μ raised to σ. Where g
 * is nearly orthogonal to that direction (Moré & Sorensen's "hard case"; at a = 0 under compression
 * E is even in a, so ∂E/∂a = 0 there) s(σ) hardly moves along it: the saddle crawl of
 * docs/notes-tfw-solver.md. The option takes d = s(σ) + τ p instead (Moré & Sorensen 1979's
 * pairing of a Newton-type step with a direction of negative curvature), p an M-unit direction with
 * pᵀKp < 0: the Ritz vector of the largest eigenvalue of (K + σ M)⁻¹ M (its eigenvalues 1/(λ + σ)
 * > 0 are largest for the most negative λ of the pencil (K, M)) after WR__WF_NC_LANCZOS steps of
 * shift-invert Lanczos in the M inner product, with the factor of K + σ M already at hand and a
 * seeded random start, used only if its Rayleigh quotient with K is negative. Of ±p the sign with the larger model
 * decrease of the projected step (a ≥ 0) is taken. τ = Δ_nc, a radius of its own (M-norm), set to
 * ‖s(σ)‖_M on the first such step of a solve, doubled after a step with ρ > 3/4, ×¼ after a
 * rejection (up to WR__WF_NC_CUTS cuts per iteration, reusing the factor; then the trial counts as
 * rejected as any other), never below WR__WF_NC_FLOOR ‖s(σ)‖_M: a shorter component along p changes
 * nothing that s(σ) alone does not, so a rejection there is the damping's to answer (without the
 * floor Δ_nc fell to 1e-47 … 1e-65 on the stretched sheet and the wasted cuts cost iterations:
 * docs/notes-tfw-solver.md). μ is not raised to σ: the damping stays the trust region's and is adapted
 * from ρ as for any other step. */
static int wr__wf_sqp_negcurv(wr__wf_sqp *Q, wr__wf_trial *out) {
    const wr_csr *K = &Q->KA.A;
    double *p = Q->pnc, *V = Q->lz, T[WR__WF_NC_LANCZOS * WR__WF_NC_LANCZOS], th[WR__WF_NC_LANCZOS];
    double Y[WR__WF_NC_LANCZOS * WR__WF_NC_LANCZOS], lam = 0.0, sm = 0.0, beta = 0.0;
    int32_t i, j, l, k = 0, n = Q->n;
    size_t ns = (size_t)n;
    wr_rng rng;
    wr_spd_stats ss;
    wr_rng_seed(&rng, WR__WF_NC_SEED);
    memset(T, 0, sizeof T);
    memcpy(Q->wnc, Q->d, sizeof(double) * ns); /* s(σ), raw (0 on the held set) */
    for (i = 0; i < n; ++i) p[i] = Q->active[i] ? 0.0 : wr_rng_uniform(&rng) - 0.5;
    /* shift-invert Lanczos in the M inner product on (K + σ M)⁻¹ M, full reorthogonalisation */
    for (k = 0; k < WR__WF_NC_LANCZOS; ++k) {
        double *q = V + (size_t)k * ns, nrm = 0.0, al = 0.0;
        for (i = 0; i < n; ++i) nrm += Q->mdiag[i] * p[i] * p[i];
        nrm = sqrt(nrm);
        if (k > 0) T[(k - 1) * WR__WF_NC_LANCZOS + k] = T[k * WR__WF_NC_LANCZOS + k - 1] = beta = nrm;
        if (!(nrm > 0.0) || !isfinite(nrm) || (k > 0 && beta <= 1e-12 * fabs(T[0]))) break; /* invariant subspace */
        for (i = 0; i < n; ++i) {
            q[i] = p[i] / nrm;
            Q->dnc[i] = Q->active[i] ? 0.0 : Q->mdiag[i] * q[i];
            p[i] = 0.0;
        }
        if (wr_spd_solver_solve(&Q->SV, K, Q->dnc, p, &ss, NULL) != WR_OK) return 0;
        for (i = 0; i < n; ++i)
            if (Q->active[i]) p[i] = 0.0;
        for (l = 0; l < 2; ++l) /* twice is enough (Parlett) */
            for (j = 0; j <= k; ++j) {
                const double *qj = V + (size_t)j * ns;
                double c = 0.0;
                for (i = 0; i < n; ++i) c += Q->mdiag[i] * qj[i] * p[i];
                for (i = 0; i < n; ++i) p[i] -= c * qj[i];
                if (j == k) al += c;
            }
        T[k * WR__WF_NC_LANCZOS + k] = al;
    }
    if (k < 2) return 0;
    {   /* the Ritz pair of the largest θ = 1 / (λ + σ) */
        double Tk[WR__WF_NC_LANCZOS * WR__WF_NC_LANCZOS];
        for (i = 0; i < k; ++i)
            for (j = 0; j < k; ++j) Tk[i * k + j] = T[i * WR__WF_NC_LANCZOS + j];
        wr_dense_sym_eig((int)k, Tk, th, Y);
    }
    for (i = 0; i < n; ++i) p[i] = 0.0;
    for (j = 0; j < k; ++j) {
        const double *qj = V + (size_t)j * ns;
        double c = Y[j * k + (k - 1)];
        for (i = 0; i < n; ++i) p[i] += c * qj[i];
    }
    lam = wr__wf_sqp_curv(Q, p, NULL, NULL); /* Rayleigh quotient pᵀKp / pᵀMp: pᵀMp below */
    for (i = 0; i < n; ++i)
        if (!Q->active[i]) sm += Q->mdiag[i] * Q->wnc[i] * Q->wnc[i];
    {
        double pm = 0.0;
        for (i = 0; i < n; ++i) pm += Q->mdiag[i] * p[i] * p[i];
        if (!(pm > 0.0)) return 0;
        for (i = 0; i < n; ++i) p[i] /= sqrt(pm); /* ‖p‖_M = 1 */
        lam /= pm;
    }
    if (!(lam < 0.0) || !(sm > 0.0)) return 0; /* no direction of negative curvature found */
    if (!(Q->nc_radius > 0.0)) Q->nc_radius = sqrt(sm);
    Q->nc_floor = WR__WF_NC_FLOOR * sqrt(sm);
    if (Q->nc_radius < Q->nc_floor) Q->nc_radius = Q->nc_floor;
    out->curv = lam;
    return 1;
}

/* d = s(σ) + Δ_nc (±p) in Q->dnc, the sign with the larger model decrease of the projected step;
 * out->gain = the chosen step's model decrease minus the other sign's (≥ 0 by the choice), and
 * out->curv = the Rayleigh quotient of the direction d - s(σ) actually added (pᵀKp/pᵀMp, < 0). */
static void wr__wf_sqp_nc_step(wr__wf_sqp *Q, wr__wf_trial *out) {
    double pred[2] = {0.0, 0.0}, sp, qk, qm = 0.0;
    int32_t i, n = Q->n;
    int sgn;
    for (sgn = 0; sgn < 2; ++sgn) {
        double tau = sgn == 0 ? Q->nc_radius : -Q->nc_radius;
        for (i = 0; i < n; ++i) Q->dnc[i] = Q->wnc[i] + tau * Q->pnc[i];
        wr__wf_sqp_project(Q, Q->dnc);
        pred[sgn] = wr__wf_sqp_predicted(Q);
    }
    sp = pred[0] >= pred[1] ? 1.0 : -1.0;
    for (i = 0; i < n; ++i) Q->dnc[i] = Q->wnc[i] + sp * Q->nc_radius * Q->pnc[i];
    wr__wf_sqp_project(Q, Q->dnc);
    out->gain = wr__wf_sqp_predicted(Q) - pred[sp > 0.0 ? 1 : 0];
    qk = wr__wf_sqp_curv(Q, Q->dnc, Q->wnc, &qm);
    out->curv = qm > 0.0 ? qk / qm : 0.0;
}

/* Evaluate the projected trial step in Q->d / Q->yt and decide it: 1 when accepted (or stopped
 * by round-off: out->roundoff), μ adapted; 0 when rejected (the caller adapts μ). */
static int wr__wf_sqp_judge(wr__wf_sqp *Q, double kkt, wr__wf_trial *out) {
    const wr_wf *wf = Q->wf;
    double pred = wr__wf_sqp_predicted(Q);
    wr_status fs;
    wr__wf_sqp_tox(wf, &Q->B, Q->avar, Q->yt, Q->na, Q->xa, Q->xo);
    fs = wr__wf_energy_impl(wf, Q->xa, Q->xo, 1, &out->Et, NULL, NULL, NULL, NULL);
    out->Et += wr__wf_reg(&Q->B, Q->greg, Q->xo, NULL);
    out->rho = (fs == WR_OK && pred > 0.0) ? (Q->E - out->Et) / pred : -1.0;
    /* the model promises less than the energy's round-off: E - Et is noise and ρ a coin flip
     * (whether the last Newton step was taken used to depend on the last bits of E). Decide
     * by the stationarity residual instead: take the step when it lowers it (a Newton step
     * near a minimiser does), else no evaluation can confirm a decrease any more and rule 1
     * (energy change below resolution) holds. */
    if (fs == WR_OK && pred >= 0.0 && pred <= WR__WF_ROUNDOFF * fmax(fabs(Q->E), WR__WF_ROUNDOFF_FLOOR * Q->eref)) {
        double Eg = 0.0, kt = HUGE_VAL;
        if (wr__wf_energy_impl(wf, Q->xa, Q->xo, 1, &Eg, Q->gx, NULL, NULL, NULL) == WR_OK) {
            wr__wf_reg(&Q->B, Q->greg, Q->xo, Q->gx + wf->nv);
            wr__wf_sqp_reduce(Q, Q->gx, Q->ks);
            kt = wr__wf_kkt(Q->yt, Q->ks, Q->n, Q->na, Q->aref, Q->eref);
        }
        if (kt < kkt) {
            out->rho = 1.0; /* for the report and rules 1/3: the model is as good as it can be checked */
            Q->mu = fmax(WR__WF_MU_MIN, Q->mu / 3.0);
            Q->nu_up = 2.0;
            out->accepted = 1;
        } else {
            out->roundoff = 1;
        }
        return 1;
    }
    if (fs == WR_OK && pred > 0.0 && out->rho > WR__WF_RHO_ACCEPT) {
        double c3 = 2.0 * out->rho - 1.0;
        Q->mu *= fmax(1.0 / 3.0, 1.0 - c3 * c3 * c3);
        if (Q->mu < WR__WF_MU_MIN) Q->mu = WR__WF_MU_MIN;
        Q->nu_up = 2.0;
        out->accepted = 1;
        return 1;
    }
    return 0;
}

/* Levenberg–Marquardt trust region (Nielsen 1999): damped steps until one is accepted on sufficient
 * actual/predicted decrease ρ, adapting μ. A step whose predicted decrease is below E's round-off
 * is judged by the stationarity residual instead (out->roundoff when it does not lower it). With
 * the negative_curvature option, see ON NEGATIVE CURVATURE. */
static wr_status wr__wf_sqp_trust_region(wr__wf_sqp *Q, double kkt, wr__wf_trial *out, wr_diag *diag) {
    double epsact = WR__WF_EPS_ACTIVE;
    memset(out, 0, sizeof *out);
    for (;;) {
        double mu_tr = Q->mu; /* the trust region's μ; raised below while K + μM does not factor */
        int failed = 0, cut;
        wr_status fs;
        while ((fs = wr__wf_sqp_damped_solve(Q, epsact, &out->nact)) != WR_OK) {
            if (fs != WR_ERR_NOT_SPD && fs != WR_ERR_NOT_CONVERGED)
                return wr_fail(diag, fs, -1, "wf solve: linear solve failed (%s)", wr_status_string(fs));
            failed = 1;
            Q->mu = fmax(WR__WF_MU_MIN, Q->mu) * WR__WF_MU_UP;
            if (Q->mu > WR__WF_MU_MAX) return WR_OK;
        }
        out->negcurv = failed && Q->hess_true && Q->D.negative_curvature && wr__wf_sqp_negcurv(Q, out);
        if (out->negcurv) Q->mu = mu_tr; /* ON NEGATIVE CURVATURE: μ stays the trust region's */
        for (cut = 0;; ++cut) {
            if (out->negcurv) wr__wf_sqp_nc_step(Q, out);
            wr__wf_sqp_project(Q, out->negcurv ? Q->dnc : Q->d);
            if (wr__wf_sqp_judge(Q, kkt, out)) {
                if (out->negcurv && out->rho > 0.75) Q->nc_radius *= 2.0;
                if (!out->negcurv) out->curv = out->gain = 0.0;
                return WR_OK;
            }
            ++Q->S.n_rejected;
            ++out->nfail;
            if (!out->negcurv) break;
            Q->nc_radius *= 0.25;
            if (Q->nc_radius < Q->nc_floor) { /* shorter changes nothing s(σ) does not: μ's turn */
                Q->nc_radius = Q->nc_floor;
                break;
            }
            if (cut + 1 >= WR__WF_NC_CUTS) break;
        }
        /* after a rejection ε shrinks ×0.1: snapping a near-bound amplitude to 0 is the one part of
         * the step μ does not shorten */
        epsact *= 0.1;
        Q->mu = fmax(WR__WF_MU_MIN, Q->mu) * Q->nu_up;
        Q->nu_up *= 2.0;
        if (Q->mu > WR__WF_MU_MAX) return WR_OK;
    }
}

/* Take the accepted trial point, report it, and test App. E.3's rules 1 and 3. Rules 1 and 3 only
 * count a step the quadratic model predicted well (ρ > 1/2): a heavily damped step is short and
 * changes E little without the iterate being stationary. Returns 1 when a rule stops the solve. */
static int wr__wf_sqp_take(wr__wf_sqp *Q, int32_t it, double kkt, const wr__wf_trial *tr) {
    double stepa = 0.0, stepz = 0.0, norma = 0.0, normz = 0.0;
    wr_wf_iter_info info;
    int32_t i;
    for (i = 0; i < Q->n; ++i) {
        double dy = fabs(Q->yt[i] - Q->y[i]);
        if (i < Q->na) {
            stepa = fmax(stepa, dy);
            norma = fmax(norma, fabs(Q->yt[i]));
        } else {
            stepz = fmax(stepz, dy);
            normz = fmax(normz, fabs(Q->yt[i]));
        }
        Q->y[i] = Q->yt[i];
    }
    info.iteration = it + 1;
    info.energy = tr->Et + Q->ebase;
    info.kkt = kkt;
    info.step = fmax(stepa / Q->aref, stepz);
    info.alpha_ls = tr->rho;
    info.shift = Q->mu;
    info.n_active = tr->nact;
    info.n_rejected = tr->nfail;
    info.true_hessian = Q->hess_true;
    info.negcurv = tr->negcurv;
    info.curvature = tr->curv;
    info.nc_gain = tr->gain;
    Q->S.n_negcurv += tr->negcurv;
    if (Q->D.progress) Q->D.progress(&info, Q->D.user);
    Q->S.iterations = it + 1;
    if (Q->hess_true && Q->S.switch_iteration < 0) Q->S.switch_iteration = it;
    if (tr->rho > 0.5 && fabs(Q->E - tr->Et) <= Q->D.tol_energy * fabs(Q->E + Q->ebase)) {
        Q->E = tr->Et;
        Q->S.stop = WR_WF_STOP_ENERGY;
        return 1;
    }
    if (tr->rho > 0.5 && stepa <= Q->D.tol_step * norma && stepz <= Q->D.tol_step * normz) {
        Q->S.stop = WR_WF_STOP_STEP;
        return 1;
    }
    Q->E = tr->Et;
    return 0;
}

/* Rule 2 (stationarity) holds at y. a = 0 is a KKT point wherever it holds (E is even in a): leave it
 * along negative curvature of E in the amplitudes at the bound before accepting it (second order,
 * wr__wf_escape). Returns 1 when y escaped (the solve goes on from the new point). */
static int wr__wf_sqp_try_escape(wr__wf_sqp *Q, double abound) {
    double Et = 0.0;
    int32_t i;
    if (Q->S.n_escapes >= WR__WF_MAX_ESCAPES) return 0;
    if (!wr__wf_escape(Q->wf, &Q->B, Q->avar, Q->na, Q->y, Q->H, Q->aref, abound, Q->E, Q->yt, Q->xa, Q->xo,
                       Q->ainit, Q->mdiag, &Et))
        return 0;
    ++Q->S.n_escapes;
    for (i = 0; i < Q->n; ++i) Q->y[i] = Q->yt[i];
    Q->E = Et;
    return 1;
}

/* 1 when every free amplitude is within the ε-active band of the bound (a <= ε a_ref): the SQP has
 * collapsed onto the flat state. Rules 1 and 3 can stop there on small steps near the saddle (a
 * Poisson–Delaunay stretched sheet at 6.5 mm stopped after 3 iterations with max a = 0.14 µm, E
 * 0.0318 J, where the wrinkled minimum has 0.0240 J), so the escape is tried before such a stop. */
static int wr__wf_sqp_flat(const wr__wf_sqp *Q) {
    int32_t i;
    for (i = 0; i < Q->na; ++i)
        if (Q->y[i] > WR__WF_EPS_ACTIVE * Q->aref) return 0;
    return Q->na > 0;
}

/* A stop by rule 1 or 3 on a flat iterate: evaluate there (fresh face Hessians for the escape's
 * curvature test) and escape if E has negative curvature along the amplitudes. Returns 1 when the
 * solve goes on, 0 to stop, -1 on an evaluation error (status in *st). */
static int wr__wf_sqp_escape_flat_stop(wr__wf_sqp *Q, wr_status *st, wr_diag *diag) {
    if (!wr__wf_sqp_flat(Q) || Q->S.n_escapes >= WR__WF_MAX_ESCAPES) return 0;
    *st = wr__wf_sqp_evaluate(Q, 0, diag);
    if (*st) return -1;
    return wr__wf_sqp_try_escape(Q, WR__WF_EPS_ACTIVE * Q->aref);
}

/* The iteration of App. E.3: evaluate, test stationarity (with the second-order escape), assemble
 * the model, take a trust-region step, test rules 1 and 3 (with the escape when the iterate is
 * flat). Leaves the stop reason in Q->S.stop. */
static wr_status wr__wf_sqp_iterate(wr__wf_sqp *Q, wr_diag *diag) {
    int have_grad = 0, rebase_kkt = 0;
    int32_t it;
    Q->mu = WR__WF_MU0;
    Q->nu_up = 2.0;
    Q->hess_true = Q->D.hessian == WR_WF_HESSIAN_TRUE;
    for (it = 0;; ++it) {
        double t1 = wr_time_seconds(), kkt;
        wr__wf_trial tr;
        wr_status st;
        int fresh_hess = 0;
        if (!have_grad) {
            st = wr__wf_sqp_evaluate(Q, it == 0, diag);
            if (st) return st;
            have_grad = 1;
            fresh_hess = 1;
        }
        kkt = wr__wf_kkt(Q->y, Q->g, Q->n, Q->na, Q->aref, Q->eref);
        if (rebase_kkt) { /* after an escape the reference residual is the escaped point's */
            Q->S.kkt0 = fmax(Q->S.kkt0, kkt);
            rebase_kkt = 0;
        }
        if (it == 0) {
            Q->S.energy0 = Q->E + Q->ebase;
            Q->S.kkt0 = kkt;
        }
        Q->S.energy = Q->E + Q->ebase;
        Q->S.kkt = kkt;
        Q->S.iterations = it;
        if (kkt <= Q->D.tol_kkt * Q->S.kkt0 || kkt == 0.0) {
            if (wr__wf_sqp_try_escape(Q, 0.0)) {
                rebase_kkt = 1;
                have_grad = 0;
                continue;
            }
            Q->S.stop = WR_WF_STOP_KKT;
            return WR_OK;
        }
        if (it >= Q->D.max_iter) {
            Q->S.stop = WR_WF_STOP_MAX_ITER;
            return WR_OK;
        }
        /* App. E.3 Hessian strategy: per-face SPD projection far from the solution, the true Hessian
         * once the relative KKT residual is below hessian_switch (AUTO), or one of them throughout. */
        if (Q->D.hessian == WR_WF_HESSIAN_AUTO && !Q->hess_true && kkt <= Q->D.hessian_switch * Q->S.kkt0)
            Q->hess_true = 1;
        if (fresh_hess) {
            st = wr__wf_sqp_assemble(Q, diag);
            if (st) return st;
        }
        wr__wf_sqp_damping(Q);
        Q->S.seconds_assembly += wr_time_seconds() - t1;
        st = wr__wf_sqp_trust_region(Q, kkt, &tr, diag);
        if (st) return st;
        if (tr.roundoff) {
            Q->S.stop = WR_WF_STOP_ENERGY;
            return WR_OK;
        }
        if (!tr.accepted) {
            Q->S.stop = WR_WF_STOP_LINE_SEARCH;
            return WR_OK;
        }
        have_grad = 0;
        if (wr__wf_sqp_take(Q, it, kkt, &tr)) {
            int go_on = wr__wf_sqp_escape_flat_stop(Q, &st, diag);
            if (go_on < 0) return st;
            if (!go_on) return WR_OK;
            Q->S.stop = WR_WF_STOP_NONE;
            rebase_kkt = 1;
        }
    }
}

/* The returned iterate in (a, ω), its objective and final stationarity residual. */
static wr_status wr__wf_sqp_finish(wr__wf_sqp *Q, double *a, double *omega, wr_diag *diag) {
    const wr_wf *wf = Q->wf;
    double E = 0.0;
    int32_t v, i;
    wr_status st;
    wr__wf_sqp_tox(wf, &Q->B, Q->avar, Q->y, Q->na, Q->xa, Q->xo);
    st = wr_wf_energy(wf, Q->xa, Q->xo, &E, Q->gx, NULL, NULL, diag);
    if (st) return st;
    Q->S.energy_reg = wr__wf_reg(&Q->B, Q->greg, Q->xo, Q->gx + wf->nv);
    E += Q->S.energy_reg;
    wr__wf_sqp_reduce(Q, Q->gx, Q->g);
    Q->S.kkt = wr__wf_kkt(Q->y, Q->g, Q->n, Q->na, Q->aref, Q->eref);
    Q->S.energy = E;
    Q->S.a_ref = Q->aref;
    Q->S.e_ref = Q->eref;
    for (v = 0; v < wf->nv; ++v) a[v] = Q->xa[v];
    for (i = 0; i < wf->ne; ++i) omega[i] = Q->xo[i];
    if (Q->S.stop == WR_WF_STOP_MAX_ITER || Q->S.stop == WR_WF_STOP_LINE_SEARCH)
        return wr_fail(diag, WR_ERR_NOT_CONVERGED, -1, "wf solve: stopped (%s) after %d iterations, KKT %g (initial %g)",
                       Q->S.stop == WR_WF_STOP_MAX_ITER ? "max iterations" : "line search", (int)Q->S.iterations,
                       Q->S.kkt, Q->S.kkt0);
    return WR_OK;
}

/* App. E.3 as a sequence of stages: unknowns and a feasible start, the reduction maps and the
 * fixed Hessian pattern, the scales, the trust-region SQP iteration, the returned iterate. */
WRDEF wr_status wr_wf_solve(const wr_wf *wf, const wr_wf_solve_desc *desc, double *a, double *omega,
                            wr_wf_solve_stats *stats, wr_diag *diag) {
    wr__wf_sqp Q;
    double t0 = wr_time_seconds();
    wr_status st;
    if (stats) memset(stats, 0, sizeof *stats);
    if (!wf || !a || !omega) return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "wf solve: NULL argument");
    memset(&Q, 0, sizeof Q);
    Q.wf = wf;
    Q.S.switch_iteration = -1;
    st = wr__wf_sqp_defaults(&Q.D, desc, diag);
    if (st) return st;
    st = wr__wf_sqp_start(&Q, a, omega, diag);
    if (!st) st = wr__wf_sqp_face_maps(&Q, diag);
    if (!st) st = wr__wf_sqp_pattern(&Q, diag);
    if (!st) st = wr__wf_sqp_scales(&Q, diag);
    if (!st) st = wr__wf_sqp_iterate(&Q, diag);
    if (!st) st = wr__wf_sqp_finish(&Q, a, omega, diag);
    Q.S.seconds = wr_time_seconds() - t0;
    if (stats) *stats = Q.S;
    wr__wf_sqp_free(&Q);
    return st;
}

#ifdef __cplusplus
}
#endif
#endif /* WRINKLE_WRINKLE_FIELD_IMPLEMENTATION_DONE */
#endif /* WRINKLE_IMPLEMENTATION */
