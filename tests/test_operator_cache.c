/* Operator cache: miss then hit, bit-identical; corrupt, truncated and
 * foreign files are detected and rebuilt. */
#include "check.h"

#include <stdint.h>
#include <unistd.h>

#include "geometry/operator_cache.h"
#include "mesh/shapes.h"

static int same_sparse(const sparse_matrix *a, const sparse_matrix *b)
{
    if (a->rows != b->rows || a->cols != b->cols || sparse_nnz(a) != sparse_nnz(b)) return 0;
    size_t nnz = sparse_nnz(a);
    return !memcmp(a->row_start, b->row_start, ((size_t)a->rows + 1) * sizeof(int)) &&
           !memcmp(a->col, b->col, nnz * sizeof(int)) && !memcmp(a->val, b->val, nnz * sizeof(double));
}

static int same_operators(const operators *a, const operators *b)
{
    size_t n = (size_t)a->nv;
    return a->nv == b->nv && a->k == b->k && a->n_hks == b->n_hks && same_sparse(&a->L, &b->L) &&
           same_sparse(&a->grad_x, &b->grad_x) && same_sparse(&a->grad_y, &b->grad_y) &&
           !memcmp(a->mass, b->mass, n * sizeof(double)) && !memcmp(a->evals, b->evals, (size_t)a->k * sizeof(double)) &&
           !memcmp(a->evecs, b->evecs, n * a->k * sizeof(double)) && !memcmp(a->frames, b->frames, n * 9 * sizeof(double)) &&
           !memcmp(a->hks, b->hks, n * a->n_hks * sizeof(double)) &&
           !memcmp(a->hks_times, b->hks_times, (size_t)a->n_hks * sizeof(double));
}

static long file_size(const char *path)
{
    struct stat st;
    return stat(path, &st) == 0 ? (long)st.st_size : -1;
}

/* Applies `damage` to the cache file, then checks the next get is a miss
 * that rebuilds the same operators and rewrites a valid file. */
static void check_rebuilt(const neuv_mesh *m, const operators_params *p, const operators *ref, const char *what)
{
    operators o;
    char *path = NULL;
    int hit = -1;
    CHECK_INT(operators_get(m, p, 1, &o, &path, &hit), NEUV_OK);
    CHECK_INT(hit, 0);
    if (hit != 0) fprintf(stderr, "damaged cache (%s) was trusted\n", what);
    CHECK(same_operators(&o, ref));
    operators_free(&o);
    free(path);
    /* And the rewritten file is a hit again. */
    CHECK_INT(operators_get(m, p, 1, &o, &path, &hit), NEUV_OK);
    CHECK_INT(hit, 1);
    CHECK(same_operators(&o, ref));
    operators_free(&o);
    free(path);
}

int main(void)
{
    /* A private cache folder (nested, not yet existing: the cache creates it). */
    char dir[4096];
    snprintf(dir, sizeof dir, "%s/cache-%d/xdg", tmp_path(""), (int)getpid());
    setenv("XDG_CACHE_HOME", dir, 1);

    neuv_mesh *m = shape_torus(1.0, 0.4, 40, 16);
    CHECK(m != NULL);
    operators_params p = {24, 8};

    operators a, b;
    char *path = NULL;
    int hit = -1;
    CHECK_INT(operators_get(m, &p, 1, &a, &path, &hit), NEUV_OK);
    CHECK_INT(hit, 0);
    CHECK(path != NULL);
    if (!path) return check_report("test_operator_cache");
    CHECK(strncmp(path, dir, strlen(dir)) == 0 && strstr(path, "/neuv/ops-") != NULL);
    CHECK(file_size(path) > 0);
    CHECK(a.seconds.eigen + a.seconds.factor > 0);

    char *path2 = NULL;
    CHECK_INT(operators_get(m, &p, 1, &b, &path2, &hit), NEUV_OK);
    CHECK_INT(hit, 1);
    CHECK(path2 && !strcmp(path, path2));
    CHECK(same_operators(&a, &b));
    CHECK(b.seconds.eigen == 0 && b.seconds.cache_load > 0);
    operators_free(&b);
    free(path2);

    /* --no-cache: computes, reports no path, identical (deterministic). */
    CHECK_INT(operators_get(m, &p, 0, &b, &path2, &hit), NEUV_OK);
    CHECK_INT(hit, 0);
    CHECK(path2 == NULL);
    CHECK(same_operators(&a, &b));
    operators_free(&b);

    /* Other parameters or other positions: other key, other file. */
    operators_params p2 = {20, 8};
    CHECK(operator_cache_key(m, &p) != operator_cache_key(m, &p2));
    neuv_mesh *moved = mesh_clone(m);
    moved->pos[5] += 1e-9;
    CHECK(operator_cache_key(m, &p) != operator_cache_key(moved, &p));
    mesh_free(moved);

    long size = file_size(path);
    unsigned char *orig = malloc((size_t)size);
    FILE *fp = fopen(path, "rb");
    CHECK(fp && fread(orig, 1, (size_t)size, fp) == (size_t)size);
    if (fp) fclose(fp);

    /* One flipped byte in the middle of the eigenvectors: CRC mismatch. */
    fp = fopen(path, "r+b");
    fseek(fp, size / 2, SEEK_SET);
    fputc(orig[size / 2] ^ 0x40, fp);
    fclose(fp);
    operators bad;
    uint64_t key = operator_cache_key(m, &p);
    CHECK_INT(operator_cache_load(path, key, a.nv, a.k, a.n_hks, &bad), NEUV_ERR_IO);
    CHECK(strstr(neuv_last_error(), "checksum") != NULL);
    check_rebuilt(m, &p, &a, "flipped byte");

    /* Truncated file. */
    CHECK(truncate(path, size - 100) == 0);
    CHECK_INT(operator_cache_load(path, key, a.nv, a.k, a.n_hks, &bad), NEUV_ERR_IO);
    check_rebuilt(m, &p, &a, "truncated");
    CHECK(truncate(path, 10) == 0);
    check_rebuilt(m, &p, &a, "truncated to 10 bytes");

    /* A foreign file: same length, other bytes. */
    fp = fopen(path, "wb");
    for (long i = 0; i < size; i++) fputc((int)(i * 131 % 251), fp);
    fclose(fp);
    CHECK_INT(operator_cache_load(path, key, a.nv, a.k, a.n_hks, &bad), NEUV_ERR_IO);
    check_rebuilt(m, &p, &a, "foreign");

    /* A valid cache file of another mesh renamed into place: key mismatch. */
    neuv_mesh *other = shape_torus(1.0, 0.3, 40, 16);
    operators oo;
    CHECK_INT(operators_compute(other, &p, &oo), NEUV_OK);
    CHECK_INT(operator_cache_save(path, operator_cache_key(other, &p), &oo), NEUV_OK);
    CHECK_INT(operator_cache_load(path, key, a.nv, a.k, a.n_hks, &bad), NEUV_ERR_IO);
    CHECK(strstr(neuv_last_error(), "key") != NULL);
    check_rebuilt(m, &p, &a, "other mesh");
    operators_free(&oo);
    mesh_free(other);

    /* An empty file. */
    fp = fopen(path, "wb");
    fclose(fp);
    check_rebuilt(m, &p, &a, "empty");

    /* The rebuilt file equals the first one byte for byte. */
    CHECK_INT(file_size(path), size);
    unsigned char *again = malloc((size_t)size);
    fp = fopen(path, "rb");
    CHECK(fp && fread(again, 1, (size_t)size, fp) == (size_t)size);
    if (fp) fclose(fp);
    CHECK(!memcmp(orig, again, (size_t)size));

    /* An unusable cache folder is not an error: computed, no path. */
    char file_as_dir[4200];
    snprintf(file_as_dir, sizeof file_as_dir, "%s/plainfile", dir);
    fp = fopen(file_as_dir, "wb");
    if (fp) fclose(fp);
    setenv("XDG_CACHE_HOME", file_as_dir, 1);
    CHECK_INT(operators_get(m, &p, 1, &b, &path2, &hit), NEUV_OK);
    CHECK_INT(hit, 0);
    CHECK(path2 == NULL);
    CHECK(same_operators(&a, &b));
    operators_free(&b);

    free(orig);
    free(again);
    free(path);
    operators_free(&a);
    mesh_free(m);
    return check_report("test_operator_cache");
}
