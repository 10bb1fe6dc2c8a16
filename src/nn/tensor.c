/* Tensors, the per-step arena and tape, leaves and parameters. */
#include "nn/nn_internal.h"

#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/error.h"
#include "core/mem.h"

#define NN_ALIGN 64

typedef struct arena_block {
    struct arena_block *next;
    size_t cap, used;
    unsigned char *mem; /* raw rounded up to NN_ALIGN */
    void *raw;          /* what mem_alloc returned: the allocator hook has no aligned form */
} arena_block;

struct nn_ctx {
    arena_block *first, *cur;
    size_t grow_count;
    nn_tensor *tail;          /* last tensor on the tape */
    neuv_status status;
    char message[512];
};

static arena_block *block_create(size_t cap)
{
    arena_block *b = mem_alloc(sizeof *b);
    if (!b) return NULL;
    b->raw = mem_alloc((cap + NN_ALIGN - 1) / NN_ALIGN * NN_ALIGN + NN_ALIGN - 1);
    if (!b->raw) { mem_free(b); return NULL; }
    b->mem = (unsigned char *)(((uintptr_t)b->raw + NN_ALIGN - 1) & ~(uintptr_t)(NN_ALIGN - 1));
    b->next = NULL;
    b->cap = cap;
    b->used = 0;
    return b;
}

static void blocks_free(arena_block *b)
{
    while (b) {
        arena_block *n = b->next;
        mem_free(b->raw);
        mem_free(b);
        b = n;
    }
}

nn_ctx *nn_ctx_create(size_t initial_bytes)
{
    nn_ctx *c = mem_calloc(1, sizeof *c);
    if (!c) { error_nomem("neural network context"); return NULL; }
    if (initial_bytes) {
        c->first = block_create(initial_bytes);
        if (!c->first) { mem_free(c); error_nomem("neural network arena"); return NULL; }
        c->grow_count = 1;
    }
    c->cur = c->first;
    return c;
}

void nn_ctx_free(nn_ctx *ctx)
{
    if (!ctx) return;
    blocks_free(ctx->first);
    mem_free(ctx);
}

void nn_ctx_reset(nn_ctx *ctx)
{
    if (!ctx) return;
    /* A step that needed several blocks gets one block of the total size, so the
     * next identical step runs without touching the heap. The old blocks go
     * first (nothing in them outlives a reset), so that the merge never holds
     * twice the step's memory. */
    size_t unmerged = 0;
    if (ctx->first && ctx->first->next) {
        size_t total = 0;
        for (arena_block *b = ctx->first; b; b = b->next) total += b->cap;
        blocks_free(ctx->first);
        ctx->first = block_create(total);
        ctx->grow_count++;
        if (!ctx->first) unmerged = total;
    }
    for (arena_block *b = ctx->first; b; b = b->next) b->used = 0;
    ctx->cur = ctx->first;
    ctx->tail = NULL;
    ctx->status = NEUV_OK;
    ctx->message[0] = '\0';
    /* The old blocks would still do, but the allocator is out of memory:
     * the step that follows fails (nn_ctx_alloc refuses) rather than go on. */
    if (unmerged)
        nn_ctx_fail(ctx, NEUV_ERR_NOMEM, "out of memory merging the neural network arena into %zu bytes", unmerged);
}

neuv_status nn_ctx_status(const nn_ctx *ctx)
{
    if (!ctx) return NEUV_ERR_INTERNAL;
    if (ctx->status != NEUV_OK) return error_set(ctx->status, "%s", ctx->message);
    return NEUV_OK;
}

size_t nn_ctx_grow_count(const nn_ctx *ctx) { return ctx ? ctx->grow_count : 0; }

size_t nn_ctx_bytes_used(const nn_ctx *ctx)
{
    size_t n = 0;
    if (ctx)
        for (arena_block *b = ctx->first; b; b = b->next) n += b->used;
    return n;
}

size_t nn_ctx_bytes_reserved(const nn_ctx *ctx)
{
    size_t n = 0;
    if (ctx)
        for (arena_block *b = ctx->first; b; b = b->next) n += b->cap;
    return n;
}

nn_tensor *nn_ctx_fail(nn_ctx *ctx, neuv_status code, const char *fmt, ...)
{
    if (ctx && ctx->status == NEUV_OK) {
        va_list ap;
        va_start(ap, fmt);
        vsnprintf(ctx->message, sizeof ctx->message, fmt, ap);
        va_end(ap);
        ctx->status = code;
        error_set(code, "%s", ctx->message);
    }
    return NULL;
}

void *nn_ctx_alloc(nn_ctx *ctx, size_t bytes)
{
    if (!ctx || ctx->status != NEUV_OK) return NULL; /* a failed step stays failed */
    size_t need = (bytes + NN_ALIGN - 1) / NN_ALIGN * NN_ALIGN;
    if (need == 0) need = NN_ALIGN;
    arena_block *b = ctx->cur;
    while (b && b->cap - b->used < need) b = b->next;
    if (!b) {
        size_t last = 0;
        arena_block *end = ctx->first;
        while (end && end->next) end = end->next;
        if (end) last = end->cap;
        size_t cap = last * 2 > need ? last * 2 : need;
        if (cap < ((size_t)1 << 20)) cap = (size_t)1 << 20;
        b = block_create(cap);
        if (!b) {
            nn_ctx_fail(ctx, NEUV_ERR_NOMEM, "out of memory growing the neural network arena to %zu bytes",
                        nn_ctx_bytes_reserved(ctx) + cap);
            return NULL;
        }
        ctx->grow_count++;
        if (end) end->next = b; else ctx->first = b;
    }
    ctx->cur = b;
    void *p = b->mem + b->used;
    b->used += need;
    return p;
}

nn_tensor *nn_node(nn_ctx *ctx, nn_op op, int rows, int cols, nn_tensor *a, nn_tensor *b)
{
    if (!ctx) return NULL;
    if (rows <= 0 || cols <= 0)
        return nn_ctx_fail(ctx, NEUV_ERR_INPUT, "%s: empty result shape %d by %d", nn_op_name(op), rows, cols);
    nn_tensor *t = nn_ctx_alloc(ctx, sizeof *t);
    if (!t) return NULL;
    memset(t, 0, sizeof *t);
    t->data = nn_ctx_alloc(ctx, (size_t)rows * (size_t)cols * sizeof(float));
    if (!t->data) return NULL;
    t->rows = rows;
    t->cols = cols;
    t->op = op;
    t->src[0] = a;
    t->src[1] = b;
    t->requires_grad = (a && a->requires_grad) || (b && b->requires_grad);
    t->src[2] = NULL;
    t->prev = ctx->tail;
    ctx->tail = t;
    return t;
}

float *nn_grad_for(nn_ctx *ctx, nn_tensor *t, int *accumulate)
{
    if (!t || !t->requires_grad) return NULL;
    if (t->grad) { *accumulate = 1; return t->grad; }
    t->grad = nn_ctx_alloc(ctx, (size_t)t->rows * (size_t)t->cols * sizeof(float));
    *accumulate = 0;
    return t->grad;
}

float *nn_grad_zeroed(nn_ctx *ctx, nn_tensor *t)
{
    int acc = 0;
    float *g = nn_grad_for(ctx, t, &acc);
    if (g && !acc) memset(g, 0, (size_t)t->rows * (size_t)t->cols * sizeof(float));
    return g;
}

/* ---- leaves ---------------------------------------------------------- */

nn_tensor *nn_new(nn_ctx *ctx, int rows, int cols)
{
    return nn_node(ctx, NN_OP_LEAF, rows, cols, NULL, NULL);
}

nn_tensor *nn_from(nn_ctx *ctx, int rows, int cols, const float *data)
{
    if (!data) return nn_ctx_fail(ctx, NEUV_ERR_INPUT, "input tensor has no data");
    nn_tensor *t = nn_new(ctx, rows, cols);
    if (t) memcpy(t->data, data, (size_t)rows * (size_t)cols * sizeof(float));
    return t;
}

nn_tensor *nn_view(nn_ctx *ctx, int rows, int cols, float *data)
{
    if (!ctx) return NULL;
    if (!data || rows <= 0 || cols <= 0)
        return nn_ctx_fail(ctx, NEUV_ERR_INPUT, "view: bad shape %d by %d or no data", rows, cols);
    nn_tensor *t = nn_ctx_alloc(ctx, sizeof *t);
    if (!t) return NULL;
    memset(t, 0, sizeof *t);
    t->rows = rows;
    t->cols = cols;
    t->data = data;
    t->op = NN_OP_LEAF;
    t->prev = ctx->tail;
    ctx->tail = t;
    return t;
}

nn_tensor *nn_fill(nn_ctx *ctx, int rows, int cols, float value)
{
    nn_tensor *t = nn_new(ctx, rows, cols);
    if (t)
        for (size_t i = 0, n = (size_t)rows * (size_t)cols; i < n; i++) t->data[i] = value;
    return t;
}

/* ---- parameters ------------------------------------------------------ */

nn_tensor *nn_param_create(int rows, int cols, const char *name)
{
    if (rows <= 0 || cols <= 0) {
        error_set(NEUV_ERR_INPUT, "parameter '%s': bad shape %d by %d", name ? name : "", rows, cols);
        return NULL;
    }
    nn_tensor *p = mem_calloc(1, sizeof *p);
    size_t n = (size_t)rows * (size_t)cols;
    char *nm = NULL;
    if (p) {
        p->data = mem_calloc(n, sizeof(float));
        p->grad = mem_calloc(n, sizeof(float));
        if (name) nm = mem_strdup(name);
    }
    if (!p || !p->data || !p->grad || (name && !nm)) {
        if (p) { mem_free(p->data); mem_free(p->grad); }
        mem_free(p);
        mem_free(nm);
        error_nomem("parameter");
        return NULL;
    }
    p->rows = rows;
    p->cols = cols;
    p->op = NN_OP_LEAF;
    p->requires_grad = 1;
    p->is_param = 1;
    p->name = nm;
    return p;
}

void nn_param_free(nn_tensor *p)
{
    if (!p) return;
    mem_free(p->data);
    mem_free(p->grad);
    mem_free((char *)p->name);
    mem_free(p);
}

void nn_params_init(nn_params *ps) { memset(ps, 0, sizeof *ps); }

nn_tensor *nn_params_find(const nn_params *ps, const char *name)
{
    for (int i = 0; i < ps->n; i++)
        if (ps->t[i]->name && !strcmp(ps->t[i]->name, name)) return ps->t[i];
    return NULL;
}

nn_tensor *nn_params_add(nn_params *ps, int rows, int cols, const char *name)
{
    if (!name || !*name) { error_set(NEUV_ERR_INPUT, "parameter needs a name"); return NULL; }
    if (nn_params_find(ps, name)) { error_set(NEUV_ERR_INPUT, "duplicate parameter name '%s'", name); return NULL; }
    if (ps->n == ps->cap) {
        int cap = ps->cap ? ps->cap * 2 : 16;
        nn_tensor **t = mem_realloc(ps->t, (size_t)cap * sizeof *t);
        if (!t) { error_nomem("parameter list"); return NULL; }
        ps->t = t;
        ps->cap = cap;
    }
    nn_tensor *p = nn_param_create(rows, cols, name);
    if (!p) return NULL;
    ps->t[ps->n++] = p;
    return p;
}

size_t nn_params_count(const nn_params *ps)
{
    size_t n = 0;
    for (int i = 0; i < ps->n; i++) n += (size_t)ps->t[i]->rows * (size_t)ps->t[i]->cols;
    return n;
}

void nn_params_zero_grad(nn_params *ps)
{
    for (int i = 0; i < ps->n; i++)
        memset(ps->t[i]->grad, 0, (size_t)ps->t[i]->rows * (size_t)ps->t[i]->cols * sizeof(float));
}

void nn_params_free(nn_params *ps)
{
    if (!ps) return;
    for (int i = 0; i < ps->n; i++) nn_param_free(ps->t[i]);
    mem_free(ps->t);
    memset(ps, 0, sizeof *ps);
}

const char *nn_op_name(nn_op op)
{
    static const char *names[NN_OP_COUNT] = {
        [NN_OP_LEAF] = "leaf", [NN_OP_MATMUL] = "matmul", [NN_OP_ADD] = "add", [NN_OP_SUB] = "sub",
        [NN_OP_MUL] = "mul", [NN_OP_DIV] = "div", [NN_OP_ADD_CONST] = "add_const",
        [NN_OP_SCALE] = "scale", [NN_OP_SUM] = "sum", [NN_OP_MEAN] = "mean",
        [NN_OP_CONCAT_COLS] = "concat_cols", [NN_OP_SLICE_COLS] = "slice_cols",
        [NN_OP_GATHER_ROWS] = "gather_rows", [NN_OP_SCATTER_ADD_ROWS] = "scatter_add_rows",
        [NN_OP_SPMM] = "spmm", [NN_OP_RELU] = "relu", [NN_OP_LEAKY_RELU] = "leaky_relu",
        [NN_OP_TANH] = "tanh", [NN_OP_SIGMOID] = "sigmoid", [NN_OP_SOFTMAX_ROWS] = "softmax_rows",
        [NN_OP_EXP] = "exp", [NN_OP_LOG] = "log", [NN_OP_SQRT] = "sqrt", [NN_OP_SQUARE] = "square",
        [NN_OP_ROW_NORM] = "row_norm", [NN_OP_ROW_DOT] = "row_dot", [NN_OP_ROW_COSINE] = "row_cosine",
        [NN_OP_CLAMP_MIN] = "clamp_min", [NN_OP_LINEAR] = "linear",
    };
    if ((int)op < 0 || op >= NN_OP_COUNT || !names[op]) return "unknown";
    return names[op];
}
