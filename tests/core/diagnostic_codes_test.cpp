#include "relief/core/diagnostic_codes.h"

#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

namespace relief {
namespace {

namespace fs = std::filesystem;

std::string read_text(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  EXPECT_TRUE(in) << "cannot read " << path;
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

const fs::path kSource = RELIEF_SOURCE_DIR;

std::set<std::string, std::less<>> registered_codes() {
  std::set<std::string, std::less<>> out;
  for (const DiagnosticCode& c : codes::kAll) out.emplace(c.code);
  return out;
}

TEST(DiagnosticCodes, AreUniqueWellFormedAndExplained) {
  const std::regex form(R"([a-z]+\.[a-z_]+)");
  std::set<std::string_view> seen;
  for (const DiagnosticCode& c : codes::kAll) {
    EXPECT_TRUE(seen.insert(c.code).second) << c.code << " is registered twice";
    EXPECT_TRUE(std::regex_match(std::string(c.code), form)) << c.code;
    EXPECT_GE(c.meaning.size(), 20u) << c.code << " has no meaning worth the name";
    EXPECT_EQ(c.meaning.find('\n'), std::string_view::npos) << c.code;
    EXPECT_EQ(c.meaning.find('|'), std::string_view::npos) << c.code << ": '|' breaks the README table";
  }
  EXPECT_EQ(std::string_view(codes::kDemSpike), "dem.spike");  // a constant reads as its code
}

// Every constant of the header is in kAll (a constant left out would escape the checks below).
TEST(DiagnosticCodes, EveryConstantIsInTheList) {
  const std::string header = read_text(kSource / "include/relief/core/diagnostic_codes.h");
  const std::regex constant(R"re(DiagnosticCode\s+k\w+\s*\{\s*"([^"]+)")re");
  const auto registered = registered_codes();
  std::size_t constants = 0;
  for (auto it = std::sregex_iterator(header.begin(), header.end(), constant); it != std::sregex_iterator();
       ++it) {
    ++constants;
    EXPECT_TRUE(registered.count((*it)[1].str())) << (*it)[1] << " is declared but not in codes::kAll";
  }
  EXPECT_EQ(constants, codes::kAll.size());
}

// The library reports codes only through the registry's constants: a string literal that is a
// registered code, or a code-like literal ("module.defect") in a statement that reports a
// diagnostic, is a code the registry does not hold (or bypasses).
TEST(DiagnosticCodes, SourcesUseTheConstantsOnly) {
  std::set<std::string, std::less<>> prefixes;
  for (const DiagnosticCode& c : codes::kAll) prefixes.emplace(c.code.substr(0, c.code.find('.')));
  const auto registered = registered_codes();
  const std::regex literal(R"re("([a-z]+)\.([a-z_]+)")re");
  std::vector<std::string> offences;
  std::size_t files = 0;
  for (const char* dir : {"src", "tools"}) {
    for (const auto& entry : fs::recursive_directory_iterator(kSource / dir)) {
      const std::string ext = entry.path().extension().string();
      if (!entry.is_regular_file() || (ext != ".cpp" && ext != ".h")) continue;
      ++files;
      const std::string text = read_text(entry.path());
      // Statement by statement (split at ';'), so that a call over several lines is one unit.
      std::size_t begin = 0;
      while (begin < text.size()) {
        const std::size_t end = std::min(text.find(';', begin), text.size());
        const std::string statement = text.substr(begin, end - begin);
        const bool reports = statement.find("report(") != std::string::npos ||
                             statement.find(".code =") != std::string::npos ||
                             statement.find("Diagnostic{") != std::string::npos;
        for (auto it = std::sregex_iterator(statement.begin(), statement.end(), literal);
             it != std::sregex_iterator(); ++it) {
          const std::string code = (*it)[1].str() + "." + (*it)[2].str();
          const bool known_module = prefixes.count((*it)[1].str()) > 0;
          if (registered.count(code) || known_module || reports) {
            offences.push_back(fs::relative(entry.path(), kSource).string() + ": \"" + code + "\"" +
                               (registered.count(code) ? " (use its constant)" : " (not registered)"));
          }
        }
        begin = end + 1;
      }
    }
  }
  EXPECT_GT(files, 100u);
  EXPECT_TRUE(offences.empty()) << [&] {
    std::string all;
    for (const std::string& o : offences) all += "\n  " + o;
    return "diagnostic codes as string literals in the sources:" + all;
  }();
}

// The README's table of codes ("| `code` | meaning |" under "Diagnostic codes") is the registry.
TEST(DiagnosticCodes, ReadmeListsTheRegistry) {
  const std::string readme = read_text(kSource / "README.md");
  const std::size_t section = readme.find("### Diagnostic codes");
  ASSERT_NE(section, std::string::npos) << "README.md has no section '### Diagnostic codes'";
  const std::size_t next = readme.find("\n#", section + 1);
  const std::string body =
      readme.substr(section, next == std::string::npos ? std::string::npos : next - section);
  const std::regex row(R"(\n\| `([a-z_.]+)` \| ([^\n]*?) \|(?=\n))");
  std::vector<std::pair<std::string, std::string>> listed;
  for (auto it = std::sregex_iterator(body.begin(), body.end(), row); it != std::sregex_iterator(); ++it)
    listed.emplace_back((*it)[1].str(), (*it)[2].str());
  ASSERT_EQ(listed.size(), codes::kAll.size()) << "README.md lists " << listed.size() << " codes";
  for (std::size_t i = 0; i < listed.size(); ++i) {
    EXPECT_EQ(listed[i].first, codes::kAll[i].code) << "row " << i + 1;
    EXPECT_EQ(listed[i].second, codes::kAll[i].meaning) << "row " << i + 1 << " (" << listed[i].first << ")";
  }
}

}  // namespace
}  // namespace relief
