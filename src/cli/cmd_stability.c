/* cmd_stability.c — `shlab stability`: a method's accuracy band by band
 * (orthogonality, homomorphism, distance to the MPFR reference) over the fixed
 * rotation set with the extremes. */
#include "cli.h"

#include <getopt.h>
#include <math.h>
#include <stdlib.h>

extern const cli_command cmd_stability;

static const char help[] =
    "Usage: shlab stability --method M --lmax L [OPTIONS]\n"
    "\n"
    "Accuracy of a rotation method band by band, l = 0..L, as the maximum over a\n"
    "fixed set of 10 rotations: β = 0, 1e-12, π/2, π-1e-9, π, the gimbal-lock\n"
    "cases (0.9, 0, -0.9) and (π/2, π, π/2), β = 1e-7 with α+γ = 0, and two seeded\n"
    "random rotations (the z method uses only those with β = 0).\n"
    "  orth   max|R Rᵀ - I| (exact up to --exact-max, above it the probe estimate\n"
    "         max|Rᵀ(R v) - v| over two seeded unit vectors; orth_exact says which)\n"
    "  hom    max|R(a)(R(b) v) - R(ab) v| over two unit probes, pairs of the set\n"
    "  ref    max|R - R_reference| (MPFR, ≥30 digits) up to --ref-max, else empty\n"
    "  broken true if the method overflowed (its numbers are then empty)\n"
    "\n"
    "  --method M           z | ivanic | zxzxz | choi | blanco | wigner | reference\n"
    "                       | taylor1 | taylor1.5 | taylor2\n"
    "  --lmax L             every band 0..L (L <= 1000)\n"
    "  --bands L1,L2,...    only these bands (increasing, <= 1000); single-band\n"
    "                       methods then compute nothing else\n"
    "  --stop-above X       stop after the first band whose orth exceeds X\n"
    "  --precision P        double (default) | float\n"
    "  --ref-max R          compare with the reference up to band R (default 40)\n"
    "  --exact-max E        exact orthogonality up to band E (default 128)\n"
    "  --convention cs|nocs\n"
    "  --degrees            print the rotations' Euler angles in degrees\n"
    "  --quiet              no progress on stderr\n"
    "  --format table|csv|json\n"
    "  --help               this text\n"
    "\n"
    "JSON: {\"method\",\"precision\",\"convention\",\"lmax\",\"unit\" (of the Euler angles),\n"
    "       \"rotations\":[{name,euler}],\n"
    "       \"rows\":[{\"band\",\"orth\",\"orth_exact\",\"hom\",\"ref\",\"broken\"}]}\n";

typedef struct {
    json_t *rows;
    int lmax, quiet, fail, sparse;
} acc;

static json_t *num_or_null(double x, int ok) { return ok ? json_real(x) : json_null(); }

static int on_row(const sh_rot_stability_row *r, void *vctx)
{
    acc *a = vctx;
    json_t *o = json_object();
    o = cli_put(o, "band", json_integer(r->band));
    o = cli_put(o, "orth", num_or_null(r->orth, !r->broken));
    o = cli_put(o, "orth_exact", json_boolean(r->orth_exact));
    o = cli_put(o, "hom", num_or_null(r->hom, !r->broken));
    o = cli_put(o, "ref", num_or_null(r->ref, r->have_ref && !r->broken));
    o = cli_put(o, "broken", json_boolean(r->broken));
    if (!o || json_array_append_new(a->rows, o)) { a->fail = 1; return SH_ENOMEM; }
    if (!a->quiet && a->lmax >= 100 && (r->band % 50 == 0 || r->band == a->lmax || a->sparse))
        fprintf(stderr, "stability: band %d of %d\n", r->band, a->lmax);
    return SH_OK;
}

static int run(int argc, char **argv)
{
    static const struct option opts[] = {CLI_LONGOPTS_BASE,
                                         CLI_LONGOPT_CONVENTION,
                                         CLI_LONGOPT_DEGREES,
                                         CLI_LONGOPT_METHOD,
                                         CLI_LONGOPT_PRECISION,
                                         {"lmax", required_argument, 0, 'L'},
                                         {"ref-max", required_argument, 0, 'r'},
                                         {"exact-max", required_argument, 0, 'e'},
                                         {"quiet", no_argument, 0, 'q'},
                                         {"bands", required_argument, 0, 'B'},
                                         {"stop-above", required_argument, 0, 's'},
                                         {0, 0, 0, 0}};
    cli_common com = CLI_COMMON_DEFAULTS;
    sh_rot_method method = SH_ROT_IVANIC;
    sh_precision prec = SH_PREC_DOUBLE;
    int lmax = -1, ref_max = 40, exact_max = 128, have_method = 0, quiet = 0, nb = 0;
    int band_list[1001], *bands = NULL; /* increasing, in 0..1000: at most 1001 */
    double stop_above = 0;
    opterr = 0;
    optind = 1;
    int o;
    while ((o = getopt_long(argc, argv, "h", opts, NULL)) != -1) {
        switch (o) {
        case 'L':
            if (cli_int("--lmax", optarg, &lmax)) return CLI_EXIT_USAGE;
            if (lmax < 0 || lmax > 1000) return cli_fail("--lmax: %d out of range 0..1000", lmax);
            break;
        case 'r':
            if (cli_int("--ref-max", optarg, &ref_max)) return CLI_EXIT_USAGE;
            if (ref_max < -1 || ref_max > 300) return cli_fail("--ref-max: %d out of range -1..300", ref_max);
            break;
        case 'e':
            if (cli_int("--exact-max", optarg, &exact_max)) return CLI_EXIT_USAGE;
            if (exact_max < -1) return cli_fail("--exact-max: %d must be >= -1", exact_max);
            break;
        case 'q': quiet = 1; break;
        case 's':
            if (cli_double("--stop-above", optarg, &stop_above)) return CLI_EXIT_USAGE;
            if (!(stop_above > 0)) return cli_fail("--stop-above: must be > 0");
            break;
        case 'B': {
            double *v = NULL;
            if (cli_doubles("--bands", optarg, &v, &nb)) return CLI_EXIT_USAGE;
            for (int q = 0; q < nb; q++) {
                if (q > 1000 || v[q] != floor(v[q]) || v[q] < 0 || v[q] > 1000 || (q && v[q] <= v[q - 1])) {
                    free(v);
                    return cli_fail("--bands: need increasing integers in 0..1000");
                }
                band_list[q] = (int)v[q];
            }
            free(v);
            bands = band_list;
            break;
        }
        default: {
            const int e = cli_common_opt(&cmd_stability, o, argv, &com);
            if (e >= 0) return e;
        }
        }
    }
    /* --method and --precision are kept by cli_common_opt */
    method = com.method;
    prec = com.prec;
    have_method = com.have_method;
    if (optind < argc) return cli_fail("stability: unexpected argument '%s'", argv[optind]);
    if (!have_method) return cli_fail("stability: --method is required");
    if (bands && lmax >= 0) return cli_fail("stability: give --lmax or --bands, not both");
    if (bands) lmax = bands[nb - 1];
    if (lmax < 0) return cli_fail("stability: --lmax (or --bands) is required");
    if (lmax + 1 > sh_rot_method_max_order(method))
        return cli_fail("stability: method %s is limited to order %d (lmax %d)",
                        sh_rot_method_name(method), sh_rot_method_max_order(method),
                        sh_rot_method_max_order(method) - 1);
    acc a = {json_array(), lmax, quiet, 0, bands != NULL};
    int st = sh_rot_stability(method, prec, com.conv, lmax, bands, bands ? nb : 0, ref_max,
                              exact_max, stop_above, on_row, &a);
    if (st) { json_decref(a.rows); return cli_fail_status(st); }
    sh_rotation set[SH_ROT_STABILITY_NSET];
    const char *names[SH_ROT_STABILITY_NSET];
    sh_rot_stability_set(set, names);
    json_t *rots = json_array();
    for (int k = 0; k < SH_ROT_STABILITY_NSET; k++) {
        if (method == SH_ROT_Z && set[k].beta != 0) continue;
        double e[3] = {cli_angle_out(set[k].alpha, com.degrees), cli_angle_out(set[k].beta, com.degrees),
                       cli_angle_out(set[k].gamma, com.degrees)};
        json_t *r = json_object();
        r = cli_put(r, "name", json_string(names[k]));
        r = cli_put(r, "euler", cli_json_array(e, 3));
        if (!r || json_array_append_new(rots, r)) { json_decref(rots); rots = NULL; break; }
    }
    json_t *root = json_object();
    root = cli_put(root, "method", json_string(sh_rot_method_name(method)));
    root = cli_put(root, "precision", json_string(sh_precision_name(prec)));
    root = cli_put(root, "convention", json_string(sh_convention_name(com.conv)));
    root = cli_put(root, "lmax", json_integer(lmax));
    root = cli_put(root, "unit", json_string(cli_angle_unit(com.degrees)));
    root = cli_put(root, "rotations", rots);
    root = cli_put(root, "rows", a.rows);
    return cli_emit(root, com.fmt);
}

const cli_command cmd_stability = {"stability", run,
                                   "a rotation method's error band by band (orthogonality, "
                                   "homomorphism, reference)",
                                   help};
