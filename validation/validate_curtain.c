/* validate_curtain — Style3D Fig. 17 / 18d: a hanging curtain whose top edge is gathered into a short
 * wavelength λ0; below it the wrinkles coarsen with depth (Vandeparre et al. 2011 wrinklons). We measure
 * the depth over which the wavelength grows from λ0 to 2λ0 and compare it with our wrinklon prediction
 * L_w = λ0² sqrt(T/B) (transition.h, Style3D Sec. 4.2.1, prefactor 1) for several bending stiffnesses.
 *
 * SETUP (stated in the result file). Rest sheet W × H in the z = 0 plane, y up, top edge y = H; gravity
 * (0, −g, 0) in the plane, so the curtain hangs in its own plane. The top edge is prescribed (scene
 * "wave" + "stretch" motion): x → W/2 + (1 − δ)(x − W/2), z = A sin(2π x/λ0), with the gather ratio δ and
 * A = λ0 √δ / π, so the sine's arc length ≈ (1 + (A k)²/4)(1 − δ) ≈ the rest width (an inextensible
 * gather, k = 2π/λ0). The sides and the bottom are free. W = 6 λ0 (whole waves, zero displacement at
 * the corners). Tension for the prediction: the weight hanging below the top edge, T = ρ_A g H (the
 * largest tension, at the top where the first transition starts; it is ρ_A g (H − x) at depth x).
 * Material: E = 1 MPa, ν = 0.3, ρ_A = 0.15 kg/m², h from Kirchhoff–Love per B.
 * Mesh: regular union-jack grid at resolution r (λ0/r cells per imposed wave). StVK + mid-edge
 * bending, gravity and the gather ramped over load steps, 1 µm seeded normal kick, hybrid
 * projected→exact Newton, CHOLMOD.
 *
 * MEASUREMENT. Horizontal probe lines every r/2 in depth, x ∈ [λ0/2, W − λ0/2] (half a wave clear of
 * the free sides), sampling the out-of-plane displacement z; spectrum.h gives the wavelength λ(d) at
 * depth d (Hann window, linear detrend, Gaussian sub-bin peak). The measured transition distance is the
 * first depth at which λ(d) reaches 2 λ0 (linear interpolation between probe lines), required to be
 * where the wrinkles are still present (amplitude ≥ 1 % of A; otherwise no transition is measured).
 * Pass (issue 5): |L_measured − L_w| ≤ 25 % of L_w for each stiffness.
 * Options: --res R [m] (default λ0/8), --quick (coarser grid, one stiffness; smoke only).
 * Exit = failed quantities, 2 on errors.
 */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "scene.h"
#include "vresult.h"

#define PI 3.14159265358979323846
#define LAMBDA0 0.010   /* imposed wavelength [m] */
#define NWAVES 6        /* W = NWAVES λ0 */
#define HEIGHT 0.080    /* [m] */
#define GATHER 0.04     /* δ: relative shortening of the top edge */
#define RHO_A 0.15      /* kg/m² */
#define YOUNG 1.0e6
#define POISSON 0.3
#define GRAV 9.81
#define AMP_FLOOR 0.01  /* wrinkles "present" while the probe amplitude is ≥ 1 % of A */
#define NB 3

typedef struct curtain_row {
    double B, T, Lw_pred, L_meas, t_solve;
    int32_t nv, newton, nd;
    wr_status st;
    double depth[512], lambda[512], amp[512];
} curtain_row;

static void progress(void *user, int32_t step, int32_t n, const wr_statics_stats *st) {
    (void)user;
    fprintf(stderr, "\r   step %d/%d Newton %3d |g|/ref %.1e %.1f s   ", (int)step, (int)n, (int)st->iterations,
            st->grad_ref > 0 ? st->grad_norm / st->grad_ref : 0.0, st->t_total);
}

static int curtain_run(double B, double r, int load_steps, curtain_row *R, const char *datpath) {
    char json[4096];
    wr_scene sc;
    wr_scene_run run;
    wr_diag d;
    wr_probe pr;
    double W = NWAVES * LAMBDA0, A = LAMBDA0 * sqrt(GATHER) / PI, *u, pts[2 * 1024], vals[1024], ds, a[2], b[2];
    int32_t ns = 512, i, k;
    snprintf(json, sizeof json,
             "{\"name\": \"curtain\","
             " \"mesh\": {\"type\": \"rectangle\", \"width\": %.17g, \"height\": %.17g, \"resolution\": %.17g},"
             " \"material\": {\"young\": %.17g, \"poisson\": %.17g, \"bending_stiffness\": %.17g, \"areal_density\": %.17g},"
             " \"energy\": {\"membrane\": \"stvk\", \"bending\": \"midedge\"},"
             " \"gravity\": [0, %.17g, 0],"
             " \"boundary\": [{\"name\": \"top\", \"box\": {\"min\": [-1, %.17g, -1], \"max\": [1, 1, 1]},"
             "   \"center\": [%.17g, %.17g, 0], \"stretch\": [%.17g, 1, 1],"
             "   \"wave\": {\"amplitude\": %.17g, \"wavelength\": %.17g, \"phase\": 0, \"along\": [1, 0, 0], \"dir\": [0, 0, 1]}}],"
             " \"solver\": {\"linear\": \"cholmod\", \"load_steps\": %d, \"perturb\": 1e-6, \"seed\": 3, \"hessian\": \"hybrid\","
             "   \"grad_tol\": 1e-8, \"max_iter\": 300}}",
             W, HEIGHT, r, YOUNG, POISSON, B, RHO_A, -GRAV, HEIGHT - 1e-6 * r, 0.5 * W, HEIGHT, 1.0 - GATHER, A, LAMBDA0,
             load_steps);
    if (wr_scene_parse(&sc, json, strlen(json), NULL, &d) != WR_OK) {
        fprintf(stderr, "validate_curtain: %s\n", d.message);
        return -1;
    }
    R->B = B;
    R->T = RHO_A * GRAV * HEIGHT;
    if (wr_wrinklon_size_tension(LAMBDA0, R->T, B, &R->Lw_pred, &d) != WR_OK) return -1;
    if (wr_scene_run_create(&run, &sc, &d) != WR_OK) {
        fprintf(stderr, "validate_curtain: %s\n", d.message);
        return -1;
    }
    R->nv = run.mesh.nv;
    fprintf(stderr, "== B = %.2e N m: r = %.2f mm, %d vertices, predicted L_w = %.1f mm\n", B, 1e3 * r, (int)R->nv,
            1e3 * R->Lw_pred);
    R->st = wr_scene_run_solve(&run, progress, NULL, &d);
    fprintf(stderr, "\n");
    if (R->st != WR_OK) fprintf(stderr, "   solve: %s\n", d.message);
    R->t_solve = run.t_solve;
    R->newton = run.newton_iterations;
    R->L_meas = NAN;
    R->nd = 0;
    u = (double *)malloc(sizeof(double) * 3 * (size_t)run.mesh.nv);
    if (!u || wr_probe_create(&pr, &run.mesh, NULL, &d) != WR_OK) {
        free(u);
        wr_scene_run_free(&run);
        wr_scene_free(&sc);
        return -1;
    }
    for (i = 0; i < 3 * run.mesh.nv; ++i) u[i] = run.x[i] - run.mesh.pos[i];
    {
        wr_afile f;
        int have_f = wr_afile_open(&f, datpath, &d) == WR_OK;
        double dir[3] = {0.0, 0.0, 1.0}, dd = 0.5 * r;
        if (have_f) fprintf(f.fp, "# depth[mm] lambda[mm] amplitude[mm]  (B = %g N m)\n", B);
        for (k = 1; k * dd < HEIGHT - r && R->nd < 512; ++k) {
            double depth = k * dd;
            wr_spectrum_result res;
            int32_t nout = 0;
            a[0] = 0.5 * LAMBDA0, a[1] = HEIGHT - depth;
            b[0] = W - 0.5 * LAMBDA0, b[1] = HEIGHT - depth;
            if (wr_path_segment(a, b, ns, 0, pts, &ds, &d) != WR_OK) break;
            if (wr_probe_sample_dir(&pr, u, dir, pts, ns, vals, &nout, &d) != WR_OK || nout) break;
            if (wr_spectrum_analyze(vals, ns, ds, 0, NULL, &res, NULL, 0, &d) != WR_OK) {
                res.wavelength = NAN;
                res.amplitude_p2p = 0.0;
            }
            R->depth[R->nd] = depth, R->lambda[R->nd] = res.wavelength, R->amp[R->nd] = res.amplitude_p2p;
            if (have_f)
                fprintf(f.fp, "%.4f %.4f %.5f\n", 1e3 * depth, 1e3 * res.wavelength, 1e3 * res.amplitude_p2p);
            R->nd++;
        }
        if (have_f) wr_afile_commit(&f, &d);
    }
    /* first crossing of 2 λ0 while the wrinkles are present */
    for (k = 1; k < R->nd; ++k) {
        if (R->amp[k] < AMP_FLOOR * A || !(R->lambda[k] == R->lambda[k])) break;
        if (R->lambda[k] >= 2.0 * LAMBDA0 && R->lambda[k - 1] < 2.0 * LAMBDA0) {
            double t = (2.0 * LAMBDA0 - R->lambda[k - 1]) / (R->lambda[k] - R->lambda[k - 1]);
            R->L_meas = R->depth[k - 1] + t * (R->depth[k] - R->depth[k - 1]);
            break;
        }
    }
    fprintf(stderr, "   measured transition %.1f mm vs predicted %.1f mm; %d Newton, %.1f s\n", 1e3 * R->L_meas,
            1e3 * R->Lw_pred, (int)R->newton, R->t_solve);
    wr_probe_free(&pr);
    free(u);
    wr_scene_run_free(&run);
    wr_scene_free(&sc);
    return 0;
}

int main(int argc, char **argv) {
    static curtain_row rows[NB];
    double Bs[NB] = {1.0e-6, 2.0e-6, 4.0e-6}, r = LAMBDA0 / 8.0;
    int i, nb = NB, quick = 0, load_steps = 6;
    char dat[NB][4096], table[8192], buf[1024], name[256];
    wr_vres *v;
    for (i = 1; i < argc; ++i) {
        if (strcmp(argv[i], "--quick") == 0) quick = 1;
        else if (strcmp(argv[i], "--res") == 0 && i + 1 < argc) r = atof(argv[++i]);
        else {
            fprintf(stderr, "usage: validate_curtain [--quick] [--res METRES]\n");
            return 2;
        }
    }
    if (quick) {
        r = LAMBDA0 / 5.0;
        nb = 1;
        Bs[0] = 2.0e-6;
    }
    v = wr_vres_begin("curtain", "Style3D Fig. 17/18d hanging curtain: lambda -> 2 lambda transition distance vs wrinklon L_w");
    if (!v) return 2;
    for (i = 0; i < nb; ++i) {
        snprintf(dat[i], sizeof dat[i], "%s/curtain_%d.dat", wr_vres_dir(), i);
        if (curtain_run(Bs[i], r, load_steps, &rows[i], dat[i]) != 0) return 2;
    }
    snprintf(table, sizeof table,
             "| B [N m] | T = rho_A g H [N/m] | predicted L_w = lambda0^2 sqrt(T/B) [mm] | measured lambda0 -> 2 lambda0 [mm] | "
             "ratio | vertices | Newton | status | solve [s] |\n|---|---|---|---|---|---|---|---|---|\n");
    for (i = 0; i < nb; ++i) {
        snprintf(buf, sizeof buf, "| %.1e | %.4f | %.2f | %.2f | %.3f | %d | %d | %s | %.1f |\n", rows[i].B, rows[i].T,
                 1e3 * rows[i].Lw_pred, 1e3 * rows[i].L_meas, rows[i].L_meas / rows[i].Lw_pred, (int)rows[i].nv,
                 (int)rows[i].newton, wr_status_string(rows[i].st), rows[i].t_solve);
        strncat(table, buf, sizeof table - strlen(table) - 1);
    }
    wr_vres_table_md(v, table);
    for (i = 0; i < nb; ++i) {
        snprintf(name, sizeof name, "transition distance, B = %.1e N m (measured vs L_w)", rows[i].B);
        wr_vres_rel(v, name, "mm", 1e3 * rows[i].Lw_pred, 1e3 * rows[i].L_meas, 0.25);
    }
    wr_vres_info(v, "paper's case: predicted L_w", "mm", 26.7, NAN);
    wr_vres_info(v, "paper's case: measured", "mm", 25.0, NAN);
    wr_vres_info(v, "mesh resolution", "mm", NAN, 1e3 * r);
    snprintf(buf, sizeof buf,
             "Curtain %.0f x %.0f mm (W = %d lambda0), lambda0 = %.0f mm, gather delta = %.2f (top edge x scaled by 1 - delta, "
             "z = A sin(2 pi x / lambda0), A = lambda0 sqrt(delta)/pi = %.3f mm), rho_A = %.2f kg/m^2, E = %.0e Pa, nu = %.1f, "
             "h from Kirchhoff-Love; gravity in the sheet's plane; sides and bottom free.",
             1e3 * NWAVES * LAMBDA0, 1e3 * HEIGHT, NWAVES, 1e3 * LAMBDA0, GATHER, 1e3 * LAMBDA0 * sqrt(GATHER) / PI, RHO_A,
             YOUNG, POISSON);
    wr_vres_note(v, buf);
    snprintf(buf, sizeof buf,
             "Regular union-jack grid at r = %.2f mm (%.1f cells per imposed wave); StVK + mid-edge bending; gravity and "
             "gather ramped over %d load steps; 1 um seeded kick; hybrid Newton; CHOLMOD.%s",
             1e3 * r, LAMBDA0 / r, load_steps, quick ? " --quick run (one stiffness, coarse): smoke only." : "");
    wr_vres_note(v, buf);
    wr_vres_note(v, "Measured transition: first depth where the FFT wavelength of z on a horizontal probe "
                    "(x in [lambda0/2, W - lambda0/2]) reaches 2 lambda0, interpolated between probes every r/2, "
                    "while the amplitude is >= 1% of A. Prediction: transition.h wr_wrinklon_size_tension with "
                    "T = rho_A g H (tension at the top edge), prefactor 1 as in Style3D Sec. 4.2.1.");
    for (i = 0; i < nb; ++i)
        if (rows[i].st != WR_OK) {
            snprintf(buf, sizeof buf, "B = %.1e: a load step ended %s (best iterate analysed)", rows[i].B,
                     wr_status_string(rows[i].st));
            wr_vres_note(v, buf);
        }
    {
        char gp[4200], png[4200], cmd[9000];
        wr_afile f;
        wr_diag d;
        snprintf(gp, sizeof gp, "%s/../figures/curtain.gp", wr_vres_dir());
        snprintf(png, sizeof png, "%s/../figures/curtain.png", wr_vres_dir());
        if (wr_afile_open(&f, gp, &d) == WR_OK) {
            fprintf(f.fp, "set terminal pngcairo size 900,500\nset output '%s'\nset grid\n", png);
            fprintf(f.fp, "set xlabel 'depth below the gathered top edge [mm]'\nset ylabel 'wavelength [mm]'\n");
            fprintf(f.fp, "set yrange [0:%g]\nplot ", 4e3 * LAMBDA0);
            for (i = 0; i < nb; ++i)
                fprintf(f.fp, "%s'%s' u 1:2 w l lw 2 t 'B = %.0e (L_w pred. %.1f mm)'", i ? ", " : "", dat[i], rows[i].B,
                        1e3 * rows[i].Lw_pred);
            fprintf(f.fp, ", %g w l dt 2 t '2 lambda0'\n", 2e3 * LAMBDA0);
            if (wr_afile_commit(&f, &d) == WR_OK) {
                snprintf(cmd, sizeof cmd, "gnuplot '%s' 2>/dev/null", gp);
                if (system(cmd) == 0) wr_vres_figure(v, "figures/curtain.png", "wavelength vs depth per bending stiffness");
            }
        }
    }
    return wr_vres_finish(v);
}
