// readContained: the child process, the pipe it answers through, and what its end means.
#include "contained_read.hpp"

#include <deform/error.hpp>

#include <fcntl.h>
#include <poll.h>
#include <sys/mman.h>
#include <sys/prctl.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <stdexcept>
#include <type_traits>

#if defined(__SANITIZE_ADDRESS__)
#define DEFORM_SANITIZED 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define DEFORM_SANITIZED 1
#endif
#endif
#ifdef DEFORM_SANITIZED
#include <sanitizer/common_interface_defs.h>
#endif

namespace deform {
namespace {

// The child's answer: one tag byte, then its payload.
constexpr char kMesh = 'M';             // the mesh and the report
constexpr char kInputError = 'E';       // the file refused: the message
constexpr char kOtherError = 'X';       // another exception: the message
constexpr char kSanitizerReport = 'S';  // written by the sanitizer's death callback, nothing after it
// The child's own failures, not the file's: the pipe closed under it, or its parent gone before it began.
constexpr int kParentGone = 3;
constexpr int kNoParent = 4;

int answer_fd = -1;  // the child's end of the pipe, for the death callback

#ifdef DEFORM_SANITIZED
void onSanitizerDeath() {
  const char tag = kSanitizerReport;
  [[maybe_unused]] const ssize_t written = ::write(answer_fd, &tag, 1);
}
#endif

void writeAll(int fd, const void* data, std::size_t size) {
  const char* bytes = static_cast<const char*>(data);
  while (size > 0) {
    const ssize_t n = ::write(fd, bytes, size);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) _exit(kParentGone);  // nobody to answer
    bytes += n;
    size -= static_cast<std::size_t>(n);
  }
}

template <typename T>
void put(int fd, const T& value) {
  static_assert(std::is_trivially_copyable_v<T>);
  writeAll(fd, &value, sizeof(T));
}

template <typename T>
void putVector(int fd, const std::vector<T>& values) {
  put<std::uint64_t>(fd, values.size());
  if (!values.empty()) writeAll(fd, values.data(), values.size() * sizeof(T));
}

void putText(int fd, const std::string& text) {
  put<std::uint64_t>(fd, text.size());
  writeAll(fd, text.data(), text.size());
}

/// Reads the child's answer in order; false when it is shorter than what it says it holds.
class Answer {
 public:
  explicit Answer(const std::string& bytes) : bytes_(bytes) {}
  template <typename T>
  bool get(T& value) {
    if (bytes_.size() - at_ < sizeof(T)) return false;
    std::memcpy(&value, bytes_.data() + at_, sizeof(T));
    at_ += sizeof(T);
    return true;
  }
  template <typename T>
  bool getVector(std::vector<T>& values) {
    std::uint64_t count = 0;
    if (!get(count) || count > (bytes_.size() - at_) / sizeof(T)) return false;
    values.resize(count);
    if (count > 0) std::memcpy(static_cast<void*>(values.data()), bytes_.data() + at_, count * sizeof(T));
    at_ += count * sizeof(T);
    return true;
  }
  bool getText(std::string& text) {
    std::vector<char> chars;
    if (!getVector(chars)) return false;
    text.assign(chars.begin(), chars.end());
    return true;
  }
  bool done() const { return at_ == bytes_.size(); }

 private:
  const std::string& bytes_;
  std::size_t at_ = 1;  // after the tag
};

[[noreturn]] void answerInChild(int fd, const std::function<Mesh(ImportReport&)>& read, ImportReport report,
                                int cpu_limit_s, pid_t parent) {
  answer_fd = fd;
  // Dies with the caller (a program stopped mid-import leaves no importer running), and a hang ends at
  // the limit (SIGXCPU).
  ::prctl(PR_SET_PDEATHSIG, SIGKILL);
  if (::getppid() != parent) _exit(kNoParent);
  const rlimit cpu{static_cast<rlim_t>(cpu_limit_s), static_cast<rlim_t>(cpu_limit_s) + 1};
  ::setrlimit(RLIMIT_CPU, &cpu);
  const rlimit no_core{0, 0};  // an abort inside assimp leaves no core file behind
  ::setrlimit(RLIMIT_CORE, &no_core);
  // The caller's handlers are not the child's: libFuzzer's would save a crash of assimp as its own
  // finding, Python's faulthandler would print a traceback. A sanitizer keeps its own (its report is a
  // finding, told to the parent by the death callback).
  for (int signal : {SIGABRT, SIGXCPU, SIGPIPE}) std::signal(signal, SIG_DFL);
#ifndef DEFORM_SANITIZED
  for (int signal : {SIGSEGV, SIGBUS, SIGILL, SIGFPE}) std::signal(signal, SIG_DFL);
#endif
  // No descriptor of the caller's but the answer's and the standard three (another thread's pipe kept
  // open here would hold its reader until this child ends).
  if (fd > 3) ::close_range(3, static_cast<unsigned>(fd) - 1, 0);
  ::close_range(static_cast<unsigned>(fd) + 1, ~0U, 0);
#ifdef DEFORM_SANITIZED
  __sanitizer_set_death_callback(onSanitizerDeath);
#endif
  try {
    const Mesh mesh = read(report);
    put(fd, kMesh);
    putText(fd, report.format);
    put(fd, report.up);
    put(fd, report.forward);
    put(fd, report.file_unit_m);
    put<std::uint64_t>(fd, report.mesh_instances);
    put<std::uint64_t>(fd, report.skipped_instances);
    putVector(fd, mesh.positions_m);
    putVector(fd, mesh.triangles);
    putVector(fd, mesh.normals);
  } catch (const InputError& e) {
    put(fd, kInputError);
    putText(fd, e.what());
  } catch (const std::exception& e) {
    put(fd, kOtherError);
    putText(fd, e.what());
  } catch (...) {
    put(fd, kOtherError);
    putText(fd, "an unknown exception");
  }
  ::close(fd);
  _exit(0);  // no atexit handlers, no static destructors: they belong to the parent
}

/// A file descriptor closed when it goes out of scope.
class OwnedFd {
 public:
  explicit OwnedFd(int fd = -1) : fd_(fd) {}
  OwnedFd(const OwnedFd&) = delete;
  OwnedFd& operator=(const OwnedFd&) = delete;
  ~OwnedFd() { reset(); }
  int get() const { return fd_; }
  void reset() {
    if (fd_ >= 0) ::close(fd_);
    fd_ = -1;
  }

 private:
  int fd_;
};

/// Reads `fd` to its end or until `deadline`; false when the deadline came first.
bool readUntil(int fd, std::chrono::steady_clock::time_point deadline, std::string& bytes) {
  char buffer[1 << 16];
  pollfd waiting{fd, POLLIN, 0};
  for (;;) {
    const auto left =
        std::chrono::duration_cast<std::chrono::milliseconds>(deadline - std::chrono::steady_clock::now());
    if (left.count() <= 0) return false;
    const int ready = ::poll(&waiting, 1, static_cast<int>(std::min<long long>(left.count(), 60000)));
    if (ready < 0 && errno != EINTR) return false;
    if (ready <= 0) continue;
    const ssize_t n = ::read(fd, buffer, sizeof buffer);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return true;
    bytes.append(buffer, static_cast<std::size_t>(n));
  }
}

std::string readAll(int fd) {
  std::string bytes;
  char buffer[1 << 16];
  for (;;) {
    const ssize_t n = ::read(fd, buffer, sizeof buffer);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) break;
    bytes.append(buffer, static_cast<std::size_t>(n));
  }
  return bytes;
}

}  // namespace

Mesh readContained(const std::string& path, const std::function<Mesh(ImportReport&)>& read,
                   ImportReport& report, int cpu_limit_s) {
  if (cpu_limit_s < 1)
    throw InputError("importer_cpu_limit_s: must be at least 1 s (got " + std::to_string(cpu_limit_s) + ")");
  const pid_t parent = ::getpid();
  int fds[2];
  if (::pipe2(fds, O_CLOEXEC) != 0)
    throw std::runtime_error(path + ": cannot open a pipe to the importer: " + std::strerror(errno));
  OwnedFd answer_end(fds[0]), child_end(fds[1]);
  // What the child writes to stderr (assimp's assertion message, a sanitizer's report) goes to a file of
  // its own: it becomes part of the one message, or is shown whole for a sanitizer report. (Without one,
  // the child's stderr stays the caller's.)
  OwnedFd child_stderr(::memfd_create("importer-stderr", MFD_CLOEXEC));
  std::fflush(nullptr);  // nothing buffered is written twice
  const pid_t child = ::fork();
  if (child < 0)
    throw std::runtime_error(path + ": cannot start the importer's process: " + std::strerror(errno));
  if (child == 0) {
    if (child_stderr.get() >= 0) ::dup2(child_stderr.get(), STDERR_FILENO);  // dup2 clears close-on-exec
    answerInChild(child_end.get(), read, report, cpu_limit_s, parent);
  }
  child_end.reset();
  // A child that blocks rather than spins (a lock held by another thread at the fork) never reaches its
  // CPU limit: a wall-clock deadline, generous for a loaded machine, ends it too.
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(4 * cpu_limit_s + 30);
  std::string bytes;
  bool answered = false;
  try {
    answered = readUntil(answer_end.get(), deadline, bytes);
  } catch (...) {  // out of memory: end the child before going on
    ::kill(child, SIGKILL);
    while (::waitpid(child, nullptr, 0) < 0 && errno == EINTR) {
    }
    throw;
  }
  if (!answered) ::kill(child, SIGKILL);
  answer_end.reset();
  int status = 0;
  while (::waitpid(child, &status, 0) < 0)
    if (errno != EINTR)
      throw std::runtime_error(path + ": cannot wait for the importer's process: " + std::strerror(errno));
  std::string said;
  if (child_stderr.get() >= 0 && ::lseek(child_stderr.get(), 0, SEEK_SET) == 0)
    said = readAll(child_stderr.get());
  if (!bytes.empty() && bytes[0] == kSanitizerReport) {
    // Only assimp and our walk of its scene run in the child; what a sanitizer finds there is in
    // practice assimp's (a bad free in its scene destructor, found by fuzz_mesh_ply), which a build
    // without sanitizers meets as an abort: the file is refused the same way, with the report's summary.
    const std::size_t summary = said.find("SUMMARY: ");
    const std::string line = summary == std::string::npos
                                 ? "no summary"
                                 : said.substr(summary + 9, said.find('\n', summary) - summary - 9);
    throw InputError(path + ": the importer (assimp) failed a memory check on this file (" + line +
                     "); refused");
  }
  // The child's last line, when it said anything (assimp: "ai_assert failure in ...").
  while (!said.empty() && (said.back() == '\n' || said.back() == '\r')) said.pop_back();
  const std::size_t line_start = said.find_last_of('\n');
  const std::string last_line = said.substr(line_start == std::string::npos ? 0 : line_start + 1);
  const std::string what = last_line.empty() ? "" : ": " + last_line;
  if (!answered)
    throw InputError(path + ": the importer (assimp) gave no answer within " +
                     std::to_string(4 * cpu_limit_s + 30) + " s on this file (stopped); refused");
  if (WIFSIGNALED(status) && WTERMSIG(status) == SIGXCPU)
    throw InputError(path + ": the importer (assimp) ran past its limit of " + std::to_string(cpu_limit_s) +
                     " s of CPU time on this file (a hang in assimp); refused");
  if (WIFSIGNALED(status)) {
    const int signal = WTERMSIG(status);
    throw InputError(path + ": the importer (assimp) crashed on this file (signal " + std::to_string(signal) +
                     ", " + strsignal(signal) + what + "); refused");
  }
  if (WIFEXITED(status) && (WEXITSTATUS(status) == kParentGone || WEXITSTATUS(status) == kNoParent))
    throw std::runtime_error(path + ": the importer's process lost its caller");
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0 || bytes.empty())
    throw InputError(path + ": the importer (assimp) stopped on this file without an answer (exit status " +
                     std::to_string(WIFEXITED(status) ? WEXITSTATUS(status) : -1) + what + "); refused");
  Answer answer(bytes);
  std::string message;
  if (bytes[0] == kInputError || bytes[0] == kOtherError) {
    if (!answer.getText(message)) throw std::runtime_error(path + ": the importer's answer was cut short");
    if (bytes[0] == kInputError) throw InputError(message);
    throw std::runtime_error(message);
  }
  Mesh mesh;
  std::uint64_t instances = 0, skipped = 0;
  const bool complete = bytes[0] == kMesh && answer.getText(report.format) && answer.get(report.up) &&
                        answer.get(report.forward) && answer.get(report.file_unit_m) &&
                        answer.get(instances) && answer.get(skipped) && answer.getVector(mesh.positions_m) &&
                        answer.getVector(mesh.triangles) && answer.getVector(mesh.normals) && answer.done();
  if (!complete) throw std::runtime_error(path + ": the importer's answer was cut short");
  report.mesh_instances = instances;
  report.skipped_instances = skipped;
  return mesh;
}

}  // namespace deform
