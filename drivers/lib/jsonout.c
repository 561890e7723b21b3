/* jsonout.c — see jsonout.h. */
#include "jsonout.h"

#include <stdio.h>
#include <string.h>

wr_status wr_json_write(const cJSON *root, const char *path, wr_diag *diag) {
    char *text = cJSON_Print(root);
    wr_status st = WR_OK;
    if (!text) return wr_fail(diag, WR_ERR_NOMEM, -1, "out of memory printing JSON for '%s'", path ? path : "-");
    if (!path || strcmp(path, "-") == 0) {
        if (fputs(text, stdout) < 0 || fputc('\n', stdout) == EOF || fflush(stdout) != 0)
            st = wr_fail(diag, WR_ERR_IO, -1, "writing JSON to standard output failed");
    } else {
        wr_afile f;
        st = wr_afile_open(&f, path, diag);
        if (st == WR_OK) {
            fputs(text, f.fp);
            fputc('\n', f.fp);
            st = wr_afile_commit(&f, diag); /* checks the stream's error flag */
        }
    }
    cJSON_free(text);
    return st;
}
