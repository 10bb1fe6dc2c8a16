/* What the other public-API files need of the atlas. */
#ifndef NEUV_API_API_ATLAS_H
#define NEUV_API_API_ATLAS_H

#include "neuv/neuv.h"

struct neuv_unwrap_result;
struct unwrap_model;

/* The added meshes as one (NULL when none was added). */
const neuv_mesh *api_atlas_input(const neuv_atlas *a);
const neuv_callbacks *api_atlas_callbacks(const neuv_atlas *a);
/* Makes r (owned from now on) the atlas's packed result, discarding every
 * stage; no stage can run again from it. model (owned from now on, may be
 * NULL): the model neuv_atlas_take_model hands over. */
neuv_status api_atlas_adopt(neuv_atlas *a, struct neuv_unwrap_result *r, struct unwrap_model *model);
/* Where the packed atlas's faces came from, for mesh `index`. */
typedef struct api_atlas_origin {
    const neuv_mesh *packed;   /* the cleaned mesh with its packed UVs */
    const int *face_chart;     /* packed->nf */
    const int *face_origin;    /* packed->nf: face of `input` each packed face is */
    const int *corner_origin;  /* 3 per packed face: the vertex of `input` at each corner */
    const neuv_mesh *input;    /* the added meshes joined */
    int v0, v1, f0, f1;        /* mesh `index`'s vertices and faces in input */
} api_atlas_origin;
/* Fills out after stage 3 (NEUV_ERR_INPUT before, or for a wrong index). */
neuv_status api_atlas_origins(neuv_atlas *a, int index, api_atlas_origin *out);
/* Hands over the model kept by generate or apply with keep_model. */
neuv_status api_atlas_take_model(neuv_atlas *a, struct unwrap_model **out);

#endif
