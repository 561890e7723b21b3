/* cli.c — see cli.h. */
#define _POSIX_C_SOURCE 200809L
#include "cli.h"

#include <ctype.h>
#include <errno.h>
#include <limits.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <sys/stat.h>
#include <unistd.h>

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
    wr_cli_progress_end(); /* the reason on its own line, not after an open terminal progress line */
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

double wr_cli_cpu_seconds(void) {
    struct timespec ts;
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

double wr_cli_load1(void) {
    double l = NAN;
    FILE *f = fopen("/proc/loadavg", "r");
    if (f) {
        if (fscanf(f, "%lf", &l) != 1) l = NAN;
        fclose(f);
    }
    return l;
}

int wr_cli_scene_args_ok(const char *scene_path, const char *out) {
    if (scene_path && out) return 1;
    wr_cli_error("need SCENE.json and -o DIR (see --help)");
    return 0;
}

/* ---- the shared argument loop ------------------------------------------------------------------- */

static int cli_take(int argc, char **argv, int *i, const wr_cli_opt *o) {
    const char *v;
    int k = 0;
    if (o->kind == WR_CLI_FLAG) {
        if (!wr_cli_is_flag(argv[*i], o->name) && !(o->alias && wr_cli_is_flag(argv[*i], o->alias))) return 0;
        *(int *)o->out = 1;
        return 1;
    }
    if ((k = wr_cli_value(argc, argv, i, o->name, &v)) == 0 && o->alias) k = wr_cli_value(argc, argv, i, o->alias, &v);
    if (k <= 0) return k;
    if (o->kind == WR_CLI_STRING) {
        if (!*v) {
            wr_cli_error("%s needs a non-empty value", o->name);
            return -1;
        }
        *(const char **)o->out = v;
        return 1;
    }
    {
        double x;
        if (!wr_cli_parse_double(v, &x)) {
            wr_cli_error("%s: malformed number '%s'", o->name, v);
            return -1;
        }
        if (o->kind == WR_CLI_INTEGER && (!(x >= o->lo && x <= o->hi) || x != floor(x))) {
            wr_cli_error("%s must be an integer in [%.0f, %.0f], got '%s'", o->name, o->lo, o->hi, v);
            return -1;
        }
        if (o->kind == WR_CLI_NUMBER && o->lo <= o->hi && !(x >= o->lo && x <= o->hi)) {
            wr_cli_error("%s must be in [%g, %g], got '%s'", o->name, o->lo, o->hi, v);
            return -1;
        }
        *(double *)o->out = x;
    }
    return 1;
}

int wr_cli_parse(int argc, char **argv, const wr_cli_opt *opts, int n_opts, const char **pos, int max_pos, int *n_pos,
                 void (*usage)(FILE *)) {
    int i, j, k;
    if (n_pos) *n_pos = 0;
    for (i = 1; i < argc; ++i) {
        if (wr_cli_is_flag(argv[i], "--help") || wr_cli_is_flag(argv[i], "-h")) {
            if (usage) usage(stdout);
            return 0;
        }
    }
    for (i = 1; i < argc; ++i) {
        for (j = 0, k = 0; j < n_opts && k == 0; ++j)
            if ((k = cli_take(argc, argv, &i, &opts[j])) > 0 && opts[j].given) *opts[j].given = 1;
        if (k < 0) return -1;
        if (k > 0) continue;
        if (argv[i][0] == '-' && argv[i][1] != 0) {
            wr_cli_error("unknown option '%s' (see --help)", argv[i]);
            return -1;
        }
        if (!n_pos || *n_pos >= max_pos) {
            if (max_pos == 0)
                wr_cli_error("unexpected argument '%s' (see --help)", argv[i]);
            else
                wr_cli_error("too many file arguments ('%s'; see --help)", argv[i]);
            return -1;
        }
        pos[(*n_pos)++] = argv[i];
    }
    return 1;
}

/* ---- cleanup ------------------------------------------------------------------------------------- */

/* Driver-side only, like the program name: one process, one main. */
static struct {
    void (*fn)(void *);
    void *p;
} wr__cli_defer[WR_CLI_MAX_DEFER];
static int wr__cli_n_defer;

void wr_cli_defer(void (*fn)(void *), void *p) {
    if (wr__cli_n_defer < WR_CLI_MAX_DEFER) {
        wr__cli_defer[wr__cli_n_defer].fn = fn;
        wr__cli_defer[wr__cli_n_defer].p = p;
        ++wr__cli_n_defer;
    }
}

int wr_cli_exit(int code) {
    while (wr__cli_n_defer > 0) {
        --wr__cli_n_defer;
        wr__cli_defer[wr__cli_n_defer].fn(wr__cli_defer[wr__cli_n_defer].p);
    }
    wr_cli_progress_end();
    /* "done" (0) and "done with a caveat" (1) both claim the results were delivered: a lost stdout
     * makes either a failure; a usage error (2) stays what it is. */
    if (!wr_cli_stdout_ok() && code < WR_CLI_EXIT_USAGE) code = WR_CLI_EXIT_FAILURE;
    return code;
}

/* ---- progress, warnings, numbers ---------------------------------------------------------------- */

static int wr__cli_tty = -1, wr__cli_open_line;

int wr_cli_progress_tty(void) {
    if (wr__cli_tty < 0) wr__cli_tty = isatty(fileno(stderr)) ? 1 : 0;
    return wr__cli_tty;
}

void wr_cli_progress(const char *fmt, ...) {
    char msg[512];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    if (wr_cli_progress_tty()) {
        fprintf(stderr, "\r%-100s", msg); /* padded: a shorter line covers the previous one */
        wr__cli_open_line = 1;
    } else {
        fprintf(stderr, "%s\n", msg);
    }
    fflush(stderr);
}

void wr_cli_progress_end(void) {
    if (wr__cli_open_line) fputc('\n', stderr);
    wr__cli_open_line = 0;
}

void wr_cli_warn(const char *fmt, ...) {
    char msg[1024];
    size_t k;
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    for (k = 0; msg[k]; ++k)
        if (msg[k] == '\n' || msg[k] == '\r') msg[k] = ' ';
    wr_cli_progress_end();
    fprintf(stderr, "%s: warning: %s\n", wr__cli_prog, msg);
}

const char *wr_cli_num(char *buf, size_t n, const char *fmt, double x) {
    if (!isfinite(x))
        snprintf(buf, n, "n/a");
    else
        snprintf(buf, n, fmt, x);
    return buf;
}

int wr_cli_stdout_ok(void) {
    if (fflush(stdout) == 0 && !ferror(stdout)) return 1;
    wr_cli_error("writing standard output failed (%s)", errno ? strerror(errno) : "disk full or closed pipe?");
    return 0;
}

/* ---- outputs ------------------------------------------------------------------------------------- */

int wr_cli_output_ok(const char *out, const char *const *inputs, int n_inputs) {
    struct stat so, si;
    int k;
    if (!out || stat(out, &so) != 0) return 1; /* does not exist yet: nothing to clash with */
    if (!S_ISREG(so.st_mode) && !S_ISDIR(so.st_mode)) {
        wr_cli_error("refusing to write '%s': it is not a regular file (a device or pipe would be replaced)", out);
        return 0;
    }
    for (k = 0; k < n_inputs; ++k)
        if (inputs[k] && stat(inputs[k], &si) == 0 && si.st_dev == so.st_dev && si.st_ino == so.st_ino) {
            wr_cli_error("refusing to write '%s': it is the input file '%s'", out, inputs[k]);
            return 0;
        }
    return 1;
}

int wr_cli_dir_outputs_ok(const char *dir, const char *const *names, int n_names, const char *const *inputs,
                          int n_inputs) {
    char p[4096];
    struct stat sd;
    int k;
    if (!wr_cli_output_ok(dir, inputs, n_inputs)) return 0;
    /* checked before any work: an existing file given as -o DIR is bad input, not a write failure
     * found after the run */
    if (stat(dir, &sd) == 0 && !S_ISDIR(sd.st_mode)) {
        wr_cli_error("output directory '%s' exists and is not a directory", dir);
        return 0;
    }
    for (k = 0; k < n_names; ++k) {
        if (snprintf(p, sizeof p, "%s/%s", dir, names[k]) >= (int)sizeof p) {
            wr_cli_error("output path too long: '%s'", dir);
            return 0;
        }
        if (!wr_cli_output_ok(p, inputs, n_inputs)) return 0;
    }
    return 1;
}
