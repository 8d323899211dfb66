/* The picture of one field of a field set (mimas plot): a colour map over
 * the two gridded directions (r-z, x-z, ...) with a colour bar in the
 * field's unit, or, on a grid with one gridded direction, the profile with
 * its standard errors. */
#include <config.h>

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "field_table.h"
#include "fieldset.h"
#include "plot.h"

static const char *const coord[2][3] = {{"x", "y", "z"}, {"r", "φ", "z"}};
static const char *const coord_unit[2][3] = {{"m", "m", "m"}, {"m", "rad", "m"}};

/* The directions drawn: those with more than one cell. */
static int drawn_directions(const mimas_fieldset_grid *g, int dirs[3])
{
    int n = 0;
    for (int d = 0; d < 3; d++)
        if (g->n[d] > 1)
            dirs[n++] = d;
    return n;
}

/* The field's unit from the field table ("" if the name is not there). */
static const char *unit_of(const char *field, int cyl)
{
    size_t k;
    return mimas_field_find(field, cyl, &k) ? mimas_field(k)->unit : "";
}

/* "kg m-3" -> "kg m^{-3}", "1" -> "" (dimensionless): enhanced text */
static void unit_text(const char *unit, char *buf, size_t len)
{
    size_t k = 0;
    buf[0] = '\0';
    if (!strcmp(unit, "1") || !unit[0])
        return;
    for (const char *u = unit; *u && k + 8 < len; u++) {
        if ((*u == '-' || (*u >= '0' && *u <= '9')) && u > unit && u[-1] != ' ' &&
            !(u[-1] == '-' || (u[-1] >= '0' && u[-1] <= '9'))) {
            size_t n = strspn(u, "-0123456789");
            k += (size_t)snprintf(buf + k, len - k, "^{%.*s}", (int)n, u);
            u += n - 1;
        } else
            buf[k++] = *u;
    }
    buf[k < len ? k : len - 1] = '\0';
}

/* viridis (matplotlib's perceptually uniform map), sampled at eleven points */
static const char viridis[] =
    "set palette defined (0 '#440154', 1 '#482475', 2 '#414487', 3 '#355f8d', 4 '#2a788e', "
    "5 '#21918c', 6 '#22a884', 7 '#44bf70', 8 '#7ad151', 9 '#bddf26', 10 '#fde725')";

static int write_data(const mimas_fieldset *fs, const double *v, const double *e,
                      const int *dirs, int ndirs, mimas_plot *p, size_t *defined,
                      mimas_error *err)
{
    const mimas_fieldset_grid *g = mimas_fieldset_grid_of(fs);
    FILE *fp = mimas_plot_data(p, "field", err);
    if (!fp)
        return err->code;
    *defined = 0;
    int a = dirs[0], b = ndirs > 1 ? dirs[1] : -1;
    int nb = b >= 0 ? g->n[b] : 1;
    /* cell index: direction 0 fastest; the other directions have one cell */
    size_t stride[3] = {1, (size_t)g->n[0], (size_t)g->n[0] * (size_t)g->n[1]};
    for (int j = 0; j < nb; j++) {
        for (int i = 0; i < g->n[a]; i++) {
            size_t c = (size_t)i * stride[a] + (b >= 0 ? (size_t)j * stride[b] : 0);
            *defined += isfinite(v[c]) != 0;
            if (b >= 0)
                fprintf(fp, "%.9g\t%.9g\t%.9g\n", g->centre[a][i], g->centre[b][j], v[c]);
            else
                fprintf(fp, "%.9g\t%.9g\t%.9g\n", g->centre[a][i], v[c], e ? e[c] : NAN);
        }
        if (b >= 0)
            fputs("\n", fp); /* gnuplot's grid blocks */
    }
    return MIMAS_OK;
}

int mimas_fieldset_plot(const mimas_fieldset *fs, const char *field,
                        const mimas_fieldset_plot_options *o, const char *png, mimas_error *err)
{
    const mimas_fieldset_grid *g = mimas_fieldset_grid_of(fs);
    int dirs[3], ndirs = drawn_directions(g, dirs);
    if (ndirs < 1 || ndirs > 2)
        return mimas_error_set(err, MIMAS_EDATA,
                               "%s: the grid has %d directions with more than one cell; a plot "
                               "needs one (a profile) or two (a map)",
                               mimas_fieldset_name(fs), ndirs);
    if (!mimas_fieldset_has(fs, field))
        return mimas_error_set(err, MIMAS_EMISSING, "%s: no field '%s' (docs/fields.md)",
                               mimas_fieldset_name(fs), field);
    double *v = malloc(g->cells * sizeof *v), *e = malloc(g->cells * sizeof *e);
    if (!v || !e) {
        free(v), free(e);
        return mimas_error_set(err, MIMAS_EIO, "out of memory");
    }
    int rc = mimas_fieldset_read(fs, field, v, e, err);
    if (!rc && o && o->error)
        memcpy(v, e, g->cells * sizeof *v);
    mimas_plot *p = NULL;
    if (!rc)
        rc = mimas_plot_open(&p, png, err);
    size_t defined = 0;
    if (!rc)
        rc = write_data(fs, v, o && o->error ? NULL : e, dirs, ndirs, p, &defined, err);
    free(v), free(e);
    if (rc) {
        mimas_plot_abort(p);
        return rc;
    }

    int cyl = g->kind == MIMAS_FIELDSET_CYLINDRICAL;
    char sym[96], unit[64], value[200], title[4400], file[4200];
    mimas_plot_symbol(field, sym, sizeof sym);
    unit_text(unit_of(field, cyl), unit, sizeof unit);
    snprintf(value, sizeof value, "%s%s%s%s%s", o && o->error ? "standard error of " : "", sym,
             unit[0] ? " (" : "", unit, unit[0] ? ")" : "");
    /* the file's own name: a long path in the title says little and may not fit */
    const char *name = mimas_fieldset_name(fs), *slash = strrchr(name, '/');
    mimas_plot_literal(slash && slash[1] ? slash + 1 : name, file, sizeof file);
    snprintf(title, sizeof title, "%s, %zu frames", file, g->frames);
    int a = dirs[0], b = ndirs > 1 ? dirs[1] : -1;
    char ca[64], script[8192];
    snprintf(ca, sizeof ca, "%s (%s)", coord[cyl][a], coord_unit[cyl][a]);
    char vrange[96] = "[*:*]";
    if (o && (isfinite(o->lo) || isfinite(o->hi))) {
        char lo[32] = "*", hi[32] = "*";
        if (isfinite(o->lo))
            snprintf(lo, sizeof lo, "%.9g", o->lo);
        if (isfinite(o->hi))
            snprintf(hi, sizeof hi, "%.9g", o->hi);
        snprintf(vrange, sizeof vrange, "[%s:%s]", lo, hi);
    }
    int logv = o && o->logscale;
    int w = 900, h = 600;
    if (!defined)
        snprintf(script, sizeof script,
                 "set title '%s'\nset label 'the field is undefined (nan) in every cell' at "
                 "graph 0.2, graph 0.5\nplot [0:1][0:1] NaN notitle\n", title);
    else if (b >= 0) {
        /* cell-centred values drawn as their cells, to scale where both axes are
         * lengths; undefined cells stay white */
        int lengths = !(cyl && (a == 1 || b == 1));
        snprintf(script, sizeof script,
                 "set title '%s'\nset xlabel '%s'\nset ylabel '%s (%s)'\nset cblabel '%s'\n"
                 "%s%s\nset cbrange %s\n%sset tics out\nset autoscale fix\nset key off\n"
                 "set rmargin 16\n"
                 "plot datadir.'/field' using 1:2:3 with image\n",
                 title, ca, coord[cyl][b], coord_unit[cyl][b], value,
                 lengths ? "set size ratio -1\n" : "", viridis, vrange,
                 logv ? "set logscale cb\n" : "");
        double ea = g->centre[a][g->n[a] - 1] - g->centre[a][0];
        double eb = g->centre[b][g->n[b] - 1] - g->centre[b][0];
        double ratio = lengths && ea > 0 && eb > 0 ? eb / ea : 0.6;
        ratio = ratio < 0.15 ? 0.15 : ratio > 3 ? 3 : ratio;
        w = 1000;
        /* the plot area is the width less the margins and the colour bar */
        h = (int)(720 * ratio) + 170;
        h = h < 320 ? 320 : h;
    } else if (a == 2) {
        /* a profile along z: height upwards */
        snprintf(script, sizeof script,
                 "set title '%s'\nset xlabel '%s'\nset ylabel '%s'\n%sset offsets graph 0.05, "
                 "graph 0.05, graph 0.02, graph 0.02\nset autoscale fix\nset key off\n"
                 "set grid\n"
                 "plot %s[*:*] datadir.'/field' using 2:1:3 with xerrorbars pt 7 ps 0.6 "
                 "lc rgb '#3060b0', '' using 2:1 with lines lc rgb '#3060b0'\n",
                 title, value, ca, logv ? "set logscale x\n" : "", vrange);
        w = 600, h = 800;
    } else
        snprintf(script, sizeof script,
                 "set title '%s'\nset xlabel '%s'\nset ylabel '%s'\n%sset offsets graph 0.02, "
                 "graph 0.02, graph 0.05, graph 0.05\nset autoscale fix\nset key off\n"
                 "set grid\n"
                 "plot [*:*]%s datadir.'/field' using 1:2:3 with yerrorbars pt 7 ps 0.6 "
                 "lc rgb '#3060b0', '' using 1:2 with lines lc rgb '#3060b0'\n",
                 title, ca, value, logv ? "set logscale y\n" : "", vrange);
    rc = mimas_plot_render(p, w, h, script, err);
    if (rc) {
        mimas_plot_abort(p);
        return rc;
    }
    return mimas_plot_commit(p, err);
}
