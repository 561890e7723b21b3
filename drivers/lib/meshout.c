/* meshout.c — see meshout.h. Uses cJSON (summary.json) and gnuplot (sizing.png) when present. */
#define _POSIX_C_SOURCE 200809L
#include "meshout.h"

#include "jsonout.h"

#include <cjson/cJSON.h>
#include <dirent.h>
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

/* Raster of the sizing picture (longest side, pixels of the data grid; the PNG is 1000 px wide). */
#define MESHOUT_GRID 420

static int have_gnuplot(void) {
    int rc = system("command -v gnuplot >/dev/null 2>&1");
    return rc != -1 && WIFEXITED(rc) && WEXITSTATUS(rc) == 0;
}

static void remove_tree(const char *dir) {
    DIR *d = opendir(dir);
    struct dirent *e;
    char p[WR_PATH_MAX];
    if (!d) return;
    while ((e = readdir(d)) != NULL) {
        if (!strcmp(e->d_name, ".") || !strcmp(e->d_name, "..")) continue;
        snprintf(p, sizeof p, "%s/%s", dir, e->d_name);
        remove(p);
    }
    closedir(d);
    rmdir(dir);
}

/* Escape a string for a single-quoted gnuplot string. */
static void gp_quote(FILE *f, const char *s) {
    fputc('\'', f);
    for (; *s; ++s) {
        if (*s == '\'')
            fputs("''", f);
        else if (*s != '\n' && *s != '\r')
            fputc(*s, f);
    }
    fputc('\'', f);
}

/* The sizing map sampled on a square grid over the rest-space extent of the mesh, in mm (NaN
 * outside every face: holes and gaps stay undefined). */
typedef struct sizing_raster {
    double x0, y0, x1, y1, cell, vmin, vmax, *val;
    int32_t nx, ny;
} sizing_raster;

/* Sample every grid point inside face f with the sizing map of the face's panel. */
static void raster_face(const wr_mesher_result *res, int32_t f, sizing_raster *R) {
    const wr_mesh *m = &res->mesh;
    double uv[6], bx0, bx1, by0, by1, det;
    int32_t p = m->face_panel ? m->face_panel[f] : 0, a0, a1, b0, b1, i, j;
    wr_mesh_face_rest(m, f, uv);
    bx0 = fmin(uv[0], fmin(uv[2], uv[4]));
    bx1 = fmax(uv[0], fmax(uv[2], uv[4]));
    by0 = fmin(uv[1], fmin(uv[3], uv[5]));
    by1 = fmax(uv[1], fmax(uv[3], uv[5]));
    det = (uv[2] - uv[0]) * (uv[5] - uv[1]) - (uv[4] - uv[0]) * (uv[3] - uv[1]);
    if (det == 0.0) return;
    a0 = (int32_t)ceil((bx0 - R->x0) / R->cell);
    a1 = (int32_t)floor((bx1 - R->x0) / R->cell);
    b0 = (int32_t)ceil((by0 - R->y0) / R->cell);
    b1 = (int32_t)floor((by1 - R->y0) / R->cell);
    for (j = b0; j <= b1; ++j)
        for (i = a0; i <= a1; ++i) {
            double x = R->x0 + i * R->cell, y = R->y0 + j * R->cell, l1, l2, *v;
            if (i < 0 || j < 0 || i >= R->nx || j >= R->ny) continue;
            l1 = ((x - uv[0]) * (uv[5] - uv[1]) - (uv[4] - uv[0]) * (y - uv[1])) / det;
            l2 = ((uv[2] - uv[0]) * (y - uv[1]) - (x - uv[0]) * (uv[3] - uv[1])) / det;
            if (l1 < -1e-12 || l2 < -1e-12 || l1 + l2 > 1.0 + 1e-12) continue;
            v = R->val + j * R->nx + i;
            *v = 1e3 * wr_mesher_eval_sizing(res, p, x, y);
            if (*v < R->vmin) R->vmin = *v;
            if (*v > R->vmax) R->vmax = *v;
        }
}

/* The extent, the grid (MESHOUT_GRID cells along the longer side) and its samples. */
static wr_status raster_build(const wr_mesher_result *res, sizing_raster *R, wr_diag *diag) {
    const wr_mesh *m = &res->mesh;
    int32_t f, k, i;
    R->x0 = R->y0 = R->vmin = HUGE_VAL;
    R->x1 = R->y1 = R->vmax = -HUGE_VAL;
    for (f = 0; f < m->nf; ++f) {
        double uv[6];
        wr_mesh_face_rest(m, f, uv);
        for (k = 0; k < 3; ++k) {
            R->x0 = fmin(R->x0, uv[2 * k]);
            R->x1 = fmax(R->x1, uv[2 * k]);
            R->y0 = fmin(R->y0, uv[2 * k + 1]);
            R->y1 = fmax(R->y1, uv[2 * k + 1]);
        }
    }
    R->cell = fmax(R->x1 - R->x0, R->y1 - R->y0) / MESHOUT_GRID;
    if (!(R->cell > 0.0)) return wr_fail(diag, WR_ERR_GEOMETRY, -1, "degenerate mesh extent");
    R->nx = (int32_t)ceil((R->x1 - R->x0) / R->cell) + 1;
    R->ny = (int32_t)ceil((R->y1 - R->y0) / R->cell) + 1;
    R->val = (double *)malloc((size_t)R->nx * (size_t)R->ny * sizeof(double));
    if (!R->val) return wr_fail(diag, WR_ERR_NOMEM, -1, "out of memory");
    for (i = 0; i < R->nx * R->ny; ++i) R->val[i] = NAN;
    for (f = 0; f < m->nf; ++f) raster_face(res, f, R);
    if (!(R->vmax >= R->vmin)) R->vmin = R->vmax = 1.0;
    if (R->vmax - R->vmin < 1e-9) R->vmax = R->vmin + 1e-3;
    return WR_OK;
}

/* Closes fp and turns a failed close into an error naming path. */
static wr_status close_checked(FILE *fp, const char *path, wr_diag *diag) {
    return fclose(fp) != 0 ? wr_fail(diag, WR_ERR_IO, -1, "writing %s failed", path) : WR_OK;
}

/* gnuplot's image data: x, y, sizing [mm] per grid point, a blank line per row. */
static wr_status write_grid(const char *path, const sizing_raster *R, wr_diag *diag) {
    FILE *fp = fopen(path, "w");
    int32_t i, j;
    if (!fp) return wr_fail(diag, WR_ERR_IO, -1, "cannot write %s", path);
    for (j = 0; j < R->ny; ++j) {
        for (i = 0; i < R->nx; ++i) {
            const double x = 1e3 * (R->x0 + i * R->cell), y = 1e3 * (R->y0 + j * R->cell), v = R->val[j * R->nx + i];
            if (isnan(v))
                fprintf(fp, "%.6g %.6g NaN\n", x, y);
            else
                fprintf(fp, "%.6g %.6g %.6g\n", x, y, v);
        }
        fputc('\n', fp);
    }
    return close_checked(fp, path, diag);
}

/* Every mesh edge as a rest-space segment [mm] (or one NaN point when edges are not drawn). */
static wr_status write_edges(const char *path, const wr_mesh *m, int draw_edges, wr_diag *diag) {
    FILE *fp = fopen(path, "w");
    int32_t e, k;
    if (!fp) return wr_fail(diag, WR_ERR_IO, -1, "cannot write %s", path);
    if (!draw_edges) fprintf(fp, "NaN NaN\n");
    for (e = 0; draw_edges && e < m->ne; ++e) {
        int32_t ff = m->edge_faces[2 * e] >= 0 ? m->edge_faces[2 * e] : m->edge_faces[2 * e + 1], ka = 0, kb = 0;
        double uv[6];
        wr_mesh_face_rest(m, ff, uv);
        for (k = 0; k < 3; ++k) {
            if (m->faces[3 * ff + k] == m->edges[2 * e]) ka = k;
            if (m->faces[3 * ff + k] == m->edges[2 * e + 1]) kb = k;
        }
        fprintf(fp, "%.6g %.6g\n%.6g %.6g\n\n", 1e3 * uv[2 * ka], 1e3 * uv[2 * ka + 1], 1e3 * uv[2 * kb],
                1e3 * uv[2 * kb + 1]);
    }
    return close_checked(fp, path, diag);
}

/* The gnuplot script: a picture sized to the extent's aspect (1000 px wide, at most 1600 px high),
 * the sizing as an image with its colour bar, the edges over it. */
static wr_status write_script(const char *path, const sizing_raster *R, const char *tpng, const char *gpath,
                              const char *epath, const char *title, int32_t nv, wr_diag *diag) {
    const double w = 1e3 * (R->x1 - R->x0), h = 1e3 * (R->y1 - R->y0), c = 1e3 * R->cell;
    int px = 1000, py = (int)(1000.0 * h / w) + 80;
    FILE *fp = fopen(path, "w");
    if (!fp) return wr_fail(diag, WR_ERR_IO, -1, "cannot write %s", path);
    if (py > 1600) {
        py = 1600;
        px = (int)(1520.0 * w / h) + 120;
    }
    if (py < 300) py = 300;
    fprintf(fp, "set terminal pngcairo size %d,%d font ',10'\nset output ", px, py);
    gp_quote(fp, tpng);
    fprintf(fp, "\nset title ");
    gp_quote(fp, title ? title : "sizing map");
    fprintf(fp, "\nset size ratio -1\nset xlabel 'x [mm]'\nset ylabel 'y [mm]'\nset cblabel 'sizing [mm]'\n"
                "set palette rgbformulae 33,13,10\nset cbrange [%g:%g]\nset xrange [%g:%g]\nset yrange [%g:%g]\n"
                "set key off\n",
            R->vmin, R->vmax, 1e3 * R->x0 - c, 1e3 * R->x1 + c, 1e3 * R->y0 - c, 1e3 * R->y1 + c);
    fprintf(fp, "plot ");
    gp_quote(fp, gpath);
    fprintf(fp, " using 1:2:3 with image, ");
    gp_quote(fp, epath);
    fprintf(fp, " using 1:2 with lines lc rgb '#202020' lw %s\n", nv > 20000 ? "0.2" : "0.5");
    return close_checked(fp, path, diag);
}

/* Runs the script and renames its picture onto png_path (atomic: a failed run leaves no file). */
static wr_status run_gnuplot(const char *spath, const char *tpng, const char *png_path, wr_diag *diag) {
    char cmd[3 * WR_PATH_MAX];
    int rc;
    snprintf(cmd, sizeof cmd, "gnuplot '%s' >/dev/null 2>&1", spath);
    rc = system(cmd);
    if (rc == -1 || !WIFEXITED(rc) || WEXITSTATUS(rc) != 0) {
        remove(tpng);
        return wr_fail(diag, WR_ERR_BACKEND, -1, "gnuplot failed rendering %s", png_path);
    }
    if (rename(tpng, png_path) != 0) {
        remove(tpng);
        return wr_fail(diag, WR_ERR_IO, -1, "cannot rename the picture onto %s", png_path);
    }
    return WR_OK;
}

wr_status wr_meshout_render_png(const wr_mesher_result *res, const char *png_path, const char *title,
                                int draw_edges, wr_diag *diag) {
    const wr_mesh *m = &res->mesh;
    char tmpl[] = "/tmp/wrinkle-mesh-plotXXXXXX", gpath[WR_PATH_MAX], epath[WR_PATH_MAX], spath[WR_PATH_MAX],
         tpng[WR_PATH_MAX + 16];
    sizing_raster R;
    wr_status st;
    if (!have_gnuplot()) return wr_fail(diag, WR_ERR_UNSUPPORTED, -1, "gnuplot not found on PATH: picture skipped");
    if (m->nf < 1) return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "empty mesh");
    memset(&R, 0, sizeof R);
    if ((st = raster_build(res, &R, diag)) != WR_OK) {
        free(R.val);
        return st;
    }
    if (!mkdtemp(tmpl)) {
        free(R.val);
        return wr_fail(diag, WR_ERR_IO, -1, "cannot create a temporary directory for the plot data");
    }
    snprintf(gpath, sizeof gpath, "%s/grid.dat", tmpl);
    snprintf(epath, sizeof epath, "%s/edges.dat", tmpl);
    snprintf(spath, sizeof spath, "%s/plot.gp", tmpl);
    snprintf(tpng, sizeof tpng, "%s.wrtmp.png", png_path);
    if ((st = write_grid(gpath, &R, diag)) == WR_OK && (st = write_edges(epath, m, draw_edges, diag)) == WR_OK &&
        (st = write_script(spath, &R, tpng, gpath, epath, title, m->nv, diag)) == WR_OK)
        st = run_gnuplot(spath, tpng, png_path, diag);
    free(R.val);
    remove_tree(tmpl);
    return st;
}

static wr_status write_seams_csv(const wr_mesher_result *res, const char *path, wr_diag *diag) {
    wr_afile af;
    wr_status st = wr_afile_open(&af, path, diag);
    int32_t i;
    if (st != WR_OK) return st;
    fprintf(af.fp, "seam,pair,vertex_a,vertex_b,ax_mm,ay_mm,bx_mm,by_mm\n");
    for (i = 0; i < res->n_seam_pairs; ++i) {
        int32_t a = res->seam_pairs[2 * i], b = res->seam_pairs[2 * i + 1];
        double ax = res->mesh.pos[3 * a], ay = res->mesh.pos[3 * a + 1], bx = res->mesh.pos[3 * b],
               by = res->mesh.pos[3 * b + 1];
        if (res->mesh.rest) {
            ax = res->mesh.rest[2 * a];
            ay = res->mesh.rest[2 * a + 1];
            bx = res->mesh.rest[2 * b];
            by = res->mesh.rest[2 * b + 1];
        }
        fprintf(af.fp, "%d,%d,%d,%d,%.9g,%.9g,%.9g,%.9g\n", (int)res->seam_pair_seam[i], (int)i, (int)a, (int)b,
                1e3 * ax, 1e3 * ay, 1e3 * bx, 1e3 * by);
    }
    return wr_afile_commit(&af, diag);
}

static wr_status write_summary(const wr_mesher_result *res, const wr_pattern_file *pf, const char *path,
                               int png_written, wr_diag *diag) {
    const wr_mesher_report *r = &res->report;
    cJSON *root = cJSON_CreateObject(), *q, *h, *t, *panels, *files;
    wr_status st;
    int32_t p;
    if (!root) return wr_fail(diag, WR_ERR_NOMEM, -1, "out of memory");
    cJSON_AddStringToObject(root, "pattern", pf && pf->name[0] ? pf->name : "");
    cJSON_AddNumberToObject(root, "vertices", r->n_vertices);
    cJSON_AddNumberToObject(root, "triangles", r->n_triangles);
    cJSON_AddNumberToObject(root, "seam_pairs", r->n_seam_pairs);
    cJSON_AddNumberToObject(root, "constraint_segments", r->n_constraint_segments);
    panels = cJSON_AddArrayToObject(root, "panels");
    for (p = 0; p < res->n_panels; ++p) {
        const wr_mesher_panel_info *pi = &res->panels[p];
        cJSON *o = cJSON_CreateObject();
        int32_t nv = pi->v_end - pi->v_begin;
        cJSON_AddStringToObject(o, "name", pf && pf->panel_names ? pf->panel_names[p] : "");
        cJSON_AddNumberToObject(o, "base_resolution_warp_mm", 1e3 * pi->r_warp);
        cJSON_AddNumberToObject(o, "base_resolution_weft_mm", 1e3 * pi->r_weft);
        cJSON_AddNumberToObject(o, "vertices_before_sewing", nv);
        cJSON_AddNumberToObject(o, "triangles", pi->f_end - pi->f_begin);
        cJSON_AddNumberToObject(o, "area_mm2", 1e6 * pi->area);
        cJSON_AddNumberToObject(o, "sizing_sources", pi->n_sources);
        cJSON_AddItemToArray(panels, o);
    }
    q = cJSON_AddObjectToObject(root, "quality");
    cJSON_AddNumberToObject(q, "min_angle_deg", r->min_angle_deg);
    cJSON_AddNumberToObject(q, "max_angle_deg", r->max_angle_deg);
    cJSON_AddNumberToObject(q, "mean_min_angle_deg", r->mean_min_angle_deg);
    cJSON_AddNumberToObject(q, "min_angle_metric_deg", r->min_angle_metric_deg);
    cJSON_AddNumberToObject(q, "mean_min_angle_metric_deg", r->mean_min_angle_metric_deg);
    cJSON_AddNumberToObject(q, "edge_ratio_mean", r->ratio_mean);
    if (isfinite(r->ratio_interior_mean))
        cJSON_AddNumberToObject(q, "edge_ratio_interior_mean", r->ratio_interior_mean);
    else
        cJSON_AddNullToObject(q, "edge_ratio_interior_mean");
    cJSON_AddNumberToObject(q, "edge_ratio_min", r->ratio_min);
    cJSON_AddNumberToObject(q, "edge_ratio_max", r->ratio_max);
    cJSON_AddNumberToObject(q, "inverted_faces", r->n_inverted);
    cJSON_AddNumberToObject(q, "zero_area_faces", r->n_zero_area);
    h = cJSON_AddObjectToObject(q, "edge_ratio_histogram");
    cJSON_AddNumberToObject(h, "lo", 0.0);
    cJSON_AddNumberToObject(h, "hi", 2.0);
    cJSON_AddItemToObject(h, "counts", cJSON_CreateIntArray(r->ratio_hist, WR_MESHER_HIST_BINS));
    t = cJSON_AddObjectToObject(root, "timings_s");
    cJSON_AddNumberToObject(t, "sizing", r->t_sizing);
    cJSON_AddNumberToObject(t, "discretise", r->t_discretise);
    cJSON_AddNumberToObject(t, "poisson", r->t_poisson);
    cJSON_AddNumberToObject(t, "cdt", r->t_cdt);
    cJSON_AddNumberToObject(t, "assemble", r->t_assemble);
    cJSON_AddNumberToObject(t, "total", r->t_total);
    files = cJSON_AddArrayToObject(root, "files");
    cJSON_AddItemToArray(files, cJSON_CreateString("mesh.obj"));
    cJSON_AddItemToArray(files, cJSON_CreateString("mesh.ply"));
    cJSON_AddItemToArray(files, cJSON_CreateString("mesh.vtk"));
    if (res->n_seam_pairs) cJSON_AddItemToArray(files, cJSON_CreateString("seams.csv"));
    if (png_written) cJSON_AddItemToArray(files, cJSON_CreateString("sizing.png"));
    cJSON_AddItemToArray(files, cJSON_CreateString("summary.json"));
    st = wr_json_write(root, path, diag);
    cJSON_Delete(root);
    return st;
}

wr_status wr_meshout_write_dir(const wr_mesher_result *res, const wr_pattern_file *pf, const char *dir, int want_png,
                               int *png_written, wr_diag *diag) {
    static const char *const names[] = {"mesh.obj", "mesh.ply", "mesh.vtk", "seams.csv", "sizing.png", "summary.json"};
    char stage[WR_PATH_MAX], p[WR_PATH_MAX + 64], q[WR_PATH_MAX + 64];
    const char *pn[4];
    const double *pv[4];
    double *panel_id = NULL;
    wr_status st;
    int png = 0, k;
    struct stat sb;
    wr_diag d2;
    int32_t f, c;
    if (png_written) *png_written = 0;
    if (!dir || !*dir) return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "empty output directory");
    if (strlen(dir) > WR_PATH_MAX - 64) return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "output directory path too long");
    if (stat(dir, &sb) != 0) {
        if (mkdir(dir, 0777) != 0)
            return wr_fail(diag, WR_ERR_IO, -1, "cannot create directory '%s' (%s)", dir, strerror(errno));
    } else if (!S_ISDIR(sb.st_mode)) {
        return wr_fail(diag, WR_ERR_IO, -1, "'%s' exists and is not a directory", dir);
    }
    snprintf(stage, sizeof stage, "%s/.wrinkle-mesh-XXXXXX", dir);
    if (!mkdtemp(stage)) return wr_fail(diag, WR_ERR_IO, -1, "cannot create a staging directory in '%s'", dir);
    /* mesh.obj: vt = pattern coordinates, vn, one group per panel named after it */
    snprintf(p, sizeof p, "%s/mesh", stage);
    if ((st = wr_meshout_write_viewer(&res->mesh, NULL, NULL, 0, pf ? (const char *const *)pf->panel_names : NULL,
                                      pf && pf->panel_names ? res->n_panels : 0, p, WR_MESHOUT_OBJ, diag)) != WR_OK)
        goto fail;
    /* mesh.ply: per-vertex sizing (and the panel of the vertex) */
    panel_id = (double *)malloc((size_t)(res->mesh.nv > 0 ? res->mesh.nv : 1) * sizeof(double));
    if (!panel_id) {
        st = wr_fail(diag, WR_ERR_NOMEM, -1, "out of memory");
        goto fail;
    }
    for (k = 0; k < res->mesh.nv; ++k) panel_id[k] = -1.0;
    for (f = 0; f < res->mesh.nf; ++f)
        for (c = 0; c < 3; ++c)
            if (panel_id[res->mesh.faces[3 * f + c]] < 0)
                panel_id[res->mesh.faces[3 * f + c]] = res->mesh.face_panel ? res->mesh.face_panel[f] : 0;
    pn[0] = "sizing";
    pv[0] = res->sizing;
    pn[1] = "sizing_warp";
    pv[1] = res->sizing_warp;
    pn[2] = "sizing_weft";
    pv[2] = res->sizing_weft;
    pn[3] = "panel";
    pv[3] = panel_id;
    snprintf(p, sizeof p, "%s/mesh.ply", stage);
    st = wr_mesh_write_ply(&res->mesh, p, 4, pn, pv, diag);
    if (st == WR_OK) { /* the same fields for ParaView, with normals and texture coordinates */
        wr_meshout_field fl[4];
        for (k = 0; k < 4; ++k) {
            fl[k].name = pn[k];
            fl[k].values = pv[k];
        }
        snprintf(p, sizeof p, "%s/mesh", stage);
        st = wr_meshout_write_viewer(&res->mesh, NULL, fl, 4, NULL, 0, p, WR_MESHOUT_VTK, diag);
    }
    free(panel_id);
    if (st != WR_OK) goto fail;
    if (res->n_seam_pairs > 0) {
        snprintf(p, sizeof p, "%s/seams.csv", stage);
        if ((st = write_seams_csv(res, p, diag)) != WR_OK) goto fail;
    }
    if (want_png) {
        char title[256];
        snprintf(title, sizeof title, "%s: sizing map and mesh (%d vertices)", pf && pf->name[0] ? pf->name : "pattern",
                 (int)res->mesh.nv);
        snprintf(p, sizeof p, "%s/sizing.png", stage);
        st = wr_meshout_render_png(res, p, title, 1, &d2);
        if (st == WR_OK)
            png = 1;
        else if (st != WR_ERR_UNSUPPORTED) {
            if (diag) *diag = d2;
            goto fail;
        }
    }
    snprintf(p, sizeof p, "%s/summary.json", stage);
    if ((st = write_summary(res, pf, p, png, diag)) != WR_OK) goto fail;
    /* commit: rename every finished file into place, then drop the stale picture/seams of a previous run */
    for (k = 0; k < (int)(sizeof names / sizeof names[0]); ++k) {
        snprintf(p, sizeof p, "%s/%s", stage, names[k]);
        snprintf(q, sizeof q, "%s/%s", dir, names[k]);
        if (stat(p, &sb) == 0 && rename(p, q) != 0) {
            st = wr_fail(diag, WR_ERR_IO, -1, "cannot move %s into '%s' (%s)", names[k], dir, strerror(errno));
            goto fail;
        }
    }
    /* files of an earlier run that would not describe this mesh */
    if (res->n_seam_pairs == 0) {
        snprintf(q, sizeof q, "%s/seams.csv", dir);
        remove(q);
    }
    if (!png) {
        snprintf(q, sizeof q, "%s/sizing.png", dir);
        remove(q);
    }
    remove_tree(stage);
    if (png_written) *png_written = png;
    return WR_OK;
fail:
    remove_tree(stage);
    return st;
}

/* ---- viewer-ready files ------------------------------------------------------------------------ */

static void viewer_normals(const wr_mesh *m, const double *pos, double *vn) {
    int32_t f, v;
    int c, k;
    memset(vn, 0, sizeof(double) * 3 * (size_t)m->nv);
    for (f = 0; f < m->nf; ++f) { /* area-weighted: the unnormalised cross product per face */
        const int32_t *t = m->faces + 3 * f;
        double u[3], w[3];
        for (k = 0; k < 3; ++k) {
            u[k] = pos[3 * t[1] + k] - pos[3 * t[0] + k];
            w[k] = pos[3 * t[2] + k] - pos[3 * t[0] + k];
        }
        for (c = 0; c < 3; ++c) {
            vn[3 * t[c]] += u[1] * w[2] - u[2] * w[1];
            vn[3 * t[c] + 1] += u[2] * w[0] - u[0] * w[2];
            vn[3 * t[c] + 2] += u[0] * w[1] - u[1] * w[0];
        }
    }
    for (v = 0; v < m->nv; ++v) {
        double n = sqrt(vn[3 * v] * vn[3 * v] + vn[3 * v + 1] * vn[3 * v + 1] + vn[3 * v + 2] * vn[3 * v + 2]);
        if (n > 0.0)
            for (k = 0; k < 3; ++k) vn[3 * v + k] /= n;
        else
            vn[3 * v + 2] = 1.0; /* isolated vertex */
    }
}

/* Texture coordinate of vertex v: rest, else (x, y) of pos. */
static void viewer_uv(const wr_mesh *m, const double *pos, int32_t v, double uv[2]) {
    if (m->rest) {
        uv[0] = m->rest[2 * v];
        uv[1] = m->rest[2 * v + 1];
    } else {
        uv[0] = pos[3 * v];
        uv[1] = pos[3 * v + 1];
    }
}

static void obj_group_name(FILE *fp, const char *const *names, int32_t n_names, int32_t g) {
    const char *s = names && g >= 0 && g < n_names ? names[g] : NULL;
    if (!s || !*s) {
        fprintf(fp, "g panel%d\n", (int)g);
        return;
    }
    fputs("g ", fp);
    for (; *s; ++s) fputc(*s == ' ' || *s == '\t' || *s == '\n' || *s == '\r' ? '_' : *s, fp);
    fputc('\n', fp);
}

static wr_status viewer_obj(const wr_mesh *m, const double *pos, const double *vn, const char *const *names,
                            int32_t n_names, const char *path, wr_diag *diag) {
    wr_afile f;
    wr_status st = wr_afile_open(&f, path, diag);
    int32_t v, t, cur = -1, k;
    int corner = m->corner_rest != NULL;
    double uv[2];
    if (st != WR_OK) return st;
    fprintf(f.fp, "# wrinkle: %d vertices, %d faces; vt = rest (pattern) coordinates [m]%s; vn = vertex normals\n",
            (int)m->nv, (int)m->nf, corner ? " per face corner" : "");
    for (v = 0; v < m->nv; ++v) fprintf(f.fp, "v %.17g %.17g %.17g\n", pos[3 * v], pos[3 * v + 1], pos[3 * v + 2]);
    if (corner)
        for (k = 0; k < 3 * m->nf; ++k) fprintf(f.fp, "vt %.17g %.17g\n", m->corner_rest[2 * k], m->corner_rest[2 * k + 1]);
    else
        for (v = 0; v < m->nv; ++v) {
            viewer_uv(m, pos, v, uv);
            fprintf(f.fp, "vt %.17g %.17g\n", uv[0], uv[1]);
        }
    for (v = 0; v < m->nv; ++v) fprintf(f.fp, "vn %.6f %.6f %.6f\n", vn[3 * v], vn[3 * v + 1], vn[3 * v + 2]);
    for (t = 0; t < m->nf; ++t) {
        const int32_t *c = m->faces + 3 * t;
        int32_t g = m->face_panel ? m->face_panel[t] : 0;
        if (t == 0 || g != cur) {
            cur = g;
            obj_group_name(f.fp, names, n_names, g);
        }
        for (k = 0; k < 3; ++k) fprintf(f.fp, "%s%d/%d/%d", k ? " " : "f ", (int)c[k] + 1, corner ? (int)(3 * t + k + 1) : (int)c[k] + 1, (int)c[k] + 1);
        fputc('\n', f.fp);
    }
    return wr_afile_commit(&f, diag);
}

static wr_status viewer_ply(const wr_mesh *m, const double *pos, const double *vn, const wr_meshout_field *fl,
                            int32_t nfl, const char *path, wr_diag *diag) {
    wr_afile f;
    wr_status st = wr_afile_open(&f, path, diag);
    int32_t v, t, k;
    double uv[2];
    if (st != WR_OK) return st;
    fprintf(f.fp, "ply\nformat ascii 1.0\ncomment wrinkle: positions [m], s t = rest coordinates [m]\n"
                  "element vertex %d\n", (int)m->nv);
    fputs("property float x\nproperty float y\nproperty float z\nproperty float nx\nproperty float ny\n"
          "property float nz\nproperty float s\nproperty float t\n", f.fp);
    for (k = 0; k < nfl; ++k) fprintf(f.fp, "property float %s\n", fl[k].name);
    fprintf(f.fp, "element face %d\nproperty list uchar int vertex_indices\nend_header\n", (int)m->nf);
    for (v = 0; v < m->nv; ++v) {
        viewer_uv(m, pos, v, uv);
        fprintf(f.fp, "%.9g %.9g %.9g %.6f %.6f %.6f %.9g %.9g", pos[3 * v], pos[3 * v + 1], pos[3 * v + 2], vn[3 * v],
                vn[3 * v + 1], vn[3 * v + 2], uv[0], uv[1]);
        for (k = 0; k < nfl; ++k) fprintf(f.fp, " %.9g", isfinite(fl[k].values[v]) ? fl[k].values[v] : 0.0);
        fputc('\n', f.fp);
    }
    for (t = 0; t < m->nf; ++t) fprintf(f.fp, "3 %d %d %d\n", (int)m->faces[3 * t], (int)m->faces[3 * t + 1], (int)m->faces[3 * t + 2]);
    return wr_afile_commit(&f, diag);
}

static wr_status viewer_vtk(const wr_mesh *m, const double *pos, const double *vn, const wr_meshout_field *fl,
                            int32_t nfl, const char *path, wr_diag *diag) {
    wr_afile f;
    wr_status st = wr_afile_open(&f, path, diag);
    int32_t v, t, k;
    double uv[2];
    if (st != WR_OK) return st;
    fprintf(f.fp, "# vtk DataFile Version 3.0\nwrinkle mesh [m]\nASCII\nDATASET POLYDATA\nPOINTS %d double\n", (int)m->nv);
    for (v = 0; v < m->nv; ++v) fprintf(f.fp, "%.9g %.9g %.9g\n", pos[3 * v], pos[3 * v + 1], pos[3 * v + 2]);
    fprintf(f.fp, "POLYGONS %d %lld\n", (int)m->nf, 4LL * m->nf);
    for (t = 0; t < m->nf; ++t) fprintf(f.fp, "3 %d %d %d\n", (int)m->faces[3 * t], (int)m->faces[3 * t + 1], (int)m->faces[3 * t + 2]);
    fprintf(f.fp, "POINT_DATA %d\nNORMALS normals float\n", (int)m->nv);
    for (v = 0; v < m->nv; ++v) fprintf(f.fp, "%.6f %.6f %.6f\n", vn[3 * v], vn[3 * v + 1], vn[3 * v + 2]);
    fputs("TEXTURE_COORDINATES rest 2 float\n", f.fp);
    for (v = 0; v < m->nv; ++v) {
        viewer_uv(m, pos, v, uv);
        fprintf(f.fp, "%.9g %.9g\n", uv[0], uv[1]);
    }
    for (k = 0; k < nfl; ++k) {
        fprintf(f.fp, "SCALARS %s double 1\nLOOKUP_TABLE default\n", fl[k].name);
        for (v = 0; v < m->nv; ++v) {
            if (isfinite(fl[k].values[v]))
                fprintf(f.fp, "%.9g\n", fl[k].values[v]);
            else
                fputs("nan\n", f.fp);
        }
    }
    return wr_afile_commit(&f, diag);
}

wr_status wr_meshout_write_viewer(const wr_mesh *m, const double *pos, const wr_meshout_field *fields, int32_t n_fields,
                                  const char *const *group_names, int32_t n_groups, const char *stem, unsigned formats,
                                  wr_diag *diag) {
    char path[WR_PATH_MAX];
    double *vn;
    wr_status st = WR_OK;
    int32_t k;
    const char *c;
    if (!m || !m->faces || m->nv < 1) return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "viewer output: empty mesh");
    if (!stem || strlen(stem) > WR_PATH_MAX - 8) return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "viewer output: bad path");
    for (k = 0; k < n_fields; ++k) {
        if (!fields[k].name || !*fields[k].name || !fields[k].values)
            return wr_fail(diag, WR_ERR_INVALID_ARG, k, "viewer output: field %d has no name or values", (int)k);
        for (c = fields[k].name; *c; ++c)
            if (!((*c >= 'a' && *c <= 'z') || (*c >= 'A' && *c <= 'Z') || (*c >= '0' && *c <= '9') || *c == '_'))
                return wr_fail(diag, WR_ERR_INVALID_ARG, k, "viewer output: field name '%s' (letters, digits, _)",
                               fields[k].name);
    }
    if (!pos) pos = m->pos;
    vn = (double *)malloc(sizeof(double) * 3 * (size_t)m->nv);
    if (!vn) return wr_fail(diag, WR_ERR_NOMEM, -1, "out of memory");
    viewer_normals(m, pos, vn);
    if (formats & WR_MESHOUT_OBJ) {
        snprintf(path, sizeof path, "%s.obj", stem);
        st = viewer_obj(m, pos, vn, group_names, n_groups, path, diag);
    }
    if (st == WR_OK && (formats & WR_MESHOUT_PLY)) {
        snprintf(path, sizeof path, "%s.ply", stem);
        st = viewer_ply(m, pos, vn, fields, n_fields, path, diag);
    }
    if (st == WR_OK && (formats & WR_MESHOUT_VTK)) {
        snprintf(path, sizeof path, "%s.vtk", stem);
        st = viewer_vtk(m, pos, vn, fields, n_fields, path, diag);
    }
    free(vn);
    return st;
}

wr_status wr_meshout_png(const char *path, const wr_render_panel *panels, int32_t n, int32_t columns, int32_t panel_w,
                         int32_t panel_h, const wr_view_desc *view, wr_diag *diag) {
    wr_image img;
    wr_status st = wr_render_panels(&img, panels, n, columns, view, panel_w, panel_h, diag);
    if (st != WR_OK) return st;
    st = wr_image_write_png(&img, path, diag);
    wr_image_free(&img);
    return st;
}

/* Offset of the wrinkled surface from the smooth subdivided base (a = 0, same phase and levels)
 * along the smooth surface's vertex normal: the wrinkle "height" a newcomer reads in a picture. */
static wr_status tfw_height(const wr_mesh *base, const double *base_pos, const wr_wf_material *mat,
                            const wr_tfw_desc *td, const wr_tfw_result *r, double *height, wr_diag *diag) {
    wr_wf wf;
    wr_mesh sm;
    double *zero = (double *)calloc((size_t)base->nv, sizeof(double)), *vn = NULL;
    wr_status st;
    int32_t v;
    int k;
    memset(&sm, 0, sizeof sm);
    if (!zero) return wr_fail(diag, WR_ERR_NOMEM, -1, "out of memory");
    st = wr_wf_create(&wf, base, base_pos, mat, diag);
    if (st == WR_OK) {
        wr_wf_set_wrinkle_free(&wf, r->wfree);
        st = wr_wf_upsample(&wf, zero, r->phi, &td->upsample, &sm, NULL, diag);
        wr_wf_free(&wf);
    }
    if (st == WR_OK && sm.nv != r->wrinkled.nv)
        st = wr_fail(diag, WR_ERR_TOPOLOGY, -1, "smooth and wrinkled meshes differ (%d vs %d vertices)", (int)sm.nv,
                     (int)r->wrinkled.nv);
    if (st == WR_OK && !(vn = (double *)malloc(sizeof(double) * 3 * (size_t)sm.nv)))
        st = wr_fail(diag, WR_ERR_NOMEM, -1, "out of memory");
    if (st == WR_OK) {
        viewer_normals(&sm, sm.pos, vn);
        for (v = 0; v < sm.nv; ++v) {
            height[v] = 0.0;
            for (k = 0; k < 3; ++k) height[v] += (r->wrinkled.pos[3 * v + k] - sm.pos[3 * v + k]) * vn[3 * v + k];
        }
    }
    free(vn);
    free(zero);
    wr_mesh_free(&sm);
    return st;
}

static wr_status tfw_picture(const char *path, const wr_mesh *base, const double *base_pos, const wr_tfw_result *r,
                             const double *height, wr_diag *diag) {
    wr_render_panel pn[2];
    wr_view_desc vd;
    wr_view v;
    char t0[160], t1[160];
    double *hmm = (double *)malloc(sizeof(double) * (size_t)r->wrinkled.nv), lo[2] = {HUGE_VAL, HUGE_VAL},
           hi[2] = {-HUGE_VAL, -HUGE_VAL}, q[3], amax = 0.0, aspect;
    int32_t i, columns, pw = 1000, ph;
    wr_status st;
    if (!hmm) return wr_fail(diag, WR_ERR_NOMEM, -1, "out of memory");
    for (i = 0; i < r->wrinkled.nv; ++i) hmm[i] = 1e3 * height[i];
    for (i = 0; i < base->nv; ++i) amax = fmax(amax, r->a[i]);
    memset(&vd, 0, sizeof vd);
    vd.has_angles = 1;
    vd.azimuth_deg = -70.0; /* a three-quarter view from the front left, 40° above the cloth */
    vd.elevation_deg = 40.0;
    /* stack the two views for a long piece, put them side by side otherwise */
    wr_view_fit(&v, base_pos, base->nv, &vd, 0, 0, 1000, 1000);
    for (i = 0; i < base->nv; ++i) {
        wr_view_project(&v, base_pos + 3 * i, q);
        lo[0] = fmin(lo[0], q[0]), hi[0] = fmax(hi[0], q[0]);
        lo[1] = fmin(lo[1], q[1]), hi[1] = fmax(hi[1], q[1]);
    }
    aspect = hi[0] > lo[0] ? (hi[1] - lo[1]) / (hi[0] - lo[0]) : 1.0;
    columns = aspect < 0.75 ? 1 : 2;
    if (columns == 2) pw = 700;
    ph = (int32_t)(pw * fmin(1.1, fmax(0.3, aspect * 1.12)));
    memset(pn, 0, sizeof pn);
    snprintf(t0, sizeof t0, "coarse base: %d vertices (TFT)", (int)base->nv);
    /* a 700 px cell holds ~38 title characters: the short form side by side, the long one stacked */
    if (columns == 2)
        snprintf(t1, sizeof t1, "TFW: %d vertices, max a %.2f mm", (int)r->wrinkled.nv, 1e3 * amax);
    else
        snprintf(t1, sizeof t1, "TFW wrinkles: %d vertices, max amplitude %.2f mm", (int)r->wrinkled.nv, 1e3 * amax);
    pn[0].pos = base_pos;
    pn[0].nv = base->nv;
    pn[0].faces = base->faces;
    pn[0].nf = base->nf;
    pn[0].title = t0;
    pn[0].style.wireframe = 1;
    pn[1].pos = r->wrinkled.pos;
    pn[1].nv = r->wrinkled.nv;
    pn[1].faces = r->wrinkled.faces;
    pn[1].nf = r->wrinkled.nf;
    pn[1].title = t1;
    pn[1].style.scalar = hmm;
    pn[1].style.colormap = WR_COLORMAP_DIVERGING;
    pn[1].colorbar_label = "wrinkle height mm";
    st = wr_meshout_png(path, pn, 2, columns, pw, ph, &vd, diag);
    free(hmm);
    return st;
}

wr_status wr_meshout_tfw_png(const char *path, const wr_mesh *base, const double *base_pos, const wr_wf_material *mat,
                             const wr_tfw_desc *td, const wr_tfw_result *r, wr_diag *diag) {
    double *height;
    wr_status st;
    if (r->wrinkled.nv <= 0) return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "no wrinkled surface to draw");
    height = (double *)malloc(sizeof(double) * (size_t)r->wrinkled.nv);
    if (!height) return wr_fail(diag, WR_ERR_NOMEM, -1, "out of memory");
    st = tfw_height(base, base_pos, mat, td, r, height, diag);
    if (st == WR_OK) st = tfw_picture(path, base, base_pos, r, height, diag);
    free(height);
    return st;
}

/* The base's local resolution per vertex: the mean rest length of its edges [m] (rest = the pattern
 * coordinates when the mesh has them, else its rest 3D positions). On a wrinkle-mesh output this is
 * the sizing map as realised (mean edge / sizing ~ 1, validation/validate_meshing.c). */
static void tfw_base_sizing(const wr_mesh *m, double *sz, double *cnt) {
    int32_t e, v;
    int k;
    for (v = 0; v < m->nv; ++v) sz[v] = cnt[v] = 0.0;
    for (e = 0; e < m->ne; ++e) {
        int32_t a = m->edges[2 * e], b = m->edges[2 * e + 1];
        double l2 = 0.0;
        if (m->rest)
            for (k = 0; k < 2; ++k) l2 += (m->rest[2 * a + k] - m->rest[2 * b + k]) * (m->rest[2 * a + k] - m->rest[2 * b + k]);
        else
            for (k = 0; k < 3; ++k) l2 += (m->pos[3 * a + k] - m->pos[3 * b + k]) * (m->pos[3 * a + k] - m->pos[3 * b + k]);
        for (k = 0; k < 2; ++k) sz[m->edges[2 * e + k]] += sqrt(l2), cnt[m->edges[2 * e + k]] += 1.0;
    }
    for (v = 0; v < m->nv; ++v) sz[v] = cnt[v] > 0.0 ? sz[v] / cnt[v] : 0.0;
}

/* The base sizing on the wrinkled mesh: Loop-subdivided exactly as the amplitude is (wr_wf_upsample
 * with a = sizing and no wrinkle-free faces, so nothing is zeroed), a smooth positive field. */
static wr_status tfw_fine_sizing(const wr_mesh *base, const double *base_pos, const wr_wf_material *mat,
                                 const wr_tfw_desc *td, const wr_tfw_result *r, const double *bsz, double **fsz,
                                 wr_diag *diag) {
    wr_wf wf;
    wr_mesh sm;
    wr_status st;
    double *fa = NULL;
    *fsz = NULL;
    memset(&sm, 0, sizeof sm);
    if ((st = wr_wf_create(&wf, base, base_pos, mat, diag)) != WR_OK) return st;
    st = wr_wf_upsample(&wf, bsz, r->phi, &td->upsample, &sm, &fa, diag);
    wr_wf_free(&wf);
    if (st == WR_OK && sm.nv != r->wrinkled.nv)
        st = wr_fail(diag, WR_ERR_TOPOLOGY, -1, "sizing and wrinkled meshes differ (%d vs %d vertices)", (int)sm.nv,
                     (int)r->wrinkled.nv);
    wr_mesh_free(&sm);
    if (st == WR_OK) {
        *fsz = (double *)malloc(sizeof(double) * (size_t)r->wrinkled.nv);
        if (*fsz)
            memcpy(*fsz, fa, sizeof(double) * (size_t)r->wrinkled.nv);
        else
            st = wr_fail(diag, WR_ERR_NOMEM, -1, "out of memory");
    }
    wr_free(fa);
    return st;
}

/* Per base vertex (one block of 5 nv): a [m], omega_abs [rad] = mean |ω| of the incident edges,
 * W = 1 when every incident face is wrinkle-free, phase = the first incident face's corner value
 * wrapped to (-π, π], sizing [m] (tfw_base_sizing); vals[k] point into the block. */
static double *tfw_base_fields(const wr_mesh *base, const wr_tfw_result *r, const double *vals[5]) {
    int32_t nv = base->nv, v, e, f;
    int k;
    double *blk = (double *)calloc((size_t)nv * 6, sizeof(double)), *amp, *wmag, *wfl, *phase, *sz, *cnt;
    if (!blk) return NULL;
    amp = blk, wmag = blk + nv, wfl = blk + 2 * (size_t)nv, phase = blk + 3 * (size_t)nv, sz = blk + 4 * (size_t)nv;
    cnt = blk + 5 * (size_t)nv; /* scratch: -1 until a vertex's phase is set, then its edge count */
    for (v = 0; v < nv; ++v) amp[v] = r->a[v], wfl[v] = 1.0, cnt[v] = -1.0;
    for (f = 0; f < base->nf; ++f)
        for (k = 0; k < 3; ++k) {
            int32_t w = base->faces[3 * f + k];
            if (!r->wfree[f]) wfl[w] = 0.0;
            if (cnt[w] < 0.0) {
                phase[w] = atan2(sin(r->phi[3 * f + k]), cos(r->phi[3 * f + k]));
                cnt[w] = 0.0;
            }
        }
    tfw_base_sizing(base, sz, cnt); /* also leaves cnt = edges per vertex */
    for (e = 0; e < base->ne; ++e)
        for (k = 0; k < 2; ++k) wmag[base->edges[2 * e + k]] += fabs(r->omega[e]);
    for (v = 0; v < nv; ++v) wmag[v] = cnt[v] > 0 ? wmag[v] / cnt[v] : 0.0;
    vals[0] = amp, vals[1] = wmag, vals[2] = wfl, vals[3] = phase, vals[4] = sz;
    return blk;
}

/* DIR/wrinkled.obj/.ply/.vtk (a, height, phase, W, sizing per fine vertex) and DIR/wrinkles.png. */
static wr_status tfw_write_wrinkled(const char *dir, const wr_mesh *base, const double *base_pos,
                                    const wr_wf_material *mat, const wr_tfw_desc *td, const wr_tfw_result *r,
                                    const double *bsz, const char *const *gn, int32_t ng, int png, wr_diag *diag) {
    char stem[WR_PATH_MAX];
    wr_meshout_field fl[5];
    double *height = (double *)malloc(sizeof(double) * (size_t)r->wrinkled.nv), *wfine = NULL, *fsz = NULL;
    int32_t n = 0, v;
    wr_status st = height ? tfw_height(base, base_pos, mat, td, r, height, diag)
                          : wr_fail(diag, WR_ERR_NOMEM, -1, "out of memory");
    if (st == WR_OK) st = tfw_fine_sizing(base, base_pos, mat, td, r, bsz, &fsz, diag);
    if (st == WR_OK) {
        if (r->wrinkled_a) fl[n].name = "a", fl[n++].values = r->wrinkled_a;
        fl[n].name = "height", fl[n++].values = height;
        /* the fine phase and wrinkle-free flag (tfw.h, wr_wf_fine_fields): a viewer can draw the
         * wave crests (phase) and the W region on the wrinkled surface itself */
        if (r->wrinkled_phase) fl[n].name = "phase", fl[n++].values = r->wrinkled_phase;
        if (r->wrinkled_wfree) {
            wfine = (double *)malloc(sizeof(double) * (size_t)r->wrinkled.nv);
            if (!wfine) st = wr_fail(diag, WR_ERR_NOMEM, -1, "out of memory");
            for (v = 0; wfine && v < r->wrinkled.nv; ++v) wfine[v] = r->wrinkled_wfree[v] ? 1.0 : 0.0;
            fl[n].name = "W", fl[n++].values = wfine;
        }
        fl[n].name = "sizing", fl[n++].values = fsz;
    }
    if (st == WR_OK) {
        snprintf(stem, sizeof stem, "%s/wrinkled", dir);
        st = wr_meshout_write_viewer(&r->wrinkled, NULL, fl, n, gn, ng, stem,
                                     WR_MESHOUT_OBJ | WR_MESHOUT_PLY | WR_MESHOUT_VTK, diag);
    }
    if (st == WR_OK && png) {
        snprintf(stem, sizeof stem, "%s/wrinkles.png", dir);
        st = tfw_picture(stem, base, base_pos, r, height, diag);
    }
    free(height);
    free(wfine);
    free(fsz);
    return st;
}

wr_status wr_meshout_tfw(const char *dir, const wr_mesh *base, const double *base_pos, const wr_wf_material *mat,
                         const wr_tfw_desc *td, const wr_tfw_result *r, const wr_obj_groups *groups, int png,
                         wr_diag *diag) {
    const char *const *gn = groups ? (const char *const *)groups->names : NULL;
    int32_t ng = groups ? groups->n : 0;
    char stem[WR_PATH_MAX];
    const char *names[5] = {"a", "omega_abs", "W", "phase", "sizing"};
    const double *vals[5];
    wr_mesh bm = *base; /* shallow view with pos = the base surface */
    wr_meshout_field fl[5];
    wr_status st;
    double *blk;
    int k;
    if (strlen(dir) > WR_PATH_MAX - 32) return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "output path too long");
    bm.pos = (double *)base_pos;
    if (!(blk = tfw_base_fields(base, r, vals))) return wr_fail(diag, WR_ERR_NOMEM, -1, "out of memory");
    snprintf(stem, sizeof stem, "%s/base", dir);
    st = wr_meshout_write_viewer(&bm, NULL, NULL, 0, gn, ng, stem, WR_MESHOUT_OBJ, diag);
    if (st == WR_OK) {
        snprintf(stem, sizeof stem, "%s/fields.ply", dir);
        st = wr_mesh_write_ply(&bm, stem, 5, names, vals, diag);
    }
    if (st == WR_OK) {
        for (k = 0; k < 5; ++k) fl[k].name = names[k], fl[k].values = vals[k];
        snprintf(stem, sizeof stem, "%s/fields", dir);
        st = wr_meshout_write_viewer(&bm, NULL, fl, 5, NULL, 0, stem, WR_MESHOUT_VTK, diag);
    }
    if (st == WR_OK && r->wrinkled.nv > 0)
        st = tfw_write_wrinkled(dir, base, base_pos, mat, td, r, vals[4], gn, ng, png, diag);
    free(blk);
    return st;
}

double wr_meshout_max_strain(const wr_mesh *m, const double *pos) {
    double *L = (double *)malloc(sizeof(double) * (size_t)(m->ne > 0 ? m->ne : 1)), worst = 0.0;
    int32_t e;
    if (!L) return 0.0;
    wr_mesh_edge_lengths(m, 1, L);
    for (e = 0; e < m->ne; ++e) {
        const double *a = pos + 3 * m->edges[2 * e], *b = pos + 3 * m->edges[2 * e + 1];
        double l = sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) + (a[2] - b[2]) * (a[2] - b[2]));
        if (L[e] > 0.0) worst = fmax(worst, fabs(l / L[e] - 1.0));
    }
    free(L);
    return worst;
}
