/* validate_meshing — Style3D Sec. 4.3 / Table 1 / Fig. 14 and the garment examples through the mesher.
 *
 * (a) a 250 mm × 250 mm square for each Table 1 fabric at its optimal resolution (Eq. 4) and uniformly
 *     at 2.5 mm: vertex counts beside the paper's #V (pass band ±8 %, issue 20), with the sizing
 *     calibration (mean edge length / sizing, within ±2 %, issue 20: the band poisson.h's own
 *     calibration test holds) measured on the same meshes. The Poisson radius factor is poisson.h's
 *     calibrated default; nothing here is tuned to the table. Beside each count: the equilateral-
 *     lattice count of the same square, 2A/(√3 r²) + P/(2r) (a reference, not a paper value), which
 *     the paper's #V follow to within 2 %: a mesh whose MEAN edge is r (ours, by calibration) has
 *     more vertices than the lattice, because irregular triangles with a given mean edge enclose
 *     less area than equilateral ones (the measured ours/lattice ratio is the price of Poisson-disk
 *     irregularity; see the notes).
 * (b) Fig. 14: the square with curved shirring lines, its sizing map and mesh as a figure.
 * (c) every pattern in examples/: vertices vs uniform 2.5 mm and vs uniform base resolution, min angle.
 * Results: validation/results/style3d_meshing.json, figures in validation/figures/.
 */
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "meshout.h"
#include "pattern.h"
#include "vresult.h"
#include "wrinkle/mesher.h"
#include "vargs.h"

typedef struct fabric_row {
    const char *name;
    double B, E, r_paper_mm, nv_paper, nv_full_paper; /* nv_full_paper: NAN when the table has none */
} fabric_row;

/* Style3D Table 1, right half ("Fabrics"): B [N·m], E [N/m²], Res. [mm], #V (ours), #V (full sim). */
static const fabric_row fabrics[5] = {
    {"Dark Blue", 1.6e-4, 1.3e5, 18.5, 241, NAN},
    {"Khaki", 2.0e-5, 5.0e5, 10.5, 708, NAN},
    {"Green", 2.6e-6, 2.0e6, 6.00, 2100, 11900},
    {"Light Blue", 3.2e-7, 8.2e6, 3.61, 5800, NAN},
    {"Rose", 4.0e-8, 1.6e7, 2.70, 10000, NAN},
};

static const char *examples[] = {
    "fig14_square_shirring", "fig08_shirring",     "fig09_folding",
    "fig10_long_short_seam", "fig11_down_filled",  "fig13_elbow",
    "fig06_anisotropic",     "garment_dress_shirred_waist", "garment_down_coat",
};

static int mesh_square(double B, double E, double uniform, wr_mesher_result *r) {
    double sq[8] = {0, 0, 0.25, 0, 0.25, 0.25, 0, 0.25};
    wr_pattern_panel pn;
    wr_pattern pat;
    wr_mesher_desc desc;
    wr_diag d;
    memset(&pn, 0, sizeof pn);
    memset(&pat, 0, sizeof pat);
    memset(&desc, 0, sizeof desc);
    pn.outer.xy = sq;
    pn.outer.n = 4;
    pn.fabric.B = B;
    pn.fabric.E = E;
    pn.name = "square";
    pat.panels = &pn;
    pat.n_panels = 1;
    desc.seed = 1;
    desc.uniform_resolution = uniform;
    if (wr_mesher_run(&pat, &desc, r, &d) != WR_OK) {
        fprintf(stderr, "validate_meshing: square B=%g E=%g: %s\n", B, E, d.message);
        return 0;
    }
    return 1;
}

static void figure_path(char *out, size_t n, const char *file) {
    snprintf(out, n, "%s/../figures/%s", wr_vres_dir(), file);
}

/* The markdown table a stage fills row by row. */
typedef struct md_table {
    char text[8192];
    size_t len;
} md_table;

static void md_begin(md_table *t, const char *header) {
    t->len = (size_t)snprintf(t->text, sizeof t->text, "%s", header);
}

static void md_row(md_table *t, const char *fmt, ...) {
    va_list ap;
    va_start(ap, fmt);
    if (t->len < sizeof t->text) t->len += (size_t)vsnprintf(t->text + t->len, sizeof t->text - t->len, fmt, ap);
    va_end(ap);
}

/* The equilateral-lattice vertex count of the S x S square at spacing r: 2A/(sqrt3 r^2) + P/(2r). */
static double lattice_count(double S, double r) { return 2.0 * S * S / (sqrt(3.0) * r * r) + 4.0 * S / (2.0 * r); }

/* (a) one Table 1 fabric: its square at the optimal resolution (r) and at uniform 2.5 mm (u). */
static void square_report(wr_vres *v, const fabric_row *f, const wr_mesher_result *r, const wr_mesher_result *u) {
    char name[256];
    const double S = 0.25;
    /* ±8 %: issue 20's band for Table 1 counts (the paper gives no tolerance; Poisson-disk meshes at
     * the calibrated mean edge run 5-9 % above the lattice count the paper's #V follow) */
    snprintf(name, sizeof name, "Table 1 %s: vertices at the optimal resolution (250 mm square)", f->name);
    wr_vres_rel(v, name, "vertices", f->nv_paper, r->mesh.nv, 0.08);
    snprintf(name, sizeof name, "Table 1 %s: ours / equilateral-lattice count at our r", f->name);
    wr_vres_info(v, name, "1", NAN, r->mesh.nv / lattice_count(S, r->panels[0].r0));
    wr_vres_reference(v, 1.0, "lattice count 2A/(sqrt3 r^2) + P/(2r)");
    snprintf(name, sizeof name, "Table 1 %s: paper #V / equilateral-lattice count at the paper's r", f->name);
    wr_vres_info(v, name, "1", NAN, f->nv_paper / lattice_count(S, 1e-3 * f->r_paper_mm));
    wr_vres_reference(v, 1.0, "lattice count 2A/(sqrt3 r^2) + P/(2r)");
    /* ±2 %: issue 20 (the calibration is a library target, mean Delaunay edge = sizing; poisson.h's
     * calibration test holds the same band), reference 1, not a paper value */
    snprintf(name, sizeof name, "Table 1 %s: mean edge length / sizing", f->name);
    wr_vres_range(v, name, "1", NAN, r->report.ratio_mean, 0.98, 1.02);
    wr_vres_reference(v, 1.0, "poisson.h calibration target");
    snprintf(name, sizeof name, "Table 1 %s: optimal resolution r", f->name);
    wr_vres_info(v, name, "mm", f->r_paper_mm, 1e3 * r->panels[0].r0);
    if (!isnan(f->nv_full_paper)) {
        snprintf(name, sizeof name, "Table 1 %s: vertices, uniform 2.5 mm (full sim)", f->name);
        wr_vres_rel(v, name, "vertices", f->nv_full_paper, u->mesh.nv, 0.08); /* ±8 %: as the optimal counts */
    } else {
        snprintf(name, sizeof name, "Table 1 %s: vertices, uniform 2.5 mm", f->name);
        wr_vres_info(v, name, "vertices", NAN, u->mesh.nv);
    }
    snprintf(name, sizeof name, "Table 1 %s: mean edge length / sizing, uniform 2.5 mm", f->name);
    wr_vres_range(v, name, "1", NAN, u->report.ratio_mean, 0.98, 1.02); /* ±2 %: as above */
    wr_vres_reference(v, 1.0, "poisson.h calibration target");
}

/* (a) the five Table 1 squares; returns the number of failed meshing runs. */
static int table1_squares(wr_vres *v) {
    md_table md;
    int i, failed_runs = 0;
    double ratio_sum = 0.0, worst_cal = 0.0;
    md_begin(&md, "| fabric | B [N m] | E [N/m^2] | r ours [mm] | r paper [mm] | #V ours | #V paper | ours/paper | "
                  "mean edge/sizing | #V uniform 2.5 mm | uniform/ours |\n"
                  "|---|---|---|---|---|---|---|---|---|---|---|\n");
    for (i = 0; i < 5; ++i) {
        const fabric_row *f = &fabrics[i];
        wr_mesher_result r, u;
        if (!mesh_square(f->B, f->E, 0.0, &r)) {
            ++failed_runs;
            continue;
        }
        if (!mesh_square(f->B, f->E, 2.5e-3, &u)) {
            wr_mesher_free(&r);
            ++failed_runs;
            continue;
        }
        square_report(v, f, &r, &u);
        if (fabs(r.report.ratio_mean - 1.0) > worst_cal) worst_cal = fabs(r.report.ratio_mean - 1.0);
        if (fabs(u.report.ratio_mean - 1.0) > worst_cal) worst_cal = fabs(u.report.ratio_mean - 1.0);
        ratio_sum += r.mesh.nv / f->nv_paper;
        md_row(&md, "| %s | %.1e | %.1e | %.2f | %.2f | %d | %.0f | %.3f | %.3f | %d | %.1fx |\n", f->name, f->B, f->E,
               1e3 * r.panels[0].r0, f->r_paper_mm, (int)r.mesh.nv, f->nv_paper, r.mesh.nv / f->nv_paper,
               r.report.ratio_mean, (int)u.mesh.nv, (double)u.mesh.nv / r.mesh.nv);
        printf("%-10s r %.2f mm  #V %6d (paper %6.0f, x%.3f)  edge/sizing %.3f  uniform 2.5 mm #V %d\n", f->name,
               1e3 * r.panels[0].r0, (int)r.mesh.nv, f->nv_paper, r.mesh.nv / f->nv_paper, r.report.ratio_mean,
               (int)u.mesh.nv);
        wr_mesher_free(&r);
        wr_mesher_free(&u);
    }
    wr_vres_table_md(v, md.text);
    wr_vres_info(v, "Table 1 squares: mean of ours/paper vertex ratios", "1", NAN, ratio_sum / 5.0);
    wr_vres_info(v, "sizing calibration: worst |mean edge/sizing - 1| over the ten square meshes", "1", NAN, worst_cal);
    wr_vres_note(v, "Table 1 vertex counts (issue 20): the paper's #V are the equilateral-lattice counts of the square at its "
                    "r to within 2 % (rows 'paper #V / equilateral-lattice count'), i.e. the paper's meshes have about the "
                    "density of equilateral triangles of edge r. Ours are calibrated so that the MEAN Delaunay edge equals "
                    "the sizing (rows 'mean edge length / sizing', within 1 %); irregular triangles with a given mean edge "
                    "enclose less area than equilateral ones, so the same mean edge takes 5-9 % more vertices (rows 'ours / "
                    "equilateral-lattice count'). That is the +6 % mean: a difference in what 'resolution r' measures (mean "
                    "edge vs lattice spacing), not a sizing error. Matching the paper's counts instead would mean "
                    "calibrating the radius factor to vertex density, ~3 % longer edges than the sizing (poisson.h's "
                    "choice, not this driver's).");
    wr_vres_info(v, "Poisson radius factor used (poisson.h calibrated default, not tuned here)", "1", NAN,
                 WR_POISSON_DEFAULT_RADIUS_FACTOR);
    return failed_runs;
}

/* One pattern of examples/ meshed three ways: by the sizing map, uniformly at its base resolution, at 2.5 mm. */
typedef struct example_run {
    wr_pattern_file pf;
    wr_mesher_result r, ub, u25;
} example_run;

/* Loads and meshes examples/<stem>.json; 0 (with a note) when it cannot be read or meshed. The two uniform
 * meshes are comparisons only: a failure there leaves them empty (nv 0) and is printed, not fatal. */
static int example_mesh(wr_vres *v, const char *stem, example_run *e) {
    char path[512], line[2048];
    wr_mesher_desc d2;
    wr_diag d;
    snprintf(path, sizeof path, "examples/%s.json", stem);
    if (wr_pattern_load(path, &e->pf, &d) != WR_OK) {
        fprintf(stderr, "validate_meshing: %s\n", d.message);
        snprintf(line, sizeof line, "%s could not be read: %s", path, d.message);
        wr_vres_note(v, line);
        return 0;
    }
    e->pf.desc.seed = 1;
    if (wr_mesher_run(&e->pf.pattern, &e->pf.desc, &e->r, &d) != WR_OK) {
        fprintf(stderr, "validate_meshing: %s: %s\n", path, d.message);
        snprintf(line, sizeof line, "%s failed to mesh: %s", path, d.message);
        wr_vres_note(v, line);
        wr_pattern_file_free(&e->pf);
        return 0;
    }
    d2 = e->pf.desc;
    d2.uniform_resolution = e->r.panels[0].r0;
    if (wr_mesher_run(&e->pf.pattern, &d2, &e->ub, &d) != WR_OK) {
        fprintf(stderr, "validate_meshing: %s uniform base: %s\n", path, d.message);
        memset(&e->ub, 0, sizeof e->ub);
    }
    d2.uniform_resolution = 2.5e-3;
    if (wr_mesher_run(&e->pf.pattern, &d2, &e->u25, &d) != WR_OK) {
        fprintf(stderr, "validate_meshing: %s uniform 2.5 mm: %s\n", path, d.message);
        memset(&e->u25, 0, sizeof e->u25);
    }
    return 1;
}

static void example_free(example_run *e) {
    wr_mesher_free(&e->r);
    wr_mesher_free(&e->ub);
    wr_mesher_free(&e->u25);
    wr_pattern_file_free(&e->pf);
}

/* The sizing map with the mesh as a figure (the first example is Style3D Fig. 14 (b)+(c)). */
static void example_figure(wr_vres *v, const char *stem, const example_run *e, int is_fig14) {
    char fname[256], fig[4096], path[512], cap[512];
    wr_diag d;
    snprintf(fname, sizeof fname, "mesh_%s.png", stem);
    figure_path(fig, sizeof fig, fname);
    if (wr_meshout_render_png(&e->r, fig, e->pf.name, 1, &d) == WR_OK) {
        snprintf(path, sizeof path, "figures/%s", fname);
        snprintf(cap, sizeof cap, "%s: sizing map [mm] with the mesh (%d vertices, min angle %.1f deg). %s", e->pf.name,
                 (int)e->r.mesh.nv, e->r.report.min_angle_deg, is_fig14 ? "Style3D Fig. 14 (b)+(c)." : "");
        wr_vres_figure(v, path, cap);
    } else {
        fprintf(stderr, "validate_meshing: figure %s: %s\n", fname, d.message);
    }
}

/* (c) one example's rows: counts, ratios, angles, sizing calibration, validity. */
static void example_report(wr_vres *v, const example_run *e) {
    const wr_mesher_result *r = &e->r;
    const char *pname = e->pf.name;
    char name[256];
    snprintf(name, sizeof name, "%s: vertices", pname);
    wr_vres_info(v, name, "vertices", NAN, r->mesh.nv);
    if (e->u25.mesh.nv > 0) {
        snprintf(name, sizeof name, "%s: uniform 2.5 mm / ours vertex ratio", pname);
        wr_vres_info(v, name, "1", NAN, (double)e->u25.mesh.nv / r->mesh.nv);
    }
    if (e->ub.mesh.nv > 0) {
        snprintf(name, sizeof name, "%s: ours / uniform base-resolution vertex ratio", pname);
        wr_vres_info(v, name, "1", NAN, (double)r->mesh.nv / e->ub.mesh.nv);
    }
    snprintf(name, sizeof name, "%s: minimum angle", pname);
    wr_vres_info(v, name, "deg", NAN, r->report.min_angle_deg);
    if (r->panels[0].r_warp != r->panels[0].r_weft) {
        snprintf(name, sizeof name, "%s: minimum angle in the warp/weft metric", pname);
        wr_vres_info(v, name, "deg", NAN, r->report.min_angle_metric_deg);
    }
    /* ±2 %: issue 20, as for the squares (graded sizing included) */
    snprintf(name, sizeof name, "%s: mean edge length / sizing", pname);
    wr_vres_range(v, name, "1", NAN, r->report.ratio_mean, 0.98, 1.02);
    wr_vres_reference(v, 1.0, "poisson.h calibration target");
    /* a valid mesh has none (mesh.h's definition), no tolerance */
    snprintf(name, sizeof name, "%s: inverted or zero-area faces", pname);
    wr_vres_range(v, name, "faces", NAN, r->report.n_inverted + r->report.n_zero_area, 0.0, 0.0);
    wr_vres_reference(v, 0.0, "mesh validity");
}

/* (b) Fig. 14 and (c) every pattern in examples/; returns the number of failed meshing runs. */
static int example_patterns(wr_vres *v) {
    md_table md;
    int i, failed_runs = 0;
    md_begin(&md, "| pattern | panels | techniques | base r [mm] | #V ours | #V uniform base | #V uniform 2.5 mm | "
                  "2.5 mm / ours | min angle [deg] | mean min angle [deg] | edge/sizing | time [s] |\n"
                  "|---|---|---|---|---|---|---|---|---|---|---|---|\n");
    for (i = 0; i < (int)(sizeof examples / sizeof examples[0]); ++i) {
        example_run e;
        const wr_mesher_result *r = &e.r;
        const wr_pattern *pt = &e.pf.pattern;
        double u25_ratio;
        memset(&e, 0, sizeof e);
        if (!example_mesh(v, examples[i], &e)) {
            ++failed_runs;
            continue;
        }
        u25_ratio = e.u25.mesh.nv > 0 ? (double)e.u25.mesh.nv / r->mesh.nv : NAN;
        example_figure(v, examples[i], &e, i == 0);
        example_report(v, &e);
        md_row(&md, "| %s | %d | %d | %.2f%s | %d | %d | %d | %.2fx | %.1f | %.1f | %.3f | %.2f |\n", e.pf.name,
               (int)pt->n_panels, (int)(pt->n_shirrings + pt->n_folds + pt->n_seams + pt->n_quilts + pt->n_collisions),
               1e3 * r->panels[0].r0, r->panels[0].r_warp != r->panels[0].r_weft ? " (fine dir.)" : "",
               (int)r->mesh.nv, (int)e.ub.mesh.nv, (int)e.u25.mesh.nv, u25_ratio, r->report.min_angle_deg,
               r->report.mean_min_angle_deg, r->report.ratio_mean, r->report.t_total);
        printf("%-28s #V %6d  uniform base %6d  uniform 2.5 mm %7d (x%.2f)  min angle %.1f  %.2f s\n", e.pf.name,
               (int)r->mesh.nv, (int)e.ub.mesh.nv, (int)e.u25.mesh.nv, u25_ratio, r->report.min_angle_deg,
               r->report.t_total);
        if (i == 0) {
            wr_vres_info(v, "Fig. 14: sizing on the shirring lines", "mm", NAN,
                         1e3 * wr_mesher_eval_sizing(r, 0, 0.125, 0.125));
            /* the paper's 6.0 mm is Table 1's Green resolution r_f; the map itself stays below r_f 42 mm
             * from line 1 (Sec. 4.2.1's transition reaches r_f 59 mm from a line: docs/garments.md) */
            wr_vres_info(v, "Fig. 14: fabric resolution r_f (Eq. 4, Table 1 Green)", "mm", 6.00, 1e3 * r->panels[0].r0);
            wr_vres_info(v, "Fig. 14: sizing at (125, 10) mm, 42 mm from shirring line 1", "mm", NAN,
                         1e3 * wr_mesher_eval_sizing(r, 0, 0.125, 0.01));
        }
        example_free(&e);
    }
    wr_vres_table_md(v, md.text);
    wr_vres_note(v, "Paper (Sec. 5.1 / Table 1): its five garments use 2.3x-10.7x fewer vertices than uniform 2.5 mm "
                    "(135K/59K .. 876K/82K). Our garment examples are simpler patterns with our own dimensions; their "
                    "uniform-2.5 mm / ours ratios are reported above, not compared against the paper's garments.");
    wr_vres_note(v, "Min angles: fold lines get two parallel constraint lines at +-0.5 mm (Sec. 4.2.3), so the "
                    "triangles between them are slivers by construction (a few degrees); anisotropic panels are "
                    "near-equilateral in the metric, i.e. stretched by r_warp/r_weft in the pattern, which lowers "
                    "their pattern-space angles.");
    return failed_runs;
}

static int validation_main(void) {
    wr_vres *v = wr_vres_begin("style3d_meshing", "Style3D Sec. 4.3: pattern -> optimal mesh (Table 1 squares, Fig. 14, garment examples)");
    char line[256];
    int failed_runs;
    if (!v) return 2;
    wr_vres_note(v, "Meshes: poisson.h variable-radius Bridson sampling (radius = WR_POISSON_DEFAULT_RADIUS_FACTOR x sizing, "
                    "the calibrated default) + triangulate.h CDT, through mesher.h; seed 1; paper model c1 = 32.08 m^-3, "
                    "c2 = -1.876e-4 m^-1. Vertex counts include boundary vertices (the paper's #V does too, we assume).");
    failed_runs = table1_squares(v);
    failed_runs += example_patterns(v);
    if (failed_runs) {
        snprintf(line, sizeof line, "%d meshing run(s) failed (see stderr)", failed_runs);
        wr_vres_note(v, line);
        wr_vres_check(v, "meshing runs that failed", "runs", 0.0, failed_runs, "must be 0", 0);
    }
    return wr_vres_finish(v) == 0 && failed_runs == 0 ? 0 : 1;
}

int main(int argc, char **argv) {
    int rc = wr_vargs(argc, argv, "validate_meshing",
                      "Style3D Sec. 4.3: patterns meshed at the optimal resolution (Table 1 squares, Fig. 14, garments).",
                      "style3d_meshing", NULL, NULL, NULL);
    return rc >= 0 ? rc : validation_main();
}
