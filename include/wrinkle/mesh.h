/* wrinkle/mesh.h — triangle meshes with a 2D rest (pattern) domain and 3D positions: oriented edges,
 * face→edge signs, edge→face and vertex→face adjacency, ordered boundary loops.
 * wrinkle v0.1.0 — MIT licence (see LICENSE). Needs only libc and libm (and core.h).
 *
 * Both papers work on this one type: Style3D ("Physics-inspired Estimation of Optimal Cloth Mesh
 * Resolution", Sec. 4) meshes 2D sewing-pattern panels and measures edge lengths against a sizing
 * field; TFW ("Fine Wrinkling on Coarsely Meshed Thin Shells", Sec. 4–5) stores the wrinkle phase
 * as a one-form ω on oriented edges and needs its discrete exterior derivative dω per face, which
 * is what face_edges / face_edge_sign give directly.
 *
 * API (every function that fills a wr_mesh — create, copy, rectangle, disk, cylinder_flat, parse_obj,
 *      read_obj — pairs with wr_mesh_free; on failure the mesh is left zeroed)
 *   wr_mesh_create(m, nv, pos3, rest2, nf, faces, diag)   copy inputs, validate, build topology
 *   wr_mesh_free(m)                                       free and zero (safe on a zeroed mesh)
 *   wr_mesh_copy(dst, src, diag)                          deep copy
 *   wr_mesh_face_rest(m, f, uv[6])                        rest-domain corners of face f
 *   wr_mesh_rectangle(m, w, h, nx, ny, diag)              regular grid on [0,w]×[0,h], alternating diagonals
 *   wr_mesh_disk(m, R, n_rings, diag)                     hexagonal-ring disk, near-equilateral faces
 *   wr_mesh_cylinder_flat(m, R, height, nu, nh, diag)     closed tube with an unrolled pattern (corner_rest)
 *   wr_mesh_set_corner_rest / wr_mesh_set_face_panel      attach optional per-face data (copied)
 *   wr_mesh_edge_lengths(m, use_rest, out[ne])            rest or 3D edge lengths
 *   wr_mesh_face_areas(m, use_rest, out[nf])              signed rest areas or 3D areas
 *   wr_mesh_face_normals(m, out[3nf]) / _vertex_normals(m, out[3nv])   unit 3D normals
 *   wr_mesh_quality(m, use_rest, &stats)                  angles, edge lengths, inverted/zero-area faces, χ
 *   wr_mesh_ratio_histogram(ratio, n, nbins, lo, hi, counts)   e.g. edge length / target length
 *   wr_mesh_parse_obj(m, text, len, diag) / wr_mesh_read_obj(m, path, diag)   Wavefront OBJ in
 *   wr_mesh_read_obj_groups(m, path, &groups, diag)       the same, with the g/o names by panel id
 *                                                         (wr_obj_groups_free; _parse_obj_groups for text)
 *   wr_mesh_write_obj(m, path, desc, diag)                OBJ out (vt = rest, g = panels), atomic
 *   wr_mesh_write_ply(m, path, nprops, names, values, diag)   ASCII PLY with per-vertex doubles, atomic
 *   wr_mesh_write_vtk(m, path, np, pnames, pvals, nc, cnames, cvals, diag)   legacy VTK POLYDATA, atomic
 *   wr_mesh_weld(out, in, n_pairs, pairs, vmap, diag)     sew: merge vertex pairs, keep each face's rest
 *   wr_mesh_pillow(out, panel, lift, diag)                two copies of a flat panel sewn along the boundary
 *
 * EXAMPLE
 *     wr_mesh m;  wr_diag d;  double *omega, worst = 0.0;  int32_t e, f;  int k;
 *     if (wr_mesh_rectangle(&m, 1.0, 0.5, 20, 10, &d) != WR_OK) { puts(d.message); return 1; }
 *     omega = (double *)wr_alloc_array((size_t)m.ne, sizeof(double));
 *     for (e = 0; e < m.ne; ++e)                       // ω = d0 u for u(x, y) = x: an exact one-form
 *         omega[e] = m.rest[2 * m.edges[2 * e + 1]] - m.rest[2 * m.edges[2 * e]];
 *     for (f = 0; f < m.nf; ++f) {                     // dω per face: zero for every exact ω
 *         double dw = 0.0;
 *         for (k = 0; k < 3; ++k) dw += m.face_edge_sign[3 * f + k] * omega[m.face_edges[3 * f + k]];
 *         worst = fmax(worst, fabs(dw));
 *     }
 *     printf("%d loop(s), %d edges, max |dω| = %g\n", m.n_loops, m.ne, worst);   // 1, 630, 0
 *     wr_free(omega);  wr_mesh_free(&m);
 *
 * ON CONVENTIONS (docs/CONVENTIONS.md)
 *   Faces are counter-clockwise in the rest (2D) domain. Edge e = (edges[2e], edges[2e+1]) with
 *   edges[2e] < edges[2e+1]; edges are numbered in lexicographic order of that pair, so the numbering
 *   depends only on the face list's vertex sets. Face f's k-th edge face_edges[3f+k] is the edge
 *   opposite corner k and is traversed from corner (k+1)%3 to corner (k+2)%3;
 *   face_edge_sign[3f+k] = +1 when that traversal goes edges[2e] → edges[2e+1], else -1.
 *   A one-form ω (TFW Sec. 4) stores ω_e = change from edges[2e] to edges[2e+1]; its discrete exterior
 *   derivative on face f is dω_f = Σ_k face_edge_sign[3f+k] · ω_{face_edges[3f+k]} (zero for ω = d0 f).
 *   edge_faces[2e] is the face that traverses e with sign +1, edge_faces[2e+1] the one with sign -1,
 *   -1 where there is none; an edge with a -1 is a boundary edge.
 *   Boundary loops are ordered along the face traversal of their boundary edges, i.e. with the mesh
 *   on the left in the rest domain: outer boundaries counter-clockwise, holes clockwise. Each loop
 *   starts at its smallest vertex index; loops are listed in order of that start vertex.
 *   vf lists each vertex's incident faces in increasing face index.
 *
 * ON VALIDATION
 *   wr_mesh_create rejects, with WR_ERR_TOPOLOGY and diag->item set: a face index outside [0,nv)
 *   (item = face), a face repeating a vertex (item = face), an edge shared by more than two faces
 *   (item = the third face; message names the edge's vertices), two faces traversing a shared edge in
 *   the same direction, i.e. inconsistent orientation (item = the second face), a non-manifold vertex
 *   whose incident faces form more than one fan (bow-tie; item = vertex). A non-finite coordinate is
 *   bad geometry, not bad connectivity: WR_ERR_GEOMETRY (item = vertex; checked after the face indices).
 *   wr_mesh_set_corner_rest likewise returns WR_ERR_GEOMETRY (item = face) for a non-finite corner.
 *   Counts < 1, NULL faces, or pos3 and rest2 both NULL → WR_ERR_INVALID_ARG.
 *   Orientation is checked combinatorially; faces whose rest area is <= 0 are not rejected here
 *   (a quality report counts them). Vertices in no face are allowed (empty vf range).
 *   nf or nv > INT32_MAX/3 → WR_ERR_OVERFLOW. The topology build is O(nv + nf) for bounded vertex
 *   degree: one counting sort of the half-edges by their low vertex (the faces read in order), a
 *   small sort per vertex, and the fan and boundary walks over the twins found there.
 *
 * ON UNITS
 *   Metres everywhere (pos, rest, corner_rest). OBJ vt values are taken as metres, unscaled.
 *
 * ON FILES
 *   Text I/O uses strtod / fprintf, so it assumes the "C" numeric locale (a program that switched
 *   LC_NUMERIC to a comma-decimal locale must switch back around these calls). Writers print 17
 *   significant digits: a write → read round trip reproduces every double exactly.
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
 *   so an enclosed volume is positive and a positive pressure (statics.h) inflates it.
 *
 * ON THREADS
 *   No global state. Read-only functions may run concurrently on one mesh.
 */
#ifndef WRINKLE_MESH_H
#define WRINKLE_MESH_H

#include "core.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct wr_mesh {
    int32_t nv, nf, ne;
    double *pos;             /* nv*3 positions [m] (always present) */
    double *rest;            /* nv*2 rest/pattern coordinates [m], or NULL (then the rest shape is pos) */
    double *corner_rest;     /* nf*6 per-face-corner rest coords [m] for sewn multi-panel meshes where a seam
                                vertex has two pattern positions; NULL when `rest` suffices. When non-NULL it
                                wins over `rest` for the rest metric. */
    int32_t *faces;          /* nf*3, CCW in the rest domain */
    int32_t *face_panel;     /* nf, panel id, or NULL */
    int32_t *edges;          /* ne*2, edges[2e] < edges[2e+1] */
    int32_t *face_edges;     /* nf*3: face f's k-th edge is opposite corner k (joins corners (k+1)%3,(k+2)%3) */
    int8_t *face_edge_sign;  /* nf*3: +1 when face f traverses that edge from edges[2e] to edges[2e+1] */
    int32_t *edge_faces;     /* ne*2: [2e] the face traversing e with sign +1, [2e+1] the face with sign -1; -1 = none */
    int32_t *vf_start, *vf;  /* vertex->incident faces CSR: faces of v are vf[vf_start[v] .. vf_start[v+1]) */
    int32_t n_loops;         /* boundary loops */
    int32_t *loop_start, *loop_verts; /* loop l = loop_verts[loop_start[l] .. loop_start[l+1]), ordered along the boundary */
} wr_mesh;

/* Copies the inputs and builds the topology. pos3: nv*3 [m] or NULL (then pos = (rest, 0)).
 * rest2: nv*2 [m] or NULL (then the rest shape is pos). faces: nf*3 vertex indices, CCW in the rest
 * domain. See ON VALIDATION for the errors. On failure *m is left zeroed. Free with wr_mesh_free. */
WRDEF wr_status wr_mesh_create(wr_mesh *m, int32_t nv, const double *pos3, const double *rest2, int32_t nf,
                               const int32_t *faces, wr_diag *diag);
/* Frees every array and zeroes *m; safe on a zeroed mesh. */
WRDEF void wr_mesh_free(wr_mesh *m);
/* Deep copy of src (including corner_rest and face_panel). On failure *dst is left zeroed. */
WRDEF wr_status wr_mesh_copy(wr_mesh *dst, const wr_mesh *src, wr_diag *diag);
/* Rest-domain corners of face f: uv = (u0,v0, u1,v1, u2,v2) [m], in face corner order.
 * Source: corner_rest if non-NULL, else rest if non-NULL, else pos: when all three corners have
 * z == 0 exactly, their (x, y); otherwise the 3D triangle laid flat isometrically in a local frame
 * (corner 0 at the origin, corner 1 on +x, corner 2 at v >= 0, so the area is >= 0). In that last
 * case only the rest metric (edge vectors up to a rotation) is meaningful, not absolute positions. */
WRDEF void wr_mesh_face_rest(const wr_mesh *m, int32_t f, double uv[6]);
/* (nx+1)*(ny+1) vertices on [0,w]×[0,h] in z = 0, rest = (x, y), vertex index j*(nx+1)+i.
 * Cell (i, j) gives faces 2(j*nx+i) and 2(j*nx+i)+1, CCW; its diagonal alternates with (i+j) parity
 * ("union jack"), so the mesh has no preferred shear direction. w, h > 0 finite; nx, ny >= 1. */
WRDEF wr_status wr_mesh_rectangle(wr_mesh *m, double w, double h, int32_t nx, int32_t ny, wr_diag *diag);

/* ---- more generators (free with wr_mesh_free) ----------------------------------------------- */
/* Disk of radius R [m] centred at the origin in z = 0, rest = (x, y): a centre vertex and n_rings
 * concentric rings, ring k having 6k equally spaced vertices at radius R k / n_rings, so triangles
 * are close to equilateral. nv = 1 + 3 n (n+1), nf = 6 n². R > 0 finite, n_rings >= 1. */
WRDEF wr_status wr_mesh_disk(wr_mesh *m, double R, int32_t n_rings, wr_diag *diag);
/* Closed tube from an unrolled rectangle: rest domain [0, 2πR] × [0, height], nu cells around and
 * nh cells along (alternating diagonals as wr_mesh_rectangle), pos = (R cos(u/R), R sin(u/R), v)
 * (outward normals). The seam columns u = 0 and u = 2πR share vertices (nv = nu (nh+1)), so a seam
 * vertex has two pattern positions: rest is NULL and corner_rest is filled. Vertex index j*nu + i
 * at angle 2π i / nu, height height j / nh. R, height > 0 finite; nu >= 3, nh >= 1. */
WRDEF wr_status wr_mesh_cylinder_flat(wr_mesh *m, double R, double height, int32_t nu, int32_t nh, wr_diag *diag);

/* ---- optional per-face data (copied; replaces what was there) ------------------------------- */
/* cr: nf*6 finite rest corners [m], or NULL to drop corner_rest. */
WRDEF wr_status wr_mesh_set_corner_rest(wr_mesh *m, const double *cr, wr_diag *diag);
/* panel: nf ids (>= 0), or NULL to drop face_panel. */
WRDEF wr_status wr_mesh_set_face_panel(wr_mesh *m, const int32_t *panel, wr_diag *diag);

/* ---- measures --------------------------------------------------------------------------------- */
/* out[ne]: edge lengths [m]. use_rest = 0: 3D lengths from pos. use_rest != 0: rest lengths; with
 * corner_rest, the mean of the lengths the edge has in its incident faces (a sewn seam edge can
 * differ slightly between its two panels); with neither rest nor corner_rest, the 3D length. */
WRDEF void wr_mesh_edge_lengths(const wr_mesh *m, int use_rest, double *out);
/* out[nf]: face areas [m²]. use_rest = 0: 3D area (>= 0). use_rest != 0: signed rest area from
 * wr_mesh_face_rest (> 0 for CCW, < 0 for an inverted face). */
WRDEF void wr_mesh_face_areas(const wr_mesh *m, int use_rest, double *out);
/* out[nf*3]: unit 3D face normals (p1-p0)×(p2-p0)/|·|; zero vector for a degenerate face. */
WRDEF void wr_mesh_face_normals(const wr_mesh *m, double *out);
/* out[nv*3]: unit vertex normals, area-weighted (sum of the unnormalised face cross products over
 * incident faces, then normalised); zero vector for an isolated vertex or a cancelling sum. */
WRDEF void wr_mesh_vertex_normals(const wr_mesh *m, double *out);
/* Principal curvatures at every vertex of the surface `pos` (nv*3 [m]; NULL = m->pos) by a least-
 * squares quadric height field over the vertex's k-ring (k = rings, 0 → 5), the estimator of
 * Panozzo et al. 2010 that the TFW paper cites for κ⊥ (Eq. 22): in a frame (e1, e2, n̂) at the vertex,
 * n̂ the area-weighted vertex normal, fit z = a x² + b xy + c y² + d x + e y to the ring's vertices;
 * the shape operator of that height field at 0 gives k1 >= k2 [1/m] (signed: positive when the
 * surface bends towards n̂) and the unit direction of k1 (d1, nv*3). A vertex with fewer than five
 * ring neighbours, or a singular fit, gets k1 = k2 = 0 and d1 = e1. k1, k2, d1 may each be NULL.
 * WR_ERR_NOMEM. */
WRDEF wr_status wr_mesh_vertex_curvature(const wr_mesh *m, const double *pos, int32_t rings, double *k1, double *k2,
                                         double *d1, wr_diag *diag);

/* Relative area below which a rest face counts as zero-area: |A| <= WR_MESH_ZERO_AREA_REL * l_max²
 * (l_max its longest rest edge). 1e-12 is ~1e4 ulps of the area scale: clearly degenerate, yet far
 * above round-off of the cross product. */
#define WR_MESH_ZERO_AREA_REL 1e-12
typedef struct wr_mesh_quality_stats {
    double min_angle_deg, max_angle_deg; /* over all face corners [deg] */
    double mean_min_angle_deg;           /* mean over faces of the face's smallest angle [deg] */
    double min_edge, mean_edge, max_edge; /* edge lengths [m] */
    double area;                          /* total area [m²] (signed rest areas summed when use_rest) */
    int32_t n_inverted;                   /* faces with rest area < 0 beyond the zero threshold */
    int32_t n_zero_area;                  /* faces with |rest area| <= WR_MESH_ZERO_AREA_REL l_max² */
    int32_t n_boundary_edges, n_loops;
    int32_t euler;                        /* nv - ne + nf */
} wr_mesh_quality_stats;
/* Angles and edge lengths in the rest domain (use_rest != 0) or in 3D (use_rest = 0); inverted and
 * zero-area faces are always counted in the rest domain. Zero-area faces give angles of 0 or 180. */
WRDEF void wr_mesh_quality(const wr_mesh *m, int use_rest, wr_mesh_quality_stats *q);
/* Histogram of ratio[n] (e.g. edge length / target length, Style3D Sec. 6) into nbins equal bins on
 * [lo, hi): counts[nbins] is overwritten. Values below lo count in bin 0, values >= hi in the last
 * bin; NaN values are skipped. WR_ERR_INVALID_ARG when n < 0, nbins < 1 or !(lo < hi) finite. */
WRDEF wr_status wr_mesh_ratio_histogram(const double *ratio, int32_t n, int32_t nbins, double lo, double hi,
                                        int32_t *counts);

/* ---- I/O (writes are atomic through wr_afile: the file appears whole or not at all) ------------ */
/* Wavefront OBJ reader. Understands v (x y z, extra numbers ignored), vt (u v [w], read as metres,
 * no scaling), f with v, v/vt, v//vn, v/vt/vn corners, negative (relative) indices, polygons
 * (fan-triangulated from their first corner), g / o (each distinct name becomes a panel id in
 * order of first appearance; faces before the first g/o form their own panel 0). Ignores vn,
 * comments, usemtl, mtllib, s, l, p and unknown statements. Either every face corner has a vt or
 * none does. When every vertex sees one vt value across its faces, rest = those values (a vertex
 * in no face gets (x, y)); otherwise corner_rest gets one vt per corner and rest stays NULL.
 * face_panel is set only when the file has g or o lines. Malformed input → WR_ERR_PARSE with
 * "line N" in the message and diag->item = N; the mesh is then validated as wr_mesh_create does
 * (WR_ERR_TOPOLOGY, item = triangle index after fan triangulation, message also names the OBJ line
 * of that face). On failure *m is left zeroed. */
WRDEF wr_status wr_mesh_parse_obj(wr_mesh *m, const char *text, size_t len, wr_diag *diag);
WRDEF wr_status wr_mesh_read_obj(wr_mesh *m, const char *path, wr_diag *diag); /* WR_ERR_IO if unreadable */
/* The g / o names of an OBJ read, so that a program writing the mesh back (wr_obj_desc.group_names)
 * keeps the panel names it was given: names[id] is the name of panel id (face_panel) for id < n;
 * names[0] is NULL when faces precede the first g/o (that unnamed panel 0). n = 0, names = NULL when
 * the file has no g/o lines. Owned by the struct: free with wr_obj_groups_free (a zeroed struct is
 * fine). */
typedef struct wr_obj_groups {
    char **names;
    int32_t n;
} wr_obj_groups;
/* wr_mesh_parse_obj / wr_mesh_read_obj, with the group names in *groups (zeroed on failure). */
WRDEF wr_status wr_mesh_parse_obj_groups(wr_mesh *m, const char *text, size_t len, wr_obj_groups *groups,
                                         wr_diag *diag);
WRDEF wr_status wr_mesh_read_obj_groups(wr_mesh *m, const char *path, wr_obj_groups *groups, wr_diag *diag);
WRDEF void wr_obj_groups_free(wr_obj_groups *groups);

/* Options of wr_mesh_write_obj; zero means default:
 *   no_rest = 0    write vt (rest per vertex, or corner_rest per corner) when available
 *   no_groups = 0  write "g panel<id>" whenever face_panel changes between consecutive faces
 *   comment = NULL no extra comment line (else one "# <comment>" line; newlines become spaces)
 *   normals = 0    nonzero: one vn per vertex (wr_mesh_vertex_normals of pos, area-weighted), faces
 *                  written v/vt/vn (or v//vn without vt): viewers shade smoothly without recomputing
 *   group_names    NULL: groups are "panel<id>"; else group_names[id] for ids < n_group_names (a
 *                  garment's panel names; spaces and empty names as "panel<id>") */
typedef struct wr_obj_desc {
    int no_rest;
    int no_groups;
    const char *comment;
    int normals;
    const char *const *group_names;
    int32_t n_group_names;
} wr_obj_desc;
/* Coordinates printed with 17 significant digits, so a write→read round trip is exact. */
WRDEF wr_status wr_mesh_write_obj(const wr_mesh *m, const char *path, const wr_obj_desc *desc, wr_diag *diag);
/* ASCII PLY: x y z as double, then nprops per-vertex double properties names[k] with values[k][nv],
 * faces as "vertex_indices" lists. Names: non-empty, printable, no whitespace, not x/y/z.
 * Non-finite property values → WR_ERR_DOMAIN (nothing written, an existing file is kept). */
WRDEF wr_status wr_mesh_write_ply(const wr_mesh *m, const char *path, int32_t nprops, const char *const *names,
                                  const double *const *values, wr_diag *diag);
/* Legacy ASCII VTK POLYDATA: POINTS, POLYGONS, then n_point POINT_DATA scalars (values[k][nv]) and
 * n_cell CELL_DATA scalars (values[k][nf]). Same name and finiteness rules as the PLY writer. */
WRDEF wr_status wr_mesh_write_vtk(const wr_mesh *m, const char *path, int32_t n_point,
                                  const char *const *point_names, const double *const *point_values,
                                  int32_t n_cell, const char *const *cell_names, const double *const *cell_values,
                                  wr_diag *diag);

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
#endif /* WRINKLE_MESH_H */

/* ============================================================================================ */
#ifdef WRINKLE_IMPLEMENTATION
#ifndef WRINKLE_MESH_IMPLEMENTATION_DONE
#define WRINKLE_MESH_IMPLEMENTATION_DONE

#include <math.h>
#include <stdlib.h>
#include <string.h>

#ifdef __cplusplus
extern "C" {
#endif

/* Frees the derived topology only (pos/rest/faces stay). */
static void wr__mesh_free_topology(wr_mesh *m) {
    wr_free(m->edges);
    wr_free(m->face_edges);
    wr_free(m->face_edge_sign);
    wr_free(m->edge_faces);
    wr_free(m->vf_start);
    wr_free(m->vf);
    wr_free(m->loop_start);
    wr_free(m->loop_verts);
    m->edges = m->face_edges = m->edge_faces = m->vf_start = m->vf = m->loop_start = m->loop_verts = NULL;
    m->face_edge_sign = NULL;
    m->ne = 0;
    m->n_loops = 0;
}

WRDEF void wr_mesh_free(wr_mesh *m) {
    if (!m) return;
    wr__mesh_free_topology(m);
    wr_free(m->pos);
    wr_free(m->rest);
    wr_free(m->corner_rest);
    wr_free(m->faces);
    wr_free(m->face_panel);
    memset(m, 0, sizeof *m);
}

/* Half-edge h (corner h % 3 of face h / 3) runs from WR__HE_A to WR__HE_B, the corners after it. */
#define WR__HE_A(m, h) ((m)->faces[3 * ((h) / 3) + ((h) % 3 + 1) % 3])
#define WR__HE_B(m, h) ((m)->faces[3 * ((h) / 3) + ((h) % 3 + 2) % 3])
/* Sort key of half-edge h running a → b: its high vertex in the upper 32 bits, then h, then 1 when
 * it runs high → low; ascending keys of one low vertex are ascending (high vertex, half-edge). */
#define WR__HE_KEY(a, b, h) \
    ((a) < (b) ? ((int64_t)(b) << 32) | ((int64_t)(h) << 1) : ((int64_t)(a) << 32) | ((int64_t)(h) << 1) | 1)
#define WR__HE_HI(k) ((int32_t)((k) >> 32))
#define WR__HE_H(k) ((int32_t)(((k)&0xffffffff) >> 1))

/* Scratch of the topology build. In sorted position i: key[i] = the WR__HE_KEY of a half-edge;
 * twin[h] = the other half-edge of h's edge, -1 on the boundary; cnt = bucket ends. */
typedef struct wr__mesh_he {
    int32_t *cnt, *twin;
    int64_t *key;
} wr__mesh_he;

static int wr__mesh_cmp_i64(const void *x, const void *y) {
    int64_t a = *(const int64_t *)x, b = *(const int64_t *)y;
    return a < b ? -1 : a > b;
}

/* The n half-edges of one low vertex in (high vertex, half-edge) order, i.e. their keys ascending:
 * insertion sort (a vertex is the low end of ~3 edges), qsort for a large fan. */
static void wr__mesh_sort_bucket(int64_t *key, int32_t n) {
    int32_t i, j;
    if (n > 32) {
        qsort(key, (size_t)n, sizeof *key, wr__mesh_cmp_i64);
        return;
    }
    for (i = 1; i < n; ++i) {
        int64_t k = key[i];
        for (j = i; j > 0 && key[j - 1] > k; --j) key[j] = key[j - 1];
        key[j] = k;
    }
}

/* key ← the 3nf half-edges ordered by (low vertex, high vertex, half-edge): one counting sort by
 * the low vertex (the faces read in order, twice), then each low vertex's few half-edges sorted. */
static void wr__mesh_sort_halfedges(const wr_mesh *m, wr__mesh_he *s) {
    const int32_t nv = m->nv, n3 = 3 * m->nf, *F = m->faces;
    int32_t f, v;
    memset(s->cnt, 0, sizeof(int32_t) * ((size_t)nv + 1));
    for (f = 0; f < n3; f += 3) {
        int32_t a = F[f], b = F[f + 1], c = F[f + 2];
        s->cnt[(b < c ? b : c) + 1]++; /* half-edge f+0: b → c; f+1: c → a; f+2: a → b */
        s->cnt[(c < a ? c : a) + 1]++;
        s->cnt[(a < b ? a : b) + 1]++;
    }
    for (v = 0; v < nv; ++v) s->cnt[v + 1] += s->cnt[v];
    for (f = 0; f < n3; f += 3) {
        const int32_t a = F[f], b = F[f + 1], c = F[f + 2];
        s->key[s->cnt[b < c ? b : c]++] = WR__HE_KEY(b, c, f);
        s->key[s->cnt[c < a ? c : a]++] = WR__HE_KEY(c, a, f + 1);
        s->key[s->cnt[a < b ? a : b]++] = WR__HE_KEY(a, b, f + 2);
    }
    /* cnt[v] is now the end of v's bucket, i.e. the start of v + 1's */
    for (v = 0; v < nv; ++v) {
        int32_t b0 = v ? s->cnt[v - 1] : 0;
        if (s->cnt[v] - b0 > 1) wr__mesh_sort_bucket(s->key + b0, s->cnt[v] - b0);
    }
}

/* edges (low, high), face_edges, face_edge_sign, edge_faces and the twins from the sorted half-edges,
 * in one pass over the runs of equal (low, high): each run is one edge, in at most two faces that
 * traverse it in opposite directions (else the error names the edge). edges and edge_faces have room
 * for the upper bound, one edge per half-edge; *ne_out = the edge count. */
static wr_status wr__mesh_fill_edges(wr_mesh *m, wr__mesh_he *s, size_t *ne_out, wr_diag *diag) {
    const int64_t *key = s->key;
    size_t i = 0, ne = 0;
    int32_t v;
    for (v = 0; v < m->nv; ++v)
        for (; i < (size_t)s->cnt[v]; ++ne) {
            const size_t end = (size_t)s->cnt[v];
            int32_t hi = WR__HE_HI(key[i]), h = WR__HE_H(key[i]), plus = !(key[i] & 1), *ef = m->edge_faces + 2 * ne;
            int two = i + 1 < end && WR__HE_HI(key[i + 1]) == hi;
            if (two && i + 2 < end && WR__HE_HI(key[i + 2]) == hi)
                return wr_fail(diag, WR_ERR_TOPOLOGY, WR__HE_H(key[i + 2]) / 3,
                               "non-manifold edge (%d,%d): shared by faces %d, %d and %d", v, hi, h / 3,
                               WR__HE_H(key[i + 1]) / 3, WR__HE_H(key[i + 2]) / 3);
            if (two && (key[i] & 1) == (key[i + 1] & 1))
                return wr_fail(diag, WR_ERR_TOPOLOGY, WR__HE_H(key[i + 1]) / 3,
                               "inconsistent orientation: faces %d and %d both traverse edge %d->%d", h / 3,
                               WR__HE_H(key[i + 1]) / 3, plus ? v : hi, plus ? hi : v);
            m->edges[2 * ne] = v;
            m->edges[2 * ne + 1] = hi;
            m->face_edges[h] = (int32_t)ne;
            m->face_edge_sign[h] = (int8_t)(plus ? 1 : -1);
            ef[plus ? 0 : 1] = h / 3;
            if (two) { /* the second half-edge runs the other way */
                int32_t t = WR__HE_H(key[i + 1]);
                m->face_edges[t] = (int32_t)ne;
                m->face_edge_sign[t] = (int8_t)-m->face_edge_sign[h];
                ef[plus ? 1 : 0] = t / 3;
                s->twin[h] = t;
                s->twin[t] = h;
                i += 2;
            } else {
                ef[plus ? 1 : 0] = -1;
                s->twin[h] = -1;
                i += 1;
            }
        }
    if (ne > (size_t)INT32_MAX / 2) return wr_fail(diag, WR_ERR_OVERFLOW, -1, "mesh has too many edges (%zu)", ne);
    *ne_out = ne;
    return WR_OK;
}

/* vertex → faces CSR (faces ascending per vertex); cnt (nv + 1) is scratch */
static void wr__mesh_vertex_faces(wr_mesh *m, int32_t *cnt) {
    const size_t nh = (size_t)3 * (size_t)m->nf;
    size_t i;
    int32_t v;
    memset(m->vf_start, 0, sizeof(int32_t) * ((size_t)m->nv + 1));
    for (i = 0; i < nh; ++i) m->vf_start[m->faces[i] + 1]++;
    for (v = 0; v < m->nv; ++v) m->vf_start[v + 1] += m->vf_start[v];
    memcpy(cnt, m->vf_start, sizeof(int32_t) * ((size_t)m->nv + 1));
    for (i = 0; i < nh; i += 3) {
        const int32_t f = (int32_t)(i / 3);
        m->vf[cnt[m->faces[i]]++] = f;
        m->vf[cnt[m->faces[i + 1]]++] = f;
        m->vf[cnt[m->faces[i + 2]]++] = f;
    }
}

/* Manifold vertices: the faces around v must form one fan. Crossing the edge (v, next) of each face
 * to its twin is an injective map on v's faces (consistent orientation), so the walk from the first
 * face either returns or stops at the boundary; then walk the other way, across (prev, v). Half-edge
 * 3f + k runs from corner k+1 to k+2: the one leaving v (corner c) is k = c+2, the one entering it
 * k = c+1; in the twin face the roles swap, hence the steps (k_t + 1) and (k_t + 2) mod 3. */
static wr_status wr__mesh_check_fans(const wr_mesh *m, const int32_t *twin, wr_diag *diag) {
    int32_t v;
    for (v = 0; v < m->nv; ++v) {
        int32_t deg = m->vf_start[v + 1] - m->vf_start[v], f0, c, h, count = 1, closed = 0;
#if defined(__GNUC__)
        /* The walk reads the twins of exactly v's faces, which vf lists: fetched a few vertices
         * ahead (faces are far apart in memory when the numbering is not spatially coherent). */
        if (v + 4 < m->nv && m->vf_start[v + 4] < m->vf_start[v + 5]) {
            int32_t i;
            __builtin_prefetch(m->faces + 3 * m->vf[m->vf_start[v + 4]]); /* its first face's corners */
            for (i = m->vf_start[v + 4]; i < m->vf_start[v + 5]; ++i) __builtin_prefetch(twin + 3 * m->vf[i]);
        }
#endif
        if (deg == 0) continue;
        f0 = m->vf[m->vf_start[v]];
        c = m->faces[3 * f0] == v ? 0 : (m->faces[3 * f0 + 1] == v ? 1 : 2);
        for (h = 3 * f0 + (c + 2) % 3; count <= deg;) { /* across (v, next) */
            int32_t t = twin[h];
            if (t < 0) break;
            if ((uint32_t)(t - 3 * f0) < 3u) { /* back in f0 */
                closed = 1;
                break;
            }
            ++count;
            h = t % 3 == 2 ? t - 2 : t + 1;
        }
        for (h = 3 * f0 + (c + 1) % 3; !closed && count <= deg;) { /* across (prev, v) */
            int32_t t = twin[h];
            if (t < 0 || (uint32_t)(t - 3 * f0) < 3u) break;
            ++count;
            h = t % 3 == 0 ? t + 2 : t - 1;
        }
        if (count != deg)
            return wr_fail(diag, WR_ERR_TOPOLOGY, v, "non-manifold vertex %d: its %d faces form more than one fan (one fan has %d)",
                           v, deg, count);
    }
    return WR_OK;
}

/* Boundary loops: boundary half-edges a→b in face traversal order; bnext[a] = b is unique at a
 * manifold vertex (one open fan has exactly one outgoing boundary half-edge). */
static wr_status wr__mesh_boundary_loops(wr_mesh *m, const int32_t *twin, wr_diag *diag) {
    const int32_t nv = m->nv;
    const size_t nh = (size_t)3 * (size_t)m->nf;
    int32_t nb = 0, l = 0, pos = 0, v, *bnext = (int32_t *)wr_alloc_array((size_t)nv + 1, sizeof(int32_t));
    uint8_t *seen = (uint8_t *)wr_calloc_array((size_t)nv + 1, 1);
    wr_status st = WR_OK;
    size_t i;
    if (!bnext || !seen) {
        st = wr_fail(diag, WR_ERR_NOMEM, -1, "mesh topology: out of memory");
        goto done;
    }
    for (v = 0; v < nv; ++v) bnext[v] = -1;
    for (i = 0; i < nh; ++i) {
        if (twin[i] >= 0) continue;
        bnext[WR__HE_A(m, (int32_t)i)] = WR__HE_B(m, (int32_t)i);
        ++nb;
    }
    for (v = 0; v < nv; ++v) { /* count loops */
        int32_t u = v, steps = 0;
        if (bnext[v] < 0 || seen[v]) continue;
        while (!seen[u] && steps <= nb) {
            seen[u] = 1;
            u = bnext[u];
            ++steps;
        }
        ++l;
    }
    m->n_loops = l;
    m->loop_start = (int32_t *)wr_alloc_array((size_t)l + 1, sizeof(int32_t));
    m->loop_verts = (int32_t *)wr_alloc_array((size_t)nb, sizeof(int32_t));
    if (!m->loop_start || !m->loop_verts) {
        st = wr_fail(diag, WR_ERR_NOMEM, -1, "mesh topology: out of memory (%d boundary edges)", nb);
        goto done;
    }
    memset(seen, 0, (size_t)nv);
    l = 0;
    for (v = 0; v < nv; ++v) {
        int32_t u = v;
        if (bnext[v] < 0 || seen[v]) continue;
        m->loop_start[l++] = pos;
        while (!seen[u] && pos < nb) {
            seen[u] = 1;
            m->loop_verts[pos++] = u;
            u = bnext[u];
        }
    }
    m->loop_start[l] = pos;
done:
    wr_free(bnext);
    wr_free(seen);
    return st;
}

/* Gives back the unused tail of an int32 array; keeps the larger block if shrinking fails. */
static void wr__mesh_shrink(int32_t **p, size_t n) {
    int32_t *q = (int32_t *)wr_realloc_array(*p, n > 0 ? n : 1, sizeof(int32_t));
    if (q) *p = q;
}

/* Builds edges, face_edges, face_edge_sign, edge_faces, vf CSR and boundary loops from nv, nf,
 * faces (already range-checked). O(nf + nv): one counting sort of the 3nf half-edges by their low
 * vertex and a small sort per vertex order them by (low vertex, high vertex); equal keys are then
 * adjacent, and the fan and loop walks follow the twins found there. */
static wr_status wr__mesh_build_topology(wr_mesh *m, wr_diag *diag) {
    const int32_t nv = m->nv, nf = m->nf;
    const size_t nh = (size_t)3 * (size_t)nf;
    wr__mesh_he s;
    wr_status st = WR_OK;
    size_t ne = 0;
    s.cnt = (int32_t *)wr_alloc_array((size_t)nv + 1, sizeof(int32_t));
    s.key = (int64_t *)wr_alloc_array(nh, sizeof(int64_t));
    s.twin = (int32_t *)wr_alloc_array(nh, sizeof(int32_t));
    if (!s.cnt || !s.key || !s.twin) {
        st = wr_fail(diag, WR_ERR_NOMEM, -1, "mesh topology: out of memory (%d faces)", nf);
        goto done;
    }
    wr__mesh_sort_halfedges(m, &s);
    m->edges = (int32_t *)wr_alloc_array(2 * nh, sizeof(int32_t)); /* room for ne <= nh; shrunk below */
    m->edge_faces = (int32_t *)wr_alloc_array(2 * nh, sizeof(int32_t));
    m->face_edges = (int32_t *)wr_alloc_array(nh, sizeof(int32_t));
    m->face_edge_sign = (int8_t *)wr_alloc_array(nh, sizeof(int8_t));
    m->vf_start = (int32_t *)wr_alloc_array((size_t)nv + 1, sizeof(int32_t));
    m->vf = (int32_t *)wr_alloc_array(nh, sizeof(int32_t));
    if (!m->edges || !m->edge_faces || !m->face_edges || !m->face_edge_sign || !m->vf_start || !m->vf) {
        st = wr_fail(diag, WR_ERR_NOMEM, -1, "mesh topology: out of memory (%d faces)", nf);
        goto done;
    }
    if ((st = wr__mesh_fill_edges(m, &s, &ne, diag)) != WR_OK) goto done;
    m->ne = (int32_t)ne;
    wr__mesh_shrink(&m->edges, 2 * ne);
    wr__mesh_shrink(&m->edge_faces, 2 * ne);
    wr__mesh_vertex_faces(m, s.cnt);
    if ((st = wr__mesh_check_fans(m, s.twin, diag)) != WR_OK) goto done;
    st = wr__mesh_boundary_loops(m, s.twin, diag);
done:
    wr_free(s.cnt);
    wr_free(s.key);
    wr_free(s.twin);
    if (st != WR_OK) wr__mesh_free_topology(m);
    return st;
}
#undef WR__HE_A
#undef WR__HE_B
#undef WR__HE_KEY
#undef WR__HE_HI
#undef WR__HE_H

WRDEF wr_status wr_mesh_create(wr_mesh *m, int32_t nv, const double *pos3, const double *rest2, int32_t nf,
                               const int32_t *faces, wr_diag *diag) {
    int32_t i, f;
    wr_status st;
    if (!m) return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "wr_mesh_create: NULL mesh");
    memset(m, 0, sizeof *m);
    if (nv < 1 || nf < 1) return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "empty mesh (nv=%d, nf=%d)", nv, nf);
    if (nf > INT32_MAX / 3)
        return wr_fail(diag, WR_ERR_OVERFLOW, -1, "too many faces (%d): 3*nf must fit int32", nf);
    /* Positions are indexed pos[3*i] and DOFs 3*v with int32 everywhere in wrinkle. */
    if (nv > INT32_MAX / 3)
        return wr_fail(diag, WR_ERR_OVERFLOW, -1, "too many vertices (nv=%d): 3*nv must fit int32", nv);
    if (!faces) return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "wr_mesh_create: NULL faces");
    if (!pos3 && !rest2) return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "wr_mesh_create: pos3 and rest2 both NULL");
    for (f = 0; f < nf; ++f) {
        int32_t a = faces[3 * f], b = faces[3 * f + 1], c = faces[3 * f + 2];
        if (a < 0 || a >= nv || b < 0 || b >= nv || c < 0 || c >= nv)
            return wr_fail(diag, WR_ERR_TOPOLOGY, f, "face %d has vertex index out of range [0,%d): (%d,%d,%d)", f,
                           nv, a, b, c);
        if (a == b || b == c || a == c)
            return wr_fail(diag, WR_ERR_TOPOLOGY, f, "face %d repeats a vertex: (%d,%d,%d)", f, a, b, c);
    }
    for (i = 0; i < nv; ++i) {
        if (pos3 && !(isfinite(pos3[3 * i]) && isfinite(pos3[3 * i + 1]) && isfinite(pos3[3 * i + 2])))
            return wr_fail(diag, WR_ERR_GEOMETRY, i, "vertex %d has a non-finite position (%g,%g,%g)", i,
                           pos3[3 * i], pos3[3 * i + 1], pos3[3 * i + 2]);
        if (rest2 && !(isfinite(rest2[2 * i]) && isfinite(rest2[2 * i + 1])))
            return wr_fail(diag, WR_ERR_GEOMETRY, i, "vertex %d has a non-finite rest coordinate (%g,%g)", i,
                           rest2[2 * i], rest2[2 * i + 1]);
    }
    m->nv = nv;
    m->nf = nf;
    m->pos = (double *)wr_alloc_array((size_t)nv * 3, sizeof(double));
    m->faces = (int32_t *)wr_alloc_array((size_t)nf * 3, sizeof(int32_t));
    if (rest2) m->rest = (double *)wr_alloc_array((size_t)nv * 2, sizeof(double));
    if (!m->pos || !m->faces || (rest2 && !m->rest)) {
        wr_mesh_free(m);
        return wr_fail(diag, WR_ERR_NOMEM, -1, "wr_mesh_create: out of memory (nv=%d, nf=%d)", nv, nf);
    }
    memcpy(m->faces, faces, sizeof(int32_t) * 3 * (size_t)nf);
    if (rest2) memcpy(m->rest, rest2, sizeof(double) * 2 * (size_t)nv);
    if (pos3) {
        memcpy(m->pos, pos3, sizeof(double) * 3 * (size_t)nv);
    } else {
        for (i = 0; i < nv; ++i) {
            m->pos[3 * i] = rest2[2 * i];
            m->pos[3 * i + 1] = rest2[2 * i + 1];
            m->pos[3 * i + 2] = 0.0;
        }
    }
    st = wr__mesh_build_topology(m, diag);
    if (st != WR_OK) wr_mesh_free(m);
    return st;
}

/* Duplicates n elements of `size` bytes; *out = NULL when src is NULL. Returns 0 on allocation failure. */
static int wr__mesh_dup(void **out, const void *src, size_t n, size_t size) {
    *out = NULL;
    if (!src) return 1;
    *out = wr_alloc_array(n, size);
    if (!*out) return 0;
    if (n) memcpy(*out, src, n * size);
    return 1;
}

WRDEF wr_status wr_mesh_copy(wr_mesh *dst, const wr_mesh *src, wr_diag *diag) {
    size_t nv, nf, ne, nl, nb;
    int ok = 1;
    void *p;
    if (!dst || !src) return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "wr_mesh_copy: NULL mesh");
    memset(dst, 0, sizeof *dst);
    nv = (size_t)src->nv;
    nf = (size_t)src->nf;
    ne = (size_t)src->ne;
    nl = (size_t)src->n_loops;
    nb = src->loop_start ? (size_t)src->loop_start[nl] : 0;
    dst->nv = src->nv;
    dst->nf = src->nf;
    dst->ne = src->ne;
    dst->n_loops = src->n_loops;
#define WR__DUP(field, n, type)                                 \
    ok &= wr__mesh_dup(&p, src->field, (n), sizeof(type)); \
    dst->field = (type *)p;
    WR__DUP(pos, 3 * nv, double)
    WR__DUP(rest, 2 * nv, double)
    WR__DUP(corner_rest, 6 * nf, double)
    WR__DUP(faces, 3 * nf, int32_t)
    WR__DUP(face_panel, nf, int32_t)
    WR__DUP(edges, 2 * ne, int32_t)
    WR__DUP(face_edges, 3 * nf, int32_t)
    WR__DUP(face_edge_sign, 3 * nf, int8_t)
    WR__DUP(edge_faces, 2 * ne, int32_t)
    WR__DUP(vf_start, nv + 1, int32_t)
    WR__DUP(vf, 3 * nf, int32_t)
    WR__DUP(loop_start, nl + 1, int32_t)
    WR__DUP(loop_verts, nb, int32_t)
#undef WR__DUP
    if (!ok) {
        wr_mesh_free(dst);
        return wr_fail(diag, WR_ERR_NOMEM, -1, "wr_mesh_copy: out of memory (nv=%d, nf=%d)", src->nv, src->nf);
    }
    return WR_OK;
}

WRDEF void wr_mesh_face_rest(const wr_mesh *m, int32_t f, double uv[6]) {
    int k;
    const int32_t *t = m->faces + 3 * f;
    if (m->corner_rest) {
        for (k = 0; k < 6; ++k) uv[k] = m->corner_rest[6 * f + k];
    } else if (m->rest) {
        for (k = 0; k < 3; ++k) {
            uv[2 * k] = m->rest[2 * t[k]];
            uv[2 * k + 1] = m->rest[2 * t[k] + 1];
        }
    } else {
        const double *p0 = m->pos + 3 * t[0], *p1 = m->pos + 3 * t[1], *p2 = m->pos + 3 * t[2];
        if (p0[2] == 0.0 && p1[2] == 0.0 && p2[2] == 0.0) {
            for (k = 0; k < 3; ++k) {
                uv[2 * k] = m->pos[3 * t[k]];
                uv[2 * k + 1] = m->pos[3 * t[k] + 1];
            }
        } else {
            /* Isometric flattening: |e1| on the x axis, corner 2 from its projections on e1 and on
             * the in-plane normal (|e1 × e2| / |e1| is the triangle height). */
            wr_vec3 e1 = wr_v3_sub(wr_v3_load(p1), wr_v3_load(p0));
            wr_vec3 e2 = wr_v3_sub(wr_v3_load(p2), wr_v3_load(p0));
            double l1 = wr_v3_norm(e1);
            uv[0] = uv[1] = 0.0;
            uv[2] = l1;
            uv[3] = 0.0;
            if (l1 > 0.0) {
                uv[4] = wr_v3_dot(e1, e2) / l1;
                uv[5] = wr_v3_norm(wr_v3_cross(e1, e2)) / l1;
            } else {
                uv[4] = wr_v3_norm(e2);
                uv[5] = 0.0;
            }
        }
    }
}

WRDEF wr_status wr_mesh_rectangle(wr_mesh *m, double w, double h, int32_t nx, int32_t ny, wr_diag *diag) {
    int64_t nv64, nf64;
    int32_t nv, nf, i, j, f = 0;
    double *rest = NULL;
    int32_t *faces = NULL;
    wr_status st;
    if (!m) return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "wr_mesh_rectangle: NULL mesh");
    memset(m, 0, sizeof *m);
    if (!(isfinite(w) && isfinite(h) && w > 0.0 && h > 0.0))
        return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "rectangle size must be finite and > 0 (w=%g, h=%g)", w, h);
    if (nx < 1 || ny < 1) return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "rectangle needs nx, ny >= 1 (%d, %d)", nx, ny);
    nv64 = (int64_t)(nx + (int64_t)1) * (ny + (int64_t)1);
    nf64 = (int64_t)2 * nx * ny;
    if (nv64 > INT32_MAX || nf64 > INT32_MAX / 3)
        return wr_fail(diag, WR_ERR_OVERFLOW, -1, "rectangle %d x %d is too large for int32 indices", nx, ny);
    nv = (int32_t)nv64;
    nf = (int32_t)nf64;
    rest = (double *)wr_alloc_array((size_t)nv * 2, sizeof(double));
    faces = (int32_t *)wr_alloc_array((size_t)nf * 3, sizeof(int32_t));
    if (!rest || !faces) {
        wr_free(rest);
        wr_free(faces);
        return wr_fail(diag, WR_ERR_NOMEM, -1, "wr_mesh_rectangle: out of memory (%d vertices)", nv);
    }
    for (j = 0; j <= ny; ++j)
        for (i = 0; i <= nx; ++i) {
            /* exact end points: w*i/nx hits w for i = nx */
            rest[2 * (j * (nx + 1) + i)] = w * (double)i / (double)nx;
            rest[2 * (j * (nx + 1) + i) + 1] = h * (double)j / (double)ny;
        }
    for (j = 0; j < ny; ++j)
        for (i = 0; i < nx; ++i) {
            int32_t v00 = j * (nx + 1) + i, v10 = v00 + 1, v01 = v00 + nx + 1, v11 = v01 + 1;
            if (((i + j) & 1) == 0) { /* diagonal v00–v11 */
                faces[3 * f] = v00, faces[3 * f + 1] = v10, faces[3 * f + 2] = v11, ++f;
                faces[3 * f] = v00, faces[3 * f + 1] = v11, faces[3 * f + 2] = v01, ++f;
            } else { /* diagonal v10–v01 */
                faces[3 * f] = v00, faces[3 * f + 1] = v10, faces[3 * f + 2] = v01, ++f;
                faces[3 * f] = v10, faces[3 * f + 1] = v11, faces[3 * f + 2] = v01, ++f;
            }
        }
    st = wr_mesh_create(m, nv, NULL, rest, nf, faces, diag);
    wr_free(rest);
    wr_free(faces);
    return st;
}

/* ---- more generators -------------------------------------------------------------------------- */

WRDEF wr_status wr_mesh_disk(wr_mesh *m, double R, int32_t n_rings, wr_diag *diag) {
    int64_t nv64, nf64;
    int32_t nv, nf = 0, k, i, j;
    double *rest = NULL;
    int32_t *faces = NULL;
    wr_status st;
    const double two_pi = 6.283185307179586;
    if (!m) return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "wr_mesh_disk: NULL mesh");
    memset(m, 0, sizeof *m);
    if (!(isfinite(R) && R > 0.0)) return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "disk radius must be finite and > 0 (R=%g)", R);
    if (n_rings < 1) return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "disk needs n_rings >= 1 (%d)", n_rings);
    nv64 = 1 + (int64_t)3 * n_rings * ((int64_t)n_rings + 1);
    nf64 = (int64_t)6 * n_rings * n_rings;
    if (nv64 > INT32_MAX || nf64 > INT32_MAX / 3)
        return wr_fail(diag, WR_ERR_OVERFLOW, -1, "disk with %d rings is too large for int32 indices", n_rings);
    nv = (int32_t)nv64;
    rest = (double *)wr_alloc_array((size_t)nv * 2, sizeof(double));
    faces = (int32_t *)wr_alloc_array((size_t)nf64 * 3, sizeof(int32_t));
    if (!rest || !faces) {
        wr_free(rest);
        wr_free(faces);
        return wr_fail(diag, WR_ERR_NOMEM, -1, "wr_mesh_disk: out of memory (%d vertices)", nv);
    }
    rest[0] = rest[1] = 0.0;
    for (k = 1; k <= n_rings; ++k) {
        int32_t base = 1 + 3 * k * (k - 1); /* first vertex of ring k */
        double r = R * (double)k / (double)n_rings;
        for (i = 0; i < 6 * k; ++i) {
            double t = two_pi * (double)i / (6.0 * k);
            rest[2 * (base + i)] = r * cos(t);
            rest[2 * (base + i) + 1] = r * sin(t);
        }
    }
    for (k = 1; k <= n_rings; ++k) {
        /* strip between ring k-1 (p vertices, p = 1 for the centre) and ring k (q = 6k vertices):
         * advance whichever ring's next vertex has the smaller angle; integer comparison of
         * (i+1)/p against (j+1)/q keeps it exact. Each step emits one CCW triangle. */
        int32_t pin = k == 1 ? 1 : 6 * (k - 1), q = 6 * k;
        int32_t ib = k == 1 ? 0 : 1 + 3 * (k - 1) * (k - 2), ob = 1 + 3 * k * (k - 1);
        i = 0;
        j = 0;
        while (i < (k == 1 ? 0 : pin) || j < q) {
            int adv_outer = (k == 1) || i >= pin || (j < q && (int64_t)(j + 1) * pin <= (int64_t)(i + 1) * q);
            int32_t a = ib + (k == 1 ? 0 : i % pin);
            if (adv_outer) {
                faces[3 * nf] = a, faces[3 * nf + 1] = ob + j % q, faces[3 * nf + 2] = ob + (j + 1) % q, ++nf;
                ++j;
            } else {
                faces[3 * nf] = a, faces[3 * nf + 1] = ob + j % q, faces[3 * nf + 2] = ib + (i + 1) % pin, ++nf;
                ++i;
            }
        }
    }
    WR_ASSERT(nf == (int32_t)nf64);
    st = wr_mesh_create(m, nv, NULL, rest, nf, faces, diag);
    wr_free(rest);
    wr_free(faces);
    return st;
}

WRDEF wr_status wr_mesh_cylinder_flat(wr_mesh *m, double R, double height, int32_t nu, int32_t nh, wr_diag *diag) {
    int64_t nv64, nf64;
    int32_t nv, nf = 0, i, j, k;
    double *pos = NULL, *cr = NULL;
    int32_t *faces = NULL;
    double circ, du, dv;
    wr_status st;
    const double two_pi = 6.283185307179586;
    if (!m) return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "wr_mesh_cylinder_flat: NULL mesh");
    memset(m, 0, sizeof *m);
    if (!(isfinite(R) && isfinite(height) && R > 0.0 && height > 0.0))
        return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "cylinder R and height must be finite and > 0 (R=%g, h=%g)", R,
                       height);
    if (nu < 3 || nh < 1)
        return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "cylinder needs nu >= 3 and nh >= 1 (%d, %d)", nu, nh);
    nv64 = (int64_t)nu * ((int64_t)nh + 1);
    nf64 = (int64_t)2 * nu * nh;
    if (nv64 > INT32_MAX || nf64 > INT32_MAX / 6)
        return wr_fail(diag, WR_ERR_OVERFLOW, -1, "cylinder %d x %d is too large for int32 indices", nu, nh);
    nv = (int32_t)nv64;
    circ = two_pi * R;
    du = circ / (double)nu;
    dv = height / (double)nh;
    pos = (double *)wr_alloc_array((size_t)nv * 3, sizeof(double));
    faces = (int32_t *)wr_alloc_array((size_t)nf64 * 3, sizeof(int32_t));
    cr = (double *)wr_alloc_array((size_t)nf64 * 6, sizeof(double));
    if (!pos || !faces || !cr) {
        st = wr_fail(diag, WR_ERR_NOMEM, -1, "wr_mesh_cylinder_flat: out of memory (%d vertices)", nv);
        goto done;
    }
    for (j = 0; j <= nh; ++j)
        for (i = 0; i < nu; ++i) {
            double t = two_pi * (double)i / (double)nu;
            pos[3 * (j * nu + i)] = R * cos(t);
            pos[3 * (j * nu + i) + 1] = R * sin(t);
            pos[3 * (j * nu + i) + 2] = height * (double)j / (double)nh;
        }
    for (j = 0; j < nh; ++j)
        for (i = 0; i < nu; ++i) {
            /* grid corners (column, row) before wrapping; the column nu is vertex column 0 */
            int32_t ci[6], cj[6];
            if (((i + j) & 1) == 0) {
                ci[0] = i, cj[0] = j, ci[1] = i + 1, cj[1] = j, ci[2] = i + 1, cj[2] = j + 1;
                ci[3] = i, cj[3] = j, ci[4] = i + 1, cj[4] = j + 1, ci[5] = i, cj[5] = j + 1;
            } else {
                ci[0] = i, cj[0] = j, ci[1] = i + 1, cj[1] = j, ci[2] = i, cj[2] = j + 1;
                ci[3] = i + 1, cj[3] = j, ci[4] = i + 1, cj[4] = j + 1, ci[5] = i, cj[5] = j + 1;
            }
            for (k = 0; k < 6; ++k) {
                int32_t f = nf + k / 3;
                faces[3 * f + k % 3] = cj[k] * nu + ci[k] % nu;
                /* exact seam coordinate: column nu sits at u = 2πR */
                cr[6 * f + 2 * (k % 3)] = ci[k] == nu ? circ : du * (double)ci[k];
                cr[6 * f + 2 * (k % 3) + 1] = cj[k] == nh ? height : dv * (double)cj[k];
            }
            nf += 2;
        }
    st = wr_mesh_create(m, nv, pos, NULL, nf, faces, diag);
    if (st == WR_OK) {
        m->corner_rest = cr;
        cr = NULL;
    }
done:
    wr_free(pos);
    wr_free(faces);
    wr_free(cr);
    return st;
}

WRDEF wr_status wr_mesh_set_corner_rest(wr_mesh *m, const double *cr, wr_diag *diag) {
    double *p;
    int32_t i;
    if (!m || !m->faces) return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "wr_mesh_set_corner_rest: empty mesh");
    if (!cr) {
        wr_free(m->corner_rest);
        m->corner_rest = NULL;
        return WR_OK;
    }
    for (i = 0; i < 6 * m->nf; ++i)
        if (!isfinite(cr[i]))
            return wr_fail(diag, WR_ERR_GEOMETRY, i / 6, "face %d has a non-finite corner rest coordinate (%g)", i / 6,
                           cr[i]);
    p = (double *)wr_alloc_array((size_t)m->nf * 6, sizeof(double));
    if (!p) return wr_fail(diag, WR_ERR_NOMEM, -1, "wr_mesh_set_corner_rest: out of memory");
    memcpy(p, cr, sizeof(double) * 6 * (size_t)m->nf);
    wr_free(m->corner_rest);
    m->corner_rest = p;
    return WR_OK;
}

WRDEF wr_status wr_mesh_set_face_panel(wr_mesh *m, const int32_t *panel, wr_diag *diag) {
    int32_t *p, i;
    if (!m || !m->faces) return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "wr_mesh_set_face_panel: empty mesh");
    if (!panel) {
        wr_free(m->face_panel);
        m->face_panel = NULL;
        return WR_OK;
    }
    for (i = 0; i < m->nf; ++i)
        if (panel[i] < 0) return wr_fail(diag, WR_ERR_INVALID_ARG, i, "face %d has negative panel id %d", i, panel[i]);
    p = (int32_t *)wr_alloc_array((size_t)m->nf, sizeof(int32_t));
    if (!p) return wr_fail(diag, WR_ERR_NOMEM, -1, "wr_mesh_set_face_panel: out of memory");
    memcpy(p, panel, sizeof(int32_t) * (size_t)m->nf);
    wr_free(m->face_panel);
    m->face_panel = p;
    return WR_OK;
}

/* ---- measures --------------------------------------------------------------------------------- */

static double wr__mesh_dist3(const double *a, const double *b) {
    return sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) + (a[2] - b[2]) * (a[2] - b[2]));
}

WRDEF void wr_mesh_edge_lengths(const wr_mesh *m, int use_rest, double *out) {
    int32_t e, f, k;
    if (use_rest && m->corner_rest) {
        for (e = 0; e < m->ne; ++e) out[e] = 0.0;
        for (f = 0; f < m->nf; ++f)
            for (k = 0; k < 3; ++k) {
                const double *c = m->corner_rest + 6 * f;
                int a = (k + 1) % 3, b = (k + 2) % 3;
                int32_t e2 = m->face_edges[3 * f + k];
                int two = m->edge_faces[2 * e2] >= 0 && m->edge_faces[2 * e2 + 1] >= 0;
                out[e2] += hypot(c[2 * b] - c[2 * a], c[2 * b + 1] - c[2 * a + 1]) * (two ? 0.5 : 1.0);
            }
    } else if (use_rest && m->rest) {
        for (e = 0; e < m->ne; ++e) {
            const double *a = m->rest + 2 * m->edges[2 * e], *b = m->rest + 2 * m->edges[2 * e + 1];
            out[e] = hypot(b[0] - a[0], b[1] - a[1]);
        }
    } else {
        for (e = 0; e < m->ne; ++e) out[e] = wr__mesh_dist3(m->pos + 3 * m->edges[2 * e], m->pos + 3 * m->edges[2 * e + 1]);
    }
}

static wr_vec3 wr__mesh_face_cross(const wr_mesh *m, int32_t f) {
    const int32_t *t = m->faces + 3 * f;
    wr_vec3 p0 = wr_v3_load(m->pos + 3 * t[0]);
    return wr_v3_cross(wr_v3_sub(wr_v3_load(m->pos + 3 * t[1]), p0), wr_v3_sub(wr_v3_load(m->pos + 3 * t[2]), p0));
}

WRDEF void wr_mesh_face_areas(const wr_mesh *m, int use_rest, double *out) {
    int32_t f;
    for (f = 0; f < m->nf; ++f) {
        if (use_rest) {
            double uv[6];
            wr_mesh_face_rest(m, f, uv);
            out[f] = wr_polygon_area(uv, 3);
        } else {
            out[f] = 0.5 * wr_v3_norm(wr__mesh_face_cross(m, f));
        }
    }
}

WRDEF void wr_mesh_face_normals(const wr_mesh *m, double *out) {
    int32_t f;
    for (f = 0; f < m->nf; ++f) wr_v3_store(wr_v3_normalized(wr__mesh_face_cross(m, f)), out + 3 * f);
}

WRDEF void wr_mesh_vertex_normals(const wr_mesh *m, double *out) {
    int32_t v, i;
    for (v = 0; v < m->nv; ++v) {
        wr_vec3 s = wr_v3(0.0, 0.0, 0.0);
        /* |cross| = 2 × area, so summing cross products is the area weighting */
        for (i = m->vf_start[v]; i < m->vf_start[v + 1]; ++i) s = wr_v3_add(s, wr__mesh_face_cross(m, m->vf[i]));
        wr_v3_store(wr_v3_normalized(s), out + 3 * v);
    }
}

/* Corner angles [deg] of a triangle given its three side lengths (law of cosines, clamped). */
static double wr__mesh_angle_deg(double adj1, double adj2, double opp) {
    double c;
    if (!(adj1 > 0.0 && adj2 > 0.0)) return 0.0;
    c = (adj1 * adj1 + adj2 * adj2 - opp * opp) / (2.0 * adj1 * adj2);
    if (c > 1.0) c = 1.0;
    if (c < -1.0) c = -1.0;
    return acos(c) * (180.0 / 3.14159265358979323846);
}

/* Vertices within `rings` edge hops of v (v excluded), by breadth-first search over the vertex→face
 * CSR; mark[] is scratch (nv, zero on entry and on return). Returns the count written to out. */
static int32_t wr__mesh_kring(const wr_mesh *m, int32_t v, int32_t rings, uint8_t *mark, int32_t *out) {
    int32_t n = 0, head = 0, level_end, r, i;
    mark[v] = 1;
    out[n++] = v;
    for (r = 0; r < rings; ++r) {
        level_end = n;
        for (; head < level_end; ++head) {
            int32_t u = out[head], t;
            for (t = m->vf_start[u]; t < m->vf_start[u + 1]; ++t) {
                const int32_t *fv = m->faces + 3 * m->vf[t];
                int c;
                for (c = 0; c < 3; ++c)
                    if (!mark[fv[c]]) {
                        mark[fv[c]] = 1;
                        out[n++] = fv[c];
                    }
            }
        }
    }
    for (i = 0; i < n; ++i) mark[out[i]] = 0;
    for (i = 1; i < n; ++i) out[i - 1] = out[i]; /* drop v itself */
    return n - 1;
}

/* Least-squares quadric z = q0 x² + q1 xy + q2 y² + q3 x + q4 y through the points (normal
 * equations, 5×5 Cholesky). Returns 0 when the system is singular. */
static int wr__mesh_fit_quadric(const double *xyz, int32_t n, double q[5]) {
    double A[25], b[5], L[25];
    int32_t i, j, k, p;
    memset(A, 0, sizeof A);
    memset(b, 0, sizeof b);
    for (p = 0; p < n; ++p) {
        double x = xyz[3 * p], y = xyz[3 * p + 1], z = xyz[3 * p + 2];
        double r[5];
        r[0] = x * x;
        r[1] = x * y;
        r[2] = y * y;
        r[3] = x;
        r[4] = y;
        for (i = 0; i < 5; ++i) {
            b[i] += r[i] * z;
            for (j = 0; j < 5; ++j) A[5 * i + j] += r[i] * r[j];
        }
    }
    for (j = 0; j < 5; ++j) {
        double d = A[6 * j];
        for (k = 0; k < j; ++k) d -= L[5 * j + k] * L[5 * j + k];
        if (!(d > 1e-14 * (A[6 * j] > 0.0 ? A[6 * j] : 1.0))) return 0;
        L[6 * j] = sqrt(d);
        for (i = j + 1; i < 5; ++i) {
            double t = A[5 * i + j];
            for (k = 0; k < j; ++k) t -= L[5 * i + k] * L[5 * j + k];
            L[5 * i + j] = t / L[6 * j];
        }
    }
    for (i = 0; i < 5; ++i) { /* L y = b, then Lᵀ q = y */
        double t = b[i];
        for (k = 0; k < i; ++k) t -= L[5 * i + k] * q[k];
        q[i] = t / L[6 * i];
    }
    for (i = 4; i >= 0; --i) {
        double t = q[i];
        for (k = i + 1; k < 5; ++k) t -= L[5 * k + i] * q[k];
        q[i] = t / L[6 * i];
    }
    return 1;
}

/* Principal curvatures of the height field z = f(x, y) = q0 x² + q1 xy + q2 y² + q3 x + q4 y at the
 * origin: I = [[1 + fx², fx fy], [fx fy, 1 + fy²]], II = [[2 q0, q1], [q1, 2 q2]] / sqrt(1 + fx² + fy²),
 * S = I⁻¹ II; k1 >= k2 its eigenvalues, (c0, c1) the parameter vector of k1's direction. */
static void wr__mesh_quadric_curvature(const double q[5], double *k1, double *k2, double c[2]) {
    double fx = q[3], fy = q[4], w = sqrt(1.0 + fx * fx + fy * fy);
    double E = 1.0 + fx * fx, F = fx * fy, G = 1.0 + fy * fy, det = E * G - F * F;
    double L = 2.0 * q[0] / w, M = q[1] / w, N = 2.0 * q[2] / w;
    /* S = I⁻¹ II */
    double s00 = (G * L - F * M) / det, s01 = (G * M - F * N) / det, s10 = (E * M - F * L) / det,
           s11 = (E * N - F * M) / det;
    double tr = s00 + s11, dd = s00 * s11 - s01 * s10, disc = sqrt(fmax(0.0, 0.25 * tr * tr - dd));
    *k1 = 0.5 * tr + disc;
    *k2 = 0.5 * tr - disc;
    /* eigenvector of k1: (s01, k1 - s00) or (k1 - s11, s10), the better conditioned one */
    if (fabs(s01) + fabs(*k1 - s00) >= fabs(*k1 - s11) + fabs(s10)) {
        c[0] = s01;
        c[1] = *k1 - s00;
    } else {
        c[0] = *k1 - s11;
        c[1] = s10;
    }
    if (!(fabs(c[0]) + fabs(c[1]) > 0.0)) {
        c[0] = 1.0;
        c[1] = 0.0;
    }
}

WRDEF wr_status wr_mesh_vertex_curvature(const wr_mesh *m, const double *pos, int32_t rings, double *k1, double *k2,
                                         double *d1, wr_diag *diag) {
    wr_mesh view;
    uint8_t *mark;
    int32_t *ring, v;
    double *nrm, *xyz;
    if (!m) return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "vertex curvature: NULL mesh");
    if (rings <= 0) rings = 5;
    view = *m;
    if (pos) view.pos = (double *)pos; /* read only: wr_mesh_vertex_normals does not write pos */
    mark = (uint8_t *)wr_calloc_array((size_t)m->nv, sizeof(uint8_t));
    ring = (int32_t *)wr_alloc_array((size_t)m->nv + 1, sizeof(int32_t));
    nrm = (double *)wr_alloc_array((size_t)m->nv * 3, sizeof(double));
    xyz = (double *)wr_alloc_array((size_t)m->nv * 3, sizeof(double));
    if (!mark || !ring || !nrm || !xyz) {
        wr_free(mark);
        wr_free(ring);
        wr_free(nrm);
        wr_free(xyz);
        return wr_fail(diag, WR_ERR_NOMEM, -1, "vertex curvature: out of memory for %d vertices", (int)m->nv);
    }
    wr_mesh_vertex_normals(&view, nrm);
    for (v = 0; v < m->nv; ++v) {
        wr_vec3 P = wr_v3_load(view.pos + 3 * v), n = wr_v3_load(nrm + 3 * v), e1, e2, dir;
        double q[5] = {0.0, 0.0, 0.0, 0.0, 0.0}, a1 = 0.0, a2 = 0.0, c[2] = {1.0, 0.0};
        int32_t nr = wr__mesh_kring(m, v, rings, mark, ring), i;
        /* e1: the tangent direction of the longest axis of the world frame not along n (stable) */
        e1 = fabs(n.x) < 0.9 ? wr_v3(1.0, 0.0, 0.0) : wr_v3(0.0, 1.0, 0.0);
        e1 = wr_v3_normalized(wr_v3_sub(e1, wr_v3_scale(n, wr_v3_dot(e1, n))));
        e2 = wr_v3_cross(n, e1);
        for (i = 0; i < nr; ++i) {
            wr_vec3 p = wr_v3_sub(wr_v3_load(view.pos + 3 * ring[i]), P);
            xyz[3 * i] = wr_v3_dot(p, e1);
            xyz[3 * i + 1] = wr_v3_dot(p, e2);
            xyz[3 * i + 2] = wr_v3_dot(p, n);
        }
        if (nr >= 5 && wr__mesh_fit_quadric(xyz, nr, q)) wr__mesh_quadric_curvature(q, &a1, &a2, c);
        if (k1) k1[v] = a1;
        if (k2) k2[v] = a2;
        if (d1) {
            /* (c0, c1) in the height field's tangent basis r_x = e1 + fx n, r_y = e2 + fy n */
            dir = wr_v3_add(wr_v3_scale(wr_v3_add(e1, wr_v3_scale(n, q[3])), c[0]),
                            wr_v3_scale(wr_v3_add(e2, wr_v3_scale(n, q[4])), c[1]));
            if (!(nr >= 5 && a1 != a2)) dir = e1;
            dir = wr_v3_normalized(dir);
            d1[3 * v] = dir.x;
            d1[3 * v + 1] = dir.y;
            d1[3 * v + 2] = dir.z;
        }
    }
    wr_free(mark);
    wr_free(ring);
    wr_free(nrm);
    wr_free(xyz);
    return WR_OK;
}

WRDEF void wr_mesh_quality(const wr_mesh *m, int use_rest, wr_mesh_quality_stats *q) {
    int32_t f, e, k;
    double sum_edge = 0.0, sum_min = 0.0;
    memset(q, 0, sizeof *q);
    q->min_angle_deg = 180.0;
    q->min_edge = INFINITY;
    for (f = 0; f < m->nf; ++f) {
        double uv[6], l[3], lr[3], area, lmax, amin = 180.0;
        wr_mesh_face_rest(m, f, uv);
        for (k = 0; k < 3; ++k) {
            int a = (k + 1) % 3, b = (k + 2) % 3;
            lr[k] = hypot(uv[2 * b] - uv[2 * a], uv[2 * b + 1] - uv[2 * a + 1]);
            l[k] = use_rest ? lr[k]
                            : wr__mesh_dist3(m->pos + 3 * m->faces[3 * f + a], m->pos + 3 * m->faces[3 * f + b]);
        }
        area = wr_polygon_area(uv, 3);
        lmax = fmax(lr[0], fmax(lr[1], lr[2]));
        if (fabs(area) <= WR_MESH_ZERO_AREA_REL * lmax * lmax) ++q->n_zero_area;
        else if (area < 0.0) ++q->n_inverted;
        q->area += use_rest ? area : 0.5 * wr_v3_norm(wr__mesh_face_cross(m, f));
        for (k = 0; k < 3; ++k) {
            double ang = wr__mesh_angle_deg(l[(k + 1) % 3], l[(k + 2) % 3], l[k]);
            if (ang < amin) amin = ang;
            if (ang < q->min_angle_deg) q->min_angle_deg = ang;
            if (ang > q->max_angle_deg) q->max_angle_deg = ang;
        }
        sum_min += amin;
    }
    q->mean_min_angle_deg = m->nf > 0 ? sum_min / m->nf : 0.0;
    if (m->nf == 0) q->min_angle_deg = 0.0;
    {
        double *len = (double *)wr_alloc_array((size_t)m->ne, sizeof(double));
        if (len) {
            wr_mesh_edge_lengths(m, use_rest, len);
            for (e = 0; e < m->ne; ++e) {
                if (len[e] < q->min_edge) q->min_edge = len[e];
                if (len[e] > q->max_edge) q->max_edge = len[e];
                sum_edge += len[e];
            }
            wr_free(len);
        } else {
            /* no memory for the scratch array: per-face pass instead (interior edges counted twice) */
            int32_t cnt = 0;
            for (f = 0; f < m->nf; ++f)
                for (k = 0; k < 3; ++k) {
                    double l = wr__mesh_dist3(m->pos + 3 * m->faces[3 * f + (k + 1) % 3],
                                              m->pos + 3 * m->faces[3 * f + (k + 2) % 3]);
                    q->min_edge = fmin(q->min_edge, l);
                    q->max_edge = fmax(q->max_edge, l);
                    sum_edge += l;
                    ++cnt;
                }
            sum_edge *= cnt > 0 ? (double)m->ne / cnt : 0.0;
        }
    }
    q->mean_edge = m->ne > 0 ? sum_edge / m->ne : 0.0;
    if (m->ne == 0) q->min_edge = 0.0;
    for (e = 0; e < m->ne; ++e) q->n_boundary_edges += (m->edge_faces[2 * e] < 0 || m->edge_faces[2 * e + 1] < 0);
    q->n_loops = m->n_loops;
    q->euler = m->nv - m->ne + m->nf;
}

WRDEF wr_status wr_mesh_ratio_histogram(const double *ratio, int32_t n, int32_t nbins, double lo, double hi,
                                        int32_t *counts) {
    int32_t i;
    double scale;
    if (n < 0 || nbins < 1 || !counts || (n > 0 && !ratio) || !(isfinite(lo) && isfinite(hi) && lo < hi))
        return WR_ERR_INVALID_ARG;
    for (i = 0; i < nbins; ++i) counts[i] = 0;
    scale = (double)nbins / (hi - lo);
    for (i = 0; i < n; ++i) {
        double x = ratio[i];
        int32_t b;
        if (isnan(x)) continue;
        if (x < lo) b = 0;
        else if (x >= hi) b = nbins - 1;
        else {
            double t = (x - lo) * scale;
            b = t >= (double)nbins ? nbins - 1 : (int32_t)t; /* rounding can land exactly on nbins */
        }
        counts[b]++;
    }
    return WR_OK;
}

/* ---- OBJ reader ------------------------------------------------------------------------------- */

/* Limits that keep every count in int32 (3 per face, 6 per corner_rest row). */
#define WR__OBJ_MAX_V (INT32_MAX / 3)
#define WR__OBJ_MAX_F (INT32_MAX / 6)

typedef struct wr__obj_grow {
    void *p;
    size_t n, cap, size;
} wr__obj_grow;

/* Makes room for `add` more elements; 0 on overflow / exhaustion. */
static int wr__obj_reserve(wr__obj_grow *g, size_t add) {
    if (g->n + add > g->cap) {
        size_t cap = g->cap ? g->cap : 64;
        void *np;
        while (cap < g->n + add) {
            if (cap > SIZE_MAX / 2) return 0;
            cap *= 2;
        }
        np = wr_realloc_array(g->p, cap, g->size);
        if (!np) return 0;
        g->p = np;
        g->cap = cap;
    }
    return 1;
}

static int wr__obj_space(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f'; }

static char *wr__obj_skip(char *s) {
    while (*s && wr__obj_space(*s)) ++s;
    return s;
}

/* Parses one finite number token at *s. 1 = ok, 0 = no token (end of line), -1 = malformed. */
static int wr__obj_number(char **s, double *out) {
    char *p = wr__obj_skip(*s), *end;
    if (!*p) return 0;
    *out = strtod(p, &end);
    if (end == p || (*end && !wr__obj_space(*end)) || !isfinite(*out)) return -1;
    *s = end;
    return 1;
}

/* Parses one OBJ index (1-based, or negative = relative to `count` elements so far) into a 0-based
 * index in [0, count). Stops at '/', whitespace or end. 1 = ok, 0 = empty field, -1 = malformed,
 * -2 = out of range. */
static int wr__obj_index(char **s, int64_t count, int32_t *out) {
    char *p = *s;
    int neg = 0;
    int64_t v = 0;
    if (*p == '/' || !*p || wr__obj_space(*p)) return 0;
    if (*p == '-' || *p == '+') neg = *p++ == '-';
    if (*p < '0' || *p > '9') return -1;
    while (*p >= '0' && *p <= '9') {
        if (v > ((int64_t)1 << 40)) return -2; /* far beyond any int32 count: stop before overflow */
        v = v * 10 + (*p++ - '0');
    }
    if (*p && *p != '/' && !wr__obj_space(*p)) return -1;
    *s = p;
    if (neg) v = count - v; /* -1 is the last element */
    else v = v - 1;
    if (v < 0 || v >= count) return -2;
    *out = (int32_t)v;
    return 1;
}

/* FNV-1a hash table of group names → panel id (ids in order of first appearance). */
typedef struct wr__obj_groups {
    char **names;
    int32_t *slot; /* cap entries: panel id or -1 */
    int32_t n, cap;
} wr__obj_groups;

static uint32_t wr__obj_hash(const char *s) {
    uint32_t h = 2166136261u;
    while (*s) h = (h ^ (uint8_t)*s++) * 16777619u;
    return h;
}

/* Returns the id of `name` (adding it), or -1 on out of memory. */
static int32_t wr__obj_group_id(wr__obj_groups *g, const char *name) {
    uint32_t h, i;
    if (2 * (g->n + 1) > g->cap) { /* grow and rehash at load 1/2 */
        int32_t ncap = g->cap ? 2 * g->cap : 16, k;
        int32_t *ns;
        char **nn;
        if (g->cap > INT32_MAX / 4) return -1;
        ns = (int32_t *)wr_alloc_array((size_t)ncap, sizeof(int32_t));
        nn = (char **)wr_realloc_array(g->names, (size_t)ncap / 2, sizeof(char *));
        if (!ns || !nn) {
            wr_free(ns);
            if (nn) g->names = nn;
            return -1;
        }
        g->names = nn;
        for (k = 0; k < ncap; ++k) ns[k] = -1;
        for (k = 0; k < g->n; ++k) {
            i = wr__obj_hash(g->names[k]) & (uint32_t)(ncap - 1);
            while (ns[i] >= 0) i = (i + 1) & (uint32_t)(ncap - 1);
            ns[i] = k;
        }
        wr_free(g->slot);
        g->slot = ns;
        g->cap = ncap;
    }
    h = wr__obj_hash(name);
    for (i = h & (uint32_t)(g->cap - 1); g->slot[i] >= 0; i = (i + 1) & (uint32_t)(g->cap - 1))
        if (strcmp(g->names[g->slot[i]], name) == 0) return g->slot[i];
    {
        size_t len = strlen(name);
        char *copy = (char *)wr_alloc_array(len + 1, 1);
        if (!copy) return -1;
        memcpy(copy, name, len + 1);
        g->names[g->n] = copy;
        g->slot[i] = g->n;
        return g->n++;
    }
}

static void wr__obj_groups_free(wr__obj_groups *g) {
    int32_t k;
    for (k = 0; k < g->n; ++k) wr_free(g->names[k]);
    wr_free(g->names);
    wr_free(g->slot);
}

/* The state of one OBJ parse (wr_mesh_parse_obj): growing arrays, the current line and group. */
typedef struct wr__obj_parse {
    wr__obj_grow V, T, FV, FT, FP, FL, CV, CT; /* FL: OBJ line of each triangle, for topology errors */
    wr__obj_groups groups;
    long line;
    int have_groups, vt_mode; /* vt_mode -1 unknown, 0 faces without vt, 1 faces with vt */
    int32_t panel;
    wr_diag *diag;
} wr__obj_parse;

#define WR__OBJ_ERR(P, ...) wr_fail((P)->diag, WR_ERR_PARSE, (int32_t)((P)->line > INT32_MAX ? INT32_MAX : (P)->line), __VA_ARGS__)
#define WR__OBJ_NOMEM(P) wr_fail((P)->diag, WR_ERR_NOMEM, -1, "OBJ: out of memory at line %ld", (P)->line)

/* "v x y z [w …]" */
static wr_status wr__obj_vertex(wr__obj_parse *P, char *p) {
    double x[3], extra;
    int k, r;
    long line = P->line;
    for (k = 0; k < 3; ++k) {
        r = wr__obj_number(&p, &x[k]);
        if (r == 0) return WR__OBJ_ERR(P, "OBJ line %ld: vertex needs 3 coordinates, got %d", line, k);
        if (r < 0) return WR__OBJ_ERR(P, "OBJ line %ld: vertex coordinate %d is not a finite number", line, k + 1);
    }
    while ((r = wr__obj_number(&p, &extra)) > 0) {
    } /* w or per-vertex colour: ignored */
    if (r < 0) return WR__OBJ_ERR(P, "OBJ line %ld: junk after vertex coordinates", line);
    if (P->V.n / 3 >= (size_t)WR__OBJ_MAX_V) return WR__OBJ_ERR(P, "OBJ line %ld: too many vertices", line);
    if (!wr__obj_reserve(&P->V, 3)) return WR__OBJ_NOMEM(P);
    memcpy((double *)P->V.p + P->V.n, x, sizeof x);
    P->V.n += 3;
    return WR_OK;
}

/* "vt u v [w]" */
static wr_status wr__obj_texcoord(wr__obj_parse *P, char *p) {
    double x[2], extra;
    int k, r;
    long line = P->line;
    for (k = 0; k < 2; ++k) {
        r = wr__obj_number(&p, &x[k]);
        if (r == 0) return WR__OBJ_ERR(P, "OBJ line %ld: texture coordinate needs u and v, got %d numbers", line, k);
        if (r < 0) return WR__OBJ_ERR(P, "OBJ line %ld: texture coordinate %d is not a finite number", line, k + 1);
    }
    while ((r = wr__obj_number(&p, &extra)) > 0) {
    }
    if (r < 0) return WR__OBJ_ERR(P, "OBJ line %ld: junk after texture coordinates", line);
    if (P->T.n / 2 >= (size_t)WR__OBJ_MAX_V) return WR__OBJ_ERR(P, "OBJ line %ld: too many texture coordinates", line);
    if (!wr__obj_reserve(&P->T, 2)) return WR__OBJ_NOMEM(P);
    memcpy((double *)P->T.p + P->T.n, x, sizeof x);
    P->T.n += 2;
    return WR_OK;
}

/* one corner "v", "v/t", "v//n" or "v/t/n" of a face into CV / CT */
static wr_status wr__obj_corner(wr__obj_parse *P, char **pp, int32_t ncorner) {
    char *p = *pp;
    int32_t vi, ti = -1, ni;
    int r, has_t = 0;
    long line = P->line;
    r = wr__obj_index(&p, (int64_t)(P->V.n / 3), &vi);
    if (r == 0 || r == -1) return WR__OBJ_ERR(P, "OBJ line %ld: corner %d: malformed vertex index", line, ncorner + 1);
    if (r == -2)
        return WR__OBJ_ERR(P, "OBJ line %ld: corner %d: vertex index out of range (index 0, or beyond the %zu vertices defined so far)",
                           line, ncorner + 1, P->V.n / 3);
    if (*p == '/') {
        ++p;
        r = wr__obj_index(&p, (int64_t)(P->T.n / 2), &ti);
        if (r == -1 || (r == 0 && *p != '/'))
            return WR__OBJ_ERR(P, "OBJ line %ld: corner %d: malformed texture index", line, ncorner + 1);
        if (r == -2)
            return WR__OBJ_ERR(P, "OBJ line %ld: corner %d: texture index out of range (%zu defined so far)", line,
                               ncorner + 1, P->T.n / 2);
        has_t = r == 1;
        if (*p == '/') {
            /* normals are not stored, but their index must still be well formed */
            ++p;
            r = wr__obj_index(&p, INT32_MAX, &ni);
            if (r != 1) return WR__OBJ_ERR(P, "OBJ line %ld: corner %d: malformed normal index", line, ncorner + 1);
        }
    }
    if (*p && !wr__obj_space(*p)) return WR__OBJ_ERR(P, "OBJ line %ld: corner %d: junk after indices", line, ncorner + 1);
    if (P->vt_mode < 0) P->vt_mode = has_t;
    if (P->vt_mode != has_t)
        return WR__OBJ_ERR(P, "OBJ line %ld: corner %d %s a texture index while earlier corners %s", line, ncorner + 1,
                           has_t ? "has" : "lacks", has_t ? "lack one" : "have one");
    if (ncorner >= WR__OBJ_MAX_F) return WR__OBJ_ERR(P, "OBJ line %ld: polygon too large", line);
    if (!wr__obj_reserve(&P->CV, 1) || !wr__obj_reserve(&P->CT, 1)) return WR__OBJ_NOMEM(P);
    ((int32_t *)P->CV.p)[P->CV.n++] = vi;
    ((int32_t *)P->CT.p)[P->CT.n++] = ti;
    *pp = p;
    return WR_OK;
}

/* "f c1 c2 c3 …": a polygon, fanned into triangles from corner 0 (keeps its orientation) */
static wr_status wr__obj_face(wr__obj_parse *P, char *p) {
    int32_t ncorner = 0, i;
    long line = P->line;
    wr_status st;
    P->CV.n = P->CT.n = 0;
    for (;;) {
        p = wr__obj_skip(p);
        if (!*p) break;
        if ((st = wr__obj_corner(P, &p, ncorner)) != WR_OK) return st;
        ++ncorner;
    }
    if (ncorner < 3) return WR__OBJ_ERR(P, "OBJ line %ld: face needs at least 3 corners, got %d", line, ncorner);
    if (P->FV.n / 3 + (size_t)(ncorner - 2) > (size_t)WR__OBJ_MAX_F) return WR__OBJ_ERR(P, "OBJ line %ld: too many faces", line);
    if (!wr__obj_reserve(&P->FV, 3 * (size_t)(ncorner - 2)) || !wr__obj_reserve(&P->FT, 3 * (size_t)(ncorner - 2)) ||
        !wr__obj_reserve(&P->FP, (size_t)(ncorner - 2)) || !wr__obj_reserve(&P->FL, (size_t)(ncorner - 2)))
        return WR__OBJ_NOMEM(P);
    for (i = 1; i + 1 < ncorner; ++i) {
        int32_t c[3];
        int k;
        c[0] = 0, c[1] = i, c[2] = i + 1;
        for (k = 0; k < 3; ++k) {
            ((int32_t *)P->FV.p)[P->FV.n++] = ((int32_t *)P->CV.p)[c[k]];
            ((int32_t *)P->FT.p)[P->FT.n++] = ((int32_t *)P->CT.p)[c[k]];
        }
        ((int32_t *)P->FP.p)[P->FP.n++] = P->panel;
        ((long *)P->FL.p)[P->FL.n++] = line;
    }
    return WR_OK;
}

/* every line of buf[0 .. end): keyword dispatch (unknown keywords are skipped) */
static wr_status wr__obj_lines(wr__obj_parse *P, char *buf, char *end) {
    char *s;
    wr_status st = WR_OK;
    for (s = buf; s < end || P->line == 0;) {
        char *eol = (char *)memchr(s, '\n', (size_t)(end - s)), *p, *kw;
        size_t kwlen;
        if (!eol) eol = end;
        ++P->line;
        if (memchr(s, 0, (size_t)(eol - s))) return WR__OBJ_ERR(P, "OBJ line %ld: NUL byte", P->line);
        *eol = 0;
        {
            char *hash = strchr(s, '#'); /* comments run to the end of the line */
            if (hash) *hash = 0;
        }
        p = wr__obj_skip(s);
        kw = p;
        while (*p && !wr__obj_space(*p)) ++p;
        kwlen = (size_t)(p - kw);
        if (kwlen == 1 && kw[0] == 'v')
            st = wr__obj_vertex(P, p);
        else if (kwlen == 2 && kw[0] == 'v' && kw[1] == 't')
            st = wr__obj_texcoord(P, p);
        else if (kwlen == 1 && kw[0] == 'f')
            st = wr__obj_face(P, p);
        else if (kwlen == 1 && (kw[0] == 'g' || kw[0] == 'o')) {
            char *name = wr__obj_skip(p), *t = name + strlen(name);
            while (t > name && wr__obj_space(t[-1])) *--t = 0;
            P->panel = wr__obj_group_id(&P->groups, name);
            if (P->panel < 0) return WR__OBJ_NOMEM(P);
            P->have_groups = 1;
        } /* else blank, or vn, vp, usemtl, mtllib, s, l, p, curves…: not needed for a triangle mesh */
        if (st != WR_OK) return st;
        s = eol + 1;
        if (eol == end) break;
    }
    return WR_OK;
}

/* faces with vt: one (u, v) per vertex if every vertex sees a single value (rest), else per-corner
 * rest positions (cr) */
static wr_status wr__obj_rest(wr__obj_parse *P, int32_t nv, int32_t nf, double **rest_out, double **cr_out) {
    uint8_t *set = (uint8_t *)wr_calloc_array((size_t)nv, 1);
    int consistent = 1;
    const int32_t *fv = (const int32_t *)P->FV.p, *ft = (const int32_t *)P->FT.p;
    const double *tv = (const double *)P->T.p;
    double *rest = (double *)wr_alloc_array((size_t)nv * 2, sizeof(double)), *cr;
    int32_t i;
    if (!set || !rest) {
        wr_free(set);
        wr_free(rest);
        return WR__OBJ_NOMEM(P);
    }
    for (i = 0; i < 3 * nf && consistent; ++i) {
        int32_t v = fv[i];
        const double *uv = tv + 2 * ft[i];
        if (!set[v]) {
            rest[2 * v] = uv[0];
            rest[2 * v + 1] = uv[1];
            set[v] = 1;
        } else if (rest[2 * v] != uv[0] || rest[2 * v + 1] != uv[1]) {
            consistent = 0;
        }
    }
    for (i = 0; i < nv && consistent; ++i)
        if (!set[i]) {
            rest[2 * i] = ((const double *)P->V.p)[3 * i];
            rest[2 * i + 1] = ((const double *)P->V.p)[3 * i + 1];
        }
    wr_free(set);
    if (consistent) {
        *rest_out = rest;
        return WR_OK;
    }
    wr_free(rest);
    cr = (double *)wr_alloc_array((size_t)nf * 6, sizeof(double));
    if (!cr) return WR__OBJ_NOMEM(P);
    for (i = 0; i < 3 * nf; ++i) {
        cr[2 * i] = tv[2 * ft[i]];
        cr[2 * i + 1] = tv[2 * ft[i] + 1];
    }
    *cr_out = cr;
    return WR_OK;
}

static void wr__obj_parse_free(wr__obj_parse *P) {
    wr_free(P->V.p);
    wr_free(P->T.p);
    wr_free(P->FV.p);
    wr_free(P->FT.p);
    wr_free(P->FP.p);
    wr_free(P->FL.p);
    wr_free(P->CV.p);
    wr_free(P->CT.p);
    wr__obj_groups_free(&P->groups);
}

/* Hand the parser's group names to *groups (its names array becomes the caller's; one more leading
 * NULL slot when faces came before the first g/o, matching the face_panel shift). */
static wr_status wr__obj_take_groups(wr__obj_parse *P, int shifted, wr_obj_groups *groups) {
    int32_t n = P->groups.n + (shifted ? 1 : 0), k;
    char **names = (char **)wr_alloc_array((size_t)(n > 0 ? n : 1), sizeof(char *));
    if (!names) return wr_fail(P->diag, WR_ERR_NOMEM, -1, "OBJ: out of memory for %d group names", (int)n);
    if (shifted) names[0] = NULL;
    for (k = 0; k < P->groups.n; ++k) names[k + (shifted ? 1 : 0)] = P->groups.names[k];
    P->groups.n = 0; /* the strings now belong to *groups */
    groups->names = names;
    groups->n = n;
    return WR_OK;
}

WRDEF void wr_obj_groups_free(wr_obj_groups *groups) {
    int32_t k;
    if (!groups) return;
    for (k = 0; k < groups->n; ++k) wr_free(groups->names[k]);
    wr_free(groups->names);
    groups->names = NULL;
    groups->n = 0;
}

WRDEF wr_status wr_mesh_parse_obj(wr_mesh *m, const char *text, size_t len, wr_diag *diag) {
    return wr_mesh_parse_obj_groups(m, text, len, NULL, diag);
}

WRDEF wr_status wr_mesh_parse_obj_groups(wr_mesh *m, const char *text, size_t len, wr_obj_groups *groups,
                                         wr_diag *diag) {
    wr__obj_parse P;
    char *buf = NULL;
    wr_status st = WR_OK;
    double *rest = NULL, *cr = NULL;
    int32_t nv, nf, i;

    if (groups) memset(groups, 0, sizeof *groups);
    if (!m) return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "wr_mesh_parse_obj: NULL mesh");
    memset(m, 0, sizeof *m);
    if (!text && len) return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "wr_mesh_parse_obj: NULL text");
    memset(&P, 0, sizeof P);
    P.V.size = P.T.size = sizeof(double);
    P.FV.size = P.FT.size = P.FP.size = P.CV.size = P.CT.size = sizeof(int32_t);
    P.FL.size = sizeof(long);
    P.vt_mode = -1;
    P.panel = -1;
    P.diag = diag;

    /* A private NUL-terminated copy: strtod needs a terminator and the caller's text may lack one. */
    buf = (char *)wr_alloc_array(len + 1, 1);
    if (!buf) return wr_fail(diag, WR_ERR_NOMEM, -1, "OBJ: out of memory for %zu bytes", len);
    if (len) memcpy(buf, text, len);
    buf[len] = 0;
    if ((st = wr__obj_lines(&P, buf, buf + len)) != WR_OK) goto done;

    nv = (int32_t)(P.V.n / 3);
    nf = (int32_t)(P.FV.n / 3);
    if (nv == 0) {
        st = WR__OBJ_ERR(&P, "OBJ: no vertices (%ld lines)", P.line);
        goto done;
    }
    if (nf == 0) {
        st = WR__OBJ_ERR(&P, "OBJ: no faces (%ld lines)", P.line);
        goto done;
    }
    if (P.vt_mode == 1 && (st = wr__obj_rest(&P, nv, nf, &rest, &cr)) != WR_OK) goto done;
    st = wr_mesh_create(m, nv, (const double *)P.V.p, rest, nf, (const int32_t *)P.FV.p, diag);
    if (st == WR_ERR_TOPOLOGY && diag && diag->item >= 0 && diag->item < nf &&
        strncmp(diag->message, "non-manifold vertex", 19) != 0) {
        /* the item is a (triangulated) face: say where it came from */
        size_t ml = strlen(diag->message);
        snprintf(diag->message + ml, sizeof diag->message - ml, " (face %d is from OBJ line %ld)", diag->item,
                 ((const long *)P.FL.p)[diag->item]);
    }
    if (st != WR_OK) goto done;
    if (cr) {
        m->corner_rest = cr;
        cr = NULL;
    }
    if (P.have_groups) {
        int32_t *fp = (int32_t *)P.FP.p;
        int any_none = 0;
        for (i = 0; i < nf; ++i) any_none |= fp[i] < 0;
        if (any_none) /* faces before the first g/o form panel 0 */
            for (i = 0; i < nf; ++i) fp[i] += 1;
        m->face_panel = fp;
        P.FP.p = NULL;
        if (groups) st = wr__obj_take_groups(&P, any_none, groups);
    }
done:
    wr_free(buf);
    wr_free(rest);
    wr_free(cr);
    wr__obj_parse_free(&P);
    if (st != WR_OK) wr_mesh_free(m);
    return st;
}
#undef WR__OBJ_ERR
#undef WR__OBJ_NOMEM

WRDEF wr_status wr_mesh_read_obj(wr_mesh *m, const char *path, wr_diag *diag) {
    return wr_mesh_read_obj_groups(m, path, NULL, diag);
}

WRDEF wr_status wr_mesh_read_obj_groups(wr_mesh *m, const char *path, wr_obj_groups *groups, wr_diag *diag) {
    char *data = NULL;
    size_t n = 0;
    wr_status st;
    if (groups) memset(groups, 0, sizeof *groups);
    if (!m) return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "wr_mesh_read_obj: NULL mesh");
    memset(m, 0, sizeof *m);
    if (!path) return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "wr_mesh_read_obj: NULL path");
    if ((st = wr_file_read(path, &data, &n, diag)) != WR_OK) return st;
    st = wr_mesh_parse_obj_groups(m, data, n, groups, diag);
    wr_free(data);
    return st;
}

/* ---- writers ------------------------------------------------------------------------------------ */

/* Property names for PLY/VTK headers: printable ASCII without whitespace, not empty. */
static wr_status wr__mesh_check_names(int32_t n, const char *const *names, const double *const *values,
                                      const char *what, int xyz_reserved, wr_diag *diag) {
    int32_t k;
    if (n < 0) return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "%s: negative property count %d", what, n);
    if (n > 0 && (!names || !values)) return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "%s: NULL names or values", what);
    for (k = 0; k < n; ++k) {
        const char *c = names[k];
        if (!c || !*c || !values[k]) return wr_fail(diag, WR_ERR_INVALID_ARG, k, "%s: property %d has no name or no values", what, k);
        for (; *c; ++c)
            if (*c <= ' ' || *c > '~')
                return wr_fail(diag, WR_ERR_INVALID_ARG, k, "%s: property %d name '%s' has whitespace or non-ASCII",
                               what, k, names[k]);
        if (xyz_reserved && (!strcmp(names[k], "x") || !strcmp(names[k], "y") || !strcmp(names[k], "z")))
            return wr_fail(diag, WR_ERR_INVALID_ARG, k, "%s: property name '%s' is reserved", what, names[k]);
    }
    return WR_OK;
}

static wr_status wr__mesh_write_begin(const wr_mesh *m, const char *path, wr_afile *f, wr_diag *diag) {
    if (!m || !m->pos || !m->faces) return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "write: empty mesh");
    return wr_afile_open(f, path, diag);
}

/* vn lines: the area-weighted unit vertex normals of m->pos (a zero vector stays zero). */
static wr_status wr__mesh_write_vn(const wr_mesh *m, FILE *fp, wr_diag *diag) {
    double *n = (double *)wr_alloc_array(3 * (size_t)m->nv, sizeof(double));
    int32_t v;
    if (!n) return wr_fail(diag, WR_ERR_NOMEM, -1, "OBJ normals: out of memory");
    wr_mesh_vertex_normals(m, n);
    for (v = 0; v < m->nv; ++v) fprintf(fp, "vn %.9g %.9g %.9g\n", n[3 * v], n[3 * v + 1], n[3 * v + 2]);
    wr_free(n);
    return WR_OK;
}

/* "g <name>" for panel id: the caller's name (spaces -> '_'; an empty or missing one, or one with
 * a character OBJ readers split on, -> "panel<id>"). */
static void wr__mesh_write_group(FILE *fp, const wr_obj_desc *d, int32_t id) {
    const char *name = d->group_names && id >= 0 && id < d->n_group_names ? d->group_names[id] : NULL;
    const char *c;
    int ok = name && *name;
    for (c = name; ok && *c; ++c) ok = (unsigned char)*c >= 0x20 && *c != '#';
    if (!ok) {
        fprintf(fp, "g panel%d\n", (int)id);
        return;
    }
    fputs("g ", fp);
    for (c = name; *c; ++c) fputc(*c == ' ' || *c == '\t' ? '_' : *c, fp);
    fputc('\n', fp);
}

WRDEF wr_status wr_mesh_write_obj(const wr_mesh *m, const char *path, const wr_obj_desc *desc, wr_diag *diag) {
    wr_obj_desc d;
    wr_afile f;
    wr_status st;
    int32_t v, t, k, cur = -1;
    int vt;
    if (desc) d = *desc;
    else memset(&d, 0, sizeof d);
    st = wr__mesh_write_begin(m, path, &f, diag);
    if (st != WR_OK) return st;
    vt = d.no_rest ? 0 : (m->corner_rest ? 2 : (m->rest ? 1 : 0));
    fprintf(f.fp, "# wrinkle mesh.h: %d vertices, %d faces%s\n", m->nv, m->nf,
            vt == 2 ? ", vt per face corner (corner_rest) [m]" : (vt == 1 ? ", vt = rest [m]" : ""));
    if (d.comment) {
        const char *c;
        fputs("# ", f.fp);
        for (c = d.comment; *c; ++c) fputc(*c == '\n' || *c == '\r' ? ' ' : *c, f.fp);
        fputc('\n', f.fp);
    }
    for (v = 0; v < m->nv; ++v)
        fprintf(f.fp, "v %.17g %.17g %.17g\n", m->pos[3 * v], m->pos[3 * v + 1], m->pos[3 * v + 2]);
    if (vt == 1)
        for (v = 0; v < m->nv; ++v) fprintf(f.fp, "vt %.17g %.17g\n", m->rest[2 * v], m->rest[2 * v + 1]);
    if (vt == 2)
        for (k = 0; k < 3 * m->nf; ++k) fprintf(f.fp, "vt %.17g %.17g\n", m->corner_rest[2 * k], m->corner_rest[2 * k + 1]);
    if (d.normals) {
        st = wr__mesh_write_vn(m, f.fp, diag);
        if (st != WR_OK) {
            wr_afile_abort(&f);
            return st;
        }
    }
    for (t = 0; t < m->nf; ++t) {
        const int32_t *c = m->faces + 3 * t;
        if (m->face_panel && !d.no_groups && (t == 0 || m->face_panel[t] != cur)) {
            cur = m->face_panel[t];
            wr__mesh_write_group(f.fp, &d, cur);
        }
        fputc('f', f.fp);
        for (k = 0; k < 3; ++k) {
            int32_t tv = vt == 1 ? c[k] + 1 : 3 * t + k + 1; /* the corner's vt index when vt == 2 */
            if (vt && d.normals) fprintf(f.fp, " %d/%d/%d", c[k] + 1, tv, c[k] + 1);
            else if (vt) fprintf(f.fp, " %d/%d", c[k] + 1, tv);
            else if (d.normals) fprintf(f.fp, " %d//%d", c[k] + 1, c[k] + 1);
            else fprintf(f.fp, " %d", c[k] + 1);
        }
        fputc('\n', f.fp);
    }
    return wr_afile_commit(&f, diag);
}

/* Writes n values with one per line; non-finite → WR_ERR_DOMAIN (the caller aborts the file). */
static wr_status wr__mesh_write_scalars(FILE *fp, const char *name, const double *x, int32_t n, wr_diag *diag) {
    int32_t i;
    for (i = 0; i < n; ++i) {
        if (!isfinite(x[i]))
            return wr_fail(diag, WR_ERR_DOMAIN, i, "property '%s' is not finite at index %d (%g)", name, i, x[i]);
        fprintf(fp, "%.17g\n", x[i]);
    }
    return WR_OK;
}

WRDEF wr_status wr_mesh_write_ply(const wr_mesh *m, const char *path, int32_t nprops, const char *const *names,
                                  const double *const *values, wr_diag *diag) {
    wr_afile f;
    wr_status st;
    int32_t v, k, t;
    st = wr__mesh_check_names(nprops, names, values, "PLY", 1, diag);
    if (st != WR_OK) return st;
    st = wr__mesh_write_begin(m, path, &f, diag);
    if (st != WR_OK) return st;
    fprintf(f.fp, "ply\nformat ascii 1.0\ncomment wrinkle mesh.h\nelement vertex %d\n", m->nv);
    fputs("property double x\nproperty double y\nproperty double z\n", f.fp);
    for (k = 0; k < nprops; ++k) fprintf(f.fp, "property double %s\n", names[k]);
    fprintf(f.fp, "element face %d\nproperty list uchar int vertex_indices\nend_header\n", m->nf);
    for (v = 0; v < m->nv; ++v) {
        fprintf(f.fp, "%.17g %.17g %.17g", m->pos[3 * v], m->pos[3 * v + 1], m->pos[3 * v + 2]);
        for (k = 0; k < nprops; ++k) {
            double x = values[k][v];
            if (!isfinite(x)) {
                wr_afile_abort(&f);
                return wr_fail(diag, WR_ERR_DOMAIN, v, "PLY property '%s' is not finite at vertex %d (%g)", names[k],
                               v, x);
            }
            fprintf(f.fp, " %.17g", x);
        }
        fputc('\n', f.fp);
    }
    for (t = 0; t < m->nf; ++t) fprintf(f.fp, "3 %d %d %d\n", m->faces[3 * t], m->faces[3 * t + 1], m->faces[3 * t + 2]);
    return wr_afile_commit(&f, diag);
}

WRDEF wr_status wr_mesh_write_vtk(const wr_mesh *m, const char *path, int32_t n_point,
                                  const char *const *point_names, const double *const *point_values,
                                  int32_t n_cell, const char *const *cell_names, const double *const *cell_values,
                                  wr_diag *diag) {
    wr_afile f;
    wr_status st;
    int32_t v, k, t;
    st = wr__mesh_check_names(n_point, point_names, point_values, "VTK point data", 0, diag);
    if (st == WR_OK) st = wr__mesh_check_names(n_cell, cell_names, cell_values, "VTK cell data", 0, diag);
    if (st != WR_OK) return st;
    st = wr__mesh_write_begin(m, path, &f, diag);
    if (st != WR_OK) return st;
    fprintf(f.fp, "# vtk DataFile Version 3.0\nwrinkle mesh\nASCII\nDATASET POLYDATA\nPOINTS %d double\n", m->nv);
    for (v = 0; v < m->nv; ++v) fprintf(f.fp, "%.17g %.17g %.17g\n", m->pos[3 * v], m->pos[3 * v + 1], m->pos[3 * v + 2]);
    fprintf(f.fp, "POLYGONS %d %lld\n", m->nf, 4LL * m->nf);
    for (t = 0; t < m->nf; ++t) fprintf(f.fp, "3 %d %d %d\n", m->faces[3 * t], m->faces[3 * t + 1], m->faces[3 * t + 2]);
    if (n_point > 0) fprintf(f.fp, "POINT_DATA %d\n", m->nv);
    for (k = 0; k < n_point && st == WR_OK; ++k) {
        fprintf(f.fp, "SCALARS %s double 1\nLOOKUP_TABLE default\n", point_names[k]);
        st = wr__mesh_write_scalars(f.fp, point_names[k], point_values[k], m->nv, diag);
    }
    if (n_cell > 0 && st == WR_OK) fprintf(f.fp, "CELL_DATA %d\n", m->nf);
    for (k = 0; k < n_cell && st == WR_OK; ++k) {
        fprintf(f.fp, "SCALARS %s double 1\nLOOKUP_TABLE default\n", cell_names[k]);
        st = wr__mesh_write_scalars(f.fp, cell_names[k], cell_values[k], m->nf, diag);
    }
    if (st != WR_OK) {
        wr_afile_abort(&f);
        return st;
    }
    return wr_afile_commit(&f, diag);
}

/* ---- sewing ------------------------------------------------------------------------------------ */

static int32_t wr__mesh_find_root(int32_t *par, int32_t v) {
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
        a = wr__mesh_find_root(par, a);
        b = wr__mesh_find_root(par, b);
        /* the smaller index is the root, so an unpaired prefix keeps its numbering */
        if (a < b)
            par[b] = a;
        else
            par[a] = b;
    }
    for (v = 0; v < in->nv; ++v) {
        int32_t r = wr__mesh_find_root(par, v);
        if (r == v) nid[v] = nn++;
    }
    for (v = 0; v < in->nv; ++v) {
        int32_t j = nid[wr__mesh_find_root(par, v)];
        if (vmap) vmap[v] = j;
        for (i = 0; i < 3; ++i) pos[3 * j + i] += in->pos[3 * v + i];
        cnt[j]++;
    }
    for (v = 0; v < nn; ++v)
        for (i = 0; i < 3; ++i) pos[3 * v + i] /= cnt[v];
    for (f = 0; f < in->nf; ++f) {
        for (k = 0; k < 3; ++k) faces[3 * f + k] = nid[wr__mesh_find_root(par, in->faces[3 * f + k])];
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
#endif /* WRINKLE_MESH_IMPLEMENTATION_DONE */
#endif /* WRINKLE_IMPLEMENTATION */
