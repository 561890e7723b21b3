/* zc_probe.h — the crest-count wavelength estimator the dynamic-simulation validators share
 * (validate_sim_curtain's METRIC, reused by validate_sim_garments): sign changes of a probe signal
 * with a hysteresis band, so noise around zero does not count as crests. Static function only. */
#ifndef WRINKLE_VALIDATION_ZC_PROBE_H
#define WRINKLE_VALIDATION_ZC_PROBE_H

#include <math.h>
#include <stdint.h>

/* 2 · length / sign changes of v[0..n), a sign change counted once the signal leaves ±band_rel of its
 * peak |v|; NaN without any. *ncross (may be NULL) receives the count. */
static inline double zc_wavelength(const double *v, int32_t n, double length, double band_rel, int32_t *ncross) {
    double vmax = 0.0, band;
    int32_t i, nc = 0, sgn = 0;
    for (i = 0; i < n; ++i) vmax = fmax(vmax, fabs(v[i]));
    if (ncross) *ncross = 0;
    if (!(vmax > 0.0)) return NAN;
    band = band_rel * vmax;
    for (i = 0; i < n; ++i) {
        int32_t s = v[i] > band ? 1 : v[i] < -band ? -1 : 0;
        if (s && sgn && s != sgn) ++nc;
        if (s) sgn = s;
    }
    if (ncross) *ncross = nc;
    return nc > 0 ? 2.0 * length / nc : NAN;
}

#endif /* WRINKLE_VALIDATION_ZC_PROBE_H */
