#include "statmc/layers/exr_files.h"

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <system_error>

#include <OpenImageIO/imagecache.h>
#include <OpenImageIO/imageio.h>

#include "statmc/layers/atomic_file.h"
#include "statmc/layers/file_error.h"
#include "statmc/layers/input_path.h"
#include "statmc/layers/isolated_decode.h"
#include "statmc/layers/layer_names.h"
#include "statmc/layers/openexr_check.h"
#include "statmc/layers/storage_rules.h"

namespace statmc::layers {

namespace fs = std::filesystem;

namespace {

// ImageBuf opens files through the shared ImageCache; forgetting them keeps a file that
// statmc later overwrites (in.exr ... -o in.exr) from being served stale.
void forget_cached(const std::string& path)
{
    OIIO::ImageCache::create(true)->invalidate(OIIO::ustring(path), true);
}

struct ForgetOnExit {
    std::string path;
    ~ForgetOnExit() { forget_cached(path); }
};

FileError unreadable(const std::string& path, const std::string& why)
{
    return FileError(path + ": not an OpenEXR/readable image: " + why);
}

[[noreturn]] void cannot_write(const std::string& path, const std::string& why)
{
    throw FileError(path + ": cannot write: " + why);
}

// The first statistics channel of `subimages`, empty when they hold a plain picture.
std::string statistics_channel(const std::vector<OIIO::ImageBuf>& subimages)
{
    for (const OIIO::ImageBuf& image : subimages)
        for (const std::string& channel : image.spec().channelnames)
            if (is_statistics_channel(channel))
                return channel;
    return {};
}

// OpenEXR for everything; another format OIIO writes (PNG, JPEG, TIFF) only for one plain
// picture, such as --display makes: statistics need OpenEXR's float channels and parts.
std::unique_ptr<OIIO::ImageOutput>
image_writer(const std::string& path, const std::vector<OIIO::ImageBuf>& subimages, bool mip_mapped)
{
    auto out = OIIO::ImageOutput::create(path);
    if (!out)
        cannot_write(path, "no writer for this file type (" + OIIO::geterror() + ")");
    if (std::string(out->format_name()) == "openexr")
        return out;
    const std::string why = " (use the .exr extension)";
    if (const std::string channel = statistics_channel(subimages); !channel.empty())
        cannot_write(path, "the image holds statistics (" + channel +
                               "), which statmc writes as OpenEXR only" + why +
                               "; for a picture, --display it first");
    if (subimages.size() > 1 || mip_mapped)
        cannot_write(path, std::string("several subimages or MIP levels are written as OpenEXR "
                                       "only") +
                               why);
    return out;
}

bool is_openexr_writer(const OIIO::ImageOutput& out)
{
    return std::string(out.format_name()) == "openexr";
}

void check_target(const std::string& path)
{
    if (path.empty() || path == "-")
        cannot_write(path, "statmc cannot write images to standard output");
    const fs::path target(path);
    const fs::path directory = target.has_parent_path() ? target.parent_path() : fs::path(".");
    std::error_code ec;
    if (!fs::is_directory(directory, ec))
        cannot_write(path, "directory '" + directory.string() + "' does not exist");
    if (fs::is_directory(target, ec))
        cannot_write(path, "it is a directory");
}

// Subimage `s` of an existing file opened for reading, after the header's checks (deep,
// volume, memory budget) and, for s = 0 with `check_whole_file`, OpenEXR's check of the
// whole file; `subimages` is set to the file's count.
std::unique_ptr<OIIO::ImageInput> open_checked(const std::string& path, int s, int& subimages,
                                               const ReadOptions& options,
                                               bool check_whole_file = false)
{
    const bool openexr = is_openexr_file(path);
    if (s == 0 && openexr)
        check_openexr_headers(path);  // before OpenEXR parses them
    auto in = OIIO::ImageInput::open(path);
    if (!in)
        throw unreadable(path, OIIO::geterror());
    subimages = 1;
    while (in->seek_subimage(subimages, 0))
        ++subimages;
    if (!in->seek_subimage(s, 0))
        throw unreadable(path, in->geterror());
    const OIIO::ImageSpec& spec = in->spec();
    if (spec.deep)
        throw FileError(path + ": deep images are not supported");
    if (spec.depth > 1)
        throw FileError(path + ": volume images are not supported");
    check_read_budget(path, s, spec,
                      options.max_memory > 0 ? options.max_memory : default_read_budget());
    // The whole file once, after the header's own checks have had their say.
    if (s == 0 && openexr && check_whole_file)
        check_openexr_structure(path);
    return in;
}

// The levels of subimage `s` of `in` as its headers declare them: the first only, or with
// `all_levels` every MIP level. Each level halves the one before (rounded down or up); a
// rip map's levels do not (OIIO lists them as levels of the full size): written back as a
// MIP map they would not be what was read, so such a file is refused rather than changed.
// Each level is smaller than the first, so the budget that admitted it covers them.
std::vector<DecodeLevel> declared_levels(OIIO::ImageInput& in, const std::string& path, int s,
                                         bool all_levels)
{
    auto halves = [](int size, int previous) {
        return size == std::max(1, previous / 2) || size == std::max(1, (previous + 1) / 2);
    };
    std::vector<DecodeLevel> levels;
    for (int m = 0; (m == 0 || all_levels) && in.seek_subimage(s, m); ++m) {
        levels.push_back({s, m, in.spec()});
        if (m == 0)
            continue;
        const OIIO::ImageSpec& previous = levels[levels.size() - 2].spec;
        const OIIO::ImageSpec& level = levels.back().spec;
        if (!halves(level.width, previous.width) || !halves(level.height, previous.height))
            throw FileError(path + ": subimage " + std::to_string(s) + " has levels that are " +
                            "not a MIP map (a rip map?), which statmc cannot keep");
    }
    return levels;
}

// The levels to read, subimage by subimage: subimage 0 alone or every one, each with its
// first level alone or all of them. Every header is judged first (open_checked).
std::vector<std::vector<DecodeLevel>> plan_read(const std::string& path, const ReadOptions& options,
                                                bool all_subimages, bool all_levels)
{
    std::vector<std::vector<DecodeLevel>> plan;
    int subimages = 1;
    for (int s = 0; s < (all_subimages ? subimages : 1); ++s) {
        auto in = open_checked(path, s, subimages, options);
        plan.push_back(declared_levels(*in, path, s, all_levels));
    }
    return plan;
}

// MIP level `m` of subimage `s` in float pixels, decoded in this process. OIIO's ImageBuf
// reads it (so that the file's own pixel types stay known as its nativespec); its forced
// read goes through ImageInput, the header through the ImageCache.
OIIO::ImageBuf read_level(const std::string& path, int s, int m)
{
    OIIO::ImageBuf image(path);
    if (!image.init_spec(path, s, m) || !image.read(s, m, /*force=*/true, OIIO::TypeDesc::FLOAT))
        throw unreadable(path, image.has_error() ? image.geterror() : OIIO::geterror());
    return image;
}

// The planned levels' pixels, in float, in the plan's shape. An OpenEXR file to be
// checked is decoded once, in the isolated decoder; where that cannot run (no decoder
// ships with the program, no shared memory), OpenEXR's checker reads the whole file first
// and this process decodes it.
std::vector<std::vector<OIIO::ImageBuf>>
read_planned(const std::string& path, const std::vector<std::vector<DecodeLevel>>& plan,
             const ReadOptions& options)
{
    std::vector<std::vector<OIIO::ImageBuf>> images(plan.size());
    const bool check = options.check_structure && is_openexr_file(path);
    if (check) {
        std::vector<DecodeLevel> levels;
        for (const std::vector<DecodeLevel>& subimage : plan)
            levels.insert(levels.end(), subimage.begin(), subimage.end());
        if (auto decoded = decode_isolated(path, levels, options.decode_timeout)) {
            std::size_t next = 0;
            for (std::size_t s = 0; s < plan.size(); ++s)
                for (std::size_t m = 0; m < plan[s].size(); ++m)
                    images[s].push_back(std::move((*decoded)[next++]));
            return images;
        }
    }
    if (check)
        check_openexr_structure(path);
    for (std::size_t s = 0; s < plan.size(); ++s)
        for (const DecodeLevel& level : plan[s])
            images[s].push_back(read_level(path, level.subimage, level.miplevel));
    return images;
}

void check_readable(const std::string& path)
{
    const std::string problem = input_path_problem(path);
    if (!problem.empty())
        throw FileError(path + ": " + problem);
}

}  // namespace

void silence_library_debug_messages()
{
    if (!std::getenv("OPENIMAGEIO_DEBUG"))
        OIIO::attribute("debug", 0);
}

void check_image_file(const std::string& path, const ReadOptions& options)
{
    check_readable(path);
    int subimages = 0;
    open_checked(path, 0, subimages, options, options.check_structure);
}

OIIO::ImageSpec read_image_header(const std::string& path, const ReadOptions& options)
{
    check_readable(path);
    const ForgetOnExit forget{path};
    int subimages = 0;
    return open_checked(path, 0, subimages, options)->spec();
}

std::vector<OIIO::ImageSpec> read_image_headers(const std::string& path, const ReadOptions& options)
{
    check_readable(path);
    const ForgetOnExit forget{path};
    std::vector<OIIO::ImageSpec> specs;
    for (const std::vector<DecodeLevel>& subimage : plan_read(path, options, true, false))
        specs.push_back(subimage.front().spec);
    return specs;
}

OIIO::ImageBuf read_image_file(const std::string& path, const ReadOptions& options)
{
    check_readable(path);
    const ForgetOnExit forget{path};
    return std::move(read_planned(path, plan_read(path, options, false, false), options)[0][0]);
}

std::vector<OIIO::ImageBuf> read_image_subimages(const std::string& path,
                                                 const ReadOptions& options, MipLevels* mip_levels)
{
    check_readable(path);
    const ForgetOnExit forget{path};
    std::vector<std::vector<OIIO::ImageBuf>> levels =
        read_planned(path, plan_read(path, options, true, mip_levels != nullptr), options);
    std::vector<OIIO::ImageBuf> images;
    if (mip_levels)
        mip_levels->clear();
    for (std::vector<OIIO::ImageBuf>& subimage : levels) {
        images.push_back(std::move(subimage.front()));
        if (mip_levels)
            mip_levels->emplace_back(std::make_move_iterator(subimage.begin() + 1),
                                     std::make_move_iterator(subimage.end()));
    }
    const int subimages = int(images.size());
    // The file's count, as OIIO reports it on a single-part file's spec.
    images[0].specmod().attribute("oiio:subimages", subimages);
    return images;
}

void write_image_file(const OIIO::ImageBuf& image, const std::string& path)
{
    write_image_file(std::vector<OIIO::ImageBuf>{image}, path, WriteOptions{});
}

void write_image_file(const std::vector<OIIO::ImageBuf>& subimages, const std::string& path,
                      const WriteOptions& options, const MipLevels& mip_levels)
{
    check_target(path);
    if (!mip_levels.empty() && mip_levels.size() != subimages.size())
        cannot_write(path, "MIP levels given for " + std::to_string(mip_levels.size()) +
                               " subimages of " + std::to_string(subimages.size()));
    // OIIO 2.4 writes MIP levels into single-part files only; dropping them would lose
    // what was read.
    for (std::size_t s = 0; s < mip_levels.size() && subimages.size() > 1; ++s)
        if (!mip_levels[s].empty())
            cannot_write(path, "subimage " + std::to_string(s) + " has " +
                                   std::to_string(mip_levels[s].size() + 1) +
                                   " MIP levels, which statmc cannot write into a multi-part "
                                   "file (keep one part with --subimage, or write each alone)");
    const bool mip_mapped =
        std::any_of(mip_levels.begin(), mip_levels.end(), [](const auto& l) { return !l.empty(); });
    auto out = image_writer(path, subimages, mip_mapped);
    const bool openexr = is_openexr_writer(*out);
    static const std::vector<OIIO::ImageBuf> none;
    auto levels_of = [&](std::size_t s) -> const std::vector<OIIO::ImageBuf>& {
        return mip_levels.empty() ? none : mip_levels[s];
    };
    // The storage rules, the user's overrides, and for a MIP map the tiles it needs.
    auto stored_spec = [&](const OIIO::ImageSpec& image_spec, bool mip_mapped) {
        OIIO::ImageSpec spec = image_spec;
        if (openexr)
            apply_storage_rules(spec);
        if (options.format != OIIO::TypeDesc::UNKNOWN)
            spec.set_format(options.format);
        if (!options.compression.empty())
            spec.attribute("compression", options.compression);
        if (mip_mapped) {
            spec.tile_width = image_spec.tile_width > 0 ? image_spec.tile_width : 64;
            spec.tile_height = image_spec.tile_height > 0 ? image_spec.tile_height : 64;
            spec.tile_depth = 1;
            // OIIO's EXR writer makes a MIP map only of a "Plain Texture".
            spec.attribute("textureformat", "Plain Texture");
            spec.attribute("openexr:levelmode", 1);  // Imf::MIPMAP_LEVELS
        }
        return spec;
    };
    std::vector<OIIO::ImageSpec> specs;
    for (std::size_t s = 0; s < subimages.size(); ++s)
        specs.push_back(stored_spec(subimages[s].spec(), !levels_of(s).empty()));

    write_file_atomically(path, [&](const std::string& temporary) {
        // The library's message, with the system's reason when it leaves it out (OpenEXR
        // says "File output failed." on a full disk).
        auto fail = [&](std::string why) {
            // The user knows the target, not the temporary the library names.
            for (std::size_t at = 0; (at = why.find(temporary, at)) != std::string::npos;
                 at += path.size())
                why.replace(at, temporary.size(), path);
            const std::string limit = storage_limit_reached(temporary);
            if (!limit.empty())
                why = limit + ": " + why;
            cannot_write(path, why);
        };
        if (!out->open(temporary, int(specs.size()), specs.data()))
            fail(out->geterror());
        for (std::size_t s = 0; s < subimages.size(); ++s) {
            if (s > 0 && !out->open(temporary, specs[s], OIIO::ImageOutput::AppendSubimage))
                fail(out->geterror());
            if (!subimages[s].write(out.get()))
                fail(subimages[s].geterror());
            for (const OIIO::ImageBuf& level : levels_of(s)) {
                if (!out->open(temporary, stored_spec(level.spec(), true),
                               OIIO::ImageOutput::AppendMIPLevel))
                    fail(out->geterror());
                if (!level.write(out.get()))
                    fail(level.geterror());
            }
        }
        if (!out->close())
            fail(out->geterror());
        out.reset();
    });
    forget_cached(path);
}

}  // namespace statmc::layers
