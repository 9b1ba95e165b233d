// Kernels (plugins/kernels/*) and the KernelTable: normalisation, derivatives, compact support,
// the table against the analytic kernel, and the lattice stability criteria of Hongbin & Xin
// (2005) that Perea & Cordero use (seed 000, eqs. 20–25).
#include "KernelTable.hpp"
#include "TestSupport.hpp"
#include "../../plugins/kernels/poly6Spiky/MullerKernels.hpp"

#include <gtest/gtest.h>
#include <cmath>
#include <functional>
#include <iomanip>
#include <map>
#include <numbers>

using namespace spindrift;

namespace {

struct KernelCase {
    std::string name;
    int dim;
    bool gradientVanishesAtOrigin = true; // eq. 22 (false for the spiky gradient, by design)
};

void PrintTo(const KernelCase& c, std::ostream* os) { *os << c.name << " " << c.dim << "D"; }

std::string caseName(const testing::TestParamInfo<KernelCase>& info) {
    return info.param.name + std::to_string(info.param.dim) + "D";
}

// ∫ W dV over the support: Gauss–Legendre (5 points) on 4096 equal intervals of [0, h], whose
// nodes include q = 1/2 (where piecewise kernels change formula).
double integral(const std::function<double(double)>& W, double h, int dim) {
    static const double x[5] = {0.0, -0.5384693101056831, 0.5384693101056831, -0.9061798459386640, 0.9061798459386640};
    static const double w[5] = {0.5688888888888889, 0.4786286704993665, 0.4786286704993665, 0.2369268850561891, 0.2369268850561891};
    const int n = 4096;
    const double dr = h / n;
    double sum = 0;
    for (int i = 0; i < n; ++i)
        for (int g = 0; g < 5; ++g) {
            const double r = (i + 0.5) * dr + 0.5 * dr * x[g];
            const double shell = dim == 2 ? 2 * std::numbers::pi * r : 4 * std::numbers::pi * r * r;
            sum += w[g] * 0.5 * dr * W(r) * shell;
        }
    return sum;
}
double integral(const Kernel& k) {
    return integral([&](double r) { return double(k.W(r)); }, k.supportRadius(), k.dimension());
}

class KernelTest : public testing::TestWithParam<KernelCase> {
protected:
    std::unique_ptr<Kernel> make(double h = 0.026) {
        auto physics = test::physicsFor(GetParam().dim, h / 2.6, 2.6);
        return test::createModel<Kernel>("type " + GetParam().name + ";", physics);
    }
};

TEST_P(KernelTest, IntegratesToOne) {
    for (double h : {0.026, 1.0, 3.5}) {
        auto k = make(h);
        EXPECT_NEAR(integral(*k), 1.0, 1e-6) << "h = " << h;
    }
}

TEST_P(KernelTest, VanishesAtAndBeyondSupport) {
    auto k = make();
    const double h = k->supportRadius();
    EXPECT_NEAR(k->W(h), 0.0, 1e-12 * k->W(0));
    EXPECT_EQ(k->W(1.01 * h), 0.0);
    EXPECT_EQ(k->dWdr(1.01 * h), 0.0);
    // W and dW/dr go continuously to zero at the support radius (every kernel here claims both)
    double maxSlope = 0;
    for (double q = 0; q < 1; q += 0.001) maxSlope = std::max(maxSlope, std::abs(double(k->dWdr(q * h))));
    EXPECT_NEAR(k->W(h * (1 - 1e-7)), 0.0, 1e-6 * k->W(0));
    EXPECT_NEAR(k->dWdr(h * (1 - 1e-7)), 0.0, 1e-6 * maxSlope);
    if (GetParam().gradientVanishesAtOrigin)
        EXPECT_NEAR(k->dWdr(0.0), 0.0, 1e-9 * std::abs(k->W(0)) / h) << "gradient must vanish at r = 0";
    else // spiky: a finite repulsion at r -> 0 (its direction r_ij/r is undefined at r = 0, where gradW is 0)
        EXPECT_LT(k->dWdr(0.0), -0.1 * maxSlope) << "this kernel documents a non-zero gradient at r = 0";
    EXPECT_GT(k->W(0), 0.0);
    for (double q = 0.05; q < 1; q += 0.05) EXPECT_LE(k->dWdr(q * h), 0.0) << "W must decrease, q = " << q;
}

TEST_P(KernelTest, GradientMatchesFiniteDifference) {
    auto k = make();
    if (!k->gradientIsDerivativeOfW()) GTEST_SKIP() << "gradient shape differs from W by design";
    // float: the step (~∛eps h/2) that balances rounding of W against truncation (worst measured
    // 4.8e-5), the difference taken over the arguments as rounded to Scalar
    const double h = k->supportRadius(), e = test::tol(1e-6, 2e-3) * h;
    double worst = 0, scale = 0;
    for (double q = 0.01; q < 0.995; q += 0.0123) {
        const double r = q * h;
        const Scalar rp = r + e, rm = r - e;
        const double fd = (k->W(rp) - k->W(rm)) / (double(rp) - double(rm));
        worst = std::max(worst, std::abs(fd - k->dWdr(r)));
        scale = std::max<double>(scale, std::abs(k->dWdr(r)));
    }
    EXPECT_LT(worst / scale, test::tol(1e-6, 1e-4));
}

TEST_P(KernelTest, LaplacianMatchesFiniteDifference) {
    auto k = make();
    if (!k->gradientIsDerivativeOfW()) GTEST_SKIP() << "laplacian shape differs from W by design";
    // float: the step (~eps^(1/4) h/3) that balances rounding against truncation (worst measured
    // 2.2e-4), and the three-point formula on the arguments as rounded to Scalar
    const double h = k->supportRadius(), e = test::tol(1e-4, 7e-3) * h;
    const int d = k->dimension();
    double worst = 0, scale = 0;
    for (double q = 0.02; q < 0.99; q += 0.0173) {
        const Scalar r = q * h, rp = r + e, rm = r - e;
        const double ep = double(rp) - r, em = r - double(rm);
        const double second = 2 * ((k->W(rp) - k->W(r)) / ep - (k->W(r) - k->W(rm)) / em) / (ep + em);
        const double lap = second + (d - 1) * k->dWdr(r) / r;
        worst = std::max(worst, std::abs(lap - k->laplacian(r)));
        scale = std::max<double>(scale, std::abs(k->laplacian(r)));
    }
    EXPECT_LT(worst / scale, test::tol(1e-5, 5e-4));
}

// The table reproduces W, dW/dr and ∇²W, and W and dW/dr from r², to 1e-6 relative to the
// largest value of each (the relative error is taken against the maximum because W → 0 at
// the support); in float to 1e-5 (~100 eps: the stored coefficients are rounded to float).
TEST_P(KernelTest, TableMatchesAnalyticKernel) {
    auto k = make();
    KernelTable table(*k);
    table.enableLaplacian();
    const double h = k->supportRadius();
    double errW = 0, errD = 0, errL = 0, maxW = 0, maxD = 0, maxL = 0, errWSq = 0, errDSq = 0;
    for (int i = 0; i <= 100000; ++i) {
        const double r = h * i / 100000.0 * 0.999999;
        errW = std::max<double>(errW, std::abs(table.W(r) - k->W(r)));
        errD = std::max<double>(errD, std::abs(table.dWdr(r) - k->dWdr(r)));
        errL = std::max<double>(errL, std::abs(table.laplacian(r) - k->laplacian(r)));
        maxW = std::max<double>(maxW, std::abs(k->W(r)));
        maxD = std::max<double>(maxD, std::abs(k->dWdr(r)));
        maxL = std::max<double>(maxL, std::abs(k->laplacian(r)));
        // the squared-distance tables of the pair loops: W(r) and r · (dW/dr / r)
        errWSq = std::max<double>(errWSq, std::abs(table.WSq(r * r) - k->W(r)));
        // (at r = 0 the gradient is zero by definition, whatever dW/dr is there: the spiky kernel)
        if (r > 0) errDSq = std::max<double>(errDSq, std::abs(table.gradFactorSq(r * r) * r - k->dWdr(r)));
    }
    EXPECT_LT(errW / maxW, test::tol(1e-6, 1e-5));
    EXPECT_LT(errD / maxD, test::tol(1e-6, 1e-5));
    EXPECT_LT(errL / maxL, test::tol(1e-6, 1e-5));
    EXPECT_LT(errWSq / maxW, test::tol(1e-6, 1e-5));
    EXPECT_LT(errDSq / maxD, test::tol(1e-6, 1e-5));
    // zero at the support (in float, h·h·(1/ds) may round into the end of the last interval)
    EXPECT_LE(std::abs(table.WSq(h * h)), test::tol(0, 1e-5) * maxW);
    EXPECT_LE(std::abs(table.gradFactorSq(h * h) * h), test::tol(0, 1e-5) * maxD);
    EXPECT_EQ(table.gradFactorSq(0), 0.0);
    EXPECT_EQ(table.W(h), 0.0);
    EXPECT_EQ(table.W(2 * h), 0.0);
    EXPECT_DOUBLE_EQ(table.W0(), k->W(0));
    // gradient direction: points from j to i times dW/dr (< 0): towards j
    const Vec3 rij(0.3 * h, 0.1 * h, 0);
    const Vec3 g = table.gradW(rij);
    EXPECT_LT(g.dot(rij), 0.0);
    EXPECT_EQ(table.gradW(Vec3::Zero()), Vec3::Zero());
}

INSTANTIATE_TEST_SUITE_P(Kernels, KernelTest,
                         testing::Values(KernelCase{"cubicSpline", 2}, KernelCase{"cubicSpline", 3},
                                         KernelCase{"wendlandC2", 2}, KernelCase{"wendlandC2", 3},
                                         KernelCase{"sinc2", 2}, KernelCase{"sinc2", 3},
                                         KernelCase{"poly6Spiky", 2, false}, KernelCase{"poly6Spiky", 3, false}),
                         caseName);

// poly6Spiky uses three shapes, each normalised on its own: hold each one's integral, gradient
// and laplacian against its own W, and the plugin against the shapes it assembles.
TEST(Poly6Spiky, EachShapeIsNormalisedWithDerivativesOfItsOwnW) {
    for (int dim : {2, 3}) {
        for (double h : {0.026, 1.0}) {
            const muller::Poly6 poly6(h, dim);
            const muller::Spiky spiky(h, dim);
            const muller::Viscosity visc(h, dim);
            EXPECT_NEAR(integral([&](double r) { return poly6.W(r); }, h, dim), 1.0, 1e-6) << "poly6 " << dim << "D";
            EXPECT_NEAR(integral([&](double r) { return spiky.W(r); }, h, dim), 1.0, 1e-6) << "spiky " << dim << "D";
            EXPECT_NEAR(integral([&](double r) { return visc.W(r); }, h, dim), 1.0, 1e-6) << "viscosity " << dim << "D";
            // W(h) = 0 and W'(h) = 0 for the viscosity kernel (Müller's construction)
            EXPECT_NEAR(visc.W(h * (1 - 1e-9)), 0.0, 1e-9 * visc.W(0.5 * h));
            EXPECT_NEAR(visc.dWdr(h * (1 - 1e-9)), 0.0, 1e-9 * std::abs(visc.dWdr(0.5 * h)));
            const double e = 1e-6 * h;
            double worst[4] = {0, 0, 0, 0}, scale[4] = {0, 0, 0, 0};
            for (double q = 0.02; q < 0.99; q += 0.0173) {
                const double r = q * h;
                auto track = [&](int k, double approx, double exact) {
                    worst[k] = std::max(worst[k], std::abs(approx - exact));
                    scale[k] = std::max(scale[k], std::abs(exact));
                };
                track(0, (poly6.W(r + e) - poly6.W(r - e)) / (2 * e), poly6.dWdr(r));
                track(1, (spiky.W(r + e) - spiky.W(r - e)) / (2 * e), spiky.dWdr(r));
                track(2, (visc.W(r + e) - visc.W(r - e)) / (2 * e), visc.dWdr(r));
                // ∇²W = r^(1−d) d/dr (r^(d−1) W'), differenced on r^(d−1) W' (smooth, unlike W at r → 0)
                auto flux = [&](double x) { return std::pow(x, dim - 1) * visc.dWdr(x); };
                track(3, (flux(r + e) - flux(r - e)) / (2 * e) / std::pow(r, dim - 1), visc.laplacian(r));
                EXPECT_GT(visc.laplacian(r), 0.0);
            }
            EXPECT_LT(worst[0] / scale[0], 1e-6) << "poly6 gradient " << dim << "D";
            EXPECT_LT(worst[1] / scale[1], 1e-6) << "spiky gradient " << dim << "D";
            EXPECT_LT(worst[2] / scale[2], 1e-6) << "viscosity-kernel gradient " << dim << "D";
            EXPECT_LT(worst[3] / scale[3], 1e-5) << "viscosity-kernel laplacian " << dim << "D";
        }
        // the plugin: W from poly6, dW/dr from spiky, laplacian from the viscosity kernel
        auto physics = test::physicsFor(dim, 0.01, 2.6);
        auto k = test::createModel<Kernel>("type poly6Spiky;", physics);
        EXPECT_FALSE(k->gradientIsDerivativeOfW());
        const double h = k->supportRadius();
        const muller::Poly6 poly6(h, dim);
        const muller::Spiky spiky(h, dim);
        const muller::Viscosity visc(h, dim);
        for (double q = 0; q < 1.05; q += 0.05) {
            const Scalar r = q * h; // the plugin returns the double shapes rounded to Scalar
            EXPECT_SCALAR_EQ(k->W(r), poly6.W(r));
            EXPECT_SCALAR_EQ(k->dWdr(r), spiky.dWdr(r));
            EXPECT_SCALAR_EQ(k->laplacian(r), visc.laplacian(r));
        }
    }
}

// Hongbin & Xin (2005) criteria, as Perea & Cordero use them (seed 000, eqs. 20–25): on a
// regular lattice of spacing d with support α·d, an evaluation point at any offset R from a
// lattice point should see M = Σ_j W(|R − x_j|) d^dim = 1 and N = Σ_j ∇W(R − x_j) = 0 (made
// dimensionless as |N| d^dim h). The worst deviations over offsets R/d in the unit cell are
// printed per kernel and support ratio and held against a bound per kernel (a bit above what
// each kernel reaches, so a change that makes a kernel worse on the lattice fails).
struct LatticeDeviation {
    double sum = 0;      // max |M − 1|
    double gradient = 0; // max |N| d^dim h
};

LatticeDeviation latticeDeviation(const Kernel& k, double spacing) {
    const int dim = k.dimension();
    const double h = k.supportRadius(), d = spacing, volume = std::pow(d, dim);
    const int reach = int(std::ceil(h / d)) + 1, samples = 8;
    LatticeDeviation worst;
    for (int oz = 0; oz < (dim == 3 ? samples : 1); ++oz)
        for (int oy = 0; oy < samples; ++oy)
            for (int ox = 0; ox < samples; ++ox) {
                const Vec3 R = d * Vec3(double(ox) / samples, double(oy) / samples, double(oz) / samples);
                double M = 0;
                Vec3 N = Vec3::Zero();
                for (int k3 = (dim == 3 ? -reach : 0); k3 <= (dim == 3 ? reach : 0); ++k3)
                    for (int k2 = -reach; k2 <= reach; ++k2)
                        for (int k1 = -reach; k1 <= reach; ++k1) {
                            const Vec3 rij = R - d * Vec3(k1, k2, k3);
                            const double r = rij.norm();
                            M += k.W(r) * volume;
                            if (r > 0) N += rij * (k.dWdr(r) / r) * volume * h;
                        }
                worst.sum = std::max(worst.sum, std::abs(M - 1));
                worst.gradient = std::max<double>(worst.gradient, N.norm());
            }
    return worst;
}

TEST(KernelLatticeCriteria, HongbinXinSumsOnARegularLattice) {
    // bounds per kernel on (max |M − 1|, max |N|) over the support ratios 2, 2.6 and 3
    // (measured worst: cubicSpline 4.3e-3 / 4.7e-2, wendlandC2 3.8e-2 / 0.26, sinc2 1.2e-2 / 9.2e-2,
    // poly6Spiky 1.6e-2 / 1.8: the spiky gradient does not vanish at r = 0, so an offset next to a
    // lattice point sees a one-sided push — the failure of criterion eq. 22 shows up in N)
    const std::map<std::string, std::pair<double, double>> bounds = {
        {"cubicSpline", {6e-3, 7e-2}}, {"wendlandC2", {5e-2, 0.35}}, {"sinc2", {1.6e-2, 0.13}}, {"poly6Spiky", {2.5e-2, 2.5}}};
    std::cout << "Hongbin-Xin lattice criteria, worst over offsets R/d in the unit cell:\n"
              << "  kernel        dim  h/d   max|M-1|    max|N| d^dim h\n";
    for (const auto& [name, bound] : bounds)
        for (int dim : {2, 3}) {
            LatticeDeviation worstOverRatios;
            for (double ratio : {2.0, 2.6, 3.0}) {
                auto physics = test::physicsFor(dim, 0.01, ratio);
                auto k = test::createModel<Kernel>("type " + name + ";", physics);
                const LatticeDeviation dev = latticeDeviation(*k, physics.particleSpacing);
                std::cout << "  " << std::left << std::setw(13) << name << " " << dim << "D   " << std::setw(4) << ratio
                          << "  " << std::scientific << std::setprecision(3) << dev.sum << "   " << dev.gradient
                          << std::defaultfloat << "\n";
                worstOverRatios.sum = std::max(worstOverRatios.sum, dev.sum);
                worstOverRatios.gradient = std::max(worstOverRatios.gradient, dev.gradient);
            }
            EXPECT_LT(worstOverRatios.sum, bound.first) << name << " " << dim << "D";
            EXPECT_LT(worstOverRatios.gradient, bound.second) << name << " " << dim << "D";
        }
}

} // namespace
