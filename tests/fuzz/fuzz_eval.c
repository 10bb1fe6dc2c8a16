/* libFuzzer target: what `neuv eval` does with its input, on an OBJ with
 * texture coordinates: read, weld (neuv_mesh_weld), then every metric
 * (neuv_evaluate) and their JSON. The UVs are the file's, so the metrics see
 * folded, degenerate, huge and coincident UVs, unreferenced vt lines and
 * zero-area faces. Checked: the reader's contract (fuzz_check.h), then that
 * weld and evaluate either succeed, with counts in range, or fail with a
 * one-line NEUV_ERR_INPUT. */
#include <stdint.h>

#include "fuzz_check.h"
#include "io/mesh_io.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    if (size == 0 || memchr(data, '\0', size)) return 0;
    char *text = fuzz_text_copy(data, size);
    if (!text) return 0;
    neuv_mesh *m = NULL;
    neuv_status s = io_read_obj(text, size, &m);
    free(text);
    if (s != NEUV_OK) { fuzz_check_failure(s, m); return 0; }
    fuzz_check_mesh(m);
    if (!neuv_mesh_has_uv(m)) { mesh_free(m); return 0; }
    s = neuv_mesh_weld(m, NULL);
    if (s == NEUV_OK) {
        fuzz_check_mesh(m);
        neuv_metrics mt;
        s = neuv_evaluate(m, NULL, &mt);
        if (s == NEUV_OK) {
            if (mt.charts < 0 || mt.flipped < 0 || mt.flipped > m->nf || mt.degenerate_uv < 0 ||
                mt.degenerate_uv > m->nf || mt.excluded_faces < 0 || mt.excluded_faces > m->nf)
                abort();
            if (!(mt.overlap_fraction >= 0) && !isnan(mt.overlap_fraction)) abort();
            char *json = neuv_metrics_json(&mt, m, "fuzz.obj");
            if (!json) abort();
            neuv_free(json);
        } else if (s != NEUV_ERR_INPUT && s != NEUV_ERR_NOMEM) {
            abort();
        }
    } else {
        fuzz_check_failure(s, NULL);
    }
    mesh_free(m);
    return 0;
}
