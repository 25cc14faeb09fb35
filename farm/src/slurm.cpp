#include "statmc/farm/slurm.h"

#include <cerrno>
#include <cstring>
#include <sstream>
#include <stdexcept>

#include <fcntl.h>
#include <poll.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

extern char** environ;

namespace statmc::farm {

namespace {

std::string trimmed(std::string s)
{
    while (!s.empty() && (s.back() == '\n' || s.back() == '\r' || s.back() == ' '))
        s.pop_back();
    return s;
}

std::string joined(const std::vector<std::string>& items, const char* separator)
{
    std::string out;
    for (const std::string& s : items)
        out += (out.empty() ? "" : separator) + s;
    return out;
}

// Reads both pipes to the end (in turn as they fill, so that neither blocks the child).
void drain(int out_fd, int err_fd, std::string& out, std::string& err)
{
    pollfd fds[2] = {{out_fd, POLLIN, 0}, {err_fd, POLLIN, 0}};
    std::string* sinks[2] = {&out, &err};
    int open_fds = 2;
    char buffer[4096];
    while (open_fds > 0) {
        if (::poll(fds, 2, -1) < 0) {
            if (errno == EINTR)
                continue;
            break;
        }
        for (int i = 0; i < 2; ++i) {
            if (fds[i].fd < 0 || !(fds[i].revents & (POLLIN | POLLHUP | POLLERR)))
                continue;
            const ssize_t n = ::read(fds[i].fd, buffer, sizeof buffer);
            if (n > 0) {
                sinks[i]->append(buffer, std::size_t(n));
            } else if (n == 0 || errno != EINTR) {
                ::close(fds[i].fd);
                fds[i].fd = -1;
                --open_fds;
            }
        }
    }
}

}  // namespace

CommandResult run_command(const std::vector<std::string>& argv)
{
    int out_pipe[2], err_pipe[2];
    if (::pipe2(out_pipe, O_CLOEXEC) != 0)
        throw std::runtime_error(argv[0] + ": cannot start: " + std::strerror(errno));
    if (::pipe2(err_pipe, O_CLOEXEC) != 0) {
        const int error = errno;
        ::close(out_pipe[0]);
        ::close(out_pipe[1]);
        throw std::runtime_error(argv[0] + ": cannot start: " + std::strerror(error));
    }
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_adddup2(&actions, out_pipe[1], 1);
    posix_spawn_file_actions_adddup2(&actions, err_pipe[1], 2);
    std::vector<char*> args;
    for (const std::string& a : argv)
        args.push_back(const_cast<char*>(a.c_str()));
    args.push_back(nullptr);
    pid_t pid = 0;
    const int spawned = ::posix_spawnp(&pid, args[0], &actions, nullptr, args.data(), environ);
    posix_spawn_file_actions_destroy(&actions);
    ::close(out_pipe[1]);
    ::close(err_pipe[1]);
    if (spawned != 0) {
        ::close(out_pipe[0]);
        ::close(err_pipe[0]);
        throw std::runtime_error(argv[0] + ": cannot run it: " + std::strerror(spawned) +
                                 (spawned == ENOENT ? "; is it installed and on PATH?" : ""));
    }
    CommandResult r;
    drain(out_pipe[0], err_pipe[0], r.out, r.err);
    int status = 0;
    while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
    }
    r.status = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
    return r;
}

std::string submit(const std::string& script, const std::vector<std::string>& options,
                   const std::vector<std::string>& script_args)
{
    std::vector<std::string> argv{"sbatch", "--parsable"};
    argv.insert(argv.end(), options.begin(), options.end());
    argv.push_back(script);
    argv.insert(argv.end(), script_args.begin(), script_args.end());
    const CommandResult r = run_command(argv);
    // --parsable prints "jobid" or "jobid;cluster".
    const std::string id = trimmed(r.out.substr(0, r.out.find(';')));
    if (r.status != 0 || id.empty() || id.find_first_not_of("0123456789") != std::string::npos)
        throw std::runtime_error(joined(argv, " ") + " failed (exit status " +
                                 std::to_string(r.status) + "): " +
                                 trimmed(r.err.empty() ? r.out : r.err));
    return id;
}

std::map<std::string, std::string> queued_states(const std::vector<std::string>& job_ids)
{
    const CommandResult r =
        run_command({"squeue", "-h", "-r", "-j", joined(job_ids, ","), "-o", "%i %T"});
    std::map<std::string, std::string> states;
    if (r.status != 0) {
        // squeue refuses job ids it has forgotten (all ended): nothing is queued. Anything
        // else (the controller not answering) is no answer at all.
        if (r.err.find("Invalid job id") != std::string::npos)
            return states;
        throw std::runtime_error("squeue failed (exit status " + std::to_string(r.status) +
                                 "): " + trimmed(r.err));
    }
    std::istringstream lines(r.out);
    std::string id, state;
    while (lines >> id >> state)
        states[id] = state;
    return states;
}

std::map<std::string, std::string> accounted_states(const std::vector<std::string>& job_ids)
{
    std::map<std::string, std::string> states;
    CommandResult r;
    try {
        r = run_command(
            {"sacct", "-n", "-P", "-X", "-j", joined(job_ids, ","), "-o", "JobID,State"});
    } catch (const std::runtime_error&) {
        return states;
    }
    if (r.status != 0)
        return states;
    std::istringstream lines(r.out);
    std::string line;
    while (std::getline(lines, line)) {
        const auto bar = line.find('|');
        if (bar != std::string::npos)
            states[line.substr(0, bar)] = line.substr(bar + 1, line.find(' ', bar) - bar - 1);
    }
    return states;
}

}  // namespace statmc::farm
