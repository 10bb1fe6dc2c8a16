/* Up-front memory estimate and budget for training (memory_budget.h). */
#include "unwrap/memory_budget.h"

#include <stdio.h>
#include <unistd.h>

#include "core/error.h"

/* Peak resident bytes per face of `neuv unwrap --train-faces 0`, default
 * options, one thread, measured on procedural blobs of 5k to 328k faces
 * (bench/bench_memory.sh; bench/RESULTS.md "Memory"): the largest of the
 * per-face figures, times a margin of 1.25 for other shapes and thread
 * counts. A fixed part (the program, its libraries, BLAS buffers) is added. */
enum { TRAIN_BYTES_PER_FACE = 10 * 1024, FIXED_BYTES = 96 << 20 };
static const double MARGIN = 1.25;

double memory_training_estimate(double faces)
{
    return FIXED_BYTES + MARGIN * TRAIN_BYTES_PER_FACE * (faces > 0 ? faces : 0);
}

double memory_budget_bytes(int max_memory_mb)
{
    if (max_memory_mb > 0) return (double)max_memory_mb * 1024 * 1024;
    long pages = sysconf(_SC_PHYS_PAGES), page = sysconf(_SC_PAGESIZE);
    if (pages <= 0 || page <= 0) return -1;
    return 0.5 * (double)pages * (double)page;
}

/* "1.5 GiB" or "96 MiB". */
static void size_text(double bytes, char *out, size_t n)
{
    const double mib = 1024.0 * 1024, gib = 1024 * mib;
    if (bytes >= gib) snprintf(out, n, "%.1f GiB", bytes / gib);
    else snprintf(out, n, "%.0f MiB", bytes / mib);
}

neuv_status memory_check_training(double faces, int max_memory_mb, const char *what, const char *hint)
{
    if (max_memory_mb < 0)
        return error_set(NEUV_ERR_INPUT, "max_memory_mb must be 0 (half of the machine's memory) or a size in MiB");
    double need = memory_training_estimate(faces), budget = memory_budget_bytes(max_memory_mb);
    if (budget < 0 || need <= budget) return NEUV_OK;
    char need_s[32], budget_s[32];
    size_text(need, need_s, sizeof need_s);
    size_text(budget, budget_s, sizeof budget_s);
    return error_set(NEUV_ERR_NOMEM, "training on all %.0f faces of %s needs about %s, over the memory budget of %s (%s): %s",
                     faces, what, need_s, budget_s,
                     max_memory_mb > 0 ? "--max-memory" : "half of this machine's memory", hint);
}
