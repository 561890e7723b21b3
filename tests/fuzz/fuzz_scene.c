/* libFuzzer harness: the statics scene JSON reader (drivers/lib/scene.c wr_scene_parse, pure, no
 * file access) and, for small generated meshes, the set-up step wr_scene_run_create (rest mesh,
 * shell, prescribed sets). Linked with drivers/lib/scene.c (Makefile FUZZ_EXTRA_fuzz_scene).
 * Contract: no crash or sanitizer report, no leak; a failure carries a one-line message naming the
 * JSON path. */
/* This harness is the program's one WRINKLE_IMPLEMENTATION unit. */
#define WRINKLE_IMPLEMENTATION
#include "wrinkle/wrinkle.h"
#include "scene.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

/* Rough vertex count of a generated mesh, or -1 when it is not small / not generated. */
static double approx_vertices(const wr_scene_mesh *m) {
    double r = m->resolution, n = -1.0;
    switch (m->kind) {
    case WR_SCENE_MESH_RECTANGLE:
        if (m->nx > 0 && m->ny > 0) return ((double)m->nx + 1) * ((double)m->ny + 1);
        /* fall through */
    case WR_SCENE_MESH_DELAUNAY_RECTANGLE:
        if (r > 0) n = (m->width / r + 2) * (m->height / r + 2);
        break;
    case WR_SCENE_MESH_DISK:
        if (r > 0) n = 4.0 * (m->radius / r + 2) * (m->radius / r + 2);
        break;
    case WR_SCENE_MESH_CYLINDER:
        if (r > 0) n = (6.3 * m->radius / r + 2) * (m->height / r + 2);
        break;
    default:
        break;
    }
    return (n == n) ? n : -1.0;
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
    wr_scene sc;
    wr_diag d;
    wr_status s;
    memset(&d, 0, sizeof d);
    s = wr_scene_parse(&sc, (const char *)data, size, "/nonexistent-fuzz-dir", &d);
    if (s == WR_OK) {
        double nv = approx_vertices(&sc.mesh);
        if (nv >= 0 && nv <= 3000) {
            wr_scene_run run;
            memset(&run, 0, sizeof run);
            (void)wr_scene_run_create(&run, &sc, &d);
            wr_scene_run_free(&run);
        }
    } else if (d.status != s || memchr(d.message, 0, sizeof d.message) == NULL || strchr(d.message, '\n')) {
        abort();
    }
    wr_scene_free(&sc);
    return 0;
}
