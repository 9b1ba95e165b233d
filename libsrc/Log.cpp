#include "Log.hpp"

#include <cstdio>
#include <iostream>
#include <mutex>
#include <unistd.h>

namespace spindrift::log {
namespace {
std::mutex mutex;
bool quiet = false;
bool progressShown = false;

void clearProgressLocked() {
    if (progressShown) {
        std::cout << "\r\033[K";
        progressShown = false;
    }
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
}

void warning(const std::string& line) {
    std::lock_guard lock(mutex);
    clearProgressLocked();
    std::cout << "--> Warning: " << line << std::endl;
}

void progress(const std::string& line) {
    if (quiet || !stdoutIsTerminal()) return;
    std::lock_guard lock(mutex);
    std::cout << "\r\033[K" << line << std::flush;
    progressShown = true;
}

void clearProgress() {
    std::lock_guard lock(mutex);
    clearProgressLocked();
    std::cout << std::flush;
}

} // namespace spindrift::log
