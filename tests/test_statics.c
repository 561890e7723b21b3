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
