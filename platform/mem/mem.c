/* The accounting allocator behind --max-memory (see mem.h). */
#include "mem/mem.h"

#include <stdatomic.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#ifdef __linux__
#include <sys/mman.h>
#endif

/* Each block starts with its size, padded so the caller's bytes keep malloc's alignment. */
typedef union {
    size_t size;
    max_align_t align;
} block_header;

static _Atomic size_t cap = SIZE_MAX, in_use, peak;
static atomic_bool refused;
/* Written by the refusing thread; rtk allocates on one thread at a time. */
static char refusal[256];

void rtp_mem_set_cap(size_t bytes) { atomic_store(&cap, bytes); }
size_t rtp_mem_cap(void) { return atomic_load(&cap); }
size_t rtp_mem_in_use(void) { return atomic_load(&in_use); }
size_t rtp_mem_peak(void) { return atomic_load(&peak); }
bool rtp_mem_refused(void) { return atomic_load(&refused); }
void rtp_mem_forget_refusal(void) { atomic_store(&refused, false); }
const char *rtp_mem_refusal(void) { return refusal; }

const char *rtp_mem_describe(size_t bytes, char *buf, size_t size)
{
    const size_t mib = (size_t)1 << 20;
    if (bytes < mib)
        snprintf(buf, size, "%zu bytes", bytes);
    else if (bytes % mib == 0)
        snprintf(buf, size, "%zu MiB", bytes / mib);
    else
        snprintf(buf, size, "%.1f MiB", (double)bytes / (double)mib);
    return buf;
}

/* total is what the allocation would have brought what to; over_cap: refused by the cap,
 * not by malloc. */
static void refuse(const char *what, size_t total, bool over_cap)
{
    char need[32], limit[32], used[32];
    rtp_mem_describe(total, need, sizeof need);
    if (over_cap)
        snprintf(refusal, sizeof refusal, "%s (%s) does not fit in --max-memory (%s; %s in use)", what, need,
                 rtp_mem_describe(rtp_mem_cap(), limit, sizeof limit),
                 rtp_mem_describe(rtp_mem_in_use(), used, sizeof used));
    else
        snprintf(refusal, sizeof refusal, "%s (%s): out of memory", what, need);
    atomic_store(&refused, true);
}

/* Counts size more bytes, unless that would pass the cap. */
static bool reserve(size_t size)
{
    size_t now = atomic_load(&in_use), limit = atomic_load(&cap);
    do {
        if (size > limit || now > limit - size) return false;
    } while (!atomic_compare_exchange_weak(&in_use, &now, now + size));
    size_t high = atomic_load(&peak);
    while (now + size > high && !atomic_compare_exchange_weak(&peak, &high, now + size)) {
    }
    return true;
}

static void release(size_t size) { atomic_fetch_sub(&in_use, size); }

/* Asks for transparent huge pages inside a block of 32 MiB or more: Linux's default
 * "madvise" mode gives them only to memory so advised, and on a virtual machine the first
 * touch of a 4 KiB page costs about 15 us (docs/performance.md, "Page faults"). glibc
 * maps every block that large on its own, so the advice leaves with the block. */
static void advise_huge_pages(void *p, size_t size)
{
#if defined(__linux__) && defined(MADV_HUGEPAGE)
    const uintptr_t huge = (uintptr_t)2 << 20;
    if (size < ((size_t)32 << 20)) return;
    uintptr_t lo = ((uintptr_t)p + huge - 1) & ~(huge - 1), hi = ((uintptr_t)p + size) & ~(huge - 1);
    if (hi > lo) madvise((void *)lo, hi - lo, MADV_HUGEPAGE);
#else
    (void)p;
    (void)size;
#endif
}

bool rtp_mem_fits(size_t size, const char *what)
{
    size_t now = atomic_load(&in_use), limit = atomic_load(&cap);
    if (size <= limit && now <= limit - size) return true;
    refuse(what, size, true);
    return false;
}

bool rtp_mem_hold(size_t size, const char *what)
{
    if (reserve(size)) return true;
    refuse(what, size, true);
    return false;
}

void rtp_mem_unhold(size_t size) { release(size); }

void *rtp_mem_alloc(size_t size, const char *what)
{
    if (size > SIZE_MAX - sizeof(block_header) || !reserve(size)) {
        refuse(what, size, true);
        return NULL;
    }
    block_header *h = malloc(sizeof *h + size);
    if (!h) {
        release(size);
        refuse(what, size, false);
        return NULL;
    }
    h->size = size;
    advise_huge_pages(h + 1, size);
    return h + 1;
}

void *rtp_mem_calloc(size_t count, size_t size, const char *what)
{
    if (size && count > SIZE_MAX / size) {
        refuse(what, SIZE_MAX, true);
        return NULL;
    }
    void *p = rtp_mem_alloc(count * size, what);
    if (p) memset(p, 0, count * size);
    return p;
}

void *rtp_mem_realloc(void *p, size_t size, const char *what)
{
    if (!p) return rtp_mem_alloc(size, what);
    block_header *h = (block_header *)p - 1;
    size_t old = h->size;
    if (size > old && (size > SIZE_MAX - sizeof *h || !reserve(size - old))) {
        refuse(what, size, true);
        return NULL;
    }
    block_header *grown = realloc(h, sizeof *h + size);
    if (!grown) {
        if (size > old) release(size - old);
        refuse(what, size, false);
        return NULL;
    }
    if (size < old) release(old - size);
    grown->size = size;
    advise_huge_pages(grown + 1, size);
    return grown + 1;
}

char *rtp_mem_strdup(const char *s, const char *what)
{
    size_t n = strlen(s) + 1;
    char *copy = rtp_mem_alloc(n, what);
    if (copy) memcpy(copy, s, n);
    return copy;
}

void rtp_mem_free(void *p)
{
    if (!p) return;
    block_header *h = (block_header *)p - 1;
    release(h->size);
    free(h);
}
