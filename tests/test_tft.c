/* tests/test_tft.c — tft.h: relaxed membrane density (TFW App. B): StVK in tension, zero in slack,
 * uniaxial formula in the wrinkled regime, C¹ across regime boundaries, FD derivatives, convexity in
 * the strain and in the positions of a triangle, tension-only stress. */
#include <criterion/criterion.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "wrinkle/shell.h"
#include "wrinkle/tft.h"

#define TF_Y 2.5
#define TF_NU 0.3
#define TF_H 0.1

static void tf_iso_C(double Y, double nu, double h, double C[9]) {
    double k = h * Y / (1 - nu * nu);
    memset(C, 0, sizeof(double) * 9);
    C[0] = C[4] = k;
    C[1] = C[3] = k * nu;
    C[8] = k * 0.5 * (1 - nu);
}

/* strain with principal values (m1, m2) and major direction at angle th */
static void tf_eps(double m1, double m2, double th, double eps[3]) {
    double c = cos(th), s = sin(th);
    eps[0] = m1 * c * c + m2 * s * s;
    eps[1] = m1 * s * s + m2 * c * c;
    eps[2] = (m1 - m2) * c * s;
}

Test(tft, taut_equals_stvk) {
    wr_rng rng;
    double C[9];
    int t, i;
    wr_rng_seed(&rng, 1);
    tf_iso_C(TF_Y, TF_NU, TF_H, C);
    for (t = 0; t < 200; ++t) {
        double m1 = 0.1 * wr_rng_uniform(&rng) + 1e-3, m2, eps[3], W, Ws, dW[3], dWs[3], H[9], Hs[9];
        /* anywhere in the taut wedge μ2 ∈ [−νμ1, μ1], including slightly compressive μ2 */
        m2 = -TF_NU * m1 + (1 + TF_NU) * m1 * wr_rng_uniform(&rng);
        tf_eps(m1, m2, 6.283 * wr_rng_uniform(&rng), eps);
        cr_assert_eq(wr_tft_regime_of(eps, TF_NU), WR_TFT_TAUT);
        W = wr_tft_density(eps, TF_Y, TF_NU, TF_H, dW, H);
        Ws = wr_shell_stvk_density(C, eps, dWs, Hs);
        cr_expect(fabs(W - Ws) <= 1e-14 * Ws, "W %.17g vs StVK %.17g", W, Ws);
        for (i = 0; i < 3; ++i) cr_expect(fabs(dW[i] - dWs[i]) <= 1e-14 * (fabs(dWs[0]) + fabs(dWs[1]) + fabs(dWs[2])));
        for (i = 0; i < 9; ++i) cr_expect(fabs(H[i] - Hs[i]) <= 1e-14 * fabs(Hs[0]));
    }
}

Test(tft, slack_is_zero) {
    wr_rng rng;
    int t, i;
    wr_rng_seed(&rng, 2);
    for (t = 0; t < 100; ++t) {
        double m1 = -0.1 * wr_rng_uniform(&rng) - 1e-9, m2 = m1 - 0.1 * wr_rng_uniform(&rng), eps[3], dW[3], H[9];
        tf_eps(m1, m2, 6.283 * wr_rng_uniform(&rng), eps);
        cr_assert_eq(wr_tft_regime_of(eps, TF_NU), WR_TFT_SLACK);
        cr_expect_eq(wr_tft_density(eps, TF_Y, TF_NU, TF_H, dW, H), 0.0);
        for (i = 0; i < 3; ++i) cr_expect_eq(dW[i], 0.0);
        for (i = 0; i < 9; ++i) cr_expect_eq(H[i], 0.0);
    }
}

/* Wrinkled: W = h·Y·μ1²/2 and the stress is uniaxial along the major direction d:
 * ∂W/∂ε = hYμ1 d dᵀ, i.e. (d0², d1², 2 d0 d1)·hYμ1 in (ε11, ε22, ε12) coordinates. */
Test(tft, uniaxial_formula) {
    double eps[3], dW[3], th = 0.4, c = cos(th), s = sin(th), m1 = 0.02, W, k = TF_H * TF_Y * m1;
    tf_eps(m1, -0.05, th, eps);
    cr_assert_eq(wr_tft_regime_of(eps, TF_NU), WR_TFT_WRINKLED);
    W = wr_tft_density(eps, TF_Y, TF_NU, TF_H, dW, NULL);
    cr_expect(fabs(W - 0.5 * TF_H * TF_Y * m1 * m1) < 1e-15, "W %.17g", W);
    cr_expect(fabs(dW[0] - k * c * c) < 1e-15 && fabs(dW[1] - k * s * s) < 1e-15 && fabs(dW[2] - 2 * k * c * s) < 1e-15,
              "dW %g %g %g", dW[0], dW[1], dW[2]);
    /* independent of ν and of μ2 inside the regime: the free-contraction minimiser λ̂2 = −νλ1 */
    tf_eps(m1, -0.3, th, eps);
    cr_expect(fabs(wr_tft_density(eps, TF_Y, 0.45, TF_H, NULL, NULL) - 0.5 * TF_H * TF_Y * m1 * m1) < 1e-15);
    /* μ2 = −νμ1 exactly on the boundary: StVK at (μ1, −νμ1) equals hYμ1²/2 (TFT App. B identity) */
    {
        double C[9];
        tf_iso_C(TF_Y, TF_NU, TF_H, C);
        tf_eps(m1, -TF_NU * m1, th, eps);
        cr_expect(fabs(wr_shell_stvk_density(C, eps, NULL, NULL) - 0.5 * TF_H * TF_Y * m1 * m1) < 1e-15);
    }
}

Test(tft, regimes_and_principal) {
    double eps[3], mu[2], dir[2];
    tf_eps(0.03, 0.01, 1.0, eps);
    wr_tft_principal(eps, mu, dir);
    cr_expect(fabs(mu[0] - 0.03) < 1e-15 && fabs(mu[1] - 0.01) < 1e-15);
    cr_expect(fabs(fabs(dir[0] * cos(1.0) + dir[1] * sin(1.0)) - 1.0) < 1e-14);
    cr_expect_eq(wr_tft_regime_of(eps, TF_NU), WR_TFT_TAUT);
    tf_eps(0.03, -0.0089, 0.2, eps); /* > −0.009 */
    cr_expect_eq(wr_tft_regime_of(eps, TF_NU), WR_TFT_TAUT);
    tf_eps(0.03, -0.0091, 0.2, eps);
    cr_expect_eq(wr_tft_regime_of(eps, TF_NU), WR_TFT_WRINKLED);
    tf_eps(-1e-6, -0.1, 0.2, eps);
    cr_expect_eq(wr_tft_regime_of(eps, TF_NU), WR_TFT_SLACK);
    eps[0] = eps[1] = eps[2] = 0.0;
    cr_expect_eq(wr_tft_regime_of(eps, TF_NU), WR_TFT_TAUT);
    cr_expect_eq(wr_tft_density(eps, TF_Y, TF_NU, TF_H, NULL, NULL), 0.0);
}

/* C¹ across both boundaries: values and gradients on either side of μ2 = −νμ1 and of μ1 = 0 differ
 * by O(δ) (a jump in the gradient would show up as an O(1) difference). */
Test(tft, c1_across_regime_boundaries) {
    double d = 1e-7, th = 0.7, m1 = 0.05;
    double ea[3], eb[3], ga[3], gb[3], Wa, Wb, gs = TF_H * TF_Y * m1;
    int i;
    tf_eps(m1, -TF_NU * m1 + d, th, ea);
    tf_eps(m1, -TF_NU * m1 - d, th, eb);
    cr_assert_eq(wr_tft_regime_of(ea, TF_NU), WR_TFT_TAUT);
    cr_assert_eq(wr_tft_regime_of(eb, TF_NU), WR_TFT_WRINKLED);
    Wa = wr_tft_density(ea, TF_Y, TF_NU, TF_H, ga, NULL);
    Wb = wr_tft_density(eb, TF_Y, TF_NU, TF_H, gb, NULL);
    cr_expect(fabs(Wa - Wb) < 10 * d * gs, "W jump %.3e", Wa - Wb);
    for (i = 0; i < 3; ++i) cr_expect(fabs(ga[i] - gb[i]) < 10 * d * TF_H * TF_Y, "grad jump %.3e", ga[i] - gb[i]);
    /* μ1 = 0 boundary between wrinkled and slack */
    tf_eps(d, -0.05, th, ea);
    tf_eps(-d, -0.05, th, eb);
    cr_assert_eq(wr_tft_regime_of(ea, TF_NU), WR_TFT_WRINKLED);
    cr_assert_eq(wr_tft_regime_of(eb, TF_NU), WR_TFT_SLACK);
    Wa = wr_tft_density(ea, TF_Y, TF_NU, TF_H, ga, NULL);
    for (i = 0; i < 3; ++i) cr_expect(fabs(ga[i]) < 10 * d * TF_H * TF_Y);
    cr_expect(Wa < d * d * TF_H * TF_Y);
}

/* FD of W → dW and dW → d2W in strain coordinates, in all three regimes, at samples at least 1e-4
 * away from the kinks (central step 1e-7: truncation ~1e-14, round-off ~1e-9 relative). */
Test(tft, fd_density_derivatives) {
    wr_rng rng;
    int t, i, j, tested[3] = {0, 0, 0};
    const double st = 1e-7;
    wr_rng_seed(&rng, 4);
    for (t = 0; t < 600; ++t) {
        double eps[3], mu[2], dW[3], H[9], ep[3], gp[3], gm[3], Wp, Wm, errg = 0, ng = 0, errh = 0, nh = 0;
        wr_tft_regime reg;
        for (i = 0; i < 3; ++i) eps[i] = 0.2 * (2 * wr_rng_uniform(&rng) - 1);
        wr_tft_principal(eps, mu, NULL);
        if (fabs(mu[0]) < 1e-4 || fabs(mu[1] + TF_NU * mu[0]) < 1e-4) continue;
        reg = wr_tft_regime_of(eps, TF_NU);
        if (reg == WR_TFT_SLACK) {
            tested[2]++;
            continue; /* identically zero, checked in slack_is_zero */
        }
        tested[reg]++;
        wr_tft_density(eps, TF_Y, TF_NU, TF_H, dW, H);
        for (i = 0; i < 3; ++i) {
            memcpy(ep, eps, sizeof ep);
            ep[i] += st;
            Wp = wr_tft_density(ep, TF_Y, TF_NU, TF_H, gp, NULL);
            ep[i] -= 2 * st;
            Wm = wr_tft_density(ep, TF_Y, TF_NU, TF_H, gm, NULL);
            errg += pow((Wp - Wm) / (2 * st) - dW[i], 2);
            ng += dW[i] * dW[i];
            for (j = 0; j < 3; ++j) {
                errh += pow((gp[j] - gm[j]) / (2 * st) - H[3 * j + i], 2);
                nh += H[3 * j + i] * H[3 * j + i];
            }
        }
        cr_expect(sqrt(errg / ng) < 1e-6, "regime %d: dW rel. error %.3e", reg, sqrt(errg / ng));
        cr_expect(sqrt(errh / nh) < 1e-6, "regime %d: d2W rel. error %.3e", reg, sqrt(errh / nh));
    }
    cr_expect(tested[0] > 50 && tested[1] > 50 && tested[2] > 50, "coverage %d %d %d", tested[0], tested[1], tested[2]);
}

/* Convexity in the strain: midpoint inequality on random pairs spanning all regimes; PSD Hessian
 * and PSD stress (tension only) at every sample. */
Test(tft, convex_in_strain_and_tension_only) {
    wr_rng rng;
    int t, i;
    wr_rng_seed(&rng, 5);
    for (t = 0; t < 5000; ++t) {
        double a[3], b[3], c[3], Wa, Wb, Wc, dW[3], H[9], lam[3], smu[2];
        for (i = 0; i < 3; ++i) {
            a[i] = 0.2 * (2 * wr_rng_uniform(&rng) - 1);
            b[i] = 0.2 * (2 * wr_rng_uniform(&rng) - 1);
            c[i] = 0.5 * (a[i] + b[i]);
        }
        Wa = wr_tft_density(a, TF_Y, TF_NU, TF_H, NULL, NULL);
        Wb = wr_tft_density(b, TF_Y, TF_NU, TF_H, NULL, NULL);
        Wc = wr_tft_density(c, TF_Y, TF_NU, TF_H, dW, H);
        cr_expect(Wc <= 0.5 * (Wa + Wb) + 1e-15 * (Wa + Wb), "midpoint convexity violated by %.3e",
                  Wc - 0.5 * (Wa + Wb));
        wr_dense_sym_eig(3, H, lam, NULL);
        cr_expect(lam[0] >= -1e-12 * fabs(lam[2]), "d2W eigenvalue %.3e", lam[0]);
        /* stress matrix [[∂W/∂ε11, ½∂W/∂ε12], [½∂W/∂ε12, ∂W/∂ε22]] is PSD */
        {
            double sv[3];
            sv[0] = dW[0];
            sv[1] = dW[1];
            sv[2] = 0.5 * dW[2];
            wr_tft_principal(sv, smu, NULL);
            cr_expect(smu[1] >= -1e-14 * TF_H * TF_Y, "compressive stress %.3e", smu[1]);
        }
    }
}

/* One rest triangle; deformation x_v = R·F0·ū_v with F0 from a target strain. */
static void tf_triangle(wr_mesh *m, wr_shell *s, wr_membrane_model model) {
    static const double rest[6] = {0.0, 0.0, 1.0, 0.1, 0.3, 0.8};
    static const int32_t tri[3] = {0, 1, 2};
    wr_shell_desc d;
    cr_assert_eq(wr_mesh_create(m, 3, NULL, rest, 1, tri, NULL), WR_OK);
    memset(&d, 0, sizeof d);
    d.young = TF_Y;
    d.poisson = TF_NU;
    d.thickness = TF_H;
    d.membrane = model;
    d.bending = WR_BENDING_NONE;
    cr_assert_eq(wr_shell_create(s, m, &d, NULL), WR_OK);
}

/* x9 realising Green strain eps in the face's rest frame (F = U = sqrt(I + 2ε), tilted out of plane). */
static void tf_x_for_strain(const wr_shell *s, const wr_mesh *m, const double eps[3], double x9[9]) {
    double Cm[3], mu[2], dir[2], l1, l2, U[4], D[4], det, di[4], F[6];
    int v, i;
    Cm[0] = 1 + 2 * eps[0];
    Cm[1] = 1 + 2 * eps[1];
    Cm[2] = 2 * eps[2];
    wr_tft_principal(Cm, mu, dir);
    l1 = sqrt(mu[0]);
    l2 = sqrt(mu[1]);
    U[0] = l1 * dir[0] * dir[0] + l2 * dir[1] * dir[1];
    U[1] = U[2] = (l1 - l2) * dir[0] * dir[1];
    U[3] = l1 * dir[1] * dir[1] + l2 * dir[0] * dir[0];
    /* rest-frame matrix of this face is D⁻¹ = s->dinv: positions x_v = F ū_v with ū in that frame,
     * i.e. [x1−x0, x2−x0] = F·D with D = dinv⁻¹ */
    memcpy(di, s->dinv, sizeof di);
    det = di[0] * di[3] - di[1] * di[2];
    D[0] = di[3] / det;
    D[1] = -di[1] / det;
    D[2] = -di[2] / det;
    D[3] = di[0] / det;
    /* F = Rot · [U; 0] with Rot a fixed rotation about (1,1,1)/√3 by 0.5 rad (rigid: no energy change) */
    {
        double ax[3] = {0.5773502691896258, 0.5773502691896258, 0.5773502691896258}, c = cos(0.5), sn = sin(0.5), R[9];
        int a, b;
        for (a = 0; a < 3; ++a)
            for (b = 0; b < 3; ++b) R[3 * a + b] = (a == b ? c : 0.0) + (1 - c) * ax[a] * ax[b];
        R[1] -= sn * ax[2];
        R[2] += sn * ax[1];
        R[3] += sn * ax[2];
        R[5] -= sn * ax[0];
        R[6] -= sn * ax[1];
        R[7] += sn * ax[0];
        for (a = 0; a < 3; ++a)
            for (b = 0; b < 2; ++b) F[2 * a + b] = R[3 * a] * U[b] + R[3 * a + 1] * U[2 + b];
    }
    for (i = 0; i < 3; ++i) x9[i] = 0.1 * (i + 1);
    for (v = 1; v < 3; ++v)
        for (i = 0; i < 3; ++i) x9[3 * v + i] = x9[i] + F[2 * i] * D[v - 1] + F[2 * i + 1] * D[2 + v - 1];
    (void)m;
}

/* Element level: FD of the TFT triangle energy in x at strains 1e-3 on either side of each regime
 * boundary, and convexity in the positions: the 9×9 Hessian is PSD (TFT stress is tension-only and
 * W̃ convex and Loewner-monotone), while plain StVK in the same compressed states is not. */
Test(tft, element_fd_near_boundaries_and_convex_in_x) {
    wr_mesh m;
    wr_shell s, sv;
    wr_rng rng;
    double targets[6][2] = {{0.05, -TF_NU * 0.05 + 1e-3}, {0.05, -TF_NU * 0.05 - 1e-3}, {1e-3, -0.04},
                            {-1e-3, -0.04},               {0.04, 0.02},                  {0.02, -0.2}};
    int t, i, j, stvk_indef = 0;
    const double st = 1e-7;
    tf_triangle(&m, &s, WR_MEMBRANE_TFT);
    {
        wr_shell_desc d;
        memset(&d, 0, sizeof d);
        d.young = TF_Y;
        d.poisson = TF_NU;
        d.thickness = TF_H;
        d.bending = WR_BENDING_NONE;
        cr_assert_eq(wr_shell_create(&sv, &m, &d, NULL), WR_OK);
    }
    wr_rng_seed(&rng, 6);
    for (t = 0; t < 6 + 200; ++t) {
        double eps[3], x[9], g[9], H[81], gp[9], gm[9], Ep, Em, errg = 0, ng = 0, errh = 0, nh = 0, lam[9];
        if (t < 6)
            tf_eps(targets[t][0], targets[t][1], 0.3 + t, eps);
        else
            tf_eps(0.3 * wr_rng_uniform(&rng) - 0.1, -0.3 * wr_rng_uniform(&rng), 6.283 * wr_rng_uniform(&rng), eps);
        tf_x_for_strain(&s, &m, eps, x);
        {
            double got[3];
            int k;
            /* the construction reproduces the target strain */
            wr_shell_face_strain(&s, 0, x, got);
            for (k = 0; k < 3; ++k) cr_assert(fabs(got[k] - eps[k]) < 1e-13, "strain %d: %g vs %g", k, got[k], eps[k]);
        }
        wr_shell_membrane_element(&s, 0, x, g, H);
        if (t < 6) {
            for (i = 0; i < 9; ++i) {
                double xi = x[i];
                x[i] = xi + st;
                Ep = wr_shell_membrane_element(&s, 0, x, gp, NULL);
                x[i] = xi - st;
                Em = wr_shell_membrane_element(&s, 0, x, gm, NULL);
                x[i] = xi;
                errg += pow((Ep - Em) / (2 * st) - g[i], 2);
                ng += g[i] * g[i];
                for (j = 0; j < 9; ++j) {
                    errh += pow((gp[j] - gm[j]) / (2 * st) - H[9 * j + i], 2);
                    nh += H[9 * j + i] * H[9 * j + i];
                }
            }
            if (targets[t][0] < 0) {
                cr_expect(ng == 0 && nh == 0, "slack triangle must be force-free");
            } else {
                cr_expect(sqrt(errg / ng) < 1e-6, "target %d: gradient rel. error %.3e", t, sqrt(errg / ng));
                cr_expect(sqrt(errh / nh) < 1e-6, "target %d: Hessian rel. error %.3e", t, sqrt(errh / nh));
            }
        }
        wr_dense_sym_eig(9, H, lam, NULL);
        cr_expect(lam[0] >= -1e-12 * fmax(fabs(lam[8]), 1e-300), "TFT element Hessian eigenvalue %.3e (max %.3e)", lam[0],
                  lam[8]);
        wr_shell_membrane_element(&sv, 0, x, NULL, H);
        wr_dense_sym_eig(9, H, lam, NULL);
        if (lam[0] < -1e-6 * lam[8]) stvk_indef++;
    }
    cr_expect(stvk_indef > 50, "StVK should be indefinite under compression (%d states)", stvk_indef);
    wr_shell_free(&s);
    wr_shell_free(&sv);
    wr_mesh_free(&m);
}
