/* tfw_probe.h — validation-side helpers shared by the TFW Sec. 6 drivers (sphere drape, inflatables,
 * cross-check): the smooth Loop surface under a wrinkled one, the out-of-base (normal) wrinkle
 * displacement, a plane-cut ring signal resampled at equal angles (for sewn meshes, whose two panels
 * overlap in the rest plane so a rest-domain probe circle is ambiguous), a small figure writer and
 * the ring wave count. Static functions only (each driver is its own program). */
#ifndef WRINKLE_VALIDATION_TFW_PROBE_H
#define WRINKLE_VALIDATION_TFW_PROBE_H

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "wrinkle/wrinkle.h"
#include "wrinkle/tfw.h"
#include "vresult.h"

#define TP_PI 3.14159265358979323846

/* The smooth Loop surface of the base (a = 0, same W and phase, same levels): the wrinkled mesh
 * minus Eq. 19's displacement, vertex for vertex. */
static inline wr_status tp_smooth_surface(const wr_mesh *m, const double *x, const wr_wf_material *mat, const wr_tfw_result *r,
                                   const wr_wf_upsample_desc *ud, wr_mesh *sm, wr_diag *d) {
    wr_wf wf;
    double *zero = (double *)calloc((size_t)m->nv, sizeof(double));
    wr_status s;
    memset(sm, 0, sizeof *sm);
    if (!zero) return wr_fail(d, WR_ERR_NOMEM, -1, "smooth surface: out of memory");
    s = wr_wf_create(&wf, m, x, mat, d);
    if (!s) {
        wr_wf_set_wrinkle_free(&wf, r->wfree);
        s = wr_wf_upsample(&wf, zero, r->phi, ud, sm, NULL, d);
        wr_wf_free(&wf);
    }
    free(zero);
    return s;
}

/* out[v] = (wrinkled − smooth)·n̂_smooth(v): the wrinkle's displacement off the base [m]. */
static inline void tp_normal_disp(const wr_mesh *fine, const wr_mesh *sm, double *out) {
    double *n = (double *)malloc(sizeof(double) * 3 * (size_t)sm->nv);
    int32_t v;
    if (!n) return;
    wr_mesh_vertex_normals(sm, n);
    for (v = 0; v < sm->nv; ++v) {
        const double *w = fine->pos + 3 * v, *p = sm->pos + 3 * v, *nn = n + 3 * v;
        out[v] = (w[0] - p[0]) * nn[0] + (w[1] - p[1]) * nn[1] + (w[2] - p[2]) * nn[2];
    }
    free(n);
}

typedef struct tp_cut {
    double th, val;
} tp_cut;

static inline int tp_cmp_cut(const void *a, const void *b) {
    double x = ((const tp_cut *)a)->th, y = ((const tp_cut *)b)->th;
    return x < y ? -1 : x > y;
}

/* Cut the surface `pos` (nv*3, e.g. the smooth Loop surface) by the plane z = z0; keep cut points
 * whose distance from the z axis through (cx, cy) is >= rho_min (separates the torus' outer
 * equator from its inner one); interpolate the per-vertex field along the cut edges; resample the
 * cut at n equal angles about that axis (linear, periodic). *n_pts = cut points used. */
static inline wr_status tp_ring(const wr_mesh *m, const double *pos, const double *field, double z0, double cx, double cy,
                         double rho_min, int32_t n, double *out, int32_t *n_pts, wr_diag *d) {
    tp_cut *pts = (tp_cut *)malloc(sizeof(tp_cut) * (size_t)m->ne + 16);
    int32_t e, np = 0, i, j;
    if (!pts) return wr_fail(d, WR_ERR_NOMEM, -1, "ring: out of memory");
    for (e = 0; e < m->ne; ++e) {
        int32_t a = m->edges[2 * e], b = m->edges[2 * e + 1];
        double za = pos[3 * a + 2] - z0, zb = pos[3 * b + 2] - z0, t, px, py;
        if ((za < 0.0) == (zb < 0.0)) continue;
        t = za / (za - zb);
        px = pos[3 * a] + t * (pos[3 * b] - pos[3 * a]) - cx;
        py = pos[3 * a + 1] + t * (pos[3 * b + 1] - pos[3 * a + 1]) - cy;
        if (!(hypot(px, py) >= rho_min) || !(hypot(px, py) > 0.0)) continue;
        pts[np].th = atan2(py, px);
        pts[np].val = field[a] + t * (field[b] - field[a]);
        ++np;
    }
    if (n_pts) *n_pts = np;
    if (np < 8) {
        free(pts);
        return wr_fail(d, WR_ERR_GEOMETRY, -1, "ring: only %d cut points at z = %g", (int)np, z0);
    }
    qsort(pts, (size_t)np, sizeof(tp_cut), tp_cmp_cut);
    for (i = 0, j = 0; i < n; ++i) {
        double th = -TP_PI + 2.0 * TP_PI * i / n, t0, t1, v0, v1;
        while (j < np && pts[j].th < th) ++j;
        if (j == 0 || j == np) { /* wrap-around neighbours */
            t0 = pts[np - 1].th - 2.0 * TP_PI;
            t1 = pts[0].th;
            if (j == np) {
                t0 = pts[np - 1].th;
                t1 = pts[0].th + 2.0 * TP_PI;
            }
            v0 = pts[np - 1].val;
            v1 = pts[0].val;
        } else {
            t0 = pts[j - 1].th;
            v0 = pts[j - 1].val;
            t1 = pts[j].th;
            v1 = pts[j].val;
        }
        out[i] = t1 > t0 ? v0 + (v1 - v0) * (th - t0) / (t1 - t0) : v0;
    }
    free(pts);
    return WR_OK;
}

/* Periodic analysis of a closed signal of length `perimeter`; harmonics below kmin are excluded
 * (max_wavelength = perimeter/kmin; kmin <= 1: the spectrum default). */
static inline wr_status tp_analyze_closed(const double *sig, int32_t n, double perimeter, int32_t kmin, wr_spectrum_result *sr,
                                   wr_diag *d) {
    wr_spectrum_desc sd;
    memset(&sd, 0, sizeof sd);
    if (kmin > 1) sd.max_wavelength = perimeter / kmin * (1.0 + 1e-9);
    return wr_spectrum_analyze(sig, n, perimeter / n, 1, &sd, sr, NULL, 0, d);
}

/* Writes <results>/<stem>.dat (columns given by the caller through fp), <figures>/<stem>.gp with
 * `plot_cmd` (may use %s = the .dat path twice at most via the caller's own formatting) and runs
 * gnuplot; adds the figure to v on success. */
static inline void tp_figure(wr_vres *v, const char *stem, const char *gp_body, const char *caption) {
    char gp[700], png[700], cmd[1600], rel[300];
    wr_afile f;
    wr_diag d;
    memset(&d, 0, sizeof d);
    snprintf(gp, sizeof gp, "%s/../figures/%s.gp", wr_vres_dir(), stem);
    snprintf(png, sizeof png, "%s/../figures/%s.png", wr_vres_dir(), stem);
    if (wr_afile_open(&f, gp, &d) != WR_OK) {
        wr_vres_note(v, "figure script could not be written");
        return;
    }
    fprintf(f.fp, "set terminal pngcairo size 1000,%d\nset output '%s'\n", 420, png);
    fputs(gp_body, f.fp);
    if (wr_afile_commit(&f, &d) != WR_OK) return;
    snprintf(cmd, sizeof cmd, "gnuplot '%s' 2>/dev/null", gp);
    snprintf(rel, sizeof rel, "figures/%s.png", stem);
    if (system(cmd) == 0)
        wr_vres_figure(v, rel, caption);
    else
        wr_vres_note(v, "gnuplot failed; figure not drawn");
}

/* Circulation of the one-form ω around a closed vertex loop (loop[0..n), consecutive vertices joined
 * by mesh edges) divided by 2π: the number of wrinkle waves crossing the loop (TFW: dφ = ω).
 * NaN when two consecutive loop vertices share no edge. */
static inline double tp_circulation(const wr_mesh *m, const double *omega, const int32_t *loop, int32_t n) {
    double circ = 0.0;
    int32_t i;
    for (i = 0; i < n; ++i) {
        int32_t a = loop[i], b = loop[(i + 1) % n], k, found = 0;
        for (k = m->vf_start[a]; k < m->vf_start[a + 1] && !found; ++k) {
            int32_t f = m->vf[k], q;
            for (q = 0; q < 3; ++q) {
                int32_t e = m->face_edges[3 * f + q];
                if ((m->edges[2 * e] == a && m->edges[2 * e + 1] == b) || (m->edges[2 * e] == b && m->edges[2 * e + 1] == a)) {
                    circ += m->edges[2 * e] == a ? omega[e] : -omega[e];
                    found = 1;
                    break;
                }
            }
        }
        if (!found) return NAN;
    }
    return fabs(circ) / (2.0 * TP_PI);
}

#endif
