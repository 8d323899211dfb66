/* MercuryDPM output as a stream backend: particles from .data files, contacts
 * and wall contacts from .fstat files, matched by time.  The formats and the
 * sign conventions, with the MercuryDPM source they were verified against,
 * are in docs/readers-mercury.md.
 *
 * Both inputs are streams read one line at a time: all .data files one after
 * another, all .fstat files one after another.  At any moment the state holds
 * the header of the next .data time step and the opening line of the next
 * .fstat time step ("pending"); the rows go straight into the caller's frame,
 * so memory does not grow with the number of time steps. */
#include <config.h>

#include <math.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "backend.h"
#include "numparse.h"
#include "text_input.h"

/* A header announcing more particles is not a MercuryDPM file. */
#define MAX_PARTICLES 1000000000LL
/* Two times match when they differ by at most this fraction (see match()). */
#define TIME_RTOL 1e-6
/* The two rows of one particle pair must agree to this relative precision. */
#define DUP_RTOL 1e-6
/* |n| (and |t| when ft > 0) must be 1 within this. */
#define UNIT_TOL 1e-3

enum {
    HEADER_2D = 6,  /* N t xmin ymin xmax ymax */
    HEADER_3D = 8,  /* N t xmin ymin zmin xmax ymax zmax */
    ROW_2D = 8,     /* x y vx vy r theta -omega_z info */
    ROW_3D = 14,    /* x y z vx vy vz r theta(3) omega(3) info */
    FSTAT_ROW = 16  /* t i j cx cy cz delta delta_t fn ft nx ny nz tx ty tz */
};

static const double PI = 3.14159265358979323846;

static const unsigned CONTACT_BITS = MIMAS_C_I | MIMAS_C_J | MIMAS_C_POINT | MIMAS_C_FORCE |
                                     MIMAS_C_FORCE_N | MIMAS_C_FORCE_T | MIMAS_C_OVERLAP;
static const unsigned WALL_BITS = MIMAS_W_PARTICLE | MIMAS_W_WALL | MIMAS_W_POINT |
                                  MIMAS_W_FORCE | MIMAS_W_FORCE_N | MIMAS_W_FORCE_T |
                                  MIMAS_W_OVERLAP;

/* A list of files read as one stream. */
typedef struct merc_files {
    char **names;
    size_t n, next;   /* next: index of the file to open next */
    text_input in;    /* the current file, when open */
    int open;
    int got_any;      /* the current file had a non-blank line */
    const char *path; /* name of the current (or last) file */
} merc_files;

/* One particle-pair row, for finding the two rows of a pair. */
typedef struct pair_key {
    size_t lo, hi, row;
} pair_key;

typedef struct merc_state {
    merc_files data, fstat;
    double density;
    int with_contacts, allow_missing;
    size_t skipped;
    int64_t step;        /* 0-based position of the next time step in the .data stream */

    /* the header of the next .data time step */
    int hdr_pending;     /* read (by open) but not yet used */
    int file_dim;        /* 2 or 3: the first header of the current .data file */
    int dim;
    long long hdr_n;
    double hdr_t;
    long hdr_line;
    mimas_box hdr_box;

    /* the opening line "# t marker" of the next .fstat time step */
    int have_block;
    double block_t;
    int block_marker;    /* 0: point column is a centre; 1: the contact point */

    /* per pair row of the current block: its line and the normal as written */
    long *row_line;
    double (*row_n)[3];
    unsigned char *drop;
    pair_key *keys, *sorted;  /* the pair keys, and room to sort them into */
    size_t row_cap;
    size_t *bucket;            /* the counting sort's start of each particle's keys */
    size_t bucket_cap;
} merc_state;

/* ---- small helpers ---------------------------------------------------------- */

/* "PATH:LINE: message" for a line other than the one last read. */
static int error_at(mimas_error *err, const char *path, long line, const char *fmt, ...)
    __attribute__((format(printf, 4, 5)));

static int error_at(mimas_error *err, const char *path, long line, const char *fmt, ...)
{
    char msg[MIMAS_ERROR_MSG_MAX];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    return mimas_error_set(err, MIMAS_EDATA, "%s:%ld: %s", path, line, msg);
}

/* Separators between values ('\r' too: skip_token stops at one without
 * passing it, so it must be skipped here). */
static const char SEPARATORS[] = " \t\r\v\f";

/* p past the SEPARATORS (strspn's work, without its set-up for each of the numbers) */
static inline char *skip_separators(char *p)
{
    while (*p == ' ' || *p == '\t' || *p == '\r' || *p == '\v' || *p == '\f')
        p++;
    return p;
}

/* The token at p for a message: at most 40 characters, unprintable bytes as '?'. */
static const char *quote_token(const char *p, char buf[41])
{
    size_t k = 0;
    for (; k < 40 && p[k] && !strchr(SEPARATORS, p[k]); k++)
        buf[k] = (unsigned char)p[k] < 0x20 || (unsigned char)p[k] >= 0x7f ? '?' : p[k];
    buf[k] = '\0';
    return buf;
}

/* Parses the whitespace-separated numbers at p into v (at most cap of them)
 * and returns how many tokens the line has, or -1 with *bad pointing at the
 * first token (within the first cap) that is not a finite number.  in_line: p
 * lies in a line from text_line (read ahead on its padding). */
static int split_numbers(char *p, double *v, int cap, char **bad, int in_line)
{
    int count = 0;
    for (;;) {
        p = skip_separators(p);
        if (*p == '\0')
            return count;
        if (count < cap) {
            if ((in_line ? parse_double_in_line(&p, &v[count]) : parse_double(&p, &v[count])) !=
                0) {
                *bad = p;
                return -1;
            }
        } else {
            skip_token(&p);
        }
        count++;
    }
}

static int bad_number(const text_input *in, mimas_error *err, const char *line, const char *bad)
{
    int index = 1;
    for (const char *p = line; p < bad; p++)
        if ((p == line || strchr(SEPARATORS, p[-1])) && !strchr(SEPARATORS, *p))
            index++;
    char q[41];
    return text_error(in, err, "value %d ('%s') is not a finite number", index,
                      quote_token(bad, q));
}

static int is_integral(double x)
{
    return x == floor(x);
}

static double norm3(const double a[3])
{
    return sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
}

static int grow_array(void **p, size_t n, size_t size)
{
    void *q = realloc(*p, n * size);
    if (!q)
        return -1;
    *p = q;
    return 0;
}

/* ---- file lists --------------------------------------------------------------- */

/* Closes the current file and opens the next one; MIMAS_END when none is left. */
static int files_advance(merc_files *fs, mimas_error *err)
{
    if (fs->open) {
        text_close(&fs->in);
        fs->open = 0;
    }
    if (fs->next >= fs->n)
        return MIMAS_END;
    int rc = text_open(&fs->in, fs->names[fs->next], err);
    if (rc)
        return rc;
    fs->path = fs->names[fs->next++];
    fs->open = 1;
    fs->got_any = 0;
    return MIMAS_OK;
}

/* The next line of the current file that is not blank; NULL at its end
 * (*rc MIMAS_OK) or on an error. */
static char *next_line(merc_files *fs, int *rc, mimas_error *err)
{
    *rc = MIMAS_OK;
    if (!fs->open)
        return NULL;
    for (;;) {
        size_t len;
        char *line = text_line(&fs->in, &len, rc, err);
        if (!line)
            return NULL;
        if (line[strspn(line, SEPARATORS)] != '\0') {
            fs->got_any = 1;
            return line;
        }
    }
}

static int empty_file(const merc_files *fs, mimas_error *err, const char *what)
{
    return error_at(err, fs->path, 1, "empty file: no %s", what);
}

/* ---- .data -------------------------------------------------------------------- */

/* Parses a time-step header "N t xmin ymin [zmin] xmax ymax [zmax]". */
static int parse_header(merc_state *s, char *line, mimas_error *err)
{
    const text_input *in = &s->data.in;
    double v[ROW_3D];
    char *bad, *p = line;
    int k = split_numbers(line, v, ROW_3D, &bad, 1);
    if (k < 0)
        return bad_number(in, err, line, bad);
    int dim = k == HEADER_3D ? 3 : k == HEADER_2D ? 2 : 0;
    if (!dim) {
        int row = s->file_dim == 3 ? ROW_3D : s->file_dim == 2 ? ROW_2D : -1;
        return text_error(in, err, "a time-step header has 8 values (3-D: N t xmin ymin zmin "
                          "xmax ymax zmax) or 6 (2-D: N t xmin ymin xmax ymax); this line has "
                          "%d%s", k,
                          k == row ? " (more particle rows than the header announced?)" : "");
    }
    int64_t n;
    char q[41];
    if (parse_int64(&p, &n) != 0)
        return text_error(in, err, "'%s' is not a particle count (the first value of a "
                          "time-step header)", quote_token(line + strspn(line, " \t"), q));
    if (n < 0)
        return text_error(in, err, "negative particle count %lld in a time-step header",
                          (long long)n);
    if (n > MAX_PARTICLES)
        return text_error(in, err, "particle count %lld is absurd (more than %lld): not a "
                          "MercuryDPM time-step header", (long long)n, MAX_PARTICLES);
    if (s->file_dim && dim != s->file_dim)
        return text_error(in, err, "%d-D time-step header in a file whose first time step is "
                          "%d-D", dim, s->file_dim);
    mimas_box b;
    memset(&b, 0, sizeof b);
    for (int a = 0; a < dim; a++) {
        b.lo[a] = v[2 + a];
        b.hi[a] = v[2 + dim + a];
        if (b.lo[a] > b.hi[a])
            return text_error(in, err, "box minimum %.10g exceeds maximum %.10g in %c", b.lo[a],
                              b.hi[a], "xyz"[a]);
    }
    s->file_dim = s->dim = dim;
    s->hdr_n = n;
    s->hdr_t = v[1];
    s->hdr_line = in->line;
    s->hdr_box = b; /* not periodic: .data files do not record periodicity */
    return MIMAS_OK;
}

/* Reads the next time-step header, opening further .data files as needed;
 * MIMAS_END after the last one. */
static int data_header(merc_state *s, mimas_error *err)
{
    if (s->hdr_pending) {
        s->hdr_pending = 0;
        return MIMAS_OK;
    }
    for (;;) {
        int rc;
        char *line = next_line(&s->data, &rc, err);
        if (line)
            return parse_header(s, line, err);
        if (rc)
            return rc;
        if (s->data.open && !s->data.got_any)
            return empty_file(&s->data, err, "MercuryDPM time step");
        rc = files_advance(&s->data, err);
        if (rc)
            return rc;
        s->file_dim = 0;
    }
}

static int prepare_particles(mimas_frame *f, unsigned bits, mimas_error *err)
{
    mimas_table_keep_only(&f->particles, &mimas_particles_desc, bits);
    mimas_table_drop_extras(&f->particles, &mimas_particles_desc);
    int rc = mimas_table_set_present(&f->particles, &mimas_particles_desc, bits, err);
    if (!rc)
        rc = mimas_table_resize(&f->particles, &mimas_particles_desc, 0, err);
    return rc;
}

/* Stores one particle row (values v as written) as particle k. */
static int store_particle(merc_state *s, mimas_frame *f, size_t k, const double *v,
                          mimas_error *err)
{
    mimas_particles *p = &f->particles;
    int rc = mimas_table_resize(p, &mimas_particles_desc, k + 1, err);
    if (rc)
        return rc;
    double r, info;
    if (s->dim == 3) {
        for (int a = 0; a < 3; a++) {
            p->pos[k][a] = v[a];
            p->vel[k][a] = v[3 + a];
            p->omega[k][a] = v[10 + a]; /* v[7..9] are orientation angles, not kept */
        }
        r = v[6];
        info = v[13];
    } else {
        p->pos[k][0] = v[0];
        p->pos[k][1] = v[1];
        p->pos[k][2] = 0.0;
        p->vel[k][0] = v[2];
        p->vel[k][1] = v[3];
        p->vel[k][2] = 0.0;
        /* MercuryDPM writes -omega_z in 2-D (xballs plots x-y as x-z) and
         * negates it again when it reads the file back */
        p->omega[k][0] = p->omega[k][1] = 0.0;
        p->omega[k][2] = -v[6];
        r = v[4];
        info = v[7];
    }
    if (r < 0)
        return text_error(&s->data.in, err, "negative radius %.10g", r);
    if (!is_integral(info) || fabs(info) > INT32_MAX)
        return text_error(&s->data.in, err, "the last column (info) is %.10g, not a species "
                          "index (an integer)", info);
    p->id[k] = (int64_t)k; /* .data files have no ids: the row index is the id */
    p->type[k] = (int32_t)info;
    p->radius[k] = r;
    if (p->mass)
        p->mass[k] = s->density * 4.0 / 3.0 * PI * r * r * r; /* a sphere also in 2-D */
    return MIMAS_OK;
}

/* Reads the hdr_n particle rows of the current time step into f. */
static int read_particles(merc_state *s, mimas_frame *f, mimas_error *err)
{
    unsigned bits = MIMAS_P_ID | MIMAS_P_TYPE | MIMAS_P_RADIUS | MIMAS_P_POS | MIMAS_P_VEL |
                    MIMAS_P_OMEGA | (s->density > 0 ? MIMAS_P_MASS : 0u);
    int rc = prepare_particles(f, bits, err);
    if (rc)
        return rc;
    int width = s->dim == 3 ? ROW_3D : ROW_2D;
    for (size_t k = 0; k < (size_t)s->hdr_n; k++) {
        char *line = next_line(&s->data, &rc, err);
        if (!line)
            return rc ? rc
                      : text_error(&s->data.in, err, "truncated: the time step at line %ld "
                                   "(t = %.10g) announces %lld particles but the file ends "
                                   "after %zu", s->hdr_line, s->hdr_t, s->hdr_n, k);
        double v[ROW_3D];
        char *bad;
        int count = split_numbers(line, v, width, &bad, 1);
        if (count < 0)
            return bad_number(&s->data.in, err, line, bad);
        if (count != width)
            return text_error(&s->data.in, err, "particle row %zu of %lld has %d values; a "
                              "%d-D .data row has %d (%s)", k + 1, s->hdr_n, count, s->dim,
                              width, s->dim == 3 ? "x y z vx vy vz r theta_x theta_y theta_z "
                              "omega_x omega_y omega_z info" : "x y vx vy r theta omega info");
        rc = store_particle(s, f, k, v, err);
        if (rc)
            return rc;
    }
    f->step = s->step;
    f->time = s->hdr_t;
    f->box = s->hdr_box;
    return MIMAS_OK;
}

/* ---- .fstat ------------------------------------------------------------------- */

/* Sets *opening to 1 if line is "# t marker" (the first of the three header
 * lines MercuryDPM writes per time step, stored as the pending block), to 0
 * for another '#' line. */
static int opening_line(merc_state *s, char *line, int *opening, mimas_error *err)
{
    double v[2];
    char *bad;
    *opening = 0;
    if (split_numbers(line + 1, v, 2, &bad, 1) != 2)
        return MIMAS_OK; /* the box line and the radii line have 6 values (radii may be nan) */
    if (v[1] != 0.0 && v[1] != 1.0)
        return text_error(&s->fstat.in, err, "time-step line '# t marker' has marker %.10g; "
                          "MercuryDPM writes 0 (point column is a centre) or 1 (contact point)",
                          v[1]);
    *opening = 1;
    s->block_t = v[0];
    s->block_marker = (int)v[1];
    return MIMAS_OK;
}

/* Reads up to the opening line of the next .fstat time step, opening further
 * files as needed; have_block is 0 when there is none. */
static int fstat_next_block(merc_state *s, mimas_error *err)
{
    s->have_block = 0;
    for (;;) {
        int rc;
        char *line = next_line(&s->fstat, &rc, err);
        if (line) {
            int opening = 0;
            rc = line[0] == '#' ? opening_line(s, line, &opening, err) : MIMAS_OK;
            if (rc)
                return rc;
            if (!opening)
                return text_error(&s->fstat.in, err, "expected the line '# t marker' that "
                                  "opens a .fstat time step");
            s->have_block = 1;
            return MIMAS_OK;
        }
        if (rc)
            return rc;
        if (s->fstat.open && !s->fstat.got_any)
            return empty_file(&s->fstat, err, ".fstat time step");
        rc = files_advance(&s->fstat, err);
        if (rc == MIMAS_END)
            return MIMAS_OK;
        if (rc)
            return rc;
    }
}

static int reserve_rows(merc_state *s, size_t n, mimas_error *err)
{
    if (n <= s->row_cap)
        return MIMAS_OK;
    size_t cap = s->row_cap ? s->row_cap : 64;
    while (cap < n)
        cap += cap / 2;
    if (grow_array((void **)&s->row_line, cap, sizeof *s->row_line) ||
        grow_array((void **)&s->row_n, cap, sizeof *s->row_n) ||
        grow_array((void **)&s->drop, cap, sizeof *s->drop) ||
        grow_array((void **)&s->keys, cap, sizeof *s->keys) ||
        grow_array((void **)&s->sorted, cap, sizeof *s->sorted))
        return mimas_error_set(err, MIMAS_EIO, "out of memory for the MercuryDPM reader");
    s->row_cap = cap;
    return MIMAS_OK;
}

/* The particle index in column col of a contact row. */
static int row_index(merc_state *s, const mimas_frame *f, double x, const char *col,
                     size_t *index, mimas_error *err)
{
    if (!is_integral(x) || x < 0)
        return text_error(&s->fstat.in, err, "%s '%.10g' is not a particle index", col, x);
    if (x >= (double)f->particles.n)
        return text_error(&s->fstat.in, err, "%s %.0f names a particle the time step does not "
                          "have (it has %zu, indices 0 to %zu; %s:%ld)", col, x, f->particles.n,
                          f->particles.n ? f->particles.n - 1 : 0, s->data.path, s->hdr_line);
    *index = (size_t)x;
    return MIMAS_OK;
}

/* A particle-wall row: j = -1 - wall index.  MercuryDPM writes the normal and
 * tangential directions of wall rows flipped (n points from the particle into
 * the wall), so the force on the particle is -(fn n + ft t). */
static int add_wall_row(merc_state *s, mimas_frame *f, size_t i, double j, const double *v,
                        mimas_error *err)
{
    if (!is_integral(j) || -j - 1 > INT32_MAX)
        return text_error(&s->fstat.in, err, "wall index '%.10g' is not -1 - wall id", j);
    mimas_wall_contacts *w = &f->walls;
    size_t k = w->n;
    int rc = mimas_table_resize(w, &mimas_walls_desc, k + 1, err);
    if (rc)
        return rc;
    const double *n = v + 10, *t = v + 13;
    w->particle[k] = i;
    w->wall[k] = (int32_t)(-j - 1);
    w->overlap[k] = v[6];
    for (int a = 0; a < 3; a++) {
        w->force_n[k][a] = -v[8] * n[a];
        w->force_t[k][a] = -v[9] * t[a];
        w->force[k][a] = w->force_n[k][a] + w->force_t[k][a];
        /* marker 0: the point column is r - (R - delta) n_in (on the wall
         * surface); the contact point is r - (R - delta/2) n_in, n_in = -n */
        w->point[k][a] = s->block_marker ? v[3 + a]
                                         : f->particles.pos[i][a] +
                                               (f->particles.radius[i] - 0.5 * v[6]) * n[a];
    }
    return MIMAS_OK;
}

/* A particle-pair row "i j ...": n points from j to i and the force on i
 * exerted by j is fn n + ft t (the same holds for the mirrored row). */
static int add_pair_row(merc_state *s, mimas_frame *f, size_t i, size_t j, const double *v,
                        mimas_error *err)
{
    if (i == j)
        return text_error(&s->fstat.in, err, "contact of particle %zu with itself", i);
    mimas_contacts *c = &f->contacts;
    size_t k = c->n;
    int rc = mimas_table_resize(c, &mimas_contacts_desc, k + 1, err);
    if (!rc)
        rc = reserve_rows(s, k + 1, err);
    if (rc)
        return rc;
    c->i[k] = i;
    c->j[k] = j;
    c->overlap[k] = v[6];
    for (int a = 0; a < 3; a++) {
        c->point[k][a] = v[3 + a];
        c->force_n[k][a] = v[8] * v[10 + a];
        c->force_t[k][a] = v[9] * v[13 + a];
        c->force[k][a] = c->force_n[k][a] + c->force_t[k][a];
        s->row_n[k][a] = v[10 + a];
    }
    s->row_line[k] = s->fstat.in.line;
    return MIMAS_OK;
}

/* Parses a contact row; with f NULL (a skipped time step) only its form is checked. */
static int contact_row(merc_state *s, mimas_frame *f, char *line, mimas_error *err)
{
    double v[FSTAT_ROW];
    char *bad;
    int count = split_numbers(line, v, FSTAT_ROW, &bad, 1);
    if (count < 0)
        return bad_number(&s->fstat.in, err, line, bad);
    if (count != FSTAT_ROW)
        return text_error(&s->fstat.in, err, "contact row has %d values; a .fstat row has 16 "
                          "(t i j cx cy cz delta delta_t fn ft nx ny nz tx ty tz)", count);
    if (v[9] < 0)
        return text_error(&s->fstat.in, err, "negative tangential force magnitude %.10g", v[9]);
    if (fabs(norm3(v + 10) - 1.0) > UNIT_TOL)
        return text_error(&s->fstat.in, err, "normal (%.10g %.10g %.10g) is not a unit vector",
                          v[10], v[11], v[12]);
    if (v[9] > 0 && fabs(norm3(v + 13) - 1.0) > UNIT_TOL)
        return text_error(&s->fstat.in, err, "tangential direction (%.10g %.10g %.10g) is not "
                          "a unit vector", v[13], v[14], v[15]);
    if (!f)
        return MIMAS_OK;
    size_t i = 0, j = 0;   /* set by row_index; initialised for -O3's flow analysis */
    int rc = row_index(s, f, v[1], "particle index i", &i, err);
    if (rc)
        return rc;
    if (v[2] < 0)
        return add_wall_row(s, f, i, v[2], v, err);
    rc = row_index(s, f, v[2], "particle index j", &j, err);
    return rc ? rc : add_pair_row(s, f, i, j, v, err);
}

static int cmp_key(const void *a, const void *b)
{
    const pair_key *x = a, *y = b;
    if (x->lo != y->lo)
        return x->lo < y->lo ? -1 : 1;
    if (x->hi != y->hi)
        return x->hi < y->hi ? -1 : 1;
    return (x->row > y->row) - (x->row < y->row);
}

/* a == sign * b to DUP_RTOL of the larger length */
static int same_vec(const double a[3], const double b[3], double sign)
{
    double d[3] = {a[0] - sign * b[0], a[1] - sign * b[1], a[2] - sign * b[2]};
    return norm3(d) <= DUP_RTOL * fmax(norm3(a), norm3(b));
}

/* The two rows a, b of one pair (written once from each side) must agree:
 * same point and overlap, opposite forces and normals. */
static int check_mirror(merc_state *s, const mimas_contacts *c, size_t a, size_t b,
                        mimas_error *err)
{
    const char *what = NULL;
    if (c->i[a] == c->i[b])
        return error_at(err, s->fstat.path, s->row_line[b], "the contact of particles %zu and "
                        "%zu is listed twice from the same side (also at line %ld)", c->i[b],
                        c->j[b], s->row_line[a]);
    if (!same_vec(c->point[a], c->point[b], 1.0))
        what = "contact point";
    else if (fabs(c->overlap[a] - c->overlap[b]) >
             DUP_RTOL * fmax(fabs(c->overlap[a]), fabs(c->overlap[b])))
        what = "overlap";
    else if (!same_vec(s->row_n[a], s->row_n[b], -1.0))
        what = "normal (must be opposite)";
    else if (!same_vec(c->force_n[a], c->force_n[b], -1.0))
        what = "normal force";
    else if (!same_vec(c->force_t[a], c->force_t[b], -1.0))
        what = "tangential force";
    if (what)
        return error_at(err, s->fstat.path, s->row_line[b], "the two rows of the contact of "
                        "particles %zu and %zu disagree (this line and line %ld): %s",
                        c->i[b], c->j[b], s->row_line[a], what);
    return MIMAS_OK;
}

/* Sorts the n > 0 keys by (lo, hi, row), as qsort with cmp_key would: a counting sort by
 * lo (stable: the rows stay in order; a bucket per index up to the largest lo, which is
 * below the particle count: the indices were checked when read), then each particle's few
 * keys by hi in place (an insertion sort, which moves no key past another lo).  Linear where
 * qsort took n log n comparisons (47e6 instructions for the 113,000 rows of a 20,000-sphere
 * frame's .fstat). */
static int sort_keys(merc_state *s, size_t n, mimas_error *err)
{
    size_t top = 0;
    for (size_t k = 0; k < n; k++)
        top = s->keys[k].lo > top ? s->keys[k].lo : top;
    if (top + 2 > s->bucket_cap) {
        if (top + 2 < top || grow_array((void **)&s->bucket, top + 2, sizeof *s->bucket))
            return mimas_error_set(err, MIMAS_EIO, "out of memory for the MercuryDPM reader");
        s->bucket_cap = top + 2;
    }
    size_t *at = s->bucket;
    memset(at, 0, (top + 2) * sizeof *at);
    for (size_t k = 0; k < n; k++)
        at[s->keys[k].lo + 1]++;
    for (size_t p = 0; p <= top; p++)
        at[p + 1] += at[p];
    for (size_t k = 0; k < n; k++)
        s->sorted[at[s->keys[k].lo]++] = s->keys[k];
    for (size_t k = 1; k < n; k++) {
        pair_key x = s->sorted[k];
        size_t m = k;
        while (m > 0 && cmp_key(&s->sorted[m - 1], &x) > 0) {
            s->sorted[m] = s->sorted[m - 1];
            m--;
        }
        s->sorted[m] = x;
    }
    pair_key *t = s->keys;
    s->keys = s->sorted;
    s->sorted = t;
    return MIMAS_OK;
}

/* Marks the duplicate row of every pair written from both sides (keeping
 * the row with i < j) after checking that the two agree. */
static int mark_duplicates(merc_state *s, const mimas_contacts *c, mimas_error *err)
{
    size_t n = c->n;
    if (n == 0)
        return MIMAS_OK;
    for (size_t k = 0; k < n; k++) {
        s->keys[k] = (pair_key){c->i[k] < c->j[k] ? c->i[k] : c->j[k],
                                c->i[k] < c->j[k] ? c->j[k] : c->i[k], k};
        s->drop[k] = 0;
    }
    int rc = sort_keys(s, n, err);
    if (rc)
        return rc;
    for (size_t g = 0; g < n;) {
        size_t e = g + 1;
        while (e < n && s->keys[e].lo == s->keys[g].lo && s->keys[e].hi == s->keys[g].hi)
            e++;
        if (e - g > 2)
            return error_at(err, s->fstat.path, s->row_line[s->keys[g + 2].row], "particles "
                            "%zu and %zu have a third contact row (lines %ld and %ld have the "
                            "other two)", s->keys[g].lo, s->keys[g].hi,
                            s->row_line[s->keys[g].row], s->row_line[s->keys[g + 1].row]);
        if (e - g == 2) {
            size_t a = s->keys[g].row, b = s->keys[g + 1].row;
            rc = check_mirror(s, c, a, b, err);
            if (rc)
                return rc;
            s->drop[c->i[a] > c->j[a] ? a : b] = 1;
        }
        g = e;
    }
    return MIMAS_OK;
}

/* Moves contact row k to row m, written with i < j. */
static void keep_contact(merc_state *s, mimas_frame *f, size_t k, size_t m)
{
    mimas_contacts *c = &f->contacts;
    const mimas_particles *p = &f->particles;
    size_t i = c->i[k];
    double delta = c->overlap[k];
    int flip = i > c->j[k];
    c->i[m] = flip ? c->j[k] : i;
    c->j[m] = flip ? i : c->j[k];
    c->overlap[m] = delta;
    for (int a = 0; a < 3; a++) {
        /* marker 0: the point column is the middle between the centres; the
         * contact point is r_i - (R_i - delta/2) n, n from j to i */
        c->point[m][a] = s->block_marker ? c->point[k][a]
                                         : p->pos[i][a] - (p->radius[i] - 0.5 * delta) *
                                                              s->row_n[k][a];
        /* Newton's third law: the force on j exerted by i is the opposite */
        double sign = flip ? -1.0 : 1.0;
        c->force_n[m][a] = sign * c->force_n[k][a];
        c->force_t[m][a] = sign * c->force_t[k][a];
        c->force[m][a] = sign * c->force[k][a];
    }
}

static int finish_block(merc_state *s, mimas_frame *f, mimas_error *err)
{
    int rc = mark_duplicates(s, &f->contacts, err);
    if (rc)
        return rc;
    size_t m = 0;
    for (size_t k = 0; k < f->contacts.n; k++)
        if (!s->drop[k])
            keep_contact(s, f, k, m++);
    f->contacts.n = m;
    f->has_contacts = f->has_walls = 1;
    return MIMAS_OK;
}

static int prepare_contacts(mimas_frame *f, int with, mimas_error *err)
{
    unsigned cbits = with ? CONTACT_BITS : 0u, wbits = with ? WALL_BITS : 0u;
    mimas_table_keep_only(&f->contacts, &mimas_contacts_desc, cbits);
    mimas_table_drop_extras(&f->contacts, &mimas_contacts_desc);
    mimas_table_keep_only(&f->walls, &mimas_walls_desc, wbits);
    mimas_table_drop_extras(&f->walls, &mimas_walls_desc);
    int rc = mimas_table_set_present(&f->contacts, &mimas_contacts_desc, cbits, err);
    if (!rc)
        rc = mimas_table_set_present(&f->walls, &mimas_walls_desc, wbits, err);
    if (!rc)
        rc = mimas_table_resize(&f->contacts, &mimas_contacts_desc, 0, err);
    if (!rc)
        rc = mimas_table_resize(&f->walls, &mimas_walls_desc, 0, err);
    f->has_contacts = f->has_walls = 0;
    return rc;
}

/* Reads the rows of the pending .fstat time step into f (NULL: skips them)
 * up to the next opening line or the end of the file. */
static int read_block(merc_state *s, mimas_frame *f, mimas_error *err)
{
    int header_lines = 0; /* after "# t marker": the box line and the radii line */
    size_t rows = 0;
    s->have_block = 0;
    for (;;) {
        int rc;
        char *line = next_line(&s->fstat, &rc, err);
        if (!line) {
            if (rc)
                return rc;
            rc = f ? finish_block(s, f, err) : MIMAS_OK;
            return rc ? rc : fstat_next_block(s, err);
        }
        if (line[0] == '#') {
            int opening;
            rc = opening_line(s, line, &opening, err);
            if (rc)
                return rc;
            if (opening) {
                s->have_block = 1;
                return f ? finish_block(s, f, err) : MIMAS_OK;
            }
            if (rows || header_lines == 2)
                return text_error(&s->fstat.in, err, "unexpected '#' line: MercuryDPM writes "
                                  "'#' lines only as the three header lines of a time step "
                                  "('# t marker', the box, the radii)");
            header_lines++;
            continue;
        }
        rc = contact_row(s, f, line, err);
        if (rc)
            return rc;
        rows++;
    }
}

/* Positions the .fstat stream on the time step of the pending .data header.
 * Sets *skip when the .data time step has no contacts and may be dropped. */
static int match(merc_state *s, int *skip, mimas_error *err)
{
    *skip = 0;
    for (;;) {
        if (!s->have_block) {
            if (s->allow_missing) {
                *skip = 1;
                return MIMAS_OK;
            }
            return text_error(&s->data.in, err, "time step t = %.10g has no contacts: the "
                              ".fstat input ends (%s) before it", s->hdr_t, s->fstat.path);
        }
        /* MercuryDPM prints both times with the same stream precision (10
         * significant digits, 13 before), so a true pair is equal; the
         * tolerance allows either file to have been written with as few as 7 */
        if (fabs(s->hdr_t - s->block_t) <= TIME_RTOL * fmax(fabs(s->hdr_t), fabs(s->block_t)))
            return MIMAS_OK;
        if (s->block_t > s->hdr_t) {
            if (s->allow_missing) {
                *skip = 1;
                return MIMAS_OK;
            }
            return text_error(&s->data.in, err, "time step t = %.10g has no contacts in the "
                              ".fstat input (its next time step is t = %.10g at %s:%ld)",
                              s->hdr_t, s->block_t, s->fstat.path, s->fstat.in.line);
        }
        if (!s->allow_missing)
            return text_error(&s->fstat.in, err, "contact time step t = %.10g has no time step "
                              "in the .data input (its next one is t = %.10g at %s:%ld)",
                              s->block_t, s->hdr_t, s->data.path, s->hdr_line);
        int rc = read_block(s, NULL, err);
        if (rc)
            return rc;
    }
}

/* ---- the backend ------------------------------------------------------------ */

static int probe_line(const char *head, size_t n, size_t *pos, char *buf, size_t cap,
                      int need_newline)
{
    size_t start = *pos, end = start;
    while (end < n && head[end] != '\n')
        end++;
    if ((need_newline && end == n) || end - start >= cap || memchr(head + start, '\0', end - start))
        return 0;
    memcpy(buf, head + start, end - start);
    buf[end - start] = '\0';
    buf[strcspn(buf, "\r")] = '\0';
    *pos = end < n ? end + 1 : end;
    return 1;
}

/* Number of values of a header line with a non-negative integer first, else 0. */
static int probe_header(char *line, int64_t *count)
{
    char *p = line, *bad;
    double v[HEADER_3D];
    if (parse_int64(&p, count) != 0 || *count < 0)
        return 0;
    int k = split_numbers(p, v, HEADER_3D, &bad, 0);
    return k == HEADER_2D - 1 || k == HEADER_3D - 1 ? k + 1 : 0;
}

/* A .data file: "N t box" with 6 or 8 numbers, then a row of 8 or 14 numbers
 * (or, when N is 0, nothing or another header of the same kind). */
static int probe(const char *path, const char *head, size_t n)
{
    (void)path;
    char l1[512], l2[1024], *bad;
    size_t pos = 0;
    int64_t count;
    if (!probe_line(head, n, &pos, l1, sizeof l1, 1))
        return 0;
    int width = probe_header(l1, &count);
    if (!width || !probe_line(head, n, &pos, l2, sizeof l2, 0))
        return 0;
    if (count == 0) {
        int64_t c2;
        return l2[strspn(l2, " \t")] == '\0' || probe_header(l2, &c2) == width;
    }
    double v[ROW_3D];
    int cols = split_numbers(l2, v, ROW_3D, &bad, 0);
    return cols == (width == HEADER_3D ? ROW_3D : ROW_2D);
}

static void close_stream(void *state)
{
    merc_state *s = state;
    if (!s)
        return;
    if (s->data.open)
        text_close(&s->data.in);
    if (s->fstat.open)
        text_close(&s->fstat.in);
    reader_free_names(s->data.names, s->data.n);
    reader_free_names(s->fstat.names, s->fstat.n);
    free(s->row_line);
    free(s->row_n);
    free(s->drop);
    free(s->keys);
    free(s->sorted);
    free(s->bucket);
    free(s);
}

static int check_options(const char *first, const mimas_reader_options *o, mimas_error *err)
{
    if (o->nwalls)
        return mimas_error_set(err, MIMAS_EUSAGE, "%s: MercuryDPM .fstat files hold the wall "
                               "contacts too; give them with --contacts", first);
    if (o->contact_columns || o->wall_columns)
        return mimas_error_set(err, MIMAS_EUSAGE, "%s: MercuryDPM .fstat columns are fixed; "
                               "contact or wall column names do not apply", first);
    if (!(o->density >= 0) || !isfinite(o->density))
        return mimas_error_set(err, MIMAS_EUSAGE, "density must be positive");
    return MIMAS_OK;
}

static int open_stream(void **state, const char *const *inputs, size_t ninputs,
                       const mimas_reader_options *o, mimas_error *err)
{
    *state = NULL;
    if (ninputs == 0)
        return mimas_error_set(err, MIMAS_EUSAGE, "no input file");
    int rc = check_options(inputs[0], o, err);
    if (rc)
        return rc;
    merc_state *s = calloc(1, sizeof *s);
    if (!s)
        return mimas_error_set(err, MIMAS_EIO, "out of memory for the MercuryDPM reader");
    s->density = o->density;
    s->with_contacts = o->ncontacts > 0;
    s->allow_missing = o->allow_missing_contacts;
    rc = reader_expand_names(inputs, ninputs, &s->data.names, &s->data.n, err);
    if (!rc && s->with_contacts)
        rc = reader_expand_names(o->contacts, o->ncontacts, &s->fstat.names, &s->fstat.n, err);
    /* read the first headers now, so that a bad file is reported at once */
    if (!rc)
        rc = files_advance(&s->data, err);
    if (!rc)
        rc = data_header(s, err);
    if (rc == MIMAS_END)
        rc = empty_file(&s->data, err, "MercuryDPM time step");
    s->hdr_pending = 1;
    if (!rc && s->with_contacts)
        rc = files_advance(&s->fstat, err);
    if (!rc && s->with_contacts)
        rc = fstat_next_block(s, err);
    if (rc) {
        close_stream(s);
        return rc;
    }
    *state = s;
    return MIMAS_OK;
}

static int next(void *state, mimas_frame *f, mimas_error *err)
{
    merc_state *s = state;
    for (;;) {
        int rc = data_header(s, err);
        if (rc == MIMAS_END) {
            if (s->have_block && !s->allow_missing)
                return text_error(&s->fstat.in, err, "contact time step t = %.10g has no time "
                                  "step in the .data input (it ends at t = %.10g)", s->block_t,
                                  s->hdr_t);
            return MIMAS_END;
        }
        int skip = 0;
        if (!rc && s->with_contacts)
            rc = match(s, &skip, err);
        if (!rc)
            rc = read_particles(s, f, err);
        if (!rc)
            rc = prepare_contacts(f, s->with_contacts && !skip, err);
        if (rc)
            return rc;
        s->step++;
        if (skip) {
            s->skipped++;
            continue;
        }
        return s->with_contacts ? read_block(s, f, err) : MIMAS_OK;
    }
}

static size_t skipped(void *state)
{
    return ((merc_state *)state)->skipped;
}

static const char *source(void *state)
{
    return ((merc_state *)state)->data.path;
}

const reader_backend reader_mercury = {"mercury", "MercuryDPM (.data, .fstat)", probe,
                                       open_stream, next, skipped, close_stream, source, NULL,
                                       NULL, NULL, NULL};
