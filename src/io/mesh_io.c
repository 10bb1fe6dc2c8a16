/* neuv_mesh_load / neuv_mesh_save: checks on the path, then dispatch by
 * extension (case-insensitive) to the readers and writers in mesh_io.h. */
#include "io/mesh_io.h"

#include <ctype.h>
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "core/atomic_file.h"
#include "core/error.h"
#include "core/log.h"
#include "core/mem.h"

/* Lower-cased extension with its dot (".obj"), "" when there is none. */
static void extension_of(const char *path, char ext[16])
{
    ext[0] = '\0';
    const char *slash = strrchr(path, '/');
    const char *dot = strrchr(slash ? slash + 1 : path, '.');
    if (!dot || strlen(dot) >= 16) return;
    size_t i = 0;
    for (; dot[i]; i++) ext[i] = (char)tolower((unsigned char)dot[i]);
    ext[i] = '\0';
}

/* Reads the whole file into one NUL-terminated buffer: parsing from memory
 * with strtod is many times faster than reading characters from a FILE. */
neuv_status io_read_all(FILE *fp, char **data, size_t *len)
{
    size_t cap = 1 << 16, n = 0;
    struct stat st;
    if (fstat(fileno(fp), &st) == 0 && S_ISREG(st.st_mode) && st.st_size > 0) cap = (size_t)st.st_size + 1;
    char *buf = mem_alloc(cap);
    if (!buf) return error_nomem("the file contents");
    for (;;) {
        if (n + 1 >= cap) {
            size_t c = cap * 2;
            char *b = mem_realloc(buf, c);
            if (!b) { mem_free(buf); return error_nomem("the file contents"); }
            buf = b;
            cap = c;
        }
        size_t got = fread(buf + n, 1, cap - 1 - n, fp);
        n += got;
        if (got == 0) break;
    }
    if (ferror(fp)) {
        mem_free(buf);
        return error_set(NEUV_ERR_IO, "read failed: %s", strerror(errno));
    }
    buf[n] = '\0';
    *data = buf;
    *len = n;
    return NEUV_OK;
}

typedef enum mesh_format { FMT_UNKNOWN, FMT_OBJ, FMT_OFF, FMT_PLY, FMT_GLTF, FMT_ASSIMP } mesh_format;

static mesh_format input_format(const char *ext)
{
    if (!strcmp(ext, ".obj")) return FMT_OBJ;
    if (!strcmp(ext, ".off")) return FMT_OFF;
    if (!strcmp(ext, ".ply")) return FMT_PLY;
    if (!strcmp(ext, ".gltf") || !strcmp(ext, ".glb")) return FMT_GLTF;
    if (ext[0] && io_assimp_supports(ext)) return FMT_ASSIMP; /* .stl, .gltf, .glb, .fbx, ... */
    return FMT_UNKNOWN;
}

static neuv_status mesh_load(const char *path, neuv_mesh **out)
{
    *out = NULL;
    if (!path || !*path) return error_set(NEUV_ERR_INPUT, "no file name given");
    struct stat st;
    if (stat(path, &st) != 0) return error_set(NEUV_ERR_IO, "cannot open: %s", strerror(errno));
    if (S_ISDIR(st.st_mode)) return error_set(NEUV_ERR_IO, "is a directory, not a mesh file");
    char ext[16];
    extension_of(path, ext);
    mesh_format fmt = input_format(ext);
    if (fmt == FMT_UNKNOWN) {
        if (!ext[0])
            return error_set(NEUV_ERR_INPUT, "no file extension to tell the format (expected .obj, .off, .ply, .stl, .gltf, .glb)");
        return error_set(NEUV_ERR_INPUT, "unknown format '%s' (expected .obj, .off, .ply, .stl, .gltf, .glb)", ext);
    }
    if (S_ISREG(st.st_mode) && st.st_size == 0) return error_set(NEUV_ERR_INPUT, "empty file");
    if (fmt == FMT_ASSIMP) return io_read_assimp(path, out);

    FILE *fp = fopen(path, "rb");
    if (!fp) return error_set(NEUV_ERR_IO, "cannot open: %s", strerror(errno));
    char *data = NULL;
    size_t len = 0;
    neuv_status s = io_read_all(fp, &data, &len);
    fclose(fp);
    if (s != NEUV_OK) return s;
    if (len == 0) {
        s = error_set(NEUV_ERR_INPUT, "empty file");
    } else if (fmt == FMT_PLY) {
        s = io_read_ply(data, len, out);
    } else if (fmt == FMT_GLTF) {
        /* Buffers named by URI are relative to the file's folder. */
        const char *slash = strrchr(path, '/');
        size_t dl = slash ? (size_t)(slash - path) + 1 : 0;
        char *dir = mem_alloc(dl + 1);
        if (!dir) {
            s = error_nomem("the file's folder");
        } else {
            memcpy(dir, path, dl);
            dir[dl] = '\0';
            s = io_read_gltf(data, len, dir, out);
            mem_free(dir);
        }
    } else if (memchr(data, '\0', len)) {
        /* A text reader would stop at the NUL and silently drop the rest. */
        s = error_set(NEUV_ERR_INPUT, "binary data in a text %s file", fmt == FMT_OBJ ? "OBJ" : "OFF");
    } else {
        s = fmt == FMT_OBJ ? io_read_obj(data, len, out) : io_read_off(data, len, out);
    }
    mem_free(data);
    return s;
}

neuv_status neuv_mesh_load(const char *path, const neuv_callbacks *cb, neuv_mesh **out)
{
    if (!out) return error_set(NEUV_ERR_INPUT, "neuv_mesh_load: no output pointer");
    log_scope scope;
    log_scope_open(&scope, cb);
    neuv_status s = mesh_load(path, out);
    log_scope_close(&scope);
    return s;
}

neuv_status neuv_mesh_save(const neuv_mesh *mesh, const char *path)
{
    if (!mesh) return error_set(NEUV_ERR_INTERNAL, "neuv_mesh_save: no mesh");
    if (!path || !*path) return error_set(NEUV_ERR_INPUT, "no output file name given");
    char ext[16];
    extension_of(path, ext);
    int kind = !strcmp(ext, ".obj") ? 1 : !strcmp(ext, ".ply") ? 2 : !strcmp(ext, ".glb") ? 3
             : !strcmp(ext, ".gltf") ? 4 : 0;
    if (!kind) {
        if (!ext[0]) return error_set(NEUV_ERR_INPUT, "no file extension to tell the output format (expected .obj, .ply, .glb, .gltf)");
        return error_set(NEUV_ERR_INPUT, "unknown output format '%s' (expected .obj, .ply, .glb, .gltf)", ext);
    }
    /* A mesh made by neuv is always consistent; checking is cheap and turns a
     * bug elsewhere into a message instead of a wild read. */
    for (size_t c = 0; c < 3 * (size_t)mesh->nf; c++)
        if (mesh->tri[c] < 0 || mesh->tri[c] >= mesh->nv ||
            (mesh->nuv > 0 && mesh->tri_uv && (mesh->tri_uv[c] < 0 || mesh->tri_uv[c] >= mesh->nuv)))
            return error_set(NEUV_ERR_INTERNAL, "cannot save: face %zu has an index out of range", c / 3);
    atomic_file af;
    neuv_status s = atomic_file_open(&af, path);
    if (s != NEUV_OK) return s;
    /* A large buffer: the writers emit many small records. Freed only after
     * the FILE that uses it is closed (commit or abort). */
    char *iobuf = mem_alloc(1 << 20);
    if (!iobuf) { atomic_file_abort(&af); return error_nomem("the output buffer"); }
    setvbuf(af.fp, iobuf, _IOFBF, 1 << 20);
    switch (kind) {
    case 1: s = io_write_obj(mesh, af.fp); break;
    case 2: s = io_write_ply(mesh, af.fp); break;
    default: s = io_write_gltf(mesh, af.fp, kind == 3); break;
    }
    if (s != NEUV_OK) atomic_file_abort(&af);
    else s = atomic_file_commit(&af);
    mem_free(iobuf);
    return s;
}
