#include <config.h>

#include "cli.h"
#include "outfile.h"

#include "parallel.h"

#include <ctype.h>
#include <errno.h>
#include <getopt.h>
#include <glob.h>
#include <math.h>
#include <signal.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#include <hdf5.h>
#ifdef _OPENMP
#include <omp.h>
#endif

#include "tmpfiles.h"

#define MAX_OPTIONS 64

static const cli_option input_options[] = {
    {"format", 0, "FMT", "input format: native, lammps or mercury (default: from the content)"},
    {"contacts", 0, "FILE", "contact dump(s): LIGGGHTS pair/gran/local, LAMMPS pair/local, "
                            "MercuryDPM .fstat (repeat the option or use a '*' pattern)"},
    {"wall-contacts", 0, "FILE", "wall-contact dump(s): LIGGGHTS wall/gran/local"},
    {"contact-columns", 0, "LIST", "what the contact dump's c_ID[k] columns are: the keywords the "
                                   "LIGGGHTS compute was given (pos,id,force,...,history:3,...) "
                                   "or LAMMPS names in dump order (patom1,patom2,dist,fx,fy,fz)"},
    {"wall-columns", 0, "LIST", "the same for the wall-contact dump"},
    {"density", 0, "RHO", "particle density (kg/m3) for masses when the input has none"},
    {"timestep", 0, "DT", "time step (s): time = step * DT for dumps without ITEM: TIME"},
    {"allow-missing-contacts", 0, NULL, "skip frames whose contact data are missing instead of "
                                        "failing"},
    {"quiet", 'q', NULL, "no progress output"},
};
#define NINPUT (sizeof input_options / sizeof input_options[0])
/* The stream buffer of a table written to a file */
#define CLI_OUTPUT_BUFFER ((size_t)1 << 20)

void cli_inputs_free(cli_inputs *in)
{
    free(in->contacts);
    free(in->walls);
    memset(in, 0, sizeof *in);
}

static int push(const char ***list, size_t *n, const char *v)
{
    const char **g = realloc(*list, (*n + 1) * sizeof *g);
    if (!g)
        return -1;
    g[(*n)++] = v;
    *list = g;
    return 0;
}

static int input_option(const cli_command *cmd, cli_inputs *in, size_t k, const char *arg)
{
    mimas_reader_options *o = &in->opt;
    double v;
    switch (k) {
    case 0: o->format = arg; return 0;
    case 1:
        if (push(&in->contacts, &o->ncontacts, arg))
            return cli_fail(cmd, 2, "out of memory for the list of options");
        o->contacts = in->contacts;
        return 0;
    case 2:
        if (push(&in->walls, &o->nwalls, arg))
            return cli_fail(cmd, 2, "out of memory for the list of options");
        o->walls = in->walls;
        return 0;
    case 3: o->contact_columns = arg; return 0;
    case 4: o->wall_columns = arg; return 0;
    case 5:
    case 6:
        if (cli_parse_double(arg, &v) || !(v > 0))
            return cli_fail(cmd, 1, "--%s needs a positive number, not '%s'",
                            input_options[k].name, arg);
        *(k == 5 ? &o->density : &o->timestep) = v;
        return 0;
    case 7: o->allow_missing_contacts = 1; return 0;
    case 8: in->quiet = 1; return 0;
    }
    return 1;
}

/* What a reader found out by itself, on standard error. */
static void note(void *ctx, const char *message)
{
    fprintf(stderr, "mimas %s: %s\n", ((const cli_command *)ctx)->name, message);
}

int cli_open_inputs(const cli_command *cmd, cli_inputs *in, int argc, char **argv, int first,
                    mimas_reader **r)
{
    if (first >= argc)
        return cli_fail(cmd, 1, "no input file (see mimas %s --help)", cmd->name);
    if (!in->quiet) {
        in->opt.notify = note;
        in->opt.notify_ctx = (void *)cmd;
    }
    mimas_error err;
    int rc = mimas_reader_open(r, (const char *const *)argv + first, (size_t)(argc - first),
                               &in->opt, &err);
    if (rc)
        return cli_fail(cmd, mimas_exit_status(rc), "%s", err.msg);
    return 0;
}

int cli_fail(const cli_command *cmd, int status, const char *fmt, ...)
{
    /* under MPI every rank agrees on the failure; one of them says it */
    if (mimas_par_rank() != 0)
        return status;
    va_list ap;
    fprintf(stderr, "mimas %s: ", cmd->name);
    va_start(ap, fmt);
    vfprintf(stderr, fmt, ap);
    va_end(ap);
    fputc('\n', stderr);
    return status;
}

void cli_print_help(const cli_command *cmd, FILE *out)
{
    fprintf(out, "Usage: mimas %s %s\n\n%s\n", cmd->name, cmd->usage, cmd->summary);
    if (cmd->description && cmd->description[0])
        fprintf(out, "\n%s\n", cmd->description);
    fprintf(out, "\nOptions:\n");
    size_t nin = cmd->reads_inputs ? NINPUT : 0;
    for (size_t k = 0; k <= cmd->noptions + nin; k++) {
        const cli_option *o = k < cmd->noptions          ? &cmd->options[k]
                              : k < cmd->noptions + nin ? &input_options[k - cmd->noptions]
                                                        : &(cli_option){"help", 'h', NULL,
                                                                "print this help and exit"};
        if (k == cmd->noptions && nin)
            fprintf(out, "\nInput options:\n");
        char left[64];
        int w = o->short_name ? snprintf(left, sizeof left, "-%c, --%s", o->short_name, o->name)
                              : snprintf(left, sizeof left, "    --%s", o->name);
        if (o->arg)
            snprintf(left + w, sizeof left - (size_t)w, " %s", o->arg);
        fprintf(out, "  %-28s %s\n", left, o->help);
    }
    if (cmd->examples && cmd->examples[0]) {
        fprintf(out, "\nExamples:\n");
        for (const char *l = cmd->examples; *l;) {
            size_t len = strcspn(l, "\n");
            fprintf(out, len ? "  %.*s\n" : "%.*s\n", (int)len, l);
            l += len + (l[len] == '\n');
        }
    }
}

/* roff needs backslashes doubled and leading dots or quotes escaped */
static void roff_text(FILE *out, const char *s)
{
    int bol = 1;
    for (; *s; s++) {
        if (bol && (*s == '.' || *s == '\''))
            fputs("\\&", out);
        if (*s == '\\')
            fputs("\\e", out);
        else if (*s == '-')
            fputs("\\-", out);
        else
            fputc(*s, out);
        bol = *s == '\n';
    }
}

/* EXAMPLES: the "# " lines as text, the commands as indented literal lines */
static void man_examples(FILE *out, const char *text)
{
    fprintf(out, ".SH EXAMPLES\n");
    int literal = 0, para = 1;
    for (const char *l = text; *l;) {
        size_t len = strcspn(l, "\n");
        char line[1024];
        snprintf(line, sizeof line, "%.*s", (int)(len < sizeof line ? len : sizeof line - 1), l);
        int comment = line[0] == '#';
        if (!len || comment) {
            if (literal)
                fprintf(out, ".fi\n.RE\n"), literal = 0;
            if (!len)
                para = 1;
            else {
                char *words = line + (line[1] == ' ' ? 2 : 1);
                if (para) {
                    fprintf(out, ".PP\n"), para = 0;
                    words[0] = (char)toupper((unsigned char)words[0]);
                }
                roff_text(out, words);
                fputc('\n', out);
            }
        } else {
            if (!literal)
                fprintf(out, ".RS 4\n.nf\n"), literal = 1;
            roff_text(out, line);
            fputc('\n', out);
            para = 1;
        }
        l += len + (l[len] == '\n');
    }
    if (literal)
        fprintf(out, ".fi\n.RE\n");
}

void cli_print_man(const cli_command *cmd, const char *version, FILE *out)
{
    fprintf(out, ".TH MIMAS-%s 1 \"\" \"mimas %s\" \"mimas manual\"\n", cmd->name, version);
    fprintf(out, ".SH NAME\nmimas\\-%s \\- ", cmd->name);
    roff_text(out, cmd->summary);
    fprintf(out, "\n.SH SYNOPSIS\n.B mimas %s\n", cmd->name);
    roff_text(out, cmd->usage);
    fprintf(out, "\n.SH DESCRIPTION\n");
    roff_text(out, cmd->description);
    fprintf(out, "\n.SH OPTIONS\n");
    size_t nin = cmd->reads_inputs ? NINPUT : 0;
    for (size_t k = 0; k < cmd->noptions + nin; k++) {
        const cli_option *o = k < cmd->noptions ? &cmd->options[k]
                                                : &input_options[k - cmd->noptions];
        fprintf(out, ".TP\n");
        if (o->short_name)
            fprintf(out, "\\fB\\-%c\\fR, ", o->short_name);
        fprintf(out, "\\fB\\-\\-");
        roff_text(out, o->name);
        fprintf(out, "\\fR");
        if (o->arg) {
            fprintf(out, " \\fI");
            roff_text(out, o->arg);
            fprintf(out, "\\fR");
        }
        fprintf(out, "\n");
        roff_text(out, o->help);
        fprintf(out, "\n");
    }
    if (cmd->examples && cmd->examples[0])
        man_examples(out, cmd->examples);
    fprintf(out, ".SH EXIT STATUS\n0 on success, 1 on bad usage, 2 on bad input data, with a "
                 "one\\-line message naming the file and the problem.\n"
                 ".SH SEE ALSO\n.BR mimas (1)\n");
}

/* Option arguments that are comma lists (by their placeholder: SPEC, LIST, L
 * or one with a comma) may have no empty item; no argument may be empty. */
static int check_argument(const cli_command *cmd, const cli_option *o, const char *arg)
{
    if (!arg[0] || !arg[strspn(arg, " \t")])
        return cli_fail(cmd, 1, "--%s needs a value, not an empty %s", o->name, o->arg);
    int list = strstr(o->arg, "SPEC") || strstr(o->arg, "LIST") || !strcmp(o->arg, "L") ||
               strchr(o->arg, ',');
    if (list && (arg[0] == ',' || arg[strlen(arg) - 1] == ',' || strstr(arg, ",,")))
        return cli_fail(cmd, 1, "--%s '%s': an empty item in the comma list", o->name, arg);
    return 0;
}

int cli_parse(const cli_command *cmd, int argc, char **argv, cli_handler handler, void *ctx,
              cli_inputs *inputs, int *first)
{
    struct option longopts[MAX_OPTIONS + NINPUT + 2];
    char shortopts[3 * (MAX_OPTIONS + NINPUT) + 8];
    size_t ns = 0, nin = inputs ? NINPUT : 0;
    if (cmd->noptions > MAX_OPTIONS)
        return cli_fail(cmd, 1, "too many options declared");
    shortopts[ns++] = ':'; /* report missing arguments distinctly */
    size_t nall = cmd->noptions + nin;
    for (size_t k = 0; k < nall; k++) {
        const cli_option *o = k < cmd->noptions ? &cmd->options[k]
                                                : &input_options[k - cmd->noptions];
        longopts[k] = (struct option){o->name, o->arg ? required_argument : no_argument, NULL,
                                      256 + (int)k};
        if (o->short_name) {
            shortopts[ns++] = o->short_name;
            if (o->arg)
                shortopts[ns++] = ':';
        }
    }
    longopts[nall] = (struct option){"help", no_argument, NULL, 'h'};
    longopts[nall + 1] = (struct option){NULL, 0, NULL, 0};
    shortopts[ns++] = 'h';
    shortopts[ns] = '\0';

    optind = 1;
    opterr = 0;
    for (;;) {
        int c = getopt_long(argc, argv, shortopts, longopts, NULL);
        if (c == -1)
            break;
        if (c == 'h') {
            if (mimas_par_rank() == 0)
                cli_print_help(cmd, stdout);
            return -1;
        }
        if (c == '?')
            return cli_fail(cmd, 1, "unknown option '%s' (see mimas %s --help)",
                            argv[optind - 1], cmd->name);
        if (c == ':')
            return cli_fail(cmd, 1, "option '%s' needs an argument", argv[optind - 1]);
        size_t opt = nall;
        if (c >= 256)
            opt = (size_t)(c - 256);
        else
            for (size_t k = 0; k < nall; k++) {
                const cli_option *o = k < cmd->noptions ? &cmd->options[k]
                                                        : &input_options[k - cmd->noptions];
                if (o->short_name == c)
                    opt = k;
            }
        if (opt >= nall)
            return cli_fail(cmd, 1, "unknown option (see mimas %s --help)", cmd->name);
        const cli_option *od = opt < cmd->noptions ? &cmd->options[opt]
                                                   : &input_options[opt - cmd->noptions];
        if (od->arg && check_argument(cmd, od, optarg))
            return 1;
        int rc = opt >= cmd->noptions ? input_option(cmd, inputs, opt - cmd->noptions, optarg)
                 : handler            ? handler(ctx, opt, optarg)
                                      : 0;
        if (rc)
            return rc;
    }
    *first = optind;
    return 0;
}

int cli_parse_double(const char *s, double *v)
{
    char *end;
    errno = 0;
    double x = strtod(s, &end);
    if (end == s || *end != '\0' || errno == ERANGE || !isfinite(x))
        return -1;
    *v = x;
    return 0;
}

int cli_parse_range(const char *arg, double *lo, double *hi)
{
    const char *colon = strchr(arg, ':');
    if (!colon)
        return -1;
    char a[64], b[64];
    size_t la = (size_t)(colon - arg), lb = strlen(colon + 1);
    if (la >= sizeof a || lb >= sizeof b)
        return -1;
    memcpy(a, arg, la);
    a[la] = '\0';
    memcpy(b, colon + 1, lb + 1);
    *lo = -INFINITY;
    *hi = INFINITY;
    if ((la && cli_parse_double(a, lo)) || (lb && cli_parse_double(b, hi)))
        return -1;
    return *hi > *lo ? 0 : -1;
}

int cli_parse_pair(const char *s, double *a, double *b)
{
    double x, y;
    if (cli_parse_range(s, &x, &y) || !isfinite(x) || !isfinite(y))
        return -1;
    *a = x;
    *b = y;
    return 0;
}

int cli_parse_long(const char *s, long *v)
{
    char *end;
    errno = 0;
    long x = strtol(s, &end, 10);
    if (end == s || *end != '\0' || errno == ERANGE)
        return -1;
    *v = x;
    return 0;
}

int cli_parse_threads(const cli_command *cmd, const char *arg, int *threads)
{
    long v;
    if (cli_parse_long(arg, &v) || v < 1 || v > 1024)
        return cli_fail(cmd, 1, "--threads needs a number from 1 to 1024, not '%s'", arg);
    *threads = (int)v;
    return 0;
}

int cli_parse_types(const cli_command *cmd, const char *opt, const char *arg, int32_t *types,
                    size_t max, size_t *n)
{
    char *text = strdup(arg), *save = NULL;
    if (!text)
        return cli_fail(cmd, 2, "out of memory for the list of options");
    int rc = 0;
    for (char *tok = strtok_r(text, ",", &save); tok && !rc; tok = strtok_r(NULL, ",", &save)) {
        long v;
        if (cli_parse_long(tok, &v) || v < INT32_MIN || v > INT32_MAX || *n >= max)
            rc = cli_fail(cmd, 1, "--%s needs a comma list of type numbers, not '%s'", opt, arg);
        else
            types[(*n)++] = (int32_t)v;
    }
    free(text);
    return rc;
}

int cli_window_time(const cli_command *cmd, cli_window *w, int from, const char *arg)
{
    double t;
    if (cli_parse_double(arg, &t))
        return cli_fail(cmd, 1, "--%s needs a time, not '%s'", from ? "from" : "to", arg);
    if (from)
        w->from = t, w->has_from = 1;
    else
        w->to = t, w->has_to = 1;
    return 0;
}

int cli_window_every(const cli_command *cmd, cli_window *w, const char *arg)
{
    if (cli_parse_long(arg, &w->every) || w->every < 1)
        return cli_fail(cmd, 1, "--every needs a positive whole number, not '%s'", arg);
    return 0;
}

int cli_window_take(cli_window *w, const mimas_frame *f, const char *input, mimas_error *err)
{
    if ((w->has_from || w->has_to) && isnan(f->time)) {
        mimas_error_set(err, MIMAS_EUSAGE, "%s: frame at step %lld has no time; give "
                        "--timestep for --from/--to", input, (long long)f->step);
        return -1;
    }
    if ((w->has_from && f->time < w->from) || (w->has_to && f->time > w->to))
        return 0;
    return w->seen++ % (w->every > 1 ? w->every : 1) == 0;
}

char *cli_command_line(int argc, char **argv)
{
    size_t len = 16;
    for (int k = 0; k < argc; k++)
        len += strlen(argv[k]) + 1;
    char *s = malloc(len);
    if (!s)
        return NULL;
    strcpy(s, "mimas");
    for (int k = 0; k < argc; k++) {
        strcat(s, " ");
        strcat(s, argv[k]);
    }
    return s;
}

static double seconds(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

void cli_progress_begin(cli_progress *p, int quiet)
{
    memset(p, 0, sizeof *p);
    p->on = !quiet && isatty(STDERR_FILENO) && mimas_par_rank() == 0;
    p->start = p->last = seconds();
}

void cli_progress_start(cli_progress *p, const cli_inputs *in)
{
    cli_progress_begin(p, in->quiet);
}

void cli_progress_total(cli_progress *p, const mimas_reader *r)
{
    p->total = mimas_reader_total(r);
}

/* 1 if a line is due now: the first update, then every half second */
static int progress_due(cli_progress *p)
{
    if (!p->on)
        return 0;
    double now = seconds();
    if (p->shown && now - p->last < 0.5)
        return 0;
    p->shown = 1;
    p->last = now;
    return 1;
}

/* "45 s", "3 min 05 s", "2 h 05 min" */
static void duration_text(double s, char *buf, size_t len)
{
    if (!(s >= 0) || s > 3.6e8)
        snprintf(buf, len, "?");
    else if (s < 59.5)
        snprintf(buf, len, "%.0f s", s < 1 ? 1 : s);
    else if (s < 3599.5)
        snprintf(buf, len, "%d min %02d s", (int)(s + 0.5) / 60, (int)(s + 0.5) % 60);
    else
        snprintf(buf, len, "%d h %02d min", (int)(s + 30) / 3600, (int)(s + 30) % 3600 / 60);
}

static void progress_line(cli_progress *p, const cli_command *cmd, const char *what,
                          double done, double total, double left, const char *detail)
{
    char text[32];
    if (left < 0)
        left = done > 0 ? (seconds() - p->start) * (total - done) / done : -1;
    duration_text(left, text, sizeof text);
    fprintf(stderr, "\r\033[Kmimas %s: %s %.0f/%.0f (%.0f %%), %s%s%s left", cmd->name, what,
            done, total, total > 0 ? 100 * done / total : 0, detail ? detail : "",
            detail ? ", " : "", text);
    fflush(stderr);
}

void cli_progress_work(cli_progress *p, const cli_command *cmd, const char *what, double done,
                       double total, double left, const char *detail)
{
    if (progress_due(p))
        progress_line(p, cmd, what, done, total, left, detail);
}

void cli_progress_frame(cli_progress *p, const cli_command *cmd, size_t frames, long long step,
                        double time)
{
    if (!progress_due(p))
        return;
    char detail[96];
    if (isnan(time))
        snprintf(detail, sizeof detail, "step %lld", step);
    else
        snprintf(detail, sizeof detail, "step %lld, time %g s", step, time);
    if (p->total >= frames && p->total > 0) {
        progress_line(p, cmd, "frame", (double)frames, (double)p->total, -1, detail);
        return;
    }
    fprintf(stderr, "\r\033[Kmimas %s: %zu frames (%s)", cmd->name, frames, detail);
    fflush(stderr);
}

void cli_progress_count(cli_progress *p, const cli_command *cmd, const char *what, size_t done,
                        size_t total)
{
    cli_progress_work(p, cmd, what, (double)done, (double)total, -1, NULL);
}

void cli_progress_done(cli_progress *p)
{
    if (p->on && p->shown)
        fputs("\r\033[K", stderr);
}

int cli_output_open(cli_output *o, const char *path, mimas_error *err)
{
    memset(o, 0, sizeof *o);
    if (!path || !strcmp(path, "-")) {
        o->fp = stdout;
        return MIMAS_OK;
    }
    o->path = path;
    o->slot = -1;
    /* a device or a pipe takes the table as it comes: renamed onto, a
     * finished file would replace it */
    if (mimas_output_is_special(path)) {
        o->tmp[0] = '\0';
    } else {
        if (mimas_tmpfile_name(o->tmp, sizeof o->tmp, path))
            return mimas_error_set(err, MIMAS_EUSAGE, "%s: the file name is too long", path);
        o->slot = mimas_tmpfile_add(o->tmp);
    }
    o->fp = fopen(o->tmp[0] ? o->tmp : path, "w");
    if (!o->fp) {
        int e = errno;
        mimas_tmpfile_forget(o->slot);
        return mimas_error_set(err, MIMAS_EIO, "%s: cannot write: %s", path, strerror(e));
    }
    /* a file takes the table in large writes (a 15 MB table in 15 rather than 3,700
     * system calls); a pipe or device as it comes.  glibc ignores the size unless
     * given the buffer. */
    if (o->tmp[0] && (o->buf = malloc(CLI_OUTPUT_BUFFER)))
        setvbuf(o->fp, o->buf, _IOFBF, CLI_OUTPUT_BUFFER);
    return MIMAS_OK;
}

int cli_output_close(cli_output *o, int ok, mimas_error *err)
{
    if (!o->fp)
        return MIMAS_OK;
    int rc = MIMAS_OK;
    if (!o->path) {
        errno = 0;
        if (ok && (fflush(stdout) != 0 || ferror(stdout)))
            rc = mimas_error_set(err, MIMAS_EIO, "cannot write the table to standard output: %s",
                                 errno ? strerror(errno) : "write error");
    } else {
        int bad = ferror(o->fp) != 0;
        errno = 0;
        int closed = fclose(o->fp) == 0;
        free(o->buf);
        o->buf = NULL;
        if (ok && (bad || !closed || (o->tmp[0] && rename(o->tmp, o->path) != 0)))
            rc = mimas_error_set(err, MIMAS_EIO, "%s: cannot write the table: %s", o->path,
                                 errno ? strerror(errno) : "write error");
        if ((!ok || rc) && o->tmp[0])
            remove(o->tmp);
        mimas_tmpfile_forget(o->slot);
    }
    o->fp = NULL;
    return rc;
}

int cli_write_table(const char *path, void (*write)(FILE *fp, const void *ctx), const void *ctx,
                    mimas_error *err)
{
    cli_output o;
    int rc = cli_output_open(&o, path, err);
    if (rc)
        return rc;
    write(o.fp, ctx);
    int bad = ferror(o.fp) != 0;
    rc = cli_output_close(&o, !bad, err);
    if (bad && !rc)
        rc = mimas_error_set(err, MIMAS_EIO, "%s: cannot write the table", path ? path : "-");
    return rc;
}

int cli_parse_temperature(const cli_command *cmd, const char *arg, unsigned *bits)
{
    static const char *const names[3] = {"s", "r", "phi"};
    char buf[64];
    if (strlen(arg) >= sizeof buf)
        return cli_fail(cmd, 1, "--temperature-components: a comma list of s, r, phi");
    snprintf(buf, sizeof buf, "%s", arg);
    *bits = 0;
    char *save = NULL;
    for (char *tok = strtok_r(buf, ",", &save); tok; tok = strtok_r(NULL, ",", &save)) {
        int c = 0;
        while (c < 3 && strcmp(tok, names[c]))
            c++;
        if (c == 3)
            return cli_fail(cmd, 1, "--temperature-components: '%s' is not s, r or phi", tok);
        *bits |= 1u << c;
    }
    return *bits ? 0 : cli_fail(cmd, 1, "--temperature-components: a comma list of s, r, phi");
}

int cli_types_option(const cli_command *cmd, cli_types *t, int exclude, const char *arg)
{
    if (t->given)
        return cli_fail(cmd, 1, "--types and --exclude-types exclude each other");
    t->given = 1;
    t->exclude = exclude;
    return cli_parse_types(cmd, exclude ? "exclude-types" : "types", arg, t->types, 64, &t->n);
}

int cli_positive_option(const cli_command *cmd, const char *opt, const char *arg, double *v)
{
    if (cli_parse_double(arg, v) || !(*v > 0))
        return cli_fail(cmd, 1, "--%s needs a positive number, not '%s'", opt, arg);
    return 0;
}

int cli_pair_option(const cli_command *cmd, const char *opt, const char *placeholder,
                    const char *arg, double *a, double *b)
{
    if (cli_parse_pair(arg, a, b))
        return cli_fail(cmd, 1, "--%s needs %s with the first below the second, not '%s'", opt,
                        placeholder, arg);
    return 0;
}

/* ---- signals: temporary files go with the process ---- */

static void on_fatal_signal(int sig)
{
    mimas_tmpfile_remove_all();
    signal(sig, SIG_DFL);
    raise(sig);
}

static void cleanup_on_signals(void)
{
    static const int sigs[] = {SIGINT, SIGTERM, SIGHUP, SIGPIPE};
    for (size_t k = 0; k < sizeof sigs / sizeof sigs[0]; k++) {
        struct sigaction sa;
        memset(&sa, 0, sizeof sa);
        sa.sa_handler = on_fatal_signal;
        sigemptyset(&sa.sa_mask);
        struct sigaction old;
        /* a signal the caller ignores (nohup, a shell's background job) stays ignored */
        if (sigaction(sigs[k], NULL, &old) == 0 && old.sa_handler == SIG_IGN)
            continue;
        sigaction(sigs[k], &sa, NULL);
    }
}

/* ---- an output is never one of the inputs ---- */

static int same_file(const struct stat *a, const char *name)
{
    struct stat b;
    return stat(name, &b) == 0 && a->st_dev == b.st_dev && a->st_ino == b.st_ino;
}

/* The input that is the file *st (NULL if none). */
static const char *input_matching(const struct stat *st, const char *const *names, size_t n)
{
    for (size_t k = 0; k < n; k++) {
        glob_t g;
        memset(&g, 0, sizeof g);
        if (strchr(names[k], '*') && glob(names[k], 0, NULL, &g) == 0) {
            const char *hit = NULL;
            for (size_t m = 0; m < g.gl_pathc && !hit; m++)
                if (same_file(st, g.gl_pathv[m]))
                    hit = names[k];
            globfree(&g);
            if (hit)
                return hit;
        } else if (same_file(st, names[k])) {
            return names[k];
        }
    }
    return NULL;
}

int cli_refuse_input_as_output(const cli_command *cmd, const char *output, const cli_inputs *in,
                               char *const *names, int n)
{
    struct stat st;
    if (!output || !strcmp(output, "-") || stat(output, &st) != 0)
        return 0;
    const char *hit = input_matching(&st, (const char *const *)names, n > 0 ? (size_t)n : 0);
    if (!hit && in)
        hit = input_matching(&st, in->contacts, in->opt.ncontacts);
    if (!hit && in)
        hit = input_matching(&st, in->walls, in->opt.nwalls);
    if (hit)
        return cli_fail(cmd, 1, "%s: the output is also an input (%s); it would be destroyed: "
                        "choose another output name", output, hit);
    return 0;
}

#ifdef _OPENMP
/* Whether the command line asks for one thread: --threads 1 or --threads=1. */
static int one_thread(int argc, char **argv)
{
    for (int k = 1; k < argc; k++) {
        if (!strcmp(argv[k], "--threads=1") ||
            (!strcmp(argv[k], "--threads") && k + 1 < argc && !strcmp(argv[k + 1], "1")))
            return 1;
    }
    return 0;
}
#endif

void cli_start(int argc, char **argv)
{
#ifdef _OPENMP
    /* One thread: no thread of OpenMP's ever waits (every parallel region of the program
     * then has one thread), so the program need not start again, which costs as much as
     * its first start (loading its shared libraries, some 9 ms) */
    if (one_thread(argc, argv))
        omp_set_num_threads(1);
    else if (!getenv("OMP_WAIT_POLICY") && setenv("OMP_WAIT_POLICY", "passive", 1) == 0)
        execv("/proc/self/exe", argv); /* returns only if it failed: go on as we are */
#else
    (void)argc;
    (void)argv;
#endif
    H5dont_atexit();
    cleanup_on_signals();
}
