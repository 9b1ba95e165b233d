// Spindrift — the pair loop, written once: every fluid particle i against its fluid neighbours j
// and the particles b of every wall system, on the step's neighbour lists, in the balanced
// parallel schedule of the search (forEachParticleBalanced), with the wall masses and the
// cached pair gradients. A model supplies only a pair term: what one neighbour contributes.
//
//   struct ViscousTerm {                       // a pair term
//       using Sum = Vec3;                      // what the loop sums for particle i
//       static constexpr bool usesGradient = true; // the loop fills pair.gradW (= ∇_i W_ij)
//       static constexpr bool usesKernel = false;  // (true: the loop fills pair.W = W_ij, from
//                                                  //  the same table lookup as the gradient)
//       static constexpr bool usesDampedGradient = false; // (true: pair.dampedGradFactor, with
//                                                  //  ∇_i W_ij/(r² + η²) = r_ij · that; KernelTable)
//       struct Particle { Vec3 v; Scalar rho; };   // i's own values, read once
//       Particle particle(std::size_t i) const;
//       void fluid(const Particle&, const Pair&, Sum&) const;     // neighbour j of the fluid
//       void wall(const Particle&, const WallPair&, Sum&) const;  // particle b of a wall
//   };
//   addPairAcceleration(scene, ViscousTerm{...});   // a_i += Σ, or
//   forEachPairSum(scene, x, term, [&](std::size_t i, const Particle& pi, const Sum& sum) { ... });
//
// A term without a wall() member leaves the walls out, as does one whose `bool visitsWalls`
// member is false at run time (a wallFactor of 0); one with `static constexpr bool
// visitsFluid = false` visits only the walls (its fluid() is never called). The loop reads positions x (the fluid's
// own or predicted ones, e.g. PCISPH's); the walls are where their motion puts them at the
// evaluation's time. Results are bit for bit independent of the thread count: each i is summed
// by one thread in list order.
#pragma once

#include "Scene.hpp"

#include <array>

namespace spindrift {

// f(k, j, r_ij, r²) for every neighbour j of particle i in 'list' (positions xi of the set i
// belongs to, xj of the neighbours' set), k the pair's place in the list. r_ij is the nearest
// periodic image when the domain is periodic. The walk counts k (not a pointer into the
// indices), so that data kept per pair is addressed by the loop's one induction variable.
template <class F>
inline void forEachNeighbourPair(const NeighbourList& list, const std::vector<Vec3>& xi,
                                 const std::vector<Vec3>& xj, std::size_t i, F&& f) {
    const Vec3 x = xi[i];
    const Index* indices = list.indices.data();
    const std::size_t begin = list.offsets[i], end = list.offsets[i + 1];
    if (list.periodic) {
        for (std::size_t k = begin; k != end; ++k) {
            const Index j = indices[k];
            Vec3 rij = x - xj[j];
            list.periodic->minimumImage(rij);
            f(k, j, rij, rij.squaredNorm());
        }
        return;
    }
    for (std::size_t k = begin; k != end; ++k) {
        const Index j = indices[k];
        const Vec3 rij = x - xj[j];
        f(k, j, rij, rij.squaredNorm());
    }
}

// f(j, r_ij, r²) for every neighbour j of particle i in 'list' (forEachNeighbourPair).
template <class F>
inline void forEachNeighbour(const NeighbourList& list, const std::vector<Vec3>& xi,
                             const std::vector<Vec3>& xj, std::size_t i, F&& f) {
    forEachNeighbourPair(list, xi, xj, i, [&](std::size_t, Index j, const Vec3& rij, Scalar r2) { f(j, rij, r2); });
}

// One neighbour as the loop hands it to a term.
struct Pair {
    Index j;         // the neighbour, in its system
    Vec3 r;          // x_i − x_j (nearest periodic image)
    Scalar r2;       // |r|²
    Vec3 gradW;      // ∇_i W_ij (terms with usesGradient; else zero)
    Scalar W;        // W_ij (terms with usesKernel; else zero)
    Scalar dampedGradFactor; // ∇_i W_ij/(r² + η²) = r · this, η² = 0.01 h² (usesDampedGradient; else zero)
    std::size_t k;   // the pair's place in its list (for data kept per pair)
};

// A wall system's data as the pair terms read it (pointers into its fields).
struct WallView {
    const Vec3* x;             // positions
    const Vec3* v;             // its own velocity (zero when fixed)
    const Vec3* vViscous;      // the velocity viscous terms see (Adami's no-slip extrapolation, or v)
    const Scalar* mass;        // M_b of the boundary model
    const Scalar* p;           // its own pressure and density (when not mirrored)
    const Scalar* rho;
    bool mirrored;             // pressure and density are those of the fluid particle i
    bool moving;               // v is not zero (a wall with a motion)
};

// A wall neighbour: the pair, and the wall it belongs to.
struct WallPair : Pair {
    const WallView& wall;
    Scalar mass() const { return wall.mass[j]; }
};

inline WallView viewOf(const WallSystem& w) {
    return {w.particles.position().data(), w.particles.velocity().data(), w.velocitySeenByViscosity().data(),
            w.mass ? w.mass->data() : nullptr, w.particles.pressure().data(), w.particles.density().data(),
            w.pressureMirrored, w.moving()};
}

namespace detail {
template <class Term>
concept HasWallTerm = requires(const Term& t, const typename Term::Particle& pi, const WallPair& p,
                               typename Term::Sum& s) { t.wall(pi, p, s); };
template <class Term> constexpr bool usesGradient() {
    if constexpr (requires { Term::usesGradient; }) return Term::usesGradient;
    else return false;
}
template <class Term> constexpr bool usesKernel() {
    if constexpr (requires { Term::usesKernel; }) return Term::usesKernel;
    else return false;
}
template <class Term> constexpr bool usesDampedGradient() {
    if constexpr (requires { Term::usesDampedGradient; }) return Term::usesDampedGradient;
    else return false;
}
// What a term asks of the kernel for one pair: ∇_i W_ij, W_ij, the damped gradient factor (each
// zero when not asked for), from one table lookup (the values not asked for are never computed).
// withGradient false: the caller has the gradient (the scene's cache). Always inlined, as the
// table's lookup: called, it computes every value (GCC called both in dfsph's two-term pass).
struct PairKernel {
    Vec3 gradW;
    Scalar W, dampedGradFactor;
};
template <class Term, bool withGradient = true>
[[gnu::always_inline]] inline PairKernel pairKernel(const KernelTable& kt, const Vec3& rij, Scalar r2) {
    constexpr bool g = withGradient && usesGradient<Term>(), w = usesKernel<Term>(), d = usesDampedGradient<Term>();
    if constexpr (!g && !w && !d) {
        return {Vec3::Zero(), 0, 0};
    } else {
        const KernelTable::Values v = kt.valuesSq(r2);
        return {g ? Vec3(rij * v.gradFactor) : Vec3::Zero(), w ? v.W : Scalar(0), d ? v.dampedGradFactor : Scalar(0)};
    }
}
// A zero sum: Sum{} for scalars and structs, Zero() for Eigen vectors (whose default
// constructor leaves them uninitialised).
template <class Sum> Sum zeroSum() {
    if constexpr (requires { Sum::Zero(); }) return Sum::Zero();
    else return Sum{};
}
template <class Term> constexpr bool visitsFluid() {
    if constexpr (requires { Term::visitsFluid; }) return Term::visitsFluid;
    else return true;
}
} // namespace detail

// Calls out(i, particle_i, Σ) for every fluid particle i, Σ = Σ_j term.fluid + Σ_walls Σ_b
// term.wall, at fluid positions x. The pair gradients come from the scene's cache when it holds
// them for x (the fluid's own positions and the current lists), else from the kernel table.
template <class Term, class Out>
void forEachPairSum(const Scene& s, const std::vector<Vec3>& x, const Term& term, Out&& out) {
    using Sum = typename Term::Sum;
    constexpr bool gradient = detail::usesGradient<Term>();
    constexpr bool walls = detail::HasWallTerm<Term>;
    static_assert(sizeof(Term) <= 256, "a pair term is a few pointers and numbers (copied per particle)");
    const KernelTable* kt = &s.kernel;
    const NeighbourList& ff = s.search.fluidNeighbours();
    // the walls that take part (those with a boundary model's masses): what their loops read,
    // gathered once per call rather than once per particle
    struct WallLoop {
        WallView view;
        const std::vector<Vec3>* x;
        const NeighbourList* list;
    };
    std::array<WallLoop, NeighbourSearch::maxLists> wallLoops;
    std::size_t wallCount = 0;
    bool wallsWanted = walls;
    if constexpr (requires { term.visitsWalls; }) wallsWanted = walls && term.visitsWalls;
    if (wallsWanted)
        for (std::size_t k = 0; k < s.walls.size(); ++k)
            if (s.walls[k].mass)
                wallLoops[wallCount++] = {viewOf(s.walls[k]), &s.walls[k].particles.position(), &s.search.wallNeighbours(k)};
    const Vec3* cached = gradient && &x == &s.fluid.position() && s.gradients.validFor(s.search)
                             ? s.gradients.values.data()
                             : nullptr;
    const auto pass = [&](auto fluidKernel) {
        forEachParticleBalanced(s.search, [&](std::size_t i) {
            // the term and the kernel lookup as copies local to the particle: nothing in its pair
            // loops can change them, so they stay in registers (read through the captured
            // references, the compiler reloaded the term's pointers and the table's address every pair)
            const Term t = term;
            const auto kernel = fluidKernel;
            const KernelTable& table = *kt;
            const auto pi = t.particle(i);
            Sum sum = detail::zeroSum<Sum>();
            if constexpr (detail::visitsFluid<Term>())
                forEachNeighbourPair(ff, x, x, i, [&](std::size_t k, Index j, const Vec3& rij, Scalar r2) {
                    const detail::PairKernel w = kernel(table, k, rij, r2);
                    t.fluid(pi, Pair{j, rij, r2, w.gradW, w.W, w.dampedGradFactor, k}, sum);
                });
            if constexpr (walls)
                for (std::size_t w = 0; w < wallCount; ++w) {
                    const WallLoop& loop = wallLoops[w];
                    forEachNeighbourPair(*loop.list, x, *loop.x, i, [&](std::size_t k, Index b, const Vec3& rib, Scalar r2) {
                        const detail::PairKernel w = detail::pairKernel<Term>(table, rib, r2);
                        t.wall(pi, WallPair{{b, rib, r2, w.gradW, w.W, w.dampedGradFactor, k}, loop.view}, sum);
                    });
                }
            out(i, pi, sum);
        }, wallCount > 0 ? NeighbourSearch::PairWork::FluidAndWall : NeighbourSearch::PairWork::Fluid);
    };
    if (cached)
        pass([cached](const KernelTable& table, std::size_t k, const Vec3& rij, Scalar r2) {
            detail::PairKernel w = detail::pairKernel<Term, false>(table, rij, r2);
            w.gradW = cached[k];
            return w;
        });
    else
        pass([](const KernelTable& table, std::size_t, const Vec3& rij, Scalar r2) {
            return detail::pairKernel<Term>(table, rij, r2);
        });
}

// out(i, particle_i, Σ) for every fluid particle, Σ = Σ_j term.cached(particle_i, j, ∇W_ij) over
// its fluid neighbours with the scene's cached gradients (they must be valid): no positions are
// read, for solvers that linearise about the positions of one search (dfsph). A term with
// visits(i) is summed (and out called) only for the particles it visits.
template <class Term, class Out> void forEachCachedPairSum(const Scene& s, const Term& term, Out&& out) {
    using Sum = typename Term::Sum;
    const NeighbourList& ff = s.search.fluidNeighbours();
    const Vec3* g = s.gradients.values.data();
    forEachParticleBalanced(s.search, [&](std::size_t i) {
        const Term t = term; // a local copy, kept in registers (forEachPairSum)
        if constexpr (requires { t.visits(i); })
            if (!t.visits(i)) return;
        const auto pi = t.particle(i);
        Sum sum = detail::zeroSum<Sum>();
        for (std::uint32_t k = ff.offsets[i]; k < ff.offsets[i + 1]; ++k) t.cached(pi, ff.indices[k], g[k], sum);
        out(i, pi, sum);
    }, NeighbourSearch::PairWork::Fluid);
}

// a_i += Σ of the term (Sum = Vec3) for every fluid particle, at the fluid's positions.
template <class Term> void addPairAcceleration(Scene& s, const Term& term) {
    auto& a = s.fluid.acceleration();
    forEachPairSum(s, s.fluid.position(), term, [&](std::size_t i, const auto&, const Vec3& sum) { a[i] += sum; });
}

// Summation density ρ_i = m (W(0) + Σ_j W_ij) + Σ_walls Σ_b M_b W_ib at positions x.
struct SummationDensityTerm {
    struct Sum {
        Scalar fluid = 0, wall = 0; // Σ_j W_ij, Σ_b M_b W_ib
    };
    static constexpr bool usesKernel = true;
    struct Particle {};
    Particle particle(std::size_t) const { return {}; }
    void fluid(const Particle&, const Pair& p, Sum& sum) const { sum.fluid += p.W; }
    void wall(const Particle&, const WallPair& p, Sum& sum) const { sum.wall += p.mass() * p.W; }
};
inline void summationDensity(const Scene& s, const std::vector<Vec3>& x, std::vector<Scalar>& rho) {
    const Scalar m = s.fluid.particleMass(), w0 = s.kernel.W0();
    rho.resize(x.size());
    forEachPairSum(s, x, SummationDensityTerm{}, [&](std::size_t i, const auto&, const auto& sum) {
        rho[i] = m * (w0 + sum.fluid) + sum.wall;
    });
}

// The continuity equation (Monaghan 1992): dρ_i/dt = Σ_j m (v_i − v_j)·∇_i W_ij + Σ_b M_b (v_i − v_b)·∇_i W_ib,
// v_b the wall's own velocity (zero when fixed), at the fluid's positions.
struct ContinuityTerm {
    struct Sum {
        Scalar fluid = 0, wall = 0; // Σ_j (v_i − v_j)·∇W_ij, Σ_b M_b (v_i − v_b)·∇W_ib
    };
    static constexpr bool usesGradient = true;
    using Particle = Vec3; // v_i
    const Vec3* v;
    Particle particle(std::size_t i) const { return v[i]; }
    void fluid(const Vec3& vi, const Pair& p, Sum& sum) const { sum.fluid += (vi - v[p.j]).dot(p.gradW); }
    void wall(const Vec3& vi, const WallPair& p, Sum& sum) const { sum.wall += p.mass() * (vi - p.wall.v[p.j]).dot(p.gradW); }
};
inline void continuityDensityRate(const Scene& s, std::vector<Scalar>& rate) {
    const Scalar m = s.fluid.particleMass();
    rate.resize(s.fluid.size());
    forEachPairSum(s, s.fluid.position(), ContinuityTerm{s.fluid.velocity().data()},
                   [&](std::size_t i, const auto&, const auto& sum) { rate[i] = m * sum.fluid + sum.wall; });
}

// Two pair terms summed in one pass over the pairs (each pair's kernel values looked up once),
// for models that add to a core term (a density diffusion to the continuity equation): Sum and
// Particle hold each term's own; a wall pair goes to the terms that have a wall().
template <class A, class B> struct TwoTerms {
    static_assert(detail::visitsFluid<A>() && detail::visitsFluid<B>(), "TwoTerms: terms that visit the fluid");
    struct Sum {
        typename A::Sum a = detail::zeroSum<typename A::Sum>();
        typename B::Sum b = detail::zeroSum<typename B::Sum>();
    };
    struct Particle {
        typename A::Particle a;
        typename B::Particle b;
    };
    static constexpr bool usesGradient = detail::usesGradient<A>() || detail::usesGradient<B>();
    static constexpr bool usesKernel = detail::usesKernel<A>() || detail::usesKernel<B>();
    static constexpr bool usesDampedGradient = detail::usesDampedGradient<A>() || detail::usesDampedGradient<B>();
    A first;
    B second;
    Particle particle(std::size_t i) const { return {first.particle(i), second.particle(i)}; }
    void fluid(const Particle& pi, const Pair& p, Sum& sum) const {
        first.fluid(pi.a, p, sum.a);
        second.fluid(pi.b, p, sum.b);
    }
    void wall(const Particle& pi, const WallPair& p, Sum& sum) const
        requires(detail::HasWallTerm<A> || detail::HasWallTerm<B>)
    {
        if constexpr (detail::HasWallTerm<A>) first.wall(pi.a, p, sum.a);
        if constexpr (detail::HasWallTerm<B>) second.wall(pi.b, p, sum.b);
    }
};

// The continuity equation with a density diffusion term D (Sum = Scalar, fluid pairs) in the
// same pass: rate_i = m Σ_j (v_i − v_j)·∇W_ij + Σ_b M_b (v_i − v_b)·∇W_ib + scale Σ_j D_ij.
template <class Diffusion>
inline void continuityDensityRate(const Scene& s, std::vector<Scalar>& rate, const Diffusion& diffusion, Scalar scale) {
    const Scalar m = s.fluid.particleMass();
    rate.resize(s.fluid.size());
    forEachPairSum(s, s.fluid.position(), TwoTerms<ContinuityTerm, Diffusion>{{s.fluid.velocity().data()}, diffusion},
                   [&](std::size_t i, const auto&, const auto& sum) {
                       rate[i] = m * sum.a.fluid + sum.a.wall + scale * sum.b;
                   });
}

// The symmetric pressure acceleration from q = p/ρ² (Monaghan 1992):
//   a_i = −Σ_j m (q_i + q_j) ∇_i W_ij − Σ_b M_b (q_i + q_b) ∇_i W_ib,
// q_b = q_i on a wall that mirrors the fluid's pressure, else its own p_b/ρ_b².
struct SymmetricPressureTerm {
    struct Sum {
        Vec3 fluid = Vec3::Zero(), wall = Vec3::Zero(); // Σ_j (q_i + q_j) ∇W_ij, Σ_b M_b (q_i + q_b) ∇W_ib
    };
    static constexpr bool usesGradient = true;
    using Particle = Scalar; // q_i
    const Scalar* q;
    Particle particle(std::size_t i) const { return q[i]; }
    void fluid(Scalar qi, const Pair& p, Sum& sum) const { sum.fluid += (qi + q[p.j]) * p.gradW; }
    void wall(Scalar qi, const WallPair& p, Sum& sum) const {
        const Scalar qb = p.wall.mirrored ? qi : p.wall.p[p.j] / (p.wall.rho[p.j] * p.wall.rho[p.j]);
        sum.wall += (p.mass() * (qi + qb)) * p.gradW;
    }
};

// out(i, a_i) with a_i the symmetric pressure acceleration of q = p/ρ² at positions x ('out'
// lets a solver use a_i in the same pass: PCISPH predicts the next positions with it).
template <class Out>
inline void symmetricPressureAcceleration(const Scene& s, const std::vector<Vec3>& x, const Scalar* q, Out&& out) {
    const Scalar m = s.fluid.particleMass();
    forEachPairSum(s, x, SymmetricPressureTerm{q}, [&](std::size_t i, const auto&, const auto& sum) {
        out(i, Vec3(-(m * sum.fluid + sum.wall)));
    });
}

// a_i += the symmetric pressure acceleration of p and ρ at the fluid's positions. p/ρ² is taken
// once per particle (in 'pOverRho2', the caller's scratch storage), not once per pair.
inline void addSymmetricPressureAcceleration(Scene& s, std::vector<Scalar>& pOverRho2) {
    const auto& p = s.fluid.pressure();
    const auto& rho = s.fluid.density();
    const std::size_t n = p.size();
    pOverRho2.resize(n);
    Scalar* q = pOverRho2.data();
#pragma omp parallel for schedule(static)
    for (std::size_t i = 0; i < n; ++i) q[i] = p[i] / (rho[i] * rho[i]);
    auto& a = s.fluid.acceleration();
    symmetricPressureAcceleration(s, s.fluid.position(), q, [&](std::size_t i, const Vec3& ai) { a[i] += ai; });
}

} // namespace spindrift
