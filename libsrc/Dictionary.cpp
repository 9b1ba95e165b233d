// Spindrift — OpenFOAM-syntax dictionaries: lexer, parser, typed lookups and writer.
//
// Parsing is done in two layers:
//   Lexer            turns text into tokens (words, numbers, strings, punctuation, `$name`,
//                    `#directive`) and skips comments; it knows line and column of everything.
//   DictionaryParser builds Dictionary objects from the tokens: entries, sub-dictionaries,
//                    `#include`, `$name` substitution and the precise syntax errors.
// Typed lookups (get<T>) are explicit instantiations at the end of this file.
#include "Dictionary.hpp"

#include "Log.hpp"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <fstream>
#include <iomanip>
#include <limits>
#include <mutex>
#include <optional>
#include <sstream>
#include <string_view>
#include <system_error>
#include <type_traits>
#include <utility>

namespace spindrift {
namespace fs = std::filesystem;

namespace {

const std::string headerKeyword = "FoamFile";

// Bounds on what one dictionary may hold (see Dictionary.hpp). Sub-dictionaries are parsed
// recursively, so their nesting bounds the stack (10,000 levels overflowed it). The token bounds
// keep memory in check: a token takes about 100 bytes, a sub-dictionary about five times that,
// so it counts as 5. The tighter bound on what `$name` substitution adds stops doubling
// (`b ($a $a); c ($b $b); ...`) while it is still cheap: a 1 kB input reached 10^7 tokens in
// seconds and more than 1 GB.
constexpr int maxIncludeDepth = 32;
constexpr std::size_t maxNestingLevels = 256;
constexpr std::size_t maxTokens = 10'000'000;
constexpr std::size_t maxSubstitutedTokens = 100'000;
constexpr std::size_t subDictionaryTokens = 5; // with its keyword
constexpr std::uintmax_t maxFileBytes = std::uintmax_t(64) << 20;
constexpr std::uintmax_t maxTotalFileBytes = std::uintmax_t(256) << 20;
constexpr int keywordWidth = 16; // toString() pads keywords to this width, as OpenFOAM does

bool isWordChar(char c) {
    return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '.' || c == ':' ||
           c == '<' || c == '>' || c == '-' || c == '+';
}

bool isWord(const std::string& text) {
    return !text.empty() && std::all_of(text.begin(), text.end(), isWordChar);
}

std::string locationText(const SourceLocation& where) {
    return where.file + ":" + std::to_string(where.line) + ":" + std::to_string(where.column);
}

std::string join(const std::vector<std::string>& words) {
    std::string out;
    for (const auto& w : words) out += (out.empty() ? "" : " ") + w;
    return out;
}

std::string quote(const std::string& text) {
    std::string out = "\"";
    for (char c : text) {
        if (c == '"' || c == '\\') out += '\\';
        out += c;
    }
    return out + "\"";
}

enum class NumberStatus { Ok, OutOfRange, NotANumber };

// A token is a number when it parses completely as a double: an optional sign, then a digit or
// '.', e.g. 1, -9.81, +2, 1e-5, .5. ("inf", "nan" and hex are words.)
NumberStatus parseNumber(const std::string& text, double& value) {
    std::string_view s = text;
    if (!s.empty() && s.front() == '+') {
        s.remove_prefix(1);
        if (!s.empty() && s.front() == '-') return NumberStatus::NotANumber;
    }
    const std::size_t first = !s.empty() && s.front() == '-' ? 1 : 0;
    if (s.size() <= first) return NumberStatus::NotANumber;
    const char c = s[first];
    if (!std::isdigit(static_cast<unsigned char>(c)) && c != '.') return NumberStatus::NotANumber;
    const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), value);
    if (end != s.data() + s.size()) return NumberStatus::NotANumber;
    if (ec == std::errc::result_out_of_range) return NumberStatus::OutOfRange;
    if (ec != std::errc()) return NumberStatus::NotANumber;
    return NumberStatus::Ok;
}

std::string sizeText(std::uintmax_t bytes) {
    std::ostringstream s;
    s << std::fixed << std::setprecision(1) << static_cast<double>(bytes) / double(1 << 20) << " MiB (" << bytes
      << " bytes)";
    return s.str();
}

struct FileContents {
    enum class Status { Read, CannotOpen, TooLarge };
    Status status = Status::CannotOpen;
    std::uintmax_t size = 0; // known unless CannotOpen
    std::string text;

    // For Status::TooLarge.
    std::string tooLargeMessage() const {
        return "is " + sizeText(size) + "; a dictionary file may be at most " + std::to_string(maxFileBytes >> 20) + " MiB";
    }
};

// Regular files only (never /dev/zero or a FIFO: a dictionary must not hang the solver), of at
// most maxFileBytes.
FileContents readWholeFile(const fs::path& file) {
    FileContents out;
    std::error_code ec;
    if (!fs::is_regular_file(file, ec)) return out;
    const std::uintmax_t size = fs::file_size(file, ec);
    if (ec) return out;
    if (size > maxFileBytes) {
        out.status = FileContents::Status::TooLarge;
        out.size = size;
        return out;
    }
    std::ifstream in(file, std::ios::binary);
    if (!in) return out;
    out.text.resize(static_cast<std::size_t>(size));
    in.read(out.text.data(), static_cast<std::streamsize>(size));
    out.text.resize(static_cast<std::size_t>(in.gcount())); // the file may have shrunk meanwhile
    out.size = out.text.size();
    out.status = FileContents::Status::Read;
    return out;
}

// ---------------------------------------------------------------------------------------------
// Lexer

enum class Lex { Word, Number, String, Open, Close, LBrace, RBrace, Semicolon, Variable, Directive, End };

struct LexToken {
    Lex kind = Lex::End;
    std::string text;    // word/number text, unescaped string, variable name (without '$'),
                         // directive (with '#')
    SourceLocation where;
    int endLine = 0;     // position just after the token
    int endColumn = 0;
};

bool isUtf8Continuation(char c) { return (static_cast<unsigned char>(c) & 0xC0) == 0x80; }

// Messages show at most the start of a long value (a type error must not print a list of a
// million tokens) or of a long word.
constexpr std::size_t maxShownTokens = 12;
constexpr std::size_t maxShownCharacters = 80;

std::string shortText(std::string text) {
    if (text.size() <= maxShownCharacters) return text;
    std::size_t length = maxShownCharacters;
    while (length > 0 && isUtf8Continuation(text[length])) --length; // whole characters only
    text.resize(length);
    return text + " ...";
}

// How a token is named in "found ..." parts of messages.
std::string describe(const LexToken& t) {
    switch (t.kind) {
    case Lex::Word:
    case Lex::Number: return "'" + shortText(t.text) + "'";
    case Lex::String: return "string " + shortText(quote(t.text));
    case Lex::Open: return "'('";
    case Lex::Close: return "')'";
    case Lex::LBrace: return "'{'";
    case Lex::RBrace: return "'}'";
    case Lex::Semicolon: return "';'";
    case Lex::Variable: return "'$" + shortText(t.text) + "'";
    case Lex::Directive: return "'" + t.text + "'";
    case Lex::End: return "end of file";
    }
    return "?";
}

// Length of the UTF-8 sequence starting with byte 'lead' (1 for ASCII), 0 for a byte that cannot
// start one.
int utf8Length(unsigned char lead) {
    if (lead < 0x80) return 1;
    if (lead >= 0xC2 && lead <= 0xDF) return 2;
    if (lead >= 0xE0 && lead <= 0xEF) return 3;
    if (lead >= 0xF0 && lead <= 0xF4) return 4;
    return 0;
}

class Lexer {
public:
    Lexer(std::string text, std::string file) : text_(std::move(text)), file_(std::move(file)) {
        if (text_.compare(0, 3, "\xEF\xBB\xBF") == 0) pos_ = 3; // UTF-8 byte order mark
    }

    const std::string& file() const { return file_; }

    // While a keyword's value is read, errors of the lexer name that keyword too: a stray
    // character or '0,02' is then reported with the keyword it spoils.
    class ValueOf {
    public:
        ValueOf(Lexer& lexer, const std::string& keyword) : lexer_(lexer) { lexer_.keyword_ = keyword; }
        ~ValueOf() { lexer_.keyword_.clear(); }
        ValueOf(const ValueOf&) = delete;
        ValueOf& operator=(const ValueOf&) = delete;

    private:
        Lexer& lexer_;
    };

    const LexToken& peek() {
        if (!peeked_) {
            lookahead_ = scan();
            peeked_ = true;
        }
        return lookahead_;
    }

    LexToken next() {
        peek();
        peeked_ = false;
        return std::move(lookahead_);
    }

private:
    bool atEnd() const { return pos_ >= text_.size(); }
    char current() const { return text_[pos_]; }
    char following() const { return pos_ + 1 < text_.size() ? text_[pos_ + 1] : '\0'; }
    SourceLocation here() const { return {file_, line_, column_}; }

    [[noreturn]] void fail(const SourceLocation& where, const std::string& message) const {
        throw InputError(where, message, keyword_);
    }

    // Columns count characters: the continuation bytes of a UTF-8 character take no column.
    void advance() {
        if (text_[pos_] == '\n') {
            ++line_;
            column_ = 1;
        } else if (!isUtf8Continuation(text_[pos_])) {
            ++column_;
        }
        ++pos_;
    }

    // "unexpected character ..." for the character at the current position, shown as itself when
    // it is printable ASCII or valid UTF-8.
    [[noreturn]] void unexpectedCharacter(const SourceLocation& where) const {
        const auto lead = static_cast<unsigned char>(current());
        if (lead == ',') fail(where, "unexpected character ',' (list elements are separated by spaces, not commas)");
        if (std::isprint(lead)) fail(where, "unexpected character '" + std::string(1, current()) + "'");
        const int length = utf8Length(lead);
        if (length > 1 && pos_ + static_cast<std::size_t>(length) <= text_.size()) {
            char32_t code = lead & (0xFF >> (length + 1));
            bool valid = true;
            for (int i = 1; i < length; ++i) {
                valid = valid && isUtf8Continuation(text_[pos_ + i]);
                code = (code << 6) | (static_cast<unsigned char>(text_[pos_ + i]) & 0x3F);
            }
            const char32_t smallest = length == 2 ? 0x80 : length == 3 ? 0x800 : 0x10000;
            valid = valid && code >= smallest && code <= 0x10FFFF && !(code >= 0xD800 && code <= 0xDFFF);
            if (valid) {
                std::ostringstream u;
                u << "U+" << std::uppercase << std::hex << std::setw(4) << std::setfill('0') << std::uint32_t(code);
                fail(where, "unexpected character '" + text_.substr(pos_, static_cast<std::size_t>(length)) + "' (" +
                                u.str() + "; only comments and quoted strings may hold non-ASCII text)");
            }
        }
        std::ostringstream hex;
        hex << "byte 0x" << std::hex << std::setw(2) << std::setfill('0') << int(lead);
        fail(where, "unexpected character " + hex.str() + (lead >= 0x80 ? " (not UTF-8 text)" : ""));
    }

    // A number written with a decimal comma, '0,02': the lexer is at the ','.
    [[noreturn]] void decimalComma(const LexToken& number) {
        const SourceLocation comma = here();
        std::string written = number.text;
        written += ',';
        advance();
        written += readWordChars();
        if (!atEnd() && current() == ',') // '1,2,3': commas as list separators
            fail(comma, "unexpected character ',' (list elements are separated by spaces, not commas)");
        fail(number.where, "'" + shortText(written) + "' is not a number (use a decimal point)");
    }

    void skipSpaceAndComments() {
        while (!atEnd()) {
            const char c = current();
            if (std::isspace(static_cast<unsigned char>(c))) {
                advance();
            } else if (c == '/' && following() == '/') {
                // to the end of the line in one step: the column is reset there anyway
                pos_ = std::min(text_.find('\n', pos_), text_.size());
            } else if (c == '/' && following() == '*') {
                const SourceLocation start = here();
                advance();
                advance();
                for (;;) {
                    if (atEnd()) fail(start, "unterminated comment: '/*' without a matching '*/'");
                    if (current() == '*' && following() == '/') {
                        advance();
                        advance();
                        break;
                    }
                    advance();
                }
            } else {
                return;
            }
        }
    }

    std::string readWordChars() {
        std::string s;
        while (!atEnd() && isWordChar(current())) {
            s += current();
            advance();
        }
        return s;
    }

    LexToken scan() {
        skipSpaceAndComments();
        LexToken t;
        if (atEnd()) {
            // End of input is reported just after the last token (not on a trailing empty line).
            t.where = {file_, lastEndLine_, lastEndColumn_};
            t.endLine = lastEndLine_;
            t.endColumn = lastEndColumn_;
            return t;
        }
        t.where = here();
        const char c = current();
        auto single = [&](Lex kind) {
            t.kind = kind;
            t.text = std::string(1, c);
            advance();
        };
        switch (c) {
        case '(': single(Lex::Open); break;
        case ')': single(Lex::Close); break;
        case '{': single(Lex::LBrace); break;
        case '}': single(Lex::RBrace); break;
        case ';': single(Lex::Semicolon); break;
        case '"':
            t.kind = Lex::String;
            advance();
            for (;;) {
                if (atEnd() || current() == '\n')
                    fail(t.where, "unterminated string: missing closing '\"' on this line");
                const char s = current();
                if (s == '"') {
                    advance();
                    break;
                }
                if (s == '\\' && (following() == '"' || following() == '\\')) advance();
                t.text += current();
                advance();
            }
            break;
        case '$':
            t.kind = Lex::Variable;
            advance();
            t.text = readWordChars();
            if (t.text.empty()) fail(t.where, "expected a keyword name after '$'");
            break;
        case '#':
            t.kind = Lex::Directive;
            advance();
            t.text = "#";
            while (!atEnd() && std::isalpha(static_cast<unsigned char>(current()))) {
                t.text += current();
                advance();
            }
            if (t.text == "#") fail(t.where, "expected a directive name after '#' (e.g. #include)");
            break;
        default:
            if (!isWordChar(c)) unexpectedCharacter(t.where);
            t.text = readWordChars();
            double ignored = 0;
            t.kind = parseNumber(t.text, ignored) == NumberStatus::NotANumber ? Lex::Word : Lex::Number;
            if (t.kind == Lex::Number && !atEnd() && current() == ',' &&
                std::isdigit(static_cast<unsigned char>(following())))
                decimalComma(t);
            break;
        }
        t.endLine = lastEndLine_ = line_;
        t.endColumn = lastEndColumn_ = column_;
        return t;
    }

    std::string text_;
    std::string file_;
    std::size_t pos_ = 0;
    int line_ = 1;
    int column_ = 1;
    int lastEndLine_ = 1;
    int lastEndColumn_ = 1;
    LexToken lookahead_;
    bool peeked_ = false;
    std::string keyword_; // whose value is being read (see ValueOf), or empty
};

Token toToken(LexToken t) {
    Token out;
    switch (t.kind) {
    case Lex::Word: out.kind = Token::Kind::Word; break;
    case Lex::Number: out.kind = Token::Kind::Number; break;
    case Lex::String: out.kind = Token::Kind::String; break;
    case Lex::Open: out.kind = Token::Kind::Open; break;
    case Lex::Close: out.kind = Token::Kind::Close; break;
    default: break; // never called for other kinds
    }
    out.text = std::move(t.text);
    out.where = std::move(t.where);
    return out;
}

std::string tokenText(const Token& t) { return t.kind == Token::Kind::String ? quote(t.text) : t.text; }

// Value tokens as written in a file: "(0 -9.81 0)", "uniform 1", "\"a b\"".
std::string tokensText(const std::vector<Token>& tokens, std::size_t begin = 0,
                       std::size_t end = std::string::npos) {
    end = std::min(end, tokens.size());
    std::string out;
    for (std::size_t i = begin; i < end; ++i) {
        const bool noSpace = i == begin || tokens[i].kind == Token::Kind::Close ||
                             tokens[i - 1].kind == Token::Kind::Open;
        if (!noSpace) out += ' ';
        out += tokenText(tokens[i]);
    }
    return out;
}

// The value tokens [begin, end) as written, or their start followed by " ...".
std::string shownTokensText(const std::vector<Token>& tokens, std::size_t begin, std::size_t end) {
    end = std::min(end, tokens.size());
    if (end - begin <= maxShownTokens) return shortText(tokensText(tokens, begin, end));
    const std::string text = shortText(tokensText(tokens, begin, begin + maxShownTokens));
    return text.ends_with(" ...") ? text : text + " ...";
}

// How deeply lists nest in a value.
std::size_t listDepth(const std::vector<Token>& tokens) {
    std::size_t depth = 0, deepest = 0;
    for (const Token& t : tokens) {
        if (t.kind == Token::Kind::Open) deepest = std::max(deepest, ++depth);
        if (t.kind == Token::Kind::Close) --depth;
    }
    return deepest;
}

} // namespace

// ---------------------------------------------------------------------------------------------
// Parser

namespace detail {

// A dictionary's name, "controlDict.pressure.kernel": the enclosing dictionary's name and the
// keyword, joined when first asked for. (The full name stored in every sub-dictionary would cost
// depth times keyword length bytes each: quadratic in the input for long keywords.)
struct ScopedName {
    ScopedName(std::shared_ptr<const ScopedName> enclosing, std::string keyword)
        : parent(std::move(enclosing)), last(std::move(keyword)) {}

    const std::string& text() const {
        if (!parent) return last;
        std::call_once(joinedOnce, [this] {
            std::vector<const std::string*> parts;
            for (const ScopedName* n = this; n; n = n->parent.get()) parts.push_back(&n->last);
            for (auto part = parts.rbegin(); part != parts.rend(); ++part)
                joined.append(part == parts.rbegin() ? "" : ".").append(**part);
        });
        return joined;
    }

    const std::shared_ptr<const ScopedName> parent; // null at the top
    const std::string last;                          // the keyword (the file's name at the top)

private:
    mutable std::once_flag joinedOnce;
    mutable std::string joined;
};

} // namespace detail

class DictionaryParser {
public:
    using Name = std::shared_ptr<const detail::ScopedName>;

    // 'scopes': the dictionaries that `$name` may look into, outermost first; the last one is
    // the dictionary being filled.
    explicit DictionaryParser(std::vector<Dictionary*> scopes) : scopes_(std::move(scopes)) {}

    void parseText(Dictionary& into, std::string text, const std::string& file) {
        bytesRead_ += text.size();
        Lexer lexer(std::move(text), file);
        const Origin origin(*this);
        parseEntries(lexer, into, nullptr);
    }

    // The entry for Dictionary::set(): 'valueText' is a value ("0.01", "(0 -9.81 0)") or a
    // dictionary body in braces ("{ type wcsph; }").
    Entry parseOverride(Dictionary& owner, const std::string& keyword, const std::string& valueText) {
        const SourceLocation where{"<override>", 0, 0};
        Lexer lexer(valueText, where.file);
        bool isDict = false;
        {
            Lexer::ValueOf value(lexer, keyword);
            isDict = lexer.peek().kind == Lex::LBrace;
        }
        if (isDict) {
            const LexToken open = lexer.next();
            auto sub = makeDictionary(childName(owner, keyword), where);
            parseSubDictionary(lexer, *sub, open, keyword);
            Lexer::ValueOf value(lexer, keyword);
            if (lexer.peek().kind == Lex::Semicolon) lexer.next();
            const LexToken& rest = lexer.peek();
            if (rest.kind != Lex::End)
                throw InputError(rest.where, "unexpected " + describe(rest) + " after the dictionary for '" +
                                                 keyword + "'", keyword);
            return Entry{keyword, where, {}, sub};
        }
        LexToken keywordToken;
        keywordToken.kind = Lex::Word;
        keywordToken.text = keyword;
        keywordToken.where = where;
        Entry e = makeEntry(keywordToken, readValue(lexer, keywordToken, true), owner);
        e.where = where;
        return e;
    }

    static Name childName(const Dictionary& parent, const std::string& keyword) {
        static const Name unnamed = std::make_shared<const detail::ScopedName>(nullptr, "");
        return std::make_shared<const detail::ScopedName>(parent.name_ ? parent.name_ : unnamed, keyword);
    }

    static std::shared_ptr<Dictionary> makeDictionary(Name name, const SourceLocation& where) {
        auto d = std::make_shared<Dictionary>();
        d->name_ = std::move(name);
        d->where_ = where;
        return d;
    }

    // For a copy made by `$dict` while parsing: the depth of the copy itself (that of the entry
    // it becomes) and the variable, to hold the copy to maxNestingLevels and maxTokens.
    struct CopyLimits {
        DictionaryParser& parser;
        std::size_t level;
        const LexToken& variable;
        const std::string& keyword;
    };

    // Deep copy named 'name' (sub-dictionaries renamed below it); lookup marks are not copied.
    static std::shared_ptr<Dictionary> clone(const Dictionary& source, Name name, const SourceLocation& where,
                                             const CopyLimits* limits = nullptr) {
        if (limits && limits->level > maxNestingLevels)
            throw InputError(limits->variable.where, "dictionaries nested deeper than " +
                                                         std::to_string(maxNestingLevels) + " levels (copying '$" +
                                                         limits->variable.text + "' here)",
                             limits->keyword);
        auto copy = makeDictionary(std::move(name), where);
        copy->entries_.reserve(source.entries_.size());
        copy->index_.reserve(source.entries_.size());
        for (const Entry& e : source.entries_) {
            if (limits)
                limits->parser.countTokens(e.isDict() ? subDictionaryTokens : 1 + e.tokens.size(), Added::BySubstitution,
                                           limits->variable.where, limits->keyword,
                                           [&] { return "copying '$" + limits->variable.text + "'"; });
            Entry c{e.keyword, e.where, e.tokens, nullptr};
            if (e.isDict()) {
                std::optional<CopyLimits> deeper;
                if (limits) deeper.emplace(CopyLimits{limits->parser, limits->level + 1, limits->variable, limits->keyword});
                c.dict = clone(*e.dict, childName(*copy, e.keyword), e.dict->where_, deeper ? &*deeper : nullptr);
            }
            copy->append(std::move(c));
        }
        return copy;
    }

    // Adds an entry read from the current origin. A keyword given twice by one origin (a file's
    // own text, one #include, one `$dict;` merge) is an error naming both places: two walls of
    // one name, a repeated endTime. An entry of another origin overrides (logged): a value
    // replaces the earlier entry in place, a dictionary given again is merged into the earlier
    // one, entry by entry (OpenFOAM's #inputMode merge) — `#include "defaults"` then changes.
    void addEntry(Dictionary& d, Entry e) {
        const auto [known, added] = origins_[&d].try_emplace(e.keyword, unknownOrigin);
        const unsigned previous = std::exchange(known->second, origin_);
        Entry* existing = d.find(std::string_view(e.keyword));
        if (!existing) {
            d.append(std::move(e));
            return;
        }
        if (previous == origin_)
            throw InputError(e.where, "duplicate entry '" + e.keyword + "' in " + d.name() + ": already given at " +
                                          locationText(existing->where) + "; remove one of them",
                             e.keyword);
        if (existing->isDict() && e.isDict()) {
            for (auto& sub : e.dict->entries_) addEntry(*existing->dict, std::move(sub));
            return;
        }
        log::info("    " + locationText(e.where) + ": '" + e.keyword + "' overrides the entry of " + d.name() +
                  " at " + locationText(existing->where));
        if (existing->isDict()) origins_.erase(existing->dict.get()); // (freed: its address may come again)
        *existing = std::move(e);
    }

    // Replaces or appends, without merging (Dictionary::set, setDict).
    static void replaceEntry(Dictionary& d, Entry e) {
        if (Entry* existing = d.find(std::string_view(e.keyword)))
            *existing = std::move(e);
        else
            d.append(std::move(e));
    }

private:
    enum class Added { ByReading, BySubstitution };

    // Entries read while one lives come from one origin (a file's text, an #include, a `$dict;`
    // merge); the previous origin is restored after.
    class Origin {
    public:
        explicit Origin(DictionaryParser& parser) : parser_(parser), previous_(parser.origin_) {
            parser.origin_ = ++parser.origins;
        }
        ~Origin() { parser_.origin_ = previous_; }
        Origin(const Origin&) = delete;
        Origin& operator=(const Origin&) = delete;

    private:
        DictionaryParser& parser_;
        unsigned previous_;
    };

    // Counts 'n' more tokens (keywords and value tokens) against maxTokens, and against
    // maxSubstitutedTokens too when `$name` adds them; 'cause' (called only for the error) says
    // what adds them, e.g. "substituting '$b'".
    template <class Cause>
    void countTokens(std::size_t n, Added how, const SourceLocation& where, const std::string& keyword, Cause cause) {
        if (how == Added::BySubstitution) {
            if (n > maxSubstitutedTokens - substitutedCount_)
                throw InputError(where, cause() + " makes the substitutions in this dictionary exceed " +
                                            std::to_string(maxSubstitutedTokens) +
                                            " tokens (keywords, values and sub-dictionaries)",
                                 keyword);
            substitutedCount_ += n;
        }
        if (n > maxTokens - tokenCount_)
            throw InputError(where, cause() + " makes the dictionary exceed " + std::to_string(maxTokens) +
                                        " tokens (keywords, values and sub-dictionaries; read, #included or "
                                        "substituted)",
                             keyword);
        tokenCount_ += n;
    }

    // Reads entries into 'dict' until the '}' matching 'open' (or end of input when 'open' is
    // null, i.e. at file level).
    void parseEntries(Lexer& lexer, Dictionary& dict, const LexToken* open) {
        for (;;) {
            LexToken t = lexer.next();
            switch (t.kind) {
            case Lex::End:
                if (open)
                    throw InputError(t.where, "missing '}' at end of file: dictionary '" + dict.name() +
                                                  "' opened at " + locationText(open->where) +
                                                  " is not closed");
                return;
            case Lex::RBrace:
                if (open) return;
                throw InputError(t.where, "unexpected '}' (no dictionary is open here)");
            case Lex::Semicolon:
                continue; // stray ';', e.g. after a dictionary's '}'
            case Lex::Directive:
                parseDirective(lexer, dict, t);
                continue;
            case Lex::Variable:
                mergeVariable(lexer, dict, t);
                continue;
            case Lex::Word:
                parseEntry(lexer, dict, t);
                continue;
            default:
                throw InputError(t.where, "expected a keyword, found " + describe(t));
            }
        }
    }

    // The body of a sub-dictionary, after its '{'. Sub-dictionaries are parsed recursively, so
    // their depth is bounded (the stack overflowed at some thousands).
    void parseSubDictionary(Lexer& lexer, Dictionary& sub, const LexToken& open, const std::string& keyword) {
        if (scopes_.size() > maxNestingLevels) // scopes_ holds the enclosing dictionaries
            throw InputError(open.where, "dictionaries nested deeper than " + std::to_string(maxNestingLevels) +
                                             " levels", keyword);
        scopes_.push_back(&sub);
        parseEntries(lexer, sub, &open);
        scopes_.pop_back();
    }

    // `keyword value...;` or `keyword { ... }`
    void parseEntry(Lexer& lexer, Dictionary& dict, const LexToken& keyword) {
        countTokens(1, Added::ByReading, keyword.where, keyword.text, [&] { return "the keyword '" + keyword.text + "'"; });
        bool isDict = false;
        {
            Lexer::ValueOf value(lexer, keyword.text);
            isDict = lexer.peek().kind == Lex::LBrace;
        }
        if (isDict) {
            countTokens(subDictionaryTokens - 1, Added::ByReading, keyword.where, keyword.text,
                        [&] { return "the dictionary '" + keyword.text + "'"; });
            const LexToken open = lexer.next();
            auto sub = makeDictionary(childName(dict, keyword.text), keyword.where);
            parseSubDictionary(lexer, *sub, open, keyword.text);
            addEntry(dict, Entry{keyword.text, keyword.where, {}, sub});
            return;
        }
        addEntry(dict, makeEntry(keyword, readValue(lexer, keyword, false), dict));
    }

    // The raw tokens of a value, up to and including the ';' (which is consumed, not returned).
    // 'untilEnd' (for set()): the value ends at the end of the text, ';' optional, and may span
    // lines. Otherwise, outside parentheses, a value does not continue onto a new line: a token
    // on a later line means the ';' is missing. (A list may start on the line after the keyword.)
    std::vector<LexToken> readValue(Lexer& lexer, const LexToken& keyword, bool untilEnd) {
        const std::string& kw = keyword.text;
        const Lexer::ValueOf value(lexer, kw);
        std::vector<LexToken> raw;
        std::vector<SourceLocation> openLists;
        int previousLine = keyword.endLine;
        for (;;) {
            const LexToken& t = lexer.peek(); // valid until lexer.next()
            const bool inList = !openLists.empty();
            auto unclosedList = [&] {
                return InputError(t.where, "expected ')' to close the list opened at " +
                                               locationText(openLists.back()) + ", found " + describe(t),
                                  kw);
            };
            auto missingSemicolon = [&](const std::string& suffix = "") {
                if (raw.empty())
                    return InputError(t.where, "expected a value for '" + kw + "', found " + describe(t) + suffix, kw);
                return InputError(t.where, "expected ';' after the value of '" + kw + "', found " + describe(t) + suffix, kw);
            };
            if (!inList) {
                if (t.kind == Lex::Semicolon || (untilEnd && t.kind == Lex::End)) {
                    if (raw.empty()) throw InputError(t.where, "missing value for '" + kw + "' before " + describe(t), kw);
                    const Lex end = t.kind;
                    lexer.next();
                    if (untilEnd && end == Lex::Semicolon && lexer.peek().kind != Lex::End)
                        throw InputError(lexer.peek().where, "unexpected " + describe(lexer.peek()) +
                                                                 " after the value of '" + kw + "'", kw);
                    return raw;
                }
                if (!untilEnd && t.kind != Lex::End && t.where.line > previousLine &&
                    !(raw.empty() && t.kind == Lex::Open))
                    throw missingSemicolon(" on a new line");
            }
            switch (t.kind) {
            case Lex::End:
            case Lex::LBrace:
            case Lex::RBrace:
            case Lex::Directive:
            case Lex::Semicolon: // only reached inside a list
                if (inList) throw unclosedList();
                throw missingSemicolon();
            case Lex::Open:
                if (openLists.size() >= maxNestingLevels)
                    throw InputError(t.where, "lists nested deeper than " + std::to_string(maxNestingLevels) + " levels", kw);
                openLists.push_back(t.where);
                break;
            case Lex::Close:
                if (!inList) throw InputError(t.where, "unexpected ')' in the value of '" + kw + "' (no list is open)", kw);
                openLists.pop_back();
                break;
            default:
                break;
            }
            countTokens(1, Added::ByReading, t.where, kw, [&] { return "the value of '" + kw + "'"; });
            previousLine = t.endLine;
            raw.push_back(lexer.next());
        }
    }

    // Builds the entry from raw tokens, substituting `$name`s. A value that is exactly one
    // `$dictName` makes the entry a copy of that dictionary.
    Entry makeEntry(const LexToken& keyword, std::vector<LexToken> raw, Dictionary& dict) {
        Entry e{keyword.text, keyword.where, {}, nullptr};
        if (raw.size() == 1 && raw.front().kind == Lex::Variable) {
            const Entry& source = resolve(raw.front());
            if (source.isDict()) {
                countTokens(subDictionaryTokens - 1, Added::BySubstitution, raw.front().where, keyword.text,
                            [&] { return "copying '$" + raw.front().text + "'"; });
                const CopyLimits limits{*this, scopes_.size(), raw.front(), keyword.text};
                e.dict = clone(*source.dict, childName(dict, keyword.text), keyword.where, &limits);
                return e;
            }
        }
        // Sized first: the token bound is checked before anything is copied, and the value is
        // allocated once.
        std::vector<const Entry*> substituted(raw.size(), nullptr);
        std::size_t size = 0;
        std::size_t openLists = 0;
        for (std::size_t i = 0; i < raw.size(); ++i) {
            const LexToken& t = raw[i];
            if (t.kind != Lex::Variable) {
                if (t.kind == Lex::Open) ++openLists;
                if (t.kind == Lex::Close) --openLists;
                ++size;
                continue;
            }
            const Entry& source = resolve(t);
            if (source.isDict())
                throw InputError(t.where, "'$" + t.text + "' is a dictionary; it can only be the whole value of an entry ('" +
                                              keyword.text + " $" + t.text + ";')", keyword.text);
            countTokens(source.tokens.size(), Added::BySubstitution, t.where, keyword.text,
                        [&] { return "substituting '$" + t.text + "'"; });
            if (openLists + listDepth(source.tokens) > maxNestingLevels)
                throw InputError(t.where, "lists nested deeper than " + std::to_string(maxNestingLevels) +
                                              " levels (substituting '$" + t.text + "' here)", keyword.text);
            substituted[i] = &source;
            size += source.tokens.size();
        }
        e.tokens.reserve(size);
        for (std::size_t i = 0; i < raw.size(); ++i) {
            if (substituted[i])
                e.tokens.insert(e.tokens.end(), substituted[i]->tokens.begin(), substituted[i]->tokens.end());
            else
                e.tokens.push_back(toToken(std::move(raw[i])));
        }
        return e;
    }

    // `$dictName;` at keyword position: the entries of that dictionary are merged into 'dict'.
    void mergeVariable(Lexer& lexer, Dictionary& dict, const LexToken& variable) {
        const Entry& source = resolve(variable);
        if (!source.isDict())
            throw InputError(variable.where, "'$" + variable.text + "' used as an entry must name a dictionary "
                                             "(to use a value, write 'keyword $" + variable.text + ";')");
        const LexToken& after = lexer.peek();
        if (after.kind != Lex::Semicolon)
            throw InputError(after.where, "expected ';' after '$" + variable.text + "', found " + describe(after));
        lexer.next();
        // the copy stands at the level of 'dict', which receives its entries; no keyword to name
        static const std::string noKeyword;
        const CopyLimits limits{*this, scopes_.size() - 1, variable, noKeyword};
        auto copy = clone(*source.dict, dict.name_, dict.where_, &limits);
        const Origin origin(*this);
        for (auto& e : copy->entries_) addEntry(dict, std::move(e));
    }

    // Looks `path` up in 'd': the keyword itself, else `a.b` as entry b of sub-dictionary a
    // (recursively). Marks what it finds as used (the file itself uses it). The prefixes before
    // each '.' are hashed incrementally: one pass over the path per dictionary searched.
    static const Entry* lookupPath(Dictionary& d, std::string_view path) {
        if (Entry* e = d.find(path)) {
            d.used_.emplace(path);
            return e;
        }
        std::size_t prefixHash = detail::KeywordHash::seed;
        std::size_t hashedLength = 0;
        for (auto dot = path.find('.'); dot != std::string_view::npos; dot = path.find('.', dot + 1)) {
            prefixHash = detail::KeywordHash::extend(prefixHash, path.substr(hashedLength, dot - hashedLength));
            hashedLength = dot;
            Entry* head = d.find(detail::HashedKeyword{path.substr(0, dot), prefixHash});
            if (!head || !head->isDict()) continue;
            if (const Entry* found = lookupPath(*head->dict, path.substr(dot + 1))) {
                d.used_.insert(head->keyword);
                return found;
            }
        }
        return nullptr;
    }

    // `$name`: the current scope, then the enclosing ones out to the top.
    const Entry& resolve(const LexToken& variable) {
        for (auto scope = scopes_.rbegin(); scope != scopes_.rend(); ++scope)
            if (const Entry* e = lookupPath(**scope, variable.text)) return *e;
        std::vector<std::string> visible;
        for (const Dictionary* scope : scopes_)
            for (const auto& e : scope->entries_) visible.push_back(e.keyword);
        std::string message = "undefined variable '$" + variable.text + "'";
        const std::string suggestion = closestMatch(variable.text, visible);
        if (!suggestion.empty()) message += " (did you mean '$" + suggestion + "'?)";
        throw InputError(variable.where, message);
    }

    void parseDirective(Lexer& lexer, Dictionary& dict, const LexToken& directive) {
        const bool optional = directive.text == "#includeIfPresent";
        if (directive.text != "#include" && !optional)
            throw InputError(directive.where, "unknown directive '" + directive.text +
                                                  "' (supported: #include, #includeIfPresent)");
        const LexToken name = lexer.next();
        if (name.kind != Lex::String)
            throw InputError(name.where, "expected a quoted file name after '" + directive.text + "', found " +
                                             describe(name));
        const fs::path relative = name.text;
        const fs::path includingDir = fs::path(lexer.file()).parent_path();
        const fs::path file =
            relative.is_absolute() || includingDir.empty() ? relative : (includingDir / relative).lexically_normal();
        FileContents contents = readWholeFile(file);
        if (contents.status == FileContents::Status::TooLarge)
            throw InputError(directive.where, "include file '" + file.string() + "' " + contents.tooLargeMessage());
        if (contents.status == FileContents::Status::CannotOpen) {
            if (optional) return;
            throw InputError(directive.where, "cannot open include file '" + file.string() + "'");
        }
        if (includeDepth_ >= maxIncludeDepth)
            throw InputError(directive.where, "#include nested more than " + std::to_string(maxIncludeDepth) +
                                                  " deep (does '" + file.string() + "' include itself?)");
        if (contents.size > maxTotalFileBytes - std::min(bytesRead_, maxTotalFileBytes))
            throw InputError(directive.where, "including '" + file.string() + "' makes the files read for this dictionary exceed " +
                                                  std::to_string(maxTotalFileBytes >> 20) + " MiB (repeated #includes count each time)");
        bytesRead_ += contents.size;
        ++includeDepth_;
        Lexer included(std::move(contents.text), file.string());
        {
            const Origin origin(*this);
            parseEntries(included, dict, nullptr);
        }
        --includeDepth_;
    }

    std::vector<Dictionary*> scopes_;
    // which origin gave each keyword of each dictionary filled (addEntry)
    std::unordered_map<const Dictionary*, std::unordered_map<std::string, unsigned>> origins_;
    static constexpr unsigned unknownOrigin = ~0u; // an entry copied in (a `kw $dict;` copy's)
    unsigned origins = 0, origin_ = 0; // origins started, the current one (0: Dictionary::set's value)
    int includeDepth_ = 0;
    std::size_t tokenCount_ = 0;       // against maxTokens
    std::size_t substitutedCount_ = 0; // against maxSubstitutedTokens
    std::uintmax_t bytesRead_ = 0;   // against maxTotalFileBytes
};

// ---------------------------------------------------------------------------------------------
// Dictionary

Dictionary::Dictionary(std::string scopedName, SourceLocation where)
    : name_(std::make_shared<const detail::ScopedName>(nullptr, std::move(scopedName))), where_(std::move(where)) {}

const std::string& Dictionary::name() const {
    static const std::string unnamed;
    return name_ ? name_->text() : unnamed;
}

template <class Key>
const Entry* Dictionary::find(const Key& keyword) const {
    const auto it = index_.find(keyword);
    return it == index_.end() ? nullptr : &entries_[it->second];
}

template <class Key>
Entry* Dictionary::find(const Key& keyword) {
    return const_cast<Entry*>(std::as_const(*this).find(keyword));
}

void Dictionary::append(Entry entry) {
    index_.emplace(entry.keyword, entries_.size());
    entries_.push_back(std::move(entry));
}

Dictionary Dictionary::fromFile(const fs::path& file) {
    const std::string path = file.string();
    FileContents contents = readWholeFile(file);
    if (contents.status == FileContents::Status::TooLarge)
        throw InputError({path, 0, 0}, "file " + contents.tooLargeMessage());
    if (contents.status != FileContents::Status::Read) throw InputError({path, 0, 0}, "cannot open file");
    Dictionary d(file.filename().string(), {path, 0, 0});
    DictionaryParser({&d}).parseText(d, std::move(contents.text), path);
    return d;
}

Dictionary Dictionary::fromString(const std::string& text, const std::string& fileName) {
    std::string name = fs::path(fileName).filename().string();
    if (name.empty()) name = fileName;
    Dictionary d(name, {fileName, 0, 0});
    DictionaryParser({&d}).parseText(d, text, fileName);
    return d;
}

bool Dictionary::found(const std::string& keyword) const { return findEntry(keyword) != nullptr; }

bool Dictionary::isDict(const std::string& keyword) const {
    const Entry* e = findEntry(keyword);
    return e && e->isDict();
}

std::vector<std::string> Dictionary::keywords() const {
    std::vector<std::string> out;
    for (const auto& e : entries_)
        if (e.keyword != headerKeyword) out.push_back(e.keyword);
    return out;
}

const Entry* Dictionary::findEntry(const std::string& keyword) const { return find(std::string_view(keyword)); }

SourceLocation Dictionary::locationOf(const std::string& keyword) const {
    const Entry* e = findEntry(keyword);
    return e ? e->where : where_;
}

const Entry& Dictionary::requireEntry(const std::string& keyword) const {
    markUsed(keyword);
    if (const Entry* e = findEntry(keyword)) return *e;
    std::string message = "keyword '" + keyword + "' is missing in " + name();
    const std::string suggestion = closestMatch(keyword, keywords());
    if (!suggestion.empty()) message += " (did you mean '" + suggestion + "'?)";
    throw InputError(where_, message, keyword);
}

namespace {
[[noreturn]] void notADictionary(const Dictionary& d, const Entry& e) {
    throw InputError(e.where, "'" + e.keyword + "' in " + d.name() + " must be a dictionary ('" + e.keyword +
                                  " { ... }'), found the value '" + shownTokensText(e.tokens, 0, e.tokens.size()) + "'",
                     e.keyword);
}
} // namespace

const Dictionary& Dictionary::subDict(const std::string& keyword) const {
    const Entry& e = requireEntry(keyword);
    if (!e.isDict()) notADictionary(*this, e);
    return *e.dict;
}

const Dictionary* Dictionary::findDict(const std::string& keyword) const {
    markUsed(keyword);
    const Entry* e = findEntry(keyword);
    if (!e) return nullptr;
    if (!e->isDict()) notADictionary(*this, *e);
    return e->dict.get();
}

void Dictionary::markUsed(const std::string& keyword) const { used_.insert(keyword); }

void Dictionary::checkAllKeywordsUsed() const {
    for (const auto& e : entries_) {
        if (e.keyword == headerKeyword || used_.count(e.keyword)) continue;
        const std::vector<std::string> valid(used_.begin(), used_.end()); // std::set: sorted
        std::string message = "unknown keyword '" + e.keyword + "' in " + name();
        const std::string suggestion = closestMatch(e.keyword, valid);
        if (!suggestion.empty()) message += " (did you mean '" + suggestion + "'?)";
        message += "; valid keywords: (" + join(valid) + ")";
        throw InputError(e.where, message, e.keyword);
    }
}

std::string Dictionary::getWord(const std::string& keyword, const std::vector<std::string>& allowed) const {
    std::string value = get<std::string>(keyword);
    if (std::find(allowed.begin(), allowed.end(), value) != allowed.end()) return value;
    std::string message = "unknown value '" + value + "' for '" + keyword + "'; valid: (" + join(allowed) + ")";
    const std::string suggestion = closestMatch(value, allowed);
    if (!suggestion.empty()) message += "; did you mean '" + suggestion + "'?";
    throw InputError(findEntry(keyword)->tokens.front().where, message, keyword);
}

std::string Dictionary::getWordOrDefault(const std::string& keyword, const std::vector<std::string>& allowed,
                                         const std::string& defaultValue) const {
    markUsed(keyword);
    if (found(keyword)) return getWord(keyword, allowed);
    logDefaultOnce(name() + "." + keyword, isWord(defaultValue) ? defaultValue : quote(defaultValue));
    return defaultValue;
}

void Dictionary::set(const std::string& keyword, const std::string& valueText) {
    if (!isWord(keyword))
        throw InputError({"<override>", 0, 0}, "invalid keyword '" + keyword +
                                                   "' (letters, digits and _ . : < > - + only)");
    Entry e = DictionaryParser({this}).parseOverride(*this, keyword, valueText);
    DictionaryParser::replaceEntry(*this, std::move(e));
}

void Dictionary::setDict(const std::string& keyword, const Dictionary& dict) {
    if (!isWord(keyword))
        throw InputError({"<override>", 0, 0}, "invalid keyword '" + keyword +
                                                   "' (letters, digits and _ . : < > - + only)");
    auto copy = DictionaryParser::clone(dict, DictionaryParser::childName(*this, keyword), dict.where());
    DictionaryParser::replaceEntry(*this, Entry{keyword, dict.where(), {}, copy});
}

void Dictionary::remove(const std::string& keyword) {
    const auto it = index_.find(std::string_view(keyword));
    if (it == index_.end()) return;
    entries_.erase(entries_.begin() + static_cast<std::ptrdiff_t>(it->second));
    index_.clear();
    for (std::size_t i = 0; i < entries_.size(); ++i) index_.emplace(entries_[i].keyword, i);
}

std::string Dictionary::toString(int indent) const {
    const std::string pad(static_cast<std::size_t>(std::max(indent, 0)), ' ');
    std::ostringstream out;
    for (const auto& e : entries_) {
        if (e.isDict()) {
            out << pad << e.keyword << "\n" << pad << "{\n" << e.dict->toString(std::max(indent, 0) + 4) << pad << "}\n";
        } else {
            const int width = std::max<int>(keywordWidth, static_cast<int>(e.keyword.size()) + 1);
            out << pad << std::left << std::setw(width) << e.keyword << tokensText(e.tokens) << ";\n";
        }
    }
    return out.str();
}

void logDefaultOnce(const std::string& scopedKeyword, const std::string& valueText) {
    static std::mutex mutex;
    static std::set<std::string> logged;
    {
        std::lock_guard lock(mutex);
        if (!logged.insert(scopedKeyword).second) return;
    }
    log::info("    default: " + scopedKeyword + " " + valueText);
}

// ---------------------------------------------------------------------------------------------
// Typed values

namespace {

// How a value token is named in "found ..." parts of type errors.
std::string describeValue(const std::vector<Token>& tokens, std::size_t i) {
    const Token& t = tokens[i];
    switch (t.kind) {
    case Token::Kind::Word: return "word '" + shownTokensText(tokens, i, i + 1) + "'";
    case Token::Kind::Number: return "number " + shownTokensText(tokens, i, i + 1);
    case Token::Kind::String: return "string " + shownTokensText(tokens, i, i + 1);
    case Token::Kind::Close: return "')'";
    case Token::Kind::Open: {
        int depth = 0;
        std::size_t end = i;
        for (; end < tokens.size() && end - i <= maxShownTokens; ++end) { // no further than is shown
            if (tokens[end].kind == Token::Kind::Open) ++depth;
            if (tokens[end].kind == Token::Kind::Close && --depth == 0) break;
        }
        return "list " + shownTokensText(tokens, i, end + 1);
    }
    }
    return "?";
}

// Reads one entry's value as a given type; every error names the entry's keyword and points at
// the offending token.
class ValueReader {
public:
    explicit ValueReader(const Entry& e) : e_(e) {}

    const std::string& keyword() const { return e_.keyword; }

    // The value's tokens; a dictionary or an empty value is an error.
    const std::vector<Token>& tokens(const std::string& expected) const {
        if (e_.isDict()) throw InputError(e_.where, "expected " + expected + " for '" + keyword() + "', found a dictionary", keyword());
        if (e_.tokens.empty()) throw InputError(e_.where, "missing value for '" + keyword() + "'", keyword());
        return e_.tokens;
    }

    [[noreturn]] void typeError(std::size_t i, const std::string& expected) const {
        throw InputError(e_.tokens[i].where, "expected " + expected + " for '" + keyword() + "', found " +
                                                 describeValue(e_.tokens, i), keyword());
    }

    [[noreturn]] void outOfRange(const Token& t, const std::string& range) const {
        throw InputError(t.where, "number " + shortText(t.text) + " for '" + keyword() + "' is out of range (" + range + ")", keyword());
    }

    // Nothing may follow token 'end' - 1.
    void requireEnd(std::size_t end, const std::string& expected) const {
        if (end < e_.tokens.size())
            throw InputError(e_.tokens[end].where, "unexpected " + describeValue(e_.tokens, end) + " after the value of '" +
                                                       keyword() + "' (expected " + expected + ")", keyword());
    }

    // A value of exactly one token of kind 'a' (or 'b').
    const Token& single(const std::string& expected, Token::Kind a, Token::Kind b) const {
        const auto& toks = tokens(expected);
        if (toks[0].kind != a && toks[0].kind != b) typeError(0, expected);
        requireEnd(1, expected);
        return toks[0];
    }
    const Token& single(const std::string& expected, Token::Kind a) const { return single(expected, a, a); }

    double number(std::size_t i, const std::string& expected) const {
        const Token& t = e_.tokens[i];
        if (t.kind != Token::Kind::Number) typeError(i, expected);
        double v = 0;
        if (parseNumber(t.text, v) != NumberStatus::Ok) outOfRange(t, "double");
        return v;
    }

    Scalar scalar(std::size_t i, const std::string& expected) const {
        const double v = number(i, expected);
        if constexpr (std::is_same_v<Scalar, float>) {
            if (std::abs(v) > std::numeric_limits<float>::max()) outOfRange(e_.tokens[i], "float");
        }
        return static_cast<Scalar>(v);
    }

    // A list starting at token i; calls item(j) for the index of each element's first token,
    // which returns the index after the element. Returns the index after the ')'.
    template <class Item>
    std::size_t list(std::size_t i, const std::string& expected, Item item) const {
        const auto& toks = e_.tokens;
        if (toks[i].kind != Token::Kind::Open) typeError(i, expected);
        std::size_t j = i + 1;
        while (j < toks.size() && toks[j].kind != Token::Kind::Close) j = item(j);
        return j + 1; // the parser guarantees balanced parentheses
    }

    // `(x y z)` at token i; returns the index after it.
    std::size_t vec3(std::size_t i, Vec3& out, const std::string& expected) const {
        const std::string component = "a number as vector component";
        int n = 0;
        const std::size_t end = list(i, expected, [&](std::size_t j) {
            const Scalar v = scalar(j, component);
            if (n < 3) out[n] = v;
            ++n;
            return j + 1;
        });
        if (n != 3)
            throw InputError(e_.tokens[i].where, "expected 3 components (x y z) for '" + keyword() + "', found " +
                                                     std::to_string(n), keyword());
        return end;
    }

private:
    const Entry& e_;
};

// Integers: 42, -7, +3; whole numbers written otherwise (1e3, 100.0) are accepted too, 1.5 is not.
template <class I>
I readInteger(const ValueReader& r) {
    const std::string expected = std::is_unsigned_v<I> ? "a non-negative integer" : "an integer";
    const Token& t = r.single(expected, Token::Kind::Number);
    std::string_view s = t.text;
    if (!s.empty() && s.front() == '+') s.remove_prefix(1);
    long long value = 0;
    const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), value);
    const bool plainInteger = end == s.data() + s.size() && ec == std::errc();
    double d = 0;
    const NumberStatus status = parseNumber(t.text, d);
    if (!plainInteger && status == NumberStatus::Ok && d != std::trunc(d)) r.typeError(0, expected);
    if (std::is_unsigned_v<I> && (plainInteger ? value < 0 : d < 0)) r.typeError(0, expected);
    bool inRange = false;
    if (plainInteger) {
        inRange = std::in_range<I>(value);
    } else {
        const double upper = std::ldexp(1.0, std::numeric_limits<I>::digits); // max + 1, exact
        const double lower = std::is_signed_v<I> ? -upper : 0.0;
        inRange = status == NumberStatus::Ok && d >= lower && d < upper;
        if (inRange) value = static_cast<long long>(d);
    }
    if (!inRange) {
        std::ostringstream range;
        range << std::numeric_limits<I>::min() << " to " << std::numeric_limits<I>::max();
        r.outOfRange(t, range.str());
    }
    return static_cast<I>(value);
}

template <class T> T readAs(const ValueReader& r);

template <> double readAs<double>(const ValueReader& r) {
    r.single("a number", Token::Kind::Number);
    return r.number(0, "a number");
}

template <> float readAs<float>(const ValueReader& r) {
    const Token& t = r.single("a number", Token::Kind::Number);
    const double v = r.number(0, "a number");
    if (std::abs(v) > std::numeric_limits<float>::max()) r.outOfRange(t, "float");
    return static_cast<float>(v);
}

template <> int readAs<int>(const ValueReader& r) { return readInteger<int>(r); }
template <> long readAs<long>(const ValueReader& r) { return readInteger<long>(r); }
template <> unsigned readAs<unsigned>(const ValueReader& r) { return readInteger<unsigned>(r); }

template <> bool readAs<bool>(const ValueReader& r) {
    const std::string expected = "a switch (true/false, on/off, yes/no)";
    const Token& t = r.single(expected, Token::Kind::Word);
    if (t.text == "true" || t.text == "on" || t.text == "yes") return true;
    if (t.text == "false" || t.text == "off" || t.text == "no") return false;
    r.typeError(0, expected);
}

template <> std::string readAs<std::string>(const ValueReader& r) {
    return r.single("a word or quoted string", Token::Kind::Word, Token::Kind::String).text;
}

template <> Vec3 readAs<Vec3>(const ValueReader& r) {
    const std::string expected = "a vector (x y z)";
    r.tokens(expected);
    Vec3 v = Vec3::Zero();
    r.requireEnd(r.vec3(0, v, expected), expected);
    return v;
}

template <> std::vector<double> readAs<std::vector<double>>(const ValueReader& r) {
    const std::string expected = "a list of numbers";
    r.tokens(expected);
    std::vector<double> out;
    const std::size_t end = r.list(0, expected, [&](std::size_t j) {
        out.push_back(r.number(j, "a number as list element"));
        return j + 1;
    });
    r.requireEnd(end, expected);
    return out;
}

template <> std::vector<std::string> readAs<std::vector<std::string>>(const ValueReader& r) {
    const std::string expected = "a list of words";
    const auto& toks = r.tokens(expected);
    std::vector<std::string> out;
    const std::size_t end = r.list(0, expected, [&](std::size_t j) {
        if (toks[j].kind != Token::Kind::Word && toks[j].kind != Token::Kind::String)
            r.typeError(j, "a word or quoted string as list element");
        out.push_back(toks[j].text);
        return j + 1;
    });
    r.requireEnd(end, expected);
    return out;
}

template <> std::vector<Vec3> readAs<std::vector<Vec3>>(const ValueReader& r) {
    const std::string expected = "a list of vectors ((x y z) ...)";
    r.tokens(expected);
    std::vector<Vec3> out;
    const std::size_t end = r.list(0, expected, [&](std::size_t j) {
        Vec3 v = Vec3::Zero();
        const std::size_t next = r.vec3(j, v, "a vector (x y z) as list element");
        out.push_back(v);
        return next;
    });
    r.requireEnd(end, expected);
    return out;
}

// Default values as they would be written in a dictionary (for the "default:" log line).
template <class T>
std::string formatValue(const T& v) {
    std::ostringstream s;
    s << v;
    return s.str();
}
template <> std::string formatValue<bool>(const bool& v) { return v ? "true" : "false"; }
template <> std::string formatValue<std::string>(const std::string& v) { return isWord(v) ? v : quote(v); }
template <> std::string formatValue<Vec3>(const Vec3& v) {
    std::ostringstream s;
    s << "(" << v.x() << " " << v.y() << " " << v.z() << ")";
    return s.str();
}
template <class T>
std::string formatList(const std::vector<T>& values) {
    std::string out = "(";
    for (std::size_t i = 0; i < values.size(); ++i) out.append(i ? " " : "").append(formatValue(values[i]));
    return out + ")";
}
template <> std::string formatValue<std::vector<double>>(const std::vector<double>& v) { return formatList(v); }
template <> std::string formatValue<std::vector<std::string>>(const std::vector<std::string>& v) { return formatList(v); }
template <> std::string formatValue<std::vector<Vec3>>(const std::vector<Vec3>& v) { return formatList(v); }

} // namespace

template <class T>
T Dictionary::get(const std::string& keyword) const {
    return readAs<T>(ValueReader(requireEntry(keyword)));
}

template <class T>
T Dictionary::getOrDefault(const std::string& keyword, const T& defaultValue) const {
    markUsed(keyword);
    if (found(keyword)) return get<T>(keyword);
    logDefaultOnce(name() + "." + keyword, formatValue(defaultValue));
    return defaultValue;
}

#define SPINDRIFT_DICTIONARY_TYPE(T)                                                      \
    template T Dictionary::get<T>(const std::string&) const;                              \
    template T Dictionary::getOrDefault<T>(const std::string&, const T&) const;

SPINDRIFT_DICTIONARY_TYPE(double)
SPINDRIFT_DICTIONARY_TYPE(float)
SPINDRIFT_DICTIONARY_TYPE(int)
SPINDRIFT_DICTIONARY_TYPE(long)
SPINDRIFT_DICTIONARY_TYPE(unsigned)
SPINDRIFT_DICTIONARY_TYPE(bool)
SPINDRIFT_DICTIONARY_TYPE(std::string)
SPINDRIFT_DICTIONARY_TYPE(Vec3)
SPINDRIFT_DICTIONARY_TYPE(std::vector<double>)
SPINDRIFT_DICTIONARY_TYPE(std::vector<std::string>)
SPINDRIFT_DICTIONARY_TYPE(std::vector<Vec3>)

#undef SPINDRIFT_DICTIONARY_TYPE

} // namespace spindrift
