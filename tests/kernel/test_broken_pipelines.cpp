// Every file in tests/kernel/broken/ is a pipeline with mistakes; its "# expect: [FILE:]LINE:COL:
// TEXT" lines say which errors it must produce, where, and what they must say.
#include <regex>

#include "test_support.hpp"

namespace wysiwyf::test {

namespace fs = std::filesystem;

struct Expectation {
  std::string file_suffix;  // empty: the pipeline file itself
  int line, column;
  std::string text;
};

std::vector<Expectation> expectations(const fs::path& file) {
  std::vector<Expectation> out;
  std::ifstream in(file);
  static const std::regex re(R"(^# expect: (?:([^:]+):)?(\d+):(\d+): (.*)$)");
  for (std::string line; std::getline(in, line);) {
    std::smatch m;
    if (std::regex_match(line, m, re))
      out.push_back({m[1].str(), std::stoi(m[2].str()), std::stoi(m[3].str()), m[4].str()});
  }
  return out;
}

// Every error of the file in one check, as `wysiwyf validate` reports them.
std::vector<ConfigIssue> all_errors(const fs::path& file) {
  Loader loader(test_search_dirs());
  return check_pipeline(file.string(), {}, loader).validation.errors;
}

class BrokenPipeline : public ::testing::TestWithParam<std::string> {};

TEST_P(BrokenPipeline, GivesTheExpectedErrorsAtTheirLines) {
  const fs::path file = fs::path(WYSIWYF_TEST_BROKEN_DIR) / GetParam();
  const auto wanted = expectations(file);
  ASSERT_FALSE(wanted.empty()) << file << " has no '# expect:' line";
  const auto errors = all_errors(file);
  ASSERT_FALSE(errors.empty()) << file << " was accepted";
  std::string got;
  for (const auto& e : errors) got += "  " + e.str() + "\n";
  for (const auto& w : wanted) {
    const std::string where_file = w.file_suffix.empty() ? file.string() : w.file_suffix;
    const bool found = std::any_of(errors.begin(), errors.end(), [&](const ConfigIssue& e) {
      const bool file_ok =
          e.where.file.size() >= where_file.size() &&
          e.where.file.compare(e.where.file.size() - where_file.size(), where_file.size(), where_file) == 0;
      return file_ok && e.where.line == w.line && e.where.column == w.column &&
             e.message.find(w.text) != std::string::npos;
    });
    EXPECT_TRUE(found) << "expected at " << where_file << ":" << w.line << ":" << w.column << ": " << w.text
                       << "\ngot:\n"
                       << got;
  }
}

std::vector<std::string> corpus() {
  std::vector<std::string> names;
  for (const auto& e : fs::directory_iterator(WYSIWYF_TEST_BROKEN_DIR))
    if (e.path().extension() == ".yaml") names.push_back(e.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}

INSTANTIATE_TEST_SUITE_P(Corpus, BrokenPipeline, ::testing::ValuesIn(corpus()),
                         [](const ::testing::TestParamInfo<std::string>& info) {
                           std::string n = info.param.substr(0, info.param.size() - 5);
                           return n;
                         });

// A file with ten mistakes of different kinds gets ten errors from one check: none hidden by
// another (the file's own before its components'), none reported twice as a knock-on.
TEST(BrokenPipelineCorpus, TenMistakesAreTenErrorsInOneCheck) {
  const fs::path file = fs::path(WYSIWYF_TEST_BROKEN_DIR) / "ten_mistakes.yaml";
  const auto errors = all_errors(file);
  std::string got;
  for (const auto& e : errors) got += "  " + e.str() + "\n";
  EXPECT_EQ(expectations(file).size(), 10u);
  EXPECT_EQ(errors.size(), 10u) << got;
  EXPECT_TRUE(std::is_sorted(errors.begin(), errors.end(), [](const ConfigIssue& a, const ConfigIssue& b) {
    return a.where.line < b.where.line;
  })) << got;
}

TEST(BrokenPipelineCorpus, HasAtLeastTwentyFiles) { EXPECT_GE(corpus().size(), 20u); }

TEST(PipelineErrors, CommandLineSetNamesAnUnknownComponent) {
  try {
    load_pipeline_from_string("wysiwyf: 1\ncomponents:\n  probe: {type: test_probe, rate: 100}\n", "p.yaml",
                              {"prob.params.gain=1"});
    FAIL() << "accepted";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("--set prob.params.gain=1: error: found component 'prob'"), std::string::npos)
        << e.what();
    EXPECT_NE(std::string(e.what()).find("did you mean 'probe'"), std::string::npos) << e.what();
  }
}

TEST(PipelineErrors, CommandLineSetValueIsValidatedLikeTheFile) {
  const PipelineSpec spec = load_pipeline_from_string(
      "wysiwyf: 1\ncomponents:\n  probe: {type: test_probe, rate: 100}\n", "p.yaml", {"probe.params.gain=99"});
  Loader loader(test_search_dirs());
  const auto v = validate_pipeline(spec, loader);
  ASSERT_EQ(v.errors.size(), 1u);
  EXPECT_EQ(v.errors[0].where.file, "--set probe.params.gain=99");
  EXPECT_NE(v.errors[0].message.find("expected a value in [-10, 10]"), std::string::npos) << v.errors[0].message;
}

TEST(PipelineErrors, UnknownProcessGroupListsTheGroups) {
  const PipelineSpec spec = load_pipeline_from_string(
      "wysiwyf: 1\ncomponents:\n  a: {type: test_probe, rate: 100, process: vision}\n"
      "  b: {type: test_probe, rate: 100, process: haptics}\n",
      "p.yaml");
  Loader loader(test_search_dirs());
  const auto v = validate_pipeline(spec, loader, "visoin");
  ASSERT_FALSE(v.ok());
  EXPECT_NE(v.errors[0].message.find("expected one of vision, haptics (did you mean 'vision'?)"), std::string::npos)
      << v.errors[0].message;
}

}  // namespace wysiwyf::test
