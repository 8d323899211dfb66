/* The space-time diagram of mimas plugs (plugs_plot.c). */
#ifndef MIMAS_PLUGS_PLOT_H
#define MIMAS_PLUGS_PLOT_H

#include "axial_profile.h"
#include "error.h"
#include "plugs.h"

typedef struct mimas_stplot mimas_stplot;
int mimas_stplot_open(mimas_stplot **p, const char *png, const mimas_slices *sl,
                      mimas_error *err);
/* One frame's porosity column and its tracked plug centres. */
int mimas_stplot_frame(mimas_stplot *p, const mimas_axial *ax, double time,
                       const mimas_plug_list *plugs, mimas_error *err);
/* Renders with gnuplot and puts the PNG in place; frees p. */
int mimas_stplot_finish(mimas_stplot *p, mimas_error *err);
void mimas_stplot_abort(mimas_stplot *p);

#endif
