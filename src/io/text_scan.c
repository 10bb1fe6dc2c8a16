#include "io/text_scan.h"

#include <errno.h>
#include <stdlib.h>
#include <string.h>

static int is_blank(char ch) { return ch == ' ' || ch == '\t' || ch == '\r' || ch == '\f' || ch == '\v'; }
static int is_space(char ch) { return is_blank(ch) || ch == '\n'; }

void text_skip_blanks(text_cursor *c)
{
    while (is_blank(*c->p)) c->p++;
}

int text_at_line_end(text_cursor *c)
{
    text_skip_blanks(c);
    return *c->p == '\n' || *c->p == '\0';
}

void text_next_line(text_cursor *c)
{
    const char *nl = strchr(c->p, '\n');
    if (nl) { c->p = nl + 1; c->line++; }
    else c->p += strlen(c->p);
}

int text_skip_space(text_cursor *c, int comments)
{
    for (;;) {
        char ch = *c->p;
        if (ch == '\n') { c->line++; c->p++; }
        else if (is_blank(ch)) c->p++;
        else if (comments && ch == '#') {
            while (*c->p && *c->p != '\n') c->p++;
        } else return ch != '\0';
    }
}

/* A token must end at whitespace or the end of text: "1.5abc" is malformed
 * rather than 1.5 followed by a stray word. */
static int token_ends(const char *p) { return *p == '\0' || is_space(*p); }

int text_read_double(text_cursor *c, double *x)
{
    text_skip_blanks(c);
    if (*c->p == '\n' || *c->p == '\0') return 0;
    char *end;
    double v = strtod(c->p, &end);
    if (end == c->p || !token_ends(end)) return -1;
    *x = v; /* overflow gives ±inf, which the loader reports as non-finite */
    c->p = end;
    return 1;
}

int text_read_long(text_cursor *c, long long *x)
{
    text_skip_blanks(c);
    if (*c->p == '\n' || *c->p == '\0') return 0;
    char *end;
    errno = 0;
    long long v = strtoll(c->p, &end, 10);
    if (end == c->p || !token_ends(end) || errno == ERANGE) return -1;
    *x = v;
    c->p = end;
    return 1;
}

void text_token(const text_cursor *c, char out[32])
{
    const char *p = c->p;
    while (is_blank(*p)) p++;
    int n = 0;
    while (p[n] && !is_space(p[n]) && n < 24) n++;
    memcpy(out, p, (size_t)n);
    out[n] = '\0';
    if (n == 24 && p[n] && !is_space(p[n])) strcpy(out + 21, "...");
}
