/* validate_curtain — Style3D Fig. 17 / 18d: a hanging curtain whose top edge is gathered into a short
 * wavelength λ0; below it the wrinkles coarsen with depth (Vandeparre et al. 2011 wrinklons). We measure
 * the depth over which the wrinkles go from λ0 to 2λ0 and compare it with both wrinklon forms of
 * Style3D Sec. 4.2.1 (transition.h, unit prefactor, as the paper writes them):
 *   tension form      L_w = λ0² sqrt(T/B)            (heavy curtain: gravity tension T dominates)
 *   compression form  L_w = λ0^{3/2} (δ/h²)^{1/4}    (light curtain: membrane stretching dominates)
 * for three bending stiffnesses, plus one run at 4× the areal density (the tension form doubles, the
 * compression form does not change) to tell which regime the simulated curtain is in, and one
 * tension-dominated curtain (H = 200 mm, ρ_A = 2.5 kg/m², T = 4.9 N/m) inside the tension form's regime.
 *
 * WHICH FORM APPLIES (our re-derivation of Vandeparre et al.'s energy balance; the Style3D text only
 * gives the two results). A wrinklon of length L, width λ and amplitude A ~ λ sqrt(δ) costs bending
 * u_b ~ B A²/λ⁴ per area and stretching of the material lines tilted by A/L: u_s ~ T (A/L)² when the
 * hanging weight's tension dominates (heavy), u_s ~ E h (A/L)⁴ when the sheet's own stretching does
 * (light). Minimising (u_s + u_b) L λ over L gives the two forms. Heavy applies when T ≫ E h (A/L)²,
 * i.e. T/(E h) ≫ (A/L)²; the table prints both sides. With a fabric-like E = 1 MPa they are comparable
 * here, so the density run decides.
 *
 * SETUP (stated in the result file). Rest sheet W × H in the z = 0 plane, y up, top edge y = H; gravity
 * (0, −g, 0) in the plane, so the curtain hangs in its own plane. The top edge is prescribed (scene
 * "wave" + "stretch" motion): x → W/2 + (1 − δ)(x − W/2), z = A sin(2π x/λ0), with the gather ratio δ and
 * A = λ0 √δ / π, so the sine's arc length ≈ (1 + (A k)²/4)(1 − δ) ≈ the rest width (an inextensible
 * gather, k = 2π/λ0). The sides and the bottom are free (--sides holds the side edges at the gathered
 * width instead). W = 12 λ0 (whole waves, zero displacement at the corners). Tension: the weight hanging
 * below the top edge, T = ρ_A g H (the largest tension, at the top where the transition starts; it is
 * ρ_A g (H − x) at depth x). Material: E = 1 MPa, ν = 0.3, ρ_A = 0.15 kg/m², h from Kirchhoff–Love per B.
 * Mesh: regular union-jack grid at resolution r (λ0/r cells per imposed wave). StVK + mid-edge
 * bending, gravity and the gather ramped over load steps, 1 µm seeded normal kick, hybrid
 * projected→exact Newton, CHOLMOD.
 *
 * MEASUREMENT. Horizontal probe lines every r/2 in depth, x ∈ [λ0/2, W − λ0/2] (half a wave clear of
 * the free sides), sampling the out-of-plane displacement z. The measured transition distance is the
 * first depth where the wavelength one sees — 2 × probe length / sign changes of z minus its
 * least-squares cubic (the cubic takes the sheet-scale bow; a sign change counts once |z| leaves a
 * ±5 % band) — reaches 2λ0. Cross-checks from a least-squares fit of {cubic, sin/cos(2πx/λ0),
 * sin/cos(πx/λ0)}: the depth where the λ0 amplitude a1 has halved, where the 2λ0 amplitude a2
 * overtakes a1, and where a2 is largest (the 2λ0 wrinkle fully formed, when there is a 2λ0 stage);
 * and the old metric, the first depth where the FFT peak wavelength reaches 2λ0 — which turned out to
 * be the jump of the peak from the λ0 bin to the sheet-scale bow (λ ≈ 30–50 mm), not a 2λ0 wrinkle.
 * Pass (issue 5): |L_measured − L_w| ≤ 25 % of L_w for each stiffness, checked against both forms.
 * Columns (issue 20): the forms' values are computed, not printed by Style3D, so they stand in the
 * "reference" column with the formula as source; "paper" holds only Fig. 18d's 26.7 / 25 mm.
 * Options: --res R [m] (default λ0/8), --quick (coarser grid, one stiffness; smoke only), experiment
 * switches --B, --waves, --sides, --young, --rho, --height, --dump FILE (z grid).
 * Exit = failed quantities, 2 on errors.
 */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"
#include "scene.h"
#include "vresult.h"

#define PI 3.14159265358979323846
#define LAMBDA0 0.010   /* imposed wavelength [m] */
#define NWAVES 12       /* W = NWAVES λ0 (6 left the 2λ0 fit dominated by the sheet-scale bow) */
#define HEIGHT 0.080    /* [m] (default; --height) */
#define GATHER 0.04     /* δ: relative shortening of the top edge */
#define RHO_A 0.15      /* kg/m² (default; --rho) */
#define YOUNG 1.0e6
#define POISSON 0.3
#define GRAV 9.81
#define AMP_FLOOR 0.01  /* wrinkles "present" while the probe amplitude is ≥ 1 % of A */
#define NB 3
#define HEAVY_HEIGHT 0.200 /* [m] tension-dominated run (see main) */
#define HEAVY_RHO 2.5      /* kg/m² */

/* experiment switches (command line) */
static int g_nwaves = NWAVES;    /* --waves N: W = N λ0 */
static double g_height = HEIGHT; /* --height M */
static double g_young = YOUNG;   /* --young PA */
static double g_rho = RHO_A;     /* --rho KG_M2: areal density (T = ρ_A g H scales with it) */
static int g_sides = 0;          /* --sides: side edges held at the gathered width (roller-like clamp) */
static const char *g_dump = NULL; /* --dump FILE: z on a depth × x grid */

typedef struct curtain_row {
    double B, rho, T, h, Lw_pred, Lw_comp, Lw_amp, L_zc, L_a1half, L_fft, L_mid, L_end, a2_end, a1_end, t_solve;
    int32_t nv, newton, nd;
    wr_status st;
    double depth[512], lambda[512], amp[512];
    double a1[512], a2[512], lzc[512]; /* λ0-mode and 2λ0-mode amplitudes [m], zero-crossing wavelength [m] */
} curtain_row;

/* Least-squares fit of z(x) on a probe to {1, ξ, ξ², ξ³, sin/cos(k0 x), sin/cos(k0 x / 2)} (ξ the
 * probe coordinate scaled to [−1, 1]): the cubic takes the curtain's global sag/bow (the long-wave
 * shape the FFT peak jumps to), the two Fourier pairs measure the imposed λ0 wrinkles and the
 * period-doubled 2λ0 wrinkles separately. a1, a2 = half peak-to-peak amplitudes of the two pairs. */
#define NMODE 8
static int modal_fit(const double *x, const double *z, int32_t n, double k0, double *a1, double *a2, double *resid) {
    double M[NMODE][NMODE + 1], phi[NMODE], x0 = x[0], x1 = x[n - 1];
    int32_t i, j, k, r;
    memset(M, 0, sizeof M);
    for (i = 0; i < n; ++i) {
        double xi = (2.0 * x[i] - x0 - x1) / (x1 - x0);
        phi[0] = 1.0, phi[1] = xi, phi[2] = xi * xi, phi[3] = xi * xi * xi;
        phi[4] = sin(k0 * x[i]), phi[5] = cos(k0 * x[i]), phi[6] = sin(0.5 * k0 * x[i]), phi[7] = cos(0.5 * k0 * x[i]);
        for (j = 0; j < NMODE; ++j) {
            for (k = 0; k < NMODE; ++k) M[j][k] += phi[j] * phi[k];
            M[j][NMODE] += phi[j] * z[i];
        }
    }
    for (k = 0; k < NMODE; ++k) { /* Gaussian elimination, partial pivoting */
        int32_t piv = k;
        for (r = k + 1; r < NMODE; ++r)
            if (fabs(M[r][k]) > fabs(M[piv][k])) piv = r;
        if (!(fabs(M[piv][k]) > 0.0)) return -1;
        if (piv != k)
            for (j = 0; j <= NMODE; ++j) {
                double t = M[k][j];
                M[k][j] = M[piv][j], M[piv][j] = t;
            }
        for (r = k + 1; r < NMODE; ++r) {
            double f = M[r][k] / M[k][k];
            for (j = k; j <= NMODE; ++j) M[r][j] -= f * M[k][j];
        }
    }
    for (k = NMODE - 1; k >= 0; --k) {
        for (j = k + 1; j < NMODE; ++j) M[k][NMODE] -= M[k][j] * M[j][NMODE];
        M[k][NMODE] /= M[k][k];
    }
    *a1 = hypot(M[4][NMODE], M[5][NMODE]);
    *a2 = hypot(M[6][NMODE], M[7][NMODE]);
    if (resid) /* z minus the cubic: the wrinkles alone, for the zero-crossing count */
        for (i = 0; i < n; ++i) {
            double xi = (2.0 * x[i] - x0 - x1) / (x1 - x0);
            resid[i] = z[i] - (M[0][NMODE] + xi * (M[1][NMODE] + xi * (M[2][NMODE] + xi * M[3][NMODE])));
        }
    return 0;
}

/* Mean wavelength from sign changes of the detrended signal: 2 × length / crossings. A sign change
 * only counts once the signal has left a ±5 % band of its peak (noise near zero does not count). */
static double zero_cross_wavelength(const double *v, int32_t n, double length) {
    double vmax = 0.0, band;
    int32_t i, nc = 0, sgn = 0;
    for (i = 0; i < n; ++i) vmax = fmax(vmax, fabs(v[i]));
    band = 0.05 * vmax;
    if (!(vmax > 0.0)) return NAN;
    for (i = 0; i < n; ++i) {
        int32_t s = v[i] > band ? 1 : v[i] < -band ? -1 : 0;
        if (s && sgn && s != sgn) ++nc;
        if (s) sgn = s;
    }
    return nc > 0 ? 2.0 * length / nc : NAN;
}

static void progress(void *user, int32_t step, int32_t n, const wr_statics_stats *st) {
    (void)user;
    wr_cli_progress("   step %d/%d Newton %3d |g|/ref %.1e %.1f s", (int)step, (int)n, (int)st->iterations,
            st->grad_ref > 0 ? st->grad_norm / st->grad_ref : 0.0, st->t_total);
}

/* The curtain's scene (docs/scene-format.md): a W × height sheet gathered at the top by a clamp
 * that compresses it by GATHER and imposes the λ0 wave, gravity along -y, optional side clamps. */
static int curtain_scene(double B, double r, int load_steps, wr_scene *sc) {
    char json[8192], sides[1024] = "";
    const double W = g_nwaves * LAMBDA0, A = LAMBDA0 * sqrt(GATHER) / PI;
    wr_diag d;
    if (g_sides)
        snprintf(sides, sizeof sides,
                 ", {\"name\": \"sides\", \"box\": {\"min\": [-1, -1, -1], \"max\": [%.17g, 1, 1]},"
                 " \"center\": [%.17g, 0, 0], \"stretch\": [%.17g, 1, 1]},"
                 " {\"name\": \"sides2\", \"box\": {\"min\": [%.17g, -1, -1], \"max\": [1, 1, 1]},"
                 " \"center\": [%.17g, 0, 0], \"stretch\": [%.17g, 1, 1]}",
                 1e-6 * r, 0.5 * W, 1.0 - GATHER, W - 1e-6 * r, 0.5 * W, 1.0 - GATHER);
    snprintf(json, sizeof json,
             "{\"name\": \"curtain\","
             " \"mesh\": {\"type\": \"rectangle\", \"width\": %.17g, \"height\": %.17g, \"resolution\": %.17g},"
             " \"material\": {\"young\": %.17g, \"poisson\": %.17g, \"bending_stiffness\": %.17g, \"areal_density\": %.17g},"
             " \"energy\": {\"membrane\": \"stvk\", \"bending\": \"midedge\"},"
             " \"gravity\": [0, %.17g, 0],"
             " \"boundary\": [{\"name\": \"top\", \"box\": {\"min\": [-1, %.17g, -1], \"max\": [1, 1, 1]},"
             "   \"center\": [%.17g, %.17g, 0], \"stretch\": [%.17g, 1, 1],"
             "   \"wave\": {\"amplitude\": %.17g, \"wavelength\": %.17g, \"phase\": 0, \"along\": [1, 0, 0], \"dir\": [0, 0, 1]}}%s],"
             " \"solver\": {\"linear\": \"cholmod\", \"load_steps\": %d, \"perturb\": 1e-6, \"seed\": 3, \"hessian\": \"hybrid\","
             "   \"grad_tol\": 1e-8, \"max_iter\": 300}}",
             W, g_height, r, g_young, POISSON, B, g_rho, -GRAV, g_height - 1e-6 * r, 0.5 * W, g_height, 1.0 - GATHER, A, LAMBDA0,
             sides, load_steps);
    if (wr_scene_parse(sc, json, strlen(json), NULL, &d) != WR_OK) {
        fprintf(stderr, "validate_curtain: %s\n", d.message);
        return 0;
    }
    return 1;
}

/* The wrinklon sizes the formulas predict for this row: the tension form (the hanging weight's
 * tension T at the top), the compression form with h as the scene derives it (Kirchhoff–Love), and
 * Vandeparre et al.'s light-curtain law before A ~ λ sqrt(δ) is substituted: L ~ λ (A/h)^{1/2}, with
 * the gather's exact amplitude A = λ0 sqrt(δ)/π (the compression form is this times sqrt(π)). */
static int curtain_predictions(double B, curtain_row *R) {
    const double A = LAMBDA0 * sqrt(GATHER) / PI;
    wr_diag d;
    R->B = B;
    R->T = g_rho * GRAV * g_height;
    if (wr_wrinklon_size_tension(LAMBDA0, R->T, B, &R->Lw_pred, &d) != WR_OK) return 0;
    R->h = cbrt(12.0 * (1.0 - POISSON * POISSON) * B / g_young);
    if (wr_wrinklon_size_compression(LAMBDA0, GATHER, R->h, &R->Lw_comp, &d) != WR_OK) return 0;
    R->Lw_amp = LAMBDA0 * sqrt(A / R->h);
    return 1;
}

/* Horizontal probes every r/2 down the curtain: the out-of-plane displacement's FFT wavelength and
 * amplitude, the modal λ0 and 2λ0 amplitudes and the crest-count wavelength of what the cubic leaves;
 * written to datpath (and every 8th sample to --dump). 0 when the probe cannot be built. */
static int curtain_probes(const wr_mesh *m, const double *u, double r, curtain_row *R, const char *datpath) {
    const double W = g_nwaves * LAMBDA0, dd = 0.5 * r, dir[3] = {0.0, 0.0, 1.0};
    const int32_t ns = 512;
    double pts[2 * 1024], vals[1024], xs[1024], resid[1024], ds, a[2], b[2];
    wr_probe pr;
    wr_afile f;
    wr_diag d;
    FILE *dump;
    int32_t k, j;
    int have_f;
    if (wr_probe_create(&pr, m, NULL, &d) != WR_OK) return 0;
    have_f = wr_afile_open(&f, datpath, &d) == WR_OK;
    dump = g_dump ? fopen(g_dump, "w") : NULL;
    if (have_f)
        fprintf(f.fp, "# depth[mm] lambda_fft[mm] amplitude_p2p[mm] a_lambda0[mm] a_2lambda0[mm] lambda_zc[mm]  (B = %g N m)\n", R->B);
    for (k = 1; k * dd < g_height - r && R->nd < 512; ++k) {
        double depth = k * dd, a1 = NAN, a2 = NAN;
        wr_spectrum_result res;
        int32_t nout = 0;
        a[0] = 0.5 * LAMBDA0, a[1] = g_height - depth;
        b[0] = W - 0.5 * LAMBDA0, b[1] = g_height - depth;
        if (wr_path_segment(a, b, ns, 0, pts, &ds, &d) != WR_OK) break;
        if (wr_probe_sample_dir(&pr, u, dir, pts, ns, vals, &nout, &d) != WR_OK || nout) break;
        if (wr_spectrum_analyze(vals, ns, ds, 0, NULL, &res, NULL, 0, &d) != WR_OK) {
            res.wavelength = NAN;
            res.amplitude_p2p = 0.0;
        }
        R->depth[R->nd] = depth, R->lambda[R->nd] = res.wavelength, R->amp[R->nd] = res.amplitude_p2p;
        for (j = 0; j < ns; ++j) xs[j] = pts[2 * j];
        R->lzc[R->nd] = NAN;
        if (modal_fit(xs, vals, ns, 2.0 * PI / LAMBDA0, &a1, &a2, resid) == 0)
            R->lzc[R->nd] = zero_cross_wavelength(resid, ns, xs[ns - 1] - xs[0]);
        R->a1[R->nd] = a1, R->a2[R->nd] = a2;
        if (dump) {
            for (j = 0; j < ns; j += 8) fprintf(dump, "%.4f %.4f %.6f\n", 1e3 * depth, 1e3 * xs[j], 1e3 * vals[j]);
            fprintf(dump, "\n");
        }
        if (have_f)
            fprintf(f.fp, "%.4f %.4f %.5f %.5f %.5f %.4f\n", 1e3 * depth, 1e3 * res.wavelength, 1e3 * res.amplitude_p2p,
                    1e3 * R->a1[R->nd], 1e3 * R->a2[R->nd], 1e3 * R->lzc[R->nd]);
        R->nd++;
    }
    if (have_f) wr_afile_commit(&f, &d);
    if (dump) fclose(dump);
    wr_probe_free(&pr);
    return 1;
}

/* The depth (linear interpolation between probes) where y first rises through c from below, among
 * the first `upto` probes; NAN when it does not. */
static double first_rise(const double *depth, const double *y, int32_t upto, double c) {
    int32_t k;
    for (k = 1; k < upto; ++k)
        if (y[k] >= c && y[k - 1] < c) return depth[k - 1] + (c - y[k - 1]) / (y[k] - y[k - 1]) * (depth[k] - depth[k - 1]);
    return NAN;
}

/* The depths the row reports, from its probes. */
static void curtain_depths(curtain_row *R) {
    const double A = LAMBDA0 * sqrt(GATHER) / PI;
    int32_t k, km = 0, present = 1;
    /* FFT peak: first crossing of 2 λ0 while the wrinkles are present */
    while (present < R->nd && !(R->amp[present] < AMP_FLOOR * A) && R->lambda[present] == R->lambda[present]) ++present;
    R->L_fft = first_rise(R->depth, R->lambda, present, 2.0 * LAMBDA0);
    /* Period doubling from the modal amplitudes. Midpoint: first depth where the 2λ0 amplitude a2
     * overtakes the λ0 amplitude a1. End: the depth where a2 is largest — the 2λ0 wrinkle has finished
     * forming there (crest pairs merged); deeper it coarsens or fades itself. Parabolic interpolation
     * through the three probes around the maximum. */
    for (k = 1; k < R->nd; ++k)
        if (R->a2[k] >= R->a1[k] && R->a2[k - 1] < R->a1[k - 1]) {
            double f0 = R->a2[k - 1] - R->a1[k - 1], f1 = R->a2[k] - R->a1[k];
            R->L_mid = R->depth[k - 1] + f0 / (f0 - f1) * (R->depth[k] - R->depth[k - 1]);
            break;
        }
    for (k = 1; k < R->nd; ++k)
        if (R->a2[k] > R->a2[km]) km = k;
    if (km > 0 && km < R->nd - 1 && R->a2[km] > R->a1[km]) {
        double ym = R->a2[km - 1], y0 = R->a2[km], yp = R->a2[km + 1], den = ym - 2.0 * y0 + yp;
        double off = den < 0.0 ? 0.5 * (ym - yp) / den : 0.0;
        R->L_end = R->depth[km] + off * (R->depth[km + 1] - R->depth[km]);
        R->a2_end = y0, R->a1_end = R->a1[km];
    }
    /* Primary: the wavelength one sees — the crest-count wavelength of the detrended probe (sign
     * changes of z minus its cubic) — first reaches 2λ0. */
    R->L_zc = first_rise(R->depth, R->lzc, R->nd, 2.0 * LAMBDA0);
    /* Fading of the imposed pattern: a1 down to half its value on the first probe line. */
    for (k = 1; k < R->nd; ++k)
        if (R->a1[k] <= 0.5 * R->a1[0] && R->a1[k - 1] > 0.5 * R->a1[0]) {
            double t = (R->a1[k - 1] - 0.5 * R->a1[0]) / (R->a1[k - 1] - R->a1[k]);
            R->L_a1half = R->depth[k - 1] + t * (R->depth[k] - R->depth[k - 1]);
            break;
        }
}

/* One stiffness B at resolution r: solve the hanging curtain, probe it, read off the depths. */
static int curtain_run(double B, double r, int load_steps, curtain_row *R, const char *datpath) {
    wr_scene sc;
    wr_scene_run run;
    wr_diag d;
    double *u;
    int32_t i;
    if (!curtain_scene(B, r, load_steps, &sc)) return -1;
    if (!curtain_predictions(B, R)) {
        wr_scene_free(&sc);
        return -1;
    }
    if (wr_scene_run_create(&run, &sc, &d) != WR_OK) {
        fprintf(stderr, "validate_curtain: %s\n", d.message);
        wr_scene_free(&sc);
        return -1;
    }
    R->nv = run.mesh.nv;
    fprintf(stderr, "== B = %.2e N m: r = %.2f mm, %d vertices, predicted L_w = %.1f mm\n", B, 1e3 * r, (int)R->nv,
            1e3 * R->Lw_pred);
    R->st = wr_scene_run_solve(&run, progress, NULL, &d);
    wr_cli_progress_end();
    if (R->st != WR_OK) fprintf(stderr, "   solve: %s\n", d.message);
    R->t_solve = run.t_solve;
    R->newton = run.newton_iterations;
    R->L_zc = R->L_a1half = R->L_fft = R->L_mid = R->L_end = R->a2_end = R->a1_end = NAN;
    R->rho = g_rho;
    R->nd = 0;
    u = (double *)malloc(sizeof(double) * 3 * (size_t)run.mesh.nv);
    if (u)
        for (i = 0; i < 3 * run.mesh.nv; ++i) u[i] = run.x[i] - run.mesh.pos[i];
    if (!u || !curtain_probes(&run.mesh, u, r, R, datpath)) {
        free(u);
        wr_scene_run_free(&run);
        wr_scene_free(&sc);
        return -1;
    }
    curtain_depths(R);
    fprintf(stderr, "   crest-count 2 lambda0 at %.1f mm, a1 halved at %.1f mm; FFT-peak 2 lambda0 crossing %.1f mm, a2 = a1 at %.1f mm, a2 max at %.1f mm; predicted %.1f mm; %d Newton, %.1f s\n",
            1e3 * R->L_zc, 1e3 * R->L_a1half, 1e3 * R->L_fft, 1e3 * R->L_mid, 1e3 * R->L_end, 1e3 * R->Lw_pred, (int)R->newton, R->t_solve);
    free(u);
    wr_scene_run_free(&run);
    wr_scene_free(&sc);
    return 0;
}

/* least-squares slope of ln y over ln x (n points, finite ones only) */
/* Sources of the formula values the rows compare with: computed by transition.h, not printed in a
 * paper, so they go in the "reference" column (issue 20), the "paper" column stays empty. */
#define SRC_TENSION "formula: tension form L_w = lambda0^2 sqrt(T/B), prefactor 1 (Style3D Sec. 4.2.1, transition.h)"
#define SRC_COMPRESSION \
    "formula: compression form L_w = lambda0^1.5 (delta/h^2)^0.25, prefactor 1 (Style3D Sec. 4.2.1, transition.h)"

/* A pass/fail row ±rel_tol around a formula's value: the band is built on the reference, paper = NAN. */
static void rel_reference(wr_vres *v, const char *name, double ref_mm, double ours_mm, double rel_tol, const char *source) {
    wr_vres_range(v, name, "mm", NAN, ours_mm, ref_mm - rel_tol * fabs(ref_mm), ref_mm + rel_tol * fabs(ref_mm));
    wr_vres_reference(v, ref_mm, source);
}

static double loglog_slope(const double *x, const double *y, int n) {
    double sx = 0, sy = 0, sxx = 0, sxy = 0;
    int i, m = 0;
    for (i = 0; i < n; ++i)
        if (x[i] > 0.0 && y[i] > 0.0 && isfinite(y[i])) {
            double lx = log(x[i]), ly = log(y[i]);
            sx += lx, sy += ly, sxx += lx * lx, sxy += lx * ly, ++m;
        }
    if (m < 2) return NAN;
    return (m * sxy - sx * sy) / (m * sxx - sx * sx);
}

/* What one invocation runs: the options, then the curtains and their result rows. */
typedef struct {
    curtain_row rows[NB + 2];
    double Bs[NB], r, A; /* stiffnesses [N m], mesh resolution [m], gather amplitude [m] */
    int nb, quick, load_steps, heavy_check, nrun;
    char dat[NB + 2][4096], field[4096];
} curtain_ctx;

static void curtain_usage(FILE *f) {
    fprintf(f,
            "usage: validate_curtain [--quick] [--res METRES] [--B NM] [--waves N] [--sides] [--young PA] [--rho KG_M2]\n"
            "       [--height M] [--dump FILE]\n"
            "  Style3D Fig. 17/18d hanging curtain (StVK statics): the lambda -> 2 lambda transition distance\n"
            "  against the wrinklon length. Writes validation/results/curtain.json (or under\n"
            "  $WRINKLE_RESULTS_DIR) and its figures; `make validate` runs it.\n");
}

/* Stage 1: options (and the globals they set), cli.h's strict parsing: 0, 1 after --help (usage on
 * stdout), or 2 with the one-line error on stderr (a bad value must never become a run that
 * rewrites the result file). */
static int curtain_args(curtain_ctx *c, int argc, char **argv) {
    double r = LAMBDA0 / 8.0, Bone = 0.0, waves = NWAVES;
    int k, nb = NB, quick = 0, heavy_check = 1;
    double *Bs = c->Bs;
    const wr_cli_opt opts[] = {
        {"--quick", NULL, WR_CLI_FLAG, &quick, 0.0, 0.0, NULL},
        {"--res", NULL, WR_CLI_NUMBER, &r, 1e-5, 1.0, NULL},
        {"--B", NULL, WR_CLI_NUMBER, &Bone, 1e-15, 1.0, NULL},
        {"--waves", NULL, WR_CLI_INTEGER, &waves, 2.0, 1000.0, NULL},
        {"--sides", NULL, WR_CLI_FLAG, &g_sides, 0.0, 0.0, NULL},
        {"--height", NULL, WR_CLI_NUMBER, &g_height, 1e-4, 100.0, NULL},
        {"--young", NULL, WR_CLI_NUMBER, &g_young, 1.0, 1e13, NULL},
        {"--rho", NULL, WR_CLI_NUMBER, &g_rho, 1e-6, 1e4, NULL},
        {"--dump", NULL, WR_CLI_STRING, (void *)&g_dump, 0.0, 0.0, NULL},
    };
    Bs[0] = 1.0e-6, Bs[1] = 2.0e-6, Bs[2] = 4.0e-6;
    wr_cli_set_program(argv[0]);
    k = wr_cli_parse(argc, argv, opts, (int)(sizeof opts / sizeof opts[0]), NULL, 0, NULL, curtain_usage);
    if (k <= 0) return k < 0 ? 2 : 1;
    g_nwaves = (int)waves;
    if (quick) {
        r = LAMBDA0 / 5.0;
        nb = 1;
        Bs[0] = 2.0e-6;
    }
    if (Bone > 0.0) {
        nb = 1;
        Bs[0] = Bone;
    }
    if (quick || Bone > 0.0) heavy_check = 0;
    c->r = r, c->nb = nb, c->quick = quick, c->heavy_check = heavy_check;
    c->load_steps = 6;
    c->A = LAMBDA0 * sqrt(GATHER) / PI;
    return 0;
}

/* Stage 2: the curtains — nb stiffnesses, then (full run) 4x the areal density and the
 * tension-dominated curtain; 0, or 2 when a run could not be set up. */
static int curtain_runs(curtain_ctx *c) {
    curtain_row *rows = c->rows;
    const double *Bs = c->Bs, r = c->r;
    int i, nb = c->nb, load_steps = c->load_steps, heavy_check = c->heavy_check, nrun;
    char (*dat)[4096] = c->dat, *field = c->field;
    size_t field_size = sizeof c->field;
    snprintf(field, field_size, "%s/curtain_field.dat", wr_vres_dir());
    for (i = 0; i < nb; ++i) {
        snprintf(dat[i], sizeof dat[i], "%s/curtain_%d.dat", wr_vres_dir(), i);
        if (!g_dump && (nb == 1 || i == 1)) g_dump = field; /* heat map of the middle stiffness */
        if (curtain_run(Bs[i], r, load_steps, &rows[i], dat[i]) != 0) return 2;
        if (g_dump == field) g_dump = NULL;
    }
    nrun = nb;
    if (heavy_check) { /* the same curtain with 4x the areal density: the tension form predicts 2x L_w */
        double rho0 = g_rho;
        g_rho = 4.0 * rho0;
        snprintf(dat[nb], sizeof dat[nb], "%s/curtain_%d.dat", wr_vres_dir(), nb);
        if (curtain_run(Bs[1], r, load_steps, &rows[nb], dat[nb]) != 0) return 2;
        g_rho = rho0;
        nrun = nb + 1;
        /* Tension-dominated curtain: the tension form's own regime, T/(E h) well above (A/L)^2. A taller
         * sheet (the transition must fit) of a heavy material: H = 200 mm, rho_A = 2.5 kg/m^2, T = 4.9 N/m. */
        {
            double H0 = g_height;
            g_height = HEAVY_HEIGHT, g_rho = HEAVY_RHO;
            snprintf(dat[nb + 1], sizeof dat[nb + 1], "%s/curtain_%d.dat", wr_vres_dir(), nb + 1);
            if (curtain_run(Bs[1], r, load_steps, &rows[nb + 1], dat[nb + 1]) != 0) return 2;
            g_height = H0, g_rho = rho0;
            nrun = nb + 2;
        }
    }
    c->nrun = nrun;
    return 0;
}

/* Stage 3: the per-run table. */
static void curtain_table(wr_vres *v, const curtain_ctx *c) {
    const curtain_row *rows = c->rows;
    const double A = c->A;
    int i, nrun = c->nrun;
    char table[8192], buf[2048];
    snprintf(table, sizeof table,
             "| B [N m] | rho_A [kg/m^2] | T = rho_A g H [N/m] | h (K-L) [mm] | L_w tension form [mm] | L_w compression form [mm] | "
             "lambda0 (A/h)^0.5 [mm] | "
             "crest-count lambda >= 2 lambda0 [mm] | ratio to tension / compression form | a1 halved [mm] | a2 = a1 [mm] | a2 max [mm] | "
             "FFT peak >= 2 lambda0 [mm] | T/(E h) vs (A/L)^2 | vertices | Newton | status | solve [s] |\n"
             "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n");
    for (i = 0; i < nrun; ++i) {
        const curtain_row *R = &rows[i];
        double Eh = g_young * R->h, LL = R->L_zc > 0.0 ? R->L_zc : R->Lw_comp;
        snprintf(buf, sizeof buf,
                 "| %.1e | %.2f | %.4f | %.3f | %.2f | %.2f | %.2f | %.2f | %.2f / %.2f | %.2f | %.2f | %.2f | %.2f | %.1e vs %.1e | %d | %d | %s | %.1f |\n",
                 R->B, R->rho, R->T, 1e3 * R->h, 1e3 * R->Lw_pred, 1e3 * R->Lw_comp, 1e3 * R->Lw_amp, 1e3 * R->L_zc, R->L_zc / R->Lw_pred,
                 R->L_zc / R->Lw_comp, 1e3 * R->L_a1half, 1e3 * R->L_mid, 1e3 * R->L_end, 1e3 * R->L_fft, R->T / Eh,
                 (A / LL) * (A / LL), (int)R->nv, (int)R->newton, wr_status_string(R->st), R->t_solve);
        strncat(table, buf, sizeof table - strlen(table) - 1);
    }
    wr_vres_table_md(v, table);
}

/* Stage 4: the quantities — pass/fail rows against the two forms (reference column), the rest reported. */
static void curtain_quantities(wr_vres *v, const curtain_ctx *c) {
    const curtain_row *rows = c->rows;
    const double r = c->r;
    int i, nb = c->nb, heavy_check = c->heavy_check;
    double x[NB], y[NB];
    char name[256];
    for (i = 0; i < nb; ++i) {
        snprintf(name, sizeof name, "transition distance, B = %.1e N m: measured vs tension form lambda0^2 sqrt(T/B)", rows[i].B);
        rel_reference(v, name, 1e3 * rows[i].Lw_pred, 1e3 * rows[i].L_zc, 0.25, SRC_TENSION); /* ±25 %: issue 5 */
    }
    for (i = 0; i < nb; ++i) {
        snprintf(name, sizeof name, "transition distance, B = %.1e N m: measured vs compression form lambda0^1.5 (delta/h^2)^0.25",
                 rows[i].B);
        rel_reference(v, name, 1e3 * rows[i].Lw_comp, 1e3 * rows[i].L_zc, 0.25, SRC_COMPRESSION); /* ±25 %: issue 5 */
    }
    for (i = 0; i < nb; ++i) {
        snprintf(name, sizeof name, "B = %.1e N m: measured vs lambda0 (A/h)^0.5 (PRL light-curtain law, exact gather amplitude; info)",
                 rows[i].B);
        wr_vres_info(v, name, "mm", NAN, 1e3 * rows[i].L_zc);
        wr_vres_reference(v, 1e3 * rows[i].Lw_amp, "formula: PRL light-curtain law lambda0 (A/h)^0.5, prefactor 1, A the exact "
                                                   "gather amplitude (transition.h)");
        snprintf(name, sizeof name, "B = %.1e N m: depth where the lambda0 amplitude a1 has halved", rows[i].B);
        wr_vres_info(v, name, "mm", NAN, 1e3 * rows[i].L_a1half);
        snprintf(name, sizeof name, "B = %.1e N m: depth of the largest 2 lambda0 amplitude a2", rows[i].B);
        wr_vres_info(v, name, "mm", NAN, 1e3 * rows[i].L_end);
        snprintf(name, sizeof name, "B = %.1e N m: FFT-peak crossing of 2 lambda0 (old metric)", rows[i].B);
        wr_vres_info(v, name, "mm", NAN, 1e3 * rows[i].L_fft);
    }
    if (nb >= 2) {
        for (i = 0; i < nb; ++i) x[i] = rows[i].B, y[i] = rows[i].L_zc;
        wr_vres_info(v, "exponent of L vs B (tension form -1/2, compression form -1/6 via h ~ B^(1/3))", "", NAN,
                     loglog_slope(x, y, nb));
        wr_vres_reference(v, -0.5, "formula: the tension form's exponent, L_w = lambda0^2 sqrt(T/B) (Style3D Sec. 4.2.1)");
    }
    if (heavy_check) {
        wr_vres_info(v, "L(4 rho_A) / L(rho_A) at B = 2e-6 (tension form 2, compression form 1)", "", NAN,
                     rows[nb].L_zc / rows[1].L_zc);
        wr_vres_reference(v, 2.0, "formula: the tension form L_w ~ sqrt(T), T = rho_A g H: sqrt(4) (Style3D Sec. 4.2.1)");
        snprintf(name, sizeof name,
                 "tension-dominated curtain (H = %.0f mm, rho_A = %.1f kg/m^2, T = %.2f N/m, B = 2e-6): measured vs tension form",
                 1e3 * HEAVY_HEIGHT, HEAVY_RHO, rows[nb + 1].T);
        rel_reference(v, name, 1e3 * rows[nb + 1].Lw_pred, 1e3 * rows[nb + 1].L_zc, 0.25, SRC_TENSION); /* ±25 %: issue 5 */
        wr_vres_info(v, "exponent of L vs T, B = 2e-6, T = 0.118 -> 4.9 N/m (tension form 1/2, compression form 0)", "", NAN,
                     log(rows[nb + 1].L_zc / rows[1].L_zc) / log(rows[nb + 1].T / rows[1].T));
        wr_vres_reference(v, 0.5, "formula: the tension form's exponent, L_w = lambda0^2 sqrt(T/B) (Style3D Sec. 4.2.1)");
    }
    /* the two numbers Style3D prints for its own curtain (Fig. 18d): paper values */
    wr_vres_info(v, "paper's case: predicted L_w", "mm", 26.7, NAN);
    wr_vres_info(v, "paper's case: measured", "mm", 25.0, NAN);
    wr_vres_info(v, "mesh resolution", "mm", NAN, 1e3 * r);
}

/* Stage 5: the notes — set-up, metric, predictions, regime and result read-outs. */
static void curtain_notes(wr_vres *v, const curtain_ctx *c) {
    const curtain_row *rows = c->rows;
    const double r = c->r, A = c->A;
    int i, nb = c->nb, quick = c->quick, load_steps = c->load_steps, heavy_check = c->heavy_check, nrun = c->nrun;
    double x[NB], y[NB];
    char buf[2048];
    snprintf(buf, sizeof buf,
             "Curtain %.0f x %.0f mm (W = %d lambda0), lambda0 = %.0f mm, gather delta = %.2f (top edge x scaled by 1 - delta, "
             "z = A sin(2 pi x / lambda0), A = lambda0 sqrt(delta)/pi = %.3f mm), rho_A = %.2f kg/m^2, E = %.0e Pa, nu = %.1f, "
             "h from Kirchhoff-Love; gravity in the sheet's plane; %s.",
             1e3 * g_nwaves * LAMBDA0, 1e3 * g_height, g_nwaves, 1e3 * LAMBDA0, GATHER, 1e3 * A, g_rho, g_young, POISSON,
             g_sides ? "side edges held at the gathered width (x scaled by 1 - delta, z = 0), bottom free"
                     : "sides and bottom free");
    wr_vres_note(v, buf);
    snprintf(buf, sizeof buf,
             "Regular union-jack grid at r = %.2f mm (%.1f cells per imposed wave); StVK + mid-edge bending; gravity and "
             "gather ramped over %d load steps; 1 um seeded kick; hybrid Newton; CHOLMOD.%s",
             1e3 * r, LAMBDA0 / r, load_steps, quick ? " --quick run (one stiffness, coarse): smoke only." : "");
    wr_vres_note(v, buf);
    wr_vres_note(v, "Measured transition distance: first depth where the crest-count wavelength (2 x probe length / sign "
                    "changes of z minus its least-squares cubic, which takes the sheet-scale bow) reaches 2 lambda0. Until this "
                    "session the metric was the first depth where the FFT peak wavelength reaches 2 lambda0; the probe spectra "
                    "show that this is the jump of the peak from the lambda0 bin straight to the sheet-scale bow (30-50 mm, as "
                    "long as the probe), where that bow outgrows the fading lambda0 wrinkles - not a 2 lambda0 wrinkle. It is "
                    "still listed, with the depth where the lambda0 amplitude a1 has halved and the depth of the largest 2 lambda0 "
                    "amplitude a2 (from a least-squares fit of cubic + lambda0 + 2 lambda0 sines on each probe).");
    wr_vres_note(v, "Predictions: transition.h as Style3D Sec. 4.2.1 writes them, prefactor 1: tension form lambda0^2 sqrt(T/B) "
                    "with T = rho_A g H (tension at the top edge), and compression form lambda0^1.5 (delta/h^2)^0.25 with the "
                    "gather delta and the Kirchhoff-Love h. Neither Style3D nor, as far as we could check, Vandeparre et al. "
                    "give an O(1) prefactor (both write '~'; the search tool reached only the PRL's first page), so transition.h "
                    "is unchanged: no justified factor was found, and none is fitted to this measurement.");
    if (nb >= 2 && rows[1].L_zc > 0.0) {
        double Eh = g_young * rows[1].h, q = A / rows[1].L_zc;
        snprintf(buf, sizeof buf,
                 "Regime (re-derived from Vandeparre et al.'s balance: bending B A^2/lambda^4 against stretching T (A/L)^2 "
                 "for a heavy curtain, E h (A/L)^4 for a light one; the tension form needs T/(E h) >> (A/L)^2). At B = 2e-6: "
                 "T/(E h) = %.1e, (A/L)^2 = %.1e at the measured L = %.1f mm (E h = %.0f N/m): %s",
                 rows[1].T / Eh, q * q, 1e3 * rows[1].L_zc, Eh,
                 q * q > rows[1].T / Eh ? "the sheet's own stretching outweighs the hanging weight's tension, so this "
                                          "fabric-like curtain is a LIGHT curtain and the tension form is outside its regime."
                                        : "by this estimate the hanging weight's tension dominates (heavy curtain), the "
                                          "tension form's regime.");
        wr_vres_note(v, buf);
    }
    if (heavy_check && rows[1].L_zc > 0.0) {
        snprintf(buf, sizeof buf,
                 "Tension test: 4x the areal density (T = %.3f instead of %.3f N/m) changes the measured distance by a factor "
                 "%.2f (a1-halved depth: %.2f); the tension form predicts 2, the compression form 1.",
                 rows[nb].T, rows[1].T, rows[nb].L_zc / rows[1].L_zc, rows[nb].L_a1half / rows[1].L_a1half);
        wr_vres_note(v, buf);
        {
            const curtain_row *R = &rows[nb + 1];
            double q = A / R->L_zc;
            snprintf(buf, sizeof buf,
                     "Tension-dominated run: H = %.0f mm, rho_A = %.1f kg/m^2, T = %.2f N/m at the top, T/(E h) = %.1e vs (A/L)^2 = "
                     "%.1e (%.1fx: the tension form's regime). Measured %.1f mm (a1 halved at %.1f mm) against the tension "
                     "form's %.1f mm: 42x the tension of the default curtain lengthens the transition by %.2fx (a1-halved "
                     "depth %.2fx), where the tension form predicts %.1fx. %s",
                     1e3 * HEAVY_HEIGHT, HEAVY_RHO, R->T, R->T / (g_young * R->h), q * q, R->T / (g_young * R->h) / (q * q),
                     1e3 * R->L_zc, 1e3 * R->L_a1half, 1e3 * R->Lw_pred, R->L_zc / rows[1].L_zc, R->L_a1half / rows[1].L_a1half,
                     sqrt(R->T / rows[1].T),
                     !(R->L_zc > 0.0 && rows[1].L_zc > 0.0)
                         ? "No crest-count transition was measured in one of the two runs."
                     : R->L_zc / rows[1].L_zc < 0.5 * sqrt(R->T / rows[1].T)
                         ? "So the miss is not only a matter of regime: the simulated lambda0 wrinkles give way within a few "
                           "wavelengths of the gathered edge nearly whatever T and B, like an edge boundary layer of width "
                           "~lambda0 rather than a wrinklon whose length grows as sqrt(T/B). Likely cause (not settled here): the "
                           "scaling argument assumes a slow, self-similar cascade (L >> lambda) away from the boundary, while the "
                           "hinged sinusoidal top edge prescribes only positions and the sheet relaxes from it like a "
                           "Saint-Venant edge layer; the paper's measurement (its own cloth simulation, set-up not given) may "
                           "also define the distance differently."
                         : "Here the measured distance does follow the tension form's sqrt(T) to within a factor 2.");
            wr_vres_note(v, buf);
        }
    }
    if (nb >= 2) {
        double rt[NB], rc[NB], ra[NB];
        for (i = 0; i < nb; ++i)
            rt[i] = rows[i].L_zc / rows[i].Lw_pred, rc[i] = rows[i].L_zc / rows[i].Lw_comp, ra[i] = rows[i].L_zc / rows[i].Lw_amp;
        for (i = 0; i < nb; ++i) x[i] = rows[i].B, y[i] = rows[i].L_zc;
        snprintf(buf, sizeof buf,
                 "Result: measured/predicted = %.2f, %.2f, %.2f (tension form), %.2f, %.2f, %.2f (compression form) and "
                 "%.2f, %.2f, %.2f (lambda0 (A/h)^0.5, info) for B = 1, 2, 4e-6 N m; L ~ B^%.2f measured (tension form -0.50, "
                 "compression form -0.17 through h ~ B^(1/3)). For this fabric-like curtain the tension form (the one the old "
                 "result used) is outside its regime and the density test shows no sqrt(T); the light-curtain forms have the "
                 "weak T and B dependence seen here, but over-predict the magnitude too. For reference, the PRL's law in terms of the "
                 "amplitude, L ~ lambda (A/h)^0.5, with the exact gather amplitude A = lambda0 sqrt(delta)/pi, is sqrt(pi) = "
                 "1.77 below Style3D's compression form (which substitutes A ~ lambda sqrt(delta)); that is a prefactor "
                 "convention of a scaling law, so it is listed for information and not applied to transition.h.",
                 rt[0], rt[1], rt[2], rc[0], rc[1], rc[2], ra[0], ra[1], ra[2], loglog_slope(x, y, nb));
        wr_vres_note(v, buf);
    }
    wr_vres_note(v, "Exploratory runs this session (B = 2e-6 N m, r = 2 mm unless stated; same driver with --B/--waves/--sides/"
                    "--young/--rho/--res; not part of this file's runs). W = 6 lambda0: crest-count 2 lambda0 at 10.4 mm, a1 "
                    "halved at 11.9 mm, a2 largest at 18.0 mm, FFT metric 7.4 mm; the same at r = 1.25 mm (8 cells per wave): "
                    "11.5 / 11.1 / 16.2 / 7.8 mm, so 2 mm is resolved to ~10 %; W = 6 lambda0 with 4x rho_A: 11.0 / 12.6 / 18.0 mm "
                    "(tension form: 2x); W = 6 lambda0 with the side edges held at the gathered width: 8.4 / 15.3 / 18.0 mm. "
                    "W = 12 lambda0 (the default here): a1 halved at 12.0 mm as with W = 6 lambda0, but a2 stays below 0.07 mm "
                    "over the top 40 mm: the lambda0 wrinkles merge straight into sheet-scale folds of 40-55 mm, so the large 2 "
                    "lambda0 amplitude seen at W = 6 lambda0 was the projection of the 60 mm sheet's bow, not period doubling. "
                    "E = 1e4 Pa (E h = 13 N/m): the wrinkles decay exponentially (e-folding ~4 mm) with no coarsening at all - "
                    "the gather is taken up in-plane when stretching is cheap, so the cascade needs E h large, which is what "
                    "makes this curtain light. Tension-dominated try: W = 6 lambda0, H = 200 mm, rho_A = 0.75 kg/m^2 "
                    "(T = 1.47 N/m, 12.5x; T/(E h) = 5.3e-3 vs (A/L)^2 = 2.8e-3): crest-count 2 lambda0 at 12.0 mm, a1 halved "
                    "at 14.2 mm, a2 largest at 21.5 mm - 15-20 % more than at T = 0.118 N/m where the tension form predicts "
                    "3.5x (85.8 mm).");
    wr_vres_note(v, "The paper's case: Style3D quotes 26.7 mm predicted vs 25 mm measured but states neither its curtain's "
                    "lambda, delta, thickness nor tension. The compression form for this curtain at B = 2e-6 N m (lambda0 = "
                    "10 mm, delta = 0.04, E = 1 MPa, nu = 0.3) happens to give 26.75 mm; we cannot tell whether that is the "
                    "paper's case or a coincidence.");
    for (i = 0; i < nrun; ++i)
        if (rows[i].st != WR_OK) {
            snprintf(buf, sizeof buf, "B = %.1e, rho_A = %.2f: a load step ended %s (best iterate analysed)", rows[i].B,
                     rows[i].rho, wr_status_string(rows[i].st));
            wr_vres_note(v, buf);
        }
}

/* Stage 6: the three gnuplot figures (wavelength, modal amplitudes, field), each attached once drawn. */
static void curtain_figures(wr_vres *v, const curtain_ctx *c) {
    const curtain_row *rows = c->rows;
    const char(*dat)[4096] = c->dat, *field = c->field;
    int i, nb = c->nb, nrun = c->nrun;
    char gp[4200], png[4200], cmd[9000];
    wr_afile f;
    wr_diag d;
    snprintf(gp, sizeof gp, "%s/../figures/curtain.gp", wr_vres_dir());
    snprintf(png, sizeof png, "%s/../figures/curtain.png", wr_vres_dir());
    if (wr_afile_open(&f, gp, &d) == WR_OK) {
        fprintf(f.fp, "set terminal pngcairo size 1000,520\nset output '%s'\nset grid\nset key bottom right\n", png);
        fprintf(f.fp, "set xlabel 'depth below the gathered top edge [mm]'\nset ylabel 'crest-count wavelength [mm]'\n");
        fprintf(f.fp, "set xrange [0:%g]\nset yrange [0:%g]\nplot ", 1e3 * g_height, 6e3 * LAMBDA0);
        for (i = 0; i < nrun; ++i)
            fprintf(f.fp, "%s'%s' u 1:6 w l lw 2 lc %d t 'B = %.0e, rho_A = %.2f: 2 lambda0 at %.1f mm (L_w tension %.1f, compression %.1f)'",
                    i ? ", " : "", dat[i], i + 1, rows[i].B, rows[i].rho, 1e3 * rows[i].L_zc, 1e3 * rows[i].Lw_pred,
                    1e3 * rows[i].Lw_comp);
        fprintf(f.fp, ", %g w l dt 2 lc rgb 'black' t '2 lambda0'\n", 2e3 * LAMBDA0);
        if (wr_afile_commit(&f, &d) == WR_OK) {
            snprintf(cmd, sizeof cmd, "gnuplot '%s' 2>/dev/null", gp);
            if (system(cmd) == 0)
                wr_vres_figure(v, "figures/curtain.png", "wavelength (crest count of the detrended probe) vs depth");
        }
    }
    snprintf(gp, sizeof gp, "%s/../figures/curtain_modes.gp", wr_vres_dir());
    snprintf(png, sizeof png, "%s/../figures/curtain_modes.png", wr_vres_dir());
    if (wr_afile_open(&f, gp, &d) == WR_OK) {
        fprintf(f.fp, "set terminal pngcairo size 1000,520\nset output '%s'\nset grid\nset key top right\n", png);
        fprintf(f.fp, "set xlabel 'depth below the gathered top edge [mm]'\nset ylabel 'modal amplitude [mm]'\n");
        fprintf(f.fp, "set xrange [0:%g]\nplot ", 1e3 * g_height);
        for (i = 0; i < nrun; ++i)
            fprintf(f.fp,
                    "%s'%s' u 1:4 w l lw 2 lc %d t 'lambda0 mode, B = %.0e, rho_A = %.2f', '%s' u 1:5 w l lw 2 dt 2 lc %d "
                    "t '2 lambda0 mode (max: %.1f mm; L_w tension %.1f / compression %.1f mm)'",
                    i ? ", " : "", dat[i], i + 1, rows[i].B, rows[i].rho, dat[i], i + 1, 1e3 * rows[i].L_end,
                    1e3 * rows[i].Lw_pred, 1e3 * rows[i].Lw_comp);
        fprintf(f.fp, "\n");
        if (wr_afile_commit(&f, &d) == WR_OK) {
            snprintf(cmd, sizeof cmd, "gnuplot '%s' 2>/dev/null", gp);
            if (system(cmd) == 0)
                wr_vres_figure(v, "figures/curtain_modes.png",
                               "lambda0 (solid) and 2 lambda0 (dashed) wrinkle amplitudes vs depth, per stiffness");
        }
    }
    snprintf(gp, sizeof gp, "%s/../figures/curtain_field.gp", wr_vres_dir());
    snprintf(png, sizeof png, "%s/../figures/curtain_field.png", wr_vres_dir());
    if (wr_afile_open(&f, gp, &d) == WR_OK) {
        fprintf(f.fp, "set terminal pngcairo size 700,700\nset output '%s'\nset view map\nset size ratio -1\n", png);
        fprintf(f.fp, "set xlabel 'x [mm]'\nset ylabel 'depth [mm]'\nset yrange [%g:0]\nset cblabel 'z [mm]'\n", 1e3 * g_height);
        fprintf(f.fp, "set palette defined (-1 'blue', 0 'white', 1 'red')\nset title 'out-of-plane z, B = %.0e N m'\n",
                rows[nb == 1 ? 0 : 1].B);
        fprintf(f.fp, "splot '%s' u 2:1:3 w pm3d notitle\n", field);
        if (wr_afile_commit(&f, &d) == WR_OK) {
            snprintf(cmd, sizeof cmd, "gnuplot '%s' 2>/dev/null", gp);
            if (system(cmd) == 0)
                wr_vres_figure(v, "figures/curtain_field.png", "out-of-plane displacement over the curtain (probe window)");
        }
    }
}

int main(int argc, char **argv) {
    static curtain_ctx c;
    wr_vres *v;
    int rc = curtain_args(&c, argc, argv);
    if (rc != 0) return rc == 1 ? 0 : 2;
    v = wr_vres_begin("curtain", "Style3D Fig. 17/18d hanging curtain: lambda -> 2 lambda transition distance vs wrinklon L_w");
    if (!v) return 2;
    if (curtain_runs(&c) != 0) return 2;
    curtain_table(v, &c);
    curtain_quantities(v, &c);
    curtain_notes(v, &c);
    curtain_figures(v, &c);
    return wr_vres_finish(v);
}
