/* vresult.h — validation result files (driver-side helper, not a public wrinkle header).
 *
 * Every validation driver writes validation/results/<case_id>.json through this API; REPORT.md and any
 * other tool read those files, never the drivers' prose. Schema (one object):
 *   { "case": id, "title": str, "generated": ISO-8601 UTC, "machine": str,
 *     "quantities": [ { "name", "unit", "paper": number|null, "ours": number|null,
 *                       "tolerance": str, "lo": number|null, "hi": number|null,
 *                       "pass": true|false|null,
 *                       ["reference": number, "reference_source": str] } ... ],
 *     "notes": [str...], "figures": [ {"path", "caption"} ... ], "tables_md": [str...],
 *     "failed": int }
 * "pass": null marks a reported (informational) quantity without a pass band.
 * "paper" holds only a value printed in a paper. Anything else a quantity is compared with (an
 * elastica, a finer solve, a calibration target, a formula) is its "reference", with its source
 * (wr_vres_reference, issue 20).
 * The output directory is $WRINKLE_RESULTS_DIR if set, else "validation/results".
 */
#ifndef WRINKLE_VRESULT_H
#define WRINKLE_VRESULT_H
#include <math.h>

typedef struct wr_vres wr_vres;

/* Starts a result; also makes the results directory and <results>/../figures when missing (one
 * level each, not mkdir -p), so a driver's data files and figures can be written before
 * wr_vres_finish. */
wr_vres *wr_vres_begin(const char *case_id, const char *title);
/* |ours - paper| <= rel_tol * |paper| */
void wr_vres_rel(wr_vres *v, const char *name, const char *unit, double paper, double ours, double rel_tol);
/* |ours - paper| <= abs_tol */
void wr_vres_abs(wr_vres *v, const char *name, const char *unit, double paper, double ours, double abs_tol);
/* lo <= ours <= hi; paper may be NAN (written as null) */
void wr_vres_range(wr_vres *v, const char *name, const char *unit, double paper, double ours, double lo,
                   double hi);
/* reported without a pass band */
void wr_vres_info(wr_vres *v, const char *name, const char *unit, double paper, double ours);
/* an explicit verdict with its own tolerance text (for criteria the helpers above cannot express) */
void wr_vres_check(wr_vres *v, const char *name, const char *unit, double paper, double ours,
                   const char *tolerance, int pass);
/* Attaches a non-paper reference value and its source (what it is, where it comes from) to the
 * quantity added last; its band (lo, hi) should be built around that reference, with paper = NAN. */
void wr_vres_reference(wr_vres *v, double reference, const char *source);
void wr_vres_note(wr_vres *v, const char *text);
void wr_vres_figure(wr_vres *v, const char *path_relative_to_validation_dir, const char *caption);
void wr_vres_table_md(wr_vres *v, const char *markdown);
/* Writes the file atomically and frees v. Returns the number of failed quantities, or -1 when the
 * file could not be written (reason on stderr). */
int wr_vres_finish(wr_vres *v);
/* The directory results go to (see above); figures go to <results>/../figures. */
const char *wr_vres_dir(void);
#endif
