/* exr_internal.h — declarations shared by the EXR reader's C and C++ parts
 * (src/io/), not installed. */
#ifndef SHLAB_EXR_INTERNAL_H
#define SHLAB_EXR_INTERNAL_H

#include "shlab.h"

#ifdef __cplusplus
extern "C" {
#endif

/* exr_cxx.cpp: read the pixels of `part` of the EXR data in memory through
 * OpenEXR's C++ library into img (width, height, nchan, names and data set
 * by the caller; the data window starts at xmin, ymin).  Every exception is
 * caught and returned as a status with a reason. */
int sh__exr_read_cxx(const void *data, size_t size, const char *name, int part, int xmin, int ymin,
                     sh_image *img);

#ifdef __cplusplus
}
#endif
#endif
