/* tests/test_spectrum.c — wavelength counting: FFT path (Parseval), sub-bin peak accuracy on pure
 * tones, amplitude estimates, dominant-tone selection, noise robustness, zero-crossing cross-check,
 * closed-curve counts, probe sampling on wr_mesh_rectangle, and every error path. */
#include <criterion/criterion.h>
#include <float.h>
#include <math.h>
#include <string.h>

#include "wrinkle/mesh.h"
#include "wrinkle/spectrum.h"

#define TWO_PI 6.28318530717958647692

/* Accuracy bounds asserted below (measured worst cases over dense sweeps of the period count and
 * phase, N = 64…1024, are in docs/spectrum.md):
 *   wavelength, >= 3 periods on an open probe: 1 %   (measured worst 0.33 % at 3–4 periods)
 *   wavelength, >= 5 periods:                   0.05 % (measured worst 0.02 %)
 *   amplitude (spectral, LS fit, and peak-to-peak when >= 20 samples per wave): 2 %
 *                                               (measured worst 0.85 % spectral at 3–4 periods) */
#define LAMBDA_TOL_3 0.01
#define LAMBDA_TOL_5 0.0005
#define AMP_TOL 0.02
/* least-squares wavelength and amplitude on a clean tone + line: 1e-6 relative (measured worst 3e-8) */
#define LAMBDA_TOL_LS 1e-6

static double *tone(int32_t n, double ds, double lambda, double amp, double phase, double offset, double slope) {
    double *x = (double *)wr_alloc_array((size_t)n, sizeof(double));
    int32_t i;
    cr_assert_not_null(x);
    for (i = 0; i < n; ++i) {
        double s = (double)i * ds;
        x[i] = amp * sin(TWO_PI * s / lambda + phase) + offset + slope * s;
    }
    return x;
}

Test(spectrum, parseval_through_fft_path) {
    /* Σ x² = (1/nfft)(P_0 + 2 Σ_{0<k<nfft/2} P_k + P_{nfft/2}[even]), for several padded lengths,
     * including an odd one (no Nyquist bin). */
    static const int32_t nffts[4] = {100, 128, 257, 400};
    double x[100], P[201], sx = 0.0;
    wr_rng rng;
    int t;
    int32_t i;
    wr_rng_seed(&rng, 7);
    for (i = 0; i < 100; ++i) {
        x[i] = wr_rng_normal(&rng) + 0.3;
        sx += x[i] * x[i];
    }
    for (t = 0; t < 4; ++t) {
        int32_t nf = nffts[t], k, nb = nf / 2 + 1;
        double sp = 0.0;
        cr_assert_eq(wr_spectrum_rfft_power(x, 100, nf, P, NULL), WR_OK);
        for (k = 0; k < nb; ++k) {
            double wgt = (k == 0 || (nf % 2 == 0 && k == nf / 2)) ? 1.0 : 2.0;
            sp += wgt * P[k];
        }
        sp /= (double)nf;
        cr_assert_float_eq(sp, sx, 1e-12 * sx, "nfft=%d: Parseval %.17g vs %.17g", nf, sp, sx);
    }
}

Test(spectrum, pure_tone_wavelength_integer_and_fractional_periods) {
    static const double periods[] = {3.0, 3.37, 4.5, 5.0, 7.81, 12.25, 31.0, 47.6};
    static const int32_t ns[2] = {128, 512};
    double worst3 = 0.0, worst5 = 0.0;
    int a, b, c;
    for (a = 0; a < 2; ++a)
        for (b = 0; b < (int)(sizeof periods / sizeof periods[0]); ++b)
            for (c = 0; c < 4; ++c) {
                int32_t n = ns[a];
                double ds = 2e-3, L = (double)(n - 1) * ds, lam = L / periods[b], err;
                double *x = tone(n, ds, lam, 1.5e-3, 0.7 * c + 0.1, 0.02, 0.05);
                wr_spectrum_result r;
                wr_diag d;
                cr_assert_eq(wr_spectrum_analyze(x, n, ds, 0, NULL, &r, NULL, 0, &d), WR_OK, "%s", d.message);
                err = fabs(r.wavelength / lam - 1.0);
                cr_assert_lt(err, LAMBDA_TOL_3, "n=%d periods=%g phase#%d: lambda err %.3g", n, periods[b], c, err);
                if (periods[b] >= 5.0) cr_assert_lt(err, LAMBDA_TOL_5, "n=%d periods=%g: %.3g", n, periods[b], err);
                cr_assert_float_eq(r.count, periods[b], LAMBDA_TOL_3 * periods[b] * 1.02);
                /* the LS model (line + tone) is exact for this signal: only the search tolerance is left */
                cr_assert_lt(fabs(r.wavelength_ls / lam - 1.0), LAMBDA_TOL_LS, "LS lambda err %g",
                             fabs(r.wavelength_ls / lam - 1.0));
                cr_assert_lt(fabs(r.amplitude_fit / 1.5e-3 - 1.0), LAMBDA_TOL_LS);
                cr_assert_eq(r.count_rounded, (int32_t)floor(r.count + 0.5));
                cr_assert(!r.peak_at_band_edge);
                if (periods[b] >= 5.0) worst5 = fmax(worst5, err);
                worst3 = fmax(worst3, err);
                wr_free(x);
            }
    cr_log_info("pure tones: worst lambda error %.4f %% (>=3 periods), %.5f %% (>=5 periods)", 100 * worst3,
                100 * worst5);
}

Test(spectrum, short_probes_need_the_least_squares_wavelength) {
    /* 2–3 waves on an open probe: the Hann-windowed FFT peak is biased by its mirror image (up to
     * ~8 %, measured), the least-squares wavelength is not. */
    static const double periods[] = {2.0, 2.3, 2.62, 2.95};
    double worst_fft = 0.0;
    int b, c;
    for (b = 0; b < 4; ++b)
        for (c = 0; c < 3; ++c) {
            int32_t n = 256;
            double ds = 1e-3, lam = (double)(n - 1) * ds / periods[b];
            double *x = tone(n, ds, lam, 1.0, 1.3 * c, 0.5, 2.0);
            wr_spectrum_result r;
            cr_assert_eq(wr_spectrum_analyze(x, n, ds, 0, NULL, &r, NULL, 0, NULL), WR_OK);
            cr_assert_lt(fabs(r.wavelength_ls / lam - 1.0), LAMBDA_TOL_LS, "periods %g: LS lambda err %g", periods[b],
                         fabs(r.wavelength_ls / lam - 1.0));
            cr_assert_float_eq(r.count_ls, periods[b], 1e-5);
            cr_assert_lt(fabs(r.amplitude_p2p - 1.0), AMP_TOL, "p2p %g", r.amplitude_p2p);
            cr_assert_lt(fabs(r.zc_wavelength / lam - 1.0), 0.01, "zc wavelength %g vs %g", r.zc_wavelength, lam);
            worst_fft = fmax(worst_fft, fabs(r.wavelength / lam - 1.0));
            wr_free(x);
        }
    cr_log_info("2-3 waves: FFT lambda worst error %.2f %% (LS within %g)", 100 * worst_fft, LAMBDA_TOL_LS);
}

Test(spectrum, amplitude_estimates_within_two_percent) {
    static const double periods[] = {3.2, 6.5, 10.0, 17.3};
    int b, c;
    for (b = 0; b < 4; ++b)
        for (c = 0; c < 3; ++c) {
            int32_t n = 512;
            double ds = 1e-3, lam = (double)(n - 1) * ds / periods[b], A = 4e-3;
            double *x = tone(n, ds, lam, A, 1.1 * c, -0.3, 0.8);
            wr_spectrum_result r;
            cr_assert_eq(wr_spectrum_analyze(x, n, ds, 0, NULL, &r, NULL, 0, NULL), WR_OK);
            cr_assert_lt(fabs(r.amplitude_spectral / A - 1.0), AMP_TOL, "spectral %g vs %g", r.amplitude_spectral, A);
            cr_assert_lt(fabs(r.amplitude_fit / A - 1.0), AMP_TOL, "fit %g vs %g", r.amplitude_fit, A);
            /* >= 20 samples per wave here (lam/ds >= 29), so the sampled extremes are within 0.6 % */
            cr_assert_lt(fabs(r.amplitude_p2p / A - 1.0), AMP_TOL, "p2p %g vs %g (periods %g)", r.amplitude_p2p, A,
                         periods[b]);
            cr_assert_float_eq(r.window_sum, 0.5 * (n - 1), 1e-9 * n); /* symmetric Hann */
            wr_free(x);
        }
}

Test(spectrum, power_array_and_bins) {
    int32_t n = 200, nb = wr_spectrum_bins(n, 0, NULL), k, kmax = 1;
    double ds = 1e-3, lam = 0.0199;
    double *x = tone(n, ds, lam, 1.0, 0.0, 0.0, 0.0), *P;
    wr_spectrum_result r;
    cr_assert_eq(nb, 4 * n / 2 + 1);
    cr_assert_eq(wr_spectrum_bins(n, 1, NULL), n / 2 + 1, "closed curves are not padded");
    cr_assert_eq(wr_spectrum_bins(7, 0, NULL), -1);
    P = (double *)wr_alloc_array((size_t)nb, sizeof(double));
    cr_assert_eq(wr_spectrum_analyze(x, n, ds, 0, NULL, &r, P, nb, NULL), WR_OK);
    cr_assert_eq(r.n_bins, nb);
    cr_assert_eq(r.nfft, 4 * n);
    for (k = 1; k < nb; ++k)
        if (P[k] > P[kmax]) kmax = k;
    cr_assert_eq(kmax, r.peak_bin);
    /* a tone of amplitude A on the peak gives |X| close to A·Σw/2 (within the sub-bin scallop) */
    cr_assert_lt(fabs(2.0 * sqrt(P[kmax]) / r.window_sum - 1.0), 0.05);
    cr_assert_gt(r.peak_power_fraction, 0.99);
    wr_free(P);
    wr_free(x);
}

Test(spectrum, two_tone_and_chirp_pick_the_dominant) {
    int32_t n = 600, i, order;
    double ds = 1e-3, L = (n - 1) * ds;
    double *x = (double *)wr_alloc_array((size_t)n, sizeof(double));
    wr_spectrum_result r;
    for (order = 0; order < 2; ++order) {
        /* strong tone 1.0 at lam_a, weaker 0.5 at lam_b; swap which one is the short wavelength */
        double lam_a = order ? 0.013 : 0.047, lam_b = order ? 0.047 : 0.013;
        for (i = 0; i < n; ++i) x[i] = sin(TWO_PI * i * ds / lam_a) + 0.5 * sin(TWO_PI * i * ds / lam_b + 1.0);
        cr_assert_eq(wr_spectrum_analyze(x, n, ds, 0, NULL, &r, NULL, 0, NULL), WR_OK);
        cr_assert_lt(fabs(r.wavelength / lam_a - 1.0), LAMBDA_TOL_3, "two-tone picked %g, want %g", r.wavelength, lam_a);
        cr_assert_lt(fabs(r.amplitude_spectral - 1.0), 0.02);
    }
    /* Linear chirp, local wavenumber k(s) = k0·(0.9 + 0.2 s/L): the dominant wavenumber lies inside
     * the swept range, near its centre k0 (a chirp spreads its power evenly over the sweep). */
    {
        double k0 = 1.0 / 0.02;
        for (i = 0; i < n; ++i) {
            double s = i * ds;
            x[i] = sin(TWO_PI * k0 * (0.9 * s + 0.1 * s * s / L));
        }
        cr_assert_eq(wr_spectrum_analyze(x, n, ds, 0, NULL, &r, NULL, 0, NULL), WR_OK);
        cr_assert_gt(r.wavenumber, 0.9 * k0);
        cr_assert_lt(r.wavenumber, 1.1 * k0);
        cr_assert_lt(fabs(r.wavenumber / k0 - 1.0), 0.05, "chirp dominant %g vs centre %g", r.wavenumber, k0);
    }
    wr_free(x);
}

Test(spectrum, noise_robustness_snr10) {
    /* SNR 10 as a power ratio: signal power A²/2, noise σ² = A²/20. 20 seeds. */
    int32_t n = 400, i;
    int seed;
    double ds = 1e-3, lam = 0.037, A = 1.0, sigma = A / sqrt(20.0), worst = 0.0, worst_amp = 0.0;
    double *x = (double *)wr_alloc_array((size_t)n, sizeof(double));
    for (seed = 1; seed <= 20; ++seed) {
        wr_rng rng;
        wr_spectrum_result r;
        wr_rng_seed(&rng, (uint64_t)seed);
        for (i = 0; i < n; ++i) x[i] = A * sin(TWO_PI * i * ds / lam + 0.2 * seed) + sigma * wr_rng_normal(&rng);
        cr_assert_eq(wr_spectrum_analyze(x, n, ds, 0, NULL, &r, NULL, 0, NULL), WR_OK);
        worst = fmax(worst, fabs(r.wavelength / lam - 1.0));
        worst = fmax(worst, fabs(r.wavelength_ls / lam - 1.0));
        worst_amp = fmax(worst_amp, fabs(r.amplitude_spectral / A - 1.0));
        worst_amp = fmax(worst_amp, fabs(r.amplitude_fit / A - 1.0));
        /* the hysteresis zero-crossing count agrees with the FFT count within one wave */
        cr_assert_leq(fabs(r.zc_waves - r.count), 1.0, "seed %d: zc %g vs fft %g", seed, r.zc_waves, r.count);
    }
    cr_assert_lt(worst, LAMBDA_TOL_3, "SNR 10: worst lambda error %g", worst);
    cr_assert_lt(worst_amp, 0.05, "SNR 10: worst amplitude error %g", worst_amp);
    cr_log_info("SNR 10 (FFT and LS): worst lambda err %.4f %%, amplitude err %.3f %%", 100 * worst, 100 * worst_amp);
    wr_free(x);
}

Test(spectrum, zero_crossings_agree_with_fft) {
    static const double periods[] = {3.3, 6.0, 11.7, 25.5};
    int b, c;
    for (b = 0; b < 4; ++b)
        for (c = 0; c < 4; ++c) {
            int32_t n = 500;
            double ds = 1e-3, lam = (n - 1) * ds / periods[b];
            double *x = tone(n, ds, lam, 2.0, 0.9 * c, 1.0, -3.0);
            wr_spectrum_result r;
            cr_assert_eq(wr_spectrum_analyze(x, n, ds, 0, NULL, &r, NULL, 0, NULL), WR_OK);
            /* 2·periods zeros in the open interval, ±1 by where the ends cut the wave */
            cr_assert_leq(fabs(r.zc_waves - periods[b]), 1.0, "zc %g vs periods %g", r.zc_waves, periods[b]);
            cr_assert_lt(fabs(r.zc_wavelength / lam - 1.0), 0.01, "zc wavelength %g vs %g", r.zc_wavelength, lam);
            wr_free(x);
        }
}

Test(spectrum, closed_curve_counts_exact) {
    static const int32_t ks[3] = {7, 25, 46};
    int a, c;
    for (a = 0; a < 3; ++a)
        for (c = 0; c < 3; ++c) {
            int32_t n = 256, i;
            double R = 0.5, ds = TWO_PI * R / n, x[256];
            wr_spectrum_result r;
            for (i = 0; i < n; ++i) x[i] = 0.01 * cos(ks[a] * TWO_PI * i / n + 0.77 * c) + 0.003;
            cr_assert_eq(wr_spectrum_analyze(x, n, ds, 1, NULL, &r, NULL, 0, NULL), WR_OK);
            cr_assert_eq(r.count_rounded, ks[a]);
            cr_assert_float_eq(r.count, (double)ks[a], 1e-9, "k=%d count %.12g", ks[a], r.count);
            cr_assert_eq(r.n_zero_crossings, 2 * ks[a], "k=%d zero crossings %d", ks[a], r.n_zero_crossings);
            cr_assert_float_eq(r.amplitude_spectral, 0.01, 1e-9);
            cr_assert_eq(r.nfft, n);
        }
}

/* Field per vertex of a rectangle mesh. */
static void fill_field(const wr_mesh *m, double *f, int kind, double lam, double k_ang, double cx, double cy) {
    int32_t v;
    for (v = 0; v < m->nv; ++v) {
        double x = m->rest[2 * v], y = m->rest[2 * v + 1];
        if (kind == 0) f[v] = sin(TWO_PI * y / lam);
        if (kind == 1) f[v] = 2.0 * x + 3.0 * y + 1.0;
        if (kind == 2) f[v] = sin(k_ang * atan2(y - cy, x - cx));
    }
}

Test(spectrum, probe_on_rectangle_recovers_lambda) {
    wr_mesh m;
    wr_probe pr;
    wr_diag d;
    double lam = 0.0625, *f, *vec, pts[2 * 300], z[300], z2[300], ds, a[2] = {0.37, 0.0}, b[2] = {0.37, 0.5};
    double dir[3] = {0.0, 0.0, 2.0};
    int32_t nout, i;
    wr_spectrum_result r;
    cr_assert_eq(wr_mesh_rectangle(&m, 0.6, 0.5, 30, 200, &d), WR_OK, "%s", d.message);
    f = (double *)wr_alloc_array((size_t)m.nv, sizeof(double));
    vec = (double *)wr_calloc_array((size_t)m.nv * 3u, sizeof(double));
    fill_field(&m, f, 0, lam, 0, 0, 0);
    for (i = 0; i < m.nv; ++i) vec[3 * i + 2] = f[i];
    cr_assert_eq(wr_probe_create(&pr, &m, NULL, &d), WR_OK, "%s", d.message);
    cr_assert_eq(wr_path_segment(a, b, 300, 0, pts, &ds, &d), WR_OK);
    cr_assert_float_eq(ds, 0.5 / 299, 1e-15);
    cr_assert_eq(wr_probe_sample(&pr, f, pts, 300, z, &nout, &d), WR_OK, "%s", d.message);
    cr_assert_eq(nout, 0, "points on the boundary ends must be found");
    cr_assert_eq(wr_probe_sample_dir(&pr, vec, dir, pts, 300, z2, &nout, &d), WR_OK);
    for (i = 0; i < 300; ++i) cr_assert_float_eq(z[i], z2[i], 1e-15);
    cr_assert_eq(wr_spectrum_analyze(z, 300, ds, 0, NULL, &r, NULL, 0, &d), WR_OK, "%s", d.message);
    cr_assert_lt(fabs(r.wavelength / lam - 1.0), LAMBDA_TOL_3, "mesh probe lambda %g vs %g", r.wavelength, lam);
    cr_assert_float_eq(r.count, 0.5 / lam, 0.01 * 0.5 / lam);
    /* 25 vertices per wave along y: the P1 interpolant of the sine loses ~0.5 % of its LS amplitude */
    cr_log_info("mesh probe: lambda err %.4f %%, amplitude_fit %.5f", 100 * fabs(r.wavelength / lam - 1.0), r.amplitude_fit);
    cr_assert_lt(fabs(r.amplitude_fit - 1.0), 0.02, "amplitude %g", r.amplitude_fit);
    /* a direction orthogonal to the displacement gives a flat signal: no oscillation */
    dir[0] = 1.0;
    dir[2] = 0.0;
    cr_assert_eq(wr_probe_sample_dir(&pr, vec, dir, pts, 300, z2, &nout, &d), WR_OK);
    cr_assert_eq(wr_spectrum_analyze(z2, 300, ds, 0, NULL, &r, NULL, 0, &d), WR_ERR_DOMAIN);
    wr_probe_free(&pr);
    wr_free(f);
    wr_free(vec);
    wr_mesh_free(&m);
}

Test(spectrum, probe_interpolates_linear_fields_exactly) {
    wr_mesh m;
    wr_probe pr;
    wr_rng rng;
    double f[11 * 8], pts[2 * 200], z[200];
    int32_t i, nout;
    cr_assert_eq(wr_mesh_rectangle(&m, 1.0, 0.7, 10, 7, NULL), WR_OK);
    fill_field(&m, f, 1, 0, 0, 0, 0);
    wr_rng_seed(&rng, 3);
    for (i = 0; i < 200; ++i) {
        pts[2 * i] = wr_rng_uniform(&rng);
        pts[2 * i + 1] = 0.7 * wr_rng_uniform(&rng);
    }
    /* corners and a vertex exactly */
    pts[0] = 0.0;
    pts[1] = 0.0;
    pts[2] = 1.0;
    pts[3] = 0.7;
    pts[4] = 0.3;
    pts[5] = 0.2;
    cr_assert_eq(wr_probe_create(&pr, &m, NULL, NULL), WR_OK);
    cr_assert_eq(wr_probe_sample(&pr, f, pts, 200, z, &nout, NULL), WR_OK);
    cr_assert_eq(nout, 0);
    for (i = 0; i < 200; ++i)
        cr_assert_float_eq(z[i], 2.0 * pts[2 * i] + 3.0 * pts[2 * i + 1] + 1.0, 1e-12, "point %d", i);
    {
        double bary[3];
        int32_t fidx = wr_probe_locate(&pr, 0.55, 0.33, bary);
        cr_assert_geq(fidx, 0);
        cr_assert_float_eq(bary[0] + bary[1] + bary[2], 1.0, 1e-14);
        cr_assert(bary[0] >= 0 && bary[1] >= 0 && bary[2] >= 0);
        cr_assert_eq(wr_probe_locate(&pr, 1.2, 0.33, bary), -1);
        cr_assert_eq(wr_probe_locate(&pr, 0.5, -1e-3, bary), -1);
    }
    wr_probe_free(&pr);
    wr_probe_free(&pr); /* safe twice */
    wr_mesh_free(&m);
}

Test(spectrum, probe_circle_on_mesh_counts_waves) {
    /* angular field sin(k·atan2) on a 100×100 grid, sampled on a circle of radius 0.35 around the
     * centre: the count must be exactly k (mesh interpolation only smooths the wave). */
    static const int32_t ks[3] = {7, 25, 46};
    wr_mesh m;
    wr_probe pr;
    double *f, pts[2 * 512], z[512], c[2] = {0.5, 0.5}, ds;
    int a;
    int32_t nout;
    cr_assert_eq(wr_mesh_rectangle(&m, 1.0, 1.0, 100, 100, NULL), WR_OK);
    f = (double *)wr_alloc_array((size_t)m.nv, sizeof(double));
    cr_assert_eq(wr_probe_create(&pr, &m, NULL, NULL), WR_OK);
    cr_assert_eq(wr_path_circle(c, 0.35, 512, pts, &ds, NULL), WR_OK);
    cr_assert_float_eq(ds, TWO_PI * 0.35 / 512, 1e-15);
    for (a = 0; a < 3; ++a) {
        wr_spectrum_result r;
        fill_field(&m, f, 2, 0, (double)ks[a], 0.5, 0.5);
        cr_assert_eq(wr_probe_sample(&pr, f, pts, 512, z, &nout, NULL), WR_OK);
        cr_assert_eq(nout, 0);
        cr_assert_eq(wr_spectrum_analyze(z, 512, ds, 1, NULL, &r, NULL, 0, NULL), WR_OK);
        cr_assert_eq(r.count_rounded, ks[a]);
        cr_assert_eq(r.n_zero_crossings, 2 * ks[a], "k=%d: %d crossings", ks[a], r.n_zero_crossings);
    }
    wr_probe_free(&pr);
    wr_free(f);
    wr_mesh_free(&m);
}

Test(spectrum, closed_segment_and_polyline_paths) {
    double a[2] = {0.0, 0.2}, b[2] = {1.0, 0.2}, pts[2 * 10], ds, L;
    double sq[8] = {0, 0, 1, 0, 1, 1, 0, 1};
    double poly[6] = {0, 0, 3, 0, 3, 4};
    int32_t i;
    cr_assert_eq(wr_path_segment(a, b, 10, 1, pts, &ds, NULL), WR_OK);
    cr_assert_float_eq(ds, 0.1, 1e-15);
    cr_assert_float_eq(pts[2 * 9], 0.9, 1e-15);
    cr_assert_eq(wr_path_polyline(sq, 4, 1, 8, pts, &ds, &L, NULL), WR_OK);
    cr_assert_float_eq(L, 4.0, 1e-15);
    cr_assert_float_eq(ds, 0.5, 1e-15);
    for (i = 1; i < 8; ++i) {
        double dx = pts[2 * i] - pts[2 * i - 2], dy = pts[2 * i + 1] - pts[2 * i - 1];
        cr_assert_float_eq(fabs(dx) + fabs(dy), 0.5, 1e-12, "step %d", i); /* along the square's sides */
    }
    cr_assert_float_eq(pts[2 * 3], 1.0, 1e-12); /* sample 3 at arc length 1.5: (1, 0.5) */
    cr_assert_float_eq(pts[2 * 3 + 1], 0.5, 1e-12);
    cr_assert_eq(wr_path_polyline(poly, 3, 0, 8, pts, &ds, &L, NULL), WR_OK);
    cr_assert_float_eq(L, 7.0, 1e-15);
    cr_assert_float_eq(ds, 1.0, 1e-15);
    cr_assert_float_eq(pts[2 * 7], 3.0, 0.0);
    cr_assert_float_eq(pts[2 * 7 + 1], 4.0, 0.0);
    cr_assert_float_eq(pts[2 * 4 + 1], 1.0, 1e-12); /* arc length 4: (3, 1) */
}

Test(spectrum, outside_points_are_nan_and_counted) {
    wr_mesh m;
    wr_probe pr;
    wr_spectrum_result r;
    wr_diag d;
    double f[21 * 21], pts[2 * 40], z[40], ds, a[2] = {-0.25, 0.5}, b[2] = {1.0, 0.5};
    int32_t nout, i, nnan = 0, first_nan = -1;
    cr_assert_eq(wr_mesh_rectangle(&m, 1.0, 1.0, 20, 20, NULL), WR_OK);
    fill_field(&m, f, 1, 0, 0, 0, 0);
    cr_assert_eq(wr_probe_create(&pr, &m, NULL, NULL), WR_OK);
    cr_assert_eq(wr_path_segment(a, b, 40, 0, pts, &ds, NULL), WR_OK);
    cr_assert_eq(wr_probe_sample(&pr, f, pts, 40, z, &nout, NULL), WR_OK);
    for (i = 0; i < 40; ++i)
        if (isnan(z[i])) {
            ++nnan;
            if (first_nan < 0) first_nan = i;
        }
    cr_assert_eq(nout, 8, "x < 0 for i < 8: got %d", nout); /* x_i = −0.25 + i·1.25/39 < 0 ⇔ i <= 7 */
    cr_assert_eq(nnan, nout);
    cr_assert_eq(wr_spectrum_analyze(z, 40, ds, 0, NULL, &r, NULL, 0, &d), WR_ERR_INVALID_ARG);
    cr_assert_eq(d.item, first_nan);
    {
        int32_t start = -1, len = wr_probe_longest_run(z, 40, &start);
        double hole[6] = {1.0, NAN, 2.0, 3.0, INFINITY, 4.0};
        cr_assert_eq(len, 32);
        cr_assert_eq(start, 8);
        cr_assert_eq(wr_probe_longest_run(hole, 6, &start), 2);
        cr_assert_eq(start, 2);
        cr_assert_eq(wr_probe_longest_run(hole + 1, 1, &start), 0);
    }
    /* all outside */
    a[0] = 2.0;
    b[0] = 3.0;
    cr_assert_eq(wr_path_segment(a, b, 40, 0, pts, &ds, NULL), WR_OK);
    cr_assert_eq(wr_probe_sample(&pr, f, pts, 40, z, &nout, &d), WR_ERR_GEOMETRY);
    cr_assert_eq(nout, 40);
    wr_probe_free(&pr);
    wr_mesh_free(&m);
}

Test(spectrum, error_paths) {
    double x[64], P[8], ds = 1e-3;
    wr_spectrum_result r;
    wr_spectrum_desc desc;
    wr_diag d;
    int32_t i;
    for (i = 0; i < 64; ++i) x[i] = sin(0.5 * i);
    cr_assert_eq(wr_spectrum_analyze(x, 7, ds, 0, NULL, &r, NULL, 0, &d), WR_ERR_INVALID_ARG);
    cr_assert_eq(wr_spectrum_analyze(x, 64, 0.0, 0, NULL, &r, NULL, 0, &d), WR_ERR_INVALID_ARG);
    cr_assert_eq(wr_spectrum_analyze(x, 64, -1.0, 0, NULL, &r, NULL, 0, &d), WR_ERR_INVALID_ARG);
    cr_assert_eq(wr_spectrum_analyze(x, 64, NAN, 0, NULL, &r, NULL, 0, &d), WR_ERR_INVALID_ARG);
    cr_assert_eq(wr_spectrum_analyze(x, 64, INFINITY, 0, NULL, &r, NULL, 0, &d), WR_ERR_INVALID_ARG);
    cr_assert_eq(wr_spectrum_analyze(NULL, 64, ds, 0, NULL, &r, NULL, 0, &d), WR_ERR_INVALID_ARG);
    x[17] = INFINITY;
    cr_assert_eq(wr_spectrum_analyze(x, 64, ds, 0, NULL, &r, NULL, 0, &d), WR_ERR_INVALID_ARG);
    cr_assert_eq(d.item, 17);
    x[17] = sin(0.5 * 17);
    /* power buffer too small */
    cr_assert_eq(wr_spectrum_analyze(x, 64, ds, 0, NULL, &r, P, 8, &d), WR_ERR_INVALID_ARG);
    /* flat and linear signals: nothing left after detrending */
    {
        double flat[16];
        for (i = 0; i < 16; ++i) flat[i] = 3.0 + 0.5 * i;
        cr_assert_eq(wr_spectrum_analyze(flat, 16, ds, 0, NULL, &r, NULL, 0, &d), WR_ERR_DOMAIN);
        for (i = 0; i < 16; ++i) flat[i] = 0.0;
        cr_assert_eq(wr_spectrum_analyze(flat, 16, ds, 1, NULL, &r, NULL, 0, &d), WR_ERR_DOMAIN);
    }
    /* bad descriptors */
    memset(&desc, 0, sizeof desc);
    desc.pad_factor = -1;
    cr_assert_eq(wr_spectrum_analyze(x, 64, ds, 0, &desc, &r, NULL, 0, &d), WR_ERR_INVALID_ARG);
    memset(&desc, 0, sizeof desc);
    desc.detrend = 99;
    cr_assert_eq(wr_spectrum_analyze(x, 64, ds, 0, &desc, &r, NULL, 0, &d), WR_ERR_INVALID_ARG);
    memset(&desc, 0, sizeof desc);
    desc.window = -2;
    cr_assert_eq(wr_spectrum_analyze(x, 64, ds, 0, &desc, &r, NULL, 0, &d), WR_ERR_INVALID_ARG);
    memset(&desc, 0, sizeof desc);
    desc.peak_fit = 17;
    cr_assert_eq(wr_spectrum_analyze(x, 64, ds, 0, &desc, &r, NULL, 0, &d), WR_ERR_INVALID_ARG);
    memset(&desc, 0, sizeof desc);
    desc.min_wavelength = 0.02;
    desc.max_wavelength = 0.01;
    cr_assert_eq(wr_spectrum_analyze(x, 64, ds, 0, &desc, &r, NULL, 0, &d), WR_ERR_INVALID_ARG);
    memset(&desc, 0, sizeof desc);
    desc.min_wavelength = -1.0;
    cr_assert_eq(wr_spectrum_analyze(x, 64, ds, 0, &desc, &r, NULL, 0, &d), WR_ERR_INVALID_ARG);
    memset(&desc, 0, sizeof desc);
    desc.zc_hysteresis = 1.5;
    cr_assert_eq(wr_spectrum_analyze(x, 64, ds, 0, &desc, &r, NULL, 0, &d), WR_ERR_INVALID_ARG);
    /* a band between two bins: wavelengths in (0.0336, 0.0338) m on a 64-sample closed curve of
     * perimeter 0.064 m hold no bin (bin 2 = 0.032 m, bin 1 = 0.064 m) */
    memset(&desc, 0, sizeof desc);
    desc.min_wavelength = 0.0336;
    desc.max_wavelength = 0.0338;
    cr_assert_eq(wr_spectrum_analyze(x, 64, ds, 1, &desc, &r, NULL, 0, &d), WR_ERR_INVALID_ARG);
    /* rfft */
    cr_assert_eq(wr_spectrum_rfft_power(x, 64, 32, P, &d), WR_ERR_INVALID_ARG);
    cr_assert_eq(wr_spectrum_rfft_power(x, 0, 32, P, &d), WR_ERR_INVALID_ARG);
    x[3] = NAN;
    cr_assert_eq(wr_spectrum_rfft_power(x, 8, 8, P, &d), WR_ERR_INVALID_ARG);
    cr_assert_eq(d.item, 3);
}

Test(spectrum, band_limits_steer_the_peak) {
    /* Two tones; restricting the band to short wavelengths selects the weaker short one. */
    int32_t n = 512, i;
    double ds = 1e-3, x[512];
    wr_spectrum_desc desc;
    wr_spectrum_result r;
    for (i = 0; i < n; ++i) x[i] = sin(TWO_PI * i * ds / 0.05) + 0.3 * sin(TWO_PI * i * ds / 0.011);
    memset(&desc, 0, sizeof desc);
    desc.max_wavelength = 0.02;
    cr_assert_eq(wr_spectrum_analyze(x, n, ds, 0, &desc, &r, NULL, 0, NULL), WR_OK);
    cr_assert_lt(fabs(r.wavelength / 0.011 - 1.0), LAMBDA_TOL_3, "band-limited peak %g", r.wavelength);
    /* a band that cuts into the strong lobe reports the edge */
    desc.max_wavelength = 0.0;
    desc.min_wavelength = 0.06;
    cr_assert_eq(wr_spectrum_analyze(x, n, ds, 0, &desc, &r, NULL, 0, NULL), WR_OK);
    cr_assert(r.peak_at_band_edge, "peak at %g should be flagged as band edge", r.wavelength);
}

Test(spectrum, probe_errors) {
    wr_mesh m, empty;
    wr_probe pr;
    wr_probe_desc pd;
    wr_diag d;
    double f[4] = {0, 0, 0, 0}, pts[4] = {0.1, 0.1, NAN, 0.0}, z[2], dir[3] = {0, 0, 0};
    double a[2] = {0, 0}, c[2] = {0, 0}, vv[4] = {0, 0, 0, 0};
    int32_t nout;
    static const int32_t tri[6] = {0, 1, 2, 1, 3, 2};
    double pos3[12] = {0, 0, 0, 1, 0, 0, 0, 1, 0.5, 1, 1, 0};
    memset(&empty, 0, sizeof empty);
    cr_assert_eq(wr_probe_create(&pr, &empty, NULL, &d), WR_ERR_INVALID_ARG);
    /* a non-planar mesh with no rest coordinates has no common 2D domain */
    cr_assert_eq(wr_mesh_create(&m, 4, pos3, NULL, 2, tri, &d), WR_OK, "%s", d.message);
    cr_assert_eq(wr_probe_create(&pr, &m, NULL, &d), WR_ERR_GEOMETRY);
    cr_assert_eq(d.item, 2);
    wr_mesh_free(&m);
    cr_assert_eq(wr_mesh_rectangle(&m, 1.0, 1.0, 1, 1, NULL), WR_OK);
    memset(&pd, 0, sizeof pd);
    pd.cells_per_face = -1.0;
    cr_assert_eq(wr_probe_create(&pr, &m, &pd, &d), WR_ERR_INVALID_ARG);
    pd.cells_per_face = 0.0;
    pd.tol = 0.7;
    cr_assert_eq(wr_probe_create(&pr, &m, &pd, &d), WR_ERR_INVALID_ARG);
    cr_assert_eq(wr_probe_create(&pr, &m, NULL, &d), WR_OK);
    cr_assert_eq(wr_probe_sample(&pr, f, pts, 2, z, &nout, &d), WR_ERR_INVALID_ARG);
    cr_assert_eq(d.item, 1);
    cr_assert_eq(wr_probe_sample(&pr, f, pts, 0, z, &nout, &d), WR_ERR_INVALID_ARG);
    cr_assert_eq(wr_probe_sample_dir(&pr, f, dir, pts, 1, z, &nout, &d), WR_ERR_INVALID_ARG);
    cr_assert_eq(wr_probe_sample_dir(&pr, f, NULL, pts, 1, z, &nout, &d), WR_ERR_INVALID_ARG);
    wr_probe_free(&pr);
    cr_assert_eq(wr_probe_sample(&pr, f, pts, 1, z, &nout, &d), WR_ERR_INVALID_ARG, "freed probe");
    wr_mesh_free(&m);
    /* paths */
    cr_assert_eq(wr_path_segment(a, a, 10, 0, vv, NULL, &d), WR_ERR_INVALID_ARG);
    cr_assert_eq(wr_path_segment(a, c, 1, 0, vv, NULL, &d), WR_ERR_INVALID_ARG);
    cr_assert_eq(wr_path_circle(c, 0.0, 10, vv, NULL, &d), WR_ERR_INVALID_ARG);
    cr_assert_eq(wr_path_circle(c, 1.0, 2, vv, NULL, &d), WR_ERR_INVALID_ARG);
    cr_assert_eq(wr_path_polyline(vv, 1, 0, 10, vv, NULL, NULL, &d), WR_ERR_INVALID_ARG);
    cr_assert_eq(wr_path_polyline(vv, 2, 0, 10, vv, NULL, NULL, &d), WR_ERR_INVALID_ARG, "zero length");
}

/* Regression: a mesh whose finite rest coordinates span more than DBL_MAX made the locator's cell
 * size infinite and its cell counts NaN → int32 conversion (undefined behaviour). Now an error. */
Test(spectrum, probe_extent_overflow_is_geometry_error) {
    double rest[8] = {-1e308, -1e308, 1e308, -1e308, 1e308, 1e308, -1e308, 1e308};
    int32_t faces[6] = {0, 1, 2, 0, 2, 3};
    wr_mesh m;
    wr_probe pr;
    wr_diag d;
    cr_assert_eq(wr_mesh_create(&m, 4, NULL, rest, 2, faces, NULL), WR_OK);
    cr_expect_eq(wr_probe_create(&pr, &m, NULL, &d), WR_ERR_GEOMETRY);
    cr_expect(strstr(d.message, "extent") != NULL, "%s", d.message);
    wr_probe_free(&pr);
    wr_mesh_free(&m);
}

/* Regression: |X_k|² of a tone with amplitude 1e200 overflowed to inf (the peak search then returned
 * the first band bin: lambda = 0.2 m with WR_OK) and with amplitude 1e-200 underflowed to 0 ("no power
 * inside the band"). The analysis is scale-free: far outside double's comfortable range the signal is
 * scaled by an exact power of two. Wavelengths must equal the unit-amplitude ones bit for bit,
 * amplitudes scale exactly, and the power array scales by amp² (where representable). */
Test(spectrum, extreme_amplitudes_give_the_unit_amplitude_answer) {
    static const double amps[] = {0x1p-700, 1e-200, 1e200, 0x1p+700};
    const int32_t n = 256;
    const double ds = 1e-3, lam = 0.016;
    double *x1 = tone(n, ds, lam, 1.0, 0.3, 0.0, 0.0), *x = (double *)wr_alloc_array((size_t)n, sizeof(double));
    double p1[2 * 4 * 256 + 1], p[2 * 4 * 256 + 1];
    wr_spectrum_result r1, r;
    wr_diag d;
    int32_t i, a, pb;
    for (pb = 0; pb < 2; ++pb) {
        cr_assert_eq(wr_spectrum_analyze(x1, n, ds, pb, NULL, &r1, p1, 2 * 4 * 256 + 1, &d), WR_OK, "%s", d.message);
        for (a = 0; a < 4; ++a) {
            for (i = 0; i < n; ++i) x[i] = x1[i] * amps[a];
            cr_assert_eq(wr_spectrum_analyze(x, n, ds, pb, NULL, &r, p, 2 * 4 * 256 + 1, &d), WR_OK,
                         "amp %g: %s", amps[a], d.message);
            if (amps[a] == 0x1p-700 || amps[a] == 0x1p+700) { /* exact powers of two: bitwise */
                cr_expect_eq(r.wavelength, r1.wavelength, "amp %g: %.17g vs %.17g", amps[a], r.wavelength,
                             r1.wavelength);
                cr_expect_eq(r.wavelength_ls, r1.wavelength_ls);
                cr_expect_eq(r.amplitude_p2p, r1.amplitude_p2p * amps[a]);
                cr_expect_eq(r.amplitude_fit, r1.amplitude_fit * amps[a]);
                cr_expect_eq(r.peak_bin, r1.peak_bin);
                cr_expect_eq(r.n_zero_crossings, r1.n_zero_crossings);
            }
            /* 1e±200 rounds every sample once: the FFT path moves by ulps, the golden-section LS search
             * within its own tolerance (LAMBDA_TOL_LS) */
            cr_expect(fabs(r.wavelength / r1.wavelength - 1.0) < 1e-12, "amp %g: lambda %.17g vs %.17g", amps[a],
                      r.wavelength, r1.wavelength);
            cr_expect(fabs(r.amplitude_spectral / (r1.amplitude_spectral * amps[a]) - 1.0) < 1e-12, "amp %g", amps[a]);
            cr_expect(fabs(r.wavelength_ls / r1.wavelength_ls - 1.0) < LAMBDA_TOL_LS, "amp %g", amps[a]);
            cr_expect(fabs(r.amplitude_fit / (r1.amplitude_fit * amps[a]) - 1.0) < LAMBDA_TOL_LS, "amp %g", amps[a]);
            cr_expect_eq(r.peak_bin, r1.peak_bin);
            {
                /* the power array is in the caller's units: amp² p1, inf or ~0 where that is not a double */
                double want = p1[r1.peak_bin] * amps[a] * amps[a];
                if (isinf(want))
                    cr_expect(isinf(p[r.peak_bin]), "amp %g: %g", amps[a], p[r.peak_bin]);
                else if (want < DBL_MIN)
                    cr_expect(p[r.peak_bin] < DBL_MIN, "amp %g: %g", amps[a], p[r.peak_bin]);
                else
                    cr_expect(fabs(p[r.peak_bin] / want - 1.0) < 1e-12, "amp %g", amps[a]);
            }
        }
    }
    wr_free(x);
    wr_free(x1);
}

/* Regression: probe paths whose length overflows a double (finite ends 2e308 apart, a circle of
 * radius 1e308) returned WR_OK with ds = inf and infinite points. Now WR_ERR_DOMAIN. */
Test(spectrum, path_length_overflow_is_domain_error) {
    double a[2] = {-1e308, 0.0}, b[2] = {1e308, 0.0}, v[4] = {-1e308, 0.0, 1e308, 0.0}, c[2] = {0.0, 0.0};
    double pts[2 * 16], ds = 0.0, len = 0.0;
    wr_diag d;
    cr_expect_eq(wr_path_segment(a, b, 16, 0, pts, &ds, &d), WR_ERR_DOMAIN);
    cr_expect(strstr(d.message, "overflow") != NULL, "%s", d.message);
    cr_expect_eq(wr_path_polyline(v, 2, 0, 16, pts, &ds, &len, &d), WR_ERR_DOMAIN);
    cr_expect(strstr(d.message, "overflow") != NULL, "%s", d.message);
    cr_expect_eq(wr_path_circle(c, 1e308, 16, pts, &ds, &d), WR_ERR_DOMAIN);
    c[0] = 1.5e308;
    cr_expect_eq(wr_path_circle(c, 0.5e308, 16, pts, &ds, &d), WR_ERR_DOMAIN);
    /* the largest representable cases still work */
    a[0] = -0.5e308, b[0] = 0.5e308, c[0] = 0.0;
    cr_expect_eq(wr_path_segment(a, b, 16, 0, pts, &ds, &d), WR_OK, "%s", d.message);
    cr_expect(isfinite(ds));
    cr_expect_eq(wr_path_circle(c, 1e307, 16, pts, &ds, &d), WR_OK, "%s", d.message);
}
