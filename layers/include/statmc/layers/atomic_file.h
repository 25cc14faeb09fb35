// Files written whole or not at all, for every writer (images, render checkpoints): the
// bytes go to a hidden temporary in the target's directory, reach the disk, and only then
// replace the target by rename, so a crash, a full disk or a kill never leaves a partial
// file or loses the previous one.
#pragma once

#include <functional>
#include <string>

namespace statmc::layers {

/// Removes the temporaries of `target` that killed processes of this host left, then runs
/// `write(temporary)` on a hidden name next to `target`, flushes the file to disk
/// (fsync) and renames it onto `target`. When `write` throws or a step fails, the
/// temporary is removed and `target` keeps its previous contents. Failures of the flush or
/// rename throw FileError "<target>: cannot write: ..."; what `write` throws passes through.
void write_file_atomically(const std::string& target,
                           const std::function<void(const std::string& temporary)>& write);

/// Removes the temporaries of every write in progress in this process. Async-signal-safe
/// (unlink on names held in a fixed table): for signal handlers, so that an interrupted
/// write leaves nothing behind.
void remove_unfinished_temporaries() noexcept;

/// A signal handler for a host that ends on the signal: remove_unfinished_temporaries(),
/// then the signal's default action, so the process still ends as the signal says.
extern "C" void remove_temporaries_and_end(int signal_number);

/// For a host that writes files: SIGINT, SIGTERM and SIGHUP run remove_temporaries_and_end
/// (unless the caller's parent set them to be ignored, as nohup does), and SIGXFSZ is
/// ignored, so that a write past `ulimit -f` fails with an error instead of a core dump.
void install_write_signal_handlers();

/// What the system says about a write of `path` that just failed, when a library's own
/// message does not: "No space left on device (12 KB free)" when its file system is (all
/// but) full, "File too large (...)" when the file has reached the process's file size
/// limit (ulimit -f); "" when neither explains it.
std::string storage_limit_reached(const std::string& path);

/// write_file_atomically for a text file (a script, a record): `text` as its whole content.
/// Throws FileError "<target>: cannot write: ..." on failure.
void write_text_file_atomically(const std::string& target, const std::string& text);

}  // namespace statmc::layers
