/* The plug analysis runs in memory that does not grow with the number of
 * frames: 3000 frames of a tube with four plugs (a merge on the way) through
 * the axial profiles, the detection, the plug-centred profiles, the
 * tracking, the space-time HDF5 fields and the plug table: the peak memory
 * after frame 3000 is that after frame 1500 (a frame's profile kept per
 * frame would add about 3 MB; the per-frame plug rows about 0.5 MB). */
#include <config.h>

#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>

#include "axial_profile.h"
#include "plug_frame.h"
#include "plug_tracking.h"
#include "plugs.h"
#include "plugs_output.h"
#include "scratch.h"

static long peak_kb(void)
{
    struct rusage u;
    getrusage(RUSAGE_SELF, &u);
    return u.ru_maxrss;
}

static void test_flat(void **state)
{
    (void)state;
    tube_spec t;
    tube_spec_default(&t);
    t.length = 0.1;
    t.nplugs = 4;
    t.plugs[0] = (plug_spec){0.005, 0.01, 0.004, 0.55, 0, 0, 0};
    t.plugs[1] = (plug_spec){0.025, 0.01, 0.002, 0.55, 0, 0, 0};
    t.plugs[2] = (plug_spec){0.05, 0.01, 0.001, 0.55, 0, 0, 0};
    t.plugs[3] = (plug_spec){0.075, 0.01, 0.001, 0.55, 0, 0, 0};
    mimas_error err;
    mimas_axial_options o;
    memset(&o, 0, sizeof o);
    o.geom.axis = t.axis;
    o.geom.radius = t.radius;
    o.geom.length = t.length;
    o.flow_at = 0.05;
    assert_int_equal(mimas_slices_set(&o.slices, 0, t.length, t.d / 2, &err), 0);
    mimas_axial *ax;
    assert_int_equal(mimas_axial_create(&ax, &o, &err), 0);
    mimas_tracking_options to;
    memset(&to, 0, sizeof to);
    to.max_shift = NAN;
    to.bins = (mimas_profile_bins){t.d, -20, 0.5, 80};
    to.v0 = to.l0 = -INFINITY;
    to.v1 = to.l1 = INFINITY;
    to.stats_w = 0.01;
    to.stats_n = 10;
    mimas_tracker *tr;
    assert_int_equal(mimas_tracker_create(&tr, &to, &err), 0);
    mimas_plug_options po = {0.6, t.d};
    const char *path = scratch_path("spacetime.h5");
    mimas_spacetime *st;
    assert_int_equal(mimas_spacetime_open(&st, path, ax, &err), 0);
    static const mimas_ocolumn cols[3] = {{"time", "s", "", 0, 0}, {"track", "1", "", 0, 0},
                                          {"centre", "m", "", 0, 0}};
    mimas_h5out *h5;
    assert_int_equal(mimas_h5out_open(&h5, scratch_path("tables.h5"), &err), 0);
    mimas_otable *tab;
    assert_int_equal(mimas_otable_open(&tab, h5, "/plugs", cols, 3, &err), 0);
    mimas_plug_list l = {0};
    size_t *cnt = malloc(to.bins.n * MIMAS_AX_NFIELDS * sizeof *cnt);
    double *prof = malloc(8 * to.bins.n * MIMAS_AX_NFIELDS * sizeof *prof);
    mimas_frame f;
    mimas_frame_init(&f);
    long early = 0;
    for (int k = 0; k < 3000; k++) {
        double time = 0.01 * k;
        assert_int_equal(plug_frame(&f, &t, time, k), 0);
        if (mimas_axial_compute(ax, &f, &err) ||
            mimas_plugs_detect(ax, &po, (size_t)k, time, &l, &err))
            fail_msg("%s", err.msg);
        assert_true(l.n >= 1 && l.n <= 8);
        for (size_t j = 0; j < l.n; j++)
            mimas_plug_profile(ax, &l.p[j], &to.bins, &prof[j * to.bins.n * MIMAS_AX_NFIELDS],
                               cnt);
        if (mimas_tracker_add(tr, time, &l, prof, &err) ||
            mimas_spacetime_append(st, ax, k, time, &err))
            fail_msg("%s", err.msg);
        for (size_t j = 0; j < l.n; j++) {
            double row[3] = {time, (double)l.p[j].track, l.p[j].centre};
            assert_int_equal(mimas_otable_row(tab, row, NULL, &err), 0);
        }
        if (k == 1500)
            early = peak_kb();
    }
    long late = peak_kb();
    assert_int_equal(mimas_tracker_finish(tr, &err), 0);
    /* the merge of the first two plugs happened */
    assert_true(mimas_tracker_nevents(tr) >= 1);
    assert_int_equal(mimas_spacetime_finish(st, NULL, &err), 0);
    assert_int_equal(mimas_otable_close(tab, &err), 0);
    assert_int_equal(mimas_h5out_commit(h5, NULL, &err), 0);
    mimas_frame_free(&f);
    mimas_plug_list_free(&l);
    free(prof);
    free(cnt);
    mimas_axial_free(ax);
    mimas_tracker_free(tr);
    if (late - early > 512)
        fail_msg("peak memory grew by %ld kB from frame 1500 to frame 3000", late - early);
}

int main(void)
{
    const struct CMUnitTest tests[] = {cmocka_unit_test(test_flat)};
    return cmocka_run_group_tests(tests, scratch_setup, scratch_teardown);
}
