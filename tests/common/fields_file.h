/* Field files with chosen contents, in the layout mimas average -o writes
 * (averaging/output_h5.c: /mimas, /grid, /fields/NAME/{mean,std,count}),
 * for the tests of the analyses that read them. */
#ifndef MIMAS_TEST_FIELDS_FILE_H
#define MIMAS_TEST_FIELDS_FILE_H

#include <stddef.h>

#include "parameters.h"

typedef struct fields_file_spec {
    const char *kind;        /* "cylindrical", "cartesian" or "none" */
    int n[3];                /* cells per direction (direction 0 fastest) */
    const double *centre[3]; /* cell centres per direction (NULL: zeros) */
    int gridded[3];
    int frames;              /* the count of every defined value */
    int version[2];          /* fields_version ({0, 0}: the current one) */
    const mimas_parameters *params; /* run parameters (/parameters/scenario), or NULL */
} fields_file_spec;

/* Writes the fields names[k] with mean[k] and standard errors sem[k]
 * (NULL: none) per cell; std = sem sqrt(frames).  Returns 0 on success. */
int write_fields_file(const char *path, const fields_file_spec *s, size_t nfields,
                      const char *const *names, const double *const *mean,
                      const double *const *sem);

#endif
