// mueller2003 — surface tension from the colour field, Müller, Charypar & Gross (2003), "Particle-
// based fluid simulation for interactive applications", Proc. SCA 2003, 154–159,
// doi:10.2312/SCA03/154-159, eqs. 15–19 (the continuum surface force of Brackbill, Kothe & Zemach
// 1992, doi:10.1016/0021-9991(92)90240-Y); seed 000 §8 (Perea & Cordero). docs/MODELS.md
// §mueller2003, with what differs from the paper and why.
//
// The colour c is 1 on fluid and 0 outside; with fluid particles only (a free surface) its
// gradient ∇c_i = Σ_j V_j ∇_i W_ij points into the fluid where the fluid ends. The force per volume
// is the CSF f = σ κ δ_s n̂_in, in the paper's notation −σ ∇²c n/|n|:
//   a_i = σ κ_i δ_i ∇c_i/(|∇c_i| ρ_i)
// with two changes from the paper that make σ the physical coefficient (the Laplace jump σ/R in
// 2D, 2σ/R in 3D) wherever the particles lie:
//  - δ_i, the surface's delta function: w_i = max(0, |∇c_i| − g_0) ramped to 0 where M_i's
//    smallest eigenvalue λ_i says bulk (KernelCorrection.hpp: λ 0.49 on a flat surface's outer
//    row, 0.90 on the next, 0.97 inside), g_0 a tenth of |∇c| on a flat lattice surface's outer
//    row, divided by its integral across the surface at i, C_i = Σ_j V_j w_j K(s_ij) (K the
//    case's kernel of the distance s_ij in i's tangent plane, normalised in d − 1 dimensions):
//    ∫ δ dn = 1 however the surface particles are spaced (the paper's −∇²c integrates to a
//    value of the layout, not to the jump of c);
//  - κ_i is not −∇²c/|∇c| (which a one-sided colour field gets wrong by a factor of order one)
//    but the surface divergence of the outward normal, κ = ∇_s · n: the renormalised normals n_j
//    (MomentAndColour) of the surface neighbours fitted by least squares in i's tangent plane
//    (weights V_j W_ij δ_j), averaged over the same neighbours (Shepard), clamped to |κ| ≤
//    (d − 1)/h, and carried from the particles' row to the surface Δx/2 beyond it (d − 1 equal
//    curvatures: κ ← κ/(1 + κ Δx/(2(d − 1)))).
// One-sided, the force is not antisymmetric: its sum over the fluid (round-off for a droplet at
// rest, not once the particles move) is taken off the surface particles in proportion to δ_i,
// so momentum is kept. Walls count in ∇c and M (a fluid against a wall has no surface there);
// walls are not pulled (no adhesion).
//
//   surfaceTension { type mueller2003; sigma 0.0728; }   // σ [N/m]
#include "KernelCorrection.hpp" // MomentAndColourTerm, smallestEigenvalue
#include "PairLoop.hpp"
#include "Plugin.hpp"
#include "SurfaceTensionModel.hpp"

#include <Eigen/LU>

#include <algorithm>
#include <cmath>
#include <numbers>

namespace {
using namespace spindrift;

// An orthonormal basis of the plane normal to n (its first d − 1 columns; 2D: the one tangent in
// the xy plane).
Mat3 tangentBasis(const Vec3& n, int d) {
    Mat3 T = Mat3::Zero();
    if (d == 2) {
        T.col(0) = Vec3(-n[1], n[0], 0);
        return T;
    }
    const Vec3 a = std::abs(n[0]) < Scalar(0.9) ? Vec3::UnitX() : Vec3::UnitY();
    T.col(0) = n.cross(a).normalized();
    T.col(1) = n.cross(T.col(0));
    return T;
}

// The surface divergence of the normal at i: the least-squares fit of n_j − n_i = G s_j over the
// surface neighbours, s_j the tangential coordinates of x_j − x_i; κ_i = trace G.
struct CurvatureTerm {
    struct Sum {
        Mat3 ss = Mat3::Zero(); // Σ w s sᵀ
        Mat3 ns = Mat3::Zero(); // Σ w (Tᵀ Δn) sᵀ
    };
    static constexpr bool usesKernel = true;
    struct Particle {
        Vec3 n;
        Mat3 T;
        Scalar delta;
    };
    const Vec3* normal;
    const Scalar* delta;
    const Scalar* rho;
    Scalar m;
    int d;
    Particle particle(std::size_t i) const { return {normal[i], tangentBasis(normal[i], d), delta[i]}; }
    void fluid(const Particle& pi, const Pair& q, Sum& sum) const {
        if (pi.delta <= 0 || delta[q.j] <= 0) return;
        const Scalar w = (m / rho[q.j]) * q.W * delta[q.j];
        const Vec3 s = -(pi.T.transpose() * q.r); // x_j − x_i in the tangent plane
        const Vec3 dn = pi.T.transpose() * (normal[q.j] - pi.n);
        sum.ss.noalias() += w * s * s.transpose();
        sum.ns.noalias() += w * dn * s.transpose();
    }
};

// The Shepard average of κ over the surface neighbours (weights V_j W_ij δ_j, i's own included).
struct SmoothingTerm {
    struct Sum {
        Scalar weighted = 0, weight = 0;
    };
    static constexpr bool usesKernel = true;
    using Particle = Scalar; // δ_i
    const Scalar* kappa;
    const Scalar* delta;
    const Scalar* rho;
    Scalar m;
    Particle particle(std::size_t i) const { return delta[i]; }
    void fluid(Scalar deltai, const Pair& q, Sum& sum) const {
        if (deltai <= 0 || delta[q.j] <= 0) return;
        const Scalar w = (m / rho[q.j]) * q.W * delta[q.j];
        sum.weighted += w * kappa[q.j];
        sum.weight += w;
    }
};

// C_i = Σ_j V_j w_j K(s_ij) (i's own included): the surface weight w's integral across the surface
// at i, K the kernel over the tangent plane (the case's kernel of the tangential distance s_ij,
// normalised in d − 1 dimensions)
struct ColumnTerm {
    using Sum = Scalar;
    struct Particle {
        Vec3 n;
        Scalar w;
    };
    const Vec3* normal;
    const Scalar* weight;
    const Scalar* rho;
    Scalar m;
    const KernelTable* kernel;
    Particle particle(std::size_t i) const { return {normal[i], weight[i]}; }
    void fluid(const Particle& pi, const Pair& q, Sum& sum) const {
        if (pi.w <= 0 || weight[q.j] <= 0) return;
        const Scalar along = pi.n.dot(q.r);
        sum += (m / rho[q.j]) * weight[q.j] * kernel->W(std::sqrt(std::max(Scalar(0), q.r2 - along * along)));
    }
};

class Mueller2003 final : public SurfaceTensionModel {
public:
    explicit Mueller2003(const ModelContext& c) : SurfaceTensionModel(c) {}

    void initialise(Scene& s) override {
        for (ParticleSystem* fluid : s.ofRole(SystemRole::fluid)) fluid->particles.addScalar("curvature", {false});
        calibrate(s);
    }

    void addAcceleration(Scene& s, ParticleSystem& fluid, const Step&) override {
        const std::size_t count = fluid.size();
        const int d = s.physics.dimension;
        const Scalar m = fluid.particles.particleMass(), h = s.constants.supportRadius;
        const Scalar* rho = fluid.particles.density().data();
        const auto& x = fluid.particles.position();
        auto& kappa = *fluid.particles.findScalar("curvature");
        direction_.resize(count);
        normal_.resize(count);
        weight_.resize(count);
        delta_.resize(count);
        rawKappa_.resize(count);
        // w_i, the normals, the force's direction
        forEachPairSum(s, fluid, x, MomentAndColourTerm{rho, m}, [&](std::size_t i, Scalar, const MomentAndColour& sum) {
            const Scalar g = sum.colour.norm();
            direction_[i] = g > 0 ? Vec3(sum.colour / g) : Vec3::Zero();
            normal_[i] = sum.outwardNormal(d);
            weight_[i] = normal_[i].squaredNorm() > 0 ? surfaceWeight(g, smallestEigenvalue(sum.moment, d)) : 0;
        });
        // δ_i = w_i/C_i
        const Scalar W0 = s.kernel.W(0);
        forEachPairSum(s, fluid, x, ColumnTerm{normal_.data(), weight_.data(), rho, m, &s.kernel},
                       [&](std::size_t i, const ColumnTerm::Particle& pi, Scalar sum) {
                           const Scalar column = (sum + (m / rho[i]) * pi.w * W0) * tangentialNorm_;
                           delta_[i] = column > 0 ? pi.w / column : 0;
                       });
        const Scalar kappaMax = Scalar(d - 1) / h;
        forEachPairSum(s, fluid, x, CurvatureTerm{normal_.data(), delta_.data(), rho, m, d},
                       [&](std::size_t i, const CurvatureTerm::Particle&, const CurvatureTerm::Sum& sum) {
                           rawKappa_[i] = std::clamp(fitTrace(sum, d), -kappaMax, kappaMax);
                       });
        const Scalar depth = Scalar(0.5) * s.physics.particleSpacing / Scalar(d - 1);
        forEachPairSum(s, fluid, x, SmoothingTerm{rawKappa_.data(), delta_.data(), rho, m},
                       [&](std::size_t i, Scalar deltai, const SmoothingTerm::Sum& sum) {
                           const Scalar self = (m / rho[i]) * W0 * deltai;
                           const Scalar weight = sum.weight + self;
                           const Scalar k = weight > 0 ? (sum.weighted + self * rawKappa_[i]) / weight : 0;
                           kappa[i] = k / (1 + k * depth);
                       });
        auto& a = fluid.particles.acceleration();
        const Scalar sigma = this->sigma();
        tension_.resize(count);
        forEachIndex(count, [&](std::size_t i) { tension_[i] = (sigma * kappa[i] * delta_[i] / rho[i]) * direction_[i]; });
        // the net force, taken off in proportion to δ (momentum kept)
        const Vec3 net = deterministicSum<Vec3>(count, [&](std::size_t i) { return tension_[i]; });
        const double deltaSum = deterministicSum(count, [&](std::size_t i) { return double(delta_[i]); });
        const Vec3 perDelta = deltaSum > 0 ? Vec3(net / Scalar(deltaSum)) : Vec3::Zero();
        forEachIndex(count, [&](std::size_t i) { a[i] += tension_[i] - delta_[i] * perDelta; });
    }

    // no boundary term: no force on a wall or body
    void addReactions(const Scene&, const ParticleSystem&, const Step&, Reactions&) const override {}

private:
    static Scalar fitTrace(const CurvatureTerm::Sum& sum, int d) {
        if (d == 2) return sum.ss(0, 0) > 0 ? sum.ns(0, 0) / sum.ss(0, 0) : Scalar(0);
        const Eigen::Matrix<Scalar, 2, 2> A = sum.ss.topLeftCorner<2, 2>(), B = sum.ns.topLeftCorner<2, 2>();
        if (!(std::abs(A.determinant()) > Scalar(1e-6) * A.squaredNorm())) return 0;
        return (B * A.inverse()).trace();
    }

    // g_0 from |∇c| on the outer row of a flat free surface of the lattice, and K's normalisation
    // 1/∫ W(|s|) ds over a line (2D) or a plane (3D), for the case's kernel.
    void calibrate(const Scene& s) {
        const int d = s.physics.dimension;
        const Scalar dx = s.physics.particleSpacing, h = s.constants.supportRadius;
        const int reach = int(std::ceil(h / dx)) + 1;
        const Scalar V = std::pow(dx, Scalar(d));
        const Vec3 xi(0, Scalar(-0.5) * dx, 0);
        Vec3 colour = Vec3::Zero();
        for (int k = 0; k <= 2 * reach; ++k)
            for (int a = -reach; a <= reach; ++a)
                for (int b = (d == 3 ? -reach : 0); b <= (d == 3 ? reach : 0); ++b) {
                    const Vec3 r = xi - Vec3(Scalar(a) * dx, -(Scalar(k) + Scalar(0.5)) * dx, Scalar(b) * dx);
                    const Scalar len = r.norm();
                    if (len > 0 && len < h) colour += V * s.kernel.gradW(r, len);
                }
        threshold_ = Scalar(0.1) * colour.norm();
        double integral = 0;
        const int steps = 4000;
        for (int k = 0; k < steps; ++k) {
            const double r = (k + 0.5) * double(h) / steps;
            integral += (d == 2 ? 2.0 : 2 * std::numbers::pi * r) * double(s.kernel.W(Scalar(r))) * double(h) / steps;
        }
        tangentialNorm_ = Scalar(1 / integral);
    }

    // |∇c| above the bulk's noise, where M's smallest eigenvalue says surface: 1 at λ ≤ 0.65 (a
    // flat surface's outer row has 0.49, the next 0.90), 0 from λ = 0.85 (the bulk, ≈ 0.97 at any
    // disorder), linear between
    Scalar surfaceWeight(Scalar g, Scalar lambda) const {
        return std::max(Scalar(0), g - threshold_) * std::clamp((Scalar(0.85) - lambda) / Scalar(0.2), Scalar(0), Scalar(1));
    }

    Scalar threshold_ = 0, tangentialNorm_ = 0;
    std::vector<Vec3> direction_, normal_, tension_;
    std::vector<Scalar> weight_, delta_, rawKappa_;
};
} // namespace

SPINDRIFT_PLUGIN(SurfaceTensionModel, Mueller2003)
