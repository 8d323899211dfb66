/* mimas info: what a data set holds. */
#include <config.h>

#include <math.h>
#include <stdio.h>
#include <string.h>

#include "commands.h"
#include "native.h"
#include "reader.h"

typedef struct range {
    size_t lo, hi;
} range;

typedef struct summary {
    size_t frames;
    mimas_frame_meta first, last;
    range np, nc, nw;
    int box_changes;
    int has_contacts, has_walls;
    char quantities[3][1024];  /* particles, contacts, wall contacts */
    mimas_tube tube;           /* of the first frame */
    int has_gas;
    size_t gas_cells[3];
    double gas_origin[3], gas_spacing[3];
} summary;

static void widen(range *r, size_t v, int first)
{
    if (first || v < r->lo)
        r->lo = v;
    if (first || v > r->hi)
        r->hi = v;
}

static void add_meta(summary *s, const mimas_frame_meta *m)
{
    int first = s->frames == 0;
    widen(&s->np, m->n_particles, first);
    widen(&s->nc, m->n_contacts, first);
    widen(&s->nw, m->n_walls, first);
    if (first)
        s->first = *m;
    else if (!mimas_box_equal(&m->box, &s->first.box))
        s->box_changes = 1;
    s->last = *m;
    s->frames++;
}

static void quantities(char *buf, size_t len, const void *tab, const mimas_table_desc *d)
{
    size_t at = 0;
    buf[0] = '\0';
    unsigned present = mimas_table_present(tab, d);
    for (size_t c = 0; c < d->ncolumns && at < len; c++)
        if (present & d->columns[c].bit)
            at += (size_t)snprintf(buf + at, len - at, " %s", d->columns[c].name);
    const size_t n_extra = *(const size_t *)((const char *)tab + d->off_n_extra);
    const mimas_extra *extra = *(mimas_extra *const *)((const char *)tab + d->off_extra);
    for (size_t e = 0; e < n_extra && at < len; e++)
        at += (size_t)snprintf(buf + at, len - at, " %s[%d]", extra[e].name, extra[e].ncomp);
}

static void note_quantities(summary *s, const mimas_frame *f)
{
    quantities(s->quantities[0], sizeof s->quantities[0], &f->particles, &mimas_particles_desc);
    quantities(s->quantities[1], sizeof s->quantities[1], &f->contacts, &mimas_contacts_desc);
    quantities(s->quantities[2], sizeof s->quantities[2], &f->walls, &mimas_walls_desc);
    s->has_contacts = f->has_contacts;
    s->has_walls = f->has_walls;
    s->tube = f->tube;
    s->has_gas = f->gas.present;
    if (f->gas.present) {
        memcpy(s->gas_cells, f->gas.cells, sizeof s->gas_cells);
        memcpy(s->gas_origin, f->gas.origin, sizeof s->gas_origin);
        memcpy(s->gas_spacing, f->gas.spacing, sizeof s->gas_spacing);
    }
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

static void print_counts(const char *label, int present, range r)
{
    if (present)
        printf("%-21s %zu .. %zu per frame\n", label, r.lo, r.hi);
    else
        printf("%-21s none\n", label);
}

static void print_summary(const summary *s, const char *format, size_t skipped)
{
    printf("%-21s %s\n", "format:", format);
    printf("%-21s %zu\n", "frames:", s->frames);
    if (skipped)
        printf("%-21s %zu (their contact data were missing)\n", "frames skipped:", skipped);
    if (s->frames == 0)
        return;
    if (isnan(s->first.time))
        printf("%-21s unknown (no ITEM: TIME; give --timestep) (steps %lld .. %lld)\n", "time:",
               (long long)s->first.step, (long long)s->last.step);
    else
        printf("%-21s %.9g .. %.9g s (steps %lld .. %lld)\n", "time:", s->first.time,
               s->last.time, (long long)s->first.step, (long long)s->last.step);
    print_counts("particles:", 1, s->np);
    print_counts("contacts:", s->has_contacts, s->nc);
    print_counts("wall contacts:", s->has_walls, s->nw);
    print_box(s->box_changes ? "box (first frame):" : "box:", &s->first.box);
    if (s->box_changes)
        print_box("box (last frame):", &s->last.box);
    printf("%-21s%s\n", "particle quantities:", s->quantities[0]);
    if (s->has_contacts)
        printf("%-21s%s\n", "contact quantities:", s->quantities[1]);
    if (s->has_walls)
        printf("%-21s%s\n", "wall quantities:", s->quantities[2]);
    const mimas_tube *t = &s->tube;
    if (t->present)
        printf("%-21s axis from (%.9g, %.9g, %.9g) m along (%.9g, %.9g, %.9g), radius %.9g m, "
               "length %.9g m\n", "tube:", t->origin[0], t->origin[1], t->origin[2],
               t->direction[0], t->direction[1], t->direction[2], t->radius, t->length);
    if (s->has_gas)
        printf("%-21s pressure porosity velocity on %zu x %zu x %zu cells of %.9g x %.9g x %.9g m "
               "from (%.9g, %.9g, %.9g) m\n", "gas fields:", s->gas_cells[0], s->gas_cells[1],
               s->gas_cells[2], s->gas_spacing[0], s->gas_spacing[1], s->gas_spacing[2],
               s->gas_origin[0], s->gas_origin[1], s->gas_origin[2]);
}

/* One native file: counts from the per-frame index, no frame data but the first. */
static int native_summary(const char *path, summary *s, char *format, size_t len,
                          mimas_error *err)
{
    mimas_native *r;
    int rc = mimas_native_open(&r, path, err);
    if (rc)
        return rc;
    snprintf(format, len, "mimas native %d (H5MD 1.1), written by %s",
             MIMAS_NATIVE_VERSION_MAJOR, mimas_native_creator(r));
    size_t nf = mimas_native_frames(r);
    mimas_frame_meta m;
    for (size_t k = 0; !rc && k < nf; k++) {
        rc = mimas_native_frame_meta(r, k, &m, err);
        if (!rc)
            add_meta(s, &m);
    }
    mimas_frame f;
    mimas_frame_init(&f);
    if (!rc && nf > 0)
        rc = mimas_native_read(r, 0, &f, err);
    if (!rc && nf > 0)
        note_quantities(s, &f);
    s->has_contacts = mimas_native_has_contacts(r);
    s->has_walls = mimas_native_has_walls(r);
    mimas_frame_free(&f);
    mimas_native_close(r);
    return rc;
}

/* Any input: every frame streamed once. */
static int stream_summary(mimas_reader *r, summary *s, mimas_error *err)
{
    mimas_frame f;
    mimas_frame_init(&f);
    int rc;
    while ((rc = mimas_reader_next(r, &f, err)) == MIMAS_OK) {
        mimas_frame_meta m = {f.step, f.time, f.box, f.particles.n, f.contacts.n, f.walls.n};
        if (s->frames == 0)
            note_quantities(s, &f);
        add_meta(s, &m);
    }
    mimas_frame_free(&f);
    return rc == MIMAS_END ? MIMAS_OK : rc;
}

static int is_single_native(const cli_inputs *in, int argc, char **argv, int first)
{
    if (argc - first != 1 || in->opt.ncontacts || in->opt.nwalls)
        return 0;
    if (in->opt.format)
        return !strcmp(in->opt.format, "native");
    FILE *fp = fopen(argv[first], "rb");
    char sig[8] = {0};
    size_t n = fp ? fread(sig, 1, 8, fp) : 0;
    if (fp)
        fclose(fp);
    return n == 8 && !memcmp(sig, "\x89HDF\r\n\x1a\n", 8);
}

static int run(const cli_command *cmd, int argc, char **argv)
{
    int first;
    cli_inputs in = {0};
    int rc = cli_parse(cmd, argc, argv, NULL, NULL, &in, &first);
    if (rc) {
        cli_inputs_free(&in);
        return rc < 0 ? 0 : rc;
    }
    if (first >= argc) {
        cli_inputs_free(&in);
        return cli_fail(cmd, 1, "no input file (see mimas info --help)");
    }
    summary s;
    memset(&s, 0, sizeof s);
    char format[160];
    size_t skipped = 0;
    mimas_error err;
    if (is_single_native(&in, argc, argv, first)) {
        rc = native_summary(argv[first], &s, format, sizeof format, &err);
    } else {
        mimas_reader *r;
        rc = cli_open_inputs(cmd, &in, argc, argv, first, &r);
        if (rc) {
            cli_inputs_free(&in);
            return rc;
        }
        snprintf(format, sizeof format, "%s", mimas_reader_format(r));
        rc = stream_summary(r, &s, &err);
        skipped = mimas_reader_skipped(r);
        mimas_reader_close(r);
    }
    cli_inputs_free(&in);
    if (rc)
        return cli_fail(cmd, mimas_exit_status(rc), "%s", err.msg);
    if (argc - first == 1)
        printf("%-21s %s\n", "file:", argv[first]);
    else
        printf("%-21s %s ... (%d files)\n", "files:", argv[first], argc - first);
    print_summary(&s, format, skipped);
    return 0;
}

const cli_command cmd_info = {
    "info",
    "describe a data set: frames, times, counts, box and quantities",
    "[options] INPUT...",
    "Prints the format, the number of frames, the time range, the particles,\n"
    "contacts and wall contacts per frame (min .. max), the box and which\n"
    "quantities the data carry.  Works on every input mimas reads; several\n"
    "inputs (a dump series) are described as one data set.",
    NULL,
    0,
    1,
    run,
    "# what a data set holds: format, frames, times, counts per frame, box, quantities\n"
    "mimas info run.h5\n"
    "\n"
    "# a LIGGGHTS run with per-atom and pair/gran/local dumps (a series as a quoted\n"
    "# pattern); the contact columns are the keywords its compute pair/gran/local was given\n"
    "K=pos,vel,id,force,force_normal,force_tangential,torque,torque_normal,torque_tangential,history,contactArea,delta,contactPoint\n"
    "mimas info 'dump.*.atom.gz' --contacts 'dump.*.pgl.gz' --contact-columns $K",
};
