/* Tutorial walk 1 — from fabric to mesh (Style3D Sec. 4). docs/tutorial-1-fabric-to-mesh.md explains
 * every step; each step prints a number you can check against the text.
 *
 *   cc -std=c11 -O2 -Iinclude examples/tutorial/fabric_to_mesh.c -o fabric_to_mesh -lm && ./fabric_to_mesh
 */
#define WRINKLE_IMPLEMENTATION
#include "wrinkle/core.h"
#include "wrinkle/mesh.h"
#include "wrinkle/resolution.h"
#include "wrinkle/transition.h"
#include "wrinkle/sizing.h"
#include "wrinkle/poisson.h"
#include "wrinkle/triangulate.h"
#include "wrinkle/mesher.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#define CHECK(call)                                                              \
    do {                                                                         \
        if ((call) != WR_OK) {                                                   \
            fprintf(stderr, "%s failed: %s\n", #call, d.message);                \
            return 1;                                                            \
        }                                                                        \
    } while (0)

int main(void) {
    wr_diag d;
    wr_resolution_model model;
    double B = 2.6e-6, E = 2.0e6; /* Table 1 "Green" */
    double r_f, r_sh, L_w, h, A1, lambda;
    wr_transition t;
    wr_sizing *map = NULL;

    /* Step 1 — Eq. 4's constants from the designer's ranges (Sec. 4.1.1). */
    CHECK(wr_resolution_calibrate(2e3, 2e6, 1e-9, 1e-3, 2.5e-3, 50e-3, &model, &d));
    printf("step 1  c1 = %.2f m^-3, c2 = %.4g m^-1\n", model.c1, model.c2);

    /* Step 2 — the fabric's optimal resolution: solve c1 r^6 + c2 r^4 = B/E. */
    CHECK(wr_resolution_from_BE(&model, B, E, NULL, &r_f, &d));
    printf("step 2  Green fabric (B = %g N m, E = %g Pa): r_f = %.2f mm\n", B, E, 1e3 * r_f);

    /* Step 3 — a shirring line's source resolution (Sec. 4.2.2): extra stiffness E_sh, shrinkage 0.5. */
    CHECK(wr_source_shirring(&model, B, E, 2.0e6, 0.5, 1.0, NULL, &r_sh, &d));
    printf("step 3  shirring source r_sh = %.2f mm\n", 1e3 * r_sh);

    /* Step 4 — how fast the refinement fades: the source's wavelength (Fig. 4's r = sqrt(λ²/16 + A²)
     * with A = (√2/π) λ √δ, inverted: r = c λ), its wrinklon size (compression form, Sec. 4.2.1) and
     * the transition power m = log r / log L_w (millimetres inside transition.h). */
    h = cbrt(12.0 * (1.0 - 0.09) * B / E); /* Kirchhoff–Love thickness: B/E = h³/(12(1-ν²)), ν = 0.3 */
    CHECK(wr_cm_amplitude(1.0, 0.5, &A1, &d)); /* amplitude per unit wavelength at δ = 1 − ρ = 0.5 */
    lambda = r_sh / wr_cm_optimal_resolution(1.0, A1);
    CHECK(wr_wrinklon_size_compression(lambda, 0.5, h, &L_w, &d));
    CHECK(wr_transition_make(r_sh, L_w, NULL, &t, &d));
    printf("step 4  h = %.3f mm, lambda_sh = %.2f mm, L_w = %.1f mm, m = %.3f; r(L_w) = %.2f mm (= 2 r_sh)\n",
           1e3 * h, 1e3 * lambda, 1e3 * L_w, t.m, 1e3 * wr_transition_eval(&t, L_w));

    /* Step 5 — the sizing map r_v = min(r_f, r_sh + x^m) around a straight shirring line. */
    {
        double line[4] = {0.05, 0.125, 0.20, 0.125};
        CHECK(wr_sizing_create(r_f, NULL, &map, &d));
        CHECK(wr_sizing_add_polyline(map, line, 2, &t, &d));
        CHECK(wr_sizing_build(map, &d));
        printf("step 5  sizing on the line %.2f mm, 10 mm away %.2f mm, 60 mm away %.2f mm\n",
               1e3 * wr_sizing_eval(map, 0.125, 0.125), 1e3 * wr_sizing_eval(map, 0.125, 0.135),
               1e3 * wr_sizing_eval(map, 0.125, 0.185));
        wr_sizing_free(map);
    }

    /* Step 6 — the whole pipeline (Sec. 4.3): Poisson sampling + constrained Delaunay on a 250 mm square. */
    {
        double sq[8] = {0, 0, 0.25, 0, 0.25, 0.25, 0, 0.25}, line[4] = {0.05, 0.125, 0.20, 0.125};
        wr_pattern_panel pn;
        wr_pattern_shirring sh;
        wr_pattern pat;
        wr_mesher_result res;
        memset(&pn, 0, sizeof pn);
        memset(&sh, 0, sizeof sh);
        memset(&pat, 0, sizeof pat);
        pn.outer.xy = sq;
        pn.outer.n = 4;
        pn.fabric.B = B;
        pn.fabric.E = E;
        sh.panel = 0;
        sh.xy = line;
        sh.n = 2;
        sh.E_sh = 2.0e6;
        sh.rho = 0.5;
        pat.panels = &pn;
        pat.n_panels = 1;
        pat.shirrings = &sh;
        pat.n_shirrings = 1;
        CHECK(wr_mesher_run(&pat, NULL, &res, &d));
        printf("step 6  mesh: %d vertices, %d triangles, min angle %.1f deg, mean edge/sizing %.3f\n",
               res.mesh.nv, res.mesh.nf, res.report.min_angle_deg, res.report.ratio_mean);
        wr_mesher_free(&res);
    }
    return 0;
}
