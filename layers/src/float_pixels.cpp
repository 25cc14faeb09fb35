#include "statmc/layers/float_pixels.h"

#include "statmc/layers/layer_error.h"

namespace statmc::layers {

namespace {

void require_local_float(const OIIO::ImageBuf& buf)
{
    if (!has_local_float_pixels(buf))
        throw LayerError("the image does not hold local float pixels (convert it with "
                         "layers::local_float_pixels)");
}

std::ptrdiff_t floats(OIIO::stride_t bytes) { return std::ptrdiff_t(bytes / sizeof(float)); }

}  // namespace

bool has_local_float_pixels(const OIIO::ImageBuf& buf)
{
    return buf.initialized() && buf.localpixels() != nullptr &&
           buf.spec().format == OIIO::TypeDesc::FLOAT && !buf.deep();
}

const OIIO::ImageBuf& local_float_pixels(const OIIO::ImageBuf& src, OIIO::ImageBuf& scratch)
{
    if (has_local_float_pixels(src))
        return src;
    if (!scratch.copy(src, OIIO::TypeDesc::FLOAT) || !has_local_float_pixels(scratch))
        throw LayerError("cannot convert the image to float pixels: " + scratch.geterror());
    return scratch;
}

ConstPlane channel_plane(const OIIO::ImageBuf& buf, int channel)
{
    require_local_float(buf);
    const auto* base = static_cast<const float*>(buf.localpixels());
    return {base + channel, floats(buf.pixel_stride()), floats(buf.scanline_stride())};
}

Plane channel_plane(OIIO::ImageBuf& buf, int channel)
{
    require_local_float(buf);
    auto* base = static_cast<float*>(buf.localpixels());
    return {base + channel, floats(buf.pixel_stride()), floats(buf.scanline_stride())};
}

}  // namespace statmc::layers
