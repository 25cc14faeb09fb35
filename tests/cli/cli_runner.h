// Runs the built statmc binary as a user would: own process, stdin from /dev/null,
// stdout and stderr captured, and a time limit so that a hang fails the test.
#pragma once

#include <string>
#include <vector>

namespace statmc::test {

struct CliResult {
    int exit_code = -1;  ///< -1 when the process did not exit normally
    int signal = 0;      ///< the signal that ended it, if one did
    bool timed_out = false;
    std::string out, err;
};

/// Runs the built statmc.
CliResult run_cli(const std::vector<std::string>& args, int timeout_seconds = 120);

/// Runs another program (`program` is a path) the same way: oiiotool, to compare with.
CliResult run_program(const std::string& program, const std::vector<std::string>& args,
                      int timeout_seconds = 120);

}  // namespace statmc::test
