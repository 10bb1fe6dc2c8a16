/* libFuzzer target: the model loader behind neuv_model_load
 * (unwrap_model_parse: the checkpoint container, then the model's header
 * keys and ranges, every tensor's presence and shape, face, chart and network
 * indices). Each input is tried as it is and with its CRC fields rewritten,
 * so that mutations of a real saved model reach the model's own checks.
 * Checked: a model that loads is freed cleanly; a failure is NEUV_ERR_INPUT
 * (or NEUV_ERR_NOMEM) with one non-empty line and no model. */
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "checkpoint_crcs.h"
#include "fuzz_check.h"
#include "unwrap/unwrap_model.h"

static void check_one(const uint8_t *data, size_t size)
{
    unwrap_model *md = NULL;
    neuv_status s = unwrap_model_parse(data, size, &md);
    if (s == NEUV_OK) {
        if (!md) abort();
        unwrap_model_free(md);
        return;
    }
    fuzz_check_failure(s, md);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    fuzz_as_is_and_crcs_fixed(data, size, check_one);
    return 0;
}
