// The command-line options of the sampling strategies (Russian roulette, MIS), shared by
// statmc-render and bench/bench_sampling so that both spell and check them alike.
// Header-only: only programs that link CLI11 include it.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include <CLI/CLI.hpp>

#include "statmc/render/integrator.h"

namespace statmc::render {

struct SamplingOptions {
    RouletteSettings roulette;
    MisSettings mis;

    /// Copies the choices into `settings` (maxdepth is left alone).
    void apply(IntegratorSettings& settings) const
    {
        settings.roulette = roulette;
        settings.mis = mis;
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
}

}  // namespace statmc::render
