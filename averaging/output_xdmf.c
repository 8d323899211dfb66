/* XDMF sidecars of field files.  The fields are cell values, so they are
 * cell-centred attributes of the mesh of cell corners (the rendered domain
 * is the grid's).  Cartesian grids: vectors and tensors are joined from
 * their component datasets.  Cylindrical grids: the mesh is the grid's cells
 * mapped to Cartesian space (cells with straight edges); without phi cells
 * it is the r-z half plane at phi = 0 (ParaView's Rotational Extrusion turns
 * it into the ring); vectors and tensors are their Cartesian components at
 * the cell centres, stored for the purpose under /xdmf. */
#include <config.h>

#include "output_xdmf.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fields.h"
#include "h5util.h"
#include "xdmf.h"

static int ends_with(const char *s, const char *suffix)
{
    size_t n = strlen(s), m = strlen(suffix);
    return n > m && !strcmp(s + n - m, suffix);
}

size_t fields_groups(int cyl, const unsigned char *want, fields_group *groups, size_t max)
{
    static const char *const vec[2][3] = {{"_x", "_y", "_z"}, {"_r", "_phi", "_z"}};
    static const char *const ten[2][6] = {{"_xx", "_yy", "_zz", "_xy", "_xz", "_yz"},
                                          {"_rr", "_phiphi", "_zz", "_rphi", "_rz", "_phiz"}};
    size_t nf = mimas_fields_count(), ng = 0;
    for (size_t k = 0; k < nf && ng < max; k++) {
        for (int kind = 0; kind < 2; kind++) {
            const char *const *suf = kind ? ten[cyl] : vec[cyl];
            int n = kind ? 6 : 3;
            const char *first = mimas_field_name(k, cyl);
            if (!first || !ends_with(first, suf[0]) || k + (size_t)n > nf)
                continue;
            size_t base = strlen(first) - strlen(suf[0]);
            int ok = 1;
            for (int c = 0; c < n && ok; c++) {
                const char *name = mimas_field_name(k + (size_t)c, cyl);
                ok = name && want[k + (size_t)c] && strlen(name) == base + strlen(suf[c]) &&
                     !strncmp(name, first, base) && !strcmp(name + base, suf[c]);
            }
            if (!ok || base >= sizeof groups[ng].name)
                continue;
            snprintf(groups[ng].name, sizeof groups[ng].name, "%.*s", (int)base, first);
            groups[ng].first = k;
            groups[ng].ncomp = n;
            ng++;
            break;
        }
    }
    return ng;
}

/* Corners along each direction: the cell bounds; cylindrical grids without
 * phi cells have the single phi = 0. */
static int corner_counts(const mimas_grid *g, int none, int m[3])
{
    int flat_phi = g->kind == MIMAS_GRID_CYLINDRICAL && !none && !g->gridded[1];
    for (int d = 0; d < 3; d++)
        m[d] = (none ? 1 : g->n[d]) + 1;
    if (flat_phi)
        m[1] = 1;
    return flat_phi;
}

static void to_cartesian(const mimas_grid *g, const double q[3], double p[3])
{
    double a0 = q[0] * cos(q[1]), a1 = q[0] * sin(q[1]);
    for (int d = 0; d < 3; d++)
        p[d] = g->origin[d] + a0 * g->ex[d] + a1 * g->ey[d] + q[2] * g->ez[d];
}

int fields_write_corners(hid_t gg, const mimas_grid *g, int none)
{
    int m[3];
    int flat_phi = corner_counts(g, none, m);
    size_t n = (size_t)m[0] * (size_t)m[1] * (size_t)m[2];
    double *xyz = malloc(n * 3 * sizeof *xyz);
    if (!xyz)
        return -1;
    int cyl = g->kind == MIMAS_GRID_CYLINDRICAL && !none;
    for (size_t c = 0; c < n; c++) {
        int idx[3] = {(int)(c % (size_t)m[0]), (int)(c / (size_t)m[0] % (size_t)m[1]),
                      (int)(c / ((size_t)m[0] * (size_t)m[1]))};
        double q[3];
        for (int d = 0; d < 3; d++) {
            int cells = m[d] - 1;
            q[d] = cells == 0 ? 0.0
                   : idx[d] == cells ? g->hi[d]
                                     : g->lo[d] + (g->hi[d] - g->lo[d]) * idx[d] / cells;
        }
        if (flat_phi)
            q[1] = 0.0;
        if (cyl)
            to_cartesian(g, q, &xyz[3 * c]);
        else
            memcpy(&xyz[3 * c], q, sizeof q);
    }
    hsize_t dims[4] = {(hsize_t)m[2], (hsize_t)m[1], (hsize_t)m[0], 3};
    int rc = h5_write_doubles(gg, "corners", 4, dims, xyz, "m",
                              "cell corners, Cartesian (the XDMF mesh)");
    free(xyz);
    return rc;
}

int fields_xdmf_stored(const mimas_grid *g, int none)
{
    return none || mimas_grid_cells(g) == 1 || g->kind == MIMAS_GRID_CYLINDRICAL;
}

int fields_write_cartesian(hid_t file, const mimas_grid *g, const fields_group *groups,
                           size_t ngroups, const double *mean, size_t nf)
{
    size_t cells = mimas_grid_cells(g);
    int cyl = g->kind == MIMAS_GRID_CYLINDRICAL;
    hid_t gx = H5Gcreate2(file, "/xdmf", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    double *out = malloc(cells * 6 * sizeof *out);
    int rc = gx < 0 || !out;
    for (size_t k = 0; !rc && k < ngroups; k++) {
        const fields_group *gr = &groups[k];
        for (size_t c = 0; c < cells; c++) {
            double q[3];
            mimas_grid_cell_centre(g, c, q);
            double phi = g->gridded[1] ? q[1] : 0.0;
            /* columns of R: e_r, e_phi, e_z in Cartesian components (the
             * identity on Cartesian grids) */
            double R[3][3];
            for (int d = 0; d < 3; d++) {
                R[d][0] = cyl ? cos(phi) * g->ex[d] + sin(phi) * g->ey[d] : d == 0;
                R[d][1] = cyl ? -sin(phi) * g->ex[d] + cos(phi) * g->ey[d] : d == 1;
                R[d][2] = cyl ? g->ez[d] : d == 2;
            }
            const double *v = &mean[c * nf + gr->first];
            if (gr->ncomp == 3) {
                for (int a = 0; a < 3; a++)
                    out[3 * c + (size_t)a] = R[a][0] * v[0] + R[a][1] * v[1] + R[a][2] * v[2];
                continue;
            }
            /* xx yy zz xy xz yz -> T, then R T R^T in xx xy xz yy yz zz */
            double T[3][3] = {{v[0], v[3], v[4]}, {v[3], v[1], v[5]}, {v[4], v[5], v[2]}}, C[3][3];
            for (int a = 0; a < 3; a++)
                for (int b = 0; b < 3; b++) {
                    C[a][b] = 0;
                    for (int i = 0; i < 3; i++)
                        for (int j = 0; j < 3; j++)
                            C[a][b] += R[a][i] * T[i][j] * R[b][j];
                }
            double six[6] = {C[0][0], C[0][1], C[0][2], C[1][1], C[1][2], C[2][2]};
            memcpy(&out[6 * c], six, sizeof six);
        }
        hsize_t dims[4] = {(hsize_t)g->n[2], (hsize_t)g->n[1], (hsize_t)g->n[0],
                           (hsize_t)gr->ncomp};
        rc |= h5_write_doubles(gx, gr->name, 4, dims, out, mimas_field(gr->first)->unit,
                               gr->ncomp == 3 ? "Cartesian components x y z (for XDMF)"
                                              : "Cartesian components xx xy xz yy yz zz "
                                                "(for XDMF)");
    }
    free(out);
    if (gx >= 0)
        H5Gclose(gx);
    return rc;
}

/* The shape XDMF is told: (n2, n1, n0) cells on (n2 + 1, n1 + 1, n0 + 1)
 * corners, or without the phi direction for cylindrical grids without phi
 * cells (a 2-d mesh: ParaView reads no cell data on a 3-d mesh one corner
 * thick). */
typedef struct mesh_shape {
    int rank;
    unsigned long long cells[3], corners[3];
} mesh_shape;

static void shape_of(const mimas_grid *g, int none, mesh_shape *ms)
{
    int m[3];
    int flat = corner_counts(g, none, m);
    ms->rank = 0;
    for (int d = 2; d >= 0; d--) {
        if (flat && d == 1)
            continue;
        ms->cells[ms->rank] = (unsigned long long)(m[d] - 1);
        ms->corners[ms->rank] = (unsigned long long)m[d];
        ms->rank++;
    }
}

/* The mesh of cell corners and its geometry (/grid/corners, read as
 * corners x 3 whatever its stored rank). */
static void write_mesh(xdmf_writer *x, const mesh_shape *ms, int indent)
{
    fprintf(x->fp, "%*s<Topology TopologyType=\"%s\" Dimensions=\"", indent, "",
            ms->rank == 3 ? "3DSMesh" : "2DSMesh");
    for (int d = 0; d < ms->rank; d++)
        fprintf(x->fp, "%s%llu", d ? " " : "", ms->corners[d]);
    fprintf(x->fp, "\"/>\n%*s<Geometry GeometryType=\"XYZ\">\n", indent, "");
    unsigned long long dims[4];
    memcpy(dims, ms->corners, sizeof ms->corners);
    dims[ms->rank] = 3;
    xdmf_item it;
    xdmf_item_whole(&it, "/grid/corners", 1, 8, ms->rank + 1, dims);
    xdmf_write_item(x, indent + 1, &it);
    fprintf(x->fp, "%*s</Geometry>\n", indent, "");
}

/* An item of the field file seen in the mesh's shape: /fields/NAME/WHAT
 * (frame < 0), or frame k of /frames/NAME; ncomp > 1 for the stored vector
 * and tensor datasets (/xdmf/NAME, /tensors/NAME: ncomp values a cell). */
static void field_item(xdmf_item *it, const char *dataset, const mimas_grid *g, int none,
                       const mesh_shape *ms, long frame, size_t frames, int ncomp)
{
    unsigned long long dims[5];
    int rank = 0;
    if (frame >= 0)
        dims[rank++] = frames;
    for (int d = 2; d >= 0; d--)
        dims[rank++] = none ? 1 : (unsigned long long)g->n[d];
    if (ncomp == 9)
        dims[rank++] = 3, dims[rank++] = 3;
    else if (ncomp > 1)
        dims[rank++] = (unsigned long long)ncomp;
    xdmf_item_whole(it, dataset, 1, 8, rank, dims);
    if (frame >= 0)
        xdmf_item_frame(it, (unsigned long long)frame, 0);
    unsigned long long out[4];
    memcpy(out, ms->cells, sizeof ms->cells);
    out[ms->rank] = (unsigned long long)ncomp;
    xdmf_item_shape(it, ms->rank + (ncomp > 1), out);
}

/* The attributes of one grid: the time average (frame < 0) or frame k of /frames. */
static void write_attributes(xdmf_writer *x, const mimas_grid *g, int none, const mesh_shape *ms,
                             const unsigned char *want, long frame, size_t frames,
                             const char *full_tensor)
{
    int cyl = g->kind == MIMAS_GRID_CYLINDRICAL && !none;
    size_t nf = mimas_fields_count();
    char path[6][160];   /* the datasets of the joined components */
    char one[160];
    xdmf_item it;
    static const char *const what[3] = {"mean", "std", "sem"};
    for (size_t k = 0; k < nf; k++) {
        const char *name = mimas_field_name(k, cyl);
        if (!name || !want[k])
            continue;
        for (int s = 0; s < (frame < 0 ? 3 : 1); s++) {
            if (frame < 0)
                snprintf(one, sizeof one, "/fields/%s/%s", name, what[s]);
            else
                snprintf(one, sizeof one, "/frames/%s", name);
            field_item(&it, one, g, none, ms, frame, frames, 1);
            char label[96];
            snprintf(label, sizeof label, "%s%s%s", name, s ? "_" : "", s ? what[s] : "");
            xdmf_write_attribute(x, 4, label, "Scalar", "Cell", &it);
        }
    }
    fields_group groups[16];
    size_t ng = fields_groups(cyl, want, groups, 16);
    int stored = fields_xdmf_stored(g, none);
    for (size_t k = 0; k < ng; k++) {
        const char *type = groups[k].ncomp == 3 ? "Vector" : "Tensor6";
        if (stored) {
            if (frame >= 0)
                continue; /* per frame: the components only */
            snprintf(one, sizeof one, "/xdmf/%.31s", groups[k].name);
            field_item(&it, one, g, none, ms, -1, 0, groups[k].ncomp);
            xdmf_write_attribute(x, 4, groups[k].name, type, "Cell", &it);
            continue;
        }
        /* JOIN in XDMF's order: x y z, or xx xy xz yy yz zz */
        static const int order6[6] = {0, 3, 4, 1, 5, 2};
        xdmf_item items[6];
        for (int c = 0; c < groups[k].ncomp; c++) {
            size_t col = groups[k].first + (size_t)(groups[k].ncomp == 6 ? order6[c] : c);
            if (frame < 0)
                snprintf(path[c], sizeof path[c], "/fields/%s/mean", mimas_field_name(col, 0));
            else
                snprintf(path[c], sizeof path[c], "/frames/%s", mimas_field_name(col, 0));
            field_item(&items[c], path[c], g, none, ms, frame, frames, 1);
        }
        xdmf_write_joined(x, 4, groups[k].name, type, "Cell", items, groups[k].ncomp);
    }
    if (full_tensor && !cyl && frame < 0) { /* in (x, y, z) components */
        snprintf(one, sizeof one, "/tensors/%s", full_tensor);
        field_item(&it, one, g, none, ms, -1, 0, 9);
        char label[64];
        snprintf(label, sizeof label, "%s_full", full_tensor);
        xdmf_write_attribute(x, 4, label, "Tensor", "Cell", &it);
    }
}

int fields_write_xdmf(const char *h5path, const mimas_grid *g, int none,
                      const unsigned char *want, size_t frames, const double *times,
                      int has_full_tensor, const char *full_tensor, mimas_error *err)
{
    char path[4200];
    xdmf_writer x;
    mimas_xdmf_path(h5path, NULL, path, sizeof path);
    int rc = xdmf_begin(&x, path, h5path, err);
    if (rc)
        return rc;
    mesh_shape ms;
    shape_of(g, none, &ms);
    fputs("  <Grid Name=\"mimas fields\" GridType=\"Uniform\">\n", x.fp);
    write_mesh(&x, &ms, 3);
    write_attributes(&x, g, none, &ms, want, -1, 0, has_full_tensor ? full_tensor : NULL);
    fputs("  </Grid>\n", x.fp);
    rc = xdmf_end(&x, 1, err);
    if (rc || frames == 0)
        return rc;
    char fpath[4200];
    mimas_xdmf_path(h5path, "-frames", fpath, sizeof fpath);
    rc = xdmf_begin(&x, fpath, h5path, err);
    if (rc) {
        remove(path);
        return rc;
    }
    fputs("  <Grid Name=\"mimas fields per frame\" GridType=\"Collection\" "
          "CollectionType=\"Temporal\">\n", x.fp);
    for (size_t k = 0; k < frames; k++) {
        fprintf(x.fp, "   <Grid Name=\"frame %zu\" GridType=\"Uniform\">\n"
                      "    <Time Value=\"%.17g\"/>\n", k, isfinite(times[k]) ? times[k] : (double)k);
        write_mesh(&x, &ms, 4);
        write_attributes(&x, g, none, &ms, want, (long)k, frames, NULL);
        fputs("   </Grid>\n", x.fp);
    }
    fputs("  </Grid>\n", x.fp);
    rc = xdmf_end(&x, 1, err);
    if (rc)
        remove(path);
    return rc;
}
