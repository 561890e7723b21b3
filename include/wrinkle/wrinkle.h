/* wrinkle/wrinkle.h — includes every wrinkle module.
 * wrinkle v0.1.0 — MIT licence (see LICENSE).
 *
 * Define WRINKLE_IMPLEMENTATION in exactly one .c/.cpp file before including this header.
 * Modules that need a Debian library say so at their top: spectrum.h needs FFTW (-lfftw3);
 * the CHOLMOD backend in pcg.h is compiled only with -DWR_USE_CHOLMOD=1 (-lcholmod).
 * Everything else needs only libc and libm.
 */
#ifndef WRINKLE_WRINKLE_H
#define WRINKLE_WRINKLE_H
#include "core.h"
/* modules (one line each, foundations first) */
#endif /* WRINKLE_WRINKLE_H */

/* Each module guards its own implementation, so re-including under WRINKLE_IMPLEMENTATION is safe. */
#ifdef WRINKLE_IMPLEMENTATION
#include "core.h"
/* modules-impl */
#endif
