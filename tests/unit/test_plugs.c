/* Plug detection and tracking (averaging/plugs.c, averaging/plug_tracking.c):
 * the tracker on plug lists made here (velocities against gsl_fit_linear,
 * merges, splits, the gate, passages, the per-track averages of profiles
 * and statistics), and the whole per-frame chain on synthetic tubes with
 * known plugs (tests/common/plug_frame.h): positions, lengths, velocities,
 * a merge at a known frame and a split. */
#include <config.h>

#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>

#include "assert_close.h"

#include <gsl/gsl_fit.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "axial_profile.h"
#include "plug_frame.h"
#include "plug_tracking.h"
#include "plugs.h"

static mimas_plug mk(double centre, double length, double v, double time)
{
    mimas_plug p;
    memset(&p, 0, sizeof p);
    p.time = time;
    p.centre = centre;
    p.back = centre - length / 2;
    p.front = centre + length / 2;
    p.length = length;
    p.velocity = v;
    p.mass = 1e-3 * length;
    p.min_porosity = 0.4;
    p.wall_pressure = 100;
    return p;
}

static void tracking_options(mimas_tracking_options *o)
{
    memset(o, 0, sizeof *o);
    o->max_shift = NAN;
    o->v0 = o->l0 = -INFINITY;
    o->v1 = o->l1 = INFINITY;
}

/* frame of plugs at time t */
static void add(mimas_tracker *t, double time, const mimas_plug *p, size_t n)
{
    mimas_plug_list l = {0};
    l.p = malloc((n ? n : 1) * sizeof *l.p);
    memcpy(l.p, p, n * sizeof *p);
    l.n = l.cap = n;
    mimas_error err;
    if (mimas_tracker_add(t, time, &l, NULL, &err))
        fail_msg("%s", err.msg);
    free(l.p);
}

static void tracks_string(const mimas_event *e, char *buf, size_t len)
{
    size_t k = 0;
    for (size_t m = 0; m < e->nbefore + e->nafter; m++)
        k += (size_t)snprintf(buf + k, len - k, "%s%ld", m == 0 ? "" : m == e->nbefore ? ">" : ",",
                              e->tracks[m]);
}

/* The plug velocity and its error are those of an ordinary least-squares
 * fit (gsl_fit_linear) of the centre over time; front and back velocities
 * the slopes of their own fits. */
static void test_velocity_fit(void **state)
{
    (void)state;
    mimas_tracking_options o;
    tracking_options(&o);
    mimas_tracker *t;
    mimas_error err;
    assert_int_equal(mimas_tracker_create(&t, &o, &err), 0);
    double tt[12], cc[12], ff[12];
    for (int k = 0; k < 12; k++) {
        tt[k] = 0.5 + 0.01 * k;
        double jitter = 1e-4 * sin(1.7 * k * k);
        cc[k] = 0.03 + 0.23 * (tt[k] - 0.5) + jitter;
        double len = 0.02 + 1e-4 * cos(2.3 * k);
        ff[k] = cc[k] + len / 2;
        mimas_plug p = mk(cc[k], len, 0.2, tt[k]);
        add(t, tt[k], &p, 1);
    }
    assert_int_equal(mimas_tracker_finish(t, &err), 0);
    assert_int_equal(mimas_tracker_ntracks(t), 1);
    const mimas_track_row *r = mimas_tracker_track(t, 0);
    double c0, c1, cov00, cov01, cov11, sumsq;
    gsl_fit_linear(tt, 1, cc, 1, 12, &c0, &c1, &cov00, &cov01, &cov11, &sumsq);
    assert_close(r->plug_velocity, c1, 1e-12);
    assert_close(r->plug_velocity_err, sqrt(cov11), 1e-12 * sqrt(cov11) + 1e-15);
    gsl_fit_linear(tt, 1, ff, 1, 12, &c0, &c1, &cov00, &cov01, &cov11, &sumsq);
    assert_close(r->front_velocity, c1, 1e-12);
    assert_int_equal(r->frames, 12);
    assert_close(r->first_time, 0.5, 0);
    assert_close(r->last_time, 0.61, 1e-15);
    assert_close(r->particle_velocity, 0.2, 1e-15);
    assert_int_equal(mimas_tracker_nevents(t), 0);
    mimas_tracker_free(t);
}

/* Two plugs that meet at frame 5 (one plug from then on), a plug that
 * splits at frame 5 into two, and a plug that vanishes while another
 * appears far away. */
static void test_merge_split_gate(void **state)
{
    (void)state;
    mimas_tracking_options o;
    tracking_options(&o);
    mimas_tracker *t;
    mimas_error err;
    char ids[64];
    assert_int_equal(mimas_tracker_create(&t, &o, &err), 0);
    for (int k = 0; k < 10; k++) {
        double time = 0.01 * k;
        if (k < 5) {
            mimas_plug p[2] = {mk(0.02 + 0.5 * time, 0.01, 0.5, time),
                               mk(0.06 + 0.1 * time, 0.01, 0.1, time)};
            add(t, time, p, 2);
        } else {
            mimas_plug p = mk(0.045 + 0.1 * time, 0.025, 0.1, time);
            add(t, time, &p, 1);
        }
    }
    assert_int_equal(mimas_tracker_finish(t, &err), 0);
    assert_int_equal(mimas_tracker_ntracks(t), 3);
    assert_int_equal(mimas_tracker_nevents(t), 1);
    const mimas_event *e = mimas_tracker_event(t, 0);
    assert_int_equal(e->kind, MIMAS_EVENT_MERGE);
    assert_string_equal(mimas_event_kind_name(e->kind), "merge");
    assert_close(e->time, 0.05, 1e-15);
    tracks_string(e, ids, sizeof ids);
    assert_string_equal(ids, "1,2>3");
    assert_close(mimas_tracker_track(t, 0)->plug_velocity, 0.5, 1e-12);
    assert_close(mimas_tracker_track(t, 0)->last_time, 0.04, 1e-15);
    assert_close(mimas_tracker_track(t, 1)->plug_velocity, 0.1, 1e-12);
    assert_close(mimas_tracker_track(t, 2)->first_time, 0.05, 1e-15);
    assert_close(mimas_tracker_track(t, 2)->plug_velocity, 0.1, 1e-12);
    assert_int_equal(mimas_tracker_track(t, 2)->frames, 5);
    mimas_tracker_free(t);

    /* split */
    assert_int_equal(mimas_tracker_create(&t, &o, &err), 0);
    for (int k = 0; k < 10; k++) {
        double time = 0.01 * k;
        if (k < 5) {
            mimas_plug p = mk(0.05 + 0.2 * time, 0.03, 0.2, time);
            add(t, time, &p, 1);
        } else {
            mimas_plug p[2] = {mk(0.04 + 0.05 * time, 0.012, 0.05, time),
                               mk(0.06 + 0.2 * time, 0.012, 0.2, time)};
            add(t, time, p, 2);
        }
    }
    assert_int_equal(mimas_tracker_finish(t, &err), 0);
    assert_int_equal(mimas_tracker_nevents(t), 1);
    e = mimas_tracker_event(t, 0);
    assert_int_equal(e->kind, MIMAS_EVENT_SPLIT);
    tracks_string(e, ids, sizeof ids);
    assert_string_equal(ids, "1>2,3");
    assert_close(e->time, 0.05, 1e-15);
    assert_close(mimas_tracker_track(t, 1)->plug_velocity, 0.05, 1e-12);
    assert_close(mimas_tracker_track(t, 2)->plug_velocity, 0.2, 1e-12);
    mimas_tracker_free(t);

    /* a plug gone, another far away: two tracks, no event; the gate is
     * the plug's length (no two plugs in a frame) */
    assert_int_equal(mimas_tracker_create(&t, &o, &err), 0);
    mimas_plug a = mk(0.19, 0.01, 0.2, 0.0), b = mk(0.01, 0.01, 0.2, 0.01);
    add(t, 0.0, &a, 1);
    add(t, 0.01, &b, 1);
    assert_int_equal(mimas_tracker_finish(t, &err), 0);
    assert_int_equal(mimas_tracker_ntracks(t), 2);
    assert_int_equal(mimas_tracker_nevents(t), 0);
    assert_true(isnan(mimas_tracker_track(t, 0)->plug_velocity));
    mimas_tracker_free(t);

    /* --max-shift: a plug that jumps 5 mm in a frame (beyond its predicted
     * place, no overlap) is the same plug with a gate of 1 cm, not with 1 mm */
    for (int g = 0; g < 2; g++) {
        o.max_shift = g ? 0.01 : 0.001;
        assert_int_equal(mimas_tracker_create(&t, &o, &err), 0);
        mimas_plug c = mk(0.05, 0.002, 0.0, 0.0), d = mk(0.055, 0.002, 0.0, 0.01);
        add(t, 0.0, &c, 1);
        add(t, 0.01, &d, 1);
        assert_int_equal(mimas_tracker_finish(t, &err), 0);
        assert_int_equal(mimas_tracker_ntracks(t), g ? 1 : 2);
        mimas_tracker_free(t);
    }
    /* times must increase; frames without time are refused */
    o.max_shift = NAN;
    assert_int_equal(mimas_tracker_create(&t, &o, &err), 0);
    add(t, 0.1, &a, 1);
    mimas_plug_list l = {&a, 1, 1};
    assert_int_equal(mimas_tracker_add(t, 0.1, &l, NULL, &err), MIMAS_EDATA);
    assert_non_null(strstr(err.msg, "must increase"));
    assert_int_equal(mimas_tracker_add(t, NAN, &l, NULL, &err), MIMAS_EDATA);
    assert_non_null(strstr(err.msg, "--timestep"));
    mimas_tracker_free(t);
}

/* Passages: three plugs 4 cm apart at 0.2 m/s, observed for 0.5 s; a plug
 * whose centre starts at c0 crosses the plane s_w in (0, T] when c0 < s_w
 * <= c0 + 0.2 T.  Windows of 5 cm from 0. */
static void test_passages_and_stats(void **state)
{
    (void)state;
    mimas_tracking_options o;
    tracking_options(&o);
    o.stats_s0 = 0;
    o.stats_w = 0.05;
    o.stats_n = 6;
    mimas_tracker *t;
    mimas_error err;
    assert_int_equal(mimas_tracker_create(&t, &o, &err), 0);
    double c0[3] = {0.01, 0.05, 0.09}, v = 0.2, T = 0.5;
    for (int k = 0; k <= 50; k++) {
        double time = 0.01 * k;
        mimas_plug p[3];
        size_t n = 0;
        for (int q = 0; q < 3; q++) {
            double c = c0[q] + v * time;
            if (c < 0.3)
                p[n++] = mk(c, 0.01, 0.18, time);
        }
        add(t, time, p, n);
    }
    assert_int_equal(mimas_tracker_finish(t, &err), 0);
    assert_close(mimas_tracker_span(t), T, 1e-15);
    for (size_t w = 0; w < o.stats_n; w++) {
        double sw = 0.05 * (w + 0.5);
        long want = 0;
        for (int q = 0; q < 3; q++)
            want += c0[q] < sw && sw <= c0[q] + v * T && sw < 0.3;
        long passages;
        double rate, rerr;
        mimas_tracker_passages(t, w, &passages, &rate, &rerr);
        assert_int_equal(passages, want);
        assert_close(rate, want / T, 1e-12);
        assert_close(rerr, sqrt((double)want) / T, 1e-12);
        /* every track that was centred in the window gives one sample: the
         * plug velocity 0.2 from the centre's steps, particle velocity 0.18 */
        double mean, sem;
        size_t n;
        mimas_tracker_stat(t, w, MIMAS_ST_PLUG_VELOCITY, &mean, &sem, &n);
        if (0.05 * w > c0[2] + v * T) { /* no plug reaches the window */
            assert_int_equal(n, 0);
            assert_true(isnan(mean));
            continue;
        }
        assert_true(n >= 1);
        assert_close(mean, 0.2, 1e-10);
        mimas_tracker_stat(t, w, MIMAS_ST_PARTICLE_VELOCITY, &mean, &sem, &n);
        assert_close(mean, 0.18, 1e-12);
        mimas_tracker_stat(t, w, MIMAS_ST_LENGTH, &mean, &sem, &n);
        assert_close(mean, 0.01, 1e-14);
        if (n > 1)
            assert_close(sem, 0.0, 1e-14);
    }
    mimas_tracker_free(t);
}

/* Plug-centred profiles: one sample per track (the mean of its plugs),
 * then the mean and standard error over tracks; windows select plugs. */
static void test_profile_average(void **state)
{
    (void)state;
    mimas_tracking_options o;
    tracking_options(&o);
    o.bins.n = 2;
    o.bins.d = 1e-3;
    o.bins.lo = -1;
    o.bins.w = 1;
    o.v1 = 0.3; /* the third plug (0.5 m/s) is left out */
    size_t np = o.bins.n * MIMAS_AX_NFIELDS;
    mimas_tracker *t;
    mimas_error err;
    assert_int_equal(mimas_tracker_create(&t, &o, &err), 0);
    double *prof = calloc(3 * np, sizeof *prof);
    for (int k = 0; k < 2; k++) {
        double time = 0.01 * k;
        mimas_plug p[3] = {mk(0.02 + 0.1 * time, 0.01, 0.1, time),
                           mk(0.08 + 0.1 * time, 0.01, 0.1, time),
                           mk(0.14 + 0.1 * time, 0.01, 0.5, time)};
        for (size_t q = 0; q < np; q++) {
            prof[q] = k == 0 ? 1.0 : 3.0; /* track 1: mean 2 */
            prof[np + q] = 4.0;           /* track 2: 4 */
            prof[2 * np + q] = 100.0;     /* outside the window */
        }
        if (k == 0)
            prof[1] = NAN; /* bin 0, field 1 missing once in track 1 */
        mimas_plug_list l = {p, 3, 3};
        assert_int_equal(mimas_tracker_add(t, time, &l, prof, &err), 0);
    }
    assert_int_equal(mimas_tracker_finish(t, &err), 0);
    double mean, sem;
    size_t n;
    mimas_tracker_profile(t, 0, 0, &mean, &sem, &n);
    assert_int_equal(n, 2);
    assert_close(mean, 3.0, 1e-15);
    assert_close(sem, 1.0, 1e-15);
    mimas_tracker_profile(t, 0, 1, &mean, &sem, &n);
    assert_close(mean, 3.5, 1e-15); /* track 1's only value 3 */
    mimas_tracker_free(t);
    free(prof);
}

/* ---- the whole chain on synthetic tubes ---- */

typedef struct chain {
    mimas_axial *ax;
    mimas_plug_options po;
    mimas_tracker *tr;
    mimas_plug_list list;
    mimas_frame f;
    double w;
} chain;

static void chain_open(chain *c, const tube_spec *t, const mimas_tracking_options *to)
{
    mimas_error err;
    mimas_axial_options o;
    memset(&o, 0, sizeof o);
    memset(c, 0, sizeof *c);
    o.geom.axis = t->axis;
    o.geom.radius = t->radius;
    o.geom.length = t->length;
    o.flow_at = NAN;
    o.check_inside = 1;
    assert_int_equal(mimas_slices_set(&o.slices, 0, t->length, t->d / 2, &err), 0);
    c->w = o.slices.w;
    assert_int_equal(mimas_axial_create(&c->ax, &o, &err), 0);
    c->po.threshold = 0.6;
    c->po.min_length = t->d;
    assert_int_equal(mimas_tracker_create(&c->tr, to, &err), 0);
    mimas_frame_init(&c->f);
}

static void chain_frame(chain *c, const tube_spec *t, size_t k, double dt)
{
    mimas_error err;
    assert_int_equal(plug_frame(&c->f, t, (double)k * dt, (int64_t)k), 0);
    assert_int_equal(mimas_axial_compute(c->ax, &c->f, &err), 0);
    assert_int_equal(mimas_plugs_detect(c->ax, &c->po, k, c->f.time, &c->list, &err), 0);
    assert_int_equal(mimas_tracker_add(c->tr, c->f.time, &c->list, NULL, &err), 0);
}

static void chain_close(chain *c)
{
    mimas_axial_free(c->ax);
    mimas_tracker_free(c->tr);
    mimas_plug_list_free(&c->list);
    mimas_frame_free(&c->f);
}

/* Two plugs (backs at 2 and 10 cm, 3 and 4 cm long, 0.2 and 0.1 m/s) in a
 * dilute background, vertical and horizontal: every frame finds both; each
 * centre within W/2 of the constructed one (at most one slice's mass
 * missing at either end), ends within a + W inside and W outside the
 * constructed ends (the solid fraction ramps over a diameter about each
 * end, through half its plateau at the end: the threshold's 0.4/0.55 is
 * crossed inside); the tracks' plug velocities within 2 W / span. */
static void test_synthetic_tube(void **state)
{
    (void)state;
    for (int horizontal = 0; horizontal < 2; horizontal++) {
        tube_spec t;
        tube_spec_default(&t);
        mimas_error err;
        if (horizontal)
            assert_int_equal(mimas_axis_parse(&t.axis, "0.1,0.2,0.3,1,0,0", &err), 0);
        t.dilute = 0.02;
        t.nplugs = 2;
        t.plugs[0] = (plug_spec){0.02, 0.03, 0.2, 0.55, 0, 0, 0};
        t.plugs[1] = (plug_spec){0.10, 0.04, 0.1, 0.55, 0, 0, 0};
        mimas_tracking_options o;
        tracking_options(&o);
        chain c;
        chain_open(&c, &t, &o);
        double dt = 0.01, a = t.d / 2;
        for (size_t k = 0; k < 20; k++) {
            chain_frame(&c, &t, k, dt);
            assert_int_equal(c.list.n, 2);
            for (size_t q = 0; q < 2; q++) {
                const mimas_plug *p = &c.list.p[q];
                double back = t.plugs[q].back + t.plugs[q].v * c.f.time;
                double front = back + t.plugs[q].length;
                assert_close(p->centre, 0.5 * (back + front), 0.5 * c.w);
                assert_true(p->back >= back - c.w && p->back <= back + a + c.w);
                assert_true(p->front <= front + c.w && p->front >= front - a - c.w);
                assert_close(p->length, p->front - p->back, 1e-15);
                assert_false(p->cut);
                assert_true(p->min_porosity < 0.5);
                assert_int_equal(p->track, (long)q + 1);
            }
        }
        assert_int_equal(mimas_tracker_finish(c.tr, &err), 0);
        assert_int_equal(mimas_tracker_ntracks(c.tr), 2);
        assert_int_equal(mimas_tracker_nevents(c.tr), 0);
        for (size_t q = 0; q < 2; q++) {
            const mimas_track_row *r = mimas_tracker_track(c.tr, q);
            assert_int_equal(r->frames, 20);
            assert_close(r->plug_velocity, t.plugs[q].v, 2 * c.w / 0.19);
        }
        chain_close(&c);
    }
}

/* A fast plug (0.5 m/s, back 2 cm, 2 cm long) reaches a slow one (0.1 m/s,
 * back 6 cm) at t = 0.05 s (gap 2 cm closing at 0.4 m/s): the frame at 0.05
 * has one plug and the event merge 1,2>3; later, the plug's upper half goes
 * on at 0.1 m/s and its lower half stays from t = 0.12 (0.01 s later 1 mm
 * apart... so 0.6 m/s apart: 6 mm at the next frame): split 3>4,5 at 0.13. */
static void test_synthetic_merge_split(void **state)
{
    (void)state;
    tube_spec t;
    tube_spec_default(&t);
    t.nplugs = 2;
    t.plugs[0] = (plug_spec){0.02, 0.02, 0.5, 0.55, 0, 0, 0};
    t.plugs[1] = (plug_spec){0.06, 0.02, 0.1, 0.55, 0.12, 0.5, -0.5};
    mimas_tracking_options o;
    tracking_options(&o);
    chain c;
    chain_open(&c, &t, &o);
    for (size_t k = 0; k < 20; k++) {
        chain_frame(&c, &t, k, 0.01);
        size_t want = k < 5 ? 2 : k < 13 ? 1 : 2;
        assert_int_equal(c.list.n, want);
    }
    mimas_error err;
    assert_int_equal(mimas_tracker_finish(c.tr, &err), 0);
    assert_int_equal(mimas_tracker_nevents(c.tr), 2);
    char ids[64];
    const mimas_event *e = mimas_tracker_event(c.tr, 0);
    assert_int_equal(e->kind, MIMAS_EVENT_MERGE);
    assert_close(e->time, 0.05, 1e-15);
    tracks_string(e, ids, sizeof ids);
    assert_string_equal(ids, "1,2>3");
    e = mimas_tracker_event(c.tr, 1);
    assert_int_equal(e->kind, MIMAS_EVENT_SPLIT);
    assert_close(e->time, 0.13, 1e-15);
    tracks_string(e, ids, sizeof ids);
    assert_string_equal(ids, "3>4,5");
    /* after the merge the plug moves at 0.1 m/s, after the split its halves
     * at -0.5 and 0.1 m/s (ends: fits over 8 and 7 frames) */
    assert_close(mimas_tracker_track(c.tr, 2)->plug_velocity, 0.1, 2 * c.w / 0.07);
    assert_close(mimas_tracker_track(c.tr, 3)->plug_velocity, -0.5, 2 * c.w / 0.06);
    assert_close(mimas_tracker_track(c.tr, 4)->plug_velocity, 0.1, 2 * c.w / 0.06);
    chain_close(&c);
}

/* No plugs at all: an empty tube and a dilute one give no plug and no track. */
static void test_no_plugs(void **state)
{
    (void)state;
    tube_spec t;
    tube_spec_default(&t);
    t.dilute = 0.1;
    mimas_tracking_options o;
    tracking_options(&o);
    chain c;
    chain_open(&c, &t, &o);
    for (size_t k = 0; k < 3; k++) {
        chain_frame(&c, &t, k, 0.01);
        assert_int_equal(c.list.n, 0);
    }
    mimas_error err;
    assert_int_equal(mimas_tracker_finish(c.tr, &err), 0);
    assert_int_equal(mimas_tracker_ntracks(c.tr), 0);
    assert_int_equal(mimas_tracker_frames(c.tr), 3);
    chain_close(&c);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_velocity_fit),       cmocka_unit_test(test_merge_split_gate),
        cmocka_unit_test(test_passages_and_stats), cmocka_unit_test(test_profile_average),
        cmocka_unit_test(test_synthetic_tube),     cmocka_unit_test(test_synthetic_merge_split),
        cmocka_unit_test(test_no_plugs),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
