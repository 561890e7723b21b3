/* bench_pcg — wr_spd_solve on the Newton matrix of a clamped linear membrane (K + M/dt^2, 3 DOF per
 * vertex) at 1e4, 1e5 and 4e5 vertices: every PCG preconditioner against CHOLMOD in the same run.
 *
 * Matrix (tests/membrane_fixture.h): 1 m x 1 m square, alternating-diagonal triangulation,
 * plane-stress CST with 2D modulus Y = 1e4 N/m and nu = 0.3, lumped mass rho = 0.2 kg/m^2 on all
 * 3 DOFs over dt = 1/30 s (Style3D's step). Top row of vertices clamped (all 3 DOFs) through
 * wr_spd_desc.fixed. Load: gravity in the plane (-y) plus a deterministic out-of-plane load.
 * Tolerance 1e-8 relative residual. Times are wall-clock seconds for create + factor + solve
 * (everything a caller pays for one solve); setup[s] is the create + factor part of it (CHOLMOD:
 * ordering/analysis + numeric factorisation; AMG: hierarchy construction), and CHOLMOD's numeric
 * factorisation alone is listed below each table. PCG runs on one thread; CHOLMOD's BLAS may use
 * both cores (the mapped BLAS library is printed at the end).
 * Median of 5 runs; a method whose first run exceeds WR_BENCH_SLOW seconds is run once, and one
 * whose predicted time at the next size exceeds WR_BENCH_SKIP seconds is skipped there (printed).
 * Usage: bench_pcg [max_vertices [method,method,...]]   (default 400000, all methods)
 */
/* The implementation comes from drivers/lib/impl.c (linked into every bench by the Makefile). */
#include "wrinkle/core.h"
#include "wrinkle/sparse.h"
#include "wrinkle/spd.h"
#include "../tests/membrane_fixture.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define WR_BENCH_RUNS 5
#define WR_BENCH_SLOW 60.0  /* s: beyond this one run only (keeps the whole bench < ~10 min) */
#define WR_BENCH_SKIP 100.0 /* s: predicted single-run time above which a method is skipped */

static const wr_solver_method methods[] = {WR_SOLVER_PCG_JACOBI, WR_SOLVER_PCG_BLOCK3, WR_SOLVER_PCG_IC0,
                                           WR_SOLVER_PCG_AMG, WR_SOLVER_CHOLMOD};
#define NM ((int)(sizeof methods / sizeof methods[0]))

static int cmp_double(const void *a, const void *b) {
    double x = *(const double *)a, y = *(const double *)b;
    return x < y ? -1 : x > y;
}

static double median(double *v, int n) {
    qsort(v, (size_t)n, sizeof *v, cmp_double);
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

static void print_machine(void) {
    FILE *f = fopen("/proc/cpuinfo", "r");
    char line[512], model[256] = "unknown";
    long ncpu = 0;
    if (f) {
        while (fgets(line, sizeof line, f)) {
            if (!strncmp(line, "model name", 10) && !strcmp(model, "unknown")) {
                char *c = strchr(line, ':');
                if (c) {
                    snprintf(model, sizeof model, "%s", c + 2);
                    model[strcspn(model, "\n")] = 0;
                }
            }
            if (!strncmp(line, "processor", 9)) ncpu++;
        }
        fclose(f);
    }
    printf("machine: %ld logical CPUs, %s\n", ncpu, model);
}

/* Which BLAS did CHOLMOD pull in? Look at the shared objects mapped into this process. */
static void print_blas(void) {
    FILE *f = fopen("/proc/self/maps", "r");
    char line[1024], seen[8][512];
    int ns = 0, k;
    if (!f) return;
    while (fgets(line, sizeof line, f)) {
        char *p = strchr(line, '/');
        if (!p || (!strstr(p, "blas") && !strstr(p, "lapack"))) continue;
        p[strcspn(p, "\n")] = 0;
        for (k = 0; k < ns && strcmp(seen[k], p); ++k) {
        }
        if (k == ns && ns < 8) snprintf(seen[ns++], sizeof seen[0], "%s", p);
    }
    fclose(f);
    for (k = 0; k < ns; ++k) printf("BLAS/LAPACK mapped: %s\n", seen[k]);
    if (!ns) printf("BLAS/LAPACK mapped: none found in /proc/self/maps\n");
}

int main(int argc, char **argv) {
    const int32_t grids[3] = {99, 315, 631}; /* cells per side: 1e4, 99856, 399424 vertices */
    long max_vertices = argc > 1 ? atol(argv[1]) : 400000;
    double prev_time[NM];
    int32_t prev_nv = 0;
    int gi, m;
    print_machine();
    printf("problem: clamped membrane K + M/dt^2, Y=1e4 N/m, nu=0.3, rho=0.2 kg/m^2, dt=1/30 s, rel_tol 1e-8\n");
    for (m = 0; m < NM; ++m) prev_time[m] = 0.0;
    for (gi = 0; gi < 3; ++gi) {
        membrane_params P;
        wr_csr A;
        wr_diag d;
        double *mass, *b, *x, t_ch = 0.0, times[NM], fac_only = 0.0;
        uint8_t *fixed;
        int32_t nv, v, k;
        wr_rng rng;
        memset(&P, 0, sizeof P);
        P.nx = P.ny = grids[gi];
        P.w = P.h = 1.0;
        P.Y = 1e4;
        P.nu = 0.3;
        P.rho = 0.2;
        P.dt = 1.0 / 30.0;
        nv = (P.nx + 1) * (P.ny + 1);
        if (nv > max_vertices) break;
        mass = (double *)wr_alloc_array((size_t)nv, sizeof(double));
        if (membrane_matrix(&P, &A, mass, &d) != WR_OK) {
            printf("matrix build failed: %s\n", d.message);
            return 1;
        }
        b = (double *)wr_alloc_array((size_t)A.n, sizeof(double));
        x = (double *)wr_alloc_array((size_t)A.n, sizeof(double));
        fixed = (uint8_t *)wr_calloc_array((size_t)A.n, 1);
        wr_rng_seed(&rng, 2025);
        for (v = 0; v < nv; ++v) {
            b[3 * v + 0] = 0.0;
            b[3 * v + 1] = -9.81 * mass[v];
            b[3 * v + 2] = mass[v] * (0.5 + wr_rng_uniform(&rng));
            if (v / (P.nx + 1) == P.ny)
                for (k = 0; k < 3; ++k) fixed[3 * v + k] = 1;
        }
        printf("\n== %d vertices, n = %d DOFs, nnz = %d ==\n", (int)nv, (int)A.n, (int)A.nnz);
        printf("%-12s %6s %10s %10s %12s %11s  %s\n", "method", "runs", "median[s]", "setup[s]", "iterations",
               "rel.resid", "notes");
        for (m = 0; m < NM; ++m) {
            double runs[WR_BENCH_RUNS], facs[WR_BENCH_RUNS], setups[WR_BENCH_RUNS], predicted = 0.0;
            int r, nruns = WR_BENCH_RUNS;
            wr_spd_stats st;
            wr_status s = WR_OK;
            times[m] = -1.0;
            if (argc > 2 && !strstr(argv[2], wr_solver_method_name(methods[m]))) continue;
            if (prev_nv > 0 && prev_time[m] > 0.0) {
                /* O(n^1.5) growth for both PCG on a 2D elliptic problem and nested-dissection Cholesky */
                double ratio = (double)nv / prev_nv;
                predicted = prev_time[m] * ratio * sqrt(ratio);
                if (predicted > WR_BENCH_SKIP) {
                    printf("%-12s skipped: predicted %.0f s per run from the previous size\n",
                           wr_solver_method_name(methods[m]), predicted);
                    prev_time[m] = predicted;
                    continue;
                }
            }
            for (r = 0; r < nruns; ++r) {
                wr_spd_solver S;
                wr_spd_desc sd;
                double t0;
                memset(&sd, 0, sizeof sd);
                sd.method = methods[m];
                sd.rel_tol = 1e-8;
                sd.fixed = fixed;
                memset(x, 0, sizeof(double) * (size_t)A.n);
                t0 = wr_time_seconds();
                s = wr_spd_solver_create(&S, &A, &sd, &d);
                if (s == WR_OK) s = wr_spd_solver_factor(&S, &A, &d);
                if (s == WR_OK) s = wr_spd_solver_solve(&S, &A, b, x, &st, &d);
                runs[r] = wr_time_seconds() - t0;
                facs[r] = S.factor_seconds;
                setups[r] = S.analyze_seconds + S.factor_seconds;
                wr_spd_solver_free(&S);
                if (s != WR_OK) break;
                if (r == 0 && runs[0] > WR_BENCH_SLOW) nruns = 1;
            }
            if (s != WR_OK) {
                printf("%-12s FAILED: %s (%s)\n", wr_solver_method_name(methods[m]), wr_status_string(s), d.message);
                continue;
            }
            times[m] = median(runs, nruns);
            prev_time[m] = times[m];
            if (methods[m] == WR_SOLVER_CHOLMOD) {
                t_ch = times[m];
                fac_only = median(facs, nruns);
            }
            printf("%-12s %6d %10.3f %10.3f %12d %11.2e  %s%s\n", wr_solver_method_name(methods[m]), nruns, times[m],
                   median(setups, nruns), (int)st.iterations, st.rel_residual, nruns < WR_BENCH_RUNS ? "single run (> 60 s) " : "",
                   st.ic_shift > 0 ? "IC shift used" : "");
            fflush(stdout);
        }
        if (t_ch > 0.0) {
            printf("ratios to cholmod (time / cholmod time; < 1 = faster than CHOLMOD):\n");
            for (m = 0; m < NM; ++m)
                if (times[m] > 0.0) printf("  %-12s %7.2fx\n", wr_solver_method_name(methods[m]), times[m] / t_ch);
            printf("  cholmod numeric factorisation alone: %.3f s (analysis + factor + solve %.3f s)\n", fac_only, t_ch);
        }
        prev_nv = nv;
        wr_free(mass);
        wr_free(b);
        wr_free(x);
        wr_free(fixed);
        wr_csr_free(&A);
    }
    printf("\n");
    print_blas();
    return 0;
}
