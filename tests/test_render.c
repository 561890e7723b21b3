/* Tests for render.h: coverage of a known triangle, the tie rule on shared edges, depth order,
 * two-sided shading, the fitted camera, the colour maps, the PNG writer read back through libpng. */
#define _POSIX_C_SOURCE 200809L
#include <criterion/criterion.h>
#include <math.h>
#include <png.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "wrinkle/render.h"

/* A camera whose projection is the identity on (x, y): pixel x = world x, pixel y = world y, depth =
 * world z (looking along +z). Built by hand so the tests know every pixel position exactly. */
static wr_view identity_view(void) {
    wr_view v;
    memset(&v, 0, sizeof v);
    v.right[0] = 1.0;
    v.upv[1] = -1.0; /* wr_view_project flips y for image rows; this undoes it */
    v.fwd[2] = 1.0;
    v.scale = 1.0;
    return v;
}

static int covered(const wr_image *img, int i, int j) { return img->depth[(size_t)j * img->w + i] < 1e300; }

static int count_covered(const wr_image *img) {
    int i, j, n = 0;
    for (j = 0; j < img->h; ++j)
        for (i = 0; i < img->w; ++i) n += covered(img, i, j);
    return n;
}

/* Triangle (2,2), (10.2,2), (2,10.2): pixel centres (i+½, j+½) with i, j >= 2 and i + j + 1 < 12.2,
 * i.e. a + b <= 7 for a = i-2, b = j-2: 8·9/2 = 36 pixels, no centre on an edge. */
Test(render, known_triangle_covers_expected_pixels) {
    wr_image img;
    wr_view v = identity_view();
    double pos[9] = {2, 2, 0, 10.2, 2, 0, 2, 10.2, 0};
    int32_t f[3] = {0, 1, 2};
    int i, j;
    wr_render_style s;
    memset(&s, 0, sizeof s);
    cr_assert_eq(wr_image_create(&img, 16, 16, NULL), WR_OK);
    cr_assert_eq(wr_render_mesh(&img, &v, pos, 3, f, 1, &s, NULL), WR_OK);
    cr_expect_eq(count_covered(&img), 36);
    for (j = 0; j < 16; ++j)
        for (i = 0; i < 16; ++i) {
            int want = i >= 2 && j >= 2 && i + j <= 11;
            cr_expect_eq(covered(&img, i, j), want, "pixel (%d, %d)", i, j);
            /* uncovered pixels keep the white background */
            if (!want) cr_expect_eq(img.rgb[3 * (j * 16 + i)], 255);
        }
    wr_image_free(&img);
}

/* A square [1,9]² split along its diagonal, whose pixel centres (i+½, j+½) fall exactly on the
 * diagonal x = y for i = j: each pixel must be drawn by exactly one triangle — 64 in all, and each
 * triangle's own count is 64 minus the other's (28 strictly below + 8 on the diagonal for one). */
Test(render, shared_edge_pixels_drawn_once) {
    wr_image img;
    wr_view v = identity_view();
    double pos[12] = {1, 1, 0, 9, 1, 0, 9, 9, 0, 1, 9, 0};
    int32_t lower[3] = {0, 1, 2}, upper[3] = {0, 2, 3};
    wr_render_style s;
    int n1, n2;
    memset(&s, 0, sizeof s);
    cr_assert_eq(wr_image_create(&img, 12, 12, NULL), WR_OK);
    cr_assert_eq(wr_render_mesh(&img, &v, pos, 4, lower, 1, &s, NULL), WR_OK);
    n1 = count_covered(&img);
    wr_image_free(&img);
    cr_assert_eq(wr_image_create(&img, 12, 12, NULL), WR_OK);
    cr_assert_eq(wr_render_mesh(&img, &v, pos, 4, upper, 1, &s, NULL), WR_OK);
    n2 = count_covered(&img);
    cr_expect_eq(n1 + n2, 64, "lower %d + upper %d", n1, n2);
    cr_expect(n1 == 28 || n1 == 36, "lower triangle %d pixels: 28 off-diagonal, plus the 8 diagonal ones or not", n1);
    wr_image_free(&img);
}

/* Two overlapping triangles at depths 1 (red) and 2 (blue): the nearer one wins whatever the order. */
Test(render, depth_order) {
    double pos[18] = {0, 0, 1, 12, 0, 1, 0, 12, 1, /* near */ 0, 0, 2, 12, 0, 2, 0, 12, 2 /* far */};
    int32_t near_f[3] = {0, 1, 2}, far_f[3] = {3, 4, 5};
    int order;
    for (order = 0; order < 2; ++order) {
        wr_image img;
        wr_view v = identity_view();
        wr_render_style red, blue;
        const uint8_t *px;
        memset(&red, 0, sizeof red);
        memset(&blue, 0, sizeof blue);
        red.base_rgb[0] = 1.0, red.base_rgb[1] = 0.001, red.base_rgb[2] = 0.001;
        blue.base_rgb[0] = 0.001, blue.base_rgb[1] = 0.001, blue.base_rgb[2] = 1.0;
        red.specular = blue.specular = 1e-9;
        cr_assert_eq(wr_image_create(&img, 16, 16, NULL), WR_OK);
        if (order == 0) {
            wr_render_mesh(&img, &v, pos, 6, near_f, 1, &red, NULL);
            wr_render_mesh(&img, &v, pos, 6, far_f, 1, &blue, NULL);
        } else {
            wr_render_mesh(&img, &v, pos, 6, far_f, 1, &blue, NULL);
            wr_render_mesh(&img, &v, pos, 6, near_f, 1, &red, NULL);
        }
        px = img.rgb + 3 * (3 * 16 + 3);
        cr_expect(px[0] > 100 && px[2] < 10, "order %d: pixel (3,3) = (%d, %d, %d), want red", order, px[0], px[1], px[2]);
        cr_expect_float_eq(img.depth[3 * 16 + 3], 1.0, 1e-12);
        wr_image_free(&img);
    }
}

/* Cloth has no inside: the same triangle wound either way, lit from the camera, shades alike. */
Test(render, two_sided) {
    double pos[9] = {1, 1, 0, 14, 1, 0, 1, 14, 0};
    int32_t ccw[3] = {0, 1, 2}, cw[3] = {0, 2, 1};
    wr_image a, b;
    wr_view v = identity_view();
    wr_render_style s;
    memset(&s, 0, sizeof s);
    cr_assert_eq(wr_image_create(&a, 16, 16, NULL), WR_OK);
    cr_assert_eq(wr_image_create(&b, 16, 16, NULL), WR_OK);
    wr_render_mesh(&a, &v, pos, 3, ccw, 1, &s, NULL);
    wr_render_mesh(&b, &v, pos, 3, cw, 1, &s, NULL);
    cr_expect_eq(memcmp(a.rgb, b.rgb, 3 * 16 * 16), 0);
    /* lit, not the ambient term only: the light has a component along the view axis */
    cr_expect_gt(a.rgb[3 * (4 * 16 + 4)], (int)(0.35 * 0.80 * 255 + 20));
    wr_image_free(&a);
    wr_image_free(&b);
}

/* The fitted camera puts every vertex inside the viewport, with the margin, and the long side of
 * the projection spans the viewport minus the margins (the fit is tight). */
Test(render, view_fit) {
    double pos[12] = {0, 0, 0, 0.25, 0, 0, 0.25, 0.1, 0.01, 0, 0.1, 0};
    wr_view v;
    wr_view_desc d;
    double lo[2] = {1e9, 1e9}, hi[2] = {-1e9, -1e9}, q[3];
    int i, az;
    memset(&d, 0, sizeof d);
    for (az = -180; az <= 180; az += 45) {
        d.has_angles = 1;
        d.azimuth_deg = az;
        d.elevation_deg = 30;
        wr_view_fit(&v, pos, 4, &d, 100, 50, 400, 300);
        lo[0] = lo[1] = 1e9;
        hi[0] = hi[1] = -1e9;
        for (i = 0; i < 4; ++i) {
            wr_view_project(&v, pos + 3 * i, q);
            lo[0] = fmin(lo[0], q[0]), hi[0] = fmax(hi[0], q[0]);
            lo[1] = fmin(lo[1], q[1]), hi[1] = fmax(hi[1], q[1]);
        }
        /* margin 0.06 × 300 = 18 px on each side; 1e-9 px for rounding */
        cr_expect(lo[0] >= 118 - 1e-9 && hi[0] <= 482 + 1e-9 && lo[1] >= 68 - 1e-9 && hi[1] <= 332 + 1e-9,
                  "az %d: projection [%g, %g] x [%g, %g]", az, lo[0], hi[0], lo[1], hi[1]);
        cr_expect(fabs((hi[0] - lo[0]) - 364) < 1e-9 || fabs((hi[1] - lo[1]) - 264) < 1e-9, "az %d: fit not tight", az);
    }
    /* top view (elevation 90): x to the right, y up the screen */
    d.azimuth_deg = -90;
    d.elevation_deg = 90;
    wr_view_fit(&v, pos, 4, &d, 0, 0, 400, 300);
    wr_view_project(&v, pos + 3, q); /* (0.25, 0, 0): right, bottom */
    cr_expect(q[0] > 300 && q[1] > 150, "top view: (%g, %g)", q[0], q[1]);
}

Test(render, colormaps) {
    double c[3];
    wr_colormap(WR_COLORMAP_DIVERGING, 0.5, c);
    cr_expect(c[0] > 0.9 && c[1] > 0.9 && c[2] > 0.9, "diverging middle is white");
    wr_colormap(WR_COLORMAP_DIVERGING, 0.0, c);
    cr_expect(c[2] > c[0], "diverging low end is blue");
    wr_colormap(WR_COLORMAP_DIVERGING, 1.0, c);
    cr_expect(c[0] > c[2], "diverging high end is red");
    wr_colormap(WR_COLORMAP_SEQUENTIAL, 0.0, c);
    cr_expect(c[0] + c[1] + c[2] < 0.7, "sequential low end is dark");
    wr_colormap(WR_COLORMAP_SEQUENTIAL, 1.0, c);
    cr_expect(c[0] + c[1] > 1.8, "sequential high end is yellow");
    wr_colormap(WR_COLORMAP_SEQUENTIAL, NAN, c); /* NaN: the low end, never garbage */
    cr_expect(c[0] + c[1] + c[2] < 0.7);
}

/* Scalar colour: a triangle whose three vertices carry the range's minimum gets the map's low end. */
Test(render, scalar_colour) {
    double pos[9] = {1, 1, 0, 14, 1, 0, 1, 14, 0}, lo[3] = {0, 0, 0}, c[3];
    int32_t f[3] = {0, 1, 2};
    wr_image img;
    wr_view v = identity_view();
    wr_render_style s;
    const uint8_t *px;
    memset(&s, 0, sizeof s);
    s.scalar = lo;
    s.scalar_lo = 0.0;
    s.scalar_hi = 1.0;
    s.colormap = WR_COLORMAP_DIVERGING;
    s.specular = 1e-9;
    s.ambient = 1.0;
    s.diffuse = 1e-9;
    cr_assert_eq(wr_image_create(&img, 16, 16, NULL), WR_OK);
    wr_render_mesh(&img, &v, pos, 3, f, 1, &s, NULL);
    wr_colormap(WR_COLORMAP_DIVERGING, 0.0, c);
    px = img.rgb + 3 * (3 * 16 + 3);
    cr_expect(abs(px[0] - (int)(c[0] * 255 + 0.5)) <= 1 && abs(px[2] - (int)(c[2] * 255 + 0.5)) <= 1,
              "(%d, %d, %d)", px[0], px[1], px[2]);
    wr_image_free(&img);
}

Test(render, bad_input) {
    wr_image img;
    wr_view v = identity_view();
    double pos[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    int32_t f[3] = {0, 1, 3};
    wr_diag d;
    cr_expect_eq(wr_image_create(&img, 0, 10, &d), WR_ERR_INVALID_ARG);
    cr_expect_eq(wr_image_create(&img, 100000, 10, &d), WR_ERR_INVALID_ARG);
    cr_assert_eq(wr_image_create(&img, 8, 8, NULL), WR_OK);
    cr_expect_eq(wr_render_mesh(&img, &v, pos, 3, f, 1, NULL, &d), WR_ERR_INVALID_ARG);
    cr_expect_eq(d.item, 0);
    cr_expect_eq(wr_image_downsample(&img, 3, &d), WR_ERR_INVALID_ARG);
    wr_image_free(&img);
}

/* 2×2 box filter: the mean of each block, rounded. */
Test(render, downsample) {
    wr_image img;
    int c;
    cr_assert_eq(wr_image_create(&img, 4, 2, NULL), WR_OK);
    memset(img.rgb, 0, 4 * 2 * 3);
    for (c = 0; c < 3; ++c) img.rgb[c] = 255, img.rgb[3 + c] = 255, img.rgb[12 + c] = 1; /* block 0: 255,255,0,1 */
    cr_assert_eq(wr_image_downsample(&img, 2, NULL), WR_OK);
    cr_expect_eq(img.w, 2);
    cr_expect_eq(img.h, 1);
    cr_expect_eq(img.rgb[0], 128); /* (255+255+0+1)/4 = 127.75 */
    cr_expect_eq(img.rgb[3], 0);
    wr_image_free(&img);
}

/* Write through wr_image_write_png, read back with libpng's reader: the same pixels. */
Test(render, png_round_trip) {
    wr_image img;
    char path[] = "/tmp/wr_render_testXXXXXX";
    int fd = mkstemp(path), i;
    png_image rd;
    uint8_t *buf;
    cr_assert(fd >= 0);
    close(fd);
    cr_assert_eq(wr_image_create(&img, 37, 23, NULL), WR_OK);
    for (i = 0; i < 37 * 23 * 3; ++i) img.rgb[i] = (uint8_t)(i * 7 + i / 3);
    cr_assert_eq(wr_image_write_png(&img, path, NULL), WR_OK);
    memset(&rd, 0, sizeof rd);
    rd.version = PNG_IMAGE_VERSION;
    cr_assert(png_image_begin_read_from_file(&rd, path), "libpng: %s", rd.message);
    cr_expect_eq(rd.width, 37);
    cr_expect_eq(rd.height, 23);
    rd.format = PNG_FORMAT_RGB;
    buf = (uint8_t *)malloc(PNG_IMAGE_SIZE(rd));
    cr_assert(png_image_finish_read(&rd, NULL, buf, 0, NULL), "libpng: %s", rd.message);
    cr_expect_eq(memcmp(buf, img.rgb, 37 * 23 * 3), 0);
    free(buf);
    remove(path);
    /* an unwritable path fails cleanly and names it */
    {
        wr_diag d;
        cr_expect_neq(wr_image_write_png(&img, "/nonexistent-dir/x.png", &d), WR_OK);
        cr_expect(strstr(d.message, "/nonexistent-dir/x.png") != NULL, "%s", d.message);
    }
    wr_image_free(&img);
}

/* Text draws ink inside its box and nothing outside it. */
Test(render, text) {
    wr_image img;
    static const double ink[3] = {0, 0, 0};
    int i, j, inside = 0, outside = 0;
    cr_assert_eq(wr_image_create(&img, 40, 12, NULL), WR_OK);
    wr_image_text(&img, 2, 2, 1, ink, "A1");
    for (j = 0; j < 12; ++j)
        for (i = 0; i < 40; ++i) {
            int dark = img.rgb[3 * (j * 40 + i)] == 0;
            if (i >= 2 && i < 13 && j >= 2 && j < 9) inside += dark;
            else outside += dark;
        }
    cr_expect_eq(outside, 0);
    cr_expect_eq(inside, 18 + 10, "'A' has 18 ink pixels and '1' 10: %d", inside); /* see the glyph table */
    wr_image_free(&img);
}
