/* mimas against MercuryCG (MercuryDPM's coarse-graining tool) on the same
 * MercuryDPM files: tests/data/mercury/box150.{data,fstat} (150 spheres and
 * their particle and wall contacts) and MercuryCG's XYZ Gauss output
 * box150_xyz.stat (command line in tests/data/mercury/README.md).
 *   - the particle fields (solid fraction, density, momentum, momentum flux)
 *     and the wall force density agree to MercuryCG's printed digits;
 *   - the contact stress is the exact line integral of the kernel, checked
 *     against GSL quadrature here; MercuryCG's differs by about 1.5 % of the
 *     largest component, because it integrates a cylinder-cut kernel instead
 *     (tests/data/mercury/check_mercurycg.py reproduces it to the digit). */
#include <config.h>

#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>

#include <gsl/gsl_integration.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "assert_close.h"
#include "average.h"
#include "fields.h"
#include "reader.h"

static char path_buf[4][1024];
static const char *data_path(int k, const char *name)
{
    const char *top = getenv("TEST_SRCDIR");
    snprintf(path_buf[k], sizeof path_buf[k], "%s/data/mercury/%s", top ? top : "tests", name);
    return path_buf[k];
}

enum { NX = 6, NY = 6, NZ = 9 };
static const double W = 0.001, CUTOFF = 3.0, H = 0.001;

static void load(mimas_frame *f)
{
    const char *in[1] = {data_path(0, "box150.data")}, *fs[1] = {data_path(1, "box150.fstat")};
    mimas_reader_options o;
    mimas_reader_options_default(&o);
    o.format = "mercury";
    o.contacts = fs;
    o.ncontacts = 1;
    o.density = 1.0; /* MercuryCG's density without a .restart file */
    mimas_reader *r;
    mimas_error err;
    if (mimas_reader_open(&r, in, 1, &o, &err))
        fail_msg("%s", err.msg);
    mimas_frame_init(f);
    if (mimas_reader_next(r, f, &err))
        fail_msg("%s", err.msg);
    mimas_reader_close(r);
}

/* MercuryCG's rows: time x y z, VolumeFraction, Density, Momentum (3),
 * MomentumFlux (xx xy xz yy yz zz), ContactStress (9, row-major),
 * InteractionForce (3), ParticleSize (6) */
enum { M_X = 1, M_VF = 4, M_RHO, M_MOM, M_FLUX = M_MOM + 3, M_CS = M_FLUX + 6,
       M_IF = M_CS + 9, M_COLS = M_IF + 3 + 6 };

static double (*read_stat(size_t *n))[M_COLS]
{
    FILE *fp = fopen(data_path(2, "box150_xyz.stat"), "r");
    assert_non_null(fp);
    char line[4096];
    assert_non_null(fgets(line, sizeof line, fp));
    assert_non_null(fgets(line, sizeof line, fp));
    double (*rows)[M_COLS] = calloc(NX * NY * NZ, sizeof *rows);
    *n = 0;
    while (fgets(line, sizeof line, fp) && *n < NX * NY * NZ) {
        char *p = line;
        for (int k = 0; k < M_COLS; k++) {
            char *end;
            rows[*n][k] = strtod(p, &end);
            assert_true(end != p);
            p = end;
        }
        (*n)++;
    }
    fclose(fp);
    assert_int_equal(*n, NX * NY * NZ);
    return rows;
}

/* |mimas - printed| within half a unit of the printed sixth digit */
static void assert_digits(double mine, double printed)
{
    double unit = printed != 0 ? pow(10.0, floor(log10(fabs(printed))) - 5) : 0.0;
    double tol = 0.5 * unit * (1 + 1e-9) + 1e-300;
    if (!(fabs(mine - printed) <= tol) && !(printed == 0 && fabs(mine) < 1e-30))
        fail_msg("mimas %.17g, MercuryCG printed %.6g (tolerance %.3g)", mine, printed, tol);
}

static mimas_average *average(const mimas_frame *f)
{
    mimas_average_options o;
    memset(&o, 0, sizeof o);
    mimas_error err;
    assert_int_equal(mimas_grid_parse(&o.grid, "x=0:0.006:6,y=0:0.006:6,z=0:0.009:9", NULL, &err),
                     0);
    assert_int_equal(mimas_weight_parse(&o.weight, "gauss:w=0.001", &err), 0);
    mimas_average *a;
    assert_int_equal(mimas_average_create(&a, &o, &err), 0);
    assert_int_equal(mimas_average_add(a, f, &err), 0);
    return a;
}

static size_t cell_of_row(const double *row)
{
    int i = (int)floor(row[M_X] / H), j = (int)floor(row[M_X + 1] / H),
        k = (int)floor(row[M_X + 2] / H);
    return (size_t)i + NX * ((size_t)j + NY * (size_t)k);
}

static void test_particle_fields(void **state)
{
    (void)state;
    mimas_frame f;
    load(&f);
    mimas_average *a = average(&f);
    size_t n;
    double (*rows)[M_COLS] = read_stat(&n);
    const int sym[6][2] = {{0, 0}, {0, 1}, {0, 2}, {1, 1}, {1, 2}, {2, 2}};
    for (size_t r = 0; r < n; r++) {
        double S[NSUMS];
        mimas_average_sums(a, cell_of_row(rows[r]), S);
        assert_digits(S[S_V], rows[r][M_VF]);
        assert_digits(S[S_M], rows[r][M_RHO]);
        for (int d = 0; d < 3; d++) {
            assert_digits(S[S_P + d], rows[r][M_MOM + d]);
            assert_digits(S[S_W + d], rows[r][M_IF + d]);
        }
        for (int q = 0; q < 6; q++)
            assert_digits(S[S_K + mimas_sym_index(sym[q][0], sym[q][1])], rows[r][M_FLUX + q]);
    }
    free(rows);
    mimas_average_free(a);
    mimas_frame_free(&f);
}

/* ---- the exact line integral, by quadrature here ---- */

static double COEF;
static double seg_a[3], seg_b[3], seg_r[3];

static double kernel_along(double s, void *p)
{
    (void)p;
    double q = 0;
    for (int d = 0; d < 3; d++) {
        double x = seg_r[d] - seg_a[d] - s * (seg_b[d] - seg_a[d]);
        q += x * x;
    }
    double R = CUTOFF * W;
    return q < R * R ? COEF * exp(-q / (2 * W * W)) : 0.0;
}

/* int_0^1 phi(r - a - s (b - a)) ds with break points at the cut sphere about r:
 * GSL's 24-point Gauss-Legendre rule on each smooth piece (a Gaussian over at most
 * about one width: exact to rounding) */
static double line_integral(const gsl_integration_glfixed_table *ws, const double r[3],
                            const double a[3], const double b[3])
{
    double A = 0, B = 0, Cq = 0, R = CUTOFF * W;
    for (int d = 0; d < 3; d++) {
        seg_a[d] = a[d];
        seg_b[d] = b[d];
        seg_r[d] = r[d];
        A += (b[d] - a[d]) * (b[d] - a[d]);
        B += (r[d] - a[d]) * (b[d] - a[d]);
        Cq += (r[d] - a[d]) * (r[d] - a[d]);
    }
    Cq -= R * R;
    double pts[4] = {0, 0, 0, 0};
    int np = 0;
    pts[np++] = 0;
    double disc = B * B - A * Cq;
    if (disc > 0) {
        double s1 = (B - sqrt(disc)) / A, s2 = (B + sqrt(disc)) / A;
        if (s1 > 0 && s1 < 1)
            pts[np++] = s1;
        if (s2 > 0 && s2 < 1)
            pts[np++] = s2;
    } else if (Cq > 0) {
        return 0.0;
    }
    pts[np++] = 1;
    gsl_function F = {kernel_along, NULL};
    double total = 0;
    for (int k = 0; k + 1 < np; k++)
        total += gsl_integration_glfixed(&F, pts[k], pts[k + 1], ws);
    return total;
}

static void add_branch(double (*T)[9], const gsl_integration_glfixed_table *ws, const double a[3],
                       const double b[3], const double f[3])
{
    for (size_t c = 0; c < NX * NY * NZ; c++) {
        int i = (int)(c % NX), j = (int)(c / NX % NY), k = (int)(c / (NX * NY));
        double r[3] = {(i + 0.5) * H, (j + 0.5) * H, (k + 0.5) * H};
        double psi = line_integral(ws, r, a, b);
        if (psi == 0)
            continue;
        for (int x = 0; x < 3; x++)
            for (int y = 0; y < 3; y++)
                T[c][3 * x + y] += f[x] * (b[y] - a[y]) * psi;
    }
}

static void test_contact_stress(void **state)
{
    (void)state;
    double C = CUTOFF;
    COEF = 1.0 / (pow(2 * M_PI * W * W, 1.5) *
                  (erf(C / M_SQRT2) - sqrt(2 / M_PI) * C * exp(-0.5 * C * C)));
    mimas_frame f;
    load(&f);
    assert_true(f.contacts.n > 200 && f.walls.n > 50);
    mimas_average *a = average(&f);
    double (*T)[9] = calloc(NX * NY * NZ, sizeof *T);
    gsl_integration_glfixed_table *ws = gsl_integration_glfixed_table_alloc(24);
    const mimas_particles *p = &f.particles;
    for (size_t k = 0; k < f.contacts.n; k++) /* from r_j to r_i, f on i */
        add_branch(T, ws, p->pos[f.contacts.j[k]], p->pos[f.contacts.i[k]], f.contacts.force[k]);
    for (size_t k = 0; k < f.walls.n; k++) /* from the contact point to the centre */
        add_branch(T, ws, f.walls.point[k], p->pos[f.walls.particle[k]], f.walls.force[k]);
    gsl_integration_glfixed_table_free(ws);
    double scale = 0;
    for (size_t c = 0; c < NX * NY * NZ; c++)
        for (int q = 0; q < 9; q++)
            scale = fmax(scale, fabs(T[c][q]));
    size_t n;
    double (*rows)[M_COLS] = read_stat(&n);
    double worst = 0, mscale = 0;
    for (size_t r = 0; r < n; r++) {
        size_t c = cell_of_row(rows[r]);
        double S[NSUMS];
        mimas_average_sums(a, c, S);
        for (int q = 0; q < 9; q++) {
            assert_close(S[S_C + q], T[c][q], 1e-10 * scale);
            worst = fmax(worst, fabs(S[S_C + q] - rows[r][M_CS + q]));
            mscale = fmax(mscale, fabs(rows[r][M_CS + q]));
        }
    }
    /* MercuryCG's cylinder-cut kernel: about 1.5 % of the largest component away
     * (check_mercurycg.py: 1.47 %) */
    assert_true(worst / mscale > 0.01 && worst / mscale < 0.02);
    free(rows);
    free(T);
    mimas_average_free(a);
    mimas_frame_free(&f);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_particle_fields),
        cmocka_unit_test(test_contact_stress),
    };
    return cmocka_run_group_tests_name("mercurycg", tests, NULL, NULL);
}
