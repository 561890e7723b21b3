/* scene.c — see scene.h and docs/scene-format.md. Uses cJSON (Debian libcjson-dev). */
#define _POSIX_C_SOURCE 200809L
#include "scene.h"
#include "jsonin.h"

#include "jsonout.h"

#include <cjson/cJSON.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#define SC_PI 3.14159265358979323846
/* Largest mesh a scene may request from a generator: keeps a typo ("resolution": 1e-6) from
 * allocating gigabytes before anything is solved. 2e6 vertices is ~20× the benchmark's top size. */
#define SC_MAX_VERTICES 2000000
/* Hybrid Newton: gradient, relative to the scene's force scale G (see wr_scene_run_solve), at which the
 * projected phase hands over to the exact Hessian. 1e-3: past the saddle-escape phase, far from the
 * final tolerance. */
#define SC_HYBRID_SWITCH 1e-3

/* ---------------------------------------------------------------------------------------------- */
/* parsing helpers: every error names the JSON path (declared in jsonin.h, shared with simscene.c) */

wr_status wr_jin_err(wr_jin *c, const char *path, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 3, 4)))
#endif
    ;
wr_status wr_jin_err(wr_jin *c, const char *path, const char *fmt, ...) {
    char msg[400], full[WR_DIAG_MESSAGE_LEN], line[WR_DIAG_MESSAGE_LEN];
    size_t i, o = 0;
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    snprintf(full, sizeof full, "%s: %s", path, msg);
    /* Paths and messages quote the file's own keys and strings, which may hold control characters:
     * show them as \xHH so the message stays one line (wr_diag contract; fuzzer finding
     * tests/regressions/scene_newline_in_key.fuzz_scene). */
    for (i = 0; full[i] && o + 5 < sizeof line; ++i) {
        unsigned char ch = (unsigned char)full[i];
        if (ch < 0x20 || ch == 0x7f) o += (size_t)snprintf(line + o, sizeof line - o, "\\x%02x", ch);
        else line[o++] = (char)ch;
    }
    line[o] = 0;
    return wr_fail(c->diag, WR_ERR_PARSE, -1, "%s", line);
}

void wr_jin_path(char *out, size_t n, const char *base, const char *key) { snprintf(out, n, "%s.%s", base, key); }

/* Reject keys not in the list (a typo must not silently fall back to a default). */
wr_status wr_jin_keys(wr_jin *c, const cJSON *obj, const char *path, const char *const *allowed) {
    const cJSON *it;
    if (!cJSON_IsObject(obj)) return wr_jin_err(c, path, "must be an object");
    for (it = obj->child; it; it = it->next) {
        const char *const *a;
        int ok = 0;
        for (a = allowed; *a; ++a)
            if (strcmp(*a, it->string) == 0) ok = 1;
        if (!ok) {
            char p[512];
            wr_jin_path(p, sizeof p, path, it->string);
            return wr_jin_err(c, p, "unknown key");
        }
    }
    return WR_OK;
}

/* Optional number: *found = 0 when absent. rule: WR_JIN_ANY finite, WR_JIN_POS > 0, WR_JIN_NONNEG >= 0. */
wr_status wr_jin_num(wr_jin *c, const cJSON *obj, const char *key, const char *path, int rule, double *out,
                        int *found) {
    const cJSON *v = cJSON_GetObjectItemCaseSensitive(obj, key);
    char p[512];
    if (found) *found = 0;
    if (!v) return WR_OK;
    wr_jin_path(p, sizeof p, path, key);
    if (!cJSON_IsNumber(v) || !isfinite(v->valuedouble)) return wr_jin_err(c, p, "must be a finite number");
    if (rule == WR_JIN_POS && !(v->valuedouble > 0.0)) return wr_jin_err(c, p, "must be > 0 (got %g)", v->valuedouble);
    if (rule == WR_JIN_NONNEG && !(v->valuedouble >= 0.0)) return wr_jin_err(c, p, "must be >= 0 (got %g)", v->valuedouble);
    *out = v->valuedouble;
    if (found) *found = 1;
    return WR_OK;
}

wr_status wr_jin_int(wr_jin *c, const cJSON *obj, const char *key, const char *path, long lo, long hi,
                        int32_t *out, int *found) {
    const cJSON *v = cJSON_GetObjectItemCaseSensitive(obj, key);
    char p[512];
    if (found) *found = 0;
    if (!v) return WR_OK;
    wr_jin_path(p, sizeof p, path, key);
    if (!cJSON_IsNumber(v) || v->valuedouble != floor(v->valuedouble) || v->valuedouble < (double)lo ||
        v->valuedouble > (double)hi)
        return wr_jin_err(c, p, "must be an integer in [%ld, %ld]", lo, hi);
    *out = (int32_t)v->valuedouble;
    if (found) *found = 1;
    return WR_OK;
}

wr_status wr_jin_vec(wr_jin *c, const cJSON *obj, const char *key, const char *path, int n, double *out,
                        int *found) {
    const cJSON *v = cJSON_GetObjectItemCaseSensitive(obj, key), *e;
    char p[512];
    int i = 0;
    if (found) *found = 0;
    if (!v) return WR_OK;
    wr_jin_path(p, sizeof p, path, key);
    if (!cJSON_IsArray(v) || cJSON_GetArraySize(v) != n) return wr_jin_err(c, p, "must be an array of %d numbers", n);
    for (e = v->child; e; e = e->next, ++i) {
        if (!cJSON_IsNumber(e) || !isfinite(e->valuedouble)) {
            char q[540];
            snprintf(q, sizeof q, "%s[%d]", p, i);
            return wr_jin_err(c, q, "must be a finite number");
        }
        out[i] = e->valuedouble;
    }
    if (found) *found = 1;
    return WR_OK;
}

wr_status wr_jin_bool(wr_jin *c, const cJSON *obj, const char *key, const char *path, int *out) {
    const cJSON *v = cJSON_GetObjectItemCaseSensitive(obj, key);
    char p[512];
    if (!v) return WR_OK;
    wr_jin_path(p, sizeof p, path, key);
    if (!cJSON_IsBool(v)) return wr_jin_err(c, p, "must be true or false");
    *out = cJSON_IsTrue(v) ? 1 : 0;
    return WR_OK;
}

/* String choice: index into names (NULL-terminated), *out unchanged when absent. */
wr_status wr_jin_enum(wr_jin *c, const cJSON *obj, const char *key, const char *path, const char *const *names,
                         int *out, int required) {
    const cJSON *v = cJSON_GetObjectItemCaseSensitive(obj, key);
    char p[512], list[256];
    int i;
    wr_jin_path(p, sizeof p, path, key);
    if (!v) return required ? wr_jin_err(c, p, "is required") : WR_OK;
    list[0] = 0;
    for (i = 0; names[i]; ++i) {
        if (cJSON_IsString(v) && strcmp(v->valuestring, names[i]) == 0) {
            *out = i;
            return WR_OK;
        }
        strncat(list, i ? ", " : "", sizeof list - strlen(list) - 1);
        strncat(list, names[i], sizeof list - strlen(list) - 1);
    }
    return wr_jin_err(c, p, "must be one of: %s", list);
}

wr_status wr_jin_str(wr_jin *c, const cJSON *obj, const char *key, const char *path, char *out, size_t cap,
                        int required) {
    const cJSON *v = cJSON_GetObjectItemCaseSensitive(obj, key);
    char p[512];
    wr_jin_path(p, sizeof p, path, key);
    if (!v) return required ? wr_jin_err(c, p, "is required") : WR_OK;
    if (!cJSON_IsString(v) || v->valuestring[0] == 0) return wr_jin_err(c, p, "must be a non-empty string");
    if (strlen(v->valuestring) >= cap) return wr_jin_err(c, p, "longer than %d characters", (int)cap - 1);
    strcpy(out, v->valuestring);
    return WR_OK;
}

static const char *const SC_MESH_TYPES[] = {"obj", "rectangle", "disk", "cylinder", "delaunay_rectangle", "lattice", NULL};
static const char *const SC_MEMBRANES[] = {"stvk", "tft", "none", NULL};
static const char *const SC_BENDINGS[] = {"midedge", "quadratic", "none", NULL};
static const char *const SC_ELEMENTS[] = {"linear", "loop", NULL}; /* shell.h ON THE LOOP ELEMENT */
static const char *const SC_LINEAR[] = {"auto", "pcg-jacobi", "pcg-block3", "pcg-ic0", "cholmod", "pcg-amg", NULL};
static const char *const SC_HESSIAN[] = {"exact", "projected", "hybrid", NULL};

const char *wr_scene_mesh_kind_name(wr_scene_mesh_kind k) {
    return (k >= WR_SCENE_MESH_OBJ && k <= WR_SCENE_MESH_LATTICE) ? SC_MESH_TYPES[k] : "?";
}

void wr_scene_defaults(wr_scene *sc) {
    int i;
    memset(sc, 0, sizeof *sc);
    strcpy(sc->name, "scene");
    sc->ramp_gravity = 1;
    sc->linear = WR_SOLVER_AUTO;
    sc->load_steps = 1;
    sc->hessian = WR_SCENE_HESSIAN_EXACT;
    for (i = 0; i < WR_SCENE_MAX_BC; ++i) sc->bc[i].stretch[0] = sc->bc[i].stretch[1] = sc->bc[i].stretch[2] = 1.0;
}

void wr_scene_free(wr_scene *sc) {
    int32_t i;
    if (!sc) return;
    for (i = 0; i < WR_SCENE_MAX_BC; ++i) {
        free(sc->bc[i].indices);
        sc->bc[i].indices = NULL;
        sc->bc[i].n_indices = 0;
    }
}

/* the file path at key "path" of o (JSON path P), relative to the scene's directory unless absolute */
static wr_status sc_parse_path(wr_jin *c, const cJSON *o, const char *P, const char *base_dir, char *out, size_t cap) {
    char rel[WR_SCENE_PATH_LEN], q[160];
    wr_status st;
    size_t lb, lr;
    rel[0] = 0;
    if ((st = wr_jin_str(c, o, "path", P, rel, sizeof rel, 1)) != WR_OK) return st;
    if (rel[0] == '/' || !base_dir || !base_dir[0]) {
        snprintf(out, cap, "%s", rel);
        return WR_OK;
    }
    lb = strlen(base_dir), lr = strlen(rel);
    wr_jin_path(q, sizeof q, P, "path");
    if (lb + lr + 2 > cap) return wr_jin_err(c, q, "resolved path too long");
    memcpy(out, base_dir, lb);
    out[lb] = '/';
    memcpy(out + lb + 1, rel, lr + 1);
    return WR_OK;
}

static wr_status sc_parse_mesh(wr_jin *c, const cJSON *o, const char *base_dir, wr_scene_mesh *m) {
    static const char *const keys[] = {"type", "path", "width", "height", "radius", "resolution", "nx", "ny",
                                       "seed", "pillow", "angle", "weld", NULL};
    const char *P = "$.mesh";
    wr_status st;
    int kind = 0, fw = 0, fh = 0, fr = 0, fres = 0, fnx = 0, fny = 0, fs = 0, fp = 0, fa = 0;
    int32_t seed = 0;
    if ((st = wr_jin_keys(c, o, P, keys)) != WR_OK) return st;
    if ((st = wr_jin_enum(c, o, "type", P, SC_MESH_TYPES, &kind, 1)) != WR_OK) return st;
    m->kind = (wr_scene_mesh_kind)kind;
    if ((st = wr_jin_num(c, o, "width", P, WR_JIN_POS, &m->width, &fw)) != WR_OK) return st;
    if ((st = wr_jin_num(c, o, "height", P, WR_JIN_POS, &m->height, &fh)) != WR_OK) return st;
    if ((st = wr_jin_num(c, o, "radius", P, WR_JIN_POS, &m->radius, &fr)) != WR_OK) return st;
    if ((st = wr_jin_num(c, o, "resolution", P, WR_JIN_POS, &m->resolution, &fres)) != WR_OK) return st;
    if ((st = wr_jin_int(c, o, "nx", P, 1, 100000, &m->nx, &fnx)) != WR_OK) return st;
    if ((st = wr_jin_int(c, o, "ny", P, 1, 100000, &m->ny, &fny)) != WR_OK) return st;
    if ((st = wr_jin_int(c, o, "seed", P, 0, 2147483647L, &seed, &fs)) != WR_OK) return st;
    m->seed = (uint64_t)seed;
    if ((st = wr_jin_num(c, o, "pillow", P, WR_JIN_POS, &m->pillow_lift, &fp)) != WR_OK) return st;
    if ((st = wr_jin_num(c, o, "angle", P, WR_JIN_ANY, &m->angle_deg, &fa)) != WR_OK) return st;
    if (fa && m->kind != WR_SCENE_MESH_LATTICE) return wr_jin_err(c, "$.mesh.angle", "only for type lattice");
    if ((st = wr_jin_num(c, o, "weld", P, WR_JIN_NONNEG, &m->weld_tol, &m->has_weld)) != WR_OK) return st;
    if (m->has_weld && m->kind != WR_SCENE_MESH_OBJ) return wr_jin_err(c, "$.mesh.weld", "only for type obj");
    /* a pillow doubles a flat panel with a boundary (statics.h ON PRESSURE needs a closed surface) */
    if (fp && m->kind != WR_SCENE_MESH_RECTANGLE && m->kind != WR_SCENE_MESH_DISK &&
        m->kind != WR_SCENE_MESH_DELAUNAY_RECTANGLE)
        return wr_jin_err(c, "$.mesh.pillow", "needs a flat panel: type rectangle, disk or delaunay_rectangle");
    switch (m->kind) {
    case WR_SCENE_MESH_OBJ:
        return sc_parse_path(c, o, P, base_dir, m->path, sizeof m->path);
    case WR_SCENE_MESH_RECTANGLE:
    case WR_SCENE_MESH_DELAUNAY_RECTANGLE:
    case WR_SCENE_MESH_LATTICE:
        if (!fw) return wr_jin_err(c, "$.mesh.width", "is required for type %s", SC_MESH_TYPES[kind]);
        if (!fh) return wr_jin_err(c, "$.mesh.height", "is required for type %s", SC_MESH_TYPES[kind]);
        if (m->kind == WR_SCENE_MESH_RECTANGLE && (fnx || fny)) {
            if (!(fnx && fny)) return wr_jin_err(c, fnx ? "$.mesh.ny" : "$.mesh.nx", "nx and ny go together");
            return WR_OK;
        }
        break;
    case WR_SCENE_MESH_DISK:
        if (!fr) return wr_jin_err(c, "$.mesh.radius", "is required for type disk");
        break;
    case WR_SCENE_MESH_CYLINDER:
        if (!fr) return wr_jin_err(c, "$.mesh.radius", "is required for type cylinder");
        if (!fh) return wr_jin_err(c, "$.mesh.height", "is required for type cylinder");
        break;
    }
    if (!fres) return wr_jin_err(c, "$.mesh.resolution", "is required for type %s", SC_MESH_TYPES[kind]);
    return WR_OK;
}

static wr_status sc_parse_material(wr_jin *c, const cJSON *o, wr_scene *sc) {
    static const char *const keys[] = {"young", "poisson", "thickness", "bending_stiffness", "density",
                                       "areal_density", "orthotropic", NULL};
    static const char *const okeys[] = {"young_warp", "young_weft", "shear_modulus", "poisson_warp", NULL};
    const char *P = "$.material";
    wr_shell_desc *d = &sc->shell;
    wr_status st;
    int fE = 0, fh = 0, fB = 0, fd = 0, fa = 0, fnu = 0;
    const cJSON *orth;
    if ((st = wr_jin_keys(c, o, P, keys)) != WR_OK) return st;
    if ((st = wr_jin_num(c, o, "young", P, WR_JIN_POS, &d->young, &fE)) != WR_OK) return st;
    if ((st = wr_jin_num(c, o, "poisson", P, WR_JIN_ANY, &d->poisson, &fnu)) != WR_OK) return st;
    if (fnu && !(d->poisson > -1.0 && d->poisson <= 0.5))
        return wr_jin_err(c, "$.material.poisson", "must be in (-1, 0.5] (got %g)", d->poisson);
    if ((st = wr_jin_num(c, o, "thickness", P, WR_JIN_POS, &d->thickness, &fh)) != WR_OK) return st;
    if ((st = wr_jin_num(c, o, "bending_stiffness", P, WR_JIN_POS, &d->bending_stiffness, &fB)) != WR_OK) return st;
    if ((st = wr_jin_num(c, o, "density", P, WR_JIN_NONNEG, &d->density, &fd)) != WR_OK) return st;
    if ((st = wr_jin_num(c, o, "areal_density", P, WR_JIN_NONNEG, &sc->areal_density, &fa)) != WR_OK) return st;
    if (!fE) return wr_jin_err(c, "$.material.young", "is required");
    if (!fh && !fB) return wr_jin_err(c, "$.material", "needs thickness or bending_stiffness");
    if (fd && fa) return wr_jin_err(c, "$.material.areal_density", "give density or areal_density, not both");
    if (!fh) /* Kirchhoff–Love (Style3D Sec. 4.1.1): B = E h³/(12(1−ν²)) solved for h */
        d->thickness = cbrt(12.0 * (1.0 - d->poisson * d->poisson) * d->bending_stiffness / d->young);
    if (fa) d->density = sc->areal_density / d->thickness;
    orth = cJSON_GetObjectItemCaseSensitive(o, "orthotropic");
    if (orth) {
        const char *Q = "$.material.orthotropic";
        int f1 = 0, f2 = 0, f3 = 0;
        if ((st = wr_jin_keys(c, orth, Q, okeys)) != WR_OK) return st;
        if ((st = wr_jin_num(c, orth, "young_warp", Q, WR_JIN_POS, &d->young_warp, &f1)) != WR_OK) return st;
        if ((st = wr_jin_num(c, orth, "young_weft", Q, WR_JIN_POS, &d->young_weft, &f2)) != WR_OK) return st;
        if ((st = wr_jin_num(c, orth, "shear_modulus", Q, WR_JIN_POS, &d->shear_modulus, &f3)) != WR_OK) return st;
        if ((st = wr_jin_num(c, orth, "poisson_warp", Q, WR_JIN_ANY, &d->poisson_warp, NULL)) != WR_OK) return st;
        if (!f1 || !f2 || !f3)
            return wr_jin_err(c, Q, "needs young_warp, young_weft and shear_modulus");
        d->orthotropic = 1;
    }
    return WR_OK;
}

static wr_status sc_parse_bc(wr_jin *c, const cJSON *o, const char *P, wr_scene_bc *b) {
    static const char *const keys[] = {"name", "box", "indices", "center", "translate", "stretch", "shear", "twist",
                                       "wave", NULL};
    static const char *const bkeys[] = {"min", "max", NULL};
    static const char *const tkeys[] = {"axis", "angle", NULL};
    static const char *const wkeys[] = {"amplitude", "wavelength", "phase", "along", "dir", NULL};
    const cJSON *box, *idx, *tw, *wv;
    char p[512];
    wr_status st;
    int f = 0, i;
    if ((st = wr_jin_keys(c, o, P, keys)) != WR_OK) return st;
    if ((st = wr_jin_str(c, o, "name", P, b->name, sizeof b->name, 0)) != WR_OK) return st;
    box = cJSON_GetObjectItemCaseSensitive(o, "box");
    idx = cJSON_GetObjectItemCaseSensitive(o, "indices");
    if (!!box == !!idx) return wr_jin_err(c, P, "needs exactly one of box or indices");
    if (box) {
        int f1 = 0, f2 = 0;
        wr_jin_path(p, sizeof p, P, "box");
        if ((st = wr_jin_keys(c, box, p, bkeys)) != WR_OK) return st;
        if ((st = wr_jin_vec(c, box, "min", p, 3, b->box_lo, &f1)) != WR_OK) return st;
        if ((st = wr_jin_vec(c, box, "max", p, 3, b->box_hi, &f2)) != WR_OK) return st;
        if (!f1 || !f2) return wr_jin_err(c, p, "needs min and max");
        for (i = 0; i < 3; ++i)
            if (b->box_lo[i] > b->box_hi[i]) return wr_jin_err(c, p, "min[%d] > max[%d]", i, i);
        b->select = WR_SCENE_SELECT_BOX;
    } else {
        const cJSON *e;
        int n = cJSON_GetArraySize(idx);
        wr_jin_path(p, sizeof p, P, "indices");
        if (!cJSON_IsArray(idx) || n < 1) return wr_jin_err(c, p, "must be a non-empty array of vertex indices");
        b->indices = (int32_t *)malloc(sizeof(int32_t) * (size_t)n);
        if (!b->indices) return wr_fail(c->diag, WR_ERR_NOMEM, -1, "%s: out of memory", p);
        b->n_indices = n;
        i = 0;
        for (e = idx->child; e; e = e->next, ++i) {
            if (!cJSON_IsNumber(e) || e->valuedouble != floor(e->valuedouble) || e->valuedouble < 0 ||
                e->valuedouble > 2147483647.0) {
                char q[540];
                snprintf(q, sizeof q, "%s[%d]", p, i);
                return wr_jin_err(c, q, "must be a vertex index (integer >= 0)");
            }
            b->indices[i] = (int32_t)e->valuedouble;
        }
        b->select = WR_SCENE_SELECT_INDICES;
    }
    if ((st = wr_jin_vec(c, o, "center", P, 3, b->center, NULL)) != WR_OK) return st;
    if ((st = wr_jin_vec(c, o, "translate", P, 3, b->translate, NULL)) != WR_OK) return st;
    if ((st = wr_jin_vec(c, o, "stretch", P, 3, b->stretch, &f)) != WR_OK) return st;
    if (f)
        for (i = 0; i < 3; ++i)
            if (!(b->stretch[i] > 0.0)) {
                wr_jin_path(p, sizeof p, P, "stretch");
                return wr_jin_err(c, p, "scale factors must be > 0");
            }
    if ((st = wr_jin_vec(c, o, "shear", P, 3, b->shear, NULL)) != WR_OK) return st;
    tw = cJSON_GetObjectItemCaseSensitive(o, "twist");
    if (tw) {
        int fa = 0, fg = 0;
        wr_jin_path(p, sizeof p, P, "twist");
        if ((st = wr_jin_keys(c, tw, p, tkeys)) != WR_OK) return st;
        if ((st = wr_jin_vec(c, tw, "axis", p, 3, b->twist_axis, &fa)) != WR_OK) return st;
        if ((st = wr_jin_num(c, tw, "angle", p, WR_JIN_ANY, &b->twist_angle, &fg)) != WR_OK) return st;
        if (!fa || !fg) return wr_jin_err(c, p, "needs axis and angle");
        if (!(fabs(b->twist_axis[0]) + fabs(b->twist_axis[1]) + fabs(b->twist_axis[2]) > 0.0))
            return wr_jin_err(c, p, "axis must be nonzero");
    }
    wv = cJSON_GetObjectItemCaseSensitive(o, "wave");
    if (wv) {
        int fa = 0, fl = 0, f1 = 0, f2 = 0;
        wr_jin_path(p, sizeof p, P, "wave");
        if ((st = wr_jin_keys(c, wv, p, wkeys)) != WR_OK) return st;
        if ((st = wr_jin_num(c, wv, "amplitude", p, WR_JIN_ANY, &b->wave_amplitude, &fa)) != WR_OK) return st;
        if ((st = wr_jin_num(c, wv, "wavelength", p, WR_JIN_POS, &b->wave_length, &fl)) != WR_OK) return st;
        if ((st = wr_jin_num(c, wv, "phase", p, WR_JIN_ANY, &b->wave_phase, NULL)) != WR_OK) return st;
        if ((st = wr_jin_vec(c, wv, "along", p, 3, b->wave_along, &f1)) != WR_OK) return st;
        if ((st = wr_jin_vec(c, wv, "dir", p, 3, b->wave_dir, &f2)) != WR_OK) return st;
        if (!fa || !fl || !f1 || !f2) return wr_jin_err(c, p, "needs amplitude, wavelength, along and dir");
    }
    return WR_OK;
}

static wr_status sc_parse_solver(wr_jin *c, const cJSON *o, wr_scene *sc) {
    static const char *const keys[] = {"linear", "linear_tol", "grad_tol", "max_iter", "load_steps", "perturb",
                                       "seed", "hessian", NULL};
    const char *P = "$.solver";
    wr_status st;
    int lin = (int)sc->linear, hes = (int)sc->hessian;
    int32_t seed = 0;
    int fs = 0;
    if ((st = wr_jin_keys(c, o, P, keys)) != WR_OK) return st;
    if ((st = wr_jin_enum(c, o, "linear", P, SC_LINEAR, &lin, 0)) != WR_OK) return st;
    sc->linear = (wr_solver_method)lin;
    if ((st = wr_jin_enum(c, o, "hessian", P, SC_HESSIAN, &hes, 0)) != WR_OK) return st;
    sc->hessian = (wr_scene_hessian)hes;
    if ((st = wr_jin_num(c, o, "linear_tol", P, WR_JIN_POS, &sc->linear_tol, NULL)) != WR_OK) return st;
    if ((st = wr_jin_num(c, o, "grad_tol", P, WR_JIN_POS, &sc->grad_tol, NULL)) != WR_OK) return st;
    if ((st = wr_jin_int(c, o, "max_iter", P, 1, 1000000, &sc->max_iter, NULL)) != WR_OK) return st;
    if ((st = wr_jin_int(c, o, "load_steps", P, 1, 100000, &sc->load_steps, NULL)) != WR_OK) return st;
    if ((st = wr_jin_num(c, o, "perturb", P, WR_JIN_NONNEG, &sc->perturb, NULL)) != WR_OK) return st;
    if ((st = wr_jin_int(c, o, "seed", P, 0, 2147483647L, &seed, &fs)) != WR_OK) return st;
    if (fs) sc->seed = (uint64_t)seed;
    return WR_OK;
}

static wr_status sc_parse_probe(wr_jin *c, const cJSON *o, const char *P, wr_scene_probe *pr) {
    static const char *const keys[] = {"name", "from", "to", "samples", "dir", "closed", "panel", NULL};
    const cJSON *pn = cJSON_GetObjectItemCaseSensitive(o, "panel");
    wr_status st;
    int f1 = 0, f2 = 0, fd = 0;
    if ((st = wr_jin_keys(c, o, P, keys)) != WR_OK) return st;
    if ((st = wr_jin_str(c, o, "name", P, pr->name, sizeof pr->name, 0)) != WR_OK) return st;
    if ((st = wr_jin_vec(c, o, "from", P, 2, pr->from, &f1)) != WR_OK) return st;
    if ((st = wr_jin_vec(c, o, "to", P, 2, pr->to, &f2)) != WR_OK) return st;
    if (!f1 || !f2) return wr_jin_err(c, P, "needs from and to");
    if (pr->from[0] == pr->to[0] && pr->from[1] == pr->to[1]) return wr_jin_err(c, P, "from and to coincide");
    pr->samples = 512;
    if ((st = wr_jin_int(c, o, "samples", P, WR_SPECTRUM_MIN_SAMPLES, 1 << 22, &pr->samples, NULL)) != WR_OK) return st;
    pr->dir[2] = 1.0;
    if (cJSON_IsString(cJSON_GetObjectItemCaseSensitive(o, "dir"))) {
        char p[512], w[16];
        wr_jin_path(p, sizeof p, P, "dir");
        if (wr_jin_str(c, o, "dir", P, w, sizeof w, 0) != WR_OK || strcmp(w, "normal") != 0)
            return wr_jin_err(c, p, "must be [x, y, z] or \"normal\"");
        pr->dir_normal = 1;
    } else if ((st = wr_jin_vec(c, o, "dir", P, 3, pr->dir, &fd)) != WR_OK) return st;
    if (fd && !(fabs(pr->dir[0]) + fabs(pr->dir[1]) + fabs(pr->dir[2]) > 0.0)) {
        char p[512];
        wr_jin_path(p, sizeof p, P, "dir");
        return wr_jin_err(c, p, "must be nonzero");
    }
    if (pn) { /* an OBJ g/o name, or a panel id; resolved against the mesh in wr_scene_run_create */
        char p[512];
        pr->has_panel = 1;
        wr_jin_path(p, sizeof p, P, "panel");
        if (cJSON_IsString(pn)) {
            if ((st = wr_jin_str(c, o, "panel", P, pr->panel_name, sizeof pr->panel_name, 0)) != WR_OK) return st;
        } else if (!cJSON_IsNumber(pn)) {
            return wr_jin_err(c, p, "must be a panel name (OBJ g/o) or an integer panel id >= 0");
        } else if ((st = wr_jin_int(c, o, "panel", P, 0, INT32_MAX, &pr->panel_id, NULL)) != WR_OK) {
            return st;
        }
    }
    return wr_jin_bool(c, o, "closed", P, &pr->closed);
}

wr_status wr_jin_analytic_obstacle(wr_jin *c, const cJSON *e, const char *P, wr_obstacle *o) {
    int f1 = 0, f2 = 0, f3 = 0;
    wr_status st;
    if (o->kind == WR_OBSTACLE_PLANE) {
        if ((st = wr_jin_vec(c, e, "point", P, 3, o->p, &f1)) != WR_OK || (st = wr_jin_vec(c, e, "normal", P, 3, o->normal, &f2)) != WR_OK)
            return st;
        if (!f1 || !f2) return wr_jin_err(c, P, "plane needs point and normal");
        if (!(o->normal[0] * o->normal[0] + o->normal[1] * o->normal[1] + o->normal[2] * o->normal[2] > 0.0))
            return wr_jin_err(c, P, "plane normal must not be zero");
        return WR_OK;
    }
    if (o->kind == WR_OBSTACLE_SPHERE) {
        if ((st = wr_jin_vec(c, e, "center", P, 3, o->p, &f1)) != WR_OK || (st = wr_jin_num(c, e, "radius", P, WR_JIN_POS, &o->radius, &f2)) != WR_OK)
            return st;
        return f1 && f2 ? WR_OK : wr_jin_err(c, P, "sphere needs center and radius");
    }
    if ((st = wr_jin_vec(c, e, "p", P, 3, o->p, &f1)) != WR_OK || (st = wr_jin_vec(c, e, "q", P, 3, o->q, &f2)) != WR_OK ||
        (st = wr_jin_num(c, e, "radius", P, WR_JIN_POS, &o->radius, &f3)) != WR_OK)
        return st;
    return f1 && f2 && f3 ? WR_OK : wr_jin_err(c, P, "capsule needs p, q and radius");
}

static const char *const SC_OBSTACLES[] = {"plane", "sphere", "capsule", "obj", "mannequin", NULL};

/* $.obstacles[k] (P): the keys of its type, required ones present (docs/scene-format.md) */
static wr_status sc_parse_obstacle(wr_jin *c, const cJSON *e, const char *P, const char *base_dir, wr_scene_obstacle *ob) {
    static const char *const keys[5][6] = {{"type", "point", "normal", NULL},
                                           {"type", "center", "radius", NULL},
                                           {"type", "p", "q", "radius", NULL},
                                           {"type", "path", "translate", NULL},
                                           {"type", "height", "target_faces", "cell", "translate", NULL}};
    wr_obstacle *o = &ob->analytic;
    int kind = 0;
    wr_status st;
    if (!cJSON_IsObject(e)) return wr_jin_err(c, P, "must be an object");
    if ((st = wr_jin_enum(c, e, "type", P, SC_OBSTACLES, &kind, 1)) != WR_OK) return st;
    if ((st = wr_jin_keys(c, e, P, keys[kind])) != WR_OK) return st;
    ob->kind = (wr_scene_obstacle_kind)kind;
    switch (ob->kind) {
    case WR_SCENE_OBSTACLE_PLANE:
    case WR_SCENE_OBSTACLE_SPHERE:
    case WR_SCENE_OBSTACLE_CAPSULE:
        o->kind = ob->kind == WR_SCENE_OBSTACLE_PLANE ? WR_OBSTACLE_PLANE
                  : ob->kind == WR_SCENE_OBSTACLE_SPHERE ? WR_OBSTACLE_SPHERE
                                                        : WR_OBSTACLE_CAPSULE;
        return wr_jin_analytic_obstacle(c, e, P, o);
    case WR_SCENE_OBSTACLE_OBJ:
        o->kind = WR_OBSTACLE_MESH;
        if ((st = sc_parse_path(c, e, P, base_dir, ob->path, sizeof ob->path)) != WR_OK) return st;
        return wr_jin_vec(c, e, "translate", P, 3, ob->translate, NULL);
    default:
        o->kind = WR_OBSTACLE_MESH;
        if ((st = wr_jin_num(c, e, "height", P, WR_JIN_POS, &ob->body.height, NULL)) != WR_OK ||
            (st = wr_jin_int(c, e, "target_faces", P, WR_BODY_MIN_FACES, 2000000, &ob->body.target_faces, NULL)) != WR_OK ||
            (st = wr_jin_num(c, e, "cell", P, WR_JIN_POS, &ob->body.cell, NULL)) != WR_OK)
            return st;
        return wr_jin_vec(c, e, "translate", P, 3, ob->translate, NULL);
    }
}

/* $.obstacles (array, <= WR_SCENE_MAX_OBSTACLES) and $.contact {dhat, stiffness} */
static wr_status sc_parse_contact(wr_jin *c, const cJSON *root, const char *base_dir, wr_scene *sc) {
    static const char *const ckeys[] = {"dhat", "stiffness", NULL};
    const cJSON *o = cJSON_GetObjectItemCaseSensitive(root, "obstacles"), *e;
    wr_status st;
    int i;
    if (o) {
        if (!cJSON_IsArray(o)) return wr_jin_err(c, "$.obstacles", "must be an array");
        if (cJSON_GetArraySize(o) > WR_SCENE_MAX_OBSTACLES)
            return wr_jin_err(c, "$.obstacles", "more than %d obstacles", WR_SCENE_MAX_OBSTACLES);
        for (e = o->child, i = 0; e; e = e->next, ++i) {
            char p[64];
            snprintf(p, sizeof p, "$.obstacles[%d]", i);
            if ((st = sc_parse_obstacle(c, e, p, base_dir, &sc->obstacle[i])) != WR_OK) return st;
            sc->n_obstacles = i + 1;
        }
    }
    if (!(o = cJSON_GetObjectItemCaseSensitive(root, "contact"))) return WR_OK;
    if ((st = wr_jin_keys(c, o, "$.contact", ckeys)) != WR_OK) return st;
    if ((st = wr_jin_num(c, o, "dhat", "$.contact", WR_JIN_POS, &sc->contact_dhat, NULL)) != WR_OK) return st;
    return wr_jin_num(c, o, "stiffness", "$.contact", WR_JIN_POS, &sc->contact_stiffness, NULL);
}

wr_status wr_scene_parse(wr_scene *sc, const char *text, size_t len, const char *base_dir, wr_diag *diag) {
    static const char *const keys[] = {"name", "mesh", "material", "energy", "gravity", "ramp_gravity", "pressure",
                                       "boundary", "solver", "probes", "obstacles", "contact", NULL};
    static const char *const ekeys[] = {"membrane", "bending", "element", NULL};
    wr_jin c;
    cJSON *root;
    const cJSON *o, *e;
    wr_status st = WR_OK;
    int i;
    c.diag = diag;
    wr_scene_defaults(sc);
    if (!text) return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "$: no text");
    root = cJSON_ParseWithLength(text, len);
    if (!root) {
        const char *ep = cJSON_GetErrorPtr();
        long off = (ep && ep >= text && ep <= text + len) ? (long)(ep - text) : -1;
        return wr_fail(diag, WR_ERR_PARSE, -1, "$: malformed JSON near byte %ld", off);
    }
    if ((st = wr_jin_keys(&c, root, "$", keys)) != WR_OK) goto done;
    if ((st = wr_jin_str(&c, root, "name", "$", sc->name, sizeof sc->name, 0)) != WR_OK) goto done;
    o = cJSON_GetObjectItemCaseSensitive(root, "mesh");
    if (!o) {
        st = wr_jin_err(&c, "$.mesh", "is required");
        goto done;
    }
    if ((st = sc_parse_mesh(&c, o, base_dir, &sc->mesh)) != WR_OK) goto done;
    o = cJSON_GetObjectItemCaseSensitive(root, "material");
    if (!o) {
        st = wr_jin_err(&c, "$.material", "is required");
        goto done;
    }
    if ((st = sc_parse_material(&c, o, sc)) != WR_OK) goto done;
    o = cJSON_GetObjectItemCaseSensitive(root, "energy");
    if (o) {
        int mem = 0, ben = 0, elem = 0;
        if ((st = wr_jin_keys(&c, o, "$.energy", ekeys)) != WR_OK) goto done;
        if ((st = wr_jin_enum(&c, o, "element", "$.energy", SC_ELEMENTS, &elem, 0)) != WR_OK) goto done;
        sc->shell.loop_element = elem;
        if ((st = wr_jin_enum(&c, o, "membrane", "$.energy", SC_MEMBRANES, &mem, 0)) != WR_OK) goto done;
        if ((st = wr_jin_enum(&c, o, "bending", "$.energy", SC_BENDINGS, &ben, 0)) != WR_OK) goto done;
        sc->shell.membrane = (wr_membrane_model)mem;
        sc->shell.bending = (wr_bending_model)ben;
    }
    if (sc->shell.orthotropic && (sc->shell.membrane == WR_MEMBRANE_TFT || sc->shell.bending == WR_BENDING_QUADRATIC)) {
        st = wr_jin_err(&c, "$.material.orthotropic", "needs membrane stvk and bending midedge (shell.h)");
        goto done;
    }
    if ((st = wr_jin_vec(&c, root, "gravity", "$", 3, sc->gravity, NULL)) != WR_OK) goto done;
    if ((st = wr_jin_bool(&c, root, "ramp_gravity", "$", &sc->ramp_gravity)) != WR_OK) goto done;
    if ((st = wr_jin_num(&c, root, "pressure", "$", WR_JIN_ANY, &sc->pressure, NULL)) != WR_OK) goto done;
    o = cJSON_GetObjectItemCaseSensitive(root, "boundary");
    if (o) {
        if (!cJSON_IsArray(o)) {
            st = wr_jin_err(&c, "$.boundary", "must be an array");
            goto done;
        }
        if (cJSON_GetArraySize(o) > WR_SCENE_MAX_BC) {
            st = wr_jin_err(&c, "$.boundary", "more than %d sets", WR_SCENE_MAX_BC);
            goto done;
        }
        for (e = o->child, i = 0; e; e = e->next, ++i) {
            char p[64];
            snprintf(p, sizeof p, "$.boundary[%d]", i);
            snprintf(sc->bc[i].name, sizeof sc->bc[i].name, "set%d", i);
            sc->n_bc = i + 1;
            if ((st = sc_parse_bc(&c, e, p, &sc->bc[i])) != WR_OK) goto done;
        }
    }
    o = cJSON_GetObjectItemCaseSensitive(root, "solver");
    if (o && (st = sc_parse_solver(&c, o, sc)) != WR_OK) goto done;
    if ((st = sc_parse_contact(&c, root, base_dir, sc)) != WR_OK) goto done;
    o = cJSON_GetObjectItemCaseSensitive(root, "probes");
    if (o) {
        if (!cJSON_IsArray(o)) {
            st = wr_jin_err(&c, "$.probes", "must be an array");
            goto done;
        }
        if (cJSON_GetArraySize(o) > WR_SCENE_MAX_PROBES) {
            st = wr_jin_err(&c, "$.probes", "more than %d probes", WR_SCENE_MAX_PROBES);
            goto done;
        }
        for (e = o->child, i = 0; e; e = e->next, ++i) {
            char p[64];
            snprintf(p, sizeof p, "$.probes[%d]", i);
            snprintf(sc->probe[i].name, sizeof sc->probe[i].name, "probe%d", i);
            sc->n_probes = i + 1;
            if ((st = sc_parse_probe(&c, e, p, &sc->probe[i])) != WR_OK) goto done;
        }
    }
done:
    cJSON_Delete(root);
    if (st != WR_OK) wr_scene_free(sc);
    return st;
}

wr_status wr_scene_load(wr_scene *sc, const char *path, wr_diag *diag) {
    char *buf = NULL, dir[WR_SCENE_PATH_LEN];
    size_t n = 0;
    const char *slash;
    wr_status st;
    wr_scene_defaults(sc);
    st = wr_file_read(path, &buf, &n, diag); /* core.h: WR_ERR_IO naming the path, or WR_ERR_NOMEM */
    if (st != WR_OK) return st;
    slash = strrchr(path, '/');
    if (slash && (size_t)(slash - path) < sizeof dir) {
        memcpy(dir, path, (size_t)(slash - path));
        dir[slash - path] = 0;
    } else
        strcpy(dir, ".");
    st = wr_scene_parse(sc, buf, n, dir, diag);
    wr_free(buf);
    return st;
}

/* ---------------------------------------------------------------------------------------------- */
/* building                                                                                        */

static double sc_const_sizing(void *user, double x, double y) {
    (void)x;
    (void)y;
    return *(const double *)user;
}

wr_status wr_scene_mesh_delaunay(wr_mesh *m, double w, double h, double r, uint64_t seed, wr_diag *diag) {
    double box[8];
    wr_poisson_domain dom;
    wr_poisson_desc pd;
    wr_poisson_result pr;
    wr_cdt_input in;
    wr_cdt_desc cd;
    wr_cdt_result cr;
    wr_status st;
    box[0] = 0.0, box[1] = 0.0, box[2] = w, box[3] = 0.0, box[4] = w, box[5] = h, box[6] = 0.0, box[7] = h;
    memset(&dom, 0, sizeof dom);
    memset(&pd, 0, sizeof pd);
    memset(&in, 0, sizeof in);
    memset(&cd, 0, sizeof cd);
    memset(&cr, 0, sizeof cr);
    dom.outer.xy = box;
    dom.outer.n = 4;
    dom.outer.closed = 1;
    pd.seed = seed;
    pd.max_points = SC_MAX_VERTICES;
    st = wr_poisson_sample(&dom, sc_const_sizing, &r, &pd, &pr, diag);
    if (st != WR_OK) return st;
    in.points = pr.points;
    in.n_points = pr.n_points;
    in.segments = pr.segments;
    in.n_segments = pr.n_segments;
    cd.seed = seed;
    st = wr_cdt_triangulate(&in, &cd, &cr, diag);
    if (st == WR_OK) st = wr_mesh_create(m, cr.n_points, NULL, cr.points, cr.n_triangles, cr.triangles, diag);
    wr_cdt_free(&cr);
    wr_poisson_free(&pr);
    return st;
}

wr_status wr_scene_mesh_lattice(wr_mesh *m, double w, double h, double r, double theta_deg, wr_diag *diag) {
    double c = cos(theta_deg * SC_PI / 180.0), s = sin(theta_deg * SC_PI / 180.0), R = sqrt(w * w + h * h);
    int32_t nb_x = (int32_t)floor(w / r + 0.5), nb_y = (int32_t)floor(h / r + 0.5), cap, np = 0, nseg, i, j, k;
    int32_t jmax = (int32_t)ceil(R / (r * 0.8660254037844386)) + 2, imax = (int32_t)ceil(R / r) + jmax + 2;
    double *pts;
    int32_t *seg;
    wr_cdt_input in;
    wr_cdt_desc cd;
    wr_cdt_result cr;
    wr_status st;
    if (nb_x < 1) nb_x = 1;
    if (nb_y < 1) nb_y = 1;
    nseg = 2 * (nb_x + nb_y);
    cap = nseg + (2 * imax + 1) * (2 * jmax + 1);
    pts = (double *)malloc(sizeof(double) * 2 * (size_t)cap);
    seg = (int32_t *)malloc(sizeof(int32_t) * 2 * (size_t)nseg);
    if (!pts || !seg) {
        free(pts), free(seg);
        return wr_fail(diag, WR_ERR_NOMEM, -1, "lattice: out of memory");
    }
    /* boundary loop, counter-clockwise: bottom, right, top, left */
    for (k = 0; k < nb_x; ++k) pts[2 * np] = w * k / nb_x, pts[2 * np + 1] = 0.0, ++np;
    for (k = 0; k < nb_y; ++k) pts[2 * np] = w, pts[2 * np + 1] = h * k / nb_y, ++np;
    for (k = 0; k < nb_x; ++k) pts[2 * np] = w - w * k / nb_x, pts[2 * np + 1] = h, ++np;
    for (k = 0; k < nb_y; ++k) pts[2 * np] = 0.0, pts[2 * np + 1] = h - h * k / nb_y, ++np;
    for (k = 0; k < nseg; ++k) seg[2 * k] = k, seg[2 * k + 1] = (k + 1) % nseg;
    for (j = -jmax; j <= jmax; ++j)
        for (i = -imax; i <= imax; ++i) {
            double u = (i + 0.5 * j) * r, v = j * 0.8660254037844386 * r;
            double x = 0.5 * w + c * u - s * v, y = 0.5 * h + s * u + c * v;
            if (x >= 0.5 * r && x <= w - 0.5 * r && y >= 0.5 * r && y <= h - 0.5 * r && np < cap)
                pts[2 * np] = x, pts[2 * np + 1] = y, ++np;
        }
    memset(&in, 0, sizeof in), memset(&cd, 0, sizeof cd), memset(&cr, 0, sizeof cr);
    in.points = pts, in.n_points = np, in.segments = seg, in.n_segments = nseg;
    cd.seed = 1;
    st = wr_cdt_triangulate(&in, &cd, &cr, diag);
    if (st == WR_OK) st = wr_mesh_create(m, cr.n_points, NULL, cr.points, cr.n_triangles, cr.triangles, diag);
    wr_cdt_free(&cr);
    free(pts), free(seg);
    return st;
}

static wr_status sc_build_panel(const wr_scene_mesh *g, wr_mesh *m, wr_obj_groups *groups, wr_diag *diag);

/* The scene's mesh: the generated or read one, doubled into a pillow when asked. */
/* The scene's rest mesh; an OBJ's group names go to *groups (a pillow's two sides are panels 0 and 1
 * of wr_mesh_pillow, not the file's, so it keeps none). */
static wr_status sc_build_mesh(const wr_scene_mesh *g, wr_mesh *m, wr_obj_groups *groups, wr_diag *diag) {
    wr_mesh panel;
    wr_status st;
    if (!(g->pillow_lift > 0.0)) return sc_build_panel(g, m, groups, diag);
    memset(&panel, 0, sizeof panel);
    if ((st = sc_build_panel(g, &panel, NULL, diag)) != WR_OK) return st;
    st = wr_mesh_pillow(m, &panel, g->pillow_lift, diag);
    wr_mesh_free(&panel);
    return st;
}

typedef struct sc_xkey {
    double x;
    int32_t v;
} sc_xkey;
static int sc_xkey_cmp(const void *a, const void *b) {
    double d = ((const sc_xkey *)a)->x - ((const sc_xkey *)b)->x;
    return d < 0.0 ? -1 : d > 0.0;
}

/* $.mesh.weld: every two vertices at most tol apart in 3D (a sweep over the vertices sorted by x)
 * merged by mesh.h wr_mesh_weld, each face keeping its rest corners (corner_rest) and its panel. */
static wr_status sc_weld_coincident(wr_mesh *m, double tol, wr_diag *diag) {
    sc_xkey *key = (sc_xkey *)malloc(sizeof(sc_xkey) * (size_t)m->nv);
    int32_t *pairs = NULL, np = 0, cap = 0, i, j;
    wr_mesh w;
    wr_status st = WR_OK;
    if (!key) return wr_fail(diag, WR_ERR_NOMEM, -1, "$.mesh.weld: out of memory");
    for (i = 0; i < m->nv; ++i) key[i].x = m->pos[3 * i], key[i].v = i;
    qsort(key, (size_t)m->nv, sizeof *key, sc_xkey_cmp);
    for (i = 0; i < m->nv && st == WR_OK; ++i)
        for (j = i + 1; j < m->nv && key[j].x - key[i].x <= tol; ++j) {
            const double *a = m->pos + 3 * key[i].v, *b = m->pos + 3 * key[j].v;
            double dy = a[1] - b[1], dz = a[2] - b[2], dx = a[0] - b[0];
            if (dx * dx + dy * dy + dz * dz > tol * tol) continue;
            if (np == cap) {
                int32_t *t = (int32_t *)realloc(pairs, sizeof(int32_t) * 2 * (size_t)(cap = 2 * cap + 64));
                if (!t) {
                    st = wr_fail(diag, WR_ERR_NOMEM, -1, "$.mesh.weld: out of memory");
                    break;
                }
                pairs = t;
            }
            pairs[2 * np] = key[i].v, pairs[2 * np + 1] = key[j].v, ++np;
        }
    free(key);
    if (st == WR_OK && np > 0) {
        if ((st = wr_mesh_weld(&w, m, np, pairs, NULL, diag)) == WR_OK) {
            wr_mesh_free(m);
            *m = w;
        } else {
            char msg[WR_DIAG_MESSAGE_LEN];
            snprintf(msg, sizeof msg, "%s", diag ? diag->message : "");
            st = wr_fail(diag, st, -1, "$.mesh.weld: merging the %d vertex pairs within %g m: %s", (int)np, tol, msg);
        }
    }
    free(pairs);
    return st;
}

static wr_status sc_build_panel(const wr_scene_mesh *g, wr_mesh *m, wr_obj_groups *groups, wr_diag *diag) {
    double r = g->resolution;
    double est = 0.0;
    wr_status st;
    switch (g->kind) {
    case WR_SCENE_MESH_OBJ:
        if ((st = wr_mesh_read_obj_groups(m, g->path, groups, diag)) != WR_OK || !g->has_weld) return st;
        if ((st = sc_weld_coincident(m, g->weld_tol, diag)) != WR_OK) {
            wr_mesh_free(m);
            if (groups) wr_obj_groups_free(groups);
        }
        return st;
    case WR_SCENE_MESH_RECTANGLE: {
        int32_t nx = g->nx, ny = g->ny;
        if (nx <= 0) {
            est = (g->width / r + 1.0) * (g->height / r + 1.0);
            if (est > SC_MAX_VERTICES) break;
            nx = (int32_t)fmax(1.0, floor(g->width / r + 0.5));
            ny = (int32_t)fmax(1.0, floor(g->height / r + 0.5));
        }
        return wr_mesh_rectangle(m, g->width, g->height, nx, ny, diag);
    }
    case WR_SCENE_MESH_DISK: {
        est = 3.0 * (g->radius / r) * (g->radius / r + 1.0);
        if (est > SC_MAX_VERTICES) break;
        return wr_mesh_disk(m, g->radius, (int32_t)fmax(1.0, floor(g->radius / r + 0.5)), diag);
    }
    case WR_SCENE_MESH_CYLINDER: {
        double nu = fmax(3.0, floor(2.0 * SC_PI * g->radius / r + 0.5)), nh = fmax(1.0, floor(g->height / r + 0.5));
        est = nu * (nh + 1.0);
        if (est > SC_MAX_VERTICES) break;
        return wr_mesh_cylinder_flat(m, g->radius, g->height, (int32_t)nu, (int32_t)nh, diag);
    }
    case WR_SCENE_MESH_DELAUNAY_RECTANGLE:
        est = 1.2 * g->width * g->height / (r * r);
        if (est > SC_MAX_VERTICES) break;
        return wr_scene_mesh_delaunay(m, g->width, g->height, r, g->seed, diag);
    case WR_SCENE_MESH_LATTICE:
        est = 1.2 * g->width * g->height / (0.8660254037844386 * r * r);
        if (est > SC_MAX_VERTICES) break;
        return wr_scene_mesh_lattice(m, g->width, g->height, r, g->angle_deg, diag);
    }
    return wr_fail(diag, WR_ERR_BUDGET, -1, "$.mesh.resolution: %g m would need ~%.3g vertices (limit %d)", r, est,
                   SC_MAX_VERTICES);
}

void wr_scene_run_free(wr_scene_run *run) {
    int32_t k;
    if (!run) return;
    for (k = 0; run->obstacle_meshes && run->sc && k < run->sc->n_obstacles; ++k) wr_obstacle_mesh_free(&run->obstacle_meshes[k]);
    free(run->obstacle_meshes);
    free(run->obstacles);
    wr_shell_free(&run->shell);
    wr_mesh_free(&run->mesh);
    wr_obj_groups_free(&run->groups);
    free(run->fixed);
    free(run->bc_of);
    free(run->x);
    free(run->steps);
    memset(run, 0, sizeof *run);
}

/* $.obstacles: the analytic ones as given, the meshes read (obj) or made (mannequin), moved by their
 * translate, and built into statics.h mesh obstacles; errors name the obstacle's JSON path */
static wr_status sc_build_obstacles(wr_scene_run *run, wr_diag *diag) {
    const wr_scene *sc = run->sc;
    int32_t k, i;
    if (sc->n_obstacles == 0) return WR_OK;
    run->obstacles = (wr_obstacle *)calloc((size_t)sc->n_obstacles, sizeof(wr_obstacle));
    run->obstacle_meshes = (wr_obstacle_mesh *)calloc((size_t)sc->n_obstacles, sizeof(wr_obstacle_mesh));
    if (!run->obstacles || !run->obstacle_meshes) return wr_fail(diag, WR_ERR_NOMEM, -1, "$.obstacles: out of memory");
    for (k = 0; k < sc->n_obstacles; ++k) {
        const wr_scene_obstacle *ob = &sc->obstacle[k];
        wr_mesh m;
        wr_status st;
        char msg[WR_DIAG_MESSAGE_LEN];
        run->obstacles[k] = ob->analytic;
        if (ob->kind != WR_SCENE_OBSTACLE_OBJ && ob->kind != WR_SCENE_OBSTACLE_MANNEQUIN) continue;
        memset(&m, 0, sizeof m);
        st = ob->kind == WR_SCENE_OBSTACLE_OBJ ? wr_mesh_read_obj(&m, ob->path, diag) : wr_body_mannequin(&m, &ob->body, diag);
        if (st == WR_OK) {
            for (i = 0; i < 3 * m.nv; ++i) m.pos[i] += ob->translate[i % 3];
            st = wr_obstacle_mesh_create(&run->obstacle_meshes[k], m.pos, m.nv, m.faces, m.nf, diag);
        }
        wr_mesh_free(&m);
        if (st != WR_OK) {
            snprintf(msg, sizeof msg, "%s", diag ? diag->message : "");
            return wr_fail(diag, st, k, "$.obstacles[%d]%s: %s", (int)k, ob->kind == WR_SCENE_OBSTACLE_OBJ ? ".path" : "", msg);
        }
        run->obstacles[k].mesh = &run->obstacle_meshes[k];
    }
    return WR_OK;
}

static wr_status sc_probe_check_panels(const wr_mesh *m, int32_t i, const double *pts, int32_t n, wr_diag *diag);

/* Panels of m: 1 + the largest face_panel id (1 without face_panel). */
static int32_t sc_n_panels(const wr_mesh *m) {
    int32_t f, n = 1;
    for (f = 0; m->face_panel && f < m->nf; ++f)
        if (m->face_panel[f] >= n) n = m->face_panel[f] + 1;
    return n;
}

/* $.probes[i].panel against the mesh: run->probe_panel[i] = the panel id, or -1 (no selector, or panel
 * 0 of a mesh without face_panel, which is every face). */
static wr_status sc_resolve_probe_panels(wr_scene_run *run, wr_diag *diag) {
    const wr_mesh *m = &run->mesh;
    int32_t i, k, np = sc_n_panels(m);
    for (i = 0; i < run->sc->n_probes; ++i) {
        const wr_scene_probe *P = &run->sc->probe[i];
        int32_t id = P->panel_id;
        run->probe_panel[i] = -1;
        if (!P->has_panel && np > 1) { /* refused before the solve when its line lies on overlapping panels */
            double *pts = (double *)malloc(sizeof(double) * 2 * (size_t)P->samples), ds;
            wr_status st = pts ? wr_path_segment(P->from, P->to, P->samples, P->closed, pts, &ds, diag)
                               : wr_fail(diag, WR_ERR_NOMEM, -1, "probe: out of memory");
            if (st == WR_OK) st = sc_probe_check_panels(m, i, pts, P->samples, diag);
            free(pts);
            if (st != WR_OK) return st;
        }
        if (!P->has_panel) continue;
        if (P->panel_name[0]) {
            char names[256] = "";
            for (id = -1, k = 0; k < run->groups.n; ++k) {
                const char *g = run->groups.names[k];
                if (!g) continue;
                if (strcmp(g, P->panel_name) == 0) id = k;
                if (strlen(names) + strlen(g) + 3 < sizeof names) snprintf(names + strlen(names), sizeof names - strlen(names), "%s%s", names[0] ? ", " : "", g);
            }
            if (id < 0)
                return wr_fail(diag, WR_ERR_INVALID_ARG, i, "$.probes[%d].panel: no panel named \"%s\" in the mesh (%s%s)",
                               (int)i, P->panel_name, names[0] ? "its OBJ groups: " : "it has no OBJ g/o names", names);
        } else if (id >= np) {
            return wr_fail(diag, WR_ERR_INVALID_ARG, i, "$.probes[%d].panel: panel id %d, the mesh has %d panel%s", (int)i,
                           (int)id, (int)np, np == 1 ? "" : "s");
        }
        run->probe_panel[i] = m->face_panel ? id : -1;
    }
    return WR_OK;
}

wr_status wr_scene_run_create(wr_scene_run *run, const wr_scene *sc, wr_diag *diag) {
    wr_status st;
    int32_t i, b, nv;
    double t0 = wr_time_seconds();
    memset(run, 0, sizeof *run);
    run->sc = sc;
    if ((st = sc_build_mesh(&sc->mesh, &run->mesh, &run->groups, diag)) != WR_OK) return st;
    run->t_mesh = wr_time_seconds() - t0;
    t0 = wr_time_seconds();
    if ((st = wr_shell_create(&run->shell, &run->mesh, &sc->shell, diag)) != WR_OK) goto fail;
    nv = run->mesh.nv;
    run->fixed = (uint8_t *)calloc((size_t)nv, 1);
    run->bc_of = (int32_t *)malloc(sizeof(int32_t) * (size_t)nv);
    run->x = (double *)malloc(sizeof(double) * 3 * (size_t)nv);
    run->steps = (wr_scene_step_stats *)calloc((size_t)sc->load_steps, sizeof(wr_scene_step_stats));
    if (!run->fixed || !run->bc_of || !run->x || !run->steps) {
        st = wr_fail(diag, WR_ERR_NOMEM, -1, "scene: out of memory (%d vertices)", (int)nv);
        goto fail;
    }
    memcpy(run->x, run->mesh.pos, sizeof(double) * 3 * (size_t)nv);
    for (i = 0; i < nv; ++i) run->bc_of[i] = -1;
    /* later sets win where they overlap (stated in docs/scene-format.md) */
    for (b = 0; b < sc->n_bc; ++b) {
        const wr_scene_bc *B = &sc->bc[b];
        int32_t hits = 0;
        if (B->select == WR_SCENE_SELECT_BOX) {
            for (i = 0; i < nv; ++i) {
                const double *p = run->mesh.pos + 3 * i;
                if (p[0] >= B->box_lo[0] && p[0] <= B->box_hi[0] && p[1] >= B->box_lo[1] && p[1] <= B->box_hi[1] &&
                    p[2] >= B->box_lo[2] && p[2] <= B->box_hi[2]) {
                    run->bc_of[i] = b;
                    ++hits;
                }
            }
        } else {
            for (i = 0; i < B->n_indices; ++i) {
                if (B->indices[i] >= nv) {
                    st = wr_fail(diag, WR_ERR_INVALID_ARG, i, "$.boundary[%d].indices[%d]: vertex %d >= %d vertices",
                                 (int)b, (int)i, (int)B->indices[i], (int)nv);
                    goto fail;
                }
                run->bc_of[B->indices[i]] = b;
                ++hits;
            }
        }
        if (hits == 0) {
            st = wr_fail(diag, WR_ERR_INVALID_ARG, b, "$.boundary[%d].box: selects no vertex", (int)b);
            goto fail;
        }
    }
    for (i = 0; i < nv; ++i)
        if (run->bc_of[i] >= 0) {
            run->fixed[i] = 1;
            run->n_fixed++;
        }
    if ((st = sc_build_obstacles(run, diag)) != WR_OK) goto fail;
    if ((st = sc_resolve_probe_panels(run, diag)) != WR_OK) goto fail;
    run->t_setup = wr_time_seconds() - t0;
    return WR_OK;
fail:
    wr_scene_run_free(run);
    return st;
}

/* The library motion (statics.h WR_MOTION_AFFINE) of prescribed set B (scene.h formula). */
static void sc_motion(const wr_scene_bc *B, wr_motion *m) {
    int k;
    memset(m, 0, sizeof *m);
    m->kind = WR_MOTION_AFFINE;
    for (k = 0; k < 3; ++k) {
        m->origin[k] = B->center[k];
        m->vec[k] = B->translate[k];
        m->axis[k] = B->twist_axis[k];
        m->grad[4 * k] = B->stretch[k] - 1.0;
        m->wave_along[k] = B->wave_along[k];
        m->wave_dir[k] = B->wave_dir[k];
    }
    m->grad[1] = B->shear[0], m->grad[2] = B->shear[1], m->grad[5] = B->shear[2];
    m->amount = B->twist_angle;
    m->wave_amplitude = B->wave_amplitude;
    m->wave_length = B->wave_length;
    m->wave_phase = B->wave_phase;
}

typedef struct sc_prog {
    wr_scene_run *run;
    wr_scene_progress_fn fn;
    void *user;
    wr_status worst;
    wr_diag *diag;
} sc_prog;

static void sc_progress(void *user, const wr_statics_stats *st) {
    sc_prog *p = (sc_prog *)user;
    if (p->fn) p->fn(p->user, st->increment, p->run->sc->load_steps, st);
}

/* statics.h increments.done: one load step's figures into the run */
static void sc_step_done(void *user, int32_t k, int32_t n, wr_status status, const wr_statics_stats *st,
                         const wr_diag *dd) {
    sc_prog *p = (sc_prog *)user;
    wr_scene_run *run = p->run;
    wr_scene_step_stats *ss = &run->steps[k - 1];
    ss->fraction = (double)k / n;
    ss->st = *st;
    ss->status = status;
    run->n_steps_done = k;
    run->newton_iterations += st->iterations;
    run->linear_iterations += st->linear_iterations;
    run->t_assembly += st->t_assembly;
    run->t_projection += st->t_projection;
    run->t_linear += st->t_linear;
    run->t_line_search += st->t_line_search;
    /* keep going after NOT_CONVERGED (later steps often recover); the run reports the first one */
    if (status == WR_ERR_NOT_CONVERGED && p->worst == WR_OK) {
        p->worst = status;
        if (p->diag && dd) *p->diag = *dd;
    }
}

/* Load stepping through statics.h's incremental solve: step k of N applies fraction k/N of every
 * prescribed motion (and of gravity unless ramp_gravity is false), starting each step from the
 * affine prediction, with one absolute force scale for every step (increments.absolute_reference),
 * hybrid Newton when asked (increments.hybrid_switch = SC_HYBRID_SWITCH). */
wr_status wr_scene_run_solve(wr_scene_run *run, wr_scene_progress_fn progress, void *user, wr_diag *diag) {
    const wr_scene *sc = run->sc;
    int32_t b, i, nv = run->mesh.nv, *verts = NULL, *start = NULL;
    wr_motion *motions = NULL;
    wr_statics_desc d;
    wr_statics_stats st;
    wr_diag dd;
    sc_prog pg;
    wr_status rs;
    double t0 = wr_time_seconds();
    memset(&dd, 0, sizeof dd);
    motions = (wr_motion *)calloc((size_t)sc->n_bc + 1, sizeof(wr_motion));
    verts = (int32_t *)malloc(sizeof(int32_t) * ((size_t)nv + 1));
    start = (int32_t *)calloc((size_t)sc->n_bc + 2, sizeof(int32_t));
    if (!motions || !verts || !start) {
        free(motions), free(verts), free(start);
        return wr_fail(diag, WR_ERR_NOMEM, -1, "scene: out of memory");
    }
    /* each set's vertices (later sets win where they overlap: bc_of) */
    for (i = 0; i < nv; ++i)
        if (run->bc_of[i] >= 0) start[run->bc_of[i] + 1]++;
    for (b = 0; b < sc->n_bc; ++b) start[b + 1] += start[b];
    for (i = 0; i < nv; ++i)
        if (run->bc_of[i] >= 0) verts[start[run->bc_of[i]]++] = i;
    for (b = sc->n_bc; b > 0; --b) start[b] = start[b - 1];
    start[0] = 0;
    for (b = 0; b < sc->n_bc; ++b) {
        sc_motion(&sc->bc[b], motions + b);
        motions[b].verts = verts + start[b];
        motions[b].n_verts = start[b + 1] - start[b];
    }
    memset(&d, 0, sizeof d);
    d.stop.max_iter = sc->max_iter;
    d.stop.grad_tol = sc->grad_tol;
    for (i = 0; i < 3; ++i) d.loads.gravity[i] = sc->gravity[i];
    d.loads.pressure = sc->pressure;
    d.start.perturb = sc->perturb;
    d.start.seed = sc->seed;
    d.contact.obstacles = run->obstacles;
    d.contact.n_obstacles = sc->n_obstacles;
    d.contact.dhat = sc->contact_dhat;
    d.contact.stiffness = sc->contact_stiffness;
    d.hessian.projection = sc->hessian == WR_SCENE_HESSIAN_EXACT ? WR_PROJECT_NONE : WR_PROJECT_FAST;
    d.linear.solver.method = sc->linear;
    d.linear.solver.rel_tol = sc->linear_tol;
    d.increments.predictor = WR_STATICS_PREDICT_AFFINE;
    d.increments.ramp_gravity = sc->ramp_gravity;
    d.increments.absolute_reference = 1;
    d.increments.hybrid_switch = sc->hessian == WR_SCENE_HESSIAN_HYBRID ? SC_HYBRID_SWITCH : 0.0;
    d.increments.done = sc_step_done;
    d.stability = sc->stability;
    memset(&pg, 0, sizeof pg);
    pg.run = run, pg.fn = progress, pg.user = user, pg.worst = WR_OK, pg.diag = diag;
    d.progress = progress ? sc_progress : NULL;
    d.progress_user = &pg;
    rs = wr_statics_solve_incremental(&run->shell, run->x, &d, motions, sc->n_bc, sc->load_steps, &st, &dd);
    free(motions), free(verts), free(start);
    run->t_solve = wr_time_seconds() - t0;
    if (rs != WR_OK && rs != WR_ERR_NOT_CONVERGED) {
        if (diag) *diag = dd;
        run->solve_status = rs;
        return rs;
    }
    run->solve_status = pg.worst;
    return pg.worst;
}

/* Interpolated m->pos at (x, y) in the faces of panel k (mask), and whether it is there. */
static int sc_panel_point(const wr_mesh *m, const wr_probe *p, double x, double y, double out[3]) {
    double b[3];
    int32_t f = wr_probe_locate(p, x, y, b), c, j;
    if (f < 0) return 0;
    for (c = 0; c < 3; ++c)
        for (out[c] = 0.0, j = 0; j < 3; ++j) out[c] += b[j] * m->pos[3 * m->faces[3 * f + j] + c];
    return 1;
}

/* Probe i without a panel on a mesh of several: refuse when a point lies in two panels whose positions
 * differ there (overlapping panels; a seam between abutting panels has one position). */
static wr_status sc_probe_check_panels(const wr_mesh *m, int32_t i, const double *pts, int32_t n, wr_diag *diag) {
    int32_t np = sc_n_panels(m), k, f, j, *first = (int32_t *)malloc(sizeof(int32_t) * (size_t)n);
    double *x0 = (double *)malloc(sizeof(double) * 3 * (size_t)n), lo[3] = {HUGE_VAL, HUGE_VAL, HUGE_VAL},
           hi[3] = {-HUGE_VAL, -HUGE_VAL, -HUGE_VAL}, tol = 0.0, x[3];
    uint8_t *mask = (uint8_t *)malloc((size_t)m->nf);
    wr_status st = WR_OK;
    if (!first || !x0 || !mask) st = wr_fail(diag, WR_ERR_NOMEM, -1, "probe: out of memory");
    for (j = 0; j < 3 * m->nv; ++j) lo[j % 3] = fmin(lo[j % 3], m->pos[j]), hi[j % 3] = fmax(hi[j % 3], m->pos[j]);
    for (k = 0; k < 3; ++k) tol += (hi[k] - lo[k]) * (hi[k] - lo[k]);
    tol = 1e-9 * sqrt(tol);
    for (j = 0; j < n && st == WR_OK; ++j) first[j] = -1;
    for (k = 0; k < np && st == WR_OK; ++k) {
        wr_probe_desc pd;
        wr_probe p;
        memset(&pd, 0, sizeof pd);
        for (f = 0; f < m->nf; ++f) mask[f] = m->face_panel[f] == k;
        pd.face_mask = mask;
        if (wr_probe_create(&p, m, &pd, NULL) != WR_OK) continue; /* a panel without area */
        for (j = 0; j < n && st == WR_OK; ++j) {
            if (!sc_panel_point(m, &p, pts[2 * j], pts[2 * j + 1], x)) continue;
            if (first[j] < 0) {
                first[j] = k;
                memcpy(x0 + 3 * j, x, sizeof x);
            } else if (wr_v3_norm(wr_v3_sub(wr_v3_load(x), wr_v3_load(x0 + 3 * j))) > tol) {
                st = wr_fail(diag, WR_ERR_INVALID_ARG, i,
                             "$.probes[%d]: sample %d at rest (%g, %g) m lies in panels %d and %d, which overlap in the rest domain; set \"panel\"",
                             (int)i, (int)j, pts[2 * j], pts[2 * j + 1], (int)first[j], (int)k);
            }
        }
        wr_probe_free(&p);
    }
    free(first), free(x0), free(mask);
    return st;
}

wr_status wr_scene_probe_locator(const wr_scene_run *run, int32_t i, const wr_mesh *m, const double *pts, int32_t n,
                                 wr_probe *p, wr_diag *diag) {
    int32_t k = run->probe_panel[i], f;
    wr_probe_desc pd;
    uint8_t *mask;
    wr_status st;
    memset(p, 0, sizeof *p);
    if (k < 0 || !m->face_panel) {
        if (m->face_panel && sc_n_panels(m) > 1 && (st = sc_probe_check_panels(m, i, pts, n, diag)) != WR_OK) return st;
        return wr_probe_create(p, m, NULL, diag);
    }
    if (!(mask = (uint8_t *)malloc((size_t)m->nf))) return wr_fail(diag, WR_ERR_NOMEM, -1, "probe: out of memory");
    for (f = 0; f < m->nf; ++f) mask[f] = m->face_panel[f] == k;
    memset(&pd, 0, sizeof pd);
    pd.face_mask = mask;
    st = wr_probe_create(p, m, &pd, diag);
    free(mask);
    return st;
}

wr_status wr_scene_probe_field(const wr_scene_probe *P, const wr_mesh *m, const double *x, const double *x0,
                               double *field, wr_diag *diag) {
    double *nrm = NULL, d[3], len = sqrt(P->dir[0] * P->dir[0] + P->dir[1] * P->dir[1] + P->dir[2] * P->dir[2]);
    int32_t v;
    int k;
    if (P->dir_normal) {
        wr_mesh ref = *m; /* a shallow view: m's topology at the reference positions */
        ref.pos = (double *)x0;
        if (!(nrm = (double *)malloc(sizeof(double) * 3 * (size_t)m->nv)))
            return wr_fail(diag, WR_ERR_NOMEM, -1, "probe: out of memory");
        wr_mesh_vertex_normals(&ref, nrm);
    }
    for (k = 0; k < 3; ++k) d[k] = len > 0.0 ? P->dir[k] / len : (k == 2);
    for (v = 0; v < m->nv; ++v) {
        const double *n = nrm ? nrm + 3 * v : d;
        field[v] = 0.0;
        for (k = 0; k < 3; ++k) field[v] += (x[3 * v + k] - x0[3 * v + k]) * n[k];
    }
    free(nrm);
    return WR_OK;
}

wr_status wr_scene_run_probe_samples(const wr_scene_run *run, int32_t i, double *pts, double *vals, double *ds,
                                     wr_diag *diag) {
    const wr_scene_probe *P = &run->sc->probe[i];
    wr_probe pr;
    double *u;
    int32_t nout = 0, n = P->samples;
    wr_status st;
    if ((st = wr_path_segment(P->from, P->to, n, P->closed, pts, ds, diag)) != WR_OK) return st;
    u = (double *)malloc(sizeof(double) * (size_t)run->mesh.nv);
    if (!u) return wr_fail(diag, WR_ERR_NOMEM, -1, "probe: out of memory");
    st = wr_scene_probe_field(P, &run->mesh, run->x, run->mesh.pos, u, diag);
    if (st == WR_OK) st = wr_scene_probe_locator(run, i, &run->mesh, pts, n, &pr, diag);
    if (st == WR_OK) {
        st = wr_probe_sample(&pr, u, pts, n, vals, &nout, diag);
        if (st == WR_OK && nout > 0)
            st = wr_fail(diag, WR_ERR_GEOMETRY, i, "$.probes[%d]: %d of %d samples fall outside the rest mesh", (int)i,
                         (int)nout, (int)n);
        wr_probe_free(&pr);
    }
    free(u);
    return st;
}

wr_status wr_scene_run_probe(const wr_scene_run *run, int32_t i, wr_spectrum_result *res, wr_diag *diag) {
    int32_t n = run->sc->probe[i].samples;
    double *pts = (double *)malloc(sizeof(double) * 2 * (size_t)n), *vals = (double *)malloc(sizeof(double) * (size_t)n);
    double ds;
    wr_status st;
    if (!pts || !vals) {
        free(pts);
        free(vals);
        return wr_fail(diag, WR_ERR_NOMEM, -1, "probe: out of memory");
    }
    st = wr_scene_run_probe_samples(run, i, pts, vals, &ds, diag);
    if (st == WR_OK) st = wr_spectrum_analyze(vals, n, ds, run->sc->probe[i].closed, NULL, res, NULL, 0, diag);
    free(pts);
    free(vals);
    return st;
}

/* ---------------------------------------------------------------------------------------------- */
/* output                                                                                          */

void wr_scene_run_contact_json(const wr_scene_run *run, cJSON *obj) {
    const wr_statics_stats *last;
    if (run->sc->n_obstacles == 0) return;
    cJSON_AddNumberToObject(obj, "obstacles", run->sc->n_obstacles);
    if (run->n_steps_done == 0) return;
    last = &run->steps[run->n_steps_done - 1].st;
    cJSON_AddNumberToObject(obj, "min_obstacle_distance_m", last->min_distance);
    cJSON_AddNumberToObject(obj, "contact_vertices", last->n_contacts);
    cJSON_AddNumberToObject(obj, "contact_dhat_m", last->contact_dhat);
    cJSON_AddNumberToObject(obj, "contact_stiffness_N_m", last->contact_stiffness);
}

static wr_status sc_write_summary(const wr_scene_run *run, const char *path, wr_diag *diag) {
    const wr_scene *sc = run->sc;
    cJSON *root = cJSON_CreateObject(), *a, *o;
    wr_status st;
    double Em = 0.0, Eb = 0.0, E = 0.0, maxu = 0.0;
    int32_t i;
    if (!root) return wr_fail(diag, WR_ERR_NOMEM, -1, "summary: out of memory");
    wr_shell_energy_parts(&run->shell, run->x, &Em, &Eb, NULL);
    wr_shell_energy(&run->shell, run->x, &E, NULL, NULL);
    for (i = 0; i < run->mesh.nv; ++i) {
        double dx = run->x[3 * i] - run->mesh.pos[3 * i], dy = run->x[3 * i + 1] - run->mesh.pos[3 * i + 1],
               dz = run->x[3 * i + 2] - run->mesh.pos[3 * i + 2];
        maxu = fmax(maxu, sqrt(dx * dx + dy * dy + dz * dz));
    }
    cJSON_AddStringToObject(root, "scene", sc->name);
    cJSON_AddStringToObject(root, "mesh_type", wr_scene_mesh_kind_name(sc->mesh.kind));
    cJSON_AddNumberToObject(root, "vertices", run->mesh.nv);
    cJSON_AddNumberToObject(root, "faces", run->mesh.nf);
    cJSON_AddNumberToObject(root, "prescribed_vertices", run->n_fixed);
    cJSON_AddNumberToObject(root, "thickness_m", run->shell.thickness);
    cJSON_AddNumberToObject(root, "bending_stiffness_Nm", run->shell.bending_stiffness);
    cJSON_AddNumberToObject(root, "density_kg_m3", run->shell.density);
    cJSON_AddStringToObject(root, "status", wr_status_string(run->solve_status));
    o = cJSON_AddObjectToObject(root, "energy_J");
    cJSON_AddNumberToObject(o, "shell", E);
    cJSON_AddNumberToObject(o, "membrane", Em);
    cJSON_AddNumberToObject(o, "bending", Eb);
    if (run->n_steps_done > 0) {
        const wr_statics_stats *last = &run->steps[run->n_steps_done - 1].st;
        cJSON_AddNumberToObject(o, "total_potential", last->energy);
        cJSON_AddNumberToObject(root, "final_grad_norm_N", last->grad_norm);
        cJSON_AddNumberToObject(root, "final_grad_ref_N", last->grad_ref);
        if (sc->pressure != 0.0) cJSON_AddNumberToObject(root, "enclosed_volume_m3", last->volume);
    }
    if (sc->pressure != 0.0) cJSON_AddNumberToObject(root, "pressure_Pa", sc->pressure);
    wr_scene_run_contact_json(run, root);
    cJSON_AddNumberToObject(root, "max_displacement_m", maxu);
    cJSON_AddNumberToObject(root, "newton_iterations", run->newton_iterations);
    cJSON_AddNumberToObject(root, "linear_iterations", run->linear_iterations);
    o = cJSON_AddObjectToObject(root, "timings_s");
    cJSON_AddNumberToObject(o, "mesh", run->t_mesh);
    cJSON_AddNumberToObject(o, "setup", run->t_setup);
    cJSON_AddNumberToObject(o, "solve", run->t_solve);
    cJSON_AddNumberToObject(o, "assembly", run->t_assembly);
    cJSON_AddNumberToObject(o, "projection", run->t_projection);
    cJSON_AddNumberToObject(o, "linear_solve", run->t_linear);
    cJSON_AddNumberToObject(o, "line_search", run->t_line_search);
    a = cJSON_AddArrayToObject(root, "load_steps");
    for (i = 0; i < run->n_steps_done; ++i) {
        const wr_scene_step_stats *s = &run->steps[i];
        cJSON *e = cJSON_CreateObject();
        cJSON_AddNumberToObject(e, "fraction", s->fraction);
        cJSON_AddStringToObject(e, "status", wr_status_string(s->status));
        cJSON_AddNumberToObject(e, "iterations", s->st.iterations);
        cJSON_AddNumberToObject(e, "grad_norm", s->st.grad_norm);
        cJSON_AddNumberToObject(e, "grad_ref", s->st.grad_ref);
        cJSON_AddNumberToObject(e, "seconds", s->st.t_total);
        cJSON_AddItemToArray(a, e);
    }
    a = cJSON_AddArrayToObject(root, "probes");
    for (i = 0; i < sc->n_probes; ++i) {
        cJSON *e = cJSON_CreateObject();
        wr_spectrum_result r;
        wr_diag pd;
        cJSON_AddStringToObject(e, "name", sc->probe[i].name);
        if (wr_scene_run_probe(run, i, &r, &pd) == WR_OK) {
            cJSON_AddNumberToObject(e, "wavelength_m", r.wavelength);
            cJSON_AddNumberToObject(e, "count", r.count);
            cJSON_AddNumberToObject(e, "count_rounded", r.count_rounded);
            cJSON_AddNumberToObject(e, "wavelength_ls_m", r.wavelength_ls);
            cJSON_AddNumberToObject(e, "zero_crossing_waves", r.zc_waves);
            cJSON_AddNumberToObject(e, "amplitude_m", r.amplitude_p2p);
            cJSON_AddNumberToObject(e, "peak_power_fraction", r.peak_power_fraction);
        } else
            cJSON_AddStringToObject(e, "error", pd.message);
        cJSON_AddItemToArray(a, e);
    }
    st = wr_json_write(root, path, diag);
    cJSON_Delete(root);
    return st;
}

wr_status wr_scene_run_write(const wr_scene_run *run, const char *dir, wr_diag *diag) {
    char path[WR_PATH_MAX];
    wr_mesh m = run->mesh; /* shallow view with pos = deformed */
    int32_t nv = run->mesh.nv, i, f, k;
    double *pv[8], *acc, *w;
    const char *names[8] = {"ux", "uy", "uz", "u_mag", "strain_11", "strain_22", "strain_12", "prescribed"};
    wr_status st;
    wr_obj_desc od;
    if (strlen(dir) + 20 > sizeof path) return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "%s: path too long", dir);
    mkdir(dir, 0777); /* may exist; a real failure shows up when the files are opened */
    m.pos = run->x;
    memset(&od, 0, sizeof od);
    od.comment = run->sc->name;
    od.normals = 1; /* vt (rest) and vn on the deformed surface, for viewers */
    od.group_names = (const char *const *)run->groups.names; /* the input OBJ's panel names */
    od.n_group_names = run->groups.n;
    snprintf(path, sizeof path, "%s/deformed.obj", dir);
    if ((st = wr_mesh_write_obj(&m, path, &od, diag)) != WR_OK) return st;
    acc = (double *)calloc((size_t)nv * 9, sizeof(double));
    if (!acc) return wr_fail(diag, WR_ERR_NOMEM, -1, "fields: out of memory");
    for (k = 0; k < 8; ++k) pv[k] = acc + (size_t)k * nv;
    w = acc + (size_t)8 * nv;
    for (i = 0; i < nv; ++i) {
        double s2 = 0.0;
        for (k = 0; k < 3; ++k) {
            pv[k][i] = run->x[3 * i + k] - run->mesh.pos[3 * i + k];
            s2 += pv[k][i] * pv[k][i];
        }
        pv[3][i] = sqrt(s2);
        pv[7][i] = run->fixed[i] ? 1.0 : 0.0;
    }
    /* Green strain per face (rest frame), area-weighted onto vertices */
    for (f = 0; f < run->mesh.nf; ++f) {
        double eps[3], A = run->shell.area[f];
        wr_shell_face_strain(&run->shell, f, run->x, eps);
        for (k = 0; k < 3; ++k) {
            int32_t v = run->mesh.faces[3 * f + k];
            pv[4][v] += A * eps[0], pv[5][v] += A * eps[1], pv[6][v] += A * eps[2];
            w[v] += A;
        }
    }
    for (i = 0; i < nv; ++i)
        if (w[i] > 0.0) pv[4][i] /= w[i], pv[5][i] /= w[i], pv[6][i] /= w[i];
    snprintf(path, sizeof path, "%s/fields.ply", dir);
    st = wr_mesh_write_ply(&m, path, 8, names, (const double *const *)pv, diag);
    free(acc);
    if (st != WR_OK) return st;
    snprintf(path, sizeof path, "%s/summary.json", dir);
    return sc_write_summary(run, path, diag);
}
