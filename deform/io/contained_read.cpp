// readContained: the child process, the pipe it answers through, and what its end means.
#include "contained_read.hpp"

#include <deform/error.hpp>

#include <sys/prctl.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
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
    if (n <= 0) _exit(3);  // the parent is gone: nobody to answer
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
  if (::getppid() != parent) _exit(4);
  const rlimit cpu{static_cast<rlim_t>(cpu_limit_s), static_cast<rlim_t>(cpu_limit_s) + 1};
  ::setrlimit(RLIMIT_CPU, &cpu);
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
  if (::pipe(fds) != 0)
    throw std::runtime_error(path + ": cannot open a pipe to the importer: " + std::strerror(errno));
  // What the child writes to stderr (assimp's assertion message, a sanitizer's report) goes to a file of
  // its own: it becomes part of the one message, or is shown whole for a sanitizer report.
  std::FILE* child_stderr = std::tmpfile();
  std::fflush(nullptr);  // nothing buffered is written twice
  const pid_t child = ::fork();
  if (child < 0) {
    const int error = errno;
    ::close(fds[0]);
    ::close(fds[1]);
    if (child_stderr != nullptr) std::fclose(child_stderr);
    throw std::runtime_error(path + ": cannot start the importer's process: " + std::strerror(error));
  }
  if (child == 0) {
    ::close(fds[0]);
    if (child_stderr != nullptr) ::dup2(::fileno(child_stderr), STDERR_FILENO);
    answerInChild(fds[1], read, report, cpu_limit_s, parent);
  }
  ::close(fds[1]);
  const std::string bytes = readAll(fds[0]);
  ::close(fds[0]);
  int status = 0;
  while (::waitpid(child, &status, 0) < 0 && errno == EINTR) {
  }
  std::string said;
  if (child_stderr != nullptr) {
    std::rewind(child_stderr);
    said = readAll(::fileno(child_stderr));
    std::fclose(child_stderr);
  }
  if (!bytes.empty() && bytes[0] == kSanitizerReport) {
    std::fprintf(stderr, "%s%s: a sanitizer reported an error while importing this file (above)\n",
                 said.c_str(), path.c_str());
    std::abort();
  }
  // The child's last line, when it said anything (assimp: "ai_assert failure in ...").
  while (!said.empty() && (said.back() == '\n' || said.back() == '\r')) said.pop_back();
  const std::string last_line =
      said.substr(said.find_last_of('\n') == std::string::npos ? 0 : said.find_last_of('\n') + 1);
  const std::string what = last_line.empty() ? "" : ": " + last_line;
  if (WIFSIGNALED(status) && WTERMSIG(status) == SIGXCPU)
    throw InputError(
        path + ": the importer (assimp) ran past its limit of " + std::to_string(cpu_limit_s) +
        " s of CPU time on this file (a hang in assimp; ImportOptions::importer_cpu_limit_s); refused");
  if (WIFSIGNALED(status)) {
    const int signal = WTERMSIG(status);
    throw InputError(path + ": the importer (assimp) crashed on this file (signal " + std::to_string(signal) +
                     ", " + strsignal(signal) + what + "); refused");
  }
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
