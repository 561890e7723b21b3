/* bench_statics — Newton solve time vs vertex count on the Style3D Fig. 16 stretch test
 * (examples/scenes/stretch.json: 0.25 m × 0.1 m, StVK + mid-edge bending, 12.78 % stretch), with each
 * linear solver of pcg.h (PCG block-Jacobi 3×3, IC(0), smoothed-aggregation AMG, and IC(0)/AMG with
 * inexact-Newton forcing) against CHOLMOD in the same run, compared by the TIME TO THE SAME RESIDUAL
 * (issue 5 "Benchmarks"), with the time split into assembly / projection / linear solve / line search
 * (TFW Fig. 23 style) from wr_statics_stats.
 *
 * Protocol: one load step (the whole stretch), affine warm start, projected Newton (per-element PSD
 * projection, statics.h WR_PROJECT_FAST) called directly (the scene gives mesh, material and
 * prescribed sets). CHOLMOD runs first, exactly NEWTON_ITERS Newton iterations (a full wrinkled solve
 * takes hundreds of iterations; the reduced protocol keeps 1e5 vertices affordable); its final
 * relative gradient g_C = |g|/ref is the target. Every PCG variant then runs Newton with grad_tol =
 * g_C (1 + TARGET_SLACK) and up to MAX_ITER_FACTOR × NEWTON_ITERS iterations, and the time it takes
 * to get there is compared with CHOLMOD's time for its NEWTON_ITERS iterations: an inexact linear
 * solve (the "+EW" rows: statics.h linear.forcing η_max, PCG relative tolerance
 * min(η_max, max(1e-8, sqrt(|g|/ref))) per step) is cheaper per iteration but may need more Newton
 * iterations, and this protocol charges it for them. The other rows solve every Newton system to
 * relative residual 1e-8. TARGET_SLACK (1 %) only absorbs round-off: with linear solves to 1e-8 the
 * PCG iterates equal CHOLMOD's to ~1e-8, and without the slack a final |g| larger by 1e-9 relative
 * would cost a whole extra Newton iteration. A variant that does not reach the target is reported
 * as "no" and takes no part in the comparison.
 * Median of RUNS runs per (size, method) while a run takes < SLOW seconds, else one run (n = 1).
 * Sizes: regular grids of about 1e3, 3e3, 1e4, 3e4, 1e5 vertices, stopping at max_vertices (argv[1],
 * default 100000), skipping sizes below min_vertices (argv[2], default 0); argv[3] caps the runs;
 * argv[4], a comma-separated list of method names (e.g. pcg-ic0,pcg-ic0+EW0.1), limits the PCG rows
 * (CHOLMOD always runs: it sets the target).
 * Times: wall clock of the Newton solve (st.t_total) and process CPU time (getrusage; CPU time is the
 * steadier figure on a shared machine, where wall time includes waiting for a core). PCG runs on
 * one thread; CHOLMOD's BLAS may use both cores unless OPENBLAS_NUM_THREADS=1 (printed at the start):
 * its CPU time then exceeds its wall time.
 */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>

#include "scene.h"

#define SCENE_PATH "examples/scenes/stretch.json"
#define NEWTON_ITERS 3
#define MAX_ITER_FACTOR 4   /* PCG variants get up to 4x CHOLMOD's Newton iterations to reach its |g| */
#define TARGET_SLACK 1e-2   /* relative: round-off allowance on CHOLMOD's final |g| (see protocol) */
#define RUNS 5
#define SLOW 30.0 /* s per run above which one run only */

/* CHOLMOD first (it sets the target); the "+EW" rows use statics.h's inexact Newton forcing
 * (linear.forcing = mforcing) */
static const wr_solver_method methods[] = {WR_SOLVER_CHOLMOD,  WR_SOLVER_PCG_BLOCK3, WR_SOLVER_PCG_IC0, WR_SOLVER_PCG_AMG,
                                           WR_SOLVER_PCG_IC0,  WR_SOLVER_PCG_IC0,    WR_SOLVER_PCG_AMG};
static const double mforcing[] = {0.0, 0.0, 0.0, 0.0, 0.1, 0.01, 0.1};
static const char *const mnames[] = {"cholmod", "pcg-block3", "pcg-ic0", "pcg-amg", "pcg-ic0+EW0.1", "pcg-ic0+EW0.01",
                                     "pcg-amg+EW0.1"};
#define NM 7
/* block-Jacobi PCG is left out above this size (measured 12.7x CHOLMOD per iteration at 1e5 vertices,
 * 190 s per Newton iteration: one run would take 10 minutes) */
#define BLOCK3_MAX_VERTICES 30000

static int cmp_double(const void *a, const void *b) {
    double x = *(const double *)a, y = *(const double *)b;
    return x < y ? -1 : x > y;
}

typedef struct sample {
    double wall, cpu, asm_, proj, lin, ls, grad;
    int32_t nv, iters, lin_iters, reached;
} sample;

static double cpu_seconds(void) {
    struct rusage ru;
    if (getrusage(RUSAGE_SELF, &ru) != 0) return NAN;
    return (double)ru.ru_utime.tv_sec + 1e-6 * (double)ru.ru_utime.tv_usec + (double)ru.ru_stime.tv_sec +
           1e-6 * (double)ru.ru_stime.tv_usec;
}

/* One Newton solve. target <= 0: exactly NEWTON_ITERS iterations (the CHOLMOD reference); else stop
 * at |g|/ref <= target, at most MAX_ITER_FACTOR * NEWTON_ITERS iterations. */
static int one_run(const wr_scene *base, double r, int mi, double target_g, sample *s) {
    wr_scene sc = *base;
    wr_scene_run run;
    wr_diag d;
    int32_t k, v;
    double c0, *target;
    wr_statics_desc sd;
    wr_statics_stats st;
    wr_status rs;
    wr_solver_method m = methods[mi];
    sc.mesh.resolution = r;
    sc.mesh.nx = sc.mesh.ny = 0;
    sc.load_steps = 1;
    sc.max_iter = NEWTON_ITERS;
    sc.hessian = WR_SCENE_HESSIAN_PROJECTED;
    sc.linear = m;
    sc.linear_tol = 1e-8;
    sc.perturb = 1e-5;
    sc.n_probes = 0;
    if (wr_scene_run_create(&run, &sc, &d) != WR_OK) {
        fprintf(stderr, "bench_statics: %s\n", d.message);
        return -1;
    }
    /* the scene's stretch in one step, solved by statics.h directly (the scene runner has no forcing
     * option): prescribed rows at X_c + S (X − X_c) of their set, free vertices warm-started by the
     * stretched set's affine map (what the scene runner's affine warm start gives for this scene) */
    target = (double *)malloc(sizeof(double) * 3 * (size_t)run.mesh.nv);
    if (!target) {
        wr_scene_run_free(&run);
        return -1;
    }
    for (v = 0; v < run.mesh.nv; ++v) {
        const wr_scene_bc *bc = &sc.bc[run.bc_of[v] >= 0 ? run.bc_of[v] : sc.n_bc - 1];
        for (k = 0; k < 3; ++k) {
            double S = bc->stretch[k] != 0.0 ? bc->stretch[k] : 1.0;
            target[3 * v + k] = bc->center[k] + S * (run.mesh.pos[3 * v + k] - bc->center[k]);
        }
        if (!run.fixed[v]) memcpy(run.x + 3 * v, target + 3 * v, sizeof(double) * 3);
    }
    memset(&sd, 0, sizeof sd);
    sd.loads.fixed = run.fixed;
    sd.loads.target = target;
    sd.stop.max_iter = target_g > 0.0 ? MAX_ITER_FACTOR * NEWTON_ITERS : NEWTON_ITERS;
    sd.stop.grad_tol = target_g > 0.0 ? target_g : 1e-8;
    sd.start.perturb = 1e-5;
    sd.start.seed = sc.seed;
    sd.hessian.projection = WR_PROJECT_FAST;
    sd.linear.solver.method = m;
    sd.linear.solver.rel_tol = 1e-8;
    sd.linear.forcing = mforcing[mi];
    c0 = cpu_seconds();
    rs = wr_statics_solve(&run.shell, run.x, &sd, &st, &d);
    s->cpu = cpu_seconds() - c0;
    if (rs != WR_OK && rs != WR_ERR_NOT_CONVERGED) {
        fprintf(stderr, "bench_statics: %s: %s\n", mnames[mi], d.message);
        free(target);
        wr_scene_run_free(&run);
        return -1;
    }
    s->nv = run.mesh.nv;
    s->iters = st.iterations;
    s->lin_iters = st.linear_iterations;
    s->wall = st.t_total;
    s->asm_ = st.t_assembly;
    s->proj = st.t_projection;
    s->lin = st.t_linear;
    s->ls = st.t_line_search;
    s->grad = st.grad_ref > 0 ? st.grad_norm / st.grad_ref : NAN;
    s->reached = target_g > 0.0 ? (rs == WR_OK && s->grad <= target_g) : 1;
    free(target);
    wr_scene_run_free(&run);
    return 0;
}

/* 1 when name is one of the comma-separated entries of list */
static int listed(const char *list, const char *name) {
    size_t len = strlen(name);
    const char *p = list;
    while (*p) {
        const char *e = strchr(p, ',');
        size_t l = e ? (size_t)(e - p) : strlen(p);
        if (l == len && strncmp(p, name, len) == 0) return 1;
        if (!e) break;
        p = e + 1;
    }
    return 0;
}

static double med(double *v, int n) {
    qsort(v, (size_t)n, sizeof *v, cmp_double);
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

int main(int argc, char **argv) {
    wr_scene sc;
    wr_diag d;
    /* resolutions for ~1e3, 3e3, 1e4, 3e4, 1e5 vertices on 0.25 × 0.1 m: nv ≈ 0.025 / r² */
    const double res[] = {5.0e-3, 2.9e-3, 1.58e-3, 0.91e-3, 0.5e-3};
    const int NR = (int)(sizeof res / sizeof res[0]);
    long max_v = argc > 1 ? atol(argv[1]) : 100000, min_v = argc > 2 ? atol(argv[2]) : 0;
    int runs = argc > 3 ? atoi(argv[3]) : RUNS;
    const char *only = argc > 4 ? argv[4] : NULL;
    int i, m, k;
    const char *blas = getenv("OPENBLAS_NUM_THREADS");
    if (runs < 1 || runs > RUNS) runs = RUNS;
    if (wr_scene_load(&sc, SCENE_PATH, &d) != WR_OK) {
        fprintf(stderr, "bench_statics: %s (run from the repository root)\n", d.message);
        return 1;
    }
    printf("Newton solve to the same residual on the stretch test (0.25 x 0.1 m, h 0.1 mm, nu 0.5, E 1 MPa, "
           "12.78 %% stretch in one load step): CHOLMOD does %d projected-Newton iterations, each PCG variant runs "
           "until its abs(g)/ref <= CHOLMOD's x (1 + %g) (at most %d iterations). Median of up to %d runs (n = runs; "
           "1 when a run exceeds %.0f s). Times are totals for the solve [s]; OPENBLAS_NUM_THREADS=%s\n\n",
           NEWTON_ITERS, TARGET_SLACK, MAX_ITER_FACTOR * NEWTON_ITERS, runs, SLOW, blas ? blas : "(unset)");
    printf("| vertices | method | n | Newton it | reached | wall [s] | cpu [s] | assembly | projection | linear | "
           "line search | PCG it/Newton it | final abs(g)/ref | wall vs CHOLMOD | cpu vs CHOLMOD |\n"
           "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n");
    for (i = 0; i < NR; ++i) {
        double wall[NM], cpu[NM], expect = 0.025 / (res[i] * res[i]), gtarget = 0.0;
        sample first[NM];
        if (expect > 1.3 * (double)max_v) break;
        if (expect < (double)min_v / 1.3) continue;
        for (m = 0; m < NM; ++m) {
            sample s[RUNS];
            double a[RUNS], b[RUNS], c[RUNS], e[RUNS], f[RUNS], cp[RUNS];
            int n = 0;
            wall[m] = cpu[m] = INFINITY;
            first[m].nv = 0;
            first[m].reached = 0;
            if (m > 0 && only && !listed(only, mnames[m])) continue;
            if (methods[m] == WR_SOLVER_PCG_BLOCK3 && expect > BLOCK3_MAX_VERTICES) {
                printf("| ~%.0f | %s | 0 | skipped (BLOCK3_MAX_VERTICES) | | | | | | | | | | | |\n", expect, mnames[m]);
                continue;
            }
            for (k = 0; k < runs; ++k) {
                if (one_run(&sc, res[i], m, m == 0 ? 0.0 : gtarget, &s[k]) != 0) return 1;
                ++n;
                if (s[k].wall > SLOW) break;
            }
            if (m == 0) gtarget = s[0].grad * (1.0 + TARGET_SLACK);
            for (k = 0; k < n; ++k)
                a[k] = s[k].wall, b[k] = s[k].asm_, c[k] = s[k].proj, e[k] = s[k].lin, f[k] = s[k].ls, cp[k] = s[k].cpu;
            first[m] = s[0];
            if (s[0].reached) {
                wall[m] = med(a, n);
                cpu[m] = med(cp, n);
            }
            printf("| %d | %s | %d | %d | %s | %.2f | %.2f | %.2f | %.2f | %.2f | %.2f | %.1f | %.2e | ", (int)s[0].nv,
                   mnames[m], n, (int)s[0].iters, s[0].reached ? "yes" : "no", med(a, n), med(cp, n), med(b, n),
                   med(c, n), med(e, n), med(f, n), (double)s[0].lin_iters / (s[0].iters > 0 ? s[0].iters : 1),
                   s[0].grad);
            if (m == 0) printf("1 | 1 |\n");
            else if (s[0].reached) printf("%.2fx | %.2fx |\n", wall[m] / wall[0], cpu[m] / cpu[0]);
            else printf("(target not reached) | |\n");
            fflush(stdout);
        }
        {
            /* the best PCG variant by CPU time to the target (robust on a shared machine), against CHOLMOD */
            int best = -1;
            for (m = 1; m < NM; ++m)
                if (first[m].reached && (best < 0 || cpu[m] < cpu[best])) best = m;
            if (best < 0)
                printf("| %d | no PCG variant reached CHOLMOD's abs(g)/ref %.2e | | | | | | | | | | | | | |\n",
                       (int)first[0].nv, first[0].grad);
            else
                printf("| %d | best PCG = %s / CHOLMOD | | %d vs %d | | %.2fx | %.2fx | | | | | | %.2e vs %.2e | %s | |\n",
                       (int)first[0].nv, mnames[best], (int)first[best].iters, (int)first[0].iters, wall[best] / wall[0],
                       cpu[best] / cpu[0], first[best].grad, first[0].grad,
                       cpu[best] <= cpu[0] ? "PCG faster (cpu)" : "CHOLMOD faster (cpu)");
        }
        fflush(stdout);
    }
    if (i < NR) printf("stopped before %.0f vertices (max_vertices = %ld)\n", 0.025 / (res[i] * res[i]), max_v);
    wr_scene_free(&sc);
    return 0;
}
