// isobaric — the isobaric pressure term of Perea & Cordero (seed 000, eqs. 13–16;
// docs/MODELS.md §isobaric), with summation density and the Tait equation of state of wcsph
// (TaitEquationOfState.hpp; the paper uses γ = 5.65).
//
//   ∇p_i = 1/(2ρ_i) Σ_j m_j P_p ∇_i W_ij,   P_p = α (p_j − p_i) + β ρ_i² (p_i/ρ_i² + p_j/ρ_j²),
//   a_i = −∇p_i/ρ_i,  α = α(𝒫; δ) (IsobaricBlend.hpp), β = 2 − α.
// Oriented so that β = 2 is exactly the wcsph force and α = 2 the difference form
// (1/ρ_i) Σ m_j (p_j − p_i) ∇_i W_ij: a neighbourhood of uniform pressure (𝒫 = 0, α = 2) feels
// no pressure force at all, even at a free surface. α = 2 at 𝒫 = 0 falls to 0 at 𝒫 ≈ 2δ, so
// δ → 0 gives wcsph wherever pressures differ. The paper's eq. 15 as printed grows above 2 for
// 𝒫 > 0; docs/MODELS.md §isobaric's restatement of its intent is implemented.
// The α part is not pairwise antisymmetric (the pair's difference terms add instead of
// cancelling), so this term does not conserve momentum exactly; the β part does.
// Walls (not in the paper, which uses a collision response): a wall particle b stands in for
// the fluid missing from i's neighbourhood, so its term takes the blend of i's fluid pairs,
//   a_i −= Ψ_b [ᾱ_i (p_b − p_i)/(2ρ_i²) + (2 − ᾱ_i)/2 (p_i/ρ_i² + P_b)] ∇_i W_ib,
// ᾱ_i = the mean of α_ij over i's fluid neighbours weighted by |∇_i W_ij · n_i|, n_i =
// Σ_b Ψ_b ∇_i W_ib (pairs along the wall carry no share of the push towards it). With a mirroring boundary
// (akinci) P_b = p_i/ρ_i² as in wcsph and, in the difference part, the hydrostatic
// extrapolation p_b = p_i + ρ_i g·(x_b − x_i) (Adami et al. 2012; clamped at 0 with
// clampNegativePressure); otherwise the boundary's own p_b, ρ_b. So the wall balances the
// share of the sum form's 2p_i Σ m ∇W (the "deficiency" push towards a wall) that the
// fluid pairs keep: ᾱ = 0 is the wcsph wall term, ᾱ = 2 the difference form completed by the
// wall. (A symmetric wall term under a blended fluid term pushes fluid off the walls by
// ~p/(ρ h) and blows up a hydrostatic tank within a few dozen steps.)
//
// The difference form has no repulsion between two particles of equal pressure, so where it
// dominates particles pair up: in tutorials/hydrostaticTank2D (wendlandC2, c0 = 25 m/s) δ ≥ 0.04
// blows up within 0.015 s whatever the time step, δ ≤ 0.03 runs. The default δ is therefore the
// value of the paper's own simulation (§8), not its recommended range 0.05–0.25.
//
//   pressure { type isobaric; delta 4.5e-3; gamma 5.65; soundSpeed 20; clampNegativePressure yes; }
//   delta: the isobaric factor δ, 0 < δ ≤ 0.25.
#include "IsobaricBlend.hpp"
#include "Plugin.hpp"
#include "PressureModel.hpp"
#include "PairLoop.hpp"
#include "TaitEquationOfState.hpp"

#include <sstream>

namespace {
using namespace spindrift;

// Σ_b M_b ∇_i W_ib: the direction of i's wall deficiency (zero away from walls).
struct TowardsWallTerm {
    using Sum = Vec3;
    static constexpr bool usesGradient = true, visitsFluid = false;
    struct Particle {};
    Particle particle(std::size_t) const { return {}; }
    void fluid(const Particle&, const Pair&, Sum&) const {}
    void wall(const Particle&, const WallPair& p, Sum& sum) const { sum += p.mass() * p.gradW; }
};

// The blended pressure force of i's fluid pairs, with the weights of the wall blend ᾱ_i, and the
// wall sums that ᾱ_i combines (it is known only once every fluid pair is summed):
//   wall part = ᾱ_i Σ_b M_b (p_b − p_i)/(2ρ_i²) ∇W_ib + (2 − ᾱ_i)/2 Σ_b M_b (P_i + P_b) ∇W_ib.
struct IsobaricTerm {
    struct Sum {
        Vec3 fluid = Vec3::Zero();        // Σ_j m coeff_ij ∇W_ij
        Scalar alphaWeighted = 0, weight = 0; // Σ α_ij |∇W_ij·n_i|, Σ |∇W_ij·n_i|
        Vec3 wallDifference = Vec3::Zero(); // Σ_b M_b (p_b − p_i)/(2ρ_i²) ∇W_ib
        Vec3 wallSum = Vec3::Zero();        // Σ_b M_b (P_i + P_b) ∇W_ib
    };
    static constexpr bool usesGradient = true;
    struct Particle {
        Scalar p, rho, P, halfInvRho2;
        Vec3 towardsWall;
    };
    const Scalar* p;
    const Scalar* rho;
    const Vec3* towardsWall;
    Scalar m;
    Vec3 g;
    bool clamp;
    isobaric::Blend blend;

    Particle particle(std::size_t i) const {
        const Scalar r2 = rho[i] * rho[i];
        return {p[i], rho[i], p[i] / r2, Scalar(0.5) / r2, towardsWall[i]};
    }
    void fluid(const Particle& pi, const Pair& q, Sum& sum) const {
        if (!(q.r2 > 0)) return;
        const Scalar alpha = Scalar(blend.alpha(pi.p, p[q.j]));
        const Scalar coeff = alpha * (p[q.j] - pi.p) * pi.halfInvRho2 +
                             Scalar(0.5) * (2 - alpha) * (pi.P + p[q.j] / (rho[q.j] * rho[q.j]));
        sum.fluid += (m * coeff) * q.gradW;
        const Scalar w = std::abs(q.gradW.dot(pi.towardsWall));
        sum.alphaWeighted += alpha * w;
        sum.weight += w;
    }
    void wall(const Particle& pi, const WallPair& q, Sum& sum) const {
        Scalar pWall, Pb;
        if (q.src.mirrored) {
            pWall = pi.p - pi.rho * g.dot(q.r); // p_i + ρ_i g·(x_b − x_i)
            if (clamp && pWall < 0) pWall = 0;
            Pb = pi.P;
        } else {
            pWall = q.src.p[q.j];
            Pb = pWall / (q.src.rho[q.j] * q.src.rho[q.j]);
        }
        sum.wallDifference += (q.mass() * (pWall - pi.p) * pi.halfInvRho2) * q.gradW;
        sum.wallSum += (q.mass() * (pi.P + Pb)) * q.gradW;
    }
};

class Isobaric final : public PressureModel {
public:
    explicit Isobaric(const ModelContext& c) : blend_(readDelta(c.dict)) { eos_.read(c.dict, c.physics.rho0); }

    Scalar soundSpeed(const SceneConstants& c, const PhysicalParameters& physics) const override {
        return eos_.resolveSoundSpeed(c, physics);
    }
    Scalar eosExponent() const override { return eos_.gamma; }
    void initialise(Scene& s) override {
        eos_.initialise(s);
        for (ParticleSystem* fluid : s.ofRole(SystemRole::fluid))
            fluid->particles.addVector("isobaricTowardsWall", {false, false, true}); // scratch: Σ_b M_b ∇W_ib
    }
    bool integratesDensity() const override { return eos_.continuity; }

    void computeDensity(Scene& s, ParticleSystem& fluid, const Step&) override { eos_.densityAndPressure(s, fluid); }

    void addPressureAcceleration(Scene& s, ParticleSystem& fluid, const Step&) override {
        const auto& x = fluid.particles.position();
        auto& n = *fluid.particles.findVector("isobaricTowardsWall");
        forEachPairSum(s, fluid, x, TowardsWallTerm{}, [&](std::size_t i, const auto&, const Vec3& sum) { n[i] = sum; });
        auto& a = fluid.particles.acceleration();
        alpha_.resize(x.size());
        forEachPairSum(s, fluid, x, termOf(s, fluid), [&](std::size_t i, const auto&, const IsobaricTerm::Sum& sum) {
            const Scalar alpha = sum.weight > 0 ? sum.alphaWeighted / sum.weight : Scalar(0);
            alpha_[i] = alpha;
            a[i] -= sum.fluid + alpha * sum.wallDifference + Scalar(0.5) * (2 - alpha) * sum.wallSum;
        });
    }

    // a_ib = −(ᾱ_i M_b (p_b − p_i)/(2ρ_i²) + (2 − ᾱ_i)/2 M_b (P_i + P_b)) ∇W_ib with each particle's
    // blend ᾱ_i of the last pass
    void addReactions(const Scene& s, const ParticleSystem& fluid, const Step&, Reactions& r) const override {
        const IsobaricTerm term = termOf(s, fluid);
        spindrift::addReactions(s, fluid, fluid.particles.position(), term, [&](std::size_t i, const auto& pi, const WallPair& q) {
            IsobaricTerm::Sum c;
            term.wall(pi, q, c);
            return Vec3(-(alpha_[i] * c.wallDifference + Scalar(0.5) * (2 - alpha_[i]) * c.wallSum));
        }, ForceKind::pressure, r);
    }

private:
    IsobaricTerm termOf(const Scene& s, const ParticleSystem& fluid) const {
        return {fluid.particles.pressure().data(), fluid.particles.density().data(),
                fluid.particles.findVector("isobaricTowardsWall")->data(), fluid.particles.particleMass(),
                s.physics.gravity, eos_.clampNegative, blend_};
    }

    static double readDelta(const Dictionary& d) {
        const double delta = d.getOrDefault<double>("delta", 4.5e-3);
        if (!isobaric::Blend::validDelta(delta)) {
            std::ostringstream m;
            m << "the isobaric factor delta must be in (0, 0.25] (got " << delta
              << "; the paper recommends 0.05-0.25, its wave scene uses 4.5e-3)";
            throw InputError(d.locationOf("delta"), m.str(), "delta");
        }
        return delta;
    }

    isobaric::Blend blend_;
    TaitEquationOfState eos_;
    std::vector<Scalar> alpha_; // each particle's wall blend ᾱ_i of the last pass
};
} // namespace

SPINDRIFT_PLUGIN(PressureModel, Isobaric)
