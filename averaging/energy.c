#include <config.h>

#include "energy.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#include "native.h"
#include "thermo_log.h"

static const char *const names[MIMAS_ENERGY_N] = {"total", "kinetic", "rotational", "elastic",
                                                  "bridge"};
/* the observables of mimas simulate, by quantity (total is computed) */
static const char *const observables[MIMAS_ENERGY_N] = {NULL, "kinetic_energy",
                                                        "rotational_energy", "elastic_energy",
                                                        "bridge_energy"};

const char *mimas_energy_name(int q)
{
    return q >= 0 && q < MIMAS_ENERGY_N ? names[q] : NULL;
}

void mimas_energy_options_default(mimas_energy_options *o)
{
    memset(o, 0, sizeof *o);
    o->from = -INFINITY;
    o->to = INFINITY;
}

/* Welford's running mean and sum of squared deviations */
typedef struct running {
    size_t n;
    double mean, m2;
} running;

static void running_add(running *r, double v)
{
    double d = v - r->mean;
    r->mean += d / (double)++r->n;
    r->m2 += d * (v - r->mean);
}

typedef struct accumulator {
    running r[MIMAS_ENERGY_N];
    mimas_energy *e;
} accumulator;

static void start(accumulator *a, mimas_energy *e)
{
    memset(a, 0, sizeof *a);
    memset(e, 0, sizeof *e);
    a->e = e;
    e->from = e->to = NAN;
}

/* One frame at time t: v[q] for the quantities (NaN: not in this frame). */
static void add_frame(accumulator *a, double t, double *v, int total_given)
{
    if (!total_given)
        v[MIMAS_ENERGY_TOTAL] = v[MIMAS_ENERGY_KINETIC] + v[MIMAS_ENERGY_ROTATIONAL];
    for (int q = 0; q < MIMAS_ENERGY_N; q++)
        if (isfinite(v[q]))
            running_add(&a->r[q], v[q]);
    if (!a->e->frames++)
        a->e->from = t;
    a->e->to = t;
}

static void finish(accumulator *a)
{
    for (int q = 0; q < MIMAS_ENERGY_N; q++) {
        mimas_energy_stat *s = &a->e->q[q];
        const running *r = &a->r[q];
        s->n = r->n;
        s->mean = r->n ? r->mean : NAN;
        s->sd = r->n > 1 ? sqrt(r->m2 / (double)(r->n - 1)) : NAN;
        s->cv = s->sd / s->mean;
    }
}

/* 1 if t is in the window; -1 (err set) if the window needs a time t lacks. */
static int in_window(const mimas_energy_options *o, double t, const char *path,
                     mimas_error *err)
{
    int open = !isfinite(o->from) && !isfinite(o->to);
    if (open)
        return 1;
    if (isnan(t)) {
        mimas_error_set(err, MIMAS_EUSAGE, "%s: the times are unknown (no Time column and no "
                        "timestep command in the log): give --timestep to use --from and --to",
                        path);
        return -1;
    }
    return t >= o->from && t <= o->to;
}

static int of_native(const char *path, const mimas_energy_options *o, mimas_energy *e,
                     mimas_error *err)
{
    mimas_native *r;
    int rc = mimas_native_open(&r, path, err);
    if (rc)
        return rc;
    accumulator a;
    start(&a, e);
    long index[MIMAS_ENERGY_N];
    int any = 0;
    for (int q = 0; q < MIMAS_ENERGY_N; q++) {
        index[q] = -1;
        for (size_t i = 0; observables[q] && i < mimas_native_observables(r); i++)
            if (!strcmp(mimas_native_observable_name(r, i, NULL), observables[q]))
                index[q] = (long)i;
        e->q[q].present = index[q] >= 0;
        any |= index[q] >= 0;
    }
    e->q[MIMAS_ENERGY_TOTAL].present = index[MIMAS_ENERGY_KINETIC] >= 0 &&
                                       index[MIMAS_ENERGY_ROTATIONAL] >= 0;
    if (!any)
        rc = mimas_error_set(err, MIMAS_EDATA, "%s: no energy observables (mimas simulate "
                             "writes them to /observables/all)", path);
    size_t frames = mimas_native_frames(r);
    for (size_t k = 0; !rc && k < frames; k++) {
        mimas_frame_meta m;
        rc = mimas_native_frame_meta(r, k, &m, err);
        int take = rc ? 0 : in_window(o, m.time, path, err);
        if (take < 0)
            rc = err->code;
        if (take <= 0)
            continue;
        double v[MIMAS_ENERGY_N];
        for (int q = 0; !rc && q < MIMAS_ENERGY_N; q++) {
            v[q] = NAN;
            if (index[q] >= 0)
                rc = mimas_native_observable_read(r, (size_t)index[q], k, 1, &v[q], err);
        }
        if (!rc)
            add_frame(&a, m.time, v, 0);
    }
    mimas_native_close(r);
    finish(&a);
    return rc;
}

static int of_log(const char *path, const mimas_energy_options *o, mimas_energy *e,
                  mimas_error *err)
{
    const char *cols[MIMAS_ENERGY_N];
    size_t idx[MIMAS_ENERGY_N], n = 0;
    for (int q = 0; q < MIMAS_ENERGY_N; q++) {
        const char *c = o->columns[q] ? o->columns[q] : q == MIMAS_ENERGY_KINETIC ? "KinEng"
                                                                                   : NULL;
        idx[q] = (size_t)-1;
        if (c) {
            idx[q] = n;
            cols[n++] = c;
        }
    }
    mimas_thermo_log *log;
    int rc = mimas_thermo_log_open(&log, path, cols, n, o->dt, err);
    if (rc)
        return rc;
    accumulator a;
    start(&a, e);
    int total_given = o->columns[MIMAS_ENERGY_TOTAL] != NULL;
    int64_t step;
    double t, row[MIMAS_ENERGY_N];
    while (!rc && (rc = mimas_thermo_log_next(log, &step, &t, row, err)) == MIMAS_OK) {
        int take = in_window(o, t, path, err);
        if (take < 0)
            rc = err->code;
        if (take <= 0)
            continue;
        double v[MIMAS_ENERGY_N];
        for (int q = 0; q < MIMAS_ENERGY_N; q++)
            v[q] = idx[q] != (size_t)-1 ? row[idx[q]] : NAN;
        add_frame(&a, t, v, total_given);
    }
    if (rc == MIMAS_END)
        rc = MIMAS_OK;
    int any = 0;
    for (int q = 0; q < MIMAS_ENERGY_N; q++) {
        e->q[q].present = idx[q] != (size_t)-1 && mimas_thermo_log_has(log, idx[q]);
        any |= e->q[q].present;
    }
    if (!total_given)
        e->q[MIMAS_ENERGY_TOTAL].present = e->q[MIMAS_ENERGY_KINETIC].present &&
                                           e->q[MIMAS_ENERGY_ROTATIONAL].present;
    mimas_thermo_log_close(log);
    if (!rc && !any) {
        char list[256] = "";
        for (size_t k = 0, at = 0; k < n && at < sizeof list; k++)
            at += (size_t)snprintf(list + at, sizeof list - at, "%s%s", k ? ", " : "", cols[k]);
        rc = mimas_error_set(err, MIMAS_EDATA, "%s: no thermo output with %s", path,
                             n ? list : "any column asked for");
    }
    finish(&a);
    return rc;
}

int mimas_energy_of(const char *path, const mimas_energy_options *o, mimas_energy *e,
                    mimas_error *err)
{
    memset(e, 0, sizeof *e);
    FILE *fp = fopen(path, "rb");
    char head[16] = {0};
    size_t n = fp ? fread(head, 1, sizeof head, fp) : 0;
    if (fp)
        fclose(fp);
    if (!fp)
        return mimas_error_set(err, MIMAS_EDATA, "%s: cannot open", path);
    int rc;
    if (n >= 8 && !memcmp(head, "\x89HDF\r\n\x1a\n", 8))
        rc = of_native(path, o, e, err);
    else if (mimas_thermo_log_probe(head, n) || (n >= 2 && !memcmp(head, "\x1f\x8b", 2)))
        rc = of_log(path, o, e, err);
    else
        rc = mimas_error_set(err, MIMAS_EDATA, "%s: neither a native file nor a LAMMPS or "
                             "LIGGGHTS log", path);
    if (!rc && e->frames == 0)
        rc = mimas_error_set(err, MIMAS_EDATA, "%s: no frame in the selected time range", path);
    return rc;
}
