// Spindrift — the pair loop, written once: every particle i of a query system (a fluid, or a
// passive system) against its neighbours j in every source system it interacts with (its own
// system, the other fluids, the walls and bodies), on the step's neighbour lists, in the
// balanced parallel schedule of the search (forEachParticleBalanced), with the boundaries'
// masses and the cached pair gradients. A model supplies only a pair term: what one neighbour
// contributes.
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
//       void fluid(const Particle&, const Pair&, Sum&) const;     // neighbour j of its own fluid
//       void wall(const Particle&, const WallPair&, Sum&) const;  // particle b of a wall or body
//   };
//   addPairAcceleration(scene, fluid, ViscousTerm{...});   // a_i += Σ, or
//   forEachPairSum(scene, fluid, x, term, [&](std::size_t i, const Particle& pi, const Sum& sum) { ... });
//
// The pair names its source system (Pair::src: its number, role and the fields every term may
// read: positions, velocities, density, pressure, masses), so a contribution can be attributed
// to the system it comes from. A term's fluid() is called for the neighbours in the query's own
// system; for those in another fluid system only when the term declares `static constexpr bool
// visitsOtherFluids = true` (it then reads neighbour j through p.src alone, never through arrays
// of its own system). A term without a wall() member leaves the boundaries out, as does one whose
// `bool visitsWalls` member is false at run time (a wallFactor of 0); one with `static constexpr
// bool visitsFluid = false` visits only the boundaries (its fluid() is never called). The loop
// reads the query's positions x (its own or predicted ones, e.g. PCISPH's); the boundaries are
// where their motion puts them at the evaluation's time. Results are bit for bit independent of
// the thread count: each i is summed by one thread in list order.
#pragma once

#include "Reactions.hpp"
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

// A source system as pair terms read it (pointers into its fields).
struct SourceView {
    std::size_t system;        // its number (Scene::systems)
    SystemRole role;
    const Vec3* x;             // positions
    const Vec3* v;             // its own velocity (zero for a fixed wall)
    const Vec3* vViscous;      // the velocity viscous terms see (Adami's no-slip extrapolation, or v)
    const Scalar* mass;        // a boundary's M_b of the boundary model (null for a fluid)
    Scalar particleMass;       // a fluid's particle mass
    const Scalar* p;           // pressure and density (a boundary's own, when not mirrored)
    const Scalar* rho;
    bool mirrored;             // a boundary whose pressure and density are those of the fluid particle i
    bool moving;               // a boundary whose v is not zero (a wall with a motion, a body)
    const Vec3* normal;        // a single layer's surface normals (ParticleSystem::surfaceNormal), else null
    Scalar surfaceSpacing;     // and its sampling radius
};

inline SourceView viewOf(const ParticleSystem& p) {
    const ParticleSet& set = p.particles;
    return {p.index,
            p.role,
            set.position().data(),
            set.velocity().data(),
            p.velocitySeenByViscosity().data(),
            p.mass ? p.mass->data() : nullptr,
            set.particleMass(),
            set.pressure().data(),
            set.density().data(),
            p.pressureMirrored,
            p.movingBoundary(),
            p.surfaceNormal ? p.surfaceNormal->data() : nullptr,
            p.surfaceSpacing};
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
    const SourceView& src; // the system j belongs to
};

// A boundary neighbour (a wall or body particle b).
struct WallPair : Pair {
    Scalar mass() const { return src.mass[j]; } // M_b
};

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
template <class Term> constexpr bool visitsOtherFluids() {
    if constexpr (requires { Term::visitsOtherFluids; }) return Term::visitsOtherFluids;
    else return false;
}
} // namespace detail

// Calls out(i, particle_i, Σ) for every particle i of the query system, Σ = Σ_j term.fluid over
// its own system (and the other fluids, for a term that visits them) + Σ_boundaries Σ_b
// term.wall, at the query's positions x. The pair gradients of its own list come from the
// system's cache when it holds them for x (the system's own positions and the current lists),
// else from the kernel table.
template <class Term, class Out>
void forEachPairSum(const Scene& s, const ParticleSystem& query, const std::vector<Vec3>& x, const Term& term, Out&& out) {
    using Sum = typename Term::Sum;
    constexpr bool gradient = detail::usesGradient<Term>();
    constexpr bool walls = detail::HasWallTerm<Term>;
    constexpr bool otherFluids = detail::visitsFluid<Term>() && detail::visitsOtherFluids<Term>();
    static_assert(sizeof(Term) <= 256, "a pair term is a few pointers and numbers (copied per particle)");
    const KernelTable* kt = &s.kernel;
    const QueryLists& q = s.search.of(query.index);
    const NeighbourList* own = q.hasOwn() ? &q.own() : nullptr;
    const SourceView ownView = viewOf(query);
    // the other sources that take part (boundaries with a boundary model's masses; other fluids
    // for a term that visits them): what their loops read, gathered once per call rather than
    // once per particle
    struct SourceLoop {
        SourceView view;
        const std::vector<Vec3>* x;
        const NeighbourList* list;
    };
    std::array<SourceLoop, NeighbourSearch::maxLists> boundaryLoops, fluidLoops;
    std::size_t boundaryCount = 0, fluidCount = 0;
    bool wallsWanted = walls;
    if constexpr (requires { term.visitsWalls; }) wallsWanted = walls && term.visitsWalls;
    for (std::size_t k = 0; k < q.sourceCount(); ++k) {
        const ParticleSystem& src = s.system(q.source(k));
        if (src.index == query.index) continue;
        if (wallsWanted && src.isBoundary() && src.mass)
            boundaryLoops[boundaryCount++] = {viewOf(src), &src.particles.position(), &q.list(k)};
        else if (otherFluids && src.isFluid())
            fluidLoops[fluidCount++] = {viewOf(src), &src.particles.position(), &q.list(k)};
    }
    const Vec3* cached = gradient && own && &x == &query.particles.position() && query.gradients.validFor(q)
                             ? query.gradients.values.data()
                             : nullptr;
    const auto pass = [&](auto ownKernel) {
        forEachParticleBalanced(q, [&](std::size_t i) {
            // the term and the kernel lookup as copies local to the particle: nothing in its pair
            // loops can change them, so they stay in registers (read through the captured
            // references, the compiler reloaded the term's pointers and the table's address every pair)
            const Term t = term;
            const auto kernel = ownKernel;
            const KernelTable& table = *kt;
            const auto pi = t.particle(i);
            Sum sum = detail::zeroSum<Sum>();
            if constexpr (detail::visitsFluid<Term>()) {
                if (own)
                    forEachNeighbourPair(*own, x, x, i, [&](std::size_t k, Index j, const Vec3& rij, Scalar r2) {
                        const detail::PairKernel w = kernel(table, k, rij, r2);
                        t.fluid(pi, Pair{j, rij, r2, w.gradW, w.W, w.dampedGradFactor, k, ownView}, sum);
                    });
                if constexpr (otherFluids)
                    for (std::size_t f = 0; f < fluidCount; ++f) {
                        const SourceLoop& loop = fluidLoops[f];
                        forEachNeighbourPair(*loop.list, x, *loop.x, i, [&](std::size_t k, Index j, const Vec3& rij, Scalar r2) {
                            const detail::PairKernel w = detail::pairKernel<Term>(table, rij, r2);
                            t.fluid(pi, Pair{j, rij, r2, w.gradW, w.W, w.dampedGradFactor, k, loop.view}, sum);
                        });
                    }
            }
            if constexpr (walls)
                for (std::size_t w = 0; w < boundaryCount; ++w) {
                    const SourceLoop& loop = boundaryLoops[w];
                    forEachNeighbourPair(*loop.list, x, *loop.x, i, [&](std::size_t k, Index b, const Vec3& rib, Scalar r2) {
                        const detail::PairKernel w = detail::pairKernel<Term>(table, rib, r2);
                        t.wall(pi, WallPair{{b, rib, r2, w.gradW, w.W, w.dampedGradFactor, k, loop.view}}, sum);
                    });
                }
            out(i, pi, sum);
        }, boundaryCount + fluidCount > 0 ? QueryLists::PairWork::All : QueryLists::PairWork::Own);
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

// The reactions of a term's boundary pairs (Reactions.hpp), for every boundary system the fluid
// interacts with whose reactions are wanted: F = Σ_i Σ_b −m_i a_ib and M_O = Σ x_b × (−m_i a_ib),
// a_ib = accelerationOf(i, particle_i, pair) the acceleration the term gives fluid particle i
// from boundary particle b (for a term whose result is a_i += c Σ: c times its wall() of a zero
// sum), at the fluid's positions x (those of its final pass). Added to 'reactions' as 'kind'.
template <class Term, class Acceleration>
void addReactions(const Scene& s, const ParticleSystem& fluid, const std::vector<Vec3>& x, const Term& term,
                  Acceleration&& accelerationOf, ForceKind kind, Reactions& reactions) {
    using V3 = Wrench::V3;
    const QueryLists& q = s.listsOf(fluid);
    const double m = fluid.particles.particleMass();
    const KernelTable& table = s.kernel;
    const std::size_t n = q.size();
    std::vector<V3> force, moment;
    for (std::size_t k = 0; k < q.sourceCount(); ++k) {
        const ParticleSystem& boundary = s.system(q.source(k));
        if (!boundary.isBoundary() || !boundary.mass || !reactions.wanted(boundary.index)) continue;
        const SourceView view = viewOf(boundary);
        const std::vector<Vec3>& xb = boundary.particles.position();
        const NeighbourList& list = q.list(k);
        force.assign(n, V3::Zero());
        moment.assign(n, V3::Zero());
        forEachParticleBalanced(q, [&](std::size_t i) {
            const Term t = term;
            const auto pi = t.particle(i);
            V3 f = V3::Zero(), mo = V3::Zero();
            forEachNeighbourPair(list, x, xb, i, [&](std::size_t k, Index b, const Vec3& rib, Scalar r2) {
                const detail::PairKernel w = detail::pairKernel<Term>(table, rib, r2);
                const Vec3 a = accelerationOf(i, pi, WallPair{{b, rib, r2, w.gradW, w.W, w.dampedGradFactor, k, view}});
                const V3 fb = -m * a.template cast<double>();
                f += fb;
                mo += xb[b].template cast<double>().cross(fb);
            });
            force[i] = f;
            moment[i] = mo;
        });
        Wrench w;
        w.force = deterministicSum<V3>(n, [&](std::size_t i) { return force[i]; });
        w.moment = deterministicSum<V3>(n, [&](std::size_t i) { return moment[i]; });
        reactions.add(boundary.index, kind, w);
    }
}

// out(i, particle_i, Σ) for every particle of the query system, Σ = Σ_j term.cached(particle_i, j,
// ∇W_ij) over its own neighbours with the system's cached gradients (they must be valid): no
// positions are read, for solvers that linearise about the positions of one search (dfsph). A
// term with visits(i) is summed (and out called) only for the particles it visits.
template <class Term, class Out>
void forEachCachedPairSum(const Scene& s, const ParticleSystem& query, const Term& term, Out&& out) {
    using Sum = typename Term::Sum;
    const QueryLists& q = s.search.of(query.index);
    const NeighbourList& own = q.own();
    const Vec3* g = query.gradients.values.data();
    forEachParticleBalanced(q, [&](std::size_t i) {
        const Term t = term; // a local copy, kept in registers (forEachPairSum)
        if constexpr (requires { t.visits(i); })
            if (!t.visits(i)) return;
        const auto pi = t.particle(i);
        Sum sum = detail::zeroSum<Sum>();
        for (std::uint32_t k = own.offsets[i]; k < own.offsets[i + 1]; ++k) t.cached(pi, own.indices[k], g[k], sum);
        out(i, pi, sum);
    }, QueryLists::PairWork::Own);
}

// a_i += Σ of the term (Sum = Vec3) for every particle of the fluid, at its positions.
template <class Term> void addPairAcceleration(Scene& s, ParticleSystem& fluid, const Term& term) {
    auto& a = fluid.particles.acceleration();
    forEachPairSum(s, fluid, fluid.particles.position(), term,
                   [&](std::size_t i, const auto&, const Vec3& sum) { a[i] += sum; });
}

// Summation density ρ_i = m (W(0) + Σ_j W_ij) + Σ_boundaries Σ_b M_b W_ib at positions x.
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
inline void summationDensity(const Scene& s, const ParticleSystem& fluid, const std::vector<Vec3>& x,
                             std::vector<Scalar>& rho) {
    const Scalar m = fluid.particles.particleMass(), w0 = s.kernel.W0();
    rho.resize(x.size());
    forEachPairSum(s, fluid, x, SummationDensityTerm{}, [&](std::size_t i, const auto&, const auto& sum) {
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
    void wall(const Vec3& vi, const WallPair& p, Sum& sum) const { sum.wall += p.mass() * (vi - p.src.v[p.j]).dot(p.gradW); }
};
inline void continuityDensityRate(const Scene& s, const ParticleSystem& fluid, std::vector<Scalar>& rate) {
    const Scalar m = fluid.particles.particleMass();
    rate.resize(fluid.size());
    forEachPairSum(s, fluid, fluid.particles.position(), ContinuityTerm{fluid.particles.velocity().data()},
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
inline void continuityDensityRate(const Scene& s, const ParticleSystem& fluid, std::vector<Scalar>& rate,
                                  const Diffusion& diffusion, Scalar scale) {
    const Scalar m = fluid.particles.particleMass();
    rate.resize(fluid.size());
    forEachPairSum(s, fluid, fluid.particles.position(),
                   TwoTerms<ContinuityTerm, Diffusion>{{fluid.particles.velocity().data()}, diffusion},
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
        const Scalar qb = p.src.mirrored ? qi : p.src.p[p.j] / (p.src.rho[p.j] * p.src.rho[p.j]);
        sum.wall += (p.mass() * (qi + qb)) * p.gradW;
    }
};

// out(i, a_i) with a_i the symmetric pressure acceleration of q = p/ρ² at positions x ('out'
// lets a solver use a_i in the same pass: PCISPH predicts the next positions with it).
template <class Out>
inline void symmetricPressureAcceleration(const Scene& s, const ParticleSystem& fluid, const std::vector<Vec3>& x,
                                          const Scalar* q, Out&& out) {
    const Scalar m = fluid.particles.particleMass();
    forEachPairSum(s, fluid, x, SymmetricPressureTerm{q}, [&](std::size_t i, const auto&, const auto& sum) {
        out(i, Vec3(-(m * sum.fluid + sum.wall)));
    });
}

// The reactions of the symmetric pressure term of q = p/ρ² at positions x: a_ib = −M_b (q_i + q_b) ∇W_ib.
inline void addSymmetricPressureReactions(const Scene& s, const ParticleSystem& fluid, const std::vector<Vec3>& x,
                                          const Scalar* q, Reactions& reactions) {
    const SymmetricPressureTerm term{q};
    addReactions(s, fluid, x, term, [&](std::size_t, Scalar qi, const WallPair& p) {
        SymmetricPressureTerm::Sum c;
        term.wall(qi, p, c);
        return Vec3(-c.wall);
    }, ForceKind::pressure, reactions);
}

// The reactions of a pressure that acts from the boundaries on one side only, a_ib = −M_b q_i ∇W_ib
// with q_i the fluid particle's own (dfsph's wall term, the position-based solvers' correction
// as an acceleration), at positions x.
struct OneSidedWallPressureTerm {
    using Sum = Vec3;
    static constexpr bool usesGradient = true, visitsFluid = false;
    using Particle = Scalar; // q_i
    const Scalar* q;
    Particle particle(std::size_t i) const { return q[i]; }
    void wall(Scalar qi, const WallPair& p, Sum& sum) const { sum -= (p.mass() * qi) * p.gradW; }
};
inline void addOneSidedWallPressureReactions(const Scene& s, const ParticleSystem& fluid, const std::vector<Vec3>& x,
                                             const Scalar* q, Reactions& reactions) {
    const OneSidedWallPressureTerm term{q};
    addReactions(s, fluid, x, term, [&](std::size_t, Scalar qi, const WallPair& p) {
        Vec3 c = Vec3::Zero();
        term.wall(qi, p, c);
        return c;
    }, ForceKind::pressure, reactions);
}

// The reactions of a term whose result is a_i += scale Σ (Sum = Vec3): a_ib = scale × its wall
// contribution.
template <class Term>
void addScaledReactions(const Scene& s, const ParticleSystem& fluid, const Term& term, Scalar scale, ForceKind kind,
                        Reactions& reactions) {
    addReactions(s, fluid, fluid.particles.position(), term, [&](std::size_t, const auto& pi, const WallPair& p) {
        Vec3 c = Vec3::Zero();
        term.wall(pi, p, c);
        return Vec3(scale * c);
    }, kind, reactions);
}

// q_i = p_i/ρ_i² of every particle of the fluid (taken once per particle, not once per pair).
inline void pressureOverDensitySquared(const ParticleSystem& fluid, std::vector<Scalar>& q) {
    const auto& p = fluid.particles.pressure();
    const auto& rho = fluid.particles.density();
    q.resize(p.size());
    Scalar* out = q.data();
    forEachIndex(p.size(), [&](std::size_t i) { out[i] = p[i] / (rho[i] * rho[i]); });
}

// a_i += the symmetric pressure acceleration of p and ρ at the fluid's positions (p/ρ² in
// 'pOverRho2', the caller's scratch storage).
inline void addSymmetricPressureAcceleration(Scene& s, ParticleSystem& fluid, std::vector<Scalar>& pOverRho2) {
    pressureOverDensitySquared(fluid, pOverRho2);
    auto& a = fluid.particles.acceleration();
    symmetricPressureAcceleration(s, fluid, fluid.particles.position(), pOverRho2.data(),
                                  [&](std::size_t i, const Vec3& ai) { a[i] += ai; });
}

} // namespace spindrift
