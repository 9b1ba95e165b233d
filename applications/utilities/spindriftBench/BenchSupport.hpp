// Spindrift — what spindriftBench and spindriftStress share: their command line, model
// combinations from `-vary "key=v1,v2"` and `-combination` options, dictionary overrides on a
// copy of a case, running the solver (or a case's Allrun) as a child process with a time limit,
// judging how it ended from its exit and its log (final "End:" line, blow-up message), CSV
// output and the python3/matplotlib plotting scripts.
//
// Overrides. A key names an entry by its dictionary path, e.g. `pressure.type` (sphSchemes'
// pressure sub-dictionary), `particleSpacing` (constant/fluidProperties), `endTime`
// (system/controlDict). It is looked up in system/controlDict, system/sphSchemes,
// system/sphSolution, constant/fluidProperties and constant/geometry: the file holding the
// full path is used (an error if several do); if none does, the file holding the parent
// dictionary (an error if none or several; a top-level key then needs an existing entry).
// Setting `<model>.type` to another model replaces that sub-dictionary by `type <name>;` plus
// the entries given for that model in the presets (benchDict `presets { pressure { pcisph
// { ... } } }`), since the old model's keywords mean nothing to the new one. Type overrides are
// applied before the other overrides of a combination.
#pragma once

#include "Case.hpp"
#include "Dictionary.hpp"

#include <boost/program_options.hpp>
#include <csignal>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace spindrift::bench {

struct Override {
    std::string key, value;
};
using Combination = std::vector<Override>;

// "key=v1,v2,v3" → key and values (values may hold spaces and parentheses, not commas).
struct VaryOption {
    std::string key;
    std::vector<std::string> values;
};
VaryOption parseVary(const std::string& text);

// "kernel.type=sinc2 pressure.type=isobaric": one explicit combination (values without spaces).
Combination parseCombination(const std::string& text);

// The entries of a dictionary of `key value;` lines (no sub-dictionaries) as overrides, e.g.
// benchDict's `quick { endTime 0.1; particleSpacing 0.004; }`.
Combination overridesFrom(const Dictionary& dict);

// Cartesian product, the first option outermost; one empty combination for no options.
std::vector<Combination> combinations(const std::vector<VaryOption>& options);

// Parses a utility's command line (single-dash long options, as OpenFOAM's) into 'vm'. Returns
// the exit status when the utility is done: 0 after printing the help (-help), 2 after printing
// the error and the help; nothing when it goes on.
std::optional<int> parseCommandLine(int argc, char** argv, const boost::program_options::options_description& options,
                                    const std::string& utility, boost::program_options::variables_map& vm);
// The cores this process may use (its CPU affinity mask, as nproc counts them; at least 1).
int availableCores();
// Checks the options both utilities share: -threads (1 to availableCores(): more threads than
// cores only wait for each other, and thousands fail in the OpenMP runtime) and -timeout (0 =
// none, else positive seconds). Throws std::runtime_error naming the option.
void checkThreadsAndTimeout(const boost::program_options::variables_map& vm);

// The combinations a command line asks for: the product of its -vary options, plus its
// -combination options (alone when there is no -vary).
std::vector<Combination> requestedCombinations(const boost::program_options::variables_map& vm);

// "wcsph_cubicSpline_0.01": values joined by '_', characters unsafe in file names replaced.
std::string combinationName(const Combination& c);
// Names for a list of combinations: combinationName() when those are distinct, else every
// override qualified by its key ("viscosity-pereaCordero_integrator-pereaCordero").
std::vector<std::string> uniqueNames(const std::vector<Combination>& combos);
// "pressure.type=wcsph kernel.type=cubicSpline"
std::string combinationLabel(const Combination& c);
// Starts a combination's line of progress on stdout: its label, padded (the outcome follows).
void printLabel(const Combination& c);

// Model kinds named by `<sub-dictionary>.type` keys (kernel, pressure, ...): the kind whose
// availability decides whether a combination can run; empty for other keys.
std::string kindOfTypeKey(const std::string& key);
// The first type override in 'c' whose plugin is not available, as "kind 'name'"; empty if all are.
std::string unavailableModel(const Combination& c);

// The five dictionaries of a case, editable and written back.
class CaseDictionaries {
public:
    explicit CaseDictionaries(const std::filesystem::path& caseDir);
    // Applies one override (see the header comment); 'presets' may be null.
    void apply(const Override& o, const Dictionary* presets);
    // Applies a combination: type overrides first.
    void apply(const Combination& c, const Dictionary* presets);
    // Writes the dictionaries that changed, each under a header comment.
    void write(const std::string& header = "// written by spindrift's bench utilities (overrides applied)\n") const;
    // The case-relative paths of the dictionaries that changed (e.g. "system/sphSchemes").
    std::vector<std::string> changedFiles() const;
    Dictionary& file(const std::string& relative); // e.g. "system/controlDict"

private:
    struct File {
        std::string relative;
        Dictionary dict;
        bool present = false, changed = false;
    };
    std::filesystem::path dir_;
    std::vector<File> files_;
};

// Sets 'path' (dotted) in 'dict' to 'value', creating the last component; intermediate
// dictionaries must exist. Returns false if an intermediate dictionary is missing.
bool setPath(Dictionary& dict, const std::string& path, const std::string& value);
bool hasPath(const Dictionary& dict, const std::string& path);
const Dictionary* findPath(const Dictionary& dict, const std::string& path); // a sub-dictionary
// Replaces the sub-dictionary at 'path' by 'replacement'.
void setDictPath(Dictionary& dict, const std::string& path, const Dictionary& replacement);

// Runs argv in 'workDir' with stdout and stderr to 'logFile', extra environment 'env'
// (NAME=value), in its own process group; after 'timeoutSeconds' (0 = none) the group is sent
// 'timeoutSignal' (SIGTERM, then SIGKILL 5 s later; SIGKILL: at once, as the soak's kills).
// Returns the exit status (128 + signal if killed) and whether it timed out.
struct ProcessResult {
    int status = -1;
    bool timedOut = false;
    double seconds = 0;
};
ProcessResult runProcess(const std::vector<std::string>& argv, const std::filesystem::path& workDir,
                         const std::filesystem::path& logFile, const std::vector<std::string>& env,
                         double timeoutSeconds, int timeoutSignal = SIGTERM);

// The solver's final line "End: N steps to time T in W s wall time (...), K times written,
// max density error E%[, average iterations A]".
struct EndLine {
    bool found = false;
    long steps = 0;
    double endTime = 0, wallSeconds = 0, maxDensityError = 0, averageIterations = 0;
    long fluidParticles = 0;
};
EndLine parseEndLine(const std::filesystem::path& logFile);
// The first line of a log holding 'needle' (empty if none).
std::string findLine(const std::filesystem::path& logFile, const std::string& needle);
// The last non-empty line of a log.
std::string lastLine(const std::filesystem::path& logFile);

// How a run ended, from its exit status and the solver's log.
struct RunOutcome {
    std::string status; // ok | unstable | failed | timeout
    std::string note;   // why it is not ok: the time limit, the blow-up message, the log's last line
    EndLine end;        // the solver's final line, when it wrote one
};
struct OutcomeRules {
    bool endLine = true;   // the solver writes an "End:" line (false for -dryRun)
    bool anyBlowUp = false; // a blow-up the solver recovered from (onBlowUp reduceDeltaT) is unstable too
};
// timeout when the time limit stopped it; unstable when the log reports a blow-up (and no End:
// line, unless rules.anyBlowUp); ok on exit 0 with the End: line (when expected); else failed,
// with the log's last line as the note.
RunOutcome runOutcome(const ProcessResult& process, const std::filesystem::path& solverLog, double timeoutSeconds,
                      OutcomeRules rules = {});

// Rows of a postProcessing .dat file (every start-time folder of postProcessing/<name>/ in
// time order): the header's column names (Time first) and the numbers.
struct Table {
    std::vector<std::string> columns;
    std::vector<std::vector<double>> rows;
    int column(const std::string& name) const; // -1 if absent
    std::vector<double> values(const std::string& name) const;
};
Table readPostProcessing(const std::filesystem::path& caseDir, const std::string& name);

// CSV with a fixed header, rows appended and flushed one at a time.
class CsvWriter {
public:
    CsvWriter(const std::filesystem::path& file, const std::vector<std::string>& columns);
    void row(const std::vector<std::string>& values);
    std::size_t columns() const { return columns_; }
private:
    std::filesystem::path file_;
    std::size_t columns_;
};
std::string csvNumber(double v, int precision = 6);

// Directory of the running executable (where the solver and the plotting scripts are).
std::filesystem::path executableDirectory();
// A python3 that imports matplotlib ($SPINDRIFT_PYTHON, python3, /usr/bin/python3), or empty.
std::string findPython();
// A plotting script shipped with the utilities: next to the executable, in
// ../share/spindrift/, or in the source tree.
std::filesystem::path findScript(const std::string& name);
// Runs the plotting script 'script' with 'arguments' in 'output' (log in output/log.plot).
// Returns whether it drew its plots; warns on stderr, as 'utility', when it could not.
bool runPlotScript(const std::string& utility, const std::string& script, const std::vector<std::string>& arguments,
                   const std::filesystem::path& output, double timeoutSeconds);

} // namespace spindrift::bench
