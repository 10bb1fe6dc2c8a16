/* Per-format readers and writers behind neuv_mesh_load / neuv_mesh_save
 * (mesh_io.c picks one by the file's extension).
 *
 * Readers take the whole file in memory (NUL-terminated; `len` bytes before
 * the NUL) and produce a mesh exactly as the file has it: vertex order and
 * float64 values preserved, polygons triangulated, UVs per corner. They
 * validate (indices in range, finite coordinates, at least one face) but
 * never weld or clean; that is mesh/clean.h's job.
 *
 * Writers write to an open file (an atomic_file's temporary); the caller
 * commits or aborts. */
#ifndef NEUV_IO_MESH_IO_H
#define NEUV_IO_MESH_IO_H

#include <stddef.h>
#include <stdio.h>

#include "mesh/mesh.h"

/* The whole of an open file in one NUL-terminated buffer (mem_free it);
 * *len excludes the NUL. NEUV_ERR_IO on a read error, NEUV_ERR_NOMEM. */
neuv_status io_read_all(FILE *fp, char **data, size_t *len);

/* Wavefront OBJ: v, vt, vn, f (v, v/vt, v//vn, v/vt/vn, negative indices),
 * usemtl (a material per face); the rest is skipped. */
neuv_status io_read_obj(const char *text, size_t len, neuv_mesh **out);
/* OFF and its COFF/NOFF/STOFF variants, with # comments. */
neuv_status io_read_off(const char *text, size_t len, neuv_mesh **out);
/* PLY: ascii, binary_little_endian, binary_big_endian; vertex normals nx, ny,
 * nz; colours and other properties kept in the attributes (docs/formats.md). */
neuv_status io_read_ply(const char *data, size_t len, neuv_mesh **out);
/* glTF 2.0, as .gltf (JSON) or .glb (binary), with neuv's own reader
 * (gltf_read.c says what it reads and refuses). `dir`: the folder that
 * buffer URIs naming files are relative to; NULL refuses such buffers. */
neuv_status io_read_gltf(const char *data, size_t len, const char *dir, neuv_mesh **out);
/* Any other format Assimp reads (STL, FBX, ...), meshes concatenated with
 * their node transforms applied. */
neuv_status io_read_assimp(const char *path, neuv_mesh **out);
/* 1 when Assimp can read files with this extension (".stl"). */
int io_assimp_supports(const char *ext);

/* OBJ with v (exact decimal), vt and f v/vt (1-based); f v without UVs. */
neuv_status io_write_obj(const neuv_mesh *m, FILE *fp);
/* Binary little-endian PLY: double x,y,z, float UVs (two pairs when
 * attr->nuv0 > 0), normals, colours, polygons and kept properties; vertices
 * split where corners differ (ply_write.c, docs/formats.md). */
neuv_status io_write_ply(const neuv_mesh *m, FILE *fp);
/* glTF 2.0: binary .glb (binary = 1) or .gltf with the buffer embedded as a
 * base64 data URI (binary = 0); a primitive per material, NORMAL, COLOR_0,
 * TEXCOORD_0 (and TEXCOORD_1 = the atlas when attr->nuv0 > 0), the kept
 * materials and node name; vertices split where corners differ (gltf_write.c). */
neuv_status io_write_gltf(const neuv_mesh *m, FILE *fp, int binary);

#endif
