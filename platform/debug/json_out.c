/* JSON strings and numbers; see json_out.h. */
#include "debug/json_out.h"

#include <math.h>

void rtp_json_string(FILE *out, const char *s)
{
    fputc('"', out);
    for (; *s; s++) {
        unsigned char c = (unsigned char)*s;
        if (c == '"' || c == '\\')
            fprintf(out, "\\%c", c);
        else if (c < 0x20)
            fprintf(out, "\\u%04x", c);
        else
            fputc(c, out);
    }
    fputc('"', out);
}

void rtp_json_number(FILE *out, double d)
{
    if (isfinite(d))
        fprintf(out, "%.17g", d);
    else
        fputs("null", out);
}

void rtp_json_vec3(FILE *out, double x, double y, double z)
{
    fputc('[', out);
    rtp_json_number(out, x);
    fputs(", ", out);
    rtp_json_number(out, y);
    fputs(", ", out);
    rtp_json_number(out, z);
    fputc(']', out);
}
