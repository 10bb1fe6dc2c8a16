/* Checkpoint files: magic, version, JSON header, named float32 tensors with CRC32.
 * The loader trusts nothing: every length is checked against the bytes that
 * remain before anything is allocated or copied. */
#include "nn/checkpoint.h"

#include <errno.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "core/atomic_file.h"
#include "core/error.h"
#include "core/hash.h"
#include "core/mem.h"

static const char MAGIC[8] = {'N', 'E', 'U', 'V', 'M', 'O', 'D', 'L'};
/* Smallest tensor record: name length, a 1-byte name, rows, cols, CRC, no data. */
#define MIN_TENSOR_RECORD 17

/* ---- writing --------------------------------------------------------- */

static void put_u32(unsigned char *b, uint32_t v)
{
    b[0] = (unsigned char)v; b[1] = (unsigned char)(v >> 8);
    b[2] = (unsigned char)(v >> 16); b[3] = (unsigned char)(v >> 24);
}

static int write_u32(FILE *fp, uint32_t v)
{
    unsigned char b[4];
    put_u32(b, v);
    return fwrite(b, 1, 4, fp) == 4;
}

/* Little-endian bytes of floats, in chunks, with the running CRC. */
static int write_floats(FILE *fp, const float *x, size_t n, uint32_t *crc)
{
    unsigned char buf[4096];
    size_t i = 0;
    while (i < n) {
        size_t m = n - i < sizeof buf / 4 ? n - i : sizeof buf / 4;
        for (size_t k = 0; k < m; k++) {
            uint32_t u;
            memcpy(&u, &x[i + k], 4);
            put_u32(buf + 4 * k, u);
        }
        if (crc) *crc = crc32_bytes(*crc, buf, 4 * m);
        else if (fwrite(buf, 1, 4 * m, fp) != 4 * m) return 0;
        i += m;
    }
    return 1;
}

static int name_ok(const char *s, size_t n)
{
    if (n < 1 || n > NN_CHECKPOINT_MAX_NAME) return 0;
    for (size_t i = 0; i < n; i++)
        if ((unsigned char)s[i] < 0x20 || (unsigned char)s[i] > 0x7e) return 0;
    return 1;
}

/* CRC of a tensor record's name and shape; the data bytes continue it, so a
 * damaged name or shape is caught like damaged data. */
static uint32_t record_crc(const char *name, uint32_t name_len, uint32_t rows, uint32_t cols)
{
    unsigned char shape[8];
    put_u32(shape, rows);
    put_u32(shape + 4, cols);
    return crc32_bytes(crc32_bytes(0, name, name_len), shape, 8);
}

neuv_status nn_checkpoint_save(const char *path, const char *config,
                               nn_tensor *const *t, const char *const *names, int n)
{
    if (!config) config = "{}";
    if (n < 0) return error_set(NEUV_ERR_INTERNAL, "checkpoint: %d tensors", n);
    for (int i = 0; i < n; i++) {
        const char *nm = names ? names[i] : t[i]->name;
        if (!nm || !name_ok(nm, strlen(nm)))
            return error_set(NEUV_ERR_INPUT, "checkpoint: tensor %d needs a printable name of 1..%d characters",
                             i, NN_CHECKPOINT_MAX_NAME);
    }
    size_t hlen = strlen(config);
    if (hlen > UINT32_MAX) return error_set(NEUV_ERR_INPUT, "checkpoint: header too long");
    atomic_file af;
    neuv_status st = atomic_file_open(&af, path);
    if (st != NEUV_OK) return st;
    int ok = fwrite(MAGIC, 1, 8, af.fp) == 8 && write_u32(af.fp, NN_CHECKPOINT_VERSION) &&
             write_u32(af.fp, (uint32_t)hlen) && fwrite(config, 1, hlen, af.fp) == hlen &&
             write_u32(af.fp, crc32_bytes(0, config, hlen)) && write_u32(af.fp, (uint32_t)n);
    for (int i = 0; ok && i < n; i++) {
        const char *nm = names ? names[i] : t[i]->name;
        size_t count = (size_t)t[i]->rows * (size_t)t[i]->cols;
        uint32_t crc = record_crc(nm, (uint32_t)strlen(nm), (uint32_t)t[i]->rows, (uint32_t)t[i]->cols);
        write_floats(NULL, t[i]->data, count, &crc);
        ok = write_u32(af.fp, (uint32_t)strlen(nm)) && fwrite(nm, 1, strlen(nm), af.fp) == strlen(nm) &&
             write_u32(af.fp, (uint32_t)t[i]->rows) && write_u32(af.fp, (uint32_t)t[i]->cols) &&
             write_u32(af.fp, crc) && write_floats(af.fp, t[i]->data, count, NULL);
    }
    if (!ok) {
        atomic_file_abort(&af);
        return error_set(NEUV_ERR_IO, "cannot write checkpoint %s", path);
    }
    return atomic_file_commit(&af);
}

neuv_status nn_checkpoint_save_params(const char *path, const char *config, const nn_params *ps)
{
    return nn_checkpoint_save(path, config, ps->t, NULL, ps->n);
}

/* ---- reading --------------------------------------------------------- */

typedef struct reader {
    const unsigned char *p;
    size_t left;
} reader;

static int read_u32(reader *r, uint32_t *v)
{
    if (r->left < 4) return 0;
    *v = (uint32_t)r->p[0] | (uint32_t)r->p[1] << 8 | (uint32_t)r->p[2] << 16 | (uint32_t)r->p[3] << 24;
    r->p += 4;
    r->left -= 4;
    return 1;
}

void nn_checkpoint_free(nn_checkpoint *c)
{
    if (!c) return;
    for (int i = 0; i < c->n; i++) {
        mem_free(c->t[i].name);
        mem_free(c->t[i].data);
    }
    mem_free(c->t);
    mem_free(c->config);
    memset(c, 0, sizeof *c);
}

static neuv_status truncated(const char *what, size_t need, size_t left)
{
    return error_set(NEUV_ERR_INPUT, "truncated checkpoint: %s needs %zu bytes, %zu left", what, need, left);
}

static neuv_status parse(reader *r, nn_checkpoint *out)
{
    if (r->left < 8) return truncated("magic", 8, r->left);
    if (memcmp(r->p, MAGIC, 8) != 0) return error_set(NEUV_ERR_INPUT, "not a neuv checkpoint (bad magic)");
    r->p += 8;
    r->left -= 8;
    uint32_t version, hlen, hcrc = 0, count;
    if (!read_u32(r, &version)) return truncated("version", 4, r->left);
    if (version != NN_CHECKPOINT_VERSION)
        return error_set(NEUV_ERR_INPUT, "wrong checkpoint version %u (this neuv reads %d)", version,
                         NN_CHECKPOINT_VERSION);
    out->version = version;
    if (!read_u32(r, &hlen)) return truncated("header length", 4, r->left);
    if ((size_t)hlen + 4 > r->left) return truncated("JSON header", (size_t)hlen + 4, r->left);
    if (memchr(r->p, 0, hlen)) return error_set(NEUV_ERR_INPUT, "checkpoint header contains a NUL byte");
    out->config = mem_alloc((size_t)hlen + 1);
    if (!out->config) return error_nomem("checkpoint header");
    memcpy(out->config, r->p, hlen);
    out->config[hlen] = '\0';
    uint32_t crc = crc32_bytes(0, r->p, hlen);
    r->p += hlen;
    r->left -= hlen;
    read_u32(r, &hcrc);
    if (crc != hcrc)
        return error_set(NEUV_ERR_INPUT, "CRC mismatch in checkpoint header (stored %08x, computed %08x)", hcrc, crc);
    if (!read_u32(r, &count)) return truncated("tensor count", 4, r->left);
    if ((uint64_t)count * MIN_TENSOR_RECORD > r->left)
        return error_set(NEUV_ERR_INPUT, "truncated checkpoint: %u tensors announced but only %zu bytes follow",
                         count, r->left);
    out->t = mem_calloc(count ? count : 1, sizeof *out->t);
    if (!out->t) return error_nomem("checkpoint tensor list");
    for (uint32_t i = 0; i < count; i++) {
        uint32_t nlen, rows, cols, dcrc;
        if (!read_u32(r, &nlen)) return truncated("tensor name length", 4, r->left);
        if (nlen < 1 || nlen > NN_CHECKPOINT_MAX_NAME)
            return error_set(NEUV_ERR_INPUT, "tensor %u: name length %u outside 1..%d", i, nlen,
                             NN_CHECKPOINT_MAX_NAME);
        if (nlen > r->left) return truncated("tensor name", nlen, r->left);
        if (!name_ok((const char *)r->p, nlen))
            return error_set(NEUV_ERR_INPUT, "tensor %u: name has non-printable bytes", i);
        char name[NN_CHECKPOINT_MAX_NAME + 1];
        memcpy(name, r->p, nlen);
        name[nlen] = '\0';
        r->p += nlen;
        r->left -= nlen;
        if (r->left < 12)
            return error_set(NEUV_ERR_INPUT, "truncated checkpoint: tensor '%s' shape and CRC need 12 bytes, %zu left",
                             name, r->left);
        read_u32(r, &rows);
        read_u32(r, &cols);
        read_u32(r, &dcrc);
        if (rows == 0 || cols == 0 || rows > INT32_MAX || cols > INT32_MAX || (uint64_t)rows * cols > INT32_MAX)
            return error_set(NEUV_ERR_INPUT, "tensor '%s': shape %u by %u is not usable", name, rows, cols);
        uint64_t bytes = (uint64_t)rows * cols * 4;
        if (bytes > r->left) {
            return error_set(NEUV_ERR_INPUT, "truncated checkpoint: tensor '%s' needs %llu bytes, %zu left", name,
                             (unsigned long long)bytes, r->left);
        }
        for (uint32_t k = 0; k < i; k++)
            if (!strcmp(out->t[k].name, name))
                return error_set(NEUV_ERR_INPUT, "tensor '%s' appears twice", name);
        uint32_t got = crc32_bytes(record_crc(name, nlen, rows, cols), r->p, (size_t)bytes);
        if (got != dcrc)
            return error_set(NEUV_ERR_INPUT, "CRC mismatch in tensor '%s' (stored %08x, computed %08x)", name,
                             dcrc, got);
        nn_checkpoint_tensor *t = &out->t[i];
        t->name = mem_strdup(name);
        t->data = mem_alloc((size_t)bytes);
        if (!t->name || !t->data) {
            mem_free(t->name); mem_free(t->data);
            t->name = NULL; t->data = NULL;
            return error_nomem("checkpoint tensor");
        }
        t->rows = (int)rows;
        t->cols = (int)cols;
        out->n = (int)i + 1;
        for (size_t k = 0; k < (size_t)rows * cols; k++) {
            const unsigned char *b = r->p + 4 * k;
            uint32_t u = (uint32_t)b[0] | (uint32_t)b[1] << 8 | (uint32_t)b[2] << 16 | (uint32_t)b[3] << 24;
            memcpy(&t->data[k], &u, 4);
        }
        r->p += bytes;
        r->left -= (size_t)bytes;
    }
    if (r->left) return error_set(NEUV_ERR_INPUT, "%zu unexpected bytes after the last tensor", r->left);
    return NEUV_OK;
}

neuv_status nn_checkpoint_parse(const void *bytes, size_t len, nn_checkpoint *out)
{
    memset(out, 0, sizeof *out);
    reader r = {bytes, len};
    if (!bytes && len) return error_set(NEUV_ERR_INTERNAL, "checkpoint: no bytes");
    neuv_status st = parse(&r, out);
    if (st != NEUV_OK) nn_checkpoint_free(out);
    return st;
}

neuv_status nn_checkpoint_load(const char *path, nn_checkpoint *out)
{
    memset(out, 0, sizeof *out);
    FILE *fp = fopen(path, "rb");
    if (!fp) return error_set(NEUV_ERR_IO, "cannot open: %s", strerror(errno));
    struct stat info;
    if (fstat(fileno(fp), &info) != 0 || !S_ISREG(info.st_mode)) {
        fclose(fp);
        return error_set(NEUV_ERR_IO, "cannot read: not a regular file");
    }
    long size = (long)info.st_size;
    unsigned char *buf = mem_alloc(size ? (size_t)size : 1);
    if (!buf) { fclose(fp); return error_nomem("checkpoint file"); }
    size_t got = fread(buf, 1, (size_t)size, fp);
    int err = ferror(fp);
    fclose(fp);
    if (err || got != (size_t)size) { mem_free(buf); return error_set(NEUV_ERR_IO, "read failed"); }
    neuv_status st = nn_checkpoint_parse(buf, (size_t)size, out);
    mem_free(buf);
    return st;
}

const nn_checkpoint_tensor *nn_checkpoint_find(const nn_checkpoint *c, const char *name)
{
    for (int i = 0; i < c->n; i++)
        if (!strcmp(c->t[i].name, name)) return &c->t[i];
    return NULL;
}

neuv_status nn_checkpoint_restore_params(const nn_checkpoint *c, nn_params *ps)
{
    for (int i = 0; i < ps->n; i++) {
        nn_tensor *p = ps->t[i];
        const nn_checkpoint_tensor *t = nn_checkpoint_find(c, p->name);
        if (!t) return error_set(NEUV_ERR_INPUT, "checkpoint has no tensor '%s'", p->name);
        if (t->rows != p->rows || t->cols != p->cols)
            return error_set(NEUV_ERR_INPUT, "tensor '%s' is %d by %d in the checkpoint, the model needs %d by %d",
                             p->name, t->rows, t->cols, p->rows, p->cols);
    }
    for (int i = 0; i < ps->n; i++) {
        const nn_checkpoint_tensor *t = nn_checkpoint_find(c, ps->t[i]->name);
        memcpy(ps->t[i]->data, t->data, (size_t)t->rows * (size_t)t->cols * sizeof(float));
    }
    return NEUV_OK;
}
