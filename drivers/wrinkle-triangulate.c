/* wrinkle-triangulate — constrained Delaunay triangulation of Shewchuk Triangle's .node/.poly files
 * with wrinkle's triangulate.h (exact predicates, CDT, Ruppert refinement). A drop-in for the common
 * Triangle command lines:
 *
 *   wrinkle-triangulate [-pqazcQVS...] [--no-split-intersections] name[.poly|.node]
 *
 *   -p        read name.poly (vertices, segments, holes) and triangulate it constrained; without -p
 *             the vertices of name.node are triangulated (convex hull)
 *   -q[deg]   quality: minimum angle, default 20 degrees (at most 34)
 *   -a<area>  maximum triangle area
 *   -c        keep the convex hull (do not remove triangles outside the segments)
 *   -S<n>     at most n Steiner points
 *   -z        number output items from zero (input numbering is detected from the first vertex)
 *   -Q        quiet: no summary line;  -V  verbose: timings and a wr_cdt_check verification
 *   --no-split-intersections   reject crossing segments (WR_ERR_GEOMETRY naming both: a
 *             self-intersecting garment boundary) instead of splitting them at a Steiner point as
 *             Triangle does (the default)
 *   -h, --help
 *   Switches may be combined as in Triangle: -pq30a0.01
 *
 * Output (as Triangle): name.1.node, name.1.ele and, with -p, name.1.poly (segments; its node section
 * is empty and refers to the .node file). An input named name.1.poly gives name.2.*. Files are
 * written atomically; an output that is the input file is refused. Exit status (as every wrinkle
 * driver): 0 ok; 1 the Steiner budget stopped refinement without -S (mesh written); 2 bad input —
 * command line or input file (one line "file:line: reason" on stderr); 3 the outputs could not be
 * written. The Triangle-style switch string is parsed here (it is not the --name VALUE form the
 * other drivers share through cli.h). */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"
#include "wrinkle/core.h"
#include "wrinkle/polyfile.h"

static void usage(FILE *f) {
    fprintf(f,
            "usage: wrinkle-triangulate [-pqazcQVS...] [--no-split-intersections] name[.poly|.node]\n"
            "  -p         read name.poly (segments, holes): constrained Delaunay triangulation\n"
            "  -q[deg]    quality refinement, minimum angle (default 20, at most 34)\n"
            "  -a<area>   maximum triangle area\n"
            "  -c         keep the convex hull (do not carve outside the segments)\n"
            "  -S<n>      at most n Steiner points\n"
            "  -z         number output items from zero\n"
            "  -Q / -V    quiet / verbose (adds a full wr_cdt_check verification)\n"
            "  --no-split-intersections  reject crossing segments instead of splitting them\n"
            "writes name.1.node, name.1.ele (and name.1.poly with -p), like Triangle\n"
            "exit status: 0 ok, 1 Steiner budget reached (mesh written), 2 bad input, 3 write failure\n");
}

/* numeric run after a switch letter, e.g. the "30" of "-pq30a.2"; *k advanced past it */
static int switch_number(const char *s, size_t *k, double *out, int *present) {
    char buf[64];
    size_t b = *k, e = b;
    while (s[e] && strchr("0123456789.eE+-", s[e])) ++e;
    *present = e > b;
    if (!*present) return 1;
    if (e - b >= sizeof buf) return 0;
    memcpy(buf, s + b, e - b);
    buf[e - b] = 0;
    *k = e;
    return wr_cli_parse_double(buf, out);
}

/* "dir/name.1" -> "dir/name.2"; "dir/name" -> "dir/name.1" */
static int output_base(const char *in, char *out, size_t cap) {
    size_t n = strlen(in), d = n;
    while (d > 0 && in[d - 1] >= '0' && in[d - 1] <= '9') --d;
    if (d < n && d > 0 && in[d - 1] == '.' && n - d < 9) {
        long it = strtol(in + d, NULL, 10);
        return snprintf(out, cap, "%.*s%ld", (int)d, in, it + 1) < (int)cap;
    }
    return snprintf(out, cap, "%s.1", in) < (int)cap;
}

static int write_outputs(const char *base, const wr_cdt_poly *P, const wr_cdt_result *r, int poly, int first,
                         wr_diag *dg) {
    char path[WR_PATH_MAX];
    wr_afile f;
    int32_t i, t, *inv = NULL, *bnd = NULL;
    memset(&f, 0, sizeof f); /* wr_afile_abort on a never-opened file is then a no-op */
    inv = (int32_t *)wr_alloc_array((size_t)r->n_points, sizeof(int32_t));
    bnd = (int32_t *)wr_calloc_array((size_t)r->n_points, sizeof(int32_t));
    if (!inv || !bnd) {
        wr_free(inv);
        wr_free(bnd);
        wr_fail(dg, WR_ERR_NOMEM, -1, "out of memory");
        return 0;
    }
    for (i = 0; i < r->n_points; ++i) inv[i] = -1;
    for (i = r->n_map - 1; i >= 0; --i) inv[r->point_map[i]] = i;
    for (t = 0; t < 3 * r->n_triangles; ++t)
        if (r->neighbors[t] < 0 || r->edge_segment[t] >= 0) {
            int k = t % 3;
            bnd[r->triangles[t - k + (k + 1) % 3]] = bnd[r->triangles[t - k + (k + 2) % 3]] = 1;
        }
    /* .node: Triangle's boundary-marker rule: the input's marker when it has one, the segment's
     * marker for Steiner points on a segment, otherwise 1 on the boundary and 0 inside */
    if (snprintf(path, sizeof path, "%s.node", base) >= (int)sizeof path) {
        wr_fail(dg, WR_ERR_INVALID_ARG, -1, "output path too long");
        goto fail;
    }
    if (wr_afile_open(&f, path, dg) != WR_OK) goto fail;
    fprintf(f.fp, "%d 2 0 1\n", r->n_points);
    for (i = 0; i < r->n_points; ++i) {
        int32_t mk = bnd[i];
        if (inv[i] >= 0 && P->has_point_markers && P->point_markers[inv[i]] != 0)
            mk = P->point_markers[inv[i]];
        else if (inv[i] < 0 && r->point_segment[i] >= 0 && P->has_segment_markers)
            mk = P->segment_markers[r->point_segment[i]];
        fprintf(f.fp, "%d %.17g %.17g %d\n", i + first, r->points[2 * i], r->points[2 * i + 1], mk);
    }
    if (wr_afile_commit(&f, dg) != WR_OK) goto fail;
    if (snprintf(path, sizeof path, "%s.ele", base) >= (int)sizeof path) {
        wr_fail(dg, WR_ERR_INVALID_ARG, -1, "output path too long");
        goto fail;
    }
    if (wr_afile_open(&f, path, dg) != WR_OK) goto fail;
    fprintf(f.fp, "%d 3 0\n", r->n_triangles);
    for (t = 0; t < r->n_triangles; ++t)
        fprintf(f.fp, "%d %d %d %d\n", t + first, r->triangles[3 * t] + first, r->triangles[3 * t + 1] + first,
                r->triangles[3 * t + 2] + first);
    if (wr_afile_commit(&f, dg) != WR_OK) goto fail;
    if (poly) {
        if (snprintf(path, sizeof path, "%s.poly", base) >= (int)sizeof path) {
            wr_fail(dg, WR_ERR_INVALID_ARG, -1, "output path too long");
            goto fail;
        }
        if (wr_afile_open(&f, path, dg) != WR_OK) goto fail;
        fprintf(f.fp, "0 2 0 1\n%d 1\n", r->n_segments);
        for (i = 0; i < r->n_segments; ++i)
            fprintf(f.fp, "%d %d %d %d\n", i + first, r->segments[2 * i] + first, r->segments[2 * i + 1] + first,
                    P->has_segment_markers ? P->segment_markers[r->segment_id[i]] : 1);
        fprintf(f.fp, "%d\n", P->n_holes);
        for (i = 0; i < P->n_holes; ++i)
            fprintf(f.fp, "%d %.17g %.17g\n", i + first, P->holes[2 * i], P->holes[2 * i + 1]);
        if (wr_afile_commit(&f, dg) != WR_OK) goto fail;
    }
    wr_free(inv);
    wr_free(bnd);
    return 1;
fail:
    wr_afile_abort(&f);
    wr_free(inv);
    wr_free(bnd);
    return 0;
}

int main(int argc, char **argv) {
    int poly = 0, zero = 0, quiet = 0, verbose = 0, i, rc = 0;
    const char *input = NULL;
    char stem[WR_PATH_MAX], src[WR_PATH_MAX + 8], base[WR_PATH_MAX];
    long steiner = -1;
    wr_cdt_desc d;
    wr_cdt_poly P;
    wr_cdt_input in;
    wr_cdt_result r;
    wr_diag dg;
    wr_status st;
    size_t n;
    wr_cli_set_program(argv[0]);
    memset(&d, 0, sizeof d);
    d.split_intersections = 1; /* Triangle splits intersecting segments */
    for (i = 1; i < argc; ++i) {
        const char *a = argv[i];
        size_t k;
        if (strcmp(a, "-h") == 0 || strcmp(a, "--help") == 0) {
            usage(stdout);
            return 0;
        }
        if (strcmp(a, "--split-intersections") == 0) { /* the default, as in Triangle */
            d.split_intersections = 1;
            continue;
        }
        if (strcmp(a, "--no-split-intersections") == 0) {
            d.split_intersections = 0;
            continue;
        }
        if (a[0] != '-' || a[1] == 0) {
            if (input) {
                wr_cli_error("more than one input file ('%s' and '%s')", input, a);
                return WR_CLI_EXIT_USAGE;
            }
            input = a;
            continue;
        }
        for (k = 1; a[k];) {
            char c = a[k++];
            double x = 0.0;
            int present = 0;
            switch (c) {
            case 'p': poly = 1; break;
            case 'z': zero = 1; break;
            case 'Q': quiet = 1; break;
            case 'V': verbose = 1; break;
            case 'c': d.keep_convex_hull = 1; break;
            case 'h': usage(stdout); return 0;
            case 'q':
                if (!switch_number(a, &k, &x, &present) || (present && !(x > 0.0 && x <= 34.0))) {
                    wr_cli_error("-q: minimum angle must be a number in (0, 34] degrees ('%s')", a);
                    return WR_CLI_EXIT_USAGE;
                }
                d.quality = 1;
                d.min_angle_deg = present ? x : 20.0;
                break;
            case 'a':
                if (!switch_number(a, &k, &x, &present) || !present || !(x > 0.0)) {
                    wr_cli_error("-a: needs a positive maximum area, e.g. -a0.01 ('%s')", a);
                    return WR_CLI_EXIT_USAGE;
                }
                d.max_area = x;
                break;
            case 'S':
                if (!switch_number(a, &k, &x, &present) || !present || x < 0.0 || x != (double)(long)x || x > 1e9) {
                    wr_cli_error("-S: needs a whole number of Steiner points ('%s')", a);
                    return WR_CLI_EXIT_USAGE;
                }
                steiner = (long)x;
                break;
            default:
                wr_cli_error("unknown switch '%c' in '%s' (see --help)", c, a);
                return WR_CLI_EXIT_USAGE;
            }
        }
    }
    if (!input) {
        wr_cli_error("no input file (see --help)");
        return WR_CLI_EXIT_USAGE;
    }
    n = strlen(input);
    if (n + 8 >= sizeof stem) {
        wr_cli_error("input path too long");
        return WR_CLI_EXIT_USAGE;
    }
    memcpy(stem, input, n + 1);
    if (n > 5 && (strcmp(stem + n - 5, ".poly") == 0 || strcmp(stem + n - 5, ".node") == 0)) stem[n - 5] = 0;
    if (snprintf(src, sizeof src, "%s.%s", stem, poly ? "poly" : "node") >= (int)sizeof src) {
        wr_cli_error("input path too long");
        return WR_CLI_EXIT_USAGE;
    }
    st = wr_cdt_poly_read(src, &P, &dg);
    if (st != WR_OK) {
        wr_cli_error("%s", dg.message);
        return st == WR_ERR_NOMEM ? WR_CLI_EXIT_FAILURE : WR_CLI_EXIT_USAGE;
    }
    memset(&in, 0, sizeof in);
    in.points = P.points;
    in.n_points = P.n_points;
    if (poly) {
        in.segments = P.segments;
        in.n_segments = P.n_segments;
        in.holes = P.holes;
        in.n_holes = P.n_holes;
    }
    /* no hidden budget: without -S refinement runs until it is done (the library's default budget
     * is for callers that cannot bound their input; Triangle has none either) */
    d.max_vertices = steiner >= 0 ? (int32_t)(steiner + P.n_points > 2000000000L ? 2000000000L : steiner + P.n_points)
                                  : (int32_t)(INT32_MAX / 4);
    st = wr_cdt_triangulate(&in, &d, &r, &dg);
    if (st != WR_OK && st != WR_ERR_BUDGET) {
        wr_cli_error("%s: %s", src, dg.message);
        wr_cdt_poly_free(&P);
        return st == WR_ERR_NOMEM ? WR_CLI_EXIT_FAILURE : WR_CLI_EXIT_USAGE;
    }
    if (st == WR_ERR_BUDGET) {
        /* Triangle's -S semantics: stop at the limit and write what was reached */
        wr_cli_error("%s: %s%s", src, dg.message, steiner >= 0 ? "" : " (mesh written)");
        if (steiner < 0) rc = 1;
    }
    if (!output_base(stem, base, sizeof base)) {
        wr_cli_error("output path too long");
        wr_cdt_free(&r);
        wr_cdt_poly_free(&P);
        return WR_CLI_EXIT_USAGE;
    }
    {
        char o[WR_PATH_MAX + 8];
        const char *ins[2];
        const char *ext[3] = {"node", "ele", "poly"};
        int k;
        char sib[WR_PATH_MAX + 8];
        ins[0] = src;
        snprintf(sib, sizeof sib, "%s.node", stem); /* a .poly with an empty node section reads it */
        ins[1] = sib;
        for (k = 0; k < (poly ? 3 : 2); ++k) {
            snprintf(o, sizeof o, "%s.%s", base, ext[k]);
            if (!wr_cli_output_ok(o, ins, 2)) {
                wr_cdt_free(&r);
                wr_cdt_poly_free(&P);
                return WR_CLI_EXIT_USAGE;
            }
        }
    }
    if (!write_outputs(base, &P, &r, poly, zero ? 0 : 1, &dg)) {
        wr_cli_error("%s", dg.message);
        wr_cdt_free(&r);
        wr_cdt_poly_free(&P);
        return WR_CLI_EXIT_FAILURE;
    }
    if (!quiet)
        printf("%s: %d vertices (%d Steiner), %d triangles, %d subsegments, min angle %.2f deg -> %s.node/.ele%s\n",
               src, r.n_points, r.n_steiner, r.n_triangles, r.n_segments, r.min_angle_deg, base, poly ? "/.poly" : "");
    if (verbose) {
        wr_cdt_check_info info;
        wr_status cs = wr_cdt_check(&r, -1, &info, &dg);
        printf("  input: %d points (%d duplicates merged), %d segments, %d holes; time %.3f s\n", P.n_points,
               r.n_duplicates, in.n_segments, in.n_holes, r.seconds);
        printf("  check: %s%s%s; components %d, boundary loops %d, Euler V-E+F = %d\n", wr_status_string(cs),
               cs ? ": " : "", cs ? dg.message : "", info.n_components, info.n_boundary_loops, info.euler);
        if (cs != WR_OK) rc = 1;
    }
    wr_cdt_free(&r);
    wr_cdt_poly_free(&P);
    return wr_cli_exit(rc);
}
