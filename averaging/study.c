#include <config.h>

#include "study.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* ---- the study variable ---- */

int mimas_study_value(const mimas_parameters *ps, const char *source, const char *name,
                      double *value, mimas_error *err)
{
    *value = NAN;
    if (!ps->n)
        return mimas_error_set(err, MIMAS_EDATA,
                               "%s: no run parameters to take '%s' from (they come from mimas "
                               "simulate through mimas average); give --study-values",
                               source, name);
    const mimas_parameter *q;
    if (mimas_parameters_find(ps, name, &q, err))
        return mimas_error_prefix(err, "%s", source);
    if (q->kind == MIMAS_PARAM_MIXED)
        return mimas_error_set(err, MIMAS_EDATA, "%s: the runs averaged into it differ in %s",
                               source, q->name);
    if (q->kind == MIMAS_PARAM_TEXT)
        return mimas_error_set(err, MIMAS_EDATA, "%s: %s is '%s', not a number", source,
                               q->name, q->text);
    *value = q->value;
    return MIMAS_OK;
}

int mimas_study_parse_values(const char *spec, double *v, size_t max, size_t *n,
                             mimas_error *err)
{
    *n = 0;
    const char *s = spec;
    while (1) {
        char *end;
        double x = strtod(s, &end);
        if (end == s || !isfinite(x) || (*end && *end != ',') || *n >= max)
            return mimas_error_set(err, MIMAS_EUSAGE, "study values are numbers V1,V2,... "
                                   "(at most %zu), not '%s'", max, spec);
        v[(*n)++] = x;
        if (!*end)
            return MIMAS_OK;
        s = end + 1;
    }
}

static int same_value(const mimas_parameter *a, const mimas_parameter *b)
{
    return a && b && a->kind == b->kind && a->kind != MIMAS_PARAM_MIXED &&
           !strcmp(a->text, b->text);
}

void mimas_study_differences(const mimas_parameters *const *ps, size_t n, const char *name,
                             char *buf, size_t len)
{
    size_t at = 0;
    buf[0] = '\0';
    const mimas_parameter *study = NULL;
    if (name && n)
        mimas_parameters_find(ps[0], name, &study, NULL);
    for (size_t r = 0; r < n; r++)
        for (size_t k = 0; k < ps[r]->n; k++) {
            const mimas_parameter *q = &ps[r]->p[k];
            if (study && !strcmp(q->name, study->name))
                continue;
            /* listed once: at the first run that has it */
            int seen = 0;
            for (size_t e = 0; e < r && !seen; e++)
                seen = mimas_parameters_get(ps[e], q->name) != NULL;
            if (seen)
                continue;
            int differs = q->kind == MIMAS_PARAM_MIXED || r > 0;
            for (size_t o = r + 1; o < n && !differs; o++)
                differs = !same_value(q, mimas_parameters_get(ps[o], q->name));
            if (differs && at < len)
                at += (size_t)snprintf(buf + at, len - at, "%s%s", at ? ", " : "", q->name);
        }
}

/* ---- trends ---- */

typedef struct run_value {
    double x, y, err;
} run_value;

static int by_x(const void *a, const void *b)
{
    double u = ((const run_value *)a)->x, v = ((const run_value *)b)->x;
    return (u > v) - (u < v);
}

/* 100 (b - a)/a with the error of independent a and b */
static void change(const run_value *a, const run_value *b, double *c, double *e)
{
    *c = 100 * (b->y - a->y) / a->y;
    double q = b->y / a->y;
    *e = 100 * fabs(q) * hypot(a->err / a->y, b->err / b->y);
    if (!isfinite(*c))
        *c = *e = NAN;
    if (!isfinite(*e))
        *e = NAN;
}

int mimas_study_trend(const double *x, const double *y, const double *yerr, size_t n,
                      double lo, double hi, mimas_trend *t, mimas_error *err)
{
    memset(t, 0, sizeof *t);
    t->change_first = t->change_first_err = t->change_rest = t->change_rest_err = NAN;
    double *xin = calloc(n ? n : 1, sizeof *xin);
    run_value *v = malloc((n ? n : 1) * sizeof *v);
    if (!xin || !v) {
        free(xin), free(v);
        return mimas_error_set(err, MIMAS_EIO, "out of memory");
    }
    for (size_t k = 0; k < n; k++)
        xin[k] = x[k] >= lo && x[k] <= hi ? x[k] : NAN;
    int rc = mimas_fit_line(xin, y, NULL, n, 3, &t->line, err);
    /* the distinct study values with a value, runs of equal x averaged */
    size_t m = 0;
    for (size_t k = 0; k < n; k++)
        if (isfinite(x[k]) && isfinite(y[k]))
            v[m++] = (run_value){x[k], y[k], yerr && isfinite(yerr[k]) ? yerr[k] : NAN};
    qsort(v, m, sizeof *v, by_x);
    size_t d = 0;
    for (size_t k = 0; k < m;) {
        size_t e = k;
        double sy = 0, se = 0;
        while (e < m && v[e].x == v[k].x) {
            sy += v[e].y;
            se += v[e].err * v[e].err;
            e++;
        }
        double c = (double)(e - k);
        v[d++] = (run_value){v[k].x, sy / c, sqrt(se) / c};
        k = e;
    }
    if (d >= 2)
        change(&v[0], &v[1], &t->change_first, &t->change_first_err);
    if (d >= 3)
        change(&v[1], &v[d - 1], &t->change_rest, &t->change_rest_err);
    free(xin);
    free(v);
    return rc;
}
