/* Bump allocator; see arena.h. */
#include "arena.h"
#include "invariant.h"

void rt_arena_init(rt_arena *a, void *memory, size_t capacity)
{
    a->base = memory;
    a->capacity = capacity;
    a->used = 0;
    a->high_water = 0;
    a->wanted = 0;
}

void *rt_arena_alloc(rt_arena *a, size_t size) { return rt_arena_alloc_aligned(a, size, 16); }

void *rt_arena_alloc_aligned(rt_arena *a, size_t size, size_t align)
{
    RT_ASSERT(align != 0 && (align & (align - 1)) == 0 && a->used <= a->capacity);
    size_t misalign = ((uintptr_t)a->base + a->used) & (align - 1);
    size_t start = a->used + (misalign ? align - misalign : 0);
    if (start < a->used || size > SIZE_MAX - start || start + size > a->capacity) {
        a->wanted = size > SIZE_MAX - start ? SIZE_MAX : start + size;
        return NULL;
    }
    a->used = start + size;
    if (a->used > a->high_water) a->high_water = a->used;
    return a->base + start;
}

void *rt_arena_alloc_array(rt_arena *a, size_t count, size_t size)
{
    if (size != 0 && count > SIZE_MAX / size) {
        a->wanted = SIZE_MAX;
        return NULL;
    }
    return rt_arena_alloc(a, count * size);
}

void *rt_arena_array(rt_arena *a, size_t count, size_t size)
{
    void *p = rt_arena_alloc_array(a, count, size);
    /* -fno-builtin would keep a plain loop byte by byte; memset is allowed in the core. */
    if (p) __builtin_memset(p, 0, count * size);
    return p;
}

size_t rt_arena_mark(const rt_arena *a) { return a->used; }

void rt_arena_reset(rt_arena *a, size_t mark)
{
    if (mark <= a->used) a->used = mark;
}

void *rt_arena_keep(rt_arena *a, const void *from, size_t n)
{
    void *to = rt_arena_alloc(a, n);
    RT_ASSERT(to && (const uint8_t *)to <= (const uint8_t *)from);
    if (to != from) __builtin_memmove(to, from, n);
    return to;
}
