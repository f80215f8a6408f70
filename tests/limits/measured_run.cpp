#include "measured_run.h"

#include <chrono>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <fcntl.h>
#include <stdexcept>
#include <sys/resource.h>
#include <sys/wait.h>
#include <thread>
#include <unistd.h>

#if defined(__SANITIZE_ADDRESS__)
#define Q3_LIMITS_ASAN 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define Q3_LIMITS_ASAN 1
#endif
#endif

namespace q3::test {

namespace {

std::string readAndRemove(const std::string& path) {
    std::string text;
    if (FILE* f = std::fopen(path.c_str(), "rb")) {
        char buffer[4096];
        size_t n;
        while ((n = std::fread(buffer, 1, sizeof buffer, f)) > 0) text.append(buffer, n);
        std::fclose(f);
    }
    std::remove(path.c_str());
    return text;
}

}  // namespace

std::vector<std::string> MeasuredRun::linesStartingWith(const std::string& prefix) const {
    std::vector<std::string> lines;
    size_t start = 0;
    while (start < output.size()) {
        size_t end = output.find('\n', start);
        if (end == std::string::npos) end = output.size();
        const std::string line = output.substr(start, end - start);
        if (line.rfind(prefix, 0) == 0) lines.push_back(line);
        start = end + 1;
    }
    return lines;
}

std::string MeasuredRun::describe() const {
    char head[160];
    if (signalled)
        std::snprintf(head, sizeof head, "killed by signal %d%s", signal, timedOut ? " (time budget exceeded)" : "");
    else
        std::snprintf(head, sizeof head, "exit code %d", exitCode);
    std::string tail = output.size() > 1500 ? "..." + output.substr(output.size() - 1500) : output;
    return std::string(head) + ", " + std::to_string(seconds) + " s, peak RSS " + std::to_string(peakRssKb / 1024) +
           " MB, output:\n" + tail;
}

MeasuredRun runMeasured(const std::vector<std::string>& argv, const RunLimits& limits) {
    char outputPath[] = "/tmp/q3limits-output-XXXXXX";
    const int outputFd = ::mkstemp(outputPath);
    if (outputFd < 0) throw std::runtime_error("cannot create a temporary output file");

    std::vector<char*> args;
    for (const std::string& a : argv) args.push_back(const_cast<char*>(a.c_str()));
    args.push_back(nullptr);

    const auto start = std::chrono::steady_clock::now();
    const pid_t pid = ::fork();
    if (pid < 0) {
        ::close(outputFd);
        throw std::runtime_error("fork failed");
    }
    if (pid == 0) {
        // Child: only async-signal-safe calls until exec.
        ::dup2(outputFd, STDOUT_FILENO);
        ::dup2(outputFd, STDERR_FILENO);
        ::close(outputFd);
#ifndef Q3_LIMITS_ASAN
        struct rlimit cap;
        cap.rlim_cur = cap.rlim_max = static_cast<rlim_t>(limits.addressSpaceBytes);
        ::setrlimit(RLIMIT_AS, &cap);
#endif
        ::execv(args[0], args.data());
        ::_exit(127);
    }
    ::close(outputFd);

    MeasuredRun run;
    int status = 0;
    struct rusage usage {};
    for (;;) {
        const pid_t done = ::wait4(pid, &status, WNOHANG, &usage);
        if (done == pid) break;
        if (done < 0) throw std::runtime_error("wait4 failed");
        const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        if (!run.timedOut && elapsed > limits.seconds) {
            run.timedOut = true;
            ::kill(pid, SIGKILL);
        }
        std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
    run.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    run.peakRssKb = usage.ru_maxrss;
    run.signalled = WIFSIGNALED(status);
    run.signal = run.signalled ? WTERMSIG(status) : 0;
    run.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    run.output = readAndRemove(outputPath);
    return run;
}

}  // namespace q3::test
