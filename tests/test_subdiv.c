/* tests/test_subdiv.c — subdiv.h: the regular Loop patch's basis against closed forms (partition of
 * unity, linear and quadratic precision, derivatives by finite differences), the face stencil against
 * the regular patch evaluated directly on a valence-6 lattice, and on an irregular mesh against an
 * independent global Loop step (the limit surface does not change under subdivision), the ghost-vertex
 * stencils of boundary faces (partition of unity, linear precision at a straight boundary); and
 * shell.h's Koiter point energy that the Loop element integrates (closed forms, finite differences),
 * with and without ghost-vertex boundaries. */
#include <criterion/criterion.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "wrinkle/shell.h"
#include "wrinkle/statics.h"
#include "wrinkle/subdiv.h"

/* lattice points of the 12 basis functions (subdiv.h ON THE REGULAR PATCH), (i, j) → i e1 + j e2 */
static const int lat[12][2] = {{0, -1}, {-1, 0}, {1, -1}, {0, 0}, {-1, 1}, {2, -1},
                               {1, 0},  {0, 1},  {-1, 2}, {2, 0}, {1, 1},  {0, 2}};
static void lat_xy(int i, int j, double xy[2]) {
    xy[0] = i + 0.5 * j;
    xy[1] = 0.8660254037844386 * j;
}

Test(subdiv, basis_partition_of_unity_and_fd_derivatives) {
    double pts[4][2] = {{1.0 / 3, 1.0 / 3}, {0.1, 0.7}, {0.6, 0.05}, {0.0, 0.0}};
    int p, i, k;
    for (p = 0; p < 4; ++p) {
        double N[12], dN[24], d2N[36], s = 0, sd[2] = {0, 0}, sdd[3] = {0, 0, 0}, h = 1e-5;
        double Np[12], Nm[12], dNp[24], dNm[24];
        wr_subdiv_loop_basis(pts[p][0], pts[p][1], N, dN, d2N);
        for (i = 0; i < 12; ++i) {
            s += N[i];
            cr_assert_geq(N[i], -1e-15, "box-spline basis is non-negative (N%d = %g)", i, N[i]);
            for (k = 0; k < 2; ++k) sd[k] += dN[2 * i + k];
            for (k = 0; k < 3; ++k) sdd[k] += d2N[3 * i + k];
        }
        cr_assert_float_eq(s, 1.0, 1e-14, "partition of unity: %.17g", s);
        for (k = 0; k < 2; ++k) cr_assert_float_eq(sd[k], 0.0, 1e-13);
        for (k = 0; k < 3; ++k) cr_assert_float_eq(sdd[k], 0.0, 1e-12);
        for (k = 0; k < 2; ++k) { /* central differences of N and dN along v (k = 0) and w (k = 1) */
            wr_subdiv_loop_basis(pts[p][0] + (k == 0 ? h : 0), pts[p][1] + (k == 1 ? h : 0), Np, dNp, NULL);
            wr_subdiv_loop_basis(pts[p][0] - (k == 0 ? h : 0), pts[p][1] - (k == 1 ? h : 0), Nm, dNm, NULL);
            for (i = 0; i < 12; ++i) {
                cr_assert_float_eq((Np[i] - Nm[i]) / (2 * h), dN[2 * i + k], 1e-9, "dN%d/d%c", i, "vw"[k]);
                /* ∂v of (∂v, ∂w) gives (vv, vw); ∂w gives (vw, ww) */
                cr_assert_float_eq((dNp[2 * i] - dNm[2 * i]) / (2 * h), d2N[3 * i + k], 1e-8);
                cr_assert_float_eq((dNp[2 * i + 1] - dNm[2 * i + 1]) / (2 * h), d2N[3 * i + k + 1], 1e-8);
            }
        }
    }
}

Test(subdiv, basis_reproduces_linear_and_quadratic_functions) {
    /* on the lattice: Σ N_i L_i is the point u·L_u + v·L_v + w·L_w exactly (linear precision), and for a
     * sampled quadratic q the patch differs from q by a constant, so its derivatives are q's */
    double pts[3][2] = {{0.2, 0.3}, {1.0 / 3, 1.0 / 3}, {0.7, 0.1}};
    int p, i;
    for (p = 0; p < 3; ++p) {
        double v = pts[p][0], w = pts[p][1], N[12], dN[24], d2N[36], X[2] = {0, 0}, e1[2], e2[2], want[2];
        double s = 0, sv = 0, sw = 0, svv = 0, svw = 0, sww = 0, qx, qy;
        wr_subdiv_loop_basis(v, w, N, dN, d2N);
        lat_xy(1, 0, e1);
        lat_xy(0, 1, e2);
        for (i = 0; i < 12; ++i) {
            double xy[2], q;
            lat_xy(lat[i][0], lat[i][1], xy);
            X[0] += N[i] * xy[0];
            X[1] += N[i] * xy[1];
            q = 0.3 * xy[0] * xy[0] - 0.7 * xy[0] * xy[1] + 1.1 * xy[1] * xy[1] + 0.2 * xy[0] - 0.5 * xy[1];
            s += N[i] * q;
            sv += dN[2 * i] * q;
            sw += dN[2 * i + 1] * q;
            svv += d2N[3 * i] * q;
            svw += d2N[3 * i + 1] * q;
            sww += d2N[3 * i + 2] * q;
        }
        want[0] = v * e1[0] + w * e2[0];
        want[1] = v * e1[1] + w * e2[1];
        cr_assert_float_eq(X[0], want[0], 1e-14);
        cr_assert_float_eq(X[1], want[1], 1e-14);
        qx = 0.6 * want[0] - 0.7 * want[1] + 0.2; /* ∇q at the point */
        qy = -0.7 * want[0] + 2.2 * want[1] - 0.5;
        cr_assert_float_eq(sv, qx * e1[0] + qy * e1[1], 1e-13, "q_v");
        cr_assert_float_eq(sw, qx * e2[0] + qy * e2[1], 1e-13, "q_w");
        cr_assert_float_eq(svv, 0.6 * e1[0] * e1[0] - 1.4 * e1[0] * e1[1] + 2.2 * e1[1] * e1[1], 1e-12);
        cr_assert_float_eq(svw, 0.6 * e1[0] * e2[0] - 0.7 * (e1[0] * e2[1] + e1[1] * e2[0]) + 2.2 * e1[1] * e2[1], 1e-12);
        cr_assert_float_eq(sww, 0.6 * e2[0] * e2[0] - 1.4 * e2[0] * e2[1] + 2.2 * e2[1] * e2[1], 1e-12);
        (void)s;
    }
}

/* A (n+1)² triangular lattice, vertex (i, j) = i e1 + j e2, random heights and in-plane jitter (the
 * limit-surface identities hold for any control positions); faces (i,j),(i+1,j),(i,j+1) and
 * (i+1,j),(i+1,j+1),(i,j+1), counter-clockwise. */
static void lattice_mesh(wr_mesh *m, int n, unsigned seed) {
    int32_t nv = (n + 1) * (n + 1), nf = 2 * n * n, *faces = (int32_t *)malloc(sizeof(int32_t) * 3 * (size_t)nf), i, j, f = 0;
    double *pos = (double *)malloc(sizeof(double) * 3 * (size_t)nv), *rest = (double *)malloc(sizeof(double) * 2 * (size_t)nv);
    wr_rng rng;
    wr_diag d;
    wr_rng_seed(&rng, seed);
    for (j = 0; j <= n; ++j)
        for (i = 0; i <= n; ++i) {
            int32_t v = j * (n + 1) + i;
            lat_xy(i, j, rest + 2 * v);
            pos[3 * v] = rest[2 * v] + 0.1 * (wr_rng_uniform(&rng) - 0.5);
            pos[3 * v + 1] = rest[2 * v + 1] + 0.1 * (wr_rng_uniform(&rng) - 0.5);
            pos[3 * v + 2] = 0.3 * (wr_rng_uniform(&rng) - 0.5);
        }
    for (j = 0; j < n; ++j)
        for (i = 0; i < n; ++i) {
            int32_t a = j * (n + 1) + i;
            faces[3 * f] = a;
            faces[3 * f + 1] = a + 1;
            faces[3 * f + 2] = a + n + 1;
            ++f;
            faces[3 * f] = a + 1;
            faces[3 * f + 1] = a + n + 2;
            faces[3 * f + 2] = a + n + 1;
            ++f;
        }
    cr_assert_eq(wr_mesh_create(m, nv, pos, rest, nf, faces, &d), WR_OK, "%s", d.message);
    free(faces);
    free(pos);
    free(rest);
}

/* x at the stencil's 6 rows (position, ∂v, ∂w, ∂vv, ∂vw, ∂ww) */
static void apply_stencil(const wr_mesh *m, int32_t n, const int32_t *verts, const double *W, double x[6][3]) {
    int k, i, j;
    for (k = 0; k < 6; ++k)
        for (i = 0; i < 3; ++i) {
            x[k][i] = 0.0;
            for (j = 0; j < n; ++j) x[k][i] += W[k * n + j] * m->pos[3 * verts[j] + i];
        }
}

Test(subdiv, stencil_equals_the_regular_patch_on_a_valence6_lattice) {
    /* the central child of a regular face is the parent patch turned by 180° and halved: same point,
     * first derivatives −½, second ¼ of the parent patch's at its centre (subdiv.h ON THE STENCIL) */
    wr_mesh m;
    int n = 8, ci, cj, tested = 0;
    lattice_mesh(&m, n, 7u);
    for (cj = 2; cj <= n - 3; ++cj)
        for (ci = 2; ci <= n - 3; ++ci) {
            int32_t f = 2 * (cj * n + ci), cnt, verts[WR_SUBDIV_MAX_STENCIL], i, k;
            double W[6 * WR_SUBDIV_MAX_STENCIL], x[6][3], N[12], dN[24], d2N[36], y[6][3], scale[6] = {1, -0.5, -0.5, 0.25, 0.25, 0.25};
            wr_diag d;
            cr_assert_eq(wr_subdiv_loop_stencil(&m, f, &cnt, verts, W, &d), WR_OK, "%s", d.message);
            cr_assert_eq(cnt, 12, "a regular face's stencil is its 12 patch vertices, got %d", cnt);
            apply_stencil(&m, cnt, verts, W, x);
            wr_subdiv_loop_basis(1.0 / 3, 1.0 / 3, N, dN, d2N);
            memset(y, 0, sizeof y);
            for (i = 0; i < 12; ++i) {
                int32_t v = (cj + lat[i][1]) * (n + 1) + ci + lat[i][0];
                double b[6];
                b[0] = N[i];
                b[1] = dN[2 * i];
                b[2] = dN[2 * i + 1];
                b[3] = d2N[3 * i];
                b[4] = d2N[3 * i + 1];
                b[5] = d2N[3 * i + 2];
                for (k = 0; k < 6; ++k) {
                    int c;
                    for (c = 0; c < 3; ++c) y[k][c] += b[k] * m.pos[3 * v + c];
                }
            }
            for (k = 0; k < 6; ++k) {
                int c;
                for (c = 0; c < 3; ++c)
                    cr_assert_float_eq(x[k][c], scale[k] * y[k][c], 1e-12, "face %d row %d comp %d: %.15g vs %.15g", f, k,
                                       c, x[k][c], scale[k] * y[k][c]);
            }
            ++tested;
        }
    cr_assert_gt(tested, 10);
    wr_mesh_free(&m);
}

/* One global Loop step of m, written edge by edge (not through the stencil code): new vertex i < nv
 * is vertex i's vertex point, nv + e the edge point of edge e; each face → four, the central one
 * (ep(e_BC), ep(e_CA), ep(e_AB)) stored at 4f + 3. Only interior-vertex positions are meaningful. */
static void loop_step(const wr_mesh *m, wr_mesh *out) {
    int32_t nv = m->nv + m->ne, nf = 4 * m->nf, e, v, f, k;
    int32_t *faces = (int32_t *)malloc(sizeof(int32_t) * 3 * (size_t)nf), *val = (int32_t *)calloc((size_t)m->nv, sizeof(int32_t));
    double *pos = (double *)calloc(3 * (size_t)nv, sizeof(double)), *sum = (double *)calloc(3 * (size_t)m->nv, sizeof(double));
    wr_diag d;
    for (e = 0; e < m->ne; ++e) {
        int32_t a = m->edges[2 * e], b = m->edges[2 * e + 1], s;
        for (k = 0; k < 3; ++k) {
            sum[3 * a + k] += m->pos[3 * b + k];
            sum[3 * b + k] += m->pos[3 * a + k];
            pos[3 * (m->nv + e) + k] = 0.375 * (m->pos[3 * a + k] + m->pos[3 * b + k]);
        }
        val[a]++;
        val[b]++;
        for (s = 0; s < 2; ++s) {
            int32_t g = m->edge_faces[2 * e + s], c;
            if (g < 0) continue;
            for (c = 0; c < 3; ++c)
                if (m->faces[3 * g + c] != a && m->faces[3 * g + c] != b)
                    for (k = 0; k < 3; ++k) pos[3 * (m->nv + e) + k] += 0.125 * m->pos[3 * m->faces[3 * g + c] + k];
        }
    }
    for (v = 0; v < m->nv; ++v) {
        double c = 0.375 + 0.25 * cos(2.0 * 3.14159265358979323846 / val[v]), beta = (0.625 - c * c) / val[v];
        for (k = 0; k < 3; ++k) pos[3 * v + k] = (1.0 - val[v] * beta) * m->pos[3 * v + k] + beta * sum[3 * v + k];
    }
    for (f = 0; f < m->nf; ++f) {
        int32_t A = m->faces[3 * f], B = m->faces[3 * f + 1], C = m->faces[3 * f + 2];
        int32_t eBC = m->nv + m->face_edges[3 * f], eCA = m->nv + m->face_edges[3 * f + 1], eAB = m->nv + m->face_edges[3 * f + 2];
        int32_t t[12] = {A, eAB, eCA, B, eBC, eAB, C, eCA, eBC, eBC, eCA, eAB};
        memcpy(faces + 12 * f, t, sizeof t);
    }
    cr_assert_eq(wr_mesh_create(out, nv, pos, NULL, nf, faces, &d), WR_OK, "%s", d.message);
    free(faces);
    free(val);
    free(pos);
    free(sum);
}

Test(subdiv, stencil_is_invariant_under_a_loop_step_on_an_irregular_mesh) {
    /* wr_mesh_rectangle's union-jack grid has valences 4 and 8: every face is irregular. The limit
     * surface of the once-subdivided mesh is the same surface, and the subdivided mesh's central child
     * of face f has the same centre: same point, derivatives −½ and ¼ (one more half-turn and halving) */
    wr_mesh m, r;
    wr_diag d;
    int32_t f, tested = 0, i;
    wr_rng rng;
    cr_assert_eq(wr_mesh_rectangle(&m, 1.0, 1.0, 6, 6, &d), WR_OK);
    wr_rng_seed(&rng, 3u);
    for (i = 0; i < m.nv; ++i) m.pos[3 * i + 2] = 0.2 * (wr_rng_uniform(&rng) - 0.5);
    loop_step(&m, &r);
    for (f = 0; f < m.nf; ++f) {
        int32_t n1, n2, v1[WR_SUBDIV_MAX_STENCIL], v2[WR_SUBDIV_MAX_STENCIL], k, c;
        double W1[6 * WR_SUBDIV_MAX_STENCIL], W2[6 * WR_SUBDIV_MAX_STENCIL], x1[6][3], x2[6][3], scale[6] = {1, -0.5, -0.5, 0.25, 0.25, 0.25};
        double wsum = 0.0;
        if (wr_subdiv_loop_stencil(&m, f, &n1, v1, W1, NULL) != WR_OK) continue; /* a boundary corner */
        cr_assert_eq(wr_subdiv_loop_stencil(&r, 4 * f + 3, &n2, v2, W2, &d), WR_OK, "%s", d.message);
        for (k = 0; k < n1; ++k) wsum += W1[k];
        cr_assert_float_eq(wsum, 1.0, 1e-14, "position weights sum to 1");
        apply_stencil(&m, n1, v1, W1, x1);
        apply_stencil(&r, n2, v2, W2, x2);
        for (k = 0; k < 6; ++k)
            for (c = 0; c < 3; ++c)
                cr_assert_float_eq(x2[k][c], scale[k] * x1[k][c], 1e-12, "face %d row %d comp %d: %.15g vs %.15g", f, k, c,
                                   x2[k][c], scale[k] * x1[k][c]);
        ++tested;
    }
    cr_assert_geq(tested, 16, "interior faces tested: %d", tested);
    wr_mesh_free(&r);
    wr_mesh_free(&m);
}

Test(subdiv, boundary_faces_and_bad_arguments_are_refused) {
    wr_mesh m;
    wr_diag d;
    int32_t n, verts[WR_SUBDIV_MAX_STENCIL];
    double W[6 * WR_SUBDIV_MAX_STENCIL];
    cr_assert_eq(wr_mesh_rectangle(&m, 1.0, 1.0, 4, 4, &d), WR_OK);
    cr_assert_eq(wr_subdiv_loop_stencil(&m, 0, &n, verts, W, &d), WR_ERR_TOPOLOGY);
    cr_assert_eq(d.item, 0);
    cr_assert(strstr(d.message, "boundary") != NULL, "%s", d.message);
    cr_assert_eq(wr_subdiv_loop_stencil(&m, m.nf, &n, verts, W, &d), WR_ERR_INVALID_ARG);
    cr_assert_eq(wr_subdiv_loop_stencil(NULL, 0, &n, verts, W, &d), WR_ERR_INVALID_ARG);
    wr_mesh_free(&m);
}

/* subdiv.h ON GHOST VERTICES: interior faces keep their stencil; every stencil is a partition of unity
 * (position weights sum to 1, derivative weights to 0: the construction is affine); at a straight
 * boundary of a valence-6 lattice the ghosts are the missing lattice points themselves, so there a
 * boundary face reproduces linear data exactly (the limit point is the face centroid's value, the
 * second derivatives vanish) as an interior face does. The lattice's rhombus corners (one or two
 * faces) get valence 4 or 5 rings and are only checked for the partition of unity. */
static int32_t vertex_faces(const wr_mesh *m, int32_t v) { return m->vf_start[v + 1] - m->vf_start[v]; }

Test(subdiv, ghost_stencil_keeps_interior_faces_and_reproduces_linear_data_at_a_straight_boundary) {
    wr_mesh m;
    int n = 6, straight = 0, corner = 0;
    int32_t f, v;
    lattice_mesh(&m, n, 3u);
    for (v = 0; v < m.nv; ++v) { /* planar lattice with a linear height */
        m.pos[3 * v] = m.rest[2 * v], m.pos[3 * v + 1] = m.rest[2 * v + 1];
        m.pos[3 * v + 2] = 0.3 * m.pos[3 * v] - 0.2 * m.pos[3 * v + 1] + 0.1;
    }
    for (f = 0; f < m.nf; ++f) {
        int32_t n0, n1, v0[WR_SUBDIV_MAX_STENCIL], v1[WR_SUBDIV_MAX_STENCIL], j, c, k;
        double W0[6 * WR_SUBDIV_MAX_STENCIL], W1[6 * WR_SUBDIV_MAX_STENCIL], x[6][3], sum[6] = {0, 0, 0, 0, 0, 0}, cen[3] = {0, 0, 0};
        int is_straight = 1;
        wr_diag d;
        wr_status plain = wr_subdiv_loop_stencil(&m, f, &n0, v0, W0, NULL);
        cr_assert_eq(wr_subdiv_loop_stencil_ghost(&m, f, &n1, v1, W1, &d), WR_OK, "face %d: %s", (int)f, d.message);
        for (k = 0; k < 6; ++k)
            for (j = 0; j < n1; ++j) sum[k] += W1[k * n1 + j];
        cr_assert_float_eq(sum[0], 1.0, 1e-13, "face %d: position weights sum to %.15g", (int)f, sum[0]);
        for (k = 1; k < 6; ++k) cr_assert_float_eq(sum[k], 0.0, 1e-12, "face %d row %d: weights sum to %.3g", (int)f, k, sum[k]);
        if (plain == WR_OK) {
            cr_assert_eq(n1, n0);
            cr_assert_eq(memcmp(v0, v1, sizeof(int32_t) * (size_t)n0), 0, "face %d: interior stencil changed", (int)f);
            cr_assert_eq(memcmp(W0, W1, sizeof(double) * 6 * (size_t)n0), 0, "face %d: interior weights changed", (int)f);
            continue;
        }
        for (c = 0; c < 3; ++c) {
            int32_t a = m.faces[3 * f + c], nb = vertex_faces(&m, a);
            int interior = 1;
            for (j = 0; j < m.ne; ++j)
                if ((m.edges[2 * j] == a || m.edges[2 * j + 1] == a) && (m.edge_faces[2 * j] < 0 || m.edge_faces[2 * j + 1] < 0))
                    interior = 0;
            if (!interior && nb != 3) is_straight = 0;
            for (k = 0; k < 3; ++k) cen[k] += m.pos[3 * a + k] / 3.0;
        }
        if (!is_straight) {
            ++corner;
            continue;
        }
        apply_stencil(&m, n1, v1, W1, x);
        for (k = 0; k < 3; ++k) cr_assert_float_eq(x[0][k], cen[k], 1e-12, "face %d: limit point %d %.15g vs centroid %.15g", (int)f, k, x[0][k], cen[k]);
        for (j = 3; j < 6; ++j)
            for (k = 0; k < 3; ++k) cr_assert_float_eq(x[j][k], 0.0, 1e-12, "face %d: second derivative row %d = %.3g", (int)f, j, x[j][k]);
        ++straight;
    }
    cr_assert_gt(straight, 4 * n - 12, "straight-boundary faces checked: %d", straight);
    cr_assert_gt(corner, 0);
    wr_mesh_free(&m);
}

/* ---- wr_shell_koiter_point: the energy the Loop element evaluates at each face centre ------------ */

static void koiter_rest_plate(wr_shell_koiter_rest *r, double Y, double h, double nu) {
    memset(r, 0, sizeof *r);
    r->A[0] = 1.0;
    r->A[2] = 1.0;
    r->Ym = Y * h / (1.0 - nu * nu);
    r->Db = Y * h * h * h / (12.0 * (1.0 - nu * nu));
    r->nu = nu;
}

Test(subdiv, koiter_point_closed_forms) {
    /* flat rest, unit metric. (1) a cylinder of radius R bent about w: κ11 = 1/R, W = ½ D / R²;
     * (2) a uniaxial stretch x_v = λ e1 with free lateral contraction... here held: ε11 = (λ² − 1)/2,
     * W = ½ Ym ε11² (plane-stress StVK with ε22 = 0); (3) equal biaxial ε: W = Ym (1 + ν) ε² */
    wr_shell_koiter_rest r;
    double p[15], R = 0.05, lam = 1.1, e, W;
    koiter_rest_plate(&r, 1e6, 1e-3, 0.3);
    memset(p, 0, sizeof p);
    p[0] = 1.0;
    p[4] = 1.0;
    p[8] = 1.0 / R; /* x_vv = n / R */
    W = wr_shell_koiter_point(&r, p, NULL, NULL);
    cr_assert_float_eq(W, 0.5 * r.Db / (R * R), 1e-12 * W, "cylinder: %.15g vs %.15g", W, 0.5 * r.Db / (R * R));
    p[8] = 0.0;
    p[0] = lam;
    e = 0.5 * (lam * lam - 1.0);
    W = wr_shell_koiter_point(&r, p, NULL, NULL);
    cr_assert_float_eq(W, 0.5 * r.Ym * e * e, 1e-12 * W);
    p[4] = lam;
    W = wr_shell_koiter_point(&r, p, NULL, NULL);
    cr_assert_float_eq(W, r.Ym * (1.0 + r.nu) * e * e, 1e-12 * W);
    /* a sheared parametrisation of the same plate (A ≠ I) measures the same physical strain energy:
     * rest x_v = (1, 0, 0), x_w = (0.4, 1, 0); deformed by the stretch diag(λ, 1) */
    r.A[0] = 1.0;
    r.A[1] = 0.4;
    r.A[2] = 1.16;
    memset(p, 0, sizeof p);
    p[0] = lam;
    p[3] = 0.4 * lam;
    p[4] = 1.0;
    W = wr_shell_koiter_point(&r, p, NULL, NULL); /* √det A = 1 */
    cr_assert_float_eq(W, 0.5 * r.Ym * e * e, 1e-12 * W, "sheared parameters: %.15g vs %.15g", W, 0.5 * r.Ym * e * e);
}

Test(subdiv, koiter_point_gradient_and_hessian_match_finite_differences) {
    wr_shell_koiter_rest r;
    wr_rng rng;
    int trial, i, j;
    wr_rng_seed(&rng, 11u);
    for (trial = 0; trial < 4; ++trial) {
        double p[15], g[15], H[225], gp[15], gm[15], h = 1e-6, gmax = 0.0, hmax = 0.0;
        koiter_rest_plate(&r, 1e6, 2e-3, 0.35);
        r.A[0] = 1.0 + 0.3 * wr_rng_uniform(&rng);
        r.A[1] = 0.2 * (wr_rng_uniform(&rng) - 0.5);
        r.A[2] = 0.8 + 0.3 * wr_rng_uniform(&rng);
        for (i = 0; i < 3; ++i) r.B[i] = 2.0 * (wr_rng_uniform(&rng) - 0.5);
        for (i = 0; i < 15; ++i) p[i] = 0.3 * (wr_rng_uniform(&rng) - 0.5);
        p[0] += 1.0;
        p[4] += 1.0;
        wr_shell_koiter_point(&r, p, g, H);
        for (i = 0; i < 15; ++i) {
            gmax = fmax(gmax, fabs(g[i]));
            for (j = 0; j < 15; ++j) hmax = fmax(hmax, fabs(H[15 * i + j]));
        }
        for (i = 0; i < 15; ++i) {
            double q[15], Ep, Em;
            memcpy(q, p, sizeof q);
            q[i] = p[i] + h;
            Ep = wr_shell_koiter_point(&r, q, gp, NULL);
            q[i] = p[i] - h;
            Em = wr_shell_koiter_point(&r, q, gm, NULL);
            cr_assert_float_eq((Ep - Em) / (2 * h), g[i], 1e-6 * gmax, "trial %d: dE/dp%d %.10g vs %.10g", trial, i,
                               (Ep - Em) / (2 * h), g[i]);
            for (j = 0; j < 15; ++j)
                cr_assert_float_eq((gp[j] - gm[j]) / (2 * h), H[15 * j + i], 1e-6 * hmax, "trial %d: H[%d][%d] %.10g vs %.10g",
                                   trial, j, i, (gp[j] - gm[j]) / (2 * h), H[15 * j + i]);
        }
        for (i = 0; i < 15; ++i)
            for (j = 0; j < i; ++j) cr_assert_float_eq(H[15 * i + j], H[15 * j + i], 1e-12 * hmax, "H symmetric");
    }
}

/* ---- the Loop element in wr_shell (shell.h ON THE LOOP ELEMENT) ----------------------------------- */

/* elem: desc.loop_element (1: interior faces, 2: every face with ghost vertices) */
static void loop_shell_elem(wr_shell *s, const wr_mesh *m, int elem) {
    wr_shell_desc sd;
    wr_diag d;
    memset(&sd, 0, sizeof sd);
    sd.membrane = WR_MEMBRANE_STVK;
    sd.bending = WR_BENDING_DIHEDRAL;
    sd.young = 1e6;
    sd.poisson = 0.3;
    sd.thickness = 1e-3;
    sd.loop_element = elem;
    cr_assert_eq(wr_shell_create(s, m, &sd, &d), WR_OK, "%s", d.message);
}

Test(subdiv, loop_shell_uniform_stretch_is_exact) {
    /* an affine map of a planar mesh maps its limit surface affinely: uniform strain on Loop faces as on
     * linear ones, so E = area · ½ Ym ε² (ε22 held at 0) exactly; with ghost vertices (loop_element 2,
     * every face a Loop face) as well, the ghosts being affine completions */
    int elem;
    for (elem = 1; elem <= 2; ++elem) {
        wr_mesh m;
        wr_shell s;
        wr_diag d;
        double lam = 1.05, e = 0.5 * (lam * lam - 1.0), E, Ym;
        int32_t v;
        cr_assert_eq(wr_mesh_rectangle(&m, 1.0, 0.5, 10, 5, &d), WR_OK);
        loop_shell_elem(&s, &m, elem);
        if (elem == 1) cr_assert_gt(s.n_loop_faces, 20, "Loop faces: %d of %d", s.n_loop_faces, m.nf);
        else cr_assert_eq(s.n_loop_faces, m.nf, "ghosts: Loop faces %d of %d", s.n_loop_faces, m.nf);
        for (v = 0; v < m.nv; ++v) m.pos[3 * v] *= lam;
        cr_assert_eq(wr_shell_energy(&s, m.pos, &E, NULL, &d), WR_OK, "%s", d.message);
        Ym = 1e6 * 1e-3 / (1.0 - 0.09);
        cr_assert_float_eq(E, 0.5 * 0.5 * Ym * e * e, 1e-10 * E, "element %d: E = %.15g vs %.15g", elem, E, 0.25 * Ym * e * e);
        wr_shell_free(&s);
        if (elem == 2) {
            wr_shell_desc sd;
            memset(&sd, 0, sizeof sd);
            sd.young = 1e6, sd.poisson = 0.3, sd.thickness = 1e-3, sd.loop_element = 3;
            cr_assert_eq(wr_shell_create(&s, &m, &sd, &d), WR_ERR_INVALID_ARG, "loop_element 3 accepted");
        }
        wr_mesh_free(&m);
    }
}

/* Control points of m (rest scaled by `scale`) placed isometrically on a cylinder of radius 0.3 m
 * about the y axis; the Loop faces' bending and membrane energies over ½ D / R² × their rest area. */
static void cylinder_energies_elem(const wr_mesh *m0, double scale, int elem, int all_faces, double out[2]) {
    wr_mesh m;
    wr_shell s;
    wr_diag d;
    double R = 0.3, D = 1e6 * 1e-9 / (12.0 * 0.91), area = 0.0, Eb = 0.0, Em = 0.0;
    int32_t v, f;
    cr_assert_eq(wr_mesh_copy(&m, m0, &d), WR_OK);
    for (v = 0; v < 2 * m.nv; ++v) m.rest[v] *= scale;
    loop_shell_elem(&s, &m, elem);
    for (v = 0; v < m.nv; ++v) {
        double u = m.rest[2 * v];
        m.pos[3 * v] = R * sin(u / R);
        m.pos[3 * v + 1] = m.rest[2 * v + 1];
        m.pos[3 * v + 2] = R * (1.0 - cos(u / R));
    }
    for (f = 0; f < m.nf; ++f) {
        double em, eb;
        if (!all_faces && s.loop_start[f + 1] == s.loop_start[f]) continue;
        cr_assert_eq(wr_shell_face_energy(&s, f, m.pos, &em, &eb), WR_OK);
        Em += em;
        Eb += eb;
        area += s.area[f];
    }
    out[0] = Eb / (0.5 * D / (R * R) * area);
    out[1] = Em / (0.5 * D / (R * R) * area);
    wr_shell_free(&s);
    wr_mesh_free(&m);
}

/* the Loop faces only (loop_element 1) */
static void cylinder_energies(const wr_mesh *m0, double scale, double out[2]) { cylinder_energies_elem(m0, scale, 1, 0, out); }

/* The whole sheet bent to the cylinder, boundary faces included: with ghost vertices (every face a
 * Loop face) and with the linear boundary row (loop_element 1, dihedral bending there). Both errors
 * are a boundary layer one row wide, O(h); measured bending / closed form at n = 10, 20, 40: ghosts
 * 0.9330, 0.9684, 0.9847, linear row 0.9601, 0.9812, 0.9910. The ghosts' free-edge completion
 * (subdiv.h ON GHOST VERTICES) pulls the curvature across the edge towards zero, so on an imposed
 * cylinder it misses 1.7 times more than the linear row: not the improvement the boundary was for. */
Test(subdiv, loop_shell_ghost_boundary_bent_to_a_cylinder) {
    double r[3][2][2];
    int level, elem;
    for (level = 0; level < 3; ++level)
        for (elem = 1; elem <= 2; ++elem) {
            wr_mesh m;
            int n = 10 << level;
            lattice_mesh(&m, n, 1u);
            cylinder_energies_elem(&m, 0.4 / n, elem, 1, r[level][elem - 1]);
            wr_mesh_free(&m);
        }
    for (elem = 0; elem < 2; ++elem) {
        double e0 = fabs(r[0][elem][0] - 1.0), e1 = fabs(r[1][elem][0] - 1.0), e2 = fabs(r[2][elem][0] - 1.0);
        cr_assert_lt(e1, 0.55 * e0, "element %d: bending error %.4g -> %.4g, not O(h)", elem + 1, e0, e1);
        cr_assert_lt(e2, 0.55 * e1, "element %d: bending error %.4g -> %.4g, not O(h)", elem + 1, e1, e2);
        cr_assert_lt(r[2][elem][1], 0.1 * r[0][elem][1], "element %d: membrane %.3g -> %.3g", elem + 1, r[0][elem][1],
                     r[2][elem][1]);
    }
    cr_assert_lt(fabs(r[2][1][0] - 1.0), 0.02, "ghosts, n = 40: bending / closed form %.4f", r[2][1][0]);
}

Test(subdiv, loop_shell_bent_to_a_cylinder) {
    /* The limit surface of control points on a cylinder is a slightly smaller cylinder (subdivision does
     * not interpolate): on the valence-6 lattice the bending energy tends to ½ D / R² per unit area at
     * second order in h and the membrane energy to 0 at fourth. On the union-jack grid every face
     * touches valence-4 and valence-8 vertices, where Loop surfaces do not reproduce quadratics: the
     * bending energy keeps a bias that does not refine away (measured +6.8 %; bounded here at 8 %, the
     * element's known limitation on highly irregular meshes) while the membrane still converges. */
    double lat[3][2], uj[2][2];
    int level;
    for (level = 0; level < 3; ++level) {
        wr_mesh m;
        int n = 20 << level;
        lattice_mesh(&m, n, 1u);
        cylinder_energies(&m, 0.4 / n, lat[level]);
        wr_mesh_free(&m);
    }
    for (level = 0; level < 2; ++level) {
        wr_mesh m;
        wr_diag d;
        cr_assert_eq(wr_mesh_rectangle(&m, 0.6, 0.4, 30 << level, 20 << level, &d), WR_OK);
        cylinder_energies(&m, 1.0, uj[level]);
        wr_mesh_free(&m);
    }
    cr_assert_lt(fabs(lat[0][0] - 1.0), 2e-3, "lattice h = 2 cm: bending / closed form %.6f", lat[0][0]);
    cr_assert_lt(fabs(lat[2][0] - 1.0), 0.3 * 0.3 * fabs(lat[0][0] - 1.0), "bending error %.3g -> %.3g: not O(h^2)",
                 fabs(lat[0][0] - 1.0), fabs(lat[2][0] - 1.0));
    cr_assert_lt(lat[2][1], 0.1 * 0.1 * lat[0][1], "membrane %.3g -> %.3g: not O(h^4)", lat[0][1], lat[2][1]);
    cr_assert_lt(fabs(uj[1][0] - 1.0), 0.08, "union jack: bending / closed form %.4f", uj[1][0]);
    cr_assert_lt(uj[1][1], 0.1 * uj[0][1], "union jack membrane %.3g -> %.3g", uj[0][1], uj[1][1]);
}

/* Assembles the streamed blocks into a dense matrix */
typedef struct dense_sink {
    int32_t n;
    double *H;
} dense_sink;
static wr_status dense_add(void *user, int32_t k, const int32_t *verts, const double *Ke) {
    dense_sink *ds = (dense_sink *)user;
    int32_t a, b, i, j;
    for (a = 0; a < k; ++a)
        for (b = 0; b < k; ++b)
            for (i = 0; i < 3; ++i)
                for (j = 0; j < 3; ++j) ds->H[(3 * verts[a] + i) * 3 * ds->n + 3 * verts[b] + j] += Ke[(3 * a + i) * 3 * k + 3 * b + j];
    return WR_OK;
}

static void loop_shell_fd(int elem) {
    wr_mesh m;
    wr_shell s;
    wr_diag d;
    wr_rng rng;
    dense_sink ds;
    wr_hess_sink hs;
    double *g, *gp, *gm, gmax = 0.0, hmax = 0.0, h = 1e-7;
    int32_t v, i, j, N;
    cr_assert_eq(wr_mesh_rectangle(&m, 0.1, 0.1, 5, 5, &d), WR_OK);
    loop_shell_elem(&s, &m, elem);
    wr_rng_seed(&rng, 5u);
    for (v = 0; v < 3 * m.nv; ++v) m.pos[v] += 0.004 * (wr_rng_uniform(&rng) - 0.5);
    N = 3 * m.nv;
    g = (double *)calloc((size_t)N, sizeof(double));
    gp = (double *)calloc((size_t)N, sizeof(double));
    gm = (double *)calloc((size_t)N, sizeof(double));
    ds.n = m.nv;
    ds.H = (double *)calloc((size_t)N * (size_t)N, sizeof(double));
    hs.user = &ds;
    hs.add = dense_add;
    cr_assert_eq(wr_shell_energy(&s, m.pos, NULL, g, &d), WR_OK);
    cr_assert_eq(wr_shell_hessian_elements(&s, m.pos, 0, &hs, &d), WR_OK);
    for (i = 0; i < N; ++i) {
        gmax = fmax(gmax, fabs(g[i]));
        for (j = 0; j < N; ++j) hmax = fmax(hmax, fabs(ds.H[(size_t)i * N + j]));
    }
    for (i = 0; i < N; ++i) {
        double x0 = m.pos[i], Ep, Em;
        m.pos[i] = x0 + h;
        wr_shell_energy(&s, m.pos, &Ep, gp, NULL);
        m.pos[i] = x0 - h;
        wr_shell_energy(&s, m.pos, &Em, gm, NULL);
        m.pos[i] = x0;
        cr_assert_float_eq((Ep - Em) / (2 * h), g[i], 1e-5 * gmax, "dE/dx%d %.8g vs %.8g", i, (Ep - Em) / (2 * h), g[i]);
        for (j = 0; j < N; ++j)
            cr_assert_float_eq((gp[j] - gm[j]) / (2 * h), ds.H[(size_t)j * N + i], 1e-5 * hmax, "H[%d][%d] %.8g vs %.8g", j, i,
                               (gp[j] - gm[j]) / (2 * h), ds.H[(size_t)j * N + i]);
    }
    free(g);
    free(gp);
    free(gm);
    free(ds.H);
    wr_shell_free(&s);
    wr_mesh_free(&m);
}

Test(subdiv, loop_shell_gradient_and_hessian_match_finite_differences) { loop_shell_fd(1); }

/* the same with ghost vertices: every face (boundary faces' stencils fold the ghosts) */
Test(subdiv, loop_shell_ghost_gradient_and_hessian_match_finite_differences) { loop_shell_fd(2); }

/* A cantilever strip under its weight, clamped by holding its first two vertex columns (subdiv.h ON
 * GHOST VERTICES: with ghosts that fixes the slope), the other edges free: tip deflection against
 * beam theory w = q L⁴ / (8 E I) over the free length L (x from the second column), ν = 0 so the
 * plate and the beam agree; w/L = 1e-3, linear regime. Union-jack grids (the Loop element's +6.8 %
 * bending bias there, ON THE LOOP ELEMENT) of 40 × 8 and 80 × 16 faces' columns. */
static double cantilever_tip_ratio(int nx, int elem) {
    wr_mesh m;
    wr_shell s;
    wr_shell_desc sd;
    wr_statics_desc st;
    wr_statics_stats ss;
    wr_diag d;
    double Lx = 0.1, b = 0.02, h = 1e-3, E = 1e6, dx = Lx / nx, L = Lx - dx, EI = E * b * h * h * h / 12.0, rho = 0.068,
           q, wtip = 0.0, *x;
    int32_t v, ntip = 0;
    uint8_t *pin;
    cr_assert_eq(wr_mesh_rectangle(&m, Lx, b, nx, nx / 5, &d), WR_OK);
    memset(&sd, 0, sizeof sd);
    sd.membrane = WR_MEMBRANE_STVK, sd.bending = WR_BENDING_DIHEDRAL;
    sd.young = E, sd.poisson = 0.0, sd.thickness = h, sd.density = rho, sd.loop_element = elem;
    cr_assert_eq(wr_shell_create(&s, &m, &sd, &d), WR_OK, "%s", d.message);
    x = (double *)malloc(sizeof(double) * 3 * m.nv);
    pin = (uint8_t *)calloc((size_t)m.nv, 1);
    memcpy(x, m.pos, sizeof(double) * 3 * m.nv);
    for (v = 0; v < m.nv; ++v) pin[v] = m.pos[3 * v] < 1.5 * dx;
    memset(&st, 0, sizeof st);
    st.loads.gravity[2] = -9.81, st.loads.fixed = pin;
    cr_assert_eq(wr_statics_solve(&s, x, &st, &ss, &d), WR_OK, "%s", d.message);
    for (v = 0; v < m.nv; ++v)
        if (m.pos[3 * v] > Lx - 1e-9) wtip -= x[3 * v + 2], ++ntip;
    q = rho * 9.81 * h * b;
    free(x), free(pin);
    wr_shell_free(&s);
    wr_mesh_free(&m);
    return wtip / ntip / (q * L * L * L * L / (8.0 * EI));
}

Test(subdiv, loop_shell_ghost_cantilever_clamped_by_two_rows) {
    /* measured tip / beam theory, linear boundary row and ghosts: 1.0193, 1.0293 (nx 40), 0.9893, 0.9937
     * (80), 0.9749, 0.9769 (160, not run here: 16 s): the two boundaries agree within 0.2 % once fine,
     * and the drift below 1 is the union-jack bending bias, not the clamp. A hinge (slope not held)
     * would leave a mechanism. */
    double r[2][2];
    int k, elem;
    for (k = 0; k < 2; ++k)
        for (elem = 1; elem <= 2; ++elem) r[k][elem - 1] = cantilever_tip_ratio(40 << k, elem);
    for (k = 0; k < 2; ++k) {
        cr_assert_lt(fabs(r[k][1] - 1.0), 0.04, "ghosts, nx %d: tip / beam theory %.4f", 40 << k, r[k][1]);
        cr_assert_lt(fabs(r[k][0] - 1.0), 0.04, "linear row, nx %d: tip / beam theory %.4f", 40 << k, r[k][0]);
        cr_assert_lt(fabs(r[k][1] / r[k][0] - 1.0), 0.015, "nx %d: ghosts %.4f vs linear row %.4f", 40 << k, r[k][1],
                     r[k][0]);
    }
}

/* ---- the Loop element's rest from per-face corners (shell.h ON THE LOOP ELEMENT) ------------------ */

/* corner_rest for m: each face's rest corners moved by the rigid motion of its region (faces with
 * centroid x > cx: rotated by 0.7 rad and translated by (3, -2); y > cy, the rest: by -1.1 rad and
 * (-5, 1); the others unmoved), so every stencil crossing a region boundary needs the chart's
 * rotation and translation to be one flat piece again */
static void corner_rest_pieces(wr_mesh *m, double cx, double cy) {
    double *cr = (double *)malloc(sizeof(double) * 6 * (size_t)m->nf);
    int32_t f, k;
    wr_diag d;
    for (f = 0; f < m->nf; ++f) {
        double uv[6], gx = 0.0, gy = 0.0, th = 0.0, t[2] = {0.0, 0.0};
        wr_mesh_face_rest(m, f, uv);
        for (k = 0; k < 3; ++k) gx += uv[2 * k] / 3.0, gy += uv[2 * k + 1] / 3.0;
        if (gx > cx) th = 0.7, t[0] = 3.0, t[1] = -2.0;
        else if (gy > cy) th = -1.1, t[0] = -5.0, t[1] = 1.0;
        for (k = 0; k < 3; ++k) {
            double u = uv[2 * k], w = uv[2 * k + 1];
            cr[6 * f + 2 * k] = cos(th) * u - sin(th) * w + t[0];
            cr[6 * f + 2 * k + 1] = sin(th) * u + cos(th) * w + t[1];
        }
    }
    cr_assert_eq(wr_mesh_set_corner_rest(m, cr, &d), WR_OK, "%s", d.message);
    free(cr);
}

Test(subdiv, loop_shell_rest_from_corners_matches_the_per_vertex_rest) {
    /* a flat sheet whose rest is given per face corner in three rigidly moved pieces: the Loop rest
     * (metric, curvature, weights) equals the per-vertex rest's face by face, the energies agree at a
     * random state, and at the embedded rest (pos = (rest, 0)) energy and gradient are zero */
    wr_mesh m, mc;
    wr_shell s, sc;
    wr_diag d;
    double E, Ec, *g, *x, gmax = 0.0;
    int32_t f, v, i, nloop_cross = 0; /* Loop faces compared */
    lattice_mesh(&m, 12, 7u);
    cr_assert_eq(wr_mesh_copy(&mc, &m, &d), WR_OK);
    corner_rest_pieces(&mc, 6.0, 5.0);
    loop_shell_elem(&s, &m, 1);
    loop_shell_elem(&sc, &mc, 1);
    cr_assert_eq(sc.n_loop_faces, s.n_loop_faces);
    cr_assert_gt(s.n_loop_faces, 100, "Loop faces %d", s.n_loop_faces);
    for (f = 0; f < m.nf; ++f) {
        const wr_shell_koiter_rest *a = s.loop_rest + f, *b = sc.loop_rest + f;
        cr_assert_eq(sc.loop_start[f + 1] - sc.loop_start[f], s.loop_start[f + 1] - s.loop_start[f]);
        if (s.loop_start[f + 1] == s.loop_start[f]) continue;
        for (i = 0; i < 3; ++i) {
            cr_assert_float_eq(b->A[i], a->A[i], 1e-10 * (a->A[0] + a->A[2]), "face %d: A[%d] %.12g vs %.12g", (int)f, (int)i,
                               b->A[i], a->A[i]);
            cr_assert_float_eq(b->B[i], a->B[i], 1e-10 * sqrt(a->A[0] + a->A[2]), "face %d: B[%d] %.3g", (int)f, (int)i, b->B[i]);
        }
        cr_assert_float_eq(sc.loop_wt[f], s.loop_wt[f], 1e-10 * s.loop_wt[f], "face %d: weight", (int)f);
        nloop_cross++;
    }
    cr_assert_gt(nloop_cross, 100);
    cr_assert_eq(wr_shell_energy(&s, m.pos, &E, NULL, &d), WR_OK, "%s", d.message);
    cr_assert_eq(wr_shell_energy(&sc, m.pos, &Ec, NULL, &d), WR_OK, "%s", d.message);
    cr_assert_float_eq(Ec, E, 1e-9 * E, "random state: E %.12g (corners) vs %.12g (per vertex)", Ec, E);
    x = (double *)malloc(sizeof(double) * 3 * (size_t)m.nv);
    g = (double *)malloc(sizeof(double) * 3 * (size_t)m.nv);
    for (v = 0; v < m.nv; ++v) x[3 * v] = m.rest[2 * v], x[3 * v + 1] = m.rest[2 * v + 1], x[3 * v + 2] = 0.0;
    cr_assert_eq(wr_shell_energy(&sc, x, &Ec, g, &d), WR_OK, "%s", d.message);
    for (i = 0; i < 3 * m.nv; ++i) gmax = fmax(gmax, fabs(g[i]));
    cr_assert_lt(fabs(Ec), 1e-18, "energy at the rest %.3g J", Ec);
    cr_assert_lt(gmax, 1e-9, "gradient at the rest %.3g N", gmax); /* Y h = 1e3 N/m on unit cells */
    free(x), free(g);
    wr_shell_free(&s), wr_shell_free(&sc);
    wr_mesh_free(&m), wr_mesh_free(&mc);
}

/* A closed tube (wr_mesh_cylinder_flat, corner_rest = the unrolled pattern) with its pattern cut moved
 * by `shift` cells around: the same surface, the seam elsewhere */
static void tube_seam_shifted(wr_mesh *m, double R, int32_t nu, int32_t shift) {
    double W = 2.0 * 3.14159265358979323846 * R, *cr = (double *)malloc(sizeof(double) * 6 * (size_t)m->nf);
    int32_t f, k;
    wr_diag d;
    for (f = 0; f < m->nf; ++f) {
        double umin = 1e300;
        for (k = 0; k < 3; ++k) {
            cr[6 * f + 2 * k] = m->corner_rest[6 * f + 2 * k] + shift * W / nu;
            cr[6 * f + 2 * k + 1] = m->corner_rest[6 * f + 2 * k + 1];
            umin = fmin(umin, cr[6 * f + 2 * k]);
        }
        if (umin > W - 1e-9 * W)
            for (k = 0; k < 3; ++k) cr[6 * f + 2 * k] -= W;
    }
    cr_assert_eq(wr_mesh_set_corner_rest(m, cr, &d), WR_OK, "%s", d.message);
    free(cr);
}

Test(subdiv, loop_shell_tube_with_a_seam_has_a_flat_rest_wherever_the_seam_is) {
    /* the rest-flat tube rolled up: its Loop rest (flat: B = 0, the unrolled metric) does not depend
     * on where the pattern is cut, so every face's energy is the same with the seam at column 0 or at
     * nu/2 + 1, and the bending energy of the Loop faces is the closed form ½ D / R² per unit area
     * within the union-jack grid's bias (8 %, loop_shell_bent_to_a_cylinder) */
    const double R = 0.3, D = 1e6 * 1e-9 / (12.0 * 0.91);
    const int32_t nu = 40, nh = 12;
    wr_mesh m, ms;
    wr_shell s, ss;
    wr_diag d;
    double Eb = 0.0, area = 0.0, bmax = 0.0;
    int32_t f;
    cr_assert_eq(wr_mesh_cylinder_flat(&m, R, 0.5, nu, nh, &d), WR_OK, "%s", d.message);
    cr_assert(m.corner_rest != NULL);
    cr_assert_eq(wr_mesh_copy(&ms, &m, &d), WR_OK);
    tube_seam_shifted(&ms, R, nu, nu / 2 + 1);
    loop_shell_elem(&s, &m, 1);
    loop_shell_elem(&ss, &ms, 1);
    cr_assert_gt(s.n_loop_faces, 2 * nu * (nh - 3), "Loop faces %d", s.n_loop_faces);
    for (f = 0; f < m.nf; ++f) {
        double em, eb, ems, ebs;
        int i;
        if (s.loop_start[f + 1] == s.loop_start[f]) continue;
        for (i = 0; i < 3; ++i) bmax = fmax(bmax, fabs(s.loop_rest[f].B[i]));
        cr_assert_eq(wr_shell_face_energy(&s, f, m.pos, &em, &eb), WR_OK);
        cr_assert_eq(wr_shell_face_energy(&ss, f, m.pos, &ems, &ebs), WR_OK);
        cr_assert_float_eq(ems, em, 1e-8 * (em + eb), "face %d: membrane %.6g (seam moved) vs %.6g", (int)f, ems, em);
        cr_assert_float_eq(ebs, eb, 1e-8 * eb, "face %d: bending %.6g (seam moved) vs %.6g", (int)f, ebs, eb);
        Eb += eb;
        area += s.area[f];
    }
    cr_assert_lt(bmax, 1e-12, "rest curvature %.3g: the rest is not flat", bmax);
    cr_assert_lt(fabs(Eb / (0.5 * D / (R * R) * area) - 1.0), 0.08, "bending / closed form %.4f", Eb / (0.5 * D / (R * R) * area));
    wr_shell_free(&s), wr_shell_free(&ss);
    wr_mesh_free(&m), wr_mesh_free(&ms);
}
