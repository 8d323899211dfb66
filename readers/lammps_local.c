/* Column layouts of local dumps.  LIGGGHTS names every column c_ID[k] and
 * orders them by its own fixed keyword order, whatever order the compute was
 * given; the user names the keywords (--contact-columns) and mimas lays them
 * out (checked against compute_pair_gran_local.cpp of LIGGGHTS 3.8 and real
 * output: tests/data/liggghts/README.md).  Headers whose columns carry real
 * names, and LAMMPS pair/local + property/local columns, name each column. */
#include <config.h>

#include "lammps_local.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "lammps_infer.h"
#include "numparse.h"

enum {
    L_SKIP, L_ID1, L_ID2, L_WALLID, L_F, L_FN, L_FT, L_DELTA, L_DIST, L_CP, L_EXTRA
};

/* LIGGGHTS' order and widths (history: its width depends on the model). */
static const struct {
    const char *key;
    int width;
} gran_order[] = {
    {"pos", 6},          {"vel", 6},           {"id", 3},
    {"force", 3},        {"force_normal", 3},  {"force_tangential", 3},
    {"torque", 3},       {"torque_normal", 3}, {"torque_tangential", 3},
    {"history", -1},     {"contactArea", 1},   {"delta", 1},
    {"contactPoint", 3}, {"ms_id", 2},         {"heatFlux", 1},
};
#define NGRAN (sizeof gran_order / sizeof gran_order[0])

void local_layout_free(local_layout *l)
{
    dump_columns_free(&l->c);
    local_layout keep = *l;
    memset(l, 0, sizeof *l);
    l->keywords = keep.keywords;
    l->walls = keep.walls;
    l->notify = keep.notify;
    l->notify_ctx = keep.notify_ctx;
}

static size_t add_extra(local_layout *l, const char *name, int ncomp)
{
    return dump_columns_add_extra(&l->c, name, ncomp);
}

static void set(dump_col *c, int target, int comp)
{
    c->target = target;
    c->comp = comp;
}

/* The columns of one LIGGGHTS keyword, starting at cols. */
static void gran_keyword(local_layout *l, const char *key, int width, dump_col *cols)
{
    for (int k = 0; k < width; k++)
        set(&cols[k], L_SKIP, 0);
    if (!strcmp(key, "pos")) {
        /* walls: the contact point on the wall, then the particle position */
        if (l->walls)
            for (int k = 0; k < 3; k++)
                set(&cols[k], L_CP, k);
    } else if (!strcmp(key, "id")) {
        if (l->walls) { /* mesh index, triangle id, particle id */
            set(&cols[0], L_WALLID, 0);
            size_t e = add_extra(l, "triangle", 1);
            set(&cols[1], L_EXTRA, 0);
            cols[1].extra = e;
            set(&cols[2], L_ID1, 0);
        } else { /* id 1, id 2, periodic flag */
            set(&cols[0], L_ID1, 0);
            set(&cols[1], L_ID2, 0);
        }
    } else if (!strcmp(key, "force") || !strcmp(key, "force_normal") ||
               !strcmp(key, "force_tangential")) {
        int t = key[5] == '\0' ? L_F : (key[6] == 'n' ? L_FN : L_FT);
        for (int k = 0; k < 3; k++)
            set(&cols[k], t, k);
    } else if (!strcmp(key, "delta")) {
        set(&cols[0], L_DELTA, 0);
    } else if (!strcmp(key, "contactPoint")) {
        /* LIGGGHTS writes zeros here for wall contacts: the wall point of
         * "pos" is the contact point there */
        if (!l->walls)
            for (int k = 0; k < 3; k++)
                set(&cols[k], L_CP, k);
    } else if (strcmp(key, "vel") != 0) {
        /* torques, history, contact area, ...: kept as extra columns */
        size_t e = add_extra(l, !strcmp(key, "contactArea") ? "contact_area" : key, width);
        for (int k = 0; k < width; k++) {
            set(&cols[k], L_EXTRA, k);
            cols[k].extra = e;
        }
    }
}

/* --contact-columns KEY,KEY[:N],... (keywords) against c_ID[k] columns. */
static int gran_layout(dump_series *s, local_layout *l, const char *keywords, mimas_error *err)
{
    int width[NGRAN] = {0};
    int history_open = 0;
    char *text = strdup(keywords), *save = NULL;
    if (!text)
        return mimas_error_set(err, MIMAS_EIO, "out of memory for the contact dump reader");
    int rc = MIMAS_OK;
    for (char *tok = strtok_r(text, ",", &save); tok && !rc; tok = strtok_r(NULL, ",", &save)) {
        char *colon = strchr(tok, ':');
        long n = -1;
        if (colon) {
            *colon = '\0';
            char *end;
            n = strtol(colon + 1, &end, 10);
            if (*end || n < 1 || n > 64)
                rc = mimas_error_set(err, MIMAS_EUSAGE, "column keyword '%s:%s': the width "
                                     "must be a number from 1 to 64", tok, colon + 1);
        }
        size_t k = 0;
        while (k < NGRAN && strcmp(gran_order[k].key, tok) != 0)
            k++;
        if (rc)
            break;
        if (k == NGRAN)
            rc = mimas_error_set(err, MIMAS_EUSAGE,
                                 "unknown contact column keyword '%s' (LIGGGHTS: pos vel id "
                                 "force force_normal force_tangential torque torque_normal "
                                 "torque_tangential history[:N] contactArea delta contactPoint "
                                 "ms_id heatFlux)", tok);
        else if (width[k])
            rc = mimas_error_set(err, MIMAS_EUSAGE, "contact column keyword '%s' given twice",
                                 tok);
        else if (gran_order[k].width < 0) {
            width[k] = (int)n;
            history_open = n < 0;
        } else if (colon && n != gran_order[k].width) {
            rc = mimas_error_set(err, MIMAS_EUSAGE, "keyword '%s' has %d columns", tok,
                                 gran_order[k].width);
        } else {
            width[k] = gran_order[k].width;
        }
    }
    free(text);
    if (rc)
        return rc;
    /* history without a width: whatever columns the others leave */
    int total = 0;
    for (size_t k = 0; k < NGRAN; k++)
        total += width[k] > 0 ? width[k] : 0;
    if (history_open) {
        if ((long)l->c.ncols <= total)
            return text_error(&s->in, err, "%zu columns leave none for 'history'", l->c.ncols);
        for (size_t k = 0; k < NGRAN; k++)
            if (gran_order[k].width < 0)
                width[k] = (int)l->c.ncols - total;
        total = (int)l->c.ncols;
    }
    if ((size_t)total != l->c.ncols)
        return text_error(&s->in, err, "the keywords '%s' make %d columns, the dump has %zu",
                          keywords, total, l->c.ncols);
    int at = 0;
    for (size_t k = 0; k < NGRAN; k++)
        if (width[k] > 0) {
            gran_keyword(l, gran_order[k].key, width[k], &l->c.cols[at]);
            at += width[k];
        }
    return MIMAS_OK;
}

/* Columns with real names (or LAMMPS pair/local and property/local names
 * given by the user in dump order). */
static const struct {
    const char *name;
    int target, comp;
} named[] = {
    {"patom1", L_ID1, 0}, {"id1", L_ID1, 0},   {"patom2", L_ID2, 0}, {"id2", L_ID2, 0},
    {"fx", L_F, 0},       {"fy", L_F, 1},      {"fz", L_F, 2},       {"fnx", L_FN, 0},
    {"fny", L_FN, 1},     {"fnz", L_FN, 2},    {"ftx", L_FT, 0},     {"fty", L_FT, 1},
    {"ftz", L_FT, 2},     {"cpx", L_CP, 0},    {"cpy", L_CP, 1},     {"cpz", L_CP, 2},
    {"delta", L_DELTA, 0}, {"overlap", L_DELTA, 0}, {"dist", L_DIST, 0},
    {"wall", L_WALLID, 0},
};

static int named_layout(dump_series *s, local_layout *l, const char *names, mimas_error *err)
{
    char *text = strdup(names), *save = NULL;
    if (!text)
        return mimas_error_set(err, MIMAS_EIO, "out of memory for the contact dump reader");
    size_t c = 0;
    int rc = MIMAS_OK, prev_idx = 0;
    const char *sep = strchr(names, ',') ? "," : " \t";
    for (char *tok = strtok_r(text, sep, &save); tok && !rc; tok = strtok_r(NULL, sep, &save)) {
        if (c >= l->c.ncols) {
            rc = text_error(&s->in, err, "more column names than the dump's %zu columns",
                            l->c.ncols);
            break;
        }
        dump_col *col = &l->c.cols[c++];
        set(col, L_EXTRA, 0);
        for (size_t k = 0; k < sizeof named / sizeof named[0]; k++)
            if (!strcmp(named[k].name, tok))
                set(col, named[k].target, named[k].comp);
        if (col->target != L_EXTRA)
            prev_idx = 0;
        /* other names are extras; NAME[1] NAME[2] ... form one of k components */
        else if (dump_columns_extra_column(&l->c, col, tok, &prev_idx))
            rc = text_error(&s->in, err, "column '%s' appears twice", tok);
    }
    free(text);
    if (!rc && c != l->c.ncols)
        rc = text_error(&s->in, err, "%zu column names for the dump's %zu columns", c,
                        l->c.ncols);
    return rc;
}

/* 1 if every keyword of a comma list is a LIGGGHTS keyword (with an
 * optional ":N"); LAMMPS pair/local names (patom1, dist, fx, ...) are not. */
static int all_gran_keywords(const char *keywords)
{
    const char *p = keywords;
    while (*p) {
        size_t n = strcspn(p, ",:");
        int found = 0;
        for (size_t k = 0; k < NGRAN; k++)
            found |= strlen(gran_order[k].key) == n && !strncmp(gran_order[k].key, p, n);
        if (!found)
            return 0;
        p += strcspn(p, ",");
        if (*p)
            p++;
    }
    return 1;
}

static int is_anonymous(const char *columns)
{
    return strncmp(columns + strspn(columns, " \t"), "c_", 2) == 0 && strchr(columns, '[');
}

static int build_layout(dump_series *s, local_layout *l, mimas_error *err)
{
    local_layout_free(l);
    int rc0 = dump_columns_reset(&l->c, s->h.columns, err);
    if (rc0)
        return rc0;
    char *p = s->h.columns;
    while (skip_token(&p) == 0)
        l->c.ncols++;
    int gran = l->keywords && all_gran_keywords(l->keywords);
    int rc;
    if (l->keywords && gran)
        rc = gran_layout(s, l, l->keywords, err);
    else if (l->keywords)
        rc = named_layout(s, l, l->keywords, err);
    else if (is_anonymous(s->h.columns)) {
        /* LIGGGHTS' anonymous columns: the keyword set their count tells,
         * checked on the first contacts read (local_read) */
        if (gran_infer_keywords(l->c.ncols, l->inferred, sizeof l->inferred))
            return text_error(&s->in, err, "local dump columns are anonymous (%.20s...) and "
                              "%zu of them are none of the LIGGGHTS keyword sets mimas "
                              "recognises: name the keywords of the compute with --%s-columns",
                              s->h.columns + strspn(s->h.columns, " \t"), l->c.ncols,
                              l->walls ? "wall" : "contact");
        rc = gran_layout(s, l, l->inferred, err);
        l->check_pending = 1;
    } else
        rc = named_layout(s, l, s->h.columns, err);
    if (rc)
        return rc;
    int have[L_EXTRA][3];
    memset(have, 0, sizeof have);
    for (size_t c = 0; c < l->c.ncols; c++)
        if (l->c.cols[c].target != L_EXTRA && l->c.cols[c].target != L_SKIP)
            have[l->c.cols[c].target][l->c.cols[c].comp]++;
    if (!have[L_ID1][0] || (!l->walls && !have[L_ID2][0]))
        return text_error(&s->in, err, "the contact columns do not name both particle ids");
    l->bits = l->walls ? MIMAS_W_PARTICLE | MIMAS_W_WALL : MIMAS_C_I | MIMAS_C_J;
    static const int vec[3] = {L_F, L_FN, L_FT};
    static const unsigned cbit[3] = {MIMAS_C_FORCE, MIMAS_C_FORCE_N, MIMAS_C_FORCE_T};
    static const unsigned wbit[3] = {MIMAS_W_FORCE, MIMAS_W_FORCE_N, MIMAS_W_FORCE_T};
    for (int v = 0; v < 3; v++) {
        int n = have[vec[v]][0] + have[vec[v]][1] + have[vec[v]][2];
        if (n == 3)
            l->bits |= l->walls ? wbit[v] : cbit[v];
        else if (n)
            return text_error(&s->in, err, "the contact columns name an incomplete vector");
    }
    l->derive_overlap = !have[L_DELTA][0] && have[L_DIST][0] && !l->walls;
    if (have[L_DELTA][0] || l->derive_overlap)
        l->bits |= l->walls ? MIMAS_W_OVERLAP : MIMAS_C_OVERLAP;
    int ncp = have[L_CP][0] + have[L_CP][1] + have[L_CP][2];
    if (ncp != 0 && ncp != 3)
        return text_error(&s->in, err, "the contact columns name an incomplete contact point");
    /* without a contact point, pair contacts get c = r_i - (R_i - delta/2) n
     * (docs/theory.md §1); wall contacts cannot (the wall's geometry is unknown) */
    l->derive_point = ncp == 0 && !l->walls;
    if (ncp == 3 || l->derive_point)
        l->bits |= l->walls ? MIMAS_W_POINT : MIMAS_C_POINT;
    return MIMAS_OK;
}

int local_skip(dump_series *s, mimas_error *err)
{
    int rc = MIMAS_OK;
    for (size_t k = 0; k < s->h.count; k++)
        if (!dump_series_row(s, k, &rc, err))
            return rc;
    return MIMAS_OK;
}

/* c = r_i - (R_i - delta/2) n with n the unit vector from j to i (minimum
 * image), the contact point of docs/theory.md §1; also the overlap from a distance
 * column when the dump has no delta. */
static int derive(local_layout *l, mimas_frame *f, const double *dist, dump_series *s,
                  mimas_error *err)
{
    mimas_contacts *c = &f->contacts;
    const mimas_particles *p = &f->particles;
    if (l->derive_point && !(p->present & MIMAS_P_RADIUS))
        return mimas_error_set(err, MIMAS_EMISSING, "%s: contact points need particle radii "
                               "(the per-atom dump has no radius column)", s->in.path);
    for (size_t k = 0; k < c->n; k++) {
        size_t i = c->i[k], j = c->j[k];
        double d[3] = {p->pos[i][0] - p->pos[j][0], p->pos[i][1] - p->pos[j][1],
                       p->pos[i][2] - p->pos[j][2]};
        mimas_box_min_image(&f->box, d);
        double r = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
        if (l->derive_overlap) {
            if (!(p->present & MIMAS_P_RADIUS))
                return mimas_error_set(err, MIMAS_EMISSING, "%s: overlaps from distances need "
                                       "particle radii", s->in.path);
            c->overlap[k] = p->radius[i] + p->radius[j] - dist[k];
        }
        if (!l->derive_point)
            continue;
        if (!(r > 0))
            return mimas_error_set(err, MIMAS_EDATA, "%s: contact %zu joins two particles at "
                                   "the same place", s->in.path, k);
        double delta = (c->present & MIMAS_C_OVERLAP) ? c->overlap[k]
                                                      : p->radius[i] + p->radius[j] - r;
        double a = (p->radius[i] - 0.5 * delta) / r;
        for (int m = 0; m < 3; m++)
            c->point[k][m] = p->pos[i][m] - a * d[m];
    }
    return MIMAS_OK;
}

static int setup_table(local_layout *l, void *tab, const mimas_table_desc *d, size_t n,
                       mimas_error *err)
{
    mimas_table_keep_only(tab, d, l->bits);
    int rc = mimas_table_set_present(tab, d, l->bits, err);
    if (!rc)
        rc = dump_columns_extras_to(&l->c, tab, d, err);
    return rc ? rc : mimas_table_resize(tab, d, n, err);
}

/* The inferred keywords against the first contacts read with them: a data
 * error if they do not fit, else the reader's notify is told. */
static int check_inferred(dump_series *s, local_layout *l, const mimas_frame *f, size_t n,
                          mimas_error *err)
{
    char why[256];
    const char *opt = l->walls ? "wall-columns" : "contact-columns";
    if (gran_check_inferred(f, l->walls, why, sizeof why))
        return mimas_error_set(err, MIMAS_EDATA, "%s: the %zu anonymous columns look like "
                               "--%s %s, but %s (timestep %lld): give --%s", s->in.path,
                               l->c.ncols, opt, l->inferred, why, (long long)s->h.step, opt);
    l->check_pending = 0;
    if (l->notify) {
        char msg[900];
        snprintf(msg, sizeof msg, "%s: %zu anonymous columns read as --%s %s (checked on "
                 "timestep %lld: %zu %scontact%s)", s->in.path, l->c.ncols, opt, l->inferred,
                 (long long)s->h.step, n, l->walls ? "wall " : "", n == 1 ? "" : "s");
        l->notify(l->notify_ctx, msg);
    }
    return MIMAS_OK;
}

int local_read(dump_series *s, local_layout *l, mimas_frame *f, const mimas_id_index *index,
               mimas_error *err)
{
    int rc = MIMAS_OK;
    if (!dump_columns_current(&l->c, s->h.columns))
        rc = build_layout(s, l, err);
    if (rc)
        return rc;
    size_t n = s->h.count;
    void *tab = l->walls ? (void *)&f->walls : (void *)&f->contacts;
    const mimas_table_desc *d = l->walls ? &mimas_walls_desc : &mimas_contacts_desc;
    rc = setup_table(l, tab, d, n, err);
    double *dist = l->derive_overlap ? malloc((n ? n : 1) * sizeof *dist) : NULL;
    if (!rc && l->derive_overlap && !dist)
        rc = mimas_error_set(err, MIMAS_EIO, "out of memory for the contact dump reader");
    mimas_contacts *c = &f->contacts;
    mimas_wall_contacts *w = &f->walls;
    for (size_t k = 0; !rc && k < n; k++) {
        char *q = dump_series_row(s, k, &rc, err);
        if (!q)
            break;
        const size_t ncols = l->c.ncols;
        for (size_t col = 0; !rc && col < ncols; col++) {
            const dump_col *lc = &l->c.cols[col];
            double v = 0;
            int bad = lc->target == L_SKIP ? skip_token(&q) : parse_double_in_line(&q, &v);
            if (bad == -1) {
                rc = text_error(&s->in, err, "row has %zu values, the header names %zu", col,
                                ncols);
                break;
            }
            if (bad) {
                rc = text_error(&s->in, err, "value %zu is not a finite number", col + 1);
                break;
            }
            size_t idx = 0;
            switch (lc->target) {
            case L_ID1:
            case L_ID2:
                /* ids are written as numbers (LIGGGHTS prints them as doubles) */
                if (v != floor(v) || fabs(v) > 9007199254740992.0) {
                    rc = text_error(&s->in, err, "value %zu is not a particle id", col + 1);
                } else if (!mimas_id_index_find(index, (int64_t)v, &idx)) {
                    rc = text_error(&s->in, err, "contact names atom id %lld, which the per-atom "
                                    "snapshot of timestep %lld does not have", (long long)v,
                                    (long long)s->h.step);
                } else if (l->walls) {
                    w->particle[k] = idx;
                } else if (lc->target == L_ID1) {
                    c->i[k] = idx;
                } else {
                    c->j[k] = idx;
                }
                break;
            case L_WALLID:
                if (v != floor(v) || fabs(v) > 2147483647.0)
                    rc = text_error(&s->in, err, "value %zu is not a wall id", col + 1);
                else
                    w->wall[k] = (int32_t)v;
                break;
            case L_F: (l->walls ? w->force : c->force)[k][lc->comp] = v; break;
            case L_FN: (l->walls ? w->force_n : c->force_n)[k][lc->comp] = v; break;
            case L_FT: (l->walls ? w->force_t : c->force_t)[k][lc->comp] = v; break;
            case L_CP: (l->walls ? w->point : c->point)[k][lc->comp] = v; break;
            case L_DELTA: (l->walls ? w->overlap : c->overlap)[k] = v; break;
            case L_DIST: dist[k] = v; break;
            case L_EXTRA: {
                mimas_extra *x = l->walls ? &w->extra[lc->extra] : &c->extra[lc->extra];
                x->data[k * (size_t)x->ncomp + (size_t)lc->comp] = v;
                break;
            }
            default: break;
            }
        }
        if (!rc && skip_token(&q) == 0)
            rc = text_error(&s->in, err, "row has more values than the %zu the header names",
                            l->c.ncols);
    }
    if (!rc && !l->walls && (l->derive_point || l->derive_overlap))
        rc = derive(l, f, dist, s, err);
    free(dist);
    if (!rc && l->check_pending && n > 0)
        rc = check_inferred(s, l, f, n, err);
    if (!rc) {
        if (l->walls)
            f->has_walls = 1;
        else
            f->has_contacts = 1;
    }
    return rc;
}
