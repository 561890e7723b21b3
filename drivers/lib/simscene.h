/* simscene.h — the JSON scene format of bin/wrinkle-sim (driver-side helper, not a public wrinkle
 * header; compiled once as drivers/lib/simscene.c, linked into every program, needs cJSON).
 * The format is documented in docs/sim-scene-format.md; examples in examples/sim/.
 *
 * Pipeline (each step fallible, errors as wr_status + wr_diag like the library):
 *   wr_simscene_parse(sc, text, len, base_dir, diag)  JSON text → wr_simscene (no file access).
 *                                  Errors are WR_ERR_PARSE with one line naming the JSON path, e.g.
 *                                  "$.time.dt: must be > 0 (got -1)".
 *   wr_simscene_load(sc, path, diag)      read a file, then parse (base_dir = its directory)
 *   wr_simscene_run_create(run, sc, diag) cloth mesh and shell, placement, pins, obstacles, the sim
 *   wr_simscene_run_frames(run, frame_fn, user, diag)  every frame to the scene's duration
 *   wr_simscene_write_frame(run, dir, k, diag)   DIR/frame_%04d.obj|ply (atomic)
 *   wr_simscene_write_summary(run, path, diag)   summary JSON (atomic)
 *   wr_simscene_run_free(run) / wr_simscene_free(sc)
 *
 * Memory: wr_simscene owns its index lists (wr_simscene_free); wr_simscene_run owns mesh, shell,
 * state, sim and the per-frame records (wr_simscene_run_free). Both are safe to free when zeroed or
 * after a failed create/parse.
 */
#ifndef WRINKLE_SIMSCENE_H
#define WRINKLE_SIMSCENE_H

#include "wrinkle/wrinkle.h"

#define WR_SIMSCENE_NAME_LEN 64
#define WR_SIMSCENE_PATH_LEN 1024
#define WR_SIMSCENE_MAX_PINS 16
#define WR_SIMSCENE_MAX_OBSTACLES 16
/* a generated cloth mesh may not exceed this (a typo like "resolution": 1e-6 must not allocate GBs) */
#define WR_SIMSCENE_MAX_VERTICES 2000000
/* frames a scene may ask for (duration / dt): 10 min at 30 fps */
#define WR_SIMSCENE_MAX_FRAMES 18000

typedef enum wr_simscene_mesh_kind {
    WR_SIMSCENE_MESH_RECTANGLE = 0, /* wr_mesh_rectangle in its rest plane z = 0 */
    WR_SIMSCENE_MESH_DISK,          /* wr_mesh_disk */
    WR_SIMSCENE_MESH_OBJ            /* Wavefront OBJ (vt = rest coordinates) */
} wr_simscene_mesh_kind;

typedef struct wr_simscene_pin {
    int select_box;            /* 1: box, 0: indices */
    double lo[3], hi[3];       /* inclusive box on the PLACED initial positions [m] */
    int32_t *indices;          /* owned */
    int32_t n_indices;
} wr_simscene_pin;

typedef struct wr_simscene_cloth {
    wr_simscene_mesh_kind kind;
    char path[WR_SIMSCENE_PATH_LEN];
    double width, height, radius, resolution;
    int32_t nx, ny;
    wr_shell_desc shell;
    double areal_density;
    double rotate_axis[3], rotate_angle; /* placement: rotation about the origin [rad], then ... */
    double translate[3];                 /* ... translation [m] */
    double velocity[3];                  /* initial velocity [m/s] */
    wr_simscene_pin pin[WR_SIMSCENE_MAX_PINS];
    int32_t n_pins;
} wr_simscene_cloth;

typedef struct wr_simscene {
    char name[WR_SIMSCENE_NAME_LEN];
    wr_simscene_cloth cloth;
    wr_obstacle analytic[WR_SIMSCENE_MAX_OBSTACLES];
    int32_t n_analytic;
    double duration;        /* [s] */
    wr_dyn_desc dyn;        /* pointer fields unset (filled by run_create) */
    int32_t output_every;   /* write every Nth frame (frame 0 = the initial state is always written) */
    int output_ply;         /* 0: OBJ, 1: PLY */
} wr_simscene;

typedef struct wr_simscene_frame {
    double t, t_ns, t_ch, t_total, residual_rel, min_distance, h_min;
    int32_t newton, pcg, line_search, contacts, halvings, steps;
    wr_newton_stop stop;
} wr_simscene_frame;

typedef struct wr_simscene_run {
    const wr_simscene *sc; /* borrowed */
    wr_mesh mesh;          /* rest mesh; pos = the placed initial positions */
    wr_shell shell;
    uint8_t *fixed;
    int32_t n_fixed;
    double *x, *v;
    wr_dyn sim;
    wr_dyn_state state;
    wr_simscene_frame *frames; /* n_frames_max */
    int32_t n_frames, n_frames_max;
    wr_status status;          /* of the run (WR_OK or the failing step's status) */
    char status_message[WR_DIAG_MESSAGE_LEN];
    double t_setup, t_run;
} wr_simscene_run;

/* Called after every frame k (1-based, frame 0 is the initial state); nonzero stops the run. */
typedef int (*wr_simscene_frame_fn)(void *user, const wr_simscene_run *run, int32_t k);

void wr_simscene_defaults(wr_simscene *sc);
wr_status wr_simscene_parse(wr_simscene *sc, const char *text, size_t len, const char *base_dir, wr_diag *diag);
wr_status wr_simscene_load(wr_simscene *sc, const char *path, wr_diag *diag);
void wr_simscene_free(wr_simscene *sc);

wr_status wr_simscene_run_create(wr_simscene_run *run, const wr_simscene *sc, wr_diag *diag);
/* Runs to sc->duration. A failed step ends the run: its status is returned and kept in run->status,
 * the frames before it stay recorded. */
wr_status wr_simscene_run_frames(wr_simscene_run *run, wr_simscene_frame_fn fn, void *user, wr_diag *diag);
wr_status wr_simscene_write_frame(const wr_simscene_run *run, const char *dir, int32_t k, wr_diag *diag);
/* The name frame k gets in DIR ("frame_0007.obj"); out must hold 32 bytes. */
void wr_simscene_frame_name(const wr_simscene *sc, int32_t k, char *out);
wr_status wr_simscene_write_summary(const wr_simscene_run *run, const char *path, wr_diag *diag);
void wr_simscene_run_free(wr_simscene_run *run);

#endif
