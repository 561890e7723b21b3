/* wrinkle/body.h — a procedural mannequin for the dynamic simulator: a closed, watertight,
 * self-intersection-free triangle mesh of a standing human figure (~1.7 m, A-pose) built from
 * smooth primitives, so examples and tests need no outside data. Any other body comes in as an OBJ
 * (mesh.h wr_mesh_read_obj).
 * wrinkle v0.1.0 — MIT licence (see LICENSE). Needs core.h and mesh.h; otherwise libc and libm.
 *
 * The figure is the zero level set of F(p) = smooth-min over primitives (ellipsoids for the chest,
 * abdomen, pelvis, head, hands and feet; round cones — capsules with different end radii — for the
 * neck, shoulders, upper arms, forearms, thighs and shins), F < 0 inside, F ≈ the signed distance
 * [m] away from the blends (ellipsoids use a distance bound, so F is not exact there). It is meshed
 * by marching tetrahedra on a regular grid split into Kuhn tetrahedra (six per cube, all sharing
 * the cube's main diagonal, so neighbouring cubes split their shared faces the same way):
 *   - watertight and 2-manifold: every surface vertex sits on a grid edge and is shared by every
 *     tetrahedron around that edge, and a grid value exactly 0 is moved to +0 (outside) so no
 *     vertex sits on a grid node;
 *   - free of self-intersection: the piece of surface inside a tetrahedron is one triangle or one
 *     quad (two triangles) with its corners on that tetrahedron's edges, so pieces of different
 *     tetrahedra meet only along shared faces, exactly in shared segments;
 *   - oriented outward: each triangle's normal points from F < 0 to F > 0.
 *   The surface point on an edge is the linear-interpolation root, clamped to [WR_BODY_CLAMP,
 *   1 − WR_BODY_CLAMP] of the edge so no triangle degenerates to a sliver at a grid node (the
 *   clamp keeps the point on its edge, so the three properties hold).
 *
 * API (wr_body_mannequin fills a wr_mesh: free it with wr_mesh_free; on failure it is left zeroed)
 *   wr_body_mannequin(mesh, desc, diag)   the figure, z up, feet at z = 0, facing −y
 *   wr_body_sdf(desc, p)                  F(p) [m] (negative inside)
 *   wr_body_parts(desc, parts, n)         named axes and radii of the limbs and torso (garment
 *                                         placement: wrap a panel onto a cylinder around a part)
 *
 * EXAMPLE
 *     wr_mesh m;  wr_diag d;  wr_body_desc bd;  int32_t e, open = 0;
 *     memset(&bd, 0, sizeof bd);                            // 1.7 m, ~20k triangles
 *     if (wr_body_mannequin(&m, &bd, &d) != WR_OK) { puts(d.message); return 1; }
 *     for (e = 0; e < m.ne; ++e) open += m.edge_faces[2 * e] < 0 || m.edge_faces[2 * e + 1] < 0;
 *     printf("%d vertices, %d triangles, %d open edges\n", m.nv, m.nf, open);   // ..., 0 open edges
 *     wr_mesh_free(&m);
 *
 * ON UNITS
 *   Metres. desc.height scales the whole figure (the primitives are laid out for 1.7 m).
 *
 * ON THREADS
 *   No global mutable state (the primitive tables are const); distinct calls may run concurrently.
 */
#ifndef WRINKLE_BODY_H
#define WRINKLE_BODY_H

#include "core.h"
#include "mesh.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Defaults (zero means default): height 1.7 m; target_faces 20000 (the grid spacing is chosen so
 * the mesh has about that many triangles); cell > 0 overrides the spacing [m]. target_faces outside
 * [WR_BODY_MIN_FACES, 2e6] is WR_ERR_INVALID_ARG, a grid of more than 2e7 cubes WR_ERR_BUDGET. */
typedef struct wr_body_desc {
    double height;
    int32_t target_faces;
    double cell;
} wr_body_desc;

/* A body part as a cylinder-like axis: from p to q [m] with radius at p and q (round cone). */
typedef struct wr_body_part {
    const char *name; /* "torso", "left_upper_arm", ... (static strings) */
    double p[3], q[3];
    double rp, rq;
} wr_body_part;

#define WR_BODY_N_PARTS 11
/* below ~1e4 triangles the grid (h > 4 cm) no longer resolves the 2.2 cm hands: a hand can come
 * off as its own component (measured at 8000), so fewer are refused */
#define WR_BODY_MIN_FACES 10000
/* marching-tetrahedra root clamp (fraction of a grid edge): keeps the smallest triangle corner
 * angle away from 0 at grid nodes; 0.05 moves a surface point by at most 5 % of a cell */
#define WR_BODY_CLAMP 0.05

WRDEF wr_status wr_body_mannequin(wr_mesh *m, const wr_body_desc *desc, wr_diag *diag);
WRDEF double wr_body_sdf(const wr_body_desc *desc, const double p[3]);
/* Fills parts[0..min(n, WR_BODY_N_PARTS)) and returns WR_BODY_N_PARTS. */
WRDEF int32_t wr_body_parts(const wr_body_desc *desc, wr_body_part *parts, int32_t n);

#ifdef __cplusplus
}
#endif
#endif /* WRINKLE_BODY_H */

/* ============================================================================================ */
#ifdef WRINKLE_IMPLEMENTATION
#ifndef WRINKLE_BODY_IMPLEMENTATION_DONE
#define WRINKLE_BODY_IMPLEMENTATION_DONE

#include <math.h>
#include <string.h>

#ifdef __cplusplus
extern "C" {
#endif

#define WR__BODY_H0 1.7         /* the layout's height [m] */
#define WR__BODY_MAX_CELLS 2.0e7 /* grid cubes: ~1 GB of work arrays would be far past any use */

/* the layout at 1.7 m: round cones (p, q, rp, rq) and ellipsoids (centre, radii), z up, facing −y */
typedef struct wr__body_cone {
    const char *name;
    double p[3], q[3], rp, rq;
} wr__body_cone;
typedef struct wr__body_ell {
    double c[3], r[3];
} wr__body_ell;

static const wr__body_cone wr__body_cones[WR_BODY_N_PARTS] = {
    {"torso", {0.0, 0.0, 0.90}, {0.0, 0.0, 1.40}, 0.115, 0.125},
    {"neck", {0.0, 0.0, 1.44}, {0.0, 0.0, 1.58}, 0.055, 0.048},
    {"shoulders", {-0.175, 0.0, 1.42}, {0.175, 0.0, 1.42}, 0.058, 0.058},
    {"left_upper_arm", {0.19, 0.0, 1.41}, {0.37, 0.0, 1.20}, 0.047, 0.037},
    {"left_forearm", {0.37, 0.0, 1.20}, {0.53, 0.0, 1.01}, 0.036, 0.028},
    {"right_upper_arm", {-0.19, 0.0, 1.41}, {-0.37, 0.0, 1.20}, 0.047, 0.037},
    {"right_forearm", {-0.37, 0.0, 1.20}, {-0.53, 0.0, 1.01}, 0.036, 0.028},
    {"left_thigh", {0.105, 0.0, 0.86}, {0.11, 0.0, 0.48}, 0.072, 0.052},
    {"left_shin", {0.11, 0.0, 0.48}, {0.11, 0.01, 0.09}, 0.050, 0.034},
    {"right_thigh", {-0.105, 0.0, 0.86}, {-0.11, 0.0, 0.48}, 0.072, 0.052},
    {"right_shin", {-0.11, 0.0, 0.48}, {-0.11, 0.01, 0.09}, 0.050, 0.034}};

#define WR__BODY_N_ELL 8
static const wr__body_ell wr__body_ells[WR__BODY_N_ELL] = {
    {{0.0, 0.0, 1.28}, {0.155, 0.105, 0.17}},   /* chest */
    {{0.0, 0.0, 1.06}, {0.140, 0.095, 0.15}},   /* abdomen */
    {{0.0, 0.0, 0.90}, {0.170, 0.105, 0.11}},   /* pelvis */
    {{0.0, -0.005, 1.63}, {0.078, 0.092, 0.108}}, /* head */
    {{0.565, 0.0, 0.955}, {0.022, 0.040, 0.072}},  /* left hand */
    {{-0.565, 0.0, 0.955}, {0.022, 0.040, 0.072}}, /* right hand */
    {{0.11, -0.045, 0.045}, {0.045, 0.115, 0.045}}, /* left foot */
    {{-0.11, -0.045, 0.045}, {0.045, 0.115, 0.045}}}; /* right foot */

/* Signed distance to a round cone (capsule with end radii ra at a, rb at b), exact (the tangent-cone
 * construction: project onto the axis, correct for the slope of the side). */
static double wr__body_round_cone(const double p[3], const double a[3], const double b[3], double ra, double rb) {
    double ba[3], pa[3], l2 = 0.0, l, t, q[2], sn, cs, dot = 0.0, pp = 0.0;
    int i;
    for (i = 0; i < 3; ++i) {
        ba[i] = b[i] - a[i];
        pa[i] = p[i] - a[i];
        l2 += ba[i] * ba[i];
        dot += pa[i] * ba[i];
        pp += pa[i] * pa[i];
    }
    l = sqrt(l2);
    /* 2D frame: q[0] = distance from the axis, q[1] = coordinate along it */
    q[1] = dot / l;
    q[0] = sqrt(fmax(pp - q[1] * q[1], 0.0));
    /* the side line touches both end circles; its outward unit normal is n = (cs, sn) with
     * sn = (ra − rb)/l, and n·q = ra on it; the tangent points sit at s = 0 and s = cs·l along the
     * line's direction (−sn, cs) */
    sn = (ra - rb) / l;
    cs = sqrt(fmax(1.0 - sn * sn, 0.0));
    t = -q[0] * sn + q[1] * cs;
    if (t < 0.0) return sqrt(q[0] * q[0] + q[1] * q[1]) - ra;
    if (t > cs * l) return sqrt(q[0] * q[0] + (q[1] - l) * (q[1] - l)) - rb;
    return q[0] * cs + q[1] * sn - ra;
}

/* Ellipsoid distance bound k0 (k0 − 1)/k1 (Quílez): exact on the surface, a good bound near it. */
static double wr__body_ellipsoid(const double p[3], const double c[3], const double r[3]) {
    double k0 = 0.0, k1 = 0.0;
    int i;
    for (i = 0; i < 3; ++i) {
        double u = (p[i] - c[i]) / r[i];
        k0 += u * u;
        k1 += u * u / (r[i] * r[i]);
    }
    k0 = sqrt(k0);
    k1 = sqrt(k1);
    return k1 > 0.0 ? k0 * (k0 - 1.0) / k1 : -fmin(r[0], fmin(r[1], r[2]));
}

/* polynomial smooth minimum with blend width k [m] (C¹): min(a, b) − k/4 h², h = max(k − |a − b|, 0)/k */
static double wr__body_smin(double a, double b, double k) {
    double h = fmax(k - fabs(a - b), 0.0) / k;
    return fmin(a, b) - 0.25 * k * h * h;
}

/* F at the 1.7 m layout */
static double wr__body_F(const double p[3]) {
    double f = HUGE_VAL;
    int i;
    for (i = 0; i < WR__BODY_N_ELL; ++i) {
        /* hands and feet join their limb with a narrow blend, the torso parts with a wide one */
        double k = i < 4 ? 0.05 : 0.02;
        f = f == HUGE_VAL ? wr__body_ellipsoid(p, wr__body_ells[i].c, wr__body_ells[i].r)
                          : wr__body_smin(f, wr__body_ellipsoid(p, wr__body_ells[i].c, wr__body_ells[i].r), k);
    }
    for (i = 0; i < WR_BODY_N_PARTS; ++i) {
        const wr__body_cone *c = wr__body_cones + i;
        /* limbs blend narrowly (0.02 m), so the arms do not web onto the torso nor the thighs onto
         * each other (their gaps are > 4 cm); torso, neck and shoulders blend widely */
        double k = i < 3 ? 0.05 : 0.025;
        f = wr__body_smin(f, wr__body_round_cone(p, c->p, c->q, c->rp, c->rq), k);
    }
    return f;
}

static double wr__body_scale(const wr_body_desc *d) { return (d && d->height > 0.0 ? d->height : WR__BODY_H0) / WR__BODY_H0; }

WRDEF double wr_body_sdf(const wr_body_desc *desc, const double p[3]) {
    double s = wr__body_scale(desc), q[3];
    q[0] = p[0] / s;
    q[1] = p[1] / s;
    q[2] = p[2] / s;
    return s * wr__body_F(q);
}

WRDEF int32_t wr_body_parts(const wr_body_desc *desc, wr_body_part *parts, int32_t n) {
    double s = wr__body_scale(desc);
    int32_t i, j;
    for (i = 0; i < n && i < WR_BODY_N_PARTS; ++i) {
        parts[i].name = wr__body_cones[i].name;
        for (j = 0; j < 3; ++j) {
            parts[i].p[j] = s * wr__body_cones[i].p[j];
            parts[i].q[j] = s * wr__body_cones[i].q[j];
        }
        parts[i].rp = s * wr__body_cones[i].rp;
        parts[i].rq = s * wr__body_cones[i].rq;
    }
    /* the torso's own radius is the ellipsoids', wider than the cone: report the chest's half width */
    if (n > 0) parts[0].rp = s * 0.17, parts[0].rq = s * 0.155;
    return WR_BODY_N_PARTS;
}

/* ---- marching tetrahedra ------------------------------------------------------------------------ */

typedef struct wr__body_grid {
    int32_t nx, ny, nz;      /* nodes per axis */
    double lo[3], h;         /* node (i, j, k) at lo + h (i, j, k) */
    double *F;               /* node values */
    int32_t *ev;             /* per node: 7 edge-vertex slots (+x, +y, +z, +x+y, +x+z, +y+z, +x+y+z), −1 none */
    double *pos;             /* vertices */
    int32_t nv, cap_v;
    int32_t *tri;
    int32_t nt, cap_t;
} wr__body_grid;

static int64_t wr__body_node(const wr__body_grid *g, int32_t i, int32_t j, int32_t k) {
    return ((int64_t)k * g->ny + j) * g->nx + i;
}

/* the 7 forward edge directions from a node (all edges of the Kuhn split start at their lower node) */
static const int wr__body_dirs[7][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {1, 1, 0}, {1, 0, 1}, {0, 1, 1}, {1, 1, 1}};

/* Vertex on the grid edge between nodes a and b (offsets oa, ob within the cube), created once. */
static int32_t wr__body_edge_vertex(wr__body_grid *g, int32_t ci, int32_t cj, int32_t ck, const int *oa, const int *ob) {
    int lo[3], d[3], s, i;
    int64_t na, nb, nl;
    double fa, fb, t, pa[3];
    int32_t *slot;
    for (i = 0; i < 3; ++i) {
        lo[i] = oa[i] < ob[i] ? oa[i] : ob[i];
        d[i] = oa[i] > ob[i] ? oa[i] - ob[i] : ob[i] - oa[i];
    }
    for (s = 0; s < 7; ++s)
        if (wr__body_dirs[s][0] == d[0] && wr__body_dirs[s][1] == d[1] && wr__body_dirs[s][2] == d[2]) break;
    nl = wr__body_node(g, ci + lo[0], cj + lo[1], ck + lo[2]);
    slot = g->ev + 7 * nl + s;
    if (*slot >= 0) return *slot;
    na = wr__body_node(g, ci + oa[0], cj + oa[1], ck + oa[2]);
    nb = wr__body_node(g, ci + ob[0], cj + ob[1], ck + ob[2]);
    fa = g->F[na];
    fb = g->F[nb];
    t = fa / (fa - fb);
    t = fmin(1.0 - WR_BODY_CLAMP, fmax(WR_BODY_CLAMP, t));
    if (g->nv == g->cap_v) {
        int32_t cap = g->cap_v ? 2 * g->cap_v : 4096;
        double *np = (double *)wr_realloc_array(g->pos, 3 * (size_t)cap, sizeof(double));
        if (!np) return -1;
        g->pos = np;
        g->cap_v = cap;
    }
    for (i = 0; i < 3; ++i) {
        pa[i] = g->lo[i] + g->h * (double)((i == 0 ? ci : i == 1 ? cj : ck) + oa[i]);
        g->pos[3 * g->nv + i] = pa[i] + t * g->h * (double)(ob[i] - oa[i]);
    }
    *slot = g->nv;
    return g->nv++;
}

static int wr__body_push_tri(wr__body_grid *g, int32_t a, int32_t b, int32_t c, const double out_dir[3]) {
    double e1[3], e2[3], n[3];
    int i;
    if (a < 0 || b < 0 || c < 0) return 0;
    if (g->nt == g->cap_t) {
        int32_t cap = g->cap_t ? 2 * g->cap_t : 8192;
        int32_t *nt = (int32_t *)wr_realloc_array(g->tri, 3 * (size_t)cap, sizeof(int32_t));
        if (!nt) return 0;
        g->tri = nt;
        g->cap_t = cap;
    }
    for (i = 0; i < 3; ++i) {
        e1[i] = g->pos[3 * b + i] - g->pos[3 * a + i];
        e2[i] = g->pos[3 * c + i] - g->pos[3 * a + i];
    }
    n[0] = e1[1] * e2[2] - e1[2] * e2[1];
    n[1] = e1[2] * e2[0] - e1[0] * e2[2];
    n[2] = e1[0] * e2[1] - e1[1] * e2[0];
    /* orient outward: the normal must point along out_dir (from the inside corners to the outside) */
    if (n[0] * out_dir[0] + n[1] * out_dir[1] + n[2] * out_dir[2] < 0.0) {
        int32_t t = b;
        b = c;
        c = t;
    }
    g->tri[3 * g->nt] = a;
    g->tri[3 * g->nt + 1] = b;
    g->tri[3 * g->nt + 2] = c;
    g->nt++;
    return 1;
}

/* One tetrahedron (corner offsets o[4] within cube (ci, cj, ck)): 0, 1 or 2 triangles. */
static int wr__body_tet(wr__body_grid *g, int32_t ci, int32_t cj, int32_t ck, const int (*o)[3]) {
    int in[4], nin = 0, a, b, c, i, ia[4], io[4], ni = 0, no = 0;
    double cin[3] = {0, 0, 0}, cout[3] = {0, 0, 0}, dir[3];
    for (a = 0; a < 4; ++a) {
        double f = g->F[wr__body_node(g, ci + o[a][0], cj + o[a][1], ck + o[a][2])];
        in[a] = f < 0.0;
        nin += in[a];
        if (in[a]) ia[ni++] = a;
        else io[no++] = a;
        for (i = 0; i < 3; ++i) (in[a] ? cin : cout)[i] += (double)o[a][i];
    }
    if (nin == 0 || nin == 4) return 1;
    for (i = 0; i < 3; ++i) dir[i] = cout[i] / no - cin[i] / ni;
    if (nin == 1 || nin == 3) { /* one corner apart: a triangle on its three edges */
        int lone = nin == 1 ? ia[0] : io[0], v[3], k = 0;
        for (a = 0; a < 4; ++a)
            if (a != lone) v[k++] = wr__body_edge_vertex(g, ci, cj, ck, o[lone], o[a]);
        return wr__body_push_tri(g, v[0], v[1], v[2], dir);
    }
    /* two and two: a quad on the four edges between the pairs, split along one diagonal */
    a = wr__body_edge_vertex(g, ci, cj, ck, o[ia[0]], o[io[0]]);
    b = wr__body_edge_vertex(g, ci, cj, ck, o[ia[0]], o[io[1]]);
    c = wr__body_edge_vertex(g, ci, cj, ck, o[ia[1]], o[io[1]]);
    i = wr__body_edge_vertex(g, ci, cj, ck, o[ia[1]], o[io[0]]);
    /* a-b-c-i is the quad's cycle (consecutive vertices share an inside or an outside corner) */
    return wr__body_push_tri(g, a, b, c, dir) && wr__body_push_tri(g, a, c, i, dir);
}

/* the six Kuhn tetrahedra of a unit cube: paths 000 → 111 along the axes in every order */
static void wr__body_kuhn(int t, int o[4][3]) {
    static const int perm[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
    int k, i;
    o[0][0] = o[0][1] = o[0][2] = 0;
    for (k = 0; k < 3; ++k) {
        for (i = 0; i < 3; ++i) o[k + 1][i] = o[k][i];
        o[k + 1][perm[t][k]] = 1;
    }
}

static void wr__body_grid_free(wr__body_grid *g) {
    wr_free(g->F);
    wr_free(g->ev);
    wr_free(g->pos);
    wr_free(g->tri);
    memset(g, 0, sizeof *g);
}

WRDEF wr_status wr_body_mannequin(wr_mesh *m, const wr_body_desc *desc, wr_diag *diag) {
    wr__body_grid g;
    double s, h, lo[3] = {-0.63, -0.20, -0.02}, hi[3] = {0.63, 0.14, 1.76}, area = 1.95, cells;
    int32_t target, i, j, k, t;
    int64_t nn, n;
    wr_status st = WR_OK;
    if (!m) return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "body: NULL mesh");
    memset(m, 0, sizeof *m);
    memset(&g, 0, sizeof g);
    if (desc && (!(desc->height >= 0.0) || !(desc->cell >= 0.0) || desc->height - desc->height != 0.0 ||
                 desc->cell - desc->cell != 0.0))
        return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "body: height %g and cell %g must be >= 0 and finite", desc->height,
                       desc->cell);
    target = desc && desc->target_faces ? desc->target_faces : 20000;
    if (target < WR_BODY_MIN_FACES || target > 2000000)
        return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "body: target_faces %d outside [%d, 2e6]", (int)target,
                       WR_BODY_MIN_FACES);
    s = wr__body_scale(desc);
    /* marching tetrahedra on Kuhn cubes leaves about 7.3 triangles per h² of this figure's
     * nominal area (measured: 17.0k triangles at h = 2.90 cm with area = 1.95 m²) */
    h = desc && desc->cell > 0.0 ? desc->cell / s : sqrt(7.3 * area / (double)target);
    cells = ((hi[0] - lo[0]) / h + 3) * ((hi[1] - lo[1]) / h + 3) * ((hi[2] - lo[2]) / h + 3);
    if (cells > WR__BODY_MAX_CELLS)
        return wr_fail(diag, WR_ERR_BUDGET, -1, "body: a %.3g m grid needs %.3g cubes (at most %.0e)", h * s, cells,
                       WR__BODY_MAX_CELLS);
    g.h = h;
    for (i = 0; i < 3; ++i) g.lo[i] = lo[i] - h;
    g.nx = (int32_t)ceil((hi[0] - lo[0]) / h) + 3;
    g.ny = (int32_t)ceil((hi[1] - lo[1]) / h) + 3;
    g.nz = (int32_t)ceil((hi[2] - lo[2]) / h) + 3;
    nn = (int64_t)g.nx * g.ny * g.nz;
    g.F = (double *)wr_alloc_array((size_t)nn, sizeof(double));
    g.ev = (int32_t *)wr_alloc_array(7 * (size_t)nn, sizeof(int32_t));
    if (!g.F || !g.ev) {
        wr__body_grid_free(&g);
        return wr_fail(diag, WR_ERR_NOMEM, -1, "body: out of memory (%lld grid nodes)", (long long)nn);
    }
    for (n = 0; n < 7 * nn; ++n) g.ev[n] = -1;
    for (k = 0; k < g.nz; ++k)
        for (j = 0; j < g.ny; ++j)
            for (i = 0; i < g.nx; ++i) {
                double p[3], f;
                p[0] = g.lo[0] + h * i;
                p[1] = g.lo[1] + h * j;
                p[2] = g.lo[2] + h * k;
                f = wr__body_F(p);
                /* the box border is outside by construction; a value of exactly 0 counts as outside */
                if (i == 0 || j == 0 || k == 0 || i == g.nx - 1 || j == g.ny - 1 || k == g.nz - 1) f = fmax(f, h);
                g.F[wr__body_node(&g, i, j, k)] = f == 0.0 ? 0.0 : f;
            }
    for (k = 0; k + 1 < g.nz && st == WR_OK; ++k)
        for (j = 0; j + 1 < g.ny && st == WR_OK; ++j)
            for (i = 0; i + 1 < g.nx && st == WR_OK; ++i)
                for (t = 0; t < 6; ++t) {
                    int o[4][3];
                    wr__body_kuhn(t, o);
                    if (!wr__body_tet(&g, i, j, k, (const int(*)[3])o)) {
                        st = wr_fail(diag, WR_ERR_NOMEM, -1, "body: out of memory (%d vertices)", (int)g.nv);
                        break;
                    }
                }
    if (st == WR_OK) {
        for (n = 0; n < 3 * (int64_t)g.nv; ++n) g.pos[n] *= s;
        st = wr_mesh_create(m, g.nv, g.pos, NULL, g.nt, g.tri, diag);
    }
    wr__body_grid_free(&g);
    return st;
}

#ifdef __cplusplus
}
#endif
#endif /* WRINKLE_BODY_IMPLEMENTATION_DONE */
#endif /* WRINKLE_IMPLEMENTATION */
