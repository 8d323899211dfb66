#include <config.h>

#include "voro_walls.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* A finite number filling the whole token. */
static int number(const char *s, double *v)
{
    char *end;
    *v = strtod(s, &end);
    return end != s && !*end && isfinite(*v);
}

static int parse_plane(char *args, mimas_voro_wall *w)
{
    char *save = NULL, *axis = strtok_r(args, ":", &save), *h = strtok_r(NULL, ":", &save);
    if (!axis || !h || strtok_r(NULL, ":", &save) || !number(h, &w->offset))
        return -1;
    double sign = 1.0;
    if (*axis == '-' || *axis == '+')
        sign = *axis++ == '-' ? -1.0 : 1.0;
    if (strlen(axis) != 1 || !strchr("xyz", *axis))
        return -1;
    memset(w->normal, 0, sizeof w->normal);
    w->normal[*axis - 'x'] = sign;
    w->offset *= sign; /* sign * x >= sign * H */
    w->kind = MIMAS_VORO_PLANE;
    return 0;
}

static int parse_cylinder(char *args, mimas_voro_wall *w)
{
    char *save = NULL, *tok[5];
    int nt = 0;
    for (char *t = strtok_r(args, ":", &save); t; t = strtok_r(NULL, ":", &save))
        if (nt < 5)
            tok[nt++] = t;
        else
            return -1;
    if (nt < 1 || !number(tok[0], &w->radius) || !(w->radius > 0))
        return -1;
    int at = 1;
    w->inner = 0;
    /* "inside" (the spelling: the cylinder inside the packing) = inner */
    if (at < nt && (!strcmp(tok[at], "inner") || !strcmp(tok[at], "inside") ||
                    !strcmp(tok[at], "outer"))) {
        w->inner = strcmp(tok[at], "outer") != 0;
        at++;
    }
    w->axis[0] = w->axis[1] = 0.0;
    if (at < nt && (nt - at != 2 || !number(tok[at], &w->axis[0]) ||
                    !number(tok[at + 1], &w->axis[1])))
        return -1;
    w->kind = MIMAS_VORO_CYLINDER;
    return 0;
}

int mimas_voro_walls_parse(const char *spec, mimas_voro_wall *walls, size_t max, size_t *n,
                           mimas_error *err)
{
    *n = 0;
    char *text = strdup(spec), *save = NULL;
    if (!text)
        return mimas_error_set(err, MIMAS_EIO, "out of memory for the walls");
    int rc = MIMAS_OK;
    for (char *tok = strtok_r(text, ",", &save); tok && !rc; tok = strtok_r(NULL, ",", &save)) {
        char *copy = strdup(tok);
        if (!copy) {
            rc = mimas_error_set(err, MIMAS_EIO, "out of memory for the walls");
            break;
        }
        mimas_voro_wall w;
        memset(&w, 0, sizeof w);
        int bad = 1;
        if (!strncmp(tok, "plane:", 6))
            bad = parse_plane(tok + 6, &w);
        else if (!strncmp(tok, "cylinder:", 9))
            bad = parse_cylinder(tok + 9, &w);
        if (bad)
            rc = mimas_error_set(err, MIMAS_EUSAGE, "bad wall '%s' (plane:AXIS:H with AXIS x, "
                                 "y, z, -x, -y or -z; cylinder:R[:outer|:inner][:X0:Y0])", copy);
        else if (*n >= max)
            rc = mimas_error_set(err, MIMAS_EUSAGE, "more than %zu walls", max);
        else
            walls[(*n)++] = w;
        free(copy);
    }
    if (!rc && *n == 0)
        rc = mimas_error_set(err, MIMAS_EUSAGE, "no wall in '%s'", spec);
    free(text);
    return rc;
}
