/* Tests for wrinkle/tfw.h's ON OUTCOMES guards: a slack base is refused (or solved on request), a
 * base with no compression says nothing wrinkles, a compressed-and-stretched base wrinkles, and a
 * barely compressed coarse base returns the flat outcome. Bases are affine maps of a flat rectangle,
 * so the Eq. 29 strain of every face is known in closed form: base = diag(sx, sy) × rest gives
 * eigenvalues sx² − 1 and sy² − 1. */
#include <criterion/criterion.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "wrinkle/tfw.h"

/* the rectangle mapped by x → sx·x, y → sy·y (flat, so II_b = 0) */
static double *affine_base(const wr_mesh *m, double sx, double sy) {
    double *x = (double *)malloc(sizeof(double) * 3 * (size_t)m->nv);
    int32_t v;
    cr_assert_not_null(x);
    for (v = 0; v < m->nv; ++v) {
        x[3 * v] = sx * m->pos[3 * v];
        x[3 * v + 1] = sy * m->pos[3 * v + 1];
        x[3 * v + 2] = 0.0;
    }
    return x;
}

static wr_wf_material material(double h) {
    wr_wf_material mat;
    mat.young = 1e6;
    mat.poisson = 0.3;
    mat.thickness = h;
    return mat;
}

static wr_tfw_desc quick_desc(void) {
    wr_tfw_desc td;
    memset(&td, 0, sizeof td);
    td.solve.max_iter = 200;
    td.no_upsample = 1;
    return td;
}

Test(tfw_outcome, slack_base_is_refused_with_the_reason_and_solved_on_request) {
    wr_mesh m;
    wr_wf_material mat = material(1e-4);
    wr_tfw_desc td = quick_desc();
    wr_tfw_result r;
    wr_diag d;
    double *x;
    wr_status st;
    cr_assert_eq(wr_mesh_rectangle(&m, 0.2, 0.1, 10, 5, NULL), WR_OK);
    x = affine_base(&m, 0.9, 0.9); /* compressed 10 % both ways: eigenvalues -0.19, -0.19 */
    st = wr_tfw_fields(&m, x, &mat, &td, &r, &d);
    cr_assert_eq(st, WR_ERR_DOMAIN, "slack base: %s", wr_status_string(st));
    cr_assert_eq(r.outcome, WR_TFW_SLACK);
    cr_assert_eq(r.n_slack, m.nf);
    cr_assert_eq(r.n_compressed, m.nf);
    cr_assert_not_null(strstr(d.message, "slack base"), "message names the cause: %s", d.message);
    cr_assert_null(r.a, "a refused run returns no fields");
    td.allow_slack = 1;
    st = wr_tfw_fields(&m, x, &mat, &td, &r, &d);
    cr_assert(st == WR_OK || st == WR_ERR_NOT_CONVERGED, "allow_slack solves: %s", wr_status_string(st));
    cr_assert_eq(r.outcome, WR_TFW_SLACK);
    cr_assert_not_null(r.a);
    wr_tfw_result_free(&r);
    free(x);
    wr_mesh_free(&m);
}

Test(tfw_outcome, no_compression_means_nothing_wrinkles) {
    wr_mesh m;
    wr_wf_material mat = material(1e-4);
    wr_tfw_desc td = quick_desc();
    wr_tfw_result r;
    double *x;
    cr_assert_eq(wr_mesh_rectangle(&m, 0.2, 0.1, 10, 5, NULL), WR_OK);
    x = affine_base(&m, 1.05, 1.02); /* stretched both ways: nothing is compressed */
    cr_assert_eq(wr_tfw_fields(&m, x, &mat, &td, &r, NULL), WR_OK);
    cr_assert_eq(r.outcome, WR_TFW_NO_COMPRESSION);
    cr_assert_eq(r.n_compressed, 0);
    cr_assert_eq(r.n_wrinkle_free, m.nf);
    cr_assert_eq(r.max_amplitude, 0.0);
    cr_assert_not_null(strstr(wr_tfw_outcome_reason(r.outcome), "nothing wrinkles"));
    wr_tfw_result_free(&r);
    free(x);
    wr_mesh_free(&m);
}

/* Compressed 4 % along x, stretched 4 % along y, h = 0.1 mm: wrinkles of amplitude ~ (λ/π) sqrt(ε)
 * ≫ 1 % of h (WRINKLED; a flat threshold set too high fails here). At 1e-6 compression the bending
 * cost wins and the SQP returns a = 0 on every vertex (FLAT, although every face is compressed). */
Test(tfw_outcome, compressed_and_stretched_base_wrinkles_barely_compressed_is_flat) {
    wr_mesh m;
    wr_wf_material mat = material(1e-4);
    wr_tfw_desc td = quick_desc();
    wr_tfw_result r;
    double *x;
    wr_status st;
    cr_assert_eq(wr_mesh_rectangle(&m, 0.2, 0.1, 20, 10, NULL), WR_OK);
    x = affine_base(&m, 0.96, 1.04);
    st = wr_tfw_fields(&m, x, &mat, &td, &r, NULL);
    cr_assert(st == WR_OK || st == WR_ERR_NOT_CONVERGED, "%s", wr_status_string(st));
    cr_assert_eq(r.outcome, WR_TFW_WRINKLED, "outcome %d, max a %g m", (int)r.outcome, r.max_amplitude);
    cr_assert_eq(r.n_slack, 0);
    cr_assert_gt(r.max_amplitude, 1e-2 * mat.thickness);
    wr_tfw_result_free(&r);
    free(x);
    x = affine_base(&m, 1.0 - 1e-6, 1.04);
    st = wr_tfw_fields(&m, x, &mat, &td, &r, NULL);
    cr_assert(st == WR_OK || st == WR_ERR_NOT_CONVERGED, "%s", wr_status_string(st));
    cr_assert_eq(r.n_compressed, m.nf);
    cr_assert_eq(r.outcome, WR_TFW_FLAT, "outcome %d, max a %g m", (int)r.outcome, r.max_amplitude);
    wr_tfw_result_free(&r);
    free(x);
    wr_mesh_free(&m);
}

#include "scene.h"

static int cmp_dbl(const void *a, const void *b) {
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* median of 2π / |∇φ| [m] over faces with mean corner amplitude >= 0.2 max a; ∇φ from the phase
 * changes along the face's edges 0→1, 0→2 on the surface pos (ω from edges[2e] to edges[2e+1]) */
static double median_wavelength(const wr_mesh *m, const double *pos, const double *a, const double *omega) {
    double amax = 0.0, *lam = (double *)malloc(sizeof(double) * (size_t)m->nf), med;
    int32_t f, v, n = 0;
    cr_assert_not_null(lam);
    for (v = 0; v < m->nv; ++v) amax = fmax(amax, a[v]);
    for (f = 0; f < m->nf; ++f) {
        const int32_t *fv = m->faces + 3 * f;
        double d[2], e[2][3], g11 = 0, g12 = 0, g22 = 0, det, c1, c2, gg;
        int k, i;
        if ((a[fv[0]] + a[fv[1]] + a[fv[2]]) / 3.0 < 0.2 * amax) continue;
        for (k = 0; k < 2; ++k) { /* corner 0 → corner k+1: the edge opposite corner 2-k */
            int32_t ed = m->face_edges[3 * f + 2 - k];
            d[k] = m->edges[2 * ed] == fv[0] ? omega[ed] : -omega[ed];
            for (i = 0; i < 3; ++i) e[k][i] = pos[3 * fv[k + 1] + i] - pos[3 * fv[0] + i];
        }
        for (i = 0; i < 3; ++i) {
            g11 += e[0][i] * e[0][i];
            g12 += e[0][i] * e[1][i];
            g22 += e[1][i] * e[1][i];
        }
        det = g11 * g22 - g12 * g12;
        c1 = (g22 * d[0] - g12 * d[1]) / det;
        c2 = (g11 * d[1] - g12 * d[0]) / det;
        gg = c1 * c1 * g11 + 2.0 * c1 * c2 * g12 + c2 * c2 * g22;
        if (gg > 0.0) lam[n++] = 2.0 * 3.14159265358979323846 / sqrt(gg);
    }
    cr_assert_gt(n, 0);
    qsort(lam, (size_t)n, sizeof(double), cmp_dbl);
    med = lam[n / 2];
    free(lam);
    return med;
}

/* Regression (found by the demo): on a Poisson–Delaunay stretched sheet at the fabric's r = 6.46 mm
 * (789 vertices) the SQP collapsed onto the flat saddle a ≈ 0 and stopped by rule 1 after 3
 * iterations (max a 0.14 µm, "nothing wrinkles"), while the same sheet on a grid wrinkles with 7.7
 * periods. The flat-stop escape (wrinkle_field.h wr__wf_sqp_flat) must find the wrinkles: periods
 * across the width within ±1 of the grid's 7.7 (the meshes differ) and an amplitude of the grid's
 * order (0.35 mm). */
Test(tfw_outcome, delaunay_sheet_escapes_the_flat_stop, .timeout = 120) {
    static const char scene_json[] =
        "{\"name\": \"del\", \"mesh\": {\"type\": \"delaunay_rectangle\", \"width\": 0.25, \"height\": 0.1,"
        " \"resolution\": 0.0064578, \"seed\": 1},"
        " \"material\": {\"young\": 1.0e6, \"poisson\": 0.5, \"thickness\": 1.0e-4, \"density\": 0},"
        " \"boundary\": [{\"name\": \"left\", \"box\": {\"min\": [-1e-9, -1, -1], \"max\": [1e-9, 1, 1]}},"
        " {\"name\": \"right\", \"box\": {\"min\": [0.249999999, -1, -1], \"max\": [1, 1, 1]},"
        " \"center\": [0, 0, 0], \"stretch\": [1.1278, 1, 1]}],"
        " \"solver\": {\"linear\": \"cholmod\", \"load_steps\": 4, \"grad_tol\": 1e-8, \"max_iter\": 200,"
        " \"hessian\": \"projected\"}}";
    wr_scene sc;
    wr_scene_run run;
    wr_wf_material mat = material(1e-4);
    wr_tfw_desc td = quick_desc();
    wr_tfw_result r;
    wr_diag d;
    wr_status st;
    double lam;
    cr_assert_eq(wr_scene_parse(&sc, scene_json, sizeof scene_json - 1, ".", &d), WR_OK, "%s", d.message);
    sc.shell.membrane = WR_MEMBRANE_TFT; /* TFW Sec. 4.1 base, as wrinkle-tfw sets it */
    sc.shell.bending = WR_BENDING_QUADRATIC;
    cr_assert_eq(wr_scene_run_create(&run, &sc, &d), WR_OK, "%s", d.message);
    st = wr_scene_run_solve(&run, NULL, NULL, &d);
    cr_assert(st == WR_OK || st == WR_ERR_NOT_CONVERGED, "base: %s", d.message);
    mat.young = 1e6;
    mat.poisson = 0.5;
    td.solve.max_iter = 0; /* the default budget */
    st = wr_tfw_fields(&run.mesh, run.x, &mat, &td, &r, &d);
    cr_assert(st == WR_OK || st == WR_ERR_NOT_CONVERGED, "%s", wr_status_string(st));
    cr_assert_eq(r.outcome, WR_TFW_WRINKLED, "outcome %d, max a %g m after %d SQP iterations", (int)r.outcome,
                 r.max_amplitude, (int)r.sqp.iterations);
    cr_assert_gt(r.max_amplitude, 0.1e-3, "max a %g m", r.max_amplitude);
    cr_assert_lt(r.max_amplitude, 1.0e-3, "max a %g m", r.max_amplitude);
    /* wavelength: median over visibly wrinkled faces (mean a >= 0.2 max a) of 2π / |∇φ| on the base,
     * against the grid's 12.9 mm (validation/results/tfw_stretched_sheet.json) ± 15 % (mesh kinds) */
    lam = median_wavelength(&run.mesh, run.x, r.a, r.omega);
    cr_assert(lam > 0.85 * 12.9e-3 && lam < 1.15 * 12.9e-3, "median wavelength %g mm", 1e3 * lam);
    wr_tfw_result_free(&r);
    wr_scene_run_free(&run);
    wr_scene_free(&sc);
}
