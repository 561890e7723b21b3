/* validate_tfw_sheared_rectangle — TFW Sec. 6 "Sheared Rectangles" (Fig. 9) after Wong & Pellegrino
 * (2006, "Wrinkled membranes" Parts I and III): a Kapton membrane 380 × 128 mm, 25 µm thick,
 * E = 3530 MPa, ν = 0.3, long edges clamped, the top edge displaced by δ = 3 mm parallel to the bottom
 * one, short edges free, no pre-tension. (δ = 3 mm is confirmed by the Part III figure caption found
 * by the search tool; the size and material are from our reading of Part I and are stated as such in
 * the result file.) The TFW paper gives no numbers beyond "1k vertices", 25 TFW wrinkles and 19 in the
 * experiment. Base: TFT + quadratic bending (Sec. 4.1) on a 54 × 17 union-jack grid (990 vertices),
 * one load step (TFT + quadratic bending under prescribed motions is convex in the free positions, so
 * the equilibrium does not depend on the load path and intermediate increments are needless; the solve
 * keeps the 800-step budget the former 4 × 200 had: docs/notes-tfw-solver.md); wr_tfw_fields with Loop
 * level 3. Pass row (issue 20): the paper-literal set-up, i.e.
 * no amplitude condition on the clamps (the paper states none). Reported beside it, named as OUR
 * modelling choice: a = 0 held on the clamped vertices (the clamps hold the membrane in the base
 * surface, so Eq. 19's out-of-plane term vanishes there; Wong & Pellegrino Part I: the wrinkle profile
 * is close to a half sine along each wrinkle, i.e. zero at both clamps; the authors' code has it as
 * an option). Count: spectrum.h on a 1024-sample probe along the
 * horizontal mid-line (y = 64 mm) of the wrinkled mesh's out-of-plane coordinate (the wrinkles run at
 * about 45°, so each crosses the mid-line once). Pass band (issue 6, set before either run): 17–27
 * wrinkles, i.e. the paper's 25 within the spread between it and the experiment's 19, plus 2.
 * Output: validation/results/tfw_sheared_rectangle.json, figures/tfw_sheared_rectangle.png.
 * --stvk-loop: instead, the full StVK reference with the Loop element (issue 15; see its section below),
 * into tfw_sheared_rectangle_stvk_loop.json. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "wrinkle/wrinkle.h"
#include "wrinkle/tfw.h"
#include "vresult.h"
#include "tfw_probe.h"
#include "vargs.h"
#include "scene.h"

#define L_SHEET 0.38
#define H_SHEET 0.128
#define SHEAR 0.003
#define NPROBE 1024
#define YOUNG 3530e6
#define NU 0.3
#define THICK 25e-6
#define BASE_LOAD_STEPS 1 /* convex base energy: one increment (see the top comment) */
#define BASE_MAX_ITER 800 /* the Newton budget of the former 4 increments × 200 */

static int validation_main(void) {
    wr_diag d;
    wr_mesh m;
    wr_shell sh;
    wr_shell_desc sd;
    wr_statics_desc st;
    wr_statics_stats ss;
    tp_clamps cl;
    wr_wf_material mat;
    wr_tfw_desc td;
    wr_tfw_result r, r0;
    wr_spectrum_result sr;
    wr_vres *v;
    int32_t vv, i;
    double *x, *pts, *zv, ds = 0.0, t0, t_base, amax = 0.0, zmax = 0.0, A[2], B[2];
    wr_status s_base, s_tfw, s_tfw0, s_sp;
    double count0 = NAN, wl0 = NAN, zc0 = NAN;
    char buf[768];
    memset(&d, 0, sizeof d);
    memset(&r, 0, sizeof r);
    memset(&r0, 0, sizeof r0);
    if (wr_mesh_rectangle(&m, L_SHEET, H_SHEET, 54, 17, &d)) {
        fprintf(stderr, "mesh: %s\n", d.message);
        return 1;
    }
    wr_tfw_base_shell_desc(YOUNG, NU, THICK, 0.0, &sd);
    if (wr_shell_create(&sh, &m, &sd, &d)) {
        fprintf(stderr, "shell: %s\n", d.message);
        return 1;
    }
    x = (double *)malloc(sizeof(double) * 3 * m.nv);
    if (!x || tp_clamps_select(&cl, &m, 1, 0.0, H_SHEET, &d)) { /* bottom edge clamped, top edge sheared */
        fprintf(stderr, "clamps: out of memory\n");
        return 1;
    }
    cl.mo[1].kind = WR_MOTION_TRANSLATE;
    cl.mo[1].vec[0] = SHEAR;
    memset(&st, 0, sizeof st);
    st.stop.max_iter = BASE_MAX_ITER;
    t0 = wr_time_seconds();
    s_base = tp_clamped_solve(&sh, &m, &cl, &st, BASE_LOAD_STEPS, x, &ss, &d);
    t_base = wr_time_seconds() - t0;
    fprintf(stderr, "base: %s, %d Newton steps, %.2f s\n", wr_status_string(s_base), ss.total_iterations, t_base);
    mat.young = YOUNG;
    mat.poisson = NU;
    mat.thickness = THICK;
    memset(&td, 0, sizeof td);
    td.upsample.levels = 3;
    tp_tfw_pair(&m, x, &mat, &td, cl.flags, &r0, &s_tfw0, &r, &s_tfw, &d);
    v = wr_vres_begin("tfw_sheared_rectangle", "TFW Sec. 6 sheared rectangle after Wong & Pellegrino 2006 (Fig. 9): wrinkle count");
    if (s_tfw != WR_OK && s_tfw != WR_ERR_NOT_CONVERGED) {
        snprintf(buf, sizeof buf, "TFW pipeline failed: %s", d.message);
        wr_vres_note(v, buf);
        wr_vres_check(v, "wrinkles", "wrinkles", 25.0, NAN, "17-27 (issue 6)", 0);
        return wr_vres_finish(v) == 0 ? 0 : 1;
    }
    for (vv = 0; vv < m.nv; ++vv) amax = fmax(amax, r.a[vv]);
    /* probe along the horizontal mid-line (rest domain of the subdivided mesh) */
    pts = (double *)malloc(sizeof(double) * 2 * NPROBE);
    zv = (double *)malloc(sizeof(double) * NPROBE);
    A[1] = B[1] = 0.5 * H_SHEET;
    A[0] = 0.0;
    B[0] = L_SHEET;
    memset(&sr, 0, sizeof sr);
    s_sp = pts && zv ? tp_line_field(&r.wrinkled, NULL, A, B, NPROBE, pts, &ds, zv, &sr, &d) : WR_ERR_NOMEM;
    if (!s_sp) zmax = tp_max_abs(zv, NPROBE);
    if (!s_sp && (s_tfw0 == WR_OK || s_tfw0 == WR_ERR_NOT_CONVERGED)) {
        wr_spectrum_result s0;
        double *zv0 = (double *)malloc(sizeof(double) * NPROBE), ds0 = 0.0;
        if (zv0 && !tp_line_field(&r0.wrinkled, NULL, A, B, NPROBE, NULL, &ds0, zv0, &s0, &d)) {
            count0 = s0.count;
            wl0 = s0.wavelength;
            zc0 = s0.zc_waves;
        }
        free(zv0);
    }
    /* pass row: the paper-literal set-up (no clamp condition on a); band 17-27 from issue 6 */
    wr_vres_range(v, "wrinkles along the mid-line (FFT count), paper-literal set-up (no amplitude condition at the clamps)",
                  "wrinkles", 25.0, count0, 17.0, 27.0);
    wr_vres_info(v, "waves by zero crossings, paper-literal set-up", "waves", 25.0, zc0);
    wr_vres_info(v, "wavelength along the mid-line, paper-literal set-up", "mm", NAN, 1e3 * wl0);
    wr_vres_info(v, "SQP iterations, paper-literal set-up (both solves)", "", 147, r0.sqp.iterations);
    /* our modelling choice, reported beside it */
    wr_vres_info(v, "wrinkles along the mid-line (FFT count), OUR CHOICE a = 0 on the clamped vertices", "wrinkles", 25.0,
                 s_sp ? NAN : sr.count);
    wr_vres_info(v, "wrinkles in the experiment (Wong & Pellegrino 2006) vs ours with a = 0 clamps", "wrinkles", 19.0,
                 s_sp ? NAN : sr.count);
    wr_vres_info(v, "wrinkles, least-squares wavelength, a = 0 clamps", "wrinkles", 25.0, s_sp ? NAN : sr.count_ls);
    wr_vres_info(v, "waves by hysteresis zero crossings, a = 0 clamps", "waves", 25.0, s_sp ? NAN : sr.zc_waves);
    wr_vres_info(v, "wavelength along the mid-line (FFT), a = 0 clamps", "mm", NAN, s_sp ? NAN : 1e3 * sr.wavelength);
    /* Cerda & Mahadevan's balance applied along the 45° wrinkles: length √2 H between the clamps,
     * tension strain γ/2 = δ/(2H); spacing along the mid-line √2 λ */
    {
        double lw = sqrt(2.0) * H_SHEET, eps = 0.5 * SHEAR / H_SHEET;
        double lam = sqrt(2.0 * 3.14159265358979 * lw * THICK) / pow(3.0 * (1.0 - NU * NU) * eps, 0.25);
        wr_vres_info(v, "Cerda-Mahadevan estimate along the 45 deg wrinkles (length sqrt2 H, strain delta/2H)", "wrinkles", NAN,
                     L_SHEET / (sqrt(2.0) * lam));
        wr_vres_reference(v, L_SHEET / (sqrt(2.0) * lam), "Cerda & Mahadevan 2003 scaling along the 45 deg wrinkles");
    }
    wr_vres_info(v, "peak |z| on the probe", "mm", NAN, s_sp ? NAN : 1e3 * zmax);
    wr_vres_info(v, "max a on the base vertices", "mm", NAN, 1e3 * amax);
    wr_vres_info(v, "base vertices", "", 1000, m.nv);
    wr_vres_info(v, "wrinkle-free faces |W| (Sec. 5.1)", "", NAN, r.n_wrinkle_free);
    tp_solver_rows(v, &r, s_tfw, ss.total_iterations, t_base, BASE_LOAD_STEPS, 2.27, 21, 147, 27.52);
    wr_vres_note(v, "Setup (Wong & Pellegrino 2006): Kapton 380 x 128 mm, 25 um, E = 3530 MPa, nu = 0.3, shear displacement "
                    "3 mm of the top clamp, short edges free; delta = 3 mm confirmed from their Part III, size and "
                    "material from our reading of Part I (not re-checked against the paper text here).");
    wr_vres_note(v, "Sources found (search tool): msp.org/jomms/2006/1-1/p02 (Part I abstract: rectangular membrane in "
                    "simple shear, wrinkle profile ~ half sine wave in the longitudinal direction, pattern essentially "
                    "unchanged with growing shear); shellbuckling.com softShellsMembranes page 9 (Part III: 'membrane in "
                    "shear with delta = 3 mm', wrinkles at 45 deg in the central region, fan regions near two corners). "
                    "The 380 x 128 mm size, 25 um Kapton HN with E = 3530 MPa, nu = 0.3, and the absence of pre-tension "
                    "could not be confirmed from retrieved text.");
    wr_vres_note(v, "Count = probe length (0.38 m) / FFT wavelength along y = 64 mm.");
    wr_vres_note(v, "TFT base in one load step (the TFT + quadratic-bending energy is convex in the free positions, so the "
                    "load path does not move the equilibrium; 4 load steps took 785 Newton steps, 600 of them in the three "
                    "intermediate steps, each ending at max_iter). The base is set to energy round-off only to ~15 um at the "
                    "free short edges (zero-tension faces held by the quadratic bending alone), and the amplitude there, where "
                    "max a sits, moves by up to ~17 % between equally converged bases: docs/notes-tfw-solver.md.");
    wr_vres_note(v, "Clamp condition: a = 0 on the clamped vertices of both long edges (the clamps hold the membrane in "
                    "the base surface, so Eq. 19's out-of-plane term a cos(phi) vanishes there; Wong & Pellegrino find a "
                    "half-sine profile along each wrinkle). Without it, TFT leaves shear compression right up to the clamps, "
                    "the amplitude stays finite along the whole wrinkle, no crest tension opposes the bending term and the "
                    "wavelength grows (see the 'paper-literal' rows). The paper states no amplitude condition for this case, "
                    "so the pass row is the run without it (issue 20) and the a = 0 run is our modelling choice.");
    if (s_base != WR_OK) {
        snprintf(buf, sizeof buf, "TFT base solve ended %s (best iterate used).", wr_status_string(s_base));
        wr_vres_note(v, buf);
    }
    tp_render_figure(v, "tfw_sheared_rectangle_render", &m, x, &mat, &td, &r, "rendered: the 990-vertex TFT base beside the TFW wrinkled surface (Loop level 3, a = 0 on the clamps), coloured by wrinkle height");
    /* figure: probe profile */
    if (!s_sp)
        tp_profile_figure(v, "tfw_sheared_rectangle", pts, 2, zv, NPROBE, "x along the mid-line [mm]", "z of the wrinkled surface [mm]",
                          "TFW sheared rectangle (990-vertex base, 3 mm shear), y = 64 mm", "TFW, Loop level 3", "wrinkled-surface profile along the horizontal mid-line");
    i = wr_vres_finish(v);
    tp_clamps_free(&cl);
    free(x);
    free(pts);
    free(zv);
    wr_tfw_result_free(&r);
    wr_tfw_result_free(&r0);
    wr_shell_free(&sh);
    wr_mesh_free(&m);
    return i < 0 ? 1 : 0;
}

/* ---- --stvk-loop (issue 15): the StVK reference with the Loop element ----------------------------
 * Full StVK simulation of the same set-up (StVK membrane + Koiter bending on the Loop limit surface,
 * shell.h loop_element 1: the faces with a boundary corner keep linear StVK + mid-edge bending), on the
 * kit's Poisson + Delaunay rectangles (scene delaunay_rectangle, seed 1) of r = 5, 3.75, 2.8, 2.1 and 1.6 mm, the
 * shear in 4 load steps with tp_loop_solve (2.5 um = h/10 seeded kick at every step, the
 * stability test after each). Metric, fixed before the runs: the pass row's probe (1024 samples along
 * y = 64 mm in the rest domain) of the equilibrium's z, FFT count and wavelength (spectrum.h).
 * Converged: the two finest solves WR_OK and count and wavelength within 5 % between them (issue 15's
 * rule). Pass row: the finest mesh's count against the TFW paper's StVK reference, 13 wrinkles, +-2
 * (set before the run); a count that is not converged is NAN there (a miss, reported as such). */
#define SL_NRUN 5
#define SL_REL 0.05

typedef struct sl_run {
    double r, count, wavelength, zc, zmax;
    int32_t nv;
    tp_loop_stats ls;
    wr_status st, sp;
    double *pts, *zv; /* the probe, kept for the figure */
} sl_run;

static void stvk_loop_run(sl_run *o) {
    wr_diag d;
    wr_mesh m;
    wr_shell sh;
    wr_shell_desc sd;
    tp_clamps cl;
    wr_spectrum_result sr;
    double *x = NULL, *zf = NULL, A[2] = {0.0, 0.5 * H_SHEET}, B[2] = {L_SHEET, 0.5 * H_SHEET}, ds = 0.0;
    int32_t v;
    o->count = o->wavelength = o->zc = o->zmax = NAN;
    o->sp = WR_ERR_INVALID_ARG;
    memset(&d, 0, sizeof d);
    if ((o->st = wr_scene_mesh_delaunay(&m, L_SHEET, H_SHEET, o->r, 1, &d)) != WR_OK) {
        fprintf(stderr, "stvk-loop mesh: %s\n", d.message);
        return;
    }
    o->nv = m.nv;
    tp_loop_shell_desc(YOUNG, NU, THICK, &sd);
    if ((o->st = wr_shell_create(&sh, &m, &sd, &d)) != WR_OK) {
        fprintf(stderr, "stvk-loop shell: %s\n", d.message);
        wr_mesh_free(&m);
        return;
    }
    x = (double *)malloc(sizeof(double) * 3 * (size_t)m.nv);
    zf = (double *)malloc(sizeof(double) * (size_t)m.nv);
    o->pts = (double *)malloc(sizeof(double) * 2 * NPROBE);
    o->zv = (double *)malloc(sizeof(double) * NPROBE);
    if (!x || !zf || !o->pts || !o->zv || (o->st = tp_clamps_select(&cl, &m, 1, 0.0, H_SHEET, &d)) != WR_OK) {
        if (!x || !zf || !o->pts || !o->zv) o->st = WR_ERR_NOMEM;
        free(x), free(zf);
        wr_shell_free(&sh);
        wr_mesh_free(&m);
        return;
    }
    cl.mo[1].kind = WR_MOTION_TRANSLATE;
    cl.mo[1].vec[0] = SHEAR;
    o->st = tp_loop_solve(&sh, &m, &cl, 4, 0.1 * THICK, 1, 200, x, &o->ls, &d);
    if (o->st == WR_OK || o->st == WR_ERR_NOT_CONVERGED) {
        for (v = 0; v < m.nv; ++v) zf[v] = x[3 * v + 2];
        o->zmax = tp_max_abs(zf, m.nv);
        o->sp = tp_line_field(&m, zf, A, B, NPROBE, o->pts, &ds, o->zv, &sr, &d);
        if (!o->sp) o->count = sr.count, o->wavelength = sr.wavelength, o->zc = sr.zc_waves;
    }
    tp_clamps_free(&cl);
    free(x), free(zf);
    wr_shell_free(&sh);
    wr_mesh_free(&m);
}

/* the result file from the meshes run so far (rewritten after each; a mesh not run has nv 0) */
static int stvk_loop_report(const sl_run *R) {
    wr_vres *v;
    char buf[512], table[3072];
    size_t off = 0;
    int i, ok, conv;
    double dc = NAN, dl = NAN;
    ok = R[SL_NRUN - 2].st == WR_OK && R[SL_NRUN - 1].st == WR_OK && !R[SL_NRUN - 2].sp && !R[SL_NRUN - 1].sp;
    if (ok) {
        dc = fabs(R[SL_NRUN - 1].count - R[SL_NRUN - 2].count) / R[SL_NRUN - 1].count;
        dl = fabs(R[SL_NRUN - 1].wavelength - R[SL_NRUN - 2].wavelength) / R[SL_NRUN - 1].wavelength;
    }
    conv = ok && dc <= SL_REL && dl <= SL_REL;
    v = wr_vres_begin("tfw_sheared_rectangle_stvk_loop",
                      "TFW Sec. 6 sheared rectangle: the StVK reference with the Loop element (issue 15)");
    snprintf(buf, sizeof buf, "wrinkles along the mid-line (FFT count), StVK + Loop element, %d vertices, counted only if converged",
             (int)R[SL_NRUN - 1].nv);
    wr_vres_range(v, buf, "wrinkles", 13.0, conv ? R[SL_NRUN - 1].count : NAN, 11.0, 15.0);
    snprintf(buf, sizeof buf, "StVK + Loop: relative change of the count between the %.1f and %.1f mm meshes (both solves WR_OK)",
             1e3 * R[SL_NRUN - 2].r, 1e3 * R[SL_NRUN - 1].r);
    wr_vres_check(v, buf, "", NAN, ok ? dc : NAN, "<= 0.05 (issue 15)", ok && dc <= SL_REL);
    snprintf(buf, sizeof buf, "StVK + Loop: relative change of the wavelength between the %.1f and %.1f mm meshes (both solves WR_OK)",
             1e3 * R[SL_NRUN - 2].r, 1e3 * R[SL_NRUN - 1].r);
    wr_vres_check(v, buf, "", NAN, ok ? dl : NAN, "<= 0.05 (issue 15)", ok && dl <= SL_REL);
    for (i = 0; i < SL_NRUN; ++i) {
        snprintf(buf, sizeof buf, "wrinkles along the mid-line (FFT count), StVK + Loop, %d vertices (r %.2f mm)", (int)R[i].nv,
                 1e3 * R[i].r);
        wr_vres_info(v, buf, "wrinkles", 13.0, R[i].count);
        snprintf(buf, sizeof buf, "wavelength along the mid-line (FFT), StVK + Loop, %d vertices", (int)R[i].nv);
        wr_vres_info(v, buf, "mm", NAN, 1e3 * R[i].wavelength);
        snprintf(buf, sizeof buf, "TFW paper's count (25) vs StVK + Loop, %d vertices", (int)R[i].nv);
        wr_vres_info(v, buf, "wrinkles", 25.0, R[i].count);
    }
    off += (size_t)snprintf(table + off, sizeof table - off,
                            "| r [mm] | vertices | status | Newton | escapes | negative modes | wrinkles (FFT) | zero-crossing waves | wavelength [mm] | peak abs z [mm] | solve [s] |\n"
                            "|---|---|---|---|---|---|---|---|---|---|---|\n");
    for (i = 0; i < SL_NRUN; ++i)
        off += (size_t)snprintf(table + off, sizeof table - off, "| %.2f | %d | %s | %d | %d | %d | %.2f | %.1f | %.2f | %.3f | %.0f |\n",
                                1e3 * R[i].r, (int)R[i].nv, R[i].nv ? wr_status_string(R[i].st) : "not run yet", (int)R[i].ls.newton, (int)R[i].ls.escapes,
                                (int)R[i].ls.modes, R[i].count, R[i].zc, 1e3 * R[i].wavelength, 1e3 * R[i].zmax, R[i].ls.t);
    wr_vres_table_md(v, table);
    wr_vres_note(v, "Set-up as the TFW rows (Kapton 380 x 128 mm, 25 um, E = 3530 MPa, nu = 0.3, bottom edge clamped, top "
                    "edge translated 3 mm, short edges free), but a full StVK simulation: StVK membrane + Koiter bending on "
                    "the Loop limit surface (shell.h loop_element 1; faces with a boundary corner keep linear StVK + mid-edge "
                    "bending), Poisson + Delaunay meshes (seed 1), 4 load steps, hybrid Newton to 1e-8, a 2.5 um seeded kick "
                    "and statics.h's stability test at every step.");
    wr_vres_note(v, "Metric (fixed before the runs): the TFW rows' probe, 1024 samples along y = 64 mm (rest domain) of the "
                    "equilibrium's z, FFT count = 0.38 m / wavelength. Converged = both solves WR_OK and count and "
                    "wavelength within 5 % between the two finest meshes; the pass row (TFW paper's StVK 13 +- 2, band set before the "
                    "run) takes the finest count only when converged.");
    if (!conv) wr_vres_note(v, "NOT CONVERGED by the 5 % rule (or a solve did not end WR_OK): the pass row is a miss.");
    for (i = SL_NRUN - 1; i >= 0 && !(R[i].pts && R[i].nv > 0 && !R[i].sp); --i) continue;
    if (i >= 0) /* the finest mesh run so far */
        tp_profile_figure(v, "tfw_sheared_rectangle_stvk_loop", R[i].pts, 2, R[i].zv, NPROBE, "x along the mid-line [mm]",
                          "z [mm]", "StVK + Loop element, sheared rectangle, y = 64 mm", "StVK + Loop element",
                          "StVK + Loop equilibrium: z along the horizontal mid-line (finest mesh run)");
    return wr_vres_finish(v);
}

static int stvk_loop_main(void) {
    static const double res[SL_NRUN] = {5.0e-3, 3.75e-3, 2.8e-3, 2.1e-3, 1.6e-3};
    sl_run R[SL_NRUN];
    int i, rc = 0;
    memset(R, 0, sizeof R);
    for (i = 0; i < SL_NRUN; ++i) R[i].count = R[i].wavelength = R[i].zc = R[i].zmax = NAN, R[i].st = WR_ERR_NOT_CONVERGED;
    for (i = 0; i < SL_NRUN; ++i) {
        R[i].r = res[i];
        stvk_loop_run(&R[i]);
        rc = stvk_loop_report(R);
    }
    for (i = 0; i < SL_NRUN; ++i) free(R[i].pts), free(R[i].zv);
    return rc < 0 ? 1 : 0;
}

int main(int argc, char **argv) {
    static const char *const flags[] = {"--stvk-loop", NULL};
    int set[1];
    int rc = wr_vargs(argc, argv, "validate_tfw_sheared_rectangle",
                      "TFW Sec. 6 sheared rectangle (Fig. 9): wrinkle count.",
                      "tfw_sheared_rectangle", flags,
                      "  --stvk-loop: instead, the StVK reference with the Loop element on Delaunay meshes of 5 to 1.6 mm\n"
                      "    (tfw_sheared_rectangle_stvk_loop.json; ~1.5 CPU hours, make validate-long).\n", set);
    if (rc >= 0) return rc;
    return set[0] ? stvk_loop_main() : validation_main();
}
