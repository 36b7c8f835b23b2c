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
static const char *requested; /* --part NAME */
static void exp_shard_setup(int argc, char **argv, int first);

void exp_init(int argc, char **argv)
{
    /* --help answers without running (and without touching OUTDIR); any
     * other option, a missing or an extra argument is a usage error */
    const char *name = strrchr(argv[0], '/') ? strrchr(argv[0], '/') + 1 : argv[0];
    for (int i = 1; i < argc; i++)
        if (!strcmp(argv[i], "--help") || !strcmp(argv[i], "-h")) {
            printf("Usage: %s OUTDIR [--part NAME] [--shard I/N | --merge FILE...]\n\n"
                   "Run the experiment %s (experiments/%s/%s.c: the comment at its top says\n"
                   "what it measures) and write its data files and its fragments of the report\n"
                   "(index.md, claims.tsv; timings under OUTDIR/timing/) into OUTDIR.  The plots\n"
                   "come from experiments/%s/*.gp.  `make report` runs every experiment into\n"
                   "reports/NAME and assembles the report.  Environment: REV (the revision\n"
                   "stamped into the files), SHLAB (the shlab binary, for experiments that call\n"
                   "it), PROBES_DIR (default data/probes).\n"
                   "  --part NAME    run only the part NAME that the experiment computes on\n"
                   "                 request (into OUTDIR/NAME; OUTDIR's own files untouched)\n"
                   "  --shard I/N    compute only shard I's items, into OUTDIR/shard-I-of-N.items\n"
                   "  --merge FILE.. the N shard files: write what the unsharded run writes\n",
                   name, name, name, name, name);
            exit(fflush(stdout) == 0 && !ferror(stdout) ? 0 : 2);
        }
    /* OUTDIR [--part NAME] [--shard I/N | --merge FILE...] */
    int first = 2;
    if (argc >= 4 && !strcmp(argv[2], "--part")) {
        requested = argv[3];
        first = 4;
    }
    if (argc < 2 || argv[1][0] == '-' || !argv[1][0] || (requested && (!*requested || strchr(requested, '/'))) ||
        (argc > first && strcmp(argv[first], "--shard") && strcmp(argv[first], "--merge"))) {
        fprintf(stderr, "%s: error: usage: %s OUTDIR [--part NAME] [--shard I/N | --merge FILE...] (or --help)\n",
                name, name);
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
    /* fresh fragments for this run (a requested part leaves OUTDIR's own) */
    char p[4096];
    snprintf(p, sizeof p, "%s/index.md", outdir);
    if (!requested) remove(p);
    snprintf(p, sizeof p, "%s/claims.tsv", outdir);
    if (!requested) remove(p);
    exp_shard_setup(argc - (first - 2), argv, first); /* --shard I/N, --merge FILE... */
}

const char *exp_requested_part(void) { return requested; }

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

/* characters (not bytes) of a UTF-8 string */
static size_t utf8_chars(const char *s)
{
    size_t n = 0;
    for (; *s; s++) n += ((unsigned char)*s & 0xC0) != 0x80;
    return n;
}

void exp_claim(const char *id, const char *source, const char *statement, const char *printed,
               const char *measured, const char *tolerance, const char *verdict,
               const char *evidence)
{
    static const char *const cols[8] = {"claim_id", "source", "statement", "printed", "measured",
                                        "tolerance", "verdict", "evidence"};
    static const char *const verdicts[] = {"reproduced", "differs", "not-applicable", "inconclusive", "not-measured"};
    const char *f[8] = {id, source, statement, printed, measured, tolerance, verdict, evidence};
    /* the ledger's form (exp.h; tests/cli/test_ledger.sh checks the assembled
     * ledgers): a row that breaks it stops the experiment here, at its source */
    int known = 0;
    for (size_t i = 0; i < sizeof verdicts / sizeof *verdicts; i++) known |= verdict && !strcmp(verdict, verdicts[i]);
    const char *bad = !known ? "verdict not in the vocabulary of exp.h" : NULL;
    for (int i = 0; i < 8 && !bad; i++)
        if (!f[i] || !*f[i]) bad = "an empty cell (write \"-\")";
        else if (utf8_chars(f[i]) > EXP_CELL_MAX) bad = "a cell longer than EXP_CELL_MAX characters";
    if (!bad && strcmp(verdict, "reproduced") && !strstr(evidence, "why: ")) bad = "no \"why: \" in the evidence";
    if (bad) {
        fprintf(stderr, "experiment: claim %s: %s\n", id ? id : "(null)", bad);
        for (int i = 0; i < 8; i++)
            fprintf(stderr, "  %s (%zu characters): %s\n", cols[i], f[i] ? utf8_chars(f[i]) : 0, f[i] ? f[i] : "(null)");
        exit(1);
    }
    char line[8192] = "", cell[2048];
    for (int i = 0; i < 8; i++) {
        clean(cell, sizeof cell, f[i]);
        strncat(line, cell, sizeof line - strlen(line) - 2);
        strncat(line, i < 7 ? "\t" : "\n", sizeof line - strlen(line) - 1);
    }
    append("claims.tsv", line);
}

const char *exp_evidence(char *buf, size_t n, const char *files, const char *verdict, const char *why)
{
    if (!strcmp(verdict, "reproduced")) why = NULL;
    else if (!strcmp(verdict, "not-measured"))
        why = "the run was noisy (the noise criterion of the bench engine), so it gives no verdict.";
    else if (!strcmp(verdict, "inconclusive"))
        why = "the ratio's quartiles, widened by the run-to-run spread, straddle a bound of the tolerance.";
    snprintf(buf, n, "%s%s%s", files, why ? "; why: " : "", why ? why : "");
    return buf;
}

void exp_claim_judged(const char *id, const char *source, const char *statement, const char *printed,
                      const char *measured, const char *tolerance, int ok, const char *files, const char *why)
{
    char ev[1024];
    const char *v = ok ? "reproduced" : "differs";
    exp_claim(id, source, statement, printed, measured, tolerance, v, exp_evidence(ev, sizeof ev, files, v, why));
}

exp_side exp_ratio_side(const sh_bench_ratio *r, double lo, double hi)
{
    const double a = fmin(r->q1, r->median * (1 - EXP_RUN_TO_RUN));
    const double b = fmax(r->q3, r->median * (1 + EXP_RUN_TO_RUN));
    if (a >= lo && b <= hi) return EXP_INSIDE;
    if (b < lo || a > hi) return EXP_OUTSIDE;
    return EXP_STRADDLES;
}

const char *exp_sides_verdict(const exp_side *s, int n)
{
    int out = 0, str = 0;
    for (int k = 0; k < n; k++) out |= s[k] == EXP_OUTSIDE, str |= s[k] == EXP_STRADDLES;
    return out ? "differs" : str ? "inconclusive" : "reproduced";
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

/* ---- shards (exp.h) ------------------------------------------------------- */

static enum { RUN_WHOLE, RUN_SHARD, RUN_MERGE } run_mode = RUN_WHOLE;
static sh_shard shard = SH_SHARD_ALL;
static FILE *shard_out;
static char shard_path[4200];
static long shard_rows;
typedef struct {
    long item;
    int n;
    double *v;
} shard_rec;
static shard_rec *recs;
static size_t nrecs;
static const char *program = "";

static void shard_fail(const char *fmt, ...) __attribute__((format(printf, 1, 2), noreturn));
static void shard_fail(const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    fputs("experiment: ", stderr);
    vfprintf(stderr, fmt, ap);
    fputc('\n', stderr);
    va_end(ap);
    exit(2);
}

/* --shard: the file is complete (end line, renamed into place) only when
 * the experiment exits with status 0 */
static void shard_finish(int status, void *arg)
{
    (void)arg;
    if (!shard_out) return;
    char tmp[4300];
    snprintf(tmp, sizeof tmp, "%s.tmp", shard_path);
    if (status == 0) fprintf(shard_out, "# end rows %ld\n", shard_rows);
    if (fclose(shard_out) != 0 || status != 0 || rename(tmp, shard_path) != 0) remove(tmp);
    shard_out = NULL;
}

static int rec_cmp(const void *a, const void *b)
{
    const shard_rec *x = a, *y = b;
    return (x->item > y->item) - (x->item < y->item);
}

/* --merge: read every file; they must be the N shards of this run */
static void shard_load(char **files, int nf)
{
    int N = 0, *seen = NULL;
    char want[3000];
    snprintf(want, sizeof want, "# shlab experiment shard: revision %s: %s", revision, program);
    for (int q = 0; q < nf; q++) {
        FILE *f = fopen(files[q], "r");
        if (!f) shard_fail("--merge: cannot open %s: %s", files[q], strerror(errno));
        char *line = NULL;
        size_t cap = 0;
        ssize_t len;
        long lineno = 0, rows = 0, ended = -1;
        int I = -1, n = -1;
        while ((len = getline(&line, &cap, f)) >= 0) {
            lineno++;
            if (len > 0 && line[len - 1] == '\n') line[--len] = '\0';
            if (lineno == 1) {
                /* "# shard I of N" then the run's identity */
                int off = 0;
                if (sscanf(line, "# shard %d of %d%n", &I, &n, &off) != 2 || I < 0 || I >= n || n > SH_SHARD_MAX)
                    shard_fail("--merge: %s is not a shard file of an experiment", files[q]);
                if (strcmp(line + off, want + 1))
                    shard_fail("--merge: %s is a shard of another run (%.200s)", files[q], line + off);
                if (!N) {
                    N = n;
                    if (!(seen = calloc((size_t)N, sizeof *seen))) shard_fail("out of memory");
                } else if (n != N) {
                    shard_fail("--merge: %s is one of %d shards, the others of %d", files[q], n, N);
                }
                if (seen[I]++) shard_fail("--merge: shard %d of %d given twice (%s)", I, N, files[q]);
                continue;
            }
            if (ended >= 0) shard_fail("--merge: %s: text after the end line", files[q]);
            if (sscanf(line, "# end rows %ld", &ended) == 1) {
                if (ended != rows) shard_fail("--merge: %s: %ld rows, the end line says %ld", files[q], rows, ended);
                continue;
            }
            shard_rec r;
            char *p = line, *e;
            r.item = strtol(p, &e, 10);
            r.n = (int)strtol(e, &p, 10);
            const sh_shard s = {I, N};
            if (e == line || p == e || r.n < 0 || r.n > 1000 || !sh_shard_owns(&s, r.item))
                shard_fail("--merge: %s line %ld: not an item of shard %d of %d", files[q], lineno, I, N);
            if (!(r.v = malloc(sizeof *r.v * (size_t)(r.n ? r.n : 1)))) shard_fail("out of memory");
            for (int k = 0; k < r.n; k++) {
                r.v[k] = strtod(p, &e); /* hexadecimal: exact */
                if (e == p) shard_fail("--merge: %s line %ld: value %d missing", files[q], lineno, k + 1);
                p = e;
            }
            shard_rec *nr = realloc(recs, sizeof *recs * (nrecs + 1));
            if (!nr) shard_fail("out of memory");
            recs = nr;
            recs[nrecs++] = r;
            rows++;
        }
        free(line);
        fclose(f);
        if (lineno == 0) shard_fail("--merge: %s is empty", files[q]);
        if (ended < 0) shard_fail("--merge: %s has no end line (the shard did not finish)", files[q]);
    }
    for (int i = 0; i < N; i++)
        if (!seen[i]) shard_fail("--merge: shard %d of %d is missing", i, N);
    free(seen);
    qsort(recs, nrecs, sizeof *recs, rec_cmp);
    for (size_t i = 1; i < nrecs; i++)
        if (recs[i].item == recs[i - 1].item) shard_fail("--merge: item %ld given twice", recs[i].item);
}

/* argc counts the arguments from argv[first - 2] on (OUTDIR, --part NAME skipped) */
static void exp_shard_setup(int argc, char **argv, int first)
{
    if (argc < 3) return;
    /* the run's identity: the experiment and its part (its OUTDIR may
     * differ per shard) */
    static char ident[256];
    const char *prog = strrchr(argv[0], '/') ? strrchr(argv[0], '/') + 1 : argv[0];
    snprintf(ident, sizeof ident, "%s%s%s", prog, requested ? " --part " : "", requested ? requested : "");
    program = ident;
    argv += first - 2;
    /* the options are not part of the run's identity: drop them from the
     * command every data header prints */
    char *cut = strstr(command, !strcmp(argv[2], "--shard") ? " --shard" : " --merge");
    if (cut) *cut = '\0';
    if (!strcmp(argv[2], "--shard") && argc == 4) {
        if (sh_shard_parse(argv[3], &shard)) shard_fail("--shard: %s", sh_last_error());
        run_mode = RUN_SHARD;
        snprintf(shard_path, sizeof shard_path, "%s/shard-%d-of-%d.items", outdir, shard.index, shard.count);
        char tmp[4300];
        snprintf(tmp, sizeof tmp, "%s.tmp", shard_path);
        if (!(shard_out = fopen(tmp, "w"))) shard_fail("cannot write %s: %s", tmp, strerror(errno));
        fprintf(shard_out, "# shard %d of %d shlab experiment shard: revision %s: %s\n", shard.index, shard.count,
                revision, program);
        on_exit(shard_finish, NULL);
    } else if (!strcmp(argv[2], "--merge") && argc >= 4) {
        run_mode = RUN_MERGE;
        shard_load(argv + 3, argc - 3);
    } else {
        shard_fail("usage: %s OUTDIR [--part NAME] [--shard I/N | --merge FILE...]", prog);
    }
}

int exp_computes(long item)
{
    return run_mode == RUN_WHOLE || (run_mode == RUN_SHARD && sh_shard_owns(&shard, item));
}

int exp_item(long item, int n, double *v)
{
    if (run_mode == RUN_WHOLE) return 1;
    if (run_mode == RUN_SHARD) {
        if (!sh_shard_owns(&shard, item)) return 0;
        fprintf(shard_out, "%ld %d", item, n);
        for (int k = 0; k < n; k++) fprintf(shard_out, " %a", v[k]);
        fputc('\n', shard_out);
        shard_rows++;
        return 1;
    }
    const shard_rec key = {item, 0, NULL};
    const shard_rec *r = bsearch(&key, recs, nrecs, sizeof *recs, rec_cmp);
    if (!r) shard_fail("--merge: item %ld is in none of the shard files", item);
    if (r->n != n) shard_fail("--merge: item %ld has %d values, the experiment wants %d", item, r->n, n);
    memcpy(v, r->v, sizeof *v * (size_t)n);
    return 1;
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
