/* libFuzzer harness: the garment pattern JSON reader (drivers/lib/pattern.c wr_pattern_parse) and,
 * on success, the mesher itself (mesher.h wr_mesher_run) under a small vertex budget — the path
 * bin/wrinkle-mesh takes. Linked with drivers/lib/pattern.c (Makefile FUZZ_EXTRA_fuzz_pattern).
 * Contract: no crash or sanitizer report, no leak; failures carry a one-line message; a successful
 * mesh has in-range faces and a positive finite sizing value per vertex. */
/* This harness is the program's one WRINKLE_IMPLEMENTATION unit. */
#define WRINKLE_IMPLEMENTATION
#include "wrinkle/wrinkle.h"
#include "pattern.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

static void must(int cond) {
    if (!cond) abort();
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
    wr_pattern_file pf;
    wr_diag d;
    wr_status s;
    memset(&d, 0, sizeof d);
    s = wr_pattern_parse((const char *)data, size, "fuzz.json", &pf, &d);
    if (s == WR_OK) {
        wr_mesher_desc md = pf.desc;
        wr_mesher_result res;
        int32_t i;
        md.max_vertices = 2000; /* bounded work per input */
        memset(&d, 0, sizeof d);
        s = wr_mesher_run(&pf.pattern, &md, &res, &d);
        if (s == WR_OK) {
            for (i = 0; i < 3 * res.mesh.nf; ++i) must(res.mesh.faces[i] >= 0 && res.mesh.faces[i] < res.mesh.nv);
            for (i = 0; i < res.mesh.nv; ++i) must(res.sizing[i] > 0.0 && isfinite(res.sizing[i]));
        } else {
            must(d.status == s && memchr(d.message, 0, sizeof d.message) != NULL && !strchr(d.message, '\n'));
        }
        wr_mesher_free(&res);
    } else {
        must(d.status == s && memchr(d.message, 0, sizeof d.message) != NULL && !strchr(d.message, '\n'));
    }
    wr_pattern_file_free(&pf);
    return 0;
}
