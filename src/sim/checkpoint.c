/* Checkpoint files (see checkpoint.h). */
#include <config.h>

#include "checkpoint.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

static const char magic[8] = {'M', 'I', 'M', 'A', 'S', 'C', 'K', '\n'};
enum { CHECKPOINT_VERSION = 5 };

typedef struct ck_header {
    char magic[8];
    uint32_t version, endian;
    uint64_t n, ne, nwalls, nmotions, builds;
    int64_t step, last_id;
    uint64_t nextra;          /* scenario blocks after the DEM state, each preceded by its size */
} ck_header;

/* the particle arrays, in one list for writing and reading */
#define CK_ARRAYS(X)                                                                         \
    X(id) X(type) X(radius) X(mass) X(inertia) X(liquid) X(x) X(v) X(w) X(f) X(t) X(x_ref) \
    X(image) X(glued) X(anchor) X(bridges) X(wall_near) X(held)

static int put(FILE *fp, const void *p, size_t size)
{
    return size && fwrite(p, size, 1, fp) != 1;
}

int sim_checkpoint_write(const dem_system *s, const sim_ck_chunk *extra, size_t nextra,
                         const char *path, mimas_error *err)
{
    char tmp[4200];
    snprintf(tmp, sizeof tmp, "%s.tmp%ld", path, (long)getpid());
    FILE *fp = fopen(tmp, "wb");
    if (!fp)
        return mimas_error_set(err, MIMAS_EIO, "%s: cannot write the checkpoint", tmp);
    ck_header h = {.version = CHECKPOINT_VERSION, .endian = 0x01020304u, .n = s->n,
                   .ne = s->nl.ne, .nwalls = (uint64_t)s->nwalls,
                   .nmotions = (uint64_t)s->nmotions, .builds = s->nl.builds, .step = s->step,
                   .last_id = s->last_id, .nextra = nextra};
    memcpy(h.magic, magic, sizeof magic);
    int bad = put(fp, &h, sizeof h);
    size_t n = s->n;
#define PUT(a) bad |= put(fp, s->a, n * sizeof *s->a);
    CK_ARRAYS(PUT)
#undef PUT
    bad |= put(fp, s->wall_xi, n * DEM_MAX_WALLS * sizeof *s->wall_xi);
    bad |= put(fp, s->wall_f, n * DEM_MAX_WALLS * sizeof *s->wall_f);
    bad |= put(fp, s->wall_delta, n * DEM_MAX_WALLS * sizeof *s->wall_delta);
    bad |= put(fp, s->walls, sizeof s->walls);
    bad |= put(fp, s->motions, sizeof s->motions);
    bad |= put(fp, s->nl.start, (n + 1) * sizeof *s->nl.start);
    bad |= put(fp, s->nl.e, s->nl.ne * sizeof *s->nl.e);
    bad |= put(fp, s->nl.bv, s->nl.ne * sizeof *s->nl.bv);
    for (size_t c = 0; c < nextra; c++) {
        uint64_t size = extra[c].size;
        bad |= put(fp, &size, sizeof size);
        bad |= put(fp, extra[c].data, extra[c].size);
    }
    bad |= put(fp, magic, sizeof magic);   /* end mark */
    bad |= fflush(fp) != 0 || fsync(fileno(fp)) != 0;
    bad |= fclose(fp) != 0;
    if (bad || rename(tmp, path) != 0) {
        unlink(tmp);
        return mimas_error_set(err, MIMAS_EIO, "%s: cannot write the checkpoint", path);
    }
    return MIMAS_OK;
}

static int get(FILE *fp, void *p, size_t size)
{
    return size && fread(p, size, 1, fp) != 1;
}

int sim_checkpoint_read(dem_system *s, const sim_ck_chunk *extra, size_t nextra,
                        const char *path, mimas_error *err)
{
    FILE *fp = fopen(path, "rb");
    if (!fp)
        return mimas_error_set(err, MIMAS_EDATA, "%s: no checkpoint to resume from", path);
    ck_header h;
    int rc = MIMAS_OK;
    if (get(fp, &h, sizeof h) || memcmp(h.magic, magic, sizeof magic) != 0)
        rc = mimas_error_set(err, MIMAS_EDATA, "%s: not a mimas checkpoint", path);
    else if (h.version != CHECKPOINT_VERSION || h.endian != 0x01020304u)
        rc = mimas_error_set(err, MIMAS_EDATA, "%s: checkpoint of another version or machine",
                             path);
    else if (h.nwalls != (uint64_t)s->nwalls || h.nmotions != (uint64_t)s->nmotions ||
             h.nextra != nextra)
        rc = mimas_error_set(err, MIMAS_EDATA, "%s: the checkpoint has %llu walls and %llu "
                             "moving parts, the scenario %d and %d: not the same scenario", path,
                             (unsigned long long)h.nwalls, (unsigned long long)h.nmotions,
                             s->nwalls, s->nmotions);
    else if (h.n > (uint64_t)INT32_MAX || h.ne > (uint64_t)SIZE_MAX / sizeof(dem_entry))
        rc = mimas_error_set(err, MIMAS_EDATA, "%s: the checkpoint is damaged", path);
    if (!rc)
        rc = dem_reserve(s, (size_t)h.n, err);
    if (rc) {
        fclose(fp);
        return rc;
    }
    size_t n = (size_t)h.n;
    s->n = n;
    dem_nlist *nl = &s->nl;
    free(nl->start);
    free(nl->e);
    free(nl->bv);
    nl->start = malloc((n + 1) * sizeof *nl->start);
    nl->e = malloc((h.ne ? h.ne : 1) * sizeof *nl->e);
    nl->bv = malloc((h.ne ? h.ne : 1) * sizeof *nl->bv);
    nl->n = n;
    nl->ne = h.ne;
    nl->builds = h.builds;
    if (!nl->start || !nl->e || !nl->bv) {
        fclose(fp);
        return mimas_error_set(err, MIMAS_EIO, "out of memory reading %s", path);
    }
    int bad = 0;
#define GET(a) bad |= get(fp, s->a, n * sizeof *s->a);
    CK_ARRAYS(GET)
#undef GET
    bad |= get(fp, s->wall_xi, n * DEM_MAX_WALLS * sizeof *s->wall_xi);
    bad |= get(fp, s->wall_f, n * DEM_MAX_WALLS * sizeof *s->wall_f);
    bad |= get(fp, s->wall_delta, n * DEM_MAX_WALLS * sizeof *s->wall_delta);
    bad |= get(fp, s->walls, sizeof s->walls);
    bad |= get(fp, s->motions, sizeof s->motions);
    bad |= get(fp, nl->start, (n + 1) * sizeof *nl->start);
    bad |= get(fp, nl->e, h.ne * sizeof *nl->e);
    bad |= get(fp, nl->bv, h.ne * sizeof *nl->bv);
    for (size_t c = 0; c < nextra && !bad; c++) {
        uint64_t size;
        bad = get(fp, &size, sizeof size) || size != extra[c].size ||
              get(fp, extra[c].data, extra[c].size);
    }
    char end[8];
    bad |= get(fp, end, sizeof end) || memcmp(end, magic, sizeof magic) != 0;
    fclose(fp);
    if (!bad && nl->start[n] != h.ne)
        bad = 1;
    for (size_t k = 0; k < h.ne && !bad; k++)
        bad = nl->e[k].j < 0 || (size_t)nl->e[k].j >= n;
    if (bad)
        return mimas_error_set(err, MIMAS_EDATA, "%s: the checkpoint is truncated or damaged",
                               path);
    s->step = h.step;
    s->last_id = h.last_id;
    return dem_neighbours_transpose(nl, err);
}
