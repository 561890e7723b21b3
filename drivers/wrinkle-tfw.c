/* wrinkle-tfw — TFW wrinkles end to end on a JSON scene (docs/scene-format.md).
 *
 *   wrinkle-tfw SCENE.json -o DIR [--levels N] [--png] [--quiet]
 *
 * The scene's mesh, material, boundary conditions, gravity and load steps give the base surface,
 * solved with the TFW Sec. 4.1 model whatever the scene's shell section says (TFT membrane +
 * quadratic bending, statics.h through the scene library). Then tfw.h: wrinkle-free set W, App. E.2
 * initial guess, App. E.3 SQP, App. E.4 phase, App. E.5 Loop upsampling (N levels, default 2).
 * Writes DIR/base.obj, DIR/wrinkled.obj (vt, vn), DIR/fields.ply + fields.vtk (per base vertex: a
 * [m], |ω| mean over incident edges [rad], W = 1 when every incident face is wrinkle-free, phase
 * [rad], sizing [m]), DIR/wrinkled.ply + wrinkled.vtk (per fine vertex: a, height [m], phase [rad], W,
 * sizing [m]; drivers/lib/meshout.h says what each is), with --png
 * DIR/wrinkles.png (render.h: the coarse base beside the wrinkled surface) and DIR/summary.json
 * (TFT and SQP iterations, residuals, timings, wrinkle counts per scene probe measured on the
 * wrinkled surface). Every file is written to a temporary name and renamed. Progress on stderr.
 * Exit: 0 done; 1 outputs written but the base or the SQP did not converge; 2 bad input (one line);
 * 3 solver or output failure. Warnings (stderr, the run goes on): a thickness above 1 cm (metres
 * meant as millimetres?), an edge strained by more than 100 %.
 */
#define _POSIX_C_SOURCE 200809L
#include <cjson/cJSON.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "cli.h"
#include "plausible.h"
#include "jsonout.h"
#include "meshout.h"
#include "scene.h"
#include "wrinkle/tfw.h"

static void usage(FILE *f) {
    fprintf(f,
            "usage: wrinkle-tfw SCENE.json -o DIR [options]\n"
            "  TFW wrinkles (Chen et al. 2021) on the scene's TFT base surface (format: docs/scene-format.md).\n"
            "  Writes DIR/base.obj, DIR/wrinkled.obj (vt, vn, the input OBJ's panel names), DIR/fields.ply + .vtk\n"
            "  (a, |omega|, W, phase, sizing per base vertex), DIR/wrinkled.ply + .vtk (a, height, phase, W, sizing\n"
            "  per fine vertex), DIR/summary.json (with the scene's probes measured on the wrinkled surface:\n"
            "  per-panel probes also on a welded sewn base, $.mesh.weld; docs/scene-format.md).\n"
            "options:\n"
            "  -o, --output DIR     output directory (created if missing)\n"
            "  --levels N           Loop subdivision levels of the wrinkled mesh (default 2, 0..5)\n"
            "  --png                also DIR/wrinkles.png: the coarse base beside the wrinkled surface\n"
            "  --clamp-amplitude    a = 0 on the scene's prescribed vertices (the TFW paper's clamp reading, and\n"
            "                       the release's code; default: a clamp holds the base only, as the release's\n"
            "                       shipped examples ran: docs/notes-tfw-authors.md)\n"
            "  --kappa K            curvature of Eq. 22: midedge (default) or vertex-fit (quadric fit, as the\n"
            "                       authors' release; wrinkle_field.h ON READINGS OF THE PAPER)\n"
            "  --wset R             wrinkle-free set W: paper (Sec. 5.1, default) or release (own eigenvalue)\n"
            "  --start R            App. E.2 start: paper (default) or release (the release's amplitude scale)\n"
            "  --quiet              no progress on stderr\n"
            "  -h, --help           this text\n"
            "exit status: 0 ok, 1 not converged (outputs written), 2 bad input, 3 failure\n");
}

static void base_progress(void *user, int32_t step, int32_t n, const wr_statics_stats *st) {
    (void)user;
    wr_cli_progress("  TFT base: step %d/%d  Newton %3d  |g|/ref %.2e  %.1f s", (int)step, (int)n, (int)st->iterations,
                    st->grad_ref > 0 ? st->grad_norm / st->grad_ref : 0.0, st->t_total);
}

static void sqp_progress(const wr_wf_iter_info *info, void *user) {
    (void)user;
    wr_cli_progress("  SQP: iteration %4d  E %.8e J  KKT %.2e  mu %.1e  active %d", (int)info->iteration, info->energy,
                    info->kkt, info->shift, (int)info->n_active);
}

static void free_scene(void *p) { wr_scene_free((wr_scene *)p); }
static void free_run(void *p) { wr_scene_run_free((wr_scene_run *)p); }
static void free_tfw(void *p) { wr_tfw_result_free((wr_tfw_result *)p); }

/* Probe i of the scene on the wrinkled surface: displacement from the smooth (a = 0) subdivided base
 * along the probe direction, or along the smooth base's normal with "dir": "normal" (only the faces of the probe's panel; fine keeps the base's face_panel). */
static wr_status probe_wrinkled(const wr_scene_run *run, int32_t i, const wr_mesh *fine, const double *smooth,
                                wr_spectrum_result *res, wr_diag *d) {
    const wr_scene_probe *pr = &run->sc->probe[i];
    wr_probe p;
    int32_t n = pr->samples > 0 ? pr->samples : 512, nout = 0, start = 0, len;
    double *pts = (double *)malloc(sizeof(double) * 2 * (size_t)n), *val = (double *)malloc(sizeof(double) * (size_t)n);
    double *fld = (double *)malloc(sizeof(double) * (size_t)fine->nv), ds = 0.0;
    wr_status st;
    if (!pts || !val || !fld) {
        free(pts);
        free(val);
        free(fld);
        return wr_fail(d, WR_ERR_NOMEM, -1, "probe: out of memory");
    }
    st = wr_scene_probe_field(pr, fine, fine->pos, smooth, fld, d);
    if (!st && pr->closed) {
        double c[2], r;
        c[0] = 0.5 * (pr->from[0] + pr->to[0]);
        c[1] = 0.5 * (pr->from[1] + pr->to[1]);
        r = 0.5 * hypot(pr->to[0] - pr->from[0], pr->to[1] - pr->from[1]);
        st = wr_path_circle(c, r, n, pts, &ds, d);
    } else if (!st) {
        st = wr_path_segment(pr->from, pr->to, n, 0, pts, &ds, d);
    }
    if (!st) st = wr_scene_probe_locator(run, i, fine, pts, n, &p, d);
    if (!st) {
        st = wr_probe_sample(&p, fld, pts, n, val, &nout, d);
        if (!st) {
            len = nout ? wr_probe_longest_run(val, n, &start) : n;
            st = wr_spectrum_analyze(val + start, len, ds, pr->closed && !nout, NULL, res, NULL, 0, d);
        }
        wr_probe_free(&p);
    }
    free(pts);
    free(val);
    free(fld);
    return st;
}

/* One run of the driver: its options, the scene and base solve, the TFW result, and the exit code so far. */
typedef struct tfw_job {
    const char *scene_path, *out, *kappa_name, *wset_name, *start_name;
    double levels_d;
    int quiet, png, clamp_amplitude, rc;
    wr_scene sc;
    wr_scene_run run;
    wr_wf_material mat;
    wr_tfw_desc td;
    wr_tfw_result r;
    wr_status st, tst;   /* base solve, TFW */
    char base_warning[512];
    double t0;           /* TFW start */
} tfw_job;

/* Command line; returns -1 to go on, else the exit code (0 after --help). */
static int parse_args(tfw_job *j, int argc, char **argv) {
    wr_cli_opt opts[8];
    int i, n_pos = 0;
    memset(opts, 0, sizeof opts);
    opts[0].name = "--output", opts[0].alias = "-o", opts[0].kind = WR_CLI_STRING, opts[0].out = (void *)&j->out;
    opts[1].name = "--levels", opts[1].kind = WR_CLI_INTEGER, opts[1].out = &j->levels_d, opts[1].lo = 0, opts[1].hi = 5;
    opts[2].name = "--quiet", opts[2].alias = "-q", opts[2].kind = WR_CLI_FLAG, opts[2].out = &j->quiet;
    opts[3].name = "--png", opts[3].kind = WR_CLI_FLAG, opts[3].out = &j->png;
    opts[4].name = "--clamp-amplitude", opts[4].kind = WR_CLI_FLAG, opts[4].out = &j->clamp_amplitude;
    opts[5].name = "--kappa", opts[5].kind = WR_CLI_STRING, opts[5].out = (void *)&j->kappa_name;
    opts[6].name = "--wset", opts[6].kind = WR_CLI_STRING, opts[6].out = (void *)&j->wset_name;
    opts[7].name = "--start", opts[7].kind = WR_CLI_STRING, opts[7].out = (void *)&j->start_name;
    if ((i = wr_cli_parse(argc, argv, opts, 8, &j->scene_path, 1, &n_pos, usage)) <= 0) return i < 0 ? WR_CLI_EXIT_USAGE : 0;
    if (j->kappa_name && strcmp(j->kappa_name, "midedge") != 0 && strcmp(j->kappa_name, "vertex-fit") != 0) {
        wr_cli_error("--kappa: '%s' is neither midedge nor vertex-fit", j->kappa_name);
        return WR_CLI_EXIT_USAGE;
    }
    if (j->wset_name && strcmp(j->wset_name, "paper") != 0 && strcmp(j->wset_name, "release") != 0) {
        wr_cli_error("--wset: '%s' is neither paper nor release", j->wset_name);
        return WR_CLI_EXIT_USAGE;
    }
    if (j->start_name && strcmp(j->start_name, "paper") != 0 && strcmp(j->start_name, "release") != 0) {
        wr_cli_error("--start: '%s' is neither paper nor release", j->start_name);
        return WR_CLI_EXIT_USAGE;
    }
    if (!wr_cli_scene_args_ok(j->scene_path, j->out)) return WR_CLI_EXIT_USAGE;
    if (strlen(j->out) > 3000) {
        wr_cli_error("output path too long");
        return WR_CLI_EXIT_USAGE;
    }
    return -1;
}

/* Loads the scene and checks it and the output directory before any work; -1 to go on, else the exit code. */
static int load_scene(tfw_job *j) {
    static const char *const outputs[] = {"base.obj",    "wrinkled.obj", "wrinkled.ply", "wrinkled.vtk",
                                          "fields.ply",  "fields.vtk",   "wrinkles.png", "summary.json"};
    const char *inputs[2];
    wr_diag d;
    if (wr_scene_load(&j->sc, j->scene_path, &d) != WR_OK) {
        wr_cli_error("%s: %s", j->scene_path, d.message);
        return WR_CLI_EXIT_USAGE;
    }
    wr_cli_defer(free_scene, &j->sc);
    inputs[0] = j->scene_path;
    inputs[1] = j->sc.mesh.kind == WR_SCENE_MESH_OBJ ? j->sc.mesh.path : NULL;
    if (!wr_cli_dir_outputs_ok(j->out, outputs, (int)(sizeof outputs / sizeof outputs[0]), inputs, 2))
        return wr_cli_exit(WR_CLI_EXIT_USAGE);
    if (j->sc.shell.orthotropic) {
        wr_cli_error("%s: $.material: TFW needs an isotropic material (orthotropic given)", j->scene_path);
        return wr_cli_exit(WR_CLI_EXIT_USAGE);
    }
    {
        char what[WR_PATH_MAX + 32];
        snprintf(what, sizeof what, "%s: $.material.thickness", j->scene_path);
        wr_plausible_thickness(what, j->sc.shell.thickness);
    }
    return -1;
}

/* The TFT base (TFW Sec. 4.1 model, whatever the scene asked for); -1 to go on, else the exit code.
 * An unconverged base is said after the TFW step, unless that step refuses the base. */
static int solve_base(tfw_job *j) {
    wr_diag d;
    j->sc.shell.membrane = WR_MEMBRANE_TFT;
    j->sc.shell.bending = WR_BENDING_QUADRATIC;
    j->st = wr_scene_run_create(&j->run, &j->sc, &d);
    if (j->st != WR_OK) {
        wr_cli_error("%s: %s", j->scene_path, d.message);
        return wr_cli_exit(j->st == WR_ERR_NOMEM ? WR_CLI_EXIT_FAILURE : WR_CLI_EXIT_USAGE);
    }
    wr_cli_defer(free_run, &j->run);
    if (!j->quiet)
        fprintf(stderr, "%s: %d vertices, %d faces, %d prescribed, %d load step(s)\n", j->sc.name, (int)j->run.mesh.nv,
                (int)j->run.mesh.nf, (int)j->run.n_fixed, (int)j->sc.load_steps);
    j->st = wr_scene_run_solve(&j->run, j->quiet ? NULL : base_progress, NULL, &d);
    wr_cli_progress_end();
    if (j->st != WR_OK && j->st != WR_ERR_NOT_CONVERGED) {
        wr_cli_error("base solve failed: %s", d.message);
        return wr_cli_exit(WR_CLI_EXIT_FAILURE);
    }
    if (j->st == WR_ERR_NOT_CONVERGED) {
        snprintf(j->base_warning, sizeof j->base_warning, "%s", d.message);
        j->rc = 1;
    }
    wr_plausible_strain("the base", wr_meshout_max_strain(&j->run.mesh, j->run.x));
    return -1;
}

/* tfw.h on the base, and what it says of the outcome (even with --quiet); -1 to go on, else the exit code. */
static int run_tfw(tfw_job *j) {
    wr_diag d;
    j->mat.young = j->sc.shell.young;
    j->mat.poisson = j->sc.shell.poisson;
    j->mat.thickness = j->sc.shell.thickness;
    memset(&j->td, 0, sizeof j->td);
    j->td.upsample.levels = (int32_t)j->levels_d;
    if (j->clamp_amplitude) j->td.a_zero_vertices = j->run.fixed;
    if (j->kappa_name && strcmp(j->kappa_name, "vertex-fit") == 0) j->td.kappa = WR_WF_KAPPA_VERTEX_FIT;
    if (j->wset_name && strcmp(j->wset_name, "release") == 0) j->td.classify.rule = WR_WF_WSET_RELEASE;
    if (j->start_name && strcmp(j->start_name, "release") == 0) j->td.init.rule = WR_WF_INIT_RELEASE;
    if (j->td.upsample.levels == 0) j->td.no_upsample = 1;
    if (!j->quiet) j->td.solve.progress = sqp_progress;
    j->t0 = wr_time_seconds();
    wr_cli_defer(free_tfw, &j->r);
    j->tst = wr_tfw_fields(&j->run.mesh, j->run.x, &j->mat, &j->td, &j->r, &d);
    wr_cli_progress_end();
    if (j->tst != WR_OK && j->tst != WR_ERR_NOT_CONVERGED) {
        /* a slack base is the scene's set-up, not a failure of the solver (tfw.h ON OUTCOMES) */
        int slack = j->tst == WR_ERR_DOMAIN && j->r.outcome == WR_TFW_SLACK;
        if (!slack && j->base_warning[0]) wr_cli_warn("base: %s", j->base_warning);
        wr_cli_error("%s: %s", slack ? j->scene_path : "wrinkle field failed", d.message);
        return wr_cli_exit(slack ? WR_CLI_EXIT_USAGE : WR_CLI_EXIT_FAILURE);
    }
    if (j->base_warning[0]) wr_cli_warn("base: %s", j->base_warning);
    if (j->r.outcome != WR_TFW_WRINKLED)
        fprintf(stderr, "%s: note: %s (%d of %d faces compressed, %d in W)\n", wr_cli_program(),
                wr_tfw_outcome_reason(j->r.outcome), (int)j->r.n_compressed, (int)j->run.mesh.nf,
                (int)j->r.n_wrinkle_free);
    else if (j->r.n_slack > 0)
        fprintf(stderr, "%s: warning: %d faces outside W are compressed in both directions; their amplitude is not "
                        "bounded by tension (tfw.h ON OUTCOMES)\n",
                wr_cli_program(), (int)j->r.n_slack);
    if (j->tst == WR_ERR_NOT_CONVERGED) {
        wr_cli_warn("%s", d.message);
        j->rc = 1;
    }
    return -1;
}

/* summary.json: the outcome, the base solve, the SQP and the timings; returns the (empty) probes array. */
static cJSON *summary_fields(const tfw_job *j, cJSON *root) {
    const wr_tfw_result *r = &j->r;
    const wr_scene_run *run = &j->run;
    cJSON *base = cJSON_AddObjectToObject(root, "base"), *sqp = cJSON_AddObjectToObject(root, "sqp"),
          *tm = cJSON_AddObjectToObject(root, "timings_s"), *probes = cJSON_AddArrayToObject(root, "probes");
    double amax = 0.0;
    int32_t v;
    for (v = 0; v < run->mesh.nv; ++v) amax = fmax(amax, r->a[v]);
    cJSON_AddStringToObject(root, "scene", j->sc.name);
    cJSON_AddNumberToObject(root, "base_vertices", run->mesh.nv);
    cJSON_AddNumberToObject(root, "base_faces", run->mesh.nf);
    cJSON_AddNumberToObject(root, "wrinkled_vertices", j->td.no_upsample ? 0 : r->wrinkled.nv);
    cJSON_AddNumberToObject(root, "wrinkle_free_faces", r->n_wrinkle_free);
    cJSON_AddNumberToObject(root, "max_amplitude_m", amax);
    cJSON_AddStringToObject(root, "outcome", r->outcome == WR_TFW_WRINKLED ? "wrinkled" : "nothing_wrinkles");
    cJSON_AddStringToObject(root, "outcome_reason", wr_tfw_outcome_reason(r->outcome));
    cJSON_AddNumberToObject(root, "compressed_faces", r->n_compressed);
    cJSON_AddNumberToObject(root, "slack_faces", r->n_slack);
    cJSON_AddStringToObject(base, "status", wr_status_string(j->st));
    cJSON_AddNumberToObject(base, "newton_iterations", run->newton_iterations);
    cJSON_AddNumberToObject(base, "load_steps", run->n_steps_done);
    if (run->n_steps_done > 0) {
        const wr_statics_stats *ls = &run->steps[run->n_steps_done - 1].st;
        cJSON_AddNumberToObject(base, "relative_gradient", ls->grad_ref > 0 ? ls->grad_norm / ls->grad_ref : 0.0);
        if (run->sc->pressure != 0.0) cJSON_AddNumberToObject(base, "enclosed_volume_m3", ls->volume);
    }
    if (run->sc->pressure != 0.0) cJSON_AddNumberToObject(base, "pressure_Pa", run->sc->pressure);
    wr_scene_run_contact_json(run, base); /* obstacles, min_obstacle_distance_m, contact_vertices */
    cJSON_AddStringToObject(sqp, "status", wr_status_string(j->tst));
    cJSON_AddNumberToObject(sqp, "iterations", r->sqp.iterations);
    cJSON_AddNumberToObject(sqp, "rejected", r->sqp.n_rejected);
    cJSON_AddNumberToObject(sqp, "factorizations", r->sqp.n_factorizations);
    cJSON_AddNumberToObject(sqp, "escapes", r->sqp.n_escapes);
    cJSON_AddNumberToObject(sqp, "stop_rule", (double)r->sqp.stop);
    cJSON_AddNumberToObject(sqp, "kkt0", r->sqp.kkt0);
    cJSON_AddNumberToObject(sqp, "kkt", r->sqp.kkt);
    cJSON_AddNumberToObject(sqp, "energy0_J", r->sqp.energy0);
    cJSON_AddNumberToObject(sqp, "energy_J", r->sqp.energy);
    cJSON_AddNumberToObject(sqp, "unknowns", r->sqp.n_vars);
    cJSON_AddNumberToObject(tm, "tft_base", run->t_solve);
    cJSON_AddNumberToObject(tm, "tfw_total", wr_time_seconds() - j->t0);
    cJSON_AddNumberToObject(tm, "sqp", r->seconds_sqp);
    cJSON_AddNumberToObject(tm, "sqp_assembly", r->sqp.seconds_assembly);
    cJSON_AddNumberToObject(tm, "sqp_linear", r->sqp.seconds_solve);
    cJSON_AddNumberToObject(tm, "init", r->seconds_init);
    cJSON_AddNumberToObject(tm, "phase", r->seconds_phase);
    cJSON_AddNumberToObject(tm, "upsample", r->seconds_upsample);
    return probes;
}

/* summary.json's probes: each scene probe on the wrinkled surface, as the displacement from the smooth
 * subdivided base (a = 0). */
static void summary_probes(const tfw_job *j, cJSON *probes) {
    wr_wf wf;
    wr_mesh sm;
    wr_diag d;
    double *zero = (double *)calloc((size_t)j->run.mesh.nv, sizeof(double)), *smooth = NULL;
    int i;
    memset(&sm, 0, sizeof sm);
    if (zero && wr_wf_create(&wf, &j->run.mesh, j->run.x, &j->mat, &d) == WR_OK) {
        wr_wf_set_wrinkle_free(&wf, j->r.wfree);
        if (wr_wf_upsample(&wf, zero, j->r.phi, &j->td.upsample, &sm, NULL, &d) == WR_OK && sm.nv == j->r.wrinkled.nv)
            smooth = sm.pos;
        wr_wf_free(&wf);
    }
    for (i = 0; i < j->sc.n_probes && smooth; ++i) {
        const wr_scene_probe *sp = &j->sc.probe[i];
        wr_spectrum_result pr;
        cJSON *o = cJSON_CreateObject();
        cJSON_AddStringToObject(o, "name", sp->name);
        if (probe_wrinkled(&j->run, i, &j->r.wrinkled, smooth, &pr, &d) == WR_OK) {
            cJSON_AddNumberToObject(o, "count", pr.count);
            cJSON_AddNumberToObject(o, "count_rounded", pr.count_rounded);
            cJSON_AddNumberToObject(o, "zero_crossing_waves", pr.zc_waves);
            cJSON_AddNumberToObject(o, "wavelength_m", pr.wavelength);
            cJSON_AddNumberToObject(o, "amplitude_m", pr.amplitude_p2p);
            if (!j->quiet) {
                char b1[32], b2[32], b3[32];
                fprintf(stderr, "  probe %s: %s wrinkles, wavelength %s mm, amplitude %s mm\n", sp->name,
                        wr_cli_num(b1, sizeof b1, "%.2f", pr.count), wr_cli_num(b2, sizeof b2, "%.3f", 1e3 * pr.wavelength),
                        wr_cli_num(b3, sizeof b3, "%.3f", 1e3 * pr.amplitude_p2p));
            }
        } else {
            cJSON_AddStringToObject(o, "error", d.message);
        }
        cJSON_AddItemToArray(probes, o);
    }
    wr_mesh_free(&sm);
    free(zero);
}

/* The meshes and fields (meshout.h), then summary.json; -1 to go on (a failed summary.json sets the exit
 * code), else the exit code. */
static int write_outputs(tfw_job *j) {
    char path[4096];
    cJSON *root, *probes;
    wr_diag d;
    mkdir(j->out, 0777); /* may exist; real failures show up when the files are opened */
    if (wr_meshout_tfw(j->out, &j->run.mesh, j->run.x, &j->mat, &j->td, &j->r, &j->run.groups, j->png, &d) != WR_OK) {
        wr_cli_error("writing %s: %s", j->out, d.message);
        return wr_cli_exit(WR_CLI_EXIT_FAILURE);
    }
    root = cJSON_CreateObject();
    probes = summary_fields(j, root);
    if (!j->td.no_upsample && j->sc.n_probes > 0) summary_probes(j, probes);
    snprintf(path, sizeof path, "%s/summary.json", j->out);
    if (wr_json_write(root, path, &d) != WR_OK) {
        wr_cli_error("writing %s: %s", path, d.message);
        j->rc = WR_CLI_EXIT_FAILURE;
    }
    cJSON_Delete(root);
    return -1;
}

int main(int argc, char **argv) {
    static tfw_job j; /* static: zeroed, and its deferred cleanups outlive main's frame */
    int e;
    j.levels_d = 2.0;
    wr_cli_set_program(argv[0]);
    if ((e = parse_args(&j, argc, argv)) >= 0) return e;
    if ((e = load_scene(&j)) >= 0) return e;
    if ((e = solve_base(&j)) >= 0) return e;
    if ((e = run_tfw(&j)) >= 0) return e;
    if ((e = write_outputs(&j)) >= 0) return e;
    if (!j.quiet) {
        fprintf(stderr, "  TFT %.2f s (%d Newton steps); TFW %.2f s: SQP %d iterations %.2f s, KKT %.2e of %.2e\n",
                j.run.t_solve, (int)j.run.newton_iterations, wr_time_seconds() - j.t0, (int)j.r.sqp.iterations,
                j.r.seconds_sqp, j.r.sqp.kkt, j.r.sqp.kkt0);
        fprintf(stderr, "  outputs in %s/ (base.obj, wrinkled.obj/.ply/.vtk, fields.ply/.vtk%s, summary.json)\n", j.out,
                j.png ? ", wrinkles.png" : "");
    }
    return wr_cli_exit(j.rc);
}
