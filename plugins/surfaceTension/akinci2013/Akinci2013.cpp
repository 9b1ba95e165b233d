// akinci2013 — surface tension by cohesion and curvature, with adhesion to walls: Akinci, Akinci &
// Teschner (2013), "Versatile surface tension and adhesion for SPH fluids", ACM Trans. Graph.
// 32(6), 182, doi:10.1145/2508363.2508395, eqs. 1–7 (what SPlisHSPlasH's users pick).
// docs/MODELS.md §akinci2013.
//
//   a_i = γ Σ_j K_ij (−m_j C(r_ij) x̂_ij − (n_i − n_j))  −  β Σ_b M_b A(r_ib) x̂_ib
//   K_ij = 2ρ0/(ρ_i + ρ_j),   n_i = h Σ_j (m_j/ρ_j) ∇_i W_ij   (h the support radius)
//   C(r) = c_d/h^(d+6) · { 2(h − r)³r³ − h⁶/64 for 0 < r ≤ h/2;  (h − r)³r³ for h/2 < r ≤ h }
//   A(r) = 0.007/h^(d+0.25) · (−4r²/h + 6r − 2h)^(1/4) for h/2 < r ≤ h (0 elsewhere)
// c_3 = 32/π (the paper's, 3D); the paper has no 2D form: c_2 is chosen so that a flat surface's
// cohesive tension per γρ0² is the same in 2D as in 3D, the virial of a pair force F(r) across a
// plane (Kirkwood & Buff) being σ = (π/8)∫F r⁴dr in 3D and (1/3)∫F r³dr in 2D: c_2 = (3π/8) c_3
// ∫C̃ r⁴ dr/∫C̃ r³ dr (C̃ the bracket at h = 1), ≈ 7.78.
//
// The paper's γ is not σ (its two terms even have different units; as in the paper and in
// SPlisHSPlasH, SI units fix their balance). The user gives σ in N/m and γ follows from it. A
// pairwise cohesion holds the fluid together by a tension in its bulk (the pair virial P_c < 0,
// like van der Waals' a/v²), which the equation of state's pressure balances: inside a flat
// surface p = −P_c ≠ 0, and the mechanical pressure, the one whose jump is Laplace's, is p + P_c
// (Irving & Kirkwood). The model writes P_c per particle, `cohesionPressure` =
// (m/(2d V_i)) Σ_j x_ij·a_ij over its pair accelerations a_ij, V_i = Δx^d ρ0/ρ_i its lattice cell.
// At start it computes the tension per unit γ for the case's kernel, Δx, h and m (calibrate()):
// the cohesion's by Kirkwood & Buff's integral, the curvature term's from the jump it holds up in
// a drop of the case's lattice (it has no bulk part); γ = σ/σ₁, logged with the bulk pressure. Both
// terms are pair-antisymmetric (K_ij = K_ji): the fluid's momentum is kept pair by pair. The
// adhesion β = `adhesion`·γ pulls the fluid to every boundary particle of a boundary model with
// masses; its reaction is reported on the wall (ForceKind other).
//
//   surfaceTension { type akinci2013; sigma 0.0728; adhesion 0; }   // σ [N/m]; β/γ (0: none)
#include "Log.hpp"
#include "PairLoop.hpp"
#include "Plugin.hpp"
#include "SurfaceTensionModel.hpp"

#include <array>
#include <cmath>
#include <numbers>
#include <sstream>

namespace {
using namespace spindrift;

// Akinci's cohesion spline C(r) and adhesion spline A(r), for support h in d dimensions.
struct AkinciSplines {
    Scalar h, cohesionScale, adhesionScale, core; // core: h⁶/64
    AkinciSplines(Scalar support, int d)
        : h(support),
          cohesionScale(Scalar((d == 3 ? 32 / std::numbers::pi : cohesion2D) / std::pow(double(support), d + 6))),
          adhesionScale(Scalar(0.007 / std::pow(double(support), d + 0.25))), core(Scalar(std::pow(double(support), 6) / 64)) {}
    Scalar cohesion(Scalar r) const {
        if (!(r > 0) || r > h) return 0;
        const Scalar c = (h - r) * (h - r) * (h - r) * r * r * r;
        return cohesionScale * (2 * r > h ? c : 2 * c - core);
    }
    Scalar adhesion(Scalar r) const {
        if (2 * r <= h || r > h) return 0;
        return adhesionScale * std::pow(std::max(Scalar(0), -4 * r * r / h + 6 * r - 2 * h), Scalar(0.25));
    }
    // c_2: σ_coh(2D) = (1/3) ∫ C r³ dr equals σ_coh(3D) = (π/8) ∫ C r⁴ dr at h = 1
    static inline const double cohesion2D = [] {
        double r3 = 0, r4 = 0;
        const int n = 20000;
        for (int k = 0; k < n; ++k) {
            const double r = (k + 0.5) / n, c = (1 - r) * (1 - r) * (1 - r) * r * r * r;
            const double shape = 2 * r > 1 ? c : 2 * c - 1.0 / 64;
            r3 += shape * r * r * r / n;
            r4 += shape * r * r * r * r / n;
        }
        return (std::numbers::pi / 8) * (32 / std::numbers::pi) * r4 / (r3 / 3);
    }();
};

// n_i = h Σ_j V_j ∇_i W_ij over the fluid (Akinci's normal: it points into the fluid, of order 1
// at the surface's outer row, 0 inside)
struct NormalTerm {
    using Sum = Vec3;
    static constexpr bool usesGradient = true;
    struct Particle {};
    const Scalar* rho;
    Scalar m;
    Particle particle(std::size_t) const { return {}; }
    void fluid(const Particle&, const Pair& q, Sum& sum) const { sum += (m / rho[q.j]) * q.gradW; }
};

// Σ_j K_ij (−m C x̂_ij − (n_i − n_j)) + (β/γ) Σ_b −M_b A x̂_ib: the acceleration per unit γ, and
// the virial Σ_j x_ij·a_ij of its fluid pairs
struct CohesionCurvatureTerm {
    struct Sum {
        Vec3 a = Vec3::Zero();
        Scalar virial = 0;
    };
    struct Particle {
        Vec3 n;
        Scalar rho;
    };
    const Vec3* normal;
    const Scalar* rho;
    Scalar m, rho0, adhesionRatio;
    AkinciSplines spline;
    bool visitsWalls;
    Particle particle(std::size_t i) const { return {normal[i], rho[i]}; }
    void fluid(const Particle& pi, const Pair& q, Sum& sum) const {
        const Scalar K = 2 * rho0 / (pi.rho + rho[q.j]);
        const Scalar r = std::sqrt(q.r2);
        const Scalar pull = r > 0 ? m * spline.cohesion(r) / r : Scalar(0);
        const Vec3 aij = -K * (pull * q.r + (pi.n - normal[q.j]));
        sum.a += aij;
        sum.virial += q.r.dot(aij);
    }
    void wall(const Particle&, const WallPair& q, Sum& sum) const {
        const Scalar r = std::sqrt(q.r2);
        if (r > 0) sum.a -= (adhesionRatio * q.mass() * spline.adhesion(r) / r) * q.r;
    }
};

class Akinci2013 final : public SurfaceTensionModel {
public:
    explicit Akinci2013(const ModelContext& c) : SurfaceTensionModel(c), adhesion_(readAdhesion(c.dict)) {}

    void initialise(Scene& s) override {
        for (ParticleSystem* fluid : s.ofRole(SystemRole::fluid)) fluid->particles.addScalar("cohesionPressure", {false});
        const Calibration c = calibrate(s, 8 * double(s.constants.supportRadius));
        gamma_ = c.sigmaPerGamma > 0 ? Scalar(double(sigma()) / c.sigmaPerGamma) : Scalar(0);
        std::ostringstream m;
        m << "surfaceTension akinci2013: gamma " << gamma_ << " for sigma " << sigma() << " N/m (per unit gamma: a tension "
          << c.sigmaPerGamma << " N/m, on a lattice drop of radius " << c.radius << " m; the cohesion's bulk pressure "
          << c.bulkPerGamma * gamma_ << " Pa, balanced by the equation of state's: the field cohesionPressure)";
        log::info(m.str());
    }

    void addAcceleration(Scene& s, ParticleSystem& fluid, const Step&) override {
        if (gamma_ == 0) return;
        const std::size_t count = fluid.size();
        const Scalar m = fluid.particles.particleMass(), h = s.constants.supportRadius;
        const Scalar* rho = fluid.particles.density().data();
        const auto& x = fluid.particles.position();
        normal_.resize(count);
        forEachPairSum(s, fluid, x, NormalTerm{rho, m}, [&](std::size_t i, const auto&, const Vec3& sum) { normal_[i] = h * sum; });
        auto& a = fluid.particles.acceleration();
        auto& virialPressure = *fluid.particles.findScalar("cohesionPressure");
        // per volume of the particle's lattice cell Δx^d, compressed as its density says (ρ0/ρ_i):
        // the volume its m fills on the lattice (m/ρ_i is that only where Σ W Δx^d is 1)
        const Scalar cellDensity = m / std::pow(s.physics.particleSpacing, Scalar(s.physics.dimension));
        const Scalar perDimension = gamma_ * cellDensity / (Scalar(2 * s.physics.dimension) * s.physics.rho0);
        forEachPairSum(s, fluid, x, termOf(s, fluid), [&](std::size_t i, const auto&, const CohesionCurvatureTerm::Sum& sum) {
            a[i] += gamma_ * sum.a;
            virialPressure[i] = perDimension * rho[i] * sum.virial;
        });
    }

    // the adhesion's reaction on the walls: −m_i a_ib
    void addReactions(const Scene& s, const ParticleSystem& fluid, const Step&, Reactions& r) const override {
        if (gamma_ == 0 || adhesion_ == 0) return;
        const CohesionCurvatureTerm term = termOf(s, fluid);
        spindrift::addReactions(s, fluid, fluid.particles.position(), term, [&](std::size_t, const auto& pi, const WallPair& q) {
            CohesionCurvatureTerm::Sum sum;
            term.wall(pi, q, sum);
            return Vec3(gamma_ * sum.a);
        }, ForceKind::other, r);
    }

    Scalar gamma() const { return gamma_; }

private:
    CohesionCurvatureTerm termOf(const Scene& s, const ParticleSystem& fluid) const {
        return {normal_.data(), fluid.particles.density().data(), fluid.particles.particleMass(), s.physics.rho0,
                adhesion_, AkinciSplines(s.constants.supportRadius, s.physics.dimension), adhesion_ > 0};
    }

    // σ₁, the tension per unit γ: the cohesion's by Kirkwood & Buff's virial across a plane of
    // uniform fluid, σ_c = (π/8) ρ0² ∫ C r⁴ dr (3D), (1/3) ρ0² ∫ C r³ dr (2D) (ρ0 = m/V, the case's
    // particle mass over its volume Δx^d); the curvature term's from the pressure jump it holds up
    // in a drop of the case's lattice (points (k + ½)Δx within R), ⟨∫ ρ a·(−x̂) dr⟩ =
    // Σ_i m a_i·(−x̂_i)/(Ω |x_i|^(d−1)) = σ_n (d − 1)/R (R from the drop's volume N Δx^d): it has no
    // bulk part (n = 0 inside), so the drop measures it cleanly, where the cohesion's jump is its
    // bulk pressure (the lattice's −P_c, tens of times σ/R) plus σ_c (d − 1)/R. The bulk pressure
    // per unit γ, −P_c = −(ρ0/(2d)) Σ_j x_ij·a_ij over a whole lattice neighbourhood, is logged.
    struct Calibration {
        double sigmaPerGamma, bulkPerGamma, radius;
    };
    static Calibration calibrate(const Scene& s, double R) {
        const int d = s.physics.dimension;
        const double dx = s.physics.particleSpacing, h = s.constants.supportRadius;
        const double cell = std::pow(dx, d), m = s.constants.particleMass, V = cell, rho = m / V;
        const int M = int(std::ceil(R / dx)), side = 2 * M, reach = int(std::ceil(h / dx));
        const int sideZ = d == 3 ? side : 1;
        const auto pointOf = [&](int a, int b, int c) {
            return Vec3(Scalar((a - M + 0.5) * dx), Scalar((b - M + 0.5) * dx), d == 3 ? Scalar((c - M + 0.5) * dx) : Scalar(0));
        };
        std::vector<std::array<int, 3>> offsets;
        for (int k = (d == 3 ? -reach : 0); k <= (d == 3 ? reach : 0); ++k)
            for (int j = -reach; j <= reach; ++j)
                for (int l = -reach; l <= reach; ++l)
                    if ((l || j || k) && double(Vec3(Scalar(l), Scalar(j), Scalar(k)).norm()) * dx < h) offsets.push_back({l, j, k});
        std::vector<int> at(std::size_t(side) * side * sideZ, -1);
        std::vector<Vec3> x;
        std::vector<std::array<int, 3>> cellOf;
        for (int c = 0; c < sideZ; ++c)
            for (int b = 0; b < side; ++b)
                for (int a = 0; a < side; ++a)
                    if (double(pointOf(a, b, c).norm()) < R) {
                        at[(std::size_t(c) * side + b) * side + a] = int(x.size());
                        x.push_back(pointOf(a, b, c));
                        cellOf.push_back({a, b, c});
                    }
        const auto neighbours = [&](std::size_t i, auto&& visit) {
            for (const auto& [l, j, k] : offsets) {
                const int A = cellOf[i][0] + l, B = cellOf[i][1] + j, C = cellOf[i][2] + k;
                if (A < 0 || B < 0 || C < 0 || A >= side || B >= side || C >= sideZ) continue;
                const int n = at[(std::size_t(C) * side + B) * side + A];
                if (n >= 0) visit(std::size_t(n), Vec3(x[i] - x[std::size_t(n)]));
            }
        };
        std::vector<Vec3> normal(x.size(), Vec3::Zero());
        for (std::size_t i = 0; i < x.size(); ++i)
            neighbours(i, [&](std::size_t, const Vec3& r) { normal[i] += Scalar(h * m / rho) * s.kernel.gradW(r, r.norm()); });
        const double solidAngle = d == 2 ? 2 * std::numbers::pi : 4 * std::numbers::pi;
        double jump = 0;
        for (std::size_t i = 0; i < x.size(); ++i) {
            Vec3 a = Vec3::Zero();
            neighbours(i, [&](std::size_t j, const Vec3&) { a -= normal[i] - normal[j]; });
            jump += m * double(a.dot(-x[i] / x[i].norm())) / (solidAngle * std::pow(double(x[i].norm()), d - 1));
        }
        const double radius = std::pow(double(x.size()) * cell / (d == 2 ? std::numbers::pi : 4 * std::numbers::pi / 3), 1.0 / d);
        const AkinciSplines spline(Scalar(h), d);
        double moment = 0; // ∫ C r⁴ dr (3D), ∫ C r³ dr (2D)
        const int steps = 4000;
        for (int k = 0; k < steps; ++k) {
            const double r = (k + 0.5) * h / steps;
            moment += double(spline.cohesion(Scalar(r))) * std::pow(r, d + 1) * h / steps;
        }
        const double cohesion = (d == 3 ? std::numbers::pi / 8 : 1.0 / 3) * rho * rho * moment;
        double virial = 0; // Σ_j x_ij·a_ij of a bulk particle: −m C(r) r each
        for (const auto& [l, j, k] : offsets) {
            const double r = double(Vec3(Scalar(l), Scalar(j), Scalar(k)).norm()) * dx;
            virial -= m * double(spline.cohesion(Scalar(r))) * r;
        }
        return {cohesion + jump * radius / (d - 1), -rho / (2 * d) * virial, radius};
    }

    static Scalar readAdhesion(const Dictionary& d) {
        const double a = d.getOrDefault<double>("adhesion", 0.0);
        if (!(a >= 0) || !std::isfinite(a))
            throw InputError(d.locationOf("adhesion"), "adhesion (beta/gamma, the pull to the walls) must be 0 or positive",
                             "adhesion");
        return Scalar(a);
    }

    Scalar adhesion_, gamma_ = 0;
    std::vector<Vec3> normal_;
};
} // namespace

SPINDRIFT_PLUGIN(SurfaceTensionModel, Akinci2013)
