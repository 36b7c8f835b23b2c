/* exp.c — see exp.h. */
#define _GNU_SOURCE
#include "exp.h"

#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

static const char *outdir = ".";
static char partdir[4096] = ".";
static char command[2048];
static const char *revision = "unknown";

void exp_init(int argc, char **argv)
{
    /* --help answers without running (and without touching OUTDIR); any
     * other option, a missing or an extra argument is a usage error */
    const char *name = strrchr(argv[0], '/') ? strrchr(argv[0], '/') + 1 : argv[0];
    for (int i = 1; i < argc; i++)
        if (!strcmp(argv[i], "--help") || !strcmp(argv[i], "-h")) {
            printf("Usage: %s OUTDIR\n\n"
                   "Run the experiment %s (experiments/%s/%s.c: the comment at its top says\n"
                   "what it measures) and write its data files and its fragments of the report\n"
                   "(index.md, claims.tsv; timings under OUTDIR/timing/) into OUTDIR.  The plots\n"
                   "come from experiments/%s/*.gp.  `make report` runs every experiment into\n"
                   "reports/NAME and assembles the report.  Environment: REV (the revision\n"
                   "stamped into the files), SHLAB (the shlab binary, for experiments that call\n"
                   "it), PROBES_DIR (default data/probes).\n",
                   name, name, name, name, name);
            exit(fflush(stdout) == 0 && !ferror(stdout) ? 0 : 2);
        }
    if (argc != 2 || argv[1][0] == '-' || !argv[1][0]) {
        fprintf(stderr, "%s: error: usage: %s OUTDIR (or --help)\n", name, name);
        exit(2);
    }
    outdir = argv[1];
    mkdir(outdir, 0777);
    snprintf(partdir, sizeof partdir, "%s", outdir);
    const char *r = getenv("REV");
    if (r && *r) revision = r;
    size_t n = 0;
    for (int i = 0; i < argc && n < sizeof command - 1; i++) {
        const char *a = i == 0 ? (strrchr(argv[0], '/') ? strrchr(argv[0], '/') + 1 : argv[0]) : argv[i];
        n += snprintf(command + n, sizeof command - n, "%s%s", i ? " " : "", a);
    }
    /* fresh fragments for this run */
    char p[4096];
    snprintf(p, sizeof p, "%s/index.md", outdir);
    remove(p);
    snprintf(p, sizeof p, "%s/claims.tsv", outdir);
    remove(p);
}

const char *exp_outdir(void) { return partdir; }

const char *exp_revision(void) { return revision; }

void exp_part(const char *part)
{
    static char done[16][64];
    static int ndone;
    if (!part) {
        snprintf(partdir, sizeof partdir, "%s", outdir);
        return;
    }
    snprintf(partdir, sizeof partdir, "%s/%s", outdir, part);
    mkdir(partdir, 0777);
    for (int i = 0; i < ndone; i++)
        if (!strcmp(done[i], part)) return;
    if (ndone < 16) snprintf(done[ndone++], sizeof done[0], "%s", part);
    char p[4200];
    snprintf(p, sizeof p, "%s/index.md", partdir);
    remove(p);
    snprintf(p, sizeof p, "%s/claims.tsv", partdir);
    remove(p);
}

FILE *exp_data(const char *name, const char *title, const char *columns)
{
    char p[4200];
    snprintf(p, sizeof p, "%s/%s", partdir, name);
    FILE *f = fopen(p, "w");
    if (!f) {
        fprintf(stderr, "experiment: cannot write %s: %s\n", p, strerror(errno));
        exit(1);
    }
    fprintf(f, "# %s\n# shlab revision: %s\n# command: %s\n# columns: %s\n", title, revision, command,
            columns);
    return f;
}

static void append(const char *file, const char *text)
{
    char p[4200];
    snprintf(p, sizeof p, "%s/%s", partdir, file);
    FILE *f = fopen(p, "a");
    if (!f) {
        fprintf(stderr, "experiment: cannot write %s\n", p);
        exit(1);
    }
    fputs(text, f);
    fclose(f);
}

void exp_index(const char *fmt, ...)
{
    char *s = NULL;
    va_list ap;
    va_start(ap, fmt);
    if (vasprintf(&s, fmt, ap) < 0) s = NULL;
    va_end(ap);
    if (!s) exit(1);
    append("index.md", s);
    append("index.md", "\n\n");
    free(s);
}

static void clean(char *dst, size_t n, const char *s)
{
    size_t k = 0;
    for (; s && *s && k + 1 < n; s++) dst[k++] = (*s == '\t' || *s == '\n') ? ' ' : *s;
    dst[k] = '\0';
}

void exp_claim(const char *id, const char *source, const char *statement, const char *printed,
               const char *measured, const char *tolerance, const char *verdict,
               const char *evidence)
{
    const char *f[8] = {id, source, statement, printed, measured, tolerance, verdict, evidence};
    char line[8192] = "", cell[2048];
    for (int i = 0; i < 8; i++) {
        clean(cell, sizeof cell, f[i]);
        strncat(line, cell, sizeof line - strlen(line) - 2);
        strncat(line, i < 7 ? "\t" : "\n", sizeof line - strlen(line) - 1);
    }
    append("claims.tsv", line);
}

exp_side exp_ratio_side(const sh_bench_ratio *r, double lo, double hi)
{
    const double a = fmin(r->q1, r->median * (1 - EXP_RUN_TO_RUN));
    const double b = fmax(r->q3, r->median * (1 + EXP_RUN_TO_RUN));
    if (a >= lo && b <= hi) return EXP_INSIDE;
    if (b < lo || a > hi) return EXP_OUTSIDE;
    return EXP_STRADDLES;
}

void exp_progress(const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    fputs("  ", stderr);
    vfprintf(stderr, fmt, ap);
    fputc('\n', stderr);
    va_end(ap);
}

void exp_check(int st, const char *what)
{
    if (st != SH_OK) {
        fprintf(stderr, "experiment: %s failed: %s\n", what, sh_last_error());
        exit(1);
    }
}

int exp_scene_envs(const char *dflt, const char *fallback, sh_env **envs, char names[][64], int max, int *have_probes)
{
    const char *pdir = getenv("PROBES_DIR") ? getenv("PROBES_DIR") : "data/probes";
    const char *list = getenv("SCENE_PROBES") ? getenv("SCENE_PROBES") : dflt;
    int n = 0;
    char buf[1024], path[4096];
    snprintf(buf, sizeof buf, "%s", list ? list : "");
    for (char *tok = strtok(buf, ", "); tok && n < max; tok = strtok(NULL, ", ")) {
        snprintf(path, sizeof path, "%s/%s.exr", pdir, tok);
        FILE *f = fopen(path, "rb");
        if (!f) continue;
        fclose(f);
        sh_image img;
        exp_check(sh_exr_read(path, &img, NULL), path);
        exp_check(sh_env_from_image(&img, &envs[n]), path);
        sh_image_free(&img);
        snprintf(names[n], 64, "%s", tok);
        n++;
    }
    *have_probes = n > 0;
    if (n || !fallback) return n;
    fprintf(stderr, "no probes (%s) in %s (run `make probes`): analytic lights instead\n", list ? list : "", pdir);
    return exp_scene_lights(fallback, envs, names, max);
}

int exp_scene_lights(const char *specs, sh_env **envs, char names[][64], int max)
{
    char buf[1024];
    int n = 0;
    snprintf(buf, sizeof buf, "%s", specs);
    for (char *tok = strtok(buf, ";"); tok && n < max; tok = strtok(NULL, ";")) {
        sh_light L;
        exp_check(sh_light_parse(tok, 0, &L), tok);
        exp_check(sh_env_from_light(&L, &envs[n]), tok);
        snprintf(names[n], 64, "%s", tok);
        n++;
    }
    return n;
}

int exp_scene_full(void)
{
    const char *v = getenv("SCENES");
    return v && !strcmp(v, "full");
}

void exp_kept(const char *part, const char *why)
{
    const char *name = strrchr(outdir, '/') ? strrchr(outdir, '/') + 1 : outdir;
    char p[4200];
    snprintf(p, sizeof p, "%s/%s/index.md", outdir, part);
    FILE *f = fopen(p, "r");
    char rev[64] = "";
    if (f) {
        /* the revision the kept part names: its first "code revision `X`" */
        char line[8192];
        while (!rev[0] && fgets(line, sizeof line, f)) {
            const char *q = strstr(line, "code revision `");
            if (q) sscanf(q + 15, "%63[^`]", rev);
        }
        fclose(f);
    }
    if (f)
        fprintf(stderr, "%s: %s/ kept as committed (computed at code revision %s): %s\n", name, part, rev[0] ? rev : "unknown", why);
    else
        fprintf(stderr, "%s: %s/ not computed (%s)\n", name, part, why);
}
