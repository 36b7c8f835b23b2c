/* cli_angles.c — one meaning of --degrees in every command (docs/CONVENTIONS.md
 * "Angles and units"): every angle a command reads and every angle it prints
 * is in degrees with --degrees and in radians without, and every printed
 * angle is accompanied by a "unit" field.  Also the two warnings about
 * angles that every command words the same way: an angle that looks like
 * degrees given as radians, and an approximate rotation asked to rotate
 * beyond its accurate range. */
#define _GNU_SOURCE /* vasprintf */
#include "cli.h"

#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <string.h>
#include <stdlib.h>

/* Warnings are kept until the command has finished: printed when it
 * succeeds or a check fails, dropped when it fails with a usage error, whose
 * one line must then be alone on stderr. */
#define WARN_MAX 8
static char *warnings[WARN_MAX];
static int nwarn;

void cli_warn(const char *fmt, ...)
{
    if (nwarn == WARN_MAX) return;
    va_list ap;
    va_start(ap, fmt);
    char *msg = NULL;
    if (vasprintf(&msg, fmt, ap) >= 0) {
        /* the same warning once, however often the input is read */
        for (int i = 0; i < nwarn && msg; i++)
            if (!strcmp(warnings[i], msg)) {
                free(msg);
                msg = NULL;
            }
        if (msg) warnings[nwarn++] = msg;
    }
    va_end(ap);
}

void cli_warn_flush(int rc)
{
    for (int i = 0; i < nwarn; i++) {
        if (rc != CLI_EXIT_USAGE) fprintf(stderr, "shlab: warning: %s\n", warnings[i]);
        free(warnings[i]);
    }
    nwarn = 0;
}

const char *cli_angle_unit(int degrees) { return degrees ? "degrees" : "radians"; }

/* Degrees are rounded to 15 significant digits: the conversion is good to
 * about one ulp, and 3.5° should print as 3.5, not 3.4999999999999996. */
double cli_angle_out(double radians, int degrees)
{
    if (!degrees || !isfinite(radians)) return radians;
    char buf[32];
    snprintf(buf, sizeof buf, "%.15g", radians * (180.0 / M_PI));
    return strtod(buf, NULL);
}

void cli_warn_radians(const char *cmd, const char *what, double value, int degrees)
{
    if (!degrees && fabs(value) > 2 * M_PI)
        cli_warn("%s: %s %g is more than 2π radians; degrees given without --degrees?", cmd, what, value);
}

double cli_angle_in(const char *cmd, const char *what, double value, int degrees)
{
    cli_warn_radians(cmd, what, value, degrees);
    return degrees ? value * (M_PI / 180.0) : value;
}

/* The lobe error (docs/CONVENTIONS.md "Taylor-approximated rotation") is
 * that of the unit cos⁷ lobe; it stops changing from order 9 on (the lobe
 * has almost no energy above band 8), so it is evaluated at order ≤ 32. */
#define APPROX_TOL 1e-2 /* the "1e-2" in the warning */
#define APPROX_MAX_ORDER 32

void cli_warn_approx_rotation(const char *cmd, sh_rot_method m, int order, const sh_rotation *rot,
                              int degrees)
{
    if (sh_rot_method_is_exact(m) || order < 2) return;
    const int n = order < APPROX_MAX_ORDER ? order : APPROX_MAX_ORDER;
    const double beta = rot->beta;
    double lim, err;
    /* first crossing of the tolerance by a 0.25° scan, then bisection */
    if (sh_taylor_lobe_limit(n, m, 7, APPROX_TOL, beta, 0.25 * M_PI / 180, &lim) != SH_OK) return;
    if (!(lim < beta)) return;
    if (sh_taylor_lobe_error(n, m, beta, 7, &err) != SH_OK) return;
    const char *u = degrees ? "°" : " rad";
    cli_warn("%s: %s at β = %.4g%s is beyond %.3g%s, where its lobe error reaches 1e-2; estimated lobe "
             "error here %.2g (unit cos⁷ lobe, order %d; see 'shlab taylor-error')",
             cmd, sh_rot_method_name(m), cli_angle_out(beta, degrees), u, cli_angle_out(lim, degrees), u, err, n);
}

int cli_light_has_angles(const sh_light *L)
{
    return L->kind == SH_LIGHT_CAP || L->kind == SH_LIGHT_CIE_CLEAR || L->kind == SH_LIGHT_CIE_PARTLY;
}

void cli_light_warn(const char *cmd, const sh_light *L, int degrees)
{
    /* the cap and the sun's zenith angle are refused beyond π (π/2); only the
     * sun's azimuth can exceed 2π (p[] is already in radians) */
    if (L->kind == SH_LIGHT_CIE_CLEAR || L->kind == SH_LIGHT_CIE_PARTLY)
        cli_warn_radians(cmd, "--light sun azimuth", L->p[1], degrees);
}
