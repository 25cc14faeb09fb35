// Helpers shared by the renderer tests: scratch directories, tiny scenes as strings,
// whole renders in-process and sample-by-sample comparisons of two integrators.
#pragma once

#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <memory>
#include <sstream>
#include <string>

#include <sys/wait.h>
#include <unistd.h>

#include "statmc/render/camera.h"
#include "statmc/render/integrator.h"
#include "statmc/render/render_loop.h"
#include "statmc/render/scene.h"
#include "statmc/render/scene_description.h"

namespace statmc::render::test {

/// A fresh directory under the system temp dir, removed with everything in it.
class ScratchDir {
public:
    explicit ScratchDir(const std::string& tag)
    {
        static int serial = 0;
        path_ = std::filesystem::temp_directory_path() /
                ("statmc-render-test-" + tag + "-" + std::to_string(::getpid()) + "-" +
                 std::to_string(serial++));
        std::filesystem::create_directories(path_);
    }
    ~ScratchDir()
    {
        std::error_code ignored;
        std::filesystem::remove_all(path_, ignored);
    }
    ScratchDir(const ScratchDir&) = delete;
    ScratchDir& operator=(const ScratchDir&) = delete;

    std::string file(const std::string& name) const { return (path_ / name).string(); }
    std::string write(const std::string& name, const std::string& text) const
    {
        std::ofstream(path_ / name, std::ios::binary) << text;
        return file(name);
    }

private:
    std::filesystem::path path_;
};

/// What a program run through the shell did.
struct ProgramRun {
    int status;          ///< exit status; -1 when it did not exit normally
    std::string output;  ///< stdout and stderr
};

/// Runs `command` (a shell command line) with stdout and stderr captured in `dir`.
inline ProgramRun run_program(const std::string& command, const ScratchDir& dir)
{
    const std::string log = dir.file("log.txt");
    const int raw = std::system((command + " > \"" + log + "\" 2>&1").c_str());
    std::ifstream in(log);
    std::stringstream ss;
    ss << in.rdbuf();
    return {WIFEXITED(raw) ? WEXITSTATUS(raw) : -1, ss.str()};
}

/// The shared scenes folder (../shared beside the source tree), or "" when absent.
inline std::string shared_dir()
{
    const std::string dir = STATMC_SHARED_DIR;
    return std::filesystem::is_directory(dir + "/scenes") ? dir : std::string();
}

/// An axis-aligned quad as a pbrt trianglemesh with its normal given explicitly.
inline std::string quad(const std::string& p, const std::string& n)
{
    return "Shape \"trianglemesh\" \"integer indices\" [0 1 2 0 2 3] \"point P\" [" + p +
           "] \"normal N\" [" + n + " " + n + " " + n + " " + n + "]\n";
}

/// A grey room (floor, back wall, ceiling) lit by a small quad under the ceiling: light
/// bounces around, so paths are long enough for roulette and both MIS techniques.
inline std::string test_room(int maxdepth = 8)
{
    return "LookAt 0 1 3  0 1 0  0 1 0\nCamera \"perspective\" \"float fov\" 60\n"
           "Integrator \"path\" \"integer maxdepth\" " +
           std::to_string(maxdepth) +
           "\nWorldBegin\n"
           "AttributeBegin\nAreaLightSource \"diffuse\" \"rgb L\" [8 8 8]\n" +
           quad("-0.3 1.99 -0.3  0.3 1.99 -0.3  0.3 1.99 0.3  -0.3 1.99 0.3", "0 -1 0") +
           "AttributeEnd\nMaterial \"matte\" \"rgb Kd\" [0.7 0.7 0.7]\n" +
           quad("-1 0 -1  1 0 -1  1 0 1  -1 0 1", "0 1 0") +
           quad("-1 2 -1  1 2 -1  1 2 1  -1 2 1", "0 -1 0") +
           quad("-1 0 -1  1 0 -1  1 2 -1  -1 2 -1", "0 0 1") + "WorldEnd\n";
}

struct Rendered {
    std::unique_ptr<Film> film;
    RenderStats stats;
    std::uint64_t rays = 0;  ///< rays traced (Embree queries)
};

/// Renders `desc` at w×h with the progressive schedule to `spp` (adaptively with
/// `adaptive`); the integrator takes the scene's maxdepth, and the film tracks what
/// `integrator` needs, with `bounce_layers` every per-bounce quantity in full too.
inline Rendered render_scene(const SceneDescription& desc, int w, int h, int spp,
                             std::uint64_t seed, int threads, IntegratorSettings integrator = {},
                             const AdaptiveSettings& adaptive = {}, bool bounce_layers = false)
{
    Scene scene(desc);
    scene.enable_profiling(true);
    const Camera camera(desc.camera, w, h);
    RenderSettings rs;
    rs.width = w;
    rs.height = h;
    rs.schedule = schedule_for_spp(spp);
    rs.seed = seed;
    rs.threads = threads;
    integrator.maxdepth = desc.maxdepth;
    rs.integrator = integrator;
    rs.adaptive = adaptive;
    Rendered r{std::make_unique<Film>(w, h, bounce_layout_for(integrator),
                                      bounce_layers_for(integrator, bounce_layers)),
               {},
               0};
    r.stats = render(scene, camera, rs, *r.film);
    r.rays = scene.traversal_counters().rays;
    return r;
}

/// How many of 256 camera samples (one per pixel of a 16×16 camera, same random numbers)
/// `a` and `b` (given `estimates`) compute differently, bit for bit.
inline int differing_samples(const PathIntegrator& a, const PathIntegrator& b, const Camera& camera,
                             const PixelEstimates& estimates, std::uint64_t seed)
{
    int differ = 0;
    for (int i = 0; i < 256; ++i) {
        Sampler sa(seed, std::uint64_t(i), 0), sb(seed, std::uint64_t(i), 0);
        GuideSample ga, gb;
        const Ray ray = camera.generate(float(i % 16) + 0.5f, float(i / 16) + 0.5f);
        const Rgb x = a.radiance(ray, sa, ga), y = b.radiance(ray, sb, gb, nullptr, &estimates);
        differ += !(x.r == y.r && x.g == y.g && x.b == y.b);
    }
    return differ;
}

}  // namespace statmc::render::test
