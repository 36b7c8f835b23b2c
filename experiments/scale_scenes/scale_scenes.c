/* scale_scenes — SH scaling against ground truth (Wang et al. 2006, Sec. 3,
 * Figs. 5-7 in spirit).  Scenes and error measures: see src/scale/scale_scene.c.
 *  sphere    occluder radius ρ = r/2, sampled at d = r, scaled to k = d/r;
 *  cone      cone occluder θ0 = 45°, rim at r/2·(1 + 0.3 cosφ) (non-zonal);
 *  midrange  two smooth lobes on a sphere of radius R, and (when present) a
 *            real HDR probe from $PROBES_DIR (default data/probes), captured at
 *            the centre and scaled to d = kR along +z.
 *  midrange_tilted  the lobes displaced along a tilted axis d (θ = 60°,
 *            φ = 135°): rotate the capture so that d becomes +z (zxzxz plan),
 *            scale, rotate back; the exact radiance by the ray-sphere hit
 *            about d, the untruncated reference about d without SH rotations.
 * Every scene with plain and energy-preserving scaling; orders 2, 4, 6, 8.
 * The probe scene is a kept part (reports/scale_scenes/probes/, exp.h):
 * without a probe it is left as it is, and its text names the revision that
 * computed it. */
#include <dirent.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "exp.h"

static const int orders[4] = {2, 4, 6, 8};

/* One scene: rows "k order family energy err_scaled err_geom err_trunc". */
static void sweep(FILE *f, const sh_scale_scene *sc, const double *ks, int nk, const sh_scale_family *fams, int nf,
                  double fam_cone, double res[4][2][2][64][3])
{
    const int nmax = 64;
    double Sr[64];
    for (int o = 0; o < 4; o++) {
        exp_progress("%s scene, order %d", sh_scale_scene_name(sc->kind), orders[o]);
        exp_check(sh_scale_scene_exact(sc, orders[o], SH_CS, sh_scale_scene_k_ref(sc), Sr), "reference projection");
        /* one curve after another (family, mode), so that gnuplot's lines connect */
        for (int fa = 0; fa < nf; fa++)
            for (int e = 0; e < 2; e++)
                for (int q = 0; q < nk && q < nmax; q++) {
                    sh_scaling s = {fams[fa], ks[q], fams[fa] == SH_SCALE_CONE ? fam_cone : 0.0, e};
                    sh_scale_scene_err er;
                    exp_check(sh_scale_scene_errors(sc, orders[o], SH_CS, &s, ks[q], Sr, &er, NULL), "scene errors");
                    fprintf(f, "%.6f %d %d %d %.6e %.6e %.6e\n", ks[q], orders[o], fa, e, er.err_scaled, er.err_geom,
                            er.err_trunc);
                    res[o][fa][e][q][0] = er.err_scaled;
                    res[o][fa][e][q][1] = er.err_geom;
                    res[o][fa][e][q][2] = er.err_trunc;
                }
        fprintf(f, "\n\n");
    }
}

static void write_matrix(const char *name, const char *title, const float *v, int W, int H)
{
    FILE *f = exp_data(name, title, "gnuplot matrix: rows = θ from 0 (top), columns = φ");
    for (int j = 0; j < H; j++) {
        for (int i = 0; i < W; i++) fprintf(f, "%s%.5g", i ? " " : "", v[(size_t)j * W + i]);
        fputc('\n', f);
    }
    fclose(f);
}

/* Exact scene function at k, point-sampled on a lat-long grid. */
static void write_exact(const char *name, const sh_scale_scene *sc, double k, int W)
{
    const int H = W / 2;
    float *v = malloc(sizeof(float) * W * H);
    for (int j = 0; j < H; j++)
        for (int i = 0; i < W; i++)
            v[j * W + i] = (float)sh_scale_scene_value(sc, k, M_PI * (j + 0.5) / H, 2 * M_PI * (i + 0.5) / W);
    char t[128];
    snprintf(t, sizeof t, "%s scene at k = %g, exact", sh_scale_scene_name(sc->kind), k);
    write_matrix(name, t, v, W, H);
    free(v);
}

static void write_recon(const char *name, const char *title, int order, const double *c, int W, const char *exr)
{
    sh_window none = {SH_WINDOW_NONE, 0};
    sh_image img;
    exp_check(sh_reconstruct_latlong(order, SH_CS, c, 1, &none, W, &img), "reconstruct");
    write_matrix(name, title, img.data, img.width, img.height);
    if (exr) {
        char p[4096];
        snprintf(p, sizeof p, "%s/%s", exp_outdir(), exr);
        exp_check(sh_exr_write(p, &img), "EXR write");
    }
    sh_image_free(&img);
}

static int find_probe(char *path, size_t n)
{
    const char *dir = getenv("PROBES_DIR") ? getenv("PROBES_DIR") : "data/probes";
    DIR *d = opendir(dir);
    if (!d) return 0;
    struct dirent *e;
    char best[256] = "";
    while ((e = readdir(d))) {
        const size_t L = strlen(e->d_name);
        if (L > 4 && !strcmp(e->d_name + L - 4, ".exr") && L < sizeof best &&
            (!best[0] || strcmp(e->d_name, best) < 0))
            strcpy(best, e->d_name);
    }
    closedir(d);
    if (!best[0]) return 0;
    snprintf(path, n, "%s/%s", dir, best);
    return 1;
}

static double res_sph[4][2][2][64][3], res_cone[4][2][2][64][3], res_mid[4][2][2][64][3], res_probe[4][2][2][64][3],
    res_tilt[4][2][2][64][3];

int main(int argc, char **argv)
{
    exp_init(argc, argv);
    const sh_scale_family occ_f[2] = {SH_SCALE_LINEAR, SH_SCALE_CONE}, mid_f[1] = {SH_SCALE_MIDRANGE};

    /* ---- sphere occluder ---- */
    sh_scale_scene sph = {SH_SCENE_SPHERE, 0.5, 0, 0, NULL, NULL, NULL, 0, {0, 0, 0}, 0};
    const int nks = 21;
    double ks[64];
    for (int q = 0; q < nks; q++) ks[q] = sh_scale_grid_point(SH_SPACING_GEOMETRIC, 0.55, 2.5, q, nks);
    FILE *f = exp_data("sphere.dat", "sphere occluder rho = r/2: scaling from d = r to d = k r",
                       "k order family(0 linear, 1 cone θ0 = acos(1/2)) energy err_scaled err_geom err_trunc; one block per order");
    sweep(f, &sph, ks, nks, occ_f, 2, acos(0.5), res_sph);
    fclose(f);
    const int k2 = nks - 4; /* k ≈ 1.7 */
    const int k07 = 3;

    /* ---- cone occluder ---- */
    sh_scale_scene cone = {SH_SCENE_CONE, 0.5, M_PI / 4, 0.3, NULL, NULL, NULL, 0, {0, 0, 0}, 0};
    double kc[64];
    for (int q = 0; q < nks; q++) kc[q] = sh_scale_grid_point(SH_SPACING_GEOMETRIC, 0.7, 2.5, q, nks);
    f = exp_data("cone.dat", "cone occluder θ0 = 45°, rim r/2 (1 + 0.3 cosφ)",
                 "k order family(0 linear, 1 cone θ0 = 45°) energy err_scaled err_geom err_trunc; one block per order");
    sweep(f, &cone, kc, nks, occ_f, 2, M_PI / 4, res_cone);
    fclose(f);

    /* ---- mid-range: analytic lobes ---- */
    sh_scale_scene mid = {SH_SCENE_MIDRANGE, 0, 0, 0, sh_scale_scene_lobes_fn, NULL, NULL, 160, {0, 0, 0}, 0};
    const int nkm = 19;
    double km[64];
    for (int q = 0; q < nkm; q++) km[q] = -0.9 + 1.8 * q / (nkm - 1);
    f = exp_data("midrange.dat", "mid-range environment (two smooth lobes), centre to d = kR along +z",
                 "k order family(0 midrange) energy err_scaled err_geom err_trunc; one block per order");
    sweep(f, &mid, km, nkm, mid_f, 1, 0, res_mid);
    fclose(f);

    /* ---- mid-range: the same lobes, displaced along a tilted axis ---- */
    const double tth = 60.0 * M_PI / 180.0, tph = 135.0 * M_PI / 180.0;
    sh_scale_scene tilt = mid;
    sh_dir_from_angles(tth, tph, tilt.dir);
    tilt.rotation = SH_ROT_ZXZXZ;
    f = exp_data("midrange_tilted.dat",
                 "mid-range environment (two smooth lobes), centre to d = kR along the tilted axis (theta, phi) = (60, 135) "
                 "deg: rotate to the axis (zxzxz), scale, rotate back",
                 "k order family(0 midrange) energy err_scaled err_geom err_trunc; one block per order");
    sweep(f, &tilt, km, nkm, mid_f, 1, 0, res_tilt);
    fclose(f);

    /* ---- mid-range: a real probe, when present ---- */
    char probe[4096];
    int have_probe = find_probe(probe, sizeof probe);
    sh_image img = {0};
    const int nkp = 9;
    double kp[64];
    for (int q = 0; q < nkp; q++) kp[q] = -0.8 + 1.6 * q / (nkp - 1);
    if (have_probe && (sh_exr_read(probe, &img, NULL) || img.width != 2 * img.height)) {
        fprintf(stderr, "scale_scenes: probe %s unusable (%s); skipped\n", probe, sh_last_error());
        sh_image_free(&img);
        have_probe = 0;
    }
    if (have_probe) {
        exp_part("probes");
        f = exp_data("probe.dat", probe, "k order family(0 midrange) energy err_scaled err_geom err_trunc; one block per order");
        sh_scale_scene ps = {SH_SCENE_MIDRANGE, 0, 0, 0, NULL, NULL, &img, 256, {0, 0, 0}, 0};
        sweep(f, &ps, kp, nkp, mid_f, 1, 0, res_probe);
        fclose(f);
        /* kp[q] = -0.8 + 0.2 q → q = 7 is k = 0.6 */
        char me[5200];
        snprintf(me, sizeof me, "%s, order 4, k = 0.6: plain %.3f, energy-preserving %.3f (relative L2 of luminance coefficients)",
                 probe, res_probe[1][0][0][7][0], res_probe[1][0][1][7][0]);
        exp_claim("scale-probe-midrange", "Wang et al. 2006, Sec. 3.2", "mid-range lighting from a captured environment",
                  "qualitative (Fig. 11)", me, "-", "not-applicable",
                  "scale_scenes/probes/probe.dat; why: Fig. 11 is qualitative, so there is no number to compare; the "
                  "row records the error measured on a captured probe.");
        exp_index("![probe](scale_scenes_probe.png)\n\n"
                  "Mid-range lighting from a captured environment: the same sweep with the first HDR probe found, "
                  "`%s` (luminance, bilinear lookup, 256-node product rule; computed at code revision `%s`, kept "
                  "as it is by a `make report` without the probes of `make probes`). Order 4, k = 0.6: plain %.3f, "
                  "energy-preserving %.3f.",
                  probe, exp_revision(), res_probe[1][0][0][7][0], res_probe[1][0][1][7][0]);
        exp_part(NULL);
    } else {
        fprintf(stderr, "scale_scenes: no probe found (run `make probes`): the probe scene is kept as it is\n");
    }

    /* ---- images (Figs. 5-7 in spirit), order 8, 96×48 lat-long ---- */
    const int W = 96, NO = 8, n = NO * NO;
    double Sr[64], Se[64], Sd[64];
    const double kimg[3] = {0.75, 1.3, 2.0};
    exp_check(sh_scale_scene_exact(&cone, NO, SH_CS, 1.0, Sr), "cone reference");
    for (int q = 0; q < 3; q++) {
        char nm[64], t[160];
        snprintf(nm, sizeof nm, "img_cone_exact_%d.dat", q);
        write_exact(nm, &cone, kimg[q], W);
        sh_scaling s = {SH_SCALE_CONE, kimg[q], M_PI / 4, 0};
        sh_scale_scene_err er;
        exp_check(sh_scale_scene_errors(&cone, NO, SH_CS, &s, kimg[q], Sr, &er, Sd), "cone scaled");
        snprintf(nm, sizeof nm, "img_cone_scaled_%d.dat", q);
        snprintf(t, sizeof t, "cone scene, order-8 reconstruction of cone-family plain scaling from k = 1 to %g", kimg[q]);
        char ex[64];
        snprintf(ex, sizeof ex, "cone_scaled_cone_k%g_order8.exr", kimg[q]);
        write_recon(nm, t, NO, Sd, W, ex);
        s.family = SH_SCALE_LINEAR;
        exp_check(sh_scale_scene_errors(&cone, NO, SH_CS, &s, kimg[q], Sr, &er, Sd), "linear scaled");
        snprintf(nm, sizeof nm, "img_cone_linear_%d.dat", q);
        snprintf(t, sizeof t, "cone scene, order-8 reconstruction of linear-family plain scaling from k = 1 to %g", kimg[q]);
        snprintf(ex, sizeof ex, "cone_scaled_linear_k%g_order8.exr", kimg[q]);
        write_recon(nm, t, NO, Sd, W, ex);
    }
    const double kmi = 0.7;
    write_exact("img_mid_exact.dat", &mid, kmi, W);
    exp_check(sh_scale_scene_exact(&mid, NO, SH_CS, 0.0, Sr), "mid reference");
    exp_check(sh_scale_scene_exact(&mid, NO, SH_CS, kmi, Se), "mid exact");
    write_recon("img_mid_exact_proj.dat", "mid-range k = 0.7: order-8 projection of the exact radiance", NO, Se, W,
                "midrange_exact_order8.exr");
    for (int e = 0; e < 2; e++) {
        sh_scaling s = {SH_SCALE_MIDRANGE, kmi, 0, e};
        sh_scale_scene_err er;
        exp_check(sh_scale_scene_errors(&mid, NO, SH_CS, &s, kmi, Sr, &er, Sd), "mid scaled");
        write_recon(e ? "img_mid_energy.dat" : "img_mid_plain.dat",
                    e ? "mid-range k = 0.7: energy-preserving scaling of the centre capture, order 8"
                      : "mid-range k = 0.7: plain scaling of the centre capture, order 8",
                    NO, Sd, W, e ? "midrange_scaled_energy_order8.exr" : "midrange_scaled_plain_order8.exr");
    }
    /* the tilted axis at the same k */
    write_exact("img_tilt_exact.dat", &tilt, kmi, W);
    exp_check(sh_scale_scene_exact(&tilt, NO, SH_CS, kmi, Se), "tilted exact");
    write_recon("img_tilt_exact_proj.dat", "mid-range k = 0.7 along (60, 135) deg: order-8 projection of the exact radiance",
                NO, Se, W, "midrange_tilted_exact_order8.exr");
    for (int e = 0; e < 2; e++) {
        sh_scaling s = {SH_SCALE_MIDRANGE, kmi, 0, e};
        sh_scale_scene_err er;
        exp_check(sh_scale_scene_errors(&tilt, NO, SH_CS, &s, kmi, Sr, &er, Sd), "tilted scaled");
        write_recon(e ? "img_tilt_energy.dat" : "img_tilt_plain.dat",
                    e ? "mid-range k = 0.7 along (60, 135) deg: energy-preserving scaling (rotate, scale, rotate back), order 8"
                      : "mid-range k = 0.7 along (60, 135) deg: plain scaling (rotate, scale, rotate back), order 8",
                    NO, Sd, W, e ? "midrange_tilted_scaled_energy_order8.exr" : "midrange_tilted_scaled_plain_order8.exr");
    }
    (void)n;

    /* ---- claims and index ---- */
    /* midrange index of k = ±0.5: km[q] = -0.9 + 0.1 q → q = 14 is 0.5 */
    const int q05 = 14;
    char me[5000];
    double worst_mid_plain_geom = 0, worst_cone_geom = 0, worst_tilt_plain_geom = 0;
    for (int o = 0; o < 4; o++) {
        for (int q = 0; q < nkm; q++) worst_mid_plain_geom = fmax(worst_mid_plain_geom, res_mid[o][0][0][q][1]);
        for (int q = 0; q < nkm; q++) worst_tilt_plain_geom = fmax(worst_tilt_plain_geom, res_tilt[o][0][0][q][1]);
        for (int q = 0; q < nks; q++) worst_cone_geom = fmax(worst_cone_geom, res_cone[o][1][0][q][1]);
    }
    snprintf(me, sizeof me,
             "geometry alone: mid-range k = 0.5 plain %.1e, energy-preserving %.2f; sphere k = %.2f plain %.3f, "
             "energy %.2f; cone (cone family) plain %.1e, energy %.2f at k = %.2f",
             res_mid[1][0][0][q05][1], res_mid[1][0][1][q05][1], ks[k2], res_sph[1][1][0][k2][1],
             res_sph[1][1][1][k2][1], worst_cone_geom, res_cone[1][1][1][k2][1], kc[k2]);
    const int energy_wrong = worst_mid_plain_geom < 1e-12 && res_mid[1][0][1][q05][1] > 0.05;
    exp_claim("wang-energy-for-radiance", "Wang et al. 2006, Sec. 3.1",
              "radiance of light sources (SRFs, and mid-range lighting in Sec. 3.2) is scaled with the energy-preserving "
              "ψ = sin τ·τ′",
              "energy-preserving for radiance", me, "energy-preserving geometry error > 5 % where plain is exact (< 1e-12)",
              energy_wrong ? "differs" : "reproduced",
              energy_wrong ? "scale_scenes/midrange.dat, sphere.dat, cone.dat; why: radiance is invariant along a ray, "
                             "so plain scaling is the exact transport and the solid-angle factor makes it wrong."
                           : "scale_scenes/midrange.dat, sphere.dat, cone.dat");
    snprintf(me, sizeof me,
             "sphere occluder ρ = r/2, order 8, k = %.2f / %.2f: geometry error cone %.3f / %.3f, linear %.3f / "
             "%.3f; total cone %.3f / %.3f, linear %.3f / %.3f",
             ks[k07], ks[k2], res_sph[3][1][0][k07][1], res_sph[3][1][0][k2][1], res_sph[3][0][0][k07][1],
             res_sph[3][0][0][k2][1], res_sph[3][1][0][k07][0], res_sph[3][1][0][k2][0], res_sph[3][0][0][k07][0],
             res_sph[3][0][0][k2][0]);
    const int cone_close = res_sph[3][1][0][k2][1] < 0.1 && res_sph[3][1][0][k07][1] < 0.1;
    exp_claim_judged("wang-cone-approximation", "Wang et al. 2006, Sec. 3.1",
                     "the cone approximation (Figs. 4-5) gives visibility close to the actual one at other radii (here a "
                     "sphere occluder, not a cone; the linear family beside it)",
                     "qualitative (Fig. 5)", me, "geometry error < 10 % (relative L2, order 8)", cone_close,
                     "scale_scenes/sphere.dat",
                     "the cone family's geometry error reaches 10 % at k = 0.7 or 2.");
    snprintf(me, sizeof me,
             "along (θ, φ) = (60°, 135°), orders 2-8, k = -0.9..0.9: largest plain geometry error %.1e; order 4, "
             "k = 0.5: plain %.3f, energy-preserving %.3f (index.md#scale_scenes)",
             worst_tilt_plain_geom, res_tilt[1][0][0][q05][0], res_tilt[1][0][1][q05][0]);
    exp_claim_judged("wang-midrange-arbitrary-axis", "Wang et al. 2006, Sec. 3.2",
                     "a displacement in any direction is handled by rotating to the axis, scaling and rotating back",
                     "rotate, scale, rotate back", me, "plain geometry error < 1e-12 (the +z case's level)",
                     worst_tilt_plain_geom < 1e-12,
                     "scale_scenes/midrange_tilted.dat",
                     "the rotate-scale-rotate pipeline is off the exact geometry by more than 1e-12.");
    snprintf(me, sizeof me,
             "order 4, plain: sphere scene k = %.2f total %.2f, truncation alone %.2f; cone scene (exact geometry) "
             "k = %.2f: %.2f; order 8: %.2f and %.2f",
             ks[k2], res_sph[1][1][0][k2][0], res_sph[1][1][0][k2][2], kc[k2], res_cone[1][1][0][k2][0],
             res_sph[3][1][0][k2][0], res_cone[3][1][0][k2][0]);
    exp_claim("scale-truncation", "Wang et al. 2006, Sec. 3.1",
              "scaling a truncated (fourth-order) field: the error when shrinking (k > 1) is dominated by truncation, "
              "not by the family",
              "-", me, "-", "not-applicable",
              "scale_scenes/sphere.dat, cone.dat; why: the paper does not separate truncation from the family's "
              "geometry; the row records the split measured here.");
    exp_index("![sphere occluder](scale_scenes_sphere.png)\n\n"
              "**Sphere occluder** (radius r/2, centre at θ = 0): the occlusion seen from distance d is exactly the "
              "cap arcsin(ρ/d) (closed form, sh_cap_zonal). It is projected at d = r, scaled to d = k r with the "
              "linear family (k) and the cone family (θ0 = arccos(ρ/r) = 60°, the cone through the silhouette seen "
              "from r), plain and energy-preserving, and compared with the exact projection at d. Solid: total "
              "relative L2 error |M S_r − E|/|E|; dashed: the family's geometry alone (scaling the exact function, "
              "no truncation). At order 8, k = %.2f: cone family geometry %.3f, linear %.3f; the total error is "
              "dominated by truncation when shrinking (k > 1): the truncated capture's ringing near θ = π is "
              "stretched over the whole far side.\n\n"
              "![cone occluder](scale_scenes_cone.png)\n\n"
              "**Cone occluder** (θ0 = 45°, rim at height r/2·(1 + 0.3 cos φ): not zonal). Its rim lies on the "
              "cone surface, so the cone family is exact geometry: the dashed plain cone curve sits at %.0e "
              "(quadrature level) for every k and order, and what remains is truncation only. This independently "
              "confirms the cone τ of docs/CONVENTIONS.md (also checked against a 3-D ray-cone intersection in the "
              "unit tests).\n\n"
              "![mid-range lighting](scale_scenes_midrange.png)\n\n"
              "**Mid-range lighting** (two smooth non-zonal lobes on a sphere of radius R, captured at the centre, "
              "exact radiance at d = kR by ray-sphere intersection, projected by a 160-node product rule). Plain "
              "scaling with the mid-range family is exact geometry (dashed, %.0e); its error is truncation only "
              "(order 4, k = 0.5: %.3f). Energy-preserving scaling multiplies by the solid-angle Jacobian "
              "sin τ·τ′/sin θ and is wrong by %.2f (geometry alone, k = 0.5) — more than the truncation error.\n\n"
              "**Which scaling is right where.** Visibility (0/1) and radiance from an emitting surface are both "
              "invariant along a ray, so the value seen in direction θ from the new point is the value seen in "
              "direction τ(θ) from the old one: plain scaling (ψ = sin θ) is the exact transport in all three "
              "scenes. Energy-preserving scaling keeps ∫F dΩ, which is right only for a *density per solid angle of "
              "a conserved quantity* mapped by τ (e.g. the angular distribution of a fixed amount of flux); for "
              "radiance it makes a source seen from closer up both larger and dimmer, so the irradiance does not "
              "grow as 1/d². The paper's use of energy-preserving scaling for the radiance of light sources "
              "(Sec. 3.1) is therefore not supported by these measurements.\n\n"
              "![mid-range lighting, tilted axis](scale_scenes_midrange_tilted.png)\n\n"
              "**Mid-range lighting along a tilted axis** (the same lobes, the point moved to kR·d with d at "
              "(θ, φ) = (60°, 135°)): the centre capture is rotated so that d becomes +z (zxzxz rotation plan), "
              "scaled with the mid-range matrix and rotated back (`shlab scale-scene --scene midrange --dir X,Y,Z`). "
              "The exact radiance comes from the ray-sphere hit about d and the untruncated reference F_r∘τ is "
              "evaluated about d directly (3×3 rotation of directions, no SH rotation), so the dashed plain "
              "geometry curve (largest %.1e over orders 2–8 and k) checks the rotate → scale → rotate back "
              "pipeline as well as the geometry. Order 4, k = 0.5: plain %.3f (all truncation), energy-preserving %.3f "
              "although its geometry alone is wrong by %.3f (truncation and geometry errors partly cancel at low "
              "order); along +z: %.3f, %.3f. The errors depend on the direction only through the environment's "
              "position relative to the axis.\n\n"
              "![tilted reconstructions](scale_scenes_tilted_images.png)\n\n"
              "![reconstructions](scale_scenes_images.png)\n\n"
              "Reconstructions in the spirit of Figs. 5 and 7 (lat-long, θ down): top, the exact cone-occluder "
              "visibility at k = 0.75, 1.3, 2; middle, order-8 reconstruction of cone-family scaling of the capture "
              "at k = 1; bottom, the same with the linear family. Mid-range at k = 0.7 (Fig. 6/11 in spirit): exact "
              "radiance, order-8 projection of it, and plain and energy-preserving scaling of the centre capture "
              "(EXR files of the last three beside this report; the tilted-axis ones as midrange_tilted_*.exr; the "
              "cone-scene reconstructions as cone_scaled_*.exr).",
              ks[k2], res_sph[3][1][0][k2][1], res_sph[3][0][0][k2][1], fmax(worst_cone_geom, 1e-16),
              fmax(worst_mid_plain_geom, 1e-16), res_mid[1][0][0][q05][0], res_mid[1][0][1][q05][1],
              fmax(worst_tilt_plain_geom, 1e-16), res_tilt[1][0][0][q05][0], res_tilt[1][0][1][q05][0],
              res_tilt[1][0][1][q05][1], res_mid[1][0][0][q05][0], res_mid[1][0][1][q05][0]);
    sh_image_free(&img);
    return 0;
}
