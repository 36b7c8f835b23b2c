/* cmd_bench_shader.c — `shlab bench --shader FILE --abi matrix|quat|euler`:
 * rotations per second of a compute shader on the Vulkan device for K
 * rotations per dispatch, beside shlab's CPU kernel rotating the same K
 * rotations at once, timed interleaved in one child process
 * (sh_shader_bench: paired ratios, the noise rule). */
#include "cli.h"
#include "lab/lab.h"

#include <math.h>
#include <stddef.h>
#include <stdlib.h>
#include <string.h>

typedef struct {
    const char *shader, *entry, *defines, *abi_s;
    int order, device, repeat, quiet, fmt, conv;
    double target_ms, timeout;
    sh_rot_method cpu;
    struct { int n, v[SH_SHADER_BENCH_MAX_K]; } k;
} shbench_args;

static int parse_k(const char *opt, const char *s, void *field)
{
    shbench_args *a = (shbench_args *)((char *)field - offsetof(shbench_args, k));
    a->k.n = 0;
    for (const char *p = s; *p;) {
        char *e;
        const long v = strtol(p, &e, 10);
        if (e == p || v < 1 || v > (1L << 20) || a->k.n == SH_SHADER_BENCH_MAX_K || (*e && *e != ','))
            return cli_fail("%s: up to %d counts in 1..%ld, comma separated, not '%s'", opt, SH_SHADER_BENCH_MAX_K,
                            1L << 20, s);
        a->k.v[a->k.n++] = (int)v;
        p = *e ? e + 1 : e;
    }
    return a->k.n ? 0 : cli_fail("%s: empty", opt);
}

static const cli_opt shbench_opts[] = {
    CLI_STRING(shbench_args, shader, "shader", "FILE", "the compute shader (.glsl, .comp, .hlsl, .spv)"),
    CLI_STRING(shbench_args, abi_s, "abi", "NAME", "its rotation input: matrix | quat | euler (required)"),
    CLI_ORDER(shbench_args, order, 64, "the CPU kernel's batched limit", "the order (default 4)"),
    CLI_CUSTOM(shbench_args, k, "count", "LIST", parse_k, "1,16,256,4096,65536,1048576",
               "rotations per dispatch, 1..2^20 (comma separated)"),
    CLI_CUSTOM(shbench_args, cpu, "cpu-method", "M", cli_parse_method, "zxzxz",
               "shlab's CPU method beside it (float, K rotations per\ncall, sh_rot_plan_rotate_many_f)"),
    CLI_STRING(shbench_args, entry, "entry", "NAME", "the entry point (default main)"),
    CLI_STRING(shbench_args, defines, "define", "NAME[=V],...", "preprocessor macros"),
    CLI_INT(shbench_args, device, "device", "N", 0, 64, NULL, "the Vulkan device (default: the first GPU, else the first)"),
    CLI_CONVENTION(shbench_args, conv),
    CLI_INT(shbench_args, repeat, "repeat", "R", 3, 1000, "15", "timed rounds"),
    CLI_REAL(shbench_args, target_ms, "target-ms", "T", 0, 10000, CLI_LO_OPEN, "5", "shortest sample"),
    CLI_REAL(shbench_args, timeout, "timeout", "S", 0.1, 3600, 0, "10", "seconds one dispatch may take"),
    CLI_FLAG(shbench_args, quiet, "quiet", "no progress on stderr"),
    CLI_FORMAT(shbench_args, fmt),
    CLI_END,
};

static const cli_cmd shbench_decl = {
    .name = "bench --shader",
    .usage = "bench --shader FILE --abi matrix|quat|euler [--order N] [--count LIST] [OPTIONS]",
    .about =
        "Rotations per second of a compute shader (the convention of\n"
        "docs/check-your-kernel.md, \"Shaders\") on the Vulkan device, for K rotations\n"
        "per dispatch, beside shlab's CPU kernel (--cpu-method, float) rotating the\n"
        "same K rotations per call.  Both are timed interleaved in one process, one\n"
        "sample each per round, as `shlab bench` times (paired ratio per round, the\n"
        "noise rule).  A dispatch's time is submit to fence: the buffers stay on the\n"
        "device (uploads and downloads are not timed); the first dispatch's outputs at\n"
        "each K are checked against shlab's exact rotation (max_error).  On a CPU device (lavapipe) the\n"
        "shader's figures are CPU figures too, and the output says so.\n",
    .opts = shbench_opts,
    .notes = "JSON: {\"shader\",\"abi\",\"order\",\"device\",\"driver\",\"device_is_cpu\",\"note\",\"cpu_method\",\n"
             "       \"noisy\",\"noise\",\"rows\":[{\"k\",\"shader_ns_per_rotation\",\"shader_rotations_per_s\",\n"
             "       \"cpu_ns_per_rotation\",\"cpu_rotations_per_s\",\"ratio\",\"ratio_q1\",\"ratio_q3\",\n"
             "       \"max_error\",\"noisy\"}]}  (ratio = shader time / CPU time per rotation, median over\n"
             "       rounds; max_error = max |output − exact| of the first dispatch's K outputs, the\n"
             "       exact rotation by zxzxz in double from the same matrices)\n",
};

int cli_bench_shader(const cli_command *bench, int argc, char **argv)
{
    (void)bench; /* its own declaration: --help here is this comparison's */
    shbench_args a = {.order = 4};
    cli_parsed seen;
    int rc = cli_args_parse(&shbench_decl, argc, argv, &a, &seen);
    if (rc >= 0) return rc;
    if (!a.abi_s) return cli_fail("bench: --shader needs --abi matrix|quat|euler (its rotation input)");
    sh_shader_form form;
    if (sh_shader_form_parse(a.abi_s, &form)) return cli_fail("bench: --abi: %s", sh_last_error());
    if (cli_input("shader", a.shader)) return CLI_EXIT_USAGE;
    sh_shader s;
    if (sh_shader_load(a.shader, a.entry, a.defines, &s)) return cli_fail_status(SH_EFORMAT);
    s.form = form;
    s.device = cli_given(&seen, "device") ? a.device : -1;
    s.timeout_s = a.timeout;
    sh_shader_bench_opts o = {.order = a.order, .nk = a.k.n, .cpu_method = a.cpu, .bench = SH_BENCH_OPTS_DEFAULT,
                              .cfg = SH_BENCH_CFG_DEFAULT};
    memcpy(o.k, a.k.v, sizeof a.k.v);
    o.bench.conv = (sh_convention)a.conv;
    o.cfg.samples = a.repeat;
    o.cfg.min_sample_ms = a.target_ms;
    if (!a.quiet) fprintf(stderr, "bench: timing %d counts of rotations per dispatch in a child process\n", a.k.n);
    sh_shader_bench_result *r = calloc(1, sizeof *r);
    if (!r) { sh_shader_free(&s); return cli_fail("out of memory"); }
    const int st = sh_shader_bench(&s, &o, r);
    sh_shader_free(&s);
    if (st) { free(r); return cli_fail("bench: %s", sh_last_error()); }
    if (r->report.cases.failed) {
        fprintf(stderr, "bench: %s\n", r->report.cases.failure);
        free(r);
        return CLI_EXIT_CHECK;
    }
    json_t *rows = json_array();
    int noisy = 0;
    char why[240] = "";
    for (int q = 0; q < a.k.n && rows; q++) {
        const sh_bench_stats *g = &r->shader[q], *c = &r->cpu[q];
        const sh_bench_noise *nz = &r->noise[q];
        if (nz->noisy && !noisy) snprintf(why, sizeof why, "K = %d: %.200s", a.k.v[q], nz->why);
        noisy |= nz->noisy;
        json_t *row = json_pack("{s:i}", "k", a.k.v[q]);
        row = cli_put(row, "shader_ns_per_rotation", json_real(g->ns_median));
        row = cli_put(row, "shader_rotations_per_s", json_real(g->ns_median > 0 ? 1e9 / g->ns_median : 0));
        row = cli_put(row, "cpu_ns_per_rotation", json_real(c->ns_median));
        row = cli_put(row, "cpu_rotations_per_s", json_real(c->ns_median > 0 ? 1e9 / c->ns_median : 0));
        row = cli_put(row, "ratio", json_real(r->ratio[q].median));
        row = cli_put(row, "ratio_q1", json_real(r->ratio[q].q1));
        row = cli_put(row, "ratio_q3", json_real(r->ratio[q].q3));
        row = cli_put(row, "max_error", json_real(r->max_error[q]));
        row = cli_put(row, "noisy", json_boolean(nz->noisy));
        if (!row || json_array_append_new(rows, row)) json_decref(rows), rows = NULL;
    }
    json_t *root = json_pack("{s:s,s:s,s:i}", "shader", a.shader, "abi", a.abi_s, "order", a.order);
    root = cli_put(root, "device", json_string(r->report.device));
    root = cli_put(root, "driver", json_string(r->report.driver));
    root = cli_put(root, "device_is_cpu", json_boolean(r->report.is_cpu));
    root = cli_put(root, "note", json_string(r->report.is_cpu ? "a CPU device (lavapipe): the shader's figures are CPU "
                                                                "figures, on the cores the CPU kernel shares"
                                                              : "the shader on the device, the CPU kernel on one core"));
    root = cli_put(root, "cpu_method", json_string(sh_rot_method_name(a.cpu)));
    root = cli_put(root, "noisy", json_boolean(noisy));
    root = cli_put(root, "noise", json_string(why));
    root = cli_put(root, "rows", rows);
    free(r);
    if (noisy) cli_warn("bench: noisy run (%s); do not draw conclusions from it", why);
    return cli_emit(root, (cli_format)a.fmt);
}
