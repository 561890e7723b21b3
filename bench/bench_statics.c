/* bench_statics — Newton time per iteration vs vertex count on the Style3D Fig. 16 stretch test
 * (examples/scenes/stretch.json: 0.25 m × 0.1 m, StVK + mid-edge bending, 12.78 % stretch), with each
 * linear solver of pcg.h (PCG block-Jacobi 3×3, IC(0), smoothed-aggregation AMG) against CHOLMOD in
 * the same run. Time per Newton iteration split into assembly / projection / linear solve / line search
 * (TFW Fig. 23 style), from wr_statics_stats.
 *
 * Protocol: one load step (the whole stretch), affine warm start, projected Newton (per-element PSD
 * projection, statics.h WR_PROJECT_FAST) called directly (the scene gives mesh, material and
 * prescribed sets), exactly NEWTON_ITERS Newton iterations (max_iter; the solve
 * then stops with WR_ERR_NOT_CONVERGED, which is expected here: we time iterations, not a converged
 * solve — a full wrinkled solve takes hundreds of iterations and minutes at 4e3 vertices), linear
 * relative tolerance 1e-8 for every method; the "+EW" rows instead use statics.h's inexact Newton
 * forcing (linear_forcing 0.1: PCG relative tolerance min(0.1, max(1e-8, sqrt(|g|/ref))) per step),
 * so compare their final |g|/ref too. Median of RUNS runs per (size, method) while a run takes
 * < SLOW seconds, else one run (printed as n=1). Sizes: regular grids of about 1e3, 3e3, 1e4, 3e4, 1e5
 * vertices, stopping at max_vertices (argv[1], default 100000), skipping sizes below min_vertices
 * (argv[2], default 0). The final relative gradient is
 * printed so that the methods' iterations can be compared (an inexact PCG step may reduce less).
 * PCG runs on one thread; CHOLMOD's BLAS may use both cores (OPENBLAS_NUM_THREADS=1 keeps it on one:
 * on a shared, loaded machine its spinning threads cost more than they give).
 * Reduced protocol (issue 5 "Benchmarks"): the full stretch (12.78 %) in one load step and only
 * NEWTON_ITERS Newton iterations per run, so that 1e5 vertices is affordable; the quantity compared
 * is the time per Newton iteration, not a converged solve.
 * Output: a markdown table (wall and process-CPU time per iteration; the split into assembly /
 * projection / linear solve / line search is wall time from wr_statics_stats, TFW Fig. 23 style),
 * then per size the best PCG variant against CHOLMOD. CPU time is the more robust figure when the
 * machine is shared (wall time then includes waiting for a core).
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
#define RUNS 5
#define SLOW 30.0 /* s per run above which one run only */

/* CHOLMOD last; the "+EW" rows use statics.h's inexact Newton forcing (linear_forcing = FORCING) */
static const wr_solver_method methods[] = {WR_SOLVER_PCG_BLOCK3, WR_SOLVER_PCG_IC0, WR_SOLVER_PCG_AMG,
                                           WR_SOLVER_PCG_IC0,    WR_SOLVER_PCG_AMG, WR_SOLVER_CHOLMOD};
static const double mforcing[] = {0.0, 0.0, 0.0, 0.1, 0.1, 0.0};
static const char *const mnames[] = {"pcg-block3", "pcg-ic0", "pcg-amg", "pcg-ic0+EW", "pcg-amg+EW", "cholmod"};
#define NM 6
/* block-Jacobi PCG is left out above this size (measured 12.7x CHOLMOD per iteration at 1e5 vertices,
 * 190 s per Newton iteration: one run would take 10 minutes) */
#define BLOCK3_MAX_VERTICES 30000

static int cmp_double(const void *a, const void *b) {
    double x = *(const double *)a, y = *(const double *)b;
    return x < y ? -1 : x > y;
}

typedef struct sample {
    double it, cpu, asm_, proj, lin, ls, grad;
    int32_t nv, iters, lin_iters;
} sample;

static double cpu_seconds(void) {
    struct rusage ru;
    if (getrusage(RUSAGE_SELF, &ru) != 0) return NAN;
    return (double)ru.ru_utime.tv_sec + 1e-6 * (double)ru.ru_utime.tv_usec + (double)ru.ru_stime.tv_sec +
           1e-6 * (double)ru.ru_stime.tv_usec;
}

static int one_run(const wr_scene *base, double r, int mi, sample *s) {
    wr_scene sc = *base;
    wr_scene_run run;
    wr_diag d;
    int32_t k, v;
    double c0, *target;
    wr_statics_desc sd;
    wr_statics_stats st;
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
    sd.fixed = run.fixed;
    sd.target = target;
    sd.max_iter = NEWTON_ITERS;
    sd.grad_tol = 1e-8;
    sd.perturb = 1e-5;
    sd.seed = sc.seed;
    sd.projection = WR_PROJECT_FAST;
    sd.linear.method = m;
    sd.linear.rel_tol = 1e-8;
    sd.linear_forcing = mforcing[mi];
    c0 = cpu_seconds();
    {
        wr_status rs = wr_statics_solve(&run.shell, run.x, &sd, &st, &d);
        if (rs != WR_OK && rs != WR_ERR_NOT_CONVERGED) {
            fprintf(stderr, "bench_statics: %s: %s\n", mnames[mi], d.message);
            free(target);
            wr_scene_run_free(&run);
            return -1;
        }
    }
    k = st.iterations > 0 ? st.iterations : 1;
    s->nv = run.mesh.nv;
    s->iters = st.iterations;
    s->lin_iters = st.linear_iterations;
    s->it = st.t_total / k;
    s->cpu = (cpu_seconds() - c0) / k;
    s->asm_ = st.t_assembly / k;
    s->proj = st.t_projection / k;
    s->lin = st.t_linear / k;
    s->ls = st.t_line_search / k;
    s->grad = st.grad_ref > 0 ? st.grad_norm / st.grad_ref : NAN;
    free(target);
    wr_scene_run_free(&run);
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
    int i, m, k;
    if (wr_scene_load(&sc, SCENE_PATH, &d) != WR_OK) {
        fprintf(stderr, "bench_statics: %s (run from the repository root)\n", d.message);
        return 1;
    }
    printf("Newton time per iteration [ms] on the stretch test (0.25 x 0.1 m, h 0.1 mm, nu 0.5, E 1 MPa, 12.78 %% "
           "stretch in one load step), %d projected-Newton iterations per run, median of up to %d runs "
           "(n = runs; 1 when a run exceeds %.0f s)\n\n",
           NEWTON_ITERS, RUNS, SLOW);
    printf("| vertices | method | n | wall/it | cpu/it | assembly | projection | linear | line search | PCG it/Newton it | "
           "final abs(g)/ref | wall vs CHOLMOD |\n|---|---|---|---|---|---|---|---|---|---|---|---|\n");
    for (i = 0; i < NR; ++i) {
        double per_it[NM], cpu_it[NM], expect = 0.025 / (res[i] * res[i]);
        sample first[NM];
        if (expect > 1.3 * (double)max_v) break;
        if (expect < (double)min_v / 1.3) continue;
        for (m = 0; m < NM; ++m) {
            sample s[RUNS];
            double a[RUNS], b[RUNS], c[RUNS], e[RUNS], f[RUNS], cp[RUNS];
            int n = 0;
            if (methods[m] == WR_SOLVER_PCG_BLOCK3 && expect > BLOCK3_MAX_VERTICES) {
                per_it[m] = cpu_it[m] = INFINITY;
                first[m].grad = NAN;
                first[m].nv = 0;
                printf("| ~%.0f | %s | 0 | skipped (BLOCK3_MAX_VERTICES) | | | | | | | | |\n", expect, mnames[m]);
                continue;
            }
            for (k = 0; k < RUNS; ++k) {
                if (one_run(&sc, res[i], m, &s[k]) != 0) return 1;
                ++n;
                if (s[k].it * NEWTON_ITERS > SLOW) break;
            }
            for (k = 0; k < n; ++k)
                a[k] = s[k].it, b[k] = s[k].asm_, c[k] = s[k].proj, e[k] = s[k].lin, f[k] = s[k].ls, cp[k] = s[k].cpu;
            per_it[m] = med(a, n);
            cpu_it[m] = med(cp, n);
            first[m] = s[0];
            printf("| %d | %s | %d | %.1f | %.1f | %.1f | %.1f | %.1f | %.1f | %.1f | %.2e | %s |\n", (int)s[0].nv,
                   mnames[m], n, 1e3 * per_it[m], 1e3 * cpu_it[m], 1e3 * med(b, n), 1e3 * med(c, n), 1e3 * med(e, n),
                   1e3 * med(f, n), (double)s[0].lin_iters / (s[0].iters > 0 ? s[0].iters : 1), s[0].grad,
                   m == NM - 1 ? "1" : "(below)");
            fflush(stdout);
        }
        {
            /* the best PCG variant by CPU time per Newton iteration (robust on a shared machine), against CHOLMOD */
            int best = 0;
            for (m = 1; m < NM - 1; ++m)
                if (cpu_it[m] < cpu_it[best]) best = m;
            printf("| %d | best PCG = %s / CHOLMOD | | %.2fx (wall) | %.2fx (cpu) | | | | | | %.2e vs %.2e | %s |\n",
                   (int)first[NM - 1].nv, mnames[best], per_it[best] / per_it[NM - 1], cpu_it[best] / cpu_it[NM - 1],
                   first[best].grad, first[NM - 1].grad, cpu_it[best] <= cpu_it[NM - 1] ? "PCG faster (cpu)" : "CHOLMOD faster (cpu)");
            for (m = 0; m < NM - 1; ++m)
                if (first[m].nv > 0)
                    fprintf(stderr, "  %d vertices: %-10s wall/it vs CHOLMOD %.2fx, cpu/it %.2fx\n", (int)first[m].nv,
                        mnames[m], per_it[m] / per_it[NM - 1], cpu_it[m] / cpu_it[NM - 1]);
        }
        fflush(stdout);
    }
    if (i < NR) printf("stopped before %.0f vertices (max_vertices = %ld)\n", 0.025 / (res[i] * res[i]), max_v);
    wr_scene_free(&sc);
    return 0;
}
