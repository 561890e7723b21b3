/* vresult.c — see vresult.h. Uses cJSON (Debian libcjson-dev). */
#define _GNU_SOURCE /* RTLD_DEFAULT */
#include "vresult.h"

#include <cjson/cJSON.h>
#include <dlfcn.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>

#include "jsonout.h"
#include "wrinkle/core.h"

struct wr_vres {
    cJSON *root, *quantities, *notes, *figures, *tables;
    int failed;
    char id[128];
};

const char *wr_vres_dir(void) {
    const char *d = getenv("WRINKLE_RESULTS_DIR");
    return (d && *d) ? d : "validation/results";
}

/* Appends ", OpenBLAS core NAME" when OpenBLAS is the BLAS in this process. OpenBLAS picks its
 * kernels at run time from the CPU (DYNAMIC_ARCH), and the kernels sum in different orders: the same
 * binary gave tfw_stretched_sheet's peak amplitude 0.34535165 mm with the SkylakeX kernels and
 * 0.34531994 mm with the Haswell/Zen ones (2026-12-02, OPENBLAS_CORETYPE forced on one machine), and
 * TFW's nearly flat wave-count optimum moves with such round-off. So a result names its kernel.
 * Looked up with dlsym so that this file does not link OpenBLAS itself (libblas.so.3 may be any BLAS). */
static void blas_core(char *out, size_t n) {
    void *sym = dlsym(RTLD_DEFAULT, "openblas_get_corename");
    char *(*corename)(void);
    size_t k = strlen(out);
    if (!sym || k + 1 >= n) return;
    memcpy(&corename, &sym, sizeof corename); /* object to function pointer without a pedantic cast */
    snprintf(out + k, n - k, ", OpenBLAS core %s", corename());
}

static void machine_string(char *out, size_t n) {
    FILE *f = fopen("/proc/cpuinfo", "r");
    char line[512], model[256] = "unknown CPU";
    long cores = 0;
    if (f) {
        while (fgets(line, sizeof line, f)) {
            if (!strncmp(line, "model name", 10)) {
                char *c = strchr(line, ':');
                if (c) {
                    size_t k;
                    snprintf(model, sizeof model, "%s", c + 2);
                    k = strlen(model);
                    if (k && model[k - 1] == '\n') model[k - 1] = 0;
                }
            }
            if (!strncmp(line, "processor", 9)) ++cores;
        }
        fclose(f);
    }
    snprintf(out, n, "%s, %ld cores", model, cores);
    blas_core(out, n);
}

wr_vres *wr_vres_begin(const char *case_id, const char *title) {
    wr_vres *v = (wr_vres *)calloc(1, sizeof *v);
    char buf[64], mach[400];
    time_t t = time(NULL);
    struct tm tmv;
    if (!v) return NULL;
    mkdir(wr_vres_dir(), 0777); /* may exist already; a real failure shows when a file is opened */
    {
        char fig[4200];
        snprintf(fig, sizeof fig, "%s/../figures", wr_vres_dir());
        mkdir(fig, 0777);
    }
    snprintf(v->id, sizeof v->id, "%s", case_id);
    v->root = cJSON_CreateObject();
    cJSON_AddStringToObject(v->root, "case", case_id);
    cJSON_AddStringToObject(v->root, "title", title);
    gmtime_r(&t, &tmv);
    strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", &tmv);
    cJSON_AddStringToObject(v->root, "generated", buf);
    machine_string(mach, sizeof mach);
    cJSON_AddStringToObject(v->root, "machine", mach);
    v->quantities = cJSON_AddArrayToObject(v->root, "quantities");
    v->notes = cJSON_AddArrayToObject(v->root, "notes");
    v->figures = cJSON_AddArrayToObject(v->root, "figures");
    v->tables = cJSON_AddArrayToObject(v->root, "tables_md");
    return v;
}

static void add_num_or_null(cJSON *o, const char *key, double x) {
    if (isfinite(x))
        cJSON_AddNumberToObject(o, key, x);
    else
        cJSON_AddNullToObject(o, key);
}

static void add_q(wr_vres *v, const char *name, const char *unit, double paper, double ours, const char *tol,
                  double lo, double hi, int pass /* -1 = null */) {
    cJSON *q;
    if (!v) return;
    q = cJSON_CreateObject();
    cJSON_AddStringToObject(q, "name", name);
    cJSON_AddStringToObject(q, "unit", unit ? unit : "");
    add_num_or_null(q, "paper", paper);
    add_num_or_null(q, "ours", ours);
    cJSON_AddStringToObject(q, "tolerance", tol);
    add_num_or_null(q, "lo", lo);
    add_num_or_null(q, "hi", hi);
    if (pass < 0)
        cJSON_AddNullToObject(q, "pass");
    else
        cJSON_AddBoolToObject(q, "pass", pass);
    if (pass == 0) v->failed++;
    cJSON_AddItemToArray(v->quantities, q);
}

void wr_vres_rel(wr_vres *v, const char *name, const char *unit, double paper, double ours, double rel_tol) {
    char tol[64];
    int pass = isfinite(ours) && isfinite(paper) && fabs(ours - paper) <= rel_tol * fabs(paper);
    snprintf(tol, sizeof tol, "±%g%% relative", 100.0 * rel_tol);
    add_q(v, name, unit, paper, ours, tol, paper - rel_tol * fabs(paper), paper + rel_tol * fabs(paper), pass);
}

void wr_vres_abs(wr_vres *v, const char *name, const char *unit, double paper, double ours, double abs_tol) {
    char tol[64];
    int pass = isfinite(ours) && isfinite(paper) && fabs(ours - paper) <= abs_tol;
    snprintf(tol, sizeof tol, "±%g %s", abs_tol, unit ? unit : "");
    add_q(v, name, unit, paper, ours, tol, paper - abs_tol, paper + abs_tol, pass);
}

void wr_vres_range(wr_vres *v, const char *name, const char *unit, double paper, double ours, double lo,
                   double hi) {
    char tol[96];
    int pass = isfinite(ours) && ours >= lo && ours <= hi;
    snprintf(tol, sizeof tol, "[%g, %g]", lo, hi);
    add_q(v, name, unit, paper, ours, tol, lo, hi, pass);
}

void wr_vres_info(wr_vres *v, const char *name, const char *unit, double paper, double ours) {
    add_q(v, name, unit, paper, ours, "reported", NAN, NAN, -1);
}

void wr_vres_check(wr_vres *v, const char *name, const char *unit, double paper, double ours,
                   const char *tolerance, int pass) {
    add_q(v, name, unit, paper, ours, tolerance, NAN, NAN, pass ? 1 : 0);
}

void wr_vres_reference(wr_vres *v, double reference, const char *source) {
    cJSON *q;
    if (!v || cJSON_GetArraySize(v->quantities) == 0) return;
    q = cJSON_GetArrayItem(v->quantities, cJSON_GetArraySize(v->quantities) - 1);
    add_num_or_null(q, "reference", reference);
    cJSON_AddStringToObject(q, "reference_source", source ? source : "");
}

void wr_vres_note(wr_vres *v, const char *text) {
    if (v) cJSON_AddItemToArray(v->notes, cJSON_CreateString(text));
}

void wr_vres_figure(wr_vres *v, const char *path, const char *caption) {
    cJSON *f;
    if (!v) return;
    f = cJSON_CreateObject();
    cJSON_AddStringToObject(f, "path", path);
    cJSON_AddStringToObject(f, "caption", caption);
    cJSON_AddItemToArray(v->figures, f);
}

void wr_vres_table_md(wr_vres *v, const char *markdown) {
    if (v) cJSON_AddItemToArray(v->tables, cJSON_CreateString(markdown));
}

int wr_vres_finish(wr_vres *v) {
    char path[WR_PATH_MAX];
    wr_diag d;
    int failed;
    if (!v) return -1;
    cJSON_AddNumberToObject(v->root, "failed", v->failed);
    mkdir(wr_vres_dir(), 0777); /* may exist already */
    snprintf(path, sizeof path, "%s/%s.json", wr_vres_dir(), v->id);
    failed = v->failed;
    if (wr_json_write(v->root, path, &d) != WR_OK) {
        fprintf(stderr, "validation: cannot write %s: %s\n", path, d.message);
        failed = -1;
    }
    cJSON_Delete(v->root);
    free(v);
    return failed;
}
