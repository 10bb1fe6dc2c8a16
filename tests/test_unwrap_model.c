/* Saved unwrap models (unwrap_model.h): save -> load -> save gives the same
 * bytes, the loaded model reproduces the atlas on the source mesh exactly,
 * and damaged files (flipped byte, truncation, wrong version, wrong format)
 * are refused with NEUV_ERR_INPUT and a one-line message. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "core/error.h"
#include "mesh/shapes.h"
#include "models/param_net.h"
#include "unwrap/unwrap_apply.h"
#include "unwrap/unwrap_internal.h"
#include "unwrap/unwrap_model.h"

static unsigned char *read_all(const char *path, size_t *n)
{
    FILE *fp = fopen(path, "rb");
    if (!fp) return NULL;
    fseek(fp, 0, SEEK_END);
    long len = ftell(fp);
    fseek(fp, 0, SEEK_SET);
    unsigned char *b = malloc((size_t)len + 1);
    *n = b ? fread(b, 1, (size_t)len, fp) : 0;
    fclose(fp);
    return b;
}

static void write_all(const char *path, const unsigned char *b, size_t n)
{
    FILE *fp = fopen(path, "wb");
    if (!fp) return;
    fwrite(b, 1, n, fp);
    fclose(fp);
}

/* Loading must fail with NEUV_ERR_INPUT and a one-line message. */
static void expect_rejected(const char *path, const char *label)
{
    unwrap_model *m = NULL;
    neuv_status s = unwrap_model_load(path, &m);
    CHECK_INT(s, NEUV_ERR_INPUT);
    CHECK(m == NULL);
    const char *msg = neuv_last_error();
    CHECK(msg && *msg && !strchr(msg, '\n'));
    if (s != NEUV_ERR_INPUT) printf("  %s: status %d (%s)\n", label, s, msg ? msg : "");
}

int main(void)
{
    /* A classic-method model keeps the test fast: PatchNet still trains and is saved. */
    neuv_mesh *mesh = shape_capsule(0.5, 1.0, 16, 8);
    CHECK(mesh != NULL);
    neuv_unwrap_options o;
    neuv_unwrap_options_init(&o);
    o.method = NEUV_METHOD_LSCM;
    o.iters = 30;
    o.use_cache = 0;
    o.threads = 1;
    unwrap_model *model = NULL;
    neuv_unwrap_result *r = NULL;
    CHECK_INT(unwrap_budgeted(mesh, &o, 0, &model, &r), NEUV_OK);
    CHECK(model && r);
    if (!model || !r) return check_report("test_unwrap_model");

    const char *p1 = tmp_path("model1.neuv"), *p2 = tmp_path("model2.neuv");
    char path1[512], path2[512];
    snprintf(path1, sizeof path1, "%s", p1);
    snprintf(path2, sizeof path2, "%s", p2);
    CHECK_INT(model->refine, 0); /* classic maps are not refined */
    model->refine = 123;         /* the field round-trips (only network charts use it) */
    CHECK_INT(unwrap_model_save(model, path1), NEUV_OK);
    unwrap_model *back = NULL;
    CHECK_INT(unwrap_model_load(path1, &back), NEUV_OK);
    CHECK(back != NULL);
    if (back) {
        CHECK_INT(back->n_charts, model->n_charts);
        CHECK_INT(back->refine, 123);
        CHECK_INT(back->source->nv, model->source->nv);
        CHECK(memcmp(back->source->pos, model->source->pos, sizeof(double) * 3 * (size_t)model->source->nv) == 0);
        CHECK(memcmp(back->source->uv, model->source->uv, sizeof(double) * 2 * (size_t)model->source->nuv) == 0);
        CHECK(memcmp(back->face_chart, model->face_chart, sizeof(int) * (size_t)model->source->nf) == 0);
        CHECK(memcmp(back->xf, model->xf, sizeof *model->xf * (size_t)model->n_charts) == 0);
        CHECK(back->patchnet != NULL && back->param == NULL);
        CHECK_INT(unwrap_model_save(back, path2), NEUV_OK);
        size_t n1 = 0, n2 = 0;
        unsigned char *b1 = read_all(path1, &n1), *b2 = read_all(path2, &n2);
        CHECK(b1 && b2 && n1 == n2 && n1 > 100 && memcmp(b1, b2, n1) == 0); /* bit-exact round trip */

        /* Applied to its own source mesh the model gives back the atlas exactly. */
        neuv_unwrap_result *again = NULL;
        unwrap_apply_options ao = {1, 0, 0, 0, 0, 0, 0, NULL};
        CHECK_INT(unwrap_apply(r->mesh, back, &ao, &again), NEUV_OK);
        if (again) {
            const neuv_mesh *a = r->mesh, *b = again->mesh;
            CHECK_INT(b->nf, a->nf);
            double worst = 0;
            for (int f = 0; f < a->nf && b->nf == a->nf; f++)
                for (int k = 0; k < 3; k++)
                    for (int q = 0; q < 2; q++) {
                        double d = a->uv[2 * a->tri_uv[3 * f + k] + q] - b->uv[2 * b->tri_uv[3 * f + k] + q];
                        if (d < 0) d = -d;
                        if (d > worst) worst = d;
                    }
            CHECK(worst < 1e-12);
            CHECK_INT(again->metrics.flipped, 0);
            neuv_unwrap_result_free(again);
        }

        /* Damaged copies. */
        if (b1) {
            const char *bad = tmp_path("bad.neuv");
            char badp[512];
            snprintf(badp, sizeof badp, "%s", bad);
            unsigned char *c = malloc(n1);
            memcpy(c, b1, n1);
            c[n1 / 2] ^= 0x40; /* inside some tensor: its CRC fails */
            write_all(badp, c, n1);
            expect_rejected(badp, "flipped byte");
            write_all(badp, b1, n1 - 7);
            expect_rejected(badp, "truncated");
            write_all(badp, b1, 20);
            expect_rejected(badp, "header cut");
            memcpy(c, b1, n1);
            c[8] = 99; /* checkpoint version */
            write_all(badp, c, n1);
            expect_rejected(badp, "checkpoint version");
            memcpy(c, b1, n1);
            char *fmt = NULL;
            for (size_t i = 0; i + 17 <= n1 && !fmt; i++)
                if (!memcmp(c + i, "neuv-unwrap-model", 17)) fmt = (char *)c + i;
            CHECK(fmt != NULL);
            if (fmt) { fmt[0] = 'x'; write_all(badp, c, n1); }
            /* The header CRC fails first; either way the file is refused. */
            expect_rejected(badp, "format name");
            write_all(badp, (const unsigned char *)"not a model at all\n", 19);
            expect_rejected(badp, "text file");
            free(c);
        }
        free(b1);
        free(b2);
        unwrap_model_free(back);
    }
    unwrap_model *none = NULL;
    CHECK_INT(unwrap_model_load(tmp_path("does-not-exist.neuv"), &none), NEUV_ERR_IO);

    unwrap_model_free(model);
    neuv_unwrap_result_free(r);

    /* A neural model whose networks have more charts than its atlas (the
     * pieces of a chart split on the full mesh, when the model was trained
     * on a simplified copy, keep heads of their own) saves and loads: the
     * loader once required at most one network chart per atlas chart. */
    o.method = NEUV_METHOD_NEURAL;
    o.iters = 20;
    model = NULL;
    r = NULL;
    CHECK_INT(unwrap_budgeted(mesh, &o, 0, &model, &r), NEUV_OK);
    if (model && model->param && model->param->heads) {
        int hs = param_head_size(&model->param->f), id = -1;
        float *head = malloc(sizeof(float) * (size_t)hs);
        memcpy(head, model->param->heads, sizeof(float) * (size_t)hs);
        while (model->param->n_charts <= model->n_charts + 1)
            CHECK_INT(param_net_add_chart(model->param, 0, head, 1.0, &id), NEUV_OK);
        free(head);
        CHECK_INT(unwrap_model_save(model, path1), NEUV_OK);
        unwrap_model *more = NULL;
        CHECK_INT(unwrap_model_load(path1, &more), NEUV_OK);
        CHECK(more && more->param && more->param->n_charts == model->param->n_charts);
        CHECK(more && more->n_charts == model->n_charts && more->n_charts < model->param->n_charts);
        if (more) {
            CHECK_INT(unwrap_model_save(more, path2), NEUV_OK);
            size_t n1 = 0, n2 = 0;
            unsigned char *b1 = read_all(path1, &n1), *b2 = read_all(path2, &n2);
            CHECK(b1 && b2 && n1 == n2 && memcmp(b1, b2, n1) == 0); /* the extra heads round-trip */
            free(b1);
            free(b2);
        }
        unwrap_model_free(more);
    } else {
        CHECK(!"the neural model kept no per-chart heads");
    }
    unwrap_model_free(model);
    neuv_unwrap_result_free(r);
    mesh_free(mesh);
    return check_report("test_unwrap_model");
}
