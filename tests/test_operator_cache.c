/* Operator cache.
 *
 * Key: changes with each input the operators depend on (each field of
 * operators_params, the vertex and face counts, one coordinate moved by one
 * ulp, the order of one triangle's indices, the order of two triangles, the
 * digest of the code) and with nothing else (a copy of the mesh: same key).
 *
 * Files: a miss writes, a hit reads the same operators bit for bit. Then the
 * file is damaged in every way below, and each time the next operators_get
 * must not fail, must not take the file (a miss), must return operators
 * equal to freshly computed ones (every value, bit for bit, and the eigen
 * shift), and must leave a new valid file (byte-identical to the first,
 * put in place by rename: a new inode, no temporary left), which the next
 * get reads (a hit). Damage: truncations at several lengths (the empty file
 * among them), one byte appended, one byte flipped at a sample of offsets
 * over the whole file (header, arrays, CRC), a header of another format
 * version / byte order / magic / key with a correct CRC (so the header check
 * is what catches it, not the CRC), a column index out of range with a
 * correct CRC (the sparse structure check), a valid file of another mesh,
 * and valid files of this key but other parameters (k, n_hks). A folder in
 * place of the file: a miss, not an error, the folder left alone.
 *
 * Memory: with an allocator that fails the Nth allocation, a hit and a miss
 * over a damaged file return NEUV_ERR_NOMEM for every N, never a miss or a
 * result, and leak nothing. */
#include "check.h"
#include "failing_alloc.h"

#include <dirent.h>
#include <stdatomic.h>
#include <stdint.h>
#include <unistd.h>

#include "core/hash.h"
#include "core/mem.h"
#include "geometry/operator_cache.h"
#include "mesh/shapes.h"

enum { HEADER_BYTES = 72, OFF_VERSION = 8, OFF_BYTE_ORDER = 12, OFF_KEY = 16 };

/* ---- comparing operators ----------------------------------------------- */

static int same_sparse(const sparse_matrix *a, const sparse_matrix *b)
{
    if (a->rows != b->rows || a->cols != b->cols || sparse_nnz(a) != sparse_nnz(b)) return 0;
    size_t nnz = sparse_nnz(a);
    return !memcmp(a->row_start, b->row_start, ((size_t)a->rows + 1) * sizeof(int)) &&
           !memcmp(a->col, b->col, nnz * sizeof(int)) && !memcmp(a->val, b->val, nnz * sizeof(double));
}

static double max_abs_diff(const double *a, const double *b, size_t n)
{
    double d = 0.0;
    for (size_t i = 0; i < n; i++)
        if (!(fabs(a[i] - b[i]) <= d)) d = fabs(a[i] - b[i]); /* NaN wins */
    return d;
}

/* Every value of a equals b's, bit for bit (the cache stores the bytes, and
 * a fresh computation is deterministic); on a mismatch, says where and by
 * how much. */
static int same_operators(const operators *a, const operators *b)
{
    if (a->nv != b->nv || a->k != b->k || a->n_hks != b->n_hks || !a->mass || !b->mass) {
        fprintf(stderr, "  operators differ in size: nv %d/%d, k %d/%d, n_hks %d/%d\n", a->nv, b->nv, a->k, b->k,
                a->n_hks, b->n_hks);
        return 0;
    }
    size_t n = (size_t)a->nv;
    struct { const char *name; const double *x, *y; size_t len; } arrays[] = {
        {"mass", a->mass, b->mass, n},
        {"evals", a->evals, b->evals, (size_t)a->k},
        {"evecs", a->evecs, b->evecs, n * a->k},
        {"frames", a->frames, b->frames, n * 9},
        {"hks", a->hks, b->hks, n * a->n_hks},
        {"hks_times", a->hks_times, b->hks_times, (size_t)a->n_hks},
        {"sigma", &a->sigma, &b->sigma, 1},
    };
    int same = 1;
    for (size_t i = 0; i < sizeof arrays / sizeof *arrays; i++)
        if (memcmp(arrays[i].x, arrays[i].y, arrays[i].len * sizeof(double))) {
            fprintf(stderr, "  %s differs, max |difference| %.3g\n", arrays[i].name,
                    max_abs_diff(arrays[i].x, arrays[i].y, arrays[i].len));
            same = 0;
        }
    if (!same_sparse(&a->L, &b->L)) { fprintf(stderr, "  L differs\n"); same = 0; }
    if (!same_sparse(&a->grad_x, &b->grad_x)) { fprintf(stderr, "  grad_x differs\n"); same = 0; }
    if (!same_sparse(&a->grad_y, &b->grad_y)) { fprintf(stderr, "  grad_y differs\n"); same = 0; }
    return same;
}

/* ---- files --------------------------------------------------------------- */

static long file_size(const char *path)
{
    struct stat st;
    return stat(path, &st) == 0 ? (long)st.st_size : -1;
}

static unsigned char *read_all(const char *path, long *size)
{
    *size = file_size(path);
    if (*size < 0) return NULL;
    unsigned char *b = malloc((size_t)*size + 1);
    FILE *fp = fopen(path, "rb");
    if (!b || !fp || fread(b, 1, (size_t)*size, fp) != (size_t)*size) {
        free(b);
        b = NULL;
    }
    if (fp) fclose(fp);
    return b;
}

static void write_all(const char *path, const unsigned char *b, long size)
{
    unlink(path);
    FILE *fp = fopen(path, "wb");
    CHECK(fp != NULL);
    if (!fp) return;
    CHECK(fwrite(b, 1, (size_t)size, fp) == (size_t)size);
    fclose(fp);
}

/* The CRC of the file's last 4 bytes, recomputed over the rest. */
static void fix_crc(unsigned char *b, long size)
{
    uint32_t crc = crc32_bytes(0, b, (size_t)size - 4);
    memcpy(b + size - 4, &crc, 4);
}

/* Entries of the cache folder other than the cache file (temporaries left
 * by a write, say). */
static int stray_entries(const char *dir, const char *path)
{
    const char *base = strrchr(path, '/') + 1;
    DIR *d = opendir(dir);
    if (!d) return -1;
    int n = 0;
    struct dirent *e;
    while ((e = readdir(d)))
        if (strcmp(e->d_name, ".") && strcmp(e->d_name, "..") && strcmp(e->d_name, base)) n++;
    closedir(d);
    return n;
}

/* ---- the checks -------------------------------------------------------- */

typedef struct fixture {
    const neuv_mesh *m;
    operators_params p;
    operators fresh;        /* operators_compute's, no cache */
    char *path, *dir;       /* the cache file and its folder */
    unsigned char *valid;   /* the first file written */
    long size;
    uint64_t key;
} fixture;

/* The file at f->path is damaged (`what`): the next get must be a miss that
 * gives the fresh operators and replaces the file, by rename, with a valid
 * one that the get after reads. */
static void check_rebuilt(fixture *f, const char *what)
{
    struct stat before;
    int existed = stat(f->path, &before) == 0;
    int failures = check_failures;
    operators o;
    char *path = NULL;
    int hit = -1;
    CHECK_INT(operators_get(f->m, &f->p, 1, &o, &path, &hit), NEUV_OK);
    CHECK_INT(hit, 0);
    CHECK(path && !strcmp(path, f->path));
    CHECK(same_operators(&o, &f->fresh));
    operators_free(&o);
    mem_free(path);
    long size;
    unsigned char *now = read_all(f->path, &size);
    CHECK(now && size == f->size && !memcmp(now, f->valid, (size_t)f->size));
    free(now);
    struct stat after;
    CHECK(stat(f->path, &after) == 0 && S_ISREG(after.st_mode));
    if (existed) CHECK(after.st_ino != before.st_ino); /* renamed into place, not written over */
    CHECK_INT(stray_entries(f->dir, f->path), 0);
    CHECK_INT(operators_get(f->m, &f->p, 1, &o, &path, &hit), NEUV_OK);
    CHECK_INT(hit, 1);
    CHECK(same_operators(&o, &f->fresh));
    operators_free(&o);
    mem_free(path);
    if (check_failures != failures) fprintf(stderr, "  ^ after damage: %s\n", what);
}

/* Writes bytes b as the cache file; operator_cache_load must refuse it
 * (with a message containing `why`, when not NULL) and leave ops zeroed;
 * then, when rebuild is set, check_rebuilt. */
static void check_refused(fixture *f, const unsigned char *b, long size, const char *why, int rebuild,
                          const char *what)
{
    write_all(f->path, b, size);
    operators bad;
    memset(&bad, 0x5a, sizeof bad);
    int failures = check_failures;
    CHECK_INT(operator_cache_load(f->path, f->key, f->fresh.nv, f->fresh.k, f->fresh.n_hks, &bad), NEUV_ERR_IO);
    if (why) CHECK(strstr(neuv_last_error(), why) != NULL);
    CHECK(bad.mass == NULL && bad.L.val == NULL && bad.nv == 0);
    if (check_failures != failures) fprintf(stderr, "  ^ %s (%s)\n", what, neuv_last_error());
    if (rebuild) check_rebuilt(f, what);
}

static void check_keys(const neuv_mesh *m, operators_params p)
{
    uint64_t key = operator_cache_key(m, &p);
    const char *code = operator_cache_code_hash();

    /* The digest is CMake's SHA-256: 64 lowercase hex digits. */
    CHECK_INT(strlen(code), 64);
    CHECK(strspn(code, "0123456789abcdef") == 64);
    CHECK(operator_cache_key_for(m, &p, code) == key);

    /* The same inputs: the same key (a copy, not the same pointers). */
    neuv_mesh *c = mesh_clone(m);
    CHECK(operator_cache_key(c, &p) == key);
    operators_params def = operators_default_params();
    CHECK(operator_cache_key(c, NULL) == operator_cache_key(c, &def));

    /* Each parameter, one step either way. */
    for (int d = -1; d <= 1; d += 2) {
        operators_params q = p;
        q.k += d;
        CHECK(operator_cache_key(m, &q) != key);
        q = p;
        q.n_hks += d;
        CHECK(operator_cache_key(m, &q) != key);
    }

    /* Each coordinate of a few vertices, one ulp either way. */
    int vs[] = {0, 1, m->nv / 2, m->nv - 1};
    for (size_t a = 0; a < sizeof vs / sizeof *vs; a++)
        for (int x = 0; x < 3; x++)
            for (int d = -1; d <= 1; d += 2) {
                double *v = &c->pos[(size_t)vs[a] * 3 + x], keep = *v;
                *v = nextafter(keep, d > 0 ? INFINITY : -INFINITY);
                CHECK(*v != keep);
                if (operator_cache_key(c, &p) == key) fprintf(stderr, "vertex %d coordinate %d moved by one ulp: same key\n", vs[a], x);
                CHECK(operator_cache_key(c, &p) != key);
                *v = keep;
            }
    CHECK(operator_cache_key(c, &p) == key);

    /* One triangle's indices in another order: rotated (the same oriented
     * triangle) and reversed (the other orientation). */
    int *t = c->tri + 3 * (c->nf / 3), t0 = t[0], t1 = t[1], t2 = t[2];
    t[0] = t1, t[1] = t2, t[2] = t0;
    CHECK(operator_cache_key(c, &p) != key);
    t[0] = t0, t[1] = t2, t[2] = t1;
    CHECK(operator_cache_key(c, &p) != key);
    t[0] = t0, t[1] = t1, t[2] = t2;
    /* Two triangles swapped. */
    int s[3];
    memcpy(s, c->tri, sizeof s);
    memcpy(c->tri, c->tri + 3, sizeof s);
    memcpy(c->tri + 3, s, sizeof s);
    CHECK(operator_cache_key(c, &p) != key);
    memcpy(c->tri + 3, c->tri, sizeof s);
    memcpy(c->tri, s, sizeof s);
    CHECK(operator_cache_key(c, &p) == key);

    /* Fewer faces or vertices (the same leading arrays). */
    c->nf--;
    CHECK(operator_cache_key(c, &p) != key);
    c->nf++;
    c->nv--;
    CHECK(operator_cache_key(c, &p) != key);
    c->nv++;

    /* The code: any other digest, even one hex digit off. */
    char other[65];
    memcpy(other, code, 65);
    other[63] = other[63] == '0' ? '1' : '0';
    CHECK(operator_cache_key_for(m, &p, other) != key);
    other[63] = code[63];
    other[0] = other[0] == 'f' ? 'e' : 'f';
    CHECK(operator_cache_key_for(m, &p, other) != key);
    CHECK(operator_cache_key_for(m, &p, "") != key);
    mesh_free(c);
}

/* Out of memory: with the file bytes `file` in place, a get whose Nth
 * allocation fails returns NEUV_ERR_NOMEM, never a quiet miss or a result,
 * and leaks nothing; for every N. */
static void check_nomem(fixture *f, const unsigned char *file, long size, const char *what)
{
    write_all(f->path, file, size);
    arm(0);
    long live = atomic_load(&n_live);
    operators o;
    int hit = -1;
    CHECK_INT(operators_get(f->m, &f->p, 1, &o, NULL, &hit), NEUV_OK);
    long total = atomic_load(&n_calls);
    operators_free(&o);
    CHECK(total > 0);
    int failures = check_failures, tried = 0;
    for (long n = 1; n <= total; n++) {
        write_all(f->path, file, size);
        arm(n);
        memset(&o, 0x5a, sizeof o);
        char *path = (char *)1;
        neuv_status s = operators_get(f->m, &f->p, 1, &o, &path, &hit);
        arm(0);
        tried++;
        if (s != NEUV_ERR_NOMEM) fprintf(stderr, "  %s: allocation %ld of %ld failed, got status %d\n", what, n, total, s);
        CHECK_INT(s, NEUV_ERR_NOMEM);
        CHECK(path == NULL && o.mass == NULL && o.nv == 0);
        if (s == NEUV_OK) { operators_free(&o); mem_free(path); }
        CHECK_INT(atomic_load(&n_live), live);
        live = atomic_load(&n_live); /* one leak reported once, not again at every N */
    }
    printf("%s: %ld allocations, %d failed one at a time%s\n", what, total, tried,
           check_failures != failures ? " (FAILURES)" : "");
}

int main(void)
{
    /* The counting allocator first, as neuv_set_allocator asks; it never
     * fails until armed. */
    neuv_set_allocator(&failing_allocator);

    /* A private cache folder (nested, not yet existing: the cache creates it). */
    char xdg[4096];
    snprintf(xdg, sizeof xdg, "%s/cache-%d/xdg", tmp_path(""), (int)getpid());
    setenv("XDG_CACHE_HOME", xdg, 1);

    /* 640 vertices: the ARPACK path (sigma != 0). */
    neuv_mesh *m = shape_torus(1.0, 0.4, 40, 16);
    CHECK(m != NULL);
    if (!m) return check_report("test_operator_cache");
    fixture f = {.m = m, .p = {24, 8}};
    CHECK_INT(operators_compute(m, &f.p, &f.fresh), NEUV_OK);
    CHECK(f.fresh.sigma != 0);
    check_keys(m, f.p);
    f.key = operator_cache_key(m, &f.p);

    operators a, b;
    int hit = -1;
    CHECK_INT(operators_get(m, &f.p, 1, &a, &f.path, &hit), NEUV_OK);
    CHECK_INT(hit, 0);
    CHECK(f.path != NULL);
    if (!f.path) return check_report("test_operator_cache");
    CHECK(strncmp(f.path, xdg, strlen(xdg)) == 0 && strstr(f.path, "/neuv/ops-") != NULL);
    char name[64];
    snprintf(name, sizeof name, "/neuv/ops-%016llx.bin", (unsigned long long)f.key);
    CHECK(strstr(f.path, name) != NULL);
    f.dir = strdup(f.path);
    *strrchr(f.dir, '/') = '\0';
    CHECK(a.seconds.eigen + a.seconds.factor > 0);
    CHECK(same_operators(&a, &f.fresh));
    f.valid = read_all(f.path, &f.size);
    CHECK(f.valid != NULL && f.size > HEADER_BYTES + 4);
    if (!f.valid) return check_report("test_operator_cache");

    char *path2 = NULL;
    CHECK_INT(operators_get(m, &f.p, 1, &b, &path2, &hit), NEUV_OK);
    CHECK_INT(hit, 1);
    CHECK(path2 && !strcmp(f.path, path2));
    CHECK(same_operators(&b, &f.fresh));
    CHECK(b.seconds.eigen == 0 && b.seconds.cache_load > 0);
    operators_free(&b);
    mem_free(path2);

    /* --no-cache: computes, reports no path, identical (deterministic). */
    CHECK_INT(operators_get(m, &f.p, 0, &b, &path2, &hit), NEUV_OK);
    CHECK_INT(hit, 0);
    CHECK(path2 == NULL);
    CHECK(same_operators(&b, &f.fresh));
    operators_free(&b);

    /* Truncated: empty, inside the header, the header alone, inside the
     * arrays, without the CRC, one byte short; and one byte too many. */
    unsigned char *buf = malloc((size_t)f.size + 1);
    long cuts[] = {0, 1, 8, HEADER_BYTES - 1, HEADER_BYTES, HEADER_BYTES + 1, f.size / 2, f.size - 4, f.size - 1};
    for (size_t i = 0; i < sizeof cuts / sizeof *cuts; i++) {
        char what[64];
        snprintf(what, sizeof what, "truncated to %ld of %ld bytes", cuts[i], f.size);
        check_refused(&f, f.valid, cuts[i], NULL, 1, what);
    }
    memcpy(buf, f.valid, (size_t)f.size);
    buf[f.size] = 0;
    check_refused(&f, buf, f.size + 1, "length", 1, "one byte appended");

    /* One byte flipped: every header byte and every 997th byte after it, the
     * CRC's included, refused by the load; a sample of those (every 7th)
     * through the whole get. */
    int flips = 0;
    for (long off = 0; off < f.size; off += off < HEADER_BYTES + 8 ? 1 : 997) {
        memcpy(buf, f.valid, (size_t)f.size);
        buf[off] ^= (unsigned char)(1u << (off % 8));
        char what[64];
        snprintf(what, sizeof what, "byte %ld of %ld flipped", off, f.size);
        check_refused(&f, buf, f.size, NULL, flips++ % 7 == 0, what);
    }
    for (long off = f.size - 4; off < f.size; off++) {
        memcpy(buf, f.valid, (size_t)f.size);
        buf[off] ^= 0x80;
        check_refused(&f, buf, f.size, "checksum", off == f.size - 1, "CRC byte flipped");
    }
    printf("flipped bytes: %d offsets\n", flips + 4);

    /* Headers with a correct CRC: the field check itself must catch them. */
    uint32_t u;
    memcpy(buf, f.valid, (size_t)f.size);
    memcpy(&u, buf + OFF_VERSION, 4);
    CHECK_INT(u, OPERATOR_CACHE_VERSION);
    u++;
    memcpy(buf + OFF_VERSION, &u, 4);
    fix_crc(buf, f.size);
    check_refused(&f, buf, f.size, "version", 1, "another format version");

    memcpy(buf, f.valid, (size_t)f.size);
    u = 0x04030201u;
    memcpy(buf + OFF_BYTE_ORDER, &u, 4);
    fix_crc(buf, f.size);
    check_refused(&f, buf, f.size, "byte order", 1, "other byte order");

    memcpy(buf, f.valid, (size_t)f.size);
    buf[3] = 'X';
    fix_crc(buf, f.size);
    check_refused(&f, buf, f.size, "not a neuv", 1, "other magic");

    memcpy(buf, f.valid, (size_t)f.size);
    uint64_t k64 = operator_cache_key_for(m, &f.p, "another version of the code");
    memcpy(buf + OFF_KEY, &k64, 8);
    fix_crc(buf, f.size);
    check_refused(&f, buf, f.size, "key", 1, "the key of other code");

    /* The first column index of L out of range (CRC fixed). */
    memcpy(buf, f.valid, (size_t)f.size);
    int32_t col = m->nv;
    memcpy(buf + HEADER_BYTES + ((size_t)m->nv + 1) * 4, &col, 4);
    fix_crc(buf, f.size);
    check_refused(&f, buf, f.size, "inconsistent", 1, "a column out of range");

    /* Same length, other bytes. */
    for (long i = 0; i < f.size; i++) buf[i] = (unsigned char)(i * 131 % 251);
    check_refused(&f, buf, f.size, NULL, 1, "foreign bytes");

    /* A valid file of another mesh, renamed into place. */
    neuv_mesh *other = shape_torus(1.0, 0.3, 40, 16);
    operators oo;
    CHECK_INT(operators_compute(other, &f.p, &oo), NEUV_OK);
    CHECK_INT(operator_cache_save(f.path, operator_cache_key(other, &f.p), &oo), NEUV_OK);
    operators_free(&oo);
    mesh_free(other);
    long size;
    unsigned char *file = read_all(f.path, &size);
    check_refused(&f, file, size, "key", 1, "another mesh's file");
    free(file);

    /* A valid file of this key but other parameters (a collision, or
     * someone's copy): the sizes do not match the ones asked for. */
    operators_params others[] = {{f.p.k - 4, f.p.n_hks}, {f.p.k, f.p.n_hks - 2}, {f.p.k + 4, f.p.n_hks + 2}};
    for (size_t i = 0; i < sizeof others / sizeof *others; i++) {
        CHECK_INT(operators_compute(m, &others[i], &oo), NEUV_OK);
        CHECK_INT(operator_cache_save(f.path, f.key, &oo), NEUV_OK);
        operators_free(&oo);
        file = read_all(f.path, &size);
        char what[96];
        snprintf(what, sizeof what, "a file of this key for k %d, n_hks %d", others[i].k, others[i].n_hks);
        check_refused(&f, file, size, "sizes", 1, what);
        free(file);
    }

    /* A folder in place of the file: a miss and no error, each time; the
     * folder is not the library's to delete. Once it is gone, a file again. */
    unlink(f.path);
    CHECK(mkdir(f.path, 0755) == 0);
    for (int round = 0; round < 2; round++) {
        char *path = NULL;
        CHECK_INT(operators_get(m, &f.p, 1, &b, &path, &hit), NEUV_OK);
        CHECK_INT(hit, 0);
        CHECK(same_operators(&b, &f.fresh));
        operators_free(&b);
        mem_free(path);
        struct stat st;
        CHECK(stat(f.path, &st) == 0 && S_ISDIR(st.st_mode));
        CHECK_INT(stray_entries(f.dir, f.path), 0);
    }
    operators bad;
    CHECK_INT(operator_cache_load(f.path, f.key, f.fresh.nv, f.fresh.k, f.fresh.n_hks, &bad), NEUV_ERR_IO);
    CHECK(strstr(neuv_last_error(), "regular file") != NULL);
    CHECK(rmdir(f.path) == 0);
    check_rebuilt(&f, "folder removed");

    /* Out of memory, every allocation one at a time: a hit, and a miss over
     * a damaged file (the load, the computation, the write). */
    check_nomem(&f, f.valid, f.size, "hit");
    memcpy(buf, f.valid, (size_t)f.size);
    buf[f.size / 2] ^= 1;
    check_nomem(&f, buf, f.size, "miss over a flipped byte");
    write_all(f.path, f.valid, f.size);

    /* An unusable cache folder is not an error: computed, no path. */
    char file_as_dir[4200];
    snprintf(file_as_dir, sizeof file_as_dir, "%s/plainfile", xdg);
    FILE *fp = fopen(file_as_dir, "wb");
    if (fp) fclose(fp);
    setenv("XDG_CACHE_HOME", file_as_dir, 1);
    CHECK_INT(operators_get(m, &f.p, 1, &b, &path2, &hit), NEUV_OK);
    CHECK_INT(hit, 0);
    CHECK(path2 == NULL);
    CHECK(same_operators(&b, &f.fresh));
    operators_free(&b);

    free(buf);
    free(f.valid);
    free(f.dir);
    mem_free(f.path);
    operators_free(&a);
    operators_free(&f.fresh);
    mesh_free(m);
    neuv_set_allocator(NULL);
    return check_report("test_operator_cache");
}
