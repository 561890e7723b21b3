/* bench_poisson: samples/second of wr_poisson_sample for ~1e6 samples at constant sizing and at a
 * 20×-graded sizing h = h0 (1 + 19 x) on the unit square; median of 5 runs each, and the ratio
 * graded/constant (near 1 when the multi-level grid keeps the work per sample independent of the
 * radius range, see poisson.h "ON THE ACCELERATION GRID"). Prints the machine. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <math.h>

#include "wrinkle/core.h"
#include "wrinkle/poisson.h"

#define RUNS 5

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

/* returns median samples/s; *n_out = points of the last run */
static double run(wr_poisson_sizing_fn fn, double h, const char *label) {
    static const double sq[8] = {0, 0, 1, 0, 1, 1, 0, 1};
    double rate[RUNS], secs[RUNS];
    int k;
    int32_t n = 0;
    wr_poisson_domain dom;
    wr_poisson_desc desc;
    memset(&dom, 0, sizeof dom);
    memset(&desc, 0, sizeof desc);
    dom.outer.xy = sq;
    dom.outer.n = 4;
    for (k = 0; k < RUNS; ++k) {
        wr_poisson_result res;
        wr_diag d;
        double t0;
        desc.seed = (uint64_t)k + 1;
        t0 = wr_time_seconds();
        if (wr_poisson_sample(&dom, fn, &h, &desc, &res, &d) != WR_OK) {
            printf("%s: error %s\n", label, d.message);
            exit(1);
        }
        secs[k] = wr_time_seconds() - t0;
        rate[k] = res.n_points / secs[k];
        n = res.n_points;
        wr_poisson_free(&res);
    }
    qsort(rate, RUNS, sizeof(double), cmp_d);
    qsort(secs, RUNS, sizeof(double), cmp_d);
    printf("%-28s n = %8d points  median %.3f s  median %.0f samples/s  (min %.0f, max %.0f)\n", label, (int)n,
           secs[RUNS / 2], rate[RUNS / 2], rate[0], rate[RUNS - 1]);
    return rate[RUNS / 2];
}

int main(void) {
    /* h chosen so both runs give ≈ 1e6 points: n ≈ κ/(c h)² for constant h; for the ramp
     * ∫0^1 dx / (1 + 19x)² = 1/20, so h0 = h / sqrt(20) gives the same count. */
    double h = 0.00099, h0 = h / sqrt(20.0), rc, rv;
    machine();
    rc = run(size_const, h, "constant sizing");
    rv = run(size_ramp, h0, "20x graded sizing");
    printf("ratio graded/constant samples/s = %.3f\n", rv / rc);
    return 0;
}
