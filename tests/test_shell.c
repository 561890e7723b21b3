/* tests/test_shell.c — shell.h: finite-difference gradients and Hessians of every energy, rigid-motion
 * invariance, zero energy at rest, closed-form stretch energy, cylinder bending against the plate
 * value, orthotropy, SPD projection, error paths. */
#include <criterion/criterion.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "wrinkle/shell.h"

#define SH_PI 3.14159265358979323846
/* Central differences with step h on O(1)-scaled problems have truncation error ~h² ≈ 1e-12 and
 * round-off ~1e-16/h ≈ 1e-10 relative: the brief's 1e-6 bound leaves four orders of margin. */
#define SH_FD_STEP 1e-6
#define SH_FD_TOL 1e-6

typedef struct sh_dense {
    int32_t n; /* dofs */
    double *K;
    int32_t fail_after; /* sink test: return an error on call number fail_after (-1 = never) */
    int32_t calls;
    int32_t max_k;
    double min_ratio; /* min over elements of λ_min / max|λ| */
} sh_dense;

static wr_status sh_dense_add(void *user, int32_t k, const int32_t *verts, const double *Ke) {
    sh_dense *d = (sh_dense *)user;
    int32_t a, b, i, j;
    if (d->fail_after >= 0 && d->calls == d->fail_after) return WR_ERR_NOMEM;
    d->calls++;
    if (k > d->max_k) d->max_k = k;
    if (3 * k <= WR_DENSE_MAX) {
        double lam[WR_DENSE_MAX], big;
        wr_dense_sym_eig(3 * k, Ke, lam, NULL);
        big = fmax(fabs(lam[0]), fabs(lam[3 * k - 1]));
        if (big > 0 && lam[0] / big < d->min_ratio) d->min_ratio = lam[0] / big;
    }
    for (a = 0; a < k; ++a)
        for (b = 0; b < k; ++b)
            for (i = 0; i < 3; ++i)
                for (j = 0; j < 3; ++j)
                    d->K[(3 * verts[a] + i) * d->n + 3 * verts[b] + j] += Ke[(3 * a + i) * 3 * k + 3 * b + j];
    return WR_OK;
}

static void sh_desc(wr_shell_desc *d, wr_membrane_model mm, wr_bending_model bm) {
    memset(d, 0, sizeof *d);
    d->membrane = mm;
    d->bending = bm;
    d->young = 3.0;
    d->poisson = 0.3;
    d->thickness = 0.2;
}

/* 3×3-cell rectangle with jittered interior rest coordinates (so no two faces share a shape). */
static void sh_mesh(wr_mesh *m, wr_rng *rng, int32_t n) {
    int32_t i, j;
    cr_assert_eq(wr_mesh_rectangle(m, 1.0, 1.0, n, n, NULL), WR_OK);
    for (j = 1; j < n; ++j)
        for (i = 1; i < n; ++i) {
            int32_t v = j * (n + 1) + i;
            m->rest[2 * v] += 0.15 / n * (2.0 * wr_rng_uniform(rng) - 1.0);
            m->rest[2 * v + 1] += 0.15 / n * (2.0 * wr_rng_uniform(rng) - 1.0);
        }
}

/* Deformed state: rest lifted to 3D, bent, sheared and jittered by `amp` of the cell size. */
static void sh_deform(const wr_mesh *m, wr_rng *rng, double amp, double *x) {
    int32_t v;
    for (v = 0; v < m->nv; ++v) {
        double u = m->rest[2 * v], w = m->rest[2 * v + 1];
        x[3 * v] = 1.05 * u + 0.1 * w + amp * (2.0 * wr_rng_uniform(rng) - 1.0);
        x[3 * v + 1] = 0.95 * w + amp * (2.0 * wr_rng_uniform(rng) - 1.0);
        x[3 * v + 2] = 0.3 * u * u - 0.2 * u * w + amp * (2.0 * wr_rng_uniform(rng) - 1.0);
    }
}

static double sh_norm(const double *a, int32_t n) {
    double s = 0.0;
    int32_t i;
    for (i = 0; i < n; ++i) s += a[i] * a[i];
    return sqrt(s);
}

/* FD check of gradient and assembled element Hessians (both raw and against the energy). */
static void sh_fd_check(const wr_shell *s, const double *x0, const char *what) {
    int32_t n = 3 * s->nv, i, j;
    double *x = (double *)malloc(sizeof(double) * n), *g = (double *)malloc(sizeof(double) * n);
    double *gp = (double *)malloc(sizeof(double) * n), *gm = (double *)malloc(sizeof(double) * n);
    double *gfd = (double *)malloc(sizeof(double) * n), *Hfd = (double *)calloc((size_t)n * n, sizeof(double));
    double E, Ep, Em, errg, errh, nh;
    sh_dense d;
    wr_hess_sink sink;
    memcpy(x, x0, sizeof(double) * n);
    cr_assert_eq(wr_shell_energy(s, x, &E, g, NULL), WR_OK, "%s", what);
    for (i = 0; i < n; ++i) {
        double xi = x[i];
        x[i] = xi + SH_FD_STEP;
        cr_assert_eq(wr_shell_energy(s, x, &Ep, gp, NULL), WR_OK);
        x[i] = xi - SH_FD_STEP;
        cr_assert_eq(wr_shell_energy(s, x, &Em, gm, NULL), WR_OK);
        x[i] = xi;
        gfd[i] = (Ep - Em) / (2.0 * SH_FD_STEP);
        for (j = 0; j < n; ++j) Hfd[j * n + i] = (gp[j] - gm[j]) / (2.0 * SH_FD_STEP);
    }
    for (i = 0; i < n; ++i) gfd[i] -= g[i];
    errg = sh_norm(gfd, n) / sh_norm(g, n);
    d.n = n;
    d.K = (double *)calloc((size_t)n * n, sizeof(double));
    d.fail_after = -1;
    d.calls = 0;
    d.max_k = 0;
    d.min_ratio = 1e300;
    sink.user = &d;
    sink.add = sh_dense_add;
    cr_assert_eq(wr_shell_hessian_elements(s, x, 0, &sink, NULL), WR_OK);
    nh = sh_norm(d.K, n * n);
    for (i = 0; i < n * n; ++i) Hfd[i] -= d.K[i];
    errh = sh_norm(Hfd, n * n) / nh;
    cr_expect(sh_norm(g, n) > 0.0, "%s: zero gradient, test is void", what);
    cr_expect(errg < SH_FD_TOL, "%s: gradient FD rel. error %.3e", what, errg);
    cr_expect(errh < SH_FD_TOL, "%s: Hessian FD rel. error %.3e", what, errh);
    free(x);
    free(g);
    free(gp);
    free(gm);
    free(gfd);
    free(Hfd);
    free(d.K);
}

Test(shell, fd_gradient_hessian_all_models) {
    wr_rng rng;
    wr_mesh m;
    int mm, bm;
    wr_rng_seed(&rng, 7);
    sh_mesh(&m, &rng, 3);
    for (mm = 0; mm < 3; ++mm)
        for (bm = 0; bm < 3; ++bm) {
            wr_shell s;
            wr_shell_desc d;
            double *x = (double *)malloc(sizeof(double) * 3 * m.nv);
            char what[64];
            if (mm == 2 && bm == 2) {
                free(x);
                continue;
            }
            sh_desc(&d, (wr_membrane_model)mm, (wr_bending_model)bm);
            cr_assert_eq(wr_shell_create(&s, &m, &d, NULL), WR_OK);
            sh_deform(&m, &rng, 0.05, x);
            snprintf(what, sizeof what, "membrane %d bending %d", mm, bm);
            sh_fd_check(&s, x, what);
            wr_shell_free(&s);
            free(x);
        }
    wr_mesh_free(&m);
}

Test(shell, fd_orthotropic_and_curved_rest) {
    wr_rng rng;
    wr_mesh m;
    wr_shell s;
    wr_shell_desc d;
    double *x, *grain, *rest3;
    int32_t f, v;
    wr_rng_seed(&rng, 11);
    sh_mesh(&m, &rng, 3);
    x = (double *)malloc(sizeof(double) * 3 * m.nv);
    rest3 = (double *)malloc(sizeof(double) * 3 * m.nv);
    grain = (double *)malloc(sizeof(double) * m.nf);
    for (f = 0; f < m.nf; ++f) grain[f] = SH_PI * wr_rng_uniform(&rng);
    sh_desc(&d, WR_MEMBRANE_STVK, WR_BENDING_MIDEDGE);
    d.orthotropic = 1;
    d.young_warp = 5.0;
    d.young_weft = 2.0;
    d.shear_modulus = 0.4;
    d.poisson_warp = 0.35;
    d.grain_angle = grain;
    cr_assert_eq(wr_shell_create(&s, &m, &d, NULL), WR_OK);
    sh_deform(&m, &rng, 0.05, x);
    sh_fd_check(&s, x, "orthotropic");
    wr_shell_free(&s);
    /* 3D curved rest (rest metric and rest curvature from rest_pos3) */
    for (v = 0; v < m.nv; ++v) {
        double u = m.rest[2 * v], w = m.rest[2 * v + 1];
        rest3[3 * v] = u;
        rest3[3 * v + 1] = w;
        rest3[3 * v + 2] = 0.25 * sin(2.0 * u) + 0.1 * w * w;
    }
    sh_desc(&d, WR_MEMBRANE_STVK, WR_BENDING_MIDEDGE);
    d.rest_pos3 = rest3;
    cr_assert_eq(wr_shell_create(&s, &m, &d, NULL), WR_OK);
    cr_expect(s.bbar != NULL);
    sh_fd_check(&s, x, "curved rest");
    wr_shell_free(&s);
    free(x);
    free(rest3);
    free(grain);
    wr_mesh_free(&m);
}

/* Element kernel alone, every boundary mask (missing neighbours), random stencils. */
Test(shell, fd_midedge_element_every_mask) {
    wr_rng rng;
    int32_t mask, trial, i, j;
    wr_rng_seed(&rng, 3);
    /* mask 0 (an isolated triangle): all mid-edge normals are the face normal, II ≡ 0, so the energy
     * is the constant ½ bbarᵀQ bbar with zero gradient and Hessian — checked exactly below. */
    for (mask = 0; mask < 8; ++mask)
        for (trial = 0; trial < 3; ++trial) {
            double x[18], Q[9], bbar[3], g[18], H[324], gp[18], gm[18], E, Ep, Em, errg = 0, errh = 0, ng = 0, nh = 0;
            /* a face near the xy-plane and neighbours folded by random dihedral angles */
            static const double base[18] = {0, 0, 0, 1, 0, 0, 0.2, 0.9, 0, 1.0, 1.0, 0, -0.6, 0.6, 0, 0.6, -0.8, 0};
            double M[9] = {2.0, 0.3, 0.1, 0.3, 1.5, -0.2, 0.1, -0.2, 1.0}; /* SPD */
            for (i = 0; i < 18; ++i) x[i] = base[i] + 0.15 * (2.0 * wr_rng_uniform(&rng) - 1.0);
            for (i = 0; i < 3; ++i) x[9 + 3 * i + 2] += 0.5 * (2.0 * wr_rng_uniform(&rng) - 1.0);
            for (i = 0; i < 9; ++i) Q[i] = M[i];
            for (i = 0; i < 3; ++i) bbar[i] = 0.3 * (2.0 * wr_rng_uniform(&rng) - 1.0);
            cr_assert_eq(wr_shell_midedge_element(x, mask, Q, bbar, &E, g, H, NULL), WR_OK);
            for (i = 0; i < 18; ++i) {
                double xi = x[i], gfd;
                x[i] = xi + SH_FD_STEP;
                wr_shell_midedge_element(x, mask, Q, bbar, &Ep, gp, NULL, NULL);
                x[i] = xi - SH_FD_STEP;
                wr_shell_midedge_element(x, mask, Q, bbar, &Em, gm, NULL, NULL);
                x[i] = xi;
                gfd = (Ep - Em) / (2.0 * SH_FD_STEP);
                errg += (gfd - g[i]) * (gfd - g[i]);
                ng += g[i] * g[i];
                for (j = 0; j < 18; ++j) {
                    double h = (gp[j] - gm[j]) / (2.0 * SH_FD_STEP);
                    errh += (h - H[j * 18 + i]) * (h - H[j * 18 + i]);
                    nh += H[j * 18 + i] * H[j * 18 + i];
                }
                /* absent vertices: exactly zero rows */
                if (i >= 9 && !(mask & (1 << ((i - 9) / 3)))) cr_expect_eq(g[i], 0.0);
            }
            if (mask == 0) {
                /* Σ_k w_k = 0 cancels only to round-off in the Hessian: |H| <= 1e-13 relative to |Q||bbar|·|x| ~ 1 */
                cr_expect(ng == 0.0 && errg == 0.0 && sqrt(nh) < 1e-13, "isolated triangle: |g|² %g |H| %g", ng,
                          sqrt(nh));
                continue;
            }
            cr_expect(sqrt(errg / ng) < SH_FD_TOL, "mask %d: gradient rel. error %.3e", mask, sqrt(errg / ng));
            cr_expect(sqrt(errh / nh) < SH_FD_TOL, "mask %d: Hessian rel. error %.3e", mask, sqrt(errh / nh));
        }
}

Test(shell, rigid_motion_invariance) {
    wr_rng rng;
    wr_mesh m;
    int mm, bm;
    wr_rng_seed(&rng, 5);
    sh_mesh(&m, &rng, 4);
    for (mm = 0; mm < 2; ++mm)
        for (bm = 0; bm < 2; ++bm) {
            wr_shell s;
            wr_shell_desc d;
            int32_t v, i;
            double *x = (double *)malloc(sizeof(double) * 3 * m.nv), *y = (double *)malloc(sizeof(double) * 3 * m.nv);
            double *g = (double *)malloc(sizeof(double) * 3 * m.nv);
            double E0, E1, ft[3] = {0, 0, 0}, tq[3] = {0, 0, 0}, gn;
            /* rotation about axis (1,2,2)/3 by 0.7 rad, then translation */
            double ax[3] = {1.0 / 3, 2.0 / 3, 2.0 / 3}, c = cos(0.7), sn = sin(0.7), R[9];
            for (i = 0; i < 9; ++i) {
                int a = i / 3, b = i % 3;
                R[i] = (a == b ? c : 0.0) + (1.0 - c) * ax[a] * ax[b];
            }
            R[1] -= sn * ax[2];
            R[2] += sn * ax[1];
            R[3] += sn * ax[2];
            R[5] -= sn * ax[0];
            R[6] -= sn * ax[1];
            R[7] += sn * ax[0];
            sh_desc(&d, (wr_membrane_model)mm, (wr_bending_model)bm);
            cr_assert_eq(wr_shell_create(&s, &m, &d, NULL), WR_OK);
            sh_deform(&m, &rng, 0.05, x);
            cr_assert_eq(wr_shell_energy(&s, x, &E0, g, NULL), WR_OK);
            for (v = 0; v < m.nv; ++v)
                for (i = 0; i < 3; ++i)
                    y[3 * v + i] = R[3 * i] * x[3 * v] + R[3 * i + 1] * x[3 * v + 1] + R[3 * i + 2] * x[3 * v + 2] +
                                   0.3 * (i + 1);
            cr_assert_eq(wr_shell_energy(&s, y, &E1, NULL, NULL), WR_OK);
            cr_expect(fabs(E1 - E0) <= 1e-12 * E0, "models %d/%d: E %.17g vs %.17g", mm, bm, E0, E1);
            /* gradient orthogonal to the 6 rigid modes: net force and net torque vanish */
            for (v = 0; v < m.nv; ++v) {
                const double *p = x + 3 * v, *q = g + 3 * v;
                for (i = 0; i < 3; ++i) ft[i] += q[i];
                tq[0] += p[1] * q[2] - p[2] * q[1];
                tq[1] += p[2] * q[0] - p[0] * q[2];
                tq[2] += p[0] * q[1] - p[1] * q[0];
            }
            gn = sh_norm(g, 3 * m.nv);
            cr_expect(sh_norm(ft, 3) < 1e-12 * gn && sh_norm(tq, 3) < 1e-12 * gn, "models %d/%d: force %.3e torque %.3e",
                      mm, bm, sh_norm(ft, 3), sh_norm(tq, 3));
            wr_shell_free(&s);
            free(x);
            free(y);
            free(g);
        }
    wr_mesh_free(&m);
}

Test(shell, zero_energy_at_rest) {
    wr_rng rng;
    wr_mesh m;
    int mm, bm;
    double *rest3, *x, *g, E;
    int32_t v;
    wr_rng_seed(&rng, 9);
    sh_mesh(&m, &rng, 4);
    x = (double *)malloc(sizeof(double) * 3 * m.nv);
    g = (double *)malloc(sizeof(double) * 3 * m.nv);
    rest3 = (double *)malloc(sizeof(double) * 3 * m.nv);
    for (v = 0; v < m.nv; ++v) {
        x[3 * v] = m.rest[2 * v];
        x[3 * v + 1] = m.rest[2 * v + 1];
        x[3 * v + 2] = 0.0;
    }
    for (mm = 0; mm < 3; ++mm)
        for (bm = 0; bm < 3; ++bm) {
            wr_shell s;
            wr_shell_desc d;
            sh_desc(&d, (wr_membrane_model)mm, (wr_bending_model)bm);
            cr_assert_eq(wr_shell_create(&s, &m, &d, NULL), WR_OK);
            cr_assert_eq(wr_shell_energy(&s, x, &E, g, NULL), WR_OK);
            cr_expect(fabs(E) < 1e-28 && sh_norm(g, 3 * m.nv) < 1e-13, "models %d/%d: E %g |g| %g", mm, bm, E,
                      sh_norm(g, 3 * m.nv));
            wr_shell_free(&s);
        }
    /* a curved 3D rest shape is stress-free in its own configuration */
    for (v = 0; v < m.nv; ++v) {
        rest3[3 * v] = m.rest[2 * v];
        rest3[3 * v + 1] = m.rest[2 * v + 1];
        rest3[3 * v + 2] = 0.3 * sin(3.0 * m.rest[2 * v]) * m.rest[2 * v + 1];
    }
    {
        wr_shell s;
        wr_shell_desc d;
        sh_desc(&d, WR_MEMBRANE_STVK, WR_BENDING_MIDEDGE);
        d.rest_pos3 = rest3;
        cr_assert_eq(wr_shell_create(&s, &m, &d, NULL), WR_OK);
        cr_assert_eq(wr_shell_energy(&s, rest3, &E, g, NULL), WR_OK);
        cr_expect(fabs(E) < 1e-28 && sh_norm(g, 3 * m.nv) < 1e-13, "curved rest: E %g |g| %g", E, sh_norm(g, 3 * m.nv));
        /* but flattening it costs bending energy */
        cr_assert_eq(wr_shell_energy(&s, x, &E, NULL, NULL), WR_OK);
        cr_expect(E > 1e-4, "flattened curved rest: E %g", E);
        wr_shell_free(&s);
    }
    free(x);
    free(g);
    free(rest3);
    wr_mesh_free(&m);
}

/* Uniform biaxial stretch (s1, s2) plus shear of a flat square: every face has the same Green strain
 * ε = ½(FᵀF − I), and the energy is A·h(α/2 tr²ε + β tr ε²) with TFW Eq. 33's α, β. */
Test(shell, uniform_stretch_closed_form) {
    wr_mesh m;
    int32_t v;
    double Y = 2.0e5, nu = 0.35, h = 1.0e-3, alpha = Y * nu / (1 - nu * nu), beta = Y / (2 * (1 + nu));
    double Fm[6] = {1.1, 0.05, 0.0, 1.03, 0.02, -0.01}; /* 3×2 row-major deformation gradient */
    double C11 = 0, C22 = 0, C12 = 0, e11, e22, e12, expect, E, *x;
    int k, mm;
    cr_assert_eq(wr_mesh_rectangle(&m, 0.8, 0.5, 5, 4, NULL), WR_OK);
    x = (double *)malloc(sizeof(double) * 3 * m.nv);
    for (v = 0; v < m.nv; ++v)
        for (k = 0; k < 3; ++k) x[3 * v + k] = Fm[2 * k] * m.rest[2 * v] + Fm[2 * k + 1] * m.rest[2 * v + 1];
    for (k = 0; k < 3; ++k) {
        C11 += Fm[2 * k] * Fm[2 * k];
        C22 += Fm[2 * k + 1] * Fm[2 * k + 1];
        C12 += Fm[2 * k] * Fm[2 * k + 1];
    }
    e11 = 0.5 * (C11 - 1);
    e22 = 0.5 * (C22 - 1);
    e12 = 0.5 * C12;
    expect = 0.8 * 0.5 * h * (0.5 * alpha * (e11 + e22) * (e11 + e22) + beta * (e11 * e11 + e22 * e22 + 2 * e12 * e12));
    for (mm = 0; mm < 2; ++mm) {
        wr_shell s;
        wr_shell_desc d;
        memset(&d, 0, sizeof d);
        d.young = Y;
        d.poisson = nu;
        d.thickness = h;
        d.membrane = (wr_membrane_model)mm; /* both principal strains are > 0 here: TFT = StVK */
        d.bending = WR_BENDING_MIDEDGE;     /* planar deformation: no bending energy */
        cr_assert_eq(wr_shell_create(&s, &m, &d, NULL), WR_OK);
        cr_assert_eq(wr_shell_energy(&s, x, &E, NULL, NULL), WR_OK);
        cr_expect(fabs(E - expect) <= 1e-12 * expect, "membrane %d: E %.15g expected %.15g", mm, E, expect);
        wr_shell_free(&s);
    }
    free(x);
    wr_mesh_free(&m);
}

/* Cylinder: bend a W×H strip around the y axis, vertices exactly on the radius-R cylinder
 * (isometric in the arc length). Plate value: B/(2R²) per unit area.
 * Mid-edge: each union-jack triangle has exactly one vertical (crease) edge with dihedral angle
 * φ = Δu/R; the normalised mid-edge normal gives the face curvature κ = 2·chord·sin(φ/2)/Δu² =
 * (1/R)(1 − φ²/12 + O(φ⁴)) (chord vs arc), so interior faces carry (B/2R²)(1 − φ²/6) and the energy
 * error there is ≤ φ²/6. Triangles whose crease is a FREE boundary edge (columns 0 and nx−1) see
 * n̂ = face normal (TFW App. A) and carry no bending, so the total is short by exactly 1/nx of it:
 * E_total / (E_plate (1 − 1/nx)) = 1 − O(φ²). We check both and that the error shrinks with nx. */
Test(shell, cylinder_midedge_matches_plate) {
    double R = 0.5, Wd = 1.0, Hd = 0.4, B = 0.0, prev = 1.0;
    int32_t nxs[3] = {8, 16, 32}, t;
    for (t = 0; t < 3; ++t) {
        wr_mesh m;
        wr_shell s;
        wr_shell_desc d;
        int32_t nx = nxs[t], ny = nxs[t] / 2, v, f;
        double *x, E, plate, phi = Wd / nx / R, Eint = 0.0, Aint = 0.0, rel_int, rel_tot;
        cr_assert_eq(wr_mesh_rectangle(&m, Wd, Hd, nx, ny, NULL), WR_OK);
        x = (double *)malloc(sizeof(double) * 3 * m.nv);
        for (v = 0; v < m.nv; ++v) {
            double u = m.rest[2 * v];
            x[3 * v] = R * sin(u / R);
            x[3 * v + 1] = m.rest[2 * v + 1];
            x[3 * v + 2] = R * (1.0 - cos(u / R));
        }
        memset(&d, 0, sizeof d);
        d.young = 1.0e6;
        d.poisson = 0.3;
        d.thickness = 1e-3;
        d.membrane = WR_MEMBRANE_NONE;
        cr_assert_eq(wr_shell_create(&s, &m, &d, NULL), WR_OK);
        B = s.bending_stiffness;
        cr_expect(fabs(B - 1.0e6 * 1e-9 / (12.0 * (1 - 0.09))) < 1e-15 * B);
        cr_assert_eq(wr_shell_energy(&s, x, &E, NULL, NULL), WR_OK);
        for (f = 0; f < m.nf; ++f) {
            int32_t verts[6], mask = wr_shell_face_stencil(&s, f, verts), k;
            double x18[18], e;
            int interior_crease = 1;
            for (k = 0; k < 3; ++k) {
                /* a boundary edge on x = 0 or x = W is a free crease */
                int32_t a = verts[(k + 1) % 3], b = verts[(k + 2) % 3];
                if (!(mask & (1 << k)) && m.rest[2 * a] == m.rest[2 * b]) interior_crease = 0;
            }
            for (k = 0; k < 18; ++k) x18[k] = verts[k / 3] >= 0 ? x[3 * verts[k / 3] + k % 3] : 0.0;
            cr_assert_eq(wr_shell_midedge_element(x18, mask, s.qbend + 9 * f, NULL, &e, NULL, NULL, NULL), WR_OK);
            if (interior_crease) {
                Eint += e;
                Aint += s.area[f];
            }
        }
        plate = B / (2 * R * R);
        rel_int = fabs(Eint / (plate * Aint) - 1.0);
        rel_tot = fabs(E / (plate * Wd * Hd * (1.0 - 1.0 / nx)) - 1.0);
        cr_expect(rel_int <= phi * phi / 6.0 * 1.01, "nx %d: interior faces rel. error %.3e > phi^2/6 = %.3e", nx,
                  rel_int, phi * phi / 6);
        cr_expect(rel_tot <= phi * phi / 6.0 * 1.01, "nx %d: total rel. error %.3e", nx, rel_tot);
        cr_expect(fabs(E / (plate * Wd * Hd) - 1.0) < prev, "error must shrink with refinement");
        prev = fabs(E / (plate * Wd * Hd) - 1.0);
        wr_shell_free(&s);
        free(x);
        wr_mesh_free(&m);
    }
}

/* Quadratic bending on the same cylinder: interior vertices only, (B/2)|Lx|²/A_v → (B/2R²)·A_v.
 * On this grid the diagonals carry zero cotangent weight (right angles), so (Lx)_v/A_v is the
 * 5-point second difference of (R sin(u/R), R(1−cos(u/R))): (2 cos φ − 2)/Δu² · R(·) = (1/R)(1 −
 * φ²/12 + O(φ⁴)) times the unit normal. Hence E/E_plate(interior area) = 1 − φ²/6 + O(φ⁴): we bound
 * the error by 1.01·φ²/6 and require it to shrink ~4× per refinement. */
Test(shell, cylinder_quadratic_matches_plate) {
    double R = 0.5, Wd = 1.0, Hd = 0.4, prev = 0.0;
    int32_t nxs[3] = {8, 16, 32}, t;
    for (t = 0; t < 3; ++t) {
        wr_mesh m;
        wr_shell s;
        wr_shell_desc d;
        int32_t nx = nxs[t], ny = nxs[t] / 2, v, i;
        double *x, E, Aint = 0.0, phi = Wd / nx / R, rel;
        cr_assert_eq(wr_mesh_rectangle(&m, Wd, Hd, nx, ny, NULL), WR_OK);
        x = (double *)malloc(sizeof(double) * 3 * m.nv);
        for (v = 0; v < m.nv; ++v) {
            double u = m.rest[2 * v];
            x[3 * v] = R * sin(u / R);
            x[3 * v + 1] = m.rest[2 * v + 1];
            x[3 * v + 2] = R * (1.0 - cos(u / R));
        }
        memset(&d, 0, sizeof d);
        d.young = 1.0e6;
        d.poisson = 0.3;
        d.thickness = 1e-3;
        d.membrane = WR_MEMBRANE_NONE;
        d.bending = WR_BENDING_QUADRATIC;
        cr_assert_eq(wr_shell_create(&s, &m, &d, NULL), WR_OK);
        cr_expect_eq(s.n_qb, (nx - 1) * (ny - 1));
        for (i = 0; i < s.n_qb; ++i) Aint += s.bending_stiffness / s.qb_coef[i];
        /* mixed Voronoi areas of interior vertices tile the interior */
        cr_expect(fabs(Aint - (Wd - Wd / nx) * (Hd - Hd / ny)) < 1e-12, "interior area %.15g", Aint);
        cr_assert_eq(wr_shell_energy(&s, x, &E, NULL, NULL), WR_OK);
        rel = fabs(E / (s.bending_stiffness / (2 * R * R) * Aint) - 1.0);
        cr_expect(rel <= 1.01 * phi * phi / 6.0, "nx %d: rel. error %.3e > phi^2/6 %.3e", nx, rel, phi * phi / 6.0);
        if (t > 0) cr_expect(rel < 0.3 * prev, "nx %d: error %.3e did not shrink from %.3e", nx, rel, prev);
        prev = rel;
        wr_shell_free(&s);
        free(x);
        wr_mesh_free(&m);
    }
}

/* Orthotropic: stretch along the grain direction θ → only warp strain, W = h·C11·ε²/2 with
 * C11 = E1/(1−ν12ν21); the same stretch across the grain gives E2/(1−ν12ν21). */
Test(shell, orthotropic_grain_direction) {
    wr_mesh m;
    wr_shell s;
    wr_shell_desc d;
    double theta = 0.5, E1 = 4.0e5, E2 = 1.0e5, n12 = 0.3, h = 5e-4, st = 1.04, *x, *grain, E;
    double n21 = n12 * E2 / E1, den = 1 - n12 * n21, eps = 0.5 * (st * st - 1), A = 0.6 * 0.6;
    int32_t v, f, pass;
    cr_assert_eq(wr_mesh_rectangle(&m, 0.6, 0.6, 4, 4, NULL), WR_OK);
    x = (double *)malloc(sizeof(double) * 3 * m.nv);
    grain = (double *)malloc(sizeof(double) * m.nf);
    for (f = 0; f < m.nf; ++f) grain[f] = theta;
    memset(&d, 0, sizeof d);
    d.orthotropic = 1;
    d.young_warp = E1;
    d.young_weft = E2;
    d.shear_modulus = 3e4;
    d.poisson_warp = n12;
    d.thickness = h;
    d.grain_angle = grain;
    d.bending = WR_BENDING_NONE;
    cr_assert_eq(wr_shell_create(&s, &m, &d, NULL), WR_OK);
    for (pass = 0; pass < 2; ++pass) {
        double ang = theta + pass * 0.5 * SH_PI, c = cos(ang), sn = sin(ang), expect;
        for (v = 0; v < m.nv; ++v) {
            double u = m.rest[2 * v], w = m.rest[2 * v + 1], along = c * u + sn * w;
            /* F = I + (st − 1) d dᵀ */
            x[3 * v] = u + (st - 1) * along * c;
            x[3 * v + 1] = w + (st - 1) * along * sn;
            x[3 * v + 2] = 0.0;
        }
        cr_assert_eq(wr_shell_energy(&s, x, &E, NULL, NULL), WR_OK);
        expect = A * h * 0.5 * (pass == 0 ? E1 : E2) / den * eps * eps;
        cr_expect(fabs(E - expect) < 1e-12 * expect, "pass %d: E %.15g expected %.15g", pass, E, expect);
    }
    wr_shell_free(&s);
    free(x);
    free(grain);
    wr_mesh_free(&m);
}

Test(shell, projected_hessian_psd_and_sink_errors) {
    wr_rng rng;
    wr_mesh m;
    wr_shell s;
    wr_shell_desc d;
    sh_dense dn;
    wr_hess_sink sink;
    wr_diag dg;
    double *x, *lam;
    int32_t n, i;
    wr_rng_seed(&rng, 21);
    sh_mesh(&m, &rng, 3);
    n = 3 * m.nv;
    x = (double *)malloc(sizeof(double) * n);
    lam = (double *)malloc(sizeof(double) * n);
    sh_desc(&d, WR_MEMBRANE_STVK, WR_BENDING_MIDEDGE);
    cr_assert_eq(wr_shell_create(&s, &m, &d, NULL), WR_OK);
    /* compress strongly so the raw Hessian is indefinite */
    sh_deform(&m, &rng, 0.1, x);
    for (i = 0; i < n; i += 3) x[i] *= 0.6;
    dn.n = n;
    dn.K = (double *)calloc((size_t)n * n, sizeof(double));
    dn.fail_after = -1;
    dn.calls = 0;
    dn.max_k = 0;
    dn.min_ratio = 1e300;
    sink.user = &dn;
    sink.add = sh_dense_add;
    cr_assert_eq(wr_shell_hessian_elements(&s, x, 0, &sink, NULL), WR_OK);
    cr_expect_eq(dn.calls, m.nf);
    cr_expect_eq(dn.max_k, 6);
    cr_expect(dn.min_ratio < -1e-3, "compressed state should give indefinite element Hessians (min %.3e)",
              dn.min_ratio);
    dn.min_ratio = 1e300;
    cr_assert_eq(wr_shell_hessian_elements(&s, x, 1, &sink, NULL), WR_OK);
    cr_expect(dn.min_ratio > -1e-12, "projected element Hessian: min eigenvalue / max |eigenvalue| = %.3e",
              dn.min_ratio);
    /* sink failure stops and is reported with the face index */
    dn.fail_after = 3;
    dn.calls = 0;
    cr_expect_eq(wr_shell_hessian_elements(&s, x, 0, &sink, &dg), WR_ERR_NOMEM);
    cr_expect_eq(dg.item, 3);
    cr_expect_eq(wr_shell_hessian_elements(&s, x, 0, NULL, &dg), WR_ERR_INVALID_ARG);
    wr_shell_free(&s);
    /* quadratic-bending stencils: sink failure reported too */
    sh_desc(&d, WR_MEMBRANE_NONE, WR_BENDING_QUADRATIC);
    cr_assert_eq(wr_shell_create(&s, &m, &d, NULL), WR_OK);
    dn.fail_after = 1;
    dn.calls = 0;
    cr_expect_eq(wr_shell_hessian_elements(&s, x, 0, &sink, &dg), WR_ERR_NOMEM);
    cr_expect_eq(dg.item, 1);
    wr_shell_free(&s);
    free(dn.K);
    free(x);
    free(lam);
    wr_mesh_free(&m);
}

/* ON ELEMENT HESSIANS: face blocks + quadratic stencils streamed separately sum to the full stream,
 * the quadratic part does not depend on x, and unknown parts flags are rejected */
Test(shell, hessian_parts_sum_to_all) {
    wr_rng rng;
    wr_mesh m;
    wr_shell s;
    wr_shell_desc d;
    sh_dense all, part, part2;
    wr_hess_sink sink;
    wr_diag dg;
    double *x;
    int32_t n, i, calls_faces;
    wr_rng_seed(&rng, 33);
    sh_mesh(&m, &rng, 3);
    n = 3 * m.nv;
    x = (double *)malloc(sizeof(double) * n);
    sh_deform(&m, &rng, 0.05, x);
    sh_desc(&d, WR_MEMBRANE_TFT, WR_BENDING_QUADRATIC);
    cr_assert_eq(wr_shell_create(&s, &m, &d, NULL), WR_OK);
    cr_assert(s.n_qb > 0, "no quadratic stencils: test is void");
    memset(&all, 0, sizeof all);
    all.n = part.n = part2.n = n;
    all.fail_after = -1;
    all.min_ratio = 1e300;
    part = all;
    part2 = all;
    all.K = (double *)calloc((size_t)n * n, sizeof(double));
    part.K = (double *)calloc((size_t)n * n, sizeof(double));
    part2.K = (double *)calloc((size_t)n * n, sizeof(double));
    sink.add = sh_dense_add;
    sink.user = &all;
    cr_assert_eq(wr_shell_hessian_elements(&s, x, 0, &sink, NULL), WR_OK);
    sink.user = &part;
    cr_assert_eq(wr_shell_hessian_elements_part(&s, x, 0, WR_SHELL_HESS_FACES, &sink, NULL), WR_OK);
    calls_faces = part.calls;
    cr_expect_eq(calls_faces, m.nf);
    cr_assert_eq(wr_shell_hessian_elements_part(&s, x, 0, WR_SHELL_HESS_QUADRATIC, &sink, NULL), WR_OK);
    cr_expect_eq(part.calls - calls_faces, s.n_qb);
    cr_expect_eq(part.calls, all.calls);
    for (i = 0; i < n * n; ++i)
        cr_expect(fabs(part.K[i] - all.K[i]) <= 1e-12 * (fabs(all.K[i]) + 1.0), "entry %d: %g vs %g", (int)i, part.K[i],
                  all.K[i]);
    /* the quadratic part at the rest positions is the same matrix (constant in x) */
    sink.user = &part2;
    cr_assert_eq(wr_shell_hessian_elements_part(&s, m.pos, 0, WR_SHELL_HESS_QUADRATIC, &sink, NULL), WR_OK);
    memset(part.K, 0, sizeof(double) * (size_t)n * n);
    part.calls = 0;
    sink.user = &part;
    cr_assert_eq(wr_shell_hessian_elements_part(&s, x, 0, WR_SHELL_HESS_QUADRATIC, &sink, NULL), WR_OK);
    for (i = 0; i < n * n; ++i) cr_expect_eq(part.K[i], part2.K[i]);
    cr_expect_eq(wr_shell_hessian_elements_part(&s, x, 0, 4, &sink, &dg), WR_ERR_INVALID_ARG);
    part.calls = 0;
    cr_expect_eq(wr_shell_hessian_elements_part(&s, x, 0, 0, &sink, NULL), WR_OK);
    cr_expect_eq(part.calls, 0);
    wr_shell_free(&s);
    free(all.K);
    free(part.K);
    free(part2.K);
    free(x);
    wr_mesh_free(&m);
}

Test(shell, vertex_masses_and_strain) {
    wr_mesh m;
    wr_shell s;
    wr_shell_desc d;
    double *mass, tot = 0, eps[3];
    int32_t v;
    cr_assert_eq(wr_mesh_rectangle(&m, 2.0, 1.0, 4, 3, NULL), WR_OK);
    sh_desc(&d, WR_MEMBRANE_STVK, WR_BENDING_MIDEDGE);
    d.density = 300.0;
    cr_assert_eq(wr_shell_create(&s, &m, &d, NULL), WR_OK);
    mass = (double *)malloc(sizeof(double) * m.nv);
    wr_shell_vertex_masses(&s, mass);
    for (v = 0; v < m.nv; ++v) tot += mass[v];
    cr_expect(fabs(tot - 300.0 * 0.2 * 2.0) < 1e-12, "total mass %.15g", tot);
    for (v = 0; v < m.nv; ++v) m.pos[3 * v] *= 1.1;
    wr_shell_face_strain(&s, 5, m.pos, eps);
    cr_expect(fabs(eps[0] - 0.5 * (1.21 - 1)) < 1e-14 && fabs(eps[1]) < 1e-14 && fabs(eps[2]) < 1e-14);
    wr_shell_free(&s);
    wr_shell_free(&s); /* safe on a zeroed shell */
    free(mass);
    wr_mesh_free(&m);
}

Test(shell, error_paths) {
    wr_mesh m, m3;
    wr_shell s;
    wr_shell_desc d;
    wr_diag dg;
    double grain[2] = {0.0, NAN}, *x, E;
    static const double sq_pos[12] = {0, 0, 0, 1, 0, 0.3, 0, 1, 0, 1, 1, 0.2};
    static const int32_t sq_faces[6] = {0, 1, 2, 1, 3, 2};
    static const double deg_rest[6] = {0, 0, 1, 0, 2, 0};
    static const int32_t deg_faces[3] = {0, 1, 2};
    cr_assert_eq(wr_mesh_rectangle(&m, 1.0, 1.0, 1, 1, NULL), WR_OK);
    cr_assert_eq(wr_mesh_create(&m3, 4, sq_pos, NULL, 2, sq_faces, NULL), WR_OK);
    sh_desc(&d, WR_MEMBRANE_STVK, WR_BENDING_MIDEDGE);
    cr_expect_eq(wr_shell_create(&s, &m, NULL, &dg), WR_ERR_INVALID_ARG);
    cr_expect_eq(wr_shell_create(&s, NULL, &d, &dg), WR_ERR_INVALID_ARG);
    cr_expect_eq(wr_shell_create(NULL, &m, &d, &dg), WR_ERR_INVALID_ARG);
    d.young = 0.0;
    cr_expect_eq(wr_shell_create(&s, &m, &d, &dg), WR_ERR_DOMAIN);
    sh_desc(&d, WR_MEMBRANE_STVK, WR_BENDING_MIDEDGE);
    d.thickness = -1.0;
    cr_expect_eq(wr_shell_create(&s, &m, &d, &dg), WR_ERR_DOMAIN);
    sh_desc(&d, WR_MEMBRANE_STVK, WR_BENDING_MIDEDGE);
    d.poisson = 1.0;
    cr_expect_eq(wr_shell_create(&s, &m, &d, &dg), WR_ERR_DOMAIN);
    sh_desc(&d, WR_MEMBRANE_STVK, WR_BENDING_MIDEDGE);
    d.density = -1.0;
    cr_expect_eq(wr_shell_create(&s, &m, &d, &dg), WR_ERR_DOMAIN);
    sh_desc(&d, WR_MEMBRANE_STVK, WR_BENDING_MIDEDGE);
    d.bending_stiffness = NAN;
    cr_expect_eq(wr_shell_create(&s, &m, &d, &dg), WR_ERR_DOMAIN);
    sh_desc(&d, (wr_membrane_model)7, WR_BENDING_MIDEDGE);
    cr_expect_eq(wr_shell_create(&s, &m, &d, &dg), WR_ERR_INVALID_ARG);
    sh_desc(&d, WR_MEMBRANE_STVK, (wr_bending_model)-1);
    cr_expect_eq(wr_shell_create(&s, &m, &d, &dg), WR_ERR_INVALID_ARG);
    /* orthotropy */
    sh_desc(&d, WR_MEMBRANE_STVK, WR_BENDING_MIDEDGE);
    d.orthotropic = 1;
    d.young_warp = 2;
    d.young_weft = 1;
    d.shear_modulus = 0;
    cr_expect_eq(wr_shell_create(&s, &m, &d, &dg), WR_ERR_DOMAIN);
    d.shear_modulus = 0.5;
    d.poisson_warp = 1.5; /* 2.25·1/2 >= 1 */
    cr_expect_eq(wr_shell_create(&s, &m, &d, &dg), WR_ERR_DOMAIN);
    d.poisson_warp = 0.3;
    d.membrane = WR_MEMBRANE_TFT;
    cr_expect_eq(wr_shell_create(&s, &m, &d, &dg), WR_ERR_UNSUPPORTED);
    d.membrane = WR_MEMBRANE_STVK;
    d.bending = WR_BENDING_QUADRATIC;
    cr_expect_eq(wr_shell_create(&s, &m, &d, &dg), WR_ERR_UNSUPPORTED);
    d.bending = WR_BENDING_MIDEDGE;
    d.bending_stiffness = 1.0;
    cr_expect_eq(wr_shell_create(&s, &m, &d, &dg), WR_ERR_INVALID_ARG);
    d.bending_stiffness = 0.0;
    cr_expect_eq(wr_shell_create(&s, &m3, &d, &dg), WR_ERR_UNSUPPORTED); /* 3D rest: no grain frame */
    d.grain_angle = grain;
    cr_expect_eq(wr_shell_create(&s, &m, &d, &dg), WR_ERR_DOMAIN);
    cr_expect_eq(dg.item, 1);
    /* quadratic bending needs a flat rest */
    sh_desc(&d, WR_MEMBRANE_TFT, WR_BENDING_QUADRATIC);
    cr_expect_eq(wr_shell_create(&s, &m3, &d, &dg), WR_ERR_UNSUPPORTED);
    d.rest_pos3 = sq_pos;
    cr_expect_eq(wr_shell_create(&s, &m, &d, &dg), WR_ERR_UNSUPPORTED);
    /* a 3D rest shape with a non-finite coordinate */
    {
        double bad[12];
        memcpy(bad, sq_pos, sizeof bad);
        bad[4] = INFINITY;
        sh_desc(&d, WR_MEMBRANE_STVK, WR_BENDING_MIDEDGE);
        d.rest_pos3 = bad;
        cr_expect_eq(wr_shell_create(&s, &m, &d, &dg), WR_ERR_DOMAIN);
        cr_expect_eq(dg.item, 1);
    }
    wr_mesh_free(&m);
    /* degenerate (zero-area) rest face */
    cr_assert_eq(wr_mesh_create(&m, 3, NULL, deg_rest, 1, deg_faces, NULL), WR_OK);
    sh_desc(&d, WR_MEMBRANE_STVK, WR_BENDING_MIDEDGE);
    cr_expect_eq(wr_shell_create(&s, &m, &d, &dg), WR_ERR_GEOMETRY);
    cr_expect_eq(dg.item, 0);
    cr_expect(s.faces == NULL, "failed create leaves a zeroed shell");
    wr_mesh_free(&m);
    /* evaluation errors: a collapsed face, a non-finite coordinate, NULL x */
    cr_assert_eq(wr_mesh_rectangle(&m, 1.0, 1.0, 2, 2, NULL), WR_OK);
    sh_desc(&d, WR_MEMBRANE_STVK, WR_BENDING_MIDEDGE);
    cr_assert_eq(wr_shell_create(&s, &m, &d, NULL), WR_OK);
    x = (double *)malloc(sizeof(double) * 3 * m.nv);
    memcpy(x, m.pos, sizeof(double) * 3 * m.nv);
    memcpy(x + 3 * m.faces[1], x + 3 * m.faces[0], sizeof(double) * 3); /* face 0 collapses */
    cr_expect_eq(wr_shell_energy(&s, x, &E, NULL, &dg), WR_ERR_GEOMETRY);
    {
        sh_dense dn;
        wr_hess_sink sink;
        dn.n = 3 * m.nv;
        dn.K = (double *)calloc((size_t)dn.n * dn.n, sizeof(double));
        dn.fail_after = -1;
        dn.calls = 0;
        dn.max_k = 0;
        dn.min_ratio = 1e300;
        sink.user = &dn;
        sink.add = sh_dense_add;
        cr_expect_eq(wr_shell_hessian_elements(&s, x, 1, &sink, &dg), WR_ERR_GEOMETRY);
        free(dn.K);
    }
    memcpy(x, m.pos, sizeof(double) * 3 * m.nv);
    x[4] = NAN;
    cr_expect_eq(wr_shell_energy(&s, x, &E, NULL, &dg), WR_ERR_DOMAIN);
    cr_expect_eq(wr_shell_energy(&s, NULL, &E, NULL, &dg), WR_ERR_INVALID_ARG);
    wr_shell_free(&s);
    free(x);
    wr_mesh_free(&m);
    wr_mesh_free(&m3);
}

/* ==== Baraff–Witkin membrane and dihedral bending ================================================ */

static void sh_desc_bw(wr_shell_desc *d, wr_bending_model bm) {
    sh_desc(d, WR_MEMBRANE_BARAFF_WITKIN, bm);
    d->stretch_warp = 4.0;
    d->stretch_weft = 1.5;
    d->stretch_shear = 0.7;
}

Test(shell, fd_baraff_witkin_and_dihedral) {
    wr_rng rng;
    wr_mesh m;
    wr_shell s;
    wr_shell_desc d;
    double *x, *grain, *rest3;
    int32_t f, v, bm;
    wr_rng_seed(&rng, 17);
    sh_mesh(&m, &rng, 3);
    x = (double *)malloc(sizeof(double) * 3 * m.nv);
    rest3 = (double *)malloc(sizeof(double) * 3 * m.nv);
    grain = (double *)malloc(sizeof(double) * m.nf);
    for (f = 0; f < m.nf; ++f) grain[f] = SH_PI * wr_rng_uniform(&rng);
    /* BW with every bending model, random grain */
    for (bm = 0; bm < 4; ++bm) {
        char what[64];
        sh_desc_bw(&d, (wr_bending_model)bm);
        d.grain_angle = grain;
        cr_assert_eq(wr_shell_create(&s, &m, &d, NULL), WR_OK);
        sh_deform(&m, &rng, 0.05, x);
        snprintf(what, sizeof what, "Baraff-Witkin, bending %d", (int)bm);
        sh_fd_check(&s, x, what);
        wr_shell_free(&s);
    }
    /* StVK + dihedral with warp/weft bending and grain; TFT + dihedral */
    sh_desc(&d, WR_MEMBRANE_STVK, WR_BENDING_DIHEDRAL);
    d.bending_warp = 0.02;
    d.bending_weft = 0.005;
    d.grain_angle = grain;
    cr_assert_eq(wr_shell_create(&s, &m, &d, NULL), WR_OK);
    sh_deform(&m, &rng, 0.05, x);
    sh_fd_check(&s, x, "StVK + anisotropic dihedral");
    wr_shell_free(&s);
    sh_desc(&d, WR_MEMBRANE_TFT, WR_BENDING_DIHEDRAL);
    cr_assert_eq(wr_shell_create(&s, &m, &d, NULL), WR_OK);
    sh_fd_check(&s, x, "TFT + dihedral");
    wr_shell_free(&s);
    /* dihedral on a curved 3D rest (rest hinge angles) */
    for (v = 0; v < m.nv; ++v) {
        double u = m.rest[2 * v], w = m.rest[2 * v + 1];
        rest3[3 * v] = u;
        rest3[3 * v + 1] = w;
        rest3[3 * v + 2] = 0.25 * sin(2.0 * u) + 0.1 * w * w;
    }
    sh_desc(&d, WR_MEMBRANE_STVK, WR_BENDING_DIHEDRAL);
    d.rest_pos3 = rest3;
    cr_assert_eq(wr_shell_create(&s, &m, &d, NULL), WR_OK);
    cr_expect(s.bbar != NULL);
    sh_fd_check(&s, x, "dihedral, curved rest");
    /* the curved rest itself has zero energy and zero gradient */
    {
        double E, *g = (double *)malloc(sizeof(double) * 3 * m.nv);
        cr_assert_eq(wr_shell_energy(&s, rest3, &E, g, NULL), WR_OK);
        cr_expect(fabs(E) < 1e-28 && sh_norm(g, 3 * m.nv) < 1e-14, "rest: E %g |g| %g", E, sh_norm(g, 3 * m.nv));
        free(g);
    }
    wr_shell_free(&s);
    free(x);
    free(rest3);
    free(grain);
    wr_mesh_free(&m);
}

/* Element kernel: every mask, random stencils, including hinges folded past ±170°. */
Test(shell, fd_dihedral_element_every_mask) {
    wr_rng rng;
    int32_t mask, trial, i, j;
    wr_rng_seed(&rng, 5);
    for (mask = 1; mask < 8; ++mask)
        for (trial = 0; trial < 4; ++trial) {
            double x[18], thbar[3], g[18], H[324], gp[18], gm[18], E, Ep, Em, th[3], errg = 0, errh = 0, ng = 0, nh = 0;
            static const double base[18] = {0, 0, 0, 1, 0, 0, 0.2, 0.9, 0, 1.0, 1.0, 0, -0.6, 0.6, 0, 0.6, -0.8, 0};
            double M[9] = {2.0, 0.3, 0.1, 0.3, 1.5, -0.2, 0.1, -0.2, 1.0};
            for (i = 0; i < 18; ++i) x[i] = base[i] + 0.15 * (2.0 * wr_rng_uniform(&rng) - 1.0);
            for (i = 0; i < 3; ++i) x[9 + 3 * i + 2] += 0.5 * (2.0 * wr_rng_uniform(&rng) - 1.0);
            if (trial == 3) { /* fold every neighbour back over the face: hinges near ±180° */
                for (i = 0; i < 3; ++i) {
                    double *q = x + 9 + 3 * i, c[3];
                    int a = (i + 1) % 3, b = (i + 2) % 3, k;
                    for (k = 0; k < 3; ++k) c[k] = 0.5 * (x[3 * a + k] + x[3 * b + k]);
                    for (k = 0; k < 2; ++k) q[k] = 2.0 * c[k] - q[k] + 0.7 * (x[3 * i + k] - c[k]) * 1.0;
                    q[2] = 0.05 + 0.02 * i;
                }
            }
            for (i = 0; i < 3; ++i) thbar[i] = 0.3 * (2.0 * wr_rng_uniform(&rng) - 1.0);
            cr_assert_eq(wr_shell_dihedral_element(x, mask, M, thbar, &E, g, H, th), WR_OK);
            for (i = 0; i < 18; ++i) {
                double xi = x[i], gfd;
                x[i] = xi + SH_FD_STEP;
                wr_shell_dihedral_element(x, mask, M, thbar, &Ep, gp, NULL, NULL);
                x[i] = xi - SH_FD_STEP;
                wr_shell_dihedral_element(x, mask, M, thbar, &Em, gm, NULL, NULL);
                x[i] = xi;
                gfd = (Ep - Em) / (2.0 * SH_FD_STEP);
                errg += (gfd - g[i]) * (gfd - g[i]);
                ng += g[i] * g[i];
                for (j = 0; j < 18; ++j) {
                    double h = (gp[j] - gm[j]) / (2.0 * SH_FD_STEP);
                    errh += (h - H[j * 18 + i]) * (h - H[j * 18 + i]);
                    nh += H[j * 18 + i] * H[j * 18 + i];
                }
                if (i >= 9 && !(mask & (1 << ((i - 9) / 3)))) cr_expect_eq(g[i], 0.0);
            }
            if (trial == 3)
                for (i = 0; i < 3; ++i)
                    if (mask & (1 << i)) cr_expect(fabs(th[i]) > 2.6, "folded hinge %d at %g rad", i, th[i]);
            cr_expect(sqrt(errg / ng) < SH_FD_TOL, "mask %d trial %d: gradient rel. error %.3e", mask, trial,
                      sqrt(errg / ng));
            cr_expect(sqrt(errh / nh) < SH_FD_TOL, "mask %d trial %d: Hessian rel. error %.3e", mask, trial,
                      sqrt(errh / nh));
        }
}

/* Two congruent triangles (rhombus) sharing edge x0x1 of length ℓ, altitudes h, folded about the
 * edge to dihedral angle θ (isometric). Per face the hinge gives the curvature θ/h across the edge
 * (b = −θ h̄, ON DIHEDRAL BENDING), so E = 2·(ℓh/2)·(B/2)(θ/h)² = Bℓθ²/(2h) exactly, for any θ in
 * (−π, π]; past 180° the stateless hinge reads θ − 2π (wrapped), so E(180.1°) = E(179.9°). */
static void sh_hinge(double ell, double hh, double theta, double x[12]) {
    memset(x, 0, sizeof(double) * 12);
    x[3] = ell;                    /* x1 */
    x[6] = 0.3 * ell;              /* x2: face A in the plane z = 0, above the edge (+y) */
    x[7] = hh;
    x[9] = 0.7 * ell;              /* x3: face B rotated by θ about the x axis from the −y side */
    x[10] = -hh * cos(theta);
    x[11] = -hh * sin(theta);
}

Test(shell, dihedral_hinge_closed_form_and_folds) {
    double ell = 0.2, hh = 0.1, B = 3e-3, degs[6] = {30.0, 90.0, 150.0, 179.9, 180.1, -120.0};
    int32_t faces[6] = {0, 1, 2, 1, 0, 3}, t, i;
    double rest[8] = {0, 0, 0.2, 0, 0.06, 0.1, 0.14, -0.1};
    wr_mesh m;
    wr_shell s, smid;
    wr_shell_desc d;
    cr_assert_eq(wr_mesh_create(&m, 4, NULL, rest, 2, faces, NULL), WR_OK);
    memset(&d, 0, sizeof d);
    d.young = 1e6;
    d.poisson = 0.3;
    d.thickness = 1e-3;
    d.bending_stiffness = B;
    d.membrane = WR_MEMBRANE_NONE;
    d.bending = WR_BENDING_DIHEDRAL;
    cr_assert_eq(wr_shell_create(&s, &m, &d, NULL), WR_OK);
    d.bending = WR_BENDING_MIDEDGE;
    cr_assert_eq(wr_shell_create(&smid, &m, &d, NULL), WR_OK);
    for (t = 0; t < 6; ++t) {
        double th = degs[t] * SH_PI / 180.0, x[12], E, Em, g[12], ref, thw = th, ang;
        if (thw > SH_PI) thw -= 2.0 * SH_PI;
        sh_hinge(ell, hh, th, x);
        cr_assert_eq(wr_shell_hinge_angle(x, &ang, NULL, NULL), 0);
        /* the sign convention: folding face B up (towards +z, the face normal of A) is θ > 0 */
        cr_expect(fabs(ang - thw) < 1e-14, "%g deg: hinge angle %.17g, expected %.17g", degs[t], ang, thw);
        cr_assert_eq(wr_shell_energy(&s, x, &E, g, NULL), WR_OK);
        ref = B * ell * thw * thw / (2.0 * hh);
        cr_expect(fabs(E - ref) < 1e-13 * ref, "%g deg: E %.15g, closed form %.15g", degs[t], E, ref);
        /* against the mid-edge model on the same isometric fold: b scales by θ / (2 sin(θ/2)) */
        if (fabs(degs[t]) < 179.0) {
            double r = thw / (2.0 * sin(0.5 * thw));
            cr_assert_eq(wr_shell_energy(&smid, x, &Em, NULL, NULL), WR_OK);
            cr_expect(fabs(E - r * r * Em) < 1e-12 * E, "%g deg: dihedral %.15g vs mid-edge x r^2 %.15g", degs[t], E,
                      r * r * Em);
        }
        /* gradient against central differences on the same side of the cut (|θ| <= 179.9°,
         * FD step 1e-7 m moves θ by ~1e-6 rad, far from the ±180° cut 1.7e-3 rad away) */
        for (i = 0; i < 12; ++i) {
            double xp[12], xm[12], Ep, Emm, h = 1e-7;
            memcpy(xp, x, sizeof xp);
            memcpy(xm, x, sizeof xm);
            xp[i] += h;
            xm[i] -= h;
            wr_shell_energy(&s, xp, &Ep, NULL, NULL);
            wr_shell_energy(&s, xm, &Emm, NULL, NULL);
            cr_expect(fabs((Ep - Emm) / (2 * h) - g[i]) <= 1e-6 * sh_norm(g, 12), "%g deg, dof %d: FD %g vs %g",
                      degs[t], i, (Ep - Emm) / (2 * h), g[i]);
        }
        /* finite: |∇E| = B ℓ |θ| / h · |∇θ|, |∇θ| <= √(2·(1/h)² + edge terms) — bounded at 179.9° */
        cr_expect(sh_norm(g, 12) < 10.0 * B * ell * SH_PI / (hh * hh), "%g deg: |g| %g", degs[t], sh_norm(g, 12));
    }
    /* the mid-edge model fails exactly at the fold; the dihedral one does not */
    {
        double x[12], E;
        sh_hinge(ell, hh, SH_PI, x);
        cr_expect_eq(wr_shell_energy(&smid, x, &E, NULL, NULL), WR_ERR_GEOMETRY);
        cr_expect_eq(wr_shell_energy(&s, x, &E, NULL, NULL), WR_OK);
        cr_expect(fabs(E - B * ell * SH_PI * SH_PI / (2 * hh)) < 1e-12 * E);
    }
    wr_shell_free(&s);
    /* rest hinge at 170° (3D rest), folded on to 185° (read as −175° by atan2): δθ wraps to +15°,
     * E = Bℓ(15°)²/(2h); without the wrap it would be (345°)², 529 times more */
    {
        double r3[12], x[12], E, dt = 15.0 * SH_PI / 180.0;
        sh_hinge(ell, hh, 170.0 * SH_PI / 180.0, r3);
        sh_hinge(ell, hh, 185.0 * SH_PI / 180.0, x);
        d.bending = WR_BENDING_DIHEDRAL;
        d.rest_pos3 = r3;
        cr_assert_eq(wr_shell_create(&s, &m, &d, NULL), WR_OK);
        cr_assert_eq(wr_shell_energy(&s, r3, &E, NULL, NULL), WR_OK);
        cr_expect(fabs(E) < 1e-25, "rest energy %g", E);
        cr_assert_eq(wr_shell_energy(&s, x, &E, NULL, NULL), WR_OK);
        cr_expect(fabs(E - B * ell * dt * dt / (2 * hh)) < 1e-12 * E, "E %.15g vs %.15g", E, B * ell * dt * dt / (2 * hh));
        wr_shell_free(&s);
        /* the mirror case: rest −170°, folded to −185° (read +175°): δθ = +345° wraps to −15° */
        sh_hinge(ell, hh, -170.0 * SH_PI / 180.0, r3);
        sh_hinge(ell, hh, 175.0 * SH_PI / 180.0, x);
        cr_assert_eq(wr_shell_create(&s, &m, &d, NULL), WR_OK);
        cr_assert_eq(wr_shell_energy(&s, x, &E, NULL, NULL), WR_OK);
        cr_expect(fabs(E - B * ell * dt * dt / (2 * hh)) < 1e-12 * E, "E %.15g vs %.15g", E, B * ell * dt * dt / (2 * hh));
        wr_shell_free(&s);
    }
    wr_shell_free(&smid);
    wr_mesh_free(&m);
}

/* Cylinder as in cylinder_midedge_matches_plate. Every union-jack triangle has one vertical (crease)
 * edge whose rest altitude is Δu and whose hinge angle is exactly Δu/R (consecutive facets of vertices
 * on the cylinder turn by the arc angle), and its other two edges are flat hinges (the quad strip
 * between two generators is planar). So an interior face carries κ = (Δu/R)/Δu = 1/R exactly: the
 * interior energy equals the plate value B/(2R²) to round-off (bound 1e-12), with no φ² term
 * (the mid-edge model's chord error); the free crease columns carry none, as for mid-edge. */
Test(shell, cylinder_dihedral_matches_plate) {
    double R = 0.5, Wd = 1.0, Hd = 0.4;
    int32_t nxs[2] = {8, 32}, t, grain_pass;
    for (t = 0; t < 2; ++t)
        for (grain_pass = 0; grain_pass < 3; ++grain_pass) {
            wr_mesh m;
            wr_shell s;
            wr_shell_desc d;
            int32_t nx = nxs[t], ny = nxs[t] / 2, v, f;
            double *x, *grain, E, plate, Bc, rel;
            cr_assert_eq(wr_mesh_rectangle(&m, Wd, Hd, nx, ny, NULL), WR_OK);
            x = (double *)malloc(sizeof(double) * 3 * m.nv);
            grain = (double *)malloc(sizeof(double) * m.nf);
            for (f = 0; f < m.nf; ++f) grain[f] = grain_pass == 2 ? 0.5 * SH_PI : 0.0;
            for (v = 0; v < m.nv; ++v) {
                double u = m.rest[2 * v];
                x[3 * v] = R * sin(u / R);
                x[3 * v + 1] = m.rest[2 * v + 1];
                x[3 * v + 2] = R * (1.0 - cos(u / R));
            }
            memset(&d, 0, sizeof d);
            d.young = 1.0e6;
            d.poisson = 0.3;
            d.thickness = 1e-3;
            d.membrane = WR_MEMBRANE_NONE;
            d.bending = WR_BENDING_DIHEDRAL;
            if (grain_pass > 0) { /* warp/weft bending: the cylinder bends along x, the warp at grain 0 */
                d.bending_warp = 4e-5;
                d.bending_weft = 1e-5;
                d.grain_angle = grain;
            }
            cr_assert_eq(wr_shell_create(&s, &m, &d, NULL), WR_OK);
            if (grain_pass > 0) { /* ON ANISOTROPIC BENDING: ν√(B1B2) coupling, (1−ν)/2·√(B1B2) twist */
                cr_expect(fabs(s.C_bend[1] - 0.3 * 2e-5) < 1e-20 && fabs(s.C_bend[8] - 0.35 * 2e-5) < 1e-20,
                          "C_bend %g %g", s.C_bend[1], s.C_bend[8]);
            }
            Bc = grain_pass == 0 ? s.bending_stiffness : (grain_pass == 1 ? 4e-5 : 1e-5);
            cr_assert_eq(wr_shell_energy(&s, x, &E, NULL, NULL), WR_OK);
            plate = Bc / (2 * R * R);
            rel = fabs(E / (plate * Wd * Hd * (1.0 - 1.0 / nx)) - 1.0);
            cr_expect(rel < 1e-12, "nx %d grain pass %d: rel. error %.3e", nx, grain_pass, rel);
            wr_shell_free(&s);
            free(x);
            free(grain);
            wr_mesh_free(&m);
        }
}

/* Baraff–Witkin closed forms on a 4×4 sheet: uniaxial stretch λ along the warp gives
 * E = A·½k_u(λ−1)² (the weft and shear conditions stay 0); along the weft ½k_v(λ−1)²; a simple shear
 * x = u + γ v gives |F2| = √(1+γ²), F1·F2 = γ: E = A[½k_v(√(1+γ²)−1)² + ½k_s γ²]. With the grain
 * turned by θ the same stretch along the grain direction gives the warp value. */
Test(shell, baraff_witkin_closed_forms) {
    wr_mesh m;
    wr_shell s;
    wr_shell_desc d;
    double A = 0.36, ku = 4.0, kv = 1.5, ks = 0.7, lam = 1.07, gam = 0.2, *x, *grain, E, expect, theta = 0.6;
    int32_t v, f, pass;
    cr_assert_eq(wr_mesh_rectangle(&m, 0.6, 0.6, 4, 4, NULL), WR_OK);
    x = (double *)malloc(sizeof(double) * 3 * m.nv);
    grain = (double *)malloc(sizeof(double) * m.nf);
    for (f = 0; f < m.nf; ++f) grain[f] = theta;
    sh_desc_bw(&d, WR_BENDING_NONE);
    cr_assert_eq(wr_shell_create(&s, &m, &d, NULL), WR_OK);
    for (pass = 0; pass < 3; ++pass) {
        for (v = 0; v < m.nv; ++v) {
            double u = m.rest[2 * v], w = m.rest[2 * v + 1];
            x[3 * v] = pass == 0 ? lam * u : (pass == 1 ? u : u + gam * w);
            x[3 * v + 1] = pass == 1 ? lam * w : w;
            x[3 * v + 2] = 0.0;
        }
        cr_assert_eq(wr_shell_energy(&s, x, &E, NULL, NULL), WR_OK);
        expect = pass == 0   ? A * 0.5 * ku * (lam - 1) * (lam - 1)
                 : pass == 1 ? A * 0.5 * kv * (lam - 1) * (lam - 1)
                             : A * (0.5 * kv * (sqrt(1 + gam * gam) - 1) * (sqrt(1 + gam * gam) - 1) + 0.5 * ks * gam * gam);
        cr_expect(fabs(E - expect) < 1e-13 * expect, "pass %d: E %.15g expected %.15g", pass, E, expect);
    }
    wr_shell_free(&s);
    d.grain_angle = grain;
    cr_assert_eq(wr_shell_create(&s, &m, &d, NULL), WR_OK);
    for (v = 0; v < m.nv; ++v) {
        double u = m.rest[2 * v], w = m.rest[2 * v + 1], c = cos(theta), sn = sin(theta), along = c * u + sn * w;
        x[3 * v] = u + (lam - 1) * along * c;
        x[3 * v + 1] = w + (lam - 1) * along * sn;
        x[3 * v + 2] = 0.0;
    }
    cr_assert_eq(wr_shell_energy(&s, x, &E, NULL, NULL), WR_OK);
    expect = A * 0.5 * ku * (lam - 1) * (lam - 1);
    cr_expect(fabs(E - expect) < 1e-12 * expect, "grain %g: E %.15g expected %.15g", theta, E, expect);
    /* small strain: BW equals orthotropic StVK with ν12 = 0, E1 h = k_u, E2 h = k_v, G h = k_s
     * (|F1| − 1 = ε11 + O(ε²), F1·F2 = 2ε12): relative difference O(strain) = O(1e-4) here */
    {
        wr_shell so;
        wr_shell_desc od;
        double Eo, e = 1e-4;
        memset(&od, 0, sizeof od);
        od.orthotropic = 1;
        od.thickness = 1e-3;
        od.young_warp = ku / od.thickness;
        od.young_weft = kv / od.thickness;
        od.shear_modulus = ks / od.thickness;
        od.grain_angle = grain;
        od.bending = WR_BENDING_NONE;
        cr_assert_eq(wr_shell_create(&so, &m, &od, NULL), WR_OK);
        for (v = 0; v < m.nv; ++v) {
            double u = m.rest[2 * v], w = m.rest[2 * v + 1];
            x[3 * v] = u * (1 + e) + 0.7 * e * w;
            x[3 * v + 1] = w * (1 - 0.5 * e) + 0.2 * e * u;
            x[3 * v + 2] = 0.0;
        }
        cr_assert_eq(wr_shell_energy(&s, x, &E, NULL, NULL), WR_OK);
        cr_assert_eq(wr_shell_energy(&so, x, &Eo, NULL, NULL), WR_OK);
        cr_expect(fabs(E / Eo - 1.0) < 10.0 * e, "small strain: BW %.10g vs orthotropic StVK %.10g", E, Eo);
        cr_expect(fabs(E / Eo - 1.0) > 1e-9, "the two models differ at O(strain): the test sees both");
        wr_shell_free(&so);
    }
    wr_shell_free(&s);
    free(x);
    free(grain);
    wr_mesh_free(&m);
}

Test(shell, baraff_witkin_and_dihedral_errors) {
    wr_mesh m, m3;
    wr_shell s;
    wr_shell_desc d;
    wr_diag dg;
    static const double pos[12] = {0, 0, 0, 1, 0, 0.3, 0, 1, 0, 1, 1, 0.2};
    static const int32_t faces[6] = {0, 1, 2, 1, 3, 2};
    cr_assert_eq(wr_mesh_rectangle(&m, 1.0, 1.0, 2, 2, NULL), WR_OK);
    cr_assert_eq(wr_mesh_create(&m3, 4, pos, NULL, 2, faces, NULL), WR_OK);
    sh_desc_bw(&d, WR_BENDING_DIHEDRAL);
    d.stretch_shear = 0.0;
    cr_expect_eq(wr_shell_create(&s, &m, &d, &dg), WR_ERR_DOMAIN);
    sh_desc_bw(&d, WR_BENDING_DIHEDRAL);
    cr_expect_eq(wr_shell_create(&s, &m3, &d, &dg), WR_ERR_UNSUPPORTED); /* 3D rest: no warp/weft */
    sh_desc_bw(&d, WR_BENDING_NONE);
    d.young = 0.0; /* allowed: BW needs no Young's modulus without bending */
    cr_expect_eq(wr_shell_create(&s, &m, &d, &dg), WR_OK);
    wr_shell_free(&s);
    sh_desc_bw(&d, WR_BENDING_DIHEDRAL);
    d.young = 0.0; /* ... but the default B does */
    cr_expect_eq(wr_shell_create(&s, &m, &d, &dg), WR_ERR_DOMAIN);
    sh_desc(&d, WR_MEMBRANE_STVK, WR_BENDING_DIHEDRAL);
    d.bending_warp = 1e-3; /* weft missing */
    cr_expect_eq(wr_shell_create(&s, &m, &d, &dg), WR_ERR_DOMAIN);
    sh_desc(&d, WR_MEMBRANE_STVK, WR_BENDING_QUADRATIC);
    d.bending_warp = d.bending_weft = 1e-3;
    cr_expect_eq(wr_shell_create(&s, &m, &d, &dg), WR_ERR_UNSUPPORTED);
    sh_desc(&d, WR_MEMBRANE_STVK, (wr_bending_model)4);
    cr_expect_eq(wr_shell_create(&s, &m, &d, &dg), WR_ERR_INVALID_ARG);
    {   /* a zero-area deformed face is a geometry error, not a NaN */
        double x[27];
        int32_t v;
        sh_desc(&d, WR_MEMBRANE_NONE, WR_BENDING_DIHEDRAL);
        cr_assert_eq(wr_shell_create(&s, &m, &d, NULL), WR_OK);
        for (v = 0; v < 9; ++v) {
            x[3 * v] = m.rest[2 * v];
            x[3 * v + 1] = 0.0;
            x[3 * v + 2] = 0.0;
        }
        cr_expect_eq(wr_shell_energy(&s, x, NULL, NULL, &dg), WR_ERR_GEOMETRY);
        wr_shell_free(&s);
    }
    wr_mesh_free(&m);
    wr_mesh_free(&m3);
}

/* Equilateral lattice (edge a) wrapped on a cylinder of radius R, axis along the rows and across
 * them: interior faces against B/(2R²). Measured (n = 10, 20, 40, 80 rows): dihedral 7.6e-4,
 * 1.9e-4, 4.8e-5, 1.2e-5 along the rows (second order in a/R) and 0 to round-off across them;
 * mid-edge 4.2e-3 … 6.5e-5. Bound: (a/R)²/24 (twice the measured constant of the along-rows case,
 * from the O(a²/R²) facet/arc difference), and the dihedral error must not exceed the mid-edge one. */
Test(shell, cylinder_dihedral_equilateral_mesh) {
    int32_t ns[2] = {10, 20}, t, rot;
    double R = 0.5;
    for (t = 0; t < 2; ++t)
        for (rot = 0; rot < 2; ++rot) {
            int32_t n = ns[t], nv = (n + 1) * (n + 1), nf = 2 * n * n, i, j, f = 0, bm;
            double a = 1.0 / n, *rest = (double *)malloc(sizeof(double) * 2 * nv), *x = (double *)malloc(sizeof(double) * 3 * nv);
            double err[2];
            int32_t *F = (int32_t *)malloc(sizeof(int32_t) * 3 * nf);
            for (j = 0; j <= n; ++j)
                for (i = 0; i <= n; ++i) {
                    rest[2 * (j * (n + 1) + i)] = a * (i + 0.5 * j);
                    rest[2 * (j * (n + 1) + i) + 1] = a * j * sqrt(3.0) / 2.0;
                }
            for (j = 0; j < n; ++j)
                for (i = 0; i < n; ++i) {
                    int32_t v = j * (n + 1) + i, t6[6] = {v, v + 1, v + n + 1, v + 1, v + n + 2, v + n + 1};
                    memcpy(F + 3 * f, t6, sizeof t6);
                    f += 2;
                }
            for (i = 0; i < nv; ++i) {
                double u = rest[2 * i], w = rest[2 * i + 1], tt;
                if (rot) tt = u, u = w, w = tt;
                x[3 * i] = R * sin(u / R);
                x[3 * i + 1] = w;
                x[3 * i + 2] = R * (1.0 - cos(u / R));
            }
            for (bm = 0; bm < 2; ++bm) {
                wr_mesh m;
                wr_shell s;
                wr_shell_desc d;
                double Ei = 0.0, Ai = 0.0;
                cr_assert_eq(wr_mesh_create(&m, nv, NULL, rest, nf, F, NULL), WR_OK);
                memset(&d, 0, sizeof d);
                d.young = 1e6;
                d.poisson = 0.3;
                d.thickness = 1e-3;
                d.membrane = WR_MEMBRANE_NONE;
                d.bending = bm ? WR_BENDING_DIHEDRAL : WR_BENDING_MIDEDGE;
                cr_assert_eq(wr_shell_create(&s, &m, &d, NULL), WR_OK);
                for (f = 0; f < nf; ++f) {
                    int32_t vv[6], mask = wr_shell_face_stencil(&s, f, vv), k;
                    double x18[18], e;
                    if (mask != 7) continue;
                    for (k = 0; k < 18; ++k) x18[k] = x[3 * vv[k / 3] + k % 3];
                    if (bm)
                        cr_assert_eq(wr_shell_dihedral_element(x18, mask, s.qbend + 9 * f, NULL, &e, NULL, NULL, NULL), WR_OK);
                    else
                        cr_assert_eq(wr_shell_midedge_element(x18, mask, s.qbend + 9 * f, NULL, &e, NULL, NULL, NULL), WR_OK);
                    Ei += e;
                    Ai += s.area[f];
                }
                err[bm] = fabs(Ei / (s.bending_stiffness / (2 * R * R) * Ai) - 1.0);
                wr_shell_free(&s);
                wr_mesh_free(&m);
            }
            cr_expect(err[1] <= (a / R) * (a / R) / 24.0, "n %d rot %d: dihedral rel. error %.3e > %.3e", n, rot, err[1],
                      (a / R) * (a / R) / 24.0);
            cr_expect(err[1] <= err[0], "n %d rot %d: dihedral %.3e worse than mid-edge %.3e", n, rot, err[1], err[0]);
            free(rest);
            free(x);
            free(F);
        }
}

/* Mixed Voronoi areas (Meyer et al. 2003) partition the surface: on a closed mesh every vertex has a
 * quadratic-bending stencil and Σ_v A_v = Σ_f A_f exactly — circumcentric thirds on non-obtuse
 * faces, A/2 to the obtuse corner and A/4 to the others on obtuse ones. The panel (a hexagon with its
 * centre pushed towards one side) has obtuse faces, doubled into a closed pillow (mesh.h). Swapping
 * the obtuse weights (A/4 obtuse, A/2 others) gives 1.25 A per obtuse face and fails. */
Test(shell, mixed_voronoi_areas_partition_a_closed_surface) {
    double pos[7 * 3] = {0}, asum = 0.0, vsum = 0.0;
    int32_t faces[6 * 3], i, n_obtuse = 0;
    wr_mesh panel, pil;
    wr_shell sh;
    wr_shell_desc sd;
    wr_diag d;
    for (i = 0; i < 6; ++i) {
        pos[3 * i] = cos(i * 3.14159265358979323846 / 3.0);
        pos[3 * i + 1] = sin(i * 3.14159265358979323846 / 3.0);
        faces[3 * i] = 6, faces[3 * i + 1] = i, faces[3 * i + 2] = (i + 1) % 6;
    }
    pos[18] = 0.55; /* the centre, close to the edge between vertices 0 and 1 */
    pos[19] = 0.3;
    cr_assert_eq(wr_mesh_create(&panel, 7, pos, NULL, 6, faces, &d), WR_OK, "%s", d.message);
    cr_assert_eq(wr_mesh_pillow(&pil, &panel, 0.1, &d), WR_OK, "%s", d.message);
    memset(&sd, 0, sizeof sd);
    sd.membrane = WR_MEMBRANE_TFT;
    sd.bending = WR_BENDING_QUADRATIC;
    sd.young = 1e6;
    sd.poisson = 0.3;
    sd.thickness = 1e-3;
    cr_assert_eq(wr_shell_create(&sh, &pil, &sd, &d), WR_OK, "%s", d.message);
    for (i = 0; i < 6; ++i) { /* the panel really has obtuse faces (angle at the centre > 90°) */
        const double *c = pos + 18, *a = pos + 3 * i, *b = pos + 3 * ((i + 1) % 6);
        if ((a[0] - c[0]) * (b[0] - c[0]) + (a[1] - c[1]) * (b[1] - c[1]) < 0.0) ++n_obtuse;
    }
    cr_assert(n_obtuse >= 1, "test panel has no obtuse face");
    cr_assert_eq(sh.n_qb, pil.nv, "a closed surface: every vertex is interior (%d of %d)", (int)sh.n_qb, (int)pil.nv);
    for (i = 0; i < pil.nf; ++i) asum += sh.area[i];
    for (i = 0; i < sh.n_qb; ++i) vsum += sh.bending_stiffness / sh.qb_coef[i];
    cr_assert(fabs(vsum / asum - 1.0) < 1e-12, "sum of vertex areas %.15g vs surface %.15g", vsum, asum);
    wr_shell_free(&sh);
    wr_mesh_free(&pil);
    wr_mesh_free(&panel);
}
