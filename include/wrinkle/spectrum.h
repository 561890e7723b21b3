/* wrinkle/spectrum.h — wrinkle wavelength counting: probe sampling of a mesh field along lines and
 * closed curves in the rest domain, and spectral analysis (dominant wavelength, wrinkle count,
 * amplitude, zero-crossing cross-check) of the sampled signal.
 * wrinkle v0.1.0 — MIT licence (see LICENSE).
 *
 * DEPENDENCIES
 *   Needs FFTW 3 (double precision): link with -lfftw3 (Debian: libfftw3-dev). Plus core.h, mesh.h.
 *
 * WHAT IT IS FOR
 *   Both papers validate by measuring wrinkles: Style3D Sec. 5 / Fig. 18 compares the wavelength that
 *   appears in a simulation with the predicted characteristic wavelength λ (Eq. 1) and the resolution
 *   r_opt = sqrt(λ²/16 + A²) built from it (Sec. 4.1.1), so both λ and the amplitude A are measured;
 *   TFW Sec. 6.2 / Fig. 21 counts "the number of wrinkles around the cylinder" as the objective,
 *   discrete convergence measure. This header turns a per-vertex field (out-of-plane displacement,
 *   radial displacement, height) into those numbers reproducibly.
 *
 * API (one line each)
 *   wr_probe_create / wr_probe_free     uniform-grid point locator over the mesh's REST (2D) domain
 *   wr_probe_locate                      face + barycentric coordinates of one rest-domain point
 *   wr_path_segment                      N equally spaced points on a segment (open, or closed = periodic)
 *   wr_path_polyline                     N points equally spaced by arc length on a polyline / polygon
 *   wr_path_circle                       N points equally spaced on a circle (closed)
 *   wr_probe_sample                      per-vertex scalar field (nv) at rest-domain points
 *   wr_probe_sample_dir                  per-vertex 3D vector field (nv*3) · direction at the points
 *   wr_probe_longest_run                 longest stretch of inside (finite) samples of a probe
 *   wr_spectrum_bins                     number of spectrum bins wr_spectrum_analyze will produce
 *   wr_spectrum_analyze                  detrend, window, pad, real FFT, peak + sub-bin fit, counts
 *   wr_spectrum_rfft_power               the bare FFT path: |X_k|² of a zero-padded real signal
 *
 * EXAMPLE
 *     wr_mesh m;  wr_probe pr;  wr_spectrum_result res;  wr_diag d;
 *     double a[2] = {0.0, 0.05}, b[2] = {0.2, 0.05}, pts[2 * 512], z[512], w[101 * 11], ds;
 *     int32_t n_out, i;
 *     wr_mesh_rectangle(&m, 0.2, 0.1, 100, 10, &d);              // 20 × 10 cm sheet, 2 mm grid
 *     for (i = 0; i < m.nv; ++i)                                 // a 2 cm wave, 1 mm amplitude
 *         w[i] = 1e-3 * sin(6.283185307179586 * m.rest[2 * i] / 0.02);
 *     wr_probe_create(&pr, &m, NULL, &d);
 *     wr_path_segment(a, b, 512, 0, pts, &ds, &d);               // open probe, ds = |b-a|/511
 *     wr_probe_sample(&pr, w, pts, 512, z, &n_out, &d);          // outside points -> NaN, counted
 *     if (wr_spectrum_analyze(z, 512, ds, 0, NULL, &res, NULL, 0, &d) == WR_OK)    // 0.02 m, 10, ~0.95e-3 m
 *         printf("lambda = %g m, %g wrinkles, A = %g m\n", res.wavelength, res.count, res.amplitude_p2p);
 *     wr_probe_free(&pr);  wr_mesh_free(&m);
 *
 * ON THE METHOD (see docs/spectrum.md for the derivations and the measured accuracy)
 *   1. Detrend: remove the least-squares mean / line / parabola (default: line for open probes, where
 *      a global tilt or sag of the sheet would otherwise leak into the lowest bins; mean for closed).
 *   2. Window: Hann for open probes (the ends of an open probe cut a wave anywhere; the window's side
 *      lobes fall as 1/k³ so the cut does not smear the peak); none for closed curves, whose sampled
 *      signal is exactly periodic, so the rectangular window is leak-free there.
 *   3. Zero-pad open probes to pad_factor·N (default 4): interpolates the spectrum 4× more finely so the
 *      3-point peak fit sees the smooth top of the main lobe. Closed curves are never padded (padding
 *      would break their periodicity); their spectrum lives on integer wave counts already.
 *   4. Real FFT with FFTW (fftw_plan_dft_r2c_1d, FFTW_ESTIMATE: no measuring, no wisdom is read or
 *      written, the result does not depend on the machine's history).
 *   5. Peak: the largest |X_k|² with k inside the band [k_min, k_max] given by max/min wavelength (DC is
 *      always excluded), refined by a 3-point fit: Gaussian = parabola through the LOG magnitudes
 *      (default; exact for a Gaussian lobe and close for Hann) or parabola through the magnitudes.
 *      wavenumber = (k + δ)/(nfft·ds) [1/m], wavelength = 1/wavenumber [m].
 *   6. count = length / wavelength; length = (N−1)·ds for open probes, N·ds (the perimeter) for closed.
 *   7. Refit: the trend polynomial is fitted again by least squares TOGETHER with cos/sin at f*, and
 *      only that trend is subtracted (plain detrending of a sine with a non-integer number of periods
 *      eats part of the sine and biases the peak-to-peak amplitude by up to ~16 %).
 *   8. Amplitude three ways: (max − min)/2 of the refitted-detrended signal; the spectral estimate
 *      2·|X(f*)|/Σw evaluated at f* by a direct DFT sum (no scalloping loss; Σw = the window's
 *      coherent gain); the least-squares amplitude of the tone from step 7.
 *   9. A least-squares wavelength (wavelength_ls): the frequency of the step-7 model that explains
 *      the most signal, found by golden section within ±½ bin of the FFT estimate. Window-free, so it
 *      stays accurate on probes holding only 2–3 waves, where the FFT peak is biased by its mirror.
 *  10. Cross-check: hysteresis (Schmitt-trigger) zero crossings of the refitted-detrended signal after
 *      a short centred moving average; waves = crossings / 2; a second wavelength from the spacing of
 *      the first and last crossings.
 *
 * ON UNITS AND CONVENTIONS
 *   Rest-domain points [m] are the coordinates wr_mesh_face_rest returns (corner_rest, else rest,
 *   else pos when the mesh lies in z = 0; a mesh with neither rest coordinates nor a planar pos has no
 *   common 2D domain and is refused). Multi-panel patterns must not overlap in the rest plane (the
 *   locator returns the face where the point is deepest). ds [m]. Wavenumber in cycles per metre (not rad/m). Amplitudes in the field's units.
 *   Probe points outside the mesh get NaN and are counted; wr_spectrum_analyze rejects NaN, so the
 *   caller decides (wr_probe_longest_run gives the longest inside stretch to analyse) — silently
 *   bridging a hole would fake a wavelength.
 *
 * ON MEMORY
 *   wr_probe_create allocates (through WR_MALLOC) — free with wr_probe_free. The probe borrows the
 *   mesh: keep it alive and unchanged while the probe is used. wr_spectrum_analyze allocates its FFT
 *   buffers with fftw_malloc (SIMD alignment); those do NOT go through WR_MALLOC/WR_FREE. Everything
 *   it allocates is freed before it returns.
 *
 * ON COST
 *   wr_spectrum_analyze: one O(N log N) FFT plus ~62 least-squares fits of the wavelength_ls search
 *   (O(N) trig each), which dominate. wr_probe_create: O(faces) (a uniform grid of
 *   desc.cells_per_face cells per face over the rest domain); wr_probe_sample: O(1) per point for
 *   evenly sized faces. Timings: docs/spectrum.md, "Measured accuracy".
 *
 * ON THREADS
 *   FFTW's planner (fftw_plan_*, fftw_destroy_plan) is NOT thread-safe, and wr_spectrum_analyze /
 *   wr_spectrum_rfft_power plan on every call. Call them from one thread at a time (or call FFTW's
 *   fftw_make_planner_thread_safe() once at start-up). The probe functions keep no global state;
 *   one wr_probe may be read from many threads.
 */
#ifndef WRINKLE_SPECTRUM_H
#define WRINKLE_SPECTRUM_H

#include "core.h"
#include "mesh.h"

#ifdef __cplusplus
extern "C" {
#endif

/* ---- point location in the rest domain ------------------------------------------------------ */
/* Defaults: cells_per_face = 1 (about one grid cell per face), tol = 1e-9 (barycentric slack, so
 * points on a shared edge or on the boundary are found; relative, dimensionless). */
typedef struct wr_probe_desc {
    double cells_per_face; /* grid cells per face; > 0 */
    double tol;            /* accept a face when every barycentric coordinate >= -tol */
    const uint8_t *face_mask; /* nf, borrowed during create: faces with 0 are left out of the grid (never
                                 located; e.g. one panel of a sewn mesh); NULL = every face */
} wr_probe_desc;

typedef struct wr_probe {
    const wr_mesh *mesh;  /* borrowed */
    double *face_uv;      /* nf*6 rest corners, cached */
    int32_t *cell_start;  /* gx*gy+1, CSR over cells */
    int32_t *cell_faces;  /* faces whose (slightly inflated) rest bounding box touches the cell */
    int32_t gx, gy;       /* grid cells in x and y */
    double x0, y0, h;     /* grid origin and cell size [m] */
    double tol;           /* barycentric slack */
    int32_t n_degenerate; /* faces with zero rest area, left out of the grid */
} wr_probe;

/* Build the locator. Errors: mesh without faces, non-finite rest coordinates, all faces
 * degenerate, a rest extent that overflows a double (WR_ERR_GEOMETRY), bad desc (WR_ERR_INVALID_ARG),
 * WR_ERR_NOMEM. On failure *p is zeroed. */
WRDEF wr_status wr_probe_create(wr_probe *p, const wr_mesh *m, const wr_probe_desc *desc, wr_diag *diag);
WRDEF void wr_probe_free(wr_probe *p); /* safe on a zeroed probe */
/* Face containing rest point (x, y) (the face where it is deepest inside when it lies on an edge),
 * barycentric coordinates in bary[3] (corner order of the face). Returns the face or -1 (outside). */
WRDEF int32_t wr_probe_locate(const wr_probe *p, double x, double y, double bary[3]);

/* ---- probe paths (rest-domain points, pts is n*2) --------------------------------------------- */
/* Segment a→b. closed = 0: n points including both ends, *ds = |b−a|/(n−1). closed = 1: a→b is one
 * full period (e.g. the rest-space circumference of a cylinder cut along a seam at a ≡ b); n points
 * excluding b, *ds = |b−a|/n. Needs n >= 2, a != b. */
WRDEF wr_status wr_path_segment(const double a[2], const double b[2], int32_t n, int closed, double *pts,
                                double *ds, wr_diag *diag);
/* Polyline with nv >= 2 vertices (verts nv*2), resampled at equal arc length. closed = 0: n points
 * from the first to the last vertex, *ds = length/(n−1). closed = 1: the polygon (last vertex joins the
 * first), n points starting at verts[0], *ds = perimeter/n. *length (optional) = length or perimeter. */
WRDEF wr_status wr_path_polyline(const double *verts, int32_t nv, int closed, int32_t n, double *pts,
                                 double *ds, double *length, wr_diag *diag);
/* Circle, centre c, radius r > 0, n points at angles 2πi/n; *ds = 2πr/n (arc length).
 * All three paths: a length, circumference or point that overflows a double is WR_ERR_DOMAIN. */
WRDEF wr_status wr_path_circle(const double c[2], double r, int32_t n, double *pts, double *ds, wr_diag *diag);

/* ---- sampling ---------------------------------------------------------------------------- */
/* out[i] = barycentric interpolation of field (nv values) at pts[2i..2i+1]; NaN where the point is
 * outside the mesh. *n_outside (optional) = number of such points. WR_ERR_GEOMETRY when every point
 * is outside; WR_ERR_INVALID_ARG for n < 1 or a non-finite point. */
WRDEF wr_status wr_probe_sample(const wr_probe *p, const double *field, const double *pts, int32_t n, double *out,
                                int32_t *n_outside, wr_diag *diag);
/* Same with a per-vertex 3D vector field vec (nv*3, e.g. displacement pos − rest) projected on
 * dir[3] (need not be unit; it is normalised; zero -> WR_ERR_INVALID_ARG): out = vec·dir/|dir|. */
WRDEF wr_status wr_probe_sample_dir(const wr_probe *p, const double *vec, const double dir[3], const double *pts,
                                    int32_t n, double *out, int32_t *n_outside, wr_diag *diag);

/* Longest run of consecutive finite samples in z[0..n): returns its length (0 if none) and its first
 * index in *start. Analyse z + *start with that length to skip the part of a probe that left the mesh
 * (the spacing is unchanged; the probe length shrinks accordingly). */
WRDEF int32_t wr_probe_longest_run(const double *z, int32_t n, int32_t *start);

/* ---- spectral analysis ------------------------------------------------------------------- */
enum { WR_DETREND_DEFAULT = 0, WR_DETREND_NONE, WR_DETREND_MEAN, WR_DETREND_LINEAR, WR_DETREND_QUADRATIC };
enum { WR_WINDOW_DEFAULT = 0, WR_WINDOW_NONE, WR_WINDOW_HANN };
enum { WR_PEAK_DEFAULT = 0, WR_PEAK_GAUSSIAN, WR_PEAK_QUADRATIC, WR_PEAK_NONE };

/* Minimum number of samples: below 8 a 3-point peak fit inside a band that excludes DC is meaningless. */
#define WR_SPECTRUM_MIN_SAMPLES 8

/* Defaults (zero means default):
 *   detrend        LINEAR for open probes, MEAN for closed curves
 *   window         HANN for open, NONE for closed
 *   peak_fit       GAUSSIAN (parabola through log |X|²)
 *   pad_factor     4 for open (nfft = 4N); closed curves are never padded (pad_factor ignored)
 *   min_wavelength 2·ds (Nyquist)                                                     [m]
 *   max_wavelength length (one wave over the probe / around the curve)                [m]
 *   zc_smooth      0.1: moving-average width for the zero-crossing count, as a fraction of the FFT
 *                  wavelength (rounded to an odd number of samples; < 2 samples = no smoothing);
 *                  has_zc_smooth = 1 makes an explicit 0 mean "no smoothing"
 *   zc_hysteresis  0.3: trigger thresholds ±zc_hysteresis·(max−min)/2 of the smoothed signal;
 *                  0.3 rejects noise excursions up to ~0.3 A yet still counts waves whose amplitude
 *                  sags to a third of the largest; has_zc_hysteresis = 1 makes 0 meaningful          */
typedef struct wr_spectrum_desc {
    int32_t detrend, window, peak_fit;
    int32_t pad_factor;
    double min_wavelength, max_wavelength;
    double zc_smooth;
    int has_zc_smooth;
    double zc_hysteresis;
    int has_zc_hysteresis;
} wr_spectrum_desc;

typedef struct wr_spectrum_result {
    int32_t n;                 /* samples analysed */
    int32_t nfft;              /* transform length (N·pad_factor for open, N for closed) */
    int32_t n_bins;            /* nfft/2 + 1; bin k has wavenumber k/(nfft·ds) */
    int periodic;              /* 1 when analysed as a closed curve */
    double ds;                 /* sample spacing [m] */
    double length;             /* (N−1)·ds open, N·ds closed [m] */
    int32_t k_min, k_max;      /* searched band of bins */
    int32_t peak_bin;          /* bin of the largest |X_k|² in the band */
    double peak_offset;        /* sub-bin offset δ of the fitted peak, in bins, |δ| <= 0.5 normally */
    int peak_at_band_edge;     /* 1 when the power still rises beyond the band edge: λ is a band limit */
    double wavenumber;         /* (peak_bin + δ)/(nfft·ds) [cycles/m] */
    double wavelength;         /* 1/wavenumber [m] */
    double count;              /* length / wavelength (wrinkles along the probe or around the curve) */
    double wavelength_ls;      /* least-squares tone wavelength (trend + tone model, frequency refined
                                  near the FFT peak) [m]; preferable on probes with < 4 waves */
    double count_ls;           /* length / wavelength_ls */
    int32_t count_rounded;     /* nearest integer (for closed curves: the integer harmonic, = peak_bin) */
    double amplitude_p2p;      /* (max − min)/2 of the signal minus the jointly refitted trend [field units] */
    double amplitude_spectral; /* 2·|DFT(f*)|/Σw of the detrended, windowed signal [field units] */
    double amplitude_fit;      /* least-squares amplitude of the tone at f*, fitted jointly with the trend */
    double peak_power_fraction;/* power within ±2·pad_factor bins of the peak / all power except DC */
    double window_sum;         /* Σ w_n (coherent gain × N) */
    int32_t n_zero_crossings;  /* hysteresis crossings of the smoothed detrended signal */
    double zc_waves;           /* n_zero_crossings / 2 */
    double zc_wavelength;      /* open: 2·(last − first crossing)/(n_zc − 1); closed: length/zc_waves; 0 if n/a */
    int32_t zc_smooth_samples; /* moving-average width actually used (1 = none) */
} wr_spectrum_result;

/* Bins of the spectrum wr_spectrum_analyze will return (nfft/2 + 1), or -1 for invalid n/desc. */
WRDEF int32_t wr_spectrum_bins(int32_t n, int periodic, const wr_spectrum_desc *desc);
/* Analyse x[0..n) sampled at spacing ds [m]; periodic = 1 for a closed curve (sample n would equal
 * sample 0). power (optional, capacity power_cap >= wr_spectrum_bins) receives |X_k|² of the detrended,
 * windowed, padded signal, unnormalised FFTW scaling (a tone of amplitude A centred on bin k gives
 * |X_k| = A·Σw/2). Errors: n < 8, ds <= 0 or non-finite, non-finite sample (item = index), bad desc,
 * empty band (WR_ERR_INVALID_ARG); no oscillation left after detrending (WR_ERR_DOMAIN); FFTW
 * planning failure (WR_ERR_BACKEND); WR_ERR_NOMEM. res is written only on success. The result does not
 * depend on the signal's scale (any finite amplitude; see WR__SP_SCALE_EXP), but power[] is returned
 * in the caller's units and so is inf / 0 where amp² itself is not a double (beyond ~1e±154). */
WRDEF wr_status wr_spectrum_analyze(const double *x, int32_t n, double ds, int periodic, const wr_spectrum_desc *desc,
                                    wr_spectrum_result *res, double *power, int32_t power_cap, wr_diag *diag);
/* The bare transform: power[k] = |X_k|², k = 0..nfft/2, of x[0..n) zero-padded to nfft >= n,
 * X_k = Σ x_j e^{−2πijk/nfft} (FFTW's unnormalised forward convention). Parseval:
 * Σ x_j² = (1/nfft)·(P_0 + 2 Σ_{0<k<nfft/2} P_k + [nfft even] P_{nfft/2}  (+ 2 P_{(nfft−1)/2} if odd)).
 * n >= 1, nfft >= n; non-finite x -> WR_ERR_INVALID_ARG. */
WRDEF wr_status wr_spectrum_rfft_power(const double *x, int32_t n, int32_t nfft, double *power, wr_diag *diag);

#ifdef __cplusplus
}
#endif
#endif /* WRINKLE_SPECTRUM_H */

/* ============================================================================================ */
#ifdef WRINKLE_IMPLEMENTATION
#ifndef WRINKLE_SPECTRUM_IMPLEMENTATION_DONE
#define WRINKLE_SPECTRUM_IMPLEMENTATION_DONE

#include <fftw3.h>
#include <float.h>
#include <math.h>
#include <string.h>

#ifdef __cplusplus
extern "C" {
#endif

#define WR__SP_PI 3.14159265358979323846
/* Largest grid side; bounds the grid at 2^24 cells whatever the mesh's aspect ratio. */
#define WR__PROBE_MAX_SIDE 4096
/* Relative slack added to a face's bounding box before it is binned: points within the barycentric
 * tolerance of an edge may sit a hair outside the exact box. */
#define WR__PROBE_BOX_SLACK 1e-9

/* Relative power below which a neighbouring bin counts as rounding noise in the peak fit. */
#define WR__SP_NOISE_FLOOR 1e-24
/* Default barycentric slack of the locator [1] (see wr_probe_desc): points within ~1e-9 of an edge
 * in barycentric units are inside, so probes along a shared edge never fall between two faces. */
#define WR__PROBE_DEFAULT_TOL 1e-9
/* Pivot threshold of the small trend+tone least-squares solve, relative to its largest diagonal [1]. */
#define WR__SP_SOLVE_PIVOT_REL 1e-12
/* Slack in bins [1] that keeps a band edge falling exactly on a bin inclusive despite rounding. */
#define WR__SP_BAND_EDGE_SLACK 1e-9
/* "Flat after detrending": amplitude below this fraction of max |x| [1] is rounding noise. */
#define WR__SP_FLAT_REL 1e-12
/* |X_k|² ~ (n·max|x|)² overflows past max|x| ~ 1e150 and underflows below ~1e-160: when max|x| lies
 * outside [2^-E, 2^E] the analysis runs on x·2^-e (e its binary exponent; exact) and scales the
 * amplitudes and the power array back. Inside the range nothing is scaled (results unchanged). */
#define WR__SP_SCALE_EXP 400

/* ---- probe ---- */
static void wr__probe_desc_defaults(const wr_probe_desc *in, wr_probe_desc *out) {
    if (in)
        *out = *in;
    else
        memset(out, 0, sizeof *out);
    if (out->cells_per_face == 0.0) out->cells_per_face = 1.0;
    if (out->tol == 0.0) out->tol = WR__PROBE_DEFAULT_TOL;
}

WRDEF void wr_probe_free(wr_probe *p) {
    if (!p) return;
    wr_free(p->face_uv);
    wr_free(p->cell_start);
    wr_free(p->cell_faces);
    memset(p, 0, sizeof *p);
}

static void wr__probe_cell_range(const wr_probe *p, const double *uv, int32_t *ix0, int32_t *ix1, int32_t *iy0,
                                 int32_t *iy1) {
    double xmin = uv[0], xmax = uv[0], ymin = uv[1], ymax = uv[1], pad;
    int k;
    for (k = 1; k < 3; ++k) {
        xmin = fmin(xmin, uv[2 * k]);
        xmax = fmax(xmax, uv[2 * k]);
        ymin = fmin(ymin, uv[2 * k + 1]);
        ymax = fmax(ymax, uv[2 * k + 1]);
    }
    pad = WR__PROBE_BOX_SLACK * p->h * (double)(p->gx > p->gy ? p->gx : p->gy) + 1e-12 * p->h;
    *ix0 = (int32_t)floor((xmin - pad - p->x0) / p->h);
    *ix1 = (int32_t)floor((xmax + pad - p->x0) / p->h);
    *iy0 = (int32_t)floor((ymin - pad - p->y0) / p->h);
    *iy1 = (int32_t)floor((ymax + pad - p->y0) / p->h);
    if (*ix0 < 0) *ix0 = 0;
    if (*iy0 < 0) *iy0 = 0;
    if (*ix1 > p->gx - 1) *ix1 = p->gx - 1;
    if (*iy1 > p->gy - 1) *iy1 = p->gy - 1;
}

WRDEF wr_status wr_probe_create(wr_probe *p, const wr_mesh *m, const wr_probe_desc *desc_in, wr_diag *diag) {
    wr_probe_desc desc;
    double xmin = HUGE_VAL, xmax = -HUGE_VAL, ymin = HUGE_VAL, ymax = -HUGE_VAL, w, hgt, cells;
    int32_t f, c, ncell, n_ok = 0, total = 0;
    memset(p, 0, sizeof *p);
    if (!m || m->nf < 1 || !m->faces) return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "probe: mesh has no faces");
    wr__probe_desc_defaults(desc_in, &desc);
    if (!(desc.cells_per_face > 0.0) || !isfinite(desc.cells_per_face))
        return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "probe: cells_per_face=%g must be > 0", desc.cells_per_face);
    if (!(desc.tol >= 0.0) || !(desc.tol < 0.5))
        return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "probe: tol=%g must be in [0, 0.5)", desc.tol);
    if (!m->rest && !m->corner_rest) {
        /* Without rest coordinates wr_mesh_face_rest flattens each non-planar face in its own frame,
         * so there is no common 2D domain to locate points in. A mesh lying in z = 0 is its own. */
        int32_t v;
        for (v = 0; v < m->nv; ++v)
            if (m->pos[3 * v + 2] != 0.0)
                return wr_fail(diag, WR_ERR_GEOMETRY, v,
                               "probe: mesh has no rest coordinates and vertex %d is off the z = 0 plane", (int)v);
    }
    p->mesh = m;
    p->tol = desc.tol;
    p->face_uv = (double *)wr_alloc_array((size_t)m->nf * 6u, sizeof(double));
    if (!p->face_uv) {
        wr_probe_free(p);
        return wr_fail(diag, WR_ERR_NOMEM, -1, "probe: out of memory for %d faces", (int)m->nf);
    }
    for (f = 0; f < m->nf; ++f) {
        double *uv = p->face_uv + 6 * (size_t)f;
        int k;
        wr_mesh_face_rest(m, f, uv);
        for (k = 0; k < 6; ++k)
            if (!isfinite(uv[k])) {
                wr_probe_free(p);
                return wr_fail(diag, WR_ERR_GEOMETRY, f, "probe: face %d has a non-finite rest coordinate", (int)f);
            }
        if (desc.face_mask && !desc.face_mask[f]) continue;
        if (wr_polygon_area(uv, 3) == 0.0) {
            ++p->n_degenerate;
            continue;
        }
        ++n_ok;
        for (k = 0; k < 3; ++k) {
            xmin = fmin(xmin, uv[2 * k]);
            xmax = fmax(xmax, uv[2 * k]);
            ymin = fmin(ymin, uv[2 * k + 1]);
            ymax = fmax(ymax, uv[2 * k + 1]);
        }
    }
    if (n_ok == 0) {
        wr_probe_free(p);
        return wr_fail(diag, WR_ERR_GEOMETRY, -1, "probe: all %d faces%s have zero rest area", (int)m->nf,
                       desc.face_mask ? " not masked out" : "");
    }
    w = xmax - xmin;
    hgt = ymax - ymin;
    /* Finite coordinates can still span more than DBL_MAX; no grid can cover that box. */
    if (!isfinite(w) || !isfinite(hgt)) {
        wr_probe_free(p);
        return wr_fail(diag, WR_ERR_GEOMETRY, -1, "probe: rest extent [%g, %g] x [%g, %g] m overflows a double", xmin,
                       xmax, ymin, ymax);
    }
    /* Cell size from the bounding-box area shared among cells_per_face·n_ok cells. */
    cells = desc.cells_per_face * (double)n_ok;
    p->h = sqrt(w * hgt / cells);
    if (!(p->h > 0.0)) p->h = fmax(w, hgt) / cells; /* never: a face with area has a 2D box */
    if (w / p->h > WR__PROBE_MAX_SIDE) p->h = w / WR__PROBE_MAX_SIDE;
    if (hgt / p->h > WR__PROBE_MAX_SIDE) p->h = hgt / WR__PROBE_MAX_SIDE;
    p->gx = (int32_t)ceil(w / p->h);
    p->gy = (int32_t)ceil(hgt / p->h);
    if (p->gx < 1) p->gx = 1;
    if (p->gy < 1) p->gy = 1;
    if (p->gx > WR__PROBE_MAX_SIDE) p->gx = WR__PROBE_MAX_SIDE;
    if (p->gy > WR__PROBE_MAX_SIDE) p->gy = WR__PROBE_MAX_SIDE;
    /* Make the grid cover the box exactly: cell size from the larger demand. */
    p->h = fmax(w / p->gx, hgt / p->gy);
    p->x0 = xmin;
    p->y0 = ymin;
    ncell = p->gx * p->gy;
    p->cell_start = (int32_t *)wr_calloc_array((size_t)ncell + 1u, sizeof(int32_t));
    if (!p->cell_start) {
        wr_probe_free(p);
        return wr_fail(diag, WR_ERR_NOMEM, -1, "probe: out of memory for %d cells", (int)ncell);
    }
    /* Two passes (count, fill) build the cell -> faces CSR. */
    for (f = 0; f < m->nf; ++f) {
        const double *uv = p->face_uv + 6 * (size_t)f;
        int32_t ix0, ix1, iy0, iy1, ix, iy;
        if ((desc.face_mask && !desc.face_mask[f]) || wr_polygon_area(uv, 3) == 0.0) continue;
        wr__probe_cell_range(p, uv, &ix0, &ix1, &iy0, &iy1);
        for (iy = iy0; iy <= iy1; ++iy)
            for (ix = ix0; ix <= ix1; ++ix) {
                if (total == INT32_MAX) {
                    wr_probe_free(p);
                    return wr_fail(diag, WR_ERR_OVERFLOW, f, "probe: too many face-cell entries");
                }
                ++p->cell_start[iy * p->gx + ix + 1];
                ++total;
            }
    }
    for (c = 0; c < ncell; ++c) p->cell_start[c + 1] += p->cell_start[c];
    p->cell_faces = (int32_t *)wr_alloc_array((size_t)total, sizeof(int32_t));
    if (!p->cell_faces) {
        wr_probe_free(p);
        return wr_fail(diag, WR_ERR_NOMEM, -1, "probe: out of memory for %d face-cell entries", (int)total);
    }
    {
        int32_t *fill = (int32_t *)wr_alloc_array((size_t)ncell, sizeof(int32_t));
        if (!fill) {
            wr_probe_free(p);
            return wr_fail(diag, WR_ERR_NOMEM, -1, "probe: out of memory");
        }
        memcpy(fill, p->cell_start, sizeof(int32_t) * (size_t)ncell);
        for (f = 0; f < m->nf; ++f) {
            const double *uv = p->face_uv + 6 * (size_t)f;
            int32_t ix0, ix1, iy0, iy1, ix, iy;
            if ((desc.face_mask && !desc.face_mask[f]) || wr_polygon_area(uv, 3) == 0.0) continue;
            wr__probe_cell_range(p, uv, &ix0, &ix1, &iy0, &iy1);
            for (iy = iy0; iy <= iy1; ++iy)
                for (ix = ix0; ix <= ix1; ++ix) p->cell_faces[fill[iy * p->gx + ix]++] = f;
        }
        wr_free(fill);
    }
    return WR_OK;
}

WRDEF int32_t wr_probe_locate(const wr_probe *p, double x, double y, double bary[3]) {
    double fx, fy, best = -HUGE_VAL, slack;
    int32_t ix, iy, c, j, best_f = -1;
    if (!p || !p->cell_start || !isfinite(x) || !isfinite(y)) return -1;
    fx = (x - p->x0) / p->h;
    fy = (y - p->y0) / p->h;
    /* Points a hair outside the box may still be within tol of a boundary edge. */
    slack = WR__PROBE_BOX_SLACK;
    if (fx < -slack || fy < -slack || fx > p->gx + slack || fy > p->gy + slack) return -1;
    ix = (int32_t)floor(fx);
    iy = (int32_t)floor(fy);
    if (ix < 0) ix = 0;
    if (iy < 0) iy = 0;
    if (ix > p->gx - 1) ix = p->gx - 1;
    if (iy > p->gy - 1) iy = p->gy - 1;
    c = iy * p->gx + ix;
    for (j = p->cell_start[c]; j < p->cell_start[c + 1]; ++j) {
        int32_t f = p->cell_faces[j];
        const double *uv = p->face_uv + 6 * (size_t)f;
        double a2 = 2.0 * wr_polygon_area(uv, 3), l[3], mn;
        /* Barycentric coordinate of corner k = signed area of (point, next two corners) / area. */
        l[0] = ((uv[2] - x) * (uv[5] - y) - (uv[4] - x) * (uv[3] - y)) / a2;
        l[1] = ((uv[4] - x) * (uv[1] - y) - (uv[0] - x) * (uv[5] - y)) / a2;
        l[2] = 1.0 - l[0] - l[1];
        mn = fmin(l[0], fmin(l[1], l[2]));
        if (mn > best) {
            best = mn;
            best_f = f;
            if (bary) {
                bary[0] = l[0];
                bary[1] = l[1];
                bary[2] = l[2];
            }
        }
    }
    if (best_f < 0 || best < -p->tol) return -1;
    return best_f;
}

/* ---- paths ---- */
WRDEF wr_status wr_path_segment(const double a[2], const double b[2], int32_t n, int closed, double *pts,
                                double *ds, wr_diag *diag) {
    double L, denom;
    int32_t i;
    if (n < 2) return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "path: n=%d points, need >= 2", (int)n);
    if (!isfinite(a[0]) || !isfinite(a[1]) || !isfinite(b[0]) || !isfinite(b[1]))
        return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "path: non-finite segment end");
    L = hypot(b[0] - a[0], b[1] - a[1]);
    if (!(L > 0.0)) return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "path: segment has zero length");
    if (!isfinite(L)) return wr_fail(diag, WR_ERR_DOMAIN, -1, "path: segment length overflows a double");
    denom = closed ? (double)n : (double)(n - 1);
    for (i = 0; i < n; ++i) {
        double t = (double)i / denom;
        pts[2 * i] = a[0] + t * (b[0] - a[0]);
        pts[2 * i + 1] = a[1] + t * (b[1] - a[1]);
    }
    if (!closed) { /* exact end point, no rounding drift */
        pts[2 * (n - 1)] = b[0];
        pts[2 * (n - 1) + 1] = b[1];
    }
    if (ds) *ds = L / denom;
    return WR_OK;
}

WRDEF wr_status wr_path_polyline(const double *verts, int32_t nv, int closed, int32_t n, double *pts, double *ds,
                                 double *length, wr_diag *diag) {
    double L = 0.0, step, acc = 0.0;
    int32_t nseg, s, i;
    if (nv < 2) return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "path: polyline has %d vertices, need >= 2", (int)nv);
    if (n < 2) return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "path: n=%d points, need >= 2", (int)n);
    for (i = 0; i < 2 * nv; ++i)
        if (!isfinite(verts[i])) return wr_fail(diag, WR_ERR_INVALID_ARG, i / 2, "path: vertex %d is not finite", (int)(i / 2));
    nseg = closed ? nv : nv - 1;
    for (s = 0; s < nseg; ++s) {
        int32_t t = (s + 1) % nv;
        L += hypot(verts[2 * t] - verts[2 * s], verts[2 * t + 1] - verts[2 * s + 1]);
    }
    if (!(L > 0.0)) return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "path: polyline has zero length");
    if (!isfinite(L)) return wr_fail(diag, WR_ERR_DOMAIN, -1, "path: polyline length overflows a double");
    step = closed ? L / n : L / (n - 1);
    /* Walk the segments once; sample i sits at arc length i·step. */
    s = 0;
    for (i = 0; i < n; ++i) {
        double target = (double)i * step, seg;
        int32_t t;
        for (;;) {
            t = (s + 1) % nv;
            seg = hypot(verts[2 * t] - verts[2 * s], verts[2 * t + 1] - verts[2 * s + 1]);
            if (target <= acc + seg || s == nseg - 1) break;
            acc += seg;
            ++s;
        }
        {
            double u = seg > 0.0 ? (target - acc) / seg : 0.0;
            if (u < 0.0) u = 0.0;
            if (u > 1.0) u = 1.0;
            pts[2 * i] = verts[2 * s] + u * (verts[2 * t] - verts[2 * s]);
            pts[2 * i + 1] = verts[2 * s + 1] + u * (verts[2 * t + 1] - verts[2 * s + 1]);
        }
    }
    if (!closed) {
        pts[2 * (n - 1)] = verts[2 * (nv - 1)];
        pts[2 * (n - 1) + 1] = verts[2 * (nv - 1) + 1];
    }
    if (ds) *ds = step;
    if (length) *length = L;
    return WR_OK;
}

WRDEF wr_status wr_path_circle(const double c[2], double r, int32_t n, double *pts, double *ds, wr_diag *diag) {
    int32_t i;
    if (n < 3) return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "path: circle with n=%d points, need >= 3", (int)n);
    if (!(r > 0.0) || !isfinite(r)) return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "path: circle radius r=%g", r);
    if (!isfinite(c[0]) || !isfinite(c[1])) return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "path: non-finite centre");
    /* the circumference and every point c ± r must be doubles */
    if (!isfinite(2.0 * WR__SP_PI * r) || !isfinite(fabs(c[0]) + r) || !isfinite(fabs(c[1]) + r))
        return wr_fail(diag, WR_ERR_DOMAIN, -1, "path: circle (%g, %g) r=%g overflows a double", c[0], c[1], r);
    for (i = 0; i < n; ++i) {
        double t = 2.0 * WR__SP_PI * (double)i / (double)n;
        pts[2 * i] = c[0] + r * cos(t);
        pts[2 * i + 1] = c[1] + r * sin(t);
    }
    if (ds) *ds = 2.0 * WR__SP_PI * r / (double)n;
    return WR_OK;
}

/* ---- sampling ---- */
static wr_status wr__probe_sample(const wr_probe *p, const double *field, const double *dir, const double *pts,
                                  int32_t n, double *out, int32_t *n_outside, wr_diag *diag) {
    int32_t i, nout = 0;
    double d[3] = {0.0, 0.0, 0.0};
    if (n_outside) *n_outside = 0;
    if (!p || !p->cell_start) return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "probe: not created");
    if (n < 1) return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "probe: n=%d points", (int)n);
    if (dir) {
        double nd = sqrt(dir[0] * dir[0] + dir[1] * dir[1] + dir[2] * dir[2]);
        if (!(nd > 0.0) || !isfinite(nd))
            return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "probe: direction (%g, %g, %g) is zero or not finite", dir[0],
                           dir[1], dir[2]);
        d[0] = dir[0] / nd;
        d[1] = dir[1] / nd;
        d[2] = dir[2] / nd;
    }
    for (i = 0; i < n; ++i) {
        double bary[3];
        int32_t f;
        if (!isfinite(pts[2 * i]) || !isfinite(pts[2 * i + 1]))
            return wr_fail(diag, WR_ERR_INVALID_ARG, i, "probe: point %d is not finite", (int)i);
        f = wr_probe_locate(p, pts[2 * i], pts[2 * i + 1], bary);
        if (f < 0) {
            out[i] = NAN;
            ++nout;
            continue;
        }
        {
            const int32_t *fv = p->mesh->faces + 3 * (size_t)f;
            double v = 0.0;
            int k;
            for (k = 0; k < 3; ++k) {
                double s;
                if (dir) {
                    const double *q = field + 3 * (size_t)fv[k];
                    s = q[0] * d[0] + q[1] * d[1] + q[2] * d[2];
                } else {
                    s = field[fv[k]];
                }
                v += bary[k] * s;
            }
            out[i] = v;
        }
    }
    if (n_outside) *n_outside = nout;
    if (nout == n) return wr_fail(diag, WR_ERR_GEOMETRY, -1, "probe: all %d points lie outside the mesh", (int)n);
    return WR_OK;
}

WRDEF wr_status wr_probe_sample(const wr_probe *p, const double *field, const double *pts, int32_t n, double *out,
                                int32_t *n_outside, wr_diag *diag) {
    return wr__probe_sample(p, field, NULL, pts, n, out, n_outside, diag);
}

WRDEF wr_status wr_probe_sample_dir(const wr_probe *p, const double *vec, const double dir[3], const double *pts,
                                    int32_t n, double *out, int32_t *n_outside, wr_diag *diag) {
    if (!dir) return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "probe: NULL direction");
    return wr__probe_sample(p, vec, dir, pts, n, out, n_outside, diag);
}

WRDEF int32_t wr_probe_longest_run(const double *z, int32_t n, int32_t *start) {
    int32_t i, best = 0, best_start = 0, cur = 0;
    for (i = 0; i < n; ++i) {
        if (isfinite(z[i])) {
            if (++cur > best) {
                best = cur;
                best_start = i - cur + 1;
            }
        } else {
            cur = 0;
        }
    }
    if (start) *start = best_start;
    return best;
}

/* ---- spectrum ---- */
static wr_status wr__spectrum_desc_defaults(const wr_spectrum_desc *in, int periodic, wr_spectrum_desc *out,
                                            wr_diag *diag) {
    if (in)
        *out = *in;
    else
        memset(out, 0, sizeof *out);
    if (out->detrend < 0 || out->detrend > WR_DETREND_QUADRATIC)
        return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "spectrum: unknown detrend %d", (int)out->detrend);
    if (out->window < 0 || out->window > WR_WINDOW_HANN)
        return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "spectrum: unknown window %d", (int)out->window);
    if (out->peak_fit < 0 || out->peak_fit > WR_PEAK_NONE)
        return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "spectrum: unknown peak_fit %d", (int)out->peak_fit);
    if (out->pad_factor < 0 || out->pad_factor > 64)
        return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "spectrum: pad_factor=%d not in 0..64", (int)out->pad_factor);
    if (!(out->min_wavelength >= 0.0) || !(out->max_wavelength >= 0.0))
        return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "spectrum: wavelength band [%g, %g] must be >= 0",
                       out->min_wavelength, out->max_wavelength);
    if (!(out->zc_smooth >= 0.0) || !(out->zc_hysteresis >= 0.0) || !(out->zc_hysteresis < 1.0) ||
        !isfinite(out->zc_smooth))
        return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "spectrum: zc_smooth=%g (>= 0) zc_hysteresis=%g (in [0,1))",
                       out->zc_smooth, out->zc_hysteresis);
    if (out->detrend == WR_DETREND_DEFAULT) out->detrend = periodic ? WR_DETREND_MEAN : WR_DETREND_LINEAR;
    if (out->window == WR_WINDOW_DEFAULT) out->window = periodic ? WR_WINDOW_NONE : WR_WINDOW_HANN;
    if (out->peak_fit == WR_PEAK_DEFAULT) out->peak_fit = WR_PEAK_GAUSSIAN;
    if (out->pad_factor == 0) out->pad_factor = 4;
    if (periodic) out->pad_factor = 1; /* padding would break the exact periodicity of a closed curve */
    if (out->zc_smooth == 0.0 && !out->has_zc_smooth) out->zc_smooth = 0.1;
    if (out->zc_hysteresis == 0.0 && !out->has_zc_hysteresis) out->zc_hysteresis = 0.3;
    return WR_OK;
}

WRDEF int32_t wr_spectrum_bins(int32_t n, int periodic, const wr_spectrum_desc *desc) {
    wr_spectrum_desc d;
    if (n < WR_SPECTRUM_MIN_SAMPLES) return -1;
    if (wr__spectrum_desc_defaults(desc, periodic, &d, NULL) != WR_OK) return -1;
    if ((int64_t)n * d.pad_factor > (int64_t)INT32_MAX / 2) return -1;
    return n * d.pad_factor / 2 + 1;
}

/* Least-squares removal of a polynomial of degree `deg` (0, 1, 2) in t ∈ [−1, 1]: Gram–Schmidt on the
 * sampled monomials gives an orthogonal basis, so each projection is a single dot product and the
 * result does not suffer from the ill-conditioning of the normal equations. */
static wr_status wr__detrend(double *y, int32_t n, int deg) {
    double *B;
    int j, k;
    int32_t i;
    if (deg < 0) return WR_OK;
    B = (double *)wr_alloc_array((size_t)n * 3u, sizeof(double));
    if (!B) return WR_ERR_NOMEM;
    for (j = 0; j <= deg; ++j) {
        double *b = B + (size_t)j * (size_t)n, nn = 0.0, c;
        for (i = 0; i < n; ++i) {
            double t = n > 1 ? 2.0 * (double)i / (double)(n - 1) - 1.0 : 0.0;
            b[i] = j == 0 ? 1.0 : (j == 1 ? t : t * t);
        }
        for (k = 0; k < j; ++k) { /* orthogonalise against the earlier (normalised) basis vectors */
            const double *q = B + (size_t)k * (size_t)n;
            double dot = 0.0;
            for (i = 0; i < n; ++i) dot += q[i] * b[i];
            for (i = 0; i < n; ++i) b[i] -= dot * q[i];
        }
        for (i = 0; i < n; ++i) nn += b[i] * b[i];
        nn = sqrt(nn);
        for (i = 0; i < n; ++i) b[i] /= nn;
        c = 0.0;
        for (i = 0; i < n; ++i) c += b[i] * y[i];
        for (i = 0; i < n; ++i) y[i] -= c * b[i];
    }
    wr_free(B);
    return WR_OK;
}

/* Solve the small dense system A z = b (m <= 5) by Gaussian elimination with partial pivoting.
 * Returns 0 when a pivot is below WR__SP_SOLVE_PIVOT_REL of the largest diagonal (singular). */
static int wr__small_solve(int m, double *A, double *b) {
    int i, j, k;
    double scale = 0.0;
    for (i = 0; i < m; ++i) scale = fmax(scale, fabs(A[i * m + i]));
    for (k = 0; k < m; ++k) {
        int piv = k;
        for (i = k + 1; i < m; ++i)
            if (fabs(A[i * m + k]) > fabs(A[piv * m + k])) piv = i;
        if (!(fabs(A[piv * m + k]) > WR__SP_SOLVE_PIVOT_REL * scale)) return 0;
        if (piv != k) {
            double t;
            for (j = 0; j < m; ++j) {
                t = A[k * m + j];
                A[k * m + j] = A[piv * m + j];
                A[piv * m + j] = t;
            }
            t = b[k];
            b[k] = b[piv];
            b[piv] = t;
        }
        for (i = k + 1; i < m; ++i) {
            double f = A[i * m + k] / A[k * m + k];
            for (j = k; j < m; ++j) A[i * m + j] -= f * A[k * m + j];
            b[i] -= f * b[k];
        }
    }
    for (k = m - 1; k >= 0; --k) {
        double s = b[k];
        for (j = k + 1; j < m; ++j) s -= A[k * m + j] * b[j];
        b[k] = s / A[k * m + k];
    }
    return 1;
}

/* Least-squares fit of x by {polynomial of degree deg in t ∈ [−1,1]} ∪ {cos, sin at fr cycles/sample}
 * (deg = −1: tone only). coef[0..m) receives the coefficients (polynomial first, then cos, sin),
 * *proj the explained sum of squares coefᵀΦᵀx (= Σx² − residual), so maximising *proj over fr is the
 * least-squares frequency. Returns m, or 0 when the normal equations are numerically singular. */
static int wr__ls_tone(const double *x, int32_t n, int deg, double fr, double coef[5], double *proj) {
    double A[25], rhs[5], phi[5];
    int m = deg + 1 + 2, j, k;
    int32_t i;
    memset(A, 0, sizeof A);
    memset(coef, 0, 5 * sizeof(double));
    for (i = 0; i < n; ++i) {
        double t = 2.0 * (double)i / (double)(n - 1) - 1.0, ph = 2.0 * WR__SP_PI * fr * (double)i;
        int q = 0;
        if (deg >= 0) phi[q++] = 1.0;
        if (deg >= 1) phi[q++] = t;
        if (deg >= 2) phi[q++] = t * t;
        phi[q++] = cos(ph);
        phi[q++] = sin(ph);
        for (j = 0; j < m; ++j) {
            for (k = 0; k < m; ++k) A[j * m + k] += phi[j] * phi[k];
            coef[j] += phi[j] * x[i];
        }
    }
    memcpy(rhs, coef, sizeof rhs);
    if (!wr__small_solve(m, A, coef)) return 0;
    *proj = 0.0;
    for (j = 0; j < m; ++j) *proj += coef[j] * rhs[j];
    return m;
}

/* Golden-section search for the least-squares tone frequency in [f_lo, f_hi] (cycles/sample), where
 * the explained sum of squares is unimodal for a clean peak (the interval is ±half an unpadded bin
 * around the FFT estimate). WR__SP_GOLDEN_ITERS shrinks the interval by 0.618^60 ≈ 3e-13. */
#define WR__SP_GOLDEN_ITERS 60
static double wr__ls_frequency(const double *x, int32_t n, int deg, double f_lo, double f_hi) {
    const double g = 0.6180339887498949;
    double a = f_lo, b = f_hi, c = b - g * (b - a), d = a + g * (b - a), pc = -HUGE_VAL, pd = -HUGE_VAL, coef[5];
    int it;
    if (!wr__ls_tone(x, n, deg, c, coef, &pc)) pc = -HUGE_VAL;
    if (!wr__ls_tone(x, n, deg, d, coef, &pd)) pd = -HUGE_VAL;
    for (it = 0; it < WR__SP_GOLDEN_ITERS; ++it) {
        if (pc >= pd) {
            b = d;
            d = c;
            pd = pc;
            c = b - g * (b - a);
            if (!wr__ls_tone(x, n, deg, c, coef, &pc)) pc = -HUGE_VAL;
        } else {
            a = c;
            c = d;
            pc = pd;
            d = a + g * (b - a);
            if (!wr__ls_tone(x, n, deg, d, coef, &pd)) pd = -HUGE_VAL;
        }
    }
    return 0.5 * (a + b);
}

/* y = x − (polynomial part of the joint fit at fr); *amp = the tone's amplitude. On a singular
 * system y is left as it was (the plain detrended signal) and *amp = 0. */
static void wr__trend_refit(const double *x, int32_t n, int deg, double fr, double *y, double *amp) {
    double coef[5], proj;
    int m = wr__ls_tone(x, n, deg, fr, coef, &proj);
    int32_t i;
    *amp = 0.0;
    if (!m) return;
    for (i = 0; i < n; ++i) {
        double t = 2.0 * (double)i / (double)(n - 1) - 1.0, trend = 0.0;
        if (deg >= 0) trend += coef[0];
        if (deg >= 1) trend += coef[1] * t;
        if (deg >= 2) trend += coef[2] * t * t;
        y[i] = x[i] - trend;
    }
    *amp = hypot(coef[m - 2], coef[m - 1]);
}

/* FFTW r2c of buf[0..nfft) into |X_k|², k = 0..nfft/2. buf may be modified. */
static wr_status wr__rfft_power(const double *x, int32_t n, int32_t nfft, double *power, wr_diag *diag) {
    double *in;
    fftw_complex *out;
    fftw_plan plan;
    int32_t k, nb = nfft / 2 + 1;
    in = (double *)fftw_malloc(sizeof(double) * (size_t)nfft);
    out = (fftw_complex *)fftw_malloc(sizeof(fftw_complex) * (size_t)nb);
    if (!in || !out) {
        if (in) fftw_free(in);
        if (out) fftw_free(out);
        return wr_fail(diag, WR_ERR_NOMEM, -1, "spectrum: fftw_malloc of %d samples failed", (int)nfft);
    }
    /* FFTW_ESTIMATE: heuristic plan, does not touch the arrays, reads/writes no wisdom. */
    plan = fftw_plan_dft_r2c_1d((int)nfft, in, out, FFTW_ESTIMATE);
    if (!plan) {
        fftw_free(in);
        fftw_free(out);
        return wr_fail(diag, WR_ERR_BACKEND, -1, "spectrum: FFTW could not plan an r2c transform of length %d",
                       (int)nfft);
    }
    memcpy(in, x, sizeof(double) * (size_t)n);
    for (k = n; k < nfft; ++k) in[k] = 0.0;
    fftw_execute(plan);
    {
        /* Read through a double* so the code is the same whether fftw_complex is double[2] or a
         * C99 _Complex double (when <complex.h> came first): both have this layout. */
        const double *o = (const double *)out;
        for (k = 0; k < nb; ++k) power[k] = o[2 * k] * o[2 * k] + o[2 * k + 1] * o[2 * k + 1];
    }
    fftw_destroy_plan(plan);
    fftw_free(in);
    fftw_free(out);
    return WR_OK;
}

WRDEF wr_status wr_spectrum_rfft_power(const double *x, int32_t n, int32_t nfft, double *power, wr_diag *diag) {
    int32_t i;
    if (n < 1 || nfft < n)
        return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "spectrum: n=%d, nfft=%d (need 1 <= n <= nfft)", (int)n, (int)nfft);
    for (i = 0; i < n; ++i)
        if (!isfinite(x[i])) return wr_fail(diag, WR_ERR_INVALID_ARG, i, "spectrum: sample %d is %g", (int)i, x[i]);
    return wr__rfft_power(x, n, nfft, power, diag);
}

/* Centred moving average of odd width m; periodic wraps, open shrinks the window at the ends. */
static void wr__moving_average(const double *y, int32_t n, int32_t m, int periodic, double *out) {
    int32_t i, j, h = m / 2;
    for (i = 0; i < n; ++i) {
        double s = 0.0;
        int32_t cnt = 0;
        for (j = i - h; j <= i + h; ++j) {
            int32_t jj = j;
            if (periodic) {
                jj = ((j % n) + n) % n;
            } else if (j < 0 || j >= n) {
                continue;
            }
            s += y[jj];
            ++cnt;
        }
        out[i] = s / (double)cnt;
    }
}

/* Schmitt-trigger zero crossings with thresholds ±thr. A crossing is located at the last sign change
 * of v before the trigger fires (linear interpolation, in samples). For closed curves the scan
 * continues around the loop back to where the state was first set, so the count is even. */
static int32_t wr__zero_crossings(const double *v, int32_t n, double thr, int periodic, double *first_pos,
                                  double *last_pos) {
    int state = 0;
    int32_t i, count = 0, first_set = -1, steps;
    double last_zero = 0.0;
    *first_pos = *last_pos = 0.0;
    steps = n;
    for (i = 0; i < steps; ++i) {
        int32_t ii = i % n, prev = (i - 1 + n) % n;
        double a = v[prev], b = v[ii];
        if (i > 0 || periodic) {
            if ((a < 0.0 && b >= 0.0) || (a > 0.0 && b <= 0.0)) last_zero = (double)i - 1.0 + a / (a - b);
        }
        if (b > thr && state != 1) {
            if (state == -1) {
                if (count == 0) *first_pos = last_zero;
                *last_pos = last_zero;
                ++count;
            }
            if (state == 0) first_set = i;
            state = 1;
        } else if (b < -thr && state != -1) {
            if (state == 1) {
                if (count == 0) *first_pos = last_zero;
                *last_pos = last_zero;
                ++count;
            }
            if (state == 0) first_set = i;
            state = -1;
        }
        if (periodic && i == n - 1 && first_set >= 0) steps = n + first_set + 1;
    }
    return count;
}

/* Half the peak-to-peak range of v: the (max − min)/2 amplitude. */
static double wr__sp_half_range(const double *v, int32_t n) {
    double lo = v[0], hi = v[0];
    int32_t i;
    for (i = 1; i < n; ++i) {
        lo = fmin(lo, v[i]);
        hi = fmax(hi, v[i]);
    }
    return 0.5 * (hi - lo);
}

/* The bins [k_min, k_max] of the wavelength band (default: 2 ds to the probe length). */
static wr_status wr__sp_band(const wr_spectrum_desc *desc, wr_spectrum_result *r, wr_diag *diag) {
    double lmin = desc->min_wavelength > 0.0 ? desc->min_wavelength : 2.0 * r->ds;
    double lmax = desc->max_wavelength > 0.0 ? desc->max_wavelength : r->length;
    double kmin_d, kmax_d;
    const int32_t nb = r->n_bins;
    if (!(lmin < lmax))
        return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "spectrum: min_wavelength %g >= max_wavelength %g", lmin, lmax);
    /* bin k <-> wavelength nfft·ds/k; the slack keeps a band edge that falls on a bin inclusive */
    kmin_d = ceil((double)r->nfft * r->ds / lmax - WR__SP_BAND_EDGE_SLACK);
    kmax_d = floor((double)r->nfft * r->ds / lmin + WR__SP_BAND_EDGE_SLACK);
    r->k_min = kmin_d < 1.0 ? 1 : (int32_t)fmin(kmin_d, (double)nb);
    r->k_max = kmax_d > (double)(nb - 1) ? nb - 1 : (int32_t)kmax_d;
    if (r->k_min > r->k_max)
        return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "spectrum: band [%g, %g] m holds no frequency bin (ds=%g, n=%d)", lmin,
                       lmax, r->ds, (int)r->n);
    return WR_OK;
}

/* The power-of-two exponent e by which x is analysed as x·2^-e (0 when |x| needs no scaling; see
 * WR__SP_SCALE_EXP). */
static int wr__sp_scale_exponent(const double *x, int32_t n) {
    double xmax_abs = 0.0;
    int32_t i;
    int e = 0;
    for (i = 0; i < n; ++i) xmax_abs = fmax(xmax_abs, fabs(x[i]));
    if (xmax_abs > 0.0) {
        (void)frexp(xmax_abs, &e);
        if (e >= -WR__SP_SCALE_EXP && e <= WR__SP_SCALE_EXP) e = 0;
    }
    return e;
}

/* The fractional offset of the true peak from bin kp: a parabola through the peak and its two
 * neighbours (in log power for WR_PEAK_GAUSSIAN, in magnitude for WR_PEAK_QUADRATIC), within ±1. */
static double wr__sp_peak_offset(const double *pw, int32_t kp, int32_t nb, int32_t fit) {
    double a, b, c, den, off = 0.0;
    if (fit == WR_PEAK_NONE || kp < 1 || kp + 1 >= nb) return 0.0;
    if (fit == WR_PEAK_GAUSSIAN) {
        /* Parabola through log power: δ = ½(a−c)/(a−2b+c). Neighbours below 1e-24 of the peak
         * power (1e-12 in magnitude) are FFT rounding noise (a tone exactly on a bin of a
         * closed curve, whose true neighbours are 0): they are floored to the same value so
         * the noise cannot tilt the parabola; then δ = 0. */
        double fl = pw[kp] * WR__SP_NOISE_FLOOR + DBL_MIN;
        a = log(fmax(pw[kp - 1], fl));
        b = log(fmax(pw[kp], fl));
        c = log(fmax(pw[kp + 1], fl));
    } else {
        a = sqrt(pw[kp - 1]);
        b = sqrt(pw[kp]);
        c = sqrt(pw[kp + 1]);
    }
    den = a - 2.0 * b + c;
    if (den < 0.0) off = 0.5 * (a - c) / den;
    if (off > 1.0) off = 1.0;
    if (off < -1.0) off = -1.0;
    return off;
}

/* The dominant bin in the band, its refined frequency, the wavelength and count it gives, the share
 * of the non-DC power its lobe holds, and the tone's amplitude by a direct DFT of the windowed
 * signal yw at the refined frequency (no scalloping loss). */
static wr_status wr__sp_peak(const double *pw, const double *yw, const wr_spectrum_desc *desc, wr_spectrum_result *r,
                             wr_diag *diag) {
    const int32_t nb = r->n_bins, n = r->n;
    double total = 0.0, band = 0.0, fr, re = 0.0, im = 0.0;
    int32_t k, kp, hw, lo, hi, i;
    r->peak_bin = r->k_min;
    for (k = r->k_min; k <= r->k_max; ++k)
        if (pw[k] > pw[r->peak_bin]) r->peak_bin = k;
    for (k = 1; k < nb; ++k) total += pw[k];
    if (!(pw[r->peak_bin] > 0.0)) return wr_fail(diag, WR_ERR_DOMAIN, -1, "spectrum: no power inside the wavelength band");
    kp = r->peak_bin;
    if ((kp == r->k_min && kp - 1 >= 1 && pw[kp - 1] > pw[kp]) || (kp == r->k_max && kp + 1 < nb && pw[kp + 1] > pw[kp]))
        r->peak_at_band_edge = 1;
    r->peak_offset = wr__sp_peak_offset(pw, kp, nb, desc->peak_fit);
    r->wavenumber = ((double)kp + r->peak_offset) / ((double)r->nfft * r->ds);
    r->wavelength = 1.0 / r->wavenumber;
    r->count = r->length / r->wavelength;
    r->count_rounded = r->periodic ? kp : (int32_t)floor(r->count + 0.5);
    hw = 2 * desc->pad_factor, lo = kp - hw < 1 ? 1 : kp - hw, hi = kp + hw > nb - 1 ? nb - 1 : kp + hw;
    for (k = lo; k <= hi; ++k) band += pw[k];
    r->peak_power_fraction = total > 0.0 ? band / total : 0.0;
    fr = ((double)kp + r->peak_offset) / (double)r->nfft;
    for (i = 0; i < n; ++i) {
        double ph = 2.0 * WR__SP_PI * fr * (double)i;
        re += yw[i] * cos(ph);
        im -= yw[i] * sin(ph);
    }
    r->amplitude_spectral = 2.0 * sqrt(re * re + im * im) / r->window_sum;
    return WR_OK;
}

/* Zero crossings of the detrended (not windowed) signal y, smoothed over desc->zc_smooth
 * wavelengths (an odd window, sm is its n-sample scratch), with a Schmitt trigger at
 * desc->zc_hysteresis of the smoothed half range. */
static void wr__sp_zero_crossing_stage(const double *y, const wr_spectrum_desc *desc, wr_spectrum_result *r, double *sm) {
    const int32_t n = r->n;
    int32_t m = (int32_t)floor(desc->zc_smooth * r->wavelength / r->ds + 0.5);
    double thr, p0, p1;
    if (m < 2) m = 1;
    if (m % 2 == 0) ++m;
    if (m > n) m = (n % 2) ? n : n - 1;
    r->zc_smooth_samples = m;
    if (m > 1)
        wr__moving_average(y, n, m, r->periodic, sm);
    else
        memcpy(sm, y, sizeof(double) * (size_t)n);
    thr = desc->zc_hysteresis * wr__sp_half_range(sm, n);
    r->n_zero_crossings = wr__zero_crossings(sm, n, thr, r->periodic, &p0, &p1);
    r->zc_waves = 0.5 * (double)r->n_zero_crossings;
    if (r->periodic)
        r->zc_wavelength = r->n_zero_crossings > 0 ? r->length / r->zc_waves : 0.0;
    else
        r->zc_wavelength = r->n_zero_crossings > 1 ? 2.0 * (p1 - p0) * r->ds / (double)(r->n_zero_crossings - 1) : 0.0;
}

/* Checks the arguments and fills the result's geometry (n, length, nfft, bins, band); r arrives zeroed. */
static wr_status wr__sp_setup(const double *x, int32_t n, double ds, int periodic, const wr_spectrum_desc *desc_in,
                              wr_spectrum_desc *desc, wr_spectrum_result *r, int32_t power_cap, int want_power,
                              wr_diag *diag) {
    wr_status st;
    int32_t i;
    if (n < WR_SPECTRUM_MIN_SAMPLES)
        return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "spectrum: n=%d samples, need >= %d", (int)n,
                       WR_SPECTRUM_MIN_SAMPLES);
    if (!(ds > 0.0) || !isfinite(ds)) return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "spectrum: spacing ds=%g must be > 0", ds);
    for (i = 0; i < n; ++i)
        if (!isfinite(x[i]))
            return wr_fail(diag, WR_ERR_INVALID_ARG, i, "spectrum: sample %d is %g (outside the mesh?)", (int)i, x[i]);
    st = wr__spectrum_desc_defaults(desc_in, periodic, desc, diag);
    if (st != WR_OK) return st;
    if ((int64_t)n * desc->pad_factor > (int64_t)INT32_MAX / 2)
        return wr_fail(diag, WR_ERR_OVERFLOW, -1, "spectrum: n=%d × pad_factor=%d too large", (int)n, (int)desc->pad_factor);
    r->n = n;
    r->periodic = periodic ? 1 : 0;
    r->ds = ds;
    r->length = periodic ? (double)n * ds : (double)(n - 1) * ds;
    r->nfft = n * desc->pad_factor;
    r->n_bins = r->nfft / 2 + 1;
    if (want_power && power_cap < r->n_bins)
        return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "spectrum: power capacity %d < %d bins", (int)power_cap, (int)r->n_bins);
    return wr__sp_band(desc, r, diag);
}

WRDEF wr_status wr_spectrum_analyze(const double *x, int32_t n, double ds, int periodic, const wr_spectrum_desc *desc_in,
                                    wr_spectrum_result *res_out, double *power, int32_t power_cap, wr_diag *diag) {
    wr_spectrum_desc desc;
    wr_spectrum_result r;
    wr_status st;
    double *y = NULL, *yw = NULL, *pw = NULL, *sm = NULL, *xsc = NULL, xs = 0.0;
    int32_t i, k, nb, deg;
    int scale_e;
    if (!x || !res_out) return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "spectrum: NULL signal or result");
    memset(&r, 0, sizeof r);
    st = wr__sp_setup(x, n, ds, periodic, desc_in, &desc, &r, power_cap, power != NULL, diag);
    if (st != WR_OK) return st;
    nb = r.n_bins;
    y = (double *)wr_alloc_array((size_t)n, sizeof(double));
    yw = (double *)wr_alloc_array((size_t)n, sizeof(double));
    sm = (double *)wr_alloc_array((size_t)n, sizeof(double));
    pw = (double *)wr_alloc_array((size_t)nb, sizeof(double));
    if (!y || !yw || !sm || !pw) {
        st = wr_fail(diag, WR_ERR_NOMEM, -1, "spectrum: out of memory for n=%d", (int)n);
        goto done;
    }
    scale_e = wr__sp_scale_exponent(x, n);
    if (scale_e != 0) { /* see WR__SP_SCALE_EXP: analyse x·2^-e, x itself is not modified */
        xsc = (double *)wr_alloc_array((size_t)n, sizeof(double));
        if (!xsc) {
            st = wr_fail(diag, WR_ERR_NOMEM, -1, "spectrum: out of memory for n=%d", (int)n);
            goto done;
        }
        for (i = 0; i < n; ++i) xsc[i] = ldexp(x[i], -scale_e);
        x = xsc;
    }
    /* 1. detrend */
    memcpy(y, x, sizeof(double) * (size_t)n);
    deg = desc.detrend == WR_DETREND_NONE ? -1
                                          : (desc.detrend == WR_DETREND_MEAN ? 0 : (desc.detrend == WR_DETREND_LINEAR ? 1 : 2));
    if (wr__detrend(y, n, deg) != WR_OK) {
        st = wr_fail(diag, WR_ERR_NOMEM, -1, "spectrum: out of memory for detrending");
        goto done;
    }
    /* "No oscillation": what is left after detrending is rounding noise of the input's size. */
    r.amplitude_p2p = wr__sp_half_range(y, n);
    for (i = 0; i < n; ++i) xs = fmax(xs, fabs(x[i]));
    if (!(r.amplitude_p2p > WR__SP_FLAT_REL * xs) || r.amplitude_p2p == 0.0) {
        st = wr_fail(diag, WR_ERR_DOMAIN, -1, "spectrum: signal is flat after detrending (amplitude %g)",
                     ldexp(r.amplitude_p2p, scale_e));
        goto done;
    }
    /* 2. window (symmetric Hann: zero at both ends of an open probe) and zero-padded power spectrum */
    r.window_sum = 0.0;
    for (i = 0; i < n; ++i) {
        double w = desc.window == WR_WINDOW_HANN ? 0.5 - 0.5 * cos(2.0 * WR__SP_PI * (double)i / (double)(n - 1)) : 1.0;
        yw[i] = y[i] * w;
        r.window_sum += w;
    }
    st = wr__rfft_power(yw, n, r.nfft, pw, diag);
    if (st != WR_OK) goto done;
    /* 3. the peak in the band */
    st = wr__sp_peak(pw, yw, &desc, &r, diag);
    if (st != WR_OK) goto done;
    /* 4. Least-squares frequency of the joint model {trend polynomial, cos, sin}, searched within ±half
     * an unpadded bin of the FFT estimate f*: window-free, so it stays accurate on probes holding only
     * 2–3 waves, where the FFT peak is pulled by its own negative-frequency image (measured: 8 % at
     * 2 periods). Then the joint refit at that frequency: plain detrending removes the part of a sine
     * with a non-integer number of periods that correlates with the line / parabola, which biased
     * (max−min)/2 by up to ~16 % at 3 periods (measured); fitting the trend together with the tone
     * removes only the true trend. The tone's LS amplitude is amplitude_fit. If the small system is
     * singular, y stays the plain detrended signal. Cost: ~62 fits of O(25 N) each. */
    {
        double f0 = ((double)r.peak_bin + r.peak_offset) / (double)r.nfft, half = 0.5 / (double)n;
        double fls = wr__ls_frequency(x, n, deg, fmax(f0 - half, 0.25 / (double)n), fmin(f0 + half, 0.5));
        r.wavelength_ls = ds / fls;
        r.count_ls = r.length / r.wavelength_ls;
        wr__trend_refit(x, n, deg, fls, y, &r.amplitude_fit);
    }
    r.amplitude_p2p = wr__sp_half_range(y, n);
    /* 5. zero crossings */
    wr__sp_zero_crossing_stage(y, &desc, &r, sm);
    if (scale_e != 0) { /* back to the caller's units (power may over/underflow there: its own range) */
        r.amplitude_p2p = ldexp(r.amplitude_p2p, scale_e);
        r.amplitude_spectral = ldexp(r.amplitude_spectral, scale_e);
        r.amplitude_fit = ldexp(r.amplitude_fit, scale_e);
        for (k = 0; k < nb; ++k) pw[k] = ldexp(pw[k], 2 * scale_e);
    }
    if (power) memcpy(power, pw, sizeof(double) * (size_t)nb);
    *res_out = r;
    st = WR_OK;
done:
    wr_free(xsc);
    wr_free(y);
    wr_free(yw);
    wr_free(sm);
    wr_free(pw);
    return st;
}

#ifdef __cplusplus
}
#endif
#endif /* WRINKLE_SPECTRUM_IMPLEMENTATION_DONE */
#endif /* WRINKLE_IMPLEMENTATION */
