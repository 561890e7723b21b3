/* Tests for wrinkle/predicates.h beyond the sign tests of test_triangulate.c (orient2d, incircle
 * against exact integer arithmetic) and test_collision.c (orient3d): the accurate value
 * wr_orient2d_value, and the filter boundary where plain floating point gets the sign wrong. */
#include <criterion/criterion.h>
#include <math.h>

#include "wrinkle/predicates.h"

/* p one ulp above the line y = x through q = (12, 12), r = (24, 24): det[p−r; q−r] =
 * (−23.5)(−12) − (−23.5 + 2^-53)(−12) = 12 · 2^-53 exactly (a double). The plain formula rounds both
 * products to 282 and returns 0; the exact sign is > 0 and wr_orient2d_value is the exact value. */
Test(predicates, orient2d_value_exact_where_the_float_formula_cancels) {
    double p[2] = {0.5, 0.5}, q[2] = {12.0, 12.0}, r[2] = {24.0, 24.0};
    const double exact = 12.0 * ldexp(1.0, -53);
    p[1] = nextafter(0.5, 1.0);
    cr_assert_eq(p[1] - 0.5, ldexp(1.0, -53));
    cr_assert_eq(wr_orient2d_fast(p, q, r), 0.0, "the example needs the float formula to cancel");
    cr_assert_gt(wr_orient2d(p, q, r), 0.0);
    cr_assert_lt(wr_orient2d(q, p, r), 0.0);
    cr_assert_eq(wr_orient2d_value(p, q, r), exact, "value %.17g, exact %.17g", wr_orient2d_value(p, q, r), exact);
    cr_assert_eq(wr_orient2d_value(r, p, q), exact, "cyclic permutation");
    cr_assert_eq(wr_orient2d_value(q, p, r), -exact);
    /* well away from degeneracy the value is the determinant to rounding */
    {
        double a[2] = {0.0, 0.0}, b[2] = {3.0, 0.0}, c[2] = {0.0, 2.0};
        cr_assert_eq(wr_orient2d_value(a, b, c), 6.0);
        cr_assert_eq(wr_orient2d(a, b, c), 6.0);
    }
}

/* The three predicates are exact on exactly degenerate input built from non-representable decimals:
 * points on the line y = 0.1 x + 0.3 are not collinear in binary, so the sign is whatever the doubles
 * say — but a point and its two copies, a square's corners (cocircular) and four points of z = 0 are. */
Test(predicates, exact_zero_on_exact_degeneracies) {
    double a[2] = {0.1, 0.7}, b[2] = {0.3, 1.1}, sq[4][2] = {{0.1, 0.1}, {0.7, 0.1}, {0.7, 0.7}, {0.1, 0.7}};
    double A[3] = {0.1, 0.2, 0.0}, B[3] = {0.7, 0.3, 0.0}, C[3] = {0.2, 0.9, 0.0}, D[3] = {1e10, -3e-7, 0.0};
    double E[3] = {0.1, 0.2, 1e-30};
    cr_assert_eq(wr_orient2d(a, b, a), 0.0);
    cr_assert_eq(wr_orient2d(a, a, b), 0.0);
    cr_assert_eq(wr_incircle(sq[0], sq[1], sq[2], sq[3]), 0.0, "a square's corners are cocircular");
    cr_assert_eq(wr_orient3d(A, B, C, D), 0.0, "four points in z = 0");
    cr_assert_gt(wr_orient3d(A, B, C, E), 0.0, "d above the CCW triangle: > 0 (the normal's side)");
    cr_assert_lt(wr_orient3d(A, C, B, E), 0.0);
}
