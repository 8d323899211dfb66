#include <config.h>

#include "lammps_series.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "backend.h"
#include "numparse.h"

static int starts(const char *line, const char *prefix)
{
    return strncmp(line, prefix, strlen(prefix)) == 0;
}

static char *need_line(text_input *in, const char *what, int *rc, mimas_error *err)
{
    size_t len;
    char *line = text_line(in, &len, rc, err);
    if (!line && !*rc) {
        in->line++;
        *rc = text_error(in, err, "file ends where %s was expected", what);
    }
    return line;
}

/* One line holding exactly one integer (or number) and nothing else. */
static int one_int(text_input *in, const char *what, int64_t *v, mimas_error *err)
{
    int rc;
    char *p = need_line(in, what, &rc, err);
    if (!p)
        return rc;
    if (parse_int64(&p, v) != 0 || skip_token(&p) == 0)
        return text_error(in, err, "%s is not an integer", what);
    return MIMAS_OK;
}

/* ITEM: BOX BOUNDS [xy xz yz] [flags]: orthogonal bounds, or the bounding box
 * of a triclinic box with its tilt factors (converted as the LAMMPS dump
 * documentation says). */
static int read_box(text_input *in, char *item, mimas_box *b, mimas_error *err)
{
    char *p = item + strlen("ITEM: BOX BOUNDS");
    int tilted = 0;
    char tok[3][16];
    int ntok = 0;
    while (ntok < 3) {
        while (*p == ' ' || *p == '\t')
            p++;
        if (!*p)
            break;
        size_t n = strcspn(p, " \t");
        if (n >= sizeof tok[0])
            return text_error(in, err, "unexpected box flag '%.*s'", (int)n, p);
        memcpy(tok[ntok], p, n);
        tok[ntok][n] = '\0';
        p += n;
        if (ntok == 0 && !strcmp(tok[0], "xy")) {
            tilted = 1;
            continue; /* "xy xz yz" precede the flags */
        }
        if (tilted && (!strcmp(tok[0], "xz") || !strcmp(tok[0], "yz")))
            continue;
        if (!strcmp(tok[ntok], "abc"))
            return text_error(in, err, "general triclinic boxes (BOX BOUNDS abc origin) are "
                                       "not supported");
        ntok++;
    }
    for (int d = 0; d < 3; d++) {
        /* "pp" periodic; f, s, m (fixed, shrink-wrapped) are not */
        b->periodic[d] = ntok == 3 && tok[d][0] == 'p' && tok[d][1] == 'p' && tok[d][2] == 0;
        if (ntok == 3 && (strlen(tok[d]) != 2 || !strchr("pfsm", tok[d][0]) ||
                          !strchr("pfsm", tok[d][1])))
            return text_error(in, err, "unexpected box flag '%s'", tok[d]);
    }
    double lo[3], hi[3], tilt[3] = {0, 0, 0};
    for (int d = 0; d < 3; d++) {
        int rc;
        char *q = need_line(in, "a box bound", &rc, err);
        if (!q)
            return rc;
        if (parse_double(&q, &lo[d]) || parse_double(&q, &hi[d]) ||
            (tilted && parse_double(&q, &tilt[d])) || skip_token(&q) == 0)
            return text_error(in, err, "box bounds must be %d numbers", tilted ? 3 : 2);
    }
    if (tilted) {
        double xy = tilt[0], xz = tilt[1], yz = tilt[2];
        double mn = fmin(fmin(0.0, xy), fmin(xz, xy + xz));
        double mx = fmax(fmax(0.0, xy), fmax(xz, xy + xz));
        lo[0] -= mn;
        hi[0] -= mx;
        lo[1] -= fmin(0.0, yz);
        hi[1] -= fmax(0.0, yz);
        b->xy = xy;
        b->xz = xz;
        b->yz = yz;
    } else {
        b->xy = b->xz = b->yz = 0.0;
    }
    for (int d = 0; d < 3; d++) {
        if (!(hi[d] > lo[d]))
            return text_error(in, err, "box bounds are empty or reversed");
        b->lo[d] = lo[d];
        b->hi[d] = hi[d];
    }
    return MIMAS_OK;
}

static int keep_columns(dump_header *h, const char *names, mimas_error *err)
{
    size_t n = strlen(names) + 1;
    if (n > h->columns_cap) {
        char *c = realloc(h->columns, n);
        if (!c)
            return mimas_error_set(err, MIMAS_EIO, "out of memory for the dump reader");
        h->columns = c;
        h->columns_cap = n;
    }
    memcpy(h->columns, names, n);
    return MIMAS_OK;
}

/* Reads items up to and including ITEM: ATOMS / ITEM: ENTRIES.  Returns
 * MIMAS_END if the file ends before a new snapshot starts. */
static int read_header(text_input *in, dump_header *h, mimas_error *err)
{
    int got_step = 0, got_count = 0, got_box = 0;
    h->has_time = 0;
    for (;;) {
        int rc;
        size_t len;
        char *line = text_line(in, &len, &rc, err);
        if (!line) {
            if (rc)
                return rc;
            if (got_step || got_count || h->has_time) {
                in->line++;
                return text_error(in, err, "file ends inside a snapshot header");
            }
            return MIMAS_END;
        }
        if (!got_step && !h->has_time && len == strspn(line, " \t"))
            continue; /* blank lines between snapshots */
        if (!starts(line, "ITEM: "))
            return text_error(in, err, "expected an ITEM: line, found '%.40s'", line);
        if (!strcmp(line, "ITEM: TIMESTEP")) {
            int64_t step;
            if ((rc = one_int(in, "the timestep", &step, err)))
                return rc;
            h->step = step;
            got_step = 1;
        } else if (!strcmp(line, "ITEM: TIME")) {
            char *p = need_line(in, "the time", &rc, err);
            if (!p)
                return rc;
            if (parse_double(&p, &h->time) || skip_token(&p) == 0)
                return text_error(in, err, "the time is not a number");
            h->has_time = 1;
        } else if (!strcmp(line, "ITEM: UNITS") || !strcmp(line, "ITEM: LABEL")) {
            if (!need_line(in, "a value", &rc, err))
                return rc;
        } else if (!strcmp(line, "ITEM: NUMBER OF ATOMS") ||
                   !strcmp(line, "ITEM: NUMBER OF ENTRIES")) {
            int64_t n;
            if ((rc = one_int(in, "the count", &n, err)))
                return rc;
            if (n < 0 || n > (int64_t)1 << 40)
                return text_error(in, err, "count %lld is impossible", (long long)n);
            h->count = (size_t)n;
            h->entries = line[16] == 'E';
            got_count = 1;
        } else if (starts(line, "ITEM: BOX BOUNDS")) {
            if ((rc = read_box(in, line, &h->box, err)))
                return rc;
            got_box = 1;
        } else if (starts(line, "ITEM: ATOMS") || starts(line, "ITEM: ENTRIES")) {
            if (!got_step || !got_count)
                return text_error(in, err, "%s before TIMESTEP and NUMBER OF ...", line);
            if (!got_box)
                return text_error(in, err, "snapshot without BOX BOUNDS");
            int local = line[6] == 'E';
            if (local != h->entries)
                return text_error(in, err, "ITEM: %s after NUMBER OF %s", local ? "ENTRIES" : "ATOMS",
                                  local ? "ATOMS" : "ENTRIES");
            const char *names = line + (local ? 13 : 11);
            return keep_columns(h, names, err);
        } else {
            return text_error(in, err, "unknown item '%.40s'", line);
        }
    }
}

/* ---- the series ---- */

static int first_step(const char *path, int64_t *step, mimas_error *err)
{
    text_input in;
    int rc = text_open(&in, path, err);
    if (rc)
        return rc;
    dump_header h;
    memset(&h, 0, sizeof h);
    rc = read_header(&in, &h, err);
    if (rc == MIMAS_END)
        rc = mimas_error_set(err, MIMAS_EDATA, "%s: empty file (no snapshot)", path);
    *step = h.step;
    free(h.columns);
    text_close(&in);
    return rc;
}

typedef struct {
    char *path;
    int64_t step;
} named_step;

static int cmp_step(const void *a, const void *b)
{
    int64_t x = ((const named_step *)a)->step, y = ((const named_step *)b)->step;
    return (x > y) - (x < y);
}

int dump_series_open(dump_series *s, char **paths, size_t n, mimas_error *err)
{
    memset(s, 0, sizeof *s);
    s->paths = paths;
    s->npaths = n;
    if (n > 1) {
        named_step *ns = malloc(n * sizeof *ns);
        if (!ns)
            return mimas_error_set(err, MIMAS_EIO, "out of memory for the dump reader");
        for (size_t k = 0; k < n; k++) {
            ns[k].path = paths[k];
            int rc = first_step(paths[k], &ns[k].step, err);
            if (rc) {
                free(ns);
                return rc;
            }
        }
        qsort(ns, n, sizeof *ns, cmp_step); /* stable enough: equal steps are an error later */
        for (size_t k = 0; k < n; k++)
            paths[k] = ns[k].path;
        free(ns);
    }
    if (n == 0)
        return mimas_error_set(err, MIMAS_EUSAGE, "no dump file");
    int rc = text_open(&s->in, paths[0], err);
    s->is_open = rc == MIMAS_OK;
    return rc;
}

int dump_series_header(dump_series *s, mimas_error *err)
{
    for (;;) {
        if (!s->is_open)
            return MIMAS_END;
        int rc = read_header(&s->in, &s->h, err);
        if (rc == MIMAS_OK) {
            if (s->have_last && s->h.step <= s->last_step)
                return text_error(&s->in, err, "timestep %lld follows %lld: snapshots are "
                                  "out of order or repeated", (long long)s->h.step,
                                  (long long)s->last_step);
            s->have_last = 1;
            s->last_step = s->h.step;
            return MIMAS_OK;
        }
        if (rc != MIMAS_END)
            return rc;
        if (s->in.line == 0)
            return mimas_error_set(err, MIMAS_EDATA, "%s: empty file", s->in.path);
        text_close(&s->in);
        s->is_open = 0;
        if (++s->cur < s->npaths) {
            rc = text_open(&s->in, s->paths[s->cur], err);
            if (rc)
                return rc;
            s->is_open = 1;
        }
    }
}

char *dump_series_row(dump_series *s, size_t k, int *rc, mimas_error *err)
{
    size_t len;
    char *line = text_line(&s->in, &len, rc, err);
    if (!line && !*rc) {
        s->in.line++;
        *rc = text_error(&s->in, err, "file ends after %zu of %zu rows (cut short?)", k,
                         s->h.count);
    } else if (line && starts(line, "ITEM:")) {
        *rc = text_error(&s->in, err, "snapshot has %zu rows, its header says %zu", k,
                         s->h.count);
        line = NULL;
    }
    return line;
}

void dump_series_close(dump_series *s)
{
    if (s->is_open)
        text_close(&s->in);
    free(s->h.columns);
    reader_free_names(s->paths, s->npaths);
    memset(s, 0, sizeof *s);
}

/* ---- column layouts ---- */

int dump_columns_current(const dump_columns *c, const char *header)
{
    return c->header && strcmp(c->header, header) == 0;
}

void dump_columns_free(dump_columns *c)
{
    free(c->slots);
    free(c->header);
    free(c->cols);
    free(c->extra_name);
    free(c->extra_ncomp);
    memset(c, 0, sizeof *c);
}

int dump_columns_reset(dump_columns *c, const char *header, mimas_error *err)
{
    dump_columns_free(c);
    size_t cap = 2 + strlen(header) / 2; /* a column takes at least 2 characters */
    c->header = strdup(header);
    c->cols = calloc(cap, sizeof *c->cols);
    c->extra_name = calloc(cap, sizeof *c->extra_name);
    c->extra_ncomp = calloc(cap, sizeof *c->extra_ncomp);
    c->nslots = 2 * cap;
    c->slots = calloc(c->nslots, sizeof *c->slots);
    if (!c->header || !c->cols || !c->extra_name || !c->extra_ncomp || !c->slots)
        return mimas_error_set(err, MIMAS_EIO, "out of memory for the %zu-character column "
                               "header", strlen(header));
    return MIMAS_OK;
}

/* FNV-1a of the name as stored (cut to the slot width) */
static size_t name_hash(const char *name)
{
    size_t h = 1469598103934665603u;
    for (size_t k = 0; name[k] && k < 63; k++)
        h = (h ^ (unsigned char)name[k]) * 1099511628211u;
    return h;
}

size_t dump_columns_find_extra(const dump_columns *c, const char *name)
{
    char key[64];
    snprintf(key, sizeof key, "%s", name);
    for (size_t h = name_hash(key) % c->nslots;; h = (h + 1) % c->nslots) {
        if (!c->slots[h])
            return (size_t)-1;
        if (!strcmp(c->extra_name[c->slots[h] - 1], key))
            return c->slots[h] - 1;
    }
}

size_t dump_columns_add_extra(dump_columns *c, const char *name, int ncomp)
{
    snprintf(c->extra_name[c->nextra], sizeof c->extra_name[0], "%s", name);
    c->extra_ncomp[c->nextra] = ncomp;
    size_t h = name_hash(c->extra_name[c->nextra]) % c->nslots;
    while (c->slots[h])
        h = (h + 1) % c->nslots;
    c->slots[h] = c->nextra + 1;
    return c->nextra++;
}

/* "c_stress[3]" -> base "c_stress", index 3; other names: index 0. */
static int split_index(const char *name, char *base, size_t cap)
{
    const char *br = strchr(name, '[');
    size_t n = br ? (size_t)(br - name) : strlen(name);
    int idx = 0;
    if (br) {
        char *end;
        long v = strtol(br + 1, &end, 10);
        if (end != br + 1 && end[0] == ']' && end[1] == '\0' && v > 0 && v < 1000)
            idx = (int)v;
        else
            n = strlen(name);
    }
    if (n >= cap)
        n = cap - 1;
    memcpy(base, name, n);
    base[n] = '\0';
    return idx;
}

int dump_columns_extra_column(dump_columns *c, dump_col *col, const char *name, int *prev_idx)
{
    char base[64];
    int idx = split_index(name, base, sizeof base);
    if (idx > 1 && c->nextra && idx == *prev_idx + 1 &&
        !strcmp(c->extra_name[c->nextra - 1], base)) {
        col->extra = c->nextra - 1;
        col->comp = c->extra_ncomp[col->extra]++;
    } else {
        if (dump_columns_find_extra(c, idx ? base : name) != (size_t)-1)
            return -1;
        col->extra = dump_columns_add_extra(c, idx ? base : name, 1);
        col->comp = 0;
    }
    *prev_idx = idx;
    return 0;
}

int dump_columns_extras_to(const dump_columns *c, void *tab, const mimas_table_desc *d,
                           mimas_error *err)
{
    const size_t n_extra = *(const size_t *)((const char *)tab + d->off_n_extra);
    const mimas_extra *extra = *(mimas_extra *const *)((const char *)tab + d->off_extra);
    int same = n_extra == c->nextra;
    for (size_t e = 0; same && e < c->nextra; e++)
        same = !strcmp(extra[e].name, c->extra_name[e]) && extra[e].ncomp == c->extra_ncomp[e];
    if (same)
        return MIMAS_OK;
    mimas_table_drop_extras(tab, d);
    int rc = MIMAS_OK;
    /* the names are distinct (the layout refused a repeated one) */
    for (size_t e = 0; !rc && e < c->nextra; e++)
        rc = mimas_table_add_new_extra(tab, d, c->extra_name[e], c->extra_ncomp[e], err);
    return rc;
}
