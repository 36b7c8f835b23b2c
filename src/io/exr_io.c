/* exr_io.c — OpenEXR image I/O through OpenEXRCore (the C library of
 * OpenEXR 3.1): read scanline or tiled parts with half, float or uint
 * channels into planar float images, and write float images (ZIP).
 *
 * Reading.  The first non-deep part is read.  Channels are taken by name:
 * R,G,B (A and everything else is ignored) or, failing those, a single Y.
 * Every channel type is converted to float by OpenEXRCore's unpacker
 * (user_data_type = EXR_PIXEL_FLOAT).  OpenEXRCore 3.1 cannot decompress
 * DWAA/DWAB ("not yet implemented"), so those files — recognised from the
 * header's compression attribute, or from EXR_ERR_FEATURE_NOT_IMPLEMENTED
 * during decoding — are read through the C++ library's ImfCRgbaFile C
 * interface instead (exr_rgba_fallback.c).
 *
 * Status mapping: the file cannot be opened → SH_EIO; the header or a chunk
 * is corrupt or missing (truncated file, garbage) → SH_EFORMAT; no R,G,B or
 * Y channel → SH_EFORMAT naming the channels found; sub-sampled channels or
 * deep data → SH_ENOTSUP.
 *
 * Writing.  A temporary file "<path>.tmp.XXXXXX" is created next to the
 * target with mkstemp(), written by OpenEXRCore (one scanline part, FLOAT
 * channels, ZIP compression) and renamed over the target; on any failure it
 * is removed, so a partial file is never left under either name.
 *
 * [1] OpenEXR Core API, openexr_context.h / openexr_decode.h /
 *     openexr_encode.h (OpenEXR 3.1.5).
 */
#include "core/shlab_internal.h"

#include <errno.h>
#include <openexr.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#define TMP_SUFFIX ".tmp.XXXXXX"


void sh_image_free(sh_image *img)
{
    if (!img) return;
    free(img->data);
    img->data = NULL;
    img->width = img->height = img->nchan = 0;
}

/* Last message OpenEXRCore reported on this thread (its default handler
 * would print to stderr, which a library must not do). */
static _Thread_local char core_msg[256];

static void core_error_handler(exr_const_context_t ctxt, exr_result_t code, const char *msg)
{
    (void)ctxt;
    snprintf(core_msg, sizeof core_msg, "%s", msg ? msg : exr_get_default_error_message(code));
}

static const char *core_reason(exr_result_t rv)
{
    return core_msg[0] ? core_msg : exr_get_default_error_message(rv);
}

/* Status for a failed OpenEXRCore read call: I/O failures on a file that
 * exists are still format errors (short reads of a truncated file). */
static int read_status(exr_result_t rv)
{
    if (rv == EXR_ERR_OUT_OF_MEMORY) return SH_ENOMEM;
    return SH_EFORMAT;
}

/* Pick channels: R,G,B (all three) or Y.  src[k] is the index in the
 * channel list of output channel k.  Returns the number of output channels,
 * 0 if none is usable. */
static int pick_channels(const exr_attr_chlist_t *cl, int src[SH_IMAGE_MAX_CHANNELS],
                         char names[SH_IMAGE_MAX_CHANNELS][8])
{
    static const char *const rgb[3] = {"R", "G", "B"};
    int idx[3] = {-1, -1, -1}, y = -1;
    for (int i = 0; i < cl->num_channels; i++) {
        const char *n = cl->entries[i].name.str;
        for (int k = 0; k < 3; k++)
            if (!strcmp(n, rgb[k])) idx[k] = i;
        if (!strcmp(n, "Y")) y = i;
    }
    if (idx[0] >= 0 && idx[1] >= 0 && idx[2] >= 0) {
        for (int k = 0; k < 3; k++) {
            src[k] = idx[k];
            strcpy(names[k], rgb[k]);
        }
        return 3;
    }
    if (y >= 0) {
        src[0] = y;
        strcpy(names[0], "Y");
        return 1;
    }
    return 0;
}

static int no_channel_error(const char *path, const exr_attr_chlist_t *cl)
{
    char list[160] = "";
    size_t used = 0;
    for (int i = 0; i < cl->num_channels && used < sizeof list - 1; i++) {
        int w = snprintf(list + used, sizeof list - used, "%s%s", i ? ", " : "",
                         cl->entries[i].name.str);
        if (w < 0) break;
        used += (size_t)w;
        if (used >= sizeof list) { used = sizeof list - 1; break; }
    }
    return sh_error(SH_EFORMAT, "%s: no usable channel (need R,G,B or Y; found %s)", path,
                    cl->num_channels ? list : "none");
}

/* Decode one chunk into the planar float image at (x0, y0) (data-window
 * relative).  `dec` is initialised on first use (*inited = 0 → 1). */
static exr_result_t decode_chunk(exr_context_t ctxt, int part, const exr_chunk_info_t *ci,
                                 exr_decode_pipeline_t *dec, int *inited, sh_image *img,
                                 const int *src, int x0, int y0)
{
    exr_result_t rv;
    if (!*inited) {
        rv = exr_decoding_initialize(ctxt, part, ci, dec);
        if (rv != EXR_ERR_SUCCESS) return rv;
        *inited = 1;
    } else {
        rv = exr_decoding_update(ctxt, part, ci, dec);
        if (rv != EXR_ERR_SUCCESS) return rv;
    }
    const size_t plane = (size_t)img->width * img->height;
    for (int c = 0; c < dec->channel_count; c++) dec->channels[c].decode_to_ptr = NULL;
    for (int k = 0; k < img->nchan; k++) {
        /* channels in the pipeline are in the header's (sorted) order */
        exr_coding_channel_info_t *ch = &dec->channels[src[k]];
        ch->user_bytes_per_element = 4;
        ch->user_data_type = EXR_PIXEL_FLOAT;
        ch->user_pixel_stride = 4;
        ch->user_line_stride = 4 * img->width;
        ch->decode_to_ptr =
            (uint8_t *)(img->data + k * plane + (size_t)y0 * img->width + x0);
    }
    rv = exr_decoding_choose_default_routines(ctxt, part, dec);
    if (rv != EXR_ERR_SUCCESS) return rv;
    return exr_decoding_run(ctxt, part, dec);
}

int sh_exr_read(const char *path, sh_image *img, int *used_fallback)
{
    if (used_fallback) *used_fallback = 0;
    if (!img) return sh_error(SH_EINVAL, "sh_exr_read: image is NULL");
    memset(img, 0, sizeof *img);
    if (!path || !*path) return sh_error(SH_EINVAL, "sh_exr_read: empty path");

    FILE *probe = fopen(path, "rb");
    if (!probe) return sh_error(SH_EIO, "cannot open '%s': %s", path, strerror(errno));
    fclose(probe);

    exr_context_initializer_t init = EXR_DEFAULT_CONTEXT_INITIALIZER;
    init.error_handler_fn = core_error_handler;
    init.flags = EXR_CONTEXT_FLAG_DISABLE_CHUNK_RECONSTRUCTION;
    exr_context_t ctxt = NULL;
    core_msg[0] = '\0';
    exr_result_t rv = exr_start_read(&ctxt, path, &init);
    if (rv != EXR_ERR_SUCCESS) {
        exr_finish(&ctxt);
        if (rv == EXR_ERR_FILE_ACCESS)
            return sh_error(SH_EIO, "cannot read '%s': %s", path, core_reason(rv));
        return sh_error(read_status(rv), "%s: not a readable OpenEXR file (%s)", path,
                        core_reason(rv));
    }

    int st = SH_OK;
    int nparts = 0, part = -1;
    exr_storage_t storage = EXR_STORAGE_SCANLINE;
    exr_get_count(ctxt, &nparts);
    for (int p = 0; p < nparts; p++) {
        if (exr_get_storage(ctxt, p, &storage) == EXR_ERR_SUCCESS &&
            (storage == EXR_STORAGE_SCANLINE || storage == EXR_STORAGE_TILED)) {
            part = p;
            break;
        }
    }
    const exr_attr_chlist_t *cl = NULL;
    exr_attr_box2i_t dw;
    exr_compression_t comp = EXR_COMPRESSION_NONE;
    int src[SH_IMAGE_MAX_CHANNELS];
    exr_decode_pipeline_t dec;
    memset(&dec, 0, sizeof dec);
    int dec_inited = 0;

    if (part < 0) {
        st = sh_error(SH_ENOTSUP, "%s: no flat (non-deep) image part", path);
        goto done;
    }
    if (exr_get_channels(ctxt, part, &cl) != EXR_ERR_SUCCESS || !cl ||
        exr_get_data_window(ctxt, part, &dw) != EXR_ERR_SUCCESS ||
        exr_get_compression(ctxt, part, &comp) != EXR_ERR_SUCCESS) {
        st = sh_error(SH_EFORMAT, "%s: header lacks channels, dataWindow or compression", path);
        goto done;
    }
    img->nchan = pick_channels(cl, src, img->names);
    if (img->nchan == 0) {
        st = no_channel_error(path, cl);
        goto done;
    }
    for (int k = 0; k < img->nchan; k++) {
        const exr_attr_chlist_entry_t *e = &cl->entries[src[k]];
        if (e->x_sampling != 1 || e->y_sampling != 1) {
            st = sh_error(SH_ENOTSUP, "%s: channel %s is sub-sampled (%d×%d)", path,
                          e->name.str, e->x_sampling, e->y_sampling);
            goto done;
        }
    }
    if (comp == EXR_COMPRESSION_DWAA || comp == EXR_COMPRESSION_DWAB) {
        exr_finish(&ctxt);
        st = sh_exr_read_rgba(path, img);
        if (st == SH_OK && used_fallback) *used_fallback = 1;
        return st;
    }
    {
        const int64_t w = (int64_t)dw.max.x - dw.min.x + 1, h = (int64_t)dw.max.y - dw.min.y + 1;
        if (w < 1 || h < 1 || w > (1 << 24) || h > (1 << 24) || w * h > SH_IMAGE_MAX_PIXELS) {
            st = sh_error(SH_EFORMAT, "%s: unusable data window %lld×%lld", path, (long long)w,
                          (long long)h);
            goto done;
        }
        img->width = (int)w;
        img->height = (int)h;
    }
    img->data = calloc((size_t)img->width * img->height * img->nchan, sizeof(float));
    if (!img->data) {
        st = sh_error(SH_ENOMEM, "%s: cannot allocate %d×%d×%d floats", path, img->width,
                      img->height, img->nchan);
        goto done;
    }

    if (storage == EXR_STORAGE_SCANLINE) {
        int32_t spc = 0;
        if (exr_get_scanlines_per_chunk(ctxt, part, &spc) != EXR_ERR_SUCCESS || spc < 1) {
            st = sh_error(SH_EFORMAT, "%s: bad scanlines per chunk", path);
            goto done;
        }
        for (int64_t y = dw.min.y; y <= dw.max.y; y += spc) {
            exr_chunk_info_t ci;
            rv = exr_read_scanline_chunk_info(ctxt, part, (int)y, &ci);
            if (rv == EXR_ERR_SUCCESS) {
                /* the chunk starts at ci.start_y, which is y rounded to a chunk boundary */
                const int y0 = ci.start_y - dw.min.y;
                if (y0 < 0 || y0 + ci.height > img->height || ci.width != img->width) {
                    st = sh_error(SH_EFORMAT, "%s: chunk at line %d does not fit the data window",
                                  path, (int)y);
                    goto done;
                }
                rv = decode_chunk(ctxt, part, &ci, &dec, &dec_inited, img, src, 0, y0);
            }
            if (rv != EXR_ERR_SUCCESS) goto decode_failed;
        }
    } else {
        uint32_t tw = 0, th = 0;
        exr_tile_level_mode_t lm;
        exr_tile_round_mode_t rm;
        if (exr_get_tile_descriptor(ctxt, part, &tw, &th, &lm, &rm) != EXR_ERR_SUCCESS ||
            tw < 1 || th < 1) {
            st = sh_error(SH_EFORMAT, "%s: bad tile description", path);
            goto done;
        }
        const int ntx = (int)((img->width + (int64_t)tw - 1) / tw);
        const int nty = (int)((img->height + (int64_t)th - 1) / th);
        for (int ty = 0; ty < nty; ty++)
            for (int tx = 0; tx < ntx; tx++) {
                exr_chunk_info_t ci;
                rv = exr_read_tile_chunk_info(ctxt, part, tx, ty, 0, 0, &ci);
                if (rv == EXR_ERR_SUCCESS) {
                    const int x0 = tx * (int)tw, y0 = ty * (int)th;
                    if (x0 + ci.width > img->width || y0 + ci.height > img->height) {
                        st = sh_error(SH_EFORMAT, "%s: tile (%d,%d) does not fit the data window",
                                      path, tx, ty);
                        goto done;
                    }
                    rv = decode_chunk(ctxt, part, &ci, &dec, &dec_inited, img, src, x0, y0);
                }
                if (rv != EXR_ERR_SUCCESS) goto decode_failed;
            }
    }
    goto done;

decode_failed:
    if (rv == EXR_ERR_FEATURE_NOT_IMPLEMENTED) {
        /* a compression OpenEXRCore cannot decode: try the C++ library */
        if (dec_inited) exr_decoding_destroy(ctxt, &dec);
        exr_finish(&ctxt);
        sh_image_free(img);
        st = sh_exr_read_rgba(path, img);
        if (st == SH_OK && used_fallback) *used_fallback = 1;
        return st;
    }
    st = sh_error(read_status(rv), "%s: corrupt or truncated pixel data (%s)", path,
                  core_reason(rv));

done:
    if (dec_inited) exr_decoding_destroy(ctxt, &dec);
    exr_finish(&ctxt);
    if (st != SH_OK) {
        sh_image_free(img);
        memset(img, 0, sizeof *img);
    }
    return st;
}

/* ------------------------------------------------------------- writing */

static int check_image(const sh_image *img, const char *who)
{
    if (!img || !img->data) return sh_error(SH_EINVAL, "%s: image is empty", who);
    if (img->width < 1 || img->height < 1)
        return sh_error(SH_EINVAL, "%s: image size %d×%d", who, img->width, img->height);
    if (img->nchan < 1 || img->nchan > SH_IMAGE_MAX_CHANNELS)
        return sh_error(SH_EINVAL, "%s: %d channels (1..%d)", who, img->nchan,
                        SH_IMAGE_MAX_CHANNELS);
    for (int k = 0; k < img->nchan; k++) {
        if (!img->names[k][0] || memchr(img->names[k], '\0', 8) == NULL)
            return sh_error(SH_EINVAL, "%s: channel %d has no name", who, k);
        for (int j = 0; j < k; j++)
            if (!strcmp(img->names[j], img->names[k]))
                return sh_error(SH_EINVAL, "%s: channel name %s repeated", who, img->names[k]);
    }
    return SH_OK;
}

int sh__make_temp_path(const char *path, char **tmp_out)
{
    /* The file really written is the link's target when path is a symbolic
     * link (the link stays a link), and an existing target must be a regular
     * file: renaming over /dev/null or a FIFO would replace the node itself. */
    struct stat sb;
    char *target = NULL;
    if (lstat(path, &sb) == 0 && S_ISLNK(sb.st_mode)) {
        target = realpath(path, NULL);
        if (!target) return sh_error(SH_EIO, "cannot write '%s': it is a symbolic link to nowhere", path);
    } else {
        target = strdup(path);
        if (!target) return sh_error(SH_ENOMEM, "out of memory");
    }
    if (stat(target, &sb) == 0 && !S_ISREG(sb.st_mode)) {
        free(target);
        return sh_error(SH_EIO, "cannot write '%s': not a regular file", path);
    }
    const size_t n = strlen(target) + 16;
    char *tmp = malloc(n);
    if (!tmp) {
        free(target);
        return sh_error(SH_ENOMEM, "out of memory");
    }
    snprintf(tmp, n, "%s" TMP_SUFFIX, target);
    free(target);
    int fd = mkstemp(tmp);
    if (fd < 0) {
        int e = errno;
        free(tmp);
        return sh_error(SH_EIO, "cannot write '%s': %s", path, strerror(e));
    }
    close(fd);
    *tmp_out = tmp;
    return SH_OK;
}

int sh__commit_temp(const char *tmp, const char *path)
{
    /* the target is the temporary name without its suffix (see above) */
    const size_t n = strlen(tmp) - (sizeof TMP_SUFFIX - 1);
    char *target = strndup(tmp, n);
    if (!target) {
        unlink(tmp);
        return sh_error(SH_ENOMEM, "out of memory");
    }
    /* mkstemp makes the file 0600; give it the usual 0666 & ~umask */
    mode_t um = umask(0);
    umask(um);
    chmod(tmp, 0666 & ~um);
    int rc = rename(tmp, target);
    int e = errno;
    free(target);
    if (rc != 0) {
        unlink(tmp);
        return sh_error(SH_EIO, "cannot write '%s': %s", path, strerror(e));
    }
    return SH_OK;
}

int sh_exr_write(const char *path, const sh_image *img)
{
    int st = check_image(img, "sh_exr_write");
    if (st) return st;
    if (!path || !*path) return sh_error(SH_EINVAL, "sh_exr_write: empty path");
    char *tmp = NULL;
    if ((st = sh__make_temp_path(path, &tmp))) return st;

    exr_context_initializer_t init = EXR_DEFAULT_CONTEXT_INITIALIZER;
    init.error_handler_fn = core_error_handler;
    exr_context_t ctxt = NULL;
    exr_encode_pipeline_t enc;
    memset(&enc, 0, sizeof enc);
    int enc_inited = 0, part = 0;
    const size_t plane = (size_t)img->width * img->height;
    core_msg[0] = '\0';

    exr_result_t rv = exr_start_write(&ctxt, tmp, EXR_WRITE_FILE_DIRECTLY, &init);
    if (rv == EXR_ERR_SUCCESS) rv = exr_add_part(ctxt, "shlab", EXR_STORAGE_SCANLINE, &part);
    if (rv == EXR_ERR_SUCCESS)
        rv = exr_initialize_required_attr_simple(ctxt, part, img->width, img->height,
                                                 EXR_COMPRESSION_ZIP);
    for (int k = 0; k < img->nchan && rv == EXR_ERR_SUCCESS; k++)
        rv = exr_add_channel(ctxt, part, img->names[k], EXR_PIXEL_FLOAT,
                             EXR_PERCEPTUALLY_LOGARITHMIC, 1, 1);
    if (rv == EXR_ERR_SUCCESS) rv = exr_write_header(ctxt);
    int32_t spc = 1;
    if (rv == EXR_ERR_SUCCESS) rv = exr_get_scanlines_per_chunk(ctxt, part, &spc);
    for (int y = 0; rv == EXR_ERR_SUCCESS && y < img->height; y += spc) {
        exr_chunk_info_t ci;
        rv = exr_write_scanline_chunk_info(ctxt, part, y, &ci);
        if (rv != EXR_ERR_SUCCESS) break;
        rv = enc_inited ? exr_encoding_update(ctxt, part, &ci, &enc)
                        : exr_encoding_initialize(ctxt, part, &ci, &enc);
        if (rv != EXR_ERR_SUCCESS) break;
        enc_inited = 1;
        /* the pipeline lists channels in header (sorted) order: match by name */
        for (int c = 0; c < enc.channel_count; c++) {
            exr_coding_channel_info_t *ch = &enc.channels[c];
            int k = 0;
            while (k < img->nchan && strcmp(img->names[k], ch->channel_name)) k++;
            if (k == img->nchan) { rv = EXR_ERR_INVALID_ARGUMENT; break; }
            ch->user_bytes_per_element = 4;
            ch->user_data_type = EXR_PIXEL_FLOAT;
            ch->user_pixel_stride = 4;
            ch->user_line_stride = 4 * img->width;
            ch->encode_from_ptr = (const uint8_t *)(img->data + k * plane +
                                                    (size_t)(ci.start_y) * img->width);
        }
        if (rv != EXR_ERR_SUCCESS) break;
        rv = exr_encoding_choose_default_routines(ctxt, part, &enc);
        if (rv == EXR_ERR_SUCCESS) rv = exr_encoding_run(ctxt, part, &enc);
    }
    if (enc_inited) exr_encoding_destroy(ctxt, &enc);
    exr_result_t frv = exr_finish(&ctxt);
    if (rv == EXR_ERR_SUCCESS) rv = frv;
    if (rv != EXR_ERR_SUCCESS) {
        unlink(tmp);
        free(tmp);
        return sh_error(rv == EXR_ERR_OUT_OF_MEMORY ? SH_ENOMEM : SH_EIO,
                        "cannot write '%s': %s", path, core_reason(rv));
    }
    st = sh__commit_temp(tmp, path);
    free(tmp);
    return st;
}
