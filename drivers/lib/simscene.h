/* simscene.h — the JSON scene format of bin/wrinkle-sim (driver-side helper, not a public wrinkle
 * header; compiled once as drivers/lib/simscene.c, linked into every program, needs cJSON).
 * The format is documented in docs/sim-scene-format.md; examples in examples/sim/.
 *
 * Pipeline (each step fallible, errors as wr_status + wr_diag like the library):
 *   wr_simscene_parse(sc, text, len, base_dir, diag)  JSON text → wr_simscene (no file access).
 *                                  Errors are WR_ERR_PARSE with one line naming the JSON path, e.g.
 *                                  "$.time.dt: must be > 0 (got -1)".
 *   wr_simscene_load(sc, path, diag)      read a file, then parse (base_dir = its directory)
 *   wr_simscene_run_create(run, sc, diag) cloth mesh and shell (or the garment: pattern → mesher →
 *                                  placement → sewing, garment.h), placement, pins, the body and
 *                                  the obstacles, the sim
 *   wr_simscene_run_frames(run, frame_fn, user, diag)  every frame to the scene's duration
 *   wr_simscene_write_frame(run, dir, k, diag)   DIR/frame_%04d.obj|ply (atomic)
 *   wr_simscene_write_welded(run, path, diag)  a garment's current state as one sewn OBJ: the seam
 *                                  pairs merged (mesh.h wr_mesh_weld, positions averaged), per-corner
 *                                  vt = each panel's pattern corners, g = panel names (atomic)
 *   wr_simscene_write_png(run, dir, k, diag)     DIR/frame_%04d.png: front and 3/4 views, cloth
 *                                  over the triangle-mesh bodies (render.h, atomic)
 *   wr_simscene_write_bodies(run, dir, diag)     DIR/body.obj: every triangle-mesh body/obstacle
 *                                  at its first pose (atomic; nothing when there is none)
 *   wr_simscene_write_summary(run, path, diag)   summary JSON (atomic)
 *   wr_simscene_inputs(sc, list, max)            the input files a scene reads (for the driver's
 *                                  never-overwrite-an-input check)
 *   wr_simscene_run_free(run) / wr_simscene_free(sc)
 *
 * A garment's frames are written on the pattern mesh's vertices (the unsewn topology, the same in
 * every frame, so a viewer can play them as one animation): after the weld the two vertices of a
 * seam pair carry the same position.
 *
 * Memory: wr_simscene owns its index lists, placements and body paths (wr_simscene_free);
 * wr_simscene_run owns mesh, shell, state, sim, the garment, bodies and the per-frame records
 * (wr_simscene_run_free). Both are safe to free when zeroed or after a failed create/parse.
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
/* OBJ files of a keyframed body (one per key) */
#define WR_SIMSCENE_MAX_BODY_KEYS 4096
#define WR_SIMSCENE_MAX_INPUTS (3 + WR_SIMSCENE_MAX_OBSTACLES)

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

/* One panel's placement ($.garment.placements[i]); panel by name or index, resolved against the
 * pattern at run_create. */
typedef struct wr_simscene_placement {
    char panel[WR_SIMSCENE_NAME_LEN]; /* name, or "" when given by index */
    int32_t panel_index;              /* -1 when given by name */
    wr_garment_placement pl;
    int has_origin;                   /* else: bottom centre of the panel's pattern bounding box */
    char part[32];                    /* cylinder around a mannequin part ("" = explicit axis) */
    double offset;                    /* along the part's axis from its start [m] */
} wr_simscene_placement;

typedef struct wr_simscene_garment {
    char pattern[WR_SIMSCENE_PATH_LEN]; /* pattern JSON (docs/pattern-format.md), resolved path */
    double resolution;                  /* > 0: uniform mesh resolution [m] overriding the pattern */
    int has_seed;
    int32_t seed;
    wr_shell_desc shell;
    double areal_density;
    wr_simscene_placement *placements; /* owned */
    int32_t n_placements;
    wr_garment_desc sewing;             /* also the gathering settings (thread_area, gather_time, ...) and the
                                           gravity hold ($.garment.gravity_hold: gravity_delay, gravity_ramp) */
    int no_gathering;                   /* $.garment.gathering.enabled = false */
    double velocity[3];
    wr_simscene_pin pin[WR_SIMSCENE_MAX_PINS];
    int32_t n_pins;
} wr_simscene_garment;

typedef enum wr_simscene_body_kind {
    WR_SIMSCENE_BODY_NONE = 0,
    WR_SIMSCENE_BODY_MANNEQUIN, /* body.h's procedural figure */
    WR_SIMSCENE_BODY_OBJ,       /* a static OBJ */
    WR_SIMSCENE_BODY_SEQUENCE   /* OBJ keyframes (same topology) at given times */
} wr_simscene_body_kind;

typedef struct wr_simscene_body {
    wr_simscene_body_kind kind;
    wr_body_desc mannequin;
    char path[WR_SIMSCENE_PATH_LEN];
    char (*paths)[WR_SIMSCENE_PATH_LEN]; /* sequence: n_keys resolved paths (owned) */
    double *times;                        /* sequence: n_keys increasing times [s] (owned) */
    int32_t n_keys;
} wr_simscene_body;

typedef struct wr_simscene {
    char name[WR_SIMSCENE_NAME_LEN];
    int is_garment;                 /* $.garment instead of $.cloth */
    wr_simscene_cloth cloth;
    wr_simscene_garment garment;
    wr_simscene_body body;
    wr_obstacle analytic[WR_SIMSCENE_MAX_OBSTACLES];
    int32_t n_analytic;
    char mesh_obstacle[WR_SIMSCENE_MAX_OBSTACLES][WR_SIMSCENE_PATH_LEN]; /* {"type": "mesh"} OBJ paths */
    int32_t mesh_obstacle_index[WR_SIMSCENE_MAX_OBSTACLES];             /* their $.obstacles index */
    int32_t n_mesh_obstacles;
    double duration;        /* [s] */
    wr_dyn_desc dyn;        /* pointer fields unset (filled by run_create) */
    int32_t output_every;   /* write every Nth frame (frame 0 = the initial state is always written) */
    int output_ply;         /* 0: OBJ, 1: PLY */
} wr_simscene;

typedef struct wr_simscene_frame {
    double t, t_ns, t_ch, t_total, residual_rel, min_distance, h_min;
    double seam_gap; /* garment: largest seam-pair distance after the frame [m] (0 once welded) */
    int32_t welded;  /* garment: 1 once welded */
    double gravity_scale; /* garment: the gravity factor of the frame (garment.h ON HOLDING; 1 without a hold) */
    int32_t newton, pcg, line_search, contacts, halvings, steps;
    wr_newton_stop stop;
} wr_simscene_frame;

typedef struct wr_simscene_run {
    const wr_simscene *sc; /* borrowed */
    wr_mesh mesh;          /* rest mesh; pos = the placed initial positions (garment: the pattern mesh) */
    wr_shell shell;        /* cloth scenes (a garment's shell is gs.shell) */
    uint8_t *fixed;
    int32_t n_fixed;
    double *x, *v;         /* cloth: the state; garment: x = positions on the pattern mesh's vertices */
    wr_dyn sim;            /* cloth scenes */
    wr_dyn_state state;
    wr_garment_sim gs;     /* garment scenes */
    wr_mesher_result mr;   /* the garment's pattern mesh and seams */
    char **panel_names;    /* the pattern's panel names (owned copies) */
    int32_t n_panels;
    wr_garment_line *glines; /* the pattern's shirring lines, then its quilt stitches (garment.h ON GATHERING) */
    int32_t **gline_verts;   /* their vertex chains (owned) */
    double **gline_xy;       /* their pattern polylines (owned copies: the stitch points of a stitch_length) */
    int32_t n_glines;
    wr_mesh bodies[1 + WR_SIMSCENE_MAX_OBSTACLES]; /* triangle-mesh bodies: $.body, then mesh obstacles */
    wr_dyn_body dbodies[1 + WR_SIMSCENE_MAX_OBSTACLES];
    double *body_key_pos, *body_key_time; /* a keyframed $.body */
    int32_t n_bodies;
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
wr_status wr_simscene_write_welded(const wr_simscene_run *run, const char *path, wr_diag *diag);
wr_status wr_simscene_write_png(const wr_simscene_run *run, const char *dir, int32_t k, wr_diag *diag);
wr_status wr_simscene_write_bodies(const wr_simscene_run *run, const char *dir, wr_diag *diag);
/* The simulator of the run (the cloth's, or the garment's current one). */
const wr_dyn *wr_simscene_dyn(const wr_simscene_run *run);
/* Fills list[0..n) with the input paths (scene's own file excluded); returns n. */
int32_t wr_simscene_inputs(const wr_simscene *sc, const char **list, int32_t max);
/* The name frame k gets in DIR ("frame_0007.obj"); out must hold 32 bytes. */
void wr_simscene_frame_name(const wr_simscene *sc, int32_t k, char *out);
wr_status wr_simscene_write_summary(const wr_simscene_run *run, const char *path, wr_diag *diag);
void wr_simscene_run_free(wr_simscene_run *run);

#endif
