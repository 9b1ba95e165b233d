// The three kernel shapes of Müller, Charypar & Gross (2003), on the support radius h, for
// d = 2 and 3, each normalised on its own (∫ W dV = 1). Header-only so the unit tests can hold
// each shape against its own W (tests/unit/KernelTest.cpp); the plugin poly6Spiky.cpp uses
//   poly6      W = σ (h² − r²)³,            σ3 = 315/(64π h⁹), σ2 = 4/(π h⁸)
//   spiky      W = σ (h − r)³,              σ3 = 15/(π h⁶),    σ2 = 10/(π h⁵)
//   viscosity  3D: W = σ (−r³/(2h³) + r²/h² + h/(2r) − 1),  σ3 = 15/(2π h³),
//                  ∇²W = 45/(π h⁶) (h − r)
//              2D: the kernel with ∇²W = 40/(π h⁵) (h − r), W(h) = W'(h) = 0:
//                  W = σ (q²/4 − q³/9 − ln(q)/6 − 5/36),  σ2 = 40/(π h²)   (q = r/h)
// (The 2D viscosity kernel solves (1/r)(r W')' = C (h − r) with W(h) = W'(h) = 0 and is
// normalised by C = 40/(π h⁵); its laplacian is the one commonly quoted for 2D.)
#pragma once

#include <cmath>
#include <numbers>

namespace spindrift::muller {

struct Poly6 {
    double h, sigma;
    Poly6(double supportRadius, int dim)
        : h(supportRadius),
          sigma(dim == 2 ? 4.0 / (std::numbers::pi * std::pow(h, 8)) : 315.0 / (64.0 * std::numbers::pi * std::pow(h, 9))) {}
    double W(double r) const {
        if (r >= h) return 0;
        const double t = h * h - r * r;
        return sigma * t * t * t;
    }
    double dWdr(double r) const { // −6 σ r (h² − r²)²
        if (r >= h) return 0;
        const double t = h * h - r * r;
        return -6 * sigma * r * t * t;
    }
};

struct Spiky {
    double h, sigma;
    Spiky(double supportRadius, int dim)
        : h(supportRadius),
          sigma(dim == 2 ? 10.0 / (std::numbers::pi * std::pow(h, 5)) : 15.0 / (std::numbers::pi * std::pow(h, 6))) {}
    double W(double r) const {
        if (r >= h) return 0;
        const double t = h - r;
        return sigma * t * t * t;
    }
    double dWdr(double r) const { // −3 σ (h − r)²: does not vanish at r = 0 (by design)
        if (r >= h) return 0;
        const double t = h - r;
        return -3 * sigma * t * t;
    }
};

struct Viscosity {
    double h, sigma;
    int dim;
    Viscosity(double supportRadius, int dimension)
        : h(supportRadius),
          sigma(dimension == 2 ? 40.0 / (std::numbers::pi * h * h) : 15.0 / (2.0 * std::numbers::pi * h * h * h)),
          dim(dimension) {}
    // Singular at r = 0 (integrably); only its laplacian is used by the solver.
    double W(double r) const {
        if (r >= h) return 0;
        const double q = r / h;
        if (dim == 2) return sigma * (q * q / 4 - q * q * q / 9 - std::log(q) / 6 - 5.0 / 36);
        return sigma * (-q * q * q / 2 + q * q + 1 / (2 * q) - 1);
    }
    double dWdr(double r) const {
        if (r >= h) return 0;
        const double q = r / h;
        if (dim == 2) return sigma / h * (q / 2 - q * q / 3 - 1 / (6 * q));
        return sigma / h * (-1.5 * q * q + 2 * q - 1 / (2 * q * q));
    }
    double laplacian(double r) const { // positive on [0, h): dissipative pairwise
        if (r >= h) return 0;
        return (dim == 2 ? 40.0 / (std::numbers::pi * std::pow(h, 5)) : 45.0 / (std::numbers::pi * std::pow(h, 6))) * (h - r);
    }
};

} // namespace spindrift::muller
