// The loader accepts a good component library and refuses broken ones with a useful message.
#include <algorithm>
#include <filesystem>

#include "test_support.hpp"

namespace wysiwyf::test {

const std::string kBroken = std::string(WYSIWYF_TEST_COMPONENT_DIR) + "/broken";

std::string load_error(Loader& loader, const std::string& path) {
  try {
    loader.load_file(path);
  } catch (const LoadError& e) {
    return e.what();
  }
  return "(loaded without error)";
}

TEST(Loader, LoadsAGoodLibraryAndCreatesItsComponent) {
  Loader loader(test_search_dirs());
  const ComponentLibrary& lib = loader.load("test_probe");
  EXPECT_EQ(lib.type_name, "test_probe");
  EXPECT_EQ(lib.entry->abi_version, kAbiVersion);
  EXPECT_STREQ(lib.entry->build_id, kernel_build_id());
  ComponentPtr c = loader.create("test_probe");
  ASSERT_NE(c, nullptr);
  const auto d = describe_component(loader, "test_probe");
  EXPECT_EQ(d.ports.size(), 2u);
  EXPECT_EQ(d.params.front().name, "gain");
}

TEST(Loader, RefusesAWrongAbiVersionAndSaysToRebuild) {
  Loader loader(test_search_dirs());
  const std::string msg = load_error(loader, kBroken + "/wysiwyf_test_wrong_abi.so");
  EXPECT_NE(msg.find("component ABI version 999"), std::string::npos) << msg;
  EXPECT_NE(msg.find("this kernel has ABI version " + std::to_string(kAbiVersion)), std::string::npos) << msg;
  EXPECT_NE(msg.find("rebuild"), std::string::npos) << msg;
}

TEST(Loader, RefusesALibraryBuiltAgainstOtherKernelHeaders) {
  Loader loader(test_search_dirs());
  const std::string msg = load_error(loader, kBroken + "/wysiwyf_test_wrong_build.so");
  EXPECT_NE(msg.find("kernel build 0123456789abcdef"), std::string::npos) << msg;
  EXPECT_NE(msg.find(kernel_build_id()), std::string::npos) << msg;
  EXPECT_NE(msg.find("rebuild"), std::string::npos) << msg;
}

TEST(Loader, RefusesALibraryWithoutTheEntryPoint) {
  Loader loader(test_search_dirs());
  const std::string msg = load_error(loader, kBroken + "/wysiwyf_test_no_entry.so");
  EXPECT_NE(msg.find("is not a wysiwyf component library"), std::string::npos) << msg;
  EXPECT_NE(msg.find("wysiwyf_component_entry"), std::string::npos) << msg;
  EXPECT_NE(msg.find("WYSIWYF_COMPONENT"), std::string::npos) << msg;
}

TEST(Loader, RefusesALibraryWithAnUnresolvedSymbol) {
  Loader loader(test_search_dirs());
  const std::string msg = load_error(loader, kBroken + "/wysiwyf_test_unresolved.so");
  EXPECT_NE(msg.find("cannot load component library"), std::string::npos) << msg;
  EXPECT_NE(msg.find("wysiwyf_test_function_nobody_defines"), std::string::npos) << msg;
}

TEST(Loader, MissingFileAndUnknownTypeListTheKnownTypes) {
  Loader loader(test_search_dirs());
  EXPECT_NE(load_error(loader, "/nonexistent/wysiwyf_x.so").find("does not exist"), std::string::npos);
  try {
    loader.load("test_prob");
    FAIL() << "an unknown type loaded";
  } catch (const LoadError& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("unknown component type 'test_prob'"), std::string::npos) << msg;
    EXPECT_NE(msg.find("known types: test_display_recorder, test_pose_sink, test_probe"), std::string::npos) << msg;
  }
}

TEST(Loader, SearchPathPutsTheEnvironmentFirst) {
  setenv("WYSIWYF_COMPONENT_PATH", "/first:/second", 1);
  const auto dirs = Loader::default_search_dirs();
  unsetenv("WYSIWYF_COMPONENT_PATH");
  ASSERT_GE(dirs.size(), 3u);
  EXPECT_EQ(dirs[0], "/first");
  EXPECT_EQ(dirs[1], "/second");
  // Then this build's components, found from the program's and the core's place, not from a path
  // compiled in or an environment variable.
  EXPECT_NE(
      std::find(dirs.begin(), dirs.end(), std::filesystem::weakly_canonical(WYSIWYF_COMPONENT_BUILD_DIR).string()),
      dirs.end());
}

}  // namespace wysiwyf::test
