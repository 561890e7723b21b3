/* wrinkle-resolution — optimal cloth mesh resolution from bending stiffness and Young's modulus
 * (Style3D Eq. 4, Sec. 4.1). One job: turn material numbers into a target edge length.
 *
 * Modes (see --help):  single fabric (B, E or h, ν, E), orthotropic (warp/weft pairs), calibration of
 * c1, c2 from design ranges, the inverse y(r), and CSV batch. Text output ends with the answer as
 * the last line; --json prints one object instead. Invalid input: exit 2 and one line on stderr.
 */
#include <cjson/cJSON.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"
#include "plausible.h"
#include "jsonout.h"
#include "wrinkle/resolution.h"

static void usage(FILE *to) {
    fprintf(to,
            "usage: wrinkle-resolution --bending B --young E [options]\n"
            "       wrinkle-resolution --thickness h --poisson nu --young E [options]\n"
            "       wrinkle-resolution --warp-bending Bw --warp-young Ew --weft-bending Bf --weft-young Ef\n"
            "       wrinkle-resolution --calibrate [--E-min X --E-max X --B-min X --B-max X\n"
            "                                       --r-min-mm X --r-max-mm X]\n"
            "       wrinkle-resolution --inverse-mm R\n"
            "       wrinkle-resolution --csv FILE|-\n"
            "\n"
            "Optimal cloth mesh resolution r from the Style3D scaling law c1 r^6 + c2 r^4 = B/E (Eq. 4).\n"
            "Units: B in N*m, E in N/m^2, h in m, resolutions in mm on the command line.\n"
            "\n"
            "  --bending B, --young E   bending stiffness and Young's modulus of the fabric\n"
            "  --thickness h --poisson nu   derive B = E h^3 / (12 (1 - nu^2)) (Kirchhoff-Love)\n"
            "  --warp-bending/--warp-young/--weft-bending/--weft-young   orthotropic fabric: prints the\n"
            "                           warp and weft resolutions (edge length along each direction);\n"
            "                           the last line is \"R_WARP_MM R_WEFT_MM\"\n"
            "  --calibrate              print c1 [m^-3] and c2 [m^-1] from design ranges (missing bounds\n"
            "                           take the paper's: E 2e3..2e6, B 1e-9..1e-3, r 2.5..50 mm);\n"
            "                           the last line is \"C1 C2\"\n"
            "  --inverse-mm R           print y = c1 r^6 + c2 r^4 [m^3] for r in mm (r must exceed the\n"
            "                           model's zero, about 2.42 mm for the paper's constants)\n"
            "  --csv FILE               batch: rows name,B,E (optional header) -> name,B,E,r_mm on stdout;\n"
            "                           '-' reads stdin. All rows are checked first: a bad row prints one\n"
            "                           error line and no table\n"
            "  --c1 X --c2 X            use this model instead of the paper's calibration (both needed)\n"
            "  --r-lo-mm X --r-hi-mm X  design band: a result outside it is an error (or clamped with\n"
            "                           --clamp)\n"
            "  --json                   print one JSON object instead of text\n"
            "  --help                   this text\n"
            "\n"
            "Output: text mode prints the inputs and the model, then the answer (mm) as the LAST line.\n"
            "Warnings (stderr, the answer is still printed): --thickness above 1 cm (it is in metres:\n"
            "0.3 mm is 3e-4), a resolution outside the 2.5-50 mm band Eq. 4 was calibrated on.\n"
            "Exit: 0 ok; 2 invalid input (one-line reason on stderr); 3 output failure.\n");
}

typedef struct opts {
    double B, E, h, nu;
    int has_B, has_E, has_h, has_nu;
    double Bw, Ew, Bf, Ef;
    int has_Bw, has_Ew, has_Bf, has_Ef;
    int calibrate;
    double E_min, E_max, B_min, B_max, r_min_mm, r_max_mm;
    double inverse_mm;
    int has_inverse;
    const char *csv;
    double c1, c2;
    int has_c1, has_c2;
    double r_lo_mm, r_hi_mm;
    int has_lo, has_hi, clamp;
    int json;
} opts;

/* Prints o to stdout and frees it; exit status 1 when the output failed. */
static int print_json(cJSON *o) {
    wr_diag d;
    wr_status st = wr_json_write(o, "-", &d);
    cJSON_Delete(o);
    if (st != WR_OK) wr_cli_error("%s", d.message);
    return st == WR_OK ? 0 : WR_CLI_EXIT_FAILURE;
}

static int fail_status(const char *what, const wr_diag *d) {
    if (what)
        wr_cli_error("%s: %s", what, d->message);
    else
        wr_cli_error("%s", d->message);
    return WR_CLI_EXIT_USAGE;
}

/* Strip trailing CR/LF and surrounding blanks of a CSV field in place. */
static char *trim(char *s) {
    char *e;
    while (*s == ' ' || *s == '\t') ++s;
    e = s + strlen(s);
    while (e > s && (e[-1] == ' ' || e[-1] == '\t' || e[-1] == '\n' || e[-1] == '\r')) *--e = 0;
    return s;
}

/* The CSV batch's output, built in memory: every row is validated (and its resolution computed)
 * before the first byte reaches stdout, so bad input anywhere gives one error line and no output. */
typedef struct csv_out {
    char *p;
    size_t n, cap;
} csv_out;

/* Appends one formatted row; 0 when out of memory or the row cannot be formatted. */
static int csv_append(csv_out *o, const char *name, double B, double E, double r_mm) {
    int k = snprintf(NULL, 0, "%s,%.6g,%.6g,%.6f\n", name, B, E, r_mm);
    if (k < 0) return 0;
    if (o->n + (size_t)k + 1 > o->cap) {
        size_t cap = o->cap ? o->cap : 4096;
        char *q;
        while (o->n + (size_t)k + 1 > cap) cap *= 2;
        q = (char *)wr_realloc_array(o->p, cap, 1);
        if (!q) return 0;
        o->p = q;
        o->cap = cap;
    }
    snprintf(o->p + o->n, (size_t)k + 1, "%s,%.6g,%.6g,%.6f\n", name, B, E, r_mm);
    o->n += (size_t)k;
    return 1;
}

static int run_csv(const opts *o, const wr_resolution_model *m, const wr_resolution_desc *desc) {
    FILE *f = strcmp(o->csv, "-") == 0 ? stdin : fopen(o->csv, "r");
    char line[4096];
    long lineno = 0, rows = 0;
    csv_out out;
    int rc;
    memset(&out, 0, sizeof out);
    if (!f) {
        wr_cli_error("--csv: cannot open '%s'", o->csv);
        return WR_CLI_EXIT_USAGE;
    }
    while (fgets(line, sizeof line, f)) {
        char *fld[4], *p = line, *name;
        int nf = 0;
        double B, E, r;
        wr_diag d;
        ++lineno;
        if (!strchr(line, '\n') && !feof(f)) {
            wr_cli_error("--csv line %ld: longer than %d characters", lineno, (int)sizeof line - 2);
            goto bad;
        }
        if (*trim(line) == 0) continue; /* blank lines */
        while (nf < 4) {
            char *c = strchr(p, ',');
            fld[nf++] = p;
            if (!c) break;
            *c = 0;
            p = c + 1;
        }
        if (nf != 3) {
            wr_cli_error("--csv line %ld: expected 3 columns name,B,E, got %d", lineno, nf);
            goto bad;
        }
        name = trim(fld[0]);
        fld[1] = trim(fld[1]);
        fld[2] = trim(fld[2]);
        if (rows == 0 && lineno == 1 && !wr_cli_parse_double(fld[1], &B)) {
            if (!strcmp(fld[1], "B") && !strcmp(fld[2], "E")) continue; /* header */
        }
        if (!wr_cli_parse_double(fld[1], &B)) {
            wr_cli_error("--csv line %ld: malformed B '%s'", lineno, fld[1]);
            goto bad;
        }
        if (!wr_cli_parse_double(fld[2], &E)) {
            wr_cli_error("--csv line %ld: malformed E '%s'", lineno, fld[2]);
            goto bad;
        }
        if (strchr(name, '"')) {
            wr_cli_error("--csv line %ld: quoted names are not supported", lineno);
            goto bad;
        }
        if (wr_resolution_from_BE(m, B, E, desc, &r, &d) != WR_OK) {
            wr_cli_error("--csv line %ld (%s): %s", lineno, name, d.message);
            goto bad;
        }
        if (!csv_append(&out, name, B, E, 1e3 * r)) {
            wr_cli_error("--csv line %ld: out of memory buffering the output", lineno);
            goto bad;
        }
        ++rows;
    }
    if (ferror(f)) {
        wr_cli_error("--csv: read error on '%s'", o->csv);
        goto bad;
    }
    if (f != stdin) fclose(f);
    /* all input is good: now write the whole table */
    rc = fputs("name,B,E,r_mm\n", stdout) == EOF || (out.n && fwrite(out.p, 1, out.n, stdout) != out.n) ||
                 fflush(stdout) != 0
             ? WR_CLI_EXIT_FAILURE
             : 0;
    if (rc) wr_cli_error("--csv: writing the output failed (disk full or closed pipe?)");
    wr_free(out.p);
    return rc;
bad:
    if (f != stdin) fclose(f);
    wr_free(out.p);
    return WR_CLI_EXIT_USAGE;
}

/* The command line into o (defaults: the paper's design ranges); -1 to go on, else the exit code. */
static int parse_opts(opts *o, int *has_range, int argc, char **argv) {
    /* one table, the shared loop (cli.h): name, kind, destination, range, "given" flag */
#define OPT(nm, kd, dst, flag)                                                                   \
    tab[n].name = nm, tab[n].kind = kd, tab[n].out = (void *)(dst), tab[n].lo = 1.0, tab[n].hi = 0.0, \
    tab[n].given = flag, ++n
    wr_cli_opt tab[32];
    int n = 0, npos = 0, k;
    memset(o, 0, sizeof *o);
    o->E_min = WR_RESOLUTION_PAPER_E_MIN;
    o->E_max = WR_RESOLUTION_PAPER_E_MAX;
    o->B_min = WR_RESOLUTION_PAPER_B_MIN;
    o->B_max = WR_RESOLUTION_PAPER_B_MAX;
    o->r_min_mm = 1e3 * WR_RESOLUTION_PAPER_R_MIN;
    o->r_max_mm = 1e3 * WR_RESOLUTION_PAPER_R_MAX;
    memset(tab, 0, sizeof tab);
    OPT("--json", WR_CLI_FLAG, &o->json, NULL);
    OPT("--calibrate", WR_CLI_FLAG, &o->calibrate, NULL);
    OPT("--clamp", WR_CLI_FLAG, &o->clamp, NULL);
    OPT("--csv", WR_CLI_STRING, &o->csv, NULL);
    OPT("--bending", WR_CLI_NUMBER, &o->B, &o->has_B);
    OPT("--young", WR_CLI_NUMBER, &o->E, &o->has_E);
    OPT("--thickness", WR_CLI_NUMBER, &o->h, &o->has_h);
    OPT("--poisson", WR_CLI_NUMBER, &o->nu, &o->has_nu);
    OPT("--warp-bending", WR_CLI_NUMBER, &o->Bw, &o->has_Bw);
    OPT("--warp-young", WR_CLI_NUMBER, &o->Ew, &o->has_Ew);
    OPT("--weft-bending", WR_CLI_NUMBER, &o->Bf, &o->has_Bf);
    OPT("--weft-young", WR_CLI_NUMBER, &o->Ef, &o->has_Ef);
    OPT("--E-min", WR_CLI_NUMBER, &o->E_min, has_range);
    OPT("--E-max", WR_CLI_NUMBER, &o->E_max, has_range);
    OPT("--B-min", WR_CLI_NUMBER, &o->B_min, has_range);
    OPT("--B-max", WR_CLI_NUMBER, &o->B_max, has_range);
    OPT("--r-min-mm", WR_CLI_NUMBER, &o->r_min_mm, has_range);
    OPT("--r-max-mm", WR_CLI_NUMBER, &o->r_max_mm, has_range);
    OPT("--inverse-mm", WR_CLI_NUMBER, &o->inverse_mm, &o->has_inverse);
    OPT("--c1", WR_CLI_NUMBER, &o->c1, &o->has_c1);
    OPT("--c2", WR_CLI_NUMBER, &o->c2, &o->has_c2);
    OPT("--r-lo-mm", WR_CLI_NUMBER, &o->r_lo_mm, &o->has_lo);
    OPT("--r-hi-mm", WR_CLI_NUMBER, &o->r_hi_mm, &o->has_hi);
#undef OPT
    if ((k = wr_cli_parse(argc, argv, tab, n, NULL, 0, &npos, usage)) <= 0) return k < 0 ? WR_CLI_EXIT_USAGE : 0;
    return -1;
}

/* Exactly one mode; -1 when so, else the exit code. */
static int check_mode(const opts *o, int has_range) {
    const int modes = (o->has_B || o->has_E || o->has_h || o->has_nu) + (o->has_Bw || o->has_Ew || o->has_Bf || o->has_Ef) +
                      o->calibrate + o->has_inverse + (o->csv != NULL);
    if (modes == 0) {
        wr_cli_error("nothing to do: give --bending and --young (see --help)");
        return WR_CLI_EXIT_USAGE;
    }
    if (has_range && !o->calibrate) {
        wr_cli_error("--E-min/--E-max/--B-min/--B-max/--r-min-mm/--r-max-mm only apply with --calibrate");
        return WR_CLI_EXIT_USAGE;
    }
    if (modes > 1) {
        wr_cli_error("choose one mode: single fabric, warp/weft, --calibrate, --inverse-mm or --csv");
        return WR_CLI_EXIT_USAGE;
    }
    return -1;
}

/* --calibrate: c1, c2 from the design ranges (resolution.h). */
static int run_calibrate(const opts *o) {
    wr_resolution_model m;
    wr_diag d;
    if (wr_resolution_calibrate(o->E_min, o->E_max, o->B_min, o->B_max, 1e-3 * o->r_min_mm, 1e-3 * o->r_max_mm, &m, &d) !=
        WR_OK)
        return fail_status(NULL, &d);
    if (o->json) {
        cJSON *j = cJSON_CreateObject();
        cJSON_AddNumberToObject(j, "c1", m.c1);
        cJSON_AddNumberToObject(j, "c2", m.c2);
        cJSON_AddNumberToObject(j, "y_min", o->B_min / o->E_max);
        cJSON_AddNumberToObject(j, "y_max", o->B_max / o->E_min);
        cJSON_AddNumberToObject(j, "r_min_mm", o->r_min_mm);
        cJSON_AddNumberToObject(j, "r_max_mm", o->r_max_mm);
        return print_json(j);
    }
    printf("E in [%g, %g] N/m^2, B in [%g, %g] N*m, r in [%g, %g] mm\n", o->E_min, o->E_max, o->B_min, o->B_max,
           o->r_min_mm, o->r_max_mm);
    printf("y_min = B_min/E_max = %.6g m^3, y_max = B_max/E_min = %.6g m^3\n", o->B_min / o->E_max, o->B_max / o->E_min);
    printf("c1 = %.6g m^-3\nc2 = %.6g m^-1\n", m.c1, m.c2);
    printf("%.10g %.10g\n", m.c1, m.c2);
    return wr_cli_exit(0);
}

/* The model (--c1/--c2 or the paper's) and the design band; -1 to go on, else the exit code. */
static int build_model(const opts *o, wr_resolution_model *m, wr_resolution_desc *desc) {
    wr_diag d;
    if (o->has_c1 != o->has_c2) {
        wr_cli_error("--c1 and --c2 must be given together");
        return WR_CLI_EXIT_USAGE;
    }
    if (o->has_c1) {
        wr_resolution_domain_info dom;
        m->c1 = o->c1;
        m->c2 = o->c2;
        if (wr_resolution_domain(m, &dom, &d) != WR_OK) return fail_status(NULL, &d);
    } else {
        *m = wr_resolution_model_paper();
    }
    memset(desc, 0, sizeof *desc);
    desc->clamp = o->clamp;
    if (o->has_lo) {
        if (!(o->r_lo_mm > 0.0)) {
            wr_cli_error("--r-lo-mm must be > 0, got %g", o->r_lo_mm);
            return WR_CLI_EXIT_USAGE;
        }
        desc->r_lo = 1e-3 * o->r_lo_mm;
    }
    if (o->has_hi) {
        if (!(o->r_hi_mm > 0.0)) {
            wr_cli_error("--r-hi-mm must be > 0, got %g", o->r_hi_mm);
            return WR_CLI_EXIT_USAGE;
        }
        desc->r_hi = 1e-3 * o->r_hi_mm;
    }
    if (o->has_lo && o->has_hi && !(o->r_lo_mm < o->r_hi_mm)) {
        wr_cli_error("inverted design band: --r-lo-mm %g >= --r-hi-mm %g", o->r_lo_mm, o->r_hi_mm);
        return WR_CLI_EXIT_USAGE;
    }
    return -1;
}

/* --inverse-mm: y = c1 r^6 + c2 r^4 for the given r. */
static int run_inverse(const opts *o, const wr_resolution_model *m) {
    double y;
    wr_diag d;
    if (wr_resolution_y(m, 1e-3 * o->inverse_mm, &y, &d) != WR_OK) return fail_status(NULL, &d);
    if (!isfinite(y)) { /* never "inf" as an answer (nor a JSON null): r is far beyond any cloth */
        wr_cli_error("--inverse-mm %g: y = c1 r^6 + c2 r^4 overflows a double (r is in millimetres)", o->inverse_mm);
        return WR_CLI_EXIT_USAGE;
    }
    if (o->json) {
        cJSON *j = cJSON_CreateObject();
        cJSON_AddNumberToObject(j, "r_mm", o->inverse_mm);
        cJSON_AddNumberToObject(j, "r_m", 1e-3 * o->inverse_mm);
        cJSON_AddNumberToObject(j, "y", y);
        cJSON_AddNumberToObject(j, "c1", m->c1);
        cJSON_AddNumberToObject(j, "c2", m->c2);
        return print_json(j);
    }
    printf("r = %g mm, c1 = %.6g m^-3, c2 = %.6g m^-1\n", o->inverse_mm, m->c1, m->c2);
    printf("y = B/E [m^3]:\n%.10g\n", y);
    return wr_cli_exit(0);
}

/* Warp/weft pairs: one resolution per direction (Style3D Sec. 4.2.1). */
static int run_orthotropic(const opts *o, const wr_resolution_model *m, const wr_resolution_desc *desc) {
    double rw, rf;
    wr_diag d;
    if (!(o->has_Bw && o->has_Ew && o->has_Bf && o->has_Ef)) {
        wr_cli_error("orthotropic input needs all of --warp-bending --warp-young --weft-bending --weft-young");
        return WR_CLI_EXIT_USAGE;
    }
    if (wr_resolution_orthotropic(m, o->Bw, o->Ew, o->Bf, o->Ef, desc, &rw, &rf, &d) != WR_OK)
        return fail_status(d.item == 0 ? "warp" : "weft", &d);
    wr_plausible_band("r_warp", rw);
    wr_plausible_band("r_weft", rf);
    if (o->json) {
        cJSON *j = cJSON_CreateObject();
        cJSON_AddNumberToObject(j, "r_warp_mm", 1e3 * rw);
        cJSON_AddNumberToObject(j, "r_weft_mm", 1e3 * rf);
        cJSON_AddNumberToObject(j, "r_warp_m", rw);
        cJSON_AddNumberToObject(j, "r_weft_m", rf);
        cJSON_AddNumberToObject(j, "y_warp", o->Bw / o->Ew);
        cJSON_AddNumberToObject(j, "y_weft", o->Bf / o->Ef);
        cJSON_AddNumberToObject(j, "c1", m->c1);
        cJSON_AddNumberToObject(j, "c2", m->c2);
        return print_json(j);
    }
    printf("warp: B = %g N*m, E = %g N/m^2 -> r_warp = %.4f mm (edge length along the warp)\n", o->Bw, o->Ew, 1e3 * rw);
    printf("weft: B = %g N*m, E = %g N/m^2 -> r_weft = %.4f mm (edge length along the weft)\n", o->Bf, o->Ef, 1e3 * rf);
    printf("%.4f %.4f\n", 1e3 * rw, 1e3 * rf);
    return wr_cli_exit(0);
}

/* B from --bending or Kirchhoff-Love (--thickness, --poisson); -1 to go on, else the exit code. */
static int single_bending(const opts *o, double *B) {
    wr_diag d;
    if (!o->has_E) {
        wr_cli_error("--young E is required");
        return WR_CLI_EXIT_USAGE;
    }
    if (o->has_B && (o->has_h || o->has_nu)) {
        wr_cli_error("give either --bending or --thickness/--poisson, not both");
        return WR_CLI_EXIT_USAGE;
    }
    if (o->has_h != o->has_nu) {
        wr_cli_error("--thickness and --poisson must be given together");
        return WR_CLI_EXIT_USAGE;
    }
    if (!o->has_B && !o->has_h) {
        wr_cli_error("--bending B (or --thickness h --poisson nu) is required");
        return WR_CLI_EXIT_USAGE;
    }
    if (!o->has_h) {
        *B = o->B;
        return -1;
    }
    wr_plausible_thickness("--thickness", o->h);
    return wr_kl_bending(o->E, o->h, o->nu, B, &d) == WR_OK ? -1 : fail_status(NULL, &d);
}

/* One fabric: r from Eq. 4. */
static int run_single(const opts *o, const wr_resolution_model *m, const wr_resolution_desc *desc) {
    double B, r;
    wr_diag d;
    int e;
    if ((e = single_bending(o, &B)) >= 0) return e;
    if (wr_resolution_from_BE(m, B, o->E, desc, &r, &d) != WR_OK) return fail_status(NULL, &d);
    wr_plausible_band("r", r);
    if (o->json) {
        cJSON *j = cJSON_CreateObject();
        wr_resolution_domain_info dom;
        cJSON_AddNumberToObject(j, "r_mm", 1e3 * r);
        cJSON_AddNumberToObject(j, "r_m", r);
        cJSON_AddNumberToObject(j, "y", B / o->E);
        cJSON_AddNumberToObject(j, "c1", m->c1);
        cJSON_AddNumberToObject(j, "c2", m->c2);
        cJSON_AddNumberToObject(j, "B", B);
        cJSON_AddNumberToObject(j, "E", o->E);
        if (o->has_h) {
            cJSON_AddNumberToObject(j, "thickness", o->h);
            cJSON_AddNumberToObject(j, "poisson", o->nu);
        }
        if (wr_resolution_domain(m, &dom, NULL) == WR_OK) cJSON_AddNumberToObject(j, "r_zero_mm", 1e3 * dom.r_zero);
        cJSON_AddBoolToObject(j, "paper_model", !o->has_c1);
        return print_json(j);
    }
    if (o->has_h) printf("Kirchhoff-Love: h = %g m, nu = %g -> B = %.6g N*m\n", o->h, o->nu, B);
    printf("B = %g N*m, E = %g N/m^2, y = B/E = %.6g m^3\n", B, o->E, B / o->E);
    printf("model (Eq. 4): c1 = %.6g m^-3, c2 = %.6g m^-1%s\n", m->c1, m->c2, o->has_c1 ? "" : " (paper)");
    printf("optimal resolution [mm]:\n%.4f\n", 1e3 * r);
    return wr_cli_exit(0);
}

int main(int argc, char **argv) {
    opts o;
    wr_resolution_model m;
    wr_resolution_desc desc;
    int e, has_range = 0;
    wr_cli_set_program(argv[0]);
    if ((e = parse_opts(&o, &has_range, argc, argv)) >= 0) return e;
    if ((e = check_mode(&o, has_range)) >= 0) return e;
    if (o.calibrate) return run_calibrate(&o);
    if ((e = build_model(&o, &m, &desc)) >= 0) return e;
    if (o.csv) return run_csv(&o, &m, &desc);
    if (o.has_inverse) return run_inverse(&o, &m);
    if (o.has_Bw || o.has_Ew || o.has_Bf || o.has_Ef) return run_orthotropic(&o, &m, &desc);
    return run_single(&o, &m, &desc);
}
