/* meshout.h — writing a mesher result (driver-side helper, not a public wrinkle header; compiled once
 * as drivers/lib/meshout.c and linked into every program). Used by bin/wrinkle-mesh and
 * bin/validate_meshing.
 *
 *   wr_meshout_render_png(res, png, title, draw_edges, diag)
 *       picture of the sizing map (colour, mm) with the mesh edges over it, through gnuplot
 *       (png terminal) from temporary data files; the PNG appears atomically (temp + rename).
 *       Returns WR_ERR_UNSUPPORTED without touching png when gnuplot is not on PATH.
 *   wr_meshout_write_dir(res, pf, dir, want_png, diag)
 *       DIR/mesh.obj, mesh.ply, seams.csv (only when seams exist), summary.json and, when want_png,
 *       sizing.png. Everything is first written into a private staging directory inside DIR and
 *       renamed into place only when every file is complete; on failure the staging directory is
 *       removed and DIR keeps whatever it held before. A missing gnuplot is not a failure: the
 *       picture is skipped (*png_written = 0; png_written may be NULL). A seams.csv or sizing.png
 *       left from an earlier run that this run does not write is removed.
 */
#ifndef WRINKLE_DRIVERS_MESHOUT_H
#define WRINKLE_DRIVERS_MESHOUT_H

#include "pattern.h"
#include "wrinkle/mesher.h"

wr_status wr_meshout_render_png(const wr_mesher_result *res, const char *png_path, const char *title,
                                int draw_edges, wr_diag *diag);
wr_status wr_meshout_write_dir(const wr_mesher_result *res, const wr_pattern_file *pf, const char *dir, int want_png,
                               int *png_written, wr_diag *diag);

#endif
