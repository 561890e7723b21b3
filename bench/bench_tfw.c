/* bench_tfw: TFW timings per validation case against the paper's Table 2 (8-core i9-9900K):
 * stretched sheet (522 vertices; paper TFT 0.45 s + TFW 3.93 s), sheared rectangle (990; 2.27 +
 * 27.52 s), twisted cylinder (696; paper 688 vertices, 0.69 + 104.92 s). Per case: TFT base time
 * (statics.h, 4 load steps), SQP iterations, SQP time, and the TFW time split like the paper's
 * Fig. 23 (SQP assembly / SQP linear solves / SQP rest / init + phase + upsampling). Medians of 5
 * runs; the SQP is also run with the per-face-projected Hessian throughout (WR_WF_HESSIAN_PROJECTED,
 * the paper's first method) as the in-run peer, ratio printed. The sheared-rectangle base takes
 * ~45 s here, so it is timed once (marked "1 run") unless --full is given. Prints the machine. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "wrinkle/wrinkle.h"
#include "wrinkle/tfw.h"

#define RUNS 5
#define PI_ 3.14159265358979323846

static int cmp_d(const void *a, const void *b) {
    double x = *(const double *)a, y = *(const double *)b;
    return x < y ? -1 : x > y;
}
static double median(double *v, int n) {
    qsort(v, (size_t)n, sizeof(double), cmp_d);
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
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

typedef struct bcase {
    const char *name;
    int kind; /* 0 sheet, 1 shear, 2 cylinder */
    double paper_tft, paper_tfw;
    int paper_iters, paper_nv;
} bcase;

/* builds mesh, shell and motions; returns base positions after the statics solve in x */
static int solve_base(int kind, wr_mesh *m, double **xout, double *t_base, wr_wf_material *mat) {
    wr_diag d;
    wr_shell sh;
    wr_shell_desc sd;
    wr_statics_desc st;
    wr_statics_stats ss;
    wr_motion mo[2];
    int32_t *s0, *s1, n0 = 0, n1 = 0, v;
    double *x, t0;
    wr_status s;
    if (kind == 0) {
        wr_mesh_rectangle(m, 0.25, 0.1, 28, 17, &d);
        mat->young = 1e6, mat->poisson = 0.5, mat->thickness = 1e-4;
    } else if (kind == 1) {
        wr_mesh_rectangle(m, 0.38, 0.128, 54, 17, &d);
        mat->young = 3530e6, mat->poisson = 0.3, mat->thickness = 25e-6;
    } else {
        wr_mesh_cylinder_flat(m, 1.0, 5.0, 29, 23, &d);
        mat->young = 10e6, mat->poisson = 0.44, mat->thickness = 1e-4;
    }
    wr_tfw_base_shell_desc(mat->young, mat->poisson, mat->thickness, 0.0, &sd);
    if (wr_shell_create(&sh, m, &sd, &d)) return 0;
    s0 = (int32_t *)malloc(sizeof(int32_t) * m->nv);
    s1 = (int32_t *)malloc(sizeof(int32_t) * m->nv);
    x = (double *)malloc(sizeof(double) * 3 * m->nv);
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
    memset(&st, 0, sizeof st);
    memcpy(x, m->pos, sizeof(double) * 3 * m->nv);
    t0 = wr_time_seconds();
    s = wr_statics_solve_incremental(&sh, x, &st, mo, 2, 4, &ss, &d);
    *t_base = wr_time_seconds() - t0;
    wr_shell_free(&sh);
    free(s0);
    free(s1);
    *xout = x;
    return s == WR_OK || s == WR_ERR_NOT_CONVERGED;
}

int main(int argc, char **argv) {
    static const bcase cases[3] = {{"stretched sheet", 0, 0.45, 3.93, 23, 522},
                                   {"sheared rectangle", 1, 2.27, 27.52, 147, 1000},
                                   {"twisted cylinder", 2, 0.69, 104.92, 813, 688}};
    int full = argc > 1 && !strcmp(argv[1], "--full"), c, r;
    machine();
    printf("TFW per case, medians of %d runs (base: see runs column); paper = Table 2, 8-core i9-9900K\n", RUNS);
    printf("%-18s %6s %5s %9s %9s %6s %9s %9s | split of TFW: %7s %7s %7s %7s | %9s %9s %7s | %9s %7s\n", "case",
           "nv", "runs", "TFT [s]", "paper", "SQP it", "TFW [s]", "paper", "asm", "linear", "sqp-rest", "other",
           "speedup", "TFT x", "paper it", "proj [s]", "proj/auto");
    for (c = 0; c < 3; ++c) {
        wr_mesh m;
        wr_wf_material mat;
        double tb[RUNS], tt[RUNS], ta[RUNS], tl[RUNS], ts[RUNS], tp[RUNS], *x = NULL, t_base;
        int nb = (cases[c].kind == 1 && !full) ? 1 : RUNS, iters = 0;
        for (r = 0; r < nb; ++r) {
            memset(&m, 0, sizeof m);
            if (r > 0) free(x);
            if (!solve_base(cases[c].kind, &m, &x, &t_base, &mat)) {
                printf("%s: base failed\n", cases[c].name);
                return 1;
            }
            tb[r] = t_base;
            if (r < nb - 1) wr_mesh_free(&m);
        }
        for (r = 0; r < RUNS; ++r) {
            wr_tfw_desc td;
            wr_tfw_result res;
            wr_diag d;
            memset(&td, 0, sizeof td);
            td.upsample.levels = 2;
            wr_tfw_fields(&m, x, &mat, &td, &res, &d);
            tt[r] = res.seconds_total;
            ta[r] = res.sqp.seconds_assembly;
            tl[r] = res.sqp.seconds_solve;
            ts[r] = res.seconds_sqp - res.sqp.seconds_assembly - res.sqp.seconds_solve;
            iters = res.sqp.iterations;
            wr_tfw_result_free(&res);
            td.solve.hessian = WR_WF_HESSIAN_PROJECTED;
            td.no_upsample = 1;
            wr_tfw_fields(&m, x, &mat, &td, &res, &d);
            tp[r] = res.seconds_sqp;
            wr_tfw_result_free(&res);
        }
        {
            /* the split comes from the run whose TFW total is the median, so its parts add up */
            double mtb = median(tb, nb), mtt, mta, mtl, mts, mtp;
            double tt2[RUNS];
            int k, km = 0;
            memcpy(tt2, tt, sizeof tt);
            mtt = median(tt2, RUNS);
            for (k = 0; k < RUNS; ++k)
                if (tt[k] == mtt) km = k;
            mta = ta[km];
            mtl = tl[km];
            mts = ts[km];
            mtp = median(tp, RUNS);
            printf("%-18s %6d %5d %9.3f %9.2f %6d %9.3f %9.2f | %12.3f %7.3f %7.3f %7.3f | %8.1fx %8.1fx %7d | %9.3f %7.2f\n",
                   cases[c].name, (int)m.nv, nb, mtb, cases[c].paper_tft, iters, mtt, cases[c].paper_tfw, mta, mtl, mts,
                   mtt - mta - mtl - mts, (cases[c].paper_tft + cases[c].paper_tfw) / (mtb + mtt),
                   cases[c].paper_tft / mtb, cases[c].paper_iters, mtp, mtp / (mta + mtl + mts));
        }
        free(x);
        wr_mesh_free(&m);
    }
    printf("speedup = (paper TFT + TFW) / (ours TFT + TFW); TFT x = paper TFT / ours; proj = SQP seconds with the "
           "projected Hessian throughout (in-run peer), proj/auto its ratio to the default AUTO strategy.\n");
    return 0;
}
