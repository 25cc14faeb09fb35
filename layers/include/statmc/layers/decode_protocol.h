// What the isolated decoder and its parent agree on (isolated_decode.h): the layout of the
// shared memory and of the decoder's command line. No library is needed to read it, so
// the decoder program links OpenEXR alone and starts in milliseconds.
//
//   statmc-decode FD PPID PATH  (S M W H X Y C NAME_1 ... NAME_C)...
//
// FD: the shared memory; PPID: the parent, which the decoder never outlives; per level:
// subimage (EXR part), MIP level, the data window's size and origin, and the channels in
// the order the parent holds them. The memory holds each level's float pixels
// (interleaved, row by row over the data window; a UINT channel's bits as stored, for the
// parent to convert as OIIO does), each from a page boundary, then kMessageBytes for the
// reason of a failure (exit status kDecodeFailed).
#pragma once

#include <cstdint>
#include <vector>

namespace statmc::layers::decode_protocol {

constexpr std::uint64_t kMessageBytes = 4096;
constexpr std::uint64_t kPage = 4096;
constexpr int kChildFd = 3;
constexpr int kDecodeFailed = 2;
constexpr int kLevelFields = 7;  // S M W H X Y C, then C names

inline std::uint64_t level_bytes(std::uint64_t width, std::uint64_t height, std::uint64_t channels)
{
    return width * height * channels * sizeof(float);
}

inline std::uint64_t page_up(std::uint64_t bytes) { return (bytes + kPage - 1) / kPage * kPage; }

/// Where each level starts in the memory, each on a page, so that the parent can free a
/// level's pages as it copies them out; the last entry is where the message starts.
inline std::vector<std::uint64_t> level_offsets(const std::vector<std::uint64_t>& sizes)
{
    std::vector<std::uint64_t> offsets;
    std::uint64_t at = 0;
    for (std::uint64_t size : sizes) {
        offsets.push_back(at);
        at += page_up(size);
    }
    offsets.push_back(at);
    return offsets;
}

}  // namespace statmc::layers::decode_protocol
