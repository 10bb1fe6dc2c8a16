/* Operator cache files. See operator_cache.h. */
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "core/atomic_file.h"
#include "core/error.h"
#include "core/hash.h"
#include "core/log.h"
#include "core/mem.h"
#include "core/timer.h"
#include "geometry/operator_cache.h"

/* NEUV_OPERATORS_CODE_HASH: generated at configure time into the build
 * folder (CMakeLists.txt), not a header of src/, hence the angle brackets. */
#include <operators_code_hash.h>

static const char CACHE_MAGIC[8] = {'N', 'E', 'U', 'V', 'O', 'P', 'S', '\0'};
static const uint32_t BYTE_ORDER_MARK = 0x01020304u;

/* Fixed-size header, written field by field in this order. */
typedef struct cache_header {
    char magic[8];
    uint32_t version, byte_order;
    uint64_t key;
    int32_t nv, k, n_hks, reserved;
    int64_t nnz_L, nnz_gx, nnz_gy;
    double sigma;
} cache_header;

const char *operator_cache_code_hash(void)
{
    return NEUV_OPERATORS_CODE_HASH;
}

/* A new field in operators_params changes what the operators are: it must
 * enter the key below, and then this size. */
_Static_assert(sizeof(operators_params) == 2 * sizeof(int), "operators_params changed: add its new field to the cache key");

uint64_t operator_cache_key_for(const neuv_mesh *m, const operators_params *p, const char *code_hash)
{
    operators_params q = p ? *p : operators_default_params();
    /* Field by field (no padding bytes), sizes first so that the arrays
     * after them cannot shift into one another. */
    int32_t head[5] = {m->nv, m->nf, q.k, q.n_hks, OPERATOR_CACHE_VERSION};
    uint64_t h = hash_bytes(HASH_INIT, head, sizeof head);
    h = hash_bytes(h, code_hash, strlen(code_hash) + 1);
    h = hash_bytes(h, m->pos, (size_t)m->nv * 3 * sizeof *m->pos);
    return hash_bytes(h, m->tri, (size_t)m->nf * 3 * sizeof *m->tri);
}

uint64_t operator_cache_key(const neuv_mesh *m, const operators_params *p)
{
    return operator_cache_key_for(m, p, operator_cache_code_hash());
}

/* mkdir -p */
static int make_dirs(char *path)
{
    for (char *p = path + 1; *p; p++)
        if (*p == '/') {
            *p = '\0';
            int bad = mkdir(path, 0755) != 0 && errno != EEXIST;
            *p = '/';
            if (bad) return -1;
        }
    if (mkdir(path, 0755) != 0 && errno != EEXIST) return -1;
    struct stat st;
    return stat(path, &st) == 0 && S_ISDIR(st.st_mode) ? 0 : -1;
}

neuv_status operator_cache_dir(char **dir)
{
    *dir = NULL;
    const char *xdg = getenv("XDG_CACHE_HOME"), *home = getenv("HOME");
    char *d = NULL;
    /* XDG: a relative XDG_CACHE_HOME is invalid and ignored. */
    if (xdg && xdg[0] == '/') {
        d = mem_alloc(strlen(xdg) + 8);
        if (d) sprintf(d, "%s/neuv", xdg);
    } else if (home && home[0]) {
        d = mem_alloc(strlen(home) + 16);
        if (d) sprintf(d, "%s/.cache/neuv", home);
    } else {
        return error_set(NEUV_ERR_IO, "no cache folder: neither XDG_CACHE_HOME nor HOME is set");
    }
    if (!d) return error_nomem("cache path");
    if (make_dirs(d) != 0) {
        neuv_status s = error_set(NEUV_ERR_IO, "cannot create cache folder %s: %s", d, strerror(errno));
        mem_free(d);
        return s;
    }
    *dir = d;
    return NEUV_OK;
}

/* ---- writing ---------------------------------------------------------- */

typedef struct writer {
    FILE *fp;
    uint32_t crc;
    int bad;
} writer;

static void put(writer *w, const void *p, size_t n)
{
    if (w->bad || n == 0) return;
    if (fwrite(p, 1, n, w->fp) != n) w->bad = 1;
    w->crc = crc32_bytes(w->crc, p, n);
}

static void put_sparse(writer *w, const sparse_matrix *a)
{
    put(w, a->row_start, ((size_t)a->rows + 1) * sizeof *a->row_start);
    put(w, a->col, sparse_nnz(a) * sizeof *a->col);
    put(w, a->val, sparse_nnz(a) * sizeof *a->val);
}

neuv_status operator_cache_save(const char *path, uint64_t key, const operators *ops)
{
    cache_header h;
    memset(&h, 0, sizeof h);
    memcpy(h.magic, CACHE_MAGIC, 8);
    h.version = OPERATOR_CACHE_VERSION;
    h.byte_order = BYTE_ORDER_MARK;
    h.key = key;
    h.nv = ops->nv;
    h.k = ops->k;
    h.n_hks = ops->n_hks;
    h.nnz_L = (int64_t)sparse_nnz(&ops->L);
    h.nnz_gx = (int64_t)sparse_nnz(&ops->grad_x);
    h.nnz_gy = (int64_t)sparse_nnz(&ops->grad_y);
    h.sigma = ops->sigma;

    atomic_file af;
    neuv_status s = atomic_file_open(&af, path);
    if (s) return s;
    writer w = {af.fp, 0, 0};
    put(&w, h.magic, 8);
    put(&w, &h.version, 4);
    put(&w, &h.byte_order, 4);
    put(&w, &h.key, 8);
    put(&w, &h.nv, 4);
    put(&w, &h.k, 4);
    put(&w, &h.n_hks, 4);
    put(&w, &h.reserved, 4);
    put(&w, &h.nnz_L, 8);
    put(&w, &h.nnz_gx, 8);
    put(&w, &h.nnz_gy, 8);
    put(&w, &h.sigma, 8);
    size_t nv = (size_t)ops->nv;
    put_sparse(&w, &ops->L);
    put(&w, ops->mass, nv * sizeof(double));
    put(&w, ops->evals, (size_t)ops->k * sizeof(double));
    put(&w, ops->evecs, nv * ops->k * sizeof(double));
    put(&w, ops->frames, nv * 9 * sizeof(double));
    put_sparse(&w, &ops->grad_x);
    put_sparse(&w, &ops->grad_y);
    put(&w, ops->hks, nv * ops->n_hks * sizeof(double));
    put(&w, ops->hks_times, (size_t)ops->n_hks * sizeof(double));
    uint32_t crc = w.crc;
    put(&w, &crc, 4);
    if (w.bad) {
        atomic_file_abort(&af);
        return error_set(NEUV_ERR_IO, "cannot write cache file %s", path);
    }
    return atomic_file_commit(&af);
}

/* ---- reading ---------------------------------------------------------- */

typedef struct reader {
    const unsigned char *p;
    size_t left;
} reader;

static int take(reader *r, void *dst, size_t n)
{
    if (n > r->left) return -1;
    memcpy(dst, r->p, n);
    r->p += n;
    r->left -= n;
    return 0;
}

/* Structure check: row starts from 0 to nnz, nondecreasing; columns in
 * range and strictly increasing within a row. */
static int sparse_valid(const sparse_matrix *a)
{
    if (a->row_start[0] != 0) return 0;
    for (int r = 0; r < a->rows; r++) {
        if (a->row_start[r + 1] < a->row_start[r]) return 0;
        for (int p = a->row_start[r]; p < a->row_start[r + 1]; p++)
            if (a->col[p] < 0 || a->col[p] >= a->cols || (p > a->row_start[r] && a->col[p] <= a->col[p - 1])) return 0;
    }
    return 1;
}

static int take_sparse(reader *r, int n, int64_t nnz, sparse_matrix *a)
{
    a->rows = a->cols = n;
    a->row_start = mem_alloc(((size_t)n + 1) * sizeof *a->row_start);
    a->col = mem_alloc(((size_t)nnz + 1) * sizeof *a->col);
    a->val = mem_alloc(((size_t)nnz + 1) * sizeof *a->val);
    if (!a->row_start || !a->col || !a->val) return -2;
    if (take(r, a->row_start, ((size_t)n + 1) * sizeof *a->row_start) || take(r, a->col, (size_t)nnz * sizeof *a->col) ||
        take(r, a->val, (size_t)nnz * sizeof *a->val))
        return -1;
    if (a->row_start[n] != nnz || !sparse_valid(a)) return -1;
    return 0;
}

static neuv_status bad_file(const char *path, const char *what)
{
    return error_set(NEUV_ERR_IO, "cache file %s: %s", path, what);
}

neuv_status operator_cache_load(const char *path, uint64_t key, int nv, int k, int n_hks, operators *ops)
{
    memset(ops, 0, sizeof *ops);
    FILE *fp = fopen(path, "rb");
    if (!fp) return error_set(NEUV_ERR_IO, "cache file %s: %s", path, strerror(errno));
    struct stat st;
    if (fstat(fileno(fp), &st) != 0 || !S_ISREG(st.st_mode)) { fclose(fp); return bad_file(path, "not a regular file"); }
    unsigned char hb[72]; /* the header fields below, packed */
    cache_header h;
    reader hr = {hb, sizeof hb};
    if (fread(hb, 1, sizeof hb, fp) != sizeof hb) { fclose(fp); return bad_file(path, "shorter than its header"); }
    take(&hr, h.magic, 8);
    take(&hr, &h.version, 4);
    take(&hr, &h.byte_order, 4);
    take(&hr, &h.key, 8);
    take(&hr, &h.nv, 4);
    take(&hr, &h.k, 4);
    take(&hr, &h.n_hks, 4);
    take(&hr, &h.reserved, 4);
    take(&hr, &h.nnz_L, 8);
    take(&hr, &h.nnz_gx, 8);
    take(&hr, &h.nnz_gy, 8);
    take(&hr, &h.sigma, 8);
    const char *why = NULL;
    if (memcmp(h.magic, CACHE_MAGIC, 8)) why = "not a neuv operator cache";
    else if (h.version != OPERATOR_CACHE_VERSION) why = "other format version";
    else if (h.byte_order != BYTE_ORDER_MARK) why = "other byte order";
    else if (h.key != key) why = "key does not match the mesh";
    else if (h.nv != nv || h.k != k || h.n_hks != n_hks) why = "sizes do not match the mesh";
    else if (h.nnz_L < 0 || h.nnz_gx < 0 || h.nnz_gy < 0 || h.nnz_L > 0x7fffffff || h.nnz_gx > 0x7fffffff ||
             h.nnz_gy > 0x7fffffff)
        why = "bad sparse sizes";
    if (why) { fclose(fp); return bad_file(path, why); }

    /* Whole expected length, then one read, then the CRC over all of it. */
    size_t n = (size_t)nv, ints = 3 * (n + 1) + (size_t)h.nnz_L + (size_t)h.nnz_gx + (size_t)h.nnz_gy;
    size_t doubles = (size_t)h.nnz_L + (size_t)h.nnz_gx + (size_t)h.nnz_gy + n + (size_t)k + n * k + 9 * n +
                     n * n_hks + (size_t)n_hks;
    size_t total = sizeof hb + ints * 4 + doubles * 8 + 4;
    if ((size_t)st.st_size != total) {
        fclose(fp);
        return bad_file(path, "length does not match its header (truncated?)");
    }
    unsigned char *buf = mem_alloc(total);
    if (!buf) { fclose(fp); return error_nomem("cache file"); }
    memcpy(buf, hb, sizeof hb);
    size_t got = fread(buf + sizeof hb, 1, total - sizeof hb, fp);
    fclose(fp);
    if (got != total - sizeof hb) { mem_free(buf); return bad_file(path, "truncated"); }
    uint32_t crc;
    memcpy(&crc, buf + total - 4, 4);
    if (crc32_bytes(0, buf, total - 4) != crc) { mem_free(buf); return bad_file(path, "checksum mismatch"); }

    reader r = {buf + sizeof hb, total - sizeof hb - 4};
    ops->nv = nv;
    ops->k = k;
    ops->n_hks = n_hks;
    ops->sigma = h.sigma;
    ops->mass = mem_alloc(n * sizeof(double));
    ops->evals = mem_alloc((size_t)k * sizeof(double));
    ops->evecs = mem_alloc(n * k * sizeof(double));
    ops->frames = mem_alloc(n * 9 * sizeof(double));
    ops->hks = mem_alloc(n * n_hks * sizeof(double));
    ops->hks_times = mem_alloc((size_t)n_hks * sizeof(double));
    int rc = -2;
    if (ops->mass && ops->evals && ops->evecs && ops->frames && ops->hks && ops->hks_times) {
        rc = take_sparse(&r, nv, h.nnz_L, &ops->L);
        if (!rc) rc = take(&r, ops->mass, n * sizeof(double));
        if (!rc) rc = take(&r, ops->evals, (size_t)k * sizeof(double));
        if (!rc) rc = take(&r, ops->evecs, n * k * sizeof(double));
        if (!rc) rc = take(&r, ops->frames, n * 9 * sizeof(double));
        if (!rc) rc = take_sparse(&r, nv, h.nnz_gx, &ops->grad_x);
        if (!rc) rc = take_sparse(&r, nv, h.nnz_gy, &ops->grad_y);
        if (!rc) rc = take(&r, ops->hks, n * n_hks * sizeof(double));
        if (!rc) rc = take(&r, ops->hks_times, (size_t)n_hks * sizeof(double));
        if (!rc && r.left != 0) rc = -1;
    }
    mem_free(buf);
    if (rc) {
        operators_free(ops);
        return rc == -2 ? error_nomem("cached operators") : bad_file(path, "inconsistent contents");
    }
    return NEUV_OK;
}

neuv_status operators_get(const neuv_mesh *m, const operators_params *params, int use_cache,
                          operators *ops, char **cache_path, int *cache_hit)
{
    operators_params p = params ? *params : operators_default_params();
    if (cache_path) *cache_path = NULL;
    if (cache_hit) *cache_hit = 0;
    memset(ops, 0, sizeof *ops);
    if (!use_cache || !m || m->nv <= 0 || m->nf <= 0 || p.k < 1 || p.n_hks < 1)
        return operators_compute(m, &p, ops);

    char *dir = NULL, *path = NULL;
    uint64_t key = operator_cache_key(m, &p);
    neuv_status s = operator_cache_dir(&dir);
    if (s == NEUV_ERR_NOMEM) return s;
    if (s != NEUV_OK) {
        log_message(NEUV_LOG_DEBUG, "operator cache off: %s", neuv_last_error());
    } else {
        path = mem_alloc(strlen(dir) + 32);
        if (path) sprintf(path, "%s/ops-%016llx.bin", dir, (unsigned long long)key);
        mem_free(dir);
        if (!path) return error_nomem("cache path");
    }
    /* Reading: anything but a valid file of this key is a miss. No file is
     * the usual miss and says nothing; a file that is there and unusable
     * (damaged, truncated, foreign, a folder) says why, then is replaced. */
    if (path) {
        double t0 = now_seconds();
        struct stat st;
        if (stat(path, &st) == 0) {
            int k = p.k < m->nv ? p.k : m->nv;
            s = operator_cache_load(path, key, m->nv, k, p.n_hks, ops);
            if (s == NEUV_OK) {
                ops->seconds.cache_load = now_seconds() - t0;
                ops->seconds.total = ops->seconds.cache_load;
                if (cache_hit) *cache_hit = 1;
                if (cache_path) *cache_path = path; else mem_free(path);
                log_progress("operators", 1.0, "from cache");
                return NEUV_OK;
            }
            if (s == NEUV_ERR_NOMEM) { mem_free(path); return s; }
            log_message(NEUV_LOG_INFO, "operator cache not used (%s); recomputing", neuv_last_error());
        } else if (errno != ENOENT) {
            log_message(NEUV_LOG_DEBUG, "operator cache file %s: %s; recomputing", path, strerror(errno));
        }
    }
    s = operators_compute(m, &p, ops);
    if (s) { mem_free(path); return s; }
    if (path) {
        s = operator_cache_save(path, key, ops);
        if (s == NEUV_ERR_NOMEM) { operators_free(ops); mem_free(path); return s; }
        if (s != NEUV_OK) log_message(NEUV_LOG_DEBUG, "operator cache not written: %s", neuv_last_error());
    }
    if (cache_path) *cache_path = path; else mem_free(path);
    return NEUV_OK;
}
