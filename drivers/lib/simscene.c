/* simscene.c — see simscene.h and docs/sim-scene-format.md. Uses cJSON (Debian libcjson-dev); the
 * JSON readers are scene.c's (jsonin.h), so both scene formats check and word errors alike. */
#define _POSIX_C_SOURCE 200809L
#include "simscene.h"

#include "jsonin.h"
#include "jsonout.h"
#include "pattern.h"

#include <cjson/cJSON.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* ---- sections --------------------------------------------------------------------------------- */

static wr_status ss_path_at(wr_jin *d, const cJSON *o, const char *key, const char *P, const char *base_dir, char *out);

static wr_status ss_parse_mesh(wr_jin *d, const cJSON *o, const char *base_dir, wr_simscene_cloth *c) {
    static const char *const keys[] = {"type", "width", "height", "radius", "resolution", "nx", "ny", "path", NULL};
    static const char *const kinds[] = {"rectangle", "disk", "obj", NULL};
    const char *P = "$.cloth.mesh";
    int kind = -1, fw = 0, fh = 0, fr = 0, fres = 0, fnx = 0, fny = 0;
    wr_status st;
    if ((st = wr_jin_keys(d, o, P, keys)) != WR_OK) return st;
    if (!cJSON_GetObjectItemCaseSensitive(o, "type")) return wr_jin_err(d, "$.cloth.mesh.type", "is required");
    if ((st = wr_jin_enum(d, o, "type", P, kinds, &kind, 0)) != WR_OK) return st;
    c->kind = (wr_simscene_mesh_kind)kind;
    if ((st = wr_jin_num(d, o, "width", P, WR_JIN_POS, &c->width, &fw)) != WR_OK) return st;
    if ((st = wr_jin_num(d, o, "height", P, WR_JIN_POS, &c->height, &fh)) != WR_OK) return st;
    if ((st = wr_jin_num(d, o, "radius", P, WR_JIN_POS, &c->radius, &fr)) != WR_OK) return st;
    if ((st = wr_jin_num(d, o, "resolution", P, WR_JIN_POS, &c->resolution, &fres)) != WR_OK) return st;
    if ((st = wr_jin_int(d, o, "nx", P, 1, 100000, &c->nx, &fnx)) != WR_OK) return st;
    if ((st = wr_jin_int(d, o, "ny", P, 1, 100000, &c->ny, &fny)) != WR_OK) return st;
    if (c->kind == WR_SIMSCENE_MESH_RECTANGLE) {
        if (!fw || !fh) return wr_jin_err(d, P, "rectangle needs width and height");
        if (!fres && !(fnx && fny)) return wr_jin_err(d, P, "rectangle needs resolution or nx and ny");
        if (!fnx) c->nx = (int32_t)fmax(1.0, floor(c->width / c->resolution + 0.5));
        if (!fny) c->ny = (int32_t)fmax(1.0, floor(c->height / c->resolution + 0.5));
        if (((double)c->nx + 1) * ((double)c->ny + 1) > WR_SIMSCENE_MAX_VERTICES)
            return wr_jin_err(d, "$.cloth.mesh.resolution", "%d x %d cells exceed %d vertices", (int)c->nx, (int)c->ny,
                          WR_SIMSCENE_MAX_VERTICES);
    } else if (c->kind == WR_SIMSCENE_MESH_DISK) {
        double rings;
        if (!fr || !fres) return wr_jin_err(d, P, "disk needs radius and resolution");
        rings = floor(c->radius / c->resolution + 0.5);
        if (rings < 1.0) rings = 1.0;
        if (1.0 + 3.0 * rings * (rings + 1.0) > WR_SIMSCENE_MAX_VERTICES)
            return wr_jin_err(d, "$.cloth.mesh.resolution", "%g rings exceed %d vertices", rings, WR_SIMSCENE_MAX_VERTICES);
        c->nx = (int32_t)rings;
    } else {
        if ((st = ss_path_at(d, o, "path", P, base_dir, c->path)) != WR_OK) return st;
    }
    return WR_OK;
}

/* $.cloth.material or $.garment.material (P) into a shell desc; areal density kept in *areal. */
static wr_status ss_parse_material(wr_jin *d, const cJSON *o, const char *P, wr_shell_desc *s, double *areal) {
    static const char *const keys[] = {"young", "poisson", "thickness", "bending_stiffness", "density", "areal_density",
                                       "membrane", "bending", NULL};
    static const char *const mem[] = {"stvk", "tft", "none", NULL};
    static const char *const bend[] = {"midedge", "quadratic", "none", NULL};
    char q[128];
    int fE = 0, fh = 0, fB = 0, fd = 0, fa = 0, fnu = 0, m = 0, b = 0;
    wr_status st;
    if ((st = wr_jin_keys(d, o, P, keys)) != WR_OK) return st;
    if ((st = wr_jin_num(d, o, "young", P, WR_JIN_POS, &s->young, &fE)) != WR_OK) return st;
    if ((st = wr_jin_num(d, o, "poisson", P, WR_JIN_ANY, &s->poisson, &fnu)) != WR_OK) return st;
    if (fnu && !(s->poisson > -1.0 && s->poisson <= 0.5)) {
        wr_jin_path(q, sizeof q, P, "poisson");
        return wr_jin_err(d, q, "must be in (-1, 0.5] (got %g)", s->poisson);
    }
    if ((st = wr_jin_num(d, o, "thickness", P, WR_JIN_POS, &s->thickness, &fh)) != WR_OK) return st;
    if ((st = wr_jin_num(d, o, "bending_stiffness", P, WR_JIN_POS, &s->bending_stiffness, &fB)) != WR_OK) return st;
    if ((st = wr_jin_num(d, o, "density", P, WR_JIN_POS, &s->density, &fd)) != WR_OK) return st;
    if ((st = wr_jin_num(d, o, "areal_density", P, WR_JIN_POS, areal, &fa)) != WR_OK) return st;
    if ((st = wr_jin_enum(d, o, "membrane", P, mem, &m, 0)) != WR_OK) return st;
    if ((st = wr_jin_enum(d, o, "bending", P, bend, &b, 0)) != WR_OK) return st;
    s->membrane = (wr_membrane_model)m;
    s->bending = (wr_bending_model)b;
    if (!fE) {
        wr_jin_path(q, sizeof q, P, "young");
        return wr_jin_err(d, q, "is required");
    }
    if (!fh && !fB) return wr_jin_err(d, P, "needs thickness or bending_stiffness");
    if (!fd && !fa) return wr_jin_err(d, P, "needs density or areal_density (a dynamic cloth has mass)");
    if (fd && fa) {
        wr_jin_path(q, sizeof q, P, "areal_density");
        return wr_jin_err(d, q, "give density or areal_density, not both");
    }
    if (!fh) /* Kirchhoff–Love (Style3D Sec. 4.1.1): B = E h³/(12(1−ν²)) solved for h */
        s->thickness = cbrt(12.0 * (1.0 - s->poisson * s->poisson) * s->bending_stiffness / s->young);
    if (fa) s->density = *areal / s->thickness;
    return WR_OK;
}

static wr_status ss_parse_indices(wr_jin *d, const cJSON *idx, const char *P, int32_t **out, int32_t *n) {
    const cJSON *e;
    int32_t k = 0, cnt;
    if (!cJSON_IsArray(idx) || (cnt = cJSON_GetArraySize(idx)) < 1) return wr_jin_err(d, P, "must be a non-empty array");
    *out = (int32_t *)wr_alloc_array((size_t)cnt, sizeof(int32_t));
    if (!*out) return wr_fail(d->diag, WR_ERR_NOMEM, -1, "%s: out of memory", P);
    for (e = idx->child; e; e = e->next, ++k) {
        if (!cJSON_IsNumber(e) || e->valuedouble != floor(e->valuedouble) || e->valuedouble < 0 ||
            e->valuedouble > (double)INT32_MAX) {
            char q[540];
            snprintf(q, sizeof q, "%s[%d]", P, (int)k);
            return wr_jin_err(d, q, "must be a vertex index >= 0");
        }
        (*out)[k] = (int32_t)e->valuedouble;
    }
    *n = cnt;
    return WR_OK;
}

/* pins sets at path P ("$.cloth.pins", "$.garment.pins") */
static wr_status ss_parse_pins(wr_jin *d, const cJSON *pins, const char *P0, wr_simscene_pin *pin, int32_t *n_pins) {
    static const char *const pinkeys[] = {"box", "indices", NULL};
    static const char *const bkeys[] = {"min", "max", NULL};
    const cJSON *e;
    wr_status st;
    int k = 0;
    if (!cJSON_IsArray(pins)) return wr_jin_err(d, P0, "must be an array");
    if (cJSON_GetArraySize(pins) > WR_SIMSCENE_MAX_PINS) return wr_jin_err(d, P0, "at most %d sets", WR_SIMSCENE_MAX_PINS);
    for (e = pins->child; e; e = e->next, ++k) {
        char P[64], q[96];
        const cJSON *box, *idx;
        wr_simscene_pin *p = pin + k;
        snprintf(P, sizeof P, "%s[%d]", P0, k);
        if ((st = wr_jin_keys(d, e, P, pinkeys)) != WR_OK) return st;
        *n_pins = k + 1;
        box = cJSON_GetObjectItemCaseSensitive(e, "box");
        idx = cJSON_GetObjectItemCaseSensitive(e, "indices");
        if (!!box == !!idx) return wr_jin_err(d, P, "needs exactly one of box or indices");
        if (box) {
            int f1 = 0, f2 = 0;
            snprintf(q, sizeof q, "%s.box", P);
            if ((st = wr_jin_keys(d, box, q, bkeys)) != WR_OK) return st;
            if ((st = wr_jin_vec(d, box, "min", q, 3, p->lo, &f1)) != WR_OK) return st;
            if ((st = wr_jin_vec(d, box, "max", q, 3, p->hi, &f2)) != WR_OK) return st;
            if (!f1 || !f2) return wr_jin_err(d, q, "needs min and max");
            p->select_box = 1;
        } else {
            snprintf(q, sizeof q, "%s.indices", P);
            if ((st = ss_parse_indices(d, idx, q, &p->indices, &p->n_indices)) != WR_OK) return st;
        }
    }
    return WR_OK;
}

static wr_status ss_parse_cloth(wr_jin *d, const cJSON *o, const char *base_dir, wr_simscene_cloth *c) {
    static const char *const keys[] = {"mesh", "material", "placement", "velocity", "pins", NULL};
    static const char *const pkeys[] = {"rotate", "translate", NULL};
    static const char *const rkeys[] = {"axis", "angle", NULL};
    const cJSON *m, *pl, *pins;
    wr_status st;
    if ((st = wr_jin_keys(d, o, "$.cloth", keys)) != WR_OK) return st;
    if (!(m = cJSON_GetObjectItemCaseSensitive(o, "mesh"))) return wr_jin_err(d, "$.cloth.mesh", "is required");
    if ((st = ss_parse_mesh(d, m, base_dir, c)) != WR_OK) return st;
    if (!(m = cJSON_GetObjectItemCaseSensitive(o, "material"))) return wr_jin_err(d, "$.cloth.material", "is required");
    if ((st = ss_parse_material(d, m, "$.cloth.material", &c->shell, &c->areal_density)) != WR_OK) return st;
    if ((st = wr_jin_vec(d, o, "velocity", "$.cloth", 3, c->velocity, NULL)) != WR_OK) return st;
    if ((pl = cJSON_GetObjectItemCaseSensitive(o, "placement"))) {
        const cJSON *r;
        if ((st = wr_jin_keys(d, pl, "$.cloth.placement", pkeys)) != WR_OK) return st;
        if ((st = wr_jin_vec(d, pl, "translate", "$.cloth.placement", 3, c->translate, NULL)) != WR_OK) return st;
        if ((r = cJSON_GetObjectItemCaseSensitive(pl, "rotate"))) {
            int fa = 0, fang = 0;
            const char *R = "$.cloth.placement.rotate";
            if ((st = wr_jin_keys(d, r, R, rkeys)) != WR_OK) return st;
            if ((st = wr_jin_vec(d, r, "axis", R, 3, c->rotate_axis, &fa)) != WR_OK) return st;
            if ((st = wr_jin_num(d, r, "angle", R, WR_JIN_ANY, &c->rotate_angle, &fang)) != WR_OK) return st;
            if (!fa || !fang) return wr_jin_err(d, R, "needs axis and angle [rad]");
            if (!(c->rotate_axis[0] * c->rotate_axis[0] + c->rotate_axis[1] * c->rotate_axis[1] +
                      c->rotate_axis[2] * c->rotate_axis[2] >
                  0.0))
                return wr_jin_err(d, "$.cloth.placement.rotate.axis", "must not be zero");
        }
    }
    if ((pins = cJSON_GetObjectItemCaseSensitive(o, "pins")) && (st = ss_parse_pins(d, pins, "$.cloth.pins", c->pin, &c->n_pins)) != WR_OK)
        return st;
    return WR_OK;
}

/* A file path from the scene (JSON path q), relative to the scene's directory unless absolute. */
static wr_status ss_resolve(wr_jin *d, const char *rel, const char *q, const char *base_dir, char *out) {
    if (!rel[0]) return wr_jin_err(d, q, "must be a non-empty string");
    if (rel[0] == '/' || !base_dir || !base_dir[0])
        snprintf(out, WR_SIMSCENE_PATH_LEN, "%s", rel);
    else if ((size_t)snprintf(out, WR_SIMSCENE_PATH_LEN, "%s/%s", base_dir, rel) >= WR_SIMSCENE_PATH_LEN)
        return wr_jin_err(d, q, "path too long");
    return WR_OK;
}

static wr_status ss_path_at(wr_jin *d, const cJSON *o, const char *key, const char *P, const char *base_dir, char *out) {
    char rel[WR_SIMSCENE_PATH_LEN], q[160];
    wr_status st = wr_jin_str(d, o, key, P, rel, sizeof rel, 1);
    if (st != WR_OK) return st;
    wr_jin_path(q, sizeof q, P, key);
    return ss_resolve(d, rel, q, base_dir, out);
}

static wr_status ss_parse_obstacles(wr_jin *d, const cJSON *arr, const char *base_dir, wr_simscene *sc) {
    static const char *const keys[] = {"type", "point", "normal", "center", "radius", "p", "q", "path", NULL};
    static const char *const kinds[] = {"plane", "sphere", "capsule", "mesh", NULL};
    const cJSON *e;
    int k = 0;
    wr_status st;
    if (!cJSON_IsArray(arr)) return wr_jin_err(d, "$.obstacles", "must be an array");
    if (cJSON_GetArraySize(arr) > WR_SIMSCENE_MAX_OBSTACLES)
        return wr_jin_err(d, "$.obstacles", "at most %d obstacles", WR_SIMSCENE_MAX_OBSTACLES);
    for (e = arr->child; e; e = e->next, ++k) {
        char P[64];
        int kind = -1;
        wr_obstacle *o = sc->analytic + sc->n_analytic;
        snprintf(P, sizeof P, "$.obstacles[%d]", k);
        if ((st = wr_jin_keys(d, e, P, keys)) != WR_OK) return st;
        if ((st = wr_jin_enum(d, e, "type", P, kinds, &kind, 1)) != WR_OK) return st;
        if (kind == 3) { /* a triangle mesh from an OBJ, static (dynamics.h wr_dyn_body) */
            static const char *const mkeys[] = {"type", "path", NULL};
            if ((st = wr_jin_keys(d, e, P, mkeys)) != WR_OK) return st;
            if ((st = ss_path_at(d, e, "path", P, base_dir, sc->mesh_obstacle[sc->n_mesh_obstacles])) != WR_OK) return st;
            sc->mesh_obstacle_index[sc->n_mesh_obstacles++] = k;
            continue;
        }
        memset(o, 0, sizeof *o);
        o->kind = (wr_obstacle_kind)kind;
        if ((st = wr_jin_analytic_obstacle(d, e, P, o)) != WR_OK) return st;
        sc->n_analytic++;
    }
    return WR_OK;
}

/* $.body: the mannequin, a static OBJ, or an OBJ sequence (keys at times, or at fps). */
static wr_status ss_parse_body(wr_jin *d, const cJSON *o, const char *base_dir, wr_simscene_body *b) {
    static const char *const keys[] = {"type", "height", "target_faces", "cell", "path", "paths", "times", "fps", NULL};
    static const char *const kinds[] = {"mannequin", "obj", "obj_sequence", NULL};
    const char *P = "$.body";
    int kind = 0, fh = 0, ft = 0, fc = 0;
    wr_status st;
    if ((st = wr_jin_keys(d, o, P, keys)) != WR_OK) return st;
    if ((st = wr_jin_enum(d, o, "type", P, kinds, &kind, 1)) != WR_OK) return st;
    b->kind = (wr_simscene_body_kind)(kind + 1);
    if (b->kind == WR_SIMSCENE_BODY_MANNEQUIN) {
        static const char *const mkeys[] = {"type", "height", "target_faces", "cell", NULL};
        if ((st = wr_jin_keys(d, o, P, mkeys)) != WR_OK) return st;
        if ((st = wr_jin_num(d, o, "height", P, WR_JIN_POS, &b->mannequin.height, &fh)) != WR_OK) return st;
        if ((st = wr_jin_int(d, o, "target_faces", P, WR_BODY_MIN_FACES, 2000000, &b->mannequin.target_faces, &ft)) != WR_OK)
            return st;
        if ((st = wr_jin_num(d, o, "cell", P, WR_JIN_POS, &b->mannequin.cell, &fc)) != WR_OK) return st;
        return WR_OK;
    }
    if (b->kind == WR_SIMSCENE_BODY_OBJ) {
        static const char *const okeys[] = {"type", "path", NULL};
        if ((st = wr_jin_keys(d, o, P, okeys)) != WR_OK) return st;
        return ss_path_at(d, o, "path", P, base_dir, b->path);
    }
    {
        static const char *const skeys[] = {"type", "paths", "times", "fps", NULL};
        const cJSON *paths = cJSON_GetObjectItemCaseSensitive(o, "paths"), *times = cJSON_GetObjectItemCaseSensitive(o, "times"), *e;
        double fps = 0.0;
        int ffps = 0;
        int32_t k = 0, n;
        if ((st = wr_jin_keys(d, o, P, skeys)) != WR_OK) return st;
        if (!cJSON_IsArray(paths) || (n = cJSON_GetArraySize(paths)) < 2 || n > WR_SIMSCENE_MAX_BODY_KEYS)
            return wr_jin_err(d, "$.body.paths", "must be an array of 2 to %d OBJ paths", WR_SIMSCENE_MAX_BODY_KEYS);
        if ((st = wr_jin_num(d, o, "fps", P, WR_JIN_POS, &fps, &ffps)) != WR_OK) return st;
        if (!!times == !!ffps) return wr_jin_err(d, P, "an obj_sequence needs exactly one of times or fps");
        if (times && (!cJSON_IsArray(times) || cJSON_GetArraySize(times) != n))
            return wr_jin_err(d, "$.body.times", "must be an array of %d times [s], one per path", (int)n);
        b->paths = (char(*)[WR_SIMSCENE_PATH_LEN])wr_alloc_array((size_t)n, WR_SIMSCENE_PATH_LEN);
        b->times = (double *)wr_alloc_array((size_t)n, sizeof(double));
        if (!b->paths || !b->times) return wr_fail(d->diag, WR_ERR_NOMEM, -1, "$.body: out of memory");
        b->n_keys = n;
        for (e = paths->child; e; e = e->next, ++k) {
            char q[64];
            snprintf(q, sizeof q, "$.body.paths[%d]", (int)k);
            if (!cJSON_IsString(e) || strlen(e->valuestring) >= WR_SIMSCENE_PATH_LEN) return wr_jin_err(d, q, "must be a path");
            if ((st = ss_resolve(d, e->valuestring, q, base_dir, b->paths[k])) != WR_OK) return st;
            b->times[k] = k / (ffps ? fps : 1.0);
        }
        if (times)
            for (k = 0, e = times->child; e; e = e->next, ++k) {
                char q[64];
                snprintf(q, sizeof q, "$.body.times[%d]", (int)k);
                if (!cJSON_IsNumber(e) || !isfinite(e->valuedouble)) return wr_jin_err(d, q, "must be a finite number");
                b->times[k] = e->valuedouble;
                if (k > 0 && !(b->times[k] > b->times[k - 1])) return wr_jin_err(d, q, "times must increase");
            }
    }
    return WR_OK;
}

/* $.garment.placements[i] */
static wr_status ss_parse_placement(wr_jin *d, const cJSON *e, const char *P, wr_simscene_placement *sp) {
    static const char *const keys[] = {"panel", "origin", "cylinder", "rigid", NULL};
    static const char *const ckeys[] = {"radius", "angle", "point", "axis", "ref", "part", "offset", NULL};
    static const char *const rkeys[] = {"rotate", "translate", NULL};
    static const char *const rotkeys[] = {"axis", "angle", NULL};
    const cJSON *pn, *cyl, *rig;
    char q[128], r[160];
    wr_status st;
    if ((st = wr_jin_keys(d, e, P, keys)) != WR_OK) return st;
    pn = cJSON_GetObjectItemCaseSensitive(e, "panel");
    wr_jin_path(q, sizeof q, P, "panel");
    sp->panel_index = -1;
    if (!pn) return wr_jin_err(d, q, "is required (a panel name or index of the pattern)");
    if (cJSON_IsNumber(pn)) {
        if (pn->valuedouble != floor(pn->valuedouble) || pn->valuedouble < 0 || pn->valuedouble > 1e6)
            return wr_jin_err(d, q, "must be a panel index >= 0 or a name");
        sp->panel_index = (int32_t)pn->valuedouble;
    } else if ((st = wr_jin_str(d, e, "panel", P, sp->panel, sizeof sp->panel, 1)) != WR_OK) {
        return st;
    }
    if ((st = wr_jin_vec(d, e, "origin", P, 2, sp->pl.origin, &sp->has_origin)) != WR_OK) return st;
    cyl = cJSON_GetObjectItemCaseSensitive(e, "cylinder");
    rig = cJSON_GetObjectItemCaseSensitive(e, "rigid");
    if (!!cyl == !!rig) return wr_jin_err(d, P, "needs exactly one of cylinder or rigid");
    if (cyl) {
        int fr = 0;
        wr_jin_path(q, sizeof q, P, "cylinder");
        sp->pl.kind = WR_GARMENT_CYLINDER;
        if ((st = wr_jin_keys(d, cyl, q, ckeys)) != WR_OK) return st;
        if ((st = wr_jin_num(d, cyl, "radius", q, WR_JIN_POS, &sp->pl.cylinder.radius, &fr)) != WR_OK) return st;
        if (!fr) {
            wr_jin_path(r, sizeof r, q, "radius");
            return wr_jin_err(d, r, "is required [m]");
        }
        if ((st = wr_jin_num(d, cyl, "angle", q, WR_JIN_ANY, &sp->pl.cylinder.angle, NULL)) != WR_OK) return st;
        if ((st = wr_jin_vec(d, cyl, "point", q, 3, sp->pl.cylinder.point, NULL)) != WR_OK) return st;
        if ((st = wr_jin_vec(d, cyl, "axis", q, 3, sp->pl.cylinder.axis, NULL)) != WR_OK) return st;
        if ((st = wr_jin_vec(d, cyl, "ref", q, 3, sp->pl.cylinder.ref, NULL)) != WR_OK) return st;
        if ((st = wr_jin_num(d, cyl, "offset", q, WR_JIN_ANY, &sp->offset, NULL)) != WR_OK) return st;
        if (cJSON_GetObjectItemCaseSensitive(cyl, "part")) {
            if ((st = wr_jin_str(d, cyl, "part", q, sp->part, sizeof sp->part, 1)) != WR_OK) return st;
            if (cJSON_GetObjectItemCaseSensitive(cyl, "point") || cJSON_GetObjectItemCaseSensitive(cyl, "axis"))
                return wr_jin_err(d, q, "give part (and offset) or point and axis, not both");
        }
    } else {
        const cJSON *rot;
        wr_jin_path(q, sizeof q, P, "rigid");
        sp->pl.kind = WR_GARMENT_RIGID;
        if ((st = wr_jin_keys(d, rig, q, rkeys)) != WR_OK) return st;
        if ((st = wr_jin_vec(d, rig, "translate", q, 3, sp->pl.rigid.translate, NULL)) != WR_OK) return st;
        if ((rot = cJSON_GetObjectItemCaseSensitive(rig, "rotate"))) {
            int fa = 0, fang = 0;
            wr_jin_path(r, sizeof r, q, "rotate");
            if ((st = wr_jin_keys(d, rot, r, rotkeys)) != WR_OK) return st;
            if ((st = wr_jin_vec(d, rot, "axis", r, 3, sp->pl.rigid.axis, &fa)) != WR_OK) return st;
            if ((st = wr_jin_num(d, rot, "angle", r, WR_JIN_ANY, &sp->pl.rigid.angle, &fang)) != WR_OK) return st;
            if (!fa || !fang) return wr_jin_err(d, r, "needs axis and angle [rad]");
        }
    }
    return WR_OK;
}

/* $.garment */
static wr_status ss_parse_garment(wr_jin *d, const cJSON *o, const char *base_dir, wr_simscene_garment *g) {
    static const char *const keys[] = {"pattern", "resolution", "seed", "material", "placements", "sewing", "gathering", "velocity",
                                       "pins", "gravity_hold", NULL};
    static const char *const gkeys[] = {"enabled", "thread_area", "time", "immediate", "stitch_edges", NULL};
    static const char *const skeys[] = {"stiffness", "start_stiffness", "weld_tolerance", "max_time", "weld",
                                        "self_contact", NULL};
    static const char *const hkeys[] = {"delay", "ramp", NULL};
    const cJSON *m, *arr, *e, *sw, *pins, *ga, *ho;
    wr_status st;
    int32_t k = 0;
    if ((st = wr_jin_keys(d, o, "$.garment", keys)) != WR_OK) return st;
    if ((st = ss_path_at(d, o, "pattern", "$.garment", base_dir, g->pattern)) != WR_OK) return st;
    if ((st = wr_jin_num(d, o, "resolution", "$.garment", WR_JIN_POS, &g->resolution, NULL)) != WR_OK) return st;
    if ((st = wr_jin_int(d, o, "seed", "$.garment", 0, INT32_MAX, &g->seed, &g->has_seed)) != WR_OK) return st;
    if (!(m = cJSON_GetObjectItemCaseSensitive(o, "material"))) return wr_jin_err(d, "$.garment.material", "is required");
    if ((st = ss_parse_material(d, m, "$.garment.material", &g->shell, &g->areal_density)) != WR_OK) return st;
    if ((st = wr_jin_vec(d, o, "velocity", "$.garment", 3, g->velocity, NULL)) != WR_OK) return st;
    if ((pins = cJSON_GetObjectItemCaseSensitive(o, "pins")) && (st = ss_parse_pins(d, pins, "$.garment.pins", g->pin, &g->n_pins)) != WR_OK)
        return st;
    arr = cJSON_GetObjectItemCaseSensitive(o, "placements");
    if (!cJSON_IsArray(arr) || cJSON_GetArraySize(arr) < 1)
        return wr_jin_err(d, "$.garment.placements", "is required: one placement per panel");
    g->placements = (wr_simscene_placement *)wr_calloc_array((size_t)cJSON_GetArraySize(arr), sizeof(wr_simscene_placement));
    if (!g->placements) return wr_fail(d->diag, WR_ERR_NOMEM, -1, "$.garment.placements: out of memory");
    for (e = arr->child; e; e = e->next, ++k) {
        char P[64];
        snprintf(P, sizeof P, "$.garment.placements[%d]", (int)k);
        g->n_placements = k + 1;
        if ((st = ss_parse_placement(d, e, P, g->placements + k)) != WR_OK) return st;
    }
    if ((sw = cJSON_GetObjectItemCaseSensitive(o, "sewing"))) {
        const char *S = "$.garment.sewing";
        int weld = 1, self = 1;
        if ((st = wr_jin_keys(d, sw, S, skeys)) != WR_OK) return st;
        if ((st = wr_jin_num(d, sw, "stiffness", S, WR_JIN_POS, &g->sewing.stiffness, NULL)) != WR_OK) return st;
        if ((st = wr_jin_num(d, sw, "start_stiffness", S, WR_JIN_POS, &g->sewing.start_stiffness, NULL)) != WR_OK) return st;
        if ((st = wr_jin_num(d, sw, "weld_tolerance", S, WR_JIN_POS, &g->sewing.weld_tol, NULL)) != WR_OK) return st;
        if ((st = wr_jin_num(d, sw, "max_time", S, WR_JIN_POS, &g->sewing.max_time, NULL)) != WR_OK) return st;
        if ((st = wr_jin_bool(d, sw, "weld", S, &weld)) != WR_OK) return st;
        if ((st = wr_jin_bool(d, sw, "self_contact", S, &self)) != WR_OK) return st;
        g->sewing.no_weld = !weld;
        g->sewing.no_self_while_sewing = !self;
    }
    if ((ga = cJSON_GetObjectItemCaseSensitive(o, "gathering"))) { /* garment.h ON GATHERING */
        const char *S = "$.garment.gathering";
        int on = 1, imm = 0;
        if ((st = wr_jin_keys(d, ga, S, gkeys)) != WR_OK) return st;
        if ((st = wr_jin_bool(d, ga, "enabled", S, &on)) != WR_OK) return st;
        if ((st = wr_jin_num(d, ga, "thread_area", S, WR_JIN_POS, &g->sewing.thread_area, NULL)) != WR_OK) return st;
        if ((st = wr_jin_num(d, ga, "time", S, WR_JIN_POS, &g->sewing.gather_time, NULL)) != WR_OK) return st;
        if ((st = wr_jin_bool(d, ga, "immediate", S, &imm)) != WR_OK) return st;
        if ((st = wr_jin_int(d, ga, "stitch_edges", S, 1, 1000, &g->sewing.stitch_edges, NULL)) != WR_OK) return st;
        g->no_gathering = !on;
        g->sewing.gather_immediate = imm;
    }
    if ((ho = cJSON_GetObjectItemCaseSensitive(o, "gravity_hold"))) { /* garment.h ON HOLDING */
        const char *S = "$.garment.gravity_hold";
        if ((st = wr_jin_keys(d, ho, S, hkeys)) != WR_OK) return st;
        if ((st = wr_jin_num(d, ho, "delay", S, WR_JIN_NONNEG, &g->sewing.gravity_delay, NULL)) != WR_OK) return st;
        if ((st = wr_jin_num(d, ho, "ramp", S, WR_JIN_NONNEG, &g->sewing.gravity_ramp, NULL)) != WR_OK) return st;
    }
    return WR_OK;
}

static wr_status ss_parse_settings(wr_jin *d, const cJSON *root, wr_simscene *sc) {
    static const char *const tkeys[] = {"duration", "dt", "substeps", "max_halvings", NULL};
    static const char *const dkeys[] = {"mass", "stiffness", NULL};
    static const char *const ckeys[] = {"dhat", "stiffness", "friction", "friction_eps_v", "self", NULL};
    static const char *const skeys[] = {"linear", "linear_tol", "linear_forcing", "max_iter", "velocity_tol", "grad_tol",
                                        "hessian", NULL};
    static const char *const okeys[] = {"every", "format", NULL};
    static const char *const lin[] = {"auto", "pcg-jacobi", "pcg-block3", "pcg-ic0", "cholmod", "pcg-amg", NULL};
    static const char *const hess[] = {"projected", "jacobi", "exact", NULL};
    static const char *const fmt[] = {"obj", "ply", NULL};
    wr_dyn_desc *dd = &sc->dyn;
    const cJSON *o;
    wr_status st;
    int f = 0, e = 0;
    if ((st = wr_jin_vec(d, root, "gravity", "$", 3, dd->gravity, NULL)) != WR_OK) return st;
    if ((o = cJSON_GetObjectItemCaseSensitive(root, "time"))) {
        if ((st = wr_jin_keys(d, o, "$.time", tkeys)) != WR_OK) return st;
        if ((st = wr_jin_num(d, o, "duration", "$.time", WR_JIN_NONNEG, &sc->duration, NULL)) != WR_OK) return st;
        if ((st = wr_jin_num(d, o, "dt", "$.time", WR_JIN_POS, &dd->time.dt, NULL)) != WR_OK) return st;
        if ((st = wr_jin_int(d, o, "substeps", "$.time", 1, 1000, &dd->time.substeps, NULL)) != WR_OK) return st;
        if ((st = wr_jin_int(d, o, "max_halvings", "$.time", 0, 30, &dd->time.max_halvings, &f)) != WR_OK) return st;
        dd->time.has_max_halvings = f;
    }
    if (sc->duration / dd->time.dt > WR_SIMSCENE_MAX_FRAMES)
        return wr_jin_err(d, "$.time.duration", "%g s at dt %g s is more than %d frames", sc->duration, dd->time.dt,
                      WR_SIMSCENE_MAX_FRAMES);
    if ((o = cJSON_GetObjectItemCaseSensitive(root, "damping"))) {
        if ((st = wr_jin_keys(d, o, "$.damping", dkeys)) != WR_OK) return st;
        if ((st = wr_jin_num(d, o, "mass", "$.damping", WR_JIN_NONNEG, &dd->damping.mass, NULL)) != WR_OK) return st;
        if ((st = wr_jin_num(d, o, "stiffness", "$.damping", WR_JIN_NONNEG, &dd->damping.stiffness, NULL)) != WR_OK) return st;
    }
    if ((o = cJSON_GetObjectItemCaseSensitive(root, "contact"))) {
        if ((st = wr_jin_keys(d, o, "$.contact", ckeys)) != WR_OK) return st;
        if ((st = wr_jin_num(d, o, "dhat", "$.contact", WR_JIN_POS, &dd->contact.dhat, NULL)) != WR_OK) return st;
        if ((st = wr_jin_num(d, o, "stiffness", "$.contact", WR_JIN_POS, &dd->contact.stiffness, NULL)) != WR_OK) return st;
        if ((st = wr_jin_num(d, o, "friction", "$.contact", WR_JIN_NONNEG, &dd->contact.friction, NULL)) != WR_OK) return st;
        if ((st = wr_jin_num(d, o, "friction_eps_v", "$.contact", WR_JIN_POS, &dd->contact.friction_eps_v, NULL)) != WR_OK)
            return st;
        {
            int self = 1;
            if ((st = wr_jin_bool(d, o, "self", "$.contact", &self)) != WR_OK) return st;
            dd->contact.no_self = !self;
        }
    }
    if ((o = cJSON_GetObjectItemCaseSensitive(root, "solver"))) {
        int m = 0, h = 0;
        if ((st = wr_jin_keys(d, o, "$.solver", skeys)) != WR_OK) return st;
        if ((st = wr_jin_enum(d, o, "linear", "$.solver", lin, &m, 0)) != WR_OK) return st;
        dd->linear.method = (wr_solver_method)m;
        if ((st = wr_jin_num(d, o, "linear_tol", "$.solver", WR_JIN_POS, &dd->linear.rel_tol, &f)) != WR_OK) return st;
        if (f && !(dd->linear.rel_tol < 1.0)) return wr_jin_err(d, "$.solver.linear_tol", "must be < 1");
        if ((st = wr_jin_num(d, o, "linear_forcing", "$.solver", WR_JIN_NONNEG, &dd->newton.forcing, &f)) != WR_OK) return st;
        if (f && !(dd->newton.forcing < 1.0)) return wr_jin_err(d, "$.solver.linear_forcing", "must be < 1");
        if ((st = wr_jin_int(d, o, "max_iter", "$.solver", 1, 100000, &dd->newton.max_iter, NULL)) != WR_OK) return st;
        if ((st = wr_jin_num(d, o, "velocity_tol", "$.solver", WR_JIN_POS, &dd->newton.velocity_tol, NULL)) != WR_OK) return st;
        if ((st = wr_jin_num(d, o, "grad_tol", "$.solver", WR_JIN_POS, &dd->newton.grad_tol, NULL)) != WR_OK) return st;
        if ((st = wr_jin_enum(d, o, "hessian", "$.solver", hess, &h, 0)) != WR_OK) return st;
        dd->newton.projection = h == 0 ? WR_PROJECT_FAST : h == 1 ? WR_PROJECT_JACOBI : WR_PROJECT_NONE;
    }
    if ((o = cJSON_GetObjectItemCaseSensitive(root, "output"))) {
        if ((st = wr_jin_keys(d, o, "$.output", okeys)) != WR_OK) return st;
        if ((st = wr_jin_int(d, o, "every", "$.output", 1, 1000000, &sc->output_every, NULL)) != WR_OK) return st;
        if ((st = wr_jin_enum(d, o, "format", "$.output", fmt, &e, 0)) != WR_OK) return st;
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
    for (i = 0; i < WR_SIMSCENE_MAX_PINS; ++i) {
        wr_free(sc->cloth.pin[i].indices);
        wr_free(sc->garment.pin[i].indices);
    }
    wr_free(sc->garment.placements);
    wr_free(sc->body.paths);
    wr_free(sc->body.times);
    memset(sc, 0, sizeof *sc);
}

wr_status wr_simscene_parse(wr_simscene *sc, const char *text, size_t len, const char *base_dir, wr_diag *diag) {
    static const char *const keys[] = {"name", "cloth", "garment", "body", "obstacles", "gravity", "time", "damping",
                                       "contact", "solver", "output", NULL};
    cJSON *root;
    const cJSON *o, *cl, *ga;
    wr_status st;
    wr_jin c;
    c.diag = diag;
    wr_simscene_defaults(sc);
    root = cJSON_ParseWithLength(text, len);
    if (!root)
        return wr_jin_err(&c, "$", "not valid JSON (near byte %ld)", (long)(cJSON_GetErrorPtr() ? cJSON_GetErrorPtr() - text : 0));
    if ((st = wr_jin_keys(&c, root, "$", keys)) != WR_OK) goto done;
    if ((st = wr_jin_str(&c, root, "name", "$", sc->name, sizeof sc->name, 0)) != WR_OK) goto done;
    cl = cJSON_GetObjectItemCaseSensitive(root, "cloth");
    ga = cJSON_GetObjectItemCaseSensitive(root, "garment");
    if (!!cl == !!ga) {
        st = wr_jin_err(&c, "$", "needs exactly one of cloth (a sheet) or garment (a sewn pattern)");
        goto done;
    }
    sc->is_garment = ga != NULL;
    if (cl && (st = ss_parse_cloth(&c, cl, base_dir, &sc->cloth)) != WR_OK) goto done;
    if (ga && (st = ss_parse_garment(&c, ga, base_dir, &sc->garment)) != WR_OK) goto done;
    if ((o = cJSON_GetObjectItemCaseSensitive(root, "body")) && (st = ss_parse_body(&c, o, base_dir, &sc->body)) != WR_OK)
        goto done;
    if ((o = cJSON_GetObjectItemCaseSensitive(root, "obstacles")) && (st = ss_parse_obstacles(&c, o, base_dir, sc)) != WR_OK)
        goto done;
    st = ss_parse_settings(&c, root, sc);
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

int32_t wr_simscene_inputs(const wr_simscene *sc, const char **list, int32_t max) {
    int32_t n = 0, k;
    if (!sc->is_garment && sc->cloth.kind == WR_SIMSCENE_MESH_OBJ && n < max) list[n++] = sc->cloth.path;
    if (sc->is_garment && n < max) list[n++] = sc->garment.pattern;
    if (sc->body.kind == WR_SIMSCENE_BODY_OBJ && n < max) list[n++] = sc->body.path;
    for (k = 0; k < sc->body.n_keys && n < max; ++k) list[n++] = sc->body.paths[k];
    for (k = 0; k < sc->n_mesh_obstacles && n < max; ++k) list[n++] = sc->mesh_obstacle[k];
    return n;
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

static wr_status ss_pins(wr_simscene_run *run, const wr_simscene_pin *pin, int32_t n_pins, const char *P, wr_diag *diag) {
    int32_t k, v, i;
    for (k = 0; k < n_pins; ++k) {
        const wr_simscene_pin *p = pin + k;
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
                    return wr_fail(diag, WR_ERR_PARSE, k, "%s[%d].indices[%d]: vertex %d >= vertex count %d", P, (int)k, (int)i,
                                   (int)p->indices[i], (int)run->mesh.nv);
                run->fixed[p->indices[i]] = 1, hit++;
            }
        }
        if (!hit) return wr_fail(diag, WR_ERR_PARSE, k, "%s[%d]: selects no vertex", P, (int)k);
    }
    for (v = 0; v < run->mesh.nv; ++v) run->n_fixed += run->fixed[v];
    return WR_OK;
}

void wr_simscene_run_free(wr_simscene_run *run) {
    int32_t i;
    if (!run) return;
    wr_dyn_free(&run->sim);
    wr_shell_free(&run->shell);
    wr_garment_sim_free(&run->gs);
    wr_mesher_free(&run->mr);
    for (i = 0; i < run->n_glines; ++i) wr_free(run->gline_verts[i]), wr_free(run->gline_xy ? run->gline_xy[i] : NULL);
    wr_free(run->gline_verts);
    wr_free(run->gline_xy);
    wr_free(run->glines);
    for (i = 0; i < run->n_panels; ++i) wr_free(run->panel_names ? run->panel_names[i] : NULL);
    wr_free(run->panel_names);
    for (i = 0; i < 1 + WR_SIMSCENE_MAX_OBSTACLES; ++i) wr_mesh_free(&run->bodies[i]);
    wr_free(run->body_key_pos);
    wr_free(run->body_key_time);
    wr_mesh_free(&run->mesh);
    wr_free(run->fixed);
    wr_free(run->x);
    wr_free(run->v);
    wr_free(run->frames);
    memset(run, 0, sizeof *run);
}

/* An OBJ read for $.body / $.obstacles[k] (P), errors prefixed with P. */
static wr_status ss_read_obj(const char *path, const char *P, wr_mesh *m, wr_diag *diag) {
    wr_status st = wr_mesh_read_obj(m, path, diag);
    if (st != WR_OK) {
        char msg[WR_DIAG_MESSAGE_LEN];
        snprintf(msg, sizeof msg, "%s", diag ? diag->message : "");
        return wr_fail(diag, st, -1, "%s: %s", P, msg);
    }
    return WR_OK;
}

/* The triangle-mesh bodies: $.body first (mannequin, OBJ, OBJ keys), then every mesh obstacle. */
static wr_status ss_bodies(wr_simscene_run *run, wr_diag *diag) {
    const wr_simscene *sc = run->sc;
    const wr_simscene_body *b = &sc->body;
    wr_status st;
    int32_t k, i;
    if (b->kind == WR_SIMSCENE_BODY_MANNEQUIN) {
        if ((st = wr_body_mannequin(&run->bodies[0], &b->mannequin, diag)) != WR_OK) {
            char msg[WR_DIAG_MESSAGE_LEN];
            snprintf(msg, sizeof msg, "%s", diag ? diag->message : "");
            return wr_fail(diag, st, -1, "$.body: %s", msg);
        }
    } else if (b->kind == WR_SIMSCENE_BODY_OBJ) {
        if ((st = ss_read_obj(b->path, "$.body.path", &run->bodies[0], diag)) != WR_OK) return st;
    } else if (b->kind == WR_SIMSCENE_BODY_SEQUENCE) {
        wr_mesh key;
        if ((st = ss_read_obj(b->paths[0], "$.body.paths[0]", &run->bodies[0], diag)) != WR_OK) return st;
        run->body_key_pos = (double *)wr_alloc_array((size_t)b->n_keys * 3 * (size_t)run->bodies[0].nv, sizeof(double));
        run->body_key_time = (double *)wr_alloc_array((size_t)b->n_keys, sizeof(double));
        if (!run->body_key_pos || !run->body_key_time) return wr_fail(diag, WR_ERR_NOMEM, -1, "$.body: out of memory");
        for (k = 0; k < b->n_keys; ++k) {
            char P[64];
            snprintf(P, sizeof P, "$.body.paths[%d]", (int)k);
            if ((st = ss_read_obj(b->paths[k], P, &key, diag)) != WR_OK) return st;
            if (key.nv != run->bodies[0].nv || key.nf != run->bodies[0].nf ||
                memcmp(key.faces, run->bodies[0].faces, sizeof(int32_t) * 3 * (size_t)key.nf) != 0) {
                wr_mesh_free(&key);
                return wr_fail(diag, WR_ERR_PARSE, k, "%s: %s has another topology than paths[0] (every key must have the same vertices and faces)",
                               P, b->paths[k]);
            }
            memcpy(run->body_key_pos + 3 * (size_t)key.nv * k, key.pos, sizeof(double) * 3 * (size_t)key.nv);
            run->body_key_time[k] = b->times[k];
            wr_mesh_free(&key);
        }
    }
    run->n_bodies = b->kind != WR_SIMSCENE_BODY_NONE;
    for (k = 0; k < sc->n_mesh_obstacles; ++k) {
        char P[64];
        snprintf(P, sizeof P, "$.obstacles[%d].path", (int)sc->mesh_obstacle_index[k]);
        if ((st = ss_read_obj(sc->mesh_obstacle[k], P, &run->bodies[run->n_bodies], diag)) != WR_OK) return st;
        run->n_bodies++;
    }
    /* the dynamics' view: body 0 gets the keys of a sequence; run->n_bodies counts meshes in use */
    for (i = 0, k = 0; k < 1 + sc->n_mesh_obstacles; ++k) {
        wr_mesh *m = &run->bodies[k];
        wr_dyn_body *db;
        if (!m->faces) continue;
        db = run->dbodies + i++;
        memset(db, 0, sizeof *db);
        db->nv = m->nv;
        db->nf = m->nf;
        db->faces = m->faces;
        db->pos = m->pos;
        if (k == 0 && b->kind == WR_SIMSCENE_BODY_SEQUENCE) {
            db->n_keys = b->n_keys;
            db->key_time = run->body_key_time;
            db->key_pos = run->body_key_pos;
        }
    }
    run->n_bodies = i;
    return WR_OK;
}

/* The panel a placement names, or -1 (message into diag). */
static int32_t ss_find_panel(const wr_simscene_run *run, const wr_simscene_placement *sp, int32_t k, wr_diag *diag) {
    int32_t p;
    if (sp->panel_index >= 0) {
        if (sp->panel_index < run->n_panels) return sp->panel_index;
        wr_fail(diag, WR_ERR_PARSE, k, "$.garment.placements[%d].panel: index %d but the pattern has %d panels", (int)k,
                (int)sp->panel_index, (int)run->n_panels);
        return -1;
    }
    for (p = 0; p < run->n_panels; ++p)
        if (strcmp(run->panel_names[p], sp->panel) == 0) return p;
    wr_fail(diag, WR_ERR_PARSE, k, "$.garment.placements[%d].panel: no panel named \"%s\" in the pattern", (int)k, sp->panel);
    return -1;
}

/* Resolve $.garment.placements against the pattern: one per panel, default origins (bottom centre of
 * the panel's pattern bounding box), cylinders round mannequin parts; into pl[n_panels]. */
static wr_status ss_placements(wr_simscene_run *run, wr_garment_placement *pl, int32_t *which, wr_diag *diag) {
    const wr_simscene_garment *g = &run->sc->garment;
    const wr_mesh *m = &run->mr.mesh;
    wr_body_part parts[WR_BODY_N_PARTS];
    int32_t k, p, v, f;
    for (p = 0; p < run->n_panels; ++p) which[p] = -1;
    wr_body_parts(&run->sc->body.mannequin, parts, WR_BODY_N_PARTS);
    for (k = 0; k < g->n_placements; ++k) {
        const wr_simscene_placement *sp = g->placements + k;
        wr_garment_placement *q;
        if ((p = ss_find_panel(run, sp, k, diag)) < 0) return WR_ERR_PARSE;
        if (which[p] >= 0)
            return wr_fail(diag, WR_ERR_PARSE, k, "$.garment.placements[%d].panel: panel %d '%s' is already placed by placements[%d]",
                           (int)k, (int)p, run->panel_names[p], (int)which[p]);
        which[p] = k;
        q = pl + p;
        *q = sp->pl;
        if (!sp->has_origin) { /* bottom centre of the panel's pattern bounding box */
            double lo[2] = {HUGE_VAL, HUGE_VAL}, hi[2] = {-HUGE_VAL, -HUGE_VAL};
            for (f = 0; f < m->nf; ++f) {
                if (m->face_panel[f] != p) continue;
                for (v = 0; v < 3; ++v) {
                    const double *r = m->rest + 2 * m->faces[3 * f + v];
                    lo[0] = fmin(lo[0], r[0]), lo[1] = fmin(lo[1], r[1]), hi[0] = fmax(hi[0], r[0]), hi[1] = fmax(hi[1], r[1]);
                }
            }
            q->origin[0] = 0.5 * (lo[0] + hi[0]);
            q->origin[1] = lo[1];
        }
        if (sp->part[0]) {
            int32_t i, found = -1;
            if (run->sc->body.kind != WR_SIMSCENE_BODY_MANNEQUIN)
                return wr_fail(diag, WR_ERR_PARSE, k, "$.garment.placements[%d].cylinder.part: needs a $.body of type \"mannequin\"",
                               (int)k);
            for (i = 0; i < WR_BODY_N_PARTS; ++i)
                if (strcmp(parts[i].name, sp->part) == 0) found = i;
            if (found < 0)
                return wr_fail(diag, WR_ERR_PARSE, k, "$.garment.placements[%d].cylinder.part: no mannequin part \"%s\" (torso, neck, "
                               "shoulders, left_upper_arm, left_forearm, right_upper_arm, right_forearm, left_thigh, left_shin, "
                               "right_thigh, right_shin)", (int)k, sp->part);
            {
                const wr_body_part *bp = parts + found;
                double ax[3], l;
                for (i = 0; i < 3; ++i) ax[i] = bp->q[i] - bp->p[i];
                l = sqrt(ax[0] * ax[0] + ax[1] * ax[1] + ax[2] * ax[2]);
                for (i = 0; i < 3; ++i) {
                    q->cylinder.axis[i] = ax[i];
                    q->cylinder.point[i] = bp->p[i] + sp->offset * ax[i] / l;
                }
            }
        }
        if (wr_garment_placement_check(q, k, diag) != WR_OK) {
            char msg[WR_DIAG_MESSAGE_LEN];
            snprintf(msg, sizeof msg, "%s", diag ? diag->message : "");
            return wr_fail(diag, WR_ERR_PARSE, k, "$.garment.placements[%d]: %s", (int)k, msg);
        }
    }
    for (p = 0; p < run->n_panels; ++p)
        if (which[p] < 0)
            return wr_fail(diag, WR_ERR_PARSE, p, "$.garment.placements: panel %d '%s' has no placement", (int)p, run->panel_names[p]);
    return WR_OK;
}

/* The pattern's shirring lines, then every quilt's stitch lines, as gathered lines on the mesher's
 * mesh (garment.h ON GATHERING): each polyline's vertex chain from the constraint segments. */
static wr_status ss_gather_lines(wr_simscene_run *run, const wr_pattern *pat, wr_diag *diag) {
    int32_t n = pat->n_shirrings, i, u, k = 0;
    wr_status st;
    for (i = 0; i < pat->n_quilts; ++i) n += pat->quilts[i].n_lines;
    if (n == 0) return WR_OK;
    run->glines = (wr_garment_line *)wr_calloc_array((size_t)n, sizeof(wr_garment_line));
    run->gline_verts = (int32_t **)wr_calloc_array((size_t)n, sizeof(int32_t *));
    run->gline_xy = (double **)wr_calloc_array((size_t)n, sizeof(double *));
    if (!run->glines || !run->gline_verts || !run->gline_xy) return wr_fail(diag, WR_ERR_NOMEM, -1, "out of memory");
    for (i = 0; i < pat->n_shirrings + pat->n_quilts; ++i) {
        int quilt = i >= pat->n_shirrings;
        int32_t q = i - pat->n_shirrings, nl = quilt ? pat->quilts[q].n_lines : 1;
        for (u = 0; u < nl; ++u, ++k) {
            const double *xy = quilt ? pat->quilts[q].lines[u].xy : pat->shirrings[i].xy;
            int32_t np = quilt ? pat->quilts[q].lines[u].n : pat->shirrings[i].n, nv;
            run->n_glines = k + 1;
            st = wr_garment_line_chain(&run->mr.mesh, run->mr.constraint_segments, run->mr.n_constraint_segments, xy, np,
                                       &run->gline_verts[k], &nv, diag);
            if (st != WR_OK) {
                char msg[WR_DIAG_MESSAGE_LEN];
                snprintf(msg, sizeof msg, "%s", diag ? diag->message : "");
                return quilt ? wr_fail(diag, st, q, "quilts[%d].lines[%d]: %s", (int)q, (int)u, msg)
                             : wr_fail(diag, st, i, "shirring[%d]: %s", (int)i, msg);
            }
            run->glines[k].vertices = run->gline_verts[k];
            run->glines[k].n_vertices = nv;
            run->glines[k].rho = quilt ? pat->quilts[q].rho : pat->shirrings[i].rho;
            run->glines[k].modulus = quilt ? pat->quilts[q].E_sh : pat->shirrings[i].E_sh;
            run->glines[k].stitch_length = quilt ? pat->quilts[q].stitch_length : pat->shirrings[i].stitch_length;
            if (!(run->gline_xy[k] = (double *)wr_alloc_array((size_t)np, 2 * sizeof(double))))
                return wr_fail(diag, WR_ERR_NOMEM, -1, "out of memory");
            memcpy(run->gline_xy[k], xy, sizeof(double) * 2 * (size_t)np);
            run->glines[k].xy = run->gline_xy[k], run->glines[k].n_xy = np;
        }
    }
    return WR_OK;
}

/* Pattern → mesher → placements → pins → garment sim (garment.h). */
static wr_status ss_garment(wr_simscene_run *run, wr_dyn_desc *dd, wr_diag *diag) {
    const wr_simscene_garment *g = &run->sc->garment;
    wr_pattern_file pf;
    wr_garment_placement *pl = NULL;
    int32_t *which = NULL, p, v, i;
    wr_garment gm;
    wr_status st;
    char msg[WR_DIAG_MESSAGE_LEN];
    if ((st = wr_pattern_load(g->pattern, &pf, diag)) != WR_OK) {
        snprintf(msg, sizeof msg, "%s", diag ? diag->message : "");
        return wr_fail(diag, WR_ERR_PARSE, -1, "$.garment.pattern: %s: %s", g->pattern, msg);
    }
    pf.desc.sew = 0; /* the unsewn mesh: garment.h sews */
    if (g->resolution > 0.0) pf.desc.uniform_resolution = g->resolution;
    if (g->has_seed) pf.desc.seed = (uint64_t)g->seed;
    if (pf.desc.max_vertices <= 0 || pf.desc.max_vertices > WR_SIMSCENE_MAX_VERTICES) pf.desc.max_vertices = WR_SIMSCENE_MAX_VERTICES;
    st = wr_mesher_run(&pf.pattern, &pf.desc, &run->mr, diag);
    if (st == WR_OK && !g->no_gathering) st = ss_gather_lines(run, &pf.pattern, diag);
    run->n_panels = pf.pattern.n_panels;
    run->panel_names = (char **)wr_calloc_array((size_t)run->n_panels + 1, sizeof(char *));
    if (st == WR_OK && !run->panel_names) st = wr_fail(diag, WR_ERR_NOMEM, -1, "out of memory");
    for (p = 0; p < run->n_panels && st == WR_OK; ++p) {
        size_t n = strlen(pf.panel_names[p]) + 1;
        if (!(run->panel_names[p] = (char *)wr_alloc_array(n, 1))) st = wr_fail(diag, WR_ERR_NOMEM, -1, "out of memory");
        else memcpy(run->panel_names[p], pf.panel_names[p], n);
    }
    wr_pattern_file_free(&pf);
    if (st != WR_OK) {
        snprintf(msg, sizeof msg, "%s", diag ? diag->message : "");
        return wr_fail(diag, st, diag ? diag->item : -1, "$.garment.pattern: %s: %s", g->pattern, msg);
    }
    pl = (wr_garment_placement *)wr_calloc_array((size_t)run->n_panels, sizeof *pl);
    which = (int32_t *)wr_alloc_array((size_t)run->n_panels, sizeof(int32_t));
    if (!pl || !which) {
        st = wr_fail(diag, WR_ERR_NOMEM, -1, "out of memory");
        goto done;
    }
    if ((st = ss_placements(run, pl, which, diag)) != WR_OK) goto done;
    /* the placed pattern mesh: frames are written on it, pins are selected on it */
    if ((st = wr_mesh_copy(&run->mesh, &run->mr.mesh, diag)) != WR_OK) goto done;
    if ((st = wr_garment_place(&run->mesh, pl, run->n_panels, diag)) != WR_OK) goto done;
    if (run->sc->body.kind == WR_SIMSCENE_BODY_MANNEQUIN) /* the SDF sees a panel placed wholly inside */
        for (v = 0; v < run->mesh.nv; ++v)
            if (wr_body_sdf(&run->sc->body.mannequin, run->mesh.pos + 3 * v) < 0.0) {
                int32_t f = run->mesh.vf[run->mesh.vf_start[v]];
                p = run->mesh.face_panel[f];
                st = wr_fail(diag, WR_ERR_GEOMETRY, which[p], "$.garment.placements[%d]: panel '%s' as placed has vertex %d inside the mannequin",
                             (int)which[p], run->panel_names[p], (int)v);
                goto done;
            }
    run->fixed = (uint8_t *)wr_calloc_array((size_t)run->mesh.nv, 1);
    run->x = (double *)wr_alloc_array(3 * (size_t)run->mesh.nv, sizeof(double));
    if (!run->fixed || !run->x) {
        st = wr_fail(diag, WR_ERR_NOMEM, -1, "out of memory (%d vertices)", (int)run->mesh.nv);
        goto done;
    }
    if ((st = ss_pins(run, g->pin, g->n_pins, "$.garment.pins", diag)) != WR_OK) goto done;
    memset(&gm, 0, sizeof gm);
    gm.pattern = &run->mr.mesh;
    gm.seam_pairs = run->mr.seam_pairs;
    gm.seam_pair_seam = run->mr.seam_pair_seam;
    gm.n_seam_pairs = run->mr.n_seam_pairs;
    gm.placements = pl;
    gm.n_placements = run->n_panels;
    gm.lines = run->glines;
    gm.n_lines = run->n_glines;
    dd->fixed = run->fixed;
    if ((st = wr_garment_sim_create(&run->gs, &gm, &g->shell, dd, &g->sewing, diag)) != WR_OK) {
        snprintf(msg, sizeof msg, "%s", diag ? diag->message : "");
        if (st == WR_ERR_GEOMETRY && diag && diag->item >= 0 && diag->item < run->n_panels)
            st = wr_fail(diag, st, which[diag->item], "$.garment.placements[%d]: %s", (int)which[diag->item], msg);
        else
            st = wr_fail(diag, st, diag ? diag->item : -1, "$.garment: %s", msg);
        goto done;
    }
    for (v = 0; v < run->gs.nv0; ++v)
        for (i = 0; i < 3; ++i) run->gs.v[3 * v + i] = run->fixed[v] ? 0.0 : g->velocity[i];
    wr_garment_sim_unsewn_positions(&run->gs, run->x);
done:
    wr_free(pl);
    wr_free(which);
    return st;
}

const wr_dyn *wr_simscene_dyn(const wr_simscene_run *run) { return run->sc->is_garment ? &run->gs.dyn : &run->sim; }

wr_status wr_simscene_run_create(wr_simscene_run *run, const wr_simscene *sc, wr_diag *diag) {
    const wr_simscene_cloth *c = &sc->cloth;
    wr_dyn_desc dd;
    wr_status st;
    double t0 = wr_time_seconds();
    int32_t i;
    memset(run, 0, sizeof *run);
    run->sc = sc;
    run->n_frames_max = (int32_t)ceil(sc->duration / sc->dyn.time.dt - 1e-9) + 1;
    run->frames = (wr_simscene_frame *)wr_calloc_array((size_t)run->n_frames_max, sizeof(wr_simscene_frame));
    if (!run->frames) {
        st = wr_fail(diag, WR_ERR_NOMEM, -1, "out of memory (%d frames)", (int)run->n_frames_max);
        goto fail;
    }
    if ((st = ss_bodies(run, diag)) != WR_OK) goto fail;
    dd = sc->dyn;
    dd.contact.analytic = sc->analytic;
    dd.contact.n_analytic = sc->n_analytic;
    dd.contact.bodies = run->n_bodies ? run->dbodies : NULL;
    dd.contact.n_bodies = run->n_bodies;
    if (sc->is_garment) {
        if ((st = ss_garment(run, &dd, diag)) != WR_OK) goto fail;
        run->frames[0].seam_gap = run->gs.gap;
        run->t_setup = wr_time_seconds() - t0;
        return WR_OK;
    }
    if ((st = ss_build_mesh(c, &run->mesh, diag)) != WR_OK) goto fail;
    if ((st = wr_shell_create(&run->shell, &run->mesh, &c->shell, diag)) != WR_OK) goto fail;
    ss_place(c, run->mesh.pos, run->mesh.nv);
    run->fixed = (uint8_t *)wr_calloc_array((size_t)run->mesh.nv, 1);
    run->x = (double *)wr_alloc_array(3 * (size_t)run->mesh.nv, sizeof(double));
    run->v = (double *)wr_alloc_array(3 * (size_t)run->mesh.nv, sizeof(double));
    if (!run->fixed || !run->x || !run->v) {
        st = wr_fail(diag, WR_ERR_NOMEM, -1, "out of memory (%d vertices)", (int)run->mesh.nv);
        goto fail;
    }
    if ((st = ss_pins(run, c->pin, c->n_pins, "$.cloth.pins", diag)) != WR_OK) goto fail;
    memcpy(run->x, run->mesh.pos, sizeof(double) * 3 * (size_t)run->mesh.nv);
    for (i = 0; i < 3 * run->mesh.nv; ++i) run->v[i] = run->fixed[i / 3] ? 0.0 : c->velocity[i % 3];
    dd.fixed = run->fixed;
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
        if (sc->is_garment)
            st = wr_garment_sim_step(&run->gs, &fs, diag);
        else
            st = wr_dyn_step(&run->sim, &run->state, &fs, diag);
        if (st != WR_OK) {
            run->status = st;
            snprintf(run->status_message, sizeof run->status_message, "frame %d: %.490s", (int)(run->n_frames + 1),
                     diag ? diag->message : wr_status_text(st));
            break;
        }
        run->n_frames++;
        if (sc->is_garment) {
            wr_garment_sim_unsewn_positions(&run->gs, run->x);
            f->t = run->gs.state.t;
            f->seam_gap = run->gs.gap;
            f->welded = run->gs.welded;
            f->gravity_scale = run->gs.gravity_scale;
        } else {
            f->t = run->state.t;
        }
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
    run->t_run = wr_time_seconds() - t0;
    return st;
}

void wr_simscene_frame_name(const wr_simscene *sc, int32_t k, char *out) {
    snprintf(out, 32, "frame_%04d.%s", (int)k, sc->output_ply ? "ply" : "obj");
}

wr_status wr_simscene_write_frame(const wr_simscene_run *run, const char *dir, int32_t k, wr_diag *diag) {
    char name[32], path[WR_PATH_MAX];
    wr_mesh m = run->mesh;
    wr_obj_desc od;
    wr_simscene_frame_name(run->sc, k, name);
    if ((size_t)snprintf(path, sizeof path, "%s/%s", dir, name) >= sizeof path)
        return wr_fail(diag, WR_ERR_IO, -1, "output path too long: %s/%s", dir, name);
    m.pos = run->x; /* a shallow view: the mesh's topology with the current positions */
    if (run->sc->output_ply) return wr_mesh_write_ply(&m, path, 0, NULL, NULL, diag);
    memset(&od, 0, sizeof od);
    od.normals = 1; /* viewers shade the frame smoothly; groups named after the pattern's panels */
    od.group_names = (const char *const *)run->panel_names;
    od.n_group_names = run->panel_names ? run->n_panels : 0;
    return wr_mesh_write_obj(&m, path, &od, diag);
}

wr_status wr_simscene_write_welded(const wr_simscene_run *run, const char *path, wr_diag *diag) {
    wr_mesh m = run->mesh, w;
    wr_obj_desc od;
    wr_status st;
    if (!run->sc->is_garment) return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "welded output: not a garment scene");
    m.pos = run->x; /* a shallow view, as in write_frame: the pattern mesh at the current positions */
    if ((st = wr_mesh_weld(&w, &m, run->gs.n_pairs, run->gs.pairs, NULL, diag)) != WR_OK) return st;
    memset(&od, 0, sizeof od);
    od.group_names = (const char *const *)run->panel_names;
    od.n_group_names = run->panel_names ? run->n_panels : 0;
    od.comment = "wrinkle-sim --weld-final: the last frame sewn (seam pairs merged, vt = each face's pattern corners)";
    st = wr_mesh_write_obj(&w, path, &od, diag);
    wr_mesh_free(&w);
    return st;
}

/* Body positions now: the sim's copy (moving bodies move), as one array per body. */
static const double *ss_body_pos(const wr_simscene_run *run, int32_t b) {
    const wr_dyn *dyn = wr_simscene_dyn(run);
    int32_t off = 0, i;
    if (!dyn->body_x) return run->dbodies[b].pos;
    for (i = 0; i < b; ++i) off += run->dbodies[i].nv;
    return dyn->body_x + 3 * (size_t)off;
}

wr_status wr_simscene_write_bodies(const wr_simscene_run *run, const char *dir, wr_diag *diag) {
    char path[WR_PATH_MAX];
    int32_t b, nv = 0, nf = 0, i, ov = 0, of = 0;
    int32_t *F;
    double *X;
    wr_mesh m;
    wr_status st;
    if (run->n_bodies < 1) return WR_OK;
    if ((size_t)snprintf(path, sizeof path, "%s/body.obj", dir) >= sizeof path)
        return wr_fail(diag, WR_ERR_IO, -1, "output path too long: %s/body.obj", dir);
    for (b = 0; b < run->n_bodies; ++b) nv += run->dbodies[b].nv, nf += run->dbodies[b].nf;
    F = (int32_t *)wr_alloc_array(3 * (size_t)nf, sizeof(int32_t));
    X = (double *)wr_alloc_array(3 * (size_t)nv, sizeof(double));
    if (!F || !X) {
        wr_free(F);
        wr_free(X);
        return wr_fail(diag, WR_ERR_NOMEM, -1, "body.obj: out of memory");
    }
    for (b = 0; b < run->n_bodies; ++b) {
        const wr_dyn_body *db = run->dbodies + b;
        memcpy(X + 3 * ov, ss_body_pos(run, b), sizeof(double) * 3 * (size_t)db->nv);
        for (i = 0; i < 3 * db->nf; ++i) F[3 * of + i] = db->faces[i] + ov;
        ov += db->nv;
        of += db->nf;
    }
    st = wr_mesh_create(&m, nv, X, NULL, nf, F, diag);
    if (st == WR_OK) {
        wr_obj_desc od;
        memset(&od, 0, sizeof od);
        od.normals = 1;
        st = wr_mesh_write_obj(&m, path, &od, diag);
    }
    wr_mesh_free(&m);
    wr_free(F);
    wr_free(X);
    return st;
}

/* DIR/frame_NNNN.png: the cloth (red, wireframe) over the triangle-mesh bodies (grey) from the
 * front (−y, the mannequin's facing side) and at 3/4, both fitted to the cloth with a margin. */
wr_status wr_simscene_write_png(const wr_simscene_run *run, const char *dir, int32_t k, wr_diag *diag) {
#if defined(WR_USE_LIBPNG) && WR_USE_LIBPNG
    static const double az[2] = {-90.0, -35.0};
    char path[WR_PATH_MAX];
    wr_image img;
    wr_status st;
    int32_t vw = 480, vh = 560, i, b;
    if ((size_t)snprintf(path, sizeof path, "%s/frame_%04d.png", dir, (int)k) >= sizeof path)
        return wr_fail(diag, WR_ERR_IO, -1, "output path too long: %s", dir);
    if ((st = wr_image_create(&img, 2 * vw, vh, diag)) != WR_OK) return st;
    for (i = 0; i < 2 && st == WR_OK; ++i) {
        wr_view view;
        wr_view_desc vd;
        wr_render_style cs, bs;
        memset(&vd, 0, sizeof vd);
        vd.has_angles = 1;
        vd.azimuth_deg = az[i];
        vd.elevation_deg = 12.0;
        wr_view_fit(&view, run->x, run->mesh.nv, &vd, i * vw, 0, vw, vh);
        view.scale *= 0.75; /* some of the body around the cloth */
        memset(&bs, 0, sizeof bs);
        bs.base_rgb[0] = bs.base_rgb[1] = bs.base_rgb[2] = 0.72;
        memset(&cs, 0, sizeof cs);
        cs.base_rgb[0] = 0.78, cs.base_rgb[1] = 0.32, cs.base_rgb[2] = 0.30;
        cs.wireframe = 1;
        cs.wire_width = 0.4;
        for (b = 0; b < run->n_bodies && st == WR_OK; ++b)
            st = wr_render_mesh(&img, &view, ss_body_pos(run, b), run->dbodies[b].nv, run->dbodies[b].faces, run->dbodies[b].nf,
                                &bs, diag);
        if (st == WR_OK) st = wr_render_mesh(&img, &view, run->x, run->mesh.nv, run->mesh.faces, run->mesh.nf, &cs, diag);
    }
    {
        static const double ink[3] = {0.1, 0.1, 0.1};
        char title[160];
        const wr_simscene_frame *f = run->frames + k;
        if (run->sc->is_garment)
            snprintf(title, sizeof title, "%s  t %.3f s  seam gap %.2f mm%s", run->sc->name, f->t, 1e3 * f->seam_gap,
                     f->welded ? "  welded" : "");
        else
            snprintf(title, sizeof title, "%s  t %.3f s", run->sc->name, f->t);
        wr_image_text(&img, 8, 8, 2, ink, title);
    }
    if (st == WR_OK) st = wr_image_write_png(&img, path, diag);
    wr_image_free(&img);
    return st;
#else
    (void)run, (void)dir, (void)k;
    return wr_fail(diag, WR_ERR_UNSUPPORTED, -1, "--png needs the kit built with WR_USE_LIBPNG=1 (libpng)");
#endif
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
    const wr_dyn *dyn = wr_simscene_dyn(run);
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
    cJSON_AddNumberToObject(root, "dt", dyn->desc.time.dt);
    cJSON_AddNumberToObject(root, "substeps", dyn->desc.time.substeps);
    cJSON_AddStringToObject(root, "linear", wr_solver_method_name(dyn->desc.linear.method));
    cJSON_AddNumberToObject(root, "linear_tol", dyn->desc.linear.rel_tol);
    cJSON_AddNumberToObject(root, "linear_forcing", dyn->desc.newton.forcing);
    cJSON_AddNumberToObject(root, "contact_dhat", dyn->dhat);
    cJSON_AddNumberToObject(root, "contact_stiffness", dyn->kappa);
    cJSON_AddNumberToObject(root, "bodies", run->n_bodies);
    if (run->sc->is_garment) {
        const wr_garment_sim *gs = &run->gs;
        cJSON *g = cJSON_AddObjectToObject(root, "garment");
        cJSON_AddNumberToObject(g, "panels", run->n_panels);
        cJSON_AddNumberToObject(g, "seam_pairs", gs->n_pairs);
        cJSON_AddNumberToObject(g, "initial_seam_gap", run->frames[0].seam_gap);
        cJSON_AddNumberToObject(g, "sewing_stiffness_start", gs->k_start);
        cJSON_AddNumberToObject(g, "sewing_stiffness", gs->k_full);
        cJSON_AddNumberToObject(g, "weld_tolerance", gs->desc.weld_tol);
        cJSON_AddNumberToObject(g, "gravity_delay", gs->desc.gravity_delay);
        cJSON_AddNumberToObject(g, "gravity_ramp", gs->desc.gravity_ramp);
        cJSON_AddBoolToObject(g, "welded", gs->welded);
        cJSON_AddNumberToObject(g, "gathered_lines", gs->n_lines);
        cJSON_AddNumberToObject(g, "thread_segments", gs->n_thr);
        if (gs->n_lines > 0) {
            cJSON *ls = cJSON_AddArrayToObject(g, "lines");
            int32_t L;
            for (L = 0; L < gs->n_lines; ++L) {
                cJSON *o = cJSON_CreateObject();
                double now, rest;
                wr_garment_sim_thread_length(gs, L, &now, &rest);
                cJSON_AddNumberToObject(o, "vertices", run->glines[L].n_vertices);
                cJSON_AddNumberToObject(o, "rho", run->glines[L].rho);
                cJSON_AddNumberToObject(o, "rest_length", rest);
                cJSON_AddNumberToObject(o, "length", now);
                cJSON_AddItemToArray(ls, o);
            }
        }
        if (gs->welded) {
            cJSON_AddNumberToObject(g, "weld_frame", gs->weld_frame);
            cJSON_AddNumberToObject(g, "weld_gap", gs->weld_gap);
            cJSON_AddNumberToObject(g, "welded_vertices", gs->mesh.nv);
        }
    }
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
        if (run->sc->is_garment) {
            cJSON_AddNumberToObject(o, "seam_gap", f->seam_gap);
            cJSON_AddNumberToObject(o, "gravity_scale", f->gravity_scale);
        }
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
