/* A PLY writer for the parser target's differential check: the same mesh in ASCII,
 * binary little endian or binary big endian, every value as a double (exact both ways). */
#ifndef FZ_PLY_WRITE_H
#define FZ_PLY_WRITE_H

#include "load/ply.h"

typedef enum { FZ_PLY_ASCII, FZ_PLY_LITTLE, FZ_PLY_BIG } fz_ply_format;

/* The file's bytes, malloc'd (released by the caller with free); NULL when out of memory. */
char *fz_ply_write(const rtp_ply_mesh *mesh, fz_ply_format format, size_t *size);

#endif
