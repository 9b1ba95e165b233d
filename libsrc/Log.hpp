// Spindrift — the run log. Info lines go to stdout; warnings to stdout prefixed "--> Warning:".
// Every line is flushed as it is written, so a log redirected to a file (log.spindrift) is
// complete up to the last line even when the process dies. When stdout is a terminal, a
// progress line is kept at the bottom: log lines are printed above it and it is drawn again
// below them, until clearProgress().
//
// Last words: a fatal signal (SIGSEGV, SIGBUS, SIGFPE, SIGILL, SIGABRT) writes
//   spindrift: fatal signal SIGSEGV at step 41, time 0.000737 (last completed step)
// to the log and to stderr, with async-signal-safe calls only (write(2) of a buffer the run
// loop formats after each step), then dies of the signal, so the exit status stays its own.
#pragma once

#include <cstddef>
#include <sstream>
#include <string>
#include <string_view>

namespace spindrift::log {

void info(const std::string& line);
void warning(const std::string& line);
// Progress line (terminal only; no-op otherwise). Cleared by clearProgress(). Redrawn at most 4
// times a second (a call within 250 ms of the last redraw only keeps its text, which the next
// redraw or log line shows).
void progress(const std::string& line);
void clearProgress();
bool stdoutIsTerminal();
// Silence info lines (tests); warnings still go out.
void setQuiet(bool quiet);

// Installs the fatal-signal handlers (once, at start-up). Until setFatalSignalContext is
// called the message says "during set-up".
void installFatalSignalHandlers();
// What the fatal-signal message says after the signal's name, e.g. "at step 41, time 0.000737
// (last completed step)". Not async-signal-safe itself: call it from the run loop, never from
// a handler. Longer text is cut at 200 characters.
void setFatalSignalContext(std::string_view context);

// Async-signal-safe helpers for signal handlers (write(2) only, no allocation):
// "SIGSEGV", "SIGINT", ... ("signal" for one not named here).
const char* signalName(int signal);
// Writes 'text' to stdout (the log) and to stderr, once when both are the same file (a log
// taking both, or the terminal); first erases a progress line on the terminal.
void writeLastWords(const char* text, std::size_t length);

// Stream-style helper: log::Line() << "Time = " << t;  (printed at destruction)
class Line {
public:
    Line() = default;
    Line(const Line&) = delete;
    ~Line() { info(stream_.str()); }
    template <class T> Line& operator<<(const T& v) { stream_ << v; return *this; }
private:
    std::ostringstream stream_;
};

} // namespace spindrift::log
