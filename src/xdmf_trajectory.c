/* The XDMF sidecar of a native trajectory: every committed frame as a grid
 * of unconnected points (Polyvertex) in a temporal collection, the
 * positions as geometry and each per-particle element as an attribute,
 * all as hyperslabs of the frame's first n slots (varying particle counts
 * need nothing more). */
#include <config.h>

#include "xdmf.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "native.h"

/* AttributeType of a per-particle element of k components (NULL: none). */
static const char *attribute_type(int ncomp)
{
    switch (ncomp) {
    case 1: return "Scalar";
    case 3: return "Vector";
    case 6: return "Tensor6";
    case 9: return "Tensor";
    }
    return NULL;
}

static int write_frames(xdmf_writer *x, mimas_native *r, mimas_error *err)
{
    size_t ncols = mimas_native_particle_columns(r);
    mimas_native_column *cols = calloc(ncols ? ncols : 1, sizeof *cols);
    char (*paths)[96] = calloc(ncols ? ncols : 1, sizeof *paths);
    if (!cols || !paths) {
        free(cols);
        free(paths);
        return mimas_error_set(err, MIMAS_EIO, "out of memory");
    }
    long pos = -1;
    for (size_t c = 0; c < ncols; c++) {
        mimas_native_particle_column(r, c, &cols[c]);
        snprintf(paths[c], sizeof paths[c], "/particles/all/%s/value", cols[c].name);
        if (!strcmp(cols[c].name, "position"))
            pos = (long)c;
    }
    fputs("  <Grid Name=\"particles\" GridType=\"Collection\" CollectionType=\"Temporal\">\n",
          x->fp);
    int rc = MIMAS_OK;
    size_t frames = mimas_native_frames(r);
    for (size_t k = 0; !rc && pos >= 0 && k < frames; k++) {
        mimas_frame_meta m;
        rc = mimas_native_frame_meta(r, k, &m, err);
        if (rc || m.n_particles == 0)
            continue; /* an empty frame has nothing to show */
        unsigned long long n = m.n_particles;
        fprintf(x->fp, "   <Grid Name=\"step %lld\" GridType=\"Uniform\">\n", (long long)m.step);
        /* the time, or the step where the input had no time */
        fprintf(x->fp, "    <Time Value=\"%.17g\"/>\n",
                isfinite(m.time) ? m.time : (double)m.step);
        fprintf(x->fp, "    <Topology TopologyType=\"Polyvertex\" NumberOfElements=\"%llu\" "
                       "NodesPerElement=\"1\"/>\n    <Geometry GeometryType=\"XYZ\">\n", n);
        xdmf_item it;
        xdmf_item_whole(&it, paths[pos], cols[pos].is_float, cols[pos].precision,
                        cols[pos].rank, cols[pos].dims);
        xdmf_item_frame(&it, k, n);
        xdmf_write_item(x, 5, &it);
        fputs("    </Geometry>\n", x->fp);
        for (size_t c = 0; c < ncols; c++) {
            const char *type = attribute_type(cols[c].ncomp);
            if ((long)c == pos || !type)
                continue;
            xdmf_item_whole(&it, paths[c], cols[c].is_float, cols[c].precision, cols[c].rank,
                            cols[c].dims);
            xdmf_item_frame(&it, k, n);
            /* species is what visualisation tools call the particle type */
            const char *name = !strcmp(cols[c].name, "species") ? "type" : cols[c].name;
            xdmf_write_attribute(x, 4, name, type, "Node", &it);
        }
        fputs("   </Grid>\n", x->fp);
    }
    fputs("  </Grid>\n", x->fp);
    free(cols);
    free(paths);
    return rc;
}

int mimas_xdmf_trajectory(const char *h5path, const char *xdmf_path, mimas_error *err)
{
    mimas_native *r;
    int rc = mimas_native_open(&r, h5path, err);
    if (rc)
        return rc;
    xdmf_writer x;
    rc = xdmf_begin(&x, xdmf_path, h5path, err);
    if (!rc)
        rc = write_frames(&x, r, err);
    int closed = xdmf_end(&x, rc == MIMAS_OK, err);
    mimas_native_close(r);
    return rc ? rc : closed;
}
