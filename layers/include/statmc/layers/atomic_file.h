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

/// write_file_atomically for a text file (a script, a record): `text` as its whole content.
/// Throws FileError "<target>: cannot write: ..." on failure.
void write_text_file_atomically(const std::string& target, const std::string& text);

}  // namespace statmc::layers
