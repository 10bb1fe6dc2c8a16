/* libFuzzer target: the checkpoint container (nn_checkpoint_parse), each
 * input tried as it is and with its CRC fields rewritten.
 *
 * Built by scripts/fuzz.sh (clang, -fsanitize=fuzzer,address,undefined);
 * the corpus tests/fuzz/corpus/ is replayed by ctest (fuzz_replay_checkpoint,
 * under ASan/UBSan in `make sanitize`), and tests/test_nn_checkpoint.c and
 * tests/cli_checkpoint.sh load each of its files too. The invariants checked
 * here: no crash, no leak, and a failure is NEUV_ERR_INPUT with one
 * non-empty line, leaving the output empty. */
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "checkpoint_crcs.h"
#include "nn/checkpoint.h"

static void check_one(const uint8_t *data, size_t size)
{
    nn_checkpoint ck;
    neuv_status st = nn_checkpoint_parse(data, size, &ck);
    if (st == NEUV_OK) {
        /* Touch everything the loader returned. */
        volatile float sink = 0;
        size_t hl = strlen(ck.config);
        (void)hl;
        for (int i = 0; i < ck.n; i++) {
            if (!nn_checkpoint_find(&ck, ck.t[i].name)) abort();
            for (long k = 0; k < (long)ck.t[i].rows * ck.t[i].cols; k++) sink += ck.t[i].data[k];
        }
        (void)sink;
        nn_checkpoint_free(&ck);
        return;
    }
    const char *m = neuv_last_error();
    if (st != NEUV_ERR_INPUT || !m[0] || strchr(m, '\n')) abort();
    if (ck.t || ck.config || ck.n) abort();
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    fuzz_as_is_and_crcs_fixed(data, size, check_one);
    return 0;
}
