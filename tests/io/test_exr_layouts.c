/* test_exr_layouts.c — the EXR reader on every layout OpenEXR writes:
 * every compression (NONE, RLE, ZIPS, ZIP, PIZ, PXR24, B44, B44A, DWAA,
 * DWAB) × pixel type (half, float, uint, and the three mixed in one file) ×
 * channel layout (RGB, RGBA, BGRZ, A/Y/Z, Y, YA, RGBAZ, RGB+Y+A+Z, and Y
 * with sub-sampled chroma) × storage (scanline, tiled, mipmap, ripmap).
 *
 * The files are written by OpenEXR's C++ library (tests/exr_writer.cpp),
 * the reference implementation, with a data window that starts at (-4, 6)
 * and a size (38×22) that leaves partial chunks, tiles and DWA blocks.
 * Independent truths: for lossless storage the values written (chosen exact
 * in half); for lossy storage (B44/B44A/DWA of half, PXR24 of float) the
 * C++ library's own reading of the same file.  Half RGBA files crashed
 * OpenEXRCore 3.1.5's unpacker before (see src/io/exr_io.c). */
#include "testutil.h"
#include "exr_writer.h"

#include <ImfCRgbaFile.h>
#include <string.h>
#include <unistd.h>

#define W 38
#define H 22
#define XMIN (-4)
#define YMIN 6

static char path[64];

static void setup(void)
{
    strcpy(path, "/tmp/shlab_test_layouts.XXXXXX");
    int fd = mkstemp(path);
    ck_assert_int_ge(fd, 0);
    close(fd);
}

static void teardown(void) { unlink(path); }

typedef struct {
    const char *label;
    int nchan;
    const char *names[6];
    int sub; /* channels after the first are sub-sampled 2×2 (scanline only) */
} layout;

static const layout layouts[] = {
    {"RGB", 3, {"R", "G", "B"}, 0},
    {"RGBA", 4, {"R", "G", "B", "A"}, 0},
    {"BGRZ", 4, {"B", "G", "R", "Z"}, 0},
    {"AYZ", 3, {"A", "Y", "Z"}, 0},
    {"Y", 1, {"Y"}, 0},
    {"YA", 2, {"Y", "A"}, 0},
    {"RGBAZ", 5, {"R", "G", "B", "A", "Z"}, 0},
    {"ABGRYZ", 6, {"A", "B", "G", "R", "Y", "Z"}, 0},
    {"Y+RY,BY", 3, {"Y", "RY", "BY"}, 1},
};
#define NLAYOUT ((int)(sizeof layouts / sizeof *layouts))

/* pixel types: all half, all float, all uint, or mixed (channel c gets
 * half, float, uint in turn) */
static int ptype(int t, int c) { return t < 3 ? (t == 0 ? TW_HALF : t == 1 ? TW_FLOAT : TW_UINT) : (c % 3 == 0 ? TW_HALF : c % 3 == 1 ? TW_FLOAT : TW_UINT); }
static const char *const tname[4] = {"half", "float", "uint", "mixed"};
static const char *const sname[4] = {"scanline", "tiled", "mipmap", "ripmap"};
static const char *const cname[10] = {"none", "rle", "zips", "zip", "piz", "pxr24", "b44", "b44a", "dwaa", "dwab"};

/* A value exactly representable in half (and as uint: a non-negative
 * integer), different per channel and pixel. */
static float value(int type, int c, int i)
{
    if (type == TW_UINT) return (float)((i * 7919u + 131u * (unsigned)c) % 2048u);
    return (float)((i * (c + 3) + 17 * c) % 257) / 8.0f - 10.0f;
}

/* Lossy: B44/B44A on half channels, PXR24 on float channels, DWAA/DWAB on
 * half and float channels. */
static int lossy(int comp, int type)
{
    if (type == TW_HALF) return comp == 6 || comp == 7 || comp == 8 || comp == 9;
    if (type == TW_FLOAT) return comp == 5 || comp == 8 || comp == 9;
    return 0;
}

static int one_file(int comp, int storage, int t, const layout *L, char *why, size_t nwhy)
{
    tw_spec s;
    memset(&s, 0, sizeof s);
    s.width = W;
    s.height = H;
    s.xmin = XMIN;
    s.ymin = YMIN;
    s.compression = comp;
    s.storage = storage;
    s.tile_w = storage == TW_TILED ? 16 : 8;
    s.tile_h = 8;
    s.nchan = L->nchan;
    void *planes[6];
    for (int c = 0; c < L->nchan; c++) {
        s.names[c] = L->names[c];
        s.types[c] = ptype(t, c);
        s.xs[c] = s.ys[c] = L->sub && c > 0 ? 2 : 1;
        const int n = (W / s.xs[c]) * (H / s.ys[c]);
        planes[c] = malloc((size_t)n * 4);
        for (int i = 0; i < n; i++) {
            const float v = value(s.types[c], c, i);
            if (s.types[c] == TW_HALF) {
                ImfHalf h;
                ImfFloatToHalf(v, &h);
                ((uint16_t *)planes[c])[i] = h;
            } else if (s.types[c] == TW_FLOAT) {
                ((float *)planes[c])[i] = v;
            } else {
                ((uint32_t *)planes[c])[i] = (uint32_t)v;
            }
        }
    }
    int bad = 0;
    if (tw_write(path, &s, (const void *const *)planes)) {
        snprintf(why, nwhy, "writer failed: %s", tw_error());
        bad = 1;
    }
    sh_image img;
    int fb = -1;
    if (!bad && sh_exr_read(path, &img, &fb) != SH_OK) {
        snprintf(why, nwhy, "read failed: %s", sh_last_error());
        bad = 1;
    }
    if (!bad) {
        /* channel choice: R,G,B if all present, else Y */
        int want[3], nw = 0;
        for (int k = 0; k < 3; k++)
            for (int c = 0; c < L->nchan; c++)
                if (!strcmp(L->names[c], (const char *[]){"R", "G", "B"}[k])) want[nw++] = c;
        if (nw < 3) {
            nw = 0;
            for (int c = 0; c < L->nchan; c++)
                if (!strcmp(L->names[c], "Y")) want[nw++] = c;
        }
        /* the C++ library decodes DWA, B44 with non-half channels and
         * sub-sampled parts (see src/io/exr_io.c) */
        int mixed44 = 0;
        for (int c = 0; c < L->nchan; c++) mixed44 |= (comp == 6 || comp == 7) && s.types[c] != TW_HALF;
        const int want_fb = comp >= 8 || mixed44 || L->sub;
        if (img.nchan != nw || img.width != W || img.height != H || fb != want_fb) {
            snprintf(why, nwhy, "got %d channels %d×%d fallback %d", img.nchan, img.width, img.height, fb);
            bad = 1;
        }
        float *ref = malloc(sizeof(float) * W * H);
        for (int k = 0; !bad && k < nw; k++) {
            const int c = want[k];
            if (strcmp(img.names[k], L->names[c])) {
                snprintf(why, nwhy, "channel %d is %s, expected %s", k, img.names[k], L->names[c]);
                bad = 1;
                break;
            }
            if (lossy(comp, s.types[c])) {
                if (tw_read_channel(path, L->names[c], ref)) {
                    snprintf(why, nwhy, "C++ read failed: %s", tw_error());
                    bad = 1;
                    break;
                }
            } else {
                for (int i = 0; i < W * H; i++) ref[i] = value(s.types[c], c, i);
            }
            for (int i = 0; i < W * H; i++)
                if (memcmp(&img.data[(size_t)k * W * H + i], &ref[i], sizeof(float)) != 0) {
                    float *cx = malloc(sizeof(float) * W * H);
                    tw_read_channel(path, L->names[c], cx);
                    snprintf(why, nwhy, "channel %s pixel (%d,%d): %.9g, expected %.9g (C++ reads %.9g)", L->names[c],
                             i % W, i / W, img.data[(size_t)k * W * H + i], ref[i], cx[i]);
                    free(cx);
                    bad = 1;
                    break;
                }
        }
        free(ref);
        sh_image_free(&img);
    }
    for (int c = 0; c < L->nchan; c++) free(planes[c]);
    return bad;
}

START_TEST(every_layout)
{
    int files = 0, failures = 0;
    char why[256], first[512] = "";
    for (int comp = 0; comp < 10; comp++)
        for (int storage = 0; storage < 4; storage++)
            for (int t = 0; t < 4; t++)
                for (int l = 0; l < NLAYOUT; l++) {
                    if (layouts[l].sub && storage != TW_SCANLINE) continue; /* tiles are never sub-sampled */
                    files++;
                    if (one_file(comp, storage, t, &layouts[l], why, sizeof why)) {
                        if (!failures)
                            snprintf(first, sizeof first, "%s %s %s %s: %s", cname[comp], sname[storage],
                                     tname[t], layouts[l].label, why);
                        if (getenv("SHLAB_TEST_VERBOSE"))
                            fprintf(stderr, "%s %s %s %s: %s\n", cname[comp], sname[storage], tname[t],
                                    layouts[l].label, why);
                        failures++;
                    }
                }
    ck_assert_msg(failures == 0, "%d of %d files read wrongly; first: %s", failures, files, first);
}
END_TEST

static Suite *layouts_suite(void)
{
    Suite *s = suite_create("exr_layouts");
    TCase *tc = tcase_create("layouts");
    tcase_add_checked_fixture(tc, setup, teardown);
    tcase_set_timeout(tc, 600);
    tcase_add_test(tc, every_layout);
    suite_add_tcase(s, tc);
    return s;
}

SHLAB_TEST_MAIN(layouts_suite)
