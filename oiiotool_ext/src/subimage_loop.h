// Which subimages a command works on, as oiiotool decides: subimage 0 only (the result
// then has one subimage), every subimage with -a, or with `:subimages=LIST` the listed
// ones (indices or part names), the others passing through unchanged.
#pragma once

#include <cstddef>
#include <functional>
#include <string>
#include <vector>

#include <OpenImageIO/imagebuf.h>

#include "image_stack.h"
#include "statmc/tool/command.h"

namespace statmc::tool {

struct ToolContext;

/// One subimage's work: the same subimage of each input in, the result out (carrying
/// its error, ImageBufAlgo's return form).
using SubimageOp = std::function<OIIO::ImageBuf(const std::vector<const OIIO::ImageBuf*>&)>;

/// The subimage `which` names in `image`: its part name (oiio:subimagename) or its
/// index. Throws HostError "<command>: <label> has no subimage ..." listing the names.
std::size_t find_subimage(const StackImage& image, const std::string& which,
                          const std::string& command);

/// The `:subimages=` modifier of the commands that take it.
host::ModifierSpec subimages_modifier();

/// Pops `count` images, runs `op` on the subimages the invocation selects and pushes
/// the result. Throws HostError naming the command and input on failure, and when -a
/// pairs inputs with different subimage counts.
void apply_to_subimages(ToolContext& ctx, const Invocation& inv, std::size_t count,
                        const SubimageOp& op);

}  // namespace statmc::tool
