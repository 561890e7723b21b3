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

wr_status wr_meshout_render_png(const wr_mesher_result *res, const char *png_path, const char *title,
                                int draw_edges, wr_diag *diag) {
    const wr_mesh *m = &res->mesh;
    char tmpl[] = "/tmp/wrinkle-mesh-plotXXXXXX", gpath[WR_PATH_MAX], epath[WR_PATH_MAX], spath[WR_PATH_MAX],
         tpng[WR_PATH_MAX + 16], cmd[3 * WR_PATH_MAX];
    double x0 = HUGE_VAL, y0 = HUGE_VAL, x1 = -HUGE_VAL, y1 = -HUGE_VAL, cell, *val = NULL, vmin = HUGE_VAL,
           vmax = -HUGE_VAL;
    int32_t f, k, nx, ny, i, j, e;
    FILE *fp;
    int rc;
    wr_status st = WR_OK;
    if (!have_gnuplot()) return wr_fail(diag, WR_ERR_UNSUPPORTED, -1, "gnuplot not found on PATH: picture skipped");
    if (m->nf < 1) return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "empty mesh");
    for (f = 0; f < m->nf; ++f) {
        double uv[6];
        wr_mesh_face_rest(m, f, uv);
        for (k = 0; k < 3; ++k) {
            x0 = fmin(x0, uv[2 * k]);
            x1 = fmax(x1, uv[2 * k]);
            y0 = fmin(y0, uv[2 * k + 1]);
            y1 = fmax(y1, uv[2 * k + 1]);
        }
    }
    cell = fmax(x1 - x0, y1 - y0) / MESHOUT_GRID;
    if (!(cell > 0.0)) return wr_fail(diag, WR_ERR_GEOMETRY, -1, "degenerate mesh extent");
    nx = (int32_t)ceil((x1 - x0) / cell) + 1;
    ny = (int32_t)ceil((y1 - y0) / cell) + 1;
    val = (double *)malloc((size_t)nx * (size_t)ny * sizeof(double));
    if (!val) return wr_fail(diag, WR_ERR_NOMEM, -1, "out of memory");
    for (i = 0; i < nx * ny; ++i) val[i] = NAN;
    /* rasterise every face with its panel's sizing map (holes and gaps stay undefined) */
    for (f = 0; f < m->nf; ++f) {
        double uv[6], bx0, bx1, by0, by1, det;
        int32_t p = m->face_panel ? m->face_panel[f] : 0, a0, a1, b0, b1;
        wr_mesh_face_rest(m, f, uv);
        bx0 = fmin(uv[0], fmin(uv[2], uv[4]));
        bx1 = fmax(uv[0], fmax(uv[2], uv[4]));
        by0 = fmin(uv[1], fmin(uv[3], uv[5]));
        by1 = fmax(uv[1], fmax(uv[3], uv[5]));
        det = (uv[2] - uv[0]) * (uv[5] - uv[1]) - (uv[4] - uv[0]) * (uv[3] - uv[1]);
        if (det == 0.0) continue;
        a0 = (int32_t)ceil((bx0 - x0) / cell);
        a1 = (int32_t)floor((bx1 - x0) / cell);
        b0 = (int32_t)ceil((by0 - y0) / cell);
        b1 = (int32_t)floor((by1 - y0) / cell);
        for (j = b0; j <= b1; ++j)
            for (i = a0; i <= a1; ++i) {
                double x = x0 + i * cell, y = y0 + j * cell, l1, l2;
                if (i < 0 || j < 0 || i >= nx || j >= ny) continue;
                l1 = ((x - uv[0]) * (uv[5] - uv[1]) - (uv[4] - uv[0]) * (y - uv[1])) / det;
                l2 = ((uv[2] - uv[0]) * (y - uv[1]) - (x - uv[0]) * (uv[3] - uv[1])) / det;
                if (l1 < -1e-12 || l2 < -1e-12 || l1 + l2 > 1.0 + 1e-12) continue;
                val[j * nx + i] = 1e3 * wr_mesher_eval_sizing(res, p, x, y);
                if (val[j * nx + i] < vmin) vmin = val[j * nx + i];
                if (val[j * nx + i] > vmax) vmax = val[j * nx + i];
            }
    }
    if (!(vmax >= vmin)) vmin = vmax = 1.0;
    if (vmax - vmin < 1e-9) vmax = vmin + 1e-3;
    if (!mkdtemp(tmpl)) {
        free(val);
        return wr_fail(diag, WR_ERR_IO, -1, "cannot create a temporary directory for the plot data");
    }
    snprintf(gpath, sizeof gpath, "%s/grid.dat", tmpl);
    snprintf(epath, sizeof epath, "%s/edges.dat", tmpl);
    snprintf(spath, sizeof spath, "%s/plot.gp", tmpl);
    snprintf(tpng, sizeof tpng, "%s.wrtmp.png", png_path);
    fp = fopen(gpath, "w");
    if (!fp) {
        st = wr_fail(diag, WR_ERR_IO, -1, "cannot write %s", gpath);
        goto done;
    }
    for (j = 0; j < ny; ++j) {
        for (i = 0; i < nx; ++i) {
            if (isnan(val[j * nx + i]))
                fprintf(fp, "%.6g %.6g NaN\n", 1e3 * (x0 + i * cell), 1e3 * (y0 + j * cell));
            else
                fprintf(fp, "%.6g %.6g %.6g\n", 1e3 * (x0 + i * cell), 1e3 * (y0 + j * cell), val[j * nx + i]);
        }
        fputc('\n', fp);
    }
    if (fclose(fp) != 0) {
        st = wr_fail(diag, WR_ERR_IO, -1, "writing %s failed", gpath);
        goto done;
    }
    fp = fopen(epath, "w");
    if (!fp) {
        st = wr_fail(diag, WR_ERR_IO, -1, "cannot write %s", epath);
        goto done;
    }
    if (draw_edges)
        for (e = 0; e < m->ne; ++e) {
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
    else
        fprintf(fp, "NaN NaN\n");
    if (fclose(fp) != 0) {
        st = wr_fail(diag, WR_ERR_IO, -1, "writing %s failed", epath);
        goto done;
    }
    fp = fopen(spath, "w");
    if (!fp) {
        st = wr_fail(diag, WR_ERR_IO, -1, "cannot write %s", spath);
        goto done;
    }
    {
        double w = 1e3 * (x1 - x0), h = 1e3 * (y1 - y0);
        int px = 1000, py = (int)(1000.0 * h / w) + 80;
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
                vmin, vmax, 1e3 * x0 - 1e3 * cell, 1e3 * x1 + 1e3 * cell, 1e3 * y0 - 1e3 * cell,
                1e3 * y1 + 1e3 * cell);
        fprintf(fp, "plot ");
        gp_quote(fp, gpath);
        fprintf(fp, " using 1:2:3 with image, ");
        gp_quote(fp, epath);
        fprintf(fp, " using 1:2 with lines lc rgb '#202020' lw %s\n", m->nv > 20000 ? "0.2" : "0.5");
    }
    if (fclose(fp) != 0) {
        st = wr_fail(diag, WR_ERR_IO, -1, "writing %s failed", spath);
        goto done;
    }
    snprintf(cmd, sizeof cmd, "gnuplot '%s' >/dev/null 2>&1", spath);
    rc = system(cmd);
    if (rc == -1 || !WIFEXITED(rc) || WEXITSTATUS(rc) != 0) {
        remove(tpng);
        st = wr_fail(diag, WR_ERR_BACKEND, -1, "gnuplot failed rendering %s", png_path);
        goto done;
    }
    if (rename(tpng, png_path) != 0) {
        remove(tpng);
        st = wr_fail(diag, WR_ERR_IO, -1, "cannot rename the picture onto %s", png_path);
        goto done;
    }
done:
    free(val);
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
    if (res->n_seam_pairs) cJSON_AddItemToArray(files, cJSON_CreateString("seams.csv"));
    if (png_written) cJSON_AddItemToArray(files, cJSON_CreateString("sizing.png"));
    cJSON_AddItemToArray(files, cJSON_CreateString("summary.json"));
    st = wr_json_write(root, path, diag);
    cJSON_Delete(root);
    return st;
}

wr_status wr_meshout_write_dir(const wr_mesher_result *res, const wr_pattern_file *pf, const char *dir, int want_png,
                               int *png_written, wr_diag *diag) {
    static const char *const names[] = {"mesh.obj", "mesh.ply", "seams.csv", "sizing.png", "summary.json"};
    char stage[WR_PATH_MAX], p[WR_PATH_MAX + 64], q[WR_PATH_MAX + 64], comment[512];
    const char *pn[4];
    const double *pv[4];
    double *panel_id = NULL;
    wr_obj_desc od;
    wr_status st;
    int png = 0, k, n;
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
    /* mesh.obj */
    memset(&od, 0, sizeof od);
    snprintf(comment, sizeof comment, "wrinkle-mesh: %s; groups panel<i> are, in order:", pf && pf->name[0] ? pf->name : "pattern");
    n = (int)strlen(comment);
    for (k = 0; pf && pf->panel_names && k < res->n_panels && n < (int)sizeof comment - 40; ++k)
        n += snprintf(comment + n, sizeof comment - (size_t)n, " %d=%s", k, pf->panel_names[k][0] ? pf->panel_names[k] : "(unnamed)");
    od.comment = comment;
    snprintf(p, sizeof p, "%s/mesh.obj", stage);
    if ((st = wr_mesh_write_obj(&res->mesh, p, &od, diag)) != WR_OK) goto fail;
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
    for (k = 0; k < 5; ++k) {
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
