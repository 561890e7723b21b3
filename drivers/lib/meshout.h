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
 *       left from an earlier run that this run does not write is removed. Also writes mesh.vtk
 *       (the same per-vertex fields for ParaView) and names the OBJ groups after the panels.
 *
 * Viewer-ready files (ParaView, MeshLab, Blender) for any mesh plus per-vertex fields:
 *   wr_meshout_write_viewer(mesh, pos, fields, n_fields, group_names, stem, formats, diag)
 *       STEM.obj: v, vt (rest coordinates; corner_rest per corner for sewn meshes; (x, y) of pos
 *                 when the mesh has no rest), vn (area-weighted vertex normals of pos), one `g`
 *                 per panel named group_names[panel] (spaces → '_'; NULL or "" → panel<i>);
 *       STEM.ply: x y z nx ny nz s t [float] then each field [float] (Blender reads float
 *                 properties; s t are the texture coordinates MeshLab and Blender look for);
 *       STEM.vtk: legacy POLYDATA with NORMALS, TEXTURE_COORDINATES and one SCALARS per field.
 *       formats: WR_MESHOUT_OBJ | WR_MESHOUT_PLY | WR_MESHOUT_VTK. pos NULL = mesh->pos. Field
 *       names: letters, digits and '_'. Non-finite field values are written as 0 in PLY (which has
 *       no NaN convention) and as NaN in VTK (ParaView shows them as missing) — the count of such
 *       values is not an error here; callers that must not have any check first. Atomic per file.
 *   wr_meshout_max_strain(mesh, pos)
 *       largest |l / L − 1| over the edges, l at pos, L in the rest metric: the plausibility check
 *       of the drivers (a result above 1, i.e. 100 %, is almost always a unit slip or a runaway).
 *   wr_meshout_png(path, panels, n, columns, panel_w, panel_h, view, diag)
 *       wr_render_panels + wr_image_write_png (render.h): the pictures of --png.
 *   wr_meshout_tfw(dir, base_mesh, base_pos, material, tfw_desc, tfw_result, groups, png, diag)
 *       the TFW outputs of bin/wrinkle-tfw (and the demo): DIR/base.obj (vt, vn, groups: the
 *       input OBJ's g names when groups is non-NULL, else panel<id>; wrinkled.obj the same),
 *       DIR/fields.ply + fields.vtk (per base vertex: a [m], phase [rad, one corner's value wrapped
 *       to (-π, π]], omega_abs [rad, mean |ω| of the incident edges], W = 1 where every incident
 *       face is wrinkle-free, sizing [m] = the base's local resolution, the mean rest length of the
 *       vertex's edges: on a wrinkle-mesh output, the sizing map as realised), DIR/wrinkled.obj/.ply/
 *       .vtk (per fine vertex: a [m], height [m] = the wrinkled surface's offset from the smooth
 *       (a = 0) subdivided base along its normal, phase, W, and sizing Loop-subdivided) and,
 *       when png is nonzero, DIR/wrinkles.png: the coarse base with its edges beside the wrinkled
 *       surface coloured by height. Nothing is written when result->wrinkled is empty except the
 *       base files. Each file atomic.
 *   wr_meshout_tfw_png(path, base_mesh, base_pos, material, tfw_desc, tfw_result, diag)
 *       that picture alone, at any path (the validation report's renders).
 */
#ifndef WRINKLE_DRIVERS_MESHOUT_H
#define WRINKLE_DRIVERS_MESHOUT_H

#include "pattern.h"
#include "wrinkle/mesher.h"
#include "wrinkle/render.h"
#include "wrinkle/tfw.h"

#define WR_MESHOUT_OBJ 1u
#define WR_MESHOUT_PLY 2u
#define WR_MESHOUT_VTK 4u

typedef struct wr_meshout_field {
    const char *name;     /* e.g. "amplitude" */
    const double *values; /* nv values */
} wr_meshout_field;

wr_status wr_meshout_render_png(const wr_mesher_result *res, const char *png_path, const char *title,
                                int draw_edges, wr_diag *diag);
wr_status wr_meshout_write_dir(const wr_mesher_result *res, const wr_pattern_file *pf, const char *dir, int want_png,
                               int *png_written, wr_diag *diag);
wr_status wr_meshout_write_viewer(const wr_mesh *m, const double *pos, const wr_meshout_field *fields, int32_t n_fields,
                                  const char *const *group_names, int32_t n_groups, const char *stem, unsigned formats,
                                  wr_diag *diag);
wr_status wr_meshout_tfw(const char *dir, const wr_mesh *base, const double *base_pos, const wr_wf_material *mat,
                         const wr_tfw_desc *td, const wr_tfw_result *r, const wr_obj_groups *groups, int png,
                         wr_diag *diag);
wr_status wr_meshout_tfw_png(const char *path, const wr_mesh *base, const double *base_pos, const wr_wf_material *mat,
                             const wr_tfw_desc *td, const wr_tfw_result *r, wr_diag *diag);
double wr_meshout_max_strain(const wr_mesh *m, const double *pos);
wr_status wr_meshout_png(const char *path, const wr_render_panel *panels, int32_t n, int32_t columns, int32_t panel_w,
                         int32_t panel_h, const wr_view_desc *view, wr_diag *diag);

#endif
