/* slab_profile: a complete libmimas program (docs/api.md).
 *
 * Reads any input mimas reads (native HDF5 files, LAMMPS/LIGGGHTS dumps,
 * MercuryDPM output), averages every frame over N slabs along z with exact
 * Heaviside-bin weights, and prints the time-averaged solid fraction and
 * vertical velocity of each slab with their standard errors, as TSV.  With
 * -o it also copies the frames into a native mimas file.
 *
 *   slab_profile [-n N] [-o COPY.h5] INPUT...
 *
 * Build it against an installed mimas:
 *
 *   cc -std=c17 slab_profile.c $(pkg-config --cflags --libs mimas) -lm -o slab_profile
 *
 * make check builds this file against a `make install DESTDIR=...` of the
 * tree and runs it (tests/cli/api.test), so it stays in step with the
 * library. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <mimas.h>

/* The columns printed: looked up by name in the field table, which maps the
 * columns of mimas_average_fields() to names, units and definitions. */
static const char *const wanted[] = {"nu", "v_z"};
#define NWANTED (sizeof wanted / sizeof wanted[0])

static int fail(const mimas_error *err)
{
    fprintf(stderr, "slab_profile: %s\n", err->msg);
    return mimas_exit_status(err->code);
}

/* Prints one row per slab: z, then each wanted field and its standard error
 * (sd over frames / sqrt of the frames in which it was defined). */
static int print_profile(const mimas_average *avg, mimas_error *err)
{
    const mimas_grid *grid = mimas_average_grid(avg);
    size_t cells = mimas_grid_cells(grid), nf = mimas_fields_count();
    size_t col[NWANTED];
    for (size_t w = 0; w < NWANTED; w++)
        if (!mimas_field_find(wanted[w], 0, &col[w]))
            return mimas_error_set(err, MIMAS_EMISSING, "no field '%s'", wanted[w]);

    double *mean = malloc(cells * nf * sizeof *mean), *sd = malloc(cells * nf * sizeof *sd),
           *count = malloc(cells * nf * sizeof *count);
    if (!mean || !sd || !count || mimas_average_fields(avg, mean, sd, count) < 0) {
        free(mean), free(sd), free(count);
        return mimas_error_set(err, MIMAS_EIO, "out of memory");
    }

    printf("# %zu frames; units: z m", mimas_average_frames(avg));
    for (size_t w = 0; w < NWANTED; w++)
        printf(", %s %s", wanted[w], mimas_field(col[w])->unit);
    printf("\nz");
    for (size_t w = 0; w < NWANTED; w++)
        printf("\t%s\t%s_sem", wanted[w], wanted[w]);
    printf("\n");
    for (size_t c = 0; c < cells; c++) {
        double centre[3];
        mimas_grid_cell_centre(grid, c, centre);
        printf("%.17g", centre[2]);
        for (size_t w = 0; w < NWANTED; w++) {
            size_t k = c * nf + col[w];
            double sem = count[k] >= 2 ? sd[k] / sqrt(count[k]) : NAN;
            printf("\t%.17g\t%.17g", mean[k], sem);
        }
        printf("\n");
    }
    free(mean), free(sd), free(count);
    return MIMAS_OK;
}

int main(int argc, char **argv)
{
    int nslabs = 10;
    const char *copy = NULL;
    int a = 1;
    for (; a < argc && argv[a][0] == '-'; a += 2) {
        if (a + 1 >= argc)
            break;
        if (!strcmp(argv[a], "-n"))
            nslabs = atoi(argv[a + 1]);
        else if (!strcmp(argv[a], "-o"))
            copy = argv[a + 1];
        else
            break;
    }
    if (a >= argc || argv[a][0] == '-' || nslabs < 1) {
        fprintf(stderr, "usage: slab_profile [-n N] [-o COPY.h5] INPUT...\n");
        return 1;
    }

    mimas_error err;
    mimas_error_clear(&err);

    /* Reader: open all inputs (format detected from the content). */
    mimas_reader_options ropt;
    mimas_reader_options_default(&ropt);
    mimas_reader *reader = NULL;
    if (mimas_reader_open(&reader, (const char *const *)argv + a, (size_t)(argc - a), &ropt,
                          &err))
        return fail(&err);

    /* Frame: one, reused for every snapshot (memory does not grow with the
     * number of frames). */
    mimas_frame frame;
    mimas_frame_init(&frame);

    mimas_writer *writer = NULL;
    mimas_average *avg = NULL;
    int rc;
    while ((rc = mimas_reader_next(reader, &frame, &err)) == MIMAS_OK) {
        if (!avg) {
            /* Average: N slabs between the box's z bounds of the first frame;
             * x and y are not gridded (they span the box). */
            mimas_average_options aopt;
            memset(&aopt, 0, sizeof aopt);
            char spec[128];
            snprintf(spec, sizeof spec, "z=%.17g:%.17g:%d", frame.box.lo[2], frame.box.hi[2],
                     nslabs);
            aopt.spread = 1; /* keep the spread over frames: standard errors */
            if (mimas_grid_parse(&aopt.grid, spec, NULL, &err) ||
                mimas_weight_parse(&aopt.weight, "bins", &err) ||
                mimas_average_create(&avg, &aopt, &err))
                break;
        }
        if (copy && !writer) {
            /* Writer: atomic, so COPY.h5 appears only when it is complete. */
            mimas_writer_options wopt;
            mimas_writer_options_default(&wopt);
            wopt.atomic = 1;
            wopt.provenance = "docs/examples/slab_profile.c";
            if (mimas_writer_open(&writer, copy, &wopt, &err))
                break;
        }
        if (mimas_average_add(avg, &frame, &err) ||
            (writer && mimas_writer_append(writer, &frame, &err)))
            break;
    }
    if (rc == MIMAS_END && !avg)
        rc = mimas_error_set(&err, MIMAS_EDATA, "%s: no frames", argv[a]);
    else if (rc == MIMAS_END)
        rc = MIMAS_OK;
    else
        rc = err.code ? err.code : rc;

    if (rc == MIMAS_OK)
        rc = print_profile(avg, &err);
    if (writer) {
        if (rc == MIMAS_OK)
            rc = mimas_writer_close(writer, &err);
        else
            mimas_writer_abort(writer); /* no partial copy is left behind */
    }
    mimas_average_free(avg);
    mimas_frame_free(&frame);
    mimas_reader_close(reader);
    return rc == MIMAS_OK ? 0 : fail(&err);
}
