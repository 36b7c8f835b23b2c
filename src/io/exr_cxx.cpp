/* exr_cxx.cpp — reading EXR pixels through OpenEXR's C++ library, for the
 * files OpenEXRCore 3.1 cannot decode (DWAA/DWAB: "not yet implemented in
 * C").  sh_exr_read_mem (exr_io.c) has already read the header with
 * OpenEXRCore, checked the chunk table against the data's size, picked the
 * channels and allocated the image; this file only fills it in.
 *
 * The data is read from memory (an Imf::IStream over the caller's bytes,
 * every read bounds-checked), with one thread and without the library's
 * chunk-table reconstruction.  Every channel is read as FLOAT into the
 * image's planes (Slice::Make places the data window's origin).  The C++
 * library reports failures as exceptions; every one is caught here.
 */
#include "io/exr_internal.h"

#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfIO.h>
#include <ImfInputPart.h>
#include <ImfMultiPartInputFile.h>
#include <Iex.h>

#include <cstring>
#include <exception>
#include <new>

namespace {

class MemIStream : public Imf::IStream {
  public:
    MemIStream(const void *data, size_t size, const char *name)
        : Imf::IStream(name), d_(static_cast<const char *>(data)), n_(size), pos_(0)
    {
    }
    bool read(char c[], int len) override
    {
        if (len < 0 || pos_ > n_ || static_cast<uint64_t>(len) > n_ - pos_)
            throw IEX_NAMESPACE::InputExc("unexpected end of file");
        std::memcpy(c, d_ + pos_, static_cast<size_t>(len));
        pos_ += static_cast<uint64_t>(len);
        return pos_ < n_;
    }
    uint64_t tellg() override { return pos_; }
    void seekg(uint64_t pos) override { pos_ = pos; }
    void clear() override {}

  private:
    const char *d_;
    uint64_t n_, pos_;
};

} // namespace

extern "C" int sh__exr_read_cxx(const void *data, size_t size, const char *name, int part,
                                int xmin, int ymin, sh_image *img)
{
    try {
        MemIStream is(data, size, name);
        Imf::MultiPartInputFile file(is, 1, false);
        if (part < 0 || part >= file.parts())
            return sh_error(SH_EFORMAT, "%s: part %d not found by the C++ library", name, part);
        Imf::InputPart in(file, part);
        const IMATH_NAMESPACE::Box2i dw = in.header().dataWindow();
        if (dw.min.x != xmin || dw.min.y != ymin || (int64_t)dw.max.x - dw.min.x + 1 != img->width ||
            (int64_t)dw.max.y - dw.min.y + 1 != img->height)
            return sh_error(SH_EFORMAT, "%s: the C++ library reads a different data window", name);
        Imf::FrameBuffer fb;
        const size_t plane = (size_t)img->width * (size_t)img->height;
        for (int k = 0; k < img->nchan; k++)
            fb.insert(img->names[k],
                      Imf::Slice::Make(Imf::FLOAT, img->data + (size_t)k * plane, dw, sizeof(float),
                                       sizeof(float) * (size_t)img->width));
        in.setFrameBuffer(fb);
        in.readPixels(dw.min.y, dw.max.y);
        return SH_OK;
    } catch (const std::bad_alloc &) {
        return sh_error(SH_ENOMEM, "%s: out of memory while decoding", name);
    } catch (const std::exception &e) {
        return sh_error(SH_EFORMAT, "%s: corrupt or truncated pixel data (%s)", name, e.what());
    } catch (...) {
        return sh_error(SH_EFORMAT, "%s: corrupt or truncated pixel data", name);
    }
}
