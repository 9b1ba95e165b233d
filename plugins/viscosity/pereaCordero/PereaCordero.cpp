// pereaCordero — the damped viscous term of Perea & Cordero (seed 000, eqs. 17–18;
// docs/MODELS.md §pereaCordero-viscosity), with the kernel's laplacian (the core tabulates it; poly6Spiky gives Müller's
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
// Walls: their particles with the fluid particle's density and viscosity, moving with the
// velocity the boundary model gives viscous terms (wallFactor scales them; 0 = free slip). The
// density of that term is max(ρ_i, ρ0) (wallDensityFloor yes, the default): a summed density
// falls short of ρ0 by missing neighbours, and μ/ρ_i² made the wall's friction on a lone
// particle (0.33–0.45 ρ0) 5–9 times the bulk's, holding it on a wall (issue 34, pereaWave).
//
//   viscosity { type pereaCordero; form difference; mu 0.26; dampingScale 0.1; wallFactor 1; wallDensityFloor yes; }
#include "Log.hpp"
#include "Plugin.hpp"
#include "PairLoop.hpp"
#include "ViscosityModel.hpp"

#include <algorithm>
#include <sstream>

namespace {
using namespace spindrift;

// The damped pair term: m_j ∇²W_ij Γ_ij times the velocity part of the chosen form.
struct DampedViscosityTerm {
    using Sum = Vec3;
    struct Particle {
        Vec3 v;
        Scalar rho, c, cWall; // c = μ_i/ρ_i²; cWall the same at max(ρ_i, wallRho)
    };
    const KernelTable& kt;
    const Vec3* v;
    const Scalar* rho;
    Scalar m, mu, nu, g, wallFactor; // Γ = exp(−g |v_ji| / (ρ_i ρ_j r)), g = 2 h ρ0² / U
    Scalar wallRho;                  // the wall term's least density: ρ0 (wallDensityFloor yes), else 0
    bool constantMu, paper, visitsWalls;
    Scalar muOverRho2(Scalar r) const { return constantMu ? mu / (r * r) : nu / r; }
    Scalar gamma(const Vec3& dv, Scalar rhoiRhoj, Scalar r) const {
        const Scalar num = g * dv.norm();
        return num > 0 ? std::exp(-num / (rhoiRhoj * r)) : Scalar(1);
    }
    Particle particle(std::size_t i) const {
        return {v[i], rho[i], muOverRho2(rho[i]), muOverRho2(std::max(rho[i], wallRho))};
    }
    void fluid(const Particle& pi, const Pair& q, Sum& sum) const {
        const Scalar r = std::sqrt(q.r2);
        const Vec3 dv = v[q.j] - pi.v;
        const Scalar w = m * kt.laplacian(r) * gamma(dv, pi.rho * rho[q.j], r), cj = muOverRho2(rho[q.j]);
        if (paper) sum += w * (cj * v[q.j] + pi.c * pi.v);
        else sum += (w * Scalar(0.5) * (pi.c + cj)) * dv;
    }
    // the wall's particles with ρ_b = ρ_i and μ_b = μ_i, moving with the velocity viscous terms see;
    // ρ_i floored at ρ0 (wallDensityFloor): a summed density short of ρ0 is missing neighbours, and
    // μ/ρ_i² would scale the wall's no-slip friction on a particle by (ρ0/ρ_i)²
    void wall(const Particle& pi, const WallPair& q, Sum& sum) const {
        const Scalar r = std::sqrt(q.r2);
        const Vec3 vb = q.src.vViscous[q.j], dv = vb - pi.v;
        const Scalar w = wallFactor * q.mass() * kt.laplacian(r) * gamma(dv, pi.rho * pi.rho, r) * pi.cWall;
        sum += paper ? Vec3(w * (vb + pi.v)) : Vec3(w * dv);
    }
};

class PereaCordero final : public ViscosityModel {
public:
    explicit PereaCordero(const ModelContext& c)
        : paperForm_(c.dict.getWordOrDefault("form", {"difference", "paper"}, "difference") == "paper"),
          constantMu_(c.dict.found("mu")), mu_(constantMu_ ? c.dict.get<double>("mu") : 0.0), nu_(c.physics.nu),
          rho0_(c.physics.rho0), wallFactor_(c.dict.getOrDefault<double>("wallFactor", 1.0)),
          wallFloor_(c.dict.getOrDefault<bool>("wallDensityFloor", true)) {
        if (constantMu_ && !(mu_ > 0))
            throw InputError(c.dict.locationOf("mu"), "mu (dynamic viscosity) must be positive", "mu");
        if (!constantMu_ && !(nu_ > 0))
            throw InputError(c.dict.where(), "pereaCordero viscosity needs a viscosity: 'viscosity' (kinematic) in "
                                             "constant/fluidProperties or 'mu' (dynamic) here", "mu");
        const Scalar h = c.constants.supportRadius;
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

    double maxTimeStep(const Scene& s, const StateSpeeds&) const override {
        return viscousTimeStepLimit(s, constantMu_ ? mu_ / rho0_ : nu_);
    }

    void initialise(Scene& s) override { s.kernel.enableLaplacian(); }

    void addAcceleration(Scene& s, ParticleSystem& fluid, const Step&) override {
        addPairAcceleration(s, fluid, termOf(s, fluid));
    }
    void addReactions(const Scene& s, const ParticleSystem& fluid, const Step&, Reactions& r) const override {
        addScaledReactions(s, fluid, termOf(s, fluid), Scalar(1), ForceKind::viscous, r);
    }

private:
    DampedViscosityTerm termOf(const Scene& s, const ParticleSystem& fluid) const {
        const Scalar h = s.constants.supportRadius;
        return {s.kernel,    fluid.particles.velocity().data(), fluid.particles.density().data(),
                fluid.particles.particleMass(), mu_, nu_, 2 * h * rho0_ * rho0_ / dampingScale_,
                wallFactor_, wallFloor_ ? rho0_ : Scalar(0), constantMu_, paperForm_, wallFactor_ != 0};
    }

    bool paperForm_, constantMu_;
    Scalar mu_, nu_, rho0_, wallFactor_, dampingScale_ = 0;
    bool wallFloor_;
};
} // namespace

SPINDRIFT_PLUGIN(ViscosityModel, PereaCordero)
