#include <config.h>

#include "cli.h"

#include <errno.h>
#include <getopt.h>
#include <math.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>

#define MAX_OPTIONS 64

int cli_fail(const cli_command *cmd, int status, const char *fmt, ...)
{
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
    for (size_t k = 0; k <= cmd->noptions; k++) {
        const cli_option *o = k < cmd->noptions ? &cmd->options[k]
                                                : &(cli_option){"help", 'h', NULL,
                                                                "print this help and exit"};
        char left[64];
        int w = o->short_name ? snprintf(left, sizeof left, "-%c, --%s", o->short_name, o->name)
                              : snprintf(left, sizeof left, "    --%s", o->name);
        if (o->arg)
            snprintf(left + w, sizeof left - (size_t)w, " %s", o->arg);
        fprintf(out, "  %-28s %s\n", left, o->help);
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
    for (size_t k = 0; k < cmd->noptions; k++) {
        const cli_option *o = &cmd->options[k];
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
    fprintf(out, ".SH EXIT STATUS\n0 on success, 1 on bad usage, 2 on bad input data, with a "
                 "one\\-line message naming the file and the problem.\n"
                 ".SH SEE ALSO\n.BR mimas (1)\n");
}

int cli_parse(const cli_command *cmd, int argc, char **argv, cli_handler handler, void *ctx,
              int *first)
{
    struct option longopts[MAX_OPTIONS + 2];
    char shortopts[3 * MAX_OPTIONS + 8];
    size_t ns = 0;
    if (cmd->noptions > MAX_OPTIONS)
        return cli_fail(cmd, 1, "too many options declared");
    shortopts[ns++] = ':';  /* report missing arguments distinctly */
    for (size_t k = 0; k < cmd->noptions; k++) {
        const cli_option *o = &cmd->options[k];
        longopts[k] = (struct option){o->name, o->arg ? required_argument : no_argument, NULL,
                                      256 + (int)k};
        if (o->short_name) {
            shortopts[ns++] = o->short_name;
            if (o->arg)
                shortopts[ns++] = ':';
        }
    }
    longopts[cmd->noptions] = (struct option){"help", no_argument, NULL, 'h'};
    longopts[cmd->noptions + 1] = (struct option){NULL, 0, NULL, 0};
    shortopts[ns++] = 'h';
    shortopts[ns] = '\0';

    optind = 1;
    opterr = 0;
    for (;;) {
        int longindex = -1;
        int c = getopt_long(argc, argv, shortopts, longopts, &longindex);
        if (c == -1)
            break;
        if (c == 'h') {
            cli_print_help(cmd, stdout);
            return -1;
        }
        if (c == '?')
            return cli_fail(cmd, 1, "unknown option '%s' (see mimas %s --help)",
                            argv[optind - 1], cmd->name);
        if (c == ':')
            return cli_fail(cmd, 1, "option '%s' needs an argument", argv[optind - 1]);
        size_t opt = cmd->noptions;
        if (c >= 256)
            opt = (size_t)(c - 256);
        else
            for (size_t k = 0; k < cmd->noptions; k++)
                if (cmd->options[k].short_name == c)
                    opt = k;
        if (opt >= cmd->noptions)
            return cli_fail(cmd, 1, "unknown option (see mimas %s --help)", cmd->name);
        int rc = handler ? handler(ctx, opt, optarg) : 0;
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
