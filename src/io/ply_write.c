#include <stdio.h>

#include "core/error.h"
#include "io/byte_order.h"
#include "io/mesh_io.h"
#include "io/seam_split.h"

neuv_status io_write_ply(const neuv_mesh *m, FILE *fp)
{
    seam_split sp;
    neuv_status s = seam_split_vertices(m, &sp);
    if (s != NEUV_OK) return s;
    fprintf(fp, "ply\nformat binary_little_endian 1.0\ncomment neuv %s\n", neuv_version());
    /* double positions so a round trip is exact; float UVs as other tools expect. */
    fprintf(fp, "element vertex %d\nproperty double x\nproperty double y\nproperty double z\n", sp.nv);
    if (sp.uv) fprintf(fp, "property float s\nproperty float t\n");
    fprintf(fp, "element face %d\nproperty list uchar int vertex_indices\nend_header\n", m->nf);
    unsigned char rec[32];
    for (int v = 0; v < sp.nv; v++) {
        const double *p = m->pos + 3 * (size_t)sp.src[v];
        unsigned char *q = rec;
        for (int k = 0; k < 3; k++) q = put_f64le(q, p[k]);
        if (sp.uv) {
            q = put_f32le(q, (float)sp.uv[2 * (size_t)v]);
            q = put_f32le(q, (float)sp.uv[2 * (size_t)v + 1]);
        }
        fwrite(rec, 1, (size_t)(q - rec), fp);
    }
    for (int f = 0; f < m->nf; f++) {
        unsigned char *q = rec;
        *q++ = 3;
        for (int k = 0; k < 3; k++) q = put_u32le(q, (uint32_t)sp.tri[3 * (size_t)f + k]);
        fwrite(rec, 1, (size_t)(q - rec), fp);
    }
    seam_split_free(&sp);
    return ferror(fp) ? error_set(NEUV_ERR_IO, "write failed (disk full?)") : NEUV_OK;
}
