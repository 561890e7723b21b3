/* cli.c — see cli.h. */
#include "cli.h"

#include <ctype.h>
#include <errno.h>
#include <limits.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* Driver-side only: one program name per process, set once at the start of main. */
static char wr__cli_prog[128] = "wrinkle";

void wr_cli_set_program(const char *argv0) {
    const char *b;
    if (!argv0 || !*argv0) return;
    b = strrchr(argv0, '/');
    snprintf(wr__cli_prog, sizeof wr__cli_prog, "%s", b ? b + 1 : argv0);
}

const char *wr_cli_program(void) { return wr__cli_prog; }

void wr_cli_error(const char *fmt, ...) {
    char msg[1024];
    size_t k;
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    for (k = 0; msg[k]; ++k)
        if (msg[k] == '\n' || msg[k] == '\r') msg[k] = ' ';
    fprintf(stderr, "%s: %s\n", wr__cli_prog, msg);
}

int wr_cli_parse_double(const char *s, double *out) {
    char *end;
    double v;
    size_t k;
    if (!s || !*s) return 0;
    /* strtod would also take hex floats, "inf", "nan" and leading blanks: allow only the plain
     * decimal alphabet so that a typo never turns into a number. */
    for (k = 0; s[k]; ++k)
        if (!isdigit((unsigned char)s[k]) && !strchr("+-.eE", s[k])) return 0;
    errno = 0;
    v = strtod(s, &end);
    if (end == s || *end != '\0' || !isfinite(v)) return 0;
    if (errno == ERANGE && v != 0.0) return 0; /* overflow (underflow to a tiny value is accepted) */
    *out = v;
    return 1;
}

int wr_cli_parse_long(const char *s, long *out) {
    char *end;
    long v;
    size_t k;
    if (!s || !*s) return 0;
    for (k = 0; s[k]; ++k)
        if (!isdigit((unsigned char)s[k]) && !(k == 0 && (s[k] == '-' || s[k] == '+'))) return 0;
    errno = 0;
    v = strtol(s, &end, 10);
    if (end == s || *end != '\0' || errno == ERANGE) return 0;
    *out = v;
    return 1;
}

int wr_cli_is_flag(const char *arg, const char *name) { return arg && name && strcmp(arg, name) == 0; }

int wr_cli_value(int argc, char **argv, int *i, const char *name, const char **value) {
    const char *a = argv[*i];
    size_t n = strlen(name);
    if (strncmp(a, name, n) != 0) return 0;
    if (a[n] == '=') {
        *value = a + n + 1;
        return 1;
    }
    if (a[n] != '\0') return 0; /* a longer option sharing the prefix */
    if (*i + 1 >= argc) {
        wr_cli_error("option %s needs a value", name);
        return -1;
    }
    *i += 1;
    *value = argv[*i];
    return 1;
}

int wr_cli_double(int argc, char **argv, int *i, const char *name, double *out) {
    const char *v;
    int k = wr_cli_value(argc, argv, i, name, &v);
    if (k <= 0) return k;
    if (!wr_cli_parse_double(v, out)) {
        wr_cli_error("%s: malformed number '%s'", name, v);
        return -1;
    }
    return 1;
}

int wr_cli_integer(int argc, char **argv, int *i, const char *name, double lo, double hi, double *out) {
    double x;
    int k = wr_cli_double(argc, argv, i, name, &x);
    if (k <= 0) return k;
    if (!(x >= lo && x <= hi) || x != floor(x)) {
        wr_cli_error("%s must be an integer in [%.0f, %.0f]", name, lo, hi);
        return -1;
    }
    *out = x;
    return 1;
}

int wr_cli_scene_arg(int argc, char **argv, int *i, const char **scene_path, const char **out) {
    const char *v;
    int k;
    if ((k = wr_cli_value(argc, argv, i, "-o", &v)) != 0 || (k = wr_cli_value(argc, argv, i, "--output", &v)) != 0) {
        if (k < 0) return -1;
        *out = v;
        return 1;
    }
    if (argv[*i][0] == '-' && argv[*i][1] != 0) { /* a lone "-" is a file name (stdin) */
        wr_cli_error("unknown option '%s' (see --help)", argv[*i]);
        return -1;
    }
    if (*scene_path) {
        wr_cli_error("more than one scene file ('%s', '%s')", *scene_path, argv[*i]);
        return -1;
    }
    *scene_path = argv[*i];
    return 1;
}

int wr_cli_scene_args_ok(const char *scene_path, const char *out) {
    if (scene_path && out) return 1;
    wr_cli_error("need SCENE.json and -o DIR (see --help)");
    return 0;
}
