/* wrinkle/shell.h — discrete thin-shell elastic energy: StVK, tension-field or Baraff–Witkin membrane,
 * mid-edge (Koiter), fold-safe dihedral or quadratic (Bergou) bending; values, gradients and
 * per-element Hessians.
 * wrinkle v0.1.0 — MIT licence (see LICENSE). Needs only libc and libm (and core.h, mesh.h, tft.h).
 *
 * This is the one place wrinkle writes shell energy. The StVK reference solver and the TFT
 * base-surface solve of TFW ("Fine Wrinkling on Coarsely Meshed Thin Shells", 2021, Sec. 4.1) both
 * use it. Discretisation (TFW App. A):
 *   - first fundamental form per face, I = drᵀdr from the edge vectors, rest I_u from the 2D rest
 *     (pattern) corners (wr_mesh_face_rest) or from a 3D rest shape;
 *   - second fundamental form per face from mid-edge normals (Grinspun 2003, Weischedel 2012, Chen et
 *     al. 2018), TFW App. A: II = 2 [[e1·(n̂1−n̂0), e2·(n̂1−n̂0)], [e2·(n̂1−n̂0), e2·(n̂2−n̂0)]] with
 *     e1 = v1−v0, e2 = v2−v0 and n̂c the mid-edge normal of the edge opposite corner c;
 *     n̂c = the unit face normal on a boundary edge, otherwise the NORMALISED average of the two
 *     adjacent unit face normals ("mid-edge average normal"). Normalising is our reading of the hat
 *     in the paper; it makes a crease of dihedral angle φ contribute 2 sin(φ/2), which is exact for a
 *     cylinder sampled by vertices on it (see the tests). Each n̂c is perpendicular to its own edge,
 *     so the two off-diagonal readings e1·(n̂2−n̂0) and e2·(n̂1−n̂0) agree and II is symmetric.
 *   - membrane: StVK (TFW Eq. 2, 4, 33) or its tension-field relaxation (TFW App. B, tft.h), or an
 *     orthotropic StVK (warp/weft moduli, shear modulus, grain angle) for anisotropic fabrics, or the
 *     Baraff–Witkin warp/weft/shear membrane (the Style3D paper's simulator, its Sec. 5);
 *   - bending: Koiter with the mid-edge II (TFW Eq. 3), or the same Koiter energy on a shape operator
 *     built from atan2 hinge angles that stays finite through 180° folds (ON DIHEDRAL BENDING), or
 *     Bergou et al. 2006 quadratic bending (TFW Eq. 28, recommended for the TFT base surface), or none.
 *
 * API (create/free pair: wr_shell_create → wr_shell_free)
 *   wr_shell_create(s, mesh, desc, diag)            material, model choice, precomputed rest data
 *   wr_shell_free(s)                                free and zero (safe on a zeroed shell)
 *   wr_shell_energy(s, x, E, grad, diag)            total energy [J] and gradient (nv*3) at x (nv*3)
 *   wr_shell_energy_parts(s, x, Emem, Ebend, diag)  membrane and bending parts
 *   wr_shell_face_energy(s, f, x, Emem, Ebend)      one face's membrane and bending energy
 *   wr_shell_hessian_elements(s, x, project, sink, diag)  element Hessians streamed to a callback
 *   wr_shell_hessian_elements_part(s, x, project, parts, sink, diag)  only the face blocks and/or
 *                                                   the (constant) quadratic-bending blocks
 *   wr_shell_vertex_masses(s, mass)                 lumped masses ρ·h·A/3 [kg] (for gravity)
 *   wr_shell_face_strain(s, f, x, eps)              Green strain (ε11, ε22, ε12) of face f
 *   wr_shell_face_stencil(s, f, verts)              the 6 vertices of face f's bending stencil
 *   wr_shell_face_block(s, f, x, n, verts, Ke)      face f's Hessian block (membrane + bending)
 *                                                   over the n vertices it couples, unprojected
 *   wr_shell_membrane_element(s, f, x9, g, H)       one face's membrane energy, gradient, Hessian
 *   wr_shell_midedge_element(x18, mask, Q, bbar, E, g, H)   one face's mid-edge bending
 *   wr_shell_dihedral_element(x18, mask, M, thbar, E, g, H, theta)  one face's dihedral bending
 *   wr_shell_hinge_angle(x12, theta, g, H)          signed atan2 dihedral angle of a hinge, ∇, ∇²
 *   wr_shell_stvk_density(C, eps, dW, d2W)          Voigt StVK density in Green-strain coordinates
 *   wr_shell_koiter_point(pt, p, E, g, H)           Koiter shell energy density at one point of a
 *                                                   smooth surface (subdiv.h's Loop limit surface)
 *
 * EXAMPLE
 *     wr_mesh m;  wr_shell s;  wr_shell_desc d;  wr_diag dg;  double E, *g;
 *     if (wr_mesh_rectangle(&m, 1.0, 1.0, 20, 20, &dg) != WR_OK) { puts(dg.message); return 1; }
 *     memset(&d, 0, sizeof d);
 *     d.young = 1e6; d.poisson = 0.3; d.thickness = 1e-3;         // SI units
 *     d.membrane = WR_MEMBRANE_TFT; d.bending = WR_BENDING_QUADRATIC; // TFW Sec. 4.1 base surface
 *     if (wr_shell_create(&s, &m, &d, &dg) != WR_OK) { puts(dg.message); return 1; }
 *     g = (double *)wr_alloc_array(3 * (size_t)m.nv, sizeof(double));
 *     if (wr_shell_energy(&s, m.pos, &E, g, &dg) != WR_OK) { puts(dg.message); return 1; }
 *     printf("E = %g J at rest\n", E);                              // 0 (to rounding)
 *     wr_shell_free(&s);  wr_mesh_free(&m);  wr_free(g);
 *
 * ON NORMALISATION
 *   TFW Eq. (1) as printed reads E = ½∫(h/4 W_s + h³/12 W_b) with ‖M‖²_SV = α/2 tr²M + β tr M²,
 *   α = Yν/(1−ν²), β = Y/(2(1+ν)) (Eq. 33). Expanding that gives exactly HALF the standard
 *   plane-stress StVK membrane energy h(α/2 tr²ε + β tr ε²) (ε = ½(I_u⁻¹I − id), Green strain) and
 *   half the Kirchhoff plate energy D/2[(κ1+κ2)² − 2(1−ν)κ1κ2]. The factor does not move an unloaded
 *   minimiser but it does matter against gravity, so we use the standard normalisation:
 *       E_mem  = Σ_f A_f · (h/4) ‖I_u⁻¹I − id‖²_SV        = Σ_f A_f · ½ γᵀ (h C) γ
 *       E_bend = Σ_f A_f · (h³/12) ‖I_u⁻¹(II − II_u)‖²_SV  = Σ_f A_f · ½ κᵀ C_b κ
 *   with Voigt vectors γ = (ε11, ε22, 2ε12), κ = (K11, K22, 2K12), K = I_u⁻¹(II − II_u) expressed in
 *   an orthonormal rest frame, C = Y/(1−ν²)[[1,ν,0],[ν,1,0],[0,0,(1−ν)/2]] and C_b = B/Y·(1−ν²)·C
 *   with B = Y h³/(12(1−ν²)) by default (desc.bending_stiffness overrides B). A cylinder of radius
 *   R then stores B/(2R²) per unit area, the plate value. Quadratic bending:
 *       E_qb = (B/2) Σ_{interior v} |(L x)_v|² / A_v
 *   with L the cotangent Laplacian of the flat rest mesh and A_v the mixed Voronoi area (Meyer et al.
 *   2003), i.e. (B/2)∫|Δx|² = (B/2)∫(κ1+κ2)², the plate energy for isometric bending of a flat
 *   sheet (Bergou et al. 2006, vertex form; TFW Eq. 28 writes the first Lamé parameter α as the
 *   coefficient, which vanishes at ν = 0, so we read it as the bending modulus B). Its Hessian is
 *   constant. Boundary vertices carry no term: the cotangent Laplacian of a boundary vertex does not
 *   vanish on the flat rest mesh (it sees the boundary flux), so including it would put energy into
 *   the rest state; this kit does not add Wang et al. 2015's boundary correction. A free boundary thus
 *   only resists bending through its interior neighbours' stencils.
 *
 * ON ORTHOTROPY
 *   desc.orthotropic: C = 1/(1−ν12ν21)[[E1, ν12E2, 0], [ν12E2, E2, 0], [0, 0, G12(1−ν12ν21)]]
 *   (E1 warp, E2 weft, ν21 = ν12E2/E1), membrane h·C and bending h³/12·C, in the material frame of
 *   each face: warp at grain_angle[f] [rad] from the rest-domain x axis. Needs a 2D rest domain.
 *   TFT and quadratic bending are isotropic models and reject orthotropy (WR_ERR_UNSUPPORTED).
 *
 * ON BARAFF–WITKIN
 *   Baraff & Witkin 1998 ("Large steps in cloth simulation", Sec. 4.2–4.3), with the columns of the
 *   deformation gradient in the material frame, F1 = ∂x/∂u along the warp (grain_angle[f] from the
 *   rest x axis) and F2 = ∂x/∂v along the weft: stretch conditions C_u = |F1| − 1, C_v = |F2| − 1 and
 *   the shear condition C_s = F1·F2, each with its stiffness, integrated over the rest area:
 *       E_mem = Σ_f A_f · ½ (k_u C_u² + k_v C_v² + k_s C_s²),   k = stretch_warp, _weft, _shear [N/m].
 *   (BW write C = a·(…) and E = k/2 CᵀC, i.e. a² per triangle; we take the area-integrated density
 *   so that k is a per-width stiffness and the energy does not depend on the mesh.) For small strain
 *   C_u ≈ ε11, C_v ≈ ε22, C_s ≈ 2ε12: orthotropic StVK with ν12 = 0, E1h = k_u, E2h = k_v, G12h = k_s
 *   (checked in the tests). The conditions resist compression like stretch (no buckling relief) and
 *   carry no Poisson coupling. Needs a 2D rest domain (the grain). The stretch-condition Hessian
 *   k[I − (I − f̂f̂ᵀ)/|F|] is indefinite under compression (|F| < 1): project_spd handles it.
 *
 * ON DIHEDRAL BENDING (which formulation, and why)
 *   The Style3D simulator uses the "stable discrete bending" of Wang, Yang & Wang 2023 (TOG 42(6)
 *   175): dihedral-angle-based (DAB) bending energies ψ(θ) of each hinge, with an analytic
 *   eigensystem of the hinge Hessian (four positive, four negative, four zero eigenvalues) used to
 *   project it PSD, and an orthotropic geometric stiffness that keeps only bending modes near
 *   degenerate triangles (from the paper's abstract; its full text was not available to us, so we
 *   do not implement those two Hessian rectifications: the face block is projected numerically,
 *   wr_dense_project_spd, when project_spd is set). What we take from it is the DAB kinematics: θ
 *   from atan2 of the two face normals, finite and smooth at any fold short of degenerate faces.
 *   Energy: the mid-edge II of TFW App. A equals b = (−φ0 h0 − φ1 h1, −φ0 h0 − φ2 h2, −φ0 h0) with
 *   φ_k = 2 sin(θ_k/2) and h_k the altitude onto edge k (write n̂_k = R(θ_k/2) n̂, rotation about the
 *   edge); its singularity at θ = π is only in the normalised average normal. We keep that shape
 *   operator but use φ_k = θ_k (atan2) and the REST altitudes h̄_k, so b = W θ with a constant W and
 *       E_bend,f = ½ (b − b̄)ᵀ Q_f (b − b̄) = ½ δθᵀ M_f δθ,   M_f = Wᵀ Q_f W  (3×3 per face),
 *   i.e. a DAB energy coupling the three hinges of a face so that it is the Koiter (or warp/weft)
 *   plate energy of the face's shape operator, rather than a per-hinge k(θ−θ̄)² (Discrete Shells):
 *   one energy with the kit's mid-edge model (same Q_f, same rest II machinery), and the coupled
 *   form carries the Poisson and warp/weft tensor terms that a sum of independent hinges cannot.
 *   Why φ = θ: the energy stays finite at the fold (π²/4 times the mid-edge
 *   value 2² there), the restoring torque grows up to the fold instead of vanishing (2 sin(θ/2) has
 *   zero slope at π, which would make tight folds free), and an isometric hinge gets exactly the
 *   curvature θ/h. Why rest altitudes: the Hessian then needs only ∇θ and ∇²θ of each hinge; the
 *   difference to deformed altitudes is O(strain × curvature), small for cloth. On a cylinder meshed
 *   with edges along the generators the face curvature is exactly 1/R; on an equilateral mesh the
 *   energy converges as O((a/R)²) (a the edge length), closer than mid-edge at the same mesh
 *   (figures and the check: tests/test_shell.c, cylinder_dihedral_equilateral_mesh).
 *   Stateless: δθ = θ − θ̄ is wrapped into
 *   (−π, π], so the one non-smooth configuration is the fold exactly opposite the rest angle (two
 *   faces lying flat on each other for a flat rest): E is continuous there but its slope changes
 *   sign, and a hinge pushed past it reads as folded the other way (contact must prevent that in a
 *   simulation). Degenerate deformed faces (zero area) are WR_ERR_GEOMETRY; |∇θ| grows like 1/h.
 *   The rest angles θ̄ come from rest_pos3 when given, else 0 (flat).
 *
 * ON ANISOTROPIC BENDING
 *   bending_warp = B1, bending_weft = B2 [N·m] (both > 0) give C_b = [[B1, ν√(B1B2), 0],
 *   [ν√(B1B2), B2, 0], [0, 0, (1−ν)/2·√(B1B2)]] in the material frame (ν = poisson, or poisson_warp
 *   when orthotropic): a cylinder bent along the warp stores B1/(2R²), along the weft B2/(2R²). The
 *   coupling and twist terms are our reading (fabric data give B1 and B2 only): the isotropic values
 *   with B replaced by the geometric mean. Works with mid-edge and dihedral bending and any membrane.
 *
 * ON ELEMENT HESSIANS
 *   wr_shell_hessian_elements calls sink->add(user, k, verts, Ke) once per element: per face, the
 *   membrane (3 vertices) plus mid-edge or dihedral bending (3 face vertices + up to 3 across the
 *   edges, k <= 6) summed into one 3k×3k row-major block, dof order (v0x, v0y, v0z, v1x, …); and,
 *   with quadratic bending, one block per interior vertex stencil (the vertex and its neighbours).
 *   project_spd == 1 replaces each face block by its nearest PSD matrix (wr_dense_project_spd, floor
 *   0), WR_SHELL_PROJECT_LARGE only the Loop element's (ON THE LOOP ELEMENT); the quadratic blocks are
 *   PSD by construction. A non-WR_OK return from add stops the loop.
 *   The quadratic-bending blocks do not depend on x (TFW Eq. 28 is quadratic in the positions), so a
 *   Newton loop can assemble them once: wr_shell_hessian_elements_part streams only the face blocks
 *   (parts = WR_SHELL_HESS_FACES), only the quadratic stencils (WR_SHELL_HESS_QUADRATIC), or both
 *   (WR_SHELL_HESS_ALL, what wr_shell_hessian_elements does), each in the same order as above.
 *
 * ON THE LOOP ELEMENT (desc.loop_element; issue 15, docs/design-higher-order-shell.md)
 *   Cirak, Ortiz & Schröder 2000: the surface is the Loop limit surface of the mesh (subdiv.h), and
 *   each face with three interior corners carries Koiter's energy (wr_shell_koiter_point: the StVK
 *   membrane and plate bending written in the limit surface's own metric and second fundamental
 *   form) at its centre, one quadrature point, weighted by the face's rest area. Strain and curvature
 *   come from one smooth map, so a wave whose crests cross the edges has no interpolation strain —
 *   the defect of linear triangles on unstructured meshes under strong tension. With loop_element = 1
 *   faces with a corner on the boundary keep the linear element (membrane + desc.bending); the mix
 *   tiles the rest domain exactly (area weights), so a uniform strain is exact everywhere. With
 *   loop_element = 2 every face is a Loop face, boundary corners completed by ghost vertices
 *   (subdiv.h ON GHOST VERTICES, our reading of Cirak & Ortiz 2001): an edge whose vertices are free
 *   is a free edge (the ghosts pull the curvature across it towards zero, no bending moment);
 *   holding the boundary vertices alone is a hinge; holding them and the vertices of the faces along
 *   the edge clamps it (the ghosts, hence the tangent plane there, are fixed). Needs the isotropic StVK
 *   membrane (WR_ERR_UNSUPPORTED otherwise). Rest state: rest_pos3, else the rest domain, else pos, one
 *   point per vertex; on a mesh with corner_rest (a sewn seam, a closed tube's unrolled pattern) each
 *   face's stencil gets its own flat chart instead: the faces around its corners laid into the face's
 *   rest corners one shared edge at a time by the rigid motion (rotation + translation) that aligns
 *   the edge, so the rest limit surface is flat and unstrained across a seam (a vertex whose panels'
 *   angles do not close to 2π takes its first face's placement). Statics only (wr_shell_face_block,
 *   hence dynamics.h, refuses Loop faces). Hessian blocks span the face's stencil (12 vertices on a regular patch, up to
 *   WR_SUBDIV_MAX_STENCIL), larger than newton.h can project: with project_spd != 0 (1, or
 *   WR_SHELL_PROJECT_LARGE as statics.h passes when its Newton step projects) they are projected PSD
 *   in the 15-D point space (x_v, x_w, x_vv, x_vw, x_ww), with 0 they are exact. Accuracy
 *   (tests/test_subdiv.c; figures in docs/design-higher-order-shell.md, "Measured"): on a valence-6
 *   lattice bent to a cylinder the bending energy converges at O(h²), the membrane's at O(h⁴); near
 *   extraordinary vertices (valence 4/8) a bending bias stays under refinement — Loop surfaces do
 *   not reproduce quadratics there, a known limitation. Boundary faces (ghosts or the linear row)
 *   leave a one-row boundary layer, O(h) (the ghosts' free-edge completion relaxes an imposed
 *   curvature at the edge); uniform strain is exact with both.
 * ON UNITS
 *   Y, E1, E2, G12 [Pa], h [m], B, B1, B2 [N·m], k_u, k_v, k_s [N/m], ρ [kg/m³], positions [m],
 *   energies [J], angles [rad].
 *
 * ON THREADS
 *   A created shell is read-only; concurrent evaluations on distinct x are safe.
 */
#ifndef WRINKLE_SHELL_H
#define WRINKLE_SHELL_H

#include "core.h"
#include "mesh.h"
#include "subdiv.h"
#include "tft.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef enum wr_membrane_model {
    WR_MEMBRANE_STVK = 0, /* St. Venant–Kirchhoff (TFW Eq. 2) */
    WR_MEMBRANE_TFT = 1,  /* tension-field relaxation (TFW App. B, tft.h) */
    WR_MEMBRANE_NONE = 2,
    WR_MEMBRANE_BARAFF_WITKIN = 3 /* Baraff & Witkin 1998 warp/weft stretch + shear conditions */
} wr_membrane_model;

typedef enum wr_bending_model {
    WR_BENDING_MIDEDGE = 0,   /* Koiter bending with the mid-edge II (TFW Eq. 3, App. A) */
    WR_BENDING_QUADRATIC = 1, /* Bergou et al. 2006 quadratic bending, flat rest (TFW Eq. 28) */
    WR_BENDING_NONE = 2,
    WR_BENDING_DIHEDRAL = 3 /* fold-safe: the face shape operator from atan2 hinge angles */
} wr_bending_model;

/* Defaults (zero means default):
 *   membrane WR_MEMBRANE_STVK, bending WR_BENDING_MIDEDGE;
 *   young [Pa] and thickness [m]: required > 0 (isotropic); poisson 0 is ν = 0, must be in (−1, 1);
 *   bending_stiffness [N·m]: 0 → Y h³/(12(1−ν²)); density [kg/m³]: 0 → massless;
 *   orthotropic 0 → isotropic; with orthotropic != 0: young_warp, young_weft, shear_modulus > 0,
 *   poisson_warp = ν12 (0 allowed) with ν12²·E2/E1 < 1; grain_angle NULL → all 0;
 *   rest_pos3 NULL → rest from the mesh (corner_rest, else rest, else pos); non-NULL: an nv*3 3D rest
 *   shape whose metric AND curvature (II_u) are the rest state;
 *   membrane WR_MEMBRANE_BARAFF_WITKIN: stretch_warp, stretch_weft, stretch_shear > 0 [N/m] required
 *   (ON BARAFF–WITKIN), needs a 2D rest domain; young may then be 0 when the bending stiffness is
 *   given otherwise (bending_stiffness, bending_warp/weft, or no bending);
 *   bending_warp, bending_weft [N·m]: both 0 → isotropic (B, or h³/12·C when orthotropic); both > 0
 *   → warp/weft bending (ON ANISOTROPIC BENDING) with mid-edge or dihedral bending. */
/* The rest data of one quadrature point of a smooth shell (issue 15's Loop element, subdiv.h):
 * covariant rest metric A = (A11, A12, A22) and rest curvature B (b_ab = x_ab · n), in the surface
 * parameters (v, w); membrane stiffness Ym = E h / (1 − ν²) [N/m], bending stiffness
 * Db = E h³ / (12 (1 − ν²)) [N·m], Poisson ratio nu. */
typedef struct wr_shell_koiter_rest {
    double A[3], B[3], Ym, Db, nu;
} wr_shell_koiter_rest;

typedef struct wr_shell_desc {
    wr_membrane_model membrane;
    wr_bending_model bending;
    double young;
    double poisson;
    double thickness;
    double bending_stiffness;
    double density;
    int32_t orthotropic;
    double young_warp, young_weft, shear_modulus, poisson_warp;
    const double *grain_angle; /* nf [rad], copied */
    const double *rest_pos3;   /* nv*3 [m], copied into rest data, not kept */
    double stretch_warp, stretch_weft, stretch_shear; /* Baraff–Witkin stiffnesses [N/m] */
    double bending_warp, bending_weft; /* [N·m]: anisotropic bending (mid-edge or dihedral) */
    int32_t loop_element;      /* 1: Koiter energy on the Loop limit surface of faces with interior corners, 2:
                                  of every face, ghost vertices at the boundary (ON THE LOOP ELEMENT) */
} wr_shell_desc;

typedef struct wr_shell {
    int32_t nv, nf;
    wr_membrane_model membrane;
    wr_bending_model bending;
    double young, poisson, thickness, density, bending_stiffness; /* resolved; B also for orthotropic (warp) */
    int32_t orthotropic;
    double bw_k[3];   /* Baraff–Witkin warp, weft, shear stiffnesses [N/m] (BW membrane only) */
    double C_mem[9];  /* h·C, Voigt (ε11, ε22, 2ε12), row-major [N/m] */
    double C_bend[9]; /* bending Voigt stiffness [N·m] */
    int32_t *faces;   /* nf*3 copy of the mesh faces */
    int32_t *opp;     /* nf*3: vertex across the edge opposite corner k, or -1 on a boundary edge */
    double *dinv;     /* nf*4 row-major inverse of the rest edge matrix [ū1−ū0, ū2−ū0], material frame */
    double *area;     /* nf rest areas [m²] */
    double *qbend;    /* nf*9: mid-edge: E_bend,f = ½ δbᵀ Q δb, δb = (b11, b22, b12) − rest, barycentric
                         coords; dihedral: E_bend,f = ½ δθᵀ M δθ, δθ = hinge angles of edges 0..2 − rest */
    double *bbar;     /* nf*3 rest II (b11, b22, b12), or rest hinge angles (dihedral), or NULL (flat rest) */
    int32_t n_qb;     /* quadratic-bending stencils (interior vertices) */
    int32_t *qb_start, *qb_vert; /* stencil s: qb_vert[qb_start[s] .. qb_start[s+1]), centre first */
    double *qb_w;     /* cotangent weights L_vj (centre weight = −Σ) */
    double *qb_coef;  /* n_qb: B / A_v [N/m] */
    double total_area;
    /* the Loop element (ON THE LOOP ELEMENT): face f's limit-surface stencil is loop_vert/loop_w
     * [loop_start[f] .. loop_start[f+1]) (empty: the linear element); loop_w holds 6 weights per entry */
    int32_t n_loop_faces;
    int32_t *loop_start, *loop_vert;
    double *loop_w, *loop_wt; /* loop_wt: nf quadrature weights, rest area / √det A (ON THE LOOP ELEMENT) */
    wr_shell_koiter_rest *loop_rest;
} wr_shell;

/* Element Hessian consumer. Ke is 3k×3k row-major over verts[0..k). */
typedef struct wr_hess_sink {
    void *user;
    wr_status (*add)(void *user, int32_t k, const int32_t *verts, const double *Ke);
} wr_hess_sink;

WRDEF wr_status wr_shell_create(wr_shell *s, const wr_mesh *m, const wr_shell_desc *desc, wr_diag *diag);
WRDEF void wr_shell_free(wr_shell *s);
/* Total energy [J] at positions x (nv*3 [m]); grad (nv*3 [N]) is overwritten when non-NULL.
 * WR_ERR_GEOMETRY (item = face) when a deformed face or mid-edge normal is degenerate (zero area, or
 * two adjacent faces folded flat onto each other); WR_ERR_DOMAIN (item = vertex) for a non-finite
 * coordinate, or when the result is not finite. */
WRDEF wr_status wr_shell_energy(const wr_shell *s, const double *x, double *E, double *grad, wr_diag *diag);
WRDEF wr_status wr_shell_energy_parts(const wr_shell *s, const double *x, double *E_membrane, double *E_bending,
                                      wr_diag *diag);
/* One face's membrane and bending energy [J] at x (the face-block split of wr_shell_energy_parts; the
 * quadratic bending model has no per-face part and gives 0). WR_ERR_INVALID_ARG, WR_ERR_GEOMETRY. */
WRDEF wr_status wr_shell_face_energy(const wr_shell *s, int32_t f, const double *x, double *E_membrane, double *E_bending);
WRDEF wr_status wr_shell_hessian_elements(const wr_shell *s, const double *x, int32_t project_spd,
                                          const wr_hess_sink *sink, wr_diag *diag);
/* parts for wr_shell_hessian_elements_part (ON ELEMENT HESSIANS); any other bit is WR_ERR_INVALID_ARG */
#define WR_SHELL_HESS_FACES 1     /* per face: membrane + mid-edge bending */
#define WR_SHELL_HESS_QUADRATIC 2 /* per interior vertex stencil: quadratic bending (constant in x) */
#define WR_SHELL_HESS_ALL 3
/* project_spd of wr_shell_hessian_elements(_part): 0 every block exact, 1 every block projected PSD,
 * WR_SHELL_PROJECT_LARGE only the blocks too large for newton.h's projection (the Loop element's) */
#define WR_SHELL_PROJECT_LARGE 2
WRDEF wr_status wr_shell_hessian_elements_part(const wr_shell *s, const double *x, int32_t project_spd, int32_t parts,
                                               const wr_hess_sink *sink, wr_diag *diag);
WRDEF void wr_shell_vertex_masses(const wr_shell *s, double *mass);
WRDEF void wr_shell_face_strain(const wr_shell *s, int32_t f, const double *x, double eps[3]);
/* verts[0..2] = face corners, verts[3+k] = vertex across the edge opposite corner k or -1.
 * Returns the mask (bit k set when verts[3+k] exists). */
WRDEF int32_t wr_shell_face_stencil(const wr_shell *s, int32_t f, int32_t verts[6]);
/* Face f's element Hessian at x (nv*3): membrane plus mid-edge or dihedral bending, over the *n
 * vertices it couples (its 3 corners, and with mid-edge/dihedral bending the vertices across its
 * edges that exist), written to verts[0..n) and Ke ((3n)² row-major, at most 18×18 = 324), not
 * projected: the one face block the statics (through the sink) and the dynamic simulator share.
 * Returns WR_OK or WR_ERR_GEOMETRY (an undefined normal in the bending stencil). */
WRDEF wr_status wr_shell_face_block(const wr_shell *s, int32_t f, const double *x, int32_t *n, int32_t verts[6],
                                    double Ke[324]);
/* Membrane energy of face f with corner positions x9; g (9) and H (81) may be NULL. */
WRDEF double wr_shell_membrane_element(const wr_shell *s, int32_t f, const double x[9], double *g, double *H);
/* Mid-edge bending of one stencil x18 (layout of wr_shell_face_stencil; absent vertices ignored):
 * E = ½ δbᵀ Q δb, δb = II − bbar (bbar NULL = 0). g (18), H (324), b (3: b11, b22, b12) may be NULL.
 * WR_ERR_GEOMETRY when a normal is undefined. */
WRDEF wr_status wr_shell_midedge_element(const double x[18], int32_t mask, const double Q[9], const double *bbar,
                                         double *E, double *g, double *H, double *b);
/* Dihedral (fold-safe) bending of one stencil x18 (layout of wr_shell_face_stencil): E = ½ δθᵀ M δθ,
 * δθ_k = θ_k − thbar_k wrapped into (−π, π] (thbar NULL = 0), θ_k the signed atan2 angle of the hinge
 * across edge k (0 when absent). g (18), H (324), theta (3) may be NULL. WR_ERR_GEOMETRY when a face
 * of the stencil is degenerate (zero area) or the hinge edge has zero length. */
WRDEF wr_status wr_shell_dihedral_element(const double x[18], int32_t mask, const double M[9], const double *thbar,
                                          double *E, double *g, double *H, double *theta);
/* Signed dihedral angle θ ∈ (−π, π] of the hinge x0 x1 (shared edge) between faces (x0, x1, x2) and
 * (x1, x0, x3): the rotation about (x1 − x0) taking the first face's normal to the second's, 0 when
 * flat, ±π when folded flat onto each other. g (12) and H (144) may be NULL. Returns 0 on success,
 * −1 for a degenerate face or edge. */
WRDEF int32_t wr_shell_hinge_angle(const double x[12], double *theta, double *g, double *H);
/* ½ γᵀCγ with γ = (ε11, ε22, 2ε12); dW, d2W w.r.t. (ε11, ε22, ε12); either may be NULL. */
WRDEF double wr_shell_stvk_density(const double C[9], const double eps[3], double *dW, double *d2W);
/* Koiter's isotropic thin-shell energy at one point, per unit parameter area: √det A · [Q_Ym(ε) +
 * Q_Db(κ)], ε = ½ (a − A), κ = b − B, Q_k(s) = ½ k [(1 − ν) tr((A⁻¹s)²) + ν (tr A⁻¹s)²] (the StVK
 * membrane and the plate bending density written covariantly). p (15) = (x_v, x_w, x_vv, x_vw, x_ww)
 * of the deformed surface; g (15) and H (225, row-major) may be NULL. The Hessian is exact (not
 * projected). Returns NaN when x_v × x_w vanishes (no normal). */
WRDEF double wr_shell_koiter_point(const wr_shell_koiter_rest *rest, const double p[15], double *g, double *H);

#ifdef __cplusplus
}
#endif
#endif /* WRINKLE_SHELL_H */

/* ============================================================================================ */
#ifdef WRINKLE_IMPLEMENTATION
#ifndef WRINKLE_SHELL_IMPLEMENTATION_DONE
#define WRINKLE_SHELL_IMPLEMENTATION_DONE

#include <math.h>
#include <string.h>

#ifdef __cplusplus
extern "C" {
#endif

WRDEF double wr_shell_stvk_density(const double C[9], const double eps[3], double *dW, double *d2W) {
    /* γ = T ε with T = diag(1, 1, 2): dW = T C γ, d2W = T C T. */
    double gam[3], Cg[3];
    int i, j;
    gam[0] = eps[0];
    gam[1] = eps[1];
    gam[2] = 2.0 * eps[2];
    for (i = 0; i < 3; ++i) Cg[i] = C[3 * i] * gam[0] + C[3 * i + 1] * gam[1] + C[3 * i + 2] * gam[2];
    if (dW) {
        dW[0] = Cg[0];
        dW[1] = Cg[1];
        dW[2] = 2.0 * Cg[2];
    }
    if (d2W)
        for (i = 0; i < 3; ++i)
            for (j = 0; j < 3; ++j) d2W[3 * i + j] = C[3 * i + j] * (i == 2 ? 2.0 : 1.0) * (j == 2 ? 2.0 : 1.0);
    return 0.5 * (gam[0] * Cg[0] + gam[1] * Cg[1] + gam[2] * Cg[2]);
}

/* ---- Koiter energy at one point of a smooth surface (the Loop element's quadrature point) ------ */

/* Q(s) = ½ k [(1 − ν) tr((A⁻¹s)²) + ν (tr A⁻¹s)²] as ½ sᵀ M s over s = (s11, s12, s22), s12 counted
 * once: M from the polarisation of Q on the unit tensors (exact for a quadratic form). */
static double wr__koiter_q(const double Ai[3], double k, double nu, const double s[3]) {
    double m11 = Ai[0] * s[0] + Ai[1] * s[1], m12 = Ai[0] * s[1] + Ai[1] * s[2]; /* (A⁻¹ s) row 1 */
    double m21 = Ai[1] * s[0] + Ai[2] * s[1], m22 = Ai[1] * s[1] + Ai[2] * s[2]; /* row 2 */
    double tr = m11 + m22, tr2 = m11 * m11 + 2.0 * m12 * m21 + m22 * m22;
    return 0.5 * k * ((1.0 - nu) * tr2 + nu * tr * tr);
}

static void wr__koiter_matrix(const double Ai[3], double k, double nu, double M[9]) {
    double e[3][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}}, q[3];
    int i, j, c;
    for (i = 0; i < 3; ++i) q[i] = wr__koiter_q(Ai, k, nu, e[i]);
    for (i = 0; i < 3; ++i)
        for (j = 0; j < 3; ++j) {
            double sij[3];
            if (i == j) {
                M[3 * i + j] = 2.0 * q[i];
                continue;
            }
            for (c = 0; c < 3; ++c) sij[c] = e[i][c] + e[j][c];
            M[3 * i + j] = wr__koiter_q(Ai, k, nu, sij) - q[i] - q[j];
        }
}

/* [v]× as a row-major 3×3 */
static void wr__koiter_cross(const double v[3], double X[9]) {
    X[0] = 0.0;
    X[1] = -v[2];
    X[2] = v[1];
    X[3] = v[2];
    X[4] = 0.0;
    X[5] = -v[0];
    X[6] = -v[1];
    X[7] = v[0];
    X[8] = 0.0;
}

/* H[ra.., cb..] += s · (X Y) for 3×3 blocks at DOF offsets ra, cb of the 15 × 15 Hessian */
static void wr__koiter_block(double *H, int ra, int cb, double s, const double X[9]) {
    int i, j;
    for (i = 0; i < 3; ++i)
        for (j = 0; j < 3; ++j) H[(ra + i) * 15 + cb + j] += s * X[3 * i + j];
}

static void wr__koiter_mul(const double X[9], const double Y[9], double Z[9], int transpose_x) {
    int i, j, k;
    for (i = 0; i < 3; ++i)
        for (j = 0; j < 3; ++j) {
            double t = 0.0;
            for (k = 0; k < 3; ++k) t += (transpose_x ? X[3 * k + i] : X[3 * i + k]) * Y[3 * k + j];
            Z[3 * i + j] = t;
        }
}

WRDEF double wr_shell_koiter_point(const wr_shell_koiter_rest *rest, const double p[15], double *g, double *H) {
    const double *xv = p, *xw = p + 3, *xab[3];
    double detA = rest->A[0] * rest->A[2] - rest->A[1] * rest->A[1], sq = sqrt(detA), Ai[3], a[3], r, n[3], eps[3],
           kap[3], Mm[9], Mb[9], Sm[3], Sb[3], Jm[3][15], Jb[3][15], E;
    int i, j, c, k;
    xab[0] = p + 6;
    xab[1] = p + 9;
    xab[2] = p + 12;
    Ai[0] = rest->A[2] / detA;
    Ai[1] = -rest->A[1] / detA;
    Ai[2] = rest->A[0] / detA;
    a[0] = xv[1] * xw[2] - xv[2] * xw[1];
    a[1] = xv[2] * xw[0] - xv[0] * xw[2];
    a[2] = xv[0] * xw[1] - xv[1] * xw[0];
    r = sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
    if (!(r > 0.0)) return NAN;
    for (c = 0; c < 3; ++c) n[c] = a[c] / r;
    eps[0] = 0.5 * (xv[0] * xv[0] + xv[1] * xv[1] + xv[2] * xv[2] - rest->A[0]);
    eps[1] = 0.5 * (xv[0] * xw[0] + xv[1] * xw[1] + xv[2] * xw[2] - rest->A[1]);
    eps[2] = 0.5 * (xw[0] * xw[0] + xw[1] * xw[1] + xw[2] * xw[2] - rest->A[2]);
    for (k = 0; k < 3; ++k) kap[k] = xab[k][0] * n[0] + xab[k][1] * n[1] + xab[k][2] * n[2] - rest->B[k];
    wr__koiter_matrix(Ai, rest->Ym, rest->nu, Mm);
    wr__koiter_matrix(Ai, rest->Db, rest->nu, Mb);
    for (i = 0; i < 3; ++i) {
        Sm[i] = Mm[3 * i] * eps[0] + Mm[3 * i + 1] * eps[1] + Mm[3 * i + 2] * eps[2];
        Sb[i] = Mb[3 * i] * kap[0] + Mb[3 * i + 1] * kap[1] + Mb[3 * i + 2] * kap[2];
    }
    E = sq * 0.5 * (eps[0] * Sm[0] + eps[1] * Sm[1] + eps[2] * Sm[2] + kap[0] * Sb[0] + kap[1] * Sb[1] + kap[2] * Sb[2]);
    if (!g && !H) return E;
    /* Jacobians of ε and κ with respect to p. ε: ∂ε11/∂x_v = x_v, ∂ε12 = ½ (x_w, x_v), ∂ε22/∂x_w = x_w.
     * κ_k = x_k · n(a), a = x_v × x_w: ∂/∂x_k = n; through n, with q = (I − n nᵀ) x_k / r:
     * ∂/∂x_v = x_w × q, ∂/∂x_w = q × x_v. */
    memset(Jm, 0, sizeof Jm);
    memset(Jb, 0, sizeof Jb);
    for (c = 0; c < 3; ++c) {
        Jm[0][c] = xv[c];
        Jm[1][c] = 0.5 * xw[c];
        Jm[1][3 + c] = 0.5 * xv[c];
        Jm[2][3 + c] = xw[c];
    }
    for (k = 0; k < 3; ++k) {
        double cn = xab[k][0] * n[0] + xab[k][1] * n[1] + xab[k][2] * n[2], q[3];
        for (c = 0; c < 3; ++c) q[c] = (xab[k][c] - cn * n[c]) / r;
        Jb[k][0] = xw[1] * q[2] - xw[2] * q[1];
        Jb[k][1] = xw[2] * q[0] - xw[0] * q[2];
        Jb[k][2] = xw[0] * q[1] - xw[1] * q[0];
        Jb[k][3] = q[1] * xv[2] - q[2] * xv[1];
        Jb[k][4] = q[2] * xv[0] - q[0] * xv[2];
        Jb[k][5] = q[0] * xv[1] - q[1] * xv[0];
        for (c = 0; c < 3; ++c) Jb[k][6 + 3 * k + c] = n[c];
    }
    if (g)
        for (i = 0; i < 15; ++i)
            g[i] = sq * (Sm[0] * Jm[0][i] + Sm[1] * Jm[1][i] + Sm[2] * Jm[2][i] + Sb[0] * Jb[0][i] + Sb[1] * Jb[1][i] +
                         Sb[2] * Jb[2][i]);
    if (!H) return E;
    /* Gauss–Newton part Jᵀ M J, then the stresses times the second derivatives of ε and κ */
    for (i = 0; i < 15; ++i)
        for (j = 0; j < 15; ++j) {
            double t = 0.0;
            int u, w;
            for (u = 0; u < 3; ++u)
                for (w = 0; w < 3; ++w) t += Jm[u][i] * Mm[3 * u + w] * Jm[w][j] + Jb[u][i] * Mb[3 * u + w] * Jb[w][j];
            H[15 * i + j] = t;
        }
    for (c = 0; c < 3; ++c) { /* ε: ∂²ε11/∂x_v² = I, ∂²ε12/∂x_v∂x_w = ½ I, ∂²ε22/∂x_w² = I */
        H[15 * c + c] += Sm[0];
        H[15 * (3 + c) + 3 + c] += Sm[2];
        H[15 * c + 3 + c] += 0.5 * Sm[1];
        H[15 * (3 + c) + c] += 0.5 * Sm[1];
    }
    {
        /* κ: Σ_k S_k ∇²κ_k. With c = Σ_k S_k x_k (one vector, κ is linear in S): ∇²_a (c·n) =
         * [−(c nᵀ + n cᵀ) − (c·n) I + 3 (c·n) n nᵀ] / r²; J_v = ∂a/∂x_v = −[x_w]×, J_w = [x_v]×; the
         * bilinear a adds −[∇_a]× to the (x_v, x_w) block; the (x_k, x_v/x_w) blocks are S_k ∂n. */
        double cv[3], cn, ga[3], Fa[9], P[9], Xw[9], Xv[9], T[9], U[9], G[9];
        for (c = 0; c < 3; ++c) cv[c] = Sb[0] * xab[0][c] + Sb[1] * xab[1][c] + Sb[2] * xab[2][c];
        cn = cv[0] * n[0] + cv[1] * n[1] + cv[2] * n[2];
        for (i = 0; i < 3; ++i) {
            ga[i] = (cv[i] - cn * n[i]) / r;
            for (j = 0; j < 3; ++j) {
                Fa[3 * i + j] = (-(cv[i] * n[j] + n[i] * cv[j]) - (i == j ? cn : 0.0) + 3.0 * cn * n[i] * n[j]) / (r * r);
                P[3 * i + j] = ((i == j ? 1.0 : 0.0) - n[i] * n[j]) / r;
            }
        }
        wr__koiter_cross(xw, Xw);
        wr__koiter_cross(xv, Xv);
        for (i = 0; i < 9; ++i) Xw[i] = -Xw[i]; /* J_v */
        wr__koiter_mul(Fa, Xw, T, 0);             /* Fa J_v */
        wr__koiter_mul(Xw, T, U, 1);              /* J_vᵀ Fa J_v */
        wr__koiter_block(H, 0, 0, 1.0, U);
        wr__koiter_mul(Fa, Xv, T, 0); /* Fa J_w */
        wr__koiter_mul(Xv, T, U, 1);  /* J_wᵀ Fa J_w */
        wr__koiter_block(H, 3, 3, 1.0, U);
        wr__koiter_mul(Xw, T, U, 1); /* J_vᵀ Fa J_w */
        wr__koiter_cross(ga, G);
        for (i = 0; i < 3; ++i)
            for (j = 0; j < 3; ++j) {
                H[15 * i + 3 + j] += U[3 * i + j] - G[3 * i + j];
                H[15 * (3 + j) + i] += U[3 * i + j] - G[3 * i + j];
            }
        /* (x_k, x_v) = S_k P J_v and (x_k, x_w) = S_k P J_w, with their transposes */
        wr__koiter_mul(P, Xw, T, 0);
        wr__koiter_mul(P, Xv, U, 0);
        for (k = 0; k < 3; ++k)
            for (i = 0; i < 3; ++i)
                for (j = 0; j < 3; ++j) {
                    int rk = 6 + 3 * k + i;
                    H[15 * rk + j] += Sb[k] * T[3 * i + j];
                    H[15 * j + rk] += Sb[k] * T[3 * i + j];
                    H[15 * rk + 3 + j] += Sb[k] * U[3 * i + j];
                    H[15 * (3 + j) + rk] += Sb[k] * U[3 * i + j];
                }
    }
    for (i = 0; i < 225; ++i) H[i] *= sq;
    return E;
}

/* Rows of the rest-frame gradient operator: F = Σ_v x_v ⊗ G[v], G[1] = dinv row 0, G[2] = row 1. */
static void wr__shell_G(const double *dinv, double G[6]) {
    G[2] = dinv[0];
    G[3] = dinv[1];
    G[4] = dinv[2];
    G[5] = dinv[3];
    G[0] = -G[2] - G[4];
    G[1] = -G[3] - G[5];
}

static void wr__shell_F(const double *dinv, const double x[9], double F1[3], double F2[3]) {
    double G[6];
    int i;
    wr__shell_G(dinv, G);
    for (i = 0; i < 3; ++i) {
        F1[i] = G[0] * x[i] + G[2] * x[3 + i] + G[4] * x[6 + i];
        F2[i] = G[1] * x[i] + G[3] * x[3 + i] + G[5] * x[6 + i];
    }
}

static void wr__shell_eps(const double F1[3], const double F2[3], double eps[3]) {
    eps[0] = 0.5 * (F1[0] * F1[0] + F1[1] * F1[1] + F1[2] * F1[2] - 1.0);
    eps[1] = 0.5 * (F2[0] * F2[0] + F2[1] * F2[1] + F2[2] * F2[2] - 1.0);
    eps[2] = 0.5 * (F1[0] * F2[0] + F1[1] * F2[1] + F1[2] * F2[2]);
}

/* Baraff & Witkin 1998 Sec. 4.2–4.3 on the material-frame columns F1 = ∂x/∂u (warp), F2 = ∂x/∂v
 * (weft): stretch conditions |F1| − 1, |F2| − 1 and the shear condition F1·F2, each squared with its
 * stiffness and integrated over the rest area (ON BARAFF–WITKIN). */
static double wr__shell_bw_element(const double k[3], double A, const double G[6], const double F1[3],
                                   const double F2[3], double *g, double *H) {
    double l1 = sqrt(F1[0] * F1[0] + F1[1] * F1[1] + F1[2] * F1[2]);
    double l2 = sqrt(F2[0] * F2[0] + F2[1] * F2[1] + F2[2] * F2[2]);
    double c = F1[0] * F2[0] + F1[1] * F2[1] + F1[2] * F2[2], dW1[3], dW2[3], W;
    double s1 = l1 > 0.0 ? (l1 - 1.0) / l1 : 0.0, s2 = l2 > 0.0 ? (l2 - 1.0) / l2 : 0.0;
    int v, w, i, j;
    W = 0.5 * k[0] * (l1 - 1.0) * (l1 - 1.0) + 0.5 * k[1] * (l2 - 1.0) * (l2 - 1.0) + 0.5 * k[2] * c * c;
    if (!g && !H) return A * W;
    /* ∂W/∂F1 = k_u (|F1| − 1) F1/|F1| + k_s (F1·F2) F2, and symmetrically for F2 */
    for (i = 0; i < 3; ++i) {
        dW1[i] = k[0] * s1 * F1[i] + k[2] * c * F2[i];
        dW2[i] = k[1] * s2 * F2[i] + k[2] * c * F1[i];
    }
    if (g)
        for (v = 0; v < 3; ++v)
            for (i = 0; i < 3; ++i) g[3 * v + i] = A * (G[2 * v] * dW1[i] + G[2 * v + 1] * dW2[i]);
    if (H) {
        /* blocks of ∂²W/∂Fa∂Fb: 11 = k_u [I − (I − f̂f̂ᵀ)/|F1|] + k_s F2F2ᵀ, 22 likewise,
         * 12 = k_s (F2 F1ᵀ + (F1·F2) I); at |F| = 0 the stretch term's curvature is taken as 0 */
        double W11[9], W22[9], W12[9];
        for (i = 0; i < 3; ++i)
            for (j = 0; j < 3; ++j) {
                double d = i == j ? 1.0 : 0.0;
                W11[3 * i + j] = (l1 > 0.0 ? k[0] * (d - (d - F1[i] * F1[j] / (l1 * l1)) / l1) : 0.0) + k[2] * F2[i] * F2[j];
                W22[3 * i + j] = (l2 > 0.0 ? k[1] * (d - (d - F2[i] * F2[j] / (l2 * l2)) / l2) : 0.0) + k[2] * F1[i] * F1[j];
                W12[3 * i + j] = k[2] * (F2[i] * F1[j] + c * d);
            }
        for (v = 0; v < 3; ++v)
            for (w = 0; w < 3; ++w)
                for (i = 0; i < 3; ++i)
                    for (j = 0; j < 3; ++j)
                        H[(3 * v + i) * 9 + 3 * w + j] =
                            A * (G[2 * v] * G[2 * w] * W11[3 * i + j] + G[2 * v + 1] * G[2 * w + 1] * W22[3 * i + j] +
                                 G[2 * v] * G[2 * w + 1] * W12[3 * i + j] + G[2 * v + 1] * G[2 * w] * W12[3 * j + i]);
    }
    return A * W;
}

WRDEF double wr_shell_membrane_element(const wr_shell *s, int32_t f, const double x[9], double *g, double *H) {
    const double *dinv = s->dinv + 4 * f;
    double A = s->area[f], G[6], F1[3], F2[3], eps[3], dW[3], d2W[9], W, D[3][3][3];
    int c, d, v, w, i, j;
    if (s->membrane == WR_MEMBRANE_NONE) {
        if (g) memset(g, 0, sizeof(double) * 9);
        if (H) memset(H, 0, sizeof(double) * 81);
        return 0.0;
    }
    wr__shell_G(dinv, G);
    wr__shell_F(dinv, x, F1, F2);
    if (s->membrane == WR_MEMBRANE_BARAFF_WITKIN) return wr__shell_bw_element(s->bw_k, A, G, F1, F2, g, H);
    wr__shell_eps(F1, F2, eps);
    if (s->membrane == WR_MEMBRANE_TFT)
        W = wr_tft_density(eps, s->young, s->poisson, s->thickness, dW, d2W);
    else
        W = wr_shell_stvk_density(s->C_mem, eps, dW, d2W);
    if (!g && !H) return A * W;
    /* D[c][v] = ∂ε_c/∂x_v (3-vector): ε11 → G_v1 F1, ε22 → G_v2 F2, ε12 → ½(G_v1 F2 + G_v2 F1). */
    for (v = 0; v < 3; ++v)
        for (i = 0; i < 3; ++i) {
            D[0][v][i] = G[2 * v] * F1[i];
            D[1][v][i] = G[2 * v + 1] * F2[i];
            D[2][v][i] = 0.5 * (G[2 * v] * F2[i] + G[2 * v + 1] * F1[i]);
        }
    if (g)
        for (v = 0; v < 3; ++v)
            for (i = 0; i < 3; ++i) g[3 * v + i] = A * (dW[0] * D[0][v][i] + dW[1] * D[1][v][i] + dW[2] * D[2][v][i]);
    if (H) {
        double P[3][3][9]; /* d2W_cd · D[c][v][i], the left-to-right products of the sum below */
        for (v = 0; v < 3; ++v)
            for (i = 0; i < 3; ++i)
                for (c = 0; c < 3; ++c)
                    for (d = 0; d < 3; ++d) P[v][i][3 * c + d] = d2W[3 * c + d] * D[c][v][i];
        for (v = 0; v < 3; ++v)
            for (w = 0; w < 3; ++w) {
                /* geometric stiffness: Σ_c dW_c ∂²ε_c/∂x_v∂x_w, a multiple of the 3×3 identity */
                double geo = dW[0] * G[2 * v] * G[2 * w] + dW[1] * G[2 * v + 1] * G[2 * w + 1] +
                             dW[2] * 0.5 * (G[2 * v] * G[2 * w + 1] + G[2 * v + 1] * G[2 * w]);
                for (i = 0; i < 3; ++i)
                    for (j = 0; j < 3; ++j) {
                        double hv = i == j ? geo : 0.0;
                        for (c = 0; c < 3; ++c)
                            for (d = 0; d < 3; ++d) hv += P[v][i][3 * c + d] * D[d][w][j];
                        H[(3 * v + i) * 9 + 3 * w + j] = A * hv;
                    }
            }
    }
    return A * W;
}

WRDEF void wr_shell_face_strain(const wr_shell *s, int32_t f, const double *x, double eps[3]) {
    double x9[9], F1[3], F2[3];
    int k, i;
    for (k = 0; k < 3; ++k)
        for (i = 0; i < 3; ++i) x9[3 * k + i] = x[3 * s->faces[3 * f + k] + i];
    wr__shell_F(s->dinv + 4 * f, x9, F1, F2);
    wr__shell_eps(F1, F2, eps);
}

/* ---- mid-edge bending ---------------------------------------------------------------------- */
/* 3×18 Jacobians are row-major J[r*18 + col]; local vertex v occupies columns 3v..3v+2. */
#define WR__ME_N 18

static void wr__skew_add(double *J, int v, const double u[3], double sgn) {
    /* J[:, 3v..3v+2] += sgn·[u]×, [u]× y = u × y */
    J[0 * 18 + 3 * v + 1] += -sgn * u[2];
    J[0 * 18 + 3 * v + 2] += sgn * u[1];
    J[1 * 18 + 3 * v + 0] += sgn * u[2];
    J[1 * 18 + 3 * v + 2] += -sgn * u[0];
    J[2 * 18 + 3 * v + 0] += -sgn * u[1];
    J[2 * 18 + 3 * v + 1] += sgn * u[0];
}

/* N = (x_b − x_a) × (x_c − x_a) and its Jacobian: dN = −[u2]× du1 + [u1]× du2. */
static void wr__cross_jac(const double *x, int a, int b, int c, double N[3], double J[54]) {
    double u1[3], u2[3];
    int i;
    for (i = 0; i < 3; ++i) {
        u1[i] = x[3 * b + i] - x[3 * a + i];
        u2[i] = x[3 * c + i] - x[3 * a + i];
    }
    N[0] = u1[1] * u2[2] - u1[2] * u2[1];
    N[1] = u1[2] * u2[0] - u1[0] * u2[2];
    N[2] = u1[0] * u2[1] - u1[1] * u2[0];
    memset(J, 0, sizeof(double) * 54);
    wr__skew_add(J, b, u2, -1.0);
    wr__skew_add(J, c, u1, 1.0);
    wr__skew_add(J, a, u2, 1.0);
    wr__skew_add(J, a, u1, -1.0);
}

/* H += Hessian of z·N for N of wr__cross_jac: blocks α_v β_w Z + β_v α_w Zᵀ with Z_de = ε_dec z_c,
 * u1 = Σ α_v x_v, u2 = Σ β_v x_v. */
static void wr__cross_hess_add(int a, int b, int c, const double z[3], double *H) {
    double Z[9];
    int vs[3], v, w, i, j;
    double al[3], be[3];
    Z[0] = 0.0;
    Z[1] = z[2];
    Z[2] = -z[1];
    Z[3] = -z[2];
    Z[4] = 0.0;
    Z[5] = z[0];
    Z[6] = z[1];
    Z[7] = -z[0];
    Z[8] = 0.0;
    vs[0] = a;
    vs[1] = b;
    vs[2] = c;
    al[0] = -1.0;
    al[1] = 1.0;
    al[2] = 0.0;
    be[0] = -1.0;
    be[1] = 0.0;
    be[2] = 1.0;
    for (v = 0; v < 3; ++v)
        for (w = 0; w < 3; ++w) {
            double p = al[v] * be[w], q = be[v] * al[w];
            if (p == 0.0 && q == 0.0) continue;
            for (i = 0; i < 3; ++i)
                for (j = 0; j < 3; ++j) H[(3 * vs[v] + i) * 18 + 3 * vs[w] + j] += p * Z[3 * i + j] + q * Z[3 * j + i];
        }
}

/* u = y/|y|, P = (I − uuᵀ)/|y| (Jacobian of the normalisation). Returns |y|. */
static double wr__normalize(const double y[3], double u[3], double P[9]) {
    double r = sqrt(y[0] * y[0] + y[1] * y[1] + y[2] * y[2]);
    int i, j;
    if (!(r > 0.0)) return 0.0;
    for (i = 0; i < 3; ++i) u[i] = y[i] / r;
    if (P)
        for (i = 0; i < 3; ++i)
            for (j = 0; j < 3; ++j) P[3 * i + j] = ((i == j ? 1.0 : 0.0) - u[i] * u[j]) / r;
    return r;
}

/* Σ_c w_c ∂²u_c/∂y∂y for u = y/|y|: [−(w uᵀ + u wᵀ) − (w·u) I + 3 (w·u) u uᵀ] / |y|². */
static void wr__normalize_hess(const double u[3], double r, const double w[3], double N2[9]) {
    double wu = w[0] * u[0] + w[1] * u[1] + w[2] * u[2];
    int i, j;
    for (i = 0; i < 3; ++i)
        for (j = 0; j < 3; ++j)
            N2[3 * i + j] = (-(w[i] * u[j] + u[i] * w[j]) - (i == j ? wu : 0.0) + 3.0 * wu * u[i] * u[j]) / (r * r);
}

static void wr__m3_mul_J(const double *M, const double *J, double *out) {
    int i, k, c;
    for (i = 0; i < 3; ++i)
        for (c = 0; c < 18; ++c) {
            double t = 0.0;
            for (k = 0; k < 3; ++k) t += M[3 * i + k] * J[k * 18 + c];
            out[i * 18 + c] = t;
        }
}

static void wr__m3_mulv(const double *M, const double *v, double *out) {
    int i;
    for (i = 0; i < 3; ++i) out[i] = M[3 * i] * v[0] + M[3 * i + 1] * v[1] + M[3 * i + 2] * v[2];
}

/* H += s · Jaᵀ A Jb (A 3×3, NULL = identity). */
static void wr__add_JtAJ(double *H, const double *Ja, const double *A, const double *Jb, double s) {
    double AJ[54];
    int r, c, k;
    if (A)
        wr__m3_mul_J(A, Jb, AJ);
    else
        memcpy(AJ, Jb, sizeof AJ);
    for (r = 0; r < 18; ++r) {
        double a0 = Ja[r], a1 = Ja[18 + r], a2 = Ja[36 + r];
        if (a0 == 0.0 && a1 == 0.0 && a2 == 0.0) continue;
        for (c = 0; c < 18; ++c) H[r * 18 + c] += s * (a0 * AJ[c] + a1 * AJ[18 + c] + a2 * AJ[36 + c]);
    }
    (void)k;
}

WRDEF wr_status wr_shell_midedge_element(const double x[18], int32_t mask, const double Q[9], const double *bbar,
                                         double *E, double *g, double *H, double *bout) {
    double Nf[3], JNf[54], nf[3], Pf[9], Jnf[54], rf;
    double Ng[3][3], JNg[3][54], ng[3][3], Png[3][9], rg[3];
    double sv[3][3], m[3][3], Ps[3][9], rs[3], Jm[3][54], Js[3][54];
    double e1[3], e2[3], Je1[54], Je2[54], b[3], db[3], gb[3];
    double dm[3][3], Jdm[3][54], Jb[3][54];
    int k, i, c, need = (g || H);
    /* comp → (edge vector, mid-edge normals plus/minus): b11 = 2e1·(n̂1−n̂0), b22 = 2e2·(n̂2−n̂0),
     * b12 = 2e2·(n̂1−n̂0) (TFW App. A). */
    static const int cplus[3] = {1, 2, 1};

    rf = 0.0;
    wr__cross_jac(x, 0, 1, 2, Nf, JNf);
    rf = wr__normalize(Nf, nf, Pf);
    if (!(rf > 0.0)) return WR_ERR_GEOMETRY;
    wr__m3_mul_J(Pf, JNf, Jnf);
    for (k = 0; k < 3; ++k) {
        if (mask & (1 << k)) {
            int a = (k + 1) % 3, bb = (k + 2) % 3, q = 3 + k;
            double Jng[54];
            /* the neighbour traverses the shared edge b → a; its third vertex is q */
            wr__cross_jac(x, bb, a, q, Ng[k], JNg[k]);
            rg[k] = wr__normalize(Ng[k], ng[k], Png[k]);
            if (!(rg[k] > 0.0)) return WR_ERR_GEOMETRY;
            for (i = 0; i < 3; ++i) sv[k][i] = nf[i] + ng[k][i];
            rs[k] = wr__normalize(sv[k], m[k], Ps[k]);
            if (!(rs[k] > 1e-12)) return WR_ERR_GEOMETRY; /* faces folded onto each other */
            if (need) {
                wr__m3_mul_J(Png[k], JNg[k], Jng);
                for (i = 0; i < 54; ++i) Js[k][i] = Jnf[i] + Jng[i];
                wr__m3_mul_J(Ps[k], Js[k], Jm[k]);
            }
        } else {
            for (i = 0; i < 3; ++i) m[k][i] = nf[i];
            if (need) memcpy(Jm[k], Jnf, sizeof Jnf);
        }
    }
    for (i = 0; i < 3; ++i) {
        e1[i] = x[3 + i] - x[i];
        e2[i] = x[6 + i] - x[i];
    }
    for (c = 0; c < 3; ++c) {
        const double *e = c == 0 ? e1 : e2;
        for (i = 0; i < 3; ++i) dm[c][i] = m[cplus[c]][i] - m[0][i];
        b[c] = 2.0 * (e[0] * dm[c][0] + e[1] * dm[c][1] + e[2] * dm[c][2]);
    }
    if (bout)
        for (c = 0; c < 3; ++c) bout[c] = b[c];
    if (!Q) return WR_OK;
    for (c = 0; c < 3; ++c) db[c] = b[c] - (bbar ? bbar[c] : 0.0);
    wr__m3_mulv(Q, db, gb);
    if (E) *E = 0.5 * (db[0] * gb[0] + db[1] * gb[1] + db[2] * gb[2]);
    if (!need) return WR_OK;

    memset(Je1, 0, sizeof Je1);
    memset(Je2, 0, sizeof Je2);
    for (i = 0; i < 3; ++i) {
        Je1[i * 18 + i] = -1.0;
        Je1[i * 18 + 3 + i] = 1.0;
        Je2[i * 18 + i] = -1.0;
        Je2[i * 18 + 6 + i] = 1.0;
    }
    for (c = 0; c < 3; ++c) {
        const double *e = c == 0 ? e1 : e2;
        const double *Je = c == 0 ? Je1 : Je2;
        int col;
        for (i = 0; i < 54; ++i) Jdm[c][i] = Jm[cplus[c]][i] - Jm[0][i];
        for (col = 0; col < 18; ++col) {
            double t = 0.0;
            for (i = 0; i < 3; ++i) t += dm[c][i] * Je[i * 18 + col] + e[i] * Jdm[c][i * 18 + col];
            Jb[c][col] = 2.0 * t;
        }
    }
    if (g)
        for (i = 0; i < 18; ++i) g[i] = gb[0] * Jb[0][i] + gb[1] * Jb[1][i] + gb[2] * Jb[2][i];
    if (H) {
        double w[3][3], vf[3], vg[3][3], N2[9], z[3];
        int r, col;
        memset(H, 0, sizeof(double) * 324);
        /* Gauss–Newton part Jbᵀ Q Jb (the products Jb_pr Q_pq formed once per row: the same
         * left-to-right products; a row whose Jb column is zero is left at +0, which is what the
         * sum 0 + (0·Q)·Jb gives for finite Q, Jb) */
        for (r = 0; r < 18; ++r) {
            double JQ[9];
            int p, q;
            if (Jb[0][r] == 0.0 && Jb[1][r] == 0.0 && Jb[2][r] == 0.0) continue;
            for (p = 0; p < 3; ++p)
                for (q = 0; q < 3; ++q) JQ[3 * p + q] = Jb[p][r] * Q[3 * p + q];
            for (col = 0; col < 18; ++col) {
                double t = 0.0;
                for (p = 0; p < 3; ++p)
                    for (q = 0; q < 3; ++q) t += JQ[3 * p + q] * Jb[q][col];
                H[r * 18 + col] = t;
            }
        }
        /* Σ_c gb_c ∇²b_c: the bilinear cross terms 2(Jeᵀ Jdm + Jdmᵀ Je) … */
        for (c = 0; c < 3; ++c) {
            const double *Je = c == 0 ? Je1 : Je2;
            wr__add_JtAJ(H, Je, NULL, Jdm[c], 2.0 * gb[c]);
            wr__add_JtAJ(H, Jdm[c], NULL, Je, 2.0 * gb[c]);
        }
        /* … and the mid-edge normals' second derivatives contracted with w_k = ∂E/∂n̂_k. */
        for (i = 0; i < 3; ++i) {
            w[1][i] = 2.0 * (gb[0] * e1[i] + gb[2] * e2[i]);
            w[2][i] = 2.0 * gb[1] * e2[i];
            w[0][i] = -w[1][i] - w[2][i];
        }
        vf[0] = vf[1] = vf[2] = 0.0;
        for (k = 0; k < 3; ++k) {
            if (mask & (1 << k)) {
                double v[3];
                wr__normalize_hess(m[k], rs[k], w[k], N2);
                wr__add_JtAJ(H, Js[k], N2, Js[k], 1.0);
                wr__m3_mulv(Ps[k], w[k], v);
                for (i = 0; i < 3; ++i) {
                    vf[i] += v[i];
                    vg[k][i] = v[i];
                }
            } else {
                for (i = 0; i < 3; ++i) vf[i] += w[k][i];
            }
        }
        wr__normalize_hess(nf, rf, vf, N2);
        wr__add_JtAJ(H, JNf, N2, JNf, 1.0);
        wr__m3_mulv(Pf, vf, z);
        wr__cross_hess_add(0, 1, 2, z, H);
        for (k = 0; k < 3; ++k) {
            if (!(mask & (1 << k))) continue;
            wr__normalize_hess(ng[k], rg[k], vg[k], N2);
            wr__add_JtAJ(H, JNg[k], N2, JNg[k], 1.0);
            wr__m3_mulv(Png[k], vg[k], z);
            wr__cross_hess_add((k + 2) % 3, (k + 1) % 3, 3 + k, z, H);
        }
        /* symmetrise round-off */
        for (r = 0; r < 18; ++r)
            for (col = r + 1; col < 18; ++col) {
                double t = 0.5 * (H[r * 18 + col] + H[col * 18 + r]);
                H[r * 18 + col] = H[col * 18 + r] = t;
            }
    }
    return WR_OK;
}

/* ---- dihedral (fold-safe) bending ------------------------------------------------------------ */
/* Hinge x0 x1 (slots s0 s1), faces A = (x0, x1, x2) and B = (x1, x0, x3) in the 18-dof layout.
 * θ = atan2(Y, X) with X = N_A·N_B and Y = (N_A × N_B)·ê = P/L, P = N_A·(N_B × e), e = x1 − x0,
 * L = |e| (N_A, N_B the unnormalised normals): X = |N_A||N_B| cos θ and Y = |N_A||N_B| sin θ, so θ is
 * defined (and smooth in x) whenever both faces have area, including at and near θ = ±π where the
 * mid-edge average normal vanishes. Derivatives by the chain rule through the bilinear pieces:
 *   ∇X = J_Aᵀ N_B + J_Bᵀ N_A,   ∇P = J_Aᵀ (N_B × e) + J_Bᵀ (e × N_A) + J_eᵀ (N_A × N_B),
 *   ∇²P = S + Sᵀ + N_A'' : (N_B × e) + N_B'' : (e × N_A),  S = J_Aᵀ(−[e]×)J_B + J_Aᵀ[N_B]×J_e − J_Bᵀ[N_A]×J_e,
 *   ∇θ = (X∇Y − Y∇X)/(X² + Y²) and its derivative. g and H are overwritten. Returns 0, or −1 when a
 * face or the edge is degenerate. */
static int wr__hinge18(const double *x, int s0, int s1, int s2, int s3, double *th, double *g, double *H) {
    double NA[3], NB[3], JA[54], JB[54], Je[54], e[3], L, X, P, Y, r2, u[3], w[3], t[3], eh[3];
    double gX[18], gP[18], gL[18], gY[18], Z[9];
    int i, j;
    for (i = 0; i < 3; ++i) e[i] = x[3 * s1 + i] - x[3 * s0 + i];
    L = sqrt(e[0] * e[0] + e[1] * e[1] + e[2] * e[2]);
    wr__cross_jac(x, s0, s1, s2, NA, JA);
    wr__cross_jac(x, s1, s0, s3, NB, JB);
    X = NA[0] * NB[0] + NA[1] * NB[1] + NA[2] * NB[2];
    u[0] = NB[1] * e[2] - NB[2] * e[1];
    u[1] = NB[2] * e[0] - NB[0] * e[2];
    u[2] = NB[0] * e[1] - NB[1] * e[0];
    P = NA[0] * u[0] + NA[1] * u[1] + NA[2] * u[2];
    if (!(L > 0.0)) return -1;
    Y = P / L;
    r2 = X * X + Y * Y;
    if (!(r2 > 0.0)) return -1;
    *th = atan2(Y, X);
    if (!g && !H) return 0;
    w[0] = e[1] * NA[2] - e[2] * NA[1];
    w[1] = e[2] * NA[0] - e[0] * NA[2];
    w[2] = e[0] * NA[1] - e[1] * NA[0];
    t[0] = NA[1] * NB[2] - NA[2] * NB[1];
    t[1] = NA[2] * NB[0] - NA[0] * NB[2];
    t[2] = NA[0] * NB[1] - NA[1] * NB[0];
    for (i = 0; i < 3; ++i) eh[i] = e[i] / L;
    memset(Je, 0, sizeof Je);
    for (i = 0; i < 3; ++i) {
        Je[i * 18 + 3 * s0 + i] = -1.0;
        Je[i * 18 + 3 * s1 + i] = 1.0;
    }
    for (j = 0; j < 18; ++j) {
        double a = 0.0, p = 0.0, l = 0.0;
        for (i = 0; i < 3; ++i) {
            a += JA[i * 18 + j] * NB[i] + JB[i * 18 + j] * NA[i];
            p += JA[i * 18 + j] * u[i] + JB[i * 18 + j] * w[i] + Je[i * 18 + j] * t[i];
            l += Je[i * 18 + j] * eh[i];
        }
        gX[j] = a;
        gP[j] = p;
        gL[j] = l;
        gY[j] = p / L - P * l / (L * L);
    }
    if (g)
        for (j = 0; j < 18; ++j) g[j] = (X * gY[j] - Y * gX[j]) / r2;
    if (H) {
        double HX[324], HP[324], HL[324], S[324], M3[9];
        int r, c;
        memset(HX, 0, sizeof HX);
        memset(HP, 0, sizeof HP);
        memset(HL, 0, sizeof HL);
        memset(S, 0, sizeof S);
        /* ∇²X = J_AᵀJ_B + J_BᵀJ_A + N_A'':N_B + N_B'':N_A */
        wr__add_JtAJ(HX, JA, NULL, JB, 1.0);
        wr__add_JtAJ(HX, JB, NULL, JA, 1.0);
        wr__cross_hess_add(s0, s1, s2, NB, HX);
        wr__cross_hess_add(s1, s0, s3, NA, HX);
        /* S = J_Aᵀ(−[e]×)J_B + J_Aᵀ[N_B]×J_e + J_Bᵀ(−[N_A]×)J_e, with [v]× y = v × y */
        Z[0] = 0.0, Z[1] = e[2], Z[2] = -e[1], Z[3] = -e[2], Z[4] = 0.0, Z[5] = e[0], Z[6] = e[1], Z[7] = -e[0],
        Z[8] = 0.0; /* −[e]× */
        wr__add_JtAJ(S, JA, Z, JB, 1.0);
        M3[0] = 0.0, M3[1] = -NB[2], M3[2] = NB[1], M3[3] = NB[2], M3[4] = 0.0, M3[5] = -NB[0], M3[6] = -NB[1],
        M3[7] = NB[0], M3[8] = 0.0; /* [N_B]× */
        wr__add_JtAJ(S, JA, M3, Je, 1.0);
        M3[0] = 0.0, M3[1] = NA[2], M3[2] = -NA[1], M3[3] = -NA[2], M3[4] = 0.0, M3[5] = NA[0], M3[6] = NA[1],
        M3[7] = -NA[0], M3[8] = 0.0; /* −[N_A]× */
        wr__add_JtAJ(S, JB, M3, Je, 1.0);
        for (r = 0; r < 18; ++r)
            for (c = 0; c < 18; ++c) HP[r * 18 + c] = S[r * 18 + c] + S[c * 18 + r];
        wr__cross_hess_add(s0, s1, s2, u, HP);
        wr__cross_hess_add(s1, s0, s3, w, HP);
        /* ∇²L = J_eᵀ (I − êêᵀ)/L J_e */
        for (r = 0; r < 3; ++r)
            for (c = 0; c < 3; ++c) M3[3 * r + c] = ((r == c ? 1.0 : 0.0) - eh[r] * eh[c]) / L;
        wr__add_JtAJ(HL, Je, M3, Je, 1.0);
        for (r = 0; r < 18; ++r)
            for (c = 0; c < 18; ++c) {
                double hy = HP[r * 18 + c] / L - (gP[r] * gL[c] + gL[r] * gP[c]) / (L * L) -
                            P * HL[r * 18 + c] / (L * L) + 2.0 * P * gL[r] * gL[c] / (L * L * L);
                double gt = (X * gY[r] - Y * gX[r]) / r2;
                H[r * 18 + c] = (X * hy - Y * HX[r * 18 + c] + gX[c] * gY[r] - gY[c] * gX[r]) / r2 -
                                gt * 2.0 * (X * gX[c] + Y * gY[c]) / r2;
            }
        for (r = 0; r < 18; ++r)
            for (c = r + 1; c < 18; ++c) {
                double a = 0.5 * (H[r * 18 + c] + H[c * 18 + r]);
                H[r * 18 + c] = H[c * 18 + r] = a;
            }
    }
    return 0;
}

WRDEF int32_t wr_shell_hinge_angle(const double x[12], double *theta, double *g, double *H) {
    double x18[18], g18[18], H18[324];
    int i, j;
    memset(x18, 0, sizeof x18);
    memcpy(x18, x, 12 * sizeof(double));
    if (wr__hinge18(x18, 0, 1, 2, 3, theta, g ? g18 : NULL, H ? H18 : NULL) != 0) return -1;
    if (g) memcpy(g, g18, 12 * sizeof(double));
    if (H)
        for (i = 0; i < 12; ++i)
            for (j = 0; j < 12; ++j) H[12 * i + j] = H18[18 * i + j];
    return 0;
}

/* δθ wrapped into (−π, π]: the branch cut sits opposite the rest angle */
static double wr__wrap_angle(double d) {
    const double pi = 3.14159265358979323846;
    while (d > pi) d -= 2.0 * pi;
    while (d <= -pi) d += 2.0 * pi;
    return d;
}

WRDEF wr_status wr_shell_dihedral_element(const double x[18], int32_t mask, const double M[9], const double *thbar,
                                          double *E, double *g, double *H, double *theta) {
    double th[3], dth[3], m[3], gt[3][18], Ht[3][324];
    int k, a, b, i, need = g || H;
    for (k = 0; k < 3; ++k) {
        th[k] = dth[k] = 0.0;
        if (need) memset(gt[k], 0, sizeof gt[k]);
        if (!(mask & (1 << k))) continue;
        /* hinge across edge k: the face's corners (k+1, k+2) traversed as in the face, its corner k and
         * the vertex across (slot 3 + k); the neighbour traverses the edge backwards (as for mid-edge) */
        if (wr__hinge18(x, (k + 1) % 3, (k + 2) % 3, k, 3 + k, &th[k], need ? gt[k] : NULL, H ? Ht[k] : NULL) != 0)
            return WR_ERR_GEOMETRY;
        dth[k] = wr__wrap_angle(th[k] - (thbar ? thbar[k] : 0.0));
    }
    if (theta)
        for (k = 0; k < 3; ++k) theta[k] = th[k];
    if (!M) return WR_OK;
    for (a = 0; a < 3; ++a) m[a] = M[3 * a] * dth[0] + M[3 * a + 1] * dth[1] + M[3 * a + 2] * dth[2];
    if (E) *E = 0.5 * (dth[0] * m[0] + dth[1] * m[1] + dth[2] * m[2]);
    if (g)
        for (i = 0; i < 18; ++i) g[i] = m[0] * gt[0][i] + m[1] * gt[1][i] + m[2] * gt[2][i];
    if (H) {
        /* Gauss–Newton part Σ M_ab ∇θ_a∇θ_bᵀ plus the geometric stiffness Σ m_a ∇²θ_a (indefinite:
         * the part Wang et al. 2023 analyse; the shell's project_spd projects the whole face block) */
        int r, c;
        for (r = 0; r < 18; ++r)
            for (c = 0; c < 18; ++c) {
                double v = 0.0;
                for (a = 0; a < 3; ++a) {
                    if (!(mask & (1 << a))) continue;
                    v += m[a] * Ht[a][r * 18 + c];
                    for (b = 0; b < 3; ++b)
                        if (mask & (1 << b)) v += M[3 * a + b] * gt[a][r] * gt[b][c];
                }
                H[r * 18 + c] = v;
            }
    }
    return WR_OK;
}

WRDEF int32_t wr_shell_face_stencil(const wr_shell *s, int32_t f, int32_t verts[6]) {
    int32_t mask = 0;
    int k;
    for (k = 0; k < 3; ++k) {
        verts[k] = s->faces[3 * f + k];
        verts[3 + k] = s->opp[3 * f + k];
        if (verts[3 + k] >= 0) mask |= 1 << k;
    }
    return mask;
}

static void wr__shell_gather(const wr_shell *s, int32_t f, const double *x, int32_t verts[6], int32_t *mask,
                             double x18[18]) {
    int k, i;
    *mask = wr_shell_face_stencil(s, f, verts);
    for (k = 0; k < 6; ++k)
        for (i = 0; i < 3; ++i) x18[3 * k + i] = verts[k] >= 0 ? x[3 * verts[k] + i] : 0.0;
}

/* ---- creation ------------------------------------------------------------------------------ */

static void wr__shell_voigt_iso(double Y, double nu, double scale, double C[9]) {
    double k = scale * Y / (1.0 - nu * nu);
    memset(C, 0, sizeof(double) * 9);
    C[0] = C[4] = k;
    C[1] = C[3] = k * nu;
    C[8] = k * 0.5 * (1.0 - nu);
}

/* Q = A Pᵀ C_b P with P: δb (b11, b22, b12) → κ = Voigt of dinvᵀ δb dinv. */
static void wr__shell_qbend(const double *dinv, double A, const double *Cb, double Q[9]) {
    double r1x = dinv[0], r1y = dinv[1], r2x = dinv[2], r2y = dinv[3], P[9], CP[9];
    int i, j, k;
    P[0] = r1x * r1x;
    P[3] = r1y * r1y;
    P[6] = 2.0 * r1x * r1y;
    P[1] = r2x * r2x;
    P[4] = r2y * r2y;
    P[7] = 2.0 * r2x * r2y;
    P[2] = 2.0 * r1x * r2x;
    P[5] = 2.0 * r1y * r2y;
    P[8] = 2.0 * (r1x * r2y + r2x * r1y);
    for (i = 0; i < 3; ++i)
        for (j = 0; j < 3; ++j) {
            CP[3 * i + j] = 0.0;
            for (k = 0; k < 3; ++k) CP[3 * i + j] += Cb[3 * i + k] * P[3 * k + j];
        }
    for (i = 0; i < 3; ++i)
        for (j = 0; j < 3; ++j) {
            Q[3 * i + j] = 0.0;
            for (k = 0; k < 3; ++k) Q[3 * i + j] += A * P[3 * k + i] * CP[3 * k + j];
        }
}

/* Dihedral bending form M = Wᵀ Q W on the hinge angles (ON DIHEDRAL BENDING): the mid-edge II with
 * n̂_k = R(θ_k/2) n̂ is b = (−φ0 h0 − φ1 h1, −φ0 h0 − φ2 h2, −φ0 h0), φ_k = 2 sin(θ_k/2), h_k the
 * altitude onto edge k; here φ_k = θ_k and h_k the REST altitude, so b = W θ with W constant. */
static void wr__shell_mdih(const double *dinv, double A, const double *uv, const double *Cb, double M[9]) {
    double Q[9], W[9], h[3], QW[9];
    int k, i, j, l;
    wr__shell_qbend(dinv, A, Cb, Q);
    for (k = 0; k < 3; ++k) {
        const double *p = uv + 2 * ((k + 1) % 3), *q = uv + 2 * ((k + 2) % 3);
        h[k] = 2.0 * A / sqrt((q[0] - p[0]) * (q[0] - p[0]) + (q[1] - p[1]) * (q[1] - p[1]));
    }
    W[0] = -h[0], W[1] = -h[1], W[2] = 0.0;
    W[3] = -h[0], W[4] = 0.0, W[5] = -h[2];
    W[6] = -h[0], W[7] = 0.0, W[8] = 0.0;
    for (i = 0; i < 3; ++i)
        for (j = 0; j < 3; ++j) {
            QW[3 * i + j] = 0.0;
            for (l = 0; l < 3; ++l) QW[3 * i + j] += Q[3 * i + l] * W[3 * l + j];
        }
    for (i = 0; i < 3; ++i)
        for (j = 0; j < 3; ++j) {
            M[3 * i + j] = 0.0;
            for (l = 0; l < 3; ++l) M[3 * i + j] += W[3 * l + i] * QW[3 * l + j];
        }
}

WRDEF void wr_shell_free(wr_shell *s) {
    if (!s) return;
    wr_free(s->faces);
    wr_free(s->opp);
    wr_free(s->dinv);
    wr_free(s->area);
    wr_free(s->qbend);
    wr_free(s->bbar);
    wr_free(s->qb_start);
    wr_free(s->qb_vert);
    wr_free(s->qb_w);
    wr_free(s->qb_coef);
    wr_free(s->loop_start);
    wr_free(s->loop_vert);
    wr_free(s->loop_w);
    wr_free(s->loop_wt);
    wr_free(s->loop_rest);
    memset(s, 0, sizeof *s);
}

/* ---- the Loop element (ON THE LOOP ELEMENT) ------------------------------------------------- */

/* p = (x_v, x_w, x_vv, x_vw, x_ww) of face f's limit surface at its centre, from positions x */
static void wr__shell_loop_p(const wr_shell *s, int32_t f, const double *x, double p[15]) {
    int32_t j0 = s->loop_start[f], n = s->loop_start[f + 1] - j0, j, k, i;
    const double *W = s->loop_w + 6 * (size_t)j0;
    memset(p, 0, sizeof(double) * 15);
    for (k = 0; k < 5; ++k)
        for (j = 0; j < n; ++j) {
            double w = W[(k + 1) * n + j];
            for (i = 0; i < 3; ++i) p[3 * k + i] += w * x[3 * s->loop_vert[j0 + j] + i];
        }
}


/* face f's limit-surface stencil: boundary corners completed by ghosts with loop_element 2 (subdiv.h
 * ON GHOST VERTICES); WR_ERR_TOPOLOGY = the face keeps the linear element */
static wr_status wr__shell_loop_stencil(const wr_shell_desc *desc, const wr_mesh *m, int32_t f, int32_t *n, int32_t *verts,
                                        double *W) {
    return desc->loop_element == 2 ? wr_subdiv_loop_stencil_ghost(m, f, n, verts, W, NULL)
                                   : wr_subdiv_loop_stencil(m, f, n, verts, W, NULL);
}

/* Placement of face g in a 2D chart (ON THE LOOP ELEMENT, per-corner rest): the rigid motion (a
 * rotation, then a translation) that maps g's rest corners a, b of the shared edge onto their chart
 * positions Pa, Pb in the neighbour's placement — edge directions aligned, midpoints matched (a sewn
 * edge may differ slightly in length between its two panels). */
static void wr__shell_chart_place(const double uvg[6], int ka, int kb, const double Pa[2], const double Pb[2], double out[6]) {
    double qx = uvg[2 * kb] - uvg[2 * ka], qy = uvg[2 * kb + 1] - uvg[2 * ka + 1], px = Pb[0] - Pa[0], py = Pb[1] - Pa[1];
    double th = atan2(py, px) - atan2(qy, qx), c = cos(th), sn = sin(th), t[2];
    double mx = 0.5 * (uvg[2 * ka] + uvg[2 * kb]), my = 0.5 * (uvg[2 * ka + 1] + uvg[2 * kb + 1]);
    int k;
    t[0] = 0.5 * (Pa[0] + Pb[0]) - (c * mx - sn * my);
    t[1] = 0.5 * (Pa[1] + Pb[1]) - (sn * mx + c * my);
    for (k = 0; k < 3; ++k) {
        double u = uvg[2 * k], w = uvg[2 * k + 1];
        out[2 * k] = c * u - sn * w + t[0];
        out[2 * k + 1] = sn * u + c * w + t[1];
    }
}

#define WR__SHELL_CHART_MAX (3 * WR_SUBDIV_MAX_VALENCE)

/* Rest positions Rl (n*3, z = 0) of face f's stencil verts[0..n) from the per-face rest corners
 * (ON THE LOOP ELEMENT): the faces around f's corners, which hold every stencil vertex, are laid into
 * f's own chart one shared edge at a time (wr__shell_chart_place), so a seam or a panel boundary
 * inside the stencil is crossed by a rigid motion and the 1-ring is one flat piece. A vertex gets
 * the position of the first face that places it. WR_ERR_GEOMETRY when a stencil vertex is not reached. */
static wr_status wr__shell_loop_chart(const wr_mesh *m, int32_t f, int32_t n, const int32_t *verts, double *Rl, wr_diag *diag) {
    int32_t F[WR__SHELL_CHART_MAX], nF = 0, c, i, j, k, q;
    double P[6 * WR__SHELL_CHART_MAX];
    unsigned char placed[WR__SHELL_CHART_MAX];
    int grew = 1;
    F[nF++] = f; /* f first, in its own rest corners */
    wr_mesh_face_rest(m, f, P);
    placed[0] = 1;
    for (c = 0; c < 3; ++c) /* the faces of f's corners' 1-rings */
        for (i = m->vf_start[m->faces[3 * f + c]]; i < m->vf_start[m->faces[3 * f + c] + 1]; ++i) {
            int32_t g = m->vf[i], dup = 0;
            for (j = 0; j < nF; ++j) dup |= F[j] == g;
            if (!dup && nF < WR__SHELL_CHART_MAX) placed[nF] = 0, F[nF++] = g;
        }
    while (grew) {
        grew = 0;
        for (j = 1; j < nF; ++j) {
            double uvg[6];
            if (placed[j]) continue;
            wr_mesh_face_rest(m, F[j], uvg);
            for (k = 0; k < 3 && !placed[j]; ++k) {
                int32_t e = m->face_edges[3 * F[j] + k], a = m->faces[3 * F[j] + (k + 1) % 3], b = m->faces[3 * F[j] + (k + 2) % 3];
                int32_t h = m->edge_faces[2 * e] == F[j] ? m->edge_faces[2 * e + 1] : m->edge_faces[2 * e];
                for (q = 0; q < nF; ++q)
                    if (placed[q] && F[q] == h) {
                        int ca = 0, cb = 0, r;
                        for (r = 0; r < 3; ++r) {
                            if (m->faces[3 * h + r] == a) ca = r;
                            if (m->faces[3 * h + r] == b) cb = r;
                        }
                        wr__shell_chart_place(uvg, (k + 1) % 3, (k + 2) % 3, P + 6 * q + 2 * ca, P + 6 * q + 2 * cb, P + 6 * j);
                        placed[j] = 1, grew = 1;
                        break;
                    }
            }
        }
    }
    for (i = 0; i < n; ++i) {
        int found = 0;
        for (j = 0; j < nF && !found; ++j)
            for (c = 0; c < 3 && placed[j] && !found; ++c)
                if (m->faces[3 * F[j] + c] == verts[i]) {
                    Rl[3 * i] = P[6 * j + 2 * c], Rl[3 * i + 1] = P[6 * j + 2 * c + 1], Rl[3 * i + 2] = 0.0;
                    found = 1;
                }
        if (!found)
            return wr_fail(diag, WR_ERR_GEOMETRY, f, "shell: face %d's Loop stencil vertex %d is not reached by its rest chart",
                           (int)f, (int)verts[i]);
    }
    return WR_OK;
}

/* p of face f's stencil (verts/W, n entries) at local positions Rl (n*3, stencil order) */
static void wr__shell_loop_p_local(int32_t n, const double *W, const double *Rl, double p[15]) {
    int32_t j, k, i;
    memset(p, 0, sizeof(double) * 15);
    for (k = 0; k < 5; ++k)
        for (j = 0; j < n; ++j)
            for (i = 0; i < 3; ++i) p[3 * k + i] += W[(k + 1) * n + j] * Rl[3 * j + i];
}

static wr_status wr__shell_build_loop(wr_shell *s, const wr_mesh *m, const wr_shell_desc *desc, wr_diag *diag) {
    int32_t f, v, total = 0, n, verts[WR_SUBDIV_MAX_STENCIL];
    double W[6 * WR_SUBDIV_MAX_STENCIL], *R = NULL, nu = s->poisson;
    wr_status st = WR_OK;
    if (desc->loop_element != 1 && desc->loop_element != 2)
        return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "shell: loop_element %d is not 0, 1 or 2", (int)desc->loop_element);
    if (s->orthotropic || s->membrane != WR_MEMBRANE_STVK)
        return wr_fail(diag, WR_ERR_UNSUPPORTED, -1, "shell: the Loop element needs the isotropic StVK membrane");
    s->loop_start = (int32_t *)wr_calloc_array((size_t)m->nf + 1, sizeof(int32_t));
    s->loop_rest = (wr_shell_koiter_rest *)wr_calloc_array((size_t)m->nf, sizeof(wr_shell_koiter_rest));
    s->loop_wt = (double *)wr_calloc_array((size_t)m->nf, sizeof(double));
    R = (double *)wr_alloc_array(3 * (size_t)m->nv, sizeof(double));
    if (!s->loop_start || !s->loop_rest || !s->loop_wt || !R) {
        st = wr_fail(diag, WR_ERR_NOMEM, -1, "shell: out of memory (Loop element)");
        goto done;
    }
    for (v = 0; v < m->nv; ++v) { /* the rest surface: rest_pos3, else the pattern plane, else pos */
        int i;
        for (i = 0; i < 3; ++i)
            R[3 * v + i] = desc->rest_pos3 ? desc->rest_pos3[3 * v + i]
                           : m->rest      ? (i < 2 ? m->rest[2 * v + i] : 0.0)
                                          : m->pos[3 * v + i];
    }
    for (f = 0; f < m->nf; ++f) { /* first pass: sizes */
        s->loop_start[f] = total;
        if (wr__shell_loop_stencil(desc, m, f, &n, verts, W) == WR_OK) total += n;
    }
    s->loop_start[m->nf] = total;
    s->loop_vert = (int32_t *)wr_alloc_array((size_t)total + 1, sizeof(int32_t));
    s->loop_w = (double *)wr_alloc_array(6 * (size_t)total + 1, sizeof(double));
    if (!s->loop_vert || !s->loop_w) {
        st = wr_fail(diag, WR_ERR_NOMEM, -1, "shell: out of memory (Loop element)");
        goto done;
    }
    for (f = 0; f < m->nf; ++f) {
        int32_t j0 = s->loop_start[f];
        double p[15], a[3], r;
        wr_shell_koiter_rest *kr = s->loop_rest + f;
        int c;
        if (s->loop_start[f + 1] == j0) continue;
        wr__shell_loop_stencil(desc, m, f, &n, verts, W);
        memcpy(s->loop_vert + j0, verts, sizeof(int32_t) * (size_t)n);
        memcpy(s->loop_w + 6 * (size_t)j0, W, sizeof(double) * 6 * (size_t)n);
        if (m->corner_rest && !desc->rest_pos3) { /* per-corner rest: each stencil in its own chart */
            double Rl[3 * WR_SUBDIV_MAX_STENCIL];
            if ((st = wr__shell_loop_chart(m, f, n, verts, Rl, diag)) != WR_OK) goto done;
            wr__shell_loop_p_local(n, W, Rl, p);
        } else {
            wr__shell_loop_p(s, f, R, p);
        }
        kr->A[0] = p[0] * p[0] + p[1] * p[1] + p[2] * p[2];
        kr->A[1] = p[0] * p[3] + p[1] * p[4] + p[2] * p[5];
        kr->A[2] = p[3] * p[3] + p[4] * p[4] + p[5] * p[5];
        a[0] = p[1] * p[5] - p[2] * p[4];
        a[1] = p[2] * p[3] - p[0] * p[5];
        a[2] = p[0] * p[4] - p[1] * p[3];
        r = sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
        if (!(r > 0.0) || !(kr->A[0] * kr->A[2] - kr->A[1] * kr->A[1] > 0.0)) {
            st = wr_fail(diag, WR_ERR_GEOMETRY, f, "shell: face %d's rest limit surface has no tangent plane", (int)f);
            goto done;
        }
        for (c = 0; c < 3; ++c) kr->B[c] = (p[6 + 3 * c] * a[0] + p[7 + 3 * c] * a[1] + p[8 + 3 * c] * a[2]) / r;
        kr->Ym = s->young * s->thickness / (1.0 - nu * nu);
        kr->Db = s->bending == WR_BENDING_NONE ? 0.0 : s->bending_stiffness;
        kr->nu = nu;
        /* koiter_point is per unit parameter area (√det A built in): weighting by area / √det A makes
         * each face count its rest area, so Loop and linear faces tile the rest domain exactly */
        s->loop_wt[f] = s->area[f] / sqrt(kr->A[0] * kr->A[2] - kr->A[1] * kr->A[1]);
        s->n_loop_faces++;
    }
done:
    wr_free(R);
    return st;
}

/* Face f's Loop energy (parts), gradient added to grad when non-NULL */
static void wr__shell_loop_energy(const wr_shell *s, int32_t f, const double *x, double *em, double *eb, double *grad) {
    int32_t j0 = s->loop_start[f], n = s->loop_start[f + 1] - j0, j, k, i;
    const double *W = s->loop_w + 6 * (size_t)j0;
    wr_shell_koiter_rest rm = s->loop_rest[f], rb = s->loop_rest[f];
    double p[15], g[15];
    wr__shell_loop_p(s, f, x, p);
    rm.Db = 0.0;
    rb.Ym = 0.0;
    *em += s->loop_wt[f] * wr_shell_koiter_point(&rm, p, NULL, NULL);
    *eb += s->loop_wt[f] * wr_shell_koiter_point(&rb, p, NULL, NULL);
    if (!grad) return;
    wr_shell_koiter_point(s->loop_rest + f, p, g, NULL);
    for (k = 0; k < 5; ++k)
        for (j = 0; j < n; ++j) {
            double w = s->loop_wt[f] * W[(k + 1) * n + j];
            for (i = 0; i < 3; ++i) grad[3 * s->loop_vert[j0 + j] + i] += w * g[3 * k + i];
        }
}

/* Face f's Loop Hessian block over its stencil: loop_wt · Wᵀ H_p W, H_p projected PSD in the point
 * space unless exact (Ke: (3n)² with n = the stencil size) */
static void wr__shell_loop_block(const wr_shell *s, int32_t f, const double *x, int exact, double *Ke) {
    int32_t j0 = s->loop_start[f], n = s->loop_start[f + 1] - j0, a, b, k, l, i, jj;
    const double *W = s->loop_w + 6 * (size_t)j0;
    double p[15], H[225], T[15 * 3 * WR_SUBDIV_MAX_STENCIL];
    wr__shell_loop_p(s, f, x, p);
    wr_shell_koiter_point(s->loop_rest + f, p, NULL, H);
    if (!exact) wr_dense_project_spd(15, H, 0.0);
    /* T = H_p (W ⊗ I): 15 × 3n, then Ke = (W ⊗ I)ᵀ T */
    for (k = 0; k < 15; ++k)
        for (b = 0; b < n; ++b)
            for (jj = 0; jj < 3; ++jj) {
                double t = 0.0;
                for (l = 0; l < 5; ++l) t += H[15 * k + 3 * l + jj] * W[(l + 1) * n + b];
                T[k * 3 * n + 3 * b + jj] = t;
            }
    for (a = 0; a < n; ++a)
        for (i = 0; i < 3; ++i)
            for (b = 0; b < 3 * n; ++b) {
                double t = 0.0;
                for (k = 0; k < 5; ++k) t += W[(k + 1) * n + a] * T[(3 * k + i) * 3 * n + b];
                Ke[(3 * a + i) * 3 * n + b] = s->loop_wt[f] * t;
            }
}


static double wr__cot2(const double *o, const double *p, const double *q) {
    /* cotangent of the angle at o in triangle (o, p, q), 2D */
    double ax = p[0] - o[0], ay = p[1] - o[1], bx = q[0] - o[0], by = q[1] - o[1];
    return (ax * bx + ay * by) / fabs(ax * by - ay * bx);
}

static wr_status wr__shell_build_qb(wr_shell *s, const wr_mesh *m, const double *uvall, wr_diag *diag) {
    int8_t *bnd = (int8_t *)wr_calloc_array((size_t)m->nv, 1);
    double *avor = (double *)wr_calloc_array((size_t)m->nv, sizeof(double));
    int32_t v, e, nst = 0, total = 0, cap = 0;
    int32_t *lv = NULL;
    double *lw = NULL;
    if (!bnd || !avor) {
        wr_free(bnd);
        wr_free(avor);
        return wr_fail(diag, WR_ERR_NOMEM, -1, "quadratic bending: out of memory");
    }
    for (e = 0; e < m->ne; ++e)
        if (m->edge_faces[2 * e] < 0 || m->edge_faces[2 * e + 1] < 0) bnd[m->edges[2 * e]] = bnd[m->edges[2 * e + 1]] = 1;
    /* mixed Voronoi areas (Meyer et al. 2003) */
    {
        int32_t f;
        for (f = 0; f < m->nf; ++f) {
            const double *uv = uvall + 6 * f;
            double A = s->area[f], cot[3];
            int c, obtuse = -1;
            for (c = 0; c < 3; ++c) {
                cot[c] = wr__cot2(uv + 2 * c, uv + 2 * ((c + 1) % 3), uv + 2 * ((c + 2) % 3));
                if (cot[c] < 0.0) obtuse = c;
            }
            for (c = 0; c < 3; ++c) {
                int32_t vi = m->faces[3 * f + c];
                if (obtuse < 0) {
                    int a = (c + 1) % 3, b = (c + 2) % 3;
                    double la2 = (uv[2 * a] - uv[2 * c]) * (uv[2 * a] - uv[2 * c]) +
                                 (uv[2 * a + 1] - uv[2 * c + 1]) * (uv[2 * a + 1] - uv[2 * c + 1]);
                    double lb2 = (uv[2 * b] - uv[2 * c]) * (uv[2 * b] - uv[2 * c]) +
                                 (uv[2 * b + 1] - uv[2 * c + 1]) * (uv[2 * b + 1] - uv[2 * c + 1]);
                    avor[vi] += 0.125 * (la2 * cot[b] + lb2 * cot[a]);
                } else {
                    avor[vi] += obtuse == c ? 0.5 * A : 0.25 * A;
                }
            }
        }
    }
    for (v = 0; v < m->nv; ++v)
        if (!bnd[v] && m->vf_start[v + 1] > m->vf_start[v]) {
            ++nst;
            total += 1 + 2 * (m->vf_start[v + 1] - m->vf_start[v]);
        }
    s->n_qb = nst;
    s->qb_start = (int32_t *)wr_alloc_array((size_t)nst + 1, sizeof(int32_t));
    s->qb_vert = (int32_t *)wr_alloc_array((size_t)total, sizeof(int32_t));
    s->qb_w = (double *)wr_alloc_array((size_t)total, sizeof(double));
    s->qb_coef = (double *)wr_alloc_array((size_t)nst, sizeof(double));
    if (!s->qb_start || !s->qb_vert || !s->qb_w || !s->qb_coef) {
        wr_free(bnd);
        wr_free(avor);
        return wr_fail(diag, WR_ERR_NOMEM, -1, "quadratic bending: out of memory");
    }
    nst = 0;
    total = 0;
    (void)cap;
    for (v = 0; v < m->nv; ++v) {
        int32_t j, n = 1, t;
        double wsum = 0.0;
        if (bnd[v] || m->vf_start[v + 1] <= m->vf_start[v]) continue;
        s->qb_start[nst] = total;
        lv = s->qb_vert + total;
        lw = s->qb_w + total;
        lv[0] = v;
        lw[0] = 0.0;
        for (j = m->vf_start[v]; j < m->vf_start[v + 1]; ++j) {
            int32_t f = m->vf[j], c = 0, side;
            const double *uv = uvall + 6 * f;
            while (m->faces[3 * f + c] != v) ++c;
            /* edge (v, a) gets ½cot of the angle at b; edge (v, b) gets ½cot of the angle at a */
            for (side = 0; side < 2; ++side) {
                int a = (c + 1 + side) % 3, b = (c + 2 - side) % 3;
                int32_t va = m->faces[3 * f + a];
                double wv = 0.5 * wr__cot2(uv + 2 * b, uv + 2 * c, uv + 2 * a);
                for (t = 1; t < n; ++t)
                    if (lv[t] == va) break;
                if (t == n) {
                    lv[n] = va;
                    lw[n] = 0.0;
                    ++n;
                }
                lw[t] += wv;
                wsum += wv;
            }
        }
        lw[0] = -wsum;
        if (!(avor[v] > 0.0)) {
            wr_free(bnd);
            wr_free(avor);
            return wr_fail(diag, WR_ERR_GEOMETRY, v, "quadratic bending: vertex %d has zero rest area", (int)v);
        }
        s->qb_coef[nst] = s->bending_stiffness / avor[v];
        total += n;
        ++nst;
    }
    s->qb_start[nst] = total;
    wr_free(bnd);
    wr_free(avor);
    return WR_OK;
}

static int wr__shell_finite(double v) { return v == v && v - v == 0.0; }

/* The arguments every model needs: known models, h > 0, ρ >= 0, B >= 0 (B = 0: derived). */
static wr_status wr__shell_check_desc(const wr_mesh *m, const wr_shell_desc *desc, wr_diag *diag) {
    if (!m || !desc || !m->faces || m->nf < 1 || m->nv < 3)
        return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "shell: NULL mesh/desc or empty mesh");
    if ((int)desc->membrane < 0 || (int)desc->membrane > 3)
        return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "shell: unknown membrane model %d", (int)desc->membrane);
    if ((int)desc->bending < 0 || (int)desc->bending > 3)
        return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "shell: unknown bending model %d", (int)desc->bending);
    if (!(desc->thickness > 0.0) || !wr__shell_finite(desc->thickness))
        return wr_fail(diag, WR_ERR_DOMAIN, -1, "shell: thickness %g m must be > 0", desc->thickness);
    if (!(desc->density >= 0.0) || !wr__shell_finite(desc->density))
        return wr_fail(diag, WR_ERR_DOMAIN, -1, "shell: density %g kg/m^3 must be >= 0", desc->density);
    if (!(desc->bending_stiffness >= 0.0) || !wr__shell_finite(desc->bending_stiffness))
        return wr_fail(diag, WR_ERR_DOMAIN, -1, "shell: bending_stiffness %g N*m must be >= 0",
                       desc->bending_stiffness);
    return WR_OK;
}

/* Baraff–Witkin's warp, weft and shear stiffnesses [N/m]; the grain needs a 2D rest domain. */
static wr_status wr__shell_bw_setup(wr_shell *s, const wr_mesh *m, const wr_shell_desc *desc, wr_diag *diag) {
    double ku = desc->stretch_warp, kv = desc->stretch_weft, ks = desc->stretch_shear;
    if (!(ku > 0.0) || !(kv > 0.0) || !(ks > 0.0) || !wr__shell_finite(ku + kv + ks))
        return wr_fail(diag, WR_ERR_DOMAIN, -1,
                       "shell: Baraff-Witkin stretch_warp=%g stretch_weft=%g stretch_shear=%g N/m must be > 0", ku, kv,
                       ks);
    if (desc->rest_pos3 || (!m->rest && !m->corner_rest))
        return wr_fail(diag, WR_ERR_UNSUPPORTED, -1, "shell: Baraff-Witkin needs a 2D rest domain for warp/weft");
    s->bw_k[0] = ku;
    s->bw_k[1] = kv;
    s->bw_k[2] = ks;
    return WR_OK;
}

/* Warp/weft bending stiffnesses: both > 0, mid-edge or dihedral bending, not with a single B, and a
 * 2D rest domain for the grain. */
static wr_status wr__shell_check_aniso_bend(const wr_mesh *m, const wr_shell_desc *desc, wr_diag *diag) {
    if (!(desc->bending_warp > 0.0) || !(desc->bending_weft > 0.0) ||
        !wr__shell_finite(desc->bending_warp + desc->bending_weft))
        return wr_fail(diag, WR_ERR_DOMAIN, -1, "shell: bending_warp %g and bending_weft %g N*m must both be > 0",
                       desc->bending_warp, desc->bending_weft);
    if (desc->bending != WR_BENDING_MIDEDGE && desc->bending != WR_BENDING_DIHEDRAL)
        return wr_fail(diag, WR_ERR_UNSUPPORTED, -1, "shell: warp/weft bending needs mid-edge or dihedral bending");
    if (desc->bending_stiffness > 0.0)
        return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "shell: give bending_stiffness or bending_warp/weft, not both");
    if (desc->rest_pos3 || (!m->rest && !m->corner_rest))
        return wr_fail(diag, WR_ERR_UNSUPPORTED, -1, "shell: warp/weft bending needs a 2D rest domain for the grain");
    return WR_OK;
}

/* Isotropic plane stress: the membrane and bending Voigt matrices from Y, ν, h (B from Kirchhoff–Love
 * unless given). Baraff–Witkin carries its own stretch stiffnesses: Y is then only needed for a
 * default B, and an unset Y becomes the effective warp modulus, for downstream defaults. */
static wr_status wr__shell_iso_material(wr_shell *s, const wr_shell_desc *desc, int bw, int aniso_bend, wr_diag *diag) {
    double Y = desc->young, nu = desc->poisson, h = desc->thickness;
    int need_y = !(bw && (desc->bending == WR_BENDING_NONE || desc->bending_stiffness > 0.0 || aniso_bend));
    if (!need_y && Y == 0.0) Y = s->bw_k[0] / h;
    if (!(Y > 0.0) || !wr__shell_finite(Y)) return wr_fail(diag, WR_ERR_DOMAIN, -1, "shell: young %g Pa must be > 0", Y);
    if (!(nu > -1.0 && nu < 1.0))
        return wr_fail(diag, WR_ERR_DOMAIN, -1, "shell: poisson %g outside (-1, 1) (plane-stress stability)", nu);
    s->young = Y;
    s->poisson = nu;
    s->bending_stiffness = desc->bending_stiffness > 0.0 ? desc->bending_stiffness : Y * h * h * h / (12.0 * (1.0 - nu * nu));
    wr__shell_voigt_iso(Y, nu, h, s->C_mem);
    wr__shell_voigt_iso(1.0 - nu * nu, nu, s->bending_stiffness, s->C_bend); /* B·[[1,ν,0],[ν,1,0],[0,0,(1−ν)/2]] */
    return WR_OK;
}

/* Orthotropic plane stress in the grain frame: E1 (warp), E2 (weft), G12, ν12 (ν21 = ν12 E2/E1). */
static wr_status wr__shell_ortho_material(wr_shell *s, const wr_mesh *m, const wr_shell_desc *desc, wr_diag *diag) {
    double E1 = desc->young_warp, E2 = desc->young_weft, G = desc->shear_modulus, n12 = desc->poisson_warp;
    double h = desc->thickness, n21, den, C[9];
    int i;
    if (!(E1 > 0.0) || !(E2 > 0.0) || !(G > 0.0) || !wr__shell_finite(E1 + E2 + G))
        return wr_fail(diag, WR_ERR_DOMAIN, -1, "shell: orthotropic moduli E1=%g E2=%g G12=%g Pa must be > 0", E1, E2, G);
    if (!(n12 * n12 * E2 / E1 < 1.0))
        return wr_fail(diag, WR_ERR_DOMAIN, -1, "shell: poisson_warp %g violates nu12^2*E2/E1 < 1", n12);
    if (desc->membrane == WR_MEMBRANE_TFT || desc->bending == WR_BENDING_QUADRATIC)
        return wr_fail(diag, WR_ERR_UNSUPPORTED, -1, "shell: TFT membrane and quadratic bending are isotropic-only");
    if (desc->bending_stiffness > 0.0)
        return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "shell: bending_stiffness override is isotropic-only");
    if (desc->rest_pos3 || (!m->rest && !m->corner_rest))
        return wr_fail(diag, WR_ERR_UNSUPPORTED, -1, "shell: orthotropy needs a 2D rest domain for the grain");
    n21 = n12 * E2 / E1;
    den = 1.0 - n12 * n21;
    C[0] = E1 / den;
    C[1] = C[3] = n12 * E2 / den;
    C[4] = E2 / den;
    C[2] = C[5] = C[6] = C[7] = 0.0;
    C[8] = G;
    for (i = 0; i < 9; ++i) {
        s->C_mem[i] = h * C[i];
        s->C_bend[i] = h * h * h / 12.0 * C[i];
    }
    s->young = E1;
    s->poisson = n12;
    s->bending_stiffness = s->C_bend[0];
    return WR_OK;
}

/* ON ANISOTROPIC BENDING: B1 warp, B2 weft, coupling ν√(B1B2), twist (1−ν)/2·√(B1B2). */
static void wr__shell_aniso_bending(wr_shell *s, const wr_shell_desc *desc) {
    double B1 = desc->bending_warp, B2 = desc->bending_weft, Bg = sqrt(B1 * B2), nu = s->poisson;
    memset(s->C_bend, 0, sizeof s->C_bend);
    s->C_bend[0] = B1;
    s->C_bend[4] = B2;
    s->C_bend[1] = s->C_bend[3] = nu * Bg;
    s->C_bend[8] = 0.5 * (1.0 - nu) * Bg;
    s->bending_stiffness = B1;
}

/* Whether the rest shape is 3D: given as rest_pos3 (checked finite), or the mesh has no 2D rest
 * domain and its positions leave the z = 0 plane. */
static wr_status wr__shell_rest_is_3d(const wr_mesh *m, const wr_shell_desc *desc, int *is3d, wr_diag *diag) {
    int32_t i;
    int flat_pos = 1;
    if (desc->rest_pos3)
        for (i = 0; i < 3 * m->nv; ++i)
            if (!wr__shell_finite(desc->rest_pos3[i]))
                return wr_fail(diag, WR_ERR_DOMAIN, i / 3, "shell: rest_pos3 of vertex %d is not finite", (int)(i / 3));
    if (!m->rest && !m->corner_rest)
        for (i = 0; i < m->nv; ++i)
            if (m->pos[3 * i + 2] != 0.0) flat_pos = 0;
    *is3d = desc->rest_pos3 != NULL || (!m->rest && !m->corner_rest && !flat_pos);
    return WR_OK;
}

/* opp[3f + k]: the vertex across the edge opposite corner k of face f (-1 on the boundary). */
static void wr__shell_opposites(wr_shell *s, const wr_mesh *m) {
    int32_t f, k, c;
    for (f = 0; f < m->nf; ++f)
        for (k = 0; k < 3; ++k) {
            int32_t e = m->face_edges[3 * f + k];
            int32_t g = m->edge_faces[2 * e] == f ? m->edge_faces[2 * e + 1] : m->edge_faces[2 * e];
            int32_t a = m->faces[3 * f + (k + 1) % 3], b = m->faces[3 * f + (k + 2) % 3], q = -1;
            if (g >= 0)
                for (c = 0; c < 3; ++c) {
                    int32_t vv = m->faces[3 * g + c];
                    if (vv != a && vv != b) q = vv;
                }
            s->opp[3 * f + k] = q;
        }
}

/* Face f's rest triangle in a 2D chart: the rest domain, or for a 3D rest shape the in-plane frame
 * (e1/|e1|, n̂ × e1/|e1|), where corner 2 lands at v = |e1×e2|/|e1| > 0. */
static wr_status wr__shell_face_chart(const wr_mesh *m, int32_t f, const double *R3, int is3d, double uv[6], wr_diag *diag) {
    const int32_t *t = m->faces + 3 * f;
    double e1[3], e2[3], l1, n[3], nn, t2[3];
    int i;
    if (!is3d) {
        wr_mesh_face_rest(m, f, uv);
        return WR_OK;
    }
    for (i = 0; i < 3; ++i) {
        e1[i] = R3[3 * t[1] + i] - R3[3 * t[0] + i];
        e2[i] = R3[3 * t[2] + i] - R3[3 * t[0] + i];
    }
    l1 = sqrt(e1[0] * e1[0] + e1[1] * e1[1] + e1[2] * e1[2]);
    n[0] = e1[1] * e2[2] - e1[2] * e2[1];
    n[1] = e1[2] * e2[0] - e1[0] * e2[2];
    n[2] = e1[0] * e2[1] - e1[1] * e2[0];
    nn = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    if (!(l1 > 0.0) || !(nn > 0.0)) return wr_fail(diag, WR_ERR_GEOMETRY, f, "shell: rest face %d is degenerate", (int)f);
    t2[0] = (n[1] * e1[2] - n[2] * e1[1]) / (nn * l1);
    t2[1] = (n[2] * e1[0] - n[0] * e1[2]) / (nn * l1);
    t2[2] = (n[0] * e1[1] - n[1] * e1[0]) / (nn * l1);
    uv[0] = uv[1] = 0.0;
    uv[2] = l1;
    uv[3] = 0.0;
    uv[4] = (e1[0] * e2[0] + e1[1] * e2[1] + e1[2] * e2[2]) / l1;
    uv[5] = t2[0] * e2[0] + t2[1] * e2[1] + t2[2] * e2[2];
    return WR_OK;
}

/* Face f's rest data from its chart uv: the area, the inverse rest edge matrix in the material frame
 * (coordinates along (cos θ, sin θ) and its left normal, dinv = D⁻¹ R(θ); θ the face's grain angle
 * when the material has a grain), and the constant bending quadratic form of the model. */
static wr_status wr__shell_face_rest(wr_shell *s, int32_t f, const double uv[6], double ang, wr_diag *diag) {
    double D[4], det, cs, sn;
    D[0] = uv[2] - uv[0];
    D[1] = uv[4] - uv[0];
    D[2] = uv[3] - uv[1];
    D[3] = uv[5] - uv[1];
    det = D[0] * D[3] - D[1] * D[2];
    if (!(det > 0.0) || !wr__shell_finite(det))
        return wr_fail(diag, WR_ERR_GEOMETRY, f, "shell: rest face %d has area %g (degenerate or clockwise)", (int)f,
                       0.5 * det);
    s->area[f] = 0.5 * det;
    s->total_area += 0.5 * det;
    if (!wr__shell_finite(ang)) return wr_fail(diag, WR_ERR_DOMAIN, f, "shell: grain_angle of face %d is not finite", (int)f);
    cs = cos(ang);
    sn = sin(ang);
    {
        double i00 = D[3] / det, i01 = -D[1] / det, i10 = -D[2] / det, i11 = D[0] / det;
        double *di = s->dinv + 4 * f;
        di[0] = i00 * cs + i01 * sn;
        di[1] = -i00 * sn + i01 * cs;
        di[2] = i10 * cs + i11 * sn;
        di[3] = -i10 * sn + i11 * cs;
    }
    if (s->bending == WR_BENDING_MIDEDGE) wr__shell_qbend(s->dinv + 4 * f, s->area[f], s->C_bend, s->qbend + 9 * f);
    if (s->bending == WR_BENDING_DIHEDRAL) wr__shell_mdih(s->dinv + 4 * f, s->area[f], uv, s->C_bend, s->qbend + 9 * f);
    return WR_OK;
}

/* For a 3D rest shape, each face's rest bending measure (hinge angles or mid-edge normals), so that
 * the rest shape is stress-free. */
static wr_status wr__shell_rest_bbar(wr_shell *s, const double *R3, wr_diag *diag) {
    int32_t f, verts[6], mask;
    double x18[18];
    for (f = 0; f < s->nf; ++f) {
        wr__shell_gather(s, f, R3, verts, &mask, x18);
        if (s->bending == WR_BENDING_DIHEDRAL) {
            if (wr_shell_dihedral_element(x18, mask, NULL, NULL, NULL, NULL, NULL, s->bbar + 3 * f) != WR_OK)
                return wr_fail(diag, WR_ERR_GEOMETRY, f, "shell: rest hinge angle of face %d undefined", (int)f);
        } else if (wr_shell_midedge_element(x18, mask, NULL, NULL, NULL, NULL, NULL, s->bbar + 3 * f) != WR_OK) {
            return wr_fail(diag, WR_ERR_GEOMETRY, f, "shell: rest mid-edge normal of face %d undefined", (int)f);
        }
    }
    return WR_OK;
}

/* The material of s (Voigt matrices, B) from desc: Baraff–Witkin stiffnesses, isotropic or
 * orthotropic plane stress, warp/weft bending. */
static wr_status wr__shell_material(wr_shell *s, const wr_mesh *m, const wr_shell_desc *desc, int bw, int aniso_bend,
                                    wr_diag *diag) {
    wr_status st;
    if (bw && (st = wr__shell_bw_setup(s, m, desc, diag)) != WR_OK) return st;
    if (aniso_bend && (st = wr__shell_check_aniso_bend(m, desc, diag)) != WR_OK) return st;
    st = s->orthotropic ? wr__shell_ortho_material(s, m, desc, diag) : wr__shell_iso_material(s, desc, bw, aniso_bend, diag);
    if (st != WR_OK) return st;
    if (aniso_bend) wr__shell_aniso_bending(s, desc);
    return WR_OK;
}

/* Per-face rest data (chart, area, material frame, bending forms), the 3D rest bending measure, and
 * the quadratic-bending and Loop-element data of the models that need them. */
static wr_status wr__shell_rest_state(wr_shell *s, const wr_mesh *m, const wr_shell_desc *desc, int is3d, int grained,
                                      double *uvall, wr_diag *diag) {
    const double *R3 = desc->rest_pos3 ? desc->rest_pos3 : m->pos;
    wr_status st;
    int32_t f;
    for (f = 0; f < m->nf; ++f) {
        double *uv = uvall + 6 * f, ang = (grained && desc->grain_angle) ? desc->grain_angle[f] : 0.0;
        if ((st = wr__shell_face_chart(m, f, R3, is3d, uv, diag)) != WR_OK) return st;
        if ((st = wr__shell_face_rest(s, f, uv, ang, diag)) != WR_OK) return st;
    }
    if (is3d && (st = wr__shell_rest_bbar(s, R3, diag)) != WR_OK) return st;
    if (s->bending == WR_BENDING_QUADRATIC && (st = wr__shell_build_qb(s, m, uvall, diag)) != WR_OK) return st;
    if (desc->loop_element && (st = wr__shell_build_loop(s, m, desc, diag)) != WR_OK) return st;
    return WR_OK;
}

WRDEF wr_status wr_shell_create(wr_shell *s, const wr_mesh *m, const wr_shell_desc *desc, wr_diag *diag) {
    int is3d = 0, aniso_bend, bw;
    double *uvall = NULL;
    wr_status st;
    if (!s) return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "shell: NULL output");
    memset(s, 0, sizeof *s);
    if ((st = wr__shell_check_desc(m, desc, diag)) != WR_OK) return st;
    s->nv = m->nv;
    s->nf = m->nf;
    s->membrane = desc->membrane;
    s->bending = desc->bending;
    s->thickness = desc->thickness;
    s->density = desc->density;
    s->orthotropic = desc->orthotropic != 0;
    aniso_bend = desc->bending_warp != 0.0 || desc->bending_weft != 0.0;
    bw = desc->membrane == WR_MEMBRANE_BARAFF_WITKIN;
    if ((st = wr__shell_material(s, m, desc, bw, aniso_bend, diag)) != WR_OK) return st;
    if ((st = wr__shell_rest_is_3d(m, desc, &is3d, diag)) != WR_OK) return st;
    if (is3d && desc->bending == WR_BENDING_QUADRATIC)
        return wr_fail(diag, WR_ERR_UNSUPPORTED, -1, "shell: quadratic bending assumes a flat rest (TFW Sec. 4.1)");
    s->faces = (int32_t *)wr_alloc_array((size_t)m->nf * 3, sizeof(int32_t));
    s->opp = (int32_t *)wr_alloc_array((size_t)m->nf * 3, sizeof(int32_t));
    s->dinv = (double *)wr_alloc_array((size_t)m->nf * 4, sizeof(double));
    s->area = (double *)wr_alloc_array((size_t)m->nf, sizeof(double));
    s->qbend = (double *)wr_calloc_array((size_t)m->nf * 9, sizeof(double));
    uvall = (double *)wr_alloc_array((size_t)m->nf * 6, sizeof(double));
    if (is3d) s->bbar = (double *)wr_calloc_array((size_t)m->nf * 3, sizeof(double));
    if (!s->faces || !s->opp || !s->dinv || !s->area || !s->qbend || !uvall || (is3d && !s->bbar)) {
        st = wr_fail(diag, WR_ERR_NOMEM, -1, "shell: out of memory (%d faces)", (int)m->nf);
    } else {
        memcpy(s->faces, m->faces, sizeof(int32_t) * 3 * (size_t)m->nf);
        wr__shell_opposites(s, m);
        st = wr__shell_rest_state(s, m, desc, is3d, s->orthotropic || bw || aniso_bend, uvall, diag);
    }
    wr_free(uvall);
    if (st != WR_OK) wr_shell_free(s);
    return st;
}

/* ---- mesh-level evaluation ----------------------------------------------------------------- */

/* Face f's membrane and bending energy added to *em, *eb (and its gradient to grad when non-NULL):
 * the Loop element where the face has one, else the linear membrane and the face's bending stencil.
 * WR_ERR_GEOMETRY when a normal of the bending stencil is undefined. */
static wr_status wr__shell_face_eval(const wr_shell *s, int32_t f, const double *x, double *em, double *eb, double *grad) {
    int32_t verts[6], mask, k, i;
    double x18[18], g9[9], g18[18], e = 0.0;
    if (s->loop_start && s->loop_start[f + 1] > s->loop_start[f]) {
        wr__shell_loop_energy(s, f, x, em, eb, grad);
        return WR_OK;
    }
    wr__shell_gather(s, f, x, verts, &mask, x18);
    if (s->membrane != WR_MEMBRANE_NONE) {
        *em += wr_shell_membrane_element(s, f, x18, grad ? g9 : NULL, NULL);
        if (grad)
            for (k = 0; k < 3; ++k)
                for (i = 0; i < 3; ++i) grad[3 * verts[k] + i] += g9[3 * k + i];
    }
    if (s->bending == WR_BENDING_MIDEDGE || s->bending == WR_BENDING_DIHEDRAL) {
        wr_status es = s->bending == WR_BENDING_MIDEDGE
                           ? wr_shell_midedge_element(x18, mask, s->qbend + 9 * f, s->bbar ? s->bbar + 3 * f : NULL, &e,
                                                      grad ? g18 : NULL, NULL, NULL)
                           : wr_shell_dihedral_element(x18, mask, s->qbend + 9 * f, s->bbar ? s->bbar + 3 * f : NULL, &e,
                                                       grad ? g18 : NULL, NULL, NULL);
        if (es != WR_OK) return WR_ERR_GEOMETRY;
        *eb += e;
        if (grad)
            for (k = 0; k < 6; ++k)
                if (verts[k] >= 0)
                    for (i = 0; i < 3; ++i) grad[3 * verts[k] + i] += g18[3 * k + i];
    }
    return WR_OK;
}

WRDEF wr_status wr_shell_face_energy(const wr_shell *s, int32_t f, const double *x, double *E_membrane, double *E_bending) {
    double em = 0.0, eb = 0.0;
    wr_status st;
    if (!s || !x || f < 0 || f >= s->nf) return WR_ERR_INVALID_ARG;
    st = wr__shell_face_eval(s, f, x, &em, &eb, NULL);
    if (E_membrane) *E_membrane = em;
    if (E_bending) *E_bending = eb;
    return st;
}

static wr_status wr__shell_eval(const wr_shell *s, const double *x, double *Em, double *Eb, double *grad,
                                wr_diag *diag) {
    int32_t f, st, i;
    double em = 0.0, eb = 0.0;
    if (!s || !x || !s->faces) return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "shell energy: NULL shell or x");
    for (f = 0; f < 3 * s->nv; ++f)
        if (!wr__shell_finite(x[f]))
            return wr_fail(diag, WR_ERR_DOMAIN, f / 3, "shell energy: vertex %d has a non-finite coordinate", (int)(f / 3));
    if (grad) memset(grad, 0, sizeof(double) * 3 * (size_t)s->nv);
    for (f = 0; f < s->nf; ++f)
        if (wr__shell_face_eval(s, f, x, &em, &eb, grad) != WR_OK)
            return wr_fail(diag, WR_ERR_GEOMETRY, f, "shell energy: face %d has an undefined normal", (int)f);
    if (s->bending == WR_BENDING_QUADRATIC)
        for (st = 0; st < s->n_qb; ++st) {
            double lx[3] = {0.0, 0.0, 0.0};
            int32_t j;
            for (j = s->qb_start[st]; j < s->qb_start[st + 1]; ++j)
                for (i = 0; i < 3; ++i) lx[i] += s->qb_w[j] * x[3 * s->qb_vert[j] + i];
            eb += 0.5 * s->qb_coef[st] * (lx[0] * lx[0] + lx[1] * lx[1] + lx[2] * lx[2]);
            if (grad)
                for (j = s->qb_start[st]; j < s->qb_start[st + 1]; ++j)
                    for (i = 0; i < 3; ++i) grad[3 * s->qb_vert[j] + i] += s->qb_coef[st] * s->qb_w[j] * lx[i];
        }
    if (!wr__shell_finite(em + eb)) return wr_fail(diag, WR_ERR_DOMAIN, -1, "shell energy is not finite (%g)", em + eb);
    if (Em) *Em = em;
    if (Eb) *Eb = eb;
    return WR_OK;
}

WRDEF wr_status wr_shell_energy(const wr_shell *s, const double *x, double *E, double *grad, wr_diag *diag) {
    double em = 0.0, eb = 0.0;
    wr_status st = wr__shell_eval(s, x, &em, &eb, grad, diag);
    if (st == WR_OK && E) *E = em + eb;
    return st;
}

WRDEF wr_status wr_shell_energy_parts(const wr_shell *s, const double *x, double *E_membrane, double *E_bending,
                                      wr_diag *diag) {
    return wr__shell_eval(s, x, E_membrane, E_bending, NULL, diag);
}

WRDEF wr_status wr_shell_face_block(const wr_shell *s, int32_t f, const double *x, int32_t *n, int32_t verts[6],
                                    double Ke[324]) {
    int32_t vs[6], mask, idx[6], k = 0, a, b, i, j;
    double x18[18], H18[324], H9[81];
    int bend = s->bending == WR_BENDING_MIDEDGE || s->bending == WR_BENDING_DIHEDRAL;
    if (s->loop_start && s->loop_start[f + 1] > s->loop_start[f]) return WR_ERR_UNSUPPORTED; /* its stencil is larger */
    wr__shell_gather(s, f, x, vs, &mask, x18);
    if (bend) {
        wr_status es = s->bending == WR_BENDING_MIDEDGE
                           ? wr_shell_midedge_element(x18, mask, s->qbend + 9 * f, s->bbar ? s->bbar + 3 * f : NULL, NULL,
                                                      NULL, H18, NULL)
                           : wr_shell_dihedral_element(x18, mask, s->qbend + 9 * f, s->bbar ? s->bbar + 3 * f : NULL, NULL,
                                                       NULL, H18, NULL);
        if (es != WR_OK) return WR_ERR_GEOMETRY;
    } else {
        memset(H18, 0, sizeof H18);
    }
    if (s->membrane != WR_MEMBRANE_NONE) {
        wr_shell_membrane_element(s, f, x18, NULL, H9);
        for (a = 0; a < 9; ++a)
            for (b = 0; b < 9; ++b) H18[a * 18 + b] += H9[a * 9 + b];
    }
    /* without mid-edge or dihedral bending the face block only couples its own 3 corners */
    for (a = 0; a < 6; ++a)
        if (vs[a] >= 0 && (a < 3 || bend)) idx[k++] = a;
    for (a = 0; a < k; ++a)
        for (b = 0; b < k; ++b)
            for (i = 0; i < 3; ++i)
                for (j = 0; j < 3; ++j) Ke[(3 * a + i) * 3 * k + 3 * b + j] = H18[(3 * idx[a] + i) * 18 + 3 * idx[b] + j];
    for (a = 0; a < k; ++a) verts[a] = vs[idx[a]];
    *n = k;
    return WR_OK;
}

WRDEF wr_status wr_shell_hessian_elements(const wr_shell *s, const double *x, int32_t project_spd,
                                          const wr_hess_sink *sink, wr_diag *diag) {
    return wr_shell_hessian_elements_part(s, x, project_spd, WR_SHELL_HESS_ALL, sink, diag);
}

WRDEF wr_status wr_shell_hessian_elements_part(const wr_shell *s, const double *x, int32_t project_spd, int32_t parts,
                                               const wr_hess_sink *sink, wr_diag *diag) {
    int32_t f, st;
    if (!s || !x || !sink || !sink->add || !s->faces)
        return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "shell Hessian: NULL shell, x or sink");
    if (parts & ~WR_SHELL_HESS_ALL)
        return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "shell Hessian: unknown parts flags 0x%x", (unsigned)parts);
    for (f = 0; f < 3 * s->nv; ++f)
        if (!wr__shell_finite(x[f]))
            return wr_fail(diag, WR_ERR_DOMAIN, f / 3, "shell Hessian: vertex %d has a non-finite coordinate", (int)(f / 3));
    if ((parts & WR_SHELL_HESS_FACES) &&
        (s->membrane != WR_MEMBRANE_NONE || s->bending == WR_BENDING_MIDEDGE || s->bending == WR_BENDING_DIHEDRAL))
        for (f = 0; f < s->nf; ++f) {
            int32_t verts[6], n = 0;
            double Ke[324];
            wr_status rs;
            if (s->loop_start && s->loop_start[f + 1] > s->loop_start[f]) {
                int32_t nl = s->loop_start[f + 1] - s->loop_start[f];
                double *KL = (double *)wr_alloc_array((size_t)9 * (size_t)nl * (size_t)nl, sizeof(double));
                if (!KL) return wr_fail(diag, WR_ERR_NOMEM, f, "shell Hessian: out of memory");
                wr__shell_loop_block(s, f, x, project_spd == 0, KL);
                rs = sink->add(sink->user, nl, s->loop_vert + s->loop_start[f], KL);
                wr_free(KL);
                if (rs != WR_OK) return wr_fail(diag, rs, f, "shell Hessian: sink rejected face %d", (int)f);
                continue;
            }
            if (wr_shell_face_block(s, f, x, &n, verts, Ke) != WR_OK)
                return wr_fail(diag, WR_ERR_GEOMETRY, f, "shell Hessian: face %d has an undefined normal", (int)f);
            if (project_spd == 1) wr_dense_project_spd(3 * n, Ke, 0.0);
            rs = sink->add(sink->user, n, verts, Ke);
            if (rs != WR_OK) return wr_fail(diag, rs, f, "shell Hessian: sink rejected face %d", (int)f);
        }
    if ((parts & WR_SHELL_HESS_QUADRATIC) && s->bending == WR_BENDING_QUADRATIC) {
        double *Ke = NULL;
        int32_t cap = 0;
        for (st = 0; st < s->n_qb; ++st) {
            int32_t j0 = s->qb_start[st], n = s->qb_start[st + 1] - j0, a, b, i;
            wr_status rs;
            if (n > cap) {
                double *nk = (double *)wr_realloc_array(Ke, (size_t)9 * (size_t)n * (size_t)n, sizeof(double));
                if (!nk) {
                    wr_free(Ke);
                    return wr_fail(diag, WR_ERR_NOMEM, st, "shell Hessian: out of memory");
                }
                Ke = nk;
                cap = n;
            }
            memset(Ke, 0, sizeof(double) * 9 * (size_t)n * (size_t)n);
            for (a = 0; a < n; ++a)
                for (b = 0; b < n; ++b)
                    for (i = 0; i < 3; ++i)
                        Ke[(3 * a + i) * 3 * n + 3 * b + i] = s->qb_coef[st] * s->qb_w[j0 + a] * s->qb_w[j0 + b];
            rs = sink->add(sink->user, n, s->qb_vert + j0, Ke);
            if (rs != WR_OK) {
                wr_free(Ke);
                return wr_fail(diag, rs, st, "shell Hessian: sink rejected bending stencil %d", (int)st);
            }
        }
        wr_free(Ke);
    }
    return WR_OK;
}

WRDEF void wr_shell_vertex_masses(const wr_shell *s, double *mass) {
    int32_t f, k;
    memset(mass, 0, sizeof(double) * (size_t)s->nv);
    for (f = 0; f < s->nf; ++f)
        for (k = 0; k < 3; ++k) mass[s->faces[3 * f + k]] += s->density * s->thickness * s->area[f] / 3.0;
}

#ifdef __cplusplus
}
#endif
#endif /* WRINKLE_SHELL_IMPLEMENTATION_DONE */
#endif /* WRINKLE_IMPLEMENTATION */
