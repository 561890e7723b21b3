/* zc_probe.h — the probe-signal steps the dynamic-simulation validators share (validate_sim_curtain's
 * METRIC, reused by validate_sim_garments): the least-squares cubic detrend that removes the
 * sheet- or panel-scale shape from a probe, then the crest-count wavelength from sign changes with a
 * hysteresis band, so noise around zero does not count as crests. Static functions only. */
#ifndef WRINKLE_VALIDATION_ZC_PROBE_H
#define WRINKLE_VALIDATION_ZC_PROBE_H

#include <math.h>
#include <stdint.h>
#include <string.h>

/* Least-squares cubic of z[0..n) over ξ ∈ [−1, 1] (n >= 4 samples, evenly spaced), subtracted in
 * place: what is left is the wrinkle signal without the sheet's bow or the panel's hips and flare. */
static inline void zc_detrend_cubic(double *z, int32_t n) {
    double M[4][5], p[4];
    int32_t i, j, k, r;
    memset(M, 0, sizeof M);
    for (i = 0; i < n; ++i) {
        double xi = -1.0 + 2.0 * i / (n - 1.0);
        p[0] = 1.0, p[1] = xi, p[2] = xi * xi, p[3] = xi * xi * xi;
        for (j = 0; j < 4; ++j) {
            for (k = 0; k < 4; ++k) M[j][k] += p[j] * p[k];
            M[j][4] += p[j] * z[i];
        }
    }
    for (k = 0; k < 4; ++k) /* the Gram matrix is SPD and well conditioned on [−1, 1]: no pivoting */
        for (r = k + 1; r < 4; ++r) {
            double f = M[r][k] / M[k][k];
            for (j = k; j < 5; ++j) M[r][j] -= f * M[k][j];
        }
    for (k = 3; k >= 0; --k) {
        for (j = k + 1; j < 4; ++j) M[k][4] -= M[k][j] * M[j][4];
        M[k][4] /= M[k][k];
    }
    for (i = 0; i < n; ++i) {
        double xi = -1.0 + 2.0 * i / (n - 1.0);
        z[i] -= M[0][4] + xi * (M[1][4] + xi * (M[2][4] + xi * M[3][4]));
    }
}

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
