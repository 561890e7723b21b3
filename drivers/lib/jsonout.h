/* jsonout.h — write one cJSON document, the way every wrinkle driver does (compiled once as
 * drivers/lib/jsonout.c and linked into every program; installed with the format readers as
 * <wrinkle/formats/jsonout.h> in libwrinkle-formats.a, which scene.c uses).
 *
 *   wr_json_write(root, path, diag)   indented JSON + newline; path "-" (or NULL) = stdout, any other
 *                                     path through wr_afile (temporary + rename: the file appears whole
 *                                     or not at all). root stays owned by the caller.
 * Errors: WR_ERR_NOMEM when cJSON cannot print, WR_ERR_IO (message names the path) when the file
 * cannot be written or stdout fails.
 */
#ifndef WRINKLE_JSONOUT_H
#define WRINKLE_JSONOUT_H

#include <cjson/cJSON.h>

#include "wrinkle/core.h"

wr_status wr_json_write(const cJSON *root, const char *path, wr_diag *diag);

#endif
