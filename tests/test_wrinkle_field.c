/* Tests for wrinkle/wrinkle_field.h (TFW wrinkle-field energy, W set, init, SQP, phase, upsampling). */
#include <criterion/criterion.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "wrinkle/spectrum.h"
#include "wrinkle/wrinkle_field.h"

#define PI 3.14159265358979323846

/* A rectangle whose base surface is compressed along x by `cx`, stretched along y by `sy` and lifted
 * by a bump of height `bump` (so II_b and κ⊥ are nonzero). */
static void make_base(const wr_mesh *m, double w, double h, double cx, double sy, double bump, double *base) {
    int32_t v;
    for (v = 0; v < m->nv; ++v) {
        double x = m->pos[3 * v], y = m->pos[3 * v + 1];
        base[3 * v] = (1.0 - cx) * x;
        base[3 * v + 1] = (1.0 + sy) * y;
        base[3 * v + 2] = bump * sin(PI * x / w) * sin(PI * y / h) + 0.3 * bump * x * y / (w * h);
    }
}

static wr_wf_material material(void) {
    wr_wf_material mat;
    mat.young = 1e6;
    mat.poisson = 0.3;
    mat.thickness = 1e-3;
    return mat;
}

static double total_energy(const wr_wf *wf, const double *x) {
    double E = 0.0;
    cr_assert_eq(wr_wf_energy(wf, x, x + wf->nv, &E, NULL, NULL, NULL, NULL), WR_OK);
    return E;
}

Test(wrinkle_field, energy_gradient_and_hessian_match_finite_differences) {
    wr_mesh m;
    wr_wf wf;
    wr_rng rng;
    wr_wf_material mat = material();
    double *base, *x, *g, *gp, *gm, *H, *Hd, E;
    int32_t n, i, j, f;
    double gmax = 0.0, gerr = 0.0, hmax = 0.0, herr = 0.0;
    cr_assert_eq(wr_mesh_rectangle(&m, 0.1, 0.05, 4, 3, NULL), WR_OK);
    base = (double *)malloc(sizeof(double) * 3 * m.nv);
    make_base(&m, 0.1, 0.05, 0.1, 0.02, 0.01, base);
    cr_assert_eq(wr_wf_create(&wf, &m, base, &mat, NULL), WR_OK);
    n = m.nv + m.ne;
    x = (double *)malloc(sizeof(double) * n);
    g = (double *)malloc(sizeof(double) * n);
    gp = (double *)malloc(sizeof(double) * n);
    gm = (double *)malloc(sizeof(double) * n);
    H = (double *)malloc(sizeof(double) * 36 * m.nf);
    Hd = (double *)calloc((size_t)n * n, sizeof(double));
    wr_rng_seed(&rng, 7);
    for (i = 0; i < m.nv; ++i) x[i] = 1e-3 * (0.5 + wr_rng_uniform(&rng));
    for (i = 0; i < m.ne; ++i) x[m.nv + i] = 2.0 * wr_rng_uniform(&rng) - 1.0;
    /* W_s^2 must be active somewhere for the test to cover it. */
    {
        int any = 0;
        for (f = 0; f < m.nf; ++f) any |= wf.c2[f] > 0.0;
        cr_assert(any, "no face with a nonzero crest-curvature term");
    }
    cr_assert_eq(wr_wf_energy(&wf, x, x + m.nv, &E, g, H, NULL, NULL), WR_OK);
    for (f = 0; f < m.nf; ++f) {
        int32_t idx[6];
        double sg[6];
        int r, c;
        wr_wf_face_dofs(&wf, f, idx, sg);
        for (r = 0; r < 6; ++r)
            for (c = 0; c < 6; ++c) Hd[(size_t)idx[r] * n + idx[c]] += H[36 * f + 6 * r + c];
    }
    for (i = 0; i < n; ++i) {
        double hstep = i < m.nv ? 1e-7 : 1e-5, xi = x[i], Ep, Em;
        x[i] = xi + hstep;
        Ep = total_energy(&wf, x);
        cr_assert_eq(wr_wf_energy(&wf, x, x + m.nv, &Ep, gp, NULL, NULL, NULL), WR_OK);
        x[i] = xi - hstep;
        cr_assert_eq(wr_wf_energy(&wf, x, x + m.nv, &Em, gm, NULL, NULL, NULL), WR_OK);
        x[i] = xi;
        gmax = fmax(gmax, fabs(g[i]) * (i < m.nv ? 1e-3 : 1.0));
        gerr = fmax(gerr, fabs((Ep - Em) / (2 * hstep) - g[i]) * (i < m.nv ? 1e-3 : 1.0));
        for (j = 0; j < n; ++j) {
            double sj = j < m.nv ? 1e-3 : 1.0, si = i < m.nv ? 1e-3 : 1.0;
            double fd = (gp[j] - gm[j]) / (2 * hstep);
            hmax = fmax(hmax, fabs(Hd[(size_t)j * n + i]) * si * sj);
            herr = fmax(herr, fabs(fd - Hd[(size_t)j * n + i]) * si * sj);
        }
    }
    cr_assert(gmax > 0.0 && hmax > 0.0);
    cr_log_info("FD: grad err %g / %g, Hessian err %g / %g", gerr, gmax, herr, hmax);
    cr_expect(gerr <= 1e-6 * gmax, "gradient FD error %g vs scale %g", gerr, gmax);
    cr_expect(herr <= 1e-5 * hmax, "Hessian FD error %g vs scale %g", herr, hmax);
    free(base); free(x); free(g); free(gp); free(gm); free(H); free(Hd);
    wr_wf_free(&wf);
    wr_mesh_free(&m);
}

/* The hand-expanded face evaluation (default) against the literal monomial transcription of
 * Eq. 20–27 (wf.reference_eval): energy, terms, gradient and per-face Hessians agree to round-off, at
 * a generic point with every term active (W_s^2 included) and with a = 0 on every other vertex (the
 * bound the SQP holds amplitudes at). */
Test(wrinkle_field, fast_evaluation_matches_reference_transcription) {
    wr_mesh m;
    wr_wf wf;
    wr_rng rng;
    wr_wf_material mat = material();
    double *base, *x, *g[2], *H[2], E[2], T[2][WR_WF_NTERMS];
    int32_t n, i, pass;
    cr_assert_eq(wr_mesh_rectangle(&m, 0.1, 0.05, 5, 3, NULL), WR_OK);
    base = (double *)malloc(sizeof(double) * 3 * m.nv);
    make_base(&m, 0.1, 0.05, 0.1, 0.02, 0.01, base);
    cr_assert_eq(wr_wf_create(&wf, &m, base, &mat, NULL), WR_OK);
    n = m.nv + m.ne;
    x = (double *)malloc(sizeof(double) * n);
    for (i = 0; i < 2; ++i) {
        g[i] = (double *)malloc(sizeof(double) * n);
        H[i] = (double *)malloc(sizeof(double) * 36 * m.nf);
    }
    wr_rng_seed(&rng, 11);
    for (pass = 0; pass < 2; ++pass) {
        double gs = 0.0, ge = 0.0, hs = 0.0, he = 0.0, ts = 0.0, te = 0.0;
        int r;
        for (i = 0; i < m.nv; ++i) x[i] = pass && i % 2 == 0 ? 0.0 : 1e-3 * (0.2 + wr_rng_uniform(&rng));
        for (i = 0; i < m.ne; ++i) x[m.nv + i] = 3.0 * wr_rng_uniform(&rng) - 1.5;
        for (r = 0; r < 2; ++r) {
            wf.reference_eval = r;
            cr_assert_eq(wr_wf_energy(&wf, x, x + m.nv, &E[r], g[r], H[r], T[r], NULL), WR_OK);
        }
        for (i = 0; i < n; ++i) {
            double sc = i < m.nv ? 1e-3 : 1.0; /* gradient in J per (1 mm of a) and per rad */
            gs = fmax(gs, fabs(g[1][i]) * sc);
            ge = fmax(ge, fabs(g[1][i] - g[0][i]) * sc);
        }
        for (i = 0; i < 36 * m.nf; ++i) {
            int32_t f = i / 36, rr = (i % 36) / 6, cc = i % 6;
            double sc = (rr < 3 ? 1e-3 : 1.0) * (cc < 3 ? 1e-3 : 1.0);
            (void)f;
            hs = fmax(hs, fabs(H[1][i]) * sc);
            he = fmax(he, fabs(H[1][i] - H[0][i]) * sc);
        }
        for (i = 0; i < WR_WF_NTERMS; ++i) {
            ts = fmax(ts, fabs(T[1][i]));
            te = fmax(te, fabs(T[1][i] - T[0][i]));
        }
        cr_log_info("pass %d: E %.17g vs %.17g, grad %g / %g, Hessian %g / %g", pass, E[0], E[1], ge, gs, he, hs);
        cr_assert(gs > 0.0 && hs > 0.0 && ts > 0.0);
        cr_expect(fabs(E[0] - E[1]) <= 1e-13 * fabs(E[1]), "energy %.17g vs reference %.17g", E[0], E[1]);
        cr_expect(te <= 1e-13 * ts, "terms differ by %g (scale %g)", te, ts);
        cr_expect(ge <= 1e-13 * gs, "gradient differs by %g (scale %g)", ge, gs);
        cr_expect(he <= 1e-13 * hs, "Hessian differs by %g (scale %g)", he, hs);
        if (pass == 0) cr_expect(T[1][WR_WF_TERM_S2] > 0.0 && T[1][WR_WF_TERM_S3] > 0.0, "every term must be active");
    }
    for (i = 0; i < 2; ++i) {
        free(g[i]);
        free(H[i]);
    }
    free(base);
    free(x);
    wr_wf_free(&wf);
    wr_mesh_free(&m);
}

static void fill_scaled(const wr_mesh *m, double sx, double sy, double *base) {
    int32_t v;
    for (v = 0; v < m->nv; ++v) {
        base[3 * v] = sx * m->pos[3 * v];
        base[3 * v + 1] = sy * m->pos[3 * v + 1];
        base[3 * v + 2] = 0.0;
    }
}

Test(wrinkle_field, eq29_eigenvalues_and_wrinkle_free_set) {
    wr_mesh m;
    wr_wf wf;
    wr_wf_material mat = material();
    double *base;
    int32_t f;
    cr_assert_eq(wr_mesh_rectangle(&m, 0.2, 0.1, 8, 4, NULL), WR_OK);
    base = (double *)malloc(sizeof(double) * 3 * m.nv);
    /* pure tension: both eigenvalues of I_u⁻¹(I_b - I_u) are 1.1² - 1 and 1.05² - 1 */
    fill_scaled(&m, 1.1, 1.05, base);
    cr_assert_eq(wr_wf_create(&wf, &m, base, &mat, NULL), WR_OK);
    for (f = 0; f < m.nf; ++f) {
        cr_assert_float_eq(wf.lambda[2 * f], 1.05 * 1.05 - 1.0, 1e-12);
        cr_assert_float_eq(wf.lambda[2 * f + 1], 1.1 * 1.1 - 1.0, 1e-12);
    }
    cr_assert_eq(wr_wf_classify(&wf, NULL), m.nf, "tension everywhere -> W is every face");
    {
        double *a = (double *)calloc(m.nv, sizeof(double)), *om = (double *)calloc(m.ne, sizeof(double)), E = 1.0;
        cr_assert_eq(wr_wf_init(&wf, NULL, a, om, NULL), WR_OK);
        for (f = 0; f < m.nv; ++f) cr_assert_eq(a[f], 0.0);
        for (f = 0; f < m.ne; ++f) cr_assert_eq(om[f], 0.0);
        cr_assert_eq(wr_wf_energy(&wf, a, om, &E, NULL, NULL, NULL, NULL), WR_OK);
        cr_assert_eq(E, 0.0, "all faces in W contribute nothing (Eq. 37)");
        free(a);
        free(om);
    }
    wr_wf_free(&wf);
    /* compression along x: λ0 = 0.9² - 1 with w along x */
    fill_scaled(&m, 0.9, 1.0, base);
    cr_assert_eq(wr_wf_create(&wf, &m, base, &mat, NULL), WR_OK);
    for (f = 0; f < m.nf; ++f) {
        const double *iu = wf.iu + 3 * f, *w = wf.wdir + 2 * f;
        /* chart vector w pushed to the rest plane must be ±x̂ */
        double uv[6], X, Y;
        wr_mesh_face_rest(&m, f, uv);
        X = (uv[2] - uv[0]) * w[0] + (uv[4] - uv[0]) * w[1];
        Y = (uv[3] - uv[1]) * w[0] + (uv[5] - uv[1]) * w[1];
        cr_assert_float_eq(wf.lambda[2 * f], 0.81 - 1.0, 1e-12);
        cr_assert_float_eq(fabs(X), 1.0, 1e-12);
        cr_assert_float_eq(Y, 0.0, 1e-12);
        cr_assert_float_eq(iu[0] * w[0] * w[0] + 2 * iu[1] * w[0] * w[1] + iu[2] * w[1] * w[1], 1.0, 1e-12);
        cr_assert_eq(wf.c2[f], 0.0, "flat base: κ⊥ = 0");
    }
    cr_assert_eq(wr_wf_classify(&wf, NULL), 0);
    wr_wf_free(&wf);
    /* the Sec. 5.1 rule: a single compressed face among tension faces averages to tension, and an
     * isolated tension face inside compression is filtered out of W */
    fill_scaled(&m, 1.0, 1.0, base);
    {
        wr_wf_classify_desc cd;
        int32_t mid = 2 * (2 * 8 + 4);
        memset(&cd, 0, sizeof cd);
        cr_assert_eq(wr_wf_create(&wf, &m, base, &mat, NULL), WR_OK);
        for (f = 0; f < m.nf; ++f) wf.lambda[2 * f] = f == mid ? -0.2 : 0.1;
        cr_assert_eq(wr_wf_classify(&wf, &cd), m.nf);
        for (f = 0; f < m.nf; ++f) wf.lambda[2 * f] = f == mid ? 0.9 : -0.5;
        for (f = 0; f < 3; ++f) {
            int32_t e = m.face_edges[3 * mid + f], g = m.edge_faces[2 * e] == mid ? m.edge_faces[2 * e + 1] : m.edge_faces[2 * e];
            wf.lambda[2 * g] = -0.1;
        }
        cd.no_outlier_filter = 1;
        cr_assert_eq(wr_wf_classify(&wf, &cd), 1, "unfiltered: the isolated face averages to tension");
        cd.no_outlier_filter = 0;
        cr_assert_eq(wr_wf_classify(&wf, &cd), 0, "filter removes the isolated W face");
        wr_wf_free(&wf);
    }
    free(base);
    wr_mesh_free(&m);
}

Test(wrinkle_field, zero_energy_at_rest_and_error_paths) {
    wr_mesh m;
    wr_wf wf;
    wr_wf_material mat = material();
    double *a, *om, *g, E = 1.0, terms[WR_WF_NTERMS];
    int32_t i;
    wr_diag d;
    cr_assert_eq(wr_mesh_rectangle(&m, 0.1, 0.1, 3, 3, NULL), WR_OK);
    cr_assert_eq(wr_wf_create(&wf, &m, NULL, &mat, NULL), WR_OK); /* base = rest */
    a = (double *)calloc(m.nv, sizeof(double));
    om = (double *)calloc(m.ne, sizeof(double));
    g = (double *)malloc(sizeof(double) * (m.nv + m.ne));
    cr_assert_eq(wr_wf_energy(&wf, a, om, &E, g, NULL, terms, NULL), WR_OK);
    cr_assert_eq(E, 0.0);
    for (i = 0; i < m.nv + m.ne; ++i) cr_assert_eq(g[i], 0.0);
    /* tension base with W forced empty: a = 0 is stationary and E = the base stretching term only */
    wr_wf_free(&wf);
    {
        double *base = (double *)malloc(sizeof(double) * 3 * m.nv);
        fill_scaled(&m, 1.1, 1.0, base);
        cr_assert_eq(wr_wf_create(&wf, &m, base, &mat, NULL), WR_OK);
        free(base);
    }
    cr_assert_eq(wr_wf_energy(&wf, a, om, &E, g, NULL, terms, NULL), WR_OK);
    for (i = 0; i < m.nv + m.ne; ++i) cr_assert_eq(g[i], 0.0);
    /* uniaxial 2ε = 0.21 along x: h/4 (α/2 + β) 0.21² per unit area, area 0.01 m² */
    {
        double nu = 0.3, al = 1e6 * nu / (1 - nu * nu), be = 1e6 / (2 * (1 + nu));
        cr_assert_float_eq(terms[WR_WF_TERM_S1], 1e-3 / 4 * (al / 2 + be) * 0.21 * 0.21 * 0.01, 1e-12);
        cr_assert_float_eq(E, terms[WR_WF_TERM_S1], 1e-15);
    }
    a[0] = NAN;
    cr_assert_eq(wr_wf_energy(&wf, a, om, &E, NULL, NULL, NULL, &d), WR_ERR_DOMAIN);
    cr_assert_eq(d.item, 0);
    cr_assert_eq(wr_wf_energy(&wf, NULL, om, &E, NULL, NULL, NULL, NULL), WR_ERR_INVALID_ARG);
    wr_wf_free(&wf);
    mat.young = -1.0;
    cr_assert_eq(wr_wf_create(&wf, &m, NULL, &mat, &d), WR_ERR_DOMAIN);
    mat = material();
    mat.poisson = 1.0;
    cr_assert_eq(wr_wf_create(&wf, &m, NULL, &mat, NULL), WR_ERR_DOMAIN);
    mat = material();
    mat.thickness = 0.0;
    cr_assert_eq(wr_wf_create(&wf, &m, NULL, &mat, NULL), WR_ERR_DOMAIN);
    mat = material();
    cr_assert_eq(wr_wf_create(&wf, NULL, NULL, &mat, NULL), WR_ERR_INVALID_ARG);
    {
        double *base = (double *)calloc(3 * m.nv, sizeof(double)); /* collapsed base */
        cr_assert_eq(wr_wf_create(&wf, &m, base, &mat, &d), WR_ERR_GEOMETRY);
        base[0] = INFINITY;
        cr_assert_eq(wr_wf_create(&wf, &m, base, &mat, &d), WR_ERR_DOMAIN);
        free(base);
    }
    free(a);
    free(om);
    free(g);
    wr_mesh_free(&m);
}

Test(wrinkle_field, curl_free_projection) {
    wr_mesh m;
    wr_wf wf;
    wr_rng rng;
    wr_wf_material mat = material();
    double *om, *om0, *curl;
    uint8_t *wfl;
    int32_t f, e, hole = 0;
    cr_assert_eq(wr_mesh_rectangle(&m, 0.2, 0.1, 10, 5, NULL), WR_OK);
    cr_assert_eq(wr_wf_create(&wf, &m, NULL, &mat, NULL), WR_OK);
    /* W = a block of faces in the middle: a hole, so ω may circulate around it */
    wfl = (uint8_t *)calloc(m.nf, 1);
    for (f = 0; f < m.nf; ++f) {
        int32_t cell = f / 2, i = cell % 10, j = cell / 10;
        if (i >= 4 && i <= 5 && j >= 2 && j <= 2) {
            wfl[f] = 1;
            ++hole;
        }
    }
    wr_wf_set_wrinkle_free(&wf, wfl);
    om = (double *)malloc(sizeof(double) * m.ne);
    om0 = (double *)malloc(sizeof(double) * m.ne);
    curl = (double *)malloc(sizeof(double) * m.nf);
    wr_rng_seed(&rng, 3);
    for (e = 0; e < m.ne; ++e) om0[e] = om[e] = wr_rng_normal(&rng);
    cr_assert_eq(wr_wf_project_closed(&wf, om, NULL), WR_OK);
    wr_wf_curl(&m, om, curl);
    for (f = 0; f < m.nf; ++f)
        if (!wfl[f]) cr_assert(fabs(curl[f]) < 1e-10, "face %d curl %g", f, curl[f]);
    /* least squares: the residual is orthogonal to closed forms, e.g. to d0 of a hat function */
    {
        int32_t v;
        for (v = 0; v < m.nv; ++v) {
            double s = 0.0;
            for (e = 0; e < m.ne; ++e) {
                if (m.edges[2 * e] == v) s -= (om[e] - om0[e]);
                if (m.edges[2 * e + 1] == v) s += (om[e] - om0[e]);
            }
            cr_assert(fabs(s) < 1e-9, "residual not orthogonal to d0 at vertex %d: %g", v, s);
        }
    }
    /* a closed form is left unchanged, including its circulation around the hole */
    {
        double circ0 = 0.0;
        for (e = 0; e < m.ne; ++e) {
            int32_t i = m.edges[2 * e], j = m.edges[2 * e + 1];
            double xi = m.pos[3 * i] - 0.1, yi = m.pos[3 * i + 1] - 0.05, xj = m.pos[3 * j] - 0.1, yj = m.pos[3 * j + 1] - 0.05;
            double dth = atan2(yj, xj) - atan2(yi, xi);
            if (dth > PI) dth -= 2 * PI;
            if (dth < -PI) dth += 2 * PI;
            om0[e] = om[e] = 2.5 * dth + 3.0 * (m.pos[3 * j] - m.pos[3 * i]);
        }
        (void)circ0;
        cr_assert_eq(wr_wf_project_closed(&wf, om, NULL), WR_OK);
        for (e = 0; e < m.ne; ++e) cr_assert(fabs(om[e] - om0[e]) < 1e-9);
    }
    cr_assert(hole > 0);
    free(om);
    free(om0);
    free(curl);
    free(wfl);
    wr_wf_free(&wf);
    wr_mesh_free(&m);
}

/* ω = dφ for φ = k x on a rectangle (W empty). */
static void omega_linear(const wr_mesh *m, double k, double *om) {
    int32_t e;
    for (e = 0; e < m->ne; ++e) om[e] = k * (m->pos[3 * m->edges[2 * e + 1]] - m->pos[3 * m->edges[2 * e]]);
}

Test(wrinkle_field, phase_recovers_period_count_on_rectangle) {
    wr_mesh m;
    wr_wf wf;
    wr_wf_material mat = material();
    wr_wf_phase_stats ps;
    double L = 0.25, *om, *phi, k = 2 * PI * 5 / L;
    int32_t f, c;
    cr_assert_eq(wr_mesh_rectangle(&m, L, 0.1, 12, 5, NULL), WR_OK);
    cr_assert_eq(wr_wf_create(&wf, &m, NULL, &mat, NULL), WR_OK);
    om = (double *)malloc(sizeof(double) * m.ne);
    phi = (double *)malloc(sizeof(double) * 3 * m.nf);
    omega_linear(&m, k, om);
    cr_assert_eq(wr_wf_phase(&wf, om, phi, &ps, NULL), WR_OK);
    cr_assert(ps.max_residual < 1e-9, "residual %g", ps.max_residual);
    cr_assert_eq(ps.n_conflicts, 0);
    /* φ - k x is one constant over every corner: 5 whole periods across the 0.25 m sheet */
    {
        double c0 = phi[0] - k * m.pos[3 * m.faces[0]];
        for (f = 0; f < m.nf; ++f)
            for (c = 0; c < 3; ++c) cr_assert(fabs(phi[3 * f + c] - k * m.pos[3 * m.faces[3 * f + c]] - c0) < 1e-9);
    }
    free(om);
    free(phi);
    wr_wf_free(&wf);
    wr_mesh_free(&m);
}

Test(wrinkle_field, phase_rounds_fractional_circulation_on_cylinder) {
    wr_mesh m;
    wr_wf wf;
    wr_wf_material mat = material();
    wr_wf_phase_stats ps;
    double *om, *phi, N = 5.3, total = 0.0;
    int32_t nu = 24, e, i;
    cr_assert_eq(wr_mesh_cylinder_flat(&m, 0.1, 0.1, nu, 3, NULL), WR_OK);
    cr_assert_eq(wr_wf_create(&wf, &m, NULL, &mat, NULL), WR_OK);
    om = (double *)malloc(sizeof(double) * m.ne);
    phi = (double *)malloc(sizeof(double) * 3 * m.nf);
    for (e = 0; e < m.ne; ++e) {
        int32_t a = m.edges[2 * e], b = m.edges[2 * e + 1];
        double dth = atan2(m.pos[3 * b + 1], m.pos[3 * b]) - atan2(m.pos[3 * a + 1], m.pos[3 * a]);
        if (dth > PI) dth -= 2 * PI;
        if (dth < -PI) dth += 2 * PI;
        om[e] = N * dth; /* closed, but 5.3 periods around the tube */
    }
    cr_assert_eq(wr_wf_phase(&wf, om, phi, &ps, NULL), WR_OK);
    cr_assert_eq(ps.n_conflicts, 0);
    cr_assert(ps.n_nonzero_jumps > 0);
    /* walk the bottom ring, differences taken inside faces: the winding must be exactly 5 periods */
    for (i = 0; i < nu; ++i) {
        int32_t a = i, b = (i + 1) % nu, f, c, ca = -1, cb = -1, found = 0;
        for (f = 0; f < m.nf && !found; ++f) {
            ca = cb = -1;
            for (c = 0; c < 3; ++c) {
                if (m.faces[3 * f + c] == a) ca = 3 * f + c;
                if (m.faces[3 * f + c] == b) cb = 3 * f + c;
            }
            found = ca >= 0 && cb >= 0;
        }
        cr_assert(found);
        total += phi[cb] - phi[ca];
    }
    cr_assert(fabs(total - 2 * PI * 5) < 1e-8, "winding %g periods", total / (2 * PI));
    free(om);
    free(phi);
    wr_wf_free(&wf);
    wr_mesh_free(&m);
}

Test(wrinkle_field, loop_counts_and_linear_reproduction) {
    wr_mesh m, fine;
    int32_t *ff = NULL, v, mode;
    double *vals, *out = NULL;
    cr_assert_eq(wr_mesh_disk(&m, 1.0, 3, NULL), WR_OK);
    vals = (double *)malloc(sizeof(double) * 4 * m.nv);
    for (v = 0; v < m.nv; ++v) {
        /* perturb positions so the mesh is irregular in the plane; f is affine in the positions */
        double x = m.pos[3 * v] + 0.05 * sin(7.0 * v), y = m.pos[3 * v + 1] + 0.05 * cos(5.0 * v);
        vals[4 * v] = x;
        vals[4 * v + 1] = y;
        vals[4 * v + 2] = 0.3 * x - 0.2 * y;
        vals[4 * v + 3] = 2.0 * x + 3.0 * y + 1.0;
    }
    for (mode = 0; mode < 2; ++mode) {
        wr_wf_loop_desc ld;
        ld.boundary = (int)mode;
        cr_assert_eq(wr_wf_loop_step(&m, 4, vals, &ld, &ff, &out, NULL), WR_OK);
        for (v = 0; v < m.nv + m.ne; ++v) {
            double x = out[4 * v], y = out[4 * v + 1];
            cr_assert(fabs(out[4 * v + 3] - (2.0 * x + 3.0 * y + 1.0)) < 1e-12);
            cr_assert(fabs(out[4 * v + 2] - (0.3 * x - 0.2 * y)) < 1e-12);
        }
        cr_assert_eq(wr_mesh_create(&fine, m.nv + m.ne, NULL, out, 4 * m.nf, ff, NULL), WR_OK);
        cr_assert_eq(fine.nv, m.nv + m.ne);
        cr_assert_eq(fine.nf, 4 * m.nf);
        cr_assert_eq(fine.ne, 2 * m.ne + 3 * m.nf);
        cr_assert_eq(fine.n_loops, 1);
        wr_mesh_free(&fine);
        free(ff);
        free(out);
    }
    /* a regular interior vertex of valence 6: β = 1/16 */
    {
        wr_wf_loop_desc ld;
        double *one = (double *)calloc(m.nv, sizeof(double));
        one[0] = 1.0; /* the disk centre (valence 6) */
        ld.boundary = WR_WF_LOOP_BOUNDARY_FIXED;
        cr_assert_eq(wr_wf_loop_step(&m, 1, one, &ld, &ff, &out, NULL), WR_OK);
        cr_assert_float_eq(out[0], 1.0 - 6.0 / 16.0, 1e-15);
        free(ff);
        free(out);
        free(one);
    }
    cr_assert_eq(wr_wf_loop_step(&m, 0, vals, NULL, &ff, &out, NULL), WR_ERR_INVALID_ARG);
    free(vals);
    wr_mesh_free(&m);
}

Test(wrinkle_field, flat_sheet_eq19_displacement) {
    wr_mesh m, fine;
    wr_wf wf;
    wr_wf_material mat = material();
    wr_wf_upsample_desc ud;
    double L = 0.25, A = 4e-4, k = 2 * PI * 5 / L, *a, *om, *phi, *fa = NULL, zmax = 0.0, x0, c0;
    int32_t v;
    cr_assert_eq(wr_mesh_rectangle(&m, L, 0.1, 12, 5, NULL), WR_OK);
    cr_assert_eq(wr_wf_create(&wf, &m, NULL, &mat, NULL), WR_OK);
    a = (double *)malloc(sizeof(double) * m.nv);
    om = (double *)malloc(sizeof(double) * m.ne);
    phi = (double *)malloc(sizeof(double) * 3 * m.nf);
    for (v = 0; v < m.nv; ++v) a[v] = A;
    omega_linear(&m, k, om);
    cr_assert_eq(wr_wf_phase(&wf, om, phi, NULL, NULL), WR_OK);
    c0 = phi[0] - k * m.pos[3 * m.faces[0]];
    memset(&ud, 0, sizeof ud);
    ud.levels = 3;
    cr_assert_eq(wr_wf_upsample(&wf, a, phi, &ud, &fine, &fa, NULL), WR_OK);
    cr_assert_eq(fine.nf, 64 * m.nf);
    x0 = 0.0;
    for (v = 0; v < fine.nv; ++v) {
        /* rest x of the fine vertex; φ = k x + c0 is reproduced exactly by the Loop stencils */
        double x = fine.rest[2 * v], ph = k * x + c0;
        double z = fine.pos[3 * v + 2], dx = fine.pos[3 * v] - x;
        cr_assert(fabs(fa[v] - A) < 1e-15);
        cr_assert(fabs(z - A * cos(ph)) < 1e-12, "z %g vs %g", z, A * cos(ph));
        cr_assert(fabs(dx - A * A / 8.0 * k * sin(2 * ph)) < 1e-12, "in-plane %g vs %g", dx, A * A / 8 * k * sin(2 * ph));
        cr_assert(fabs(fine.pos[3 * v + 1] - fine.rest[2 * v + 1]) < 1e-15);
        zmax = fmax(zmax, z);
    }
    (void)x0;
    /* the vertex where φ ≡ 0 (mod 2π) is on the fine grid: peak displacement = a */
    cr_assert_float_eq(zmax, A, 1e-15 + 1e-12 * A);
    wr_mesh_free(&fine);
    free(fa);
    ud.no_inplane = 1;
    ud.levels = 1;
    cr_assert_eq(wr_wf_upsample(&wf, a, phi, &ud, &fine, NULL, NULL), WR_OK);
    for (v = 0; v < fine.nv; ++v) cr_assert(fabs(fine.pos[3 * v] - fine.rest[2 * v]) < 1e-15);
    wr_mesh_free(&fine);
    ud.levels = 9;
    cr_assert_eq(wr_wf_upsample(&wf, a, phi, &ud, &fine, NULL, NULL), WR_ERR_BUDGET);
    free(a);
    free(om);
    free(phi);
    wr_wf_free(&wf);
    wr_mesh_free(&m);
}

/* wr_wf_upsample_fields on the flat sheet with a band of faces in W: per fine vertex the phase is
 * φ = k x + c0 wrapped to (-π, π] (compared through cos and sin, and the range) away from W, the
 * height over the flat base is a cos(phase) exactly everywhere, and the wrinkle-free flag is 1 exactly on the vertices whose fine
 * faces all descend from W faces (fine face j of level L is a child of coarse face j >> 2L). */
Test(wrinkle_field, upsample_fields_phase_amplitude_and_w_flags) {
    wr_mesh m, fine;
    wr_wf wf;
    wr_wf_material mat = material();
    wr_wf_upsample_desc ud;
    wr_wf_fine_fields F;
    double L = 0.25, A = 4e-4, k = 2 * PI * 5 / L, *a, *om, *phi, c0;
    uint8_t *wflag;
    int32_t v, f, t, n_free = 0, n_wr = 0, n_far = 0;
    cr_assert_eq(wr_mesh_rectangle(&m, L, 0.1, 12, 5, NULL), WR_OK);
    cr_assert_eq(wr_wf_create(&wf, &m, NULL, &mat, NULL), WR_OK);
    wflag = (uint8_t *)calloc((size_t)m.nf, 1);
    for (f = 0; f < m.nf; ++f) { /* W: the faces whose centroid is in the left fifth */
        const int32_t *fv = m.faces + 3 * f;
        double cx = (m.pos[3 * fv[0]] + m.pos[3 * fv[1]] + m.pos[3 * fv[2]]) / 3.0;
        wflag[f] = cx < 0.2 * L;
    }
    wr_wf_set_wrinkle_free(&wf, wflag);
    a = (double *)malloc(sizeof(double) * m.nv);
    om = (double *)malloc(sizeof(double) * m.ne);
    phi = (double *)malloc(sizeof(double) * 3 * m.nf);
    for (v = 0; v < m.nv; ++v) a[v] = A;
    omega_linear(&m, k, om);
    cr_assert_eq(wr_wf_phase(&wf, om, phi, NULL, NULL), WR_OK);
    for (f = 0; f < m.nf && wflag[f]; ++f) {}
    c0 = phi[3 * f] - k * m.pos[3 * m.faces[3 * f]];
    memset(&ud, 0, sizeof ud);
    ud.levels = 2;
    ud.no_inplane = 1;
    cr_assert_eq(wr_wf_upsample_fields(&wf, a, phi, &ud, &fine, &F, NULL), WR_OK);
    cr_assert_eq(F.nv, fine.nv);
    for (v = 0; v < fine.nv; ++v) {
        double x = fine.rest[2 * v], ph = k * x + c0, z = fine.pos[3 * v + 2];
        int all_w = 1;
        for (t = fine.vf_start[v]; t < fine.vf_start[v + 1]; ++t) all_w &= wflag[fine.vf[t] >> 4];
        cr_assert_eq(F.wfree[v], all_w, "vertex %d: wfree %d, faces all in W %d", (int)v, F.wfree[v], all_w);
        if (all_w) {
            cr_assert_eq(F.a[v], 0.0);
            cr_assert_eq(F.phase[v], 0.0);
            cr_assert(fabs(z) < 1e-15);
            ++n_free;
            continue;
        }
        ++n_wr;
        cr_assert(F.phase[v] > -PI && F.phase[v] <= PI, "phase %g outside (-pi, pi]", F.phase[v]);
        /* linear φ is reproduced exactly where the Loop stencils see no W face (W corners carry φ = 0):
         * two levels reach at most two coarse cells (L/12 each) beyond a vertex */
        if (x > 0.2 * L + 2.5 * L / 12.0) {
            cr_assert(fabs(cos(F.phase[v]) - cos(ph)) < 1e-12 && fabs(sin(F.phase[v]) - sin(ph)) < 1e-12,
                      "vertex %d: phase %g vs k x + c0 = %g (mod 2 pi)", (int)v, F.phase[v], ph);
            cr_assert(fabs(F.a[v] - A) < 1e-15);
            ++n_far;
        }
        cr_assert(F.a[v] >= 0.0 && F.a[v] <= A * (1.0 + 1e-15)); /* near W, a tapers through the zeros there */
        cr_assert(fabs(z - F.a[v] * cos(F.phase[v])) < 1e-12, "height %g vs a cos(phase) %g", z,
                  F.a[v] * cos(F.phase[v]));
    }
    cr_assert(n_free > 0 && n_wr > n_free && n_far > n_wr / 2);
    wr_mesh_free(&fine);
    wr_wf_fine_fields_free(&F);
    wr_wf_fine_fields_free(&F); /* zeroed: a second free is harmless */
    cr_assert_eq(wr_wf_upsample_fields(&wf, a, phi, &ud, &fine, NULL, NULL), WR_ERR_INVALID_ARG);
    free(a);
    free(om);
    free(phi);
    free(wflag);
    wr_wf_free(&wf);
    wr_mesh_free(&m);
}

/* The wrinkled mesh keeps the base's panels (so its OBJ carries the panel names): with every coarse
 * face its own panel id, each fine face's panel must be the coarse face that contains it in the rest
 * domain (checked by barycentric coordinates of the fine face's rest centroid, independent of the
 * child numbering), at 1 and 3 levels; a base without panels gives a fine mesh without. */
Test(wrinkle_field, upsample_keeps_the_base_panels) {
    wr_mesh m, fine;
    wr_wf wf;
    wr_wf_material mat = material();
    wr_wf_upsample_desc ud;
    double *a, *phi;
    int32_t *panel, f, F, lv, v;
    cr_assert_eq(wr_mesh_rectangle(&m, 0.2, 0.1, 6, 3, NULL), WR_OK);
    panel = (int32_t *)malloc(sizeof(int32_t) * (size_t)m.nf);
    for (f = 0; f < m.nf; ++f) panel[f] = f;
    a = (double *)calloc((size_t)m.nv, sizeof(double));
    phi = (double *)calloc((size_t)(3 * m.nf), sizeof(double));
    for (v = 0; v < m.nv; ++v) a[v] = 1e-4;
    for (lv = 1; lv <= 3; lv += 2) {
        cr_assert_eq(wr_mesh_set_face_panel(&m, panel, NULL), WR_OK);
        cr_assert_eq(wr_wf_create(&wf, &m, NULL, &mat, NULL), WR_OK);
        memset(&ud, 0, sizeof ud);
        ud.levels = lv;
        cr_assert_eq(wr_wf_upsample(&wf, a, phi, &ud, &fine, NULL, NULL), WR_OK);
        cr_assert_not_null(fine.face_panel);
        for (F = 0; F < fine.nf; ++F) {
            const int32_t *c = m.faces + 3 * fine.face_panel[F], *g = fine.faces + 3 * F;
            double px = 0, py = 0, x0 = m.rest[2 * c[0]], y0 = m.rest[2 * c[0] + 1];
            double e1x = m.rest[2 * c[1]] - x0, e1y = m.rest[2 * c[1] + 1] - y0;
            double e2x = m.rest[2 * c[2]] - x0, e2y = m.rest[2 * c[2] + 1] - y0, det, b1, b2;
            int k;
            for (k = 0; k < 3; ++k) px += fine.rest[2 * g[k]] / 3, py += fine.rest[2 * g[k] + 1] / 3;
            det = e1x * e2y - e1y * e2x;
            b1 = ((px - x0) * e2y - (py - y0) * e2x) / det;
            b2 = (e1x * (py - y0) - e1y * (px - x0)) / det;
            cr_assert(b1 > 0 && b2 > 0 && b1 + b2 < 1, "level %d fine face %d: centroid not inside its panel's face %d",
                      (int)lv, (int)F, (int)fine.face_panel[F]);
        }
        wr_mesh_free(&fine);
        wr_wf_free(&wf);
    }
    cr_assert_eq(wr_mesh_set_face_panel(&m, NULL, NULL), WR_OK);
    cr_assert_eq(wr_wf_create(&wf, &m, NULL, &mat, NULL), WR_OK);
    cr_assert_eq(wr_wf_upsample(&wf, a, phi, NULL, &fine, NULL, NULL), WR_OK);
    cr_assert_null(fine.face_panel);
    wr_mesh_free(&fine);
    wr_wf_free(&wf);
    free(a);
    free(phi);
    free(panel);
    wr_mesh_free(&m);
}

/* A sewn base's per-corner rest coordinates and panels through the upsampling (ON SEWN BASES), in
 * closed form: two faces sharing the edge (1, 2), each with its own chart, the two charts OVERLAPPING
 * in the rest plane as a welded skirt's front and back do (face 0: (0,0) (1,0) (0,1); face 1, corners
 * (2, 1, 3): (0,0) (1,0) (1,1)). One step gives each child the parent's corners and the midpoints of
 * the parent's edges in the parent's chart, cornered as wr_wf_loop_step's children; a child face has
 * its parent's panel; two levels are two steps; a rest point in the overlap is located in panel 1's
 * fine faces at the barycentric position it has in face 1's chart. */
Test(wrinkle_field, upsample_carries_corner_rest_and_panels) {
    static const double P[12] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0.2};
    static const int32_t T[6] = {0, 1, 2, 2, 1, 3}, panel[2] = {4, 7};
    static const double CR[12] = {0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 1, 1};
    static const double want[48] = {0, 0, .5, 0, 0, .5,     1, 0, .5, .5, .5, 0,   0, 1, 0, .5, .5, .5,
                                    .5, .5, 0, .5, .5, 0,   0, 0, .5, 0, .5, .5,   1, 0, 1, .5, .5, 0,
                                    1, 1, .5, .5, 1, .5,    1, .5, .5, .5, .5, 0};
    double got[48], lv2[192], a[4] = {0, 0, 0, 0}, phi[6] = {0, 0, 0, 0, 0, 0}, bary[3];
    wr_mesh m, fine;
    wr_wf wf;
    wr_wf_material mat = material();
    wr_wf_upsample_desc ud;
    wr_probe pr;
    wr_probe_desc pd;
    uint8_t mask[32];
    int32_t i, F;
    cr_assert_eq(wr_mesh_create(&m, 4, P, NULL, 2, T, NULL), WR_OK);
    cr_assert_eq(wr_mesh_set_corner_rest(&m, CR, NULL), WR_OK);
    cr_assert_eq(wr_mesh_set_face_panel(&m, panel, NULL), WR_OK);
    wr_wf_loop_corner_rest(2, CR, got);
    for (i = 0; i < 48; ++i) cr_assert(got[i] == want[i], "corner rest %d: %g, want %g", (int)i, got[i], want[i]);
    wr_wf_loop_corner_rest(8, got, lv2);
    cr_assert_eq(wr_wf_create(&wf, &m, NULL, &mat, NULL), WR_OK);
    memset(&ud, 0, sizeof ud);
    ud.levels = 2;
    cr_assert_eq(wr_wf_upsample(&wf, a, phi, &ud, &fine, NULL, NULL), WR_OK);
    cr_assert_eq(fine.nf, 32);
    cr_assert_not_null(fine.corner_rest);
    cr_assert_not_null(fine.face_panel);
    for (i = 0; i < 192; ++i) cr_assert(fine.corner_rest[i] == lv2[i], "level 2 corner rest %d", (int)i);
    for (F = 0; F < 32; ++F) {
        cr_assert_eq(fine.face_panel[F], panel[F >> 4], "fine face %d: panel %d", (int)F, (int)fine.face_panel[F]);
        mask[F] = fine.face_panel[F] == 7;
    }
    memset(&pd, 0, sizeof pd);
    pd.face_mask = mask;
    cr_assert_eq(wr_probe_create(&pr, &fine, &pd, NULL), WR_OK);
    F = wr_probe_locate(&pr, 0.6, 0.2, bary); /* in both charts; in face 1's: 0.4 c0 + 0.4 c1 + 0.2 c2 */
    cr_assert(F >= 16 && fine.face_panel[F] == 7, "located in fine face %d", (int)F);
    {
        const double *c = fine.corner_rest + 6 * F;
        double x = bary[0] * c[0] + bary[1] * c[2] + bary[2] * c[4], y = bary[0] * c[1] + bary[1] * c[3] + bary[2] * c[5];
        cr_assert(fabs(x - 0.6) < 1e-12 && fabs(y - 0.2) < 1e-12, "located at (%g, %g)", x, y);
    }
    wr_probe_free(&pr);
    wr_mesh_free(&fine);
    wr_wf_free(&wf);
    /* a base without corner_rest gives a fine mesh without */
    cr_assert_eq(wr_mesh_set_corner_rest(&m, NULL, NULL), WR_OK);
    cr_assert_eq(wr_wf_create(&wf, &m, NULL, &mat, NULL), WR_OK);
    cr_assert_eq(wr_wf_upsample(&wf, a, phi, &ud, &fine, NULL, NULL), WR_OK);
    cr_assert_null(fine.corner_rest);
    wr_mesh_free(&fine);
    wr_wf_free(&wf);
    wr_mesh_free(&m);
}

static int g_progress_calls;
static void count_progress(const wr_wf_iter_info *info, void *user) {
    (void)user;
    cr_assert(isfinite(info->energy) && info->kkt >= 0.0);
    ++g_progress_calls;
}

/* A uniformly compressed flat sheet with a free everywhere has no minimiser: along (s·a, ω/s) the
 * relief a²|dφ|² is fixed and the bending term a²|dφ|⁴ ∝ 1/s² decays to 0 (this is why the first SQP
 * test on this case "stalled"). The solver must still keep every iterate feasible and decrease E. */
Test(wrinkle_field, sqp_on_unbounded_compressed_sheet_stays_feasible) {
    wr_mesh m;
    wr_wf wf;
    wr_wf_material mat;
    wr_wf_solve_desc sd;
    wr_wf_solve_stats ss;
    double *base, *a, *om, *curl, *a2, *o2, Eprev = INFINITY, s;
    int32_t v, f, e;
    wr_status st;
    mat.young = 1e6;
    mat.poisson = 0.5;
    mat.thickness = 1e-4;
    cr_assert_eq(wr_mesh_rectangle(&m, 0.25, 0.1, 12, 5, NULL), WR_OK);
    base = (double *)malloc(sizeof(double) * 3 * m.nv);
    fill_scaled(&m, 0.97, 1.0, base);
    cr_assert_eq(wr_wf_create(&wf, &m, base, &mat, NULL), WR_OK);
    cr_assert_eq(wr_wf_classify(&wf, NULL), 0);
    a = (double *)malloc(sizeof(double) * m.nv);
    om = (double *)malloc(sizeof(double) * m.ne);
    a2 = (double *)malloc(sizeof(double) * m.nv);
    o2 = (double *)malloc(sizeof(double) * m.ne);
    curl = (double *)malloc(sizeof(double) * m.nf);
    cr_assert_eq(wr_wf_init(&wf, NULL, a, om, NULL), WR_OK);
    for (s = 1.0; s <= 64.0; s *= 2.0) {
        double E;
        for (v = 0; v < m.nv; ++v) a2[v] = s * a[v];
        for (e = 0; e < m.ne; ++e) o2[e] = om[e] / s;
        cr_assert_eq(wr_wf_energy(&wf, a2, o2, &E, NULL, NULL, NULL, NULL), WR_OK);
        cr_assert(E < 0.3 * Eprev, "E(s = %g) = %g not < 0.3 E(s/2) = %g", s, E, 0.3 * Eprev);
        Eprev = E;
    }
    memset(&sd, 0, sizeof sd);
    sd.progress = count_progress;
    sd.max_iter = 20;
    g_progress_calls = 0;
    st = wr_wf_solve(&wf, &sd, a, om, &ss, NULL);
    cr_assert(st == WR_ERR_NOT_CONVERGED && ss.stop == WR_WF_STOP_MAX_ITER, "status %d stop %d", (int)st, (int)ss.stop);
    cr_assert(ss.energy < ss.energy0);
    cr_assert_eq(g_progress_calls, ss.iterations);
    for (v = 0; v < m.nv; ++v) cr_assert(a[v] >= 0.0);
    wr_wf_curl(&m, om, curl);
    for (f = 0; f < m.nf; ++f) cr_assert(fabs(curl[f]) < 1e-9, "curl %g", curl[f]);
    free(base);
    free(a);
    free(om);
    free(a2);
    free(o2);
    free(curl);
    wr_wf_free(&wf);
    wr_mesh_free(&m);
}

/* Regression for the stalled SQP (KKT 1.06e-5 -> 9.0e-6 in 200 iterations): the reduced Hessian
 * PᵀHP applied face_edge_sign twice (face_hess is already in global ω orientation), so Newton used a
 * wrong Hessian (19% off in a finite-difference check) and converged linearly at best.
 * Case: a stretched-sheet-like base (x stretched 10%, width contracted by up to 10% in the middle,
 * more than the Poisson contraction, so the middle wrinkles), ends clamped (W = end columns). */
static void stretched_base(const wr_mesh *m, double L, double H, double *base) {
    int32_t v;
    for (v = 0; v < m->nv; ++v) {
        double x = m->pos[3 * v], y = m->pos[3 * v + 1];
        base[3 * v] = 1.1 * x;
        base[3 * v + 1] = (y - 0.5 * H) * (1.0 - 0.1 * sin(PI * x / L)) + 0.5 * H;
        base[3 * v + 2] = 0.0;
    }
}

/* The clamped stretched sheet of the SQP tests: an L × H rectangle (12 × 5 cells) on stretched_base,
 * E = 1 MPa, ν = 0.5, h = 0.1 mm, W = the faces within 2 cm of either end; a0 (nv) and o0 (ne) from
 * wr_wf_init. The caller frees base, wfl, a0, o0, the wf and the mesh. */
static void clamped_sheet_setup(wr_mesh *m, wr_wf *wf, double L, double H, double **base, uint8_t **wfl, double **a0,
                                double **o0) {
    wr_wf_material mat;
    int32_t f, k;
    mat.young = 1e6;
    mat.poisson = 0.5;
    mat.thickness = 1e-4;
    cr_assert_eq(wr_mesh_rectangle(m, L, H, 12, 5, NULL), WR_OK);
    *base = (double *)malloc(sizeof(double) * 3 * m->nv);
    stretched_base(m, L, H, *base);
    cr_assert_eq(wr_wf_create(wf, m, *base, &mat, NULL), WR_OK);
    *wfl = (uint8_t *)calloc((size_t)m->nf, 1);
    for (f = 0; f < m->nf; ++f) {
        double cx = 0.0;
        for (k = 0; k < 3; ++k) cx += m->pos[3 * m->faces[3 * f + k]] / 3.0;
        (*wfl)[f] = (uint8_t)(cx < 0.02 || cx > L - 0.02);
    }
    wr_wf_set_wrinkle_free(wf, *wfl);
    *a0 = (double *)malloc(sizeof(double) * m->nv);
    *o0 = (double *)malloc(sizeof(double) * m->ne);
    cr_assert_eq(wr_wf_init(wf, NULL, *a0, *o0, NULL), WR_OK);
}

Test(wrinkle_field, sqp_converges_to_kkt_1e8_on_clamped_stretched_sheet) {
    const double L = 0.25, Hh = 0.1;
    wr_mesh m;
    wr_wf wf;
    double *base, *a0, *o0, *a, *om, *curl, Eref = 0.0;
    uint8_t *wfl;
    int32_t v, f, k, h;
    static const wr_wf_hessian strat[3] = {WR_WF_HESSIAN_AUTO, WR_WF_HESSIAN_TRUE, WR_WF_HESSIAN_PROJECTED};
    static const int32_t max_it[3] = {40, 40, 80}; /* measured 24, 26, 62 */
    clamped_sheet_setup(&m, &wf, L, Hh, &base, &wfl, &a0, &o0);
    a = (double *)malloc(sizeof(double) * m.nv);
    om = (double *)malloc(sizeof(double) * m.ne);
    curl = (double *)malloc(sizeof(double) * m.nf);
    for (h = 0; h < 3; ++h) {
        wr_wf_solve_desc sd;
        wr_wf_solve_stats ss;
        wr_status st;
        memcpy(a, a0, sizeof(double) * m.nv);
        memcpy(om, o0, sizeof(double) * m.ne);
        memset(&sd, 0, sizeof sd);
        sd.hessian = strat[h];
        sd.tol_energy = 1e-300; /* only the KKT rule may stop */
        sd.tol_step = 1e-300;
        sd.max_iter = 200;
        sd.progress = count_progress;
        g_progress_calls = 0;
        st = wr_wf_solve(&wf, &sd, a, om, &ss, NULL);
        cr_log_info("SQP strategy %d: %d iters (%d rejected, %d factorisations, true Hessian from %d), E %.10g -> "
                    "%.10g, KKT %g -> %g, %.3f s",
                    (int)strat[h], ss.iterations, ss.n_rejected, ss.n_factorizations, ss.switch_iteration, ss.energy0,
                    ss.energy, ss.kkt0, ss.kkt, ss.seconds);
        cr_assert_eq(st, WR_OK, "strategy %d: status %d stop %d KKT %g/%g", (int)strat[h], (int)st, (int)ss.stop,
                     ss.kkt, ss.kkt0);
        cr_assert_eq(ss.stop, WR_WF_STOP_KKT);
        cr_assert(ss.kkt <= 1e-8 * ss.kkt0);
        cr_assert(ss.iterations <= max_it[h], "strategy %d: %d iterations", (int)strat[h], ss.iterations);
        cr_assert_eq(g_progress_calls, ss.iterations);
        cr_assert(ss.energy < 0.75 * ss.energy0); /* wrinkling relieves a quarter of the stretching energy */
        if (h == 0)
            Eref = ss.energy;
        else
            cr_assert(fabs(ss.energy - Eref) <= 1e-9 * Eref, "%.12g vs %.12g", ss.energy, Eref);
        for (v = 0; v < m.nv; ++v) cr_assert(a[v] >= 0.0);
        for (f = 0; f < m.nf; ++f)
            if (wfl[f])
                for (k = 0; k < 3; ++k) cr_assert_eq(a[m.faces[3 * f + k]], 0.0);
        wr_wf_curl(&m, om, curl);
        for (f = 0; f < m.nf; ++f)
            if (!wfl[f]) cr_assert(fabs(curl[f]) < 1e-9, "curl %g", curl[f]);
        /* interior amplitude ~1 mm (measured 0.98 mm), zero at the clamps */
        {
            double amax = 0.0;
            for (v = 0; v < m.nv; ++v) amax = fmax(amax, a[v]);
            cr_assert(amax > 5e-4 && amax < 2e-3, "amax %g", amax);
        }
    }
    /* a = 0 is a KKT point (E is even in a); from a = 0 the second-order escape must find the
     * wrinkles again (TFW App. F: "amplitude first vanishes globally ... then wrinkles emerge") */
    {
        wr_wf_solve_desc sd;
        wr_wf_solve_stats ss;
        double amax = 0.0;
        memset(a, 0, sizeof(double) * m.nv);
        memcpy(om, o0, sizeof(double) * m.ne);
        memset(&sd, 0, sizeof sd);
        sd.tol_energy = 1e-300;
        sd.tol_step = 1e-300;
        cr_assert_eq(wr_wf_solve(&wf, &sd, a, om, &ss, NULL), WR_OK);
        cr_log_info("SQP from a = 0: %d iters, %d escapes, E %.10g -> %.10g, KKT %g -> %g", ss.iterations,
                    ss.n_escapes, ss.energy0, ss.energy, ss.kkt0, ss.kkt);
        cr_assert(ss.n_escapes >= 1);
        cr_assert_eq(ss.stop, WR_WF_STOP_KKT);
        cr_assert(ss.kkt <= 1e-8 * ss.kkt0 && ss.kkt0 > 0.0);
        cr_assert(ss.energy < ss.energy0);
        cr_assert(fabs(ss.energy - Eref) <= 1e-6 * Eref, "%.12g vs %.12g", ss.energy, Eref);
        for (v = 0; v < m.nv; ++v) amax = fmax(amax, a[v]);
        cr_assert(amax > 5e-4 && amax < 2e-3, "amax %g", amax);
    }
    {
        wr_wf_solve_desc sd;
        memset(&sd, 0, sizeof sd);
        sd.hessian = (wr_wf_hessian)7;
        cr_assert_eq(wr_wf_solve(&wf, &sd, a, om, NULL, NULL), WR_ERR_INVALID_ARG);
    }
    free(base);
    free(a0);
    free(o0);
    free(a);
    free(om);
    free(curl);
    free(wfl);
    wr_wf_free(&wf);
    wr_mesh_free(&m);
}

/* The negative_curvature option (wrinkle_field.h ON NEGATIVE CURVATURE), as the progress callback
 * reports it: steps holding a direction p, its curvature pᵀKp/pᵀMp and the model's sign preference. */
typedef struct nc_log {
    int32_t calls, nc_steps, bad_curv, bad_sign;
    double min_curv;
} nc_log;
static void nc_progress(const wr_wf_iter_info *info, void *user) {
    nc_log *L = (nc_log *)user;
    ++L->calls;
    if (!info->negcurv) return;
    ++L->nc_steps;
    L->bad_curv += !(info->curvature < 0.0);
    L->bad_sign += !(info->nc_gain >= 0.0);
    L->min_curv = fmin(L->min_curv, info->curvature);
}

/* "Same final fields" of docs/notes-tfw-solver.md (issue 16): |ΔE|/|E| <= 1e-8, max |Δa| <= 2.5e-2
 * max a, and on edges whose mean amplitude is >= 0.1 max a, max |Δω| <= 5e-2 max |ω| (up to a global
 * sign of ω). Returns 1 when (a1, o1, E1) and (a2, o2, E2) agree so. */
static int same_fields(const wr_mesh *m, const double *a1, const double *o1, double E1, const double *a2,
                       const double *o2, double E2) {
    double amax = 0.0, omax = 0.0, da = 0.0, dp = 0.0, dm = 0.0;
    int32_t v, e;
    for (v = 0; v < m->nv; ++v) {
        amax = fmax(amax, a1[v]);
        da = fmax(da, fabs(a1[v] - a2[v]));
    }
    for (e = 0; e < m->ne; ++e) {
        double ae = 0.5 * (a1[m->edges[2 * e]] + a1[m->edges[2 * e + 1]]);
        omax = fmax(omax, fabs(o1[e]));
        if (ae < 0.1 * amax) continue;
        dp = fmax(dp, fabs(o1[e] - o2[e]));
        dm = fmax(dm, fabs(o1[e] + o2[e]));
    }
    cr_log_info("same fields: |dE|/E %.3g, max|da|/max a %.3g, max|dw|/max|w| %.3g", fabs(E1 - E2) / fabs(E1),
                da / amax, fmin(dp, dm) / omax);
    return fabs(E1 - E2) <= 1e-8 * fabs(E1) && da <= 2.5e-2 * amax && fmin(dp, dm) <= 5e-2 * omax;
}

/* Off (the default) the option changes nothing: no step reports a direction. On, on the clamped
 * stretched sheet with the true Hessian throughout (whose factorisation fails on the saddle of the
 * E.2 start), the solve takes steps along negative curvature, each with pᵀKp < 0 and the sign the
 * model prefers, and ends at the default's minimum by the criterion above (KKT stop 1e-8). */
Test(wrinkle_field, sqp_negative_curvature_option_same_minimum) {
    const double L = 0.25, Hh = 0.1;
    wr_mesh m;
    wr_wf wf;
    double *base, *a0, *o0, *a[2], *om[2], E[2] = {0.0, 0.0};
    uint8_t *wfl;
    int32_t it[2] = {0, 0}, k, h;
    static const wr_wf_hessian strat[2] = {WR_WF_HESSIAN_TRUE, WR_WF_HESSIAN_AUTO};
    clamped_sheet_setup(&m, &wf, L, Hh, &base, &wfl, &a0, &o0);
    for (k = 0; k < 2; ++k) {
        a[k] = (double *)malloc(sizeof(double) * m.nv);
        om[k] = (double *)malloc(sizeof(double) * m.ne);
    }
    for (h = 0; h < 2; ++h) {
        int32_t ntot = 0;
        for (k = 0; k < 2; ++k) {
            wr_wf_solve_desc sd;
            wr_wf_solve_stats ss;
            nc_log lg;
            memset(&lg, 0, sizeof lg);
            memcpy(a[k], a0, sizeof(double) * m.nv);
            memcpy(om[k], o0, sizeof(double) * m.ne);
            memset(&sd, 0, sizeof sd);
            sd.hessian = strat[h];
            sd.negative_curvature = k;
            sd.tol_energy = 1e-300; /* only the KKT rule may stop */
            sd.tol_step = 1e-300;
            sd.max_iter = 200;
            sd.progress = nc_progress;
            sd.user = &lg;
            cr_assert_eq(wr_wf_solve(&wf, &sd, a[k], om[k], &ss, NULL), WR_OK);
            cr_log_info("hessian %d, negative_curvature %d: %d iterations (%d rejected, %d factorisations), %d "
                        "negative-curvature steps (min curvature %g), E %.12g, KKT %g / %g",
                        (int)strat[h], (int)k, ss.iterations, ss.n_rejected, ss.n_factorizations, ss.n_negcurv,
                        lg.min_curv, ss.energy, ss.kkt, ss.kkt0);
            cr_assert_eq(ss.stop, WR_WF_STOP_KKT);
            cr_assert_eq(lg.calls, ss.iterations);
            cr_assert_eq(lg.nc_steps, ss.n_negcurv);
            cr_assert_eq(lg.bad_curv, 0, "%d steps along a direction of positive curvature", lg.bad_curv);
            cr_assert_eq(lg.bad_sign, 0, "%d steps along the sign the model does not prefer", lg.bad_sign);
            if (k == 0) cr_assert_eq(ss.n_negcurv, 0);
            ntot += ss.n_negcurv;
            it[k] = ss.iterations;
            E[k] = ss.energy;
        }
        if (h == 0) cr_assert(ntot >= 1, "the true Hessian's saddle must be left along negative curvature");
        cr_assert(same_fields(&m, a[0], om[0], E[0], a[1], om[1], E[1]), "hessian %d: %d vs %d iterations",
                  (int)strat[h], it[0], it[1]);
    }
    {
        wr_wf_solve_desc sd;
        memset(&sd, 0, sizeof sd);
        sd.negative_curvature = 2;
        cr_assert_eq(wr_wf_solve(&wf, &sd, a[0], om[0], NULL, NULL), WR_ERR_INVALID_ARG);
    }
    for (k = 0; k < 2; ++k) {
        free(a[k]);
        free(om[k]);
    }
    free(base);
    free(a0);
    free(o0);
    free(wfl);
    wr_wf_free(&wf);
    wr_mesh_free(&m);
}

/* Energies and ρ of the accepted steps, as the progress callback reports them. */
#define TERM_MAX_STEPS 400
static double g_step_e[TERM_MAX_STEPS], g_step_rho[TERM_MAX_STEPS];
static int g_steps;
static void record_steps(const wr_wf_iter_info *info, void *user) {
    (void)user;
    if (g_steps < TERM_MAX_STEPS) {
        g_step_e[g_steps] = info->energy;
        g_step_rho[g_steps] = info->alpha_ls;
    }
    ++g_steps;
}

/* App. E.3 rule 1 as implemented: stop at the FIRST accepted step the quadratic model predicted well
 * (ρ > 1/2) whose energy change is <= tol_energy · |E| (E the objective before the step), never
 * earlier, and return its end point. Checked at the default tol_energy (1e-10) and at 1e-5, which
 * must stop earlier; the start has no amplitude at the bound with zero gradient, so no escape moves
 * E between reported steps. Also: the SQP with the literal monomial evaluator (reference_eval) takes
 * the same steps to the same energy (the cached Q, moments and K positions change nothing). */
Test(wrinkle_field, sqp_energy_rule_stops_at_first_qualifying_step) {
    const double L = 0.25, Hh = 0.1;
    static const double tols[2] = {0.0, 1e-5};
    wr_mesh m;
    wr_wf wf;
    double *base, *a0, *o0, *a, *om, Edef = 0.0;
    uint8_t *wfl;
    int32_t t, itdef = 0;
    clamped_sheet_setup(&m, &wf, L, Hh, &base, &wfl, &a0, &o0);
    a = (double *)malloc(sizeof(double) * m.nv);
    om = (double *)malloc(sizeof(double) * m.ne);
    for (t = 0; t < 3; ++t) {
        wr_wf_solve_desc sd;
        wr_wf_solve_stats ss;
        double tol = t == 1 ? tols[1] : 1e-10, Eprev;
        int32_t i;
        memcpy(a, a0, sizeof(double) * m.nv);
        memcpy(om, o0, sizeof(double) * m.ne);
        memset(&sd, 0, sizeof sd);
        sd.tol_energy = t == 1 ? tols[1] : 0.0;
        sd.progress = record_steps;
        wf.reference_eval = t == 2;
        g_steps = 0;
        cr_assert_eq(wr_wf_solve(&wf, &sd, a, om, &ss, NULL), WR_OK);
        cr_log_info("tol_energy %g%s: %d steps, stop %d, E %.15g, KKT %g of %g", tol, t == 2 ? " (reference eval)" : "",
                    ss.iterations, (int)ss.stop, ss.energy, ss.kkt, ss.kkt0);
        cr_assert_eq(ss.n_escapes, 0);
        cr_assert_eq(g_steps, ss.iterations);
        cr_assert(g_steps <= TERM_MAX_STEPS);
        cr_assert_eq(ss.stop, WR_WF_STOP_ENERGY, "stop rule %d", (int)ss.stop);
        Eprev = ss.energy0;
        for (i = 0; i < g_steps; ++i) {
            int qualifies = g_step_rho[i] > 0.5 && fabs(Eprev - g_step_e[i]) <= tol * fabs(Eprev);
            if (i + 1 < g_steps)
                cr_assert(!qualifies, "step %d already met rule 1 (dE %g, E %g, rho %g)", (int)i + 1,
                          Eprev - g_step_e[i], Eprev, g_step_rho[i]);
            else
                cr_assert(qualifies, "last step does not meet rule 1 (dE %g, E %g, rho %g)", Eprev - g_step_e[i], Eprev,
                          g_step_rho[i]);
            Eprev = g_step_e[i];
        }
        /* the returned fields are the last step's end point */
        cr_assert(fabs(ss.energy - g_step_e[g_steps - 1]) <= 1e-12 * fabs(ss.energy));
        if (t == 0) {
            Edef = ss.energy;
            itdef = ss.iterations;
        } else if (t == 1) {
            cr_assert(ss.iterations < itdef, "a looser rule 1 must stop earlier (%d vs %d)", ss.iterations, itdef);
            cr_assert(ss.energy >= Edef - 1e-12 * fabs(Edef));
        } else {
            cr_assert_eq(ss.iterations, itdef, "reference evaluator: %d steps vs %d", ss.iterations, itdef);
            cr_assert(fabs(ss.energy - Edef) <= 1e-12 * fabs(Edef), "%.15g vs %.15g", ss.energy, Edef);
        }
    }
    wf.reference_eval = 0;
    free(base);
    free(wfl);
    free(a0);
    free(o0);
    free(a);
    free(om);
    wr_wf_free(&wf);
    wr_mesh_free(&m);
}

Test(wrinkle_field, sqp_in_tension_drives_amplitude_to_zero) {
    wr_mesh m;
    wr_wf wf;
    wr_wf_material mat = material();
    wr_wf_solve_stats ss;
    wr_wf_solve_desc sd;
    double *base, *a, *om, E;
    int32_t v;
    cr_assert_eq(wr_mesh_rectangle(&m, 0.1, 0.05, 6, 3, NULL), WR_OK);
    base = (double *)malloc(sizeof(double) * 3 * m.nv);
    fill_scaled(&m, 1.05, 1.02, base);
    cr_assert_eq(wr_wf_create(&wf, &m, base, &mat, NULL), WR_OK); /* W left empty on purpose */
    a = (double *)malloc(sizeof(double) * m.nv);
    om = (double *)malloc(sizeof(double) * m.ne);
    for (v = 0; v < m.nv; ++v) a[v] = 1e-3;
    omega_linear(&m, 100.0, om);
    memset(&sd, 0, sizeof sd);
    sd.tol_energy = 1e-300; /* not |ΔE| ∝ a²: the bound must be identified (or E at round-off) */
    cr_assert_eq(wr_wf_solve(&wf, &sd, a, om, &ss, NULL), WR_OK);
    for (v = 0; v < m.nv; ++v) cr_assert(a[v] >= 0.0 && a[v] < 1e-9, "a[%d] = %g", v, a[v]);
    /* the minimum is the plain base stretching energy */
    {
        double *z = (double *)calloc(m.nv, sizeof(double)), terms[WR_WF_NTERMS];
        cr_assert_eq(wr_wf_energy(&wf, z, om, &E, NULL, NULL, terms, NULL), WR_OK);
        cr_assert(fabs(ss.energy - E) <= 1e-10 * E, "%g vs %g", ss.energy, E);
        free(z);
    }
    free(base);
    free(a);
    free(om);
    wr_wf_free(&wf);
    wr_mesh_free(&m);
}

/* Clamped-edge condition (wr_wf_set_amplitude_zero) and the Cerda-Mahadevan balance. On the clamped,
 * stretched sheet (no W set: the clamps hold a = 0 instead) the solved fields must keep a = 0 on the
 * clamped vertices, stay curl free, and select the wavelength of Cerda & Mahadevan's bending-vs-crest-
 * tension balance on the envelope E_wf itself produces: k⁴ = T ∫a'² / (D ∫a²) along the mid-line,
 * T = E h ε_xx (Green strain 0.105 of the 1.1 stretch), D = E h³ / (12(1 - ν²)) (from Eq. 21's
 * ½ daᵀda term against Eq. 26's W_b^2; a factor 2 error in either moves k by 19 %). */
Test(wrinkle_field, clamped_amplitude_and_cerda_mahadevan_wavelength) {
    const double L = 0.25, Hh = 0.1, E = 1e6, nu = 0.5, h = 1e-4;
    const int32_t nx = 24, ny = 6;
    wr_mesh m;
    wr_wf wf;
    wr_wf_material mat;
    wr_wf_solve_desc sd;
    wr_wf_solve_stats ss;
    double *base, *a, *om, *curl, s2 = 0.0, d2 = 0.0, ksum = 0.0, wsum = 0.0, kpred, T, D, amax = 0.0;
    double *xs, *as;
    uint8_t *az;
    int32_t v, f, k, nmid = 0;
    mat.young = E;
    mat.poisson = nu;
    mat.thickness = h;
    cr_assert_eq(wr_mesh_rectangle(&m, L, Hh, nx, ny, NULL), WR_OK);
    base = (double *)malloc(sizeof(double) * 3 * m.nv);
    stretched_base(&m, L, Hh, base);
    cr_assert_eq(wr_wf_create(&wf, &m, base, &mat, NULL), WR_OK);
    az = (uint8_t *)calloc((size_t)m.nv, 1);
    for (v = 0; v < m.nv; ++v) az[v] = (uint8_t)(m.pos[3 * v] < 1e-9 || m.pos[3 * v] > L - 1e-9);
    wr_wf_set_amplitude_zero(&wf, az);
    a = (double *)malloc(sizeof(double) * m.nv);
    om = (double *)malloc(sizeof(double) * m.ne);
    curl = (double *)malloc(sizeof(double) * m.nf);
    cr_assert_eq(wr_wf_init(&wf, NULL, a, om, NULL), WR_OK);
    for (v = 0; v < m.nv; ++v)
        if (az[v]) cr_assert_eq(a[v], 0.0);
    memset(&sd, 0, sizeof sd);
    sd.tol_energy = 1e-300; /* only the KKT rule may stop */
    sd.tol_step = 1e-300;
    sd.max_iter = 300;
    cr_assert_eq(wr_wf_solve(&wf, &sd, a, om, &ss, NULL), WR_OK);
    cr_assert_eq(ss.stop, WR_WF_STOP_KKT);
    for (v = 0; v < m.nv; ++v) {
        cr_assert(a[v] >= 0.0);
        if (az[v]) cr_assert_eq(a[v], 0.0, "clamped vertex %d has a = %g", v, a[v]);
        amax = fmax(amax, a[v]);
    }
    cr_assert(amax > 1e-4, "amax %g", amax);
    wr_wf_curl(&m, om, curl);
    for (f = 0; f < m.nf; ++f) cr_assert(fabs(curl[f]) < 1e-9, "curl %g", curl[f]);
    /* envelope along the mid-line row y = H/2 (vertex row ny/2 of the grid), exact integrals of the
     * piecewise-linear a */
    xs = (double *)malloc(sizeof(double) * m.nv);
    as = (double *)malloc(sizeof(double) * m.nv);
    for (v = 0; v < m.nv; ++v)
        if (fabs(m.pos[3 * v + 1] - 0.5 * Hh) < 1e-9) {
            xs[nmid] = m.pos[3 * v];
            as[nmid++] = a[v];
        }
    cr_assert_eq(nmid, nx + 1);
    for (k = 1; k < nmid; ++k) /* rows are produced in x order by wr_mesh_rectangle */
        cr_assert(xs[k] > xs[k - 1]);
    for (k = 0; k + 1 < nmid; ++k) {
        double dx = xs[k + 1] - xs[k];
        s2 += dx / 3.0 * (as[k] * as[k] + as[k] * as[k + 1] + as[k + 1] * as[k + 1]);
        d2 += (as[k + 1] - as[k]) * (as[k + 1] - as[k]) / dx;
    }
    /* |dφ| on the faces, weighted by a² (where the wrinkles are) */
    for (f = 0; f < m.nf; ++f) {
        int32_t idx[6];
        double sg[6], w[3], p0, p1, am = 0.0, kk;
        const double *ii = wf.iu_inv + 3 * f;
        wr_wf_face_dofs(&wf, f, idx, sg);
        for (k = 0; k < 3; ++k) {
            w[k] = sg[3 + k] * om[idx[3 + k] - m.nv];
            am += a[m.faces[3 * f + k]] / 3.0;
        }
        p0 = (-w[0] - w[1] + 2.0 * w[2]) / 3.0;
        p1 = (w[0] - 2.0 * w[1] + w[2]) / 3.0;
        kk = sqrt(p0 * p0 * ii[0] + 2.0 * p0 * p1 * ii[1] + p1 * p1 * ii[2]);
        ksum += am * am * kk;
        wsum += am * am;
    }
    T = E * h * 0.5 * (1.1 * 1.1 - 1.0);
    D = E * h * h * h / (12.0 * (1.0 - nu * nu));
    kpred = pow(T * d2 / (D * s2), 0.25);
    cr_log_info("clamped sheet: %d iters, KKT %g/%g, amax %.3g mm, L_eff %.1f mm, k %.1f vs CM %.1f rad/m (%.2f mm vs %.2f mm), "
                "folds %d",
                ss.iterations, ss.kkt, ss.kkt0, 1e3 * amax, 1e3 * PI * sqrt(s2 / d2), ksum / wsum, kpred,
                2e3 * PI / (ksum / wsum), 2e3 * PI / kpred, wr_wf_count_folds(&wf, a, om));
    /* measured 408.1 vs 407.4 rad/m (0.2 %) */
    cr_assert(fabs(ksum / wsum / kpred - 1.0) < 0.03, "k %g vs Cerda-Mahadevan %g", ksum / wsum, kpred);
    wr_wf_set_amplitude_zero(&wf, NULL);
    for (v = 0; v < m.nv; ++v) cr_assert_eq(wf.azero[v], 0);
    free(xs);
    free(as);
    free(base);
    free(a);
    free(om);
    free(curl);
    free(az);
    wr_wf_free(&wf);
    wr_mesh_free(&m);
}

/* A zig-zag phase (φ = 2.5 on odd grid rows, 0 on even ones) is curl free and, face by face, has the
 * same |dφ| as the monotone φ = 2.5·row: the fold E_wf cannot see. wr_wf_count_folds must find it and
 * wr_wf_unfold must return the monotone one-form (up to a global sign) with no folds. */
Test(wrinkle_field, unfold_turns_zigzag_phase_monotone) {
    const double L = 0.1, Hh = 0.05;
    const int32_t nx = 8, ny = 6;
    wr_mesh m;
    wr_wf wf;
    wr_wf_material mat = material();
    double *a, *om, *mono, dy = Hh / ny, sgn = 0.0, E0 = 0.0, E1 = 0.0;
    int32_t v, e, nf0, nf1;
    cr_assert_eq(wr_mesh_rectangle(&m, L, Hh, nx, ny, NULL), WR_OK);
    cr_assert_eq(wr_wf_create(&wf, &m, NULL, &mat, NULL), WR_OK);
    a = (double *)malloc(sizeof(double) * m.nv);
    om = (double *)malloc(sizeof(double) * m.ne);
    mono = (double *)malloc(sizeof(double) * m.ne);
    for (v = 0; v < m.nv; ++v) a[v] = 1e-3;
    for (e = 0; e < m.ne; ++e) {
        int32_t r0 = (int32_t)floor(m.pos[3 * m.edges[2 * e] + 1] / dy + 0.5);
        int32_t r1 = (int32_t)floor(m.pos[3 * m.edges[2 * e + 1] + 1] / dy + 0.5);
        om[e] = 2.5 * ((r1 % 2) - (r0 % 2));
        mono[e] = 2.5 * (r1 - r0);
    }
    nf0 = wr_wf_count_folds(&wf, a, om);
    cr_assert(nf0 >= nx, "zig-zag has %d fold edges", nf0);
    cr_assert_eq(wr_wf_count_folds(&wf, a, mono), 0);
    cr_assert_eq(wr_wf_energy(&wf, a, om, &E0, NULL, NULL, NULL, NULL), WR_OK);
    cr_assert_eq(wr_wf_unfold(&wf, a, om, NULL), WR_OK);
    nf1 = wr_wf_count_folds(&wf, a, om);
    cr_assert_eq(nf1, 0);
    for (e = 0; e < m.ne; ++e) {
        if (sgn == 0.0 && mono[e] != 0.0) sgn = om[e] / mono[e] > 0.0 ? 1.0 : -1.0;
        cr_assert(fabs(om[e] - sgn * mono[e]) < 1e-9, "edge %d: %g vs %g", e, om[e], sgn * mono[e]);
    }
    /* the energy is blind to the fold: same E before and after (the point of the fold counter) */
    cr_assert_eq(wr_wf_energy(&wf, a, om, &E1, NULL, NULL, NULL, NULL), WR_OK);
    cr_log_info("zig-zag: %d folds -> %d, E %.12g vs %.12g", nf0, nf1, E0, E1);
    cr_assert(fabs(E1 - E0) <= 1e-9 * fabs(E0), "E %g vs %g", E1, E0);
    free(a);
    free(om);
    free(mono);
    wr_wf_free(&wf);
    wr_mesh_free(&m);
}

/* A fold is a reversal of dφ's direction, whatever its length: the count of the zig-zag above must not
 * change when the phase steps are scaled from 2.5 rad per row (|dφ| = 300 rad/m) down to 2.5e-4 rad
 * (0.03 rad/m, dφ·dφ' ~ −1e-3 (rad/m)²) or up to 2.5e4 rad. Kills a fold test `dot < −tol` with a
 * dimensional tolerance (the suite's fields have |dφ| ~ 1e2–1e3 rad/m, where such a tolerance hides). */
Test(wrinkle_field, fold_count_does_not_depend_on_the_wave_number) {
    const double L = 0.1, Hh = 0.05, scales[3] = {1e-4, 1.0, 1e4};
    const int32_t nx = 8, ny = 6;
    wr_mesh m;
    wr_wf wf;
    wr_wf_material mat = material();
    double *a, *om, dy = Hh / ny;
    int32_t v, e, k, n[3];
    cr_assert_eq(wr_mesh_rectangle(&m, L, Hh, nx, ny, NULL), WR_OK);
    cr_assert_eq(wr_wf_create(&wf, &m, NULL, &mat, NULL), WR_OK);
    a = (double *)malloc(sizeof(double) * m.nv);
    om = (double *)malloc(sizeof(double) * m.ne);
    for (v = 0; v < m.nv; ++v) a[v] = 1e-3;
    for (k = 0; k < 3; ++k) {
        for (e = 0; e < m.ne; ++e) {
            int32_t r0 = (int32_t)floor(m.pos[3 * m.edges[2 * e] + 1] / dy + 0.5);
            int32_t r1 = (int32_t)floor(m.pos[3 * m.edges[2 * e + 1] + 1] / dy + 0.5);
            om[e] = scales[k] * 2.5 * ((r1 % 2) - (r0 % 2));
        }
        n[k] = wr_wf_count_folds(&wf, a, om);
    }
    cr_log_info("zig-zag fold counts at phase steps 2.5e-4, 2.5, 2.5e4 rad: %d %d %d", n[0], n[1], n[2]);
    cr_assert(n[1] >= nx, "zig-zag has %d fold edges", n[1]);
    cr_assert_eq(n[0], n[1], "small |dphi|: %d folds vs %d", n[0], n[1]);
    cr_assert_eq(n[2], n[1], "large |dphi|: %d folds vs %d", n[2], n[1]);
    free(a);
    free(om);
    wr_wf_free(&wf);
    wr_mesh_free(&m);
}
