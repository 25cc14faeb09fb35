// The command-line options of the sampling strategies (Russian roulette, MIS, adaptive
// sampling), shared by
// statmc-render and bench/bench_sampling so that both spell and check them alike.
// Header-only: only programs that link CLI11 include it.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include <CLI/CLI.hpp>

#include "option_checks.h"

#include "statmc/render/adaptive_sampling.h"
#include "statmc/render/integrator.h"
#include "statmc/render/render_loop.h"

namespace statmc::render {

struct SamplingOptions {
    RouletteSettings roulette;
    MisSettings mis;
    /// The radius of the filter that denoises the per-bounce estimates ACRR and SMIS steer by.
    int estimates_radius = RenderSettings{}.bounce_filter.radius;

    /// Copies the choices into `settings` (maxdepth is left alone).
    void apply(RenderSettings& settings) const
    {
        settings.integrator.roulette = roulette;
        settings.integrator.mis = mis;
        settings.bounce_filter.radius = estimates_radius;
    }
};

/// An option read straight into an enum field from its spellings: help, default and
/// errors as CLI::IsMember over the spellings gives them ("x not in {a,b}"), and
/// nothing else accepted (CLI::CheckedTransformer would also take the enum's numbers).
template <class Mode>
CLI::Option* add_mode_option(CLI::App& app, const std::string& name, Mode& mode,
                             const std::vector<std::pair<std::string, Mode>>& spellings,
                             const std::string& help)
{
    std::string set, current;
    for (const auto& [spelling, value] : spellings) {
        set += (set.empty() ? "{" : ",") + spelling;
        if (value == mode)
            current = spelling;
    }
    set += "}";
    const CLI::Validator spelled(
        [spellings, set](std::string& input) -> std::string {
            for (const auto& [spelling, value] : spellings)
                if (input == spelling) {
                    input = std::to_string(int(value));
                    return {};
                }
            return input + " not in " + set;
        },
        set);
    return app.add_option(name, mode, help)
        ->type_name("TEXT")
        ->default_str(current)
        ->transform(spelled);
}

inline void add_sampling_options(CLI::App& app, SamplingOptions& o)
{
    add_mode_option<RouletteMode>(
        app, "--rr", o.roulette.mode,
        {{"classic", RouletteMode::Classic}, {"acrr", RouletteMode::Acrr}},
        "Russian roulette: classic (pbrt-v3, from the throughput) or acrr (approximate "
        "contribution from denoised per-bounce radiance, docs/method.md §7)");
    app.add_option("--rr-bounces", o.roulette.tracked_bounces,
                   "ACRR: tracked bounces beside the pixel (layers bounce0L..bounce<N>L)")
        ->capture_default_str()
        ->check(CLI::Range(1, 32));
    app.add_option(
           "--rr-start-bounce", o.roulette.start_bounce,
           "roulette after the BSDF sample at vertices >= this one (0 = first hit; 4 = pbrt-v3)")
        ->capture_default_str()
        ->check(CLI::NonNegativeNumber);
    add_mode_option<MisMode>(
        app, "--mis", o.mis.mode,
        {{"standard", MisMode::Standard}, {"selective", MisMode::Selective}},
        "MIS: standard (power heuristic) or selective (skip a technique whose denoised win "
        "share is below --mis-threshold, docs/method.md §8)");
    app.add_option("--mis-bounces", o.mis.tracked_bounces,
                   "SMIS: tracked vertices (layers bounce<j>LightWins, bounce<j>BsdfWins)")
        ->capture_default_str()
        ->check(CLI::Range(1, 32));
    app.add_option("--mis-threshold", o.mis.threshold, "SMIS: win-share threshold, in [0, 0.5)")
        ->capture_default_str()
        ->check(CLI::Range(0.0, 0.4999));
    app.add_option("--estimates-radius", o.estimates_radius,
                   "ACRR/SMIS: radius of the filter that denoises the per-bounce estimates after "
                   "each iteration (docs/sampling.md)")
        ->capture_default_str()
        ->check(CLI::Range(0, 64));
}

/// --adaptive and its settings; the settings need the flag.
inline void add_adaptive_options(CLI::App& app, AdaptiveSettings& a)
{
    auto* flag = app.add_flag(
        "--adaptive", a.enabled,
        "adaptive sampling: after --adaptive-min-spp uniform samples, each iteration spends "
        "its samples where the denoised estimate is least certain (docs/sampling.md) "
        "[default: off]");
    app.add_option("--noise-threshold", a.noise_threshold,
                   "adaptive: a pixel stops once the 95% interval of its own mean is within "
                   "± this fraction of its value; 0 = none stops, samples only move")
        ->capture_default_str()
        ->check(number_at_least(0))
        ->needs(flag);
    app.add_option("--adaptive-min-spp", a.min_spp,
                   "adaptive: samples per pixel every pixel takes before sampling adapts, and "
                   "the fewest a pixel holds before it may stop")
        ->capture_default_str()
        ->check(CLI::Range(1, 1 << 20))
        ->needs(flag);
    app.add_option("--adaptive-min-rate", a.min_rate,
                   "adaptive: every pixel that has not stopped takes at least this fraction of "
                   "an iteration's samples per pixel (and at least 1)")
        ->capture_default_str()
        ->check(CLI::Range(0.001, 1.0))
        ->needs(flag);
}

}  // namespace statmc::render
