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
