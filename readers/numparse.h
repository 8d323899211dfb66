/* Number parsing for text dumps: a fast exact path for the common case,
 * strtod/strtoll for the rest. */
#ifndef MIMAS_NUMPARSE_H
#define MIMAS_NUMPARSE_H

#include <stdint.h>

/* Parses the next whitespace-separated token at *p as a finite double,
 * correctly rounded (as strtod).  Skips leading blanks; advances *p past the
 * token.  Returns 0, or -1 if the token is missing (end of line) and -2 if
 * it is not a finite number. */
int parse_double(char **p, double *v);
/* The same for a token in a line from text_line (its padding lets digits be read eight
 * at a time): the same result, faster on long numbers. */
int parse_double_in_line(char **p, double *v);
/* The same for a decimal integer (a token like "12.0" is not one). */
int parse_int64(char **p, int64_t *v);
/* Skips one token; returns 0, or -1 at the end of the line. */
int skip_token(char **p);

#endif
