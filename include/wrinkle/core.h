/* wrinkle/core.h — status codes, diagnostics, allocation hooks, seeded RNG, atomic files,
 * and the small fixed-size linear algebra every other wrinkle module stands on.
 * wrinkle v0.1.0 — MIT licence (see LICENSE). Needs only libc and libm.
 *
 * HOW TO USE
 *   In exactly one .c or .cpp file:
 *       #define WRINKLE_IMPLEMENTATION
 *       #include "wrinkle/wrinkle.h"      (or any single header)
 *   Everywhere else just #include the header(s) you need.
 *
 * CONFIGURATION (define before the implementation is compiled)
 *   WR_MALLOC(sz) / WR_REALLOC(p,sz) / WR_FREE(p)   allocation hooks (default: libc). They must be
 *       defined together. They cannot reach memory owned by FFTW or CHOLMOD (see those headers).
 *   WR_STATIC            make every public function `static` (all of wrinkle private to one TU).
 *   WR_ASSERT(x)         programmer-error checks (default: assert). Never used on user data.
 *
 * API
 *   wr_status_string(s)                    name of a status code ("WR_ERR_INVALID_ARG")
 *   wr_diag                                caller-owned error detail (message, item index, backend code)
 *   wr_rng_seed / _u64 / _uniform / _normal   explicit seeded RNG (xoshiro256**), no global state
 *   wr_afile_open / _commit / _abort       write-to-temp-then-rename files
 *   wr_file_read(path, &text, &len, diag)  whole file into a NUL-terminated buffer (free with wr_free)
 *   wr_time_seconds()                      wall clock for timings in reports
 *   wr_v2_* wr_v3_* wr_m2_* wr_m3_*        2-/3-vectors and 2×2/3×3 matrices (by value)
 *   wr_m2_sym_eig                          closed-form eigen-decomposition of a symmetric 2×2
 *   wr_dense_sym_eig / wr_dense_project_spd  cyclic-Jacobi eigen-solver for small dense symmetric
 *                                          matrices and the per-element SPD projection built on it
 *   wr_polygon_area / wr_point_in_polygon / wr_segment_distance   2D geometry on xy point arrays
 *                                          (signed shoelace area, crossing-number test, point-segment
 *                                          distance) shared by the meshing-side modules
 *
 * EXAMPLE
 *     wr_diag d;  wr_rng rng;  wr_afile f;  wr_mat2 A;  wr_vec2 vec[2];  double u, lam[2];
 *     wr_rng_seed(&rng, 42);                      // every random result is reproducible
 *     u = wr_rng_uniform(&rng);                   // in [0, 1)
 *     A = wr_m2(2.0, 1.0, 1.0, 3.0);
 *     wr_m2_sym_eig(A, lam, vec);                 // lam ascending: 1.382, 3.618
 *     if (wr_afile_open(&f, "out.txt", &d) != WR_OK) { puts(d.message); return 1; }
 *     fprintf(f.fp, "%g %g %g\n", u, lam[0], lam[1]);
 *     if (wr_afile_commit(&f, &d) != WR_OK) { puts(d.message); return 1; }   // whole or not at all
 *     printf("lambda = %.3f, %.3f\n", lam[0], lam[1]);
 *
 * ON ERRORS
 *   Fallible functions return wr_status (WR_OK == 0) and take an optional `wr_diag *` (may be NULL).
 *   Library code never prints, never exits, never aborts on user input.
 *
 * ON THREADS
 *   Nothing here keeps global mutable state; distinct objects may be used from distinct threads.
 */
#ifndef WRINKLE_CORE_H
#define WRINKLE_CORE_H

#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

#define WR_VERSION_MAJOR 0
#define WR_VERSION_MINOR 1
#define WR_VERSION_PATCH 0
#define WR_VERSION_STRING "0.1.0"

#ifndef WRDEF
#ifdef WR_STATIC
#define WRDEF static
#else
#define WRDEF extern
#endif
#endif

#ifdef __cplusplus
extern "C" {
#endif

/* One list gives both the enum and the strings. */
#define WR_STATUS_LIST(X)                                                                   \
    X(WR_OK, "ok")                                                                          \
    X(WR_ERR_INVALID_ARG, "invalid argument")                                               \
    X(WR_ERR_NOMEM, "out of memory")                                                        \
    X(WR_ERR_OVERFLOW, "size arithmetic overflow")                                          \
    X(WR_ERR_IO, "file input/output failed")                                                \
    X(WR_ERR_PARSE, "malformed input file")                                                 \
    X(WR_ERR_DOMAIN, "value outside the model's domain")                                    \
    X(WR_ERR_GEOMETRY, "invalid geometry")                                                  \
    X(WR_ERR_TOPOLOGY, "invalid mesh topology")                                             \
    X(WR_ERR_BUDGET, "a caller-set budget would be exceeded")                               \
    X(WR_ERR_NOT_SPD, "matrix is not symmetric positive definite")                          \
    X(WR_ERR_NOT_CONVERGED, "iteration did not converge (best iterate kept)")               \
    X(WR_ERR_BACKEND, "backend library failed")                                             \
    X(WR_ERR_UNSUPPORTED, "not available in this build")

typedef enum wr_status {
#define WR__STATUS_ENUM(name, text) name,
    WR_STATUS_LIST(WR__STATUS_ENUM)
#undef WR__STATUS_ENUM
    WR_STATUS_COUNT
} wr_status;

/* Caller-owned error detail. Every field is written on failure; on success it is left alone. */
#define WR_DIAG_MESSAGE_LEN 512
typedef struct wr_diag {
    wr_status status;                  /* the status that was returned */
    int32_t item;                      /* index of the offending item (vertex, segment, row…), or -1 */
    /* Where the item sits, for callers that report it without parsing `message` (all -1 when not
     * applicable; wr_fail sets them to -1, the failing module fills what it knows):
     * part = the part holding the curve (the mesher's panel), curve = the curve within the part
     * (poisson.h numbering: 0 outer, 1 + i hole i, 1 + n_holes + j line j), item = the index within
     * the curve; other_curve / other_item = the second item of a pair (two crossing segments). */
    int32_t part, curve, other_curve, other_item;
    int32_t backend_code;              /* error code from GSL / FFTW / CHOLMOD when relevant, else 0 */
    char message[WR_DIAG_MESSAGE_LEN]; /* one line, no trailing newline */
} wr_diag;

WRDEF const char *wr_status_string(wr_status s); /* "WR_ERR_PARSE" */
WRDEF const char *wr_status_text(wr_status s);   /* "malformed input file" */
/* Fill `diag` (if not NULL) and return `s`: `return wr_fail(d, WR_ERR_DOMAIN, -1, "B=%g", B);` */
WRDEF wr_status wr_fail(wr_diag *diag, wr_status s, int32_t item, const char *fmt, ...)
#if defined(__GNUC__) || defined(__clang__)
    __attribute__((format(printf, 4, 5)))
#endif
    ;

/* ---- allocation ------------------------------------------------------------------------ */
/* Overflow-checked array allocation through the hooks; NULL on overflow or exhaustion.
 * Zero elements yield a valid unique pointer (never NULL) so callers need no special case. */
WRDEF void *wr_alloc_array(size_t count, size_t size);
WRDEF void *wr_calloc_array(size_t count, size_t size);
WRDEF void *wr_realloc_array(void *p, size_t count, size_t size);
WRDEF void wr_free(void *p);

/* ---- random numbers: xoshiro256** seeded through splitmix64 ------------------------------- */
typedef struct wr_rng {
    uint64_t s[4];
} wr_rng;
WRDEF void wr_rng_seed(wr_rng *r, uint64_t seed);
WRDEF uint64_t wr_rng_u64(wr_rng *r);
WRDEF double wr_rng_uniform(wr_rng *r);             /* [0, 1), 53 random bits */
WRDEF double wr_rng_normal(wr_rng *r);              /* standard normal (Box–Muller) */
WRDEF uint32_t wr_rng_below(wr_rng *r, uint32_t n); /* uniform in [0, n), n > 0, unbiased */

/* ---- atomic files --------------------------------------------------------------------- */
/* Writes go to "<path>.wrtmp<k>"; commit flushes, closes and renames over <path>. An abort (or an
 * error in commit) removes the temporary and leaves whatever stood at <path> untouched. */
#define WR_PATH_MAX 4096
typedef struct wr_afile {
    FILE *fp;
    char path[WR_PATH_MAX];
    char tmp[WR_PATH_MAX + 16];
} wr_afile;
WRDEF wr_status wr_afile_open(wr_afile *f, const char *path, wr_diag *diag);
WRDEF wr_status wr_afile_commit(wr_afile *f, wr_diag *diag);
WRDEF void wr_afile_abort(wr_afile *f);

/* Read the whole file at `path` (regular file or pipe) into a new buffer with a NUL appended:
 * *text owns len + 1 bytes (free with wr_free), *len (optional) = bytes read, the NUL not counted.
 * Embedded NUL bytes are kept: a caller that wants text compares strlen(*text) with *len.
 * WR_ERR_IO when the file cannot be opened or read (message names the path), WR_ERR_NOMEM;
 * on failure *text = NULL. */
WRDEF wr_status wr_file_read(const char *path, char **text, size_t *len, wr_diag *diag);

/* Wall-clock seconds (C11 timespec_get); only differences are meaningful. */
WRDEF double wr_time_seconds(void);

/* ---- small fixed-size linear algebra ------------------------------------------------------ */
typedef struct wr_vec2 {
    double x, y;
} wr_vec2;
typedef struct wr_vec3 {
    double x, y, z;
} wr_vec3;
typedef struct wr_mat2 {
    double m[2][2]; /* m[row][col] */
} wr_mat2;
typedef struct wr_mat3 {
    double m[3][3]; /* m[row][col] */
} wr_mat3;

WRDEF wr_vec2 wr_v2(double x, double y);
WRDEF wr_vec2 wr_v2_add(wr_vec2 a, wr_vec2 b);
WRDEF wr_vec2 wr_v2_sub(wr_vec2 a, wr_vec2 b);
WRDEF wr_vec2 wr_v2_scale(wr_vec2 a, double s);
WRDEF double wr_v2_dot(wr_vec2 a, wr_vec2 b);
WRDEF double wr_v2_cross(wr_vec2 a, wr_vec2 b); /* z of the 3D cross product */
WRDEF double wr_v2_norm(wr_vec2 a);

WRDEF wr_vec3 wr_v3(double x, double y, double z);
WRDEF wr_vec3 wr_v3_load(const double *p); /* p[0..2] */
WRDEF void wr_v3_store(wr_vec3 a, double *p);
WRDEF wr_vec3 wr_v3_add(wr_vec3 a, wr_vec3 b);
WRDEF wr_vec3 wr_v3_sub(wr_vec3 a, wr_vec3 b);
WRDEF wr_vec3 wr_v3_scale(wr_vec3 a, double s);
WRDEF double wr_v3_dot(wr_vec3 a, wr_vec3 b);
WRDEF wr_vec3 wr_v3_cross(wr_vec3 a, wr_vec3 b);
WRDEF double wr_v3_norm(wr_vec3 a);
WRDEF wr_vec3 wr_v3_normalized(wr_vec3 a); /* zero vector stays zero */

WRDEF wr_mat2 wr_m2(double a00, double a01, double a10, double a11);
WRDEF wr_mat2 wr_m2_identity(void);
WRDEF wr_mat2 wr_m2_add(wr_mat2 a, wr_mat2 b);
WRDEF wr_mat2 wr_m2_sub(wr_mat2 a, wr_mat2 b);
WRDEF wr_mat2 wr_m2_scale(wr_mat2 a, double s);
WRDEF wr_mat2 wr_m2_mul(wr_mat2 a, wr_mat2 b);
WRDEF wr_mat2 wr_m2_transpose(wr_mat2 a);
WRDEF double wr_m2_det(wr_mat2 a);
WRDEF double wr_m2_trace(wr_mat2 a);
WRDEF wr_vec2 wr_m2_mulv(wr_mat2 a, wr_vec2 v);
/* Inverse; returns 0 and leaves *out untouched when |det| <= tiny * |a|^2 (singular). */
WRDEF int wr_m2_inverse(wr_mat2 a, wr_mat2 *out);
/* Symmetric 2×2 (uses the average of the off-diagonals): eigenvalues ascending in lam[0..1],
 * unit eigenvectors in vec[0..1], right-handed (vec[1] = rot90(vec[0])). Closed form, stable. */
WRDEF void wr_m2_sym_eig(wr_mat2 a, double lam[2], wr_vec2 vec[2]);

WRDEF wr_mat3 wr_m3_identity(void);
WRDEF wr_mat3 wr_m3_mul(wr_mat3 a, wr_mat3 b);
WRDEF wr_mat3 wr_m3_transpose(wr_mat3 a);
WRDEF double wr_m3_det(wr_mat3 a);
WRDEF wr_vec3 wr_m3_mulv(wr_mat3 a, wr_vec3 v);
WRDEF int wr_m3_inverse(wr_mat3 a, wr_mat3 *out); /* 0 when singular */

/* Cyclic Jacobi for an n×n symmetric matrix A (row-major, only read). Eigenvalues ascending in
 * lam[n]; eigenvectors as columns of V (row-major n×n) when V != NULL. n <= WR_DENSE_MAX.
 * Accurate to a few ulps relative to ||A|| for the n <= 18 element matrices wrinkle uses. */
#define WR_DENSE_MAX 32
WRDEF void wr_dense_sym_eig(int n, const double *A, double *lam, double *V);
/* Replace symmetric A (n×n, row-major, in place) by V max(Λ, floor) Vᵀ: the per-element Hessian
 * projection that keeps Newton's matrix SPD on non-convex energies. floor >= 0. Returns the number
 * of eigenvalues that were raised. */
WRDEF int wr_dense_project_spd(int n, double *A, double floor);

/* ---- small 2D geometry on point arrays: xy = x0 y0 x1 y1 ... [m] -------------------------- */
/* Signed area [m²] of the closed polygon xy[0..n) (the last point joins the first): > 0 when
 * counter-clockwise. The shoelace sum runs about xy[0], not the origin, so a small polygon far from
 * the origin keeps its digits. For n = 3 it is the triangle area ½ (p1 − p0) × (p2 − p0).
 * n < 3 gives 0. Plain floating point (no exact arithmetic): use triangulate.h for predicates. */
WRDEF double wr_polygon_area(const double *xy, int32_t n);
/* Crossing-number test: 1 when (x, y) is inside the closed polygon xy[0..n), else 0. Edges count
 * with the half-open rule (y_i > y) != (y_j > y), so for a point ON the boundary the answer may go
 * either way; callers that care test the boundary distance with their own tolerance first. Holes are
 * separate polygons (inside the outer and not inside any hole). n < 3 gives 0. */
WRDEF int wr_point_in_polygon(const double *xy, int32_t n, double x, double y);
/* Distance [m] from p to the closed segment [a, b]; *t (optional) = the parameter in [0, 1] of the
 * closest point a + t (b − a). A zero-length segment is the point a (t = 0). Where the closest point
 * is interior the distance is |(b − a) × (p − a)| / |b − a|, which is exactly 0 for p on the line
 * (the projected-point form leaves ~1e-17 m there). */
WRDEF double wr_segment_distance(const double p[2], const double a[2], const double b[2], double *t);

#ifdef __cplusplus
}
#endif
#endif /* WRINKLE_CORE_H */

/* ============================================================================================ */
#ifdef WRINKLE_IMPLEMENTATION
#ifndef WRINKLE_CORE_IMPLEMENTATION_DONE
#define WRINKLE_CORE_IMPLEMENTATION_DONE

#include <math.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#if !defined(WR_MALLOC) && !defined(WR_REALLOC) && !defined(WR_FREE)
#define WR_MALLOC(sz) malloc(sz)
#define WR_REALLOC(p, sz) realloc(p, sz)
#define WR_FREE(p) free(p)
#elif !defined(WR_MALLOC) || !defined(WR_REALLOC) || !defined(WR_FREE)
#error "wrinkle: define all of WR_MALLOC, WR_REALLOC and WR_FREE, or none"
#endif

#ifndef WR_ASSERT
#include <assert.h>
#define WR_ASSERT(x) assert(x)
#endif

#ifdef __cplusplus
extern "C" {
#endif

/* Singularity test of wr_m2_inverse / wr_m3_inverse: |det| <= ABS + REL·(entry scale)^n counts as
 * singular. REL = 1e-14 ≈ 45 ulps: a determinant that small relative to its terms is rounding noise
 * (condition number beyond ~1e14); ABS keeps an all-zero matrix singular. */
#define WR__SINGULAR_REL 1e-14
#define WR__SINGULAR_ABS 1e-300
/* Cyclic Jacobi stops when Σ offdiag² <= OFF_REL2 · Σ diag², i.e. off-diagonal mass below 1e-15
 * relative (a few ulps of ||A||), or after MAX_SWEEPS sweeps (quadratic convergence needs < 10 for
 * n <= 32; the cap only bounds work on NaN input). */
#define WR__JACOBI_OFF_REL2 1e-30
#define WR__JACOBI_MAX_SWEEPS 60

WRDEF const char *wr_status_string(wr_status s) {
    switch (s) {
#define WR__STATUS_NAME(name, text) \
    case name:                      \
        return #name;
        WR_STATUS_LIST(WR__STATUS_NAME)
#undef WR__STATUS_NAME
    default:
        return "WR_STATUS_UNKNOWN";
    }
}

WRDEF const char *wr_status_text(wr_status s) {
    switch (s) {
#define WR__STATUS_TEXT(name, text) \
    case name:                      \
        return text;
        WR_STATUS_LIST(WR__STATUS_TEXT)
#undef WR__STATUS_TEXT
    default:
        return "unknown status";
    }
}

WRDEF wr_status wr_fail(wr_diag *diag, wr_status s, int32_t item, const char *fmt, ...) {
    if (diag) {
        va_list ap;
        diag->status = s;
        diag->item = item;
        diag->part = diag->curve = diag->other_curve = diag->other_item = -1;
        diag->backend_code = 0;
        va_start(ap, fmt);
        vsnprintf(diag->message, sizeof diag->message, fmt, ap);
        va_end(ap);
    }
    return s;
}

WRDEF void *wr_alloc_array(size_t count, size_t size) {
    size_t bytes;
    if (size != 0 && count > SIZE_MAX / size) return NULL;
    bytes = count * size;
    return WR_MALLOC(bytes ? bytes : 1);
}

WRDEF void *wr_calloc_array(size_t count, size_t size) {
    void *p = wr_alloc_array(count, size);
    if (p && count && size) memset(p, 0, count * size);
    return p;
}

WRDEF void *wr_realloc_array(void *p, size_t count, size_t size) {
    size_t bytes;
    if (size != 0 && count > SIZE_MAX / size) return NULL;
    bytes = count * size;
    return WR_REALLOC(p, bytes ? bytes : 1);
}

WRDEF void wr_free(void *p) {
    if (p) WR_FREE(p);
}

static uint64_t wr__splitmix64(uint64_t *x) {
    uint64_t z = (*x += 0x9E3779B97F4A7C15ULL);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
    return z ^ (z >> 31);
}

static uint64_t wr__rotl(uint64_t x, int k) { return (x << k) | (x >> (64 - k)); }

WRDEF void wr_rng_seed(wr_rng *r, uint64_t seed) {
    uint64_t x = seed;
    int i;
    for (i = 0; i < 4; ++i) r->s[i] = wr__splitmix64(&x);
}

WRDEF uint64_t wr_rng_u64(wr_rng *r) {
    uint64_t *s = r->s;
    uint64_t result = wr__rotl(s[1] * 5, 7) * 9;
    uint64_t t = s[1] << 17;
    s[2] ^= s[0];
    s[3] ^= s[1];
    s[1] ^= s[2];
    s[0] ^= s[3];
    s[2] ^= t;
    s[3] = wr__rotl(s[3], 45);
    return result;
}

WRDEF double wr_rng_uniform(wr_rng *r) { return (double)(wr_rng_u64(r) >> 11) * (1.0 / 9007199254740992.0); }

WRDEF double wr_rng_normal(wr_rng *r) {
    double u1 = 1.0 - wr_rng_uniform(r); /* (0, 1]: log is finite */
    double u2 = wr_rng_uniform(r);
    return sqrt(-2.0 * log(u1)) * cos(6.283185307179586 * u2);
}

WRDEF uint32_t wr_rng_below(wr_rng *r, uint32_t n) {
    /* Lemire's multiply-shift with rejection: exact uniformity. */
    uint64_t m = (uint64_t)(uint32_t)(wr_rng_u64(r) >> 32) * n;
    uint32_t lo = (uint32_t)m;
    if (lo < n) {
        uint32_t t = (uint32_t)(-n) % n;
        while (lo < t) {
            m = (uint64_t)(uint32_t)(wr_rng_u64(r) >> 32) * n;
            lo = (uint32_t)m;
        }
    }
    return (uint32_t)(m >> 32);
}

WRDEF wr_status wr_afile_open(wr_afile *f, const char *path, wr_diag *diag) {
    size_t n;
    int k;
    f->fp = NULL;
    f->path[0] = f->tmp[0] = 0;
    if (!path || !*path) return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "empty output path");
    n = strlen(path);
    if (n >= WR_PATH_MAX) return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "output path too long");
    memcpy(f->path, path, n + 1);
    /* C11 "x" mode: exclusive create, so two writers never share a temporary. */
    for (k = 0; k < 1000 && !f->fp; ++k) {
        snprintf(f->tmp, sizeof f->tmp, "%s.wrtmp%d", path, k);
        f->fp = fopen(f->tmp, "wbx");
    }
    if (!f->fp) return wr_fail(diag, WR_ERR_IO, -1, "cannot create a temporary file beside '%s'", path);
    return WR_OK;
}

WRDEF wr_status wr_afile_commit(wr_afile *f, wr_diag *diag) {
    int bad;
    if (!f->fp) return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "file was not open");
    bad = ferror(f->fp) != 0;
    bad |= fflush(f->fp) != 0;
    bad |= fclose(f->fp) != 0;
    f->fp = NULL;
    if (bad) {
        remove(f->tmp);
        return wr_fail(diag, WR_ERR_IO, -1, "writing '%s' failed (disk full?); previous file kept", f->path);
    }
    if (rename(f->tmp, f->path) != 0) {
        remove(f->tmp);
        return wr_fail(diag, WR_ERR_IO, -1, "cannot rename temporary onto '%s'", f->path);
    }
    return WR_OK;
}

WRDEF void wr_afile_abort(wr_afile *f) {
    if (f->fp) {
        fclose(f->fp);
        f->fp = NULL;
        remove(f->tmp);
    }
}

/* First read chunk [bytes]; the buffer then doubles, so a file of n bytes costs O(n) copies. */
#define WR__FILE_READ_CHUNK 65536

WRDEF wr_status wr_file_read(const char *path, char **text, size_t *len, wr_diag *diag) {
    FILE *fp;
    char *buf = NULL;
    size_t n = 0, cap = 0;
    if (text) *text = NULL;
    if (len) *len = 0;
    if (!path || !text) return wr_fail(diag, WR_ERR_INVALID_ARG, -1, "wr_file_read: NULL path or output");
    fp = fopen(path, "rb");
    if (!fp) return wr_fail(diag, WR_ERR_IO, -1, "cannot open '%s' for reading", path);
    for (;;) {
        size_t got;
        if (cap - n < 2) { /* room for at least one byte plus the terminator */
            size_t ncap = cap ? 2 * cap : WR__FILE_READ_CHUNK;
            char *nb = ncap > cap ? (char *)wr_realloc_array(buf, ncap, 1) : NULL;
            if (!nb) {
                wr_free(buf);
                fclose(fp);
                return wr_fail(diag, WR_ERR_NOMEM, -1, "out of memory reading '%s' (%zu bytes so far)", path, n);
            }
            buf = nb;
            cap = ncap;
        }
        got = fread(buf + n, 1, cap - n - 1, fp);
        n += got;
        if (got == 0) break;
    }
    if (ferror(fp)) {
        wr_free(buf);
        fclose(fp);
        return wr_fail(diag, WR_ERR_IO, -1, "read error on '%s'", path);
    }
    fclose(fp);
    buf[n] = 0;
    *text = buf;
    if (len) *len = n;
    return WR_OK;
}

WRDEF double wr_time_seconds(void) {
    struct timespec ts;
    if (timespec_get(&ts, TIME_UTC) != TIME_UTC) return (double)clock() / CLOCKS_PER_SEC;
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* ---- vectors and matrices ---- */
WRDEF wr_vec2 wr_v2(double x, double y) {
    wr_vec2 r;
    r.x = x;
    r.y = y;
    return r;
}
WRDEF wr_vec2 wr_v2_add(wr_vec2 a, wr_vec2 b) { return wr_v2(a.x + b.x, a.y + b.y); }
WRDEF wr_vec2 wr_v2_sub(wr_vec2 a, wr_vec2 b) { return wr_v2(a.x - b.x, a.y - b.y); }
WRDEF wr_vec2 wr_v2_scale(wr_vec2 a, double s) { return wr_v2(a.x * s, a.y * s); }
WRDEF double wr_v2_dot(wr_vec2 a, wr_vec2 b) { return a.x * b.x + a.y * b.y; }
WRDEF double wr_v2_cross(wr_vec2 a, wr_vec2 b) { return a.x * b.y - a.y * b.x; }
WRDEF double wr_v2_norm(wr_vec2 a) { return hypot(a.x, a.y); }

WRDEF wr_vec3 wr_v3(double x, double y, double z) {
    wr_vec3 r;
    r.x = x;
    r.y = y;
    r.z = z;
    return r;
}
WRDEF wr_vec3 wr_v3_load(const double *p) { return wr_v3(p[0], p[1], p[2]); }
WRDEF void wr_v3_store(wr_vec3 a, double *p) {
    p[0] = a.x;
    p[1] = a.y;
    p[2] = a.z;
}
WRDEF wr_vec3 wr_v3_add(wr_vec3 a, wr_vec3 b) { return wr_v3(a.x + b.x, a.y + b.y, a.z + b.z); }
WRDEF wr_vec3 wr_v3_sub(wr_vec3 a, wr_vec3 b) { return wr_v3(a.x - b.x, a.y - b.y, a.z - b.z); }
WRDEF wr_vec3 wr_v3_scale(wr_vec3 a, double s) { return wr_v3(a.x * s, a.y * s, a.z * s); }
WRDEF double wr_v3_dot(wr_vec3 a, wr_vec3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
WRDEF wr_vec3 wr_v3_cross(wr_vec3 a, wr_vec3 b) {
    return wr_v3(a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x);
}
WRDEF double wr_v3_norm(wr_vec3 a) { return sqrt(wr_v3_dot(a, a)); }
WRDEF wr_vec3 wr_v3_normalized(wr_vec3 a) {
    double n = wr_v3_norm(a);
    return n > 0.0 ? wr_v3_scale(a, 1.0 / n) : a;
}

WRDEF wr_mat2 wr_m2(double a00, double a01, double a10, double a11) {
    wr_mat2 r;
    r.m[0][0] = a00;
    r.m[0][1] = a01;
    r.m[1][0] = a10;
    r.m[1][1] = a11;
    return r;
}
WRDEF wr_mat2 wr_m2_identity(void) { return wr_m2(1.0, 0.0, 0.0, 1.0); }
WRDEF wr_mat2 wr_m2_add(wr_mat2 a, wr_mat2 b) {
    return wr_m2(a.m[0][0] + b.m[0][0], a.m[0][1] + b.m[0][1], a.m[1][0] + b.m[1][0], a.m[1][1] + b.m[1][1]);
}
WRDEF wr_mat2 wr_m2_sub(wr_mat2 a, wr_mat2 b) {
    return wr_m2(a.m[0][0] - b.m[0][0], a.m[0][1] - b.m[0][1], a.m[1][0] - b.m[1][0], a.m[1][1] - b.m[1][1]);
}
WRDEF wr_mat2 wr_m2_scale(wr_mat2 a, double s) {
    return wr_m2(a.m[0][0] * s, a.m[0][1] * s, a.m[1][0] * s, a.m[1][1] * s);
}
WRDEF wr_mat2 wr_m2_mul(wr_mat2 a, wr_mat2 b) {
    return wr_m2(a.m[0][0] * b.m[0][0] + a.m[0][1] * b.m[1][0], a.m[0][0] * b.m[0][1] + a.m[0][1] * b.m[1][1],
                 a.m[1][0] * b.m[0][0] + a.m[1][1] * b.m[1][0], a.m[1][0] * b.m[0][1] + a.m[1][1] * b.m[1][1]);
}
WRDEF wr_mat2 wr_m2_transpose(wr_mat2 a) { return wr_m2(a.m[0][0], a.m[1][0], a.m[0][1], a.m[1][1]); }
WRDEF double wr_m2_det(wr_mat2 a) { return a.m[0][0] * a.m[1][1] - a.m[0][1] * a.m[1][0]; }
WRDEF double wr_m2_trace(wr_mat2 a) { return a.m[0][0] + a.m[1][1]; }
WRDEF wr_vec2 wr_m2_mulv(wr_mat2 a, wr_vec2 v) {
    return wr_v2(a.m[0][0] * v.x + a.m[0][1] * v.y, a.m[1][0] * v.x + a.m[1][1] * v.y);
}
WRDEF int wr_m2_inverse(wr_mat2 a, wr_mat2 *out) {
    double d = wr_m2_det(a);
    double s = fabs(a.m[0][0]) + fabs(a.m[0][1]) + fabs(a.m[1][0]) + fabs(a.m[1][1]);
    if (!(fabs(d) > WR__SINGULAR_ABS + WR__SINGULAR_REL * s * s)) return 0;
    *out = wr_m2(a.m[1][1] / d, -a.m[0][1] / d, -a.m[1][0] / d, a.m[0][0] / d);
    return 1;
}

WRDEF void wr_m2_sym_eig(wr_mat2 a, double lam[2], wr_vec2 vec[2]) {
    double p = a.m[0][0], q = a.m[1][1], r = 0.5 * (a.m[0][1] + a.m[1][0]);
    double half_diff = 0.5 * (p - q);
    double rad = hypot(half_diff, r);
    double mean = 0.5 * (p + q);
    double c, s, n;
    lam[0] = mean - rad;
    lam[1] = mean + rad;
    /* The larger eigenvector is (half_diff + rad, r) or, to avoid cancellation when half_diff < 0,
     * (r, rad - half_diff); both are the same direction up to scale. */
    if (rad == 0.0) {
        c = 1.0;
        s = 0.0;
    } else if (half_diff >= 0.0) {
        c = half_diff + rad;
        s = r;
    } else {
        c = r;
        s = rad - half_diff;
    }
    n = hypot(c, s);
    if (n > 0.0) {
        c /= n;
        s /= n;
    } else {
        c = 1.0;
        s = 0.0;
    }
    /* vec[1] is the eigenvector of lam[1]; vec[0] = rot(-90°) of it so that vec[1] = rot90(vec[0]). */
    vec[1] = wr_v2(c, s);
    vec[0] = wr_v2(s, -c);
}

WRDEF wr_mat3 wr_m3_identity(void) {
    wr_mat3 r;
    int i, j;
    for (i = 0; i < 3; ++i)
        for (j = 0; j < 3; ++j) r.m[i][j] = i == j ? 1.0 : 0.0;
    return r;
}
WRDEF wr_mat3 wr_m3_mul(wr_mat3 a, wr_mat3 b) {
    wr_mat3 r;
    int i, j;
    for (i = 0; i < 3; ++i)
        for (j = 0; j < 3; ++j) r.m[i][j] = a.m[i][0] * b.m[0][j] + a.m[i][1] * b.m[1][j] + a.m[i][2] * b.m[2][j];
    return r;
}
WRDEF wr_mat3 wr_m3_transpose(wr_mat3 a) {
    wr_mat3 r;
    int i, j;
    for (i = 0; i < 3; ++i)
        for (j = 0; j < 3; ++j) r.m[i][j] = a.m[j][i];
    return r;
}
WRDEF double wr_m3_det(wr_mat3 a) {
    return a.m[0][0] * (a.m[1][1] * a.m[2][2] - a.m[1][2] * a.m[2][1]) -
           a.m[0][1] * (a.m[1][0] * a.m[2][2] - a.m[1][2] * a.m[2][0]) +
           a.m[0][2] * (a.m[1][0] * a.m[2][1] - a.m[1][1] * a.m[2][0]);
}
WRDEF wr_vec3 wr_m3_mulv(wr_mat3 a, wr_vec3 v) {
    return wr_v3(a.m[0][0] * v.x + a.m[0][1] * v.y + a.m[0][2] * v.z,
                 a.m[1][0] * v.x + a.m[1][1] * v.y + a.m[1][2] * v.z,
                 a.m[2][0] * v.x + a.m[2][1] * v.y + a.m[2][2] * v.z);
}
WRDEF int wr_m3_inverse(wr_mat3 a, wr_mat3 *out) {
    double d = wr_m3_det(a), s = 0.0;
    wr_mat3 r;
    int i, j;
    for (i = 0; i < 3; ++i)
        for (j = 0; j < 3; ++j) s = fmax(s, fabs(a.m[i][j]));
    if (!(fabs(d) > WR__SINGULAR_ABS + WR__SINGULAR_REL * s * s * s)) return 0;
    r.m[0][0] = (a.m[1][1] * a.m[2][2] - a.m[1][2] * a.m[2][1]) / d;
    r.m[0][1] = (a.m[0][2] * a.m[2][1] - a.m[0][1] * a.m[2][2]) / d;
    r.m[0][2] = (a.m[0][1] * a.m[1][2] - a.m[0][2] * a.m[1][1]) / d;
    r.m[1][0] = (a.m[1][2] * a.m[2][0] - a.m[1][0] * a.m[2][2]) / d;
    r.m[1][1] = (a.m[0][0] * a.m[2][2] - a.m[0][2] * a.m[2][0]) / d;
    r.m[1][2] = (a.m[0][2] * a.m[1][0] - a.m[0][0] * a.m[1][2]) / d;
    r.m[2][0] = (a.m[1][0] * a.m[2][1] - a.m[1][1] * a.m[2][0]) / d;
    r.m[2][1] = (a.m[0][1] * a.m[2][0] - a.m[0][0] * a.m[2][1]) / d;
    r.m[2][2] = (a.m[0][0] * a.m[1][1] - a.m[0][1] * a.m[1][0]) / d;
    *out = r;
    return 1;
}

WRDEF void wr_dense_sym_eig(int n, const double *A, double *lam, double *V) {
    double a[WR_DENSE_MAX * WR_DENSE_MAX], v[WR_DENSE_MAX * WR_DENSE_MAX];
    int i, j, k, sweep;
    WR_ASSERT(n > 0 && n <= WR_DENSE_MAX);
    for (i = 0; i < n; ++i)
        for (j = 0; j < n; ++j) {
            a[i * n + j] = 0.5 * (A[i * n + j] + A[j * n + i]);
            v[i * n + j] = i == j ? 1.0 : 0.0;
        }
    for (sweep = 0; sweep < WR__JACOBI_MAX_SWEEPS; ++sweep) {
        double off = 0.0, diag = 0.0;
        for (i = 0; i < n; ++i) {
            diag += a[i * n + i] * a[i * n + i];
            for (j = i + 1; j < n; ++j) off += a[i * n + j] * a[i * n + j];
        }
        if (off <= WR__JACOBI_OFF_REL2 * diag || off == 0.0) break;
        for (i = 0; i < n; ++i)
            for (j = i + 1; j < n; ++j) {
                double apq = a[i * n + j], app, aqq, theta, t, c, s;
                if (apq == 0.0) continue;
                app = a[i * n + i];
                aqq = a[j * n + j];
                /* Rutishauser's stable rotation: t = sgn(θ)/(|θ| + sqrt(θ²+1)). */
                theta = (aqq - app) / (2.0 * apq);
                t = (theta >= 0.0 ? 1.0 : -1.0) / (fabs(theta) + sqrt(theta * theta + 1.0));
                c = 1.0 / sqrt(t * t + 1.0);
                s = t * c;
                for (k = 0; k < n; ++k) {
                    double akp = a[k * n + i], akq = a[k * n + j];
                    a[k * n + i] = c * akp - s * akq;
                    a[k * n + j] = s * akp + c * akq;
                }
                for (k = 0; k < n; ++k) {
                    double apk = a[i * n + k], aqk = a[j * n + k];
                    a[i * n + k] = c * apk - s * aqk;
                    a[j * n + k] = s * apk + c * aqk;
                }
                for (k = 0; k < n; ++k) {
                    double vkp = v[k * n + i], vkq = v[k * n + j];
                    v[k * n + i] = c * vkp - s * vkq;
                    v[k * n + j] = s * vkp + c * vkq;
                }
            }
    }
    /* selection sort, ascending, columns follow */
    for (i = 0; i < n; ++i) lam[i] = a[i * n + i];
    for (i = 0; i < n; ++i) {
        int m = i;
        for (j = i + 1; j < n; ++j)
            if (lam[j] < lam[m]) m = j;
        if (m != i) {
            double t = lam[i];
            lam[i] = lam[m];
            lam[m] = t;
            for (k = 0; k < n; ++k) {
                t = v[k * n + i];
                v[k * n + i] = v[k * n + m];
                v[k * n + m] = t;
            }
        }
    }
    if (V) memcpy(V, v, sizeof(double) * (size_t)(n * n));
}

WRDEF int wr_dense_project_spd(int n, double *A, double floor) {
    double lam[WR_DENSE_MAX], V[WR_DENSE_MAX * WR_DENSE_MAX];
    int i, j, k, raised = 0;
    wr_dense_sym_eig(n, A, lam, V);
    for (k = 0; k < n; ++k)
        if (lam[k] < floor) {
            lam[k] = floor;
            ++raised;
        }
    if (!raised) return 0;
    for (i = 0; i < n; ++i)
        for (j = 0; j < n; ++j) {
            double s = 0.0;
            for (k = 0; k < n; ++k) s += V[i * n + k] * lam[k] * V[j * n + k];
            A[i * n + j] = s;
        }
    return raised;
}

WRDEF double wr_polygon_area(const double *xy, int32_t n) {
    double a2 = 0.0;
    int32_t i;
    /* Fan of triangles (p0, p_i, p_{i+1}): the same sum as the shoelace, relative to p0. */
    for (i = 1; i + 1 < n; ++i) {
        double ux = xy[2 * i] - xy[0], uy = xy[2 * i + 1] - xy[1];
        double vx = xy[2 * i + 2] - xy[0], vy = xy[2 * i + 3] - xy[1];
        a2 += ux * vy - uy * vx;
    }
    return 0.5 * a2;
}

WRDEF int wr_point_in_polygon(const double *xy, int32_t n, double x, double y) {
    int32_t i, j;
    int in = 0;
    if (n < 3) return 0;
    for (i = 0, j = n - 1; i < n; j = i++) {
        double xi = xy[2 * i], yi = xy[2 * i + 1], xj = xy[2 * j], yj = xy[2 * j + 1];
        /* the half-open rule never divides by yi - yj == 0 */
        if ((yi > y) != (yj > y) && x < xj + (y - yj) * (xi - xj) / (yi - yj)) in = !in;
    }
    return in;
}

WRDEF double wr_segment_distance(const double p[2], const double a[2], const double b[2], double *t) {
    double ex = b[0] - a[0], ey = b[1] - a[1], ee = ex * ex + ey * ey, u = 0.0, dx, dy;
    if (ee > 0.0) {
        u = ((p[0] - a[0]) * ex + (p[1] - a[1]) * ey) / ee;
        u = u < 0.0 ? 0.0 : (u > 1.0 ? 1.0 : u);
    }
    if (t) *t = u;
    if (u > 0.0 && u < 1.0) return fabs(ex * (p[1] - a[1]) - ey * (p[0] - a[0])) / sqrt(ee);
    dx = a[0] + u * ex - p[0];
    dy = a[1] + u * ey - p[1];
    return sqrt(dx * dx + dy * dy);
}

#ifdef __cplusplus
}
#endif
#endif /* WRINKLE_CORE_IMPLEMENTATION_DONE */
#endif /* WRINKLE_IMPLEMENTATION */
