/* wrinkle_capi.c — the flat C interface of build/libwrinkle.so, for the Python package
 * python/wrinkle (ctypes) and any other language with a C FFI.
 *
 * This is the shared library's one implementation unit: it compiles every wrinkle module
 * (WRINKLE_IMPLEMENTATION, the kit's full configuration: CHOLMOD, FFTW, libpng) and links the
 * pattern and scene readers (drivers/lib/pattern.c, scene.c, jsonout.c; cJSON). The kit's own
 * structs stay inside: each call below takes and returns plain numbers, flat arrays and opaque
 * handles, so a binding needs no struct layouts.
 *
 * Conventions
 *   - Errors: a function returns 0 (or a non-NULL handle) on success; on failure a non-zero status
 *     (or NULL) and a one-line message in err[errlen] (the wr_diag text, naming the item).
 *   - Results with sizes known only after the computation come back as a handle: *_sizes tells
 *     the caller how much to allocate, *_get copies into caller-owned arrays, *_free releases.
 *   - Units as in the headers: metres, N·m, N/m², radians.
 *
 * Functions
 *   wr_py_resolution(B, E, &r, err, n)                            Style3D Eq. 4 [m]
 *   wr_py_mesher_run(pattern_json, err, n) -> handle              Style3D Sec. 4: sizing map + mesh
 *   wr_py_mesher_sizes(h, &nv, &nf, &n_panels)
 *   wr_py_mesher_get(h, pos[nv*3], rest[nv*2], faces[nf*3], face_panel[nf], sizing[nv], r_panel[n_panels])
 *   wr_py_mesher_sizing(h, panel, xy[2n], n, out[n])              the sizing map at pattern points [m]
 *   wr_py_mesher_free(h)
 *   wr_py_triangulate(pts[2n], n, segs[2s], s, holes[2k], k, min_angle_deg, max_area, err, n) -> handle
 *   wr_py_cdt_sizes(h, &n_points, &n_triangles) / wr_py_cdt_get(h, points, triangles) / wr_py_cdt_free(h)
 *   wr_py_statics(scene_json, base_dir, err, n) -> handle         scene format (docs/scene-format.md)
 *   wr_py_statics_sizes(h, &nv, &nf, &newton, &status)
 *   wr_py_statics_get(h, rest_pos[nv*3], rest[nv*2], pos[nv*3], faces[nf*3])
 *   wr_py_statics_free(h)
 *   wr_py_tfw(nv, rest_pos, rest2 (or NULL), nf, faces, base_pos, E, nu, h, levels, err, n) -> handle
 *   wr_py_tfw_sizes(h, &ne, &n_fine_v, &n_fine_f, &sqp_iterations, &status)
 *   wr_py_tfw_get(h, a[nv], omega[ne], phi[3nf], wfree[nf] (uint8), fine_pos, fine_faces, fine_a)
 *   wr_py_tfw_free(h)
 *   wr_py_render_png(path, n, pos[], nv[], faces[], nf[], scalar[], titles[], columns, w, h, az, el, err, n)
 *       n meshes side by side (render.h), scalar[i] may be NULL (plain shading) — a diverging map
 *       when the scalar takes both signs, else a sequential one; the first view gets its edges;
 *       az, el the camera's azimuth and elevation [deg] (NaN: render.h's default three-quarter view).
 */
#define WRINKLE_IMPLEMENTATION
#include "wrinkle/wrinkle.h"
#include "wrinkle/spectrum.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "pattern.h"
#include "scene.h"

#define WR_PY_EXPORT __attribute__((visibility("default")))

static void py_err(char *err, int n, const wr_diag *d, const char *fallback) {
    if (err && n > 0) snprintf(err, (size_t)n, "%s", d && d->message[0] ? d->message : fallback);
}

WR_PY_EXPORT int wr_py_resolution(double B, double E, double *r, char *err, int n) {
    wr_resolution_model m = wr_resolution_model_paper();
    wr_diag d;
    wr_status st;
    memset(&d, 0, sizeof d);
    st = wr_resolution_from_BE(&m, B, E, NULL, r, &d);
    if (st != WR_OK) py_err(err, n, &d, "resolution failed");
    return (int)st;
}

/* ---- mesher ------------------------------------------------------------------------------------ */

typedef struct wr_py_mesher {
    wr_pattern_file pf;
    wr_mesher_result res;
} wr_py_mesher;

WR_PY_EXPORT void *wr_py_mesher_run(const char *json, char *err, int n) {
    wr_py_mesher *h = (wr_py_mesher *)calloc(1, sizeof *h);
    wr_diag d;
    memset(&d, 0, sizeof d);
    if (!h) {
        py_err(err, n, NULL, "out of memory");
        return NULL;
    }
    if (wr_pattern_parse(json, strlen(json), "pattern", &h->pf, &d) != WR_OK ||
        wr_mesher_run(&h->pf.pattern, &h->pf.desc, &h->res, &d) != WR_OK) {
        py_err(err, n, &d, "meshing failed");
        wr_pattern_file_free(&h->pf);
        free(h);
        return NULL;
    }
    return h;
}

WR_PY_EXPORT void wr_py_mesher_sizes(const void *hv, int32_t *nv, int32_t *nf, int32_t *np) {
    const wr_py_mesher *h = (const wr_py_mesher *)hv;
    *nv = h->res.mesh.nv;
    *nf = h->res.mesh.nf;
    *np = h->res.n_panels;
}

WR_PY_EXPORT void wr_py_mesher_get(const void *hv, double *pos, double *rest, int32_t *faces, int32_t *face_panel,
                                   double *sizing, double *r_panel) {
    const wr_py_mesher *h = (const wr_py_mesher *)hv;
    const wr_mesh *m = &h->res.mesh;
    int32_t v, f, p;
    memcpy(pos, m->pos, sizeof(double) * 3 * (size_t)m->nv);
    for (v = 0; v < m->nv; ++v) {
        rest[2 * v] = m->rest ? m->rest[2 * v] : m->pos[3 * v];
        rest[2 * v + 1] = m->rest ? m->rest[2 * v + 1] : m->pos[3 * v + 1];
        sizing[v] = h->res.sizing ? h->res.sizing[v] : NAN;
    }
    memcpy(faces, m->faces, sizeof(int32_t) * 3 * (size_t)m->nf);
    for (f = 0; f < m->nf; ++f) face_panel[f] = m->face_panel ? m->face_panel[f] : 0;
    for (p = 0; p < h->res.n_panels; ++p) r_panel[p] = h->res.panels[p].r0;
}

WR_PY_EXPORT void wr_py_mesher_sizing(const void *hv, int32_t panel, const double *xy, int32_t n, double *out) {
    const wr_py_mesher *h = (const wr_py_mesher *)hv;
    int32_t i;
    for (i = 0; i < n; ++i)
        out[i] = panel >= 0 && panel < h->res.n_panels ? wr_mesher_eval_sizing(&h->res, panel, xy[2 * i], xy[2 * i + 1])
                                                       : NAN;
}

WR_PY_EXPORT void wr_py_mesher_free(void *hv) {
    wr_py_mesher *h = (wr_py_mesher *)hv;
    if (!h) return;
    wr_mesher_free(&h->res);
    wr_pattern_file_free(&h->pf);
    free(h);
}

/* ---- triangulation ----------------------------------------------------------------------------- */

WR_PY_EXPORT void *wr_py_triangulate(const double *pts, int32_t np, const int32_t *segs, int32_t ns,
                                     const double *holes, int32_t nh, double min_angle_deg, double max_area,
                                     char *err, int n) {
    wr_cdt_result *r = (wr_cdt_result *)calloc(1, sizeof *r);
    wr_cdt_input in;
    wr_cdt_desc desc;
    wr_diag d;
    memset(&d, 0, sizeof d);
    memset(&in, 0, sizeof in);
    memset(&desc, 0, sizeof desc);
    if (!r) {
        py_err(err, n, NULL, "out of memory");
        return NULL;
    }
    in.points = pts;
    in.n_points = np;
    in.segments = ns > 0 ? segs : NULL;
    in.n_segments = ns;
    in.holes = nh > 0 ? holes : NULL;
    in.n_holes = nh;
    if (min_angle_deg > 0.0) {
        desc.quality = 1;
        desc.min_angle_deg = min_angle_deg;
    }
    desc.max_area = max_area > 0.0 ? max_area : 0.0;
    if (wr_cdt_triangulate(&in, &desc, r, &d) != WR_OK) {
        py_err(err, n, &d, "triangulation failed");
        wr_cdt_free(r);
        free(r);
        return NULL;
    }
    return r;
}

WR_PY_EXPORT void wr_py_cdt_sizes(const void *hv, int32_t *np, int32_t *nt) {
    const wr_cdt_result *r = (const wr_cdt_result *)hv;
    *np = r->n_points;
    *nt = r->n_triangles;
}

WR_PY_EXPORT void wr_py_cdt_get(const void *hv, double *pts, int32_t *tris) {
    const wr_cdt_result *r = (const wr_cdt_result *)hv;
    memcpy(pts, r->points, sizeof(double) * 2 * (size_t)r->n_points);
    memcpy(tris, r->triangles, sizeof(int32_t) * 3 * (size_t)r->n_triangles);
}

WR_PY_EXPORT void wr_py_cdt_free(void *hv) {
    if (!hv) return;
    wr_cdt_free((wr_cdt_result *)hv);
    free(hv);
}

/* ---- statics (a scene, docs/scene-format.md) ------------------------------------------------------ */

typedef struct wr_py_statics_h {
    wr_scene sc;
    wr_scene_run run;
    wr_status status;
} wr_py_statics_h;

WR_PY_EXPORT void *wr_py_statics(const char *json, const char *base_dir, char *err, int n) {
    wr_py_statics_h *h = (wr_py_statics_h *)calloc(1, sizeof *h);
    wr_diag d;
    memset(&d, 0, sizeof d);
    if (!h) {
        py_err(err, n, NULL, "out of memory");
        return NULL;
    }
    if (wr_scene_parse(&h->sc, json, strlen(json), base_dir ? base_dir : ".", &d) != WR_OK ||
        wr_scene_run_create(&h->run, &h->sc, &d) != WR_OK) {
        py_err(err, n, &d, "scene failed");
        wr_scene_run_free(&h->run);
        wr_scene_free(&h->sc);
        free(h);
        return NULL;
    }
    h->status = wr_scene_run_solve(&h->run, NULL, NULL, &d);
    if (h->status != WR_OK && h->status != WR_ERR_NOT_CONVERGED) {
        py_err(err, n, &d, "solve failed");
        wr_scene_run_free(&h->run);
        wr_scene_free(&h->sc);
        free(h);
        return NULL;
    }
    if (h->status != WR_OK) py_err(err, n, &d, "not converged"); /* kept: the caller may warn */
    return h;
}

WR_PY_EXPORT void wr_py_statics_sizes(const void *hv, int32_t *nv, int32_t *nf, int32_t *newton, int32_t *status) {
    const wr_py_statics_h *h = (const wr_py_statics_h *)hv;
    *nv = h->run.mesh.nv;
    *nf = h->run.mesh.nf;
    *newton = h->run.newton_iterations;
    *status = (int32_t)h->status;
}

WR_PY_EXPORT void wr_py_statics_get(const void *hv, double *rest_pos, double *rest, double *pos, int32_t *faces) {
    const wr_py_statics_h *h = (const wr_py_statics_h *)hv;
    const wr_mesh *m = &h->run.mesh;
    int32_t v;
    memcpy(rest_pos, m->pos, sizeof(double) * 3 * (size_t)m->nv);
    memcpy(pos, h->run.x, sizeof(double) * 3 * (size_t)m->nv);
    for (v = 0; v < m->nv; ++v) {
        rest[2 * v] = m->rest ? m->rest[2 * v] : m->pos[3 * v];
        rest[2 * v + 1] = m->rest ? m->rest[2 * v + 1] : m->pos[3 * v + 1];
    }
    memcpy(faces, m->faces, sizeof(int32_t) * 3 * (size_t)m->nf);
}

WR_PY_EXPORT void wr_py_statics_free(void *hv) {
    wr_py_statics_h *h = (wr_py_statics_h *)hv;
    if (!h) return;
    wr_scene_run_free(&h->run);
    wr_scene_free(&h->sc);
    free(h);
}

/* ---- TFW ------------------------------------------------------------------------------------------ */

typedef struct wr_py_tfw_h {
    wr_mesh m;
    wr_tfw_result r;
    wr_status status;
} wr_py_tfw_h;

WR_PY_EXPORT void *wr_py_tfw(int32_t nv, const double *rest_pos, const double *rest2, int32_t nf, const int32_t *faces,
                             const double *base_pos, double young, double poisson, double thickness, int32_t levels,
                             char *err, int n) {
    wr_py_tfw_h *h = (wr_py_tfw_h *)calloc(1, sizeof *h);
    wr_wf_material mat;
    wr_tfw_desc td;
    wr_diag d;
    memset(&d, 0, sizeof d);
    if (!h) {
        py_err(err, n, NULL, "out of memory");
        return NULL;
    }
    if (wr_mesh_create(&h->m, nv, rest_pos, rest2, nf, faces, &d) != WR_OK) {
        py_err(err, n, &d, "mesh rejected");
        free(h);
        return NULL;
    }
    mat.young = young;
    mat.poisson = poisson;
    mat.thickness = thickness;
    memset(&td, 0, sizeof td);
    td.upsample.levels = levels;
    if (levels == 0) td.no_upsample = 1;
    h->status = wr_tfw_fields(&h->m, base_pos, &mat, &td, &h->r, &d);
    if (h->status != WR_OK && h->status != WR_ERR_NOT_CONVERGED) {
        py_err(err, n, &d, "TFW failed");
        wr_tfw_result_free(&h->r);
        wr_mesh_free(&h->m);
        free(h);
        return NULL;
    }
    if (h->status != WR_OK) py_err(err, n, &d, "not converged");
    return h;
}

WR_PY_EXPORT void wr_py_tfw_sizes(const void *hv, int32_t *ne, int32_t *fnv, int32_t *fnf, int32_t *iters,
                                  int32_t *status) {
    const wr_py_tfw_h *h = (const wr_py_tfw_h *)hv;
    *ne = h->m.ne;
    *fnv = h->r.wrinkled.nv;
    *fnf = h->r.wrinkled.nf;
    *iters = h->r.sqp.iterations;
    *status = (int32_t)h->status;
}

WR_PY_EXPORT void wr_py_tfw_edges(const void *hv, int32_t *edges) {
    const wr_py_tfw_h *h = (const wr_py_tfw_h *)hv;
    memcpy(edges, h->m.edges, sizeof(int32_t) * 2 * (size_t)h->m.ne);
}

WR_PY_EXPORT void wr_py_tfw_get(const void *hv, double *a, double *omega, double *phi, uint8_t *wfree, double *fpos,
                                int32_t *ffaces, double *fa) {
    const wr_py_tfw_h *h = (const wr_py_tfw_h *)hv;
    int32_t v;
    memcpy(a, h->r.a, sizeof(double) * (size_t)h->m.nv);
    memcpy(omega, h->r.omega, sizeof(double) * (size_t)h->m.ne);
    memcpy(phi, h->r.phi, sizeof(double) * 3 * (size_t)h->m.nf);
    memcpy(wfree, h->r.wfree, (size_t)h->m.nf);
    if (h->r.wrinkled.nv > 0) {
        memcpy(fpos, h->r.wrinkled.pos, sizeof(double) * 3 * (size_t)h->r.wrinkled.nv);
        memcpy(ffaces, h->r.wrinkled.faces, sizeof(int32_t) * 3 * (size_t)h->r.wrinkled.nf);
        for (v = 0; v < h->r.wrinkled.nv; ++v) fa[v] = h->r.wrinkled_a ? h->r.wrinkled_a[v] : NAN;
    }
}

/* The wrinkled surface's per-vertex phase [rad, (-π, π]] and wrinkle-free flag (tfw.h). */
WR_PY_EXPORT void wr_py_tfw_fine(const void *hv, double *phase, uint8_t *wfree) {
    const wr_py_tfw_h *h = (const wr_py_tfw_h *)hv;
    if (h->r.wrinkled.nv <= 0 || !h->r.wrinkled_phase || !h->r.wrinkled_wfree) return;
    memcpy(phase, h->r.wrinkled_phase, sizeof(double) * (size_t)h->r.wrinkled.nv);
    memcpy(wfree, h->r.wrinkled_wfree, (size_t)h->r.wrinkled.nv);
}

WR_PY_EXPORT void wr_py_tfw_free(void *hv) {
    wr_py_tfw_h *h = (wr_py_tfw_h *)hv;
    if (!h) return;
    wr_tfw_result_free(&h->r);
    wr_mesh_free(&h->m);
    free(h);
}

/* ---- pictures ---------------------------------------------------------------------------------- */

WR_PY_EXPORT int wr_py_render_png(const char *path, int32_t n, const double *const *pos, const int32_t *nv,
                                  const int32_t *const *faces, const int32_t *nf, const double *const *scalar,
                                  const char *const *titles, int32_t columns, int32_t w, int32_t h,
                                  double azimuth_deg, double elevation_deg, char *err, int errlen) {
    wr_render_panel *p = (wr_render_panel *)calloc((size_t)(n > 0 ? n : 1), sizeof *p);
    wr_view_desc vd;
    wr_image img;
    wr_diag d;
    wr_status st;
    int32_t i, v;
    memset(&d, 0, sizeof d);
    memset(&vd, 0, sizeof vd);
    if (isfinite(azimuth_deg) && isfinite(elevation_deg)) {
        vd.has_angles = 1;
        vd.azimuth_deg = azimuth_deg;
        vd.elevation_deg = elevation_deg;
    }
    if (!p) {
        py_err(err, errlen, NULL, "out of memory");
        return (int)WR_ERR_NOMEM;
    }
    for (i = 0; i < n; ++i) {
        p[i].pos = pos[i];
        p[i].nv = nv[i];
        p[i].faces = faces[i];
        p[i].nf = nf[i];
        p[i].title = titles ? titles[i] : NULL;
        p[i].style.wireframe = i == 0 && nf[i] <= 20000;
        if (scalar && scalar[i]) {
            double lo = HUGE_VAL, hi = -HUGE_VAL;
            for (v = 0; v < nv[i]; ++v)
                if (isfinite(scalar[i][v])) lo = fmin(lo, scalar[i][v]), hi = fmax(hi, scalar[i][v]);
            p[i].style.scalar = scalar[i];
            p[i].style.colormap = lo < 0.0 && hi > 0.0 ? WR_COLORMAP_DIVERGING : WR_COLORMAP_SEQUENTIAL;
            p[i].colorbar_label = "";
        }
    }
    st = wr_render_panels(&img, p, n, columns, &vd, w, h, &d);
    if (st == WR_OK) {
        st = wr_image_write_png(&img, path, &d);
        wr_image_free(&img);
    }
    free(p);
    if (st != WR_OK) py_err(err, errlen, &d, "render failed");
    return (int)st;
}
