/* test_exr_damage.c — damaged EXR files never crash the reader.
 *
 * In the style of OpenEXR's own fuzzFile test: good files (every
 * compression, scanline and tiled, half RGBA and float RGB, written by
 * OpenEXR's C++ library, tests/exr_writer.cpp) are damaged with seeded
 * random bytes — up to 10% of the bytes of a window that slides over the
 * whole file, then of the first 2048 bytes (the header and offset table) —
 * and read back from memory after each damage.  Every read must return a
 * status: SH_OK with a complete image, or an error with no image and a
 * one-line reason.  Under `make check SANITIZE=1` this also means no
 * sanitizer report. */
#include "testutil.h"
#include "exr_writer.h"

#include <ImfCRgbaFile.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

static char path[64];

static void setup(void)
{
    strcpy(path, "/tmp/shlab_test_damage.XXXXXX");
    int fd = mkstemp(path);
    ck_assert_int_ge(fd, 0);
    close(fd);
}

static void teardown(void) { unlink(path); }

/* a small seeded generator (64-bit LCG, Knuth's MMIX constants) */
static uint64_t rng_state;
static uint32_t rnd(void)
{
    rng_state = rng_state * 6364136223846793005ULL + 1442695040888963407ULL;
    return (uint32_t)(rng_state >> 33);
}

static unsigned char *load(const char *p, size_t *n)
{
    FILE *f = fopen(p, "rb");
    ck_assert_ptr_nonnull(f);
    fseek(f, 0, SEEK_END);
    long len = ftell(f);
    fseek(f, 0, SEEK_SET);
    unsigned char *b = malloc((size_t)len);
    ck_assert_uint_eq(fread(b, 1, (size_t)len, f), (size_t)len);
    fclose(f);
    *n = (size_t)len;
    return b;
}

/* Damage up to 10% of the bytes in [start, start+len) and read. */
static void damage_and_read(const unsigned char *good, size_t n, size_t start, size_t len,
                            unsigned char *work, const sh_exr_limits *lim, int *ok, int *bad)
{
    memcpy(work, good, n);
    if (start + len > n) len = n - start;
    const size_t k = len / 10 + 1;
    for (size_t j = 0; j < k && len; j++) work[start + rnd() % len] = (unsigned char)rnd();
    sh_image img;
    const int st = sh_exr_read_mem(work, n, "damaged", lim, &img, NULL);
    if (st == SH_OK) {
        ck_assert_ptr_nonnull(img.data);
        ck_assert(img.nchan == 1 || img.nchan == 3);
        ck_assert(img.width >= 1 && img.height >= 1);
        (*ok)++;
    } else {
        ck_assert_ptr_null(img.data);
        ck_assert(st == SH_EFORMAT || st == SH_ENOMEM || st == SH_ENOTSUP);
        const char *why = sh_last_error();
        ck_assert_msg(why[0] && !strchr(why, '\n') && !strchr(why, '\r'), "reason: %s", why);
        (*bad)++;
    }
    sh_image_free(&img);
}

START_TEST(damaged_files)
{
    const int w = 45, h = 35;
    int ok = 0, bad = 0, files = 0;
    sh_exr_limits lim;
    sh_exr_limits_default(&lim);
    lim.max_bytes = 256LL << 20; /* a damaged header may ask for more: refused, not attempted */
    rng_state = 20240601;
    for (int comp = 0; comp < 10; comp++)
        for (int tiled = 0; tiled < 2; tiled++)
            for (int kind = 0; kind < 2; kind++) {
                /* kind 0: half RGBA; kind 1: float RGB */
                tw_spec s;
                memset(&s, 0, sizeof s);
                s.width = w;
                s.height = h;
                s.compression = comp;
                s.storage = tiled ? TW_TILED : TW_SCANLINE;
                s.tile_w = 16;
                s.tile_h = 16;
                s.nchan = kind ? 3 : 4;
                static const char *const nm[] = {"R", "G", "B", "A"};
                void *planes[4];
                for (int c = 0; c < s.nchan; c++) {
                    s.names[c] = nm[c];
                    s.types[c] = kind ? TW_FLOAT : TW_HALF;
                    planes[c] = malloc((size_t)w * h * 4);
                    for (int i = 0; i < w * h; i++) {
                        const float v = (float)(0.5 + 0.4 * sin(0.1 * i + c));
                        if (kind) ((float *)planes[c])[i] = v;
                        else ImfFloatToHalf(v, &((ImfHalf *)planes[c])[i]);
                    }
                }
                ck_assert_msg(tw_write(path, &s, (const void *const *)planes) == 0, "%s", tw_error());
                for (int c = 0; c < s.nchan; c++) free(planes[c]);
                size_t n;
                unsigned char *good = load(path, &n), *work = malloc(n);
                /* the undamaged file reads */
                sh_image img;
                ck_assert_int_eq(sh_exr_read_mem(good, n, "good", &lim, &img, NULL), SH_OK);
                sh_image_free(&img);
                /* a window of n/20 bytes sliding by half its width (40
                 * steps), three passes */
                const size_t win = n / 20 + 1;
                for (int pass = 0; pass < 3; pass++)
                    for (size_t start = 0; start < n; start += win / 2 + 1)
                        damage_and_read(good, n, start, win, work, &lim, &ok, &bad);
                /* the first 2048 bytes, 200 times */
                for (int r = 0; r < 200; r++)
                    damage_and_read(good, n, 0, n < 2048 ? n : 2048, work, &lim, &ok, &bad);
                /* and every length it can be cut to, in 41 steps */
                for (int r = 0; r <= 40; r++) {
                    sh_image cut;
                    const int st = sh_exr_read_mem(good, n * (size_t)r / 41, "cut", &lim, &cut, NULL);
                    ck_assert(st == SH_EFORMAT || (st == SH_OK && cut.data));
                    if (st == SH_OK) ok++;
                    else bad++;
                    sh_image_free(&cut);
                }
                free(good);
                free(work);
                files++;
            }
    if (getenv("SHLAB_TEST_VERBOSE"))
        fprintf(stderr, "damage: %d files, %d damaged reads: %d read, %d refused\n", files, ok + bad,
                ok, bad);
    ck_assert_int_gt(bad, 0); /* the damage did reach the reader's checks */
}
END_TEST

static Suite *damage_suite(void)
{
    Suite *s = suite_create("exr_damage");
    TCase *tc = tcase_create("damage");
    tcase_add_checked_fixture(tc, setup, teardown);
    tcase_set_timeout(tc, 900);
    tcase_add_test(tc, damaged_files);
    suite_add_tcase(s, tc);
    return s;
}

SHLAB_TEST_MAIN(damage_suite)
