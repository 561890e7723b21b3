/* validate_table1 — Style3D Table 1: optimal resolutions of five garments and five fabrics from their
 * bending stiffness B and Young's modulus E (Eq. 4 with the paper's calibration), plus the calibrated
 * constants c1, c2 (Sec. 4.1.1) and the cantilever fabric of Fig. 18 (6.45 mm).
 *
 * Every number is recomputed from first principles: c1, c2 come from the closed-form 2×2 calibration
 * of the paper's design ranges (not from the printed constants), and each r from the branch-safe
 * root solve of Eq. 4. Pass band: 1% relative to the printed value (the paper prints 3 significant
 * digits, i.e. up to ~0.7% rounding for 18.5 mm and 6.00 mm).
 * Writes validation/results/style3d_table1.json. Exit status = number of failed quantities (0 = pass).
 */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "vresult.h"
#include "wrinkle/resolution.h"
#include "vargs.h"

/* Table 1 transcribed from the paper text (B in N·m, E in N/m², r in mm). */
typedef struct row {
    const char *name;
    const char *kind;
    double B, E, r_mm;
} row;

static const row rows[] = {
    {"Wine Style", "garment", 2.0e-6, 3.0e5, 7.83},   {"Pinkish Puff", "garment", 2.0e-6, 8.0e5, 6.69},
    {"Mint Melody", "garment", 7.8e-7, 6.6e4, 8.58},  {"Golden Grace", "garment", 2.0e-6, 1.1e5, 9.21},
    {"Blue Ballet", "garment", 2.5e-6, 1.1e5, 9.55},  {"Dark Blue", "fabric", 1.6e-4, 1.3e5, 18.5},
    {"Khaki", "fabric", 2.0e-5, 5.0e5, 10.5},          {"Green", "fabric", 2.6e-6, 2.0e6, 6.00},
    {"Light Blue", "fabric", 3.2e-7, 8.2e6, 3.61},     {"Rose", "fabric", 4.0e-8, 1.6e7, 2.70},
};

#define REL_TOL 0.01 /* 1 % of the printed value: Table 1 prints 3 significant digits (7.83, 18.5, 2.70: rounding
                      * up to 0.3 %), c1 and c2 4 digits; the rest is room for the paper's unstated rounding of
                      * the constants it solved with (this driver's original band, kept) */

static int validation_main(void) {
    wr_vres *v = wr_vres_begin("style3d_table1", "Style3D Table 1: optimal resolution from B and E (Eq. 4)");
    wr_resolution_model m = wr_resolution_model_paper();
    wr_resolution_domain_info dom;
    char table[8192], name[160];
    size_t i, used;
    double r;
    wr_diag d;
    int failed;
    if (!v) {
        fprintf(stderr, "validate_table1: cannot start the result file\n");
        return 2;
    }
    wr_vres_rel(v, "c1 (calibrated from the design ranges)", "m^-3", 32.08, m.c1, REL_TOL);
    wr_vres_rel(v, "c2 (calibrated from the design ranges)", "m^-1", -1.876e-4, m.c2, REL_TOL);
    if (wr_resolution_domain(&m, &dom, &d) == WR_OK)
        wr_vres_info(v, "model zero r0 = sqrt(-c2/c1) (smallest reachable resolution)", "mm", NAN, 1e3 * dom.r_zero);

    used = (size_t)snprintf(table, sizeof table,
                            "| example | kind | B [N·m] | E [N/m²] | y = B/E [m³] | paper r [mm] | ours r [mm] | rel. diff |\n"
                            "|---|---|---|---|---|---|---|---|\n");
    for (i = 0; i < sizeof rows / sizeof rows[0]; ++i) {
        snprintf(name, sizeof name, "Table 1 %s %s (B=%.2g, E=%.2g)", rows[i].kind, rows[i].name, rows[i].B,
                 rows[i].E);
        if (wr_resolution_from_BE(&m, rows[i].B, rows[i].E, NULL, &r, &d) != WR_OK) {
            fprintf(stderr, "validate_table1: %s: %s\n", rows[i].name, d.message);
            wr_vres_note(v, d.message);
            r = NAN;
        }
        wr_vres_rel(v, name, "mm", rows[i].r_mm, 1e3 * r, REL_TOL);
        if (used < sizeof table)
            used += (size_t)snprintf(table + used, sizeof table - used,
                                     "| %s | %s | %.2g | %.2g | %.3g | %.2f | %.3f | %+.2f%% |\n", rows[i].name,
                                     rows[i].kind, rows[i].B, rows[i].E, rows[i].B / rows[i].E, rows[i].r_mm, 1e3 * r,
                                     100.0 * (1e3 * r - rows[i].r_mm) / rows[i].r_mm);
        printf("%-13s B=%-8.2g E=%-8.2g paper %6.2f mm  ours %7.3f mm  (%+.2f%%)\n", rows[i].name, rows[i].B,
               rows[i].E, rows[i].r_mm, 1e3 * r, 100.0 * (1e3 * r - rows[i].r_mm) / rows[i].r_mm);
    }
    if (wr_resolution_from_BE(&m, 2.0e-6, 1.0e6, NULL, &r, &d) != WR_OK) r = NAN;
    wr_vres_rel(v, "Fig. 18 cantilever fabric (B=2e-6, E=1e6)", "mm", 6.45, 1e3 * r, REL_TOL);
    printf("%-13s B=%-8.2g E=%-8.2g paper %6.2f mm  ours %7.3f mm  (%+.2f%%)\n", "cantilever", 2e-6, 1e6, 6.45,
           1e3 * r, 100.0 * (1e3 * r - 6.45) / 6.45);
    printf("c1 = %.6g m^-3 (paper 32.08), c2 = %.6g m^-1 (paper -1.876e-4)\n", m.c1, m.c2);

    wr_vres_table_md(v, table);
    wr_vres_note(v, "c1 and c2 are recomputed with the closed-form 2x2 system of Sec. 4.1.1 from the design ranges "
                    "E in [2e3, 2e6] N/m^2, B in [1e-9, 1e-3] N*m, r in [2.5, 50] mm (coarsest r with y_max = "
                    "B_max/E_min, finest with y_min = B_min/E_max); the printed constants are used only as "
                    "reference values here.");
    wr_vres_note(v, "r solves c1 r^6 + c2 r^4 = B/E on the increasing positive branch r > sqrt(-c2/c1) (about "
                    "2.42 mm) by bracketed Newton on u = r^2; unique root for every y > 0.");
    wr_vres_note(v, "Table 1 values were checked against the paper text (plain-text extraction). The largest "
                    "deviations (Green +0.57%, Dark Blue -0.44%) are NOT explained by the rounded constants (c1 = "
                    "32.08, c2 = -1.876e-4 give the same deviations) nor by 3-digit rounding of r; they are "
                    "consistent with B and E being printed to 2 significant digits: r grows like y^(1/6) for "
                    "large r, so a +-3% rounding of B moves r by about +-0.5%.");
    failed = wr_vres_finish(v);
    if (failed < 0) return 2;
    printf("failed quantities: %d\n", failed);
    return failed;
}

int main(int argc, char **argv) {
    int rc = wr_vargs(argc, argv, "validate_table1",
                      "Style3D Table 1: the optimal resolution of each fabric from B and E (Eq. 4).",
                      "style3d_table1", NULL, NULL, NULL);
    return rc >= 0 ? rc : validation_main();
}
