/* wrinkle/polyfile.h — Shewchuk Triangle's files: .node / .poly / .ele / .area read into arrays for
 * wr_cdt_triangulate (triangulate.h), and a result written back as Triangle writes it (.node, .ele,
 * .poly, .edge, .neigh, .v.node / .v.edge, 6-node elements) — the input and output of
 * wrinkle-triangulate and of scripts written for Triangle.
 * wrinkle v0.1.0 — MIT licence (see LICENSE). Needs only libc and libm.
 *
 * Formats (Triangle's documentation): .node "<#vertices> <dim 2> <#attributes> <#markers 0|1>" then
 * one line "<i> <x> <y> [attributes] [marker]" per vertex; .poly: a node section (or "0 2 0 1" and a
 * sibling .node), "<#segments> <#markers>" and "<j> <a> <b> [marker]", "<#holes>" and "<k> <x> <y>",
 * optionally "<#regions>" and "<r> <x> <y> <attribute> <maximum area>" (one number after x y is
 * both, as in Triangle); .ele "<#triangles> <#nodes 3|6> <#attributes>" and "<t> <a> <b> <c> [...]";
 * .area "<#triangles>" and "<t> <maximum area>" (<= 0: none); .edge "<#edges> <#markers>" and
 * "<e> <a> <b> [marker]"; .neigh "<#triangles> 3" and "<t> <n0> <n1> <n2>" (n_k across the edge
 * opposite corner k, -1 on the boundary); .v.node: one Voronoi vertex per triangle (its
 * circumcentre, attributes interpolated linearly); .v.edge "<e> <t1> <t2>", or "<e> <t> -1 <dx>
 * <dy>" for the ray outward across a boundary edge (direction: the edge turned clockwise, its length).
 * Numbering from 0 or 1 (the first vertex decides, and the output follows it); '#' starts a comment.
 * Errors name "file:line".
 *
 * ON OUTPUT (Triangle's conventions, checked against Triangle 1.6's own output)
 *   Every input vertex keeps its number, duplicates included (they are written but used by no
 *   triangle; -j / jettison drops unused vertices and renumbers); Steiner points follow, then with
 *   second_order the edge midpoints. Boundary markers: a vertex's nonzero input marker is kept;
 *   otherwise it takes the nonzero marker of the lowest-numbered input segment through it; otherwise
 *   1 when it lies on the mesh boundary, else 0. A subsegment carries its segment's marker, or 1 when
 *   that is 0 and the subsegment bounds the mesh; an unconstrained boundary edge 1; other edges 0;
 *   a midpoint its edge's. Triangle attributes: those of the previous mesh's triangle a triangle
 *   descends from (refinement), then with region_attribute the attribute of the region it lies in
 *   (0 outside every region). Subsegments that bound no remaining triangle are not written.
 *
 * API
 *   wr_cdt_poly_parse(poly_text, node_text, name, out, diag)   from memory
 *   wr_cdt_poly_read(path, out, diag)                          from name.poly (+ name.node) or name.node
 *   wr_cdt_poly_free(p)
 *   wr_cdt_ele_parse(ele_text, area_text, name, area_name, n_points, first, out, diag)   a previous mesh
 *   wr_cdt_ele_read(ele_path, area_path, n_points, first, out, diag), wr_cdt_ele_free(e)
 *   wr_cdt_out_build(poly, input, prev, result, desc, out, diag)   Triangle's outputs as arrays
 *   wr_cdt_out_write(out, poly, base, desc, diag)   base.node, .ele, .poly, .edge, .neigh, .v.node, .v.edge
 *   wr_cdt_out_free(o)
 *
 * EXAMPLE
 *     wr_cdt_poly P; wr_diag dg;
 *     const char *poly = "4 2 0 0\n1 0 0\n2 1 0\n3 1 1\n4 0 1\n4 0\n1 1 2\n2 2 3\n3 3 4\n4 4 1\n0\n";
 *     if (wr_cdt_poly_parse(poly, NULL, "square.poly", &P, &dg) != WR_OK) { puts(dg.message); return 1; }
 *     printf("%d vertices, %d segments\n", P.n_points, P.n_segments);   // 4, 4 (0-based in P)
 *     wr_cdt_poly_free(&P);
 *
 * ON UNITS, OWNERSHIP AND THREADS
 *   Coordinates, attributes and areas are read and written as the files hold them (no unit is
 *   assumed; the triangulator's tolerances are in the same unit). Every parse/read/build fills a
 *   caller-owned struct that the matching _free releases (a failed call leaves it zeroed, so _free
 *   is safe either way). Text I/O assumes the "C" numeric locale: numbers are read to the double
 *   strtod gives and reals written as printf's "%.17g" writes them (exact integer arithmetic of its
 *   own, libc where that does not reach). No global state.
 */
#ifndef WRINKLE_POLYFILE_H
#define WRINKLE_POLYFILE_H

#include "triangulate.h"

#ifdef __cplusplus
extern "C" {
#endif

/* ---- Triangle's .node / .poly files ---- */
typedef struct wr_cdt_poly {
    double *points;           /* n_points × 2 */
    int32_t n_points;
    double *attributes;       /* n_points × n_attributes vertex attributes (NULL when none) */
    int32_t n_attributes;
    int32_t *point_markers;   /* n_points boundary markers (0 when the file has none) */
    int32_t *segments;        /* n_segments × 2, converted to 0-based */
    int32_t n_segments;
    int32_t *segment_markers; /* n_segments (0 when the file has none) */
    double *holes;            /* n_holes × 2 */
    int32_t n_holes;
    double *regions;          /* n_regions × 4: seed x, y, attribute, maximum area (as wr_cdt_input) */
    int32_t n_regions;
    int first_index;          /* 0 or 1: numbering the file used (from its first vertex) */
    int has_point_markers, has_segment_markers;
} wr_cdt_poly;

/* poly_text: contents of a .poly file (NULL: read only node_text as a .node file). node_text: the
 * .node file, needed when the .poly node section is empty ("0 2 0 1"), else may be NULL. name:
 * file name used in messages "name:line: reason". */
WRDEF wr_status wr_cdt_poly_parse(const char *poly_text, const char *node_text, const char *name,
                                  wr_cdt_poly *out, wr_diag *diag);
/* path ending in .poly (reads the sibling .node if needed) or .node. */
WRDEF wr_status wr_cdt_poly_read(const char *path, wr_cdt_poly *out, wr_diag *diag);
WRDEF void wr_cdt_poly_free(wr_cdt_poly *p);

/* A previous mesh (Triangle's .ele, with its .area) to refine: wr_cdt_input.triangles and
 * .triangle_area. */
typedef struct wr_cdt_ele {
    int32_t *triangles;  /* n_triangles × 3 corners, 0-based (the extra nodes of 6-node elements dropped) */
    int32_t n_triangles;
    int32_t n_corners;   /* nodes per element in the file (3 or 6) */
    double *attributes;  /* n_triangles × n_attributes (NULL when none) */
    int32_t n_attributes;
    double *areas;       /* n_triangles maximum areas from the .area file (<= 0: none); NULL without one */
} wr_cdt_ele;

/* ele_text: the .ele file; area_text: its .area file or NULL. n_points: vertices of the mesh (corner
 * numbers are checked against it); first: the vertex numbering (wr_cdt_poly.first_index). */
WRDEF wr_status wr_cdt_ele_parse(const char *ele_text, const char *area_text, const char *name,
                                 const char *area_name, int32_t n_points, int first, wr_cdt_ele *out,
                                 wr_diag *diag);
WRDEF wr_status wr_cdt_ele_read(const char *ele_path, const char *area_path, int32_t n_points, int first,
                                wr_cdt_ele *out, wr_diag *diag);
WRDEF void wr_cdt_ele_free(wr_cdt_ele *e);

/* What wr_cdt_out_build makes and wr_cdt_out_write writes (zero means default: .node and .ele, the
 * input's numbering, boundary markers written):
 *   first_number, has_first_number  numbering of the files (default: the input's first_index)
 *   poly           also write base.poly (the subsegments, the holes, the regions passed in)
 *   hull_segments  the unconstrained boundary edges are segments of the .poly too (Triangle's -c)
 *   edges          base.edge (-e);  neighbors: base.neigh (-n);  voronoi: base.v.node/.v.edge (-v)
 *   jettison       drop vertices no triangle uses (duplicates, eaten by holes) and renumber (-j)
 *   second_order   6-node triangles: edge midpoints as nodes 4-6 opposite corners 1-3 (-o2)
 *   region_attribute  one more triangle attribute: the region's (-A)
 *   no_markers     no boundary markers in the files (-B)
 *   no_node, no_ele  do not write base.node / base.ele (-N, -E)
 *   command        written as a last comment line "# Generated by <command>" when not NULL */
typedef struct wr_cdt_out_desc {
    int32_t first_number;
    int has_first_number;
    int poly, hull_segments, edges, neighbors, voronoi, jettison, second_order, region_attribute;
    int no_markers, no_node, no_ele;
    const char *command;
} wr_cdt_out_desc;

/* Triangle's outputs as arrays, numbered from 0 (the files add first_number). */
typedef struct wr_cdt_out {
    int32_t n_nodes;
    double *nodes;            /* n_nodes × 2 */
    double *node_attributes;  /* n_nodes × n_node_attributes */
    int32_t n_node_attributes;
    int32_t *node_markers;    /* n_nodes */
    int32_t *node_of;         /* result vertex -> node (-1: jettisoned) */
    int32_t n_elements, n_corners;
    int32_t *elements;        /* n_elements × n_corners */
    double *element_attributes; /* n_elements × n_element_attributes */
    int32_t n_element_attributes;
    int32_t *neighbors;       /* n_elements × 3 */
    int32_t n_edges;
    int32_t *edges;           /* n_edges × 2 nodes */
    int32_t *edge_markers;    /* n_edges */
    int32_t *edge_triangles;  /* n_edges × 2: the triangles on each side (second -1 on the boundary) */
    int32_t n_segments;
    int32_t *segments;        /* n_segments × 2 nodes */
    int32_t *segment_markers;
    double *voronoi_nodes;    /* n_elements × 2 circumcentres (with desc.voronoi) */
    double *voronoi_attributes; /* n_elements × n_node_attributes */
    int32_t *voronoi_edges;   /* n_edges × 2 Voronoi vertices (second -1: a ray) */
    double *voronoi_rays;     /* n_edges × 2 ray directions (0 for finite edges) */
    int32_t n_regions;        /* regions written to the .poly */
    const double *regions;
} wr_cdt_out;

/* poly: the files read (markers, attributes, holes); input: what was passed to wr_cdt_triangulate
 * (its regions); prev: the previous mesh when refining (its triangle attributes), may be NULL;
 * r: the result. */
WRDEF wr_status wr_cdt_out_build(const wr_cdt_poly *poly, const wr_cdt_input *input, const wr_cdt_ele *prev,
                                 const wr_cdt_result *r, const wr_cdt_out_desc *desc, wr_cdt_out *out,
                                 wr_diag *diag);
/* Writes base.node, base.ele and what desc asks for, each atomically (wr_afile). */
WRDEF wr_status wr_cdt_out_write(const wr_cdt_out *o, const wr_cdt_poly *poly, const char *base,
                                 const wr_cdt_out_desc *desc, wr_diag *diag);
WRDEF void wr_cdt_out_free(wr_cdt_out *o);

#ifdef __cplusplus
}
#endif
#endif /* WRINKLE_POLYFILE_H */

#ifdef WRINKLE_IMPLEMENTATION
#ifndef WRINKLE_POLYFILE_IMPLEMENTATION_DONE
#define WRINKLE_POLYFILE_IMPLEMENTATION_DONE

#include <float.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#ifdef __cplusplus
extern "C" {
#endif

/* ---- decimal numbers in and out ----
 * wr__dec_read: a token [+-]digits[.digits][e[+-]digits] (or .digits) to the double strtod gives, for
 * 19 significant digits or fewer and a decimal exponent within +-19 of them (Clinger's exact
 * double-precision path for w <= 2^53 and |q| <= 22, else w * 10^q in 128-bit integers, rounded to
 * nearest-even with a sticky bit). 0 for any other token (hex, inf, nan, more digits, a wider
 * exponent): the caller uses strtod. wr__fmt_g17: the text printf's "%.17g" gives (17 significant
 * digits rounded to nearest-even from the exact binary value, trailing zeros dropped), from the
 * exact product m * 2^e * 10^s in 128 bits when it fits, else through snprintf. Both need a 128-bit
 * integer type (GCC, Clang) and fall back to strtod / snprintf without one. */
static const uint64_t wr__p10u[20] = {1ull,
                                      10ull,
                                      100ull,
                                      1000ull,
                                      10000ull,
                                      100000ull,
                                      1000000ull,
                                      10000000ull,
                                      100000000ull,
                                      1000000000ull,
                                      10000000000ull,
                                      100000000000ull,
                                      1000000000000ull,
                                      10000000000000ull,
                                      100000000000000ull,
                                      1000000000000000ull,
                                      10000000000000000ull,
                                      100000000000000000ull,
                                      1000000000000000000ull,
                                      10000000000000000000ull};
static const double wr__p10d[23] = {1e0,  1e1,  1e2,  1e3,  1e4,  1e5,  1e6,  1e7,  1e8,  1e9,  1e10, 1e11,
                                    1e12, 1e13, 1e14, 1e15, 1e16, 1e17, 1e18, 1e19, 1e20, 1e21, 1e22};
static const char wr__dig2[201] = "00010203040506070809101112131415161718192021222324"
                                  "25262728293031323334353637383940414243444546474849"
                                  "50515253545556575859606162636465666768697071727374"
                                  "75767778798081828384858687888990919293949596979899";
/* v as exactly nd decimal digits (leading zeros) at b, two at a time */
static void wr__put_digits(char *b, uint32_t v, int nd) {
    for (; nd >= 2; nd -= 2, v /= 100u) memcpy(b + nd - 2, wr__dig2 + 2 * (v % 100u), 2);
    if (nd) b[0] = (char)('0' + (int)v);
}
#if defined(__SIZEOF_INT128__)
#define WR__HAS_U128 1
__extension__ typedef unsigned __int128 wr__u128;
static int wr__u128_bits(wr__u128 v) {
    uint64_t hi = (uint64_t)(v >> 64), lo = (uint64_t)v;
    return hi ? 128 - __builtin_clzll(hi) : lo ? 64 - __builtin_clzll(lo) : 0;
}
/* v * 2^sh rounded to a double, v's bits below the 53 kept rounded to nearest-even; sticky: a
 * nonzero part below v's last bit was dropped. */
static double wr__u128_round(wr__u128 v, int sh, int sticky) {
    int nb = wr__u128_bits(v), cut = nb > 53 ? nb - 53 : 0;
    uint64_t m = (uint64_t)(v >> cut);
    if (cut > 0) {
        wr__u128 low = v & ((((wr__u128)1) << cut) - 1), half = ((wr__u128)1) << (cut - 1);
        if (low > half || (low == half && (sticky || (m & 1u)))) ++m;
    }
    { /* m * 2^(cut + sh): m < 2^54 exact, 2^(cut + sh) a normal double, the product normal here */
        uint64_t pb = (uint64_t)(cut + sh + 1023) << 52;
        double p2;
        memcpy(&p2, &pb, sizeof p2);
        return (double)m * p2;
    }
}
#endif

static int wr__dec_read(const char *s, int n, double *x) {
#ifdef WR__HAS_U128
    const char *e = s + n;
    uint64_t w = 0;
    int neg = 0, nd = 0, q = 0, seen = 0, ex = 0, eneg = 0;
    if (s < e && (*s == '+' || *s == '-')) neg = *s++ == '-';
    for (; s < e && *s >= '0' && *s <= '9'; ++s, seen = 1)
        if (w || *s != '0') {
            if (++nd > 19) return 0;
            w = 10u * w + (uint64_t)(*s - '0');
        }
    if (s < e && *s == '.')
        for (++s; s < e && *s >= '0' && *s <= '9'; ++s, seen = 1) {
            --q;
            if (w || *s != '0') {
                if (++nd > 19) return 0;
                w = 10u * w + (uint64_t)(*s - '0');
            }
        }
    if (!seen) return 0;
    if (s < e && (*s == 'e' || *s == 'E')) {
        if (++s < e && (*s == '+' || *s == '-')) eneg = *s++ == '-';
        if (s == e) return 0;
        for (; s < e && *s >= '0' && *s <= '9'; ++s)
            if ((ex = 10 * ex + (*s - '0')) > 9999) return 0;
        q += eneg ? -ex : ex;
    }
    if (s != e) return 0;
    if (w == 0) {
        *x = neg ? -0.0 : 0.0;
        return 1;
    }
#if defined(FLT_EVAL_METHOD) && FLT_EVAL_METHOD == 0
    if (w <= (1ull << 53) && q >= -22 && q <= 22) { /* both operands exact: one rounding */
        *x = q < 0 ? (double)w / wr__p10d[-q] : (double)w * wr__p10d[q];
        if (neg) *x = -*x;
        return 1;
    }
#endif
    if (q >= 0 && q <= 19) {
        *x = wr__u128_round((wr__u128)w * wr__p10u[q], 0, 0);
    } else if (q < 0 && q >= -19) {
        int k = 128 - wr__u128_bits(w);
        wr__u128 num = ((wr__u128)w) << k, p = wr__p10u[-q];
        *x = wr__u128_round(num / p, -k, num % p != 0);
    } else {
        return 0;
    }
    if (neg) *x = -*x;
    return 1;
#else
    (void)s, (void)n, (void)x;
    return 0;
#endif
}

/* "%.17g" of x into b (room for 32 characters); returns the length. */
static int wr__fmt_g17(char *b, double x) {
#ifdef WR__HAS_U128
    uint64_t bits, m, q = 0;
    int be, e, d, s, len = 0, nd = 17, i, pass;
    char dg[20];
    memcpy(&bits, &x, sizeof bits);
    be = (int)((bits >> 52) & 0x7ffu);
    m = (bits & ((1ull << 52) - 1u)) | (1ull << 52);
    e = be - 1075; /* |x| = m * 2^e */
    if (be == 0 && (bits << 1) == 0) { /* +-0 */
        if (bits >> 63) b[len++] = '-';
        b[len++] = '0';
        b[len] = 0;
        return len;
    }
    if (be == 0 || be == 0x7ff || e > 70) return snprintf(b, 32, "%.17g", x);
    d = (int)floor((e + 52) * 0.30102999566398120); /* floor(log10 |x|) or one less */
    for (pass = 0; pass < 2; ++pass) {
        wr__u128 v;
        s = 16 - d; /* q = round(|x| * 10^s) has 17 digits */
        if (s > 22 || s < -22) return snprintf(b, 32, "%.17g", x);
        if (s >= 0) {
            v = (wr__u128)m * wr__p10u[s > 19 ? 19 : s];
            if (s > 19) v *= wr__p10u[s - 19];
            if (e >= 0) {
                q = (uint64_t)(v << e);
            } else {
                wr__u128 low = v & ((((wr__u128)1) << -e) - 1), half = ((wr__u128)1) << (-e - 1);
                q = (uint64_t)(v >> -e);
                if (low > half || (low == half && (q & 1u))) ++q;
            }
        } else {
            wr__u128 p = (wr__u128)wr__p10u[-s > 19 ? 19 : -s], r;
            if (-s > 19) p *= wr__p10u[-s - 19];
            v = ((wr__u128)m) << e;
            q = (uint64_t)(v / p);
            r = v % p;
            if (2 * r > p || (2 * r == p && (q & 1u))) ++q;
        }
        if (q < wr__p10u[17]) break;
        ++d; /* |x| >= 10^(d+1), or rounding carried to 10^17 */
    }
    if (q >= wr__p10u[17]) q /= 10u; /* the carry: 10^17 -> 10^16 */
    wr__put_digits(dg, (uint32_t)(q / 100000000u), 9);
    wr__put_digits(dg + 9, (uint32_t)(q % 100000000u), 8);
    while (nd > 1 && dg[nd - 1] == '0') --nd;
    if (bits >> 63) b[len++] = '-';
    if (d >= -4 && d < 17) {
        if (d < 0) { /* 0.000ddd */
            b[len++] = '0';
            b[len++] = '.';
            for (i = -1; i > d; --i) b[len++] = '0';
            memcpy(b + len, dg, (size_t)nd);
            len += nd;
        } else if (nd <= d + 1) { /* an integer: ddd000 */
            memcpy(b + len, dg, (size_t)nd);
            memset(b + len + nd, '0', (size_t)(d + 1 - nd));
            len += d + 1;
        } else { /* ddd.ddd */
            memcpy(b + len, dg, (size_t)(d + 1));
            b[len + d + 1] = '.';
            memcpy(b + len + d + 2, dg + d + 1, (size_t)(nd - d - 1));
            len += nd + 1;
        }
    } else {
        b[len++] = dg[0];
        if (nd > 1) b[len++] = '.';
        for (i = 1; i < nd; ++i) b[len++] = dg[i];
        b[len++] = 'e';
        b[len++] = d < 0 ? '-' : '+';
        if (d < 0) d = -d;
        if (d >= 100) b[len++] = (char)('0' + d / 100);
        b[len++] = (char)('0' + d / 10 % 10);
        b[len++] = (char)('0' + d % 10);
    }
    b[len] = 0;
    return len;
#else
    return snprintf(b, 32, "%.17g", x);
#endif
}

/* ---- Triangle .node / .poly reader ---- */
#define WR__PL_MAXTOK 64 /* tokens looked at per line: index, x, y, up to 60 attributes, marker */
typedef struct wr__pl {
    const char *p;    /* next unread character */
    const char *name; /* for messages */
    int line;         /* current line number (1-based) */
    int ntok;
    const char *tok[WR__PL_MAXTOK];
    int tlen[WR__PL_MAXTOK];
} wr__pl;

/* Advance to the next line holding tokens ('#' starts a comment). 0 at end of text. */
static int wr__pl_next(wr__pl *L) {
    while (*L->p) {
        const char *s = L->p;
        int in_comment = 0;
        L->line++;
        L->ntok = 0;
        while (*s && *s != '\n' && *s != '\r') {
            if (*s == '#') in_comment = 1;
            if (!in_comment && !(*s == ' ' || *s == '\t' || *s == ',')) {
                const char *b = s;
                while (*s && *s != '\n' && *s != '\r' && *s != ' ' && *s != '\t' && *s != ',' && *s != '#') ++s;
                if (L->ntok < WR__PL_MAXTOK) {
                    L->tok[L->ntok] = b;
                    L->tlen[L->ntok] = (int)(s - b);
                }
                L->ntok++;
                continue;
            }
            ++s;
        }
        if (*s == '\r' && s[1] == '\n') ++s;
        if (*s) ++s;
        L->p = s;
        if (L->ntok > 0) return 1;
    }
    return 0;
}

static int wr__pl_num(const wr__pl *L, int i, double *x) {
    char buf[128], *end;
    if (i >= L->ntok || i >= WR__PL_MAXTOK || L->tlen[i] >= (int)sizeof buf) return 0;
    if (wr__dec_read(L->tok[i], L->tlen[i], x)) return 1;
    memcpy(buf, L->tok[i], (size_t)L->tlen[i]);
    buf[L->tlen[i]] = 0;
    *x = strtod(buf, &end);
    return end != buf && *end == 0 && isfinite(*x);
}
static int wr__pl_int(const wr__pl *L, int i, int32_t *v) {
    double x;
    if (!wr__pl_num(L, i, &x) || x != floor(x) || x < -2147483647.0 || x > 2147483647.0) return 0;
    *v = (int32_t)x;
    return 1;
}

/* Each vertex, segment or hole takes a line of its own, so a section declaring more entries than
 * there are lines left cannot be complete: checked before allocating, so a header that declares
 * 2e8 vertices in a 100-byte file fails at once instead of reserving gigabytes (fuzzer finding
 * tests/regressions/poly_huge_vertex_count.fuzz_poly). Counts '\n' and '\r' (an upper bound on the
 * lines left), stopping as soon as `need` is reached. */
static int wr__pl_lines_left(const wr__pl *L, int32_t need) {
    const char *s = L->p;
    int32_t n;
    if (need <= 0) return 1;
    n = *s ? 1 : 0;
    for (; *s && n < need; ++s)
        if (*s == '\n' || *s == '\r') ++n;
    return n >= need;
}

/* node section (header already on the current line) */
static wr_status wr__pl_nodes(wr__pl *L, wr_cdt_poly *out, wr_diag *diag) {
    int32_t n, dim, nattr = 0, nmark = 0, i, k;
    if (!wr__pl_int(L, 0, &n) || n < 0)
        return wr_fail(diag, WR_ERR_PARSE, -1, "%s:%d: bad vertex count", L->name, L->line);
    if (L->ntok > 1 && (!wr__pl_int(L, 1, &dim) || dim != 2))
        return wr_fail(diag, WR_ERR_PARSE, -1, "%s:%d: dimension must be 2", L->name, L->line);
    if (L->ntok > 2 && (!wr__pl_int(L, 2, &nattr) || nattr < 0 || nattr > WR__PL_MAXTOK - 4))
        return wr_fail(diag, WR_ERR_PARSE, -1, "%s:%d: bad attribute count (0..%d)", L->name, L->line,
                       WR__PL_MAXTOK - 4);
    if (L->ntok > 3 && (!wr__pl_int(L, 3, &nmark) || nmark < 0 || nmark > 1))
        return wr_fail(diag, WR_ERR_PARSE, -1, "%s:%d: boundary-marker count must be 0 or 1", L->name, L->line);
    if (n > INT32_MAX / 8) return wr_fail(diag, WR_ERR_PARSE, -1, "%s:%d: too many vertices", L->name, L->line);
    if (!wr__pl_lines_left(L, n))
        return wr_fail(diag, WR_ERR_PARSE, -1, "%s:%d: declares %d vertices but fewer lines follow", L->name, L->line,
                       n);
    out->points = (double *)wr_alloc_array((size_t)n * 2, sizeof(double));
    out->point_markers = (int32_t *)wr_calloc_array((size_t)n, sizeof(int32_t));
    if (nattr > 0) out->attributes = (double *)wr_alloc_array((size_t)n * (size_t)nattr, sizeof(double));
    if (!out->points || !out->point_markers || (nattr > 0 && n > 0 && !out->attributes))
        return wr_fail(diag, WR_ERR_NOMEM, -1, "out of memory");
    out->n_attributes = nattr;
    out->has_point_markers = nmark;
    for (i = 0; i < n; ++i) {
        int32_t idx;
        if (!wr__pl_next(L))
            return wr_fail(diag, WR_ERR_PARSE, -1, "%s:%d: file ends after %d of %d vertices", L->name, L->line, i, n);
        if (L->ntok < 3 + nattr + nmark || !wr__pl_int(L, 0, &idx) || !wr__pl_num(L, 1, &out->points[2 * i]) ||
            !wr__pl_num(L, 2, &out->points[2 * i + 1]))
            return wr_fail(diag, WR_ERR_PARSE, -1, "%s:%d: expected '<index> <x> <y>%s%s' with finite numbers",
                           L->name, L->line, nattr ? " <attributes>" : "", nmark ? " <marker>" : "");
        if (i == 0) out->first_index = idx == 0 ? 0 : 1; /* Triangle's rule: numbering follows vertex 1 */
        if (idx != out->first_index + i)
            return wr_fail(diag, WR_ERR_PARSE, -1, "%s:%d: vertex number %d, expected %d", L->name, L->line, idx,
                           out->first_index + i);
        for (k = 0; k < nattr; ++k)
            if (!wr__pl_num(L, 3 + k, &out->attributes[(size_t)i * nattr + k]))
                return wr_fail(diag, WR_ERR_PARSE, -1, "%s:%d: attribute %d is not a finite number", L->name,
                               L->line, k + 1);
        if (nmark && !wr__pl_int(L, 3 + nattr, &out->point_markers[i]))
            return wr_fail(diag, WR_ERR_PARSE, -1, "%s:%d: bad boundary marker", L->name, L->line);
        out->n_points = i + 1;
    }
    return WR_OK;
}

/* region list (header on the current line): "<r> <x> <y> <attribute> [<maximum area>]" */
static wr_status wr__pl_regions(wr__pl *L, wr_cdt_poly *out, wr_diag *diag) {
    int32_t nr, i;
    if (!wr__pl_int(L, 0, &nr) || nr < 0 || nr > INT32_MAX / 8)
        return wr_fail(diag, WR_ERR_PARSE, -1, "%s:%d: bad region count", L->name, L->line);
    if (!wr__pl_lines_left(L, nr))
        return wr_fail(diag, WR_ERR_PARSE, -1, "%s:%d: declares %d regions but fewer lines follow", L->name, L->line,
                       nr);
    out->regions = (double *)wr_alloc_array((size_t)nr * 4, sizeof(double));
    if (nr > 0 && !out->regions) return wr_fail(diag, WR_ERR_NOMEM, -1, "out of memory");
    for (i = 0; i < nr; ++i) {
        double *g = out->regions + 4 * i;
        int32_t idx;
        if (!wr__pl_next(L) || L->ntok < 4 || !wr__pl_int(L, 0, &idx) || !wr__pl_num(L, 1, g) ||
            !wr__pl_num(L, 2, g + 1) || !wr__pl_num(L, 3, g + 2) || (L->ntok > 4 && !wr__pl_num(L, 4, g + 3)))
            return wr_fail(diag, WR_ERR_PARSE, -1,
                           "%s:%d: expected '<index> <x> <y> <attribute> [<maximum area>]' for region %d of %d",
                           L->name, L->line, i + out->first_index, nr);
        if (L->ntok == 4) g[3] = g[2]; /* Triangle: a lone value is both attribute and area bound */
        out->n_regions = i + 1;
    }
    return WR_OK;
}

WRDEF void wr_cdt_poly_free(wr_cdt_poly *p) {
    if (!p) return;
    wr_free(p->points);
    wr_free(p->point_markers);
    wr_free(p->segments);
    wr_free(p->segment_markers);
    wr_free(p->holes);
    wr_free(p->attributes);
    wr_free(p->regions);
    memset(p, 0, sizeof *p);
}

WRDEF wr_status wr_cdt_poly_parse(const char *poly_text, const char *node_text, const char *name, wr_cdt_poly *out,
                                  wr_diag *diag) {
    wr__pl L;
    wr_status st;
    int32_t n_nodes, m, nmark = 0, i, nh;
    char nodename[WR_PATH_MAX];
    if (!out) return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "out is NULL");
    memset(out, 0, sizeof *out);
    if (!name) name = "<input>";
    {
        size_t ln = strlen(name);
        if (ln > 5 && strcmp(name + ln - 5, ".poly") == 0 && ln < sizeof nodename) {
            memcpy(nodename, name, ln - 5);
            memcpy(nodename + ln - 5, ".node", 6);
        } else {
            snprintf(nodename, sizeof nodename, "%s", name);
        }
    }
    if (!poly_text && !node_text) return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "no text to parse");
    memset(&L, 0, sizeof L);
    if (!poly_text) { /* a lone .node file */
        L.p = node_text;
        L.name = name;
        if (!wr__pl_next(&L)) return wr_fail(diag, WR_ERR_PARSE, -1, "%s:%d: empty file", name, L.line);
        st = wr__pl_nodes(&L, out, diag);
        if (st != WR_OK) wr_cdt_poly_free(out);
        return st;
    }
    L.p = poly_text;
    L.name = name;
    if (!wr__pl_next(&L)) return wr_fail(diag, WR_ERR_PARSE, -1, "%s:%d: empty file", name, L.line);
    if (!wr__pl_int(&L, 0, &n_nodes) || n_nodes < 0)
        return wr_fail(diag, WR_ERR_PARSE, -1, "%s:%d: bad vertex count", name, L.line);
    if (n_nodes > 0) {
        st = wr__pl_nodes(&L, out, diag);
        if (st != WR_OK) goto fail;
    } else { /* "0 2 0 1": the vertices are in the .node file */
        wr__pl N;
        if (!node_text) {
            st = wr_fail(diag, WR_ERR_PARSE, -1, "%s:%d: the node section is empty and no .node file was read", name,
                         L.line);
            goto fail;
        }
        memset(&N, 0, sizeof N);
        N.p = node_text;
        N.name = nodename;
        if (!wr__pl_next(&N)) {
            st = wr_fail(diag, WR_ERR_PARSE, -1, "%s:%d: empty file", nodename, N.line);
            goto fail;
        }
        st = wr__pl_nodes(&N, out, diag);
        if (st != WR_OK) goto fail;
    }
    if (!wr__pl_next(&L)) {
        st = wr_fail(diag, WR_ERR_PARSE, -1, "%s:%d: missing segment section", name, L.line);
        goto fail;
    }
    if (!wr__pl_int(&L, 0, &m) || m < 0 || m > INT32_MAX / 8 ||
        (L.ntok > 1 && (!wr__pl_int(&L, 1, &nmark) || nmark < 0 || nmark > 1))) {
        st = wr_fail(diag, WR_ERR_PARSE, -1, "%s:%d: expected '<#segments> <#markers 0|1>'", name, L.line);
        goto fail;
    }
    if (!wr__pl_lines_left(&L, m)) {
        st = wr_fail(diag, WR_ERR_PARSE, -1, "%s:%d: declares %d segments but fewer lines follow", name, L.line, m);
        goto fail;
    }
    out->segments = (int32_t *)wr_alloc_array((size_t)m * 2, sizeof(int32_t));
    out->segment_markers = (int32_t *)wr_calloc_array((size_t)m, sizeof(int32_t));
    if (!out->segments || !out->segment_markers) {
        st = wr_fail(diag, WR_ERR_NOMEM, -1, "out of memory");
        goto fail;
    }
    out->has_segment_markers = nmark;
    for (i = 0; i < m; ++i) {
        int32_t idx, a, b;
        if (!wr__pl_next(&L)) {
            st = wr_fail(diag, WR_ERR_PARSE, -1, "%s:%d: file ends after %d of %d segments", name, L.line, i, m);
            goto fail;
        }
        if (L.ntok < 3 + nmark || !wr__pl_int(&L, 0, &idx) || !wr__pl_int(&L, 1, &a) || !wr__pl_int(&L, 2, &b) ||
            (nmark && !wr__pl_int(&L, 3, &out->segment_markers[i]))) {
            st = wr_fail(diag, WR_ERR_PARSE, -1, "%s:%d: expected '<index> <end> <end>%s' (integers)", name, L.line,
                         nmark ? " <marker>" : "");
            goto fail;
        }
        a -= out->first_index;
        b -= out->first_index;
        if (a < 0 || a >= out->n_points || b < 0 || b >= out->n_points) {
            st = wr_fail(diag, WR_ERR_PARSE, i, "%s:%d: segment %d references vertex %d, outside [%d, %d]", name, L.line,
                         idx, (a < 0 || a >= out->n_points ? a : b) + out->first_index, out->first_index,
                         out->n_points - 1 + out->first_index);
            goto fail;
        }
        out->segments[2 * i] = a;
        out->segments[2 * i + 1] = b;
        out->n_segments = i + 1;
    }
    if (!wr__pl_next(&L)) return WR_OK; /* Triangle tolerates a missing hole section */
    if (!wr__pl_int(&L, 0, &nh) || nh < 0 || nh > INT32_MAX / 8) {
        st = wr_fail(diag, WR_ERR_PARSE, -1, "%s:%d: bad hole count", name, L.line);
        goto fail;
    }
    if (!wr__pl_lines_left(&L, nh)) {
        st = wr_fail(diag, WR_ERR_PARSE, -1, "%s:%d: declares %d holes but fewer lines follow", name, L.line, nh);
        goto fail;
    }
    out->holes = (double *)wr_alloc_array((size_t)nh * 2, sizeof(double));
    if (!out->holes) {
        st = wr_fail(diag, WR_ERR_NOMEM, -1, "out of memory");
        goto fail;
    }
    for (i = 0; i < nh; ++i) {
        int32_t idx;
        if (!wr__pl_next(&L) || L.ntok < 3 || !wr__pl_int(&L, 0, &idx) || !wr__pl_num(&L, 1, &out->holes[2 * i]) ||
            !wr__pl_num(&L, 2, &out->holes[2 * i + 1])) {
            st = wr_fail(diag, WR_ERR_PARSE, -1, "%s:%d: expected '<index> <x> <y>' for hole %d of %d", name, L.line,
                         i + out->first_index, nh);
            goto fail;
        }
        out->n_holes = i + 1;
    }
    if (!wr__pl_next(&L)) return WR_OK; /* the region list is optional */
    st = wr__pl_regions(&L, out, diag);
    if (st != WR_OK) goto fail;
    return WR_OK;
fail:
    wr_cdt_poly_free(out);
    return st;
}

/* core.h's wr_file_read, plus the one check a text format needs: an embedded NUL byte would end
 * the parse early and silently, so it is refused. */
static char *wr__slurp(const char *path, wr_diag *diag, wr_status *st) {
    char *buf = NULL;
    size_t len = 0;
    *st = wr_file_read(path, &buf, &len, diag);
    if (*st != WR_OK) return NULL;
    if (strlen(buf) != len) {
        wr_free(buf);
        *st = wr_fail(diag, WR_ERR_PARSE, -1, "%s: contains a NUL byte (not a text file)", path);
        return NULL;
    }
    return buf;
}

WRDEF wr_status wr_cdt_poly_read(const char *path, wr_cdt_poly *out, wr_diag *diag) {
    size_t ln;
    char *poly = NULL, *node = NULL;
    wr_status st;
    if (!out) return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "out is NULL");
    memset(out, 0, sizeof *out);
    if (!path) return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "path is NULL");
    ln = strlen(path);
    if (ln > 5 && strcmp(path + ln - 5, ".poly") == 0) {
        wr__pl L;
        int32_t nn = -1;
        poly = wr__slurp(path, diag, &st);
        if (!poly) return st;
        memset(&L, 0, sizeof L);
        L.p = poly;
        L.name = path;
        if (wr__pl_next(&L) && wr__pl_int(&L, 0, &nn) && nn == 0) {
            char np[WR_PATH_MAX];
            if (ln >= sizeof np) {
                wr_free(poly);
                return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "path too long");
            }
            memcpy(np, path, ln - 5);
            memcpy(np + ln - 5, ".node", 6);
            node = wr__slurp(np, diag, &st);
            if (!node) {
                wr_free(poly);
                return st;
            }
        }
        st = wr_cdt_poly_parse(poly, node, path, out, diag);
    } else {
        node = wr__slurp(path, diag, &st);
        if (!node) return st;
        st = wr_cdt_poly_parse(NULL, node, path, out, diag);
    }
    wr_free(poly);
    wr_free(node);
    return st;
}

/* ---- a previous mesh: .ele (+ .area) ---- */
WRDEF void wr_cdt_ele_free(wr_cdt_ele *e) {
    if (!e) return;
    wr_free(e->triangles);
    wr_free(e->attributes);
    wr_free(e->areas);
    memset(e, 0, sizeof *e);
}

static wr_status wr__ele_area(const char *text, const char *name, wr_cdt_ele *out, wr_diag *diag) {
    wr__pl L;
    int32_t n, i;
    memset(&L, 0, sizeof L);
    L.p = text;
    L.name = name;
    if (!wr__pl_next(&L) || !wr__pl_int(&L, 0, &n) || n != out->n_triangles)
        return wr_fail(diag, WR_ERR_PARSE, -1, "%s:%d: expected the triangle count %d of the .ele file", name, L.line,
                       out->n_triangles);
    out->areas = (double *)wr_alloc_array((size_t)n, sizeof(double));
    if (n > 0 && !out->areas) return wr_fail(diag, WR_ERR_NOMEM, -1, "out of memory");
    for (i = 0; i < n; ++i) {
        int32_t idx;
        if (!wr__pl_next(&L) || L.ntok < 2 || !wr__pl_int(&L, 0, &idx) || !wr__pl_num(&L, 1, &out->areas[i]))
            return wr_fail(diag, WR_ERR_PARSE, -1, "%s:%d: expected '<triangle> <maximum area>' for triangle %d of %d",
                           name, L.line, i, n);
    }
    return WR_OK;
}

WRDEF wr_status wr_cdt_ele_parse(const char *ele_text, const char *area_text, const char *name,
                                 const char *area_name, int32_t n_points, int first, wr_cdt_ele *out,
                                 wr_diag *diag) {
    wr__pl L;
    int32_t n, nc = 3, na = 0, i, k;
    wr_status st;
    if (!out) return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "out is NULL");
    memset(out, 0, sizeof *out);
    if (!ele_text) return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "no .ele text");
    if (!name) name = "<ele>";
    if (!area_name) area_name = "<area>";
    memset(&L, 0, sizeof L);
    L.p = ele_text;
    L.name = name;
    if (!wr__pl_next(&L) || !wr__pl_int(&L, 0, &n) || n < 0 || n > INT32_MAX / 8 ||
        (L.ntok > 1 && (!wr__pl_int(&L, 1, &nc) || (nc != 3 && nc != 6))) ||
        (L.ntok > 2 && (!wr__pl_int(&L, 2, &na) || na < 0 || na > WR__PL_MAXTOK - 8)))
        return wr_fail(diag, WR_ERR_PARSE, -1, "%s:%d: expected '<#triangles> <#nodes 3|6> <#attributes 0..%d>'",
                       name, L.line, WR__PL_MAXTOK - 8);
    if (!wr__pl_lines_left(&L, n))
        return wr_fail(diag, WR_ERR_PARSE, -1, "%s:%d: declares %d triangles but fewer lines follow", name, L.line, n);
    out->triangles = (int32_t *)wr_alloc_array((size_t)n * 3, sizeof(int32_t));
    if (na > 0) out->attributes = (double *)wr_alloc_array((size_t)n * (size_t)na, sizeof(double));
    if ((n > 0 && !out->triangles) || (n > 0 && na > 0 && !out->attributes)) {
        wr_cdt_ele_free(out);
        return wr_fail(diag, WR_ERR_NOMEM, -1, "out of memory");
    }
    out->n_corners = nc;
    out->n_attributes = na;
    for (i = 0; i < n; ++i) {
        int32_t idx, v;
        if (!wr__pl_next(&L)) {
            st = wr_fail(diag, WR_ERR_PARSE, -1, "%s:%d: file ends after %d of %d triangles", name, L.line, i, n);
            goto fail;
        }
        if (L.ntok < 1 + nc + na || !wr__pl_int(&L, 0, &idx)) {
            st = wr_fail(diag, WR_ERR_PARSE, -1, "%s:%d: expected '<triangle> <%d nodes>%s' for triangle %d of %d",
                         name, L.line, nc, na ? " <attributes>" : "", i + first, n);
            goto fail;
        }
        for (k = 0; k < 3; ++k) {
            if (!wr__pl_int(&L, 1 + k, &v) || v - first < 0 || v - first >= n_points) {
                st = wr_fail(diag, WR_ERR_PARSE, i, "%s:%d: corner %d of triangle %d is not a vertex in [%d, %d]", name,
                             L.line, k + 1, idx, first, n_points - 1 + first);
                goto fail;
            }
            out->triangles[3 * i + k] = v - first;
        }
        for (k = 0; k < na; ++k)
            if (!wr__pl_num(&L, 1 + nc + k, &out->attributes[(size_t)i * na + k])) {
                st = wr_fail(diag, WR_ERR_PARSE, i, "%s:%d: attribute %d of triangle %d is not a finite number", name,
                             L.line, k + 1, idx);
                goto fail;
            }
        out->n_triangles = i + 1;
    }
    if (area_text && (st = wr__ele_area(area_text, area_name, out, diag)) != WR_OK) goto fail;
    return WR_OK;
fail:
    wr_cdt_ele_free(out);
    return st;
}

WRDEF wr_status wr_cdt_ele_read(const char *ele_path, const char *area_path, int32_t n_points, int first,
                                wr_cdt_ele *out, wr_diag *diag) {
    char *ele, *area = NULL;
    wr_status st;
    if (!out) return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "out is NULL");
    memset(out, 0, sizeof *out);
    if (!ele_path) return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "path is NULL");
    ele = wr__slurp(ele_path, diag, &st);
    if (!ele) return st;
    if (area_path && !(area = wr__slurp(area_path, diag, &st))) {
        wr_free(ele);
        return st;
    }
    st = wr_cdt_ele_parse(ele, area, ele_path, area_path, n_points, first, out, diag);
    wr_free(ele);
    wr_free(area);
    return st;
}

/* ---- Triangle's outputs ---- */
WRDEF void wr_cdt_out_free(wr_cdt_out *o) {
    if (!o) return;
    wr_free(o->nodes);
    wr_free(o->node_attributes);
    wr_free(o->node_markers);
    wr_free(o->node_of);
    wr_free(o->elements);
    wr_free(o->element_attributes);
    wr_free(o->neighbors);
    wr_free(o->edges);
    wr_free(o->edge_markers);
    wr_free(o->edge_triangles);
    wr_free(o->segments);
    wr_free(o->segment_markers);
    wr_free(o->voronoi_nodes);
    wr_free(o->voronoi_attributes);
    wr_free(o->voronoi_edges);
    wr_free(o->voronoi_rays);
    memset(o, 0, sizeof *o);
}

static int wr__pl_pair_cmp(const void *x, const void *y) {
    const int32_t *a = (const int32_t *)x, *b = (const int32_t *)y;
    return a[0] != b[0] ? (a[0] < b[0] ? -1 : 1) : a[1] != b[1] ? (a[1] < b[1] ? -1 : 1) : 0;
}

/* Sort n triples (a, b, e) by (a, b), a and b in [0, nv): two stable counting sorts (by b, then by a),
 * O(n + nv) instead of qsort's comparator calls (issue 17: ~60k instructions on the bench's bodice).
 * The pairs are distinct (one key per edge), so the order is the one qsort gives; qsort when out of
 * memory. */
static void wr__pl_sort_pairs(int32_t *q, int32_t n, int32_t nv) {
    int32_t *cnt = (int32_t *)wr_alloc_array((size_t)nv + 1, sizeof(int32_t));
    int32_t *tmp = (int32_t *)wr_alloc_array((size_t)n * 3 + 1, sizeof(int32_t));
    int32_t i, pass;
    if (!cnt || !tmp) {
        qsort(q, (size_t)n, 3 * sizeof(int32_t), wr__pl_pair_cmp);
    } else {
        for (pass = 1; pass >= 0; --pass) { /* pass 1: by b into tmp; pass 0: by a back into q */
            int32_t *src = pass ? q : tmp, *dst = pass ? tmp : q, s = 0;
            memset(cnt, 0, sizeof(int32_t) * ((size_t)nv + 1));
            for (i = 0; i < n; ++i) cnt[src[3 * i + pass]]++;
            for (i = 0; i <= nv; ++i) {
                int32_t c = cnt[i];
                cnt[i] = s;
                s += c;
            }
            for (i = 0; i < n; ++i) {
                int32_t *d = dst + 3 * cnt[src[3 * i + pass]]++;
                d[0] = src[3 * i];
                d[1] = src[3 * i + 1];
                d[2] = src[3 * i + 2];
            }
        }
    }
    wr_free(cnt);
    wr_free(tmp);
}

/* Scratch of wr_cdt_out_build, in result-vertex / half-edge numbering. */
typedef struct wr__ob {
    const wr_cdt_poly *P;
    const wr_cdt_result *r;
    int32_t *canon;  /* result vertex -> its first input vertex (-1: a Steiner point) */
    int32_t *vmark;  /* result vertex -> boundary marker */
    int32_t *bestseg; /* lowest input segment with a nonzero marker through the vertex */
    int32_t *used;   /* result vertex used by a triangle */
    int32_t *hedge;  /* half-edge 3t+k -> edge */
    int32_t *ekey;   /* n_edges × 3: low, high result vertex, edge (sorted; constrained edges only) */
    int32_t n_ekey;
    int32_t *ev;     /* n_edges × 2 result vertices (a -> b counter-clockwise in edge_triangles[0]) */
} wr__ob;

static int32_t wr__seg_marker(const wr_cdt_poly *P, int32_t s) {
    if (s < 0) return 0;
    if (s >= P->n_segments) return 1; /* the boundary of a previous mesh (refinement) */
    return P->has_segment_markers ? P->segment_markers[s] : 0;
}

/* Edges from the triangles (each once, from the triangle with the lower number or the only one),
 * their markers, and the vertex markers (see ON OUTPUT). */
static wr_status wr__ob_edges(wr__ob *B, wr_cdt_out *o, wr_diag *diag) {
    const wr_cdt_result *r = B->r;
    int32_t nt = r->n_triangles, t, k, ne = 0, v;
    for (t = 0; t < 3 * nt; ++t) ne += r->neighbors[t] < 0 || r->neighbors[t] > t / 3;
    o->edge_markers = (int32_t *)wr_alloc_array((size_t)ne + 1, sizeof(int32_t));
    o->edge_triangles = (int32_t *)wr_alloc_array((size_t)ne + 1, 2 * sizeof(int32_t));
    B->ev = (int32_t *)wr_alloc_array((size_t)ne + 1, 2 * sizeof(int32_t));
    B->hedge = (int32_t *)wr_alloc_array(3 * (size_t)nt + 1, sizeof(int32_t));
    B->ekey = (int32_t *)wr_alloc_array((size_t)ne + 1, 3 * sizeof(int32_t));
    if (!o->edge_markers || !o->edge_triangles || !B->ev || !B->hedge || !B->ekey)
        return wr_fail(diag, WR_ERR_NOMEM, -1, "out of memory");
    o->n_edges = 0;
    for (t = 0; t < nt; ++t)
        for (k = 0; k < 3; ++k) {
            int32_t h = 3 * t + k, nb = r->neighbors[h], a = r->triangles[3 * t + (k + 1) % 3],
                    b = r->triangles[3 * t + (k + 2) % 3], es = r->edge_segment[h], e, raw, j;
            if (!(nb < 0 || nb > t)) continue;
            e = o->n_edges++;
            B->ev[2 * e] = a;
            B->ev[2 * e + 1] = b;
            o->edge_triangles[2 * e] = t;
            o->edge_triangles[2 * e + 1] = nb;
            B->hedge[h] = e;
            for (j = 0; nb >= 0 && j < 3; ++j) /* the same edge seen from the neighbour */
                if (r->neighbors[3 * nb + j] == t && r->triangles[3 * nb + (j + 1) % 3] == b) B->hedge[3 * nb + j] = e;
            raw = wr__seg_marker(B->P, es);
            o->edge_markers[e] = es >= 0 && raw != 0 ? raw : nb < 0 ? 1 : 0;
            if (es >= 0) {
                int32_t *q = B->ekey + 3 * B->n_ekey++;
                q[0] = a < b ? a : b;
                q[1] = a < b ? b : a;
                q[2] = e;
                if (raw != 0) {
                    if (es < B->bestseg[a]) B->bestseg[a] = es;
                    if (es < B->bestseg[b]) B->bestseg[b] = es;
                }
            }
        }
    wr__pl_sort_pairs(B->ekey, B->n_ekey, r->n_points);
    for (v = 0; v < r->n_points; ++v)
        if (B->vmark[v] == 0 && B->bestseg[v] < INT32_MAX) B->vmark[v] = wr__seg_marker(B->P, B->bestseg[v]);
    for (k = 0; k < o->n_edges; ++k)
        if (o->edge_triangles[2 * k + 1] < 0) {
            if (B->vmark[B->ev[2 * k]] == 0) B->vmark[B->ev[2 * k]] = 1;
            if (B->vmark[B->ev[2 * k + 1]] == 0) B->vmark[B->ev[2 * k + 1]] = 1;
        }
    return WR_OK;
}

/* The node list: every input vertex under its own number (duplicates too), then the Steiner points,
 * then (second_order) one midpoint per edge; with jettison only the used ones, renumbered. */
static wr_status wr__ob_nodes(wr__ob *B, const wr_cdt_out_desc *d, wr_cdt_out *o, wr_diag *diag) {
    const wr_cdt_result *r = B->r;
    const wr_cdt_poly *P = B->P;
    int32_t nin = r->n_map, nst = r->n_points - r->n_input_points, n0 = nin + nst, na = P->n_attributes, i, k, n = 0;
    int32_t nmid = d->second_order ? o->n_edges : 0;
    if (r->n_attributes != 0 && r->n_attributes != na)
        return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "the result has %d attributes per vertex, the input %d",
                       r->n_attributes, na);
    o->n_node_attributes = na;
    o->nodes = (double *)wr_alloc_array((size_t)n0 + (size_t)nmid + 1, 2 * sizeof(double));
    o->node_markers = (int32_t *)wr_alloc_array((size_t)n0 + (size_t)nmid + 1, sizeof(int32_t));
    o->node_attributes = (double *)wr_alloc_array(((size_t)n0 + (size_t)nmid) * (size_t)na + 1, sizeof(double));
    o->node_of = (int32_t *)wr_alloc_array((size_t)r->n_points + 1, sizeof(int32_t));
    if (!o->nodes || !o->node_markers || !o->node_attributes || !o->node_of)
        return wr_fail(diag, WR_ERR_NOMEM, -1, "out of memory");
    for (i = 0; i < r->n_points; ++i) o->node_of[i] = -1;
    for (i = 0; i < n0; ++i) {
        int32_t v = i < nin ? r->point_map[i] : r->n_input_points + (i - nin), mine = i >= nin || B->canon[v] == i;
        const double *xy = i < nin ? P->points + 2 * i : r->points + 2 * v;
        const double *at = na == 0 ? NULL : i < nin ? P->attributes + (size_t)i * na : r->attributes + (size_t)v * na;
        if (d->jettison && !(mine && B->used[v])) continue;
        o->nodes[2 * n] = xy[0];
        o->nodes[2 * n + 1] = xy[1];
        for (k = 0; k < na; ++k) o->node_attributes[(size_t)n * na + k] = at[k];
        o->node_markers[n] = mine ? B->vmark[v] : P->has_point_markers ? P->point_markers[i] : 0;
        if (mine) o->node_of[v] = n;
        ++n;
    }
    for (i = 0; i < nmid; ++i) {
        const double *a = r->points + 2 * B->ev[2 * i], *b = r->points + 2 * B->ev[2 * i + 1];
        const double *aa = na ? r->attributes + (size_t)B->ev[2 * i] * na : NULL,
                     *ba = na ? r->attributes + (size_t)B->ev[2 * i + 1] * na : NULL;
        o->nodes[2 * n] = 0.5 * (a[0] + b[0]);
        o->nodes[2 * n + 1] = 0.5 * (a[1] + b[1]);
        for (k = 0; k < na; ++k) o->node_attributes[(size_t)n * na + k] = 0.5 * (aa[k] + ba[k]);
        o->node_markers[n] = o->edge_markers[i];
        ++n;
    }
    o->n_nodes = n;
    return WR_OK;
}

/* Triangles (corners, midpoints), their attributes, neighbours, the .poly segments, edges in nodes. */
static wr_status wr__ob_elements(wr__ob *B, const wr_cdt_input *in, const wr_cdt_ele *prev, const wr_cdt_out_desc *d,
                                 wr_cdt_out *o, wr_diag *diag) {
    const wr_cdt_result *r = B->r;
    int32_t nt = r->n_triangles, nc = d->second_order ? 6 : 3, t, k, i, mid0 = o->n_nodes - (d->second_order ? o->n_edges : 0);
    int32_t npa = prev ? prev->n_attributes : 0, nea = npa + (d->region_attribute ? 1 : 0), nreg = in ? in->n_regions : 0;
    o->n_elements = nt;
    o->n_corners = nc;
    o->n_element_attributes = nea;
    o->elements = (int32_t *)wr_alloc_array((size_t)nt * (size_t)nc + 1, sizeof(int32_t));
    o->element_attributes = (double *)wr_alloc_array((size_t)nt * (size_t)nea + 1, sizeof(double));
    o->neighbors = (int32_t *)wr_alloc_array(3 * (size_t)nt + 1, sizeof(int32_t));
    o->edges = (int32_t *)wr_alloc_array((size_t)o->n_edges + 1, 2 * sizeof(int32_t));
    o->segments = (int32_t *)wr_alloc_array((size_t)r->n_segments + (size_t)o->n_edges + 1, 2 * sizeof(int32_t));
    o->segment_markers = (int32_t *)wr_alloc_array((size_t)r->n_segments + (size_t)o->n_edges + 1, sizeof(int32_t));
    if (!o->elements || !o->element_attributes || !o->neighbors || !o->edges || !o->segments || !o->segment_markers)
        return wr_fail(diag, WR_ERR_NOMEM, -1, "out of memory");
    for (t = 0; t < nt; ++t) {
        int32_t tag = r->triangle_region ? r->triangle_region[t] : -1;
        double *ea = o->element_attributes + (size_t)t * nea;
        for (k = 0; k < 3; ++k) {
            o->elements[nc * t + k] = o->node_of[r->triangles[3 * t + k]];
            o->neighbors[3 * t + k] = r->neighbors[3 * t + k];
            if (nc == 6) o->elements[nc * t + 3 + k] = mid0 + B->hedge[3 * t + k];
        }
        for (k = 0; k < npa; ++k)
            ea[k] = tag >= nreg && tag - nreg < prev->n_triangles ? prev->attributes[(size_t)(tag - nreg) * npa + k] : 0.0;
        if (d->region_attribute) ea[npa] = tag >= 0 && tag < nreg ? in->regions[4 * tag + 2] : 0.0;
    }
    for (i = 0; i < o->n_edges; ++i) {
        o->edges[2 * i] = o->node_of[B->ev[2 * i]];
        o->edges[2 * i + 1] = o->node_of[B->ev[2 * i + 1]];
    }
    /* subsegments in the result's order, those that are mesh edges; then (hull_segments) the other
     * boundary edges */
    o->n_segments = 0;
    for (i = 0; i < r->n_segments; ++i) {
        int32_t key[2], a = r->segments[2 * i], b = r->segments[2 * i + 1];
        const int32_t *hit;
        key[0] = a < b ? a : b;
        key[1] = a < b ? b : a;
        hit = (const int32_t *)bsearch(key, B->ekey, (size_t)B->n_ekey, 3 * sizeof(int32_t), wr__pl_pair_cmp);
        if (!hit) continue;
        o->segments[2 * o->n_segments] = o->node_of[a];
        o->segments[2 * o->n_segments + 1] = o->node_of[b];
        o->segment_markers[o->n_segments++] = o->edge_markers[hit[2]];
    }
    for (i = 0; d->hull_segments && i < o->n_edges; ++i)
        if (o->edge_triangles[2 * i + 1] < 0) {
            int32_t t0 = o->edge_triangles[2 * i], h;
            for (h = 3 * t0; h < 3 * t0 + 3 && B->hedge[h] != i; ++h) {}
            if (r->edge_segment[h] >= 0) continue;
            o->segments[2 * o->n_segments] = o->edges[2 * i];
            o->segments[2 * o->n_segments + 1] = o->edges[2 * i + 1];
            o->segment_markers[o->n_segments++] = o->edge_markers[i];
        }
    if (in && in->n_regions > 0) {
        o->n_regions = in->n_regions; /* as the file gave them (the caller may have changed the areas) */
        o->regions = B->P->n_regions == in->n_regions ? B->P->regions : in->regions;
    }
    return WR_OK;
}

/* Voronoi diagram: a vertex per triangle at its circumcentre (attributes: the affine interpolant of
 * the corners' there), an edge per mesh edge between the two triangles' vertices, or a ray across
 * a boundary edge a -> b (counter-clockwise) in direction (b_y - a_y, a_x - b_x), outward. */
static wr_status wr__ob_voronoi(wr__ob *B, wr_cdt_out *o, wr_diag *diag) {
    const wr_cdt_result *r = B->r;
    int32_t nt = r->n_triangles, na = o->n_node_attributes, t, i, k;
    o->voronoi_nodes = (double *)wr_alloc_array((size_t)nt + 1, 2 * sizeof(double));
    o->voronoi_attributes = (double *)wr_alloc_array((size_t)nt * (size_t)na + 1, sizeof(double));
    o->voronoi_edges = (int32_t *)wr_alloc_array((size_t)o->n_edges + 1, 2 * sizeof(int32_t));
    o->voronoi_rays = (double *)wr_alloc_array((size_t)o->n_edges + 1, 2 * sizeof(double));
    if (!o->voronoi_nodes || !o->voronoi_attributes || !o->voronoi_edges || !o->voronoi_rays)
        return wr_fail(diag, WR_ERR_NOMEM, -1, "out of memory");
    for (t = 0; t < nt; ++t) {
        const int32_t *v = r->triangles + 3 * t;
        const double *a = r->points + 2 * v[0], *b = r->points + 2 * v[1], *c = r->points + 2 * v[2];
        double bx = b[0] - a[0], by = b[1] - a[1], cx = c[0] - a[0], cy = c[1] - a[1];
        double D = 2.0 * (bx * cy - by * cx), b2 = bx * bx + by * by, c2 = cx * cx + cy * cy;
        double ux = (cy * b2 - by * c2) / D, uy = (bx * c2 - cx * b2) / D, l1, l2;
        o->voronoi_nodes[2 * t] = a[0] + ux;
        o->voronoi_nodes[2 * t + 1] = a[1] + uy;
        /* barycentric coordinates of the circumcentre (u = l1 (b - a) + l2 (c - a)) */
        l1 = 2.0 * (ux * cy - uy * cx) / D;
        l2 = 2.0 * (bx * uy - by * ux) / D;
        for (k = 0; k < na; ++k) {
            const double *A = r->attributes + (size_t)v[0] * na, *Bv = r->attributes + (size_t)v[1] * na,
                         *C = r->attributes + (size_t)v[2] * na;
            o->voronoi_attributes[(size_t)t * na + k] = A[k] + l1 * (Bv[k] - A[k]) + l2 * (C[k] - A[k]);
        }
    }
    for (i = 0; i < o->n_edges; ++i) {
        const double *a = r->points + 2 * B->ev[2 * i], *b = r->points + 2 * B->ev[2 * i + 1];
        o->voronoi_edges[2 * i] = o->edge_triangles[2 * i];
        o->voronoi_edges[2 * i + 1] = o->edge_triangles[2 * i + 1];
        o->voronoi_rays[2 * i] = o->edge_triangles[2 * i + 1] < 0 ? b[1] - a[1] : 0.0;
        o->voronoi_rays[2 * i + 1] = o->edge_triangles[2 * i + 1] < 0 ? a[0] - b[0] : 0.0;
    }
    return WR_OK;
}

WRDEF wr_status wr_cdt_out_build(const wr_cdt_poly *poly, const wr_cdt_input *input, const wr_cdt_ele *prev,
                                 const wr_cdt_result *r, const wr_cdt_out_desc *desc, wr_cdt_out *out,
                                 wr_diag *diag) {
    wr__ob B;
    wr_cdt_out_desc d0;
    wr_status st;
    int32_t i, t;
    if (!out) return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "out is NULL");
    memset(out, 0, sizeof *out);
    if (!poly || !r) return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "poly or result is NULL");
    if (r->n_map != poly->n_points || r->n_input_points > r->n_points || r->n_points < 0 || r->n_triangles < 0)
        return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "the result (%d input points) is not of this input (%d vertices)",
                       r->n_map, poly->n_points);
    if (!desc) {
        memset(&d0, 0, sizeof d0);
        desc = &d0;
    }
    memset(&B, 0, sizeof B);
    B.P = poly;
    B.r = r;
    B.canon = (int32_t *)wr_alloc_array((size_t)r->n_points + 1, sizeof(int32_t));
    B.vmark = (int32_t *)wr_calloc_array((size_t)r->n_points + 1, sizeof(int32_t));
    B.bestseg = (int32_t *)wr_alloc_array((size_t)r->n_points + 1, sizeof(int32_t));
    B.used = (int32_t *)wr_calloc_array((size_t)r->n_points + 1, sizeof(int32_t));
    if (!B.canon || !B.vmark || !B.bestseg || !B.used) {
        st = wr_fail(diag, WR_ERR_NOMEM, -1, "out of memory");
        goto done;
    }
    for (i = 0; i < r->n_points; ++i) {
        B.canon[i] = -1;
        B.bestseg[i] = INT32_MAX;
    }
    for (i = r->n_map - 1; i >= 0; --i) B.canon[r->point_map[i]] = i;
    for (i = 0; i < r->n_input_points; ++i)
        B.vmark[i] = poly->has_point_markers && B.canon[i] >= 0 ? poly->point_markers[B.canon[i]] : 0;
    for (t = 0; t < 3 * r->n_triangles; ++t) B.used[r->triangles[t]] = 1;
    if ((st = wr__ob_edges(&B, out, diag)) != WR_OK) goto done;
    if ((st = wr__ob_nodes(&B, desc, out, diag)) != WR_OK) goto done;
    if ((st = wr__ob_elements(&B, input, prev, desc, out, diag)) != WR_OK) goto done;
    if (desc->voronoi && (st = wr__ob_voronoi(&B, out, diag)) != WR_OK) goto done;
done:
    wr_free(B.canon);
    wr_free(B.vmark);
    wr_free(B.bestseg);
    wr_free(B.used);
    wr_free(B.hedge);
    wr_free(B.ekey);
    wr_free(B.ev);
    if (st != WR_OK) wr_cdt_out_free(out);
    return st;
}

/* ---- writing ---- */
typedef struct wr__ow {
    wr_afile f;
    char path[WR_PATH_MAX];
    const char *command;
} wr__ow;

static wr_status wr__ow_open(wr__ow *w, const char *base, const char *ext, wr_diag *diag) {
    if (snprintf(w->path, sizeof w->path, "%s.%s", base, ext) >= (int)sizeof w->path)
        return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "output path too long: '%s.%s'", base, ext);
    return wr_afile_open(&w->f, w->path, diag);
}
/* Output lines are built in a buffer written with one fwrite when nearly full (and before a file is
 * closed): integers converted by hand (most of Triangle's files), reals as "%.17g" writes them
 * (wr__fmt_g17; they read back to the same double). */
#define WR__LN_CAP 8192
typedef struct wr__line {
    FILE *fp;
    int n;   /* bytes in b */
    int col; /* numbers on the current line */
    char b[WR__LN_CAP];
} wr__line;
static void wr__ln_flush(wr__line *L) {
    if (L->n > 0) fwrite(L->b, 1, (size_t)L->n, L->fp);
    L->n = 0;
}
static void wr__ln_room(wr__line *L) {
    if (L->n > WR__LN_CAP - 40) wr__ln_flush(L);
    if (L->col++ > 0) L->b[L->n++] = ' ';
}
static void wr__ln_i(wr__line *L, int32_t v) {
    int nd = 1;
    uint32_t u = v < 0 ? 0u - (uint32_t)v : (uint32_t)v;
    wr__ln_room(L);
    if (v < 0) L->b[L->n++] = '-';
    while (nd < 10 && u >= wr__p10u[nd]) ++nd;
    wr__put_digits(L->b + L->n, u, nd);
    L->n += nd;
}
static void wr__ln_r(wr__line *L, double x) {
    wr__ln_room(L);
    L->n += wr__fmt_g17(L->b + L->n, x);
}
static void wr__ln_rs(wr__line *L, const double *x, int32_t n) {
    int32_t k;
    for (k = 0; k < n; ++k) wr__ln_r(L, x[k]);
}
static void wr__ln_end(wr__line *L) {
    L->b[L->n++] = '\n';
    L->col = 0;
}
/* a header line of n integers */
static void wr__ln_head(wr__line *L, int n, int32_t a, int32_t b, int32_t c, int32_t d) {
    const int32_t v[4] = {a, b, c, d};
    int k;
    for (k = 0; k < n; ++k) wr__ln_i(L, v[k]);
    wr__ln_end(L);
}
static wr_status wr__ow_close(wr__ow *w, wr__line *L, wr_diag *diag) {
    wr__ln_flush(L);
    if (w->command) fprintf(w->f.fp, "# Generated by %s\n", w->command);
    return wr_afile_commit(&w->f, diag);
}

WRDEF wr_status wr_cdt_out_write(const wr_cdt_out *o, const wr_cdt_poly *poly, const char *base,
                                 const wr_cdt_out_desc *desc, wr_diag *diag) {
    wr__ow w;
    wr__line *L;
    wr_cdt_out_desc d0;
    wr_status st = WR_OK;
    int32_t i, k, f, mk, na;
    if (!o || !base) return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "out or base is NULL");
    if (!desc) {
        memset(&d0, 0, sizeof d0);
        desc = &d0;
    }
    L = (wr__line *)wr_alloc_array(1, sizeof(wr__line));
    if (!L) return wr_fail(diag, WR_ERR_NOMEM, -1, "out of memory");
    L->n = L->col = 0;
    f = desc->has_first_number ? desc->first_number : poly ? poly->first_index : 0;
    mk = !desc->no_markers;
    na = o->n_node_attributes;
    w.f.fp = NULL; /* not memset: w holds three path buffers (12 KB), each written before it is read */
    w.f.path[0] = w.f.tmp[0] = w.path[0] = 0;
    w.command = desc->command;
    if (!desc->no_node) {
        if ((st = wr__ow_open(&w, base, "node", diag)) != WR_OK) goto fail;
        L->fp = w.f.fp;
        wr__ln_head(L, 4, o->n_nodes, 2, na, mk);
        for (i = 0; i < o->n_nodes; ++i) {
            wr__ln_i(L, i + f);
            wr__ln_rs(L, o->nodes + 2 * i, 2);
            wr__ln_rs(L, o->node_attributes + (size_t)i * na, na);
            if (mk) wr__ln_i(L, o->node_markers[i]);
            wr__ln_end(L);
        }
        if ((st = wr__ow_close(&w, L, diag)) != WR_OK) goto fail;
    }
    if (!desc->no_ele) {
        if ((st = wr__ow_open(&w, base, "ele", diag)) != WR_OK) goto fail;
        L->fp = w.f.fp;
        wr__ln_head(L, 3, o->n_elements, o->n_corners, o->n_element_attributes, 0);
        for (i = 0; i < o->n_elements; ++i) {
            wr__ln_i(L, i + f);
            for (k = 0; k < o->n_corners; ++k) wr__ln_i(L, o->elements[(size_t)i * o->n_corners + k] + f);
            wr__ln_rs(L, o->element_attributes + (size_t)i * o->n_element_attributes, o->n_element_attributes);
            wr__ln_end(L);
        }
        if ((st = wr__ow_close(&w, L, diag)) != WR_OK) goto fail;
    }
    if (desc->poly) {
        if ((st = wr__ow_open(&w, base, "poly", diag)) != WR_OK) goto fail;
        L->fp = w.f.fp;
        wr__ln_head(L, 4, 0, 2, na, mk);
        wr__ln_head(L, 2, o->n_segments, mk, 0, 0);
        for (i = 0; i < o->n_segments; ++i) {
            wr__ln_i(L, i + f);
            wr__ln_i(L, o->segments[2 * i] + f);
            wr__ln_i(L, o->segments[2 * i + 1] + f);
            if (mk) wr__ln_i(L, o->segment_markers[i]);
            wr__ln_end(L);
        }
        wr__ln_head(L, 1, poly ? poly->n_holes : 0, 0, 0, 0);
        for (i = 0; poly && i < poly->n_holes; ++i) {
            wr__ln_i(L, i + f);
            wr__ln_rs(L, poly->holes + 2 * i, 2);
            wr__ln_end(L);
        }
        if (o->n_regions > 0) {
            wr__ln_head(L, 1, o->n_regions, 0, 0, 0);
            for (i = 0; i < o->n_regions; ++i) {
                wr__ln_i(L, i + f);
                wr__ln_rs(L, o->regions + 4 * i, 4);
                wr__ln_end(L);
            }
        }
        if ((st = wr__ow_close(&w, L, diag)) != WR_OK) goto fail;
    }
    if (desc->edges) {
        if ((st = wr__ow_open(&w, base, "edge", diag)) != WR_OK) goto fail;
        L->fp = w.f.fp;
        wr__ln_head(L, 2, o->n_edges, mk, 0, 0);
        for (i = 0; i < o->n_edges; ++i) {
            wr__ln_i(L, i + f);
            wr__ln_i(L, o->edges[2 * i] + f);
            wr__ln_i(L, o->edges[2 * i + 1] + f);
            if (mk) wr__ln_i(L, o->edge_markers[i]);
            wr__ln_end(L);
        }
        if ((st = wr__ow_close(&w, L, diag)) != WR_OK) goto fail;
    }
    if (desc->neighbors) {
        if ((st = wr__ow_open(&w, base, "neigh", diag)) != WR_OK) goto fail;
        L->fp = w.f.fp;
        wr__ln_head(L, 2, o->n_elements, 3, 0, 0);
        for (i = 0; i < o->n_elements; ++i) {
            wr__ln_i(L, i + f);
            for (k = 0; k < 3; ++k) wr__ln_i(L, o->neighbors[3 * i + k] < 0 ? -1 : o->neighbors[3 * i + k] + f);
            wr__ln_end(L);
        }
        if ((st = wr__ow_close(&w, L, diag)) != WR_OK) goto fail;
    }
    if (desc->voronoi && o->voronoi_nodes) {
        if ((st = wr__ow_open(&w, base, "v.node", diag)) != WR_OK) goto fail;
        L->fp = w.f.fp;
        wr__ln_head(L, 4, o->n_elements, 2, na, 0);
        for (i = 0; i < o->n_elements; ++i) {
            wr__ln_i(L, i + f);
            wr__ln_rs(L, o->voronoi_nodes + 2 * i, 2);
            wr__ln_rs(L, o->voronoi_attributes + (size_t)i * na, na);
            wr__ln_end(L);
        }
        if ((st = wr__ow_close(&w, L, diag)) != WR_OK) goto fail;
        if ((st = wr__ow_open(&w, base, "v.edge", diag)) != WR_OK) goto fail;
        L->fp = w.f.fp;
        wr__ln_head(L, 2, o->n_edges, 0, 0, 0);
        for (i = 0; i < o->n_edges; ++i) {
            wr__ln_i(L, i + f);
            wr__ln_i(L, o->voronoi_edges[2 * i] + f);
            if (o->voronoi_edges[2 * i + 1] >= 0) {
                wr__ln_i(L, o->voronoi_edges[2 * i + 1] + f);
            } else {
                wr__ln_i(L, -1);
                wr__ln_rs(L, o->voronoi_rays + 2 * i, 2);
            }
            wr__ln_end(L);
        }
        if ((st = wr__ow_close(&w, L, diag)) != WR_OK) goto fail;
    }
    wr_free(L);
    return WR_OK;
fail:
    wr_afile_abort(&w.f);
    wr_free(L);
    return st;
}

#ifdef __cplusplus
}
#endif
#endif /* WRINKLE_POLYFILE_IMPLEMENTATION_DONE */
#endif /* WRINKLE_IMPLEMENTATION */
