/* raytrace.c — the Embree 3 scene, ray queries, threads, tangent frames.
 *
 * Embree's lifetimes (rtcNewDevice, rtcCommitScene, rtcGetDeviceError,
 * rtcSetDeviceErrorFunction in Embree 3.13): the device is a reference-
 * counted factory; geometry is committed, attached (the scene takes a
 * reference) and released at once; the scene is committed before any ray.
 * A failed rtcNewDevice returns NULL and rtcGetDeviceError(NULL) says why;
 * afterwards each thread keeps its first error until read, and the error
 * callback runs on the thread of the failing call — it records the message
 * in this thread's buffer, and sh__embree_status turns the error into an
 * SH_E* status with one line.  Commit drops primitives with NaN/Inf corners
 * silently, so the mesh is checked by us first. */
#include "scene_internal.h"

#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

static _Thread_local char embree_msg[256];

static void on_embree_error(void *user, enum RTCError code, const char *str)
{
    (void)user;
    snprintf(embree_msg, sizeof embree_msg, "%s", str ? str : "");
}

static int map_error(enum RTCError e)
{
    switch (e) {
    case RTC_ERROR_NONE: return SH_OK;
    case RTC_ERROR_OUT_OF_MEMORY: return SH_ENOMEM;
    case RTC_ERROR_UNSUPPORTED_CPU: return SH_ENOTSUP;
    case RTC_ERROR_INVALID_ARGUMENT:
    case RTC_ERROR_INVALID_OPERATION: return SH_EINVAL;
    default: return SH_ENUM;
    }
}

static const char *error_name(enum RTCError e)
{
    switch (e) {
    case RTC_ERROR_OUT_OF_MEMORY: return "out of memory";
    case RTC_ERROR_UNSUPPORTED_CPU: return "unsupported CPU";
    case RTC_ERROR_INVALID_ARGUMENT: return "invalid argument";
    case RTC_ERROR_INVALID_OPERATION: return "invalid operation";
    case RTC_ERROR_CANCELLED: return "cancelled";
    default: return "unknown error";
    }
}

int sh__embree_status(const sh_scene *s, const char *what)
{
    const enum RTCError e = rtcGetDeviceError(s ? s->dev : NULL);
    if (e == RTC_ERROR_NONE) return SH_OK;
    const int st = sh_error(map_error(e), "embree: %s: %s%s%s", what, error_name(e), embree_msg[0] ? ": " : "",
                            embree_msg);
    embree_msg[0] = 0;
    return st;
}

int sh__online_cpus(void)
{
    const long n = sysconf(_SC_NPROCESSORS_ONLN);
    return n > 0 ? (int)(n > 256 ? 256 : n) : 1;
}

double sh__now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

void sh_scene_free(sh_scene *s)
{
    if (!s) return;
    if (s->scn) rtcReleaseScene(s->scn);
    if (s->dev) rtcReleaseDevice(s->dev);
    sh_mesh_free(&s->mesh);
    free(s->flip);
    free(s);
}

const sh_mesh *sh_scene_mesh(const sh_scene *s) { return s ? &s->mesh : NULL; }
int sh_scene_threads(const sh_scene *s) { return s ? s->threads : 1; }
double sh_scene_diag(const sh_scene *s) { return s ? s->diag : 0; }

int sh_scene_create(const sh_mesh *m, int threads, sh_scene **out)
{
    if (!out) return sh_error(SH_EINVAL, "sh_scene_create: no output");
    *out = NULL;
    if (!m || !m->pos || !m->normal || !m->tri || m->nvert < 1 || m->ntri < 1)
        return sh_error(SH_EINVAL, "sh_scene_create: empty or incomplete mesh");
    if (threads < 0 || threads > 256) return sh_error(SH_EINVAL, "threads %d not in 0..256", threads);
    for (long long i = 0; i < 3LL * m->nvert; i++)
        if (!isfinite(m->pos[i]) || !isfinite(m->normal[i]))
            return sh_error(SH_EINVAL, "sh_scene_create: vertex %lld is not finite", i / 3);
    for (long long i = 0; i < 3LL * m->ntri; i++)
        if (m->tri[i] < 0 || m->tri[i] >= m->nvert)
            return sh_error(SH_EINVAL, "sh_scene_create: triangle %lld refers to vertex %d of %d", i / 3, m->tri[i],
                            m->nvert);
    sh_scene *s = calloc(1, sizeof *s);
    if (!s) return sh_error(SH_ENOMEM, "out of memory");
    int st = sh_mesh_copy(m, &s->mesh);
    if (st) { free(s); return st; }
    s->threads = threads > 0 ? threads : sh__online_cpus();
    /* the front of a triangle: the side its vertex normals face (the
     * winding of a loaded mesh need not agree) */
    if (!(s->flip = malloc((size_t)m->ntri))) { sh_scene_free(s); return sh_error(SH_ENOMEM, "out of memory"); }
    for (int t = 0; t < m->ntri; t++) {
        const int *c = m->tri + 3 * t;
        const double *a = m->pos + 3 * c[0], *b = m->pos + 3 * c[1], *d = m->pos + 3 * c[2];
        const double e1[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, e2[3] = {d[0] - a[0], d[1] - a[1], d[2] - a[2]};
        const double g[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]};
        double dn = 0;
        for (int k = 0; k < 3; k++) dn += g[k] * (m->normal[3 * c[0] + k] + m->normal[3 * c[1] + k] + m->normal[3 * c[2] + k]);
        s->flip[t] = dn < 0;
    }
    double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
    for (int v = 0; v < m->nvert; v++)
        for (int k = 0; k < 3; k++) {
            lo[k] = fmin(lo[k], m->pos[3 * v + k]);
            hi[k] = fmax(hi[k], m->pos[3 * v + k]);
        }
    s->diag = sqrt((hi[0] - lo[0]) * (hi[0] - lo[0]) + (hi[1] - lo[1]) * (hi[1] - lo[1]) + (hi[2] - lo[2]) * (hi[2] - lo[2]));
    char cfg[64];
    snprintf(cfg, sizeof cfg, "threads=%d,verbose=0", s->threads);
    embree_msg[0] = 0;
    s->dev = rtcNewDevice(cfg);
    if (!s->dev) {
        const enum RTCError e = rtcGetDeviceError(NULL);
        sh_scene_free(s);
        return sh_error(map_error(e) ? map_error(e) : SH_ENUM, "embree: cannot create a device: %s", error_name(e));
    }
    rtcSetDeviceErrorFunction(s->dev, on_embree_error, s);
    s->scn = rtcNewScene(s->dev);
    if ((st = sh__embree_status(s, "rtcNewScene"))) { sh_scene_free(s); return st; }
    rtcSetSceneFlags(s->scn, RTC_SCENE_FLAG_ROBUST);
    rtcSetSceneBuildQuality(s->scn, RTC_BUILD_QUALITY_HIGH);
    RTCGeometry g = rtcNewGeometry(s->dev, RTC_GEOMETRY_TYPE_TRIANGLE);
    if ((st = sh__embree_status(s, "rtcNewGeometry"))) { sh_scene_free(s); return st; }
    float *vb = rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float),
                                        (size_t)m->nvert);
    unsigned *ib = rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(unsigned),
                                           (size_t)m->ntri);
    if ((st = sh__embree_status(s, "rtcSetNewGeometryBuffer")) || !vb || !ib) {
        rtcReleaseGeometry(g);
        sh_scene_free(s);
        return st ? st : sh_error(SH_ENOMEM, "embree: no geometry buffer");
    }
    for (long long i = 0; i < 3LL * m->nvert; i++) vb[i] = (float)m->pos[i];
    for (long long i = 0; i < 3LL * m->ntri; i++) ib[i] = (unsigned)m->tri[i];
    rtcCommitGeometry(g);
    rtcAttachGeometry(s->scn, g);
    rtcReleaseGeometry(g); /* the scene holds its reference */
    if ((st = sh__embree_status(s, "building the geometry"))) { sh_scene_free(s); return st; }
    rtcCommitScene(s->scn);
    if ((st = sh__embree_status(s, "rtcCommitScene"))) { sh_scene_free(s); return st; }
    *out = s;
    return SH_OK;
}

int sh__intersect(const sh_scene *s, const double org[3], const double dir[3], float tfar, double *t, double *u,
                  double *v, int *front)
{
    struct RTCIntersectContext ctx;
    rtcInitIntersectContext(&ctx);
    struct RTCRayHit rh;
    rh.ray.org_x = (float)org[0]; rh.ray.org_y = (float)org[1]; rh.ray.org_z = (float)org[2];
    rh.ray.dir_x = (float)dir[0]; rh.ray.dir_y = (float)dir[1]; rh.ray.dir_z = (float)dir[2];
    rh.ray.tnear = 0.0f;
    rh.ray.tfar = tfar;
    rh.ray.time = 0.0f;
    rh.ray.mask = 0xFFFFFFFFu;
    rh.ray.id = 0;
    rh.ray.flags = 0;
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect1(s->scn, &ctx, &rh);
    if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return 0;
    const int tri = (int)rh.hit.primID;
    *t = rh.ray.tfar;
    *u = rh.hit.u;
    *v = rh.hit.v;
    /* Embree's Ng = e1 × e2 of the stored winding (unnormalised) */
    const double dn = dir[0] * rh.hit.Ng_x + dir[1] * rh.hit.Ng_y + dir[2] * rh.hit.Ng_z;
    *front = s->flip[tri] ? dn > 0 : dn < 0;
    return tri + 1;
}

static int ray_args(const sh_scene *s, const double org[3], const double dir[3], double tnear, double tfar,
                    double d[3])
{
    if (!s || !org || !dir) return sh_error(SH_EINVAL, "ray query: bad arguments");
    const double len = sqrt(dir[0] * dir[0] + dir[1] * dir[1] + dir[2] * dir[2]);
    if (!(len > 0) || !isfinite(len) || !isfinite(org[0]) || !isfinite(org[1]) || !isfinite(org[2]))
        return sh_error(SH_EINVAL, "ray query: origin or direction not finite, or a zero direction");
    if (!(tnear >= 0) || !(tfar >= tnear)) return sh_error(SH_EINVAL, "ray query: need 0 <= tnear <= tfar");
    for (int k = 0; k < 3; k++) d[k] = dir[k] / len;
    return SH_OK;
}

int sh_scene_occluded(const sh_scene *s, const double org[3], const double dir[3], double tnear, double tfar,
                      int *occluded)
{
    double d[3];
    int st = ray_args(s, org, dir, tnear, tfar, d);
    if (st) return st;
    const double o[3] = {org[0] + tnear * d[0], org[1] + tnear * d[1], org[2] + tnear * d[2]};
    *occluded = sh__occluded(s, o, d, (float)(tfar - tnear));
    return sh__embree_status(s, "rtcOccluded1");
}

int sh_scene_intersect(const sh_scene *s, const double org[3], const double dir[3], double tnear, double tfar,
                       sh_hit *hit)
{
    double d[3];
    int st = ray_args(s, org, dir, tnear, tfar, d);
    if (st) return st;
    memset(hit, 0, sizeof *hit);
    const double o[3] = {org[0] + tnear * d[0], org[1] + tnear * d[1], org[2] + tnear * d[2]};
    const int r = sh__intersect(s, o, d, (float)(tfar - tnear), &hit->t, &hit->u, &hit->v, &hit->front);
    if (r) {
        hit->hit = 1;
        hit->tri = r - 1;
        hit->t += tnear;
    }
    return sh__embree_status(s, "rtcIntersect1");
}

void sh_scene_ray_origin(const sh_scene *s, int v, double eps, double org[3])
{
    const double e = (eps > 0 ? eps : 1e-4) * s->diag;
    for (int k = 0; k < 3; k++) org[k] = s->mesh.pos[3 * v + k] + e * s->mesh.normal[3 * v + k];
}

/* ------------------------------------------------------------- threads */

typedef struct {
    sh__work_fn fn;
    void *ctx;
    int n, chunk;
    atomic_int next, done, failed;
    int status;
    char msg[512];
    pthread_mutex_t lock;
    sh_progress_fn progress;
    void *progress_ctx;
    const char *what;
} pool;

typedef struct {
    pool *p;
    int thread;
} worker_arg;

static void *worker(void *arg)
{
    worker_arg *w = arg;
    pool *p = w->p;
    for (;;) {
        if (atomic_load(&p->failed)) break;
        const int b = atomic_fetch_add(&p->next, p->chunk);
        if (b >= p->n) break;
        const int e = b + p->chunk < p->n ? b + p->chunk : p->n;
        const int st = p->fn(p->ctx, w->thread, b, e);
        if (st) {
            pthread_mutex_lock(&p->lock);
            if (!atomic_load(&p->failed)) {
                p->status = st;
                snprintf(p->msg, sizeof p->msg, "%s", sh_last_error());
                atomic_store(&p->failed, 1);
            }
            pthread_mutex_unlock(&p->lock);
            break;
        }
        const int d = atomic_fetch_add(&p->done, e - b) + (e - b);
        if (w->thread == 0 && p->progress) p->progress(p->progress_ctx, d, p->n, p->what);
    }
    return NULL;
}

int sh__parallel_for(int threads, int n, int chunk, sh__work_fn fn, void *ctx, sh_progress_fn progress,
                     void *progress_ctx, const char *what)
{
    if (n <= 0) return SH_OK;
    if (threads <= 0) threads = sh__online_cpus();
    if (threads > n) threads = n;
    pool p = {.fn = fn, .ctx = ctx, .n = n, .chunk = chunk > 0 ? chunk : 1, .progress = progress,
              .progress_ctx = progress_ctx, .what = what};
    atomic_init(&p.next, 0);
    atomic_init(&p.done, 0);
    atomic_init(&p.failed, 0);
    pthread_mutex_init(&p.lock, NULL);
    pthread_t *tid = malloc(sizeof(pthread_t) * (size_t)threads);
    worker_arg *args = malloc(sizeof(worker_arg) * (size_t)threads);
    if (!tid || !args) {
        free(tid);
        free(args);
        pthread_mutex_destroy(&p.lock);
        return sh_error(SH_ENOMEM, "out of memory");
    }
    int started = 1;
    for (int t = 0; t < threads; t++) args[t] = (worker_arg){&p, t};
    for (int t = 1; t < threads; t++) {
        if (pthread_create(&tid[t], NULL, worker, &args[t]) != 0) break;
        started++;
    }
    worker(&args[0]);
    for (int t = 1; t < started; t++) pthread_join(tid[t], NULL);
    free(tid);
    free(args);
    pthread_mutex_destroy(&p.lock);
    if (atomic_load(&p.failed)) return sh_error(p.status, "%s", p.msg);
    if (progress) progress(progress_ctx, n, n, what);
    return SH_OK;
}

/* ------------------------------------------------------------- frames */

void sh__tangent_frame(const double n[3], double M[9])
{
    /* Duff et al. 2017, Listing 3: branchless ONB (t, b) about n */
    const double sign = copysign(1.0, n[2]);
    const double a = -1.0 / (sign + n[2]);
    const double bb = n[0] * n[1] * a;
    const double t[3] = {1.0 + sign * n[0] * n[0] * a, sign * bb, -sign * n[0]};
    const double b[3] = {bb, sign + n[1] * n[1] * a, -n[1]};
    /* keep det = +1: swap t and b when (t × b)·n < 0 */
    const double tb = (t[1] * b[2] - t[2] * b[1]) * n[0] + (t[2] * b[0] - t[0] * b[2]) * n[1] +
                      (t[0] * b[1] - t[1] * b[0]) * n[2];
    const double *c0 = tb > 0 ? t : b, *c1 = tb > 0 ? b : t;
    for (int r = 0; r < 3; r++) {
        M[3 * r + 0] = c0[r];
        M[3 * r + 1] = c1[r];
        M[3 * r + 2] = n[r];
    }
}

int sh__rotate_frame(sh_rot_plan *plan, const double M[9], const double *in, double *out)
{
    /* the matrix straight into the plan (sh_rot_plan_set_matrix: no Euler
     * angles in between; 1.2-1.7x faster per record use than angles + set,
     * docs/scenes.md "Radiance cache") */
    int st = sh_rot_plan_set_matrix(plan, M);
    if (st) return st;
    return sh_rot_plan_apply(plan, in, out);
}

int sh_scene_rotate_coeffs(int order, sh_convention conv, sh_rot_method method, const sh_rotation *rot, int nchan,
                           const double *in, double *out)
{
    if (!rot || !in || !out || nchan < 1) return sh_error(SH_EINVAL, "sh_scene_rotate_coeffs: bad arguments");
    sh_rot_plan *p = NULL;
    int st = sh_rot_plan_create(order, method, SH_PREC_DOUBLE, conv, &p);
    if (st) return st;
    if (!(st = sh_rot_plan_set(p, rot)))
        for (int c = 0; c < nchan && !st; c++)
            st = sh_rot_plan_apply(p, in + (size_t)c * order * order, out + (size_t)c * order * order);
    sh_rot_plan_free(p);
    return st;
}

void sh__cosine_samples(int s, uint64_t seed, double *d)
{
    /* the stream starts at a hash of the seed: seeds k and k+1 must not
     * give the same stream shifted by one step (splitmix steps by the
     * golden constant, so a state of seed·golden would) */
    uint64_t h = seed ^ 0x632BE59BD9B4E019ull;
    uint64_t x = sh__splitmix(&h);
    for (int i = 0; i < s; i++)
        for (int j = 0; j < s; j++) {
            const double u = (i + sh__uniform(&x)) / s, v = (j + sh__uniform(&x)) / s;
            const double r = sqrt(u), ph = 2 * M_PI * v;
            double *o = d + 3 * ((size_t)i * s + j);
            o[0] = r * cos(ph);
            o[1] = r * sin(ph);
            o[2] = sqrt(fmax(0.0, 1.0 - u));
        }
}
