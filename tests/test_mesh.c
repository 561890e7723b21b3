/* tests/test_mesh.c — wr_mesh: sign/orientation conventions, topology, validation, generators, I/O. */
#define _POSIX_C_SOURCE 200809L /* mkdtemp, opendir for the atomic-write tests */
#include <criterion/criterion.h>
#include <dirent.h>
#include <stdlib.h>
#include <unistd.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "wrinkle/mesh.h"

#define WR_TEST_PI 3.14159265358979323846

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

static void expect_create_error(wr_status want, int32_t nv, const double *pos, const double *rest, int32_t nf,
                                const int32_t *faces, int32_t item, const char *needle) {
    wr_mesh m;
    wr_diag d;
    wr_status st;
    memset(&d, 0, sizeof d);
    m.nv = 77;
    st = wr_mesh_create(&m, nv, pos, rest, nf, faces, &d);
    cr_assert_eq(st, want, "expected %s, got %s (%s)", wr_status_string(want), wr_status_string(st), needle);
    cr_assert_eq(d.status, want);
    cr_assert_eq(d.item, item, "item %d, expected %d: %s", d.item, item, d.message);
    cr_assert(strstr(d.message, needle) != NULL, "message '%s' lacks '%s'", d.message, needle);
    cr_assert_eq(m.nv, 0);
    cr_assert_null(m.pos);
    cr_assert_null(m.edges);
}

static void expect_topology_error(int32_t nv, const double *pos, const double *rest, int32_t nf,
                                  const int32_t *faces, int32_t item, const char *needle) {
    expect_create_error(WR_ERR_TOPOLOGY, nv, pos, rest, nf, faces, item, needle);
}

/* wr_mesh_create orders half-edges by their low vertex, then by the high vertex within each low
 * vertex (insertion sort up to 32, a qsort beyond): a fan of 100 faces puts 200 half-edges under
 * vertex 0, so the large-bucket path must give the same conventions as the small one. Everything is
 * checked against the face list directly (ON CONVENTIONS). */
Test(mesh, topology_of_a_large_fan_matches_the_conventions) {
    enum { N = 100 };
    double rest[2 * (N + 1)];
    int32_t faces[3 * N], i, e, f, k;
    wr_mesh m;
    wr_diag d;
    rest[0] = rest[1] = 0.0;
    for (i = 0; i < N; ++i) {
        rest[2 * (i + 1)] = cos(6.283185307179586 * i / N);
        rest[2 * (i + 1) + 1] = sin(6.283185307179586 * i / N);
        /* faces listed from the last, corners rotated, so neither order is the sorted one */
        faces[3 * (N - 1 - i)] = 1 + i;
        faces[3 * (N - 1 - i) + 1] = 1 + (i + 1) % N;
        faces[3 * (N - 1 - i) + 2] = 0;
    }
    cr_assert_eq(wr_mesh_create(&m, N + 1, NULL, rest, N, faces, &d), WR_OK, "%s", d.message);
    cr_expect_eq(m.ne, 2 * N);
    cr_expect_eq(m.n_loops, 1);
    cr_expect_eq(m.loop_start[1], N);
    for (e = 0; e < m.ne; ++e) {
        cr_expect_lt(m.edges[2 * e], m.edges[2 * e + 1], "edge %d", e);
        if (e > 0)
            cr_expect(m.edges[2 * e - 2] < m.edges[2 * e] ||
                          (m.edges[2 * e - 2] == m.edges[2 * e] && m.edges[2 * e - 1] < m.edges[2 * e + 1]),
                      "edges %d and %d out of lexicographic order", e - 1, e);
        /* spokes (0, i) are interior, rim edges are boundary */
        cr_expect_eq(m.edge_faces[2 * e] >= 0 && m.edge_faces[2 * e + 1] >= 0, m.edges[2 * e] == 0, "edge %d", e);
    }
    for (f = 0; f < m.nf; ++f)
        for (k = 0; k < 3; ++k) {
            int32_t a = m.faces[3 * f + (k + 1) % 3], b = m.faces[3 * f + (k + 2) % 3], ee = m.face_edges[3 * f + k];
            int plus = a < b;
            cr_expect(m.edges[2 * ee] == (plus ? a : b) && m.edges[2 * ee + 1] == (plus ? b : a), "face %d edge %d", f, k);
            cr_expect_eq(m.face_edge_sign[3 * f + k], plus ? 1 : -1, "face %d edge %d", f, k);
            cr_expect_eq(m.edge_faces[2 * ee + (plus ? 0 : 1)], f, "face %d edge %d", f, k);
        }
    wr_mesh_free(&m);
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
    /* non-finite coordinates are geometry errors, not topology ones */
    expect_create_error(WR_ERR_GEOMETRY, 4, NULL, bad_rest, 2, sq_faces, 2, "vertex 2");
    memset(bad_pos, 0, sizeof bad_pos);
    bad_pos[3 * 3 + 2] = INFINITY;
    expect_create_error(WR_ERR_GEOMETRY, 4, bad_pos, sq_rest, 2, sq_faces, 3, "vertex 3");
    expect_topology_error(5, NULL, fan_rest, 3, nonmanifold, 2, "non-manifold edge (0,1)");
    expect_topology_error(5, NULL, bow_rest, 2, bowtie, 0, "non-manifold vertex 0");
    {
        /* two closed tetrahedra sharing only vertex 0: two closed fans there, every edge manifold */
        static const double tp[21] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, -1, 0, 0, 0, -1, 0, 0, 0, -1};
        static const int32_t tt[24] = {0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3, 0, 5, 4, 0, 4, 6, 0, 6, 5, 4, 5, 6};
        wr_mesh one;
        cr_assert_eq(wr_mesh_create(&one, 4, tp, NULL, 4, tt, NULL), WR_OK, "a single tetrahedron is fine");
        cr_assert_eq(one.nv - one.ne + one.nf, 2);
        cr_assert_eq(one.n_loops, 0);
        wr_mesh_free(&one);
        expect_topology_error(7, tp, NULL, 8, tt, 0, "non-manifold vertex 0");
    }
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

/* ---- generators ---------------------------------------------------------------------------------- */

Test(mesh, disk_counts_area_quality) {
    int32_t n;
    for (n = 1; n <= 6; ++n) {
        wr_mesh m;
        wr_diag d;
        wr_mesh_quality_stats q;
        double R = 0.7, want;
        int32_t f;
        cr_assert_eq(wr_mesh_disk(&m, R, n, &d), WR_OK, "%s", d.message);
        cr_assert_eq(m.nv, 1 + 3 * n * (n + 1));
        cr_assert_eq(m.nf, 6 * n * n);
        cr_assert_eq(m.nv - m.ne + m.nf, 1);
        cr_assert_eq(m.n_loops, 1);
        cr_assert_eq(m.loop_start[1], 6 * n);
        check_invariants(&m);
        wr_mesh_quality(&m, 1, &q);
        cr_assert_eq(q.n_inverted, 0);
        cr_assert_eq(q.n_zero_area, 0);
        /* the disk is the regular 6n-gon inscribed in radius R */
        want = 0.5 * 6 * n * R * R * sin(2.0 * WR_TEST_PI / (6 * n));
        cr_assert_float_eq(q.area, want, 1e-13, "n=%d area %.17g want %.17g", n, q.area, want);
        cr_assert_gt(q.min_angle_deg, 25.0, "n=%d min angle %g", n, q.min_angle_deg);
        for (f = 0; f < m.nf; ++f) {
            double uv[6];
            wr_mesh_face_rest(&m, f, uv);
            cr_assert_gt(0.5 * ((uv[2] - uv[0]) * (uv[5] - uv[1]) - (uv[4] - uv[0]) * (uv[3] - uv[1])), 0.0);
        }
        wr_mesh_free(&m);
    }
    {
        wr_mesh m;
        cr_assert_eq(wr_mesh_disk(&m, -1.0, 3, NULL), WR_ERR_INVALID_ARG);
        cr_assert_eq(wr_mesh_disk(&m, 1.0, 0, NULL), WR_ERR_INVALID_ARG);
        cr_assert_eq(wr_mesh_disk(&m, 1.0, 100000, NULL), WR_ERR_OVERFLOW);
    }
}

Test(mesh, cylinder_is_a_closed_tube) {
    wr_mesh m;
    wr_diag d;
    wr_mesh_quality_stats q;
    const double R = 0.3, H = 0.5;
    const int32_t nu = 12, nh = 4;
    double *len, *nrm, du = 2.0 * WR_TEST_PI * R / nu;
    int32_t e, v, i;
    cr_assert_eq(wr_mesh_cylinder_flat(&m, R, H, nu, nh, &d), WR_OK, "%s", d.message);
    cr_assert_eq(m.nv, nu * (nh + 1));
    cr_assert_eq(m.nf, 2 * nu * nh);
    cr_assert_eq(m.nv - m.ne + m.nf, 0, "tube: χ = 0");
    cr_assert_null(m.rest);
    cr_assert_not_null(m.corner_rest);
    cr_assert_eq(m.n_loops, 2);
    check_invariants(&m);
    /* bottom loop runs in +u (mesh on the left), top loop in −u */
    for (i = 0; i < nu; ++i) cr_assert_eq(m.loop_verts[i], i);
    cr_assert_eq(m.loop_verts[nu], nh * nu);
    cr_assert_eq(m.loop_verts[nu + 1], nh * nu + nu - 1);
    /* rest domain is the unrolled rectangle: total area 2πR H, no inverted faces */
    wr_mesh_quality(&m, 1, &q);
    cr_assert_float_eq(q.area, 2.0 * WR_TEST_PI * R * H, 1e-14);
    cr_assert_eq(q.n_inverted, 0);
    cr_assert_float_eq(q.min_angle_deg, atan((H / nh) / du) * 180.0 / WR_TEST_PI < atan(du / (H / nh)) * 180.0 / WR_TEST_PI
                                            ? atan((H / nh) / du) * 180.0 / WR_TEST_PI
                                            : atan(du / (H / nh)) * 180.0 / WR_TEST_PI,
                       1e-9);
    /* rest lengths of horizontal edges are du (also across the seam); 3D lengths are chords */
    len = (double *)malloc(sizeof(double) * (size_t)m.ne);
    wr_mesh_edge_lengths(&m, 1, len);
    for (e = 0; e < m.ne; ++e) {
        int32_t a = m.edges[2 * e], b = m.edges[2 * e + 1];
        if (a / nu == b / nu) cr_assert_float_eq(len[e], du, 1e-14, "edge %d-%d rest length %g", a, b, len[e]);
    }
    wr_mesh_edge_lengths(&m, 0, len);
    for (e = 0; e < m.ne; ++e) {
        int32_t a = m.edges[2 * e], b = m.edges[2 * e + 1];
        if (a / nu == b / nu) cr_assert_float_eq(len[e], 2.0 * R * sin(WR_TEST_PI / nu), 1e-14);
    }
    free(len);
    /* outward normals */
    nrm = (double *)malloc(sizeof(double) * 3 * (size_t)m.nv);
    wr_mesh_vertex_normals(&m, nrm);
    for (v = 0; v < m.nv; ++v) {
        double radial = (nrm[3 * v] * m.pos[3 * v] + nrm[3 * v + 1] * m.pos[3 * v + 1]) / R;
        cr_assert_gt(radial, 0.95, "vertex %d normal·radial = %g", v, radial);
    }
    free(nrm);
    wr_mesh_free(&m);
    cr_assert_eq(wr_mesh_cylinder_flat(&m, R, H, 2, 4, NULL), WR_ERR_INVALID_ARG);
    cr_assert_eq(wr_mesh_cylinder_flat(&m, R, 0.0, 6, 4, NULL), WR_ERR_INVALID_ARG);
}

/* ---- measures ------------------------------------------------------------------------------------- */

Test(mesh, lengths_areas_normals_on_rectangle) {
    wr_mesh m;
    double len[64], area[32], fn[96], vn[64 * 3];
    int32_t e, f, v;
    cr_assert_eq(wr_mesh_rectangle(&m, 3.0, 2.0, 3, 2, NULL), WR_OK); /* unit cells */
    cr_assert_leq(m.ne, 64);
    wr_mesh_edge_lengths(&m, 1, len);
    for (e = 0; e < m.ne; ++e) {
        int32_t dd = m.edges[2 * e + 1] - m.edges[2 * e];
        double want = (dd == 1 || dd == 4) ? 1.0 : sqrt(2.0);
        cr_assert_float_eq(len[e], want, 1e-15, "edge %d", e);
    }
    wr_mesh_face_areas(&m, 1, area);
    for (f = 0; f < m.nf; ++f) cr_assert_float_eq(area[f], 0.5, 1e-15);
    /* the 3D areas of the flat mesh are the same half cells (make mutate: a 3D area without its ½
     * survived the ">= 0.5" check below) */
    wr_mesh_face_areas(&m, 0, area);
    for (f = 0; f < m.nf; ++f) cr_assert_float_eq(area[f], 0.5, 1e-15, "3D area of face %d: %g", (int)f, area[f]);
    wr_mesh_face_normals(&m, fn);
    wr_mesh_vertex_normals(&m, vn);
    for (f = 0; f < m.nf; ++f) cr_assert_eq(fn[3 * f + 2], 1.0);
    for (v = 0; v < m.nv; ++v) cr_assert_eq(vn[3 * v + 2], 1.0);
    /* lift vertex 5 (interior): 3D lengths and areas change, rest ones do not */
    m.pos[3 * 5 + 2] = 1.0;
    wr_mesh_edge_lengths(&m, 0, len);
    for (e = 0; e < m.ne; ++e)
        if (m.edges[2 * e] == 5 || m.edges[2 * e + 1] == 5) {
            int32_t dd = m.edges[2 * e + 1] - m.edges[2 * e];
            cr_assert_float_eq(len[e], (dd == 1 || dd == 4) ? sqrt(2.0) : sqrt(3.0), 1e-15);
        }
    wr_mesh_face_areas(&m, 0, area);
    for (f = 0; f < m.nf; ++f) cr_assert_geq(area[f], 0.5);
    wr_mesh_face_areas(&m, 1, area);
    for (f = 0; f < m.nf; ++f) cr_assert_float_eq(area[f], 0.5, 1e-15);
    wr_mesh_free(&m);
}

Test(mesh, quality_counts_inverted_and_degenerate) {
    wr_mesh m;
    wr_mesh_quality_stats q;
    cr_assert_eq(wr_mesh_rectangle(&m, 2.0, 2.0, 2, 2, NULL), WR_OK);
    wr_mesh_quality(&m, 1, &q);
    cr_assert_float_eq(q.min_angle_deg, 45.0, 1e-12);
    cr_assert_float_eq(q.max_angle_deg, 90.0, 1e-12);
    cr_assert_float_eq(q.mean_min_angle_deg, 45.0, 1e-12);
    cr_assert_float_eq(q.min_edge, 1.0, 1e-15);
    cr_assert_float_eq(q.max_edge, sqrt(2.0), 1e-15);
    cr_assert_float_eq(q.mean_edge, (12.0 + 4.0 * sqrt(2.0)) / 16.0, 1e-15);
    cr_assert_float_eq(q.area, 4.0, 1e-14);
    cr_assert_eq(q.n_inverted, 0);
    cr_assert_eq(q.n_zero_area, 0);
    cr_assert_eq(q.n_boundary_edges, 8);
    cr_assert_eq(q.n_loops, 1);
    cr_assert_eq(q.euler, 1);
    /* move centre vertex 4 past the corner (0,0): the faces touching it flip or collapse */
    m.rest[2 * 4] = 0.0;
    m.rest[2 * 4 + 1] = 0.0; /* onto vertex 0 */
    wr_mesh_quality(&m, 1, &q);
    cr_assert_eq(q.n_zero_area, 4, "zero-area %d", q.n_zero_area); /* also (1,2,4) and (3,4,6): collinear */
    m.rest[2 * 4] = -0.5;
    m.rest[2 * 4 + 1] = -0.5; /* faces around 4 whose opposite edge lies on x=0 or y=0 invert */
    wr_mesh_quality(&m, 1, &q);
    cr_assert_eq(q.n_zero_area, 0);
    cr_assert_eq(q.n_inverted, 4, "inverted %d", q.n_inverted); /* (0,1,4) (0,4,3) (1,2,4) (3,4,6) */
    /* 3D quality of the same mesh is unaffected by rest edits */
    wr_mesh_quality(&m, 0, &q);
    cr_assert_float_eq(q.min_angle_deg, 45.0, 1e-12);
    wr_mesh_free(&m);
}

Test(mesh, ratio_histogram) {
    static const double r[10] = {0.0, 0.49, 0.5, 0.99, 1.0, 1.5, 1.999, 2.0, -3.0, 7.0};
    double with_nan[3] = {0.25, NAN, 0.75};
    int32_t c[4];
    cr_assert_eq(wr_mesh_ratio_histogram(r, 10, 4, 0.0, 2.0, c), WR_OK);
    /* bins [0,.5) [.5,1) [1,1.5) [1.5,2): -3 clamps to bin 0, 2.0 and 7.0 to bin 3 */
    cr_assert_eq(c[0], 3);
    cr_assert_eq(c[1], 2);
    cr_assert_eq(c[2], 1);
    cr_assert_eq(c[3], 4);
    cr_assert_eq(wr_mesh_ratio_histogram(with_nan, 3, 2, 0.0, 1.0, c), WR_OK);
    cr_assert_eq(c[0], 1);
    cr_assert_eq(c[1], 1);
    cr_assert_eq(wr_mesh_ratio_histogram(r, 10, 0, 0.0, 2.0, c), WR_ERR_INVALID_ARG);
    cr_assert_eq(wr_mesh_ratio_histogram(r, 10, 4, 2.0, 2.0, c), WR_ERR_INVALID_ARG);
    cr_assert_eq(wr_mesh_ratio_histogram(r, 10, 4, 0.0, INFINITY, c), WR_ERR_INVALID_ARG);
    cr_assert_eq(wr_mesh_ratio_histogram(r, -1, 4, 0.0, 2.0, c), WR_ERR_INVALID_ARG);
    cr_assert_eq(wr_mesh_ratio_histogram(NULL, 0, 4, 0.0, 2.0, c), WR_OK);
    cr_assert_eq(c[0] + c[1] + c[2] + c[3], 0);
}

Test(mesh, corner_rest_and_panels_setters) {
    wr_mesh m;
    wr_diag d;
    double cr[12] = {0, 0, 2, 0, 0, 2, 2, 0, 2, 2, 0, 2}, uv[6], len[5];
    int32_t panel[2] = {3, 1}, badp[2] = {0, -1};
    cr_assert_eq(wr_mesh_create(&m, 4, NULL, sq_rest, 2, sq_faces, &d), WR_OK);
    cr_assert_eq(wr_mesh_set_corner_rest(&m, cr, &d), WR_OK);
    wr_mesh_face_rest(&m, 1, uv); /* corner_rest wins over rest */
    cr_assert_eq(uv[2], 2.0);
    cr_assert_eq(uv[3], 2.0);
    wr_mesh_edge_lengths(&m, 1, len);
    cr_assert_float_eq(len[2], 2.0 * sqrt(2.0), 1e-15);
    cr[7] = NAN;
    cr_assert_eq(wr_mesh_set_corner_rest(&m, cr, &d), WR_ERR_GEOMETRY);
    cr_assert_eq(d.item, 1);
    cr_assert_eq(wr_mesh_set_corner_rest(&m, NULL, &d), WR_OK);
    wr_mesh_face_rest(&m, 1, uv);
    cr_assert_eq(uv[2], 1.0);
    cr_assert_eq(wr_mesh_set_face_panel(&m, panel, &d), WR_OK);
    cr_assert_eq(m.face_panel[0], 3);
    cr_assert_eq(wr_mesh_set_face_panel(&m, badp, &d), WR_ERR_INVALID_ARG);
    cr_assert_eq(d.item, 1);
    cr_assert_eq(m.face_panel[1], 1, "failed set keeps the old panels");
    wr_mesh_free(&m);
}

/* ---- I/O ---------------------------------------------------------------------------------------- */

static char tmpdir[256];

static void make_tmpdir(void) {
    snprintf(tmpdir, sizeof tmpdir, "/tmp/wr_mesh_test_XXXXXX");
    cr_assert_not_null(mkdtemp(tmpdir));
}

/* Counts directory entries other than . and .. (and reports leftover temporaries). */
static int count_entries(const char *dir, int *n_tmp) {
    DIR *dp = opendir(dir);
    struct dirent *de;
    int n = 0;
    *n_tmp = 0;
    cr_assert_not_null(dp);
    while ((de = readdir(dp)) != NULL) {
        if (!strcmp(de->d_name, ".") || !strcmp(de->d_name, "..")) continue;
        ++n;
        if (strstr(de->d_name, ".wrtmp")) ++*n_tmp;
    }
    closedir(dp);
    return n;
}

static void remove_tmpdir(void) {
    DIR *dp = opendir(tmpdir);
    struct dirent *de;
    char p[600];
    if (!dp) return;
    while ((de = readdir(dp)) != NULL) {
        if (!strcmp(de->d_name, ".") || !strcmp(de->d_name, "..")) continue;
        snprintf(p, sizeof p, "%s/%s", tmpdir, de->d_name);
        remove(p);
    }
    closedir(dp);
    rmdir(tmpdir);
}

static char *slurp(const char *path, size_t *len) {
    FILE *fp = fopen(path, "rb");
    char *b;
    long n;
    cr_assert_not_null(fp, "cannot open %s", path);
    fseek(fp, 0, SEEK_END);
    n = ftell(fp);
    fseek(fp, 0, SEEK_SET);
    b = (char *)malloc((size_t)n + 1);
    cr_assert_eq(fread(b, 1, (size_t)n, fp), (size_t)n);
    b[n] = 0;
    fclose(fp);
    if (len) *len = (size_t)n;
    return b;
}

Test(mesh_io, obj_round_trip_rest_and_groups) {
    wr_mesh a, b;
    wr_diag d;
    char path[400];
    int32_t *panel, f, v, n_tmp;
    make_tmpdir();
    snprintf(path, sizeof path, "%s/rect.obj", tmpdir);
    cr_assert_eq(wr_mesh_rectangle(&a, 1.0 / 3.0, 0.7, 5, 3, &d), WR_OK);
    for (v = 0; v < a.nv; ++v) a.pos[3 * v + 2] = 0.01 * sin(1.0 + v); /* non-trivial 3D, inexact decimals */
    panel = (int32_t *)malloc(sizeof(int32_t) * (size_t)a.nf);
    for (f = 0; f < a.nf; ++f) panel[f] = f < 10 ? 0 : (f < 20 ? 1 : 2); /* ids in order of appearance */
    cr_assert_eq(wr_mesh_set_face_panel(&a, panel, &d), WR_OK);
    cr_assert_eq(wr_mesh_write_obj(&a, path, NULL, &d), WR_OK, "%s", d.message);
    cr_assert_eq(count_entries(tmpdir, &n_tmp), 1);
    cr_assert_eq(n_tmp, 0);
    cr_assert_eq(wr_mesh_read_obj(&b, path, &d), WR_OK, "%s", d.message);
    cr_assert_eq(b.nv, a.nv);
    cr_assert_eq(b.nf, a.nf);
    cr_assert_arr_eq(b.pos, a.pos, sizeof(double) * 3 * (size_t)a.nv, "positions round-trip exactly");
    cr_assert_not_null(b.rest);
    cr_assert_null(b.corner_rest);
    cr_assert_arr_eq(b.rest, a.rest, sizeof(double) * 2 * (size_t)a.nv);
    cr_assert_arr_eq(b.faces, a.faces, sizeof(int32_t) * 3 * (size_t)a.nf);
    cr_assert_not_null(b.face_panel);
    cr_assert_arr_eq(b.face_panel, panel, sizeof(int32_t) * (size_t)a.nf);
    cr_assert_arr_eq(b.edges, a.edges, sizeof(int32_t) * 2 * (size_t)a.ne);
    wr_mesh_free(&b);
    /* without vt and groups */
    {
        wr_obj_desc od;
        memset(&od, 0, sizeof od);
        od.no_rest = 1;
        od.no_groups = 1;
        od.comment = "two\nlines";
        cr_assert_eq(wr_mesh_write_obj(&a, path, &od, &d), WR_OK);
        cr_assert_eq(wr_mesh_read_obj(&b, path, &d), WR_OK, "%s", d.message);
        cr_assert_null(b.rest);
        cr_assert_null(b.face_panel);
        cr_assert_arr_eq(b.pos, a.pos, sizeof(double) * 3 * (size_t)a.nv);
        wr_mesh_free(&b);
    }
    free(panel);
    wr_mesh_free(&a);
    remove_tmpdir();
}

/* OBJ with normals and named groups (wr_obj_desc.normals, group_names): every vn line is the
 * area-weighted vertex normal (compared with wr_mesh_vertex_normals), every face corner names its
 * own vertex's vn, the groups carry the caller's names (space -> '_', an empty name -> panel<id>),
 * and the file still reads back to the same mesh and panels. */
Test(mesh_io, obj_normals_and_group_names) {
    wr_mesh a, b;
    wr_diag d;
    wr_obj_desc od;
    char path[400], *txt, *line, *save = NULL;
    const char *names[3] = {"front bodice", "", "skirt"};
    int32_t *panel, f, v, n_vn = 0, n_f = 0, n_g = 0;
    double *nrm;
    make_tmpdir();
    snprintf(path, sizeof path, "%s/named.obj", tmpdir);
    cr_assert_eq(wr_mesh_rectangle(&a, 0.3, 0.2, 4, 3, &d), WR_OK);
    for (v = 0; v < a.nv; ++v) a.pos[3 * v + 2] = 0.05 * a.pos[3 * v] * a.pos[3 * v]; /* curved: normals tilt */
    panel = (int32_t *)malloc(sizeof(int32_t) * (size_t)a.nf);
    for (f = 0; f < a.nf; ++f) panel[f] = f < 8 ? 0 : (f < 16 ? 1 : 2);
    cr_assert_eq(wr_mesh_set_face_panel(&a, panel, &d), WR_OK);
    nrm = (double *)malloc(sizeof(double) * 3 * (size_t)a.nv);
    wr_mesh_vertex_normals(&a, nrm);
    memset(&od, 0, sizeof od);
    od.normals = 1;
    od.group_names = names;
    od.n_group_names = 3;
    cr_assert_eq(wr_mesh_write_obj(&a, path, &od, &d), WR_OK, "%s", d.message);
    txt = slurp(path, NULL);
    for (line = strtok_r(txt, "\n", &save); line; line = strtok_r(NULL, "\n", &save)) {
        if (!strncmp(line, "vn ", 3)) {
            double x, y, z;
            cr_assert_eq(sscanf(line + 3, "%lf %lf %lf", &x, &y, &z), 3);
            cr_assert(n_vn < a.nv);
            cr_assert(fabs(x - nrm[3 * n_vn]) < 1e-8 && fabs(y - nrm[3 * n_vn + 1]) < 1e-8 &&
                          fabs(z - nrm[3 * n_vn + 2]) < 1e-8,
                      "vn %d: (%g %g %g) vs (%g %g %g)", (int)n_vn, x, y, z, nrm[3 * n_vn], nrm[3 * n_vn + 1],
                      nrm[3 * n_vn + 2]);
            ++n_vn;
        } else if (!strncmp(line, "f ", 2)) {
            int c[3][3], k;
            cr_assert_eq(sscanf(line + 2, "%d/%d/%d %d/%d/%d %d/%d/%d", &c[0][0], &c[0][1], &c[0][2], &c[1][0], &c[1][1],
                                &c[1][2], &c[2][0], &c[2][1], &c[2][2]),
                         9, "face line '%s'", line);
            for (k = 0; k < 3; ++k) {
                cr_assert_eq(c[k][0], a.faces[3 * n_f + k] + 1);
                cr_assert_eq(c[k][2], c[k][0], "a corner's vn is its own vertex's normal");
            }
            ++n_f;
        } else if (!strncmp(line, "g ", 2)) {
            static const char *want[3] = {"front_bodice", "panel1", "skirt"};
            cr_assert(n_g < 3);
            cr_assert_str_eq(line + 2, want[n_g]);
            ++n_g;
        }
    }
    cr_assert_eq(n_vn, a.nv);
    cr_assert_eq(n_f, a.nf);
    cr_assert_eq(n_g, 3);
    free(txt);
    cr_assert_eq(wr_mesh_read_obj(&b, path, &d), WR_OK, "%s", d.message);
    cr_assert_arr_eq(b.pos, a.pos, sizeof(double) * 3 * (size_t)a.nv);
    cr_assert_arr_eq(b.rest, a.rest, sizeof(double) * 2 * (size_t)a.nv);
    cr_assert_arr_eq(b.face_panel, panel, sizeof(int32_t) * (size_t)a.nf);
    wr_mesh_free(&b);
    /* without vt: v//vn corners, still read back */
    od.no_rest = 1;
    cr_assert_eq(wr_mesh_write_obj(&a, path, &od, &d), WR_OK, "%s", d.message);
    txt = slurp(path, NULL);
    cr_assert_not_null(strstr(txt, "\nf 1//1 "), "v//vn corners without vt");
    free(txt);
    cr_assert_eq(wr_mesh_read_obj(&b, path, &d), WR_OK, "%s", d.message);
    cr_assert_null(b.rest);
    cr_assert_arr_eq(b.pos, a.pos, sizeof(double) * 3 * (size_t)a.nv);
    wr_mesh_free(&b);
    free(nrm);
    free(panel);
    wr_mesh_free(&a);
    remove_tmpdir();
}

/* The reader hands back the g/o names by panel id, so a program that writes the mesh again keeps
 * the names it was given (wrinkle-statics / wrinkle-tfw on a wrinkle-mesh OBJ). Faces before the first
 * g form the unnamed panel 0 (names[0] NULL); a name seen again reuses its id. */
Test(mesh_io, obj_group_names_read_back) {
    static const char txt[] = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 2 0 0\nv 2 1 0\n"
                              "f 1 2 3\ng sleeve\nf 1 3 4\ng collar band\nf 2 5 6\ng sleeve\nf 2 6 3\n";
    static const int32_t want_panel[4] = {0, 1, 2, 1};
    wr_mesh m, b;
    wr_obj_groups g, g2;
    wr_obj_desc od;
    wr_diag d;
    char path[400];
    cr_assert_eq(wr_mesh_parse_obj_groups(&m, txt, sizeof txt - 1, &g, &d), WR_OK, "%s", d.message);
    cr_assert_arr_eq(m.face_panel, want_panel, sizeof want_panel);
    cr_assert_eq(g.n, 3);
    cr_assert_null(g.names[0], "faces before the first g: unnamed panel 0");
    cr_assert_str_eq(g.names[1], "sleeve");
    cr_assert_str_eq(g.names[2], "collar band");
    /* written back with those names and read again: same panels, same names (space as '_') */
    make_tmpdir();
    snprintf(path, sizeof path, "%s/groups.obj", tmpdir);
    memset(&od, 0, sizeof od);
    od.group_names = (const char *const *)g.names;
    od.n_group_names = g.n;
    cr_assert_eq(wr_mesh_write_obj(&m, path, &od, &d), WR_OK, "%s", d.message);
    cr_assert_eq(wr_mesh_read_obj_groups(&b, path, &g2, &d), WR_OK, "%s", d.message);
    cr_assert_eq(g2.n, 3, "panel0 (the unnamed one), sleeve, collar_band");
    cr_assert_str_eq(g2.names[0], "panel0");
    cr_assert_str_eq(g2.names[1], "sleeve");
    cr_assert_str_eq(g2.names[2], "collar_band");
    cr_assert_arr_eq(b.face_panel, want_panel, sizeof want_panel);
    wr_obj_groups_free(&g2);
    wr_mesh_free(&b);
    /* no g/o lines: no names; a parse error leaves the names zeroed */
    cr_assert_eq(wr_mesh_parse_obj_groups(&b, "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", 32, &g2, &d), WR_OK, "%s", d.message);
    cr_assert_eq(g2.n, 0);
    cr_assert_null(g2.names);
    wr_mesh_free(&b);
    g2.n = 7;
    cr_assert_eq(wr_mesh_parse_obj_groups(&b, "g a\nv 0 0\n", 10, &g2, &d), WR_ERR_PARSE);
    cr_assert_eq(g2.n, 0);
    cr_assert_null(g2.names);
    wr_obj_groups_free(&g2); /* zeroed: fine */
    wr_obj_groups_free(&g);
    wr_mesh_free(&m);
    remove_tmpdir();
}

Test(mesh_io, obj_round_trip_corner_rest) {
    wr_mesh a, b;
    wr_diag d;
    char path[400];
    make_tmpdir();
    snprintf(path, sizeof path, "%s/tube.obj", tmpdir);
    cr_assert_eq(wr_mesh_cylinder_flat(&a, 0.2, 0.3, 8, 3, &d), WR_OK);
    cr_assert_eq(wr_mesh_write_obj(&a, path, NULL, &d), WR_OK, "%s", d.message);
    cr_assert_eq(wr_mesh_read_obj(&b, path, &d), WR_OK, "%s", d.message);
    cr_assert_null(b.rest, "seam vertices have two vt values → corner_rest");
    cr_assert_not_null(b.corner_rest);
    cr_assert_arr_eq(b.corner_rest, a.corner_rest, sizeof(double) * 6 * (size_t)a.nf);
    cr_assert_arr_eq(b.pos, a.pos, sizeof(double) * 3 * (size_t)a.nv);
    cr_assert_eq(b.n_loops, 2);
    wr_mesh_free(&a);
    wr_mesh_free(&b);
    remove_tmpdir();
}

static wr_status parse_str(wr_mesh *m, const char *s, wr_diag *d) { return wr_mesh_parse_obj(m, s, strlen(s), d); }

Test(mesh_io, obj_features) {
    wr_mesh m;
    wr_diag d;
    /* quad + pentagon with v/vt/vn, v//vn and negative indices, CRLF, comments, groups, no final newline */
    const char *txt = "# test\r\n"
                      "mtllib x.mtl\n"
                      "v 0 0 0\nv 1 0 0\nv 1 1 0 1.0\nv 0 1 0 0.5 0.5 0.5\n"
                      "vn 0 0 1\n"
                      "f 1//1 2//1 3//1 4//1   # a quad\n"
                      "o second\n"
                      "v 2 0 0\r\nv 3 0.5 0\nv 2 1 0\n"
                      "usemtl red\ns off\n"
                      "f 2 -3 -2 -1 3";
    cr_assert_eq(parse_str(&m, txt, &d), WR_OK, "%s", d.message);
    cr_assert_eq(m.nv, 7);
    cr_assert_eq(m.nf, 2 + 3);
    {
        static const int32_t want[15] = {0, 1, 2, 0, 2, 3, 1, 4, 5, 1, 5, 6, 1, 6, 2};
        cr_assert_arr_eq(m.faces, want, sizeof want);
    }
    cr_assert_not_null(m.face_panel);
    cr_assert_eq(m.face_panel[0], 0);
    cr_assert_eq(m.face_panel[1], 0);
    cr_assert_eq(m.face_panel[2], 1);
    cr_assert_eq(m.face_panel[4], 1);
    cr_assert_null(m.rest);
    cr_assert_eq(m.pos[3 * 5], 3.0);
    wr_mesh_free(&m);
    /* vt per vertex consistent → rest; text without a NUL terminator (exact-size heap copy) */
    {
        const char *src = "v 0 0 5\nv 1 0 5\nv 0 1 5\nvt 0.1 0.2\nvt 0.3 0.2\nvt 0.1 0.4\nf 1/1 2/2 3/3";
        size_t n = strlen(src);
        char *exact = (char *)malloc(n);
        memcpy(exact, src, n);
        cr_assert_eq(wr_mesh_parse_obj(&m, exact, n, &d), WR_OK, "%s", d.message);
        free(exact);
        cr_assert_not_null(m.rest);
        cr_assert_eq(m.rest[2], 0.3);
        cr_assert_eq(m.rest[5], 0.4);
        cr_assert_eq(m.pos[2], 5.0);
        wr_mesh_free(&m);
    }
    /* two faces giving vertex 2 different vt → corner_rest */
    cr_assert_eq(parse_str(&m, "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nvt 0 0\nvt 1 0\nvt 0 1\nvt 1 1\nvt 9 9\n"
                               "f 1/1 2/2 3/3\nf 2/5 4/4 3/3\n", &d),
              WR_OK, "%s", d.message);
    cr_assert_null(m.rest);
    cr_assert_not_null(m.corner_rest);
    cr_assert_eq(m.corner_rest[6], 9.0);
    wr_mesh_free(&m);
    /* topology errors surface from the parser too */
    cr_assert_eq(parse_str(&m, "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nf 1 2 3\n\nf 2 3 4\n", &d), WR_ERR_TOPOLOGY);
    cr_assert_null(m.pos);
    cr_assert_eq(d.item, 1);
    cr_assert(strstr(d.message, "orientation") && strstr(d.message, "OBJ line 7"), "%s", d.message);
}

Test(mesh_io, hostile_obj_gives_parse_errors) {
    static const struct {
        const char *text;
        int32_t line;
    } bad[] = {
        {"", 1},
        {"# only a comment\n", 2},
        {"v 0 0 0\nv 1 0 0\nv 0 1 0\n", 4},                       /* no faces */
        {"f 1 2 3\n", 1},                                        /* no vertices yet */
        {"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 0\n", 4},             /* index 0 */
        {"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n", 4},             /* beyond the vertices */
        {"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 -4\n", 4},            /* relative before the first */
        {"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 2147483648\n", 4},
        {"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 99999999999999999999999999999\n", 4},
        {"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 -99999999999999999999999999999\n", 4},
        {"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2\n", 4},               /* truncated face */
        {"v 0 0 0\nv 1 0 0\nv 0 1 0\nf\n", 4},
        {"v 0 0 0\nv 1 0\n", 2},                                 /* truncated vertex */
        {"v 0 0 0\nv\n", 2},
        {"v 0 nan 0\n", 1},
        {"v 0 0 inf\n", 1},
        {"v 1e999 0 0\n", 1},
        {"v 0 0 0x\n", 1},
        {"v 0 0 0 abc\n", 1},
        {"vt 0.5\n", 1},
        {"vt nan 0\n", 1},
        {"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1/ 2 3\n", 4},            /* empty vt field */
        {"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1/x 2/1 3/1\n", 4},
        {"v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nf 1/1 2/2 3/1\n", 5}, /* vt index out of range */
        {"v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nf 1/1 2 3\n", 5},     /* vt on some corners only */
        {"v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nf 1/1 2/1 3/1\nf 1 2 3\n", 6},
        {"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1//x 2 3\n", 4},
        {"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3abc\n", 4},
        {"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3/1/1/1\n", 4},
        {"v 0 0 0\nv 1 0 0\nv 0 1 0\nf - 2 3\n", 4},
        {"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1.5 2 3\n", 4},
    };
    size_t i;
    for (i = 0; i < sizeof bad / sizeof bad[0]; ++i) {
        wr_mesh m;
        wr_diag d;
        char needle[32];
        wr_status st;
        memset(&d, 0, sizeof d);
        st = parse_str(&m, bad[i].text, &d);
        cr_assert_eq(st, WR_ERR_PARSE, "case %zu: status %s (%s)", i, wr_status_string(st), d.message);
        cr_assert_null(m.pos);
        if (strstr(d.message, "no faces") || strstr(d.message, "no vertices")) continue;
        cr_assert_eq(d.item, bad[i].line, "case %zu: item %d, want line %d (%s)", i, d.item, bad[i].line, d.message);
        snprintf(needle, sizeof needle, "line %d", bad[i].line);
        cr_assert(strstr(d.message, needle) != NULL, "case %zu: '%s' lacks '%s'", i, d.message, needle);
    }
    /* embedded NUL byte */
    {
        static const char nul[] = "v 0 0 0\nv 1 0\0 0\n";
        wr_mesh m;
        wr_diag d;
        cr_assert_eq(wr_mesh_parse_obj(&m, nul, sizeof nul - 1, &d), WR_ERR_PARSE);
        cr_assert_eq(d.item, 2);
    }
    {
        wr_mesh m;
        wr_diag d;
        cr_assert_eq(wr_mesh_parse_obj(&m, NULL, 0, &d), WR_ERR_PARSE); /* empty input */
        cr_assert_eq(wr_mesh_parse_obj(&m, NULL, 5, &d), WR_ERR_INVALID_ARG);
        cr_assert_eq(wr_mesh_read_obj(&m, "/nonexistent_dir_wr/x.obj", &d), WR_ERR_IO);
    }
}

/* Seeded mutation fuzzing: random byte edits of a valid OBJ must never crash (ASan/UBSan watch) and
 * must end in OK, PARSE or TOPOLOGY with a zeroed mesh on failure. */
Test(mesh_io, obj_mutation_fuzz) {
    const char *seed_txt = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n"
                           "g a\nf 1/1/1 2/2/1 3/3/1\ng b\nf -4/-4 -2/-2 -1/-1\n";
    static const char alphabet[] = "0123456789-+./ \n\tvfgtnxe#\r";
    wr_rng rng;
    size_t n = strlen(seed_txt);
    char *buf = (char *)malloc(n + 16);
    int it, ok = 0, parse = 0, topo = 0;
    wr_rng_seed(&rng, 2024);
    for (it = 0; it < 4000; ++it) {
        wr_mesh m;
        wr_diag d;
        wr_status st;
        size_t len = n, k, edits = 1 + wr_rng_below(&rng, 4);
        memcpy(buf, seed_txt, n);
        for (k = 0; k < edits; ++k) {
            size_t at = wr_rng_below(&rng, (uint32_t)len);
            uint32_t op = wr_rng_below(&rng, 3);
            char c = wr_rng_below(&rng, 8) == 0 ? (char)wr_rng_below(&rng, 256) : alphabet[wr_rng_below(&rng, sizeof alphabet - 1)];
            if (op == 0) buf[at] = c;                   /* replace */
            else if (op == 1 && len > 1) {              /* delete */
                memmove(buf + at, buf + at + 1, len - at - 1);
                --len;
            } else if (len < n + 15) {                  /* insert */
                memmove(buf + at + 1, buf + at, len - at);
                buf[at] = c;
                ++len;
            }
        }
        if (it % 7 == 0) len = wr_rng_below(&rng, (uint32_t)len + 1); /* truncation */
        st = wr_mesh_parse_obj(&m, buf, len, &d);
        cr_assert(st == WR_OK || st == WR_ERR_PARSE || st == WR_ERR_TOPOLOGY, "iteration %d: %s", it,
                  wr_status_string(st));
        if (st == WR_OK) {
            ++ok;
            check_invariants(&m);
        } else {
            cr_assert_null(m.pos);
            if (st == WR_ERR_PARSE) ++parse;
            else ++topo;
        }
        wr_mesh_free(&m);
    }
    free(buf);
    /* the mutations must actually exercise both outcomes */
    cr_assert_gt(ok, 100, "ok %d parse %d topology %d", ok, parse, topo);
    cr_assert_gt(parse, 100, "ok %d parse %d topology %d", ok, parse, topo);
}

Test(mesh_io, ply_and_vtk_writers) {
    wr_mesh m;
    wr_diag d;
    char path[400], *txt;
    double h[6] = {0.5, 1, 2, 3, 4, 5}, fc[4] = {1, 2, 3, 4.25};
    const char *names[1] = {"height"}, *cnames[1] = {"area_ratio"};
    const double *vals[1] = {h}, *cvals[1] = {fc};
    int n_tmp;
    make_tmpdir();
    cr_assert_eq(wr_mesh_rectangle(&m, 2.0, 1.0, 2, 1, &d), WR_OK); /* 6 vertices, 4 faces */
    snprintf(path, sizeof path, "%s/m.ply", tmpdir);
    cr_assert_eq(wr_mesh_write_ply(&m, path, 1, names, vals, &d), WR_OK, "%s", d.message);
    txt = slurp(path, NULL);
    cr_assert(strncmp(txt, "ply\nformat ascii 1.0\n", 21) == 0);
    cr_assert(strstr(txt, "element vertex 6\n") && strstr(txt, "property double height\n"));
    cr_assert(strstr(txt, "element face 4\nproperty list uchar int vertex_indices\nend_header\n0 0 0 0.5\n1 0 0 1\n"));
    cr_assert(strstr(txt, "\n3 0 1 4\n"));
    free(txt);
    snprintf(path, sizeof path, "%s/m.vtk", tmpdir);
    cr_assert_eq(wr_mesh_write_vtk(&m, path, 1, names, vals, 1, cnames, cvals, &d), WR_OK, "%s", d.message);
    txt = slurp(path, NULL);
    cr_assert(strncmp(txt, "# vtk DataFile Version 3.0\n", 27) == 0);
    cr_assert(strstr(txt, "DATASET POLYDATA\nPOINTS 6 double\n"));
    cr_assert(strstr(txt, "POLYGONS 4 16\n3 0 1 4\n"));
    cr_assert(strstr(txt, "POINT_DATA 6\nSCALARS height double 1\nLOOKUP_TABLE default\n0.5\n1\n"));
    cr_assert(strstr(txt, "CELL_DATA 4\nSCALARS area_ratio double 1\nLOOKUP_TABLE default\n1\n2\n3\n4.25\n"));
    free(txt);
    cr_assert_eq(wr_mesh_write_vtk(&m, path, 0, NULL, NULL, 0, NULL, NULL, &d), WR_OK);
    /* bad names */
    {
        const char *bad1[1] = {"has space"}, *bad2[1] = {"x"}, *bad3[1] = {""};
        cr_assert_eq(wr_mesh_write_ply(&m, path, 1, bad1, vals, &d), WR_ERR_INVALID_ARG);
        cr_assert_eq(wr_mesh_write_ply(&m, path, 1, bad2, vals, &d), WR_ERR_INVALID_ARG);
        cr_assert_eq(wr_mesh_write_vtk(&m, path, 1, bad3, vals, 0, NULL, NULL, &d), WR_ERR_INVALID_ARG);
        cr_assert_eq(wr_mesh_write_ply(&m, path, -1, NULL, NULL, &d), WR_ERR_INVALID_ARG);
    }
    cr_assert_eq(count_entries(tmpdir, &n_tmp), 2);
    cr_assert_eq(n_tmp, 0);
    wr_mesh_free(&m);
    remove_tmpdir();
}

/* A failed write leaves the previous file byte-for-byte and no temporary behind; a path in a missing
 * directory is WR_ERR_IO. */
Test(mesh_io, atomic_writes) {
    wr_mesh m;
    wr_diag d;
    char path[400], *before, *after;
    size_t lb, la;
    double h[6] = {0, 1, 2, NAN, 4, 5}, fc[4] = {1, 2, INFINITY, 4};
    const char *names[1] = {"h"};
    const double *vals[1] = {h}, *cvals[1] = {fc};
    int n_tmp;
    make_tmpdir();
    cr_assert_eq(wr_mesh_rectangle(&m, 2.0, 1.0, 2, 1, &d), WR_OK);
    snprintf(path, sizeof path, "%s/keep.out", tmpdir);
    cr_assert_eq(wr_mesh_write_obj(&m, path, NULL, &d), WR_OK);
    before = slurp(path, &lb);
    cr_assert_eq(wr_mesh_write_ply(&m, path, 1, names, vals, &d), WR_ERR_DOMAIN);
    cr_assert_eq(d.item, 3);
    cr_assert(strstr(d.message, "'h'") && strstr(d.message, "vertex 3"), "%s", d.message);
    cr_assert_eq(wr_mesh_write_vtk(&m, path, 0, NULL, NULL, 1, names, cvals, &d), WR_ERR_DOMAIN);
    cr_assert_eq(d.item, 2);
    after = slurp(path, &la);
    cr_assert_eq(la, lb);
    cr_assert(memcmp(before, after, lb) == 0, "failed write clobbered the file");
    cr_assert_eq(count_entries(tmpdir, &n_tmp), 1);
    cr_assert_eq(n_tmp, 0, "temporary left behind");
    free(before);
    free(after);
    snprintf(path, sizeof path, "%s/no/such/dir/x.obj", tmpdir);
    cr_assert_eq(wr_mesh_write_obj(&m, path, NULL, &d), WR_ERR_IO);
    cr_assert_eq(wr_mesh_write_ply(&m, path, 0, NULL, NULL, &d), WR_ERR_IO);
    cr_assert_eq(wr_mesh_write_vtk(&m, path, 0, NULL, NULL, 0, NULL, NULL, &d), WR_ERR_IO);
    cr_assert_eq(count_entries(tmpdir, &n_tmp), 1);
    wr_mesh_free(&m);
    remove_tmpdir();
}

/* Relabelling vertices, shuffling faces and rotating each face's corners changes no topological
 * count, keeps every invariant, and gradients stay closed (dω = 0). */
Test(mesh, relabelling_property) {
    wr_mesh a, b;
    wr_diag d;
    wr_rng rng;
    int32_t *perm, *fperm, *faces, i, f, k, e, trial;
    double *rest, *fv, *om;
    wr_rng_seed(&rng, 7);
    cr_assert_eq(wr_mesh_disk(&a, 1.0, 5, &d), WR_OK);
    perm = (int32_t *)malloc(sizeof(int32_t) * (size_t)a.nv);
    fperm = (int32_t *)malloc(sizeof(int32_t) * (size_t)a.nf);
    faces = (int32_t *)malloc(sizeof(int32_t) * 3 * (size_t)a.nf);
    rest = (double *)malloc(sizeof(double) * 2 * (size_t)a.nv);
    fv = (double *)malloc(sizeof(double) * (size_t)a.nv);
    for (trial = 0; trial < 5; ++trial) {
        for (i = 0; i < a.nv; ++i) perm[i] = i;
        for (i = a.nv - 1; i > 0; --i) {
            int32_t j = (int32_t)wr_rng_below(&rng, (uint32_t)i + 1), t = perm[i];
            perm[i] = perm[j], perm[j] = t;
        }
        for (i = 0; i < a.nf; ++i) fperm[i] = i;
        for (i = a.nf - 1; i > 0; --i) {
            int32_t j = (int32_t)wr_rng_below(&rng, (uint32_t)i + 1), t = fperm[i];
            fperm[i] = fperm[j], fperm[j] = t;
        }
        for (i = 0; i < a.nv; ++i) {
            rest[2 * perm[i]] = a.rest[2 * i];
            rest[2 * perm[i] + 1] = a.rest[2 * i + 1];
        }
        for (f = 0; f < a.nf; ++f) {
            int r = (int)wr_rng_below(&rng, 3);
            for (k = 0; k < 3; ++k) faces[3 * fperm[f] + k] = perm[a.faces[3 * f + (k + r) % 3]];
        }
        cr_assert_eq(wr_mesh_create(&b, a.nv, NULL, rest, a.nf, faces, &d), WR_OK, "%s", d.message);
        cr_assert_eq(b.ne, a.ne);
        cr_assert_eq(b.n_loops, 1);
        cr_assert_eq(b.loop_start[1], a.loop_start[1]);
        check_invariants(&b);
        for (i = 0; i < b.nv; ++i) fv[i] = wr_rng_normal(&rng);
        om = (double *)malloc(sizeof(double) * (size_t)b.ne);
        for (e = 0; e < b.ne; ++e) om[e] = fv[b.edges[2 * e + 1]] - fv[b.edges[2 * e]];
        for (f = 0; f < b.nf; ++f) {
            double dw = 0.0, uv[6];
            for (k = 0; k < 3; ++k) dw += b.face_edge_sign[3 * f + k] * om[b.face_edges[3 * f + k]];
            cr_assert_float_eq(dw, 0.0, 1e-13);
            wr_mesh_face_rest(&b, f, uv);
            cr_assert_gt((uv[2] - uv[0]) * (uv[5] - uv[1]) - (uv[4] - uv[0]) * (uv[3] - uv[1]), 0.0);
        }
        free(om);
        wr_mesh_free(&b);
    }
    free(perm);
    free(fperm);
    free(faces);
    free(rest);
    free(fv);
    wr_mesh_free(&a);
}

/* A vertex of very high degree (closed fan of 3000 faces) is handled in one pass. */
Test(mesh, high_degree_vertex) {
    const int32_t n = 3000;
    double *rest = (double *)malloc(sizeof(double) * 2 * (size_t)(n + 1));
    int32_t *faces = (int32_t *)malloc(sizeof(int32_t) * 3 * (size_t)n), i;
    wr_mesh m;
    wr_diag d;
    rest[0] = rest[1] = 0.0;
    for (i = 0; i < n; ++i) {
        rest[2 * (i + 1)] = cos(2.0 * WR_TEST_PI * i / n);
        rest[2 * (i + 1) + 1] = sin(2.0 * WR_TEST_PI * i / n);
        faces[3 * i] = 0, faces[3 * i + 1] = 1 + i, faces[3 * i + 2] = 1 + (i + 1) % n;
    }
    cr_assert_eq(wr_mesh_create(&m, n + 1, NULL, rest, n, faces, &d), WR_OK, "%s", d.message);
    cr_assert_eq(m.vf_start[1] - m.vf_start[0], n);
    cr_assert_eq(m.ne, 2 * n);
    cr_assert_eq(m.n_loops, 1);
    cr_assert_eq(m.loop_start[1], n);
    check_invariants(&m);
    wr_mesh_free(&m);
    free(rest);
    free(faces);
}

/* Regression: wr_mesh_create accepted nv > INT32_MAX/3 although every module indexes positions as
 * pos[3*i] with int32 i (and DOFs as 3*v): the validation loop itself overflowed 3*i and read past
 * the caller's array. Now WR_ERR_OVERFLOW before any position is read, like nf > INT32_MAX/3. */
Test(mesh, create_rejects_nv_beyond_int32_over_3) {
    double pos[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    int32_t tri[3] = {0, 1, 2};
    wr_mesh m;
    wr_diag d;
    cr_expect_eq(wr_mesh_create(&m, INT32_MAX / 3 + 1, pos, NULL, 1, tri, &d), WR_ERR_OVERFLOW);
    cr_expect(strstr(d.message, "nv") != NULL, "%s", d.message);
    cr_expect_eq(m.nv, 0);
    cr_expect_eq(wr_mesh_create(&m, 3, pos, NULL, 1, tri, &d), WR_OK);
    wr_mesh_free(&m);
}
