#include "mesh/clean.h"
#include "mesh/mesh_attributes.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "core/error.h"
#include "core/log.h"
#include "core/mem.h"
#include "core/union_find.h"
#include "mesh/edge_faces.h"

/* splitmix64 finalizer: spreads nearby bit patterns over the table. */
static uint64_t mix64(uint64_t k)
{
    k ^= k >> 30; k *= 0xbf58476d1ce4e5b9ULL;
    k ^= k >> 27; k *= 0x94d049bb133111ebULL;
    return k ^ (k >> 31);
}

static uint64_t double_bits(double x)
{
    x += 0.0; /* -0.0 becomes +0.0 so both hash alike, as they compare equal */
    uint64_t b;
    memcpy(&b, &x, sizeof b);
    return b;
}

static size_t table_size(size_t n)
{
    size_t cap = 16;
    while (cap < 2 * n + 2) cap <<= 1;
    return cap;
}

/* Welds exactly equal positions. rep (may be NULL, #V) receives for each
 * new vertex the input vertex it came from. Returns the number removed, -1 on OOM. */
static int weld(neuv_mesh *m, int *rep)
{
    size_t cap = table_size((size_t)m->nv);
    int *table = mem_alloc(sizeof(int) * cap);
    int *remap = mem_alloc(sizeof(int) * (size_t)(m->nv > 0 ? m->nv : 1));
    if (!table || !remap) { mem_free(table); mem_free(remap); return -1; }
    for (size_t i = 0; i < cap; i++) table[i] = -1;
    int n = 0;
    for (int v = 0; v < m->nv; v++) {
        const double *p = m->pos + 3 * v;
        uint64_t h = mix64(double_bits(p[0]) ^ mix64(double_bits(p[1]) ^ mix64(double_bits(p[2]))));
        size_t i = (size_t)h & (cap - 1);
        for (;; i = (i + 1) & (cap - 1)) {
            int u = table[i];
            if (u < 0) {
                table[i] = v;
                remap[v] = n;
                /* remap[v] <= v, so compacting in place never overwrites a later vertex. */
                memmove(m->pos + 3 * n, p, sizeof(double) * 3);
                if (rep) rep[n] = v;
                n++;
                break;
            }
            /* Compares against the compacted copy of u, which holds u's position. */
            const double *q = m->pos + 3 * remap[u];
            if (q[0] == p[0] && q[1] == p[1] && q[2] == p[2]) { remap[v] = remap[u]; break; }
        }
    }
    for (size_t c = 0; c < (size_t)m->nf * 3; c++) m->tri[c] = remap[m->tri[c]];
    int removed = m->nv - n;
    m->nv = n;
    mem_free(table); mem_free(remap);
    return removed;
}

int mesh_weld_positions(neuv_mesh *m)
{
    int n = weld(m, NULL);
    /* Faces are kept, so polygons and face values stay; per-vertex values
     * of merged vertices cannot, so none is kept. */
    if (n > 0 && m->attr) {
        mem_free(m->attr->color);
        m->attr->color = NULL;
        m->attr->color_channels = 0;
        ply_extra_free(&m->attr->ply_vertex);
    }
    return n;
}

/* Keeps the faces with keep[f] != 0, in order, with their UV corners. */
static void keep_faces(neuv_mesh *m, const unsigned char *keep)
{
    int n = 0;
    for (int f = 0; f < m->nf; f++) {
        if (!keep[f]) continue;
        memmove(m->tri + 3 * n, m->tri + 3 * f, sizeof(int) * 3);
        if (m->tri_uv) memmove(m->tri_uv + 3 * n, m->tri_uv + 3 * f, sizeof(int) * 3);
        n++;
    }
    m->nf = n;
}

static int is_degenerate(const neuv_mesh *m, int f)
{
    const int *t = m->tri + 3 * f;
    if (t[0] == t[1] || t[1] == t[2] || t[2] == t[0]) return 1;
    const double *a = m->pos + 3 * t[0], *b = m->pos + 3 * t[1], *c = m->pos + 3 * t[2];
    double e[3][3], len2 = 0;
    for (int k = 0; k < 3; k++) {
        e[0][k] = b[k] - a[k]; e[1][k] = c[k] - b[k]; e[2][k] = a[k] - c[k];
    }
    for (int i = 0; i < 3; i++) {
        double l = e[i][0] * e[i][0] + e[i][1] * e[i][1] + e[i][2] * e[i][2];
        if (l > len2) len2 = l;
    }
    double x = e[0][1] * e[2][2] - e[0][2] * e[2][1];
    double y = e[0][2] * e[2][0] - e[0][0] * e[2][2];
    double z = e[0][0] * e[2][1] - e[0][1] * e[2][0];
    double cross = sqrt(x * x + y * y + z * z);
    /* Relative test: a sliver whose sine of angle is at rounding level is flat. */
    return !(cross > 1e-14 * len2);
}

static void sort3(const int *t, int s[3])
{
    s[0] = t[0]; s[1] = t[1]; s[2] = t[2];
    if (s[0] > s[1]) { int x = s[0]; s[0] = s[1]; s[1] = x; }
    if (s[1] > s[2]) { int x = s[1]; s[1] = s[2]; s[2] = x; }
    if (s[0] > s[1]) { int x = s[0]; s[0] = s[1]; s[1] = x; }
}

/* Drops degenerate faces, then faces whose vertex set repeats an earlier
 * face's. Returns 0, -1 on OOM. */
static int drop_bad_faces(neuv_mesh *m, mesh_clean_report *r)
{
    unsigned char *keep = mem_alloc((size_t)(m->nf > 0 ? m->nf : 1));
    size_t cap = table_size((size_t)m->nf);
    int *table = mem_alloc(sizeof(int) * cap);
    if (!keep || !table) { mem_free(keep); mem_free(table); return -1; }
    for (size_t i = 0; i < cap; i++) table[i] = -1;
    for (int f = 0; f < m->nf; f++) {
        keep[f] = !is_degenerate(m, f);
        if (!keep[f]) { r->degenerate_faces++; continue; }
        int s[3];
        sort3(m->tri + 3 * f, s);
        uint64_t h = mix64((uint64_t)(uint32_t)s[0] ^ mix64(((uint64_t)(uint32_t)s[1] << 32) ^ (uint32_t)s[2]));
        for (size_t i = (size_t)h & (cap - 1);; i = (i + 1) & (cap - 1)) {
            if (table[i] < 0) { table[i] = f; break; }
            int o[3];
            sort3(m->tri + 3 * table[i], o);
            if (o[0] == s[0] && o[1] == s[1] && o[2] == s[2]) { keep[f] = 0; r->duplicate_faces++; break; }
        }
    }
    keep_faces(m, keep);
    mem_free(keep); mem_free(table);
    return 0;
}

/* Corner of face f at vertex v. */
static int corner_at(const neuv_mesh *m, int f, int v)
{
    for (int k = 0; k < 3; k++)
        if (m->tri[3 * f + k] == v) return 3 * f + k;
    return -1;
}

/* The two sides of edge e that stay attached: the first face and the first
 * later face that runs along the edge the other way (so the pair can be
 * oriented consistently), else the second face. */
static void kept_pair(const neuv_mesh *m, const edge_faces *t, int e, int *s0, int *s1)
{
    int b = t->start[e], n = edge_faces_count(t, e);
    *s0 = t->side[b];
    *s1 = t->side[b + 1];
    for (int i = 1; i < n; i++) {
        int s = t->side[b + i];
        if (m->tri[s] != m->tri[*s0]) { *s1 = s; return; }
    }
}

/* Joins the corners of two faces across the edge they share, at both ends. */
static void join_sides(union_find *u, const neuv_mesh *m, int s0, int s1)
{
    int f = s0 / 3, g = s1 / 3;
    int a = m->tri[s0], b = m->tri[3 * f + (s0 % 3 + 1) % 3];
    uf_union(u, corner_at(m, f, a), corner_at(m, g, a));
    uf_union(u, corner_at(m, f, b), corner_at(m, g, b));
}

/* One round of splitting. Corners are grouped into fans (joined across
 * manifold edges and the kept pair of each non-manifold edge); every fan
 * of a vertex after its first gets a copy of the vertex. With `isolate`,
 * faces detached from a non-manifold edge are cut from all their
 * neighbours (the fallback when a first round could not separate them).
 * Returns the number of non-manifold edges seen, -1 on OOM, -2 when
 * refusing (refuse != 0) with the error set. */
static int split_round(neuv_mesh *m, int isolate, int count_vertices, int refuse, const int *rep,
                       mesh_clean_report *r)
{
    edge_faces t;
    if (edge_faces_build(&t, m) != 0) return -1;
    int nc = 3 * m->nf, nm_edges = 0;
    for (int e = 0; e < t.ne; e++) {
        if (edge_faces_count(&t, e) <= 2) continue;
        if (refuse) {
            int a = t.edge_v[2 * e], b = t.edge_v[2 * e + 1], n = edge_faces_count(&t, e);
            edge_faces_free(&t);
            error_set(NEUV_ERR_INPUT, "non-manifold edge between vertices %d and %d (%d faces)",
                      rep ? rep[a] : a, rep ? rep[b] : b, n);
            return -2;
        }
        nm_edges++;
    }
    if (isolate && nm_edges == 0) { edge_faces_free(&t); return 0; }
    union_find fan, all;
    unsigned char *isolated = mem_calloc((size_t)m->nf + 1, 1);
    int *first_root = mem_alloc(sizeof(int) * (size_t)(m->nv > 0 ? m->nv : 1));
    if (!isolated || !first_root || uf_init(&fan, nc) != 0) {
        mem_free(isolated); mem_free(first_root); edge_faces_free(&t);
        return -1;
    }
    /* Without non-manifold edges the fans are the same either way. */
    int separate_all = count_vertices && nm_edges > 0;
    if (uf_init(&all, separate_all ? nc : 0) != 0) {
        mem_free(isolated); mem_free(first_root); uf_free(&fan); edge_faces_free(&t);
        return -1;
    }
    if (isolate)
        for (int e = 0; e < t.ne; e++) {
            if (edge_faces_count(&t, e) <= 2) continue;
            int s0, s1;
            kept_pair(m, &t, e, &s0, &s1);
            for (int i = t.start[e]; i < t.start[e + 1]; i++)
                if (t.side[i] != s0 && t.side[i] != s1) isolated[t.side[i] / 3] = 1;
        }
    for (int e = 0; e < t.ne; e++) {
        int n = edge_faces_count(&t, e), b = t.start[e];
        if (n < 2) continue;
        int s0 = t.side[b], s1 = t.side[b + 1];
        if (n > 2) kept_pair(m, &t, e, &s0, &s1);
        if (!isolated[s0 / 3] && !isolated[s1 / 3]) join_sides(&fan, m, s0, s1);
        /* `all` ignores the cut, so it tells bow-tie vertices from the
         * ends of a non-manifold edge. */
        if (separate_all)
            for (int i = 1; i < n; i++) join_sides(&all, m, t.side[b], t.side[b + i]);
    }
    edge_faces_free(&t);

    if (count_vertices) {
        for (int v = 0; v < m->nv; v++) first_root[v] = -1;
        int bowties = 0;
        for (int c = 0; c < nc; c++) {
            int v = m->tri[c], root = uf_find(separate_all ? &all : &fan, c);
            if (first_root[v] == -1) first_root[v] = root;
            else if (first_root[v] >= 0 && first_root[v] != root) {
                if (refuse) {
                    mem_free(isolated); mem_free(first_root); uf_free(&fan); uf_free(&all);
                    error_set(NEUV_ERR_INPUT, "non-manifold vertex %d (its faces form more than one fan)",
                              rep ? rep[v] : v);
                    return -2;
                }
                first_root[v] = -2; /* counted */
                bowties++;
            }
        }
        r->nonmanifold_vertices += bowties;
    }
    uf_free(&all);

    /* A fan's vertex: the original for the first fan met in corner order,
     * a new copy for every later one. */
    int *fan_vertex = mem_alloc(sizeof(int) * (size_t)(nc > 0 ? nc : 1));
    int *source = mem_alloc(sizeof(int) * (size_t)(nc > 0 ? nc : 1));
    unsigned char *claimed = mem_calloc((size_t)m->nv + 1, 1);
    if (!fan_vertex || !source || !claimed) {
        mem_free(fan_vertex); mem_free(source); mem_free(claimed); mem_free(isolated); mem_free(first_root); uf_free(&fan);
        return -1;
    }
    int added = 0;
    for (int c = 0; c < nc; c++) fan_vertex[c] = -1;
    for (int c = 0; c < nc; c++) {
        int root = uf_find(&fan, c), v = m->tri[c];
        if (fan_vertex[root] < 0) {
            if (!claimed[v]) { claimed[v] = 1; fan_vertex[root] = v; }
            else { source[added] = v; fan_vertex[root] = m->nv + added++; }
        }
        m->tri[c] = fan_vertex[root];
    }
    int status = nm_edges;
    if (added > 0) {
        double *pos = mem_realloc(m->pos, sizeof(double) * 3 * (size_t)(m->nv + added));
        if (!pos) status = -1;
        else {
            m->pos = pos;
            for (int i = 0; i < added; i++) memcpy(pos + 3 * (m->nv + i), pos + 3 * source[i], sizeof(double) * 3);
            m->nv += added;
            r->split_vertices += added;
        }
    }
    mem_free(fan_vertex); mem_free(source); mem_free(claimed); mem_free(isolated); mem_free(first_root); uf_free(&fan);
    return status;
}

/* Removes vertices no face uses, keeping the order of the rest. Returns 0, -1 on OOM. */
static int drop_unreferenced(neuv_mesh *m, mesh_clean_report *r)
{
    int *remap = mem_alloc(sizeof(int) * (size_t)(m->nv > 0 ? m->nv : 1));
    if (!remap) return -1;
    for (int v = 0; v < m->nv; v++) remap[v] = -1;
    for (int c = 0; c < 3 * m->nf; c++) remap[m->tri[c]] = 0;
    int n = 0;
    for (int v = 0; v < m->nv; v++) {
        if (remap[v] < 0) continue;
        remap[v] = n;
        memmove(m->pos + 3 * n, m->pos + 3 * v, sizeof(double) * 3);
        n++;
    }
    for (int c = 0; c < 3 * m->nf; c++) m->tri[c] = remap[m->tri[c]];
    r->unreferenced_vertices += m->nv - n;
    m->nv = n;
    mem_free(remap);
    return 0;
}

static void flip_face(neuv_mesh *m, int f)
{
    int x = m->tri[3 * f + 1]; m->tri[3 * f + 1] = m->tri[3 * f + 2]; m->tri[3 * f + 2] = x;
    if (m->tri_uv) {
        x = m->tri_uv[3 * f + 1]; m->tri_uv[3 * f + 1] = m->tri_uv[3 * f + 2]; m->tri_uv[3 * f + 2] = x;
    }
}

static double det3(const double *o, const double *pa, const double *pb, const double *pc)
{
    double a[3] = {pa[0] - o[0], pa[1] - o[1], pa[2] - o[2]};
    double b[3] = {pb[0] - o[0], pb[1] - o[1], pb[2] - o[2]};
    double c[3] = {pc[0] - o[0], pc[1] - o[1], pc[2] - o[2]};
    return a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) +
           a[2] * (b[0] * c[1] - b[1] * c[0]);
}

/* Breadth-first search over each component: a neighbour across a shared
 * edge must run along it the other way, which fixes each face's flip bit
 * relative to the component's first face. Returns 0, -1 on OOM. */
static int orient(neuv_mesh *m, mesh_clean_report *r)
{
    edge_faces t;
    if (edge_faces_build(&t, m) != 0) return -1;
    signed char *flip = mem_alloc((size_t)m->nf + 1);
    int *queue = mem_alloc(sizeof(int) * ((size_t)m->nf + 1));
    if (!flip || !queue) { mem_free(flip); mem_free(queue); edge_faces_free(&t); return -1; }
    memset(flip, -1, (size_t)m->nf + 1);
    for (int seed = 0; seed < m->nf; seed++) {
        if (flip[seed] >= 0) continue;
        int head = 0, tail = 0, closed = 1, orientable = 1;
        flip[seed] = 0;
        queue[tail++] = seed;
        while (head < tail) {
            int f = queue[head++];
            for (int k = 0; k < 3; k++) {
                int e = t.face_edge[3 * f + k];
                if (edge_faces_count(&t, e) != 2) { closed = 0; continue; }
                int s = t.side[t.start[e]] == 3 * f + k ? t.side[t.start[e] + 1] : t.side[t.start[e]];
                int g = s / 3;
                int same_direction = m->tri[s] == m->tri[3 * f + k];
                int want = flip[f] ^ same_direction;
                if (flip[g] < 0) { flip[g] = (signed char)want; queue[tail++] = g; }
                else if (flip[g] != want) orientable = 0;
            }
        }
        if (!orientable) {
            r->nonorientable_components++;
            log_message(NEUV_LOG_WARN, "component with face %d is non-orientable; left as it is", seed);
            continue;
        }
        int invert = 0;
        if (closed) {
            /* Outward normals enclose a positive volume (divergence theorem). */
            const double *o = m->pos + 3 * m->tri[3 * seed];
            double vol = 0;
            for (int i = 0; i < tail; i++) {
                const int *tri = m->tri + 3 * queue[i];
                double d = det3(o, m->pos + 3 * tri[0], m->pos + 3 * tri[1], m->pos + 3 * tri[2]);
                vol += flip[queue[i]] ? -d : d;
            }
            invert = vol < 0;
        } else {
            /* No inside to point away from: keep most faces as they were. */
            int flipped = 0;
            for (int i = 0; i < tail; i++) flipped += flip[queue[i]];
            invert = 2 * flipped > tail;
        }
        for (int i = 0; i < tail; i++)
            if (flip[queue[i]] ^ invert) { flip_face(m, queue[i]); r->flipped_faces++; }
    }
    mem_free(flip); mem_free(queue); edge_faces_free(&t);
    return 0;
}

static neuv_status validate(const neuv_mesh *m)
{
    for (int c = 0; c < 3 * m->nf; c++)
        if (m->tri[c] < 0 || m->tri[c] >= m->nv)
            return error_set(NEUV_ERR_INPUT, "face %d uses vertex %d, but there are only %d vertices",
                             c / 3, m->tri[c], m->nv);
    if (m->tri_uv)
        for (int c = 0; c < 3 * m->nf; c++)
            if (m->tri_uv[c] < 0 || m->tri_uv[c] >= m->nuv)
                return error_set(NEUV_ERR_INPUT, "face %d uses UV %d, but there are only %d UVs",
                                 c / 3, m->tri_uv[c], m->nuv);
    return NEUV_OK;
}

neuv_status mesh_clean(neuv_mesh *m, const mesh_clean_options *opts, mesh_clean_report *report)
{
    mesh_clean_report local;
    mesh_clean_report *r = report ? report : &local;
    memset(r, 0, sizeof *r);
    int split = opts ? opts->split_nonmanifold : 1;
    neuv_status st = validate(m);
    if (st != NEUV_OK) return st;

    /* Work on a copy so that m is untouched when we refuse or run out of memory.
     * The file's normals, materials, polygons and attributes are not carried through the repairs:
     * a cleaned mesh has none (the seams they mark are found on the input,
     * unwrap/unwrap_seams.c). */
    neuv_mesh *w = mesh_clone(m);
    int *rep = mem_alloc(sizeof(int) * (size_t)(m->nv > 0 ? m->nv : 1));
    if (!w || !rep) { mesh_free(w); mem_free(rep); return error_nomem("mesh copy"); }
    mesh_set_normals(w, 0, NULL, NULL);
    mesh_set_face_material(w, NULL);

    st = NEUV_OK;
    int welded = weld(w, rep);
    if (welded < 0) st = error_nomem("vertex weld table");
    else r->welded_vertices = welded;
    if (st == NEUV_OK && drop_bad_faces(w, r) != 0) st = error_nomem("face table");
    /* The first round splits fans at non-manifold edges and bow-ties; a
     * later round only runs when an edge is still shared by more than two
     * faces (the detached face reached both ends through other faces) and
     * then cuts such faces loose entirely. */
    for (int round = 0; round < 3 && st == NEUV_OK; round++) {
        int n = split_round(w, round > 0, round == 0, !split, round == 0 ? rep : NULL, r);
        if (n == -2) st = NEUV_ERR_INPUT;
        else if (n < 0) st = error_nomem("non-manifold split");
        else {
            if (round == 0) r->nonmanifold_edges = n;
            if (n == 0) break;
        }
    }
    if (st == NEUV_OK && drop_unreferenced(w, r) != 0) st = error_nomem("vertex table");
    if (st == NEUV_OK && orient(w, r) != 0) st = error_nomem("orientation");
    mem_free(rep);
    if (st != NEUV_OK) { mesh_free(w); return st; }

    /* Move the cleaned arrays into m (UV coordinates are unchanged). */
    mem_free(m->pos); mem_free(m->tri); mem_free(m->tri_uv);
    m->pos = w->pos; m->tri = w->tri; m->tri_uv = w->tri_uv;
    m->nv = w->nv; m->nf = w->nf;
    w->pos = NULL; w->tri = NULL; w->tri_uv = NULL;
    mesh_free(w);
    mesh_set_normals(m, 0, NULL, NULL);
    mesh_set_face_material(m, NULL);
    mesh_drop_file_structure(m);
    return NEUV_OK;
}
