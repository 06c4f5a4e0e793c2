/* lex.h: the tokenizer of the mcrt scene language.
 * Tokens are words, numbers, quoted strings and braces, each with a 1-based line and column
 * (a tab is one column). The text is a byte range: it need not be NUL-terminated. */
#ifndef MCRT_LEX_H
#define MCRT_LEX_H

#include <stddef.h>

#include "core/diag.h"

/* The longest word or number, and the longest string (a file path), in bytes. */
#define MC_LEX_MAX_TOKEN 255
#define MC_LEX_MAX_STRING 4095

enum tok_kind {
    TOK_EOF,
    TOK_WORD,   /* [A-Za-z_][A-Za-z0-9_]* */
    TOK_NUMBER, /* a finite number that fits a float, in strtod syntax; value in num */
    TOK_STRING, /* "..." on one line; text/len exclude the quotes */
    TOK_LBRACE,
    TOK_RBRACE,
    TOK_ERROR   /* the message is in the lexer's diag */
};

struct token {
    enum tok_kind kind;
    const char *text; /* points into the scene text */
    size_t len;
    int line, col;
    double num;       /* TOK_NUMBER */
};

struct lexer {
    const char *p, *end;
    int line, col;
    const char *name; /* for messages */
    mc_diag *d;
};

/* Start lexing text[0..len). len must be below 2^30 so that lines and columns fit an int. */
void mc_lex_init(struct lexer *lx, const char *text, size_t len, const char *name, mc_diag *d);
/* Read the next token into t and return its kind. Comments (# to end of line) and whitespace are
 * skipped. On malformed input (a byte outside the language, an unclosed string, an overlong
 * token, a malformed, non-finite or out-of-range number) it fills the diag with
 * "name:line:col: message" (status MCRT_ERR_PARSE) and returns TOK_ERROR; t then holds the
 * position. After TOK_EOF every further call returns TOK_EOF again. */
enum tok_kind mc_lex_next(struct lexer *lx, struct token *t);

#endif
