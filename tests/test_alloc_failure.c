/* Out of memory, honestly. An application allocator (neuv_set_allocator)
 * counts live blocks and fails the Nth allocation (alloc or realloc call).
 * A small unwrap through the public API (an atlas) runs once to count its allocations
 * A; then it runs again with the Nth failing, for many N, and every time it
 * must return NEUV_ERR_NOMEM, leave its out-pointer NULL, and free all it
 * allocated (the live count is back where it was). Only the Nth fails, not
 * every one after it, so a failure the library swallows (a note dropped, a
 * fallback taken) shows up as NEUV_OK. neuv_mesh_save under every failure
 * leaves neither the file nor its temporary, and neuv_atlas_report_json
 * returns NULL.
 *
 * Which N: every one up to a cap, then, above it, `per_stage` evenly spaced
 * over each stage of the pipeline (the stages the progress callback names,
 * located in the counting run; "param", named once per chart, is one
 * stage). The packer makes most of the allocations (footprints for every
 * trial) and takes little time; the networks make few and take most of it
 * (a neural run that gets past them costs ~3 s of CPU under ASan). A stride
 * per stage tries each stage as often, whatever its count.
 *
 * The calls: the atlas unwrap (LSCM, then the networks on one thread and
 * on two), a surface model applied to a finer triangulation, a category
 * model trained on two shapes and applied to a third, loading a mesh in
 * each written format and loading a model file; then the report and the
 * three writers. Loading may absorb a failure where a block it shrinks to
 * size stays as it was: there a success counts when its mesh equals the
 * reference, and the test prints how many did.
 *
 * Figures (80-face icosphere, threads 1: the order of allocations is then
 * fixed; the test prints its own): LSCM 24,192 allocations, every N up to
 * 300, then 8 per stage: 340 runs. Neural (3 steps per network, refine 2)
 * 28,437, every N up to 60 (its first ~2,000 are LSCM's: cleaning,
 * operators, PatchNet, charts), then 3 per stage: 84 runs; on two threads
 * ~31,500, every N up to 20 then 2 per stage. Surface model applied: every
 * one of its 822. Category training 7,485 and inference 11,687: every N up
 * to 60 then 4 per stage. Loading: every one. 26 s in a Release build here.
 * Set NEUV_ALLOC_FAILURE_EVERY (a large value tries every N),
 * NEUV_ALLOC_FAILURE_PER_STAGE, or NEUV_ALLOC_FAILURE_N (that one N only,
 * to debug a failure). */
#include <dirent.h>
#include <stdatomic.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "check.h"
#include "failing_alloc.h"
#include "mesh/shapes.h"
#include "neuv/neuv.h"


static double now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static long env_long(const char *name, long fallback)
{
    const char *v = getenv(name);
    return v && *v ? atol(v) : fallback;
}

/* Stages as the progress callback names them: where each begins, counted
 * in allocations. */
#define MAX_STAGES 64
static struct { char name[32]; long start; } stage[MAX_STAGES];
static int n_stages;

static int on_progress(void *user, const char *name, double fraction, const char *detail)
{
    (void)user; (void)fraction; (void)detail;
    if (n_stages > 0 && !strcmp(stage[n_stages - 1].name, name)) return 1;
    if (n_stages == MAX_STAGES) return 1;
    snprintf(stage[n_stages].name, sizeof stage[n_stages].name, "%s", name);
    stage[n_stages].start = atomic_load(&n_calls) + 1;
    n_stages++;
    return 1;
}

/* One call an application makes, run again and again under failure: on
 * failure *out must be NULL and nothing kept; release frees a success. */
typedef struct job {
    const char *label;
    neuv_status (*run)(const struct job *j, const neuv_callbacks *cb, void **out);
    void (*release)(void *out);
    const neuv_mesh *mesh;
    const neuv_mesh *const *meshes; /* category training */
    int n_meshes;
    const neuv_unwrap_options *o;
    const neuv_model *model;        /* applied */
    const char *path;               /* loaded */
    /* Where the call may absorb a failure (a block shrunk to size that
     * stays as it was): 1 when a successful result equals the reference. */
    int (*same)(const void *out, const void *ref);
} job;

static void release_atlas(void *a) { neuv_atlas_destroy(a); }

static int same_mesh(const void *x, const void *y)
{
    const neuv_mesh *a = x, *b = y;
    int nv = neuv_mesh_vertex_count(a), nf = neuv_mesh_face_count(a);
    if (nv != neuv_mesh_vertex_count(b) || nf != neuv_mesh_face_count(b)) return 0;
    double *pa = malloc(sizeof(double) * 3 * (size_t)nv), *pb = malloc(sizeof(double) * 3 * (size_t)nv);
    int *ta = malloc(sizeof(int) * 3 * (size_t)nf), *tb = malloc(sizeof(int) * 3 * (size_t)nf);
    int same = pa && pb && ta && tb;
    if (same) {
        neuv_mesh_get_positions(a, pa);
        neuv_mesh_get_positions(b, pb);
        neuv_mesh_get_indices(a, ta);
        neuv_mesh_get_indices(b, tb);
        same = !memcmp(pa, pb, sizeof(double) * 3 * (size_t)nv) && !memcmp(ta, tb, sizeof(int) * 3 * (size_t)nf);
    }
    free(pa); free(pb); free(ta); free(tb);
    return same;
}
static void release_mesh(void *m) { neuv_mesh_free(m); }
static void release_model(void *m) { neuv_model_free(m); }

/* An unwrap as an application makes it: an atlas, the mesh added (copied),
 * all stages, or with a model the model applied. */
static neuv_status atlas_job(const job *j, const neuv_callbacks *cb, void **out)
{
    *out = NULL;
    neuv_atlas *a = NULL;
    neuv_status s = neuv_atlas_create(&a);
    if (s == NEUV_OK) {
        neuv_atlas_set_callbacks(a, cb);
        s = neuv_atlas_add_loaded_mesh(a, j->mesh);
    }
    if (s == NEUV_OK && !j->model) s = neuv_atlas_generate(a, j->o);
    if (s == NEUV_OK && j->model) {
        neuv_apply_options ao;
        neuv_apply_options_init(&ao);
        ao.threads = 1;
        ao.use_cache = 0;
        s = neuv_atlas_apply_model(a, j->model, &ao);
    }
    if (s != NEUV_OK) { neuv_atlas_destroy(a); return s; }
    *out = a;
    return NEUV_OK;
}

static neuv_status unwrap_once(const neuv_mesh *mesh, const neuv_unwrap_options *o, const neuv_callbacks *cb,
                               neuv_atlas **out)
{
    job j = {"unwrap", atlas_job, release_atlas, mesh, NULL, 0, o, NULL, NULL, NULL};
    void *a = NULL;
    neuv_status s = atlas_job(&j, cb, &a);
    *out = a;
    return s;
}

static neuv_status train_job(const job *j, const neuv_callbacks *cb, void **out)
{
    neuv_model *m = NULL;
    neuv_status s = neuv_train_category(j->meshes, j->n_meshes, j->o, 3, cb, &m, NULL);
    *out = m;
    return s;
}

static neuv_status load_job(const job *j, const neuv_callbacks *cb, void **out)
{
    neuv_mesh *m = NULL;
    neuv_status s = neuv_mesh_load(j->path, cb, &m);
    *out = m;
    return s;
}

static neuv_status model_load_job(const job *j, const neuv_callbacks *cb, void **out)
{
    (void)cb;
    neuv_model *m = NULL;
    neuv_status s = neuv_model_load(j->path, &m);
    *out = m;
    return s;
}

static int cmp_long(const void *a, const void *b)
{
    long x = *(const long *)a, y = *(const long *)b;
    return (x > y) - (x < y);
}

/* Allocations lo..hi of stage s, clipped to those above `every`
 * (hi < lo: none). Stage -1 is what comes before the first report. */
static void stage_range(int s, long a, long every, long *lo, long *hi)
{
    *lo = s < 0 ? 1 : stage[s].start;
    *hi = s + 1 < n_stages ? stage[s + 1].start - 1 : a;
    if (*lo <= every) *lo = every + 1;
}

/* The N to try for a call of `a` allocations: 1..every, then per_stage
 * evenly spaced over each stage (a stage the callback names more than once,
 * as "param" once per chart, counts as one). Returns how many, ascending. */
static long choose_n(long a, long every, long per_stage, long **out)
{
    long cap = (every < a ? every : a) + (long)(MAX_STAGES + 1) * per_stage + 1, n = 0;
    long *list = malloc(sizeof *list * (size_t)cap);
    if (!list) return 0;
    for (long k = 1; k <= a && k <= every; k++) list[n++] = k;
    for (int s = -1; s < n_stages; s++) {
        int first = 1; /* s is the first mention of its name */
        for (int t = 0; t < s; t++)
            if (!strcmp(stage[t].name, stage[s].name)) first = 0;
        if (s >= 0 && !first) continue;
        long len = 0, lo, hi;
        for (int t = s; t < n_stages; t++) {
            if (t != s && (s < 0 || strcmp(stage[t].name, stage[s].name))) continue;
            stage_range(t, a, every, &lo, &hi);
            if (hi >= lo) len += hi - lo + 1;
            if (s < 0) break;
        }
        for (long j = 0; j < per_stage && len > 0; j++) {
            long pos = len * (2 * j + 1) / (2 * per_stage); /* 0-based within the stage */
            for (int t = s; t < n_stages; t++) {
                if (t != s && (s < 0 || strcmp(stage[t].name, stage[s].name))) continue;
                stage_range(t, a, every, &lo, &hi);
                if (hi >= lo && pos <= hi - lo) { list[n++] = lo + pos; break; }
                if (hi >= lo) pos -= hi - lo + 1;
                if (s < 0) break;
            }
        }
    }
    qsort(list, (size_t)n, sizeof *list, cmp_long);
    long m = 0;
    for (long i = 0; i < n; i++)
        if (m == 0 || list[i] != list[m - 1]) list[m++] = list[i];
    *out = list;
    return m;
}

static int runs_total;

static void run_under_failure(const job *j, long every, long per_stage)
{
    const char *label = j->label;
    long live0 = atomic_load(&n_live);
    n_stages = 0;
    arm(0);
    const neuv_callbacks stages = {NULL, on_progress, NULL};
    void *r = NULL;
    neuv_status s = j->run(j, &stages, &r);
    long a = atomic_load(&n_calls);
    CHECK_INT(s, NEUV_OK);
    if (s != NEUV_OK) fprintf(stderr, "%s: %s\n", label, neuv_last_error());
    void *ref = r; /* released at the end: its blocks are live meanwhile */
    long live_ref = atomic_load(&n_live);

    long *list = NULL, count = choose_n(a, every, per_stage, &list);
    long only = env_long("NEUV_ALLOC_FAILURE_N", 0);
    if (only > 0) { list[0] = only; count = 1; }
    int bad = 0, absorbed = 0;
    double t0 = now();
    for (long i = 0; i < count; i++) {
        long n = list[i];
        arm(n);
        r = &r; /* not NULL: the call must clear it */
        s = j->run(j, NULL, &r); /* the callbacks allocate nothing: same N as the counting run */
        arm(0);
        int same = s == NEUV_OK && r && j->same && j->same(r, ref);
        if (same) { j->release(r); r = NULL; absorbed++; }
        long leaked = atomic_load(&n_live) - live_ref;
        int ok = (s == NEUV_ERR_NOMEM && r == NULL && leaked == 0) || (same && leaked == 0);
        if (!ok && bad++ < 20)
            fprintf(stderr, "%s: allocation %ld of %ld failing: status %d (%s), result %s, %ld blocks leaked\n", label,
                    n, a, s, neuv_last_error(), r ? "set" : "NULL", leaked);
        CHECK(ok);
        if (s == NEUV_OK && r) j->release(r);
        atomic_store(&n_live, live_ref); /* a leak is reported once */
    }
    if (ref) j->release(ref);
    CHECK_INT(atomic_load(&n_live), live0);
    printf("%s: %ld allocations; failed each of 1..%ld, then %ld per stage: %ld runs (%d absorbed: a block not shrunk, "
           "the same result), %.1f s. Stages from:", label, a, every < a ? every : a, per_stage, count, absorbed,
           now() - t0);
    for (int k = 0; k < n_stages; k++) printf(" %s %ld", stage[k].name, stage[k].start);
    printf("\n");
    runs_total += (int)count;
    free(list);
}

/* Whether `dir` holds `name` or a temporary of it (name.tmp-XXXXXX). */
static int leftover(const char *dir, const char *name)
{
    DIR *d = opendir(dir);
    if (!d) return 0;
    size_t n = strlen(name);
    int found = 0;
    for (struct dirent *e; (e = readdir(d));)
        if (!strncmp(e->d_name, name, n) && (e->d_name[n] == '\0' || e->d_name[n] == '.')) found = 1;
    closedir(d);
    return found;
}

static void save_under_failure(const neuv_mesh *mesh, const char *name)
{
    const char *path = tmp_path(name);
    const char *dir = tmp_path("");
    unlink(path);
    long live0 = atomic_load(&n_live);
    arm(0);
    CHECK_INT(neuv_mesh_save(mesh, path), NEUV_OK);
    long a = atomic_load(&n_calls);
    CHECK_INT(atomic_load(&n_live), live0);
    CHECK(access(path, F_OK) == 0);
    unlink(path);
    for (long n = 1; n <= a; n++) {
        arm(n);
        neuv_status s = neuv_mesh_save(mesh, path);
        arm(0);
        CHECK_INT(s, NEUV_ERR_NOMEM);
        CHECK_INT(atomic_load(&n_live), live0);
        CHECK(!leftover(dir, name));
        atomic_store(&n_live, live0);
        unlink(path);
    }
    printf("save %s: %ld allocations, each failed in turn\n", name, a);
}

static void report_under_failure(const neuv_atlas *r)
{
    long live0 = atomic_load(&n_live);
    arm(0);
    char *json = neuv_atlas_report_json(r, "sphere", 0, 0);
    long a = atomic_load(&n_calls);
    CHECK(json != NULL);
    neuv_free(json);
    CHECK_INT(atomic_load(&n_live), live0);
    for (long n = 1; n <= a; n++) {
        arm(n);
        json = neuv_atlas_report_json(r, "sphere", 0, 0);
        arm(0);
        CHECK(json == NULL);
        neuv_free(json);
        CHECK_INT(atomic_load(&n_live), live0);
        atomic_store(&n_live, live0);
    }
    printf("report: %ld allocations, each failed in turn\n", a);
}

int main(void)
{
    neuv_set_allocator(&failing_allocator); /* before any other call, as the contract asks */

    neuv_mesh *mesh = shape_icosphere(1, 1.0);
    CHECK(mesh != NULL);
    if (!mesh) return check_report("alloc_failure");

    long every = env_long("NEUV_ALLOC_FAILURE_EVERY", 0), per_stage = env_long("NEUV_ALLOC_FAILURE_PER_STAGE", 0);
    neuv_unwrap_options o;
    neuv_unwrap_options_init(&o);
    o.use_cache = 0;
    o.threads = 1;
    o.resolution = 64;
    o.iters = 3;
    o.method = NEUV_METHOD_LSCM;
    job lscm = {"lscm", atlas_job, release_atlas, mesh, NULL, 0, &o, NULL, NULL, NULL};
    run_under_failure(&lscm, every ? every : 300, per_stage ? per_stage : 8);

    /* The networks: PatchNet and the parameterization networks, 3 steps each. */
    o.method = NEUV_METHOD_NEURAL;
    o.refine = 2;
    job neural = {"neural", atlas_job, release_atlas, mesh, NULL, 0, &o, NULL, NULL, NULL};
    run_under_failure(&neural, every ? every : 60, per_stage ? per_stage : 3);

    /* The same on two threads: the allocations' order varies from run to
     * run, each failure must still come back as NEUV_ERR_NOMEM. */
    neuv_unwrap_options two = o;
    two.threads = 2;
    job threads = {"neural, 2 threads", atlas_job, release_atlas, mesh, NULL, 0, &two, NULL, NULL, NULL};
    run_under_failure(&threads, every ? every : 20, per_stage ? per_stage : 2);

    /* A surface model (trained here with every allocation granted) carried
     * to another triangulation of the sphere, then a category model trained
     * on two shapes, under failure, and applied to a third. */
    neuv_mesh *finer = shape_icosphere(2, 1.0);
    neuv_mesh *other = shape_icosphere(1, 1.3);
    CHECK(finer && other);
    neuv_model *surface = NULL;
    {
        neuv_unwrap_options keep = o;
        keep.keep_model = 1;
        neuv_atlas *src = NULL;
        job j = {"source", atlas_job, release_atlas, mesh, NULL, 0, &keep, NULL, NULL, NULL};
        void *got = NULL;
        CHECK_INT(atlas_job(&j, NULL, &got), NEUV_OK);
        src = got;
        if (src) CHECK_INT(neuv_atlas_take_model(src, &surface), NEUV_OK);
        neuv_atlas_destroy(src);
    }
    if (surface && finer) {
        job apply = {"apply surface model", atlas_job, release_atlas, finer, NULL, 0, &o, surface, NULL, NULL};
        run_under_failure(&apply, every ? every : 100000, per_stage);
    }
    const neuv_mesh *pair[2] = {mesh, other};
    neuv_model *category = NULL;
    if (other) {
        job train = {"train category", train_job, release_model, NULL, pair, 2, &o, NULL, NULL, NULL};
        run_under_failure(&train, every ? every : 60, per_stage ? per_stage : 4);
        CHECK_INT(neuv_train_category(pair, 2, &o, 3, NULL, &category, NULL), NEUV_OK);
    }
    if (category && finer) {
        job apply = {"apply category model", atlas_job, release_atlas, finer, NULL, 0, &o, category, NULL, NULL};
        run_under_failure(&apply, every ? every : 60, per_stage ? per_stage : 4);
    }

    /* Loading: a mesh in each format neuv writes, and a model file. */
    const char *formats[3] = {"alloc_load.obj", "alloc_load.ply", "alloc_load.glb"};
    for (int k = 0; k < 3; k++) {
        const char *path = tmp_path(formats[k]);
        CHECK_INT(neuv_mesh_save(finer ? finer : mesh, path), NEUV_OK);
        char label[32];
        snprintf(label, sizeof label, "load %s", formats[k] + strlen("alloc_load."));
        job load = {label, load_job, release_mesh, NULL, NULL, 0, NULL, NULL, path, same_mesh};
        run_under_failure(&load, 100000, 0);
        unlink(path);
    }
    if (category) {
        const char *path = tmp_path("alloc_load.neuv");
        CHECK_INT(neuv_model_save(category, path), NEUV_OK);
        job load = {"load model", model_load_job, release_model, NULL, NULL, 0, NULL, NULL, path, NULL};
        run_under_failure(&load, 100000, 0);
        unlink(path);
    }
    neuv_model_free(surface);
    neuv_model_free(category);
    neuv_mesh_free(finer);
    neuv_mesh_free(other);

    arm(0);
    neuv_atlas *r = NULL;
    CHECK_INT(unwrap_once(mesh, &o, NULL, &r), NEUV_OK);
    if (r) {
        report_under_failure(r);
        save_under_failure(neuv_atlas_mesh(r), "alloc_failure.obj");
        save_under_failure(neuv_atlas_mesh(r), "alloc_failure.ply");
        save_under_failure(neuv_atlas_mesh(r), "alloc_failure.glb");
    }
    neuv_atlas_destroy(r);
    neuv_mesh_free(mesh);
    CHECK_INT(atomic_load(&n_live), 0);
    neuv_set_allocator(NULL);
    printf("%d unwraps under failure\n", runs_total);
    return check_report("alloc_failure");
}
