/* A cursor over a NUL-terminated text buffer for the text mesh formats
 * (OBJ, OFF, ASCII PLY): numbers are read with strtod/strtol straight from
 * the buffer, and the line number is kept for error messages.
 *
 * strtod and strtol skip leading whitespace, newlines included, so a missing
 * number would silently be taken from the next line. Every reader here first
 * skips blanks itself and refuses to cross a line end unless asked to. */
#ifndef NEUV_IO_TEXT_SCAN_H
#define NEUV_IO_TEXT_SCAN_H

typedef struct text_cursor {
    const char *p; /* current position; the buffer ends with '\0' */
    int line;      /* 1-based line number of p */
} text_cursor;

/* Skips spaces, tabs and carriage returns; stops at '\n' or '\0'. */
void text_skip_blanks(text_cursor *c);
/* 1 when only blanks remain before the end of the line (or of the text). */
int text_at_line_end(text_cursor *c);
/* Moves to the first character after the next '\n' (or to the end). */
void text_next_line(text_cursor *c);
/* Skips whitespace across lines; with `comments`, also '#' to end of line.
 * Returns 0 when the end of the text is reached. */
int text_skip_space(text_cursor *c, int comments);

/* Reads one number at the cursor (after skipping blanks on this line).
 * Returns 1 on success, 0 when the line has no more tokens, -1 when the token
 * is not a number (the cursor then stays on the token). */
int text_read_double(text_cursor *c, double *x);
int text_read_long(text_cursor *c, long long *x);
/* Copies the token at the cursor (up to 24 characters) for a message. */
void text_token(const text_cursor *c, char out[32]);

#endif
