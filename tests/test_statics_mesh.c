/* tests/test_statics_mesh.c — statics.h mesh obstacles (ON MESH OBSTACLES): the signed distance of a
 * triangulated sphere against the analytic sphere (signs, values within the chord error, the BVH
 * answer equal to a brute-force scan), the barrier term's gradient and Hessian by finite differences
 * on a cube, a sheet settling on the triangulated sphere against the same sheet on the analytic
 * one, and bad meshes refused. */
#include <criterion/criterion.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "wrinkle/statics.h"

#define PI 3.14159265358979323846

/* A latitude–longitude sphere of radius R about the origin: poles on the z axis, nlat bands of
 * nlon quads (triangles at the poles), outward counter-clockwise. *V, *F malloc'd. */
static void uv_sphere(double R, int32_t nlat, int32_t nlon, double **V, int32_t *nv, int32_t **F, int32_t *nf) {
    int32_t i, j, k = 0, f = 0;
    *nv = 2 + (nlat - 1) * nlon;
    *nf = 2 * nlon * (nlat - 1);
    *V = (double *)malloc(sizeof(double) * 3 * (size_t)*nv);
    *F = (int32_t *)malloc(sizeof(int32_t) * 3 * (size_t)*nf);
    (*V)[k++] = 0, (*V)[k++] = 0, (*V)[k++] = R; /* vertex 0: north pole */
    for (i = 1; i < nlat; ++i)
        for (j = 0; j < nlon; ++j) {
            double th = PI * i / nlat, ph = 2 * PI * j / nlon;
            (*V)[k++] = R * sin(th) * cos(ph), (*V)[k++] = R * sin(th) * sin(ph), (*V)[k++] = R * cos(th);
        }
    (*V)[k++] = 0, (*V)[k++] = 0, (*V)[k++] = -R; /* last: south pole */
#define UVV(i, j) (1 + ((i) - 1) * nlon + ((j) % nlon))
    for (j = 0; j < nlon; ++j) {
        int32_t *t = *F + 3 * f++;
        t[0] = 0, t[1] = UVV(1, j), t[2] = UVV(1, j + 1);
    }
    for (i = 1; i + 1 < nlat; ++i)
        for (j = 0; j < nlon; ++j) {
            int32_t a = UVV(i, j), b = UVV(i + 1, j), c = UVV(i + 1, j + 1), d = UVV(i, j + 1), *t = *F + 3 * f;
            t[0] = a, t[1] = b, t[2] = c, t[3] = a, t[4] = c, t[5] = d;
            f += 2;
        }
    for (j = 0; j < nlon; ++j) {
        int32_t *t = *F + 3 * f++;
        t[0] = *nv - 1, t[1] = UVV(nlat - 1, j + 1), t[2] = UVV(nlat - 1, j);
    }
#undef UVV
}

/* the unit cube [0, 1]³ scaled by L, 12 outward triangles */
static void cube(double L, double V[24], int32_t F[36]) {
    static const int32_t q[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
    int32_t i, k;
    for (i = 0; i < 8; ++i)
        for (k = 0; k < 3; ++k) V[3 * i + k] = L * ((i >> k) & 1);
    for (i = 0; i < 6; ++i) {
        F[6 * i] = q[i][0], F[6 * i + 1] = q[i][1], F[6 * i + 2] = q[i][2];
        F[6 * i + 3] = q[i][0], F[6 * i + 4] = q[i][2], F[6 * i + 5] = q[i][3];
    }
}

static double urand(uint64_t *s) {
    *s = *s * 6364136223846793005ULL + 1442695040888963407ULL;
    return (double)(*s >> 11) / 9007199254740992.0;
}

/* Every point of an inscribed lat–long polyhedron lies between radius R cos δ and R, δ = the largest
 * angular span of a band or sector (π/nlat, 2π/nlon): a point of a face is within angle δ of a
 * corner. So |d_mesh − (|x| − R)| <= R (1 − cos δ) (chord error), the sign is exact outside radius R
 * and inside R cos δ, and the BVH's nearest face gives the brute-force minimum distance. */
Test(statics_mesh, signed_distance_of_a_triangulated_sphere) {
    const double R = 0.1;
    const int32_t nlat = 16, nlon = 32;
    double *V, delta = fmax(PI / nlat, 2 * PI / nlon), chord = R * (1 - cos(delta)), maxerr = 0.0;
    int32_t *F, nv, nf, k, f, n_in = 0, n_out = 0;
    uint64_t seed = 7;
    wr_obstacle_mesh om;
    wr_obstacle ob;
    wr_diag dg;
    uv_sphere(R, nlat, nlon, &V, &nv, &F, &nf);
    cr_assert_eq(wr_obstacle_mesh_create(&om, V, nv, F, nf, &dg), WR_OK, "%s", dg.message);
    cr_expect_eq(om.n_open_edges, 0, "closed sphere: %d open edges", (int)om.n_open_edges);
    memset(&ob, 0, sizeof ob);
    ob.kind = WR_OBSTACLE_MESH;
    ob.mesh = &om;
    for (k = 0; k < 2000; ++k) {
        double x[3], r = 0.02 + 0.16 * urand(&seed), z = 2 * urand(&seed) - 1, ph = 2 * PI * urand(&seed), c[3], g[3];
        double d, brute = HUGE_VAL, rc;
        int32_t face;
        x[0] = r * sqrt(1 - z * z) * cos(ph), x[1] = r * sqrt(1 - z * z) * sin(ph), x[2] = r * z;
        d = wr_obstacle_mesh_closest(&om, x, c, g, &face);
        cr_expect(fabs(wr_obstacle_distance(&ob, x, NULL) - d) == 0.0, "the obstacle kind dispatches to the mesh");
        maxerr = fmax(maxerr, fabs(d - (r - R)));
        cr_expect(fabs(d - (r - R)) <= chord, "r %.4f: d %.6e vs sphere %.6e (chord %.2e)", r, d, r - R, chord);
        if (r > R) {
            cr_expect(d > 0.0, "outside at r %.4f but d %.3e", r, d);
            ++n_out;
        }
        if (r < R * cos(delta)) {
            cr_expect(d < 0.0, "inside at r %.4f but d %.3e", r, d);
            ++n_in;
        }
        rc = sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]);
        cr_expect(rc <= R * (1 + 1e-12) && rc >= R * cos(delta) * (1 - 1e-12), "closest point at radius %.5f", rc);
        cr_expect(fabs(sqrt(g[0] * g[0] + g[1] * g[1] + g[2] * g[2]) - 1.0) < 1e-12);
        cr_expect((g[0] * x[0] + g[1] * x[1] + g[2] * x[2]) / r > 0.8, "∇d points outward (radially) at r %.4f", r);
        for (f = 0; f < nf; ++f) {
            const int32_t *t = F + 3 * f;
            brute = fmin(brute, wr_collision_point_triangle_dist2(x, V + 3 * t[0], V + 3 * t[1], V + 3 * t[2], NULL, NULL,
                                                                   NULL, NULL));
        }
        cr_expect(fabs(fabs(d) - sqrt(brute)) <= 1e-13 * R, "BVH %.15e vs brute force %.15e", fabs(d), sqrt(brute));
    }
    cr_expect(n_in > 100 && n_out > 100, "%d inside, %d outside samples", (int)n_in, (int)n_out);
    cr_expect(maxerr > 0.05 * chord, "the chord bound is not vacuous (max error %.2e, bound %.2e)", maxerr, chord);
    wr_obstacle_mesh_free(&om);
    free(V);
    free(F);
}

/* the barrier term of wr_obstacle_barrier against central differences: g against the energy, H against
 * g (exact in a face region, where ∇²d = 0), ∇d against d near a face, an edge and a corner, inside
 * and outside */
Test(statics_mesh, barrier_gradient_and_hessian_fd) {
    double V[24], dhat = 2e-3, kappa = 30.0, h = 1e-8;
    int32_t F[36], p, i, j;
    wr_obstacle_mesh om;
    wr_obstacle ob;
    const double pts[6][3] = {{0.04, 0.06, 0.1008},   /* above the top face, 0.8 mm */
                              {0.03, -0.0006, 0.05},  /* beside the y = 0 face, 0.6 mm */
                              {0.05, 0.1009, 0.1011}, /* near the edge y = z = 0.1 */
                              {0.1007, 0.1004, 0.1012}, /* near the corner (0.1, 0.1, 0.1) */
                              {0.05, 0.04, 0.097},    /* inside, 3 mm under the top face */
                              {0.099, 0.098, 0.05}};  /* inside near the edge x = y = 0.1 */
    cube(0.1, V, F);
    cr_assert_eq(wr_obstacle_mesh_create(&om, V, 8, F, 12, NULL), WR_OK);
    cr_expect_eq(om.n_open_edges, 0);
    memset(&ob, 0, sizeof ob);
    ob.kind = WR_OBSTACLE_MESH;
    ob.mesh = &om;
    cr_expect(fabs(wr_obstacle_distance(&ob, pts[0], NULL) - 0.0008) < 1e-15);
    cr_expect(fabs(wr_obstacle_distance(&ob, pts[4], NULL) + 0.003) < 1e-15, "3 mm inside: d = -3 mm");
    cr_expect(fabs(wr_obstacle_distance(&ob, pts[5], NULL) + 0.001) < 1e-15, "1 mm inside the x = 0.1 face");
    for (p = 0; p < 6; ++p) {
        double gd[3], d = wr_obstacle_distance(&ob, pts[p], gd);
        for (i = 0; i < 3; ++i) {
            double xp[3], xm[3];
            memcpy(xp, pts[p], sizeof xp), memcpy(xm, pts[p], sizeof xm);
            xp[i] += h, xm[i] -= h;
            cr_expect(fabs((wr_obstacle_distance(&ob, xp, NULL) - wr_obstacle_distance(&ob, xm, NULL)) / (2 * h) - gd[i]) < 1e-6,
                      "point %d: ∂d/∂x%d %.8f vs FD (d %.3e)", (int)p, (int)i, gd[i], d);
        }
    }
    for (p = 0; p < 4; ++p) {
        double g[3], H[9], d, E = wr_obstacle_barrier(&ob, pts[p], dhat, kappa, &d, g, H);
        cr_expect(d > 0.0 && d < dhat && E > 0.0, "point %d inside d̂ (d %.3e, E %.3e)", (int)p, d, E);
        for (i = 0; i < 3; ++i) {
            double xp[3], xm[3], gp[3], gm[3], Ep, Em;
            memcpy(xp, pts[p], sizeof xp), memcpy(xm, pts[p], sizeof xm);
            xp[i] += h, xm[i] -= h;
            Ep = wr_obstacle_barrier(&ob, xp, dhat, kappa, NULL, gp, NULL);
            Em = wr_obstacle_barrier(&ob, xm, dhat, kappa, NULL, gm, NULL);
            cr_expect(fabs((Ep - Em) / (2 * h) - g[i]) <= 1e-6 * (1e-3 + fabs(g[i])), "point %d: g%d %.6e vs FD %.6e", (int)p,
                      (int)i, g[i], (Ep - Em) / (2 * h));
            if (p < 2) /* face regions: H is the whole Hessian */
                for (j = 0; j < 3; ++j)
                    cr_expect(fabs((gp[j] - gm[j]) / (2 * h) - H[3 * j + i]) <= 1e-5 * (1.0 + fabs(H[3 * j + i])),
                              "point %d: H%d%d %.6e vs FD %.6e", (int)p, (int)j, (int)i, H[3 * j + i], (gp[j] - gm[j]) / (2 * h));
        }
        {
            /* edge / corner regions: along ∇d the full Hessian is b'' (∇²d ∇d = 0), the dropped part is off it */
            double gd[3], gp[3], gm[3], xp[3], xm[3], Hg = 0.0, fd = 0.0;
            wr_obstacle_distance(&ob, pts[p], gd);
            for (i = 0; i < 3; ++i) xp[i] = pts[p][i] + h * gd[i], xm[i] = pts[p][i] - h * gd[i];
            wr_obstacle_barrier(&ob, xp, dhat, kappa, NULL, gp, NULL);
            wr_obstacle_barrier(&ob, xm, dhat, kappa, NULL, gm, NULL);
            for (i = 0; i < 3; ++i)
                for (j = 0; j < 3; ++j) Hg += gd[i] * H[3 * i + j] * gd[j];
            for (i = 0; i < 3; ++i) fd += gd[i] * (gp[i] - gm[i]) / (2 * h);
            cr_expect(fabs(Hg - fd) <= 1e-5 * fabs(fd), "point %d: ∇dᵀH∇d %.6e vs FD %.6e", (int)p, Hg, fd);
        }
    }
    {
        double g[3], H[9], d;
        cr_expect(wr_obstacle_barrier(&ob, pts[4], dhat, kappa, &d, g, H) == HUGE_VAL && d < 0.0, "inside: +inf");
        cr_expect_eq(wr_obstacle_barrier(&ob, (const double[3]){0.05, 0.05, 0.2}, dhat, kappa, &d, g, H), 0.0);
        cr_expect(g[0] == 0.0 && g[1] == 0.0 && g[2] == 0.0 && H[8] == 0.0, "beyond d̂: no force");
    }
    wr_obstacle_mesh_free(&om);
}

typedef struct sheet_case {
    wr_mesh m;
    wr_shell s;
    uint8_t *fixed;
    int32_t centre;
} sheet_case;

static void sheet_setup(sheet_case *c, int32_t n) {
    wr_shell_desc d;
    memset(c, 0, sizeof *c);
    cr_assert_eq(wr_mesh_rectangle(&c->m, 0.5, 0.5, n, n, NULL), WR_OK);
    memset(&d, 0, sizeof d);
    d.young = 1e5, d.poisson = 0.3, d.thickness = 1e-3, d.density = 200.0;
    d.membrane = WR_MEMBRANE_TFT, d.bending = WR_BENDING_QUADRATIC;
    cr_assert_eq(wr_shell_create(&c->s, &c->m, &d, NULL), WR_OK);
    c->fixed = (uint8_t *)calloc((size_t)c->m.nv, 1);
    c->centre = (n / 2) * (n + 1) + n / 2;
    c->fixed[c->centre] = 1;
}

/* the sheet centred over the origin 5 mm above z = R, its centre pinned 1 mm above the top (as in
 * test_statics.c's sheet_on_sphere: a free sheet slides off a frictionless ball) */
static wr_status sheet_solve(sheet_case *c, const wr_obstacle *ob, double R, double *x, wr_statics_stats *st, wr_diag *dg) {
    wr_statics_desc sd;
    int32_t v;
    for (v = 0; v < c->m.nv; ++v) {
        x[3 * v] = c->m.rest[2 * v] - 0.25;
        x[3 * v + 1] = c->m.rest[2 * v + 1] - 0.25;
        x[3 * v + 2] = R + 0.005;
    }
    x[3 * c->centre + 2] = R + 0.001;
    memset(&sd, 0, sizeof sd);
    sd.loads.fixed = c->fixed;
    sd.loads.gravity[2] = -9.81;
    sd.contact.obstacles = ob;
    sd.contact.n_obstacles = 1;
    sd.contact.dhat = 2e-3;
    return wr_statics_solve(&c->s, x, &sd, st, dg);
}

/* The same sheet on the analytic sphere and on a 48 × 96 lat–long triangulation of it (chord error
 * c = R(1 − cos(π/48)) = 0.21 mm), d̂ = 2 mm: both converge, no vertex of the mesh solve is inside
 * the mesh (CCD), and every vertex agrees in (ρ, z) = (distance from the vertical axis, height)
 * within c + d̂: each contact vertex rests somewhere in (0, d̂) off its surface (where depends on κ
 * and, for the mesh's IPC sum over the faces within d̂, on how many faces that is: ON MESH
 * OBSTACLES) and the two surfaces are c apart. Rotation about the vertical axis through the pin is
 * a zero-energy mode of the analytic problem (frictionless ball), which the facets break, so
 * Cartesian positions are not compared. Measured (sheet 10 × 10): 1.18 mm at 48 bands, d̂ = 2 mm;
 * 0.82 / 0.86 mm at 48 / 96 bands with d̂ = 1 mm; 0.65 / 0.32 mm with d̂ = 0.5 mm; Π within 0.1 %. */
Test(statics_mesh, sheet_on_triangulated_sphere_matches_analytic) {
    const double R = 0.1;
    sheet_case c;
    wr_obstacle ball, mball;
    wr_obstacle_mesh om;
    wr_statics_stats sa, sm;
    wr_diag dg;
    double *V, *xa, *xm, dmax = 0.0, dmin = HUGE_VAL, chord = R * (1 - cos(PI / 48));
    int32_t *F, nv, nf, v;
    sheet_setup(&c, 10);
    xa = (double *)malloc(sizeof(double) * 3 * (size_t)c.m.nv);
    xm = (double *)malloc(sizeof(double) * 3 * (size_t)c.m.nv);
    memset(&ball, 0, sizeof ball);
    ball.kind = WR_OBSTACLE_SPHERE;
    ball.radius = R;
    cr_assert_eq(sheet_solve(&c, &ball, R, xa, &sa, &dg), WR_OK, "analytic: %s", dg.message);
    uv_sphere(R, 48, 96, &V, &nv, &F, &nf);
    cr_assert_eq(wr_obstacle_mesh_create(&om, V, nv, F, nf, &dg), WR_OK, "%s", dg.message);
    memset(&mball, 0, sizeof mball);
    mball.kind = WR_OBSTACLE_MESH;
    mball.mesh = &om;
    cr_assert_eq(sheet_solve(&c, &mball, R, xm, &sm, &dg), WR_OK, "mesh: %s", dg.message);
    for (v = 0; v < c.m.nv; ++v) {
        double e = hypot(hypot(xa[3 * v], xa[3 * v + 1]) - hypot(xm[3 * v], xm[3 * v + 1]), xa[3 * v + 2] - xm[3 * v + 2]);
        dmax = fmax(dmax, e);
        if (!c.fixed[v]) dmin = fmin(dmin, wr_obstacle_distance(&mball, xm + 3 * v, NULL));
    }
    cr_expect(dmin > 0.0 && dmin == sm.min_distance, "mesh: min distance %.3e (stats %.3e)", dmin, sm.min_distance);
    cr_expect(sm.n_contacts > 0 && sa.n_contacts > 0, "both rest on the ball (%d, %d contacts)", sm.n_contacts, sa.n_contacts);
    cr_expect(dmax <= chord + 2e-3, "(rho, z) differ by %.3e m (chord error %.2e m, d̂ 2 mm)", dmax, chord);
    cr_expect(fabs(sm.energy - sa.energy) <= 1e-2 * fabs(sa.energy), "Π %.6e (mesh) vs %.6e", sm.energy, sa.energy);
    cr_log_info("sheet on sphere: analytic %d Newton, mesh %d Newton, max (rho, z) diff %.3e m, min d %.3e m", sa.iterations,
                sm.iterations, dmax, sm.min_distance);
    wr_obstacle_mesh_free(&om);
    free(V), free(F), free(xa), free(xm), free(c.fixed);
    wr_shell_free(&c.s);
    wr_mesh_free(&c.m);
}

Test(statics_mesh, bad_meshes_refused) {
    double V[24], W[24], x[3] = {0.05, 0.05, 0.2};
    int32_t F[36], G[36];
    wr_obstacle_mesh om;
    wr_obstacle ob;
    wr_diag dg;
    sheet_case c;
    wr_statics_desc sd;
    cube(0.1, V, F);
    cr_expect_eq(wr_obstacle_mesh_create(&om, V, 8, F, 0, &dg), WR_ERR_INVALID_ARG, "no faces");
    cr_expect_eq(om.nf, 0, "left zeroed");
    cr_expect_eq(wr_obstacle_mesh_create(&om, V, 0, F, 12, &dg), WR_ERR_INVALID_ARG, "no vertices");
    cr_expect_eq(wr_obstacle_mesh_create(&om, NULL, 8, F, 12, &dg), WR_ERR_INVALID_ARG);
    memcpy(G, F, sizeof G);
    G[7] = 8;
    cr_expect_eq(wr_obstacle_mesh_create(&om, V, 8, G, 12, &dg), WR_ERR_INVALID_ARG, "index out of range");
    cr_expect_eq(dg.item, 2);
    memcpy(G, F, sizeof G);
    G[13] = G[12];
    cr_expect_eq(wr_obstacle_mesh_create(&om, V, 8, G, 12, &dg), WR_ERR_GEOMETRY, "repeated corner");
    cr_expect_eq(dg.item, 4);
    memcpy(W, V, sizeof W);
    W[3 * 2] = W[3 * 3], W[3 * 2 + 1] = W[3 * 3 + 1], W[3 * 2 + 2] = W[3 * 3 + 2]; /* vertex 2 onto 3 */
    cr_expect_eq(wr_obstacle_mesh_create(&om, W, 8, F, 12, &dg), WR_ERR_GEOMETRY, "zero-area face: %s", dg.message);
    memcpy(W, V, sizeof W);
    W[5] = NAN;
    cr_expect_eq(wr_obstacle_mesh_create(&om, W, 8, F, 12, &dg), WR_ERR_DOMAIN, "non-finite");
    cr_expect_eq(dg.item, 1);
    cr_expect_eq(om.pos, NULL);
    wr_obstacle_mesh_free(&om); /* safe on the zeroed struct */
    /* a mesh obstacle without its mesh, and one behind an open mesh (a single triangle): */
    sheet_setup(&c, 4);
    memset(&ob, 0, sizeof ob);
    ob.kind = WR_OBSTACLE_MESH;
    memset(&sd, 0, sizeof sd);
    sd.contact.obstacles = &ob;
    sd.contact.n_obstacles = 1;
    {
        double *xs = (double *)malloc(sizeof(double) * 3 * (size_t)c.m.nv);
        memcpy(xs, c.m.pos, sizeof(double) * 3 * (size_t)c.m.nv);
        cr_expect_eq(wr_statics_solve(&c.s, xs, &sd, NULL, &dg), WR_ERR_INVALID_ARG, "NULL mesh refused");
        free(xs);
    }
    cr_assert_eq(wr_obstacle_mesh_create(&om, V, 8, F, 1, &dg), WR_OK);
    cr_expect_eq(om.n_open_edges, 3, "one triangle: 3 open edges");
    cr_expect(fabs(wr_obstacle_mesh_closest(&om, x, NULL, NULL, NULL) + 0.2) < 1e-15, "behind the face (its normal is -z)");
    wr_obstacle_mesh_free(&om);
    free(c.fixed);
    wr_shell_free(&c.s);
    wr_mesh_free(&c.m);
}
