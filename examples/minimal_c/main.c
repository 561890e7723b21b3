/* Minimal drop-in use of wrinkle from C: this file is the one translation unit that defines
 * WRINKLE_IMPLEMENTATION. Build (installed kit):
 *     cc -std=c11 main.c $(pkg-config --cflags --libs wrinkle) -o minimal_c
 * Job 1 (Style3D): the optimal mesh resolution of a fabric (Eq. 4), then a panel meshed at it.
 * Job 2 (TFW): wrinkle a coarse sheet — wrinkle field on a stretched base whose width contracts
 * more than Poisson's ratio allows, a few SQP iterations, Loop upsampling to the wrinkled surface. */
#define WRINKLE_IMPLEMENTATION
#include "wrinkle/wrinkle.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static int mesh_a_panel(void) {
    const double B = 2.6e-6, E = 2.0e6; /* Style3D Table 1 "Green": N·m, N/m² */
    double outline[8] = {0, 0, 0.30, 0, 0.30, 0.20, 0, 0.20}; /* a 300 × 200 mm panel [m] */
    wr_resolution_model model = wr_resolution_model_paper();
    wr_pattern_panel panel;
    wr_pattern pattern;
    wr_mesher_result res;
    wr_diag d;
    double r;
    if (wr_resolution_from_BE(&model, B, E, NULL, &r, &d) != WR_OK) {
        fprintf(stderr, "resolution: %s\n", d.message);
        return 1;
    }
    memset(&panel, 0, sizeof panel);
    memset(&pattern, 0, sizeof pattern);
    panel.name = "panel";
    panel.outer.xy = outline;
    panel.outer.n = 4;
    panel.fabric.B = B;
    panel.fabric.E = E;
    pattern.panels = &panel;
    pattern.n_panels = 1;
    if (wr_mesher_run(&pattern, NULL, &res, &d) != WR_OK) {
        fprintf(stderr, "mesher: %s\n", d.message);
        return 1;
    }
    printf("fabric B=%g N*m E=%g N/m^2: optimal resolution %.2f mm\n", B, E, 1e3 * r);
    printf("panel 300x200 mm: %d vertices, %d triangles, min angle %.1f deg, mean edge/sizing %.3f\n",
           (int)res.mesh.nv, (int)res.mesh.nf, res.report.min_angle_deg, res.report.ratio_mean);
    wr_mesher_free(&res);
    return 0;
}

static int wrinkle_a_sheet(void) {
    const double L = 0.25, H = 0.10, PI = 3.14159265358979323846;
    wr_mesh m;
    wr_wf wf;
    wr_wf_material mat;
    wr_wf_solve_desc sd;
    wr_wf_solve_stats ss;
    wr_wf_upsample_desc ud;
    wr_mesh fine;
    wr_diag d;
    wr_status st;
    double *base = NULL, *a = NULL, *omega = NULL, *phi = NULL, amax = 0.0, zmax = 0.0;
    uint8_t *clamped = NULL;
    int32_t v, f, k;
    int rc = 1;
    memset(&fine, 0, sizeof fine);
    memset(&wf, 0, sizeof wf);
    if (wr_mesh_rectangle(&m, L, H, 12, 5, &d) != WR_OK) { /* the coarse sheet: 12 × 5 cells */
        fprintf(stderr, "mesh: %s\n", d.message);
        return 1;
    }
    base = (double *)malloc(sizeof(double) * 3 * (size_t)m.nv);
    a = (double *)malloc(sizeof(double) * (size_t)m.nv);
    omega = (double *)malloc(sizeof(double) * (size_t)m.ne);
    phi = (double *)malloc(sizeof(double) * 3 * (size_t)m.nf);
    clamped = (uint8_t *)calloc((size_t)m.nf, 1);
    if (!base || !a || !omega || !phi || !clamped) goto done;
    /* Base surface (a tension-field solve would give it): 10% stretch along x, the width pulled in by
     * up to 10% mid-span — more than the Poisson contraction, so the middle has to wrinkle. */
    for (v = 0; v < m.nv; ++v) {
        double x = m.pos[3 * v], y = m.pos[3 * v + 1];
        base[3 * v] = 1.1 * x;
        base[3 * v + 1] = (y - 0.5 * H) * (1.0 - 0.1 * sin(PI * x / L)) + 0.5 * H;
        base[3 * v + 2] = 0.0;
    }
    mat.young = 1e6; /* Pa */
    mat.poisson = 0.5;
    mat.thickness = 1e-4; /* m */
    if ((st = wr_wf_create(&wf, &m, base, &mat, &d)) != WR_OK) goto fail;
    for (f = 0; f < m.nf; ++f) { /* the clamped ends carry no wrinkles (TFW Sec. 5.1: the set W) */
        double cx = 0.0;
        for (k = 0; k < 3; ++k) cx += m.pos[3 * m.faces[3 * f + k]] / 3.0;
        clamped[f] = (uint8_t)(cx < 0.02 || cx > L - 0.02);
    }
    wr_wf_set_wrinkle_free(&wf, clamped);
    if ((st = wr_wf_init(&wf, NULL, a, omega, &d)) != WR_OK) goto fail; /* TFW App. E.2 */
    memset(&sd, 0, sizeof sd);
    sd.max_iter = 60; /* a few SQP iterations (App. E.3); ~25 reach KKT 1e-8 here */
    st = wr_wf_solve(&wf, &sd, a, omega, &ss, &d);
    if (st != WR_OK && st != WR_ERR_NOT_CONVERGED) goto fail; /* not converged keeps the best iterate */
    if ((st = wr_wf_phase(&wf, omega, phi, NULL, &d)) != WR_OK) goto fail; /* App. E.4 */
    memset(&ud, 0, sizeof ud);
    ud.levels = 3;
    if ((st = wr_wf_upsample(&wf, a, phi, &ud, &fine, NULL, &d)) != WR_OK) goto fail; /* App. E.5, Eq. 19 */
    for (v = 0; v < m.nv; ++v) amax = fmax(amax, a[v]);
    for (v = 0; v < fine.nv; ++v) zmax = fmax(zmax, fabs(fine.pos[3 * v + 2]));
    printf("coarse sheet %d vertices: SQP %d iterations (%s), E_wf %.4g -> %.4g J, max amplitude %.3f mm\n",
           (int)m.nv, (int)ss.iterations, wr_status_string(st), ss.energy0, ss.energy, 1e3 * amax);
    printf("wrinkled surface: %d vertices, max |z| %.3f mm\n", (int)fine.nv, 1e3 * zmax);
    rc = 0;
    goto done;
fail:
    fprintf(stderr, "wrinkle field: %s\n", d.message);
done:
    wr_mesh_free(&fine);
    wr_wf_free(&wf);
    wr_mesh_free(&m);
    free(base);
    free(a);
    free(omega);
    free(phi);
    free(clamped);
    return rc;
}

int main(void) {
    int rc = mesh_a_panel();
    return rc ? rc : wrinkle_a_sheet();
}
