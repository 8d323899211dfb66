#include <config.h>

#include "cli_tube.h"

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
    const cli_tube_pick *p = ctx;
    return mimas_tube_setup_from(data, p->axis, p->radius, f, p->types->types, p->types->n,
                                 p->types->exclude, err);
}
