// spindriftParallelCeiling — what this machine lets a pair loop gain from more threads, right now.
//
//   spindriftParallelCeiling [-threads N] [-mib 10] [-sweeps 100]
//
// Sweeps a pair loop shaped like the solver's: points sorted in space, each with 32 neighbours
// among the nearby points (a CSR list), summing a function of their distances, one static
// parallel region of equal halves per sweep and nothing else: no serial work, no imbalance of
// the code's own. Its working set (-mib, positions and list) is sized like a benchmark case's,
// so it meets the same caches. The time of a sweep on 1 and on N threads, run back to back,
// gives the speed-up the host allows at that moment: on a shared or virtual machine the other
// tenants' use of the cores and caches makes it vary from run to run. tutorials/benchmarks/Allrun
// -scaling runs it beside each solver run, so that the solver's speed-up is read against it.
// Prints: "ceiling: threads N, P points x 32 neighbours (M MiB): T ms per sweep (mean of S)".
#include <boost/program_options.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <iomanip>
#include <iostream>
#include <random>
#include <vector>
#ifdef _OPENMP
#include <omp.h>
#endif

namespace po = boost::program_options;

namespace {

constexpr int neighbours = 32;

struct PairLoop {
    std::vector<double> x, y, z, out;
    std::vector<std::uint32_t> index; // neighbours * points

    explicit PairLoop(std::size_t points) : x(points), y(points), z(points), out(points), index(neighbours * points) {
        std::mt19937 rng(1);
        std::uniform_real_distribution<double> jitter(0, 1);
        for (std::size_t i = 0; i < points; ++i) { // along a line: the neighbours of i are near i in memory
            x[i] = double(i) + jitter(rng);
            y[i] = jitter(rng);
            z[i] = jitter(rng);
        }
        // neighbours within ±window of i, as the lists of a space-filling-curve order reach
        const long window = 2048, n = long(points);
        std::uniform_int_distribution<long> offset(-window, window);
        for (long i = 0; i < n; ++i)
            for (int k = 0; k < neighbours; ++k) index[neighbours * i + k] = std::uint32_t(std::clamp(i + offset(rng), 0L, n - 1));
    }

    void sweep() {
        const long n = long(out.size());
#pragma omp parallel for schedule(static)
        for (long i = 0; i < n; ++i) {
            double sum = 0;
            for (int k = 0; k < neighbours; ++k) {
                const std::uint32_t j = index[neighbours * i + k];
                const double dx = x[i] - x[j], dy = y[i] - y[j], dz = z[i] - z[j];
                sum += 1.0 / (1.0 + dx * dx + dy * dy + dz * dz);
            }
            out[i] = sum;
        }
    }
};

} // namespace

int main(int argc, char** argv) {
    po::options_description options("Usage: spindriftParallelCeiling [options]\nOptions");
    options.add_options()
        ("help", "print this help and exit")
        ("threads", po::value<int>(), "number of OpenMP threads (default: all)")
        ("mib", po::value<double>()->default_value(10), "working set in MiB (positions and neighbour list)")
        ("sweeps", po::value<int>()->default_value(100), "sweeps timed (after one untimed)");
    po::variables_map vm;
    try {
        const auto style = po::command_line_style::unix_style | po::command_line_style::allow_long_disguise;
        po::store(po::command_line_parser(argc, argv).options(options).style(style).run(), vm);
        po::notify(vm);
        if (vm.count("threads") && vm["threads"].as<int>() < 1) throw std::runtime_error("-threads must be at least 1");
        if (!(vm["mib"].as<double>() > 0) || vm["sweeps"].as<int>() < 1)
            throw std::runtime_error("-mib must be positive and -sweeps at least 1");
    } catch (const std::exception& e) {
        std::cerr << "spindriftParallelCeiling: " << e.what() << "\n" << options << std::endl;
        return 2;
    }
    if (vm.count("help")) {
        std::cout << options << std::endl;
        return 0;
    }
    int threads = 1;
#ifdef _OPENMP
    if (vm.count("threads")) omp_set_num_threads(vm["threads"].as<int>());
    threads = omp_get_max_threads();
#endif
    const double bytesPerPoint = 4.0 * sizeof(double) + neighbours * sizeof(std::uint32_t);
    const std::size_t points = std::max<std::size_t>(std::size_t(vm["mib"].as<double>() * 1048576 / bytesPerPoint), 1);
    PairLoop loop(points);
    loop.sweep(); // first touch, caches
    const int sweeps = vm["sweeps"].as<int>();
    const auto start = std::chrono::steady_clock::now();
    for (int s = 0; s < sweeps; ++s) loop.sweep();
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    double check = 0;
    for (double v : loop.out) check += v;
    if (!std::isfinite(check)) return 1; // keeps the sums from being optimised away
    std::cout << "ceiling: threads " << threads << ", " << points << " points x " << neighbours << " neighbours ("
              << std::fixed << std::setprecision(1) << points * bytesPerPoint / 1048576 << " MiB): " << std::setprecision(3)
              << 1000 * seconds / sweeps << " ms per sweep (mean of " << sweeps << ")\n";
    return 0;
}
