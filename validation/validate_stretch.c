/* validate_stretch — Style3D Fig. 16 stretch test (also TFW Sec. 6.4 / Wang et al. 2018).
 *
 * A 0.25 m × 0.1 m sheet, h = 0.1 mm, ν = 0.5, E = 1 MPa, short edges clamped, stretched 12.78 % along
 * its long edge (examples/scenes/stretch.json: StVK membrane + mid-edge bending, 4 load steps, seeded
 * 10 µm normal kick, hybrid projected→exact Newton, CHOLMOD). Two mesh families, each used at every
 * resolution (2.5 mm, r_opt, 2·r_opt, 5 mm; r_opt from Style3D Eq. 4, resolution.h paper calibration,
 * with B = E h³/(12(1−ν²)), Kirchhoff–Love): regular union-jack grids (wr_mesh_rectangle) and
 * unstructured Poisson-disk + Delaunay meshes (the scene's delaunay_rectangle, poisson.h +
 * triangulate.h, uniform sizing r) like the paper's own meshes. Wrinkles are counted on probes across
 * the full width near mid-length (out-of-plane displacement, spectrum.h): count = W / λ_FFT; a second,
 * reported-only count is the wrinkled band width / λ (the band is where |w| >= 10 % of its peak).
 * A row whose peak amplitude is below FLAT_AMPLITUDE is flat: it has no wrinkles (count 0), and the
 * spectrum of its sub-micrometre noise is not reported as a count.
 * Cerda–Mahadevan: λ = 2√π (B L²/T)^{1/4} with T = E h γ (tension per unit width from the imposed
 * strain γ = 0.1278) and L = 0.25 m (the sheet length).
 * Pass bands (issue 5), on the grid family (the only one that wrinkles at these resolutions; see the
 * notes): count(r_opt) within ±1 of count(2.5 mm); count(2.5 mm) within ±2 of the paper's 7;
 * λ(2.5 mm) within 20 % of Cerda–Mahadevan. A flat row fails every band it enters. Reported: amplitude (Wang et al. 2018: 0.35 mm), solve
 * times and the ratio t(2.5 mm)/t(r_opt) measured in this run.
 * Options: --quick (5 mm and r_opt only, for smoke tests). Exit = failed quantities, 2 on errors.
 */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "scene.h"
#include "stretch_probe.h"
#include "vresult.h"
#include "vargs.h"

#define SCENE_PATH "examples/scenes/stretch.json"
#define NPROBE SP_NPROBE
#define GAMMA 0.1278 /* imposed stretch (Style3D Fig. 16) */
#define PAPER_COUNT_25 7.0
#define WANG_AMPLITUDE 0.35e-3 /* m, TFW Sec. 6.4 quoting Wang et al. 2018 */
/* Peak out-of-plane amplitude [m] below which a solved sheet counts as flat: h/100. Wrinkled rows
 * here have 0.25-0.3 mm; flat rows (the 10 um seeded kick decayed) sit below 0.5 um, and their
 * spectrum is numerical noise whose "count" (5.6 on the old 2 r_opt row) means nothing. Set after
 * those results were seen (f7b8294): any threshold between 0.5 um and 0.25 mm splits the rows the
 * same way; h/100 is the round value inside that gap. */
#define FLAT_AMPLITUDE 1.0e-6
#define BAND_FRACTION 0.1 /* |w| >= 10 % of the probe's peak marks the wrinkled band */
#define NRES 4

typedef struct row {
    const char *label;
    int delaunay; /* 0 = union-jack grid, 1 = Poisson + Delaunay */
    double r, mean_edge;
    double band, band_count; /* wrinkled band width across y [m] at L/2 and band / λ */
    double zone_len;         /* rest length along x of the wrinkled zone (|w| >= 10 % of the sheet's peak) [m] */
    double grad_final, grad_ref; /* last load step: ‖∇Π_free‖ and its reference [N] */
    int flat, bad_steps;
    int32_t nv;
    double count, wavelength, wavelength_ls, zc_waves, amplitude, t_solve;
    double count_p[NPROBE], lambda_p[NPROBE], count_min, count_max; /* per probe line */
    int np;
    int newton;
    wr_status status;
    int ok;
} row;

static int run_row(const wr_scene *base, row *R, const char *datpath) {
    wr_scene sc = *base;
    wr_scene_run run;
    wr_spectrum_result res;
    wr_diag d;
    sc.mesh.resolution = R->r;
    sc.mesh.nx = sc.mesh.ny = 0;
    if (R->delaunay) sc.mesh.kind = WR_SCENE_MESH_DELAUNAY_RECTANGLE, sc.mesh.seed = 1;
    R->ok = 0;
    sp_place_probes(&sc, base); /* probe 0 stays at L/2 (profile, amplitude and zero crossings are read there) */
    if (wr_scene_run_create(&run, &sc, &d) != WR_OK) {
        fprintf(stderr, "validate_stretch: %s\n", d.message);
        return -1;
    }
    R->nv = run.mesh.nv;
    {
        /* mean rest edge length: what "resolution" means for each family (grid diagonals are √2 r) */
        double sum = 0.0;
        int32_t e;
        for (e = 0; e < run.mesh.ne; ++e) {
            const double *a = run.mesh.pos + 3 * run.mesh.edges[2 * e], *b = run.mesh.pos + 3 * run.mesh.edges[2 * e + 1];
            sum += sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) + (a[2] - b[2]) * (a[2] - b[2]));
        }
        R->mean_edge = run.mesh.ne ? sum / run.mesh.ne : 0.0;
    }
    fprintf(stderr, "== %s %s: r = %.3f mm, %d vertices, mean edge %.3f mm\n", R->delaunay ? "delaunay" : "grid", R->label,
            1e3 * R->r, (int)R->nv, 1e3 * R->mean_edge);
    R->status = wr_scene_run_solve(&run, sp_progress, NULL, &d);
    wr_cli_progress_end();
    R->t_solve = run.t_solve;
    R->newton = run.newton_iterations;
    {
        /* longitudinal extent of the wrinkles, in rest coordinates: Cerda–Mahadevan's L is the length
         * over which the tension straightens a wrinkle (K = T/L², from ∂x ζ ~ ζ/L), which their derivation
         * takes as the clamp distance; here we measure it for a reported-only comparison */
        double zmax = 0.0, xlo = 1e300, xhi = -1e300;
        int32_t i;
        for (i = 0; i < run.mesh.nv; ++i) zmax = fmax(zmax, fabs(run.x[3 * i + 2]));
        for (i = 0; i < run.mesh.nv; ++i)
            if (zmax >= FLAT_AMPLITUDE && fabs(run.x[3 * i + 2]) >= BAND_FRACTION * zmax)
                xlo = fmin(xlo, run.mesh.pos[3 * i]), xhi = fmax(xhi, run.mesh.pos[3 * i]);
        R->zone_len = xhi > xlo ? xhi - xlo : 0.0;
    }
    {
        int32_t k;
        R->bad_steps = 0;
        for (k = 0; k < run.n_steps_done; ++k) R->bad_steps += run.steps[k].status != WR_OK;
        if (run.n_steps_done > 0) {
            R->grad_final = run.steps[run.n_steps_done - 1].st.grad_norm;
            R->grad_ref = run.steps[run.n_steps_done - 1].st.grad_ref;
        }
    }
    if (R->status != WR_OK) fprintf(stderr, "   solve: %s\n", d.message);
    if (R->status == WR_OK || R->status == WR_ERR_NOT_CONVERGED) {
        if (wr_scene_run_probe(&run, 0, &res, &d) == WR_OK) {
            int32_t n = sc.probe[0].samples, i;
            double *pts = (double *)malloc(sizeof(double) * 2 * (size_t)n), *v = (double *)malloc(sizeof(double) * (size_t)n), ds;
            int k;
            R->np = 0;
            for (k = 0; k < NPROBE; ++k) {
                wr_spectrum_result rk;
                if (wr_scene_run_probe(&run, k, &rk, &d) != WR_OK) continue;
                R->count_p[R->np] = rk.count, R->lambda_p[R->np] = rk.wavelength, R->np++;
            }
            R->count = sp_median(R->count_p, R->np);
            R->wavelength = sp_median(R->lambda_p, R->np);
            R->count_min = R->count_max = R->count_p[0];
            for (k = 1; k < R->np; ++k) R->count_min = fmin(R->count_min, R->count_p[k]), R->count_max = fmax(R->count_max, R->count_p[k]);
            R->wavelength_ls = res.wavelength_ls;
            R->zc_waves = res.zc_waves;
            R->amplitude = res.amplitude_p2p;
            R->ok = 1;
            R->flat = R->amplitude < FLAT_AMPLITUDE;
            if (R->flat) R->count = R->count_min = R->count_max = 0.0, R->wavelength = NAN;
            if (pts && v && wr_scene_run_probe_samples(&run, 0, pts, v, &ds, &d) == WR_OK) {
                wr_afile f;
                double vmax = 0.0, ylo = 0.0, yhi = 0.0;
                int seen = 0;
                for (i = 0; i < n; ++i) vmax = fmax(vmax, fabs(v[i]));
                for (i = 0; i < n; ++i)
                    if (fabs(v[i]) >= BAND_FRACTION * vmax) {
                        if (!seen) ylo = pts[2 * i + 1], seen = 1;
                        yhi = pts[2 * i + 1];
                    }
                R->band = R->flat ? 0.0 : yhi - ylo;
                R->band_count = R->flat ? 0.0 : R->band / R->wavelength;
                if (wr_afile_open(&f, datpath, &d) == WR_OK) {
                    for (i = 0; i < n; ++i) fprintf(f.fp, "%.6e %.6e\n", 1e3 * pts[2 * i + 1], 1e3 * v[i]);
                    wr_afile_commit(&f, &d);
                }
            }
            free(pts);
            free(v);
        } else
            fprintf(stderr, "   probe: %s\n", d.message);
    }
    fprintf(stderr, "   %smedian count %.2f over %d probes [%.2f, %.2f] (zc at L/2 %.1f), lambda %.2f mm, band %.1f mm, amplitude %.4f mm, %d Newton, %.1f s, |g| %.2e N\n",
            R->flat ? "FLAT: " : "", R->count, R->np, R->count_min, R->count_max, R->zc_waves, 1e3 * R->wavelength, 1e3 * R->band,
            1e3 * R->amplitude, R->newton, R->t_solve, R->grad_final);
    wr_scene_run_free(&run);
    return 0;
}

static const char *fmt_count(char *b, size_t n, const row *R) {
    if (!R->nv) snprintf(b, n, "not run");
    else if (!R->ok) snprintf(b, n, "solve failed");
    else if (R->flat) snprintf(b, n, "0 (flat)");
    else snprintf(b, n, "%.2f", R->count);
    return b;
}

/* The sheet's constants and what the theory says of it. */
typedef struct stretch_case {
    wr_scene sc;
    double B, r_opt, lam_cm, T; /* Kirchhoff-Love bending, Style3D Eq. 4, Cerda-Mahadevan λ, tension per width */
    row rows[2 * NRES];         /* [0, NRES): grid, [NRES, 2 NRES): Delaunay; 2.5 mm, r_opt, 2 r_opt, 5 mm */
    char dat[2 * NRES][4096];   /* each row's probe profile */
} stretch_case;

#define NROWS (2 * NRES)
#define SHEET_L 0.25
#define SHEET_W 0.1

/* Loads the scene and derives B, r_opt (Eq. 4, paper calibration), T = E h γ and λ_CM; labels the rows. */
static int case_setup(stretch_case *c, wr_diag *d) {
    static const char *const lab[NRES] = {"2.5 mm", "r_opt", "2 r_opt", "5 mm"};
    wr_resolution_model mdl = wr_resolution_model_paper();
    double E, h, nu, rr[NRES];
    int i;
    if (wr_scene_load(&c->sc, SCENE_PATH, d) != WR_OK) return 0;
    E = c->sc.shell.young, h = c->sc.shell.thickness, nu = c->sc.shell.poisson;
    if (wr_kl_bending(E, h, nu, &c->B, d) != WR_OK || wr_resolution_from_BE(&mdl, c->B, E, NULL, &c->r_opt, d) != WR_OK) {
        wr_scene_free(&c->sc);
        return 0;
    }
    c->T = E * h * GAMMA;
    wr_cm_wavelength(c->B, c->T, SHEET_L, &c->lam_cm, d);
    fprintf(stderr, "B = %.4e N·m, r_opt = %.3f mm, Cerda–Mahadevan λ = %.2f mm (%.2f across W)\n", c->B, 1e3 * c->r_opt,
            1e3 * c->lam_cm, SHEET_W / c->lam_cm);
    rr[0] = 2.5e-3, rr[1] = c->r_opt, rr[2] = 2.0 * c->r_opt, rr[3] = 5.0e-3;
    memset(c->rows, 0, sizeof c->rows);
    for (i = 0; i < NROWS; ++i) {
        c->rows[i].label = lab[i % NRES];
        c->rows[i].r = rr[i % NRES];
        c->rows[i].delaunay = i >= NRES;
        snprintf(c->dat[i], sizeof c->dat[i], "%s/stretch_profile_%s%d.dat", wr_vres_dir(), c->rows[i].delaunay ? "del" : "",
                 i % NRES);
    }
    return 1;
}

/* Solves every row (--quick: r_opt and 5 mm only); 0 when a row cannot be run at all. */
static int case_run(stretch_case *c, int quick) {
    int i;
    for (i = 0; i < NROWS; ++i) {
        if (quick && (i % NRES == 0 || i % NRES == 2)) continue;
        if (run_row(&c->sc, &c->rows[i], c->dat[i]) != 0) return 0;
    }
    return 1;
}

static void report_table(wr_vres *v, const stretch_case *c) {
    char table[8192], buf[4096];
    int i;
    snprintf(table, sizeof table,
             "| mesh | r [mm] | mean edge [mm] | vertices | median count W/λ (5 probes) | count range | band [mm] | band/λ | zero-crossing waves (L/2) | median λ [mm] | amplitude [mm] | Newton | steps not converged | final abs. residual [N] | solve [s] |\n"
             "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n");
    for (i = 0; i < NROWS; ++i) {
        const row *R = &c->rows[i];
        if (!R->nv) continue;
        if (R->flat)
            snprintf(buf, sizeof buf, "| %s %s | %.3f | %.3f | %d | 0 (flat) | - | - | - | - | - | %.1e | %d | %d of %d | %.1e | %.1f |\n",
                     R->delaunay ? "Delaunay" : "grid", R->label, 1e3 * R->r, 1e3 * R->mean_edge, (int)R->nv,
                     1e3 * R->amplitude, R->newton, R->bad_steps, c->sc.load_steps, R->grad_final, R->t_solve);
        else
            snprintf(buf, sizeof buf, "| %s %s | %.3f | %.3f | %d | %.2f | %.2f-%.2f | %.1f | %.2f | %.1f | %.2f | %.3f | %d | %d of %d | %.1e | %.1f |\n",
                     R->delaunay ? "Delaunay" : "grid", R->label, 1e3 * R->r, 1e3 * R->mean_edge, (int)R->nv, R->count,
                     R->count_min, R->count_max, 1e3 * R->band, R->band_count, R->zc_waves, 1e3 * R->wavelength,
                     1e3 * R->amplitude, R->newton, R->bad_steps, c->sc.load_steps, R->grad_final, R->t_solve);
        strncat(table, buf, sizeof table - strlen(table) - 1);
    }
    wr_vres_table_md(v, table);
}

/* The pass bands of issue 5 (set before the runs) and the full run's reported rows. */
static void report_bands(wr_vres *v, const stretch_case *c, wr_diag *d) {
    const row *g25 = &c->rows[0], *gop = &c->rows[1];
    const int both = g25->ok && gop->ok && !g25->flat && !gop->flat;
    double lam_zone = NAN;
    char buf[256];
    int i;
    /* ±1 wrinkle between r_opt and 2.5 mm (the paper's claim that r_opt keeps the count), ±2 of the
     * paper's 7 at 2.5 mm, 20 % of the Cerda–Mahadevan λ (the scaling law's prefactor uncertainty as
     * the issue states it) */
    /* the "paper" column holds only printed values (issue 20): our 2.5 mm count and the
     * Cerda–Mahadevan formula are references, with their sources */
    wr_vres_check(v, "count at r_opt vs count at 2.5 mm (grid)", "wrinkles", NAN, gop->flat ? 0.0 : gop->count,
                  "within +-1", both && fabs(gop->count - g25->count) <= 1.0);
    wr_vres_reference(v, g25->flat ? 0.0 : g25->count, "our 2.5 mm grid solve (the paper's claim: r_opt keeps the count)");
    wr_vres_check(v, "count at 2.5 mm (grid)", "wrinkles", PAPER_COUNT_25, g25->flat ? 0.0 : g25->count,
                  "within +-2 of 7", g25->ok && !g25->flat && fabs(g25->count - PAPER_COUNT_25) <= 2.0);
    wr_vres_check(v, "wavelength at 2.5 mm vs Cerda-Mahadevan (grid)", "mm", NAN, 1e3 * g25->wavelength,
                  "within 20%", g25->ok && !g25->flat && fabs(g25->wavelength - c->lam_cm) <= 0.2 * c->lam_cm);
    wr_vres_reference(v, 1e3 * c->lam_cm, "formula: Cerda-Mahadevan lambda = 2 sqrt(pi) (B L^2 / T)^(1/4), L = sheet length "
                                          "(resolution.h wr_cm_wavelength)");
    wr_vres_info(v, "peak amplitude at 2.5 mm (grid; Wang et al. 2018)", "mm", 1e3 * WANG_AMPLITUDE, 1e3 * g25->amplitude);
    wr_vres_info(v, "wrinkled band / wavelength at 2.5 mm (grid; second count, reported only)", "wrinkles", NAN,
                 g25->band_count);
    if (g25->zone_len > 0.0) wr_cm_wavelength(c->B, c->T, g25->zone_len, &lam_zone, d);
    wr_vres_info(v, "wrinkled zone length along x at 2.5 mm (grid, rest coordinates)", "mm", NAN, 1e3 * g25->zone_len);
    wr_vres_info(v, "Cerda-Mahadevan wavelength with L = wrinkled zone length (diagnostic, reported only)", "mm", NAN,
                 1e3 * lam_zone);
    wr_vres_info(v, "count at 2 r_opt (grid; 0 = flat)", "wrinkles", NAN, c->rows[2].flat ? 0.0 : c->rows[2].count);
    wr_vres_info(v, "count at 5 mm (grid)", "wrinkles", 4.0, c->rows[3].flat ? 0.0 : c->rows[3].count);
    for (i = NRES; i < NROWS; ++i) {
        snprintf(buf, sizeof buf, "count at %s (Delaunay; 0 = flat)", c->rows[i].label);
        wr_vres_info(v, buf, "wrinkles", i == NRES ? PAPER_COUNT_25 : (i == NRES + 3 ? 4.0 : NAN),
                     c->rows[i].flat ? 0.0 : c->rows[i].count);
    }
    wr_vres_info(v, "solve time ratio t(2.5 mm) / t(r_opt), grid, same run", "", NAN, g25->t_solve / gop->t_solve);
    wr_vres_info(v, "vertex ratio n(2.5 mm) / n(r_opt), grid", "", NAN, (double)g25->nv / gop->nv);
    wr_vres_info(v, "solve time ratio t(2.5 mm) / t(r_opt), Delaunay, same run", "", NAN,
                 c->rows[NRES].t_solve / c->rows[NRES + 1].t_solve);
}

/* A note per row whose load steps did not all converge, then every row's count in one line. */
static void report_row_notes(wr_vres *v, const stretch_case *c) {
    char buf[4096], a[NRES][24], b4[NRES][24];
    int i;
    for (i = 0; i < NROWS; ++i) {
        const row *R = &c->rows[i];
        if (!R->nv || R->status == WR_OK) continue;
        snprintf(buf, sizeof buf, "%s %s row: %d of %d load steps ended %s (best iterate analysed; final residual %.1e N, reference %.1e N)",
                 R->delaunay ? "Delaunay" : "grid", R->label, R->bad_steps, c->sc.load_steps, wr_status_string(R->status),
                 R->grad_final, R->grad_ref);
        wr_vres_note(v, buf);
    }
    for (i = 0; i < NRES; ++i) fmt_count(a[i], sizeof a[i], &c->rows[i]), fmt_count(b4[i], sizeof b4[i], &c->rows[NRES + i]);
    snprintf(buf, sizeof buf, "Counts W/lambda: grid %s / %s / %s / %s, Delaunay %s / %s / %s / %s at 2.5 mm / r_opt / 2 r_opt / 5 mm "
             "(paper: 7 / 6 at its 3.8 mm / - / 4).", a[0], a[1], a[2], a[3], b4[0], b4[1], b4[2], b4[3]);
    wr_vres_note(v, buf);
}

/* What the meshes, the count and the solver are, and what was measured about why the counts differ. */
static void report_method_notes(wr_vres *v) {
    wr_vres_note(v, "Meshes: (grid) regular union-jack grids (wr_mesh_rectangle), nx = round(0.25/r), ny = round(0.1/r), vertex spacing r, "
                    "diagonals sqrt(2) r; (Delaunay) Poisson-disk samples with radius r plus constrained Delaunay (scene type "
                    "delaunay_rectangle, seed 1), mean edge = r. Same family at every resolution.");
    wr_vres_note(v, "Count = probe length / FFT wavelength on 512-sample probes across the full width at x = L/2 + k L/20, "
                    "k = -2..2 (out-of-plane displacement), median of the five (range in the table); amplitude at x = L/2. "
                    "Rows with peak amplitude < 1 um (h/100) are flat and get count 0: the old table counted the noise of the "
                    "flat 2 r_opt grid row as 5.57. Second count (reported, not used for a band): the wrinkled band width at L/2 "
                    "(|w| >= 10% of its peak) / lambda; the wrinkles fill only the middle of the width, so W/lambda overstates the "
                    "visible wrinkles. The zero-crossing column uses spectrum.h's hysteresis counter (0.3 of the largest "
                    "half-amplitude), which misses the weak outer waves.");
    wr_vres_note(v, "Solver: StVK + mid-edge bending, 4 load steps of the clamp motion, 10 um seeded normal kick at the first "
                    "step (3.2% strain), projected Newton to 1e-3 then exact-Hessian Newton to 1e-8 relative gradient, CHOLMOD.");
    wr_vres_note(v, "Why the grid counts are not consistent across resolutions (measured in this session, scratch runs): "
                    "at 5 mm and r_opt the grid wrinkle is the shortest wave the grid can carry, lambda = 10.8 mm = 2.2 cells at "
                    "5 mm and 9.1 mm = 2.2 cells at r_opt, not a physical wavelength; it is identical for kick seeds 1 and 2 "
                    "(count 10.95 both), i.e. selected by the grid, not by the perturbation. At 2.5 mm lambda = 12 mm = 4.8 cells. "
                    "The flat-vs-wrinkled energy difference is ~4e-7 J on the 5 mm grid, 25x smaller than the change of the flat "
                    "membrane energy between meshes (2.3936e-2 J grid 5 mm vs 2.3921e-2 J Delaunay 2.5 mm), so the "
                    "discretisation error, not the physics, decides the pattern at these resolutions.");
    wr_vres_note(v, "Delaunay meshes do not wrinkle at 5, 4.17, 2.5, 1.5 mm (13974 vertices) or even 1.1 mm (25885 vertices, "
                    "scratch runs, same solver settings): the flat state is a local "
                    "minimum there - a 0.3 mm random kick at full load, and a smooth 0.3 mm, 12 mm-wavelength wrinkle added to "
                    "the converged flat 2.5 mm state, both relax back to the flat energy with monotone projected Newton. "
                    "Likely cause: membrane locking of linear (constant-strain) triangles - on an unstructured mesh a "
                    "piecewise-linear wrinkle w(y) cannot bend without spurious in-plane strain, while grid rows aligned with "
                    "the crests fold for free. This matches TFW Sec. 6.4 / Fig. 7: StVK on Delaunay meshes shows no waves at 16k "
                    "vertices and 3 waves (0.17-0.31 mm) from 32k to 130k, and qualitatively right wrinkles only from 260k.");
    wr_vres_note(v, "Load-step sensitivity (grid r_opt, scratch runs): 4 and 16 load steps give the same pattern (count "
                    "10.95, lambda 9.13 mm, 0.255 mm; 16 steps: 752 Newton, one step NOT_CONVERGED), i.e. the coarse-grid "
                    "wavelength does not relax with more steps; with 8 steps the kick (applied at 1.6% strain) decayed and the "
                    "sheet stayed on the flat branch to 12.78% (amplitude < 1 um, a step NOT_CONVERGED near the flat saddle). "
                    "The static result depends on the loading path where the seeded kick lands.");
    wr_vres_note(v, "Cerda-Mahadevan inputs: lambda = 2 sqrt(pi) (B L^2/T)^(1/4) = (2 pi L h)^(1/2) / (3 (1-nu^2) gamma)^(1/4), "
                    "B = E h^3/(12(1-nu^2)) = 1.11e-7 N m, T = E h gamma = 12.78 N/m, L = 0.25 m: 17.1 mm, 5.8 waves across W. "
                    "Literature for this exact sheet (0.25 x 0.1 m, h = 0.1 mm, nu = 0.5, E = 1 MPa): TFW Sec. 6.4 reports 5 wave "
                    "periods and 0.42 mm peak amplitude from TFW, 'within 20% of Wang et al. 2018', i.e. about 5 waves across "
                    "0.1 m (lambda ~ 17-20 mm if the waves fill the width); StVK on fine Delaunay meshes (TFW Fig. 7) gives 3 "
                    "waves. Panaitescu et al. 2019 (arXiv:1906.10054) and Xin & Davidovitch 2021 (arXiv:2012.13051) confirm the "
                    "C-M scaling of the wavelength with tension but revisit its prefactor and the length entering it (stress, "
                    "not strain, collapses). So ~17 mm, not 12 mm, is the physical scale; our 12 mm at 2.5 mm (grid) is 30% "
                    "short, consistent with a grid-biased pattern at 4.8 cells per wave, and only fine meshes (>= 32k vertices "
                    "on Delaunay) could settle it - beyond this run's budget.");
    wr_vres_note(v, "Grid refinement (scratch run, same settings): a 150 x 60 grid (r = 1.67 mm, 9211 vertices) gives lambda "
                    "12.60 mm (7.6 cells per wave), count 7.94 on all five probes, amplitude 0.289 mm, but every load step "
                    "stopped at max_iter (final residual 1.4e-10 N; 810 Newton, 2144 s on the loaded box). So on grids lambda "
                    "stays at 12.0-12.6 mm from 4.8 to 7.6 cells per wave: the 30% gap to Cerda-Mahadevan is not (only) grid "
                    "under-resolution at 2.5 mm.");
    wr_vres_note(v, "Likely cause of the short wavelength: Cerda-Mahadevan's L is the length over which the tension "
                    "straightens a wrinkle (K = T/L^2) and their derivation takes the wrinkles to run clamp to clamp. In this "
                    "L/W = 2.5 sheet they occupy only the middle of the length (measured zone length in the table: |w| >= 10% "
                    "of the peak); C-M with that L gives the diagnostic wavelength listed above (reported only; the band keeps "
                    "L = 0.25 m as issue 5 specifies).");
    wr_vres_note(v, "TFT variant not run: the tension-field membrane has no compressive stiffness at all, so a flat "
                    "sheet is already its minimiser and it cannot buckle into wrinkles (it is TFW's coarse base "
                    "surface, not a reduced-compression StVK).");
}

/* The probe profiles across the width at mid-length, both mesh families, as one gnuplot figure. */
static void profile_figure(wr_vres *v, const stretch_case *c, wr_diag *d) {
    char figdir[4096], gp[4200], png[4200], cmd[9000];
    wr_afile f;
    int first = 1, i;
    snprintf(figdir, sizeof figdir, "%s/../figures", wr_vres_dir());
    snprintf(gp, sizeof gp, "%s/stretch.gp", figdir);
    snprintf(png, sizeof png, "%s/stretch.png", figdir);
    if (wr_afile_open(&f, gp, d) != WR_OK) return;
    /* eight curves: the key goes beside the frame, inside it covered the crests */
    fprintf(f.fp, "set terminal pngcairo size 1200,500 noenhanced\nset output '%s'\nset key outside right top\n", png);
    fprintf(f.fp, "set xlabel 'y across the width [mm]'\nset ylabel 'out-of-plane displacement [mm]'\n");
    fprintf(f.fp, "set title 'Stretch test, x = L/2 (solid: union-jack grid, dashed: Delaunay)'\nplot ");
    for (i = 0; i < NROWS; ++i) {
        const row *R = &c->rows[i];
        if (!R->ok) continue;
        fprintf(f.fp, "%s'%s' w l %st '%s %s (%.2f mm, %d vertices%s)'", first ? "" : ", ", c->dat[i],
                R->delaunay ? "dt 2 " : "", R->delaunay ? "Delaunay" : "grid", R->label, 1e3 * R->r, (int)R->nv,
                R->flat ? ", flat" : "");
        first = 0;
    }
    fprintf(f.fp, "\n");
    if (wr_afile_commit(&f, d) != WR_OK) return;
    snprintf(cmd, sizeof cmd, "gnuplot '%s' 2>/dev/null", gp);
    if (system(cmd) == 0) wr_vres_figure(v, "figures/stretch.png", "probe profiles across the width at mid-length, both mesh families");
    else wr_vres_note(v, "gnuplot failed; figure not drawn");
}

static int validation_main(int quick) {
    static stretch_case c; /* ~40 kB of paths: off the stack */
    wr_diag d;
    wr_vres *v;
    int failed;
    if (!case_setup(&c, &d)) {
        fprintf(stderr, "validate_stretch: %s\n", d.message);
        return 2;
    }
    v = wr_vres_begin("stretch", "Style3D Fig. 16 stretch test: wrinkle count vs mesh resolution (StVK statics)");
    if (!v || !case_run(&c, quick)) {
        wr_scene_free(&c.sc);
        return 2;
    }
    report_table(v, &c);
    wr_vres_info(v, "bending stiffness B (Kirchhoff-Love)", "N m", NAN, c.B);
    wr_vres_info(v, "r_opt (Style3D Eq. 4, paper calibration)", "mm", 3.8, 1e3 * c.r_opt);
    wr_vres_info(v, "Cerda-Mahadevan wavelength (T = E h gamma, L = 0.25 m)", "mm", NAN, 1e3 * c.lam_cm);
    if (!quick) {
        report_bands(v, &c, &d);
    } else {
        wr_vres_note(v, "--quick run: only r_opt and 5 mm were solved; the pass bands need the 2.5 mm row.");
        wr_vres_info(v, "count at r_opt (grid)", "wrinkles", 6.0, c.rows[1].flat ? 0.0 : c.rows[1].count);
        wr_vres_info(v, "count at 5 mm (grid)", "wrinkles", 4.0, c.rows[3].flat ? 0.0 : c.rows[3].count);
    }
    report_row_notes(v, &c);
    report_method_notes(v);
    profile_figure(v, &c, &d);
    wr_scene_free(&c.sc);
    failed = wr_vres_finish(v);
    return failed;
}

int main(int argc, char **argv) {
    static const char *const flags[] = {"--quick", NULL};
    int set[1], rc = wr_vargs(argc, argv, "validate_stretch",
                              "Style3D Fig. 16 stretch test: wrinkle count over mesh resolution (StVK statics).",
                              "stretch", flags, "  --quick: 5 mm and r_opt only (a smoke test).\n", set);
    return rc >= 0 ? rc : validation_main(set[0]);
}
