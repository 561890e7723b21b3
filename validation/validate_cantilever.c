/* validate_cantilever — Style3D Fig. 18a–c: a fabric strip (B = 2e-6 N·m, E = 1e6 N/m²) clamped
 * horizontally at one end sags under gravity; mesh resolutions 20 → 2.5 mm against the heavy-elastica
 * reference (validation/elastica_ref.h, GSL shooting).
 *
 * CLAMP. A clamp made of fixed vertices does not impose the slope with mid-edge bending (shell.h):
 * the mid-edge normal of an edge on the clamp line is the normalised average of the flat clamped face
 * and the first free face, i.e. it carries half the free face's rotation, so the clamp acts as a
 * partial hinge and the tip error falls only first-order in r (measured with one or two clamped cell
 * columns behind the clamp line, L = 25 mm: +9.2 % at 2.5 mm, +4.7 % at 1.25 mm, independent of the
 * strip width and of ν, and the same with two extra clamped columns). We impose the clamp by mirror
 * symmetry instead: a strip of length 2L whose CENTRE vertex column is fixed. Both halves are the same
 * cantilever; the regular union-jack grid is mirror-symmetric about every vertex column, so on the
 * clamp line the two adjacent face normals are mirror images and their average — the mid-edge normal —
 * is exactly vertical: zero slope, a true clamp. Measured: second-order convergence (5.6 %, 1.2 %,
 * 0.3 % at L/r = 5, 10, 20). The cost is twice the vertices.
 *
 * GEOMETRY (stated in the result file). Main sweep: free length L = 100 mm, width b = 25 mm (the
 * ASTM D1388 strip width; a length at which 20 mm is 5 cells, so the coarse end of the sweep means
 * something), areal density ρ_A = 0.0025 kg/m² so that the self-weight parameter κ = ρ_A g L³/B =
 * 12.3: a large deflection (tip ≈ 0.74 L) that is not a vertical hang. A real fabric (0.15 kg/m²) at
 * 100 mm would have κ = 736 and hang nearly straight down, making the tip insensitive to the mesh.
 * The main strip's geometry is OUR CHOICE (60× lighter than fabric), stated as such in its rows.
 * Second sweep (pass/fail rows since issue 20, the main strip's bands): the D1388-scale overhang
 * L = 25 mm with a real fabric's ρ_A = 0.15 kg/m² (κ = 11.5), the same problem at a quarter of the
 * length, so a given r is 4× coarser relative to L.
 * ν = 0.3, thickness from Kirchhoff–Love h = (12(1−ν²)B/E)^{1/3}. The elastica is a beam of rigidity
 * B per unit width; the plate's anticlastic coupling changes the tip by < 0.05 % here (measured ν = 0
 * vs 0.3 at L = 25 mm). StVK + mid-edge bending, full gravity in one solve, exact-Hessian Newton to
 * 1e-10 relative gradient (statics.h ON STOPPING), CHOLMOD, with the membrane continuation of
 * statics.h (membrane_ramp: first the equilibrium with the membrane ~1000× (main strip) or ~80×
 * (25 mm strip) softer, see CANT_SOFT_STRAIN, then the real shell). Without it every Newton step is limited to ~1–2 mm by the quartic stretch of a
 * linearised rotation, and the former protocol (5 gravity load steps through the scene runner) ended
 * WR_ERR_NOT_CONVERGED at r <= 5 mm after 460–990 Newton steps (1.25 mm: 991 steps, 369 s).
 * Reported per resolution: tip deflection (mean −z of both tip columns), its error against the
 * elastica, and the shape error (largest distance of a mesh vertex from the reference curve in the
 * (|x − x_clamp|, z) plane, / L). Pass (issue 5): tip deflection at r_opt within 2 % of the elastica
 * and within 1 % of the 2.5 mm solve, on both strips (issue 20); and the paper's "the curve flattens
 * at r_opt" read on each sweep (see the rows). Exit = failed quantities, 2 on errors.
 */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "elastica_ref.h"
#include "scene.h"
#include "vresult.h"
#include "vargs.h"

#define SCENE_PATH "examples/scenes/cantilever.json"
#define L_MAIN 0.100
#define RHOA_MAIN 0.0025 /* kg/m², see GEOMETRY */
#define L_SHORT 0.025
#define RHOA_SHORT 0.15
#define WIDTH 0.025
#define NREF 4001
#define NRES 10
#define I25 8 /* index of the 2.5 mm solve; 1.25 mm is an extra convergence row */
#define NSHORT 5
/* statics.h membrane_ramp s0 = ρ_A g L / (E h · CANT_SOFT_STRAIN): the soft stage stretches the strip
 * by ~1 % (its ON MEMBRANE CONTINUATION advice; 8.8e-4 for the main strip, 1.3e-2 for the 25 mm one,
 * where 1e-3 let the soft path fold the strip at the clamp) */
#define CANT_SOFT_STRAIN 0.01

typedef struct cant_case {
    double L, rhoA;
    elastica_ref_result er;
    double xr[NREF], yr[NREF];
} cant_case;

typedef struct cant_row {
    double r, tip, shape, t_solve;
    int32_t nv, newton;
    int stop; /* wr_newton_stop */
    wr_status st;
} cant_row;

/* One solve: strip of length 2L (nx cells per half), centre column clamped (see CLAMP); one_sided != 0
 * instead builds the former one-sided clamp (one clamped cell column behind x = 0), for the record. */
static int cant_solve(const wr_scene *base, const cant_case *cc, double r, int one_sided, cant_row *out) {
    wr_scene s2 = *base;
    wr_scene_run run;
    wr_diag d;
    int32_t nx = (int32_t)fmax(1.0, floor(cc->L / r + 0.5)), ny = (int32_t)fmax(1.0, floor(WIDTH / r + 0.5)), k;
    double cell = cc->L / nx, xc, sum = 0.0, cnt = 0.0, worst = 0.0;
    s2.shell.density = cc->rhoA / s2.shell.thickness;
    s2.areal_density = cc->rhoA;
    s2.mesh.height = WIDTH;
    s2.mesh.ny = ny;
    if (one_sided) {
        xc = cell;
        s2.mesh.width = cc->L + cell;
        s2.mesh.nx = nx + 1;
        s2.bc[0].box_lo[0] = -1.0;
        s2.bc[0].box_hi[0] = cell * (1.0 + 1e-9);
    } else {
        xc = cc->L;
        s2.mesh.width = 2.0 * cc->L;
        s2.mesh.nx = 2 * nx;
        s2.bc[0].box_lo[0] = cc->L - 1e-6 * cell;
        s2.bc[0].box_hi[0] = cc->L + 1e-6 * cell;
    }
    if (wr_scene_run_create(&run, &s2, &d) != WR_OK) {
        fprintf(stderr, "validate_cantilever: %s\n", d.message);
        return -1;
    }
    out->r = r;
    {
        /* the scene's material, mesh and clamp; one statics solve with the membrane continuation */
        wr_statics_desc sd;
        wr_statics_stats st;
        memset(&sd, 0, sizeof sd);
        for (k = 0; k < 3; ++k) sd.loads.gravity[k] = s2.gravity[k];
        sd.loads.fixed = run.fixed;
        sd.stop.grad_tol = s2.grad_tol;
        sd.stop.max_iter = s2.max_iter;
        sd.hessian.projection = s2.hessian == WR_SCENE_HESSIAN_EXACT ? WR_PROJECT_NONE : WR_PROJECT_FAST;
        sd.linear.solver.method = s2.linear;
        sd.continuation.membrane_ramp = fmin(0.1, cc->rhoA * fabs(s2.gravity[2]) * cc->L /
                                         (s2.shell.young * s2.shell.thickness * CANT_SOFT_STRAIN));
        out->st = wr_statics_solve(&run.shell, run.x, &sd, &st, &d);
        out->t_solve = st.t_total;
        out->newton = st.iterations;
        out->stop = (int)st.stop;
        if (out->st != WR_OK) fprintf(stderr, "validate_cantilever: %s\n", d.message);
    }
    out->nv = run.mesh.nv;
    for (k = 0; k < run.mesh.nv; ++k) {
        const double *X = run.mesh.pos + 3 * k, *x = run.x + 3 * k;
        double best = INFINITY, s = fabs(x[0] - xc), S = fabs(X[0] - xc);
        int32_t q;
        if (S > cc->L - 1e-6 * cell) { /* a tip vertex (either half) */
            sum += -x[2];
            cnt += 1.0;
        }
        if ((one_sided && X[0] < xc) ) continue; /* clamped band behind the clamp line */
        for (q = 0; q + 1 < NREF; ++q) {
            double ax = cc->xr[q], az = cc->yr[q], bx = cc->xr[q + 1], bz = cc->yr[q + 1];
            double ux = bx - ax, uz = bz - az, t = ((s - ax) * ux + (x[2] - az) * uz) / (ux * ux + uz * uz), dx, dz;
            t = t < 0 ? 0 : (t > 1 ? 1 : t);
            dx = s - (ax + t * ux), dz = x[2] - (az + t * uz);
            best = fmin(best, dx * dx + dz * dz);
        }
        worst = fmax(worst, sqrt(best));
    }
    out->tip = sum / cnt;
    out->shape = worst / cc->L;
    fprintf(stderr, "L %.0f mm, r %.2f mm%s: %d vertices, tip %.4f mm (err %+.3f%%), shape err %.3f%% L, %s, %d Newton, %.2f s\n",
            1e3 * cc->L, 1e3 * r, one_sided ? " (one-sided clamp)" : "", (int)out->nv, 1e3 * out->tip,
            100.0 * (out->tip / cc->er.tip_deflection - 1.0), 100.0 * out->shape, wr_status_string(out->st),
            (int)out->newton, out->t_solve);
    wr_scene_run_free(&run);
    return 0;
}

static int cant_ref(cant_case *cc, double B, double g) {
    char err[256];
    /* per unit width: D = B, q = ρ_A g (elastica_ref.h MODEL) */
    if (elastica_ref_solve(cc->L, B, cc->rhoA * g, 0.0, NREF, cc->xr, cc->yr, NULL, &cc->er, err, sizeof err) != 0) {
        fprintf(stderr, "validate_cantilever: elastica: %s\n", err);
        return -1;
    }
    fprintf(stderr, "elastica L = %.0f mm, rho_A = %g kg/m^2: kappa %.3f, tip deflection %.4f mm\n", 1e3 * cc->L, cc->rhoA,
            cc->er.kappa, 1e3 * cc->er.tip_deflection);
    return 0;
}

static void cant_table(wr_vres *v, const cant_case *cc, const cant_row *rows, int n, int i_opt, const char *title) {
    char table[8192], buf[512];
    int i;
    snprintf(table, sizeof table,
             "%s\n\n| r [mm] | L/r | vertices | tip deflection [mm] | error vs elastica | shape error / L | status | Newton | solve [s] |\n"
             "|---|---|---|---|---|---|---|---|---|\n", title);
    for (i = 0; i < n; ++i) {
        snprintf(buf, sizeof buf, "| %.2f%s | %.1f | %d | %.4f | %+.3f %% | %.3f %% | %s | %d | %.2f |\n", 1e3 * rows[i].r,
                 i == i_opt ? " (r_opt)" : "", cc->L / rows[i].r, (int)rows[i].nv, 1e3 * rows[i].tip,
                 100.0 * (rows[i].tip / cc->er.tip_deflection - 1.0), 100.0 * rows[i].shape, wr_status_string(rows[i].st),
                 (int)rows[i].newton, rows[i].t_solve);
        strncat(table, buf, sizeof table - strlen(table) - 1);
    }
    wr_vres_table_md(v, table);
}

/* The sweep index from which the tip "flattens": the coarsest row i such that every row i..last
 * (finer, up to the last) has |tip / ref - 1| <= tol; -1 when not even the last one does. ref <= 0
 * means the last row's own tip. */
static int coarsest_within(const cant_row *rows, int last, double ref, double tol) {
    int i, j, found = -1;
    if (!(ref > 0.0)) ref = rows[last].tip;
    for (i = last; i >= 0; --i) {
        int ok = 1;
        for (j = i; j <= last; ++j)
            if (fabs(rows[j].tip / ref - 1.0) > tol) ok = 0;
        if (!ok) break;
        found = i;
    }
    return found;
}

/* Both sweeps and their references: the main strip over res (n_main, r_opt at I_OPT) and the 25 mm
 * strip over sres (NSHORT, r_opt at 1), plus the former one-sided clamp at 2.5 mm for the record. */
typedef struct cant_run {
    wr_scene sc;
    double B, E, g, r_opt;
    double res[NRES], sres[NSHORT];
    cant_case cm, cs;
    cant_row rows[NRES], srows[NSHORT], hinge;
} cant_run;

#define I_OPT 4 /* r_opt's row in the main sweep (between 7.5 and 5 mm) */

/* Scene, r_opt (Eq. 4) and both elastica references; 0 on failure (said on stderr). */
static int run_setup(cant_run *R) {
    static const double res[NRES] = {20e-3, 15e-3, 10e-3, 7.5e-3, 0.0, 5e-3, 4e-3, 3e-3, 2.5e-3, 1.25e-3};
    static const double sres[NSHORT] = {10e-3, 0.0, 5e-3, 2.5e-3, 1.25e-3};
    wr_resolution_model mdl = wr_resolution_model_paper();
    wr_diag d;
    if (wr_scene_load(&R->sc, SCENE_PATH, &d) != WR_OK) {
        fprintf(stderr, "validate_cantilever: %s\n", d.message);
        return 0;
    }
    R->B = R->sc.shell.bending_stiffness, R->E = R->sc.shell.young, R->g = -R->sc.gravity[2];
    if (wr_resolution_from_BE(&mdl, R->B, R->E, NULL, &R->r_opt, &d) != WR_OK) {
        fprintf(stderr, "validate_cantilever: %s\n", d.message);
        return 0;
    }
    memcpy(R->res, res, sizeof res);
    memcpy(R->sres, sres, sizeof sres);
    R->res[I_OPT] = R->r_opt;
    R->sres[1] = R->r_opt;
    R->cm.L = L_MAIN, R->cm.rhoA = RHOA_MAIN;
    R->cs.L = L_SHORT, R->cs.rhoA = RHOA_SHORT;
    if (cant_ref(&R->cm, R->B, R->g) != 0 || cant_ref(&R->cs, R->B, R->g) != 0) return 0;
    fprintf(stderr, "r_opt %.3f mm\n", 1e3 * R->r_opt);
    return 1;
}

static int run_solves(cant_run *R) {
    int i;
    for (i = 0; i < NRES; ++i)
        if (cant_solve(&R->sc, &R->cm, R->res[i], 0, &R->rows[i]) != 0) return 0;
    for (i = 0; i < NSHORT; ++i)
        if (cant_solve(&R->sc, &R->cs, R->sres[i], 0, &R->srows[i]) != 0) return 0;
    return cant_solve(&R->sc, &R->cs, 2.5e-3, 1, &R->hinge) == 0;
}

/* Tip and shape errors per resolution of both sweeps, for the figure. */
static void write_dat(const cant_run *R, const char *dat) {
    wr_afile f;
    wr_diag d;
    int i;
    if (wr_afile_open(&f, dat, &d) != WR_OK) return;
    fprintf(f.fp, "# r[mm] tip_err_L100[%%] shape_err_L100[%%L]\n");
    for (i = 0; i < NRES; ++i)
        fprintf(f.fp, "%.6f %.6f %.6f\n", 1e3 * R->rows[i].r, 100.0 * (R->rows[i].tip / R->cm.er.tip_deflection - 1.0),
                100.0 * R->rows[i].shape);
    fprintf(f.fp, "\n\n# L = 25 mm sweep\n");
    for (i = 0; i < NSHORT; ++i)
        fprintf(f.fp, "%.6f %.6f %.6f\n", 1e3 * R->srows[i].r, 100.0 * (R->srows[i].tip / R->cs.er.tip_deflection - 1.0),
                100.0 * R->srows[i].shape);
    wr_afile_commit(&f, &d);
}

/* Issue 5's bands on one strip: the tip at r_opt within 2 % of the elastica and within 1 % of the
 * 2.5 mm solve (the elastica and the 2.5 mm solve are references, not paper values; issue 20). */
static void report_tip_bands(wr_vres *v, const char *strip, const char *strip_short, const cant_case *cc,
                             const cant_row *at_opt, const cant_row *at25) {
    const double te = 1e3 * cc->er.tip_deflection, t25 = 1e3 * at25->tip;
    char name[512];
    snprintf(name, sizeof name, "tip deflection at r_opt vs elastica, %s", strip);
    wr_vres_range(v, name, "mm", NAN, 1e3 * at_opt->tip, 0.98 * te, 1.02 * te);
    wr_vres_reference(v, te, "heavy elastica, validation/elastica_ref.h");
    snprintf(name, sizeof name, "tip deflection at r_opt vs 2.5 mm solve, %s", strip_short);
    wr_vres_range(v, name, "mm", NAN, 1e3 * at_opt->tip, 0.99 * t25, 1.01 * t25);
    wr_vres_reference(v, t25, "our 2.5 mm solve");
}

/* Style3D Sec. 6 / Fig. 18: the tip-vs-r curve flattens at r_opt. Read on each sweep (issue 20: a
 * pass/fail row): the coarsest r from which every finer tip stays within 1 % (issue 5's band against
 * the 2.5 mm solve) of the 2.5 mm tip must be r_opt itself — on the main sweep its neighbours are
 * 7.5 mm (coarser) and 5 mm (finer), so flattening at 7.5 mm means r_opt is not where the curve
 * flattens, and at 5 mm that r_opt is too coarse. */
static void report_main(wr_vres *v, const cant_run *R) {
    const cant_row *rows = R->rows;
    const int flat = coarsest_within(rows, I25, 0.0, 0.01), within2 = coarsest_within(rows, I25, R->cm.er.tip_deflection, 0.02);
    wr_vres_info(v, "elastica tip deflection (L = 100 mm, rho_A = 0.0025 kg/m^2)", "mm", NAN, 1e3 * R->cm.er.tip_deflection);
    wr_vres_info(v, "self-weight parameter kappa = rho_A g L^3 / B (main sweep)", "", NAN, R->cm.er.kappa);
    wr_vres_info(v, "r_opt (Style3D Eq. 4)", "mm", 6.45, 1e3 * R->r_opt);
    report_tip_bands(v, "main strip (OUR CHOSEN geometry: L = 100 mm, rho_A = 0.0025 kg/m^2, 60x lighter than fabric)",
                     "main strip (our chosen geometry)", &R->cm, &rows[I_OPT], &rows[I25]);
    wr_vres_info(v, "tip deflection at 2.5 mm vs elastica (relative error)", "%", NAN,
                 100.0 * (rows[I25].tip / R->cm.er.tip_deflection - 1.0));
    wr_vres_info(v, "shape error / L at r_opt", "%", NAN, 100.0 * rows[I_OPT].shape);
    wr_vres_check(v, "curve flattens at r_opt, main strip (coarsest r with all finer tips within 1% of 2.5 mm)", "mm", 6.45,
                  flat >= 0 ? 1e3 * R->res[flat] : NAN, "= r_opt on the sweep (neighbours 7.5, 5 mm)", flat == I_OPT);
    wr_vres_info(v, "coarsest r with all finer tips within 2% of the elastica", "mm", 6.45,
                 within2 >= 0 ? 1e3 * R->res[within2] : NAN);
}

/* The realistic-density strip (real fabric rho_A at the D1388 overhang): the main strip's bands
 * (issue 5), pass/fail rows since issue 20; and the former one-sided clamp for the record. */
static void report_short(wr_vres *v, const cant_run *R) {
    const cant_row *srows = R->srows;
    const int flat_s = coarsest_within(srows, 3, 0.0, 0.01);
    report_tip_bands(v, "realistic strip (L = 25 mm, rho_A = 0.15 kg/m^2)", "realistic strip", &R->cs, &srows[1], &srows[3]);
    wr_vres_check(v, "curve flattens at r_opt, realistic strip (coarsest r with all finer tips within 1% of 2.5 mm)", "mm",
                  6.45, flat_s >= 0 ? 1e3 * R->sres[flat_s] : NAN, "= r_opt on the sweep (neighbours 10, 5 mm)",
                  flat_s == 1);
    wr_vres_info(v, "L = 25 mm sweep: tip error vs elastica at r_opt", "%", NAN,
                 100.0 * (srows[1].tip / R->cs.er.tip_deflection - 1.0));
    wr_vres_info(v, "L = 25 mm sweep: tip error vs elastica at 2.5 mm", "%", NAN,
                 100.0 * (srows[3].tip / R->cs.er.tip_deflection - 1.0));
    wr_vres_info(v, "L = 25 mm, 2.5 mm, former one-sided clamp (fixed cell column): tip error vs elastica", "%", NAN,
                 100.0 * (R->hinge.tip / R->cs.er.tip_deflection - 1.0));
}

static void report_notes(wr_vres *v) {
    wr_vres_note(v, "Main strip: free length 100 mm, width 25 mm, areal density 0.0025 kg/m^2 (kappa = 12.3; chosen so "
                    "the deflection is large, tip ~0.74 L, but not a vertical hang, and 20 mm is 5 cells), nu = 0.3, "
                    "h from Kirchhoff-Love (0.28 mm). Second sweep: 25 mm overhang at 0.15 kg/m^2 (kappa = 11.5).");
    wr_vres_note(v, "Clamp by mirror symmetry: a 2L strip with its centre vertex column fixed; the mid-edge normal on the "
                    "clamp line is then exactly vertical. A clamp of fixed vertex columns acts as a partial hinge with "
                    "mid-edge bending (the clamp-line mid-edge normal averages the flat clamped face and the first free "
                    "face) and converges first-order only; its 2.5 mm tip error at L = 25 mm is reported above.");
    wr_vres_note(v, "The flattening resolution of a self-weight cantilever scales with L at fixed kappa (the error is a "
                    "function of r/L); the 100 mm strip is the geometry requested for this issue, the 25 mm sweep shows "
                    "the same problem 4x coarser relative to L.");
    wr_vres_note(v, "StVK + mid-edge bending, full gravity in one solve, exact-Hessian Newton to 1e-10 relative gradient, "
                    "CHOLMOD, statics.h membrane continuation (membrane_ramp s0 = rho_A g L / (E h 0.01), i.e. the "
                    "equilibrium with a membrane soft enough to stretch ~1 % first (s0 = 8.8e-4 main strip, 1.3e-2 "
                    "25 mm strip), then the real shell; Newton column = all stages). The elastica is inextensible; "
                    "the StVK strip stretches by ~1e-5 (negligible).");
    wr_vres_note(v, "Former protocol (gravity in 5 load steps, no continuation): every solve at r <= 5 mm ended "
                    "WR_ERR_NOT_CONVERGED after 460-990 Newton steps (2.5 mm: 593 steps, 49 s; 1.25 mm: 991 steps, "
                    "369 s): a Newton step that rotates a part of the strip is linear in the positions and stretches "
                    "it quadratically, so the membrane limited every step to ~1-2 mm of an 80 mm tip travel.");
}

/* Tip and shape error vs r on log axes, r_opt dashed. */
static void error_figure(wr_vres *v, const cant_run *R, const char *dat) {
    char gp[4200], png[4200], cmd[9000];
    wr_afile f;
    wr_diag d;
    snprintf(gp, sizeof gp, "%s/../figures/cantilever.gp", wr_vres_dir());
    snprintf(png, sizeof png, "%s/../figures/cantilever.png", wr_vres_dir());
    if (wr_afile_open(&f, gp, &d) != WR_OK) return;
    fprintf(f.fp, "set terminal pngcairo size 800,500\nset output '%s'\nset logscale xy\n", png);
    fprintf(f.fp, "set xlabel 'mesh resolution r [mm]'\nset ylabel '|error| [%%]'\nset grid\nset key top left\n");
    fprintf(f.fp, "set arrow from %.4f, graph 0 to %.4f, graph 1 nohead dt 2\n", 1e3 * R->r_opt, 1e3 * R->r_opt);
    fprintf(f.fp, "plot '%s' i 0 u 1:(abs($2)) w lp t 'tip vs elastica, L = 100 mm', '%s' i 0 u 1:3 w lp t "
                  "'shape error / L, L = 100 mm', '%s' i 1 u 1:(abs($2)) w lp t 'tip vs elastica, L = 25 mm'\n",
            dat, dat, dat);
    if (wr_afile_commit(&f, &d) != WR_OK) return;
    snprintf(cmd, sizeof cmd, "gnuplot '%s' 2>/dev/null", gp);
    if (system(cmd) == 0) wr_vres_figure(v, "figures/cantilever.png", "tip-deflection and shape error vs resolution (dashed: r_opt)");
}

/* A note per solve that did not converge. */
static void report_status_notes(wr_vres *v, const cant_run *R) {
    char buf[512];
    int i;
    for (i = 0; i < NRES; ++i)
        if (R->rows[i].st != WR_OK) {
            snprintf(buf, sizeof buf, "L = 100 mm, r = %.2f mm ended %s", 1e3 * R->rows[i].r, wr_status_string(R->rows[i].st));
            wr_vres_note(v, buf);
        }
    for (i = 0; i < NSHORT; ++i)
        if (R->srows[i].st != WR_OK) {
            snprintf(buf, sizeof buf, "L = 25 mm, r = %.2f mm ended %s", 1e3 * R->srows[i].r, wr_status_string(R->srows[i].st));
            wr_vres_note(v, buf);
        }
}

static int validation_main(void) {
    static cant_run R; /* ~130 kB of elastica reference curves: off the stack */
    char dat[4096];
    wr_vres *v;
    int failed;
    if (!run_setup(&R)) return 2;
    v = wr_vres_begin("cantilever", "Style3D Fig. 18a-c cantilever: tip deflection vs mesh resolution against the heavy elastica");
    if (!v || !run_solves(&R)) {
        wr_scene_free(&R.sc);
        return 2;
    }
    cant_table(v, &R.cm, R.rows, NRES, I_OPT,
               "Main sweep: L = 100 mm, b = 25 mm, rho_A = 0.0025 kg/m^2 (kappa = 12.3), mirror-symmetric clamp");
    cant_table(v, &R.cs, R.srows, NSHORT, 1,
               "Second sweep: L = 25 mm, b = 25 mm, rho_A = 0.15 kg/m^2 (kappa = 11.5), mirror-symmetric clamp");
    snprintf(dat, sizeof dat, "%s/cantilever.dat", wr_vres_dir());
    write_dat(&R, dat);
    report_main(v, &R);
    report_short(v, &R);
    report_notes(v);
    error_figure(v, &R, dat);
    report_status_notes(v, &R);
    wr_scene_free(&R.sc);
    failed = wr_vres_finish(v);
    return failed;
}

int main(int argc, char **argv) {
    int rc = wr_vargs(argc, argv, "validate_cantilever",
                      "Style3D Fig. 18a-c: cantilever tip deflection against the heavy elastica, over mesh resolution.",
                      "cantilever", NULL, NULL, NULL);
    return rc >= 0 ? rc : validation_main();
}
