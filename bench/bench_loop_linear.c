/* bench_loop_linear — issue 15's bench: time to a converged wrinkle wavelength on the stretched sheet
 * with the Loop-subdivision element (shell.h ON THE LOOP ELEMENT) against the linear element
 * (constant-strain StVK + mid-edge bending), in the same run.
 *
 * Problem: examples/scenes/stretch.json (0.25 × 0.1 m, h 0.1 mm, E 1 MPa, ν 0.5, short edges clamped,
 * 12.78 % stretch in 4 load steps, 10 µm seeded kick, hybrid Newton to 1e-8, CHOLMOD), the scene's
 * Poisson + Delaunay meshes (seed 1), and for BOTH elements the same solver options, statics.h's
 * stability test after every load step (check 1, perturb_each 1): without it the linear element stays
 * on the flat saddle at 31k vertices (validate_statics_stability), so a comparison without it would
 * charge the linear element nothing for a wrong answer.
 *
 * Ladders (Delaunay r, about N vertices):
 *   Loop   3.5, 2.5, 1.8 mm (2.6k, 5k, 9.7k; validate_statics_loop's meshes), and 1.3 mm (18k) only
 *          when 2.5 → 1.8 has not converged;
 *   linear r = 1.0 mm (30926 / N)^{1/2} for N = 32k, 65k (validate_statics_fig7's meshes). The linear
 *          ladder starts at 32k because its flat state is a stable minimum up to 18k (lowest
 *          eigenvalue > 0, validate_statics_stability) and 16k is flat (validate_statics_fig7): the
 *          flat rungs it would also cost a user are NOT charged to it (in its favour).
 * CONVERGED (defined before the runs): rung k of a ladder is converged when rungs k and k + 1 both
 * solved (WR_OK), both wrinkle (peak |w| >= 1 µm), and both the crest count W / λ_FFT and the FFT
 * wavelength (median of 5 probes, stretch_probe.h, validate_statics_loop's metric) of rung k are within
 * 5 % of rung k + 1's (issue 15's band). TIME TO A CONVERGED WAVELENGTH = the solve times of the pair
 * (k, k + 1) that first agrees (what it costs to know the answer is converged); the whole ladder up to
 * k + 1 is printed too. Both in wall seconds (wr_scene_run t_solve) and process CPU seconds (steadier on
 * the shared box); the 1-minute load average is printed before every row.
 * Arguments: --no-65k (linear 32k only: the linear time to converged is then a lower bound with the
 * 65k rung's time extrapolated from the Loop-free fit t ~ N^p of the linear rungs that ran, p = 1.5
 * when only one ran), --loop-only, --help. Expensive: the default run takes about an hour on a
 * 2-core box (linear 65k dominates).
 */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "cli.h"
#include "scene.h"
#include "../validation/stretch_probe.h"

#define SCENE_PATH "examples/scenes/stretch.json"
#define FLAT_AMPLITUDE 1.0e-6 /* m, h/100 */
#define CONVERGED_REL 0.05    /* issue 15 */
#define MAXR 4

typedef struct brow {
    const char *label;
    int loop;
    double r;
    int ran, ok, flat, newton;
    int32_t nv;
    double count, wavelength, waves, zmax, t_wall, t_cpu, t_stab, load;
} brow;

static int run_row(const wr_scene *base, brow *R) {
    wr_scene sc;
    wr_scene_run run;
    wr_diag d;
    wr_status st;
    double p2p, c0;
    int32_t k;
    sp_delaunay_stability_scene(&sc, base, R->r, R->loop);
    if (wr_scene_run_create(&run, &sc, &d) != WR_OK) {
        fprintf(stderr, "bench_loop_linear: %s\n", d.message);
        return -1;
    }
    R->nv = run.mesh.nv;
    R->load = wr_cli_load1();
    c0 = wr_cli_cpu_seconds();
    st = wr_scene_run_solve(&run, NULL, NULL, &d);
    R->t_cpu = wr_cli_cpu_seconds() - c0;
    if (st != WR_OK) fprintf(stderr, "bench_loop_linear: %s: %s\n", R->label, d.message);
    R->ran = 1, R->ok = st == WR_OK;
    R->t_wall = run.t_solve;
    R->newton = run.newton_iterations;
    R->t_stab = 0.0;
    for (k = 0; k < run.n_steps_done; ++k)
        R->t_stab += run.steps[k].st.t_stability, R->newton += run.steps[k].st.stability_iterations;
    sp_measure(&run, &R->count, &R->wavelength, &p2p, &R->zmax, NULL);
    R->waves = sp_wave_periods(&run);
    R->flat = R->zmax < FLAT_AMPLITUDE;
    if (R->flat) R->count = R->waves = 0.0, R->wavelength = NAN;
    printf("%-7s %-9s %7d %5.2f %6.2f %6.1f %7.4f %5s %6d %8.1f %8.1f %8.1f %5.2f\n", R->loop ? "Loop" : "linear",
           R->label, (int)R->nv, R->count, 1e3 * R->wavelength, R->waves, 1e3 * R->zmax, R->ok ? "ok" : "FAIL",
           R->newton, R->t_wall, R->t_stab, R->t_cpu, R->load);
    fflush(stdout);
    wr_scene_run_free(&run);
    return 0;
}

/* CONVERGED of the top block, for rungs a (coarser) and b */
static int agrees(const brow *a, const brow *b) {
    return a->ran && b->ran && a->ok && b->ok && !a->flat && !b->flat &&
           fabs(a->count / b->count - 1.0) <= CONVERGED_REL && fabs(a->wavelength / b->wavelength - 1.0) <= CONVERGED_REL;
}

/* the first agreeing pair of a ladder: prints it and returns its wall time (NAN when none) */
static double summary(const char *name, const brow *L, int n, double *cpu) {
    int k;
    double ladder_w = 0.0, ladder_c = 0.0;
    *cpu = NAN;
    for (k = 0; k + 1 < n; ++k) {
        ladder_w += L[k].t_wall, ladder_c += L[k].t_cpu;
        if (agrees(L + k, L + k + 1)) {
            double w = L[k].t_wall + L[k + 1].t_wall, c = L[k].t_cpu + L[k + 1].t_cpu;
            ladder_w += L[k + 1].t_wall, ladder_c += L[k + 1].t_cpu;
            printf("%s: converged at %s (%d v) against %s (%d v): count %.2f vs %.2f, wavelength %.3f vs %.3f mm;\n"
                   "  time to converged (the pair) %.1f s wall, %.1f s CPU; whole ladder to %s %.1f s wall, %.1f s CPU\n",
                   name, L[k].label, (int)L[k].nv, L[k + 1].label, (int)L[k + 1].nv, L[k].count, L[k + 1].count,
                   1e3 * L[k].wavelength, 1e3 * L[k + 1].wavelength, w, c, L[k + 1].label, ladder_w, ladder_c);
            *cpu = c;
            return w;
        }
    }
    printf("%s: no converged pair among the rungs run\n", name);
    return NAN;
}

int main(int argc, char **argv) {
    wr_scene base;
    wr_diag d;
    brow loop[MAXR], lin[MAXR];
    int no65 = 0, loop_only = 0, nl = 0, nn = 0, i;
    double tl, tn, cl, cn;
    for (i = 1; i < argc; ++i) {
        if (strcmp(argv[i], "--no-65k") == 0) no65 = 1;
        else if (strcmp(argv[i], "--loop-only") == 0) loop_only = 1;
        else {
            fprintf(stderr, "usage: bench_loop_linear [--no-65k] [--loop-only]  (see the source's top block)\n");
            return strcmp(argv[i], "--help") == 0 ? 0 : 2;
        }
    }
    if (wr_scene_load(&base, SCENE_PATH, &d) != WR_OK) {
        fprintf(stderr, "bench_loop_linear: %s\n", d.message);
        return 1;
    }
    memset(loop, 0, sizeof loop), memset(lin, 0, sizeof lin);
    loop[nl].label = "3.5mm", loop[nl].r = 3.5e-3, loop[nl++].loop = 1;
    loop[nl].label = "2.5mm", loop[nl].r = 2.5e-3, loop[nl++].loop = 1;
    loop[nl].label = "1.8mm", loop[nl].r = 1.8e-3, loop[nl++].loop = 1;
    lin[nn].label = "32k", lin[nn++].r = 1.0e-3 * sqrt(30926.0 / 32e3);
    if (!no65) lin[nn].label = "65k", lin[nn++].r = 1.0e-3 * sqrt(30926.0 / 65e3);
    printf("stretched sheet, Delaunay seed 1, stability test on (check 1, perturb_each 1); one run per row\n");
    printf("element mesh      vertices crest  lam_mm  waves peak_mm  solve Newton wall_s   stab_s    cpu_s  load\n");
    for (i = 0; i < 3; ++i)
        if (run_row(&base, loop + i) != 0) return 1;
    if (!agrees(loop + 1, loop + 2)) {
        loop[nl].label = "1.3mm", loop[nl].r = 1.3e-3, loop[nl].loop = 1;
        if (run_row(&base, loop + nl++) != 0) return 1;
    }
    for (i = 0; !loop_only && i < nn; ++i)
        if (run_row(&base, lin + i) != 0) return 1;
    tl = summary("Loop", loop, nl, &cl);
    if (loop_only) return 0;
    tn = summary("linear", lin, nn, &cn);
    if (isnan(tn)) {
        /* lower bound: the last rung run + the next rung's time extrapolated (t ~ N^p) */
        double p = 1.5, tw, tc;
        const brow *a = lin + nn - 1;
        if (nn >= 2 && lin[nn - 2].t_wall > 0.0) p = log(a->t_wall / lin[nn - 2].t_wall) / log((double)a->nv / lin[nn - 2].nv);
        tw = a->t_wall * (1.0 + pow(2.0, p)), tc = a->t_cpu * (1.0 + pow(2.0, p));
        printf("linear: lower bound = %s measured + the next rung (2x vertices) extrapolated with t ~ N^%.2f: "
               "%.1f s wall, %.1f s CPU (extrapolated, not measured)\n", a->label, p, tw, tc);
        tn = tw, cn = tc;
    }
    if (!isnan(tl) && !isnan(tn))
        printf("ratio linear / Loop, time to converged: %.1fx wall, %.1fx CPU (issue 15 expects >= 5x)\n", tn / tl, cn / cl);
    wr_scene_free(&base);
    return 0;
}
