// Spindrift — errors caused by the user's input: they carry file, line, column and keyword
// so the one-line message tells exactly where to look.
#pragma once

#include <stdexcept>
#include <string>
#include <vector>

namespace spindrift {

struct SourceLocation {
    std::string file;   // path as given (e.g. "system/controlDict")
    int line = 0;       // 1-based, 0 = unknown
    int column = 0;     // 1-based, 0 = unknown
};

// "<file>:<line>:<column>: <severity>: <message> (keyword '<kw>')"; parts that are unknown
// (empty file, line or column 0) are left out, and so is an empty severity. An InputError's
// text with severity "error"; a log::warning about an input that is legal but likely wrong
// with none (the log says "--> Warning: <file>:<line>:<column>: ...").
std::string locatedMessage(const SourceLocation& where, const std::string& severity, const std::string& message,
                           const std::string& keyword = "");

// Message format: "<file>:<line>:<column>: error: <what> (keyword '<kw>')"
class InputError : public std::runtime_error {
public:
    InputError(const SourceLocation& where, const std::string& message,
               const std::string& keyword = "");
    const SourceLocation& where() const { return where_; }
    const std::string& keyword() const { return keyword_; }
    const std::string& message() const { return message_; }

private:
    SourceLocation where_;
    std::string keyword_;
    std::string message_;
};

// The time loop stopped at a state it refuses to go on from (a blow-up: a particle beyond the
// domain, too fast, a density error too large, a non-finite field), after writing the last good
// state; the message names it and what to try.
class BlowUpError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

// Why writing 'path' failed, from the errno the failed call left: "no space left on device
// (<path>)" for ENOSPC (a full disk), "disk quota exceeded (<path>)" for EDQUOT, else
// "cannot write '<path>': <strerror>" ("cannot write '<path>'" when errno says nothing).
std::string describeWriteFailure(const std::string& path, int errorNumber);

// Returns the candidate closest to 'word' (edit distance), or "" when nothing is close.
std::string closestMatch(const std::string& word, const std::vector<std::string>& candidates);

} // namespace spindrift
