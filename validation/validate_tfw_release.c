/* validate_tfw_release — TFW against the authors' release on its own shipped example (issue 16).
 *
 * The authors' repository (zhenchen-jay/WrinkledTensionFields) ships a pressurised disk: rest disk
 * (R 0.1 m, 273 vertices), their TFT base (rim pulled in to 0.08 m, 600 Pa), the clamped rim, and
 * their TFW fields on it (E 1e7 Pa, ν 0.44, h 0.1 mm, clamp on). Nothing of theirs is committed here:
 * the driver reads those files from $WR_TFW_RELEASE_DATA (a directory holding disk.obj,
 * disk_simulated.obj, disc_clamped_vertices.dat, disk_dphi_simulated.txt, copied from a checkout of
 * their public repository) and, when it is not set, leaves the committed result file alone.
 *
 * Metric, fixed before the runs: waves around the disk = the winding of the phase along the rim
 * (boundary loop), |∮ω| / 2π, the circulation of ω along the rim edges — ours, and theirs from their
 * shipped per-edge ω (their dphi file; their per-vertex φ is aliased there, |ω| ≈ 10 rad per rim
 * edge). Both are integers when the pattern closes. Ours is solved on their base without a clamp (their json's
 * clamp file name does not match the shipped file, so their run had none: docs/notes-tfw-authors.md), once
 * with each reading of κ⊥ in Eq. 22 (wrinkle_field.h wr_wf_kappa), once with a = 0 on the rim, and once per
 * combination of the release's other readings (W rule, start, no unfold: k_variants); the dress likewise.
 * Pass rule (set before the run): with the release's reading (vertex quadric-fit κ⊥) our count is
 * within 5 % of theirs — the two codes then evaluate the same energy up to the curvature estimator's
 * neighbourhood and normal, which should not move a 1 %-flat optimum by more. The default reading
 * is reported beside it. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "wrinkle/wrinkle.h"
#include "wrinkle/tfw.h"
#include "tfw_probe.h"
#include "vresult.h"
#include "vargs.h"

/* per-vertex numbers, one per line (their amplitude / phase files) */
static double *read_column(const char *path, int32_t n) {
    FILE *f = fopen(path, "r");
    double *x = (double *)malloc(sizeof(double) * (size_t)n);
    int32_t i;
    if (!f || !x) {
        if (f) fclose(f);
        free(x);
        return NULL;
    }
    for (i = 0; i < n; ++i)
        if (fscanf(f, "%lf", &x[i]) != 1) break;
    fclose(f);
    if (i < n) {
        free(x);
        return NULL;
    }
    return x;
}

/* clamped vertex file: lines "index x y z" (other lines ignored) → nv flags */
static uint8_t *read_clamped(const char *path, int32_t nv, int32_t *count) {
    FILE *f = fopen(path, "r");
    uint8_t *fl = (uint8_t *)calloc((size_t)nv, 1);
    char line[512];
    *count = 0;
    if (!f || !fl) {
        if (f) fclose(f);
        free(fl);
        return NULL;
    }
    while (fgets(line, sizeof line, f)) {
        int idx;
        double a, b, c;
        if (sscanf(line, "%d %lf %lf %lf", &idx, &a, &b, &c) == 4 && idx >= 0 && idx < nv && !fl[idx]) {
            fl[idx] = 1;
            ++*count;
        }
    }
    fclose(f);
    return fl;
}

/* The release numbers its edges in lexicographic order of (lower vertex, higher vertex) (a sorted
 * map over face edges) and stores ω per edge from the lower to the higher vertex, as the kit does:
 * their edge k is our edge order[k] once ours are sorted the same way. */
static const wr_mesh *g_sort_mesh;
static int cmp_edge(const void *a, const void *b) {
    const int32_t *E = g_sort_mesh->edges, x = *(const int32_t *)a, y = *(const int32_t *)b;
    if (E[2 * x] != E[2 * y]) return E[2 * x] < E[2 * y] ? -1 : 1;
    return (E[2 * x + 1] > E[2 * y + 1]) - (E[2 * x + 1] < E[2 * y + 1]);
}

static double *their_omega_on_our_edges(const wr_mesh *m, const double *dphi) {
    int32_t *order = (int32_t *)malloc(sizeof(int32_t) * (size_t)m->ne), k;
    double *om = (double *)malloc(sizeof(double) * (size_t)m->ne);
    if (!order || !om) {
        free(order);
        free(om);
        return NULL;
    }
    for (k = 0; k < m->ne; ++k) order[k] = k;
    g_sort_mesh = m;
    qsort(order, (size_t)m->ne, sizeof(int32_t), cmp_edge);
    for (k = 0; k < m->ne; ++k) om[order[k]] = dphi[k];
    free(order);
    return om;
}

typedef struct run_out {
    wr_status st;
    double waves, amax, seconds;
    double e_ours, e_theirs; /* this reading's E_wf at our fields and at the release's, on our W [J] */
    int32_t sqp_iters, n_w, unfolded;
} run_out;

/* One reading of each place where the release differs from the paper's text (docs/notes-tfw-authors.md):
 * κ⊥ of Eq. 22, the W rule, the E.2 start's scale and smoothing, and the unfold re-solve (ours only). */
typedef struct variant {
    const char *name;
    wr_wf_kappa kappa;
    wr_wf_wset_rule wset;
    wr_wf_init_rule init;
    int no_unfold;
} variant;

static const variant k_variants[] = {
    {"vertex-fit kappa + release W rule", WR_WF_KAPPA_VERTEX_FIT, WR_WF_WSET_RELEASE, WR_WF_INIT_PAPER, 0},
    {"vertex-fit kappa + release start", WR_WF_KAPPA_VERTEX_FIT, WR_WF_WSET_PAPER, WR_WF_INIT_RELEASE, 0},
    {"vertex-fit kappa + release W rule + release start", WR_WF_KAPPA_VERTEX_FIT, WR_WF_WSET_RELEASE,
     WR_WF_INIT_RELEASE, 0},
    {"every release reading (vertex-fit kappa, W rule, start, no unfold)", WR_WF_KAPPA_VERTEX_FIT,
     WR_WF_WSET_RELEASE, WR_WF_INIT_RELEASE, 1},
    {"mid-edge kappa + release W rule, start, no unfold", WR_WF_KAPPA_MIDEDGE, WR_WF_WSET_RELEASE,
     WR_WF_INIT_RELEASE, 1},
};
#define N_VARIANTS ((int)(sizeof k_variants / sizeof k_variants[0]))

static void variant_desc(const variant *va, wr_tfw_desc *td) {
    memset(td, 0, sizeof *td);
    td->no_upsample = 1;
    if (!va) return;
    td->kappa = va->kappa;
    td->classify.rule = va->wset;
    td->init.rule = va->init;
    td->no_unfold = va->no_unfold;
}

static run_out run_tfw_v(const wr_mesh *m, const uint8_t *a_zero, const variant *va, const double *their_a,
                         const double *their_om) {
    wr_wf_material mat;
    wr_tfw_desc td;
    wr_tfw_result r;
    wr_diag d;
    run_out o;
    wr_wf_kappa kappa = va ? va->kappa : WR_WF_KAPPA_MIDEDGE;
    memset(&o, 0, sizeof o);
    mat.young = 1e7;
    mat.poisson = 0.44;
    mat.thickness = 1e-4;
    variant_desc(va, &td);
    td.a_zero_vertices = a_zero;
    o.st = wr_tfw_fields(m, m->pos, &mat, &td, &r, &d);
    o.waves = NAN;
    if (o.st == WR_OK || o.st == WR_ERR_NOT_CONVERGED) {
        o.waves = tp_circulation(m, r.omega, m->loop_verts + m->loop_start[0], m->loop_start[1] - m->loop_start[0]);
        o.amax = r.max_amplitude;
        o.sqp_iters = r.sqp.iterations;
        o.n_w = r.n_wrinkle_free;
        o.unfolded = r.unfolded;
        o.seconds = r.seconds_total;
        o.e_ours = o.e_theirs = NAN;
        if (their_a && their_om) { /* both fields in this reading's energy, on our W */
            wr_wf wf;
            if (wr_wf_create(&wf, m, m->pos, &mat, &d) == WR_OK) {
                if (wr_wf_set_kappa(&wf, kappa, &d) == WR_OK) {
                    wr_wf_set_wrinkle_free(&wf, r.wfree);
                    wr_wf_energy(&wf, r.a, r.omega, &o.e_ours, NULL, NULL, NULL, &d);
                    wr_wf_energy(&wf, their_a, their_om, &o.e_theirs, NULL, NULL, NULL, &d);
                }
                wr_wf_free(&wf);
            }
        }
        wr_tfw_result_free(&r);
    } else {
        fprintf(stderr, "validate_tfw_release: TFW failed: %s\n", d.message);
    }
    return o;
}

static run_out run_tfw(const wr_mesh *m, const uint8_t *a_zero, wr_wf_kappa kappa, const double *their_a,
                       const double *their_om) {
    variant va;
    memset(&va, 0, sizeof va);
    va.kappa = kappa;
    return run_tfw_v(m, a_zero, &va, their_a, their_om);
}

/* Phase change along face f's edge from corner i to corner j (ω from edges[2e] to edges[2e+1]). */
static double corner_dphi(const wr_mesh *m, const double *omega, int32_t f, int i, int j) {
    int k = 3 - i - j; /* the edge opposite the third corner joins i and j */
    int32_t e = m->face_edges[3 * f + k], vi = m->faces[3 * f + i];
    return m->edges[2 * e] == vi ? omega[e] : -omega[e];
}

static int cmp_double(const void *a, const void *b) {
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* Median wrinkle wavelength 2π / |∇φ| [m] over the faces whose mean corner amplitude is at least
 * 0.2 × max a (visible wrinkles; the same rule for both codes), ∇φ the face's gradient on the base
 * surface from the phase changes along its edges 0→1 and 0→2. */
static double median_wavelength(const wr_mesh *m, const double *a, const double *omega, int32_t *n_used) {
    double amax = 0.0, *lam = (double *)malloc(sizeof(double) * (size_t)m->nf), med = NAN;
    int32_t f, v, n = 0;
    for (v = 0; v < m->nv; ++v) amax = fmax(amax, a[v]);
    for (f = 0; lam && f < m->nf; ++f) {
        const int32_t *fv = m->faces + 3 * f;
        double am = (a[fv[0]] + a[fv[1]] + a[fv[2]]) / 3.0, d01, d02, e1[3], e2[3], g11, g12, g22, det, c1, c2, gg;
        int i;
        if (!(am >= 0.2 * amax) || !(amax > 0.0)) continue;
        for (i = 0; i < 3; ++i) {
            e1[i] = m->pos[3 * fv[1] + i] - m->pos[3 * fv[0] + i];
            e2[i] = m->pos[3 * fv[2] + i] - m->pos[3 * fv[0] + i];
        }
        d01 = corner_dphi(m, omega, f, 0, 1);
        d02 = corner_dphi(m, omega, f, 0, 2);
        /* ∇φ = c1 e1 + c2 e2 with G (c1, c2) = (d01, d02), G the face's Gram matrix */
        g11 = e1[0] * e1[0] + e1[1] * e1[1] + e1[2] * e1[2];
        g12 = e1[0] * e2[0] + e1[1] * e2[1] + e1[2] * e2[2];
        g22 = e2[0] * e2[0] + e2[1] * e2[1] + e2[2] * e2[2];
        det = g11 * g22 - g12 * g12;
        if (!(det > 0.0)) continue;
        c1 = (g22 * d01 - g12 * d02) / det;
        c2 = (g11 * d02 - g12 * d01) / det;
        gg = c1 * c1 * g11 + 2.0 * c1 * c2 * g12 + c2 * c2 * g22;
        if (gg > 0.0) lam[n++] = 2.0 * TP_PI / sqrt(gg);
    }
    if (n > 0) {
        qsort(lam, (size_t)n, sizeof(double), cmp_double);
        med = n % 2 ? lam[n / 2] : 0.5 * (lam[n / 2 - 1] + lam[n / 2]);
    }
    free(lam);
    *n_used = n;
    return med;
}

/* The dress: their rest garment (3D, seams unwelded: more vertices, the same faces in the same order)
 * gives each face its rest triangle, laid flat as corner_rest; their TFT base gives positions. */
typedef struct dress_out {
    int ok;
    int32_t nv, nf, n_theirs, n_ours, sqp_iters;
    double lam_theirs, lam_ours, lam_fit, amax_theirs, amax_ours, corr;
    double lam_var[N_VARIANTS];
    double lam_from_theirs, e_ratio_from_theirs; /* every release reading, SQP started from their fields */
    wr_status st;
} dress_out;

/* Every release reading on the dress, our SQP started from their shipped fields (their dress json starts
 * their solve from them too): the median wavelength where ours stops and E there / E at their fields. */
static void dress_from_theirs(const wr_mesh *m, const wr_wf_material *mat, const double *ta, const double *tom,
                              dress_out *o) {
    wr_wf wf;
    wr_wf_classify_desc cd;
    wr_wf_solve_desc sd;
    wr_wf_solve_stats ss;
    wr_diag d;
    double *a = (double *)malloc(sizeof(double) * (size_t)m->nv), *om = (double *)malloc(sizeof(double) * (size_t)m->ne);
    double e0 = NAN, e1 = NAN;
    int32_t nn;
    o->lam_from_theirs = o->e_ratio_from_theirs = NAN;
    if (a && om && wr_wf_create(&wf, m, m->pos, mat, &d) == WR_OK) {
        memset(&cd, 0, sizeof cd);
        memset(&sd, 0, sizeof sd);
        cd.rule = WR_WF_WSET_RELEASE;
        memcpy(a, ta, sizeof(double) * (size_t)m->nv);
        memcpy(om, tom, sizeof(double) * (size_t)m->ne);
        if (wr_wf_set_kappa(&wf, WR_WF_KAPPA_VERTEX_FIT, &d) == WR_OK && wr_wf_classify(&wf, &cd) >= 0) {
            wr_wf_energy(&wf, ta, tom, &e0, NULL, NULL, NULL, &d);
            if (wr_wf_solve(&wf, &sd, a, om, &ss, &d) <= WR_ERR_NOT_CONVERGED) {
                wr_wf_energy(&wf, a, om, &e1, NULL, NULL, NULL, &d);
                o->lam_from_theirs = median_wavelength(m, a, om, &nn);
                o->e_ratio_from_theirs = e1 / e0;
            }
        }
        wr_wf_free(&wf);
    }
    free(a);
    free(om);
}

static dress_out run_dress(const char *dir, wr_wf_kappa kappa_alt) {
    char p[4096];
    wr_mesh rest, base, m;
    wr_diag d;
    dress_out o;
    double *cr = NULL, *ta = NULL, *tdp = NULL, *tom = NULL;
    int32_t f, k;
    memset(&o, 0, sizeof o);
    memset(&m, 0, sizeof m);
    snprintf(p, sizeof p, "%s/dress2.obj", dir);
    if (wr_mesh_read_obj(&rest, p, &d)) return o;
    snprintf(p, sizeof p, "%s/dress2_simulated.obj", dir);
    if (wr_mesh_read_obj(&base, p, &d)) {
        wr_mesh_free(&rest);
        return o;
    }
    if (rest.nf == base.nf && wr_mesh_create(&m, base.nv, base.pos, NULL, base.nf, base.faces, &d) == WR_OK) {
        cr = (double *)malloc(sizeof(double) * 6 * (size_t)m.nf);
        for (f = 0; cr && f < m.nf; ++f) {
            /* wr_mesh_face_rest lays a 3D triangle flat isometrically (corner 0 at 0, corner 1 on +x) */
            wr_mesh tri;
            memset(&tri, 0, sizeof tri);
            tri.pos = rest.pos;
            tri.faces = rest.faces;
            wr_mesh_face_rest(&tri, f, cr + 6 * (size_t)f);
        }
        snprintf(p, sizeof p, "%s/dress2_amplitude_simulated.txt", dir);
        ta = read_column(p, m.nv);
        snprintf(p, sizeof p, "%s/dress2_dphi_simulated.txt", dir);
        tdp = read_column(p, m.ne);
        tom = tdp ? their_omega_on_our_edges(&m, tdp) : NULL;
    }
    if (cr && ta && tom && wr_mesh_set_corner_rest(&m, cr, &d) == WR_OK) {
        wr_wf_material mat;
        wr_tfw_desc td;
        wr_tfw_result r;
        double sa = 0, sb = 0, saa = 0, sbb = 0, sab = 0;
        mat.young = 1e5; /* their dress2_TFW.json */
        mat.poisson = 0.3;
        mat.thickness = 1e-3;
        memset(&td, 0, sizeof td);
        td.no_upsample = 1;
        o.nv = m.nv;
        o.nf = m.nf;
        o.lam_theirs = median_wavelength(&m, ta, tom, &o.n_theirs);
        for (k = 0; k < m.nv; ++k) o.amax_theirs = fmax(o.amax_theirs, ta[k]);
        o.st = wr_tfw_fields(&m, m.pos, &mat, &td, &r, &d);
        if (o.st == WR_OK || o.st == WR_ERR_NOT_CONVERGED) {
            o.lam_ours = median_wavelength(&m, r.a, r.omega, &o.n_ours);
            o.amax_ours = r.max_amplitude;
            o.sqp_iters = r.sqp.iterations;
            for (k = 0; k < m.nv; ++k) {
                sa += r.a[k];
                sb += ta[k];
                saa += r.a[k] * r.a[k];
                sbb += ta[k] * ta[k];
                sab += r.a[k] * ta[k];
            }
            o.corr = (sab - sa * sb / m.nv) / sqrt((saa - sa * sa / m.nv) * (sbb - sb * sb / m.nv));
            wr_tfw_result_free(&r);
            td.kappa = kappa_alt;
            if (wr_tfw_fields(&m, m.pos, &mat, &td, &r, &d) <= WR_ERR_NOT_CONVERGED) {
                int32_t nn;
                o.lam_fit = median_wavelength(&m, r.a, r.omega, &nn);
                wr_tfw_result_free(&r);
            }
            dress_from_theirs(&m, &mat, ta, tom, &o);
            for (k = 0; k < N_VARIANTS; ++k) {
                int32_t nn;
                o.lam_var[k] = NAN;
                variant_desc(&k_variants[k], &td);
                if (wr_tfw_fields(&m, m.pos, &mat, &td, &r, &d) <= WR_ERR_NOT_CONVERGED) {
                    o.lam_var[k] = median_wavelength(&m, r.a, r.omega, &nn);
                    wr_tfw_result_free(&r);
                }
            }
            o.ok = 1;
        } else {
            fprintf(stderr, "validate_tfw_release: dress TFW failed: %s\n", d.message);
        }
    }
    free(cr);
    free(ta);
    free(tdp);
    free(tom);
    wr_mesh_free(&m);
    wr_mesh_free(&rest);
    wr_mesh_free(&base);
    return o;
}

static int validation_main(void) {
    const char *dir = getenv("WR_TFW_RELEASE_DATA");
    char p_rest[4096], p_base[4096], p_clamp[4096], p_phi[4096], buf[512];
    double *their_om, *their_a;
    wr_mesh rest, base, m;
    wr_diag d;
    double *rest2, *their_phi, their_waves;
    uint8_t *clamped;
    int32_t v, n_clamped;
    run_out mid, fit, midc, var[N_VARIANTS];
    dress_out dr;
    int k;
    wr_vres *vr;
    if (!dir || !*dir) {
        printf("validate_tfw_release: skipped (set WR_TFW_RELEASE_DATA to a directory with the authors' disk files; "
               "validation/results/tfw_release.json is left as it is)\n");
        return 0;
    }
    snprintf(p_rest, sizeof p_rest, "%s/disk.obj", dir);
    snprintf(p_base, sizeof p_base, "%s/disk_simulated.obj", dir);
    snprintf(p_clamp, sizeof p_clamp, "%s/disc_clamped_vertices.dat", dir);
    snprintf(p_phi, sizeof p_phi, "%s/disk_dphi_simulated.txt", dir);
    if (wr_mesh_read_obj(&rest, p_rest, &d) || wr_mesh_read_obj(&base, p_base, &d)) {
        fprintf(stderr, "validate_tfw_release: %s\n", d.message);
        return 2;
    }
    if (rest.nv != base.nv || rest.nf != base.nf) {
        fprintf(stderr, "validate_tfw_release: rest and base meshes differ (%d/%d vertices)\n", (int)rest.nv, (int)base.nv);
        return 2;
    }
    rest2 = (double *)malloc(sizeof(double) * 2 * (size_t)rest.nv);
    for (v = 0; v < rest.nv; ++v) {
        rest2[2 * v] = rest.pos[3 * v];
        rest2[2 * v + 1] = rest.pos[3 * v + 1];
    }
    if (wr_mesh_create(&m, base.nv, base.pos, rest2, base.nf, base.faces, &d) != WR_OK || m.n_loops != 1) {
        fprintf(stderr, "validate_tfw_release: disk mesh: %s\n", m.n_loops != 1 ? "not one boundary loop" : d.message);
        return 2;
    }
    clamped = read_clamped(p_clamp, m.nv, &n_clamped);
    their_phi = read_column(p_phi, m.ne); /* their ω per edge */
    if (!clamped || !their_phi) {
        fprintf(stderr, "validate_tfw_release: cannot read %s or %s\n", p_clamp, p_phi);
        return 2;
    }
    their_om = their_omega_on_our_edges(&m, their_phi);
    their_waves = their_om ? tp_circulation(&m, their_om, m.loop_verts + m.loop_start[0], m.loop_start[1] - m.loop_start[0])
                           : NAN;
    snprintf(p_phi, sizeof p_phi, "%s/disk_amplitude_simulated.txt", dir);
    their_a = read_column(p_phi, m.nv);
    mid = run_tfw(&m, NULL, WR_WF_KAPPA_MIDEDGE, their_a, their_om);
    fit = run_tfw(&m, NULL, WR_WF_KAPPA_VERTEX_FIT, their_a, their_om);
    midc = run_tfw(&m, clamped, WR_WF_KAPPA_MIDEDGE, NULL, NULL);
    for (k = 0; k < N_VARIANTS; ++k) {
        var[k] = run_tfw_v(&m, NULL, &k_variants[k], their_a, their_om);
        fprintf(stderr, "disk, %s: %.2f waves (%d SQP it, |W| %d, unfolded %d); E ours %.6g, release fields %.6g\n",
                k_variants[k].name, var[k].waves, (int)var[k].sqp_iters, (int)var[k].n_w, (int)var[k].unfolded,
                var[k].e_ours, var[k].e_theirs);
    }
    free(their_om);
    free(their_a);
    fprintf(stderr, "E default: ours %.6g theirs %.6g; E release reading: ours %.6g theirs %.6g\n", mid.e_ours, mid.e_theirs,
            fit.e_ours, fit.e_theirs);
    fprintf(stderr, "release %.2f waves; ours mid-edge %.2f (%d SQP it), vertex fit %.2f (%d SQP it), mid-edge + a = 0 "
                    "on the rim %.2f\n",
            their_waves, mid.waves, (int)mid.sqp_iters, fit.waves, (int)fit.sqp_iters, midc.waves);
    dr = run_dress(dir, WR_WF_KAPPA_VERTEX_FIT);
    if (dr.ok)
        fprintf(stderr, "dress: median wavelength release %.1f mm (%d faces), ours %.1f mm (%d faces), vertex fit %.1f mm; "
                        "max a %.2f / %.2f mm; a correlation %.3f\n",
                1e3 * dr.lam_theirs, (int)dr.n_theirs, 1e3 * dr.lam_ours, (int)dr.n_ours, 1e3 * dr.lam_fit,
                1e3 * dr.amax_theirs, 1e3 * dr.amax_ours, dr.corr);
    vr = wr_vres_begin("tfw_release", "TFW against the authors' release on their pressurised disk (issue 16)");
    wr_vres_info(vr, "release: waves around the rim (their shipped omega)", "waves", NAN, their_waves);
    /* 5 %: the header's pass rule and its reasoning (same energy up to the curvature estimator). It was
     * committed together with the first result (-2.4 %, fc6bb6b), so the history cannot show that it
     * predates the result; it is the header's statement, not a derived or issue-given band. */
    wr_vres_check(vr, "ours, release reading (vertex quadric-fit kappa): waves around the rim", "waves", NAN, fit.waves,
                  "within 5 % of the release's count", fabs(fit.waves - their_waves) <= 0.05 * their_waves);
    wr_vres_info(vr, "ours, default reading (mid-edge II kappa): waves around the rim", "waves", NAN, mid.waves);
    wr_vres_info(vr, "ours / release, default reading", "", NAN, mid.waves / their_waves);
    wr_vres_info(vr, "ours / release, release reading", "", NAN, fit.waves / their_waves);
    wr_vres_info(vr, "E_wf (default reading) at our fields", "J", NAN, mid.e_ours);
    wr_vres_info(vr, "E_wf (default reading) at the release's fields", "J", NAN, mid.e_theirs);
    wr_vres_info(vr, "E_wf (release reading) at our fields", "J", NAN, fit.e_ours);
    wr_vres_info(vr, "E_wf (release reading) at the release's fields", "J", NAN, fit.e_theirs);
    wr_vres_info(vr, "max amplitude, default reading", "mm", NAN, 1e3 * mid.amax);
    wr_vres_info(vr, "max amplitude, release reading", "mm", NAN, 1e3 * fit.amax);
    wr_vres_info(vr, "SQP iterations, default / release reading", "", NAN, mid.sqp_iters);
    wr_vres_info(vr, "SQP iterations, release reading", "", NAN, fit.sqp_iters);
    wr_vres_info(vr, "TFW seconds, default reading", "s", NAN, mid.seconds);
    wr_vres_info(vr, "ours, mid-edge kappa with a = 0 on the clamped rim (our former set-up): waves", "waves", NAN,
                 midc.waves);
    for (k = 0; k < N_VARIANTS; ++k) {
        snprintf(buf, sizeof buf, "ours, %s: waves around the rim", k_variants[k].name);
        wr_vres_info(vr, buf, "waves", NAN, var[k].waves);
        snprintf(buf, sizeof buf, "E_wf (%s) at our fields / at the release's fields", k_variants[k].name);
        wr_vres_info(vr, buf, "", NAN, var[k].e_ours / var[k].e_theirs);
    }
    if (dr.ok) {
        wr_vres_info(vr, "dress: release median wavelength (faces with a >= 0.2 max a)", "mm", NAN, 1e3 * dr.lam_theirs);
        wr_vres_info(vr, "dress: ours, default reading, median wavelength", "mm", NAN, 1e3 * dr.lam_ours);
        wr_vres_info(vr, "dress: ours, release reading (vertex fit), median wavelength", "mm", NAN, 1e3 * dr.lam_fit);
        wr_vres_info(vr, "dress: ours / release wavelength, default reading", "", NAN, dr.lam_ours / dr.lam_theirs);
        wr_vres_info(vr, "dress: ours / release wavelength, release reading", "", NAN, dr.lam_fit / dr.lam_theirs);
        /* the release's value is a reference, not a paper value (issue 20: the paper column holds
         * only printed numbers) */
        wr_vres_info(vr, "dress: max amplitude, ours (default) against the release's shipped fields", "mm", NAN,
                     1e3 * dr.amax_ours);
        wr_vres_reference(vr, 1e3 * dr.amax_theirs, "the authors' release: max a of its shipped dress2 fields");
        wr_vres_info(vr, "dress: amplitude correlation ours (default) vs release", "", NAN, dr.corr);
        wr_vres_info(vr, "dress: every release reading, SQP from the release's fields: median wavelength", "mm", NAN,
                     1e3 * dr.lam_from_theirs);
        wr_vres_info(vr, "dress: every release reading, SQP from the release's fields: E there / E at their fields", "",
                     NAN, dr.e_ratio_from_theirs);
        fprintf(stderr, "dress, every release reading, from their fields: %.1f mm, E ratio %.9f\n",
                1e3 * dr.lam_from_theirs, dr.e_ratio_from_theirs);
        for (k = 0; k < N_VARIANTS; ++k) {
            snprintf(buf, sizeof buf, "dress: ours, %s, median wavelength", k_variants[k].name);
            wr_vres_info(vr, buf, "mm", NAN, 1e3 * dr.lam_var[k]);
            fprintf(stderr, "dress, %s: median wavelength %.1f mm\n", k_variants[k].name, 1e3 * dr.lam_var[k]);
        }
    }
    snprintf(buf, sizeof buf,
             "Their disk: %d vertices, %d faces, %d clamped rim vertices; E 1e7 Pa, nu 0.44, h 0.1 mm (their disk_TFW.json). "
             "Files read from $WR_TFW_RELEASE_DATA, copied from a checkout of the authors' public repository; "
             "nothing of theirs is in this tree.",
             (int)m.nv, (int)m.nf, (int)n_clamped);
    wr_vres_note(vr, buf);
    wr_vres_note(vr, "Eq. 22 term by term: the release evaluates W_s^2 as 0.5 ||2a sqrt(beta/(alpha+2beta)) kappa (t^T I t) Id||^2_SV "
                     "= 4 a^2 kappa^2 beta(alpha+beta)/(alpha+2beta) (t^T I t)^2, the printed Eq. 22 (same prefactor as ours); it "
                     "differs in kappa: per-vertex principal curvatures of a quadric fit over 5-rings, Euler's formula along "
                     "the tension direction at each corner, averaged over the face, and the term only on faces in mixed "
                     "tension/compression. Ours by default: the App. A mid-edge II per face, which on a boundary edge has only "
                     "the face's own normal and so under-reads the rim's curvature, where the disk wrinkles.");
    free(rest2);
    free(their_phi);
    free(clamped);
    wr_mesh_free(&m);
    wr_mesh_free(&rest);
    wr_mesh_free(&base);
    return wr_vres_finish(vr) < 0 ? 1 : 0;
}

int main(int argc, char **argv) {
    int rc = wr_vargs(argc, argv, "validate_tfw_release",
                      "TFW against the authors' release on their pressurised disk ($WR_TFW_RELEASE_DATA).",
                      "tfw_release", NULL, NULL, NULL);
    return rc >= 0 ? rc : validation_main();
}
