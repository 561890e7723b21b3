/* wrinkle-mesh — garment pattern (JSON, millimetres) → one optimally resolved simulation mesh
 * (Style3D Sec. 4.1–4.3). See --help and docs/pattern-format.md. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"
#include "plausible.h"
#include "meshout.h"
#include "pattern.h"
#include "wrinkle/mesher.h"

static void usage(FILE *f) {
    fprintf(f,
            "usage: wrinkle-mesh [PATTERN.json] -o DIR [options]\n"
            "\n"
            "Meshes a garment pattern at its optimal, technique-aware resolution (Style3D Sec. 4):\n"
            "per-panel sizing maps from the fabrics (Eq. 4) and the garment-making techniques\n"
            "(shirring, folds, seams, down-filling, high-collision areas), Poisson sampling and a\n"
            "constrained Delaunay triangulation. Without PATTERN.json it meshes the built-in example:\n"
            "the paper's Fig. 14 square (250 mm, Table 1 Green fabric) with curved shirring lines.\n"
            "\n"
            "Outputs (all written whole or not at all):\n"
            "  DIR/mesh.obj      vertices, vt = 2D rest (pattern) positions, vn, one group per panel\n"
            "                    named after it\n"
            "  DIR/mesh.ply      per-vertex sizing, sizing_warp, sizing_weft [m] and panel id\n"
            "  DIR/mesh.vtk      the same fields for ParaView (with normals, texture coordinates)\n"
            "  DIR/sizing.png    the sizing map with the mesh over it (needs gnuplot; skipped with a\n"
            "                    warning when gnuplot is missing)\n"
            "  DIR/seams.csv     vertex pairs to sew, in order along each seam (only with seams)\n"
            "  DIR/summary.json  vertex/triangle counts, quality, per-stage timings\n"
            "\n"
            "Options:\n"
            "  -o, --output DIR        output directory (created if missing; required)\n"
            "  --seed N                sampling seed (default: the file's mesher.seed, else 0)\n"
            "  --uniform MM            ignore fabrics and techniques, mesh uniformly at MM millimetres\n"
            "  --max-vertices N        vertex budget (default: the file's, else 20000000)\n"
            "  --sew                   merge seam vertex pairs (corner rest coordinates in the OBJ)\n"
            "  --no-png                do not draw sizing.png\n"
            "  -q, --quiet             no summary line on stdout, no progress on stderr\n"
            "  -h, --help              this text\n"
            "\n"
            "Progress (stderr, unless -q): the sizing stage, then one report per panel meshed; on a\n"
            "terminal one line redrawn in place, redirected one plain line each.\n"
            "\n"
            "Warnings (stderr, the mesh is still written): a panel smaller than one edge (coordinates in\n"
            "metres in a millimetre file?), a base resolution outside the 2.5-50 mm band Eq. 4 was\n"
            "calibrated on.\n"
            "\n"
            "Exit status: 0 success, 2 bad input (command line, pattern file, or geometry the mesher\n"
            "refuses), 3 the mesh could not be computed (memory) or written.\n");
}

/* desc.progress: after the sizing map, after each panel, at the end (mesher.h ON PROGRESS). */
static void progress(void *user, const wr_mesher_progress *p) {
    char name[64];
    size_t k;
    (void)user;
    snprintf(name, sizeof name, "%s", p->panel_name ? p->panel_name : "");
    for (k = 0; name[k]; ++k) /* user text: keep the progress line one line */
        if ((unsigned char)name[k] < 32) name[k] = ' ';
    if (!strcmp(p->stage, "sizing"))
        wr_cli_progress("  sizing map: %d panel%s, %.2f s", (int)p->n_panels, p->n_panels == 1 ? "" : "s", p->seconds);
    else if (!strcmp(p->stage, "panel"))
        wr_cli_progress("  panel %d/%d%s%s%s meshed: %d vertices so far, %.2f s", (int)p->panel + 1, (int)p->n_panels,
                        name[0] ? " '" : "", name, name[0] ? "'" : "", (int)p->n_vertices,
                        p->seconds);
    else
        wr_cli_progress_end();
}

static void free_pattern(void *p) { wr_pattern_file_free((wr_pattern_file *)p); }
static void free_result(void *p) { wr_mesher_free((wr_mesher_result *)p); }

/* Mesher failures caused by the pattern (geometry, values, budget) are bad input; the rest is ours. */
static int mesher_exit(wr_status st) {
    return st == WR_ERR_NOMEM || st == WR_ERR_IO || st == WR_ERR_BACKEND ? WR_CLI_EXIT_FAILURE : WR_CLI_EXIT_USAGE;
}

int main(int argc, char **argv) {
    const char *in = NULL, *out = NULL;
    static const char *const outputs[] = {"mesh.obj", "mesh.ply", "mesh.vtk", "seams.csv", "sizing.png", "summary.json"};
    double seed = -1.0, uniform = 0.0, maxv = 0.0;
    int sew = 0, no_png = 0, quiet = 0, png = 0, n_pos = 0, k;
    wr_pattern_file pf;
    wr_mesher_result res;
    wr_diag d;
    wr_status st;
    wr_cli_opt opts[8];
    memset(opts, 0, sizeof opts);
    opts[0].name = "--output", opts[0].alias = "-o", opts[0].kind = WR_CLI_STRING, opts[0].out = (void *)&out;
    opts[1].name = "--seed", opts[1].kind = WR_CLI_INTEGER, opts[1].out = &seed, opts[1].hi = 9007199254740992.0;
    opts[2].name = "--uniform", opts[2].kind = WR_CLI_NUMBER, opts[2].out = &uniform, opts[2].lo = 1e-6,
    opts[2].hi = 1e9;
    opts[3].name = "--max-vertices", opts[3].kind = WR_CLI_INTEGER, opts[3].out = &maxv, opts[3].lo = 1,
    opts[3].hi = 2147483647.0;
    opts[4].name = "--sew", opts[4].kind = WR_CLI_FLAG, opts[4].out = &sew;
    opts[5].name = "--no-png", opts[5].kind = WR_CLI_FLAG, opts[5].out = &no_png;
    opts[6].name = "--quiet", opts[6].alias = "-q", opts[6].kind = WR_CLI_FLAG, opts[6].out = &quiet;
    wr_cli_set_program(argv[0]);
    if ((k = wr_cli_parse(argc, argv, opts, 7, &in, 1, &n_pos, usage)) <= 0) return k < 0 ? WR_CLI_EXIT_USAGE : 0;
    if (!out) {
        wr_cli_error("no output directory (use -o DIR; see --help)");
        return WR_CLI_EXIT_USAGE;
    }
    if (!wr_cli_dir_outputs_ok(out, outputs, (int)(sizeof outputs / sizeof outputs[0]), &in, in ? 1 : 0))
        return WR_CLI_EXIT_USAGE;
    memset(&pf, 0, sizeof pf);
    memset(&res, 0, sizeof res);
    st = in ? wr_pattern_load(in, &pf, &d) : wr_pattern_builtin_fig14(&pf, &d);
    if (st != WR_OK) {
        wr_cli_error("%s", d.message);
        return st == WR_ERR_NOMEM ? WR_CLI_EXIT_FAILURE : WR_CLI_EXIT_USAGE;
    }
    wr_cli_defer(free_pattern, &pf);
    if (seed >= 0) pf.desc.seed = (uint64_t)seed;
    if (uniform > 0.0) pf.desc.uniform_resolution = uniform * 1e-3;
    if (maxv > 0) pf.desc.max_vertices = (int32_t)maxv;
    if (sew) pf.desc.sew = 1;
    if (!quiet) pf.desc.progress = progress;
    st = wr_mesher_run(&pf.pattern, &pf.desc, &res, &d);
    wr_cli_progress_end(); /* a failure leaves the terminal line open */
    if (st != WR_OK) {
        /* the library names its option (max_vertices); the user's lever here is the CLI flag */
        wr_cli_error("%s: %s%s", in ? in : "built-in example", d.message,
                     st == WR_ERR_BUDGET ? "; raise the budget with --max-vertices N or coarsen the mesh with --uniform MM" : "");
        return wr_cli_exit(mesher_exit(st));
    }
    wr_cli_defer(free_result, &res);
    wr_plausible_pattern(&pf, &res);
    st = wr_meshout_write_dir(&res, &pf, out, !no_png, &png, &d);
    if (st != WR_OK) {
        wr_cli_error("%s", d.message);
        return wr_cli_exit(WR_CLI_EXIT_FAILURE);
    }
    if (!no_png && !png) wr_cli_warn("gnuplot not found, sizing.png skipped");
    if (!quiet) {
        char b1[32], b2[32];
        printf("%s: %d vertices, %d triangles, %d seam pairs; min angle %s deg, mean edge/sizing %s; %.2f s -> %s/\n",
               pf.name[0] ? pf.name : (in ? in : "pattern"), (int)res.mesh.nv, (int)res.mesh.nf, (int)res.n_seam_pairs,
               wr_cli_num(b1, sizeof b1, "%.1f", res.report.min_angle_deg),
               wr_cli_num(b2, sizeof b2, "%.3f", res.report.ratio_mean), res.report.t_total, out);
    }
    return wr_cli_exit(0);
}
