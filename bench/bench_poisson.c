/* bench_poisson: samples per CPU second of wr_poisson_sample for ~1.2e6 samples on the unit square,
 * at constant sizing and at a 20×-graded sizing h = h0 (1 + 19 x); median of RUNS runs each.
 *
 *   bin/bench_poisson                     this build only
 *   bin/bench_poisson --baseline OLD      also OLD, a bench_poisson built against another
 *                                         poisson.h (e.g. main's), run as a child process
 *                                         alternately with this build (same load, same run)
 *   bin/bench_poisson --one CASE SEED     one run, one line "n cpu_s wall_s" (used by --baseline)
 *
 * Only wr_poisson_sample is used, so the same source builds against the old header. CPU seconds
 * (clock()) are the figure on a shared machine; wall is printed beside. The sizes are chosen for a
 * point count, not a radius: h differs between builds when their density κ differs, so h is found
 * by one small calibration run per build ("--one" prints the count at the reference h). */
#define _POSIX_C_SOURCE 200809L /* popen */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <math.h>
#include <time.h>

#include "wrinkle/core.h"
#include "wrinkle/poisson.h"

#define RUNS 5
#define TARGET_POINTS 1.2e6

static double size_const(void *u, double x, double y) {
    (void)x;
    (void)y;
    return *(const double *)u;
}
static double size_ramp(void *u, double x, double y) {
    (void)y;
    return *(const double *)u * (1.0 + 19.0 * x);
}

static int cmp_d(const void *a, const void *b) {
    double x = *(const double *)a, y = *(const double *)b;
    return x < y ? -1 : x > y;
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
    printf("machine: %s, %d logical CPUs (single-threaded benchmark)\n", model, ncpu);
}

/* One sampling of the unit square; graded != 0 for the ramp. h is the constant sizing (or h0). */
static int sample_once(int graded, double h, uint64_t seed, int32_t *n, double *cpu, double *wall) {
    static const double sq[8] = {0, 0, 1, 0, 1, 1, 0, 1};
    wr_poisson_domain dom;
    wr_poisson_desc desc;
    wr_poisson_result res;
    wr_diag d;
    clock_t c0;
    memset(&dom, 0, sizeof dom);
    memset(&desc, 0, sizeof desc);
    dom.outer.xy = sq;
    dom.outer.n = 4;
    desc.seed = seed;
    c0 = clock();
    if (wr_poisson_sample(&dom, graded ? size_ramp : size_const, &h, &desc, &res, &d) != WR_OK) {
        fprintf(stderr, "bench_poisson: %s\n", d.message);
        return 1;
    }
    *cpu = (double)(clock() - c0) / CLOCKS_PER_SEC;
    *wall = res.seconds;
    *n = res.n_points;
    wr_poisson_free(&res);
    return 0;
}

/* h giving ~TARGET_POINTS for this build: N ∝ 1/h², measured at 8× the spacing (N/64). For the
 * ramp ∫0^1 dx / (1 + 19x)² = 1/20, so h0 = h / sqrt(20) gives about the same count. */
static double sizing_for_target(int graded) {
    double h = 0.0089 / (graded ? sqrt(20.0) : 1.0), cpu, wall;
    int32_t n;
    if (sample_once(graded, h, 99, &n, &cpu, &wall)) exit(1);
    return h * sqrt((double)n / TARGET_POINTS);
}

/* Run OLD --one CASE SEED; parse "n cpu wall". */
static int run_child(const char *bin, int graded, uint64_t seed, int32_t *n, double *cpu, double *wall) {
    char cmd[1024];
    FILE *p;
    int nn, ok;
    snprintf(cmd, sizeof cmd, "'%s' --one %s %llu", bin, graded ? "graded" : "constant", (unsigned long long)seed);
    p = popen(cmd, "r");
    if (!p) return 1;
    ok = fscanf(p, "%d %lf %lf", &nn, cpu, wall) == 3;
    *n = nn;
    return pclose(p) != 0 || !ok;
}

static void report(const char *who, const char *label, const int32_t *n, const double *cpu, const double *wall,
                   double *med_rate) {
    double rate[RUNS], c[RUNS], w[RUNS];
    int k;
    for (k = 0; k < RUNS; ++k) {
        rate[k] = n[k] / cpu[k];
        c[k] = cpu[k];
        w[k] = wall[k];
    }
    qsort(rate, RUNS, sizeof(double), cmp_d);
    qsort(c, RUNS, sizeof(double), cmp_d);
    qsort(w, RUNS, sizeof(double), cmp_d);
    printf("%-9s %-18s n = %8d  median cpu %.3f s (wall %.3f s)  median %8.0f samples/cpu-s  (min %.0f, max %.0f)\n",
           who, label, (int)n[RUNS - 1], c[RUNS / 2], w[RUNS / 2], rate[RUNS / 2], rate[0], rate[RUNS - 1]);
    *med_rate = rate[RUNS / 2];
}

int main(int argc, char **argv) {
    const char *baseline = NULL;
    int graded;
    if (argc == 4 && !strcmp(argv[1], "--one")) {
        int32_t n;
        double cpu, wall;
        graded = !strcmp(argv[2], "graded");
        if (sample_once(graded, sizing_for_target(graded), strtoull(argv[3], NULL, 10), &n, &cpu, &wall)) return 1;
        printf("%d %.6f %.6f\n", (int)n, cpu, wall);
        return 0;
    }
    if (argc == 3 && !strcmp(argv[1], "--baseline")) baseline = argv[2];
    else if (argc != 1) {
        fprintf(stderr, "usage: bench_poisson [--baseline OLD_BENCH_BINARY | --one constant|graded SEED]\n");
        return 2;
    }
    machine();
    for (graded = 0; graded < 2; ++graded) {
        const char *label = graded ? "20x graded sizing" : "constant sizing";
        int32_t n_new[RUNS], n_old[RUNS];
        double c_new[RUNS], w_new[RUNS], c_old[RUNS], w_old[RUNS], r_new, r_old;
        double h = sizing_for_target(graded);
        int k;
        for (k = 0; k < RUNS; ++k) { /* alternate: both builds see the same load */
            if (baseline && run_child(baseline, graded, (uint64_t)k + 1, &n_old[k], &c_old[k], &w_old[k])) {
                fprintf(stderr, "bench_poisson: baseline '%s' failed\n", baseline);
                return 1;
            }
            if (sample_once(graded, h, (uint64_t)k + 1, &n_new[k], &c_new[k], &w_new[k])) return 1;
        }
        report("this", label, n_new, c_new, w_new, &r_new);
        if (baseline) {
            report("baseline", label, n_old, c_old, w_old, &r_old);
            printf("          ratio this/baseline samples per cpu-s = %.2f\n", r_new / r_old);
        }
    }
    return 0;
}
