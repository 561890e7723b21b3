/* validate_tfw_sphere_drape — TFW Sec. 6 "Sphere Drape" (Fig. 5): a 1 m × 1 m square sheet draped
 * by gravity on a sphere of radius 0.2 m; density 200 kg/m³, ν = 0.3, E = 0.1 MPa, h = 1 mm.
 * Base: TFT membrane + quadratic bending (TFW Sec. 4.1) on a 40 × 40 union-jack grid (1681 vertices,
 * the paper's "1.6k") through statics.h with the sphere obstacle (frictionless IPC-style barrier).
 * A frictionless sheet on a sphere is a saddle (it slides off), so the centre vertex is pinned 1 mm
 * above the sphere's top, inside the barrier's d̂ = 2 mm. Gravity is ramped in 4 increments (each
 * warm-started). Then wr_tfw_fields (Loop level 3).
 * Count: on the rest domain, circles of radius 0.30 / 0.35 / 0.40 m about the sheet's centre; the
 * field is the wrinkled surface's displacement off the smooth Loop base along its normal; periodic
 * FFT (spectrum.h), count = integer harmonic of the peak, amplitude = (max − min)/2.
 * StVK reference: StVK membrane + dihedral bending (shell.h WR_BENDING_DIHEDRAL: the mid-edge
 * Koiter energy on atan2 hinge angles, finite through 180° folds) on a 60 × 60 grid (3721 vertices), same pin,
 * started from the TFT base interpolated onto the fine grid (TFW App. F.4 initialises StVK from the
 * TFT base; from the flat sheet it did not finish in 4 minutes here), full gravity, 1e-4 m seeded
 * kick, at most REF_MAX_ITER = 160 Newton steps (an 80 × 80 run took 164 steps and 330 s and stalled
 * in the line search at |g|/ref = 22); counted on the same circles from the distance to the
 * sphere's vertical axis (no base surface exists there), harmonics below 10 excluded (the square's
 * 4-fold base shape puts power at 4 and 8); the same ρ measure is applied to the TFW surface.
 * With mid-edge bending the reference stalled in the line search at 60 × 60 (folds closing onto single
 * edges, where the mid-edge normal is singular); with dihedral bending it keeps descending but does
 * not reach the gradient tolerance within REF_MAX_ITER, and 60 × 60 resolves only ~2.7 edges per TFW
 * wave; the driver reports the fold angles and the TFW wavelength in reference edges (result notes).
 * Paper: no wrinkle count or amplitude in the text (Fig. 5 images only; ARCSim 32k, MD 72k vertices;
 * TFW 46 SQP iterations, 15.06 s). Pass bands: none (issue 6: reported beside the StVK reference
 * where one converges); sanity checks: base converged, no vertex inside the sphere.
 * Output: validation/results/tfw_sphere_drape.json, figures/tfw_sphere_drape.png. */
#include "tfw_probe.h"
#include "vargs.h"

#define SIDE 1.0
#define RBALL 0.2
#define NBASE 40
#define NREF 60
#define NSAMP 2048
#define NRAD 3
#define GRAVITY_STEPS 4
#define KMIN_RHO 10
/* Newton budget of the StVK reference (80 x 80 from the TFT base: 164 steps, 330 s, line-search stall
 * at |g|/ref 22 -- over this driver's time box) */
#define REF_MAX_ITER 160

static const double radii[NRAD] = {0.30, 0.35, 0.40};

typedef struct solve_out {
    wr_status st;
    int32_t iters, nv, fails, stop, n_contacts;
    double seconds, min_dist, grad_rel, zmin, ccd_alpha_min;
} solve_out;

/* Square sheet centred over the ball, 5 mm above its top; centre vertex pinned 1 mm above the top. *
 * init NULL: flat start 5 mm above the ball, gravity ramped in GRAVITY_STEPS increments (the TFT
 * base). init != NULL (nv*3): start there (the StVK reference, started from the TFT base as TFW
 * App. F.4 does), full gravity in one solve. */
static void drape(wr_mesh *m, int32_t n, wr_membrane_model mem, wr_bending_model ben, const double *init, double *x,
                  solve_out *o) {
    wr_shell sh;
    wr_shell_desc sd;
    wr_statics_desc st;
    wr_statics_stats ss;
    wr_obstacle ball;
    wr_diag d;
    uint8_t *fixed = (uint8_t *)calloc((size_t)m->nv, 1);
    int32_t v, c = (n / 2) * (n + 1) + n / 2, k;
    double t0 = wr_time_seconds();
    memset(o, 0, sizeof *o);
    o->nv = m->nv;
    memset(&sd, 0, sizeof sd);
    sd.membrane = mem;
    sd.bending = ben;
    sd.young = 1e5;
    sd.poisson = 0.3;
    sd.thickness = 1e-3;
    sd.density = 200.0;
    if ((o->st = wr_shell_create(&sh, m, &sd, &d)) != WR_OK) {
        free(fixed);
        return;
    }
    for (v = 0; v < m->nv; ++v) {
        x[3 * v] = m->rest[2 * v] - 0.5 * SIDE;
        x[3 * v + 1] = m->rest[2 * v + 1] - 0.5 * SIDE;
        x[3 * v + 2] = RBALL + 5e-3;
    }
    fixed[c] = 1;
    x[3 * c + 2] = RBALL + 1e-3;
    memset(&ball, 0, sizeof ball);
    ball.kind = WR_OBSTACLE_SPHERE;
    ball.radius = RBALL;
    if (init) {
        /* interpolated coarse positions can sit inside the ball by the coarse chord's sagitta: push
         * such vertices out to half the barrier width along the sphere normal */
        memcpy(x, init, sizeof(double) * 3 * (size_t)m->nv);
        for (v = 0; v < m->nv; ++v) {
            double g[3], dist = wr_obstacle_distance(&ball, x + 3 * v, g);
            int q;
            if (!fixed[v] && dist < 1e-3)
                for (q = 0; q < 3; ++q) x[3 * v + q] += (1e-3 - dist) * g[q];
        }
    }
    for (k = init ? GRAVITY_STEPS : 1; k <= GRAVITY_STEPS; ++k) {
        memset(&st, 0, sizeof st);
        st.loads.fixed = fixed;
        st.loads.gravity[2] = -9.81 * k / GRAVITY_STEPS;
        st.contact.obstacles = &ball;
        st.contact.n_obstacles = 1;
        st.contact.dhat = 2e-3;
        st.stop.max_iter = init ? REF_MAX_ITER : 300;
        if (k == 1 || init) {
            st.start.perturb = 1e-4; /* seeded kick off the flat start / the symmetric TFT base */
            st.start.seed = 11;
        }
        o->st = wr_statics_solve(&sh, x, &st, &ss, &d);
        o->iters += ss.iterations;
        if (o->st) ++o->fails;
        fprintf(stderr, "  %s %d v, g step %d: %s, %d Newton, |g|/ref %.1e, %.1f s\n", mem == WR_MEMBRANE_TFT ? "TFT" : "StVK",
                (int)m->nv, (int)k, wr_status_string(o->st), (int)ss.iterations, ss.grad_norm / ss.grad_ref,
                wr_time_seconds() - t0);
    }
    o->stop = (int32_t)ss.stop;
    o->min_dist = ss.min_distance;
    o->n_contacts = ss.n_contacts;
    o->ccd_alpha_min = ss.ccd_alpha_min;
    o->grad_rel = ss.grad_ref > 0 ? ss.grad_norm / ss.grad_ref : NAN;
    o->zmin = 1e300;
    for (v = 0; v < m->nv; ++v) o->zmin = fmin(o->zmin, x[3 * v + 2]);
    o->seconds = wr_time_seconds() - t0;
    wr_shell_free(&sh);
    free(fixed);
}

/* Sample per-vertex field on a rest-domain circle about the sheet centre; NaN-free or error. */
static wr_status circle_count(const wr_mesh *m, const double *field, double r, int32_t kmin, wr_spectrum_result *sr,
                              double *sig, wr_diag *d) {
    wr_probe p;
    double c[2] = {0.5 * SIDE, 0.5 * SIDE}, *pts = (double *)malloc(sizeof(double) * 2 * NSAMP), ds;
    int32_t nout = 0;
    wr_status s;
    if (!pts) return WR_ERR_NOMEM;
    s = wr_probe_create(&p, m, NULL, d);
    if (!s) s = wr_path_circle(c, r, NSAMP, pts, &ds, d);
    if (!s) s = wr_probe_sample(&p, field, pts, NSAMP, sig, &nout, d);
    if (!s && nout) s = wr_fail(d, WR_ERR_GEOMETRY, nout, "circle r = %g: %d samples outside", r, (int)nout);
    if (!s) s = tp_analyze_closed(sig, NSAMP, 2.0 * TP_PI * r, kmin, sr, d);
    wr_probe_free(&p);
    free(pts);
    return s;
}

/* Largest angle between the normals of two faces sharing an interior edge [deg], and how many
 * interior edges exceed FOLD_DEG: 180 deg means two faces folded flat onto each other, where the
 * mid-edge normal (the normalised sum of the two face normals, shell.h) is undefined -- the
 * mid-edge bending energy and its gradient grow without bound as a fold closes to one edge. */
#define FOLD_DEG 170.0
static void fold_stats(const wr_mesh *m, const double *x, double *maxdeg, int32_t *nfold) {
    int32_t e, k, q;
    *maxdeg = 0.0;
    *nfold = 0;
    for (e = 0; e < m->ne; ++e) {
        double nn[2][3], c, l;
        if (m->edge_faces[2 * e] < 0 || m->edge_faces[2 * e + 1] < 0) continue;
        for (k = 0; k < 2; ++k) {
            const int32_t *f = m->faces + 3 * m->edge_faces[2 * e + k];
            double u[3], w[3];
            for (q = 0; q < 3; ++q) {
                u[q] = x[3 * f[1] + q] - x[3 * f[0] + q];
                w[q] = x[3 * f[2] + q] - x[3 * f[0] + q];
            }
            nn[k][0] = u[1] * w[2] - u[2] * w[1];
            nn[k][1] = u[2] * w[0] - u[0] * w[2];
            nn[k][2] = u[0] * w[1] - u[1] * w[0];
            l = sqrt(nn[k][0] * nn[k][0] + nn[k][1] * nn[k][1] + nn[k][2] * nn[k][2]);
            for (q = 0; q < 3; ++q) nn[k][q] /= l > 0 ? l : 1.0;
        }
        c = nn[0][0] * nn[1][0] + nn[0][1] * nn[1][1] + nn[0][2] * nn[1][2];
        c = 180.0 / TP_PI * acos(fmax(-1.0, fmin(1.0, c)));
        *maxdeg = fmax(*maxdeg, c);
        if (c > FOLD_DEG) ++*nfold;
    }
}

/* Length [m] of the deformed image of the rest circle of radius r (positions x on mesh m, sampled at
 * NSAMP points): the drape's perimeter there, over which the waves are spread. */
static double ring_length(const wr_mesh *m, const double *x, double r, wr_diag *d) {
    wr_probe p;
    double c[2] = {0.5 * SIDE, 0.5 * SIDE}, ds, len = NAN, *pts = (double *)malloc(sizeof(double) * 2 * NSAMP),
           *f = (double *)malloc(sizeof(double) * (size_t)m->nv), *xs = (double *)malloc(sizeof(double) * 3 * NSAMP);
    int32_t nout = 0, q, i;
    if (pts && f && xs && wr_probe_create(&p, m, NULL, d) == WR_OK) {
        int ok = wr_path_circle(c, r, NSAMP, pts, &ds, d) == WR_OK;
        for (q = 0; ok && q < 3; ++q) {
            for (i = 0; i < m->nv; ++i) f[i] = x[3 * i + q];
            ok = wr_probe_sample(&p, f, pts, NSAMP, xs + (size_t)q * NSAMP, &nout, d) == WR_OK && nout == 0;
        }
        if (ok) {
            len = 0.0;
            for (i = 0; i < NSAMP; ++i) {
                int32_t j = (i + 1) % NSAMP;
                len += sqrt((xs[j] - xs[i]) * (xs[j] - xs[i]) + (xs[NSAMP + j] - xs[NSAMP + i]) * (xs[NSAMP + j] - xs[NSAMP + i]) +
                            (xs[2 * NSAMP + j] - xs[2 * NSAMP + i]) * (xs[2 * NSAMP + j] - xs[2 * NSAMP + i]));
            }
        }
        wr_probe_free(&p);
    }
    free(pts);
    free(f);
    free(xs);
    return len;
}

static void rho_field(const wr_mesh *m, double *out) {
    int32_t v;
    for (v = 0; v < m->nv; ++v) out[v] = hypot(m->pos[3 * v], m->pos[3 * v + 1]);
}

/* Everything the two solves and the two analyses produce, read by the report stages. */
typedef struct drape_case {
    wr_mesh m, mref, sm; /* TFT base grid, StVK reference grid, smooth Loop base surface */
    wr_tfw_result r;
    solve_out ob, oref;
    wr_spectrum_result sr_n[NRAD], sr_rho[NRAD], sr_ref[NRAD];
    wr_status s_n[NRAD], s_rho[NRAD], s_ref[NRAD], s_tfw;
    double *x, *xref, *sig_n[NRAD], *sig_r;
    double len_base[NRAD], len_ref[NRAD], fold_max, amax;
    int32_t n_fold;
} drape_case;

static int case_init(drape_case *c, wr_diag *d) {
    int i;
    memset(c, 0, sizeof *c);
    c->s_tfw = WR_ERR_INVALID_ARG;
    c->fold_max = NAN;
    c->n_fold = -1;
    for (i = 0; i < NRAD; ++i) {
        c->s_n[i] = c->s_rho[i] = c->s_ref[i] = WR_ERR_INVALID_ARG;
        c->len_base[i] = c->len_ref[i] = NAN;
        c->sig_n[i] = (double *)calloc(NSAMP, sizeof(double));
    }
    if (wr_mesh_rectangle(&c->m, SIDE, SIDE, NBASE, NBASE, d) || wr_mesh_rectangle(&c->mref, SIDE, SIDE, NREF, NREF, d))
        return 0;
    c->x = (double *)malloc(sizeof(double) * 3 * c->m.nv);
    c->xref = (double *)malloc(sizeof(double) * 3 * c->mref.nv);
    c->sig_r = (double *)calloc(NSAMP, sizeof(double));
    return c->x && c->xref && c->sig_r;
}

static void case_free(drape_case *c) {
    int i;
    wr_mesh_free(&c->sm);
    wr_tfw_result_free(&c->r);
    wr_mesh_free(&c->m);
    wr_mesh_free(&c->mref);
    free(c->x);
    free(c->xref);
    free(c->sig_r);
    for (i = 0; i < NRAD; ++i) free(c->sig_n[i]);
}

/* The TFT base (gravity ramped), then TFW on it (Loop level 3) and the counts on the three circles:
 * from the normal displacement off the smooth base, and from rho (the distance to the vertical axis). */
static void tfw_on_base(drape_case *c, wr_diag *d) {
    wr_wf_material mat;
    wr_tfw_desc td;
    wr_mesh based; /* the base as a mesh with the rest coordinates of m */
    int i;
    drape(&c->m, NBASE, WR_MEMBRANE_TFT, WR_BENDING_QUADRATIC, NULL, c->x, &c->ob);
    mat.young = 1e5;
    mat.poisson = 0.3;
    mat.thickness = 1e-3;
    memset(&td, 0, sizeof td);
    td.upsample.levels = 3;
    if (wr_mesh_create(&based, c->m.nv, c->x, c->m.rest, c->m.nf, c->m.faces, d) == WR_OK) {
        c->s_tfw = wr_tfw_fields(&based, c->x, &mat, &td, &c->r, d);
        if ((c->s_tfw == WR_OK || c->s_tfw == WR_ERR_NOT_CONVERGED) &&
            tp_smooth_surface(&based, c->x, &mat, &c->r, &td.upsample, &c->sm, d) == WR_OK) {
            double *fn = (double *)malloc(sizeof(double) * (size_t)c->sm.nv);
            double *frho = (double *)malloc(sizeof(double) * (size_t)c->sm.nv);
            tp_normal_disp(&c->r.wrinkled, &c->sm, fn);
            rho_field(&c->r.wrinkled, frho);
            for (i = 0; i < NRAD; ++i) {
                c->s_n[i] = circle_count(&c->r.wrinkled, fn, radii[i], 1, &c->sr_n[i], c->sig_n[i], d);
                c->s_rho[i] = circle_count(&c->r.wrinkled, frho, radii[i], KMIN_RHO, &c->sr_rho[i], c->sig_r, d);
            }
            free(fn);
            free(frho);
        }
        wr_mesh_free(&based);
    }
    for (i = 0; c->r.a && i < c->m.nv; ++i) c->amax = fmax(c->amax, c->r.a[i]);
    for (i = 0; i < NRAD; ++i) c->len_base[i] = ring_length(&c->m, c->x, radii[i], d);
    fprintf(stderr, "TFW: %s, SQP %d it, %.2f s; counts %d %d %d\n", wr_status_string(c->s_tfw), (int)c->r.sqp.iterations,
            c->r.seconds_total, c->s_n[0] ? -1 : (int)c->sr_n[0].count_rounded,
            c->s_n[1] ? -1 : (int)c->sr_n[1].count_rounded, c->s_n[2] ? -1 : (int)c->sr_n[2].count_rounded);
}

/* The StVK reference on the NREF x NREF grid, started from the TFT base interpolated (barycentric, on
 * the rest domain) onto it, and its rho counts, fold angles and perimeters. */
static void stvk_reference(drape_case *c, wr_diag *d) {
    wr_probe pc;
    wr_mesh dr; /* deformed reference with its rest coordinates */
    const wr_mesh *m = &c->m;
    double *xi = (double *)malloc(sizeof(double) * 3 * c->mref.nv), b[3];
    double *fr = (double *)malloc(sizeof(double) * (size_t)c->mref.nv), *tmp = (double *)malloc(sizeof(double) * NSAMP);
    int32_t vv, f, q, i;
    if (wr_probe_create(&pc, m, NULL, d) == WR_OK) {
        for (vv = 0; vv < c->mref.nv; ++vv) {
            f = wr_probe_locate(&pc, c->mref.rest[2 * vv], c->mref.rest[2 * vv + 1], b);
            for (q = 0; q < 3; ++q)
                xi[3 * vv + q] = f < 0 ? NAN
                                       : b[0] * c->x[3 * m->faces[3 * f] + q] + b[1] * c->x[3 * m->faces[3 * f + 1] + q] +
                                             b[2] * c->x[3 * m->faces[3 * f + 2] + q];
        }
        wr_probe_free(&pc);
    }
    drape(&c->mref, NREF, WR_MEMBRANE_STVK, WR_BENDING_DIHEDRAL, xi, c->xref, &c->oref); /* fold-safe bending */
    if (wr_mesh_create(&dr, c->mref.nv, c->xref, c->mref.rest, c->mref.nf, c->mref.faces, d) == WR_OK) {
        rho_field(&dr, fr);
        fold_stats(&c->mref, c->xref, &c->fold_max, &c->n_fold);
        for (i = 0; i < NRAD; ++i) c->len_ref[i] = ring_length(&c->mref, c->xref, radii[i], d);
        for (i = 0; i < NRAD; ++i) c->s_ref[i] = circle_count(&dr, fr, radii[i], KMIN_RHO, &c->sr_ref[i], tmp, d);
        wr_mesh_free(&dr);
    }
    free(xi);
    free(fr);
    free(tmp);
}

/* Sanity checks and, per rest circle, the TFW and StVK counts and amplitudes. */
static void report_counts(wr_vres *v, const drape_case *c) {
    char buf[1024];
    int i;
    wr_vres_check(v, "TFT base solve converged (all 4 gravity increments)", "failed increments", NAN, c->ob.fails, "0",
                  c->ob.fails == 0);
    wr_vres_check(v, "TFT base: smallest vertex-sphere distance (free vertices)", "m", NAN, c->ob.min_dist, "> 0",
                  c->ob.min_dist > 0.0);
    wr_vres_check(v, "TFW pipeline produced fields (OK or SQP not converged)", "", NAN, (double)c->s_tfw,
                  "status 0 or NOT_CONVERGED", c->s_tfw == WR_OK || c->s_tfw == WR_ERR_NOT_CONVERGED);
    for (i = 0; i < NRAD; ++i) {
        const int no_n = c->s_n[i] != WR_OK, no_ref = c->s_ref[i] || c->oref.st;
        snprintf(buf, sizeof buf, "TFW radial wrinkles, rest circle r = %.2f m (normal displacement, FFT harmonic)", radii[i]);
        wr_vres_info(v, buf, "wrinkles", NAN, no_n ? NAN : c->sr_n[i].count_rounded);
        snprintf(buf, sizeof buf, "TFW wrinkle amplitude (max-min)/2, r = %.2f m", radii[i]);
        wr_vres_info(v, buf, "mm", NAN, no_n ? NAN : 1e3 * c->sr_n[i].amplitude_p2p);
        snprintf(buf, sizeof buf, "TFW zero-crossing waves, r = %.2f m", radii[i]);
        wr_vres_info(v, buf, "wrinkles", NAN, no_n ? NAN : c->sr_n[i].zc_waves);
        snprintf(buf, sizeof buf, "TFW radial wrinkles from rho (harmonics >= %d), r = %.2f m", KMIN_RHO, radii[i]);
        wr_vres_info(v, buf, "wrinkles", NAN, c->s_rho[i] ? NAN : c->sr_rho[i].count_rounded);
        snprintf(buf, sizeof buf, "StVK %d-vertex reference: radial wrinkles from rho (harmonics >= %d), r = %.2f m",
                 (int)c->mref.nv, KMIN_RHO, radii[i]);
        wr_vres_info(v, buf, "wrinkles", NAN, no_ref ? NAN : c->sr_ref[i].count_rounded);
        snprintf(buf, sizeof buf, "StVK reference amplitude of rho (max-min)/2, r = %.2f m", radii[i]);
        wr_vres_info(v, buf, "mm", NAN, no_ref ? NAN : 1e3 * c->sr_ref[i].amplitude_p2p);
        if (c->oref.st && !c->s_ref[i]) {
            snprintf(buf, sizeof buf, "StVK reference did NOT converge (%s); its best iterate at r = %.2f m shows %d waves "
                     "(rho, amplitude %.2f mm) -- not a reference.", wr_status_string(c->oref.st), radii[i],
                     (int)c->sr_ref[i].count_rounded, 1e3 * c->sr_ref[i].amplitude_p2p);
            wr_vres_note(v, buf);
        }
    }
}

/* How many reference edges one TFW wave gets where the waves are: the drape's perimeter at that rest
 * circle over the TFW count, in units of the reference grid's rest edge SIDE/NREF. */
static void report_wavelengths(wr_vres *v, const drape_case *c) {
    char buf[1024];
    int i;
    for (i = 0; i < NRAD; ++i) {
        double lam = c->s_n[i] ? NAN : c->len_base[i] / c->sr_n[i].count_rounded;
        snprintf(buf, sizeof buf, "TFT base: perimeter of the drape at rest circle r = %.2f m", radii[i]);
        wr_vres_info(v, buf, "m", NAN, c->len_base[i]);
        snprintf(buf, sizeof buf, "TFW wavelength along the drape (perimeter / count), r = %.2f m", radii[i]);
        wr_vres_info(v, buf, "mm", NAN, 1e3 * lam);
        snprintf(buf, sizeof buf, "TFW wavelength in StVK %d x %d grid edges (%.1f mm), r = %.2f m", NREF, NREF,
                 1e3 * SIDE / NREF, radii[i]);
        wr_vres_info(v, buf, "edges", NAN, lam / (SIDE / NREF));
        snprintf(buf, sizeof buf, "StVK reference: perimeter of the drape at rest circle r = %.2f m", radii[i]);
        wr_vres_info(v, buf, "m", NAN, c->len_ref[i]);
    }
}

/* The solves' statistics beside the paper's (1.6k vertices, 46 SQP iterations, 15.06 s), and where
 * the StVK reference stops: contact state and fold angles at its returned iterate (restarting Newton
 * from that iterate was tried: a few more steps end in another line-search stall at a much larger
 * gradient, so it is not done). */
static void report_solves(wr_vres *v, const drape_case *c) {
    char buf[256];
    wr_vres_info(v, "max a on the base vertices", "mm", NAN, 1e3 * c->amax);
    wr_vres_info(v, "base vertices", "", 1600, c->m.nv);
    wr_vres_info(v, "TFT base time (4 gravity increments)", "s", NAN, c->ob.seconds);
    wr_vres_info(v, "TFT base Newton steps (all increments)", "", NAN, c->ob.iters);
    wr_vres_info(v, "TFT base lowest z (sphere centre at 0)", "m", NAN, c->ob.zmin);
    wr_vres_info(v, "SQP iterations", "", 46, c->r.sqp.iterations);
    wr_vres_info(v, "TFW time (E.2 to E.5)", "s", 15.06, c->r.seconds_total);
    wr_vres_info(v, "wrinkle-free faces |W|", "", NAN, c->r.n_wrinkle_free);
    wr_vres_info(v, "StVK reference vertices", "", NAN, c->oref.nv);
    wr_vres_check(v, "StVK reference converged (one full-gravity solve from the TFT base)", "failed increments", NAN,
                  c->oref.fails, "0 (informational: a miss means no converged reference)", c->oref.fails == 0);
    wr_vres_info(v, "StVK reference time", "s", NAN, c->oref.seconds);
    wr_vres_info(v, "StVK reference Newton steps", "", NAN, c->oref.iters);
    wr_vres_info(v, "StVK reference: smallest vertex-sphere distance", "mm", NAN, 1e3 * c->oref.min_dist);
    wr_vres_info(v, "StVK reference: free vertices within d_hat of the sphere", "", NAN, c->oref.n_contacts);
    wr_vres_info(v, "StVK reference: smallest CCD step cut", "", NAN, c->oref.ccd_alpha_min);
    wr_vres_info(v, "StVK reference final relative gradient", "", NAN, c->oref.grad_rel);
    wr_vres_info(v, "StVK reference: largest angle between adjacent face normals", "deg", NAN, c->fold_max);
    snprintf(buf, sizeof buf, "StVK reference: interior edges folded beyond %.0f deg", FOLD_DEG);
    wr_vres_info(v, buf, "", NAN, c->n_fold);
    wr_vres_info(v, "StVK reference stop rule (1 gradient, 2 step, 3 max-iter, 4 line search)", "", NAN, c->oref.stop);
}

static void report_table(wr_vres *v, const drape_case *c) {
    char table[4096];
    size_t off;
    int i;
    off = (size_t)snprintf(table, sizeof table,
                           "| rest radius [m] | TFW count (normal disp.) | TFW amp. [mm] | TFW count (rho, k>=%d) | StVK %d v "
                           "count (rho) | StVK rho amp. [mm] |\n|---|---|---|---|---|---|\n",
                           KMIN_RHO, (int)c->mref.nv);
    for (i = 0; i < NRAD && off < sizeof table; ++i)
        off += (size_t)snprintf(table + off, sizeof table - off, "| %.2f | %d | %.3f | %d | %d%s | %.3f |\n", radii[i],
                                c->s_n[i] ? -1 : (int)c->sr_n[i].count_rounded,
                                c->s_n[i] ? NAN : 1e3 * c->sr_n[i].amplitude_p2p,
                                c->s_rho[i] ? -1 : (int)c->sr_rho[i].count_rounded,
                                c->s_ref[i] ? -1 : (int)c->sr_ref[i].count_rounded, c->oref.st ? " (not converged)" : "",
                                c->s_ref[i] ? NAN : 1e3 * c->sr_ref[i].amplitude_p2p);
    wr_vres_table_md(v, table);
}

/* Why the StVK reference does not converge, and what a converged one would need. */
static void report_reference_notes(wr_vres *v, const drape_case *c) {
    char buf[1024];
    snprintf(buf, sizeof buf,
             "Why the StVK reference does not converge: Newton stopped by rule %d (3 = the %d-step budget, 4 = line "
             "search) at |g|/ref %.1e; at its returned iterate %d interior edges are folded beyond %.0f deg (largest "
             "normal angle %.2f deg) on the %d x %d grid (rest edge %.1f mm), whose folds close onto single edges "
             "(ridges at rest radius ~0.17-0.34 m, where the sheet leaves the sphere). The dihedral bending stays "
             "finite and smooth there (the mid-edge normal of the earlier reference degenerated at 180 deg and "
             "stalled the line search at |g|/ref 2.9e-2).",
             (int)c->oref.stop, REF_MAX_ITER, c->oref.grad_rel, (int)c->n_fold, FOLD_DEG, c->fold_max, NREF, NREF,
             1e3 * SIDE / NREF);
    wr_vres_note(v, buf);
    wr_vres_note(v, "Exploration with the earlier MID-EDGE reference (s10, HEAD statics with the first-assembly contact fix, same pin, 1e-4 m kick, nice'd on the "
                    "loaded box): 60x60 from the TFT base 130 Newton / 133 s, line-search stall at |g|/ref 2.9e-2 after "
                    "reaching 1.5e-4 (12 waves, as here; 3 edges > 178 deg); 40x40 from the TFT base 158 Newton / 40 s, "
                    "stall at 3.7e-2 (5 edges > 178 deg, 11-14 waves); 40x40 with shift_raise = 10: 200 Newton (max), "
                    "mu driven to 5.6e8, steps 4e-18 m, |g|/ref 8.7e-2 (11 edges > 178 deg); 40x40 with d_hat = 0.5 mm: 160 "
                    "Newton, stall at |g|/ref 0.12 (12 edges > 178 deg, 11-12 waves); 30x30 from the flat sheet (1 increment): 147 "
                    "Newton, stall at |g|/ref 37; restarting Newton at a stalled 40x40 iterate: 3 steps of 1e-11 m, "
                    "gradient x2600, stall. membrane_ramp does not apply: the hanging skirt's load per width "
                    "(~rho_A g 0.4 m = 0.8 N/m) is 0.8 % of Eh, so ON MEMBRANE CONTINUATION's rule s0 >~ 100 load/(Eh) "
                    "gives s0 ~ 1.");
    wr_vres_note(v, "What a converged reference needs: a grid that resolves the folds, i.e. several edges per TFW wave "
                    "along the drape (rows 'TFW wavelength in ... grid edges': 2.7 at 60x60): at ~6 edges per wave "
                    "~7.5 mm edges (~135x135, ~18k vertices) -- hundreds of Newton steps at several s each on this box, "
                    "outside this driver's budget. The sub-mesh folds also cap the coarse reference's count (12 here "
                    "against TFW's 28), so its best iterate says nothing about the count.");
}

/* The normal wrinkle displacement on the three rest circles (written only when the middle circle
 * was analysed, as its samples are the figure's reason to exist). */
static void ring_figure(wr_vres *v, const drape_case *c, wr_diag *d) {
    wr_afile f;
    char dat[700], buf[1024];
    int i;
    snprintf(dat, sizeof dat, "%s/tfw_sphere_drape_ring.dat", wr_vres_dir());
    if (wr_afile_open(&f, dat, d) != WR_OK) return;
    for (i = 0; i < NSAMP; ++i)
        fprintf(f.fp, "%.6g %.6g %.6g %.6g\n", 360.0 * i / NSAMP, 1e3 * c->sig_n[0][i], 1e3 * c->sig_n[1][i],
                1e3 * c->sig_n[2][i]);
    if (wr_afile_commit(&f, d) != WR_OK) return;
    snprintf(buf, sizeof buf,
             "set xlabel 'angle on the rest circle [deg]'\nset ylabel 'wrinkle displacement off the base [mm]'\n"
             "set title 'TFW sphere drape, %d-vertex base'\n"
             "set xrange [0:360]\nset xtics 45\nset key outside right top\n"
             "plot '%s' u 1:2 w l t 'r = 0.30 m', '' u 1:3 w l t 'r = 0.35 m', '' u 1:4 w l t 'r = 0.40 m'\n",
             (int)c->m.nv, dat);
    tp_figure(v, "tfw_sphere_drape", buf, "normal wrinkle displacement on three rest circles");
}

static int validation_main(void) {
    drape_case c;
    wr_diag d;
    wr_vres *v;
    char buf[256];
    double t_all = wr_time_seconds();
    int failed;
    memset(&d, 0, sizeof d);
    if (!case_init(&c, &d)) {
        fprintf(stderr, "validate_tfw_sphere_drape: set-up: %s\n", d.message[0] ? d.message : "out of memory");
        case_free(&c);
        return 1;
    }
    tfw_on_base(&c, &d);
    stvk_reference(&c, &d);
    v = wr_vres_begin("tfw_sphere_drape", "TFW Sec. 6 sphere drape (Fig. 5): radial wrinkles around the drape");
    report_counts(v, &c);
    report_wavelengths(v, &c);
    report_solves(v, &c);
    report_table(v, &c);
    wr_vres_note(v, "The TFW paper gives no wrinkle count or amplitude for the sphere drape in its text (Fig. 5 images only).");
    wr_vres_note(v, "Frictionless contact: the centre vertex is pinned 1 mm above the sphere top (inside d_hat = 2 mm); "
                    "otherwise the sheet slides off (a saddle of the energy). Gravity ramped in 4 warm-started increments.");
    wr_vres_note(v, "-1 in the table = probe/analysis failed (see notes) or no result.");
    if (c.oref.st) report_reference_notes(v, &c);
    if (c.s_tfw != WR_OK) {
        snprintf(buf, sizeof buf, "TFW status %s (SQP stop %d, rel. KKT %.1e).", wr_status_string(c.s_tfw),
                 (int)c.r.sqp.stop, c.r.sqp.kkt0 > 0 ? c.r.sqp.kkt / c.r.sqp.kkt0 : NAN);
        wr_vres_note(v, buf);
    }
    snprintf(buf, sizeof buf, "Total driver time %.1f s on the shared 2-core box.", wr_time_seconds() - t_all);
    wr_vres_note(v, buf);
    if (!c.s_n[1]) ring_figure(v, &c, &d);
    failed = wr_vres_finish(v);
    case_free(&c);
    /* 1 only when the result file could not be written: a missed quantity is in the file, not the exit */
    return failed < 0 ? 1 : 0;
}

int main(int argc, char **argv) {
    int rc = wr_vargs(argc, argv, "validate_tfw_sphere_drape",
                      "TFW Sec. 6 sphere drape (Fig. 5): radial wrinkles.",
                      "tfw_sphere_drape", NULL, NULL, NULL);
    return rc >= 0 ? rc : validation_main();
}
