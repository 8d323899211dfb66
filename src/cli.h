/* Command-line plumbing shared by the subcommands: each command declares its
 * options once, as data, and help text and parsing are driven from that. */
#ifndef MIMAS_CLI_H
#define MIMAS_CLI_H

#include <stddef.h>
#include <stdio.h>

#include "reader.h"

typedef struct cli_option {
    const char *name;    /* long name without "--" */
    char short_name;     /* 0 if none */
    const char *arg;     /* argument placeholder, NULL for a flag */
    const char *help;
} cli_option;

/* The input options every command that reads data accepts (--format,
 * --contacts, --density, ...), collected into reader options. */
typedef struct cli_inputs {
    mimas_reader_options opt;
    const char **contacts, **walls;   /* point into argv */
    int quiet;
} cli_inputs;
void cli_inputs_free(cli_inputs *in);

typedef struct cli_command {
    const char *name;
    const char *summary;      /* one line */
    const char *usage;        /* arguments after "mimas NAME" */
    const char *description;  /* paragraph(s) for --help and the man page */
    const cli_option *options;
    size_t noptions;
    int reads_inputs;         /* also takes the input options (cli_inputs) */
    int (*run)(const struct cli_command *cmd, int argc, char **argv);
    /* Shell lines for the EXAMPLES of --help and the man page (NULL: none):
     * "# " lines explain, the others are commands; a blank line separates
     * examples.  tests/cli/examples.test runs them. */
    const char *examples;
} cli_command;

/* Called for every option found: opt is an index into cmd->options, arg its
 * argument or NULL.  Returns 0, or an exit status after printing a message. */
typedef int (*cli_handler)(void *ctx, size_t opt, const char *arg);

/* Parses argv (argv[0] is the command name).  Handles --help itself (prints
 * help, returns -1 meaning "done, exit 0").  On a usage error prints
 * "mimas NAME: ..." and returns 1.  On success returns 0 and sets *first to
 * the index of the first positional argument. */
int cli_parse(const cli_command *cmd, int argc, char **argv, cli_handler handler, void *ctx,
              cli_inputs *inputs, int *first);
/* Opens the positional arguments argv[first..argc-1] as one input; prints
 * the error and returns the exit status on failure. */
int cli_open_inputs(const cli_command *cmd, cli_inputs *in, int argc, char **argv, int first,
                    mimas_reader **r);

void cli_print_help(const cli_command *cmd, FILE *out);
/* The command's man page (roff), from the same declaration as --help. */
void cli_print_man(const cli_command *cmd, const char *version, FILE *out);
/* "mimas NAME: message" on stderr; returns status. */
int cli_fail(const cli_command *cmd, int status, const char *fmt, ...)
    __attribute__((format(printf, 3, 4)));
/* A progress line on standard error, only when it is a terminal and not
 * quiet: at the first update, then at most twice a second.  With a known
 * total it says how far and how long is left, "mimas CMD: frame 120/500
 * (24 %), step S, time T s, 1 min 20 s left"; else "mimas CMD: 120 frames
 * (step S, time T s)".  cli_progress_done erases the line. */
typedef struct cli_progress {
    int on, shown;
    double start, last;
    size_t total;   /* frames the input holds (0: unknown) */
} cli_progress;
/* For commands that read inputs (quiet from -q). */
void cli_progress_start(cli_progress *p, const cli_inputs *in);
/* For the others. */
void cli_progress_begin(cli_progress *p, int quiet);
/* The total from the reader, when its format knows it (native files). */
void cli_progress_total(cli_progress *p, const mimas_reader *r);
/* After each frame read (frames: read so far, used or not). */
void cli_progress_frame(cli_progress *p, const cli_command *cmd, size_t frames, long long step,
                        double time);
/* Any work of known size: "mimas CMD: WHAT done/total (P %), DETAIL, T left";
 * left: the seconds left if the caller knows them better (< 0: from the
 * time since cli_progress_begin and done/total); detail may be NULL. */
void cli_progress_work(cli_progress *p, const cli_command *cmd, const char *what, double done,
                       double total, double left, const char *detail);
/* The same for a count of things: "mimas CMD: WHAT DONE/TOTAL (P %), T left". */
void cli_progress_count(cli_progress *p, const cli_command *cmd, const char *what, size_t done,
                        size_t total);
void cli_progress_done(cli_progress *p);

/* A table written to standard output, or to a file under a temporary name
 * renamed into place when complete (no partial output). */
typedef struct cli_output {
    FILE *fp;
    const char *path;   /* NULL: standard output */
    char tmp[4200];     /* "": written straight to path (a device or a pipe) */
    int slot;           /* in the temporary-file registry (src/tmpfiles.h) */
    char *buf;          /* the stream's buffer (a file's: large), or NULL */
} cli_output;
/* path NULL or "-": standard output; a path that is not a regular file
 * (/dev/null, a pipe) is written straight through. */
int cli_output_open(cli_output *o, const char *path, mimas_error *err);
/* Finishes the table: with ok, flushes (and renames the file into place);
 * else removes the temporary file.  Returns MIMAS_OK or a write error. */
int cli_output_close(cli_output *o, int ok, mimas_error *err);

/* A comma list of particle types ("1,3") into types[] (at most max, *n
 * counts them); on a bad list prints the usage error naming --opt and
 * returns 1. */
int cli_parse_types(const cli_command *cmd, const char *opt, const char *arg, int32_t *types,
                    size_t max, size_t *n);

/* --types L or --exclude-types L (they exclude each other). */
typedef struct cli_types {
    int32_t types[64];
    size_t n;
    int exclude, given;
} cli_types;
/* The option's list into t (exclude: it was --exclude-types); prints the
 * usage error and returns 1 on a bad list or when both options are given. */
int cli_types_option(const cli_command *cmd, cli_types *t, int exclude, const char *arg);

/* The frames a command uses: --from T0 --to T1 (simulation times) and
 * --every K of those. */
typedef struct cli_window {
    double from, to;
    int has_from, has_to;
    long every;   /* 0 or 1: every frame */
    long seen;    /* frames inside the time window so far */
} cli_window;
/* --from (from = 1) or --to TIME into the window; prints the usage error
 * and returns 1 on a bad time. */
int cli_window_time(const cli_command *cmd, cli_window *w, int from, const char *arg);
/* --every K into the window; prints the usage error and returns 1 unless
 * K is a positive whole number. */
int cli_window_every(const cli_command *cmd, cli_window *w, const char *arg);
/* 1 if frame f is used, 0 if not; MIMAS_EUSAGE (negated: -1) with err set
 * when the window needs a time the frame (of input) does not have. */
int cli_window_take(cli_window *w, const mimas_frame *f, const char *input, mimas_error *err);

/* Writes a whole table with write(fp, ctx) to path (NULL or "-": standard
 * output) through cli_output: nothing is left at path on failure. */
int cli_write_table(const char *path, void (*write)(FILE *fp, const void *ctx), const void *ctx,
                    mimas_error *err);

/* "mimas ARGS..." (malloc'd), for provenance attributes. */
char *cli_command_line(int argc, char **argv);
/* Parses a number; returns 0 on success. */
int cli_parse_double(const char *s, double *v);
/* "LO:HI", "LO:" or ":HI" (a bound left out is -+infinity) with LO < HI;
 * returns 0 on success. */
int cli_parse_range(const char *arg, double *lo, double *hi);
int cli_parse_long(const char *s, long *v);
/* --temperature-components: a comma list of s, r, phi into the bits 1, 2,
 * 4 (MIMAS_TEMP_S, _R, _PHI of axial_profile.h); prints the usage error and
 * returns 1 otherwise. */
int cli_parse_temperature(const cli_command *cmd, const char *arg, unsigned *bits);
/* "A:B" with A < B (finite numbers); returns 0 on success. */
int cli_parse_pair(const char *s, double *a, double *b);
/* Option parsers that print the usage error naming --opt and return 1 on a
 * bad argument, else 0: a positive number; A:B with A < B (placeholder
 * names what A and B are, e.g. "S0:S1"). */
int cli_positive_option(const cli_command *cmd, const char *opt, const char *arg, double *v);
int cli_pair_option(const cli_command *cmd, const char *opt, const char *placeholder,
                    const char *arg, double *a, double *b);
/* "LO:HI", "LO:" or ":HI" (bounds left out are -inf, +inf; LO < HI); 0 on success. */
int cli_parse_range(const char *arg, double *lo, double *hi);
/* --threads N (1..1024) into *threads; prints the usage error and returns 1 otherwise. */
int cli_parse_threads(const cli_command *cmd, const char *arg, int *threads);

/* ---- safety nets every command uses (issue 15) ---- */
/* What main() does first:
 * - OpenMP threads wait passively (OMP_WAIT_POLICY=passive) unless the user
 *   set OMP_WAIT_POLICY: libgomp reads it when it is loaded, before main(),
 *   so the program executes itself once more with it set; with --threads 1
 *   on the command line every parallel region has one thread, no thread
 *   waits, and the program goes on as it is;
 * - HDF5 does not close files at exit (a file whose flush failed on a full
 *   disk would make it loop; mimas closes its files itself);
 * - SIGINT, SIGTERM, SIGHUP and SIGPIPE remove the temporary output files
 *   (src/tmpfiles.h), then end the program as they would have. */
void cli_start(int argc, char **argv);
/* Refuses an output that is one of the inputs: 0 if output (NULL: none) is
 * not an existing file that is also one of names[0..n-1] (after '*'
 * expansion) or of in's contact files (NULL: none) -- the same file, by
 * device and inode, whatever its name; else prints the usage error and
 * returns 1. */
int cli_refuse_input_as_output(const cli_command *cmd, const char *output, const cli_inputs *in,
                               char *const *names, int n);

#endif
