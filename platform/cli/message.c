/* One-line messages on stderr (see message.h). */
#include "cli/message.h"

#include <stdarg.h>
#include <stdbool.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

/* Length of the valid UTF-8 sequence at s (2 to 4 bytes) that is not a C1 control, or 0. */
static size_t utf8_printable(const unsigned char *s)
{
    size_t n = s[0] >= 0xf0 ? 4 : s[0] >= 0xe0 ? 3 : s[0] >= 0xc2 ? 2 : 0;
    if (n == 0 || s[0] > 0xf4) return 0;
    for (size_t i = 1; i < n; i++)
        if ((s[i] & 0xc0) != 0x80) return 0;
    if (n == 2 && s[0] == 0xc2 && s[1] < 0xa0) return 0;  /* U+0080..U+009F: C1 controls */
    if (n == 3 && s[0] == 0xe0 && s[1] < 0xa0) return 0;  /* overlong */
    if (n == 3 && s[0] == 0xed && s[1] >= 0xa0) return 0; /* surrogates */
    if (n == 4 && s[0] == 0xf0 && s[1] < 0x90) return 0;  /* overlong */
    if (n == 4 && s[0] == 0xf4 && s[1] >= 0x90) return 0; /* beyond U+10FFFF */
    return n;
}

size_t rtp_message_escape_char(const char *s, char piece[8], size_t *step)
{
    static const char named[] = "\a\b\t\n\v\f\r", letters[] = "abtnvfr";
    const unsigned char *p = (const unsigned char *)s;
    size_t n = utf8_printable(p);
    if (n > 0) { /* a printable character beyond ASCII */
        memcpy(piece, p, n);
        *step = n;
        return n;
    }
    *step = 1;
    if (*p >= 0x20 && *p < 0x7f) {
        piece[0] = (char)*p;
        return 1;
    }
    if (*p < 0x20 && strchr(named, *p)) {
        piece[0] = '\\';
        piece[1] = letters[strchr(named, *p) - named];
        return 2;
    }
    return (size_t)snprintf(piece, 8, "\\x%02x", *p);
}

void rtp_message_escape(const char *s, char *out, size_t size)
{
    size_t len = 0;
    if (size == 0) return;
    while (*s) {
        char piece[8];
        size_t step, n = rtp_message_escape_char(s, piece, &step);
        if (len + n >= size) break;
        memcpy(out + len, piece, n);
        len += n;
        s += step;
    }
    out[len] = '\0';
}

void rtp_message(const char *cmd, const char *fmt, ...)
{
    char raw[4096], line[4096 * 4 + 64];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(raw, sizeof raw, fmt, ap);
    va_end(ap);
    int head = snprintf(line, sizeof line, "rtk%s%s: ", cmd ? " " : "", cmd ? cmd : "");
    rtp_message_escape(raw, line + head, sizeof line - (size_t)head - 1);
    size_t len = strlen(line);
    line[len++] = '\n';
    fwrite(line, 1, len, stderr);
    fflush(stderr);
}
