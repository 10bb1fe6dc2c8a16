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
 * call leaves the out-pointer NULL and allocates nothing.
 *
 * Errors: every fallible call returns a neuv_status. On failure a one-line
 * message describing what is wrong is available from neuv_last_error() (per
 * thread) until the next failing call. The library never exits and never
 * prints: it reports through the callbacks set with neuv_set_callbacks().
 */
#ifndef NEUV_NEUV_H
#define NEUV_NEUV_H

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
const char *neuv_last_error(void);
/* Short name of a status ("ok", "bad input", ...). */
const char *neuv_status_name(neuv_status status);
/* Process exit code for a status: 0 ok, 2 bad input/IO, 1 internal. */
int neuv_exit_code(neuv_status status);

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
void neuv_set_callbacks(neuv_log_fn log, neuv_progress_fn progress, void *user);

const char *neuv_version(void);

/* A triangle mesh, optionally with per-corner UVs. */
typedef struct neuv_mesh neuv_mesh;

/* Reads OBJ, OFF, PLY (ASCII and binary), STL, glTF/GLB; polygons are triangulated. */
neuv_status neuv_mesh_load(const char *path, neuv_mesh **out);
/* Writes by extension: .obj, .ply, .glb/.gltf; atomically (temporary file, then rename). */
neuv_status neuv_mesh_save(const neuv_mesh *mesh, const char *path);
void neuv_mesh_free(neuv_mesh *mesh);
int neuv_mesh_vertex_count(const neuv_mesh *mesh);
int neuv_mesh_face_count(const neuv_mesh *mesh);
int neuv_mesh_has_uv(const neuv_mesh *mesh);

#ifdef __cplusplus
}
#endif
#endif
