/* The up-front memory estimate and refusal of training (unwrap/memory_budget.h)
 * and its reach through the library: neuv_atlas_generate and
 * neuv_atlas_compute_charts refuse a mesh over the budget before they start. */
#include <stdint.h>

#include "check.h"

#include "neuv/neuv.h"
#include "unwrap/memory_budget.h"

static void test_estimate_and_budget(void)
{
    /* Linear in the faces, with a positive fixed part. */
    double e0 = memory_training_estimate(0), e1 = memory_training_estimate(1e5), e2 = memory_training_estimate(2e5);
    CHECK(e0 > 0);
    CHECK(e1 > e0);
    CHECK_NEAR(e2 - e1, e1 - e0, 1e-6 * e2);
    /* Between 8 and 16 KiB per face: bench/RESULTS.md measured 9.7 at 82k
     * faces, and the estimate adds a margin of 1.25. */
    double per_face = (e1 - e0) / 1e5;
    CHECK(per_face >= 8 * 1024 && per_face <= 16 * 1024);
    CHECK_NEAR(memory_budget_bytes(100), 100.0 * 1024 * 1024, 0);
    double half = memory_budget_bytes(0);
    CHECK(half > 64.0 * 1024 * 1024); /* half the machine's memory: more than 64 MiB anywhere CI runs */
}

static void test_check(void)
{
    CHECK(memory_check_training(1000, 0, "this mesh", "hint") == NEUV_OK);
    CHECK(memory_check_training(1000, 100000, "this mesh", "hint") == NEUV_OK);
    /* 100k faces need more than 1 GiB: refused under a 1 GiB budget. */
    CHECK(memory_check_training(1e5, 1024, "this mesh", "use less") == NEUV_ERR_NOMEM);
    const char *m = neuv_last_error();
    CHECK(strstr(m, "100000 faces of this mesh") != NULL);
    CHECK(strstr(m, "needs about 1.") != NULL);
    CHECK(strstr(m, "budget of 1.0 GiB (--max-memory)") != NULL);
    CHECK(strstr(m, "use less") != NULL);
    CHECK(strchr(m, '\n') == NULL);
    /* Just over and just under the estimate. */
    double need = memory_training_estimate(5e4) / (1024.0 * 1024);
    CHECK(memory_check_training(5e4, (int)need + 1, "x", "h") == NEUV_OK);
    CHECK(memory_check_training(5e4, (int)need - 1, "x", "h") == NEUV_ERR_NOMEM);
    CHECK(memory_check_training(10, -1, "x", "h") == NEUV_ERR_INPUT);
}

/* A flat grid of n by n squares (2 n² faces). */
static void grid_decl(int n, float *pos, uint32_t *idx, neuv_mesh_decl *d)
{
    for (int j = 0; j <= n; j++)
        for (int i = 0; i <= n; i++) {
            float *p = pos + 3 * (j * (n + 1) + i);
            p[0] = (float)i / n; p[1] = (float)j / n; p[2] = 0.1f * (float)((i * j) % 3) / n;
        }
    int k = 0;
    for (int j = 0; j < n; j++)
        for (int i = 0; i < n; i++) {
            uint32_t a = (uint32_t)(j * (n + 1) + i), b = a + 1, c = a + (uint32_t)n + 1, e = c + 1;
            idx[k++] = a; idx[k++] = b; idx[k++] = e;
            idx[k++] = a; idx[k++] = e; idx[k++] = c;
        }
    memset(d, 0, sizeof *d);
    d->positions = pos; d->position_type = NEUV_FLOAT32; d->position_stride = 3 * sizeof(float);
    d->vertex_count = (n + 1) * (n + 1);
    d->indices = idx; d->index_type = NEUV_UINT32; d->index_count = 6 * n * n;
}

static void test_library_refuses(void)
{
    enum { N = 40 };
    static float pos[3 * (N + 1) * (N + 1)];
    static uint32_t idx[6 * N * N];
    neuv_mesh_decl d;
    grid_decl(N, pos, idx, &d);
    neuv_atlas *a = NULL;
    CHECK(neuv_atlas_create(&a) == NEUV_OK);
    CHECK(neuv_atlas_add_mesh(a, &d) == NEUV_OK);
    neuv_unwrap_options uo;
    neuv_unwrap_options_init(&uo);
    CHECK_INT(uo.max_memory_mb, 0);
    uo.max_memory_mb = 1; /* 3200 faces need more than 1 MiB */
    uo.use_cache = 0;
    CHECK(neuv_atlas_generate(a, &uo) == NEUV_ERR_NOMEM);
    CHECK(strstr(neuv_last_error(), "3200 faces of this mesh needs about") != NULL);
    CHECK_INT(neuv_atlas_stage(a), 0);
    uo.max_memory_mb = -5;
    CHECK(neuv_atlas_generate(a, &uo) == NEUV_ERR_INPUT);
    neuv_chart_options co;
    neuv_chart_options_init(&co);
    CHECK_INT(co.max_memory_mb, 0);
    co.max_memory_mb = 1;
    co.use_cache = 0;
    CHECK(neuv_atlas_compute_charts(a, &co) == NEUV_ERR_NOMEM);
    CHECK_INT(neuv_atlas_stage(a), 0);
    /* Enough budget: the stage runs. */
    co.max_memory_mb = 100000;
    co.iters = 3;
    CHECK(neuv_atlas_compute_charts(a, &co) == NEUV_OK);
    CHECK_INT(neuv_atlas_stage(a), 1);
    neuv_atlas_destroy(a);
}

int main(void)
{
    test_estimate_and_budget();
    test_check();
    test_library_refuses();
    return check_report("test_memory_budget");
}
