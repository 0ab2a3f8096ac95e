// Output: every file and every standard-output result of the commands is
// written here, the way coreutils' install/mv and moreutils' sponge do it.
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <array>
#include <cerrno>
#include <climits>
#include <csignal>
#include <cstdlib>
#include <cstring>
#include <iostream>
#include <vector>

#include "commands.hpp"

namespace superball::cli {
namespace detail {
namespace {

/// Temporary files that a signal must remove: a fixed table, so that the
/// handler only reads memory (async-signal-safe).  A slot is in use while
/// its first byte is not 0.
constexpr std::size_t max_temporaries = 16;
std::array<std::array<char, PATH_MAX>, max_temporaries> temporaries{};

extern "C" void remove_temporaries_and_reraise(int signal) {
  for (auto& t : temporaries)
    if (t[0] != '\0') ::unlink(t.data());
  std::signal(signal, SIG_DFL);
  std::raise(signal);
}

/// Install the handler once, for the signals that end a run (not where the
/// caller ignores them, e.g. under nohup).
void install_handlers() {
  static const bool installed = [] {
    for (int s : {SIGINT, SIGTERM, SIGHUP, SIGPIPE}) {
      struct sigaction old {};
      if (::sigaction(s, nullptr, &old) == 0 && old.sa_handler == SIG_IGN) continue;
      struct sigaction act {};
      act.sa_handler = remove_temporaries_and_reraise;
      sigemptyset(&act.sa_mask);
      ::sigaction(s, &act, nullptr);
    }
    return true;
  }();
  (void)installed;
}

/// Register \p path; returns its slot, or -1 when the table is full (the
/// destructor still removes it; only a signal would leave it).
int register_temporary(const std::string& path) {
  if (path.size() >= PATH_MAX) return -1;
  install_handlers();
  for (std::size_t k = 0; k < max_temporaries; ++k)
    if (temporaries[k][0] == '\0') {
      // Copy all but the first byte, then the first: the slot is never half-written when in use.
      std::memcpy(temporaries[k].data() + 1, path.c_str() + 1, path.size());
      temporaries[k][0] = path[0];
      return static_cast<int>(k);
    }
  return -1;
}

void unregister_temporary(int slot) {
  if (slot >= 0) temporaries[static_cast<std::size_t>(slot)][0] = '\0';
}

/// The names that mean this process's standard output or error.
int standard_descriptor(const std::string& path) {
  if (path.empty() || path == "-" || path == "/dev/stdout" || path == "/dev/fd/1" || path == "/proc/self/fd/1") return STDOUT_FILENO;
  if (path == "/dev/stderr" || path == "/dev/fd/2" || path == "/proc/self/fd/2") return STDERR_FILENO;
  return -1;
}

std::string directory_of(const std::string& path) {
  const auto slash = path.rfind('/');
  return slash == std::string::npos ? "." : slash == 0 ? "/" : path.substr(0, slash);
}

/// The process's umask, read without changing it for long.
mode_t current_umask() {
  const mode_t mask = ::umask(022);
  ::umask(mask);
  return mask;
}

/// A file the running command reads: no output may name it.
struct Input {
  std::string name;  ///< "--scene t.toml", for messages
  dev_t device;
  ino_t inode;
};

std::vector<Input>& inputs() {
  static std::vector<Input> all;
  return all;
}

}  // namespace
}  // namespace detail

void note_input(const std::string& option, const std::string& path) {
  struct stat st {};
  // Only a regular file can be replaced by an output; a folder (reproduce --scenes) or a device is left to the writes.
  if (detail::standard_descriptor(path) >= 0 || ::stat(path.c_str(), &st) != 0 || !S_ISREG(st.st_mode)) return;
  detail::inputs().push_back({(option.empty() ? "" : option + " ") + path, st.st_dev, st.st_ino});
}

void check_not_input(const std::string& what, const std::string& path) {
  // An output that does not exist yet is no file that is read: the inputs exist (they are noted as they are read).
  struct stat st {};
  if (detail::standard_descriptor(path) >= 0 || ::stat(path.c_str(), &st) != 0) return;
  for (const detail::Input& in : detail::inputs())
    if (in.device == st.st_dev && in.inode == st.st_ino)
      throw std::invalid_argument(what + ": is the file of " + in.name + ", which this command reads; write the output elsewhere");
}

void check_outputs(const CLI::App& command) {
  auto values = [&](const char* option) {
    const CLI::Option* o = command.get_option_no_throw(option);
    return o ? o->results() : std::vector<std::string>{};
  };
  for (const char* option : {"scene", "--scene"})
    for (const std::string& path : values(option)) note_input(option[0] == '-' ? option : "the scene", path);
  for (const char* option : {"--output", "--out", "--part", "--checkpoint", "--plot"})
    for (const std::string& path : values(option)) {
      const std::string named = std::string(std::strcmp(option, "--output") == 0 ? "-o" : option) + " " + path;
      check_not_input(named, path);
      // map --plot PREFIX writes the figure's four files beside it.
      if (std::strcmp(option, "--plot") == 0 && command.get_name() == "map")
        for (const char* ext : {".dat", ".gp", ".png", ".svg"}) check_not_input(named + " (" + path + ext + ")", path + ext);
    }
}

struct Output::Impl {
  std::string name;    ///< the path as given, or "standard output": what messages say
  std::string target;  ///< the file the temporary replaces (a symbolic link resolved)
  std::string tmp;     ///< the temporary, when replacing a file
  int fd = -1;
  bool owned = false;  ///< fd is ours to close
  int slot = -1;       ///< the temporary's slot in detail::temporaries
  bool committed = false;

  [[noreturn]] void fail(int error) const { throw OutputError(name + ": " + std::strerror(error)); }

  void discard() {
    if (owned && fd >= 0) ::close(fd);
    fd = -1;
    if (!tmp.empty()) ::unlink(tmp.c_str());
    detail::unregister_temporary(slot);
    slot = -1;
  }
};

Output::Output(std::string path) : impl_(std::make_unique<Impl>()) {
  Impl& o = *impl_;
  const int standard = detail::standard_descriptor(path);
  if (standard >= 0) {
    o.name = standard == STDOUT_FILENO ? "standard output" : "standard error";
    o.fd = standard;
    std::cout.flush();
    return;
  }
  o.name = path;
  check_not_input(path, path);
  struct stat st {};
  const bool exists = ::stat(path.c_str(), &st) == 0;
  if (!exists && errno != ENOENT) o.fail(errno);
  if (exists && S_ISDIR(st.st_mode)) o.fail(EISDIR);
  if (exists && !S_ISREG(st.st_mode)) {
    // A device, FIFO or socket: written into directly, never replaced.
    o.fd = ::open(path.c_str(), O_WRONLY | O_CLOEXEC | O_NOCTTY);
    if (o.fd < 0) o.fail(errno);
    o.owned = true;
    return;
  }
  struct stat link {};
  if (::lstat(path.c_str(), &link) != 0 && errno != ENOENT) o.fail(errno);
  if (S_ISLNK(link.st_mode)) {
    // An existing link: its target is replaced, the link kept.
    if (!exists) throw OutputError(path + ": a symbolic link to a file that does not exist");
    char resolved[PATH_MAX];
    if (!::realpath(path.c_str(), resolved)) o.fail(errno);
    o.target = resolved;
  } else {
    o.target = path;
  }
  // The temporary beside the target, so that rename() is atomic.
  const std::string dir = detail::directory_of(o.target);
  const std::string base = o.target.substr(o.target.rfind('/') == std::string::npos ? 0 : o.target.rfind('/') + 1);
  std::string tmp = dir + "/." + base + ".XXXXXX";
  o.fd = ::mkostemp(tmp.data(), O_CLOEXEC);
  if (o.fd < 0) o.fail(errno);
  o.owned = true;
  o.tmp = tmp;
  o.slot = detail::register_temporary(tmp);
  // An existing file keeps its permissions (and its owner, where we may set it); a new one gets 0666 & ~umask.
  if (exists && ::geteuid() == 0 && ::fchown(o.fd, st.st_uid, st.st_gid) != 0) {
    const int error = errno;
    o.discard();
    o.fail(error);
  }
  const mode_t mode = exists ? (st.st_mode & 07777) : (0666 & ~detail::current_umask());
  if (::fchmod(o.fd, mode) != 0) {
    const int error = errno;
    o.discard();
    o.fail(error);
  }
}

Output::~Output() {
  if (!impl_->committed) impl_->discard();
}

void Output::write(std::string_view text) {
  Impl& o = *impl_;
  if (o.fd < 0) throw std::logic_error("Output::write(): " + o.name + " is already committed");
  while (!text.empty()) {
    const ssize_t n = ::write(o.fd, text.data(), text.size());
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) o.fail(errno);
    text.remove_prefix(static_cast<std::size_t>(n));
  }
}

void Output::commit() {
  Impl& o = *impl_;
  if (o.fd < 0) throw std::logic_error("Output::commit(): " + o.name + " is already committed");
  if (o.tmp.empty()) {
    const int fd = o.fd;
    o.fd = -1;
    if (o.owned && ::close(fd) != 0) o.fail(errno);
    o.committed = true;
    return;
  }
  // Data on disk before the name points at it; then the directory entry.
  if (::fsync(o.fd) != 0 || ::close(o.fd) != 0) {
    const int error = errno;
    o.fd = -1;
    o.fail(error);
  }
  o.fd = -1;
  if (::rename(o.tmp.c_str(), o.target.c_str()) != 0) o.fail(errno);
  detail::unregister_temporary(o.slot);
  o.slot = -1;
  o.tmp.clear();
  o.committed = true;
  const int dir = ::open(detail::directory_of(o.target).c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (dir < 0) o.fail(errno);
  const int synced = ::fsync(dir), error = errno;
  ::close(dir);
  if (synced != 0 && error != EINVAL) o.fail(error);
}

void write_output(const std::string& path, std::string_view text) {
  Output out(path);
  out.write(text);
  out.commit();
}

void guard_standard_descriptors() {
  for (int fd : {STDIN_FILENO, STDOUT_FILENO, STDERR_FILENO})
    if (::fcntl(fd, F_GETFD) < 0 && errno == EBADF) {
      // Read-only /dev/null in the slot: writes there fail (EBADF) as on a closed descriptor.
      const int null = ::open("/dev/null", O_RDONLY);
      if (null >= 0 && null != fd) {
        ::dup2(null, fd);
        ::close(null);
      }
    }
}

}  // namespace superball::cli
