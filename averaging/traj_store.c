#include <config.h>

#include "traj_store.h"

#include <errno.h>
#include <hdf5.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "h5util.h"

/* frames per chunk at most, and the share of the memory one chunk may take */
#define MAX_CHUNK_FRAMES 128
#define CHUNK_SHARE 8
/* slots per chunk of the scratch dataset (the reads take blocks of slots) */
#define DISK_CHUNK_SLOTS 16
/* slots a write call takes */
#define WRITE_SLOTS (64 * DISK_CHUNK_SLOTS)
/* HDF5's metadata cache of the scratch file (its chunk index), at most */
#define METADATA_CACHE_BYTES ((size_t)2 << 20)

typedef struct chunk {
    size_t t0;       /* first frame */
    size_t nframes;  /* frames written */
    size_t cap;      /* frames the buffer holds */
    size_t nslots;   /* slots (rows) */
    double *data;    /* [nslots][cap][ncomp] */
} chunk;

struct mimas_traj_store {
    size_t ncomp, memory;
    char dir[4096];
    size_t frames, slots;
    size_t chunk_frames;   /* chosen at the first frame */
    chunk cur;             /* being filled */
    chunk *kept;           /* finished, in memory */
    size_t nkept, capkept, kept_bytes;
    int finished, on_disk;
    hid_t file, dset;
    size_t disk_slots, disk_frames;
    h5_quiet quiet;
};

static size_t chunk_bytes(const mimas_traj_store *s, size_t nslots, size_t cap)
{
    return nslots * cap * s->ncomp * sizeof(double);
}

static void fill_absent(double *p, size_t n)
{
    for (size_t k = 0; k < n; k++)
        p[k] = NAN;
}

int mimas_traj_store_create(mimas_traj_store **out, const mimas_traj_store_options *o,
                            mimas_error *err)
{
    *out = NULL;
    if (o->ncomp < 1 || o->ncomp > 8)
        return mimas_error_set(err, MIMAS_EUSAGE, "a trajectory record has 1 to 8 values");
    mimas_traj_store *s = calloc(1, sizeof *s);
    if (!s)
        return mimas_error_set(err, MIMAS_EIO, "out of memory");
    s->ncomp = o->ncomp;
    s->memory = o->memory;
    const char *dir = o->scratch_dir;
    if (!dir || !*dir)
        dir = getenv("TMPDIR");
    snprintf(s->dir, sizeof s->dir, "%s", dir && *dir ? dir : "/tmp");
    s->file = s->dset = -1;
    *out = s;
    return MIMAS_OK;
}

static int h5_fail(mimas_traj_store *s, const char *what, mimas_error *err)
{
    char text[256];
    h5_error_text(text, sizeof text);
    return mimas_error_set(err, MIMAS_EIO, "scratch file in %s: cannot %s%s%s", s->dir, what,
                           text[0] ? ": " : "", text);
}

/* Creates the scratch file (unlinked at once) and its dataset
 * [slots][frames][ncomp], NaN where nothing was written. */
static int open_disk(mimas_traj_store *s, mimas_error *err)
{
    char path[4200];
    snprintf(path, sizeof path, "%s/.mimas-disperse-XXXXXX", s->dir);
    int fd = mkstemp(path);
    if (fd < 0)
        return mimas_error_set(err, MIMAS_EIO, "cannot make a scratch file in %s: %s", s->dir,
                               strerror(errno));
    close(fd);
    h5_quiet_begin(&s->quiet);
    /* the chunk index of a long run has many nodes: a bounded metadata cache
     * (HDF5 lets it grow to 32 MB) writes them out instead of keeping them */
    hid_t fapl = H5Pcreate(H5P_FILE_ACCESS);
    H5AC_cache_config_t mdc;
    memset(&mdc, 0, sizeof mdc);
    mdc.version = H5AC__CURR_CACHE_CONFIG_VERSION;
    if (H5Pget_mdc_config(fapl, &mdc) >= 0) {
        mdc.set_initial_size = 1;
        mdc.initial_size = METADATA_CACHE_BYTES / 2;
        mdc.min_size = METADATA_CACHE_BYTES / 4;
        mdc.max_size = METADATA_CACHE_BYTES;
        H5Pset_mdc_config(fapl, &mdc);
    }
    s->file = H5Fcreate(path, H5F_ACC_TRUNC, H5P_DEFAULT, fapl);
    H5Pclose(fapl);
    /* from here on the file lives only through the open handle */
    unlink(path);
    if (s->file < 0) {
        h5_quiet_end(&s->quiet);
        return h5_fail(s, "create it", err);
    }
    hsize_t dims[3] = {0, 0, s->ncomp};
    hsize_t ck[3] = {DISK_CHUNK_SLOTS, s->chunk_frames, s->ncomp};
    double nan = NAN;
    s->dset = h5_create_growing(s->file, "records", H5T_NATIVE_DOUBLE, 3, 2, dims, ck, &nan, 0);
    h5_quiet_end(&s->quiet);
    if (s->dset < 0)
        return h5_fail(s, "create its dataset", err);
    s->on_disk = 1;
    return MIMAS_OK;
}

/* Slots [a, a + n) of chunk c into the dataset (extent already set). */
static int write_slots(mimas_traj_store *s, const chunk *c, size_t a, size_t n)
{
    hsize_t mdims[3] = {c->nslots, c->cap, s->ncomp};
    hsize_t mstart[3] = {a, 0, 0}, start[3] = {a, c->t0, 0};
    hsize_t count[3] = {n, c->nframes, s->ncomp};
    int rc = 0;
    hid_t fs = H5Dget_space(s->dset);
    hid_t ms = H5Screate_simple(3, mdims, NULL);
    if (fs < 0 || H5Sselect_hyperslab(fs, H5S_SELECT_SET, start, NULL, count, NULL) < 0 ||
        H5Sselect_hyperslab(ms, H5S_SELECT_SET, mstart, NULL, count, NULL) < 0 ||
        H5Dwrite(s->dset, H5T_NATIVE_DOUBLE, ms, fs, H5P_DEFAULT, c->data) < 0)
        rc = -1;
    if (fs >= 0)
        H5Sclose(fs);
    H5Sclose(ms);
    return rc;
}

/* A chunk into the dataset, WRITE_SLOTS slots a call (HDF5 keeps a record
 * of every dataset chunk a call touches). */
static int write_chunk(mimas_traj_store *s, const chunk *c, mimas_error *err)
{
    if (!c->nframes || !c->nslots)
        return MIMAS_OK;
    size_t slots = c->nslots > s->disk_slots ? c->nslots : s->disk_slots;
    size_t frames = c->t0 + c->nframes > s->disk_frames ? c->t0 + c->nframes : s->disk_frames;
    hsize_t ext[3] = {slots, frames, s->ncomp};
    int rc = 0;
    h5_quiet_begin(&s->quiet);
    if (H5Dset_extent(s->dset, ext) < 0)
        rc = -1;
    for (size_t a = 0; a < c->nslots && !rc; a += WRITE_SLOTS)
        rc = write_slots(s, c, a, c->nslots - a < WRITE_SLOTS ? c->nslots - a : WRITE_SLOTS);
    h5_quiet_end(&s->quiet);
    if (rc)
        return h5_fail(s, "write to it (is the disk full?)", err);
    s->disk_slots = slots;
    s->disk_frames = frames;
    return MIMAS_OK;
}

/* Moves the kept chunks to the scratch file (opening it). */
static int spill(mimas_traj_store *s, mimas_error *err)
{
    int rc = s->on_disk ? MIMAS_OK : open_disk(s, err);
    for (size_t k = 0; k < s->nkept && !rc; k++)
        rc = write_chunk(s, &s->kept[k], err);
    if (rc)
        return rc;
    for (size_t k = 0; k < s->nkept; k++)
        free(s->kept[k].data);
    s->nkept = 0;
    s->kept_bytes = 0;
    return MIMAS_OK;
}

/* Ends the chunk being filled: kept in memory while it (and, unless it is
 * the last, the next one) fit, else everything goes to the scratch file. */
static int end_chunk(mimas_traj_store *s, int last, mimas_error *err)
{
    chunk *c = &s->cur;
    if (!c->nframes)
        return MIMAS_OK;
    size_t bytes = chunk_bytes(s, c->nslots, c->cap);
    int rc = MIMAS_OK;
    if (!s->on_disk && s->kept_bytes + (last ? 1 : 2) * bytes > s->memory)
        rc = spill(s, err);
    if (rc)
        return rc;
    if (s->on_disk) {
        rc = write_chunk(s, c, err);
        free(c->data);
    } else {
        if (s->nkept == s->capkept) {
            size_t cap = s->capkept ? 2 * s->capkept : 16;
            chunk *k = realloc(s->kept, cap * sizeof *k);
            if (!k)
                return mimas_error_set(err, MIMAS_EIO, "out of memory");
            s->kept = k;
            s->capkept = cap;
        }
        s->kept[s->nkept++] = *c;
        s->kept_bytes += bytes;
    }
    memset(c, 0, sizeof *c);
    return rc;
}

static int too_small(const mimas_traj_store *s, size_t nslots, mimas_error *err)
{
    return mimas_error_set(err, MIMAS_EUSAGE,
                           "--memory %zu bytes cannot hold one frame of %zu particles (%zu "
                           "bytes); give more", s->memory, nslots, chunk_bytes(s, nslots, 1));
}

/* A new chunk from frame s->frames for nslots slots. */
static int start_chunk(mimas_traj_store *s, size_t nslots, mimas_error *err)
{
    size_t one = chunk_bytes(s, nslots ? nslots : 1, 1);
    if (!s->chunk_frames) {
        size_t f = s->memory / CHUNK_SHARE / one;
        s->chunk_frames = f < 1 ? 1 : f > MAX_CHUNK_FRAMES ? MAX_CHUNK_FRAMES : f;
    }
    size_t cap = s->chunk_frames;
    if (s->kept_bytes + cap * one > s->memory) {
        int rc = spill(s, err);
        if (rc)
            return rc;
    }
    if (one > s->memory)
        return too_small(s, nslots, err);
    if (cap * one > s->memory)
        cap = s->memory / one;
    chunk *c = &s->cur;
    c->t0 = s->frames;
    c->nframes = 0;
    c->cap = cap;
    c->nslots = nslots;
    size_t n = nslots * cap * s->ncomp;
    c->data = malloc((n ? n : 1) * sizeof *c->data);
    if (!c->data)
        return mimas_error_set(err, MIMAS_EIO, "out of memory");
    fill_absent(c->data, n);
    return MIMAS_OK;
}

/* More rows for the chunk being filled (absent records). */
static int grow_chunk(mimas_traj_store *s, size_t nslots, mimas_error *err)
{
    chunk *c = &s->cur;
    size_t bytes = chunk_bytes(s, nslots, c->cap);
    if (s->kept_bytes + bytes > s->memory) {
        int rc = spill(s, err);
        if (rc)
            return rc;
    }
    if (bytes > s->memory) {
        /* this chunk ends early; the next one holds fewer frames */
        int rc = end_chunk(s, 0, err);
        return rc ? rc : start_chunk(s, nslots, err);
    }
    size_t n = nslots * c->cap * s->ncomp, old = c->nslots * c->cap * s->ncomp;
    double *d = realloc(c->data, (n ? n : 1) * sizeof *d);
    if (!d)
        return mimas_error_set(err, MIMAS_EIO, "out of memory");
    fill_absent(d + old, n - old);
    c->data = d;
    c->nslots = nslots;
    return MIMAS_OK;
}

int mimas_traj_store_next_frame(mimas_traj_store *s, size_t nslots, mimas_error *err)
{
    if (s->finished)
        return mimas_error_set(err, MIMAS_EUSAGE, "the trajectory store is finished");
    if (nslots < s->slots)
        nslots = s->slots;
    int rc = MIMAS_OK;
    if (s->cur.data && s->cur.nframes == s->cur.cap)
        rc = end_chunk(s, 0, err);
    if (!rc && !s->cur.data)
        rc = start_chunk(s, nslots, err);
    if (!rc && nslots > s->cur.nslots)
        rc = grow_chunk(s, nslots, err);
    if (rc)
        return rc;
    s->cur.nframes++;
    s->frames++;
    s->slots = nslots;
    return MIMAS_OK;
}

double *mimas_traj_store_record(mimas_traj_store *s, size_t slot)
{
    const chunk *c = &s->cur;
    return c->data + (slot * c->cap + c->nframes - 1) * s->ncomp;
}

int mimas_traj_store_finish(mimas_traj_store *s, mimas_error *err)
{
    if (s->finished)
        return MIMAS_OK;
    s->finished = 1;
    int rc = end_chunk(s, 1, err);
    free(s->cur.data);
    memset(&s->cur, 0, sizeof s->cur);
    return rc;
}

int mimas_traj_store_spill(mimas_traj_store *s, mimas_error *err)
{
    if (!s->finished)
        return mimas_error_set(err, MIMAS_EUSAGE, "the trajectory store is not finished");
    if (!s->nkept)
        return MIMAS_OK;
    return spill(s, err);
}

size_t mimas_traj_store_frames(const mimas_traj_store *s) { return s->frames; }
size_t mimas_traj_store_slots(const mimas_traj_store *s) { return s->slots; }
size_t mimas_traj_store_ncomp(const mimas_traj_store *s) { return s->ncomp; }
int mimas_traj_store_on_disk(const mimas_traj_store *s) { return s->on_disk; }

size_t mimas_traj_store_bytes(const mimas_traj_store *s)
{
    return s->kept_bytes + (s->cur.data ? chunk_bytes(s, s->cur.nslots, s->cur.cap) : 0);
}

/* Slots first .. first+n-1 (all on disk) into out[n][T][ncomp], a row of
 * dataset chunks a call. */
static int read_disk(mimas_traj_store *s, size_t first, size_t n, double *out, mimas_error *err)
{
    size_t T = s->frames, have = first < s->disk_slots ? s->disk_slots - first : 0;
    if (have > n)
        have = n;
    if (!have || !s->disk_frames)
        return MIMAS_OK;
    int rc = 0;
    h5_quiet_begin(&s->quiet);
    for (size_t a = 0; a < have && !rc; a += DISK_CHUNK_SLOTS) {
        size_t m = have - a < DISK_CHUNK_SLOTS ? have - a : DISK_CHUNK_SLOTS;
        hsize_t start[3] = {first + a, 0, 0}, count[3] = {m, s->disk_frames, s->ncomp};
        hsize_t mdims[3] = {m, T, s->ncomp}, zero[3] = {0, 0, 0};
        hid_t fs = H5Dget_space(s->dset);
        hid_t ms = H5Screate_simple(3, mdims, NULL);
        if (fs < 0 || H5Sselect_hyperslab(fs, H5S_SELECT_SET, start, NULL, count, NULL) < 0 ||
            H5Sselect_hyperslab(ms, H5S_SELECT_SET, zero, NULL, count, NULL) < 0 ||
            H5Dread(s->dset, H5T_NATIVE_DOUBLE, ms, fs, H5P_DEFAULT, out + a * T * s->ncomp) < 0)
            rc = -1;
        if (fs >= 0)
            H5Sclose(fs);
        H5Sclose(ms);
    }
    h5_quiet_end(&s->quiet);
    return rc ? h5_fail(s, "read from it", err) : MIMAS_OK;
}

int mimas_traj_store_read(mimas_traj_store *s, size_t first, size_t n, double *out,
                          mimas_error *err)
{
    if (!s->finished)
        return mimas_error_set(err, MIMAS_EUSAGE, "the trajectory store is not finished");
    size_t T = s->frames, nc = s->ncomp;
    fill_absent(out, n * T * nc);
    if (s->on_disk)
        return read_disk(s, first, n, out, err);
    for (size_t k = 0; k < s->nkept; k++) {
        const chunk *c = &s->kept[k];
        for (size_t j = 0; j < n && first + j < c->nslots; j++)
            memcpy(out + (j * T + c->t0) * nc, c->data + (first + j) * c->cap * nc,
                   c->nframes * nc * sizeof *out);
    }
    return MIMAS_OK;
}

void mimas_traj_store_free(mimas_traj_store *s)
{
    if (!s)
        return;
    for (size_t k = 0; k < s->nkept; k++)
        free(s->kept[k].data);
    free(s->kept);
    free(s->cur.data);
    h5_quiet_begin(&s->quiet);
    if (s->dset >= 0)
        H5Dclose(s->dset);
    if (s->file >= 0)
        H5Fclose(s->file);
    h5_quiet_end(&s->quiet);
    free(s);
}
