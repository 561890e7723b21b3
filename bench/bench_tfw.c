/* bench_tfw: TFW timings per validation case against the paper's Table 2 (8-core i9-9900K):
 * stretched sheet (522 vertices; paper TFT 10 it 0.45 s + TFW 23 it 3.93 s), sheared rectangle
 * (990; paper 1k, 21 it 2.27 s + 147 it 27.52 s), twisted cylinder (696; paper 688, 12 it 0.69 s +
 * 813 it 104.92 s), teabag (962 sewn; paper 936, 8 it 0.78 s + 46 it 7.32 s).
 *
 * TFT base (statics.h, TFW Sec. 4.1): Newton iterations, seconds, and their split into assembly
 * (+ per-element projection), linear solves and line search, plus line-search energy evaluations.
 * The base is solved in ONE load increment: TFT + quadratic bending is convex (TFW Sec. 6.5 "an
 * entirely convex problem"), so its minimiser does not depend on the path and load stepping only
 * multiplies the Newton solves (measured here: stretched sheet 28 Newton steps in 4 increments
 * against 9 in 1; twisted cylinder 33 against 14, same equilibrium to 1e-9 m). The teabag adds the
 * pressure work −pV (not convex) and is solved at full pressure from the lifted pillow, as in
 * validate_tfw_inflatables.
 * Element Hessians are assembled exactly (statics projection WR_PROJECT_NONE): the TFT membrane and
 * quadratic-bending blocks are PSD already (convex energy), so the per-element projection changes
 * nothing there (same Newton iterates measured on the sheet and the cylinder); with pressure it
 * discards each face's indefinite −p∇²V part, which turns Newton linear near the inflated
 * equilibrium (teabag: |∇Π| halves per step, 24 Newton steps) while the exact Hessian is SPD there
 * (11 steps, quadratic); far from it the statics' global shift raise keeps each step a descent one.
 * TFW: SQP iterations, SQP seconds, and the whole TFW time split like the paper's Fig. 23: SQP
 * assembly (gradient + Hessian), SQP linear solves (the paper's QP-solver share), the rest of the
 * SQP (energy evaluations in the step control, bookkeeping) and everything outside the SQP (setup,
 * W, initialisation, phase, Loop upsampling to level 2).
 * Medians of RUNS runs per case, except the sheared-rectangle base (Newton needs ~300 steps there,
 * 296–358 measured, 2.3 s CPU; timed once unless --full, marked in the runs column).
 * TFT base speed (statics.h ON ASSEMBLY CACHE, and OMP_THREAD_LIMIT below), CPU seconds, same box
 * under load ~3, before → after: stretched sheet 0.079 → 0.030 (9 Newton steps both), sheared
 * rectangle 6.31 (313 steps) → 2.30 (358), twisted cylinder 0.260 → 0.080 (14), teabag 0.342 → 0.137
 * (11); assembly per sheet solve 0.033 → 0.013 s. What is left is CHOLMOD's supernodal numeric
 * factorisation (perf, cylinder base: OpenBLAS 45 %, CHOLMOD 20 % of which its internal
 * cholmod_l_transpose_sym 10 %, the shell's element Hessians ~5 %); simplicial CHOLMOD was 2.5–5×
 * slower on all three (sheet 0.028 → 0.072 s, cylinder 0.092 → 0.447 s, teabag 0.136 → 0.708 s),
 * so the supernodal default stays. The sheared base's step count is path-sensitive: round-off-level
 * changes (assembly order, -O2/-O3) give 296–358 steps and bases up to 3.6e-5 m apart (Π equal to
 * 1.4e-10 J of 0.245 J), see statics.h ON SHIFT.
 * --shift-raise=R sets statics desc.shift.raise = R for the TFT bases (μ ×R after backtracked
 * steps, statics.h ON SHIFT; off by default). Measured on the sheared-rectangle base (one
 * increment, default grad_tol): R = 10 313 → 175 Newton steps (CPU 11.4–13.8 → 6.3–6.7 s), R = 100 → 126
 * (3.3–4.7 s); sheet, cylinder and teabag never backtrack, same iterates. Not the default because the
 * base it returns is not the same to 1e-6 m: max vertex distance 1.4e-4 m (R = 10) and 1.5e-4 m
 * (R = 100), with Π higher by 4e-10 J of 0.245 J, and the TFW SQP after it took 73 iterations
 * instead of 55. The minimiser is that poorly determined along the bending-held directions: the
 * default path stops at ‖∇Π‖ = 3.5e-8 of the reference (a round-off or step stop, at grad_tol 1e-8
 * and 1e-11 alike), while R = 10 with grad_tol 1e-9 or 1e-11 stops 3.4e-5 m away after 299 steps, so
 * the gain is mostly an earlier gradient stop in a flat valley, not a faster approach to the same
 * point. --peer also times the SQP with the per-face-projected Hessian throughout (WR_WF_HESSIAN_PROJECTED, the paper's method) as an in-run
 * peer. Prints the machine and the load average (the box is shared: timings are noisy).
 * BLAS/OpenMP threads: unless OPENBLAS_NUM_THREADS, OMP_NUM_THREADS and OMP_WAIT_POLICY are all
 * set, the bench sets them to 1, 1, PASSIVE and re-executes itself (the libraries read them when
 * they are loaded, before main). On this 2-core shared box CHOLMOD's threaded BLAS spent ~75 % of
 * the teabag base solve in sched_yield (perf), 2.3–4.1 s against 0.7–1.2 s single-threaded for the
 * same 11 Newton steps (load ~8); the factorisations here (≤ 3k DOFs) are too small for threads
 * to pay. CHOLMOD's supernodal numeric factorisation still opens OpenMP teams of its own fixed size
 * (3 extra threads seen in perf whatever OMP_NUM_THREADS says), whose idle threads spin unless the
 * wait policy is passive: twisted-cylinder base, 14 Newton steps, user CPU 0.60–0.65 s (ACTIVE),
 * 0.23 s (default), 0.18–0.19 s (PASSIVE). Those teams are opened by num_threads clauses inside CHOLMOD,
 * which OMP_NUM_THREADS does not cap but OMP_THREAD_LIMIT does: with OMP_THREAD_LIMIT=1 the kernel's
 * futex / task-switch share (~20 % of a base solve in perf) disappears and the base linear time
 * halved (sheet 0.055 → 0.031 s, cylinder 0.223 → 0.120 s, teabag 0.297 → 0.165 s, same iterates),
 * so the bench sets it to 1 too.
 * --base-only times the TFT bases alone (no TFW fields; for profiling the statics solve). */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "wrinkle/wrinkle.h"
#include "wrinkle/tfw.h"

#define RUNS 5
#define PI_ 3.14159265358979323846

static int cmp_d(const void *a, const void *b) {
    double x = *(const double *)a, y = *(const double *)b;
    return x < y ? -1 : x > y;
}
static double median(const double *v0, int n) {
    double v[RUNS];
    memcpy(v, v0, sizeof(double) * (size_t)n);
    qsort(v, (size_t)n, sizeof(double), cmp_d);
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}
/* index of the run whose value is the (upper) median, so the parts of that run add up */
static int median_index(const double *v, int n) {
    double m = median(v, n), best = HUGE_VAL;
    int k, km = 0;
    for (k = 0; k < n; ++k)
        if (fabs(v[k] - m) < best) best = fabs(v[k] - m), km = k;
    return km;
}

/* CPU seconds of this process (all threads; the BLAS is single-threaded here): on a shared box the
 * wall clock also counts the time other jobs hold the cores, the CPU time does not. */
static double cpu_seconds(void) {
    struct timespec ts;
    if (clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts) != 0) return NAN;
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static void machine(void) {
    FILE *f = fopen("/proc/cpuinfo", "r");
    char line[256], model[256] = "unknown";
    int ncpu = 0;
    if (f) {
        while (fgets(line, sizeof line, f)) {
            if (!strncmp(line, "model name", 10) && ncpu++ == 0) {
                char *c = strchr(line, ':');
                if (c) snprintf(model, sizeof model, "%s", c + 2);
                model[strcspn(model, "\n")] = 0;
            }
        }
        fclose(f);
    }
    printf("machine: %s, %d logical CPUs (single-threaded code)\n", model, ncpu);
}
static void loadavg(const char *when) {
    FILE *f = fopen("/proc/loadavg", "r");
    char line[128] = "?";
    if (f) {
        if (!fgets(line, sizeof line, f)) strcpy(line, "?");
        fclose(f);
    }
    line[strcspn(line, "\n")] = 0;
    printf("load average %s: %s\n", when, line);
}

typedef struct bcase {
    const char *name;
    int kind; /* 0 sheet, 1 shear, 2 cylinder, 3 teabag */
    double paper_tft, paper_tfw;
    int paper_tft_it, paper_iters, paper_nv;
} bcase;

typedef struct base_timing {
    double total, cpu, assembly, linear, line_search;
    int iters, ls_evals;
    wr_status status;
} base_timing;

/* Builds the case's mesh and solves the TFT base; x gets the base positions. 0 on failure. */
/* statics desc.shift_raise of the TFT base solves (statics.h ON SHIFT): 0 = off, --shift-raise=R */
static double g_shift_raise = 0.0;

static int solve_base(int kind, wr_mesh *m, double **xout, base_timing *bt, wr_wf_material *mat) {
    wr_diag d;
    wr_shell sh;
    wr_shell_desc sd;
    wr_statics_desc st;
    wr_statics_stats ss;
    wr_motion mo[2];
    int32_t *s0 = NULL, *s1 = NULL, n0 = 0, n1 = 0, v;
    double *x, t0, c0;
    wr_status s;
    memset(m, 0, sizeof *m);
    memset(&st, 0, sizeof st);
    memset(&ss, 0, sizeof ss);
    if (kind == 0) {
        if (wr_mesh_rectangle(m, 0.25, 0.1, 28, 17, &d)) return 0;
        mat->young = 1e6, mat->poisson = 0.5, mat->thickness = 1e-4;
    } else if (kind == 1) {
        if (wr_mesh_rectangle(m, 0.38, 0.128, 54, 17, &d)) return 0;
        mat->young = 3530e6, mat->poisson = 0.3, mat->thickness = 25e-6;
    } else if (kind == 2) {
        if (wr_mesh_cylinder_flat(m, 1.0, 5.0, 29, 23, &d)) return 0;
        mat->young = 10e6, mat->poisson = 0.44, mat->thickness = 1e-4;
    } else {
        /* teabag as in validate_tfw_inflatables: two 1.4 × 0.74 m panels (30 × 16) sewn, tent 0.1 m, 10 Pa */
        wr_mesh panel;
        memset(&panel, 0, sizeof panel);
        if (wr_mesh_rectangle(&panel, 1.4, 0.74, 30, 16, &d)) return 0;
        s = wr_mesh_pillow(m, &panel, 0.1, &d);
        wr_mesh_free(&panel);
        if (s) return 0;
        mat->young = 1e5, mat->poisson = 0.3, mat->thickness = 1e-3;
    }
    wr_tfw_base_shell_desc(mat->young, mat->poisson, mat->thickness, 0.0, &sd);
    if (wr_shell_create(&sh, m, &sd, &d)) return 0;
    st.hessian.projection = WR_PROJECT_NONE; /* exact Hessians, see the top comment */
    st.shift.raise = g_shift_raise;  /* off unless --shift-raise=R, see the top comment */
    x = (double *)malloc(sizeof(double) * 3 * m->nv);
    memcpy(x, m->pos, sizeof(double) * 3 * m->nv);
    if (kind == 3) {
        st.loads.pressure = 10.0;
        st.stop.max_iter = 300;
        c0 = cpu_seconds();
        t0 = wr_time_seconds();
        s = wr_statics_solve(&sh, x, &st, &ss, &d);
        bt->total = wr_time_seconds() - t0;
        bt->cpu = cpu_seconds() - c0;
    } else {
        s0 = (int32_t *)malloc(sizeof(int32_t) * m->nv);
        s1 = (int32_t *)malloc(sizeof(int32_t) * m->nv);
        for (v = 0; v < m->nv; ++v) {
            double c = kind == 0 ? m->pos[3 * v] : kind == 1 ? m->pos[3 * v + 1] : m->pos[3 * v + 2];
            double hi = kind == 0 ? 0.25 : kind == 1 ? 0.128 : 5.0;
            if (c < 1e-9) s0[n0++] = v;
            if (c > hi - 1e-9) s1[n1++] = v;
        }
        memset(mo, 0, sizeof mo);
        mo[0].kind = WR_MOTION_HOLD;
        mo[0].verts = s0;
        mo[0].n_verts = n0;
        mo[1].verts = s1;
        mo[1].n_verts = n1;
        if (kind == 0) {
            mo[1].kind = WR_MOTION_STRETCH;
            mo[1].axis[0] = 1.0;
            mo[1].amount = 0.1278;
        } else if (kind == 1) {
            mo[1].kind = WR_MOTION_TRANSLATE;
            mo[1].vec[0] = 0.003;
        } else {
            mo[1].kind = WR_MOTION_TWIST;
            mo[1].axis[2] = 1.0;
            mo[1].amount = 10.0 * PI_ / 180.0;
        }
        /* one increment: the TFT + quadratic-bending problem is convex (see the top comment) */
        st.stop.max_iter = 1000;
        c0 = cpu_seconds();
        t0 = wr_time_seconds();
        s = wr_statics_solve_incremental(&sh, x, &st, mo, 2, 1, &ss, &d);
        bt->total = wr_time_seconds() - t0;
        bt->cpu = cpu_seconds() - c0;
    }
    bt->assembly = ss.t_assembly + ss.t_projection;
    bt->linear = ss.t_linear;
    bt->line_search = ss.t_line_search;
    bt->iters = ss.iterations;
    bt->ls_evals = ss.line_search_evals;
    bt->status = s;
    wr_shell_free(&sh);
    free(s0);
    free(s1);
    *xout = x;
    return s == WR_OK || s == WR_ERR_NOT_CONVERGED;
}

int main(int argc, char **argv) {
    static const bcase cases[4] = {{"stretched sheet", 0, 0.45, 3.93, 10, 23, 522},
                                   {"sheared rectangle", 1, 2.27, 27.52, 21, 147, 1000},
                                   {"twisted cylinder", 2, 0.69, 104.92, 12, 813, 688},
                                   {"teabag", 3, 0.78, 7.32, 8, 46, 936}};
    int full = 0, peer = 0, only = -1, base_only = 0, c, r, a;
    if (!getenv("OPENBLAS_NUM_THREADS") || !getenv("OMP_NUM_THREADS") || !getenv("OMP_WAIT_POLICY") ||
        !getenv("OMP_THREAD_LIMIT")) {
        /* single-threaded BLAS / OpenMP, passive waits (see the top comment); on failure run as we are */
        if (!getenv("OPENBLAS_NUM_THREADS")) setenv("OPENBLAS_NUM_THREADS", "1", 1);
        if (!getenv("OMP_NUM_THREADS")) setenv("OMP_NUM_THREADS", "1", 1);
        if (!getenv("OMP_WAIT_POLICY")) setenv("OMP_WAIT_POLICY", "PASSIVE", 1);
        if (!getenv("OMP_THREAD_LIMIT")) setenv("OMP_THREAD_LIMIT", "1", 1);
        execv("/proc/self/exe", argv);
    }
    for (a = 1; a < argc; ++a) {
        if (!strcmp(argv[a], "--full")) full = 1;
        else if (!strcmp(argv[a], "--peer")) peer = 1;
        else if (!strcmp(argv[a], "--base-only")) base_only = 1;
        else if (!strncmp(argv[a], "--shift-raise=", 14)) g_shift_raise = atof(argv[a] + 14);
        else if (!strncmp(argv[a], "--case=", 7)) only = atoi(argv[a] + 7);
    }
    machine();
    printf("OPENBLAS_NUM_THREADS=%s OMP_NUM_THREADS=%s OMP_WAIT_POLICY=%s OMP_THREAD_LIMIT=%s\n",
           getenv("OPENBLAS_NUM_THREADS"), getenv("OMP_NUM_THREADS"), getenv("OMP_WAIT_POLICY"), getenv("OMP_THREAD_LIMIT"));
    loadavg("at start");
    printf("TFW per case, medians over the runs column (base runs / TFW runs); paper = Table 2, 8-core i9-9900K\n");
    printf("TFT base: Newton it, seconds, split asm(+proj)/linear/line-search, line-search energy evals, status\n");
    printf("%-18s %5s %5s | %4s %4s %8s %7s %7s %7s %7s %4s %-5s | %4s %4s %8s %7s | %7s %7s %7s %7s | %7s %7s %7s\n",
           "case", "nv", "runs", "it", "ppr", "TFT [s]", "paper", "asm", "linear", "ls", "lsev", "stat", "it", "ppr",
           "TFW [s]", "paper", "sqp-asm", "sqp-lin", "sqp-rst", "other", "TFT x", "TFW x", "total x");
    for (c = 0; c < 4; ++c) {
        wr_mesh m;
        wr_wf_material mat;
        base_timing bt[RUNS];
        double tb[RUNS], tt[RUNS], cb[RUNS], ct[RUNS], ta[RUNS], tl[RUNS], ts[RUNS], tp[RUNS], *x = NULL;
        int nb = (cases[c].kind == 1 && !full) ? 1 : RUNS, iters = 0, kb, kt;
        if (only >= 0 && c != only) continue;
        for (r = 0; r < nb; ++r) {
            if (r > 0) {
                free(x);
                wr_mesh_free(&m);
            }
            if (!solve_base(cases[c].kind, &m, &x, &bt[r], &mat)) {
                printf("%s: base failed (%s)\n", cases[c].name, wr_status_string(bt[r].status));
                return 1;
            }
            tb[r] = bt[r].total;
            cb[r] = bt[r].cpu;
        }
        if (base_only) {
            /* --base-only: the TFT base alone (profiling the statics solve), no TFW fields */
            const base_timing *b = &bt[median_index(cb, nb)];
            printf("%-18s %5d %2d    | %4d %4d %8.3f %7.2f %7.3f %7.3f %7.3f %4d %-5s | CPU %.3f s (median), %.1fx paper\n",
                   cases[c].name, (int)m.nv, nb, b->iters, cases[c].paper_tft_it, median(tb, nb), cases[c].paper_tft,
                   b->assembly, b->linear, b->line_search, b->ls_evals, b->status == WR_OK ? "ok" : "NOCONV",
                   median(cb, nb), cases[c].paper_tft / median(cb, nb));
            fflush(stdout);
            free(x);
            wr_mesh_free(&m);
            continue;
        }
        for (r = 0; r < RUNS; ++r) {
            wr_tfw_desc td;
            wr_tfw_result res;
            wr_diag d;
            double c0;
            memset(&td, 0, sizeof td);
            td.upsample.levels = 2;
            c0 = cpu_seconds();
            wr_tfw_fields(&m, x, &mat, &td, &res, &d);
            ct[r] = cpu_seconds() - c0;
            tt[r] = res.seconds_total;
            ta[r] = res.sqp.seconds_assembly;
            tl[r] = res.sqp.seconds_solve;
            ts[r] = res.seconds_sqp - res.sqp.seconds_assembly - res.sqp.seconds_solve;
            iters = res.sqp.iterations;
            wr_tfw_result_free(&res);
            tp[r] = NAN;
            if (peer) {
                td.solve.hessian = WR_WF_HESSIAN_PROJECTED;
                td.no_upsample = 1;
                wr_tfw_fields(&m, x, &mat, &td, &res, &d);
                tp[r] = res.seconds_sqp;
                wr_tfw_result_free(&res);
            }
        }
        {
            double mtb = median(tb, nb), mtt = median(tt, RUNS);
            const base_timing *b;
            kb = median_index(tb, nb);
            kt = median_index(tt, RUNS);
            b = &bt[kb];
            printf("%-18s %5d %2d/%-2d | %4d %4d %8.3f %7.2f %7.3f %7.3f %7.3f %4d %-5s | %4d %4d %8.3f %7.2f | %7.3f %7.3f "
                   "%7.3f %7.3f | %6.1fx %6.1fx %6.1fx\n",
                   cases[c].name, (int)m.nv, nb, RUNS, b->iters, cases[c].paper_tft_it, mtb, cases[c].paper_tft,
                   b->assembly, b->linear, b->line_search, b->ls_evals, b->status == WR_OK ? "ok" : "NOCONV", iters,
                   cases[c].paper_iters, mtt, cases[c].paper_tfw, ta[kt], tl[kt], ts[kt], tt[kt] - ta[kt] - tl[kt] - ts[kt],
                   cases[c].paper_tft / mtb, cases[c].paper_tfw / mtt,
                   (cases[c].paper_tft + cases[c].paper_tfw) / (mtb + mtt));
            if (tt[kt] > 0.0)
                printf("%-18s   Fig. 23 split of the median TFW run: SQP assembly %.0f%%, SQP linear solves %.0f%%, SQP rest "
                       "%.0f%%, outside the SQP %.0f%% (paper, all cases: gradient + Hessian 24.3%%, QP solver 54.8%%, line "
                       "search 11.9%%, misc. 9.1%%)\n",
                       "", 100.0 * ta[kt] / tt[kt], 100.0 * tl[kt] / tt[kt], 100.0 * ts[kt] / tt[kt],
                       100.0 * (tt[kt] - ta[kt] - tl[kt] - ts[kt]) / tt[kt]);
            printf("%-18s   CPU seconds (medians): TFT %.3f, TFW %.3f -> x paper: TFT %.1fx, TFW %.1fx, total %.1fx\n", "",
                   median(cb, nb), median(ct, RUNS), cases[c].paper_tft / median(cb, nb),
                   cases[c].paper_tfw / median(ct, RUNS),
                   (cases[c].paper_tft + cases[c].paper_tfw) / (median(cb, nb) + median(ct, RUNS)));
            if (peer)
                printf("%-18s   peer: SQP with the projected Hessian throughout %.3f s (median), %.2fx the default SQP\n", "",
                       median(tp, RUNS), median(tp, RUNS) / (ta[kt] + tl[kt] + ts[kt]));
            fflush(stdout);
        }
        free(x);
        wr_mesh_free(&m);
    }
    loadavg("at end");
    printf("x = paper wall seconds / ours (TFT, TFW, TFT + TFW), wall clock on the table line, process CPU time on the "
           "CPU line (steadier on a shared box); goal >= 10x. it/ppr = our / paper iterations. "
           "sqp-asm/sqp-lin/sqp-rst/other = parts of the median TFW run (Fig. 23 split).\n");
    return 0;
}
