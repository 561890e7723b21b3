/* pattern.c — see pattern.h and docs/pattern-format.md. Uses cJSON (Debian libcjson-dev). */
#include "pattern.h"
#include "wrinkle/garment.h"

#include <cjson/cJSON.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#define MM 1e-3 /* file millimetres → metres */

/* ---- arena ---------------------------------------------------------------------------------- */
static void *pf_alloc(wr_pattern_file *f, size_t count, size_t size) {
    void *p;
    if (f->n_allocs_ == f->cap_allocs_) {
        int nc = f->cap_allocs_ ? 2 * f->cap_allocs_ : 32;
        void **na = (void **)realloc(f->allocs_, (size_t)nc * sizeof(void *));
        if (!na) return NULL;
        f->allocs_ = na;
        f->cap_allocs_ = nc;
    }
    p = wr_calloc_array(count ? count : 1, size);
    if (p) f->allocs_[f->n_allocs_++] = p;
    return p;
}

void wr_pattern_file_free(wr_pattern_file *f) {
    int i;
    if (!f) return;
    for (i = 0; i < f->n_allocs_; ++i) wr_free(f->allocs_[i]);
    free(f->allocs_);
    memset(f, 0, sizeof *f);
}

/* ---- parse context ---------------------------------------------------------------------------- */
typedef struct pctx {
    wr_pattern_file *f;
    wr_diag *diag;
    const char *file; /* name used in messages */
    cJSON *fabrics;   /* top-level "fabrics" object or NULL */
} pctx;

static wr_status perr(pctx *c, wr_status s, const char *path, const char *fmt, ...)
#if defined(__GNUC__) || defined(__clang__)
    __attribute__((format(printf, 4, 5)))
#endif
    ;
static wr_status perr(pctx *c, wr_status s, const char *path, const char *fmt, ...) {
    char msg[WR_DIAG_MESSAGE_LEN];
    va_list ap;
    wr_status st;
    va_start(ap, fmt);
    vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    st = wr_fail(c->diag, s, -1, "%s: %s: %s", c->file, path, msg);
    /* names and keys are user text: keep the message one line */
    if (c->diag) {
        char *q;
        for (q = c->diag->message; *q; ++q)
            if (*q == '\n' || *q == '\r') *q = ' ';
    }
    return st;
}

/* Path builders (JSON paths are short; a longer one is cut, never overflowed). */
static void cat2(char *out, size_t n, const char *a, const char *b) {
    size_t la = strlen(a), lb = strlen(b);
    if (la > n - 1) la = n - 1;
    memmove(out, a, la);
    if (lb > n - 1 - la) lb = n - 1 - la;
    memcpy(out + la, b, lb);
    out[la + lb] = 0;
}
static void join(char *out, size_t n, const char *path, const char *key) {
    char k[160];
    k[0] = '.';
    cat2(k + 1, sizeof k - 1, key, "");
    cat2(out, n, path, k);
}
static void joini(char *out, size_t n, const char *path, int i) {
    char k[24];
    snprintf(k, sizeof k, "[%d]", i);
    cat2(out, n, path, k);
}

/* Strict keys: every member of obj must be in allowed (NULL-terminated); "comment" is always allowed. */
static wr_status check_keys(pctx *c, const cJSON *obj, const char *path, const char *const *allowed) {
    const cJSON *it;
    cJSON_ArrayForEach(it, obj) {
        int k, ok = 0;
        const cJSON *o2;
        if (!it->string) return perr(c, WR_ERR_PARSE, path, "member without a name");
        if (!strcmp(it->string, "comment")) ok = 1;
        for (k = 0; allowed[k] && !ok; ++k) ok = !strcmp(it->string, allowed[k]);
        if (!ok) return perr(c, WR_ERR_PARSE, path, "unknown key \"%s\"", it->string);
        /* duplicate keys would silently shadow each other in cJSON lookups */
        for (o2 = it->next; o2; o2 = o2->next)
            if (o2->string && !strcmp(o2->string, it->string))
                return perr(c, WR_ERR_PARSE, path, "duplicate key \"%s\"", it->string);
    }
    return WR_OK;
}

static wr_status need_object(pctx *c, const cJSON *v, const char *path) {
    if (!cJSON_IsObject(v)) return perr(c, WR_ERR_PARSE, path, "expected an object");
    return WR_OK;
}

/* Optional number: *present = 0 when missing. Must be finite. */
static wr_status get_num(pctx *c, const cJSON *obj, const char *path, const char *key, int required, double *out,
                         int *present) {
    const cJSON *v = cJSON_GetObjectItemCaseSensitive(obj, key);
    char p[512];
    join(p, sizeof p, path, key);
    if (present) *present = v != NULL;
    if (!v) {
        if (required) return perr(c, WR_ERR_PARSE, p, "missing");
        return WR_OK;
    }
    if (!cJSON_IsNumber(v)) return perr(c, WR_ERR_PARSE, p, "expected a number");
    if (!isfinite(v->valuedouble)) return perr(c, WR_ERR_PARSE, p, "number is not finite");
    *out = v->valuedouble;
    return WR_OK;
}

/* Number with range check: lo/hi inclusive unless the *_open flags say otherwise. */
static wr_status get_range(pctx *c, const cJSON *obj, const char *path, const char *key, int required, double lo,
                           int lo_open, double hi, int hi_open, double *out, int *present) {
    double x = 0.0;
    int pr = 0;
    wr_status st = get_num(c, obj, path, key, required, &x, &pr);
    char p[512];
    if (st != WR_OK) return st;
    if (present) *present = pr;
    if (!pr) return WR_OK;
    join(p, sizeof p, path, key);
    if ((lo_open ? !(x > lo) : !(x >= lo)) || (hi_open ? !(x < hi) : !(x <= hi)))
        return perr(c, WR_ERR_PARSE, p, "%g outside %c%g, %g%c", x, lo_open ? '(' : '[', lo, hi, hi_open ? ')' : ']');
    *out = x;
    return WR_OK;
}

static wr_status get_bool(pctx *c, const cJSON *obj, const char *path, const char *key, int *out) {
    const cJSON *v = cJSON_GetObjectItemCaseSensitive(obj, key);
    char p[512];
    if (!v) return WR_OK;
    join(p, sizeof p, path, key);
    if (!cJSON_IsBool(v)) return perr(c, WR_ERR_PARSE, p, "expected true or false");
    *out = cJSON_IsTrue(v) ? 1 : 0;
    return WR_OK;
}

/* One point [x, y] in mm → metres. */
static wr_status get_point(pctx *c, const cJSON *v, const char *path, double *xy) {
    const cJSON *a, *b;
    if (!cJSON_IsArray(v) || cJSON_GetArraySize(v) != 2) return perr(c, WR_ERR_PARSE, path, "expected [x, y]");
    a = cJSON_GetArrayItem(v, 0);
    b = cJSON_GetArrayItem(v, 1);
    if (!cJSON_IsNumber(a) || !cJSON_IsNumber(b)) return perr(c, WR_ERR_PARSE, path, "expected two numbers");
    if (!isfinite(a->valuedouble) || !isfinite(b->valuedouble))
        return perr(c, WR_ERR_PARSE, path, "coordinate is not finite");
    xy[0] = a->valuedouble * MM;
    xy[1] = b->valuedouble * MM;
    return WR_OK;
}

/* Array of points with at least min_n entries. */
static wr_status get_points(pctx *c, const cJSON *v, const char *path, int min_n, double **xy, int32_t *n) {
    int i, cnt;
    const cJSON *it;
    char p[512];
    if (!v) return perr(c, WR_ERR_PARSE, path, "missing");
    if (!cJSON_IsArray(v)) return perr(c, WR_ERR_PARSE, path, "expected an array of [x, y] points");
    cnt = cJSON_GetArraySize(v);
    if (cnt < min_n) return perr(c, WR_ERR_PARSE, path, "fewer than %d points", min_n);
    *xy = (double *)pf_alloc(c->f, (size_t)(2 * cnt), sizeof(double));
    if (!*xy) return perr(c, WR_ERR_NOMEM, path, "out of memory");
    i = 0;
    cJSON_ArrayForEach(it, v) {
        wr_status st;
        joini(p, sizeof p, path, i);
        if ((st = get_point(c, it, p, *xy + 2 * i)) != WR_OK) return st;
        ++i;
    }
    *n = cnt;
    return WR_OK;
}

/* Panel reference: name (string) or index (integer). */
static wr_status get_panel_ref(pctx *c, const cJSON *obj, const char *path, int32_t *out) {
    const cJSON *v = cJSON_GetObjectItemCaseSensitive(obj, "panel");
    char p[512];
    int32_t i;
    join(p, sizeof p, path, "panel");
    if (!v) return perr(c, WR_ERR_PARSE, p, "missing");
    if (cJSON_IsString(v)) {
        for (i = 0; i < c->f->pattern.n_panels; ++i)
            if (!strcmp(c->f->panel_names[i], v->valuestring)) {
                *out = i;
                return WR_OK;
            }
        return perr(c, WR_ERR_PARSE, p, "no panel named \"%s\"", v->valuestring);
    }
    if (cJSON_IsNumber(v)) {
        double d = v->valuedouble;
        if (d != floor(d) || d < 0 || d >= c->f->pattern.n_panels)
            return perr(c, WR_ERR_PARSE, p, "panel index %g does not exist (%d panels)", d, (int)c->f->pattern.n_panels);
        *out = (int32_t)d;
        return WR_OK;
    }
    return perr(c, WR_ERR_PARSE, p, "expected a panel name or index");
}

static wr_status parse_fabric(pctx *c, const cJSON *v, const char *path, wr_pattern_fabric *fb) {
    static const char *const keys[] = {"name", "B", "E", "warp", "weft", "grain_angle_deg", "resolution",
                                       "resolution_warp", "resolution_weft", NULL};
    static const char *const dkeys[] = {"B", "E", NULL};
    wr_status st;
    int has_warp, has_weft, pr;
    const cJSON *w, *f;
    double g = 0.0, r;
    char p[512];
    memset(fb, 0, sizeof *fb);
    if (cJSON_IsString(v)) {
        const cJSON *named = c->fabrics ? cJSON_GetObjectItemCaseSensitive(c->fabrics, v->valuestring) : NULL;
        if (!named) return perr(c, WR_ERR_PARSE, path, "no fabric named \"%s\" in \"fabrics\"", v->valuestring);
        snprintf(p, sizeof p, "fabrics.%s", v->valuestring);
        if (!cJSON_IsObject(named)) return perr(c, WR_ERR_PARSE, p, "a named fabric must be an object");
        return parse_fabric(c, named, p, fb);
    }
    if ((st = need_object(c, v, path)) != WR_OK) return st;
    if ((st = check_keys(c, v, path, keys)) != WR_OK) return st;
    w = cJSON_GetObjectItemCaseSensitive(v, "warp");
    f = cJSON_GetObjectItemCaseSensitive(v, "weft");
    has_warp = w != NULL;
    has_weft = f != NULL;
    if (has_warp != has_weft) return perr(c, WR_ERR_PARSE, path, "give both \"warp\" and \"weft\" or neither");
    if (has_warp) {
        fb->anisotropic = 1;
        if (cJSON_GetObjectItemCaseSensitive(v, "B") || cJSON_GetObjectItemCaseSensitive(v, "E") ||
            cJSON_GetObjectItemCaseSensitive(v, "resolution"))
            return perr(c, WR_ERR_PARSE, path, "an anisotropic fabric takes B/E inside \"warp\" and \"weft\"");
        join(p, sizeof p, path, "warp");
        if ((st = need_object(c, w, p)) != WR_OK || (st = check_keys(c, w, p, dkeys)) != WR_OK) return st;
        if ((st = get_range(c, w, p, "B", 1, 0.0, 1, HUGE_VAL, 1, &fb->B_warp, NULL)) != WR_OK) return st;
        if ((st = get_range(c, w, p, "E", 1, 0.0, 1, HUGE_VAL, 1, &fb->E_warp, NULL)) != WR_OK) return st;
        join(p, sizeof p, path, "weft");
        if ((st = need_object(c, f, p)) != WR_OK || (st = check_keys(c, f, p, dkeys)) != WR_OK) return st;
        if ((st = get_range(c, f, p, "B", 1, 0.0, 1, HUGE_VAL, 1, &fb->B_weft, NULL)) != WR_OK) return st;
        if ((st = get_range(c, f, p, "E", 1, 0.0, 1, HUGE_VAL, 1, &fb->E_weft, NULL)) != WR_OK) return st;
        if ((st = get_num(c, v, path, "grain_angle_deg", 0, &g, NULL)) != WR_OK) return st;
        fb->grain_angle = g * 0.017453292519943295;
        if ((st = get_range(c, v, path, "resolution_warp", 0, 0.0, 1, HUGE_VAL, 1, &r, &pr)) != WR_OK) return st;
        if (pr) fb->resolution_warp = r * MM;
        if ((st = get_range(c, v, path, "resolution_weft", 0, 0.0, 1, HUGE_VAL, 1, &r, &pr)) != WR_OK) return st;
        if (pr) fb->resolution_weft = r * MM;
        if ((fb->resolution_warp > 0.0) != (fb->resolution_weft > 0.0))
            return perr(c, WR_ERR_PARSE, path, "give both resolution_warp and resolution_weft or neither");
        return WR_OK;
    }
    if (cJSON_GetObjectItemCaseSensitive(v, "resolution_warp") || cJSON_GetObjectItemCaseSensitive(v, "resolution_weft") ||
        cJSON_GetObjectItemCaseSensitive(v, "grain_angle_deg"))
        return perr(c, WR_ERR_PARSE, path, "resolution_warp/_weft and grain_angle_deg need \"warp\" and \"weft\"");
    if ((st = get_range(c, v, path, "resolution", 0, 0.0, 1, HUGE_VAL, 1, &r, &pr)) != WR_OK) return st;
    if (pr) fb->resolution = r * MM;
    if ((st = get_range(c, v, path, "B", !pr, 0.0, 1, HUGE_VAL, 1, &fb->B, NULL)) != WR_OK) return st;
    if ((st = get_range(c, v, path, "E", !pr, 0.0, 1, HUGE_VAL, 1, &fb->E, NULL)) != WR_OK) return st;
    if ((fb->B > 0.0) != (fb->E > 0.0)) return perr(c, WR_ERR_PARSE, path, "give both B and E or neither");
    return WR_OK;
}

/* Optional array member; *arr = NULL when missing. */
static wr_status get_array(pctx *c, const cJSON *obj, const char *path, const char *key, const cJSON **arr) {
    const cJSON *v = cJSON_GetObjectItemCaseSensitive(obj, key);
    char p[512];
    *arr = NULL;
    if (!v) return WR_OK;
    join(p, sizeof p, path, key);
    if (!cJSON_IsArray(v)) return perr(c, WR_ERR_PARSE, p, "expected an array");
    *arr = v;
    return WR_OK;
}

static wr_status parse_panels(pctx *c, const cJSON *root) {
    static const char *const keys[] = {"name", "outer", "holes", "fabric", NULL};
    const cJSON *arr = cJSON_GetObjectItemCaseSensitive(root, "panels"), *it;
    wr_pattern_panel *pn;
    int i = 0, n, j;
    wr_status st;
    if (!arr) return perr(c, WR_ERR_PARSE, "panels", "missing");
    if (!cJSON_IsArray(arr) || (n = cJSON_GetArraySize(arr)) < 1)
        return perr(c, WR_ERR_PARSE, "panels", "expected a non-empty array");
    pn = (wr_pattern_panel *)pf_alloc(c->f, (size_t)n, sizeof *pn);
    c->f->panel_names = (char **)pf_alloc(c->f, (size_t)n, sizeof(char *));
    if (!pn || !c->f->panel_names) return perr(c, WR_ERR_NOMEM, "panels", "out of memory");
    c->f->pattern.panels = pn;
    c->f->pattern.n_panels = n;
    cJSON_ArrayForEach(it, arr) {
        char p[512], q[512], r[512];
        const cJSON *nm, *holes, *h;
        joini(p, sizeof p, "panels", i);
        if ((st = need_object(c, it, p)) != WR_OK || (st = check_keys(c, it, p, keys)) != WR_OK) return st;
        nm = cJSON_GetObjectItemCaseSensitive(it, "name");
        if (nm && !cJSON_IsString(nm)) {
            join(q, sizeof q, p, "name");
            return perr(c, WR_ERR_PARSE, q, "expected a string");
        }
        c->f->panel_names[i] = (char *)pf_alloc(c->f, nm ? strlen(nm->valuestring) + 1 : 1, 1);
        if (!c->f->panel_names[i]) return perr(c, WR_ERR_NOMEM, p, "out of memory");
        if (nm) {
            if (!nm->valuestring[0]) {
                join(q, sizeof q, p, "name");
                return perr(c, WR_ERR_PARSE, q, "empty name");
            }
            for (j = 0; j < i; ++j)
                if (!strcmp(c->f->panel_names[j], nm->valuestring)) {
                    join(q, sizeof q, p, "name");
                    return perr(c, WR_ERR_PARSE, q, "duplicate panel name \"%s\"", nm->valuestring);
                }
            strcpy(c->f->panel_names[i], nm->valuestring);
        }
        pn[i].name = c->f->panel_names[i];
        join(q, sizeof q, p, "outer");
        if ((st = get_points(c, cJSON_GetObjectItemCaseSensitive(it, "outer"), q, 3, (double **)&pn[i].outer.xy,
                             &pn[i].outer.n)) != WR_OK)
            return st;
        if ((st = get_array(c, it, p, "holes", &holes)) != WR_OK) return st;
        if (holes) {
            int nh = cJSON_GetArraySize(holes), k = 0;
            wr_pattern_curve *hc = (wr_pattern_curve *)pf_alloc(c->f, (size_t)nh, sizeof *hc);
            if (!hc) return perr(c, WR_ERR_NOMEM, p, "out of memory");
            join(q, sizeof q, p, "holes");
            cJSON_ArrayForEach(h, holes) {
                joini(r, sizeof r, q, k);
                if ((st = get_points(c, h, r, 3, (double **)&hc[k].xy, &hc[k].n)) != WR_OK) return st;
                ++k;
            }
            pn[i].holes = hc;
            pn[i].n_holes = nh;
        }
        join(q, sizeof q, p, "fabric");
        if (!cJSON_GetObjectItemCaseSensitive(it, "fabric")) return perr(c, WR_ERR_PARSE, q, "missing");
        if ((st = parse_fabric(c, cJSON_GetObjectItemCaseSensitive(it, "fabric"), q, &pn[i].fabric)) != WR_OK) return st;
        ++i;
    }
    return WR_OK;
}

/* transition_length (mm, optional, > 0) */
static wr_status get_tl(pctx *c, const cJSON *o, const char *p, double *out) {
    double x = 0.0;
    int pr = 0;
    wr_status st = get_range(c, o, p, "transition_length", 0, 0.0, 1, HUGE_VAL, 1, &x, &pr);
    if (st == WR_OK && pr) *out = x * MM;
    return st;
}

/* stitch_length (mm, optional, >= 0; 0 or absent: the garment's mesh-edge stitches): in metres into
 * *out, and each polyline lines[0..n_lines) split at its stitches (garment.h wr_garment_line_split),
 * so the mesher keeps a vertex at every stitch (garment.h ON GATHERING). */
static wr_status get_stitch(pctx *c, const cJSON *o, const char *p, double *out, wr_pattern_curve *lines, int32_t n_lines) {
    double x = 0.0;
    int pr = 0;
    int32_t k;
    char q[512];
    wr_status st = get_range(c, o, p, "stitch_length", 0, 0.0, 0, HUGE_VAL, 1, &x, &pr);
    if (st != WR_OK || !pr || x == 0.0) return st;
    *out = x * MM;
    join(q, sizeof q, p, "stitch_length");
    for (k = 0; k < n_lines; ++k) {
        double *xy = NULL, *kept;
        int32_t n = 0;
        wr_diag d;
        if (wr_garment_line_split(lines[k].xy, lines[k].n, *out, &xy, &n, &d) != WR_OK) return perr(c, WR_ERR_PARSE, q, "%s", d.message);
        kept = (double *)pf_alloc(c->f, (size_t)n, 2 * sizeof(double));
        if (kept) memcpy(kept, xy, sizeof(double) * 2 * (size_t)n);
        wr_free(xy);
        if (!kept) return perr(c, WR_ERR_NOMEM, q, "out of memory");
        lines[k].xy = kept;
        lines[k].n = n;
    }
    return WR_OK;
}

/* One technique entry of a list: the object at path p, already checked against its keys. */
typedef wr_status (*tech_item_fn)(pctx *c, const cJSON *it, const char *p, void *item);

/* The optional top-level list "kind": each entry an object with only the given keys, parsed by fn into
 * an array of items of `size` bytes (*items stays NULL when the key is absent). */
static wr_status parse_list(pctx *c, const cJSON *root, const char *kind, const char *const *keys, size_t size,
                            tech_item_fn fn, void **items, int32_t *n_items) {
    const cJSON *arr, *it;
    unsigned char *a;
    wr_status st;
    char p[512];
    int i = 0, n;
    if ((st = get_array(c, root, "$", kind, &arr)) != WR_OK || !arr) return st;
    n = cJSON_GetArraySize(arr);
    a = (unsigned char *)pf_alloc(c->f, (size_t)n, size);
    if (!a) return perr(c, WR_ERR_NOMEM, kind, "out of memory");
    cJSON_ArrayForEach(it, arr) {
        joini(p, sizeof p, kind, i);
        if ((st = need_object(c, it, p)) != WR_OK || (st = check_keys(c, it, p, keys)) != WR_OK) return st;
        if ((st = fn(c, it, p, a + (size_t)i * size)) != WR_OK) return st;
        ++i;
    }
    *items = a;
    *n_items = n;
    return WR_OK;
}

/* The polyline under key `key` of it (at least min_points points). */
static wr_status get_line(pctx *c, const cJSON *it, const char *p, const char *key, int min_points, const double **xy,
                          int32_t *n) {
    char q[512];
    join(q, sizeof q, p, key);
    return get_points(c, cJSON_GetObjectItemCaseSensitive(it, key), q, min_points, (double **)xy, n);
}

static wr_status shirring_item(pctx *c, const cJSON *it, const char *p, void *item) {
    wr_pattern_shirring *a = (wr_pattern_shirring *)item;
    wr_status st;
    if ((st = get_panel_ref(c, it, p, &a->panel)) != WR_OK || (st = get_line(c, it, p, "line", 2, &a->xy, &a->n)) != WR_OK)
        return st;
    if ((st = get_range(c, it, p, "E_sh", 0, 0.0, 0, HUGE_VAL, 1, &a->E_sh, NULL)) != WR_OK) return st;
    if ((st = get_range(c, it, p, "rho", 1, 0.0, 1, 1.0, 0, &a->rho, NULL)) != WR_OK) return st;
    if ((st = get_range(c, it, p, "n", 0, 0.0, 1, HUGE_VAL, 1, &a->n_exp, NULL)) != WR_OK) return st;
    {
        wr_pattern_curve ln;
        ln.xy = a->xy, ln.n = a->n;
        if ((st = get_stitch(c, it, p, &a->stitch_length, &ln, 1)) != WR_OK) return st;
        a->xy = ln.xy, a->n = ln.n;
    }
    return get_tl(c, it, p, &a->transition_length);
}

static wr_status fold_item(pctx *c, const cJSON *it, const char *p, void *item) {
    wr_pattern_fold *a = (wr_pattern_fold *)item;
    wr_status st;
    double x;
    int pr;
    if ((st = get_panel_ref(c, it, p, &a->panel)) != WR_OK || (st = get_line(c, it, p, "line", 2, &a->xy, &a->n)) != WR_OK)
        return st;
    if ((st = get_range(c, it, p, "angle_deg", 0, 0.0, 1, 360.0, 0, &a->angle_deg, NULL)) != WR_OK) return st;
    if ((st = get_range(c, it, p, "offset", 0, 0.0, 1, HUGE_VAL, 1, &x, &pr)) != WR_OK) return st;
    if (pr) a->offset = x * MM;
    if ((st = get_range(c, it, p, "curvature_radius", 0, 0.0, 1, HUGE_VAL, 1, &x, &pr)) != WR_OK) return st;
    if (pr) a->curvature_radius = x * MM;
    return get_tl(c, it, p, &a->transition_length);
}

/* One side of a seam: a panel and the boundary stretch from -> to (optionally reversed). */
static wr_status seam_side(pctx *c, const cJSON *it, const char *p, int s, wr_pattern_seam_side *ss) {
    static const char *const skeys[] = {"panel", "from", "to", "reverse", NULL};
    const cJSON *sd = cJSON_GetObjectItemCaseSensitive(it, s ? "b" : "a");
    char q[512], r[512];
    wr_status st;
    join(q, sizeof q, p, s ? "b" : "a");
    if (!sd) return perr(c, WR_ERR_PARSE, q, "missing");
    if ((st = need_object(c, sd, q)) != WR_OK || (st = check_keys(c, sd, q, skeys)) != WR_OK) return st;
    if ((st = get_panel_ref(c, sd, q, &ss->panel)) != WR_OK) return st;
    join(r, sizeof r, q, "from");
    if (!cJSON_GetObjectItemCaseSensitive(sd, "from")) return perr(c, WR_ERR_PARSE, r, "missing");
    if ((st = get_point(c, cJSON_GetObjectItemCaseSensitive(sd, "from"), r, ss->from)) != WR_OK) return st;
    join(r, sizeof r, q, "to");
    if (!cJSON_GetObjectItemCaseSensitive(sd, "to")) return perr(c, WR_ERR_PARSE, r, "missing");
    if ((st = get_point(c, cJSON_GetObjectItemCaseSensitive(sd, "to"), r, ss->to)) != WR_OK) return st;
    return get_bool(c, sd, q, "reverse", &ss->reverse);
}

static wr_status seam_item(pctx *c, const cJSON *it, const char *p, void *item) {
    wr_pattern_seam *a = (wr_pattern_seam *)item;
    wr_status st;
    if ((st = seam_side(c, it, p, 0, &a->a)) != WR_OK || (st = seam_side(c, it, p, 1, &a->b)) != WR_OK) return st;
    return get_tl(c, it, p, &a->transition_length);
}

/* quilts (down-filling): a panel and its quilting lines */
static wr_status quilt_item(pctx *c, const cJSON *it, const char *p, void *item) {
    wr_pattern_quilt *a = (wr_pattern_quilt *)item;
    const cJSON *ls, *l;
    wr_pattern_curve *lc;
    char q[512];
    wr_status st;
    int k = 0, nl;
    if ((st = get_panel_ref(c, it, p, &a->panel)) != WR_OK) return st;
    join(q, sizeof q, p, "lines");
    ls = cJSON_GetObjectItemCaseSensitive(it, "lines");
    if (!ls) return perr(c, WR_ERR_PARSE, q, "missing");
    if (!cJSON_IsArray(ls) || (nl = cJSON_GetArraySize(ls)) < 1)
        return perr(c, WR_ERR_PARSE, q, "expected a non-empty array of polylines");
    lc = (wr_pattern_curve *)pf_alloc(c->f, (size_t)nl, sizeof *lc);
    if (!lc) return perr(c, WR_ERR_NOMEM, q, "out of memory");
    cJSON_ArrayForEach(l, ls) {
        char r[512];
        joini(r, sizeof r, q, k);
        if ((st = get_points(c, l, r, 2, (double **)&lc[k].xy, &lc[k].n)) != WR_OK) return st;
        ++k;
    }
    a->lines = lc;
    a->n_lines = nl;
    if ((st = get_range(c, it, p, "rho", 1, 0.0, 1, 1.0, 0, &a->rho, NULL)) != WR_OK) return st;
    if ((st = get_range(c, it, p, "E_sh", 0, 0.0, 0, HUGE_VAL, 1, &a->E_sh, NULL)) != WR_OK) return st;
    if ((st = get_range(c, it, p, "pressure", 0, 0.0, 0, HUGE_VAL, 1, &a->pressure, NULL)) != WR_OK) return st;
    if ((st = get_stitch(c, it, p, &a->stitch_length, lc, nl)) != WR_OK) return st;
    return get_tl(c, it, p, &a->transition_length);
}

/* collisions: a polygon, or a circle given by center + radius */
static wr_status collision_item(pctx *c, const cJSON *it, const char *p, void *item) {
    wr_pattern_collision *a = (wr_pattern_collision *)item;
    const cJSON *poly = cJSON_GetObjectItemCaseSensitive(it, "polygon"), *ctr = cJSON_GetObjectItemCaseSensitive(it, "center");
    char q[512];
    wr_status st;
    if ((st = get_panel_ref(c, it, p, &a->panel)) != WR_OK) return st;
    if ((poly != NULL) == (ctr != NULL || cJSON_GetObjectItemCaseSensitive(it, "radius") != NULL))
        return perr(c, WR_ERR_PARSE, p, "give either \"polygon\" or \"center\" + \"radius\"");
    if (poly) {
        join(q, sizeof q, p, "polygon");
        if ((st = get_points(c, poly, q, 3, (double **)&a->xy, &a->n)) != WR_OK) return st;
    } else {
        join(q, sizeof q, p, "center");
        if (!ctr) return perr(c, WR_ERR_PARSE, q, "missing");
        if ((st = get_point(c, ctr, q, a->center)) != WR_OK) return st;
        if ((st = get_range(c, it, p, "radius", 1, 0.0, 1, HUGE_VAL, 1, &a->radius, NULL)) != WR_OK) return st;
        a->radius *= MM;
    }
    if ((st = get_range(c, it, p, "compression", 1, 0.0, 1, 1.0, 1, &a->compression, NULL)) != WR_OK) return st;
    return get_tl(c, it, p, &a->transition_length);
}

/* The garment techniques of Style3D Sec. 4.2, each an optional list, in this order. */
static wr_status parse_techniques(pctx *c, const cJSON *root) {
    static const char *const shirring_keys[] = {"panel", "line", "E_sh", "rho", "n", "transition_length", "stitch_length",
                                                NULL};
    static const char *const fold_keys[] = {"panel", "line", "angle_deg", "offset", "curvature_radius", "transition_length",
                                            NULL};
    static const char *const seam_keys[] = {"a", "b", "transition_length", NULL};
    static const char *const quilt_keys[] = {"panel", "lines", "rho", "E_sh", "pressure", "transition_length", "stitch_length",
                                             NULL};
    static const char *const collision_keys[] = {"panel", "polygon", "center", "radius", "compression",
                                                 "transition_length", NULL};
    wr_pattern *pt = &c->f->pattern;
    void *sh = NULL, *fo = NULL, *se = NULL, *qu = NULL, *co = NULL;
    wr_status st;
    if ((st = parse_list(c, root, "shirring", shirring_keys, sizeof(wr_pattern_shirring), shirring_item, &sh,
                         &pt->n_shirrings)) != WR_OK)
        return st;
    if (sh) pt->shirrings = (const wr_pattern_shirring *)sh;
    if ((st = parse_list(c, root, "folds", fold_keys, sizeof(wr_pattern_fold), fold_item, &fo, &pt->n_folds)) != WR_OK)
        return st;
    if (fo) pt->folds = (const wr_pattern_fold *)fo;
    if ((st = parse_list(c, root, "seams", seam_keys, sizeof(wr_pattern_seam), seam_item, &se, &pt->n_seams)) != WR_OK)
        return st;
    if (se) pt->seams = (const wr_pattern_seam *)se;
    if ((st = parse_list(c, root, "quilts", quilt_keys, sizeof(wr_pattern_quilt), quilt_item, &qu, &pt->n_quilts)) != WR_OK)
        return st;
    if (qu) pt->quilts = (const wr_pattern_quilt *)qu;
    if ((st = parse_list(c, root, "collisions", collision_keys, sizeof(wr_pattern_collision), collision_item, &co,
                         &pt->n_collisions)) != WR_OK)
        return st;
    if (co) pt->collisions = (const wr_pattern_collision *)co;
    return WR_OK;
}

static wr_status parse_mesher(pctx *c, const cJSON *root) {
    static const char *const keys[] = {"seed", "max_vertices", "sew", "uniform_resolution", "radius_factor", NULL};
    const cJSON *m = cJSON_GetObjectItemCaseSensitive(root, "mesher");
    wr_status st;
    double x;
    int pr;
    if (!m) return WR_OK;
    if ((st = need_object(c, m, "mesher")) != WR_OK || (st = check_keys(c, m, "mesher", keys)) != WR_OK) return st;
    if ((st = get_range(c, m, "mesher", "seed", 0, 0.0, 0, 9007199254740992.0, 0, &x, &pr)) != WR_OK) return st;
    if (pr) {
        if (x != floor(x)) return perr(c, WR_ERR_PARSE, "mesher.seed", "expected a non-negative integer");
        c->f->desc.seed = (uint64_t)x;
    }
    if ((st = get_range(c, m, "mesher", "max_vertices", 0, 1.0, 0, 2147483647.0, 0, &x, &pr)) != WR_OK) return st;
    if (pr) {
        if (x != floor(x)) return perr(c, WR_ERR_PARSE, "mesher.max_vertices", "expected an integer");
        c->f->desc.max_vertices = (int32_t)x;
    }
    if ((st = get_bool(c, m, "mesher", "sew", &c->f->desc.sew)) != WR_OK) return st;
    if ((st = get_range(c, m, "mesher", "uniform_resolution", 0, 0.0, 1, HUGE_VAL, 1, &x, &pr)) != WR_OK) return st;
    if (pr) c->f->desc.uniform_resolution = x * MM;
    if ((st = get_range(c, m, "mesher", "radius_factor", 0, 0.0, 1, 10.0, 0, &c->f->desc.radius_factor, NULL)) != WR_OK)
        return st;
    return WR_OK;
}

wr_status wr_pattern_parse(const char *text, size_t len, const char *name, wr_pattern_file *out, wr_diag *diag) {
    static const char *const keys[] = {"format", "name", "units", "fabrics", "panels", "shirring", "folds",
                                       "seams", "quilts", "collisions", "mesher", NULL};
    pctx c;
    cJSON *root;
    const cJSON *v;
    const char *end = NULL;
    wr_status st;
    if (!out) return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "NULL output");
    memset(out, 0, sizeof *out);
    c.f = out;
    c.diag = diag;
    c.file = name ? name : "pattern";
    c.fabrics = NULL;
    if (!text) return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "%s: NULL text", c.file);
    root = cJSON_ParseWithLengthOpts(text, len, &end, 0);
    if (!root) {
        /* name the line of the error */
        size_t off = (end && end >= text && (size_t)(end - text) <= len) ? (size_t)(end - text) : 0, k;
        int line = 1;
        const char *e2 = cJSON_GetErrorPtr();
        if (e2 && e2 >= text && (size_t)(e2 - text) <= len) off = (size_t)(e2 - text);
        for (k = 0; k < off; ++k) line += text[k] == '\n';
        return wr_fail(diag, WR_ERR_PARSE, line, "%s: line %d: malformed JSON", c.file, line);
    }
    /* only whitespace may follow the document */
    if (end) {
        while ((size_t)(end - text) < len && (*end == ' ' || *end == '\t' || *end == '\n' || *end == '\r')) ++end;
        if ((size_t)(end - text) < len && *end != '\0') {
            cJSON_Delete(root);
            return wr_fail(diag, WR_ERR_PARSE, -1, "%s: trailing characters after the JSON document", c.file);
        }
    }
    if ((st = need_object(&c, root, "$")) != WR_OK) goto done;
    if ((st = check_keys(&c, root, "$", keys)) != WR_OK) goto done;
    v = cJSON_GetObjectItemCaseSensitive(root, "format");
    if (v && (!cJSON_IsString(v) || strcmp(v->valuestring, "wrinkle-pattern/1") != 0)) {
        st = perr(&c, WR_ERR_PARSE, "format", "expected \"wrinkle-pattern/1\"");
        goto done;
    }
    v = cJSON_GetObjectItemCaseSensitive(root, "units");
    if (v && (!cJSON_IsString(v) || strcmp(v->valuestring, "mm") != 0)) {
        st = perr(&c, WR_ERR_PARSE, "units", "only \"mm\" is supported (lengths in millimetres)");
        goto done;
    }
    v = cJSON_GetObjectItemCaseSensitive(root, "name");
    if (v) {
        if (!cJSON_IsString(v)) {
            st = perr(&c, WR_ERR_PARSE, "name", "expected a string");
            goto done;
        }
        snprintf(out->name, sizeof out->name, "%s", v->valuestring);
    }
    v = cJSON_GetObjectItemCaseSensitive(root, "fabrics");
    if (v) {
        if (!cJSON_IsObject(v)) {
            st = perr(&c, WR_ERR_PARSE, "fabrics", "expected an object of named fabrics");
            goto done;
        }
        c.fabrics = (cJSON *)v;
    }
    if ((st = parse_panels(&c, root)) != WR_OK) goto done;
    if ((st = parse_techniques(&c, root)) != WR_OK) goto done;
    if ((st = parse_mesher(&c, root)) != WR_OK) goto done;
    /* named fabrics must all parse, also the unused ones (a typo there is still a typo) */
    if (c.fabrics) {
        const cJSON *it;
        cJSON_ArrayForEach(it, c.fabrics) {
            wr_pattern_fabric tmp;
            char p[512];
            if (cJSON_IsString(it)) {
                st = perr(&c, WR_ERR_PARSE, "fabrics", "\"%s\": a named fabric must be an object", it->string);
                goto done;
            }
            snprintf(p, sizeof p, "fabrics.%s", it->string ? it->string : "?");
            if ((st = parse_fabric(&c, it, p, &tmp)) != WR_OK) goto done;
        }
    }
done:
    cJSON_Delete(root);
    if (st != WR_OK) wr_pattern_file_free(out);
    return st;
}

wr_status wr_pattern_load(const char *path, wr_pattern_file *out, wr_diag *diag) {
    struct stat sb;
    char *buf = NULL;
    size_t n = 0;
    wr_status st;
    if (out) memset(out, 0, sizeof *out);
    if (!path || !out) return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "NULL argument");
    /* a regular file over the limit is refused before anything is read */
    if (stat(path, &sb) == 0 && S_ISREG(sb.st_mode) && (double)sb.st_size > (double)WR_PATTERN_MAX_FILE_BYTES)
        return wr_fail(diag, WR_ERR_IO, -1, "%s: larger than %ld bytes", path, (long)WR_PATTERN_MAX_FILE_BYTES);
    st = wr_file_read(path, &buf, &n, diag); /* core.h: WR_ERR_IO naming the path, or WR_ERR_NOMEM */
    if (st != WR_OK) return st;
    if (n > (size_t)WR_PATTERN_MAX_FILE_BYTES) { /* a pipe or device that delivered more */
        wr_free(buf);
        return wr_fail(diag, WR_ERR_IO, -1, "%s: larger than %ld bytes", path, (long)WR_PATTERN_MAX_FILE_BYTES);
    }
    st = wr_pattern_parse(buf, n, path, out, diag);
    wr_free(buf);
    return st;
}

/* Built-in example: Style3D Fig. 14 — a 250 mm square of the Table 1 "Green" fabric (B = 2.6e-6 N·m,
 * E = 2.0e6 N/m², r = 6.0 mm) with three curved (sinusoidal) shirring lines; E_sh = E and shrinkage
 * ρ = 0.5 (our choice: the paper gives no values for this figure). */
const char WR_PATTERN_FIG14_JSON[] =
    "{\n"
    "  \"format\": \"wrinkle-pattern/1\",\n"
    "  \"name\": \"fig14-square-shirring\",\n"
    "  \"units\": \"mm\",\n"
    "  \"comment\": \"Style3D Fig. 14: 250 mm square, Table 1 Green fabric, three curved shirring lines\",\n"
    "  \"fabrics\": { \"green\": { \"B\": 2.6e-6, \"E\": 2.0e6 } },\n"
    "  \"panels\": [ { \"name\": \"square\", \"fabric\": \"green\",\n"
    "      \"outer\": [[0, 0], [250, 0], [250, 250], [0, 250]] } ],\n"
    "  \"shirring\": [\n"
    "    { \"panel\": \"square\", \"E_sh\": 2.0e6, \"rho\": 0.5, \"line\": [[25, 62.5], [37.5, 69.6], [50, 72.5], [62.5, 69.6],"
    " [75, 62.5], [87.5, 55.4], [100, 52.5], [112.5, 55.4], [125, 62.5], [137.5, 69.6], [150, 72.5], [162.5, 69.6],"
    " [175, 62.5], [187.5, 55.4], [200, 52.5], [212.5, 55.4], [225, 62.5]] },\n"
    "    { \"panel\": \"square\", \"E_sh\": 2.0e6, \"rho\": 0.5, \"line\": [[25, 125], [37.5, 132.1], [50, 135], [62.5, 132.1],"
    " [75, 125], [87.5, 117.9], [100, 115], [112.5, 117.9], [125, 125], [137.5, 132.1], [150, 135], [162.5, 132.1],"
    " [175, 125], [187.5, 117.9], [200, 115], [212.5, 117.9], [225, 125]] },\n"
    "    { \"panel\": \"square\", \"E_sh\": 2.0e6, \"rho\": 0.5, \"line\": [[25, 187.5], [37.5, 194.6], [50, 197.5], [62.5, 194.6],"
    " [75, 187.5], [87.5, 180.4], [100, 177.5], [112.5, 180.4], [125, 187.5], [137.5, 194.6], [150, 197.5], [162.5, 194.6],"
    " [175, 187.5], [187.5, 180.4], [200, 177.5], [212.5, 180.4], [225, 187.5]] }\n"
    "  ]\n"
    "}\n";

wr_status wr_pattern_builtin_fig14(wr_pattern_file *out, wr_diag *diag) {
    return wr_pattern_parse(WR_PATTERN_FIG14_JSON, sizeof WR_PATTERN_FIG14_JSON - 1, "built-in fig14", out, diag);
}
