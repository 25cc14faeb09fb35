// ImageBufAlgo's calling conventions, written once for every operator: the bool form puts
// any error on the destination and throws nothing; the return form wraps it; and
// nthreads = 0 means OIIO's global "threads" attribute.
#pragma once

#include <exception>
#include <string_view>

#include <OpenImageIO/imagebuf.h>

namespace statmc::layers {

/// `nthreads` as a count: itself when positive, else OIIO's global "threads" attribute
/// (0 when that is unset too, which TBB-based code reads as "all cores").
int thread_count(int nthreads);

/// Runs `body` (returning bool); whatever it throws becomes `dst.errorfmt(...)` and false,
/// so that operator implementations may throw while their callers never see it.
template <class Body>
bool errors_on(OIIO::ImageBuf& dst, std::string_view op, Body&& body)
{
    try {
        return body();
    } catch (const std::exception& e) {
        dst.errorfmt("{}", e.what());
    } catch (...) {
        dst.errorfmt("{}: unknown error", op);
    }
    return false;
}

/// The return form of a bool-form call `call(dst)`: check `has_error()` on the result.
template <class Call>
OIIO::ImageBuf returned_image(std::string_view op, Call&& call)
{
    OIIO::ImageBuf result;
    if (!call(result) && !result.has_error())
        result.errorfmt("{} failed", op);
    return result;
}

}  // namespace statmc::layers
