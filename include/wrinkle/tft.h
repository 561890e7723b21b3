/* wrinkle/tft.h — tension-field-theory (TFT) relaxed membrane energy density: the convex envelope of
 * the St. Venant–Kirchhoff membrane energy that resists tension but not compression.
 * wrinkle v0.1.0 — MIT licence (see LICENSE). Needs only libc and libm (and core.h).
 *
 * TFW ("Fine Wrinkling on Coarsely Meshed Thin Shells", 2021) Sec. 4.1 computes the coarse base
 * surface r_b with this relaxed energy (plus quadratic bending) instead of StVK, because the relaxed
 * energy lets the coarse mesh compress without buckling into aliased wrinkles. App. B gives the
 * density in terms of the principal strains λ1 >= λ2 of the strain I_u⁻¹ I − id:
 *
 *     W̃(λ1, λ2) = 0                      λ1 < 0                      (slack: compressed both ways)
 *               = W(λ1, λ̂2(λ1))          λ1 >= 0, λ2 < λ̂2(λ1)        (wrinkled: uniaxial tension)
 *               = W(λ1, λ2)              λ1 >= 0, λ2 >= λ̂2(λ1)       (taut)
 *     W(λ1, λ2) = α/2 (λ1+λ2)² + β (λ1² + λ2²),  λ̂2(λ1) = argmin_λ2 W(λ1, λ2)
 *
 * With α = Yν/(1−ν²), β = Y/(2(1+ν)) (TFW Eq. 33) the minimiser is λ̂2 = −αλ1/(α+2β) = −νλ1 (the
 * Poisson contraction of a free lateral edge) and W(λ1, −νλ1) = (Y/2) λ1²: the wrinkled regime is
 * exactly uniaxial tension along the major principal direction.
 *
 * API
 *   wr_tft_regime_of(eps, poisson)                         TAUT / WRINKLED / SLACK for a strain
 *   wr_tft_density(eps, young, poisson, thickness, dW, d2W) relaxed energy per rest area [J/m²],
 *                                                          gradient and Hessian in strain coordinates
 *   wr_tft_principal(eps, mu, dir)                         principal Green strains and directions
 *
 * EXAMPLE
 *     double eps[3] = {0.02, -0.05, 0.0};           // Green strain (ε11, ε22, ε12) in a rest frame
 *     double dW[3], d2W[9], W;
 *     W = wr_tft_density(eps, 1e6, 0.3, 1e-3, dW, d2W);          // = h·Y·ε11²/2 = 0.2 J/m² (wrinkled)
 *     printf("W = %g J/m^2\n", W);
 *     if (wr_tft_regime_of(eps, 0.3) == WR_TFT_WRINKLED) puts("wrinkles run along the tension");
 *
 * ON STRAIN COORDINATES
 *   eps = (ε11, ε22, ε12) is the Green strain ε = ½(FᵀF − I) = ½ I_u⁻¹(I − I_u) in an orthonormal
 *   frame of the rest triangle, i.e. HALF the paper's λ's: λ_i = 2 μ_i where μ_i are the eigenvalues
 *   of ε. ε12 is the tensor (not engineering) shear and is ONE coordinate: dW[2] = ∂W/∂ε12 counts both
 *   off-diagonal entries. The taut density is the usual plane-stress StVK h (α/2 tr²ε + β tr ε²)
 *   = (h/4)‖I_u⁻¹I − id‖²_SV; that is the standard plate normalisation, twice TFW Eq. (1) as printed
 *   (see shell.h "ON NORMALISATION"). The wrinkled density is h·Y·μ1²/2. The regime boundaries do
 *   not depend on the overall factor.
 *
 * ON SMOOTHNESS AND CONVEXITY
 *   W̃ is C¹ (the wrinkled branch is a minimum over λ2, so its λ2-derivative vanishes on the
 *   boundary λ2 = −νλ1; both branches vanish with their gradient at λ1 = 0) and convex in ε; its
 *   stress ∂W̃/∂ε is positive semidefinite (tension only), so W̃ is also non-decreasing in the Loewner
 *   order and W̃(½(FᵀF − I)) is convex in the positions of a triangle. The Hessian jumps across the
 *   regime boundaries (second derivatives are one-sided there).
 *
 * ON THREADS
 *   Pure functions, no state.
 */
#ifndef WRINKLE_TFT_H
#define WRINKLE_TFT_H

#include "core.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef enum wr_tft_regime {
    WR_TFT_TAUT = 0,     /* both principal stretches resisted: plain StVK */
    WR_TFT_WRINKLED = 1, /* uniaxial tension along the major principal direction, wrinkles along it */
    WR_TFT_SLACK = 2     /* compressed in every direction: no stress, no energy */
} wr_tft_regime;

/* Principal Green strains mu[0] >= mu[1] of eps = (ε11, ε22, ε12) and, if dir != NULL, the unit
 * direction of mu[0] in the rest frame (dir[0], dir[1]). */
WRDEF void wr_tft_principal(const double eps[3], double mu[2], double dir[2]);
/* Regime of TFW App. B for Green strain eps and Poisson ratio nu (−1 < nu < 1). */
WRDEF wr_tft_regime wr_tft_regime_of(const double eps[3], double poisson);
/* Relaxed membrane energy per unit rest area [J/m²] (TFW App. B) for Young's modulus [Pa], Poisson
 * ratio (−1 < ν < 1) and thickness [m]. dW (3) and d2W (3×3 row-major) are the gradient and Hessian
 * with respect to (ε11, ε22, ε12); either may be NULL. */
WRDEF double wr_tft_density(const double eps[3], double young, double poisson, double thickness, double *dW,
                            double *d2W);

#ifdef __cplusplus
}
#endif
#endif /* WRINKLE_TFT_H */

/* ============================================================================================ */
#ifdef WRINKLE_IMPLEMENTATION
#ifndef WRINKLE_TFT_IMPLEMENTATION_DONE
#define WRINKLE_TFT_IMPLEMENTATION_DONE

#include <math.h>

#ifdef __cplusplus
extern "C" {
#endif

WRDEF void wr_tft_principal(const double eps[3], double mu[2], double dir[2]) {
    double lam[2];
    wr_vec2 vec[2];
    wr_m2_sym_eig(wr_m2(eps[0], eps[2], eps[2], eps[1]), lam, vec);
    mu[0] = lam[1];
    mu[1] = lam[0];
    if (dir) {
        dir[0] = vec[1].x;
        dir[1] = vec[1].y;
    }
}

WRDEF wr_tft_regime wr_tft_regime_of(const double eps[3], double poisson) {
    double mu[2];
    wr_tft_principal(eps, mu, NULL);
    /* App. B: slack when the larger principal strain is negative; wrinkled when the smaller one is
     * below the free-contraction value λ̂2 = −ν λ1 (same boundary for Green strains μ = λ/2). */
    if (mu[0] < 0.0) return WR_TFT_SLACK;
    if (mu[1] < -poisson * mu[0]) return WR_TFT_WRINKLED;
    return WR_TFT_TAUT;
}

WRDEF double wr_tft_density(const double eps[3], double young, double poisson, double thickness, double *dW,
                            double *d2W) {
    double alpha = young * poisson / (1.0 - poisson * poisson); /* TFW Eq. 33 */
    double beta = young / (2.0 * (1.0 + poisson));
    double h = thickness;
    wr_tft_regime reg = wr_tft_regime_of(eps, poisson);
    int i;
    if (reg == WR_TFT_SLACK) {
        if (dW)
            for (i = 0; i < 3; ++i) dW[i] = 0.0;
        if (d2W)
            for (i = 0; i < 9; ++i) d2W[i] = 0.0;
        return 0.0;
    }
    if (reg == WR_TFT_TAUT) {
        /* h(α/2 tr²ε + β tr ε²) with tr ε² = ε11² + ε22² + 2ε12² (ε12 one coordinate). */
        double tr = eps[0] + eps[1];
        if (dW) {
            dW[0] = h * (alpha * tr + 2.0 * beta * eps[0]);
            dW[1] = h * (alpha * tr + 2.0 * beta * eps[1]);
            dW[2] = h * 4.0 * beta * eps[2];
        }
        if (d2W) {
            d2W[0] = h * (alpha + 2.0 * beta);
            d2W[1] = h * alpha;
            d2W[2] = 0.0;
            d2W[3] = h * alpha;
            d2W[4] = h * (alpha + 2.0 * beta);
            d2W[5] = 0.0;
            d2W[6] = 0.0;
            d2W[7] = 0.0;
            d2W[8] = h * 4.0 * beta;
        }
        return h * (0.5 * alpha * tr * tr + beta * (eps[0] * eps[0] + eps[1] * eps[1] + 2.0 * eps[2] * eps[2]));
    }
    {
        /* Wrinkled: W = h·Y·μ1²/2 with μ1 = m + r, m = (ε11+ε22)/2, r = sqrt(d² + ε12²),
         * d = (ε11−ε22)/2. r > 0 here: μ1 = μ2 = μ >= 0 with μ < −νμ would need μ(1+ν) < 0. ∇r = Jᵀu, ∇²r = Jᵀ(I − uuᵀ)J / r with J = [[½, −½, 0], [0, 0, 1]]. */
        double d = 0.5 * (eps[0] - eps[1]), r = hypot(d, eps[2]);
        double mu1 = 0.5 * (eps[0] + eps[1]) + r;
        double k = h * young;
        double ux = d / r, uy = eps[2] / r;
        double g[3];
        g[0] = 0.5 + 0.5 * ux;
        g[1] = 0.5 - 0.5 * ux;
        g[2] = uy;
        if (dW)
            for (i = 0; i < 3; ++i) dW[i] = k * mu1 * g[i];
        if (d2W) {
            /* (I − uuᵀ) = v vᵀ with v = (−uy, ux); Jᵀv = (−uy/2, uy/2, ux). */
            double jv[3];
            int j;
            jv[0] = -0.5 * uy;
            jv[1] = 0.5 * uy;
            jv[2] = ux;
            for (i = 0; i < 3; ++i)
                for (j = 0; j < 3; ++j) d2W[3 * i + j] = k * (g[i] * g[j] + mu1 * jv[i] * jv[j] / r);
        }
        return 0.5 * k * mu1 * mu1;
    }
}

#ifdef __cplusplus
}
#endif
#endif /* WRINKLE_TFT_IMPLEMENTATION_DONE */
#endif /* WRINKLE_IMPLEMENTATION */
