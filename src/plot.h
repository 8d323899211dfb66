/* Pictures by gnuplot (the commands' --plot FILE.png): the data go to files
 * in a scratch folder, gnuplot runs a script on them (its messages are
 * kept, not printed), and the PNG is written under a temporary name and
 * renamed into place when complete. */
#ifndef MIMAS_PLOT_H
#define MIMAS_PLOT_H

#include <stdio.h>

#include "error.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct mimas_plot mimas_plot;

/* Starts a picture that will be written to png. */
int mimas_plot_open(mimas_plot **p, const char *png, mimas_error *err);
/* Creates the data file name (a plain file name) in the scratch folder and
 * returns it open for writing (closed by mimas_plot_render); in the script
 * it is datadir.'/name'. */
FILE *mimas_plot_data(mimas_plot *p, const char *name, mimas_error *err);
/* Runs gnuplot: a pngcairo terminal of width x height pixels, the output
 * (a temporary name), the string variable datadir, then script; removes
 * the scratch folder.  A missing gnuplot or a failed script is MIMAS_EIO
 * with gnuplot's last message.  p stays: commit or abort it. */
int mimas_plot_render(mimas_plot *p, int width, int height, const char *script, mimas_error *err);
/* Renames the rendered PNG into place; frees p. */
int mimas_plot_commit(mimas_plot *p, mimas_error *err);
/* Removes everything (the PNG's temporary name too); frees p (NULL is fine). */
void mimas_plot_abort(mimas_plot *p);
/* s as a gnuplot single-quoted string ('' for each quote) into buf. */
void mimas_plot_quote(const char *s, char *buf, size_t len);
/* The symbol of a field of docs/fields.md in gnuplot's enhanced text (the
 * terminal is enhanced, UTF-8): "nu" -> "ν", "stress_rphi" -> "σ_{rφ}",
 * "shear_rate" -> "γ̇", "tau_phi" -> "τ_{φ}"; other names as they are, with
 * the characters enhanced text would interpret escaped.  For single-quoted
 * strings in scripts. */
void mimas_plot_symbol(const char *field, char *buf, size_t len);
/* text with the characters of enhanced text (_ ^ @ & { } ~) escaped, for
 * single-quoted strings in scripts (a file name in a title). */
void mimas_plot_literal(const char *text, char *buf, size_t len);
/* A value with its standard error for a key, in enhanced text: both to the
 * decimal place of the error's second significant digit ("0.170 ± 0.026",
 * "410 ± 61", "-7 ± 12"), with a power of ten factored out when the larger
 * of the two is below 1e-4 or from 1e6 on ("(1.23 ± 0.45)×10^{-7}").  A
 * value without a usable error (not finite, not positive, or below 1e-9 of
 * the value) is printed alone to 4 digits. */
void mimas_plot_value_error(double v, double e, char *buf, size_t len);

#ifdef __cplusplus
}
#endif
#endif
