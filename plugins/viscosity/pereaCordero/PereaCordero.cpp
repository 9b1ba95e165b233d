// pereaCordero — the damped viscous term of Perea & Cordero (seed 000, eqs. 17–18; MODELS.md
// "Viscosity"), with the kernel's laplacian (the core tabulates it; poly6Spiky gives Müller's
// viscosity kernel, sinc2 the paper's own):
//   form paper       a_i = Σ_j m_j (μ_j v_j/ρ_j² + μ_i v_i/ρ_i²) ∇²W_ij Γ_ij       (eq. 17 / ρ_i)
//   form difference  a_i = Σ_j m_j ½ (μ_j/ρ_j² + μ_i/ρ_i²) (v_j − v_i) ∇²W_ij Γ_ij  (default)
//   Γ_ij = exp(−2 |v_j − v_i| / (U (ρ_i ρ_j/ρ0²) (r/h)))                         (eq. 18)
// The printed form sums velocities: a uniformly moving fluid feels a force (wherever
// Σ_j m_j ∇²W_ij ≠ 0, e.g. near a free surface and from the missing self term), and the
// equal, not opposite, pair forces do not conserve momentum. The difference form is Galilean
// invariant, pairwise antisymmetric (momentum to round-off) and approximates ν∇²v (the ½
// makes Σ_j V_j (v_j − v_i) ∇²W_ij ≈ ∇²v carry the physical viscosity once).
// Eq. 18's exponent 2|v_ji|/(h ρ_i ρ_j r) is not dimensionless; we keep its dependence on
// |v_ji|, ρ_i ρ_j and r/h and collect the dimensional constants in a velocity scale U
// (`dampingScale`, m/s). Its default U = h² ρ0² (numerically, SI) reproduces the printed
// exponent in SI units, where Γ ≈ 1 for water; a scale comparable to neighbour relative
// speeds (e.g. 0.1 m/s) makes Γ act.
// μ: `mu` (dynamic, Pa s, uniform) if given, else μ_i = ρ_i ν with ν from fluidProperties.
// Walls: no-slip particles at rest with the fluid particle's density and viscosity
// (wallFactor scales them; 0 = free slip).
//
//   viscosity { type pereaCordero; form difference; mu 0.26; dampingScale 0.1; wallFactor 1; }
#include "Log.hpp"
#include "Plugin.hpp"
#include "SphOperators.hpp"
#include "ViscosityModel.hpp"

#include <sstream>

namespace {
using namespace spindrift;

class PereaCordero final : public ViscosityModel {
public:
    explicit PereaCordero(const ModelContext& c)
        : paperForm_(c.dict.getWordOrDefault("form", {"difference", "paper"}, "difference") == "paper"),
          constantMu_(c.dict.found("mu")), mu_(constantMu_ ? c.dict.get<double>("mu") : 0.0), nu_(c.physics.nu),
          rho0_(c.physics.rho0), wallFactor_(c.dict.getOrDefault<double>("wallFactor", 1.0)) {
        if (constantMu_ && !(mu_ > 0))
            throw InputError(c.dict.locationOf("mu"), "mu (dynamic viscosity) must be positive", "mu");
        if (!constantMu_ && !(nu_ > 0))
            throw InputError(c.dict.where(), "pereaCordero viscosity needs a viscosity: 'viscosity' (kinematic) in "
                                             "constant/fluidProperties or 'mu' (dynamic) here", "mu");
        const Scalar h = c.physics.supportRadius;
        if (c.dict.found("dampingScale")) {
            dampingScale_ = c.dict.get<double>("dampingScale");
            if (!(dampingScale_ > 0))
                throw InputError(c.dict.locationOf("dampingScale"), "dampingScale (m/s) must be positive", "dampingScale");
        } else {
            dampingScale_ = h * h * rho0_ * rho0_;
            std::ostringstream m;
            m << "    default: viscosity.dampingScale " << dampingScale_
              << " m/s (h^2 rho0^2: eq. 18 as printed, in SI units)";
            log::info(m.str());
        }
    }

    Scalar timeStepViscosity() const override { return constantMu_ ? mu_ / rho0_ : nu_; }

    void initialise(SphSystem& s) override { s.kernel.enableLaplacian(); }

    void addAcceleration(SphSystem& s, Scalar) override {
        const auto& kt = s.kernel;
        const Scalar m = s.fluid.particleMass(), h = kt.supportRadius();
        const auto& x = s.fluid.position();
        const auto& v = s.fluid.velocity();
        const auto& rho = s.fluid.density();
        auto& a = s.fluid.acceleration();
        const auto& xb = s.boundary.position();
        const Scalar* psi = s.boundaryMass ? s.boundaryMass->data() : nullptr;
        const bool constantMu = constantMu_, paper = paperForm_;
        const Scalar mu = mu_, nu = nu_, wall = wallFactor_;
        // Γ = exp(−g |v_ji| / (ρ_i ρ_j r)),  g = 2 h ρ0² / U
        const Scalar g = 2 * h * rho0_ * rho0_ / dampingScale_;
        auto muOverRho2 = [&](Scalar r) { return constantMu ? mu / (r * r) : nu / r; };
        auto gamma = [&](const Vec3& dv, Scalar rhoiRhoj, Scalar r) {
            const Scalar num = g * dv.norm();
            return num > 0 ? std::exp(-num / (rhoiRhoj * r)) : Scalar(1);
        };
#pragma omp parallel for schedule(static)
        for (std::size_t i = 0; i < x.size(); ++i) {
            const Scalar ci = muOverRho2(rho[i]);
            Vec3 acc = Vec3::Zero();
            forEachNeighbour(s.search.fluidNeighbours(), x, x, i, [&](Index j, const Vec3&, Scalar r2) {
                const Scalar r = std::sqrt(r2);
                const Vec3 dv = v[j] - v[i];
                const Scalar w = m * kt.laplacian(r) * gamma(dv, rho[i] * rho[j], r);
                const Scalar cj = muOverRho2(rho[j]);
                if (paper) acc += w * (cj * v[j] + ci * v[i]);
                else acc += (w * Scalar(0.5) * (ci + cj)) * dv;
            });
            if (psi && wall != 0)
                forEachNeighbour(s.search.boundaryNeighbours(), x, xb, i, [&](Index b, const Vec3&, Scalar r2) {
                    const Scalar r = std::sqrt(r2);
                    const Vec3 dv = -v[i]; // wall at rest, ρ_b = ρ_i, μ_b = μ_i
                    const Scalar w = wall * psi[b] * kt.laplacian(r) * gamma(dv, rho[i] * rho[i], r) * ci;
                    acc += paper ? Vec3(w * v[i]) : Vec3(w * dv);
                });
            a[i] += acc;
        }
    }

private:
    bool paperForm_, constantMu_;
    Scalar mu_, nu_, rho0_, wallFactor_, dampingScale_ = 0;
};
} // namespace

SPINDRIFT_PLUGIN(ViscosityModel, PereaCordero)
