/* wrinkle-report — collect the validation result files (validation/results/NAME.json) into REPORT.md.
 *
 * One job: read every result file written by a validation driver (schema in drivers/lib/vresult.h)
 * and write a Markdown report with a summary table, then per case its quantities (paper vs ours,
 * tolerance, pass), notes, extra tables and figures. Benchmarks: bench/RESULTS.md is appended
 * when present. Exit status: 0 when every case passed, 1 when any quantity failed, 2 on bad input
 * (options, unreadable or malformed result files, an output that is one of the inputs), 3 when the
 * report could not be written.
 */
#define _POSIX_C_SOURCE 200809L
#include <cjson/cJSON.h>
#include <dirent.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"
#include "wrinkle/core.h"

static void usage(FILE *to) {
    fprintf(to,
            "usage: wrinkle-report [RESULTS_DIR] [-o REPORT.md] [--bench BENCH.md]\n"
            "  Reads RESULTS_DIR/*.json (default validation/results) written by the validation\n"
            "  drivers and writes a Markdown report (default validation/REPORT.md).\n"
            "  Exit: 0 all pass, 1 some quantity failed, 2 bad input, 3 write failure.\n");
}

static int cmp_str(const void *a, const void *b) { return strcmp(*(char *const *)a, *(char *const *)b); }

static void fmt_num(const cJSON *x, char *out, size_t n) {
    if (!x || !cJSON_IsNumber(x)) {
        snprintf(out, n, "—");
        return;
    }
    snprintf(out, n, "%.4g", x->valuedouble);
}

static const char *str_or(const cJSON *o, const char *key, const char *dflt) {
    const cJSON *s = cJSON_GetObjectItemCaseSensitive(o, key);
    return cJSON_IsString(s) ? s->valuestring : dflt;
}

/* Missed quantities, counted from the rows themselves (pass == false): the report does not take a
 * file's own "failed" total on trust. */
static int count_missed(const cJSON *c) {
    const cJSON *it;
    int n = 0;
    cJSON_ArrayForEach(it, cJSON_GetObjectItemCaseSensitive(c, "quantities")) {
        if (cJSON_IsFalse(cJSON_GetObjectItemCaseSensitive(it, "pass"))) ++n;
    }
    return n;
}

/* A result file the report can stand behind: "quantities" is an array, and the file's "failed" (when
 * present) agrees with the rows. A disagreement means the file was edited by hand or written by a
 * broken driver, so it is refused (bad input) rather than reported either way. */
static int case_ok(const cJSON *c, const char *name) {
    const cJSON *q = cJSON_GetObjectItemCaseSensitive(c, "quantities");
    const cJSON *fl = cJSON_GetObjectItemCaseSensitive(c, "failed");
    int nf;
    if (!cJSON_IsArray(q)) {
        wr_cli_error("'%s' has no \"quantities\" array", name);
        return 0;
    }
    nf = count_missed(c);
    if (fl && (!cJSON_IsNumber(fl) || fl->valuedouble != (double)nf)) {
        wr_cli_error("'%s': \"failed\" is %s but %d of its quantities have \"pass\": false", name,
                     cJSON_IsNumber(fl) ? "a different count" : "not a number", nf);
        return 0;
    }
    return 1;
}

int main(int argc, char **argv) {
    const char *dir = "validation/results", *out = "validation/REPORT.md", *bench = "bench/RESULTS.md";
    char **names = NULL;
    cJSON **cases = NULL;
    size_t ncase = 0, cap = 0, i;
    int any_fail = 0, a;
    DIR *dp;
    struct dirent *de;
    wr_afile f;
    wr_diag d;

    {
        wr_cli_opt opts[2];
        const char *pos = NULL;
        int npos = 0;
        memset(opts, 0, sizeof opts);
        opts[0].name = "--output", opts[0].alias = "-o", opts[0].kind = WR_CLI_STRING, opts[0].out = (void *)&out;
        opts[1].name = "--bench", opts[1].kind = WR_CLI_STRING, opts[1].out = (void *)&bench;
        wr_cli_set_program(argv[0]);
        if ((a = wr_cli_parse(argc, argv, opts, 2, &pos, 1, &npos, usage)) <= 0) return a < 0 ? WR_CLI_EXIT_USAGE : 0;
        if (pos) dir = pos;
    }
    dp = opendir(dir);
    if (!dp) {
        wr_cli_error("cannot open results directory '%s'", dir);
        return WR_CLI_EXIT_USAGE;
    }
    while ((de = readdir(dp)) != NULL) {
        size_t k = strlen(de->d_name);
        if (k > 5 && !strcmp(de->d_name + k - 5, ".json")) {
            if (ncase == cap) {
                cap = cap ? 2 * cap : 16;
                names = (char **)realloc(names, cap * sizeof *names);
                if (!names) return WR_CLI_EXIT_FAILURE;
            }
            names[ncase] = (char *)malloc(strlen(dir) + k + 2);
            if (!names[ncase]) return WR_CLI_EXIT_FAILURE;
            sprintf(names[ncase], "%s/%s", dir, de->d_name);
            ++ncase;
        }
    }
    closedir(dp);
    if (ncase) qsort(names, ncase, sizeof *names, cmp_str);
    cases = (cJSON **)calloc(ncase ? ncase : 1, sizeof *cases);
    for (i = 0; i < ncase; ++i) {
        char *text = NULL;
        if (wr_file_read(names[i], &text, NULL, &d) != WR_OK) {
            wr_cli_error("%s", d.message);
            return WR_CLI_EXIT_USAGE;
        }
        cases[i] = cJSON_Parse(text);
        wr_free(text);
        if (!cases[i]) {
            wr_cli_error("'%s' is not valid JSON", names[i]);
            return WR_CLI_EXIT_USAGE;
        }
        if (!case_ok(cases[i], names[i])) return WR_CLI_EXIT_USAGE;
    }
    {
        const char **ins = (const char **)calloc(ncase + 1, sizeof *ins);
        int ok;
        if (!ins) return WR_CLI_EXIT_FAILURE;
        for (i = 0; i < ncase; ++i) ins[i] = names[i];
        ins[ncase] = bench;
        ok = wr_cli_output_ok(out, ins, (int)ncase + 1);
        free(ins);
        if (!ok) return WR_CLI_EXIT_USAGE;
    }
    if (wr_afile_open(&f, out, &d) != WR_OK) {
        wr_cli_error("%s", d.message);
        return WR_CLI_EXIT_FAILURE;
    }
    fprintf(f.fp,
            "# wrinkle — validation report\n\n"
            "Regenerated by `make validate` from `validation/results/*.json` (one file per case, written by\n"
            "the drivers in `validation/`). Each quantity shows the paper's value (only values printed in a\n"
            "paper), any other reference it is compared with and that reference's source, ours, the pass\n"
            "band and the verdict; \"reported\" rows have no pass band. Misses are listed as misses.\n\n"
            "## Summary\n\n| case | title | quantities | failed | machine |\n|---|---|---|---|---|\n");
    for (i = 0; i < ncase; ++i) {
        const cJSON *q = cJSON_GetObjectItemCaseSensitive(cases[i], "quantities");
        int nf = count_missed(cases[i]);
        if (nf) any_fail = 1;
        fprintf(f.fp, "| [%s](#%s) | %s | %d | %s%d%s | %s |\n", str_or(cases[i], "case", "?"),
                str_or(cases[i], "case", "?"), str_or(cases[i], "title", ""), cJSON_GetArraySize(q),
                nf ? "**" : "", nf, nf ? " missed**" : "", str_or(cases[i], "machine", ""));
    }
    for (i = 0; i < ncase; ++i) {
        const cJSON *c = cases[i], *it;
        fprintf(f.fp, "\n<a id=\"%s\"></a>\n## %s — %s\n\n_generated %s_\n\n", str_or(c, "case", "?"),
                str_or(c, "case", "?"), str_or(c, "title", ""), str_or(c, "generated", "?"));
        fprintf(f.fp, "| quantity | unit | paper | reference | ours | tolerance | pass |\n"
                      "|---|---|---|---|---|---|---|\n");
        cJSON_ArrayForEach(it, cJSON_GetObjectItemCaseSensitive(c, "quantities")) {
            char p[32], o[32], r[32];
            const cJSON *pass = cJSON_GetObjectItemCaseSensitive(it, "pass");
            const cJSON *ref = cJSON_GetObjectItemCaseSensitive(it, "reference");
            fmt_num(cJSON_GetObjectItemCaseSensitive(it, "paper"), p, sizeof p);
            fmt_num(cJSON_GetObjectItemCaseSensitive(it, "ours"), o, sizeof o);
            if (ref) /* issue 20: a non-paper reference, with its source */
                fmt_num(ref, r, sizeof r);
            else
                snprintf(r, sizeof r, "—");
            fprintf(f.fp, "| %s | %s | %s | %s%s%s%s | %s | %s | %s |\n", str_or(it, "name", "?"), str_or(it, "unit", ""), p,
                    r, ref ? " (" : "", ref ? str_or(it, "reference_source", "") : "", ref ? ")" : "", o,
                    str_or(it, "tolerance", ""),
                    cJSON_IsTrue(pass) ? "pass" : cJSON_IsFalse(pass) ? "**MISS**" : "—");
        }
        cJSON_ArrayForEach(it, cJSON_GetObjectItemCaseSensitive(c, "tables_md")) {
            if (cJSON_IsString(it)) fprintf(f.fp, "\n%s\n", it->valuestring);
        }
        cJSON_ArrayForEach(it, cJSON_GetObjectItemCaseSensitive(c, "figures")) {
            fprintf(f.fp, "\n![%s](%s)\n\n_%s_\n", str_or(it, "caption", ""), str_or(it, "path", ""),
                    str_or(it, "caption", ""));
        }
        if (cJSON_GetArraySize(cJSON_GetObjectItemCaseSensitive(c, "notes")) > 0) {
            fprintf(f.fp, "\nNotes:\n\n");
            cJSON_ArrayForEach(it, cJSON_GetObjectItemCaseSensitive(c, "notes")) {
                if (cJSON_IsString(it)) fprintf(f.fp, "- %s\n", it->valuestring);
            }
        }
    }
    {
        char *b = NULL; /* optional: a missing benchmark file only leaves the section out */
        if (wr_file_read(bench, &b, NULL, NULL) == WR_OK) {
            fprintf(f.fp, "\n## Benchmarks\n\nFrom `%s` (written by `make bench`; ratios against peers measured "
                          "in the same run).\n\n%s\n", bench, b);
            wr_free(b);
        }
    }
    if (wr_afile_commit(&f, &d) != WR_OK) {
        wr_cli_error("%s", d.message);
        return WR_CLI_EXIT_FAILURE;
    }
    for (i = 0; i < ncase; ++i) {
        cJSON_Delete(cases[i]);
        free(names[i]);
    }
    free(cases);
    free(names);
    printf("wrinkle-report: %zu cases -> %s%s\n", ncase, out, any_fail ? " (some quantities missed)" : "");
    return wr_cli_exit(any_fail ? 1 : 0);
}
