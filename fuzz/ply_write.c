/* PLY files written for fuzz_ply; see ply_write.h. */
#include "ply_write.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static void put_double(FILE *f, fz_ply_format format, double v)
{
    if (format == FZ_PLY_ASCII) {
        fprintf(f, " %.17g", v); /* 17 digits: strtod gives the same double back */
        return;
    }
    uint64_t bits;
    memcpy(&bits, &v, 8);
    for (int i = 0; i < 8; i++) fputc((int)(bits >> (format == FZ_PLY_LITTLE ? 8 * i : 56 - 8 * i)) & 0xff, f);
}

static void put_index(FILE *f, fz_ply_format format, uint32_t v)
{
    if (format == FZ_PLY_ASCII) {
        fprintf(f, " %u", v);
        return;
    }
    for (int i = 0; i < 4; i++) fputc((int)(v >> (format == FZ_PLY_LITTLE ? 8 * i : 24 - 8 * i)) & 0xff, f);
}

char *fz_ply_write(const rtp_ply_mesh *m, fz_ply_format format, size_t *size)
{
    char *bytes = NULL;
    FILE *f = open_memstream(&bytes, size);
    if (!f) return NULL;
    static const char *names[] = {"ascii", "binary_little_endian", "binary_big_endian"};
    fprintf(f, "ply\nformat %s 1.0\nelement vertex %u\n", names[format], m->vertex_count);
    fprintf(f, "property double x\nproperty double y\nproperty double z\n");
    if (m->normals) fprintf(f, "property double nx\nproperty double ny\nproperty double nz\n");
    if (m->uvs) fprintf(f, "property double u\nproperty double v\n");
    fprintf(f, "element face %u\nproperty list uchar uint vertex_indices\nend_header\n", m->triangle_count);
    for (uint32_t i = 0; i < m->vertex_count; i++) {
        rt_vec3 p = m->positions[i];
        put_double(f, format, rt_to_double(p.x));
        put_double(f, format, rt_to_double(p.y));
        put_double(f, format, rt_to_double(p.z));
        if (m->normals) {
            rt_vec3 n = m->normals[i];
            put_double(f, format, rt_to_double(n.x));
            put_double(f, format, rt_to_double(n.y));
            put_double(f, format, rt_to_double(n.z));
        }
        if (m->uvs) {
            put_double(f, format, rt_to_double(m->uvs[i].u));
            put_double(f, format, rt_to_double(m->uvs[i].v));
        }
        if (format == FZ_PLY_ASCII) fputc('\n', f);
    }
    for (uint32_t t = 0; t < m->triangle_count; t++) {
        if (format == FZ_PLY_ASCII)
            fputc('3', f);
        else
            fputc(3, f);
        for (int k = 0; k < 3; k++) put_index(f, format, m->indices[3 * t + k]);
        if (format == FZ_PLY_ASCII) fputc('\n', f);
    }
    if (fclose(f) != 0) {
        free(bytes);
        return NULL;
    }
    return bytes;
}
