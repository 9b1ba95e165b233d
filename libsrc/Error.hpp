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

// Returns the candidate closest to 'word' (edit distance), or "" when nothing is close.
std::string closestMatch(const std::string& word, const std::vector<std::string>& candidates);

} // namespace spindrift
