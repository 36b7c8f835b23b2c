/* exr_io.c — OpenEXR image I/O through OpenEXRCore (the C library of
 * OpenEXR 3.1): read scanline or tiled parts with half, float or uint
 * channels into planar float images, and write float images (ZIP).
 *
 * Reading.  Everything goes through sh_exr_read_mem (sh_exr_read reads the
 * file into memory first), with explicit limits (sh_exr_limits).  The first
 * non-deep part is read.  Channels are taken by name: R,G,B (A and
 * everything else is ignored) or, failing those, a single Y.
 *
 * Before a pixel is decoded or the image allocated, the header and the chunk
 * table are checked against the data: the offset table and every chunk of
 * level 0 must lie inside the data (a 2 KB file cannot describe 32768×32768
 * pixels in 8-byte chunks), the declared uncompressed size may exceed the
 * data's size at most max_ratio times, and the image plus the decoding
 * buffers must fit in max_bytes.  OpenEXRCore's own allocations go through a
 * budget allocator that refuses what would exceed max_bytes, so no header
 * reaches a multi-gigabyte malloc.
 *
 * Decoding.  Every channel of the part, used or not, is decoded to FLOAT into
 * a per-chunk scratch buffer (OpenEXRCore converts half and uint), and the
 * used channels are copied into the image.  OpenEXRCore 3.1.5 documents that a
 * channel whose decode_to_ptr is NULL is skipped, but its specialised
 * unpackers for parts of 3 or 4 half channels (chosen when every channel with
 * a destination is half with the same output layout) convert every channel,
 * writing through the NULL pointer: half RGBA, BGRZ or A/Y/Z files crashed in
 * exr_decoding_run.  Giving every channel a destination avoids that path's
 * fault for every layout (tests/io/test_exr_layouts.c reads every compression ×
 * pixel type × channel layout × scanline/tiled that OpenEXR writes).
 * OpenEXRCore 3.1 cannot decompress DWAA/DWAB ("not yet implemented"), so
 * those files — recognised from the header's compression attribute, or from
 * EXR_ERR_FEATURE_NOT_IMPLEMENTED during decoding — are decoded by the C++
 * library from the same memory, after the same checks (exr_cxx.cpp).
 *
 * Status mapping: the file cannot be opened → SH_EIO; the header or a chunk
 * is corrupt or missing (truncated file, garbage) → SH_EFORMAT; no R,G,B or
 * Y channel → SH_EFORMAT naming the channels found; a limit exceeded →
 * SH_ENOMEM (memory) or SH_EFORMAT (sizes the data cannot hold);
 * sub-sampled channels or deep data → SH_ENOTSUP.
 *
 * Writing.  A temporary file "<path>.tmp.XXXXXX" is created next to the
 * target (tempfile.c), written by OpenEXRCore (one scanline part, FLOAT
 * channels, ZIP compression) and renamed over the target; on any failure it
 * is removed, so a partial file is never left under either name.
 *
 * [1] OpenEXR Core API, openexr_context.h / openexr_decode.h /
 *     openexr_coding.h / openexr_encode.h (OpenEXR 3.1.5).
 * [2] OpenEXR file layout: magic 76 2f 31 01, version, header, offset table
 *     (one uint64 per chunk), chunks (scanline: y, size; tile: x, y, level
 *     x, level y, size; multi-part files add a part number).
 */
#include "core/shlab_internal.h"
#include "io/exr_internal.h"

#include <errno.h>
#include <fcntl.h>
#include <openexr.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>


void sh_image_free(sh_image *img)
{
    if (!img) return;
    free(img->data);
    img->data = NULL;
    img->width = img->height = img->nchan = 0;
}

void sh_exr_limits_default(sh_exr_limits *lim)
{
    const long pages = sysconf(_SC_PHYS_PAGES), psize = sysconf(_SC_PAGESIZE);
    lim->max_pixels = SH_IMAGE_MAX_PIXELS;
    lim->max_bytes = pages > 0 && psize > 0 ? (long long)pages * psize : 1LL << 34;
    lim->max_channels = 1024;
    lim->max_ratio = 65536.0;
}

/* "12.9 GB" */
static const char *human(char buf[32], double bytes)
{
    static const char *const unit[] = {"bytes", "kB", "MB", "GB", "TB", "PB"};
    int u = 0;
    while (bytes >= 1000.0 && u < 5) { bytes /= 1000.0; u++; }
    snprintf(buf, 32, u ? "%.1f %s" : "%.0f %s", bytes, unit[u]);
    return buf;
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

/* Status for a failed OpenEXRCore read call: I/O failures on data that
 * exists are format errors (short reads of a truncated file). */
static int read_status(exr_result_t rv)
{
    if (rv == EXR_ERR_OUT_OF_MEMORY) return SH_ENOMEM;
    return SH_EFORMAT;
}

/* ---- reading from memory -------------------------------------------- */
/* One read: the data (OpenEXRCore's read callbacks get it as user_data)
 * and the memory the read may still use (lim->max_bytes at its start,
 * less the image, the scratch and what OpenEXRCore holds). */
typedef struct {
    const unsigned char *data;
    size_t size;
    long long budget_left;
} mem_src;

/* ---- OpenEXRCore's allocations, within the read's budget ---------------
 * Each block carries its size in a 16-byte prefix (keeping malloc's
 * alignment).  A refused allocation is EXR_ERR_OUT_OF_MEMORY to the
 * library.  OpenEXRCore 3.1 calls the allocator with the size alone
 * (exr_memory_allocation_func_t, openexr_base.h: no context argument), so
 * the allocator finds the read it serves through budget_read: the read in
 * progress on this thread (set by read_mem for its duration, NULL
 * otherwise: then no budget applies). */
static _Thread_local mem_src *budget_read;

static void *budget_alloc(size_t n)
{
    mem_src *r = budget_read;
    if (n > (size_t)1 << 60 || (r && (long long)n > r->budget_left)) return NULL;
    unsigned char *p = malloc(n + 16);
    if (!p) return NULL;
    memcpy(p, &n, sizeof n);
    if (r) r->budget_left -= (long long)n;
    return p + 16;
}

static void budget_free(void *q)
{
    if (!q) return;
    unsigned char *p = (unsigned char *)q - 16;
    size_t n;
    memcpy(&n, p, sizeof n);
    if (budget_read) budget_read->budget_left += (long long)n;
    free(p);
}

static int64_t mem_read(exr_const_context_t ctxt, void *ud, void *buf, uint64_t sz, uint64_t off,
                        exr_stream_error_func_ptr_t err)
{
    (void)ctxt;
    (void)err;
    const mem_src *m = ud;
    if (off >= m->size) return 0;
    const uint64_t n = sz < m->size - off ? sz : m->size - off;
    memcpy(buf, m->data + off, (size_t)n);
    return (int64_t)n;
}

static int64_t mem_size(exr_const_context_t ctxt, void *ud)
{
    (void)ctxt;
    return (int64_t)((const mem_src *)ud)->size;
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
        if (!n) continue;
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

static int no_channel_error(const char *name, const exr_attr_chlist_t *cl)
{
    char list[160] = "";
    size_t used = 0;
    for (int i = 0; i < cl->num_channels && used < sizeof list - 1; i++) {
        int w = snprintf(list + used, sizeof list - used, "%s%.40s", i ? ", " : "",
                         cl->entries[i].name.str ? cl->entries[i].name.str : "?");
        if (w < 0) break;
        used += (size_t)w;
        if (used >= sizeof list) { used = sizeof list - 1; break; }
    }
    return sh_error(SH_EFORMAT, "%s: no usable channel (need R,G,B or Y; found %s)", name,
                    cl->num_channels ? list : "none");
}

/* What is known about the part after the header and chunk table checks. */
typedef struct {
    exr_context_t ctxt;
    int part;
    exr_storage_t storage;
    exr_compression_t comp;
    exr_attr_box2i_t dw;
    int64_t w, h;
    int nch;                 /* channels in the part */
    int spc;                 /* scanlines per chunk (scanline parts) */
    int64_t tw, th, ntx, nty;/* tile size and level-0 tile counts (tiled parts) */
    int64_t nchunks;         /* level-0 chunks */
    int64_t max_chunk_px;    /* largest chunk, in pixels */
} part_info;

/* Chunk k of level 0 (scanline: the k-th block of lines; tiled: row-major
 * tile k) and where it belongs in the data window. */
static exr_result_t chunk_at(const part_info *pi, int64_t k, exr_chunk_info_t *ci, int64_t *x0,
                             int64_t *y0, int64_t *cw, int64_t *chh)
{
    if (pi->storage == EXR_STORAGE_SCANLINE) {
        *x0 = 0;
        *y0 = k * pi->spc;
        *cw = pi->w;
        *chh = pi->h - *y0 < pi->spc ? pi->h - *y0 : pi->spc;
        return exr_read_scanline_chunk_info(pi->ctxt, pi->part, (int)(pi->dw.min.y + *y0), ci);
    }
    const int64_t tx = k % pi->ntx, ty = k / pi->ntx;
    *x0 = tx * pi->tw;
    *y0 = ty * pi->th;
    *cw = pi->w - *x0 < pi->tw ? pi->w - *x0 : pi->tw;
    *chh = pi->h - *y0 < pi->th ? pi->h - *y0 : pi->th;
    return exr_read_tile_chunk_info(pi->ctxt, pi->part, (int)tx, (int)ty, 0, 0, ci);
}

/* A DWAA/DWAB chunk, before it reaches the C++ library: it starts with
 * eleven little-endian uint64 counters (version, unknown uncompressed and
 * compressed size, AC / DC / RLE compressed size, RLE uncompressed and raw
 * size, AC and DC coefficient counts, AC compression), from which OpenEXR
 * 3.1.5 sizes its buffers.  A damaged counter made it allocate gigabytes
 * for a 12×10 image (found by fuzzing).  Every counter is bounded by what
 * the chunk can hold: byte sizes by its uncompressed size, coefficient
 * counts by 8×8 blocks of every channel, compressed sizes by its data. */
static int check_dwa_leader(const exr_chunk_info_t *ci, int64_t cw, int64_t chh, int nch,
                            const unsigned char *data, const char *name, int64_t k)
{
    if (ci->packed_size >= ci->unpacked_size) return SH_OK; /* stored uncompressed */
    uint64_t c[11];
    if (ci->packed_size < sizeof c)
        return sh_error(SH_EFORMAT, "%s: DWA chunk %lld is shorter than its header", name, (long long)k);
    for (int i = 0; i < 11; i++) {
        c[i] = 0;
        for (int b = 7; b >= 0; b--) c[i] = c[i] << 8 | data[ci->data_offset + 8 * (size_t)i + (size_t)b];
    }
    const uint64_t raw = ci->unpacked_size, body = ci->packed_size - sizeof c;
    const uint64_t blocks = (uint64_t)nch * (uint64_t)((cw + 7) / 8) * (uint64_t)((chh + 7) / 8);
    if (c[0] > 2 || c[1] > raw || c[6] > raw || c[7] > raw || c[8] > 63 * blocks || c[9] > blocks ||
        c[10] > 1 || c[2] > body || c[3] > body || c[4] > body || c[5] > body ||
        c[2] + c[3] + c[4] + c[5] > body)
        return sh_error(SH_EFORMAT, "%s: DWA chunk %lld has a corrupt header (sizes beyond the "
                        "chunk's %llu bytes)", name, (long long)k, (unsigned long long)raw);
    return SH_OK;
}

/* Check the chunk table against the data before anything is allocated:
 * every level-0 chunk must be where the header says, of the size it says,
 * and inside the data. */
static int check_chunks(const part_info *pi, const char *name, const unsigned char *data, size_t size,
                        const sh_exr_limits *lim, int64_t *raw_total, int64_t *max_unpacked)
{
    const int dwa = pi->comp == EXR_COMPRESSION_DWAA || pi->comp == EXR_COMPRESSION_DWAB;
    *raw_total = 0;
    *max_unpacked = 0;
    for (int64_t k = 0; k < pi->nchunks; k++) {
        exr_chunk_info_t ci;
        int64_t x0, y0, cw, chh;
        core_msg[0] = '\0';
        exr_result_t rv = chunk_at(pi, k, &ci, &x0, &y0, &cw, &chh);
        if (rv != EXR_ERR_SUCCESS)
            return sh_error(read_status(rv), "%s: chunk %lld of %lld is missing or corrupt (%s)", name,
                            (long long)k, (long long)pi->nchunks, core_reason(rv));
        if (ci.width != cw || ci.height != chh)
            return sh_error(SH_EFORMAT, "%s: chunk %lld is %d×%d pixels, expected %lld×%lld", name,
                            (long long)k, ci.width, ci.height, (long long)cw, (long long)chh);
        if (ci.data_offset < 8 || ci.data_offset > size || ci.packed_size > size - ci.data_offset ||
            (ci.packed_size == 0 && ci.unpacked_size > 0))
            return sh_error(SH_EFORMAT,
                            "%s: chunk %lld (%llu bytes at offset %llu) lies outside the %zu bytes of "
                            "data", name, (long long)k, (unsigned long long)ci.packed_size,
                            (unsigned long long)ci.data_offset, size);
        /* at most 4 bytes per sample of every channel */
        if (ci.unpacked_size > (uint64_t)cw * (uint64_t)chh * 4u * (uint64_t)pi->nch)
            return sh_error(SH_EFORMAT, "%s: chunk %lld claims %llu uncompressed bytes for %lld×%lld "
                            "pixels of %d channels", name, (long long)k,
                            (unsigned long long)ci.unpacked_size, (long long)cw, (long long)chh, pi->nch);
        int st;
        if (dwa && (st = check_dwa_leader(&ci, cw, chh, pi->nch, data, name, k))) return st;
        *raw_total += (int64_t)ci.unpacked_size;
        if ((int64_t)ci.unpacked_size > *max_unpacked) *max_unpacked = (int64_t)ci.unpacked_size;
    }
    if ((double)*raw_total > lim->max_ratio * (double)size) {
        char a[32], b[32];
        return sh_error(SH_EFORMAT,
                        "%s: %lld×%lld pixels of %d channels (%s uncompressed) cannot come from %s of "
                        "data (more than %.0f:1 compression)", name, (long long)pi->w, (long long)pi->h,
                        pi->nch, human(a, (double)*raw_total), human(b, (double)size), lim->max_ratio);
    }
    return SH_OK;
}

/* Decode every level-0 chunk with OpenEXRCore: all channels to FLOAT into
 * `scratch` (see the top of this file), then the used ones into img. */
static exr_result_t decode_core(const part_info *pi, const int *src, float *scratch, sh_image *img,
                                const char *name, int *st)
{
    exr_decode_pipeline_t dec;
    memset(&dec, 0, sizeof dec);
    int inited = 0;
    exr_result_t rv = EXR_ERR_SUCCESS;
    const size_t plane = (size_t)img->width * (size_t)img->height;
    for (int64_t k = 0; k < pi->nchunks && rv == EXR_ERR_SUCCESS; k++) {
        exr_chunk_info_t ci;
        int64_t x0, y0, cw, chh;
        core_msg[0] = '\0';
        if ((rv = chunk_at(pi, k, &ci, &x0, &y0, &cw, &chh)) != EXR_ERR_SUCCESS) break;
        if (ci.width != cw || ci.height != chh) { rv = EXR_ERR_CORRUPT_CHUNK; break; }
        rv = inited ? exr_decoding_update(pi->ctxt, pi->part, &ci, &dec)
                    : exr_decoding_initialize(pi->ctxt, pi->part, &ci, &dec);
        if (rv != EXR_ERR_SUCCESS) break;
        inited = 1;
        if (dec.channel_count != pi->nch) { rv = EXR_ERR_CORRUPT_CHUNK; break; }
        /* one plane per channel, each at most the chunk's size */
        size_t off = 0;
        for (int c = 0; c < dec.channel_count; c++) {
            exr_coding_channel_info_t *ch = &dec.channels[c];
            if (ch->width < 0 || ch->height < 0 || ch->width > cw || ch->height > chh) {
                rv = EXR_ERR_CORRUPT_CHUNK;
                break;
            }
            ch->user_bytes_per_element = 4;
            ch->user_data_type = EXR_PIXEL_FLOAT;
            ch->user_pixel_stride = 4;
            ch->user_line_stride = 4 * (ch->width > 0 ? ch->width : 1);
            ch->decode_to_ptr = (uint8_t *)(scratch + off);
            off += (size_t)ch->width * (size_t)ch->height;
        }
        if (rv != EXR_ERR_SUCCESS) break;
        rv = exr_decoding_choose_default_routines(pi->ctxt, pi->part, &dec);
        if (rv == EXR_ERR_SUCCESS) rv = exr_decoding_run(pi->ctxt, pi->part, &dec);
        if (rv != EXR_ERR_SUCCESS) break;
        /* the used channels (full resolution, checked before) into the image */
        for (int kk = 0; kk < img->nchan && rv == EXR_ERR_SUCCESS; kk++) {
            if (dec.channels[src[kk]].width != cw || dec.channels[src[kk]].height != chh) {
                rv = EXR_ERR_CORRUPT_CHUNK;
                break;
            }
            size_t o = 0;
            for (int c = 0; c < src[kk]; c++)
                o += (size_t)dec.channels[c].width * (size_t)dec.channels[c].height;
            const float *from = scratch + o;
            float *to = img->data + kk * plane + (size_t)y0 * img->width + (size_t)x0;
            for (int64_t y = 0; y < chh; y++)
                memcpy(to + (size_t)y * img->width, from + (size_t)y * cw, sizeof(float) * (size_t)cw);
        }
    }
    if (inited) exr_decoding_destroy(pi->ctxt, &dec);
    if (rv != EXR_ERR_SUCCESS && rv != EXR_ERR_FEATURE_NOT_IMPLEMENTED)
        *st = sh_error(read_status(rv), "%s: corrupt or truncated pixel data (%s)", name,
                       core_reason(rv));
    return rv;
}

/* An OpenEXRCore context reading m (errors to core_msg, allocations within
 * m's budget, no chunk table reconstruction) into pi->ctxt. */
static int start_read(mem_src *m, const char *name, part_info *pi)
{
    exr_context_initializer_t init = EXR_DEFAULT_CONTEXT_INITIALIZER;
    init.error_handler_fn = core_error_handler;
    init.alloc_fn = budget_alloc;
    init.free_fn = budget_free;
    init.user_data = m;
    init.read_fn = mem_read;
    init.size_fn = mem_size;
    init.flags = EXR_CONTEXT_FLAG_DISABLE_CHUNK_RECONSTRUCTION;
    core_msg[0] = '\0';
    const exr_result_t rv = exr_start_read(&pi->ctxt, name, &init);
    if (rv != EXR_ERR_SUCCESS)
        return sh_error(read_status(rv), "%s: not a readable OpenEXR file (%s)", name, core_reason(rv));
    return SH_OK;
}

/* The first flat (scanline or tiled, not deep) part: pi->part, pi->storage. */
static int find_flat_part(part_info *pi, const char *name)
{
    int nparts = 0;
    exr_get_count(pi->ctxt, &nparts);
    for (int p = 0; p < nparts; p++) {
        exr_storage_t s;
        if (exr_get_storage(pi->ctxt, p, &s) == EXR_ERR_SUCCESS &&
            (s == EXR_STORAGE_SCANLINE || s == EXR_STORAGE_TILED)) {
            pi->part = p;
            pi->storage = s;
            break;
        }
    }
    if (pi->part < 0) return sh_error(SH_ENOTSUP, "%s: no flat (non-deep) image part", name);
    return SH_OK;
}

/* The part's header: channels (*cl; the used ones picked into img->nchan,
 * img->names and src, none sub-sampled), data window and compression, and
 * the image size within the limits. */
static int read_header(part_info *pi, const char *name, const sh_exr_limits *lim, sh_image *img,
                       int src[SH_IMAGE_MAX_CHANNELS], const exr_attr_chlist_t **cl)
{
    if (exr_get_channels(pi->ctxt, pi->part, cl) != EXR_ERR_SUCCESS || !*cl ||
        exr_get_data_window(pi->ctxt, pi->part, &pi->dw) != EXR_ERR_SUCCESS ||
        exr_get_compression(pi->ctxt, pi->part, &pi->comp) != EXR_ERR_SUCCESS)
        return sh_error(SH_EFORMAT, "%s: header lacks channels, dataWindow or compression", name);
    pi->nch = (*cl)->num_channels;
    if (pi->nch < 1 || pi->nch > lim->max_channels)
        return sh_error(SH_EFORMAT, "%s: %d channels (1 to %d are read)", name, pi->nch,
                        lim->max_channels);
    img->nchan = pick_channels(*cl, src, img->names);
    if (img->nchan == 0) return no_channel_error(name, *cl);
    for (int k = 0; k < img->nchan; k++) {
        const exr_attr_chlist_entry_t *e = &(*cl)->entries[src[k]];
        if (e->x_sampling != 1 || e->y_sampling != 1)
            return sh_error(SH_ENOTSUP, "%s: channel %s is sub-sampled (%d×%d)", name, e->name.str,
                            e->x_sampling, e->y_sampling);
    }
    pi->w = (int64_t)pi->dw.max.x - pi->dw.min.x + 1;
    pi->h = (int64_t)pi->dw.max.y - pi->dw.min.y + 1;
    if (pi->w < 1 || pi->h < 1 || pi->w > INT32_MAX / 4 || pi->h > INT32_MAX / 4 ||
        pi->w * pi->h > lim->max_pixels)
        return sh_error(SH_EFORMAT, "%s: data window %lld×%lld (at most %lld pixels are read)", name,
                        (long long)pi->w, (long long)pi->h, lim->max_pixels);
    return SH_OK;
}

/* The chunk table's shape: chunks of level 0 (scanline blocks or tiles)
 * and the largest chunk, and the table's size against the data's. */
static int read_chunk_layout(part_info *pi, const char *name, size_t size)
{
    int32_t count = 0;
    if (exr_get_chunk_count(pi->ctxt, pi->part, &count) != EXR_ERR_SUCCESS || count < 1)
        return sh_error(SH_EFORMAT, "%s: bad chunk count", name);
    if (pi->storage == EXR_STORAGE_SCANLINE) {
        int32_t spc = 0;
        if (exr_get_scanlines_per_chunk(pi->ctxt, pi->part, &spc) != EXR_ERR_SUCCESS || spc < 1)
            return sh_error(SH_EFORMAT, "%s: bad scanlines per chunk", name);
        pi->spc = spc;
        pi->nchunks = (pi->h + spc - 1) / spc;
        pi->max_chunk_px = pi->w * (pi->h < spc ? pi->h : spc);
    } else {
        uint32_t tw = 0, th = 0;
        exr_tile_level_mode_t lm;
        exr_tile_round_mode_t rm;
        if (exr_get_tile_descriptor(pi->ctxt, pi->part, &tw, &th, &lm, &rm) != EXR_ERR_SUCCESS ||
            tw < 1 || th < 1)
            return sh_error(SH_EFORMAT, "%s: bad tile description", name);
        pi->tw = tw;
        pi->th = th;
        pi->ntx = (pi->w + pi->tw - 1) / pi->tw;
        pi->nty = (pi->h + pi->th - 1) / pi->th;
        pi->nchunks = pi->ntx * pi->nty;
        pi->max_chunk_px = (pi->w < pi->tw ? pi->w : pi->tw) * (pi->h < pi->th ? pi->h : pi->th);
    }
    /* each chunk: an 8-byte offset, a header of at least 8 bytes, and data */
    const int64_t min_bytes = 17 * (int64_t)(count > pi->nchunks ? count : pi->nchunks);
    if (pi->nchunks > count || (uint64_t)min_bytes > size)
        return sh_error(SH_EFORMAT,
                        "%s: the header describes %lld×%lld pixels in %lld chunks (the table lists "
                        "%d), which needs at least %lld bytes; the data has %zu", name,
                        (long long)pi->w, (long long)pi->h, (long long)pi->nchunks, count,
                        (long long)min_bytes, size);
    return SH_OK;
}

/* The image, if the image, the scratch of one chunk (every channel as
 * float) and OpenEXRCore's packed, unpacked and scratch buffers of one
 * chunk (max_unpacked bytes each) fit in m's budget; the image is then
 * taken from it. */
static int alloc_image(const part_info *pi, const char *name, int64_t max_unpacked, mem_src *m,
                       sh_image *img)
{
    const double img_bytes = (double)pi->w * (double)pi->h * img->nchan * sizeof(float);
    const double scratch_bytes = (double)pi->max_chunk_px * pi->nch * sizeof(float);
    const double need = img_bytes + scratch_bytes + 3.0 * (double)max_unpacked;
    if (need > (double)m->budget_left) {
        char a[32], b[32];
        return sh_error(SH_ENOMEM, "%s: reading %lld×%lld pixels needs %s, more than the %s allowed",
                        name, (long long)pi->w, (long long)pi->h, human(a, need),
                        human(b, (double)(m->budget_left > 0 ? m->budget_left : 0)));
    }
    img->width = (int)pi->w;
    img->height = (int)pi->h;
    img->data = calloc((size_t)pi->w * (size_t)pi->h * (size_t)img->nchan, sizeof(float));
    if (!img->data) {
        char a[32];
        return sh_error(SH_ENOMEM, "%s: cannot allocate %s for %d×%d×%d floats", name,
                        human(a, img_bytes), img->width, img->height, img->nchan);
    }
    m->budget_left -= (long long)img_bytes;
    return SH_OK;
}

/* Whether the C++ library decodes: what OpenEXRCore 3.1.5 cannot (DWA) or
 * decodes wrongly (B44 with non-half channels, sub-sampled channels), and
 * everything with force_cxx. */
static int use_cxx_decoder(const part_info *pi, const exr_attr_chlist_t *cl, int force_cxx)
{
    int use_cxx = force_cxx || pi->comp == EXR_COMPRESSION_DWAA || pi->comp == EXR_COMPRESSION_DWAB;
    for (int c = 0; c < pi->nch; c++) {
        const exr_attr_chlist_entry_t *e = &cl->entries[c];
        if (e->x_sampling != 1 || e->y_sampling != 1) use_cxx = 1;
        if ((pi->comp == EXR_COMPRESSION_B44 || pi->comp == EXR_COMPRESSION_B44A) &&
            e->pixel_type != EXR_PIXEL_HALF)
            use_cxx = 1;
    }
    return use_cxx;
}

/* The pixels into img: by OpenEXRCore through a chunk's scratch (*scratch,
 * the caller frees it), unless use_cxx or OpenEXRCore finds the
 * compression not implemented; then by the C++ library (*used_fallback). */
static int decode_pixels(const part_info *pi, const char *name, const int *src, int use_cxx, mem_src *m,
                         float **scratch, sh_image *img, int *used_fallback)
{
    if (!use_cxx) {
        const double scratch_bytes = (double)pi->max_chunk_px * pi->nch * sizeof(float);
        *scratch = malloc((size_t)pi->max_chunk_px * (size_t)pi->nch * sizeof(float));
        if (!*scratch) return sh_error(SH_ENOMEM, "%s: out of memory", name);
        m->budget_left -= (long long)scratch_bytes;
        int st = SH_OK;
        const exr_result_t rv = decode_core(pi, src, *scratch, img, name, &st);
        if (rv != EXR_ERR_FEATURE_NOT_IMPLEMENTED) return st;
        /* a compression OpenEXRCore cannot decode: the C++ library */
    }
    const int st = sh__exr_read_cxx(m->data, m->size, name, pi->part, pi->dw.min.x, pi->dw.min.y, img);
    if (st == SH_OK && used_fallback) *used_fallback = 1;
    return st;
}

/* The reader behind sh_exr_read_mem and sh_exr_read_rgba (force_cxx: decode
 * with the C++ library whatever the compression): the header and the chunk
 * table checked against the data and the limits before the image is
 * allocated and the pixels decoded. */
static int read_mem(const void *data, size_t size, const char *name, const sh_exr_limits *lim,
                    int force_cxx, sh_image *img, int *used_fallback)
{
    static const unsigned char magic[4] = {0x76, 0x2f, 0x31, 0x01};
    if (size < 8 || memcmp(data, magic, 4) != 0)
        return sh_error(SH_EFORMAT, "%s: not an OpenEXR file (%s)", name,
                        size < 8 ? "too short" : "no OpenEXR magic number");

    mem_src m = {data, size, lim->max_bytes};
    mem_src *const outer = budget_read;
    budget_read = &m;
    part_info pi;
    memset(&pi, 0, sizeof pi);
    pi.part = -1;
    float *scratch = NULL;
    int src[SH_IMAGE_MAX_CHANNELS];
    const exr_attr_chlist_t *cl = NULL;
    int64_t raw_total = 0, max_unpacked = 0;
    int st = start_read(&m, name, &pi);
    if (!st) st = find_flat_part(&pi, name);
    if (!st) st = read_header(&pi, name, lim, img, src, &cl);
    if (!st) st = read_chunk_layout(&pi, name, size);
    if (!st) st = check_chunks(&pi, name, data, size, lim, &raw_total, &max_unpacked);
    if (!st) st = alloc_image(&pi, name, max_unpacked, &m, img);
    if (!st) st = decode_pixels(&pi, name, src, use_cxx_decoder(&pi, cl, force_cxx), &m, &scratch, img,
                                used_fallback);

    free(scratch);
    if (pi.ctxt) exr_finish(&pi.ctxt);
    budget_read = outer;
    if (st != SH_OK) {
        sh_image_free(img);
        memset(img, 0, sizeof *img);
    }
    return st;
}

static int check_limits(const sh_exr_limits *lim)
{
    if (!(lim->max_pixels >= 1 && lim->max_bytes >= 1 && lim->max_channels >= 1 &&
          lim->max_ratio >= 1.0))
        return sh_error(SH_EINVAL, "sh_exr_limits: every limit must be positive (ratio >= 1)");
    return SH_OK;
}

int sh_exr_read_mem(const void *data, size_t size, const char *name, const sh_exr_limits *lim,
                    sh_image *img, int *used_fallback)
{
    if (used_fallback) *used_fallback = 0;
    if (!img) return sh_error(SH_EINVAL, "sh_exr_read_mem: image is NULL");
    memset(img, 0, sizeof *img);
    if (!data && size) return sh_error(SH_EINVAL, "sh_exr_read_mem: data is NULL");
    sh_exr_limits l;
    if (lim) l = *lim;
    else sh_exr_limits_default(&l);
    int st = check_limits(&l);
    if (st) return st;
    return read_mem(data ? data : "", size, name ? name : "EXR data", &l, 0, img, used_fallback);
}

/* Read a whole file into memory, counting it against lim->max_bytes. */
static int slurp(const char *path, sh_exr_limits *lim, unsigned char **buf, size_t *n)
{
    *buf = NULL;
    *n = 0;
    sh_input in;
    int st = sh_input_open("EXR image", path, lim->max_bytes - 1, &in);
    if (st) return st;
    const int fd = in.fd;
    size_t cap = (size_t)in.size, got = 0;
    unsigned char *b = malloc(cap ? cap : 1);
    if (!b) {
        close(fd);
        return sh_error(SH_ENOMEM, "%s: cannot allocate %zu bytes", path, cap);
    }
    while (got < cap) {
        ssize_t r = read(fd, b + got, cap - got);
        if (r < 0 && errno == EINTR) continue;
        if (r < 0) {
            int e = errno;
            free(b);
            close(fd);
            return sh_error(SH_EIO, "cannot read '%s': %s", path, strerror(e));
        }
        if (r == 0) break; /* the file shrank: read what is there */
        got += (size_t)r;
    }
    close(fd);
    lim->max_bytes -= (long long)cap;
    *buf = b;
    *n = got;
    return SH_OK;
}

static int read_path(const char *path, int force_cxx, sh_image *img, int *used_fallback)
{
    if (used_fallback) *used_fallback = 0;
    if (!img) return sh_error(SH_EINVAL, "EXR reader: image is NULL");
    memset(img, 0, sizeof *img);
    if (!path || !*path) return sh_error(SH_EINVAL, "EXR reader: empty path");
    sh_exr_limits lim;
    sh_exr_limits_default(&lim);
    unsigned char *buf;
    size_t n;
    int st = slurp(path, &lim, &buf, &n);
    if (st) return st;
    st = read_mem(buf, n, path, &lim, force_cxx, img, used_fallback);
    free(buf);
    return st;
}

int sh_exr_read(const char *path, sh_image *img, int *used_fallback)
{
    return read_path(path, 0, img, used_fallback);
}

int sh_exr_read_rgba(const char *path, sh_image *img)
{
    return read_path(path, 1, img, NULL);
}

/* ------------------------------------------------------------- writing */

static int check_image(const sh_image *img, const char *who)
{
    if (!img || !img->data) return sh_error(SH_EINVAL, "%s: image is empty", who);
    if (img->width < 1 || img->height < 1)
        return sh_error(SH_EINVAL, "%s: image size %d×%d", who, img->width, img->height);
    if ((long long)img->width * img->height > SH_IMAGE_MAX_PIXELS)
        return sh_error(SH_EINVAL, "%s: a %d×%d image is larger than %lld pixels (docs/ranges.md)", who, img->width,
                        img->height, (long long)SH_IMAGE_MAX_PIXELS);
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

int sh_exr_write(const char *path, const sh_image *img) { return sh_exr_write_progress(path, img, NULL, NULL); }

int sh_exr_write_progress(const char *path, const sh_image *img, sh_progress_fn progress, void *pctx)
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

    /* OpenEXRCore opens (creates) the temporary by name: inside a window */
    sigset_t old;
    sh__temp_enter(&old);
    exr_result_t rv = exr_start_write(&ctxt, tmp, EXR_WRITE_FILE_DIRECTLY, &init);
    sh__temp_leave(&old);
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
        if (rv == EXR_ERR_SUCCESS && progress)
            progress(pctx, y + spc < img->height ? y + spc : img->height, img->height, "rows written");
    }
    if (enc_inited) exr_encoding_destroy(ctxt, &enc);
    exr_result_t frv = exr_finish(&ctxt);
    if (rv == EXR_ERR_SUCCESS) rv = frv;
    if (rv != EXR_ERR_SUCCESS) {
        sh__discard_temp(tmp);
        free(tmp);
        return sh_error(rv == EXR_ERR_OUT_OF_MEMORY ? SH_ENOMEM : SH_EIO,
                        "cannot write '%s': %s", path, core_reason(rv));
    }
    st = sh__commit_temp(tmp, path);
    free(tmp);
    return st;
}
