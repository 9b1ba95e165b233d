// spindrift — the SPH solver application.
//
//   spindrift [-case DIR] [-dryRun] [-threads N] [-listModels [kind]] [-help]
#include "Log.hpp"
#include "ModelRegistry.hpp"
#include "Simulation.hpp"

#include <boost/program_options.hpp>
#include <sys/resource.h>
#include <unistd.h>
#include <ctime>
#include <iostream>
#ifdef _OPENMP
#include <omp.h>
#endif

namespace po = boost::program_options;
using namespace spindrift;

namespace {

// Peak resident memory of the process (Linux: ru_maxrss in KiB).
long peakMemoryMiB() {
    rusage usage{};
    getrusage(RUSAGE_SELF, &usage);
    return usage.ru_maxrss / 1024;
}

void listModels(const std::string& only) {
    auto& registry = ModelRegistry::instance();
    bool any = false;
    for (const auto& kind : ModelRegistry::kinds()) {
        if (!only.empty() && kind != only) continue;
        any = true;
        std::cout << kind << "\n(\n";
        for (const auto& name : registry.available(kind)) std::cout << "    " << name << '\n';
        std::cout << ")\n\n";
    }
    if (!any) {
        std::string list;
        for (const auto& k : ModelRegistry::kinds()) list += (list.empty() ? "" : " ") + k;
        throw std::runtime_error("unknown model kind '" + only + "'; valid kinds: (" + list + ")");
    }
}

std::string startedLine() {
    const std::time_t now = std::time(nullptr);
    std::tm local{};
    localtime_r(&now, &local);
    char date[32];
    std::strftime(date, sizeof date, "%Y-%m-%d %H:%M:%S", &local);
    char host[256] = "?";
    gethostname(host, sizeof host - 1);
    return std::string(date) + " on " + host + ", pid " + std::to_string(getpid());
}

void banner(const Simulation& sim, int threads) {
    const auto& s = const_cast<Simulation&>(sim).scene();
    log::Line() << "Started   : " << startedLine();
    log::Line() << "Case      : " << sim.caseFiles().dir.string();
    log::Line() << "Threads   : " << threads;
    std::ostringstream walls;
    for (const auto& w : s.walls)
        walls << w.name() << " " << w.size() << (w.moving() ? " moving" : "") << ", ";
    log::Line() << "Particles : " << s.fluid.size() << " fluid, " << s.wallParticles() << " wall ("
                << walls.str() << s.physics.dimension << "D, spacing " << s.physics.particleSpacing << " m, support "
                << s.physics.supportRadius << " m)";
    log::Line() << "Schemes   : " << sim.schemesSummary();
    std::string libs;
    for (const auto& l : ModelRegistry::instance().loadedLibraries()) libs += "\n    " + l;
    log::Line() << "Plugins   :" << libs;
}

} // namespace

int main(int argc, char** argv) {
    log::installFatalSignalHandlers();
    po::options_description options("Usage: spindrift [options]\nOptions");
    options.add_options()
        ("help", "print this help and exit")
        ("case", po::value<std::string>()->default_value("."), "case directory")
        ("dryRun", "read the case, build the particles, report counts and schemes, write the start time, stop")
        ("threads", po::value<int>(), "number of OpenMP threads")
        ("listModels", po::value<std::string>()->implicit_value(""),
         "list the available models (of one kind: kernel pressure viscosity integrator boundary)");
    po::variables_map vm;
    try {
        const auto style = po::command_line_style::unix_style | po::command_line_style::allow_long_disguise;
        po::store(po::command_line_parser(argc, argv).options(options).style(style).run(), vm);
        po::notify(vm);
    } catch (const std::exception& e) {
        std::cerr << "spindrift: " << e.what() << "\n" << options << std::endl;
        return 2;
    }
    if (vm.count("help")) {
        std::cout << options << std::endl;
        return 0;
    }
    try {
        if (vm.count("listModels")) {
            listModels(vm["listModels"].as<std::string>());
            return 0;
        }
        stopAtOnceOnSignalsDuringSetUp();
        int threads = 1;
#ifdef _OPENMP
        if (vm.count("threads")) {
            if (vm["threads"].as<int>() < 1) throw std::runtime_error("-threads must be at least 1");
            omp_set_num_threads(vm["threads"].as<int>());
        }
        threads = omp_get_max_threads();
#endif
        Simulation sim(vm["case"].as<std::string>());
        banner(sim, threads);
        if (vm.count("dryRun")) {
            sim.writeInitialState();
            log::info("Dry run: wrote time " + CaseWriter::timeName(sim.scene().time) + "; End");
            return 0;
        }
        const RunSummary r = sim.run();
        std::ostringstream o;
        o << "\nEnd: " << r.steps << " steps to time " << r.endTime << " in " << r.wallSeconds << " s wall time ("
          << r.fluidParticles << " fluid + " << r.wallParticles << " wall particles, "
          << (r.steps > 0 ? 1e6 * r.wallSeconds / (double(r.steps) * std::max<std::size_t>(r.fluidParticles, 1)) : 0.0)
          << " us per particle-step), " << r.writes << " times written, max density error "
          << 100 * r.maxDensityError << "%";
        if (r.averageIterations > 0) o << ", average iterations " << r.averageIterations;
        o << ", peak memory " << peakMemoryMiB() << " MiB";
        log::info(o.str());
        return 0;
    } catch (const InputError& e) {
        log::clearProgress();
        std::cerr << e.what() << std::endl;
        return 1;
    } catch (const std::exception& e) {
        log::clearProgress();
        std::cerr << "spindrift: error: " << e.what() << std::endl;
        return 1;
    }
}
