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
 *
 * THE SIZING CALIBRATION METRIC (every mesh here, one definition; written down before the
 * per-class numbers were looked at). Edge ratio = |T e| / mean of the two end sizings, over every
 * mesh edge once (mesher.h's report.ratio_mean, recomputed here). The pass rows exclude one class:
 *   fold-strip edges: both ends on one fold's three constraint lines (the fold line and its two
 *   parallels at ±offset, Style3D Sec. 4.2.3) and the two ends on DIFFERENT ones of those lines,
 *   i.e. the edges across the 2 × 0.5 mm strip (and across its two ends). Their length is fixed at
 *   about the offset by the technique's geometry, not by the sizing map, so they cannot test the
 *   calibration. Edges ALONG a constraint line (discretised at ∫ ds/h, by the sizing map) and edges
 *   from a line vertex to a Poisson sample stay included.
 *   A vertex is "on fold i's lines" when it is an end of a constraint segment (result's
 *   constraint_segments) of a face of fold i's panel lying within 4 × offset (the mitre limit,
 *   mesher.h clamps the mitre at 1/0.25) of fold i's polyline in the pattern; on the fold line
 *   itself when within 1e-3 × offset of it, else on the parallel on its side (sign of the distance
 *   to the nearest segment). Poisson samples keep 0.35 h (>= 1.5 mm here) from every constraint
 *   segment and no other curve comes within 4 × offset of a fold, so only the fold's lines qualify.
 * Where a mesh has fold-strip edges, the all-edge mean and the two classes (count, mean ratio) are
 * reported beside the pass row; on a mesh without folds the two means are the same number.
 * Measured afterwards (fig09, seed 1): the class is not only ~0.5 mm edges. The three lines are
 * discretised alike, so the strip is a row of thin quads: each gives a rung (~offset long) and a
 * diagonal (~ the along-line spacing, ratio ~1). The rung split (strip edges shorter than 2 ×
 * offset) is reported as a diagnosis beside the pass row; the pass row keeps the definition above.
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

/* The sizing calibration metric's edge classes (header: THE SIZING CALIBRATION METRIC). */
typedef struct edge_classes {
    double mean_all, mean_kept, mean_strip; /* mean edge ratio: all edges, pass-row edges, fold-strip edges */
    int32_t n_all, n_kept, n_strip;
    double mean_rung, mean_no_rungs; /* diagnosis: strip edges shorter than 2 x offset; all edges but those */
    int32_t n_rung;
} edge_classes;

/* Which of fold fd's lines the pattern point q lies on (header's rule): 0 the fold line, +1 / -1 the
 * parallel on the left / right of the nearest segment, 2 none (farther than 4 x offset). */
static int fold_line_of(const wr_pattern_fold *fd, double off, const double *q) {
    double best = HUGE_VAL, side = 0.0;
    int32_t k;
    for (k = 0; k + 1 < fd->n; ++k) {
        const double *a = fd->xy + 2 * k, *b = a + 2;
        double ex = b[0] - a[0], ey = b[1] - a[1], L2 = ex * ex + ey * ey, t, dx, dy, dist;
        t = L2 > 0.0 ? ((q[0] - a[0]) * ex + (q[1] - a[1]) * ey) / L2 : 0.0;
        t = t < 0.0 ? 0.0 : t > 1.0 ? 1.0 : t;
        dx = q[0] - (a[0] + t * ex);
        dy = q[1] - (a[1] + t * ey);
        dist = sqrt(dx * dx + dy * dy);
        if (dist < best) {
            best = dist;
            side = ex * (q[1] - a[1]) - ey * (q[0] - a[0]);
        }
    }
    if (!(best <= 4.0 * off * (1.0 + 1e-9))) return 2;
    if (best <= 1e-3 * off) return 0;
    return side > 0.0 ? 1 : -1;
}

/* The fold's offset when the edge of a face of panel p between pattern corners qa, qb is a fold-strip
 * edge (both ends constraint vertices (ca, cb) on one fold's lines, on different lines), else 0. */
static double fold_strip_offset(const wr_pattern *pat, int32_t p, int ca, int cb, const double *qa, const double *qb) {
    int32_t i;
    if (!ca || !cb) return 0.0;
    for (i = 0; i < pat->n_folds; ++i) {
        const wr_pattern_fold *fd = &pat->folds[i];
        double off = fd->offset > 0.0 ? fd->offset : WR_MESHER_DEFAULT_FOLD_OFFSET;
        int la, lb;
        if (fd->panel != p) continue;
        la = fold_line_of(fd, off, qa);
        lb = fold_line_of(fd, off, qb);
        if (la != 2 && lb != 2 && la != lb) return off;
    }
    return 0.0;
}

/* The edge ratios of mesher.h's report (same edges, same order, so mean_all == report.ratio_mean),
 * split into fold-strip edges and the rest. 0 when out of memory or when the all-edge mean is not
 * the report's. */
static int edge_classes_of(const wr_mesher_result *r, const wr_pattern *pat, edge_classes *ec) {
    const wr_mesh *M = &r->mesh;
    double s_all = 0.0, s_kept = 0.0, s_strip = 0.0, s_rung = 0.0;
    int32_t f, j;
    int k;
    char *con = (char *)calloc((size_t)(M->nv > 0 ? M->nv : 1), 1);
    memset(ec, 0, sizeof *ec);
    if (!con) return 0;
    for (j = 0; j < 2 * r->n_constraint_segments; ++j) con[r->constraint_segments[j]] = 1;
    for (f = 0; f < M->nf; ++f) {
        const double *T = r->panels[M->face_panel[f]].T;
        double uv[6];
        wr_mesh_face_rest(M, f, uv);
        for (k = 0; k < 3; ++k) {
            int32_t e = M->face_edges[3 * f + k], a = M->edges[2 * e], b = M->edges[2 * e + 1];
            int k1 = (k + 1) % 3, k2 = (k + 2) % 3;
            double dx = uv[2 * k2] - uv[2 * k1], dy = uv[2 * k2 + 1] - uv[2 * k1 + 1];
            double mx = T[0] * dx + T[1] * dy, my = T[2] * dx + T[3] * dy, ratio, off;
            if ((M->edge_faces[2 * e] >= 0 ? M->edge_faces[2 * e] : M->edge_faces[2 * e + 1]) != f) continue;
            ratio = sqrt(mx * mx + my * my) / (0.5 * (r->sizing[a] + r->sizing[b]));
            s_all += ratio;
            ++ec->n_all;
            off = fold_strip_offset(pat, M->face_panel[f], con[M->faces[3 * f + k1]], con[M->faces[3 * f + k2]],
                                    uv + 2 * k1, uv + 2 * k2);
            if (off > 0.0) {
                s_strip += ratio;
                ++ec->n_strip;
                if (dx * dx + dy * dy < 4.0 * off * off) { /* a rung: the diagnosis only */
                    s_rung += ratio;
                    ++ec->n_rung;
                }
            } else {
                s_kept += ratio;
                ++ec->n_kept;
            }
        }
    }
    free(con);
    ec->mean_all = ec->n_all ? s_all / ec->n_all : NAN;
    ec->mean_kept = ec->n_kept ? s_kept / ec->n_kept : NAN;
    ec->mean_strip = ec->n_strip ? s_strip / ec->n_strip : NAN;
    ec->mean_rung = ec->n_rung ? s_rung / ec->n_rung : NAN;
    ec->mean_no_rungs = ec->n_all > ec->n_rung ? (s_all - s_rung) / (ec->n_all - ec->n_rung) : NAN;
    /* same edges in the same order as mesher.h's report: more than rounding apart is a bug here (not
     * == : the library may be compiled with other floating-point contraction than this driver) */
    return ec->n_all == 0 || fabs(ec->mean_all - r->report.ratio_mean) <= 1e-12;
}

/* The square meshed (optimal when uniform == 0) with its calibration edge classes; 0 on failure. */
static int mesh_square(double B, double E, double uniform, wr_mesher_result *r, edge_classes *ec) {
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
    if (!edge_classes_of(r, &pat, ec)) {
        fprintf(stderr, "validate_meshing: square B=%g E=%g: edge classes: out of memory or report mismatch\n", B, E);
        wr_mesher_free(r);
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

/* (a) one Table 1 fabric: its square at the optimal resolution (r) and at uniform 2.5 mm (u), with their
 * calibration edge classes (no folds on a square: every edge is kept). */
static void square_report(wr_vres *v, const fabric_row *f, const wr_mesher_result *r, const wr_mesher_result *u,
                          const edge_classes *er, const edge_classes *eu) {
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
    wr_vres_range(v, name, "1", NAN, er->mean_kept, 0.98, 1.02);
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
    wr_vres_range(v, name, "1", NAN, eu->mean_kept, 0.98, 1.02); /* ±2 %: as above */
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
        edge_classes er, eu;
        if (!mesh_square(f->B, f->E, 0.0, &r, &er)) {
            ++failed_runs;
            continue;
        }
        if (!mesh_square(f->B, f->E, 2.5e-3, &u, &eu)) {
            wr_mesher_free(&r);
            ++failed_runs;
            continue;
        }
        square_report(v, f, &r, &u, &er, &eu);
        if (fabs(er.mean_kept - 1.0) > worst_cal) worst_cal = fabs(er.mean_kept - 1.0);
        if (fabs(eu.mean_kept - 1.0) > worst_cal) worst_cal = fabs(eu.mean_kept - 1.0);
        ratio_sum += r.mesh.nv / f->nv_paper;
        md_row(&md, "| %s | %.1e | %.1e | %.2f | %.2f | %d | %.0f | %.3f | %.3f | %d | %.1fx |\n", f->name, f->B, f->E,
               1e3 * r.panels[0].r0, f->r_paper_mm, (int)r.mesh.nv, f->nv_paper, r.mesh.nv / f->nv_paper,
               er.mean_kept, (int)u.mesh.nv, (double)u.mesh.nv / r.mesh.nv);
        printf("%-10s r %.2f mm  #V %6d (paper %6.0f, x%.3f)  edge/sizing %.3f  uniform 2.5 mm #V %d\n", f->name,
               1e3 * r.panels[0].r0, (int)r.mesh.nv, f->nv_paper, r.mesh.nv / f->nv_paper, er.mean_kept,
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

/* The diagnosis beside a pass row that excluded fold-strip edges: the all-edge mean and both classes. */
static void example_strip_rows(wr_vres *v, const char *pname, const edge_classes *ec) {
    /* (row name after "<panel>: ", unit, value, 1 when the row's reference is the calibration target) */
    const struct {
        const char *what, *unit;
        double value;
        int calibrated;
    } rows[] = {
        {"mean edge length / sizing, all edges (fold-strip edges included)", "1", ec->mean_all, 1},
        {"fold-strip edges", "edges", (double)ec->n_strip, 0},
        {"fold-strip edges: mean edge length / sizing", "1", ec->mean_strip, 0},
        {"other edges (the pass row's)", "edges", (double)ec->n_kept, 0},
        {"fold-strip rungs (shorter than 2 x offset)", "edges", (double)ec->n_rung, 0},
        {"fold-strip rungs: mean edge length / sizing", "1", ec->mean_rung, 0},
        {"mean edge length / sizing, only the rungs excluded", "1", ec->mean_no_rungs, 1},
    };
    char name[256], line[1400];
    size_t i;
    for (i = 0; i < sizeof rows / sizeof rows[0]; ++i) {
        snprintf(name, sizeof name, "%s: %s", pname, rows[i].what);
        wr_vres_info(v, name, rows[i].unit, NAN, rows[i].value);
        if (rows[i].calibrated) wr_vres_reference(v, 1.0, "poisson.h calibration target");
    }
    snprintf(line, sizeof line,
             "%s: of %d edges, %d are fold-strip edges (both ends on the fold's three lines, on different ones), "
             "mean edge/sizing %.3f; the other %d edges average %.4f (the pass row), all %d together %.4f. The strip "
             "class holds %d rungs (shorter than 2 x offset, mean %.3f: the fold technique, Sec. 4.2.3, fixes them at "
             "about the offset whatever the sizing) and %d diagonals of the same thin quads (about the along-line "
             "spacing); leaving out only the rungs gives %.4f. Definition in the driver's header, set before these "
             "numbers were seen; the rung split is the diagnosis, not the pass row.",
             pname, (int)ec->n_all, (int)ec->n_strip, ec->mean_strip, (int)ec->n_kept, ec->mean_kept, (int)ec->n_all,
             ec->mean_all, (int)ec->n_rung, ec->mean_rung, (int)(ec->n_strip - ec->n_rung), ec->mean_no_rungs);
    wr_vres_note(v, line);
}

/* (c) one example's rows: counts, ratios, angles, sizing calibration (edge classes ec), validity. */
static void example_report(wr_vres *v, const example_run *e, const edge_classes *ec) {
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
    /* ±2 %: issue 20, as for the squares (graded sizing included); fold-strip edges excluded (header) */
    snprintf(name, sizeof name, "%s: mean edge length / sizing%s", pname, ec->n_strip ? ", fold-strip edges excluded" : "");
    wr_vres_range(v, name, "1", NAN, ec->mean_kept, 0.98, 1.02);
    wr_vres_reference(v, 1.0, "poisson.h calibration target");
    if (ec->n_strip) example_strip_rows(v, pname, ec);
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
                  "2.5 mm / ours | min angle [deg] | mean min angle [deg] | edge/sizing (fold strips excl.) | time [s] |\n"
                  "|---|---|---|---|---|---|---|---|---|---|---|---|\n");
    for (i = 0; i < (int)(sizeof examples / sizeof examples[0]); ++i) {
        example_run e;
        const wr_mesher_result *r = &e.r;
        const wr_pattern *pt = &e.pf.pattern;
        edge_classes ec;
        double u25_ratio;
        memset(&e, 0, sizeof e);
        if (!example_mesh(v, examples[i], &e)) {
            ++failed_runs;
            continue;
        }
        u25_ratio = e.u25.mesh.nv > 0 ? (double)e.u25.mesh.nv / r->mesh.nv : NAN;
        if (!edge_classes_of(r, pt, &ec)) {
            fprintf(stderr, "validate_meshing: %s: edge classes: out of memory or report mismatch\n", e.pf.name);
            wr_vres_note(v, "edge classes failed (out of memory or all-edge mean != mesher report)");
            example_free(&e);
            ++failed_runs;
            continue;
        }
        example_figure(v, examples[i], &e, i == 0);
        example_report(v, &e, &ec);
        md_row(&md, "| %s | %d | %d | %.2f%s | %d | %d | %d | %.2fx | %.1f | %.1f | %.3f | %.2f |\n", e.pf.name,
               (int)pt->n_panels, (int)(pt->n_shirrings + pt->n_folds + pt->n_seams + pt->n_quilts + pt->n_collisions),
               1e3 * r->panels[0].r0, r->panels[0].r_warp != r->panels[0].r_weft ? " (fine dir.)" : "",
               (int)r->mesh.nv, (int)e.ub.mesh.nv, (int)e.u25.mesh.nv, u25_ratio, r->report.min_angle_deg,
               r->report.mean_min_angle_deg, ec.mean_kept, r->report.t_total);
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
