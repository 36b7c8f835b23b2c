/* verify.c — the verdict on a kernel's rotated coefficients against a golden
 * fixture, and the diagnosis of a mismatch by the known mistakes
 * (shlab/verify.h).  `shlab verify`, the plug-in runner and the Python
 * package all judge through here, so they agree to the letter. */
#include "core/shlab_internal.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

static const char *const mistake_desc[SH_MISTAKE_COUNT] = {
    "other CS-phase convention (cs vs nocs; the same as β negated: R(α,-β,γ) = S R S)",
    "inverse rotation (frame rotation / transposed matrix / conjugated quaternion)",
    "alpha and gamma swapped (Rz(γ)Ry(β)Rz(α))",
    "beta negated (Ry(-β): left-handed y rotation)",
    "degrees taken as radians (angles scaled by π/180)",
    "radians taken as degrees (angles scaled by 180/π)",
    "m-descending order within each band (input and output)",
    "m-descending order of the output within each band",
    "m-descending order of the input within each band",
};
static const char *const mistake_short[SH_MISTAKE_COUNT] = {
    "convention", "inverse", "swap", "beta", "deg2rad", "rad2deg", "mdesc", "mdesc-out", "mdesc-in",
};

const char *sh_mistake_name(sh_mistake t) { return (unsigned)t < SH_MISTAKE_COUNT ? mistake_short[t] : "?"; }
const char *sh_mistake_description(sh_mistake t) { return (unsigned)t < SH_MISTAKE_COUNT ? mistake_desc[t] : "?"; }

int sh_mistake_parse(const char *s, sh_mistake *out)
{
    for (int t = 0; s && t < SH_MISTAKE_COUNT; t++)
        if (!strcmp(s, mistake_short[t])) {
            *out = (sh_mistake)t;
            return SH_OK;
        }
    return sh_error(SH_EINVAL, "unknown mistake '%s' (convention, inverse, swap, beta, deg2rad, rad2deg, mdesc, "
                               "mdesc-out, mdesc-in)", s ? s : "");
}

/* out = in with m reversed within each band of the case's shape. */
static void reverse_bands(const sh_fixture_case *c, const double *in, double *out)
{
    const int l0 = c->band >= 0 ? c->band : 0, l1 = c->band >= 0 ? c->band : c->order - 1;
    for (int l = l0; l <= l1; l++) {
        const int off = c->band >= 0 ? 0 : l * l, w = 2 * l + 1;
        for (int i = 0; i < w; i++) out[off + i] = in[off + w - 1 - i];
    }
}

int sh_fixture_simulate(sh_mistake t, const sh_fixture_case *c, double *out)
{
    if ((unsigned)t >= SH_MISTAKE_COUNT || !c || !out) return sh_error(SH_EINVAL, "sh_fixture_simulate: bad argument");
    sh_rotation r = c->rot;
    const double a = c->rot.alpha, b = c->rot.beta, g = c->rot.gamma;
    /* the exact method for the case's size: Wigner to band 20, MPFR above */
    const sh_rot_method m = c->band > 20 ? SH_ROT_REFERENCE : SH_ROT_WIGNER;
    sh_convention conv = c->conv;
    const double *in = c->input;
    double *tmp = NULL;
    if (t == SH_MISTAKE_MDESC || t == SH_MISTAKE_MDESC_IN || t == SH_MISTAKE_MDESC_OUT) {
        tmp = malloc((size_t)c->n * sizeof *tmp);
        if (!tmp) return sh_error(SH_ENOMEM, "out of memory");
    }
    switch (t) {
    case SH_MISTAKE_CONVENTION: conv = conv == SH_CS ? SH_NOCS : SH_CS; break;
    case SH_MISTAKE_INVERSE: sh_rotation_inverse(&c->rot, &r); break;
    case SH_MISTAKE_SWAP: sh_rotation_from_euler(g, b, a, &r); break;
    case SH_MISTAKE_BETA: sh_rotation_from_euler(a, -b, g, &r); break;
    case SH_MISTAKE_DEG2RAD: sh_rotation_from_euler(a * M_PI / 180, b * M_PI / 180, g * M_PI / 180, &r); break;
    case SH_MISTAKE_RAD2DEG: sh_rotation_from_euler(a * 180 / M_PI, b * 180 / M_PI, g * 180 / M_PI, &r); break;
    case SH_MISTAKE_MDESC:
    case SH_MISTAKE_MDESC_IN: reverse_bands(c, c->input, tmp); in = tmp; break;
    default: break;
    }
    int st = sh_fixture_apply(m, SH_PREC_DOUBLE, SH_KERNEL_AUTO, 0, c, &r, conv, in, out);
    if (!st && (t == SH_MISTAKE_MDESC || t == SH_MISTAKE_MDESC_OUT)) {
        memcpy(tmp, out, (size_t)c->n * sizeof *tmp);
        reverse_bands(c, tmp, out);
    }
    free(tmp);
    return st;
}

/* max |a_i − b_i| and where; a NaN counts as worst (INFINITY). */
static double max_err(const double *a, const double *b, int n, int *at)
{
    double w = 0;
    *at = 0;
    for (int i = 0; i < n; i++) {
        const double e = fabs(a[i] - b[i]);
        if (isnan(e)) { *at = i; return INFINITY; }
        if (!(e <= w)) { w = e; *at = i; }
    }
    return w;
}

static int bad_args(const sh_fixture *fx, double *const *got, const void *out)
{
    return !fx || !fx->cases || fx->ncases < 1 || !got || !out;
}

int sh_verify_judge(const sh_fixture *fx, const unsigned char *skip, double *const *got, sh_precision tol,
                    sh_verdict *v)
{
    if (bad_args(fx, got, v)) return sh_error(SH_EINVAL, "sh_verify_judge: no fixture, outputs or verdict");
    memset(v, 0, sizeof *v);
    v->cases = fx->ncases;
    v->worst_case = -1;
    double worst_ratio = -1;
    for (int k = 0; k < fx->ncases; k++) {
        const sh_fixture_case *c = &fx->cases[k];
        if (skip && skip[k]) continue;
        v->run++;
        const double t = tol == SH_PREC_FLOAT ? c->tol_float : c->tol_double;
        int at;
        const double e = max_err(got[k], c->expected, c->n, &at);
        if (!(e <= t)) v->failed++;
        if (!(e <= t) && e <= c->tol_float) v->failed_near++;
        if (!(e / t <= worst_ratio)) {
            worst_ratio = e / t;
            v->worst_case = k;
            v->worst_index = at;
            v->worst_error = e;
            v->worst_tolerance = t;
        }
    }
    return SH_OK;
}

/* The mistake that explains every case it changes (at the float32
 * tolerance) and the most of them; -1 if none. */
static int best_mistake(const sh_fixture *fx, const unsigned char *skip, double *const *got,
                        void (*progress)(void *, long, long), void *ctx, int *n_ok, int *n_seen)
{
    int maxn = 1;
    for (int k = 0; k < fx->ncases; k++) maxn = fx->cases[k].n > maxn ? fx->cases[k].n : maxn;
    double *y = malloc((size_t)maxn * sizeof *y);
    if (!y) return -2;
    int best = -1;
    *n_ok = *n_seen = 0;
    const long total = (long)SH_MISTAKE_COUNT * fx->ncases;
    for (int t = 0; t < SH_MISTAKE_COUNT; t++) {
        /* β negated is the convention flip itself: d(-β) = S d(β) S with
         * S = (-1)^m, and S commutes with the z rotations (docs/rotation.md) */
        if (t == SH_MISTAKE_BETA) continue;
        int ok = 0, seen = 0;
        for (int k = 0; k < fx->ncases; k++) {
            const sh_fixture_case *c = &fx->cases[k];
            int at;
            if (progress) progress(ctx, (long)t * fx->ncases + k + 1, total);
            if (skip && skip[k]) continue;
            if (sh_fixture_simulate((sh_mistake)t, c, y)) continue;
            /* a transformation that changes nothing (β = 0, say) proves nothing */
            if (max_err(y, c->expected, c->n, &at) <= c->tol_float) continue;
            seen++;
            if (max_err(got[k], y, c->n, &at) <= c->tol_float) ok++;
        }
        /* the transformation must explain every case it changes */
        if (ok > *n_ok && ok == seen) *n_ok = ok, best = t, *n_seen = seen;
    }
    free(y);
    return best;
}

int sh_verify_diagnose(const sh_fixture *fx, const unsigned char *skip, double *const *got, sh_precision tol,
                       void (*progress)(void *ctx, long done, long total), void *ctx, sh_diagnosis *d)
{
    if (bad_args(fx, got, d)) return sh_error(SH_EINVAL, "sh_verify_diagnose: no fixture, outputs or diagnosis");
    memset(d, 0, sizeof *d);
    /* float precision only: every run case within its float32 tolerance */
    int float_ok = 0, run = 0;
    for (int k = 0; k < fx->ncases; k++) {
        int at;
        if (skip && skip[k]) continue;
        run++;
        if (max_err(got[k], fx->cases[k].expected, fx->cases[k].n, &at) <= fx->cases[k].tol_float) float_ok++;
    }
    if (tol == SH_PREC_DOUBLE && run > 0 && float_ok == run) {
        d->found = d->float_only = 1;
        d->cause = "float precision only: every case matches within its float32 tolerance";
        d->matches = d->checked = float_ok;
        return SH_OK;
    }
    const int best = best_mistake(fx, skip, got, progress, ctx, &d->matches, &d->checked);
    if (best == -2) return sh_error(SH_ENOMEM, "out of memory");
    d->found = best >= 0;
    d->mistake = best >= 0 ? (sh_mistake)best : SH_MISTAKE_COUNT;
    d->cause = best >= 0 ? mistake_desc[best] : "no known transformation explains the mismatch";
    return SH_OK;
}
