/* Checkpoint files: bit-exact round trip, verbatim configuration, and clean
 * one-line errors for every truncation, every damaged byte and the fuzz corpus. */
#include "check.h"

#include <dirent.h>
#include <stdint.h>

#include "core/hash.h"
#include "nn/checkpoint.h"
#include "nn/nn.h"

static unsigned char *read_all(const char *path, size_t *len)
{
    FILE *fp = fopen(path, "rb");
    if (!fp) return NULL;
    fseek(fp, 0, SEEK_END);
    long n = ftell(fp);
    fseek(fp, 0, SEEK_SET);
    unsigned char *b = malloc(n > 0 ? (size_t)n : 1);
    *len = fread(b, 1, (size_t)n, fp);
    fclose(fp);
    return b;
}

static void write_all(const char *path, const unsigned char *b, size_t n)
{
    FILE *fp = fopen(path, "wb");
    fwrite(b, 1, n, fp);
    fclose(fp);
}

/* A failure must be NEUV_ERR_INPUT with a non-empty single-line message. */
static int clean_input_error(neuv_status st)
{
    const char *m = neuv_last_error();
    return st == NEUV_ERR_INPUT && m[0] && !strchr(m, '\n');
}

static const char *CONFIG = "{\"model\": \"mlp\", \"width\": 8, \"note\": \"quotes \\\" and\\nnewlines\"}";

static void test_round_trip(const char *path)
{
    nn_params ps;
    nn_params_init(&ps);
    nn_tensor *a = nn_params_add(&ps, 3, 4, "mlp.0.w");
    nn_tensor *b = nn_params_add(&ps, 1, 4, "mlp.0.b");
    nn_tensor *c = nn_params_add(&ps, 1, 1, "diffusion.time");
    uint32_t specials[8] = {0x7fc12345u /* NaN with payload */, 0x80000000u /* -0 */, 0x00000001u /* denormal */,
                            0x7f800000u /* inf */, 0xff800000u, 0x7f7fffffu, 0x3eaaaaabu, 0xbf800000u};
    for (int i = 0; i < 12; i++) {
        uint32_t u = i < 8 ? specials[i] : 0x3f000000u + (uint32_t)i * 77777u;
        memcpy(&a->data[i], &u, 4);
    }
    for (int i = 0; i < 4; i++) b->data[i] = (float)i / 3.0f;
    c->data[0] = 1e-8f;
    CHECK_INT(nn_checkpoint_save_params(path, CONFIG, &ps), NEUV_OK);

    nn_checkpoint ck;
    CHECK_INT(nn_checkpoint_load(path, &ck), NEUV_OK);
    CHECK_INT(ck.version, NN_CHECKPOINT_VERSION);
    CHECK(ck.config && !strcmp(ck.config, CONFIG));
    CHECK_INT(ck.n, 3);
    const nn_checkpoint_tensor *t = nn_checkpoint_find(&ck, "mlp.0.w");
    CHECK(t && t->rows == 3 && t->cols == 4 && !memcmp(t->data, a->data, 12 * sizeof(float)));
    t = nn_checkpoint_find(&ck, "diffusion.time");
    CHECK(t && t->rows == 1 && t->cols == 1 && !memcmp(t->data, c->data, sizeof(float)));
    CHECK(nn_checkpoint_find(&ck, "missing") == NULL);

    /* Restore into a fresh model of the same shapes: identical bytes. */
    nn_params ps2;
    nn_params_init(&ps2);
    nn_params_add(&ps2, 3, 4, "mlp.0.w");
    nn_params_add(&ps2, 1, 4, "mlp.0.b");
    nn_params_add(&ps2, 1, 1, "diffusion.time");
    CHECK_INT(nn_checkpoint_restore_params(&ck, &ps2), NEUV_OK);
    for (int i = 0; i < 3; i++)
        CHECK(!memcmp(ps.t[i]->data, ps2.t[i]->data, (size_t)ps.t[i]->rows * ps.t[i]->cols * sizeof(float)));
    /* A model whose shapes differ is refused with the tensor's name. */
    nn_params ps3;
    nn_params_init(&ps3);
    nn_params_add(&ps3, 4, 4, "mlp.0.w");
    CHECK_INT(nn_checkpoint_restore_params(&ck, &ps3), NEUV_ERR_INPUT);
    CHECK(strstr(neuv_last_error(), "'mlp.0.w' is 3 by 4") != NULL);
    nn_params_add(&ps3, 1, 1, "other");
    nn_params_free(&ps3);
    nn_params_free(&ps2);
    nn_checkpoint_free(&ck);
    nn_params_free(&ps);
}

static void test_malformed(const char *path)
{
    size_t len = 0;
    unsigned char *good = read_all(path, &len);
    CHECK(good != NULL && len > 100);
    if (!good) return;
    unsigned char *buf = malloc(len + 8);
    nn_checkpoint ck;
    /* Every truncation. */
    int bad = 0;
    for (size_t n = 0; n < len; n++)
        if (!clean_input_error(nn_checkpoint_parse(good, n, &ck))) bad++;
    CHECK_INT(bad, 0);
    CHECK(nn_checkpoint_parse(good, len - 1, &ck) == NEUV_ERR_INPUT &&
          strstr(neuv_last_error(), "truncated checkpoint: tensor 'diffusion.time' needs 4 bytes, 3 left"));
    /* Every damaged byte (a CRC covers the header and each record). */
    bad = 0;
    for (size_t i = 0; i < len; i++) {
        memcpy(buf, good, len);
        buf[i] ^= 0x10;
        if (!clean_input_error(nn_checkpoint_parse(buf, len, &ck))) {
            bad++;
            fprintf(stderr, "byte %zu damaged: status %d (%s)\n", i, nn_checkpoint_parse(buf, len, &ck),
                    neuv_last_error());
            nn_checkpoint_free(&ck);
        }
    }
    CHECK_INT(bad, 0);
    /* Specific messages. */
    memcpy(buf, good, len);
    buf[8] = 7;
    CHECK_INT(nn_checkpoint_parse(buf, len, &ck), NEUV_ERR_INPUT);
    CHECK(!strcmp(neuv_last_error(), "wrong checkpoint version 7 (this neuv reads 1)"));
    memcpy(buf, good, len);
    buf[len - 1] ^= 0xff;
    CHECK_INT(nn_checkpoint_parse(buf, len, &ck), NEUV_ERR_INPUT);
    CHECK(strstr(neuv_last_error(), "CRC mismatch in tensor 'diffusion.time'") != NULL);
    memcpy(buf, good, len);
    buf[len] = 0;
    CHECK_INT(nn_checkpoint_parse(buf, len + 1, &ck), NEUV_ERR_INPUT);
    CHECK(strstr(neuv_last_error(), "1 unexpected bytes after the last tensor") != NULL);
    memcpy(buf, "NEUVMODX", 8);
    CHECK_INT(nn_checkpoint_parse(buf, len, &ck), NEUV_ERR_INPUT);
    CHECK(strstr(neuv_last_error(), "bad magic") != NULL);
    /* Unreadable path. */
    CHECK_INT(nn_checkpoint_load(tmp_path("no-such-dir/x.neuv"), &ck), NEUV_ERR_IO);
    write_all(tmp_path("nn_trunc.neuv"), good, 30);
    CHECK_INT(nn_checkpoint_load(tmp_path("nn_trunc.neuv"), &ck), NEUV_ERR_INPUT);
    free(buf);
    free(good);
}

static void test_huge_claim(void)
{
    /* Valid header CRC, then a tensor of 40000 by 40000 floats in a tiny file. */
    unsigned char b[64];
    size_t n = 0;
    memcpy(b, "NEUVMODL", 8); n = 8;
    uint32_t v[3] = {1, 2, 0};
    memcpy(b + n, &v[0], 4); n += 4;
    memcpy(b + n, &v[1], 4); n += 4;
    memcpy(b + n, "{}", 2); n += 2;
    uint32_t c = crc32_bytes(0, "{}", 2);
    memcpy(b + n, &c, 4); n += 4;
    uint32_t rest[5] = {1 /* count */, 1 /* name len */, 0, 40000, 40000};
    memcpy(b + n, &rest[0], 4); n += 4;
    memcpy(b + n, &rest[1], 4); n += 4;
    b[n++] = 'w';
    memcpy(b + n, &rest[3], 4); n += 4;
    memcpy(b + n, &rest[4], 4); n += 4;
    memset(b + n, 0, 8); n += 8;
    nn_checkpoint ck;
    CHECK_INT(nn_checkpoint_parse(b, n, &ck), NEUV_ERR_INPUT);
    CHECK(strstr(neuv_last_error(), "tensor 'w' needs 6400000000 bytes, 4 left") != NULL);
}

static void test_corpus(void)
{
    /* tests/fuzz/corpus beside this source file. */
    char dir[4096];
    snprintf(dir, sizeof dir, "%s", __FILE__);
    char *slash = strrchr(dir, '/');
    if (!slash) return;
    snprintf(slash, sizeof dir - (size_t)(slash - dir), "/fuzz/corpus");
    DIR *d = opendir(dir);
    CHECK(d != NULL);
    if (!d) return;
    int files = 0, ok = 0;
    struct dirent *e;
    while ((e = readdir(d))) {
        if (e->d_name[0] == '.') continue;
        char p[8192];
        snprintf(p, sizeof p, "%s/%s", dir, e->d_name);
        nn_checkpoint ck;
        neuv_status st = nn_checkpoint_load(p, &ck);
        files++;
        if (st == NEUV_OK) { ok++; nn_checkpoint_free(&ck); }
        else {
            CHECK(clean_input_error(st));
            CHECK(ck.t == NULL && ck.config == NULL);
        }
    }
    closedir(d);
    printf("  corpus: %d files, %d valid checkpoints\n", files, ok);
    CHECK(files >= 5);
}

int main(void)
{
    const char *path = tmp_path("nn_round_trip.neuv");
    test_round_trip(path);
    test_malformed(path);
    test_huge_claim();
    test_corpus();
    return check_report("test_nn_checkpoint");
}
