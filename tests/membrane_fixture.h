/* Test/bench fixture (not part of the library): a linear-elastic membrane on a triangulated
 * rectangle with 3 DOF per vertex, K + M/dt^2, built from plain arrays so it does not depend on
 * mesh.h. Used by tests/test_pcg.c and bench/bench_pcg.c.
 *
 * Grid: (nx+1)(ny+1) vertices on [0,w]x[0,h], vertex j*(nx+1)+i, two triangles per cell with the
 * diagonal alternating cell by cell (no preferred shear direction), CCW.
 * In-plane: constant-strain triangle, plane stress, 2D modulus Y [N/m] (Young's modulus times
 * thickness) and Poisson ratio nu: K_e = area * B^T D B with D = Y/(1-nu^2) [[1,nu,0],[nu,1,0],
 * [0,0,(1-nu)/2]] acting on engineering strain (eps_xx, eps_yy, 2 eps_xy).
 * Out-of-plane: only the lumped mass. Lumped mass m_v = rho * (sum of incident areas)/3 on all 3
 * DOFs, divided by dt^2 (the implicit-Euler Newton matrix of a membrane at rest).
 */
#ifndef WR_MEMBRANE_FIXTURE_H
#define WR_MEMBRANE_FIXTURE_H

#include "wrinkle/sparse.h"

typedef struct membrane_params {
    int32_t nx, ny;
    double w, h;   /* [m] */
    double Y, nu;  /* [N/m], [-] */
    double rho;    /* [kg/m^2] */
    double dt;     /* [s] */
} membrane_params;

static void membrane_face(const membrane_params *P, int32_t i, int32_t j, int second, int32_t tri[3]) {
    int32_t nx1 = P->nx + 1;
    int32_t v00 = j * nx1 + i, v10 = v00 + 1, v01 = v00 + nx1, v11 = v01 + 1;
    if ((i + j) % 2 == 0) { /* diagonal v00-v11 */
        if (!second) { tri[0] = v00; tri[1] = v10; tri[2] = v11; }
        else { tri[0] = v00; tri[1] = v11; tri[2] = v01; }
    } else { /* diagonal v10-v01 */
        if (!second) { tri[0] = v00; tri[1] = v10; tri[2] = v01; }
        else { tri[0] = v10; tri[1] = v11; tri[2] = v01; }
    }
}

/* Builds K + M/dt^2 (n = 3 nv) into *A; mass (nv, may be NULL) gets the lumped masses [kg]. */
static wr_status membrane_matrix(const membrane_params *P, wr_csr *A, double *mass, wr_diag *diag) {
    int32_t nv = (P->nx + 1) * (P->ny + 1), i, j, v;
    double dx = P->w / P->nx, dy = P->h / P->ny;
    double c = P->Y / (1.0 - P->nu * P->nu);
    double D[3][3];
    wr_triplets t;
    wr_status st;
    D[0][0] = c; D[0][1] = c * P->nu; D[0][2] = 0;
    D[1][0] = c * P->nu; D[1][1] = c; D[1][2] = 0;
    D[2][0] = 0; D[2][1] = 0; D[2][2] = c * 0.5 * (1.0 - P->nu);
    if ((st = wr_triplets_create(&t, 3 * nv, (int64_t)2 * P->nx * P->ny * 36 + 3 * nv, diag)) != WR_OK) return st;
    for (j = 0; j < P->ny; ++j)
        for (i = 0; i < P->nx; ++i) {
            int s;
            for (s = 0; s < 2; ++s) {
                int32_t tri[3], idx[9];
                double x[3], y[3], B[3][6], Ke[81], area, bb[3], cc[3];
                int a, b2, k, l;
                membrane_face(P, i, j, s, tri);
                for (a = 0; a < 3; ++a) {
                    x[a] = (tri[a] % (P->nx + 1)) * dx;
                    y[a] = (tri[a] / (P->nx + 1)) * dy;
                }
                area = 0.5 * ((x[1] - x[0]) * (y[2] - y[0]) - (x[2] - x[0]) * (y[1] - y[0]));
                /* shape-function gradients: dN_a/dx = b_a/(2A), dN_a/dy = c_a/(2A) */
                for (a = 0; a < 3; ++a) {
                    int a1 = (a + 1) % 3, a2 = (a + 2) % 3;
                    bb[a] = (y[a1] - y[a2]) / (2.0 * area);
                    cc[a] = (x[a2] - x[a1]) / (2.0 * area);
                }
                for (k = 0; k < 3; ++k)
                    for (l = 0; l < 6; ++l) B[k][l] = 0.0;
                for (a = 0; a < 3; ++a) {
                    B[0][2 * a] = bb[a];
                    B[1][2 * a + 1] = cc[a];
                    B[2][2 * a] = cc[a];
                    B[2][2 * a + 1] = bb[a];
                }
                for (k = 0; k < 81; ++k) Ke[k] = 0.0;
                for (a = 0; a < 6; ++a)
                    for (b2 = 0; b2 < 6; ++b2) {
                        double sum = 0.0;
                        for (k = 0; k < 3; ++k)
                            for (l = 0; l < 3; ++l) sum += B[k][a] * D[k][l] * B[l][b2];
                        /* local in-plane DOF a = 2*vertex + comp -> 9-DOF slot 3*vertex + comp */
                        Ke[(3 * (a / 2) + a % 2) * 9 + 3 * (b2 / 2) + b2 % 2] = area * sum;
                    }
                for (a = 0; a < 3; ++a)
                    for (k = 0; k < 3; ++k) idx[3 * a + k] = 3 * tri[a] + k;
                if ((st = wr_triplets_add_element(&t, 9, idx, Ke, diag)) != WR_OK) goto fail;
            }
        }
    for (v = 0; v < nv; ++v) {
        /* a vertex gets a third of each incident face's area: count them from the grid */
        int32_t vi = v % (P->nx + 1), vj = v / (P->nx + 1), nfaces = 0, di, dj, k;
        double m;
        for (dj = -1; dj <= 0; ++dj)
            for (di = -1; di <= 0; ++di) {
                int32_t ci = vi + di, cj = vj + dj, s;
                if (ci < 0 || cj < 0 || ci >= P->nx || cj >= P->ny) continue;
                for (s = 0; s < 2; ++s) {
                    int32_t tri[3];
                    membrane_face(P, ci, cj, s, tri);
                    nfaces += tri[0] == v || tri[1] == v || tri[2] == v;
                }
            }
        m = P->rho * nfaces * 0.5 * dx * dy / 3.0;
        if (mass) mass[v] = m;
        for (k = 0; k < 3; ++k)
            if ((st = wr_triplets_add(&t, 3 * v + k, 3 * v + k, m / (P->dt * P->dt), diag)) != WR_OK) goto fail;
    }
    st = wr_csr_from_triplets(A, &t, diag);
    wr_triplets_free(&t);
    return st;
fail:
    wr_triplets_free(&t);
    return st;
}

#endif
