/* wrinkle-statics — static equilibrium of a thin shell described by a JSON scene.
 *
 *   wrinkle-statics SCENE.json -o DIR [--quiet] [--resolution R] [--load-steps N] [--png]
 *
 * Reads the scene (docs/scene-format.md), builds the rest mesh and the shell (shell.h), applies the
 * prescribed motions in load steps and solves each step with Newton (statics.h), then writes
 * DIR/deformed.obj, DIR/fields.ply (displacement and Green strain per vertex) and DIR/summary.json
 * (energies, iterations, residuals, timings, wrinkle counts per probe); with --png DIR/deformed.png
 * (render.h: the equilibrium shaded, coloured by displacement). Progress goes to stderr. Warnings: a
 * thickness above 1 cm, an edge strained by more than 100 %.
 * Exit: 0 solved; 1 solved but a load step did not converge (outputs still written, status in the
 * summary); 2 bad input (one line naming the JSON path); 3 solver or output failure.
 */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"
#include "plausible.h"
#include "meshout.h"
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
            "  --png                also DIR/deformed.png (shaded, coloured by displacement)\n"
            "  --quiet              no progress on stderr\n"
            "  -h, --help           this text\n"
            "exit status: 0 ok, 1 not converged (outputs written), 2 bad input, 3 failure\n");
}

static void progress(void *user, int32_t step, int32_t n, const wr_statics_stats *st) {
    (void)user;
    wr_cli_progress("  step %d/%d  Newton %3d  |g|/ref %.2e  E %.6e J  %.1f s", (int)step, (int)n, (int)st->iterations,
                    st->grad_ref > 0 ? st->grad_norm / st->grad_ref : 0.0, st->energy, st->t_total);
}

static void free_scene(void *p) { wr_scene_free((wr_scene *)p); }
static void free_run(void *p) { wr_scene_run_free((wr_scene_run *)p); }

/* DIR/deformed.png: the equilibrium, coloured by the displacement from the rest shape [mm]. */
static wr_status picture(const wr_scene_run *run, const char *dir, wr_diag *d) {
    wr_render_panel pn;
    wr_view_desc vd;
    char path[4096], title[160];
    double *u = (double *)malloc(sizeof(double) * (size_t)run->mesh.nv);
    int32_t v;
    int k;
    wr_status st;
    if (!u) return wr_fail(d, WR_ERR_NOMEM, -1, "out of memory");
    for (v = 0; v < run->mesh.nv; ++v) {
        double s = 0.0;
        for (k = 0; k < 3; ++k) s += (run->x[3 * v + k] - run->mesh.pos[3 * v + k]) * (run->x[3 * v + k] - run->mesh.pos[3 * v + k]);
        u[v] = 1e3 * sqrt(s);
    }
    memset(&pn, 0, sizeof pn);
    memset(&vd, 0, sizeof vd);
    snprintf(title, sizeof title, "%s: equilibrium, %d vertices", run->sc->name, (int)run->mesh.nv);
    pn.pos = run->x;
    pn.nv = run->mesh.nv;
    pn.faces = run->mesh.faces;
    pn.nf = run->mesh.nf;
    pn.title = title;
    pn.style.scalar = u;
    pn.style.wireframe = run->mesh.nf <= 20000; /* beyond that the edges would paint the picture black */
    pn.colorbar_label = "displacement mm";
    snprintf(path, sizeof path, "%s/deformed.png", dir);
    st = wr_meshout_png(path, &pn, 1, 1, 1000, 700, &vd, d);
    free(u);
    return st;
}

int main(int argc, char **argv) {
    const char *scene_path = NULL, *out = NULL, *inputs[2];
    static const char *const outputs[] = {"deformed.obj", "fields.ply", "summary.json", "deformed.png"};
    double res_override = 0.0, steps_override = 0.0;
    int quiet = 0, png = 0, i, n_pos = 0;
    wr_scene sc;
    wr_scene_run run;
    wr_diag d;
    wr_status st;
    wr_cli_opt opts[5];
    memset(opts, 0, sizeof opts);
    opts[0].name = "--output", opts[0].alias = "-o", opts[0].kind = WR_CLI_STRING, opts[0].out = (void *)&out;
    opts[1].name = "--resolution", opts[1].kind = WR_CLI_NUMBER, opts[1].out = &res_override, opts[1].lo = 1e-9,
    opts[1].hi = 1e9;
    opts[2].name = "--load-steps", opts[2].kind = WR_CLI_INTEGER, opts[2].out = &steps_override, opts[2].lo = 1,
    opts[2].hi = 100000;
    opts[3].name = "--quiet", opts[3].alias = "-q", opts[3].kind = WR_CLI_FLAG, opts[3].out = &quiet;
    opts[4].name = "--png", opts[4].kind = WR_CLI_FLAG, opts[4].out = &png;
    wr_cli_set_program(argv[0]);
    if ((i = wr_cli_parse(argc, argv, opts, 5, &scene_path, 1, &n_pos, usage)) <= 0) return i < 0 ? WR_CLI_EXIT_USAGE : 0;
    if (!wr_cli_scene_args_ok(scene_path, out)) return WR_CLI_EXIT_USAGE;
    memset(&sc, 0, sizeof sc);
    memset(&run, 0, sizeof run);
    if (wr_scene_load(&sc, scene_path, &d) != WR_OK) {
        wr_cli_error("%s: %s", scene_path, d.message);
        return WR_CLI_EXIT_USAGE;
    }
    wr_cli_defer(free_scene, &sc);
    inputs[0] = scene_path;
    inputs[1] = sc.mesh.kind == WR_SCENE_MESH_OBJ ? sc.mesh.path : NULL;
    if (!wr_cli_dir_outputs_ok(out, outputs, 4, inputs, 2)) return wr_cli_exit(WR_CLI_EXIT_USAGE);
    {
        char what[WR_PATH_MAX + 32];
        snprintf(what, sizeof what, "%s: $.material.thickness", scene_path);
        wr_plausible_thickness(what, sc.shell.thickness);
    }
    if (res_override > 0.0) sc.mesh.resolution = res_override, sc.mesh.nx = sc.mesh.ny = 0;
    if (steps_override > 0.0) sc.load_steps = (int32_t)steps_override;
    st = wr_scene_run_create(&run, &sc, &d);
    if (st != WR_OK) {
        wr_cli_error("%s: %s", scene_path, d.message);
        return wr_cli_exit(st == WR_ERR_NOMEM ? WR_CLI_EXIT_FAILURE : WR_CLI_EXIT_USAGE);
    }
    wr_cli_defer(free_run, &run);
    if (!quiet)
        fprintf(stderr, "%s: %s mesh, %d vertices, %d faces, %d prescribed, %d load step(s)\n", sc.name,
                wr_scene_mesh_kind_name(sc.mesh.kind), (int)run.mesh.nv, (int)run.mesh.nf, (int)run.n_fixed,
                (int)sc.load_steps);
    st = wr_scene_run_solve(&run, quiet ? NULL : progress, NULL, &d);
    wr_cli_progress_end();
    if (st != WR_OK && st != WR_ERR_NOT_CONVERGED) {
        wr_cli_error("solve failed: %s", d.message);
        return wr_cli_exit(WR_CLI_EXIT_FAILURE);
    }
    if (st == WR_ERR_NOT_CONVERGED) wr_cli_warn("%s", d.message);
    wr_plausible_strain("the result", wr_meshout_max_strain(&run.mesh, run.x));
    if (wr_scene_run_write(&run, out, &d) != WR_OK || (png && picture(&run, out, &d) != WR_OK)) {
        wr_cli_error("writing %s: %s", out, d.message);
        return wr_cli_exit(WR_CLI_EXIT_FAILURE);
    }
    if (!quiet) {
        fprintf(stderr, "  %d Newton steps, solve %.2f s (assembly %.2f, projection %.2f, linear %.2f, line search %.2f)\n",
                (int)run.newton_iterations, run.t_solve, run.t_assembly, run.t_projection, run.t_linear,
                run.t_line_search);
        for (i = 0; i < sc.n_probes; ++i) {
            wr_spectrum_result r;
            char b1[32], b2[32], b3[32];
            if (wr_scene_run_probe(&run, i, &r, &d) == WR_OK)
                fprintf(stderr, "  probe %s: wavelength %s mm, %s wrinkles, amplitude %s mm\n", sc.probe[i].name,
                        wr_cli_num(b1, sizeof b1, "%.3f", 1e3 * r.wavelength), wr_cli_num(b2, sizeof b2, "%.2f", r.count),
                        wr_cli_num(b3, sizeof b3, "%.3f", 1e3 * r.amplitude_p2p));
            else
                fprintf(stderr, "  probe %s: %s\n", sc.probe[i].name, d.message);
        }
    }
    return wr_cli_exit(st == WR_OK ? 0 : 1);
}
