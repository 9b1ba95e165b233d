#include "Expression.hpp"

#include <muParser.h>

#include <cmath>
#include <sstream>

namespace spindrift {

struct Expression::Impl {
    mu::Parser parser;
    double x = 0, y = 0, z = 0; // the variables' storage (muParser keeps their addresses)
};

Expression::Expression(const std::string& text, const SourceLocation& where, const std::string& keyword)
    : impl_(std::make_unique<Impl>()), text_(text), where_(where), keyword_(keyword) {
    try {
        impl_->parser.DefineVar("x", &impl_->x);
        impl_->parser.DefineVar("y", &impl_->y);
        impl_->parser.DefineVar("z", &impl_->z);
        impl_->parser.SetExpr(text);
        impl_->parser.Eval(); // parses it: a syntax error or an unknown variable shows here
    } catch (const mu::Parser::exception_type& e) {
        const std::string unknown = e.GetCode() == mu::ecUNASSIGNABLE_TOKEN
                                        ? "unknown variable or function '" + e.GetToken() + "': "
                                        : "";
        throw InputError(where, "expression \"" + text + "\" of '" + keyword + "': " + unknown + e.GetMsg() +
                                    " (muParser; the variables are x, y and z)",
                         keyword);
    }
}

Expression::~Expression() = default;
Expression::Expression(Expression&&) noexcept = default;
Expression& Expression::operator=(Expression&&) noexcept = default;

double Expression::operator()(const Vec3& p) const {
    impl_->x = double(p[0]);
    impl_->y = double(p[1]);
    impl_->z = double(p[2]);
    double v = 0;
    try {
        v = impl_->parser.Eval();
    } catch (const mu::Parser::exception_type& e) {
        throw InputError(where_, "expression \"" + text_ + "\" of '" + keyword_ + "': " + e.GetMsg() + " (muParser)",
                         keyword_);
    }
    if (!std::isfinite(v)) {
        std::ostringstream s;
        s << "expression \"" << text_ << "\" of '" << keyword_ << "' is " << v << " at (" << p[0] << " " << p[1] << " "
          << p[2] << "): it must be finite wherever the region has particles";
        throw InputError(where_, s.str(), keyword_);
    }
    return v;
}

} // namespace spindrift
