/* The time loop of mimas simulate. */
#include <config.h>

#include "simulate.h"

#include <math.h>
#include <stdio.h>
#include <string.h>
#include <time.h>

#include "checkpoint.h"
#include "native.h"
#include "setup.h"
#include "xdmf.h"
#include "tmpfiles.h"

static double now(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

/* The names of the per-frame observables, in the order of dem_energy. */
#define NOBS 4
static const char *const obs_names[NOBS] = {"kinetic_energy", "rotational_energy",
                                            "elastic_energy", "bridge_energy"};

/* The current state as a frame with its energies, appended to w. */
static int write_frame(const dem_system *s, const sim_plan *plan, mimas_frame *f,
                       mimas_writer *w, mimas_error *err)
{
    dem_energy e;
    int rc = sim_frame_fill(s, plan, f, err);
    if (!rc)
        rc = dem_energies(s, &e, err);
    if (rc)
        return rc;
    double v[NOBS] = {e.kinetic, e.rotational, e.elastic, e.bridge};
    mimas_observable obs[NOBS];
    for (int k = 0; k < NOBS; k++)
        obs[k] = (mimas_observable){obs_names[k], "J", v[k]};
    rc = mimas_writer_observe(w, obs, NOBS, err);
    return rc ? rc : mimas_writer_append(w, f, err);
}

/* The scenario's keys as /parameters/scenario (docs/format.md). */
static int write_parameters(const sim_scenario *sc, mimas_writer *w, mimas_error *err)
{
    mimas_parameters ps;
    mimas_parameters_init(&ps);
    int rc = sim_scenario_parameters(sc, &ps, err);
    if (!rc)
        rc = mimas_writer_parameters(w, "scenario", &ps, err);
    mimas_parameters_free(&ps);
    return rc;
}

/* A new output file with the scenario's keys as its run parameters (they
 * must come before the first frame). */
static int open_output(const sim_scenario *sc, const char *path, const mimas_writer_options *wo,
                       mimas_writer **w, mimas_error *err)
{
    int rc = mimas_writer_open(w, path, wo, err);
    if (!rc && (rc = write_parameters(sc, *w, err)) != MIMAS_OK) {
        mimas_writer_abort(*w);
        *w = NULL;
    }
    return rc;
}

/* Frame k of r with its observables into w. */
static int copy_frame(mimas_native *r, const char *path, size_t k, mimas_frame *f,
                      mimas_writer *w, mimas_error *err)
{
    size_t n = mimas_native_observables(r);
    mimas_observable obs[NOBS];
    int rc = n > NOBS ? mimas_error_set(err, MIMAS_EDATA, "%s: more observables than mimas "
                                        "simulate writes", path)
                      : MIMAS_OK;
    for (size_t q = 0; !rc && q < n; q++) {
        obs[q].name = mimas_native_observable_name(r, q, &obs[q].unit);
        rc = mimas_native_observable_read(r, q, k, 1, &obs[q].value, err);
    }
    if (!rc && n)
        rc = mimas_writer_observe(w, obs, n, err);
    if (!rc)
        rc = mimas_native_read(r, k, f, err);
    return rc ? rc : mimas_writer_append(w, f, err);
}

/* --resume: the frames of the old file up to the checkpoint go into a new
 * file (under a temporary name, renamed over the old one), which the run
 * then continues.  Frames written after the checkpoint are dropped: the run
 * writes them again. */
static int reopen_output(const sim_scenario *sc, const sim_run_options *o, int64_t last_step,
                         mimas_writer **w, const mimas_writer_options *wo, mimas_error *err)
{
    char tmp[4200];
    if (mimas_tmpfile_name(tmp, sizeof tmp, o->output))
        return mimas_error_set(err, MIMAS_EUSAGE, "%s: the file name is too long", o->output);
    mimas_native *r;
    int rc = mimas_native_open(&r, o->output, err);
    if (rc)
        return rc;
    int slot = mimas_tmpfile_add(tmp);
    if ((rc = open_output(sc, tmp, wo, w, err))) {
        mimas_tmpfile_forget(slot);
        mimas_native_close(r);
        return rc;
    }
    mimas_frame f;
    mimas_frame_init(&f);
    size_t frames = mimas_native_frames(r);
    for (size_t k = 0; k < frames && !rc; k++) {
        mimas_frame_meta m;
        if ((rc = mimas_native_frame_meta(r, k, &m, err)) || m.step > last_step)
            break;
        rc = copy_frame(r, o->output, k, &f, *w, err);
    }
    mimas_frame_free(&f);
    mimas_native_close(r);
    if (!rc && rename(tmp, o->output) != 0)
        rc = mimas_error_set(err, MIMAS_EIO, "%s: cannot replace it", o->output);
    if (rc) {
        mimas_writer_abort(*w);
        *w = NULL;
        remove(tmp);
    }
    mimas_tmpfile_forget(slot);
    return rc;
}

/* Checkpoint cadence when checkpoint_every = 0 (automatic): with the first
 * frame, then with a frame once this much wall time has passed since the
 * last one, and at the end; a checkpoint costs a write of the whole state,
 * a frame of a tiny system almost nothing. */
#define CHECKPOINT_SECONDS 60.0

int sim_run(const sim_scenario *sc, const sim_run_options *o, mimas_error *err)
{
    char ckpt[4200];
    if (snprintf(ckpt, sizeof ckpt, "%s.ckpt", o->output) >= (int)sizeof ckpt - 16)
        return mimas_error_set(err, MIMAS_EUSAGE, "%s: the file name is too long", o->output);
    dem_system s;
    dem_init(&s);
    sim_plan plan;
    mimas_writer *w = NULL;
    mimas_frame f;
    mimas_frame_init(&f);
    mimas_writer_options wo;
    mimas_writer_options_default(&wo);
    wo.provenance = o->provenance;
    wo.xdmf = 1; /* the sidecar for ParaView, written when the run ends */
    sim_ck_chunk state[16];
    int rc = sim_setup(&s, sc, &plan, err);
    size_t nstate = rc ? 0 : sim_plan_state(&plan, state, 16);
    if (!rc && o->resume) {
        /* the continued file is written under a temporary name and renamed
         * over RUN.h5 at once, so the writer cannot name it in the sidecar
         * when it closes: the sidecar is written here after the close */
        mimas_writer_options wr = wo;
        wr.xdmf = 0;
        if (!(rc = sim_checkpoint_read(&s, state, nstate, ckpt, err)))
            rc = reopen_output(sc, o, s.step, &w, &wr, err);
    } else if (!rc) {
        /* everything that can fail on the scenario is done before the output
         * is created: a refused scenario leaves no file and harms none */
        sim_plan_apply(&plan, &s);
        if (!(rc = dem_neighbours_build(&s, err)))
            dem_forces(&s);
        if (!rc)
            rc = dem_check_state(&s, err);
        if (!rc) {
            remove(ckpt);
            rc = open_output(sc, o->output, &wo, &w, err);
        }
        if (!rc && plan.output_from == 0)
            rc = write_frame(&s, &plan, &f, w, err);
    }
    double t0 = now(), last = t0, last_ckpt = -INFINITY;
    int64_t first = s.step;
    while (!rc && s.step < plan.total_steps) {
        sim_plan_apply(&plan, &s);
        if ((rc = dem_step(&s, err)))
            break;
        int frame = s.step >= plan.output_from && s.step % sc->output_every == 0;
        if (frame && !(rc = dem_check_state(&s, err)))
            rc = write_frame(&s, &plan, &f, w, err);
        int stop = o->stop_at > 0 && s.step >= o->stop_at;
        int ckpt_now = stop || s.step == plan.total_steps ||
                       (sc->checkpoint_every > 0 ? s.step % sc->checkpoint_every == 0
                                                 : frame && now() - last_ckpt >= CHECKPOINT_SECONDS);
        if (!rc && ckpt_now) {
            rc = sim_checkpoint_write(&s, state, nstate, ckpt, err);
            last_ckpt = now();
        }
        if (!rc && o->progress && (s.step % 100 == 0 || s.step == plan.total_steps)) {
            double t = now();
            if (t - last >= 0.5 || s.step == plan.total_steps) {
                last = t;
                double rate = (double)(s.step - first) / (t - t0 > 0 ? t - t0 : 1e-9);
                sim_progress p = {s.step, plan.total_steps, (double)s.step * s.dt, rate,
                                  rate > 0 ? (double)(plan.total_steps - s.step) / rate : 0,
                                  s.n, mimas_writer_frames(w)};
                o->progress(o->ctx, &p);
            }
        }
        if (stop)
            break;
    }
    /* the frames written so far stay readable, whatever stopped the run */
    if (w) {
        int rc2 = mimas_writer_close(w, rc ? NULL : err);
        if (!rc)
            rc = rc2;
        if (!rc && o->resume) {
            char sidecar[4200];
            mimas_xdmf_path(o->output, NULL, sidecar, sizeof sidecar);
            rc = mimas_xdmf_trajectory(o->output, sidecar, err);
        }
    }
    if (rc == MIMAS_EDATA && o->scenario && strncmp(err->msg, "step ", 5) == 0)
        mimas_error_prefix(err, "%s", o->scenario);
    mimas_frame_free(&f);
    sim_plan_free(&plan, &s);
    dem_free(&s);
    return rc;
}
