// spindriftBench — run time against error over model combinations.
//
//   spindriftBench -case tutorials/validation/damBreak2D
//       -vary "pressure.type=wcsph,pcisph,relaxedPbf" -vary "kernel.type=cubicSpline,wendlandC2,sinc2"
//       -vary "particleSpacing=0.0028575,0.00142875" [-quick] [-output DIR] [-threads 1] [-timeout S]
//
// For every combination of the -vary values the case's input is copied to
// <output>/runs/<combination>/, the overrides are applied to the copy's dictionaries
// (BenchSupport.hpp: a key is a dictionary path such as pressure.type, particleSpacing or
// endTime), and the case is run in a child process: its Allrun when it has one (validation
// cases print their error figure as "Figure: name = value"), else the solver. A crash, a
// blow-up or a time-out of one combination is a row of the table, not the end of the bench;
// a combination naming a model whose plugin is not built is an "unavailable" row.
// The case's optional system/benchDict gives `quick { key value; ... }` (overrides applied with
// -quick, before the -vary ones) and `presets { pressure { pcisph { ... } } }` (entries a model
// needs when -vary switches to it).
//
// Output: <output>/bench.csv (combination, status, wall time, steps, average iterations, max
// density error, the case's error figure, Pareto flag), <output>/bench.png (wall time against
// error, Pareto front marked; python3 + matplotlib) and a markdown table on stdout.
//
// -pick "FIGURE<=VALUE" (FIGURE: the case's error figure, e.g. frontRMS, or maxDensityError in
// %): after the runs, the fastest combination whose |FIGURE| is at most VALUE — a point of the
// Pareto front — is written into the case's own dictionaries (system/sphSchemes, and any other
// the combination sets), each under a comment citing its bench.csv row; the file it replaces is
// kept as <file>.orig. No combination meeting the bound: the case is left alone, exit status 1.
//
// Exit status 1 when no combination ran to the end (every run failed, was unstable, timed out or
// unavailable), when an option is out of range (-threads beyond the cores, a negative -timeout,
// an -output inside the case) or when a -vary or -combination key names no entry of the case
// (checked before any run); 2 on a command line that does not parse.
//
// -soak N (Soak.hpp): instead of the table, N random kills (SIGKILL) and restarts of the case,
// each run to the end and compared bit for bit with an uninterrupted run.
#include "BenchSupport.hpp"
#include "Soak.hpp"
#include "Log.hpp"

#include <algorithm>
#include <boost/program_options.hpp>
#include <cmath>
#include <iomanip>
#include <iostream>
#include <limits>
#include <optional>
#include <sstream>
#include <regex>

namespace po = boost::program_options;
namespace fs = std::filesystem;
using namespace spindrift;
using namespace spindrift::bench;

namespace {

struct Row {
    Combination combination;
    std::string name, status, note, figureName;
    EndLine end;
    double figure = std::nan("");
    bool pareto = false;
    double error() const { return std::isfinite(figure) ? figure : 100 * end.maxDensityError; }
};

void markPareto(std::vector<Row>& rows) {
    for (auto& r : rows) {
        if (r.status != "ok" || !std::isfinite(r.error())) continue;
        r.pareto = true;
        for (const auto& o : rows) {
            if (&o == &r || o.status != "ok" || !std::isfinite(o.error())) continue;
            const bool noWorse = o.end.wallSeconds <= r.end.wallSeconds && o.error() <= r.error();
            const bool better = o.end.wallSeconds < r.end.wallSeconds || o.error() < r.error();
            if (noWorse && better) {
                r.pareto = false;
                break;
            }
        }
    }
}

struct PickRequest {
    std::string figure; // the case's figure name, or maxDensityError (%)
    double bound = 0;
};

PickRequest parsePick(const std::string& text) {
    static const std::regex pattern(R"(^\s*([A-Za-z_][A-Za-z0-9_]*)\s*<=\s*([-+0-9.eE]+)\s*$)");
    std::smatch m;
    char* end = nullptr;
    if (std::regex_match(text, m, pattern)) {
        const std::string number = m[2];
        const double bound = std::strtod(number.c_str(), &end);
        if (end && *end == '\0' && std::isfinite(bound) && bound >= 0) return {m[1], bound};
    }
    throw std::runtime_error("-pick \"" + text + "\": expected FIGURE<=VALUE with VALUE >= 0, e.g. -pick \"frontRMS<=0.15\" "
                             "(FIGURE: the case's error figure, or maxDensityError in %)");
}

// |the picked figure| of a row, NaN if the row has none.
double pickedValue(const Row& r, const PickRequest& pick) {
    if (r.status != "ok") return std::nan("");
    if (pick.figure == "maxDensityError") return r.end.found ? 100 * r.end.maxDensityError : std::nan("");
    return r.figureName == pick.figure ? std::abs(r.figure) : std::nan("");
}

std::vector<std::string> keysOf(const std::vector<Combination>& combos) {
    std::vector<std::string> keys;
    for (const auto& c : combos)
        for (const auto& o : c)
            if (std::find(keys.begin(), keys.end(), o.key) == keys.end()) keys.push_back(o.key);
    return keys;
}

std::vector<std::string> csvColumns(const std::vector<std::string>& keys) {
    std::vector<std::string> c{"combination"};
    for (const auto& k : keys) c.push_back(k);
    for (const char* s : {"status", "wallTime_s", "steps", "fluidParticles", "endTime", "avgIterations",
                          "maxDensityError_pct", "figureName", "figure", "pareto", "note"})
        c.emplace_back(s);
    return c;
}

std::vector<std::string> csvValues(const Row& r, const std::vector<std::string>& keys) {
    std::vector<std::string> v{r.name};
    for (const auto& k : keys) {
        std::string value;
        for (const auto& o : r.combination)
            if (o.key == k) value = o.value;
        v.push_back(value);
    }
    const bool ran = r.end.found;
    v.push_back(r.status);
    v.push_back(ran ? csvNumber(r.end.wallSeconds, 4) : "");
    v.push_back(ran ? std::to_string(r.end.steps) : "");
    v.push_back(ran ? std::to_string(r.end.fluidParticles) : "");
    v.push_back(ran ? csvNumber(r.end.endTime) : "");
    v.push_back(ran && r.end.averageIterations > 0 ? csvNumber(r.end.averageIterations, 4) : "");
    v.push_back(ran ? csvNumber(100 * r.end.maxDensityError, 4) : "");
    v.push_back(r.figureName);
    v.push_back(csvNumber(r.figure, 5));
    v.push_back(r.pareto ? "yes" : "");
    v.push_back(r.note);
    return v;
}

// -pick: the fastest row meeting the bound, written into the case. Returns the exit status.
int pickCombination(const PickRequest& pick, const std::vector<Row>& rows, const fs::path& caseDir,
                    const fs::path& csv, const Dictionary* presets, bool quick) {
    const Row* best = nullptr;
    std::size_t bestRow = 0, measured = 0;
    for (std::size_t k = 0; k < rows.size(); ++k) {
        const double v = pickedValue(rows[k], pick);
        if (!std::isfinite(v)) continue;
        ++measured;
        if (v <= pick.bound && (!best || rows[k].end.wallSeconds < best->end.wallSeconds)) {
            best = &rows[k];
            bestRow = k + 1;
        }
    }
    const std::string request = pick.figure + "<=" + csvNumber(pick.bound);
    if (measured == 0) {
        std::string figures;
        for (const auto& r : rows)
            if (!r.figureName.empty() && figures.find(r.figureName) == std::string::npos)
                figures += (figures.empty() ? "" : ", ") + r.figureName;
        std::cerr << "spindriftBench: -pick " << request << ": no run measured " << pick.figure << " (the case's figure: "
                  << (figures.empty() ? "none" : figures) << "; or maxDensityError); the case is unchanged\n";
        return 1;
    }
    if (!best) {
        double closest = std::numeric_limits<double>::infinity();
        for (const auto& r : rows)
            if (std::isfinite(pickedValue(r, pick))) closest = std::min(closest, pickedValue(r, pick));
        std::cerr << "spindriftBench: -pick " << request << ": no combination meets it (the best reached "
                  << closest << "); the case is unchanged\n";
        return 1;
    }
    CaseDictionaries dicts(caseDir);
    dicts.apply(best->combination, presets);
    if (dicts.changedFiles().empty()) {
        std::cout << "Picked for " << request << ": the case as it is (bench.csv row " << bestRow << "); nothing to change"
                  << std::endl;
        return 0;
    }
    std::ostringstream header;
    header << "// spindriftBench -pick \"" << request << "\": the fastest of " << measured << " measured combinations"
           << " meeting it" << (quick ? " (measured with -quick)" : "") << ",\n// " << csv.string() << " row " << bestRow
           << ": " << combinationLabel(best->combination) << ", " << csvNumber(best->end.wallSeconds, 4) << " s, "
           << pick.figure << " " << csvNumber(pickedValue(*best, pick), 5) << ".\n"
           << "// The file it replaced (with its comments) is kept beside it as .orig.\n";
    for (const auto& relative : dicts.changedFiles()) {
        const fs::path file = caseDir / relative, orig = caseDir / (relative + ".orig");
        if (fs::exists(file) && !fs::exists(orig)) fs::copy_file(file, orig); // the first original is kept
    }
    dicts.write(header.str());
    std::cout << "Picked for " << request << ": " << combinationLabel(best->combination) << " ("
              << csvNumber(best->end.wallSeconds, 4) << " s, " << pick.figure << " " << csvNumber(pickedValue(*best, pick), 5)
              << ", bench.csv row " << bestRow << ") written into";
    for (const auto& relative : dicts.changedFiles()) std::cout << " " << (caseDir / relative).string();
    std::cout << std::endl;
    return 0;
}

} // namespace

int main(int argc, char** argv) {
    po::options_description options(
        "Usage: spindriftBench -case DIR [-vary key=v1,v2,...]... [options]\n"
        "Runs a case for every combination of the -vary values and tabulates wall time against error.\nOptions");
    options.add_options()
        ("help", "print this help and exit")
        ("case", po::value<std::string>(), "the case to copy and run (required)")
        ("vary", po::value<std::vector<std::string>>()->composing(),
         "key=v1,v2,... : a dictionary entry and its values (repeatable), e.g. pressure.type=wcsph,pcisph")
        ("combination", po::value<std::vector<std::string>>()->composing(),
         "\"key=value key=value ...\": one more combination (repeatable), run besides the -vary product")
        ("quick", "apply the case's system/benchDict 'quick' overrides (short runs for CI)")
        ("output", po::value<std::string>(), "output directory (default ./bench-<caseName>)")
        ("threads", po::value<int>()->default_value(1), "OpenMP threads per run (timings: keep 1)")
        ("timeout", po::value<double>()->default_value(0), "seconds after which a run is stopped (0 = none)")
        ("keep", "keep every run's directory under <output>/runs")
        ("casePlots", "let each run's Allrun draw its plot (skipped by default: SPINDRIFT_NO_PLOT=1)")
        ("noPlot", "do not draw bench.png")
        ("pick", po::value<std::string>(),
         "\"FIGURE<=VALUE\": write the fastest combination meeting the bound into the case's dictionaries "
         "(the replaced files kept as .orig)")
        ("list", "list the combinations and stop")
        ("soak", po::value<int>(),
         "N: run the case once uninterrupted, then N times killed (SIGKILL) at a random moment, restarted "
         "(startFrom latestTime) and run to the end, each end state compared bit for bit; with at most one "
         "-combination (overrides for every run)")
        ("seed", po::value<std::uint64_t>()->default_value(1), "-soak: seed of the random kill moments");
    po::variables_map vm;
    if (const auto status = parseCommandLine(argc, argv, options, "spindriftBench", vm)) return *status;
    if (!vm.count("case")) {
        std::cerr << "spindriftBench: -case is required\n" << options << std::endl;
        return 2;
    }
    try {
        log::setQuiet(true);
        const fs::path caseDir = fs::absolute(vm["case"].as<std::string>());
        if (!fs::is_directory(caseDir / "system"))
            throw std::runtime_error("'" + caseDir.string() + "' is not a case (no system/)");
        const std::string caseName = fs::weakly_canonical(caseDir).filename().string();
        checkThreadsAndTimeout(vm);
        const auto combos = requestedCombinations(vm);
        std::optional<PickRequest> pick;
        if (vm.count("pick")) pick = parsePick(vm["pick"].as<std::string>());
        if (vm.count("list")) {
            const auto names = uniqueNames(combos);
            for (std::size_t k = 0; k < combos.size(); ++k) std::cout << names[k] << "  " << combinationLabel(combos[k]) << '\n';
            return 0;
        }
        const auto keys = keysOf(combos);
        const fs::path output = fs::absolute(vm.count("output") ? vm["output"].as<std::string>() : "bench-" + caseName);
        {
            // each run copies the case's input: an output inside the case would copy the runs into themselves
            const fs::path c = fs::weakly_canonical(caseDir), o = fs::weakly_canonical(output);
            const auto [end, rest] = std::mismatch(c.begin(), c.end(), o.begin(), o.end());
            if (end == c.end())
                throw std::runtime_error("-output " + output.string() + (o == c ? " is the case itself" : " lies inside the case " + c.string()) +
                                         ": each run copies the case's input, which would then hold the runs; give a "
                                         "directory outside the case (-output)");
        }
        const int threads = vm["threads"].as<int>();
        const double timeout = vm["timeout"].as<double>();
        const bool quick = vm.count("quick") > 0, keep = vm.count("keep") > 0;

        Dictionary benchDict("benchDict");
        if (fs::exists(caseDir / "system/benchDict")) benchDict = Dictionary::fromFile(caseDir / "system/benchDict");
        const Dictionary* presets = benchDict.findDict("presets");
        Combination quickOverrides;
        if (quick) {
            if (const Dictionary* q = benchDict.findDict("quick")) {
                quickOverrides = overridesFrom(*q);
            } else {
                std::cerr << "spindriftBench: warning: " << caseName
                          << " has no system/benchDict 'quick' settings; -quick runs it as it is\n";
            }
        }
        // every override names an entry of the case (a misspelt -vary key would fail every run)
        for (const auto& c : combos) {
            CaseDictionaries dicts(caseDir);
            dicts.apply(quickOverrides, presets);
            dicts.apply(c, presets);
        }

        const fs::path exeDir = executableDirectory();
        const fs::path solver = exeDir / "spindrift";
        const char* envDir = std::getenv("SPINDRIFT_DIR");
        const std::string spindriftDir = envDir ? envDir : SPINDRIFT_SOURCE_DIR;
        const bool hasAllrun = fs::exists(caseDir / "Allrun");
        if (vm.count("soak")) {
            SoakSettings soak;
            soak.count = vm["soak"].as<int>();
            if (soak.count < 1) throw std::runtime_error("-soak: the number of runs must be at least 1");
            if (combos.size() != 1) throw std::runtime_error("-soak takes at most one -combination (no -vary)");
            soak.seed = vm["seed"].as<std::uint64_t>();
            soak.caseDir = caseDir;
            soak.output = output;
            soak.solver = solver;
            soak.overrides = quickOverrides;
            soak.overrides.insert(soak.overrides.end(), combos.front().begin(), combos.front().end());
            soak.presets = presets;
            soak.threads = threads;
            soak.env = {"OMP_NUM_THREADS=" + std::to_string(threads), "SPINDRIFT_DIR=" + spindriftDir};
            return runSoak(soak);
        }
        fs::create_directories(output / "runs");

        std::cout << "spindriftBench: " << caseName << ", " << combos.size() << " combination(s)"
                  << (quick ? " (quick)" : "") << ", " << threads << " thread(s) per run, output " << output.string()
                  << std::endl;
        std::vector<Row> rows;
        CsvWriter partial(output / "bench.csv", csvColumns(keys));
        const auto names = uniqueNames(combos);
        for (std::size_t k = 0; k < combos.size(); ++k) {
            const Combination& c = combos[k];
            Row row;
            row.combination = c;
            row.name = names[k];
            const fs::path runDir = output / "runs" / row.name;
            printLabel(c);
            const std::string missing = unavailableModel(c);
            if (!missing.empty()) {
                row.status = "unavailable";
                row.note = missing + " is not built";
            } else {
                try {
                    fs::remove_all(runDir);
                    copyCaseInput(caseDir, runDir);
                    CaseDictionaries dicts(runDir);
                    dicts.apply(quickOverrides, presets);
                    dicts.apply(c, presets);
                    dicts.write();
                    std::vector<std::string> env{"OMP_NUM_THREADS=" + std::to_string(threads),
                                                 "SPINDRIFT_BIN=" + exeDir.string(),
                                                 "SPINDRIFT_DIR=" + spindriftDir,
                                                 "PATH=" + exeDir.string() + ":" + (std::getenv("PATH") ? std::getenv("PATH") : "")};
                    if (!vm.count("casePlots")) env.push_back("SPINDRIFT_NO_PLOT=1");
                    const fs::path solverLog = runDir / "log.spindrift";
                    ProcessResult pr;
                    if (hasAllrun) pr = runProcess({"bash", "./Allrun"}, runDir, runDir / "log.Allrun", env, timeout);
                    else
                        pr = runProcess({solver.string(), "-case", ".", "-threads", std::to_string(threads)}, runDir,
                                        solverLog, env, timeout);
                    const RunOutcome outcome = runOutcome(pr, solverLog, timeout);
                    row.status = outcome.status;
                    row.note = outcome.note;
                    row.end = outcome.end;
                    // a case's Allrun says why it failed when the solver did not (or finished)
                    if (row.status == "failed" && (row.note.empty() || row.end.found))
                        row.note = lastLine(runDir / "log.Allrun");
                    if (hasAllrun) {
                        const std::string figure = findLine(runDir / "log.Allrun", "Figure: ");
                        static const std::regex pattern(R"(Figure: (\S+) = ([^ ]+))");
                        std::smatch m;
                        if (std::regex_search(figure, m, pattern)) {
                            row.figureName = m[1];
                            row.figure = std::strtod(m[2].str().c_str(), nullptr);
                        }
                    }
                } catch (const std::exception& e) {
                    row.status = "failed";
                    row.note = e.what();
                }
                if (!keep) fs::remove_all(runDir);
            }
            std::cout << row.status;
            if (row.end.found) std::cout << "  " << std::setprecision(4) << row.end.wallSeconds << " s";
            if (std::isfinite(row.figure)) std::cout << "  " << row.figureName << " " << row.figure;
            if (!row.note.empty() && row.status != "ok") std::cout << "  (" << row.note << ")";
            std::cout << std::endl;
            partial.row(csvValues(row, keys));
            rows.push_back(row);
        }
        if (!keep) fs::remove(output / "runs");
        markPareto(rows);
        {
            CsvWriter csv(output / "bench.csv", csvColumns(keys));
            for (const auto& r : rows) csv.row(csvValues(r, keys));
        }

        // markdown table
        std::cout << "\n| combination | status | wall time [s] | steps | avg. iterations | max density error [%] | "
                  << (rows.empty() || rows.front().figureName.empty() ? "figure" : rows.front().figureName)
                  << " | Pareto |\n|---|---|---|---|---|---|---|---|\n";
        for (const auto& r : rows) {
            auto v = csvValues(r, keys);
            const std::size_t k = 1 + keys.size();
            std::cout << "| " << combinationLabel(r.combination) << " | " << v[k] << " | " << v[k + 1] << " | " << v[k + 2]
                      << " | " << v[k + 5] << " | " << v[k + 6] << " | " << v[k + 8] << " | " << v[k + 9] << " |\n";
        }
        std::cout << "\nTable: " << (output / "bench.csv").string() << std::endl;

        if (!vm.count("noPlot") &&
            runPlotScript("spindriftBench", "spindriftBenchPlot.py",
                          {(output / "bench.csv").string(), (output / "bench.png").string(), caseName + (quick ? " (quick)" : "")},
                          output, 120))
            std::cout << "Plot: " << (output / "bench.png").string() << std::endl;
        const auto ok = std::count_if(rows.begin(), rows.end(), [](const Row& r) { return r.status == "ok"; });
        if (ok == 0) {
            std::cerr << "spindriftBench: error: none of the " << rows.size()
                      << " combination(s) ran to the end (statuses and reasons above and in " << (output / "bench.csv").string()
                      << ")" << std::endl;
            return 1;
        }
        if (pick) return pickCombination(*pick, rows, caseDir, output / "bench.csv", presets, quick);
        return 0;
    } catch (const std::exception& e) {
        std::cerr << "spindriftBench: error: " << e.what() << std::endl;
        return 1;
    }
}
