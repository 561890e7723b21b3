/* vargs.h — the command line of the validation drivers that take no options or only on/off flags:
 * `--help` says what the driver reproduces and where it writes, and exits 0; an unknown argument is
 * refused with exit 2 and a one-line message (as the wrinkle-* drivers do) instead of being ignored,
 * because a validation run rewrites its result file: `validate_x --help` must not cost a run and a
 * rewritten result. Static function only. */
#ifndef WRINKLE_VALIDATION_VARGS_H
#define WRINKLE_VALIDATION_VARGS_H

#include <stdio.h>
#include <string.h>

/* Reads argv[1..argc). flags: NULL-terminated list of accepted flags (may be NULL: none), each
 * described in flag_help (may be NULL); set[k] (may be NULL when flags is) becomes 1 when flags[k] is
 * given. Returns -1 when the driver should run, otherwise the exit code to return (0 after --help,
 * 2 for an unknown argument). what: one line on what the driver reproduces; case_id: its result
 * file's name (validation/results/<case_id>.json, or under $WRINKLE_RESULTS_DIR). */
static inline int wr_vargs(int argc, char **argv, const char *name, const char *what, const char *case_id,
                           const char *const *flags, const char *flag_help, int *set) {
    int i, k;
    for (k = 0; flags && flags[k]; ++k) set[k] = 0;
    for (i = 1; i < argc; ++i) {
        int known = 0;
        if (strcmp(argv[i], "--help") == 0 || strcmp(argv[i], "-h") == 0) {
            printf("usage: %s", name);
            for (k = 0; flags && flags[k]; ++k) printf(" [%s]", flags[k]);
            printf("\n  %s\n  Writes validation/results/%s.json (or under $WRINKLE_RESULTS_DIR) and its figures;\n"
                   "  `make validate` runs it and rebuilds validation/REPORT.md.\n%s",
                   what, case_id, flag_help ? flag_help : "");
            return 0;
        }
        for (k = 0; flags && flags[k]; ++k)
            if (strcmp(argv[i], flags[k]) == 0) set[k] = known = 1;
        if (!known) {
            fprintf(stderr, "%s: unknown argument '%s' (see --help)\n", name, argv[i]);
            return 2;
        }
    }
    return -1;
}

#endif /* WRINKLE_VALIDATION_VARGS_H */
