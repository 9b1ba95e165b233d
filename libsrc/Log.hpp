// Spindrift — the run log. Info lines go to stdout; warnings to stdout prefixed "--> Warning:".
// When stdout is a terminal, a progress line is kept at the bottom and log lines are printed
// above it.
#pragma once

#include <sstream>
#include <string>

namespace spindrift::log {

void info(const std::string& line);
void warning(const std::string& line);
// Progress line (terminal only; no-op otherwise). Cleared by clearProgress().
void progress(const std::string& line);
void clearProgress();
bool stdoutIsTerminal();
// Silence info lines (tests); warnings still go out.
void setQuiet(bool quiet);

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
