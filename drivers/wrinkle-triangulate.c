/* wrinkle-triangulate — Shewchuk Triangle's command line on wrinkle's triangulate.h (exact
 * predicates, constrained or conforming Delaunay, Ruppert/Üngör refinement): a drop-in for scripts
 * written for Triangle. Reads and writes Triangle's files through polyfile.h.
 *
 *   wrinkle-triangulate [-prq[deg]a[area]AcDjevnBPNEIOXzo2YSiFlsCQVg] [--no-split-intersections] name
 *
 * name: name.node, name.poly (or -p), name.ele (refine: -r) or name.area (-r with -a), with or
 * without the extension. Switches (combined as in Triangle: -pq30a0.01e; a number after q, a, S is
 * digits and '.' only, as in Triangle, so -pq30e is -q30 and -e):
 *   -p  triangulate name.poly (segments, holes, regions), constrained
 *   -r  refine a previous mesh: name.node + name.ele (+ name.poly with -p: its segments, and
 *       name.area with -a); triangle attributes of name.ele are inherited; output name.<i+1>.*
 *   -q[deg]  minimum angle (default 20, at most 34)
 *   -a<area> maximum area everywhere; -a alone: the regional maximum areas of the .poly region list
 *       (without -r) or name.area (with -r); both may be given (-a0.1a)
 *   -A  regional attributes: one triangle attribute, the attribute of the region seed's region
 *   -c  keep the convex hull (and write its edges as segments of the .poly)
 *   -D  conforming Delaunay: every edge Delaunay (segments split as needed)
 *   -Y / -YY  no Steiner points on the boundary segments / on any segment
 *   -S<n> at most n Steiner points (stops there and writes the mesh)
 *   -j  jettison vertices no triangle uses (duplicates, vertices eaten by holes)
 *   -e  name.1.edge;  -n  name.1.neigh;  -v  name.1.v.node + name.1.v.edge (Voronoi);  -g  name.1.off
 *   -o2 6-node triangles (edge midpoints as nodes 4-6, opposite corners 1-3)
 *   -B  no boundary markers in the outputs;  -P / -N / -E  do not write the .poly / .node / .ele
 *   -I  no iteration number: outputs name.ele etc. (no .node when the vertices came from name.node,
 *       no .poly — they would be the inputs, as in Triangle; refused with -r)
 *   -O  ignore the holes of the .poly;  -z  number from zero when the input has no vertices (else
 *       the output follows the input's numbering, as in Triangle)
 *   -C  check the final mesh (wr_cdt_check, exact): exit 1 and a message if it fails
 *   -Q  quiet;  -V  verbose (timings and the -C check)
 *   accepted, no effect: -X (Triangle's switch off of exact arithmetic: ours is always exact and its
 *       filter makes that cheap), -i -F -l (Triangle's choice of Delaunay algorithm: incremental,
 *       sweepline, vertical cuts; ours is one randomized incremental algorithm), -s (Triangle's
 *       segment recovery by splitting instead of flips; ours always recovers segments exactly
 *       without Steiner points, use -D for a conforming mesh)
 *   refused: -u (Triangle's user test is C compiled into triangle.c; here it is the callback
 *       wr_cdt_desc.unsuitable of the API), -w -W (weighted/regular triangulations: not implemented)
 *   --no-split-intersections  reject crossing segments (WR_ERR_GEOMETRY naming both) instead of
 *       splitting them at a Steiner point as Triangle does (the default)
 *   -h, --help
 *
 * Outputs are Triangle's files, numbered as its input (vertices keep their input numbers,
 * duplicates included; see polyfile.h ON OUTPUT for markers and attributes); each written
 * atomically, and an output that is an input file is refused. Exit status (as every wrinkle driver):
 * 0 ok; 1 the mesh is written with a caveat (the -C check failed); 2 bad input — command line or
 * input file (one line "file:line: reason" on stderr); 3 the outputs could not be written. The
 * Triangle-style switch string is parsed here (not the --name VALUE form of cli.h). */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"
#include "wrinkle/core.h"
#include "wrinkle/polyfile.h"

static void usage(FILE *f) {
    fprintf(f,
            "usage: wrinkle-triangulate [-prq[deg]a[area]AcDjevnBPNEIOXzo2YSiFlsCQVg] [--no-split-intersections] name\n"
            "  -p        read name.poly (segments, holes, regions): constrained Delaunay\n"
            "  -r        refine name.node + name.ele (+ .poly with -p, .area with -a)\n"
            "  -q[deg]   quality: minimum angle (default 20, at most 34)\n"
            "  -a<area>  maximum area; -a alone: regional areas (.poly regions, or name.area with -r)\n"
            "  -A        regional attributes (one triangle attribute)\n"
            "  -c        keep the convex hull;  -D  conforming Delaunay;  -Y/-YY  no Steiner points on\n"
            "            boundary segments / on any segment;  -S<n>  at most n Steiner points\n"
            "  -j        jettison unused vertices;  -o2  6-node triangles\n"
            "  -e -n -v -g  also write .edge / .neigh / .v.node+.v.edge (Voronoi) / .off\n"
            "  -B        no boundary markers;  -P -N -E  no .poly / .node / .ele;  -I  no iteration number\n"
            "  -O        ignore holes;  -z  zero-based when the input has no vertices\n"
            "  -C        check the mesh (exact);  -Q  quiet;  -V  verbose\n"
            "  -X -i -F -l -s  accepted, no effect (exact arithmetic always; one Delaunay algorithm;\n"
            "            segments always recovered exactly); -u -w -W refused (-u: wr_cdt_desc.unsuitable)\n"
            "  --no-split-intersections  reject crossing segments instead of splitting them\n"
            "writes name.1.node, name.1.ele (and name.1.poly with -p or -c, ...), like Triangle\n"
            "exit status: 0 ok, 1 -C check failed (mesh written), 2 bad input, 3 write failure\n");
}

typedef struct opts {
    int poly, refine, quality, var_area, region_attr, convex, conforming, nobisect, jettison, edges, neighbors,
        voronoi, geomview, order2, no_markers, no_poly, no_node, no_ele, no_iter, no_holes, zero, check, quiet,
        verbose, split;
    double min_angle, max_area;
    long steiner;
    const char *input;
    char command[1024];
} opts;

/* Triangle's number after a switch letter: digits and '.' only (so -pq30e is -q30 -e) */
static int switch_number(const char *s, size_t *k, const char *chars, double *out, int *present) {
    char buf[64];
    size_t b = *k, e = b;
    while (s[e] && strchr(chars, s[e])) ++e;
    *present = e > b;
    if (!*present) return 1;
    if (e - b >= sizeof buf) return 0;
    memcpy(buf, s + b, e - b);
    buf[e - b] = 0;
    *k = e;
    return wr_cli_parse_double(buf, out);
}

/* one switch string "-pq30a.2e"; 0 ok, 1 help shown, -1 error (reported) */
static int parse_switches(const char *a, opts *o) {
    size_t k;
    for (k = 1; a[k];) {
        char c = a[k++];
        double x = 0.0;
        int present = 0;
        switch (c) {
        case 'p': o->poly = 1; break;
        case 'r': o->refine = 1; break;
        case 'A': o->region_attr = 1; break;
        case 'c': o->convex = 1; break;
        case 'D': o->conforming = 1; break;
        case 'j': o->jettison = 1; break;
        case 'e': o->edges = 1; break;
        case 'v': o->voronoi = 1; break;
        case 'n': o->neighbors = 1; break;
        case 'g': o->geomview = 1; break;
        case 'B': o->no_markers = 1; break;
        case 'P': o->no_poly = 1; break;
        case 'N': o->no_node = 1; break;
        case 'E': o->no_ele = 1; break;
        case 'I': o->no_iter = 1; break;
        case 'O': o->no_holes = 1; break;
        case 'z': o->zero = 1; break;
        case 'Y': o->nobisect++; break;
        case 'C': o->check = 1; break;
        case 'Q': o->quiet = 1; break;
        case 'V': o->verbose = 1; break;
        case 'X': case 'i': case 'F': case 'l': case 's': break; /* see the top comment: no effect here */
        case 'h': usage(stdout); return 1;
        case 'o':
            if (a[k] != '2') {
                wr_cli_error("-o: only -o2 (6-node triangles) exists ('%s')", a);
                return -1;
            }
            ++k;
            o->order2 = 1;
            break;
        case 'q':
            if (!switch_number(a, &k, "0123456789.", &x, &present) || (present && !(x > 0.0 && x <= 34.0))) {
                wr_cli_error("-q: minimum angle must be a number in (0, 34] degrees ('%s')", a);
                return -1;
            }
            o->quality = 1;
            o->min_angle = present ? x : 20.0;
            break;
        case 'a':
            if (!switch_number(a, &k, "0123456789.", &x, &present) || (present && !(x > 0.0))) {
                wr_cli_error("-a: a maximum area must be a positive number, e.g. -a0.01 ('%s')", a);
                return -1;
            }
            if (present)
                o->max_area = x;
            else
                o->var_area = 1;
            break;
        case 'S':
            if (!switch_number(a, &k, "0123456789", &x, &present) || !present || x > 1e9) {
                wr_cli_error("-S: needs a whole number of Steiner points ('%s')", a);
                return -1;
            }
            o->steiner = (long)x;
            break;
        case 'u':
            wr_cli_error("-u: Triangle's user test is C code compiled into triangle.c; use the callback "
                         "wr_cdt_desc.unsuitable of wrinkle/triangulate.h");
            return -1;
        case 'w': case 'W':
            wr_cli_error("-%c: weighted (regular) triangulations are not implemented", c);
            return -1;
        default:
            wr_cli_error("unknown switch '%c' in '%s' (see --help)", c, a);
            return -1;
        }
    }
    return 0;
}

/* "dir/name.1" -> "dir/name.2"; "dir/name" -> "dir/name.1" (Triangle's iteration numbers) */
static int output_base(const char *in, char *out, size_t cap) {
    size_t n = strlen(in), d = n;
    while (d > 0 && in[d - 1] >= '0' && in[d - 1] <= '9') --d;
    if (d < n && d > 0 && in[d - 1] == '.' && n - d < 9) {
        long it = strtol(in + d, NULL, 10);
        return snprintf(out, cap, "%.*s%ld", (int)d, in, it + 1) < (int)cap;
    }
    return snprintf(out, cap, "%s.1", in) < (int)cap;
}

static int ends_with(const char *s, const char *t) {
    size_t n = strlen(s), m = strlen(t);
    return n > m && strcmp(s + n - m, t) == 0;
}

/* The files a run reads. */
typedef struct inputs {
    char stem[WR_PATH_MAX], src[WR_PATH_MAX + 8], node[WR_PATH_MAX + 8], ele[WR_PATH_MAX + 8], area[WR_PATH_MAX + 8];
    int node_from_file; /* the vertices come from name.node (not from a .poly node section) */
    wr_cdt_poly P;
    wr_cdt_ele prev;
} inputs;

static int read_inputs(opts *o, inputs *I) {
    size_t n = strlen(o->input);
    wr_diag dg;
    wr_status st;
    if (n + 8 >= sizeof I->stem) {
        wr_cli_error("input path too long");
        return WR_CLI_EXIT_USAGE;
    }
    memcpy(I->stem, o->input, n + 1);
    /* Triangle: the extension of the name given says what to read */
    if (ends_with(I->stem, ".node")) I->stem[n - 5] = 0;
    else if (ends_with(I->stem, ".poly")) I->stem[n - 5] = 0, o->poly = 1;
    else if (ends_with(I->stem, ".ele")) I->stem[n - 4] = 0, o->refine = 1;
    else if (ends_with(I->stem, ".area")) I->stem[n - 5] = 0, o->refine = o->quality = o->var_area = 1;
    if (o->refine && o->no_iter) {
        wr_cli_error("-I cannot be used when refining (-r): the outputs would be the input files");
        return WR_CLI_EXIT_USAGE;
    }
    snprintf(I->src, sizeof I->src, "%s.%s", I->stem, o->poly ? "poly" : "node");
    snprintf(I->node, sizeof I->node, "%s.node", I->stem);
    snprintf(I->ele, sizeof I->ele, "%s.ele", I->stem);
    snprintf(I->area, sizeof I->area, "%s.area", I->stem);
    st = wr_cdt_poly_read(I->src, &I->P, &dg);
    if (st != WR_OK) {
        wr_cli_error("%s", dg.message);
        return st == WR_ERR_NOMEM ? WR_CLI_EXIT_FAILURE : WR_CLI_EXIT_USAGE;
    }
    I->node_from_file = !o->poly;
    if (o->poly) { /* did the .poly carry its own vertices? (its first count: 0 means name.node) */
        FILE *fp = fopen(I->src, "r");
        long nn = -1;
        char line[256];
        while (fp && fgets(line, sizeof line, fp)) { /* the first line with a number */
            char *e;
            nn = strtol(line, &e, 10);
            if (e != line) break;
            nn = -1;
        }
        if (fp) fclose(fp);
        I->node_from_file = nn == 0;
    }
    if (o->refine) {
        st = wr_cdt_ele_read(I->ele, o->var_area ? I->area : NULL, I->P.n_points, I->P.first_index, &I->prev, &dg);
        if (st != WR_OK) {
            wr_cli_error("%s", dg.message);
            return st == WR_ERR_NOMEM ? WR_CLI_EXIT_FAILURE : WR_CLI_EXIT_USAGE;
        }
    }
    return 0;
}

/* The paths this run writes, each checked against every input file. */
static int outputs_ok(const opts *o, const wr_cdt_out_desc *od, const inputs *I, const char *base) {
    const char *ins[4], *ext[8] = {"node", "ele", "poly", "edge", "neigh", "v.node", "v.edge", "off"};
    int k, on[8];
    on[0] = !od->no_node;
    on[1] = !od->no_ele;
    on[2] = od->poly;
    on[3] = od->edges;
    on[4] = od->neighbors;
    on[5] = on[6] = od->voronoi;
    on[7] = o->geomview;
    /* only the files this run reads: with -I a stale name.ele from an earlier run is an output */
    ins[0] = I->src;
    ins[1] = I->node_from_file ? I->node : NULL;
    ins[2] = o->refine ? I->ele : NULL;
    ins[3] = o->refine && o->var_area ? I->area : NULL;
    for (k = 0; k < 8; ++k) {
        char p[WR_PATH_MAX + 32];
        if (!on[k]) continue;
        if (snprintf(p, sizeof p, "%s.%s", base, ext[k]) >= (int)sizeof p) {
            wr_cli_error("output path too long");
            return 0;
        }
        if (!wr_cli_output_ok(p, ins, 4)) return 0;
    }
    return 1;
}

/* Geomview .off (Triangle's -g): vertices with z = 0, triangles 0-based. */
static int write_off(const char *base, const wr_cdt_out *w, wr_diag *dg) {
    char path[WR_PATH_MAX + 24];
    wr_afile f;
    int32_t i;
    memset(&f, 0, sizeof f);
    snprintf(path, sizeof path, "%s.off", base);
    if (wr_afile_open(&f, path, dg) != WR_OK) return 0;
    fprintf(f.fp, "OFF\n%d %d 0\n", w->n_nodes, w->n_elements);
    for (i = 0; i < w->n_nodes; ++i) fprintf(f.fp, "%.17g %.17g 0\n", w->nodes[2 * i], w->nodes[2 * i + 1]);
    for (i = 0; i < w->n_elements; ++i)
        fprintf(f.fp, "3 %d %d %d\n", w->elements[i * w->n_corners], w->elements[i * w->n_corners + 1],
                w->elements[i * w->n_corners + 2]);
    return wr_afile_commit(&f, dg) == WR_OK;
}

/* The command line into o (Triangle's switches, one input file); -1 to go on, else the exit code. */
static int parse_cmdline(int argc, char **argv, opts *o) {
    size_t cl = 0;
    int i, e;
    memset(o, 0, sizeof *o);
    o->split = 1; /* Triangle splits intersecting segments */
    o->steiner = -1;
    for (i = 0; i < argc; ++i) /* Triangle's "# Generated by" line */
        if (cl + strlen(argv[i]) + 2 < sizeof o->command)
            cl += (size_t)snprintf(o->command + cl, sizeof o->command - cl, "%s%s", i ? " " : "", argv[i]);
    for (i = 1; i < argc; ++i) {
        const char *a = argv[i];
        if (strcmp(a, "--help") == 0) {
            usage(stdout);
            return 0;
        }
        if (strcmp(a, "--split-intersections") == 0 || strcmp(a, "--no-split-intersections") == 0) {
            o->split = a[2] == 's';
            continue;
        }
        if (a[0] != '-' || a[1] == 0) {
            if (o->input) {
                wr_cli_error("more than one input file ('%s' and '%s')", o->input, a);
                return WR_CLI_EXIT_USAGE;
            }
            o->input = a;
            continue;
        }
        if ((e = parse_switches(a, o)) != 0) return e > 0 ? 0 : WR_CLI_EXIT_USAGE;
    }
    if (!o->input) {
        wr_cli_error("no input file (see --help)");
        return WR_CLI_EXIT_USAGE;
    }
    return -1;
}

/* What Triangle passes on to the triangulation: holes and regions only from a .poly and not when
 * refining; regional attributes with -A, regional areas with -a (*regions: the copy this needs,
 * caller frees); the previous mesh with -r. 0, or WR_CLI_EXIT_FAILURE when out of memory. */
static int cdt_input(const opts *o, const inputs *I, wr_cdt_input *in, double **regions) {
    int32_t i;
    memset(in, 0, sizeof *in);
    in->points = I->P.points;
    in->n_points = I->P.n_points;
    in->attributes = I->P.attributes;
    in->n_attributes = I->P.n_attributes;
    if (o->poly) {
        in->segments = I->P.segments;
        in->n_segments = I->P.n_segments;
        if (!o->refine && !o->no_holes) {
            in->holes = I->P.holes;
            in->n_holes = I->P.n_holes;
        }
        if (!o->refine && (o->region_attr || o->var_area) && I->P.n_regions > 0) {
            *regions = (double *)wr_alloc_array((size_t)I->P.n_regions, 4 * sizeof(double));
            if (!*regions) {
                wr_cli_error("out of memory");
                return WR_CLI_EXIT_FAILURE;
            }
            memcpy(*regions, I->P.regions, sizeof(double) * 4 * (size_t)I->P.n_regions);
            for (i = 0; i < I->P.n_regions; ++i)
                if (!o->var_area) (*regions)[4 * i + 3] = -1.0; /* the area bounds only with -a */
            in->regions = *regions;
            in->n_regions = I->P.n_regions;
        }
    }
    if (o->refine) {
        in->triangles = I->prev.triangles;
        in->n_triangles = I->prev.n_triangles;
        in->triangle_area = I->prev.areas;
    }
    return 0;
}

static void cdt_desc(const opts *o, const inputs *I, wr_cdt_desc *d) {
    memset(d, 0, sizeof *d);
    d->split_intersections = o->split;
    d->quality = o->quality;
    d->min_angle_deg = o->min_angle;
    d->max_area = o->max_area;
    d->keep_convex_hull = o->convex;
    d->conforming = o->conforming;
    d->no_segment_steiner = o->nobisect > 2 ? 2 : o->nobisect;
    /* no hidden budget: without -S refinement runs until it is done (Triangle has none either) */
    d->max_vertices = o->steiner >= 0 ? (int32_t)(o->steiner + I->P.n_points > 2000000000L ? 2000000000L
                                                                                           : o->steiner + I->P.n_points)
                                      : (int32_t)(INT32_MAX / 4);
}

/* Which files and sections Triangle would write for these switches. */
static void out_desc(const opts *o, const inputs *I, wr_cdt_out_desc *od) {
    memset(od, 0, sizeof *od);
    if (I->P.n_points == 0) {
        od->has_first_number = 1;
        od->first_number = o->zero ? 0 : 1;
    }
    od->poly = (o->poly || o->convex) && !o->no_poly && !o->no_iter;
    od->hull_segments = o->convex;
    od->edges = o->edges;
    od->neighbors = o->neighbors;
    od->voronoi = o->voronoi;
    od->jettison = o->jettison;
    od->second_order = o->order2;
    od->region_attribute = o->region_attr && o->poly && !o->refine;
    od->no_markers = o->no_markers;
    od->no_node = o->no_node || (o->no_iter && I->node_from_file);
    od->no_ele = o->no_ele;
    od->command = o->command;
}

/* The summary line, and with -C or -V wr_cdt_check's verdict; returns 1 when the check fails. */
static int report(const opts *o, const inputs *I, const wr_cdt_input *in, const wr_cdt_result *r, const wr_cdt_out *w,
                  const char *base) {
    wr_cdt_check_info info;
    wr_diag dg;
    wr_status cs;
    if (!o->quiet)
        printf("%s: %d vertices (%d Steiner), %d triangles, %d edges, %d segments, min angle %.2f deg -> %s.*\n",
               I->src, w->n_nodes, r->n_steiner, r->n_triangles, w->n_edges, w->n_segments, r->min_angle_deg, base);
    if (!o->check && !o->verbose) return 0;
    cs = wr_cdt_check(r, -1, &info, &dg);
    if (o->verbose)
        printf("  input: %d vertices (%d duplicates), %d segments, %d holes, %d regions; time %.3f s\n", I->P.n_points,
               r->n_duplicates, in->n_segments, in->n_holes, in->n_regions, r->seconds);
    if (!o->quiet || cs != WR_OK)
        printf("  check: %s%s%s; components %d, boundary loops %d, Euler V-E+F = %d\n", wr_status_string(cs),
               cs ? ": " : "", cs ? dg.message : "", info.n_components, info.n_boundary_loops, info.euler);
    return cs != WR_OK;
}

int main(int argc, char **argv) {
    opts o;
    inputs I;
    wr_cdt_desc d;
    wr_cdt_input in;
    wr_cdt_result r;
    wr_cdt_out w;
    wr_cdt_out_desc od;
    wr_diag dg;
    wr_status st;
    double *regions = NULL;
    char base[WR_PATH_MAX + 16];
    int rc = 0, e;
    wr_cli_set_program(argv[0]);
    /* not memset whole: I holds five path buffers (20 KB), each written before it is read */
    I.stem[0] = I.src[0] = I.node[0] = I.ele[0] = I.area[0] = 0;
    I.node_from_file = 0;
    memset(&I.P, 0, sizeof I.P);
    memset(&I.prev, 0, sizeof I.prev);
    memset(&r, 0, sizeof r);
    memset(&w, 0, sizeof w);
    if ((e = parse_cmdline(argc, argv, &o)) >= 0) return e;
    if ((e = read_inputs(&o, &I)) != 0 || (e = cdt_input(&o, &I, &in, &regions)) != 0) goto out;
    cdt_desc(&o, &I, &d);
    st = wr_cdt_triangulate(&in, &d, &r, &dg);
    if (st != WR_OK && st != WR_ERR_BUDGET) {
        wr_cli_error("%s: %s", I.src, dg.message);
        e = st == WR_ERR_NOMEM ? WR_CLI_EXIT_FAILURE : WR_CLI_EXIT_USAGE;
        goto out;
    }
    if (st == WR_ERR_BUDGET && o.steiner < 0) { /* cannot happen without -S (INT32_MAX/4 vertices) */
        wr_cli_error("%s: %s (mesh written)", I.src, dg.message);
        rc = 1;
    }
    out_desc(&o, &I, &od);
    if ((st = wr_cdt_out_build(&I.P, &in, o.refine ? &I.prev : NULL, &r, &od, &w, &dg)) != WR_OK) {
        wr_cli_error("%s: %s", I.src, dg.message);
        e = WR_CLI_EXIT_FAILURE;
        goto out;
    }
    /* out_desc leaves name.node alone under -I when it is the input; that is only right when the
     * mesh has exactly the input's vertices, else name.ele would index vertices no file holds */
    if (o.no_iter && I.node_from_file && !o.no_node && (r.n_steiner > 0 || w.n_nodes != I.P.n_points)) {
        wr_cli_error("-I: the mesh has %d vertices, not the %d of the input %s, which it would have to replace "
                     "(drop -I)",
                     (int)w.n_nodes, (int)I.P.n_points, I.node);
        e = WR_CLI_EXIT_USAGE;
        goto out;
    }
    if (o.no_iter)
        snprintf(base, sizeof base, "%s", I.stem);
    else if (!output_base(I.stem, base, sizeof base)) {
        wr_cli_error("output path too long");
        e = WR_CLI_EXIT_USAGE;
        goto out;
    }
    if (!outputs_ok(&o, &od, &I, base)) {
        e = WR_CLI_EXIT_USAGE;
        goto out;
    }
    if (wr_cdt_out_write(&w, &I.P, base, &od, &dg) != WR_OK || (o.geomview && !write_off(base, &w, &dg))) {
        wr_cli_error("%s", dg.message);
        e = WR_CLI_EXIT_FAILURE;
        goto out;
    }
    if (report(&o, &I, &in, &r, &w, base)) rc = 1;
    e = wr_cli_exit(rc);
out:
    wr_cdt_out_free(&w);
    wr_cdt_free(&r);
    wr_cdt_poly_free(&I.P);
    wr_cdt_ele_free(&I.prev);
    wr_free(regions);
    return e;
}
