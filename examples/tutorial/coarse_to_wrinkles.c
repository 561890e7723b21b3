/* Tutorial walk 2 — from a coarse mesh to wrinkles (TFW: Chen et al. 2021). docs/tutorial-2-coarse-to-
 * wrinkles.md explains every step; each prints a number you can check against the text.
 *
 *   cc -std=c11 -O2 -Iinclude -I/usr/include/suitesparse -DWR_USE_CHOLMOD=1 \
 *      examples/tutorial/coarse_to_wrinkles.c -o coarse_to_wrinkles -lcholmod -lfftw3 -lm
 *
 * The sheet is the stretched-sheet experiment of TFW Sec. 6.4 / Style3D Fig. 16: 0.25 m × 0.1 m,
 * h = 0.1 mm, E = 1 MPa, ν = 0.5, short edges clamped and pulled apart by 12.78 %.
 */
#define WRINKLE_IMPLEMENTATION
#include "wrinkle/wrinkle.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#define CHECK(call)                                                   \
    do {                                                              \
        wr_status st_ = (call);                                       \
        if (st_ != WR_OK && st_ != WR_ERR_NOT_CONVERGED) {            \
            fprintf(stderr, "%s failed: %s\n", #call, d.message);     \
            return 1;                                                 \
        }                                                             \
    } while (0)

int main(void) {
    const double W = 0.25, H = 0.10, young = 1e6, nu = 0.5, h = 1e-4, strain = 0.1278;
    wr_diag d;
    wr_mesh m;
    wr_shell shell;
    wr_shell_desc sd;
    wr_statics_desc st;
    wr_statics_stats ss;
    wr_motion mo[2];
    wr_wf_material mat;
    wr_tfw_result r;
    int32_t *left, *right, nl = 0, nr = 0, v, k;
    double *x, amax = 0.0;

    /* Step 1 — a coarse base mesh: 29 × 18 = 522 vertices, as in the paper. */
    CHECK(wr_mesh_rectangle(&m, W, H, 28, 17, &d));
    printf("step 1  base mesh: %d vertices, %d faces\n", m.nv, m.nf);

    /* Step 2 — the base surface (Sec. 4.1): tension-field membrane + quadratic bending. TFT has no
     * compressive stiffness, so the base stays smooth where the sheet wants to wrinkle. */
    wr_tfw_base_shell_desc(young, nu, h, 0.0, &sd);
    CHECK(wr_shell_create(&shell, &m, &sd, &d));
    left = (int32_t *)wr_alloc_array((size_t)m.nv, sizeof *left);
    right = (int32_t *)wr_alloc_array((size_t)m.nv, sizeof *right);
    x = (double *)wr_alloc_array((size_t)m.nv * 3, sizeof *x);
    memcpy(x, m.pos, sizeof(double) * 3 * (size_t)m.nv);
    for (v = 0; v < m.nv; ++v) {
        if (m.pos[3 * v] < 1e-9) left[nl++] = v;
        if (m.pos[3 * v] > W - 1e-9) right[nr++] = v;
    }
    memset(mo, 0, sizeof mo);
    mo[0].kind = WR_MOTION_HOLD;
    mo[0].verts = left;
    mo[0].n_verts = nl;
    mo[1].kind = WR_MOTION_STRETCH;
    mo[1].verts = right;
    mo[1].n_verts = nr;
    mo[1].axis[0] = 1.0;
    mo[1].amount = strain;
    memset(&st, 0, sizeof st);
    CHECK(wr_statics_solve_incremental(&shell, x, &st, mo, 2, 4, &ss, &d));
    printf("step 2  TFT base: %d Newton iterations, width at mid-length %.2f mm (rest 100 mm)\n",
           ss.total_iterations, 1e3 * (x[3 * (m.nv - 1 - 14) + 1] - x[3 * 14 + 1]));

    /* Steps 3–6 — W set, initial guess, SQP for (a, ω), phase, Loop upsampling + Eq. 19. */
    mat.young = young;
    mat.poisson = nu;
    mat.thickness = h;
    CHECK(wr_tfw_fields(&m, x, &mat, NULL, &r, &d));
    for (v = 0; v < r.nv; ++v) amax = fmax(amax, r.a[v]);
    printf("step 3  wrinkle-free faces (W): %d of %d\n", r.n_wrinkle_free, r.nf);
    printf("step 4  SQP: %d iterations, max amplitude %.3f mm\n", r.sqp.iterations, 1e3 * amax);
    printf("step 5  phase: %d cut edges, %d jump conflicts\n", r.phase.n_cut_edges, r.phase.n_conflicts);
    printf("step 6  wrinkled mesh: %d vertices (Loop level 2)\n", r.wrinkled.nv);

    /* Step 7 — count the wrinkles: the frequency one-form's mean |ω| per unit length near mid-length. */
    {
        double kx = 0.0;
        int32_t n = 0;
        for (k = 0; k < r.ne; ++k) {
            int32_t i = m.edges[2 * k], j = m.edges[2 * k + 1];
            double dx = m.pos[3 * j] - m.pos[3 * i], dy = m.pos[3 * j + 1] - m.pos[3 * i + 1];
            double xm = 0.5 * (m.pos[3 * i] + m.pos[3 * j]);
            if (fabs(dx) < 1e-12 && fabs(xm - 0.5 * W) < 0.02 && r.a[i] > 0 && r.a[j] > 0) {
                kx += fabs(r.omega[k]) / fabs(dy);
                ++n;
            }
        }
        if (n) printf("step 7  wavenumber across the width %.0f rad/m -> %.1f waves over 100 mm\n", kx / n,
                      kx / n * H / (2.0 * 3.141592653589793));
    }
    wr_tfw_result_free(&r);
    wr_shell_free(&shell);
    wr_free(left);
    wr_free(right);
    wr_free(x);
    wr_mesh_free(&m);
    return 0;
}
