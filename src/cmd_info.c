/* mimas info: what a data file holds. */
#include <config.h>

#include <stdio.h>
#include <string.h>

#include "commands.h"
#include "native.h"

static const cli_option options[] = {
    {"quiet", 'q', NULL, "accepted for uniformity; info prints no progress"},
};

typedef struct range {
    size_t lo, hi;
} range;

static void widen(range *r, size_t v, int first)
{
    if (first || v < r->lo)
        r->lo = v;
    if (first || v > r->hi)
        r->hi = v;
}

static void print_quantities(const char *label, const void *tab, const mimas_table_desc *d)
{
    printf("%-21s", label);
    unsigned present = mimas_table_present(tab, d);
    for (size_t c = 0; c < d->ncolumns; c++)
        if (present & d->columns[c].bit)
            printf(" %s", d->columns[c].name);
    const size_t n_extra = *(const size_t *)((const char *)tab + d->off_n_extra);
    const mimas_extra *extra = *(mimas_extra *const *)((const char *)tab + d->off_extra);
    for (size_t e = 0; e < n_extra; e++)
        printf(" %s[%d]", extra[e].name, extra[e].ncomp);
    printf("\n");
}

static void print_box(const char *label, const mimas_box *b)
{
    static const char axis[3] = {'x', 'y', 'z'};
    printf("%-21s [%.9g, %.9g] x [%.9g, %.9g] x [%.9g, %.9g] m", label, b->lo[0], b->hi[0],
           b->lo[1], b->hi[1], b->lo[2], b->hi[2]);
    if (mimas_box_is_triclinic(b))
        printf(", tilt xy %.9g xz %.9g yz %.9g", b->xy, b->xz, b->yz);
    printf(", volume %.9g m3, periodic:", mimas_box_volume(b));
    int any = 0;
    for (int d = 0; d < 3; d++)
        if (b->periodic[d]) {
            printf(" %c", axis[d]);
            any = 1;
        }
    printf("%s\n", any ? "" : " none");
}

static int info_file(const cli_command *cmd, const char *path)
{
    mimas_error err;
    mimas_native *r;
    int rc = mimas_native_open(&r, path, &err);
    if (rc)
        return cli_fail(cmd, mimas_exit_status(rc), "%s", err.msg);
    size_t nf = mimas_native_frames(r);
    range np = {0, 0}, nc = {0, 0}, nw = {0, 0};
    mimas_frame_meta first, last, m;
    memset(&first, 0, sizeof first);
    memset(&last, 0, sizeof last);
    int box_changes = 0;
    for (size_t k = 0; !rc && k < nf; k++) {
        rc = mimas_native_frame_meta(r, k, &m, &err);
        if (rc)
            break;
        widen(&np, m.n_particles, k == 0);
        widen(&nc, m.n_contacts, k == 0);
        widen(&nw, m.n_walls, k == 0);
        if (k == 0)
            first = m;
        else if (memcmp(&m.box, &first.box, sizeof m.box) != 0)
            box_changes = 1;
        last = m;
    }
    mimas_frame f;
    mimas_frame_init(&f);
    if (!rc && nf > 0)
        rc = mimas_native_read(r, 0, &f, &err);
    if (rc) {
        mimas_frame_free(&f);
        mimas_native_close(r);
        return cli_fail(cmd, mimas_exit_status(rc), "%s", err.msg);
    }
    printf("%-21s %s\n", "file:", path);
    printf("%-21s mimas native %d (H5MD 1.1), written by %s\n", "format:",
           MIMAS_NATIVE_VERSION_MAJOR, mimas_native_creator(r));
    printf("%-21s %zu\n", "frames:", nf);
    if (nf > 0) {
        printf("%-21s %.9g .. %.9g s (steps %lld .. %lld)\n", "time:", first.time, last.time,
               (long long)first.step, (long long)last.step);
        printf("%-21s %zu .. %zu per frame\n", "particles:", np.lo, np.hi);
        if (mimas_native_has_contacts(r))
            printf("%-21s %zu .. %zu per frame\n", "contacts:", nc.lo, nc.hi);
        else
            printf("%-21s none\n", "contacts:");
        if (mimas_native_has_walls(r))
            printf("%-21s %zu .. %zu per frame\n", "wall contacts:", nw.lo, nw.hi);
        else
            printf("%-21s none\n", "wall contacts:");
        print_box(box_changes ? "box (first frame):" : "box:", &first.box);
        if (box_changes)
            print_box("box (last frame):", &last.box);
        print_quantities("particle quantities:", &f.particles, &mimas_particles_desc);
        if (mimas_native_has_contacts(r))
            print_quantities("contact quantities:", &f.contacts, &mimas_contacts_desc);
        if (mimas_native_has_walls(r))
            print_quantities("wall quantities:", &f.walls, &mimas_walls_desc);
    }
    mimas_frame_free(&f);
    mimas_native_close(r);
    return 0;
}

static int run(const cli_command *cmd, int argc, char **argv)
{
    int first;
    int rc = cli_parse(cmd, argc, argv, NULL, NULL, &first);
    if (rc)
        return rc < 0 ? 0 : rc;
    if (first >= argc)
        return cli_fail(cmd, 1, "no input file (see mimas info --help)");
    for (int k = first; k < argc; k++) {
        if (k > first)
            printf("\n");
        rc = info_file(cmd, argv[k]);
        if (rc)
            return rc;
    }
    return 0;
}

const cli_command cmd_info = {
    "info",
    "describe a data file: frames, times, counts, box and quantities",
    "[options] FILE...",
    "Prints the format, the number of frames, the time range, the particles,\n"
    "contacts and wall contacts per frame (min .. max), the box and which\n"
    "quantities the file carries.",
    options,
    sizeof options / sizeof options[0],
    run,
};
