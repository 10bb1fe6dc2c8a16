/* Minimal test harness: CHECK macros that count failures, a skip exit code
 * for ctest (77), and paths to ../shared and a scratch folder. */
#ifndef NEUV_TESTS_CHECK_H
#define NEUV_TESTS_CHECK_H

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

static int check_failures;
static int check_count;

#define CHECK(cond) do { check_count++; if (!(cond)) { check_failures++; \
    fprintf(stderr, "%s:%d: CHECK failed: %s\n", __FILE__, __LINE__, #cond); } } while (0)

#define CHECK_NEAR(a, b, tol) do { double ca_ = (a), cb_ = (b); check_count++; \
    if (!(fabs(ca_ - cb_) <= (tol))) { check_failures++; \
    fprintf(stderr, "%s:%d: CHECK_NEAR failed: %s = %.12g, %s = %.12g, tol %g\n", \
            __FILE__, __LINE__, #a, ca_, #b, cb_, (double)(tol)); } } while (0)

#define CHECK_INT(a, b) do { long long ca_ = (a), cb_ = (b); check_count++; \
    if (ca_ != cb_) { check_failures++; \
    fprintf(stderr, "%s:%d: CHECK_INT failed: %s = %lld, expected %s = %lld\n", \
            __FILE__, __LINE__, #a, ca_, #b, cb_); } } while (0)

/* Ends main: prints "N passed, M failed" and returns the exit code. */
static inline int check_report(const char *name)
{
    printf("%s: %d passed, %d failed\n", name, check_count - check_failures, check_failures);
    return check_failures ? 1 : 0;
}

/* Path of a file in ../shared/meshes (or another shared subfolder), NULL if
 * ../shared is absent. */
static inline const char *shared_path(const char *rel)
{
    static char buf[4096];
    const char *root = getenv("NEUV_SHARED");
    if (!root) root = "../shared";
    struct stat st;
    if (stat(root, &st) != 0) return NULL;
    snprintf(buf, sizeof buf, "%s/%s", root, rel);
    return buf;
}

/* A scratch path under $NEUV_TEST_TMP (created), for files a test writes. */
static inline const char *tmp_path(const char *name)
{
    static char buf[4][4096];
    static int next;
    const char *root = getenv("NEUV_TEST_TMP");
    if (!root) root = "/tmp";
    mkdir(root, 0755);
    char *b = buf[next++ % 4];
    snprintf(b, 4096, "%s/%s", root, name);
    return b;
}

/* Writes n bytes to tmp_path(name) and returns that path (exits on failure). */
static inline const char *write_tmp_file(const char *name, const void *data, size_t n)
{
    const char *path = tmp_path(name);
    FILE *fp = fopen(path, "wb");
    if (!fp) { perror(path); exit(1); }
    fwrite(data, 1, n, fp);
    fclose(fp);
    return path;
}

#define SKIP(msg) do { printf("SKIP: %s\n", msg); exit(77); } while (0)

#endif
