// sinc2 — the squared-sinc kernel of Perea & Cordero (seed 000, eq. 19; docs/MODELS.md §sinc2),
// written on the support radius h (q = r/h, s = πq):
//   W = A0 · sin²(s)/s² for q < 1, 0 beyond; W and dW/dr vanish at q = 1.
// The paper prints A0 = 5.471870115/(πh³) = 1.7418/h³, which does not normalise the kernel.
// We use the constants that make ∫W dV = 1 (docs/MODELS.md §sinc2):
//   3D: A0 = π/(2h³)             (∫ 4πr² W dr = A0 · 2h³/π),
//   2D: A0 = π/(Cin(2π) h²) = 1.2887774/h²   (∫ 2πr W dr = A0 · h² Cin(2π)/π,
//       Cin(x) = ∫₀ˣ (1 − cos t)/t dt, Cin(2π) = 2.4376533930572244).
// Near r = 0 the closed forms cancel, so W, W' and W'' use their Taylor series for s < 0.1.
//
//   kernel { type sinc2; }
#include "Kernel.hpp"
#include "Plugin.hpp"

#include <cmath>
#include <numbers>

namespace {
using spindrift::Scalar;

class Sinc2 final : public spindrift::Kernel {
public:
    explicit Sinc2(const spindrift::ModelContext& c) : Kernel(c.constants.supportRadius, c.physics.dimension) {
        constexpr double cin2Pi = 2.4376533930572244118; // Cin(2π)
        a0_ = dim_ == 2 ? std::numbers::pi / (cin2Pi * h_ * h_) : std::numbers::pi / (2 * h_ * h_ * h_);
        k_ = std::numbers::pi / h_; // ds/dr
    }

    Scalar W(Scalar r) const override {
        if (r >= h_) return 0;
        return a0_ * f(k_ * r);
    }
    Scalar dWdr(Scalar r) const override {
        if (r >= h_) return 0;
        return a0_ * k_ * df(k_ * r);
    }
    // ∇²W = W'' + (d − 1) W'/r = A0 k² (f''(s) + (d − 1) f'(s)/s)
    Scalar laplacian(Scalar r) const override {
        if (r >= h_) return 0;
        const double s = k_ * r;
        return a0_ * k_ * k_ * (d2f(s) + (dim_ - 1) * dfOverS(s));
    }

private:
    static constexpr double small = 0.1;
    // f(s) = sin²s/s² = 1 − s²/3 + 2s⁴/45 − s⁶/315 + 2s⁸/14175 − …
    static double f(double s) {
        if (s < small) {
            const double t = s * s;
            return 1 + t * (-1.0 / 3 + t * (2.0 / 45 + t * (-1.0 / 315 + t * 2.0 / 14175)));
        }
        const double sn = std::sin(s);
        return sn * sn / (s * s);
    }
    // f'(s) = (s sin 2s − 2 sin²s)/s³
    static double df(double s) {
        if (s < small) return s * dfOverS(s);
        const double sn = std::sin(s);
        return (s * std::sin(2 * s) - 2 * sn * sn) / (s * s * s);
    }
    // f'(s)/s = −2/3 + 8s²/45 − 6s⁴/315 + 16s⁶/14175 − …
    static double dfOverS(double s) {
        if (s < small) {
            const double t = s * s;
            return -2.0 / 3 + t * (8.0 / 45 + t * (-6.0 / 315 + t * 16.0 / 14175));
        }
        return df(s) / s;
    }
    // f''(s) = 2 cos 2s/s² − 4 sin 2s/s³ + 6 sin²s/s⁴ = −2/3 + 24s²/45 − 30s⁴/315 + …
    static double d2f(double s) {
        if (s < small) {
            const double t = s * s;
            return -2.0 / 3 + t * (24.0 / 45 + t * (-30.0 / 315 + t * 112.0 / 14175));
        }
        const double sn = std::sin(s), s2 = s * s;
        return (2 * std::cos(2 * s) - 4 * std::sin(2 * s) / s + 6 * sn * sn / s2) / s2;
    }

    double a0_ = 0, k_ = 0;
};
} // namespace

SPINDRIFT_PLUGIN(Kernel, Sinc2)
