/* wrinkle/tfw.h — the TFW pipeline on a given base surface: wrinkle-free set, initial guess, SQP for
 * amplitude and frequency, phase, Loop upsampling to the wrinkled surface — one call, with timings.
 * wrinkle v0.1.0 — MIT licence (see LICENSE). Needs core.h, mesh.h, shell.h, wrinkle_field.h (and
 * its sparse.h, spd.h; CHOLMOD through spd.h when built with -DWR_USE_CHOLMOD=1); otherwise libc/libm.
 *
 * Paper: Chen et al., "Fine Wrinkling on Coarsely Meshed Thin Shells" (TFW, TOG 2021), Sec. 5 and
 * App. E.2–E.5. The base surface (Sec. 4.1: TFT membrane + quadratic bending) is computed by the
 * caller with statics.h (shell desc membrane = WR_MEMBRANE_TFT, bending = WR_BENDING_QUADRATIC);
 * wr_tfw_base_shell_desc fills that desc so drivers and validations use the same model.
 *
 * API (create/free pair: wr_tfw_fields → wr_tfw_result_free)
 *   wr_tfw_base_shell_desc(young, poisson, thickness, density, out)   Sec. 4.1 shell model
 *   wr_tfw_fields(mesh, base_pos, material, desc, result, diag)       W, E.2, E.3, E.4, E.5
 *   wr_tfw_result_free(result)
 *
 * EXAMPLE
 *     wr_mesh m;  wr_wf_material mat;  wr_tfw_desc td;  wr_tfw_result r;  wr_diag d;  wr_status st;
 *     double *x, amax = 0.0;  int32_t i;
 *     if (wr_mesh_rectangle(&m, 0.25, 0.10, 12, 5, &d) != WR_OK) { puts(d.message); return 1; }
 *     x = (double *)wr_alloc_array(3 * (size_t)m.nv, sizeof(double));
 *     for (i = 0; i < m.nv; ++i) {     // base surface (in practice statics.h with wr_tfw_base_shell_desc):
 *         double u = m.pos[3 * i], v = m.pos[3 * i + 1] - 0.05;      // 10 % stretch, width pulled in
 *         x[3 * i] = 1.1 * u;  x[3 * i + 1] = 0.05 + v * (1.0 - 0.1 * sin(3.14159265 * u / 0.25));  x[3 * i + 2] = 0.0;
 *     }
 *     mat.young = 1e6; mat.poisson = 0.5; mat.thickness = 1e-4;     // Pa, -, m
 *     memset(&td, 0, sizeof td);  td.solve.max_iter = 30;            // a few SQP steps (App. E.3)
 *     st = wr_tfw_fields(&m, x, &mat, &td, &r, &d);                  // W, E.2, E.3, E.4, E.5
 *     if (st != WR_OK && st != WR_ERR_NOT_CONVERGED) { puts(d.message); return 1; }
 *     for (i = 0; i < m.nv; ++i) amax = fmax(amax, r.a[i]);
 *     printf("max amplitude %.2f mm; wrinkled mesh %d vertices\n", 1e3 * amax, r.wrinkled.nv);
 *     wr_tfw_result_free(&r);  wr_free(x);  wr_mesh_free(&m);
 *
 * ON RESULTS
 *   a (nv) [m], omega (ne) [rad per edge], phi (3 nf) per-corner phase [rad], wfree (nf), the wrinkled
 *   mesh (Loop level `upsample.levels`, default 2) with, per fine vertex, the amplitude wrinkled_a [m],
 *   the phase wrinkled_phase [rad, wrapped to (-π, π]] and the wrinkle-free flag wrinkled_wfree
 *   (wr_wf_fine_fields: height over the base = a cos φ, what a viewer colours by). An SQP that stops without
 *   converging (WR_ERR_NOT_CONVERGED) still yields fields, phase and the wrinkled mesh; the status is
 *   returned after everything is filled, and result->sqp tells why.
 *
 * ON CLAMPS AND FOLDS
 *   desc->a_zero_vertices holds a = 0 on clamped vertices (wr_wf_set_amplitude_zero). After the SQP,
 *   edges where dφ reverses between wrinkled faces are counted (wr_wf_count_folds); if there are any
 *   (and not desc->no_unfold), ω is re-oriented (wr_wf_unfold) and solved again; the re-solve is kept
 *   when it has fewer folds. result->sqp_first / n_folds_first describe the first solve; result->sqp
 *   the returned one (energy, KKT, stop rule) with the work of both summed (iterations, rejected
 *   steps, factorisations, seconds); n_folds the returned fields; result->unfolded says which.
 * ON OUTCOMES
 *   TFW's fields are meaningful only where the base is compressed in one direction and stretched
 *   across it: the tension term of Eq. 21 is what bounds the wave number, so a face compressed in
 *   both principal directions (Eq. 29: both eigenvalues <= compress_tol) has no wavelength and, with
 *   the a ≥ 0 bound alone, an unbounded amplitude (a 20 cm square pulled in 10 % on all sides gives
 *   "a = 0.67 m" with no guard). result->outcome classifies every run:
 *     WR_TFW_SLACK          every face outside W is slack: refused with WR_ERR_DOMAIN before the
 *                           SQP (desc->allow_slack solves it anyway); n_slack counts partly slack bases
 *     WR_TFW_NO_COMPRESSION W is every face: no face is compressed, nothing can wrinkle (WR_OK)
 *     WR_TFW_FILTERED       compressed faces exist but Sec. 5.1's averaging and outlier filter put
 *                           them all in W: the compressed region is a few isolated faces, i.e. the
 *                           base mesh is too coarse for it (WR_OK)
 *     WR_TFW_FLAT           the SQP drove a to ≈ 0 (max a <= 1 % of the thickness): the compression
 *                           is below the threshold the bending and tension allow at wavelengths
 *                           this base can carry (WR_OK)
 *     WR_TFW_WRINKLED       otherwise.
 *   wr_tfw_outcome_reason(outcome) gives the one-line reason drivers print.
 * ON THREADS
 *   No global state.
 */
#ifndef WRINKLE_TFW_H
#define WRINKLE_TFW_H

#include "core.h"
#include "mesh.h"
#include "wrinkle_field.h"
#include "shell.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Defaults: everything zero = the defaults of each stage; W from the Sec. 5.1 rule unless
 * wfree_override is given (nf flags). */
typedef struct wr_tfw_desc {
    wr_wf_classify_desc classify;
    wr_wf_init_desc init;
    wr_wf_solve_desc solve;
    wr_wf_upsample_desc upsample;
    const uint8_t *wfree_override;
    const uint8_t *a_zero_vertices; /* nv flags or NULL: a held at 0 there (clamped edges, wr_wf_set_amplitude_zero) */
    int no_upsample; /* nonzero: skip E.5 (result->wrinkled stays empty) */
    int no_unfold;   /* nonzero: keep the SQP's ω even where dφ folds (see wr_wf_count_folds) */
    int allow_slack; /* nonzero: solve a slack base anyway instead of refusing it (ON OUTCOMES) */
    wr_wf_kappa kappa; /* κ⊥ of Eq. 22: mid-edge II (default) or the vertex quadric fit (wrinkle_field.h) */
} wr_tfw_desc;

/* What the fields say about the base (ON OUTCOMES). */
typedef enum wr_tfw_outcome {
    WR_TFW_WRINKLED = 0,       /* faces outside W and a visible amplitude somewhere */
    WR_TFW_NO_COMPRESSION = 1, /* W is every face: no face of the base is compressed (Sec. 5.1) */
    WR_TFW_FILTERED = 2,       /* compressed faces exist, but too few together for Sec. 5.1: the base
                                * mesh is too coarse for the compressed region */
    WR_TFW_FLAT = 3,           /* faces outside W, but the SQP returned a ≈ 0: compression below the
                                * wrinkling threshold, or wavelengths shorter than the base resolves */
    WR_TFW_SLACK = 4           /* every face outside W is compressed in both principal directions: no
                                * tension sets a wavelength (Eq. 21), the amplitude is unbounded */
} wr_tfw_outcome;

typedef struct wr_tfw_result {
    int32_t nv, ne, nf;
    double *a, *omega, *phi;
    uint8_t *wfree;
    int32_t n_wrinkle_free;
    wr_mesh wrinkled;
    double *wrinkled_a, *wrinkled_phase; /* per wrinkled vertex: a [m], φ wrapped to (-π, π] [rad] */
    uint8_t *wrinkled_wfree;             /* per wrinkled vertex: 1 when it touches only W faces */
    wr_wf_solve_stats sqp;          /* the returned solve (energy, KKT, stop); work counts (iterations, rejected
                                     * steps, factorisations, escapes, negative-curvature steps, seconds) summed
                                     * over both solves */
    wr_wf_solve_stats sqp_first;    /* the first SQP from the App. E.2 start */
    int32_t n_folds_first, n_folds; /* fold edges after the first SQP and in the returned ω */
    int32_t unfolded;               /* 1: the returned fields come from wr_wf_unfold + a second SQP */
    wr_wf_phase_stats phase;
    wr_tfw_outcome outcome;         /* ON OUTCOMES */
    int32_t n_compressed;           /* faces whose Eq. 29 strain has a negative eigenvalue (< -compress_tol) */
    int32_t n_slack;                /* faces outside W with both eigenvalues <= compress_tol (no tension) */
    double max_amplitude;           /* max a over vertices [m] */
    double seconds_setup, seconds_init, seconds_sqp, seconds_phase, seconds_upsample, seconds_total;
} wr_tfw_result;

WRDEF void wr_tfw_base_shell_desc(double young, double poisson, double thickness, double density, wr_shell_desc *out);
WRDEF wr_status wr_tfw_fields(const wr_mesh *m, const double *base_pos, const wr_wf_material *mat,
                              const wr_tfw_desc *desc, wr_tfw_result *res, wr_diag *diag);
WRDEF void wr_tfw_result_free(wr_tfw_result *res);
/* One line naming the outcome and its likely cause ("nothing wrinkles: ..."), for messages. */
WRDEF const char *wr_tfw_outcome_reason(wr_tfw_outcome outcome);

#ifdef __cplusplus
}
#endif
#endif /* WRINKLE_TFW_H */

#ifdef WRINKLE_IMPLEMENTATION
#ifndef WRINKLE_TFW_IMPLEMENTATION_DONE
#define WRINKLE_TFW_IMPLEMENTATION_DONE

#include <string.h>

#ifdef __cplusplus
extern "C" {
#endif

WRDEF void wr_tfw_base_shell_desc(double young, double poisson, double thickness, double density, wr_shell_desc *out) {
    memset(out, 0, sizeof *out);
    out->membrane = WR_MEMBRANE_TFT;      /* TFW Sec. 4.1, App. B */
    out->bending = WR_BENDING_QUADRATIC;  /* TFW Eq. 28 */
    out->young = young;
    out->poisson = poisson;
    out->thickness = thickness;
    out->density = density;
}

/* max a at or below this fraction of the thickness counts as flat (ON OUTCOMES): an out-of-plane
 * wave of 1 % of h is no visible wrinkle (the paper's stretched sheet has a ≈ 3.5 h), and the SQP's
 * near-zero returns on sheets that do not wrinkle are nanometres (3e-9 m on a 0.1 mm sheet). */
#define WR_TFW_FLAT_REL 1e-2

WRDEF const char *wr_tfw_outcome_reason(wr_tfw_outcome outcome) {
    switch (outcome) {
    case WR_TFW_WRINKLED: return "wrinkled";
    case WR_TFW_NO_COMPRESSION:
        return "nothing wrinkles: no face of the base is compressed (TFW Sec. 5.1 puts every face in W)";
    case WR_TFW_FILTERED:
        return "nothing wrinkles: the compressed faces are too few or isolated for Sec. 5.1's averaging and "
               "outlier filter (base mesh too coarse for the compressed region)";
    case WR_TFW_FLAT:
        return "nothing wrinkles: the SQP returned a = 0 (compression below the wrinkling threshold, or a "
               "wavelength shorter than the base mesh resolves)";
    case WR_TFW_SLACK:
        return "slack base: every face outside W is compressed in both principal directions, so no tension "
               "sets a wavelength (TFW Eq. 21) and the amplitude is unbounded";
    }
    return "unknown outcome";
}

/* Counts of compressed faces and of slack faces outside W (Eq. 29 eigenvalues, ON OUTCOMES). */
static void wr__tfw_count_strain(const wr_wf *wf, double tol, wr_tfw_result *res) {
    int32_t f;
    res->n_compressed = res->n_slack = 0;
    for (f = 0; f < wf->nf; ++f) {
        res->n_compressed += wf->lambda[2 * f] < -tol;
        res->n_slack += !wf->wfree[f] && wf->lambda[2 * f + 1] <= tol;
    }
}

/* The outcome after the SQP from W, the counts and the amplitude (ON OUTCOMES). */
static wr_tfw_outcome wr__tfw_outcome(const wr_mesh *m, double thickness, wr_tfw_result *res) {
    int32_t v;
    res->max_amplitude = 0.0;
    for (v = 0; v < m->nv; ++v) res->max_amplitude = fmax(res->max_amplitude, res->a[v]);
    if (res->n_wrinkle_free == m->nf) return res->n_compressed > 0 ? WR_TFW_FILTERED : WR_TFW_NO_COMPRESSION;
    if (res->n_slack == m->nf - res->n_wrinkle_free) return WR_TFW_SLACK;
    return res->max_amplitude <= WR_TFW_FLAT_REL * thickness ? WR_TFW_FLAT : WR_TFW_WRINKLED;
}

WRDEF void wr_tfw_result_free(wr_tfw_result *res) {
    if (!res) return;
    wr_free(res->a);
    wr_free(res->omega);
    wr_free(res->phi);
    wr_free(res->wfree);
    wr_free(res->wrinkled_a);
    wr_free(res->wrinkled_phase);
    wr_free(res->wrinkled_wfree);
    wr_mesh_free(&res->wrinkled);
    memset(res, 0, sizeof *res);
}

WRDEF wr_status wr_tfw_fields(const wr_mesh *m, const double *base_pos, const wr_wf_material *mat,
                              const wr_tfw_desc *desc, wr_tfw_result *res, wr_diag *diag) {
    wr_wf wf;
    wr_tfw_desc D;
    wr_status st, sqp_st;
    double t0 = wr_time_seconds(), t1;
    int32_t f;
    if (!res) return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "tfw: NULL result");
    memset(res, 0, sizeof *res);
    if (!m || !mat) return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "tfw: NULL mesh or material");
    if (desc)
        D = *desc;
    else
        memset(&D, 0, sizeof D);
    st = wr_wf_create(&wf, m, base_pos, mat, diag);
    if (st) return st;
    if (D.kappa != WR_WF_KAPPA_MIDEDGE && (st = wr_wf_set_kappa(&wf, D.kappa, diag)) != WR_OK) {
        wr_wf_free(&wf);
        return st;
    }
    res->nv = m->nv;
    res->ne = m->ne;
    res->nf = m->nf;
    res->a = (double *)wr_alloc_array((size_t)m->nv, sizeof(double));
    res->omega = (double *)wr_alloc_array((size_t)m->ne, sizeof(double));
    res->phi = (double *)wr_calloc_array((size_t)m->nf * 3, sizeof(double));
    res->wfree = (uint8_t *)wr_alloc_array((size_t)m->nf, sizeof(uint8_t));
    if (!res->a || !res->omega || !res->phi || !res->wfree) {
        st = wr_fail(diag, WR_ERR_NOMEM, -1, "tfw: out of memory for %d vertices", (int)m->nv);
        goto fail;
    }
    if (D.wfree_override)
        wr_wf_set_wrinkle_free(&wf, D.wfree_override);
    else if (wr_wf_classify(&wf, &D.classify) < 0) { /* Sec. 5.1 */
        st = wr_fail(diag, WR_ERR_INVALID_ARG, (int32_t)D.classify.rule, "tfw: unknown W rule %d", (int)D.classify.rule);
        goto fail;
    }
    if (D.a_zero_vertices) wr_wf_set_amplitude_zero(&wf, D.a_zero_vertices);
    for (f = 0; f < m->nf; ++f) {
        res->wfree[f] = wf.wfree[f];
        res->n_wrinkle_free += wf.wfree[f];
    }
    wr__tfw_count_strain(&wf, D.classify.compress_tol > 0.0 ? D.classify.compress_tol : WR_WF_COMPRESS_TOL_DEFAULT, res);
    if (!D.allow_slack && res->n_slack > 0 && res->n_slack == m->nf - res->n_wrinkle_free) {
        st = wr_fail(diag, WR_ERR_DOMAIN, -1, "tfw: %s (%d faces; allow_slack solves it anyway)",
                     wr_tfw_outcome_reason(WR_TFW_SLACK), (int)res->n_slack);
        goto fail;
    }
    t1 = wr_time_seconds();
    res->seconds_setup = t1 - t0;
    st = wr_wf_init(&wf, &D.init, res->a, res->omega, diag); /* App. E.2 */
    if (st) goto fail;
    res->seconds_init = wr_time_seconds() - t1;
    t1 = wr_time_seconds();
    sqp_st = wr_wf_solve(&wf, &D.solve, res->a, res->omega, &res->sqp, diag); /* App. E.3 */
    if (sqp_st && sqp_st != WR_ERR_NOT_CONVERGED) {
        st = sqp_st;
        res->seconds_sqp = wr_time_seconds() - t1;
        goto fail;
    }
    res->sqp_first = res->sqp;
    res->n_folds_first = res->n_folds = wr_wf_count_folds(&wf, res->a, res->omega);
    if (res->n_folds > 0 && !D.no_unfold) {
        /* E_wf cannot see a sign flip of dφ between faces (see wr_wf_count_folds): re-orient ω
         * consistently and solve again from there; keep the re-solve if it has fewer folds */
        double *a2 = (double *)wr_alloc_array((size_t)m->nv, sizeof(double));
        double *o2 = (double *)wr_alloc_array((size_t)m->ne, sizeof(double));
        wr_wf_solve_stats s2;
        wr_status st2;
        if (!a2 || !o2) {
            wr_free(a2);
            wr_free(o2);
            st = wr_fail(diag, WR_ERR_NOMEM, -1, "tfw: out of memory");
            goto fail;
        }
        memcpy(a2, res->a, sizeof(double) * (size_t)m->nv);
        memcpy(o2, res->omega, sizeof(double) * (size_t)m->ne);
        st2 = wr_wf_unfold(&wf, a2, o2, diag);
        if (!st2) st2 = wr_wf_solve(&wf, &D.solve, a2, o2, &s2, diag);
        if (st2 == WR_OK || st2 == WR_ERR_NOT_CONVERGED) {
            int32_t n2 = wr_wf_count_folds(&wf, a2, o2);
            if (n2 < res->n_folds) {
                memcpy(res->a, a2, sizeof(double) * (size_t)m->nv);
                memcpy(res->omega, o2, sizeof(double) * (size_t)m->ne);
                res->sqp = s2;
                res->sqp.iterations += res->sqp_first.iterations;
                res->sqp.n_rejected += res->sqp_first.n_rejected;
                res->sqp.n_factorizations += res->sqp_first.n_factorizations;
                res->sqp.n_escapes += res->sqp_first.n_escapes;
                res->sqp.n_negcurv += res->sqp_first.n_negcurv;
                res->sqp.seconds += res->sqp_first.seconds;
                res->sqp.seconds_assembly += res->sqp_first.seconds_assembly;
                res->sqp.seconds_solve += res->sqp_first.seconds_solve;
                res->n_folds = n2;
                res->unfolded = 1;
                sqp_st = st2;
            }
        } else if (st2 != WR_ERR_NOMEM) {
            st2 = WR_OK; /* a failed re-solve keeps the first solution */
        }
        wr_free(a2);
        wr_free(o2);
        if (st2 == WR_ERR_NOMEM) {
            st = st2;
            goto fail;
        }
    }
    res->seconds_sqp = wr_time_seconds() - t1;
    res->outcome = wr__tfw_outcome(m, mat->thickness, res);
    t1 = wr_time_seconds();
    st = wr_wf_phase(&wf, res->omega, res->phi, &res->phase, diag); /* App. E.4 */
    res->seconds_phase = wr_time_seconds() - t1;
    if (st) goto fail;
    if (!D.no_upsample) {
        wr_wf_fine_fields F;
        t1 = wr_time_seconds();
        st = wr_wf_upsample_fields(&wf, res->a, res->phi, &D.upsample, &res->wrinkled, &F, diag); /* E.5 */
        res->seconds_upsample = wr_time_seconds() - t1;
        if (st) goto fail;
        res->wrinkled_a = F.a;
        res->wrinkled_phase = F.phase;
        res->wrinkled_wfree = F.wfree;
    }
    wr_wf_free(&wf);
    res->seconds_total = wr_time_seconds() - t0;
    if (sqp_st) /* keep the SQP's message for the caller */
        return wr_fail(diag, WR_ERR_NOT_CONVERGED, -1, "tfw: SQP stopped (stop rule %d) after %d iterations, KKT %g of %g",
                       (int)res->sqp.stop, (int)res->sqp.iterations, res->sqp.kkt, res->sqp.kkt0);
    return WR_OK;
fail:
    wr_wf_free(&wf);
    { /* the statistics and the ON OUTCOMES counts survive a failure; the arrays do not */
        wr_wf_solve_stats keep = res->sqp;
        int32_t n_comp = res->n_compressed, n_slack = res->n_slack, n_w = res->n_wrinkle_free;
        wr_tfw_result_free(res);
        res->sqp = keep;
        res->n_compressed = n_comp;
        res->n_slack = n_slack;
        res->n_wrinkle_free = n_w;
        if (st == WR_ERR_DOMAIN && n_slack > 0) res->outcome = WR_TFW_SLACK;
    }
    return st;
}

#ifdef __cplusplus
}
#endif
#endif /* WRINKLE_TFW_IMPLEMENTATION_DONE */
#endif /* WRINKLE_IMPLEMENTATION */
