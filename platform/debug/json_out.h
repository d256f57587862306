/* The JSON values the subcommands' --json output needs escaped or checked. */
#ifndef RTP_JSON_OUT_H
#define RTP_JSON_OUT_H

#include <stdio.h>

/* A quoted JSON string; bytes from 0x80 up pass through (names are UTF-8). */
void rtp_json_string(FILE *out, const char *s);
/* A number with 17 significant digits (the exact double back when parsed); null when not finite. */
void rtp_json_number(FILE *out, double d);
/* A vector as an array of three such numbers: [x, y, z]. */
void rtp_json_vec3(FILE *out, double x, double y, double z);

#endif
