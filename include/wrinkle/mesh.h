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
 * API (create/free pairs: wr_mesh_create|wr_mesh_copy|wr_mesh_rectangle → wr_mesh_free)
 *   wr_mesh_create(m, nv, pos3, rest2, nf, faces, diag)   copy inputs, validate, build topology
 *   wr_mesh_free(m)                                       free and zero (safe on a zeroed mesh)
 *   wr_mesh_copy(dst, src, diag)                          deep copy
 *   wr_mesh_face_rest(m, f, uv[6])                        rest-domain corners of face f
 *   wr_mesh_rectangle(m, w, h, nx, ny, diag)              regular grid on [0,w]×[0,h], alternating diagonals
 *
 * EXAMPLE
 *     wr_mesh m; wr_diag d;
 *     if (wr_mesh_rectangle(&m, 1.0, 0.5, 20, 10, &d) != WR_OK) { puts(d.message); return 1; }
 *     for (int32_t f = 0; f < m.nf; ++f) {               // dω of a one-form omega[ne]
 *         double dw = 0.0;
 *         for (int k = 0; k < 3; ++k) dw += m.face_edge_sign[3*f+k] * omega[m.face_edges[3*f+k]];
 *     }
 *     printf("%d boundary loop(s), %d edges\n", m.n_loops, m.ne);
 *     wr_mesh_free(&m);
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
 *   (item = face), a face repeating a vertex (item = face), a non-finite coordinate (item = vertex),
 *   an edge shared by more than two faces (item = the third face; message names the edge's vertices),
 *   two faces traversing a shared edge in the same direction, i.e. inconsistent orientation (item =
 *   the second face), a non-manifold vertex whose incident faces form more than one fan (bow-tie;
 *   item = vertex). The contract lists non-finite coordinates with the topology errors, so they are
 *   WR_ERR_TOPOLOGY too. Counts < 1, NULL faces, or pos3 and rest2 both NULL → WR_ERR_INVALID_ARG.
 *   Orientation is checked combinatorially; faces whose rest area is <= 0 are not rejected here
 *   (a quality report counts them). Vertices in no face are allowed (empty vf range).
 *
 * ON UNITS
 *   Metres everywhere (pos, rest, corner_rest).
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

#ifdef __cplusplus
}
#endif
#endif /* WRINKLE_MESH_H */

/* ============================================================================================ */
#ifdef WRINKLE_IMPLEMENTATION
#ifndef WRINKLE_MESH_IMPLEMENTATION_DONE
#define WRINKLE_MESH_IMPLEMENTATION_DONE

#include <math.h>
#include <string.h>

#ifdef __cplusplus
extern "C" {
#endif

WRDEF void wr_mesh_free(wr_mesh *m) {
    if (!m) return;
    wr_free(m->pos);
    wr_free(m->rest);
    wr_free(m->corner_rest);
    wr_free(m->faces);
    wr_free(m->face_panel);
    wr_free(m->edges);
    wr_free(m->face_edges);
    wr_free(m->face_edge_sign);
    wr_free(m->edge_faces);
    wr_free(m->vf_start);
    wr_free(m->vf);
    wr_free(m->loop_start);
    wr_free(m->loop_verts);
    memset(m, 0, sizeof *m);
}

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

/* Builds edges, face_edges, face_edge_sign, edge_faces, vf CSR and boundary loops from nv, nf,
 * faces (already range-checked). O(nf + nv): two stable counting-sort passes order the 3nf
 * half-edges by (low vertex, high vertex); equal keys are then adjacent. */
static wr_status wr__mesh_build_topology(wr_mesh *m, wr_diag *diag) {
    const int32_t nv = m->nv, nf = m->nf;
    const size_t nh = (size_t)3 * (size_t)nf;
    int32_t *cnt = NULL, *tmp = NULL, *ord = NULL, *bnext = NULL;
    uint8_t *seen = NULL;
    wr_status st = WR_OK;
    size_t i, ne = 0;
    int32_t v;

    cnt = (int32_t *)wr_alloc_array((size_t)nv + 1, sizeof(int32_t));
    tmp = (int32_t *)wr_alloc_array(nh, sizeof(int32_t));
    ord = (int32_t *)wr_alloc_array(nh, sizeof(int32_t));
    if (!cnt || !tmp || !ord) {
        st = wr_fail(diag, WR_ERR_NOMEM, -1, "mesh topology: out of memory (%d faces)", nf);
        goto done;
    }
#define WR__HE_A(h) (m->faces[3 * ((h) / 3) + ((h) % 3 + 1) % 3])
#define WR__HE_B(h) (m->faces[3 * ((h) / 3) + ((h) % 3 + 2) % 3])
#define WR__HE_LO(h) (WR__HE_A(h) < WR__HE_B(h) ? WR__HE_A(h) : WR__HE_B(h))
#define WR__HE_HI(h) (WR__HE_A(h) < WR__HE_B(h) ? WR__HE_B(h) : WR__HE_A(h))
    /* pass 1: stable counting sort by high vertex into tmp */
    memset(cnt, 0, sizeof(int32_t) * ((size_t)nv + 1));
    for (i = 0; i < nh; ++i) cnt[WR__HE_HI((int32_t)i) + 1]++;
    for (v = 0; v < nv; ++v) cnt[v + 1] += cnt[v];
    for (i = 0; i < nh; ++i) tmp[cnt[WR__HE_HI((int32_t)i)]++] = (int32_t)i;
    /* pass 2: stable counting sort by low vertex into ord → ordered by (lo, hi, half-edge) */
    memset(cnt, 0, sizeof(int32_t) * ((size_t)nv + 1));
    for (i = 0; i < nh; ++i) cnt[WR__HE_LO(tmp[i]) + 1]++;
    for (v = 0; v < nv; ++v) cnt[v + 1] += cnt[v];
    for (i = 0; i < nh; ++i) ord[cnt[WR__HE_LO(tmp[i])]++] = tmp[i];

    /* group equal keys: count edges and validate manifoldness / orientation */
    for (i = 0; i < nh;) {
        size_t j = i + 1;
        int32_t h0 = ord[i], lo = WR__HE_LO(h0), hi = WR__HE_HI(h0);
        while (j < nh && WR__HE_LO(ord[j]) == lo && WR__HE_HI(ord[j]) == hi) ++j;
        if (j - i > 2) {
            st = wr_fail(diag, WR_ERR_TOPOLOGY, ord[i + 2] / 3,
                         "non-manifold edge (%d,%d): shared by faces %d, %d and %d", lo, hi, ord[i] / 3,
                         ord[i + 1] / 3, ord[i + 2] / 3);
            goto done;
        }
        if (j - i == 2 && (WR__HE_A(ord[i]) == lo) == (WR__HE_A(ord[i + 1]) == lo)) {
            st = wr_fail(diag, WR_ERR_TOPOLOGY, ord[i + 1] / 3,
                         "inconsistent orientation: faces %d and %d both traverse edge %d->%d", ord[i] / 3,
                         ord[i + 1] / 3, WR__HE_A(ord[i]), WR__HE_B(ord[i]));
            goto done;
        }
        ++ne;
        i = j;
    }
    if (ne > (size_t)INT32_MAX / 2) {
        st = wr_fail(diag, WR_ERR_OVERFLOW, -1, "mesh has too many edges (%zu)", ne);
        goto done;
    }
    m->ne = (int32_t)ne;
    m->edges = (int32_t *)wr_alloc_array(2 * ne, sizeof(int32_t));
    m->edge_faces = (int32_t *)wr_alloc_array(2 * ne, sizeof(int32_t));
    m->face_edges = (int32_t *)wr_alloc_array(nh, sizeof(int32_t));
    m->face_edge_sign = (int8_t *)wr_alloc_array(nh, sizeof(int8_t));
    m->vf_start = (int32_t *)wr_alloc_array((size_t)nv + 1, sizeof(int32_t));
    m->vf = (int32_t *)wr_alloc_array(nh, sizeof(int32_t));
    if (!m->edges || !m->edge_faces || !m->face_edges || !m->face_edge_sign || !m->vf_start || !m->vf) {
        st = wr_fail(diag, WR_ERR_NOMEM, -1, "mesh topology: out of memory (%zu edges)", ne);
        goto done;
    }
    ne = 0;
    for (i = 0; i < nh;) {
        size_t j = i;
        int32_t h0 = ord[i], lo = WR__HE_LO(h0), hi = WR__HE_HI(h0);
        m->edges[2 * ne] = lo;
        m->edges[2 * ne + 1] = hi;
        m->edge_faces[2 * ne] = m->edge_faces[2 * ne + 1] = -1;
        while (j < nh && WR__HE_LO(ord[j]) == lo && WR__HE_HI(ord[j]) == hi) {
            int32_t h = ord[j];
            int plus = WR__HE_A(h) == lo;
            m->face_edges[h] = (int32_t)ne;
            m->face_edge_sign[h] = (int8_t)(plus ? 1 : -1);
            m->edge_faces[2 * ne + (plus ? 0 : 1)] = h / 3;
            ++j;
        }
        ++ne;
        i = j;
    }

    /* vertex → faces CSR, faces ascending per vertex */
    memset(m->vf_start, 0, sizeof(int32_t) * ((size_t)nv + 1));
    for (i = 0; i < nh; ++i) m->vf_start[m->faces[i] + 1]++;
    for (v = 0; v < nv; ++v) m->vf_start[v + 1] += m->vf_start[v];
    memcpy(cnt, m->vf_start, sizeof(int32_t) * ((size_t)nv + 1));
    for (i = 0; i < nh; ++i) m->vf[cnt[m->faces[i]]++] = (int32_t)(i / 3);

    /* Manifold vertices: the faces around v must form one fan. Walking across the edge (v, next)
     * of each face is an injective map on v's faces (consistent orientation), so the walk from
     * the first face either returns or stops at the boundary; then walk the other way. */
    for (v = 0; v < nv; ++v) {
        int32_t deg = m->vf_start[v + 1] - m->vf_start[v], f0, f, count = 1;
        int dir;
        if (deg == 0) continue;
        f0 = m->vf[m->vf_start[v]];
        for (dir = 0; dir < 2; ++dir) {
            int closed = 0;
            f = f0;
            while (count <= deg) {
                int c = m->faces[3 * f] == v ? 0 : (m->faces[3 * f + 1] == v ? 1 : 2);
                /* dir 0 crosses (v, next): edge opposite corner c+2; dir 1 crosses (prev, v): opposite c+1 */
                int32_t e = m->face_edges[3 * f + (dir == 0 ? (c + 2) % 3 : (c + 1) % 3)];
                int32_t g = m->edge_faces[2 * e] == f ? m->edge_faces[2 * e + 1] : m->edge_faces[2 * e];
                if (g == f0) closed = 1;
                if (g < 0 || g == f0) break;
                f = g;
                ++count; /* bounded by deg + 1: the map is injective, so no face repeats before f0 */
            }
            if (closed) break; /* closed fan: nothing on the other side */
        }
        if (count != deg) {
            st = wr_fail(diag, WR_ERR_TOPOLOGY, v,
                         "non-manifold vertex %d: its %d faces form more than one fan (one fan has %d)", v,
                         deg, count);
            goto done;
        }
    }

    /* Boundary loops: boundary half-edges a→b in face traversal order; bnext[a] = b is unique at
     * a manifold vertex (one open fan has exactly one outgoing boundary half-edge). */
    {
        int32_t nb = 0, l = 0, pos = 0;
        bnext = (int32_t *)wr_alloc_array((size_t)nv, sizeof(int32_t));
        seen = (uint8_t *)wr_calloc_array((size_t)nv, 1);
        if (!bnext || !seen) {
            st = wr_fail(diag, WR_ERR_NOMEM, -1, "mesh topology: out of memory");
            goto done;
        }
        for (v = 0; v < nv; ++v) bnext[v] = -1;
        for (i = 0; i < nh; ++i) {
            int32_t e = m->face_edges[i];
            if (m->edge_faces[2 * e] >= 0 && m->edge_faces[2 * e + 1] >= 0) continue;
            bnext[WR__HE_A((int32_t)i)] = WR__HE_B((int32_t)i);
            ++nb;
        }
        /* count loops */
        for (v = 0; v < nv; ++v) {
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
    }
#undef WR__HE_A
#undef WR__HE_B
#undef WR__HE_LO
#undef WR__HE_HI
done:
    wr_free(cnt);
    wr_free(tmp);
    wr_free(ord);
    wr_free(bnext);
    wr_free(seen);
    if (st != WR_OK) wr__mesh_free_topology(m);
    return st;
}

WRDEF wr_status wr_mesh_create(wr_mesh *m, int32_t nv, const double *pos3, const double *rest2, int32_t nf,
                               const int32_t *faces, wr_diag *diag) {
    int32_t i, f;
    wr_status st;
    if (!m) return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "wr_mesh_create: NULL mesh");
    memset(m, 0, sizeof *m);
    if (nv < 1 || nf < 1) return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "empty mesh (nv=%d, nf=%d)", nv, nf);
    if (nf > INT32_MAX / 3)
        return wr_fail(diag, WR_ERR_OVERFLOW, -1, "too many faces (%d): 3*nf must fit int32", nf);
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
            return wr_fail(diag, WR_ERR_TOPOLOGY, i, "vertex %d has a non-finite position (%g,%g,%g)", i,
                           pos3[3 * i], pos3[3 * i + 1], pos3[3 * i + 2]);
        if (rest2 && !(isfinite(rest2[2 * i]) && isfinite(rest2[2 * i + 1])))
            return wr_fail(diag, WR_ERR_TOPOLOGY, i, "vertex %d has a non-finite rest coordinate (%g,%g)", i,
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

#ifdef __cplusplus
}
#endif
#endif /* WRINKLE_MESH_IMPLEMENTATION_DONE */
#endif /* WRINKLE_IMPLEMENTATION */
