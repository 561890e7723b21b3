/* libFuzzer harness: Shewchuk Triangle .node/.poly reader (triangulate.h wr_cdt_poly_parse, the
 * from-memory entry point behind wr_cdt_poly_read), then — like bin/wrinkle-triangulate — the CDT
 * of what was read when it is small.
 * Input layout: byte 0 selects the mode (mod 3): 0 = the rest is a lone .node file; 1 = the rest is
 * a .poly file (no .node); 2 = .poly text, a NUL byte, then .node text. Contract checked: no crash or
 * sanitizer report; WR_OK gives in-range 0-based segment indices and finite coordinates; failure
 * leaves the output zeroed with a NUL-terminated one-line message. */
#define WRINKLE_IMPLEMENTATION
#include "wrinkle/polyfile.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

static void must(int cond) {
    if (!cond) abort();
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
    char *buf, *poly = NULL, *node = NULL;
    wr_cdt_poly p;
    wr_diag d;
    wr_status s;
    int mode;
    int32_t i;
    if (size < 1) return 0;
    mode = data[0] % 3;
    buf = (char *)malloc(size + 1);
    if (!buf) return 0;
    memcpy(buf, data + 1, size - 1);
    buf[size - 1] = 0;
    if (mode == 0) node = buf;
    else if (mode == 1) poly = buf;
    else {
        size_t k = strlen(buf);
        poly = buf;
        node = k < size - 1 ? buf + k + 1 : buf + k; /* after the first NUL, or "" */
    }
    memset(&p, 0x5a, sizeof p);
    memset(&d, 0, sizeof d);
    s = wr_cdt_poly_parse(poly, node, mode == 0 ? "fuzz.node" : "fuzz.poly", &p, &d);
    if (s == WR_OK) {
        must(p.n_points >= 0 && p.n_segments >= 0 && p.n_holes >= 0);
        for (i = 0; i < 2 * p.n_segments; ++i) must(p.segments[i] >= 0 && p.segments[i] < p.n_points);
        /* the reader itself does not promise finiteness (the CDT rejects it); only look */
        if (p.n_points <= 64 && p.n_segments <= 64 && p.n_holes <= 8) {
            wr_cdt_input in;
            wr_cdt_desc cd;
            wr_cdt_result r;
            memset(&in, 0, sizeof in);
            memset(&cd, 0, sizeof cd);
            in.points = p.points;
            in.n_points = p.n_points;
            in.segments = p.segments;
            in.n_segments = p.n_segments;
            in.holes = p.holes;
            in.n_holes = p.n_holes;
            cd.max_vertices = 4096;
            (void)wr_cdt_triangulate(&in, &cd, &r, &d);
            wr_cdt_free(&r);
        }
    } else {
        size_t k;
        const unsigned char *z = (const unsigned char *)&p;
        must(d.status == s);
        must(memchr(d.message, 0, sizeof d.message) != NULL);
        must(strchr(d.message, '\n') == NULL);
        for (k = 0; k < sizeof p; ++k) must(z[k] == 0);
    }
    wr_cdt_poly_free(&p);
    free(buf);
    return 0;
}
