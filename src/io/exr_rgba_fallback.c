/* exr_rgba_fallback.c — EXR I/O through OpenEXR's ImfCRgbaFile C interface.
 *
 * OpenEXRCore 3.1.5 cannot decode DWAA/DWAB ("not yet implemented in C");
 * the C++ library can, and it has a small C interface (ImfCRgbaFile.h) for
 * half RGBA images.  sh_exr_read uses sh_exr_read_rgba for those files.
 * sh_exr_write_dwab_rgba exists so that tests can make their own DWAB file.
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


int sh_exr_read_rgba(const char *path, sh_image *img)
{
    if (!img) return sh_error(SH_EINVAL, "sh_exr_read_rgba: image is NULL");
    memset(img, 0, sizeof *img);
    if (!path || !*path) return sh_error(SH_EINVAL, "sh_exr_read_rgba: empty path");
    FILE *probe = fopen(path, "rb");
    if (!probe) return sh_error(SH_EIO, "cannot open '%s': %s", path, strerror(errno));
    fclose(probe);

    ImfInputFile *in = ImfOpenInputFile(path);
    if (!in) return sh_error(SH_EFORMAT, "%s: %s", path, ImfErrorMessage());
    int xmin, ymin, xmax, ymax;
    ImfHeaderDataWindow(ImfInputHeader(in), &xmin, &ymin, &xmax, &ymax);
    const long long w = (long long)xmax - xmin + 1, h = (long long)ymax - ymin + 1;
    const int chans = ImfInputChannels(in);
    int st = SH_OK;
    ImfRgba *buf = NULL;
    if (w < 1 || h < 1 || w * h > SH_IMAGE_MAX_PIXELS) {
        st = sh_error(SH_EFORMAT, "%s: unusable data window %lld×%lld", path, w, h);
        goto done;
    }
    if ((chans & IMF_WRITE_RGB) == IMF_WRITE_RGB) {
        img->nchan = 3;
        strcpy(img->names[0], "R");
        strcpy(img->names[1], "G");
        strcpy(img->names[2], "B");
    } else if (chans & IMF_WRITE_Y) {
        img->nchan = 1; /* the RGBA interface returns luminance as r = g = b = Y */
        strcpy(img->names[0], "Y");
    } else {
        st = sh_error(SH_EFORMAT, "%s: no usable channel (need R,G,B or Y)", path);
        goto done;
    }
    img->width = (int)w;
    img->height = (int)h;
    buf = malloc((size_t)w * h * sizeof *buf);
    img->data = malloc((size_t)w * h * img->nchan * sizeof(float));
    if (!buf || !img->data) {
        st = sh_error(SH_ENOMEM, "%s: cannot allocate %lld×%lld pixels", path, w, h);
        goto done;
    }
    /* The frame buffer base addresses pixel (0,0) of the data window's
     * coordinate system: base + x·xStride + y·yStride. */
    if (!ImfInputSetFrameBuffer(in, buf - xmin - (ptrdiff_t)ymin * w, 1, (size_t)w) ||
        !ImfInputReadPixels(in, ymin, ymax)) {
        st = sh_error(SH_EFORMAT, "%s: %s", path, ImfErrorMessage());
        goto done;
    }
    const size_t plane = (size_t)w * h;
    for (size_t p = 0; p < plane; p++) {
        img->data[p] = ImfHalfToFloat(buf[p].r);
        if (img->nchan == 3) {
            img->data[plane + p] = ImfHalfToFloat(buf[p].g);
            img->data[2 * plane + p] = ImfHalfToFloat(buf[p].b);
        }
    }
done:
    free(buf);
    ImfCloseInputFile(in);
    if (st != SH_OK) {
        sh_image_free(img);
        memset(img, 0, sizeof *img);
    }
    return st;
}

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
    out = ImfOpenOutputFile(tmp, hdr, channels);
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
    unlink(tmp);
    free(tmp);
    free(buf);
    return st;
}
