/* wrinkle/pcg.h — compatibility name of spd.h, the front-end for symmetric positive definite
 * systems (wr_spd_*: PCG with Jacobi / 3×3 block-Jacobi / IC(0) / AMG, or CHOLMOD). It was named
 * after its first backend; new code includes "spd.h". This header only includes it.
 * wrinkle v0.1.0 — MIT licence (see LICENSE).
 *
 * EXAMPLE
 *     printf("%s\n", wr_solver_method_name(WR_SOLVER_PCG_IC0));   // "pcg-ic0"
 */
#include "spd.h"
