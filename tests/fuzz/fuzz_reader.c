/* libFuzzer target for one of neuv's own mesh readers on arbitrary bytes,
 * chosen at compile time: -DFUZZ_READER_OBJ, -DFUZZ_READER_OFF or
 * -DFUZZ_READER_PLY give fuzz_obj, fuzz_off and fuzz_ply (scripts/fuzz.sh
 * builds them with clang, -fsanitize=fuzzer,address,undefined; ctest replays
 * the checked-in corpus tests/fuzz/corpus_<format>/ through
 * tests/fuzz/replay_main.c, under ASan/UBSan in `make sanitize`).
 * The input reaches the reader as neuv_mesh_load hands it over: never empty,
 * NUL-terminated, and for the text formats free of NUL bytes. */
#include <stdint.h>

#include "fuzz_check.h"
#include "io/mesh_io.h"

#if defined(FUZZ_READER_OBJ)
#define READ io_read_obj
#define TEXT 1
#elif defined(FUZZ_READER_OFF)
#define READ io_read_off
#define TEXT 1
#elif defined(FUZZ_READER_PLY)
#define READ io_read_ply
#define TEXT 0 /* binary PLY holds NUL bytes; the reader takes the length */
#else
#error "define FUZZ_READER_OBJ, FUZZ_READER_OFF or FUZZ_READER_PLY"
#endif

static neuv_status write_glb(const neuv_mesh *m, FILE *fp) { return io_write_gltf(m, fp, 1); }

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    if (size == 0 || (TEXT && memchr(data, '\0', size))) return 0;
    char *text = fuzz_text_copy(data, size);
    if (!text) return 0;
    neuv_mesh *m = NULL;
    neuv_status s = READ(text, size, &m);
    if (s == NEUV_OK) {
        fuzz_check_mesh(m);
        /* What was read goes back out: OBJ keeps vertices and faces (and
         * reads back), PLY splits vertices at seams (faces kept, read back),
         * glTF is written only. */
        fuzz_check_write_back(m, io_write_obj, io_read_obj, 1);
        fuzz_check_write_back(m, io_write_ply, io_read_ply, 0);
        fuzz_check_write_back(m, write_glb, NULL, 0);
    } else {
        fuzz_check_failure(s, m);
    }
    mesh_free(m);
    free(text);
    return 0;
}
