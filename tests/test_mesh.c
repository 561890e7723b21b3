/* tests/test_mesh.c — wr_mesh: sign/orientation conventions, topology, validation, generators, I/O. */
#include <criterion/criterion.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "wrinkle/mesh.h"

/* Two triangles sharing the diagonal 1–2 of the unit square:
 *   2---3
 *   | \ |
 *   0---1      faces (0,1,2) and (1,3,2), both CCW. */
static const double sq_rest[8] = {0, 0, 1, 0, 0, 1, 1, 1};
static const int32_t sq_faces[6] = {0, 1, 2, 1, 3, 2};

/* Checks every structural invariant the contract promises; used on every mesh the tests build. */
static void check_invariants(const wr_mesh *m) {
    int32_t e, f, v, k;
    for (e = 0; e < m->ne; ++e) {
        cr_assert_lt(m->edges[2 * e], m->edges[2 * e + 1], "edge %d not low<high", e);
        if (e > 0) {
            int lex = m->edges[2 * e - 2] < m->edges[2 * e] ||
                      (m->edges[2 * e - 2] == m->edges[2 * e] && m->edges[2 * e - 1] < m->edges[2 * e + 1]);
            cr_assert(lex, "edges not in lexicographic order at %d", e);
        }
        cr_assert(m->edge_faces[2 * e] >= 0 || m->edge_faces[2 * e + 1] >= 0, "edge %d has no face", e);
    }
    for (f = 0; f < m->nf; ++f)
        for (k = 0; k < 3; ++k) {
            int32_t e = m->face_edges[3 * f + k];
            int32_t a = m->faces[3 * f + (k + 1) % 3], b = m->faces[3 * f + (k + 2) % 3];
            int s = m->face_edge_sign[3 * f + k];
            cr_assert(e >= 0 && e < m->ne);
            if (s == 1) {
                cr_assert_eq(m->edges[2 * e], a);
                cr_assert_eq(m->edges[2 * e + 1], b);
                cr_assert_eq(m->edge_faces[2 * e], f);
            } else {
                cr_assert_eq(s, -1);
                cr_assert_eq(m->edges[2 * e], b);
                cr_assert_eq(m->edges[2 * e + 1], a);
                cr_assert_eq(m->edge_faces[2 * e + 1], f);
            }
        }
    cr_assert_eq(m->vf_start[0], 0);
    cr_assert_eq(m->vf_start[m->nv], 3 * m->nf);
    for (v = 0; v < m->nv; ++v) {
        int32_t i;
        for (i = m->vf_start[v]; i < m->vf_start[v + 1]; ++i) {
            int32_t f2 = m->vf[i];
            cr_assert(m->faces[3 * f2] == v || m->faces[3 * f2 + 1] == v || m->faces[3 * f2 + 2] == v);
            if (i > m->vf_start[v]) cr_assert_lt(m->vf[i - 1], f2);
        }
    }
    /* boundary loops: consecutive vertices joined by a boundary edge traversed a→b by its face */
    {
        int32_t l, nb = 0;
        for (e = 0; e < m->ne; ++e) nb += (m->edge_faces[2 * e] < 0 || m->edge_faces[2 * e + 1] < 0);
        cr_assert_eq(m->loop_start[0], 0);
        cr_assert_eq(m->loop_start[m->n_loops], nb, "loops cover %d of %d boundary edges",
                     m->loop_start[m->n_loops], nb);
        for (l = 0; l < m->n_loops; ++l) {
            int32_t s0 = m->loop_start[l], s1 = m->loop_start[l + 1], i;
            cr_assert_gt(s1 - s0, 2);
            for (i = s0; i < s1; ++i) {
                int32_t a = m->loop_verts[i], b = m->loop_verts[i + 1 < s1 ? i + 1 : s0], found = 0;
                for (f = 0; f < m->nf && !found; ++f)
                    for (k = 0; k < 3; ++k)
                        if (m->faces[3 * f + (k + 1) % 3] == a && m->faces[3 * f + (k + 2) % 3] == b) {
                            int32_t e2 = m->face_edges[3 * f + k];
                            found = m->edge_faces[2 * e2] < 0 || m->edge_faces[2 * e2 + 1] < 0;
                        }
                cr_assert(found, "loop %d: %d->%d is not a boundary half-edge", l, a, b);
            }
        }
    }
}

Test(mesh, two_triangle_conventions) {
    wr_mesh m;
    wr_diag d;
    cr_assert_eq(wr_mesh_create(&m, 4, NULL, sq_rest, 2, sq_faces, &d), WR_OK, "%s", d.message);
    cr_assert_eq(m.ne, 5);
    /* lexicographic: (0,1) (0,2) (1,2) (1,3) (2,3) */
    {
        static const int32_t want[10] = {0, 1, 0, 2, 1, 2, 1, 3, 2, 3};
        cr_assert_arr_eq(m.edges, want, sizeof want);
    }
    /* face 0 = (0,1,2): edge opposite corner 0 is 1→2 (+1, e=2); opposite 1 is 2→0 (-1, e=1);
     * opposite 2 is 0→1 (+1, e=0) */
    cr_assert_eq(m.face_edges[0], 2);
    cr_assert_eq(m.face_edge_sign[0], 1);
    cr_assert_eq(m.face_edges[1], 1);
    cr_assert_eq(m.face_edge_sign[1], -1);
    cr_assert_eq(m.face_edges[2], 0);
    cr_assert_eq(m.face_edge_sign[2], 1);
    /* face 1 = (1,3,2): opposite 0 is 3→2 (-1, e=4); opposite 1 is 2→1 (-1, e=2); opposite 2 is 1→3 (+1, e=3) */
    cr_assert_eq(m.face_edges[3], 4);
    cr_assert_eq(m.face_edge_sign[3], -1);
    cr_assert_eq(m.face_edges[4], 2);
    cr_assert_eq(m.face_edge_sign[4], -1);
    cr_assert_eq(m.face_edges[5], 3);
    cr_assert_eq(m.face_edge_sign[5], 1);
    /* shared edge 2 = (1,2): face 0 traverses it +, face 1 − */
    cr_assert_eq(m.edge_faces[4], 0);
    cr_assert_eq(m.edge_faces[5], 1);
    cr_assert_eq(m.edge_faces[0], 0);
    cr_assert_eq(m.edge_faces[1], -1);
    cr_assert_eq(m.edge_faces[8], -1); /* (2,3) is traversed 3→2 by face 1 */
    cr_assert_eq(m.edge_faces[9], 1);
    /* pos = (rest, 0) */
    cr_assert_eq(m.pos[3 * 3], 1.0);
    cr_assert_eq(m.pos[3 * 3 + 1], 1.0);
    cr_assert_eq(m.pos[3 * 3 + 2], 0.0);
    /* one boundary loop 0→1→3→2, CCW, starting at the smallest vertex */
    cr_assert_eq(m.n_loops, 1);
    {
        static const int32_t want[4] = {0, 1, 3, 2};
        cr_assert_arr_eq(m.loop_verts, want, sizeof want);
    }
    check_invariants(&m);
    wr_mesh_free(&m);
    cr_assert_null(m.pos);
    cr_assert_eq(m.nv, 0);
    wr_mesh_free(&m); /* safe on a zeroed mesh */
}

/* The point of the sign convention: ω = d0 f (ω_e = f(j) − f(i), i = edges[2e] < j) is closed. */
Test(mesh, gradient_one_form_is_closed) {
    wr_mesh m;
    wr_diag d;
    double fv[4] = {0.3, -1.7, 2.9, 0.11}, omega[5], fv2[121], *om2;
    int32_t e, f, k;
    cr_assert_eq(wr_mesh_create(&m, 4, NULL, sq_rest, 2, sq_faces, &d), WR_OK);
    for (e = 0; e < m.ne; ++e) omega[e] = fv[m.edges[2 * e + 1]] - fv[m.edges[2 * e]];
    for (f = 0; f < m.nf; ++f) {
        double dw = 0.0;
        for (k = 0; k < 3; ++k) dw += m.face_edge_sign[3 * f + k] * omega[m.face_edges[3 * f + k]];
        cr_assert_float_eq(dw, 0.0, 1e-14, "face %d: dω = %g", f, dw);
    }
    /* a non-gradient form (ω = 1 on the shared edge only) is not closed: ±1 on the two faces */
    for (e = 0; e < m.ne; ++e) omega[e] = e == 2 ? 1.0 : 0.0;
    {
        double d0 = 0, d1 = 0;
        for (k = 0; k < 3; ++k) d0 += m.face_edge_sign[k] * omega[m.face_edges[k]];
        for (k = 0; k < 3; ++k) d1 += m.face_edge_sign[3 + k] * omega[m.face_edges[3 + k]];
        cr_assert_eq(d0, 1.0);
        cr_assert_eq(d1, -1.0);
    }
    wr_mesh_free(&m);
    /* the same on a 10×10 rectangle with both diagonal directions */
    cr_assert_eq(wr_mesh_rectangle(&m, 1.0, 1.0, 10, 10, &d), WR_OK);
    om2 = (double *)malloc(sizeof(double) * (size_t)m.ne);
    for (k = 0; k < m.nv; ++k) fv2[k] = sin(3.0 * k) + 0.01 * k * k;
    for (e = 0; e < m.ne; ++e) om2[e] = fv2[m.edges[2 * e + 1]] - fv2[m.edges[2 * e]];
    for (f = 0; f < m.nf; ++f) {
        double dw = 0.0;
        for (k = 0; k < 3; ++k) dw += m.face_edge_sign[3 * f + k] * om2[m.face_edges[3 * f + k]];
        cr_assert_float_eq(dw, 0.0, 1e-12, "face %d: dω = %g", f, dw);
    }
    free(om2);
    wr_mesh_free(&m);
}

Test(mesh, rectangle_euler_and_layout) {
    static const int32_t sizes[][2] = {{1, 1}, {2, 1}, {3, 5}, {8, 8}, {17, 4}};
    size_t t;
    for (t = 0; t < sizeof sizes / sizeof sizes[0]; ++t) {
        wr_mesh m;
        wr_diag d;
        int32_t nx = sizes[t][0], ny = sizes[t][1], f, nbe = 0, e;
        cr_assert_eq(wr_mesh_rectangle(&m, 2.0, 0.5, nx, ny, &d), WR_OK, "%s", d.message);
        cr_assert_eq(m.nv, (nx + 1) * (ny + 1));
        cr_assert_eq(m.nf, 2 * nx * ny);
        cr_assert_eq(m.nv - m.ne + m.nf, 1, "Euler characteristic of a disk");
        for (e = 0; e < m.ne; ++e) nbe += (m.edge_faces[2 * e] < 0 || m.edge_faces[2 * e + 1] < 0);
        cr_assert_eq(nbe, 2 * (nx + ny));
        cr_assert_eq(m.n_loops, 1);
        cr_assert_eq(m.loop_start[1], 2 * (nx + ny));
        /* vertex index j*(nx+1)+i at (w i/nx, h j/ny), corners exact */
        cr_assert_eq(m.rest[2 * nx], 2.0);
        cr_assert_eq(m.rest[2 * ((nx + 1) * (ny + 1) - 1) + 1], 0.5);
        cr_assert_eq(m.pos[3 * (nx + 1) + 1], 0.5 / ny);
        /* all faces CCW with area w h / (2 nx ny) */
        for (f = 0; f < m.nf; ++f) {
            double uv[6], a;
            wr_mesh_face_rest(&m, f, uv);
            a = 0.5 * ((uv[2] - uv[0]) * (uv[5] - uv[1]) - (uv[4] - uv[0]) * (uv[3] - uv[1]));
            cr_assert_float_eq(a, 1.0 / (2.0 * nx * ny), 1e-14);
        }
        /* boundary loop CCW: starts at 0, goes along y = 0 first */
        cr_assert_eq(m.loop_verts[0], 0);
        cr_assert_eq(m.loop_verts[1], 1);
        cr_assert_eq(m.loop_verts[nx], nx);
        cr_assert_eq(m.loop_verts[nx + 1], 2 * nx + 1);
        check_invariants(&m);
        wr_mesh_free(&m);
    }
}

/* Alternating diagonals: half the cells use each direction (no preferred shear direction). */
Test(mesh, rectangle_alternating_diagonals) {
    wr_mesh m;
    int32_t e, up = 0, down = 0;
    cr_assert_eq(wr_mesh_rectangle(&m, 1.0, 1.0, 6, 4, NULL), WR_OK);
    for (e = 0; e < m.ne; ++e) {
        int32_t a = m.edges[2 * e], b = m.edges[2 * e + 1];
        if (b - a == 7 + 1) ++up;        /* (i,j)–(i+1,j+1) */
        else if (b - a == 7 - 1) ++down; /* (i+1,j)–(i,j+1) */
    }
    cr_assert_eq(up, 12);
    cr_assert_eq(down, 12);
    wr_mesh_free(&m);
}

Test(mesh, rectangle_errors) {
    wr_mesh m;
    wr_diag d;
    cr_assert_eq(wr_mesh_rectangle(&m, 0.0, 1.0, 2, 2, &d), WR_ERR_INVALID_ARG);
    cr_assert_eq(wr_mesh_rectangle(&m, 1.0, NAN, 2, 2, &d), WR_ERR_INVALID_ARG);
    cr_assert_eq(wr_mesh_rectangle(&m, 1.0, 1.0, 0, 2, &d), WR_ERR_INVALID_ARG);
    cr_assert_eq(wr_mesh_rectangle(&m, 1.0, 1.0, 2, -1, &d), WR_ERR_INVALID_ARG);
    cr_assert_eq(wr_mesh_rectangle(&m, 1.0, 1.0, 100000, 100000, &d), WR_ERR_OVERFLOW);
    cr_assert_null(m.pos);
}

static void expect_topology_error(int32_t nv, const double *pos, const double *rest, int32_t nf,
                                  const int32_t *faces, int32_t item, const char *needle) {
    wr_mesh m;
    wr_diag d;
    memset(&d, 0, sizeof d);
    m.nv = 77;
    cr_assert_eq(wr_mesh_create(&m, nv, pos, rest, nf, faces, &d), WR_ERR_TOPOLOGY, "expected topology error (%s)",
                 needle);
    cr_assert_eq(d.status, WR_ERR_TOPOLOGY);
    cr_assert_eq(d.item, item, "item %d, expected %d: %s", d.item, item, d.message);
    cr_assert(strstr(d.message, needle) != NULL, "message '%s' lacks '%s'", d.message, needle);
    cr_assert_eq(m.nv, 0);
    cr_assert_null(m.pos);
    cr_assert_null(m.edges);
}

Test(mesh, topology_errors) {
    static const int32_t out_of_range[6] = {0, 1, 2, 1, 4, 2};
    static const int32_t negative[6] = {0, 1, 2, 1, 3, -1};
    static const int32_t repeated[6] = {0, 1, 2, 1, 3, 3};
    static const int32_t flipped[6] = {0, 1, 2, 1, 2, 3}; /* both faces traverse 1→2 */
    /* three faces on edge (0,1): apexes 2, 3, 4 */
    static const double fan_rest[10] = {0, 0, 1, 0, 0.5, 1, 0.5, -1, 0.5, 2};
    static const int32_t nonmanifold[9] = {0, 1, 2, 1, 0, 3, 1, 0, 4};
    /* bow-tie: two triangles sharing only vertex 0 */
    static const double bow_rest[10] = {0, 0, 1, 0.2, 1, -0.2, -1, 0.2, -1, -0.2};
    static const int32_t bowtie[6] = {0, 2, 1, 0, 3, 4};
    double bad_rest[8], bad_pos[12];
    memcpy(bad_rest, sq_rest, sizeof bad_rest);
    bad_rest[5] = NAN;
    expect_topology_error(4, NULL, sq_rest, 2, out_of_range, 1, "face 1");
    expect_topology_error(4, NULL, sq_rest, 2, negative, 1, "out of range");
    expect_topology_error(4, NULL, sq_rest, 2, repeated, 1, "repeats");
    expect_topology_error(4, NULL, sq_rest, 2, flipped, 1, "orientation");
    expect_topology_error(4, NULL, bad_rest, 2, sq_faces, 2, "vertex 2");
    memset(bad_pos, 0, sizeof bad_pos);
    bad_pos[3 * 3 + 2] = INFINITY;
    expect_topology_error(4, bad_pos, sq_rest, 2, sq_faces, 3, "vertex 3");
    expect_topology_error(5, NULL, fan_rest, 3, nonmanifold, 2, "non-manifold edge (0,1)");
    expect_topology_error(5, NULL, bow_rest, 2, bowtie, 0, "non-manifold vertex 0");
}

Test(mesh, invalid_arguments) {
    wr_mesh m;
    wr_diag d;
    cr_assert_eq(wr_mesh_create(&m, 4, NULL, NULL, 2, sq_faces, &d), WR_ERR_INVALID_ARG);
    cr_assert_eq(wr_mesh_create(&m, 4, NULL, sq_rest, 0, sq_faces, &d), WR_ERR_INVALID_ARG);
    cr_assert_eq(wr_mesh_create(&m, 0, NULL, sq_rest, 2, sq_faces, &d), WR_ERR_INVALID_ARG);
    cr_assert_eq(wr_mesh_create(&m, 4, NULL, sq_rest, 2, NULL, &d), WR_ERR_INVALID_ARG);
    cr_assert_eq(wr_mesh_create(NULL, 4, NULL, sq_rest, 2, sq_faces, NULL), WR_ERR_INVALID_ARG);
    cr_assert_null(m.pos);
}

Test(mesh, closed_surface_and_holes) {
    /* octahedron: closed, χ = 2, no boundary loops, every vertex a closed fan of 4 */
    static const double p[18] = {1, 0, 0, -1, 0, 0, 0, 1, 0, 0, -1, 0, 0, 0, 1, 0, 0, -1};
    static const int32_t t[24] = {0, 2, 4, 2, 1, 4, 1, 3, 4, 3, 0, 4, 2, 0, 5, 1, 2, 5, 3, 1, 5, 0, 3, 5};
    wr_mesh m;
    wr_diag d;
    int32_t e;
    cr_assert_eq(wr_mesh_create(&m, 6, p, NULL, 8, t, &d), WR_OK, "%s", d.message);
    cr_assert_eq(m.nv - m.ne + m.nf, 2);
    cr_assert_eq(m.n_loops, 0);
    for (e = 0; e < m.ne; ++e) cr_assert(m.edge_faces[2 * e] >= 0 && m.edge_faces[2 * e + 1] >= 0);
    check_invariants(&m);
    wr_mesh_free(&m);
}

Test(mesh, annulus_two_loops) {
    /* square [0,3]^2 with the middle cell removed: 16 vertices, 8 cells → 16 faces, χ = 0 */
    int32_t faces[48], nf = 0, i, j;
    double rest[32];
    wr_mesh m;
    wr_diag d;
    for (j = 0; j < 4; ++j)
        for (i = 0; i < 4; ++i) {
            rest[2 * (4 * j + i)] = i;
            rest[2 * (4 * j + i) + 1] = j;
        }
    for (j = 0; j < 3; ++j)
        for (i = 0; i < 3; ++i) {
            int32_t v00 = 4 * j + i;
            if (i == 1 && j == 1) continue;
            faces[3 * nf] = v00, faces[3 * nf + 1] = v00 + 1, faces[3 * nf + 2] = v00 + 5, ++nf;
            faces[3 * nf] = v00, faces[3 * nf + 1] = v00 + 5, faces[3 * nf + 2] = v00 + 4, ++nf;
        }
    cr_assert_eq(wr_mesh_create(&m, 16, NULL, rest, nf, faces, &d), WR_OK, "%s", d.message);
    cr_assert_eq(m.nv - m.ne + m.nf, 0);
    cr_assert_eq(m.n_loops, 2);
    /* outer loop starts at 0 (CCW), hole starts at 5 and runs clockwise: 5→9→10→6 */
    cr_assert_eq(m.loop_start[1] - m.loop_start[0], 12);
    cr_assert_eq(m.loop_start[2] - m.loop_start[1], 4);
    {
        static const int32_t hole[4] = {5, 9, 10, 6};
        cr_assert_arr_eq(m.loop_verts + 12, hole, sizeof hole);
        cr_assert_eq(m.loop_verts[0], 0);
        cr_assert_eq(m.loop_verts[1], 1);
    }
    check_invariants(&m);
    wr_mesh_free(&m);
}

Test(mesh, copy_is_deep) {
    wr_mesh a, b;
    wr_diag d;
    cr_assert_eq(wr_mesh_rectangle(&a, 1.0, 1.0, 3, 2, &d), WR_OK);
    cr_assert_eq(wr_mesh_copy(&b, &a, &d), WR_OK);
    cr_assert_eq(b.ne, a.ne);
    cr_assert_neq(b.pos, a.pos);
    cr_assert_arr_eq(b.pos, a.pos, sizeof(double) * 3 * (size_t)a.nv);
    cr_assert_arr_eq(b.edges, a.edges, sizeof(int32_t) * 2 * (size_t)a.ne);
    cr_assert_arr_eq(b.loop_verts, a.loop_verts, sizeof(int32_t) * (size_t)a.loop_start[a.n_loops]);
    cr_assert_null(b.corner_rest);
    wr_mesh_free(&a);
    check_invariants(&b);
    wr_mesh_free(&b);
}

Test(mesh, face_rest_sources) {
    /* 3D triangle without rest: isometric flattening keeps edge lengths, area >= 0 */
    static const double p[9] = {1, 2, 3, 1, 2, 5, 4, 2, 3};
    static const int32_t t[3] = {0, 1, 2};
    wr_mesh m;
    double uv[6];
    cr_assert_eq(wr_mesh_create(&m, 3, p, NULL, 1, t, NULL), WR_OK);
    wr_mesh_face_rest(&m, 0, uv);
    cr_assert_float_eq(hypot(uv[2] - uv[0], uv[3] - uv[1]), 2.0, 1e-14);
    cr_assert_float_eq(hypot(uv[4] - uv[0], uv[5] - uv[1]), 3.0, 1e-14);
    cr_assert_float_eq(hypot(uv[4] - uv[2], uv[5] - uv[3]), sqrt(13.0), 1e-14);
    cr_assert_gt(uv[5], 0.0);
    wr_mesh_free(&m);
}
