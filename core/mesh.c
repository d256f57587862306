/* Mesh processing in object space: area-weighted smooth normals (format.md §6.6) and
 * Loop subdivision (format.md §6.7). All memory comes from the caller's arena; scratch is
 * released before returning, on success and on failure alike. */
#include "mesh.h"
#include "hash.h"

#define NONE UINT32_MAX
/* Valences below this use precomputed weights and cosines. */
#define LOOP_TABLE 16

/* ---- shared helpers ---- */

/* A power of two at least twice n (load factor <= 1/2), or 0 when that overflows. */
static size_t table_size(size_t n)
{
    size_t cap = 16;
    while (cap < n || cap - n < n) {
        if (cap > SIZE_MAX / 2) return 0;
        cap *= 2;
    }
    return cap;
}

static bool mesh_is_valid(const rt_mesh_desc *m)
{
    if (m->vertex_count >= NONE || (m->vertex_count > 0 && !m->positions)) return false;
    if (m->triangle_count > 0 && !m->indices) return false;
    for (size_t i = 0; i < 3 * (size_t)m->triangle_count; i++)
        if (m->indices[i] >= m->vertex_count) return false;
    return true;
}

/* ---- smooth normals ---- */

static bool same_bits(const rt_vec3 *a, const rt_vec3 *b)
{
    const uint8_t *x = (const uint8_t *)a, *y = (const uint8_t *)b;
    for (size_t i = 0; i < sizeof *a; i++)
        if (x[i] != y[i]) return false;
    return true;
}

/* Spread over a power-of-two table. */
static uint64_t hash_bits(const rt_vec3 *p) { return rt_hash_mix(rt_hash_bytes(p, sizeof *p)); }

rt_status rt_mesh_smooth_normals(const rt_mesh_desc *mesh, rt_arena *arena, rt_vec3 **normals_out)
{
    if (!mesh_is_valid(mesh)) return RT_ERR_INVALID;
    size_t mark = rt_arena_mark(arena);
    uint32_t n = mesh->vertex_count;
    rt_vec3 *normals = rt_arena_alloc_array(arena, n, sizeof *normals);
    size_t scratch = rt_arena_mark(arena);
    size_t cap = table_size(n);
    /* rep[v]: the first vertex with v's exact position; slots hold vertex + 1, 0 = empty. */
    uint32_t *rep = rt_arena_alloc_array(arena, n, sizeof *rep);
    rt_vec3 *sum = RT_NEW_ARRAY(arena, rt_vec3, n);
    uint32_t *slots = cap ? RT_NEW_ARRAY(arena, uint32_t, cap) : NULL;
    if (!normals || !rep || !sum || !slots) {
        if (!cap) arena->wanted = SIZE_MAX;
        rt_arena_reset(arena, mark);
        return RT_ERR_NOMEM;
    }
    const rt_vec3 *p = mesh->positions;
    for (uint32_t v = 0; v < n; v++) {
        size_t s = hash_bits(&p[v]) & (cap - 1);
        while (slots[s] != 0 && !same_bits(&p[slots[s] - 1], &p[v])) s = (s + 1) & (cap - 1);
        if (slots[s] == 0) slots[s] = v + 1;
        rep[v] = slots[s] - 1;
    }
    const uint32_t *idx = mesh->indices;
    for (uint32_t t = 0; t < mesh->triangle_count; t++) {
        uint32_t a = idx[3 * t], b = idx[3 * t + 1], c = idx[3 * t + 2];
        rt_vec3 area = rt_v3_cross(rt_v3_sub(p[b], p[a]), rt_v3_sub(p[c], p[a]));
        sum[rep[a]] = rt_v3_add(sum[rep[a]], area);
        sum[rep[b]] = rt_v3_add(sum[rep[b]], area);
        sum[rep[c]] = rt_v3_add(sum[rep[c]], area);
    }
    for (uint32_t v = 0; v < n; v++) normals[v] = rt_v3_normalize(sum[rep[v]]);
    rt_arena_reset(arena, scratch);
    *normals_out = normals;
    return RT_OK;
}

/* ---- Loop subdivision: weights ---- */

typedef struct {
    rt_real beta[LOOP_TABLE];
    rt_real cosine[LOOP_TABLE][LOOP_TABLE]; /* [k][i] = cos(2 pi i / k) */
} loop_table;

static rt_real cos_step(uint32_t i, uint32_t k)
{
    /* The fraction first, so the angle stays within [0, 2 pi) in the fixed-point build too. */
    return rt_cos(rt_mul(rt_mul(RT_C(2.0), RT_PI), rt_div(rt_from_int(i), rt_from_int(k))));
}

static rt_real beta_of(uint32_t k)
{
    rt_real t = rt_add(RT_C(3.0), rt_mul(RT_C(2.0), cos_step(1, k)));
    return rt_sub(RT_C(1.25), rt_div(rt_mul(t, t), RT_C(32.0)));
}

static void loop_table_init(loop_table *w)
{
    for (uint32_t k = 1; k < LOOP_TABLE; k++) {
        w->beta[k] = beta_of(k);
        for (uint32_t i = 0; i < k; i++) w->cosine[k][i] = cos_step(i, k);
    }
}

static rt_real loop_beta(const loop_table *w, uint32_t k) { return k < LOOP_TABLE ? w->beta[k] : beta_of(k); }
static rt_real loop_cos(const loop_table *w, uint32_t i, uint32_t k)
{
    return k < LOOP_TABLE ? w->cosine[k][i] : cos_step(i, k);
}

/* ---- Loop subdivision: topology ---- */

/* The edge from corner c to the next corner of its triangle, as (lower vertex, higher). */
static uint64_t edge_key(const rt_mesh_desc *m, size_t c)
{
    uint32_t a = m->indices[c], b = m->indices[c % 3 == 2 ? c - 2 : c + 1];
    return a < b ? (uint64_t)a << 32 | b : (uint64_t)b << 32 | a;
}

/* Corners ahead of the one being numbered whose slots are fetched. */
#define EDGE_PREFETCH 16

/* Numbers the edges of m in order of first appearance (triangles in order, edges ab bc ca):
 * tri_edge[3t + j] is the edge from corner j to corner j + 1 of triangle t. */
static rt_status number_edges(const rt_mesh_desc *m, uint32_t *tri_edge, rt_arena *arena, uint32_t *edge_count)
{
    size_t mark = rt_arena_mark(arena);
    size_t corners = 3 * (size_t)m->triangle_count, cap = table_size(corners);
    uint32_t *slots = cap ? RT_NEW_ARRAY(arena, uint32_t, cap) : NULL; /* edge + 1, 0 = empty */
    uint64_t *keys = rt_arena_alloc_array(arena, corners, sizeof *keys);
    if (!slots || !keys) {
        if (!cap) arena->wanted = SIZE_MAX;
        rt_arena_reset(arena, mark);
        return RT_ERR_NOMEM;
    }
    uint32_t count = 0;
    for (size_t c = 0; c < corners; c++) {
        /* Slots are random by design: ask for a later corner's slot while this one is probed. */
        if (c + EDGE_PREFETCH < corners)
            __builtin_prefetch(&slots[rt_hash_mix(edge_key(m, c + EDGE_PREFETCH)) & (cap - 1)]);
        uint64_t key = edge_key(m, c);
        size_t s = rt_hash_mix(key) & (cap - 1);
        while (slots[s] != 0 && keys[slots[s] - 1] != key) s = (s + 1) & (cap - 1);
        if (slots[s] == 0) {
            keys[count] = key;
            slots[s] = ++count;
        }
        tri_edge[c] = slots[s] - 1;
    }
    rt_arena_reset(arena, mark);
    *edge_count = count;
    return RT_OK;
}

/* Step 1 of format.md §6.7: every edge gets its midpoint (and midpoint uv) as vertex V + edge;
 * triangle (A,B,C) becomes (A,ab,ca), (B,bc,ab), (C,ca,bc), (ab,bc,ca). */
static void split(const rt_mesh_desc *m, const uint32_t *tri_edge, rt_vec3 *pos, rt_vec2 *uv, uint32_t *idx)
{
    uint32_t nv = m->vertex_count, next = 0;
    for (uint32_t v = 0; v < nv; v++) pos[v] = m->positions[v];
    for (uint32_t v = 0; uv && v < nv; v++) uv[v] = m->uvs[v];
    for (uint32_t t = 0; t < m->triangle_count; t++) {
        const uint32_t *tri = &m->indices[3 * t], *e = &tri_edge[3 * t];
        for (int j = 0; j < 3; j++) {
            if (e[j] != next) continue; /* edges are numbered in this very order: first sight */
            uint32_t a = tri[j], b = tri[(j + 1) % 3];
            pos[nv + next] = rt_v3_scale(rt_v3_add(m->positions[a], m->positions[b]), RT_C(0.5));
            if (uv) {
                rt_vec2 ua = m->uvs[a], ub = m->uvs[b];
                uv[nv + next] = (rt_vec2){rt_mul(rt_add(ua.u, ub.u), RT_C(0.5)), rt_mul(rt_add(ua.v, ub.v), RT_C(0.5))};
            }
            next++;
        }
        uint32_t ab = nv + e[0], bc = nv + e[1], ca = nv + e[2];
        uint32_t *o = &idx[12 * (size_t)t];
        const uint32_t four[12] = {tri[0], ab, ca, tri[1], bc, ab, tri[2], ca, bc, ab, bc, ca};
        for (int i = 0; i < 12; i++) o[i] = four[i];
    }
}

/* What ring_of keeps about a neighbour w of the vertex v whose ring it builds: stamps
 * (v + 1 while v's ring is built, 0 = never) and the chain of v's wedges starting at w.
 * One record per vertex, so a neighbour costs one cache line, not four. */
typedef struct {
    uint32_t seen;      /* w is already in v's ring */
    uint32_t head_mark; /* head below is v's */
    uint32_t head;      /* the last wedge (y, z) of v with y = w, chained by link */
    uint32_t z_mark;    /* w ends a wedge of v */
} ring_vertex;

/* Corners around each vertex (compressed rows) plus the scratch to order them into rings. */
typedef struct {
    const uint32_t *indices;
    uint32_t *offsets; /* corners of v: corners[offsets[v] .. offsets[v + 1]) */
    uint32_t *corners;
    ring_vertex *vertex;
    /* Per corner of the current vertex: the wedge (y, z) of triangle (v, y, z). */
    uint32_t *wy, *wz, *link;
    uint8_t *used;
    uint32_t *ring; /* where ring_of writes */
} ring_builder;

static rt_status ring_builder_init(ring_builder *b, const uint32_t *idx, uint32_t nv, size_t corners, rt_arena *arena)
{
    b->indices = idx;
    b->offsets = RT_NEW_ARRAY(arena, uint32_t, (size_t)nv + 1);
    b->corners = rt_arena_alloc_array(arena, corners, sizeof *b->corners);
    b->vertex = RT_NEW_ARRAY(arena, ring_vertex, nv);
    if (!b->offsets || !b->corners || !b->vertex) return RT_ERR_NOMEM;
    for (size_t c = 0; c < corners; c++) b->offsets[idx[c] + 1]++;
    uint32_t most = 0;
    for (uint32_t v = 0; v < nv; v++) {
        uint32_t m = b->offsets[v + 1];
        if (m > most) most = m;
        b->offsets[v + 1] += b->offsets[v];
    }
    /* Fill by advancing each start to its end, then shift the starts back. */
    for (size_t c = 0; c < corners; c++) b->corners[b->offsets[idx[c]]++] = (uint32_t)c;
    for (uint32_t v = nv; v > 0; v--) b->offsets[v] = b->offsets[v - 1];
    b->offsets[0] = 0;
    b->wy = rt_arena_alloc_array(arena, most, sizeof *b->wy);
    b->wz = rt_arena_alloc_array(arena, most, sizeof *b->wz);
    b->link = rt_arena_alloc_array(arena, most, sizeof *b->link);
    b->used = rt_arena_alloc_array(arena, most, sizeof *b->used);
    return b->wy && b->wz && b->link && b->used ? RT_OK : RT_ERR_NOMEM;
}

static uint32_t ring_append(ring_builder *b, uint32_t v, uint32_t k, uint32_t w)
{
    if (w == v || b->vertex[w].seen == v + 1) return k;
    b->vertex[w].seen = v + 1;
    b->ring[k] = w;
    return k + 1;
}

/* An unused wedge of v starting at y, or NONE. */
static uint32_t ring_take(ring_builder *b, uint32_t v, uint32_t y)
{
    ring_vertex *r = &b->vertex[y];
    if (r->head_mark != v + 1) return NONE;
    uint32_t i = r->head;
    while (i != NONE && b->used[i]) i = b->link[i];
    if (i == NONE) return NONE;
    r->head = b->link[i];
    b->used[i] = 1;
    return i;
}

/* The distinct neighbours of v into b->ring, in order around v: wedges (y, z) are chained
 * z -> next y. A fan that is not closed (boundary, non-manifold, mixed winding) is walked
 * from a wedge whose y ends no other wedge, so an open fan comes out in order from one
 * border to the other; what cannot be chained starts a new run appended after it. */
static uint32_t ring_of(ring_builder *b, uint32_t v)
{
    uint32_t first = b->offsets[v], m = b->offsets[v + 1] - first, stamp = v + 1;
    for (uint32_t i = 0; i < m; i++) {
        uint32_t c = b->corners[first + i], t = c - c % 3;
        uint32_t y = b->indices[t + (c + 1) % 3], z = b->indices[t + (c + 2) % 3];
        b->wy[i] = y;
        b->wz[i] = z;
        b->used[i] = 0;
        ring_vertex *r = &b->vertex[y];
        if (r->head_mark != stamp) r->head = NONE;
        r->head_mark = stamp;
        b->link[i] = r->head;
        r->head = i;
        b->vertex[z].z_mark = stamp;
    }
    uint32_t k = 0, open = 0, any = 0;
    for (;;) {
        while (open < m && (b->used[open] || b->vertex[b->wy[open]].z_mark == stamp)) open++;
        while (any < m && b->used[any]) any++;
        uint32_t s = open < m ? open : any;
        if (s == m) return k;
        b->used[s] = 1;
        k = ring_append(b, v, k, b->wy[s]);
        for (uint32_t i = s; i != NONE; i = ring_take(b, v, b->wz[i])) k = ring_append(b, v, k, b->wz[i]);
    }
}

/* Sum of cross(y - v, z - v) over v's wedges: the fallback normal where the masks give none. */
static rt_vec3 wedge_normal(const ring_builder *b, const rt_vec3 *p, uint32_t v)
{
    rt_vec3 n = rt_v3(RT_ZERO, RT_ZERO, RT_ZERO);
    for (uint32_t i = b->offsets[v]; i < b->offsets[v + 1]; i++) {
        uint32_t c = b->corners[i], t = c - c % 3;
        rt_vec3 y = p[b->indices[t + (c + 1) % 3]], z = p[b->indices[t + (c + 2) % 3]];
        n = rt_v3_add(n, rt_v3_cross(rt_v3_sub(y, p[v]), rt_v3_sub(z, p[v])));
    }
    return rt_v3_normalize(n);
}

/* Every vertex's ring, built once for the averaging and the limit: v's is
 * all[start[v] .. start[v + 1]). */
typedef struct {
    size_t *start;
    uint32_t *all;
} ring_table;

static rt_status ring_table_build(ring_builder *b, uint32_t nv, size_t corners, rt_arena *arena, ring_table *t)
{
    t->start = rt_arena_alloc_array(arena, (size_t)nv + 1, sizeof *t->start);
    /* A corner's wedge adds at most two neighbours (a run's first one and its end). */
    t->all = rt_arena_alloc_array(arena, corners, 2 * sizeof *t->all);
    if (!t->start || !t->all) return RT_ERR_NOMEM;
    size_t k = 0;
    for (uint32_t v = 0; v < nv; v++) {
        t->start[v] = k;
        b->ring = t->all + k;
        k += ring_of(b, v);
    }
    t->start[nv] = k;
    return RT_OK;
}

/* ---- Loop subdivision: one level ---- */

/* Step 2 of format.md §6.7 (from -> to), and on the last level the limit projection (to -> from)
 * and limit normals from the averaged positions. */
static void smooth(const ring_table *t, const loop_table *w, uint32_t nv, const rt_vec3 *from, rt_vec3 *to)
{
    for (uint32_t v = 0; v < nv; v++) {
        const uint32_t *ring = t->all + t->start[v];
        uint32_t k = (uint32_t)(t->start[v + 1] - t->start[v]);
        if (k == 0) {
            to[v] = from[v]; /* a vertex no triangle uses stays put */
            continue;
        }
        rt_vec3 s = rt_v3(RT_ZERO, RT_ZERO, RT_ZERO);
        for (uint32_t i = 0; i < k; i++) s = rt_v3_add(s, from[ring[i]]);
        rt_real kr = rt_from_int(k), beta = loop_beta(w, k);
        rt_real alpha = rt_div(rt_mul(kr, rt_sub(RT_ONE, beta)), beta);
        to[v] = rt_v3_div(rt_v3_add(rt_v3_scale(from[v], alpha), s), rt_add(alpha, kr));
    }
}

static void limit(const ring_builder *b, const ring_table *t, const loop_table *w, uint32_t nv, const rt_vec3 *q,
                  rt_vec3 *pos, rt_vec3 *normals)
{
    for (uint32_t v = 0; v < nv; v++) {
        const uint32_t *ring = t->all + t->start[v];
        uint32_t k = (uint32_t)(t->start[v + 1] - t->start[v]);
        rt_vec3 s = rt_v3(RT_ZERO, RT_ZERO, RT_ZERO), t1 = s, t2 = s;
        for (uint32_t i = 0; i < k; i++) {
            rt_vec3 n = q[ring[i]];
            s = rt_v3_add(s, n);
            t1 = rt_v3_add(t1, rt_v3_scale(n, loop_cos(w, i, k)));
            t2 = rt_v3_add(t2, rt_v3_scale(n, loop_cos(w, (i + k - 1) % k, k)));
        }
        if (k == 0) {
            pos[v] = q[v];
            normals[v] = s;
            continue;
        }
        rt_real kr = rt_from_int(k), eps = rt_div(rt_mul(RT_C(3.0), kr), loop_beta(w, k));
        pos[v] = rt_v3_div(rt_v3_add(rt_v3_scale(q[v], eps), s), rt_add(eps, kr));
        rt_vec3 n = rt_v3_cross(t1, t2);
        /* Valence 2 (a corner of a lone triangle) makes t2 = -t1. */
        normals[v] = rt_v3_is_zero(n) ? wedge_normal(b, q, v) : rt_v3_normalize(n);
    }
}

/* One split + average; the last level also projects to the limit and sets normals. The
 * outputs (indices, uvs, positions, normals) are allocated in that order, contiguously,
 * after tri_edge and before all scratch, so the caller can slide them down. */
static rt_status subdivide_once(const rt_mesh_desc *in, bool last, const loop_table *w, rt_arena *arena,
                                rt_mesh_desc *out)
{
    /* 3 * 4T indices and V + E vertices (E <= 3T) must stay below NONE. */
    if (in->triangle_count > NONE / 12 || (uint64_t)in->vertex_count + 3 * (uint64_t)in->triangle_count >= NONE) {
        arena->wanted = SIZE_MAX;
        return RT_ERR_NOMEM;
    }
    uint32_t *tri_edge = rt_arena_alloc_array(arena, 3 * (size_t)in->triangle_count, sizeof *tri_edge);
    uint32_t edges;
    if (!tri_edge) return RT_ERR_NOMEM;
    rt_status st = number_edges(in, tri_edge, arena, &edges);
    if (st != RT_OK) return st;
    uint32_t nv = in->vertex_count + edges, nt = 4 * in->triangle_count;
    uint32_t *idx = rt_arena_alloc_array(arena, 3 * (size_t)nt, sizeof *idx);
    rt_vec2 *uv = in->uvs ? rt_arena_alloc_array(arena, nv, sizeof *uv) : NULL;
    rt_vec3 *pos = rt_arena_alloc_array(arena, nv, sizeof *pos);
    rt_vec3 *normals = last ? rt_arena_alloc_array(arena, nv, sizeof *normals) : NULL;
    rt_vec3 *other = rt_arena_alloc_array(arena, nv, sizeof *other);
    if (!idx || (in->uvs && !uv) || !pos || (last && !normals) || !other) return RT_ERR_NOMEM;
    /* Intermediate levels: split into scratch, average into the output. The last level:
     * split into the output, average into scratch, project back into the output. */
    split(in, tri_edge, last ? pos : other, uv, idx);
    ring_builder b;
    ring_table rings;
    st = ring_builder_init(&b, idx, nv, 3 * (size_t)nt, arena);
    if (st == RT_OK) st = ring_table_build(&b, nv, 3 * (size_t)nt, arena, &rings);
    if (st != RT_OK) return st;
    if (last) {
        smooth(&rings, w, nv, pos, other);
        limit(&b, &rings, w, nv, other, pos, normals);
    } else {
        smooth(&rings, w, nv, other, pos);
    }
    *out = (rt_mesh_desc){pos, normals, uv, nv, idx, nt};
    return RT_OK;
}

/* Releases everything since mark but m's arrays, which move down to mark in allocation order. */
static void keep_only(rt_arena *arena, size_t mark, rt_mesh_desc *m)
{
    rt_arena_reset(arena, mark);
    m->indices = rt_arena_keep(arena, m->indices, 3 * (size_t)m->triangle_count * sizeof *m->indices);
    if (m->uvs) m->uvs = rt_arena_keep(arena, m->uvs, m->vertex_count * sizeof *m->uvs);
    m->positions = rt_arena_keep(arena, m->positions, m->vertex_count * sizeof *m->positions);
    if (m->normals) m->normals = rt_arena_keep(arena, m->normals, m->vertex_count * sizeof *m->normals);
}

rt_status rt_mesh_subdivide(const rt_mesh_desc *mesh, uint32_t levels, rt_arena *arena, rt_mesh_desc *out)
{
    if (levels < 1 || levels > RT_MAX_SUBDIVISION || !mesh_is_valid(mesh)) return RT_ERR_INVALID;
    loop_table w;
    loop_table_init(&w);
    size_t mark = rt_arena_mark(arena);
    rt_mesh_desc m = *mesh;
    m.normals = NULL; /* input normals are not carried through (format.md §6.7) */
    for (uint32_t level = 1; level <= levels; level++) {
        rt_mesh_desc next;
        rt_status st = subdivide_once(&m, level == levels, &w, arena, &next);
        if (st != RT_OK) {
            rt_arena_reset(arena, mark);
            return st;
        }
        keep_only(arena, mark, &next);
        m = next;
    }
    *out = m;
    return RT_OK;
}
