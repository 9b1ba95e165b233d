#include "NeighbourSearch.hpp"
#include "ParticleSet.hpp" // permuteVector

#include <cmath>
#include <limits>
#include <numeric>
#include <stdexcept>

namespace spindrift {

void UniformGrid::setup(Scalar cellSize, int dimension, const Vec3& domainMin, const Vec3& domainMax,
                        const Periodicity& periodic) {
    if (!(cellSize > 0)) throw std::invalid_argument("UniformGrid: cell size must be positive");
    dim_ = dimension;
    periodic_ = periodic;
    origin_ = domainMin;
    for (int a = 0; a < 3; ++a) {
        invCell_[a] = Scalar(1) / cellSize;
        if (a == 2 && dim_ == 2) {
            dims_[a] = 1;
        } else if (periodic.axis[a]) {
            // whole cells of at least the support radius spanning the period exactly
            origin_[a] = periodic.min[a];
            const double along = double(std::floor(periodic.length[a] / cellSize));
            if (!(along <= maxCellsAlong))
                throw std::length_error(std::string("neighbour search: the periodic length along ") + "xyz"[a] +
                                        " is too large for the support radius (" + std::to_string(along) + " cells)");
            dims_[a] = int(along);
            if (dims_[a] < 3)
                throw std::runtime_error(std::string("the periodic length along ") + "xyz"[a] +
                                         " must be at least 3 kernel support radii");
            invCell_[a] = Scalar(dims_[a]) / periodic.length[a];
        } else {
            const double along = cellsAlong(double(domainMax[a] - domainMin[a]), cellSize);
            if (!(along <= maxCellsAlong))
                throw std::length_error(std::string("neighbour search: the domain is too large for the support "
                                                    "radius along ") + "xyz"[a] + " (" + std::to_string(along) +
                                        " cells; at most " + std::to_string(long(maxCellsAlong)) + ")");
            dims_[a] = int(along);
        }
    }
    const double cells = double(dims_[0]) * dims_[1] * dims_[2];
    if (cells > maxCells)
        throw std::length_error("neighbour search: the domain is too large for the support radius (" +
                                std::to_string(cells) + " cells; at most " + std::to_string(long(maxCells)) + ")");
    for (int a = 0; a < 3; ++a) {
        latticeDims_[a] = dims_[a];
        first_[a] = 0;
    }
    // no cells until a build covers its points' range (periodic axes always whole)
    for (int a = 0; a < 3; ++a) dims_[a] = periodic_.axis[a] ? latticeDims_[a] : 1;
    cellStart_.assign(std::size_t(dims_[0]) * dims_[1] * dims_[2] + 1, 0);
    sorted_.clear();
}

namespace {
std::uint64_t spreadBits(std::uint64_t v) { // 21 bits -> every third bit
    v &= 0x1fffff;
    v = (v | v << 32) & 0x1f00000000ffffULL;
    v = (v | v << 16) & 0x1f0000ff0000ffULL;
    v = (v | v << 8) & 0x100f00f00f00f00fULL;
    v = (v | v << 4) & 0x10c30c30c30c30c3ULL;
    v = (v | v << 2) & 0x1249249249249249ULL;
    return v;
}
} // namespace

void UniformGrid::relabel(const std::vector<Index>& newIndexOf) {
    const std::size_t n = sorted_.size();
#pragma omp parallel for schedule(static)
    for (std::size_t k = 0; k < n; ++k) sorted_[k] = newIndexOf[sorted_[k]];
}

std::uint64_t UniformGrid::mortonCode(const Vec3& p) const {
    int c[3];
    latticeCoords(p, c);
    return spreadBits(c[0]) | spreadBits(c[1]) << 1 | spreadBits(c[2]) << 2;
}

void UniformGrid::build(const std::vector<Vec3>& points) {
    const std::size_t n = points.size();
    // The grid covers the range of cells the points occupy, not the whole domain box (several
    // times larger: room for splashes), so the passes over the cells below touch only that.
    // The cells stay those of the set-up lattice: the lists do not depend on the range.
    int lo[3] = {latticeDims_[0], latticeDims_[1], latticeDims_[2]}, hi[3] = {-1, -1, -1};
#pragma omp parallel for schedule(static) reduction(min : lo[:3]) reduction(max : hi[:3])
    for (std::size_t i = 0; i < n; ++i) {
        int c[3];
        latticeCoords(points[i], c);
        for (int a = 0; a < 3; ++a) {
            lo[a] = std::min(lo[a], c[a]);
            hi[a] = std::max(hi[a], c[a]);
        }
    }
    for (int a = 0; a < 3; ++a) {
        const bool all = periodic_.axis[a] || lo[a] > hi[a]; // periodic, or no points
        first_[a] = all ? 0 : lo[a];
        dims_[a] = all ? latticeDims_[a] : hi[a] - lo[a] + 1;
    }
    const std::size_t cells = std::size_t(dims_[0]) * dims_[1] * dims_[2];
    cellOf_.resize(n);
    sorted_.resize(n);
    cellStart_.resize(cells + 1);
    cellStart_[cells] = Index(n);
    cellX_.resize(n);
    cellY_.resize(n);
    cellZ_.resize(n);
    int threads = 1;
#ifdef _OPENMP
    threads = n < 4096 ? 1 : omp_get_max_threads(); // a few points: not worth the barriers
#endif
    blockPoints_.resize(std::size_t(threads));
#pragma omp parallel num_threads(threads)
    {
        int t = 0, team = 1; // the team may be smaller than asked for (a nested region)
#ifdef _OPENMP
        t = omp_get_thread_num();
        team = omp_get_num_threads();
#endif
#pragma omp for schedule(static)
        for (std::size_t i = 0; i < n; ++i) {
            int c[3];
            cellCoords(points[i], c);
            cellOf_[i] = Index((std::size_t(c[2]) * dims_[1] + c[1]) * dims_[0] + c[0]);
        }
        // A stable counting sort by cell, each thread for a block of cells: it counts the points
        // in its cells, sums them up (after the points of the blocks before), and puts them in
        // place, the last first, so cellStart_[c] ends as the first slot of cell c. A point's
        // slot depends only on the points before it in its cell, so on no thread count.
        const std::size_t cellFirst = cells * t / team, span = cells * (t + 1) / team - cellFirst;
        Index* start = cellStart_.data() + cellFirst;
        std::fill(start, start + span, Index(0));
        for (std::size_t i = 0; i < n; ++i) {
            const std::size_t c = cellOf_[i] - cellFirst; // wraps above span for the cells before
            if (c < span) ++start[c];
        }
        std::size_t inBlock = 0;
        for (std::size_t c = 0; c < span; ++c) start[c] = Index(inBlock += start[c]); // one past the cell's last
        blockPoints_[t] = inBlock;
#pragma omp barrier
        std::size_t before = 0;
        for (int u = 0; u < t; ++u) before += blockPoints_[u];
        for (std::size_t c = 0; c < span; ++c) start[c] += Index(before);
        for (std::size_t i = n; i-- > 0;) {
            const std::size_t c = cellOf_[i] - cellFirst;
            if (c < span) sorted_[--start[c]] = Index(i);
        }
#pragma omp barrier
#pragma omp for schedule(static)
        for (std::size_t k = 0; k < n; ++k) {
            const Vec3& x = points[sorted_[k]];
            cellX_[k] = x[0];
            cellY_[k] = x[1];
            cellZ_[k] = x[2];
        }
    }
}

void NeighbourSearch::setup(Scalar radius, int dimension, const Vec3& domainMin, const Vec3& domainMax,
                            const Periodicity& periodic) {
    radius_ = radius;
    dim_ = dimension;
    periodic_ = periodic;
    domainMin_ = domainMin;
    domainMax_ = domainMax;
    lattice_.setup(radius, dimension, domainMin, domainMax, periodic); // checks the domain's size
    systems_.clear();
}

std::size_t NeighbourSearch::addSystem(const std::vector<Vec3>* positions, bool fixed) {
    SystemEntry& e = systems_.emplace_back();
    e.positions = positions;
    e.fixed = fixed;
    e.query.system_ = systems_.size() - 1;
    return systems_.size() - 1;
}

void NeighbourSearch::addInteraction(std::size_t query, std::size_t source) {
    if (query >= systems_.size() || source >= systems_.size())
        throw std::logic_error("NeighbourSearch::addInteraction: no such system");
    if (interacts(query, source)) return;
    QueryLists& q = systems_[query].query;
    if (int(q.sources_.size()) == maxLists)
        throw std::runtime_error("neighbour search: a system interacts with at most " + std::to_string(maxLists) +
                                 " systems (its own, its walls and bodies)");
    // its own list first, the others in the order of their numbers
    const auto at = source == query ? q.sources_.begin()
                                    : std::upper_bound(q.sources_.begin() + (q.hasOwn() ? 1 : 0), q.sources_.end(), source);
    q.lists_.insert(q.lists_.begin() + (at - q.sources_.begin()), NeighbourList{});
    q.sources_.insert(at, source);
    q.stamp_ = -1;
    SystemEntry& s = systems_[source];
    if (!s.isSource) {
        s.isSource = true;
        s.grid.setup(radius_, dim_, domainMin_, domainMax_, periodic_);
        s.gridBuilt = false;
    }
}

bool NeighbourSearch::interacts(std::size_t query, std::size_t source) const {
    return query < systems_.size() && systems_[query].query.find(source) != nullptr;
}

const NeighbourList& NeighbourSearch::neighbours(std::size_t query, std::size_t source) const {
    const NeighbourList* list = query < systems_.size() ? systems_[query].query.find(source) : nullptr;
    if (!list)
        throw std::logic_error("neighbour search: system " + std::to_string(query) + " was not declared to interact with " +
                               std::to_string(source));
    return *list;
}

// Fills the lists of query system q for its n rows in one parallel region: gather(list, i,
// reserve) → count writes point i's neighbours in list l to the array reserve(room) gives it.
// Each thread takes its block of points (searchRange) in chunks, and then what is left of the
// others' (claimChunk), writing the rows into its own buffers (kept between calls); then each
// copies its chunks to their place in the lists, so the lists do not depend on the thread
// count, the split or who took what. The first thread writes its leading chunks straight into
// the lists, where they go. A thread's time (gather and copy) and the pairs it gathered update
// the split of the next build. (Each thread copies its own rows: the passes then find them in
// its cache.)
template <class Gather>
void NeighbourSearch::gatherLists(QueryLists& q, std::size_t n, int listCount, Gather&& gather) {
    int threads = 1;
#ifdef _OPENMP
    threads = omp_get_max_threads();
#endif
    NeighbourList* lists[maxLists];
    for (int l = 0; l < listCount; ++l) lists[l] = &q.lists_[std::size_t(l)];
    const bool timed = threads > 1 && threads == int(q.searchRanges_.size()) - 1 && q.searchRanges_.back() == n;
    std::vector<std::size_t> first(threads + 1);
    for (int t = 0; t <= threads; ++t) first[t] = timed ? q.searchRanges_[t] : n * t / threads;
    if (timed && int(q.searchSpeeds_.clocks.size()) != threads) q.searchSpeeds_.clocks.assign(threads, QueryLists::ThreadClock{});
    for (int k = 0; k < listCount; ++k) {
        lists[k]->offsets.resize(n + 1);
        lists[k]->offsets[0] = 0;
    }
    if (int(threadBuffers_.size()) < maxLists * threads) threadBuffers_.resize(std::size_t(maxLists * threads));
    if (int(threadChunks_.size()) < threads) threadChunks_.resize(threads);
    if (int(q.cursors_.size()) < threads) q.cursors_.resize(threads);
    const std::uint32_t region = q.beginRegion();
#pragma omp parallel num_threads(threads)
    {
        int t = 0;
#ifdef _OPENMP
        t = omp_get_thread_num();
        double start = omp_get_wtime();
#endif
        double busy = 0, pairs = 0; // seconds of work (not of waiting), and the pairs found
        // 1. the thread gathers its chunks; the offsets count in its buffers
        std::vector<GatherChunk>& chunks = threadChunks_[t];
        chunks.clear();
        std::size_t used[maxLists] = {}, inPlaceUsed[maxLists] = {}, inPlaceEnd = 0;
        for (int k = 0; k < threads; ++k) { // its own block first, then the others'
            const int owner = (t + k) % threads;
            for (auto [a, b] = q.claimChunk(owner, first[owner], first[owner + 1], region); a < b;
                 std::tie(a, b) = q.claimChunk(owner, first[owner], first[owner + 1], region)) {
                GatherChunk chunk{a, b, {}, {}, {}, t == 0 && a == inPlaceEnd};
                for (int l = 0; l < listCount; ++l) {
                    NeighbourList& list = *lists[l];
                    std::vector<Index>& buffer = chunk.inPlace ? list.indices : threadBuffers_[maxLists * t + l];
                    std::size_t& size = chunk.inPlace ? inPlaceUsed[l] : used[l];
                    auto reserve = [&](std::size_t room) {
                        if (size + room > buffer.size()) buffer.resize(std::max(2 * buffer.size(), size + room));
                        return buffer.data() + size;
                    };
                    chunk.start[l] = size;
                    for (std::size_t i = a; i < b; ++i) {
                        size += gather(l, i, reserve);
                        list.offsets[i + 1] = std::uint32_t(size);
                    }
                    chunk.end[l] = size;
                    pairs += double(size - chunk.start[l]);
                }
                if (chunk.inPlace) inPlaceEnd = b;
                chunks.push_back(chunk);
            }
        }
#ifdef _OPENMP
        busy += omp_get_wtime() - start;
#endif
#pragma omp barrier
#pragma omp single
        {
            // 2. the chunks in the order of their points: each one's place in the lists
            chunkOrder_.clear();
            for (int u = 0; u < threads; ++u)
                for (GatherChunk& c : threadChunks_[u]) chunkOrder_.push_back(&c);
            std::sort(chunkOrder_.begin(), chunkOrder_.end(),
                      [](const GatherChunk* x, const GatherChunk* y) { return x->first < y->first; });
            for (int l = 0; l < listCount; ++l) {
                std::size_t total = 0;
                for (GatherChunk* c : chunkOrder_) {
                    c->target[l] = total;
                    total += c->end[l] - c->start[l];
                }
                lists[l]->indices.resize(total);
            }
        }
        // 3. each thread moves its chunks' rows there (the first thread's leading ones are in
        // place) and shifts their offsets by as much
#ifdef _OPENMP
        start = omp_get_wtime();
#endif
        for (const GatherChunk& c : chunks) {
            if (c.inPlace) continue;
            for (int l = 0; l < listCount; ++l) {
                NeighbourList& list = *lists[l];
                const std::vector<Index>& buffer = threadBuffers_[maxLists * t + l];
                std::copy(buffer.begin() + c.start[l], buffer.begin() + c.end[l], list.indices.begin() + c.target[l]);
                const std::uint32_t shift = std::uint32_t(c.target[l] - c.start[l]); // modulo 2^32
                for (std::size_t i = c.first; i < c.last; ++i) list.offsets[i + 1] += shift;
            }
        }
#ifdef _OPENMP
        busy += omp_get_wtime() - start;
#endif
        if (timed) {
            for (const GatherChunk& c : chunks) pairs += double(QueryLists::perParticle * (c.last - c.first));
            q.searchSpeeds_.clocks[t].work += pairs;
            q.searchSpeeds_.clocks[t].seconds += busy;
        }
    }
}

void NeighbourSearch::buildGrid(SystemEntry& e, const std::vector<Vec3>& points) {
    e.grid.build(points);
    e.gridBuilt = true;
}

void NeighbourSearch::buildLists(SystemEntry& e, const std::vector<Vec3>& points) {
    QueryLists& q = e.query;
    const std::size_t n = std::min(e.owned, points.size());
    q.particles_ = n;
    q.stamp_ = ++stamps_;
    const Periodicity* periodic = periodic_.any() ? &periodic_ : nullptr;
    const int listCount = int(q.sources_.size());
    for (NeighbourList& list : q.lists_) list.periodic = periodic;
    const auto own = [&](int l) { return q.sources_[std::size_t(l)] == q.system_; };
    if (periodic) {
        for (int l = 0; l < listCount; ++l) {
            const SystemEntry& src = systems_[q.sources_[std::size_t(l)]];
            const std::vector<Vec3>& xs = own(l) ? points : *src.positions;
            buildNeighbourList(n, q.lists_[std::size_t(l)], [&](std::size_t i, auto&& push) {
                src.grid.forEachWithin(points[i], xs, radius_, [&](Index j) {
                    if (!own(l) || j != i) push(j);
                });
            });
        }
    } else {
        const Scalar r2 = radius_ * radius_;
        constexpr Index none = std::numeric_limits<Index>::max();
        const UniformGrid* grids[maxLists];
        for (int l = 0; l < listCount; ++l) grids[l] = &systems_[q.sources_[std::size_t(l)]].grid;
        const bool ownFirst = q.hasOwn();
        gatherLists(q, n, listCount, [&](int l, std::size_t i, auto&& reserve) {
            return grids[l]->gatherWithin(points[i], r2, ownFirst && l == 0 ? Index(i) : none, reserve);
        });
    }
    q.countOtherPairs();
    q.balanceWork();
}

void QueryLists::countOtherPairs() {
    const std::size_t n = particles_;
    otherPairsBefore_.assign(n + 1, 0);
    for (std::size_t k = hasOwn() ? 1 : 0; k < lists_.size(); ++k) {
        const std::uint32_t* offsets = lists_[k].offsets.data();
        std::uint32_t* before = otherPairsBefore_.data();
#pragma omp parallel for schedule(static)
        for (std::size_t i = 0; i <= n; ++i) before[i] += offsets[i];
    }
}

void NeighbourSearch::build() {
    // a query system keeps the lists built ahead at exactly its positions, unless a source other
    // than itself moves (its particles would be elsewhere now); lists of the last build are made
    // again (the caller asks for a build when they are stale: listsAt)
    std::vector<char> keep(systems_.size(), 0);
    for (std::size_t k = 0; k < systems_.size(); ++k) {
        const SystemEntry& e = systems_[k];
        if (!e.query.builtAhead_ || *e.positions != e.query.builtPoints_) continue;
        bool othersStill = true;
        for (std::size_t s : e.query.sources_)
            othersStill = othersStill && (s == k || (systems_[s].fixed && systems_[s].gridBuilt));
        keep[k] = othersStill;
    }
    bool any = false;
    for (std::size_t k = 0; k < systems_.size(); ++k) {
        SystemEntry& e = systems_[k];
        if (e.isSource && !keep[k] && (!e.fixed || !e.gridBuilt)) buildGrid(e, *e.positions);
    }
    for (std::size_t k = 0; k < systems_.size(); ++k) {
        SystemEntry& e = systems_[k];
        if (e.query.sources_.empty() || keep[k]) continue;
        buildLists(e, *e.positions);
        e.query.builtPoints_ = *e.positions;
        e.query.built_ = true;
        e.query.builtAhead_ = false;
        any = true;
    }
    if (any) ++builds_;
}

void NeighbourSearch::buildAhead(std::size_t query, const std::vector<Vec3>& predicted) {
    SystemEntry& e = systems_[query];
    for (std::size_t s : e.query.sources_) {
        SystemEntry& src = systems_[s];
        if (s == query) buildGrid(src, predicted);
        else if (!src.gridBuilt) buildGrid(src, *src.positions);
    }
    buildLists(e, predicted);
    e.query.builtPoints_ = predicted;
    e.query.built_ = e.query.builtAhead_ = true;
    ++builds_;
}

bool NeighbourSearch::builtAt(std::size_t query, const std::vector<Vec3>& positions) const {
    const QueryLists& q = systems_[query].query;
    return q.builtAhead_ && positions == q.builtPoints_;
}

bool NeighbourSearch::listsAt(std::size_t query, const std::vector<Vec3>& positions) const {
    const QueryLists& q = systems_[query].query;
    return q.sources_.empty() || (q.built_ && positions == q.builtPoints_);
}

void QueryLists::ThreadSpeeds::update(int threads) {
    if (int(speed.size()) != threads) speed.assign(threads, 1.0);
    if (int(clocks.size()) == threads) {
        // each thread's work per second since the last build, relative to the mean, averaged
        // over the last steps (weight 1/4 for the newest): one noisy step moves it little. A
        // thread that found its range taken by the others when it started did no work at all.
        const auto rate = [&](int t) { return clocks[t].work / clocks[t].seconds; };
        double mean = 0;
        for (int t = 0; t < threads; ++t) mean += clocks[t].seconds > 0 ? rate(t) / threads : NAN;
        if (mean > 0) { // every thread measured
            double sum = 0;
            for (int t = 0; t < threads; ++t) {
                speed[t] = 0.75 * speed[t] + 0.25 * std::clamp(rate(t) / mean, 0.25, 4.0);
                sum += speed[t];
            }
            for (double& s : speed) s *= threads / sum;
        }
    }
    clocks.assign(threads, ThreadClock{});
}

void QueryLists::balanceWork() {
    int threads = 1;
#ifdef _OPENMP
    threads = omp_get_max_threads();
#endif
    // thread t starts where the work (pairWork) reaches the share of the threads before it,
    // each thread's share in proportion to its speed
    passSpeeds_.update(threads);
    searchSpeeds_.update(threads);
    if (int(cursors_.size()) != threads) cursors_.resize(threads);
    const std::size_t n = particles_;
    const auto balance = [&](std::vector<std::size_t>& ranges, PairWork kind, const std::vector<double>& speed) {
        ranges.assign(threads + 1, n);
        ranges[0] = 0;
        const double total = double(pairWork(n, kind));
        double before = 0;
        std::size_t lo = 0;
        for (int t = 1; t < threads; ++t) {
            before += speed[t - 1];
            const double target = total * before / threads;
            std::size_t a = lo, b = n; // first i with pairWork(i) >= target
            while (a < b) {
                const std::size_t mid = (a + b) / 2;
                if (double(pairWork(mid, kind)) < target) a = mid + 1;
                else b = mid;
            }
            ranges[t] = lo = a;
        }
    };
    balance(workRanges_, PairWork::All, passSpeeds_.speed);
    balance(ownWorkRanges_, PairWork::Own, passSpeeds_.speed);
    balance(searchRanges_, PairWork::All, searchSpeeds_.speed);
}

std::vector<Index> NeighbourSearch::sortOrder(const std::vector<Vec3>& points) const {
    std::vector<std::uint64_t> codes(points.size());
#pragma omp parallel for schedule(static)
    for (std::size_t i = 0; i < points.size(); ++i) codes[i] = lattice_.mortonCode(points[i]);
    // a stable LSD radix sort by code, 11 bits a pass, as many passes as the largest code needs
    // (two for a lattice of up to 128 cells a side): a fifth of a stable comparison sort's time
    // at 7k points, a third at 59k (it runs on one thread)
    std::uint64_t largest = 0;
    for (std::uint64_t c : codes) largest |= c;
    const std::size_t n = points.size();
    std::vector<Index> order(n), scratch(n);
    std::vector<std::uint64_t> scratchCodes(n);
    std::iota(order.begin(), order.end(), Index(0));
    constexpr int digitBits = 11;
    constexpr std::size_t buckets = std::size_t(1) << digitBits;
    std::vector<std::size_t> next(buckets);
    for (int shift = 0; shift < 64 && (largest >> shift) != 0; shift += digitBits) {
        std::fill(next.begin(), next.end(), 0);
        for (std::uint64_t c : codes) ++next[(c >> shift) & (buckets - 1)];
        std::size_t slot = 0;
        for (std::size_t& b : next) slot += std::exchange(b, slot); // the first slot of each digit
        for (std::size_t k = 0; k < n; ++k) {
            const std::size_t to = next[(codes[k] >> shift) & (buckets - 1)]++;
            scratch[to] = order[k];
            scratchCodes[to] = codes[k];
        }
        order.swap(scratch);
        codes.swap(scratchCodes);
    }
    return order;
}

std::vector<std::uint32_t> permutedOffsets(const NeighbourList& list, const std::vector<Index>& order) {
    std::vector<std::uint32_t> offsets(order.size() + 1);
    offsets[0] = 0;
    for (std::size_t i = 0; i < order.size(); ++i) offsets[i + 1] = offsets[i] + list.count(order[i]);
    return offsets;
}

void NeighbourSearch::permute(std::size_t system, const std::vector<Index>& order) {
    SystemEntry& e = systems_[system];
    const std::size_t n = order.size();
    if (!e.query.sources_.empty() && n != e.query.particles_)
        throw std::logic_error("NeighbourSearch::permute: not the last build's points");
    std::vector<Index> newIndexOf(n);
#pragma omp parallel for schedule(static)
    for (std::size_t i = 0; i < n; ++i) newIndexOf[order[i]] = Index(i);
    const auto renumber = [&](Index j) { return newIndexOf[j]; };
    std::vector<Index> scratch;
    // its own rows (and, in its own list, the neighbours' numbers)
    QueryLists& q = e.query;
    for (std::size_t k = 0; k < q.lists_.size(); ++k) {
        NeighbourList& list = q.lists_[k];
        std::vector<std::uint32_t> offsets = permutedOffsets(list, order);
        if (q.sources_[k] == system) permuteRowData(list, order, offsets, list.indices, scratch, renumber);
        else permuteRowData(list, order, offsets, list.indices, scratch);
        list.offsets.swap(offsets);
        list.indices.swap(scratch);
    }
    // the other systems' lists that name its particles
    for (std::size_t o = 0; o < systems_.size(); ++o) {
        if (o == system) continue;
        QueryLists& other = systems_[o].query;
        for (std::size_t k = 0; k < other.lists_.size(); ++k) {
            if (other.sources_[k] != system) continue;
            std::vector<Index>& indices = other.lists_[k].indices;
            const std::size_t pairs = indices.size();
#pragma omp parallel for schedule(static)
            for (std::size_t p = 0; p < pairs; ++p) indices[p] = newIndexOf[indices[p]];
        }
    }
    if (e.isSource && e.gridBuilt) e.grid.relabel(newIndexOf);
    if (q.built_) permuteVector(q.builtPoints_, order);
    for (SystemEntry& s : systems_)
        std::erase_if(s.reverse, [&](const SystemEntry::Reverse& r) { return r.query == system || &s == &e; });
    e.pointGridVersion = std::numeric_limits<long>::min();
    if (!q.sources_.empty()) {
        q.countOtherPairs();
        q.balanceWork();
    }
}

NeighbourList NeighbourSearch::listBetween(std::size_t query, std::size_t source) const {
    NeighbourList list;
    list.periodic = periodic_.any() ? &periodic_ : nullptr;
    const std::vector<Vec3>& from = *systems_[query].positions;
    const std::vector<Vec3>& to = *systems_[source].positions;
    UniformGrid grid;
    grid.setup(radius_, dim_, domainMin_, domainMax_, periodic_);
    grid.build(to);
    buildNeighbourList(from.size(), list, [&](std::size_t i, auto&& push) {
        grid.forEachWithin(from[i], to, radius_, [&](Index j) {
            if (query != source || j != i) push(j);
        });
    });
    return list;
}

const NeighbourList& NeighbourSearch::reverseNeighbours(std::size_t query, std::size_t source) const {
    const SystemEntry& s = systems_[source];
    const QueryLists& q = systems_[query].query;
    for (const auto& r : s.reverse)
        if (r.query == query && r.stamp == q.stamp_) return r.list;
    std::erase_if(s.reverse, [&](const SystemEntry::Reverse& r) { return r.query == query; });
    NeighbourList t = transposeList(neighbours(query, source), s.positions->size());
    t.periodic = q.find(source)->periodic;
    return s.reverse.emplace_back(SystemEntry::Reverse{query, std::move(t), q.stamp_}).list;
}

NeighbourList transposeList(const NeighbourList& list, std::size_t columns) {
    NeighbourList t;
    t.offsets.assign(columns + 1, 0);
    const std::size_t rows = list.size();
    for (Index c : list.indices) ++t.offsets[std::size_t(c) + 1];
    for (std::size_t c = 0; c < columns; ++c) t.offsets[c + 1] += t.offsets[c];
    t.indices.resize(list.indices.size());
    std::vector<std::uint32_t> next(t.offsets.begin(), t.offsets.end() - 1);
    for (std::size_t i = 0; i < rows; ++i) // rows in ascending order: each column's row ascends
        for (const Index* it = list.begin(i), *end = list.end(i); it != end; ++it) t.indices[next[*it]++] = Index(i);
    return t;
}

} // namespace spindrift
