#include "Log.hpp"

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstring>
#include <iostream>
#include <mutex>
#include <sys/stat.h>
#include <unistd.h>

namespace spindrift::log {
namespace {
std::mutex mutex;
bool quiet = false;
std::string progressText;               // shown below the log lines until clearProgress()
std::atomic<bool> progressShown{false}; // atomic: a fatal-signal handler erases it
// progress(): at most one redraw per interval (a run of short steps would otherwise redraw it
// thousands of times a second: megabytes over ssh); log lines still redraw it at once
constexpr auto progressRedrawInterval = std::chrono::milliseconds(250);
std::chrono::steady_clock::time_point lastProgressDraw;

void clearProgressLocked() {
    if (progressShown.load()) {
        std::cout << "\r\033[K";
        progressShown.store(false);
    }
}

void redrawProgressLocked() {
    if (progressText.empty() || !stdoutIsTerminal()) return;
    std::cout << progressText;
    progressShown.store(true);
}

// The fatal-signal message's context: two buffers, the run loop fills the one not in use and
// then switches, so a handler never reads a half-written one.
constexpr std::size_t contextCapacity = 201;
char fatalContexts[2][contextCapacity] = {"during set-up", ""};
std::atomic<int> activeFatalContext{0};
std::atomic<bool> fatalSignalSeen{false};

void writeAll(int fd, const char* text, std::size_t length) {
    while (length > 0) {
        const ssize_t n = ::write(fd, text, length);
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0) return;
        text += n;
        length -= std::size_t(n);
    }
}

void append(char* buffer, std::size_t capacity, std::size_t& length, const char* text) {
    while (*text && length + 1 < capacity) buffer[length++] = *text++;
    buffer[length] = '\0';
}

extern "C" void onFatalSignal(int signal) {
    if (!fatalSignalSeen.exchange(true)) { // one message, even if several threads fault
        const int savedErrno = errno;
        char text[contextCapacity + 64];
        std::size_t n = 0;
        append(text, sizeof text, n, "spindrift: fatal signal ");
        append(text, sizeof text, n, signalName(signal));
        append(text, sizeof text, n, " ");
        append(text, sizeof text, n, fatalContexts[activeFatalContext.load()]);
        append(text, sizeof text, n, "\n");
        writeLastWords(text, n);
        errno = savedErrno;
    }
    // the default action (SA_RESETHAND restored it; SA_NODEFER lets it through at once): the
    // process ends as killed by this signal, with a core dump where the system keeps them
    ::signal(signal, SIG_DFL);
    ::raise(signal);
}
} // namespace

bool stdoutIsTerminal() {
    static const bool tty = ::isatty(STDOUT_FILENO) == 1;
    return tty;
}

void setQuiet(bool q) { quiet = q; }

void info(const std::string& line) {
    if (quiet) return;
    std::lock_guard lock(mutex);
    clearProgressLocked();
    std::cout << line << '\n';
    redrawProgressLocked();
    std::cout << std::flush;
}

void warning(const std::string& line) {
    std::lock_guard lock(mutex);
    clearProgressLocked();
    std::cout << "--> Warning: " << line << '\n';
    redrawProgressLocked();
    std::cout << std::flush;
}

void progress(const std::string& line) {
    if (quiet || !stdoutIsTerminal()) return;
    std::lock_guard lock(mutex);
    progressText = line;
    const auto now = std::chrono::steady_clock::now();
    if (progressShown.load() && now - lastProgressDraw < progressRedrawInterval) return; // drawn by the next one
    lastProgressDraw = now;
    std::cout << "\r\033[K" << line << std::flush;
    progressShown.store(true);
}

void clearProgress() {
    std::lock_guard lock(mutex);
    clearProgressLocked();
    progressText.clear();
    std::cout << std::flush;
}

const char* signalName(int signal) {
    switch (signal) {
    case SIGSEGV: return "SIGSEGV";
    case SIGBUS: return "SIGBUS";
    case SIGFPE: return "SIGFPE";
    case SIGILL: return "SIGILL";
    case SIGABRT: return "SIGABRT";
    case SIGINT: return "SIGINT";
    case SIGTERM: return "SIGTERM";
    case SIGHUP: return "SIGHUP";
    default: return "signal";
    }
}

void writeLastWords(const char* text, std::size_t length) {
    if (progressShown.load()) writeAll(STDOUT_FILENO, "\r\033[K", 4);
    writeAll(STDOUT_FILENO, text, length);
    struct stat out {}, err {};
    const bool same = ::fstat(STDOUT_FILENO, &out) == 0 && ::fstat(STDERR_FILENO, &err) == 0 &&
                      out.st_dev == err.st_dev && out.st_ino == err.st_ino;
    if (!same) writeAll(STDERR_FILENO, text, length);
}

void installFatalSignalHandlers() {
    // an alternate stack for the handler, so that a stack overflow in the main thread still
    // gets its message
    static char alternateStack[64 * 1024];
    stack_t stack{};
    stack.ss_sp = alternateStack;
    stack.ss_size = sizeof alternateStack;
    const bool haveStack = ::sigaltstack(&stack, nullptr) == 0;
    struct sigaction action {};
    action.sa_handler = onFatalSignal;
    sigemptyset(&action.sa_mask);
    action.sa_flags = SA_RESETHAND | SA_NODEFER | (haveStack ? SA_ONSTACK : 0);
    for (int signal : {SIGSEGV, SIGBUS, SIGFPE, SIGILL, SIGABRT}) ::sigaction(signal, &action, nullptr);
}

void setFatalSignalContext(std::string_view context) {
    const int next = 1 - activeFatalContext.load();
    const std::size_t n = std::min(context.size(), contextCapacity - 1);
    std::memcpy(fatalContexts[next], context.data(), n);
    fatalContexts[next][n] = '\0';
    activeFatalContext.store(next);
}

} // namespace spindrift::log
