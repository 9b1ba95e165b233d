// diffuseParticles — spray, foam and air bubbles, Ihmsen, Akinci, Akinci & Teschner (2012),
// "Unified spray, foam and air bubbles for particle-based fluids", The Visual Computer 28(6–8),
// 669–677, doi:10.1007/s00371-012-0697-9; seed 002 §4 (Duan et al.). docs/MODELS.md
// §diffuseParticles, with what differs from the paper and why.
//
// A passive system (PassiveModel.hpp: searched, written as its own block <name>.vtp, restarted,
// rolled back by the core) that never acts on the fluid. After each fluid step, every fluid
// particle i has three potentials, each clamped, Φ(I, τ) = (min(I, τmax) − min(I, τmin))/(τmax − τmin):
//   trapped air    I_ta = Φ(Σ_j |v_ij| (1 − v̂_ij·x̂_ij) W̃_ij, τ_ta),     W̃ = 1 − |x_ij|/h
//   wave crest     I_wc = Φ(Σ_j (1 − n̂_i·n̂_j) W̃_ij over surface j with x̂_ji·n̂_i < 0, τ_wc)
//                  on the surface only, and only where v̂_i·n̂_i ≥ 0.6 (moving along its normal)
//   kinetic energy I_k  = Φ(|v_i|²/2, τ_k)
// and generates n_i = I_k (k_ta I_ta + k_wc I_wc) Δt diffuse particles (rounded stochastically:
// ⌊n_i + U⌋, at most 100), each placed in the cylinder of radius Δx/2 about x_i along v_i Δt and
// moving with v_i plus its offset across the cylinder (the paper's v_d). Each diffuse particle is typed every
// step by its fluid neighbours n within h: spray below sprayNeighbours, air bubble above
// bubbleNeighbours, foam between (defaults 0.1 and 0.6 of a full neighbourhood on the case's
// lattice: 8 and 48 at h = 2.6 Δx in 3D, 2 and 12 in 2D); spray falls ballistically (exact for
// a constant g), foam goes with the fluid's Shepard velocity ṽ (x += Δt ṽ), a bubble rises,
// v += Δt(−k_b g) + k_d (ṽ − v), x += Δt v. Foam
// loses Δt of its lifetime a step and is deleted at 0; spray and bubbles do not age. A particle
// past a wall's face (the walls' share of its density, Σ_b M_b W_ib, above a flat wall's at its
// face: WallCollision.hpp) or out of the domain is deleted; when the count reaches maxParticles no more are generated (the
// log says so). The random numbers are a counter-based hash of (seed, step, the fluid particle's
// id, draw), so the result is the same at any thread count and after a restart; the only state
// beyond the particles, the next id, is kept in uniform/passive.
//
//   passive
//   {
//       diffuse
//       {
//           type             diffuseParticles;
//           trappedAir       (5 20);     // τ_ta [m/s]
//           waveCrest        (2 8);      // τ_wc [-]
//           kineticEnergy    (5 50);     // τ_k [J/kg]
//           kTrappedAir      4000;       // k_ta [1/s]
//           kWaveCrest       50000;      // k_wc [1/s]
//           lifetime         3;          // foam's [s]
//           sprayNeighbours  8;          // spray: fewer fluid neighbours than this
//           bubbleNeighbours 48;         // bubble: more than this
//           buoyancy         0.8;        // k_b
//           drag             0.5;        // k_d
//           maxParticles     1000000;
//           seed             1;
//       }
//   }
#include "KernelCorrection.hpp" // MomentAndColourTerm, smallestEigenvalue
#include "Log.hpp"
#include "PairLoop.hpp"
#include "PassiveModel.hpp"
#include "Plugin.hpp"
#include "WallCollision.hpp" // WallCollision::flatWallShare

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <sstream>

namespace {
using namespace spindrift;

enum DiffuseType : int { spray = 0, foam = 1, bubble = 2 };

// A uniform number in [0, 1) of (seed, step, particle, draw): SplitMix64's finaliser on a mix of
// the four (a counter-based generator: no state, the same draw whatever order asks for it).
double uniform(std::uint64_t seed, std::uint64_t step, std::uint64_t particle, std::uint64_t draw) {
    std::uint64_t z = seed * 0x9E3779B97F4A7C15ull ^ (step + 0x632BE59BD9B4E019ull) * 0xBF58476D1CE4E5B9ull ^
                      (particle + 0x8CB92BA72F3D8DD7ull) * 0x94D049BB133111EBull ^ (draw + 1) * 0xD6E8FEB86659FD93ull;
    for (int round = 0; round < 2; ++round) {
        z += 0x9E3779B97F4A7C15ull;
        z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
        z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
        z ^= z >> 31;
    }
    return double(z >> 11) * (1.0 / 9007199254740992.0);
}

// Φ(I, τ): 0 below τmin, 1 above τmax, linear between
struct Threshold {
    double min, max;
    double operator()(double I) const { return (std::min(I, max) - std::min(I, min)) / (max - min); }
};

// the trapped-air and wave-crest sums over the fluid neighbours
struct PotentialTerm {
    struct Sum {
        Scalar trappedAir = 0, crest = 0;
    };
    struct Particle {
        Vec3 v, n;
        bool surface;
    };
    const Vec3* v;
    const Vec3* normal;
    const signed char* surface;
    Scalar invH;
    Particle particle(std::size_t i) const { return {v[i], normal[i], surface[i] != 0}; }
    void fluid(const Particle& pi, const Pair& q, Sum& sum) const {
        const Scalar r = std::sqrt(q.r2);
        if (!(r > 0)) return;
        const Scalar weight = 1 - r * invH;
        const Vec3 vij = pi.v - v[q.j];
        const Scalar speed = vij.norm();
        if (speed > 0) sum.trappedAir += speed * (1 - vij.dot(q.r) / (speed * r)) * weight;
        // x̂_ji · n̂_i < 0: j behind i's surface (x_ji = −r_ij)
        if (pi.surface && surface[q.j] && q.r.dot(pi.n) > 0) sum.crest += (1 - pi.n.dot(normal[q.j])) * weight;
    }
};

// the fluid neighbours of a diffuse particle: their number and the Shepard velocity's sums; and
// the boundaries' share of its density, Σ_b M_b W_ib (WallCollision's measure of the distance to
// a face: past a face it exceeds a flat wall's at the face)
struct FluidAroundTerm {
    struct Sum {
        Vec3 v = Vec3::Zero();
        Scalar w = 0;
        int count = 0;
        Scalar wallShare = 0;
    };
    static constexpr bool usesKernel = true, visitsOtherFluids = true;
    struct Particle {};
    Particle particle(std::size_t) const { return {}; }
    void fluid(const Particle&, const Pair& p, Sum& sum) const {
        const Scalar w = p.src.particleMass / p.src.rho[p.j] * p.W;
        sum.v += w * p.src.v[p.j];
        sum.w += w;
        ++sum.count;
    }
    void wall(const Particle&, const WallPair& p, Sum& sum) const { sum.wallShare += p.mass() * p.W; }
};

class DiffuseParticles final : public PassiveModel {
public:
    explicit DiffuseParticles(const ModelContext& c)
        : name_(c.name), trappedAir_(range(c.dict, "trappedAir", {5, 20})), waveCrest_(range(c.dict, "waveCrest", {2, 8})),
          kineticEnergy_(range(c.dict, "kineticEnergy", {5, 50})),
          kTrappedAir_(nonNegative(c.dict, "kTrappedAir", 4000)), kWaveCrest_(nonNegative(c.dict, "kWaveCrest", 50000)),
          lifetime_(nonNegative(c.dict, "lifetime", 3)), sprayNeighbours_(c.dict.getOrDefault<int>("sprayNeighbours", -1)),
          bubbleNeighbours_(c.dict.getOrDefault<int>("bubbleNeighbours", -1)), buoyancy_(nonNegative(c.dict, "buoyancy", 0.8)),
          drag_(nonNegative(c.dict, "drag", 0.5)), maxParticles_(c.dict.getOrDefault<long>("maxParticles", 1000000)),
          seed_(std::uint64_t(c.dict.getOrDefault<long>("seed", 1))) {
        if (drag_ > 1) throw InputError(c.dict.locationOf("drag"), "drag must be between 0 and 1 (the share of the velocity "
                                                                   "difference to the fluid taken off a step)", "drag");
        // defaults: a tenth and six tenths of a full neighbourhood on the case's lattice (below)
        const double full = fullNeighbourhood(c.physics);
        if (!c.dict.found("sprayNeighbours")) sprayNeighbours_ = int(std::lround(0.1 * full));
        if (!c.dict.found("bubbleNeighbours")) bubbleNeighbours_ = int(std::lround(0.6 * full));
        if (sprayNeighbours_ < 0 || bubbleNeighbours_ < sprayNeighbours_)
            throw InputError(c.dict.locationOf(c.dict.found("bubbleNeighbours") ? "bubbleNeighbours" : "sprayNeighbours"),
                             "need 0 <= sprayNeighbours <= bubbleNeighbours (defaults here: " +
                                 std::to_string(std::lround(0.1 * full)) + ", " + std::to_string(std::lround(0.6 * full)) + ")",
                             "bubbleNeighbours");
        if (maxParticles_ < 0) throw InputError(c.dict.locationOf("maxParticles"), "maxParticles must not be negative", "maxParticles");
    }

    void initialise(Scene& s) override {
        ParticleSystem& diffuse = s.addSystem(name_, SystemRole::passive);
        diffuse.particles.addScalar("type", {true, true});
        diffuse.particles.addScalar("lifetime", {true, true});
        diffuse.particles.setUndefined("pressure");
        diffuse.particles.setUndefined("density");
        s.registerWithSearch(diffuse);
        for (const ParticleSystem* fluid : s.ofRole(SystemRole::fluid)) s.search.addInteraction(diffuse.index, fluid->index);
        for (const ParticleSystem* wall : s.boundaries()) s.search.addInteraction(diffuse.index, wall->index);
        index_ = diffuse.index;
    }

    void afterStep(Scene& s, const Step& step) override {
        ParticleSystem& diffuse = s.system(index_);
        if (!nextIdKnown_) { // a run from its start, or a restart written without uniform/passive
            for (Index id : diffuse.particles.id()) nextId_ = std::max(nextId_, std::uint64_t(id) + 1);
            nextIdKnown_ = true;
        }
        advect(s, diffuse, step);
        for (ParticleSystem* fluid : s.ofRole(SystemRole::fluid)) generate(s, *fluid, diffuse, step.dt);
        s.search.positionsChanged(diffuse.index);
    }

    std::string stateText() const override { return "    nextId " + std::to_string(nextId_) + ";\n"; }
    void readState(const Dictionary& d) override {
        nextId_ = std::uint64_t(d.get<long>("nextId"));
        nextIdKnown_ = true;
    }

private:
    // the neighbours within h of a particle inside the case's lattice (itself excluded)
    static double fullNeighbourhood(const PhysicalParameters& p) {
        const int d = p.dimension, reach = int(p.supportRadiusFactor) + 1;
        long n = 0;
        for (int a = -reach; a <= reach; ++a)
            for (int b = -reach; b <= reach; ++b)
                for (int c = (d == 3 ? -reach : 0); c <= (d == 3 ? reach : 0); ++c)
                    if (a * a + b * b + c * c > 0 && double(a * a + b * b + c * c) < double(p.supportRadiusFactor) * double(p.supportRadiusFactor))
                        ++n;
        return double(n);
    }

    static Threshold range(const Dictionary& d, const char* key, std::vector<double> fallback) {
        const auto v = d.getOrDefault<std::vector<double>>(key, fallback);
        if (v.size() != 2 || !(v[0] >= 0) || !(v[1] > v[0]))
            throw InputError(d.locationOf(key), std::string(key) + " needs (min max) with 0 <= min < max", key);
        return {v[0], v[1]};
    }
    static double nonNegative(const Dictionary& d, const char* key, double fallback) {
        const double v = d.getOrDefault<double>(key, fallback);
        if (!(v >= 0)) throw InputError(d.locationOf(key), std::string(key) + " must not be negative", key);
        return v;
    }

    // the type of every diffuse particle from its fluid neighbours, then its motion, its ageing
    // and the deletion of the expired and of those out of the domain
    void advect(Scene& s, ParticleSystem& diffuse, const Step& step) {
        const Scalar dt = step.dt;
        auto& set = diffuse.particles;
        const std::size_t count = set.size();
        if (count == 0) return;
        auto& x = set.position();
        auto& v = set.velocity();
        auto& type = *set.findScalar("type");
        auto& life = *set.findScalar("lifetime");
        const Vec3 g = s.physics.gravity;
        const Scalar kb = Scalar(buoyancy_), kd = Scalar(drag_);
        const Scalar atFace = WallCollision::flatWallShare(s, 0);
        keep_.assign(count, 1);
        forEachPairSum(s, diffuse, x, FluidAroundTerm{}, [&](std::size_t i, const auto&, const FluidAroundTerm::Sum& around) {
            const Vec3 fluidV = around.w > 0 ? Vec3(around.v / around.w) : v[i];
            const int t = around.count < sprayNeighbours_ ? spray : around.count > bubbleNeighbours_ ? bubble : foam;
            type[i] = Scalar(t);
            keep_[i] = around.wallShare < atFace; // past a wall's face: gone
            if (t == spray) { // ballistic, exact for a constant g
                x[i] += dt * v[i] + (Scalar(0.5) * dt * dt) * g;
                v[i] += dt * g;
                return;
            }
            if (t == foam) {
                v[i] = fluidV;
                life[i] -= dt;
            } else
                v[i] += -dt * kb * g + kd * (fluidV - v[i]);
            x[i] += dt * v[i];
        });
        step.core.wrap(s, diffuse, x);
        const int d = s.physics.dimension;
        const Vec3 lo = s.search.domainMin(), hi = s.search.domainMax();
        forEachIndex(count, [&](std::size_t i) {
            bool inside = keep_[i] && life[i] > 0;
            for (int k = 0; k < d; ++k) inside = inside && x[i][k] >= lo[k] && x[i][k] <= hi[k];
            keep_[i] = inside;
        });
        // delete, keeping the order of the rest
        std::vector<Index> order;
        order.reserve(count);
        for (std::size_t i = 0; i < count; ++i)
            if (keep_[i]) order.push_back(Index(i));
        const std::size_t kept = order.size();
        if (kept == count) return;
        for (std::size_t i = 0; i < count; ++i)
            if (!keep_[i]) order.push_back(Index(i));
        set.permute(order);
        set.resize(kept);
    }

    // the potentials of every particle of the fluid and the diffuse particles they generate
    void generate(Scene& s, const ParticleSystem& fluid, ParticleSystem& diffuse, Scalar dt) {
        const std::size_t count = fluid.size();
        const int d = s.physics.dimension;
        const Scalar m = fluid.particles.particleMass(), h = s.constants.supportRadius;
        const auto& x = fluid.particles.position();
        const auto& v = fluid.particles.velocity();
        const auto& id = fluid.particles.id();
        normal_.resize(count);
        surface_.resize(count);
        forEachPairSum(s, fluid, x, MomentAndColourTerm{fluid.particles.density().data(), m},
                       [&](std::size_t i, Scalar, const MomentAndColour& sum) {
                           normal_[i] = sum.outwardNormal(d);
                           surface_[i] = smallestEigenvalue(sum.moment, d) < Scalar(0.75) && normal_[i].squaredNorm() > 0;
                       });
        generated_.assign(count, 0);
        const std::uint64_t step = std::uint64_t(s.step);
        forEachPairSum(s, fluid, x, PotentialTerm{v.data(), normal_.data(), surface_.data(), 1 / h},
                       [&](std::size_t i, const PotentialTerm::Particle& pi, const PotentialTerm::Sum& sum) {
                           const Scalar speed = pi.v.norm();
                           const double kinetic = kineticEnergy_(0.5 * double(speed) * double(speed));
                           if (kinetic <= 0) return;
                           const bool alongNormal = pi.surface && speed > 0 && pi.v.dot(pi.n) >= Scalar(0.6) * speed;
                           const double crest = alongNormal ? waveCrest_(double(sum.crest)) : 0.0;
                           const double n = kinetic * (kTrappedAir_ * trappedAir_(double(sum.trappedAir)) + kWaveCrest_ * crest) * dt;
                           // (at most maxPerParticle a step: rates far beyond Ihmsen's would fill the
                           // memory; not a number, from an infinite rate times 0: none)
                           const double drawn = std::floor(n + uniform(seed_, step, id[i], 0));
                           generated_[i] = drawn > 0 ? int(std::min(drawn, double(maxPerParticle))) : 0;
                       });
        // the new particles in the fluid's order (a serial prefix sum: independent of the threads)
        auto& set = diffuse.particles;
        const std::size_t before = set.size();
        std::size_t total = 0, refused = 0;
        for (std::size_t i = 0; i < count; ++i) {
            const std::size_t room = maxParticles_ > long(before + total) ? std::size_t(maxParticles_) - before - total : 0;
            if (std::size_t(generated_[i]) > room) {
                refused += std::size_t(generated_[i]) - room;
                generated_[i] = int(room);
            }
            total += std::size_t(generated_[i]);
        }
        if (refused > 0) reportCap(s, refused);
        if (total == 0) return;
        set.resize(before + total);
        auto& xd = set.position();
        auto& vd = set.velocity();
        auto& type = *set.findScalar("type");
        auto& life = *set.findScalar("lifetime");
        auto& ids = set.id();
        const Scalar radius = Scalar(0.5) * s.physics.particleSpacing;
        std::size_t k = before;
        for (std::size_t i = 0; i < count; ++i)
            for (int draw = 0; draw < generated_[i]; ++draw, ++k) {
                const Scalar speed = v[i].norm();
                const Vec3 along = v[i] / speed;
                Vec3 e1, e2 = Vec3::Zero();
                if (d == 2) e1 = Vec3(-along[1], along[0], 0);
                else {
                    e1 = along.cross(std::abs(along[0]) < Scalar(0.9) ? Vec3::UnitX() : Vec3::UnitY()).normalized();
                    e2 = along.cross(e1);
                }
                const std::uint64_t base = 1 + 3 * std::uint64_t(draw);
                const double Xr = uniform(seed_, step, id[i], base), Xt = uniform(seed_, step, id[i], base + 1),
                             Xh = uniform(seed_, step, id[i], base + 2);
                // across the cylinder: in 2D a segment of half-width r_V, in 3D a disc
                const Vec3 across = d == 2 ? Vec3(radius * Scalar(2 * Xr - 1) * e1)
                                           : Vec3(radius * Scalar(std::sqrt(Xr)) *
                                                  (Scalar(std::cos(2 * std::numbers::pi * Xt)) * e1 +
                                                   Scalar(std::sin(2 * std::numbers::pi * Xt)) * e2));
                xd[k] = x[i] + across + Scalar(Xh) * dt * v[i];
                vd[k] = v[i] + across;
                type[k] = Scalar(foam);
                life[k] = Scalar(lifetime_);
                ids[k] = Index(nextId_++);
            }
    }

    // a warning the first time the cap stops generation, then whenever the number of steps it
    // did reaches a power of ten
    void reportCap(const Scene& s, std::size_t refused) {
        if (++cappedSteps_ < nextReport_) return;
        nextReport_ *= 10;
        std::ostringstream m;
        m << "passive " << name_ << ": maxParticles " << maxParticles_ << " reached at step " << s.step << ": " << refused
          << " diffuse particles not generated (" << cappedSteps_ << " steps with the cap so far)";
        log::warning(m.str());
    }

    static constexpr int maxPerParticle = 100; // diffuse particles a fluid particle generates a step, at most

    std::string name_;
    Threshold trappedAir_, waveCrest_, kineticEnergy_;
    double kTrappedAir_, kWaveCrest_, lifetime_;
    int sprayNeighbours_, bubbleNeighbours_;
    double buoyancy_, drag_;
    long maxParticles_;
    std::uint64_t seed_;
    std::size_t index_ = 0;
    std::uint64_t nextId_ = 0;
    bool nextIdKnown_ = false;
    long cappedSteps_ = 0, nextReport_ = 1;
    std::vector<Vec3> normal_;
    std::vector<signed char> surface_;
    std::vector<int> generated_;
    std::vector<char> keep_;
};
} // namespace

SPINDRIFT_PLUGIN(PassiveModel, DiffuseParticles)
