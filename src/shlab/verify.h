/* shlab/verify.h — golden rotation fixtures, the verdict on a kernel's
 * outputs, and the diagnosis of a mismatch (the known mistakes).  The
 * library side of `shlab verify`; the Python package and the plug-in runner
 * use the same functions, so they print the same verdicts and diagnoses.
 * Fixture format: data/fixtures/rotation/README.md.
 * Part of the public API: include <shlab.h>, which includes every part. */
#ifndef SHLAB_VERIFY_H
#define SHLAB_VERIFY_H

#include <stddef.h>

#include "rotate.h"

#ifdef __cplusplus
extern "C" {
#endif

/* A golden case: rotate `input` (order² coefficients, or the 2L+1 of band L
 * when band >= 0) by `rot` in `conv`; `expected` is exact to double rounding
 * (MPFR reference), `expected_f` the same rounded to float32. */
typedef struct {
    char id[64];
    int order, band;
    sh_convention conv;
    sh_rotation rot;
    int n; /* number of coefficients */
    double *input, *expected, *expected_f;
    double tol_double, tol_float;
} sh_fixture_case;
typedef struct {
    int ncases;
    sh_fixture_case *cases;
} sh_fixture;

/* Read a fixture file (format "shlab-rotation-fixtures/1"; at least one case;
 * every integer range-checked before use; ids unique printable text).
 * `name` names the text in error messages ("fixture 'F'"). */
int sh_fixture_load(const char *path, sh_fixture *fx);
int sh_fixture_load_mem(const char *buf, size_t n, const char *name, sh_fixture *fx);
void sh_fixture_free(sh_fixture *fx);
/* Read a candidate file {"results": {"<case id>": [n numbers], ...}} for the
 * cases of fx into out[k] (fx->cases[k].n values each, allocated by the
 * caller).  A case whose want[k] is 0 may be absent (want NULL: every case
 * is wanted); out[k] of an absent case is left alone and *present (if not
 * NULL) gets 0 there, 1 where the file has it. */
int sh_fixture_load_candidate(const char *path, const sh_fixture *fx, const unsigned char *want,
                              double **out, unsigned char *present);
int sh_fixture_load_candidate_mem(const char *buf, size_t n, const char *name, const sh_fixture *fx,
                                  const unsigned char *want, double **out, unsigned char *present);

/* out = R_sh(rot)·in for a case's shape (its order, or band only), by
 * method m in precision prec; kernel: the plan's code (SH_KERNEL_AUTO), and
 * with matrix != 0 the rotation given as its matrix. */
int sh_fixture_apply(sh_rot_method m, sh_precision prec, sh_rot_kernel kernel, int matrix,
                     const sh_fixture_case *c, const sh_rotation *rot, sh_convention conv,
                     const double *in, double *out);

/* ------------------------------------------------------------ mistakes */
/* What a wrong kernel does that --diagnose recognises. */
typedef enum {
    SH_MISTAKE_CONVENTION, /* the other CS-phase convention */
    SH_MISTAKE_INVERSE,    /* the inverse (frame) rotation */
    SH_MISTAKE_SWAP,       /* α and γ swapped */
    SH_MISTAKE_BETA,       /* β negated (the same as CONVENTION; never diagnosed) */
    SH_MISTAKE_DEG2RAD,    /* degrees taken as radians */
    SH_MISTAKE_RAD2DEG,    /* radians taken as degrees */
    SH_MISTAKE_MDESC,      /* m descending within each band, input and output */
    SH_MISTAKE_MDESC_OUT,  /* ... of the output only */
    SH_MISTAKE_MDESC_IN,   /* ... of the input only */
    SH_MISTAKE_COUNT
} sh_mistake;
/* The short name (--simulate's: "convention", "inverse", "swap", "beta",
 * "deg2rad", "rad2deg", "mdesc", "mdesc-out", "mdesc-in") and the one-line
 * description a diagnosis prints. */
const char *sh_mistake_name(sh_mistake t);
const char *sh_mistake_description(sh_mistake t);
int sh_mistake_parse(const char *s, sh_mistake *out);
/* What a kernel with mistake t outputs for case c (exact method, double). */
int sh_fixture_simulate(sh_mistake t, const sh_fixture_case *c, double *out);

/* ------------------------------------------------------------ verdict */
/* skip[k] != 0: case k was not run (above the kernel's order, not asked
 * for, refused by the kernel); skip NULL: every case ran.  got[k]: case k's
 * n outputs.  tol: SH_PREC_DOUBLE judges at each case's tol_double,
 * SH_PREC_FLOAT at its tol_float. */
typedef struct {
    int cases;        /* in the fixture */
    int run;          /* judged (not skipped) */
    int failed;       /* beyond their tolerance (NaN counts as beyond) */
    int failed_near;  /* of those, within the float32 tolerance */
    int worst_case;   /* by error over tolerance; -1 if none ran */
    int worst_index;  /* the coefficient of the worst case */
    double worst_error, worst_tolerance; /* INFINITY for a non-finite output */
} sh_verdict;
int sh_verify_judge(const sh_fixture *fx, const unsigned char *skip, double *const *got, sh_precision tol,
                    sh_verdict *v);

/* The likely cause of a mismatch.  "float precision only" if, judged at
 * double, every run case is within its float32 tolerance; else the known
 * mistake that explains every case it changes by more than the case's
 * float32 tolerance, and the most of them.  cause: one line (static). */
typedef struct {
    int found;          /* 1: cause names what happened */
    int float_only;     /* found, and it is float precision only */
    sh_mistake mistake; /* found && !float_only: the mistake */
    const char *cause;  /* "no known transformation explains the mismatch" if !found */
    int matches, checked;
} sh_diagnosis;
/* progress (may be NULL): called with done/total as cases are tried. */
int sh_verify_diagnose(const sh_fixture *fx, const unsigned char *skip, double *const *got, sh_precision tol,
                       void (*progress)(void *ctx, long done, long total), void *ctx, sh_diagnosis *d);

#ifdef __cplusplus
}
#endif
#endif /* SHLAB_VERIFY_H */
