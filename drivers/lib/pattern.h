/* pattern.h — the garment pattern JSON format (compiled once as drivers/lib/pattern.c with cJSON and
 * linked into every program). Installed by `make install` for engines as
 * <wrinkle/formats/pattern.h> with libwrinkle-formats.a (pkg-config wrinkle-formats); needs cJSON
 * (Debian libcjson-dev, MIT, -lcjson). Link it after the translation unit that defines
 * WRINKLE_IMPLEMENTATION: the library holds no wrinkle code, only the reader.
 *
 * Format: docs/pattern-format.md. Lengths in the file are MILLIMETRES (converted to metres here);
 * stiffnesses are SI (B in N·m, E in N/m²); angles in degrees. Validation is strict: unknown keys,
 * wrong types, non-finite numbers, too few points, unknown panel names, values outside their range
 * are rejected with a message naming the JSON path, e.g. "panels[1].holes[0]: fewer than 3 points".
 * Geometry that needs the whole pattern (seam ends on the boundary, overlapping seams, fold lines
 * leaving their panel) is checked by wr_mesher_run, which names the item the same way.
 *
 * API
 *   wr_pattern_parse(text, len, name, out, diag)   parse from memory (text need not be NUL-terminated)
 *   wr_pattern_load(path, out, diag)               read a file and parse it (WR_ERR_IO if unreadable)
 *   wr_pattern_builtin_fig14(out, diag)            the built-in example (Style3D Fig. 14 square)
 *   wr_pattern_file_free(f)                        free everything (safe on a zeroed struct)
 *   WR_PATTERN_FIG14_JSON                          the built-in example's JSON text
 */
#ifndef WRINKLE_DRIVERS_PATTERN_H
#define WRINKLE_DRIVERS_PATTERN_H

#include <stddef.h>

#include "wrinkle/mesher.h"

/* Largest file wr_pattern_load reads (a pattern is a few kB; 64 MB leaves room for digitised curves). */
#define WR_PATTERN_MAX_FILE_BYTES (64L << 20)

typedef struct wr_pattern_file {
    wr_pattern pattern;   /* view into the storage below; pass to wr_mesher_run */
    wr_mesher_desc desc;  /* from the optional "mesher" block (zero = defaults) */
    char name[128];       /* "name" of the pattern, or "" */
    char **panel_names;   /* n_panels names (owned; "" when the file gives none) */
    void **allocs_;       /* private: everything allocated for this file */
    int n_allocs_, cap_allocs_;
} wr_pattern_file;

wr_status wr_pattern_parse(const char *text, size_t len, const char *name, wr_pattern_file *out, wr_diag *diag);
wr_status wr_pattern_load(const char *path, wr_pattern_file *out, wr_diag *diag);
wr_status wr_pattern_builtin_fig14(wr_pattern_file *out, wr_diag *diag);
void wr_pattern_file_free(wr_pattern_file *f);

extern const char WR_PATTERN_FIG14_JSON[];

#endif
