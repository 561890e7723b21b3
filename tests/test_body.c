/* tests/test_body.c — body.h: the procedural mannequin is one closed, outward-oriented genus-0
 * surface of the requested size and height, at the triangle counts the simulator uses; F is the
 * exact distance to a limb away from the blends. */
#include <criterion/criterion.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "wrinkle/body.h"

/* connected components of the vertex graph (union–find over face corners) */
static int32_t body_components(const wr_mesh *m) {
    int32_t *par = (int32_t *)malloc(sizeof(int32_t) * (size_t)m->nv), f, v, n = 0;
    for (v = 0; v < m->nv; ++v) par[v] = v;
    for (f = 0; f < m->nf; ++f) {
        int32_t a = m->faces[3 * f], k;
        while (par[a] != a) a = par[a];
        for (k = 1; k < 3; ++k) {
            int32_t b = m->faces[3 * f + k];
            while (par[b] != b) b = par[b];
            if (a != b) par[b] = a;
        }
    }
    for (v = 0; v < m->nv; ++v) n += par[v] == v;
    free(par);
    return n;
}

/* enclosed volume (1/6) Σ x_a · (x_b × x_c): positive for outward normals */
static double body_volume(const wr_mesh *m) {
    double V = 0.0;
    int32_t f;
    for (f = 0; f < m->nf; ++f) {
        const double *a = m->pos + 3 * m->faces[3 * f], *b = m->pos + 3 * m->faces[3 * f + 1], *c = m->pos + 3 * m->faces[3 * f + 2];
        V += a[0] * (b[1] * c[2] - b[2] * c[1]) + a[1] * (b[2] * c[0] - b[0] * c[2]) + a[2] * (b[0] * c[1] - b[1] * c[0]);
    }
    return V / 6.0;
}

/* Watertight (no boundary edge), one component, Euler characteristic 2 (a sphere: no handle bridging
 * an arm to the chest or the thighs to each other, no hand come loose), outward (V > 0), within 15 %
 * of the requested triangle count, 1.70 m tall within one grid cell, at 1e4, 2e4 and 3e4 triangles. */
Test(body, mannequin_is_one_closed_outward_sphere) {
    int32_t targets[3] = {10000, 20000, 30000}, t;
    for (t = 0; t < 3; ++t) {
        wr_mesh m;
        wr_body_desc bd;
        wr_diag d;
        wr_mesh_quality_stats q;
        double zmin = HUGE_VAL, zmax = -HUGE_VAL, V;
        int32_t v, e, open = 0;
        memset(&bd, 0, sizeof bd);
        bd.target_faces = targets[t];
        cr_assert_eq(wr_body_mannequin(&m, &bd, &d), WR_OK, "%s", d.message);
        for (e = 0; e < m.ne; ++e) open += m.edge_faces[2 * e] < 0 || m.edge_faces[2 * e + 1] < 0;
        wr_mesh_quality(&m, 0, &q);
        cr_assert_eq(open, 0, "%d open edges at %d", (int)open, (int)targets[t]);
        cr_assert_eq(body_components(&m), 1);
        cr_assert_eq(q.euler, 2, "Euler characteristic %d at %d triangles", (int)q.euler, (int)targets[t]);
        cr_assert(fabs((double)(m.nf - targets[t])) < 0.15 * targets[t], "%d triangles for a target of %d", (int)m.nf, (int)targets[t]);
        for (v = 0; v < m.nv; ++v) zmin = fmin(zmin, m.pos[3 * v + 2]), zmax = fmax(zmax, m.pos[3 * v + 2]);
        cr_assert(fabs(zmin) < 0.03 && fabs(zmax - 1.7) < 0.05, "z from %.3f to %.3f m", zmin, zmax);
        V = body_volume(&m);
        /* a 1.7 m adult is ~0.06–0.08 m³; this slim figure has less */
        cr_assert(V > 0.03 && V < 0.09, "volume %.4f m^3", V);
        wr_mesh_free(&m);
    }
}

/* F < 0 inside the chest, the thighs and the head, > 0 between the legs, beside the waist (between
 * the arm and the torso) and above the head; scaling the height scales F and the mesh. */
Test(body, sdf_signs_and_scaling) {
    wr_body_desc bd;
    wr_mesh m1, m2;
    double in[4][3] = {{0, 0, 1.25}, {0.1, 0, 0.7}, {-0.1, 0, 0.7}, {0, 0, 1.63}};
    double out[4][3] = {{0, 0, 0.5}, {0.25, 0, 1.05}, {0, 0, 1.80}, {0, -0.2, 1.2}};
    int i;
    memset(&bd, 0, sizeof bd);
    for (i = 0; i < 4; ++i) {
        cr_assert_lt(wr_body_sdf(&bd, in[i]), 0.0, "point %d", i);
        cr_assert_gt(wr_body_sdf(&bd, out[i]), 0.0, "point %d", i);
    }
    bd.height = 1.7;
    cr_assert_eq(wr_body_mannequin(&m1, &bd, NULL), WR_OK);
    bd.height = 1.87; /* 10 % taller: the same grid in units of the figure, so the same mesh scaled */
    cr_assert_eq(wr_body_mannequin(&m2, &bd, NULL), WR_OK);
    cr_assert_eq(m1.nv, m2.nv);
    for (i = 0; i < 3 * m1.nv; i += 97) cr_assert_float_eq(m2.pos[i], 1.1 * m1.pos[i], 1e-12);
    {
        double p[3] = {0.0, 0.0, 1.25 * 1.1};
        bd.height = 1.87;
        cr_assert_float_eq(wr_body_sdf(&bd, p), 1.1 * wr_body_sdf(NULL, in[0]), 1e-12);
    }
    wr_mesh_free(&m1);
    wr_mesh_free(&m2);
}

Test(body, parts_and_bad_input) {
    wr_body_part parts[WR_BODY_N_PARTS];
    wr_body_desc bd;
    wr_mesh m;
    wr_diag d;
    int32_t i;
    cr_assert_eq(wr_body_parts(NULL, parts, WR_BODY_N_PARTS), WR_BODY_N_PARTS);
    cr_assert_str_eq(parts[0].name, "torso");
    for (i = 0; i < WR_BODY_N_PARTS; ++i) {
        double mid[3];
        int j;
        for (j = 0; j < 3; ++j) mid[j] = 0.5 * (parts[i].p[j] + parts[i].q[j]);
        cr_assert_lt(wr_body_sdf(NULL, mid), 0.0, "the axis of %s runs inside the body", parts[i].name);
    }
    memset(&bd, 0, sizeof bd);
    bd.target_faces = 100;
    cr_assert_eq(wr_body_mannequin(&m, &bd, &d), WR_ERR_INVALID_ARG);
    cr_assert_eq(m.nv, 0);
    bd.target_faces = 0;
    bd.height = -1.0;
    cr_assert_eq(wr_body_mannequin(&m, &bd, &d), WR_ERR_INVALID_ARG);
    bd.height = 0.0;
    bd.cell = 1e-4; /* (1.3/1e-4)·(0.4/1e-4)·(1.8/1e-4) cubes */
    cr_assert_eq(wr_body_mannequin(&m, &bd, &d), WR_ERR_BUDGET);
}

/* Away from every blend, F is the exact distance to one primitive. A point 6 cm in front of the
 * left forearm's midpoint (−y, perpendicular to the arm, which lies in the x–z plane) is ~2.8 cm
 * from the forearm and > 9 cm from every other primitive (the upper arm's end at the elbow, the
 * hand, the chest), more than the 2.5 cm limb blend apart, so the smooth minimum is the plain
 * minimum there and F must equal the distance to the forearm's round cone. That cone is the
 * convex hull of its two end spheres, i.e. the union of the spheres with linearly interpolated
 * centre and radius, so its distance is min over t in [0, 1] of |p − c(t)| − r(t) (a convex
 * function of t): found here by golden-section search to 1e-15 in t, independent of body.h's
 * tangent-cone formula. Tolerance 1e-12 m (the search's and the formula's round-off). */
Test(body, sdf_is_the_round_cone_distance_on_a_limb) {
    wr_body_part parts[WR_BODY_N_PARTS];
    const wr_body_part *fa = NULL;
    double p[3], lo = 0.0, hi = 1.0, gr = 0.5 * (sqrt(5.0) - 1.0), best, t;
    int32_t i, it;
    wr_body_parts(NULL, parts, WR_BODY_N_PARTS);
    for (i = 0; i < WR_BODY_N_PARTS; ++i)
        if (strcmp(parts[i].name, "left_forearm") == 0) fa = parts + i;
    cr_assert_not_null(fa);
    for (i = 0; i < 3; ++i) p[i] = 0.5 * (fa->p[i] + fa->q[i]);
    cr_assert_float_eq(fa->p[1], 0.0, 0.0, "the forearm lies in the x-z plane");
    cr_assert_float_eq(fa->q[1], 0.0, 0.0);
    p[1] -= 0.06;
    for (it = 0; it < 200 && hi - lo > 1e-15; ++it) {
        double a = hi - gr * (hi - lo), b = lo + gr * (hi - lo), fa_ = 0.0, fb = 0.0, ca, cb;
        for (i = 0; i < 3; ++i) {
            ca = p[i] - (fa->p[i] + a * (fa->q[i] - fa->p[i]));
            cb = p[i] - (fa->p[i] + b * (fa->q[i] - fa->p[i]));
            fa_ += ca * ca;
            fb += cb * cb;
        }
        fa_ = sqrt(fa_) - (fa->rp + a * (fa->rq - fa->rp));
        fb = sqrt(fb) - (fa->rp + b * (fa->rq - fa->rp));
        if (fa_ < fb) hi = b;
        else lo = a;
    }
    t = 0.5 * (lo + hi);
    cr_assert(t > 0.0 && t < 1.0, "the nearest point is on the cone's side (t %.6f)", t);
    best = 0.0;
    for (i = 0; i < 3; ++i) {
        double c = p[i] - (fa->p[i] + t * (fa->q[i] - fa->p[i]));
        best += c * c;
    }
    best = sqrt(best) - (fa->rp + t * (fa->rq - fa->rp));
    cr_assert(best > 0.02 && best < 0.04, "distance %.4f m to the forearm", best);
    cr_assert_float_eq(wr_body_sdf(NULL, p), best, 1e-12, "F %.15g vs the cone distance %.15g", wr_body_sdf(NULL, p), best);
}
