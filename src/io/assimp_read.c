/* Reader for the formats neuv leaves to Assimp: STL (ascii and binary)
 * and whatever else aiIsExtensionSupported accepts (glTF and GLB go to
 * gltf_read.c, never here). Only
 * triangulation is asked of Assimp (no vertex joining), so the vertices are
 * those the importer produced; an STL arrives as triangle soup, which
 * mesh/clean.h welds. Every mesh instance in the node tree is added with its
 * accumulated node transform, in float64. */
#include <assimp/cimport.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <stdio.h>
#include <string.h>

#include "core/error.h"
#include "io/mesh_builder.h"
#include "io/mesh_io.h"

int io_assimp_supports(const char *ext)
{
    return aiIsExtensionSupported(ext) == AI_TRUE;
}

typedef struct affine { double m[3][4]; } affine; /* rows of a 3x4 transform */

static affine compose(const affine *parent, const struct aiMatrix4x4 *t)
{
    const double tm[4][4] = {{t->a1, t->a2, t->a3, t->a4},
                             {t->b1, t->b2, t->b3, t->b4},
                             {t->c1, t->c2, t->c3, t->c4},
                             {t->d1, t->d2, t->d3, t->d4}};
    affine r;
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 4; j++) {
            double s = 0;
            for (int k = 0; k < 3; k++) s += parent->m[i][k] * tm[k][j];
            if (j == 3) s += parent->m[i][3]; /* * tm[3][3] assumed 1: no projective nodes */
            r.m[i][j] = s;
        }
    return r;
}

typedef struct walk {
    const struct aiScene *scene;
    mesh_builder *b;
    int faces;
} walk;

static neuv_status add_mesh(walk *w, const struct aiMesh *am, const affine *T)
{
    mesh_builder *b = w->b;
    int base = b->nv, uv_base = b->nuv;
    const struct aiVector3D *tc = am->mTextureCoords[0];
    for (unsigned i = 0; i < am->mNumVertices; i++) {
        const struct aiVector3D *p = &am->mVertices[i];
        double x = p->x, y = p->y, z = p->z, q[3];
        for (int r = 0; r < 3; r++) q[r] = T->m[r][0] * x + T->m[r][1] * y + T->m[r][2] * z + T->m[r][3];
        neuv_status s = mesh_builder_add_vertex(b, q[0], q[1], q[2]);
        if (s == NEUV_OK && tc) s = mesh_builder_add_uv(b, tc[i].x, tc[i].y);
        if (s != NEUV_OK) return s;
    }
    int corners[64], uvc[64];
    for (unsigned f = 0; f < am->mNumFaces; f++) {
        const struct aiFace *face = &am->mFaces[f];
        if (face->mNumIndices < 3) continue; /* points and lines are not surface */
        if (face->mNumIndices > 64) return error_set(NEUV_ERR_INPUT, "a face with %u corners was not triangulated", face->mNumIndices);
        int n = (int)face->mNumIndices;
        for (int k = 0; k < n; k++) {
            corners[k] = base + (int)face->mIndices[k];
            uvc[k] = uv_base + (int)face->mIndices[k];
        }
        neuv_status s = mesh_builder_add_polygon(b, n, corners, tc ? uvc : NULL, w->faces++);
        if (s != NEUV_OK) return s;
    }
    return NEUV_OK;
}

static neuv_status add_node(walk *w, const struct aiNode *node, const affine *parent, int depth)
{
    if (depth > 256) return error_set(NEUV_ERR_INPUT, "the scene's node tree is deeper than 256");
    affine T = compose(parent, &node->mTransformation);
    for (unsigned i = 0; i < node->mNumMeshes; i++) {
        unsigned mi = node->mMeshes[i];
        if (mi >= w->scene->mNumMeshes) continue;
        neuv_status s = add_mesh(w, w->scene->mMeshes[mi], &T);
        if (s != NEUV_OK) return s;
    }
    for (unsigned i = 0; i < node->mNumChildren; i++) {
        neuv_status s = add_node(w, node->mChildren[i], &T, depth + 1);
        if (s != NEUV_OK) return s;
    }
    return NEUV_OK;
}

neuv_status io_read_assimp(const char *path, neuv_mesh **out)
{
    *out = NULL;
    const struct aiScene *scene = aiImportFile(path, aiProcess_Triangulate);
    if (!scene) {
        char msg[400];
        snprintf(msg, sizeof msg, "%s", aiGetErrorString());
        for (char *p = msg; *p; p++) if (*p == '\n' || *p == '\r') *p = ' ';
        return error_set(NEUV_ERR_INPUT, "cannot read: %s", msg[0] ? msg : "Assimp failed");
    }
    mesh_builder b;
    mesh_builder_init(&b);
    walk w = {scene, &b, 0};
    affine I = {{{1, 0, 0, 0}, {0, 1, 0, 0}, {0, 0, 1, 0}}};
    neuv_status s = NEUV_OK;
    if (scene->mRootNode) {
        s = add_node(&w, scene->mRootNode, &I, 0);
    } else {
        for (unsigned i = 0; i < scene->mNumMeshes && s == NEUV_OK; i++) s = add_mesh(&w, scene->mMeshes[i], &I);
    }
    aiReleaseImport(scene);
    if (s != NEUV_OK) { mesh_builder_free(&b); return s; }
    mesh_builder_style style = {0, 0};
    return mesh_builder_finish(&b, style, out);
}
