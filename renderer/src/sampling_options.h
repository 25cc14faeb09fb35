// The command-line options of the sampling strategies (Russian roulette, MIS), shared by
// statmc-render and bench/bench_sampling so that both spell and check them alike.
// Header-only: only programs that link CLI11 include it.
#pragma once

#include <string>

#include <CLI/CLI.hpp>

#include "integrator.h"

namespace statmc::render {

struct SamplingOptions {
    std::string rr = "classic";
    std::string mis = "standard";
    RouletteSettings roulette;
    MisSettings mis_settings;

    /// Copies the choices into `settings` (maxdepth is left alone).
    void apply(IntegratorSettings& settings) const
    {
        settings.roulette = roulette;
        settings.roulette.mode = rr == "acrr" ? RouletteMode::Acrr : RouletteMode::Classic;
        settings.mis = mis_settings;
        settings.mis.mode = mis == "selective" ? MisMode::Selective : MisMode::Standard;
    }
};

inline void add_sampling_options(CLI::App& app, SamplingOptions& o)
{
    app.add_option("--rr", o.rr,
                   "Russian roulette: classic (pbrt-v3, from the throughput) or acrr (approximate "
                   "contribution from denoised per-bounce radiance, method.md §7)")
        ->capture_default_str()
        ->check(CLI::IsMember({"classic", "acrr"}));
    app.add_option("--rr-bounces", o.roulette.tracked_bounces,
                   "ACRR: tracked bounces beside the pixel (layers bounce0L..bounce<N>L)")
        ->capture_default_str()
        ->check(CLI::Range(1, 32));
    app.add_option("--rr-start-bounce", o.roulette.start_bounce,
                   "roulette after the BSDF sample at vertices >= this one (0 = first hit; 4 = pbrt-v3)")
        ->capture_default_str()
        ->check(CLI::NonNegativeNumber);
    app.add_option("--mis", o.mis,
                   "MIS: standard (power heuristic) or selective (skip a technique whose denoised win "
                   "share is below --mis-threshold, method.md §8)")
        ->capture_default_str()
        ->check(CLI::IsMember({"standard", "selective"}));
    app.add_option("--mis-bounces", o.mis_settings.tracked_bounces,
                   "SMIS: tracked vertices (layers bounce<j>LightWins, bounce<j>BsdfWins)")
        ->capture_default_str()
        ->check(CLI::Range(1, 32));
    app.add_option("--mis-threshold", o.mis_settings.threshold, "SMIS: win-share threshold, in [0, 0.5)")
        ->capture_default_str()
        ->check(CLI::Range(0.0, 0.4999));
}

}  // namespace statmc::render
