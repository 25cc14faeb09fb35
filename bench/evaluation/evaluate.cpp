// statmc-evaluate: every method of docs/evaluation.md on noisy statistics EXRs of one
// scene, timed and compared with a reference. One CSV row per (input, method); the
// charts and the report are drawn from that CSV by scripts/plot_evaluation.py.
//
//   statmc-evaluate --reference REF.exr --scene NAME --csv out.csv NOISY.exr...
//   statmc-evaluate --radius-sweep 2,5,10,20 ...   (statmc's time against radius)
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <functional>
#include <iostream>
#include <optional>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "baselines/baselines.h"
#include "statmc/compare/compare.h"
#include "statmc/core/estimator_image.h"
#include "statmc/core/luminance.h"
#include "statmc/denoise/denoise.h"
#include "statmc/layers/exr_files.h"
#include "statmc/layers/float_pixels.h"
#include "statmc/layers/guide_layers.h"
#include "statmc/layers/layer_names.h"
#include "statmc/layers/statistics_layers.h"
#include "statmc/verify/verify.h"

namespace {

using namespace statmc;

/// Median wall time of `runs` calls.
double median_seconds(int runs, const std::function<void()>& body)
{
    std::vector<double> t;
    for (int i = 0; i < runs; ++i) {
        const auto start = std::chrono::steady_clock::now();
        body();
        t.push_back(
            std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
    }
    std::sort(t.begin(), t.end());
    return t[t.size() / 2];
}

/// A float R,G,B image shaped like `like`, filled by `fill(planes)`.
OIIO::ImageBuf rgb_image(const OIIO::ImageBuf& like,
                         const std::function<void(std::array<Plane, 3>&)>& fill)
{
    OIIO::ImageSpec spec(like.spec().width, like.spec().height, 3, OIIO::TypeDesc::FLOAT);
    spec.x = like.spec().x;
    spec.y = like.spec().y;
    spec.channelnames = {"R", "G", "B"};
    OIIO::ImageBuf out(spec);
    std::array<Plane, 3> planes;
    for (int c = 0; c < 3; ++c)
        planes[c] = layers::channel_plane(out, c);
    fill(planes);
    return out;
}

/// The baselines' inputs: the means and their variances, as core's estimators give them
/// for the untransformed test (variance of the mean, per-sample or not), and the guides.
struct BaselineInputs {
    EstimatorImage est;
    std::array<ConstPlane, 3> mean, variance;
    Guides guides;

    explicit BaselineInputs(const OIIO::ImageBuf& in)
        : est(estimators_from_statistics(layers::read_statistics(in), TestDomain::Untransformed))
    {
        for (int c = 0; c < 3; ++c) {
            mean[c] = dense_plane(est.value.data() + c * est.pixels(), est.width);
            variance[c] = dense_plane(est.test_variance.data() + c * est.pixels(), est.width);
        }
        const auto albedo = layers::find_guide_layer(in.spec(), layers::kAlbedoLayer, true);
        const auto normal = layers::find_guide_layer(in.spec(), layers::kNormalLayer, false);
        if (!albedo.empty())
            guides.albedo = layers::guide_planes(in, albedo);
        if (!normal.empty())
            guides.normal = layers::guide_planes(in, normal);
    }
};

struct Denoiser {
    std::string name;
    int radius;  ///< the method's own filter radius (NL-means: its search radius; 0: none)
    /// Empty for "noisy": the input itself, untimed.
    std::function<OIIO::ImageBuf(const OIIO::ImageBuf&)> run;
};

DenoiseImageOptions statmc_options(bool guides, DenoiseImageOptions o = DenoiseImageOptions{})
{
    o.guides.albedo = o.guides.normal = guides ? GuideUse::Required : GuideUse::Off;
    return o;
}

OIIO::ImageBuf run_statmc(const OIIO::ImageBuf& in, const DenoiseImageOptions& o)
{
    OIIO::ImageBuf out;
    if (!denoise(out, in, o))
        throw std::runtime_error(out.geterror());
    return out;
}

// The classic filter with one of the default method's stages added, as the default runs
// it: each stage's effect alone.
DenoiseImageOptions classic_with(void (*add)(DenoiseImageOptions&))
{
    DenoiseImageOptions o = statmc_options(true, DenoiseImageOptions::classic());
    add(o);
    return o;
}

std::vector<Denoiser> methods()
{
    const DenoiseImageOptions statmc = statmc_options(true), unguided = statmc_options(false),
                              classic = statmc_options(true, DenoiseImageOptions::classic()),
                              paper = statmc_options(false, DenoiseImageOptions::paper());
    DenoiseImageOptions moon = paper;  // Moon et al. 2013-style test
    moon.test = TestDomainChoice::Untransformed;
    moon.filter.alpha = 0.002;
    const baselines::NlmOptions nlm;
    const baselines::CrossBilateralOptions bilateral;
    auto statmc_method = [](const char* name, const DenoiseImageOptions& o) {
        return Denoiser{name, o.filter.radius,
                        [o](const OIIO::ImageBuf& in) { return run_statmc(in, o); }};
    };
    return {
        {"noisy", 0, {}},
        statmc_method("statmc", statmc),
        statmc_method("statmc-noguides", unguided),
        statmc_method("statmc-classic", classic),
        statmc_method("statmc-paper", paper),
        statmc_method("classic+ici", classic_with([](DenoiseImageOptions& o) {
                          o.stages.radius_ladder = true;
                          o.stages.ladder = DenoiseImageOptions{}.stages.ladder;
                      })),
        statmc_method("classic+guide-noise",
                      classic_with([](DenoiseImageOptions& o) { o.filter.guide_noise = true; })),
        statmc_method("classic+context", classic_with([](DenoiseImageOptions& o) {
                          o.stages.context_radius = DenoiseImageOptions{}.stages.context_radius;
                      })),
        statmc_method("moon-ci", moon),
        {"nlm", nlm.search_radius,
         [nlm](const OIIO::ImageBuf& in) {
             const BaselineInputs b(in);
             return rgb_image(in, [&](std::array<Plane, 3>& out) {
                 baselines::nlm(b.mean, b.variance, b.est.width, b.est.height, nlm, out);
             });
         }},
        {"cross-bilateral", bilateral.radius,
         [bilateral](const OIIO::ImageBuf& in) {
             const BaselineInputs b(in);
             return rgb_image(in, [&](std::array<Plane, 3>& out) {
                 baselines::cross_bilateral(b.mean, b.guides, b.est.width, b.est.height, bilateral,
                                            out);
             });
         }},
    };
}

/// The outside denoiser whose result is also verified (docs/method.md §15).
constexpr const char* kVerifiedCandidate = "oidn-guides";

/// `candidate` held to `in`'s statistics by the verify operator at its defaults, with the
/// default denoise (albedo + normal) for the pixels it rejects.
OIIO::ImageBuf run_verify(const OIIO::ImageBuf& in, const OIIO::ImageBuf& candidate)
{
    VerifyOptions o;
    o.denoise = statmc_options(true);
    OIIO::ImageBuf out;
    if (!verify(out, in, candidate, o))
        throw std::runtime_error(out.geterror());
    return out;
}

// X.exr's result by an outside denoiser NAME, if it was run: X.NAME.exr, whose
// statmc:denoiseSeconds attribute is its time (bench/evaluation/oidn_denoise.py writes it).
std::string external_result(const std::string& input, const std::string& name)
{
    const std::string stem = input.size() > 4 && input.compare(input.size() - 4, 4, ".exr") == 0
                                 ? input.substr(0, input.size() - 4)
                                 : input;
    return stem + "." + name + ".exr";
}

/// What the reference's own sampling noise alone adds to each metric: about
/// mean(v/(ref² + ε)) to relMSE and mean(v) to the squared error, v the variance of its
/// mean. Every method's measured error carries it too, so a method below it cannot be
/// told from the truth (docs/evaluation-notes.md). Absent for a reference without
/// statistics.
struct ReferenceNoise {
    double mse = 0, relmse = 0;
};

std::optional<ReferenceNoise> reference_noise(const OIIO::ImageBuf& reference, double epsilon)
{
    if (reference.spec().channelindex(layers::kSampleCountChannel) < 0 ||
        !layers::find_statistics(reference.spec()).has(layers::Statistic::Variance))
        return std::nullopt;
    const EstimatorImage est =
        estimators_from_statistics(layers::read_statistics(reference), TestDomain::Untransformed);
    ReferenceNoise noise;
    const std::size_t values = 3 * est.pixels();
    for (std::size_t i = 0; i < values; ++i) {
        const double v = est.test_variance[i], ref = est.value[i];
        noise.mse += v / double(values);
        noise.relmse += v / (ref * ref + epsilon) / double(values);
    }
    return noise;
}

/// The beauty's R,G,B as interleaved floats (channels found by name).
std::vector<float> beauty_rgb(const OIIO::ImageBuf& image)
{
    const OIIO::ImageSpec& spec = image.spec();
    std::vector<float> rgb(std::size_t(spec.width) * spec.height * 3);
    for (int c = 0; c < 3; ++c) {
        const int channel = spec.channelindex(std::string(1, "RGB"[c]));
        if (channel < 0)
            throw std::runtime_error(std::string(image.name()) + ": no " + "RGB"[c] + " channel");
        OIIO::ROI roi = image.roi();
        roi.chbegin = channel;
        roi.chend = channel + 1;
        image.get_pixels(roi, OIIO::TypeDesc::FLOAT, rgb.data() + c, 3 * sizeof(float),
                         OIIO::AutoStride);
    }
    return rgb;
}

/// The windows around emitters and highlights where light is weighed (docs/evaluation-
/// notes.md): pixels whose reference luminance is above both its 99.5th percentile and 4
/// times its median, grown by 2 pixels within the image. The same rule as
/// scripts/promise_check.py's.
struct HighlightWindows {
    std::vector<char> inside;
    double reference_sum = 0;

    HighlightWindows(const std::vector<float>& ref, int width, int height)
        : inside(std::size_t(width) * height, 0)
    {
        const std::size_t n = inside.size();
        std::vector<double> lum(n);
        for (std::size_t i = 0; i < n; ++i)
            lum[i] = luminance(double(ref[3 * i]), double(ref[3 * i + 1]), double(ref[3 * i + 2]));
        std::vector<double> sorted = lum;
        std::sort(sorted.begin(), sorted.end());
        auto quantile = [&](double q) {  // linear interpolation, as numpy's percentile
            const double at = q * double(n - 1);
            const std::size_t lo = std::size_t(at);
            const double frac = at - double(lo);
            return lo + 1 < n ? sorted[lo] + frac * (sorted[lo + 1] - sorted[lo]) : sorted[lo];
        };
        const double threshold = std::max(quantile(0.995), 4 * quantile(0.5));
        for (int y = 0; y < height; ++y)
            for (int x = 0; x < width; ++x) {
                if (lum[std::size_t(y) * width + x] < threshold)
                    continue;
                for (int wy = std::max(0, y - 2); wy <= std::min(height - 1, y + 2); ++wy)
                    for (int wx = std::max(0, x - 2); wx <= std::min(width - 1, x + 2); ++wx)
                        inside[std::size_t(wy) * width + wx] = 1;
            }
        reference_sum = sum(ref);
    }

    /// The image's light in the windows over the reference's.
    double energy(const std::vector<float>& rgb) const
    {
        return sum(rgb) / std::max(reference_sum, 1e-12);
    }

private:
    double sum(const std::vector<float>& rgb) const
    {
        double total = 0;
        for (std::size_t i = 0; i < inside.size(); ++i)
            if (inside[i])
                total += double(rgb[3 * i]) + rgb[3 * i + 1] + rgb[3 * i + 2];
        return total;
    }
};

int attribute(const OIIO::ImageBuf& in, const char* name)
{
    return in.spec().get_int_attribute(name, -1);
}

}  // namespace

int main(int argc, char** argv)
{
    CLI::App app{"statmc-evaluate: time and score every method on noisy statistics EXRs"};
    std::string reference_path, scene, csv_path, display_config = STATMC_DISPLAY_CONFIG;
    std::vector<std::string> inputs, externals;
    std::vector<int> radii;
    int runs = 3;
    app.add_option("--reference", reference_path, "reference EXR (R,G,B)")->required();
    app.add_option("--scene", scene, "scene name for the CSV")->required();
    app.add_option("--csv", csv_path, "CSV to append to (a header is written if new)")->required();
    app.add_option("--runs", runs, "timed runs per method (the median is kept)")
        ->check(CLI::PositiveNumber);
    app.add_option("--radius-sweep", radii, "instead: time statmc at these radii")->delimiter(',');
    app.add_option("--display-config", display_config, "OCIO config for DSSIM (Filmic view)");
    app.add_option("--external", externals,
                   "also score outside denoisers' results X.NAME.exr of each input X.exr, timed "
                   "by their statmc:denoiseSeconds attribute (oidn,oidn-guides; the latter "
                   "verified too)")
        ->delimiter(',')
        ->allow_extra_args(false);
    app.add_option("inputs", inputs, "noisy statistics EXRs")->required();
    CLI11_PARSE(app, argc, argv);

    try {
        const OIIO::ImageBuf reference = layers::read_image_file(reference_path);
        CompareOptions compare_options;
        compare_options.display = DisplayOptions{display_config, "", "Filmic"};
        const std::optional<ReferenceNoise> noise =
            reference_noise(reference, compare_options.relmse_epsilon);
        const bool fresh = !std::ifstream(csv_path).good();
        std::ofstream csv(csv_path, std::ios::app);
        if (fresh)
            csv << "scene,width,height,spp,seed,method,radius,render_seconds,denoise_seconds,rmse,"
                   "mae,relmse,dssim,mse,energy\n";
        const HighlightWindows windows(beauty_rgb(reference), reference.spec().width,
                                       reference.spec().height);
        for (const std::string& path : inputs) {
            const OIIO::ImageBuf in = layers::read_image_file(path);
            const float render_seconds = in.spec().get_float_attribute("statmc:renderTime", -1.f);
            auto row = [&](const std::string& method, int radius, double seconds,
                           const OIIO::ImageBuf& result) {
                CompareMetrics m;
                OIIO::ImageBuf error;
                if (!compare(m, error, result, reference, compare_options))
                    throw std::runtime_error(path + ": " + error.geterror());
                csv << scene << ',' << in.spec().width << ',' << in.spec().height << ','
                    << attribute(in, "statmc:spp") << ',' << attribute(in, "statmc:seed") << ','
                    << method << ',' << radius << ',' << render_seconds << ',' << seconds << ','
                    << m.rmse << ',' << m.mae << ',' << m.relmse << ',' << m.dssim << ','
                    << m.rmse * m.rmse << ',' << windows.energy(beauty_rgb(result)) << '\n';
                std::printf("%s %s r=%d: %.3f s, RMSE %.4g relMSE %.4g DSSIM %.4g\n", path.c_str(),
                            method.c_str(), radius, seconds, m.rmse, m.relmse, m.dssim);
            };
            if (!radii.empty()) {
                for (int r : radii) {
                    DenoiseImageOptions o = statmc_options(false);  // the default
                    o.filter.radius = r;
                    OIIO::ImageBuf out;
                    const double s = median_seconds(runs, [&] { out = run_statmc(in, o); });
                    row("statmc", r, s, out);
                }
                continue;
            }
            if (noise)  // a row of its own, so that each (scene, spp) table can show it
                csv << scene << ',' << in.spec().width << ',' << in.spec().height << ','
                    << attribute(in, "statmc:spp") << ',' << attribute(in, "statmc:seed")
                    << ",reference-noise,0," << render_seconds << ",0," << std::sqrt(noise->mse)
                    << ",nan," << noise->relmse << ",nan," << noise->mse << ",nan\n";
            for (const Denoiser& method : methods()) {
                if (!method.run) {
                    row(method.name, method.radius, 0.0, in);
                    continue;
                }
                OIIO::ImageBuf out;
                const double s = median_seconds(runs, [&] { out = method.run(in); });
                row(method.name, method.radius, s, out);
            }
            for (const std::string& name : externals) {
                const std::string result_path = external_result(path, name);
                if (!std::ifstream(result_path).good())
                    throw std::runtime_error(result_path + ": missing (--external " + name + ")");
                const OIIO::ImageBuf result = layers::read_image_file(result_path);
                const double seconds =
                    result.spec().get_float_attribute("statmc:denoiseSeconds", -1.f);
                row(name, 0, seconds, result);
                if (name != kVerifiedCandidate)
                    continue;
                // Verified OIDN: its time is OIDN's and the verify step's together.
                OIIO::ImageBuf verified;
                const double s = median_seconds(runs, [&] { verified = run_verify(in, result); });
                row("verified-" + name, 0, seconds + s, verified);
            }
        }
    } catch (const std::exception& e) {
        std::cerr << "statmc-evaluate: " << e.what() << '\n';
        return 1;
    }
    return 0;
}
