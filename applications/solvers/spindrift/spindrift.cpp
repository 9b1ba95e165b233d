// spindrift — the SPH solver application.
//
//   spindrift [-case DIR] [-dryRun] [-force] [-threads N] [-listModels [kind]] [-version] [-help]
//   spindrift -postProcess [-func NAME] [-time RANGE] [-case DIR]
//
// Options are spelt as OpenFOAM's (-case DIR); the GNU spellings (--case DIR, --case=DIR) are
// aliases. A misspelt option is refused with the closest one ("did you mean '-dryRun'?"),
// exit status 1.
#include "BuildInfo.hpp"
#include "Error.hpp"
#include "Log.hpp"
#include "ModelRegistry.hpp"
#include "PostProcess.hpp"
#include "RunLog.hpp"
#include "Simulation.hpp"

#include <boost/program_options.hpp>
#include <sys/resource.h>
#include <unistd.h>
#include <cstdlib>
#include <cstring>
#include <iostream>
#ifdef _OPENMP
#include <omp.h>
#endif

namespace po = boost::program_options;
using namespace spindrift;

// The OpenMP runtime's wait policy, chosen before the runtime starts. libgomp reads
// OMP_WAIT_POLICY and GOMP_SPINCOUNT once, when it is loaded (before main()); by default a thread
// that reaches the end of a parallel loop first spins up to 300,000 times before it sleeps. On a
// busy machine (a laptop, a shared server, ctest running tests side by side) those spinning
// threads take the cores from the threads still working: issue 34 measured a 2-core host with
// other work running take 35-53 s with every core against 3-7.5 s with one thread. Unless the
// user chose (OMP_WAIT_POLICY or GOMP_SPINCOUNT set), the spin is bounded to
// openMPDefaultSpinCount, measured (README, "Threads"; damBreak2D to 0.02 s, medians of 5 and 3):
// on a machine as if idle 0.79 s against the runtime's default 0.72 s (passive: 1.96 s, 300
// spins: 1.35 s), on one loaded by others (load 10-15) 5.8 s against 28 s (10,000 spins: 24 s,
// passive 3.3 s, one thread 3.1 s). The runtime has read its environment by the time any code
// of ours runs (the executable's .preinit_array runs before libc has even set up the
// environment), so the process starts itself again with the variable set: execv of
// /proc/self/exe, the same pid and arguments, about 0.05 s. Not for a run on one thread (no
// thread ever waits: OMP_NUM_THREADS=1, as ctest's case tests and the bench's runs set it,
// -threads 1, or one core), which starts as fast as before.
namespace {
constexpr const char* openMPDefaultSpinCount = "1000";
constexpr const char* openMPWaitMarker = "SPINDRIFT_OPENMP_WAIT_DEFAULT"; // set for the restarted process only
bool openMPWaitDefaulted = false; // the spin bound above is in force (the user chose none)

// Whether the command line or the environment asks for one thread (or the machine has one core).
bool oneThread(int argc, char** argv) {
#ifdef _OPENMP
    if (omp_get_num_procs() <= 1) return true;
#endif
    if (const char* n = std::getenv("OMP_NUM_THREADS"); n && std::string(n) == "1") return true;
    for (int k = 1; k < argc; ++k) {
        const std::string a = argv[k];
        if ((a == "-threads" || a == "--threads") && k + 1 < argc && std::string(argv[k + 1]) == "1") return true;
        if (a == "-threads=1" || a == "--threads=1") return true;
    }
    return false;
}

void chooseOpenMPWaitPolicy(int argc, char** argv) {
#ifdef _OPENMP
    if (std::getenv(openMPWaitMarker)) { // the restarted process
        ::unsetenv(openMPWaitMarker);
        const char* spin = std::getenv("GOMP_SPINCOUNT");
        openMPWaitDefaulted = spin && std::string(spin) == openMPDefaultSpinCount;
        return;
    }
    if (std::getenv("OMP_WAIT_POLICY") || std::getenv("GOMP_SPINCOUNT")) return; // the user's choice
    if (oneThread(argc, argv)) return;
    // under valgrind /proc/self/exe is valgrind's tool, which refuses to be started so
    if (const char* preload = std::getenv("LD_PRELOAD"); preload && std::strstr(preload, "vgpreload")) return;
    if (::setenv("GOMP_SPINCOUNT", openMPDefaultSpinCount, 1) != 0 || ::setenv(openMPWaitMarker, "1", 1) != 0) return;
    ::execv("/proc/self/exe", argv);
    // no restart (no /proc): this process keeps the runtime's default, and says so
    ::unsetenv("GOMP_SPINCOUNT");
    ::unsetenv(openMPWaitMarker);
#else
    (void)argc;
    (void)argv;
#endif
}
} // namespace

namespace {

// "OMP_WAIT_POLICY passive (environment)", "GOMP_SPINCOUNT 10000 (spindrift's default)", ...
std::string openMPWaitDescription() {
    if (openMPWaitDefaulted) return std::string("GOMP_SPINCOUNT ") + openMPDefaultSpinCount + " (spindrift's default)";
    std::string d;
    for (const char* name : {"OMP_WAIT_POLICY", "GOMP_SPINCOUNT"})
        if (const char* v = std::getenv(name)) d += (d.empty() ? "" : ", ") + std::string(name) + " " + v;
    return d.empty() ? "the OpenMP runtime's default" : d + " (environment)";
}

// The options, each once: what the parser accepts and what -help prints are made from this.
struct CommandLineOption {
    std::string name;             // without the dash
    std::string argument;         // as -help shows it: "<dir>" (required), "[kind]" (optional), "" (none)
    std::string description;
    const po::value_semantic* value; // owned by the options_description once added
};

std::vector<CommandLineOption> commandLineOptions() {
    std::string kinds;
    for (const auto& kind : ModelRegistry::kinds()) kinds += (kinds.empty() ? "" : " ") + kind;
    return {
        {"case", "<dir>", "case directory (default: the current directory)",
         po::value<std::string>()->default_value(".")},
        {"dryRun", "",
         "read the case, build the particles, report counts, schemes and loaded plugins, write the start "
         "time, stop",
         new po::untyped_value(true)},
        {"force", "",
         "run a case even when its particle estimate exceeds the memory available (refused otherwise)",
         new po::untyped_value(true)},
        {"threads", "<N>",
         "number of OpenMP threads, at most the cores this process may use (default: OMP_NUM_THREADS, else "
         "every core)",
         po::value<int>()},
        {"listModels", "[kind]", "list the available models, or those of one kind: " + kinds,
         po::value<std::string>()->implicit_value("")},
        {"postProcess", "",
         "run the case's function objects (controlDict 'functions') over its written times without solving, "
         "writing postProcessing/<name>/<first time>/ as a run does",
         new po::untyped_value(true)},
        {"func", "<name>", "with -postProcess: only the function object of that name", po::value<std::string>()},
        {"time", "<range>",
         "with -postProcess: the written times to process, e.g. 0.5, 0.1:0.3, :0.2, 0.4:, 0,0.5 (default: all)",
         po::value<std::string>()},
        {"version", "", "print the version and the build (precision, type, flags) and exit",
         new po::untyped_value(true)},
        {"help", "", "print this help and exit", new po::untyped_value(true)},
    };
}

// Words of 'text' on lines of at most 'width' characters, the lines after the first indented.
std::string wrap(const std::string& text, std::size_t indent, std::size_t width) {
    std::istringstream words(text);
    std::string out, word;
    std::size_t column = indent;
    while (words >> word) {
        if (column > indent && column + 1 + word.size() > width) {
            out += '\n' + std::string(indent, ' ');
            column = indent;
        } else if (column > indent) {
            out += ' ';
            ++column;
        }
        out += word;
        column += word.size();
    }
    return out;
}

void printHelp(const std::vector<CommandLineOption>& options) {
    std::size_t column = 0;
    for (const auto& o : options) column = std::max(column, o.name.size() + 1 + (o.argument.empty() ? 0 : o.argument.size() + 1));
    column += 4; // two spaces before, two after
    std::cout << "Usage: spindrift [OPTIONS]\n"
              << "Runs the case in the current directory (or the one -case names) from its start time to its\n"
              << "endTime; output in time directories and <case>.pvd, the log on stdout.\n\nOptions:\n";
    for (const auto& o : options) {
        std::string left = "  -" + o.name + (o.argument.empty() ? "" : " " + o.argument);
        left.resize(column, ' ');
        std::cout << left << wrap(o.description, column, 95) << '\n';
    }
    std::cout << "\nThe GNU spellings are aliases: --case DIR, --case=DIR, --dryRun, ...\n";
}

void printVersion() {
    std::cout << "spindrift " << build::version;
    if (*build::gitDescribe) std::cout << " (git " << build::gitDescribe << ")";
    std::cout << "\nPrecision  : " << build::precision << "\nBuild type : " << build::type
              << "\nCompiler   : " << build::compiler << "\nFlags      : " << build::flags << "\nOpenMP     : ";
#ifdef _OPENMP
    const int threads = omp_get_max_threads();
    std::cout << "on (" << threads << (threads == 1 ? " thread" : " threads") << " here by default; wait: "
              << openMPWaitDescription() << ")";
#else
    std::cout << "off";
#endif
    std::cout << "\nSanitizers : " << build::sanitizers << '\n';
}

// An option the parser does not know: "spindrift: unknown option '-dryrun'; did you mean
// '-dryRun'?" on stderr.
std::string unknownOptionMessage(const std::string& given, const std::vector<CommandLineOption>& options) {
    std::string word = given.substr(given.find_first_not_of('-') == std::string::npos ? given.size()
                                                                                     : given.find_first_not_of('-'));
    word = word.substr(0, word.find('='));
    std::vector<std::string> names;
    for (const auto& o : options) names.push_back(o.name);
    const std::string closest = closestMatch(word, names);
    std::string message = "spindrift: unknown option '" + given + "'";
    if (!closest.empty()) message += "; did you mean '-" + closest + "'?";
    return message;
}

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
    char host[256] = "?";
    gethostname(host, sizeof host - 1);
    return localTime("%Y-%m-%d %H:%M:%S") + " on " + host + ", pid " + std::to_string(getpid());
}

void banner(const Simulation& sim, const std::string& threads) {
    const auto& s = const_cast<Simulation&>(sim).scene();
    log::Line() << "Spindrift : " << build::version << (*build::gitDescribe ? std::string(" (git ") + build::gitDescribe + ")" : "")
                << ", " << build::precision << ", " << build::type;
    log::Line() << "Started   : " << startedLine();
    log::Line() << "Case      : " << sim.caseFiles().dir.string();
    log::Line() << "Threads   : " << threads;
    std::ostringstream systems;
    for (const auto& p : s.systems)
        systems << p->name() << " (" << roleName(p->role) << (p->movingBoundary() ? ", moving" : "") << ") "
                << p->ownedSize() << ", ";
    log::Line() << "Particles : " << s.particlesOf(SystemRole::fluid) << " fluid, "
                << s.particlesOf(SystemRole::wall) + s.particlesOf(SystemRole::body) << " boundary (" << systems.str()
                << s.physics.dimension << "D, spacing " << s.physics.particleSpacing << " m, support "
                << s.constants.supportRadius << " m)";
    log::Line() << "Schemes   : " << sim.schemesSummary();
    std::string libs;
    for (const auto& l : ModelRegistry::instance().loadedLibraries()) libs += "\n    " + l;
    log::Line() << "Plugins   :" << libs;
}

// Sets the OpenMP thread count (-threads N, else OMP_NUM_THREADS, else every core) and returns it
// for the banner, with the wait policy. More threads than the cores this process may use
// (omp_get_num_procs: the CPUs of its affinity mask, as nproc counts them) only wait for each
// other, and thousands of them fail in the runtime: -threads N beyond the cores is refused,
// OMP_NUM_THREADS beyond them is capped with a warning.
std::string chooseThreadCount(const po::variables_map& vm) {
#ifdef _OPENMP
    const int cores = omp_get_num_procs();
    if (vm.count("threads")) {
        const int n = vm["threads"].as<int>();
        if (n < 1) throw std::runtime_error("-threads must be at least 1");
        if (n > cores)
            throw std::runtime_error("-threads " + std::to_string(n) + ": this process may use " +
                                     std::to_string(cores) + (cores == 1 ? " core" : " cores") +
                                     "; more threads only wait for each other: use -threads " +
                                     std::to_string(cores) + " or fewer");
        omp_set_num_threads(n);
    } else if (omp_get_max_threads() > cores) {
        log::warning("OMP_NUM_THREADS asks for " + std::to_string(omp_get_max_threads()) + " threads; this process may use " +
                     std::to_string(cores) + (cores == 1 ? " core" : " cores") + ": running " +
                     std::to_string(cores) + (cores == 1 ? " thread" : " threads"));
        omp_set_num_threads(cores);
    }
    return std::to_string(omp_get_max_threads()) + " (OpenMP wait: " + openMPWaitDescription() + ")";
#else
    (void)vm;
    return "1 (built without OpenMP)";
#endif
}

} // namespace

int main(int argc, char** argv) {
    chooseOpenMPWaitPolicy(argc, argv); // first: it may start the process again
    log::installFatalSignalHandlers();
    const std::vector<CommandLineOption> optionTable = commandLineOptions();
    po::options_description options;
    for (const auto& o : optionTable) options.add_options()(o.name.c_str(), o.value, o.description.c_str());
    po::variables_map vm;
    try {
        // -case (OpenFOAM's spelling, "long disguise") and --case both name the long option
        const auto style = po::command_line_style::unix_style | po::command_line_style::allow_long_disguise;
        const po::parsed_options parsed = po::command_line_parser(argc, argv).options(options).style(style).run();
        for (const auto& o : parsed.options) // a word that is no option's value (the parser keeps it aside)
            if (o.string_key.empty()) {
                const std::string word = o.original_tokens.empty() ? std::string() : o.original_tokens.front();
                std::cerr << "spindrift: unexpected argument '" << word << "' (a case directory is given with "
                          << "-case " << word << ")\nRun 'spindrift -help' for the options." << std::endl;
                return 1;
            }
        po::store(parsed, vm);
        po::notify(vm);
    } catch (const po::unknown_option& e) {
        std::cerr << unknownOptionMessage(e.get_option_name(), optionTable)
                  << "\nRun 'spindrift -help' for the options." << std::endl;
        return 1;
    } catch (const std::exception& e) {
        // Boost names an option '--case' whatever the spelling: name it as -help does
        std::string message = e.what();
        for (std::size_t at; (at = message.find("'--")) != std::string::npos;) message.erase(at + 1, 1);
        std::cerr << "spindrift: " << message << "\nRun 'spindrift -help' for the options." << std::endl;
        return 1;
    }
    if (vm.count("help")) {
        printHelp(optionTable);
        return 0;
    }
    if (vm.count("version")) {
        printVersion();
        return 0;
    }
    try {
        if (vm.count("listModels")) {
            listModels(vm["listModels"].as<std::string>());
            return 0;
        }
        const bool postProcessing = vm.count("postProcess") > 0;
        for (const char* o : {"func", "time"})
            if (vm.count(o) && !postProcessing)
                throw std::runtime_error(std::string("-") + o + " selects what -postProcess runs: use it with -postProcess");
        if (postProcessing && vm.count("dryRun")) throw std::runtime_error("-postProcess and -dryRun: give one of them");
        stopAtOnceOnSignalsDuringSetUp();
        const std::string threads = chooseThreadCount(vm);
        Simulation sim(vm["case"].as<std::string>(), vm.count("force") > 0);
        banner(sim, threads);
        if (postProcessing) {
            PostProcessRequest request;
            if (vm.count("func")) request.function = vm["func"].as<std::string>();
            if (vm.count("time")) request.times = vm["time"].as<std::string>();
            postProcess(sim, request);
            return 0;
        }
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
        if (r.removedParticles > 0) o << ", " << r.removedParticles << " fluid particles removed (they left the domain)";
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
