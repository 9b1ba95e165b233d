// NeighbourSearch: same neighbours as a brute-force search, for any thread count, including
// points outside the grid's domain (clamped into border cells). Most tests search a fluid
// (system 0, against itself) and walls (systems 1, 2, ...: the fluid's neighbours among them),
// declared as the scene declares them (FluidAndWalls).
#include "NeighbourSearch.hpp"
#include "TestSupport.hpp"

#include <gtest/gtest.h>
#include <algorithm>
#include <random>
#include <set>
#ifdef _OPENMP
#include <omp.h>
#endif

using namespace spindrift;

namespace {

std::vector<Vec3> randomPoints(std::size_t n, int dim, Scalar extent, unsigned seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<Scalar> u(-0.1 * extent, 1.1 * extent); // some outside the domain
    std::vector<Vec3> p(n);
    for (auto& x : p) x = Vec3(u(rng), u(rng), dim == 3 ? u(rng) : Scalar(0));
    return p;
}

std::set<Index> bruteForce(const std::vector<Vec3>& pts, const Vec3& x, Scalar h, long self) {
    std::set<Index> out;
    for (std::size_t j = 0; j < pts.size(); ++j)
        if (long(j) != self && (x - pts[j]).squaredNorm() < h * h) out.insert(Index(j));
    return out;
}

// A search over a fluid (system 0, with its own list) and wall systems (1, 2, ...; the fluid
// against each), with the particles' positions given at each build.
class FluidAndWalls {
public:
    void setup(Scalar h, int dim, const Vec3& lo, const Vec3& hi, const Periodicity& periodic = {}) {
        search.setup(h, dim, lo, hi, periodic);
        search.addSystem(&fluid_, false);
        search.addInteraction(0, 0);
    }
    struct Wall {
        const std::vector<Vec3>* positions;
        bool moving;
    };
    void setWalls(const std::vector<Wall>& walls) {
        for (const Wall& w : walls) {
            const std::size_t k = search.addSystem(w.positions, !w.moving);
            search.addInteraction(0, k);
        }
    }
    void build(const std::vector<Vec3>& points) {
        fluid_ = points;
        search.positionsChanged(0);
        search.build();
    }
    void buildAhead(const std::vector<Vec3>& points) { search.buildAhead(0, points); }
    bool builtAt(const std::vector<Vec3>& points) const { return search.builtAt(0, points); }
    void permute(const std::vector<Index>& order) {
        search.permute(0, order);
        permuteVector(fluid_, order);
    }
    const QueryLists& lists() const { return search.of(0); }
    const NeighbourList& fluidNeighbours() const { return search.neighbours(0, 0); }
    const NeighbourList& wallNeighbours(std::size_t k) const { return search.neighbours(0, k + 1); }
    const NeighbourList& wallFluidNeighbours(std::size_t k) const { return search.reverseNeighbours(0, k + 1); }
    NeighbourList wallWallList(std::size_t k, std::size_t l) const { return search.listBetween(k + 1, l + 1); }
    std::size_t wallCount() const { return search.systemCount() - 1; }
    const UniformGrid& fluidGrid() const { return search.grid(0); }
    const UniformGrid& wallGrid(std::size_t k) const { return search.grid(k + 1); }
    std::vector<Index> sortOrder(const std::vector<Vec3>& points) const { return search.sortOrder(points); }
    auto workRange(int t, int threads, QueryLists::PairWork work = QueryLists::PairWork::All) const {
        return lists().workRange(t, threads, work);
    }
    int workRangeThreads() const { return lists().workRangeThreads(); }
    void recordTime(int t, int threads, QueryLists::PairWork work, std::size_t first, std::size_t last, double seconds) const {
        lists().recordTime(t, threads, work, first, last, seconds);
    }
    const std::vector<double>& threadSpeeds() const { return lists().threadSpeeds(); }
    const std::vector<double>& searchThreadSpeeds() const { return lists().searchThreadSpeeds(); }
    auto searchRange(int t, int threads) const { return lists().searchRange(t, threads); }
    std::uint32_t wallNeighbourCount(std::size_t i) const { return lists().otherNeighbourCount(i); }

    NeighbourSearch search;

private:
    std::vector<Vec3> fluid_;
};

class NeighbourSearchTest : public testing::TestWithParam<int> {};

TEST_P(NeighbourSearchTest, MatchesBruteForce) {
    const int dim = GetParam();
    const Scalar h = 0.07, extent = 1.0;
    const auto fluid = randomPoints(dim == 2 ? 3000 : 6000, dim, extent, 1);
    const auto wall = randomPoints(1000, dim, extent, 2);
    FluidAndWalls search;
    Vec3 hi = Vec3::Constant(extent);
    if (dim == 2) hi[2] = 0;
    search.setup(h, dim, Vec3::Zero(), hi);
    search.setWalls({{&wall, false}});
    search.build(fluid);
    std::size_t pairs = 0;
    for (std::size_t i = 0; i < fluid.size(); ++i) {
        const auto& ff = search.fluidNeighbours();
        std::set<Index> got(ff.begin(i), ff.end(i));
        ASSERT_EQ(got.size(), ff.count(i)) << "duplicate neighbours of " << i;
        ASSERT_EQ(got, bruteForce(fluid, fluid[i], h, long(i))) << "fluid neighbours of " << i;
        const auto& fb = search.wallNeighbours(0);
        std::set<Index> gotB(fb.begin(i), fb.end(i));
        ASSERT_EQ(gotB, bruteForce(wall, fluid[i], h, -1)) << "wall neighbours of " << i;
        pairs += got.size();
    }
    EXPECT_GT(pairs, fluid.size()); // the test is not vacuous
    const NeighbourList bb = search.wallWallList(0, 0);
    for (std::size_t b = 0; b < wall.size(); ++b) {
        std::set<Index> got(bb.begin(b), bb.end(b));
        ASSERT_EQ(got, bruteForce(wall, wall[b], h, long(b)));
    }
}

// The fluid and wall lists are the same for any thread count and any split of the particles
// between the threads: the build's split follows its own measured times from the second build
// at a thread count on, so repeated builds run on different splits.
TEST_P(NeighbourSearchTest, ListsIndependentOfThreadCountAndSplit) {
#ifdef _OPENMP
    const int dim = GetParam();
    const auto pts = randomPoints(5000, dim, 1.0, 3);
    FluidAndWalls search;
    search.setup(0.05, dim, Vec3::Zero(), Vec3(1, 1, dim == 3 ? 1 : 0));
    const auto wall = randomPoints(1000, dim, 1.0, 4);
    search.setWalls({{&wall, false}});
    const int saved = omp_get_max_threads();
    omp_set_num_threads(1);
    search.build(pts);
    const NeighbourList fluidOne = search.fluidNeighbours(), wallOne = search.wallNeighbours(0);
    ASSERT_GT(wallOne.totalPairs(), pts.size() / 10); // not vacuous
    for (int threads : {2, 3}) {
        omp_set_num_threads(threads);
        for (int build = 0; build < 6; ++build) {
            search.build(pts);
            EXPECT_EQ(fluidOne.offsets, search.fluidNeighbours().offsets) << threads << " threads, build " << build;
            EXPECT_EQ(fluidOne.indices, search.fluidNeighbours().indices) << threads << " threads, build " << build;
            EXPECT_EQ(wallOne.offsets, search.wallNeighbours(0).offsets) << threads << " threads, build " << build;
            EXPECT_EQ(wallOne.indices, search.wallNeighbours(0).indices) << threads << " threads, build " << build;
        }
        // the split the next build takes: contiguous ranges tiling the particles, by speeds of mean 1
        std::size_t next = 0;
        for (int t = 0; t < threads; ++t) {
            const auto [first, last] = search.searchRange(t, threads);
            EXPECT_EQ(first, next);
            EXPECT_LE(first, last);
            next = last;
        }
        EXPECT_EQ(next, pts.size());
        const auto& speeds = search.searchThreadSpeeds();
        ASSERT_EQ(int(speeds.size()), threads);
        double sum = 0;
        for (double v : speeds) sum += v;
        EXPECT_NEAR(sum, threads, 1e-9);
    }
    omp_set_num_threads(saved);
#else
    GTEST_SKIP() << "built without OpenMP";
#endif
}

TEST_P(NeighbourSearchTest, SortOrderIsAPermutationAlongTheCurve) {
    const int dim = GetParam();
    const auto pts = randomPoints(2000, dim, 1.0, 4);
    FluidAndWalls search;
    search.setup(0.05, dim, Vec3::Zero(), Vec3(1, 1, dim == 3 ? 1 : 0));
    const auto order = search.sortOrder(pts);
    std::vector<Index> sorted = order;
    std::sort(sorted.begin(), sorted.end());
    for (std::size_t i = 0; i < sorted.size(); ++i) ASSERT_EQ(sorted[i], i);
    for (std::size_t i = 1; i < order.size(); ++i)
        ASSERT_LE(search.fluidGrid().mortonCode(pts[order[i - 1]]), search.fluidGrid().mortonCode(pts[order[i]]));
    // locality: consecutive particles are on average much closer than random pairs
    double consecutive = 0;
    for (std::size_t i = 1; i < order.size(); ++i) consecutive += (pts[order[i]] - pts[order[i - 1]]).norm();
    consecutive /= order.size() - 1;
    EXPECT_LT(consecutive, 0.15);
}

// Relabelling the lists after a re-sort (permute) gives what a build on the re-sorted points
// gives, pair for pair and in the same order: the sort keeps the points of a cell in their
// order. Points on a lattice (many in one cell in a row) and random ones, some outside the domain;
// with and without a periodic axis.
TEST_P(NeighbourSearchTest, PermutedListsEqualABuildOnTheReorderedPoints) {
    const int dim = GetParam();
    const Scalar h = 0.07;
    auto fluid = randomPoints(dim == 2 ? 2000 : 5000, dim, 1.0, 7);
    for (int k = 0; k < 400; ++k) fluid.emplace_back(0.3 + 0.02 * (k % 20), 0.3 + 0.02 * (k / 20), dim == 3 ? 0.5 : 0);
    std::shuffle(fluid.begin(), fluid.end(), std::mt19937(8));
    const auto wall = randomPoints(1000, dim, 1.0, 9);
    const Vec3 hi(1, 1, dim == 3 ? 1 : 0);
    for (bool periodicX : {false, true}) {
        Periodicity periodic;
        periodic.axis[0] = periodicX;
        periodic.length = Vec3(1, 0, 0);
        for (auto& x : fluid) periodic.wrap(x);
        FluidAndWalls relabelled, fresh;
        for (FluidAndWalls* s : {&relabelled, &fresh}) {
            s->setup(h, dim, Vec3::Zero(), hi, periodic);
            s->setWalls({{&wall, false}});
        }
        relabelled.build(fluid);
        const auto order = relabelled.sortOrder(fluid);
        std::vector<Vec3> sorted(fluid.size());
        for (std::size_t i = 0; i < fluid.size(); ++i) sorted[i] = fluid[order[i]];
        relabelled.permute(order);
        fresh.build(sorted);
        EXPECT_EQ(relabelled.fluidNeighbours().offsets, fresh.fluidNeighbours().offsets);
        EXPECT_EQ(relabelled.fluidNeighbours().indices, fresh.fluidNeighbours().indices);
        EXPECT_EQ(relabelled.wallNeighbours(0).offsets, fresh.wallNeighbours(0).offsets);
        EXPECT_EQ(relabelled.wallNeighbours(0).indices, fresh.wallNeighbours(0).indices);
        EXPECT_GT(fresh.fluidNeighbours().totalPairs(), 5 * fluid.size()); // not vacuous
        // the grid too: the same points in the same order around any place
        for (const Vec3& p : {Vec3(0.31, 0.33, dim == 3 ? 0.5 : 0), Vec3(0.5, 0.5, dim == 3 ? 0.5 : 0)}) {
            std::vector<Index> a, b;
            relabelled.fluidGrid().forEachWithin(p, sorted, h, [&](Index j) { a.push_back(j); });
            fresh.fluidGrid().forEachWithin(p, sorted, h, [&](Index j) { b.push_back(j); });
            EXPECT_FALSE(a.empty());
            EXPECT_EQ(a, b);
        }
    }
}

// The threads' particle ranges tile [0, n) in order and carry about equal pair work, although
// the points near the wall (here: the first ones) have many more neighbours; the fluid-only
// ranges carry equal fluid pair work.
TEST(NeighbourSearch, WorkRangesTileTheParticlesWithEqualWork) {
    std::mt19937 rng(6);
    std::uniform_real_distribution<Scalar> u(0, 1);
    std::vector<Vec3> fluid(6000), wall;
    for (auto& p : fluid) p = Vec3(u(rng), u(rng), 0);
    std::sort(fluid.begin(), fluid.end(), [](const Vec3& a, const Vec3& b) { return a[1] < b[1]; });
    for (int k = 0; k < 3; ++k) // a dense wall along y = 0
        for (int i = 0; i < 400; ++i) wall.push_back(Vec3(i / 400.0, -0.005 * k, 0));
    FluidAndWalls search;
    search.setup(0.04, 2, Vec3(0, -0.1, 0), Vec3(1, 1, 0));
    search.setWalls({{&wall, false}});
    search.build(fluid);
    const auto& ff = search.fluidNeighbours();
    const auto& fb = search.wallNeighbours(0);
    for (int threads : {1, 2, 3, 4}) {
        // a range of 'threads' as computed for the thread count of the last build, or an even split
        std::size_t next = 0;
        std::vector<double> work;
        for (int t = 0; t < threads; ++t) {
            const auto [first, last] = search.workRange(t, threads);
            ASSERT_EQ(first, next) << threads << " threads";
            ASSERT_LE(first, last);
            double w = 0;
            for (std::size_t i = first; i < last; ++i) w += ff.count(i) + fb.count(i);
            work.push_back(w);
            next = last;
        }
        EXPECT_EQ(next, fluid.size()) << threads << " threads";
        if (threads == search.workRangeThreads()) {
            const auto [lo, hi] = std::minmax_element(work.begin(), work.end());
            EXPECT_LT(*hi - *lo, 0.05 * *hi) << threads << " threads";
        }
    }
#ifdef _OPENMP
    // balanced for the build's thread count
    const int saved = omp_get_max_threads();
    omp_set_num_threads(2);
    search.build(fluid);
    omp_set_num_threads(saved);
    EXPECT_EQ(search.workRangeThreads(), 2);
    const auto [a0, a1] = search.workRange(0, 2);
    double w0 = 0, w1 = 0;
    for (std::size_t i = a0; i < a1; ++i) w0 += ff.count(i) + fb.count(i);
    for (std::size_t i = a1; i < fluid.size(); ++i) w1 += ff.count(i) + fb.count(i);
    EXPECT_LT(std::abs(w0 - w1), 0.05 * std::max(w0, w1));
    EXPECT_LT(a1, fluid.size() / 2); // the wall's side is the heavier one
    // PairWork::Fluid balances the fluid pairs alone (passes that visit no wall pair)
    const auto [f0, f1] = search.workRange(0, 2, QueryLists::PairWork::Own);
    EXPECT_EQ(f0, 0u);
    EXPECT_EQ(search.workRange(1, 2, QueryLists::PairWork::Own).second, fluid.size());
    double v0 = 0, v1 = 0;
    for (std::size_t i = 0; i < f1; ++i) v0 += ff.count(i);
    for (std::size_t i = f1; i < fluid.size(); ++i) v1 += ff.count(i);
    EXPECT_LT(std::abs(v0 - v1), 0.05 * std::max(v0, v1));
    EXPECT_GT(f1, a1); // the wall pairs no longer weigh on the first range
#endif
}

#ifdef _OPENMP
// A thread that takes twice as long for its work gets a smaller range at the next builds, until
// both finish together (a third of the work for the slow one); when it is as fast again, the
// split goes back to halves. The speeds follow the times the passes record.
TEST(NeighbourSearch, WorkRangesFollowTheThreadsMeasuredSpeeds) {
    std::mt19937 rng(7);
    std::uniform_real_distribution<Scalar> u(0, 1);
    std::vector<Vec3> fluid(6000);
    for (auto& p : fluid) p = Vec3(u(rng), u(rng), 0);
    FluidAndWalls search;
    search.setup(0.04, 2, Vec3::Zero(), Vec3(1, 1, 0));
    const auto share = [&](QueryLists::PairWork kind) { // the first thread's part of the pairs
        const auto [first, last] = search.workRange(0, 2, kind);
        const auto& ff = search.fluidNeighbours();
        return double(ff.offsets[last] - ff.offsets[first]) / double(ff.totalPairs());
    };
    const auto buildTimed = [&](double slowdown) { // the passes of a step, then the next build
        for (auto kind : {QueryLists::PairWork::All, QueryLists::PairWork::Own})
            for (int t = 0; t < 2; ++t) {
                const auto [first, last] = search.workRange(t, 2, kind);
                const auto& ff = search.fluidNeighbours();
                const double seconds = 1e-9 * double(ff.offsets[last] - ff.offsets[first] + 8 * (last - first));
                search.recordTime(t, 2, kind, first, last, t == 0 ? slowdown * seconds : seconds);
            }
        search.build(fluid);
    };
    const int saved = omp_get_max_threads();
    omp_set_num_threads(2);
    search.build(fluid);
    EXPECT_NEAR(share(QueryLists::PairWork::Own), 0.5, 0.01);
    for (int step = 0; step < 40; ++step) buildTimed(2.0);
    EXPECT_NEAR(search.threadSpeeds()[0], 2.0 / 3, 0.01);
    EXPECT_NEAR(share(QueryLists::PairWork::Own), 1.0 / 3, 0.01);
    EXPECT_NEAR(share(QueryLists::PairWork::All), 1.0 / 3, 0.01);
    buildTimed(1.0); // one step does not undo it all: the speeds are averaged over steps
    EXPECT_LT(share(QueryLists::PairWork::Own), 0.45);
    for (int step = 0; step < 40; ++step) buildTimed(1.0);
    EXPECT_NEAR(share(QueryLists::PairWork::Own), 0.5, 0.01);
    // times from another thread count are ignored
    search.recordTime(0, 3, QueryLists::PairWork::Own, 0, 10, 1.0);
    search.build(fluid);
    EXPECT_NEAR(share(QueryLists::PairWork::Own), 0.5, 0.01);
    omp_set_num_threads(saved);
}
#endif

#ifdef _OPENMP
// A balanced pass visits every particle exactly once. When a thread is held up (here thread 0,
// 20 µs a particle), the others, done with their own ranges, take the rest of its range in
// chunks instead of waiting; each thread's recorded work is what it did, so the next builds
// give the slow thread less.
TEST(NeighbourSearch, BalancedPassesShareTheRangeOfAHeldUpThread) {
    const std::vector<Vec3> fluid = randomPoints(4000, 2, 1.0, 8);
    FluidAndWalls search;
    search.setup(0.04, 2, Vec3::Zero(), Vec3(1, 1, 0));
    const int saved = omp_get_max_threads();
    for (int threads : {2, 3}) {
        omp_set_num_threads(threads);
        search.build(fluid);
        const auto [first0, last0] = search.workRange(0, threads);
        std::vector<int> visits(fluid.size(), 0), by(fluid.size(), -1);
        forEachParticleBalanced(search.lists(), [&](std::size_t i) {
            const int t = omp_get_thread_num();
            ++visits[i];
            by[i] = t;
            if (t == 0)
                for (const double start = omp_get_wtime(); omp_get_wtime() - start < 20e-6;) {
                }
        });
        EXPECT_EQ(std::count(visits.begin(), visits.end(), 1), std::ptrdiff_t(fluid.size())) << threads;
        const auto taken = std::count_if(by.begin() + first0, by.begin() + last0, [](int t) { return t != 0; });
        EXPECT_GT(taken, std::ptrdiff_t(last0 - first0) / 2) << threads << " threads: " << taken << " of "
                                                            << last0 - first0 << " taken from thread 0";
        search.build(fluid); // the split learns from the work each thread did
        EXPECT_LT(search.threadSpeeds()[0], 0.9) << threads;
    }
    omp_set_num_threads(saved);
}
#endif

// Each build's grid covers only the cells its points occupy; queries from outside that range
// (fluid beyond the walls' range, a point outside the domain) still find every neighbour.
TEST_P(NeighbourSearchTest, GridCoversTheOccupiedCellsOnly) {
    const int dim = GetParam();
    const Scalar h = 0.07;
    std::mt19937 rng(7);
    const auto inBox = [&](std::size_t n, Scalar lo, Scalar hi) {
        std::uniform_real_distribution<Scalar> u(lo, hi);
        std::vector<Vec3> p(n);
        for (auto& x : p) x = Vec3(u(rng), u(rng), dim == 3 ? u(rng) : Scalar(0));
        return p;
    };
    auto wall = inBox(800, 1.0, 1.5);
    wall.push_back(Vec3(1.5, 1.2, dim == 3 ? 1.2 : 0));
    auto fluid = inBox(dim == 2 ? 1500 : 3000, 0.8, 1.9);
    fluid.push_back(Vec3(1.55, 1.2, dim == 3 ? 1.2 : 0)); // in the cell after the walls' last one
    fluid.push_back(Vec3(9, 9, dim == 3 ? 9 : 0));         // outside the domain
    FluidAndWalls search;
    search.setup(h, dim, Vec3::Zero(), Vec3(4, 4, dim == 3 ? 4 : 0));
    const double latticeCells = std::pow(std::ceil(4 / h) + 1, dim);
    search.setWalls({{&wall, false}});
    search.build(fluid);
    EXPECT_LT(double(search.wallGrid(0).cellCount()), latticeCells / 50);
    const auto& ff = search.fluidNeighbours();
    const auto& fb = search.wallNeighbours(0);
    std::size_t wallPairs = 0;
    for (std::size_t i = 0; i < fluid.size(); ++i) {
        ASSERT_EQ(std::set<Index>(ff.begin(i), ff.end(i)), bruteForce(fluid, fluid[i], h, long(i))) << i;
        ASSERT_EQ(std::set<Index>(fb.begin(i), fb.end(i)), bruteForce(wall, fluid[i], h, -1)) << i;
        wallPairs += fb.count(i);
    }
    EXPECT_GT(fb.count(fluid.size() - 2), 0u); // the query from outside the walls' range found some
    EXPECT_GT(wallPairs, fluid.size() / 4);
    // every build covers its own points' range: the far point's clamped cell spans the domain
    EXPECT_GT(double(search.fluidGrid().cellCount()), latticeCells / 3);
    fluid.pop_back();
    search.build(fluid);
    EXPECT_LT(double(search.fluidGrid().cellCount()), latticeCells / 10);
}

TEST(NeighbourSearch, NonFiniteAndFarAwayPointsAreHandled) {
    std::vector<Vec3> pts = {Vec3(0.5, 0.5, 0), Vec3(0.52, 0.5, 0), Vec3(1e9, 1e9, 0),
                             Vec3(1e9 + 0.01, 1e9, 0), Vec3(std::nan(""), 0, 0)};
    FluidAndWalls search;
    search.setup(0.05, 2, Vec3::Zero(), Vec3(1, 1, 0));
    search.build(pts);
    const auto& l = search.fluidNeighbours();
    EXPECT_EQ(std::vector<Index>(l.begin(0), l.end(0)), std::vector<Index>{1});
    EXPECT_EQ(std::vector<Index>(l.begin(2), l.end(2)), std::vector<Index>{3});
    EXPECT_EQ(l.count(4), 0u);
}

TEST_P(NeighbourSearchTest, PeriodicAxesUseTheNearestImage) {
    const int dim = GetParam();
    const Scalar h = 0.09;
    Periodicity periodic;
    periodic.axis[0] = true; // periodic in x only; y (and z) bounded
    periodic.min = Vec3(-0.5, 0, 0);
    periodic.length = Vec3(1.0, 0, 0);
    std::mt19937 rng(5);
    std::uniform_real_distribution<Scalar> u(0, 1);
    std::vector<Vec3> pts(dim == 2 ? 2000 : 4000);
    for (auto& p : pts) p = Vec3(u(rng) - 0.5, u(rng), dim == 3 ? u(rng) : Scalar(0));
    pts[0] = Vec3(-0.49, 0.5, dim == 3 ? 0.5 : 0); // neighbours across the periodic boundary
    pts[1] = Vec3(0.49, 0.5, dim == 3 ? 0.5 : 0);
    pts[2] = Vec3(1.505, 0.5, dim == 3 ? 0.5 : 0); // outside [min, min + L): an image of x = 0.505
    FluidAndWalls search;
    search.setup(h, dim, Vec3(-0.5, 0, 0), Vec3(0.5, 1, dim == 3 ? 1 : 0), periodic);
    search.build(pts);
    const auto& l = search.fluidNeighbours();
    ASSERT_NE(l.periodic, nullptr);
    for (std::size_t i = 0; i < pts.size(); ++i) {
        std::set<Index> expected;
        for (std::size_t j = 0; j < pts.size(); ++j) {
            Vec3 d = pts[i] - pts[j];
            d[0] -= std::round(d[0]);
            if (j != i && d.squaredNorm() < h * h) expected.insert(Index(j));
        }
        ASSERT_EQ(std::set<Index>(l.begin(i), l.end(i)), expected) << "particle " << i;
    }
    EXPECT_TRUE(std::set<Index>(l.begin(0), l.end(0)).count(1)) << "pairs across the boundary are found";
    Vec3 x = pts[2];
    periodic.wrap(x);
    EXPECT_NEAR(x[0], -0.495, test::tol(1e-12, test::eps)); // float: 1.505 rounded to Scalar
}

INSTANTIATE_TEST_SUITE_P(Dimensions, NeighbourSearchTest, testing::Values(2, 3),
                         [](const auto& info) { return std::to_string(info.param) + "D"; });

// Several wall systems, one of them moving: every list matches brute force after the moving
// wall's points change (its grid is rebuilt at every build, the fixed wall's is not), the
// transpose lists every fluid neighbour of a wall particle in ascending order, and the wall–wall
// lists pair the two walls.
TEST(NeighbourSearch, WallSystemsFixedAndMovingWithTransposes) {
    const int dim = 2;
    const Scalar h = 0.06;
    auto fluid = randomPoints(2000, dim, 1.0, 11);
    const auto fixedWall = randomPoints(500, dim, 1.0, 12);
    auto movingWall = randomPoints(300, dim, 0.5, 13);
    FluidAndWalls search;
    search.setup(h, dim, Vec3::Zero(), Vec3(1.5, 1.5, 0));
    search.setWalls({{&fixedWall, false}, {&movingWall, true}});
    ASSERT_EQ(search.wallCount(), 2u);
    for (int move = 0; move < 3; ++move) {
        for (auto& x : movingWall) x += Vec3(0.2, 0.1, 0); // the wall moves between builds
        search.build(fluid);
        std::size_t pairs = 0;
        for (std::size_t i = 0; i < fluid.size(); ++i) {
            const auto& f0 = search.wallNeighbours(0);
            const auto& f1 = search.wallNeighbours(1);
            ASSERT_EQ(std::set<Index>(f0.begin(i), f0.end(i)), bruteForce(fixedWall, fluid[i], h, -1)) << i;
            ASSERT_EQ(std::set<Index>(f1.begin(i), f1.end(i)), bruteForce(movingWall, fluid[i], h, -1)) << i;
            ASSERT_EQ(search.wallNeighbourCount(i), f0.count(i) + f1.count(i));
            pairs += f1.count(i);
        }
        EXPECT_GT(pairs, 100u) << "the moving wall is among the fluid (not vacuous)";
        const auto& wallFluid = search.wallFluidNeighbours(1);
        ASSERT_EQ(wallFluid.size(), movingWall.size());
        for (std::size_t b = 0; b < movingWall.size(); ++b) {
            std::vector<Index> row(wallFluid.begin(b), wallFluid.end(b));
            EXPECT_TRUE(std::is_sorted(row.begin(), row.end()));
            ASSERT_EQ(std::set<Index>(row.begin(), row.end()), bruteForce(fluid, movingWall[b], h, -1)) << b;
        }
    }
    const NeighbourList across = search.wallWallList(0, 1);
    for (std::size_t b = 0; b < fixedWall.size(); ++b)
        ASSERT_EQ(std::set<Index>(across.begin(b), across.end(b)), bruteForce(movingWall, fixedWall[b], h, -1)) << b;
}

// A search made ahead at predicted positions is recognised when the particles get there, also
// after the particles are re-sorted with it, and forgotten after an ordinary build; listsAt
// tells the positions of the lists either way.
TEST(NeighbourSearch, BuildAheadIsKeptUntilTheNextBuild) {
    const int dim = 2;
    auto fluid = randomPoints(1500, dim, 1.0, 21);
    FluidAndWalls search;
    search.setup(0.05, dim, Vec3::Zero(), Vec3(1, 1, 0));
    search.build(fluid);
    EXPECT_FALSE(search.builtAt(fluid));
    EXPECT_TRUE(search.search.listsAt(0, fluid));
    auto ahead = fluid;
    for (auto& x : ahead) x += Vec3(0.001, -0.002, 0);
    search.buildAhead(ahead);
    EXPECT_TRUE(search.builtAt(ahead));
    EXPECT_FALSE(search.builtAt(fluid));
    EXPECT_FALSE(search.search.listsAt(0, fluid));
    const auto order = search.sortOrder(ahead);
    std::vector<Vec3> sorted(ahead.size());
    for (std::size_t i = 0; i < ahead.size(); ++i) sorted[i] = ahead[order[i]];
    search.permute(order);
    EXPECT_TRUE(search.builtAt(sorted));
    const long builds = search.search.builds();
    search.build(sorted); // kept: no search
    EXPECT_EQ(search.search.builds(), builds);
    auto moved = sorted;
    moved[0] += Vec3(0.001, 0, 0);
    search.build(moved);
    EXPECT_FALSE(search.builtAt(moved));
    EXPECT_TRUE(search.search.listsAt(0, moved));
    EXPECT_EQ(search.search.builds(), builds + 1);
    search.build(moved); // an ordinary build is made again
    EXPECT_EQ(search.search.builds(), builds + 2);
}

} // namespace
