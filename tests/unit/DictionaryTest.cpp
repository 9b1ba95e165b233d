// Tests of the OpenFOAM-syntax Dictionary: every syntax feature on valid input, typed lookups,
// defaults, used-keyword tracking, modification, the writer, and bad input reported at the exact
// file:line:column (InputError and closestMatch are tested here too).
#include "Dictionary.hpp"
#include "Log.hpp"
#include "TestSupport.hpp"

#include <gtest/gtest.h>

#include <functional>
#include <limits>
#include <set>
#include <string>
#include <vector>

namespace fs = std::filesystem;
using namespace spindrift;
using spindrift::test::TempDir;

namespace {

const std::string testFile = "case/system/testDict";

Dictionary parse(const std::string& text) { return Dictionary::fromString(text, testFile); }

// The what() of the InputError thrown by f, or a marker when nothing (or something else) is thrown.
std::string errorOf(const std::function<void()>& f) {
    try {
        f();
    } catch (const InputError& e) {
        return e.what();
    } catch (const std::exception& e) {
        return std::string("<not an InputError: ") + e.what() + ">";
    }
    return "<no error>";
}

#define EXPECT_CONTAINS(haystack, needle)                                                     \
    EXPECT_NE(std::string(haystack).find(needle), std::string::npos)                        \
        << "  expected to find: " << (needle) << "\n  in: " << (haystack)

} // namespace

// ---------------------------------------------------------------------------------------------
// InputError and closestMatch

TEST(InputError, MessageHasFileLineColumnAndKeyword) {
    const InputError e({"case/system/controlDict", 12, 5}, "expected a number", "endTime");
    EXPECT_STREQ(e.what(), "case/system/controlDict:12:5: error: expected a number (keyword 'endTime')");
    EXPECT_EQ(e.message(), "expected a number");
    EXPECT_EQ(e.keyword(), "endTime");
    EXPECT_EQ(e.where().line, 12);
    EXPECT_EQ(e.where().column, 5);
}

TEST(InputError, OmitsUnknownLineAndColumnAndMissingKeyword) {
    EXPECT_STREQ(InputError({"controlDict", 0, 0}, "cannot open file").what(), "controlDict: error: cannot open file");
    EXPECT_STREQ(InputError({"controlDict", 7, 0}, "bad").what(), "controlDict:7: error: bad");
    EXPECT_STREQ(InputError({}, "bad").what(), "error: bad");
}

TEST(ClosestMatch, FindsTheNearestCandidateWithinTheThreshold) {
    EXPECT_EQ(closestMatch("gama", {"type", "gamma", "stiffness"}), "gamma");
    EXPECT_EQ(closestMatch("symplecticEulr", {"leapfrog", "symplecticEuler"}), "symplecticEuler");
    EXPECT_EQ(closestMatch("endTime", {"endTim", "deltaT"}), "endTim");
    EXPECT_EQ(closestMatch("same", {"same"}), "same");
}

TEST(ClosestMatch, ReturnsEmptyWhenNothingIsClose) {
    EXPECT_EQ(closestMatch("gamma", {"viscosity", "type"}), "");
    EXPECT_EQ(closestMatch("gamma", {}), "");
    // threshold is max(2, length/3): 3 edits are too many for a 6-letter word ...
    EXPECT_EQ(closestMatch("abcdef", {"abcxyz"}), "");
    // ... but fine for a 9-letter one
    EXPECT_EQ(closestMatch("abcdefghi", {"abcdefxyz"}), "abcdefxyz");
}

TEST(ClosestMatch, PrefersTheFirstOfEquallyCloseCandidates) {
    EXPECT_EQ(closestMatch("cat", {"bat", "hat"}), "bat");
}

// ---------------------------------------------------------------------------------------------
// Valid syntax

TEST(DictionarySyntax, FoamFileHeaderIsKeptButExcludedFromKeywords) {
    const Dictionary d = parse(R"(
FoamFile
{
    version     2.0;
    format      ascii;
    class       dictionary;
    object      controlDict;
}
endTime 1;
)");
    EXPECT_TRUE(d.found("FoamFile"));
    EXPECT_TRUE(d.isDict("FoamFile"));
    EXPECT_EQ(d.keywords(), std::vector<std::string>{"endTime"});
    EXPECT_EQ(d.get<double>("endTime"), 1.0);
    EXPECT_NO_THROW(d.checkAllKeywordsUsed());
    EXPECT_NE(d.toString().find("FoamFile"), std::string::npos);
}

TEST(DictionarySyntax, ScalarsWordsAndQuotedStrings) {
    const Dictionary d = parse(
        "application spindrift;\n"
        "endTime     0.5;\n"
        "title       \"dam break, with spaces\";\n"
        "escaped     \"say \\\"hi\\\" \\\\ there\";\n"
        "empty       \"\";\n");
    EXPECT_EQ(d.get<std::string>("application"), "spindrift");
    EXPECT_EQ(d.get<double>("endTime"), 0.5);
    EXPECT_EQ(d.get<std::string>("title"), "dam break, with spaces");
    EXPECT_EQ(d.get<std::string>("escaped"), "say \"hi\" \\ there");
    EXPECT_EQ(d.get<std::string>("empty"), "");
    EXPECT_EQ(d.findEntry("title")->tokens.at(0).kind, Token::Kind::String);
}

TEST(DictionarySyntax, NestedSubDictionariesHaveScopedNames) {
    const Dictionary d = parse(R"(
sphSchemes
{
    pressure
    {
        type  wcsph;
        gamma 7;
    }
    kernel { type cubicSpline; }
}
)");
    EXPECT_EQ(d.name(), "testDict");
    const Dictionary& schemes = d.subDict("sphSchemes");
    EXPECT_EQ(schemes.name(), "testDict.sphSchemes");
    const Dictionary& pressure = schemes.subDict("pressure");
    EXPECT_EQ(pressure.name(), "testDict.sphSchemes.pressure");
    EXPECT_EQ(pressure.get<std::string>("type"), "wcsph");
    EXPECT_EQ(pressure.get<int>("gamma"), 7);
    EXPECT_EQ(schemes.subDict("kernel").get<std::string>("type"), "cubicSpline");
    EXPECT_EQ(schemes.keywords(), (std::vector<std::string>{"pressure", "kernel"}));
    // a sub-dictionary's location is its keyword's
    EXPECT_EQ(pressure.where().line, 4);
    EXPECT_EQ(pressure.where().column, 5);
    EXPECT_EQ(pressure.where().file, testFile);
}

TEST(DictionarySyntax, ListsVectorsAndNestedLists) {
    const Dictionary d = parse(
        "gravity   (0 -9.81 0);\n"
        "values    (1 2.5 -3e2 .5);\n"
        "empty     ();\n"
        "points    ((0 0 0) (1 2 3));\n"
        "fields    (p U \"rho\");\n"
        "libs\n"
        "(\n"
        "    \"libA.so\"\n"
        "    \"libB.so\"\n"
        ");\n");
    EXPECT_EQ(d.get<Vec3>("gravity"), Vec3(0, Scalar(-9.81), 0));
    EXPECT_EQ(d.get<std::vector<double>>("values"), (std::vector<double>{1, 2.5, -300, 0.5}));
    EXPECT_TRUE(d.get<std::vector<double>>("empty").empty());
    EXPECT_TRUE(d.get<std::vector<std::string>>("empty").empty());
    const auto points = d.get<std::vector<Vec3>>("points");
    ASSERT_EQ(points.size(), 2u);
    EXPECT_EQ(points[1], Vec3(1, 2, 3));
    EXPECT_EQ(d.get<std::vector<std::string>>("fields"), (std::vector<std::string>{"p", "U", "rho"}));
    EXPECT_EQ(d.get<std::vector<std::string>>("libs"), (std::vector<std::string>{"libA.so", "libB.so"}));
    const auto& tokens = d.findEntry("gravity")->tokens;
    ASSERT_EQ(tokens.size(), 5u);
    EXPECT_EQ(tokens.front().kind, Token::Kind::Open);
    EXPECT_EQ(tokens.back().kind, Token::Kind::Close);
    EXPECT_EQ(tokens[2].kind, Token::Kind::Number);
    EXPECT_EQ(tokens[2].text, "-9.81");
}

TEST(DictionarySyntax, CommentsOfBothKindsAreIgnoredEverywhere) {
    const Dictionary d = parse(
        "// a line comment\n"
        "/* a block comment\n"
        "   over lines { ; ( \" */\n"
        "a 1; // trailing\n"
        "b /* between keyword and value */ 2;\n"
        "g (0 /* in a list */ -9.81 // line comment in a list\n"
        "   0);\n"
        "s \"// not a comment /* */\";\n"
        "sub // before the brace\n"
        "{ /**/ c 3; }\n"
        "d 4; // comment at end of file without newline");
    EXPECT_EQ(d.keywords(), (std::vector<std::string>{"a", "b", "g", "s", "sub", "d"}));
    EXPECT_EQ(d.get<int>("a"), 1);
    EXPECT_EQ(d.get<int>("b"), 2);
    EXPECT_EQ(d.get<Vec3>("g"), Vec3(0, Scalar(-9.81), 0));
    EXPECT_EQ(d.get<std::string>("s"), "// not a comment /* */");
    EXPECT_EQ(d.subDict("sub").get<int>("c"), 3);
    EXPECT_EQ(d.get<int>("d"), 4);
}

TEST(DictionarySyntax, WordsMayContainPunctuation) {
    const Dictionary d = parse(
        "writeControl adjustableRunTime;\n"
        "U.x          1;\n"
        "field        a:b<c>-d+e_f;\n");
    EXPECT_EQ(d.get<std::string>("writeControl"), "adjustableRunTime");
    EXPECT_EQ(d.get<int>("U.x"), 1);
    EXPECT_EQ(d.get<std::string>("field"), "a:b<c>-d+e_f");
}

TEST(DictionarySyntax, NumbersAreTokensThatParseFullyAsDoubles) {
    const Dictionary d = parse("a 1; b -9.81; c 1e-5; d .5; e +2; f 1e; g inf; h 1.2.3; i -;");
    for (const char* number : {"a", "b", "c", "d", "e"})
        EXPECT_EQ(d.findEntry(number)->tokens.at(0).kind, Token::Kind::Number) << number;
    for (const char* word : {"f", "g", "h", "i"})
        EXPECT_EQ(d.findEntry(word)->tokens.at(0).kind, Token::Kind::Word) << word;
    EXPECT_EQ(d.get<double>("b"), -9.81);
    EXPECT_EQ(d.get<double>("c"), 1e-5);
    EXPECT_EQ(d.get<double>("d"), 0.5);
    EXPECT_EQ(d.get<double>("e"), 2.0);
}

TEST(DictionarySyntax, MultiTokenValuesOnOneLine) {
    const Dictionary d = parse("value uniform (0 0 0);\n");
    const auto& tokens = d.findEntry("value")->tokens;
    ASSERT_EQ(tokens.size(), 6u);
    EXPECT_EQ(tokens[0].text, "uniform");
}

TEST(DictionarySyntax, RecordsExactLocationsOfKeywordsAndValues) {
    const Dictionary d = parse("\n  endTime   0.5;\nsub\n{\n\tdeltaT 1;\n}\n");
    const Entry* e = d.findEntry("endTime");
    ASSERT_NE(e, nullptr);
    EXPECT_EQ(e->where.file, testFile);
    EXPECT_EQ(e->where.line, 2);
    EXPECT_EQ(e->where.column, 3);
    EXPECT_EQ(e->tokens.at(0).where.line, 2);
    EXPECT_EQ(e->tokens.at(0).where.column, 13);
    const SourceLocation inner = d.subDict("sub").locationOf("deltaT");
    EXPECT_EQ(inner.line, 5);
    EXPECT_EQ(inner.column, 2); // a tab is one column
    // absent keyword: the dictionary's own location
    EXPECT_EQ(d.subDict("sub").locationOf("nothing").line, 3);
    EXPECT_EQ(d.locationOf("nothing").line, 0);
    EXPECT_EQ(d.locationOf("nothing").file, testFile);
}

TEST(DictionarySyntax, KeywordGivenTwiceIsAnErrorNamingBothLines) {
    // issue 33.12: a repeated endTime, two walls 'tank' (the second silently replaced the first)
    EXPECT_EQ(errorOf([] { parse("a 1;\nb 2;\na 3;\n"); }),
              testFile + ":3:1: error: duplicate entry 'a' in testDict: already given at " + testFile +
                  ":1:1; remove one of them (keyword 'a')");
    EXPECT_EQ(errorOf([] { parse("walls\n{\n    tank { type box; }\n    tank { type container; }\n}\n"); }),
              testFile + ":4:5: error: duplicate entry 'tank' in testDict.walls: already given at " + testFile +
                  ":3:5; remove one of them (keyword 'tank')");
    // a value and a dictionary of one name, either way round
    EXPECT_CONTAINS(errorOf([] { parse("a { x 1; }\na 2;\n"); }), testFile + ":2:1: error: duplicate entry 'a'");
    EXPECT_CONTAINS(errorOf([] { parse("b 3;\nb { y 4; }\n"); }), testFile + ":2:1: error: duplicate entry 'b'");
    // inside one sub-dictionary, and in a list-valued entry (libs)
    EXPECT_CONTAINS(errorOf([] { parse("p { gamma 7; gamma 8; }\n"); }), testFile + ":1:14: error: duplicate entry 'gamma' in testDict.p");
    EXPECT_CONTAINS(errorOf([] { parse("libs (\"a.so\");\nlibs (\"b.so\");\n"); }), "duplicate entry 'libs'");
    // the same keyword in different dictionaries is no duplicate
    EXPECT_NO_THROW(parse("a 1;\np { a 2; q { a 3; } }\n"));
}

TEST(DictionarySyntax, AnEntryOverridingAnIncludedOneIsLoggedAndWins) {
    log::setQuiet(false);
    // OpenFOAM's `#include "defaults"` then changes: the later entry wins, a dictionary given again
    // is merged into the included one entry by entry, and each override is logged with both places
    TempDir dir;
    dir.writeFile("system/defaults", "endTime 1;\npressure { type wcsph; gamma 7; }\n");
    const fs::path file = dir.writeFile("system/controlDict",
                                        "#include \"defaults\"\nendTime 2;\npressure { gamma 8; c0 10; }\n");
    testing::internal::CaptureStdout();
    const Dictionary d = Dictionary::fromFile(file);
    const std::string log = testing::internal::GetCapturedStdout();
    EXPECT_EQ(d.get<int>("endTime"), 2);
    EXPECT_EQ(d.locationOf("endTime").line, 2);
    const Dictionary& p = d.subDict("pressure");
    EXPECT_EQ(p.get<std::string>("type"), "wcsph");
    EXPECT_EQ(p.get<int>("gamma"), 8);
    EXPECT_EQ(p.get<int>("c0"), 10);
    EXPECT_EQ(p.keywords(), (std::vector<std::string>{"type", "gamma", "c0"}));
    EXPECT_EQ(d.keywords(), (std::vector<std::string>{"endTime", "pressure"})) << "an override keeps the first place";
    EXPECT_CONTAINS(log, file.string() + ":2:1: 'endTime' overrides the entry of controlDict at " +
                             (dir.path() / "system/defaults").string() + ":1:1");
    EXPECT_CONTAINS(log, file.string() + ":3:12: 'gamma' overrides the entry of controlDict.pressure at ");
    // an included file's own duplicates are still an error
    dir.writeFile("system/twice", "endTime 1;\nendTime 3;\n");
    const fs::path bad = dir.writeFile("system/bad", "#include \"twice\"\n");
    EXPECT_CONTAINS(errorOf([&] { Dictionary::fromFile(bad); }),
                    (dir.path() / "system/twice").string() + ":2:1: error: duplicate entry 'endTime'");
    // and an entry given twice after the include too
    const fs::path after = dir.writeFile("system/after", "#include \"defaults\"\nendTime 2;\nendTime 3;\n");
    EXPECT_CONTAINS(errorOf([&] { Dictionary::fromFile(after); }), after.string() + ":3:1: error: duplicate entry 'endTime'");
}

TEST(DictionarySyntax, StraySemicolonsAreIgnored) {
    const Dictionary d = parse("a { x 1; };\n;\nb 2;;\n");
    EXPECT_EQ(d.keywords(), (std::vector<std::string>{"a", "b"}));
}

TEST(DictionarySyntax, EmptyInputAndEmptySubDictionary) {
    EXPECT_TRUE(parse("").entries().empty());
    EXPECT_TRUE(parse("  // only a comment\n").entries().empty());
    const Dictionary d = parse("empty {}\n");
    EXPECT_TRUE(d.subDict("empty").entries().empty());
}

TEST(DictionarySyntax, CrLfLineEndingsAreAccepted) {
    const Dictionary d = parse("a 1;\r\nb\r\n{\r\n    c (1 2 3);\r\n}\r\n");
    EXPECT_EQ(d.get<int>("a"), 1);
    EXPECT_EQ(d.subDict("b").get<Vec3>("c"), Vec3(1, 2, 3));
}

// ---------------------------------------------------------------------------------------------
// $substitution

TEST(DictionarySubstitution, ReplacesWholeValueAndListElements) {
    const Dictionary d = parse(
        "g      -9.81;\n"
        "gravity (0 $g 0);\n"
        "end    $g;\n"
        "vec    (1 2 3);\n"
        "copy   $vec;\n"
        "many   $vec extra;\n");
    EXPECT_EQ(d.get<Vec3>("gravity"), Vec3(0, Scalar(-9.81), 0));
    EXPECT_EQ(d.get<double>("end"), -9.81);
    EXPECT_EQ(d.get<Vec3>("copy"), Vec3(1, 2, 3));
    EXPECT_EQ(d.findEntry("many")->tokens.size(), 6u);
}

TEST(DictionarySubstitution, InnermostScopeWinsAndParentsAreSearched) {
    const Dictionary d = parse(R"(
rho 1000;
c   1;
outer
{
    c 2;
    outerOnly 5;
    inner
    {
        c         3;
        mine      $c;
        fromOuter $outerOnly;
        fromTop   $rho;
    }
    parentC $c;
}
topC $c;
)");
    const Dictionary& inner = d.subDict("outer").subDict("inner");
    EXPECT_EQ(inner.get<int>("mine"), 3);
    EXPECT_EQ(inner.get<int>("fromOuter"), 5);
    EXPECT_EQ(inner.get<int>("fromTop"), 1000);
    EXPECT_EQ(d.subDict("outer").get<int>("parentC"), 2);
    EXPECT_EQ(d.get<int>("topC"), 1);
}

TEST(DictionarySubstitution, ScopedNameLooksIntoSubDictionaries) {
    const Dictionary d = parse(R"(
constants { rho 1000; nested { deep 7; } }
other
{
    rho    $constants.rho;
    deep   $constants.nested.deep;
}
U.x 4;
dotted $U.x;
)");
    EXPECT_EQ(d.subDict("other").get<int>("rho"), 1000);
    EXPECT_EQ(d.subDict("other").get<int>("deep"), 7);
    EXPECT_EQ(d.get<int>("dotted"), 4); // a keyword containing '.' is found as a whole first
}

TEST(DictionarySubstitution, ScopedNameFindsSubDictionariesWhoseKeywordHasADot) {
    // "a.b" is tried as a keyword after "a" (the prefixes are hashed incrementally)
    const Dictionary d = parse("a.b { c { d 5; } }\nx $a.b.c.d;\n");
    EXPECT_EQ(d.get<int>("x"), 5);
}

TEST(DictionarySubstitution, DictionaryAsValueIsCopied) {
    Dictionary d = parse(R"(
wall { type container; layers 3; }
left  $wall;
right $wall;
)");
    const Dictionary& left = d.subDict("left");
    EXPECT_EQ(left.name(), "testDict.left");
    EXPECT_EQ(left.get<std::string>("type"), "container");
    EXPECT_EQ(left.get<int>("layers"), 3);
    EXPECT_EQ(left.where().line, 3);
    // a copy: marks on one are not marks on the other
    EXPECT_NO_THROW(left.checkAllKeywordsUsed());
    EXPECT_THROW(d.subDict("right").checkAllKeywordsUsed(), InputError);
}

TEST(DictionarySubstitution, DictionaryAtKeywordPositionIsMergedIntoScope) {
    const Dictionary d = parse(R"(
defaults { type wcsph; gamma 7; }
pressure
{
    $defaults;
    gamma 8;
}
)");
    const Dictionary& p = d.subDict("pressure");
    EXPECT_EQ(p.keywords(), (std::vector<std::string>{"type", "gamma"}));
    EXPECT_EQ(p.get<std::string>("type"), "wcsph");
    EXPECT_EQ(p.get<int>("gamma"), 8);
}

TEST(DictionarySubstitution, ReferencedKeywordsCountAsUsed) {
    const Dictionary d = parse("rho 1000;\nrhoRef $rho;\n");
    d.get<double>("rhoRef");
    EXPECT_NO_THROW(d.checkAllKeywordsUsed());
}

TEST(DictionarySubstitution, UsesEntriesFromIncludedFiles) {
    TempDir dir;
    dir.writeFile("system/common", "rho 1000;\n");
    const fs::path file = dir.writeFile("system/testDict", "#include \"common\"\nrhoRef $rho;\n");
    EXPECT_EQ(Dictionary::fromFile(file).get<int>("rhoRef"), 1000);
}

// ---------------------------------------------------------------------------------------------
// #include and files

TEST(DictionaryFiles, FromFileNamesTheDictionaryAfterTheFileAndKeepsThePathInLocations) {
    TempDir dir;
    const fs::path file = dir.writeFile("case/system/controlDict", "endTime 1;\n");
    const Dictionary d = Dictionary::fromFile(file);
    EXPECT_EQ(d.name(), "controlDict");
    EXPECT_EQ(d.where().file, file.string());
    EXPECT_EQ(d.locationOf("endTime").file, file.string());
    EXPECT_EQ(d.locationOf("endTime").line, 1);
}

TEST(DictionaryFiles, MissingTopFileIsAnInputError) {
    TempDir dir;
    const fs::path file = dir.path() / "system/controlDict";
    EXPECT_EQ(errorOf([&] { Dictionary::fromFile(file); }), file.string() + ": error: cannot open file");
    EXPECT_EQ(errorOf([&] { Dictionary::fromFile(dir.path()); }), dir.path().string() + ": error: cannot open file");
}

TEST(DictionaryFiles, IncludeIsRelativeToTheIncludingFileAndMergesIntoScope) {
    TempDir dir;
    dir.writeFile("case/constant/common", "rho 1000;\n#include \"more/nested\"\n");
    dir.writeFile("case/constant/more/nested", "nu 1e-6;\n");
    dir.writeFile("case/system/schemes", "gamma 7;\n");
    const fs::path file = dir.writeFile("case/system/controlDict",
                                        "a 1;\n"
                                        "#include \"../constant/common\"\n"
                                        "pressure\n"
                                        "{\n"
                                        "    #include \"schemes\"\n"
                                        "    type wcsph;\n"
                                        "}\n"
                                        "nu 2e-6; // later entries override included ones\n");
    const Dictionary d = Dictionary::fromFile(file);
    EXPECT_EQ(d.keywords(), (std::vector<std::string>{"a", "rho", "nu", "pressure"}));
    EXPECT_EQ(d.get<int>("rho"), 1000);
    EXPECT_EQ(d.get<double>("nu"), 2e-6);
    EXPECT_EQ(d.subDict("pressure").get<int>("gamma"), 7);
    EXPECT_EQ(d.subDict("pressure").get<std::string>("type"), "wcsph");
    // locations name the included file, from the including file's directory
    const SourceLocation rho = d.locationOf("rho");
    EXPECT_EQ(fs::path(rho.file), (dir.path() / "case/constant/common").lexically_normal());
    EXPECT_EQ(rho.line, 1);
    EXPECT_EQ(fs::path(d.subDict("pressure").locationOf("gamma").file),
              (dir.path() / "case/system/schemes").lexically_normal());
}

TEST(DictionaryFiles, MissingIncludeIsReportedAtTheIncludeDirective) {
    TempDir dir;
    const fs::path file = dir.writeFile("system/controlDict", "a 1;\n  #include \"nothere\"\n");
    const std::string message = errorOf([&] { Dictionary::fromFile(file); });
    EXPECT_CONTAINS(message, file.string() + ":2:3: error: cannot open include file '");
    EXPECT_CONTAINS(message, "nothere'");
}

TEST(DictionaryFiles, ErrorsInIncludedFilesNameTheIncludedFile) {
    TempDir dir;
    const fs::path included = dir.writeFile("system/common", "a 1;\nb 2\n");
    const fs::path file = dir.writeFile("system/controlDict", "#include \"common\"\n");
    EXPECT_CONTAINS(errorOf([&] { Dictionary::fromFile(file); }),
                    included.lexically_normal().string() + ":2:4: error: expected ';' after the value of 'b'");
}

TEST(DictionaryFiles, IncludeIfPresentIgnoresAMissingFile) {
    TempDir dir;
    dir.writeFile("system/extra", "b 2;\n");
    const fs::path file = dir.writeFile("system/controlDict",
                                        "#includeIfPresent \"nothere\"\n#includeIfPresent \"extra\"\na 1;\n");
    const Dictionary d = Dictionary::fromFile(file);
    EXPECT_EQ(d.keywords(), (std::vector<std::string>{"b", "a"}));
}

TEST(DictionaryFiles, RecursiveIncludeIsAnError) {
    TempDir dir;
    const fs::path file = dir.writeFile("system/controlDict", "a 1;\n#include \"controlDict\"\n");
    EXPECT_CONTAINS(errorOf([&] { Dictionary::fromFile(file); }), "does '");
}

// ---------------------------------------------------------------------------------------------
// Typed lookups

TEST(DictionaryLookup, NumbersOfEveryType) {
    const Dictionary d = parse("d 0.125; f 2.5; i -42; l 9000000000; u 7; w 1e3; z +3;");
    EXPECT_EQ(d.get<double>("d"), 0.125);
    EXPECT_EQ(d.get<float>("f"), 2.5f);
    EXPECT_EQ(d.get<int>("i"), -42);
    EXPECT_EQ(d.get<long>("l"), 9000000000L);
    EXPECT_EQ(d.get<unsigned>("u"), 7u);
    EXPECT_EQ(d.get<int>("w"), 1000); // a whole number in exponent form
    EXPECT_EQ(d.get<int>("z"), 3);
    EXPECT_EQ(d.get<double>("i"), -42.0); // an integer is a number
}

TEST(DictionaryLookup, BoolSpellings) {
    const Dictionary d = parse("a true; b false; c on; d off; e yes; f no;");
    EXPECT_TRUE(d.get<bool>("a"));
    EXPECT_FALSE(d.get<bool>("b"));
    EXPECT_TRUE(d.get<bool>("c"));
    EXPECT_FALSE(d.get<bool>("d"));
    EXPECT_TRUE(d.get<bool>("e"));
    EXPECT_FALSE(d.get<bool>("f"));
}

TEST(DictionaryLookup, StringsAreWordsOrQuotedStrings) {
    const Dictionary d = parse("w wcsph; q \"a b\";");
    EXPECT_EQ(d.get<std::string>("w"), "wcsph");
    EXPECT_EQ(d.get<std::string>("q"), "a b");
}

TEST(DictionaryLookup, VectorsHaveThreeComponentsEvenInTwoDimensions) {
    const Dictionary d = parse("dimension 2;\ngravity (0 -9.81 0);\nmin (0 0 0);\n");
    const Vec3 g = d.get<Vec3>("gravity");
    EXPECT_EQ(g.x(), 0);
    EXPECT_EQ(g.y(), Scalar(-9.81));
    EXPECT_EQ(g.z(), 0);
    EXPECT_EQ(d.get<Vec3>("min"), Vec3::Zero());
}

TEST(DictionaryLookup, ListsOfNumbersWordsAndVectors) {
    const Dictionary d = parse("n (1 2 3); w (a \"b c\" d); v ((1 0 0) (0 1 0) (0 0 1));");
    EXPECT_EQ(d.get<std::vector<double>>("n"), (std::vector<double>{1, 2, 3}));
    EXPECT_EQ(d.get<std::vector<std::string>>("w"), (std::vector<std::string>{"a", "b c", "d"}));
    const auto v = d.get<std::vector<Vec3>>("v");
    ASSERT_EQ(v.size(), 3u);
    EXPECT_EQ(v[2], Vec3(0, 0, 1));
}

TEST(DictionaryLookup, SubDictAndFindDict) {
    const Dictionary d = parse("a { x 1; }\nb 2;\n");
    EXPECT_EQ(d.subDict("a").get<int>("x"), 1);
    EXPECT_NE(d.findDict("a"), nullptr);
    EXPECT_EQ(d.findDict("absent"), nullptr);
    EXPECT_TRUE(d.isDict("a"));
    EXPECT_FALSE(d.isDict("b"));
    EXPECT_FALSE(d.isDict("absent"));
    EXPECT_THROW(d.findDict("b"), InputError);
    EXPECT_EQ(d.findEntry("absent"), nullptr);
}

TEST(DictionaryLookup, GetWordAcceptsOnlyAllowedValues) {
    const Dictionary d = parse("type leapfrog;\n");
    EXPECT_EQ(d.getWord("type", {"leapfrog", "symplecticEuler"}), "leapfrog");
    EXPECT_EQ(d.getWordOrDefault("scheme", {"a", "b"}, "b"), "b");
    EXPECT_EQ(d.getWordOrDefault("type", {"leapfrog"}, "x"), "leapfrog");
    EXPECT_THROW(d.getWordOrDefault("type", {"a", "b"}, "a"), InputError);
}

// ---------------------------------------------------------------------------------------------
// Defaults and used keywords

TEST(DictionaryDefaults, ReturnsTheDefaultWhenAbsentAndTheValueWhenPresent) {
    const Dictionary d = parse("gamma 8;\n");
    EXPECT_EQ(d.getOrDefault<int>("gamma", 7), 8);
    EXPECT_EQ(d.getOrDefault<double>("c0", 12.5), 12.5);
    EXPECT_EQ(d.getOrDefault<bool>("flag", true), true);
    EXPECT_EQ(d.getOrDefault<std::string>("stopAt", "endTime"), "endTime");
    EXPECT_EQ(d.getOrDefault<Vec3>("gravity", Vec3(0, -1, 0)), Vec3(0, -1, 0));
    EXPECT_TRUE(d.getOrDefault<std::vector<std::string>>("writeFields", {}).empty());
    EXPECT_EQ(d.getOrDefault<std::vector<double>>("list", {1, 2}), (std::vector<double>{1, 2}));
    EXPECT_EQ(d.getOrDefault<std::vector<Vec3>>("points", {}).size(), 0u);
    EXPECT_EQ(d.getOrDefault<unsigned>("u", 3u), 3u);
    EXPECT_EQ(d.getOrDefault<long>("l", 4L), 4L);
    EXPECT_EQ(d.getOrDefault<float>("f", 1.5f), 1.5f);
}

TEST(DictionaryDefaults, PresentValueOfTheWrongTypeIsStillAnError) {
    const Dictionary d = parse("gamma seven;\n");
    EXPECT_THROW(d.getOrDefault<int>("gamma", 7), InputError);
}

TEST(DictionaryDefaults, DefaultIsLoggedOncePerScopedKeyword) {
    const Dictionary d = Dictionary::fromString("pressure { }\n", "sphSchemes");
    const Dictionary& p = d.subDict("pressure");
    testing::internal::CaptureStdout();
    p.getOrDefault<double>("gamma", 7.0);
    p.getOrDefault<double>("gamma", 7.0);
    p.getOrDefault<Vec3>("loggedVector", Vec3(0, -9.81, 0));
    p.getWordOrDefault("loggedWord", {"a", "b"}, "b");
    const std::string out = testing::internal::GetCapturedStdout();
    EXPECT_CONTAINS(out, "    default: sphSchemes.pressure.gamma 7\n");
    EXPECT_EQ(out.find("default: sphSchemes.pressure.gamma"), out.rfind("default: sphSchemes.pressure.gamma"));
    EXPECT_CONTAINS(out, "    default: sphSchemes.pressure.loggedVector (0 -9.81 0)\n");
    EXPECT_CONTAINS(out, "    default: sphSchemes.pressure.loggedWord b\n");
}

TEST(DictionaryUsed, EveryLookupButFoundMarksTheKeywordUsed) {
    const Dictionary d = parse("a 1; b 2; c { } e { } f 3; g 4; h word; i 5;\n");
    d.get<int>("a");
    d.getOrDefault<int>("b", 0);
    d.subDict("c");
    d.findDict("e");
    d.markUsed("f");
    d.getWord("h", {"word"});
    d.getOrDefault<int>("i", 0);
    EXPECT_TRUE(d.found("g"));
    d.isDict("g");
    d.findEntry("g");
    d.locationOf("g");
    const std::string message = errorOf([&] { d.checkAllKeywordsUsed(); });
    EXPECT_CONTAINS(message, "unknown keyword 'g'");
    d.markUsed("g");
    EXPECT_NO_THROW(d.checkAllKeywordsUsed());
}

TEST(DictionaryUsed, DefaultsOfAbsentKeywordsAreListedAsValid) {
    const Dictionary d = parse("gama 8;\n");
    d.getOrDefault<double>("gamma", 7.0);
    EXPECT_CONTAINS(errorOf([&] { d.checkAllKeywordsUsed(); }), "(did you mean 'gamma'?); valid keywords: (gamma)");
}

TEST(DictionaryUsed, CheckIsNotRecursiveAndIgnoresTheHeader) {
    const Dictionary d = parse("FoamFile { version 2.0; }\nsub { unused 1; }\n");
    d.subDict("sub");
    EXPECT_NO_THROW(d.checkAllKeywordsUsed());
    EXPECT_THROW(d.subDict("sub").checkAllKeywordsUsed(), InputError);
}

// ---------------------------------------------------------------------------------------------
// Modification and writing

TEST(DictionaryModify, SetReplacesOrAppendsAndParsesValueSyntax) {
    Dictionary d = parse("deltaT 0.1;\nend 1;\n");
    d.set("deltaT", "0.01");
    d.set("gravity", "(0 -9.81 0)");
    d.set("type", "wcsph");
    d.set("title", "\"a b\"");
    EXPECT_EQ(d.get<double>("deltaT"), 0.01);
    EXPECT_EQ(d.get<Vec3>("gravity"), Vec3(0, Scalar(-9.81), 0));
    EXPECT_EQ(d.get<std::string>("type"), "wcsph");
    EXPECT_EQ(d.get<std::string>("title"), "a b");
    EXPECT_EQ(d.keywords(), (std::vector<std::string>{"deltaT", "end", "gravity", "type", "title"}));
    EXPECT_EQ(d.locationOf("deltaT").file, "<override>");
    EXPECT_EQ(d.locationOf("deltaT").line, 0);
}

TEST(DictionaryModify, SetWithBracesMakesASubDictionary) {
    Dictionary d = parse("pressure 1;\n");
    d.set("pressure", "{ type wcsph; gamma 7; }");
    ASSERT_TRUE(d.isDict("pressure"));
    const Dictionary& p = d.subDict("pressure");
    EXPECT_EQ(p.name(), "testDict.pressure");
    EXPECT_EQ(p.get<int>("gamma"), 7);
    EXPECT_EQ(p.where().file, "<override>");
}

TEST(DictionaryModify, SetSubstitutesFromTheDictionary) {
    Dictionary d = parse("g -9.81;\n");
    d.set("gravity", "(0 $g 0)");
    EXPECT_EQ(d.get<Vec3>("gravity"), Vec3(0, Scalar(-9.81), 0));
}

TEST(DictionaryModify, ErrorsInSetValuesAreReportedAtOverride) {
    Dictionary d = parse("");
    EXPECT_EQ(errorOf([&] { d.set("g", "(0 1"); }),
              "<override>:1:5: error: expected ')' to close the list opened at <override>:1:1, found end of file (keyword 'g')");
    EXPECT_CONTAINS(errorOf([&] { d.set("g", ""); }), "<override>");
    EXPECT_CONTAINS(errorOf([&] { d.set("g", "1; 2"); }), "<override>:1:4: error: unexpected '2'");
    EXPECT_CONTAINS(errorOf([&] { d.set("bad keyword", "1"); }), "invalid keyword 'bad keyword'");
    d.set("endTime", "abc");
    EXPECT_EQ(errorOf([&] { d.get<double>("endTime"); }),
              "<override>:1:1: error: expected a number for 'endTime', found word 'abc' (keyword 'endTime')");
}

TEST(DictionaryModify, SetDictCopiesAndRenamesAndRemoveDeletes) {
    Dictionary d = parse("a 1;\nb 2;\n");
    const Dictionary source = Dictionary::fromString("x 1; inner { y 2; }", "other");
    d.setDict("sub", source);
    EXPECT_EQ(d.subDict("sub").name(), "testDict.sub");
    EXPECT_EQ(d.subDict("sub").subDict("inner").name(), "testDict.sub.inner");
    EXPECT_EQ(d.subDict("sub").subDict("inner").get<int>("y"), 2);
    // a deep copy: marking the copy does not mark the source
    EXPECT_THROW(source.checkAllKeywordsUsed(), InputError);
    d.remove("a");
    d.remove("absent");
    EXPECT_EQ(d.keywords(), (std::vector<std::string>{"b", "sub"}));
}

TEST(DictionaryModify, RemoveKeepsTheOtherKeywordsFindable) {
    Dictionary d = parse("a 1; b 2; c 3; d 4;");
    d.remove("b");
    EXPECT_FALSE(d.found("b"));
    EXPECT_EQ(d.get<int>("c"), 3);
    EXPECT_EQ(d.get<int>("d"), 4);
    d.set("b", "5");
    EXPECT_EQ(d.keywords(), (std::vector<std::string>{"a", "c", "d", "b"}));
    EXPECT_EQ(d.get<int>("b"), 5);
    Dictionary copy = d;
    copy.remove("a");
    EXPECT_TRUE(d.found("a"));
    EXPECT_EQ(copy.get<int>("d"), 4);
    EXPECT_EQ(copy.get<int>("b"), 5);
}

TEST(DictionaryWrite, ToStringWritesOpenFoamSyntax) {
    const Dictionary d = parse("a 1;\ng (0 -9.81 0);\ns \"x y\";\nsub { t w; }\n");
    EXPECT_EQ(d.toString(),
              "a               1;\n"
              "g               (0 -9.81 0);\n"
              "s               \"x y\";\n"
              "sub\n"
              "{\n"
              "    t               w;\n"
              "}\n");
    EXPECT_EQ(d.subDict("sub").toString(2), "  t               w;\n");
}

TEST(DictionaryWrite, ToStringRoundTripsThroughFromString) {
    Dictionary d = parse(R"(
FoamFile { version 2.0; format ascii; object testDict; }
application     spindrift;   // comment dropped
endTime         1e-3;
title           "quotes \" and \\ backslashes";
gravity         (0 -9.81 0);
points          ((0 0 0) (1 1 1));
empty           ();
aVeryLongKeywordIndeed 3;
sphSchemes
{
    pressure { type wcsph; gamma 7; nested { deep (a "b c"); } }
    empty    { }
}
)");
    d.set("deltaT", "0.01");
    d.set("extra", "{ x 1; }");
    const std::string text = d.toString();
    const Dictionary back = Dictionary::fromString(text, testFile);
    EXPECT_EQ(back.toString(), text);
    EXPECT_EQ(back.get<std::string>("title"), "quotes \" and \\ backslashes");
    EXPECT_EQ(back.get<double>("endTime"), 1e-3);
    EXPECT_EQ(back.get<Vec3>("gravity"), Vec3(0, Scalar(-9.81), 0));
    EXPECT_EQ(back.get<std::vector<Vec3>>("points").size(), 2u);
    EXPECT_EQ(back.subDict("sphSchemes").subDict("pressure").subDict("nested").get<std::vector<std::string>>("deep"),
              (std::vector<std::string>{"a", "b c"}));
    EXPECT_EQ(back.get<double>("deltaT"), 0.01);
    EXPECT_EQ(back.subDict("extra").get<int>("x"), 1);
    EXPECT_TRUE(back.isDict("FoamFile"));
    EXPECT_EQ(back.keywords(), d.keywords());
}

// ---------------------------------------------------------------------------------------------
// Limits: nesting, size, expansion and many keywords are bounded and fail with an InputError,
// never a crash, a hang or std::bad_alloc.

namespace {
// 'levels' nested sub-dictionaries "d{d{...", 'inner' in the innermost, all closed.
std::string nestedDictionaries(int levels, const std::string& inner) {
    std::string text;
    for (int i = 0; i < levels; ++i) text += "d{";
    return text + inner + std::string(static_cast<std::size_t>(levels), '}');
}

const Dictionary& innermost(const Dictionary& d, int levels) {
    const Dictionary* inner = &d;
    for (int i = 0; i < levels; ++i) inner = &inner->subDict("d");
    return *inner;
}
} // namespace

TEST(DictionaryLimits, DeeplyNestedDictionariesAreAnErrorNotAStackOverflow) {
    // 10,000 levels overflowed the stack (exit 139, no message). The 257th '{' is at column 514.
    std::string text;
    for (int i = 0; i < 10000; ++i) text += "d{";
    EXPECT_EQ(errorOf([&] { parse(text); }),
              testFile + ":1:514: error: dictionaries nested deeper than 256 levels (keyword 'd')");
}

TEST(DictionaryLimits, DictionariesMayNest256Levels) {
    const Dictionary d = parse(nestedDictionaries(256, "x 1;"));
    EXPECT_EQ(innermost(d, 256).get<int>("x"), 1);
    EXPECT_CONTAINS(errorOf([&] { parse(nestedDictionaries(257, "x 1;")); }),
                    ":1:514: error: dictionaries nested deeper than 256 levels");
}

TEST(DictionaryLimits, DeeplyNestedListsAreAnError) {
    EXPECT_EQ(errorOf([&] { parse("v " + std::string(10000, '(') + ";\n"); }),
              testFile + ":1:259: error: lists nested deeper than 256 levels (keyword 'v')");
    const Dictionary d = parse("v " + std::string(256, '(') + "1" + std::string(256, ')') + ";\n");
    EXPECT_EQ(d.findEntry("v")->tokens.size(), 513u);
}

TEST(DictionaryLimits, SubstitutedListsCountAtTheirNewDepth) {
    const auto nestedList = [](int levels, const std::string& inner) {
        return std::string(std::size_t(levels), '(') + inner + std::string(std::size_t(levels), ')');
    };
    const std::string a = "a " + nestedList(200, "1") + ";\n";
    EXPECT_EQ(errorOf([&] { parse(a + "b " + nestedList(100, "$a") + ";\n"); }),
              testFile + ":2:103: error: lists nested deeper than 256 levels (substituting '$a' here) (keyword 'b')");
    EXPECT_EQ(parse(a + "b " + nestedList(56, "$a") + ";\n").findEntry("b")->tokens.size(), 513u);
}

TEST(DictionaryLimits, CopiedDictionariesCountAtTheirNewDepth) {
    // 'src' spans 200 levels; copied 101 levels down it would reach level 300
    const std::string src = "src{" + nestedDictionaries(199, "x 1;") + "}\n";
    EXPECT_EQ(errorOf([&] { parse(src + nestedDictionaries(100, "copy $src;")); }),
              testFile + ":2:206: error: dictionaries nested deeper than 256 levels (copying '$src' here) "
                         "(keyword 'copy')");
    EXPECT_EQ(errorOf([&] { parse(src + nestedDictionaries(100, "$src;")); }),
              testFile + ":2:201: error: dictionaries nested deeper than 256 levels (copying '$src' here)");
    // 51 + 199 = 250 levels (the copy) and 50 + 199 (the merge) are fine
    const Dictionary d = parse(src + nestedDictionaries(50, "copy $src; $src;"));
    EXPECT_EQ(innermost(innermost(d, 50).subDict("copy"), 199).get<int>("x"), 1);
    EXPECT_EQ(innermost(d, 249).get<int>("x"), 1);
}

TEST(DictionaryLimits, TwoHundredThousandKeywordsParseAndAreFound) {
    // Parsing and lookups are linear (they were quadratic: 100k keywords took a minute); times are
    // measured outside the tests, never asserted.
    constexpr int n = 200000;
    std::string text;
    for (int i = 0; i < n; ++i) text += "key" + std::to_string(i) + " " + std::to_string(i) + ";\n";
    text += "more { key7 -7; }\n$more;\nlast $key199999;\n"; // a merge overrides key7
    const Dictionary d = parse(text);
    const std::vector<std::string> keywords = d.keywords();
    ASSERT_EQ(keywords.size(), std::size_t(n) + 2);
    EXPECT_EQ(keywords[7], "key7"); // an override keeps the place of the first
    EXPECT_EQ(keywords[std::size_t(n)], "more");
    EXPECT_EQ(keywords.back(), "last");
    d.subDict("more");
    for (int i = 0; i < n; ++i) ASSERT_EQ(d.get<int>(keywords[std::size_t(i)]), i == 7 ? -7 : i) << keywords[std::size_t(i)];
    EXPECT_EQ(d.get<int>("last"), n - 1);
    EXPECT_NO_THROW(d.checkAllKeywordsUsed());
    EXPECT_CONTAINS(errorOf([&] { d.get<int>("key200000"); }), "keyword 'key200000' is missing in testDict");
}

TEST(DictionaryLimits, SubstitutionThatKeepsDoublingStopsAtItsBound) {
    // a0 x; a1 ($a0 $a0); a2 ($a1 $a1); ...: 40 levels would be 3·2^40 tokens, which ended in
    // std::bad_alloc.
    std::string text = "a0 x;\n";
    for (int i = 1; i <= 40; ++i) {
        const std::string previous = std::string("$a").append(std::to_string(i - 1));
        const std::string current = std::string("a").append(std::to_string(i));
        text.append(current).append(" (").append(previous).append(" ").append(previous).append(");\n");
    }
    EXPECT_EQ(errorOf([&] { Dictionary::fromString(text, "doubling"); }),
              "doubling:16:6: error: substituting '$a14' makes the substitutions in this dictionary exceed 100000 "
              "tokens (keywords, values and sub-dictionaries) (keyword 'a15')");
    // below the bound the same substitutions are made in full
    const Dictionary d = Dictionary::fromString(text.substr(0, text.find("a15 ")), "doubling");
    EXPECT_EQ(d.findEntry("a14")->tokens.size(), 3u * (1u << 14) - 2u);
}

TEST(DictionaryLimits, CopiesOfDictionariesStopAtTheSubstitutionBound) {
    // each d<i> holds two copies of d<i-1>: 2^i copies of d0
    const auto doubling = [](const std::string& d0) {
        std::string text = d0;
        for (int i = 1; i <= 20; ++i) {
            const std::string previous = std::string("$d").append(std::to_string(i - 1));
            const std::string current = std::string("d").append(std::to_string(i));
            text.append(current).append(" { a ").append(previous).append("; b ").append(previous).append("; }\n");
        }
        return text;
    };
    std::string list = "d0 { v (";
    for (int i = 0; i < 1000; ++i) list += " 1";
    EXPECT_EQ(errorOf([&] { Dictionary::fromString(doubling(list + "); }\n"), "copies"); }),
              "copies:7:15: error: copying '$d5' makes the substitutions in this dictionary exceed 100000 tokens "
              "(keywords, values and sub-dictionaries) (keyword 'b')");
    // a sub-dictionary counts as 5 tokens, empty or not
    EXPECT_CONTAINS(errorOf([&] { Dictionary::fromString(doubling("d0 { }\n"), "copies"); }),
                    "copies:14:9: error: copying '$d12' makes the substitutions in this dictionary exceed 100000 tokens");
}

TEST(DictionaryLimits, ReadingStopsAtTheTokenBound) {
    // 11 values of a million tokens each: every token read counts
    std::string values = " (";
    for (int i = 0; i < 999'999; ++i) values += " 1";
    values += ");\n";
    std::string text;
    for (int i = 0; i < 11; ++i) text.append("v").append(std::to_string(i)).append(values);
    const std::string message = errorOf([&] { Dictionary::fromString(text, "many"); });
    EXPECT_CONTAINS(message, "many:10:");
    EXPECT_CONTAINS(message, "error: the value of 'v9' makes the dictionary exceed 10000000 tokens (keywords, values and "
                             "sub-dictionaries; read, #included or substituted) (keyword 'v9')");
}

TEST(DictionaryFiles, FileOverTheSizeLimitGivesItsSizeAndTheLimit) {
    TempDir dir;
    const fs::path big = dir.writeFile("system/big", "");
    fs::resize_file(big, std::uintmax_t(65) << 20); // sparse: no disk space used
    EXPECT_EQ(errorOf([&] { Dictionary::fromFile(big); }),
              big.string() + ": error: file is 65.0 MiB (68157440 bytes); a dictionary file may be at most 64 MiB");
    const fs::path file = dir.writeFile("system/controlDict", "a 1;\n#include \"big\"\n");
    EXPECT_EQ(errorOf([&] { Dictionary::fromFile(file); }),
              file.string() + ":2:1: error: include file '" + big.lexically_normal().string() +
                  "' is 65.0 MiB (68157440 bytes); a dictionary file may be at most 64 MiB");
    // 64 MiB are read (and refused for what they hold: NUL bytes)
    fs::resize_file(big, std::uintmax_t(64) << 20);
    EXPECT_EQ(errorOf([&] { Dictionary::fromFile(big); }), big.string() + ":1:1: error: unexpected character byte 0x00");
}

TEST(DictionaryFiles, RepeatedIncludesAreBoundedInTotal) {
    TempDir dir;
    dir.writeFile("system/comment", "// " + std::string(std::size_t(60) << 20, '-') + "\n"); // 60 MiB, no entry
    std::string text;
    for (int i = 0; i < 5; ++i) text += "#include \"comment\"\n";
    const fs::path file = dir.writeFile("system/controlDict", text + "a 1;\n");
    EXPECT_CONTAINS(errorOf([&] { Dictionary::fromFile(file); }),
                    file.string() + ":5:1: error: including '");
    EXPECT_CONTAINS(errorOf([&] { Dictionary::fromFile(file); }),
                    "comment' makes the files read for this dictionary exceed 256 MiB (repeated #includes count each time)");
    const fs::path four = dir.writeFile("system/four", text.substr(0, text.size() / 5 * 4) + "a 1;\n");
    EXPECT_EQ(Dictionary::fromFile(four).get<int>("a"), 1);
}

// ---------------------------------------------------------------------------------------------
// Bad input: each case must fail with the exact location and message start.

namespace {

struct BadInput {
    std::string name;
    std::string text;
    std::string expected;                           // substring of what()
    std::function<void(Dictionary&)> action = {};   // a lookup to run after parsing (optional)
};

std::ostream& operator<<(std::ostream& os, const BadInput& c) { return os << c.name; }

const std::string at = testFile + ":";

const std::vector<BadInput> badInputs = {
    // --- missing ';'
    {"MissingSemicolonBeforeNextEntry", "endTime 1\ndeltaT 0.1;\n",
     at + "2:1: error: expected ';' after the value of 'endTime', found 'deltaT' on a new line"},
    {"MissingSemicolonAfterList", "gravity (0 -9.81 0)\nrho 1000;\n",
     at + "2:1: error: expected ';' after the value of 'gravity', found 'rho' on a new line"},
    {"MissingSemicolonBeforeSubDictionary", "endTime 1\npressure\n{\n}\n",
     at + "2:1: error: expected ';' after the value of 'endTime', found 'pressure'"},
    {"MissingSemicolonBeforeClosingBrace", "p\n{\n    gamma 7\n}\n",
     at + "4:1: error: expected ';' after the value of 'gamma', found '}'"},
    {"MissingSemicolonOnOneLine", "p { gamma 7 }\n", at + "1:13: error: expected ';' after the value of 'gamma', found '}'"},
    {"MissingSemicolonAtEndOfFile", "a 1;\nendTime 1\n\n",
     at + "2:10: error: expected ';' after the value of 'endTime', found end of file"},
    {"MissingValueBeforeSemicolon", "endTime ;\n", at + "1:9: error: missing value for 'endTime' before ';'"},
    {"MissingValueAndSemicolon", "endTime\ndeltaT 1;\n",
     at + "2:1: error: expected a value for 'endTime', found 'deltaT' on a new line"},
    {"ValueFollowedByBrace", "a 1 { b 2; }\n", at + "1:5: error: expected ';' after the value of 'a', found '{'"},
    // --- braces
    {"UnexpectedClosingBrace", "a 1;\n}\nb 2;\n", at + "2:1: error: unexpected '}' (no dictionary is open here)"},
    {"MissingClosingBrace", "p\n{\n    gamma 7;\n\n",
     at + "3:13: error: missing '}' at end of file: dictionary 'testDict.p' opened at " + at + "2:1 is not closed"},
    {"MissingClosingBraceOfOuterDictionary", "a\n{\n  b\n  {\n    c 1;\n  }\n",
     at + "6:4: error: missing '}' at end of file: dictionary 'testDict.a' opened at " + at + "2:1"},
    {"ExtraClosingBraceAfterSubDictionary", "a { b 1; } }\n", at + "1:12: error: unexpected '}'"},
    // --- parentheses
    {"UnclosedListBeforeSemicolon", "g (0 -9.81 0;\n",
     at + "1:13: error: expected ')' to close the list opened at " + at + "1:3, found ';'"},
    {"UnclosedNestedList", "p ((0 0 0) (1 1 1);\n",
     at + "1:19: error: expected ')' to close the list opened at " + at + "1:3, found ';'"},
    {"UnclosedListAtEndOfFile", "g\n(\n  1\n  2\n",
     at + "4:4: error: expected ')' to close the list opened at " + at + "2:1, found end of file"},
    {"UnclosedListBeforeBrace", "p { g (0 0 0; }\n", at + "1:13: error: expected ')' to close the list opened at " + at + "1:7"},
    {"UnexpectedClosingParenthesis", "g 0 -9.81 0);\n", at + "1:12: error: unexpected ')' in the value of 'g'"},
    {"ListAsKeyword", "(1 2);\n", at + "1:1: error: expected a keyword, found '('"},
    // --- comments and strings
    {"UnterminatedBlockComment", "a 1;\n  /* never closed\nb 2;\n", at + "2:3: error: unterminated comment"},
    {"UnterminatedBlockCommentInValue", "a (1 /* 2 3);\n", at + "1:6: error: unterminated comment"},
    {"UnterminatedString", "a 1;\nname \"abc;\nb 2;\n", at + "2:6: error: unterminated string"},
    {"UnterminatedStringAtEndOfFile", "name \"abc", at + "1:6: error: unterminated string"},
    // --- other lexical errors
    {"UnexpectedCharacter", "a 1;\nb = 2;\n", at + "2:3: error: unexpected character '='"},
    {"NumberAsKeyword", "1 2;\n", at + "1:1: error: expected a keyword, found '1'"},
    {"DollarWithoutName", "a $;\n", at + "1:3: error: expected a keyword name after '$'"},
    // --- a value spoiled by a character: the error names the keyword too
    {"DecimalComma", "endTime 0,02;\n", at + "1:9: error: '0,02' is not a number (use a decimal point) (keyword 'endTime')"},
    {"DecimalCommaInList", "g (0 -9,81 0);\n", at + "1:6: error: '-9,81' is not a number (use a decimal point) (keyword 'g')"},
    {"CommasBetweenListElements", "g (0,1,0);\n",
     at + "1:5: error: unexpected character ',' (list elements are separated by spaces, not commas) (keyword 'g')"},
    {"CommaAfterListElement", "g (0, -9.81, 0);\n",
     at + "1:5: error: unexpected character ',' (list elements are separated by spaces, not commas) (keyword 'g')"},
    {"NonAsciiCharacterInValue", "endTime 1.5\u00b5s;\n",
     at + "1:12: error: unexpected character '\u00b5' (U+00B5; only comments and quoted strings may hold non-ASCII "
          "text) (keyword 'endTime')"},
    {"FourByteCharacterInValue", "a \U0001F30A;\n", at + "1:3: error: unexpected character '\U0001F30A' (U+1F30A;"},
    {"InvalidUtf8ByteInValue", "endTime 1\xff;\n", at + "1:10: error: unexpected character byte 0xff (not UTF-8 text) (keyword 'endTime')"},
    {"NonAsciiCharacterInKeyword", "endTim\u00e9 1;\n", at + "1:7: error: unexpected character '\u00e9' (U+00E9;"},
    {"NonAsciiCharacterAtKeywordPosition", "a 1;\n\u00e9 2;\n", at + "2:1: error: unexpected character '\u00e9' (U+00E9; only comments and quoted strings may hold non-ASCII text)"},
    {"UnterminatedStringInValueNamesTheKeyword", "name \"abc;\n",
     at + "1:6: error: unterminated string: missing closing '\"' on this line (keyword 'name')"},
    // --- columns count characters, not bytes
    {"ColumnAfterUtf8Comment", "/* gr\u00f6\u00dfe */ endTime abc;\n", at + "1:21: error: expected a number for 'endTime', found word 'abc'",
     [](Dictionary& d) { d.get<double>("endTime"); }},
    {"ColumnAfterUtf8String", "title \"\u65e5\u672c \U0001F30A\"; x = 1;\n", at + "1:17: error: unexpected character '=' (keyword 'x')"},
    {"LongListIsShownShortened", "v (1 2 3 4 5 6 7 8 9 10 11 12 13 14 15);\n",
     at + "1:3: error: expected a number for 'v', found list (1 2 3 4 5 6 7 8 9 10 11 ... (keyword 'v')",
     [](Dictionary& d) { d.get<double>("v"); }},
    {"LongWordIsShownShortened", "v " + std::string(100, 'w') + ";\n",
     at + "1:3: error: expected a number for 'v', found word '" + std::string(80, 'w') + " ...' (keyword 'v')",
     [](Dictionary& d) { d.get<double>("v"); }},
    {"LongValueWhereSubDictionaryExpectedIsShownShortened", "p (1 2 3 4 5 6 7 8 9 10 11 12 13 14 15);\n",
     at + "1:1: error: 'p' in testDict must be a dictionary ('p { ... }'), found the value '(1 2 3 4 5 6 7 8 9 10 11 ...'",
     [](Dictionary& d) { d.subDict("p"); }},
    {"EndOfFileColumnAfterUtf8", "a \"\u00e9\"\n", at + "1:6: error: expected ';' after the value of 'a', found end of file"},
    // --- directives
    {"UnknownDirective", "#inputMode merge\n", at + "1:1: error: unknown directive '#inputMode'"},
    {"IncludeWithoutQuotedName", "#include common\n", at + "1:10: error: expected a quoted file name after '#include'"},
    {"MissingInclude", "a 1;\n#include \"doesNotExist\"\n",
     at + "2:1: error: cannot open include file 'case/system/doesNotExist'"},
    // --- substitution
    {"UndefinedVariable", "a 1;\nb $c;\n", at + "2:3: error: undefined variable '$c'"},
    {"UndefinedVariableWithSuggestion", "rho 1;\nb (0 $rh0 0);\n",
     at + "2:6: error: undefined variable '$rh0' (did you mean '$rho'?)"},
    {"UndefinedScopedVariable", "a { x 1; }\nb $a.y;\n", at + "2:3: error: undefined variable '$a.y'"},
    {"VariableDefinedInAnotherBranchIsNotVisible", "a { x 1; }\nb { y $x; }\n", at + "2:7: error: undefined variable '$x'"},
    {"VariableDefinedLaterIsUndefined", "a $b;\nb 1;\n", at + "1:3: error: undefined variable '$b'"},
    {"DictionaryVariableInsideList", "d { x 1; }\nv (1 $d);\n", at + "2:6: error: '$d' is a dictionary"},
    {"ValueVariableAtKeywordPosition", "v 1;\n$v;\n", at + "2:1: error: '$v' used as an entry must name a dictionary"},
    // --- typed lookups
    {"WordWhereNumberExpected", "endTime abc;\n",
     at + "1:9: error: expected a number for 'endTime', found word 'abc' (keyword 'endTime')",
     [](Dictionary& d) { d.get<double>("endTime"); }},
    {"StringWhereNumberExpected", "endTime \"1\";\n", at + "1:9: error: expected a number for 'endTime', found string \"1\"",
     [](Dictionary& d) { d.get<double>("endTime"); }},
    {"ListWhereNumberExpected", "endTime (1 2);\n", at + "1:9: error: expected a number for 'endTime', found list (1 2)",
     [](Dictionary& d) { d.get<double>("endTime"); }},
    {"ExtraTokenAfterNumber", "endTime 1 2;\n",
     at + "1:11: error: unexpected number 2 after the value of 'endTime' (expected a number)",
     [](Dictionary& d) { d.get<double>("endTime"); }},
    {"DictionaryWhereNumberExpected", "\nendTime { }\n", at + "2:1: error: expected a number for 'endTime', found a dictionary",
     [](Dictionary& d) { d.get<double>("endTime"); }},
    {"NumberOutOfRange", "x 1e999;\n", at + "1:3: error: number 1e999 for 'x' is out of range",
     [](Dictionary& d) { d.get<double>("x"); }},
    {"IntegerExpectedFoundFraction", "nSteps 1.5;\n", at + "1:8: error: expected an integer for 'nSteps', found number 1.5",
     [](Dictionary& d) { d.get<int>("nSteps"); }},
    {"IntegerOutOfRange", "n 3000000000;\n", at + "1:3: error: number 3000000000 for 'n' is out of range",
     [](Dictionary& d) { d.get<int>("n"); }},
    {"UnsignedGivenNegative", "layers -1;\n", at + "1:8: error: expected a non-negative integer for 'layers', found number -1",
     [](Dictionary& d) { d.get<unsigned>("layers"); }},
    {"LongExpectedFoundWord", "n many;\n", at + "1:3: error: expected an integer for 'n', found word 'many'",
     [](Dictionary& d) { d.get<long>("n"); }},
    {"FloatOutOfRange", "f 1e300;\n", at + "1:3: error: number 1e300 for 'f' is out of range (float)",
     [](Dictionary& d) { d.get<float>("f"); }},
    {"InvalidBool", "adjustTimeStep maybe;\n",
     at + "1:16: error: expected a switch (true/false, on/off, yes/no) for 'adjustTimeStep', found word 'maybe'",
     [](Dictionary& d) { d.get<bool>("adjustTimeStep"); }},
    {"NumberWhereWordExpected", "type 1;\n", at + "1:6: error: expected a word or quoted string for 'type', found number 1",
     [](Dictionary& d) { d.get<std::string>("type"); }},
    {"VectorWithTwoComponents", "gravity (0 -9.81);\n", at + "1:9: error: expected 3 components (x y z) for 'gravity', found 2",
     [](Dictionary& d) { d.get<Vec3>("gravity"); }},
    {"VectorWithFourComponents", "gravity (0 -9.81 0 1);\n", at + "1:9: error: expected 3 components (x y z) for 'gravity', found 4",
     [](Dictionary& d) { d.get<Vec3>("gravity"); }},
    {"VectorWithWordComponent", "gravity (0 g 0);\n",
     at + "1:12: error: expected a number as vector component for 'gravity', found word 'g'",
     [](Dictionary& d) { d.get<Vec3>("gravity"); }},
    {"NumberWhereVectorExpected", "gravity 9.81;\n", at + "1:9: error: expected a vector (x y z) for 'gravity', found number 9.81",
     [](Dictionary& d) { d.get<Vec3>("gravity"); }},
    {"NestedListInNumberList", "v (1 (2) 3);\n", at + "1:6: error: expected a number as list element for 'v', found list (2)",
     [](Dictionary& d) { d.get<std::vector<double>>("v"); }},
    {"NumberInWordList", "fields (p 1);\n", at + "1:11: error: expected a word or quoted string as list element for 'fields', found number 1",
     [](Dictionary& d) { d.get<std::vector<std::string>>("fields"); }},
    {"NumberInVectorList", "points ((0 0 0) 1);\n", at + "1:17: error: expected a vector (x y z) as list element for 'points', found number 1",
     [](Dictionary& d) { d.get<std::vector<Vec3>>("points"); }},
    {"WrongTypeInSubstitutedValueIsReportedAtItsDefinition", "t abc;\nendTime $t;\n",
     at + "1:3: error: expected a number for 'endTime', found word 'abc'",
     [](Dictionary& d) { d.get<double>("endTime"); }},
    // --- missing keywords, sub-dictionaries, unknown keywords and values
    {"MissingKeywordWithSuggestion", "endTim 1;\n",
     testFile + ": error: keyword 'endTime' is missing in testDict (did you mean 'endTim'?) (keyword 'endTime')",
     [](Dictionary& d) { d.get<double>("endTime"); }},
    {"MissingKeywordWithoutSuggestion", "deltaT 1;\n", testFile + ": error: keyword 'writeInterval' is missing in testDict (keyword",
     [](Dictionary& d) { d.get<double>("writeInterval"); }},
    {"MissingKeywordInSubDictionaryIsReportedAtTheSubDictionary", "\n  pressure\n  {\n  }\n",
     at + "2:3: error: keyword 'gamma' is missing in testDict.pressure",
     [](Dictionary& d) { d.subDict("pressure").get<double>("gamma"); }},
    {"MissingSubDictionary", "kernal { }\n", testFile + ": error: keyword 'kernel' is missing in testDict (did you mean 'kernal'?)",
     [](Dictionary& d) { d.subDict("kernel"); }},
    {"ValueWhereSubDictionaryExpected", "a 1;\npressure wcsph;\n",
     at + "2:1: error: 'pressure' in testDict must be a dictionary ('pressure { ... }'), found the value 'wcsph'",
     [](Dictionary& d) { d.subDict("pressure"); }},
    {"UnknownKeywordWithSuggestion", "pressure\n{\n    type      wcsph;\n    gama      7;\n    stiffness 1;\n}\n",
     at + "4:5: error: unknown keyword 'gama' in testDict.pressure (did you mean 'gamma'?); "
          "valid keywords: (gamma stiffness type) (keyword 'gama')",
     [](Dictionary& d) {
         const Dictionary& p = d.subDict("pressure");
         p.getWord("type", {"wcsph"});
         p.getOrDefault<double>("gamma", 7.0);
         p.get<double>("stiffness");
         p.checkAllKeywordsUsed();
     }},
    {"UnknownKeywordWithoutSuggestion", "endTime 1;\nfoo 2;\n",
     at + "2:1: error: unknown keyword 'foo' in testDict; valid keywords: (endTime)",
     [](Dictionary& d) {
         d.get<double>("endTime");
         d.checkAllKeywordsUsed();
     }},
    {"GetWordWithInvalidValue", "type symplecticEulr;\n",
     at + "1:6: error: unknown value 'symplecticEulr' for 'type'; valid: (leapfrog symplecticEuler); "
          "did you mean 'symplecticEuler'? (keyword 'type')",
     [](Dictionary& d) { d.getWord("type", {"leapfrog", "symplecticEuler"}); }},
    {"GetWordWithFarOffValue", "type banana;\n", at + "1:6: error: unknown value 'banana' for 'type'; valid: (leapfrog symplecticEuler) (keyword",
     [](Dictionary& d) { d.getWord("type", {"leapfrog", "symplecticEuler"}); }},
    {"SetOverrideWithWrongType", "endTime 1;\n", "<override>:1:1: error: expected a number for 'endTime', found word 'x'",
     [](Dictionary& d) {
         d.set("endTime", "x");
         d.get<double>("endTime");
     }},
};

class DictionaryBadInput : public testing::TestWithParam<BadInput> {};

} // namespace

TEST_P(DictionaryBadInput, FailsWithExactLocationAndMessage) {
    const BadInput& c = GetParam();
    const std::string message = errorOf([&] {
        Dictionary d = parse(c.text);
        if (c.action) c.action(d);
    });
    EXPECT_CONTAINS(message, c.expected);
}

INSTANTIATE_TEST_SUITE_P(Table, DictionaryBadInput, testing::ValuesIn(badInputs),
                         [](const testing::TestParamInfo<BadInput>& info) { return info.param.name; });

TEST(DictionaryBadInputTable, NamesAreUnique) {
    std::set<std::string> names;
    for (const auto& c : badInputs) EXPECT_TRUE(names.insert(c.name).second) << c.name;
}
