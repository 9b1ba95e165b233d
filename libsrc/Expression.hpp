// Spindrift — expressions of the position for initial fields (constant/geometry), evaluated by
// muParser (https://beltoforion.de/en/muparser/; Debian libmuparser-dev):
//
//   velocity ("-100*x" "100*y" "0");                 // each component a number or a quoted expression
//   initialPressure "5e6*(1 - x^2 - y^2)";            // [Pa]
//
// Variables x, y, z [m]; muParser's operators (+ - * / ^), functions (sin cos tan asin acos atan
// sinh cosh tanh exp log ln log10 sqrt abs sign min max sum avg rint) and constants _pi, _e.
// An expression that does not parse, uses another variable, or gives a value that is not finite
// is an InputError naming the file, line and keyword, with muParser's own message.
#pragma once

#include "Error.hpp"
#include "Types.hpp"

#include <memory>
#include <string>

namespace spindrift {

class Expression {
public:
    // Parses 'text' (and evaluates it once at the origin to find unknown variables); errors at
    // 'where', naming 'keyword'.
    Expression(const std::string& text, const SourceLocation& where, const std::string& keyword);
    ~Expression();
    Expression(Expression&&) noexcept;
    Expression& operator=(Expression&&) noexcept;

    // Its value at p (not thread safe: one Expression a thread). A value that is not finite is an
    // InputError that names p.
    double operator()(const Vec3& p) const;
    const std::string& text() const { return text_; }

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
    std::string text_;
    SourceLocation where_;
    std::string keyword_;
};

} // namespace spindrift
