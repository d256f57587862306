/* Open-addressing hash table of keys to indices (see name_index.h). */
#include "load/name_index.h"

#include "mem/mem.h"
#include <string.h>

/* FNV-1a. */
static uint64_t hash_of(const void *key, size_t length)
{
    const uint8_t *p = key;
    uint64_t h = 14695981039346656037ull;
    for (size_t i = 0; i < length; i++) h = (h ^ p[i]) * 1099511628211ull;
    return h;
}

static rtp_name_slot *slot_of(const rtp_name_index *ix, const void *key, size_t length)
{
    size_t mask = ix->capacity - 1, s = (size_t)hash_of(key, length) & mask;
    while (ix->slots[s].key && !(ix->slots[s].length == length && memcmp(ix->slots[s].key, key, length) == 0))
        s = (s + 1) & mask;
    return &ix->slots[s];
}

static bool grow(rtp_name_index *ix)
{
    size_t capacity = ix->capacity ? ix->capacity * 2 : 64;
    rtp_name_index bigger = {rtp_mem_calloc(capacity, sizeof(rtp_name_slot), "the name index"), capacity, ix->count};
    if (!bigger.slots) return false;
    for (size_t i = 0; i < ix->capacity; i++)
        if (ix->slots[i].key) *slot_of(&bigger, ix->slots[i].key, ix->slots[i].length) = ix->slots[i];
    rtp_mem_free(ix->slots);
    *ix = bigger;
    return true;
}

bool rtp_name_index_put(rtp_name_index *ix, const void *key, size_t length, uint32_t value)
{
    if (2 * (ix->count + 1) > ix->capacity && !grow(ix)) return false;
    rtp_name_slot *s = slot_of(ix, key, length);
    if (s->key) return true;
    *s = (rtp_name_slot){key, length, value};
    ix->count++;
    return true;
}

uint32_t rtp_name_index_get(const rtp_name_index *ix, const void *key, size_t length)
{
    if (!ix->capacity) return RTP_NAME_NONE;
    const rtp_name_slot *s = slot_of(ix, key, length);
    return s->key ? s->value : RTP_NAME_NONE;
}

void rtp_name_index_free(rtp_name_index *ix)
{
    rtp_mem_free(ix->slots);
    memset(ix, 0, sizeof *ix);
}
