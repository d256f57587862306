/* Every line rtk prints on stderr goes through here, so that every message is one line
 * whatever the paths and values in it hold: control characters (newline, escape...),
 * C1 controls and bytes that are not UTF-8 are shown escaped, as \n, \t, \x1b, \xc2\x9b,
 * never sent raw to the terminal. */
#ifndef RTP_MESSAGE_H
#define RTP_MESSAGE_H

#include <stddef.h>

/* The character at s (non-empty) as it is shown: itself, or escaped (\n, \x1b...), into
 * piece; returns the length of that and sets *step to the bytes of s it stands for. */
size_t rtp_message_escape_char(const char *s, char piece[8], size_t *step);
/* s with its control characters and invalid UTF-8 escaped, into out (cut to fit). */
void rtp_message_escape(const char *s, char *out, size_t size);
/* Prints "rtk <cmd>: <formatted message>" and a newline on stderr, escaped, in one write. */
void rtp_message(const char *cmd, const char *fmt, ...) __attribute__((format(printf, 2, 3)));

#endif
