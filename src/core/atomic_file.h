/* Atomic output: write to a temporary file beside the target, then rename.
 * A failed or abandoned write leaves no partial file and never touches an
 * existing target. */
#ifndef NEUV_CORE_ATOMIC_FILE_H
#define NEUV_CORE_ATOMIC_FILE_H

#include <stdio.h>
#include "neuv/neuv.h"

typedef struct atomic_file {
    FILE *fp;
    char *target;
    char *tmp_path;
} atomic_file;

/* Opens a temporary file in the target's folder. Fails (NEUV_ERR_IO) with a
 * message naming the problem when the folder does not exist or is not writable,
 * or when the target is a directory. The file is opened in binary mode. */
neuv_status atomic_file_open(atomic_file *af, const char *target);
/* Flushes, fsyncs and renames into place; on any failure removes the temporary. */
neuv_status atomic_file_commit(atomic_file *af);
/* Removes the temporary file; safe to call after a failed open or a commit. */
void atomic_file_abort(atomic_file *af);

#endif
