/* validate_tfw_crosscheck — issue 6 item 6: our StVK reference (statics.h, StVK membrane + mid-edge
 * bending — the model both papers compare against) on the TFW stretched sheet and twisted cylinder at
 * increasing resolution, counted with spectrum.h exactly as the TFW drivers count, beside TFW's counts
 * on the coarse base (read from validation/results/tfw_stretched_sheet.json and
 * tfw_twisted_cylinder.json, written by those drivers).
 *   Stretched sheet: 0.25 × 0.1 m, h = 0.1 mm, ν = 0.5, E = 1 MPa, 12.78 % in 4 increments, seeded
 *   1 µm normal kick; count = FFT count of z on the 512-sample cross-width probe at mid-length.
 *   Twisted cylinder: r = 1 m, 5 m, h = 0.1 mm, ν = 0.44, E = 10 MPa, top ring twisted 10° in 4
 *   increments, seeded kick; count = integer FFT harmonic of the radial coordinate of the mid-height
 *   vertex ring (periodic; nu samples, so at most nu/2 waves are resolvable).
 * Resolutions (sheet 40×16, 56×23, 84×34; cylinder 40×32, 56×44, 84×66) run in a fixed order
 * (see main) until the time budget (WALL_BUDGET seconds of this driver) is spent; a resolution that would
 * start after the budget is skipped and reported as such (on the loaded 2-core box the 40×32
 * cylinder alone took 733 Newton steps, 215 s wall; a 24×19 one stopped unconverged after 543). The paper needed 260k+ (sheet)
 * and 96k+ (cylinder) StVK vertices (Table 1); this box cannot get there in minutes, so the question
 * "at what vertex count does the full simulation agree" is answered with the largest count reached.
 * No pass bands (issue 6 sets none for item 6); base solve status is checked. The cylinder solves use
 * statics.h's exact_retry (why: see the notes written to the result file).
 * Output: validation/results/tfw_crosscheck.json, figures/tfw_crosscheck.png. */
#include <cjson/cJSON.h>

#include "tfw_probe.h"
#include "vargs.h"

#define WALL_BUDGET 200.0
#define NPROBE 512
#define NS 3
#define NC 3

typedef struct res {
    int32_t nx, ny, nv, iters, fails;
    double t, count, count_ls, amp, zc;
    wr_status st, sp;
    int ran;
} res;

static double json_quantity(const char *file, const char *name, char *generated, size_t gen_cap) {
    char path[700];
    FILE *fp;
    long n;
    char *txt;
    double out = NAN;
    cJSON *root, *q, *it;
    snprintf(path, sizeof path, "%s/%s", wr_vres_dir(), file);
    fp = fopen(path, "rb");
    if (!fp) return NAN;
    fseek(fp, 0, SEEK_END);
    n = ftell(fp);
    fseek(fp, 0, SEEK_SET);
    txt = (char *)malloc((size_t)n + 1);
    if (!txt || fread(txt, 1, (size_t)n, fp) != (size_t)n) {
        fclose(fp);
        free(txt);
        return NAN;
    }
    fclose(fp);
    txt[n] = 0;
    root = cJSON_Parse(txt);
    free(txt);
    if (!root) return NAN;
    q = cJSON_GetObjectItem(root, "generated");
    if (cJSON_IsString(q)) snprintf(generated, gen_cap, "%s", q->valuestring);
    q = cJSON_GetObjectItem(root, "quantities");
    cJSON_ArrayForEach(it, q) {
        cJSON *nm = cJSON_GetObjectItem(it, "name"), *ours = cJSON_GetObjectItem(it, "ours");
        if (cJSON_IsString(nm) && strcmp(nm->valuestring, name) == 0 && cJSON_IsNumber(ours)) out = ours->valuedouble;
    }
    cJSON_Delete(root);
    return out;
}

static void sheet(res *o) {
    wr_diag d;
    wr_mesh m;
    wr_shell sh;
    wr_shell_desc sd;
    wr_statics_desc st;
    wr_statics_stats ss;
    tp_clamps cl;
    int32_t v;
    double *x, *fz, pts[2 * NPROBE], zv[NPROBE], A[2] = {0.125, 0.0}, B[2] = {0.125, 0.1}, ds, t0 = wr_time_seconds();
    wr_spectrum_result sr;
    o->ran = 1;
    o->count = o->count_ls = o->amp = o->zc = NAN;
    if ((o->st = wr_mesh_rectangle(&m, 0.25, 0.1, o->nx, o->ny, &d))) return;
    o->nv = m.nv;
    memset(&sd, 0, sizeof sd);
    sd.membrane = WR_MEMBRANE_STVK;
    sd.bending = WR_BENDING_MIDEDGE;
    sd.young = 1e6;
    sd.poisson = 0.5;
    sd.thickness = 1e-4;
    if ((o->st = wr_shell_create(&sh, &m, &sd, &d))) {
        wr_mesh_free(&m);
        return;
    }
    x = (double *)malloc(sizeof(double) * 3 * m.nv);
    fz = (double *)malloc(sizeof(double) * m.nv);
    if (!x || !fz || (o->st = tp_clamps_select(&cl, &m, 0, 0.0, 0.25, &d)) != WR_OK) {
        if (!x || !fz) o->st = WR_ERR_NOMEM;
        free(x);
        free(fz);
        wr_shell_free(&sh);
        wr_mesh_free(&m);
        return;
    }
    cl.mo[1].kind = WR_MOTION_STRETCH;
    cl.mo[1].axis[0] = 1.0;
    cl.mo[1].amount = 0.1278;
    memset(&st, 0, sizeof st);
    st.start.perturb = 1e-6;
    st.start.seed = 3;
    st.stop.max_iter = 300;
    o->st = tp_clamped_solve(&sh, &m, &cl, &st, 4, x, &ss, &d);
    o->iters = ss.total_iterations;
    o->fails = ss.increments_failed + (o->st != WR_OK);
    o->t = wr_time_seconds() - t0;
    fprintf(stderr, "  sheet StVK %d v: %s, %d Newton, %.1f s\n", (int)m.nv, wr_status_string(o->st), (int)o->iters, o->t);
    {
        for (v = 0; v < m.nv; ++v) fz[v] = x[3 * v + 2];
        o->sp = tp_line_field(&m, fz, A, B, NPROBE, pts, &ds, zv, &sr, &d);
        if (!o->sp) {
            o->count = sr.count;
            o->count_ls = sr.count_ls;
            o->amp = sr.amplitude_p2p;
            o->zc = sr.zc_waves;
        }
    }
    tp_clamps_free(&cl);
    free(x);
    free(fz);
    wr_shell_free(&sh);
    wr_mesh_free(&m);
}

static void cylinder(res *o) {
    wr_diag d;
    wr_mesh m;
    wr_shell sh;
    wr_shell_desc sd;
    wr_statics_desc st;
    wr_statics_stats ss;
    tp_clamps cl;
    wr_spectrum_result sr;
    int32_t v, i, j;
    double *x, *sig, t0 = wr_time_seconds();
    o->ran = 1;
    o->count = o->count_ls = o->amp = o->zc = NAN;
    if ((o->st = wr_mesh_cylinder_flat(&m, 1.0, 5.0, o->nx, o->ny, &d))) return;
    o->nv = m.nv;
    memset(&sd, 0, sizeof sd);
    sd.membrane = WR_MEMBRANE_STVK;
    sd.bending = WR_BENDING_MIDEDGE;
    sd.young = 10e6;
    sd.poisson = 0.44;
    sd.thickness = 1e-4;
    if ((o->st = wr_shell_create(&sh, &m, &sd, &d))) {
        wr_mesh_free(&m);
        return;
    }
    x = (double *)malloc(sizeof(double) * 3 * m.nv);
    sig = (double *)malloc(sizeof(double) * o->nx);
    if (!x || !sig || (o->st = tp_clamps_select(&cl, &m, 2, 0.0, 5.0, &d)) != WR_OK) {
        if (!x || !sig) o->st = WR_ERR_NOMEM;
        free(x);
        free(sig);
        wr_shell_free(&sh);
        wr_mesh_free(&m);
        return;
    }
    cl.mo[1].kind = WR_MOTION_TWIST;
    cl.mo[1].axis[2] = 1.0;
    cl.mo[1].amount = 10.0 * TP_PI / 180.0;
    memset(&st, 0, sizeof st);
    st.start.perturb = 1e-5;
    st.start.seed = 5;
    st.stop.max_iter = 300;
    /* statics.h ON PROJECTION, exact_retry: the exact Hessian is tried again after the gradient has
     * fallen 10x below its first (indefinite) attempt. Without it the 56x44 cylinder crawled on a
     * nearly flat mode with projected Newton and 3 of its 4 increments stopped at max_iter (see the
     * notes); same minimiser, same tolerances, only the Newton matrix near the end differs. */
    st.hessian.exact_retry = 0.1;
    o->st = tp_clamped_solve(&sh, &m, &cl, &st, 4, x, &ss, &d);
    o->iters = ss.total_iterations;
    o->fails = ss.increments_failed + (o->st != WR_OK);
    o->t = wr_time_seconds() - t0;
    fprintf(stderr, "  cylinder StVK %d v: %s, %d Newton, %.1f s\n", (int)m.nv, wr_status_string(o->st), (int)o->iters, o->t);
    j = o->ny / 2;
    for (i = 0; i < o->nx; ++i) {
        v = j * o->nx + i;
        sig[i] = hypot(x[3 * v], x[3 * v + 1]);
    }
    o->sp = tp_analyze_closed(sig, o->nx, 2.0 * TP_PI, 1, &sr, &d);
    if (!o->sp) {
        o->count = sr.count_rounded;
        o->amp = sr.amplitude_p2p;
        o->zc = sr.zc_waves;
    }
    tp_clamps_free(&cl);
    free(x);
    free(sig);
    wr_shell_free(&sh);
    wr_mesh_free(&m);
}

static int validation_main(void) {
    static const int32_t snx[NS] = {40, 56, 84}, sny[NS] = {16, 23, 34};
    static const int32_t cnu[NC] = {40, 56, 84}, cnh[NC] = {32, 44, 66};
    /* job order (sheet s0 s2, cylinder c0 = TFW's 1.3k grid, then sheet s1, cylinder c1 c2; the
     * 56x23 sheet took 401 Newton steps against 110 at 84x34): the budget is checked before each
     * job starts */
    static const int job_case[NS + NC] = {0, 0, 1, 0, 1, 1}, job_idx[NS + NC] = {0, 2, 0, 1, 1, 2};
    res rs[NS], rc[NC];
    double t_all = wr_time_seconds(), tfw_sheet, tfw_cyl;
    char buf[2048], table[4096], gen_s[64] = "missing", gen_c[64] = "missing";
    size_t off = 0;
    wr_vres *v;
    int i;
    memset(rs, 0, sizeof rs);
    memset(rc, 0, sizeof rc);
    for (i = 0; i < NS; ++i) rs[i].nx = snx[i], rs[i].ny = sny[i];
    for (i = 0; i < NC; ++i) rc[i].nx = cnu[i], rc[i].ny = cnh[i];
    tfw_sheet = json_quantity("tfw_stretched_sheet.json", "wave periods across the width (FFT count on the probe)", gen_s, sizeof gen_s);
    /* the 40 x 32 square-cell tube is the same 1320-vertex mesh family as the StVK cylinders below */
    tfw_cyl = json_quantity("tfw_twisted_cylinder.json", "waves, square-cell (ours) tube 40 x 32 (1320 vertices), our modelling choice", gen_c,
                            sizeof gen_c);
    for (i = 0; i < NS + NC; ++i) {
        if (wr_time_seconds() - t_all >= WALL_BUDGET) break;
        if (job_case[i] == 0)
            sheet(&rs[job_idx[i]]);
        else
            cylinder(&rc[job_idx[i]]);
    }
    v = wr_vres_begin("tfw_crosscheck", "TFW vs our StVK reference at increasing resolution (stretched sheet, twisted cylinder)");
    wr_vres_info(v, "TFW stretched sheet count, 522-vertex base (from tfw_stretched_sheet.json)", "periods", 5.0, tfw_sheet);
    wr_vres_info(v, "TFW twisted cylinder count, 1320-vertex base (from tfw_twisted_cylinder.json)", "waves", 46.0, tfw_cyl);
    off += (size_t)snprintf(table + off, sizeof table - off,
                            "| case | grid | vertices | StVK status | Newton steps | time [s] | count (FFT) | zero-crossing waves | amplitude [mm] | TFW coarse count |\n|---|---|---|---|---|---|---|---|---|---|\n");
    for (i = 0; i < NS + NC; ++i) {
        res *o = i < NS ? &rs[i] : &rc[i - NS];
        const char *nm = i < NS ? "stretched sheet" : "twisted cylinder";
        if (!o->ran) {
            snprintf(buf, sizeof buf, "%s StVK at grid %dx%d skipped: time budget %.0f s spent", nm, (int)o->nx, (int)o->ny, WALL_BUDGET);
            wr_vres_note(v, buf);
            continue;
        }
        snprintf(buf, sizeof buf, "%s StVK %d vertices: base solve converged", nm, (int)o->nv);
        wr_vres_check(v, buf, "failed increments", NAN, o->fails, "0", o->fails == 0);
        snprintf(buf, sizeof buf, "%s StVK %d vertices: count", nm, (int)o->nv);
        wr_vres_info(v, buf, i < NS ? "periods" : "waves", i < NS ? 5.0 : 46.0, o->count);
        snprintf(buf, sizeof buf, "%s StVK %d vertices: amplitude (max-min)/2", nm, (int)o->nv);
        wr_vres_info(v, buf, "mm", NAN, 1e3 * o->amp);
        off += (size_t)snprintf(table + off, sizeof table - off, "| %s | %dx%d | %d | %s | %d | %.1f | %.2f | %.1f | %.3f | %.2f |\n", nm,
                                (int)o->nx, (int)o->ny, (int)o->nv, wr_status_string(o->st), (int)o->iters, o->t, o->count, o->zc,
                                1e3 * o->amp, i < NS ? tfw_sheet : tfw_cyl);
    }
    wr_vres_table_md(v, table);
    snprintf(buf, sizeof buf, "TFW counts read from tfw_stretched_sheet.json (generated %s) and tfw_twisted_cylinder.json (generated %s); "
             "run_all.sh runs this driver before those two, so on a fresh tree run it again after them.", gen_s, gen_c);
    wr_vres_note(v, buf);
    wr_vres_note(v, "Cylinder StVK count uses the mid-height vertex ring (nu samples): it cannot exceed nu/2, so grids with nu <= 84 "
                    "cannot show TFW's ~49 waves unless nu/2 >= 49.");
    wr_vres_note(v, "Cylinder StVK solves use statics.h desc.exact_retry = 0.1 (the exact Hessian is tried again once the gradient has "
                    "fallen 10x below a failed exact attempt; default tolerances grad_tol 1e-8, max_iter 300 per increment unchanged). "
                    "Why (measured with per-step Newton logs, 56x44, 2520 vertices, without it): increment 1 stopped at max_iter 300 "
                    "with |grad| = 6.1e-8 of the reference (target 1e-8); from step ~150 every step was a full (alpha = 1) projected "
                    "Newton step of ~5e-6 m, Pi falling a steady ~5e-11 J per step while |grad| stayed at 6-10e-6 N: a slow slide "
                    "along a nearly flat mode (the wave pattern rearranging), which the per-element PSD projection makes far stiffer "
                    "than it is. The exact Hessian had been tried once, at step 73 (|grad| = 1e-3 of the reference, still indefinite), "
                    "and never again. Not a fold: largest dihedral angle at the stall 34 deg, no edge above 90 deg (the sphere-drape "
                    "mid-edge fold does not occur here). 40x32 converged without the retry only just (increment 1: 201 steps, "
                    "|grad| = 9.97e-9 of the reference, linear rate ~0.95 per step). With the retry (same seed and increments): "
                    "56x44 increments 1-4 WR_OK in 261 / 153 / 254 / 253 Newton steps (921 in all, 245 s on the loaded box); "
                    "the exact Hessian was still indefinite at some retries (e.g. increment 1 at |grad| 6.5e-8 of the reference), "
                    "where projected steps carried the state over the flat stretch. 40x32 with the retry: 695 Newton steps (1042 without). "
                    "Alternatives measured on 56x44 without the retry: 8 twist increments: increment 3 NOT_CONVERGED after 300 steps "
                    "(|grad| 1.4e-5 of the reference); shift_raise = 10: no effect (it acts only on backtracked steps and the crawl "
                    "takes full ones; increment 1 identical, 300 steps, 6.1e-8); start interpolated (cylindrical coordinates, "
                    "bilinear on the pattern grid) from the converged 40x32 solution, full 10 deg in one solve: NOT_CONVERGED after "
                    "300 steps at 1.9e-8; the same start with the retry: WR_OK in 123 steps (31 s) but at a different, lower "
                    "equilibrium (Pi 0.58566 J against 0.59223 J on the 4-increment path; mid-height radius 0.777-0.961 m against "
                    "0.789-0.939 m): the coarse StVK cylinder has several wrinkled equilibria and the loading path selects one, so "
                    "the driver keeps the same 4-increment path at every resolution. The exact Hessian throughout (projection NONE) "
                    "was far slower (Pi 0.186 J after 160 steps of increment 1 against 0.028 J projected).");
    wr_vres_note(v, "Paper Table 1: StVK needed 260k+ vertices (stretched sheet) and 96k+ (twisted cylinder) to resolve the wrinkles.");
    snprintf(buf, sizeof buf, "Total driver time %.1f s (budget %.0f s before starting a new resolution), shared 2-core box.",
             wr_time_seconds() - t_all, WALL_BUDGET);
    wr_vres_note(v, buf);
    {
        wr_afile f;
        wr_diag d;
        char dat[700];
        memset(&d, 0, sizeof d);
        snprintf(dat, sizeof dat, "%s/tfw_crosscheck.dat", wr_vres_dir());
        if (wr_afile_open(&f, dat, &d) == WR_OK) {
            for (i = 0; i < NS; ++i)
                if (rs[i].ran) fprintf(f.fp, "%d %.6g %.6g\n", (int)rs[i].nv, rs[i].count, tfw_sheet);
            fprintf(f.fp, "\n\n");
            for (i = 0; i < NC; ++i)
                if (rc[i].ran) fprintf(f.fp, "%d %.6g %.6g\n", (int)rc[i].nv, rc[i].count, tfw_cyl);
            if (wr_afile_commit(&f, &d) == WR_OK) {
                snprintf(buf, sizeof buf,
                         "set multiplot layout 1,2\nset logscale x\nset xrange [300:20000]\nset xlabel 'StVK vertices'\nset key bottom right\n"
                         "set title 'stretched sheet'\nset ylabel 'periods across the width'\nset yrange [0:12]\n"
                         "plot '%s' index 0 u 1:2 w lp pt 7 t 'StVK', %.4g w l t 'TFW, 522-vertex base', 5 w l dt 2 t 'paper 5'\n"
                         "set title 'twisted cylinder'\nset ylabel 'waves at mid-height'\nset yrange [0:60]\n"
                         "plot '%s' index 1 u 1:2 w lp pt 7 t 'StVK', %.4g w l t 'TFW, 1320-vertex base', 46 w l dt 2 t 'paper 46'\n"
                         "unset multiplot\n", dat, isfinite(tfw_sheet) ? tfw_sheet : 0.0, dat, isfinite(tfw_cyl) ? tfw_cyl : 0.0);
                tp_figure(v, "tfw_crosscheck", buf, "StVK counts vs resolution beside TFW's coarse-base counts");
            }
        }
    }
    return wr_vres_finish(v) < 0 ? 1 : 0;
}

int main(int argc, char **argv) {
    int rc = wr_vargs(argc, argv, "validate_tfw_crosscheck",
                      "TFW against the kit's StVK reference at increasing resolution (reads other cases' results).",
                      "tfw_crosscheck", NULL, NULL, NULL);
    return rc >= 0 ? rc : validation_main();
}
