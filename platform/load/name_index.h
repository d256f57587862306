/* Keys (names, or any bytes) to indices, hashed: the loader's lookups of textures,
 * meshes, shaders and materials by name, and of asset files by identity, each in
 * constant time, so that loading stays linear however many there are. The index
 * points at the keys, which must outlive it; its table is counted by rtp_mem. */
#ifndef RTP_NAME_INDEX_H
#define RTP_NAME_INDEX_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#define RTP_NAME_NONE UINT32_MAX

typedef struct {
    const void *key;
    size_t length;
    uint32_t value;
} rtp_name_slot;

typedef struct {
    rtp_name_slot *slots; /* open addressing, at most half full; key NULL = free */
    size_t capacity, count;
} rtp_name_index;

/* Maps key to value; a key already present keeps its first value. False when the
 * table cannot grow (rtp_mem_refusal() says why). */
bool rtp_name_index_put(rtp_name_index *ix, const void *key, size_t length, uint32_t value);
/* The value of key, or RTP_NAME_NONE. */
uint32_t rtp_name_index_get(const rtp_name_index *ix, const void *key, size_t length);
void rtp_name_index_free(rtp_name_index *ix);

#endif
