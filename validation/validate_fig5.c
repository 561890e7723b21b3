/* validate_fig5 — Style3D Fig. 5: optimal cloth resolution r as a function of B and E (Eq. 4).
 *
 * Samples r on a log grid over B ∈ [1e-9, 1e-3] N·m and E ∈ [2e3, 2e7] N/m² (the paper's design
 * ranges, with E extended one decade so that Table 1's stiffest fabrics fall inside), writes the grid
 * to validation/results/fig5.dat (gnuplot "splot" blocks: log10 B, log10 E, r_mm), and draws
 * validation/figures/fig5.png through a gnuplot script written beside it (skipped with a note when
 * gnuplot is not installed). Quantities checked:
 *   - r increases strictly with B along every E row, decreases strictly with E along every B column;
 *   - the design corners reproduce the calibration: r(B_max, E_min) = 50 mm, r(B_min, E_max) = 2.5 mm;
 *   - r depends on B and E only through y = B/E (equal y along grid diagonals gives equal r);
 *   - every r stays above the model's zero r0 = sqrt(-c2/c1).
 * Exit status = number of failed quantities (0 = pass), 2 on I/O errors.
 */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "vresult.h"
#include "wrinkle/resolution.h"
#include "vargs.h"

#define NB 61 /* B samples: 10 per decade over 6 decades */
#define NE 41 /* E samples: 10 per decade over 4 decades */
#define LOG_B0 (-9.0)
#define LOG_B1 (-3.0)
#define LOG_E0 3.3010299956639813 /* log10(2e3) */
#define LOG_E1 7.3010299956639813 /* log10(2e7) */

static double grid_r[NB][NE];

static int validation_main(void) {
    wr_vres *v = wr_vres_begin("style3d_fig5", "Style3D Fig. 5: resolution r over bending stiffness B and Young's modulus E");
    wr_resolution_model m = wr_resolution_model_paper();
    wr_resolution_domain_info dom;
    char dat[4096], png[4200], gp[4200], figdir[4096], cmd[8600];
    wr_afile f;
    wr_diag d;
    int i, j, viol_B = 0, viol_E = 0, solve_fail = 0, failed;
    double r, rmin = INFINITY, rmax = 0.0, diag_dev = 0.0;
    if (!v) return 2;
    if (wr_resolution_domain(&m, &dom, &d) != WR_OK) {
        fprintf(stderr, "validate_fig5: %s\n", d.message);
        return 2;
    }
    for (i = 0; i < NB; ++i)
        for (j = 0; j < NE; ++j) {
            double lb = LOG_B0 + (LOG_B1 - LOG_B0) * i / (NB - 1), le = LOG_E0 + (LOG_E1 - LOG_E0) * j / (NE - 1);
            if (wr_resolution_from_BE(&m, pow(10.0, lb), pow(10.0, le), NULL, &grid_r[i][j], &d) != WR_OK) {
                ++solve_fail;
                grid_r[i][j] = NAN;
            }
            rmin = fmin(rmin, grid_r[i][j]);
            rmax = fmax(rmax, grid_r[i][j]);
        }
    for (i = 0; i < NB; ++i)
        for (j = 0; j < NE; ++j) {
            if (i + 1 < NB && !(grid_r[i + 1][j] > grid_r[i][j])) ++viol_B;
            if (j + 1 < NE && !(grid_r[i][j + 1] < grid_r[i][j])) ++viol_E;
            /* both axes have 10 samples per decade: (i+1, j+1) has the same y = B/E as (i, j) */
            if (i + 1 < NB && j + 1 < NE)
                diag_dev = fmax(diag_dev, fabs(grid_r[i + 1][j + 1] - grid_r[i][j]) / grid_r[i][j]);
        }
    /* exact properties of Eq. 4 on its increasing branch (no tolerance: a count of 0, a monotonicity,
     * equal r on equal y = B/E up to 1e-12 relative, i.e. the root solve's own rel_tol ~1e-14 plus
     * rounding; r above the model zero r0) */
    wr_vres_range(v, "root-solve failures on the 61x41 grid", "count", NAN, solve_fail, 0, 0);
    wr_vres_range(v, "violations of dr/dB > 0 (along every E row)", "count", NAN, viol_B, 0, 0);
    wr_vres_range(v, "violations of dr/dE < 0 (along every B column)", "count", NAN, viol_E, 0, 0);
    wr_vres_range(v, "max relative change of r along equal-y diagonals", "1", NAN, diag_dev, 0.0, 1e-12);
    wr_vres_range(v, "smallest r on the grid (must exceed r0 = sqrt(-c2/c1))", "mm", NAN, 1e3 * rmin,
                  1e3 * dom.r_zero, 50.0);
    wr_vres_info(v, "largest r on the grid", "mm", NAN, 1e3 * rmax);
    if (wr_resolution_from_BE(&m, 1e-3, 2e3, NULL, &r, &d) != WR_OK) r = NAN;
    /* the calibration pins the design corners to Sec. 4.1.1's 50 mm and 2.5 mm exactly: 1e-9 relative
     * is rounding of the 2x2 solve, not a tolerance on physics */
    wr_vres_rel(v, "r(B_max = 1e-3, E_min = 2e3), coarsest design corner", "mm", 50.0, 1e3 * r, 1e-9);
    if (wr_resolution_from_BE(&m, 1e-9, 2e6, NULL, &r, &d) != WR_OK) r = NAN;
    wr_vres_rel(v, "r(B_min = 1e-9, E_max = 2e6), finest design corner", "mm", 2.5, 1e3 * r, 1e-9);

    /* data file */
    snprintf(dat, sizeof dat, "%s/fig5.dat", wr_vres_dir());
    if (wr_afile_open(&f, dat, &d) != WR_OK) {
        fprintf(stderr, "validate_fig5: %s\n", d.message);
        return 2;
    }
    fprintf(f.fp, "# Style3D Fig. 5: r(B, E) from Eq. 4, c1 = %.10g m^-3, c2 = %.10g m^-1\n", m.c1, m.c2);
    fprintf(f.fp, "# columns: log10(B [N*m])  log10(E [N/m^2])  r [mm]; one block per B value\n");
    for (i = 0; i < NB; ++i) {
        for (j = 0; j < NE; ++j)
            fprintf(f.fp, "%.6f %.6f %.6f\n", LOG_B0 + (LOG_B1 - LOG_B0) * i / (NB - 1),
                    LOG_E0 + (LOG_E1 - LOG_E0) * j / (NE - 1), 1e3 * grid_r[i][j]);
        fprintf(f.fp, "\n");
    }
    if (wr_afile_commit(&f, &d) != WR_OK) {
        fprintf(stderr, "validate_fig5: %s\n", d.message);
        return 2;
    }
    printf("wrote %s (%dx%d grid, r in [%.3f, %.3f] mm)\n", dat, NB, NE, 1e3 * rmin, 1e3 * rmax);

    /* figure: a gnuplot script beside the png, then run it */
    snprintf(figdir, sizeof figdir, "%s/../figures", wr_vres_dir());
    snprintf(png, sizeof png, "%s/fig5.png", figdir);
    snprintf(gp, sizeof gp, "%s/fig5.gp", figdir);
    if (system("command -v gnuplot >/dev/null 2>&1") != 0) {
        wr_vres_note(v, "gnuplot not found: figure fig5.png skipped (data in results/fig5.dat).");
    } else {
        snprintf(cmd, sizeof cmd, "mkdir -p '%s'", figdir);
        if (system(cmd) != 0 || wr_afile_open(&f, gp, &d) != WR_OK) {
            wr_vres_note(v, "could not create the figures directory or script; figure skipped.");
        } else {
            fprintf(f.fp,
                    "# generated by validate_fig5: Style3D Fig. 5, r(B, E) from Eq. 4\n"
                    "set terminal pngcairo size 900,700 font ',11'\n"
                    "set output '%s.tmp.png'\n"
                    "set title 'Optimal resolution r [mm] (Style3D Eq. 4, c1 = %.4g m^{-3}, c2 = %.4g m^{-1})'\n"
                    "set xlabel 'log_{10} B [N m]'\nset ylabel 'log_{10} E [N/m^2]'\n"
                    "set view map\nset pm3d map interpolate 2,2\nset palette rgbformulae 33,13,10\n"
                    "set cblabel 'r [mm]'\nset logscale cb\nset cbrange [2.4:50]\nset cbtics (2.5,3,4,5,6,8,10,15,20,30,40,50)\n"
                    "set contour base\nset cntrparam levels discrete 2.5,3,4,5,6,8,10,15,20,30,40\n"
                    "set cntrlabel onecolor\n"
                    "set label 1 'contours: 2.5 3 4 5 6 8 10 15 20 30 40 mm' at screen 0.12,0.03 left\n"
                    "set key off\n"
                    "set object 1 rect from -9,log10(2e3) to -3,log10(2e6) front fs empty border lc rgb 'white' lw 2\n"
                    "$table1 << EOD\n"
                    "-5.69897 5.47712 7.83\n-5.69897 5.90309 6.69\n-6.10791 4.81954 8.58\n"
                    "-5.69897 5.04139 9.21\n-5.60206 5.04139 9.55\n-3.79588 5.11394 18.5\n"
                    "-4.69897 5.69897 10.5\n-5.58503 6.30103 6.00\n-6.49485 6.91381 3.61\n"
                    "-7.39794 7.20412 2.70\nEOD\n"
                    "splot '%s' using 1:2:3 with pm3d nocontour, \\\n"
                    "      '%s' using 1:2:3 with lines nosurface lc rgb 'black', \\\n"
                    "      $table1 using 1:2:(0) with points nocontour pt 7 ps 1.2 lc rgb 'white'\n",
                    png, m.c1, m.c2, dat, dat);
            if (wr_afile_commit(&f, &d) != WR_OK) {
                wr_vres_note(v, "could not write the gnuplot script; figure skipped.");
            } else {
                char tmp[4300];
                snprintf(tmp, sizeof tmp, "%s.tmp.png", png);
                snprintf(cmd, sizeof cmd, "gnuplot '%s' 2>/dev/null", gp);
                /* gnuplot writes to a temporary name; renaming keeps the png whole or absent. */
                if (system(cmd) == 0 && rename(tmp, png) == 0) {
                    wr_vres_figure(v, "figures/fig5.png",
                                   "r [mm] over log10 B and log10 E (Eq. 4, paper constants); white box (top edge at E = "
                                   "2e6): the paper's design ranges; white dots: the ten Table 1 materials; black: contours.");
                    printf("wrote %s\n", png);
                } else {
                    remove(tmp);
                    wr_vres_note(v, "gnuplot failed; figure fig5.png skipped (data in results/fig5.dat).");
                }
            }
        }
    }
    wr_vres_note(v, "Data: results/fig5.dat (log10 B, log10 E, r in mm; 10 samples per decade on both axes).");
    wr_vres_note(v, "The paper's Fig. 5 is a plot without printed values; this case checks its qualitative "
                    "content (monotone in B and E, dependence only on B/E, design corners at 2.5 and 50 mm).");
    failed = wr_vres_finish(v);
    if (failed < 0) return 2;
    printf("failed quantities: %d\n", failed);
    return failed;
}

int main(int argc, char **argv) {
    int rc = wr_vargs(argc, argv, "validate_fig5",
                      "Style3D Fig. 5: the resolution r over bending stiffness B and Young's modulus E (Eq. 4).",
                      "style3d_fig5", NULL, NULL, NULL);
    return rc >= 0 ? rc : validation_main();
}
