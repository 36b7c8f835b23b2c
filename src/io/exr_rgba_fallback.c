/* exr_rgba_fallback.c — writing a DWAB file through OpenEXR's ImfCRgbaFile C
 * interface.
 *
 * OpenEXRCore 3.1.5 cannot encode DWAA/DWAB ("not yet implemented in C");
 * the C++ library can, and it has a small C interface (ImfCRgbaFile.h) for
 * half RGBA images.  sh_exr_write_dwab_rgba exists so that tests can make
 * their own DWAB file (reading: exr_io.c and exr_cxx.cpp).
 *
 * The C interface returns 0 (or NULL) on failure and keeps a message for
 * ImfErrorMessage(); it catches every C++ exception.
 */
#include "core/shlab_internal.h"

#include <ImfCRgbaFile.h>
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>


int sh_exr_write_dwab_rgba(const char *path, const sh_image *img)
{
    if (!img || !img->data || img->width < 1 || img->height < 1)
        return sh_error(SH_EINVAL, "sh_exr_write_dwab_rgba: image is empty");
    if (img->nchan != 1 && img->nchan != 3 && img->nchan != 4)
        return sh_error(SH_EINVAL, "sh_exr_write_dwab_rgba: %d channels (1, 3 or 4)", img->nchan);
    if (!path || !*path) return sh_error(SH_EINVAL, "sh_exr_write_dwab_rgba: empty path");
    const int w = img->width, h = img->height;
    const size_t plane = (size_t)w * h;
    ImfRgba *buf = malloc(plane * sizeof *buf);
    if (!buf) return sh_error(SH_ENOMEM, "out of memory");
    for (size_t p = 0; p < plane; p++) {
        const float r = img->data[p];
        const float g = img->nchan >= 3 ? img->data[plane + p] : r;
        const float b = img->nchan >= 3 ? img->data[2 * plane + p] : r;
        const float a = img->nchan == 4 ? img->data[3 * plane + p] : 1.0f;
        ImfFloatToHalf(r, &buf[p].r);
        ImfFloatToHalf(g, &buf[p].g);
        ImfFloatToHalf(b, &buf[p].b);
        ImfFloatToHalf(a, &buf[p].a);
    }
    char *tmp = NULL;
    int st = sh__make_temp_path(path, &tmp);
    if (st) { free(buf); return st; }

    ImfHeader *hdr = ImfNewHeader();
    ImfOutputFile *out = NULL;
    if (!hdr) {
        st = sh_error(SH_ENOMEM, "cannot write '%s': %s", path, ImfErrorMessage());
        goto fail;
    }
    ImfHeaderSetDataWindow(hdr, 0, 0, w - 1, h - 1);
    ImfHeaderSetDisplayWindow(hdr, 0, 0, w - 1, h - 1);
    ImfHeaderSetCompression(hdr, IMF_DWAB_COMPRESSION);
    const int channels = img->nchan == 1 ? IMF_WRITE_Y
                       : img->nchan == 3 ? IMF_WRITE_RGB : IMF_WRITE_RGBA;
    sigset_t old; /* OpenEXR opens the temporary by name: inside a window */
    sh__temp_enter(&old);
    out = ImfOpenOutputFile(tmp, hdr, channels);
    sh__temp_leave(&old);
    if (!out || !ImfOutputSetFrameBuffer(out, buf, 1, (size_t)w) ||
        !ImfOutputWritePixels(out, h)) {
        st = sh_error(SH_EIO, "cannot write '%s': %s", path, ImfErrorMessage());
        goto fail;
    }
    if (!ImfCloseOutputFile(out)) {
        out = NULL;
        st = sh_error(SH_EIO, "cannot write '%s': %s", path, ImfErrorMessage());
        goto fail;
    }
    out = NULL;
    ImfDeleteHeader(hdr);
    free(buf);
    st = sh__commit_temp(tmp, path);
    free(tmp);
    return st;
fail:
    if (out) ImfCloseOutputFile(out);
    if (hdr) ImfDeleteHeader(hdr);
    sh__discard_temp(tmp);
    free(tmp);
    free(buf);
    return st;
}
