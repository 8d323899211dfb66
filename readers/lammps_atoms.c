#include <config.h>

#include "lammps_atoms.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "id_index.h"
#include "numparse.h"

enum {
    A_SKIP, A_ID, A_TYPE, A_X, A_XU, A_XS, A_XSU, A_IMAGE, A_V, A_F, A_OMEGA, A_RADIUS,
    A_DIAMETER, A_MASS, A_CG, A_LIQUID, A_EXTRA
};

/* Named per-atom columns LAMMPS and LIGGGHTS write; anything else is kept as
 * an extra column. */
static const struct {
    const char *name;
    int target, comp;
} known[] = {
    {"id", A_ID, 0},         {"type", A_TYPE, 0},       {"x", A_X, 0},
    {"y", A_X, 1},           {"z", A_X, 2},             {"xu", A_XU, 0},
    {"yu", A_XU, 1},         {"zu", A_XU, 2},           {"xs", A_XS, 0},
    {"ys", A_XS, 1},         {"zs", A_XS, 2},           {"xsu", A_XSU, 0},
    {"ysu", A_XSU, 1},       {"zsu", A_XSU, 2},         {"ix", A_IMAGE, 0},
    {"iy", A_IMAGE, 1},      {"iz", A_IMAGE, 2},        {"vx", A_V, 0},
    {"vy", A_V, 1},          {"vz", A_V, 2},            {"fx", A_F, 0},
    {"fy", A_F, 1},          {"fz", A_F, 2},            {"omegax", A_OMEGA, 0},
    {"omegay", A_OMEGA, 1},  {"omegaz", A_OMEGA, 2},    {"radius", A_RADIUS, 0},
    {"diameter", A_DIAMETER, 0}, {"mass", A_MASS, 0},
    /* the names mimas convert --to lammps gives them */
    {"coarse_grain_factor", A_CG, 0}, {"liquid_volume", A_LIQUID, 0},
};

void atom_layout_free(atom_layout *l)
{
    dump_columns_free(&l->c);
    memset(l, 0, sizeof *l);
}

static int build_layout(dump_series *s, atom_layout *l, mimas_error *err)
{
    atom_layout_free(l);
    dump_columns *cl = &l->c;
    int rc0 = dump_columns_reset(cl, s->h.columns, err);
    if (rc0)
        return rc0;
    int have[A_EXTRA][3];
    memset(have, 0, sizeof have);
    int prev_idx = 0;
    char *save = NULL, *text = strdup(s->h.columns);
    if (!text)
        return mimas_error_set(err, MIMAS_EIO, "out of memory for the ATOMS columns");
    for (char *tok = strtok_r(text, " \t", &save); tok; tok = strtok_r(NULL, " \t", &save)) {
        dump_col *c = &cl->cols[cl->ncols++];
        c->target = A_EXTRA;
        for (size_t k = 0; k < sizeof known / sizeof known[0]; k++)
            if (!strcmp(tok, known[k].name)) {
                c->target = known[k].target;
                c->comp = known[k].comp;
            }
        if (c->target != A_EXTRA) {
            if (have[c->target][c->comp]++) {
                int rc = text_error(&s->in, err, "column '%s' appears twice", tok);
                free(text);
                return rc;
            }
            prev_idx = 0;
            continue;
        }
        if (dump_columns_extra_column(cl, c, tok, &prev_idx)) {
            int rc = text_error(&s->in, err, "column '%s' appears twice", tok);
            free(text);
            return rc;
        }
    }
    free(text);
    if (!have[A_ID][0])
        return text_error(&s->in, err, "the ATOMS columns have no id");
    /* positions: x y z, else unwrapped, else scaled, else scaled unwrapped */
    static const int order[4] = {A_X, A_XU, A_XS, A_XSU};
    l->pos_target = A_SKIP;
    for (int k = 0; k < 4 && l->pos_target == A_SKIP; k++)
        if (have[order[k]][0] && have[order[k]][1] && have[order[k]][2])
            l->pos_target = order[k];
    if (l->pos_target == A_SKIP)
        return text_error(&s->in, err, "the ATOMS columns have no complete set of positions "
                                       "(x y z, xu yu zu, xs ys zs or xsu ysu zsu)");
    l->bits = MIMAS_P_ID | MIMAS_P_POS;
    if (have[A_TYPE][0])
        l->bits |= MIMAS_P_TYPE;
    if (have[A_RADIUS][0] || have[A_DIAMETER][0])
        l->bits |= MIMAS_P_RADIUS;
    if (have[A_MASS][0])
        l->bits |= MIMAS_P_MASS;
    if (have[A_CG][0])
        l->bits |= MIMAS_P_CG;
    if (have[A_LIQUID][0])
        l->bits |= MIMAS_P_LIQUID;
    static const struct {
        int target;
        unsigned bit;
    } vec[4] = {{A_V, MIMAS_P_VEL}, {A_F, MIMAS_P_FORCE}, {A_OMEGA, MIMAS_P_OMEGA},
                {A_IMAGE, MIMAS_P_IMAGE}};
    for (int k = 0; k < 4; k++) {
        int n = have[vec[k].target][0] + have[vec[k].target][1] + have[vec[k].target][2];
        if (n == 3)
            l->bits |= vec[k].bit;
        else if (n > 0)
            return text_error(&s->in, err, "the ATOMS columns have an incomplete vector "
                                           "(all three components are needed)");
    }
    /* unwrapped positions are wrapped into a periodic box by the reader
     * (readers/reader.c), which counts the shifts in image flags that start
     * at 0: the dump's own ix iy iz belong to its wrapped x y z */
    int unwrapped = l->pos_target == A_XU || l->pos_target == A_XSU;
    if (unwrapped)
        l->bits |= MIMAS_P_IMAGE;
    /* position columns not used (e.g. xu beside x) are skipped */
    for (size_t c = 0; c < cl->ncols; c++) {
        int t = cl->cols[c].target;
        if (((t == A_X || t == A_XU || t == A_XS || t == A_XSU) && t != l->pos_target) ||
            (t == A_IMAGE && unwrapped))
            cl->cols[c].target = A_SKIP;
        if (t == A_DIAMETER && have[A_RADIUS][0])
            cl->cols[c].target = A_SKIP;
    }
    return MIMAS_OK;
}

static int setup_frame(atom_layout *l, mimas_frame *f, size_t n, int want_mass,
                       mimas_error *err)
{
    mimas_particles *p = &f->particles;
    unsigned bits = l->bits | (want_mass ? MIMAS_P_MASS : 0);
    mimas_table_keep_only(p, &mimas_particles_desc, bits);
    int rc = mimas_table_set_present(p, &mimas_particles_desc, bits, err);
    if (!rc)
        rc = dump_columns_extras_to(&l->c, p, &mimas_particles_desc, err);
    if (!rc)
        rc = mimas_table_resize(p, &mimas_particles_desc, n, err);
    return rc;
}

static int parse_row(dump_series *s, const atom_layout *l, mimas_particles *p, size_t k,
                     char *row, mimas_error *err)
{
    char *q = row;
    const size_t ncols = l->c.ncols;
    for (size_t c = 0; c < ncols; c++) {
        const dump_col *col = &l->c.cols[c];
        int64_t iv = 0;
        double dv = 0;
        int bad;
        switch (col->target) {
        case A_ID:
        case A_TYPE:
        case A_IMAGE:
            bad = parse_int64(&q, &iv);
            break;
        case A_SKIP:
            bad = skip_token(&q);
            break;
        default:
            bad = parse_double_in_line(&q, &dv);
        }
        if (bad == -1)
            return text_error(&s->in, err, "row has %zu values, the ATOMS header names %zu", c,
                              ncols);
        if (bad)
            return text_error(&s->in, err, "value %zu is not %s", c + 1,
                              col->target == A_ID || col->target == A_TYPE ||
                                      col->target == A_IMAGE
                                  ? "an integer"
                                  : "a finite number");
        switch (col->target) {
        case A_ID: p->id[k] = iv; break;
        case A_TYPE:
        case A_IMAGE:
            if (iv < INT32_MIN || iv > INT32_MAX)
                return text_error(&s->in, err, "value %zu is out of range", c + 1);
            if (col->target == A_TYPE)
                p->type[k] = (int32_t)iv;
            else
                p->image[k][col->comp] = (int32_t)iv;
            break;
        case A_X:
        case A_XU:
        case A_XS:
        case A_XSU: p->pos[k][col->comp] = dv; break;
        case A_V: p->vel[k][col->comp] = dv; break;
        case A_F: p->force[k][col->comp] = dv; break;
        case A_OMEGA: p->omega[k][col->comp] = dv; break;
        case A_RADIUS: p->radius[k] = dv; break;
        case A_DIAMETER: p->radius[k] = 0.5 * dv; break;
        case A_MASS: p->mass[k] = dv; break;
        case A_CG: p->cg[k] = dv; break;
        case A_LIQUID: p->liquid[k] = dv; break;
        case A_EXTRA:
            p->extra[col->extra].data[k * (size_t)p->extra[col->extra].ncomp + (size_t)col->comp] =
                dv;
            break;
        default: break;
        }
    }
    if (skip_token(&q) == 0)
        return text_error(&s->in, err, "row has more values than the %zu the ATOMS header names",
                          ncols);
    return MIMAS_OK;
}

int atoms_read(dump_series *s, atom_layout *l, mimas_frame *f, double density, double dt,
               mimas_id_index *index, mimas_error *err)
{
    int rc = MIMAS_OK;
    if (!dump_columns_current(&l->c, s->h.columns))
        rc = build_layout(s, l, err);
    if (rc)
        return rc;
    size_t n = s->h.count;
    int want_mass = !(l->bits & MIMAS_P_MASS) && density > 0 && (l->bits & MIMAS_P_RADIUS);
    rc = setup_frame(l, f, n, want_mass, err);
    if (rc)
        return rc;
    mimas_particles *p = &f->particles;
    long first_line = s->in.line + 1;
    for (size_t k = 0; k < n; k++) {
        char *row = dump_series_row(s, k, &rc, err);
        if (!row)
            return rc;
        rc = parse_row(s, l, p, k, row, err);
        if (rc)
            return rc;
    }
    if (l->pos_target == A_XU || l->pos_target == A_XSU)
        memset(p->image, 0, n * sizeof *p->image);
    f->step = s->h.step;
    f->time = s->h.has_time ? s->h.time : (dt > 0 ? (double)s->h.step * dt : NAN);
    f->box = s->h.box;
    const mimas_box *b = &f->box;
    if (l->pos_target == A_XS || l->pos_target == A_XSU) {
        /* scaled (fractional) coordinates: x = lo + xs a + ys b + zs c */
        double L[3] = {b->hi[0] - b->lo[0], b->hi[1] - b->lo[1], b->hi[2] - b->lo[2]};
        for (size_t k = 0; k < n; k++) {
            double *x = p->pos[k], s0 = x[0], s1 = x[1], s2 = x[2];
            x[0] = b->lo[0] + s0 * L[0] + s1 * b->xy + s2 * b->xz;
            x[1] = b->lo[1] + s1 * L[1] + s2 * b->yz;
            x[2] = b->lo[2] + s2 * L[2];
        }
    }
    for (size_t k = 0; k < n && (l->bits & MIMAS_P_RADIUS); k++)
        if (!(p->radius[k] > 0))
            return mimas_error_set(err, MIMAS_EDATA, "%s:%ld: radius %g is not positive",
                                   s->in.path, first_line + (long)k, p->radius[k]);
    if (want_mass)
        for (size_t k = 0; k < n; k++)
            p->mass[k] = density * 4.0 / 3.0 * M_PI * p->radius[k] * p->radius[k] * p->radius[k];
    /* unique ids (rows may come in any order); the map serves the contacts */
    rc = mimas_id_index_build(index, p->id, n, err);
    if (rc == MIMAS_EDATA) {
        for (size_t k = 0, seen = 0; k < n; k++)
            if (p->id[k] == index->duplicate && seen++)
                return mimas_error_set(err, MIMAS_EDATA, "%s:%ld: duplicate atom id %lld",
                                       s->in.path, first_line + (long)k,
                                       (long long)index->duplicate);
    }
    if (rc)
        return rc;
    return MIMAS_OK;
}
