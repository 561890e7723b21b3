/* tests/test_statics.c — statics.h: Newton converges to a known homogeneous equilibrium, to a
 * stationary point under gravity (TFT + quadratic bending and StVK + mid-edge), error paths. */
#include <criterion/criterion.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "wrinkle/statics.h"

static int st_progress_calls;
static void st_progress(void *user, const wr_statics_stats *s) {
    (void)user;
    (void)s;
    st_progress_calls++;
}

/* All boundary vertices prescribed on a uniform in-plane deformation F; interior vertices start
 * perturbed. The unique equilibrium (convex near the solution, zero bending, homogeneous strain)
 * puts every interior vertex at F·X. */
Test(statics, prescribed_boundary_homogeneous_stretch) {
    wr_mesh m;
    wr_shell s;
    wr_shell_desc d;
    wr_statics_desc sd;
    wr_statics_stats st;
    wr_diag dg;
    int32_t nx = 6, ny = 5, v, i, j;
    uint8_t *fixed;
    double *x, *target, err = 0.0;
    int mm;
    cr_assert_eq(wr_mesh_rectangle(&m, 1.0, 0.8, nx, ny, NULL), WR_OK);
    fixed = (uint8_t *)calloc((size_t)m.nv, 1);
    x = (double *)malloc(sizeof(double) * 3 * m.nv);
    target = (double *)malloc(sizeof(double) * 3 * m.nv);
    for (mm = 0; mm < 2; ++mm) {
        memset(&d, 0, sizeof d);
        d.young = 1e5;
        d.poisson = 0.3;
        d.thickness = 1e-3;
        d.membrane = (wr_membrane_model)mm;
        d.bending = mm ? WR_BENDING_QUADRATIC : WR_BENDING_MIDEDGE;
        cr_assert_eq(wr_shell_create(&s, &m, &d, NULL), WR_OK);
        for (j = 0; j <= ny; ++j)
            for (i = 0; i <= nx; ++i) {
                v = j * (nx + 1) + i;
                fixed[v] = (i == 0 || j == 0 || i == nx || j == ny);
                target[3 * v] = 1.1 * m.rest[2 * v] + 0.05 * m.rest[2 * v + 1];
                target[3 * v + 1] = 1.05 * m.rest[2 * v + 1];
                target[3 * v + 2] = 0.0;
                x[3 * v] = m.rest[2 * v];
                x[3 * v + 1] = m.rest[2 * v + 1];
                x[3 * v + 2] = 0.0;
            }
        memset(&sd, 0, sizeof sd);
        sd.fixed = fixed;
        sd.target = target;
        sd.perturb = 1e-3;
        sd.seed = 3;
        sd.progress = st_progress;
        st_progress_calls = 0;
        cr_assert_eq(wr_statics_solve(&s, x, &sd, &st, &dg), WR_OK, "%s", dg.message);
        err = 0.0;
        for (i = 0; i < 3 * m.nv; ++i) err = fmax(err, fabs(x[i] - target[i]));
        cr_expect(err < 1e-9, "model %d: max deviation from F·X %.3e after %d steps", mm, err, st.iterations);
        cr_expect_eq(st.stop, WR_STATICS_STOP_GRADIENT);
        cr_expect(st.iterations < 30, "model %d: %d Newton steps", mm, st.iterations);
        cr_expect_eq(st_progress_calls, st.iterations);
        cr_expect(st.t_total >= st.t_linear && st.t_linear >= 0.0);
        wr_shell_free(&s);
    }
    free(fixed);
    free(x);
    free(target);
    wr_mesh_free(&m);
}

/* A sheet pinned along one edge hangs under gravity: the solve must reach the relative gradient
 * tolerance, lower the potential, and leave the pinned vertices untouched. */
Test(statics, hanging_sheet_under_gravity) {
    wr_mesh m;
    wr_shell s;
    wr_shell_desc d;
    wr_statics_desc sd;
    wr_statics_stats st;
    wr_diag dg;
    int32_t nx = 6, ny = 6, v, i;
    uint8_t *fixed;
    double *x, *x0;
    int mm;
    cr_assert_eq(wr_mesh_rectangle(&m, 0.3, 0.3, nx, ny, NULL), WR_OK);
    fixed = (uint8_t *)calloc((size_t)m.nv, 1);
    x = (double *)malloc(sizeof(double) * 3 * m.nv);
    x0 = (double *)malloc(sizeof(double) * 3 * m.nv);
    for (i = 0; i <= nx; ++i) fixed[ny * (nx + 1) + i] = 1; /* top edge y = 0.3 */
    for (mm = 0; mm < 2; ++mm) {
        double E0;
        memset(&d, 0, sizeof d);
        d.young = 1e5;
        d.poisson = 0.3;
        d.thickness = 5e-4;
        d.density = 300.0;
        d.membrane = mm ? WR_MEMBRANE_TFT : WR_MEMBRANE_STVK;
        d.bending = mm ? WR_BENDING_QUADRATIC : WR_BENDING_MIDEDGE;
        cr_assert_eq(wr_shell_create(&s, &m, &d, NULL), WR_OK);
        /* hang it vertically: rest (u, v) → (u, v, 0) rotated so y is up */
        for (v = 0; v < m.nv; ++v) {
            x[3 * v] = m.rest[2 * v];
            x[3 * v + 1] = 0.0;
            x[3 * v + 2] = m.rest[2 * v + 1];
        }
        memcpy(x0, x, sizeof(double) * 3 * m.nv);
        memset(&sd, 0, sizeof sd);
        sd.gravity[2] = -9.81;
        sd.fixed = fixed;
        sd.perturb = 1e-4;
        sd.seed = 1;
        sd.grad_tol = 1e-7;
        cr_assert_eq(wr_statics_solve(&s, x, &sd, &st, &dg), WR_OK, "model %d: %s", mm, dg.message);
        cr_expect(st.grad_norm <= 1e-7 * st.grad_ref || st.stop == WR_STATICS_STOP_STEP, "model %d: |g| %.3e ref %.3e",
                  mm, st.grad_norm, st.grad_ref);
        E0 = 0.0;
        for (v = 0; v < m.nv; ++v) {
            if (fixed[v])
                for (i = 0; i < 3; ++i) cr_expect_eq(x[3 * v + i], x0[3 * v + i]);
            E0 += x[3 * v + 2] - x0[3 * v + 2];
        }
        cr_expect(E0 < 0.0, "the sheet must sag (mean dz %g)", E0 / m.nv);
        {
            /* Π(x0) = −Σ m_v g·x_v (no strain at the start) */
            double *mass = (double *)malloc(sizeof(double) * m.nv), Pi0 = 0.0;
            wr_shell_vertex_masses(&s, mass);
            for (v = 0; v < m.nv; ++v) Pi0 += mass[v] * 9.81 * x0[3 * v + 2];
            cr_expect(st.energy < Pi0, "potential must drop: %g vs start %g", st.energy, Pi0);
            free(mass);
        }
        wr_shell_free(&s);
    }
    free(fixed);
    free(x);
    free(x0);
    wr_mesh_free(&m);
}

Test(statics, error_paths_and_not_converged) {
    wr_mesh m;
    wr_shell s;
    wr_shell_desc d;
    wr_statics_desc sd;
    wr_statics_stats st;
    wr_diag dg;
    double *x;
    uint8_t *fixed;
    int32_t v;
    cr_assert_eq(wr_mesh_rectangle(&m, 0.3, 0.3, 4, 4, NULL), WR_OK);
    memset(&d, 0, sizeof d);
    d.young = 1e5;
    d.poisson = 0.3;
    d.thickness = 5e-4;
    d.density = 300.0;
    cr_assert_eq(wr_shell_create(&s, &m, &d, NULL), WR_OK);
    x = (double *)malloc(sizeof(double) * 3 * m.nv);
    fixed = (uint8_t *)calloc((size_t)m.nv, 1);
    fixed[0] = fixed[4] = 1;
    memcpy(x, m.pos, sizeof(double) * 3 * m.nv);
    cr_expect_eq(wr_statics_solve(NULL, x, NULL, &st, &dg), WR_ERR_INVALID_ARG);
    cr_expect_eq(wr_statics_solve(&s, NULL, NULL, &st, &dg), WR_ERR_INVALID_ARG);
    memset(&sd, 0, sizeof sd);
    sd.grad_tol = -1.0;
    cr_expect_eq(wr_statics_solve(&s, x, &sd, &st, &dg), WR_ERR_INVALID_ARG);
    memset(&sd, 0, sizeof sd);
    x[5] = NAN;
    cr_expect_eq(wr_statics_solve(&s, x, &sd, &st, &dg), WR_ERR_DOMAIN);
    cr_expect_eq(dg.item, 1);
    memcpy(x, m.pos, sizeof(double) * 3 * m.nv);
    /* two Newton steps are not enough to hang a sheet: NOT_CONVERGED, best iterate kept */
    sd.fixed = fixed;
    sd.gravity[2] = -9.81;
    sd.max_iter = 2;
    sd.perturb = 1e-4;
    cr_expect_eq(wr_statics_solve(&s, x, &sd, &st, &dg), WR_ERR_NOT_CONVERGED);
    cr_expect_eq(st.stop, WR_STATICS_STOP_MAX_ITER);
    cr_expect_eq(st.iterations, 2);
    for (v = 0; v < 3 * m.nv; ++v) cr_expect(isfinite(x[v]));
    cr_expect(st.energy < 0.0);
    wr_shell_free(&s);
    free(x);
    free(fixed);
    wr_mesh_free(&m);
}

/* ---- fast PSD projection ------------------------------------------------------------------------ */

/* wr_statics_project_spd against core's Jacobi projection on random symmetric matrices of the sizes
 * the solver sees (9 = membrane face, 18 = mid-edge stencil, 30 = large); PSD input kept as is. */
Test(statics, fast_projection_matches_jacobi) {
    wr_rng r;
    int sizes[3] = {9, 18, 30}, si, rep, i, j;
    wr_rng_seed(&r, 11);
    for (si = 0; si < 3; ++si) {
        int n = sizes[si];
        for (rep = 0; rep < 20; ++rep) {
            double A[900], B[900], C[900], lam[30], nrm = 0.0, err = 0.0;
            int raised;
            for (i = 0; i < n; ++i)
                for (j = 0; j <= i; ++j) A[i * n + j] = A[j * n + i] = wr_rng_normal(&r) + (i == j ? 0.5 * rep : 0.0);
            if (rep == 0) /* a block with a null space and clustered eigenvalues: Bᵀ B, B 3×n */
                for (i = 0; i < n; ++i)
                    for (j = 0; j < n; ++j) A[i * n + j] = (double)((i % 3) == (j % 3));
            memcpy(B, A, sizeof(double) * n * n);
            memcpy(C, A, sizeof(double) * n * n);
            wr_dense_project_spd(n, B, 0.0);
            raised = wr_statics_project_spd(n, C, 0.0);
            for (i = 0; i < n * n; ++i) {
                nrm = fmax(nrm, fabs(A[i]));
                err = fmax(err, fabs(B[i] - C[i]));
            }
            cr_expect(err <= 1e-12 * nrm, "n %d rep %d: fast vs Jacobi %.3e (|A| %.3e)", n, rep, err, nrm);
            wr_dense_sym_eig(n, C, lam, NULL);
            cr_expect(lam[0] >= -1e-12 * nrm, "n %d rep %d: projected min eigenvalue %.3e", n, rep, lam[0]);
            if (rep == 0) cr_expect_eq(raised, 0, "a PSD block must pass the Cholesky test unchanged");
        }
    }
    {
        /* floor > 0 raises every eigenvalue below it */
        double A[4] = {1.0, 0.0, 0.0, -2.0}, lam[2];
        cr_expect_eq(wr_statics_project_spd(2, A, 0.5), 1);
        wr_dense_sym_eig(2, A, lam, NULL);
        cr_expect(fabs(lam[0] - 0.5) < 1e-14 && fabs(lam[1] - 1.0) < 1e-14);
    }
}

/* ---- pressure ------------------------------------------------------------------------------------ */

Test(statics, pressure_element_fd) {
    wr_rng r;
    double x[9], o[3] = {0.1, -0.2, 0.05}, g[9], H[81], gp[9], gm[9], h = 1e-6, p = 1234.5, E0;
    int i, j;
    wr_rng_seed(&r, 5);
    for (i = 0; i < 9; ++i) x[i] = wr_rng_normal(&r);
    E0 = wr_statics_pressure_element(x, o, p, g, H);
    {
        /* −p·V_f by the determinant */
        double a[3], b[3], c[3], V;
        for (i = 0; i < 3; ++i) {
            a[i] = x[i] - o[i];
            b[i] = x[3 + i] - o[i];
            c[i] = x[6 + i] - o[i];
        }
        V = (a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) + a[2] * (b[0] * c[1] - b[1] * c[0])) / 6.0;
        cr_expect(fabs(E0 + p * V) <= 1e-12 * fabs(p * V));
    }
    for (i = 0; i < 9; ++i) {
        double xp[9], xm[9], fd;
        memcpy(xp, x, sizeof x);
        memcpy(xm, x, sizeof x);
        xp[i] += h;
        xm[i] -= h;
        fd = (wr_statics_pressure_element(xp, o, p, gp, NULL) - wr_statics_pressure_element(xm, o, p, gm, NULL)) / (2 * h);
        cr_expect(fabs(fd - g[i]) <= 1e-6 * (1.0 + fabs(g[i])), "grad %d: %g vs fd %g", i, g[i], fd);
        for (j = 0; j < 9; ++j) {
            double fdh = (gp[j] - gm[j]) / (2 * h);
            cr_expect(fabs(fdh - H[j * 9 + i]) <= 1e-6 * (1.0 + fabs(H[j * 9 + i])), "H(%d,%d) %g vs fd %g", j, i,
                      H[j * 9 + i], fdh);
        }
    }
    for (i = 0; i < 9; ++i) cr_expect_eq(H[i * 9 + i], 0.0); /* zero diagonal blocks: indefinite */
}

/* Two disks sewn along their rim: closed, genus 0, outward (V > 0, origin-free), each face keeps
 * its flat rest triangle; the volume gradient is the FD gradient. */
Test(statics, pillow_weld_and_volume) {
    wr_mesh disk, bal;
    wr_shell s;
    wr_shell_desc d;
    wr_mesh_quality_stats q;
    double o1[3] = {0, 0, 0}, o2[3] = {3.0, -1.0, 2.0}, V1, V2, *g, *ar0, *ar1;
    int32_t nb, f, i;
    cr_assert_eq(wr_mesh_disk(&disk, 0.1, 3, NULL), WR_OK);
    nb = disk.loop_start[disk.n_loops];
    cr_assert_eq(wr_mesh_pillow(&bal, &disk, 0.02, NULL), WR_OK);
    cr_expect_eq(bal.nv, 2 * disk.nv - nb);
    cr_expect_eq(bal.nf, 2 * disk.nf);
    wr_mesh_quality(&bal, 0, &q);
    cr_expect_eq(q.n_loops, 0);
    cr_expect_eq(q.euler, 2);
    cr_expect_eq(q.n_inverted, 0);
    cr_assert(bal.corner_rest != NULL && bal.face_panel != NULL);
    ar0 = (double *)malloc(sizeof(double) * disk.nf);
    ar1 = (double *)malloc(sizeof(double) * bal.nf);
    wr_mesh_face_areas(&disk, 1, ar0);
    wr_mesh_face_areas(&bal, 1, ar1);
    for (f = 0; f < disk.nf; ++f) {
        cr_expect(fabs(ar1[f] - ar0[f]) < 1e-15 && fabs(ar1[disk.nf + f] - ar0[f]) < 1e-15, "face %d rest area", f);
        cr_expect_eq(bal.face_panel[f], 0);
        cr_expect_eq(bal.face_panel[disk.nf + f], 1);
    }
    memset(&d, 0, sizeof d);
    d.young = 1e6;
    d.poisson = 0.3;
    d.thickness = 1e-4;
    cr_assert_eq(wr_shell_create(&s, &bal, &d, NULL), WR_OK);
    g = (double *)malloc(sizeof(double) * 3 * bal.nv);
    V1 = wr_statics_volume(&s, bal.pos, o1, g);
    V2 = wr_statics_volume(&s, bal.pos, o2, NULL);
    cr_expect(V1 > 0.0, "outward orientation gives V > 0 (%g)", V1);
    cr_expect(fabs(V1 - V2) <= 1e-14, "closed surface: V independent of the origin (%.17g vs %.17g)", V1, V2);
    for (i = 0; i < 3 * bal.nv; i += 7) {
        double keep = bal.pos[i], h = 1e-7, Vp, Vm;
        bal.pos[i] = keep + h;
        Vp = wr_statics_volume(&s, bal.pos, o1, NULL);
        bal.pos[i] = keep - h;
        Vm = wr_statics_volume(&s, bal.pos, o1, NULL);
        bal.pos[i] = keep;
        cr_expect(fabs((Vp - Vm) / (2 * h) - g[i]) <= 1e-8, "dV/dx[%d] %g vs fd %g", i, g[i], (Vp - Vm) / (2 * h));
    }
    wr_shell_free(&s);
    free(g);
    free(ar0);
    free(ar1);
    wr_mesh_free(&bal);
    wr_mesh_free(&disk);
}

/* Mylar-balloon-like inflation: two sewn disks under increasing pressure, each solve warm-started
 * from the previous one: every solve converges and the volume grows monotonically with p. */
Test(statics, sewn_disks_inflate_monotonically) {
    wr_mesh disk, bal;
    wr_shell s;
    wr_shell_desc d;
    wr_statics_desc sd;
    wr_statics_stats st;
    wr_diag dg;
    double ps[4] = {200.0, 400.0, 800.0, 1600.0}, Vprev = 0.0, *x;
    int k, mm;
    cr_assert_eq(wr_mesh_disk(&disk, 0.1, 4, NULL), WR_OK);
    cr_assert_eq(wr_mesh_pillow(&bal, &disk, 0.01, NULL), WR_OK);
    x = (double *)malloc(sizeof(double) * 3 * bal.nv);
    for (mm = 0; mm < 2; ++mm) {
        memset(&d, 0, sizeof d);
        d.young = 1e7;
        d.poisson = 0.44;
        d.thickness = 1e-4;
        d.membrane = mm ? WR_MEMBRANE_TFT : WR_MEMBRANE_STVK;
        d.bending = WR_BENDING_MIDEDGE;
        cr_assert_eq(wr_shell_create(&s, &bal, &d, &dg), WR_OK, "%s", dg.message);
        memcpy(x, bal.pos, sizeof(double) * 3 * bal.nv);
        Vprev = 0.0;
        for (k = 0; k < 4; ++k) {
            memset(&sd, 0, sizeof sd);
            sd.pressure = ps[k];
            sd.grad_tol = 1e-8;
            cr_assert_eq(wr_statics_solve(&s, x, &sd, &st, &dg), WR_OK, "model %d p %g: %s", mm, ps[k], dg.message);
            cr_expect(st.volume > Vprev, "model %d: V(%g Pa) = %.6e must exceed %.6e", mm, ps[k], st.volume, Vprev);
            Vprev = st.volume;
        }
        wr_shell_free(&s);
    }
    free(x);
    wr_mesh_free(&bal);
    wr_mesh_free(&disk);
}
