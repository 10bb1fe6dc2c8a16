/* libFuzzer target: neuv's glTF 2.0 reader (io_read_gltf) on arbitrary
 * bytes, as a .glb or a .gltf (the reader tells them by the GLB magic).
 * Buffers naming files are refused here (no folder is given), as they are
 * for any reader of bytes in memory. Checked: a whole mesh, or a one-line
 * NEUV_ERR_INPUT (NEUV_ERR_NOMEM) with no mesh. The seeds are what
 * io_write_gltf writes, both forms, plus hand-made node trees. */
#include <stdint.h>

#include "fuzz_check.h"
#include "io/mesh_io.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    neuv_mesh *m = NULL;
    neuv_status s = io_read_gltf((const char *)data, size, NULL, &m);
    if (s == NEUV_OK) fuzz_check_mesh(m);
    else fuzz_check_failure(s, m);
    mesh_free(m);
    return 0;
}
