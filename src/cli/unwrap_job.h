/* The part of `neuv unwrap` that `neuv demo` shares: run the pipeline on a
 * loaded mesh and write the outputs (mesh, report, pictures). */
#ifndef NEUV_CLI_UNWRAP_JOB_H
#define NEUV_CLI_UNWRAP_JOB_H

#include "neuv/neuv.h"

typedef struct unwrap_job {
    const char *input_name;   /* for messages and the report */
    const char *output;       /* mesh path (.obj/.ply/.glb/.gltf) */
    const char *report;       /* JSON path or NULL */
    const char *preview;      /* picture prefix or NULL */
    int preview_color;        /* preview_color value */
    double load_seconds;
    const char *save_model;   /* --save-model path or NULL */
    const char *model;        /* --model path or NULL: apply instead of training */
    int train_faces;          /* > 0: train on a simplified copy above this many faces */
    int check_inference;      /* --check-inference (with --model) */
    int shared_layer;         /* --shared-layer (category model): no per-chart heads solved at inference */
    int lscm_baseline;        /* --lscm-baseline (with --model): the model's charts flattened by LSCM */
    int finetune;             /* --finetune N (with a category --model) */
    int refine;               /* --refine N with --model; -1: the model's */
    int uv_channel;           /* --uv-channel: 0 the atlas replaces the UVs, 1 a second set */
    int resolution, padding;  /* --resolution, --padding with --model; 0 and -1: the model's */
} unwrap_job;

/* Runs the pipeline (or applies job->model) and writes everything (the
 * mesh as it came in with the atlas as its UVs, neuv_atlas_output_mesh),
 * the model too with job->save_model; prints a summary unless quiet.
 * Returns the process exit code. */
int unwrap_job_run(const neuv_mesh *mesh, const neuv_unwrap_options *opts, const unwrap_job *job);

#endif
