#include <config.h>

#include "plot.h"
#include "outfile.h"
#include "tmpfiles.h"

#include <errno.h>
#include <fcntl.h>
#include <spawn.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

extern char **environ;

#define MAX_DATA 16

struct mimas_plot {
    char dir[4096];
    char png[4096], tmp[4200];
    char names[MAX_DATA][64];
    FILE *data[MAX_DATA];
    int ndata;
    int slot;   /* tmp in the temporary-file registry (src/tmpfiles.h) */
};

void mimas_plot_quote(const char *s, char *buf, size_t len)
{
    size_t k = 0;
    if (len < 3) {
        if (len)
            buf[0] = '\0';
        return;
    }
    buf[k++] = '\'';
    for (; *s && k + 3 < len; s++) {
        if (*s == '\'')
            buf[k++] = '\'';
        buf[k++] = *s;
    }
    buf[k++] = '\'';
    buf[k] = '\0';
}

static void path_in(const mimas_plot *p, const char *name, char *buf, size_t len)
{
    snprintf(buf, len, "%s/%s", p->dir, name);
}

int mimas_plot_open(mimas_plot **out, const char *png, mimas_error *err)
{
    *out = NULL;
    if (mimas_output_check(png, err))
        return err->code;
    mimas_plot *p = calloc(1, sizeof *p);
    if (!p)
        return mimas_error_set(err, MIMAS_EIO, "out of memory for the plot");
    const char *tmpdir = getenv("TMPDIR");
    snprintf(p->dir, sizeof p->dir, "%s/mimas-plot-XXXXXX", tmpdir && *tmpdir ? tmpdir : "/tmp");
    if (!mkdtemp(p->dir)) {
        int e = errno;
        free(p);
        return mimas_error_set(err, MIMAS_EIO, "cannot make a scratch folder for the plot: %s",
                               strerror(e));
    }
    snprintf(p->png, sizeof p->png, "%s", png);
    snprintf(p->tmp, sizeof p->tmp, "%s.tmp%ld.png", png, (long)getpid());
    p->slot = mimas_tmpfile_add(p->tmp);
    *out = p;
    return MIMAS_OK;
}

FILE *mimas_plot_data(mimas_plot *p, const char *name, mimas_error *err)
{
    if (p->ndata >= MAX_DATA || strchr(name, '/') || strlen(name) >= sizeof p->names[0]) {
        mimas_error_set(err, MIMAS_EUSAGE, "bad plot data file name '%s'", name);
        return NULL;
    }
    char path[4200];
    path_in(p, name, path, sizeof path);
    FILE *fp = fopen(path, "w");
    if (!fp) {
        mimas_error_set(err, MIMAS_EIO, "%s: cannot write: %s", path, strerror(errno));
        return NULL;
    }
    snprintf(p->names[p->ndata], sizeof p->names[0], "%s", name);
    p->data[p->ndata++] = fp;
    return fp;
}

/* Closes the data files; 0 if all were written. */
static int close_data(mimas_plot *p)
{
    int bad = 0;
    for (int k = 0; k < p->ndata; k++)
        if (p->data[k]) {
            bad |= ferror(p->data[k]) != 0;
            bad |= fclose(p->data[k]) != 0;
            p->data[k] = NULL;
        }
    return bad;
}

/* Removes the data files, the script, the log and the folder. */
static void clear_scratch(mimas_plot *p)
{
    close_data(p);
    char path[4200];
    for (int k = 0; k < p->ndata; k++) {
        path_in(p, p->names[k], path, sizeof path);
        remove(path);
    }
    const char *own[] = {"plot.gp", "gnuplot.log"};
    for (int k = 0; k < 2; k++) {
        path_in(p, own[k], path, sizeof path);
        remove(path);
    }
    rmdir(p->dir);
}

void mimas_plot_abort(mimas_plot *p)
{
    if (!p)
        return;
    clear_scratch(p);
    remove(p->tmp);
    mimas_tmpfile_forget(p->slot);
    free(p);
}

int mimas_plot_commit(mimas_plot *p, mimas_error *err)
{
    int rc = MIMAS_OK;
    if (rename(p->tmp, p->png) != 0)
        rc = mimas_error_set(err, MIMAS_EIO, "%s: cannot write: %s", p->png, strerror(errno));
    mimas_plot_abort(p);
    return rc;
}

/* The last non-empty line of gnuplot's messages. */
static void last_message(const mimas_plot *p, char *buf, size_t len)
{
    char path[4200], line[512];
    path_in(p, "gnuplot.log", path, sizeof path);
    buf[0] = '\0';
    FILE *fp = fopen(path, "r");
    if (!fp)
        return;
    while (fgets(line, sizeof line, fp)) {
        line[strcspn(line, "\r\n")] = '\0';
        if (line[strspn(line, " \t^")])
            snprintf(buf, len, "%s", line + strspn(line, " \t"));
    }
    fclose(fp);
}

/* gnuplot SCRIPT with standard output and error into the log; returns 0,
 * ENOENT when there is no gnuplot, or -1 when it failed. */
static int run_gnuplot(const mimas_plot *p, const char *script)
{
    char log[4200];
    path_in(p, "gnuplot.log", log, sizeof log);
    posix_spawn_file_actions_t fa;
    posix_spawn_file_actions_init(&fa);
    posix_spawn_file_actions_addopen(&fa, STDIN_FILENO, "/dev/null", O_RDONLY, 0);
    posix_spawn_file_actions_addopen(&fa, STDOUT_FILENO, log, O_WRONLY | O_CREAT | O_TRUNC,
                                     0600);
    posix_spawn_file_actions_adddup2(&fa, STDOUT_FILENO, STDERR_FILENO);
    char *argv[] = {"gnuplot", (char *)script, NULL};
    pid_t pid;
    int rc = posix_spawnp(&pid, "gnuplot", &fa, NULL, argv, environ);
    posix_spawn_file_actions_destroy(&fa);
    if (rc)
        return rc == ENOENT ? ENOENT : -1;
    int status;
    while (waitpid(pid, &status, 0) < 0)
        if (errno != EINTR)
            return -1;
    if (WIFEXITED(status) && WEXITSTATUS(status) == 127)
        return ENOENT;
    return WIFEXITED(status) && WEXITSTATUS(status) == 0 ? 0 : -1;
}

int mimas_plot_render(mimas_plot *p, int width, int height, const char *script, mimas_error *err)
{
    char gp[4200], q_out[8500], q_dir[8200];
    int rc = MIMAS_OK;
    if (close_data(p))
        rc = mimas_error_set(err, MIMAS_EIO, "%s: cannot write the plot data", p->png);
    path_in(p, "plot.gp", gp, sizeof gp);
    FILE *fp = rc ? NULL : fopen(gp, "w");
    if (!rc && !fp)
        rc = mimas_error_set(err, MIMAS_EIO, "%s: cannot write the plot script", p->png);
    if (fp) {
        mimas_plot_quote(p->tmp, q_out, sizeof q_out);
        mimas_plot_quote(p->dir, q_dir, sizeof q_dir);
        fprintf(fp, "set terminal pngcairo size %d,%d noenhanced font ',10'\n"
                    "set output %s\ndatadir = %s\n%s\nunset output\n",
                width, height, q_out, q_dir, script);
        if (fclose(fp) != 0)
            rc = mimas_error_set(err, MIMAS_EIO, "%s: cannot write the plot script", p->png);
    }
    if (!rc) {
        int g = run_gnuplot(p, gp);
        char msg[400];
        last_message(p, msg, sizeof msg);
        struct stat st;
        if (g == ENOENT)
            rc = mimas_error_set(err, MIMAS_EIO, "%s: gnuplot is not installed (or not on PATH); "
                                 "the plot needs it (Debian: gnuplot-nox)", p->png);
        else if (g || stat(p->tmp, &st) != 0 || st.st_size == 0)
            rc = mimas_error_set(err, MIMAS_EIO, "%s: gnuplot failed%s%s", p->png,
                                 msg[0] ? ": " : "", msg);
    }
    clear_scratch(p);
    return rc;
}
