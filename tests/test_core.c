/* Core utilities: JSON writer, RNG determinism, CRC32, union-find, UV charts, atomic files. */
#include "check.h"

#include <unistd.h>

#include "atlas/uv_charts.h"
#include "core/atomic_file.h"
#include "core/hash.h"
#include "core/json_writer.h"
#include "core/rng.h"
#include "core/union_find.h"
#include "mesh/mesh.h"

static void test_json(void)
{
    json_writer w;
    json_init(&w);
    json_begin_object(&w);
    json_key(&w, "a"); json_int(&w, 3);
    json_key(&w, "b"); json_begin_array(&w); json_number(&w, 0.1); json_number(&w, NAN); json_end_array(&w);
    json_key(&w, "s"); json_string(&w, "q\"\n");
    json_end_object(&w);
    CHECK(strcmp(json_text(&w), "{\"a\":3,\"b\":[0.1,null],\"s\":\"q\\\"\\n\"}") == 0);
    json_free(&w);
    char buf[32];
    format_double_exact(buf, 1.0 / 3.0);
    CHECK(strtod(buf, NULL) == 1.0 / 3.0);
}

static void test_rng_and_crc(void)
{
    rng a, b;
    rng_seed(&a, 42); rng_seed(&b, 42);
    int same = 1;
    double mean = 0;
    for (int i = 0; i < 10000; i++) {
        double x = rng_uniform(&a);
        if (x != rng_uniform(&b)) same = 0;
        mean += x;
    }
    CHECK(same);
    CHECK_NEAR(mean / 10000, 0.5, 0.01);
    /* The standard CRC-32 check value. */
    CHECK(crc32_bytes(0, "123456789", 9) == 0xCBF43926u);
}

static void test_union_find(void)
{
    union_find u;
    CHECK(uf_init(&u, 6) == 0);
    uf_union(&u, 0, 3); uf_union(&u, 4, 5); uf_union(&u, 3, 5);
    int lab[6];
    CHECK_INT(uf_labels(&u, lab), 3);
    CHECK(lab[0] == lab[5] && lab[1] != lab[0] && lab[2] != lab[1]);
    CHECK_INT(lab[0], 0);
    uf_free(&u);
}

/* Two triangles sharing an edge: one chart when the shared UVs agree, two when cut. */
static void test_uv_charts(void)
{
    neuv_mesh *m = mesh_create(4, 2, 4);
    double pos[12] = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0};
    int tri[6] = {0, 1, 2, 0, 2, 3};
    memcpy(m->pos, pos, sizeof pos);
    memcpy(m->tri, tri, sizeof tri);
    double uv[8] = {0, 0, 1, 0, 1, 1, 0, 1};
    memcpy(m->uv, uv, sizeof uv);
    memcpy(m->tri_uv, tri, sizeof tri);
    int fc[2];
    CHECK_INT(uv_charts(m, fc), 1);
    double uv2[10] = {0, 0, 1, 0, 1, 1, 0, 1, 5, 5};
    CHECK(mesh_set_uv(m, 5, uv2, (int[]){0, 1, 2, 4, 2, 3}) == NEUV_OK);
    CHECK_INT(uv_charts(m, fc), 2);
    CHECK(fc[0] == 0 && fc[1] == 1);
    mesh_free(m);
}

static void test_atomic_file(void)
{
    const char *p = tmp_path("atomic.txt");
    unlink(p);
    atomic_file af;
    CHECK(atomic_file_open(&af, p) == NEUV_OK);
    fputs("hello", af.fp);
    atomic_file_abort(&af);
    CHECK(access(p, F_OK) != 0); /* abandoned: nothing left behind */
    CHECK(atomic_file_open(&af, p) == NEUV_OK);
    fputs("hello", af.fp);
    CHECK(atomic_file_commit(&af) == NEUV_OK);
    CHECK(access(p, F_OK) == 0);
    CHECK(atomic_file_open(&af, "/nonexistent-folder/x.obj") == NEUV_ERR_IO);
    CHECK(strstr(neuv_last_error(), "does not exist") != NULL);
}

int main(void)
{
    test_json();
    test_rng_and_crc();
    test_union_find();
    test_uv_charts();
    test_atomic_file();
    return check_report("test_core");
}
