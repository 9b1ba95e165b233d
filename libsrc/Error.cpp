#include "Error.hpp"

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <cstddef>
#include <limits>

namespace spindrift {
std::string locatedMessage(const SourceLocation& where, const std::string& severity, const std::string& message,
                           const std::string& keyword) {
    std::string prefix = where.file;
    if (where.line > 0) {
        prefix.append(1, ':').append(std::to_string(where.line));
        if (where.column > 0) prefix.append(1, ':').append(std::to_string(where.column));
    }
    std::string text = severity.empty() ? (prefix.empty() ? "" : prefix + ": ")
                       : prefix.empty()   ? severity + ": "
                                          : prefix + ": " + severity + ": ";
    text += message;
    if (!keyword.empty()) text += " (keyword '" + keyword + "')";
    return text;
}

std::string describeWriteFailure(const std::string& path, int errorNumber) {
    if (errorNumber == ENOSPC) return "no space left on device (" + path + ")";
    if (errorNumber == EDQUOT) return "disk quota exceeded (" + path + ")";
    if (errorNumber == 0) return "cannot write '" + path + "'";
    return "cannot write '" + path + "': " + std::strerror(errorNumber);
}

namespace {

std::string formatMessage(const SourceLocation& where, const std::string& message,
                          const std::string& keyword) {
    return locatedMessage(where, "error", message, keyword);
}

// Levenshtein distance (insertions, deletions and substitutions all cost 1).
std::size_t editDistance(const std::string& a, const std::string& b) {
    std::vector<std::size_t> previous(b.size() + 1), current(b.size() + 1);
    for (std::size_t j = 0; j <= b.size(); ++j) previous[j] = j;
    for (std::size_t i = 1; i <= a.size(); ++i) {
        current[0] = i;
        for (std::size_t j = 1; j <= b.size(); ++j) {
            const std::size_t substitution = previous[j - 1] + (a[i - 1] == b[j - 1] ? 0 : 1);
            current[j] = std::min({previous[j] + 1, current[j - 1] + 1, substitution});
        }
        std::swap(previous, current);
    }
    return previous[b.size()];
}

} // namespace

InputError::InputError(const SourceLocation& where, const std::string& message,
                       const std::string& keyword)
    : std::runtime_error(formatMessage(where, message, keyword)),
      where_(where),
      keyword_(keyword),
      message_(message) {}

std::string closestMatch(const std::string& word, const std::vector<std::string>& candidates) {
    const std::string* best = nullptr;
    std::size_t bestDistance = std::numeric_limits<std::size_t>::max();
    for (const auto& candidate : candidates) {
        const std::size_t d = editDistance(word, candidate);
        if (d < bestDistance) {
            bestDistance = d;
            best = &candidate;
        }
    }
    const std::size_t limit = std::max<std::size_t>(2, word.size() / 3);
    return best && bestDistance <= limit ? *best : std::string();
}

} // namespace spindrift
