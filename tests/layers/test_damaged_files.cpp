// Damaged and hostile files end in a clear FileError naming them, before a crash, a hang or
// a huge allocation can happen: OpenEXR's own check, the memory budget on what a header
// declares, and deep images refused before their pixels are touched.
#include <gtest/gtest.h>

#include <csignal>
#include <filesystem>
#include <fstream>

#include <sys/wait.h>
#include <unistd.h>

#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfOutputFile.h>
#include <OpenImageIO/imagebuf.h>

#include "read_error.h"
#include "statmc/layers/atomic_file.h"
#include "statmc/layers/exr_files.h"
#include "statmc/layers/file_error.h"
#include "statmc/layers/statistics_layers.h"
#include "temp_dir.h"
#include "test_images.h"

namespace statmc::test {
namespace {

TEST(DamagedFiles, TruncatedAnywhereIsAnErrorNamingTheFile)
{
    TempDir dir;
    const std::string good = dir.file("good.exr");
    layers::write_image_file(
        layers::make_statistics_image(noisy_statistics(40, 30, 8, 3), {"", 8, 1}), good);
    const std::string bytes = file_bytes(good);
    ASSERT_TRUE(read_error(good).empty()) << read_error(good);
    for (double fraction : {0.0, 0.001, 0.01, 0.1, 0.5, 0.9, 0.999}) {
        const std::string cut = dir.file("cut.exr");
        std::ofstream(cut, std::ios::binary | std::ios::trunc)
            << bytes.substr(0, std::size_t(fraction * double(bytes.size())));
        const std::string e = read_error(cut);
        EXPECT_EQ(e.rfind(cut + ": ", 0), 0u) << fraction << ": " << e;
        // Without OpenEXR's check, the reader itself still fails cleanly.
        layers::ReadOptions trusting;
        trusting.check_structure = false;
        EXPECT_EQ(read_error(cut, trusting).rfind(cut + ": ", 0), 0u) << fraction;
    }
}

TEST(DamagedFiles, AHugeDeclaredImageIsRefusedBeforeAnyPixelIsAllocated)
{
    TempDir dir;
    const std::string huge = dir.file("huge.exr");
    {  // A 100000 x 100000 header with its full offset table and no pixels written.
        Imf::Header header(100000, 100000);
        header.channels().insert("R", Imf::Channel(Imf::FLOAT));
        header.channels().insert("G", Imf::Channel(Imf::FLOAT));
        header.channels().insert("B", Imf::Channel(Imf::FLOAT));
        Imf::OutputFile out(huge.c_str(), header);
    }
    layers::ReadOptions options;
    options.max_memory = 1000000000;
    EXPECT_EQ(read_error(huge, options),
              huge + ": subimage 0 declares 100000x100000 pixels x 3 channels, 120 GB as float, "
                     "more than the 1 GB one image may take (--max-memory)");
    // The default budget (half of this machine's memory) refuses it too, before OpenEXR's
    // check reads the file.
    EXPECT_NE(read_error(huge).find("declares 100000x100000 pixels"), std::string::npos);
}

TEST(DamagedFiles, DeepImagesAreRefusedBeforeTheirSamplesAreRead)
{
    TempDir dir;
    const std::string deep = dir.file("deep.exr");
    OIIO::ImageSpec spec(4, 3, 1, OIIO::TypeDesc::FLOAT);
    spec.deep = true;
    OIIO::ImageBuf buf(spec);
    ASSERT_TRUE(buf.write(deep)) << buf.geterror();
    EXPECT_EQ(read_error(deep), deep + ": deep images are not supported");
}

TEST(InterruptedWrites, TemporariesOfKilledWritersAreRemovedByTheNextWrite)
{
    TempDir dir;
    const std::string out = dir.file("out.exr");
    // A temporary as a writer killed by SIGKILL leaves it: this host, a process now gone.
    const pid_t child = ::fork();
    if (child == 0)
        ::_exit(0);
    ::waitpid(child, nullptr, 0);
    char host[256] = {};
    ::gethostname(host, sizeof host - 1);
    const std::string stale =
        dir.file(".out.exr.statmc-tmp-" + std::string(host) + "-" + std::to_string(child) + "-0");
    const std::string alive = dir.file(".out.exr.statmc-tmp-" + std::string(host) + "-" +
                                       std::to_string(::getpid()) + "-99");
    std::ofstream(stale) << "half a file";
    std::ofstream(alive) << "another writer's, still running";
    layers::write_image_file(
        layers::make_statistics_image(noisy_statistics(8, 6, 4, 1), {"", 4, 1}), out);
    EXPECT_FALSE(std::filesystem::exists(stale));
    EXPECT_TRUE(std::filesystem::exists(alive)) << "a live writer's temporary is left alone";
    EXPECT_TRUE(read_error(out).empty()) << read_error(out);
}

TEST(InterruptedWrites, ASignalDuringAWriteRemovesTheTemporaryAndKeepsTheTarget)
{
    TempDir dir;
    const std::string out = dir.file("out.txt");
    layers::write_text_file_atomically(out, "the previous output\n");
    for (int signal_number : {SIGINT, SIGTERM, SIGHUP}) {
        // A child that is signalled half-way through its write, as statmc is by Ctrl-C.
        const pid_t child = ::fork();
        if (child == 0) {
            layers::install_write_signal_handlers();
            layers::write_file_atomically(out, [&](const std::string& temporary) {
                std::ofstream(temporary) << "half a file";
                ::raise(signal_number);
            });
            ::_exit(0);  // not reached: the signal ends the child
        }
        int status = 0;
        ASSERT_EQ(::waitpid(child, &status, 0), child);
        ASSERT_TRUE(WIFSIGNALED(status)) << "the signal still ends the process";
        EXPECT_EQ(WTERMSIG(status), signal_number);
        EXPECT_EQ(dir.entries(), std::vector<std::string>{"out.txt"}) << "no temporary left";
        EXPECT_EQ(file_bytes(out), "the previous output\n");
    }
    // A signal the parent set to be ignored (nohup) stays ignored: the write completes.
    const pid_t child = ::fork();
    if (child == 0) {
        std::signal(SIGHUP, SIG_IGN);
        layers::install_write_signal_handlers();
        layers::write_file_atomically(out, [&](const std::string& temporary) {
            std::ofstream(temporary) << "written despite SIGHUP\n";
            ::raise(SIGHUP);
        });
        ::_exit(0);
    }
    int status = 0;
    ASSERT_EQ(::waitpid(child, &status, 0), child);
    EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << status;
    EXPECT_EQ(file_bytes(out), "written despite SIGHUP\n");
}

}  // namespace
}  // namespace statmc::test
