/* scene.h — the JSON scene format of the wrinkle statics drivers (compiled once as
 * drivers/lib/scene.c and linked into every program). Installed by `make install` for engines as
 * <wrinkle/formats/scene.h> with libwrinkle-formats.a (pkg-config wrinkle-formats); needs cJSON
 * (Debian libcjson-dev, MIT, -lcjson) and, for probes, FFTW through spectrum.h. Link it after the
 * translation unit that defines WRINKLE_IMPLEMENTATION: the library holds no wrinkle code.
 * The format is documented in docs/scene-format.md; examples in examples/scenes/.
 *
 * Pipeline (each step fallible, errors as wr_status + wr_diag like the library):
 *   wr_scene_parse(sc, text, len, base_dir, diag)  JSON text → wr_scene (pure, no file access; the
 *                                                  fuzz entry point). Errors are WR_ERR_PARSE with a
 *                                                  one-line message that names the JSON path, e.g.
 *                                                  "$.material.young: must be a number > 0".
 *   wr_scene_load(sc, path, diag)                  read a file, then parse (base_dir = its directory)
 *   wr_scene_run_create(run, sc, diag)             rest mesh, shell, prescribed vertex sets, obstacles
 *   wr_scene_run_solve(run, progress, user, diag)  load stepping through statics.h's incremental
 *                                                  solve (each set a WR_MOTION_AFFINE): step k of N
 *                                                  applies fraction k/N of every prescribed motion
 *                                                  (and of gravity unless ramp_gravity is false)
 *   wr_scene_run_probe(run, i, res, diag)          spectrum of probe i on the current state (only the
 *                                                  faces of its panel when it names one)
 *   wr_scene_run_write(run, dir, diag)             deformed.obj, fields.ply, summary.json (atomic)
 *   wr_scene_run_free(run) / wr_scene_free(sc)
 *
 * Memory: wr_scene owns its index lists and strings (wr_scene_free); wr_scene_run owns mesh, shell,
 * state (wr_scene_run_free). Both are safe to free when zeroed or after a failed create/parse.
 */
#ifndef WRINKLE_SCENE_H
#define WRINKLE_SCENE_H

#include "wrinkle/wrinkle.h"
#include "wrinkle/spectrum.h" /* probes (wr_spectrum_result); the umbrella includes it only with WR_USE_FFTW */

#define WR_SCENE_NAME_LEN 64
#define WR_SCENE_PATH_LEN 1024
#define WR_SCENE_MAX_BC 16
#define WR_SCENE_MAX_PROBES 32
#define WR_SCENE_MAX_OBSTACLES 16

typedef enum wr_scene_mesh_kind {
    WR_SCENE_MESH_OBJ = 0,
    WR_SCENE_MESH_RECTANGLE,          /* regular union-jack grid (wr_mesh_rectangle) */
    WR_SCENE_MESH_DISK,               /* hexagonal rings (wr_mesh_disk) */
    WR_SCENE_MESH_CYLINDER,           /* closed tube (wr_mesh_cylinder_flat) */
    WR_SCENE_MESH_DELAUNAY_RECTANGLE, /* Poisson samples (poisson.h) + Delaunay (triangulate.h) */
    WR_SCENE_MESH_LATTICE             /* equilateral lattice rotated by angle_deg, CDT to the rectangle */
} wr_scene_mesh_kind;

typedef struct wr_scene_mesh {
    wr_scene_mesh_kind kind;
    char path[WR_SCENE_PATH_LEN]; /* OBJ, resolved against the scene file's directory */
    double width, height;         /* rectangle / delaunay_rectangle [m]; cylinder height */
    double radius;                /* disk / cylinder [m] */
    double resolution;            /* target edge length [m] (generators) */
    int32_t nx, ny;               /* rectangle: explicit cell counts (override resolution when > 0) */
    uint64_t seed;                /* delaunay_rectangle sampling seed */
    double angle_deg;             /* lattice: rotation of the lattice rows from the x axis [deg] */
    double pillow_lift;           /* > 0: the flat panel doubled into a closed pillow (wr_mesh_pillow) [m] */
    int has_weld;                 /* obj: $.mesh.weld given */
    double weld_tol;              /* obj: vertices closer than this in 3D are merged (wr_mesh_weld) [m], >= 0 */
} wr_scene_mesh;

typedef enum wr_scene_select { WR_SCENE_SELECT_BOX = 0, WR_SCENE_SELECT_INDICES } wr_scene_select;

/* One prescribed vertex set. At load fraction s ∈ [0, 1] a selected vertex with rest position X
 * (3D, = the mesh's initial positions) is placed at
 *     p(s) = c + R(s·twist_angle about twist_axis through c) · F(s) · (X − c) + s·translate,
 *     F(s) = I + s·(F − I),  F = [[sx, γxy, γxz], [0, sy, γyz], [0, 0, sz]]
 * (stretch = (sx, sy, sz) scale factors, shear = (γxy, γxz, γyz)), c = center. A set with every
 * motion at its default is a clamp. */
typedef struct wr_scene_bc {
    char name[WR_SCENE_NAME_LEN];
    wr_scene_select select;
    double box_lo[3], box_hi[3]; /* inclusive box on the initial 3D positions [m] */
    int32_t *indices;            /* owned */
    int32_t n_indices;
    double center[3];
    double translate[3];
    double stretch[3];
    double shear[3];
    double twist_axis[3];
    double twist_angle; /* [rad] */
    /* sinusoidal gather (curtain top edges): adds s·amplitude·sin(2π (X·along)/wavelength + phase)
     * along `wave_dir` to the prescribed position; amplitude 0 = off */
    double wave_amplitude, wave_length, wave_phase;
    double wave_along[3], wave_dir[3];
} wr_scene_bc;

typedef struct wr_scene_probe {
    char name[WR_SCENE_NAME_LEN];
    double from[2], to[2]; /* rest-domain endpoints [m] */
    int32_t samples;       /* default 512 */
    double dir[3];         /* displacement component sampled (default (0,0,1)) */
    int dir_normal;        /* "dir": "normal": along the reference surface's unit vertex normal instead */
    int closed;
    /* $.probes[i].panel: sample only the faces of one panel (face_panel) of a multi-panel mesh whose
     * panels overlap in the rest domain. has_panel = 0: none; panel_name non-empty: an OBJ g/o name,
     * else panel_id (>= 0). Resolved against the mesh by wr_scene_run_create. */
    int has_panel;
    char panel_name[WR_SCENE_NAME_LEN];
    int32_t panel_id;
} wr_scene_probe;

/* $.obstacles[k]: an analytic obstacle (statics.h wr_obstacle), or a triangle mesh (statics.h ON MESH
 * OBSTACLES) read from an OBJ or made by body.h's mannequin, moved by translate [m]. */
typedef enum wr_scene_obstacle_kind {
    WR_SCENE_OBSTACLE_PLANE = 0,
    WR_SCENE_OBSTACLE_SPHERE,
    WR_SCENE_OBSTACLE_CAPSULE,
    WR_SCENE_OBSTACLE_OBJ,
    WR_SCENE_OBSTACLE_MANNEQUIN
} wr_scene_obstacle_kind;

typedef struct wr_scene_obstacle {
    wr_scene_obstacle_kind kind;
    wr_obstacle analytic;         /* plane / sphere / capsule (kind, p, q, normal, radius) */
    char path[WR_SCENE_PATH_LEN]; /* obj, resolved against the scene file's directory */
    wr_body_desc body;            /* mannequin (height, target_faces, cell; zero = body.h default) */
    double translate[3];          /* obj / mannequin [m] */
} wr_scene_obstacle;

/* exact: statics.h hessian.projection = WR_PROJECT_NONE (shifted until SPD); projected: per-element
 * PSD projection; hybrid: projected to a loose tolerance, then exact (statics.h increments.hybrid_switch) */
typedef enum wr_scene_hessian {
    WR_SCENE_HESSIAN_EXACT = 0,
    WR_SCENE_HESSIAN_PROJECTED,
    WR_SCENE_HESSIAN_HYBRID
} wr_scene_hessian;

typedef struct wr_scene {
    char name[WR_SCENE_NAME_LEN];
    wr_scene_mesh mesh;
    wr_shell_desc shell; /* grain_angle / rest_pos3 unused (NULL) */
    double areal_density; /* kg/m² as given (0 = not given) */
    double gravity[3];
    int ramp_gravity;     /* 1 (default): gravity ramps with the load steps */
    double pressure;      /* [Pa], > 0 inflates (statics.h ON PRESSURE); the full value at every load step */
    wr_scene_bc bc[WR_SCENE_MAX_BC];
    int32_t n_bc;
    wr_scene_probe probe[WR_SCENE_MAX_PROBES];
    int32_t n_probes;
    wr_scene_obstacle obstacle[WR_SCENE_MAX_OBSTACLES];
    int32_t n_obstacles;
    double contact_dhat, contact_stiffness; /* $.contact [m], [N/m]; 0 = statics.h ON CONTACT defaults */
    /* solver */
    wr_solver_method linear;
    double linear_tol;
    double grad_tol;
    int32_t max_iter; /* Newton steps per load step */
    int32_t load_steps;
    double perturb;   /* [m], applied at the first load step */
    uint64_t seed;
    wr_scene_hessian hessian;
    /* statics.h ON STABILITY; not read from JSON (zero = off): programs set it
     * (validation/validate_statics_stability.c) */
    wr_statics_stability_desc stability;
} wr_scene;

/* Everything one solve needs and produces. */
typedef struct wr_scene_step_stats {
    double fraction;
    wr_statics_stats st;
    wr_status status;
} wr_scene_step_stats;

typedef struct wr_scene_run {
    const wr_scene *sc;   /* borrowed */
    wr_mesh mesh;         /* rest mesh; pos = initial (rest) 3D positions */
    wr_obj_groups groups; /* an OBJ mesh's g/o names (panel id -> name) for the written OBJs; else empty */
    int32_t probe_panel[WR_SCENE_MAX_PROBES]; /* probe i's resolved panel id, -1 = every face */
    wr_shell shell;
    uint8_t *fixed;       /* nv */
    int32_t *bc_of;       /* nv: prescribed set of each vertex, -1 = free */
    double *x;            /* nv*3 current positions */
    wr_obstacle *obstacles;     /* n_obstacles of the scene, handed to every solve */
    wr_obstacle_mesh *obstacle_meshes; /* n_obstacles (zeroed for the analytic ones), owned */
    int32_t n_fixed;
    wr_scene_step_stats *steps; /* load_steps */
    int32_t n_steps_done;
    double t_mesh, t_setup, t_solve, t_assembly, t_projection, t_linear, t_line_search; /* [s] */
    int32_t newton_iterations, linear_iterations;
    wr_status solve_status;
} wr_scene_run;

typedef void (*wr_scene_progress_fn)(void *user, int32_t step, int32_t n_steps, const wr_statics_stats *st);

/* An equilateral lattice of spacing r (rows along x rotated by theta_deg about the rectangle's
 * centre), the points at least r/2 inside [0,w]×[0,h], plus boundary points every ≈ r, constrained
 * Delaunay: interior triangles are the lattice's own (the stretch test's aligned / rotated meshes). */
wr_status wr_scene_mesh_lattice(wr_mesh *m, double w, double h, double r, double theta_deg, wr_diag *diag);
/* The scene's delaunay_rectangle: Poisson-disk samples of spacing r on [0,w]×[0,h] (poisson.h, seeded),
 * constrained Delaunay (triangulate.h); rest = the samples, pos = (rest, 0). */
wr_status wr_scene_mesh_delaunay(wr_mesh *m, double w, double h, double r, uint64_t seed, wr_diag *diag);
void wr_scene_defaults(wr_scene *sc);
wr_status wr_scene_parse(wr_scene *sc, const char *text, size_t len, const char *base_dir, wr_diag *diag);
wr_status wr_scene_load(wr_scene *sc, const char *path, wr_diag *diag);
void wr_scene_free(wr_scene *sc);

wr_status wr_scene_run_create(wr_scene_run *run, const wr_scene *sc, wr_diag *diag);
wr_status wr_scene_run_solve(wr_scene_run *run, wr_scene_progress_fn progress, void *user, wr_diag *diag);
wr_status wr_scene_run_probe(const wr_scene_run *run, int32_t i, wr_spectrum_result *res, wr_diag *diag);
/* Probe samples (n = probe samples) of the displacement component, for plots. */
wr_status wr_scene_run_probe_samples(const wr_scene_run *run, int32_t i, double *pts, double *vals, double *ds,
                                     wr_diag *diag);
/* The rest-domain locator of probe i over mesh m (the run's mesh, or a mesh refined from it that
 * keeps face_panel, e.g. the TFW wrinkled surface), restricted to the faces of the probe's panel.
 * Without a panel on a mesh of several panels, the n points pts are checked first: a point lying in
 * faces of two panels whose positions m->pos there differ (overlapping panels, not a seam) is
 * ambiguous, WR_ERR_INVALID_ARG "$.probes[i]: ... set \"panel\"" (docs/scene-format.md). Free *p with
 * wr_probe_free. */
/* Probe i's sampled field per vertex of m: (x − x0)·d, d = the probe's unit dir, or with "dir":
 * "normal" the unit area-weighted vertex normal of m's faces at the positions x0 (the reference
 * surface: the initial positions for wrinkle-statics, the smooth subdivided base for wrinkle-tfw).
 * field: m->nv values. WR_ERR_NOMEM. */
wr_status wr_scene_probe_field(const wr_scene_probe *P, const wr_mesh *m, const double *x, const double *x0,
                               double *field, wr_diag *diag);
wr_status wr_scene_probe_locator(const wr_scene_run *run, int32_t i, const wr_mesh *m, const double *pts, int32_t n,
                                 wr_probe *p, wr_diag *diag);
wr_status wr_scene_run_write(const wr_scene_run *run, const char *dir, wr_diag *diag);
/* With obstacles: adds "obstacles" (count) and, after a solve, the last load step's
 * "min_obstacle_distance_m", "contact_vertices", "contact_dhat_m", "contact_stiffness_N_m" to obj. */
struct cJSON;
void wr_scene_run_contact_json(const wr_scene_run *run, struct cJSON *obj);
void wr_scene_run_free(wr_scene_run *run);

const char *wr_scene_mesh_kind_name(wr_scene_mesh_kind k);

#endif
