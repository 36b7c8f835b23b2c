/* proc.c — procedural scenes whose transfer is known in closed form.
 *
 * References:
 *  [1] Green 2003, "Spherical Harmonic Lighting: The Gritty Details", the
 *      diffuse transfer functions.
 *  [2] Howell, "A Catalog of Radiation Heat Transfer Configuration Factors",
 *      B-3: differential element parallel to a rectangle, normal through a
 *      corner.
 *  [3] The view factor from a point on the inside of a sphere to any region
 *      of the sphere is the region's area over 4πR² (the cosines at both
 *      ends equal |x−y|/2R).
 *  [4] The form factor of a sphere of radius R from a differential element at
 *      distance d, centre at angle α from the normal, wholly above the
 *      horizon: (R/d)² cos α = sin²ω cos α (a special case of the formula
 *      used below for every coefficient). */
#include "core/shlab_internal.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

const char *sh_proc_name(sh_proc_kind k)
{
    switch (k) {
    case SH_PROC_SPHERE_PLANE: return "sphere-plane";
    case SH_PROC_BOWL: return "bowl";
    case SH_PROC_BOX_OPEN: return "box-open";
    case SH_PROC_BOX_CLOSED: return "box-closed";
    }
    return "?";
}

static int default_res(sh_proc_kind k)
{
    switch (k) {
    case SH_PROC_SPHERE_PLANE: return 8;
    case SH_PROC_BOWL: return 16;
    default: return 16;
    }
}

int sh_proc_parse(const char *spec, sh_proc_scene *out)
{
    if (!spec || !out) return sh_error(SH_EINVAL, "sh_proc_parse: no scene");
    memset(out, 0, sizeof *out);
    const char *colon = strchr(spec, ':');
    const size_t len = colon ? (size_t)(colon - spec) : strlen(spec);
    static const sh_proc_kind kinds[] = {SH_PROC_SPHERE_PLANE, SH_PROC_BOWL, SH_PROC_BOX_OPEN, SH_PROC_BOX_CLOSED};
    int found = 0;
    for (size_t i = 0; i < sizeof kinds / sizeof *kinds; i++)
        if (strlen(sh_proc_name(kinds[i])) == len && !strncmp(spec, sh_proc_name(kinds[i]), len)) {
            out->kind = kinds[i];
            found = 1;
        }
    if (!found)
        return sh_error(SH_EINVAL, "unknown scene '%s' (expected sphere-plane[:R,H], bowl, box-open[:A], box-closed)",
                        spec);
    if (out->kind == SH_PROC_SPHERE_PLANE) { out->p[0] = 0.5; out->p[1] = 1.0; }
    if (out->kind == SH_PROC_BOX_OPEN) out->p[0] = 0.25;
    if (colon) {
        const int want = out->kind == SH_PROC_SPHERE_PLANE ? 2 : out->kind == SH_PROC_BOX_OPEN ? 1 : 0;
        if (want == 0) return sh_error(SH_EINVAL, "scene '%s' takes no parameters", sh_proc_name(out->kind));
        const char *s = colon + 1;
        for (int k = 0; k < want; k++) {
            char *end;
            double v = 0;
            if (sh__parse_double(s, &end, &v) != SH__NUM_OK)
                return sh_error(SH_EINVAL, "scene '%s': bad number '%s'", spec, s);
            out->p[k] = v;
            s = end;
            if (k + 1 < want) {
                if (*s != ',') return sh_error(SH_EINVAL, "scene '%s': expected %d numbers", spec, want);
                s++;
            }
        }
        if (*s) return sh_error(SH_EINVAL, "scene '%s': trailing '%s'", spec, s);
    }
    if (out->kind == SH_PROC_SPHERE_PLANE && !(out->p[0] > 0 && out->p[1] > out->p[0] && out->p[1] < 100))
        return sh_error(SH_EINVAL, "sphere-plane: need 0 < R < H < 100 (got R=%g, H=%g)", out->p[0], out->p[1]);
    if (out->kind == SH_PROC_BOX_OPEN && !(out->p[0] > 0 && out->p[0] <= 0.5))
        return sh_error(SH_EINVAL, "box-open: hole half-width must be in (0, 0.5] (got %g)", out->p[0]);
    return SH_OK;
}

/* ---------------------------------------------------------------- builder */

typedef struct {
    sh_mesh m;
    int capv, capt;
    int err;
    int count_only; /* sh_proc_size: count vertices and triangles, store nothing */
} builder;

static int b_vert(builder *b, double x, double y, double z, const double *n)
{
    if (b->count_only) return b->m.nvert++;
    if (b->m.nvert == b->capv) {
        b->capv = b->capv ? 2 * b->capv : 1024;
        double *p = realloc(b->m.pos, sizeof(double) * 3 * (size_t)b->capv);
        if (p) b->m.pos = p;
        double *q = realloc(b->m.normal, sizeof(double) * 3 * (size_t)b->capv);
        if (q) b->m.normal = q;
        if (!p || !q) { b->err = 1; b->capv = b->m.nvert; return 0; }
    }
    double *p = b->m.pos + 3 * (size_t)b->m.nvert, *q = b->m.normal + 3 * (size_t)b->m.nvert;
    p[0] = x; p[1] = y; p[2] = z;
    if (n) { q[0] = n[0]; q[1] = n[1]; q[2] = n[2]; } else q[0] = q[1] = q[2] = 0;
    return b->m.nvert++;
}

static void b_tri(builder *b, int i, int j, int k)
{
    if (b->count_only) {
        b->m.ntri++;
        return;
    }
    if (b->err) return;
    if (b->m.ntri == b->capt) {
        b->capt = b->capt ? 2 * b->capt : 2048;
        int *t = realloc(b->m.tri, sizeof(int) * 3 * (size_t)b->capt);
        if (!t) { b->err = 1; return; }
        b->m.tri = t;
    }
    int *t = b->m.tri + 3 * (size_t)b->m.ntri++;
    t[0] = i; t[1] = j; t[2] = k;
}

/* a (nu+1)×(nv+1) grid p(u,v) = o + u·eu + v·ev, u,v in [0,1]; triangles
 * counter-clockwise about eu × ev; cells whose centre satisfies skip() left
 * out (the hole). */
static void b_grid(builder *b, const double o[3], const double eu[3], const double ev[3], int nu, int nv,
                   const double *n, double hole)
{
    const int base = b->m.nvert;
    for (int j = 0; j <= nv; j++)
        for (int i = 0; i <= nu; i++) {
            const double u = (double)i / nu, v = (double)j / nv;
            b_vert(b, o[0] + u * eu[0] + v * ev[0], o[1] + u * eu[1] + v * ev[1], o[2] + u * eu[2] + v * ev[2], n);
        }
    for (int j = 0; j < nv; j++)
        for (int i = 0; i < nu; i++) {
            if (hole > 0) {
                const double cu = (i + 0.5) / nu - 0.5, cv = (j + 0.5) / nv - 0.5;
                if (fabs(cu) < hole && fabs(cv) < hole) continue;
            }
            const int a = base + j * (nu + 1) + i;
            b_tri(b, a, a + 1, a + nu + 2);
            b_tri(b, a, a + nu + 2, a + nu + 1);
        }
}

/* the box's effective hole half-width: whole cells of the top grid */
static double box_hole(const sh_proc_scene *ps, int res)
{
    return ps->kind == SH_PROC_BOX_OPEN ? round(ps->p[0] * res) / res : 0.0;
}

/* The scene's vertices and triangles into b; 1 if the normals are to be
 * computed (the box). */
static int build(const sh_proc_scene *ps, int res, builder *b_)
{
    builder b = *b_;
    int compute_normals = 0;
    if (ps->kind == SH_PROC_SPHERE_PLANE) {
        const double R = ps->p[0], H = ps->p[1], up[3] = {0, 0, 1};
        const double o[3] = {-2, -2, 0}, eu[3] = {4, 0, 0}, ev[3] = {0, 4, 0};
        b_grid(&b, o, eu, ev, 4 * res, 4 * res, up, 0);
        const int nlat = 4 * res, nlon = 8 * res;
        const int north = b_vert(&b, 0, 0, H + R, up);
        const int ring0 = b.m.nvert;
        for (int i = 1; i < nlat; i++)
            for (int j = 0; j < nlon; j++) {
                const double th = M_PI * i / nlat, ph = 2 * M_PI * j / nlon;
                const double n[3] = {sin(th) * cos(ph), sin(th) * sin(ph), cos(th)};
                b_vert(&b, R * n[0], R * n[1], H + R * n[2], n);
            }
        const double down[3] = {0, 0, -1};
        const int south = b_vert(&b, 0, 0, H - R, down);
        for (int j = 0; j < nlon; j++) b_tri(&b, north, ring0 + j, ring0 + (j + 1) % nlon);
        for (int i = 0; i + 1 < nlat - 1; i++)
            for (int j = 0; j < nlon; j++) {
                const int a = ring0 + i * nlon + j, c = ring0 + i * nlon + (j + 1) % nlon;
                b_tri(&b, a, a + nlon, c + nlon);
                b_tri(&b, a, c + nlon, c);
            }
        const int last = ring0 + (nlat - 2) * nlon;
        for (int j = 0; j < nlon; j++) b_tri(&b, south, last + (j + 1) % nlon, last + j);
    } else if (ps->kind == SH_PROC_BOWL) {
        const int nth = 2 * res, nph = 8 * res;
        const double down[3] = {0, 0, 1}; /* normal at the bottom (0,0,−1) points up */
        const int bottom = b_vert(&b, 0, 0, -1, down);
        const int ring0 = b.m.nvert;
        for (int i = 1; i <= nth; i++)
            for (int j = 0; j < nph; j++) {
                /* polar angle from the bottom; the last ring is the rim z = 0 */
                const double th = 0.5 * M_PI * i / nth, ph = 2 * M_PI * j / nph;
                const double p[3] = {sin(th) * cos(ph), sin(th) * sin(ph), i == nth ? 0.0 : -cos(th)};
                const double n[3] = {-p[0], -p[1], -p[2]};
                b_vert(&b, p[0], p[1], p[2], n);
            }
        /* counter-clockwise seen from the centre (inside) */
        for (int j = 0; j < nph; j++) b_tri(&b, bottom, ring0 + (j + 1) % nph, ring0 + j);
        for (int i = 0; i + 1 < nth; i++)
            for (int j = 0; j < nph; j++) {
                const int a = ring0 + i * nph + j, c = ring0 + i * nph + (j + 1) % nph;
                b_tri(&b, a, c + nph, a + nph);
                b_tri(&b, a, c, c + nph);
            }
    } else {
        /* six inward faces of [−½,½]²×[0,1]; each face a grid, vertices on
         * shared edges duplicated (normals computed over equal positions) */
        const double A = box_hole(ps, res);
        /* floor, top, y = −½, x = +½, y = +½, x = −½; eu × ev points inward */
        const double fo[6][3] = {{-.5, -.5, 0}, {-.5, -.5, 1}, {-.5, -.5, 0}, {.5, -.5, 0}, {-.5, .5, 0}, {-.5, -.5, 0}};
        const double fu[6][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {0, 0, 1}, {1, 0, 0}, {0, 1, 0}};
        const double fv[6][3] = {{0, 1, 0}, {1, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {0, 0, 1}};
        for (int f = 0; f < 6; f++)
            b_grid(&b, fo[f], fu[f], fv[f], res, res, NULL, f == 1 ? A : 0);
        compute_normals = 1;
    }
    *b_ = b;
    return compute_normals;
}

int sh_proc_size(const sh_proc_scene *ps, long long *nvert, long long *ntri)
{
    if (!ps || !nvert || !ntri) return sh_error(SH_EINVAL, "sh_proc_size: bad arguments");
    const int res = ps->res > 0 ? ps->res : default_res(ps->kind);
    if (res > 512) return sh_error(SH_EINVAL, "procedural scene: resolution %d > 512", res);
    builder b = {0};
    b.count_only = 1;
    build(ps, res, &b);
    *nvert = b.m.nvert;
    *ntri = b.m.ntri;
    return SH_OK;
}

int sh_mesh_procedural(const sh_proc_scene *ps, sh_mesh *out)
{
    if (!ps || !out) return sh_error(SH_EINVAL, "sh_mesh_procedural: bad arguments");
    memset(out, 0, sizeof *out);
    const int res = ps->res > 0 ? ps->res : default_res(ps->kind);
    if (res > 512) return sh_error(SH_EINVAL, "procedural scene: resolution %d > 512", res);
    builder b = {0};
    const int compute_normals = build(ps, res, &b);
    if (b.err) {
        sh_mesh_free(&b.m);
        return sh_error(SH_ENOMEM, "out of memory building %s", sh_proc_name(ps->kind));
    }
    *out = b.m;
    sh_mesh_report rep;
    int st = sh_mesh_check(out, compute_normals ? SH_MESH_COMPUTE_NORMALS : 0, &rep);
    if (st) sh_mesh_free(out);
    return st;
}

/* ------------------------------------------------------------ closed forms */

/* Howell B-3: element at distance c below the corner of an a×b rectangle in
 * a parallel plane; odd in a and in b, so rectangles anywhere are sums. */
static double howell_b3(double a, double b, double c)
{
    const double A = a / c, B = b / c, sa = sqrt(1 + A * A), sb = sqrt(1 + B * B);
    return (A / sa * atan(B / sa) + B / sb * atan(A / sb)) / (2 * M_PI);
}

/* The sphere-plane's polyhedral sphere lies between the spheres of radius
 * r_in, its faces' least distance from the centre, and R (its vertices lie
 * on the sphere of radius R; faces with a corner off it are the plane's). */
static double sphere_r_in(const sh_proc_scene *ps, const sh_mesh *m)
{
    const double R = ps->p[0], H = ps->p[1];
    double r_in = R;
    for (int f = 0; f < m->ntri; f++) {
        const double *a = m->pos + 3 * m->tri[3 * f], *b = m->pos + 3 * m->tri[3 * f + 1],
                     *e = m->pos + 3 * m->tri[3 * f + 2];
        const double ra = hypot(hypot(a[0], a[1]), a[2] - H), rb = hypot(hypot(b[0], b[1]), b[2] - H),
                     re = hypot(hypot(e[0], e[1]), e[2] - H);
        if (fabs(ra - R) > 1e-9 * R || fabs(rb - R) > 1e-9 * R || fabs(re - R) > 1e-9 * R) continue;
        const double e1[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, e2[3] = {e[0] - a[0], e[1] - a[1], e[2] - a[2]};
        const double fn[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]};
        const double fl = sqrt(fn[0] * fn[0] + fn[1] * fn[1] + fn[2] * fn[2]);
        if (fl > 0) r_in = fmin(r_in, fabs(fn[0] * a[0] + fn[1] * a[1] + fn[2] * (a[2] - H)) / fl);
    }
    return r_in;
}

/* One vertex; r_in: sphere_r_in's value (read only when bound is asked). */
static int closed_form_one(const sh_proc_scene *ps, const sh_mesh *m, int v, int order, sh_convention conv,
                           double albedo, double lift, double r_in, double *t, double *bound, int *known)
{
    if (v < 0 || v >= m->nvert) return sh_error(SH_EINVAL, "sh_proc_closed_form: vertex %d of %d", v, m->nvert);
    int st = SH_OK;
    *known = 0;
    const int n2 = order * order;
    const double *p = m->pos + 3 * v, *nv = m->normal + 3 * v;
    const double rho = albedo;
    const int res = ps->res > 0 ? ps->res : default_res(ps->kind);
    for (int i = 0; i < n2; i++) {
        t[i] = 0;
        if (bound) bound[i] = 0;
    }
    if (ps->kind == SH_PROC_BOWL) {
        if (!(p[2] < -1e-9)) return SH_OK; /* the rim itself: left out */
        /* [3]: sky through the rim = ½ of the cosine-weighted hemisphere */
        t[0] = rho * 0.5 / sqrt(4 * M_PI);
        if (bound) {
            /* allowance for the polygonal rim and chordal faces, O(Δ²) */
            const double dph = 2 * M_PI / (8 * res), dth = 0.5 * M_PI / (2 * res);
            bound[0] = rho / sqrt(4 * M_PI) * (dph * dph + dth * dth);
        }
        *known = 1;
        return SH_OK;
    }
    if (ps->kind == SH_PROC_BOX_OPEN || ps->kind == SH_PROC_BOX_CLOSED) {
        if (!(p[2] == 0 && fabs(p[0]) < 0.5 - 1e-9 && fabs(p[1]) < 0.5 - 1e-9)) return SH_OK;
        const double A = box_hole(ps, res);
        /* [2]: F of the hole [−A,A]² at height 1 − lift, by four signed corners */
        double F = 0;
        const double c = 1 - lift;
        if (A > 0) {
            const double x0 = -A - p[0], x1 = A - p[0], y0 = -A - p[1], y1 = A - p[1];
            F = howell_b3(x1, y1, c) - howell_b3(x0, y1, c) - howell_b3(x1, y0, c) + howell_b3(x0, y0, c);
        }
        t[0] = rho * F / sqrt(4 * M_PI);
        *known = 1;
        return SH_OK;
    }
    /* sphere-plane: a plane vertex (z = 0, normal +z) */
    if (!(p[2] == 0 && nv[2] == 1)) return SH_OK;
    const double R = ps->p[0], H = ps->p[1];
    const double c[3] = {-p[0], -p[1], H - lift};
    const double d = sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]);
    const double u[3] = {c[0] / d, c[1] / d, c[2] / d};
    const double w = asin(R / d), alpha = acos(fmin(1.0, u[2]));
    if (!(alpha + w < 0.5 * M_PI - 1e-6)) return SH_OK; /* the cap dips below the horizon */
    const double w_in = bound ? asin(r_in / d) : 0;
    const int ob = order + 1; /* y_i · y_1m reaches band order */
    double *U = malloc(sizeof(double) * (size_t)n2), *z = malloc(sizeof(double) * (size_t)ob),
           *yu = malloc(sizeof(double) * (size_t)ob * ob), *y1 = malloc(sizeof(double) * 4);
    if (!U || !z || !yu || !y1) {
        free(U); free(z); free(yu); free(y1);
        return sh_error(SH_ENOMEM, "out of memory");
    }
    if ((st = sh_transfer_unshadowed(order, conv, rho, nv, U)) || (st = sh_cap_zonal(w, ob, z)) ||
        (st = sh_eval_dir(ob, conv, u, yu)) || (st = sh_eval_dir(2, conv, nv, y1))) {
        free(U); free(z); free(yu); free(y1);
        return st;
    }
    /* ∫_cap y_k = √(4π/(2l+1)) z_l y_k(u) (addition theorem);
     * n·s = (4π/3) Σ_m y_1m(n) y_1m(s);  y_i y_1m = Σ_k G(i,1m,k) y_k */
    for (int i = 0; i < n2; i++) {
        int li, mi;
        sh_index_lm(i, &li, &mi);
        double C = 0;
        for (int m1 = -1; m1 <= 1; m1++) {
            const double a = 4 * M_PI / 3 * y1[sh_index(1, m1)];
            if (a == 0) continue;
            for (int lk = li > 0 ? li - 1 : 0; lk <= li + 1 && lk < ob; lk++)
                for (int mk = -lk; mk <= lk; mk++) {
                    const int k = sh_index(lk, mk);
                    const double G = sh_gaunt_real(conv, i, sh_index(1, m1), k);
                    if (G == 0) continue;
                    C += a * G * sqrt(4 * M_PI / (2 * lk + 1)) * z[lk] * yu[k];
                }
        }
        t[i] = U[i] - rho / M_PI * C;
        if (bound) bound[i] = rho / M_PI * sqrt((2 * li + 1) / (4 * M_PI)) * 2 * M_PI * (cos(w_in) - cos(w));
    }
    free(U); free(z); free(yu); free(y1);
    *known = order;
    return SH_OK;
}

static int check_args(const sh_proc_scene *ps, const sh_mesh *m, int order, double lift, const double *t,
                      const int *known)
{
    if (!ps || !m || !t || !known || !(lift >= 0 && lift < 0.1))
        return sh_error(SH_EINVAL, "sh_proc_closed_form: bad arguments");
    return sh_check_order(order);
}

int sh_proc_closed_form(const sh_proc_scene *ps, const sh_mesh *m, int v, int order, sh_convention conv,
                        double albedo, double lift, double *t, double *bound, int *known)
{
    int st = check_args(ps, m, order, lift, t, known);
    if (st) return st;
    const double r_in = bound && ps->kind == SH_PROC_SPHERE_PLANE ? sphere_r_in(ps, m) : 0;
    return closed_form_one(ps, m, v, order, conv, albedo, lift, r_in, t, bound, known);
}

int sh_proc_closed_forms(const sh_proc_scene *ps, const sh_mesh *m, int n, const int *verts, int order,
                         sh_convention conv, double albedo, double lift, double *t, double *bound, int *known)
{
    int st = check_args(ps, m, order, lift, t, known);
    if (st) return st;
    if (n < 0) return sh_error(SH_EINVAL, "sh_proc_closed_forms: %d vertices", n);
    const double r_in = bound && ps->kind == SH_PROC_SPHERE_PLANE ? sphere_r_in(ps, m) : 0;
    const size_t n2 = (size_t)order * order;
    for (int k = 0; k < n && !st; k++)
        st = closed_form_one(ps, m, verts ? verts[k] : k, order, conv, albedo, lift, r_in, t + k * n2,
                             bound ? bound + k * n2 : NULL, known + k);
    return st;
}

int sh_proc_furnace(const sh_proc_scene *ps, double albedo, double *radiance)
{
    if (!ps || !radiance || !(albedo > 0 && albedo <= 1)) return sh_error(SH_EINVAL, "sh_proc_furnace: bad arguments");
    if (ps->kind == SH_PROC_BOWL) {
        /* B = ρ(½·1 + ½·B) by [3] (the bowl's own light is spread evenly) */
        *radiance = albedo / (2 - albedo);
        return SH_OK;
    }
    if (albedo == 1 && (ps->kind == SH_PROC_BOX_OPEN || ps->kind == SH_PROC_SPHERE_PLANE)) {
        *radiance = 1;
        return SH_OK;
    }
    return sh_error(SH_ENOTSUP, "no closed-form furnace answer for %s with albedo %g", sh_proc_name(ps->kind), albedo);
}
