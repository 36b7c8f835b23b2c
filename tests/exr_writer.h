/* exr_writer.h — a test helper (tests/exr_writer.cpp) that writes EXR files
 * with OpenEXR's C++ library, the reference implementation, in any layout it
 * supports, and reads one channel back with it.  Used by the EXR tests and by
 * the fuzz seed generator; not part of the library. */
#ifndef SHLAB_TEST_EXR_WRITER_H
#define SHLAB_TEST_EXR_WRITER_H

#ifdef __cplusplus
extern "C" {
#endif

enum { TW_UINT = 0, TW_HALF = 1, TW_FLOAT = 2 };          /* Imf::PixelType */
enum { TW_SCANLINE = 0, TW_TILED, TW_MIPMAP, TW_RIPMAP }; /* storage */
#define TW_MAX_CHANNELS 8

typedef struct {
    int width, height, xmin, ymin; /* data window */
    int compression;               /* Imf::Compression = EXR_COMPRESSION_* (0..9) */
    int storage, tile_w, tile_h;
    int nchan;
    const char *names[TW_MAX_CHANNELS];
    int types[TW_MAX_CHANNELS];
    int xs[TW_MAX_CHANNELS], ys[TW_MAX_CHANNELS]; /* sampling (0 = 1; scanline only) */
} tw_spec;

/* planes[c]: the channel's samples, row-major over its (sub-sampled) grid,
 * as uint32, half bits (uint16) or float.  Level 0 of tiled files is written
 * from them, other levels with a constant.  Returns 0, or -1 with a message
 * in tw_error(). */
int tw_write(const char *path, const tw_spec *spec, const void *const *planes);
/* Read channel `name` of level 0 as float (width × height values). */
int tw_read_channel(const char *path, const char *name, float *out);
const char *tw_error(void);

#ifdef __cplusplus
}
#endif
#endif
