// The project's documentation stands alone: README, CHANGELOG, docs/, openplc/ and the man pages
// never send the reader to files outside the repository (the specification documents the
// project was built from are not shipped), and every relative link of the Markdown files leads to
// a file that exists. Nor do the sources' comments: they cite the manuals' items and our docs.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

namespace stepmod::tools {
namespace {

namespace fs = std::filesystem;

const fs::path kRoot = STEPMOD_SOURCE_DIR;

// README.md, CHANGELOG.md and every file under docs/, openplc/ and packaging/man/ (text only).
std::vector<fs::path> documentation_files() {
  std::vector<fs::path> files = {kRoot / "README.md", kRoot / "CHANGELOG.md"};
  for (const char* dir : {"docs", "openplc", "packaging/man"}) {
    for (const auto& e : fs::recursive_directory_iterator(kRoot / dir)) {
      if (e.is_regular_file() && e.path().extension() != ".png") files.push_back(e.path());
    }
  }
  return files;
}

std::string read(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

TEST(DocsSelfContained, NoReferenceToTheSpecificationOutsideTheRepository) {
  for (const fs::path& f : documentation_files()) {
    const std::string text = read(f);
    std::istringstream lines(text);
    std::string line;
    for (int n = 1; std::getline(lines, line); ++n) {
      for (const char* name : {"shared/spec", "INTERFACE.md", "MODULES.md"}) {
        if (line.find(name) == std::string::npos) continue;
        ADD_FAILURE() << fs::relative(f, kRoot).string() << ":" << n << " names " << name
                      << " (not in the repository; point at docs/interface.md instead): " << line;
      }
    }
  }
}

// Every file of the product's folders and the scripts, text only.
std::vector<fs::path> source_files() {
  std::vector<fs::path> files = {kRoot / "CMakeLists.txt"};
  for (const char* dir : {"bench",     "cmake",    "config", "core",     "daemon", "doctor",
                          "examples",  "fieldbus", "gpio",   "ipc",      "module", "module_types",
                          "packaging", "planner",  "plc",    "registry", "rt",     "scripts",
                          "systemd",   "tools",    "web",    "words"}) {
    for (const auto& e : fs::recursive_directory_iterator(kRoot / dir)) {
      if (e.is_regular_file() && e.path().extension() != ".png") files.push_back(e.path());
    }
  }
  return files;
}

TEST(DocsSelfContained, SourcesCiteTheManualsAndOurDocsOnly) {
  // The digest's section numbers and the contract's are not the reader's to look up: a comment
  // names the manual's chapter, table or checklist item, or docs/interface.md's section.
  const std::regex outside(R"(shared/spec|INTERFACE\.md|MODULES\.md|INTERFACE [0-9]|digest [0-9])");
  for (const fs::path& f : source_files()) {
    std::istringstream lines(read(f));
    std::string line;
    for (int n = 1; std::getline(lines, line); ++n) {
      EXPECT_FALSE(std::regex_search(line, outside))
          << fs::relative(f, kRoot).string() << ":" << n
          << " cites a document outside the repository: " << line;
    }
  }
}

TEST(DocsSelfContained, RelativeMarkdownLinksLeadToFiles) {
  const std::regex link(R"(\]\(([^)#\s]+)(#[^)]*)?\))");
  for (const fs::path& f : documentation_files()) {
    if (f.extension() != ".md") continue;
    const std::string text = read(f);
    for (std::sregex_iterator it(text.begin(), text.end(), link), last; it != last; ++it) {
      const std::string target = (*it)[1];
      if (target.find("://") != std::string::npos || target.rfind("mailto:", 0) == 0) continue;
      EXPECT_TRUE(fs::exists(f.parent_path() / target))
          << fs::relative(f, kRoot).string() << " links to " << target << ", which does not exist";
    }
  }
}

// The README's test command is what CI runs: .ci/run ends in `exec scripts/test`, and the README
// tells a newcomer to run that same command.
TEST(DocsSelfContained, ReadmeTestCommandIsWhatCiRuns) {
  const std::string ci = read(kRoot / ".ci/run");
  std::smatch m;
  ASSERT_TRUE(std::regex_search(ci, m, std::regex(R"(\nexec ([^\s]+))")))
      << ".ci/run has no exec line";
  const std::string command = m[1];
  const std::string readme = read(kRoot / "README.md");
  EXPECT_NE(readme.find("\n" + command + " "), std::string::npos)
      << "README.md does not show CI's test command " << command;
  EXPECT_EQ(readme.find("build/dev/"), std::string::npos)
      << "README.md names build/dev/, not a build tree";
}

}  // namespace
}  // namespace stepmod::tools
