#include "core/atomic_file.h"

#include <errno.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>
#include <fcntl.h>

#include "core/error.h"
#include "core/mem.h"

static char *dir_of(const char *path)
{
    const char *slash = strrchr(path, '/');
    if (!slash) return mem_strdup(".");
    if (slash == path) return mem_strdup("/");
    size_t n = (size_t)(slash - path);
    char *d = mem_alloc(n + 1);
    if (!d) return NULL;
    memcpy(d, path, n);
    d[n] = '\0';
    return d;
}

neuv_status atomic_file_open(atomic_file *af, const char *target)
{
    memset(af, 0, sizeof *af);
    struct stat st;
    if (stat(target, &st) == 0 && S_ISDIR(st.st_mode))
        return error_set(NEUV_ERR_IO, "is a directory");
    char *dir = dir_of(target);
    if (!dir) return error_nomem("a path");
    if (stat(dir, &st) != 0 || !S_ISDIR(st.st_mode)) {
        neuv_status s = error_set(NEUV_ERR_IO, "folder %s does not exist", dir);
        mem_free(dir);
        return s;
    }
    mem_free(dir);
    size_t n = strlen(target) + 32;
    af->tmp_path = mem_alloc(n);
    af->target = mem_strdup(target);
    if (!af->tmp_path || !af->target) { atomic_file_abort(af); return error_nomem("a path"); }
    snprintf(af->tmp_path, n, "%s.tmp-XXXXXX", target);
    int fd = mkstemp(af->tmp_path);
    if (fd < 0) {
        neuv_status s = error_set(NEUV_ERR_IO, "cannot create file: %s", strerror(errno));
        mem_free(af->tmp_path); af->tmp_path = NULL;
        atomic_file_abort(af);
        return s;
    }
    fchmod(fd, 0644);
    af->fp = fdopen(fd, "wb");
    if (!af->fp) {
        close(fd);
        atomic_file_abort(af);
        return error_set(NEUV_ERR_IO, "cannot open file for writing");
    }
    return NEUV_OK;
}

neuv_status atomic_file_commit(atomic_file *af)
{
    if (!af->fp) { atomic_file_abort(af); return error_set(NEUV_ERR_IO, "file was not open"); }
    int bad = ferror(af->fp) || fflush(af->fp) != 0 || fsync(fileno(af->fp)) != 0;
    if (fclose(af->fp) != 0) bad = 1;
    af->fp = NULL;
    if (bad) { atomic_file_abort(af); return error_set(NEUV_ERR_IO, "write failed (disk full?)"); }
    if (rename(af->tmp_path, af->target) != 0) {
        neuv_status s = error_set(NEUV_ERR_IO, "cannot rename into place: %s", strerror(errno));
        atomic_file_abort(af);
        return s;
    }
    mem_free(af->tmp_path); af->tmp_path = NULL;
    mem_free(af->target); af->target = NULL;
    return NEUV_OK;
}

void atomic_file_abort(atomic_file *af)
{
    if (af->fp) { fclose(af->fp); af->fp = NULL; }
    if (af->tmp_path) { unlink(af->tmp_path); mem_free(af->tmp_path); af->tmp_path = NULL; }
    mem_free(af->target); af->target = NULL;
}
