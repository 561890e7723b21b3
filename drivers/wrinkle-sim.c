/* wrinkle-sim — dynamic cloth simulation of a JSON scene (backward Euler on the shared Newton).
 *
 *   wrinkle-sim SCENE.json -o DIR [--quiet] [--every N] [--duration T] [--png] [--weld-final FILE.obj]
 *
 * Reads the scene (docs/sim-scene-format.md), builds the cloth (a sheet, or a garment: a pattern
 * meshed by the kit's mesher, placed panel by panel and sewn, garment.h), its pins, the body (the
 * kit's mannequin or an OBJ, static or keyframed) and obstacles, and runs dynamics.h frame by frame
 * to the scene's duration. Writes DIR/frame_0000.obj (the initial state) and every Nth frame after
 * it (OBJ or PLY, $.output), DIR/body.obj (the triangle-mesh bodies at their first pose),
 * DIR/frame_NNNN.png with --png (front and 3/4 views), and DIR/summary.json (per-frame NS and CH
 * milliseconds, Newton and PCG iterations, contacts, minimum distance, seam gap; totals and
 * medians); with --weld-final FILE.obj a garment's last frame as one sewn mesh (the seam pairs merged
 * by mesh.h wr_mesh_weld, per-corner vt = each panel's pattern corners, g = panel names: the base
 * bin/wrinkle-tfw reads, docs/notes-tfw-dress.md). Every file appears atomically (temporary +
 * rename). Progress on stderr: one updating line on a terminal, a line per tenth of the run
 * otherwise. Warnings (stderr, the run goes on,
 * plausible.h): a thickness above 1 cm (millimetres read as metres?), a garment panel smaller than
 * one edge or its base resolution outside Eq. 4's band, an edge strained by more than 100 % in any
 * frame (the worst frame is named: a transient runaway that settles is still a runaway).
 * Exit: 0 done; 1 a step failed (frames before it and the summary are written, the summary says why);
 * 2 bad input (one line naming the JSON path or option); 3 output or setup failure.
 */
#define _XOPEN_SOURCE 700
#include <errno.h>
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "cli.h"
#include "plausible.h"
#include "meshout.h"
#include "pattern.h"
#include "simscene.h"

static void usage(FILE *f) {
    fprintf(f,
            "usage: wrinkle-sim SCENE.json -o DIR [options]\n"
            "  Dynamic cloth simulation of SCENE.json (format: docs/sim-scene-format.md).\n"
            "  Writes DIR/frame_NNNN.obj (or .ply) and DIR/summary.json.\n"
            "options:\n"
            "  -o, --output DIR     output directory (created if missing)\n"
            "  --every N            write every Nth frame (overrides $.output.every)\n"
            "  --duration T         simulated time [s] (overrides $.time.duration)\n"
            "  --png                also DIR/frame_NNNN.png for every written frame (front and 3/4 views)\n"
            "  --weld-final FILE    garment scenes: also FILE (OBJ), the last frame sewn into one mesh (seam\n"
            "                       pairs merged, per-corner vt = the panels' pattern corners, g = panel names),\n"
            "                       e.g. a base for wrinkle-tfw; written when the run finishes without error;\n"
            "                       refused before the run if its folder is missing or the run writes FILE itself\n"
            "  --quiet              no progress on stderr\n"
            "  -h, --help           this text\n"
            "warnings (stderr, the run goes on): a thickness over 1 cm (it is in metres), a garment panel\n"
            "  smaller than one edge (a pattern in metres?) or its resolution outside the 2.5-50 mm band,\n"
            "  an edge strained by more than 100 %% in any frame (the worst one is named)\n"
            "exit status: 0 ok, 1 a step failed (outputs written), 2 bad input, 3 failure\n");
}

typedef struct sim_ctx {
    const char *dir;
    int quiet, tty, png;
    int32_t every, total;
    wr_status write_status;
    wr_diag write_diag;
    double worst_strain; /* largest edge strain over the frames run so far, and its frame */
    int32_t worst_frame;
} sim_ctx;

/* " seam gap 0.42 mm" / " welded" for a garment's progress line, "" for a sheet */
static const char *seam_note(const wr_simscene_run *run, const wr_simscene_frame *f) {
    static char buf[48];
    if (!run->sc->is_garment) return "";
    if (f->welded) return "  welded";
    snprintf(buf, sizeof buf, "  seam gap %.2f mm", 1e3 * f->seam_gap);
    return buf;
}

static int on_frame(void *user, const wr_simscene_run *run, int32_t k) {
    sim_ctx *c = (sim_ctx *)user;
    const wr_simscene_frame *f = run->frames + k;
    double strain = wr_meshout_max_strain(&run->mesh, run->x);
    if (strain > c->worst_strain) c->worst_strain = strain, c->worst_frame = k;
    if (k % c->every == 0 || k == c->total) {
        c->write_status = wr_simscene_write_frame(run, c->dir, k, &c->write_diag);
        if (c->write_status == WR_OK && c->png) c->write_status = wr_simscene_write_png(run, c->dir, k, &c->write_diag);
        if (c->write_status != WR_OK) return 1;
    }
    /* every frame on a terminal (one line redrawn), a tenth of the run when redirected */
    if (!c->quiet && (c->tty || k == c->total || c->total < 10 || k % (c->total / 10) == 0))
        wr_cli_progress("  frame %d/%d  t %.3f s  NS %.1f ms  CH %.1f ms  Newton %d  PCG %d  contacts %d%s", (int)k,
                        (int)c->total, f->t, 1e3 * f->t_ns, 1e3 * f->t_ch, (int)f->newton, (int)f->pcg, (int)f->contacts,
                        seam_note(run, f));
    return 0;
}

/* A garment's pattern, as wrinkle-mesh checks it (plausible.h): read again (run_create does not keep
 * the file) with the scene's uniform-resolution override, against the mesher's result. */
static void garment_plausibility(const wr_simscene *sc, const wr_simscene_run *run) {
    wr_pattern_file pf;
    wr_diag d;
    if (!sc->is_garment || wr_pattern_load(sc->garment.pattern, &pf, &d) != WR_OK) return;
    if (sc->garment.resolution > 0.0) pf.desc.uniform_resolution = sc->garment.resolution;
    wr_plausible_pattern(&pf, &run->mr);
    wr_pattern_file_free(&pf);
}

/* mkdir -p; 0 on success */
static int make_dir(const char *dir) {
    char buf[WR_PATH_MAX];
    size_t i, n = strlen(dir);
    if (n == 0 || n >= sizeof buf) return -1;
    memcpy(buf, dir, n + 1);
    for (i = 1; i <= n; ++i)
        if (buf[i] == '/' || buf[i] == 0) {
            char ch = buf[i];
            buf[i] = 0;
            if (mkdir(buf, 0777) != 0 && errno != EEXIST) return -1;
            buf[i] = ch;
        }
    {
        struct stat s;
        return stat(dir, &s) == 0 && S_ISDIR(s.st_mode) ? 0 : -1;
    }
}

/* cli.h's output checks for every file the run would write (summary, bodies, each written frame and
 * its picture) against the inputs (the scene, the cloth OBJ, the pattern, body and obstacle OBJs):
 * DIR must not be an existing file, no output may resolve to an input. 1 when all are fine. */
static int outputs_ok(const wr_simscene *sc, const char *scene_path, const char *dir, int32_t n_frames, int32_t every,
                      int png, const char *welded) {
    static const char *const fixed[] = {"summary.json", "body.obj"};
    const char *inputs[1 + WR_SIMSCENE_MAX_INPUTS + WR_SIMSCENE_MAX_BODY_KEYS];
    char name[32], path[WR_PATH_MAX + 32];
    int32_t k;
    int n;
    inputs[0] = scene_path;
    n = 1 + (int)wr_simscene_inputs(sc, inputs + 1, (int32_t)(sizeof inputs / sizeof inputs[0]) - 1);
    if (!wr_cli_dir_outputs_ok(dir, fixed, 2, inputs, n)) return 0;
    if (welded && !wr_cli_output_ok(welded, inputs, n)) return 0;
    for (k = 0; k <= n_frames; ++k) {
        if (k % every && k != n_frames) continue;
        wr_simscene_frame_name(sc, k, name);
        snprintf(path, sizeof path, "%s/%s", dir, name);
        if (!wr_cli_output_ok(path, inputs, n)) return 0;
        snprintf(path, sizeof path, "%s/frame_%04d.png", dir, (int)k);
        if (png && !wr_cli_output_ok(path, inputs, n)) return 0;
    }
    return 1;
}

/* --weld-final FILE against the run's own outputs, checked once DIR exists and before any frame is
 * run: FILE's folder must exist, and FILE must not be one of the files the run writes into DIR
 * (summary, bodies, frames, pictures), which would be overwritten after the run or overwrite them.
 * 1 when fine (error printed otherwise). */
static int welded_path_ok(const wr_simscene *sc, const char *dir, int32_t n_frames, int32_t every, int png, const char *welded) {
    static const char *const fixed[] = {"summary.json", "body.obj"};
    char wdir[WR_PATH_MAX], rw[PATH_MAX], rd[PATH_MAX], name[32];
    const char *slash = strrchr(welded, '/'), *base = slash ? slash + 1 : welded;
    int32_t k;
    if (!slash)
        strcpy(wdir, ".");
    else if (slash == welded)
        strcpy(wdir, "/");
    else if ((size_t)(slash - welded) < sizeof wdir) {
        memcpy(wdir, welded, (size_t)(slash - welded));
        wdir[slash - welded] = 0;
    } else
        wdir[0] = 0; /* too long: refused below */
    if (*base == 0 || !wdir[0] || !realpath(wdir, rw)) {
        wr_cli_error("--weld-final %s: no such folder or no file name", welded);
        return 0;
    }
    if (!realpath(dir, rd) || strcmp(rw, rd) != 0) return 1;
    for (k = 0; k < 2; ++k)
        if (strcmp(base, fixed[k]) == 0) goto clash;
    for (k = 0; k <= n_frames; ++k) {
        if (k % every && k != n_frames) continue;
        wr_simscene_frame_name(sc, k, name);
        if (strcmp(base, name) == 0) goto clash;
        snprintf(name, sizeof name, "frame_%04d.png", (int)k);
        if (png && strcmp(base, name) == 0) goto clash;
    }
    return 1;
clash:
    wr_cli_error("--weld-final %s: the run itself writes %s/%s; choose another name", welded, dir, base);
    return 0;
}

/* --weld-final: the last frame sewn into one OBJ; warns when the seams were not welded by the run
 * (the pairs' positions are then averaged across the gap). 0 on success (error printed otherwise). */
static int write_welded(const wr_simscene_run *run, const char *path, int quiet) {
    wr_diag d;
    if (!run->gs.welded)
        fprintf(stderr, "%s: warning: the seams were not welded during the run (largest seam gap %.2f mm): %s "
                        "merges each pair at its midpoint\n", wr_cli_program(), 1e3 * run->gs.gap, path);
    if (wr_simscene_write_welded(run, path, &d) != WR_OK) {
        wr_cli_error("writing %s: %s", path, d.message);
        return -1;
    }
    if (!quiet) fprintf(stderr, "  welded last frame: %s\n", path);
    return 0;
}

static void free_scene(void *p) { wr_simscene_free((wr_simscene *)p); }
static void free_run(void *p) { wr_simscene_run_free((wr_simscene_run *)p); }

int main(int argc, char **argv) {
    const char *scene_path = NULL, *out = NULL, *welded = NULL;
    double every = 0.0, duration = -1.0;
    int quiet = 0, png = 0, n_pos = 0, k;
    wr_simscene sc;
    wr_simscene_run run;
    sim_ctx ctx;
    wr_diag d;
    wr_status st;
    char summary[WR_PATH_MAX];
    wr_cli_opt opts[6];
    memset(opts, 0, sizeof opts);
    opts[0].name = "--output", opts[0].alias = "-o", opts[0].kind = WR_CLI_STRING, opts[0].out = (void *)&out;
    opts[1].name = "--every", opts[1].kind = WR_CLI_INTEGER, opts[1].out = &every, opts[1].lo = 1.0, opts[1].hi = 1e6;
    opts[2].name = "--duration", opts[2].kind = WR_CLI_NUMBER, opts[2].out = &duration, opts[2].lo = 0.0,
    opts[2].hi = 1e9; /* the frame count is checked against the scene's dt below */
    opts[3].name = "--quiet", opts[3].kind = WR_CLI_FLAG, opts[3].out = &quiet;
    opts[4].name = "--png", opts[4].kind = WR_CLI_FLAG, opts[4].out = &png;
    opts[5].name = "--weld-final", opts[5].kind = WR_CLI_STRING, opts[5].out = (void *)&welded;
    wr_cli_set_program(argv[0]);
    if ((k = wr_cli_parse(argc, argv, opts, 6, &scene_path, 1, &n_pos, usage)) <= 0) return k < 0 ? WR_CLI_EXIT_USAGE : 0;
    if (!wr_cli_scene_args_ok(scene_path, out)) return WR_CLI_EXIT_USAGE;
    if (wr_simscene_load(&sc, scene_path, &d) != WR_OK) {
        wr_cli_error("%s: %s", scene_path, d.message);
        return WR_CLI_EXIT_USAGE;
    }
    wr_cli_defer(free_scene, &sc);
    if (welded && !sc.is_garment) {
        wr_cli_error("--weld-final: %s is not a garment scene (no $.garment: nothing to weld)", scene_path);
        return wr_cli_exit(WR_CLI_EXIT_USAGE);
    }
    {
        char what[WR_PATH_MAX + 48];
        snprintf(what, sizeof what, "%s: $.%s.material.thickness", scene_path, sc.is_garment ? "garment" : "cloth");
        wr_plausible_thickness(what, sc.is_garment ? sc.garment.shell.thickness : sc.cloth.shell.thickness);
    }
    if (every > 0.0) sc.output_every = (int32_t)every;
    if (duration >= 0.0) {
        if (duration / sc.dyn.time.dt > WR_SIMSCENE_MAX_FRAMES) {
            wr_cli_error("--duration %g s at dt %g s is more than %d frames", duration, sc.dyn.time.dt, WR_SIMSCENE_MAX_FRAMES);
            return wr_cli_exit(WR_CLI_EXIT_USAGE);
        }
        sc.duration = duration;
    }
    st = wr_simscene_run_create(&run, &sc, &d);
    if (st != WR_OK) {
        wr_cli_error("%s: %s", scene_path, d.message);
        return wr_cli_exit(st == WR_ERR_NOMEM ? WR_CLI_EXIT_FAILURE : WR_CLI_EXIT_USAGE);
    }
    wr_cli_defer(free_run, &run);
    garment_plausibility(&sc, &run);
    if (!outputs_ok(&sc, scene_path, out, run.n_frames_max - 1, sc.output_every, png, welded)) return wr_cli_exit(WR_CLI_EXIT_USAGE);
    if (make_dir(out) != 0) {
        wr_cli_error("cannot create output directory %s", out);
        return wr_cli_exit(WR_CLI_EXIT_FAILURE);
    }
    if (welded && !welded_path_ok(&sc, out, run.n_frames_max - 1, sc.output_every, png, welded))
        return wr_cli_exit(WR_CLI_EXIT_USAGE);
    if ((size_t)snprintf(summary, sizeof summary, "%s/summary.json", out) >= sizeof summary) {
        wr_cli_error("output path too long: %s", out);
        return wr_cli_exit(WR_CLI_EXIT_USAGE);
    }
    memset(&ctx, 0, sizeof ctx);
    ctx.dir = out;
    ctx.quiet = quiet;
    ctx.tty = wr_cli_progress_tty();
    ctx.png = png;
    ctx.every = sc.output_every;
    ctx.total = run.n_frames_max - 1;
    if (!quiet) {
        const wr_dyn *dyn = wr_simscene_dyn(&run);
        fprintf(stderr, "%s: %d vertices, %d faces, %d pinned, %d analytic obstacle(s), %d mesh bod%s, %d frames of %.4f s, %s\n",
                sc.name, (int)run.mesh.nv, (int)run.mesh.nf, (int)run.n_fixed, (int)sc.n_analytic, (int)run.n_bodies,
                run.n_bodies == 1 ? "y" : "ies", (int)ctx.total, dyn->desc.time.dt, wr_solver_method_name(dyn->desc.linear.method));
        if (sc.is_garment)
            fprintf(stderr, "  garment: %d panels, %d seam pairs, largest seam gap %.1f mm as placed\n", (int)run.n_panels,
                    (int)run.gs.n_pairs, 1e3 * run.gs.gap);
    }
    if ((st = wr_simscene_write_frame(&run, out, 0, &d)) != WR_OK ||
        (png && (st = wr_simscene_write_png(&run, out, 0, &d)) != WR_OK) || (st = wr_simscene_write_bodies(&run, out, &d)) != WR_OK) {
        wr_cli_error("writing frame 0: %s", d.message);
        return wr_cli_exit(WR_CLI_EXIT_FAILURE);
    }
    st = wr_simscene_run_frames(&run, on_frame, &ctx, &d);
    wr_cli_progress_end();
    {
        char what[32];
        snprintf(what, sizeof what, "frame %d", (int)ctx.worst_frame);
        wr_plausible_strain(what, ctx.worst_strain);
    }
    if (ctx.write_status != WR_OK) {
        wr_cli_error("writing frames: %s", ctx.write_diag.message);
        return wr_cli_exit(WR_CLI_EXIT_FAILURE);
    }
    if (wr_simscene_write_summary(&run, summary, &d) != WR_OK) {
        wr_cli_error("writing %s: %s", summary, d.message);
        return wr_cli_exit(WR_CLI_EXIT_FAILURE);
    }
    if (st != WR_OK) {
        fprintf(stderr, "%s: %s (frames before it and the summary are written)\n", wr_cli_program(), run.status_message);
        return wr_cli_exit(1);
    }
    if (!quiet) fprintf(stderr, "  %d frames in %.2f s (setup %.2f s)\n", (int)run.n_frames, run.t_run, run.t_setup);
    if (welded && write_welded(&run, welded, quiet) != 0) return wr_cli_exit(WR_CLI_EXIT_FAILURE);
    return wr_cli_exit(0);
}
