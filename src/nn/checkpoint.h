/* Checkpoint files (.neuv models): a JSON configuration and named float32 tensors.
 *
 * Layout (all integers unsigned 32-bit little-endian):
 *   "NEUVMODL"  magic, 8 bytes
 *   version     = NN_CHECKPOINT_VERSION
 *   header_len, header bytes (JSON text, no NUL), header CRC32
 *   tensor_count
 *   per tensor: name_len (1..255), name bytes (printable ASCII), rows, cols,
 *               CRC32 (of name, rows, cols and data bytes), rows*cols float32 little-endian
 *   end of file (trailing bytes are an error)
 * Written atomically (core/atomic_file.h). */
#ifndef NEUV_NN_CHECKPOINT_H
#define NEUV_NN_CHECKPOINT_H

#include <stddef.h>
#include "nn/nn.h"

#define NN_CHECKPOINT_VERSION 1
#define NN_CHECKPOINT_MAX_NAME 255

typedef struct nn_checkpoint_tensor {
    char *name;
    int rows, cols;
    float *data;   /* rows*cols */
} nn_checkpoint_tensor;

typedef struct nn_checkpoint {
    unsigned version;
    char *config;  /* the JSON header, verbatim, NUL-terminated */
    int n;
    nn_checkpoint_tensor *t;
} nn_checkpoint;

/* Writes `config` (JSON text) and the n tensors t[i] (data read from t[i]->data)
 * under names[i] (NULL names: use t[i]->name). NEUV_ERR_IO on write failure. */
neuv_status nn_checkpoint_save(const char *path, const char *config,
                               nn_tensor *const *t, const char *const *names, int n);
/* Saves every parameter of a set under its name. */
neuv_status nn_checkpoint_save_params(const char *path, const char *config, const nn_params *ps);

/* Reads and validates a whole file. NEUV_ERR_INPUT with a one-line message for any
 * malformed content, NEUV_ERR_IO when unreadable. *out is zeroed on failure. */
neuv_status nn_checkpoint_load(const char *path, nn_checkpoint *out);
/* Same validation on bytes in memory (the fuzzing entry point). */
neuv_status nn_checkpoint_parse(const void *bytes, size_t len, nn_checkpoint *out);
void nn_checkpoint_free(nn_checkpoint *c);
const nn_checkpoint_tensor *nn_checkpoint_find(const nn_checkpoint *c, const char *name);
/* Copies every parameter of `ps` from the checkpoint; NEUV_ERR_INPUT naming the first
 * missing tensor or shape mismatch. */
neuv_status nn_checkpoint_restore_params(const nn_checkpoint *c, nn_params *ps);

#endif
