/* Time correlations of particle trajectories by FFT (docs/disperse.md,
 * "Algorithm"): for every component c of a particle's series x_t
 * (t = 0 .. frames-1; a record whose first value is NaN is absent, m_t = 0),
 * summed over the particles and over the time origins t at which both
 * frames are present,
 *   displacement:    num_c(k) = sum m_t m_{t+k} (x_{t+k} - x_t)^2
 *   autocorrelation: num_c(k) = sum m_t m_{t+k} x_t x_{t+k}
 * and the pair count(k) = sum m_t m_{t+k}, for the lags k = 0 .. max_lag;
 * num/count is the mean-square displacement or the autocorrelation.
 *
 * The algorithm of Calandrini et al. (2011), as freud and tidynamics use
 * it: the squares part of the displacement by the sum-of-squares recursion,
 * the products x_t x_{t+k} by an FFTW autocorrelation zero-padded to at least
 * frames + max_lag, O(T log T) per particle.  A particle absent inside its
 * span (a gap) is handled by indicator-weighted correlations: sum m_t m_{t+k}
 * x_{t+k}^2 and the count come from the cross-correlation of m with m x^2 and
 * the autocorrelation of m, so each lag counts only pairs that exist.
 * Because every particle's correlation is a sum of such transforms, the
 * power spectra are summed over particles and transformed back once per
 * flush.  For displacements a position near the middle of each particle's
 * span is taken off first (the displacements do not change, the rounding
 * does).
 *
 * A workspace transforms MIMAS_MSD_BLOCK particles at a time with FFTW plans
 * made once at creation (FFTW_ESTIMATE: the same numbers on every run, for
 * any order of blocks); plan creation is not thread-safe, so create
 * workspaces outside parallel regions.  Workspaces are independent: the
 * particles may be split among threads or processes and their sums added. */
#ifndef MIMAS_MSD_H
#define MIMAS_MSD_H

#include <stddef.h>

#include "error.h"

#ifdef __cplusplus
extern "C" {
#endif

#define MIMAS_MSD_BLOCK 16

typedef enum mimas_msd_kind {
    MIMAS_MSD_DISPLACEMENT,
    MIMAS_MSD_AUTOCORRELATION
} mimas_msd_kind;

/* The sums of a set of particles over the lags first .. first+nlags-1. */
typedef struct mimas_msd_sums {
    size_t ncomp, first, nlags;
    double *num;     /* [ncomp][nlags] */
    double *count;   /* [nlags] pairs */
} mimas_msd_sums;

int mimas_msd_sums_init(mimas_msd_sums *s, size_t ncomp, size_t first, size_t nlags,
                        mimas_error *err);
/* to += from (same shape). */
void mimas_msd_sums_add(mimas_msd_sums *to, const mimas_msd_sums *from);
void mimas_msd_sums_free(mimas_msd_sums *s);

typedef struct mimas_msd mimas_msd;

/* A workspace for series of frames records of ncomp components (1 to 8),
 * lags 0 .. max_lag (< frames). */
int mimas_msd_create(mimas_msd **m, mimas_msd_kind kind, size_t frames, size_t max_lag,
                     size_t ncomp, mimas_error *err);
/* Bytes a workspace of these sizes allocates. */
size_t mimas_msd_bytes(size_t frames, size_t max_lag, size_t ncomp);
/* The transform length used: the smallest 2^a 3^b 5^c 7^d (a >= 1) of at
 * least frames + max_lag. */
size_t mimas_msd_fft_length(size_t frames, size_t max_lag);
/* Adds n particles: series[j * frames * stride + t * stride + c] is
 * component c of particle j at frame t (stride >= ncomp). */
int mimas_msd_add(mimas_msd *m, const double *series, size_t n, size_t stride,
                  mimas_error *err);
/* Adds the sums of the particles added since the last flush to each of
 * the n sums s[] (of ncomp components; each over its lags, within 0 ..
 * max_lag) and starts afresh. */
int mimas_msd_flush(mimas_msd *m, mimas_msd_sums *s, size_t n, mimas_error *err);
void mimas_msd_free(mimas_msd *m);

#ifdef __cplusplus
}
#endif
#endif
