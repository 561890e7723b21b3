/* wrinkle/render.h — headless pictures of the kit's 3D results: a small z-buffer rasteriser with
 * Lambert + Blinn–Phong shading, two-sided lighting, an optional wireframe overlay and per-vertex
 * scalar colour maps (amplitude, sizing, W flags), an orthographic camera fitted to the mesh, several
 * views side by side with titles, written to PNG.
 * wrinkle v0.1.0 — MIT licence (see LICENSE). Needs core.h; libc/libm only, and libpng (-lpng) for
 * wr_image_write_png when compiled with -DWR_USE_LIBPNG=1.
 *
 * WHY A RASTERISER AND LIBPNG (not OSMesa)
 *   The pictures are of one triangle mesh at a time (a base surface, a wrinkled surface, a sizing
 *   map), a few hundred thousand triangles at most: a scan-converting z-buffer in ~300 lines draws
 *   them in well under a second, needs no GL context, gives the same pixels on every machine (tests
 *   can check them) and keeps the header dependency-free. OSMesa (libosmesa6) would bring a full
 *   software OpenGL (llvmpipe, threads, a driver stack) for the same picture. libpng is the
 *   reference PNG codec (Debian libpng-dev, zlib licence): the encoder (deflate, CRCs) is the part
 *   worth not writing by hand, so only the writer depends on it, behind WR_USE_LIBPNG — the
 *   rasteriser compiles without it, as spd.h compiles without CHOLMOD. Without libpng,
 *   wr_image_write_ppm writes a binary PPM (any viewer or `pnmtopng` converts it).
 *
 * API (create/free pairs: wr_image_create → wr_image_free; wr_render_panels → wr_image_free)
 *   wr_image_create(img, w, h, diag)          RGB8 image + depth buffer, cleared to white
 *   wr_image_free(img)
 *   wr_image_fill(img, rgb)                   clear colour and depth
 *   wr_image_downsample(img, k, diag)         box filter k×k (render at k× size for anti-aliasing)
 *   wr_view_fit(view, pos, nv, desc, x0, y0, w, h)   orthographic camera looking at pos (nv×3 [m])
 *                                             from desc's azimuth/elevation, the projected points
 *                                             fitted into the pixel rectangle (x0, y0, w, h)
 *   wr_view_project(view, p, out)             world point → pixel x, y and depth (larger = farther)
 *   wr_render_mesh(img, view, pos, nv, faces, nf, style, diag)   shade triangles into img
 *   wr_render_panels(img, panels, n, columns, view_desc, w, h, diag)   n meshes side by side, each
 *                                             in a w×h px cell (one scale for all, a title above each,
 *                                             an optional colour legend below), drawn 2× supersampled;
 *                                             img is created here
 *   wr_image_text(img, x, y, scale, rgb, text) 5×7 bitmap text (ASCII; lower case drawn as capitals)
 *   wr_image_colorbar(img, x, y, w, h, kind, lo, hi, label)   a colour map's legend with its range
 *   wr_colormap(kind, t, rgb)                 the sequential or diverging map (t in [0, 1])
 *   wr_image_write_png(img, path, diag)       [WR_USE_LIBPNG] atomic (temp + rename)
 *   wr_image_write_ppm(img, path, diag)       binary PPM, atomic
 *
 * EXAMPLE
 *     wr_image img;  wr_view v;  wr_view_desc vd;  wr_render_style rs;  wr_diag d;
 *     double pos[12] = {0, 0, 0,  1, 0, 0,  1, 1, 0.2,  0, 1, 0.2};     // a bent square [m]
 *     int32_t faces[6] = {0, 1, 2,  0, 2, 3};
 *     double amp[4] = {0.0, 0.5, 1.0, 0.5};                            // per-vertex scalar
 *     if (wr_image_create(&img, 320, 240, &d) != WR_OK) { puts(d.message); return 1; }
 *     memset(&vd, 0, sizeof vd);                                       // default 3/4 view, z up
 *     wr_view_fit(&v, pos, 4, &vd, 0, 0, img.w, img.h);
 *     memset(&rs, 0, sizeof rs);  rs.scalar = amp;  rs.wireframe = 1;  // colour by amp, edges drawn
 *     if (wr_render_mesh(&img, &v, pos, 4, faces, 2, &rs, &d) != WR_OK) { puts(d.message); return 1; }
 *     if (img.depth[(img.h / 2) * img.w + img.w / 2] > 1e300) return 1;  // the centre is covered
 *     if (wr_image_write_ppm(&img, "square.ppm", &d) != WR_OK) { puts(d.message); return 1; }
 *     wr_image_free(&img);
 *
 * ON COORDINATES
 *   Pixel (i, j) is column i from the left, row j from the top, covering [i, i+1) × [j, j+1); it is
 *   drawn when its centre (i + ½, j + ½) lies inside the projected triangle. Centres exactly on an
 *   edge belong to one of the two triangles sharing it (a fixed tie rule), so a closed mesh covers
 *   every pixel once. The camera is orthographic (lengths on screen are proportional to lengths on
 *   the cloth, which is what a wrinkle picture wants): azimuth about `up` measured from the first
 *   axis perpendicular to it (x for up = z), elevation above the horizontal plane (90° = top view).
 *   Depth is the distance along the viewing direction; the z-buffer keeps the smallest.
 *
 * ON SHADING
 *   Per-pixel normals interpolated from area-weighted vertex normals (style.flat: face normals),
 *   turned towards the viewer (two-sided: cloth has no inside); colour = albedo · (ambient +
 *   diffuse · max(0, n·l)) + specular · max(0, n·h)^shininess, light fixed to the camera (slightly
 *   upper left of the viewer by default, so surfaces facing the camera are bright whatever their
 *   orientation in the world) and every view is lit alike. Relief as shallow as a 0.3 mm wrinkle on
 *   a 25 cm sheet barely shades: colour such results by their height (the drivers do).
 *
 * ON THREADS
 *   No global state; an image may be drawn by one thread at a time.
 */
#ifndef WRINKLE_RENDER_H
#define WRINKLE_RENDER_H

#include "core.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct wr_image {
    int32_t w, h;
    uint8_t *rgb;  /* w*h*3, row-major from the top row */
    double *depth; /* w*h, HUGE_VAL where nothing was drawn */
} wr_image;

/* Camera. Defaults (zero-means-default except where a has_ flag says otherwise):
 *   azimuth_deg -60, elevation_deg 35 (used as given when has_angles), up (0, 0, 1),
 *   margin 0.06 of the smaller side of the viewport. */
typedef struct wr_view_desc {
    int has_angles;
    double azimuth_deg, elevation_deg;
    double up[3];
    double margin;
} wr_view_desc;

typedef struct wr_view {
    double right[3], upv[3], fwd[3]; /* camera frame: screen x, screen y (up), viewing direction */
    double center[3];                /* world point at the viewport's centre */
    double scale;                    /* pixels per metre */
    double cx, cy;                   /* pixel position of center */
} wr_view;

typedef enum wr_colormap_kind {
    WR_COLORMAP_SEQUENTIAL = 0, /* dark blue → green → yellow (amplitude, sizing) */
    WR_COLORMAP_DIVERGING       /* blue → white → red, white at the middle (signed height) */
} wr_colormap_kind;

/* Look. Defaults: base_rgb (0.80, 0.82, 0.88) when scalar is NULL; scalar_lo = scalar_hi = 0 →
 * the scalar's min and max (diverging map: ±max |scalar|); wire_rgb (0.15, 0.15, 0.2), wire_width
 * 0.6 px; light (-0.35, 0.45, 0.82) in camera coordinates (right, up, towards the viewer); ambient 0.35, diffuse 0.70,
 * specular 0.18, shininess 40. */
typedef struct wr_render_style {
    const double *scalar; /* nv values or NULL: colour through wr_colormap */
    double scalar_lo, scalar_hi;
    wr_colormap_kind colormap;
    double base_rgb[3];
    int wireframe;
    double wire_rgb[3];
    double wire_width;
    int flat;
    double light[3];
    double ambient, diffuse, specular, shininess;
} wr_render_style;

/* One view of wr_render_panels. */
typedef struct wr_render_panel {
    const double *pos; /* nv*3 [m] */
    int32_t nv;
    const int32_t *faces; /* nf*3 */
    int32_t nf;
    const char *title; /* drawn above the view, may be NULL */
    wr_render_style style;
    const char *colorbar_label; /* with style.scalar: a legend under the view (NULL: none) */
} wr_render_panel;

WRDEF wr_status wr_image_create(wr_image *img, int32_t w, int32_t h, wr_diag *diag);
WRDEF void wr_image_free(wr_image *img);
WRDEF void wr_image_fill(wr_image *img, const double rgb[3]);
WRDEF wr_status wr_image_downsample(wr_image *img, int32_t k, wr_diag *diag);
WRDEF void wr_view_fit(wr_view *view, const double *pos, int32_t nv, const wr_view_desc *desc, int32_t x0,
                       int32_t y0, int32_t w, int32_t h);
WRDEF void wr_view_project(const wr_view *view, const double p[3], double out[3]);
WRDEF wr_status wr_render_mesh(wr_image *img, const wr_view *view, const double *pos, int32_t nv,
                               const int32_t *faces, int32_t nf, const wr_render_style *style, wr_diag *diag);
WRDEF wr_status wr_render_panels(wr_image *img, const wr_render_panel *panels, int32_t n, int32_t columns,
                                 const wr_view_desc *view_desc, int32_t panel_w, int32_t panel_h, wr_diag *diag);
WRDEF void wr_image_text(wr_image *img, int32_t x, int32_t y, int32_t scale, const double rgb[3], const char *text);
WRDEF void wr_image_colorbar(wr_image *img, int32_t x, int32_t y, int32_t w, int32_t h, wr_colormap_kind kind,
                             double lo, double hi, const char *label);
WRDEF void wr_colormap(wr_colormap_kind kind, double t, double rgb[3]);
WRDEF wr_status wr_image_write_ppm(const wr_image *img, const char *path, wr_diag *diag);
#if defined(WR_USE_LIBPNG) && WR_USE_LIBPNG
WRDEF wr_status wr_image_write_png(const wr_image *img, const char *path, wr_diag *diag);
#endif

#ifdef __cplusplus
}
#endif
#endif /* WRINKLE_RENDER_H */

#ifdef WRINKLE_IMPLEMENTATION
#ifndef WRINKLE_RENDER_IMPLEMENTATION_DONE
#define WRINKLE_RENDER_IMPLEMENTATION_DONE

#include <math.h>
#include <string.h>
#if defined(WR_USE_LIBPNG) && WR_USE_LIBPNG
#include <png.h>
#include <setjmp.h>
#endif

#ifdef __cplusplus
extern "C" {
#endif

/* Largest image side accepted (pixels): keeps w*h*3 far from size_t overflow and a typo (1e6 px)
 * from allocating terabytes. 16384 covers a 4× supersampled 4K picture. */
#define WR_RENDER_MAX_SIDE 16384
/* wr_render_panels draws at this many times the final size, then box-filters: edges and the
 * wireframe come out anti-aliased (2 already removes the staircase; 3 costs 2.25× more for little). */
#define WR_RENDER_SUPERSAMPLE 2

WRDEF wr_status wr_image_create(wr_image *img, int32_t w, int32_t h, wr_diag *diag) {
    static const double white[3] = {1.0, 1.0, 1.0};
    memset(img, 0, sizeof *img);
    if (w < 1 || h < 1 || w > WR_RENDER_MAX_SIDE || h > WR_RENDER_MAX_SIDE)
        return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "image size %d x %d outside 1..%d", (int)w, (int)h,
                       WR_RENDER_MAX_SIDE);
    img->rgb = (uint8_t *)wr_alloc_array((size_t)w * (size_t)h, 3);
    img->depth = (double *)wr_alloc_array((size_t)w * (size_t)h, sizeof(double));
    if (!img->rgb || !img->depth) {
        wr_image_free(img);
        return wr_fail(diag, WR_ERR_NOMEM, -1, "out of memory for a %d x %d image", (int)w, (int)h);
    }
    img->w = w;
    img->h = h;
    wr_image_fill(img, white);
    return WR_OK;
}

WRDEF void wr_image_free(wr_image *img) {
    wr_free(img->rgb);
    wr_free(img->depth);
    memset(img, 0, sizeof *img);
}

static uint8_t wr__rd_byte(double c) {
    c = c < 0.0 ? 0.0 : c > 1.0 ? 1.0 : c;
    return (uint8_t)(c * 255.0 + 0.5);
}

WRDEF void wr_image_fill(wr_image *img, const double rgb[3]) {
    size_t i, n = (size_t)img->w * (size_t)img->h;
    for (i = 0; i < n; ++i) {
        img->rgb[3 * i] = wr__rd_byte(rgb[0]);
        img->rgb[3 * i + 1] = wr__rd_byte(rgb[1]);
        img->rgb[3 * i + 2] = wr__rd_byte(rgb[2]);
        img->depth[i] = HUGE_VAL;
    }
}

WRDEF wr_status wr_image_downsample(wr_image *img, int32_t k, wr_diag *diag) {
    wr_image out;
    int32_t i, j, a, b, c;
    wr_status st;
    if (k < 1 || img->w % k || img->h % k)
        return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "downsample factor %d does not divide %d x %d", (int)k,
                       (int)img->w, (int)img->h);
    if (k == 1) return WR_OK;
    if ((st = wr_image_create(&out, img->w / k, img->h / k, diag)) != WR_OK) return st;
    for (j = 0; j < out.h; ++j)
        for (i = 0; i < out.w; ++i) {
            double dmin = HUGE_VAL;
            for (c = 0; c < 3; ++c) {
                int32_t s = 0;
                for (b = 0; b < k; ++b)
                    for (a = 0; a < k; ++a) s += img->rgb[3 * ((size_t)(j * k + b) * img->w + (size_t)(i * k + a)) + c];
                out.rgb[3 * ((size_t)j * out.w + i) + c] = (uint8_t)((s + k * k / 2) / (k * k));
            }
            for (b = 0; b < k; ++b)
                for (a = 0; a < k; ++a) dmin = fmin(dmin, img->depth[(size_t)(j * k + b) * img->w + (size_t)(i * k + a)]);
            out.depth[(size_t)j * out.w + i] = dmin;
        }
    wr_image_free(img);
    *img = out;
    return WR_OK;
}

/* ---- camera ---------------------------------------------------------------------------------- */

static void wr__rd_normalize(double v[3]) {
    double n = sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    if (n > 0.0) {
        v[0] /= n;
        v[1] /= n;
        v[2] /= n;
    }
}

static void wr__rd_cross(const double a[3], const double b[3], double c[3]) {
    c[0] = a[1] * b[2] - a[2] * b[1];
    c[1] = a[2] * b[0] - a[0] * b[2];
    c[2] = a[0] * b[1] - a[1] * b[0];
}

static double wr__rd_dot(const double a[3], const double b[3]) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

/* The camera frame from azimuth/elevation about `up` (see ON COORDINATES). */
static void wr__rd_frame(wr_view *v, const wr_view_desc *d) {
    double up[3] = {0.0, 0.0, 1.0}, h0[3], h1[3], toward[3], az, el;
    int k;
    if (d && (d->up[0] != 0.0 || d->up[1] != 0.0 || d->up[2] != 0.0)) memcpy(up, d->up, sizeof up);
    wr__rd_normalize(up);
    /* h0: the coordinate axis least aligned with up, made perpendicular to it */
    k = fabs(up[0]) <= fabs(up[1]) && fabs(up[0]) <= fabs(up[2]) ? 0 : fabs(up[1]) <= fabs(up[2]) ? 1 : 2;
    h0[0] = h0[1] = h0[2] = 0.0;
    h0[k] = 1.0;
    for (k = 0; k < 3; ++k) h0[k] -= wr__rd_dot(h0, up) * up[k];
    wr__rd_normalize(h0);
    wr__rd_cross(up, h0, h1);
    az = (d && d->has_angles ? d->azimuth_deg : -60.0) * 3.14159265358979323846 / 180.0;
    el = (d && d->has_angles ? d->elevation_deg : 35.0) * 3.14159265358979323846 / 180.0;
    if (el > 1.5707963) el = 1.5707963; /* exactly 90° would leave "right" undefined */
    if (el < -1.5707963) el = -1.5707963;
    for (k = 0; k < 3; ++k) {
        toward[k] = cos(el) * (cos(az) * h0[k] + sin(az) * h1[k]) + sin(el) * up[k];
        v->fwd[k] = -toward[k];
    }
    wr__rd_cross(v->fwd, up, v->right);
    wr__rd_normalize(v->right);
    wr__rd_cross(v->right, v->fwd, v->upv);
}

WRDEF void wr_view_project(const wr_view *v, const double p[3], double out[3]) {
    double q[3];
    q[0] = p[0] - v->center[0];
    q[1] = p[1] - v->center[1];
    q[2] = p[2] - v->center[2];
    out[0] = v->cx + v->scale * wr__rd_dot(q, v->right);
    out[1] = v->cy - v->scale * wr__rd_dot(q, v->upv); /* image rows grow downwards */
    out[2] = wr__rd_dot(q, v->fwd);
}

WRDEF void wr_view_fit(wr_view *v, const double *pos, int32_t nv, const wr_view_desc *d, int32_t x0, int32_t y0,
                       int32_t w, int32_t h) {
    double lo[2] = {HUGE_VAL, HUGE_VAL}, hi[2] = {-HUGE_VAL, -HUGE_VAL}, margin, sx, sy, c2[2];
    int32_t i;
    int k;
    memset(v, 0, sizeof *v);
    wr__rd_frame(v, d);
    for (i = 0; i < nv; ++i) {
        double a = wr__rd_dot(pos + 3 * i, v->right), b = wr__rd_dot(pos + 3 * i, v->upv);
        if (!isfinite(a) || !isfinite(b)) continue;
        lo[0] = fmin(lo[0], a);
        hi[0] = fmax(hi[0], a);
        lo[1] = fmin(lo[1], b);
        hi[1] = fmax(hi[1], b);
    }
    if (!(hi[0] >= lo[0])) lo[0] = hi[0] = lo[1] = hi[1] = 0.0; /* no finite point */
    margin = (d && d->margin > 0.0 ? d->margin : 0.06) * (double)(w < h ? w : h);
    sx = (hi[0] - lo[0]) > 0.0 ? ((double)w - 2.0 * margin) / (hi[0] - lo[0]) : HUGE_VAL;
    sy = (hi[1] - lo[1]) > 0.0 ? ((double)h - 2.0 * margin) / (hi[1] - lo[1]) : HUGE_VAL;
    v->scale = fmin(sx, sy);
    if (!isfinite(v->scale) || v->scale <= 0.0) v->scale = 1.0;
    c2[0] = 0.5 * (lo[0] + hi[0]);
    c2[1] = 0.5 * (lo[1] + hi[1]);
    for (k = 0; k < 3; ++k) v->center[k] = c2[0] * v->right[k] + c2[1] * v->upv[k];
    v->cx = x0 + 0.5 * w;
    v->cy = y0 + 0.5 * h;
}

/* ---- colour map -------------------------------------------------------------------------------- */

WRDEF void wr_colormap(wr_colormap_kind kind, double t, double rgb[3]) {
    /* Sequential: five anchor colours of matplotlib's "viridis" (perceptually uniform, readable in
     * grey and by most colour-blind readers). Diverging: blue → white → red anchors in the manner of
     * Moreland's cool-warm map, white at t = ½ so a signed quantity reads as "below / above".
     * Both linearly interpolated. */
    static const double seq[5][3] = {{0.267, 0.005, 0.329},
                                     {0.229, 0.322, 0.546},
                                     {0.128, 0.567, 0.551},
                                     {0.369, 0.789, 0.383},
                                     {0.993, 0.906, 0.144}};
    static const double div[5][3] = {{0.230, 0.299, 0.754},
                                     {0.552, 0.690, 0.996},
                                     {0.950, 0.950, 0.950},
                                     {0.958, 0.603, 0.482},
                                     {0.706, 0.016, 0.150}};
    const double(*a)[3] = kind == WR_COLORMAP_DIVERGING ? div : seq;
    double s;
    int k, c;
    if (!(t >= 0.0)) t = 0.0; /* NaN → the low end */
    if (t > 1.0) t = 1.0;
    s = 4.0 * t;
    k = (int)s;
    if (k > 3) k = 3;
    s -= k;
    for (c = 0; c < 3; ++c) rgb[c] = (1.0 - s) * a[k][c] + s * a[k + 1][c];
}

/* ---- rasteriser ------------------------------------------------------------------------------- */

typedef struct wr__rd_ctx {
    wr_image *img;
    const wr_view *view;
    wr_render_style s;
    const double *vn; /* nv*3 vertex normals or NULL (flat) */
    double lo, inv_range;
    double light[3], half[3]; /* world space */
} wr__rd_ctx;

/* The colour range of style->scalar: as given, or (both 0) the finite min and max; a diverging map
 * is made symmetric about 0 so white means zero. */
static void wr__rd_range(const wr_render_style *s, int32_t nv, double *lo, double *hi) {
    int32_t i;
    *lo = s->scalar_lo;
    *hi = s->scalar_hi;
    if (*lo != 0.0 || *hi != 0.0) return;
    *lo = HUGE_VAL;
    *hi = -HUGE_VAL;
    for (i = 0; i < nv; ++i)
        if (isfinite(s->scalar[i])) {
            *lo = fmin(*lo, s->scalar[i]);
            *hi = fmax(*hi, s->scalar[i]);
        }
    if (!(*hi >= *lo)) *lo = *hi = 0.0;
    if (s->colormap == WR_COLORMAP_DIVERGING) {
        double m = fmax(fabs(*lo), fabs(*hi));
        *lo = -m;
        *hi = m;
    }
}

static void wr__rd_style_defaults(wr_render_style *s) {
    if (s->base_rgb[0] == 0.0 && s->base_rgb[1] == 0.0 && s->base_rgb[2] == 0.0) {
        s->base_rgb[0] = 0.80;
        s->base_rgb[1] = 0.82;
        s->base_rgb[2] = 0.88;
    }
    if (s->wire_rgb[0] == 0.0 && s->wire_rgb[1] == 0.0 && s->wire_rgb[2] == 0.0) {
        s->wire_rgb[0] = s->wire_rgb[1] = 0.15;
        s->wire_rgb[2] = 0.20;
    }
    if (!(s->wire_width > 0.0)) s->wire_width = 0.6;
    if (s->light[0] == 0.0 && s->light[1] == 0.0 && s->light[2] == 0.0) {
        s->light[0] = -0.35;
        s->light[1] = 0.45;
        s->light[2] = 0.82;
    }
    if (!(s->ambient > 0.0)) s->ambient = 0.35;
    if (!(s->diffuse > 0.0)) s->diffuse = 0.70;
    if (!(s->specular > 0.0)) s->specular = 0.18;
    if (!(s->shininess > 0.0)) s->shininess = 40.0;
}

/* Tie rule for pixel centres exactly on an edge a→b of a positively oriented triangle: the edge owns
 * them when it points "down" (dy > 0), or is horizontal pointing left. A shared edge is traversed in
 * opposite directions by its two triangles, so exactly one of them owns it. */
static int wr__rd_owns(double dx, double dy) { return dy > 0.0 || (dy == 0.0 && dx < 0.0); }

static void wr__rd_shade(const wr__rd_ctx *c, const double n_in[3], double scalar, double rgb[3]) {
    double n[3], ndl, ndh, alb[3], toward[3];
    int k;
    memcpy(n, n_in, sizeof n);
    wr__rd_normalize(n);
    for (k = 0; k < 3; ++k) toward[k] = -c->view->fwd[k];
    if (wr__rd_dot(n, toward) < 0.0) /* two-sided: cloth has no inside */
        for (k = 0; k < 3; ++k) n[k] = -n[k];
    if (c->s.scalar)
        wr_colormap(c->s.colormap, (scalar - c->lo) * c->inv_range, alb);
    else
        memcpy(alb, c->s.base_rgb, sizeof alb);
    ndl = wr__rd_dot(n, c->light);
    ndh = wr__rd_dot(n, c->half);
    ndl = ndl > 0.0 ? ndl : 0.0;
    ndh = ndh > 0.0 ? pow(ndh, c->s.shininess) : 0.0;
    for (k = 0; k < 3; ++k) rgb[k] = alb[k] * (c->s.ambient + c->s.diffuse * ndl) + c->s.specular * ndh;
}

/* Scan-convert one triangle: p[k] = (pixel x, pixel y, depth); n[k] normals; f[k] scalars. */
static void wr__rd_triangle(const wr__rd_ctx *c, double p[3][3], double n[3][3], const double f_in[3]) {
    wr_image *img = c->img;
    double area, inv, len[3], f[3];
    int32_t i0, i1, j0, j1, i, j;
    int own[3], k;
    memcpy(f, f_in, sizeof f);
    area = (p[1][0] - p[0][0]) * (p[2][1] - p[0][1]) - (p[1][1] - p[0][1]) * (p[2][0] - p[0][0]);
    if (!(fabs(area) > 0.0) || !isfinite(area)) return; /* edge-on or degenerate */
    if (area < 0.0) {                                  /* orient positively: swap corners 1 and 2 */
        double t[3], s;
        memcpy(t, p[1], sizeof t);
        memcpy(p[1], p[2], sizeof t);
        memcpy(p[2], t, sizeof t);
        memcpy(t, n[1], sizeof t);
        memcpy(n[1], n[2], sizeof t);
        memcpy(n[2], t, sizeof t);
        s = f[1];
        f[1] = f[2];
        f[2] = s;
        area = -area;
    }
    inv = 1.0 / area;
    for (k = 0; k < 3; ++k) {
        const double *a = p[(k + 1) % 3], *b = p[(k + 2) % 3]; /* edge opposite corner k */
        own[k] = wr__rd_owns(b[0] - a[0], b[1] - a[1]);
        len[k] = hypot(b[0] - a[0], b[1] - a[1]);
    }
    i0 = (int32_t)floor(fmin(p[0][0], fmin(p[1][0], p[2][0])) - 0.5);
    i1 = (int32_t)ceil(fmax(p[0][0], fmax(p[1][0], p[2][0])) - 0.5);
    j0 = (int32_t)floor(fmin(p[0][1], fmin(p[1][1], p[2][1])) - 0.5);
    j1 = (int32_t)ceil(fmax(p[0][1], fmax(p[1][1], p[2][1])) - 0.5);
    if (i0 < 0) i0 = 0;
    if (j0 < 0) j0 = 0;
    if (i1 > img->w - 1) i1 = img->w - 1;
    if (j1 > img->h - 1) j1 = img->h - 1;
    for (j = j0; j <= j1; ++j)
        for (i = i0; i <= i1; ++i) {
            double x = i + 0.5, y = j + 0.5, e[3], z, nn[3], rgb[3], dmin = HUGE_VAL;
            size_t px = (size_t)j * img->w + (size_t)i;
            int inside = 1;
            for (k = 0; k < 3 && inside; ++k) {
                const double *a = p[(k + 1) % 3], *b = p[(k + 2) % 3];
                e[k] = (b[0] - a[0]) * (y - a[1]) - (b[1] - a[1]) * (x - a[0]);
                if (e[k] < 0.0 || (e[k] == 0.0 && !own[k])) inside = 0;
            }
            if (!inside) continue;
            /* barycentric weights are e[k] / area (orthographic: affine in screen space) */
            z = (e[0] * p[0][2] + e[1] * p[1][2] + e[2] * p[2][2]) * inv;
            if (!(z < img->depth[px])) continue;
            img->depth[px] = z;
            for (k = 0; k < 3; ++k) nn[k] = (e[0] * n[0][k] + e[1] * n[1][k] + e[2] * n[2][k]) * inv;
            wr__rd_shade(c, nn, (e[0] * f[0] + e[1] * f[1] + e[2] * f[2]) * inv, rgb);
            if (c->s.wireframe) {
                /* distance of the centre to the nearest edge, in pixels: e_k / |edge_k| */
                for (k = 0; k < 3; ++k) dmin = fmin(dmin, e[k] / len[k]);
                if (dmin < c->s.wire_width + 0.5) {
                    double w = dmin <= c->s.wire_width ? 0.85 : 0.85 * (c->s.wire_width + 0.5 - dmin) / 0.5;
                    for (k = 0; k < 3; ++k) rgb[k] = (1.0 - w) * rgb[k] + w * c->s.wire_rgb[k];
                }
            }
            for (k = 0; k < 3; ++k) img->rgb[3 * px + k] = wr__rd_byte(rgb[k]);
        }
}

WRDEF wr_status wr_render_mesh(wr_image *img, const wr_view *view, const double *pos, int32_t nv,
                               const int32_t *faces, int32_t nf, const wr_render_style *style, wr_diag *diag) {
    wr__rd_ctx c;
    double *vn = NULL, hi = -HUGE_VAL, toward[3];
    int32_t f, i;
    int k;
    if (!img || !img->rgb || !view || (nv > 0 && !pos) || (nf > 0 && !faces) || nv < 0 || nf < 0)
        return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "render: missing image, view, positions or faces");
    for (f = 0; f < 3 * nf; ++f)
        if (faces[f] < 0 || faces[f] >= nv)
            return wr_fail(diag, WR_ERR_INVALID_ARG, f / 3, "render: face %d has vertex %d outside 0..%d", (int)(f / 3),
                           (int)faces[f], (int)nv - 1);
    memset(&c, 0, sizeof c);
    c.img = img;
    c.view = view;
    if (style) c.s = *style;
    wr__rd_style_defaults(&c.s);
    /* light and half vector from camera coordinates to world */
    for (k = 0; k < 3; ++k) {
        c.light[k] = c.s.light[0] * view->right[k] + c.s.light[1] * view->upv[k] - c.s.light[2] * view->fwd[k];
        toward[k] = -view->fwd[k];
    }
    wr__rd_normalize(c.light);
    for (k = 0; k < 3; ++k) c.half[k] = c.light[k] + toward[k];
    wr__rd_normalize(c.half);
    if (c.s.scalar) {
        wr__rd_range(&c.s, nv, &c.lo, &hi);
        c.inv_range = hi > c.lo ? 1.0 / (hi - c.lo) : 0.0;
    }
    if (!c.s.flat && nv > 0) {
        vn = (double *)wr_calloc_array(3 * (size_t)nv, sizeof(double));
        if (!vn) return wr_fail(diag, WR_ERR_NOMEM, -1, "render: out of memory for %d normals", (int)nv);
        for (f = 0; f < nf; ++f) { /* area-weighted: the unnormalised cross product */
            const double *a = pos + 3 * faces[3 * f], *b = pos + 3 * faces[3 * f + 1], *d = pos + 3 * faces[3 * f + 2];
            double u[3], w[3], x[3];
            for (k = 0; k < 3; ++k) u[k] = b[k] - a[k], w[k] = d[k] - a[k];
            wr__rd_cross(u, w, x);
            for (i = 0; i < 3; ++i)
                for (k = 0; k < 3; ++k) vn[3 * faces[3 * f + i] + k] += x[k];
        }
    }
    for (f = 0; f < nf; ++f) {
        double p[3][3], n[3][3], fv[3], fn[3], u[3], w[3];
        for (i = 0; i < 3; ++i) {
            int32_t v = faces[3 * f + i];
            wr_view_project(view, pos + 3 * v, p[i]);
            fv[i] = c.s.scalar ? c.s.scalar[v] : 0.0;
        }
        for (k = 0; k < 3; ++k) {
            u[k] = pos[3 * faces[3 * f + 1] + k] - pos[3 * faces[3 * f] + k];
            w[k] = pos[3 * faces[3 * f + 2] + k] - pos[3 * faces[3 * f] + k];
        }
        wr__rd_cross(u, w, fn);
        for (i = 0; i < 3; ++i) {
            /* a vertex normal opposing the face normal (a fold) would shade the face from behind */
            const double *src = vn ? vn + 3 * faces[3 * f + i] : fn;
            double s = vn && wr__rd_dot(src, fn) < 0.0 ? -1.0 : 1.0;
            for (k = 0; k < 3; ++k) n[i][k] = s * src[k];
            wr__rd_normalize(n[i]);
        }
        wr__rd_triangle(&c, p, n, fv);
    }
    wr_free(vn);
    return WR_OK;
}

/* ---- text, legend, panels -------------------------------------------------------------------- */

/* 5×7 glyphs, one byte per row (bit 4 = leftmost column), for the characters of wr__rd_chars. */
static const char wr__rd_chars[] = " 0123456789ABCDEFGHIJKLMNOPQRSTUVWXYZ.,:-+=()/%_'<>";
static const uint8_t wr__rd_font[][7] = {
    {0, 0, 0, 0, 0, 0, 0},
    {14, 17, 19, 21, 25, 17, 14}, {4, 12, 4, 4, 4, 4, 14},     {14, 17, 1, 2, 4, 8, 31},
    {30, 1, 1, 14, 1, 1, 30},     {2, 6, 10, 18, 31, 2, 2},    {31, 16, 30, 1, 1, 17, 14},
    {6, 8, 16, 30, 17, 17, 14},   {31, 1, 2, 4, 8, 8, 8},      {14, 17, 17, 14, 17, 17, 14},
    {14, 17, 17, 15, 1, 2, 12},
    {14, 17, 17, 31, 17, 17, 17}, {30, 17, 17, 30, 17, 17, 30}, {14, 17, 16, 16, 16, 17, 14},
    {30, 17, 17, 17, 17, 17, 30}, {31, 16, 16, 30, 16, 16, 31}, {31, 16, 16, 30, 16, 16, 16},
    {14, 17, 16, 23, 17, 17, 15}, {17, 17, 17, 31, 17, 17, 17}, {14, 4, 4, 4, 4, 4, 14},
    {7, 2, 2, 2, 2, 18, 12},      {17, 18, 20, 24, 20, 18, 17}, {16, 16, 16, 16, 16, 16, 31},
    {17, 27, 21, 21, 17, 17, 17}, {17, 17, 25, 21, 19, 17, 17}, {14, 17, 17, 17, 17, 17, 14},
    {30, 17, 17, 30, 16, 16, 16}, {14, 17, 17, 17, 21, 18, 13}, {30, 17, 17, 30, 20, 18, 17},
    {15, 16, 16, 14, 1, 1, 30},   {31, 4, 4, 4, 4, 4, 4},       {17, 17, 17, 17, 17, 17, 14},
    {17, 17, 17, 17, 17, 10, 4},  {17, 17, 17, 21, 21, 21, 10}, {17, 17, 10, 4, 10, 17, 17},
    {17, 17, 10, 4, 4, 4, 4},     {31, 1, 2, 4, 8, 16, 31},
    {0, 0, 0, 0, 0, 12, 12},      {0, 0, 0, 0, 12, 4, 8},       {0, 12, 12, 0, 12, 12, 0},
    {0, 0, 0, 31, 0, 0, 0},       {0, 4, 4, 31, 4, 4, 0},       {0, 0, 31, 0, 31, 0, 0},
    {2, 4, 8, 8, 8, 4, 2},        {8, 4, 2, 2, 2, 4, 8},        {0, 1, 2, 4, 8, 16, 0},
    {24, 25, 2, 4, 8, 19, 3},     {0, 0, 0, 0, 0, 0, 31},       {4, 4, 8, 0, 0, 0, 0},
    {2, 4, 8, 16, 8, 4, 2},       {8, 4, 2, 1, 2, 4, 8}};

WRDEF void wr_image_text(wr_image *img, int32_t x, int32_t y, int32_t scale, const double rgb[3], const char *text) {
    int32_t gx = x, r, col, a, b;
    uint8_t c8[3];
    int k;
    if (!text || !img->rgb) return;
    if (scale < 1) scale = 1;
    for (k = 0; k < 3; ++k) c8[k] = wr__rd_byte(rgb[k]);
    for (; *text; ++text, gx += 6 * scale) {
        int ch = (unsigned char)*text;
        const char *at;
        if (ch >= 'a' && ch <= 'z') ch -= 'a' - 'A';
        at = ch ? strchr(wr__rd_chars, ch) : NULL;
        if (!at) at = wr__rd_chars; /* unknown characters print as blanks */
        for (r = 0; r < 7; ++r)
            for (col = 0; col < 5; ++col) {
                if (!(wr__rd_font[at - wr__rd_chars][r] & (16 >> col))) continue;
                for (b = 0; b < scale; ++b)
                    for (a = 0; a < scale; ++a) {
                        int32_t px = gx + col * scale + a, py = y + r * scale + b;
                        if (px < 0 || py < 0 || px >= img->w || py >= img->h) continue;
                        memcpy(img->rgb + 3 * ((size_t)py * img->w + px), c8, 3);
                    }
            }
    }
}

WRDEF void wr_image_colorbar(wr_image *img, int32_t x, int32_t y, int32_t w, int32_t h, wr_colormap_kind kind,
                             double lo, double hi, const char *label) {
    static const double ink[3] = {0.1, 0.1, 0.1};
    int32_t i, j, s = h >= 28 ? 2 : 1;
    char buf[64];
    for (i = 0; i < w; ++i) {
        double rgb[3];
        wr_colormap(kind, w > 1 ? (double)i / (w - 1) : 0.0, rgb);
        for (j = 0; j < h / 2; ++j) {
            int32_t px = x + i, py = y + j;
            int k;
            if (px < 0 || py < 0 || px >= img->w || py >= img->h) continue;
            for (k = 0; k < 3; ++k) img->rgb[3 * ((size_t)py * img->w + px) + k] = wr__rd_byte(rgb[k]);
        }
    }
    snprintf(buf, sizeof buf, "%.3g", lo);
    wr_image_text(img, x, y + h / 2 + 3, s, ink, buf);
    snprintf(buf, sizeof buf, "%.3g", hi);
    wr_image_text(img, x + w - (int32_t)strlen(buf) * 6 * s, y + h / 2 + 3, s, ink, buf);
    if (label) wr_image_text(img, x + w / 2 - (int32_t)strlen(label) * 3 * s, y + h / 2 + 3, s, ink, label);
}

WRDEF wr_status wr_render_panels(wr_image *img, const wr_render_panel *panels, int32_t n, int32_t columns,
                                 const wr_view_desc *vd, int32_t panel_w, int32_t panel_h, wr_diag *diag) {
    static const double ink[3] = {0.1, 0.1, 0.1};
    const int32_t k = WR_RENDER_SUPERSAMPLE;
    int32_t rows, p, title_h, bar_h, ts, cell_h;
    double scale = HUGE_VAL;
    wr_status st;
    memset(img, 0, sizeof *img);
    if (n < 1 || !panels) return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "render: no panels");
    if (columns < 1) columns = n;
    if (panel_w < 64 || panel_h < 64) return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "render: panel smaller than 64 px");
    rows = (n + columns - 1) / columns;
    ts = panel_w >= 700 ? 3 : 2; /* glyph scale of titles and legends */
    title_h = 7 * ts + 14;
    bar_h = 14 * ts + 12;
    cell_h = title_h + panel_h + bar_h;
    if ((int64_t)columns * panel_w * k > WR_RENDER_MAX_SIDE || (int64_t)rows * cell_h * k > WR_RENDER_MAX_SIDE)
        return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "render: %d x %d panels of %d x %d px exceed %d px", (int)columns,
                       (int)rows, (int)panel_w, (int)panel_h, WR_RENDER_MAX_SIDE / k);
    if ((st = wr_image_create(img, columns * panel_w * k, rows * cell_h * k, diag)) != WR_OK) return st;
    /* one scale for all views, so sizes compare (the base and the wrinkled sheet side by side) */
    for (p = 0; p < n; ++p) {
        wr_view v;
        wr_view_fit(&v, panels[p].pos, panels[p].nv, vd, 0, 0, panel_w * k, panel_h * k);
        scale = fmin(scale, v.scale);
    }
    for (p = 0; p < n; ++p) {
        const wr_render_panel *q = panels + p;
        int32_t x0 = (p % columns) * panel_w, y0 = (p / columns) * cell_h;
        wr_view v;
        wr_view_fit(&v, q->pos, q->nv, vd, k * x0, k * (y0 + title_h), k * panel_w, k * panel_h);
        v.scale = scale;
        if ((st = wr_render_mesh(img, &v, q->pos, q->nv, q->faces, q->nf, &q->style, diag)) != WR_OK) goto fail;
    }
    if ((st = wr_image_downsample(img, k, diag)) != WR_OK) goto fail;
    for (p = 0; p < n; ++p) { /* text after the downsampling: crisp glyphs */
        const wr_render_panel *q = panels + p;
        int32_t x0 = (p % columns) * panel_w, y0 = (p / columns) * cell_h;
        if (q->title) wr_image_text(img, x0 + 10, y0 + 8, ts, ink, q->title);
        if (q->style.scalar && q->colorbar_label) {
            double lo, hi;
            wr__rd_range(&q->style, q->nv, &lo, &hi);
            wr_image_colorbar(img, x0 + panel_w / 8, y0 + title_h + panel_h + 2, 3 * panel_w / 4, bar_h - 8,
                              q->style.colormap, lo, hi, q->colorbar_label);
        }
    }
    return WR_OK;
fail:
    wr_image_free(img);
    return st;
}

/* ---- files --------------------------------------------------------------------------------- */

WRDEF wr_status wr_image_write_ppm(const wr_image *img, const char *path, wr_diag *diag) {
    wr_afile f;
    wr_status st;
    if (!img || !img->rgb) return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "write_ppm: empty image");
    if ((st = wr_afile_open(&f, path, diag)) != WR_OK) return st;
    fprintf(f.fp, "P6\n%d %d\n255\n", (int)img->w, (int)img->h);
    fwrite(img->rgb, 3, (size_t)img->w * (size_t)img->h, f.fp);
    return wr_afile_commit(&f, diag);
}

#if defined(WR_USE_LIBPNG) && WR_USE_LIBPNG
static void wr__rd_png_error(png_structp png, png_const_charp msg) {
    char *buf = (char *)png_get_error_ptr(png);
    if (buf) snprintf(buf, 200, "%s", msg);
    png_longjmp(png, 1);
}
static void wr__rd_png_warning(png_structp png, png_const_charp msg) {
    (void)png;
    (void)msg;
}

WRDEF wr_status wr_image_write_png(const wr_image *img, const char *path, wr_diag *diag) {
    wr_afile f;
    wr_status st;
    png_structp png;
    png_infop info = NULL;
    char msg[200] = "libpng error";
    int32_t j;
    if (!img || !img->rgb) return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "write_png: empty image");
    if ((st = wr_afile_open(&f, path, diag)) != WR_OK) return st;
    png = png_create_write_struct(PNG_LIBPNG_VER_STRING, msg, wr__rd_png_error, wr__rd_png_warning);
    if (png) info = png_create_info_struct(png);
    if (!png || !info) {
        png_destroy_write_struct(&png, NULL);
        wr_afile_abort(&f);
        return wr_fail(diag, WR_ERR_NOMEM, -1, "write_png: libpng could not start");
    }
    if (setjmp(png_jmpbuf(png))) { /* libpng reports errors by longjmp (nothing here holds resources) */
        png_destroy_write_struct(&png, &info);
        wr_afile_abort(&f);
        return wr_fail(diag, WR_ERR_BACKEND, -1, "write_png '%s': %s", path, msg);
    }
    png_init_io(png, f.fp);
    png_set_IHDR(png, info, (png_uint_32)img->w, (png_uint_32)img->h, 8, PNG_COLOR_TYPE_RGB, PNG_INTERLACE_NONE,
                 PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
    png_write_info(png, info);
    for (j = 0; j < img->h; ++j) png_write_row(png, img->rgb + 3 * (size_t)j * (size_t)img->w);
    png_write_end(png, info);
    png_destroy_write_struct(&png, &info);
    return wr_afile_commit(&f, diag);
}
#endif

#ifdef __cplusplus
}
#endif
#endif /* WRINKLE_RENDER_IMPLEMENTATION_DONE */
#endif /* WRINKLE_IMPLEMENTATION */
