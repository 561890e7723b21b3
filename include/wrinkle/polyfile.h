/* wrinkle/polyfile.h — Shewchuk Triangle's .node / .poly files (the input of wrinkle-triangulate and
 * of scripts written for Triangle), read into arrays for wr_cdt_triangulate (triangulate.h).
 * wrinkle v0.1.0 — MIT licence (see LICENSE). Needs only libc and libm.
 *
 * Formats (Triangle's documentation): .node "<#vertices> <dim 2> <#attributes> <#markers 0|1>" then
 * one line "<i> <x> <y> [attributes] [marker]" per vertex; .poly: a node section (or "0 2 0 1" and a
 * sibling .node), "<#segments> <#markers>" and "<j> <a> <b> [marker]", "<#holes>" and "<k> <x> <y>".
 * Numbering from 0 or 1 (the first vertex decides); '#' starts a comment. Errors name "file:line".
 *
 * API
 *   wr_cdt_poly_parse(poly_text, node_text, name, out, diag)   from memory
 *   wr_cdt_poly_read(path, out, diag)                          from name.poly (+ name.node) or name.node
 *   wr_cdt_poly_free(p)
 *
 * EXAMPLE
 *     wr_cdt_poly P; wr_diag dg;
 *     const char *poly = "4 2 0 0\n1 0 0\n2 1 0\n3 1 1\n4 0 1\n4 0\n1 1 2\n2 2 3\n3 3 4\n4 4 1\n0\n";
 *     if (wr_cdt_poly_parse(poly, NULL, "square.poly", &P, &dg) != WR_OK) { puts(dg.message); return 1; }
 *     printf("%d vertices, %d segments\n", P.n_points, P.n_segments);   // 4, 4 (0-based in P)
 *     wr_cdt_poly_free(&P);
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
    int32_t *point_markers;   /* n_points boundary markers (0 when the file has none) */
    int32_t *segments;        /* n_segments × 2, converted to 0-based */
    int32_t n_segments;
    int32_t *segment_markers; /* n_segments (0 when the file has none) */
    double *holes;            /* n_holes × 2 */
    int32_t n_holes;
    int first_index;          /* 0 or 1: numbering the file used (from its first vertex) */
    int has_point_markers, has_segment_markers;
} wr_cdt_poly;

/* poly_text: contents of a .poly file (NULL: read only node_text as a .node file). node_text: the
 * .node file, needed when the .poly node section is empty ("0 2 0 1"), else may be NULL. name:
 * file name used in messages "name:line: reason". Attributes are read and ignored. */
WRDEF wr_status wr_cdt_poly_parse(const char *poly_text, const char *node_text, const char *name,
                                  wr_cdt_poly *out, wr_diag *diag);
/* path ending in .poly (reads the sibling .node if needed) or .node. */
WRDEF wr_status wr_cdt_poly_read(const char *path, wr_cdt_poly *out, wr_diag *diag);
WRDEF void wr_cdt_poly_free(wr_cdt_poly *p);

#ifdef __cplusplus
}
#endif
#endif /* WRINKLE_POLYFILE_H */

#ifdef WRINKLE_IMPLEMENTATION
#ifndef WRINKLE_POLYFILE_IMPLEMENTATION_DONE
#define WRINKLE_POLYFILE_IMPLEMENTATION_DONE

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#ifdef __cplusplus
extern "C" {
#endif

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
    int32_t n, dim, nattr = 0, nmark = 0, i;
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
    if (!out->points || !out->point_markers) return wr_fail(diag, WR_ERR_NOMEM, -1, "out of memory");
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
        if (nmark && !wr__pl_int(L, 3 + nattr, &out->point_markers[i]))
            return wr_fail(diag, WR_ERR_PARSE, -1, "%s:%d: bad boundary marker", L->name, L->line);
        out->n_points = i + 1;
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
    return WR_OK; /* a regional-attribute section may follow; it is ignored */
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

#ifdef __cplusplus
}
#endif
#endif /* WRINKLE_POLYFILE_IMPLEMENTATION_DONE */
#endif /* WRINKLE_IMPLEMENTATION */
