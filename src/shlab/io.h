/* shlab/io.h — images and OpenEXR input/output.
 * Part of the public API: include <shlab.h>, which includes every part. */
#ifndef SHLAB_IO_H
#define SHLAB_IO_H

#include "core.h"

#ifdef __cplusplus
extern "C" {
#endif

/* ----------------------------------------------------------------- images
 * Planar float image: data[c*width*height + y*width + x]. */
#define SH_IMAGE_MAX_CHANNELS 4
/* Largest image (width × height) any routine reads, writes or projects:
 * 2²⁶ = 67,108,864 pixels (8192 × 8192, or a lat-long 11584 × 5792), the
 * size tests/core/test_ranges.c reconstructs, projects and reads in full (it was
 * 2³⁰, which no test could hold: 4 GB a channel). */
#define SH_IMAGE_MAX_PIXELS (1LL << 26)
typedef struct {
    int width, height, nchan;
    char names[SH_IMAGE_MAX_CHANNELS][8]; /* "R","G","B","A" or "Y" */
    float *data;
} sh_image;

void sh_image_free(sh_image *img);

/* Limits of the EXR reader.  Everything is checked before a pixel is decoded
 * or the image allocated; exceeding a limit is an error with one line that
 * says what was asked for. */
typedef struct {
    long long max_pixels; /* width × height (default SH_IMAGE_MAX_PIXELS) */
    long long max_bytes;  /* memory for the file's bytes, the image and the
                             decoding buffers (default: physical memory) */
    int max_channels;     /* channels in the part read (default 1024) */
    double max_ratio;     /* declared uncompressed pixel bytes per byte of
                             data (default 65536; valid files reach ~2·10⁴,
                             DWAB of a constant image) */
} sh_exr_limits;
void sh_exr_limits_default(sh_exr_limits *lim);

/* Read an OpenEXR image from memory (scanline or tiled; half, float or uint
 * channels; any compression).  Channels R,G,B (or a single Y) are read by
 * name; corrupt data or no usable channel is an error.  The header and the
 * chunk table are checked against `size` and `lim` (NULL: defaults) before
 * anything is decoded.  OpenEXRCore decodes; DWAA/DWAB data (not decodable by
 * OpenEXRCore 3.1) is decoded by OpenEXR's C++ library, and *used_fallback
 * (may be NULL) reports which.  `name` (may be NULL) names the data in
 * messages. */
int sh_exr_read_mem(const void *data, size_t size, const char *name, const sh_exr_limits *lim,
                    sh_image *img, int *used_fallback);
/* sh_exr_read_mem of a file's contents, with the default limits (the file's
 * size counts against max_bytes).  Missing or unreadable file: SH_EIO. */
int sh_exr_read(const char *path, sh_image *img, int *used_fallback);
/* Write a float EXR with OpenEXRCore; written to a temporary name and renamed,
 * so that a failure never leaves a partial file. */
int sh_exr_write(const char *path, const sh_image *img);
/* The same with progress: fn(ctx, rows written, height, "rows written") as
 * chunks of rows are compressed and written (a 46340×23170 image: minutes). */
int sh_exr_write_progress(const char *path, const sh_image *img, sh_progress_fn fn, void *ctx);

/* ------------------------------------------------------------ input files
 * The policy every reader applies (input_file.c): regular files only (a
 * FIFO, directory, device or socket is refused without blocking), the size
 * checked against max_bytes (< 0: no limit) before reading, one message
 * naming `what` ("mesh", "fixture", ...) and the path.  dev, ino identify
 * the file (the CLI refuses an output that names an input). */
typedef struct {
    int fd;
    long long size;
    unsigned long long dev, ino;
} sh_input;
int sh_input_open(const char *what, const char *path, long long max_bytes, sh_input *in);
void sh_input_close(sh_input *in);
/* The whole file into a malloc'd, NUL-terminated buffer (*n bytes). */
int sh_input_read_all(const char *what, const char *path, long long max_bytes, char **buf, size_t *n);

typedef enum { SH_LAYOUT_LATLONG = 0, SH_LAYOUT_PROBE } sh_layout;
int sh_layout_parse(const char *s, sh_layout *out);
/* Exact solid angle of every pixel (w*h weights, row-major). */
int sh_pixel_solid_angles(sh_layout layout, int width, int height, double *w);

/* Read an EXR file as sh_exr_read does, but decode its pixels with OpenEXR's
 * C++ library whatever the compression (the DWAA/DWAB path of sh_exr_read). */
int sh_exr_read_rgba(const char *path, sh_image *img);
/* Write img (1 channel → Y; 3 → RGB; 4 → RGBA) as a half-float DWAB file
 * through ImfCRgbaFile, via a temporary file renamed into place. */

#ifdef __cplusplus
}
#endif
#endif /* SHLAB_IO_H */
