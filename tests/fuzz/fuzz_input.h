/* Shared by the fuzz targets: put the fuzzer's bytes in a file (the readers
 * read files) and stream every frame of a reader until it ends or fails. */
#ifndef MIMAS_FUZZ_INPUT_H
#define MIMAS_FUZZ_INPUT_H

#include <stddef.h>
#include <stdint.h>

#include "reader.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

/* Writes data to a fresh temporary file named *.SUFFIX; returns its path
 * (static storage) or NULL. */
const char *fuzz_file(const uint8_t *data, size_t size, const char *suffix, int slot);
/* Opens the reader and reads all frames; any error is fine, a crash is not. */
void fuzz_read_all(const char *const *inputs, size_t n, const mimas_reader_options *o);

#endif
