// Spindrift — OpenFOAM-syntax dictionaries.
//
// Syntax: optional FoamFile { ... } header (kept, ignored by lookups), `keyword value;`,
// sub-dictionaries `name { ... }`, lists `( ... )` (nested, e.g. vectors `(0 -9.81 0)`),
// `//` and `/* */` comments, double-quoted strings, `#include "file"` (relative to the
// including file; `#includeIfPresent` ignores a missing file), `$name` substitution (searched in
// the current scope, then enclosing scopes; `$a.b` looks into sub-dictionary a; `kw $dict;`
// copies a dictionary, `$dict;` alone merges its entries into the current scope; a substituted
// keyword counts as used). A keyword given twice in one dictionary by the same text (a file, one
// #include, one `$dict;` merge) is an error naming both lines: two walls `tank`, a repeated
// `endTime`. An entry overriding one that an #include or a `$dict;` merge brought in is logged
// ("controlDict:20:1: 'endTime' overrides the entry of controlDict at common:3:1"): a value
// replaces it, a dictionary is merged into it entry by entry (OpenFOAM's #inputMode merge), so
// `#include "defaults"` followed by changes works as in OpenFOAM. Outside parentheses a value
// ends on its line: a value token on a new line is reported as a missing ';'. Every parse error
// throws InputError naming file:line:column (columns count UTF-8 characters, not bytes), and the
// keyword when it happens in a keyword's value.
//
// Bounds, so that no input can crash the solver or exhaust its memory (each is an InputError):
// sub-dictionaries and lists nest at most 256 levels deep (a copied `$dict` counts at its new
// depth), #include files at most 32; a file is at most 64 MiB, and the files read for one
// dictionary (#include repeats counted) at most 256 MiB; reading one dictionary handles at most
// 10^7 tokens (each keyword and value token counts 1, a sub-dictionary 5; read, #included or
// substituted; about 1 GB), of which `$name` substitution and `$dict` copies may add 10^5.
// Parsing and lookups take time linear in the input: keywords are hashed.
//
// Lookups are typed. A required keyword that is missing, or a value of the wrong type, throws
// InputError naming file, line and keyword. getOrDefault() echoes a used default once to the
// log ("    default: pressure.gamma 7"). Every lookup marks the keyword as used, so a model can
// call checkAllKeywordsUsed() after reading its sub-dictionary and a typo becomes an error
// with a "did you mean" hint instead of a silent default. toString(indent) indents by 'indent'
// spaces (4 more per sub-dictionary level).
#pragma once

#include "Error.hpp"
#include "Types.hpp"

#include <filesystem>
#include <map>
#include <memory>
#include <set>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

namespace spindrift {

struct Token {
    enum class Kind { Word, Number, String, Open, Close }; // Open/Close = '(' and ')'
    Kind kind = Kind::Word;
    std::string text;
    SourceLocation where;
};

class Dictionary;

namespace detail {
// The keyword index of a Dictionary hashes with FNV-1a: the hash of a prefix extends to that of a
// longer prefix, so all the prefixes of a `$a.b.c` path are hashed in one pass. (The hash is
// deliberately not noexcept: libstdc++ then stores each key's hash instead of rehashing keys
// while it walks a bucket.)
struct HashedKeyword {
    std::string_view text;
    std::size_t hash;
};
struct KeywordHash {
    using is_transparent = void;
    static constexpr std::size_t seed = 14695981039346656037ull;
    static std::size_t extend(std::size_t hash, std::string_view text) noexcept {
        for (const char c : text) hash = (hash ^ static_cast<unsigned char>(c)) * 1099511628211ull;
        return hash;
    }
    std::size_t operator()(std::string_view text) const { return extend(seed, text); }
    std::size_t operator()(const HashedKeyword& key) const { return key.hash; }
};
struct KeywordEqual {
    using is_transparent = void;
    bool operator()(std::string_view a, std::string_view b) const noexcept { return a == b; }
    bool operator()(const HashedKeyword& a, std::string_view b) const noexcept { return a.text == b; }
    bool operator()(std::string_view a, const HashedKeyword& b) const noexcept { return a == b.text; }
};
struct ScopedName; // "controlDict.pressure", joined only when asked for (Dictionary.cpp)
} // namespace detail

// One `keyword value;` or `keyword { ... }` entry.
struct Entry {
    std::string keyword;
    SourceLocation where;                 // location of the keyword
    std::vector<Token> tokens;            // the value, for non-dictionary entries
    std::shared_ptr<Dictionary> dict;     // set for sub-dictionaries
    bool isDict() const { return dict != nullptr; }
};

class Dictionary {
public:
    Dictionary() = default;
    explicit Dictionary(std::string scopedName, SourceLocation where = {});

    // Parse a file / a string. Throws InputError on syntax errors and on a missing file
    // (for the top file too: "cannot open file").
    static Dictionary fromFile(const std::filesystem::path& file);
    static Dictionary fromString(const std::string& text, const std::string& fileName = "<string>");

    // Name for messages: "sphSchemes" for a top-level file, "sphSchemes.pressure" below.
    const std::string& name() const;
    const SourceLocation& where() const { return where_; }

    bool found(const std::string& keyword) const;
    bool isDict(const std::string& keyword) const;
    std::vector<std::string> keywords() const;  // in file order (FoamFile excluded)

    // Sub-dictionary lookups (mark the keyword used).
    const Dictionary& subDict(const std::string& keyword) const;            // required
    const Dictionary* findDict(const std::string& keyword) const;           // nullptr if absent

    // Raw entry (nullptr if absent); does not mark as used.
    const Entry* findEntry(const std::string& keyword) const;
    // Location of a keyword, or of the dictionary itself when absent.
    SourceLocation locationOf(const std::string& keyword) const;

    // Typed lookups. Supported T: double, float, int, long, unsigned, bool (true/false, on/off,
    // yes/no), std::string (a word or quoted string), Vec3 (a list of 3 numbers),
    // std::vector<double>, std::vector<std::string>, std::vector<Vec3>.
    template <class T> T get(const std::string& keyword) const;
    template <class T> T getOrDefault(const std::string& keyword, const T& defaultValue) const;

    // Like get<std::string> but the value must be one of 'allowed' (error lists them and
    // suggests the closest).
    std::string getWord(const std::string& keyword, const std::vector<std::string>& allowed) const;
    std::string getWordOrDefault(const std::string& keyword, const std::vector<std::string>& allowed,
                                 const std::string& defaultValue) const;

    // Throws InputError at the first keyword of this dictionary (not recursive; FoamFile
    // ignored) that no lookup has touched, with "did you mean" from the touched ones.
    void checkAllKeywordsUsed() const;
    // Marks a keyword as used without reading it (e.g. `type`, read by the registry).
    void markUsed(const std::string& keyword) const;

    // Modification (used by the bench utility's overrides and by tests).
    // 'valueText' is parsed as dictionary value syntax, e.g. "0.01" or "(0 -9.81 0)".
    void set(const std::string& keyword, const std::string& valueText);
    void setDict(const std::string& keyword, const Dictionary& dict);
    void remove(const std::string& keyword);

    // Writes the dictionary back in OpenFOAM syntax (FoamFile header included when present).
    std::string toString(int indent = 0) const;

    const std::vector<Entry>& entries() const { return entries_; }

private:
    friend class DictionaryParser;
    using Index = std::unordered_map<std::string, std::size_t, detail::KeywordHash, detail::KeywordEqual>;

    const Entry& requireEntry(const std::string& keyword) const;
    template <class Key> const Entry* find(const Key& keyword) const; // Key: string_view or HashedKeyword
    template <class Key> Entry* find(const Key& keyword);
    void append(Entry entry);

    std::shared_ptr<const detail::ScopedName> name_;
    SourceLocation where_;
    std::vector<Entry> entries_; // in file order
    Index index_;                // keyword -> position in entries_
    mutable std::set<std::string> used_;
};

// Echo of defaults: each "<scope>.<keyword>" is logged once per process.
void logDefaultOnce(const std::string& scopedKeyword, const std::string& valueText);

} // namespace spindrift
