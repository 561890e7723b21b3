/* wrinkle/wrinkle.h — includes every wrinkle module.
 * wrinkle v0.1.0 — MIT licence (see LICENSE).
 *
 * Define WRINKLE_IMPLEMENTATION in exactly one .c/.cpp file before including this header.
 * Modules that need a Debian library say so at their top: spectrum.h needs FFTW (-lfftw3);
 * the CHOLMOD backend in pcg.h is compiled only with -DWR_USE_CHOLMOD=1 (-lcholmod).
 * Everything else needs only libc and libm.
 *
 * This file deliberately has no include guard: every module guards its declarations and, separately,
 * its implementation, so including this file again after defining WRINKLE_IMPLEMENTATION works.
 */
#include "core.h"
/* modules, foundations first (one line each) */
#include "mesh.h"
#include "sparse.h"
#include "pcg.h"
#include "spectrum.h"
#include "resolution.h"
#include "transition.h"
#include "tft.h"
#include "shell.h"
#include "poisson.h"
#include "triangulate.h"
#include "polyfile.h"
#include "statics.h"
#include "wrinkle_field.h"
#include "mesher.h"
#include "tfw.h"
#include "collision.h"
