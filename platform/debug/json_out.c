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
