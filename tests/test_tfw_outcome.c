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
