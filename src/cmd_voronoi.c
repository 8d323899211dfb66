/* mimas voronoi: per-particle Voronoi cells (voro++), their volumes and the
 * local solid fraction V_p/V_cell (PHYSICS 6, 002 Sec. 2.2). */
#include <config.h>

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "commands.h"
#include "reader.h"
#include "voro_cells.h"

static const cli_option options[] = {
    {"radical", 0, NULL, "radical (Laguerre) tessellation, for polydisperse packings"},
    {"exclude-types", 0, "L", "particles of these types take part but are not reported "
                              "(e.g. glued wall particles)"},
    {"tsv", 0, "FILE", "write the table to FILE (default: standard output)"},
};

typedef struct voronoi_args {
    const cli_command *cmd;
    int radical;
    int32_t types[64];
    size_t ntypes;
    const char *tsv;
} voronoi_args;

static int on_option(void *ctx, size_t opt, const char *arg)
{
    voronoi_args *a = ctx;
    if (opt == 0) {
        a->radical = 1;
        return 0;
    }
    if (opt == 2) {
        a->tsv = arg;
        return 0;
    }
    return cli_parse_types(a->cmd, "exclude-types", arg, a->types, 64, &a->ntypes);
}

static int reported(const voronoi_args *a, const mimas_particles *p, size_t k)
{
    if (!(p->present & MIMAS_P_TYPE))
        return 1;
    for (size_t m = 0; m < a->ntypes; m++)
        if (p->type[k] == a->types[m])
            return 0;
    return 1;
}

/* One frame's cells; rows "step id x y z volume nu faces". */
static int frame_cells(const voronoi_args *a, const mimas_frame *f, FILE *out, double **vol,
                       int **faces, size_t *cap, mimas_error *err)
{
    const mimas_particles *p = &f->particles;
    int rc = mimas_table_require(p, &mimas_particles_desc, MIMAS_P_RADIUS, err);
    if (rc)
        return rc;
    if (p->n > *cap) {
        double *v = realloc(*vol, p->n * sizeof *v);
        int *fc = realloc(*faces, p->n * sizeof *fc);
        if (v)
            *vol = v;
        if (fc)
            *faces = fc;
        if (!v || !fc)
            return mimas_error_set(err, MIMAS_EIO, "out of memory");
        *cap = p->n;
    }
    rc = mimas_voro_cells(&f->box, p->n, (const double (*)[3])p->pos,
                          a->radical ? p->radius : NULL, *vol, *faces, err);
    if (rc)
        return rc;
    for (size_t k = 0; k < p->n; k++) {
        if (!reported(a, p, k))
            continue;
        double vp = 4.0 / 3.0 * M_PI * pow(p->radius[k], 3);
        fprintf(out, "%lld\t%lld\t%.17g\t%.17g\t%.17g\t%.17g\t", (long long)f->step,
                (long long)p->id[k], p->pos[k][0], p->pos[k][1], p->pos[k][2], (*vol)[k]);
        /* an empty radical cell (a small sphere inside a big one's) has no fraction */
        if ((*vol)[k] > 0)
            fprintf(out, "%.17g", vp / (*vol)[k]);
        else
            fputs("nan", out);
        fprintf(out, "\t%d\n", (*faces)[k]);
    }
    return ferror(out) ? mimas_error_set(err, MIMAS_EIO, "cannot write the table") : MIMAS_OK;
}

static int run(const cli_command *cmd, int argc, char **argv)
{
    voronoi_args a = {0};
    a.cmd = cmd;
    cli_inputs in = {0};
    int first;
    int rc = cli_parse(cmd, argc, argv, on_option, &a, &in, &first);
    mimas_reader *r = NULL;
    if (!rc)
        rc = cli_open_inputs(cmd, &in, argc, argv, first, &r);
    if (rc) {
        cli_inputs_free(&in);
        return rc < 0 ? 0 : rc;
    }
    mimas_error err;
    cli_output table;
    int status = cli_output_open(&table, a.tsv, &err);
    FILE *out = table.fp;
    if (out)
        fputs("step\tid\tx\ty\tz\tvolume\tnu\tfaces\n", out);
    mimas_frame f;
    mimas_frame_init(&f);
    double *vol = NULL;
    int *faces = NULL;
    size_t cap = 0;
    cli_progress prog;
    cli_progress_start(&prog, &in);
    size_t frames = 0;
    while (!status && (status = mimas_reader_next(r, &f, &err)) == MIMAS_OK) {
        status = frame_cells(&a, &f, out, &vol, &faces, &cap, &err);
        if (status && status != MIMAS_EIO)
            mimas_error_prefix(&err, "%s: step %lld", argv[first], (long long)f.step);
        cli_progress_frame(&prog, cmd, ++frames, (long long)f.step, f.time);
    }
    cli_progress_done(&prog);
    free(vol);
    free(faces);
    mimas_frame_free(&f);
    mimas_reader_close(r);
    cli_inputs_free(&in);
    int closed = cli_output_close(&table, status == MIMAS_END, &err);
    if (closed)
        status = closed;
    if (status != MIMAS_END)
        return cli_fail(cmd, mimas_exit_status(status), "%s", err.msg);
    return 0;
}

const cli_command cmd_voronoi = {
    "voronoi",
    "per-particle Voronoi cells: volume, local solid fraction, faces",
    "[options] INPUT...",
    "Tessellates every frame with voro++ (plain, or radical with --radical) in its\n"
    "box (periodic along the periodic axes; a tilted box must be periodic along\n"
    "all three) and writes one row per particle: step, id, position, cell volume,\n"
    "local solid fraction V_p/V_cell and number of faces.  Container walls other\n"
    "than the box, the free-surface cut-off and per-particle stresses are not yet\n"
    "supported.",
    options,
    sizeof options / sizeof options[0],
    1,
    run,
};
