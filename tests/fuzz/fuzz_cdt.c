/* libFuzzer harness: constrained Delaunay triangulation (triangulate.h wr_cdt_triangulate) on raw
 * point / segment / hole input, every result verified by the exact checker wr_cdt_check.
 *
 * Byte layout (missing bytes read as 0):
 *   [0] flags: bit0 quality refinement, bit1 split_intersections, bit2 keep_convex_hull,
 *       bit3 off_center, bits 4-5 coordinate mode, bit6 merge_tolerance on, bit7 max_area on
 *   [1] n_points % 33   [2] n_segments % 25   [3] n_holes % 3   [4] min angle 5..34 deg
 *   then per point a coordinate pair, per segment two bytes (index % n_points), per hole a pair.
 * Coordinate modes (near-degenerate inputs are the point of the exercise):
 *   0 small integers in [-8, 8)    (exactly collinear / cocircular sets, duplicates)
 *   1 small integers + k·2^-48      (almost collinear, almost cocircular)
 *   2 an 8-byte double, kept only when finite with |x| in [1e-30, 1e30] (else 0) — the range the
 *     header promises exact predicates for
 *   3 per coordinate one of 0..2 chosen by a selector byte
 * Sizes are bounded (≤ 32 points, ≤ 24 segments, vertex budget 2000) so one input runs in
 * milliseconds. Contract: whenever the status is WR_OK — or WR_ERR_BUDGET, which promises "the valid
 * mesh reached so far" — wr_cdt_check must pass (CCW, constrained Delaunay, segments present,
 * Euler); every failure carries a one-line message. */
#define WRINKLE_IMPLEMENTATION
#include "wrinkle/triangulate.h"

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

typedef struct {
    const uint8_t *p;
    size_t n, at;
} reader;

static uint8_t rd8(reader *r) { return r->at < r->n ? r->p[r->at++] : 0; }

static double coord(reader *r, int mode) {
    if (mode == 3) mode = rd8(r) % 3;
    if (mode == 0) return (double)((int)(rd8(r) % 16) - 8);
    if (mode == 1) {
        double base = (double)((int)(rd8(r) % 16) - 8);
        int k = (int)(int8_t)rd8(r);
        return base + ldexp((double)k, -48);
    } else {
        uint64_t u = 0;
        double x;
        int i;
        for (i = 0; i < 8; ++i) u |= (uint64_t)rd8(r) << (8 * i);
        memcpy(&x, &u, sizeof x);
        if (!isfinite(x) || fabs(x) > 1e30 || (x != 0.0 && fabs(x) < 1e-30)) x = 0.0;
        return x;
    }
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
    reader r;
    double pts[2 * 32], holes[2 * 2];
    int32_t seg[2 * 24];
    int32_t np, ns, nh, i;
    uint8_t flags;
    int mode;
    wr_cdt_input in;
    wr_cdt_desc cd;
    wr_cdt_result res;
    wr_diag d;
    wr_status s;
    r.p = data;
    r.n = size;
    r.at = 0;
    flags = rd8(&r);
    np = rd8(&r) % 33;
    ns = rd8(&r) % 25;
    nh = rd8(&r) % 3;
    memset(&cd, 0, sizeof cd);
    cd.quality = flags & 1;
    cd.split_intersections = (flags >> 1) & 1;
    cd.keep_convex_hull = (flags >> 2) & 1;
    cd.off_center = (flags >> 3) & 1;
    mode = (flags >> 4) & 3;
    cd.min_angle_deg = 5.0 + (double)(rd8(&r) % 30);
    if (flags & 64) cd.merge_tolerance = 1e-9;
    if (flags & 128) cd.max_area = 0.5;
    cd.max_vertices = 2000;
    for (i = 0; i < np; ++i) {
        pts[2 * i] = coord(&r, mode);
        pts[2 * i + 1] = coord(&r, mode);
    }
    if (np == 0) ns = 0;
    for (i = 0; i < ns; ++i) {
        seg[2 * i] = rd8(&r) % np;
        seg[2 * i + 1] = rd8(&r) % np;
    }
    for (i = 0; i < nh; ++i) {
        holes[2 * i] = coord(&r, mode);
        holes[2 * i + 1] = coord(&r, mode);
    }
    memset(&in, 0, sizeof in);
    in.points = pts;
    in.n_points = np;
    in.segments = ns ? seg : NULL;
    in.n_segments = ns;
    in.holes = nh ? holes : NULL;
    in.n_holes = nh;
    memset(&d, 0, sizeof d);
    s = wr_cdt_triangulate(&in, &cd, &res, &d);
    if (s == WR_OK || s == WR_ERR_BUDGET) {
        wr_diag dc;
        wr_status c;
        memset(&dc, 0, sizeof dc);
        c = wr_cdt_check(&res, -1, NULL, &dc);
        if (c != WR_OK) {
            fprintf(stderr, "fuzz_cdt: triangulate returned %s but the checker says %s: %s\n",
                    wr_status_string(s), wr_status_string(c), dc.message);
            abort();
        }
        /* No assertion on min_angle_deg: triangulate.h documents two kinds of triangles refinement
         * leaves alone (input small angles, slivers with all corners on one segment), and the
         * seed doubles_slim produces such a 0° sliver with WR_OK (reported, not asserted). */
    } else if (memchr(d.message, 0, sizeof d.message) == NULL || strchr(d.message, '\n') || d.status != s) {
        abort();
    }
    wr_cdt_free(&res);
    return 0;
}
