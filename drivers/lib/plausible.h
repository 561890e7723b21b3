/* plausible.h — the drivers' plausibility warnings (issue 19; driver-side, not a public wrinkle
 * header; compiled once as drivers/lib/plausible.c and linked into every program but
 * wrinkle-triangulate).
 *
 * A run that is valid input but almost surely a slip still runs; these print one
 * "<program>: warning: ..." line each (cli.h's wr_cli_warn) so the slip is seen before it costs a
 * simulation. One place for the limits, so every driver warns alike:
 *   - a thickness over 1 cm: cloth is well under, so it is millimetres read as metres;
 *   - an edge strained by more than 100 %: a unit slip or a runaway, not cloth;
 *   - a resolution outside the 2.5-50 mm band Style3D calibrated Eq. 4 on (Sec. 4.1): the law is
 *     extrapolated there;
 *   - a pattern panel smaller than one edge of its mesh: coordinates in metres in a millimetre file.
 *
 * API
 *   wr_plausible_thickness(what, h)         h [m]; what: the option or JSON path it came from
 *   wr_plausible_strain(what, strain)       strain: largest |l/L - 1| (meshout.h's
 *                                           wr_meshout_max_strain); what: "the result", "the base"
 *   wr_plausible_band(what, r)              r [m] from Eq. 4; what: "r", "r_warp", "panel 0: base
 *                                           resolution"
 *   wr_plausible_pattern(pf, res)           every panel of a meshed pattern: its extent against
 *                                           its base edge length, and (unless the pattern was
 *                                           meshed uniformly) its warp/weft resolutions' band
 */
#ifndef WRINKLE_DRIVERS_PLAUSIBLE_H
#define WRINKLE_DRIVERS_PLAUSIBLE_H

#include "pattern.h"
#include "wrinkle/mesher.h"

void wr_plausible_thickness(const char *what, double h);
void wr_plausible_strain(const char *what, double strain);
void wr_plausible_band(const char *what, double r);
void wr_plausible_pattern(const wr_pattern_file *pf, const wr_mesher_result *res);

#endif
