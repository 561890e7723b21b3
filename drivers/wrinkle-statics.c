/* wrinkle-statics — static equilibrium of a thin shell described by a JSON scene.
 *
 *   wrinkle-statics SCENE.json -o DIR [--quiet] [--resolution R] [--load-steps N]
 *
 * Reads the scene (docs/scene-format.md), builds the rest mesh and the shell (shell.h), applies the
 * prescribed motions in load steps and solves each step with Newton (statics.h), then writes
 * DIR/deformed.obj, DIR/fields.ply (displacement and Green strain per vertex) and DIR/summary.json
 * (energies, iterations, residuals, timings, wrinkle counts per probe). Progress goes to stderr.
 * Exit: 0 solved; 1 solved but a load step did not converge (outputs still written, status in the
 * summary); 2 bad input (one line naming the JSON path); 3 solver or output failure.
 */
#define _POSIX_C_SOURCE 200809L
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"
#include "scene.h"

static void usage(FILE *f) {
    fprintf(f,
            "usage: wrinkle-statics SCENE.json -o DIR [options]\n"
            "  Static equilibrium of the shell in SCENE.json (format: docs/scene-format.md).\n"
            "  Writes DIR/deformed.obj, DIR/fields.ply, DIR/summary.json.\n"
            "options:\n"
            "  -o, --output DIR     output directory (created if missing)\n"
            "  --resolution R       override $.mesh.resolution [m]\n"
            "  --load-steps N       override $.solver.load_steps\n"
            "  --quiet              no progress on stderr\n"
            "  -h, --help           this text\n"
            "exit status: 0 ok, 1 not converged (outputs written), 2 bad input, 3 failure\n");
}

static void progress(void *user, int32_t step, int32_t n, const wr_statics_stats *st) {
    (void)user;
    fprintf(stderr, "\r  step %d/%d  Newton %3d  |g|/ref %.2e  E %.6e J  %.1f s   ", (int)step, (int)n,
            (int)st->iterations, st->grad_ref > 0 ? st->grad_norm / st->grad_ref : 0.0, st->energy, st->t_total);
}

int main(int argc, char **argv) {
    const char *scene_path = NULL, *out = NULL;
    double res_override = 0.0, steps_override = 0.0;
    int quiet = 0, i, k;
    wr_scene sc;
    wr_scene_run run;
    wr_diag d;
    wr_status st;
    wr_cli_set_program(argv[0]);
    for (i = 1; i < argc; ++i) {
        if (wr_cli_is_flag(argv[i], "--help") || wr_cli_is_flag(argv[i], "-h")) {
            usage(stdout);
            return 0;
        }
        if (wr_cli_is_flag(argv[i], "--quiet")) {
            quiet = 1;
            continue;
        }
        if ((k = wr_cli_double(argc, argv, &i, "--resolution", &res_override)) != 0) {
            if (k < 0) return WR_CLI_EXIT_USAGE;
            if (!(res_override > 0.0)) {
                wr_cli_error("--resolution must be > 0");
                return WR_CLI_EXIT_USAGE;
            }
            continue;
        }
        if ((k = wr_cli_integer(argc, argv, &i, "--load-steps", 1.0, 100000.0, &steps_override)) != 0) {
            if (k < 0) return WR_CLI_EXIT_USAGE;
            continue;
        }
        /* -o/--output DIR, the SCENE.json positional, or an unknown option */
        if (wr_cli_scene_arg(argc, argv, &i, &scene_path, &out) < 0) return WR_CLI_EXIT_USAGE;
    }
    if (!wr_cli_scene_args_ok(scene_path, out)) return WR_CLI_EXIT_USAGE;
    if (wr_scene_load(&sc, scene_path, &d) != WR_OK) {
        wr_cli_error("%s: %s", scene_path, d.message);
        return WR_CLI_EXIT_USAGE;
    }
    if (res_override > 0.0) sc.mesh.resolution = res_override, sc.mesh.nx = sc.mesh.ny = 0;
    if (steps_override > 0.0) sc.load_steps = (int32_t)steps_override;
    st = wr_scene_run_create(&run, &sc, &d);
    if (st != WR_OK) {
        wr_cli_error("%s: %s", scene_path, d.message);
        wr_scene_free(&sc);
        return st == WR_ERR_NOMEM ? 3 : WR_CLI_EXIT_USAGE;
    }
    if (!quiet)
        fprintf(stderr, "%s: %s mesh, %d vertices, %d faces, %d prescribed, %d load step(s)\n", sc.name,
                wr_scene_mesh_kind_name(sc.mesh.kind), (int)run.mesh.nv, (int)run.mesh.nf, (int)run.n_fixed,
                (int)sc.load_steps);
    st = wr_scene_run_solve(&run, quiet ? NULL : progress, NULL, &d);
    if (!quiet) fprintf(stderr, "\n");
    if (st != WR_OK && st != WR_ERR_NOT_CONVERGED) {
        wr_cli_error("solve failed: %s", d.message);
        wr_scene_run_free(&run);
        wr_scene_free(&sc);
        return 3;
    }
    if (st == WR_ERR_NOT_CONVERGED) fprintf(stderr, "%s: warning: %s\n", wr_cli_program(), d.message);
    {
        wr_status ws = wr_scene_run_write(&run, out, &d);
        if (ws != WR_OK) {
            wr_cli_error("writing %s: %s", out, d.message);
            wr_scene_run_free(&run);
            wr_scene_free(&sc);
            return 3;
        }
    }
    if (!quiet) {
        fprintf(stderr, "  %d Newton steps, solve %.2f s (assembly %.2f, projection %.2f, linear %.2f, line search %.2f)\n",
                (int)run.newton_iterations, run.t_solve, run.t_assembly, run.t_projection, run.t_linear,
                run.t_line_search);
        for (i = 0; i < sc.n_probes; ++i) {
            wr_spectrum_result r;
            if (wr_scene_run_probe(&run, i, &r, &d) == WR_OK)
                fprintf(stderr, "  probe %s: wavelength %.3f mm, %.2f wrinkles, amplitude %.3f mm\n", sc.probe[i].name,
                        1e3 * r.wavelength, r.count, 1e3 * r.amplitude_p2p);
            else
                fprintf(stderr, "  probe %s: %s\n", sc.probe[i].name, d.message);
        }
    }
    wr_scene_run_free(&run);
    wr_scene_free(&sc);
    return st == WR_OK ? 0 : 1;
}
