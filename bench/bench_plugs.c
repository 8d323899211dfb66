/* Benchmark of mimas plugs' per-frame work: axial profiles (exact slice
 * volumes) and plug detection, plus the plug-centred profiles and the
 * tracking, on synthetic tube frames of 10^4 and 10^5 particles (a tube of
 * R = 2 cm, d = 2 mm, plugs of 4 cm and solid fraction 0.55 every 6.7 cm,
 * slices of d/2), against the time to read the same frames from a native
 * file.  Prints frames/s and particles/s of one core, from the process's
 * CPU time (so that a loaded machine changes them little; all of it is one
 * thread), and the peak memory after 10, 20 and 40 frames (flat: nothing is
 * kept per frame).
 *   bench_plugs [--frames F] [--particles N] */
#include <config.h>

#include <getopt.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <time.h>
#include <unistd.h>

#include "axial_profile.h"
#include "native.h"
#include "plug_frame.h"
#include "plug_tracking.h"
#include "plugs.h"
#include "reader.h"

static double now(void)
{
    struct timespec t;
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

static long peak_kb(void)
{
    struct rusage u;
    getrusage(RUSAGE_SELF, &u);
    return u.ru_maxrss;
}

/* about n particles: plugs of 4 cm (6600 particles each) every 6.7 cm */
static void spec_for(tube_spec *t, size_t n)
{
    tube_spec_default(t);
    t->radius = 0.02;
    t->d = 0.002;
    double a = t->d / 2, V = 4.0 / 3.0 * M_PI * a * a * a;
    double per_plug = 0.55 * M_PI * t->radius * t->radius * 0.04 / V, pitch = 0.04 / 0.6;
    size_t np = (size_t)ceil((double)n / per_plug);
    t->nplugs = np < PLUG_MAX ? np : PLUG_MAX;
    for (size_t k = 0; k < t->nplugs; k++)
        t->plugs[k] = (plug_spec){0.01 + (double)k * pitch, 0.04, 0.2, 0.55, 0, 0, 0};
    /* the last plug takes the rest */
    t->plugs[t->nplugs - 1].length = 0.04 * ((double)n / per_plug - (double)(t->nplugs - 1));
    t->length = t->plugs[t->nplugs - 1].back + t->plugs[t->nplugs - 1].length + 0.03;
}

static int run(size_t particles, int frames)
{
    tube_spec t;
    spec_for(&t, particles);
    mimas_error err;
    char path[] = "/tmp/bench_plugs_XXXXXX";
    int fd = mkstemp(path);
    if (fd < 0)
        return 1;
    close(fd);
    /* the frames, written once to a native file */
    mimas_writer_options wo;
    mimas_writer_options_default(&wo);
    mimas_writer *w;
    mimas_frame f;
    mimas_frame_init(&f);
    if (mimas_writer_open(&w, path, &wo, &err))
        return fprintf(stderr, "%s\n", err.msg), 1;
    for (int k = 0; k < frames; k++)
        if (plug_frame(&f, &t, 0.001 * k, k) || mimas_writer_append(w, &f, &err))
            return fprintf(stderr, "cannot write the frames\n"), 1;
    mimas_writer_close(w, &err);
    size_t n = f.particles.n;
    /* reading alone */
    const char *in[1] = {path};
    mimas_reader *r;
    double t0 = now();
    if (mimas_reader_open(&r, in, 1, NULL, &err))
        return fprintf(stderr, "%s\n", err.msg), 1;
    int got = 0;
    while (mimas_reader_next(r, &f, &err) == MIMAS_OK)
        got++;
    mimas_reader_close(r);
    double t_read = now() - t0;
    /* the analysis of the same frames (in memory) */
    mimas_axial_options o;
    memset(&o, 0, sizeof o);
    o.geom.axis = t.axis;
    o.geom.radius = t.radius;
    o.geom.length = t.length;
    o.flow_at = 0.5 * t.length;
    o.check_inside = 1;
    mimas_slices_set(&o.slices, 0, t.length, t.d / 2, &err);
    mimas_axial *ax;
    mimas_axial_create(&ax, &o, &err);
    mimas_tracking_options to;
    memset(&to, 0, sizeof to);
    to.max_shift = NAN;
    to.bins = (mimas_profile_bins){t.d, -20, 0.5, 80};
    to.v0 = to.l0 = -INFINITY;
    to.v1 = to.l1 = INFINITY;
    to.stats_w = t.length / 10;
    to.stats_n = 10;
    mimas_tracker *tr;
    mimas_tracker_create(&tr, &to, &err);
    mimas_plug_options po = {0.6, t.d};
    mimas_plug_list l = {0};
    size_t *cnt = malloc(to.bins.n * MIMAS_AX_NFIELDS * sizeof *cnt);
    double *prof = malloc(PLUG_MAX * 2 * to.bins.n * MIMAS_AX_NFIELDS * sizeof *prof);
    double t_prof = 0, t_all = 0;
    long peak[3] = {0, 0, 0};
    for (int k = 0; k < frames; k++) {
        plug_frame(&f, &t, 0.001 * k, k);
        double a0 = now();
        if (mimas_axial_compute(ax, &f, &err) ||
            mimas_plugs_detect(ax, &po, (size_t)k, f.time, &l, &err))
            return fprintf(stderr, "%s\n", err.msg), 1;
        double a1 = now();
        for (size_t j = 0; j < l.n && j < 2 * PLUG_MAX; j++)
            mimas_plug_profile(ax, &l.p[j], &to.bins, &prof[j * to.bins.n * MIMAS_AX_NFIELDS],
                               cnt);
        if (l.n <= 2 * PLUG_MAX && mimas_tracker_add(tr, f.time, &l, prof, &err))
            return fprintf(stderr, "%s\n", err.msg), 1;
        double a2 = now();
        t_prof += a1 - a0;
        t_all += a2 - a0;
        if (k + 1 == 10 || k + 1 == 20 || k + 1 == 40)
            peak[(k + 1) / 20] = peak_kb();
    }
    printf("bench_plugs: %zu particles, %zu slices, %zu plugs per frame, %d frames\n", n,
           o.slices.n, l.n, got);
    printf("  read (native file)        %8.2f frames/s  %10.3g particles/s\n",
           frames / t_read, frames * (double)n / t_read);
    printf("  profiles + detection      %8.2f frames/s  %10.3g particles/s\n",
           frames / t_prof, frames * (double)n / t_prof);
    printf("  + plug profiles, tracking %8.2f frames/s  %10.3g particles/s\n",
           frames / t_all, frames * (double)n / t_all);
    printf("  analysis / read time      %8.2f\n", t_all / t_read);
    if (frames >= 40)
        printf("  peak memory after 10, 20, 40 frames: %ld %ld %ld kB\n", peak[0], peak[1],
               peak[2]);
    remove(path);
    mimas_frame_free(&f);
    mimas_axial_free(ax);
    mimas_tracker_free(tr);
    mimas_plug_list_free(&l);
    free(prof);
    free(cnt);
    return 0;
}

int main(int argc, char **argv)
{
    int frames = 40;
    long particles = 0;
    static const struct option opts[] = {{"frames", required_argument, NULL, 'f'},
                                         {"particles", required_argument, NULL, 'n'},
                                         {NULL, 0, NULL, 0}};
    int c;
    while ((c = getopt_long(argc, argv, "", opts, NULL)) != -1) {
        if (c == 'f')
            frames = atoi(optarg);
        else if (c == 'n')
            particles = atol(optarg);
        else
            return 1;
    }
    if (particles > 0)
        return run((size_t)particles, frames);
    return run(10000, frames) || run(100000, frames / 4 > 10 ? frames / 4 : 10);
}
