// Helpers shared by the renderer tests: scratch directories and tiny scenes as strings.
#pragma once

#include <filesystem>
#include <fstream>
#include <string>

#include <unistd.h>

namespace statmc::render::test {

/// A fresh directory under the system temp dir, removed with everything in it.
class ScratchDir {
public:
    explicit ScratchDir(const std::string& tag)
    {
        static int serial = 0;
        path_ = std::filesystem::temp_directory_path() /
                ("statmc-render-test-" + tag + "-" + std::to_string(::getpid()) + "-" + std::to_string(serial++));
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

/// The shared scenes folder (../shared beside the source tree), or "" when absent.
inline std::string shared_dir()
{
    const std::string dir = STATMC_SHARED_DIR;
    return std::filesystem::is_directory(dir + "/scenes") ? dir : std::string();
}

/// An axis-aligned quad as a pbrt trianglemesh with its normal given explicitly.
inline std::string quad(const std::string& p, const std::string& n)
{
    return "Shape \"trianglemesh\" \"integer indices\" [0 1 2 0 2 3] \"point P\" [" + p + "] \"normal N\" [" + n +
           " " + n + " " + n + " " + n + "]\n";
}

/// A grey room (floor, back wall, ceiling) lit by a small quad under the ceiling: light
/// bounces around, so paths are long enough for roulette and both MIS techniques.
inline std::string test_room(int maxdepth = 8)
{
    return "LookAt 0 1 3  0 1 0  0 1 0\nCamera \"perspective\" \"float fov\" 60\n"
           "Integrator \"path\" \"integer maxdepth\" " + std::to_string(maxdepth) + "\nWorldBegin\n"
           "AttributeBegin\nAreaLightSource \"diffuse\" \"rgb L\" [8 8 8]\n" +
           quad("-0.3 1.99 -0.3  0.3 1.99 -0.3  0.3 1.99 0.3  -0.3 1.99 0.3", "0 -1 0") +
           "AttributeEnd\nMaterial \"matte\" \"rgb Kd\" [0.7 0.7 0.7]\n" +
           quad("-1 0 -1  1 0 -1  1 0 1  -1 0 1", "0 1 0") + quad("-1 2 -1  1 2 -1  1 2 1  -1 2 1", "0 -1 0") +
           quad("-1 0 -1  1 0 -1  1 2 -1  -1 2 -1", "0 0 1") + "WorldEnd\n";
}

}  // namespace statmc::render::test
