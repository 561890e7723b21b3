/* wrinkle/wrinkle.h — includes the wrinkle modules: the dependency-free core always, the modules
 * that need a GPL library only when asked for.
 * wrinkle v0.1.0 — MIT licence (see LICENSE).
 *
 * Define WRINKLE_IMPLEMENTATION in exactly one .c/.cpp file before including this header.
 *
 * WHAT IS INCLUDED
 *   Always (libc + libm only, MIT): core, mesh, subdiv, sparse, spd (iterative solvers), resolution,
 *   transition, sizing, tft, shell, poisson, predicates, triangulate, polyfile, eigen (its solvers
 *   opt-in), newton, statics, dynamics, body, garment, wrinkle_field, mesher, tfw, collision, render.
 *   (pcg.h, the old name of spd.h, is not included; it still works as a compatibility include.)
 *   Link with -lm (pkg-config: wrinkle-core).
 *   Opt-in backends, each behind a macro so that a binary without them carries no GPL code:
 *     -DWR_USE_FFTW=1     also include spectrum.h (wrinkle counting; FFTW 3, GPL-2+, -lfftw3)
 *     -DWR_USE_CHOLMOD=1  spd.h's direct solver backend (SuiteSparse CHOLMOD, -lcholmod,
 *                         -I/usr/include/suitesparse on Debian)
 *     -DWR_USE_LIBPNG=1   render.h's PNG writer (libpng, zlib licence, -lpng)
 *     -DWR_USE_ARPACK=1   eigen.h's eigensolver and statics.h's stability test (ARPACK-ng, BSD-3,
 *                         -larpack; with WR_USE_CHOLMOD)
 *   pkg-config `wrinkle` sets the first three (the configuration the kit's own programs use; ARPACK
 *   is added by the Makefile where eigen.h's solvers are wanted).
 *   spectrum.h may always be included directly; the macro only decides what this umbrella pulls in.
 *
 * EXAMPLES
 *   examples/minimal_c/main.c (the one C translation unit defining WRINKLE_IMPLEMENTATION) and
 *   examples/minimal_cpp (the same from C++, the implementation in its own impl.cpp). Every module's
 *   top block has its own EXAMPLE and says its units and who owns what.
 *
 * This file deliberately has no include guard: every module guards its declarations and, separately,
 * its implementation, so including this file again after defining WRINKLE_IMPLEMENTATION works.
 */
#include "core.h"
/* modules, foundations first (one line each) */
#include "mesh.h"
#include "subdiv.h"
#include "sparse.h"
#include "spd.h"
#if defined(WR_USE_FFTW) && WR_USE_FFTW
#include "spectrum.h"
#endif
#include "resolution.h"
#include "transition.h"
#include "sizing.h"
#include "tft.h"
#include "shell.h"
#include "poisson.h"
#include "predicates.h"
#include "triangulate.h"
#include "polyfile.h"
#include "eigen.h"
#include "newton.h"
#include "statics.h"
#include "dynamics.h"
#include "body.h"
#include "garment.h"
#include "wrinkle_field.h"
#include "mesher.h"
#include "tfw.h"
#include "collision.h"
#include "render.h"
