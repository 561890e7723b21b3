/* bench_triangle — quality meshing against Shewchuk's Triangle 1.6, same inputs, same run.
 *
 *   WR_TRIANGLE=/path/to/triangle bin/bench_triangle [reps]      (default 21 repetitions)
 *
 * Inputs (written to a temporary directory as .poly files): the front bodice outline of
 * examples/garment_dress_shirred_waist.json (80 vertices), a unit square with five circular holes
 * (184 vertices) and, when a file A.poly sits beside the Triangle binary (Triangle's own sample),
 * that. For each input and -q30 / -q33 both programs run as processes on the same file,
 * alternating, `reps` times: CPU (user + system, from getrusage of the children) and wall per run,
 * medians reported, with the vertex counts of the outputs. Also the library call alone
 * (wr_cdt_triangulate, CPU of this process). Without WR_TRIANGLE the Triangle columns are skipped.
 * The bench never builds Triangle; bench/RESULTS.md says how the figures were obtained. */
#define _POSIX_C_SOURCE 200809L /* mkdtemp, fork, waitpid */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <math.h>
#include <sys/resource.h>
#include <sys/time.h>
#include <sys/wait.h>
#include <unistd.h>

#include "wrinkle/polyfile.h"

static double now(void) {
    struct timeval tv;
    gettimeofday(&tv, NULL);
    return tv.tv_sec + 1e-6 * tv.tv_usec;
}
static double child_cpu(void) {
    struct rusage ru;
    getrusage(RUSAGE_CHILDREN, &ru);
    return ru.ru_utime.tv_sec + 1e-6 * ru.ru_utime.tv_usec + ru.ru_stime.tv_sec + 1e-6 * ru.ru_stime.tv_usec;
}
static double self_cpu(void) {
    struct rusage ru;
    getrusage(RUSAGE_SELF, &ru);
    return ru.ru_utime.tv_sec + 1e-6 * ru.ru_utime.tv_usec + ru.ru_stime.tv_sec + 1e-6 * ru.ru_stime.tv_usec;
}
static int cmpd(const void *a, const void *b) {
    double x = *(const double *)a, y = *(const double *)b;
    return x < y ? -1 : x > y;
}
static double median(double *v, int n) {
    qsort(v, (size_t)n, sizeof *v, cmpd);
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

/* one run of prog with args; returns CPU and wall seconds */
static int run(const char *prog, const char *sw, const char *file, double *cpu, double *wall) {
    double c0, w0;
    pid_t p;
    fflush(stdout); /* the child must not inherit (and print again) buffered output */
    c0 = child_cpu();
    w0 = now();
    p = fork();
    int st;
    if (p < 0) return 0;
    if (p == 0) {
        if (!freopen("/dev/null", "w", stdout)) _exit(126);
        execl(prog, prog, sw, file, (char *)NULL);
        _exit(127);
    }
    if (waitpid(p, &st, 0) < 0 || !WIFEXITED(st) || WEXITSTATUS(st) != 0) return 0;
    *wall = now() - w0;
    *cpu = child_cpu() - c0;
    return 1;
}

/* the two generated inputs, as in tests/test_triangulate.c (refinement_size_vs_triangle) */
static void write_poly(const char *path, const double *p, int n, const int *loop_start, int nloops, const double *holes,
                       int nh) {
    FILE *f = fopen(path, "w");
    int i, l, k = 1;
    if (!f) {
        perror(path);
        exit(1);
    }
    fprintf(f, "%d 2 0 1\n", n);
    for (i = 0; i < n; ++i) fprintf(f, "%d %.17g %.17g 1\n", i + 1, p[2 * i], p[2 * i + 1]);
    fprintf(f, "%d 1\n", n);
    for (l = 0; l < nloops; ++l) {
        int a = loop_start[l], b = loop_start[l + 1];
        for (i = a; i < b; ++i) fprintf(f, "%d %d %d 1\n", k++, i + 1, (i + 1 < b ? i + 1 : a) + 1);
    }
    fprintf(f, "%d\n", nh);
    for (i = 0; i < nh; ++i) fprintf(f, "%d %.17g %.17g\n", i + 1, holes[2 * i], holes[2 * i + 1]);
    fclose(f);
}
static void make_inputs(const char *dir) {
    static const double c[] = {0, 0, 360, 0, 360, 250, 300, 330, 300, 420, 230, 420, 180, 360, 130, 420, 60, 420, 60, 330, 0, 250};
    static const double sq[] = {0, 0, 1, 0, 1, 1, 0, 1}, circ[5][4] = {{0.25, 0.25, 0.1, 24}, {0.75, 0.25, 0.06, 16},
                                                                       {0.5, 0.55, 0.14, 32}, {0.2, 0.8, 0.08, 20},
                                                                       {0.8, 0.78, 0.12, 28}};
    double p[2 * 256], holes[10];
    int ls[8], i, j, k, m = 0, h;
    char path[512];
    for (i = 0; i < 11; ++i) {
        const double *a = c + 2 * i, *b = c + 2 * ((i + 1) % 11);
        k = (int)ceil(hypot(b[0] - a[0], b[1] - a[1]) / 20.0);
        for (j = 0; j < k; ++j) {
            p[2 * m] = a[0] + (b[0] - a[0]) * j / k;
            p[2 * m + 1] = a[1] + (b[1] - a[1]) * j / k;
            ++m;
        }
    }
    ls[0] = 0;
    ls[1] = m;
    snprintf(path, sizeof path, "%s/bodice.poly", dir);
    write_poly(path, p, m, ls, 1, NULL, 0);
    m = 0;
    for (i = 0; i < 4; ++i)
        for (j = 0; j < 16; ++j) {
            const double *a = sq + 2 * i, *b = sq + 2 * ((i + 1) % 4);
            double t = j / 16.0;
            p[2 * m] = a[0] + (b[0] - a[0]) * t;
            p[2 * m + 1] = a[1] + (b[1] - a[1]) * t;
            ++m;
        }
    ls[0] = 0;
    ls[1] = m;
    for (h = 0; h < 5; ++h) {
        k = (int)circ[h][3];
        for (j = 0; j < k; ++j) {
            p[2 * m] = circ[h][0] + circ[h][2] * cos(2 * 3.141592653589793 * j / k);
            p[2 * m + 1] = circ[h][1] + circ[h][2] * sin(2 * 3.141592653589793 * j / k);
            ++m;
        }
        ls[h + 2] = m;
        holes[2 * h] = circ[h][0];
        holes[2 * h + 1] = circ[h][1];
    }
    snprintf(path, sizeof path, "%s/holes.poly", dir);
    write_poly(path, p, m, ls, 6, holes, 5);
}

static int first_int(const char *path) {
    FILE *f = fopen(path, "r");
    int n = -1;
    if (f) {
        if (fscanf(f, "%d", &n) != 1) n = -1;
        fclose(f);
    }
    return n;
}

int main(int argc, char **argv) {
    const char *tri = getenv("WR_TRIANGLE"), *names[3] = {"A", "bodice", "holes"};
    char dir[] = "/tmp/bench_triangle_XXXXXX", ours[1024], file[1200], out[1200], sw[32];
    int reps = argc > 1 ? atoi(argv[1]) : 21, q, ni, i;
    const int angles[2] = {30, 33};
    if (reps < 1) reps = 1;
    if (!mkdtemp(dir)) {
        perror("mkdtemp");
        return 1;
    }
    make_inputs(dir);
    if (tri) { /* Triangle's own sample beside its binary */
        char src[1100];
        FILE *fi, *fo;
        snprintf(src, sizeof src, "%.*s/A.poly", (int)(strrchr(tri, '/') ? strrchr(tri, '/') - tri : 1),
                 strrchr(tri, '/') ? tri : ".");
        snprintf(file, sizeof file, "%s/A.poly", dir);
        if ((fi = fopen(src, "r")) != NULL && (fo = fopen(file, "w")) != NULL) {
            int ch;
            while ((ch = fgetc(fi)) != EOF) fputc(ch, fo);
            fclose(fo);
        }
        if (fi) fclose(fi);
    } else {
        printf("WR_TRIANGLE not set: Triangle columns skipped\n");
    }
    snprintf(ours, sizeof ours, "%s", argv[0]);
    if (strrchr(ours, '/'))
        strcpy(strrchr(ours, '/') + 1, "wrinkle-triangulate");
    else
        strcpy(ours, "bin/wrinkle-triangulate");
    printf("%-7s %3s | %9s %9s %9s | %9s %9s %9s | %7s %7s | %9s\n", "input", "q", "tri cpu", "tri wall", "tri nv",
           "our cpu", "our wall", "our nv", "cpu x", "wall x", "lib cpu");
    for (ni = 0; ni < 3; ++ni)
        for (q = 0; q < 2; ++q) {
            double tc[256], tw[256], oc[256], ow[256], lc[256], c, w;
            int nt = -1, no = -1, ok = 1;
            wr_cdt_poly P;
            wr_diag dg;
            snprintf(file, sizeof file, "%s/%s.poly", dir, names[ni]);
            if (access(file, R_OK) != 0) continue;
            snprintf(sw, sizeof sw, "-Qpq%d", angles[q]);
            if (reps > 256) reps = 256;
            for (i = 0; i < reps && ok; ++i) {
                if (tri) ok &= run(tri, sw, file, &tc[i], &tw[i]);
                ok &= run(ours, sw, file, &oc[i], &ow[i]);
            }
            if (!ok) {
                printf("%-7s %3d | a run failed\n", names[ni], angles[q]);
                continue;
            }
            snprintf(out, sizeof out, "%s/%s.1.node", dir, names[ni]);
            no = first_int(out); /* both write name.1.node: ours ran last */
            if (tri) {
                run(tri, sw, file, &c, &w);
                nt = first_int(out);
            }
            if (wr_cdt_poly_read(file, &P, &dg) == WR_OK) {
                for (i = 0; i < reps; ++i) {
                    wr_cdt_input in;
                    wr_cdt_desc d;
                    wr_cdt_result r;
                    double c0 = self_cpu();
                    memset(&in, 0, sizeof in);
                    memset(&d, 0, sizeof d);
                    in.points = P.points;
                    in.n_points = P.n_points;
                    in.segments = P.segments;
                    in.n_segments = P.n_segments;
                    in.holes = P.holes;
                    in.n_holes = P.n_holes;
                    d.quality = 1;
                    d.min_angle_deg = angles[q];
                    d.split_intersections = 1;
                    wr_cdt_triangulate(&in, &d, &r, &dg);
                    lc[i] = self_cpu() - c0;
                    wr_cdt_free(&r);
                }
                wr_cdt_poly_free(&P);
            }
            if (tri)
                printf("%-7s %3d | %9.5f %9.5f %9d | %9.5f %9.5f %9d | %7.2f %7.2f | %9.6f\n", names[ni], angles[q],
                       median(tc, reps), median(tw, reps), nt, median(oc, reps), median(ow, reps), no,
                       median(oc, reps) / median(tc, reps), median(ow, reps) / median(tw, reps), median(lc, reps));
            else
                printf("%-7s %3d | %9s %9s %9s | %9.5f %9.5f %9d | %7s %7s | %9.6f\n", names[ni], angles[q], "-", "-", "-",
                       median(oc, reps), median(ow, reps), no, "-", "-", median(lc, reps));
        }
    return 0;
}
