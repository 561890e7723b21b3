/* simscene.c — see simscene.h and docs/sim-scene-format.md. Uses cJSON (Debian libcjson-dev).
 * (The small JSON readers below follow scene.c's; they are private there, so they are repeated
 * here rather than shared — a jsonin helper both could use is the natural next step.) */
#define _POSIX_C_SOURCE 200809L
#include "simscene.h"

#include "jsonout.h"

#include <cjson/cJSON.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* ---- JSON readers: every error names the JSON path ------------------------------------------- */

static wr_status ss_err(wr_diag *d, const char *path, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 3, 4)))
#endif
    ;
static wr_status ss_err(wr_diag *d, const char *path, const char *fmt, ...) {
    char msg[400], full[WR_DIAG_MESSAGE_LEN], line[WR_DIAG_MESSAGE_LEN];
    size_t i, o = 0;
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    snprintf(full, sizeof full, "%s: %s", path, msg);
    /* keys and strings come from the file: control characters shown as \xHH keep it one line */
    for (i = 0; full[i] && o + 5 < sizeof line; ++i) {
        unsigned char ch = (unsigned char)full[i];
        if (ch < 0x20 || ch == 0x7f) o += (size_t)snprintf(line + o, sizeof line - o, "\\x%02x", ch);
        else line[o++] = (char)ch;
    }
    line[o] = 0;
    return wr_fail(d, WR_ERR_PARSE, -1, "%s", line);
}

static void ss_path(char *out, size_t n, const char *base, const char *key) { snprintf(out, n, "%s.%s", base, key); }

static wr_status ss_keys(wr_diag *d, const cJSON *obj, const char *path, const char *const *allowed) {
    const cJSON *it;
    if (!cJSON_IsObject(obj)) return ss_err(d, path, "must be an object");
    for (it = obj->child; it; it = it->next) {
        const char *const *a;
        int ok = 0;
        for (a = allowed; *a; ++a)
            if (strcmp(*a, it->string) == 0) ok = 1;
        if (!ok) {
            char p[512];
            ss_path(p, sizeof p, path, it->string);
            return ss_err(d, p, "unknown key");
        }
    }
    return WR_OK;
}

enum { SS_ANY = 0, SS_POS = 1, SS_NONNEG = 2 };

static wr_status ss_num(wr_diag *d, const cJSON *obj, const char *key, const char *path, int rule, double *out,
                        int *found) {
    const cJSON *v = cJSON_GetObjectItemCaseSensitive(obj, key);
    char p[512];
    if (found) *found = 0;
    if (!v) return WR_OK;
    ss_path(p, sizeof p, path, key);
    if (!cJSON_IsNumber(v) || !isfinite(v->valuedouble)) return ss_err(d, p, "must be a finite number");
    if (rule == SS_POS && !(v->valuedouble > 0.0)) return ss_err(d, p, "must be > 0 (got %g)", v->valuedouble);
    if (rule == SS_NONNEG && !(v->valuedouble >= 0.0)) return ss_err(d, p, "must be >= 0 (got %g)", v->valuedouble);
    *out = v->valuedouble;
    if (found) *found = 1;
    return WR_OK;
}

static wr_status ss_int(wr_diag *d, const cJSON *obj, const char *key, const char *path, long lo, long hi, int32_t *out,
                        int *found) {
    const cJSON *v = cJSON_GetObjectItemCaseSensitive(obj, key);
    char p[512];
    if (found) *found = 0;
    if (!v) return WR_OK;
    ss_path(p, sizeof p, path, key);
    if (!cJSON_IsNumber(v) || v->valuedouble != floor(v->valuedouble) || v->valuedouble < (double)lo ||
        v->valuedouble > (double)hi)
        return ss_err(d, p, "must be an integer in [%ld, %ld]", lo, hi);
    *out = (int32_t)v->valuedouble;
    if (found) *found = 1;
    return WR_OK;
}

static wr_status ss_vec(wr_diag *d, const cJSON *obj, const char *key, const char *path, int n, double *out, int *found) {
    const cJSON *v = cJSON_GetObjectItemCaseSensitive(obj, key), *e;
    char p[512];
    int i = 0;
    if (found) *found = 0;
    if (!v) return WR_OK;
    ss_path(p, sizeof p, path, key);
    if (!cJSON_IsArray(v) || cJSON_GetArraySize(v) != n) return ss_err(d, p, "must be an array of %d numbers", n);
    for (e = v->child; e; e = e->next, ++i) {
        if (!cJSON_IsNumber(e) || !isfinite(e->valuedouble)) {
            char q[540];
            snprintf(q, sizeof q, "%s[%d]", p, i);
            return ss_err(d, q, "must be a finite number");
        }
        out[i] = e->valuedouble;
    }
    if (found) *found = 1;
    return WR_OK;
}

/* String value into out (cap bytes); required → error when absent. */
static wr_status ss_str(wr_diag *d, const cJSON *obj, const char *key, const char *path, char *out, size_t cap,
                        int required, int *found) {
    const cJSON *v = cJSON_GetObjectItemCaseSensitive(obj, key);
    char p[512];
    ss_path(p, sizeof p, path, key);
    if (found) *found = 0;
    if (!v) return required ? ss_err(d, p, "is required") : WR_OK;
    if (!cJSON_IsString(v) || !v->valuestring) return ss_err(d, p, "must be a string");
    if (strlen(v->valuestring) + 1 > cap) return ss_err(d, p, "longer than %d bytes", (int)cap - 1);
    memcpy(out, v->valuestring, strlen(v->valuestring) + 1);
    if (found) *found = 1;
    return WR_OK;
}

/* The string must be one of names[]; *out = its index. */
static wr_status ss_enum(wr_diag *d, const cJSON *obj, const char *key, const char *path, const char *const *names,
                         int *out) {
    char buf[64], p[512];
    int found = 0, i;
    wr_status st = ss_str(d, obj, key, path, buf, sizeof buf, 0, &found);
    if (st != WR_OK || !found) return st;
    for (i = 0; names[i]; ++i)
        if (strcmp(buf, names[i]) == 0) {
            *out = i;
            return WR_OK;
        }
    ss_path(p, sizeof p, path, key);
    return ss_err(d, p, "unknown value \"%s\"", buf);
}

/* ---- sections --------------------------------------------------------------------------------- */

static wr_status ss_parse_mesh(wr_diag *d, const cJSON *o, const char *base_dir, wr_simscene_cloth *c) {
    static const char *const keys[] = {"type", "width", "height", "radius", "resolution", "nx", "ny", "path", NULL};
    static const char *const kinds[] = {"rectangle", "disk", "obj", NULL};
    const char *P = "$.cloth.mesh";
    int kind = -1, fw = 0, fh = 0, fr = 0, fres = 0, fnx = 0, fny = 0;
    wr_status st;
    if ((st = ss_keys(d, o, P, keys)) != WR_OK) return st;
    if (!cJSON_GetObjectItemCaseSensitive(o, "type")) return ss_err(d, "$.cloth.mesh.type", "is required");
    if ((st = ss_enum(d, o, "type", P, kinds, &kind)) != WR_OK) return st;
    c->kind = (wr_simscene_mesh_kind)kind;
    if ((st = ss_num(d, o, "width", P, SS_POS, &c->width, &fw)) != WR_OK) return st;
    if ((st = ss_num(d, o, "height", P, SS_POS, &c->height, &fh)) != WR_OK) return st;
    if ((st = ss_num(d, o, "radius", P, SS_POS, &c->radius, &fr)) != WR_OK) return st;
    if ((st = ss_num(d, o, "resolution", P, SS_POS, &c->resolution, &fres)) != WR_OK) return st;
    if ((st = ss_int(d, o, "nx", P, 1, 100000, &c->nx, &fnx)) != WR_OK) return st;
    if ((st = ss_int(d, o, "ny", P, 1, 100000, &c->ny, &fny)) != WR_OK) return st;
    if (c->kind == WR_SIMSCENE_MESH_RECTANGLE) {
        if (!fw || !fh) return ss_err(d, P, "rectangle needs width and height");
        if (!fres && !(fnx && fny)) return ss_err(d, P, "rectangle needs resolution or nx and ny");
        if (!fnx) c->nx = (int32_t)fmax(1.0, floor(c->width / c->resolution + 0.5));
        if (!fny) c->ny = (int32_t)fmax(1.0, floor(c->height / c->resolution + 0.5));
        if (((double)c->nx + 1) * ((double)c->ny + 1) > WR_SIMSCENE_MAX_VERTICES)
            return ss_err(d, "$.cloth.mesh.resolution", "%d x %d cells exceed %d vertices", (int)c->nx, (int)c->ny,
                          WR_SIMSCENE_MAX_VERTICES);
    } else if (c->kind == WR_SIMSCENE_MESH_DISK) {
        double rings;
        if (!fr || !fres) return ss_err(d, P, "disk needs radius and resolution");
        rings = floor(c->radius / c->resolution + 0.5);
        if (rings < 1.0) rings = 1.0;
        if (1.0 + 3.0 * rings * (rings + 1.0) > WR_SIMSCENE_MAX_VERTICES)
            return ss_err(d, "$.cloth.mesh.resolution", "%g rings exceed %d vertices", rings, WR_SIMSCENE_MAX_VERTICES);
        c->nx = (int32_t)rings;
    } else {
        char rel[WR_SIMSCENE_PATH_LEN];
        if ((st = ss_str(d, o, "path", P, rel, sizeof rel, 1, NULL)) != WR_OK) return st;
        if (rel[0] == '/' || !base_dir || !base_dir[0])
            snprintf(c->path, sizeof c->path, "%s", rel);
        else if ((size_t)snprintf(c->path, sizeof c->path, "%s/%s", base_dir, rel) >= sizeof c->path)
            return ss_err(d, "$.cloth.mesh.path", "path too long");
    }
    return WR_OK;
}

static wr_status ss_parse_material(wr_diag *d, const cJSON *o, wr_simscene_cloth *c) {
    static const char *const keys[] = {"young", "poisson", "thickness", "bending_stiffness", "density", "areal_density",
                                       "membrane", "bending", NULL};
    static const char *const mem[] = {"stvk", "tft", "none", NULL};
    static const char *const bend[] = {"midedge", "quadratic", "none", NULL};
    const char *P = "$.cloth.material";
    wr_shell_desc *s = &c->shell;
    int fE = 0, fh = 0, fB = 0, fd = 0, fa = 0, fnu = 0, m = 0, b = 0;
    wr_status st;
    if ((st = ss_keys(d, o, P, keys)) != WR_OK) return st;
    if ((st = ss_num(d, o, "young", P, SS_POS, &s->young, &fE)) != WR_OK) return st;
    if ((st = ss_num(d, o, "poisson", P, SS_ANY, &s->poisson, &fnu)) != WR_OK) return st;
    if (fnu && !(s->poisson > -1.0 && s->poisson <= 0.5))
        return ss_err(d, "$.cloth.material.poisson", "must be in (-1, 0.5] (got %g)", s->poisson);
    if ((st = ss_num(d, o, "thickness", P, SS_POS, &s->thickness, &fh)) != WR_OK) return st;
    if ((st = ss_num(d, o, "bending_stiffness", P, SS_POS, &s->bending_stiffness, &fB)) != WR_OK) return st;
    if ((st = ss_num(d, o, "density", P, SS_POS, &s->density, &fd)) != WR_OK) return st;
    if ((st = ss_num(d, o, "areal_density", P, SS_POS, &c->areal_density, &fa)) != WR_OK) return st;
    if ((st = ss_enum(d, o, "membrane", P, mem, &m)) != WR_OK) return st;
    if ((st = ss_enum(d, o, "bending", P, bend, &b)) != WR_OK) return st;
    s->membrane = (wr_membrane_model)m;
    s->bending = (wr_bending_model)b;
    if (!fE) return ss_err(d, "$.cloth.material.young", "is required");
    if (!fh && !fB) return ss_err(d, P, "needs thickness or bending_stiffness");
    if (!fd && !fa) return ss_err(d, P, "needs density or areal_density (a dynamic cloth has mass)");
    if (fd && fa) return ss_err(d, "$.cloth.material.areal_density", "give density or areal_density, not both");
    if (!fh) /* Kirchhoff–Love (Style3D Sec. 4.1.1): B = E h³/(12(1−ν²)) solved for h */
        s->thickness = cbrt(12.0 * (1.0 - s->poisson * s->poisson) * s->bending_stiffness / s->young);
    if (fa) s->density = c->areal_density / s->thickness;
    return WR_OK;
}

static wr_status ss_parse_indices(wr_diag *d, const cJSON *idx, const char *P, int32_t **out, int32_t *n) {
    const cJSON *e;
    int32_t k = 0, cnt;
    if (!cJSON_IsArray(idx) || (cnt = cJSON_GetArraySize(idx)) < 1) return ss_err(d, P, "must be a non-empty array");
    *out = (int32_t *)wr_alloc_array((size_t)cnt, sizeof(int32_t));
    if (!*out) return wr_fail(d, WR_ERR_NOMEM, -1, "%s: out of memory", P);
    for (e = idx->child; e; e = e->next, ++k) {
        if (!cJSON_IsNumber(e) || e->valuedouble != floor(e->valuedouble) || e->valuedouble < 0 ||
            e->valuedouble > (double)INT32_MAX) {
            char q[540];
            snprintf(q, sizeof q, "%s[%d]", P, (int)k);
            return ss_err(d, q, "must be a vertex index >= 0");
        }
        (*out)[k] = (int32_t)e->valuedouble;
    }
    *n = cnt;
    return WR_OK;
}

static wr_status ss_parse_cloth(wr_diag *d, const cJSON *o, const char *base_dir, wr_simscene_cloth *c) {
    static const char *const keys[] = {"mesh", "material", "placement", "velocity", "pins", NULL};
    static const char *const pkeys[] = {"rotate", "translate", NULL};
    static const char *const rkeys[] = {"axis", "angle", NULL};
    static const char *const pinkeys[] = {"box", "indices", NULL};
    static const char *const bkeys[] = {"min", "max", NULL};
    const cJSON *m, *pl, *pins, *e;
    wr_status st;
    int k = 0;
    if ((st = ss_keys(d, o, "$.cloth", keys)) != WR_OK) return st;
    if (!(m = cJSON_GetObjectItemCaseSensitive(o, "mesh"))) return ss_err(d, "$.cloth.mesh", "is required");
    if ((st = ss_parse_mesh(d, m, base_dir, c)) != WR_OK) return st;
    if (!(m = cJSON_GetObjectItemCaseSensitive(o, "material"))) return ss_err(d, "$.cloth.material", "is required");
    if ((st = ss_parse_material(d, m, c)) != WR_OK) return st;
    if ((st = ss_vec(d, o, "velocity", "$.cloth", 3, c->velocity, NULL)) != WR_OK) return st;
    if ((pl = cJSON_GetObjectItemCaseSensitive(o, "placement"))) {
        const cJSON *r;
        if ((st = ss_keys(d, pl, "$.cloth.placement", pkeys)) != WR_OK) return st;
        if ((st = ss_vec(d, pl, "translate", "$.cloth.placement", 3, c->translate, NULL)) != WR_OK) return st;
        if ((r = cJSON_GetObjectItemCaseSensitive(pl, "rotate"))) {
            int fa = 0, fang = 0;
            const char *R = "$.cloth.placement.rotate";
            if ((st = ss_keys(d, r, R, rkeys)) != WR_OK) return st;
            if ((st = ss_vec(d, r, "axis", R, 3, c->rotate_axis, &fa)) != WR_OK) return st;
            if ((st = ss_num(d, r, "angle", R, SS_ANY, &c->rotate_angle, &fang)) != WR_OK) return st;
            if (!fa || !fang) return ss_err(d, R, "needs axis and angle [rad]");
            if (!(c->rotate_axis[0] * c->rotate_axis[0] + c->rotate_axis[1] * c->rotate_axis[1] +
                      c->rotate_axis[2] * c->rotate_axis[2] >
                  0.0))
                return ss_err(d, "$.cloth.placement.rotate.axis", "must not be zero");
        }
    }
    if ((pins = cJSON_GetObjectItemCaseSensitive(o, "pins"))) {
        if (!cJSON_IsArray(pins)) return ss_err(d, "$.cloth.pins", "must be an array");
        if (cJSON_GetArraySize(pins) > WR_SIMSCENE_MAX_PINS)
            return ss_err(d, "$.cloth.pins", "at most %d sets", WR_SIMSCENE_MAX_PINS);
        for (e = pins->child; e; e = e->next, ++k) {
            char P[64], q[96];
            const cJSON *box, *idx;
            wr_simscene_pin *p = c->pin + k;
            snprintf(P, sizeof P, "$.cloth.pins[%d]", k);
            if ((st = ss_keys(d, e, P, pinkeys)) != WR_OK) return st;
            c->n_pins = k + 1;
            box = cJSON_GetObjectItemCaseSensitive(e, "box");
            idx = cJSON_GetObjectItemCaseSensitive(e, "indices");
            if (!!box == !!idx) return ss_err(d, P, "needs exactly one of box or indices");
            if (box) {
                int f1 = 0, f2 = 0;
                snprintf(q, sizeof q, "%s.box", P);
                if ((st = ss_keys(d, box, q, bkeys)) != WR_OK) return st;
                if ((st = ss_vec(d, box, "min", q, 3, p->lo, &f1)) != WR_OK) return st;
                if ((st = ss_vec(d, box, "max", q, 3, p->hi, &f2)) != WR_OK) return st;
                if (!f1 || !f2) return ss_err(d, q, "needs min and max");
                p->select_box = 1;
            } else {
                snprintf(q, sizeof q, "%s.indices", P);
                if ((st = ss_parse_indices(d, idx, q, &p->indices, &p->n_indices)) != WR_OK) return st;
            }
        }
    }
    return WR_OK;
}

static wr_status ss_parse_obstacles(wr_diag *d, const cJSON *arr, wr_simscene *sc) {
    static const char *const keys[] = {"type", "point", "normal", "center", "radius", "p", "q", NULL};
    static const char *const kinds[] = {"plane", "sphere", "capsule", NULL};
    const cJSON *e;
    int k = 0;
    wr_status st;
    if (!cJSON_IsArray(arr)) return ss_err(d, "$.obstacles", "must be an array");
    if (cJSON_GetArraySize(arr) > WR_SIMSCENE_MAX_OBSTACLES)
        return ss_err(d, "$.obstacles", "at most %d obstacles", WR_SIMSCENE_MAX_OBSTACLES);
    for (e = arr->child; e; e = e->next, ++k) {
        char P[64];
        int kind = -1, f1 = 0, f2 = 0, f3 = 0;
        wr_obstacle *o = sc->analytic + k;
        snprintf(P, sizeof P, "$.obstacles[%d]", k);
        if ((st = ss_keys(d, e, P, keys)) != WR_OK) return st;
        if (!cJSON_GetObjectItemCaseSensitive(e, "type")) {
            char q[80];
            snprintf(q, sizeof q, "%s.type", P);
            return ss_err(d, q, "is required");
        }
        if ((st = ss_enum(d, e, "type", P, kinds, &kind)) != WR_OK) return st;
        memset(o, 0, sizeof *o);
        o->kind = (wr_obstacle_kind)kind;
        if (o->kind == WR_OBSTACLE_PLANE) {
            if ((st = ss_vec(d, e, "point", P, 3, o->p, &f1)) != WR_OK) return st;
            if ((st = ss_vec(d, e, "normal", P, 3, o->normal, &f2)) != WR_OK) return st;
            if (!f1 || !f2) return ss_err(d, P, "plane needs point and normal");
            if (!(o->normal[0] * o->normal[0] + o->normal[1] * o->normal[1] + o->normal[2] * o->normal[2] > 0.0))
                return ss_err(d, P, "plane normal must not be zero");
        } else if (o->kind == WR_OBSTACLE_SPHERE) {
            if ((st = ss_vec(d, e, "center", P, 3, o->p, &f1)) != WR_OK) return st;
            if ((st = ss_num(d, e, "radius", P, SS_POS, &o->radius, &f2)) != WR_OK) return st;
            if (!f1 || !f2) return ss_err(d, P, "sphere needs center and radius");
        } else {
            if ((st = ss_vec(d, e, "p", P, 3, o->p, &f1)) != WR_OK) return st;
            if ((st = ss_vec(d, e, "q", P, 3, o->q, &f2)) != WR_OK) return st;
            if ((st = ss_num(d, e, "radius", P, SS_POS, &o->radius, &f3)) != WR_OK) return st;
            if (!f1 || !f2 || !f3) return ss_err(d, P, "capsule needs p, q and radius");
        }
        sc->n_analytic = k + 1;
    }
    return WR_OK;
}

static wr_status ss_parse_settings(wr_diag *d, const cJSON *root, wr_simscene *sc) {
    static const char *const tkeys[] = {"duration", "dt", "substeps", "max_halvings", NULL};
    static const char *const dkeys[] = {"mass", "stiffness", NULL};
    static const char *const ckeys[] = {"dhat", "stiffness", "friction", "friction_eps_v", NULL};
    static const char *const skeys[] = {"linear", "linear_tol", "max_iter", "velocity_tol", "grad_tol", "hessian", NULL};
    static const char *const okeys[] = {"every", "format", NULL};
    static const char *const lin[] = {"auto", "pcg-jacobi", "pcg-block3", "pcg-ic0", "cholmod", "pcg-amg", NULL};
    static const char *const hess[] = {"projected", "jacobi", "exact", NULL};
    static const char *const fmt[] = {"obj", "ply", NULL};
    wr_dyn_desc *dd = &sc->dyn;
    const cJSON *o;
    wr_status st;
    int f = 0, e = 0;
    if ((st = ss_vec(d, root, "gravity", "$", 3, dd->gravity, NULL)) != WR_OK) return st;
    if ((o = cJSON_GetObjectItemCaseSensitive(root, "time"))) {
        if ((st = ss_keys(d, o, "$.time", tkeys)) != WR_OK) return st;
        if ((st = ss_num(d, o, "duration", "$.time", SS_NONNEG, &sc->duration, NULL)) != WR_OK) return st;
        if ((st = ss_num(d, o, "dt", "$.time", SS_POS, &dd->time.dt, NULL)) != WR_OK) return st;
        if ((st = ss_int(d, o, "substeps", "$.time", 1, 1000, &dd->time.substeps, NULL)) != WR_OK) return st;
        if ((st = ss_int(d, o, "max_halvings", "$.time", 0, 30, &dd->time.max_halvings, &f)) != WR_OK) return st;
        dd->time.has_max_halvings = f;
    }
    if (sc->duration / dd->time.dt > WR_SIMSCENE_MAX_FRAMES)
        return ss_err(d, "$.time.duration", "%g s at dt %g s is more than %d frames", sc->duration, dd->time.dt,
                      WR_SIMSCENE_MAX_FRAMES);
    if ((o = cJSON_GetObjectItemCaseSensitive(root, "damping"))) {
        if ((st = ss_keys(d, o, "$.damping", dkeys)) != WR_OK) return st;
        if ((st = ss_num(d, o, "mass", "$.damping", SS_NONNEG, &dd->damping.mass, NULL)) != WR_OK) return st;
        if ((st = ss_num(d, o, "stiffness", "$.damping", SS_NONNEG, &dd->damping.stiffness, NULL)) != WR_OK) return st;
    }
    if ((o = cJSON_GetObjectItemCaseSensitive(root, "contact"))) {
        if ((st = ss_keys(d, o, "$.contact", ckeys)) != WR_OK) return st;
        if ((st = ss_num(d, o, "dhat", "$.contact", SS_POS, &dd->contact.dhat, NULL)) != WR_OK) return st;
        if ((st = ss_num(d, o, "stiffness", "$.contact", SS_POS, &dd->contact.stiffness, NULL)) != WR_OK) return st;
        if ((st = ss_num(d, o, "friction", "$.contact", SS_NONNEG, &dd->contact.friction, NULL)) != WR_OK) return st;
        if ((st = ss_num(d, o, "friction_eps_v", "$.contact", SS_POS, &dd->contact.friction_eps_v, NULL)) != WR_OK)
            return st;
    }
    if ((o = cJSON_GetObjectItemCaseSensitive(root, "solver"))) {
        int m = 0, h = 0;
        if ((st = ss_keys(d, o, "$.solver", skeys)) != WR_OK) return st;
        if ((st = ss_enum(d, o, "linear", "$.solver", lin, &m)) != WR_OK) return st;
        dd->linear.method = (wr_solver_method)m;
        if ((st = ss_num(d, o, "linear_tol", "$.solver", SS_POS, &dd->linear.rel_tol, &f)) != WR_OK) return st;
        if (f && !(dd->linear.rel_tol < 1.0)) return ss_err(d, "$.solver.linear_tol", "must be < 1");
        if ((st = ss_int(d, o, "max_iter", "$.solver", 1, 100000, &dd->newton.max_iter, NULL)) != WR_OK) return st;
        if ((st = ss_num(d, o, "velocity_tol", "$.solver", SS_POS, &dd->newton.velocity_tol, NULL)) != WR_OK) return st;
        if ((st = ss_num(d, o, "grad_tol", "$.solver", SS_POS, &dd->newton.grad_tol, NULL)) != WR_OK) return st;
        if ((st = ss_enum(d, o, "hessian", "$.solver", hess, &h)) != WR_OK) return st;
        dd->newton.projection = h == 0 ? WR_PROJECT_FAST : h == 1 ? WR_PROJECT_JACOBI : WR_PROJECT_NONE;
    }
    if ((o = cJSON_GetObjectItemCaseSensitive(root, "output"))) {
        if ((st = ss_keys(d, o, "$.output", okeys)) != WR_OK) return st;
        if ((st = ss_int(d, o, "every", "$.output", 1, 1000000, &sc->output_every, NULL)) != WR_OK) return st;
        if ((st = ss_enum(d, o, "format", "$.output", fmt, &e)) != WR_OK) return st;
        sc->output_ply = e;
    }
    return WR_OK;
}

void wr_simscene_defaults(wr_simscene *sc) {
    memset(sc, 0, sizeof *sc);
    snprintf(sc->name, sizeof sc->name, "sim");
    sc->duration = 1.0;
    sc->dyn.time.dt = 1.0 / 30.0;
    sc->output_every = 1;
}

void wr_simscene_free(wr_simscene *sc) {
    int32_t i;
    if (!sc) return;
    for (i = 0; i < WR_SIMSCENE_MAX_PINS; ++i) wr_free(sc->cloth.pin[i].indices);
    memset(sc, 0, sizeof *sc);
}

wr_status wr_simscene_parse(wr_simscene *sc, const char *text, size_t len, const char *base_dir, wr_diag *diag) {
    static const char *const keys[] = {"name", "cloth", "obstacles", "gravity", "time", "damping", "contact", "solver",
                                       "output", NULL};
    cJSON *root;
    const cJSON *o;
    wr_status st;
    wr_simscene_defaults(sc);
    root = cJSON_ParseWithLength(text, len);
    if (!root) return ss_err(diag, "$", "not valid JSON (near byte %ld)", (long)(cJSON_GetErrorPtr() ? cJSON_GetErrorPtr() - text : 0));
    if ((st = ss_keys(diag, root, "$", keys)) != WR_OK) goto done;
    if ((st = ss_str(diag, root, "name", "$", sc->name, sizeof sc->name, 0, NULL)) != WR_OK) goto done;
    if (!(o = cJSON_GetObjectItemCaseSensitive(root, "cloth"))) {
        st = ss_err(diag, "$.cloth", "is required");
        goto done;
    }
    if ((st = ss_parse_cloth(diag, o, base_dir, &sc->cloth)) != WR_OK) goto done;
    if ((o = cJSON_GetObjectItemCaseSensitive(root, "obstacles")) && (st = ss_parse_obstacles(diag, o, sc)) != WR_OK)
        goto done;
    st = ss_parse_settings(diag, root, sc);
done:
    cJSON_Delete(root);
    if (st != WR_OK) wr_simscene_free(sc);
    return st;
}

wr_status wr_simscene_load(wr_simscene *sc, const char *path, wr_diag *diag) {
    char *text = NULL, dir[WR_SIMSCENE_PATH_LEN];
    const char *slash;
    size_t len = 0;
    wr_status st;
    wr_simscene_defaults(sc);
    if ((st = wr_file_read(path, &text, &len, diag)) != WR_OK) return st;
    slash = strrchr(path, '/');
    if (slash && (size_t)(slash - path) < sizeof dir) {
        memcpy(dir, path, (size_t)(slash - path));
        dir[slash - path] = 0;
    } else {
        dir[0] = 0;
    }
    st = wr_simscene_parse(sc, text, len, dir, diag);
    wr_free(text);
    return st;
}

/* ---- run -------------------------------------------------------------------------------------- */

static wr_status ss_build_mesh(const wr_simscene_cloth *c, wr_mesh *m, wr_diag *diag) {
    wr_status st;
    if (c->kind == WR_SIMSCENE_MESH_RECTANGLE)
        st = wr_mesh_rectangle(m, c->width, c->height, c->nx, c->ny, diag);
    else if (c->kind == WR_SIMSCENE_MESH_DISK)
        st = wr_mesh_disk(m, c->radius, c->nx, diag);
    else
        st = wr_mesh_read_obj(m, c->path, diag);
    if (st == WR_OK && m->nv > WR_SIMSCENE_MAX_VERTICES) {
        wr_mesh_free(m);
        return wr_fail(diag, WR_ERR_BUDGET, -1, "$.cloth.mesh: %d vertices exceed %d", (int)m->nv, WR_SIMSCENE_MAX_VERTICES);
    }
    return st;
}

/* Placement: x ← R(axis, angle)·x + translate (Rodrigues). */
static void ss_place(const wr_simscene_cloth *c, double *pos, int32_t nv) {
    double a[3] = {c->rotate_axis[0], c->rotate_axis[1], c->rotate_axis[2]}, l, cs, sn, R[9];
    int32_t v;
    int i, j;
    l = sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
    if (l > 0.0) {
        for (i = 0; i < 3; ++i) a[i] /= l;
    } else {
        a[2] = 1.0;
    }
    cs = cos(c->rotate_angle);
    sn = sin(c->rotate_angle);
    for (i = 0; i < 3; ++i)
        for (j = 0; j < 3; ++j) R[3 * i + j] = (i == j ? cs : 0.0) + (1.0 - cs) * a[i] * a[j];
    R[1] -= sn * a[2], R[2] += sn * a[1], R[3] += sn * a[2], R[5] -= sn * a[0], R[6] -= sn * a[1], R[7] += sn * a[0];
    for (v = 0; v < nv; ++v) {
        double p[3];
        for (i = 0; i < 3; ++i) p[i] = R[3 * i] * pos[3 * v] + R[3 * i + 1] * pos[3 * v + 1] + R[3 * i + 2] * pos[3 * v + 2];
        for (i = 0; i < 3; ++i) pos[3 * v + i] = p[i] + c->translate[i];
    }
}

static wr_status ss_pins(wr_simscene_run *run, wr_diag *diag) {
    const wr_simscene_cloth *c = &run->sc->cloth;
    int32_t k, v, i;
    for (k = 0; k < c->n_pins; ++k) {
        const wr_simscene_pin *p = c->pin + k;
        int32_t hit = 0;
        if (p->select_box) {
            for (v = 0; v < run->mesh.nv; ++v) {
                const double *x = run->mesh.pos + 3 * v;
                if (x[0] >= p->lo[0] && x[0] <= p->hi[0] && x[1] >= p->lo[1] && x[1] <= p->hi[1] && x[2] >= p->lo[2] &&
                    x[2] <= p->hi[2])
                    run->fixed[v] = 1, hit++;
            }
        } else {
            for (i = 0; i < p->n_indices; ++i) {
                if (p->indices[i] >= run->mesh.nv)
                    return wr_fail(diag, WR_ERR_PARSE, k, "$.cloth.pins[%d].indices[%d]: vertex %d >= vertex count %d",
                                   (int)k, (int)i, (int)p->indices[i], (int)run->mesh.nv);
                run->fixed[p->indices[i]] = 1, hit++;
            }
        }
        if (!hit) return wr_fail(diag, WR_ERR_PARSE, k, "$.cloth.pins[%d]: selects no vertex", (int)k);
    }
    for (v = 0; v < run->mesh.nv; ++v) run->n_fixed += run->fixed[v];
    return WR_OK;
}

void wr_simscene_run_free(wr_simscene_run *run) {
    if (!run) return;
    wr_dyn_free(&run->sim);
    wr_shell_free(&run->shell);
    wr_mesh_free(&run->mesh);
    wr_free(run->fixed);
    wr_free(run->x);
    wr_free(run->v);
    wr_free(run->frames);
    memset(run, 0, sizeof *run);
}

wr_status wr_simscene_run_create(wr_simscene_run *run, const wr_simscene *sc, wr_diag *diag) {
    const wr_simscene_cloth *c = &sc->cloth;
    wr_dyn_desc dd;
    wr_status st;
    double t0 = wr_time_seconds();
    int32_t i;
    memset(run, 0, sizeof *run);
    run->sc = sc;
    if ((st = ss_build_mesh(c, &run->mesh, diag)) != WR_OK) goto fail;
    if ((st = wr_shell_create(&run->shell, &run->mesh, &c->shell, diag)) != WR_OK) goto fail;
    ss_place(c, run->mesh.pos, run->mesh.nv);
    run->fixed = (uint8_t *)wr_calloc_array((size_t)run->mesh.nv, 1);
    run->x = (double *)wr_alloc_array(3 * (size_t)run->mesh.nv, sizeof(double));
    run->v = (double *)wr_alloc_array(3 * (size_t)run->mesh.nv, sizeof(double));
    run->n_frames_max = (int32_t)ceil(sc->duration / sc->dyn.time.dt - 1e-9) + 1;
    run->frames = (wr_simscene_frame *)wr_calloc_array((size_t)run->n_frames_max, sizeof(wr_simscene_frame));
    if (!run->fixed || !run->x || !run->v || !run->frames) {
        st = wr_fail(diag, WR_ERR_NOMEM, -1, "out of memory (%d vertices)", (int)run->mesh.nv);
        goto fail;
    }
    if ((st = ss_pins(run, diag)) != WR_OK) goto fail;
    memcpy(run->x, run->mesh.pos, sizeof(double) * 3 * (size_t)run->mesh.nv);
    for (i = 0; i < 3 * run->mesh.nv; ++i) run->v[i] = run->fixed[i / 3] ? 0.0 : c->velocity[i % 3];
    dd = sc->dyn;
    dd.fixed = run->fixed;
    dd.contact.analytic = sc->analytic;
    dd.contact.n_analytic = sc->n_analytic;
    if ((st = wr_dyn_create(&run->sim, &run->shell, &dd, diag)) != WR_OK) goto fail;
    wr_dyn_state_init(&run->sim, &run->state, run->x, run->v);
    run->t_setup = wr_time_seconds() - t0;
    return WR_OK;
fail:
    wr_simscene_run_free(run);
    return st;
}

wr_status wr_simscene_run_frames(wr_simscene_run *run, wr_simscene_frame_fn fn, void *user, wr_diag *diag) {
    const wr_simscene *sc = run->sc;
    double t0 = wr_time_seconds();
    wr_status st = WR_OK;
    run->n_frames = 0;
    run->status = WR_OK;
    while (run->n_frames + 1 < run->n_frames_max) {
        wr_dyn_stats fs;
        wr_simscene_frame *f = run->frames + run->n_frames + 1;
        st = wr_dyn_step(&run->sim, &run->state, &fs, diag);
        if (st != WR_OK) {
            run->status = st;
            snprintf(run->status_message, sizeof run->status_message, "frame %d: %s", (int)(run->n_frames + 1),
                     diag ? diag->message : wr_status_text(st));
            break;
        }
        run->n_frames++;
        f->t = run->state.t;
        f->t_ns = fs.t_ns;
        f->t_ch = fs.t_ch;
        f->t_total = fs.t_total;
        f->residual_rel = fs.residual_rel;
        f->min_distance = fs.min_distance;
        f->h_min = fs.h_min;
        f->newton = fs.newton_iterations;
        f->pcg = fs.linear_iterations;
        f->line_search = fs.line_search_evals;
        f->contacts = fs.n_contacts;
        f->halvings = fs.halvings;
        f->steps = fs.steps;
        f->stop = fs.stop;
        if (fn && fn(user, run, run->n_frames)) break;
    }
    (void)sc;
    run->t_run = wr_time_seconds() - t0;
    return st;
}

void wr_simscene_frame_name(const wr_simscene *sc, int32_t k, char *out) {
    snprintf(out, 32, "frame_%04d.%s", (int)k, sc->output_ply ? "ply" : "obj");
}

wr_status wr_simscene_write_frame(const wr_simscene_run *run, const char *dir, int32_t k, wr_diag *diag) {
    char name[32], path[WR_PATH_MAX];
    wr_mesh m = run->mesh;
    wr_simscene_frame_name(run->sc, k, name);
    if ((size_t)snprintf(path, sizeof path, "%s/%s", dir, name) >= sizeof path)
        return wr_fail(diag, WR_ERR_IO, -1, "output path too long: %s/%s", dir, name);
    m.pos = run->x; /* a shallow view: the mesh's topology with the current positions */
    if (run->sc->output_ply) return wr_mesh_write_ply(&m, path, 0, NULL, NULL, diag);
    return wr_mesh_write_obj(&m, path, NULL, diag);
}

static double ss_median(double *a, int32_t n) {
    int32_t i, j;
    if (n <= 0) return 0.0;
    for (i = 1; i < n; ++i) /* insertion sort: n is the frame count */
        for (j = i; j > 0 && a[j - 1] > a[j]; --j) {
            double t = a[j];
            a[j] = a[j - 1];
            a[j - 1] = t;
        }
    return n % 2 ? a[n / 2] : 0.5 * (a[n / 2 - 1] + a[n / 2]);
}

wr_status wr_simscene_write_summary(const wr_simscene_run *run, const char *path, wr_diag *diag) {
    cJSON *root = cJSON_CreateObject(), *fr, *tot;
    double *tmp = (double *)wr_alloc_array((size_t)run->n_frames + 1, sizeof(double)), sns = 0, sch = 0, dmin = HUGE_VAL;
    int32_t k, nn = 0, np = 0;
    wr_status st;
    if (!root || !tmp) {
        cJSON_Delete(root);
        wr_free(tmp);
        return wr_fail(diag, WR_ERR_NOMEM, -1, "summary: out of memory");
    }
    cJSON_AddStringToObject(root, "name", run->sc->name);
    cJSON_AddStringToObject(root, "status", wr_status_string(run->status));
    if (run->status != WR_OK) cJSON_AddStringToObject(root, "status_message", run->status_message);
    cJSON_AddNumberToObject(root, "vertices", run->mesh.nv);
    cJSON_AddNumberToObject(root, "faces", run->mesh.nf);
    cJSON_AddNumberToObject(root, "pinned", run->n_fixed);
    cJSON_AddNumberToObject(root, "dt", run->sim.desc.time.dt);
    cJSON_AddNumberToObject(root, "substeps", run->sim.desc.time.substeps);
    cJSON_AddStringToObject(root, "linear", wr_solver_method_name(run->sim.desc.linear.method));
    cJSON_AddNumberToObject(root, "linear_tol", run->sim.desc.linear.rel_tol);
    cJSON_AddNumberToObject(root, "contact_dhat", run->sim.dhat);
    cJSON_AddNumberToObject(root, "contact_stiffness", run->sim.kappa);
    cJSON_AddNumberToObject(root, "frames", run->n_frames);
    cJSON_AddNumberToObject(root, "setup_seconds", run->t_setup);
    cJSON_AddNumberToObject(root, "run_seconds", run->t_run);
    fr = cJSON_AddArrayToObject(root, "per_frame");
    for (k = 1; k <= run->n_frames; ++k) {
        const wr_simscene_frame *f = run->frames + k;
        cJSON *o = cJSON_CreateObject();
        cJSON_AddNumberToObject(o, "t", f->t);
        cJSON_AddNumberToObject(o, "ns_ms", 1e3 * f->t_ns);
        cJSON_AddNumberToObject(o, "ch_ms", 1e3 * f->t_ch);
        cJSON_AddNumberToObject(o, "total_ms", 1e3 * f->t_total);
        cJSON_AddNumberToObject(o, "newton", f->newton);
        cJSON_AddNumberToObject(o, "pcg", f->pcg);
        cJSON_AddNumberToObject(o, "line_search", f->line_search);
        cJSON_AddNumberToObject(o, "steps", f->steps);
        cJSON_AddNumberToObject(o, "halvings", f->halvings);
        cJSON_AddNumberToObject(o, "contacts", f->contacts);
        if (f->min_distance < HUGE_VAL) cJSON_AddNumberToObject(o, "min_distance", f->min_distance);
        else cJSON_AddNullToObject(o, "min_distance");
        cJSON_AddNumberToObject(o, "residual_rel", f->residual_rel);
        cJSON_AddStringToObject(o, "stop", wr_newton_stop_name(f->stop));
        cJSON_AddItemToArray(fr, o);
        sns += f->t_ns;
        sch += f->t_ch;
        nn += f->newton;
        np += f->pcg;
        dmin = fmin(dmin, f->min_distance);
    }
    tot = cJSON_AddObjectToObject(root, "totals");
    cJSON_AddNumberToObject(tot, "ns_ms", 1e3 * sns);
    cJSON_AddNumberToObject(tot, "ch_ms", 1e3 * sch);
    cJSON_AddNumberToObject(tot, "newton", nn);
    cJSON_AddNumberToObject(tot, "pcg", np);
    if (dmin < HUGE_VAL) cJSON_AddNumberToObject(tot, "min_distance", dmin);
    else cJSON_AddNullToObject(tot, "min_distance");
    for (k = 1; k <= run->n_frames; ++k) tmp[k - 1] = run->frames[k].t_ns;
    cJSON_AddNumberToObject(tot, "median_ns_ms", 1e3 * ss_median(tmp, run->n_frames));
    for (k = 1; k <= run->n_frames; ++k) tmp[k - 1] = run->frames[k].t_ch;
    cJSON_AddNumberToObject(tot, "median_ch_ms", 1e3 * ss_median(tmp, run->n_frames));
    st = wr_json_write(root, path, diag);
    cJSON_Delete(root);
    wr_free(tmp);
    return st;
}
