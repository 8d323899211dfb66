/* The reader interface: picks the backend (by --format, else by the content
 * of the first input) and passes frames through. */
#include <config.h>

#include "reader.h"

#include <errno.h>
#include <glob.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <zlib.h>

#include "backend.h"

static const reader_backend *const backends[] = {&reader_native, &reader_lammps,
                                                 &reader_mercury};
#define NBACKENDS (sizeof backends / sizeof backends[0])

struct mimas_reader {
    const reader_backend *be;
    void *state;
    char **inputs;   /* after '*' expansion */
    size_t ninputs;
    mimas_reader_options opt;
    /* the frames so far: steps increase, times do not decrease */
    int have_last;
    int64_t last_step;
    double last_time;
    int order_checked;   /* the next frame's step and time were checked by peek */
    mimas_frame ahead;   /* a frame read by peek for a format that cannot peek */
    int has_ahead;
};

void mimas_reader_options_default(mimas_reader_options *o)
{
    memset(o, 0, sizeof *o);
}

int reader_expand_names(const char *const *in, size_t n, char ***out, size_t *nout,
                        mimas_error *err)
{
    char **names = NULL;
    size_t count = 0;
    for (size_t k = 0; k < n; k++) {
        glob_t g;
        memset(&g, 0, sizeof g);
        int globbed = strchr(in[k], '*') && glob(in[k], 0, NULL, &g) == 0;
        size_t add = globbed ? g.gl_pathc : 1;
        char **grown = realloc(names, (count + add) * sizeof *grown);
        int ok = grown != NULL;
        if (grown)
            names = grown;
        for (size_t m = 0; ok && m < add; m++) {
            char *name = strdup(globbed ? g.gl_pathv[m] : in[k]);
            ok = name != NULL;
            if (name)
                names[count++] = name;
        }
        if (globbed)
            globfree(&g);
        if (!ok) {
            reader_free_names(names, count);
            return mimas_error_set(err, MIMAS_EIO, "out of memory for the list of inputs");
        }
    }
    *out = names;
    *nout = count;
    return MIMAS_OK;
}

void reader_free_names(char **names, size_t n)
{
    for (size_t k = 0; k < n; k++)
        free(names[k]);
    free(names);
}

/* The first bytes of a file, decompressed if it is gzip. */
static int peek(const char *path, char *head, size_t cap, size_t *n)
{
    gzFile gz = gzopen(path, "rb");
    if (!gz)
        return -1;
    int got = gzread(gz, head, (unsigned)cap);
    gzclose(gz);
    *n = got > 0 ? (size_t)got : 0;
    return 0;
}

static int detect(mimas_reader *r, mimas_error *err)
{
    const char *path = r->inputs[0];
    if (r->opt.format) {
        for (size_t k = 0; k < NBACKENDS; k++)
            if (!strcmp(r->opt.format, backends[k]->name)) {
                r->be = backends[k];
                return MIMAS_OK;
            }
        return mimas_error_set(err, MIMAS_EUSAGE,
                               "unknown format '%s' (native, lammps or mercury)", r->opt.format);
    }
    char head[4096];
    size_t n;
    /* HDF5 first, on the raw bytes (gzread would pass them through anyway) */
    if (peek(path, head, sizeof head - 1, &n) != 0)
        return mimas_error_set(err, MIMAS_EDATA, "%s: cannot open: %s", path, strerror(errno));
    if (n == 0)
        return mimas_error_set(err, MIMAS_EDATA, "%s: empty file", path);
    head[n] = '\0';
    for (size_t k = 0; k < NBACKENDS; k++)
        if (backends[k]->probe(path, head, n)) {
            r->be = backends[k];
            return MIMAS_OK;
        }
    return mimas_error_set(err, MIMAS_EDATA,
                           "%s:1: not a format mimas reads (native HDF5, LAMMPS/LIGGGHTS dump, "
                           "MercuryDPM .data); --format names one", path);
}

void mimas_reader_close(mimas_reader *r)
{
    if (!r)
        return;
    if (r->be && r->state)
        r->be->close(r->state);
    reader_free_names(r->inputs, r->ninputs);
    mimas_frame_free(&r->ahead);
    free(r);
}

/* "out of memory for ..." names the file it happened in */
static int name_the_file(int rc, const char *path, mimas_error *err)
{
    if (rc == MIMAS_EIO && err && !strncmp(err->msg, "out of memory", 13))
        mimas_error_prefix(err, "%s", path);
    return rc;
}

/* Every input (and contact file) exists, is a regular file (or a pipe) and is
 * given once: the same file twice would count its frames twice. */
static int check_files(const char *const *names, size_t n, const char *const *more,
                       size_t nmore, mimas_error *err)
{
    size_t total = n + nmore;
    struct stat *st = malloc((total ? total : 1) * sizeof *st);
    if (!st)
        return mimas_error_set(err, MIMAS_EIO, "out of memory for the list of %zu inputs",
                               total);
    int rc = MIMAS_OK;
    for (size_t k = 0; k < total && !rc; k++) {
        const char *name = k < n ? names[k] : more[k - n];
        if (stat(name, &st[k]) != 0)
            rc = mimas_error_set(err, MIMAS_EDATA, "%s: cannot open: %s", name, strerror(errno));
        else if (S_ISDIR(st[k].st_mode))
            rc = mimas_error_set(err, MIMAS_EDATA, "%s: is a directory, not a data file", name);
        for (size_t m = 0; m < k && !rc; m++)
            if (st[m].st_dev == st[k].st_dev && st[m].st_ino == st[k].st_ino &&
                S_ISREG(st[k].st_mode))
                rc = mimas_error_set(err, MIMAS_EUSAGE, "%s: given twice (as %s too): its "
                                     "frames would count twice", name,
                                     m < n ? names[m] : more[m - n]);
    }
    free(st);
    return rc;
}

int mimas_reader_open(mimas_reader **out, const char *const *inputs, size_t ninputs,
                      const mimas_reader_options *o, mimas_error *err)
{
    *out = NULL;
    if (ninputs == 0)
        return mimas_error_set(err, MIMAS_EUSAGE, "no input file");
    mimas_reader *r = calloc(1, sizeof *r);
    if (!r)
        return mimas_error_set(err, MIMAS_EIO, "out of memory for the list of inputs");
    if (o)
        r->opt = *o;
    mimas_frame_init(&r->ahead);
    if (r->opt.density < 0 || r->opt.timestep < 0) {
        free(r);
        return mimas_error_set(err, MIMAS_EUSAGE, "density and time step must be positive");
    }
    int rc = reader_expand_names(inputs, ninputs, &r->inputs, &r->ninputs, err);
    if (!rc) {
        /* contact files as given ('*' patterns are expanded by the backend) */
        size_t nside = r->opt.ncontacts + r->opt.nwalls, ns = 0;
        const char **side = malloc((nside ? nside : 1) * sizeof *side);
        for (size_t k = 0; side && k < nside; k++) {
            const char *name = k < r->opt.ncontacts ? r->opt.contacts[k]
                                                    : r->opt.walls[k - r->opt.ncontacts];
            if (!strchr(name, '*'))
                side[ns++] = name;
        }
        rc = side ? check_files((const char *const *)r->inputs, r->ninputs, side, ns, err)
                  : mimas_error_set(err, MIMAS_EIO, "out of memory for the list of inputs");
        free(side);
    }
    if (!rc)
        rc = detect(r, err);
    if (!rc)
        rc = name_the_file(r->be->open(&r->state, (const char *const *)r->inputs, r->ninputs,
                                       &r->opt, err),
                           r->inputs[0], err);
    if (rc) {
        r->state = NULL;
        mimas_reader_close(r);
        return rc;
    }
    *out = r;
    return MIMAS_OK;
}

/* Masses from --density for inputs without them: m = rho 4/3 pi R^3. */
static int add_masses(mimas_particles *p, double density, mimas_error *err)
{
    int rc = mimas_table_set_present(p, &mimas_particles_desc, MIMAS_P_MASS, err);
    for (size_t k = 0; !rc && k < p->n; k++)
        p->mass[k] = density * 4.0 / 3.0 * M_PI * p->radius[k] * p->radius[k] * p->radius[k];
    return rc;
}

/* Steps increase and times do not decrease over all inputs; records the
 * frame as the last one. */
static int check_order(mimas_reader *r, int64_t step, double time, mimas_error *err)
{
    int rc = MIMAS_OK;
    if (r->have_last && step <= r->last_step)
        rc = mimas_error_set(err, MIMAS_EDATA, "step %lld follows step %lld: frames are "
                             "repeated or out of order (the same data given twice?)",
                             (long long)step, (long long)r->last_step);
    if (!rc && r->have_last && isnan(time) != isnan(r->last_time))
        rc = mimas_error_set(err, MIMAS_EDATA, "some frames have a time and others not "
                             "(give --timestep, or inputs of one kind)");
    if (!rc && r->have_last && time < r->last_time)
        rc = mimas_error_set(err, MIMAS_EDATA, "time %.17g follows time %.17g: frames are "
                             "repeated or out of order (the same data given twice?)", time,
                             r->last_time);
    if (rc)
        return rc;
    r->have_last = 1;
    r->last_step = step;
    r->last_time = time;
    return MIMAS_OK;
}

static double time_of(const mimas_reader *r, int64_t step, double time)
{
    return isnan(time) && r->opt.timestep > 0 ? (double)step * r->opt.timestep : time;
}

/* What holds for the frames of every format: --timestep and --density fill
 * what the input lacks, the values are usable (mimas_frame_check), steps
 * increase and times do not decrease over all inputs (unless a peek checked
 * that already), and positions lie in the box along its periodic
 * directions. */
static int settle_frame(mimas_reader *r, mimas_frame *f, mimas_error *err)
{
    f->time = time_of(r, f->step, f->time);
    mimas_particles *p = &f->particles;
    int rc = MIMAS_OK;
    if (r->opt.density > 0 && !(p->present & MIMAS_P_MASS) && (p->present & MIMAS_P_RADIUS))
        rc = add_masses(p, r->opt.density, err);
    if (!rc)
        rc = mimas_frame_check(f, err);
    if (!rc && !r->order_checked)
        rc = check_order(r, f->step, f->time, err);
    if (!rc)
        rc = mimas_frame_wrap(f, err);
    if (rc)
        return mimas_error_prefix(err, "%s: step %lld", r->be->source(r->state),
                                  (long long)f->step);
    return MIMAS_OK;
}

int mimas_reader_next(mimas_reader *r, mimas_frame *f, mimas_error *err)
{
    if (r->has_ahead) {
        /* hand over the frame read ahead (settled then); f's memory is kept
         * for the next one */
        mimas_frame t = *f;
        *f = r->ahead;
        r->ahead = t;
        r->has_ahead = 0;
        r->order_checked = 0;
        return MIMAS_OK;
    }
    int rc = r->be->next(r->state, f, err);
    if (rc && rc != MIMAS_END)
        return name_the_file(rc, r->be->source(r->state), err);
    if (!rc)
        rc = settle_frame(r, f, err);
    r->order_checked = 0;
    return rc;
}

int mimas_reader_peek(mimas_reader *r, int64_t *step, double *time, mimas_error *err)
{
    if (r->has_ahead || r->order_checked) {
        if (r->has_ahead)
            *step = r->ahead.step, *time = r->ahead.time;
        else
            *step = r->last_step, *time = r->last_time;
        return MIMAS_OK;
    }
    if (!r->be->peek) {
        /* read the frame now: the next mimas_reader_next hands it over */
        int rc = mimas_reader_next(r, &r->ahead, err);
        if (rc)
            return rc;
        r->has_ahead = 1;
        r->order_checked = 1;
        *step = r->ahead.step;
        *time = r->ahead.time;
        return MIMAS_OK;
    }
    int rc = r->be->peek(r->state, step, time, err);
    if (rc && rc != MIMAS_END)
        return name_the_file(rc, r->be->source(r->state), err);
    if (rc)
        return rc;
    *time = time_of(r, *step, *time);
    rc = check_order(r, *step, *time, err);
    if (rc)
        return mimas_error_prefix(err, "%s: step %lld", r->be->source(r->state),
                                  (long long)*step);
    r->order_checked = 1;
    return MIMAS_OK;
}

int mimas_reader_skip(mimas_reader *r, mimas_error *err)
{
    int64_t step;
    double time;
    int rc = mimas_reader_peek(r, &step, &time, err);
    if (rc)
        return rc;
    if (r->has_ahead) {
        r->has_ahead = 0;
    } else {
        rc = r->be->skip ? r->be->skip(r->state, err) : MIMAS_OK;
        if (rc)
            return name_the_file(rc, r->be->source(r->state), err);
    }
    r->order_checked = 0;
    return MIMAS_OK;
}

const char *mimas_reader_format(const mimas_reader *r)
{
    return r->be->title;
}

size_t mimas_reader_skipped(const mimas_reader *r)
{
    return r->be->skipped ? r->be->skipped(r->state) : 0;
}

size_t mimas_reader_total(const mimas_reader *r)
{
    return r->be->total ? r->be->total(r->state) : 0;
}

const mimas_parameters *mimas_reader_parameters(const mimas_reader *r)
{
    static const mimas_parameters none = {0, 0, NULL};
    return r->be->parameters ? r->be->parameters(r->state) : &none;
}
