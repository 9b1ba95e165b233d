// Bad input gives one clear error naming file, line and keyword — and writes nothing.
// The cases are the rows of tests/data/badInputs.table (shared with tests/cases/badInputs.sh,
// which runs the real binary on the same table).
#include "Case.hpp"
#include "Log.hpp"
#include "Simulation.hpp"
#include "TestSupport.hpp"

#include <gtest/gtest.h>
#include <fstream>
#include <regex>
#include <unistd.h>

using namespace spindrift;
namespace fs = std::filesystem;

namespace {

struct BadInput {
    std::string name, file, find, replace, expected;
};
void PrintTo(const BadInput& row, std::ostream* os) { *os << row.name; }

std::string unescape(const std::string& s) {
    std::string out;
    out.reserve(s.size());
    for (std::size_t i = 0; i < s.size(); ++i) {
        if (s[i] == '\\' && i + 1 < s.size() && s[i + 1] == 'n') {
            out += '\n';
            ++i;
        } else {
            out += s[i];
        }
    }
    return out;
}

std::vector<BadInput> readTable() {
    std::ifstream in(std::string(SPINDRIFT_TEST_DATA_DIR) + "/badInputs.table");
    std::vector<BadInput> rows;
    for (std::string line; std::getline(in, line);) {
        if (line.empty() || line[0] == '#') continue;
        std::vector<std::string> cols;
        for (std::size_t start = 0;;) {
            const std::size_t bar = line.find(" | ", start);
            cols.push_back(line.substr(start, bar == std::string::npos ? std::string::npos : bar - start));
            if (bar == std::string::npos) break;
            start = bar + 3;
        }
        if (cols.size() == 5) {
            // an empty replacement is written as "| |": the split leaves "|" artefacts
            rows.push_back({cols[0], cols[1], unescape(cols[2]), unescape(cols[3]), cols[4]});
        } else if (cols.size() == 4 && cols[3].rfind("| ", 0) == 0) {
            rows.push_back({cols[0], cols[1], unescape(cols[2]), "", cols[3].substr(2)});
        } else {
            ADD_FAILURE() << "malformed row in badInputs.table: " << line;
        }
    }
    return rows;
}

// A copy of the hydrostatic tutorial with one edit, plus an existing time directory that
// must not be touched.
fs::path prepareCase(const test::TempDir& tmp, const BadInput& row) {
    const fs::path caseDir = tmp.path() / "case";
    copyCaseInput(fs::path(SPINDRIFT_SOURCE_DIR) / "tutorials/hydrostaticTank2D", caseDir);
    const fs::path file = caseDir / row.file;
    std::string text = test::readFile(file);
    const std::size_t at = text.find(row.find);
    if (at == std::string::npos) throw std::runtime_error("'" + row.find + "' not found in " + row.file);
    text.replace(at, row.find.size(), row.replace);
    std::ofstream(file) << text;
    fs::create_directories(caseDir / "0.5");
    std::ofstream(caseDir / "0.5/fluid.vtp") << "sentinel";
    return caseDir;
}

class BadInputTest : public testing::TestWithParam<BadInput> {};

TEST_P(BadInputTest, GivesALocatedErrorAndWritesNothing) {
    log::setQuiet(true);
    ModelRegistry::instance().prependSearchDirectory(SPINDRIFT_TEST_PLUGIN_DIR);
    const BadInput& row = GetParam();
    test::TempDir tmp;
    const fs::path caseDir = prepareCase(tmp, row);
    std::string message;
    try {
        Simulation sim(caseDir);
        ADD_FAILURE() << "no error for " << row.name;
    } catch (const InputError& e) {
        message = e.what();
    }
    EXPECT_TRUE(std::regex_search(message, std::regex(row.expected, std::regex::extended)))
        << "message:  " << message << "\nexpected: " << row.expected;
    EXPECT_EQ(message.find('\n'), std::string::npos) << "one line";
    EXPECT_FALSE(fs::exists(caseDir / "0")) << "nothing written";
    EXPECT_EQ(test::readFile(caseDir / "0.5/fluid.vtp"), "sentinel") << "existing results untouched";
}

INSTANTIATE_TEST_SUITE_P(Table, BadInputTest, testing::ValuesIn(readTable()),
                         [](const auto& info) { return info.param.name; });

TEST(BadInput, TableCoversTheIssueList) {
    EXPECT_GE(readTable().size(), 25u);
}

TEST(BadInput, MissingCaseDirectory) {
    try {
        Simulation sim("/nonexistent/case");
        FAIL();
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("case directory '/nonexistent/case' does not exist"), std::string::npos)
            << e.what();
    }
}

TEST(BadInput, CaseDirectoryNotWritable) {
    if (::geteuid() == 0) GTEST_SKIP() << "running as root: permissions do not stop root from writing";
    test::TempDir tmp;
    const fs::path caseDir = tmp.path() / "case";
    copyCaseInput(fs::path(SPINDRIFT_SOURCE_DIR) / "tutorials/hydrostaticTank2D", caseDir);
    fs::permissions(caseDir, fs::perms::owner_write, fs::perm_options::remove);
    EXPECT_THROW(
        {
            try {
                Simulation sim(caseDir);
            } catch (const InputError& e) {
                EXPECT_NE(std::string(e.what()).find("is not writable"), std::string::npos) << e.what();
                throw;
            }
        },
        InputError);
    fs::permissions(caseDir, fs::perms::owner_write, fs::perm_options::add);
}

} // namespace
