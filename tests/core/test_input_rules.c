/* test_input_rules.c — the library's rules for bad input: reasons are one
 * printable line whatever they quote, numbers that overflow or underflow
 * are refused, and the EXR reader's limits are applied before decoding. */
#include "testutil.h"

#include <string.h>
#include <unistd.h>

/* every byte of the reason printable (no C0 control, no DEL) */
static int printable(const char *s)
{
    for (; *s; s++)
        if ((unsigned char)*s < 0x20 || *s == 0x7f) return 0;
    return 1;
}

START_TEST(reasons_are_one_line)
{
    sh_error(SH_EINVAL, "value '%s'", "a\nb\tc\rd\x1b[31m");
    ck_assert_str_eq(sh_last_error(), "value 'a\\nb\\tc\\rd\\x1b[31m'");
    /* valid UTF-8 stays; invalid bytes, overlong forms, surrogates and C1
     * controls become \xNN */
    sh_error(SH_EINVAL, "%s", "θ=π ×2");
    ck_assert_str_eq(sh_last_error(), "θ=π ×2");
    sh_error(SH_EINVAL, "%s", "\xff\xfe|\xc0\xaf|\xed\xa0\x80|\xc2\x85|\xe2\x82");
    ck_assert_str_eq(sh_last_error(),
                     "\\xff\\xfe|\\xc0\\xaf|\\xed\\xa0\\x80|\\xc2\\x85|\\xe2\\x82");
    /* a reason longer than the buffer is cut with "..." */
    char big[3000];
    memset(big, '\n', sizeof big - 1);
    big[sizeof big - 1] = '\0';
    sh_error(SH_EINVAL, "%s", big);
    const char *r = sh_last_error();
    ck_assert(printable(r));
    ck_assert(strlen(r) < 1024);
    ck_assert_str_eq(r + strlen(r) - 3, "...");
}
END_TEST

START_TEST(numbers_out_of_range)
{
    sh_light L;
    ck_assert_int_eq(sh_light_parse("cap:1e-400", 0, &L), SH_EINVAL);
    ck_assert(printable(sh_last_error()));
    ck_assert_int_eq(sh_light_parse("const:1e400", 0, &L), SH_EINVAL);
    ck_assert_int_eq(sh_light_parse("lobe:1e-310", 0, &L), SH_EINVAL); /* subnormal */
    ck_assert_int_eq(sh_light_parse("cap:0e-400", 0, &L), SH_OK);      /* an exact zero */
    ck_assert(L.p[0] == 0.0);
    ck_assert_int_eq(sh_light_parse("cap:0.5", 0, &L), SH_OK);
    ck_assert(L.p[0] == 0.5);
    sh_window w;
    ck_assert_int_eq(sh_window_parse("gauss:1e-400", &w), SH_EINVAL);
    ck_assert_int_eq(sh_window_parse("hann:1e999", &w), SH_EINVAL);
    ck_assert_int_eq(sh_window_parse("gauss:0.25", &w), SH_OK);
    ck_assert(w.param == 0.25);
}
END_TEST

/* the bytes of a small float RGB EXR written by sh_exr_write */
static unsigned char *small_exr(int w, int h, size_t *n)
{
    char path[] = "/tmp/shlab_rules_XXXXXX";
    int fd = mkstemp(path);
    ck_assert_int_ge(fd, 0);
    close(fd);
    sh_image img = {w, h, 3, {"R", "G", "B"}, malloc(sizeof(float) * w * h * 3)};
    for (int i = 0; i < w * h * 3; i++) img.data[i] = (float)(i % 17) * 0.25f;
    ck_assert_int_eq(sh_exr_write(path, &img), SH_OK);
    sh_image_free(&img);
    FILE *f = fopen(path, "rb");
    fseek(f, 0, SEEK_END);
    *n = (size_t)ftell(f);
    fseek(f, 0, SEEK_SET);
    unsigned char *b = malloc(*n);
    ck_assert_uint_eq(fread(b, 1, *n, f), *n);
    fclose(f);
    unlink(path);
    return b;
}

START_TEST(exr_limits_before_decoding)
{
    size_t n;
    unsigned char *b = small_exr(64, 32, &n);
    sh_exr_limits lim;
    sh_exr_limits_default(&lim);
    ck_assert(lim.max_pixels == SH_IMAGE_MAX_PIXELS && lim.max_bytes > 0 && lim.max_channels == 1024);
    sh_image img;
    ck_assert_int_eq(sh_exr_read_mem(b, n, "good.exr", &lim, &img, NULL), SH_OK);
    ck_assert_int_eq(img.width, 64);
    sh_image_free(&img);
    /* too many pixels: refused, naming the window and the limit */
    lim.max_pixels = 64 * 32 - 1;
    ck_assert_int_eq(sh_exr_read_mem(b, n, "good.exr", &lim, &img, NULL), SH_EFORMAT);
    ck_assert_ptr_null(img.data);
    ck_assert(strstr(sh_last_error(), "64×32") && strstr(sh_last_error(), "2047"));
    /* too little memory: SH_ENOMEM with the size needed */
    sh_exr_limits_default(&lim);
    lim.max_bytes = 10000;
    ck_assert_int_eq(sh_exr_read_mem(b, n, "good.exr", &lim, &img, NULL), SH_ENOMEM);
    ck_assert(strstr(sh_last_error(), "needs") && strstr(sh_last_error(), "kB"));
    /* a ratio limit below this file's compression */
    sh_exr_limits_default(&lim);
    lim.max_ratio = 1.0;
    ck_assert_int_eq(sh_exr_read_mem(b, n, "good.exr", &lim, &img, NULL), SH_EFORMAT);
    ck_assert(strstr(sh_last_error(), "compression"));
    /* bad limits and arguments */
    lim.max_ratio = 0.5;
    ck_assert_int_eq(sh_exr_read_mem(b, n, "good.exr", &lim, &img, NULL), SH_EINVAL);
    ck_assert_int_eq(sh_exr_read_mem(NULL, 5, "x", NULL, &img, NULL), SH_EINVAL);
    ck_assert_int_eq(sh_exr_read_mem(b, 7, "short.exr", NULL, &img, NULL), SH_EFORMAT);
    /* every prefix of the file is refused cleanly */
    for (size_t k = 0; k < n; k += 7) {
        const int st = sh_exr_read_mem(b, k, "cut.exr", NULL, &img, NULL);
        ck_assert_int_eq(st, SH_EFORMAT);
        ck_assert_ptr_null(img.data);
        ck_assert(printable(sh_last_error()));
    }
    free(b);
}
END_TEST

static Suite *rules_suite(void)
{
    Suite *s = suite_create("input_rules");
    TCase *tc = tcase_create("rules");
    tcase_add_test(tc, reasons_are_one_line);
    tcase_add_test(tc, numbers_out_of_range);
    tcase_add_test(tc, exr_limits_before_decoding);
    suite_add_tcase(s, tc);
    return s;
}

SHLAB_TEST_MAIN(rules_suite)
