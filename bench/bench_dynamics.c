/* bench_dynamics — per-frame cost of dynamics.h (issue 13 "Performance"): numerical solving (NS:
 * assembly, PSD projection, linear solves) and collision handling (CH: detection, CCD, barrier and
 * friction terms) per 1/30 s frame against vertex count, the paper's Table 1 split.
 *
 * Cases (the sheet: StVK + mid-edge bending, Y = 1e5 Pa, ν = 0.3, 0.5 mm, 300 kg/m³, mass damping
 * 0.5/s, gravity, self-contact on, PCG block-Jacobi to 1e-5 as the paper's Sec. 5):
 *   sphere     a 0.6 m square sheet released 5 mm above an analytic sphere of radius 0.15 m (the
 *              sheet's own collision mesh is searched for self-contact every evaluation);
 *   mannequin  a 0.7 m square sheet released 5 mm above the procedural mannequin's head (body.h,
 *              20k triangles) — cloth against a triangle mesh, the broad phase over both.
 * Sizes: regular grids of about 1e3, 5e3, 2e4, 5e4, 1e5 vertices up to max_vertices (argv[1] of the
 * default mode, 100000). Per size: FRAMES frames after WARM frames of fall (contact starts within
 * the first frame), the median NS, CH and total per frame, with Newton / PCG iterations per frame.
 * Scaling exponent: least-squares slope of log(NS per frame) and log(CH per frame) against log(nv).
 *
 * Also, on the 5e3-vertex sphere sheet: NS per Newton iteration against the static solver's Newton
 * step (statics.h, the same mesh pinned at two corners under gravity, the same PCG and tolerance,
 * WR_BENCH_STATIC_ITERS steps), and the thread gain (OpenMP) when built with -fopenmp.
 *
 * Times are wall-clock (the dynamics stats) plus the process CPU seconds of the whole case
 * (getrusage): this machine is shared, and CPU seconds are the steadier figure. Run with
 * OMP_THREAD_LIMIT=1 OMP_NUM_THREADS=1 OPENBLAS_NUM_THREADS=1 for the single-thread figures.
 *
 * Usage: bench_dynamics [max_vertices]          the whole bench (a few minutes at 1e5)
 *        bench_dynamics frames CASE N FRAMES [mu] per-frame detail of one case (profiling):
 *                                               CASE sphere|mannequin, N grid cells per side
 *        BENCH_LINEAR=pcg-ic0 (any wr_solver_method_name) picks desc.linear.method (default
 *        pcg-block3); per-frame lines show the linear solves' wall time (lin, part of NS).
 *        BENCH_FORCING=0.1 sets desc.newton.forcing (η_max of the inexact-Newton PCG tolerance);
 *        BENCH_VEL_TOL=5e-3 sets desc.newton.velocity_tol [m/s];
 *        BENCH_DUMP=FILE writes the final positions (raw doubles) to FILE. */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#ifdef _OPENMP
#include <omp.h>
#endif

#ifdef WR_BENCH_IMPL /* the Makefile builds this bench as its own implementation unit, with -fopenmp */
#define WRINKLE_IMPLEMENTATION
#endif
#include "wrinkle/wrinkle.h"

#define WR_BENCH_WARM 2          /* frames of fall before timing (contact is set up within them) */
#define WR_BENCH_FRAMES 6        /* timed frames per size (medians) */
#define WR_BENCH_STATIC_ITERS 4  /* static Newton steps timed per run */

static double cpu_seconds(void) {
    struct rusage ru;
    getrusage(RUSAGE_SELF, &ru);
    return (double)ru.ru_utime.tv_sec + 1e-6 * (double)ru.ru_utime.tv_usec + (double)ru.ru_stime.tv_sec +
           1e-6 * (double)ru.ru_stime.tv_usec;
}

static int cmp_d(const void *a, const void *b) {
    double x = *(const double *)a, y = *(const double *)b;
    return x < y ? -1 : x > y;
}

static double median(const double *v, int n) {
    double t[64];
    int i;
    for (i = 0; i < n; ++i) t[i] = v[i];
    qsort(t, (size_t)n, sizeof(double), cmp_d);
    return n % 2 ? t[n / 2] : 0.5 * (t[n / 2 - 1] + t[n / 2]);
}

typedef struct bench_case {
    wr_mesh m, body;
    wr_shell s;
    wr_obstacle ball, floor, obst[2];
    wr_dyn_body db;
    wr_dyn_desc dd;
    double *x, *v;
    int have_body;
} bench_case;

static int case_make(bench_case *c, const char *kind, int32_t n, double mu) {
    wr_shell_desc sd;
    wr_diag dg;
    int32_t i;
    int mann = !strcmp(kind, "mannequin"), ball = !strcmp(kind, "ball");
    double side = mann ? 0.7 : (ball ? 0.5 : 0.6), top;
    memset(c, 0, sizeof *c);
    if (wr_mesh_rectangle(&c->m, side, side, n, n, &dg) != WR_OK) return fprintf(stderr, "%s\n", dg.message), 1;
    memset(&sd, 0, sizeof sd);
    sd.young = 1e5;
    sd.poisson = 0.3;
    sd.thickness = 5e-4;
    sd.density = 300.0;
    if (wr_shell_create(&c->s, &c->m, &sd, &dg) != WR_OK) return fprintf(stderr, "%s\n", dg.message), 1;
    memset(&c->dd, 0, sizeof c->dd);
    c->dd.gravity[2] = -9.81;
    c->dd.damping.mass = 0.5;
    c->dd.contact.friction = mu;
    if (mann) {
        wr_body_desc bd;
        memset(&bd, 0, sizeof bd);
        if (wr_body_mannequin(&c->body, &bd, &dg) != WR_OK) return fprintf(stderr, "%s\n", dg.message), 1;
        c->have_body = 1;
        top = -HUGE_VAL;
        for (i = 0; i < c->body.nv; ++i) top = fmax(top, c->body.pos[3 * i + 2]);
        memset(&c->db, 0, sizeof c->db);
        c->db.nv = c->body.nv;
        c->db.nf = c->body.nf;
        c->db.faces = c->body.faces;
        c->db.pos = c->body.pos;
        c->dd.contact.bodies = &c->db;
        c->dd.contact.n_bodies = 1;
    } else if (ball) { /* examples/sim/drape_ball.json: 0.1 m ball, floor at -0.2 m, 3 cm drop */
        c->ball.kind = WR_OBSTACLE_SPHERE;
        c->ball.radius = 0.1;
        top = 0.125;
        c->floor.kind = WR_OBSTACLE_PLANE;
        c->floor.p[2] = -0.2;
        c->floor.normal[2] = 1.0;
        c->obst[0] = c->ball;
        c->obst[1] = c->floor;
        c->dd.contact.analytic = c->obst;
        c->dd.contact.n_analytic = 2;
    } else {
        c->ball.kind = WR_OBSTACLE_SPHERE;
        c->ball.radius = 0.15;
        top = 0.15;
        c->dd.contact.analytic = &c->ball;
        c->dd.contact.n_analytic = 1;
    }
    c->x = (double *)malloc(sizeof(double) * 3 * (size_t)c->m.nv);
    c->v = (double *)calloc(3 * (size_t)c->m.nv, sizeof(double));
    if (!c->x || !c->v) return fprintf(stderr, "out of memory\n"), 1;
    for (i = 0; i < c->m.nv; ++i) {
        c->x[3 * i] = c->m.pos[3 * i] - 0.5 * side;
        c->x[3 * i + 1] = c->m.pos[3 * i + 1] - 0.5 * side;
        c->x[3 * i + 2] = top + 5e-3;
    }
    return 0;
}

static void case_free(bench_case *c) {
    wr_shell_free(&c->s);
    wr_mesh_free(&c->m);
    if (c->have_body) wr_mesh_free(&c->body);
    free(c->x);
    free(c->v);
}

typedef struct frame_fig {
    double ns, ch, tot, cpu, newton, pcg, ns_per_newton;
    int32_t nv, ok;
    uint64_t hash; /* FNV-1a of the final positions' bytes: bit-identical runs give the same */
} frame_fig;

static uint64_t fnv(const double *x, size_t n) {
    const unsigned char *p = (const unsigned char *)x;
    uint64_t h = 1469598103934665603ULL;
    size_t i;
    for (i = 0; i < n * sizeof(double); ++i) h = (h ^ p[i]) * 1099511628211ULL;
    return h;
}

/* WARM frames, then `frames` timed ones: medians into *out; verbose prints every frame */
static int case_run(const char *kind, int32_t n, double mu, int frames, int verbose, frame_fig *out) {
    bench_case c;
    wr_dyn sim;
    wr_dyn_state st;
    wr_dyn_stats fs;
    wr_diag dg;
    double ns[64], ch[64], tot[64], it[64], pcg[64], npi[64], c0 = 0.0;
    int f, k = 0, rc = 0;
    memset(out, 0, sizeof *out);
    if (case_make(&c, kind, n, mu)) return 1;
    if (getenv("BENCH_NO_HALVING")) c.dd.time.has_max_halvings = 1, c.dd.time.max_halvings = 0;
    if (getenv("BENCH_LINEAR")) { /* the linear method by name (wr_solver_method_name), default pcg-block3 */
        int m;
        for (m = 1; m < WR_SOLVER_METHOD_COUNT; ++m)
            if (!strcmp(getenv("BENCH_LINEAR"), wr_solver_method_name((wr_solver_method)m))) c.dd.linear.method = (wr_solver_method)m;
    }
    if (getenv("BENCH_FORCING")) c.dd.newton.forcing = atof(getenv("BENCH_FORCING")); /* η_max, 0 = off */
    if (getenv("BENCH_VEL_TOL")) c.dd.newton.velocity_tol = atof(getenv("BENCH_VEL_TOL")); /* m/s, 0 = default */
    if (wr_dyn_create(&sim, &c.s, &c.dd, &dg) != WR_OK) {
        fprintf(stderr, "%s\n", dg.message);
        case_free(&c);
        return 1;
    }
    wr_dyn_state_init(&sim, &st, c.x, c.v);
    out->nv = c.m.nv;
    for (f = 0; f < WR_BENCH_WARM + frames; ++f) {
        wr_status s;
        if (f == WR_BENCH_WARM) c0 = cpu_seconds();
        s = wr_dyn_step(&sim, &st, &fs, &dg);
        if (verbose)
            printf("  frame %2d  NS %8.1f ms  lin %8.1f ms  CH %8.1f ms  steps %d halv %d  Newton %3d  PCG %5d  LS %3d  contacts %6d  "
                   "dmin %.2e  ccd %.2e  pat %d proj %d  %s\n",
                   f, 1e3 * fs.t_ns, 1e3 * fs.t_linear, 1e3 * fs.t_ch, (int)fs.steps, (int)fs.halvings, (int)fs.newton_iterations,
                   (int)fs.linear_iterations, (int)fs.line_search_evals, (int)fs.n_contacts, fs.min_distance,
                   fs.ccd_alpha_min, (int)fs.pattern_builds, (int)fs.elements_projected, wr_newton_stop_name(fs.stop));
        if (s != WR_OK) {
            printf("  frame %d failed: %s\n", f, dg.message);
            rc = 1;
            break;
        }
        if (f >= WR_BENCH_WARM) {
            ns[k] = fs.t_ns;
            ch[k] = fs.t_ch;
            tot[k] = fs.t_total;
            it[k] = fs.newton_iterations;
            pcg[k] = fs.linear_iterations;
            npi[k] = fs.newton_iterations ? fs.t_ns / fs.newton_iterations : 0.0;
            k++;
        }
    }
    if (k > 0) {
        out->ns = median(ns, k);
        out->ch = median(ch, k);
        out->tot = median(tot, k);
        out->newton = median(it, k);
        out->pcg = median(pcg, k);
        out->ns_per_newton = median(npi, k);
        out->cpu = (cpu_seconds() - c0) / k;
    }
    out->ok = rc == 0;
    out->hash = fnv(c.x, 3 * (size_t)c.m.nv);
    if (getenv("BENCH_DUMP")) { /* final positions, raw doubles, for comparing two settings */
        FILE *fp = fopen(getenv("BENCH_DUMP"), "wb");
        if (!fp || fwrite(c.x, sizeof(double), 3 * (size_t)c.m.nv, fp) != 3 * (size_t)c.m.nv) rc = 1;
        if (fp) fclose(fp);
    }
    wr_dyn_free(&sim);
    case_free(&c);
    return rc;
}

/* least-squares slope of log y against log x */
static double loglog_slope(const double *x, const double *y, int n) {
    double sx = 0, sy = 0, sxx = 0, sxy = 0;
    int i;
    for (i = 0; i < n; ++i) {
        double a = log(x[i]), b = log(y[i]);
        sx += a, sy += b, sxx += a * a, sxy += a * b;
    }
    return n > 1 ? (n * sxy - sx * sy) / (n * sxx - sx * sx) : 0.0;
}

/* The static solver's Newton step on the sphere case's mesh: pinned at two corners, gravity, the same
 * PCG; seconds per Newton step (wall) of WR_BENCH_STATIC_ITERS steps. */
static double static_step_seconds(int32_t n) {
    bench_case c;
    wr_statics_desc sd;
    wr_statics_stats ss;
    wr_diag dg;
    uint8_t *fixed;
    double t;
    if (case_make(&c, "sphere", n, 0.0)) return -1.0;
    fixed = (uint8_t *)calloc((size_t)c.m.nv, 1);
    fixed[0] = fixed[n] = 1;
    memset(&sd, 0, sizeof sd);
    sd.stop.max_iter = WR_BENCH_STATIC_ITERS;
    sd.loads.gravity[2] = -9.81;
    sd.loads.fixed = fixed;
    sd.linear.solver.method = WR_SOLVER_PCG_BLOCK3;
    sd.linear.solver.rel_tol = 1e-5;
    wr_statics_solve(&c.s, c.x, &sd, &ss, &dg); /* NOT_CONVERGED expected: a fixed number of steps */
    t = ss.iterations > 0 ? ss.t_total / ss.iterations : -1.0;
    printf("  static Newton: %d steps, %d PCG iterations, %.1f ms per step (assembly %.1f, projection %.1f, linear %.1f, "
           "line search %.1f ms per step)\n",
           (int)ss.iterations, (int)ss.linear_iterations, 1e3 * t, 1e3 * ss.t_assembly / ss.iterations,
           1e3 * ss.t_projection / ss.iterations, 1e3 * ss.t_linear / ss.iterations,
           1e3 * ss.t_line_search / ss.iterations);
    free(fixed);
    case_free(&c);
    return t;
}

static int bench_all(int32_t max_nv) {
    static const int32_t cells[] = {31, 70, 141, 223, 316};
    static const char *kinds[] = {"sphere", "mannequin"};
    int kc, i;
    int rc = 0;
#ifdef _OPENMP
    printf("OpenMP: %d threads\n", omp_get_max_threads());
#else
    printf("OpenMP: off (single thread)\n");
#endif
    for (kc = 0; kc < 2; ++kc) {
        double xs[8], yn[8], yc[8];
        int np = 0;
        printf("\n== %s: per-frame medians of %d frames after %d of fall ==\n", kinds[kc], WR_BENCH_FRAMES, WR_BENCH_WARM);
        printf("%8s %10s %10s %10s %10s %8s %8s %12s\n", "vertices", "NS[ms]", "CH[ms]", "total[ms]", "cpu[s]", "Newton",
               "PCG", "NS/Newton[ms]");
        for (i = 0; i < 5; ++i) {
            frame_fig fg;
            int32_t nv = (cells[i] + 1) * (cells[i] + 1);
            if (nv > max_nv) break;
            if (case_run(kinds[kc], cells[i], 0.0, WR_BENCH_FRAMES, 0, &fg)) rc = 1;
            printf("%8d %10.1f %10.1f %10.1f %10.2f %8.0f %8.0f %12.2f%s\n", (int)fg.nv, 1e3 * fg.ns, 1e3 * fg.ch,
                   1e3 * fg.tot, fg.cpu, fg.newton, fg.pcg, 1e3 * fg.ns_per_newton, fg.ok ? "" : "  (FAILED)");
            fflush(stdout);
            if (fg.ok && fg.ns > 0 && fg.ch > 0) xs[np] = fg.nv, yn[np] = fg.ns, yc[np] = fg.ch, np++;
        }
        if (np > 1)
            printf("scaling exponent (log-log fit over %d sizes): NS ~ n^%.2f, CH ~ n^%.2f\n", np, loglog_slope(xs, yn, np),
                   loglog_slope(xs, yc, np));
    }
    {
        frame_fig fg;
        double ts;
        printf("\n== NS per Newton iteration vs the static solver's Newton step (sphere mesh, 5041 vertices) ==\n");
        case_run("sphere", 70, 0.0, WR_BENCH_FRAMES, 0, &fg);
        ts = static_step_seconds(70);
        printf("  dynamics: %.1f ms NS per Newton iteration (%.0f PCG per Newton); ratio dynamic/static %.2f\n",
               1e3 * fg.ns_per_newton, fg.newton > 0 ? fg.pcg / fg.newton : 0.0, ts > 0 ? fg.ns_per_newton / ts : 0.0);
    }
#ifdef _OPENMP
    {
        frame_fig f1, f2;
        int32_t nc = max_nv >= 20164 ? 141 : 70;
        printf("\n== threads (OpenMP face blocks: element Hessians + PSD projection), sphere, %d vertices ==\n",
               (int)((nc + 1) * (nc + 1)));
        omp_set_num_threads(1);
        case_run("sphere", nc, 0.0, WR_BENCH_FRAMES, 0, &f1);
        omp_set_num_threads(2);
        case_run("sphere", nc, 0.0, WR_BENCH_FRAMES, 0, &f2);
        printf("  1 thread: NS %.1f ms, total %.1f ms, cpu %.2f s per frame\n", 1e3 * f1.ns, 1e3 * f1.tot, f1.cpu);
        printf("  2 threads: NS %.1f ms, total %.1f ms, cpu %.2f s per frame; NS gain %.2fx; final positions %s\n",
               1e3 * f2.ns, 1e3 * f2.tot, f2.cpu, f2.ns > 0 ? f1.ns / f2.ns : 0.0,
               f1.hash == f2.hash ? "bit-identical" : "DIFFER");
        if (f1.hash != f2.hash) rc = 1;
    }
#endif
    printf("\npaper (Style3D Table 1, GPU, not comparable): 3.8 ms NS + 0.8 ms CH per frame at 59k vertices\n");
    return rc;
}

int main(int argc, char **argv) {
    if (argc >= 5 && !strcmp(argv[1], "frames")) {
        frame_fig fg;
        int rc = case_run(argv[2], (int32_t)atoi(argv[3]), argc > 5 ? atof(argv[5]) : 0.0, atoi(argv[4]), 1, &fg);
        printf("%s %d vertices: median NS %.1f ms, CH %.1f ms, total %.1f ms, cpu %.2f s per frame, positions %016llx\n",
               argv[2], (int)fg.nv, 1e3 * fg.ns, 1e3 * fg.ch, 1e3 * fg.tot, fg.cpu, (unsigned long long)fg.hash);
        return rc;
    }
    if (argc >= 2 && (!strcmp(argv[1], "-h") || !strcmp(argv[1], "--help"))) {
        printf("usage: bench_dynamics [max_vertices] | bench_dynamics frames sphere|mannequin N FRAMES [mu]\n");
        return 0;
    }
    return bench_all(argc >= 2 ? (int32_t)atoi(argv[1]) : 100000);
}
