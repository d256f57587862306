/* Internals of the PLY reader shared by its header parser (ply.c) and its body
 * reader (ply_body.c). Not part of the public interface. */
#ifndef RTP_PLY_READER_H
#define RTP_PLY_READER_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "load/ply.h"

/* Generous for real files, small enough to keep the header tables fixed-size. */
#define PLY_MAX_ELEMENTS 16
#define PLY_MAX_PROPERTIES 64
#define PLY_NAME_SIZE 32

typedef enum { PLY_INT8, PLY_UINT8, PLY_INT16, PLY_UINT16, PLY_INT32, PLY_UINT32, PLY_FLOAT32, PLY_FLOAT64 } ply_type;
typedef enum { PLY_ASCII, PLY_LITTLE_ENDIAN, PLY_BIG_ENDIAN } ply_format;

/* What a property feeds in the mesh; PLY_SKIP for everything the tracer ignores. */
typedef enum {
    PLY_SKIP,
    PLY_X,
    PLY_Y,
    PLY_Z,
    PLY_NX,
    PLY_NY,
    PLY_NZ,
    PLY_U,
    PLY_V,
    PLY_INDICES,
    PLY_ROLE_COUNT
} ply_role;

typedef struct {
    ply_type type;
    ply_type count_type; /* lists only */
    bool is_list;
    ply_role role;
} ply_property;

typedef struct {
    char name[PLY_NAME_SIZE]; /* printable, for messages */
    uint64_t count;
    unsigned long line; /* header line that declared it */
    uint32_t property_count;
    ply_property properties[PLY_MAX_PROPERTIES];
} ply_element;

typedef struct {
    const char *path;
    char *err;
    size_t err_size;
    const uint8_t *data;
    size_t size;
    size_t pos;         /* next byte to read */
    size_t value_at;    /* where the last value read started */
    unsigned long line; /* 1-based line of pos (header and ASCII body) */
    bool binary_body;   /* errors name a byte offset instead of a line */
    ply_format format;
    ply_element elements[PLY_MAX_ELEMENTS];
    uint32_t element_count;
    bool has[PLY_ROLE_COUNT];
    /* The element being read, for messages. */
    const ply_element *element;
    uint64_t index;
    rtp_ply_mesh *mesh;
    size_t triangle_capacity;
} ply_reader;

/* Writes "path: line N: ..." or "path: byte N: ..." into the error buffer; returns false. */
bool ply_fail(ply_reader *r, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
/* Reads every element of the body into r->mesh (arrays already allocated). */
bool ply_read_body(ply_reader *r);

#endif
