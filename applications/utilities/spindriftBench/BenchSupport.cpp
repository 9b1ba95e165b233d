#include "BenchSupport.hpp"

#include "ModelRegistry.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <fcntl.h>
#include <sched.h>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <regex>
#include <set>
#include <signal.h>
#include <sstream>
#include <sys/wait.h>
#include <thread>
#include <unistd.h>

extern char** environ;

namespace fs = std::filesystem;
namespace po = boost::program_options;

namespace spindrift::bench {
namespace {

std::string trim(const std::string& s) {
    const auto b = s.find_first_not_of(" \t\r\n");
    if (b == std::string::npos) return "";
    const auto e = s.find_last_not_of(" \t\r\n");
    return s.substr(b, e - b + 1);
}

std::vector<std::string> split(const std::string& s, char sep) {
    std::vector<std::string> out;
    std::string item;
    std::istringstream in(s);
    while (std::getline(in, item, sep)) out.push_back(item);
    if (!s.empty() && s.back() == sep) out.emplace_back();
    return out;
}

std::pair<std::string, std::string> splitLast(const std::string& path) {
    const auto dot = path.rfind('.');
    if (dot == std::string::npos) return {"", path};
    return {path.substr(0, dot), path.substr(dot + 1)};
}

bool isNumber(const std::string& s) {
    if (s.empty()) return false;
    char* end = nullptr;
    std::strtod(s.c_str(), &end);
    return end && *end == '\0';
}

} // namespace

VaryOption parseVary(const std::string& text) {
    const auto eq = text.find('=');
    if (eq == std::string::npos || eq == 0)
        throw std::runtime_error("-vary \"" + text + "\": expected key=value1,value2,... (e.g. pressure.type=wcsph,pcisph)");
    VaryOption v;
    v.key = trim(text.substr(0, eq));
    for (const auto& value : split(text.substr(eq + 1), ',')) {
        const std::string t = trim(value);
        if (t.empty()) throw std::runtime_error("-vary \"" + text + "\": empty value");
        v.values.push_back(t);
    }
    if (v.values.empty()) throw std::runtime_error("-vary \"" + text + "\": no values");
    return v;
}

Combination parseCombination(const std::string& text) {
    Combination c;
    std::istringstream in(text);
    std::string item;
    while (in >> item) {
        const auto eq = item.find('=');
        if (eq == std::string::npos || eq == 0 || eq + 1 == item.size())
            throw std::runtime_error("-combination \"" + text + "\": expected key=value items separated by spaces");
        c.push_back({item.substr(0, eq), item.substr(eq + 1)});
    }
    if (c.empty()) throw std::runtime_error("-combination is empty");
    return c;
}

Combination overridesFrom(const Dictionary& dict) {
    Combination out;
    for (const auto& e : dict.entries())
        if (e.isDict()) throw std::runtime_error(dict.name() + ": '" + e.keyword + "' must be a value, not a dictionary");
    static const std::regex entry(R"(^\s*(\S+)\s+(.*);\s*$)");
    std::istringstream lines(dict.toString());
    std::string line;
    while (std::getline(lines, line)) {
        std::smatch m;
        if (std::regex_match(line, m, entry) && m[1] != "FoamFile") out.push_back({m[1], trim(m[2])});
    }
    return out;
}

std::vector<Combination> combinations(const std::vector<VaryOption>& options) {
    std::vector<Combination> out{{}};
    for (const auto& o : options) {
        std::vector<Combination> next;
        for (const auto& c : out)
            for (const auto& v : o.values) {
                Combination e = c;
                e.push_back({o.key, v});
                next.push_back(e);
            }
        out = next;
    }
    return out;
}

std::optional<int> parseCommandLine(int argc, char** argv, const po::options_description& options,
                                    const std::string& utility, po::variables_map& vm) {
    try {
        const auto style = po::command_line_style::unix_style | po::command_line_style::allow_long_disguise;
        po::store(po::command_line_parser(argc, argv).options(options).style(style).run(), vm);
        po::notify(vm);
    } catch (const std::exception& e) {
        std::cerr << utility << ": " << e.what() << "\n" << options << std::endl;
        return 2;
    }
    if (vm.count("help")) {
        std::cout << options << std::endl;
        return 0;
    }
    return std::nullopt;
}

int availableCores() {
    cpu_set_t set;
    CPU_ZERO(&set);
    if (sched_getaffinity(0, sizeof set, &set) == 0 && CPU_COUNT(&set) > 0) return CPU_COUNT(&set);
    return int(std::max(1u, std::thread::hardware_concurrency()));
}

void checkThreadsAndTimeout(const po::variables_map& vm) {
    const int threads = vm["threads"].as<int>(), cores = availableCores();
    if (threads < 1 || threads > cores)
        throw std::runtime_error("-threads " + std::to_string(threads) + ": give 1 to " + std::to_string(cores) +
                                 " (the cores this process may use)");
    const double timeout = vm["timeout"].as<double>();
    if (!(timeout >= 0) || !std::isfinite(timeout)) {
        std::ostringstream m;
        m << "-timeout " << timeout << ": give the seconds after which a run is stopped (0: no limit)";
        throw std::runtime_error(m.str());
    }
}

std::vector<Combination> requestedCombinations(const po::variables_map& vm) {
    std::vector<VaryOption> vary;
    if (vm.count("vary"))
        for (const auto& v : vm["vary"].as<std::vector<std::string>>()) vary.push_back(parseVary(v));
    auto combos = combinations(vary);
    if (vm.count("combination")) {
        if (vary.empty()) combos.clear();
        for (const auto& text : vm["combination"].as<std::vector<std::string>>()) combos.push_back(parseCombination(text));
    }
    return combos;
}

std::string combinationName(const Combination& c) {
    if (c.empty()) return "base";
    std::string s;
    for (const auto& o : c) {
        if (!s.empty()) s += '_';
        for (char ch : o.value) s += (std::isalnum(static_cast<unsigned char>(ch)) || ch == '.' || ch == '-') ? ch : '-';
    }
    return s;
}

std::vector<std::string> uniqueNames(const std::vector<Combination>& combos) {
    std::vector<std::string> names;
    for (const auto& c : combos) names.push_back(combinationName(c));
    std::set<std::string> seen(names.begin(), names.end());
    if (seen.size() == names.size()) return names;
    names.clear();
    for (const auto& c : combos) {
        Combination qualified;
        for (const auto& o : c) {
            std::string key = o.key;
            if (key.size() > 5 && key.compare(key.size() - 5, 5, ".type") == 0) key.resize(key.size() - 5);
            qualified.push_back({o.key, key + "-" + o.value});
        }
        names.push_back(combinationName(qualified));
    }
    return names;
}

std::string combinationLabel(const Combination& c) {
    if (c.empty()) return "(case as it is)";
    std::string s;
    for (const auto& o : c) s += (s.empty() ? "" : " ") + o.key + "=" + o.value;
    return s;
}

void printLabel(const Combination& c) {
    std::cout << "  " << std::left << std::setw(60) << combinationLabel(c) << ' ' << std::flush;
}

std::string kindOfTypeKey(const std::string& key) {
    const auto [parent, last] = splitLast(key);
    if (last != "type" || parent.empty()) return "";
    const std::string first = parent.substr(0, parent.find('.'));
    if (first == "kernel" || first == "pressure" || first == "viscosity" || first == "integrator" ||
        first == "boundary" || first == "densityDiffusion" || first == "shifting" || first == "surfaceTension")
        return first;
    if (first == "forces") return "force";
    if (first == "functions") return "functionObject";
    return "";
}

std::string unavailableModel(const Combination& c) {
    for (const auto& o : c) {
        const std::string kind = kindOfTypeKey(o.key);
        if (kind.empty()) continue;
        const auto valid = ModelRegistry::instance().available(kind);
        if (std::find(valid.begin(), valid.end(), o.value) == valid.end()) return kind + " '" + o.value + "'";
    }
    return "";
}

// ---------------------------------------------------------------------------------------------

const Dictionary* findPath(const Dictionary& dict, const std::string& path) {
    const Dictionary* d = &dict;
    for (const auto& part : split(path, '.')) {
        if (!d->isDict(part)) return nullptr;
        d = d->findDict(part);
    }
    return d;
}

bool hasPath(const Dictionary& dict, const std::string& path) {
    const auto [parent, last] = splitLast(path);
    const Dictionary* d = parent.empty() ? &dict : findPath(dict, parent);
    return d && d->found(last);
}

bool setPath(Dictionary& dict, const std::string& path, const std::string& value) {
    const auto dot = path.find('.');
    if (dot == std::string::npos) {
        dict.set(path, value);
        return true;
    }
    const std::string head = path.substr(0, dot);
    if (!dict.isDict(head)) return false;
    Dictionary sub = *dict.findDict(head);
    if (!setPath(sub, path.substr(dot + 1), value)) return false;
    dict.setDict(head, sub);
    return true;
}

void setDictPath(Dictionary& dict, const std::string& path, const Dictionary& replacement) {
    const auto dot = path.find('.');
    if (dot == std::string::npos) {
        dict.setDict(path, replacement);
        return;
    }
    const std::string head = path.substr(0, dot);
    Dictionary sub = dict.isDict(head) ? *dict.findDict(head) : Dictionary(head);
    setDictPath(sub, path.substr(dot + 1), replacement);
    dict.setDict(head, sub);
}

CaseDictionaries::CaseDictionaries(const fs::path& caseDir) : dir_(caseDir) {
    for (const char* f : {"system/controlDict", "system/sphSchemes", "system/sphSolution",
                          "constant/fluidProperties", "constant/geometry"}) {
        File file;
        file.relative = f;
        if (fs::exists(caseDir / f)) {
            file.dict = Dictionary::fromFile(caseDir / f);
            file.present = true;
        } else {
            file.dict = Dictionary(fs::path(f).filename().string());
        }
        files_.push_back(std::move(file));
    }
}

Dictionary& CaseDictionaries::file(const std::string& relative) {
    for (auto& f : files_)
        if (f.relative == relative) {
            f.changed = true;
            return f.dict;
        }
    throw std::runtime_error("no case file " + relative);
}

void CaseDictionaries::apply(const Override& o, const Dictionary* presets) {
    const auto [parent, last] = splitLast(o.key);
    std::vector<File*> full, parents;
    for (auto& f : files_) {
        if (!f.present) continue;
        if (hasPath(f.dict, o.key)) full.push_back(&f);
        if (!parent.empty() && findPath(f.dict, parent)) parents.push_back(&f);
    }
    auto names = [](const std::vector<File*>& fs) {
        std::string s;
        for (auto* f : fs) s += (s.empty() ? "" : ", ") + f->relative;
        return s;
    };
    File* target = nullptr;
    if (full.size() > 1) throw std::runtime_error("override '" + o.key + "' is ambiguous: found in " + names(full));
    if (full.size() == 1) target = full.front();
    else if (parents.size() == 1) target = parents.front();
    else if (parents.size() > 1)
        throw std::runtime_error("override '" + o.key + "' is ambiguous: '" + parent + "' is in " + names(parents));
    else
        throw std::runtime_error("override '" + o.key + "': no case dictionary (system/controlDict, system/sphSchemes, "
                                 "system/sphSolution, constant/fluidProperties, constant/geometry) has " +
                                 (parent.empty() ? "'" + o.key + "'" : "'" + parent + "'"));
    target->changed = true;
    if (last == "type" && !parent.empty()) {
        const Dictionary* current = findPath(target->dict, parent);
        if (current && current->found("type") && current->get<std::string>("type") == o.value) return;
        std::string text = "type " + o.value + ";\n";
        if (presets)
            if (const Dictionary* p = findPath(*presets, parent + "." + o.value)) text += p->toString();
        setDictPath(target->dict, parent, Dictionary::fromString(text, "<override " + o.key + ">"));
        return;
    }
    if (!setPath(target->dict, o.key, o.value))
        throw std::runtime_error("override '" + o.key + "': cannot set it in " + target->relative);
}

void CaseDictionaries::apply(const Combination& c, const Dictionary* presets) {
    for (const auto& o : c)
        if (splitLast(o.key).second == "type") apply(o, presets);
    for (const auto& o : c)
        if (splitLast(o.key).second != "type") apply(o, presets);
}

void CaseDictionaries::write(const std::string& header) const {
    for (const auto& f : files_) {
        if (!f.changed) continue;
        fs::create_directories((dir_ / f.relative).parent_path());
        std::ofstream out(dir_ / f.relative);
        out << header << f.dict.toString();
        if (!out.flush()) throw std::runtime_error("cannot write " + (dir_ / f.relative).string());
    }
}

std::vector<std::string> CaseDictionaries::changedFiles() const {
    std::vector<std::string> changed;
    for (const auto& f : files_)
        if (f.changed) changed.push_back(f.relative);
    return changed;
}

// ---------------------------------------------------------------------------------------------

ProcessResult runProcess(const std::vector<std::string>& argv, const fs::path& workDir, const fs::path& logFile,
                         const std::vector<std::string>& env, double timeoutSeconds, int timeoutSignal) {
    // environment: ours, with 'env' replacing or adding entries
    std::vector<std::string> envStrings;
    for (char** e = environ; *e; ++e) {
        const std::string entry = *e;
        const std::string name = entry.substr(0, entry.find('='));
        const bool replaced = std::any_of(env.begin(), env.end(),
                                          [&](const std::string& x) { return x.substr(0, x.find('=')) == name; });
        if (!replaced) envStrings.push_back(entry);
    }
    envStrings.insert(envStrings.end(), env.begin(), env.end());
    std::vector<char*> envp, args;
    for (auto& s : envStrings) envp.push_back(s.data());
    envp.push_back(nullptr);
    std::vector<std::string> argvCopy = argv;
    for (auto& s : argvCopy) args.push_back(s.data());
    args.push_back(nullptr);
    const std::string log = fs::absolute(logFile).string(), dir = workDir.string();

    const auto start = std::chrono::steady_clock::now();
    const pid_t pid = fork();
    if (pid < 0) throw std::runtime_error(std::string("fork failed: ") + std::strerror(errno));
    if (pid == 0) {
        setpgid(0, 0);
        if (chdir(dir.c_str()) != 0) _exit(126);
        const int fd = open(log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
        const int in = open("/dev/null", O_RDONLY);
        if (fd < 0 || in < 0) _exit(126);
        dup2(in, 0);
        dup2(fd, 1);
        dup2(fd, 2);
        execvpe(args[0], args.data(), envp.data());
        _exit(127);
    }
    setpgid(pid, pid);
    ProcessResult result;
    int status = 0;
    bool terminated = false;
    std::chrono::steady_clock::time_point termTime;
    for (;;) {
        const pid_t r = waitpid(pid, &status, WNOHANG);
        if (r == pid) break;
        if (r < 0 && errno != EINTR) break;
        const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        if (timeoutSeconds > 0 && elapsed > timeoutSeconds && !terminated) {
            kill(-pid, timeoutSignal);
            terminated = true;
            result.timedOut = true;
            termTime = std::chrono::steady_clock::now();
        }
        if (terminated && std::chrono::duration<double>(std::chrono::steady_clock::now() - termTime).count() > 5)
            kill(-pid, SIGKILL);
        std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (WIFEXITED(status)) result.status = WEXITSTATUS(status);
    else if (WIFSIGNALED(status)) result.status = 128 + WTERMSIG(status);
    return result;
}

RunOutcome runOutcome(const ProcessResult& process, const fs::path& solverLog, double timeoutSeconds,
                      OutcomeRules rules) {
    RunOutcome o;
    o.end = parseEndLine(solverLog);
    const std::string blowUp = findLine(solverLog, "blow-up");
    if (process.timedOut) {
        o.status = "timeout";
        o.note = "stopped after " + csvNumber(timeoutSeconds, 10) + " s";
    } else if (!blowUp.empty() && (rules.anyBlowUp || !o.end.found)) {
        o.status = "unstable";
        o.note = blowUp.substr(blowUp.find("blow-up"));
    } else if (process.status == 0 && (o.end.found || !rules.endLine)) {
        o.status = "ok";
    } else {
        o.status = "failed";
        o.note = lastLine(solverLog);
    }
    return o;
}

EndLine parseEndLine(const fs::path& logFile) {
    EndLine e;
    const std::string line = findLine(logFile, "End: ");
    if (line.empty()) return e;
    static const std::regex pattern(
        R"(End: (\d+) steps to time ([^ ]+) in ([^ ]+) s wall time \((\d+) fluid.*max density error ([^%]+)%(, average iterations ([^ ,]+))?)");
    std::smatch m;
    if (!std::regex_search(line, m, pattern)) return e;
    e.found = true;
    e.steps = std::stol(m[1]);
    e.endTime = std::stod(m[2]);
    e.wallSeconds = std::stod(m[3]);
    e.fluidParticles = std::stol(m[4]);
    e.maxDensityError = std::stod(m[5]) / 100;
    if (m[7].matched) e.averageIterations = std::stod(m[7]);
    return e;
}

std::string findLine(const fs::path& logFile, const std::string& needle) {
    std::ifstream in(logFile);
    std::string line;
    while (std::getline(in, line))
        if (line.find(needle) != std::string::npos) return line;
    return "";
}

std::string lastLine(const fs::path& logFile) {
    std::ifstream in(logFile);
    std::string line, last;
    while (std::getline(in, line))
        if (!trim(line).empty()) last = trim(line);
    return last;
}

int Table::column(const std::string& name) const {
    const auto it = std::find(columns.begin(), columns.end(), name);
    return it == columns.end() ? -1 : int(it - columns.begin());
}

std::vector<double> Table::values(const std::string& name) const {
    const int c = column(name);
    if (c < 0) throw std::runtime_error("no column '" + name + "' in a postProcessing table");
    std::vector<double> v;
    for (const auto& r : rows) v.push_back(std::size_t(c) < r.size() ? r[c] : std::nan(""));
    return v;
}

Table readPostProcessing(const fs::path& caseDir, const std::string& name) {
    Table t;
    const fs::path base = caseDir / "postProcessing" / name;
    std::vector<std::pair<double, fs::path>> folders;
    std::error_code ec;
    for (const auto& e : fs::directory_iterator(base, ec))
        if (e.is_directory() && isNumber(e.path().filename().string()))
            folders.emplace_back(std::stod(e.path().filename().string()), e.path());
    std::sort(folders.begin(), folders.end());
    for (const auto& [time, folder] : folders) {
        std::ifstream in(folder / (name + ".dat"));
        std::string line;
        while (std::getline(in, line)) {
            if (line.empty()) continue;
            if (line[0] == '#') {
                if (t.columns.empty()) {
                    std::istringstream h(line.substr(1));
                    std::string c;
                    while (std::getline(h, c, '\t'))
                        if (!trim(c).empty()) t.columns.push_back(trim(c));
                }
                continue;
            }
            std::vector<double> row;
            std::istringstream r(line);
            std::string v;
            while (r >> v) row.push_back(std::strtod(v.c_str(), nullptr));
            t.rows.push_back(row);
        }
    }
    return t;
}

CsvWriter::CsvWriter(const fs::path& file, const std::vector<std::string>& columns)
    : file_(file), columns_(columns.size()) {
    fs::create_directories(fs::absolute(file).parent_path());
    std::ofstream out(file_, std::ios::trunc);
    if (!out) throw std::runtime_error("cannot write " + file.string());
    for (std::size_t i = 0; i < columns.size(); ++i) out << (i ? "," : "") << columns[i];
    out << '\n';
}

void CsvWriter::row(const std::vector<std::string>& values) {
    std::ofstream out(file_, std::ios::app);
    for (std::size_t i = 0; i < columns_; ++i) {
        std::string v = i < values.size() ? values[i] : "";
        if (v.find_first_of(",\"\n") != std::string::npos) {
            std::string q = "\"";
            for (char c : v) q += c == '"' ? std::string("\"\"") : std::string(1, c == '\n' ? ' ' : c);
            v = q + "\"";
        }
        out << (i ? "," : "") << v;
    }
    out << '\n';
}

std::string csvNumber(double v, int precision) {
    if (!std::isfinite(v)) return "";
    std::ostringstream o;
    o << std::setprecision(precision) << v;
    return o.str();
}

fs::path executableDirectory() {
    std::error_code ec;
    const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
    return ec ? fs::current_path() : exe.parent_path();
}

std::string findPython() {
    std::vector<std::string> candidates;
    if (const char* p = std::getenv("SPINDRIFT_PYTHON")) candidates.emplace_back(p);
    candidates.emplace_back("python3");
    candidates.emplace_back("/usr/bin/python3");
    for (const auto& c : candidates) {
        const std::string command = "'" + c + "' -c 'import matplotlib, numpy' > /dev/null 2>&1";
        if (std::system(command.c_str()) == 0) return c;
    }
    return "";
}

fs::path findScript(const std::string& name) {
    const fs::path exeDir = executableDirectory();
    for (const fs::path& p : {exeDir / name, exeDir / ".." / "share" / "spindrift" / name,
                              fs::path(SPINDRIFT_UTILITIES_SOURCE_DIR) / "spindriftBench" / name,
                              fs::path(SPINDRIFT_UTILITIES_SOURCE_DIR) / "spindriftStress" / name})
        if (fs::exists(p)) return p;
    return {};
}

bool runPlotScript(const std::string& utility, const std::string& script, const std::vector<std::string>& arguments,
                   const fs::path& output, double timeoutSeconds) {
    const std::string python = findPython();
    const fs::path path = findScript(script);
    if (python.empty() || path.empty()) {
        std::cerr << utility << ": warning: no python3 with matplotlib (or no " << script << "): nothing plotted\n";
        return false;
    }
    std::vector<std::string> argv{python, path.string()};
    argv.insert(argv.end(), arguments.begin(), arguments.end());
    if (runProcess(argv, output, output / "log.plot", {}, timeoutSeconds).status == 0) return true;
    std::cerr << utility << ": plotting failed, see " << (output / "log.plot").string() << '\n';
    return false;
}

} // namespace spindrift::bench
