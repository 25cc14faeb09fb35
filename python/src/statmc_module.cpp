// _statmc: the native half of `import statmc` (docs/python.md). A thin host like the
// statmc tool: files are read and written by layers/exr_files.h, operators come from the
// same plugin modules, and their parameters are parsed and checked by the tool's own
// modifier parser, so Python and the command line accept, refuse and default alike.
//
// An image crosses as (channel names, H×W×N float32 array, attributes, origin). Arrays
// from Python are wrapped by the ImageBuf without a copy, and results hand their pixels to
// the array they return.
#include <cstdlib>
#include <functional>
#include <sstream>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <OpenImageIO/imagebuf.h>

#include "statmc/layers/exr_files.h"
#include "statmc/layers/file_error.h"
#include "statmc/plugin_host/host_error.h"
#include "statmc/plugin_host/modifiers.h"
#include "statmc/plugin_host/plugin_catalog.h"
#include "statmc/plugin_sdk/operator_spec.h"

namespace py = pybind11;

namespace {

using FloatArray = py::array_t<float, py::array::c_style | py::array::forcecast>;
using Attributes = std::vector<std::pair<std::string, py::object>>;

// Only what maps to one Python scalar crosses; other header types (matrices, timecodes)
// stay with the file.
py::dict attributes_of(const OIIO::ImageSpec& spec)
{
    py::dict out;
    for (const OIIO::ParamValue& p : spec.extra_attribs) {
        const OIIO::TypeDesc t = p.type();
        if (t == OIIO::TypeInt)
            out[py::str(p.name().string())] = p.get_int();
        else if (t == OIIO::TypeFloat)
            out[py::str(p.name().string())] = p.get_float();
        else if (t == OIIO::TypeDesc::DOUBLE)
            out[py::str(p.name().string())] = *static_cast<const double*>(p.data());
        else if (t == OIIO::TypeString)
            out[py::str(p.name().string())] = p.get_string();
    }
    return out;
}

void set_attributes(OIIO::ImageSpec& spec, const py::dict& attributes)
{
    for (const auto& [key, value] : attributes) {
        const std::string name = py::str(key);
        if (py::isinstance<py::bool_>(value) || py::isinstance<py::int_>(value))
            spec.attribute(name, value.cast<int>());
        else if (py::isinstance<py::float_>(value))
            spec.attribute(name, value.cast<float>());
        else if (py::isinstance<py::str>(value))
            spec.attribute(name, value.cast<std::string>());
        else
            throw py::type_error("attribute " + name + ": expected int, float or str, got " +
                                 std::string(py::str(value.get_type().attr("__name__"))));
    }
}

// The pixels as an H×W×N float32 array. A result that owns its float pixels hands them to
// the array, which keeps the ImageBuf alive (no copy of a frame's hundred megabytes);
// anything else is copied.
py::array pixels_to_python(OIIO::ImageBuf&& image)
{
    const OIIO::ImageSpec& spec = image.spec();
    const std::vector<py::ssize_t> shape = {spec.height, spec.width, spec.nchannels};
    if (image.storage() == OIIO::ImageBuf::LOCALBUFFER && image.localpixels() &&
        spec.format == OIIO::TypeFloat && spec.depth == 1) {
        auto* owner = new OIIO::ImageBuf(std::move(image));
        py::capsule release(owner, [](void* p) { delete static_cast<OIIO::ImageBuf*>(p); });
        const std::vector<py::ssize_t> strides = {py::ssize_t(owner->scanline_stride()),
                                                  py::ssize_t(owner->pixel_stride()),
                                                  py::ssize_t(sizeof(float))};
        return py::array_t<float>(shape, strides, static_cast<float*>(owner->localpixels()),
                                  release);
    }
    FloatArray pixels(shape);
    if (!image.get_pixels(image.roi(), OIIO::TypeFloat, pixels.mutable_data()))
        throw std::runtime_error("cannot read the pixels: " + image.geterror());
    return std::move(pixels);
}

py::tuple image_to_python(OIIO::ImageBuf&& image)
{
    const OIIO::ImageSpec spec = image.spec();
    py::array pixels = pixels_to_python(std::move(image));
    return py::make_tuple(spec.channelnames, std::move(pixels), attributes_of(spec),
                          py::make_tuple(spec.x, spec.y));
}

// An image over the array's own memory: `pixels` must outlive it.
OIIO::ImageBuf image_from_python(const std::vector<std::string>& names, const FloatArray& pixels,
                                 const py::dict& attributes, const std::pair<int, int>& origin)
{
    if (pixels.ndim() != 3 || pixels.shape(2) != py::ssize_t(names.size()))
        throw py::value_error("expected an H×W×" + std::to_string(names.size()) +
                              " float32 array for channels of that number");
    OIIO::ImageSpec spec(int(pixels.shape(1)), int(pixels.shape(0)), int(names.size()),
                         OIIO::TypeFloat);
    spec.channelnames = names;
    spec.x = spec.full_x = origin.first;
    spec.y = spec.full_y = origin.second;
    spec.alpha_channel = spec.channelindex("A");
    set_attributes(spec, attributes);
    return OIIO::ImageBuf(spec, const_cast<float*>(pixels.data()));
}

py::tuple read_file(const std::string& path)
{
    OIIO::ImageBuf image;
    {
        py::gil_scoped_release unlocked;
        image = statmc::layers::read_image_file(path);
    }
    return image_to_python(std::move(image));
}

void write_file(const std::string& path, const std::vector<std::string>& names,
                const FloatArray& pixels, const py::dict& attributes, std::pair<int, int> origin)
{
    const OIIO::ImageBuf image = image_from_python(names, pixels, attributes, origin);
    py::gil_scoped_release unlocked;
    statmc::layers::write_image_file(image, path);
}

// The operator's parameters from Python's keyword values, parsed as the command line
// parses `--op:name=value`: the same checks, defaults and messages.
statmc::ParameterValues parameters(const statmc::OperatorSpec& op, const py::dict& options)
{
    std::vector<std::pair<std::string, std::string>> given;
    for (const auto& [key, value] : options) {
        std::string text;
        if (py::isinstance<py::bool_>(value))
            text = value.cast<bool>() ? "1" : "0";
        else if (py::isinstance<py::list>(value) || py::isinstance<py::tuple>(value)) {
            for (const auto& item : value)
                text += (text.empty() ? "" : ",") + std::string(py::str(item));
        } else {
            text = py::str(value);
        }
        given.emplace_back(py::str(key), text);
    }
    return statmc::host::Modifiers::parse("--" + op.name, given, op.parameters).values();
}

// (names, pixels, attributes, origin), as read() returns it.
using PythonImage = std::tuple<std::vector<std::string>, FloatArray, py::dict, std::pair<int, int>>;

// The frames around input 0 (nearest first on each side), offered to an operator that asks
// for its sequence (--denoise:temporal), as the command line offers a frame pattern's.
std::function<std::vector<const OIIO::ImageBuf*>(const std::vector<int>&)>
sequence_of(const std::vector<OIIO::ImageBuf>& previous, const std::vector<OIIO::ImageBuf>& next)
{
    return [&previous, &next](const std::vector<int>& offsets) {
        std::vector<const OIIO::ImageBuf*> frames;
        for (int offset : offsets) {
            const std::vector<OIIO::ImageBuf>& side = offset < 0 ? previous : next;
            const std::size_t k = std::size_t(std::abs(offset)) - 1;
            frames.push_back(offset != 0 && k < side.size() ? &side[k] : nullptr);
        }
        return frames;
    };
}

std::vector<OIIO::ImageBuf> images_from_python(const std::vector<PythonImage>& images)
{
    std::vector<OIIO::ImageBuf> out;
    for (const PythonImage& image : images)
        out.push_back(std::apply(image_from_python, image));
    return out;
}

py::tuple run_operator(const std::string& name, const std::vector<PythonImage>& inputs,
                       const std::vector<std::string>& labels, const py::dict& options,
                       const std::vector<PythonImage>& previous,
                       const std::vector<PythonImage>& next, int nthreads)
{
    const statmc::OperatorSpec* op = statmc::host::plugin_registry().find(name);
    if (!op)
        throw py::value_error("no operator '" + name + "'");
    const statmc::ParameterValues values = parameters(*op, options);
    const std::string command = "--" + op->name;
    if (op->check)
        if (const std::string why = op->check(values); !why.empty())
            throw py::value_error(command + ": " + why);
    if (const std::string why = op->input_count_problem(inputs.size()); !why.empty())
        throw py::value_error(command + ": " + why);

    const std::vector<OIIO::ImageBuf> images = images_from_python(inputs);
    const std::vector<OIIO::ImageBuf> before = images_from_python(previous);
    const std::vector<OIIO::ImageBuf> after = images_from_python(next);
    std::vector<const OIIO::ImageBuf*> pointers;
    for (const OIIO::ImageBuf& image : images)
        pointers.push_back(&image);
    std::ostringstream report;
    statmc::RunContext context;
    context.nthreads = nthreads;
    context.out = &report;
    context.module = op->module;
    context.input_labels = labels;
    context.input_labels.resize(inputs.size());
    if (!before.empty() || !after.empty())
        context.sequence_frames = sequence_of(before, after);
    // Collected while the GIL is released, raised as warnings once it is held again.
    std::vector<std::string> messages;
    context.message = [&messages](const std::string& line) { messages.push_back(line); };
    OIIO::ImageBuf result;
    {
        py::gil_scoped_release unlocked;
        result = op->run(pointers, values, context);
    }
    for (const std::string& line : messages)
        if (PyErr_WarnEx(PyExc_UserWarning, line.c_str(), 2) != 0)
            throw py::error_already_set();  // warnings turned into errors
    if (result.has_error())
        throw py::value_error(command + ": " + result.geterror());
    return py::make_tuple(image_to_python(std::move(result)), report.str());
}

}  // namespace

PYBIND11_MODULE(_statmc, m)
{
    m.doc() = "statmc's native operators and files (use the statmc package)";
    statmc::layers::silence_library_debug_messages();
    py::register_exception<statmc::host::HostError>(m, "ToolError", PyExc_ValueError);
    py::register_exception<statmc::layers::FileError>(m, "FileError", PyExc_OSError);

    m.def("read", &read_file, py::arg("path"),
          "(names, H×W×N float32 pixels, attributes, origin) of subimage 0 of an image file");
    m.def("write", &write_file, py::arg("path"), py::arg("names"), py::arg("pixels"),
          py::arg("attributes"), py::arg("origin"),
          "writes an OpenEXR file under the layer contract's storage rules, atomically");
    m.def("run", &run_operator, py::arg("operator"), py::arg("inputs"), py::arg("labels"),
          py::arg("options"), py::arg("previous") = std::vector<PythonImage>{},
          py::arg("next") = std::vector<PythonImage>{}, py::arg("nthreads") = 0,
          "runs a plugin operator; returns ((names, pixels, attributes, origin), report)");
    m.def(
        "help", [](const std::string& name) { return statmc::host::operator_help_text(name); },
        py::arg("operator"), "the operator's help and parameter table, as statmc --help OP");
    m.def("operators", [] {
        std::vector<std::string> names;
        for (const statmc::OperatorSpec& op : statmc::host::plugin_registry().operators())
            names.push_back(op.name);
        return names;
    });
}
