// An operator as a plugin registers it: name, help, typed parameters, inputs, and a run
// function in the style of OIIO's ImageBufAlgo return form (errors set on the result).
#pragma once

#include <functional>
#include <ostream>
#include <string>
#include <vector>

#include <OpenImageIO/imagebuf.h>

#include "statmc/plugin_sdk/parameter_spec.h"
#include "statmc/plugin_sdk/parameter_values.h"

namespace statmc {

/// `OperatorSpec::inputs` for an operator taking a run of images: the value of its `n`
/// parameter when given, else the whole stack (at least `min_inputs`).
inline constexpr int kVariadicInputs = -1;

/// What the host lends a running operator besides its images.
struct RunContext {
    int nthreads = 0;                       ///< 0 = OIIO's global "threads"; 1 = caller only
    std::ostream* out = nullptr;            ///< for reports (compare's table); may be null
    std::vector<std::string> input_labels;  ///< names of the inputs for messages (file names)
    std::string module;                     ///< the operator's module file: data ships beside it
    /// In a frame sequence (`statmc shot.#.exr --frames 1-48 …`): input 0's file at frames
    /// t + offset for each offset (≠ 0), in the frame list's order, read on demand (in
    /// parallel where the memory budget allows) and valid while the operator runs; null
    /// past the sequence's ends. May throw (an unreadable file, the budget). Empty outside
    /// a sequence, or when input 0 is not a frame of one as read. The host keeps a copy of
    /// the input as read for later frames: an in-place operator calls this before writing.
    std::function<std::vector<const OIIO::ImageBuf*>(const std::vector<int>& offsets)>
        sequence_frames;
    /// Where the operator's notes and warnings go, a line each ("--denoise: note: in.exr:
    /// …"): the statmc tool prints them on stderr, Python raises them as warnings. Unset:
    /// stderr. Called on the thread that runs the operator.
    std::function<void(const std::string& line)> message;

    /// Sends `line` to `message`, or to stderr without one.
    void tell(const std::string& line) const;
};

/// Inputs bottom of the stack first. Returns the image to push; on failure the result
/// carries the message (`result.errorfmt(...)`, seen by `has_error()`). Must not throw.
using RunFunction =
    std::function<OIIO::ImageBuf(const std::vector<const OIIO::ImageBuf*>& inputs,
                                 const ParameterValues& parameters, const RunContext& context)>;

/// The in-place form for one-input operators: the host hands over the image it popped,
/// which becomes the result. Returns false with the message on the image. Must not throw.
using RunInPlaceFunction = std::function<bool(
    OIIO::ImageBuf& image, const ParameterValues& parameters, const RunContext& context)>;

/// Cross-parameter checks beyond type and range, run before any image is read: "" when
/// fine, else a message naming the parameter.
using CheckFunction = std::function<std::string(const ParameterValues& parameters)>;

struct OperatorSpec {
    std::string name;     ///< "denoise": the command is --denoise
    std::string summary;  ///< one line
    std::string help;     ///< a paragraph for --help OP
    std::vector<ParameterSpec> parameters;
    int inputs = 1;                     ///< images popped, or kVariadicInputs
    int min_inputs = 1;                 ///< kVariadicInputs only
    std::string input_noun = "images";  ///< "renders": for "needs at least 2 renders"
    CheckFunction check;                ///< optional
    RunFunction run;
    /// Optional, one-input operators only: when set, the host runs this instead of `run`
    /// on an image it owns, sparing the operator a copy of its input.
    RunInPlaceFunction run_in_place;
    std::string module;  ///< set by the loader: the file it came from

    /// "" when `count` inputs suit the operator, else what every host says after the
    /// command's name: "needs at least 2 renders, got 1", "needs 2 images, got 1".
    std::string input_count_problem(std::size_t count) const;
};

/// Makes `op` pop a run of images: the value of its `n` parameter (added here) when given,
/// else the whole stack; at least `min_inputs`, called `noun` ("renders") in messages.
void take_variadic_inputs(OperatorSpec& op, int min_inputs, const std::string& noun);

}  // namespace statmc
