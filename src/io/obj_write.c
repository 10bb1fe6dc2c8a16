#include <stdio.h>

#include "core/error.h"
#include "core/json_writer.h"
#include "io/mesh_io.h"

neuv_status io_write_obj(const neuv_mesh *m, FILE *fp)
{
    fprintf(fp, "# neuv %s: %d vertices, %d faces%s\n", neuv_version(), m->nv, m->nf,
            m->nuv > 0 ? ", per-corner UVs" : "");
    char a[32], b[32], c[32];
    /* Shortest decimal that reads back to the same double: a round trip
     * through OBJ keeps positions bit for bit. */
    for (int v = 0; v < m->nv; v++) {
        const double *p = m->pos + 3 * (size_t)v;
        format_double_exact(a, p[0]);
        format_double_exact(b, p[1]);
        format_double_exact(c, p[2]);
        fprintf(fp, "v %s %s %s\n", a, b, c);
    }
    int with_uv = m->nuv > 0 && m->tri_uv;
    if (with_uv)
        for (int t = 0; t < m->nuv; t++) {
            format_double_exact(a, m->uv[2 * (size_t)t]);
            format_double_exact(b, m->uv[2 * (size_t)t + 1]);
            fprintf(fp, "vt %s %s\n", a, b);
        }
    for (int f = 0; f < m->nf; f++) {
        const int *t = m->tri + 3 * (size_t)f;
        if (with_uv) {
            const int *u = m->tri_uv + 3 * (size_t)f;
            fprintf(fp, "f %d/%d %d/%d %d/%d\n", t[0] + 1, u[0] + 1, t[1] + 1, u[1] + 1, t[2] + 1, u[2] + 1);
        } else {
            fprintf(fp, "f %d %d %d\n", t[0] + 1, t[1] + 1, t[2] + 1);
        }
    }
    return ferror(fp) ? error_set(NEUV_ERR_IO, "write failed (disk full?)") : NEUV_OK;
}
