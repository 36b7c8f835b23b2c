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
/* Largest image (width × height) any routine reads, writes or projects. */
#define SH_IMAGE_MAX_PIXELS (1LL << 30)
typedef struct {
    int width, height, nchan;
    char names[SH_IMAGE_MAX_CHANNELS][8]; /* "R","G","B","A" or "Y" */
    float *data;
} sh_image;

void sh_image_free(sh_image *img);
/* Read an OpenEXR file (scanline or tiled; half, float or uint channels; any
 * compression).  Channels R,G,B (or a single Y) are read by name; missing
 * file, corrupt file or no usable channel is an error.  OpenEXRCore is used
 * first; DWAA/DWAB data (not decodable by OpenEXRCore 3.1) falls back to the
 * ImfCRgbaFile C interface.  *used_fallback (may be NULL) reports which. */
int sh_exr_read(const char *path, sh_image *img, int *used_fallback);
/* Write a float EXR with OpenEXRCore; written to a temporary name and renamed,
 * so that a failure never leaves a partial file. */
int sh_exr_write(const char *path, const sh_image *img);

typedef enum { SH_LAYOUT_LATLONG = 0, SH_LAYOUT_PROBE } sh_layout;
int sh_layout_parse(const char *s, sh_layout *out);
/* Exact solid angle of every pixel (w*h weights, row-major). */
int sh_pixel_solid_angles(sh_layout layout, int width, int height, double *w);

/* Read an EXR through OpenEXR's ImfCRgbaFile C interface (the DWAA/DWAB
 * fallback of sh_exr_read; any compression the C++ library knows).  R,G,B
 * → 3 channels; a luminance-only (Y) file → 1 channel "Y"; half → float. */
int sh_exr_read_rgba(const char *path, sh_image *img);
/* Write img (1 channel → Y; 3 → RGB; 4 → RGBA) as a half-float DWAB file
 * through ImfCRgbaFile, via a temporary file renamed into place. */

#ifdef __cplusplus
}
#endif
#endif /* SHLAB_IO_H */
