/* exp.h — small helpers shared by the experiments (not part of libshlab).
 *
 * Every experiment is a program experiments/<name>/<name>.c run as
 *   <name> OUTDIR
 * It writes its data files into OUTDIR (reports/<name>/), each with a header
 * naming the columns, the shlab revision and the command; a gnuplot script
 * experiments/<name>/NAME.gp renders them to PNG; and two fragments that
 * run_all.sh assembles into the report:
 *   OUTDIR/index.md    one paragraph per figure or table (what it shows)
 *   OUTDIR/claims.tsv  rows of the claims ledger (no header)
 */
#ifndef SHLAB_EXP_H
#define SHLAB_EXP_H

#include <stdio.h>

#include "shlab.h"

/* Set up from argv: OUTDIR, the revision (env REV) and the command line. */
void exp_init(int argc, char **argv);
const char *exp_outdir(void);
/* Open OUTDIR/name for writing and print the header:
 *   # <title>
 *   # shlab revision: <rev>
 *   # command: <argv...>
 *   # columns: <columns>
 * Exits the experiment (status 1) with a message if the file cannot be opened. */
FILE *exp_data(const char *name, const char *title, const char *columns);
/* Append a paragraph (printf-style) to OUTDIR/index.md. */
void exp_index(const char *fmt, ...) __attribute__((format(printf, 1, 2)));
/* Append one claims-ledger row.  verdict: reproduced | differs | not-applicable. */
void exp_claim(const char *id, const char *source, const char *statement, const char *printed,
               const char *measured, const char *tolerance, const char *verdict,
               const char *evidence);
/* Progress line on stderr. */
void exp_progress(const char *fmt, ...) __attribute__((format(printf, 1, 2)));
/* Abort the experiment with a message if st != SH_OK. */
void exp_check(int st, const char *what);

/* Environments of the scene experiments (scene_cache, scene_shadowfield):
 * the lat-long probes of PROBES_DIR (default data/probes) whose names
 * (without .exr) are listed in SCENE_PROBES (comma list), or in `dflt`
 * when SCENE_PROBES is unset; when none of them is there, the analytic
 * lights of `fallback` (a ;-separated list of sh_light_parse specs).  Fills up to
 * `max` environments and names; *have_probes says which kind.  Exits the
 * experiment on a bad file. */
int exp_scene_envs(const char *dflt, const char *fallback, sh_env **envs, char names[][64], int max, int *have_probes);

#endif
