/* validate_statics_stability — issue 15 (first half): bifurcation-aware statics on the stretch test.
 *
 * The stretched sheet of Style3D Fig. 16 / validate_stretch (examples/scenes/stretch.json: 0.25 × 0.1 m,
 * h = 0.1 mm, E = 1 MPa, ν = 0.5, short edges clamped, 12.78 % stretch in 4 load steps, StVK +
 * mid-edge bending, 10 µm seeded kick at the first step, hybrid Newton, CHOLMOD), solved with and
 * without statics.h's stability test (ON STABILITY: after each load step the true Hessian's lowest
 * eigenpairs, K v = λ A v with A the rest vertex areas, λ in Pa/m; escape along a negative mode).
 * "Without" runs the same solve with stability.check = 2 (test and report only: the same iterates,
 * plus the eigenvalues of every step's equilibrium); "with" runs check = 1 and perturb_each = 1.
 *
 * Metrics, defined before the runs:
 *   A. Aligned union-jack grid at 5 mm (1071 vertices; validate_stretch's 5 mm grid row), twice: with
 *      the scene's kick at the first step (as validate_stretch) and with no kick at all (start.perturb
 *      = 0: the flat start is then an exact equilibrium path, every out-of-plane force vanishing by
 *      symmetry; the "unstable flat state carried to full load"). Reported for both, with and
 *      without the test: the lowest eigenvalue at every step, whether the sheet wrinkles (peak
 *      out-of-plane |w| >= 1 µm = h/100, validate_stretch's FLAT_AMPLITUDE), crest count (W / FFT
 *      wavelength, median of 5 probes across the width at L/2 + k L/20, as validate_stretch),
 *      amplitude, Π. Pass bands: (1) "with": no eigenvalue below the tolerance at full load (a stable
 *      equilibrium); (2) "with": Π at full load <= Π "without" + 1e-12 |Π| (an escape is kept only when
 *      it lowers Π). Reported: the 2 r_opt grid (8.33 mm, 403 vertices, flat in validate_stretch) with
 *      the kick, without the test: is its flat state unstable or a minimum? (--grid MM: another grid
 *      resolution for the pair; --only-grid: the grid rows alone, for scans.)
 *   B. Poisson + Delaunay meshes (the scene's delaunay_rectangle, seed 1) of r = 2.5, 1.8, 1.3, 1.0
 *      mm (about 5k, 10k, 19k, 31k vertices; --quick: 2.5 mm only; --big adds 0.8 mm, ~49k): the
 *      lowest eigenvalue of the full-load equilibrium (flat on these meshes: linear-triangle locking,
 *      validate_stretch) against the vertex count, reported (issue 15 expects the flat state's Hessian
 *      to become indefinite between 26k and 49k vertices). The 2.5 mm mesh also with the option: does
 *      it wrinkle (reported).
 * Writes validation/results/statics_stability.json. Exit = failed quantities, 2 on errors.
 * Options: --quick, --big, --grid MM, --only-grid, --help.
 */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"
#include "scene.h"
#include "stretch_probe.h"
#include "vresult.h"

#define SCENE_PATH "examples/scenes/stretch.json"
#define FLAT_AMPLITUDE 1.0e-6 /* m, h/100 (validate_stretch) */
#define ENERGY_SLACK 1e-12    /* relative: Π(with) <= Π(without) up to round-off */
#define MAXSTEP 8
#define GRID_DEFAULT_MM 5.0 /* the aligned-grid case of metric A (see the top block) */

typedef struct srow {
    const char *label;
    int delaunay, check, final_only; /* final_only: solve without the test, then test the last state only */
    int no_kick;                     /* 1: start.perturb = 0 (the flat start is an exact equilibrium path) */
    double r;
    int32_t nv;
    wr_status status;
    int ok, flat, newton, steps;
    double lam_step[MAXSTEP], lam_first_step[MAXSTEP]; /* lowest eigenvalue per step: at its end, before escapes */
    int32_t neg_step[MAXSTEP];
    double lam_final, energy, amplitude, count, wavelength, t_solve, t_stab, drop;
    int32_t neg_final, escapes, modes, checks;
} srow;

/* median count and wavelength over the probes (stretch_probe.h, validate_stretch's definition);
 * amplitude at L/2; flat = the whole sheet's peak |w| below FLAT_AMPLITUDE */
static void measure(const wr_scene_run *run, srow *R) {
    double zmax;
    sp_measure(run, &R->count, &R->wavelength, &R->amplitude, &zmax, NULL);
    R->flat = zmax < FLAT_AMPLITUDE;
    if (R->flat) R->count = 0.0, R->wavelength = NAN;
}

static int run_row(const wr_scene *base, srow *R) {
    wr_scene sc = *base;
    wr_scene_run run;
    wr_diag d;
    int32_t k;
    sc.mesh.resolution = R->r;
    sc.mesh.nx = sc.mesh.ny = 0;
    if (R->delaunay) sc.mesh.kind = WR_SCENE_MESH_DELAUNAY_RECTANGLE, sc.mesh.seed = 1;
    sp_place_probes(&sc, base);
    memset(&sc.stability, 0, sizeof sc.stability);
    sc.stability.check = R->final_only ? 0 : R->check;
    if (R->no_kick) sc.perturb = 0.0;
    sc.stability.perturb_each = R->check == 1;
    if (wr_scene_run_create(&run, &sc, &d) != WR_OK) {
        fprintf(stderr, "validate_statics_stability: %s\n", d.message);
        return -1;
    }
    R->nv = run.mesh.nv;
    fprintf(stderr, "== %s %s, stability %s: r = %.3f mm, %d vertices\n", R->delaunay ? "delaunay" : "grid", R->label,
            R->check == 1 ? "ON" : "report-only", 1e3 * R->r, (int)R->nv);
    R->status = wr_scene_run_solve(&run, sp_progress, NULL, &d);
    wr_cli_progress_end();
    if (R->status != WR_OK) fprintf(stderr, "   solve: %s\n", d.message);
    R->t_solve = run.t_solve;
    R->newton = run.newton_iterations;
    R->steps = run.n_steps_done < MAXSTEP ? run.n_steps_done : MAXSTEP;
    R->t_stab = R->drop = 0.0;
    R->escapes = R->modes = R->checks = 0;
    for (k = 0; k < R->steps; ++k) {
        const wr_statics_stats *st = &run.steps[k].st;
        R->lam_step[k] = st->stability_n_eigs > 0 ? st->stability_eigs[0] : NAN;
        R->lam_first_step[k] = st->stability_lambda_first;
        R->neg_step[k] = st->stability_negative_first;
        R->t_stab += st->t_stability, R->drop += st->stability_energy_drop;
        R->escapes += st->stability_escapes, R->modes += st->stability_modes, R->checks += st->stability_checks;
        R->newton += st->stability_iterations;
    }
    R->ok = (R->status == WR_OK || R->status == WR_ERR_NOT_CONVERGED) && R->steps > 0;
    if (R->ok) {
        const wr_statics_stats *st = &run.steps[R->steps - 1].st;
        R->lam_final = R->lam_step[R->steps - 1];
        R->neg_final = st->stability_negative;
        R->energy = st->energy;
        if (R->final_only) {
            /* the full-load equilibrium's eigenvalues alone (statics.h wr_statics_stability_test) */
            wr_statics_desc sd;
            wr_statics_stats ss;
            memset(&sd, 0, sizeof sd);
            sd.loads.fixed = run.fixed; /* prescribed vertices are at their full-load targets in x */
            if (wr_statics_stability_test(&run.shell, run.x, &sd, &ss, &d) != WR_OK) {
                fprintf(stderr, "   stability test: %s\n", d.message);
                R->ok = 0;
            }
            R->lam_final = R->lam_step[R->steps - 1] = R->lam_first_step[R->steps - 1] = ss.stability_eigs[0];
            R->neg_final = ss.stability_negative;
            R->checks = ss.stability_checks, R->t_stab = ss.t_stability;
        }
        measure(&run, R);
        fprintf(stderr, "   %s count %.2f amplitude %.4f mm, Π %.9e J, λ_min %.4g Pa/m (%d negative), escapes %d (%d modes), "
                        "drop %.3e J, %d Newton, %.1f s (stability %.1f s)\n",
                R->flat ? "FLAT" : "wrinkled", R->count, 1e3 * R->amplitude, R->energy, R->lam_final, (int)R->neg_final,
                (int)R->escapes, (int)R->modes, R->drop, R->newton, R->t_solve, R->t_stab);
    }
    wr_scene_run_free(&run);
    return 0;
}

/* "lam1 / lam2 / …" per step (λ before escapes; the value after escapes in brackets when it moved) */
static void fmt_steps(char *b, size_t n, const srow *R) {
    size_t o = 0;
    int k;
    b[0] = 0;
    for (k = 0; k < R->steps && o + 40 < n; ++k) {
        o += (size_t)snprintf(b + o, n - o, "%s%.3g", k ? " / " : "", R->lam_first_step[k]);
        if (R->lam_step[k] != R->lam_first_step[k]) o += (size_t)snprintf(b + o, n - o, " [%.3g]", R->lam_step[k]);
    }
}

static void table(wr_vres *v, const srow *rows, int n) {
    char *md = (char *)malloc(65536), st[512];
    size_t o = 0;
    int i;
    if (!md) return;
    o += (size_t)snprintf(md + o, 65536 - o,
                          "| mesh | r [mm] | vertices | stability | λ_min per step before escapes [after] [Pa/m] | negative at full load | escapes (modes) | "
                          "energy drop [J] | wrinkles | count | amplitude [mm] | Π [J] | Newton | solve [s] | of it stability [s] |\n"
                          "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n");
    for (i = 0; i < n; ++i) {
        const srow *R = rows + i;
        if (!R->nv) continue;
        fmt_steps(st, sizeof st, R);
        o += (size_t)snprintf(md + o, 65536 - o,
                              "| %s %s | %.3f | %d | %s | %s | %d | %d (%d) | %.3e | %s | %.2f | %.4f | %.9e | %d | %.1f | %.1f |\n",
                              R->delaunay ? "Delaunay" : "grid", R->label, 1e3 * R->r, (int)R->nv,
                              R->check == 1 ? "on" : "off (report only)", st, (int)R->neg_final, (int)R->escapes, (int)R->modes,
                              R->drop, R->ok ? (R->flat ? "no (flat)" : "yes") : "solve failed", R->count, 1e3 * R->amplitude,
                              R->energy, R->newton, R->t_solve, R->t_stab);
    }
    wr_vres_table_md(v, md);
    free(md);
}

/* metric A for one mesh: rows off (report only) and on */
static void metrics_pair(wr_vres *v, const srow *off, const srow *on, const char *name) {
    char q[256];
    snprintf(q, sizeof q, "%s without the test: lowest eigenvalue at full load", name);
    wr_vres_info(v, q, "Pa/m", NAN, off->lam_final);
    snprintf(q, sizeof q, "%s without the test: wrinkles (1 = yes)", name);
    wr_vres_info(v, q, "", NAN, off->flat ? 0.0 : 1.0);
    snprintf(q, sizeof q, "%s without the test: crest count", name);
    wr_vres_info(v, q, "wrinkles", NAN, off->count);
    snprintf(q, sizeof q, "%s with the test: lowest eigenvalue at full load", name);
    wr_vres_info(v, q, "Pa/m", NAN, on->lam_final);
    snprintf(q, sizeof q, "%s with the test: negative eigenvalues at full load", name);
    wr_vres_check(v, q, "", NAN, on->ok ? on->neg_final : NAN, "0 (a stable equilibrium)", on->ok && on->neg_final == 0);
    snprintf(q, sizeof q, "%s with the test: wrinkles (1 = yes)", name);
    wr_vres_info(v, q, "", NAN, on->flat ? 0.0 : 1.0);
    snprintf(q, sizeof q, "%s with the test: crest count", name);
    wr_vres_info(v, q, "wrinkles", NAN, on->count);
    snprintf(q, sizeof q, "%s with the test: amplitude (peak-to-peak/2 at L/2)", name);
    wr_vres_info(v, q, "mm", NAN, 1e3 * on->amplitude);
    snprintf(q, sizeof q, "%s: Π with the test minus Π without", name);
    wr_vres_check(v, q, "J", NAN, on->energy - off->energy, "<= 1e-12 x abs(Π without)",
                  on->ok && off->ok && on->energy <= off->energy + ENERGY_SLACK * fabs(off->energy));
}

static void usage(FILE *f) {
    fprintf(f, "usage: validate_statics_stability [--quick] [--big] [--grid MM] [--only-grid]\n"
               "  the stretch test with and without statics.h's stability test (issue 15);\n"
               "  writes validation/results/statics_stability.json. --quick: Delaunay 2.5 mm only;\n"
               "  --big: adds the 0.8 mm (~49k vertex) Delaunay mesh; --grid MM: the grid case's resolution\n"
               "  in (0.5, 50) (default 5 mm); --only-grid: run the grid rows only (no result file).\n");
}

int main(int argc, char **argv) {
    wr_scene base;
    wr_diag d;
    wr_resolution_model mdl = wr_resolution_model_paper();
    double B, r_opt;
    srow rows[16];
    static const double dres[] = {2.5e-3, 1.8e-3, 1.3e-3, 1.0e-3, 0.8e-3};
    static const char *const dlab[] = {"2.5 mm", "1.8 mm", "1.3 mm", "1.0 mm", "0.8 mm"};
    int quick = 0, big = 0, only_grid = 0, i, n = 0, nd, failed;
    double grid_mm = 0.0;
    int grid_given = 0;
    wr_vres *v;
    {
        /* cli.h's strict parsing: a malformed or out-of-range value is an error (exit 2), never a 0
         * that runs and rewrites the result file */
        const wr_cli_opt opts[] = {
            {"--quick", NULL, WR_CLI_FLAG, &quick, 0.0, 0.0, NULL},
            {"--big", NULL, WR_CLI_FLAG, &big, 0.0, 0.0, NULL},
            {"--grid", NULL, WR_CLI_NUMBER, &grid_mm, 1.0, 0.0, &grid_given}, /* lo > hi: the open range below */
            {"--only-grid", NULL, WR_CLI_FLAG, &only_grid, 0.0, 0.0, NULL},
        };
        wr_cli_set_program(argv[0]);
        if ((i = wr_cli_parse(argc, argv, opts, (int)(sizeof opts / sizeof opts[0]), NULL, 0, NULL, usage)) <= 0)
            return i < 0 ? WR_CLI_EXIT_USAGE : 0;
        if (grid_given && !(grid_mm > 0.5 && grid_mm < 50.0)) {
            wr_cli_error("--grid must be in (0.5, 50) mm, got '%g'", grid_mm);
            return WR_CLI_EXIT_USAGE;
        }
    }
    if (wr_scene_load(&base, SCENE_PATH, &d) != WR_OK) {
        fprintf(stderr, "validate_statics_stability: %s\n", d.message);
        return 2;
    }
    if (wr_kl_bending(base.shell.young, base.shell.thickness, base.shell.poisson, &B, &d) != WR_OK ||
        wr_resolution_from_BE(&mdl, B, base.shell.young, NULL, &r_opt, &d) != WR_OK) {
        fprintf(stderr, "validate_statics_stability: %s\n", d.message);
        return 2;
    }
    memset(rows, 0, sizeof rows);
    {
        static char glab[2][48];
        double rg = grid_mm > 0.0 ? 1e-3 * grid_mm : GRID_DEFAULT_MM * 1e-3;
        snprintf(glab[0], sizeof glab[0], "%.2f mm, no kick", 1e3 * rg);
        snprintf(glab[1], sizeof glab[1], "%.2f mm, kick", 1e3 * rg);
        rows[n].label = glab[0], rows[n].r = rg, rows[n].check = 2, rows[n].no_kick = 1, n++;
        rows[n].label = glab[0], rows[n].r = rg, rows[n].check = 1, rows[n].no_kick = 1, n++;
        rows[n].label = glab[1], rows[n].r = rg, rows[n].check = 2, n++;
        rows[n].label = glab[1], rows[n].r = rg, rows[n].check = 1, n++;
    }
    if (only_grid) {
        for (i = 0; i < n; ++i)
            if (run_row(&base, rows + i) != 0) return 2;
        wr_scene_free(&base);
        return 0;
    }
    rows[n].label = "2 r_opt, kick", rows[n].r = 2.0 * r_opt, rows[n].check = 2, n++;
    rows[n].label = dlab[0], rows[n].r = dres[0], rows[n].delaunay = 1, rows[n].check = 1, n++;
    nd = quick ? 1 : (big ? 5 : 4);
    for (i = 0; i < nd; ++i)
        rows[n].label = dlab[i], rows[n].r = dres[i], rows[n].delaunay = 1, rows[n].check = 2, rows[n].final_only = 1, n++;
    for (i = 0; i < n; ++i)
        if (run_row(&base, rows + i) != 0) return 2;
    v = wr_vres_begin("statics_stability", "Bifurcation-aware statics: the stretch test with and without the stability test");
    {
        char gname[2][80];
        snprintf(gname[0], sizeof gname[0], "grid %s", rows[0].label);
        snprintf(gname[1], sizeof gname[1], "grid %s", rows[2].label);
        metrics_pair(v, rows + 0, rows + 1, gname[0]);
        metrics_pair(v, rows + 2, rows + 3, gname[1]);
    }
    wr_vres_info(v, "grid 2 r_opt, kick, without the test: lowest eigenvalue at full load", "Pa/m", NAN, rows[4].lam_final);
    wr_vres_info(v, "grid 2 r_opt, kick, without the test: wrinkles (1 = yes)", "", NAN, rows[4].flat ? 0.0 : 1.0);
    wr_vres_info(v, "Delaunay 2.5 mm with the test: wrinkles (1 = yes)", "", NAN, rows[5].flat ? 0.0 : 1.0);
    wr_vres_info(v, "Delaunay 2.5 mm with the test: escapes", "", NAN, rows[5].escapes);
    wr_vres_info(v, "Delaunay 2.5 mm with the test: lowest eigenvalue at full load", "Pa/m", NAN, rows[5].lam_final);
    for (i = 6; i < n; ++i) {
        char q[160];
        snprintf(q, sizeof q, "Delaunay %s (%d vertices): lowest eigenvalue of the full-load state", rows[i].label, (int)rows[i].nv);
        wr_vres_info(v, q, "Pa/m", NAN, rows[i].lam_final);
    }
    table(v, rows, n);
    wr_vres_note(v, "Setup: examples/scenes/stretch.json as validate_stretch runs it (4 load steps, 10 um kick at the first step, "
                    "hybrid Newton to 1e-8, CHOLMOD); 'without' = stability.check 2 (the same iterates, each step's equilibrium "
                    "analysed), 'with' = check 1 + perturb_each (the kick at every step, seed + k - 1). Eigenvalues: the true "
                    "Hessian K of the StVK + mid-edge energy on the free DOFs, K v = lambda A v, A = rest vertex areas "
                    "(eigen.h: CHOLMOD LDL' inertia + ARPACK shift-invert Lanczos, 4 lowest pairs); negative = below "
                    "-1e-9 x mean diag(K)/mean(A). Escape: the lowest negative mode scaled to a largest vertex displacement "
                    "of h = 0.1 mm, both signs re-solved, the lower energy kept if below the unperturbed one.");
    wr_vres_note(v, "Machine: the shared 2-core AMD EPYC box, OMP/OpenBLAS threads 1; times are wall seconds under the "
                    "session's load (six engineers).");
    failed = wr_vres_finish(v);
    wr_scene_free(&base);
    return failed < 0 ? 2 : failed;
}
