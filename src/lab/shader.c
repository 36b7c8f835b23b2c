/* shader.c — a user's compute shader (GLSL, HLSL or SPIR-V) that rotates SH
 * coefficients, compiled here (shaderc's library) and run on a Vulkan
 * device (vk_compute.c) in the sandbox, on the cases of a golden fixture or
 * timed beside shlab's CPU kernels.
 *
 * The convention (docs/check-your-kernel.md, "Shaders"): local_size_x = 64;
 * push constants {uint order, count, form, pad}; set 0, binding 0 the
 * rotations (per rotation 9 floats of R row-major, 4 of the quaternion
 * (w, x, y, z) or 3 ZYZ angles α, β, γ, packed), binding 1 the input
 * vectors and binding 2 the outputs (count vectors of order² floats, one
 * after another), binding 3 a uint status per rotation (shlab writes 0; 1:
 * the shader does not handle this order, other values: failure).
 * Invocation k (gl_GlobalInvocationID.x) rotates vector k, k < count.
 *
 * Fixture runs: one dispatch per order, every case of that order at once (a
 * band case as the order band+1 with zeros outside the band), outputs
 * starting as NaN so a value the shader never writes fails its case. */
#include "lab/lab.h"
#include "lab/case_stream.h"
#include "lab/vk_compute.h"
#include "core/sandbox.h"
#include "core/shlab_internal.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#ifdef SHLAB_HAVE_VULKAN
#include <shaderc/shaderc.h>
#endif

static const char *const form_names[SH_SHADER_NFORMS] = {"matrix", "quat", "euler"};
static const int form_floats[SH_SHADER_NFORMS] = {9, 4, 3};

const char *sh_shader_form_name(sh_shader_form f) { return (unsigned)f < SH_SHADER_NFORMS ? form_names[f] : "?"; }

int sh_shader_form_parse(const char *s, sh_shader_form *out)
{
    for (int f = 0; s && f < SH_SHADER_NFORMS; f++)
        if (!strcmp(s, form_names[f])) {
            *out = (sh_shader_form)f;
            return SH_OK;
        }
    return sh_error(SH_EINVAL, "unknown shader input '%s' (matrix, quat or euler)", s ? s : "");
}

void sh_shader_free(sh_shader *s)
{
    if (!s) return;
    free(s->spirv);
    s->spirv = NULL;
    s->nwords = 0;
}

static int ends_with(const char *s, const char *suf)
{
    const size_t n = strlen(s), m = strlen(suf);
    return n >= m && !strcmp(s + n - m, suf);
}

/* A shader file is at most this large. */
#define SHADER_MAX_BYTES ((long long)16 << 20)

int sh_shader_load(const char *path, const char *entry, const char *defines, sh_shader *out)
{
    memset(out, 0, sizeof *out);
    out->device = -1;
    out->timeout_s = 10;
    snprintf(out->path, sizeof out->path, "%s", path);
    snprintf(out->entry, sizeof out->entry, "%s", entry && *entry ? entry : "main");
    if (!sh_vk_available()) return sh_vk_open(-1, &(sh_vk *){0}); /* says why */
    char *buf;
    size_t n;
    if (sh_input_read_all("shader", path, SHADER_MAX_BYTES, &buf, &n)) return SH_EIO;
    int st = SH_OK;
    if (ends_with(path, ".spv")) {
        if (n < 20 || n % 4 || ((const uint32_t *)(const void *)buf)[0] != 0x07230203u)
            st = sh_error(SH_EFORMAT, "shader '%s': not SPIR-V (no magic number 0x07230203 or not whole words)", path);
        else if (!(out->spirv = malloc(n))) st = sh_error(SH_ENOMEM, "out of memory");
        else memcpy(out->spirv, buf, n), out->nwords = n / 4;
        free(buf);
        return st;
    }
#ifdef SHLAB_HAVE_VULKAN
    const int hlsl = ends_with(path, ".hlsl");
    if (!hlsl && !ends_with(path, ".glsl") && !ends_with(path, ".comp")) {
        free(buf);
        return sh_error(SH_EINVAL, "shader '%s': the name must end in .glsl, .comp, .hlsl or .spv", path);
    }
    shaderc_compiler_t cc = shaderc_compiler_initialize();
    shaderc_compile_options_t o = shaderc_compile_options_initialize();
    if (!cc || !o) {
        free(buf);
        return sh_error(SH_ENOMEM, "shaderc: cannot start the compiler");
    }
    shaderc_compile_options_set_source_language(o, hlsl ? shaderc_source_language_hlsl : shaderc_source_language_glsl);
    shaderc_compile_options_set_target_env(o, shaderc_target_env_vulkan, shaderc_env_version_vulkan_1_1);
    shaderc_compile_options_set_optimization_level(o, shaderc_optimization_level_performance);
    /* --define NAME[=VALUE],...: the preprocessor's macros */
    for (const char *d = defines; d && *d;) {
        const char *e = strchr(d, ','), *end = e ? e : d + strlen(d), *eq = memchr(d, '=', (size_t)(end - d));
        const size_t nl = (size_t)((eq ? eq : end) - d);
        if (nl) shaderc_compile_options_add_macro_definition(o, d, nl, eq ? eq + 1 : NULL, eq ? (size_t)(end - eq - 1) : 0);
        d = e ? e + 1 : end;
    }
    shaderc_compilation_result_t r =
        shaderc_compile_into_spv(cc, buf, n, shaderc_compute_shader, path, out->entry, o);
    free(buf);
    if (shaderc_result_get_compilation_status(r) != shaderc_compilation_status_success) {
        char msg[400];
        snprintf(msg, sizeof msg, "%s", shaderc_result_get_error_message(r));
        for (char *c = msg; *c; c++)
            if (*c == '\n') *c = *(c + 1) ? ' ' : '\0';
        st = sh_error(SH_EFORMAT, "shader '%s' does not compile: %s", path, msg);
    } else {
        const size_t len = shaderc_result_get_length(r);
        if (!(out->spirv = malloc(len))) st = sh_error(SH_ENOMEM, "out of memory");
        else memcpy(out->spirv, shaderc_result_get_bytes(r), len), out->nwords = len / 4;
    }
    shaderc_result_release(r);
    shaderc_compile_options_release(o);
    shaderc_compiler_release(cc);
    return st;
#else
    free(buf);
    return sh_error(SH_ENOTSUP, "shlab was built without Vulkan and shaderc");
#endif
}

/* ------------------------------------------------------------ the child */

/* Rotation r in the form, as floats. */
static void put_rotation(sh_shader_form f, const sh_rotation *r, float *dst)
{
    double q[4];
    switch (f) {
    case SH_SHADER_MATRIX:
        for (int i = 0; i < 9; i++) dst[i] = (float)r->R[i];
        break;
    case SH_SHADER_QUAT:
        sh_rotation_to_quat(r, q);
        for (int i = 0; i < 4; i++) dst[i] = (float)q[i];
        break;
    default: dst[0] = (float)r->alpha, dst[1] = (float)r->beta, dst[2] = (float)r->gamma; break;
    }
}

/* Open the device and the pipeline; INFO record with the device's name. */
static int child_open(const sh_shader *s, int fd, sh_vk **v)
{
    int st = sh_vk_open(s->device, v);
    if (!st) {
        char info[SH_REC_MAX_TEXT];
        snprintf(info, sizeof info, "%s|%s|%d", sh_vk_device_name(*v), sh_vk_driver(*v), sh_vk_is_cpu(*v));
        sh__rec_send_text(fd, SH_REC_INFO, info);
        st = sh_vk_pipeline(*v, s->spirv, s->nwords, s->entry);
    }
    /* a dispatch of nothing: the driver's compilation, outside the timeouts */
    if (!st) {
        const size_t bytes[4] = {64, 64, 64, 64};
        void *map[4];
        if (!(st = sh_vk_buffers(*v, bytes, map)) && !(st = sh_vk_record(*v, 1, 0, (int)s->form, 1)))
            st = sh_vk_submit(*v, 120);
    }
    if (st) sh__rec_send_text(fd, SH_REC_OPEN, sh_last_error());
    return st;
}

typedef struct {
    const sh_shader *s;
    const sh_fixture *fx;
    const unsigned char *skip;
} fixture_job;

static int case_order(const sh_fixture_case *c) { return c->band >= 0 ? c->band + 1 : c->order; }

/* The cases of one order in one dispatch. */
static int dispatch_order(const fixture_job *j, sh_vk *v, int fd, int order, const int *ks, int K, double *res)
{
    const int n = order * order, per = form_floats[j->s->form];
    const size_t bytes[4] = {(size_t)K * per * sizeof(float), (size_t)K * n * sizeof(float),
                             (size_t)K * n * sizeof(float), (size_t)K * sizeof(uint32_t)};
    void *map[4];
    int st = sh_vk_buffers(v, bytes, map);
    if (st) return st;
    float *rot = map[0], *in = map[1], *out = map[2];
    uint32_t *status = map[3];
    for (int i = 0; i < K; i++) {
        const sh_fixture_case *c = &j->fx->cases[ks[i]];
        const int off = c->band >= 0 ? c->band * c->band : 0;
        put_rotation(j->s->form, &c->rot, rot + (size_t)i * per);
        for (int t = 0; t < n; t++) {
            in[(size_t)i * n + t] = t >= off && t < off + c->n ? (float)c->input[t - off] : 0.0f;
            out[(size_t)i * n + t] = NAN;
        }
        status[i] = 0;
    }
    /* the dispatch's first case names it if it hangs or crashes */
    if (sh__rec_send(fd, SH_REC_START, ks[0], 0, NULL, 0)) return SH_EIO;
    if ((st = sh_vk_record(v, order, K, (int)j->s->form, 1)) || (st = sh_vk_submit(v, j->s->timeout_s)))
        return sh_error(st, "%s, on the dispatch of order %d (%d cases from '%s')", sh_last_error(), order, K,
                        j->fx->cases[ks[0]].id);
    for (int i = 0; i < K; i++) {
        const sh_fixture_case *c = &j->fx->cases[ks[i]];
        const int off = c->band >= 0 ? c->band * c->band : 0;
        for (int t = 0; t < c->n; t++) res[t] = out[(size_t)i * n + off + t];
        if (sh__rec_send(fd, SH_REC_DONE, ks[i], (int)status[i], res, c->n)) return SH_EIO;
    }
    return SH_OK;
}

static int fixture_child(void *arg, int fd)
{
    const fixture_job *j = arg;
    sh_vk *v = NULL;
    if (child_open(j->s, fd, &v)) return 0; /* the OPEN record says why */
    const int nc = j->fx->ncases;
    int *ks = malloc((size_t)nc * sizeof *ks), maxn = 1, st = ks ? SH_OK : SH_ENOMEM;
    for (int k = 0; k < nc; k++) maxn = j->fx->cases[k].n > maxn ? j->fx->cases[k].n : maxn;
    double *res = malloc((size_t)maxn * sizeof *res);
    if (!res) st = SH_ENOMEM;
    for (int order = 1; !st && order <= SHLAB_MAX_ORDER; order++) {
        int K = 0, any_above = 0;
        for (int k = 0; k < nc; k++) {
            if (j->skip && j->skip[k]) continue;
            const int o = case_order(&j->fx->cases[k]);
            if (o == order) ks[K++] = k;
            any_above |= o > order;
        }
        if (K) st = dispatch_order(j, v, fd, order, ks, K, res);
        if (!any_above) break;
    }
    free(ks), free(res);
    if (st) {
        /* one line on stderr: the parent's report */
        fprintf(stderr, "%s\n", sh_last_error());
        fflush(stderr);
        _exit(SH_CASE_CHILD_FAULT);
    }
    sh_vk_close(v);
    return 0;
}

/* "name|driver|cpu" of the INFO record into the report. */
static void device_info(const char *info, sh_shader_report *rep)
{
    char tmp[SH_REC_MAX_TEXT];
    snprintf(tmp, sizeof tmp, "%s", info);
    char *a = strchr(tmp, '|'), *b = a ? strchr(a + 1, '|') : NULL;
    if (a) *a = '\0';
    if (b) *b = '\0';
    snprintf(rep->device, sizeof rep->device, "%.200s", tmp);
    snprintf(rep->driver, sizeof rep->driver, "%.200s", a ? a + 1 : "");
    rep->is_cpu = b ? atoi(b + 1) : 0;
}

int sh_shader_run_fixture(const sh_shader *s, const sh_fixture *fx, const unsigned char *skip, double **got,
                          unsigned char *status, sh_shader_report *rep)
{
    memset(rep, 0, sizeof *rep);
    rep->cases.current = -1;
    for (int k = 0; k < fx->ncases; k++) status[k] = SH_PLUGIN_CASE_NOT_RUN;
    const fixture_job j = {s, fx, skip};
    sh_case_reader r = {.fx = fx, .got = got, .rep = &rep->cases, .status = status, .who = "the shader"};
    /* the child's limits: the device's start-up (a CPU device compiles the
     * shader with LLVM, up to 120 s) and every dispatch's own timeout */
    const double wall = 150 + 2 * s->timeout_s;
    const sh_sandbox_job sj = {.child = fixture_child, .feed = sh__case_reader_feed, .arg = (void *)&j, .fctx = &r,
                               .cpu_seconds = wall, .wall_seconds = wall, .mem_bytes = 0, .what = "the shader"};
    sh_sandbox_result sr;
    const int st = sh__sandbox_run(&sj, &sr);
    if (st) return st;
    sh__case_describe(wall, fx, &sr, &r, &rep->cases);
    rep->cases.failed = rep->cases.failure[0] != '\0';
    device_info(r.info, rep);
    return SH_OK;
}

/* ------------------------------------------------------------ timing */

/* One bench entry: `count` submissions of a command buffer with one
 * dispatch of K rotations (units = K). */
typedef struct {
    sh_vk *v;
    double timeout_s;
} dispatch_entry;

static int dispatch_run(void *ctx, long count)
{
    dispatch_entry *e = ctx;
    int st = SH_OK;
    for (long i = 0; i < count && !st; i++) st = sh_vk_submit(e->v, e->timeout_s);
    return st;
}

typedef struct {
    const sh_shader *s;
    const sh_shader_bench_opts *o;
} bench_job;

/* What the timing child sends back, per K. */
typedef struct {
    int status;
    char why[256];
    sh_bench_stats shader[SH_SHADER_BENCH_MAX_K], cpu[SH_SHADER_BENCH_MAX_K];
    sh_bench_ratio ratio[SH_SHADER_BENCH_MAX_K]; /* shader / cpu per rotation, paired by round */
    sh_bench_noise noise[SH_SHADER_BENCH_MAX_K];
    double max_error[SH_SHADER_BENCH_MAX_K];
} bench_answer;

/* K rotations of the pool (cycled) in the form, and K input vectors. */
static int fill_bench(const sh_shader_bench_opts *o, int form, int K, void *map[4])
{
    const int nc = o->order * o->order, per = form_floats[form];
    double(*R)[9] = malloc(SH_BENCH_POOL * sizeof *R), *vin = malloc((size_t)SH_BENCH_POOL * nc * sizeof *vin);
    if (!R || !vin) return free(R), free(vin), sh_error(SH_ENOMEM, "out of memory");
    sh_bench_pool(o->bench.seed, o->bench.max_beta, nc, R, vin);
    for (int k = 0; k < K; k++) {
        const int q = k & (SH_BENCH_POOL - 1);
        sh_rotation r;
        memcpy(r.R, R[q], sizeof r.R);
        sh_euler_from_matrix(r.R, &r.alpha, &r.beta, &r.gamma);
        put_rotation((sh_shader_form)form, &r, (float *)map[0] + (size_t)k * per);
        for (int i = 0; i < nc; i++) ((float *)map[1])[(size_t)k * nc + i] = (float)vin[(size_t)q * nc + i];
        ((uint32_t *)map[3])[k] = 0;
    }
    free(R), free(vin);
    return SH_OK;
}

/* The first dispatch's K outputs against shlab's exact rotation in double
 * (zxzxz, from the pool's matrices; the pool repeats every SH_BENCH_POOL
 * rotations, so 64 reference vectors serve every k): max |y_shader − y|. */
static int check_outputs(const sh_shader_bench_opts *o, int K, const float *out, double *max_err)
{
    const int nc = o->order * o->order;
    double(*R)[9] = malloc(SH_BENCH_POOL * sizeof *R), *vin = malloc((size_t)SH_BENCH_POOL * nc * sizeof *vin);
    double *ref = malloc((size_t)SH_BENCH_POOL * nc * sizeof *ref);
    sh_rot_plan *p = NULL;
    int st = R && vin && ref ? sh_rot_plan_create(o->order, SH_ROT_ZXZXZ, SH_PREC_DOUBLE, o->bench.conv, &p) : SH_ENOMEM;
    if (!st) sh_bench_pool(o->bench.seed, o->bench.max_beta, nc, R, vin);
    for (int q = 0; !st && q < SH_BENCH_POOL; q++)
        if (!(st = sh_rot_plan_set_matrix(p, R[q]))) st = sh_rot_plan_apply(p, vin + (size_t)q * nc, ref + (size_t)q * nc);
    double e = 0;
    for (size_t k = 0; !st && k < (size_t)K; k++)
        for (int i = 0; i < nc; i++) {
            const double d = fabs((double)out[k * nc + i] - ref[(size_t)(k & (SH_BENCH_POOL - 1)) * nc + i]);
            if (isnan(d)) e = INFINITY; /* a NaN output is the worst */
            else if (d > e) e = d;
        }
    *max_err = e;
    sh_rot_plan_free(p);
    free(R), free(vin), free(ref);
    return st == SH_ENOMEM ? sh_error(SH_ENOMEM, "out of memory") : st;
}

static int bench_child(void *arg, int fd)
{
    const bench_job *j = arg;
    const sh_shader_bench_opts *o = j->o;
    sh_vk *v = NULL;
    if (child_open(j->s, fd, &v)) return 0;
    bench_answer *ans = calloc(1, sizeof *ans);
    if (!ans) return SH_CASE_CHILD_WRITE;
    const int n = o->order * o->order, S = o->cfg.samples > 0 ? o->cfg.samples : 15;
    double *smp = malloc(2 * (size_t)S * sizeof *smp);
    int st = smp ? SH_OK : SH_ENOMEM;
    for (int q = 0; q < o->nk && !st; q++) {
        const int K = o->k[q], per = form_floats[j->s->form];
        const size_t bytes[4] = {(size_t)K * per * sizeof(float), (size_t)K * n * sizeof(float),
                                 (size_t)K * n * sizeof(float), (size_t)K * sizeof(uint32_t)};
        void *map[4];
        if ((st = sh_vk_buffers(v, bytes, map)) || (st = fill_bench(o, (int)j->s->form, K, map)) ||
            (st = sh_vk_record(v, o->order, K, (int)j->s->form, 1)) || (st = sh_vk_submit(v, j->s->timeout_s)))
            break;
        /* the shader's status after one dispatch: it must handle the order */
        for (int k = 0; k < K && !st; k++)
            if (((uint32_t *)map[3])[k] != 0)
                st = sh_error(SH_EINVAL, "the shader set status %u for order %d (it does not rotate this order)",
                              ((uint32_t *)map[3])[k], o->order);
        if (!st) st = check_outputs(o, K, map[2], &ans->max_error[q]);
        /* beside it, shlab's CPU kernel on K rotations at once (float,
         * matrices, structure of arrays: sh_rot_plan_rotate_many_f) */
        sh_bench_entry ent[2] = {{0}};
        dispatch_entry de = {v, j->s->timeout_s};
        ent[0] = (sh_bench_entry){.name = "shader", .run = dispatch_run, .ctx = &de, .units = K};
        sh_bench_opts bo = o->bench;
        bo.input = SH_BENCH_INPUT_MATRIX;
        bo.batch = K < 4096 ? K : 4096;
        if (!st) st = sh_rot_bench_entry(o->order, o->cpu_method, SH_PREC_FLOAT, SH_BENCH_KROT, &bo, &ent[1]);
        if (!st) {
            sh_bench_stats stt[2];
            st = sh_bench_interleaved(ent, 2, &o->cfg, smp, stt, &ans->noise[q]);
            ans->shader[q] = stt[0], ans->cpu[q] = stt[1];
        }
        if (!st) st = sh_bench_paired_ratio(smp, smp + S, S, o->cfg.noise_spread, &ans->ratio[q]);
        sh_bench_entry_free(&ent[1]);
    }
    ans->status = st;
    if (st) snprintf(ans->why, sizeof ans->why, "%s", sh_last_error());
    free(smp);
    const int nd = (int)((sizeof *ans + sizeof(double) - 1) / sizeof(double));
    double *buf = calloc((size_t)nd, sizeof *buf);
    int w = -1;
    if (buf) {
        memcpy(buf, ans, sizeof *ans);
        w = sh__rec_send(fd, SH_REC_DONE, 0, 0, buf, nd);
    }
    free(buf), free(ans);
    sh_vk_close(v);
    return w ? SH_CASE_CHILD_WRITE : 0;
}


int sh_shader_bench(const sh_shader *s, const sh_shader_bench_opts *o, sh_shader_bench_result *res)
{
    memset(res, 0, sizeof *res);
    if (o->nk < 1 || o->nk > SH_SHADER_BENCH_MAX_K) return sh_error(SH_EINVAL, "shader bench: 1..%d values of K", SH_SHADER_BENCH_MAX_K);
    const size_t nd = (sizeof(bench_answer) + sizeof(double) - 1) / sizeof(double);
    sh_byte_sink sink = {.cap = 3 * (sizeof(sh_rec_hdr) + SH_REC_MAX_TEXT) + sizeof(sh_rec_hdr) + nd * sizeof(double)};
    if (!(sink.buf = malloc(sink.cap))) return sh_error(SH_ENOMEM, "out of memory");
    const bench_job j = {s, o};
    const double wall = 60 + 4 * s->timeout_s * o->nk;
    const sh_sandbox_job sj = {.child = bench_child, .feed = sh__byte_sink_feed, .arg = (void *)&j, .fctx = &sink,
                               .cpu_seconds = wall, .wall_seconds = wall, .mem_bytes = 0, .what = "the shader"};
    sh_sandbox_result sr;
    int st = sh__sandbox_run(&sj, &sr);
    /* walk the records */
    size_t at = 0;
    int done = 0;
    while (!st && at + sizeof(sh_rec_hdr) <= sink.have) {
        sh_rec_hdr h;
        memcpy(&h, sink.buf + at, sizeof h);
        at += sizeof h;
        const size_t body = h.n > 0 ? (size_t)h.n * sizeof(double) : 0;
        if (at + body > sink.have) break;
        if (h.kind == SH_REC_INFO || h.kind == SH_REC_OPEN) {
            char text[SH_REC_MAX_TEXT];
            const size_t m = body < sizeof text ? body : sizeof text - 1;
            memcpy(text, sink.buf + at, m);
            text[m] = '\0';
            if (h.kind == SH_REC_INFO) device_info(text, &res->report);
            else st = sh_error(SH_EINVAL, "the shader cannot run: %.300s", text);
        } else if (h.kind == SH_REC_DONE && (size_t)h.n == nd) {
            bench_answer ans;
            memcpy(&ans, sink.buf + at, sizeof ans);
            if (ans.status) st = sh_error(ans.status, "%s", ans.why);
            memcpy(res->shader, ans.shader, sizeof ans.shader);
            memcpy(res->cpu, ans.cpu, sizeof ans.cpu);
            memcpy(res->ratio, ans.ratio, sizeof ans.ratio);
            memcpy(res->noise, ans.noise, sizeof ans.noise);
            memcpy(res->max_error, ans.max_error, sizeof ans.max_error);
            done = 1;
        }
        at += body;
    }
    if (!st && !done) {
        sh_case_reader r = {.who = "the shader"};
        sh__case_describe(wall, NULL, &sr, &r, &res->report.cases);
        if (!res->report.cases.failure[0])
            snprintf(res->report.cases.failure, sizeof res->report.cases.failure, "the shader's process sent no answer");
        res->report.cases.failed = 1;
    }
    free(sink.buf);
    return st;
}
