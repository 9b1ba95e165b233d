// libFuzzer target: the dictionary parser must reject any input with an InputError — never
// crash, leak, hang or throw anything else. Typed lookups run on whatever parses.
#include "Dictionary.hpp"
#include "FuzzSupport.hpp"

#include <cstddef>
#include <cstdint>
#include <string>

using namespace spindrift;

namespace {
void lookEverywhere(const Dictionary& d, int depth) {
    if (depth > 8) return;
    for (const auto& key : d.keywords()) {
        try {
            if (d.isDict(key)) {
                lookEverywhere(d.subDict(key), depth + 1);
                continue;
            }
            (void)d.getOrDefault<double>(key, 0.0);
        } catch (const InputError&) {
        }
        try { (void)d.get<Vec3>(key); } catch (const InputError&) {}
        try { (void)d.get<std::vector<std::string>>(key); } catch (const InputError&) {}
        try { (void)d.get<bool>(key); } catch (const InputError&) {}
        try { (void)d.get<int>(key); } catch (const InputError&) {}
    }
    try { d.checkAllKeywordsUsed(); } catch (const InputError&) {}
}

// What toString writes must parse again. Once per input: the text holds every sub-dictionary
// (a round trip at each level cost the depth times the size, and inputs that substitute up to
// the parser's bounds timed out).
void roundTrip(const Dictionary& d) {
    const std::string text = d.toString();
    try {
        (void)Dictionary::fromString(text, "<roundtrip>");
    } catch (const InputError& e) {
        // a round trip failure is a bug: crash so the fuzzer reports it
        __builtin_trap();
    }
}
} // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    fuzz::quietLog();
    const std::string text(reinterpret_cast<const char*>(data), size);
    try {
        const Dictionary d = Dictionary::fromString(text, "<fuzz>");
        lookEverywhere(d, 0);
        roundTrip(d);
    } catch (const InputError&) {
    }
    return 0;
}
