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
 *
 * Parts.  OUTDIR itself holds the deterministic results: the same code
 * writes the same bytes, so `make report` leaves them unchanged.  Two other
 * kinds of result live in subfolders of OUTDIR, selected by exp_part():
 *   "timing"  machine-dependent results (timings), rewritten by every run;
 *             run_all.sh gathers them into reports/timing.md and
 *             reports/claims_timing.tsv, never into index.md / claims.tsv;
 *   any other name (e.g. "probes", "instructions")  a kept part: results
 *             of an optional input or tool, regenerated only when it is there
 *             and otherwise left as they are (the experiment does not select
 *             the part); its text names the revision that computed it.
 * A gnuplot script experiments/NAME/NAME.PART.gp renders into OUTDIR/PART.
 */
#ifndef SHLAB_EXP_H
#define SHLAB_EXP_H

#include <stdio.h>

#include "shlab.h"
#include "lab/lab.h"

/* Set up from argv: OUTDIR, the revision (env REV) and the command line. */
void exp_init(int argc, char **argv);
/* The folder the current part writes into (OUTDIR or OUTDIR/PART). */
const char *exp_outdir(void);
/* Select a part: NULL = OUTDIR; "timing" or a kept part's name = OUTDIR/PART
 * (created; its index.md and claims.tsv are reset the first time). */
void exp_part(const char *part);
/* The part asked for by `--part NAME` (NULL: none).  A part that is costly
 * (e.g. a sweep to a high band) is computed only on request: the experiment
 * then runs only that part (exp_part(NAME)) and leaves OUTDIR's own files
 * as they are; without the option it leaves the part as it is (kept). */
const char *exp_requested_part(void);
/* The code revision given by `make report` (env REV), or "unknown". */
const char *exp_revision(void);
/* Open OUTDIR/name for writing and print the header:
 *   # <title>
 *   # shlab revision: <rev>
 *   # command: <argv...>
 *   # columns: <columns>
 * Exits the experiment (status 1) with a message if the file cannot be opened. */
FILE *exp_data(const char *name, const char *title, const char *columns);
/* Append a paragraph (printf-style) to OUTDIR/index.md. */
void exp_index(const char *fmt, ...) __attribute__((format(printf, 1, 2)));
/* Append one claims-ledger row.  verdict: reproduced | differs | not-applicable,
 * and for speed claims (timing part) also not-measured (a noisy run) and
 * inconclusive (the ratio's uncertainty straddles the tolerance).  The form,
 * checked here (a row that breaks it ends the experiment with a message) and
 * in the assembled ledgers by tests/cli/test_ledger.sh:
 *   source     WORK or "WORK, LOCATOR" of experiments/common/sources.tsv
 *              (e.g. "Křivánek et al. 2005, Sec. 3.1", "shlab goal");
 *   every cell non-empty ("-" for none) and at most EXP_CELL_MAX characters:
 *              the detail goes to the report, the cell links its section
 *              (index.md#NAME);
 *   evidence   the data file(s); for any verdict but reproduced also
 *              "why: " and one sentence saying why, consistent with the
 *              measured cell. */
#define EXP_CELL_MAX 200
void exp_claim(const char *id, const char *source, const char *statement, const char *printed,
               const char *measured, const char *tolerance, const char *verdict,
               const char *evidence);
/* An evidence cell into buf: files, and for any verdict but reproduced
 * "; why: " and a sentence: for differs and not-applicable the caller's why,
 * for the speed verdicts not-measured (a noisy run) and inconclusive (the
 * ratio straddles the tolerance) a fixed one.  Returns buf. */
const char *exp_evidence(char *buf, size_t n, const char *files, const char *verdict, const char *why);
/* exp_claim of a claim judged by one test: verdict reproduced (evidence:
 * files) when ok, else differs (evidence: files; why: why). */
void exp_claim_judged(const char *id, const char *source, const char *statement, const char *printed,
                      const char *measured, const char *tolerance, int ok, const char *files, const char *why);
/* Speed claims (timing part).  The uncertainty of a paired ratio is its
 * quartiles over the rounds widened by ±EXP_RUN_TO_RUN, the spread of
 * paired ratios between repeated runs on a quiet machine (docs/rotation.md, "Rotation
 * speed").  EXP_INSIDE: that interval lies in [lo, hi]; EXP_OUTSIDE: wholly
 * outside it; EXP_STRADDLES: neither (the verdict is then "inconclusive"). */
#define EXP_RUN_TO_RUN 0.05
typedef enum { EXP_INSIDE, EXP_OUTSIDE, EXP_STRADDLES } exp_side;
exp_side exp_ratio_side(const sh_bench_ratio *r, double lo, double hi);
/* The verdict of a claim judged at several points (orders, ratios): "differs"
 * if one side is EXP_OUTSIDE, else "inconclusive" if one straddles, else
 * "reproduced". */
const char *exp_sides_verdict(const exp_side *s, int n);
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
/* Shards.  An experiment whose work is a list of items (bands, angles, ...)
 * can run as N processes (GNU parallel, a Slurm array), then be joined:
 *   NAME DIR_I --shard I/N   computes only the items shard I owns
 *       (sh_shard_owns) and writes them to DIR_I/shard-I-of-N.items (on
 *       success only); its other files in DIR_I are partial;
 *   NAME OUTDIR --merge FILE...   computes no item, takes every item from
 *       the N files (checked to be the shards of one run: same experiment,
 *       revision, arguments, N; each shard once; each item once) and writes
 *       exactly the output of the unsharded run.
 * The experiment numbers its items (an index fixed by its parameters) and
 * for item j with n result values v:
 *   if (exp_computes(j)) { compute v; }
 *   if (!exp_item(j, n, v)) continue;   (another shard's item)
 *   ...use v...
 * exp_item records v (--shard) or fills it from the files (--merge; an item
 * missing there ends the run with an error).  Values are kept exactly. */
int exp_computes(long item);
int exp_item(long item, int n, double *v);
/* (fallback NULL: no analytic lights; returns 0 when no probe is there.) */
/* The analytic lights of specs (;-separated sh_light_parse specs). */
int exp_scene_lights(const char *specs, sh_env **envs, char names[][64], int max);

/* The scene experiments' full study: `make report SCENES=full` (env SCENES). */
int exp_scene_full(void);
/* One line on stderr for a kept part left as it is: "NAME: PART/ kept as
 * committed (computed at code revision R): WHY" (R read from the part's
 * index.md), or "NAME: PART/ not computed (WHY)" when there is none. */
void exp_kept(const char *part, const char *why);

#endif
