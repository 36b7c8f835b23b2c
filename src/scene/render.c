/* render.c — pictures of shaded scenes: a pinhole camera's rays through
 * Embree, per-vertex values interpolated barycentrically (Gouraud, as
 * Green's renderer), the environment behind; false colour; PNG (libpng). */
#include "scene_internal.h"

#include <png.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

static void normalize(double v[3])
{
    const double l = sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    if (l > 0) for (int k = 0; k < 3; k++) v[k] /= l;
}

int sh_camera_frame(const sh_mesh *m, const double view_dir[3], double fov_deg, int width, int height, sh_camera *cam)
{
    if (!m || !m->pos || m->nvert < 1 || !view_dir || !cam) return sh_error(SH_EINVAL, "sh_camera_frame: bad arguments");
    if (!(fov_deg > 1 && fov_deg < 170) || width < 1 || height < 1 || width > 16384 || height > 16384)
        return sh_error(SH_EINVAL, "camera: field of view in (1, 170) degrees and 1..16384 pixels needed");
    double d[3] = {view_dir[0], view_dir[1], view_dir[2]};
    const double dl = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    if (!(dl > 0) || !isfinite(dl)) return sh_error(SH_EINVAL, "camera: zero or non-finite view direction");
    normalize(d);
    double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
    for (int v = 0; v < m->nvert; v++)
        for (int k = 0; k < 3; k++) {
            lo[k] = fmin(lo[k], m->pos[3 * v + k]);
            hi[k] = fmax(hi[k], m->pos[3 * v + k]);
        }
    double c[3], r = 0;
    for (int k = 0; k < 3; k++) c[k] = 0.5 * (lo[k] + hi[k]);
    for (int v = 0; v < m->nvert; v++) {
        const double *p = m->pos + 3 * v;
        r = fmax(r, sqrt((p[0] - c[0]) * (p[0] - c[0]) + (p[1] - c[1]) * (p[1] - c[1]) + (p[2] - c[2]) * (p[2] - c[2])));
    }
    if (!(r > 0)) r = 1;
    /* the bounding sphere fits the smaller field of view */
    const double fv = fov_deg * M_PI / 180, fh = 2 * atan(tan(0.5 * fv) * width / height);
    const double dist = r / sin(0.5 * fmin(fv, fh));
    for (int k = 0; k < 3; k++) {
        cam->target[k] = c[k];
        cam->eye[k] = c[k] + dist * d[k];
    }
    const int vertical = fabs(d[2]) > 0.999;
    cam->up[0] = 0;
    cam->up[1] = vertical ? 1 : 0;
    cam->up[2] = vertical ? 0 : 1;
    cam->fov_deg = fov_deg;
    cam->width = width;
    cam->height = height;
    return SH_OK;
}

typedef struct {
    const sh_scene *s;
    const sh_camera *cam;
    int nchan;
    const double *vcol;
    const sh_env *bg;
    double fw[3], rt[3], up[3], tx, ty;
    sh_image *out;
} renctx;

static int render_rows(void *vc, int thread, int begin, int end)
{
    renctx *c = vc;
    const sh_mesh *m = &c->s->mesh;
    const int W = c->cam->width, H = c->cam->height;
    const size_t np = (size_t)W * H;
    for (int y = begin; y < end; y++)
        for (int x = 0; x < W; x++) {
            const double sx = (2 * (x + 0.5) / W - 1) * c->tx, sy = (1 - 2 * (y + 0.5) / H) * c->ty;
            double d[3];
            for (int k = 0; k < 3; k++) d[k] = c->fw[k] + sx * c->rt[k] + sy * c->up[k];
            normalize(d);
            double t, u, v;
            int front;
            const int h = sh__intersect(c->s, c->cam->eye, d, INFINITY, &t, &u, &v, &front);
            double val[3] = {0, 0, 0};
            if (h) {
                const int *tc = m->tri + 3 * (h - 1);
                const double w[3] = {1 - u - v, u, v};
                for (int ch = 0; ch < c->nchan; ch++)
                    for (int j = 0; j < 3; j++) val[ch] += w[j] * c->vcol[(size_t)tc[j] * c->nchan + ch];
            } else if (c->bg) {
                double rgb[3];
                const double Y = sh_env_eval(c->bg, d, rgb);
                if (c->nchan == 1) val[0] = Y;
                else memcpy(val, rgb, sizeof rgb);
            }
            for (int ch = 0; ch < c->nchan; ch++) c->out->data[ch * np + (size_t)y * W + x] = (float)val[ch];
        }
    return sh__embree_status(c->s, "casting camera rays");
}

int sh_render(const sh_scene *s, const sh_camera *cam, int nchan, const double *vcol, const sh_env *bg, int threads,
              sh_image *out)
{
    if (!s || !cam || !vcol || !out || (nchan != 1 && nchan != 3)) return sh_error(SH_EINVAL, "sh_render: bad arguments");
    memset(out, 0, sizeof *out);
    if (cam->width < 1 || cam->height < 1 || cam->width > 16384 || cam->height > 16384 || !(cam->fov_deg > 1 && cam->fov_deg < 170))
        return sh_error(SH_EINVAL, "sh_render: bad camera");
    renctx c = {.s = s, .cam = cam, .nchan = nchan, .vcol = vcol, .bg = bg, .out = out};
    for (int k = 0; k < 3; k++) c.fw[k] = cam->target[k] - cam->eye[k];
    normalize(c.fw);
    /* right = fw × up, up' = right × fw */
    c.rt[0] = c.fw[1] * cam->up[2] - c.fw[2] * cam->up[1];
    c.rt[1] = c.fw[2] * cam->up[0] - c.fw[0] * cam->up[2];
    c.rt[2] = c.fw[0] * cam->up[1] - c.fw[1] * cam->up[0];
    normalize(c.rt);
    c.up[0] = c.rt[1] * c.fw[2] - c.rt[2] * c.fw[1];
    c.up[1] = c.rt[2] * c.fw[0] - c.rt[0] * c.fw[2];
    c.up[2] = c.rt[0] * c.fw[1] - c.rt[1] * c.fw[0];
    c.ty = tan(0.5 * cam->fov_deg * M_PI / 180);
    c.tx = c.ty * cam->width / cam->height;
    out->width = cam->width;
    out->height = cam->height;
    out->nchan = nchan;
    static const char *names[3] = {"R", "G", "B"};
    for (int ch = 0; ch < nchan; ch++) snprintf(out->names[ch], sizeof out->names[ch], "%s", nchan == 1 ? "Y" : names[ch]);
    out->data = malloc(sizeof(float) * (size_t)nchan * cam->width * cam->height);
    if (!out->data) return sh_error(SH_ENOMEM, "out of memory");
    int st = sh__parallel_for(threads > 0 ? threads : s->threads, cam->height, 4, render_rows, &c, NULL, NULL, NULL);
    if (st) sh_image_free(out);
    return st;
}

int sh_image_colormap(const sh_image *in, double vmax, sh_image *out)
{
    if (!in || !in->data || in->nchan != 1 || !out || !(vmax > 0) || !isfinite(vmax))
        return sh_error(SH_EINVAL, "sh_image_colormap: need a 1-channel image and vmax > 0");
    const size_t np = (size_t)in->width * in->height;
    memset(out, 0, sizeof *out);
    out->data = malloc(sizeof(float) * 3 * np);
    if (!out->data) return sh_error(SH_ENOMEM, "out of memory");
    out->width = in->width;
    out->height = in->height;
    out->nchan = 3;
    strcpy(out->names[0], "R");
    strcpy(out->names[1], "G");
    strcpy(out->names[2], "B");
    /* black → blue → red → yellow → white at 0, ¼, ½, ¾, 1 */
    static const double key[5][3] = {{0, 0, 0}, {0.1, 0.1, 0.8}, {0.85, 0.1, 0.1}, {1, 0.85, 0}, {1, 1, 1}};
    for (size_t k = 0; k < np; k++) {
        double x = in->data[k] / vmax;
        x = isfinite(x) ? fmin(1.0, fmax(0.0, x)) : 1.0;
        const double f = x * 4;
        int i = (int)f;
        if (i > 3) i = 3;
        const double w = f - i;
        for (int c = 0; c < 3; c++) {
            /* the map is given in display values: linearise for the PNG writer */
            const double srgb = (1 - w) * key[i][c] + w * key[i + 1][c];
            out->data[c * np + k] = (float)(srgb <= 0.04045 ? srgb / 12.92 : pow((srgb + 0.055) / 1.055, 2.4));
        }
    }
    return SH_OK;
}

int sh_png_write(const char *path, const sh_image *img, double exposure)
{
    if (!path || !img || !img->data || (img->nchan != 1 && img->nchan != 3) || img->width < 1 || img->height < 1 ||
        !(exposure > 0) || !isfinite(exposure))
        return sh_error(SH_EINVAL, "sh_png_write: need a 1- or 3-channel image and exposure > 0");
    char *tmp = NULL;
    int st = sh__make_temp_path(path, &tmp);
    if (st) return st;
    FILE *f = sh__temp_fopen(tmp, "wb");
    png_structp png = f ? png_create_write_struct(PNG_LIBPNG_VER_STRING, NULL, NULL, NULL) : NULL;
    png_infop info = png ? png_create_info_struct(png) : NULL;
    const size_t W = (size_t)img->width, np = W * img->height;
    unsigned char *row = malloc(3 * W);
    if (!f || !png || !info || !row) {
        if (png) png_destroy_write_struct(&png, info ? &info : NULL);
        if (f) fclose(f);
        free(row);
        unlink(tmp);
        free(tmp);
        return sh_error(f ? SH_ENOMEM : SH_EIO, "cannot write '%s'", path);
    }
    if (setjmp(png_jmpbuf(png))) {
        png_destroy_write_struct(&png, &info);
        fclose(f);
        free(row);
        unlink(tmp);
        free(tmp);
        return sh_error(SH_EIO, "cannot write '%s': libpng failed", path);
    }
    png_init_io(png, f);
    png_set_IHDR(png, info, img->width, img->height, 8, PNG_COLOR_TYPE_RGB, PNG_INTERLACE_NONE,
                 PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
    png_set_sRGB(png, info, PNG_sRGB_INTENT_PERCEPTUAL);
    png_write_info(png, info);
    for (int y = 0; y < img->height; y++) {
        for (size_t x = 0; x < W; x++)
            for (int c = 0; c < 3; c++) {
                const int ch = img->nchan == 1 ? 0 : c;
                double v = img->data[ch * np + (size_t)y * W + x] * exposure;
                v = isfinite(v) ? fmin(1.0, fmax(0.0, v)) : 1.0;
                v = v <= 0.0031308 ? 12.92 * v : 1.055 * pow(v, 1 / 2.4) - 0.055; /* sRGB */
                row[3 * x + c] = (unsigned char)(255 * v + 0.5);
            }
        png_write_row(png, row);
    }
    png_write_end(png, NULL);
    png_destroy_write_struct(&png, &info);
    free(row);
    if (fclose(f) != 0) {
        unlink(tmp);
        free(tmp);
        return sh_error(SH_EIO, "cannot write '%s'", path);
    }
    st = sh__commit_temp(tmp, path);
    free(tmp);
    return st;
}
