// Farm rendering as programs: tasks split a frame by sample index and merge back into one
// render's statistics; --tasks is that merge bit for bit; checkpoints survive SIGKILL and
// resume bitwise; checkpoints of other renders and damaged ones are refused (docs/farm.md).
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <thread>
#include <vector>

#include <fcntl.h>
#include <sys/wait.h>
#include <unistd.h>
#include <zlib.h>

#include <OpenImageIO/imagebuf.h>

#include "renderer_test_support.h"
#include "statmc/layers/sample_provenance.h"
#include "statmc/render/render_task.h"
#include "temp_dir.h"

namespace statmc::render::test {
namespace {

using statmc::test::file_bytes;

namespace fs = std::filesystem;

std::string quoted(const std::string& s) { return "\"" + s + "\""; }

ProgramRun render_cli(const std::string& args, const ScratchDir& dir)
{
    return run_program(quoted(STATMC_RENDER_EXE) + " " + args, dir);
}

// The room at 24x16: a few seconds of samples at most, paths of every length.
struct FarmScene {
    ScratchDir dir{"farm"};
    std::string scene = dir.write("room.pbrt", test_room());
    std::string common(int spp) const
    {
        return quoted(scene) + " --resolution 24x16 --spp " + std::to_string(spp) +
               " --seed 3 --threads 2 -q";
    }
};

OIIO::ImageBuf read(const std::string& path)
{
    OIIO::ImageBuf img(path);
    EXPECT_TRUE(img.read(0, 0, true, OIIO::TypeDesc::FLOAT)) << path << ": " << img.geterror();
    return img;
}

std::vector<float> pixels(const OIIO::ImageBuf& img)
{
    std::vector<float> v(std::size_t(img.spec().image_pixels()) * img.nchannels());
    EXPECT_TRUE(img.get_pixels(img.roi(), OIIO::TypeDesc::FLOAT, v.data()));
    return v;
}

// Channel names and every pixel bit equal.
void expect_bitwise_equal(const std::string& a, const std::string& b)
{
    const OIIO::ImageBuf x = read(a), y = read(b);
    ASSERT_EQ(x.spec().channelnames, y.spec().channelnames) << a << " vs " << b;
    const std::vector<float> px = pixels(x), py = pixels(y);
    ASSERT_EQ(px.size(), py.size());
    EXPECT_EQ(0, std::memcmp(px.data(), py.data(), px.size() * sizeof(float)))
        << a << " and " << b << " differ";
}

// Starts `args` in the background (stdout/stderr appended to `log`); returns its pid.
pid_t start(const std::vector<std::string>& args, const std::string& log)
{
    const pid_t pid = ::fork();
    if (pid == 0) {
        const int fd = ::open(log.c_str(), O_WRONLY | O_CREAT | O_APPEND, 0644);
        ::dup2(fd, 1);
        ::dup2(fd, 2);
        std::vector<char*> argv{const_cast<char*>(STATMC_RENDER_EXE)};
        for (const std::string& a : args)
            argv.push_back(const_cast<char*>(a.c_str()));
        argv.push_back(nullptr);
        ::execv(STATMC_RENDER_EXE, argv.data());
        ::_exit(127);
    }
    return pid;
}

// Waits (bounded) until `path` exists with a modification time other than `before`, or the
// process ends. True when it did.
bool wait_for_new_file(const std::string& path, fs::file_time_type before, pid_t pid)
{
    for (int i = 0; i < 3000; ++i) {  // 30 s
        std::error_code ec;
        if (fs::exists(path, ec) && fs::last_write_time(path, ec) != before)
            return true;
        if (::waitpid(pid, nullptr, WNOHANG) == pid)
            return false;
        std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
    return false;
}

int wait_exit(pid_t pid)
{
    int status = 0;
    ::waitpid(pid, &status, 0);
    return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
}

TEST(Farm, TasksSplitTheSampleIndicesDisjointlyAndCompletely)
{
    const int spp = 10, n = 3;
    int next = 0;
    for (int i = 0; i < n; ++i) {
        const layers::SampleRange r = task_samples(spp, {i, n});
        EXPECT_EQ(r.begin, next);
        EXPECT_GE(r.count(), spp / n);
        EXPECT_LE(r.count(), spp / n + 1);
        next = r.end;
    }
    EXPECT_EQ(next, spp);
    EXPECT_THROW(task_samples(3, {0, 4}), std::runtime_error);
    EXPECT_EQ(parse_task("2/4").index, 2);
    for (const char* bad : {"5/4", "0/0", "4/4", "-1/4", "1", "1/", "/4", "1/4x", "a/b"})
        EXPECT_THROW(parse_task(bad), std::runtime_error) << bad;
}

TEST(Farm, MergedTasksHoldTheStatisticsOfOneRender)
{
    const FarmScene f;
    const std::string whole = f.dir.file("whole.exr");
    ASSERT_EQ(render_cli(f.common(24) + " -o " + quoted(whole), f.dir).status, 0);
    std::string tasks;
    for (int i = 0; i < 4; ++i) {
        const std::string out = f.dir.file("t" + std::to_string(i) + ".exr");
        const ProgramRun r = render_cli(
            f.common(24) + " --task " + std::to_string(i) + "/4 -o " + quoted(out), f.dir);
        ASSERT_EQ(r.status, 0) << r.output;
        const OIIO::ImageSpec spec = read(out).spec();
        EXPECT_EQ(spec.get_int_attribute("statmc:taskIndex", -1), i);
        EXPECT_EQ(spec.get_int_attribute("statmc:taskCount"), 4);
        EXPECT_EQ(spec.get_int_attribute("statmc:seed", -1), 3);
        EXPECT_EQ(spec.get_int_attribute("statmc:sampleBegin", -1), 6 * i);
        EXPECT_EQ(spec.get_int_attribute("statmc:sampleEnd", -1), 6 * i + 6);
        tasks += " " + quoted(out);
    }
    const std::string merged = f.dir.file("merged.exr");
    const ProgramRun m =
        run_program(quoted(STATMC_CLI_EXE) + tasks + " --merge -o " + quoted(merged), f.dir);
    ASSERT_EQ(m.status, 0) << m.output;

    const OIIO::ImageBuf a = read(whole), b = read(merged);
    EXPECT_EQ(b.spec().get_int_attribute("statmc:spp"), 24);
    EXPECT_EQ(b.spec().get_int_attribute("statmc:seed", -1), 3);
    EXPECT_EQ(b.spec().get_int_attribute("statmc:sampleEnd", -1), 24);
    EXPECT_EQ(b.spec().find_attribute("statmc:taskIndex"), nullptr);
    // Mean, variance, count and guides: 1e-6 relative to the channel's largest value (float
    // storage rounds each part to 6e-8; the merge adds a few roundings).
    for (const char* name : {"R", "G", "B", "variance.R", "variance.G", "variance.B",
                             "sampleCount.Y", "albedo.R", "normal.Y", "depth.Z"}) {
        const int ca = a.spec().channelindex(name), cb = b.spec().channelindex(name);
        ASSERT_GE(ca, 0) << name;
        ASSERT_GE(cb, 0) << name;
        float scale = 0, worst = 0;
        for (int y = 0; y < 16; ++y)
            for (int x = 0; x < 24; ++x)
                scale = std::max(scale, std::abs(a.getchannel(x, y, 0, ca)));
        for (int y = 0; y < 16; ++y)
            for (int x = 0; x < 24; ++x)
                worst = std::max(worst,
                                 std::abs(a.getchannel(x, y, 0, ca) - b.getchannel(x, y, 0, cb)));
        EXPECT_LE(worst, 1e-6f * scale)
            << name << ": largest difference " << worst << " of values up to " << scale;
    }
}

TEST(Farm, TasksOptionIsBitwiseTheMergeOfTheTaskFiles)
{
    const FarmScene f;
    std::string tasks;
    for (int i = 0; i < 3; ++i) {
        const std::string out = f.dir.file("t" + std::to_string(i) + ".exr");
        ASSERT_EQ(render_cli(f.common(10) + " --task " + std::to_string(i) + "/3 -o " + quoted(out),
                             f.dir)
                      .status,
                  0);
        tasks += " " + quoted(out);
    }
    const std::string merged = f.dir.file("merged.exr"), local = f.dir.file("local.exr");
    ASSERT_EQ(
        run_program(quoted(STATMC_CLI_EXE) + tasks + " --merge -o " + quoted(merged), f.dir).status,
        0);
    const ProgramRun r = render_cli(f.common(10) + " --tasks 3 -o " + quoted(local), f.dir);
    ASSERT_EQ(r.status, 0) << r.output;
    expect_bitwise_equal(local, merged);
}

TEST(Farm, RenderKilledAtAnyMomentResumesBitwiseEqual)
{
    const FarmScene f;
    const std::string straight = f.dir.file("straight.exr"), out = f.dir.file("out.exr");
    ASSERT_EQ(render_cli(f.common(2000) + " -o " + quoted(straight), f.dir).status, 0);
    const std::string checkpoint = out + ".checkpoint", log = f.dir.file("runs.log");
    const std::vector<std::string> args{
        f.scene, "--resolution", "24x16",        "--spp", "2000",     "--seed", "3", "--threads",
        "2",     "-q",           "--checkpoint", "0.05",  "--resume", "-o",     out};
    // Killed three times, each soon after a fresh checkpoint (at a different point of the
    // render each time), then left to finish.
    int kills = 0;
    for (int round = 0; round < 3; ++round) {
        std::error_code ec;
        const auto before = fs::exists(checkpoint) ? fs::last_write_time(checkpoint, ec)
                                                   : fs::file_time_type::min();
        const pid_t pid = start(args, log);
        if (wait_for_new_file(checkpoint, before, pid)) {
            std::this_thread::sleep_for(std::chrono::milliseconds(7 * round));
            ::kill(pid, SIGKILL);
            kills += wait_exit(pid) == 128 + SIGKILL;
        } else {
            wait_exit(pid);
        }
    }
    EXPECT_GE(kills, 1) << "the render finished before it could be killed: make it longer";
    const pid_t last = start(args, log);
    ASSERT_EQ(wait_exit(last), 0) << file_bytes(log);
    EXPECT_NE(file_bytes(log).find("resuming from checkpoint"), std::string::npos)
        << file_bytes(log);
    EXPECT_FALSE(fs::exists(checkpoint)) << "removed once the output holds the render";
    expect_bitwise_equal(out, straight);
}

// A checkpoint left by a render stopped with SIGTERM (it saves the film and exits 130).
std::string stopped_render(const FarmScene& f, const std::string& out)
{
    const std::string checkpoint = out + ".checkpoint", log = f.dir.file("stop.log");
    const pid_t pid = start({f.scene, "--resolution", "24x16", "--spp", "100000", "--seed", "3",
                             "--threads", "2", "-q", "--checkpoint", "0.05", "-o", out},
                            log);
    EXPECT_TRUE(wait_for_new_file(checkpoint, fs::file_time_type::min(), pid));
    ::kill(pid, SIGTERM);
    EXPECT_EQ(wait_exit(pid), 130) << file_bytes(log);
    EXPECT_NE(file_bytes(log).find("run again with --resume"), std::string::npos)
        << file_bytes(log);
    EXPECT_FALSE(fs::exists(out)) << "a stopped task writes no output that could be merged";
    return checkpoint;
}

// `checkpoint` as a build that wrote checkpoint format `version` would have labelled it:
// the header's version field replaced and its checksum made anew (magic, header length,
// header, header CRC-32, film).
std::string with_checkpoint_version(const std::string& checkpoint, const std::string& version)
{
    std::uint32_t length = 0;
    std::memcpy(&length, checkpoint.data() + 8, sizeof length);
    std::string header = checkpoint.substr(12, length);
    const std::size_t at = header.find("\nversion=");
    const std::size_t end = header.find('\n', at + 1);
    header.replace(at, end - at, "\nversion=" + version);
    const std::uint32_t new_length = std::uint32_t(header.size());
    const std::uint32_t crc = std::uint32_t(crc32_z(
        crc32_z(0, nullptr, 0), reinterpret_cast<const Bytef*>(header.data()), header.size()));
    std::string out = checkpoint.substr(0, 8);
    out.append(reinterpret_cast<const char*>(&new_length), sizeof new_length);
    out += header;
    out.append(reinterpret_cast<const char*>(&crc), sizeof crc);
    out += checkpoint.substr(12 + length + 4);
    return out;
}

TEST(Farm, CheckpointsOfOtherRendersAndDamagedOnesAreRefused)
{
    const FarmScene f;
    const std::string out = f.dir.file("out.exr");
    const std::string checkpoint = stopped_render(f, out);
    const std::string good = file_bytes(checkpoint);
    const std::string base =
        quoted(f.scene) + " --spp 100000 --threads 2 -q --resume -o " + quoted(out);
    const std::pair<std::string, std::string> others[] = {
        {" --resolution 24x16 --seed 4", "(seed: '3' in the checkpoint, '4' in this render)"},
        {" --resolution 24x17 --seed 3",
         "(resolution: '24x16' in the checkpoint, '24x17' in this render)"},
        {" --resolution 24x16 --seed 3 --task 1/2",
         "(task: '0/1' in the checkpoint, '1/2' in this render)"},
        {" --resolution 24x16 --seed 3 --maxdepth 2", "(render settings: 'maxdepth 8"},
    };
    for (const auto& [options, message] : others) {
        const ProgramRun r = render_cli(base + options, f.dir);
        EXPECT_EQ(r.status, 1) << options;
        EXPECT_NE(r.output.find("checkpoint " + checkpoint + ": belongs to another render"),
                  std::string::npos)
            << r.output;
        EXPECT_NE(r.output.find(message), std::string::npos) << r.output;
        EXPECT_EQ(file_bytes(checkpoint), good) << "a refused checkpoint is left as it was";
    }
    const std::string same = base + " --resolution 24x16 --seed 3";
    // One of format 3, whose film held steering's quantities in full statistics: refused,
    // and kept.
    const std::string older = with_checkpoint_version(good, "3");
    std::ofstream(checkpoint, std::ios::binary | std::ios::trunc) << older;
    ProgramRun r = render_cli(same, f.dir);
    EXPECT_EQ(r.status, 1);
    EXPECT_NE(r.output.find("checkpoint " + checkpoint +
                            ": version 3, this statmc-render reads version 4"),
              std::string::npos)
        << r.output;
    EXPECT_EQ(file_bytes(checkpoint), older);
    std::ofstream(checkpoint, std::ios::binary | std::ios::trunc)
        << good.substr(0, good.size() / 2);
    r = render_cli(same, f.dir);
    EXPECT_EQ(r.status, 1);
    EXPECT_NE(r.output.find("checkpoint " + checkpoint + ": truncated"), std::string::npos)
        << r.output;
    std::string flipped = good;
    flipped[flipped.size() - 100] ^= 0x20;
    std::ofstream(checkpoint, std::ios::binary | std::ios::trunc) << flipped;
    r = render_cli(same, f.dir);
    EXPECT_EQ(r.status, 1);
    EXPECT_NE(r.output.find("corrupted: the film's checksum does not match"), std::string::npos)
        << r.output;
    EXPECT_FALSE(fs::exists(out));
}

TEST(Farm, CheckpointThatCannotBeWrittenKeepsThePreviousOne)
{
    const FarmScene f;
    const std::string out = f.dir.file("out.exr"), straight = f.dir.file("straight.exr");
    const std::string checkpoint = stopped_render(f, out);
    const std::string previous = file_bytes(checkpoint);
    // A file size limit far below a checkpoint's makes every write fail as a full disk
    // would (EFBIG instead of ENOSPC; SIGXFSZ ignored so that write() returns the error).
    const std::string log = f.dir.file("full.log");
    const std::string limited =
        "trap '' XFSZ; ulimit -f 16; exec " + quoted(STATMC_RENDER_EXE) + " " + quoted(f.scene) +
        " --resolution 24x16 --spp 100000 --seed 3 --threads 2 -q --checkpoint 0.05 --resume -o " +
        quoted(out) + " >> " + quoted(log) + " 2>&1";
    const pid_t pid = ::fork();
    if (pid == 0) {
        ::execl("/bin/sh", "sh", "-c", limited.c_str(), static_cast<char*>(nullptr));
        ::_exit(127);
    }
    for (int i = 0; i < 3000 && file_bytes(log).find("warning") == std::string::npos; ++i)
        std::this_thread::sleep_for(std::chrono::milliseconds(10));
    ::kill(pid, SIGTERM);
    EXPECT_EQ(wait_exit(pid), 130) << file_bytes(log);
    EXPECT_NE(file_bytes(log).find("cannot write checkpoint: File too large; the previous "
                                   "checkpoint is kept"),
              std::string::npos)
        << file_bytes(log);
    EXPECT_EQ(file_bytes(checkpoint), previous);
    for (const auto& entry : fs::directory_iterator(fs::path(out).parent_path()))
        EXPECT_EQ(entry.path().filename().string().find(".statmc-tmp"), std::string::npos)
            << "left behind: " << entry.path();
}

TEST(Farm, FramesRenderedWithOneSeedAreRefusedByTheTemporalDenoise)
{
    // The room is still: frames of one seed repeat each other's noise to the bit, as the
    // farm's frames did when every frame got the job's --seed.
    const FarmScene f;
    auto render_frame = [&](const std::string& name, int frame, int seed) {
        char path[64];
        std::snprintf(path, sizeof path, "%s.%04d.exr", name.c_str(), frame);
        const std::string args = quoted(f.scene) + " --resolution 24x16 --spp 8 --seed " +
                                 std::to_string(seed) + " --threads 2 -q -o " +
                                 quoted(f.dir.file(path));
        ASSERT_EQ(render_cli(args, f.dir).status, 0);
    };
    auto temporal = [&](const std::string& name) {
        return run_program(quoted(STATMC_CLI_EXE) + " " + quoted(f.dir.file(name + ".#.exr")) +
                               " --frames 1-2 --denoise:temporal=1 -o " +
                               quoted(f.dir.file(name + "-out.#.exr")),
                           f.dir);
    };
    for (int frame : {1, 2}) {
        render_frame("same", frame, 3);
        render_frame("own", frame, layers::frame_seed(3, frame));
    }
    const ProgramRun same = temporal("same");
    EXPECT_EQ(same.status, 1) << same.output;
    EXPECT_NE(
        same.output.find(".exr): it and the frame denoised drew the same samples (seed 3, samples "
                         "0..7): merged over time they would count twice"),
        std::string::npos)
        << same.output;
    EXPECT_FALSE(fs::exists(f.dir.file("same-out.0001.exr")));
    EXPECT_FALSE(fs::exists(f.dir.file("same-out.0002.exr")));
    const ProgramRun own = temporal("own");
    EXPECT_EQ(own.status, 0) << own.output;

    // Without the header's seed (another renderer, or the attribute stripped) the pixels
    // still tell.
    for (int frame : {1, 2}) {
        char from[64], to[64];
        std::snprintf(from, sizeof from, "same.%04d.exr", frame);
        std::snprintf(to, sizeof to, "bare.%04d.exr", frame);
        OIIO::ImageBuf img = read(f.dir.file(from));
        for (const char* name : {"statmc:seed", "statmc:sampleBegin", "statmc:sampleEnd"})
            img.specmod().erase_attribute(name);
        ASSERT_TRUE(img.write(f.dir.file(to))) << img.geterror();
    }
    const ProgramRun bare = temporal("bare");
    EXPECT_EQ(bare.status, 1) << bare.output;
    EXPECT_NE(bare.output.find("noisy pixels, bit for bit: they were rendered with one seed"),
              std::string::npos)
        << bare.output;
}

TEST(Farm, EveryFrameOfASequenceRecordsTheSeedItDrewWith)
{
    const FarmScene f;
    const ProgramRun r =
        render_cli(f.common(4) + " --frames 1-2 -o " + quoted(f.dir.file("seq.#.exr")), f.dir);
    ASSERT_EQ(r.status, 0) << r.output;
    for (int frame : {1, 2}) {
        char name[64];
        std::snprintf(name, sizeof name, "seq.%04d.exr", frame);
        EXPECT_EQ(read(f.dir.file(name)).spec().get_int_attribute("statmc:seed", -1),
                  layers::frame_seed(3, frame));
    }
}

}  // namespace
}  // namespace statmc::render::test
