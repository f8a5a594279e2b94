#include "engine/base/file_replace.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <random>

namespace hapscene {
namespace {

// Writes all of `text` to `fd`; false with errno set when it cannot.
bool write_all(int fd, std::string_view text) {
  std::size_t done = 0;
  while (done < text.size()) {
    const ssize_t wrote = ::write(fd, text.data() + done, text.size() - done);
    if (wrote < 0 && errno == EINTR) continue;
    if (wrote < 0) return false;
    if (wrote == 0) {
      errno = EIO;
      return false;
    }
    done += static_cast<std::size_t>(wrote);
  }
  return true;
}

// A device or pipe at `path` (after links): written in place, as fopen(path, "wb") would.
FileWriteOutcome write_through(const std::string& path, std::string_view text) {
  const int fd = ::open(path.c_str(), O_WRONLY | O_TRUNC | O_NOCTTY | O_CLOEXEC);
  if (fd < 0) return {FileWriteStep::open, errno};
  const bool written = write_all(fd, text);
  const int write_errno = errno;
  const bool closed = ::close(fd) == 0;
  if (!written) return {FileWriteStep::write, write_errno};
  if (!closed) return {FileWriteStep::write, errno};
  return {};
}

// "folder/.name.hapscene-<12 hex digits>": a name of its own next to `path`.
std::string sibling_name(const std::string& path, std::mt19937_64& random) {
  const std::size_t slash = path.rfind('/');
  const std::string folder = slash == std::string::npos ? std::string() : path.substr(0, slash + 1);
  std::string name = slash == std::string::npos ? path : path.substr(slash + 1);
  if (name.size() > 200) name.resize(200);  // room for the rest under NAME_MAX
  static const char* kHex = "0123456789abcdef";
  std::string suffix;
  std::uint64_t bits = random();
  for (int i = 0; i < 12; ++i, bits >>= 4) suffix.push_back(kHex[bits & 0xf]);
  return folder + "." + name + ".hapscene-" + suffix;
}

}  // namespace

FileWriteOutcome replace_file(const std::string& path, std::string_view text, SpecialPath special) {
  // What is at the path now: a regular file keeps its permissions; a link is replaced;
  // anything else is refused or, for outputs, written through.
  struct stat here {};
  const bool exists = ::lstat(path.c_str(), &here) == 0;
  const bool regular = exists && S_ISREG(here.st_mode);
  if (exists && !regular) {
    struct stat followed {};
    const bool special_target = ::stat(path.c_str(), &followed) == 0 && !S_ISREG(followed.st_mode);
    if (special == SpecialPath::write_through && special_target) return write_through(path, text);
    if (special == SpecialPath::refuse && !S_ISLNK(here.st_mode)) return {FileWriteStep::open, EINVAL};
  }
  // The new file: created here, by this call, under a name nobody else has.
  std::random_device seed;
  std::mt19937_64 random((static_cast<std::uint64_t>(seed()) << 32) ^ seed() ^ static_cast<std::uint64_t>(::getpid()));
  const mode_t mode = regular ? (here.st_mode & 07777) : 0666;
  std::string temporary;
  int fd = -1;
  for (int attempt = 0; attempt < 16 && fd < 0; ++attempt) {
    temporary = sibling_name(path, random);
    fd = ::open(temporary.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_NOCTTY | O_CLOEXEC, mode);
    if (fd < 0 && errno != EEXIST) return {FileWriteStep::open, errno};
  }
  if (fd < 0) return {FileWriteStep::open, EEXIST};
  // The original's permission bits exactly (the umask took some) and, where allowed, its owner.
  if (regular) {
    (void)::fchmod(fd, here.st_mode & 07777);
    if (here.st_uid != ::geteuid() || here.st_gid != ::getegid()) (void)::fchown(fd, here.st_uid, here.st_gid);
  }
  const bool written = write_all(fd, text) && ::fsync(fd) == 0;
  int error_number = errno;
  const bool closed = ::close(fd) == 0;
  if (written && !closed) error_number = errno;
  if (!written || !closed || ::rename(temporary.c_str(), path.c_str()) != 0) {
    if (written && closed) error_number = errno;
    ::unlink(temporary.c_str());
    return {FileWriteStep::write, error_number};
  }
  return {};
}

}  // namespace hapscene
