/* bench_projection — cost of the per-element Hessian projection in the StVK reference statics
 * (statics.h): WR_PROJECT_FAST (Cholesky test, eigenvalues-only QL, inverse iteration for the
 * negative eigenpairs) against WR_PROJECT_JACOBI (core.h's cyclic Jacobi on every block, the former
 * path), measured in the same run on the same Newton trajectory.
 *
 * Problem: the resolution paper's stretch test (Fig. 16): 0.25 m × 0.1 m sheet, Y = 1 MPa,
 * ν = 0.5 (0.5 − 1e-9, plane stress), h = 0.1 mm, StVK membrane + mid-edge bending, short edges
 * clamped and moved apart by 12.78% in one step, seeded normal kick 1e-5 m (seed 1) so the sheet
 * wrinkles. Regular alternating-diagonal grids of ~1e3, ~4e3 and ~1e4 vertices. Each run does
 * WR_BENCH_ITERS Newton steps (linear solver: AUTO = CHOLMOD) from the same start, so both
 * projections assemble the same matrices up to round-off; the final gradient norms are printed to
 * show that. Reported: median over WR_BENCH_RUNS runs of the wall seconds per Newton step of
 * projection, assembly, linear solve, line search and total, the process CPU seconds of the whole
 * run, and jacobi/fast ratios; then the projection alone in CPU time on the 18×18 blocks of the
 * final state (median of WR_BENCH_RUNS), the steadiest figure on a shared machine. Run with
 * OPENBLAS_NUM_THREADS=1 so CHOLMOD's BLAS threads do not inflate the CPU time.
 * Usage: bench_projection [max_vertices]   (default 11000)
 */
/* The implementation comes from drivers/lib/impl.c (linked into every bench by the Makefile). */
#include "wrinkle/core.h"
#include "wrinkle/mesh.h"
#include "wrinkle/shell.h"
#include "wrinkle/statics.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#define WR_BENCH_RUNS 5
#define WR_BENCH_ITERS 5

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

/* Projection alone, in process CPU time: the element blocks of the state x are collected once and
 * projected by both methods (the shared box makes wall time of short kernels unreliable). */
typedef struct block_set {
    double *K;
    int32_t n, cap;
} block_set;

static wr_status collect(void *user, int32_t k, const int32_t *verts, const double *Ke) {
    block_set *b = (block_set *)user;
    (void)verts;
    if (k != 6 || b->n >= b->cap) return WR_OK; /* full mid-edge stencils (18×18) */
    memcpy(b->K + 324 * (size_t)b->n++, Ke, sizeof(double) * 324);
    return WR_OK;
}

static void projection_only(const wr_shell *s, const double *x) {
    block_set b;
    wr_hess_sink hs;
    double A[324], t[2][WR_BENCH_RUNS], err = 0.0;
    int k, mi;
    int32_t i, q, neg = 0;
    b.cap = s->nf;
    b.n = 0;
    b.K = (double *)malloc(sizeof(double) * 324 * (size_t)b.cap);
    if (!b.K) return;
    hs.user = &b;
    hs.add = collect;
    wr_shell_hessian_elements(s, x, 0, &hs, NULL);
    for (k = 0; k < WR_BENCH_RUNS; ++k)
        for (mi = 0; mi < 2; ++mi) {
            clock_t c0 = clock();
            for (i = 0; i < b.n; ++i) {
                int r;
                memcpy(A, b.K + 324 * (size_t)i, sizeof A);
                r = mi == 0 ? wr_dense_project_spd(18, A, 0.0) : wr_newton_project_spd(18, A, 0.0);
                if (mi == 1 && k == 0 && r > 0) neg++;
            }
            t[mi][k] = (double)(clock() - c0) / CLOCKS_PER_SEC / b.n * 1e6;
        }
    for (i = 0; i < b.n; ++i) {
        double B[324], nrm = 0.0, e = 0.0;
        memcpy(A, b.K + 324 * (size_t)i, sizeof A);
        memcpy(B, A, sizeof B);
        wr_dense_project_spd(18, A, 0.0);
        wr_newton_project_spd(18, B, 0.0);
        for (q = 0; q < 324; ++q) {
            nrm = fmax(nrm, fabs(b.K[324 * (size_t)i + q]));
            e = fmax(e, fabs(A[q] - B[q]));
        }
        if (nrm > 0.0) err = fmax(err, e / nrm);
    }
    {
        double tj = median(t[0], WR_BENCH_RUNS), tf = median(t[1], WR_BENCH_RUNS);
        printf("projection only (cpu, %d blocks of 18x18 at the end state, %d changed by fast): jacobi %.2f us/block, "
               "fast %.2f us/block, ratio %.2fx, max |difference| / max|K| %.1e\n",
               (int)b.n, (int)neg, tj, tf, tj / tf, err);
    }
    free(b.K);
}

typedef struct run_result {
    double proj, assembly, linear, ls, total, cpu, grad;
    int32_t projected, assembled, iters;
} run_result;

static int run_once(const wr_mesh *m, const wr_shell *s, wr_projection proj, run_result *r, double *xout) {
    wr_statics_desc sd;
    wr_statics_stats st;
    wr_diag dg;
    uint8_t *fixed = (uint8_t *)calloc((size_t)m->nv, 1);
    double *x = (double *)malloc(sizeof(double) * 3 * (size_t)m->nv);
    clock_t c0;
    int32_t v;
    wr_status rs;
    if (!fixed || !x) {
        free(fixed);
        free(x);
        return 1;
    }
    for (v = 0; v < m->nv; ++v) {
        double u = m->rest[2 * v];
        x[3 * v] = 1.1278 * u;
        x[3 * v + 1] = m->rest[2 * v + 1];
        x[3 * v + 2] = 0.0;
        fixed[v] = u < 1e-12 || u > 0.25 - 1e-12;
    }
    memset(&sd, 0, sizeof sd);
    sd.loads.fixed = fixed;
    sd.start.perturb = 1e-5;
    sd.start.seed = 1;
    sd.stop.max_iter = WR_BENCH_ITERS;
    sd.hessian.projection = proj;
    c0 = clock();
    rs = wr_statics_solve(s, x, &sd, &st, &dg);
    r->cpu = (double)(clock() - c0) / CLOCKS_PER_SEC;
    if (xout) memcpy(xout, x, sizeof(double) * 3 * (size_t)m->nv);
    free(fixed);
    free(x);
    if (rs != WR_OK && rs != WR_ERR_NOT_CONVERGED) {
        printf("solve failed: %s\n", dg.message);
        return 1;
    }
    r->iters = st.iterations;
    r->proj = st.t_projection / st.iterations;
    r->assembly = st.t_assembly / st.iterations;
    r->linear = st.t_linear / st.iterations;
    r->ls = st.t_line_search / st.iterations;
    r->total = st.t_total / st.iterations;
    r->grad = st.grad_norm;
    r->projected = st.elements_projected;
    r->assembled = st.elements_assembled;
    return 0;
}

int main(int argc, char **argv) {
    const int32_t grids[3][2] = {{50, 20}, {100, 40}, {160, 64}};
    const wr_projection methods[2] = {WR_PROJECT_JACOBI, WR_PROJECT_FAST};
    const char *names[2] = {"jacobi", "fast"};
    long max_vertices = argc > 1 ? atol(argv[1]) : 11000;
    int gi, mi, k;
    print_machine();
    printf("problem: stretch test 0.25 x 0.1 m, Y=1 MPa, nu=0.5, h=0.1 mm, StVK + mid-edge, 12.78%% stretch, "
           "%d Newton steps per run, median of %d runs (wall s per Newton step; cpu s per run)\n",
           WR_BENCH_ITERS, WR_BENCH_RUNS);
    for (gi = 0; gi < 3; ++gi) {
        wr_mesh m;
        wr_shell s;
        wr_shell_desc d;
        wr_diag dg;
        double med[2][6], *xend;
        run_result last[2];
        if ((long)(grids[gi][0] + 1) * (grids[gi][1] + 1) > max_vertices) break;
        if (wr_mesh_rectangle(&m, 0.25, 0.1, grids[gi][0], grids[gi][1], &dg) != WR_OK) {
            printf("mesh: %s\n", dg.message);
            return 1;
        }
        memset(&d, 0, sizeof d);
        d.young = 1e6;
        d.poisson = 0.5 - 1e-9;
        d.thickness = 1e-4;
        if (wr_shell_create(&s, &m, &d, &dg) != WR_OK) {
            printf("shell: %s\n", dg.message);
            return 1;
        }
        xend = (double *)malloc(sizeof(double) * 3 * (size_t)m.nv);
        if (!xend) return 1;
        for (mi = 0; mi < 2; ++mi) {
            double v[6][WR_BENCH_RUNS];
            for (k = 0; k < WR_BENCH_RUNS; ++k) {
                run_result r;
                if (run_once(&m, &s, methods[mi], &r, xend)) return 1;
                v[0][k] = r.proj, v[1][k] = r.assembly, v[2][k] = r.linear, v[3][k] = r.ls, v[4][k] = r.total;
                v[5][k] = r.cpu;
                last[mi] = r;
            }
            for (k = 0; k < 6; ++k) med[mi][k] = median(v[k], WR_BENCH_RUNS);
        }
        printf("\nnv %d, nf %d\n", (int)m.nv, (int)m.nf);
        printf("%-7s %10s %10s %10s %10s %10s %10s %12s %s\n", "method", "proj", "assembly", "linear", "lsearch",
               "total", "cpu/run", "|grad| end", "blocks projected");
        for (mi = 0; mi < 2; ++mi)
            printf("%-7s %10.4f %10.4f %10.4f %10.4f %10.4f %10.3f %12.4e %d/%d\n", names[mi], med[mi][0], med[mi][1],
                   med[mi][2], med[mi][3], med[mi][4], med[mi][5], last[mi].grad, (int)last[mi].projected,
                   (int)last[mi].assembled);
        printf("ratio jacobi/fast: projection %.2fx, Newton step %.2fx, cpu %.2fx; projection share %.0f%% -> %.0f%%\n",
               med[0][0] / med[1][0], med[0][4] / med[1][4], med[0][5] / med[1][5], 100.0 * med[0][0] / med[0][4],
               100.0 * med[1][0] / med[1][4]);
        projection_only(&s, xend);
        free(xend);
        fflush(stdout);
        wr_shell_free(&s);
        wr_mesh_free(&m);
    }
    return 0;
}
