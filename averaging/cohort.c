#include <config.h>

#include "cohort.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "numparse.h"

#define COHORT_FORMS "all, types:L, ids:FILE, inserted:T0:T1 or region:SPEC@T with SPEC " \
                     "box:X0,Y0,Z0:X1,Y1,Z1, slab:S0:S1 or cylinder:R[:S0:S1]"

/* the first frame "at or after T" allows for T printed with rounding */
#define AT_TOLERANCE 1e-9

int mimas_region_contains(const mimas_region *r, const mimas_axis *axis, const double x[3])
{
    if (r->kind == MIMAS_REGION_BOX) {
        for (int d = 0; d < 3; d++)
            if (!(x[d] >= r->lo[d] && x[d] < r->hi[d]))
                return 0;
        return 1;
    }
    double l[3];
    mimas_axis_to_local(axis, x, l);
    if (!(l[2] >= r->s0 && l[2] < r->s1))
        return 0;
    return r->kind == MIMAS_REGION_SLAB || l[0] * l[0] + l[1] * l[1] < r->radius * r->radius;
}

/* A whole finite number. */
static int number(const char *s, double *v)
{
    char *end;
    errno = 0;
    *v = strtod(s, &end);
    return end != s && *end == '\0' && errno != ERANGE && isfinite(*v) ? 0 : -1;
}

/* "X,Y,Z" */
static int point(const char *s, double p[3])
{
    char buf[128];
    if (strlen(s) >= sizeof buf)
        return -1;
    strcpy(buf, s);
    char *save = NULL, *tok = strtok_r(buf, ",", &save);
    for (int d = 0; d < 3; d++, tok = strtok_r(NULL, ",", &save))
        if (!tok || number(tok, &p[d]))
            return -1;
    return tok ? -1 : 0;
}

/* Splits s (modified) at ':' into at most max fields; returns the count. */
static size_t fields(char *s, char **f, size_t max)
{
    size_t n = 0;
    for (char *p = s;; p++) {
        if (n == max)
            return max + 1;
        f[n++] = p;
        p = strchr(p, ':');
        if (!p)
            return n;
        *p = '\0';
    }
}

static int parse_region(mimas_region *r, char *text)
{
    char *f[8];
    size_t n = fields(text, f, 6);
    memset(r, 0, sizeof *r);
    r->s0 = -INFINITY;
    r->s1 = INFINITY;
    if (n == 3 && !strcmp(f[0], "box")) {
        r->kind = MIMAS_REGION_BOX;
        if (point(f[1], r->lo) || point(f[2], r->hi))
            return -1;
        for (int d = 0; d < 3; d++)
            if (!(r->hi[d] > r->lo[d]))
                return -1;
        return 0;
    }
    if (n == 3 && !strcmp(f[0], "slab")) {
        r->kind = MIMAS_REGION_SLAB;
        return number(f[1], &r->s0) || number(f[2], &r->s1) || !(r->s1 > r->s0) ? -1 : 0;
    }
    if ((n == 2 || n == 4) && !strcmp(f[0], "cylinder")) {
        r->kind = MIMAS_REGION_CYLINDER;
        if (number(f[1], &r->radius) || !(r->radius > 0))
            return -1;
        if (n == 4 && (number(f[2], &r->s0) || number(f[3], &r->s1) || !(r->s1 > r->s0)))
            return -1;
        return 0;
    }
    return -1;
}

static int parse_types(mimas_cohort *c, char *list)
{
    char *save = NULL;
    for (char *tok = strtok_r(list, ",", &save); tok; tok = strtok_r(NULL, ",", &save)) {
        double v;
        if (number(tok, &v) || v != floor(v) || fabs(v) > 2147483647.0 || c->ntypes >= 64)
            return -1;
        c->types[c->ntypes++] = (int32_t)v;
    }
    return c->ntypes ? 0 : -1;
}

/* The ids of FILE: whitespace or commas between them, '#' comments. */
static int read_ids(mimas_cohort *c, const char *path, mimas_error *err)
{
    FILE *fp = fopen(path, "r");
    if (!fp)
        return mimas_error_set(err, MIMAS_EDATA, "%s: cannot read the ids of --cohort %s: %s",
                               path, c->spec, strerror(errno));
    size_t n = 0, cap = 0, line_no = 0, len = 0;
    char *line = NULL;
    int rc = MIMAS_OK;
    while (!rc && getline(&line, &len, fp) >= 0) {
        line_no++;
        line[strcspn(line, "#")] = '\0';
        for (char *q = line; *q; q++)
            if (*q == ',')
                *q = ' ';
        char *p = line;
        int64_t v;
        int got;
        while (!rc && (got = parse_int64(&p, &v)) != -1) {
            if (got) {
                rc = mimas_error_set(err, MIMAS_EDATA, "%s line %zu: not a particle id (ids "
                                     "are whole numbers)", path, line_no);
                break;
            }
            if (n == cap) {
                cap = cap ? 2 * cap : 256;
                int64_t *g = realloc(c->id_list, cap * sizeof *g);
                if (!g) {
                    rc = mimas_error_set(err, MIMAS_EIO, "out of memory");
                    break;
                }
                c->id_list = g;
            }
            c->id_list[n++] = v;
        }
    }
    free(line);
    if (!rc && ferror(fp))
        rc = mimas_error_set(err, MIMAS_EDATA, "%s: read error", path);
    fclose(fp);
    if (!rc && !n)
        rc = mimas_error_set(err, MIMAS_EDATA, "%s: no particle id in the file", path);
    if (!rc && mimas_id_index_build(&c->ids, c->id_list, n, err))
        rc = mimas_error_prefix(err, "%s", path);
    return rc;
}

int mimas_cohort_parse(mimas_cohort *c, const char *spec, mimas_error *err)
{
    memset(c, 0, sizeof *c);
    mimas_id_index_init(&c->ids);
    if (strlen(spec) >= sizeof c->spec)
        return mimas_error_set(err, MIMAS_EUSAGE, "--cohort: the specification is too long");
    strcpy(c->spec, spec);
    char text[sizeof c->spec];
    strcpy(text, spec);
    char *colon = strchr(text, ':');
    char *rest = colon ? colon + 1 : text + strlen(text);
    if (colon)
        *colon = '\0';
    int bad = 0;
    if (!strcmp(text, "all") && !colon) {
        c->kind = MIMAS_COHORT_ALL;
    } else if (!strcmp(text, "types") && colon) {
        c->kind = MIMAS_COHORT_TYPES;
        bad = parse_types(c, rest);
    } else if (!strcmp(text, "ids") && colon && *rest) {
        c->kind = MIMAS_COHORT_IDS;
        return read_ids(c, rest, err);
    } else if (!strcmp(text, "inserted") && colon) {
        c->kind = MIMAS_COHORT_INSERTED;
        char *f[4];
        bad = fields(rest, f, 2) != 2 || number(f[0], &c->t0) || number(f[1], &c->t1) ||
              !(c->t1 >= c->t0);
    } else if (!strcmp(text, "region") && colon) {
        c->kind = MIMAS_COHORT_REGION;
        char *at = strrchr(rest, '@');
        bad = !at || number(at + 1, &c->at);
        if (!bad) {
            *at = '\0';
            bad = parse_region(&c->region, rest);
        }
    } else {
        bad = 1;
    }
    if (bad)
        return mimas_error_set(err, MIMAS_EUSAGE, "--cohort '%s': not a cohort (%s)", spec,
                               COHORT_FORMS);
    return MIMAS_OK;
}

void mimas_cohort_free(mimas_cohort *c)
{
    mimas_id_index_free(&c->ids);
    free(c->id_list);
    c->id_list = NULL;
}

struct mimas_cohorts {
    mimas_cohort *c;
    size_t n;
    uint64_t *mask;   /* by slot */
    size_t cap;
};

int mimas_cohorts_create(mimas_cohorts **out, const char *const *specs, size_t n,
                         mimas_error *err)
{
    *out = NULL;
    static const char *const all[] = {"all"};
    if (!n) {
        specs = all;
        n = 1;
    }
    if (n > MIMAS_COHORTS_MAX)
        return mimas_error_set(err, MIMAS_EUSAGE, "at most %d --cohort options",
                               MIMAS_COHORTS_MAX);
    mimas_cohorts *cs = calloc(1, sizeof *cs);
    if (cs)
        cs->c = calloc(n, sizeof *cs->c);
    if (!cs || !cs->c) {
        free(cs);
        return mimas_error_set(err, MIMAS_EIO, "out of memory");
    }
    for (size_t k = 0; k < n; k++) {
        int rc = mimas_cohort_parse(&cs->c[k], specs[k], err);
        cs->n = k + 1;
        if (rc) {
            mimas_cohorts_free(cs);
            return rc;
        }
    }
    *out = cs;
    return MIMAS_OK;
}

size_t mimas_cohorts_count(const mimas_cohorts *cs) { return cs->n; }
const mimas_cohort *mimas_cohorts_get(const mimas_cohorts *cs, size_t k) { return &cs->c[k]; }

uint64_t mimas_cohorts_mask(const mimas_cohorts *cs, size_t slot)
{
    return slot < cs->cap ? cs->mask[slot] : 0;
}

static int reserve_masks(mimas_cohorts *cs, size_t slots, mimas_error *err)
{
    if (slots <= cs->cap)
        return MIMAS_OK;
    size_t cap = cs->cap ? cs->cap : 1024;
    while (cap < slots)
        cap *= 2;
    uint64_t *m = realloc(cs->mask, cap * sizeof *m);
    if (!m)
        return mimas_error_set(err, MIMAS_EIO, "out of memory");
    memset(m + cs->cap, 0, (cap - cs->cap) * sizeof *m);
    cs->mask = m;
    cs->cap = cap;
    return MIMAS_OK;
}

/* Whether particle i joins cohort c in this frame. */
static int joins(mimas_cohort *c, const mimas_frame *f, size_t i, int is_new, int region_frame,
                 const mimas_axis *axis)
{
    const mimas_particles *p = &f->particles;
    switch (c->kind) {
    case MIMAS_COHORT_ALL: return is_new;
    case MIMAS_COHORT_TYPES:
        for (size_t k = 0; is_new && k < c->ntypes; k++)
            if (p->type[i] == c->types[k])
                return 1;
        return 0;
    case MIMAS_COHORT_IDS: {
        size_t dummy;
        return is_new && mimas_id_index_find(&c->ids, p->id[i], &dummy);
    }
    case MIMAS_COHORT_INSERTED: return is_new && f->time >= c->t0 && f->time <= c->t1;
    case MIMAS_COHORT_REGION:
        return region_frame && mimas_region_contains(&c->region, axis, p->pos[i]);
    }
    return 0;
}

int mimas_cohorts_frame(mimas_cohorts *cs, const mimas_frame *f, const size_t *slot_of,
                        const unsigned char *is_new, const mimas_axis *axis, mimas_error *err)
{
    const mimas_particles *p = &f->particles;
    size_t top = 0;
    for (size_t i = 0; i < p->n; i++)
        if (slot_of[i] != SIZE_MAX && slot_of[i] + 1 > top)
            top = slot_of[i] + 1;
    int rc = reserve_masks(cs, top, err);
    if (rc)
        return rc;
    for (size_t k = 0; k < cs->n; k++) {
        mimas_cohort *c = &cs->c[k];
        if (c->kind == MIMAS_COHORT_TYPES && p->n && !(p->present & MIMAS_P_TYPE))
            return mimas_error_set(err, MIMAS_EMISSING, "the particles have no types: "
                                   "--cohort %s needs them", c->spec);
        int region_frame = c->kind == MIMAS_COHORT_REGION && !c->decided &&
                           f->time >= c->at - AT_TOLERANCE * fabs(c->at);
        if (region_frame) {
            c->decided = 1;
            c->decided_time = f->time;
        }
        uint64_t bit = (uint64_t)1 << k;
        for (size_t i = 0; i < p->n; i++) {
            size_t s = slot_of[i];
            if (s == SIZE_MAX || (cs->mask[s] & bit))
                continue;
            if (joins(c, f, i, is_new[i], region_frame, axis)) {
                cs->mask[s] |= bit;
                c->size++;
            }
        }
    }
    return MIMAS_OK;
}

void mimas_cohorts_free(mimas_cohorts *cs)
{
    if (!cs)
        return;
    for (size_t k = 0; k < cs->n; k++)
        mimas_cohort_free(&cs->c[k]);
    free(cs->c);
    free(cs->mask);
    free(cs);
}
