/* identify.c — name a user's SH convention from data (shlab/convention.h):
 * every candidate descriptor is compared with the data band by band, the
 * candidates that fit are grouped into classes of identical bases, and the
 * answer is one class (identified), several (ambiguous: and the order that
 * would tell them apart), or none (the nearest ones).
 *
 * Residual of a candidate through band L (relative RMS):
 *   r_L = sqrt(Σ_{band ≤ L} (data − model)²) / sqrt(Σ_{band ≤ L} model²),
 * model = the candidate's basis at the directions (basis data), or shlab's
 * reference coefficients seen in the candidate's formula frame (projection
 * data: both sides as coefficients on shlab's functions, where every
 * conversion is band by band and the axes an orthogonal map, so the
 * residual is the same as in shlab's frame). */
#include "shlab.h"
#include "convention_internal.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* Directions at which two candidates are compared as functions: a Fibonacci
 * spiral of 64 points (z_j = 1 − (2j+1)/64, φ_j = j·π(3−√5) + 0.3), which
 * no signed permutation maps onto itself and on which no non-zero
 * polynomial of degree ≤ 7 in the coordinates that we compare vanishes
 * everywhere in practice (64 ≥ 8² would be needed for a guarantee at order
 * 8; the classes are also checked at the data's own points). */
#define NCHECK 64
#define CMP_MAX_ORDER 8

static void check_dir(int j, double d[3])
{
    const double z = 1.0 - (2.0 * j + 1.0) / NCHECK, r = sqrt(1.0 - z * z);
    const double ph = j * M_PI * (3.0 - sqrt(5.0)) + 0.3;
    d[0] = r * cos(ph);
    d[1] = r * sin(ph);
    d[2] = z;
}

static int max_order_of(const sh_conv *c)
{
    return (c->norm == SH_CNORM_FUMA || c->index == SH_CINDEX_FUMA) ? SH_CONV_FUMA_MAX_ORDER : CMP_MAX_ORDER;
}

/* 1 if a and b (same kind) are different functions at `order`: values at
 * the check directions differ by more than 1e-9 of their scale. */
static int differ_at(const sh_conv *a, const sh_conv *b, int order)
{
    if (a->kind != b->kind) return 1;
    const size_t nd = sh_conv_ndoubles(a, order);
    double *va = malloc(sizeof(double) * nd * 2), *vb = va ? va + nd : NULL;
    if (!va) return 1;
    int diff = 0;
    for (int j = 0; j < NCHECK && !diff; j++) {
        double d[3];
        check_dir(j, d);
        if (sh_conv_eval_dir(a, order, d, va) || sh_conv_eval_dir(b, order, d, vb)) { diff = 1; break; }
        for (size_t k = 0; k < nd; k++)
            if (fabs(va[k] - vb[k]) > 1e-9 * (1.0 + fabs(va[k]))) { diff = 1; break; }
    }
    free(va);
    return diff;
}

/* Same class: the same functions at every order both define (to 8). */
static int same_class(const sh_conv *a, const sh_conv *b)
{
    const int ma = max_order_of(a), mb = max_order_of(b);
    return !differ_at(a, b, ma < mb ? ma : mb);
}

/* The plainest name first: z-up, then the named y-up axes; neg-sin; acn. */
static int cost(const sh_conv *c)
{
    const int ax = c->axes == 0 ? 0 : (c->axes == 12 || c->axes == 8) ? 1 : 2 + sh_conv_axes_mirror(c->axes);
    return ax * 1000 + c->neg_cos * 100 + (int)c->index * 10 + (c->cs ? 0 : 1);
}

typedef struct {
    sh_conv c;
    int order;
    double band_sq[SH_IDENTIFY_MAX_ORDER], band_ref[SH_IDENTIFY_MAX_ORDER];
    double residual;
} cand;

static void finish_residuals(cand *k, sh_id_candidate *out, double tol)
{
    double num = 0, den = 0;
    out->fits_through = 0;
    int ok = 1;
    for (int l = 0; l < SH_IDENTIFY_MAX_ORDER; l++) {
        if (l < k->order) {
            num += k->band_sq[l];
            den += k->band_ref[l];
            out->band_residual[l] = sqrt(num) / sqrt(den > 1e-300 ? den : 1e-300);
            if (ok && out->band_residual[l] <= tol) out->fits_through = l + 1;
            else ok = 0;
        } else {
            out->band_residual[l] = 0;
        }
    }
    out->order = k->order;
    out->residual = k->residual;
    out->fits = k->residual <= tol;
}

static int by_residual(const void *a, const void *b)
{
    const cand *x = a, *y = b;
    if (x->residual != y->residual) return x->residual < y->residual ? -1 : 1;
    return cost(&x->c) - cost(&y->c);
}

static int by_cost(const void *a, const void *b)
{
    return cost(&((const sh_id_candidate *)a)->conv) - cost(&((const sh_id_candidate *)b)->conv);
}

/* Every descriptor of this kind at this order. */
static int enumerate(sh_conv_kind kind, int order, cand *out)
{
    int n = 0;
    if (kind == SH_KIND_REAL) {
        static const sh_conv_norm norms[] = {SH_CNORM_ORTHO, SH_CNORM_4PI, SH_CNORM_SCHMIDT, SH_CNORM_FUMA};
        const int fuma_ok = order <= SH_CONV_FUMA_MAX_ORDER;
        for (int cs = 1; cs >= 0; cs--)
            for (int nm = 0; nm < 4; nm++)
                for (int ix = 0; ix < 4; ix++)
                    for (int ng = 0; ng < 2; ng++)
                        for (int ax = 0; ax < SH_CONV_NAXES; ax++) {
                            if (!fuma_ok && (norms[nm] == SH_CNORM_FUMA || ix == SH_CINDEX_FUMA)) continue;
                            sh_conv c = {kind, cs, norms[nm], (sh_conv_index)ix, ng, ax};
                            memset(&out[n], 0, sizeof *out);
                            out[n].c = c;
                            out[n++].order = order;
                        }
    } else {
        for (int cs = 1; cs >= 0; cs--)
            for (int ax = 0; ax < SH_CONV_NAXES; ax++) {
                sh_conv c = {kind, cs, SH_CNORM_ORTHO, SH_CINDEX_ACN, 0, ax};
                memset(&out[n], 0, sizeof *out);
                out[n].c = c;
                out[n++].order = order;
            }
    }
    return n;
}
#define MAX_CAND (2 * 4 * 4 * 2 * SH_CONV_NAXES + 2 * 2 * SH_CONV_NAXES)

/* The same functions under the ambisonics name: schmidt → sn3d, 4pi → n3d. */
static sh_conv twin(sh_conv c)
{
    c.norm = c.norm == SH_CNORM_SCHMIDT ? SH_CNORM_SN3D : c.norm == SH_CNORM_4PI ? SH_CNORM_N3D : c.norm;
    return c;
}

static void add_alias(sh_id_candidate *k, sh_conv c)
{
    if (k->naliases < SH_IDENTIFY_MAX_ALIASES) k->aliases[k->naliases] = c;
    k->naliases++;
}

/* Group cands[0..n) (sorted) into classes; at most maxc classes kept.
 * Returns the number of classes written to out. */
static int group(cand *cands, int n, int maxc, double tol, sh_id_candidate *out)
{
    int nc = 0;
    int *cls = malloc(sizeof(int) * (n ? n : 1));
    if (!cls) return 0;
    for (int i = 0; i < n; i++) {
        cls[i] = -1;
        for (int q = 0; q < nc && cls[i] < 0; q++)
            if (cands[i].c.kind == out[q].conv.kind && cands[i].order == out[q].order &&
                fabs(cands[i].residual - out[q].residual) <= 1e-9 * (1 + out[q].residual) &&
                same_class(&cands[i].c, &out[q].conv))
                cls[i] = q;
        if (cls[i] >= 0) {
            sh_id_candidate *k = &out[cls[i]];
            if (cost(&cands[i].c) < cost(&k->conv)) { add_alias(k, k->conv); k->conv = cands[i].c; }
            else add_alias(k, cands[i].c);
        } else if (nc < maxc) {
            memset(&out[nc], 0, sizeof out[nc]);
            out[nc].conv = cands[i].c;
            finish_residuals(&cands[i], &out[nc], tol);
            cls[i] = nc++;
        } else {
            break;
        }
    }
    for (int q = 0; q < nc; q++) {
        /* sn3d/n3d are schmidt/4pi by other names: the twin is an alias, or
         * the name when it makes a preset (ambix) */
        const sh_conv c = out[q].conv, tw = twin(c);
        if (tw.norm != c.norm) {
            if (sh_conv_preset(&tw) && !sh_conv_preset(&c)) { out[q].conv = tw; add_alias(&out[q], c); }
            else add_alias(&out[q], tw);
        }
        if (out[q].naliases > SH_IDENTIFY_MAX_ALIASES) out[q].naliases = SH_IDENTIFY_MAX_ALIASES;
    }
    free(cls);
    return nc;
}

/* Verdict, and for several classes the order (or the input) that decides. */
static int conclude(cand *cands, int n, double tol, int projection, sh_id_result *res)
{
    qsort(cands, (size_t)n, sizeof *cands, by_residual);
    int nfit = 0;
    while (nfit < n && cands[nfit].residual <= tol) nfit++;
    res->cand = calloc(nfit ? (size_t)nfit : 5, sizeof *res->cand);
    if (!res->cand) return sh_error(SH_ENOMEM, "out of memory");
    if (!nfit) {
        res->verdict = SH_ID_NONE;
        res->ncand = group(cands, n < 400 ? n : 400, 5, tol, res->cand);
        return SH_OK;
    }
    res->ncand = group(cands, nfit, nfit, tol, res->cand);
    /* every class fits: the plainest name first */
    qsort(res->cand, (size_t)res->ncand, sizeof *res->cand, by_cost);
    res->verdict = res->ncand == 1 ? SH_ID_IDENTIFIED : SH_ID_AMBIGUOUS;
    for (int a = 0; a < res->ncand; a++)
        for (int b = a + 1; b < res->ncand; b++) {
            const sh_conv *x = &res->cand[a].conv, *y = &res->cand[b].conv;
            const int ord = res->cand[a].order;
            if (x->kind != y->kind || res->cand[b].order != ord) continue; /* needs --order */
            if (projection && differ_at(x, y, ord)) { res->needs_basis = 1; continue; }
            const int mx = max_order_of(x) < max_order_of(y) ? max_order_of(x) : max_order_of(y);
            for (int L = ord + 1; L <= mx; L++)
                if (differ_at(x, y, L)) {
                    if (L > res->needs_order) res->needs_order = L;
                    break;
                }
        }
    return SH_OK;
}

static int check_common(int order, double tol)
{
    if (order < 0 || order > SH_IDENTIFY_MAX_ORDER)
        return sh_error(SH_EINVAL, "identify reads orders 1..%d, not %d", SH_IDENTIFY_MAX_ORDER, order);
    if (!(tol > 0 && tol < 1)) return sh_error(SH_EINVAL, "tolerance %g is outside (0, 1)", tol);
    return SH_OK;
}

/* The kinds (and their orders) whose vectors have nd doubles. */
static int kinds_for(size_t nd, int order, int orders[3])
{
    int any = 0;
    for (int k = 0; k < 3; k++) {
        sh_conv c = sh_conv_shlab();
        c.kind = (sh_conv_kind)k;
        int o = 0;
        orders[k] = 0;
        if (order ? sh_conv_ndoubles(&c, order) == nd : (!sh_conv_order_of(&c, nd, &o) && o <= SH_IDENTIFY_MAX_ORDER))
            orders[k] = order ? order : o, any = 1;
    }
    return any;
}

static int no_kind(size_t nd, int order)
{
    if (order)
        return sh_error(SH_EINVAL, "%zu numbers per vector: order %d needs %d (real), %d (complex, re,im) or "
                        "%d (complex-half)", nd, order, order * order, 2 * order * order, order * (order + 1));
    return sh_error(SH_EINVAL, "%zu numbers per vector is no order 1..%d of real (n²), complex (2n²) or "
                    "complex-half (n(n+1)) coefficients", nd, SH_IDENTIFY_MAX_ORDER);
}

/* Residuals of candidates of one kind and order against basis values.  The
 * real kinds read shlab's basis at the directions turned by each axes once
 * (Y[j·n² + i] = y_i(S d_j)); U_k = w_k y_{i_k} (sh__conv_real_entry). */
static int basis_residuals(int ndir, const double *dirs, size_t per_dir, const double *values, cand *c0,
                           int nc)
{
    const int order = c0->order, n2 = order * order;
    double *Y = malloc(sizeof(double) * ((size_t)ndir * n2 + per_dir + n2));
    if (!Y) return sh_error(SH_ENOMEM, "out of memory");
    double *v = Y + (size_t)ndir * n2, *w = v + per_dir;
    int *idx = malloc(sizeof(int) * n2), st = idx ? SH_OK : sh_error(SH_ENOMEM, "out of memory");
    for (int a = 0; a < SH_CONV_NAXES && !st; a++) {
        double S[9];
        sh_conv_axes_matrix(a, S);
        for (int j = 0; j < ndir && !st && c0->c.kind == SH_KIND_REAL; j++) {
            const double *d = dirs + 3 * j;
            double s[3];
            for (int r = 0; r < 3; r++) s[r] = S[3 * r] * d[0] + S[3 * r + 1] * d[1] + S[3 * r + 2] * d[2];
            st = sh_eval_dir(order, SH_CS, s, Y + (size_t)j * n2);
        }
        for (int q = 0; q < nc && !st; q++) {
            cand *c = &c0[q];
            if (c->c.axes != a) continue;
            if (c->c.kind == SH_KIND_REAL)
                for (int k = 0; k < n2; k++) sh__conv_real_entry(&c->c, k, &idx[k], &w[k]);
            for (int j = 0; j < ndir && !st; j++) {
                if (c->c.kind == SH_KIND_REAL)
                    for (int k = 0; k < n2; k++) v[k] = w[k] * Y[(size_t)j * n2 + idx[k]];
                else
                    st = sh_conv_eval_dir(&c->c, order, dirs + 3 * j, v);
                for (size_t k = 0; k < per_dir && !st; k++) {
                    const int l = sh_conv_band_of(&c->c, order, k);
                    const double e = values[(size_t)j * per_dir + k] - v[k];
                    c->band_sq[l] += e * e;
                    c->band_ref[l] += v[k] * v[k];
                }
            }
            double num = 0, den = 0;
            for (int l = 0; l < order; l++) num += c->band_sq[l], den += c->band_ref[l];
            c->residual = sqrt(num / (den > 1e-300 ? den : 1e-300));
        }
    }
    free(idx);
    free(Y);
    return st;
}

int sh_identify_basis(int ndir, const double *dirs, size_t per_dir, const double *values, int order,
                      double tol, sh_id_result *res)
{
    memset(res, 0, sizeof *res);
    res->tol = tol;
    int st = check_common(order, tol), orders[3];
    if (st) return st;
    if (ndir < 1) return sh_error(SH_EINVAL, "no directions");
    if (!kinds_for(per_dir, order, orders)) return no_kind(per_dir, order);
    cand *cands = malloc(sizeof(cand) * MAX_CAND);
    if (!cands) return sh_error(SH_ENOMEM, "out of memory");
    int n = 0;
    for (int k = 0; k < 3 && !st; k++)
        if (orders[k]) {
            const int n0 = n;
            n += enumerate((sh_conv_kind)k, orders[k], cands + n);
            st = basis_residuals(ndir, dirs, per_dir, values, cands + n0, n - n0);
        }
    if (!st) st = conclude(cands, n, tol, 0, res);
    free(cands);
    return st;
}

int sh_identify_projection(size_t nd, const double *coeffs, const double *ref, int ref_order, int order,
                           double tol, sh_id_result *res)
{
    memset(res, 0, sizeof *res);
    res->tol = tol;
    int st = check_common(order, tol), orders[3];
    if (st) return st;
    if (!kinds_for(nd, order, orders)) return no_kind(nd, order);
    for (int k = 0; k < 3; k++)
        if (orders[k] > ref_order)
            return sh_error(SH_EINVAL, "the reference has order %d, the data order %d", ref_order, orders[k]);
    const int maxo = orders[0] > orders[1] ? (orders[0] > orders[2] ? orders[0] : orders[2])
                                           : (orders[1] > orders[2] ? orders[1] : orders[2]);
    const size_t nn = (size_t)maxo * maxo;
    cand *cands = malloc(sizeof(cand) * MAX_CAND);
    double *bref = malloc(sizeof(double) * nn * (SH_CONV_NAXES * 3 + 1)), *b = bref + nn * SH_CONV_NAXES * 3;
    if (!cands || !bref) { free(cands); free(bref); return sh_error(SH_ENOMEM, "out of memory"); }
    /* shlab's reference in the formula frame of every axes and order:
     * bref = coefficients with Σ bref_i y_i(S d) = ref(d) */
    for (int k = 0; k < 3 && !st; k++)
        for (int a = 0; orders[k] && a < SH_CONV_NAXES && !st; a++) {
            sh_conv f = sh_conv_shlab();
            f.axes = a;
            st = sh_conv_from_shlab(&f, orders[k], ref, bref + nn * (SH_CONV_NAXES * k + a));
        }
    int n = 0;
    for (int k = 0; k < 3; k++)
        if (orders[k]) n += enumerate((sh_conv_kind)k, orders[k], cands + n);
    for (int i = 0; i < n && !st; i++) {
        cand *c = &cands[i];
        sh_conv f = c->c;
        f.axes = 0;
        st = sh_conv_to_shlab(&f, c->order, coeffs, b);
        const double *r = bref + nn * (SH_CONV_NAXES * c->c.kind + c->c.axes);
        double num = 0, den = 0;
        for (int q = 0; q < c->order * c->order && !st; q++) {
            int l, m;
            sh_index_lm(q, &l, &m);
            c->band_sq[l] += (b[q] - r[q]) * (b[q] - r[q]);
            c->band_ref[l] += r[q] * r[q];
            num += (b[q] - r[q]) * (b[q] - r[q]);
            den += r[q] * r[q];
        }
        c->residual = sqrt(num / (den > 1e-300 ? den : 1e-300));
    }
    if (!st) st = conclude(cands, n, tol, 1, res);
    free(bref);
    free(cands);
    return st;
}

void sh_identify_free(sh_id_result *res)
{
    if (!res) return;
    free(res->cand);
    res->cand = NULL;
    res->ncand = 0;
}

void sh_identify_text(const sh_id_result *r, const char *file, sh_id_text *t)
{
    memset(t, 0, sizeof *t);
    if (r->verdict == SH_ID_IDENTIFIED && r->ncand > 0) {
        sh_conv_format(&r->cand[0].conv, t->convention, sizeof t->convention);
        snprintf(t->to_shlab, sizeof t->to_shlab, "shlab convert --from %s --to cs --in %.380s", t->convention,
                 file ? file : "FILE");
        snprintf(t->from_shlab, sizeof t->from_shlab, "shlab convert --from cs --to %s --in FILE", t->convention);
    } else if (r->verdict == SH_ID_AMBIGUOUS) {
        if (r->needs_basis)
            snprintf(t->needs, sizeof t->needs, "the basis values (--basis): the light's coefficients do not tell these apart");
        else if (r->needs_order)
            snprintf(t->needs, sizeof t->needs, "band %d (order %d): these agree on bands 0..%d", r->needs_order - 1,
                     r->needs_order, r->ncand ? r->cand[0].order - 1 : 0);
        else
            snprintf(t->needs, sizeof t->needs, "--order: the count of numbers fits several kinds");
    } else {
        snprintf(t->needs, sizeof t->needs, "no convention fits within %g; the nearest are listed", r->tol);
    }
}
