#pragma once
// Writing a whole file so that a reader sees the old one or the new one, never half of
// it, and so that nothing planted next to it is written through: the text goes into a
// new file with a name of its own in the same folder (created exclusively, never through
// a symbolic link: O_CREAT | O_EXCL | O_NOFOLLOW), is flushed to disk and renamed over
// the path. A file that was there keeps its permission bits (and its owner, when the
// process may set it); a symbolic link at the path itself is replaced, not followed.
// Every whole-file writer of the project goes through here (the live view's save, the
// output files of run, validate, plot, bench and calibrate).
#include <string>
#include <string_view>

namespace hapscene {

// What a path that exists and is not a regular file (nor a link to one) gets.
enum class SpecialPath {
  refuse,         // an error (EINVAL): only a regular file is replaced
  write_through,  // written in place, as opened: a device or a pipe (/dev/null, /dev/stdout)
};

// Where a write failed: opening (the new file could not be created, or a special path
// opened), or afterwards (write, flush, close, rename: a full disk).
enum class FileWriteStep { none, open, write };

struct FileWriteOutcome {
  FileWriteStep failed{FileWriteStep::none};
  int error_number{};  // errno of the failed step
  bool ok() const { return failed == FileWriteStep::none; }
};

// Replaces `path` with `text` as the header says. Leaves no new file behind on failure.
FileWriteOutcome replace_file(const std::string& path, std::string_view text, SpecialPath special);

}  // namespace hapscene
