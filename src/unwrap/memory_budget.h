/* The memory an unwrap that trains on a whole mesh needs, estimated before
 * it starts, and the refusal when that is over the budget. Training holds
 * one step of PatchNet and of the parameterization networks over every
 * face, so its peak grows with the faces it trains on (linearly: measured
 * by bench/bench_memory.sh, figures in bench/RESULTS.md). A mesh that would
 * not fit is refused with a message that says how much it needs and what
 * to use instead, rather than swapping for hours or being killed. */
#ifndef NEUV_UNWRAP_MEMORY_BUDGET_H
#define NEUV_UNWRAP_MEMORY_BUDGET_H

#include "neuv/neuv.h"

/* What the refusals suggest instead: a simplified copy, or a larger budget. */
#define MEMORY_BUDGET_HINT                                                                                   \
    "train on a simplified copy (--train-faces 20000; library: train_faces) or raise the budget "            \
    "(--max-memory MIB; library: max_memory_mb)"

/* Bytes that training on `faces` faces (PatchNet, then the networks) is
 * expected to hold at its peak: the measured bytes per face with a margin. */
double memory_training_estimate(double faces);

/* The budget in bytes for max_memory_mb (> 0: that many MiB; 0: half the
 * machine's physical memory, or no limit when it cannot be read). */
double memory_budget_bytes(int max_memory_mb);

/* NEUV_OK; NEUV_ERR_INPUT when max_memory_mb is negative; NEUV_ERR_NOMEM with a one-line message when training on
 * `faces` faces (`what`: "this mesh", "the 3 shapes") needs more than the
 * budget. `hint`: what to use instead (appended to the message). */
neuv_status memory_check_training(double faces, int max_memory_mb, const char *what, const char *hint);

#endif
