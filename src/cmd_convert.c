/* mimas convert: any input into the native format, or into LAMMPS/LIGGGHTS
 * text dumps. */
#include <config.h>

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "commands.h"
#include "lammps_write.h"
#include "native.h"
#include "reader.h"

static const cli_option options[] = {
    {"output", 'o', "OUT", "the file to write (required): OUT.h5 (native), or OUT.dump / "
                         "OUT.dump.gz with --to lammps"},
    {"deflate", 0, "LEVEL", "gzip level 0-9 of particle and contact data (default 1; 0 is "
                            "fastest)"},
    {"to", 0, "FORMAT", "native (default), or lammps: a dump custom file of the particles and "
                        "dump local files of the contacts (OUT.pairs.dump) and wall contacts "
                        "(OUT.walls.dump); the default for names ending in .dump or .dump.gz"},
};

enum { O_OUTPUT, O_DEFLATE, O_TO };

typedef struct convert_args {
    const char *output, *to;
    long deflate;
    const cli_command *cmd;
} convert_args;

static int on_option(void *ctx, size_t opt, const char *arg)
{
    convert_args *a = ctx;
    if (opt == O_OUTPUT)
        a->output = arg;
    else if (opt == O_TO && strcmp(arg, "native") != 0 && strcmp(arg, "lammps") != 0)
        return cli_fail(a->cmd, 1, "--to is native or lammps, not '%s'", arg);
    else if (opt == O_TO)
        a->to = arg;
    else if (cli_parse_long(arg, &a->deflate) || a->deflate < 0 || a->deflate > 9)
        return cli_fail(a->cmd, 1, "--deflate needs a level from 0 to 9, not '%s'", arg);
    return 0;
}

static int ends_with(const char *s, const char *suffix)
{
    size_t n = strlen(s), m = strlen(suffix);
    return n >= m && !strcmp(s + n - m, suffix);
}

/* The file being written: the native writer or the dump writer behind one
 * set of calls. */
typedef struct sink {
    void *w;
    int (*append)(void *w, const mimas_frame *f, mimas_error *err);
    size_t (*frames)(const void *w);
    int (*close)(void *w, mimas_error *err);   /* (the dumps: close_dump) */
    void (*abort)(void *w);
    int local[2];   /* the dumps wrote contact and wall-contact files */
} sink;

static int native_append(void *w, const mimas_frame *f, mimas_error *err)
{
    return mimas_writer_append(w, f, err);
}
static size_t native_frames(const void *w)
{
    return mimas_writer_frames(w);
}
static int native_close(void *w, mimas_error *err)
{
    return mimas_writer_close(w, err);
}
static void native_abort(void *w)
{
    mimas_writer_abort(w);
}
static int dump_append(void *w, const mimas_frame *f, mimas_error *err)
{
    return mimas_dump_append(w, f, err);
}
static size_t dump_frames(const void *w)
{
    return mimas_dump_frames(w);
}
static void dump_abort(void *w)
{
    mimas_dump_abort(w);
}

/* Every frame of r into the sink, which is closed (or aborted on failure). */
static int convert_frames(const cli_command *cmd, const cli_inputs *in, mimas_reader *r,
                          sink *out, int (*close)(sink *, mimas_error *), const char *input,
                          mimas_error *err)
{
    mimas_frame f;
    mimas_frame_init(&f);
    int rc;
    cli_progress prog;
    cli_progress_start(&prog, in);
    cli_progress_total(&prog, r);
    while ((rc = mimas_reader_next(r, &f, err)) == MIMAS_OK) {
        rc = out->append(out->w, &f, err);
        if (rc)
            break;
        cli_progress_frame(&prog, cmd, out->frames(out->w), (long long)f.step, f.time);
    }
    cli_progress_done(&prog);
    mimas_frame_free(&f);
    if (rc == MIMAS_END && out->frames(out->w) == 0)
        rc = mimas_error_set(err, MIMAS_EDATA, "%s: no frames to convert", input);
    if (rc == MIMAS_END)
        return close(out, err);
    out->abort(out->w);
    return rc;
}

static int close_native(sink *s, mimas_error *err)
{
    return s->close(s->w, err);
}

static int close_dump(sink *s, mimas_error *err)
{
    return mimas_dump_close(s->w, s->local, err);
}

static int run(const cli_command *cmd, int argc, char **argv)
{
    convert_args a = {NULL, NULL, 1, cmd};
    cli_inputs in = {0};
    int first;
    int rc = cli_parse(cmd, argc, argv, on_option, &a, &in, &first);
    if (!rc && !a.output)
        rc = cli_fail(cmd, 1, "no output file: give -o OUT.h5");
    if (!rc)
        rc = cli_refuse_input_as_output(cmd, a.output, &in, argv + first, argc - first);
    mimas_reader *r = NULL;
    if (!rc)
        rc = cli_open_inputs(cmd, &in, argc, argv, first, &r);
    if (rc) {
        cli_inputs_free(&in);
        return rc < 0 ? 0 : rc;
    }
    int lammps = a.to ? !strcmp(a.to, "lammps")
                      : ends_with(a.output, ".dump") || ends_with(a.output, ".dump.gz");
    mimas_error err;
    char *provenance = cli_command_line(argc, argv);
    sink out = {NULL, NULL, NULL, NULL, NULL, {0, 0}};
    if (lammps) {
        mimas_dump_writer *dw = NULL;
        rc = mimas_dump_open(&dw, a.output, &err);
        out = (sink){dw, dump_append, dump_frames, NULL, dump_abort, {0, 0}};
    } else {
        mimas_writer_options o;
        mimas_writer_options_default(&o);
        o.deflate = (int)a.deflate;
        o.atomic = 1; /* no partial output: the file appears when it is complete */
        o.xdmf = 1;   /* and its sidecar for ParaView */
        o.provenance = provenance;
        mimas_writer *nw = NULL;
        rc = mimas_writer_open(&nw, a.output, &o, &err);
        if (!rc && (rc = mimas_writer_parameters(nw, "scenario", mimas_reader_parameters(r),
                                                 &err)) != MIMAS_OK) {
            mimas_writer_abort(nw);
            nw = NULL;
        }
        out = (sink){nw, native_append, native_frames, native_close, native_abort, {0, 0}};
    }
    if (!rc)
        rc = convert_frames(cmd, &in, r, &out, lammps ? close_dump : close_native, argv[first],
                            &err);
    size_t skipped = mimas_reader_skipped(r);
    mimas_reader_close(r);
    free(provenance);
    int quiet = in.quiet;
    cli_inputs_free(&in);
    if (rc)
        return cli_fail(cmd, mimas_exit_status(rc), "%s", err.msg);
    for (int k = 0; !quiet && k < 2; k++)
        if (out.local[k]) {
            char path[4200];
            mimas_dump_local_path(a.output, k, path, sizeof path);
            fprintf(stderr, "mimas convert: %s in %s (read back with --%s %s)\n",
                    k ? "wall contacts" : "contacts", path, k ? "wall-contacts" : "contacts",
                    path);
        }
    if (skipped)
        fprintf(stderr, "mimas convert: skipped %zu frames whose contact data were missing\n",
                skipped);
    return 0;
}

const cli_command cmd_convert = {
    "convert",
    "write any input (dumps, MercuryDPM files, native files) as a native file or LAMMPS dumps",
    "[options] INPUT... -o OUT.h5 | -o OUT.dump[.gz] [--to lammps]",
    "Reads the inputs frame by frame (with their contact and wall-contact files)\n"
    "and writes them to OUT.h5 in the native format (docs/format.md), with the\n"
    "XDMF sidecar OUT.xdmf that ParaView opens.  With --to lammps (the default for\n"
    "OUT.dump and OUT.dump.gz) it writes LAMMPS/LIGGGHTS text dumps instead: the\n"
    "particles as dump custom (id type x y z ix iy iz vx vy vz omegax omegay omegaz\n"
    "fx fy fz radius mass and the extra columns, as present), the contacts and wall\n"
    "contacts as dump local files with named columns (OUT.pairs.dump,\n"
    "OUT.walls.dump; docs/readers.md), every number with 17 significant digits, so\n"
    "that reading them back gives the same frames.  A name ending in .gz is\n"
    "compressed.  Everything is written under temporary names and renamed when\n"
    "complete, so a failed conversion leaves nothing behind.  A native output keeps\n"
    "the run parameters of native inputs (not their per-frame observables).",
    options,
    sizeof options / sizeof options[0],
    1,
    run,
    "# a LIGGGHTS run with its contact dumps into one native file (docs/format.md)\n"
    "K=pos,vel,id,force,force_normal,force_tangential,torque,torque_normal,torque_tangential,history,contactArea,delta,contactPoint\n"
    "mimas convert 'dump.*.atom.gz' --contacts 'dump.*.pgl.gz' --contact-columns $K -o run.h5\n"
    "mimas info run.h5",
};
