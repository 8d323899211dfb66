/* The parameters of a run: named values with units that describe how the
 * data were made (for mimas simulate: every key of the scenario file).  They
 * are file-level metadata, not part of a frame: the native writer stores them
 * as attributes of /parameters/GROUP, the native reader gives them back,
 * mimas average copies them into the field file, and the analyses look a
 * study variable up among them (docs/format.md, "Run parameters"). */
#ifndef MIMAS_PARAMETERS_H
#define MIMAS_PARAMETERS_H

#include <stddef.h>

#include "error.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef enum mimas_parameter_kind {
    MIMAS_PARAM_REAL,     /* a floating-point number */
    MIMAS_PARAM_INTEGER,  /* a whole number */
    MIMAS_PARAM_TEXT,     /* a word: a choice ("linear") or yes/no */
    MIMAS_PARAM_MIXED     /* the inputs a result was made from differ in it */
} mimas_parameter_kind;

typedef struct mimas_parameter {
    char name[80];          /* "SECTION.KEY", e.g. "particles.liquid_content" */
    mimas_parameter_kind kind;
    double value;           /* REAL, INTEGER; NaN for TEXT and MIXED */
    char text[64];          /* the value as text (numbers with all their digits) */
    char unit[24];          /* SI unit; "" for none */
} mimas_parameter;

typedef struct mimas_parameters {
    size_t n, cap;
    mimas_parameter *p;
} mimas_parameters;

void mimas_parameters_init(mimas_parameters *ps);
void mimas_parameters_free(mimas_parameters *ps);
void mimas_parameters_clear(mimas_parameters *ps);
/* Appends SECTION.KEY with a number (kind REAL or INTEGER) or, for TEXT, the
 * word text.  unit may be NULL.  A name that exists is replaced. */
int mimas_parameters_add(mimas_parameters *ps, const char *section, const char *key,
                         mimas_parameter_kind kind, double value, const char *text,
                         const char *unit, mimas_error *err);
int mimas_parameters_copy(mimas_parameters *dst, const mimas_parameters *src, mimas_error *err);
/* The parameter of exactly this name, or NULL. */
const mimas_parameter *mimas_parameters_get(const mimas_parameters *ps, const char *name);
/* Folds other into ps for a result made from both: a parameter the two
 * give different values (or only one of them has) becomes MIXED. */
int mimas_parameters_merge(mimas_parameters *ps, const mimas_parameters *other,
                           mimas_error *err);
/* Looks up NAME: "SECTION.KEY", or a bare KEY that one section alone has.
 * MIMAS_EDATA with a message (without the source's name) when there is no
 * such parameter or a bare key is in several sections (the message lists
 * them). */
int mimas_parameters_find(const mimas_parameters *ps, const char *name,
                          const mimas_parameter **out, mimas_error *err);

#ifdef __cplusplus
}
#endif
#endif
