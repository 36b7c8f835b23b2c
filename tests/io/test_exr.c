/* test_exr.c — OpenEXR reading and writing.
 *
 * Files are made by our writers (sh_exr_write: OpenEXRCore float ZIP;
 * sh_exr_write_dwab_rgba: C++ library via ImfCRgbaFile) and by a small
 * independent OpenEXRCore writer below (tiled, HALF, UINT, arbitrary channel
 * names, any compression), so that reading is not only tested against our
 * own writer.  Values written as half/uint are chosen exactly representable,
 * so those round trips are exact.
 */
#include <stdio.h>

#include "testutil.h"

#include <ImfCRgbaFile.h>
#include <dirent.h>
#include <openexr.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

static char tmpdir[64];

static void setup(void)
{
    strcpy(tmpdir, "/tmp/shlab_test_exr.XXXXXX");
    ck_assert_ptr_nonnull(mkdtemp(tmpdir));
}

static void teardown(void)
{
    DIR *d = opendir(tmpdir);
    if (d) {
        struct dirent *e;
        char p[512];
        while ((e = readdir(d)))
            if (e->d_name[0] != '.') {
                snprintf(p, sizeof p, "%s/%s", tmpdir, e->d_name);
                unlink(p);
            }
        closedir(d);
    }
    rmdir(tmpdir);
}

static void path_in(char *buf, size_t n, const char *name) { snprintf(buf, n, "%s/%s", tmpdir, name); }

/* number of directory entries (other than . and ..) in tmpdir */
static int count_files(void)
{
    int n = 0;
    DIR *d = opendir(tmpdir);
    struct dirent *e;
    while ((e = readdir(d)))
        if (e->d_name[0] != '.') n++;
    closedir(d);
    return n;
}

static sh_image make_image(int w, int h, int nchan)
{
    sh_image img = {w, h, nchan, {{0}}, malloc(sizeof(float) * w * h * nchan)};
    static const char *rgb[] = {"R", "G", "B", "A"};
    for (int c = 0; c < nchan; c++) strcpy(img.names[c], nchan == 1 ? "Y" : rgb[c]);
    return img;
}

/* ---- an independent OpenEXRCore writer --------------------------------- */
/* planes[c] holds w*h elements of `ptype` (uint16 half bits, uint32 or float) */
static int core_write(const char *path, int tiled, exr_compression_t comp, exr_pixel_type_t ptype,
                      int nchan, const char *const *names, const void *const *planes, int w, int h)
{
    const int bpe = ptype == EXR_PIXEL_HALF ? 2 : 4;
    exr_context_t ctxt;
    exr_context_initializer_t init = EXR_DEFAULT_CONTEXT_INITIALIZER;
    int part;
    exr_result_t rv = exr_start_write(&ctxt, path, EXR_WRITE_FILE_DIRECTLY, &init);
    if (rv) return rv;
    rv = exr_add_part(ctxt, "p", tiled ? EXR_STORAGE_TILED : EXR_STORAGE_SCANLINE, &part);
    if (!rv) rv = exr_initialize_required_attr_simple(ctxt, part, w, h, comp);
    if (!rv && tiled) rv = exr_set_tile_descriptor(ctxt, part, 16, 16, EXR_TILE_ONE_LEVEL, EXR_TILE_ROUND_DOWN);
    for (int c = 0; c < nchan && !rv; c++)
        rv = exr_add_channel(ctxt, part, names[c], ptype, EXR_PERCEPTUALLY_LOGARITHMIC, 1, 1);
    if (!rv) rv = exr_write_header(ctxt);
    exr_encode_pipeline_t enc;
    memset(&enc, 0, sizeof enc);
    int inited = 0;
    int32_t spc = 1;
    if (!rv && !tiled) rv = exr_get_scanlines_per_chunk(ctxt, part, &spc);
    const int nty = tiled ? (h + 15) / 16 : (h + spc - 1) / spc, ntx = tiled ? (w + 15) / 16 : 1;
    for (int ty = 0; ty < nty && !rv; ty++)
        for (int tx = 0; tx < ntx && !rv; tx++) {
            exr_chunk_info_t ci;
            int x0 = 0, y0;
            if (tiled) {
                rv = exr_write_tile_chunk_info(ctxt, part, tx, ty, 0, 0, &ci);
                x0 = tx * 16;
                y0 = ty * 16;
            } else {
                rv = exr_write_scanline_chunk_info(ctxt, part, ty * spc, &ci);
                y0 = ty * spc;
            }
            if (rv) break;
            rv = inited ? exr_encoding_update(ctxt, part, &ci, &enc)
                        : exr_encoding_initialize(ctxt, part, &ci, &enc);
            if (rv) break;
            inited = 1;
            for (int k = 0; k < enc.channel_count; k++) {
                int c = 0;
                while (strcmp(names[c], enc.channels[k].channel_name)) c++;
                enc.channels[k].user_bytes_per_element = (int16_t)bpe;
                enc.channels[k].user_data_type = (uint16_t)ptype;
                enc.channels[k].user_pixel_stride = bpe;
                enc.channels[k].user_line_stride = bpe * w;
                enc.channels[k].encode_from_ptr =
                    (const uint8_t *)planes[c] + ((size_t)y0 * w + x0) * bpe;
            }
            rv = exr_encoding_choose_default_routines(ctxt, part, &enc);
            if (!rv) rv = exr_encoding_run(ctxt, part, &enc);
        }
    if (inited) exr_encoding_destroy(ctxt, &enc);
    exr_result_t f = exr_finish(&ctxt);
    return rv ? rv : f;
}

/* ------------------------------------------------------------------ tests */

START_TEST(float_round_trip_exact)
{
    char p[256];
    path_in(p, sizeof p, "rt.exr");
    const int w = 37, h = 23; /* not a multiple of the 16-line ZIP chunk */
    for (int nchan = 1; nchan <= 3; nchan += 2) {
        sh_image img = make_image(w, h, nchan);
        for (int i = 0; i < w * h * nchan; i++)
            img.data[i] = (float)(sin(0.37 * i) * pow(10.0, (i % 13) - 6));
        img.data[0] = -0.0f;
        img.data[1] = 3.0e38f;
        img.data[2] = 1e-40f; /* subnormal */
        ck_assert_int_eq(sh_exr_write(p, &img), SH_OK);
        ck_assert_int_eq(count_files(), 1); /* no temporary left */
        sh_image back;
        int fb = -1;
        ck_assert_int_eq(sh_exr_read(p, &back, &fb), SH_OK);
        ck_assert_int_eq(fb, 0);
        ck_assert_int_eq(back.width, w);
        ck_assert_int_eq(back.height, h);
        ck_assert_int_eq(back.nchan, nchan);
        for (int c = 0; c < nchan; c++) ck_assert_str_eq(back.names[c], img.names[c]);
        ck_assert(memcmp(back.data, img.data, sizeof(float) * w * h * nchan) == 0);
        sh_image_free(&back);
        sh_image_free(&img);
    }
}
END_TEST

START_TEST(core_tiled_half_and_uint)
{
    char p[256];
    const int w = 37, h = 23;
    uint16_t *hp[3];
    float *ref[3];
    for (int c = 0; c < 3; c++) {
        hp[c] = malloc(2 * w * h);
        ref[c] = malloc(4 * w * h);
        for (int i = 0; i < w * h; i++) {
            ref[c][i] = (float)((i * (c + 3)) % 257) / 8.0f - 10.0f; /* exact in half */
            ImfFloatToHalf(ref[c][i], &hp[c][i]);
        }
    }
    const char *rgb[] = {"R", "G", "B"};
    const exr_compression_t comps[] = {EXR_COMPRESSION_NONE, EXR_COMPRESSION_PIZ,
                                       EXR_COMPRESSION_ZIP, EXR_COMPRESSION_RLE};
    for (int tiled = 0; tiled <= 1; tiled++)
        for (size_t k = 0; k < 4; k++) {
            path_in(p, sizeof p, "half.exr");
            ck_assert_int_eq(core_write(p, tiled, comps[k], EXR_PIXEL_HALF, 3, rgb,
                                        (const void *const *)hp, w, h), 0);
            sh_image img;
            int fb;
            ck_assert_int_eq(sh_exr_read(p, &img, &fb), SH_OK);
            ck_assert_int_eq(fb, 0);
            ck_assert_int_eq(img.nchan, 3);
            ck_assert_int_eq(img.width, w);
            ck_assert_int_eq(img.height, h);
            for (int c = 0; c < 3; c++)
                ck_assert_msg(memcmp(img.data + c * w * h, ref[c], 4 * w * h) == 0,
                              "half tiled=%d comp=%d channel %d differs", tiled, (int)comps[k], c);
            sh_image_free(&img);
        }
    /* UINT luminance, tiled */
    uint32_t *u = malloc(4 * w * h);
    for (int i = 0; i < w * h; i++) u[i] = (uint32_t)(i * 7919u % 100000u);
    const char *y[] = {"Y"};
    const void *up[] = {u};
    path_in(p, sizeof p, "uint.exr");
    ck_assert_int_eq(core_write(p, 1, EXR_COMPRESSION_ZIP, EXR_PIXEL_UINT, 1, y, up, w, h), 0);
    sh_image img;
    ck_assert_int_eq(sh_exr_read(p, &img, NULL), SH_OK);
    ck_assert_int_eq(img.nchan, 1);
    ck_assert_str_eq(img.names[0], "Y");
    for (int i = 0; i < w * h; i++) ck_assert_msg(img.data[i] == (float)u[i], "uint pixel %d", i);
    sh_image_free(&img);
    free(u);
    for (int c = 0; c < 3; c++) { free(hp[c]); free(ref[c]); }
}
END_TEST

START_TEST(only_z_channel_is_format_error)
{
    char p[256];
    path_in(p, sizeof p, "z.exr");
    const int w = 8, h = 4;
    float z[32] = {0}, d[32] = {0};
    const char *names[] = {"Z", "depth"};
    const void *planes[] = {z, d};
    ck_assert_int_eq(core_write(p, 0, EXR_COMPRESSION_NONE, EXR_PIXEL_FLOAT, 2, names, planes, w, h), 0);
    sh_image img;
    ck_assert_int_eq(sh_exr_read(p, &img, NULL), SH_EFORMAT);
    ck_assert_msg(strstr(sh_last_error(), "Z") && strstr(sh_last_error(), "depth"),
                  "reason should name the channels: %s", sh_last_error());
    ck_assert_ptr_null(img.data);
    /* R and G but no B and no Y is not usable either */
    const char *rg[] = {"G", "R"};
    ck_assert_int_eq(core_write(p, 0, EXR_COMPRESSION_NONE, EXR_PIXEL_FLOAT, 2, rg, planes, w, h), 0);
    ck_assert_int_eq(sh_exr_read(p, &img, NULL), SH_EFORMAT);
}
END_TEST

START_TEST(missing_truncated_garbage)
{
    char p[256];
    sh_image img;
    path_in(p, sizeof p, "absent.exr");
    ck_assert_int_eq(sh_exr_read(p, &img, NULL), SH_EIO);
    ck_assert(strstr(sh_last_error(), "absent.exr") != NULL);

    /* a good file cut to half its length */
    path_in(p, sizeof p, "cut.exr");
    sh_image big = make_image(128, 64, 3);
    for (int i = 0; i < 128 * 64 * 3; i++) big.data[i] = (float)sin(i * 0.001) + (float)(i % 7);
    ck_assert_int_eq(sh_exr_write(p, &big), SH_OK);
    sh_image_free(&big);
    struct stat sb;
    ck_assert_int_eq(stat(p, &sb), 0);
    ck_assert_int_eq(truncate(p, sb.st_size / 2), 0);
    ck_assert_int_eq(sh_exr_read(p, &img, NULL), SH_EFORMAT);
    ck_assert_ptr_null(img.data);

    /* garbage bytes, and the EXR magic followed by garbage, and an empty file */
    path_in(p, sizeof p, "junk.exr");
    FILE *f = fopen(p, "wb");
    for (int i = 0; i < 4000; i++) fputc((i * 131 + 7) & 0xff, f);
    fclose(f);
    ck_assert_int_eq(sh_exr_read(p, &img, NULL), SH_EFORMAT);
    f = fopen(p, "wb");
    const unsigned char magic[] = {0x76, 0x2f, 0x31, 0x01, 2, 0, 0, 0};
    fwrite(magic, 1, sizeof magic, f);
    for (int i = 0; i < 300; i++) fputc((i * 57 + 3) & 0xff, f);
    fclose(f);
    ck_assert_int_eq(sh_exr_read(p, &img, NULL), SH_EFORMAT);
    f = fopen(p, "wb");
    fclose(f);
    ck_assert_int_eq(sh_exr_read(p, &img, NULL), SH_EFORMAT);
}
END_TEST

START_TEST(unwritable_path)
{
    sh_image img = make_image(4, 4, 1);
    for (int i = 0; i < 16; i++) img.data[i] = (float)i;
    char p[256];
    path_in(p, sizeof p, "no/such/dir/out.exr");
    ck_assert_int_eq(sh_exr_write(p, &img), SH_EIO);
    ck_assert(strstr(sh_last_error(), "out.exr") != NULL);
    ck_assert_int_eq(sh_exr_write_dwab_rgba(p, &img), SH_EIO);
    /* a path whose parent is a regular file */
    path_in(p, sizeof p, "plain");
    FILE *f = fopen(p, "w");
    fclose(f);
    path_in(p, sizeof p, "plain/out.exr");
    ck_assert_int_eq(sh_exr_write(p, &img), SH_EIO);
    ck_assert_int_eq(count_files(), 1); /* only "plain": nothing partial was left */
    /* a bad image is refused before anything is created */
    path_in(p, sizeof p, "bad.exr");
    img.nchan = 0;
    ck_assert_int_eq(sh_exr_write(p, &img), SH_EINVAL);
    ck_assert_int_eq(access(p, F_OK), -1);
    img.nchan = 1;
    sh_image_free(&img);
}
END_TEST

/* DWAB is lossy: a smooth image keeps it near-lossless.  Tolerance: half
 * precision rounds to 2^-11 relative (4.9e-4); DWA quantises 8×8 DCT blocks
 * of the (perceptually encoded) channels at the default quality 45, which on
 * this smooth image gave max 0.54% / mean 0.10% relative error (RGB) and
 * 0.37% / 0.09% (Y).  We allow 1% relative per pixel and 0.2% on the mean: loose
 * enough for the codec, tight enough to catch a wrong channel, a flipped or
 * shifted image, or a half/float mix-up. */
START_TEST(dwab_fallback)
{
    char p[256];
    path_in(p, sizeof p, "dwab.exr");
    const int w = 96, h = 48;
    for (int nchan = 3; nchan >= 1; nchan -= 2) {
        sh_image img = make_image(w, h, nchan);
        for (int c = 0; c < nchan; c++)
            for (int y = 0; y < h; y++)
                for (int x = 0; x < w; x++)
                    img.data[c * w * h + y * w + x] =
                        (float)(1.0 + 0.5 * c + 0.4 * sin(x / 15.0) * cos(y / 11.0));
        ck_assert_int_eq(sh_exr_write_dwab_rgba(p, &img), SH_OK);
        /* the header says DWAB, as OpenEXRCore reads it */
        exr_context_t ctxt;
        ck_assert_int_eq(exr_start_read(&ctxt, p, NULL), 0);
        exr_compression_t comp;
        ck_assert_int_eq(exr_get_compression(ctxt, 0, &comp), 0);
        ck_assert_int_eq(comp, EXR_COMPRESSION_DWAB);
        exr_finish(&ctxt);

        sh_image back;
        int fb = 0;
        ck_assert_int_eq(sh_exr_read(p, &back, &fb), SH_OK);
        ck_assert_int_eq(fb, 1);
        ck_assert_int_eq(back.width, w);
        ck_assert_int_eq(back.height, h);
        ck_assert_int_eq(back.nchan, nchan);
        double maxe = 0.0, meane = 0.0;
        for (int i = 0; i < w * h * nchan; i++) {
            const double e = fabs(back.data[i] - img.data[i]) / fabs(img.data[i]);
            maxe = fmax(maxe, e);
            meane += e / (w * h * nchan);
        }
        ck_assert_msg(maxe < 1e-2 && meane < 2e-3, "DWAB nchan=%d: max err %g mean %g", nchan,
                      maxe, meane);
        if (getenv("SHLAB_TEST_VERBOSE"))
            fprintf(stderr, "DWAB nchan=%d: max rel err %g, mean %g\n", nchan, maxe, meane);
        sh_image_free(&back);
        sh_image_free(&img);
    }
}
END_TEST

START_TEST(blender_probe_if_present)
{
    const char *cands[] = {"data/probes/city.exr", "../data/probes/city.exr"};
    const char *p = NULL;
    for (int k = 0; k < 2; k++)
        if (access(cands[k], R_OK) == 0) p = cands[k];
    if (!p) {
        fprintf(stderr, "blender_probe_if_present: skipped (run 'make probes')\n");
        return;
    }
    sh_image img;
    int fb = 0;
    ck_assert_int_eq(sh_exr_read(p, &img, &fb), SH_OK);
    ck_assert_int_eq(img.width, 1024);
    ck_assert_int_eq(img.height, 512);
    ck_assert_int_eq(img.nchan, 3);
    ck_assert_int_eq(fb, 1); /* Blender's probes are DWAB-compressed */
    /* one assertion for the 1.5 M values (an assertion per value took
     * longer than the default timeout under ASan) */
    size_t bad = 0, first = 0;
    for (size_t i = 0; i < (size_t)1024 * 512 * 3; i++)
        if (!isfinite(img.data[i]) && !bad++) first = i;
    ck_assert_msg(bad == 0, "%zu values not finite, the first at %zu", bad, first);
    sh_image_free(&img);
}
END_TEST

static Suite *exr_suite(void)
{
    Suite *s = suite_create("exr");
    TCase *tc = tcase_create("io");
    tcase_add_checked_fixture(tc, setup, teardown);
    tcase_add_test(tc, float_round_trip_exact);
    tcase_add_test(tc, core_tiled_half_and_uint);
    tcase_add_test(tc, only_z_channel_is_format_error);
    tcase_add_test(tc, missing_truncated_garbage);
    tcase_add_test(tc, unwritable_path);
    tcase_add_test(tc, dwab_fallback);
    tcase_add_test(tc, blender_probe_if_present);
    /* the probe's DWAB decode and the scan of its values under
     * SANITIZE=1 (ASan) on a shared 2-core machine: more than the default 4 s */
    tcase_set_timeout(tc, 120);
    suite_add_tcase(s, tc);
    return s;
}

SHLAB_TEST_MAIN(exr_suite)
