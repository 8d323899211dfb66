#include <config.h>

#include "cli_tube.h"

#include <math.h>
#include <string.h>

int cli_otable_open(cli_otable *t, FILE *fp, const cli_table_options *o, mimas_h5out *h5,
                    const char *group, const mimas_ocolumn *cols, size_t ncols,
                    mimas_error *err)
{
    memset(t, 0, sizeof *t);
    t->cols = cols;
    t->ncols = ncols;
    if (h5) {
        int rc = mimas_otable_open(&t->h5, h5, group, cols, ncols, err);
        if (rc)
            return rc;
    }
    if (fp) {
        t->has_text = 1;
        cli_table_start(&t->text, fp, o);
        for (size_t c = 0; c < ncols; c++)
            cli_table_column(&t->text, cols[c].name, cols[c].unit);
        cli_table_header_end(&t->text);
    }
    return MIMAS_OK;
}

int cli_otable_row(cli_otable *t, const double *v, const char *const *text, mimas_error *err)
{
    if (t->has_text) {
        for (size_t c = 0; c < t->ncols; c++) {
            if (t->cols[c].text)
                cli_table_text(&t->text, text[c]);
            else if (t->cols[c].integer && v[c] == v[c])
                cli_table_int(&t->text, (long long)v[c]);
            else
                cli_table_double(&t->text, v[c]);
        }
        cli_table_row_end(&t->text);
        if (ferror(t->text.fp))
            return mimas_error_set(err, MIMAS_EIO, "cannot write the table");
    }
    return t->h5 ? mimas_otable_row(t->h5, v, text, err) : MIMAS_OK;
}

int cli_otable_close(cli_otable *t, mimas_error *err)
{
    int rc = MIMAS_OK;
    if (t->has_text && cli_table_end(&t->text))
        rc = mimas_error_set(err, MIMAS_EIO, "cannot write the table");
    t->has_text = 0;
    int closed = mimas_otable_close(t->h5, err);
    t->h5 = NULL;
    return rc ? rc : closed;
}

int cli_tube_decide(void *ctx, const mimas_frame *f, void *data, mimas_error *err)
{
    const cli_tube_args *t = ctx;
    return mimas_tube_setup_from(data, t->axis, t->radius, f, t->types.types, t->types.n,
                                 t->types.exclude, err);
}

void cli_tube_args_init(cli_tube_args *t)
{
    memset(t, 0, sizeof *t);
    t->threshold = 0.6;
}

int cli_tube_option(const cli_command *cmd, cli_tube_args *t, int key, const char *arg)
{
    switch (key) {
    case CLI_TUBE_AXIS: t->axis = arg; return 0;
    case CLI_TUBE_RADIUS: return cli_positive_option(cmd, "tube-radius", arg, &t->radius);
    case CLI_TUBE_RANGE:
        t->has_range = 1;
        return cli_pair_option(cmd, "range", "S0:S1", arg, &t->s0, &t->s1);
    case CLI_TUBE_SLICE: return cli_positive_option(cmd, "slice", arg, &t->slice);
    case CLI_TUBE_DIAMETER: return cli_positive_option(cmd, "diameter", arg, &t->diameter);
    case CLI_TUBE_TEMP: return cli_parse_temperature(cmd, arg, &t->temperature);
    case CLI_TUBE_THRESHOLD:
        if (cli_parse_double(arg, &t->threshold) || !(t->threshold > 0) || !(t->threshold <= 1))
            return cli_fail(cmd, 1, "--threshold needs a porosity in (0, 1], not '%s'", arg);
        return 0;
    case CLI_TUBE_MINLEN: return cli_positive_option(cmd, "min-length", arg, &t->min_length);
    default: return cli_types_option(cmd, &t->types, key == CLI_TUBE_EXCLUDE, arg);
    }
}

int cli_tube_plug_setup(const cli_tube_args *t, const mimas_tube_setup *ts,
                        mimas_axial_options *ao, mimas_plug_options *po, double *d, double *s0,
                        double *s1, mimas_error *err)
{
    memset(ao, 0, sizeof *ao);
    ao->geom = ts->geom;
    *d = t->diameter > 0 ? t->diameter : ts->diameter;
    int known = isfinite(ao->geom.length);
    *s0 = t->has_range ? t->s0 : known ? 0.0 : ts->s_min;
    *s1 = t->has_range ? t->s1 : known ? ao->geom.length : ts->s_max;
    int rc;
    if ((rc = mimas_tube_defaults_known(*d, *s0, *s1, err)) ||
        (rc = mimas_slices_set(&ao->slices, *s0, *s1, t->slice > 0 ? t->slice : 0.5 * *d, err)))
        return rc;
    ao->temperature = t->temperature;
    ao->types = t->types.types;
    ao->ntypes = t->types.n;
    ao->exclude = t->types.exclude;
    ao->check_inside = 1;
    ao->flow_at = NAN; /* plug detection needs no flow rate */
    po->threshold = t->threshold;
    po->min_length = t->min_length > 0 ? t->min_length : *d;
    return MIMAS_OK;
}
