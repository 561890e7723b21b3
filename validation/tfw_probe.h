/* tfw_probe.h — validation-side helpers shared by the TFW Sec. 6 drivers: the clamped base of the
 * strips and tubes (two clamp sets picked by one rest coordinate, the incremental statics solve),
 * the paper-literal / a = 0-at-the-clamps pair of TFW runs, a field's spectrum along a straight
 * rest-domain probe, the smooth Loop surface under a wrinkled one, the out-of-base (normal) wrinkle
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
#include "meshout.h"

#define TP_PI 3.14159265358979323846

/* ---- the clamped base of the strips and tubes (stretched sheet, sheared rectangle, cylinder) ----
 * held: vertices whose rest coordinate `axis` is <= lo + 1e-9; moved: those >= hi - 1e-9; flags: 1
 * on both (the TFW runs' a = 0 set). mo[0] holds the held set, mo[1] moves the moved set: the
 * caller sets its kind, axis/vec and amount. */
typedef struct tp_clamps {
    int32_t *held, *moved, n_held, n_moved;
    uint8_t *flags;
    wr_motion mo[2];
} tp_clamps;

static inline void tp_clamps_free(tp_clamps *c) {
    free(c->held);
    free(c->moved);
    free(c->flags);
    memset(c, 0, sizeof *c);
}

static inline wr_status tp_clamps_select(tp_clamps *c, const wr_mesh *m, int axis, double lo, double hi, wr_diag *d) {
    int32_t v;
    memset(c, 0, sizeof *c);
    c->held = (int32_t *)malloc(sizeof(int32_t) * ((size_t)m->nv + 1));
    c->moved = (int32_t *)malloc(sizeof(int32_t) * ((size_t)m->nv + 1));
    c->flags = (uint8_t *)calloc((size_t)m->nv + 1, 1);
    if (!c->held || !c->moved || !c->flags) {
        tp_clamps_free(c);
        return wr_fail(d, WR_ERR_NOMEM, -1, "clamps: out of memory");
    }
    for (v = 0; v < m->nv; ++v) {
        double q = m->pos[3 * v + axis];
        if (q < lo + 1e-9) c->held[c->n_held++] = v;
        if (q > hi - 1e-9) c->moved[c->n_moved++] = v;
        c->flags[v] = (uint8_t)(q < lo + 1e-9 || q > hi - 1e-9);
    }
    c->mo[0].kind = WR_MOTION_HOLD;
    c->mo[0].verts = c->held;
    c->mo[0].n_verts = c->n_held;
    c->mo[1].verts = c->moved;
    c->mo[1].n_verts = c->n_moved;
    return WR_OK;
}

/* x (nv*3) from the rest positions to the equilibrium under the clamps' two motions, in `steps`
 * load steps (statics.h wr_statics_solve_incremental; st NULL = defaults). */
static inline wr_status tp_clamped_solve(const wr_shell *sh, const wr_mesh *m, const tp_clamps *c, const wr_statics_desc *st,
                                         int32_t steps, double *x, wr_statics_stats *ss, wr_diag *d) {
    wr_statics_desc def;
    if (!st) {
        memset(&def, 0, sizeof def);
        st = &def;
    }
    memcpy(x, m->pos, sizeof(double) * 3 * (size_t)m->nv);
    return wr_statics_solve_incremental(sh, x, st, c->mo, 2, steps, ss, d);
}

/* The StVK reference with the Loop element (issue 15; --stvk-loop of the sheared rectangle and the
 * twisted cylinder). tp_loop_shell_desc: StVK membrane, Koiter bending on the Loop limit surface
 * (loop_element 1: faces with a boundary corner keep linear StVK + mid-edge bending). tp_loop_solve:
 * `steps` load steps under the clamps with the solver of the stretch scene's converged Loop runs
 * (validate_statics_loop, validate_statics_fig7): hybrid Newton (projected to 1e-3 of the tolerance,
 * then exact), affine predictor, absolute reference, grad_tol 1e-8, max_iter per increment, a seeded
 * normal kick of `perturb` [m] at every increment and statics.h's stability test after each (check 1,
 * perturb_each 1; the binary needs WR_USE_ARPACK); progress on stderr every 10 Newton steps, a summary
 * line at the end. */
typedef struct tp_loop_stats {
    int32_t newton, escapes, modes;
    double t; /* solve wall time [s] */
} tp_loop_stats;

static inline void tp_loop_shell_desc(double young, double nu, double h, wr_shell_desc *sd) {
    memset(sd, 0, sizeof *sd);
    sd->membrane = WR_MEMBRANE_STVK;
    sd->bending = WR_BENDING_MIDEDGE;
    sd->young = young, sd->poisson = nu, sd->thickness = h;
    sd->loop_element = 1;
}

static inline void tp__loop_progress(void *user, const wr_statics_stats *s) {
    (void)user;
    if (s->iterations % 10 == 0)
        fprintf(stderr, "    increment %d, Newton %d, |g|/ref %.1e, %.0f s\n", (int)s->increment, (int)s->iterations,
                s->grad_ref > 0 ? s->grad_norm / s->grad_ref : 0.0, s->t_total);
}

static inline wr_status tp_loop_solve(const wr_shell *sh, const wr_mesh *m, const tp_clamps *c, int32_t steps, double perturb,
                                      uint64_t seed, int32_t max_iter, double *x, tp_loop_stats *out, wr_diag *d) {
    wr_statics_desc st;
    wr_statics_stats ss;
    wr_status rs;
    double t0 = wr_time_seconds();
    memset(&st, 0, sizeof st);
    memset(&ss, 0, sizeof ss);
    st.stop.max_iter = max_iter;
    st.stop.grad_tol = 1e-8;
    st.start.perturb = perturb;
    st.start.seed = seed;
    st.hessian.projection = WR_PROJECT_FAST;
    st.increments.predictor = WR_STATICS_PREDICT_AFFINE;
    st.increments.absolute_reference = 1;
    st.increments.hybrid_switch = 1e-3;
    st.stability.check = 1;
    st.stability.perturb_each = 1;
    st.progress = tp__loop_progress;
    fprintf(stderr, "stvk-loop %d vertices: solving\n", (int)m->nv);
    rs = tp_clamped_solve(sh, m, c, &st, steps, x, &ss, d);
    out->t = wr_time_seconds() - t0;
    out->newton = ss.total_iterations;
    out->escapes = ss.stability_escapes;
    out->modes = ss.stability_modes;
    fprintf(stderr, "stvk-loop %d vertices: %s, %d Newton, %d escapes, %.0f s\n", (int)m->nv, wr_status_string(rs),
            (int)out->newton, (int)out->escapes, out->t);
    return rs;
}

/* TFW twice on one clamped base: the paper-literal run (no amplitude condition; the paper states
 * none) into r0, then a = 0 held on the clamped vertices (`flags`) into r; the rest of td is used for
 * both; one progress line each on stderr. td->a_zero_vertices is left at flags. */
static inline void tp_tfw_pair(const wr_mesh *m, const double *x, const wr_wf_material *mat, wr_tfw_desc *td,
                               const uint8_t *flags, wr_tfw_result *r0, wr_status *s0, wr_tfw_result *r, wr_status *s,
                               wr_diag *d) {
    td->a_zero_vertices = NULL;
    *s0 = wr_tfw_fields(m, x, mat, td, r0, d);
    fprintf(stderr, "tfw (no clamp condition): %s, SQP %d iterations\n", wr_status_string(*s0), r0->sqp.iterations);
    td->a_zero_vertices = flags;
    *s = wr_tfw_fields(m, x, mat, td, r, d);
    fprintf(stderr, "tfw: %s, SQP %d iterations, %.2f s\n", wr_status_string(*s), r->sqp.iterations, r->seconds_sqp);
}

/* A per-vertex field of mesh m (NULL: its z coordinate) at n points along the rest-domain segment
 * A→B: the points (pts, 2n, may be NULL), spacing ds, the samples (vals, n) and, when sr is not NULL,
 * their spectrum (spectrum.h defaults). */
static inline wr_status tp_line_field(const wr_mesh *m, const double *field, const double A[2], const double B[2], int32_t n,
                                      double *pts, double *ds, double *vals, wr_spectrum_result *sr, wr_diag *d) {
    wr_probe p;
    double *own_pts = pts ? NULL : (double *)malloc(sizeof(double) * 2 * (size_t)n);
    double *z = field ? NULL : (double *)malloc(sizeof(double) * ((size_t)m->nv + 1));
    int32_t v, nout = 0;
    wr_status s = WR_OK;
    if ((!pts && !own_pts) || (!field && !z)) s = wr_fail(d, WR_ERR_NOMEM, -1, "line probe: out of memory");
    if (!s && z) {
        for (v = 0; v < m->nv; ++v) z[v] = m->pos[3 * v + 2];
        field = z;
    }
    if (!pts) pts = own_pts;
    if (!s) s = wr_probe_create(&p, m, NULL, d);
    if (!s) {
        s = wr_path_segment(A, B, n, 0, pts, ds, d);
        if (!s) s = wr_probe_sample(&p, field, pts, n, vals, &nout, d);
        if (!s && sr) {
            memset(sr, 0, sizeof *sr);
            s = wr_spectrum_analyze(vals, n, *ds, 0, NULL, sr, NULL, 0, d);
        }
        wr_probe_free(&p);
    }
    free(own_pts);
    free(z);
    return s;
}

/* max |vals[i]| */
static inline double tp_max_abs(const double *vals, int32_t n) {
    double mx = 0.0;
    int32_t i;
    for (i = 0; i < n; ++i) mx = fmax(mx, fabs(vals[i]));
    return mx;
}

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
 * equator from its inner one); the value at a cut point is the per-vertex `field` interpolated
 * along the cut edge, or (field NULL) the radial component about the axis of disp − pos, both
 * surfaces interpolated at the cut (disp: the wrinkled surface, same topology: the twisted tube's
 * radial wrinkle displacement); resample the cut at n equal angles about that axis (linear,
 * periodic). *n_pts = cut points used. Use tp_ring or tp_ring_radial. */
static inline wr_status tp__ring(const wr_mesh *m, const double *pos, const double *field, const double *disp, double z0,
                                 double cx, double cy, double rho_min, int32_t n, double *out, int32_t *n_pts, wr_diag *d) {
    tp_cut *pts = (tp_cut *)malloc(sizeof(tp_cut) * (size_t)m->ne + 16);
    int32_t e, np = 0, i, j;
    if (!pts) return wr_fail(d, WR_ERR_NOMEM, -1, "ring: out of memory");
    for (e = 0; e < m->ne; ++e) {
        int32_t a = m->edges[2 * e], b = m->edges[2 * e + 1];
        double za = pos[3 * a + 2] - z0, zb = pos[3 * b + 2] - z0, t, qx, qy, px, py, rho;
        if ((za < 0.0) == (zb < 0.0)) continue;
        t = za / (za - zb);
        qx = pos[3 * a] + t * (pos[3 * b] - pos[3 * a]);
        qy = pos[3 * a + 1] + t * (pos[3 * b + 1] - pos[3 * a + 1]);
        px = qx - cx, py = qy - cy;
        rho = hypot(px, py);
        if (!(rho >= rho_min) || !(rho > 0.0)) continue;
        pts[np].th = atan2(py, px);
        if (field) {
            pts[np].val = field[a] + t * (field[b] - field[a]);
        } else {
            double wx = disp[3 * a] + t * (disp[3 * b] - disp[3 * a]);
            double wy = disp[3 * a + 1] + t * (disp[3 * b + 1] - disp[3 * a + 1]);
            pts[np].val = ((wx - qx) * px + (wy - qy) * py) / rho;
        }
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

/* the plane cut of `pos` at z = z0 with the per-vertex field interpolated (tp__ring) */
static inline wr_status tp_ring(const wr_mesh *m, const double *pos, const double *field, double z0, double cx, double cy,
                                double rho_min, int32_t n, double *out, int32_t *n_pts, wr_diag *d) {
    return tp__ring(m, pos, field, NULL, z0, cx, cy, rho_min, n, out, n_pts, d);
}

/* the plane cut of `pos` at z = z0 with the radial component of disp − pos about the axis through
 * (cx, cy) (tp__ring) */
static inline wr_status tp_ring_radial(const wr_mesh *m, const double *pos, const double *disp, double z0, double cx,
                                       double cy, double rho_min, int32_t n, double *out, int32_t *n_pts, wr_diag *d) {
    return tp__ring(m, pos, NULL, disp, z0, cx, cy, rho_min, n, out, n_pts, d);
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

/* A probe profile figure: <results>/<stem>_probe.dat (x[i]·1e3, y[i]·1e3: mm), <figures>/<stem>.gp
 * (900 × 450, one line titled `legend`, the key below the frame) and <figures>/<stem>.png by gnuplot, added to v on success. */
static inline void tp_profile_figure(wr_vres *v, const char *stem, const double *x, int32_t xstride, const double *y,
                                     int32_t n, const char *xlabel, const char *ylabel, const char *title,
                                     const char *legend, const char *caption) {
    char dat[700], gp[700], png[700], cmd[1600], rel[300];
    wr_afile f;
    wr_diag d;
    int32_t i;
    memset(&d, 0, sizeof d);
    snprintf(dat, sizeof dat, "%s/%s_probe.dat", wr_vres_dir(), stem);
    snprintf(gp, sizeof gp, "%s/../figures/%s.gp", wr_vres_dir(), stem);
    snprintf(png, sizeof png, "%s/../figures/%s.png", wr_vres_dir(), stem);
    if (wr_afile_open(&f, dat, &d) != WR_OK) return;
    for (i = 0; i < n; ++i) fprintf(f.fp, "%.6g %.6g\n", 1e3 * x[(size_t)xstride * i], 1e3 * y[i]);
    if (wr_afile_commit(&f, &d) != WR_OK || wr_afile_open(&f, gp, &d) != WR_OK) return;
    fprintf(f.fp, "set terminal pngcairo size 900,450\nset output '%s'\n", png);
    fprintf(f.fp, "set xlabel '%s'\nset ylabel '%s'\n", xlabel, ylabel);
    fprintf(f.fp, "set title '%s'\n", title);
    fprintf(f.fp, "set key below\n"); /* a key inside the frame covered the end crests */
    fprintf(f.fp, "plot '%s' w l t '%s'\n", dat, legend);
    if (wr_afile_commit(&f, &d) != WR_OK) return;
    snprintf(cmd, sizeof cmd, "gnuplot '%s' 2>/dev/null", gp);
    snprintf(rel, sizeof rel, "figures/%s.png", stem);
    if (system(cmd) == 0)
        wr_vres_figure(v, rel, caption);
    else
        wr_vres_note(v, "gnuplot failed; figure not drawn");
}

/* A rendered picture of a TFW result (render.h through meshout.h: the coarse base with its edges
 * beside the wrinkled surface coloured by wrinkle height) as <figures>/<stem>.png, added to v. */
static inline void tp_render_figure(wr_vres *v, const char *stem, const wr_mesh *base, const double *x,
                                    const wr_wf_material *mat, const wr_tfw_desc *td, const wr_tfw_result *r,
                                    const char *caption) {
    char png[700], rel[300];
    wr_diag d;
    memset(&d, 0, sizeof d);
    snprintf(png, sizeof png, "%s/../figures/%s.png", wr_vres_dir(), stem);
    snprintf(rel, sizeof rel, "figures/%s.png", stem);
    if (wr_meshout_tfw_png(png, base, x, mat, td, r, &d) == WR_OK)
        wr_vres_figure(v, rel, caption);
    else {
        char msg[sizeof d.message + 32];
        snprintf(msg, sizeof msg, "rendered picture not drawn: %s", d.message);
        wr_vres_note(v, msg);
    }
}

/* The solver rows every TFW Sec. 6 driver reports, in one place: the base's Newton steps and time
 * (paper values paper_newton, paper_base_s, NAN where the paper prints none), the SQP's iterations
 * (paper_sqp), residuals, folds, rejections and escapes, the TFW time (paper_tfw_s), and the notes on
 * the SQP stop rule and on phase folds. base_newton / t_base / load_steps: the caller's TFT base solve. */
static inline void tp_solver_rows(wr_vres *v, const wr_tfw_result *r, wr_status s_tfw, int32_t base_newton, double t_base,
                                  int32_t load_steps, double paper_base_s, double paper_newton, double paper_sqp,
                                  double paper_tfw_s) {
    char buf[300];
    snprintf(buf, sizeof buf, "TFT base time (%d load step%s)", (int)load_steps, load_steps == 1 ? "" : "s");
    wr_vres_info(v, buf, "s", paper_base_s, t_base);
    wr_vres_info(v, "TFT base Newton steps (all load steps)", "", paper_newton, base_newton);
    wr_vres_info(v, "SQP iterations (accepted steps, both solves if unfolded)", "", paper_sqp, r->sqp.iterations);
    wr_vres_info(v, "SQP iterations of the first solve", "", paper_sqp, r->sqp_first.iterations);
    wr_vres_info(v, "SQP relative KKT residual at the end of the first solve", "", NAN,
                 r->sqp_first.kkt0 > 0.0 ? r->sqp_first.kkt / r->sqp_first.kkt0 : NAN);
    wr_vres_info(v, "phase-fold edges after the first solve (wr_wf_count_folds)", "", NAN, r->n_folds_first);
    wr_vres_info(v, "phase-fold edges in the returned fields", "", 0, r->n_folds);
    wr_vres_info(v, "SQP rejected trial steps", "", NAN, r->sqp.n_rejected);
    wr_vres_info(v, "SQP escapes from a = 0", "", NAN, r->sqp.n_escapes);
    wr_vres_info(v, "SQP relative KKT residual at the end (of the returned solve)", "", NAN, r->sqp.kkt / r->sqp.kkt0);
    wr_vres_info(v, "SQP scaled KKT residual at the end (absolute, a/a_ref and E/E_ref units)", "", NAN, r->sqp.kkt);
    wr_vres_info(v, "TFW time (E.2 to E.5)", "s", paper_tfw_s, r->seconds_total);
    wr_vres_info(v, "  of which SQP", "s", NAN, r->seconds_sqp);
    snprintf(buf, sizeof buf, "SQP stop rule %d (1 energy/round-off, 2 KKT, 3 step, 4 max-iter, 5 no acceptable step); status %s.",
             (int)r->sqp.stop, wr_status_string(s_tfw));
    wr_vres_note(v, buf);
    wr_vres_note(v, "Phase folds: E_wf only sees dphi through even terms, so a curl-free omega whose dphi flips sign between "
                    "neighbouring faces (phi zig-zagging at ~2 base edges per wavelength) costs almost nothing and the SQP can "
                    "end there; the Loop-smoothed phase then draws a wrong surface. wr_tfw_fields counts such edges, "
                    "re-orients dphi consistently (wr_wf_unfold) and solves again; the rows above give both solves.");
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
