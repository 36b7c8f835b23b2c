/* scene_transfer — Green's transfer on meshes: the closed forms of the
 * procedural scenes, the furnace and the bounce series, and the time of
 * shadowed transfer on a real mesh (the goal: order 4, 1024 rays per
 * vertex, ~10k vertices in ≤ 10 s on 2 cores).
 *
 *  1. unshadowed closed form (clamped cosine rotated to n, addition
 *     theorem) against an exact hemisphere quadrature (Gauss-Legendre in
 *     cosθ × uniform φ in the normal's frame; exact for the polynomial
 *     integrand): max |difference| over random normals, orders 1..16;
 *  2. shadowed transfer by rays (16 replications) against the closed forms
 *     of sphere-plane (every coefficient, order 4), bowl and box-open (t_0):
 *     the largest |mean − closed form| and its allowance (tessellation
 *     bound + k SE, k the Student-t quantile for a 1 % family-wise rate);
 *  3. the bowl's bounce series: bounce k adds (ρ/2)^(k+1) of a constant
 *     radiance (sphere interior view factors), measured as the mean DC
 *     radiance of the transfer after k bounces minus after k−1;
 *  4. the time (the timing part, timing/): shadowed transfer of
 *     data/models/Wuson.ply (`make models`; skipped with a line without it),
 *     order 4, 1024 rays, threads 1 and 2 interleaved in the bench engine,
 *     3 rounds.
 * Sections 1-3 are deterministic: every vertex draws its rays from its own
 * stream (seed, vertex), so the thread count and scheduling change nothing. */
#include <gsl/gsl_cdf.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "exp.h"
#include "scene/scene_internal.h"

/* one entry of the timing: shadowed transfer, order 4, 1024 rays */
typedef struct {
    sh_scene *s;
    double *T;
    int threads;
    long long rays;
} tctx;
static int run_transfer(void *vc, long count)
{
    tctx *c = vc;
    for (long k = 0; k < count; k++) {
        sh_transfer_opts o = {0};
        o.kind = SH_TRANSFER_SHADOWED;
        o.order = 4;
        o.rays = 1024;
        o.threads = c->threads;
        sh_transfer_stats st;
        const int e = sh_transfer(c->s, &o, c->T, &st);
        if (e) return e;
        c->rays = st.rays;
    }
    return SH_OK;
}

int main(int argc, char **argv)
{
    exp_init(argc, argv);
    /* ---- 1. closed form against the exact hemisphere quadrature */
    double cf_max = 0;
    {
        uint64_t x = 3;
        for (int order = 1; order <= 16; order++)
            for (int k = 0; k < 20; k++) {
                const double z = 2 * sh__uniform(&x) - 1, ph = 2 * M_PI * sh__uniform(&x), r = sqrt(1 - z * z);
                const double n[3] = {r * cos(ph), r * sin(ph), z};
                const int n2 = order * order, S = order + 2, P = 2 * order + 2;
                double t[256], q[256] = {0}, y[256], gx[32], gw[32], M[9];
                exp_check(sh_transfer_unshadowed(order, SH_CS, 1, n, t), "closed form");
                exp_check(sh__gauss_legendre(S, gx, gw), "gauss");
                sh__tangent_frame(n, M);
                for (int a = 0; a < S; a++) {
                    const double c = 0.5 * (gx[a] + 1), wc = 0.5 * gw[a], sn = sqrt(1 - c * c);
                    for (int b = 0; b < P; b++) {
                        const double pb = 2 * M_PI * (b + 0.5) / P, l[3] = {sn * cos(pb), sn * sin(pb), c};
                        const double d[3] = {M[0] * l[0] + M[1] * l[1] + M[2] * l[2], M[3] * l[0] + M[4] * l[1] + M[5] * l[2],
                                             M[6] * l[0] + M[7] * l[1] + M[8] * l[2]};
                        exp_check(sh_eval_dir(order, SH_CS, d, y), "eval");
                        for (int i = 0; i < n2; i++) q[i] += wc * (2 * M_PI / P) * c * y[i] / M_PI;
                    }
                }
                for (int i = 0; i < n2; i++) cf_max = fmax(cf_max, fabs(t[i] - q[i]));
            }
    }
    exp_progress("closed form vs quadrature: %.3g", cf_max);

    /* ---- 2. shadowed transfer against the procedural closed forms */
    const char *specs[3] = {"sphere-plane", "bowl", "box-open"};
    const int orders[3] = {4, 2, 2}, R = 16;
    FILE *fc = exp_data("closed_forms.dat", "shadowed transfer by rays (16 replications, 1024 rays) against the closed forms",
                        "scene vertices_compared coefficients max_error max_allowed max_excess(error-allowed) k tessellation_bound_max");
    char table[4096] = "| scene | vertices compared | coefficients | largest error | its allowance | largest error − allowance |\n|---|---|---|---|---|---|\n";
    int all_ok = 1;
    for (int sidx = 0; sidx < 3; sidx++) {
        sh_proc_scene ps;
        sh_mesh m;
        sh_scene *s;
        exp_check(sh_proc_parse(specs[sidx], &ps), "parse");
        exp_check(sh_mesh_procedural(&ps, &m), "mesh");
        exp_check(sh_scene_create(&m, 0, &s), "scene");
        const int order = orders[sidx], n2 = order * order, nv = m.nvert;
        double *T = malloc(sizeof(double) * nv * n2), *mu = calloc((size_t)nv * n2, sizeof(double)),
               *sq = calloc((size_t)nv * n2, sizeof(double));
        for (int r = 0; r < R; r++) {
            sh_transfer_opts o = {0};
            o.kind = SH_TRANSFER_SHADOWED;
            o.order = order;
            o.rays = 1024;
            o.seed = (unsigned long)r + 1;
            exp_check(sh_transfer(s, &o, T, NULL), "transfer");
            for (size_t i = 0; i < (size_t)nv * n2; i++) {
                mu[i] += T[i] / R;
                sq[i] += T[i] * T[i];
            }
        }
        const double k = gsl_cdf_tdist_Qinv(0.01 / (2.0 * nv * n2), R - 1);
        int cnt = 0, ncoef = 0;
        double emax = 0, amax = 0, xmax = -1e300, bmax = 0;
        for (int v = 0; v < nv; v++) {
            double t[16], b[16];
            int known;
            exp_check(sh_proc_closed_form(&ps, &m, v, order, SH_CS, 1, 1e-4 * sh_scene_diag(s), t, b, &known), "closed form");
            if (!known) continue;
            cnt++;
            for (int i = 0; i < known * known; i++) {
                const double mean = mu[(size_t)v * n2 + i];
                const double se = sqrt(fmax(0.0, (sq[(size_t)v * n2 + i] - R * mean * mean) / (R - 1)) / R);
                const double err = fabs(mean - t[i]), allow = b[i] + k * se + 1e-12;
                ncoef++;
                if (err > emax) { emax = err; amax = allow; }
                xmax = fmax(xmax, err - allow);
                bmax = fmax(bmax, b[i]);
            }
        }
        if (xmax > 0) all_ok = 0;
        fprintf(fc, "%s %d %d %.4e %.4e %.4e %.3f %.3e\n", specs[sidx], cnt, ncoef, emax, amax, xmax, k, bmax);
        char row[400];
        snprintf(row, sizeof row, "| %s (order %d%s) | %d | %d | %.2e | %.2e | %.2e |\n", specs[sidx], order,
                 sidx ? ", t_0" : ", every coefficient", cnt, ncoef, emax, amax, xmax);
        strncat(table, row, sizeof table - strlen(table) - 1);
        exp_progress("%s: %d vertices, max err %.3g, excess %.3g", specs[sidx], cnt, emax, xmax);
        free(T); free(mu); free(sq);
        sh_scene_free(s);
        sh_mesh_free(&m);
    }
    fclose(fc);

    /* ---- 3. the bowl's bounce series and the furnace */
    const double rho = 0.8;
    FILE *fb = exp_data("bounces.dat", "bowl, constant radiance 1, albedo 0.8: radiance added by bounce k (mean over vertices below the rim)",
                        "bounce measured_mean closed_form_(rho/2)^(k+1) measured_total closed_form_total_so_far");
    double furnace_dev = 0, bounce_dev = 0;
    {
        sh_proc_scene ps;
        sh_mesh m;
        sh_scene *s;
        exp_check(sh_proc_parse("bowl", &ps), "parse");
        ps.res = 8;
        exp_check(sh_mesh_procedural(&ps, &m), "mesh");
        exp_check(sh_scene_create(&m, 0, &s), "scene");
        double *T = malloc(sizeof(double) * m.nvert), prev = 0, cfsum = 0;
        for (int kb = 0; kb <= 8; kb++) {
            sh_transfer_opts o = {0};
            o.kind = kb ? SH_TRANSFER_INTERREFLECTED : SH_TRANSFER_SHADOWED;
            o.order = 1;
            o.rays = 4096;
            o.albedo = rho;
            o.max_bounces = kb;
            o.bounce_tol = 1e-300;
            exp_check(sh_transfer(s, &o, T, NULL), "transfer");
            double mean = 0;
            int c = 0;
            for (int v = 0; v < m.nvert; v++)
                if (m.pos[3 * v + 2] < -1e-9) { mean += sqrt(4 * M_PI) * T[v]; c++; }
            mean /= c;
            const double cf = pow(rho / 2, kb + 1);
            cfsum += cf;
            fprintf(fb, "%d %.6e %.6e %.6e %.6e\n", kb, mean - prev, cf, mean, cfsum);
            bounce_dev = fmax(bounce_dev, fabs(mean - prev - cf) / cf);
            prev = mean;
        }
        /* the furnace with ρ = 1: exact for the estimator */
        double *T1 = malloc(sizeof(double) * m.nvert);
        sh_transfer_opts o = {0};
        o.kind = SH_TRANSFER_INTERREFLECTED;
        o.order = 1;
        o.rays = 1024;
        o.albedo = 1;
        o.bounce_tol = 1e-13;
        o.max_bounces = 1000;
        exp_check(sh_transfer(s, &o, T1, NULL), "furnace");
        for (int v = 0; v < m.nvert; v++) furnace_dev = fmax(furnace_dev, fabs(sqrt(4 * M_PI) * T1[v] - 1));
        free(T1);
        free(T);
        sh_scene_free(s);
        sh_mesh_free(&m);
    }
    fclose(fb);

    /* ---- 4. timing on the real mesh: the timing part (machine-dependent;
     *         written by every run, skipped with a line without the models) */
    char wpath[4096];
    snprintf(wpath, sizeof wpath, "%s/Wuson.ply", getenv("MODELS_DIR") ? getenv("MODELS_DIR") : "data/models");
    exp_part("timing");
    if (access(wpath, R_OK)) {
        fprintf(stderr, "scene_transfer: timing skipped: no %s (run `make models`)\n", wpath);
        exp_index("**Timing skipped:** no `%s`. Run `make models` (copies Wuson and the spider from Debian's "
                  "assimp-testmodels) and `make report` again.",
                  wpath);
    } else {
        sh_mesh m;
        sh_mesh_report rep;
        sh_scene *s;
        exp_check(sh_mesh_load(wpath, SH_MESH_Y_UP, &m, &rep), wpath);
        exp_check(sh_scene_create(&m, 2, &s), "scene");
        double *T = malloc(sizeof(double) * m.nvert * 16);
        /* 1 and 2 threads as two entries of the interleaved engine (one
         * transfer per sample, 3 rounds): the same rounds pair them, and the
         * noise criterion says whether the machine was quiet */
        tctx ctx[2] = {{s, T, 1, 0}, {s, T, 2, 0}};
        sh_bench_entry ent[2] = {{"1 thread", run_transfer, NULL, &ctx[0], 1, 0}, {"2 threads", run_transfer, NULL, &ctx[1], 1, 0}};
        sh_bench_cfg cfg = SH_BENCH_CFG_DEFAULT;
        cfg.samples = 3;
        cfg.warmup = 0;
        cfg.count = 1;
        double smp[6];
        sh_bench_stats bs[2];
        sh_bench_noise noise;
        exp_progress("Wuson: shadowed transfer, 1 and 2 threads interleaved, 3 rounds");
        exp_check(sh_bench_interleaved(ent, 2, &cfg, smp, bs, &noise), "bench");
        sh_bench_ratio sp;
        exp_check(sh_bench_paired_ratio(smp, smp + 3, 3, 0, &sp), "ratio");
        const long long rays = ctx[0].rays;
        FILE *ft = exp_data("timing.dat", "shadowed transfer of Wuson.ply, order 4, 1024 rays per vertex (wall time)",
                            "threads round seconds rays rays_per_s");
        for (int th = 0; th < 2; th++)
            for (int r = 0; r < 3; r++)
                fprintf(ft, "%d %d %.4f %lld %.4e\n", th + 1, r, 1e-9 * smp[th * 3 + r], rays, rays / (1e-9 * smp[th * 3 + r]));
        fclose(ft);
        const double t1 = 1e-9 * bs[0].ns_median, t2 = 1e-9 * bs[1].ns_median;
        exp_index("**Time (the goal).** Shadowed transfer of `Wuson.ply` (%d vertices, %d triangles; Debian's "
                  "assimp-testmodels), order 4, 1024 rays per vertex (%lld rays): median of 3 rounds **%.2f s with 2 "
                  "threads** (range %.2f–%.2f s, %.2g rays/s) and %.2f s with 1 thread (range %.2f–%.2f s, %.2g "
                  "rays/s), the two interleaved in one process (sh_bench_interleaved); paired speed-up of 2 threads "
                  "%.2f (quartiles %.2f–%.2f). The run was %s. Data: [timing.dat](timing.dat).",
                  m.nvert, m.ntri, rays, t2, 1e-9 * bs[1].ns_min, 1e-9 * bs[1].ns_max, rays / t2, t1, 1e-9 * bs[0].ns_min,
                  1e-9 * bs[0].ns_max, rays / t1, sp.median, sp.q1, sp.q3,
                  noise.noisy ? "noisy (other work shared the machine; the times are upper bounds)" : "quiet");
        if (noise.noisy) exp_index("Noise: %s.", noise.why);
        char meas[96];
        snprintf(meas, sizeof meas, "%.2f s (2 threads, median of 3)%s", t2, noise.noisy ? ", noisy run" : "");
        /* a time within the goal is an upper bound met even under load; a
         * time beyond it is a verdict only on a quiet machine */
        exp_claim("scene-transfer-time", "shlab goal",
                  "shadowed transfer, order 4, 1024 rays/vertex, ~10k vertices, <= 10 s on 2 cores", "10 s", meas,
                  "10 s", t2 <= 10 ? "reproduced" : noise.noisy ? "not-measured" : "differs",
                  t2 <= 10 ? "scene_transfer/timing/timing.dat"
                  : noise.noisy ? "scene_transfer/timing/timing.dat; why: the time exceeds the goal in a noisy run, "
                                  "so it is no verdict (noise in timing.md)."
                                : "scene_transfer/timing/timing.dat; why: the median time on a quiet machine exceeds "
                                  "10 s.");
        free(T);
        sh_scene_free(s);
        sh_mesh_free(&m);
    }
    exp_part(NULL);

    char meas[64];
    snprintf(meas, sizeof meas, "%.2e", cf_max);
    exp_claim_judged("scene-unshadowed-closed-form", "Green 2003, SH Lighting Diffuse Surfaces",
                     "unshadowed transfer (clamped cosine rotated to n) equals an exact hemisphere quadrature", "-", meas, "1e-12",
                     cf_max <= 1e-12,
                     "scene_transfer/index.md",
                     "the closed form and the quadrature differ by more than 1e-12.");
    snprintf(meas, sizeof meas, "%.2e", furnace_dev);
    exp_claim_judged("scene-furnace", "shlab goal",
                     "energy conservation: interreflected transfer, albedo 1, constant light gives radiance 1 at every bowl "
                     "vertex", "-", meas, "1e-9", furnace_dev <= 1e-9,
                     "scene_transfer/index.md",
                     "the converged radiance departs from 1 by more than 1e-9.");

    exp_index("Green's transfer vectors on meshes (`src/scene/`): meshes read by assimp, rays cast by Embree 3, "
              "per-vertex transfer from a jittered grid of 1024 directions mapped to the hemisphere with density "
              "cosθ/π, formed in each vertex's tangent frame and rotated to the world with the SH rotation plan.");
    exp_index("**Unshadowed transfer in closed form** (t_lm = (ρ/π) √(4π/(2l+1)) z_l y_lm(n), z_l of max(0, cosθ)) "
              "against an exact quadrature of ∫_H y_i (n·s) ds in the normal's frame (Gauss-Legendre in cosθ × "
              "uniform φ, exact for the polynomial integrand), orders 1–16, 20 random normals each: largest "
              "difference **%.1e**.",
              cf_max);
    exp_index("**Shadowed transfer by rays against closed forms** (1024 rays, 16 replications with independent jitter). "
              "sphere-plane: plane vertices whose view of the sphere lies above the horizon; the cap of half-angle "
              "asin(R/d) removed from every coefficient (Gaunt coefficients and the cap's zonal coefficients); "
              "allowance = the polyhedral sphere's bracket between its inscribed and circumscribed spheres + k·SE. "
              "bowl: sky fraction ½ at every point of a sphere's inside (view factors are area fractions). box-open: "
              "the hole's view factor from the floor (Howell's B-3). k is the Student-t quantile (15 degrees of "
              "freedom) at which all comparisons of a scene together fail by chance with probability 1 %%. "
              "Data: [closed_forms.dat](closed_forms.dat).\n\n%s\n%s",
              table, all_ok ? "Every compared coefficient lies within its allowance." : "**Some coefficient lies outside its allowance.**");
    exp_index("![bounces](scene_bounces.png)\n\n**Interreflection.** Inside the bowl under a constant environment of "
              "radiance 1, bounce k adds (ρ/2)^(k+1) (each point sees the sky and the bowl half each, and the bowl "
              "spreads its light evenly), so with ρ = %.1f the series converges to ρ/(2−ρ). Measured (mean over "
              "the vertices below the rim, 4096 rays): the largest relative deviation of a bounce from the closed "
              "form is %.1e. With ρ = 1 the furnace answer (radiance 1) is exact for the estimator, since the "
              "cosine-weighted weights of each vertex sum to one: largest deviation **%.1e** after convergence "
              "(bounce tolerance 1e-13). Data: [bounces.dat](bounces.dat).",
              rho, bounce_dev, furnace_dev);
    return 0;
}
