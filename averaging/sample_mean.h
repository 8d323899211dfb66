/* The mean of a stream of samples with its standard error (Welford's
 * update), for results averaged over frames, plugs or tracks. */
#ifndef MIMAS_SAMPLE_MEAN_H
#define MIMAS_SAMPLE_MEAN_H

#include <stddef.h>

typedef struct mimas_sample_mean {
    size_t n;
    double mean, m2;   /* m2: sum of squared deviations from the mean */
} mimas_sample_mean;

void mimas_sample_mean_add(mimas_sample_mean *a, double x);
/* The mean (NaN without samples), its standard error sqrt(var/n) with the
 * n - 1 variance (NaN below two samples) and n. */
void mimas_sample_mean_get(const mimas_sample_mean *a, double *mean, double *sem, size_t *n);

#endif
