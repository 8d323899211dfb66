#include <config.h>

#include "sample_mean.h"

#include <math.h>

void mimas_sample_mean_add(mimas_sample_mean *a, double x)
{
    a->n++;
    double d = x - a->mean;
    a->mean += d / (double)a->n;
    a->m2 += d * (x - a->mean);
}

void mimas_sample_mean_get(const mimas_sample_mean *a, double *mean, double *sem, size_t *n)
{
    if (n)
        *n = a->n;
    *mean = a->n ? a->mean : NAN;
    *sem = a->n > 1 ? sqrt(fmax(0.0, a->m2) / (double)(a->n - 1) / (double)a->n) : NAN;
}
