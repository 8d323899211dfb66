/* mimas convert: any input into the native format. */
#include <config.h>

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "commands.h"
#include "native.h"
#include "reader.h"

static const cli_option options[] = {
    {"output", 'o', "OUT.h5", "the native file to write (required)"},
    {"deflate", 0, "LEVEL", "gzip level 0-9 of particle and contact data (default 1; 0 is "
                            "fastest)"},
};

typedef struct convert_args {
    const char *output;
    long deflate;
    const cli_command *cmd;
} convert_args;

static int on_option(void *ctx, size_t opt, const char *arg)
{
    convert_args *a = ctx;
    if (opt == 0)
        a->output = arg;
    else if (cli_parse_long(arg, &a->deflate) || a->deflate < 0 || a->deflate > 9)
        return cli_fail(a->cmd, 1, "--deflate needs a level from 0 to 9, not '%s'", arg);
    return 0;
}

static int run(const cli_command *cmd, int argc, char **argv)
{
    convert_args a = {NULL, 1, cmd};
    cli_inputs in = {0};
    int first;
    int rc = cli_parse(cmd, argc, argv, on_option, &a, &in, &first);
    if (!rc && !a.output)
        rc = cli_fail(cmd, 1, "no output file: give -o OUT.h5");
    mimas_reader *r = NULL;
    if (!rc)
        rc = cli_open_inputs(cmd, &in, argc, argv, first, &r);
    if (rc) {
        cli_inputs_free(&in);
        return rc < 0 ? 0 : rc;
    }
    mimas_writer_options o;
    mimas_writer_options_default(&o);
    o.deflate = (int)a.deflate;
    o.atomic = 1; /* no partial output: the file appears when it is complete */
    char *provenance = cli_command_line(argc, argv);
    o.provenance = provenance;
    mimas_writer *w = NULL;
    mimas_error err;
    mimas_frame f;
    mimas_frame_init(&f);
    rc = mimas_writer_open(&w, a.output, &o, &err);
    if (!rc)
        rc = mimas_writer_parameters(w, "scenario", mimas_reader_parameters(r), &err);
    cli_progress prog;
    cli_progress_start(&prog, &in);
    while (!rc && (rc = mimas_reader_next(r, &f, &err)) == MIMAS_OK) {
        rc = mimas_writer_append(w, &f, &err);
        cli_progress_frame(&prog, cmd, mimas_writer_frames(w), (long long)f.step, f.time);
    }
    cli_progress_done(&prog);
    if (rc == MIMAS_END && mimas_writer_frames(w) == 0)
        rc = mimas_error_set(&err, MIMAS_EDATA, "%s: no frames to convert", argv[first]);
    if (rc == MIMAS_END)
        rc = mimas_writer_close(w, &err);
    else if (w)
        mimas_writer_abort(w);
    size_t skipped = mimas_reader_skipped(r);
    mimas_frame_free(&f);
    mimas_reader_close(r);
    cli_inputs_free(&in);
    free(provenance);
    if (rc)
        return cli_fail(cmd, mimas_exit_status(rc), "%s", err.msg);
    if (skipped)
        fprintf(stderr, "mimas convert: skipped %zu frames whose contact data were missing\n",
                skipped);
    return 0;
}

const cli_command cmd_convert = {
    "convert",
    "write any input (dumps, MercuryDPM files, native files) in the native format",
    "[options] INPUT... -o OUT.h5",
    "Reads the inputs frame by frame (with their contact and wall-contact files)\n"
    "and writes them to OUT.h5 in the native format (docs/format.md).  The file\n"
    "is written under a temporary name and renamed when complete, so a failed\n"
    "conversion leaves nothing behind.  The run parameters of native inputs are\n"
    "kept (their per-frame observables are not).",
    options,
    sizeof options / sizeof options[0],
    1,
    run,
};
