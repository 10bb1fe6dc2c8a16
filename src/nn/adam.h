/* Adam optimizer (Kingma & Ba 2015, Algorithm 1, with bias correction), global
 * gradient-norm clipping and a learning-rate schedule hook. */
#ifndef NEUV_NN_ADAM_H
#define NEUV_NN_ADAM_H

#include "nn/nn.h"

/* Learning rate for step t (1-based) given the base rate; user data passed through. */
typedef float (*nn_lr_schedule)(void *user, long step, float base_lr);

typedef struct nn_adam_config {
    float lr;          /* 1e-3 */
    float beta1;       /* 0.9 */
    float beta2;       /* 0.999 */
    float eps;         /* 1e-8 */
    float clip_norm;   /* > 0: scale gradients so their global L2 norm is at most this; 0 off */
    nn_lr_schedule schedule; /* NULL: constant lr */
    void *schedule_user;
} nn_adam_config;

typedef struct nn_adam {
    nn_adam_config cfg;
    nn_params *params;   /* borrowed */
    float **m, **v;      /* first and second moments, one per parameter */
    long t;              /* steps taken */
    float last_grad_norm; /* global gradient norm before clipping, last step */
    float last_lr;
} nn_adam;

/* Defaults: lr 1e-3, betas 0.9/0.999, eps 1e-8, no clipping, constant lr. */
nn_adam_config nn_adam_defaults(void);
/* cfg NULL = defaults. The parameter set must not gain parameters afterwards. */
neuv_status nn_adam_init(nn_adam *opt, nn_params *params, const nn_adam_config *cfg);
/* One update from the parameters' current grads. */
void nn_adam_step(nn_adam *opt);
void nn_adam_free(nn_adam *opt);

#endif
