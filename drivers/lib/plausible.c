/* plausible.c — see plausible.h. */
#include "plausible.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#include "cli.h"
#include "wrinkle/resolution.h"

#define WR_PLAUSIBLE_THICKNESS_MAX 0.01 /* [m] */
#define WR_PLAUSIBLE_STRAIN_MAX 1.0

void wr_plausible_thickness(const char *what, double h) {
    if (h > WR_PLAUSIBLE_THICKNESS_MAX)
        wr_cli_warn("%s = %g m is over 1 cm: thickness is in metres (0.3 mm is 3e-4), a millimetre value read as "
                    "metres?",
                    what, h);
}

void wr_plausible_strain(const char *what, double strain) {
    if (strain > WR_PLAUSIBLE_STRAIN_MAX)
        wr_cli_warn("an edge of %s is strained by %.0f %% (over 100 %%): check the scene's units and motions", what,
                    100.0 * strain);
}

/* the band's own ends (the paper's 2.5 and 50 mm) are inside, up to rounding */
static int outside_band(double r) {
    return r < WR_RESOLUTION_PAPER_R_MIN * (1.0 - 1e-9) || r > WR_RESOLUTION_PAPER_R_MAX * (1.0 + 1e-9);
}

void wr_plausible_band(const char *what, double r) {
    if (outside_band(r))
        wr_cli_warn("%s = %.4g mm is outside the %g-%g mm band Eq. 4 was calibrated on (extrapolated)", what, 1e3 * r,
                    1e3 * WR_RESOLUTION_PAPER_R_MIN, 1e3 * WR_RESOLUTION_PAPER_R_MAX);
}

/* Largest side of the outline's bounding box [m]. */
static double outline_extent(const wr_pattern_curve *c) {
    double lo[2] = {HUGE_VAL, HUGE_VAL}, hi[2] = {-HUGE_VAL, -HUGE_VAL};
    int32_t k;
    for (k = 0; k < c->n; ++k) {
        lo[0] = fmin(lo[0], c->xy[2 * k]), hi[0] = fmax(hi[0], c->xy[2 * k]);
        lo[1] = fmin(lo[1], c->xy[2 * k + 1]), hi[1] = fmax(hi[1], c->xy[2 * k + 1]);
    }
    return fmax(hi[0] - lo[0], hi[1] - lo[1]);
}

void wr_plausible_pattern(const wr_pattern_file *pf, const wr_mesher_result *res) {
    int32_t p;
    for (p = 0; p < res->n_panels && p < pf->pattern.n_panels; ++p) {
        const char *nm = pf->panel_names && pf->panel_names[p][0] ? pf->panel_names[p] : NULL;
        double r = res->panels[p].r0, ext = outline_extent(&pf->pattern.panels[p].outer);
        char what[160];
        snprintf(what, sizeof what, "panel %d%s%s%s", (int)p, nm ? " '" : "", nm ? nm : "", nm ? "'" : "");
        if (ext < r)
            wr_cli_warn("%s is %.3g mm across, smaller than one edge (%.3g mm): coordinates in metres in a millimetre "
                        "file?",
                        what, 1e3 * ext, 1e3 * r);
        if (pf->desc.uniform_resolution > 0.0) continue; /* a chosen size, not Eq. 4's */
        /* one warning per panel: the warp's, else the weft's */
        snprintf(what + strlen(what), sizeof what - strlen(what), ": base resolution");
        wr_plausible_band(what, outside_band(res->panels[p].r_warp) ? res->panels[p].r_warp : res->panels[p].r_weft);
    }
}
