/* Reverse-mode differentiation over the ctx tape. */
#include "nn/nn_internal.h"

#include "core/error.h"

static const nn_backward_fn backward_rule[NN_OP_COUNT] = {
    [NN_OP_LEAF] = NULL,
    [NN_OP_MATMUL] = nn_backward_matmul,
    [NN_OP_ADD] = nn_backward_binary,
    [NN_OP_SUB] = nn_backward_binary,
    [NN_OP_MUL] = nn_backward_binary,
    [NN_OP_DIV] = nn_backward_binary,
    [NN_OP_ADD_CONST] = nn_backward_unary,
    [NN_OP_SCALE] = nn_backward_unary,
    [NN_OP_SUM] = nn_backward_reduce,
    [NN_OP_MEAN] = nn_backward_reduce,
    [NN_OP_CONCAT_COLS] = nn_backward_concat_cols,
    [NN_OP_SLICE_COLS] = nn_backward_slice_cols,
    [NN_OP_GATHER_ROWS] = nn_backward_gather_rows,
    [NN_OP_SCATTER_ADD_ROWS] = nn_backward_scatter_add_rows,
    [NN_OP_SPMM] = nn_backward_spmm,
    [NN_OP_RELU] = nn_backward_unary,
    [NN_OP_LEAKY_RELU] = nn_backward_unary,
    [NN_OP_TANH] = nn_backward_unary,
    [NN_OP_SIGMOID] = nn_backward_unary,
    [NN_OP_SOFTMAX_ROWS] = nn_backward_softmax_rows,
    [NN_OP_EXP] = nn_backward_unary,
    [NN_OP_LOG] = nn_backward_unary,
    [NN_OP_SQRT] = nn_backward_unary,
    [NN_OP_SQUARE] = nn_backward_unary,
    [NN_OP_ROW_NORM] = nn_backward_row_norm,
    [NN_OP_ROW_DOT] = nn_backward_row_dot,
    [NN_OP_ROW_COSINE] = nn_backward_row_cosine,
    [NN_OP_CLAMP_MIN] = nn_backward_unary,
    [NN_OP_LINEAR] = nn_backward_linear,
};

/* The tape is in creation order, which is a topological order (an op's inputs
 * exist before it), so walking it backwards visits every tensor after all the
 * tensors that consume it. Tensors the loss does not depend on keep grad NULL. */
neuv_status nn_backward(nn_ctx *ctx, nn_tensor *loss)
{
    neuv_status st = nn_ctx_status(ctx);
    if (st != NEUV_OK) return st;
    if (!loss) return error_set(NEUV_ERR_INTERNAL, "backward: no loss tensor");
    if (loss->rows != 1 || loss->cols != 1)
        return error_set(NEUV_ERR_INPUT, "backward: loss is %d by %d, not a scalar", loss->rows, loss->cols);
    if (!loss->requires_grad) return NEUV_OK; /* no parameter upstream: nothing to do */
    int acc = 0;
    float *g = nn_grad_for(ctx, loss, &acc);
    if (!g) return nn_ctx_status(ctx);
    g[0] = acc ? g[0] + 1.0f : 1.0f;
    for (nn_tensor *t = loss; t; t = t->prev) {
        if (!t->grad || !t->requires_grad || t->op == NN_OP_LEAF) continue;
        backward_rule[t->op](ctx, t);
        st = nn_ctx_status(ctx);
        if (st != NEUV_OK) return st;
    }
    return NEUV_OK;
}
