/* Bump allocator over caller-owned memory: the kernel's only source of memory.
 * One lifetime per arena; nothing is freed individually. */
#ifndef RT_ARENA_H
#define RT_ARENA_H

#include <stddef.h>
#include <stdint.h>

typedef struct {
    uint8_t *base;
    size_t capacity;
    size_t used;
    size_t high_water;
    /* Set when an allocation fails: the total bytes that allocation would have needed. */
    size_t wanted;
} rt_arena;

void rt_arena_init(rt_arena *a, void *memory, size_t capacity);
/* size bytes aligned to 16, or NULL when the arena is full (a->wanted is set). */
void *rt_arena_alloc(rt_arena *a, size_t size);
/* size bytes at an address that is a multiple of align (a power of two), or NULL. */
void *rt_arena_alloc_aligned(rt_arena *a, size_t size, size_t align);
/* count * size bytes, not zeroed; NULL on overflow of the product (wanted = SIZE_MAX) or when full. */
void *rt_arena_alloc_array(rt_arena *a, size_t count, size_t size);
/* count * size bytes, zeroed; NULL on overflow of the product or when full. */
void *rt_arena_array(rt_arena *a, size_t count, size_t size);
/* Marks for scratch use: everything allocated after the mark is released by reset. */
size_t rt_arena_mark(const rt_arena *a);
void rt_arena_reset(rt_arena *a, size_t mark);

/* Keeps n bytes at from, which was allocated after the mark the arena was just reset to:
 * they move down to a new allocation (in the order they were allocated, each lands at or
 * below where it was). Returns their new address. */
void *rt_arena_keep(rt_arena *a, const void *from, size_t n);

#define RT_NEW_ARRAY(arena, type, count) ((type *)rt_arena_array((arena), (count), sizeof(type)))

#endif
