/* exr_writer.cpp — see exr_writer.h. */
#include "exr_writer.h"

#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>
#include <ImfOutputFile.h>
#include <ImfTiledOutputFile.h>
#include <ImfTileDescriptionAttribute.h>

#include <cstdio>
#include <cstring>
#include <exception>
#include <vector>

static char err[512];

const char *tw_error(void) { return err; }

static size_t bpe(int t) { return t == TW_HALF ? 2 : 4; }

int tw_write(const char *path, const tw_spec *s, const void *const *planes)
{
    try {
        Imath::Box2i dw(Imath::V2i(s->xmin, s->ymin),
                        Imath::V2i(s->xmin + s->width - 1, s->ymin + s->height - 1));
        Imf::Header h(dw, dw);
        h.compression() = static_cast<Imf::Compression>(s->compression);
        for (int c = 0; c < s->nchan; c++) {
            const int xs = s->xs[c] > 0 ? s->xs[c] : 1, ys = s->ys[c] > 0 ? s->ys[c] : 1;
            h.channels().insert(s->names[c], Imf::Channel(static_cast<Imf::PixelType>(s->types[c]), xs, ys));
        }
        if (s->storage == TW_SCANLINE) {
            Imf::FrameBuffer fb;
            for (int c = 0; c < s->nchan; c++) {
                const int xs = s->xs[c] > 0 ? s->xs[c] : 1, ys = s->ys[c] > 0 ? s->ys[c] : 1;
                const size_t b = bpe(s->types[c]);
                const int sw = s->width / xs;
                /* base addresses sample (0,0) of the sampled grid: x/xs, y/ys */
                char *base = (char *)planes[c] - (ptrdiff_t)(s->xmin / xs) * (ptrdiff_t)b -
                             (ptrdiff_t)(s->ymin / ys) * (ptrdiff_t)sw * (ptrdiff_t)b;
                fb.insert(s->names[c], Imf::Slice(static_cast<Imf::PixelType>(s->types[c]), base, b,
                                                  b * (size_t)sw, xs, ys));
            }
            Imf::OutputFile out(path, h);
            out.setFrameBuffer(fb);
            out.writePixels(s->height);
            return 0;
        }
        const Imf::LevelMode lm = s->storage == TW_TILED  ? Imf::ONE_LEVEL
                                  : s->storage == TW_MIPMAP ? Imf::MIPMAP_LEVELS
                                                            : Imf::RIPMAP_LEVELS;
        h.setTileDescription(Imf::TileDescription(s->tile_w, s->tile_h, lm, Imf::ROUND_DOWN));
        Imf::TiledOutputFile out(path, h);
        std::vector<std::vector<char>> fill(s->nchan);
        for (int ly = 0; ly < out.numYLevels(); ly++)
            for (int lx = 0; lx < out.numXLevels(); lx++) {
                if (s->storage == TW_MIPMAP && lx != ly) continue;
                const Imath::Box2i lw = out.dataWindowForLevel(lx, ly);
                const int w = lw.max.x - lw.min.x + 1, hh = lw.max.y - lw.min.y + 1;
                Imf::FrameBuffer fb;
                for (int c = 0; c < s->nchan; c++) {
                    const size_t b = bpe(s->types[c]);
                    char *p;
                    if (lx == 0 && ly == 0) p = (char *)planes[c];
                    else {
                        fill[c].assign((size_t)w * hh * b, 0);
                        for (size_t i = 0; i < (size_t)w * hh; i++) {
                            if (s->types[c] == TW_HALF) { uint16_t one = 0x3c00; memcpy(&fill[c][i * 2], &one, 2); }
                            else if (s->types[c] == TW_FLOAT) { float one = 1.0f; memcpy(&fill[c][i * 4], &one, 4); }
                            else { uint32_t one = 1; memcpy(&fill[c][i * 4], &one, 4); }
                        }
                        p = fill[c].data();
                    }
                    fb.insert(s->names[c], Imf::Slice::Make(static_cast<Imf::PixelType>(s->types[c]), p, lw, b, b * (size_t)w));
                }
                out.setFrameBuffer(fb);
                out.writeTiles(0, out.numXTiles(lx) - 1, 0, out.numYTiles(ly) - 1, lx, ly);
            }
        return 0;
    } catch (const std::exception &e) {
        snprintf(err, sizeof err, "%s", e.what());
        return -1;
    }
}

int tw_read_channel(const char *path, const char *name, float *out)
{
    try {
        Imf::InputFile in(path);
        const Imath::Box2i dw = in.header().dataWindow();
        const size_t w = (size_t)(dw.max.x - dw.min.x + 1);
        Imf::FrameBuffer fb;
        fb.insert(name, Imf::Slice::Make(Imf::FLOAT, out, dw, sizeof(float), sizeof(float) * w));
        in.setFrameBuffer(fb);
        in.readPixels(dw.min.y, dw.max.y);
        return 0;
    } catch (const std::exception &e) {
        snprintf(err, sizeof err, "%s", e.what());
        return -1;
    }
}
