// statmc-farm without a cluster: frame patterns, the batch scripts it writes (valid bash,
// the right tasks, dependencies and pass-through options), its job record, and its
// errors when sbatch is missing or fails.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

#include <sys/wait.h>
#include <unistd.h>

#include "statmc/farm/farm_job.h"
#include "statmc/farm/frame_pattern.h"
#include "statmc/farm/job_record.h"
#include "statmc/farm/slurm.h"
#include "statmc/layers/sample_provenance.h"

namespace statmc::farm {
namespace {

namespace fs = std::filesystem;

struct Scratch {
    fs::path dir = fs::temp_directory_path() / ("statmc-farm-test-" + std::to_string(::getpid()));
    Scratch() { fs::create_directories(dir); }
    ~Scratch() { fs::remove_all(dir); }
    std::string write(const std::string& name, const std::string& text, bool executable = false)
    {
        std::ofstream(dir / name) << text;
        if (executable)
            fs::permissions(dir / name, fs::perms::owner_all);
        return (dir / name).string();
    }
};

// Runs `command` through the shell with its output in `log`; returns the output and sets
// `status` to the exit status.
std::string shell_output(const std::string& command, const std::string& log, int& status)
{
    const int raw = std::system((command + " > '" + log + "' 2>&1").c_str());
    status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
    std::ifstream in(log);
    std::stringstream text;
    text << in.rdbuf();
    return text.str();
}

FarmJob two_frames()
{
    FarmJob job;
    job.frames = {{7, "/s/shot.0007.pbrt", "/o/shot.0007.exr"},
                  {8, "/s/it's.pbrt", "/o/shot.0008.exr"}};
    job.tasks = 3;
    job.spp = 64;
    job.seed = 2;
    job.checkpoint_seconds = 30;
    job.job_dir = "/o/statmc-farm";
    job.render_exe = "/bin/statmc-render";
    job.statmc_exe = "/bin/statmc";
    job.slurm.partition = "render";
    job.slurm.cpus_per_task = 8;
    return job;
}

bool contains(const std::string& text, const std::string& part)
{
    return text.find(part) != std::string::npos;
}

// bash -n: the script parses.
int bash_syntax_check(Scratch& s, const std::string& script)
{
    const std::string path = s.write("check.sh", script);
    const int raw = std::system(("bash -n '" + path + "'").c_str());
    return WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
}

TEST(FramePattern, ExpandsOneFrameNumberAndRefusesOtherConversions)
{
    EXPECT_EQ(expand_frame("shot.%04d.pbrt", 7), "shot.0007.pbrt");
    EXPECT_EQ(expand_frame("f%d-100%%.exr", 12), "f12-100%.exr");
    EXPECT_EQ(expand_frame("plain.exr", 3), "plain.exr");
    EXPECT_TRUE(has_frame_number("a.%3d.exr"));
    EXPECT_FALSE(has_frame_number("a.%%d.exr"));
    for (const char* bad : {"a.%s.exr", "a.%d.%d.exr", "a.%x", "a.%", "a.%00004d"})
        EXPECT_THROW(expand_frame(bad, 1), std::runtime_error) << bad;
    EXPECT_EQ(parse_frames("3-5"), (std::vector<int>{3, 4, 5}));
    EXPECT_EQ(parse_frames("9"), (std::vector<int>{9}));
    for (const char* bad : {"5-3", "a", "1-", "1-2x", ""})
        EXPECT_THROW(parse_frames(bad), std::runtime_error) << bad;
}

TEST(FarmScripts, RenderArrayCoversEveryTaskOfEveryFrameAndRequeuesKilledOnes)
{
    Scratch s;
    const FarmJob job = two_frames();
    const std::string render = render_script(job);
    EXPECT_EQ(bash_syntax_check(s, render), 0) << render;
    EXPECT_TRUE(contains(render, "#SBATCH --array=0-5\n"));
    EXPECT_TRUE(contains(render, "#SBATCH --requeue\n"));
    EXPECT_TRUE(contains(render, "#SBATCH --partition=render\n"));
    EXPECT_TRUE(contains(render, "#SBATCH --cpus-per-task=8\n"));
    EXPECT_FALSE(contains(render, "--account"));
    EXPECT_TRUE(contains(render, "'/s/it'\\''s.pbrt'")) << "quoted for the shell";
    EXPECT_TRUE(contains(render, "'/o/shot.0008.task2.exr'"));
    EXPECT_TRUE(contains(render, "--task \"$task/3\" --spp 64 --seed \"${seeds[$frame]}\" "
                                 "--checkpoint 30 --resume"));
    EXPECT_TRUE(contains(render, "scontrol requeue \"${SLURM_ARRAY_JOB_ID}_${k}\""));
    EXPECT_TRUE(contains(render, "-lt 3 ]"));
}

// Runs the render script's element `k` with a fake statmc-render that prints its
// arguments and exits with `status`, and a fake scontrol; returns what they printed.
std::string run_element(Scratch& s, int k, int status)
{
    FarmJob job = two_frames();
    job.render_exe = s.write(
        "render.sh", "#!/bin/sh\necho render \"$@\"\nexit " + std::to_string(status) + "\n", true);
    s.write("scontrol", "#!/bin/sh\necho scontrol \"$@\"\n", true);
    const std::string script = s.write("render.sbatch", render_script(job));
    int ignored = 0;
    return shell_output("PATH='" + s.dir.string() + "':$PATH SLURM_ARRAY_JOB_ID=41 " +
                            "SLURM_ARRAY_TASK_ID=" + std::to_string(k) + " bash '" + script + "'",
                        (s.dir / "element.log").string(), ignored);
}

TEST(FarmScripts, ElementRendersItsTaskAndIsRequeuedOnlyWhenKilled)
{
    Scratch s;
    const std::string ok = run_element(s, 4, 0);  // frame 1 (number 8), task 1
    EXPECT_TRUE(contains(ok, "render /s/it's.pbrt -o /o/shot.0008.task1.exr --task 1/3")) << ok;
    EXPECT_FALSE(contains(ok, "scontrol")) << ok;
    const std::string killed = run_element(s, 4, 137);
    EXPECT_TRUE(contains(killed, "scontrol requeue 41_4")) << killed;
    const std::string error = run_element(s, 4, 1);
    EXPECT_FALSE(contains(error, "scontrol")) << "a scene error is not retried: " << error;
}

TEST(FarmScripts, EveryFrameRendersWithItsOwnSeedAndEveryTaskOfAFrameWithTheFramesSeed)
{
    // Frames 7 and 8 of --seed 2: one seed shared by the frames would repeat their noise
    // wherever the shot is still, and a temporal denoise would merge it as more samples.
    const FarmJob job = two_frames();
    const int seed7 = frame_seed(job, job.frames[0]), seed8 = frame_seed(job, job.frames[1]);
    EXPECT_NE(seed7, seed8);
    EXPECT_NE(seed7, job.seed);
    // The seed of frame F is the one statmc-render --frames gives frame F of --seed S.
    EXPECT_EQ(seed7, layers::frame_seed(2, 7));
    Scratch s;
    for (int k = 0; k < 6; ++k) {
        const std::string out = run_element(s, k, 0);
        const int expected = k < 3 ? seed7 : seed8;
        EXPECT_TRUE(contains(out, "--seed " + std::to_string(expected) + " ")) << k << ": " << out;
    }
}

TEST(FrameSeed, IsTheSeedForFrameZeroAndDistinctForEveryFrame)
{
    for (const int seed : {0, 1, 3, 1 << 30}) {
        EXPECT_EQ(layers::frame_seed(seed, 0), seed);
        std::set<int> seen;
        for (int frame = -100; frame <= 10000; ++frame) {
            const int s = layers::frame_seed(seed, frame);
            EXPECT_GE(s, 0);
            EXPECT_TRUE(seen.insert(s).second) << "seed " << seed << ", frame " << frame;
        }
    }
}

TEST(FarmScripts, SlurmsSigtermLetsTheRenderSaveAndRequeues)
{
    // Slurm signals the whole job: the script's shell and the render. The render saves its
    // checkpoint and exits 130; the script must live to requeue it.
    Scratch s;
    FarmJob job = two_frames();
    job.render_exe = s.write("render.sh",
                             "#!/bin/bash\ntrap 'echo saved; exit 130' TERM\n"
                             "sleep 5 & wait\n",
                             true);
    s.write("scontrol", "#!/bin/sh\necho scontrol \"$@\"\n", true);
    const std::string script = s.write("render.sbatch", render_script(job));
    int status = 0;
    const std::string out =
        shell_output("(PATH='" + s.dir.string() +
                         "':$PATH SLURM_ARRAY_JOB_ID=41 SLURM_ARRAY_TASK_ID=2 "
                         "setsid bash '" +
                         script + "' & pid=$!; sleep 1; kill -TERM -$pid; wait $pid)",
                     (s.dir / "term.log").string(), status);
    EXPECT_TRUE(contains(out, "SIGTERM: the render saves its checkpoint")) << out;
    EXPECT_TRUE(contains(out, "saved")) << out;
    EXPECT_TRUE(contains(out, "scontrol requeue 41_2")) << out;
}

TEST(FarmScripts, MergeTakesTheFramesTasksInOrderAndDenoises)
{
    Scratch s;
    FarmJob job = two_frames();
    job.denoise = true;
    job.denoise_modifiers = ":method=classic";
    const std::string merge = merge_script(job);
    EXPECT_EQ(bash_syntax_check(s, merge), 0) << merge;
    EXPECT_TRUE(contains(merge,
                         "\"${tasks[@]:$((frame * 3)):3}\" --merge -o \"${outputs[$frame]}\" "
                         "'--denoise:method=classic' -o \"${denoised[$frame]}\""))
        << merge;
    EXPECT_TRUE(contains(merge, "'/o/shot.0008.denoised.exr'"));
}

TEST(FarmJobRecord, RoundTripsAndRefusesOtherFiles)
{
    Scratch s;
    JobRecord record{two_frames(), "17", {"18", "19"}};
    record.job.job_dir = s.dir.string();
    write_job_record(record);
    const JobRecord back = read_job_record(s.dir.string());
    EXPECT_EQ(back.render_job, "17");
    EXPECT_EQ(back.merge_jobs, (std::vector<std::string>{"18", "19"}));
    EXPECT_EQ(back.job.tasks, 3);
    ASSERT_EQ(back.job.frames.size(), 2u);
    EXPECT_EQ(back.job.frames[1].scene, "/s/it's.pbrt");
    EXPECT_EQ(back.job.frames[1].number, 8);
    s.write("statmc-farm.job", "something else\n");
    EXPECT_THROW(read_job_record(s.dir.string()), std::runtime_error);
    EXPECT_THROW(read_job_record((s.dir / "nowhere").string()), std::runtime_error);
}

// statmc-farm `args` with PATH set to `path`; its output, and its exit status in `status`.
std::string farm_output(const Scratch& s, const std::string& args, const std::string& path,
                        int& status)
{
    return shell_output("PATH='" + path + "' '" STATMC_FARM_EXE "' " + args,
                        (s.dir / "farm.log").string(), status);
}

TEST(FarmCommand, SbatchMissingOrFailingIsAnErrorThatSaysSo)
{
    Scratch s;
    const std::string scene = s.write("s.pbrt", "WorldBegin\nWorldEnd\n");
    const std::string args = "submit '" + scene + "' --tasks 2 --spp 8 -o '" +
                             (s.dir / "o.exr").string() +
                             "' --render-exe /bin/true --statmc-exe /bin/true";
    int status = 0;
    // No sbatch on PATH.
    std::string out = farm_output(s, args, s.dir.string(), status);
    EXPECT_EQ(status, 1);
    EXPECT_TRUE(contains(out, "sbatch: cannot run it: No such file or directory; is it "
                              "installed and on PATH?"))
        << out;
    // sbatch refusing the job.
    s.write("sbatch",
            "#!/bin/sh\necho 'sbatch: error: invalid partition specified: nope' >&2\nexit 1\n",
            true);
    out = farm_output(s, args, s.dir.string() + ":/usr/bin:/bin", status);
    EXPECT_EQ(status, 1);
    EXPECT_TRUE(contains(out, "failed (exit status 1): sbatch: error: invalid partition specified"))
        << out;
    EXPECT_FALSE(fs::exists(job_record_path((s.dir / "statmc-farm").string())))
        << "no record of a job that was not submitted";
    // Bad input is refused before anything is written.
    out = farm_output(
        s, "submit '" + scene + "' --tasks 9 --spp 8 -o '" + (s.dir / "o.exr").string() + "'",
        s.dir.string() + ":/usr/bin:/bin", status);
    EXPECT_EQ(status, 1);
    EXPECT_TRUE(contains(out, "at most as many tasks as samples per pixel")) << out;
    // Temporal denoising needs the whole sequence: refused up front, not after the renders.
    out = farm_output(s,
                      "submit '" + scene + "' --tasks 2 --spp 8 -o '" + (s.dir / "o.exr").string() +
                          "' --denoise=radius=5:temporal=2",
                      s.dir.string() + ":/usr/bin:/bin", status);
    EXPECT_EQ(status, 1);
    EXPECT_TRUE(contains(out, "run statmc over the sequence")) << out;
    out = farm_output(s,
                      "submit '" + (s.dir / "missing.%04d.pbrt").string() + "' --frames 1-2 -o '" +
                          (s.dir / "o.%04d.exr").string() + "'",
                      s.dir.string() + ":/usr/bin:/bin", status);
    EXPECT_EQ(status, 1);
    EXPECT_TRUE(contains(out, "frame 1: scene " + (s.dir / "missing.0001.pbrt").string() +
                                  " does not exist"))
        << out;
}

TEST(FarmCommand, EveryCommandIsValidatedBeforeAnythingIsSubmitted)
{
    // The programs the jobs will run (this build's statmc-render and statmc) check their own
    // command lines; a typo fails at submit, even with --dry-run, and submits nothing.
    Scratch s;
    const std::string scene =
        s.write("s.pbrt", "Film \"image\" \"integer xresolution\" [8] "
                          "\"integer yresolution\" [8]\nCamera \"perspective\"\nWorldBegin\n"
                          "Translate 0 0 5\nShape \"sphere\"\nWorldEnd\n");
    s.write("sbatch", "#!/bin/sh\necho SBATCH-RAN >&2\nexit 1\n", true);
    const std::string path = s.dir.string() + ":/usr/bin:/bin";
    const std::string base =
        "submit '" + scene + "' --tasks 2 --spp 8 -o '" + (s.dir / "o.exr").string() + "' ";
    int status = 0;
    std::string out = farm_output(s, base + "--denoise radious=2 --dry-run", path, status);
    EXPECT_EQ(status, 1) << out;
    EXPECT_TRUE(contains(out, "frame 0: ")) << out;
    EXPECT_TRUE(contains(out, "would fail in the merge job")) << out;
    EXPECT_TRUE(contains(out, "radious")) << out;
    EXPECT_FALSE(contains(out, "#!/bin/bash")) << "no script printed: " << out;
    out = farm_output(s, base + "--render-args=--maxdepthh --render-args=3", path, status);
    EXPECT_EQ(status, 1) << out;
    EXPECT_TRUE(contains(out, "would fail in the render job")) << out;
    EXPECT_TRUE(contains(out, "--maxdepthh")) << out;
    EXPECT_FALSE(contains(out, "SBATCH-RAN")) << "sbatch must not run: " << out;
    EXPECT_FALSE(fs::exists(s.dir / "statmc-farm")) << "nothing written";
    // Valid options pass the check; the dry run then prints exactly what submit runs.
    out = farm_output(s, base + "--denoise method=classic:radius=4 --dry-run", path, status);
    EXPECT_EQ(status, 0) << out;
    EXPECT_TRUE(contains(out, "# would run: sbatch --parsable --kill-on-invalid-dep=yes "
                              "--dependency=afterok:<render job>_0:<render job>_1 "))
        << out;
}

}  // namespace
}  // namespace statmc::farm
