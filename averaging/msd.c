#include <config.h>

#include "msd.h"

#include <fftw3.h>
#include <limits.h>
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

int mimas_msd_sums_init(mimas_msd_sums *s, size_t ncomp, size_t first, size_t nlags,
                        mimas_error *err)
{
    memset(s, 0, sizeof *s);
    s->first = first;
    s->num = calloc(ncomp * nlags + 1, sizeof *s->num);
    s->count = calloc(nlags + 1, sizeof *s->count);
    if (!s->num || !s->count) {
        mimas_msd_sums_free(s);
        return mimas_error_set(err, MIMAS_EIO, "out of memory");
    }
    s->ncomp = ncomp;
    s->nlags = nlags;
    return MIMAS_OK;
}

void mimas_msd_sums_add(mimas_msd_sums *to, const mimas_msd_sums *from)
{
    for (size_t k = 0; k < to->ncomp * to->nlags; k++)
        to->num[k] += from->num[k];
    for (size_t k = 0; k < to->nlags; k++)
        to->count[k] += from->count[k];
}

void mimas_msd_sums_free(mimas_msd_sums *s)
{
    free(s->num);
    free(s->count);
    memset(s, 0, sizeof *s);
}

struct mimas_msd {
    mimas_msd_kind kind;
    size_t T, K, ncomp;
    size_t nfft, nc;       /* transform length, complex values of a real transform */
    size_t cstride;        /* complex row stride of the block output */
    double *in;            /* [BLOCK][nfft] */
    fftw_complex *out;     /* [BLOCK][cstride] */
    double *qin;           /* one row: m or m x^2 of a particle with gaps */
    fftw_complex *qout;
    fftw_complex *mrows;   /* [BLOCK][nc]: the indicator spectra M of the block */
    fftw_complex *spec;    /* [nc]: a summed spectrum on its way back */
    double *real;          /* [nfft] */
    fftw_plan many, one, inv;
    double *acc_yy;        /* [ncomp][nc] sum |Y|^2 */
    double *acc_mq;        /* [ncomp][nc] sum 2 Re(conj(M) Q) (displacement, gaps) */
    double *acc_mm;        /* [nc] sum |M|^2 (gaps) */
    double *s1;            /* [ncomp][K+1] squares by the recursion (no gaps) */
    double *cnt;           /* [K+1] pairs of the particles without gaps */
    int gaps;              /* a particle with gaps since the last flush */
    double *sq;            /* [T] one series' squares */
};

/* The smallest 2^a 3^b 5^c 7^d >= n with a >= 1. */
size_t mimas_msd_fft_length(size_t frames, size_t max_lag)
{
    size_t n = frames + max_lag, best = SIZE_MAX;
    if (n < 2)
        n = 2;
    for (size_t p7 = 1; p7 < best && p7 <= 2 * n; p7 *= 7)
        for (size_t p5 = p7; p5 < best && p5 <= 2 * n; p5 *= 5)
            for (size_t p3 = p5; p3 < best && p3 <= 2 * n; p3 *= 3) {
                size_t v = 2 * p3;
                while (v < n)
                    v *= 2;
                if (v < best)
                    best = v;
            }
    return best;
}

static size_t even(size_t n) { return n + (n & 1); }

size_t mimas_msd_bytes(size_t frames, size_t max_lag, size_t ncomp)
{
    size_t nfft = mimas_msd_fft_length(frames, max_lag), nc = nfft / 2 + 1;
    size_t doubles = MIMAS_MSD_BLOCK * nfft + 2 * nfft + max_lag + 1 + frames
                     + (2 * ncomp + 1) * nc + (ncomp + 1) * (max_lag + 1);
    size_t complexes = MIMAS_MSD_BLOCK * (even(nc) + nc) + 2 * nc;
    return doubles * sizeof(double) + complexes * sizeof(fftw_complex);
}

void mimas_msd_free(mimas_msd *m)
{
    if (!m)
        return;
    if (m->many)
        fftw_destroy_plan(m->many);
    if (m->one)
        fftw_destroy_plan(m->one);
    if (m->inv)
        fftw_destroy_plan(m->inv);
    fftw_free(m->in);
    fftw_free(m->out);
    fftw_free(m->qin);
    fftw_free(m->qout);
    fftw_free(m->mrows);
    fftw_free(m->spec);
    fftw_free(m->real);
    free(m->acc_yy);
    free(m->acc_mq);
    free(m->acc_mm);
    free(m->s1);
    free(m->cnt);
    free(m->sq);
    free(m);
}

int mimas_msd_create(mimas_msd **out, mimas_msd_kind kind, size_t frames, size_t max_lag,
                     size_t ncomp, mimas_error *err)
{
    *out = NULL;
    if (frames < 1 || max_lag >= frames || ncomp < 1 || ncomp > 8)
        return mimas_error_set(err, MIMAS_EUSAGE, "correlations need lags below the %zu "
                               "frames and 1 to 8 components", frames);
    size_t nfft = mimas_msd_fft_length(frames, max_lag);
    if (nfft > INT_MAX)
        return mimas_error_set(err, MIMAS_EUSAGE, "%zu frames are too many for one transform",
                               frames);
    mimas_msd *m = calloc(1, sizeof *m);
    if (!m)
        return mimas_error_set(err, MIMAS_EIO, "out of memory");
    m->kind = kind;
    m->T = frames;
    m->K = max_lag;
    m->ncomp = ncomp;
    m->nfft = nfft;
    m->nc = nfft / 2 + 1;
    m->cstride = even(m->nc);
    size_t B = MIMAS_MSD_BLOCK, nc = m->nc;
    m->in = fftw_alloc_real(B * nfft);
    m->out = fftw_alloc_complex(B * m->cstride);
    m->qin = fftw_alloc_real(nfft);
    m->qout = fftw_alloc_complex(nc);
    m->mrows = fftw_alloc_complex(B * nc);
    m->spec = fftw_alloc_complex(nc);
    m->real = fftw_alloc_real(nfft + max_lag + 1);
    m->acc_yy = calloc(ncomp * nc, sizeof *m->acc_yy);
    m->acc_mq = calloc(ncomp * nc, sizeof *m->acc_mq);
    m->acc_mm = calloc(nc, sizeof *m->acc_mm);
    m->s1 = calloc(ncomp * (max_lag + 1), sizeof *m->s1);
    m->cnt = calloc(max_lag + 1, sizeof *m->cnt);
    m->sq = malloc(frames * sizeof *m->sq);
    if (!m->in || !m->out || !m->qin || !m->qout || !m->mrows || !m->spec || !m->real ||
        !m->acc_yy || !m->acc_mq || !m->acc_mm || !m->s1 || !m->cnt || !m->sq) {
        mimas_msd_free(m);
        return mimas_error_set(err, MIMAS_EIO, "out of memory");
    }
    /* rows beyond a short block are transformed too: keep them finite */
    memset(m->in, 0, B * nfft * sizeof *m->in);
    int n = (int)nfft;
    m->many = fftw_plan_many_dft_r2c(1, &n, (int)B, m->in, NULL, 1, n, m->out, NULL, 1,
                                     (int)m->cstride, FFTW_ESTIMATE);
    m->one = fftw_plan_dft_r2c_1d(n, m->qin, m->qout, FFTW_ESTIMATE);
    m->inv = fftw_plan_dft_c2r_1d(n, m->spec, m->real, FFTW_ESTIMATE);
    if (!m->many || !m->one || !m->inv) {
        mimas_msd_free(m);
        return mimas_error_set(err, MIMAS_EIO, "FFTW could not plan transforms of length %zu",
                               nfft);
    }
    *out = m;
    return MIMAS_OK;
}

/* A particle of the block: its span of frames a .. a+len-1 (len 0: never
 * present), whether it is absent inside the span, and (displacements) the
 * reference taken off its values: the first record present from the middle
 * of the span on, close to the mean (small values round less) and a value
 * of the data (a particle at rest has exactly zero displacements). */
typedef struct span {
    size_t a, len;
    int gaps;
    double ref[8];
} span;

static int present(const double *rec) { return !isnan(rec[0]); }

static void find_span(const mimas_msd *m, const double *x, size_t stride, span *s)
{
    memset(s, 0, sizeof *s);
    size_t first = m->T, last = 0, n = 0;
    for (size_t t = 0; t < m->T; t++)
        if (present(x + t * stride)) {
            if (first == m->T)
                first = t;
            last = t;
            n++;
        }
    if (!n)
        return;
    s->a = first;
    s->len = last - first + 1;
    s->gaps = n < s->len;
    if (m->kind != MIMAS_MSD_DISPLACEMENT)
        return;
    size_t mid = first + (last - first) / 2;
    while (!present(x + mid * stride))
        mid++; /* ends at last at the latest */
    for (size_t c = 0; c < m->ncomp; c++)
        s->ref[c] = x[mid * stride + c];
}

/* The series value at span frame t: x - ref, or 0 where absent. */
static double value(const mimas_msd *m, const double *x, size_t stride, const span *s,
                    size_t t, size_t c)
{
    const double *rec = x + (s->a + t) * stride;
    (void)m;
    return present(rec) ? rec[c] - s->ref[c] : 0.0;
}

/* qin = the indicator (c == SIZE_MAX) or m x^2 of component c, transformed. */
static void transform_one(mimas_msd *m, const double *x, size_t stride, const span *s, size_t c)
{
    memset(m->qin, 0, m->nfft * sizeof *m->qin);
    for (size_t t = 0; t < s->len; t++) {
        if (c == SIZE_MAX) {
            m->qin[t] = present(x + (s->a + t) * stride) ? 1.0 : 0.0;
        } else {
            double v = value(m, x, stride, s, t, c);
            m->qin[t] = v * v;
        }
    }
    fftw_execute(m->one);
}

/* The pairs of a particle without gaps. */
static void add_counts(mimas_msd *m, const span *s)
{
    size_t L = s->len, kmax = L - 1 < m->K ? L - 1 : m->K;
    for (size_t k = 0; k <= kmax; k++)
        m->cnt[k] += (double)(L - k);
}

/* The squares sum_{t <= L-1-k} (x_t^2 + x_{t+k}^2) of component c of a
 * particle without gaps, from its series row, by the recursion
 * S(0) = 2 sum x^2, S(k) = S(k-1) - x_{k-1}^2 - x_{L-k}^2. */
static void add_squares(mimas_msd *m, const double *row, const span *s, size_t c)
{
    size_t L = s->len, kmax = L - 1 < m->K ? L - 1 : m->K;
    double total = 0;
    for (size_t t = 0; t < L; t++) {
        m->sq[t] = row[t] * row[t];
        total += m->sq[t];
    }
    double S = 2 * total, *s1 = m->s1 + c * (m->K + 1);
    s1[0] += S;
    for (size_t k = 1; k <= kmax; k++) {
        S -= m->sq[k - 1] + m->sq[L - k];
        s1[k] += S;
    }
}

/* Up to BLOCK particles. */
static void add_block(mimas_msd *m, const double *series, size_t n, size_t stride)
{
    size_t nfft = m->nfft, nc = m->nc, T = m->T;
    span sp[MIMAS_MSD_BLOCK];
    for (size_t j = 0; j < n; j++) {
        const double *x = series + j * T * stride;
        find_span(m, x, stride, &sp[j]);
        if (!sp[j].len)
            continue;
        if (!sp[j].gaps) {
            add_counts(m, &sp[j]);
            continue;
        }
        /* the indicator spectrum: counts, and kept for the cross terms */
        m->gaps = 1;
        transform_one(m, x, stride, &sp[j], SIZE_MAX);
        memcpy(m->mrows + j * nc, m->qout, nc * sizeof *m->qout);
        for (size_t w = 0; w < nc; w++)
            m->acc_mm[w] += m->qout[w][0] * m->qout[w][0] + m->qout[w][1] * m->qout[w][1];
    }
    for (size_t c = 0; c < m->ncomp; c++) {
        for (size_t j = 0; j < n; j++) {
            double *row = m->in + j * nfft;
            memset(row, 0, nfft * sizeof *row);
            const double *x = series + j * T * stride;
            for (size_t t = 0; t < sp[j].len; t++)
                row[t] = value(m, x, stride, &sp[j], t, c);
            if (sp[j].len && !sp[j].gaps && m->kind == MIMAS_MSD_DISPLACEMENT)
                add_squares(m, row, &sp[j], c);
        }
        fftw_execute(m->many);
        double *yy = m->acc_yy + c * nc, *mq = m->acc_mq + c * nc;
        for (size_t j = 0; j < n; j++) {
            if (!sp[j].len)
                continue;
            const fftw_complex *Y = m->out + j * m->cstride;
            for (size_t w = 0; w < nc; w++)
                yy[w] += Y[w][0] * Y[w][0] + Y[w][1] * Y[w][1];
            if (!sp[j].gaps || m->kind != MIMAS_MSD_DISPLACEMENT)
                continue;
            /* sum m_t q_{t+k} + q_t m_{t+k}: spectrum 2 Re(conj(M) Q) */
            const double *x = series + j * T * stride;
            transform_one(m, x, stride, &sp[j], c);
            const fftw_complex *M = m->mrows + j * nc;
            for (size_t w = 0; w < nc; w++)
                mq[w] += 2 * (M[w][0] * m->qout[w][0] + M[w][1] * m->qout[w][1]);
        }
    }
}

int mimas_msd_add(mimas_msd *m, const double *series, size_t n, size_t stride,
                  mimas_error *err)
{
    if (stride < m->ncomp)
        return mimas_error_set(err, MIMAS_EUSAGE, "a record stride below the components");
    for (size_t j = 0; j < n; j += MIMAS_MSD_BLOCK) {
        size_t b = n - j < MIMAS_MSD_BLOCK ? n - j : MIMAS_MSD_BLOCK;
        add_block(m, series + j * m->T * stride, b, stride);
    }
    return MIMAS_OK;
}

/* The inverse transform of a real spectrum acc (zeroed afterwards) into
 * m->real, divided by the length: the correlation at lags 0 .. K. */
static void back(mimas_msd *m, double *acc)
{
    for (size_t w = 0; w < m->nc; w++) {
        m->spec[w][0] = acc[w];
        m->spec[w][1] = 0;
        acc[w] = 0;
    }
    fftw_execute(m->inv);
    double scale = 1.0 / (double)m->nfft;
    for (size_t k = 0; k <= m->K; k++)
        m->real[k] *= scale;
}

/* Adds the lags of v (lags 0 .. K) that sums cover to row (of s's rows). */
static void add_lags(const mimas_msd *m, mimas_msd_sums *s, double *row, const double *v)
{
    for (size_t k = s->first; k < s->first + s->nlags && k <= m->K; k++)
        row[k - s->first] += v[k];
}

int mimas_msd_flush(mimas_msd *m, mimas_msd_sums *s, size_t ns, mimas_error *err)
{
    size_t K1 = m->K + 1;
    for (size_t q = 0; q < ns; q++)
        if (s[q].ncomp != m->ncomp || s[q].first + s[q].nlags > K1)
            return mimas_error_set(err, MIMAS_EUSAGE, "sums of another shape");
    int disp = m->kind == MIMAS_MSD_DISPLACEMENT;
    /* the particles' sums at every lag, then into each of s */
    double *num = m->real + m->nfft; /* [K1], after the transform's output */
    for (size_t c = 0; c < m->ncomp; c++) {
        double *s1 = m->s1 + c * K1;
        back(m, m->acc_yy + c * m->nc);
        for (size_t k = 0; k < K1; k++)
            num[k] = disp ? s1[k] - 2 * m->real[k] : m->real[k];
        memset(s1, 0, K1 * sizeof *s1);
        if (disp && m->gaps) {
            back(m, m->acc_mq + c * m->nc);
            for (size_t k = 0; k < K1; k++)
                num[k] += m->real[k];
        }
        /* a displacement at lag 0 is zero: not left to the rounding */
        if (disp)
            num[0] = 0;
        for (size_t q = 0; q < ns; q++)
            add_lags(m, &s[q], s[q].num + c * s[q].nlags, num);
    }
    if (m->gaps) {
        back(m, m->acc_mm);
        for (size_t k = 0; k < K1; k++)
            m->cnt[k] += nearbyint(m->real[k]);
    }
    for (size_t q = 0; q < ns; q++)
        add_lags(m, &s[q], s[q].count, m->cnt);
    memset(m->cnt, 0, K1 * sizeof *m->cnt);
    m->gaps = 0;
    return MIMAS_OK;
}
