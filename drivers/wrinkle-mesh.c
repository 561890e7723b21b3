/* wrinkle-mesh — garment pattern (JSON, millimetres) → one optimally resolved simulation mesh
 * (Style3D Sec. 4.1–4.3). See --help and docs/pattern-format.md. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"
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
            "  DIR/mesh.obj      vertices, vt = 2D rest (pattern) positions, one group per panel\n"
            "  DIR/mesh.ply      per-vertex sizing, sizing_warp, sizing_weft [m] and panel id\n"
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
            "  -q, --quiet             no summary line on stdout\n"
            "  -h, --help              this text\n"
            "\n"
            "Exit status: 0 success, 1 the pattern could not be meshed or written, 2 usage error.\n");
}

int main(int argc, char **argv) {
    const char *in = NULL, *out = NULL;
    double seed = -1.0, uniform = 0.0, maxv = 0.0;
    int sew = 0, no_png = 0, quiet = 0, i, png = 0;
    wr_pattern_file pf;
    wr_mesher_result res;
    wr_diag d;
    wr_status st;
    wr_cli_set_program(argv[0]);
    for (i = 1; i < argc; ++i) {
        int k;
        const char *v;
        if (!strcmp(argv[i], "-h") || !strcmp(argv[i], "--help")) {
            usage(stdout);
            return 0;
        }
        if (!strcmp(argv[i], "-o")) {
            if (i + 1 >= argc) {
                wr_cli_error("-o needs a directory");
                return WR_CLI_EXIT_USAGE;
            }
            out = argv[++i];
            continue;
        }
        if ((k = wr_cli_value(argc, argv, &i, "--output", &v)) != 0) {
            if (k < 0) return WR_CLI_EXIT_USAGE;
            out = v;
            continue;
        }
        if ((k = wr_cli_double(argc, argv, &i, "--seed", &seed)) != 0) {
            if (k < 0) return WR_CLI_EXIT_USAGE;
            if (seed < 0 || seed != (double)(long long)seed || seed > 9007199254740992.0) {
                wr_cli_error("--seed must be a non-negative integer");
                return WR_CLI_EXIT_USAGE;
            }
            continue;
        }
        if ((k = wr_cli_double(argc, argv, &i, "--uniform", &uniform)) != 0) {
            if (k < 0) return WR_CLI_EXIT_USAGE;
            if (!(uniform > 0.0)) {
                wr_cli_error("--uniform must be a positive length in mm");
                return WR_CLI_EXIT_USAGE;
            }
            continue;
        }
        if ((k = wr_cli_integer(argc, argv, &i, "--max-vertices", 1.0, 2147483647.0, &maxv)) != 0) {
            if (k < 0) return WR_CLI_EXIT_USAGE;
            continue;
        }
        if (wr_cli_is_flag(argv[i], "--sew")) {
            sew = 1;
            continue;
        }
        if (wr_cli_is_flag(argv[i], "--no-png")) {
            no_png = 1;
            continue;
        }
        if (!strcmp(argv[i], "-q") || wr_cli_is_flag(argv[i], "--quiet")) {
            quiet = 1;
            continue;
        }
        if (argv[i][0] == '-' && argv[i][1] != 0) {
            wr_cli_error("unknown option '%s' (see --help)", argv[i]);
            return WR_CLI_EXIT_USAGE;
        }
        if (in) {
            wr_cli_error("more than one pattern file ('%s' and '%s')", in, argv[i]);
            return WR_CLI_EXIT_USAGE;
        }
        in = argv[i];
    }
    if (!out) {
        wr_cli_error("no output directory (use -o DIR; see --help)");
        return WR_CLI_EXIT_USAGE;
    }
    st = in ? wr_pattern_load(in, &pf, &d) : wr_pattern_builtin_fig14(&pf, &d);
    if (st != WR_OK) {
        wr_cli_error("%s", d.message);
        return 1;
    }
    if (seed >= 0) pf.desc.seed = (uint64_t)seed;
    if (uniform > 0.0) pf.desc.uniform_resolution = uniform * 1e-3;
    if (maxv > 0) pf.desc.max_vertices = (int32_t)maxv;
    if (sew) pf.desc.sew = 1;
    st = wr_mesher_run(&pf.pattern, &pf.desc, &res, &d);
    if (st != WR_OK) {
        /* the library names its option (max_vertices); the user's lever here is the CLI flag */
        wr_cli_error("%s: %s%s", in ? in : "built-in example", d.message,
                     st == WR_ERR_BUDGET ? "; raise the budget with --max-vertices N or coarsen the mesh with --uniform MM" : "");
        wr_pattern_file_free(&pf);
        return 1;
    }
    st = wr_meshout_write_dir(&res, &pf, out, !no_png, &png, &d);
    if (st != WR_OK) {
        wr_cli_error("%s", d.message);
        wr_mesher_free(&res);
        wr_pattern_file_free(&pf);
        return 1;
    }
    if (!no_png && !png) fprintf(stderr, "%s: warning: gnuplot not found, sizing.png skipped\n", wr_cli_program());
    if (!quiet)
        printf("%s: %d vertices, %d triangles, %d seam pairs; min angle %.1f deg, mean edge/sizing %.3f; %.2f s -> %s/\n",
               pf.name[0] ? pf.name : (in ? in : "pattern"), (int)res.mesh.nv, (int)res.mesh.nf, (int)res.n_seam_pairs,
               res.report.min_angle_deg, res.report.ratio_mean, res.report.t_total, out);
    wr_mesher_free(&res);
    wr_pattern_file_free(&pf);
    return 0;
}
