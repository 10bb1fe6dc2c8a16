/* What a cleaned mesh is made of: its
 * components with their topology, and the repairs (`neuv info`). */
#include <string.h>

#include "neuv/neuv.h"
#include "api/api_json.h"
#include "core/error.h"
#include "core/log.h"
#include "core/mem.h"
#include "mesh/clean.h"
#include "mesh/topology.h"

/* Topology of every component of the cleaned mesh m, faces grouped by
 * component first (counting sort) so that each costs time linear in its
 * size. */
static neuv_status components_of(const neuv_mesh *m, neuv_component **out, int *count)
{
    int *label = mem_alloc(sizeof(int) * (size_t)(m->nf > 0 ? m->nf : 1));
    int ncomp = label ? mesh_face_components(m, label) : -1;
    int *start = ncomp >= 0 ? mem_calloc((size_t)ncomp + 2, sizeof(int)) : NULL;
    int *faces = mem_alloc(sizeof(int) * (size_t)(m->nf > 0 ? m->nf : 1));
    neuv_component *comp = ncomp >= 0 ? mem_calloc((size_t)ncomp + 1, sizeof *comp) : NULL;
    neuv_status s = NEUV_OK;
    if (!label || ncomp < 0 || !start || !faces || !comp) {
        s = error_set(NEUV_ERR_NOMEM, "out of memory computing components");
    } else {
        for (int f = 0; f < m->nf; f++) start[label[f] + 2]++;
        for (int c = 0; c < ncomp; c++) start[c + 2] += start[c + 1];
        for (int f = 0; f < m->nf; f++) faces[start[label[f] + 1]++] = f;
        for (int c = 0; c < ncomp && s == NEUV_OK; c++) {
            component_topology ct;
            s = mesh_faces_topology(m, faces + start[c], start[c + 1] - start[c], &ct);
            if (s != NEUV_OK) break;
            comp[c].faces = ct.faces;
            comp[c].vertices = ct.vertices;
            comp[c].edges = ct.edges;
            comp[c].boundary_loops = ct.boundary_loops;
            comp[c].genus = ct.genus;
            comp[c].euler = ct.euler;
            comp[c].closed = ct.closed;
        }
    }
    mem_free(label);
    mem_free(start);
    mem_free(faces);
    if (s != NEUV_OK) { mem_free(comp); return s; }
    *out = comp;
    *count = ncomp;
    return NEUV_OK;
}

neuv_status neuv_mesh_topology(const neuv_mesh *mesh, const neuv_callbacks *cb, neuv_topology *out)
{
    if (!out) return error_set(NEUV_ERR_INPUT, "neuv_mesh_topology: no output");
    memset(out, 0, sizeof *out);
    if (!mesh) return error_set(NEUV_ERR_INPUT, "neuv_mesh_topology: no mesh");
    neuv_mesh *m = mesh_clone(mesh);
    if (!m) return error_nomem("the mesh");
    log_scope scope;
    log_scope_open(&scope, cb);
    mesh_clean_report rep;
    neuv_status s = mesh_clean(m, NULL, &rep);
    log_scope_close(&scope);
    neuv_component *comp = NULL;
    int n = 0;
    if (s == NEUV_OK) s = components_of(m, &comp, &n);
    if (s == NEUV_OK) {
        out->input_vertices = mesh->nv;
        out->input_faces = mesh->nf;
        out->vertices = m->nv;
        out->faces = m->nf;
        out->has_uv = m->nuv > 0;
        memcpy(&out->repairs, &rep, sizeof out->repairs);
        out->component_count = n;
        out->components = comp;
    }
    mesh_free(m);
    return s;
}

typedef struct repair_field { const char *key; int value; } repair_field;

char *neuv_topology_json(const neuv_topology *t, const char *input_name)
{
    if (!t) { error_set(NEUV_ERR_INPUT, "neuv_topology_json: no topology"); return NULL; }
    const neuv_clean_report *r = &t->repairs;
    const repair_field f[] = {
        {"welded_vertices", r->welded_vertices},
        {"degenerate_faces", r->degenerate_faces},
        {"duplicate_faces", r->duplicate_faces},
        {"unreferenced_vertices", r->unreferenced_vertices},
        {"flipped_faces", r->flipped_faces},
        {"nonmanifold_edges", r->nonmanifold_edges},
        {"nonmanifold_vertices", r->nonmanifold_vertices},
        {"split_vertices", r->split_vertices},
        {"nonorientable_components", r->nonorientable_components},
    };
    json_writer w;
    json_init(&w);
    json_begin_object(&w);
    json_key(&w, "version"); json_string(&w, neuv_version());
    json_key(&w, "input"); json_string(&w, input_name ? input_name : "");
    json_key(&w, "input_vertices"); json_int(&w, t->input_vertices);
    json_key(&w, "input_faces"); json_int(&w, t->input_faces);
    json_key(&w, "vertices"); json_int(&w, t->vertices);
    json_key(&w, "faces"); json_int(&w, t->faces);
    json_key(&w, "has_uv"); json_bool(&w, t->has_uv);
    json_key(&w, "components");
    json_begin_array(&w);
    for (int c = 0; c < t->component_count && t->components; c++) {
        const neuv_component *ct = &t->components[c];
        json_begin_object(&w);
        json_key(&w, "faces"); json_int(&w, ct->faces);
        json_key(&w, "vertices"); json_int(&w, ct->vertices);
        json_key(&w, "edges"); json_int(&w, ct->edges);
        json_key(&w, "boundary_loops"); json_int(&w, ct->boundary_loops);
        json_key(&w, "genus"); json_int(&w, ct->genus);
        json_key(&w, "euler"); json_int(&w, ct->euler);
        json_key(&w, "closed"); json_bool(&w, ct->closed);
        json_end_object(&w);
    }
    json_end_array(&w);
    json_key(&w, "repairs");
    json_begin_object(&w);
    for (size_t i = 0; i < sizeof f / sizeof f[0]; i++) { json_key(&w, f[i].key); json_int(&w, f[i].value); }
    json_end_object(&w);
    json_end_object(&w);
    return api_json_finish(&w);
}
