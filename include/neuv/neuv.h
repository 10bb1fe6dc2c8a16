/* neuv — neural, self-supervised, discretization-agnostic UV unwrapping.
 *
 * Usage:
 *
 *     #include <neuv/neuv.h>
 *
 *     neuv_mesh *mesh = NULL;
 *     if (neuv_mesh_load("spot.obj", &mesh) != NEUV_OK) {
 *         fprintf(stderr, "error: %s\n", neuv_last_error());
 *         return 2;
 *     }
 *     printf("%d vertices, %d faces\n", neuv_mesh_vertex_count(mesh),
 *            neuv_mesh_face_count(mesh));
 *     if (neuv_mesh_save(mesh, "copy.obj") != NEUV_OK) { ... }
 *     neuv_mesh_free(mesh);
 *
 * Lifetimes: every object returned through an out-pointer (`neuv_mesh **`)
 * belongs to the caller and is released with its `_free` function; a failing
 * call leaves the out-pointer NULL and allocates nothing. A string the library
 * returns (neuv_unwrap_report_json) is the caller's too, released with
 * neuv_free. Memory comes from the C library's allocator unless the
 * application sets its own, once, first (neuv_set_allocator).
 *
 * Errors: every fallible call returns a neuv_status. On failure a one-line
 * message describing what is wrong is available from neuv_last_error() (per
 * thread) until the next failing call. The library never exits and never
 * prints: it reports through the callbacks set with neuv_set_callbacks().
 */
#ifndef NEUV_NEUV_H
#define NEUV_NEUV_H

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
    NEUV_ERR_NOMEM = 4     /* an allocation failed (mesh too large for memory) */
} neuv_status;

/* Message of the last failure on this thread ("" if none). */
NEUV_API const char *neuv_last_error(void);
/* Short name of a status ("ok", "bad input", ...). */
NEUV_API const char *neuv_status_name(neuv_status status);
/* Process exit code for a status: 0 ok, 2 bad input/IO, 1 internal. */
NEUV_API int neuv_exit_code(neuv_status status);

typedef enum neuv_log_level {
    NEUV_LOG_DEBUG = 0,
    NEUV_LOG_INFO = 1,
    NEUV_LOG_WARN = 2
} neuv_log_level;

/* A message for the user (a repair done, a choice made). */
typedef void (*neuv_log_fn)(void *user, neuv_log_level level, const char *message);
/* Progress of a long stage: fraction in [0,1]; detail is e.g. "iter 120 loss 0.031". */
typedef void (*neuv_progress_fn)(void *user, const char *stage, double fraction, const char *detail);
/* Process-wide callbacks (NULL to silence). Not thread-safe to change while running. */
NEUV_API void neuv_set_callbacks(neuv_log_fn log, neuv_progress_fn progress, void *user);

NEUV_API const char *neuv_version(void);

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

/* Releases a string the library returned for the caller to free
 * (neuv_unwrap_report_json), with the allocator it was made with. NULL does
 * nothing. */
NEUV_API void neuv_free(void *ptr);

/* A triangle mesh, optionally with per-corner UVs. */
typedef struct neuv_mesh neuv_mesh;

/* Reads OBJ, OFF, PLY (ASCII and binary), STL, glTF/GLB; polygons are triangulated. */
NEUV_API neuv_status neuv_mesh_load(const char *path, neuv_mesh **out);
/* Writes by extension: .obj, .ply, .glb/.gltf; atomically (temporary file, then rename). */
NEUV_API neuv_status neuv_mesh_save(const neuv_mesh *mesh, const char *path);
NEUV_API void neuv_mesh_free(neuv_mesh *mesh);
NEUV_API int neuv_mesh_vertex_count(const neuv_mesh *mesh);
NEUV_API int neuv_mesh_face_count(const neuv_mesh *mesh);
NEUV_API int neuv_mesh_has_uv(const neuv_mesh *mesh);

/* ---- unwrapping -------------------------------------------------------- */

typedef enum neuv_method {
    NEUV_METHOD_NEURAL = 0,  /* the paper's parameterization networks (default) */
    NEUV_METHOD_LSCM = 1,    /* least squares conformal maps, same charts */
    NEUV_METHOD_HARMONIC = 2 /* cotangent harmonic map, boundary on a circle, same charts */
} neuv_method;

typedef enum neuv_preset {
    NEUV_PRESET_FAST = 0,  /* smallest networks that reach the quality bar on a CPU */
    NEUV_PRESET_PAPER = 1  /* the paper's configuration */
} neuv_preset;

typedef struct neuv_unwrap_options {
    neuv_method method;
    neuv_preset preset;
    int charts;              /* 0: automatic; K: exactly K patches before disk cutting */
    double max_distortion;   /* auto charts: split until every chart's LSCM qce_mean is below (1.15) */
    int iters;               /* 0: preset default; otherwise training iterations per network */
    int refine;              /* neural: vertex refinement steps after the networks (400); 0: off */
    unsigned long long seed; /* every random choice derives from it (default 1) */
    int threads;             /* 0: library default */
    int resolution;          /* atlas side in pixels (1024) */
    int padding;             /* pixels between charts and to the border (2) */
    int allow_overlaps;      /* 1: skip the repair of folded charts */
    int use_cache;           /* 1: operators through the on-disk cache (default) */
} neuv_unwrap_options;

NEUV_API void neuv_unwrap_options_default(neuv_unwrap_options *o);

/* The outcome of one unwrap: the cleaned mesh with its packed UVs, the
 * charts, per-stage seconds, every repair, and the metrics. */
typedef struct neuv_unwrap_result neuv_unwrap_result;

/* Cleans a copy of `mesh` (the input is not modified), computes operators,
 * charts, the parameterization, repairs, and packs the atlas. */
NEUV_API neuv_status neuv_unwrap(const neuv_mesh *mesh, const neuv_unwrap_options *opts, neuv_unwrap_result **out);
/* The unwrapped mesh (owned by the result). */
NEUV_API const neuv_mesh *neuv_unwrap_mesh(const neuv_unwrap_result *r);
NEUV_API int neuv_unwrap_chart_count(const neuv_unwrap_result *r);
/* The JSON report of SPEC.md section 4, released with neuv_free; NULL when
 * out of memory (neuv_last_error says so). load_seconds and export_seconds
 * are the caller's own stages, added to the report. */
NEUV_API char *neuv_unwrap_report_json(const neuv_unwrap_result *r, const char *input_name,
                              double load_seconds, double export_seconds);
NEUV_API void neuv_unwrap_result_free(neuv_unwrap_result *r);

#ifdef __cplusplus
}
#endif
#endif
