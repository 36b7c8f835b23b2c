/* exr_seeds.c — writes the EXR seed corpus (tests/fuzz/corpus/exr/): small
 * files (12×10 pixels, data window at (-2, 3)) in every compression, as half
 * RGBA scanlines (the layout that crashed OpenEXRCore 3.1.5's unpacker),
 * float RGB tiles, uint Y mipmaps, half A/Y/Z, BGRZ ripmaps and Y with
 * sub-sampled chroma, written by OpenEXR's C++ library (tests/exr_writer.cpp).
 * Usage: exr_seeds DIR   (tests/fuzz/make_seeds.sh runs it) */
#include "exr_writer.h"

#include <ImfCRgbaFile.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

int main(int argc, char **argv)
{
    if (argc != 2) { fprintf(stderr, "usage: exr_seeds DIR\n"); return 2; }
    static const char *const comp[10] = {"none", "rle", "zips", "zip", "piz", "pxr24", "b44", "b44a", "dwaa", "dwab"};
    static const struct {
        const char *label;
        int storage, nchan, type, sub;
        const char *names[4];
    } kinds[] = {
        {"rgba-half-scan", TW_SCANLINE, 4, TW_HALF, 0, {"R", "G", "B", "A"}},
        {"rgb-float-tiled", TW_TILED, 3, TW_FLOAT, 0, {"R", "G", "B"}},
        {"y-uint-mipmap", TW_MIPMAP, 1, TW_UINT, 0, {"Y"}},
        {"ayz-half-scan", TW_SCANLINE, 3, TW_HALF, 0, {"A", "Y", "Z"}},
        {"bgrz-half-ripmap", TW_RIPMAP, 4, TW_HALF, 0, {"B", "G", "R", "Z"}},
        {"y-ry-by-half-scan", TW_SCANLINE, 3, TW_HALF, 1, {"Y", "RY", "BY"}},
    };
    int written = 0;
    for (size_t k = 0; k < sizeof kinds / sizeof *kinds; k++)
        for (int c = 0; c < 10; c++) {
            /* a smaller set: every compression for the first two kinds, the
             * others with zip, piz, b44 and dwab */
            if (k >= 2 && c != 3 && c != 4 && c != 6 && c != 9) continue;
            tw_spec s;
            memset(&s, 0, sizeof s);
            s.width = 12;
            s.height = 10;
            s.xmin = -2;
            s.ymin = 4;
            s.compression = c;
            s.storage = kinds[k].storage;
            s.tile_w = 8;
            s.tile_h = 4;
            s.nchan = kinds[k].nchan;
            void *planes[4];
            for (int ch = 0; ch < s.nchan; ch++) {
                s.names[ch] = kinds[k].names[ch];
                s.types[ch] = kinds[k].type;
                s.xs[ch] = s.ys[ch] = kinds[k].sub && ch ? 2 : 1;
                const int n = (s.width / s.xs[ch]) * (s.height / s.ys[ch]);
                planes[ch] = malloc((size_t)n * 4);
                for (int i = 0; i < n; i++) {
                    const float v = (float)((i * (ch + 5)) % 31) / 4.0f;
                    if (s.types[ch] == TW_HALF) ImfFloatToHalf(v, &((ImfHalf *)planes[ch])[i]);
                    else if (s.types[ch] == TW_FLOAT) ((float *)planes[ch])[i] = v;
                    else ((uint32_t *)planes[ch])[i] = (uint32_t)(v * 4);
                }
            }
            char path[512];
            snprintf(path, sizeof path, "%s/%s-%s.exr", argv[1], kinds[k].label, comp[c]);
            if (tw_write(path, &s, (const void *const *)planes)) {
                fprintf(stderr, "exr_seeds: %s: %s\n", path, tw_error());
                return 1;
            }
            for (int ch = 0; ch < s.nchan; ch++) free(planes[ch]);
            written++;
        }
    printf("exr_seeds: %d files in %s\n", written, argv[1]);
    return 0;
}
