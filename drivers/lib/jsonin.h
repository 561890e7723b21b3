/* jsonin.h — the strict JSON readers of the drivers' scene formats (defined in drivers/lib/scene.c,
 * used by scene.c and simscene.c; needs cJSON). Every error is WR_ERR_PARSE with one line naming the
 * JSON path ("$.time.dt: must be > 0 (got -1)"); control characters in keys and strings from the
 * file are shown as \xHH so the message stays one line. Not an installed header. */
#ifndef WRINKLE_DRIVERS_JSONIN_H
#define WRINKLE_DRIVERS_JSONIN_H

#include <stddef.h>

#include <cjson/cJSON.h>

#include "wrinkle/core.h"

typedef struct wr_jin {
    wr_diag *diag;
} wr_jin;

/* number rules of wr_jin_num: finite, > 0, >= 0 */
enum { WR_JIN_ANY = 0, WR_JIN_POS = 1, WR_JIN_NONNEG = 2 };

/* "<path>: <message>" into c->diag; returns WR_ERR_PARSE */
wr_status wr_jin_err(wr_jin *c, const char *path, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 3, 4)))
#endif
    ;
/* out = "<base>.<key>" */
void wr_jin_path(char *out, size_t n, const char *base, const char *key);
/* obj must be an object whose keys are all in the NULL-terminated list */
wr_status wr_jin_keys(wr_jin *c, const cJSON *obj, const char *path, const char *const *allowed);
/* Optional values (absent: *out unchanged, *found = 0 where given). */
wr_status wr_jin_num(wr_jin *c, const cJSON *obj, const char *key, const char *path, int rule, double *out, int *found);
wr_status wr_jin_int(wr_jin *c, const cJSON *obj, const char *key, const char *path, long lo, long hi, int32_t *out,
                     int *found);
wr_status wr_jin_vec(wr_jin *c, const cJSON *obj, const char *key, const char *path, int n, double *out, int *found);
wr_status wr_jin_bool(wr_jin *c, const cJSON *obj, const char *key, const char *path, int *out);
/* the string must be one of names (NULL-terminated); *out = its index */
wr_status wr_jin_enum(wr_jin *c, const cJSON *obj, const char *key, const char *path, const char *const *names, int *out,
                      int required);
/* The keys of an analytic obstacle whose kind the caller has set (plane: point, normal ≠ 0; sphere:
 * center, radius > 0; capsule: p, q, radius > 0), all required; shared by both scene formats'
 * $.obstacles[k]. Other keys are the caller's to check. */
struct wr_obstacle;
wr_status wr_jin_analytic_obstacle(wr_jin *c, const cJSON *obj, const char *path, struct wr_obstacle *o);
/* a non-empty string of at most cap − 1 bytes */
wr_status wr_jin_str(wr_jin *c, const cJSON *obj, const char *key, const char *path, char *out, size_t cap, int required);

#endif
