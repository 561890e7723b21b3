/* bench_weld — cost of garment.h's seam weld (wr_garment_sim_weld: the CCD-limited merge of ON
 * WELDING plus the exact check of the welded mesh) against the garment's size, and a fingerprint of
 * its result, so two builds (e.g. before and after a change of the merge's CCD) can be compared on
 * the same input in the same run: the weld must give the same merged positions, bit for bit.
 *
 * The garment is the A-line skirt of examples/sim/skirt_pattern.json (two panels, side seams; the
 * same numbers as tests/test_garment.c's skirt) on the procedural mannequin (body.h, 1e4 triangles;
 * the simulation sees the hip-to-knee part, as in the tests), fabric E = 1e6 Pa, ν 0.3, 0.5 mm,
 * 300 kg/m³, gravity, μ 0.5, mass damping 1/s. Two modes:
 *   sewn RES     the skirt and mannequin scaled by 0.25 (tests/test_garment.c
 *                scaled_skirt_weld_adds_no_intersection, d̂ = 0.25 mm), meshed at RES (full-size
 *                metres, before the scaling; 0.0334 is that test's mesh), sewn with the weld off (desc.no_weld) until the
 *                largest seam gap is below the weld tolerance, then welded once by hand: the state
 *                the weld meets in a real run (that test's weld, at RES 0.0334). Slow: it simulates.
 *   placed RES   the full-size skirt meshed at RES and placed (each panel half way round a 0.201 m
 *                cylinder, hem at z = 0.55 m), welded at once (tolerance 1 m): every seam pair merged
 *                across its placed gap (0 at the hem, 0.2 m at the waist), which the all-at-once
 *                midpoint merge cannot do without crossing the body, so every merged vertex is
 *                moved on its own (the per-class sweep of ON WELDING). A size-scaling case that
 *                needs no simulation (20k-60k vertices in seconds); the weld is refused or not, the
 *                same either way in both builds.
 * Output, one line: mode, RES, pattern vertices, seam pairs, the weld's CPU seconds (getrusage
 * around wr_garment_sim_weld alone), its status, welded, and the counts weld_mid_hits, weld_moved,
 * weld_blocked, weld_left, then an FNV-1a hash of the welded positions (0 when refused).
 *
 * Usage: bench_weld sewn|placed RES          (one thread: OMP_THREAD_LIMIT=1 OMP_NUM_THREADS=1)
 *        bench_weld                         sewn 0.0334, placed 0.02, placed 0.0059 (bench/run_all.sh) */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>

#ifdef WR_BENCH_IMPL /* built as its own implementation unit (the Makefile), so it can be built on any tree */
#define WRINKLE_IMPLEMENTATION
#endif
#include "wrinkle/wrinkle.h"

#define BW_PI 3.14159265358979323846

static double cpu_seconds(void) {
    struct rusage ru;
    getrusage(RUSAGE_SELF, &ru);
    return (double)ru.ru_utime.tv_sec + 1e-6 * (double)ru.ru_utime.tv_usec + (double)ru.ru_stime.tv_sec +
           1e-6 * (double)ru.ru_stime.tv_usec;
}

static int fail(const char *what, const wr_diag *d) {
    fprintf(stderr, "bench_weld: %s: %s\n", what, d->message);
    return 1;
}

/* examples/sim/skirt_pattern.json in metres, meshed at a uniform res, then scaled by s (rest and
 * placed positions), as tests/test_garment.c does */
static wr_status bw_skirt_mesh(wr_mesher_result *mr, double res, double s, wr_diag *d) {
    static const double front[8] = {0, 0, 0.63, 0, 0.53, 0.5, 0.10, 0.5};
    static const double back[8] = {0.70, 0, 1.33, 0, 1.23, 0.5, 0.80, 0.5};
    wr_pattern_panel pn[2];
    wr_pattern_seam sm[2];
    wr_pattern pat;
    wr_mesher_desc md;
    wr_status st;
    int32_t i;
    memset(pn, 0, sizeof pn);
    memset(sm, 0, sizeof sm);
    memset(&pat, 0, sizeof pat);
    memset(&md, 0, sizeof md);
    pn[0].outer.xy = front, pn[0].outer.n = 4, pn[0].fabric.B = 1e-5, pn[0].fabric.E = 1e6;
    pn[1].outer.xy = back, pn[1].outer.n = 4, pn[1].fabric = pn[0].fabric;
    sm[0].a.panel = 0, sm[0].a.from[0] = 0.63, sm[0].a.to[0] = 0.53, sm[0].a.to[1] = 0.5;
    sm[0].b.panel = 1, sm[0].b.from[0] = 0.70, sm[0].b.to[0] = 0.80, sm[0].b.to[1] = 0.5, sm[0].b.reverse = 1;
    sm[1].a.panel = 1, sm[1].a.from[0] = 1.33, sm[1].a.to[0] = 1.23, sm[1].a.to[1] = 0.5;
    sm[1].b.panel = 0, sm[1].b.from[0] = 0.0, sm[1].b.to[0] = 0.10, sm[1].b.to[1] = 0.5, sm[1].b.reverse = 1;
    pat.panels = pn, pat.n_panels = 2, pat.seams = sm, pat.n_seams = 2;
    md.uniform_resolution = res;
    md.seed = 1;
    if ((st = wr_mesher_run(&pat, &md, mr, d)) != WR_OK || s == 1.0) return st;
    for (i = 0; i < 2 * mr->mesh.nv; ++i) mr->mesh.rest[i] *= s;
    for (i = 0; i < 3 * mr->mesh.nv; ++i) mr->mesh.pos[i] *= s;
    return WR_OK;
}

/* the mannequin (height 1.7 s) and its faces with every corner in 0.35 <= z <= 1.25, |x| <= 0.30 in
 * full-size units (divided by s, cropped, multiplied back, as the test does) */
static wr_status bw_body(wr_mesh *bm, int32_t **faces, int32_t *nf, double s, wr_diag *d) {
    wr_body_desc bd;
    int32_t f, k, n = 0, i;
    wr_status st;
    memset(&bd, 0, sizeof bd);
    bd.target_faces = 10000;
    if (s != 1.0) bd.height = 1.7 * s;
    if ((st = wr_body_mannequin(bm, &bd, d)) != WR_OK) return st;
    *faces = (int32_t *)malloc(sizeof(int32_t) * 3 * (size_t)bm->nf);
    if (!*faces) return WR_ERR_NOMEM;
    if (s != 1.0)
        for (i = 0; i < 3 * bm->nv; ++i) bm->pos[i] /= s;
    for (f = 0; f < bm->nf; ++f) {
        int ok = 1;
        for (k = 0; k < 3; ++k) {
            const double *p = bm->pos + 3 * bm->faces[3 * f + k];
            ok = ok && p[2] >= 0.35 && p[2] <= 1.25 && fabs(p[0]) <= 0.30;
        }
        if (!ok) continue;
        for (k = 0; k < 3; ++k) (*faces)[3 * n + k] = bm->faces[3 * f + k];
        n++;
    }
    if (s != 1.0)
        for (i = 0; i < 3 * bm->nv; ++i) bm->pos[i] *= s;
    *nf = n;
    return WR_OK;
}

static uint64_t bw_hash(const double *x, size_t n) {
    const unsigned char *p = (const unsigned char *)x;
    uint64_t h = 1469598103934665603ull;
    size_t i;
    for (i = 0; i < n * sizeof(double); ++i) h = (h ^ p[i]) * 1099511628211ull;
    return h;
}

static int bw_case(const char *mode, double res) {
    wr_mesher_result mr;
    wr_mesh bm;
    wr_dyn_body body;
    wr_garment_placement pl[2];
    wr_garment g;
    wr_garment_sim gs;
    wr_shell_desc sd;
    wr_dyn_desc dd;
    wr_garment_desc gd;
    wr_dyn_stats fs;
    wr_diag d;
    int32_t *bf = NULL, nbf = 0, i, f, sewn;
    double s, t0, cpu;
    wr_status st;
    sewn = !strcmp(mode, "sewn");
    s = sewn ? 0.25 : 1.0;
    memset(&d, 0, sizeof d);
    if (bw_skirt_mesh(&mr, res, s, &d) != WR_OK) return fail("mesher", &d);
    if (bw_body(&bm, &bf, &nbf, s, &d) != WR_OK) return fail("mannequin", &d);
    memset(&body, 0, sizeof body);
    body.nv = bm.nv, body.nf = nbf, body.faces = bf, body.pos = bm.pos;
    memset(pl, 0, sizeof pl);
    for (i = 0; i < 2; ++i) {
        pl[i].kind = WR_GARMENT_CYLINDER;
        pl[i].origin[0] = (i ? 1.015 : 0.315) * s;
        pl[i].cylinder.point[2] = 0.55 * s;
        pl[i].cylinder.radius = 0.201 * s;
        pl[i].cylinder.angle = i ? BW_PI / 2 : -BW_PI / 2;
    }
    memset(&g, 0, sizeof g);
    g.pattern = &mr.mesh, g.seam_pairs = mr.seam_pairs, g.seam_pair_seam = mr.seam_pair_seam;
    g.n_seam_pairs = mr.n_seam_pairs, g.placements = pl, g.n_placements = 2;
    memset(&sd, 0, sizeof sd);
    sd.young = 1e6, sd.poisson = 0.3, sd.thickness = 5e-4, sd.density = 300.0;
    memset(&dd, 0, sizeof dd);
    dd.gravity[2] = -9.81;
    dd.contact.bodies = &body, dd.contact.n_bodies = 1, dd.contact.friction = 0.5, dd.contact.dhat = s * 1e-3;
    dd.damping.mass = 1.0;
    memset(&gd, 0, sizeof gd);
    gd.no_weld = sewn;          /* sewn: the weld by hand below, at the frame the step would weld */
    if (!sewn) gd.weld_tol = 1.0; /* placed: weld whatever the gap */
    if (wr_garment_sim_create(&gs, &g, &sd, &dd, &gd, &d) != WR_OK) return fail("garment", &d);
    for (f = 0; sewn && f < 30; ++f) {
        if (wr_garment_sim_step(&gs, &fs, &d) != WR_OK) return fail("step", &d);
        fprintf(stderr, "frame %d: gap %.4g mm\n", (int)f, 1e3 * gs.gap);
        if (gs.gap < gs.desc.weld_tol) break;
    }
    if (sewn && !(gs.gap < gs.desc.weld_tol)) {
        fprintf(stderr, "bench_weld: not sewn to the weld tolerance in 30 frames\n");
        return 1;
    }
    t0 = cpu_seconds();
    st = wr_garment_sim_weld(&gs, &d);
    cpu = cpu_seconds() - t0;
    printf("%s res %.4g m: %d vertices, %d seam pairs, weld %.3f s CPU, status %d, welded %d, mid_hits %d moved %d "
           "blocked %d left %d, hash %016llx\n",
           mode, res, (int)gs.nv0, (int)gs.n_pairs, cpu, (int)st, (int)gs.welded, (int)gs.weld_mid_hits,
           (int)gs.weld_moved, (int)gs.weld_blocked, (int)gs.weld_left,
           gs.welded ? (unsigned long long)bw_hash(gs.x, 3 * (size_t)gs.mesh.nv) : 0ull);
    if (st != WR_OK) fprintf(stderr, "weld: %s\n", d.message);
    wr_garment_sim_free(&gs);
    free(bf);
    wr_mesh_free(&bm);
    wr_mesher_free(&mr);
    return 0;
}

int main(int argc, char **argv) {
    double res = argc == 3 ? atof(argv[2]) : 0.0;
    if (argc == 1) /* bench/run_all.sh: the real sewn weld and two sizes of the placed one */
        return bw_case("sewn", 0.0334) || bw_case("placed", 0.02) || bw_case("placed", 0.0059);
    if (argc != 3 || (strcmp(argv[1], "sewn") && strcmp(argv[1], "placed")) || !(res > 0.0)) {
        fprintf(stderr, "usage: bench_weld [sewn|placed RES]\n");
        return 2;
    }
    return bw_case(argv[1], res);
}
