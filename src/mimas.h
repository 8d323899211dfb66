/* libmimas public interface: include this one header.
 * Link with `pkg-config --cflags --libs mimas`. */
#ifndef MIMAS_H
#define MIMAS_H

#include "error.h"
#include "frame.h"
#include "id_index.h"
#include "native.h"
#include "reader.h"
#include "voro_cells.h"
#include "average.h"
#include "field_table.h"
#include "axis.h"
#include "voronoi.h"
#include "fieldset.h"
#include "fit.h"
#include "shearband.h"
#include "rheology.h"

#ifdef __cplusplus
extern "C" {
#endif

/* The library version, e.g. "0.1.0". */
const char *mimas_version(void);

#ifdef __cplusplus
}
#endif
#endif
