/* The memory cap (--max-memory) over everything large rtk allocates: file buffers, the
 * YAML tree, mesh arrays, decoded textures (libspng's allocator), the scene arena, the
 * output image and its encoding. One accounting allocator: every block carries its size
 * in a header, and the sum of the sizes asked for, not RSS, is held under the cap.
 * What is not counted -- malloc's own overhead, libyaml's parser state, thread stacks,
 * stdio -- is the fixed baseline docs/robustness.md measures. The counters are atomic;
 * the cap is set once, before any work. Without rtp_mem_set_cap there is no cap. */
#ifndef RTP_MEM_H
#define RTP_MEM_H

#include <stdbool.h>
#include <stddef.h>

void rtp_mem_set_cap(size_t bytes);
size_t rtp_mem_cap(void);
/* Bytes allocated and not yet freed; the most there ever were. */
size_t rtp_mem_in_use(void);
size_t rtp_mem_peak(void);

/* size bytes for what ("the texture's pixels", "the scene arena"), or NULL when they
 * would take the total over the cap or malloc fails; rtp_mem_refusal() then says which. */
void *rtp_mem_alloc(size_t size, const char *what);
void *rtp_mem_calloc(size_t count, size_t size, const char *what);
/* Grows or shrinks p (NULL: allocates); on failure p is left as it was. */
void *rtp_mem_realloc(void *p, size_t size, const char *what);
char *rtp_mem_strdup(const char *s, const char *what);
void rtp_mem_free(void *p);

/* Whether size more bytes would fit, for sizes known before the work that needs them
 * (a PNG's header, a file's length); false records the refusal as an allocation would. */
bool rtp_mem_fits(size_t size, const char *what);
/* Counts size bytes that a library without an allocator takes (libyaml's buffers)
 * until rtp_mem_unhold(size); false, with the refusal recorded, when they do not fit. */
bool rtp_mem_hold(size_t size, const char *what);
void rtp_mem_unhold(size_t size);

/* True once an allocation was refused (over the cap or out of memory): a command then
 * exits with 5. rtp_mem_refusal() is the last refusal in words, e.g. "the decoded texture
 * (768 MiB) does not fit in --max-memory (1 MiB; 0.2 MiB in use)". */
bool rtp_mem_refused(void);
const char *rtp_mem_refusal(void);
/* Forgets an earlier refusal, for a library call that starts afresh (rtk_open). */
void rtp_mem_forget_refusal(void);

/* "8 MiB", "1.5 MiB" or "1000 bytes" into buf (at least 32 bytes); returns buf. */
const char *rtp_mem_describe(size_t bytes, char *buf, size_t size);

#endif
