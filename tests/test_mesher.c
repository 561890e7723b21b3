#define _POSIX_C_SOURCE 200809L /* mkdtemp for the output-directory test */
/* Tests for wrinkle/mesher.h (pattern → mesh pipeline) and the pattern JSON reader
 * (drivers/lib/pattern.h). */
#include <criterion/criterion.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "pattern.h"
#include "wrinkle/mesher.h"

static double sq250[8] = {0, 0, 0.25, 0, 0.25, 0.25, 0, 0.25};

static void one_panel(wr_pattern *pat, wr_pattern_panel *pn, const double *outer, int32_t n) {
    memset(pat, 0, sizeof *pat);
    memset(pn, 0, sizeof *pn);
    pn->outer.xy = outer;
    pn->outer.n = n;
    pn->name = "p";
    pn->fabric.B = 2.6e-6; /* Table 1 Green: r = 6.0 mm */
    pn->fabric.E = 2.0e6;
    pat->panels = pn;
    pat->n_panels = 1;
}

/* Is (a, b) an edge of the mesh? */
static int has_edge(const wr_mesh *m, int32_t a, int32_t b) {
    int32_t k, c;
    for (k = m->vf_start[a]; k < m->vf_start[a + 1]; ++k) {
        int32_t f = m->vf[k];
        for (c = 0; c < 3; ++c)
            if (m->faces[3 * f + c] == b) return 1;
    }
    return 0;
}

static void expect_every_constraint_present(const wr_mesher_result *r) {
    int32_t i, missing = 0;
    for (i = 0; i < r->n_constraint_segments; ++i)
        missing += !has_edge(&r->mesh, r->constraint_segments[2 * i], r->constraint_segments[2 * i + 1]);
    cr_expect_eq(missing, 0, "%d of %d constraint segments are not mesh edges", missing, r->n_constraint_segments);
}

/* The mesher's output for an isotropic single-panel pattern (T = I: mesh coordinates are the CDT's)
 * as a wr_cdt_result, so wr_cdt_check verifies it exactly: every triangle CCW, every unconstrained
 * interior edge locally Delaunay, every constraint segment an edge, Euler. */
static wr_status check_as_cdt(const wr_mesher_result *r, int32_t holes, wr_diag *d) {
    const wr_mesh *m = &r->mesh;
    wr_cdt_result c;
    int32_t *seg_of_edge = (int32_t *)calloc((size_t)m->ne, sizeof(int32_t)), f, k, s, e;
    wr_status st;
    memset(&c, 0, sizeof c);
    c.n_points = c.n_input_points = m->nv;
    c.points = m->rest;
    c.point_segment = (int32_t *)malloc(sizeof(int32_t) * (size_t)m->nv);
    c.n_triangles = m->nf;
    c.triangles = m->faces;
    c.neighbors = (int32_t *)malloc(sizeof(int32_t) * 3 * (size_t)m->nf);
    c.edge_segment = (int32_t *)malloc(sizeof(int32_t) * 3 * (size_t)m->nf);
    c.segment_id = (int32_t *)malloc(sizeof(int32_t) * (size_t)(r->n_constraint_segments + 1));
    cr_assert(seg_of_edge && c.point_segment && c.neighbors && c.edge_segment && c.segment_id);
    for (k = 0; k < m->nv; ++k) c.point_segment[k] = -1;
    for (e = 0; e < m->ne; ++e) seg_of_edge[e] = -1;
    for (s = 0; s < r->n_constraint_segments; ++s) {
        int32_t a = r->constraint_segments[2 * s], b = r->constraint_segments[2 * s + 1], j;
        c.segment_id[s] = s;
        for (j = m->vf_start[a]; j < m->vf_start[a + 1]; ++j)
            for (k = 0; k < 3; ++k) {
                int32_t ee = m->face_edges[3 * m->vf[j] + k];
                if ((m->edges[2 * ee] == a && m->edges[2 * ee + 1] == b) || (m->edges[2 * ee] == b && m->edges[2 * ee + 1] == a))
                    seg_of_edge[ee] = s;
            }
    }
    for (f = 0; f < m->nf; ++f)
        for (k = 0; k < 3; ++k) {
            e = m->face_edges[3 * f + k];
            c.neighbors[3 * f + k] = m->edge_faces[2 * e] == f ? m->edge_faces[2 * e + 1] : m->edge_faces[2 * e];
            c.edge_segment[3 * f + k] = seg_of_edge[e];
        }
    c.segments = c.input_segments = r->constraint_segments;
    c.n_segments = c.n_input_segments = r->n_constraint_segments;
    c.exterior_carved = 1;
    c.holes_carved = holes > 0;
    st = wr_cdt_check(&c, holes, NULL, d);
    free(seg_of_edge);
    free(c.point_segment);
    free(c.neighbors);
    free(c.edge_segment);
    free(c.segment_id);
    return st;
}

/* The 250 mm square with a hole, a shirring line and a fold (line + two parallels). */
typedef struct hole_line_fold {
    double hxy[8], line[6], fl[4];
    wr_pattern pat;
    wr_pattern_panel pn;
    wr_pattern_curve hole;
    wr_pattern_shirring sh;
    wr_pattern_fold fd;
} hole_line_fold;

static void make_hole_line_fold(hole_line_fold *t) {
    const double hxy[8] = {0.15, 0.15, 0.2, 0.15, 0.2, 0.2, 0.15, 0.2};
    const double line[6] = {0.03, 0.1, 0.125, 0.14, 0.22, 0.1}, fl[4] = {0.05, 0.04, 0.2, 0.06};
    memset(t, 0, sizeof *t);
    memcpy(t->hxy, hxy, sizeof hxy);
    memcpy(t->line, line, sizeof line);
    memcpy(t->fl, fl, sizeof fl);
    one_panel(&t->pat, &t->pn, sq250, 4);
    t->hole.xy = t->hxy;
    t->hole.n = 4;
    t->pn.holes = &t->hole;
    t->pn.n_holes = 1;
    t->sh.xy = t->line;
    t->sh.n = 3;
    t->sh.E_sh = 2.0e6;
    t->sh.rho = 0.5;
    t->fd.xy = t->fl;
    t->fd.n = 2;
    t->fd.angle_deg = 180.0;
    t->pat.shirrings = &t->sh;
    t->pat.n_shirrings = 1;
    t->pat.folds = &t->fd;
    t->pat.n_folds = 1;
}

Test(mesher, output_is_a_constrained_delaunay_triangulation) {
    /* a hole, a shirring line and a fold (line + two parallels): the sampler fills between our own
     * curves, and the CDT of the result is what the mesher hands back */
    hole_line_fold t;
    wr_mesher_result r;
    wr_diag d;
    int k;
    make_hole_line_fold(&t);
    cr_assert_eq(wr_mesher_run(&t.pat, NULL, &r, &d), WR_OK, "%s", d.message);
    for (k = 0; k < 4; ++k) cr_assert_eq(r.panels[0].T[k], k == 0 || k == 3 ? 1.0 : 0.0, "isotropic: T = I");
    cr_expect_eq(check_as_cdt(&r, 1, &d), WR_OK, "%s", d.message);
    cr_expect_eq(r.report.n_inverted + r.report.n_zero_area, 0);
    wr_mesher_free(&r);
}

Test(mesher, constant_sizing_square_edge_length_and_count) {
    wr_pattern pat;
    wr_pattern_panel pn;
    wr_mesher_result r;
    wr_diag d;
    double h = 10e-3, expect_nv;
    one_panel(&pat, &pn, sq250, 4);
    pn.fabric.resolution = h; /* explicit base resolution override */
    cr_assert_eq(wr_mesher_run(&pat, NULL, &r, &d), WR_OK, "%s", d.message);
    /* mean edge length within ±10% of the sizing (the calibration the issue asks for) */
    cr_expect(fabs(r.report.ratio_mean - 1.0) < 0.10, "mean edge/sizing %.3f", r.report.ratio_mean);
    cr_expect(fabs(r.report.ratio_interior_mean - 1.0) < 0.10, "interior mean edge/sizing %.3f",
              r.report.ratio_interior_mean);
    /* equilateral density 2/(√3 h²) plus the boundary: within ±20% */
    expect_nv = 2.0 / (sqrt(3.0) * h * h) * 0.0625 + 4 * 0.25 / h / 2;
    cr_expect(fabs(r.mesh.nv / expect_nv - 1.0) < 0.2, "nv %d vs %.0f", r.mesh.nv, expect_nv);
    cr_expect_eq(r.report.n_inverted, 0);
    cr_expect_eq(r.report.n_zero_area, 0);
    cr_expect_gt(r.report.min_angle_deg, 15.0);
    cr_expect(fabs(r.report.min_angle_metric_deg - r.report.min_angle_deg) < 1e-9); /* isotropic: T = I */
    cr_expect_eq(r.mesh.n_loops, 1);
    cr_expect_eq(r.mesh.nv - r.mesh.ne + r.mesh.nf, 1); /* a disk */
    cr_expect(fabs(r.sizing[0] - h) < 1e-15);
    cr_expect_not_null(r.mesh.face_panel);
    cr_expect_not_null(r.mesh.rest);
    wr_mesher_free(&r);
}

/* The report's angles (atan2 of cross and dot, the smallest by its own series) equal
 * wr_mesh_quality's (acos of the cosine rule, accurate on these 30-120 deg faces to ~1e-12 deg). */
Test(mesher, report_angles_equal_mesh_quality) {
    wr_pattern pat;
    wr_pattern_panel pn;
    wr_mesher_result r;
    wr_mesh_quality_stats q;
    wr_diag d;
    one_panel(&pat, &pn, sq250, 4);
    pn.fabric.resolution = 10e-3;
    cr_assert_eq(wr_mesher_run(&pat, NULL, &r, &d), WR_OK, "%s", d.message);
    wr_mesh_quality(&r.mesh, 1, &q);
    cr_expect(fabs(r.report.min_angle_deg - q.min_angle_deg) < 1e-9, "%.15g vs %.15g", r.report.min_angle_deg,
              q.min_angle_deg);
    cr_expect(fabs(r.report.max_angle_deg - q.max_angle_deg) < 1e-9, "%.15g vs %.15g", r.report.max_angle_deg,
              q.max_angle_deg);
    cr_expect(fabs(r.report.mean_min_angle_deg - q.mean_min_angle_deg) < 1e-9, "%.15g vs %.15g",
              r.report.mean_min_angle_deg, q.mean_min_angle_deg);
    wr_mesher_free(&r);
}

Test(mesher, base_resolution_from_eq4_and_uniform_mode) {
    wr_pattern pat;
    wr_pattern_panel pn;
    wr_mesher_result r, u;
    wr_mesher_desc desc;
    one_panel(&pat, &pn, sq250, 4);
    cr_assert_eq(wr_mesher_run(&pat, NULL, &r, NULL), WR_OK);
    cr_expect(fabs(r.panels[0].r0 - 6.03e-3) < 0.05e-3, "r0 = %g", r.panels[0].r0); /* Table 1: 6.00 mm */
    memset(&desc, 0, sizeof desc);
    desc.uniform_resolution = 12e-3;
    cr_assert_eq(wr_mesher_run(&pat, &desc, &u, NULL), WR_OK);
    cr_expect_lt(u.mesh.nv, r.mesh.nv / 3); /* (12/6)^2 = 4× fewer */
    wr_mesher_free(&r);
    wr_mesher_free(&u);
}

Test(mesher, deterministic_for_a_seed) {
    wr_pattern pat;
    wr_pattern_panel pn;
    wr_mesher_result a, b;
    wr_mesher_desc desc;
    one_panel(&pat, &pn, sq250, 4);
    pn.fabric.resolution = 15e-3;
    memset(&desc, 0, sizeof desc);
    desc.seed = 5;
    cr_assert_eq(wr_mesher_run(&pat, &desc, &a, NULL), WR_OK);
    cr_assert_eq(wr_mesher_run(&pat, &desc, &b, NULL), WR_OK);
    cr_assert_eq(a.mesh.nv, b.mesh.nv);
    cr_assert_eq(a.mesh.nf, b.mesh.nf);
    cr_expect_eq(memcmp(a.mesh.rest, b.mesh.rest, sizeof(double) * 2 * (size_t)a.mesh.nv), 0);
    wr_mesher_free(&a);
    wr_mesher_free(&b);
}

Test(mesher, shirring_and_fold_constraints_present_and_sizing) {
    wr_pattern pat;
    wr_pattern_panel pn;
    wr_pattern_shirring sh;
    wr_pattern_fold fd;
    wr_mesher_result r;
    wr_diag d;
    double line[6] = {0.03, 0.06, 0.125, 0.08, 0.22, 0.06};
    double fold[8] = {0.03, 0.17, 0.12, 0.17, 0.13, 0.18, 0.14, 0.17};
    double rsh, rf, s_end, s_behind;
    wr_resolution_model mdl = wr_resolution_model_paper();
    one_panel(&pat, &pn, sq250, 4);
    memset(&sh, 0, sizeof sh);
    sh.panel = 0;
    sh.xy = line;
    sh.n = 3;
    sh.E_sh = 2.0e6;
    sh.rho = 0.5;
    memset(&fd, 0, sizeof fd);
    fd.panel = 0;
    fd.xy = fold;
    fd.n = 4;
    pat.shirrings = &sh;
    pat.n_shirrings = 1;
    pat.folds = &fd;
    pat.n_folds = 1;
    cr_assert_eq(wr_mesher_run(&pat, NULL, &r, &d), WR_OK, "%s", d.message);
    expect_every_constraint_present(&r);
    /* boundary (4 sides) + shirring line + fold line + 2 parallels are all constraint chains */
    cr_expect_gt(r.n_constraint_segments, 40);
    /* Sec. 4.2.2: r_sh = ρ r(B/(E+E_sh)) on the line */
    cr_assert_eq(wr_resolution_from_BE(&mdl, 2.6e-6, 4.0e6, NULL, &rsh, NULL), WR_OK);
    cr_expect(fabs(wr_mesher_eval_sizing(&r, 0, 0.125, 0.08) - 0.5 * rsh) < 1e-9);
    rf = r.panels[0].r0;
    cr_expect(fabs(wr_mesher_eval_sizing(&r, 0, 0.125, 0.24) - rf) < 1e-12, "far from sources: r_f");
    /* Sec. 4.2.3: r_fd = (180/360) r_ng at the endpoint; directional: only the forward side (into
     * the fold, +x here) is refined, the point just behind the endpoint keeps the map's value */
    s_end = wr_mesher_eval_sizing(&r, 0, 0.03, 0.17);
    cr_expect(fabs(s_end - 0.5 * rf) < 1e-9, "endpoint %g vs %g", s_end, 0.5 * rf);
    s_behind = wr_mesher_eval_sizing(&r, 0, 0.029, 0.17);
    cr_expect(fabs(s_behind - rf) < 1e-12, "behind the endpoint %g", s_behind);
    cr_expect_lt(wr_mesher_eval_sizing(&r, 0, 0.031, 0.17), rf);
    /* the mesh follows its sizing on average */
    cr_expect(fabs(r.report.ratio_mean - 1.0) < 0.10, "ratio %.3f", r.report.ratio_mean);
    wr_mesher_free(&r);
}

Test(mesher, fold_parallel_lines_at_offset) {
    wr_pattern pat;
    wr_pattern_panel pn;
    wr_pattern_fold fd;
    wr_mesher_result r;
    wr_diag d;
    double fold[4] = {0.05, 0.125, 0.20, 0.125};
    int32_t v, above = 0, below = 0, on = 0;
    one_panel(&pat, &pn, sq250, 4);
    memset(&fd, 0, sizeof fd);
    fd.panel = 0;
    fd.xy = fold;
    fd.n = 2;
    fd.offset = 1.0e-3;
    pat.folds = &fd;
    pat.n_folds = 1;
    cr_assert_eq(wr_mesher_run(&pat, NULL, &r, &d), WR_OK, "%s", d.message);
    expect_every_constraint_present(&r);
    for (v = 0; v < r.mesh.nv; ++v) {
        double x = r.mesh.rest[2 * v], y = r.mesh.rest[2 * v + 1];
        if (x < 0.05 - 1e-12 || x > 0.20 + 1e-12) continue;
        if (fabs(y - 0.126) < 1e-12) ++above;
        if (fabs(y - 0.124) < 1e-12) ++below;
        if (fabs(y - 0.125) < 1e-12) ++on;
    }
    cr_expect_geq(above, 2);
    cr_expect_geq(below, 2);
    cr_expect_geq(on, 2);
    wr_mesher_free(&r);
}

/* Two panels, long (300 mm) top edge of A sewn to short (200 mm) bottom edge of B. */
typedef struct two_panels {
    double a[8], b[8];
    wr_pattern_panel pn[2];
    wr_pattern_seam se;
    wr_pattern pat;
} two_panels;

static void make_two(two_panels *t) {
    double a[8] = {0, 0, 0.3, 0, 0.3, 0.15, 0, 0.15}, b[8] = {0.05, 0.2, 0.25, 0.2, 0.25, 0.35, 0.05, 0.35};
    int k;
    memset(t, 0, sizeof *t);
    memcpy(t->a, a, sizeof a);
    memcpy(t->b, b, sizeof b);
    for (k = 0; k < 2; ++k) {
        t->pn[k].outer.xy = k ? t->b : t->a;
        t->pn[k].outer.n = 4;
        t->pn[k].fabric.B = 2.0e-6; /* Wine Style, 7.83 mm */
        t->pn[k].fabric.E = 3.0e5;
        t->pn[k].name = k ? "short" : "long";
    }
    t->se.a.panel = 0;
    t->se.a.from[0] = 0.0;
    t->se.a.from[1] = 0.15;
    t->se.a.to[0] = 0.3;
    t->se.a.to[1] = 0.15;
    t->se.a.reverse = 1;
    t->se.b.panel = 1;
    t->se.b.from[0] = 0.05;
    t->se.b.from[1] = 0.2;
    t->se.b.to[0] = 0.25;
    t->se.b.to[1] = 0.2;
    t->pat.panels = t->pn;
    t->pat.n_panels = 2;
    t->pat.seams = &t->se;
    t->pat.n_seams = 1;
}

Test(mesher, seam_sides_equal_counts_in_order_long_side_refined) {
    two_panels t;
    wr_mesher_result r;
    wr_diag d;
    int32_t i, n;
    double rf;
    make_two(&t);
    cr_assert_eq(wr_mesher_run(&t.pat, NULL, &r, &d), WR_OK, "%s", d.message);
    n = r.n_seam_pairs;
    cr_assert_gt(n, 10);
    for (i = 0; i < n; ++i) {
        int32_t va = r.seam_pairs[2 * i], vb = r.seam_pairs[2 * i + 1];
        cr_assert_eq(r.seam_pair_seam[i], 0);
        cr_expect(fabs(r.mesh.rest[2 * va + 1] - 0.15) < 1e-12, "side a vertex off its edge");
        cr_expect(fabs(r.mesh.rest[2 * vb + 1] - 0.2) < 1e-12, "side b vertex off its edge");
        cr_expect(va >= r.panels[0].v_begin && va < r.panels[0].v_end);
        cr_expect(vb >= r.panels[1].v_begin && vb < r.panels[1].v_end);
        if (i > 0) {
            /* monotone from→to on both sides, and consecutive pairs are mesh edges (no vertex between) */
            cr_expect_gt(r.mesh.rest[2 * va], r.mesh.rest[2 * r.seam_pairs[2 * i - 2]]);
            cr_expect_gt(r.mesh.rest[2 * vb], r.mesh.rest[2 * r.seam_pairs[2 * i - 1]]);
            cr_expect(has_edge(&r.mesh, va, r.seam_pairs[2 * i - 2]));
            cr_expect(has_edge(&r.mesh, vb, r.seam_pairs[2 * i - 1]));
        }
    }
    /* ends paired from↔from and to↔to */
    cr_expect(fabs(r.mesh.rest[2 * r.seam_pairs[0]] - 0.0) < 1e-12);
    cr_expect(fabs(r.mesh.rest[2 * r.seam_pairs[1]] - 0.05) < 1e-12);
    cr_expect(fabs(r.mesh.rest[2 * r.seam_pairs[2 * n - 2]] - 0.3) < 1e-12);
    cr_expect(fabs(r.mesh.rest[2 * r.seam_pairs[2 * n - 1]] - 0.25) < 1e-12);
    /* Sec. 4.2.4: ρ_s = 200/300 on the LONGER side only */
    rf = r.panels[0].r0;
    cr_expect(fabs(wr_mesher_eval_sizing(&r, 0, 0.15, 0.15) - (2.0 / 3.0) * rf) < 1e-9);
    cr_expect(fabs(wr_mesher_eval_sizing(&r, 1, 0.15, 0.2) - r.panels[1].r0) < 1e-12);
    /* the long side's own count: 300 mm at (2/3) r_f */
    cr_expect(abs((n - 1) - (int)lround(0.3 / ((2.0 / 3.0) * rf))) <= 1, "N = %d", n - 1);
    expect_every_constraint_present(&r);
    wr_mesher_free(&r);
}

Test(mesher, sew_merges_pairs_with_corner_rest) {
    two_panels t;
    wr_mesher_result r, s;
    wr_mesher_desc desc;
    wr_diag d;
    make_two(&t);
    memset(&desc, 0, sizeof desc);
    cr_assert_eq(wr_mesher_run(&t.pat, &desc, &r, &d), WR_OK, "%s", d.message);
    desc.sew = 1;
    cr_assert_eq(wr_mesher_run(&t.pat, &desc, &s, &d), WR_OK, "%s", d.message);
    cr_expect_eq(s.mesh.nv, r.mesh.nv - r.n_seam_pairs);
    cr_expect_eq(s.mesh.nf, r.mesh.nf);
    cr_expect_null(s.mesh.rest);
    cr_expect_not_null(s.mesh.corner_rest);
    cr_expect_eq(r.mesh.n_loops, 2);
    cr_expect_eq(s.mesh.n_loops, 1);
    cr_expect_eq(s.seam_pairs[0], s.seam_pairs[1]);
    /* the same pairing direction on both sides cannot be sewn orientably */
    t.se.b.reverse = 1;
    t.se.b.from[0] = 0.25;
    t.se.b.to[0] = 0.05;
    wr_mesher_free(&s);
    cr_expect_eq(wr_mesher_run(&t.pat, &desc, &s, &d), WR_ERR_TOPOLOGY);
    cr_expect(strstr(d.message, "sewing") != NULL, "%s", d.message);
    wr_mesher_free(&r);
}

/* The report's edge ratios, recomputed edge by edge: every edge counted once (the histogram holds
 * ne entries), the same mean / interior mean / extremes. Each edge's vector is taken in its first
 * face (edge_faces) from that face's rest corners (corner_rest when sewn). */
static void expect_ratios_per_edge(const wr_mesher_result *r) {
    const wr_mesh *M = &r->mesh;
    double sum = 0.0, sum_int = 0.0, lo = HUGE_VAL, hi = 0.0;
    int32_t e, n_int = 0, n_hist = 0, k;
    char *bnd = (char *)calloc((size_t)M->nv, 1);
    cr_assert_not_null(bnd);
    for (e = 0; e < M->n_loops; ++e)
        for (k = M->loop_start[e]; k < M->loop_start[e + 1]; ++k) bnd[M->loop_verts[k]] = 1;
    for (e = 0; e < 2 * r->n_constraint_segments; ++e) bnd[r->constraint_segments[e]] = 1;
    for (e = 0; e < M->ne; ++e) {
        int32_t a = M->edges[2 * e], b = M->edges[2 * e + 1], f = M->edge_faces[2 * e] >= 0 ? M->edge_faces[2 * e] : M->edge_faces[2 * e + 1];
        int32_t ca = 0, cb = 0;
        const double *T = r->panels[M->face_panel[f]].T;
        double uv[6], dx, dy, mx, my, ratio;
        wr_mesh_face_rest(M, f, uv);
        for (k = 0; k < 3; ++k) {
            if (M->faces[3 * f + k] == a) ca = k;
            if (M->faces[3 * f + k] == b) cb = k;
        }
        dx = uv[2 * cb] - uv[2 * ca];
        dy = uv[2 * cb + 1] - uv[2 * ca + 1];
        mx = T[0] * dx + T[1] * dy;
        my = T[2] * dx + T[3] * dy;
        ratio = sqrt(mx * mx + my * my) / (0.5 * (r->sizing[a] + r->sizing[b]));
        sum += ratio;
        if (!bnd[a] && !bnd[b]) sum_int += ratio, ++n_int;
        if (ratio < lo) lo = ratio;
        if (ratio > hi) hi = ratio;
    }
    for (k = 0; k < WR_MESHER_HIST_BINS; ++k) n_hist += r->report.ratio_hist[k];
    cr_expect_eq(n_hist, M->ne, "histogram holds %d edges, the mesh has %d", n_hist, M->ne);
    cr_expect(fabs(r->report.ratio_mean - sum / M->ne) < 1e-12, "mean %.17g vs %.17g", r->report.ratio_mean, sum / M->ne);
    cr_expect(fabs(r->report.ratio_interior_mean - sum_int / n_int) < 1e-12, "interior mean %.17g vs %.17g",
              r->report.ratio_interior_mean, sum_int / n_int);
    cr_expect(r->report.ratio_min == lo && r->report.ratio_max == hi, "min %.17g vs %.17g, max %.17g vs %.17g",
              r->report.ratio_min, lo, r->report.ratio_max, hi);
    free(bnd);
}

Test(mesher, report_counts_every_edge_once) {
    two_panels t;
    wr_pattern pat;
    wr_pattern_panel pn;
    wr_mesher_result r;
    wr_mesher_desc desc;
    wr_diag d;
    one_panel(&pat, &pn, sq250, 4);
    pn.fabric.resolution = 10e-3;
    cr_assert_eq(wr_mesher_run(&pat, NULL, &r, &d), WR_OK, "%s", d.message);
    expect_ratios_per_edge(&r);
    wr_mesher_free(&r);
    make_two(&t); /* two panels with a seam, unsewn and sewn (corner_rest) */
    memset(&desc, 0, sizeof desc);
    cr_assert_eq(wr_mesher_run(&t.pat, &desc, &r, &d), WR_OK, "%s", d.message);
    expect_ratios_per_edge(&r);
    wr_mesher_free(&r);
    desc.sew = 1;
    cr_assert_eq(wr_mesher_run(&t.pat, &desc, &r, &d), WR_OK, "%s", d.message);
    expect_ratios_per_edge(&r);
    wr_mesher_free(&r);
}

Test(mesher, anisotropic_edges_follow_warp_and_weft) {
    wr_pattern pat;
    wr_pattern_panel pn;
    wr_mesher_result r, u;
    wr_mesher_desc desc;
    wr_diag d;
    int32_t e, n_w = 0, n_f = 0;
    double s_w = 0.0, s_f = 0.0, lens_warp, ang = 0.5235987755982988; /* grain 30° */
    double rw, rf;
    one_panel(&pat, &pn, sq250, 4);
    pn.fabric.anisotropic = 1;
    pn.fabric.resolution_warp = 12e-3;
    pn.fabric.resolution_weft = 4e-3;
    pn.fabric.grain_angle = ang;
    cr_assert_eq(wr_mesher_run(&pat, NULL, &r, &d), WR_OK, "%s", d.message);
    rw = r.panels[0].r_warp;
    rf = r.panels[0].r_weft;
    cr_expect(fabs(rw - 12e-3) < 1e-15 && fabs(rf - 4e-3) < 1e-15);
    /* edges within 20° of the warp average ≈ r_warp; within 20° of the weft ≈ r_weft (interior) */
    for (e = 0; e < r.mesh.ne; ++e) {
        int32_t a = r.mesh.edges[2 * e], b = r.mesh.edges[2 * e + 1];
        double dx = r.mesh.rest[2 * b] - r.mesh.rest[2 * a], dy = r.mesh.rest[2 * b + 1] - r.mesh.rest[2 * a + 1];
        double L = sqrt(dx * dx + dy * dy), cw = fabs(dx * cos(ang) + dy * sin(ang)) / L;
        double mx = r.mesh.rest[2 * a], my = r.mesh.rest[2 * a + 1];
        if (mx < 0.03 || mx > 0.22 || my < 0.03 || my > 0.22) continue;
        if (cw > cos(20.0 * 3.141592653589793 / 180.0)) {
            s_w += L;
            ++n_w;
        } else if (cw < sin(20.0 * 3.141592653589793 / 180.0)) {
            s_f += L;
            ++n_f;
        }
    }
    cr_assert_gt(n_w, 10);
    cr_assert_gt(n_f, 10);
    lens_warp = s_w / n_w;
    cr_expect(fabs(lens_warp / rw - 1.0) < 0.2, "warp-aligned edges %.2f mm vs %.2f", 1e3 * lens_warp, 1e3 * rw);
    cr_expect(fabs((s_f / n_f) / rf - 1.0) < 0.2, "weft-aligned edges %.2f mm vs %.2f", 1e3 * s_f / n_f, 1e3 * rf);
    cr_expect(fabs(r.report.ratio_mean - 1.0) < 0.1, "metric ratio %.3f", r.report.ratio_mean);
    /* far fewer vertices than uniform fine (4 mm everywhere): about r_warp/r_weft = 3× */
    memset(&desc, 0, sizeof desc);
    desc.uniform_resolution = 4e-3;
    cr_assert_eq(wr_mesher_run(&pat, &desc, &u, NULL), WR_OK);
    cr_expect_lt(r.mesh.nv * 2, u.mesh.nv, "aniso %d vs uniform fine %d", r.mesh.nv, u.mesh.nv);
    cr_expect_eq(r.report.n_inverted, 0);
    /* near-equilateral in the metric, stretched in the pattern */
    cr_expect_gt(r.report.mean_min_angle_metric_deg, 35.0, "%.1f", r.report.mean_min_angle_metric_deg);
    cr_expect_lt(r.report.mean_min_angle_deg, r.report.mean_min_angle_metric_deg - 5.0);
    wr_mesher_free(&r);
    wr_mesher_free(&u);
}

Test(mesher, holes_quilt_collision) {
    wr_pattern pat;
    wr_pattern_panel pn;
    wr_pattern_curve hole;
    wr_pattern_quilt q;
    wr_pattern_curve ql[1];
    wr_pattern_collision c;
    wr_mesher_result r;
    wr_diag d;
    double hxy[8] = {0.15, 0.15, 0.2, 0.15, 0.2, 0.2, 0.15, 0.2};
    double stitch[4] = {0.0, 0.1, 0.25, 0.1}; /* edge to edge */
    double rf;
    int32_t f;
    one_panel(&pat, &pn, sq250, 4);
    pn.fabric.resolution = 8e-3;
    hole.xy = hxy;
    hole.n = 4;
    pn.holes = &hole;
    pn.n_holes = 1;
    memset(&q, 0, sizeof q);
    ql[0].xy = stitch;
    ql[0].n = 2;
    q.panel = 0;
    q.lines = ql;
    q.n_lines = 1;
    q.rho = 0.8;
    q.pressure = 1.0;
    memset(&c, 0, sizeof c);
    c.panel = 0;
    c.center[0] = 0.06;
    c.center[1] = 0.19;
    c.radius = 0.03;
    c.compression = 0.5;
    pat.quilts = &q;
    pat.n_quilts = 1;
    pat.collisions = &c;
    pat.n_collisions = 1;
    cr_assert_eq(wr_mesher_run(&pat, NULL, &r, &d), WR_OK, "%s", d.message);
    rf = r.panels[0].r0;
    cr_expect_eq(r.mesh.n_loops, 2);
    cr_expect_eq(r.mesh.nv - r.mesh.ne + r.mesh.nf, 0); /* annulus */
    for (f = 0; f < r.mesh.nf; ++f) {
        double uv[6], cx, cy;
        wr_mesh_face_rest(&r.mesh, f, uv);
        cx = (uv[0] + uv[2] + uv[4]) / 3;
        cy = (uv[1] + uv[3] + uv[5]) / 3;
        cr_expect(!(cx > 0.15 && cx < 0.2 && cy > 0.15 && cy < 0.2), "face %d inside the hole", f);
    }
    /* collision disk: (1 − δ) r_f inside */
    cr_expect(fabs(wr_mesher_eval_sizing(&r, 0, 0.06, 0.19) - 0.5 * rf) < 1e-12);
    /* quilt stitch: ρ r_f on the line (fabric override: no stiffness to weigh E_sh) */
    cr_expect(fabs(wr_mesher_eval_sizing(&r, 0, 0.1, 0.1) - 0.8 * rf) < 1e-9, "stitch %g vs %g",
              wr_mesher_eval_sizing(&r, 0, 0.1, 0.1), 0.8 * rf);
    expect_every_constraint_present(&r);
    wr_mesher_free(&r);
}

Test(mesher, downfill_pressure_shortens_the_transition) {
    wr_pattern pat;
    wr_pattern_panel pn;
    wr_pattern_quilt q;
    wr_pattern_curve ql[1];
    wr_mesher_result r0, r1;
    wr_mesher_desc desc;
    double stitch[4] = {0.02, 0.125, 0.23, 0.125};
    double x = 0.002;
    one_panel(&pat, &pn, sq250, 4);
    memset(&q, 0, sizeof q);
    ql[0].xy = stitch;
    ql[0].n = 2;
    q.panel = 0;
    q.lines = ql;
    q.n_lines = 1;
    q.rho = 0.7;
    q.transition_length = 30e-3;
    pat.quilts = &q;
    pat.n_quilts = 1;
    memset(&desc, 0, sizeof desc);
    desc.uniform_resolution = 0.0;
    desc.max_vertices = 0;
    cr_assert_eq(wr_mesher_run(&pat, &desc, &r0, NULL), WR_OK);
    q.pressure = 1.0;
    cr_assert_eq(wr_mesher_run(&pat, &desc, &r1, NULL), WR_OK);
    /* Sec. 4.2.5: with pressure the resolution returns to the fabric's faster */
    cr_expect_gt(wr_mesher_eval_sizing(&r1, 0, 0.1, 0.125 + x), wr_mesher_eval_sizing(&r0, 0, 0.1, 0.125 + x));
    cr_expect(fabs(wr_mesher_eval_sizing(&r1, 0, 0.1, 0.125) - wr_mesher_eval_sizing(&r0, 0, 0.1, 0.125)) < 1e-12);
    wr_mesher_free(&r0);
    wr_mesher_free(&r1);
}

/* ---- every bad-input path ------------------------------------------------------------------ */
static wr_status run_expect(const wr_pattern *pat, const wr_mesher_desc *desc, wr_status want, const char *needle) {
    wr_mesher_result r;
    wr_diag d;
    wr_status st;
    memset(&d, 0, sizeof d);
    st = wr_mesher_run(pat, desc, &r, &d);
    cr_expect_eq(st, want, "status %s (%s), wanted %s", wr_status_string(st), d.message, wr_status_string(want));
    if (needle) cr_expect(strstr(d.message, needle) != NULL, "message '%s' lacks '%s'", d.message, needle);
    cr_expect_eq(r.mesh.nv, 0); /* zeroed on failure */
    cr_expect_null(r.sizing);
    wr_mesher_free(&r);
    return st;
}

Test(mesher_errors, seams) {
    two_panels t;
    wr_pattern_seam two[2];
    make_two(&t);
    t.se.a.from[0] = 0.001; /* 1 mm inside the panel: not on its boundary */
    t.se.a.from[1] = 0.149;
    run_expect(&t.pat, NULL, WR_ERR_GEOMETRY, "seams[0].a.from");
    make_two(&t);
    t.se.b.to[0] = 0.4; /* beyond the short panel */
    run_expect(&t.pat, NULL, WR_ERR_GEOMETRY, "does not lie on the boundary");
    make_two(&t);
    two[0] = t.se;
    two[1] = t.se;
    two[1].a.from[0] = 0.1; /* overlaps the first seam's range on panel 0 */
    two[1].b.panel = 0;
    two[1].b.from[0] = 0.0;
    two[1].b.from[1] = 0.0;
    two[1].b.to[0] = 0.3;
    two[1].b.to[1] = 0.0;
    two[1].b.reverse = 0;
    t.pat.seams = two;
    t.pat.n_seams = 2;
    run_expect(&t.pat, NULL, WR_ERR_GEOMETRY, "overlaps");
    make_two(&t);
    t.se.b.panel = 7;
    run_expect(&t.pat, NULL, WR_ERR_INVALID_ARG, "seams[0]: panel 7 does not exist");
    make_two(&t);
    t.se.a.to[0] = 0.3;
    t.se.a.to[1] = 0.0; /* walks (0,0.15) → (0.3,0) against the loop: passes the corner (0,0) */
    run_expect(&t.pat, NULL, WR_ERR_GEOMETRY, "corner");
    make_two(&t);
    t.se.a.to[0] = 0.0; /* from == to */
    run_expect(&t.pat, NULL, WR_ERR_GEOMETRY, "zero length");
    make_two(&t);
    t.se.a.from[0] = NAN;
    run_expect(&t.pat, NULL, WR_ERR_GEOMETRY, "non-finite");
}

Test(mesher_errors, techniques) {
    wr_pattern pat;
    wr_pattern_panel pn;
    wr_pattern_shirring sh;
    wr_pattern_fold fd;
    wr_pattern_quilt q;
    wr_pattern_curve ql[1];
    wr_pattern_collision c;
    double line[4] = {0.05, 0.1, 0.2, 0.1}, leave[4] = {0.05, 0.1, 0.3, 0.1};
    one_panel(&pat, &pn, sq250, 4);
    memset(&sh, 0, sizeof sh);
    sh.xy = line;
    sh.n = 2;
    sh.rho = 0.0;
    pat.shirrings = &sh;
    pat.n_shirrings = 1;
    run_expect(&pat, NULL, WR_ERR_INVALID_ARG, "shirrings[0]: rho = 0 outside (0, 1]");
    sh.rho = 1.5;
    run_expect(&pat, NULL, WR_ERR_INVALID_ARG, "rho = 1.5");
    sh.rho = 0.5;
    sh.panel = 1;
    run_expect(&pat, NULL, WR_ERR_INVALID_ARG, "shirrings[0]: panel 1 does not exist");
    sh.panel = 0;
    sh.E_sh = -1.0;
    run_expect(&pat, NULL, WR_ERR_INVALID_ARG, "E_sh");
    sh.E_sh = 0.0;
    sh.xy = leave;
    run_expect(&pat, NULL, WR_ERR_GEOMETRY, "shirrings[0]");
    {
        /* two crossing shirring lines: the sampler's complaint is mapped back to the techniques */
        wr_pattern_shirring two[2];
        double cross1[4] = {0.05, 0.05, 0.2, 0.2}, cross2[4] = {0.05, 0.2, 0.2, 0.05};
        two[0] = sh;
        two[1] = sh;
        two[0].xy = cross1;
        two[1].xy = cross2;
        pat.shirrings = two;
        pat.n_shirrings = 2;
        run_expect(&pat, NULL, WR_ERR_GEOMETRY, "polyline 1 = shirrings[1]");
        {
            /* and the structured location: panel 0, curves 1 and 2 (no holes: curve 1 + j is line j) */
            wr_mesher_result r2;
            wr_diag d2;
            cr_expect_eq(wr_mesher_run(&pat, NULL, &r2, &d2), WR_ERR_GEOMETRY);
            cr_expect(strstr(d2.message, "polyline 0 = shirrings[0]") != NULL, "%s", d2.message);
            cr_expect_eq(d2.part, 0);
            cr_expect(d2.curve == 1 && d2.other_curve == 2, "curve %d, other_curve %d", (int)d2.curve,
                      (int)d2.other_curve);
        }
        pat.shirrings = &sh;
    }
    pat.n_shirrings = 0;
    memset(&fd, 0, sizeof fd);
    fd.xy = leave;
    fd.n = 2;
    pat.folds = &fd;
    pat.n_folds = 1;
    run_expect(&pat, NULL, WR_ERR_GEOMETRY, "folds[0]: point 1");
    fd.xy = line;
    fd.panel = -1;
    run_expect(&pat, NULL, WR_ERR_INVALID_ARG, "folds[0]: panel -1 does not exist");
    fd.panel = 0;
    fd.angle_deg = 400.0;
    run_expect(&pat, NULL, WR_ERR_INVALID_ARG, "fold angle");
    pat.n_folds = 0;
    memset(&q, 0, sizeof q);
    ql[0].xy = line;
    ql[0].n = 2;
    q.lines = ql;
    q.n_lines = 1;
    q.rho = 0.8;
    q.pressure = -0.5;
    pat.quilts = &q;
    pat.n_quilts = 1;
    run_expect(&pat, NULL, WR_ERR_INVALID_ARG, "quilts[0]: pressure = -0.5");
    q.pressure = 1.0;
    q.rho = 2.0;
    run_expect(&pat, NULL, WR_ERR_INVALID_ARG, "quilts[0]: rho");
    q.rho = 0.8;
    q.panel = 3;
    run_expect(&pat, NULL, WR_ERR_INVALID_ARG, "quilts[0]: panel 3");
    pat.n_quilts = 0;
    memset(&c, 0, sizeof c);
    c.radius = 0.01;
    c.center[0] = c.center[1] = 0.1;
    c.compression = 1.0;
    pat.collisions = &c;
    pat.n_collisions = 1;
    run_expect(&pat, NULL, WR_ERR_INVALID_ARG, "collisions[0]: compression");
    c.compression = 0.5;
    c.panel = 2;
    run_expect(&pat, NULL, WR_ERR_INVALID_ARG, "collisions[0]: panel 2");
    c.panel = 0;
    c.radius = 0.0;
    run_expect(&pat, NULL, WR_ERR_GEOMETRY, "collisions[0]");
}

Test(mesher_errors, panels_stiffness_budget) {
    wr_pattern pat;
    wr_pattern_panel pn;
    wr_pattern_curve hole;
    wr_mesher_desc desc;
    double flat[8] = {0, 0, 0.1, 0, 0.2, 0, 0.3, 0}, two[4] = {0, 0, 1, 1};
    double sq[8] = {0, 0, 0.25, 0, 0.25, 0.25, 0, NAN};
    one_panel(&pat, &pn, sq250, 4);
    pn.fabric.B = 0.0;
    run_expect(&pat, NULL, WR_ERR_DOMAIN, "panels[0] 'p': bending stiffness B = 0");
    pn.fabric.B = 2.6e-6;
    pn.fabric.E = -3.0;
    run_expect(&pat, NULL, WR_ERR_DOMAIN, "Young's modulus E = -3");
    pn.fabric.E = 2e6;
    pn.fabric.anisotropic = 1;
    pn.fabric.B_warp = 1e-6;
    pn.fabric.E_warp = 1e6;
    pn.fabric.B_weft = -1e-6;
    pn.fabric.E_weft = 1e6;
    run_expect(&pat, NULL, WR_ERR_DOMAIN, "weft stiffness");
    pn.fabric.anisotropic = 0;
    one_panel(&pat, &pn, flat, 4);
    run_expect(&pat, NULL, WR_ERR_GEOMETRY, "zero area");
    one_panel(&pat, &pn, two, 2);
    run_expect(&pat, NULL, WR_ERR_GEOMETRY, "fewer than 3 points");
    one_panel(&pat, &pn, sq, 4);
    run_expect(&pat, NULL, WR_ERR_GEOMETRY, "non-finite");
    one_panel(&pat, &pn, sq250, 4);
    hole.xy = two;
    hole.n = 2;
    pn.holes = &hole;
    pn.n_holes = 1;
    run_expect(&pat, NULL, WR_ERR_GEOMETRY, "hole 0 has fewer than 3 points");
    one_panel(&pat, &pn, sq250, 4);
    memset(&desc, 0, sizeof desc);
    desc.max_vertices = 500; /* 6 mm on 250 mm needs ~2.2K */
    run_expect(&pat, &desc, WR_ERR_BUDGET, "vertex budget of 500 exceeded at panels[0]");
    run_expect(NULL, NULL, WR_ERR_INVALID_ARG, "NULL pattern");
    pat.n_panels = 0;
    run_expect(&pat, NULL, WR_ERR_INVALID_ARG, "no panels");
    cr_expect_eq(wr_mesher_run(&pat, NULL, NULL, NULL), WR_ERR_INVALID_ARG);
    cr_expect(isnan(wr_mesher_eval_sizing(NULL, 0, 0, 0)));
}

/* ---- pattern JSON reader ------------------------------------------------------------------- */
static void parse_expect(const char *json, wr_status want, const char *needle) {
    wr_pattern_file pf;
    wr_diag d;
    wr_status st;
    memset(&d, 0, sizeof d);
    st = wr_pattern_parse(json, strlen(json), "t.json", &pf, &d);
    cr_expect_eq(st, want, "status %s (%s) for %s", wr_status_string(st), d.message, json);
    if (needle) cr_expect(strstr(d.message, needle) != NULL, "message '%s' lacks '%s'", d.message, needle);
    cr_expect_eq(pf.pattern.n_panels, 0);
    wr_pattern_file_free(&pf);
}

#define PANEL "{\"name\":\"a\",\"fabric\":{\"B\":2.6e-6,\"E\":2e6},\"outer\":[[0,0],[100,0],[100,100],[0,100]]}"

Test(pattern_file, parses_units_and_references) {
    const char *js = "{\"format\":\"wrinkle-pattern/1\",\"units\":\"mm\",\"name\":\"n\","
                     "\"fabrics\":{\"f\":{\"warp\":{\"B\":1e-5,\"E\":1e6},\"weft\":{\"B\":1e-7,\"E\":1e6},"
                     "\"grain_angle_deg\":90}},"
                     "\"panels\":[" PANEL ",{\"name\":\"b\",\"fabric\":\"f\",\"outer\":[[200,0],[300,0],[300,100]],"
                     "\"holes\":[[[260,20],[280,20],[280,30]]]}],"
                     "\"shirring\":[{\"panel\":\"a\",\"line\":[[10,50],[90,50]],\"rho\":0.5,\"E_sh\":1e5}],"
                     "\"folds\":[{\"panel\":0,\"line\":[[10,20],[90,20]],\"offset\":1}],"
                     "\"seams\":[{\"a\":{\"panel\":\"a\",\"from\":[100,0],\"to\":[100,100]},"
                     "\"b\":{\"panel\":\"b\",\"from\":[200,0],\"to\":[300,100],\"reverse\":true}}],"
                     "\"quilts\":[{\"panel\":\"a\",\"lines\":[[[0,80],[100,80]]],\"rho\":0.9,\"pressure\":2}],"
                     "\"collisions\":[{\"panel\":\"a\",\"center\":[50,50],\"radius\":10,\"compression\":0.3}],"
                     "\"mesher\":{\"seed\":3,\"sew\":true,\"uniform_resolution\":5}}";
    wr_pattern_file pf;
    wr_diag d;
    const wr_pattern *p;
    cr_assert_eq(wr_pattern_parse(js, strlen(js), "t.json", &pf, &d), WR_OK, "%s", d.message);
    p = &pf.pattern;
    cr_expect_eq(p->n_panels, 2);
    cr_expect_str_eq(pf.name, "n");
    cr_expect(fabs(p->panels[0].outer.xy[2] - 0.1) < 1e-15); /* 100 mm → 0.1 m */
    cr_expect_eq(p->panels[1].fabric.anisotropic, 1);
    cr_expect(fabs(p->panels[1].fabric.grain_angle - 1.5707963267948966) < 1e-15);
    cr_expect_eq(p->panels[1].n_holes, 1);
    cr_expect_eq(p->shirrings[0].panel, 0);
    cr_expect(fabs(p->folds[0].offset - 1e-3) < 1e-18);
    cr_expect_eq(p->seams[0].b.panel, 1);
    cr_expect_eq(p->seams[0].b.reverse, 1);
    cr_expect(fabs(p->quilts[0].pressure - 2.0) < 1e-15);
    cr_expect(fabs(p->collisions[0].radius - 0.01) < 1e-15);
    cr_expect_eq(pf.desc.seed, 3u);
    cr_expect_eq(pf.desc.sew, 1);
    cr_expect(fabs(pf.desc.uniform_resolution - 5e-3) < 1e-18);
    wr_pattern_file_free(&pf);
}

Test(pattern_file, builtin_fig14_meshes) {
    wr_pattern_file pf;
    wr_mesher_result r;
    wr_diag d;
    cr_assert_eq(wr_pattern_builtin_fig14(&pf, &d), WR_OK, "%s", d.message);
    cr_expect_eq(pf.pattern.n_shirrings, 3);
    pf.desc.uniform_resolution = 0.0;
    cr_assert_eq(wr_mesher_run(&pf.pattern, &pf.desc, &r, &d), WR_OK, "%s", d.message);
    cr_expect_gt(r.mesh.nv, 2000);
    cr_expect_lt(r.mesh.nv, 4000);
    expect_every_constraint_present(&r);
    wr_mesher_free(&r);
    wr_pattern_file_free(&pf);
}

Test(pattern_file, errors_name_the_json_path) {
    parse_expect("{", WR_ERR_PARSE, "line 1: malformed JSON");
    parse_expect("{\"panels\":[]}", WR_ERR_PARSE, "panels: expected a non-empty array");
    parse_expect("{}", WR_ERR_PARSE, "panels: missing");
    parse_expect("[1]", WR_ERR_PARSE, "expected an object");
    parse_expect("{\"panels\":[" PANEL "],\"bogus\":1}", WR_ERR_PARSE, "unknown key \"bogus\"");
    parse_expect("{\"units\":\"cm\",\"panels\":[" PANEL "]}", WR_ERR_PARSE, "units");
    parse_expect("{\"panels\":[" PANEL "," PANEL "]}", WR_ERR_PARSE, "panels[1].name: duplicate panel name");
    parse_expect("{\"panels\":[{\"fabric\":{\"B\":1,\"E\":1},\"outer\":[[0,0],[1,0],[1,1]],\"holes\":[[[0,0],[1,1]]]}]}",
                 WR_ERR_PARSE, "panels[0].holes[0]: fewer than 3 points");
    parse_expect("{\"panels\":[{\"fabric\":{\"B\":1,\"E\":1},\"outer\":[[0,0],[1,0],[1,\"x\"]]}]}", WR_ERR_PARSE,
                 "panels[0].outer[2]: expected two numbers");
    parse_expect("{\"panels\":[{\"fabric\":{\"B\":-1,\"E\":1},\"outer\":[[0,0],[1,0],[1,1]]}]}", WR_ERR_PARSE,
                 "panels[0].fabric.B: -1 outside (0");
    parse_expect("{\"panels\":[{\"fabric\":\"nope\",\"outer\":[[0,0],[1,0],[1,1]]}]}", WR_ERR_PARSE,
                 "no fabric named \"nope\"");
    parse_expect("{\"panels\":[{\"fabric\":{\"B\":1},\"outer\":[[0,0],[1,0],[1,1]]}]}", WR_ERR_PARSE,
                 "panels[0].fabric.E: missing");
    parse_expect("{\"panels\":[" PANEL "],\"shirring\":[{\"panel\":\"zz\",\"line\":[[1,1],[2,2]],\"rho\":0.5}]}",
                 WR_ERR_PARSE, "shirring[0].panel: no panel named \"zz\"");
    parse_expect("{\"panels\":[" PANEL "],\"shirring\":[{\"panel\":\"a\",\"line\":[[1,1],[2,2]],\"rho\":1.5}]}",
                 WR_ERR_PARSE, "shirring[0].rho: 1.5 outside (0, 1]");
    parse_expect("{\"panels\":[" PANEL "],\"quilts\":[{\"panel\":\"a\",\"lines\":[[[1,1],[2,2]]],\"rho\":0.5,"
                 "\"pressure\":-1}]}",
                 WR_ERR_PARSE, "quilts[0].pressure: -1 outside [0");
    parse_expect("{\"panels\":[" PANEL "],\"seams\":[{\"a\":{\"panel\":\"a\",\"from\":[0,0],\"to\":[1,0]}}]}",
                 WR_ERR_PARSE, "seams[0].b: missing");
    parse_expect("{\"panels\":[" PANEL "],\"folds\":[{\"panel\":5,\"line\":[[1,1],[2,2]]}]}", WR_ERR_PARSE,
                 "folds[0].panel: panel index 5 does not exist");
    parse_expect("{\"panels\":[" PANEL "],\"collisions\":[{\"panel\":\"a\",\"compression\":0.5}]}", WR_ERR_PARSE,
                 "collisions[0]: give either");
    parse_expect("{\"panels\":[" PANEL "],\"mesher\":{\"seed\":1.5}}", WR_ERR_PARSE, "mesher.seed");
    parse_expect("{\"panels\":[" PANEL "]} x", WR_ERR_PARSE, "trailing");
    parse_expect("{\"panels\":[" PANEL "],\"panels\":[" PANEL "]}", WR_ERR_PARSE, "duplicate key");
    parse_expect("{\"panels\":[{\"fabric\":{\"B\":1,\"E\":1e999},\"outer\":[[0,0],[1,0],[1,1]]}]}", WR_ERR_PARSE,
                 "not finite");
    parse_expect("{\"panels\":[" PANEL "],\"shirring\":[{\"panel\":\"a\",\"line\":[[1,1],[2,2]],\"rho\":0.5,"
                 "\"stitch_length\":-2}]}",
                 WR_ERR_PARSE, "shirring[0].stitch_length: -2 outside [0");
    parse_expect("{\"panels\":[" PANEL "],\"quilts\":[{\"panel\":\"a\",\"lines\":[[[1,1],[2,2]]],\"rho\":0.5,"
                 "\"stitch_length\":1e999}]}",
                 WR_ERR_PARSE, "quilts[0].stitch_length: number is not finite");
}

/* A shirring's and a quilt's stitch_length (mm) reach the pattern in metres with each line split at
 * its stitches k·s (k·s <= l − s/2, garment.h ON GATHERING): the 80 mm line at 20 mm gets points at
 * 30, 50, 70 mm (x from 10), the quilt's 100 mm line at 30 mm at 30, 60 mm (the 90 mm one would leave
 * 10 < 15 mm); absent or 0: the line as given. */
Test(pattern_file, stitch_length_splits_the_lines) {
    const char *js = "{\"panels\":[" PANEL "],"
                     "\"shirring\":[{\"panel\":\"a\",\"line\":[[10,50],[90,50]],\"rho\":0.5,\"stitch_length\":20},"
                     "{\"panel\":\"a\",\"line\":[[10,40],[90,40]],\"rho\":0.5,\"stitch_length\":0}],"
                     "\"quilts\":[{\"panel\":\"a\",\"lines\":[[[0,80],[100,80]]],\"rho\":0.9,\"stitch_length\":30}]}";
    double want[5] = {0.01, 0.03, 0.05, 0.07, 0.09}, wq[4] = {0.0, 0.03, 0.06, 0.1};
    wr_pattern_file pf;
    wr_diag d;
    int k;
    cr_assert_eq(wr_pattern_parse(js, strlen(js), "t.json", &pf, &d), WR_OK, "%s", d.message);
    cr_expect(fabs(pf.pattern.shirrings[0].stitch_length - 0.02) < 1e-15);
    cr_assert_eq(pf.pattern.shirrings[0].n, 5);
    for (k = 0; k < 5; ++k)
        cr_expect(fabs(pf.pattern.shirrings[0].xy[2 * k] - want[k]) < 1e-12 && fabs(pf.pattern.shirrings[0].xy[2 * k + 1] - 0.05) < 1e-15,
                  "point %d at (%g, %g)", k, pf.pattern.shirrings[0].xy[2 * k], pf.pattern.shirrings[0].xy[2 * k + 1]);
    cr_expect_eq(pf.pattern.shirrings[1].n, 2);
    cr_expect_eq(pf.pattern.shirrings[1].stitch_length, 0.0);
    cr_assert_eq(pf.pattern.quilts[0].lines[0].n, 4);
    for (k = 0; k < 4; ++k) cr_expect(fabs(pf.pattern.quilts[0].lines[0].xy[2 * k] - wq[k]) < 1e-12, "quilt point %d", k);
    wr_pattern_file_free(&pf);
}

/* Mutation fuzz of the reader: every truncation and single-byte change of a valid file either parses
 * or fails with a message; never crashes (ASan/UBSan watch). */
Test(pattern_file, mutation_fuzz) {
    const char *base = "{\"units\":\"mm\",\"panels\":[" PANEL "],\"shirring\":[{\"panel\":\"a\",\"line\":[[10,50],"
                       "[90,50]],\"rho\":0.5}],\"seams\":[{\"a\":{\"panel\":0,\"from\":[0,0],\"to\":[100,0]},"
                       "\"b\":{\"panel\":0,\"from\":[0,100],\"to\":[100,100],\"reverse\":true}}]}";
    size_t n = strlen(base), i;
    char buf[1024];
    static const char subst[] = "0-9.e\"[]{},:x ";
    int ok = 0, bad = 0;
    wr_rng rng;
    wr_rng_seed(&rng, 11);
    cr_assert_lt(n, sizeof buf);
    for (i = 0; i <= n; ++i) {
        wr_pattern_file pf;
        wr_diag d;
        memcpy(buf, base, n);
        if (wr_pattern_parse(buf, i, "fuzz", &pf, &d) == WR_OK)
            ++ok;
        else {
            ++bad;
            cr_expect_gt(strlen(d.message), 0u);
        }
        wr_pattern_file_free(&pf);
    }
    for (i = 0; i < 600; ++i) {
        wr_pattern_file pf;
        wr_diag d;
        size_t at = wr_rng_below(&rng, (uint32_t)n);
        memcpy(buf, base, n);
        buf[at] = subst[wr_rng_below(&rng, (uint32_t)(sizeof subst - 1))];
        if (wr_pattern_parse(buf, n, "fuzz", &pf, &d) == WR_OK) {
            wr_mesher_result r;
            ++ok;
            /* whatever parses must also be handled by the mesher without crashing */
            pf.desc.uniform_resolution = 20e-3;
            if (wr_mesher_run(&pf.pattern, &pf.desc, &r, &d) == WR_OK) wr_mesher_free(&r);
        } else {
            ++bad;
        }
        wr_pattern_file_free(&pf);
    }
    cr_expect_gt(ok, 0);
    cr_expect_gt(bad, 0);
}

/* ---- output directory (drivers/lib/meshout.h) ------------------------------------------------ */
#include <dirent.h>
#include <sys/stat.h>
#include <unistd.h>

#include "meshout.h"

static int count_entries(const char *dir, const char *prefix) {
    DIR *d = opendir(dir);
    struct dirent *e;
    int n = 0;
    if (!d) return -1;
    while ((e = readdir(d)) != NULL)
        if (strncmp(e->d_name, prefix, strlen(prefix)) == 0) ++n;
    closedir(d);
    return n;
}

Test(meshout, writes_whole_directory_or_nothing) {
    two_panels t;
    wr_mesher_result r;
    wr_mesh back;
    wr_diag d;
    char tmpl[] = "/tmp/wrinkle-test-meshoutXXXXXX", p[256], line[256];
    FILE *f;
    int png = -1, rows = 0;
    struct stat sb;
    make_two(&t);
    cr_assert_eq(wr_mesher_run(&t.pat, NULL, &r, &d), WR_OK, "%s", d.message);
    cr_assert_not_null(mkdtemp(tmpl));
    cr_assert_eq(wr_meshout_write_dir(&r, NULL, tmpl, 0, &png, &d), WR_OK, "%s", d.message);
    cr_expect_eq(png, 0);
    snprintf(p, sizeof p, "%s/mesh.obj", tmpl);
    cr_assert_eq(wr_mesh_read_obj(&back, p, &d), WR_OK, "%s", d.message);
    cr_expect_eq(back.nv, r.mesh.nv);
    cr_expect_eq(back.nf, r.mesh.nf);
    cr_expect_not_null(back.rest);
    cr_expect_eq(memcmp(back.rest, r.mesh.rest, sizeof(double) * 2 * (size_t)r.mesh.nv), 0); /* 17 digits: exact */
    wr_mesh_free(&back);
    snprintf(p, sizeof p, "%s/seams.csv", tmpl);
    f = fopen(p, "r");
    cr_assert_not_null(f);
    while (fgets(line, sizeof line, f)) ++rows;
    fclose(f);
    cr_expect_eq(rows, 1 + r.n_seam_pairs);
    snprintf(p, sizeof p, "%s/summary.json", tmpl);
    cr_expect_eq(stat(p, &sb), 0);
    snprintf(p, sizeof p, "%s/mesh.ply", tmpl);
    cr_expect_eq(stat(p, &sb), 0);
    cr_expect_eq(count_entries(tmpl, ".wrinkle-mesh-"), 0, "staging directory left behind");
    cr_expect_eq(count_entries(tmpl, "mesh.obj.wrtmp"), 0);
    /* a regular file where the directory should be: error, nothing created */
    snprintf(p, sizeof p, "%s/mesh.obj", tmpl);
    cr_expect_eq(wr_meshout_write_dir(&r, NULL, p, 0, &png, &d), WR_ERR_IO);
    cr_expect(strstr(d.message, "not a directory") != NULL, "%s", d.message);
    /* cleanup */
    {
        static const char *const names[] = {"mesh.obj", "mesh.ply", "mesh.vtk", "seams.csv", "sizing.png",
                                            "summary.json"};
        int k;
        for (k = 0; k < 6; ++k) {
            snprintf(p, sizeof p, "%s/%s", tmpl, names[k]);
            remove(p);
        }
        cr_expect_eq(rmdir(tmpl), 0, "unexpected files left in %s", tmpl);
    }
    wr_mesher_free(&r);
}

/* ---- progress hook and the up-front budget --------------------------------------------------- */
typedef struct progress_log {
    int calls, sizing, panels, done, last_panel, monotone, n_panels;
    int32_t last_nv;
} progress_log;

static void log_progress(void *user, const wr_mesher_progress *p) {
    progress_log *g = (progress_log *)user;
    g->calls++;
    g->n_panels = p->n_panels;
    if (p->n_vertices < g->last_nv) g->monotone = 0;
    g->last_nv = p->n_vertices;
    if (!strcmp(p->stage, "sizing")) g->sizing += (g->calls == 1 && p->panel == -1);
    if (!strcmp(p->stage, "panel")) {
        g->panels++;
        if (p->panel != g->last_panel + 1) g->monotone = 0;
        g->last_panel = p->panel;
    }
    if (!strcmp(p->stage, "done")) g->done++;
}

/* Reported once after the sizing, once per panel in order with growing vertex counts, once at the end;
 * the last count is the unsewn mesh's. The hook only observes: the mesh is the one without it. */
Test(mesher, progress_hook_reports_every_panel) {
    two_panels t;
    wr_mesher_desc desc;
    wr_mesher_result r, s;
    wr_diag d;
    progress_log g;
    make_two(&t);
    memset(&g, 0, sizeof g);
    g.last_panel = -1;
    g.monotone = 1;
    memset(&desc, 0, sizeof desc);
    desc.progress = log_progress;
    desc.progress_user = &g;
    cr_assert_eq(wr_mesher_run(&t.pat, &desc, &r, &d), WR_OK, "%s", d.message);
    cr_assert_eq(wr_mesher_run(&t.pat, NULL, &s, &d), WR_OK, "%s", d.message);
    cr_expect_eq(g.sizing, 1);
    cr_expect_eq(g.panels, 2);
    cr_expect_eq(g.done, 1);
    cr_expect_eq(g.calls, 4);
    cr_expect_eq(g.n_panels, 2);
    cr_expect(g.monotone);
    cr_expect_eq(g.last_nv, r.mesh.nv);
    cr_expect_eq(r.mesh.nv, s.mesh.nv);
    cr_expect_eq(memcmp(r.mesh.rest, s.mesh.rest, sizeof(double) * 2 * (size_t)r.mesh.nv), 0);
    wr_mesher_free(&r);
    wr_mesher_free(&s);
}

/* Issue 17: a 10 km panel at its fabric's 6 mm and a 1 µm size on a 1 m panel are refused from the
 * area/perimeter estimate before any curve is discretised (each took > 60 s and up to 440 MB before).
 * Closed forms: A / r² + P / (2r) = 1e8 / 6.03e-3² + ... ≈ 2.75e12 and 1 / 1e-12 + 4 / 2e-6 = 1.000002e12. */
Test(mesher_errors, budget_from_area_before_any_work) {
    wr_pattern pat;
    wr_pattern_panel pn;
    wr_mesher_desc desc;
    double km10[8] = {0, 0, 1e4, 0, 1e4, 1e4, 0, 1e4}, m1[8] = {0, 0, 1, 0, 1, 1, 0, 1};
    one_panel(&pat, &pn, km10, 4);
    run_expect(&pat, NULL, WR_ERR_BUDGET, "vertex budget of 20000000 exceeded at panels[0] 'p': its area 1e+08 m^2");
    one_panel(&pat, &pn, m1, 4);
    memset(&desc, 0, sizeof desc);
    desc.uniform_resolution = 1e-6;
    run_expect(&pat, &desc, WR_ERR_BUDGET, "need at least 1e+12 vertices at a 0.001 mm size");
    /* 5 mm on 1 m²: 1 / 25e-6 + 4 / 10e-3 = 40400 against a budget of 20000 */
    desc.uniform_resolution = 5e-3;
    desc.max_vertices = 20000;
    run_expect(&pat, &desc, WR_ERR_BUDGET, "need at least 4.04e+04 vertices");
}

/* ---- the output numbering (ON THE OUTPUT: WR_MESHER_ORDER_SPATIAL against _SAMPLED) ---------------- */
static const double *vertex_xy(const wr_mesher_result *r, int32_t v) { /* rest, or pos when sewn */
    static double q[2];
    if (r->mesh.rest) return r->mesh.rest + 2 * v;
    q[0] = r->mesh.pos[3 * v];
    q[1] = r->mesh.pos[3 * v + 1];
    return q;
}
static const wr_mesher_result *g_sort_res; /* qsort context */
static int cmp_vertex_xy(const void *x, const void *y) {
    double a[2], b[2];
    memcpy(a, vertex_xy(g_sort_res, *(const int32_t *)x), sizeof a);
    memcpy(b, vertex_xy(g_sort_res, *(const int32_t *)y), sizeof b);
    if (a[0] != b[0]) return a[0] < b[0] ? -1 : 1;
    return a[1] < b[1] ? -1 : a[1] > b[1];
}
static int cmp_face4(const void *x, const void *y) {
    const int32_t *a = (const int32_t *)x, *b = (const int32_t *)y;
    int k;
    for (k = 0; k < 4; ++k)
        if (a[k] != b[k]) return a[k] < b[k] ? -1 : 1;
    return 0;
}
/* map[v of s] = the vertex of r at the same position (positions are distinct in these patterns). */
static void match_vertices(const wr_mesher_result *r, const wr_mesher_result *s, int32_t *map) {
    int32_t n = r->mesh.nv, i, *ir = (int32_t *)malloc(sizeof(int32_t) * (size_t)n), *is = (int32_t *)malloc(sizeof(int32_t) * (size_t)n);
    cr_assert(ir && is);
    for (i = 0; i < n; ++i) ir[i] = is[i] = i;
    g_sort_res = r;
    qsort(ir, (size_t)n, sizeof(int32_t), cmp_vertex_xy);
    g_sort_res = s;
    qsort(is, (size_t)n, sizeof(int32_t), cmp_vertex_xy);
    for (i = 0; i < n; ++i) {
        double a[2];
        memcpy(a, vertex_xy(r, ir[i]), sizeof a);
        cr_assert(a[0] == vertex_xy(s, is[i])[0] && a[1] == vertex_xy(s, is[i])[1], "vertex positions differ at %d", i);
        if (i > 0) cr_assert(cmp_vertex_xy(&is[i - 1], &is[i]) != 0, "two vertices at one position");
        map[is[i]] = ir[i];
    }
    free(ir);
    free(is);
}
/* (corners mapped to r's ids, panel) per face, sorted: equal lists = the same triangles, corners in the
 * same rotation, on the same panels; corner_rest (sewn) compared per corner through the same sort. */
static int32_t *face_list(const wr_mesher_result *r, const int32_t *map) {
    int32_t f, k, *L = (int32_t *)malloc(sizeof(int32_t) * 5 * (size_t)r->mesh.nf);
    cr_assert(L);
    for (f = 0; f < r->mesh.nf; ++f) {
        for (k = 0; k < 3; ++k) L[5 * f + k] = map ? map[r->mesh.faces[3 * f + k]] : r->mesh.faces[3 * f + k];
        L[5 * f + 3] = r->mesh.face_panel[f];
        L[5 * f + 4] = f;
    }
    qsort(L, (size_t)r->mesh.nf, 5 * sizeof(int32_t), cmp_face4);
    return L;
}
static void expect_same_up_to_numbering(const wr_mesher_result *r, const wr_mesher_result *s) {
    const wr_mesh *a = &r->mesh, *b = &s->mesh;
    int32_t *map, *La, *Lb, i, k;
    cr_assert_eq(a->nv, b->nv);
    cr_assert_eq(a->nf, b->nf);
    cr_assert_eq(a->ne, b->ne);
    cr_assert_eq(r->n_seam_pairs, s->n_seam_pairs);
    cr_assert_eq(r->n_constraint_segments, s->n_constraint_segments);
    map = (int32_t *)malloc(sizeof(int32_t) * (size_t)a->nv);
    cr_assert(map);
    match_vertices(r, s, map);
    for (i = 0; i < b->nv; ++i)
        cr_expect(s->sizing[i] == r->sizing[map[i]] && s->sizing_warp[i] == r->sizing_warp[map[i]] &&
                      s->sizing_weft[i] == r->sizing_weft[map[i]], "sizing of vertex %d", i);
    La = face_list(r, NULL);
    Lb = face_list(s, map);
    for (i = 0; i < a->nf; ++i) {
        cr_assert(cmp_face4(La + 5 * i, Lb + 5 * i) == 0, "face %d differs", i);
        for (k = 0; k < 6 && a->corner_rest; ++k)
            cr_expect(a->corner_rest[6 * La[5 * i + 4] + k] == b->corner_rest[6 * Lb[5 * i + 4] + k]);
    }
    for (i = 0; i < 2 * r->n_seam_pairs; ++i) cr_expect_eq(map[s->seam_pairs[i]], r->seam_pairs[i], "seam pair %d", i / 2);
    for (i = 0; i < 2 * r->n_constraint_segments; ++i)
        cr_expect_eq(map[s->constraint_segments[i]], r->constraint_segments[i], "constraint segment %d", i / 2);
    for (i = 0; i < r->n_panels; ++i)
        cr_expect(r->panels[i].v_begin == s->panels[i].v_begin && r->panels[i].v_end == s->panels[i].v_end &&
                  r->panels[i].f_begin == s->panels[i].f_begin && r->panels[i].f_end == s->panels[i].f_end);
    /* the report: extremes and counts exact, means up to summation order */
    cr_expect(r->report.min_angle_deg == s->report.min_angle_deg && r->report.max_angle_deg == s->report.max_angle_deg);
    cr_expect(r->report.ratio_min == s->report.ratio_min && r->report.ratio_max == s->report.ratio_max);
    cr_expect(memcmp(r->report.ratio_hist, s->report.ratio_hist, sizeof r->report.ratio_hist) == 0);
    cr_expect(fabs(r->report.mean_min_angle_deg - s->report.mean_min_angle_deg) < 1e-12 * r->report.mean_min_angle_deg);
    cr_expect(fabs(r->report.ratio_mean - s->report.ratio_mean) < 1e-12);
    free(map);
    free(La);
    free(Lb);
}
static int cmp_i32(const void *x, const void *y) {
    int32_t a = *(const int32_t *)x, b = *(const int32_t *)y;
    return a < b ? -1 : a > b;
}
/* Median over the faces without a curve corner of (largest - smallest corner id). */
static double face_span_median(const wr_mesher_result *r, const char *on) {
    int32_t f, n = 0, *span = (int32_t *)malloc(sizeof(int32_t) * (size_t)(r->mesh.nf + 1));
    double med;
    cr_assert(span);
    for (f = 0; f < r->mesh.nf; ++f) {
        const int32_t *F = r->mesh.faces + 3 * f;
        int32_t hi = F[0] > F[1] ? F[0] : F[1], lo = F[0] < F[1] ? F[0] : F[1];
        hi = hi > F[2] ? hi : F[2];
        lo = lo < F[2] ? lo : F[2];
        if (!on[F[0]] && !on[F[1]] && !on[F[2]]) span[n++] = hi - lo;
    }
    qsort(span, (size_t)n, sizeof(int32_t), cmp_i32);
    med = n ? span[n / 2] : 0.0;
    free(span);
    return med;
}
/* The curve points (the constraint segments' ends: outer loops, holes, lines) of r, 1 each. */
static char *curve_marks(const wr_mesher_result *r) {
    char *on = (char *)calloc((size_t)r->mesh.nv, 1);
    int32_t i;
    cr_assert(on);
    for (i = 0; i < 2 * r->n_constraint_segments; ++i) on[r->constraint_segments[i]] = 1;
    return on;
}
/* The spatial order's own promises (unsewn): per panel the curve points are its first ids and the
 * faces go by nondecreasing largest corner. */
static void expect_spatial_layout(const wr_mesher_result *r) {
    int32_t p, f;
    char *on = curve_marks(r);
    for (p = 0; p < r->n_panels; ++p) {
        int32_t v = r->panels[p].v_begin, last = -1;
        while (v < r->panels[p].v_end && on[v]) ++v;
        for (; v < r->panels[p].v_end; ++v) cr_expect(!on[v], "panel %d: curve vertex %d after an interior one", p, v);
        for (f = r->panels[p].f_begin; f < r->panels[p].f_end; ++f) {
            const int32_t *F = r->mesh.faces + 3 * f;
            int32_t hi = F[0] > F[1] ? F[0] : F[1];
            hi = hi > F[2] ? hi : F[2];
            cr_expect_geq(hi, last, "panel %d face %d: largest corner %d after %d", p, f, hi, last);
            last = hi;
        }
    }
    free(on);
}

Test(mesher, spatial_order_permutes_the_sampled_order) {
    hole_line_fold h;
    wr_mesher_result r, s;
    wr_mesher_desc desc;
    wr_diag d;
    two_panels t;
    double med_s, med_r;
    int sew;
    /* one panel with a hole, a shirring line and a fold (line + parallels), 4 mm */
    make_hole_line_fold(&h);
    h.pn.fabric.resolution = 4e-3;
    memset(&desc, 0, sizeof desc);
    desc.vertex_order = WR_MESHER_ORDER_SAMPLED;
    cr_assert_eq(wr_mesher_run(&h.pat, &desc, &r, &d), WR_OK, "%s", d.message);
    desc.vertex_order = WR_MESHER_ORDER_SPATIAL;
    cr_assert_eq(wr_mesher_run(&h.pat, &desc, &s, &d), WR_OK, "%s", d.message);
    cr_assert_gt(s.mesh.nv, 3000);
    expect_same_up_to_numbering(&r, &s);
    expect_spatial_layout(&s);
    { /* nearby ids: the median id span of an interior face, against the sampler's order */
        char *on_r = curve_marks(&r), *on_s = curve_marks(&s);
        med_r = face_span_median(&r, on_r);
        med_s = face_span_median(&s, on_s);
        cr_expect_lt(med_s, 0.25 * med_r, "median face id span: spatial %g, sampled %g", med_s, med_r);
        cr_log_info("median face id span: spatial %g, sampled %g (%d vertices)", med_s, med_r, (int)s.mesh.nv);
        free(on_r);
        free(on_s);
    }
    cr_expect_eq(check_as_cdt(&s, 1, &d), WR_OK, "%s", d.message);
    wr_mesher_free(&r);
    wr_mesher_free(&s);
    /* two panels with a seam, unsewn and sewn */
    make_two(&t);
    for (sew = 0; sew < 2; ++sew) {
        desc.sew = sew;
        desc.vertex_order = WR_MESHER_ORDER_SAMPLED;
        cr_assert_eq(wr_mesher_run(&t.pat, &desc, &r, &d), WR_OK, "%s", d.message);
        desc.vertex_order = WR_MESHER_ORDER_SPATIAL;
        cr_assert_eq(wr_mesher_run(&t.pat, &desc, &s, &d), WR_OK, "%s", d.message);
        expect_same_up_to_numbering(&r, &s);
        if (!sew) {
            expect_spatial_layout(&s);
            cr_expect_eq(check_as_cdt(&s, 0, &d), WR_OK, "%s", d.message);
        }
        wr_mesher_free(&r);
        wr_mesher_free(&s);
    }
    desc.vertex_order = 2;
    cr_expect_eq(wr_mesher_run(&t.pat, &desc, &s, &d), WR_ERR_INVALID_ARG);
    cr_expect(strstr(d.message, "vertex_order") != NULL, "%s", d.message);
}
