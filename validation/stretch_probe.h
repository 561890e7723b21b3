/* stretch_probe.h — validation-side helpers shared by the statics stretch-test drivers
 * (validate_stretch, validate_statics_stability, validate_statics_loop): the Newton progress line,
 * the five probe lines across the width through the wrinkled central band, and their median crest
 * count and wavelength. Static functions only (each driver is its own program). */
#ifndef WRINKLE_VALIDATION_STRETCH_PROBE_H
#define WRINKLE_VALIDATION_STRETCH_PROBE_H

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"
#include "scene.h"

#define SP_NPROBE 5 /* probe lines at x = L/2 + k L/20, k = 0, −1, 1, −2, 2 (probe 0 at L/2) */

static inline void sp_progress(void *user, int32_t step, int32_t n, const wr_statics_stats *st) {
    (void)user;
    /* cli.h: a redrawn line on a terminal, plain lines in a log (issue 19: no '\r' in logs) */
    wr_cli_progress("   step %d/%d Newton %3d |g|/ref %.1e %.1f s", (int)step, (int)n, (int)st->iterations,
            st->grad_ref > 0 ? st->grad_norm / st->grad_ref : 0.0, st->t_total);
}

static inline int sp_cmp_d(const void *a, const void *b) {
    double x = *(const double *)a, y = *(const double *)b;
    return x < y ? -1 : x > y;
}

/* median of n <= SP_NPROBE values (the mean of the middle two for even n) */
static inline double sp_median(const double *v, int n) {
    double t[SP_NPROBE];
    int i;
    for (i = 0; i < n; ++i) t[i] = v[i];
    qsort(t, (size_t)n, sizeof *t, sp_cmp_d);
    return n % 2 ? t[n / 2] : 0.5 * (t[n / 2 - 1] + t[n / 2]);
}

/* the scene's first probe (the mid-width line of examples/scenes/stretch.json) copied to the five
 * lines across the width; the wrinkles sit in the middle of the sheet, so one line at L/2 is as good
 * as its luck */
static inline void sp_place_probes(wr_scene *sc, const wr_scene *base) {
    static const int off[SP_NPROBE] = {0, -1, 1, -2, 2};
    int k;
    sc->n_probes = SP_NPROBE;
    for (k = 0; k < SP_NPROBE; ++k) {
        sc->probe[k] = base->probe[0];
        sc->probe[k].from[0] = sc->probe[k].to[0] = 0.125 + off[k] * 0.0125;
    }
}

/* The stretch scene `base` on a Delaunay rectangle of resolution r [m] (mesher seed 1), the Loop
 * element when loop is 1, probes placed as sp_place_probes, and statics' stability test after every
 * load step with a perturbation at each (issue 15: the converged-reference set-up of
 * validate_statics_fig7 and bench_loop_linear). */
static inline void sp_delaunay_stability_scene(wr_scene *sc, const wr_scene *base, double r, int loop) {
    *sc = *base;
    sc->mesh.resolution = r;
    sc->mesh.nx = sc->mesh.ny = 0;
    sc->mesh.kind = WR_SCENE_MESH_DELAUNAY_RECTANGLE, sc->mesh.seed = 1;
    sc->shell.loop_element = loop;
    sp_place_probes(sc, base);
    memset(&sc->stability, 0, sizeof sc->stability);
    sc->stability.check = 1, sc->stability.perturb_each = 1;
}

/* median count and wavelength over the probes that could be analysed (*np of them; NAN when none),
 * probe 0's peak-to-peak amplitude, and the sheet's peak |w| */
static inline void sp_measure(const wr_scene_run *run, double *count, double *wavelength, double *amp_p2p, double *zmax,
                              int *np_out) {
    double c[SP_NPROBE], l[SP_NPROBE];
    int k, np = 0;
    int32_t i;
    wr_diag d;
    *amp_p2p = 0.0;
    for (k = 0; k < SP_NPROBE; ++k) {
        wr_spectrum_result rk;
        if (wr_scene_run_probe(run, k, &rk, &d) != WR_OK) continue;
        if (k == 0) *amp_p2p = rk.amplitude_p2p;
        c[np] = rk.count, l[np] = rk.wavelength, np++;
    }
    *count = np ? sp_median(c, np) : NAN;
    *wavelength = np ? sp_median(l, np) : NAN;
    *zmax = 0.0;
    for (i = 0; i < run->mesh.nv; ++i) *zmax = fmax(*zmax, fabs(run->x[3 * i + 2]));
    if (np_out) *np_out = np;
}

/* Wave periods the way a picture is counted (validate_sim_stretch's METRIC, for comparing with
 * counts printed in papers, e.g. TFW Fig. 7's "3 waves"): on each of the SP_NPROBE probes, the
 * out-of-plane displacement minus its least-squares line; lobes = maximal runs of one sign whose peak
 * is >= SP_LOBE_BAND of the probe's peak; periods = lobes / 2. Median over the probes (NAN when none
 * could be sampled). */
#define SP_LOBE_BAND 0.1
static inline double sp_wave_periods(const wr_scene_run *run) {
    double c[SP_NPROBE];
    int k, np = 0;
    for (k = 0; k < SP_NPROBE && k < run->sc->n_probes; ++k) {
        int32_t n = run->sc->probe[k].samples, i, lobes = 0, sgn = 0;
        double *pts = (double *)malloc(sizeof(double) * 2 * (size_t)n), *z = (double *)malloc(sizeof(double) * (size_t)n);
        double ds, pk = 0.0, lobe_pk = 0.0, sx = 0, sy = 0, sxx = 0, sxy = 0;
        wr_diag d;
        if (!pts || !z || wr_scene_run_probe_samples(run, k, pts, z, &ds, &d) != WR_OK) {
            free(pts), free(z);
            continue;
        }
        for (i = 0; i < n; ++i) sx += i, sy += z[i], sxx += (double)i * i, sxy += i * z[i];
        {
            double slope = (n * sxy - sx * sy) / (n * sxx - sx * sx), icpt = (sy - slope * sx) / n;
            for (i = 0; i < n; ++i) z[i] -= icpt + slope * i;
        }
        for (i = 0; i < n; ++i) pk = fmax(pk, fabs(z[i]));
        for (i = 0; pk > 0.0 && i <= n; ++i) { /* i == n closes the last run */
            int32_t s = i < n ? (z[i] > 0.0) - (z[i] < 0.0) : 0;
            if (s != sgn || i == n) {
                if (sgn && lobe_pk >= SP_LOBE_BAND * pk) ++lobes;
                sgn = s, lobe_pk = 0.0;
            }
            if (i < n) lobe_pk = fmax(lobe_pk, fabs(z[i]));
        }
        c[np++] = 0.5 * lobes;
        free(pts), free(z);
    }
    return np ? sp_median(c, np) : NAN;
}

#endif /* WRINKLE_VALIDATION_STRETCH_PROBE_H */
