#include <risknav/common/probe_in_child.h>

#include <fcntl.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <csignal>
#include <stdexcept>

namespace risknav::common {
std::optional<std::uint64_t> probeInChild(
    const std::function<void(const TProbeProgress&)>& work) {
    int fds[2];
    if (pipe(fds) != 0)
        throw std::runtime_error("cannot create a pipe for the probe");
    const pid_t pid = fork();
    if (pid < 0) {
        close(fds[0]);
        close(fds[1]);
        throw std::runtime_error("cannot fork the probe");
    }
    if (pid == 0) {
        close(fds[0]);
        // The child's death is the answer, not an event: no crash handler of
        // the parent's (a sanitizer's, a fuzzer's) may report it, and no core
        // file is written.
        for (const int sig : {SIGSEGV, SIGBUS, SIGABRT, SIGFPE, SIGILL})
            std::signal(sig, SIG_DFL);
        const rlimit noCore{0, 0};
        setrlimit(RLIMIT_CORE, &noCore);
        const int devnull = open("/dev/null", O_WRONLY);
        if (devnull >= 0) {
            dup2(devnull, STDOUT_FILENO);
            dup2(devnull, STDERR_FILENO);
        }
        const int out = fds[1];
        try {
            work([out](std::uint64_t done) {
                const char* p = reinterpret_cast<const char*>(&done);
                std::size_t left = sizeof(done);
                while (left > 0) {
                    const ssize_t w = write(out, p, left);
                    if (w < 0 && errno == EINTR)
                        continue;
                    if (w <= 0)
                        _exit(0);  // the parent is gone
                    p += w;
                    left -= static_cast<std::size_t>(w);
                }
            });
        } catch (...) {
        }
        _exit(0);
    }
    close(fds[1]);
    std::uint64_t last = 0, value = 0;
    std::size_t have = 0;
    for (;;) {
        const ssize_t r =
            read(fds[0], reinterpret_cast<char*>(&value) + have, sizeof(value) - have);
        if (r < 0 && errno == EINTR)
            continue;
        if (r <= 0)
            break;
        have += static_cast<std::size_t>(r);
        if (have == sizeof(value)) {
            last = value;
            have = 0;
        }
    }
    close(fds[0]);
    int status = 0;
    while (waitpid(pid, &status, 0) < 0 && errno == EINTR) {
    }
    if (WIFEXITED(status) && WEXITSTATUS(status) == 0)
        return std::nullopt;
    return last;
}
}  // namespace risknav::common
