/* Tables, result files and space-time fields of the tube analyses
 * (plugs_output.h). */
#include <config.h>

#include "plugs_output.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "h5util.h"
#include "tmpfiles.h"

/* ---- HDF5 file under a temporary name ---- */

struct mimas_h5out {
    hid_t file;
    h5_quiet quiet;
    int slot; /* in the temporary-file registry */
    char path[4096], tmp[4200];
};

int mimas_h5out_open(mimas_h5out **op, const char *path, mimas_error *err)
{
    mimas_h5out *o = calloc(1, sizeof *o);
    if (!o)
        return mimas_error_set(err, MIMAS_EIO, "out of memory");
    if (strlen(path) >= sizeof o->path) {
        free(o);
        return mimas_error_set(err, MIMAS_EUSAGE, "%.64s...: path too long", path);
    }
    snprintf(o->path, sizeof o->path, "%s", path);
    mimas_tmpfile_name(o->tmp, sizeof o->tmp, path);
    o->slot = mimas_tmpfile_add(o->tmp);
    h5_quiet_begin(&o->quiet);
    o->file = H5Fcreate(o->tmp, H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
    if (o->file < 0) {
        h5_quiet_end(&o->quiet);
        mimas_tmpfile_forget(o->slot);
        free(o);
        return mimas_error_set(err, MIMAS_EIO, "%s: cannot create the file", path);
    }
    *op = o;
    return MIMAS_OK;
}

static hid_t h5out_group(mimas_h5out *o, const char *name)
{
    hid_t lcpl = H5Pcreate(H5P_LINK_CREATE);
    H5Pset_create_intermediate_group(lcpl, 1);
    hid_t g = H5Gcreate2(o->file, name, lcpl, H5P_DEFAULT, H5P_DEFAULT);
    H5Pclose(lcpl);
    return g;
}

int mimas_h5out_commit(mimas_h5out *o, const char *provenance, mimas_error *err)
{
    hid_t g = h5out_group(o, "/mimas");
    int rc = g < 0 || h5_attr_write_str(g, "creator", PACKAGE_NAME " " PACKAGE_VERSION) ||
             (provenance && h5_attr_write_str(g, "provenance", provenance));
    if (g >= 0)
        H5Gclose(g);
    rc |= H5Fclose(o->file) < 0;
    o->file = -1;
    if (!rc)
        rc = rename(o->tmp, o->path) != 0;
    if (rc) {
        char msg[256];
        h5_error_text(msg, sizeof msg);
        mimas_error_set(err, MIMAS_EIO, "%s: cannot write the file%s%s", o->path,
                        *msg ? ": " : "", msg);
    }
    mimas_h5out_abort(o);
    return rc ? MIMAS_EIO : MIMAS_OK;
}

void mimas_h5out_abort(mimas_h5out *o)
{
    if (!o)
        return;
    if (o->file >= 0)
        H5Fclose(o->file);
    remove(o->tmp); /* gone already after a rename */
    mimas_tmpfile_forget(o->slot);
    h5_quiet_end(&o->quiet);
    free(o);
}

/* ---- tables ---- */

#define OT_BLOCK 256 /* HDF5 rows buffered per column */

struct mimas_otable {
    const mimas_ocolumn *cols;
    size_t ncols;
    hid_t *ds;        /* per column, or NULL without HDF5 */
    hid_t strtype;
    double *num;      /* OT_BLOCK x ncols */
    char **txt;       /* OT_BLOCK x ncols (text columns) */
    size_t buffered;
    hsize_t rows;     /* rows in the datasets */
    hid_t group;
    int failed;
};

int mimas_otable_open(mimas_otable **tp, mimas_h5out *h5, const char *name,
                      const mimas_ocolumn *cols, size_t ncols, mimas_error *err)
{
    hid_t group = h5out_group(h5, name);
    if (group < 0)
        return mimas_error_set(err, MIMAS_EIO, "%s: cannot write the group %s", h5->path, name);
    mimas_otable *t = calloc(1, sizeof *t);
    if (!t) {
        if (group >= 0)
            H5Gclose(group);
        return mimas_error_set(err, MIMAS_EIO, "out of memory");
    }
    t->cols = cols;
    t->ncols = ncols;
    t->group = group;
    {
        t->ds = malloc(ncols * sizeof *t->ds);
        t->num = malloc(OT_BLOCK * ncols * sizeof *t->num);
        t->txt = calloc(OT_BLOCK * ncols, sizeof *t->txt);
        t->strtype = H5Tcopy(H5T_C_S1);
        H5Tset_size(t->strtype, H5T_VARIABLE);
        if (!t->ds || !t->num || !t->txt) {
            free(t->ds);
            t->ds = NULL;
            mimas_otable_close(t, NULL);
            return mimas_error_set(err, MIMAS_EIO, "out of memory");
        }
        int rc = 0;
        hsize_t zero = 0, chunk = OT_BLOCK;
        for (size_t c = 0; c < ncols; c++) {
            t->ds[c] = h5_create_growing(group, cols[c].name,
                                         cols[c].text ? t->strtype : H5T_IEEE_F64LE, 1, 1, &zero,
                                         &chunk, NULL, cols[c].text ? 0 : 1);
            rc |= t->ds[c] < 0 ||
                  (cols[c].unit && *cols[c].unit &&
                   h5_attr_write_str(t->ds[c], "unit", cols[c].unit)) ||
                  (cols[c].meaning && h5_attr_write_str(t->ds[c], "definition", cols[c].meaning));
        }
        if (rc) {
            mimas_otable_close(t, NULL);
            return mimas_error_set(err, MIMAS_EIO, "cannot create the HDF5 table");
        }
    }
    *tp = t;
    return MIMAS_OK;
}

static int flush(mimas_otable *t)
{
    if (!t->ds || !t->buffered)
        return 0;
    int rc = 0;
    double *col = malloc(t->buffered * sizeof *col);
    char **scol = malloc(t->buffered * sizeof *scol);
    if (!col || !scol)
        rc = 1;
    for (size_t c = 0; !rc && c < t->ncols; c++) {
        hsize_t ext = t->rows + t->buffered, start = t->rows, count = t->buffered;
        if (H5Dset_extent(t->ds[c], &ext) < 0) {
            rc = 1;
            break;
        }
        hid_t fs = H5Dget_space(t->ds[c]), ms = H5Screate_simple(1, &count, NULL);
        H5Sselect_hyperslab(fs, H5S_SELECT_SET, &start, NULL, &count, NULL);
        if (t->cols[c].text) {
            for (size_t r = 0; r < t->buffered; r++)
                scol[r] = t->txt[r * t->ncols + c];
            rc |= H5Dwrite(t->ds[c], t->strtype, ms, fs, H5P_DEFAULT, scol) < 0;
        } else {
            for (size_t r = 0; r < t->buffered; r++)
                col[r] = t->num[r * t->ncols + c];
            rc |= H5Dwrite(t->ds[c], H5T_NATIVE_DOUBLE, ms, fs, H5P_DEFAULT, col) < 0;
        }
        H5Sclose(ms);
        H5Sclose(fs);
    }
    for (size_t q = 0; q < t->buffered * t->ncols; q++) {
        free(t->txt[q]);
        t->txt[q] = NULL;
    }
    free(col);
    free(scol);
    t->rows += t->buffered;
    t->buffered = 0;
    return rc;
}

int mimas_otable_row(mimas_otable *t, const double *v, const char *const *text,
                     mimas_error *err)
{
    for (size_t c = 0; c < t->ncols; c++) {
        size_t q = t->buffered * t->ncols + c;
        if (t->cols[c].text) {
            t->txt[q] = strdup(text[c]);
            if (!t->txt[q])
                t->failed = 1;
        } else {
            t->num[q] = v[c];
        }
    }
    if (++t->buffered == OT_BLOCK && flush(t))
        t->failed = 1;
    if (t->failed)
        return mimas_error_set(err, MIMAS_EIO, "cannot write the HDF5 table");
    return MIMAS_OK;
}

int mimas_otable_close(mimas_otable *t, mimas_error *err)
{
    if (!t)
        return MIMAS_OK;
    int rc = t->failed;
    if (t->ds) {
        rc |= flush(t);
        for (size_t c = 0; c < t->ncols; c++)
            if (t->ds[c] >= 0)
                H5Dclose(t->ds[c]);
    }
    if (t->txt)
        for (size_t q = 0; q < OT_BLOCK * t->ncols; q++)
            free(t->txt[q]);
    if (t->strtype > 0)
        H5Tclose(t->strtype);
    if (t->group >= 0)
        H5Gclose(t->group);
    free(t->ds);
    free(t->num);
    free(t->txt);
    free(t);
    return rc ? mimas_error_set(err, MIMAS_EIO, "cannot write the HDF5 table") : MIMAS_OK;
}

/* ---- space-time fields ---- */

struct mimas_spacetime {
    mimas_h5out *h5;
    hid_t group, step, time, field[MIMAS_AX_NFIELDS];
    hsize_t frames, ns;
    double *row;
    char xdmf[4096], xtmp[4200], base[4096];
};

int mimas_spacetime_open(mimas_spacetime **stp, const char *path, const mimas_axial *ax,
                         mimas_error *err)
{
    mimas_spacetime *st = calloc(1, sizeof *st);
    if (!st)
        return mimas_error_set(err, MIMAS_EIO, "out of memory");
    const mimas_axial_options *o = mimas_axial_opts(ax);
    st->ns = o->slices.n;
    st->row = malloc(st->ns * sizeof *st->row);
    int rc = st->row ? mimas_h5out_open(&st->h5, path, err)
                     : mimas_error_set(err, MIMAS_EIO, "out of memory");
    if (rc) {
        free(st->row);
        free(st);
        return rc;
    }
    size_t len = strlen(path);
    if (len > 3 && !strcmp(path + len - 3, ".h5"))
        snprintf(st->xdmf, sizeof st->xdmf, "%.*s.xdmf", (int)(len - 3), path);
    else
        snprintf(st->xdmf, sizeof st->xdmf, "%s.xdmf", path);
    snprintf(st->xtmp, sizeof st->xtmp, "%s.tmp%ld", st->xdmf, (long)getpid());
    const char *slash = strrchr(path, '/');
    snprintf(st->base, sizeof st->base, "%s", slash ? slash + 1 : path);
    st->group = h5out_group(st->h5, "/axial");
    /* slice centres and the geometry */
    for (hsize_t k = 0; k < st->ns; k++)
        st->row[k] = mimas_slice_centre(&o->slices, (size_t)k);
    int bad = st->group < 0 ||
              h5_write_doubles(st->group, "s", 1, &st->ns, st->row, "m",
                               "slice centre: axial coordinate along the tube axis") ||
              h5_attr_write_double(st->group, "slice_width", o->slices.w) ||
              h5_attr_write_double(st->group, "tube_radius", o->geom.radius);
    hsize_t zero[2] = {0, st->ns}, c1 = 256, c2[2] = {64, st->ns};
    st->step = h5_create_growing(st->group, "step", H5T_STD_I64LE, 1, 1, zero, &c1, NULL, 0);
    st->time = h5_create_growing(st->group, "time", H5T_IEEE_F64LE, 1, 1, zero, &c1, NULL, 0);
    bad |= st->step < 0 || st->time < 0 || h5_attr_write_str(st->time, "unit", "s");
    for (int f = 0; f < MIMAS_AX_NFIELDS; f++) {
        const mimas_axial_field_desc *d = mimas_axial_field(f);
        st->field[f] =
            h5_create_growing(st->group, d->name, H5T_IEEE_F64LE, 2, 1, zero, c2, NULL, 1);
        bad |= st->field[f] < 0 || h5_attr_write_str(st->field[f], "unit", d->unit) ||
               h5_attr_write_str(st->field[f], "definition", d->meaning);
    }
    if (bad) {
        mimas_spacetime_abort(st);
        return mimas_error_set(err, MIMAS_EIO, "%s: cannot create the space-time fields", path);
    }
    *stp = st;
    return MIMAS_OK;
}

int mimas_spacetime_append(mimas_spacetime *st, const mimas_axial *ax, int64_t step, double time,
                           mimas_error *err)
{
    hsize_t k = st->frames;
    int rc = h5_append_row(st->step, k, 0, NULL, H5T_NATIVE_INT64, &step) ||
             h5_append_row(st->time, k, 0, NULL, H5T_NATIVE_DOUBLE, &time);
    for (int f = 0; !rc && f < MIMAS_AX_NFIELDS; f++) {
        for (hsize_t s = 0; s < st->ns; s++)
            st->row[s] = mimas_axial_value(ax, (size_t)s, f);
        rc = h5_append_row(st->field[f], k, 1, &st->ns, H5T_NATIVE_DOUBLE, st->row);
    }
    if (rc)
        return mimas_error_set(err, MIMAS_EIO, "cannot write the space-time fields");
    st->frames++;
    return MIMAS_OK;
}

static int write_xdmf(const mimas_spacetime *st)
{
    FILE *fp = fopen(st->xtmp, "w");
    if (!fp)
        return -1;
    unsigned long long nf = st->frames, ns = st->ns;
    /* x = s (slices), y = time (frames): a rectilinear 2-d mesh */
    fprintf(fp, "<?xml version=\"1.0\" ?>\n<Xdmf Version=\"2.0\">\n <Domain>\n"
                "  <Grid Name=\"mimas axial profiles\" GridType=\"Uniform\">\n"
                "   <Topology TopologyType=\"2DRectMesh\" Dimensions=\"%llu %llu\"/>\n"
                "   <Geometry GeometryType=\"VXVY\">\n"
                "    <DataItem Dimensions=\"%llu\" NumberType=\"Float\" Precision=\"8\" "
                "Format=\"HDF\">%s:/axial/s</DataItem>\n"
                "    <DataItem Dimensions=\"%llu\" NumberType=\"Float\" Precision=\"8\" "
                "Format=\"HDF\">%s:/axial/time</DataItem>\n   </Geometry>\n",
            nf, ns, ns, st->base, nf, st->base);
    for (int f = 0; f < MIMAS_AX_NFIELDS; f++)
        fprintf(fp, "   <Attribute Name=\"%s\" AttributeType=\"Scalar\" Center=\"Node\">\n"
                    "    <DataItem Dimensions=\"%llu %llu\" NumberType=\"Float\" Precision=\"8\" "
                    "Format=\"HDF\">%s:/axial/%s</DataItem>\n   </Attribute>\n",
                mimas_axial_field(f)->name, nf, ns, st->base, mimas_axial_field(f)->name);
    fprintf(fp, "  </Grid>\n </Domain>\n</Xdmf>\n");
    return fclose(fp) != 0 ? -1 : 0;
}

static void close_datasets(mimas_spacetime *st)
{
    if (st->step > 0)
        H5Dclose(st->step);
    if (st->time > 0)
        H5Dclose(st->time);
    for (int f = 0; f < MIMAS_AX_NFIELDS; f++)
        if (st->field[f] > 0)
            H5Dclose(st->field[f]);
    if (st->group > 0)
        H5Gclose(st->group);
    st->step = st->time = st->group = -1;
    for (int f = 0; f < MIMAS_AX_NFIELDS; f++)
        st->field[f] = -1;
}

int mimas_spacetime_finish(mimas_spacetime *st, const char *provenance, mimas_error *err)
{
    close_datasets(st);
    int rc = write_xdmf(st) ? mimas_error_set(err, MIMAS_EIO, "%s: cannot write", st->xdmf)
                            : MIMAS_OK;
    mimas_h5out *h5 = st->h5;
    st->h5 = NULL;
    if (!rc)
        rc = mimas_h5out_commit(h5, provenance, err);
    else
        mimas_h5out_abort(h5);
    if (!rc && rename(st->xtmp, st->xdmf) != 0)
        rc = mimas_error_set(err, MIMAS_EIO, "%s: cannot write", st->xdmf);
    mimas_spacetime_abort(st);
    return rc;
}

void mimas_spacetime_abort(mimas_spacetime *st)
{
    if (!st)
        return;
    close_datasets(st);
    mimas_h5out_abort(st->h5);
    remove(st->xtmp);
    free(st->row);
    free(st);
}
