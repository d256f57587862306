/* Vertex welding: the course's mesh importer joins vertices whose attributes are
 * identical, so a file that repeats a corner per face (sculpt.ply: 31059 vertices for
 * 10353 faces) becomes one connected surface. Loop subdivision finds neighbours by
 * index (format.md §6.7) and needs that; rendering at level 0 is unchanged. */
#include "load/ply_weld.h"

#include "hash.h"
#include "mem/mem.h"
#include <string.h>

/* The attributes that must all be equal, bit for bit, for two vertices to merge. */
typedef struct {
    rt_vec3 position, normal;
    rt_vec2 uv;
} vertex_key;

static vertex_key key_of(const rtp_ply_mesh *m, uint32_t v)
{
    vertex_key k;
    memset(&k, 0, sizeof k); /* padding, if any, must compare equal */
    k.position = m->positions[v];
    if (m->normals) k.normal = m->normals[v];
    if (m->uvs) k.uv = m->uvs[v];
    return k;
}

static uint64_t hash_of(const vertex_key *k) { return rt_hash_bytes(k, sizeof *k); }

bool rtp_ply_weld(rtp_ply_mesh *m)
{
    size_t slots = 1;
    while (slots < (size_t)m->vertex_count * 2) slots <<= 1;
    /* new vertex index + 1, 0 = empty */
    uint32_t *table = rtp_mem_calloc(slots, sizeof *table, "the vertex welding table");
    uint32_t *remap =
        table ? rtp_mem_alloc((m->vertex_count ? m->vertex_count : 1) * sizeof *remap, "the vertex welding table")
              : NULL;
    if (!remap) {
        rtp_mem_free(table);
        return false;
    }
    uint32_t kept = 0;
    for (uint32_t v = 0; v < m->vertex_count; v++) {
        vertex_key k = key_of(m, v);
        size_t s = (size_t)hash_of(&k) & (slots - 1);
        for (; table[s]; s = (s + 1) & (slots - 1)) {
            vertex_key other = key_of(m, table[s] - 1);
            if (memcmp(&k, &other, sizeof k) == 0) break;
        }
        if (!table[s]) {
            /* First occurrence: keep it, moved down to the next free place (order kept). */
            m->positions[kept] = m->positions[v];
            if (m->normals) m->normals[kept] = m->normals[v];
            if (m->uvs) m->uvs[kept] = m->uvs[v];
            table[s] = ++kept;
        }
        remap[v] = table[s] - 1;
    }
    for (uint64_t i = 0; i < (uint64_t)m->triangle_count * 3; i++) m->indices[i] = remap[m->indices[i]];
    m->vertex_count = kept;
    rtp_mem_free(table);
    rtp_mem_free(remap);
    return true;
}
