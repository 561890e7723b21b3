/* probe_mesher_edges — where the mesher's edges are short: edge metric length / mean end sizing
 * (the report's ratio) split by where the edge's ends lie, on the meshes validate_meshing makes.
 *
 *   bin/probe_mesher_edges            every validate_meshing mesh: shares and means per class
 *   bin/probe_mesher_edges -v         the same plus histograms and the first ring's height
 *
 * Classes: II interior (neither end on a curve), CI curve-to-interior, CC curve-curve (both ends on
 * the outline, a hole or a constraint line; "curve" as the mesher's report counts it). First ring:
 * interior vertices with a curve neighbour; height = metric distance to the nearest constraint
 * segment / own sizing (an equilateral row on curve edges of length h has sqrt(3)/2 = 0.866).
 * A diagnosis tool (docs/notes-mesher.md), not a benchmark: run_all.sh runs only bin/bench_*. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "pattern.h"
#include "wrinkle/mesher.h"

#define NB 24 /* histogram bins of 0.05 on [0.4, 1.6) */

typedef struct cls {
    double sum;
    int32_t n, hist[NB];
} cls;

static void cls_add(cls *c, double r) {
    int b = (int)floor((r - 0.4) / 0.05);
    c->sum += r;
    ++c->n;
    c->hist[b < 0 ? 0 : (b >= NB ? NB - 1 : b)]++;
}

static void metric(const wr_mesher_result *r, int32_t v, const double *T, double *q) {
    const double *p = r->mesh.rest ? r->mesh.rest + 2 * v : r->mesh.pos + 3 * v;
    q[0] = T[0] * p[0] + T[1] * p[1];
    q[1] = T[2] * p[0] + T[3] * p[1];
}

static int32_t panel_of(const wr_mesher_result *r, int32_t v) {
    int32_t p;
    for (p = 0; p < r->n_panels; ++p)
        if (v >= r->panels[p].v_begin && v < r->panels[p].v_end) return p;
    return 0;
}

static double seg_dist(const double *a, const double *b, const double *q) {
    double ex = b[0] - a[0], ey = b[1] - a[1], l2 = ex * ex + ey * ey;
    double u = l2 > 0 ? ((q[0] - a[0]) * ex + (q[1] - a[1]) * ey) / l2 : 0.0;
    u = u < 0 ? 0 : (u > 1 ? 1 : u);
    return hypot(a[0] + u * ex - q[0], a[1] + u * ey - q[1]);
}

static void probe(const char *name, const wr_mesher_result *r, int verbose) {
    const wr_mesh *M = &r->mesh;
    char *bnd = (char *)calloc((size_t)M->nv, 1), *ring = (char *)calloc((size_t)M->nv, 1);
    cls c[3], cl[2]; /* cl: CI edges whose curve end is on a loop (0) / only on a constraint line (1) */
    int32_t e, j, k, v, nring = 0;
    double hsum = 0.0, hmin = HUGE_VAL;
    int32_t hh[NB];
    memset(c, 0, sizeof c);
    memset(cl, 0, sizeof cl);
    memset(hh, 0, sizeof hh);
    for (j = 0; j < M->n_loops; ++j)
        for (k = M->loop_start[j]; k < M->loop_start[j + 1]; ++k) bnd[M->loop_verts[k]] = 1;
    for (j = 0; j < 2 * r->n_constraint_segments; ++j)
        if (!bnd[r->constraint_segments[j]]) bnd[r->constraint_segments[j]] = 2;
    for (e = 0; e < M->ne; ++e) {
        int32_t a = M->edges[2 * e], b = M->edges[2 * e + 1];
        const double *T = r->panels[panel_of(r, a)].T;
        double qa[2], qb[2], ratio;
        metric(r, a, T, qa);
        metric(r, b, T, qb);
        ratio = hypot(qb[0] - qa[0], qb[1] - qa[1]) / (0.5 * (r->sizing[a] + r->sizing[b]));
        cls_add(&c[!bnd[a] && !bnd[b] ? 0 : (!bnd[a] || !bnd[b] ? 1 : 2)], ratio);
        if (!bnd[a] != !bnd[b]) {
            ring[bnd[a] ? b : a] = 1;
            cls_add(&cl[(bnd[a] | bnd[b]) == 2], ratio);
        }
    }
    for (v = 0; v < M->nv; ++v) {
        double q[2], d = HUGE_VAL, t;
        const double *T;
        int b;
        if (!ring[v]) continue;
        T = r->panels[panel_of(r, v)].T;
        metric(r, v, T, q);
        for (j = 0; j < r->n_constraint_segments; ++j) {
            double sa[2], sb[2];
            if (panel_of(r, r->constraint_segments[2 * j]) != panel_of(r, v)) continue;
            metric(r, r->constraint_segments[2 * j], T, sa);
            metric(r, r->constraint_segments[2 * j + 1], T, sb);
            d = fmin(d, seg_dist(sa, sb, q));
        }
        t = d / r->sizing[v];
        hsum += t;
        hmin = fmin(hmin, t);
        ++nring;
        b = (int)floor((t - 0.4) / 0.05);
        hh[b < 0 ? 0 : (b >= NB ? NB - 1 : b)]++;
    }
    {
        int32_t n = c[0].n + c[1].n + c[2].n;
        printf("%-22s nv %6d all %.3f | II %.3f (%2.0f%%)  CI %.3f (%2.0f%%: loop %.3f, line %.3f)  CC %.3f (%2.0f%%) | ring %5d height mean %.3f min %.3f\n",
               name, (int)M->nv, (c[0].sum + c[1].sum + c[2].sum) / n, c[0].sum / c[0].n, 100.0 * c[0].n / n,
               c[1].sum / c[1].n, 100.0 * c[1].n / n, cl[0].n ? cl[0].sum / cl[0].n : NAN,
               cl[1].n ? cl[1].sum / cl[1].n : NAN, c[2].n ? c[2].sum / c[2].n : NAN, 100.0 * c[2].n / n,
               (int)nring, hsum / nring, hmin);
    }
    if (verbose) {
        int b;
        printf("  ratio bin      II      CI      CC   CIloop  CIline | ring height\n");
        for (b = 0; b < NB; ++b)
            printf("  [%.2f,%.2f) %6.1f%% %6.1f%% %6.1f%% %6.1f%% %6.1f%% | %6.1f%%\n", 0.4 + 0.05 * b, 0.45 + 0.05 * b,
                   100.0 * c[0].hist[b] / (c[0].n ? c[0].n : 1), 100.0 * c[1].hist[b] / (c[1].n ? c[1].n : 1),
                   100.0 * c[2].hist[b] / (c[2].n ? c[2].n : 1), 100.0 * cl[0].hist[b] / (cl[0].n ? cl[0].n : 1),
                   100.0 * cl[1].hist[b] / (cl[1].n ? cl[1].n : 1), 100.0 * hh[b] / (nring ? nring : 1));
    }
    free(bnd);
    free(ring);
}

static int square(const char *name, double B, double E, double rf, int verbose) {
    double sq[8] = {0, 0, 0.25, 0, 0.25, 0.25, 0, 0.25};
    wr_pattern_panel pn;
    wr_pattern pat;
    wr_mesher_desc desc;
    wr_mesher_result r;
    wr_diag d;
    memset(&pn, 0, sizeof pn);
    memset(&pat, 0, sizeof pat);
    memset(&desc, 0, sizeof desc);
    pn.outer.xy = sq;
    pn.outer.n = 4;
    pn.fabric.B = B;
    pn.fabric.E = E;
    pat.panels = &pn;
    pat.n_panels = 1;
    desc.seed = getenv("PROBE_SEED") ? strtoull(getenv("PROBE_SEED"), NULL, 10) : 1;
    desc.radius_factor = rf;
    if (wr_mesher_run(&pat, &desc, &r, &d) != WR_OK) {
        fprintf(stderr, "%s: %s\n", name, d.message);
        return 1;
    }
    probe(name, &r, verbose);
    wr_mesher_free(&r);
    return 0;
}

static int example(const char *ex, double rf, int verbose) {
    wr_pattern_file pf;
    wr_mesher_result r;
    wr_diag d;
    char path[256];
    snprintf(path, sizeof path, "examples/%s.json", ex);
    if (wr_pattern_load(path, &pf, &d) != WR_OK) {
        fprintf(stderr, "%s\n", d.message);
        return 1;
    }
    pf.desc.seed = getenv("PROBE_SEED") ? strtoull(getenv("PROBE_SEED"), NULL, 10) : 1;
    pf.desc.radius_factor = rf;
    if (wr_mesher_run(&pf.pattern, &pf.desc, &r, &d) != WR_OK) {
        fprintf(stderr, "%s: %s\n", ex, d.message);
        wr_pattern_file_free(&pf);
        return 1;
    }
    probe(ex, &r, verbose);
    wr_mesher_free(&r);
    wr_pattern_file_free(&pf);
    return 0;
}

int main(int argc, char **argv) {
    static const char *ex[] = {"fig14_square_shirring", "fig08_shirring", "fig09_folding", "fig10_long_short_seam",
                               "fig11_down_filled", "fig13_elbow", "fig06_anisotropic", "garment_dress_shirred_waist",
                               "garment_down_coat"};
    static const struct { const char *n; double B, E; } sq[5] = {
        {"Table1 Dark Blue", 1.6e-4, 1.3e5}, {"Table1 Khaki", 2.0e-5, 5.0e5}, {"Table1 Green", 2.6e-6, 2.0e6},
        {"Table1 Light Blue", 3.2e-7, 8.2e6}, {"Table1 Rose", 4.0e-8, 1.6e7}};
    int verbose = argc > 1 && strcmp(argv[1], "-v") == 0, i, bad = 0;
    double rf = getenv("PROBE_RF") ? atof(getenv("PROBE_RF")) : 0.0; /* 0: the calibrated default */
    for (i = 0; i < 5; ++i) bad |= square(sq[i].n, sq[i].B, sq[i].E, rf, verbose && i == 1);
    for (i = 0; i < (int)(sizeof ex / sizeof ex[0]); ++i) bad |= example(ex[i], rf, verbose && (i == 2 || i == 0));
    return bad;
}
