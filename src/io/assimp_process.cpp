#include "assimp_process.h"

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <new>

namespace tessera::io {

namespace {

#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
constexpr bool kSanitized = true;
#elif defined(__has_feature)
#if __has_feature(address_sanitizer) || __has_feature(thread_sanitizer) || \
    __has_feature(memory_sanitizer)
constexpr bool kSanitized = true;
#else
constexpr bool kSanitized = false;
#endif
#else
constexpr bool kSanitized = false;
#endif

// The child's address space: what it has now (the parent's, copied on write) plus `bytes`.
void limitMemory(uint64_t bytes) {
  if (kSanitized) return;
  unsigned long pages = 0;
  if (FILE* statm = std::fopen("/proc/self/statm", "r")) {
    if (std::fscanf(statm, "%lu", &pages) != 1) pages = 0;
    std::fclose(statm);
  }
  const uint64_t now = uint64_t{pages} * static_cast<uint64_t>(::sysconf(_SC_PAGESIZE));
  const rlimit limit{now + bytes, now + bytes};
  ::setrlimit(RLIMIT_AS, &limit);
}

void writeAll(int fd, const std::string& text) {
  size_t done = 0;
  while (done < text.size()) {
    const ssize_t wrote = ::write(fd, text.data() + done, text.size() - done);
    if (wrote < 0 && errno == EINTR) continue;
    if (wrote <= 0) return;
    done += static_cast<size_t>(wrote);
  }
}

[[noreturn]] void runChild(int fd, const std::function<Expected<void>()>& work,
                           const std::string& name, uint64_t memory_bytes) {
  // A crash ends the child by its signal, quietly: the parent says what happened.
  for (int signal : {SIGSEGV, SIGBUS, SIGABRT, SIGFPE, SIGILL}) ::signal(signal, SIG_DFL);
  limitMemory(memory_bytes);
  std::string answer;
  try {
    Expected<void> done = work();
    answer = done ? "1" : "0" + done.error().message;
  } catch (const std::bad_alloc&) {
    answer = "0" + name + ": assimp cannot read it: it needs more memory than the budget of " +
             std::to_string(memory_bytes) + " bytes; raise it with --memory-limit";
  } catch (const std::exception& error) {
    answer = "0" + name + ": assimp cannot read it: " + error.what();
  } catch (...) {
    answer = "0" + name + ": assimp cannot read it: an unknown exception";
  }
  writeAll(fd, answer);
  ::_exit(0);  // no atexit handlers, no stdio buffers of the parent's flushed twice
}

}  // namespace

Expected<void> runIsolated(const std::function<Expected<void>()>& work, const std::string& name,
                           uint64_t memory_bytes, int seconds) {
  int fds[2];
  if (::pipe2(fds, O_CLOEXEC) != 0)
    return makeError(name + ": cannot start assimp's process: " + std::strerror(errno));
  const pid_t child = ::fork();
  if (child < 0) {
    ::close(fds[0]);
    ::close(fds[1]);
    return makeError(name + ": cannot start assimp's process: " + std::strerror(errno));
  }
  if (child == 0) {
    ::close(fds[0]);
    runChild(fds[1], work, name, memory_bytes);
  }
  ::close(fds[1]);
  std::string answer;
  bool timed_out = false;
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(seconds);
  for (;;) {
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(
        deadline - std::chrono::steady_clock::now());
    if (left.count() <= 0) {
      timed_out = true;
      break;
    }
    pollfd poll_fd{fds[0], POLLIN, 0};
    const int ready = ::poll(&poll_fd, 1, static_cast<int>(left.count()));
    if (ready < 0 && errno == EINTR) continue;
    if (ready == 0) continue;  // the deadline is checked above
    char buffer[4096];
    const ssize_t got = ready < 0 ? 0 : ::read(fds[0], buffer, sizeof buffer);
    if (got < 0 && errno == EINTR) continue;
    if (got <= 0) break;
    if (answer.size() < (64 << 10)) answer.append(buffer, static_cast<size_t>(got));
  }
  ::close(fds[0]);
  if (timed_out) ::kill(child, SIGKILL);
  int status = 0;
  while (::waitpid(child, &status, 0) < 0 && errno == EINTR) {
  }
  if (timed_out)
    return makeError(name + ": assimp cannot read it: it took longer than " +
                     std::to_string(seconds) + " s, and was stopped");
  if (!answer.empty() && answer[0] == '1') return {};
  if (!answer.empty()) return makeError(answer.substr(1));
  if (WIFSIGNALED(status))
    return makeError(name + ": assimp cannot read it: it crashed (signal " +
                     std::to_string(WTERMSIG(status)) + ", " + ::strsignal(WTERMSIG(status)) + ")");
  return makeError(name + ": assimp cannot read it: its process ended without an answer (exit " +
                   "status " + std::to_string(WEXITSTATUS(status)) + ")");
}

}  // namespace tessera::io
