/* Recursive descent over the JSON grammar; see json_check.h. */
#include "json_check.h"

#include <string.h>

#define MAX_NESTING 512

static void skip_space(const char **p)
{
    while (**p == ' ' || **p == '\t' || **p == '\n' || **p == '\r') (*p)++;
}

static bool is_digit(char c) { return c >= '0' && c <= '9'; }

static bool string(const char **p)
{
    const char *s = *p + 1; /* past the opening quote */
    for (;; s++) {
        unsigned char c = (unsigned char)*s;
        if (c == '"') break;
        if (c < 0x20) return false; /* also the end of the text */
        if (c != '\\') continue;
        c = (unsigned char)*++s;
        if (c == 'u') {
            for (int i = 0; i < 4; i++)
                if (!*++s || !strchr("0123456789abcdefABCDEF", *s)) return false;
        } else if (!c || !strchr("\"\\/bfnrt", c)) {
            return false;
        }
    }
    *p = s + 1;
    return true;
}

static bool number(const char **p)
{
    const char *s = *p;
    if (*s == '-') s++;
    if (*s == '0')
        s++;
    else if (is_digit(*s))
        while (is_digit(*s)) s++;
    else
        return false;
    if (*s == '.') {
        if (!is_digit(*++s)) return false;
        while (is_digit(*s)) s++;
    }
    if (*s == 'e' || *s == 'E') {
        s++;
        if (*s == '+' || *s == '-') s++;
        if (!is_digit(*s)) return false;
        while (is_digit(*s)) s++;
    }
    *p = s;
    return true;
}

static bool literal(const char **p, const char *word)
{
    size_t n = strlen(word);
    if (strncmp(*p, word, n)) return false;
    *p += n;
    return true;
}

static bool value(const char **p, int depth);

/* An object or array: elements separated by commas up to the closing bracket. */
static bool container(const char **p, int depth, char close)
{
    (*p)++;
    skip_space(p);
    if (**p == close) {
        (*p)++;
        return true;
    }
    for (;;) {
        if (close == '}') {
            if (**p != '"' || !string(p)) return false;
            skip_space(p);
            if (*(*p)++ != ':') return false;
        }
        if (!value(p, depth + 1)) return false;
        skip_space(p);
        char c = *(*p)++;
        if (c == close) return true;
        if (c != ',') return false;
        skip_space(p);
    }
}

static bool value(const char **p, int depth)
{
    if (depth > MAX_NESTING) return false;
    skip_space(p);
    switch (**p) {
    case '{': return container(p, depth, '}');
    case '[': return container(p, depth, ']');
    case '"': return string(p);
    case 't': return literal(p, "true");
    case 'f': return literal(p, "false");
    case 'n': return literal(p, "null");
    default: return number(p);
    }
}

bool json_is_valid(const char *text)
{
    const char *p = text;
    if (!value(&p, 0)) return false;
    skip_space(&p);
    return *p == '\0';
}
