/* libFuzzer harness for the checkpoint loader (nn_checkpoint_parse).
 *
 * Not part of the CMake build (the project must build with gcc alone). Build and run:
 *
 *   apt-get install -y clang libclang-rt-14-dev
 *   clang -g -O1 -fsanitize=fuzzer,address,undefined -D_POSIX_C_SOURCE=200809L \
 *       -DNEUV_VERSION=\"fuzz\" -Iinclude -Isrc tests/fuzz/fuzz_checkpoint.c src/nn/checkpoint.c src/nn/tensor.c \
 *       src/core/error.c src/core/hash.c src/core/atomic_file.c -fopenmp -lm -o /tmp/fuzz_checkpoint
 *   mkdir -p /tmp/fuzz-work && cp -r tests/fuzz/corpus/. /tmp/fuzz-work/
 *   /tmp/fuzz_checkpoint -max_total_time=180 -max_len=4096 /tmp/fuzz-work
 *
 * Keep at most 20 small interesting inputs in tests/fuzz/corpus/ (libFuzzer's
 * -merge=1 into an empty folder picks a covering subset); tests/test_nn_checkpoint.c
 * loads each of them. The invariants checked here: no crash, no leak, and a
 * failure is NEUV_ERR_INPUT with one non-empty line, leaving the output empty. */
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "core/hash.h"
#include "nn/checkpoint.h"

static uint32_t get_u32(const uint8_t *p) { return (uint32_t)p[0] | (uint32_t)p[1] << 8 | (uint32_t)p[2] << 16 | (uint32_t)p[3] << 24; }
static void set_u32(uint8_t *p, uint32_t v) { p[0] = (uint8_t)v; p[1] = (uint8_t)(v >> 8); p[2] = (uint8_t)(v >> 16); p[3] = (uint8_t)(v >> 24); }

/* Rewrites every CRC field that lies inside the buffer to the right value, so
 * mutations reach the checks behind the CRCs (shapes, names, duplicates,
 * trailing bytes) instead of stopping at a CRC mismatch. */
static void fix_crcs(uint8_t *b, size_t n)
{
    size_t pos = 12;
    if (n < pos + 4) return;
    uint32_t hlen = get_u32(b + 12);
    pos = 16;
    if (hlen > n - pos || n - pos - hlen < 4) return;
    set_u32(b + pos + hlen, crc32_bytes(0, b + pos, hlen));
    pos += (size_t)hlen + 4;
    if (n - pos < 4) return;
    uint32_t count = get_u32(b + pos);
    pos += 4;
    for (uint32_t i = 0; i < count && i < 1000; i++) {
        if (n - pos < 4) return;
        uint32_t nlen = get_u32(b + pos);
        pos += 4;
        if (nlen > n - pos || n - pos - nlen < 12) return;
        const uint8_t *name = b + pos;
        pos += nlen;
        uint64_t bytes = (uint64_t)get_u32(b + pos) * get_u32(b + pos + 4) * 4;
        uint32_t crc = crc32_bytes(crc32_bytes(0, name, nlen), b + pos, 8);
        size_t crc_at = pos + 8;
        pos += 12;
        if (bytes > n - pos) return;
        set_u32(b + crc_at, crc32_bytes(crc, b + pos, (size_t)bytes));
        pos += (size_t)bytes;
    }
}

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
    check_one(data, size);
    uint8_t *copy = malloc(size ? size : 1);
    if (!copy) return 0;
    memcpy(copy, data, size);
    fix_crcs(copy, size);
    check_one(copy, size);
    free(copy);
    return 0;
}
