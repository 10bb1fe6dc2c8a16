/* neuv — neural, self-supervised, discretization-agnostic UV unwrapping.
 *
 * A C99 interface. Usage, on arrays the application already holds:
 *
 *     #include <neuv/neuv.h>
 *
 *     neuv_atlas *atlas = NULL;
 *     neuv_mesh_decl mesh;
 *     neuv_mesh_decl_init(&mesh);
 *     mesh.positions = positions;          // float x, y, z per vertex
 *     mesh.position_stride = 3 * sizeof(float);
 *     mesh.vertex_count = vertex_count;
 *     mesh.indices = indices;              // uint32, three per triangle
 *     mesh.index_count = index_count;
 *     neuv_unwrap_options options;
 *     neuv_unwrap_options_init(&options);
 *     if (neuv_atlas_create(&atlas) != NEUV_OK ||
 *         neuv_atlas_add_mesh(atlas, &mesh) != NEUV_OK ||
 *         neuv_atlas_generate(atlas, &options) != NEUV_OK) {
 *         fprintf(stderr, "error: %s\n", neuv_last_error());
 *         neuv_atlas_destroy(atlas);
 *         return 2;
 *     }
 *     neuv_atlas_output out;
 *     neuv_atlas_get_output(atlas, 0, &out);
 *     for (int i = 0; i < out.vertex_count; i++)
 *         use(out.xref[i], out.uvs[2 * i], out.uvs[2 * i + 1]);   // input vertex, its UV
 *     for (int i = 0; i < out.index_count; i++)
 *         use_index(out.indices[i]);                            // three per output triangle
 *     neuv_atlas_destroy(atlas);
 *
 * The stages can also run one by one and again with other options:
 * neuv_atlas_compute_charts, neuv_atlas_parameterize, neuv_atlas_pack;
 * re-running a stage discards the stages after it. A call refused for its
 * arguments changes nothing; a stage that fails or is cancelled leaves the
 * atlas at the stage before it.
 *
 * Lifetimes: every object returned through an out-pointer (`neuv_mesh **`,
 * `neuv_atlas **`, `neuv_model **`) belongs to the caller and is released
 * with its `_free`/`_destroy` function; a failing call leaves the
 * out-pointer NULL and keeps nothing. Strings and arrays the library returns
 * by pointer are released with neuv_free. Pointers inside output structs
 * (neuv_atlas_output) belong to the object they came from and stay valid
 * until it is destroyed or its stages run again. Input arrays are copied:
 * the caller may free them once the call returns.
 * Memory comes from the C library's allocator unless the application sets
 * its own, once, first (neuv_set_allocator).
 *
 * Errors: every fallible call returns a neuv_status. On failure a one-line
 * message saying what is wrong is available from neuv_last_error() (per
 * thread) until the next failing call on that thread. The library never
 * exits and never prints: it reports through the callbacks of the object or
 * call (neuv_callbacks).
 *
 * Threads: objects are independent; two threads may each use their own
 * atlas (or model) at the same time, with the same results as one after the
 * other. One object must not be used by two threads at once. Each call may
 * use several threads itself (OpenMP; `threads` in the options, or
 * neuv_set_threads for the calls whose options have no such field).
 *
 * Determinism: same input, options, seed and thread count give the same
 * output bytes on one machine. The report's seconds are timings.
 */
#ifndef NEUV_NEUV_H
#define NEUV_NEUV_H

#include <stddef.h>

/* NEUV_API marks what the shared library exports; everything else in it is
 * hidden. Defined empty for the static library. */
#if defined(NEUV_BUILDING_SHARED) && defined(__GNUC__)
#define NEUV_API __attribute__((visibility("default")))
#else
#define NEUV_API
#endif

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

typedef enum neuv_status {
    NEUV_OK = 0,
    NEUV_ERR_INTERNAL = 1, /* a bug or an unexpected numerical failure */
    NEUV_ERR_INPUT = 2,    /* bad input file, bad argument, unusable mesh */
    NEUV_ERR_IO = 3,       /* cannot read or write a path */
    NEUV_ERR_NOMEM = 4,    /* an allocation failed (mesh too large for memory) */
    NEUV_ERR_CANCELLED = 5 /* the progress callback returned 0 */
} neuv_status;

/* Message of the last failure on this thread ("" if none). */
NEUV_API const char *neuv_last_error(void);
/* Short name of a status ("ok", "bad input", ...). */
NEUV_API const char *neuv_status_name(neuv_status status);
/* Process exit code for a status: 0 ok, 2 bad input, I/O, memory or
 * cancelled, 1 internal. */
NEUV_API int neuv_exit_code(neuv_status status);
/* "0.1.0". */
NEUV_API const char *neuv_version(void);
/* Releases a string or array the library returned by pointer, with the
 * allocator it was made with (NULL: nothing). */
NEUV_API void neuv_free(void *ptr);
/* The OpenMP threads of the calling thread's later calls (OpenMP keeps the
 * count per thread); threads < 1 changes nothing. Options with a `threads`
 * field set it again for their call. */
NEUV_API void neuv_set_threads(int threads);

/* ---- callbacks ---------------------------------------------------------- */

typedef enum neuv_log_level {
    NEUV_LOG_DEBUG = 0,
    NEUV_LOG_INFO = 1,
    NEUV_LOG_WARN = 2
} neuv_log_level;

/* A message for the user (a repair done, a choice made, a warning about the input). */
typedef void (*neuv_log_fn)(void *user, neuv_log_level level, const char *message);
/* Progress of a long stage: fraction in [0,1] within the stage; detail is
 * e.g. "iter 120 loss 0.031" or NULL. Return nonzero to go on, 0 to cancel:
 * the call then stops at its next check (within one training step) and
 * returns NEUV_ERR_CANCELLED, keeping no partial result. */
typedef int (*neuv_progress_fn)(void *user, const char *stage, double fraction, const char *detail);

/* The callbacks of one object or call. Both may be NULL (silent). They are
 * called on the thread that made the call. */
typedef struct neuv_callbacks {
    neuv_log_fn log;
    neuv_progress_fn progress;
    void *user;
} neuv_callbacks;

/* ---- meshes ------------------------------------------------------------- */

/* ---- memory ------------------------------------------------------------ */

/* An application's allocator. The functions have the contracts of malloc,
 * realloc and free with `user` passed first, except that neuv never asks
 * alloc or realloc for 0 bytes, never passes realloc a NULL ptr, and never
 * passes free a NULL ptr. A failing alloc or realloc returns NULL (realloc
 * then leaves ptr allocated as it was); neuv then frees what it holds and
 * the call returns NEUV_ERR_NOMEM. Alignment as malloc's. The functions are
 * called from several threads at once when an unwrap runs on several
 * threads, so they must be thread-safe. */
typedef struct neuv_allocator {
    void *(*alloc)(void *user, size_t size);
    void *(*realloc)(void *user, void *ptr, size_t size);
    void (*free)(void *user, void *ptr);
    void *user;
} neuv_allocator;

/* Routes neuv's allocations through *a (copied; NULL, or an allocator
 * lacking any of the three functions, restores the C library's).
 * Process-wide, like xatlas's SetAlloc: call it before any other neuv call
 * and never while one runs; an object or string made under one allocator is
 * released under the same one, so change it only when none is alive.
 * CHOLMOD's allocations go through it too: while an allocator is set it is
 * also SuiteSparse's process-wide allocator (SuiteSparse_config, put back on
 * NULL), so an application that calls SuiteSparse itself gets it there as
 * well. Not routed: what OpenBLAS, LAPACK(E), ARPACK, METIS, Assimp, CGAL,
 * meshoptimizer, libpng and the C library's stdio allocate for themselves
 * (their own allocators, or the C library's). */
NEUV_API void neuv_set_allocator(const neuv_allocator *a);

/* A triangle mesh, optionally with per-corner UVs. */
typedef struct neuv_mesh neuv_mesh;

typedef enum neuv_scalar_type { NEUV_FLOAT32 = 0, NEUV_FLOAT64 = 1 } neuv_scalar_type;
typedef enum neuv_index_type { NEUV_UINT32 = 0, NEUV_UINT16 = 1, NEUV_INT32 = 2 } neuv_index_type;

/* A mesh described by the caller's arrays (copied by the call that takes it). */
typedef struct neuv_mesh_decl {
    const void *positions;          /* vertex_count points of 3 scalars */
    neuv_scalar_type position_type; /* NEUV_FLOAT32 by default */
    size_t position_stride;         /* bytes from one vertex to the next; 0: tightly packed */
    int vertex_count;
    const void *indices;            /* index_count indices, 3 per triangle, counter-clockwise;
                                       NULL: the vertices taken three by three */
    neuv_index_type index_type;     /* NEUV_UINT32 by default */
    int index_count;
    const void *uvs;                /* optional existing UVs: 2 scalars per vertex, or NULL */
    neuv_scalar_type uv_type;
    size_t uv_stride;               /* 0: tightly packed */
} neuv_mesh_decl;

/* Zeroes d: float32 positions, uint32 indices, no UVs. */
NEUV_API void neuv_mesh_decl_init(neuv_mesh_decl *d);

/* Copies the arrays of d into a new mesh. Errors (NEUV_ERR_INPUT, with the
 * offending vertex or index in the message): no vertices or no triangles,
 * index_count not a multiple of 3, an index out of range, a position or UV
 * that is not finite, a stride smaller than its element. */
NEUV_API neuv_status neuv_mesh_create(const neuv_mesh_decl *d, neuv_mesh **out);
/* Reads OBJ, OFF, PLY (ASCII and binary), STL, glTF/GLB; polygons are
 * triangulated. Warnings about the file go to cb (may be NULL). */
NEUV_API neuv_status neuv_mesh_load(const char *path, const neuv_callbacks *cb, neuv_mesh **out);
/* Writes by extension: .obj, .ply, .glb/.gltf; atomically (a temporary file
 * in the same folder, then a rename), so a failure leaves no file behind. */
NEUV_API neuv_status neuv_mesh_save(const neuv_mesh *mesh, const char *path);
NEUV_API void neuv_mesh_free(neuv_mesh *mesh);
NEUV_API int neuv_mesh_vertex_count(const neuv_mesh *mesh);
NEUV_API int neuv_mesh_face_count(const neuv_mesh *mesh);
NEUV_API int neuv_mesh_has_uv(const neuv_mesh *mesh);
/* The repairs neuv_mesh_clean made (docs/report.md "Cleaning"). */
typedef struct neuv_clean_report {
    int welded_vertices;          /* merged into an earlier vertex at the identical position */
    int degenerate_faces;         /* dropped: a repeated vertex or zero area */
    int duplicate_faces;          /* dropped: the same vertices as an earlier face */
    int unreferenced_vertices;    /* dropped: used by no face */
    int flipped_faces;            /* reversed so that each component is consistently oriented */
    int nonmanifold_edges;        /* found with more than two faces (split apart) */
    int nonmanifold_vertices;     /* whose faces form more than one fan (split apart) */
    int split_vertices;           /* added by those splits */
    int nonorientable_components; /* left as they are (Moebius strips) */
} neuv_clean_report;
/* The repairs every unwrap makes on its copy of the input, in place: weld,
 * drop degenerate and duplicate faces, split non-manifold edges and
 * vertices, drop unreferenced vertices, orient each component (closed ones
 * outward). UVs stay with their corners. Messages (the warning about a
 * non-orientable component left as it is) go to cb (may be NULL). report
 * may be NULL. A mesh left with no faces is NEUV_ERR_INPUT. */
NEUV_API neuv_status neuv_mesh_clean(neuv_mesh *mesh, const neuv_callbacks *cb, neuv_clean_report *report);
/* Only the welding of vertices at exactly identical positions (what
 * neuv_evaluate does on its copy, so that seams are found across shared
 * edges); *welded (may be NULL) gets how many were merged. */
NEUV_API neuv_status neuv_mesh_weld(neuv_mesh *mesh, int *welded);

/* Copies out the positions (3 per vertex) and the triangles (3 vertex
 * indices per face). */
NEUV_API void neuv_mesh_get_positions(const neuv_mesh *mesh, double *positions);
NEUV_API void neuv_mesh_get_indices(const neuv_mesh *mesh, int *indices);
/* Copies out the UVs per corner: 6 numbers per face (u, v of its three
 * corners in order). Returns 1, or 0 (nothing written) when the mesh has
 * no UVs. */
NEUV_API int neuv_mesh_get_corner_uvs(const neuv_mesh *mesh, double *uvs);

/* A built-in procedural shape: "bumpy-torus" (the demo's), "sphere",
 * "capsule", "cube", "genus2", or a member (>= 0) of a family for category
 * models: "bent-capsule", "blob". member is -1 for the single shapes. */
NEUV_API neuv_status neuv_shape(const char *name, int member, neuv_mesh **out);

/* ---- options ------------------------------------------------------------ */

typedef enum neuv_method {
    NEUV_METHOD_NEURAL = 0,  /* the parameterization networks (default) */
    NEUV_METHOD_LSCM = 1,    /* least squares conformal maps, same charts */
    NEUV_METHOD_HARMONIC = 2 /* cotangent harmonic map, boundary on a circle, same charts */
} neuv_method;

typedef enum neuv_preset {
    NEUV_PRESET_FAST = 0,  /* networks sized for a CPU (default) */
    NEUV_PRESET_PAPER = 1  /* the published method's configuration */
} neuv_preset;

/* Charts: the mesh is cleaned (docs/report.md "Cleaning"), then PatchNet cuts it. */
typedef struct neuv_chart_options {
    neuv_preset preset;
    int charts;              /* 0: automatic (default); K: exactly K patches before disk cutting */
    double max_distortion;   /* automatic charts: split until every chart's LSCM qce_mean is below it (1.15) */
    int iters;               /* PatchNet training steps; 0: the preset's */
    unsigned long long seed; /* every random choice derives from it (1) */
    int threads;             /* 0: the machine's */
    int use_cache;           /* 1: operators through the on-disk cache (default 1) */
    int max_memory_mb;       /* training refuses (NEUV_ERR_NOMEM, before it starts) a mesh whose
                                estimated peak memory is above this many MiB; 0 (default): half
                                of the machine's physical memory */
    /* Required seams: no chart crosses them (docs/report.md "seams"). */
    double seam_angle;       /* > 0: every edge whose two faces' normals differ by more than this
                                many degrees (a cube's edges: 90); 0 (default): none */
    const int *seam_edges;   /* seam_edge_count pairs of vertex indices of the input mesh (of the
                                meshes in the order added, for an atlas); read during the call */
    int seam_edge_count;
    int hard_edges;          /* 1 (default): the edges where the mesh's own corner normals differ
                                (unless every corner has its face's normal: flat shading) and the
                                borders between its materials are required seams too; 0: not */
} neuv_chart_options;
NEUV_API void neuv_chart_options_init(neuv_chart_options *o);

/* Parameterization of the charts, their repair and refinement. */
typedef struct neuv_param_options {
    neuv_method method;
    neuv_preset preset;
    int iters;               /* training steps of the networks; 0: the preset's */
    int refine;              /* neural: vertex refinement steps after the networks (400); 0: none */
    unsigned long long seed; /* (1) */
    int threads;             /* 0: the machine's */
    int allow_overlaps;      /* 1: keep folded network maps (no repair) */
} neuv_param_options;
NEUV_API void neuv_param_options_init(neuv_param_options *o);

/* Packing into one square. */
typedef struct neuv_pack_options {
    int resolution;          /* atlas side in pixels, 64..16384 (1024) */
    int padding;             /* pixels between charts and to the border, 0..resolution/8 (2) */
    int keep_scale;          /* neuv_pack_uvs only: keep the charts' relative scales */
    double texels_per_unit;  /* > 0: every chart at this many pixels per unit of surface length, in as
                                many resolution-sized tiles as that takes, laid out as UDIM tiles
                                (tile k, UDIM 1001 + k, is the UV square [k mod 10, +1] x [k div 10, +1];
                                neuv_uv_tiles lists them); a chart larger than one tile at that density
                                is refused (NEUV_ERR_INPUT); not with keep_scale. 0 (default): one
                                square at the largest density that fits */
    int threads;             /* 0: the machine's (the placements of each chart are searched side by side) */
} neuv_pack_options;
NEUV_API void neuv_pack_options_init(neuv_pack_options *o);

/* All stages at once (neuv_atlas_generate), with the same fields and
 * defaults as the three stage options above. */
typedef struct neuv_unwrap_options {
    neuv_method method;
    neuv_preset preset;
    int charts;
    double max_distortion;
    int iters;
    int refine;
    unsigned long long seed;
    int threads;
    int resolution;
    int padding;
    int allow_overlaps;
    int use_cache;
    int keep_model;          /* 1: keep the networks so that neuv_atlas_get_model can save them;
                                the atlas is the same as without */
    int train_faces;         /* > 0: above this many faces, train on a simplified copy of that many
                                and apply the model to the mesh (0, the default: train on the mesh) */
    int max_memory_mb;       /* as in neuv_chart_options: the budget that training on the whole
                                mesh (or on all of a category's shapes) must fit */
    /* Required seams, as in neuv_chart_options. Not with keep_model, nor when the
       networks train on a simplified copy (train_faces) */
    double seam_angle;       /* > 0: every edge whose two faces' normals differ by more than this
                                many degrees (a cube's edges: 90); 0 (default): none */
    const int *seam_edges;   /* seam_edge_count pairs of vertex indices of the input mesh (of the
                                meshes in the order added, for an atlas); read during the call */
    int seam_edge_count;
    int hard_edges;          /* as in neuv_chart_options (default 1); where a model makes the charts
                                they are left out and counted (neuv_report.hard_edges_not_kept),
                                and with keep_model they are refused */
    double texels_per_unit;  /* as in neuv_pack_options (0, the default: off); not with keep_model (a
                                model's layout is one square) */
} neuv_unwrap_options;
NEUV_API void neuv_unwrap_options_init(neuv_unwrap_options *o);

/* ---- metrics (docs/metrics.md) ------------------------------------------ */

typedef struct neuv_metrics {
    int charts;                   /* UV-connected components */
    double qce_mean, qce_p95, qce_max;    /* quasi-conformal error s1/s2, area-weighted */
    double ase_mean, ase_abs_mean, ase_abs_mean_chart; /* area scale error */
    double l2_stretch, linf_stretch;
    double sym_dirichlet_mean;
    int flipped, degenerate_uv;   /* faces turned over / of zero UV area */
    double overlap_fraction;      /* share of UV area covered twice */
    double packing_efficiency;    /* UV area / unit square; NaN when UVs leave [0,1]^2 */
    double seam_length;           /* relative to sqrt(3D area) */
    int excluded_faces;           /* faces of (nearly) zero 3D area, left out */
} neuv_metrics;

/* The metrics of a mesh's UVs as JSON (docs/report.md "neuv eval"): an
 * object with the version, the input (input_name), vertices, faces and the metrics;
 * release with neuv_free; NULL when memory runs out. */
NEUV_API char *neuv_metrics_json(const neuv_metrics *metrics, const neuv_mesh *mesh, const char *input_name);

/* One UDIM tile of a UV layout: the unit square [u0, u0+1] x [v0, v0+1]
 * with udim = 1001 + u0 + 10 v0 (u0 in 0..9, v0 in 0..9). */
typedef struct neuv_uv_tile {
    int udim;
    int charts;                   /* UV-connected components in it */
    int faces;
    double efficiency;            /* UV area of its faces / tile area, faces counted as for
                                     packing_efficiency (one tile at [0,1]^2: the same value) */
} neuv_uv_tile;

/* The UDIM tiles mesh's UVs occupy, by udim: *tiles (*count of them;
 * release with neuv_free) lists each tile that holds a face. A layout is in
 * tiles when every face lies within one tile (to 1e-9); otherwise, or
 * without faces, *count is 0 and *tiles NULL. NEUV_ERR_INPUT when the mesh
 * has no UVs. */
NEUV_API neuv_status neuv_uv_tiles(const neuv_mesh *mesh, neuv_uv_tile **tiles, int *count);

/* The metrics of mesh's UVs, positions welded first (on a
 * copy) so that seams are found across exactly coinciding vertices.
 * NEUV_ERR_INPUT when the mesh has no UVs. Messages go to cb (may be NULL). */
NEUV_API neuv_status neuv_evaluate(const neuv_mesh *mesh, const neuv_callbacks *cb, neuv_metrics *out);

/* ---- the atlas ---------------------------------------------------------- */

typedef struct neuv_atlas neuv_atlas;

NEUV_API neuv_status neuv_atlas_create(neuv_atlas **out);
NEUV_API void neuv_atlas_destroy(neuv_atlas *atlas);
/* Callbacks for every later call on this atlas (cb copied; NULL: silent). */
NEUV_API void neuv_atlas_set_callbacks(neuv_atlas *atlas, const neuv_callbacks *cb);

/* Adds a mesh (copied). Several meshes share one atlas: they are unwrapped
 * as the components of one mesh and packed into one square, and the output
 * is given per mesh. Adding discards any stage already run. */
NEUV_API neuv_status neuv_atlas_add_mesh(neuv_atlas *atlas, const neuv_mesh_decl *mesh);
/* The same with a loaded mesh (copied). */
NEUV_API neuv_status neuv_atlas_add_loaded_mesh(neuv_atlas *atlas, const neuv_mesh *mesh);
NEUV_API int neuv_atlas_mesh_count(const neuv_atlas *atlas);

/* Stage 1: cleaning, operators, PatchNet charts. */
NEUV_API neuv_status neuv_atlas_compute_charts(neuv_atlas *atlas, const neuv_chart_options *o);
/* Stage 2 (after 1): each chart flattened, repaired where it folds, refined. */
NEUV_API neuv_status neuv_atlas_parameterize(neuv_atlas *atlas, const neuv_param_options *o);
/* Stage 3 (after 2): charts that pack badly are split, then packed; metrics. */
NEUV_API neuv_status neuv_atlas_pack(neuv_atlas *atlas, const neuv_pack_options *o);
/* All three (and, with train_faces, the simplified-copy path) in one call.
 * Gives the same bytes as the three stages with the same options. After
 * the simplified-copy path (train_faces below the face count) no single
 * stage can run again: there is no stage of the full mesh to start from. */
NEUV_API neuv_status neuv_atlas_generate(neuv_atlas *atlas, const neuv_unwrap_options *o);

/* Number of the last stage run: 0 none, 1 charts, 2 parameterized, 3 packed. */
NEUV_API int neuv_atlas_stage(const neuv_atlas *atlas);
/* Charts after the last stage run (0 before stage 1). */
NEUV_API int neuv_atlas_chart_count(const neuv_atlas *atlas);

/* The packed atlas of mesh `index` (in the order added), valid after stage
 * 3: output vertices are split where a seam runs, so each has one UV. */
typedef struct neuv_atlas_output {
    int vertex_count;
    const int *xref;           /* vertex_count: the input vertex of this mesh at the same position
                                  (the first one when several input vertices coincide) */
    const double *uvs;         /* 2 per output vertex, in [0,1]^2 */
    int index_count;           /* 3 per output triangle */
    const unsigned int *indices;
    const int *face_chart;     /* index_count / 3: chart id of each output triangle */
} neuv_atlas_output;
/* Cleaning may drop degenerate or duplicate triangles and reorient
 * components (the counts are in the report): output triangles follow the
 * cleaned mesh. */
NEUV_API neuv_status neuv_atlas_get_output(neuv_atlas *atlas, int index, neuv_atlas_output *out);
/* The whole cleaned mesh with its packed per-corner UVs (owned by the
 * atlas), e.g. for neuv_mesh_save; NULL before stage 3. */
NEUV_API const neuv_mesh *neuv_atlas_mesh(const neuv_atlas *atlas);
/* The mesh `input`, added as mesh `index`, with the packed atlas as its UVs:
 * what `neuv unwrap` writes. Everything else is input's: its vertices and
 * faces in their order, its polygons, normals, materials, groups, colours
 * and other properties as its file gave them, so writers split vertices
 * only where a UV seam runs. The atlas itself is made on a cleaned copy
 * (neuv_atlas_mesh): a face the cleaning dropped (degenerate, duplicate)
 * gets one UV at all three corners (a zero-area UV triangle: no texture,
 * no flip, no overlap), that of one of its vertices elsewhere, or (0, 0);
 * a face the cleaning turned over (report cleaning.flipped_faces) is
 * written turned over, or its UVs would be mirrored against its chart.
 * uv_channel 0: the atlas replaces input's UVs; 1: input's UVs stay the
 * first set and the atlas is the second (glTF TEXCOORD_1, PLY's second
 * pair; OBJ holds one set, so neuv_mesh_save refuses such a mesh as .obj).
 * NEUV_ERR_INPUT before stage 3, for a mesh other than the one added, for
 * uv_channel 1 on a mesh without UVs. The caller frees *out. */
NEUV_API neuv_status neuv_atlas_output_mesh(neuv_atlas *atlas, int index, const neuv_mesh *input, int uv_channel,
                                            neuv_mesh **out);
/* The metrics of the packed atlas, as neuv_evaluate reads the saved mesh. */
NEUV_API neuv_status neuv_atlas_get_metrics(const neuv_atlas *atlas, neuv_metrics *out);

/* Where a chart's final map came from (docs/report.md "sources"). */
typedef enum neuv_chart_source {
    NEUV_SOURCE_NETWORK = 0,          /* the networks' map, untouched (only placed by packing) */
    NEUV_SOURCE_NETWORK_REFINED,      /* the networks' injective map, then refined */
    NEUV_SOURCE_NETWORK_FOLDED,       /* the networks' map kept with its folds (allow_overlaps) */
    NEUV_SOURCE_LSCM_AFTER_FOLD,      /* the networks' map folded; LSCM flattened the chart */
    NEUV_SOURCE_LSCM_AFTER_SPLIT,     /* a piece of a chart split because its map folded; LSCM */
    NEUV_SOURCE_LSCM,                 /* method LSCM */
    NEUV_SOURCE_HARMONIC,             /* method harmonic */
    NEUV_SOURCE_HARMONIC_AFTER_SPLIT,
    NEUV_SOURCE_TRANSFERRED,          /* a saved model's classic chart: UVs from its source surface */
    NEUV_SOURCE_COUNT
} neuv_chart_source;
/* "network", "network+refined", ... as in the report. */
NEUV_API const char *neuv_chart_source_name(neuv_chart_source s);

typedef struct neuv_chart_info {
    int faces;
    double area;               /* 3D area */
    neuv_chart_source source;
    double network_qce;        /* the networks' own qce_mean on it before anything else touched it
                                  (NaN: the networks made no map of it) */
    double qce;                /* final qce_mean */
} neuv_chart_info;
/* Valid after stage 2 for charts 0..neuv_atlas_chart_count-1. */
NEUV_API neuv_status neuv_atlas_get_chart(const neuv_atlas *atlas, int chart, neuv_chart_info *out);

/* The report as a struct: counts and seconds of the last run. */
typedef struct neuv_report {
    int input_vertices, input_faces;
    int vertices, faces;             /* after cleaning */
    int charts;
    int charts_by_source[NEUV_SOURCE_COUNT];
    double network_area_fraction;    /* share of 3D area whose map the networks made injectively */
    double network_qce_mean;         /* area-weighted over those charts; NaN if none */
    int repairs;
    double seconds_clean, seconds_operators, seconds_patches, seconds_param, seconds_repair,
        seconds_pack, seconds_metrics, seconds_total;
    neuv_metrics metrics;            /* valid after stage 3 */
    int from_model;                  /* 1: the atlas came from a saved or category model */
    int moved_charts;                /* surface model: charts not where the model's atlas put them */
    int trained_on_copy;             /* train_faces: 1 when the networks trained on a simplified copy */
    int train_faces;                 /* ... of this many faces */
    int seam_edges;                  /* required seam edges (hard edges, materials, seam_angle, seam_edges) */
    int seams_crossed;               /* of which joined by the atlas (0 when all were kept) */
    int hard_edges_not_kept;         /* hard and material edges of the file left out: a model's charts */
    int polygons;                    /* the file's polygons of more than 3 corners */
    int polygons_split;              /* of which split between charts (written back as their triangles) */
} neuv_report;
NEUV_API neuv_status neuv_atlas_get_report(const neuv_atlas *atlas, neuv_report *out);
/* The JSON report (docs/report.md); release with neuv_free. input_name,
 * load_seconds and export_seconds are the caller's (file name, its own
 * reading and writing), added to the report. NULL (and neuv_last_error)
 * before stage 3 or when memory runs out. */
NEUV_API char *neuv_atlas_report_json(const neuv_atlas *atlas, const char *input_name, double load_seconds,
                                      double export_seconds);

/* ---- models ------------------------------------------------------------- */

/* A saved unwrap (the surface model of one mesh: reproduces its atlas on
 * other triangulations of the same surface) or a category model (trained
 * on several shapes: unwraps unseen shapes of the category by inference). */
typedef struct neuv_model neuv_model;

NEUV_API neuv_status neuv_model_load(const char *path, neuv_model **out);
/* Atomic (a temporary file, then a rename). */
NEUV_API neuv_status neuv_model_save(const neuv_model *model, const char *path);
NEUV_API void neuv_model_free(neuv_model *model);
/* 1 for a category model, 0 for a surface model. */
NEUV_API int neuv_model_is_category(const neuv_model *model);

/* The surface model of the atlas's last neuv_atlas_generate, which must
 * have run with keep_model = 1, or of its last neuv_atlas_apply_model of a
 * category model with finetune > 0 and keep_model = 1 (this shape, its
 * charts and atlas, the fine-tuned networks); else NEUV_ERR_INPUT. Hands
 * the networks over: a second call fails. */
NEUV_API neuv_status neuv_atlas_take_model(neuv_atlas *atlas, neuv_model **out);

typedef struct neuv_apply_options {
    int threads;             /* 0: the machine's */
    int use_cache;           /* (1) */
    int allow_overlaps;      /* category models: keep folded network maps */
    /* surface models */
    int check_inference;     /* 1: also run PatchNet on the mesh and report its label agreement */
    int lscm_baseline;       /* 1: a baseline, not the model's map: the model's charts flattened by LSCM */
    /* category models */
    int finetune;            /* training steps from the model's weights (0: inference only) */
    int shared_layer;        /* 1: the model's shared output layer maps every chart (no per-chart
                                layer solved on this shape) */
    int refine;              /* vertex refinement steps; -1 (default): the model's */
    int resolution;          /* the packing's square in pixels, 64..16384; 0 (default): the model's */
    int padding;             /* gutter in pixels, 0..resolution/8; -1 (default): the model's */
    int keep_model;          /* 1 (with finetune > 0): keep this shape's fine-tuned networks, charts and
                                atlas as a surface model for neuv_atlas_take_model; the atlas is the
                                same as without */
} neuv_apply_options;
NEUV_API void neuv_apply_options_init(neuv_apply_options *o);

/* Unwraps the atlas's meshes with a model instead of training: a surface
 * model carries its atlas over to this triangulation of its surface; a
 * category model charts and maps this unseen shape by inference. Replaces
 * every stage (the atlas is then at stage 3). Options that do not apply to
 * the model's kind are refused with NEUV_ERR_INPUT, never ignored: a surface
 * model keeps its source's layout (no resolution, padding, refine,
 * allow_overlaps, finetune, shared_layer or keep_model), a category model
 * has no stored labels or charts to compare (no check_inference or
 * lscm_baseline), and keep_model needs finetune > 0 (inference trains no
 * networks of this shape's). */
NEUV_API neuv_status neuv_atlas_apply_model(neuv_atlas *atlas, const neuv_model *model,
                                           const neuv_apply_options *o);

typedef struct neuv_train_report {
    int shapes, faces, charts;       /* over all shapes, after cleaning */
    int patch_k;                     /* PatchNet's patches */
    int patch_iterations, param_iterations;
    double patch_loss, param_loss;   /* at the last step */
    double seconds_operators, seconds_patches, seconds_charts, seconds_param, seconds;
} neuv_train_report;
/* The report as JSON (docs/report.md "neuv train"), naming the model file;
 * release with neuv_free; NULL when memory runs out. */
NEUV_API char *neuv_train_report_json(const neuv_train_report *report, const char *model_name);

/* Trains a category model on meshes[0..n-1] (n >= 1): method must be
 * neural; preset, charts (0: automatic after K = 8), seed, iters, refine,
 * resolution, padding and max_distortion are stored in the model and used
 * when it is applied; threads and use_cache apply here. patch_iters:
 * PatchNet steps (0: every shape seen about 40 times). report may be NULL. */
NEUV_API neuv_status neuv_train_category(const neuv_mesh *const *meshes, int n, const neuv_unwrap_options *o,
                                         int patch_iters, const neuv_callbacks *cb, neuv_model **out,
                                         neuv_train_report *report);

/* ---- existing UV maps --------------------------------------------------- */

typedef struct neuv_pack_report {
    int charts;                /* UV-connected components packed */
    int attempts;              /* packings tried */
    double texel_scale;        /* pixels per unit of surface length */
    int tiles;                 /* UDIM tiles used (1 without texels_per_unit) */
} neuv_pack_report;

/* Repacks the charts of mesh's UVs (UV-connected components) into one
 * square, in place; positions are welded first (exactly coinciding only).
 * NEUV_ERR_INPUT when the mesh has no UVs. Messages go to cb (may be
 * NULL). report may be NULL. */
NEUV_API neuv_status neuv_pack_uvs(neuv_mesh *mesh, const neuv_pack_options *o, const neuv_callbacks *cb,
                                   neuv_pack_report *report);

/* ---- pictures ---------------------------------------------------------- */

typedef enum neuv_preview_color {
    NEUV_PREVIEW_CHART = 0,  /* one colour per chart */
    NEUV_PREVIEW_QCE = 1,    /* each face by its quasi-conformal error */
    NEUV_PREVIEW_AREA = 2    /* each face by its area scale error */
} neuv_preview_color;

/* Writes PREFIX-uv.png (the UV layout: charts coloured, edges drawn,
 * flipped faces red, overlaps highlighted) and PREFIX-checker.png (the
 * mesh with a checkerboard through its UVs from four views), 1024 px.
 * NEUV_ERR_INPUT when the mesh has no UVs; NEUV_ERR_IO when a file cannot
 * be written. Messages go to cb (may be NULL). */
NEUV_API neuv_status neuv_write_preview(const neuv_mesh *mesh, const char *prefix, neuv_preview_color color,
                                        const neuv_callbacks *cb);

/* ---- files --------------------------------------------------------------- */

/* Writes text and a newline to path atomically (a temporary file in the
 * same folder, then a rename): a failure leaves no file behind. */
NEUV_API neuv_status neuv_save_text(const char *path, const char *text);

/* ---- cleaning and topology (neuv info) ---------------------------------- */


/* One connected component: faces joined across shared edges. */
typedef struct neuv_component {
    int faces, vertices, edges;
    int boundary_loops;
    int genus;                 /* (2 - euler - boundary_loops) / 2 */
    int euler;                 /* vertices - edges + faces */
    int closed;                /* 1: no boundary */
} neuv_component;

/* What a mesh is made of once cleaned. */
typedef struct neuv_topology {
    int input_vertices, input_faces;   /* of the mesh as given */
    int vertices, faces;               /* after cleaning */
    int has_uv;
    neuv_clean_report repairs;         /* what the cleaning did */
    int component_count;
    neuv_component *components;        /* component_count, numbered by their first face;
                                          release with neuv_free */
} neuv_topology;

/* Cleans a copy of mesh (the repairs of neuv_mesh_clean, messages to cb,
 * which may be NULL) and describes it. Unlike neuv_mesh_clean, a mesh whose
 * faces are all dropped is no error: it has no components. On failure
 * out->components is NULL. */
NEUV_API neuv_status neuv_mesh_topology(const neuv_mesh *mesh, const neuv_callbacks *cb, neuv_topology *out);
/* The topology as a JSON document: version, input (input_name),
 * the counts, has_uv, the components and the repairs. Release with
 * neuv_free; NULL when memory runs out. */
NEUV_API char *neuv_topology_json(const neuv_topology *topology, const char *input_name);

/* ---- classic flattening (neuv flatten) ----------------------------------- */

typedef struct neuv_flatten_report {
    double seconds;            /* the flattening solve alone */
    neuv_metrics metrics;      /* of the new UVs as the mesh holds them (not welded first) */
} neuv_flatten_report;

/* Flattens a mesh that is one topological disk (one component, one boundary
 * loop, genus 0) by method NEUV_METHOD_LSCM (least squares conformal maps,
 * free boundary) or NEUV_METHOD_HARMONIC (cotangent weights, boundary on a
 * circle). The map, scaled uniformly into [0,1]^2 with its aspect kept,
 * replaces mesh's UVs (one per vertex). mesh: cleaned (neuv_mesh_clean).
 * report may be NULL. Errors, the mesh then unchanged: NEUV_ERR_INPUT for
 * another method or a mesh that is not one disk (the message names what it
 * is: "not a disk: 1 component, closed, genus 4"); NEUV_ERR_INTERNAL when a
 * solve fails. */
NEUV_API neuv_status neuv_flatten(neuv_mesh *mesh, neuv_method method, const neuv_callbacks *cb,
                                  neuv_flatten_report *report);

/* ---- geodesic distances (neuv geodesics) --------------------------------- */

/* Heat-method geodesic distances (Crane, Weischedel, Wardetzky 2013,
 * "Geodesics in Heat") from vertex `source` to every vertex, in mesh's own
 * numbering: computed on a cleaned copy (messages to cb, may be NULL) and
 * read back through vertices at exactly equal positions.
 * Inputs:  source in 0..vertex_count-1
 * Outputs: distances (vertex_count, caller allocates): 0 at the source,
 *          INFINITY where not reached (another component, or a vertex used
 *          by no face); time (may be NULL): the diffusion time t used
 *          (the mean edge length squared)
 * Errors:  NEUV_ERR_INPUT for a source out of range or used by no face
 *          (every vertex, when cleaning dropped every face). */
NEUV_API neuv_status neuv_geodesic_distances(const neuv_mesh *mesh, int source, const neuv_callbacks *cb,
                                             double *distances, double *time);
/* Geodesic distances as a JSON document: input (input_name), source,
 * distances (count numbers, null where not finite) and seconds (the
 * caller's timing). Release with neuv_free; NULL when memory runs out. */
NEUV_API char *neuv_geodesics_json(const char *input_name, int source, const double *distances, int count,
                                   double seconds);

/* ---- geometry operators (neuv operators) --------------------------------- */

/* What the networks see of a mesh (DiffusionNet, Sharp et al. 2022): the
 * cotangent Laplacian, lumped mass, the smallest Laplacian eigenpairs,
 * spatial gradients and heat kernel signatures, of the cleaned mesh. */
typedef struct neuv_operators neuv_operators;

typedef struct neuv_operator_options {
    int k;                     /* eigenpairs wanted, 1..4096 (64); at most the vertex count are computed */
    int hks;                   /* heat kernel signature times, 1..1024 (16) */
    int use_cache;             /* 1: read and write the on-disk cache ($XDG_CACHE_HOME/neuv) (1) */
} neuv_operator_options;
NEUV_API void neuv_operator_options_init(neuv_operator_options *o);

/* Cleans a copy of mesh (messages to cb, may be NULL) and computes its
 * operators, or reads them from the cache. o NULL: defaults. Errors:
 * NEUV_ERR_INPUT for options out of range or a mesh without faces (before
 * or after cleaning); NEUV_ERR_CANCELLED; a cache that cannot be read or
 * written is never an error (the operators are computed). */
NEUV_API neuv_status neuv_operators_compute(const neuv_mesh *mesh, const neuv_operator_options *o,
                                            const neuv_callbacks *cb, neuv_operators **out);
NEUV_API void neuv_operators_free(neuv_operators *ops);

/* Pointers belong to ops. */
typedef struct neuv_operators_info {
    int vertices, faces;       /* of the cleaned mesh */
    int k;                     /* eigenpairs computed */
    const double *eigenvalues; /* k, ascending: L phi = lambda M phi */
    int hks_count;
    const double *hks_times;   /* hks_count, ascending */
    double seconds_clean;
    double seconds_laplacian, seconds_factor, seconds_eigen, seconds_gradients, seconds_hks; /* 0 on a cache hit */
    double seconds_cache_load; /* 0 unless a cache hit */
    double seconds_operators;  /* all of the operators, computed or read (not the cleaning) */
    const char *cache_path;    /* the cache file; NULL when use_cache was 0 */
    int cache_hit;             /* 1: read from cache_path; 0: computed (and written there) */
} neuv_operators_info;
NEUV_API void neuv_operators_get_info(const neuv_operators *ops, neuv_operators_info *out);
/* The operators' summary as a JSON document: version, input (input_name), the
 * counts, eigenvalues, HKS times, seconds (load_seconds: the caller's
 * reading of the file) and the cache. Release with neuv_free; NULL when
 * memory runs out. */
NEUV_API char *neuv_operators_json(const neuv_operators *ops, const char *input_name, double load_seconds);

/* ---- other triangulations of a surface (neuv remesh) --------------------- */

/* Simplification by edge collapse (meshoptimizer's quadric simplifier)
 * towards ratio * faces, ratio in (0, 1]: the positions kept are exactly
 * (bit for bit) input positions, in the input's order; UV seams are kept
 * (the count may stay above the target where seams or borders stop
 * collapses). Messages (the counts reached) to cb, may be NULL. *out: a new
 * mesh. NEUV_ERR_INPUT for a ratio out of range. */
NEUV_API neuv_status neuv_mesh_simplify(const neuv_mesh *mesh, double ratio, const neuv_callbacks *cb,
                                        neuv_mesh **out);

typedef enum neuv_subdivision {
    NEUV_SUBDIVIDE_MIDPOINT = 0, /* new vertices at edge midpoints: the same surface */
    NEUV_SUBDIVIDE_LOOP = 1      /* Loop (1987) smoothing; UVs still interpolated linearly */
} neuv_subdivision;

/* `rounds` (0..8) rounds of 1-to-4 subdivision: faces * 4^rounds faces; old
 * vertices keep their indices, corner UVs are interpolated (a seam stays a
 * seam). *out: a new mesh. NEUV_ERR_INPUT for rounds out of range, a face
 * with a repeated vertex or a mesh too large to subdivide. */
NEUV_API neuv_status neuv_mesh_subdivide(const neuv_mesh *mesh, int rounds, neuv_subdivision scheme,
                                         neuv_mesh **out);

typedef struct neuv_isotropic_options {
    double edge_length;        /* > 0: target edge length L in the mesh's units; 0: from faces (0) */
    int faces;                 /* used when edge_length is 0: about this many faces, >= 4 (0) */
    int iterations;            /* rounds of split, collapse, flip, relax, project (5) */
    double feature_degrees;    /* edges with a sharper dihedral angle are kept as polylines;
                                  >= 180: none (60) */
} neuv_isotropic_options;
NEUV_API void neuv_isotropic_options_init(neuv_isotropic_options *o);

typedef struct neuv_isotropic_report {
    int faces_in, faces_out;
    double edge_length;        /* the L of the last remeshing */
    int feature_edges_in;      /* input edges sharper than feature_degrees */
    int feature_edges_out;     /* output edges on those polylines */
    int rounds;                /* remeshings run (1 to 3 with a face target) */
    double max_distance;       /* largest distance of an output vertex to the input surface */
    double diagonal;           /* the input's bounding-box diagonal, to read max_distance against */
} neuv_isotropic_report;

/* Isotropic remeshing (Botsch and Kobbelt 2004, through CGAL): a new
 * triangulation with edges of one length that shares no vertex with the
 * input off its feature and boundary polylines; every vertex lies on the
 * input surface. With a face target, L is derived from the area and
 * corrected up to twice towards it. mesh: manifold and consistently
 * oriented (as neuv_mesh_clean leaves it); UVs are not carried over.
 * *out: a new mesh. report may be NULL. NEUV_ERR_INPUT for neither or a bad
 * target, or a non-manifold or inconsistently oriented mesh. */
NEUV_API neuv_status neuv_mesh_remesh_isotropic(const neuv_mesh *mesh, const neuv_isotropic_options *o,
                                                const neuv_callbacks *cb, neuv_mesh **out,
                                                neuv_isotropic_report *report);

typedef struct neuv_jitter_report {
    int moved_vertices;        /* interior vertices moved within the surface */
    int slid_vertices;         /* boundary vertices slid along a straight boundary */
    int fixed_vertices;        /* kept: on a feature, a UV seam or a boundary corner */
    int flipped_edges;
    double max_deviation;      /* largest distance of a moved vertex to the input surface */
} neuv_jitter_report;

/* Another triangulation of the same surface, in place: interior vertices
 * slide within the surface by random offsets (up to 0.3 of their shortest
 * edge, projected back onto it), then nearly flat edge pairs are flipped;
 * features, UV seams and boundary corners stay, UVs follow. Deterministic
 * for a seed. mesh: cleaned. report may be NULL. On failure mesh is
 * unchanged. */
NEUV_API neuv_status neuv_mesh_jitter(neuv_mesh *mesh, unsigned long long seed, neuv_jitter_report *report);

/* ---- PatchNet charts alone (neuv segment) -------------------------------- */

typedef enum neuv_features {
    NEUV_FEATURES_HKS = 0,     /* heat kernel signatures: independent of pose and triangulation, but
                                * blind to parts a symmetry exchanges (a cube's six sides) */
    NEUV_FEATURES_XYZ = 1,     /* positions */
    NEUV_FEATURES_HKS_NORMALS = 2 /* (default) heat kernel signatures and vertex normals: independent of
                                   * triangulation, translation and scale; tells a cube's sides apart */
} neuv_features;

typedef struct neuv_segment_options {
    neuv_preset preset;
    int charts;                /* 0: automatic (default); K in 1..100000: K patches before disk cutting */
    double max_distortion;     /* automatic: split until every chart's LSCM qce_mean is below it, > 1 (1.15) */
    neuv_features features;    /* PatchNet's input */
    int iters;                 /* training steps; 0: the preset's */
    unsigned long long seed;   /* (1) */
    int threads;               /* 0: the machine's */
    int use_cache;             /* 1: operators through the on-disk cache (1) */
} neuv_segment_options;
NEUV_API void neuv_segment_options_init(neuv_segment_options *o);

typedef struct neuv_segment_report {
    int vertices, faces;       /* of the mesh segmented */
    unsigned long long seed;
    neuv_features features;
    int patches;               /* PatchNet's outputs K */
    int label_charts;          /* charts straight from the per-face labels */
    int splits;                /* charts split by the automatic loop */
    int charts;                /* final */
    int iterations;            /* training steps run */
    double iterations_per_second;
    double loss, loss_cos, loss_geo; /* at the last step */
    double worst_lscm_qce;     /* the largest LSCM qce_mean of a chart */
    int lscm_flipped;          /* LSCM flipped faces over all charts */
    int cache_hit;             /* operators read from the cache */
    double seconds_operators, seconds_geodesics, seconds_train, seconds_chart_check;
    int reseeds;               /* emptied patches re-seeded by splitting the worst-fitting one */
} neuv_segment_report;

/* PatchNet's charts of mesh (stage 1 of an unwrap, alone): the network
 * trained on the mesh, its labels cut into topological disks. mesh:
 * cleaned (neuv_mesh_clean). o NULL: defaults. Progress ("patches",
 * "charts") and messages to cb (may be NULL).
 * Outputs: face_chart (face_count, caller allocates): the chart of each
 *          face, 0..*chart_count-1; report (may be NULL)
 * Errors:  NEUV_ERR_INPUT for options out of range or an unusable mesh,
 *          NEUV_ERR_CANCELLED. */
NEUV_API neuv_status neuv_segment(const neuv_mesh *mesh, const neuv_segment_options *o, const neuv_callbacks *cb,
                                  int *face_chart, int *chart_count, neuv_segment_report *report);
/* A segmentation as a JSON document: input and output (the caller's file
 * names), the report, and seconds (load_seconds and total_seconds: the
 * caller's). Release with neuv_free; NULL when memory runs out. */
NEUV_API char *neuv_segment_report_json(const neuv_segment_report *report, const char *input_name,
                                        const char *output_name, double load_seconds, double total_seconds);

/* Writes mesh with a label per face (labels: face_count values >= 0, e.g.
 * chart ids), atomically, by extension: .ply an ASCII PLY whose faces carry
 * an `int chart` property; .obj one group `g chart_N` per label.
 * NEUV_ERR_INPUT for another extension or a negative label; NEUV_ERR_IO. */
NEUV_API neuv_status neuv_save_face_labels(const neuv_mesh *mesh, const int *labels, const char *path);
/* A PNG of mesh from four views, each face coloured by its label
 * (face_count values), 1024 px. NEUV_ERR_IO when it cannot be written. */
NEUV_API neuv_status neuv_write_label_preview(const neuv_mesh *mesh, const int *labels, const char *path);

/* ---- two UV maps of one surface (neuv compare) --------------------------- */

#define NEUV_WORST_CHARTS 5

/* One of B's charts whose UVs are farthest from A's. */
typedef struct neuv_chart_mismatch {
    int b_chart;               /* B's chart (UV-connected component) */
    int a_chart;               /* the A chart holding most of its area */
    int corners;               /* its corners compared */
    double uv_mean;            /* their mean UV distance */
} neuv_chart_mismatch;

typedef struct neuv_uv_comparison {
    double uv_mean, uv_p95, uv_max;             /* UV distance (atlas units) in the matched chart */
    double nearest_mean, nearest_p95, nearest_max; /* at the closest point whatever its chart */
    double across_seam;        /* share of B's corners past their matched chart's seam */
    double chart_agreement;    /* share of B's area whose chart agrees with A's */
    double chart_agreement_faces; /* the same share counted in faces */
    double chart_agreement_facing; /* the area share with each B face located on the A faces facing its way
                                      (where two sheets touch, the plain closest point can be on the other) */
    int faces_a, faces_b, charts_a, charts_b;
    int vertices_compared;     /* distinct (vertex, UV) corners of B */
    double max_surface_distance; /* largest distance of a compared B vertex to A's surface */
    int worst_count;           /* entries of worst in use */
    neuv_chart_mismatch worst[NEUV_WORST_CHARTS]; /* largest mean UV distance first */
    neuv_metrics b_metrics;    /* of B's UVs, its identical positions welded as neuv_evaluate does */
} neuv_uv_comparison;

/* UV consistency of two UV maps of the same surface, possibly on two
 * triangulations of it (docs/transfer.md "Measuring it"): for every corner
 * of B, A's UV at the same point of the surface, in the A chart matched to
 * B's chart (past that chart's seam, its map extended), and how much of B's
 * surface lies in the chart matched to its own. Charts are found across
 * shared edges after identical positions are welded (in copies: a and b are
 * not changed), as neuv_evaluate finds them. Messages to cb (may be NULL).
 * NEUV_ERR_INPUT when a mesh has no faces or no UVs. */
NEUV_API neuv_status neuv_compare_uvs(const neuv_mesh *a, const neuv_mesh *b, const neuv_callbacks *cb,
                                      neuv_uv_comparison *out);
/* A comparison as a JSON document, naming the two files. Release with
 * neuv_free; NULL when memory runs out. */
NEUV_API char *neuv_uv_comparison_json(const neuv_uv_comparison *c, const char *a_name, const char *b_name);

/* ---- checkpoint files (neuv inspect) ------------------------------------- */

/* A .neuv file as stored: a JSON configuration and named float32 tensors
 * (any checkpoint, a model's or not). */
typedef struct neuv_checkpoint neuv_checkpoint;

/* Reads and validates the whole file. NEUV_ERR_INPUT with a one-line
 * message for malformed content (bad magic, wrong version, truncated, CRC
 * mismatch, trailing bytes, a tensor twice); NEUV_ERR_IO when it cannot be
 * read. */
NEUV_API neuv_status neuv_checkpoint_load(const char *path, neuv_checkpoint **out);
NEUV_API void neuv_checkpoint_free(neuv_checkpoint *c);
/* The file's format version. */
NEUV_API unsigned neuv_checkpoint_version(const neuv_checkpoint *c);
/* The JSON configuration, verbatim (belongs to c). */
NEUV_API const char *neuv_checkpoint_config(const neuv_checkpoint *c);
NEUV_API int neuv_checkpoint_tensor_count(const neuv_checkpoint *c);
/* Values over all tensors. */
NEUV_API long long neuv_checkpoint_parameter_count(const neuv_checkpoint *c);

typedef struct neuv_tensor_info {
    const char *name;          /* belongs to the checkpoint */
    int rows, cols;
    double min, max, rms;      /* over the finite values; NaN (min, max) when none is */
    long long nonfinite;       /* values that are NaN or infinite */
} neuv_tensor_info;
/* Tensor `index` (0..tensor_count-1, in file order). NEUV_ERR_INPUT out of range. */
NEUV_API neuv_status neuv_checkpoint_get_tensor(const neuv_checkpoint *c, int index, neuv_tensor_info *out);
/* A checkpoint's contents as a JSON document: file (file_name), version, config,
 * parameters, and each tensor's name, shape and value range. Release with
 * neuv_free; NULL when memory runs out. */
NEUV_API char *neuv_checkpoint_json(const neuv_checkpoint *c, const char *file_name);

/* ---- one call ----------------------------------------------------------- */

/* The older one-call interface: neuv_atlas_generate on a copy of mesh.
 * The result owns the unwrapped mesh. */
typedef struct neuv_unwrap_result neuv_unwrap_result;
NEUV_API neuv_status neuv_unwrap(const neuv_mesh *mesh, const neuv_unwrap_options *opts, neuv_unwrap_result **out);
NEUV_API const neuv_mesh *neuv_unwrap_mesh(const neuv_unwrap_result *r);
NEUV_API int neuv_unwrap_chart_count(const neuv_unwrap_result *r);
/* The JSON report (docs/report.md), released with neuv_free; NULL when
 * out of memory (neuv_last_error says so). load_seconds and export_seconds
 * are the caller's own stages, added to the report. */
NEUV_API char *neuv_unwrap_report_json(const neuv_unwrap_result *r, const char *input_name,
                                       double load_seconds, double export_seconds);
NEUV_API void neuv_unwrap_result_free(neuv_unwrap_result *r);

#ifdef __cplusplus
}
#endif
#endif
