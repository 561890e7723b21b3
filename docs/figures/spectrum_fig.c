/* docs/figures/spectrum_fig.c — the worked example of docs/spectrum.md: a synthetic wrinkled strip
 * on a wr_mesh_rectangle, probed across the wrinkles, analysed by wr_spectrum_analyze. Writes
 * spectrum_probe.dat and spectrum_power.dat (for spectrum.gp) and prints the numbers quoted in the doc.
 *
 *   cc -std=c11 -O2 -Iinclude docs/figures/spectrum_fig.c -o /tmp/spectrum_fig -lfftw3 -lm
 *   (cd docs/figures && /tmp/spectrum_fig && gnuplot spectrum.gp)      -> spectrum.svg
 */
#define WRINKLE_IMPLEMENTATION
#include "wrinkle/core.h"
#include "wrinkle/mesh.h"
#include "wrinkle/spectrum.h"

#include <math.h>
#include <stdio.h>

#define NPROBE 400

int main(void) {
    const double W = 0.10, H = 0.20, lambda = 0.0123, A = 1.5e-3, two_pi = 6.283185307179586;
    double pts[2 * NPROBE], z[NPROBE], *field, *power, ds, a[2] = {0.05, 0.0}, b[2] = {0.05, H};
    int32_t v, nout, nb, k;
    wr_mesh m;
    wr_probe pr;
    wr_spectrum_result r;
    wr_diag d;
    wr_rng rng;
    wr_afile f;
    if (wr_mesh_rectangle(&m, W, H, 40, 160, &d) != WR_OK) return fprintf(stderr, "%s\n", d.message), 1;
    field = (double *)wr_alloc_array((size_t)m.nv, sizeof(double));
    wr_rng_seed(&rng, 2025);
    /* out-of-plane displacement: wrinkles of wavelength lambda with an amplitude that fades towards
     * both ends, a global sag (parabola), and 5 % measurement noise */
    for (v = 0; v < m.nv; ++v) {
        double y = m.rest[2 * v + 1], env = sin(3.14159265358979 * y / H);
        field[v] = A * env * sin(two_pi * y / lambda) - 0.02 * (y / H) * (y / H) + 0.05 * A * wr_rng_normal(&rng);
    }
    if (wr_probe_create(&pr, &m, NULL, &d) != WR_OK || wr_path_segment(a, b, NPROBE, 0, pts, &ds, &d) != WR_OK ||
        wr_probe_sample(&pr, field, pts, NPROBE, z, &nout, &d) != WR_OK)
        return fprintf(stderr, "%s\n", d.message), 1;
    {
        wr_spectrum_desc desc = {0};
        desc.detrend = WR_DETREND_QUADRATIC; /* the sag is a parabola */
        nb = wr_spectrum_bins(NPROBE, 0, &desc);
        power = (double *)wr_alloc_array((size_t)nb, sizeof(double));
        if (wr_spectrum_analyze(z, NPROBE, ds, 0, &desc, &r, power, nb, &d) != WR_OK)
            return fprintf(stderr, "%s\n", d.message), 1;
    }
    printf("true wavelength %.4f mm, %.3f waves over %.0f mm\n", 1e3 * lambda, H / lambda, 1e3 * H);
    printf("FFT:  wavelength %.4f mm (err %+.3f %%), count %.3f (rounded %d)\n", 1e3 * r.wavelength,
           100 * (r.wavelength / lambda - 1), r.count, (int)r.count_rounded);
    printf("LS:   wavelength %.4f mm (err %+.3f %%), count %.3f\n", 1e3 * r.wavelength_ls,
           100 * (r.wavelength_ls / lambda - 1), r.count_ls);
    printf("zero crossings %d -> %.1f waves, zc wavelength %.4f mm\n", (int)r.n_zero_crossings, r.zc_waves,
           1e3 * r.zc_wavelength);
    printf("amplitude: peak %.3f mm; (max-min)/2 %.3f mm, spectral %.3f mm, LS %.3f mm (envelope-averaged)\n", 1e3 * A,
           1e3 * r.amplitude_p2p, 1e3 * r.amplitude_spectral, 1e3 * r.amplitude_fit);
    printf("peak bin %d of %d, offset %+.3f, peak power fraction %.3f, %d probe points outside\n", (int)r.peak_bin,
           (int)nb, r.peak_offset, r.peak_power_fraction, (int)nout);
    if (wr_afile_open(&f, "spectrum_probe.dat", &d) != WR_OK) return fprintf(stderr, "%s\n", d.message), 1;
    fprintf(f.fp, "# s[m] z[m]\n");
    for (k = 0; k < NPROBE; ++k) fprintf(f.fp, "%.9g %.9g\n", k * ds, z[k]);
    if (wr_afile_commit(&f, &d) != WR_OK) return fprintf(stderr, "%s\n", d.message), 1;
    if (wr_afile_open(&f, "spectrum_power.dat", &d) != WR_OK) return fprintf(stderr, "%s\n", d.message), 1;
    fprintf(f.fp, "# wavenumber[1/m] power (|X_k|^2, normalised to the peak); fitted peak at %.9g\n", r.wavenumber);
    for (k = 1; k < nb; ++k) fprintf(f.fp, "%.9g %.9g\n", k / (r.nfft * ds), power[k] / power[r.peak_bin]);
    if (wr_afile_commit(&f, &d) != WR_OK) return fprintf(stderr, "%s\n", d.message), 1;
    wr_free(power);
    wr_free(field);
    wr_probe_free(&pr);
    wr_mesh_free(&m);
    return 0;
}
