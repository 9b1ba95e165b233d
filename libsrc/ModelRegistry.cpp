#include "ModelRegistry.hpp"

#include "Log.hpp"

#include <boost/dll/shared_library.hpp>
#include <algorithm>
#include <bit>
#include <cstdlib>
#include <cstring>
#include <dlfcn.h>
#include <fstream>
#include <limits>
#include <link.h> // ElfW: the ELF types of this machine's class
#include <set>
#include <sstream>

namespace fs = std::filesystem;

namespace spindrift {

struct ModelRegistry::Library {
    boost::dll::shared_library handle;
};

std::string pluginFileName(const std::string& kind, const std::string& name) {
    return "libspindrift_" + kind + "_" + name + ".so";
}

const std::vector<std::string>& ModelRegistry::kinds() {
    static const std::vector<std::string> k{"kernel",   "pressure", "viscosity",      "integrator",
                                            "boundary", "force",    "surfaceTension", "densityDiffusion",
                                            "shifting", "passive",  "functionObject"};
    return k;
}

ModelRegistry& ModelRegistry::instance() {
    // Never destroyed: plugin code must stay mapped while any model object may exist.
    static ModelRegistry* registry = new ModelRegistry();
    return *registry;
}

namespace {

// The file this code was loaded from (libspindrift.so), "" if unknown. The address is that of a
// function no other library can interpose.
fs::path thisLibrary() {
    Dl_info info{};
    if (dladdr(reinterpret_cast<const void*>(&thisLibrary), &info) != 0 && info.dli_fname != nullptr)
        return info.dli_fname;
    return {};
}

} // namespace

ModelRegistry::ModelRegistry() {
    std::vector<fs::path> dirs;
    if (const char* env = std::getenv("SPINDRIFT_PLUGIN_PATH")) {
        std::stringstream s(env);
        std::string dir;
        while (std::getline(s, dir, ':'))
            if (!dir.empty()) dirs.emplace_back(dir);
    }
    // The plugins beside this library (lib/spindrift/plugins next to lib/libspindrift.so) in
    // the build tree and in any installation, wherever its prefix.
    if (const fs::path core = thisLibrary(); !core.empty())
        dirs.push_back(fs::absolute(core).parent_path() / "spindrift" / "plugins");
    std::error_code ec;
    const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
    if (!ec) dirs.push_back(exe.parent_path().parent_path() / "lib" / "spindrift" / "plugins");
    for (auto& d : dirs) {
        const fs::path canonical = fs::weakly_canonical(d, ec);
        const fs::path& use = ec ? d : canonical;
        if (std::find(searchPath_.begin(), searchPath_.end(), use) == searchPath_.end())
            searchPath_.push_back(use);
    }
}

void ModelRegistry::prependSearchDirectory(const fs::path& dir) {
    searchPath_.insert(searchPath_.begin(), dir);
}

std::vector<std::string> ModelRegistry::available(const std::string& kind) const {
    std::set<std::string> names;
    const std::string prefix = "libspindrift_" + kind + "_";
    for (const auto& dir : searchPath_) {
        std::error_code ec;
        for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
            const std::string file = it->path().filename().string();
            if (file.rfind(prefix, 0) == 0 && file.size() > prefix.size() + 3 &&
                file.compare(file.size() - 3, 3, ".so") == 0)
                names.insert(file.substr(prefix.size(), file.size() - prefix.size() - 3));
        }
    }
    for (const auto& l : loaded_)
        if (l.kind == kind) names.insert(l.name);
    return {names.begin(), names.end()};
}

namespace {

std::string describe(const PluginAbiTag& tag) {
    const std::string precision = tag.scalarBytes == 4   ? "single precision (Scalar = float)"
                                  : tag.scalarBytes == 8 ? "double precision (Scalar = double)"
                                                         : "a Scalar of " + std::to_string(tag.scalarBytes) + " bytes";
    return precision + ", interface " + std::to_string(tag.interfaceVersion);
}

// Why the plugin in 'library' cannot be called by this core ("" when its ABI tag is ours). Reads
// data only: nothing in the library runs.
std::string abiMismatch(const boost::dll::shared_library& library, const fs::path& file) {
    std::string builtFor;
    if (library.has("spindrift_abi_tag")) {
        const PluginAbiTag& tag = library.get_alias<const PluginAbiTag>("spindrift_abi_tag");
        if (tag.interfaceVersion == pluginAbiTag.interfaceVersion && tag.scalarBytes == pluginAbiTag.scalarBytes)
            return "";
        builtFor = describe(tag);
    } else if (library.has("spindrift_abi_version")) { // interface 1 exported no precision
        builtFor = "interface " + std::to_string(library.get_alias<const std::uint32_t>("spindrift_abi_version"));
    } else {
        return "";
    }
    return "plugin '" + file.string() + "' was built for " + builtFor + "; this spindrift is " +
           describe(pluginAbiTag) + ": rebuild the plugin against this installation";
}

// The ELF machine this code runs on (0: not checked).
constexpr std::uint16_t hostMachine =
#if defined(__x86_64__)
    EM_X86_64;
#elif defined(__aarch64__)
    EM_AARCH64;
#elif defined(__i386__)
    EM_386;
#elif defined(__arm__)
    EM_ARM;
#elif defined(__powerpc64__)
    EM_PPC64;
#elif defined(__riscv)
    EM_RISCV;
#else
    0;
#endif

std::string machineName(unsigned machine) {
    switch (machine) {
    case EM_X86_64: return "x86-64";
    case EM_AARCH64: return "AArch64";
    case EM_386: return "i386";
    case EM_ARM: return "ARM";
    case EM_PPC64: return "PowerPC64";
    case EM_RISCV: return "RISC-V";
    default: return "ELF machine " + std::to_string(machine);
    }
}

} // namespace

std::string unloadableLibrary(const fs::path& file) {
    // dlopen maps a library's segments where its program headers say they are in the file; pages
    // past the end of a file cut short are a SIGBUS when the loader touches them, which nothing
    // can catch. So everything the headers describe must lie within the file, before dlopen.
    using Ehdr = ElfW(Ehdr);
    using Phdr = ElfW(Phdr);
    using Shdr = ElfW(Shdr);
    std::error_code ec;
    const std::uintmax_t size = fs::file_size(file, ec);
    if (ec) return "cannot read it: " + ec.message();
    std::ifstream in(file, std::ios::binary);
    if (!in) return "cannot open it";
    const auto readAt = [&](std::uintmax_t offset, void* out, std::size_t bytes) {
        in.clear();
        in.seekg(std::streamoff(offset));
        in.read(static_cast<char*>(out), std::streamsize(bytes));
        return bool(in);
    };
    unsigned char ident[EI_NIDENT] = {};
    if (size < EI_NIDENT || !readAt(0, ident, EI_NIDENT) || std::memcmp(ident, ELFMAG, SELFMAG) != 0)
        return "it is not a shared library (no ELF header; " + std::to_string(size) + " bytes)";
    constexpr unsigned char hostClass = sizeof(void*) == 8 ? ELFCLASS64 : ELFCLASS32;
    if (ident[EI_CLASS] != hostClass)
        return std::string("it is a ") + (ident[EI_CLASS] == ELFCLASS32 ? "32" : ident[EI_CLASS] == ELFCLASS64 ? "64" : "?") +
               "-bit library; this spindrift is " + (hostClass == ELFCLASS64 ? "64" : "32") + "-bit";
    constexpr unsigned char hostData = std::endian::native == std::endian::little ? ELFDATA2LSB : ELFDATA2MSB;
    if (ident[EI_DATA] != hostData) return "it is a library of the other byte order";
    const auto cutShort = [&](const char* what, std::uintmax_t end) {
        return "it is cut short (a copy or a build interrupted?): the file has " + std::to_string(size) +
               " bytes, but " + what + " ends at byte " + std::to_string(end);
    };
    Ehdr header{};
    if (size < sizeof header || !readAt(0, &header, sizeof header)) return cutShort("its ELF header", sizeof header);
    if (header.e_type != ET_DYN)
        return header.e_type == ET_EXEC  ? "it is an executable, not a shared library"
               : header.e_type == ET_REL ? "it is an object file (.o), not a shared library"
                                         : "it is not a shared library (ELF type " + std::to_string(header.e_type) + ")";
    if (hostMachine != 0 && header.e_machine != hostMachine)
        return "it is built for " + machineName(header.e_machine) + "; this machine is " + machineName(hostMachine);
    // a table of 'count' entries of 'entrySize' bytes at 'offset' ("" when it lies within the file)
    const auto tableEnd = [&](std::uintmax_t offset, std::uintmax_t count, std::uintmax_t entrySize) -> std::uintmax_t {
        if (offset <= size && count <= (size - offset) / entrySize) return 0;
        return count > (std::numeric_limits<std::uintmax_t>::max() - offset) / entrySize
                   ? std::numeric_limits<std::uintmax_t>::max()
                   : offset + count * entrySize;
    };
    if (header.e_phnum == 0 || header.e_phentsize != sizeof(Phdr)) return "it has no program headers to load";
    if (const auto end = tableEnd(header.e_phoff, header.e_phnum, sizeof(Phdr)))
        return cutShort("its program header table", end);
    for (unsigned k = 0; k < header.e_phnum; ++k) {
        Phdr segment{};
        if (!readAt(header.e_phoff + std::uintmax_t(k) * sizeof(Phdr), &segment, sizeof segment))
            return cutShort("its program header table", header.e_phoff + (k + 1) * sizeof(Phdr));
        if (const auto end = segment.p_filesz > 0 ? tableEnd(segment.p_offset, segment.p_filesz, 1) : 0)
            return cutShort(segment.p_type == PT_LOAD ? "a segment it loads" : "a segment it describes", end);
    }
    if (header.e_shoff != 0) {
        if (header.e_shentsize != sizeof(Shdr)) return "its section header table is malformed";
        std::uintmax_t sections = header.e_shnum;
        if (sections == 0) { // 65280 sections or more: the count is section 0's size
            Shdr first{};
            if (tableEnd(header.e_shoff, 1, sizeof(Shdr)) || !readAt(header.e_shoff, &first, sizeof first))
                return cutShort("its section header table", header.e_shoff + sizeof(Shdr));
            sections = first.sh_size;
        }
        if (const auto end = tableEnd(header.e_shoff, sections, sizeof(Shdr)))
            return cutShort("its section header table", end);
    }
    return {};
}

ModelRegistry::Loaded ModelRegistry::open(const fs::path& file, const SourceLocation& where) const {
    if (const std::string problem = unloadableLibrary(file); !problem.empty())
        throw InputError(where, "cannot load plugin library '" + file.string() + "': " + problem);
    auto library = std::make_shared<Library>();
    try {
        library->handle.load(file.string(), boost::dll::load_mode::rtld_now);
    } catch (const std::exception& e) {
        // A plugin built for another precision or interface often fails here, on a core
        // function whose signature differs: read its ABI tag without binding its code to say so.
        std::string mismatch;
        try {
            const boost::dll::shared_library unbound(file.string(), boost::dll::load_mode::rtld_lazy);
            mismatch = abiMismatch(unbound, file);
        } catch (const std::exception&) {
        }
        if (!mismatch.empty()) throw InputError(where, mismatch);
        throw InputError(where, "cannot load plugin library '" + file.string() + "': " + e.what());
    }
    auto& h = library->handle;
    if (!h.has("spindrift_create") || !h.has("spindrift_kind") || !h.has("spindrift_name") ||
        !(h.has("spindrift_abi_tag") || h.has("spindrift_abi_version")))
        throw InputError(where, "'" + file.string() +
                                    "' is not a Spindrift plugin (it exports no spindrift_create)");
    if (const std::string mismatch = abiMismatch(h, file); !mismatch.empty()) throw InputError(where, mismatch);
    Loaded l{h.get_alias<const char* const>("spindrift_kind"), h.get_alias<const char* const>("spindrift_name"),
             file, library, h.get<void*>("spindrift_create")};
    const auto& known = kinds();
    if (std::find(known.begin(), known.end(), l.kind) == known.end())
        throw InputError(where, "plugin '" + file.string() + "' exports the unknown kind '" + l.kind + "'");
    return l;
}

void ModelRegistry::add(const Loaded& l) {
    loaded_.push_back(l);
    log::info("Loaded " + l.kind + " plugin '" + l.name + "' from " + l.file.string());
}

std::vector<fs::path> ModelRegistry::userLibraryDirectories(const fs::path& caseDir) const {
    std::vector<fs::path> dirs{caseDir};
    dirs.insert(dirs.end(), searchPath_.begin(), searchPath_.end());
    if (const char* env = std::getenv("LD_LIBRARY_PATH")) {
        std::stringstream s(env);
        for (std::string dir; std::getline(s, dir, ':');)
            if (!dir.empty()) dirs.emplace_back(dir);
    }
    return dirs;
}

void ModelRegistry::loadUserLibrary(const std::string& file, const fs::path& caseDir, const SourceLocation& where) {
    const fs::path p(file);
    // OpenFOAM's `libs` names: "libmyKernel.so", or "myKernel" / "libmyKernel" for it
    std::vector<fs::path> names{p};
    if (!p.has_parent_path() && p.extension() != ".so" && file.find(".so.") == std::string::npos) {
        names.push_back(file.rfind("lib", 0) == 0 ? file + ".so" : "lib" + file + ".so");
    }
    std::vector<fs::path> candidates, dirs;
    if (p.is_absolute()) {
        candidates.push_back(p);
    } else {
        dirs = userLibraryDirectories(caseDir);
        for (const auto& dir : dirs)
            for (const auto& name : names) candidates.push_back(dir / name);
    }
    for (const auto& c : candidates) {
        std::error_code ec;
        if (fs::is_regular_file(c, ec)) {
            const fs::path canonical = fs::canonical(c);
            for (const auto& l : loaded_)
                if (l.file == canonical) return;
            add(open(canonical, where));
            return;
        }
    }
    std::string looked = "no such file";
    if (!p.is_absolute()) {
        looked = "looked in";
        for (std::size_t k = 0; k < dirs.size(); ++k) looked += (k ? ", " : " ") + dirs[k].string();
        looked += ": the case directory, SPINDRIFT_PLUGIN_PATH, the plugin directories and LD_LIBRARY_PATH";
    }
    throw InputError(where, "cannot find library '" + file + "' (" + looked + ")", "libs");
}

std::string ModelRegistry::typeOf(const std::string& kind, const Dictionary& dict) const {
    if (!dict.found("type"))
        throw InputError(dict.where(), "keyword 'type' is missing in " + dict.name() +
                                           " (which " + kind + " model to use)", "type");
    return dict.get<std::string>("type");
}

void* ModelRegistry::factoryFor(const std::string& kind, const std::string& type, const Dictionary& dict) {
    for (const auto& l : loaded_)
        if (l.kind == kind && l.name == type) return l.factory;
    const std::string fileName = pluginFileName(kind, type);
    for (const auto& dir : searchPath_) {
        std::error_code ec;
        const fs::path file = dir / fileName;
        if (!fs::is_regular_file(file, ec)) continue;
        const Loaded l = open(file, dict.locationOf("type"));
        if (l.kind != kind || l.name != type)
            throw InputError(dict.locationOf("type"),
                             "plugin '" + file.string() + "' is the " + l.kind + " '" + l.name + "', not the " +
                                 kind + " '" + type + "' its file name says: build plugins with spindrift_add_plugin",
                             "type");
        add(l);
        return l.factory;
    }
    const auto valid = available(kind);
    std::string list;
    for (const auto& v : valid) list += (list.empty() ? "" : " ") + v;
    std::string message = "Unknown " + kind + " type '" + type + "'. Valid " + kind + " types are: (" + list + ")";
    const std::string suggestion = closestMatch(type, valid);
    if (!suggestion.empty()) message += "; did you mean '" + suggestion + "'?";
    throw InputError(dict.locationOf("type"), message, "type");
}

std::vector<std::string> ModelRegistry::loadedLibraries() const {
    std::vector<std::string> out;
    for (const auto& l : loaded_) out.push_back(l.file.string());
    return out;
}

} // namespace spindrift
