#include "statmc/render/exr_output.h"

#include <filesystem>
#include <stdexcept>

#include "statmc/core/plane.h"
#include "statmc/layers/exr_files.h"
#include "statmc/layers/layer_names.h"
#include "statmc/layers/statistics_layers.h"

namespace statmc::render {

namespace fs = std::filesystem;

namespace {

// `planes` without the higher moments, which a file carries only when asked for.
StatisticsPlanes without_higher_moments(StatisticsPlanes planes)
{
    planes.moment3.clear();
    planes.moment4.clear();
    planes.bc_moment4.clear();
    return planes;
}

}  // namespace

OIIO::ImageBuf make_output_image(const Film& film, const OutputInfo& info)
{
    StatisticsPlanes planes = film.stats.planes();
    if (!info.higher_moments)
        planes = without_higher_moments(std::move(planes));
    const std::vector<float> albedo = film.albedo(), normal = film.normal(), depth = film.depth();
    const std::size_t n = std::size_t(film.width) * film.height;
    layers::GuidePlanes guides;
    for (int c = 0; c < 3; ++c) {
        guides.albedo[c] = dense_plane(albedo.data() + c * n, film.width);
        guides.normal[c] = dense_plane(normal.data() + c * n, film.width);
    }
    guides.depth = dense_plane(depth.data(), film.width);
    const std::vector<float> albedo_variance = film.albedo_variance();
    const std::vector<float> normal_variance = film.normal_variance();
    guides.albedo_variance = dense_plane(albedo_variance.data(), film.width);
    guides.normal_variance = dense_plane(normal_variance.data(), film.width);
    const std::vector<float> motion = film.motion();
    if (!motion.empty())
        guides.motion = {dense_plane(motion.data(), film.width),
                         dense_plane(motion.data() + n, film.width)};
    layers::StatisticsMetadata meta;
    if (info.spp.uniform)
        meta.spp = info.spp.min;
    // Per-bounce quantities: one Y AOV each, sharing sampleCount.Y (docs/exr-layers.md).
    std::vector<StatisticsPlanes> groups;
    std::vector<layers::AovStatistics> aovs;
    if (film.bounces) {
        groups = film.bounces->group_planes();
        if (!info.higher_moments)
            for (StatisticsPlanes& group : groups)
                group = without_higher_moments(std::move(group));
        const BounceLayout& layout = film.bounces->layout();
        for (int q = 0; q < layout.quantities(); ++q)
            aovs.push_back({layout.aov(q), BounceStatistics::quantity_view(groups, q)});
    }
    OIIO::ImageBuf image = layers::make_statistics_image(planes.view(), meta, guides, aovs);
    if (!info.spp.uniform) {
        image.specmod().attribute(layers::attr::kSppMin, info.spp.min);
        image.specmod().attribute(layers::attr::kSppMean, float(info.spp.mean));
    }
    layers::write_sample_provenance(image.specmod(), info.provenance);
    image.specmod().attribute(layers::attr::kRenderTime, info.render_seconds);
    image.specmod().attribute(layers::attr::kScene, info.scene);
    if (info.frame)
        image.specmod().attribute(layers::attr::kFrame, *info.frame);
    return image;
}

void write_exr(const OIIO::ImageBuf& image, const std::string& path)
{
    layers::write_image_file(image, path);  // temporary file + rename, storage rules
}

std::string denoised_path(const std::string& path)
{
    fs::path p(path);
    const std::string ext = p.extension().string();
    p.replace_extension();
    return p.string() + ".denoised" + (ext.empty() ? ".exr" : ext);
}

}  // namespace statmc::render
