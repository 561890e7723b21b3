/* libFuzzer harness: Wavefront OBJ reader (mesh.h wr_mesh_parse_obj) on arbitrary bytes.
 * Contract checked: no crash / sanitizer report; WR_OK yields a mesh whose topology arrays are
 * consistent (indices in range, edge endpoints ordered, face→edge signs ±1); a failure leaves the
 * mesh zeroed and the diag message NUL-terminated. Build: make fuzz-smoke / make fuzz. */
#define WRINKLE_IMPLEMENTATION
#include "wrinkle/mesh.h"

#include <stdint.h>
#include <stdlib.h>
#include <string.h>

static void must(int cond) {
    if (!cond) abort(); /* a contract violation is a finding: libFuzzer saves the input */
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
    wr_mesh m;
    wr_diag d;
    wr_status s;
    int32_t i;
    memset(&m, 0x5a, sizeof m); /* the parser must not depend on the caller zeroing the mesh */
    memset(&d, 0, sizeof d);
    s = wr_mesh_parse_obj(&m, (const char *)data, size, &d);
    if (s == WR_OK) {
        must(m.nv >= 1 && m.nf >= 1 && m.ne >= 3);
        for (i = 0; i < 3 * m.nf; ++i) must(m.faces[i] >= 0 && m.faces[i] < m.nv);
        for (i = 0; i < m.ne; ++i) must(m.edges[2 * i] < m.edges[2 * i + 1]);
        for (i = 0; i < 3 * m.nf; ++i) {
            must(m.face_edges[i] >= 0 && m.face_edges[i] < m.ne);
            must(m.face_edge_sign[i] == 1 || m.face_edge_sign[i] == -1);
        }
        for (i = 0; i < 3 * m.nv; ++i) must(m.pos[i] == m.pos[i]); /* finite coordinates only */
    } else {
        size_t k;
        const unsigned char *z = (const unsigned char *)&m;
        must(d.status == s);
        must(memchr(d.message, 0, sizeof d.message) != NULL);
        for (k = 0; k < sizeof m; ++k) must(z[k] == 0);
    }
    wr_mesh_free(&m);
    return 0;
}
