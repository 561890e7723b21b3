/* wrinkle/subdiv.h — Loop subdivision limit surfaces: the regular patch's quartic box-spline basis
 * with its first and second derivatives, and per face of a wr_mesh the weights that give the limit
 * surface's position and derivatives at the face's centre as linear combinations of mesh vertices.
 * wrinkle v0.1.0 — MIT licence (see LICENSE). Needs only libc and libm (and core.h, mesh.h).
 *
 * Why: linear triangles cannot represent a wrinkle whose crests are not aligned with the mesh edges
 * without a spurious membrane strain (issue 15; docs/design-higher-order-shell.md). Loop
 * subdivision thin shells (Cirak, Ortiz & Schröder 2000, "Subdivision surfaces: a new paradigm for
 * thin-shell finite-element analysis", IJNME 47) take the surface to be the limit of Loop
 * subdivision of the mesh: C² away from extraordinary vertices, with membrane strain and curvature
 * from the same smooth map. This header is that map's geometry; the shell energy on it is the next
 * step (shell.h) and is not here.
 *
 * The two facts used (Loop 1987; Stam 1998, "Evaluation of Loop subdivision surfaces"):
 *   - A regular face (all three corners of valence 6) is a quartic box-spline patch over the 12
 *     vertices of its corners' 1-rings: x(v, w) = Σ_i N_i(u, v, w) x_i with u = 1 − v − w and the
 *     12 quartic polynomials N_i of Stam's appendix (ON THE REGULAR PATCH gives the layout).
 *   - One Loop step splits a face into four; the central child's three corners are new edge points,
 *     which always have valence 6, so the central child is a regular patch whatever the valences of
 *     the parent's corners. Its 12 control points are Loop's edge and vertex rules applied to the
 *     parent's corners' 1-rings, and the face's centre is the central child's centre. So the limit
 *     surface and its derivatives at the centre of ANY face with interior corners are fixed linear
 *     combinations of the corners' 1-ring vertices — the one-point quadrature of Cirak et al.
 *     without Stam's eigen-analysis.
 *
 * API
 *   wr_subdiv_loop_basis(v, w, N, dN, d2N)          regular-patch basis at (v, w): N[12], ∂/∂v, ∂/∂w
 *                                                   (dN[2i], dN[2i+1]) and ∂vv, ∂vw, ∂ww (d2N[3i..])
 *   wr_subdiv_loop_stencil(m, f, &n, verts, W, diag)  face f's stencil: n vertices (its corners first),
 *                                                   W (6 × n row-major: position, x_v, x_w, x_vv, x_vw,
 *                                                   x_ww weights)
 *   wr_subdiv_loop_stencil_ghost(m, f, &n, verts, W, diag)  the same, boundary corners completed by
 *                                                   ghost vertices (ON GHOST VERTICES)
 *
 * EXAMPLE
 *     wr_mesh m;  wr_diag d;  int32_t n, verts[WR_SUBDIV_MAX_STENCIL], i, k, f;  double x[6][3];
 *     double W[6 * WR_SUBDIV_MAX_STENCIL];
 *     if (wr_mesh_disk(&m, 1.0, 4, &d) != WR_OK) { puts(d.message); return 1; }
 *     f = m.vf[m.vf_start[0]];                    // a face at the centre: its corners are interior
 *     if (wr_subdiv_loop_stencil(&m, f, &n, verts, W, &d) != WR_OK) { puts(d.message); return 1; }
 *     for (k = 0; k < 6; ++k)                     // limit position and derivatives at the face centre
 *         for (i = 0; i < 3; ++i) {
 *             int32_t j;
 *             x[k][i] = 0.0;
 *             for (j = 0; j < n; ++j) x[k][i] += W[k * n + j] * m.pos[3 * verts[j] + i];
 *         }
 *     printf("%d stencil vertices, centre (%.4f, %.4f, %.4f)\n", (int)n, x[0][0], x[0][1], x[0][2]);
 *     wr_mesh_free(&m);
 *
 * ON THE REGULAR PATCH
 *   Basis i (0-based here; Stam numbers them 1..12) sits at lattice point L[i] of the triangular
 *   lattice with the patch's corners u, v, w at (0, 0), (1, 0), (0, 1) (Cartesian: i·e1 + j·e2, e1 =
 *   (1, 0), e2 = (½, √3/2)): L = (0,−1) (−1,0) (1,−1) (0,0) (−1,1) (2,−1) (1,0) (0,1) (−1,2) (2,0)
 *   (1,1) (0,2). So vertex 3 is corner u, 6 corner v, 7 corner w. Checked in tests/test_subdiv.c:
 *   partition of unity, exact reproduction of linear functions on the lattice, exact first and
 *   second derivatives of sampled quadratics (the box spline reproduces them up to a constant).
 *
 * ON THE STENCIL
 *   Parent face (A, B, C), counter-clockwise; D, E, F the apexes across AB, BC, CA. Loop's rules:
 *   edge point e_XY = 3/8 (X + Y) + 1/8 (the two apexes of edge XY); vertex point X' = (1 − nβ) X +
 *   β Σ ring(X), β(n) = (5/8 − (3/8 + cos(2π/n)/4)²)/n (Loop's original weights, the ones the limit
 *   analysis of Stam and Cirak et al. is written for). The central child (e_BC, e_CA, e_AB) is the
 *   parent turned by 180°, so its corners u, v, w are e_BC, e_CA, e_AB, and the other nine lattice
 *   points are e_CE, e_BE, C', B', e_CF, e_BD, e_AF, A', e_AD. Derivatives are with respect to the
 *   central child's own parameters (v, w): against the parent's they are −½ (first) and ¼ (second)
 *   of the parent patch's, which does not matter to a shell energy that measures strain against the
 *   rest configuration through the same map; the area weight is 4 × ½ × √det(a_rest) (the child is
 *   a quarter of the parent). wr_subdiv_loop_stencil refuses faces with a corner on the boundary
 *   (WR_ERR_TOPOLOGY, item = face); wr_subdiv_loop_stencil_ghost gives them ghost vertices.
 *
 * ON GHOST VERTICES (wr_subdiv_loop_stencil_ghost)
 *   Cirak & Ortiz 2001 (and Cirak, Ortiz & Schröder 2000 for boundary conditions) complete the
 *   patches of boundary faces with a layer of ghost vertices outside the boundary placed by linear
 *   extrapolation from the mesh, so the energy depends on mesh vertices only. The construction here
 *   is our reading of that idea, not a transcription of their rules: for a boundary vertex v whose
 *   faces form one open fan p = n_0, …, n_k = q (counter-clockwise, k faces): across each of its two
 *   boundary edges a ghost, the parallelogram completion of that edge's face — v + q − n_(k−1)
 *   across (v, q), v + p − n_1 across (v, p) — and one ghost face (v, ghost_q, ghost_p) closing the
 *   ring, which then has valence k + 3 (6 at a straight boundary of a valence-6 lattice, whose
 *   boundary vertices have k = 3). Loop's interior rules run on the closed ring and each ghost's
 *   weight is folded onto its three mesh vertices. The ghost across a boundary edge is the same from
 *   both its ends (the edge has one face), so the two corners of a boundary edge see one point there;
 *   the ghost faces are each ring's own. The completion is affine (weights 1, 1, −1), so a patch of
 *   an affine image of a planar mesh is the affine image of its patch: uniform strain is exact on
 *   boundary faces too (tests/test_subdiv.c). It does not reproduce quadratics: the ghost across an
 *   edge continues the face inside in its own plane (ghost − m = m − apex, m the edge's midpoint), a
 *   zero second difference across the edge, so the limit surface's curvature across a boundary edge
 *   is pulled towards zero — the free edge's natural condition (no bending moment), which is what an
 *   edge with no held vertices gets. A clamped edge holds its boundary vertices and the
 *   vertices of the faces along it (the ghosts are then fixed, so the tangent plane along the edge
 *   is prescribed); holding the boundary row alone is a hinge (simply supported). Corner vertices of
 *   one or two faces get the same construction (valence 4 or 5).
 *
 * ON UNITS AND OWNERSHIP
 *   Pure functions; W and verts are caller-owned arrays of WR_SUBDIV_MAX_STENCIL entries (6 × that
 *   for W). The weights are dimensionless; applied to positions in metres they give metres.
 */
#ifndef WRINKLE_SUBDIV_H
#define WRINKLE_SUBDIV_H

#include "core.h"
#include "mesh.h"

#ifdef __cplusplus
extern "C" {
#endif

/* The largest stencil: three 1-rings; a face whose corners' valences sum past this is refused
 * (WR_ERR_TOPOLOGY) — Delaunay meshes have valences 4..9, so 3 + 27 is ample. */
#define WR_SUBDIV_MAX_STENCIL 32
/* Loop's rules need a corner's full 1-ring; a ring longer than this is refused. */
#define WR_SUBDIV_MAX_VALENCE 16

/* The 12 box-spline basis functions of a regular Loop patch at (v, w), u = 1 − v − w (ON THE
 * REGULAR PATCH); dN (24: ∂v, ∂w per function) and d2N (36: ∂vv, ∂vw, ∂ww) may be NULL. */
WRDEF void wr_subdiv_loop_basis(double v, double w, double N[12], double *dN, double *d2N);
/* Face f's limit-surface stencil at its centre (ON THE STENCIL): *n vertices in verts and the 6 × n
 * weights W (row-major: position, ∂v, ∂w, ∂vv, ∂vw, ∂ww). WR_ERR_INVALID_ARG for a NULL argument or f
 * out of range; WR_ERR_TOPOLOGY (item = f) when a corner is on the boundary or the stencil exceeds
 * WR_SUBDIV_MAX_STENCIL / WR_SUBDIV_MAX_VALENCE. */
WRDEF wr_status wr_subdiv_loop_stencil(const wr_mesh *m, int32_t f, int32_t *n, int32_t *verts, double *W,
                                       wr_diag *diag);
/* The same where a corner is on the boundary: its 1-ring closed by ghost vertices folded onto mesh
 * vertices (ON GHOST VERTICES); interior faces get wr_subdiv_loop_stencil's stencil. WR_ERR_TOPOLOGY
 * (item = f) when a corner's faces are not one fan or a closed ring exceeds WR_SUBDIV_MAX_VALENCE. */
WRDEF wr_status wr_subdiv_loop_stencil_ghost(const wr_mesh *m, int32_t f, int32_t *n, int32_t *verts, double *W,
                                             wr_diag *diag);

#ifdef __cplusplus
}
#endif
#endif /* WRINKLE_SUBDIV_H */

#ifdef WRINKLE_IMPLEMENTATION
#ifndef WRINKLE_SUBDIV_IMPLEMENTATION_DONE
#define WRINKLE_SUBDIV_IMPLEMENTATION_DONE
#include <math.h>
#include <string.h>

#ifdef __cplusplus
extern "C" {
#endif

/* Stam 1998, appendix: 12 × N_i = Σ c · u^a v^b w^c over the 15 quartic monomials, in the order of
 * wr__subdiv_mono (a, b, c). */
static const signed char wr__subdiv_mono[15][3] = {{4, 0, 0}, {3, 1, 0}, {3, 0, 1}, {2, 2, 0}, {2, 1, 1},
                                                   {2, 0, 2}, {1, 3, 0}, {1, 2, 1}, {1, 1, 2}, {1, 0, 3},
                                                   {0, 4, 0}, {0, 3, 1}, {0, 2, 2}, {0, 1, 3}, {0, 0, 4}};
static const signed char wr__subdiv_coef[12][15] = {
    {1, 2, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0},         {1, 0, 2, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0},
    {1, 6, 2, 12, 6, 0, 6, 6, 0, 0, 1, 2, 0, 0, 0},        {6, 24, 24, 24, 60, 24, 8, 36, 36, 8, 1, 6, 12, 6, 1},
    {1, 2, 6, 0, 6, 12, 0, 0, 6, 6, 0, 0, 0, 2, 1},        {0, 0, 0, 0, 0, 0, 2, 0, 0, 0, 1, 0, 0, 0, 0},
    {1, 8, 6, 24, 36, 12, 24, 60, 36, 6, 6, 24, 24, 8, 1}, {1, 6, 8, 12, 36, 24, 6, 36, 60, 24, 1, 8, 24, 24, 6},
    {0, 0, 0, 0, 0, 0, 0, 0, 0, 2, 0, 0, 0, 0, 1},         {0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 1, 2, 0, 0, 0},
    {0, 0, 0, 0, 0, 0, 2, 6, 6, 2, 1, 6, 12, 6, 1},        {0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 2, 1}};

/* p^k and its first two derivatives k p^(k−1), k(k−1) p^(k−2) (zero where the power is negative) */
static void wr__subdiv_pow(double p, int k, double out[3]) {
    int i;
    out[0] = 1.0;
    out[1] = 0.0;
    out[2] = 0.0;
    for (i = 0; i < k; ++i) {
        out[2] = out[2] * p + 2.0 * out[1];
        out[1] = out[1] * p + out[0];
        out[0] *= p;
    }
}

WRDEF void wr_subdiv_loop_basis(double v, double w, double N[12], double *dN, double *d2N) {
    double u = 1.0 - v - w, pu[5][3], pv[5][3], pw[5][3];
    int i, k;
    for (k = 0; k <= 4; ++k) {
        wr__subdiv_pow(u, k, pu[k]);
        wr__subdiv_pow(v, k, pv[k]);
        wr__subdiv_pow(w, k, pw[k]);
    }
    for (i = 0; i < 12; ++i) {
        /* g = Σ c u^a v^b w^c; d/dv = ∂v − ∂u, d/dw = ∂w − ∂u (u = 1 − v − w) */
        double g = 0, gu = 0, gv = 0, gw = 0, guu = 0, gvv = 0, gww = 0, guv = 0, guw = 0, gvw = 0;
        for (k = 0; k < 15; ++k) {
            double c = wr__subdiv_coef[i][k] / 12.0;
            const double *A = pu[wr__subdiv_mono[k][0]], *B = pv[wr__subdiv_mono[k][1]], *C = pw[wr__subdiv_mono[k][2]];
            if (c == 0.0) continue;
            g += c * A[0] * B[0] * C[0];
            gu += c * A[1] * B[0] * C[0];
            gv += c * A[0] * B[1] * C[0];
            gw += c * A[0] * B[0] * C[1];
            guu += c * A[2] * B[0] * C[0];
            gvv += c * A[0] * B[2] * C[0];
            gww += c * A[0] * B[0] * C[2];
            guv += c * A[1] * B[1] * C[0];
            guw += c * A[1] * B[0] * C[1];
            gvw += c * A[0] * B[1] * C[1];
        }
        N[i] = g;
        if (dN) {
            dN[2 * i] = gv - gu;
            dN[2 * i + 1] = gw - gu;
        }
        if (d2N) {
            d2N[3 * i] = gvv - 2.0 * guv + guu;
            d2N[3 * i + 1] = gvw - guv - guw + guu;
            d2N[3 * i + 2] = gww - 2.0 * guw + guu;
        }
    }
}

/* two ghosts per boundary corner of a face */
#define WR__SUBDIV_MAX_GHOSTS 6

/* A sparse row: weights over mesh vertices, merged by vertex. */
typedef struct wr__subdiv_row {
    int32_t n, v[WR_SUBDIV_MAX_STENCIL];
    double w[WR_SUBDIV_MAX_STENCIL];
} wr__subdiv_row;

static int wr__subdiv_add(wr__subdiv_row *r, int32_t v, double w) {
    int32_t i;
    for (i = 0; i < r->n; ++i)
        if (r->v[i] == v) {
            r->w[i] += w;
            return 1;
        }
    if (r->n == WR_SUBDIV_MAX_STENCIL) return 0;
    r->v[r->n] = v;
    r->w[r->n++] = w;
    return 1;
}

/* Ghost vertices (ON GHOST VERTICES): ring entries >= 0 are mesh vertices, entry −1 − k is ghost k,
 * the point x_a + x_b − x_c of the edge (a, b) with apex c. */
typedef struct wr__subdiv_ghosts {
    int32_t n, abc[3 * WR__SUBDIV_MAX_GHOSTS];
} wr__subdiv_ghosts;

/* adds w × (entry id) to r, a ghost as its three mesh vertices */
static int wr__subdiv_add_id(wr__subdiv_row *r, const wr__subdiv_ghosts *G, int32_t id, double w) {
    const int32_t *t;
    if (id >= 0) return wr__subdiv_add(r, id, w);
    t = G->abc + 3 * (-1 - id);
    return wr__subdiv_add(r, t[0], w) & wr__subdiv_add(r, t[1], w) & wr__subdiv_add(r, t[2], -w);
}

/* The corner of face g that is vertex v, or -1. */
static int wr__subdiv_corner(const wr_mesh *m, int32_t g, int32_t v) {
    int k;
    for (k = 0; k < 3; ++k)
        if (m->faces[3 * g + k] == v) return k;
    return -1;
}

/* Vertex v's 1-ring in counter-clockwise order, starting at `first` (a neighbour of v): each incident
 * face (v, a, b) counter-clockwise maps a → b. Returns the valence, or -1 when v is on the boundary
 * (some a has no successor) or the ring is longer than WR_SUBDIV_MAX_VALENCE. */
static int32_t wr__subdiv_ring(const wr_mesh *m, int32_t v, int32_t first, int32_t ring[WR_SUBDIV_MAX_VALENCE]) {
    int32_t n = 0, cur = first, k, nf = m->vf_start[v + 1] - m->vf_start[v];
    if (nf > WR_SUBDIV_MAX_VALENCE) return -1;
    do {
        int32_t next = -1;
        for (k = m->vf_start[v]; k < m->vf_start[v + 1]; ++k) {
            int32_t g = m->vf[k];
            int c = wr__subdiv_corner(m, g, v);
            if (m->faces[3 * g + (c + 1) % 3] == cur) next = m->faces[3 * g + (c + 2) % 3];
        }
        if (next < 0 || n == WR_SUBDIV_MAX_VALENCE) return -1;
        ring[n++] = cur;
        cur = next;
    } while (cur != first);
    return n == nf ? n : -1; /* a closed fan has as many neighbours as faces */
}

/* Vertex v's ring closed by ghosts where v is on the boundary (ON GHOST VERTICES): the open fan
 * p = n_0 … n_k = q (k faces, counter-clockwise), then the ghosts across (v, q) and (v, p), so the
 * ring is n_0 … n_k, v + q − n_(k−1), v + p − n_1; rotated to start at `first` (a mesh neighbour).
 * Returns the valence, or -1 (v's faces are not one fan, or the ring is longer than the maximum). */
static int32_t wr__subdiv_ring_ghost(const wr_mesh *m, int32_t v, int32_t first, int32_t ring[WR_SUBDIV_MAX_VALENCE],
                                     wr__subdiv_ghosts *G) {
    int32_t fan[WR_SUBDIV_MAX_VALENCE], n = 0, k, j, p = -1, nf = m->vf_start[v + 1] - m->vf_start[v], start;
    if ((n = wr__subdiv_ring(m, v, first, ring)) > 0) return n;
    if (nf + 3 > WR_SUBDIV_MAX_VALENCE || nf < 1 || G->n + 2 > WR__SUBDIV_MAX_GHOSTS) return -1;
    for (k = m->vf_start[v]; k < m->vf_start[v + 1] && p < 0; ++k) { /* p: a neighbour with no predecessor */
        int32_t g = m->vf[k], a = m->faces[3 * g + (wr__subdiv_corner(m, g, v) + 1) % 3], has_pred = 0;
        for (j = m->vf_start[v]; j < m->vf_start[v + 1]; ++j) {
            int32_t h = m->vf[j];
            if (m->faces[3 * h + (wr__subdiv_corner(m, h, v) + 2) % 3] == a) has_pred = 1;
        }
        if (!has_pred) p = a;
    }
    if (p < 0) return -1;
    fan[0] = p;
    for (n = 1; n <= nf; ++n) { /* walk face by face: (v, a, b) maps a → b */
        int32_t next = -1;
        for (k = m->vf_start[v]; k < m->vf_start[v + 1]; ++k) {
            int32_t g = m->vf[k];
            int c = wr__subdiv_corner(m, g, v);
            if (m->faces[3 * g + (c + 1) % 3] == fan[n - 1]) next = m->faces[3 * g + (c + 2) % 3];
        }
        if (next < 0) break;
        fan[n] = next;
    }
    if (n != nf + 1) return -1; /* more than one fan (a bow tie), or a closed ring met twice */
    G->abc[3 * G->n] = v, G->abc[3 * G->n + 1] = fan[nf], G->abc[3 * G->n + 2] = fan[nf - 1];
    G->abc[3 * G->n + 3] = v, G->abc[3 * G->n + 4] = fan[0], G->abc[3 * G->n + 5] = fan[1];
    fan[nf + 1] = -1 - G->n;
    fan[nf + 2] = -2 - G->n;
    G->n += 2;
    n = nf + 3;
    for (start = 0; start < n && fan[start] != first; ++start) {}
    if (start == n) return -1;
    for (k = 0; k < n; ++k) ring[k] = fan[(start + k) % n];
    return n;
}

/* Loop's vertex rule for v with its ring. */
static int wr__subdiv_vertex_point(wr__subdiv_row *r, const wr__subdiv_ghosts *G, int32_t v, const int32_t *ring,
                                   int32_t n) {
    double c = 0.375 + 0.25 * cos(2.0 * 3.14159265358979323846 / (double)n), beta = (0.625 - c * c) / (double)n;
    int32_t i;
    int ok = wr__subdiv_add(r, v, 1.0 - (double)n * beta);
    for (i = 0; i < n; ++i) ok &= wr__subdiv_add_id(r, G, ring[i], beta);
    return ok;
}

/* Loop's edge rule for edge (x, y), y = ring_x[i]: the apexes are ring_x[i ± 1]. */
static int wr__subdiv_edge_point(wr__subdiv_row *r, const wr__subdiv_ghosts *G, int32_t x, const int32_t *ring_x,
                                 int32_t n, int32_t i) {
    return wr__subdiv_add(r, x, 0.375) & wr__subdiv_add_id(r, G, ring_x[i], 0.375) &
           wr__subdiv_add_id(r, G, ring_x[(i + 1) % n], 0.125) & wr__subdiv_add_id(r, G, ring_x[(i + n - 1) % n], 0.125);
}

/* Position of y in x's ring, or -1. */
static int32_t wr__subdiv_find(const int32_t *ring, int32_t n, int32_t y) {
    int32_t i;
    for (i = 0; i < n; ++i)
        if (ring[i] == y) return i;
    return -1;
}

/* Face f's stencil; ghost != 0 closes boundary corners' rings with ghost vertices (ON GHOST VERTICES) */
static wr_status wr__subdiv_stencil(const wr_mesh *m, int32_t f, int ghost, int32_t *n, int32_t *verts, double *W,
                                    wr_diag *diag) {
    int32_t A, B, C, rA[WR_SUBDIV_MAX_VALENCE], rB[WR_SUBDIV_MAX_VALENCE], rC[WR_SUBDIV_MAX_VALENCE], nA, nB, nC, i, j, k;
    wr__subdiv_row cp[12], out;
    wr__subdiv_ghosts G;
    double N[12], dN[24], d2N[36];
    int ok = 1;
    if (!m || !n || !verts || !W) return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "subdiv: NULL mesh or output");
    if (f < 0 || f >= m->nf) return wr_fail(diag, WR_ERR_INVALID_ARG, f, "subdiv: face %d out of range", (int)f);
    A = m->faces[3 * f];
    B = m->faces[3 * f + 1];
    C = m->faces[3 * f + 2];
    G.n = 0;
    nA = ghost ? wr__subdiv_ring_ghost(m, A, B, rA, &G) : wr__subdiv_ring(m, A, B, rA);
    nB = ghost ? wr__subdiv_ring_ghost(m, B, C, rB, &G) : wr__subdiv_ring(m, B, C, rB);
    nC = ghost ? wr__subdiv_ring_ghost(m, C, A, rC, &G) : wr__subdiv_ring(m, C, A, rC);
    if (nA < 0 || nB < 0 || nC < 0)
        return wr_fail(diag, WR_ERR_TOPOLOGY, f,
                       ghost ? "subdiv: face %d has a corner whose faces are not one fan, or of valence > %d (ghosts "
                               "included)"
                             : "subdiv: face %d has a corner on the boundary (or of valence > %d); its limit patch needs "
                               "ghost vertices",
                       (int)f, WR_SUBDIV_MAX_VALENCE);
    memset(cp, 0, sizeof cp);
    /* the 12 control points of the central child (ON THE STENCIL), in lattice order. The rings run
     * counter-clockwise from the face's next corner: rA = (B, C, F, ..., D), rB = (C, A, D, ..., E),
     * rC = (A, B, E, ..., F), so the edge to ring[i] has the apexes ring[i ± 1]. */
    ok &= wr__subdiv_edge_point(&cp[0], &G, C, rC, nC, 2);      /* e_CE */
    ok &= wr__subdiv_edge_point(&cp[1], &G, B, rB, nB, nB - 1); /* e_BE */
    ok &= wr__subdiv_vertex_point(&cp[2], &G, C, rC, nC);       /* C' */
    ok &= wr__subdiv_edge_point(&cp[3], &G, B, rB, nB, 0);      /* e_BC (corner u) */
    ok &= wr__subdiv_vertex_point(&cp[4], &G, B, rB, nB);       /* B' */
    ok &= wr__subdiv_edge_point(&cp[5], &G, C, rC, nC, nC - 1); /* e_CF */
    ok &= wr__subdiv_edge_point(&cp[6], &G, C, rC, nC, 0);      /* e_CA (corner v) */
    ok &= wr__subdiv_edge_point(&cp[7], &G, A, rA, nA, 0);      /* e_AB (corner w) */
    ok &= wr__subdiv_edge_point(&cp[8], &G, B, rB, nB, 2);      /* e_BD */
    ok &= wr__subdiv_edge_point(&cp[9], &G, A, rA, nA, 2);      /* e_AF */
    ok &= wr__subdiv_vertex_point(&cp[10], &G, A, rA, nA);      /* A' */
    ok &= wr__subdiv_edge_point(&cp[11], &G, A, rA, nA, nA - 1); /* e_AD */
    /* the stencil: the face's corners first (callers that fold per-face terms into the block find
     * them there), then every other vertex a control point uses, in first-use order */
    out.n = 0;
    ok &= wr__subdiv_add(&out, A, 0.0) & wr__subdiv_add(&out, B, 0.0) & wr__subdiv_add(&out, C, 0.0);
    for (i = 0; i < 12 && ok; ++i)
        for (j = 0; j < cp[i].n && ok; ++j) ok &= wr__subdiv_add(&out, cp[i].v[j], 0.0);
    if (!ok)
        return wr_fail(diag, WR_ERR_TOPOLOGY, f, "subdiv: face %d's stencil exceeds %d vertices", (int)f,
                       WR_SUBDIV_MAX_STENCIL);
    wr_subdiv_loop_basis(1.0 / 3.0, 1.0 / 3.0, N, dN, d2N);
    *n = out.n;
    memcpy(verts, out.v, sizeof(int32_t) * (size_t)out.n);
    memset(W, 0, sizeof(double) * 6 * (size_t)out.n);
    for (i = 0; i < 12; ++i) {
        double b[6];
        b[0] = N[i];
        b[1] = dN[2 * i];
        b[2] = dN[2 * i + 1];
        b[3] = d2N[3 * i];
        b[4] = d2N[3 * i + 1];
        b[5] = d2N[3 * i + 2];
        for (j = 0; j < cp[i].n; ++j) {
            int32_t col = wr__subdiv_find(out.v, out.n, cp[i].v[j]);
            for (k = 0; k < 6; ++k) W[k * out.n + col] += b[k] * cp[i].w[j];
        }
    }
    return WR_OK;
}

WRDEF wr_status wr_subdiv_loop_stencil(const wr_mesh *m, int32_t f, int32_t *n, int32_t *verts, double *W,
                                       wr_diag *diag) {
    return wr__subdiv_stencil(m, f, 0, n, verts, W, diag);
}

WRDEF wr_status wr_subdiv_loop_stencil_ghost(const wr_mesh *m, int32_t f, int32_t *n, int32_t *verts, double *W,
                                             wr_diag *diag) {
    return wr__subdiv_stencil(m, f, 1, n, verts, W, diag);
}

#ifdef __cplusplus
}
#endif
#endif /* WRINKLE_SUBDIV_IMPLEMENTATION_DONE */
#endif /* WRINKLE_IMPLEMENTATION */
