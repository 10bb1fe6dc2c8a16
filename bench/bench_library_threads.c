/* The library as a program embeds it, on T threads: one unwrap of a mesh
 * through the public API, its stage times from the report. libgomp reads
 * OMP_WAIT_POLICY when it is loaded, so the wait policy is the process's;
 * bench_library_threads.sh runs this under each policy, alternating, to
 * compare what an embedding program gets (libgomp's default) with what the
 * CLI sets for itself (PASSIVE).
 *
 *   ./build/bench/bench_library_threads MESH [threads] [iters] [max_memory_mb]
 *
 * Prints one line: total, operators, patches, param, repair and pack
 * seconds. */
#include <stdio.h>
#include <stdlib.h>

#include "neuv/neuv.h"

int main(int argc, char **argv)
{
    if (argc < 2) {
        fprintf(stderr, "usage: bench_library_threads MESH [threads] [iters] [max_memory_mb]\n");
        return 2;
    }
    neuv_mesh *mesh = NULL;
    if (neuv_mesh_load(argv[1], NULL, &mesh) != NEUV_OK) {
        fprintf(stderr, "bench_library_threads: %s\n", neuv_last_error());
        return 2;
    }
    neuv_unwrap_options o;
    neuv_unwrap_options_init(&o);
    o.threads = argc > 2 ? atoi(argv[2]) : 2;
    o.iters = argc > 3 ? atoi(argv[3]) : 0;
    o.max_memory_mb = argc > 4 ? atoi(argv[4]) : 0;
    o.use_cache = 0;
    neuv_atlas *a = NULL;
    neuv_status s = neuv_atlas_create(&a);
    if (s == NEUV_OK) s = neuv_atlas_add_loaded_mesh(a, mesh);
    if (s == NEUV_OK) s = neuv_atlas_generate(a, &o);
    neuv_report r;
    if (s == NEUV_OK) s = neuv_atlas_get_report(a, &r);
    if (s != NEUV_OK) {
        fprintf(stderr, "bench_library_threads: %s\n", neuv_last_error());
        neuv_atlas_destroy(a);
        neuv_mesh_free(mesh);
        return 1;
    }
    printf("%.3f %.3f %.3f %.3f %.3f %.3f\n", r.seconds_total, r.seconds_operators, r.seconds_patches, r.seconds_param,
           r.seconds_repair, r.seconds_pack);
    neuv_atlas_destroy(a);
    neuv_mesh_free(mesh);
    return 0;
}
