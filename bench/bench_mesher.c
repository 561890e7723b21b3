/* bench_mesher: wr_mesher_run on a 1.5 m square panel at a uniform 2.5 mm (~4.4e5 vertices), the
 * issue-17 case (target: the mesher's total <= 2x its CDT, assemble <= CDT), in CPU seconds.
 *
 *   bin/bench_mesher                the 1.5 m square at 2.5 mm, RUNS runs
 *   bin/bench_mesher SIDE_MM H_MM   another square side and uniform size [mm]
 *
 * Per run, alternately in the same process: the whole wr_mesher_run, then its three big stages
 * alone on the same input — wr_poisson_fill of the square's boundary (discretised as the mesher
 * does: equal steps of about h), wr_cdt_triangulate of the result, wr_mesh_create of the triangles
 * — each timed with clock() (CPU, so the figures hold on a loaded machine; the mesher's own
 * report.t_* are wall clock and are printed beside). Medians over RUNS runs; the load average is
 * printed at start and end. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "wrinkle/core.h"
#include "wrinkle/mesher.h"

#define RUNS 5

static int cmp_d(const void *a, const void *b) {
    double x = *(const double *)a, y = *(const double *)b;
    return x < y ? -1 : x > y;
}

static double median(const double *v, int n) {
    double s[RUNS];
    memcpy(s, v, sizeof(double) * (size_t)n);
    qsort(s, (size_t)n, sizeof(double), cmp_d);
    return s[n / 2];
}

static double loadavg(void) {
    FILE *f = fopen("/proc/loadavg", "r");
    double l = -1.0;
    if (f) {
        if (fscanf(f, "%lf", &l) != 1) l = -1.0;
        fclose(f);
    }
    return l;
}

static double cpu_since(clock_t c0) { return (double)(clock() - c0) / CLOCKS_PER_SEC; }

static double size_const(void *u, double x, double y) {
    (void)x;
    (void)y;
    return *(const double *)u;
}

/* The stages alone: fill, CDT, mesh build; CPU seconds of each, the sample count. */
static int stages(double side, double h, uint64_t seed, double *t_fill, double *t_cdt, double *t_mesh, int32_t *n_samples) {
    int32_t ns = (int32_t)floor(side / h + 0.5), n = 4 * ns, i;
    double *loop = (double *)malloc(sizeof(double) * 2 * (size_t)n);
    wr_poisson_domain dom;
    wr_poisson_desc pd;
    wr_poisson_result pr;
    wr_cdt_input ci;
    wr_cdt_desc cd;
    wr_cdt_result cr;
    wr_mesh m;
    wr_diag d;
    clock_t c0;
    int bad = 0;
    if (!loop) return 1;
    for (i = 0; i < n; ++i) { /* CCW, equal steps side / ns */
        int32_t k = i / ns, j = i % ns;
        double t = side * j / ns;
        loop[2 * i] = k == 0 ? t : k == 1 ? side : k == 2 ? side - t : 0.0;
        loop[2 * i + 1] = k == 0 ? 0.0 : k == 1 ? t : k == 2 ? side : side - t;
    }
    memset(&dom, 0, sizeof dom);
    memset(&pd, 0, sizeof pd);
    dom.outer.xy = loop;
    dom.outer.n = n;
    pd.seed = seed;
    pd.max_points = 50000000;
    c0 = clock();
    if (wr_poisson_fill(&dom, size_const, &h, &pd, &pr, &d) != WR_OK) {
        fprintf(stderr, "bench_mesher: fill: %s\n", d.message);
        free(loop);
        return 1;
    }
    *t_fill = cpu_since(c0);
    *n_samples = pr.n_points - pr.n_fixed;
    memset(&ci, 0, sizeof ci);
    memset(&cd, 0, sizeof cd);
    ci.points = pr.points;
    ci.n_points = pr.n_points;
    ci.segments = pr.segments;
    ci.n_segments = pr.n_segments;
    cd.seed = seed + 1;
    c0 = clock();
    if (wr_cdt_triangulate(&ci, &cd, &cr, &d) != WR_OK) {
        fprintf(stderr, "bench_mesher: cdt: %s\n", d.message);
        bad = 1;
    }
    *t_cdt = cpu_since(c0);
    if (!bad) {
        c0 = clock();
        if (wr_mesh_create(&m, cr.n_points, NULL, cr.points, cr.n_triangles, cr.triangles, &d) != WR_OK) {
            fprintf(stderr, "bench_mesher: mesh: %s\n", d.message);
            bad = 1;
        } else {
            *t_mesh = cpu_since(c0);
            wr_mesh_free(&m);
        }
    }
    wr_cdt_free(&cr);
    wr_poisson_free(&pr);
    free(loop);
    return bad;
}

int main(int argc, char **argv) {
    double side = 1.5, h = 2.5e-3, sq[8];
    double cpu[RUNS], fill[RUNS], cdt[RUNS], mcre[RUNS], ratio[RUNS], rate[RUNS], wp[RUNS], wc[RUNS], wa[RUNS], wt[RUNS];
    wr_pattern_panel pn;
    wr_pattern pat;
    wr_mesher_desc desc;
    int k, nv = 0;
    if (argc == 3) {
        side = atof(argv[1]) * 1e-3;
        h = atof(argv[2]) * 1e-3;
    }
    if ((argc != 1 && argc != 3) || !(side > 0.0 && h > 0.0 && side / h < 1e5)) {
        fprintf(stderr, "usage: bench_mesher [SIDE_MM H_MM]\n");
        return 2;
    }
    sq[0] = 0, sq[1] = 0, sq[2] = side, sq[3] = 0, sq[4] = side, sq[5] = side, sq[6] = 0, sq[7] = side;
    memset(&pn, 0, sizeof pn);
    memset(&pat, 0, sizeof pat);
    memset(&desc, 0, sizeof desc);
    pn.outer.xy = sq;
    pn.outer.n = 4;
    pn.fabric.B = 2.6e-6; /* Table 1 Green; ignored under uniform_resolution */
    pn.fabric.E = 2.0e6;
    pat.panels = &pn;
    pat.n_panels = 1;
    desc.uniform_resolution = h;
    printf("bench_mesher: %.4g m square at a uniform %.4g mm, %d runs, load average %.2f at start\n", side, 1e3 * h,
           RUNS, loadavg());
    for (k = 0; k < RUNS; ++k) {
        wr_mesher_result res;
        wr_diag d;
        int32_t ns = 0;
        clock_t c0 = clock();
        desc.seed = (uint64_t)k + 1;
        if (wr_mesher_run(&pat, &desc, &res, &d) != WR_OK) {
            fprintf(stderr, "bench_mesher: %s\n", d.message);
            return 1;
        }
        cpu[k] = cpu_since(c0);
        wp[k] = res.report.t_poisson;
        wc[k] = res.report.t_cdt;
        wa[k] = res.report.t_assemble;
        wt[k] = res.report.t_total;
        nv = res.mesh.nv;
        wr_mesher_free(&res);
        if (stages(side, h, (uint64_t)k + 1, &fill[k], &cdt[k], &mcre[k], &ns)) return 1;
        ratio[k] = cpu[k] / cdt[k];
        rate[k] = ns / fill[k];
    }
    printf("vertices %d\n", nv);
    printf("cpu  [s]  mesher total %.3f | alone: poisson fill %.3f  cdt %.3f  wr_mesh_create %.3f\n", median(cpu, RUNS),
           median(fill, RUNS), median(cdt, RUNS), median(mcre, RUNS));
    printf("          mesher total / cdt = %.2f (median of per-run ratios)   fill %.0f samples/cpu-s\n", median(ratio, RUNS),
           median(rate, RUNS));
    printf("wall [s]  mesher report: poisson %.3f  cdt %.3f  assemble %.3f  total %.3f (total/cdt %.2f)\n", median(wp, RUNS),
           median(wc, RUNS), median(wa, RUNS), median(wt, RUNS), median(wt, RUNS) / median(wc, RUNS));
    printf("load average %.2f at end\n", loadavg());
    return 0;
}
