/* lex.c: the scene-language tokenizer (see lex.h): a hand-written scanner over a byte range that
 * never reads past its end, in the manner of Lua's llex.c. Numbers are converted by strtod. */
#include "scene/lex.h"

#include <errno.h>
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

void mc_lex_init(struct lexer *lx, const char *text, size_t len, const char *name, mc_diag *d)
{
    lx->p = text;
    lx->end = text + len;
    lx->line = 1;
    lx->col = 1;
    lx->name = name;
    lx->d = d;
    if (len >= 3 && memcmp(text, "\xef\xbb\xbf", 3) == 0)
        lx->p += 3; /* a UTF-8 byte order mark, as some editors write: not part of line 1 */
}

static int is_alpha(int c) { return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || c == '_'; }
static int is_digit(int c) { return c >= '0' && c <= '9'; }
static int is_word_char(int c) { return is_alpha(c) || is_digit(c); }
/* A number is scanned as the longest run of these and then checked whole, so that "1.0.0" or
 * "1e" is one malformed number rather than a number followed by something else. */
static int is_number_char(int c) { return is_word_char(c) || c == '.' || c == '+' || c == '-'; }

/* Report a byte that has no place in the language at the lexer's position. */
static enum tok_kind bad_byte(struct lexer *lx, unsigned char c, const char *where)
{
    if (c > 0x20 && c < 0x7f)
        mc_fail(lx->d, MCRT_ERR_PARSE, "%s:%d:%d: unexpected character '%c'%s", lx->name, lx->line,
                lx->col, c, where);
    else
        mc_fail(lx->d, MCRT_ERR_PARSE, "%s:%d:%d: unexpected byte 0x%02x%s", lx->name, lx->line,
                lx->col, c, where);
    return TOK_ERROR;
}

/* Skip blanks and comments. Returns 0, or TOK_ERROR for a NUL byte inside a comment (text files
 * hold none, and a NUL usually means the file is binary). */
static int skip_space(struct lexer *lx)
{
    while (lx->p < lx->end) {
        unsigned char c = (unsigned char)*lx->p;
        if (c == '\n') {
            lx->line++;
            lx->col = 1;
        } else if (c == ' ' || c == '\t' || c == '\r') {
            lx->col++;
        } else if (c == '#') {
            while (lx->p < lx->end && *lx->p != '\n') {
                if (*lx->p == '\0')
                    return bad_byte(lx, 0, " in a comment");
                lx->p++;
                lx->col++;
            }
            continue;
        } else {
            return 0;
        }
        lx->p++;
    }
    return 0;
}

static enum tok_kind too_long(struct lexer *lx, const struct token *t, const char *what, int max)
{
    mc_fail(lx->d, MCRT_ERR_PARSE, "%s:%d:%d: %s longer than %d characters", lx->name, t->line,
            t->col, what, max);
    return TOK_ERROR;
}

static enum tok_kind lex_string(struct lexer *lx, struct token *t)
{
    const char *s = lx->p + 1;
    const char *q = s;
    while (q < lx->end && *q != '"' && *q != '\n') {
        unsigned char c = (unsigned char)*q;
        if (c < 0x20 && c != '\t') {
            lx->col += (int)(q - lx->p);
            lx->p = q;
            return bad_byte(lx, c, " in a string");
        }
        q++;
    }
    if (q == lx->end || *q != '"') {
        mc_fail(lx->d, MCRT_ERR_PARSE, "%s:%d:%d: string not closed (a string ends with '\"' "
                "on the same line)", lx->name, t->line, t->col);
        return TOK_ERROR;
    }
    if (q - s > MC_LEX_MAX_STRING)
        return too_long(lx, t, "string", MC_LEX_MAX_STRING);
    t->text = s;
    t->len = (size_t)(q - s);
    lx->col += (int)(q + 1 - lx->p);
    lx->p = q + 1;
    return t->kind = TOK_STRING;
}

/* Convert a scanned number run; strtod must consume it whole and give a finite float. */
static enum tok_kind lex_number(struct lexer *lx, struct token *t)
{
    char buf[MC_LEX_MAX_TOKEN + 1];
    char *endp;
    int n = (int)t->len;
    double v;
    memcpy(buf, t->text, t->len);
    buf[t->len] = '\0';
    errno = 0;
    v = strtod(buf, &endp);
    if (endp != buf + t->len) {
        mc_fail(lx->d, MCRT_ERR_PARSE, "%s:%d:%d: malformed number '%.*s'", lx->name, t->line,
                t->col, n, t->text);
        return TOK_ERROR;
    }
    if (!isfinite(v)) {
        /* Only a spelled-out nan or inf reaches here; overflow gives ERANGE and HUGE_VAL. */
        if (errno != ERANGE) {
            mc_fail(lx->d, MCRT_ERR_PARSE, "%s:%d:%d: '%.*s' is not a finite number", lx->name,
                    t->line, t->col, n, t->text);
            return TOK_ERROR;
        }
    }
    if (!isfinite(v) || fabs(v) > FLT_MAX) {
        mc_fail(lx->d, MCRT_ERR_PARSE, "%s:%d:%d: number '%.*s' is too large (the largest is "
                "about 3.4e38)", lx->name, t->line, t->col, n, t->text);
        return TOK_ERROR;
    }
    /* Underflow (ERANGE with a tiny result) is accepted: the value rounds to 0 or a subnormal. */
    t->num = v;
    return t->kind = TOK_NUMBER;
}

enum tok_kind mc_lex_next(struct lexer *lx, struct token *t)
{
    unsigned char c;
    const char *q;
    if (skip_space(lx))
        return t->kind = TOK_ERROR;
    t->text = lx->p;
    t->len = 0;
    t->line = lx->line;
    t->col = lx->col;
    t->num = 0.0;
    if (lx->p == lx->end)
        return t->kind = TOK_EOF;
    c = (unsigned char)*lx->p;
    if (c == '{' || c == '}') {
        lx->p++;
        lx->col++;
        t->len = 1;
        return t->kind = c == '{' ? TOK_LBRACE : TOK_RBRACE;
    }
    if (c == '"')
        return t->kind = lex_string(lx, t);
    q = lx->p;
    if (is_alpha(c)) {
        while (q < lx->end && is_word_char((unsigned char)*q))
            q++;
    } else if (is_digit(c) || c == '.' || c == '+' || c == '-') {
        while (q < lx->end && is_number_char((unsigned char)*q))
            q++;
    } else {
        return t->kind = bad_byte(lx, c, "");
    }
    t->len = (size_t)(q - lx->p);
    if (t->len > MC_LEX_MAX_TOKEN)
        return t->kind = too_long(lx, t, is_alpha(c) ? "word" : "number", MC_LEX_MAX_TOKEN);
    lx->col += (int)t->len;
    lx->p = q;
    if (q < lx->end && (unsigned char)*q >= 0x80)
        return t->kind = bad_byte(lx, (unsigned char)*q, ""); /* "sphère": blame the byte, not "sph" */
    if (is_alpha(c))
        return t->kind = TOK_WORD;
    return t->kind = lex_number(lx, t);
}
