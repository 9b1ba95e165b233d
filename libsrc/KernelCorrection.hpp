// The kernel gradient correction (renormalisation) of Bonet & Lok (1999), Comput. Methods Appl.
// Mech. Engrg. 180, 97–115, doi:10.1016/S0045-7825(99)00051-1; docs/MODELS.md §gradientCorrection.
//   M_i = −Σ_j V_j r_ij ⊗ ∇_i W_ij − Σ_b V_b r_ib ⊗ ∇_i W_ib,   L_i = M_i⁻ᵀ,
// so that Σ_j V_j (f_j − f_i) L_i ∇_i W_ij is the exact gradient of a linear f; walls count (V_b =
// M_b/ρ_b), so a particle beside a wall has a full matrix. Near a free surface M_i loses rank
// (its smallest eigenvalue λ_i, 1 inside, ≈ 0.5 on a flat surface): there L_i is blended with the
// identity, L_i = w M_i⁻ᵀ + (1 − w) I with w = clamp((λ_i − 0.6)/0.2, 0, 1), so a surface particle
// has the plain gradient.
//
// The corrected symmetric pressure acceleration (q = p/ρ²; each particle's correction on its own
// side of the pair, as SPHinXsys' weighted kernel gradient correction pairs p_i B_i + p_j B_j):
//   a_i = −Σ_j m (q_i L_i + q_j L_j) ∇_i W_ij − Σ_b M_b (q_i + q_b) L_i ∇_i W_ib
// The pair terms stay equal and opposite (linear momentum is kept, and a wall's reaction is
// what it gives the fluid); they are no longer along r_ij (angular momentum is not kept exactly).
#pragma once

#include "PairLoop.hpp"

#include <Eigen/Eigenvalues>
#include <Eigen/LU>

#include <algorithm>
#include <cmath>

namespace spindrift {

using Mat3 = Eigen::Matrix<Scalar, 3, 3>;

// M_i = −Σ V r_ij ⊗ ∇W_ij over the fluid and the boundaries.
struct KernelMomentTerm {
    using Sum = Mat3;
    static constexpr bool usesGradient = true;
    using Particle = Scalar; // ρ_i
    const Scalar* rho;
    Scalar m;
    Particle particle(std::size_t i) const { return rho[i]; }
    void fluid(Scalar, const Pair& p, Sum& sum) const { sum.noalias() -= (m / rho[p.j]) * p.r * p.gradW.transpose(); }
    void wall(Scalar rhoi, const WallPair& p, Sum& sum) const {
        const Scalar rhob = p.src.mirrored ? rhoi : p.src.rho[p.j];
        sum.noalias() -= (p.mass() / rhob) * p.r * p.gradW.transpose();
    }
};

// The smallest eigenvalue of M's symmetric part in the problem's d dimensions (closed form in 2D):
// 1 for a full neighbourhood, ≈ 0.5 on a flat free surface (Marrone et al. 2010's λ).
inline Scalar smallestEigenvalue(const Mat3& M, int d) {
    if (d == 2) {
        const Scalar a = M(0, 0), c = M(1, 1), b = Scalar(0.5) * (M(0, 1) + M(1, 0));
        return Scalar(0.5) * (a + c) - std::sqrt(Scalar(0.25) * (a - c) * (a - c) + b * b);
    }
    Eigen::SelfAdjointEigenSolver<Mat3> eigen;
    eigen.computeDirect(Scalar(0.5) * (M + M.transpose()), Eigen::EigenvaluesOnly);
    return eigen.eigenvalues()[0];
}

// M⁻ᵀ g in the problem's d dimensions (the renormalised gradient of Bonet & Lok, above), where M
// can be inverted (|det M| > 10⁻³ |M|^d); g as it is where it cannot (too few neighbours: a
// particle alone, a thin jet).
inline Vec3 renormalised(const Mat3& M, const Vec3& g, int d) {
    Vec3 out = g;
    if (d == 2) {
        const Eigen::Matrix<Scalar, 2, 2> M2 = M.topLeftCorner<2, 2>();
        if (std::abs(M2.determinant()) > Scalar(1e-3) * M2.squaredNorm())
            out.head<2>() = M2.inverse().transpose() * g.head<2>();
    } else if (std::abs(M.determinant()) > Scalar(1e-3) * std::pow(M.squaredNorm(), Scalar(1.5))) {
        out = M.inverse().transpose() * g;
    }
    return out;
}

// The colour function's gradient ∇c_i = Σ_j V_j ∇_i W_ij and the moment matrix M_i in one sum
// (a term adds each neighbour's V_j = m/ρ_j, or M_b/ρ_b of a boundary). The surface's outward
// normal is the renormalised −∇c_i (Marrone et al. 2010, J. Comput. Phys. 229(10), 3652–3663,
// doi:10.1016/j.jcp.2010.01.019): n_i = −M_i⁻¹ ∇c_i / |…| (M is symmetric for a radial kernel);
// M's smallest eigenvalue (smallestEigenvalue) tells the surface from the bulk.
struct MomentAndColour {
    Mat3 moment = Mat3::Zero();
    Vec3 colour = Vec3::Zero(); // ∇c_i
    void add(Scalar V, const Pair& q) {
        moment.noalias() -= V * q.r * q.gradW.transpose();
        colour += V * q.gradW;
    }
    Vec3 outwardNormal(int d) const {
        const Vec3 n = -renormalised(moment, colour, d);
        const Scalar norm = n.norm();
        return norm > 0 ? Vec3(n / norm) : Vec3::Zero();
    }
};

// M_i and ∇c_i (MomentAndColour) over the fluid and the boundaries, V = m/ρ_j (a boundary
// mirroring the fluid's density: ρ_i).
struct MomentAndColourTerm {
    using Sum = MomentAndColour;
    static constexpr bool usesGradient = true;
    using Particle = Scalar; // ρ_i
    const Scalar* rho;
    Scalar m;
    Particle particle(std::size_t i) const { return rho[i]; }
    void fluid(Scalar, const Pair& q, Sum& sum) const { sum.add(m / rho[q.j], q); }
    void wall(Scalar rhoi, const WallPair& q, Sum& sum) const {
        sum.add(q.mass() / (q.src.mirrored ? rhoi : q.src.rho[q.j]), q);
    }
};

// L_i of every particle of the fluid at positions x (in 2D the z row and column are zero).
inline void kernelCorrectionMatrices(const Scene& s, const ParticleSystem& fluid, const std::vector<Vec3>& x,
                                     std::vector<Mat3>& L) {
    const int d = s.physics.dimension;
    L.resize(x.size());
    const KernelMomentTerm term{fluid.particles.density().data(), fluid.particles.particleMass()};
    forEachPairSum(s, fluid, x, term, [&](std::size_t i, Scalar, const Mat3& M) {
        const Scalar w = std::clamp((smallestEigenvalue(M, d) - Scalar(0.6)) / Scalar(0.2), Scalar(0), Scalar(1));
        Mat3 Li = Mat3::Identity();
        if (d == 2) Li(2, 2) = 0;
        if (w > 0) {
            Mat3 inverse = Mat3::Zero();
            if (d == 2) inverse.topLeftCorner<2, 2>() = M.topLeftCorner<2, 2>().inverse().transpose();
            else inverse = M.inverse().transpose();
            Li = w * inverse + (1 - w) * Li;
        }
        L[i] = Li;
    });
}

// The corrected symmetric pressure term of q = p/ρ² (above).
struct CorrectedSymmetricPressureTerm {
    struct Sum {
        Vec3 fluid = Vec3::Zero(), wall = Vec3::Zero(); // Σ_j (q_i L_i + q_j L_j) ∇W_ij, Σ_b M_b (q_i + q_b) L_i ∇W_ib
    };
    static constexpr bool usesGradient = true;
    struct Particle {
        Scalar q;
        Mat3 qL; // q_i L_i
        Mat3 L;
    };
    const Scalar* q;
    const Mat3* L;
    Particle particle(std::size_t i) const { return {q[i], q[i] * L[i], L[i]}; }
    void fluid(const Particle& pi, const Pair& p, Sum& sum) const { sum.fluid.noalias() += (pi.qL + q[p.j] * L[p.j]) * p.gradW; }
    void wall(const Particle& pi, const WallPair& p, Sum& sum) const {
        const Scalar qb = p.src.mirrored ? pi.q : p.src.p[p.j] / (p.src.rho[p.j] * p.src.rho[p.j]);
        sum.wall.noalias() += (p.mass() * (pi.q + qb)) * (pi.L * p.gradW);
    }
};

// The corrected symmetric pressure acceleration of q = p/ρ² (q and L of every particle) at
// positions x, handed to out(i, a_i).
template <class Out>
inline void correctedSymmetricPressureAcceleration(const Scene& s, const ParticleSystem& fluid, const std::vector<Vec3>& x,
                                                   const Scalar* q, const Mat3* L, Out&& out) {
    const Scalar m = fluid.particles.particleMass();
    forEachPairSum(s, fluid, x, CorrectedSymmetricPressureTerm{q, L},
                   [&](std::size_t i, const auto&, const auto& sum) { out(i, Vec3(-(m * sum.fluid + sum.wall))); });
}

// a_i += the corrected symmetric pressure acceleration of q = p/ρ² (q and L of every particle).
inline void addCorrectedSymmetricPressureAcceleration(const Scene& s, ParticleSystem& fluid, const std::vector<Scalar>& q,
                                                      const std::vector<Mat3>& L) {
    auto& a = fluid.particles.acceleration();
    correctedSymmetricPressureAcceleration(s, fluid, fluid.particles.position(), q.data(), L.data(),
                                           [&](std::size_t i, const Vec3& ai) { a[i] += ai; });
}

// Their reactions on the walls and bodies: a_ib = −M_b (q_i + q_b) L_i ∇W_ib.
inline void addCorrectedSymmetricPressureReactions(const Scene& s, const ParticleSystem& fluid, const std::vector<Scalar>& q,
                                                   const std::vector<Mat3>& L, Reactions& reactions) {
    const CorrectedSymmetricPressureTerm term{q.data(), L.data()};
    addReactions(s, fluid, fluid.particles.position(), term,
                 [&](std::size_t, const CorrectedSymmetricPressureTerm::Particle& pi, const WallPair& p) {
                     CorrectedSymmetricPressureTerm::Sum c;
                     term.wall(pi, p, c);
                     return Vec3(-c.wall);
                 }, ForceKind::pressure, reactions);
}

} // namespace spindrift
