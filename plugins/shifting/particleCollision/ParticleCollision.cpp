// particleCollision — particle collisions against clustering, Kruisbrink, Korzilius, Pearce &
// Morvan (2018), "SPH particle collisions for the reduction of particle clustering, interface
// stabilisation and wall modelling", J. Appl. Math. Phys. 6(9) 1860–1882,
// doi:10.4236/jamp.2018.69158; docs/MODELS.md §particleCollision.
//
// The pressure force between two particles vanishes as they meet (the kernel's gradient is flat
// at r = 0), and nothing repels two particles of a density below ρ0 at all (a free surface, an
// expanding flow, where the incompressible solvers and a clamped equation of state give p = 0),
// so such particles pair up; with negative pressure the tensile instability pulls them together.
// A kinematic condition replaces the missing force: two fluid particles i, j whose positions at
// the end of the step, x* = x + Δt (v + Δt a) (symplectic Euler), would be closer than
// d_c = distance·Δx while they approach each other collide along n = (x*_i − x*_j)/|…|:
//   v*_ij·n < 0:   Δv_i = −½ (1 + e) (v*_ij·n) n,   Δv_j = −Δv_i,   v* = v + Δt a
// (equal masses; e the coefficient of restitution, 0: the approach is stopped, 1: reflected),
// added as Δv_i/Δt. Momentum is conserved pair by pair; energy with e = 1. Collisions of one
// particle with several others are summed (each from the velocities before any). The model acts
// only on pairs about to come closer than d_c: a flow whose particles keep their spacing is not
// touched. It is a shifting model as the paper says ("a particle shifting method, in the sense
// that the velocities are changed"): its drift correction δv is zero; walls are the boundary
// model's. Pairs of one fluid only: it puts no force on the boundaries (addReactions adds nothing).
//
//   shifting { type particleCollision; distance 0.7; restitution 0; sweeps 2; }
#include "PairLoop.hpp"
#include "Plugin.hpp"
#include "ShiftingModel.hpp"

#include <cmath>

namespace {
using namespace spindrift;

// Σ_j over the fluid neighbours j about to come closer than d_c: −½ (1 + e) min(0, v*_ij·n) n.
struct CollisionTerm {
    using Sum = Vec3;
    struct Particle {
        Vec3 x, v;
    };
    const Vec3* x; // predicted positions
    const Vec3* v; // predicted velocities
    Scalar distance2, half; // d_c², ½ (1 + e)
    Particle particle(std::size_t i) const { return {x[i], v[i]}; }
    void fluid(const Particle& pi, const Pair& q, Sum& sum) const {
        const Vec3 r = pi.x - x[q.j];
        const Scalar r2 = r.squaredNorm();
        if (!(r2 < distance2) || !(r2 > 0)) return;
        const Scalar approach = (pi.v - v[q.j]).dot(r); // |r| (v*_ij·n)
        if (approach < 0) sum -= (half * approach / r2) * r;
    }
};

class ParticleCollision final : public ShiftingModel {
public:
    explicit ParticleCollision(const ModelContext& c)
        : distance_(c.dict.getOrDefault<double>("distance", 0.7)),
          restitution_(c.dict.getOrDefault<double>("restitution", 0.0)),
          sweeps_(c.dict.getOrDefault<int>("sweeps", 2)) {
        if (sweeps_ < 1) throw InputError(c.dict.locationOf("sweeps"), "sweeps must be at least 1", "sweeps");
        if (!(distance_ > 0 && distance_ < 1))
            throw InputError(c.dict.locationOf("distance"), "distance (in particle spacings) must be in (0, 1)", "distance");
        if (!(restitution_ >= 0 && restitution_ <= 1))
            throw InputError(c.dict.locationOf("restitution"), "restitution must be in [0, 1]", "restitution");
    }

    void computeShift(Scene& s, ParticleSystem& fluid, const Step& step) override {
        const Scalar dt = step.dt;
        auto& shift = *fluid.particles.findVector("shiftingVelocity"); // (the core's field)
        const std::size_t n = fluid.size();
        forEachIndex(n, [&](std::size_t i) { shift[i] = Vec3::Zero(); }); // no drift correction
        if (!(dt > 0)) return;
        const auto& x = fluid.particles.position();
        const auto& v = fluid.particles.velocity();
        auto& a = fluid.particles.acceleration();
        predictedX_.resize(n);
        predictedV_.resize(n);
        const Scalar dc = Scalar(distance_) * s.physics.particleSpacing, invDt = 1 / dt;
        for (int sweep = 0; sweep < sweeps_; ++sweep) {
            forEachIndex(n, [&](std::size_t i) {
                predictedV_[i] = v[i] + dt * a[i];
                predictedX_[i] = x[i] + dt * predictedV_[i];
            });
            // the pairs from the step's lists (the displacement over a step is well inside the support)
            forEachPairSum(s, fluid, x, CollisionTerm{predictedX_.data(), predictedV_.data(), dc * dc, Scalar(0.5 * (1 + restitution_))},
                           [&](std::size_t i, const auto&, const Vec3& dv) { a[i] += invDt * dv; });
        }
    }

    void addReactions(const Scene&, const ParticleSystem&, const Step&, Reactions&) const override {}

private:
    double distance_, restitution_;
    int sweeps_; // passes over the pairs, each from the velocities the last one left
    std::vector<Vec3> predictedX_, predictedV_;
};
} // namespace

SPINDRIFT_PLUGIN(ShiftingModel, ParticleCollision)
