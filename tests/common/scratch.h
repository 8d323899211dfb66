/* A scratch folder for a test program: cmocka group setup/teardown that make
 * and remove it, and paths inside it. */
#ifndef MIMAS_TEST_SCRATCH_H
#define MIMAS_TEST_SCRATCH_H

int scratch_setup(void **state);
int scratch_teardown(void **state);
/* "SCRATCH/name" (32 rotating buffers: several may be in use at once). */
const char *scratch_path(const char *name);

#endif
