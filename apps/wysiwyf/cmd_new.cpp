// wysiwyf new component NAME [--dir DIR]: a ready out-of-tree component folder (source,
// CMakeLists.txt with find_package(wysiwyf), one Harness test) that builds and passes as written.
#include <cctype>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <regex>

#include "cli.hpp"
#include "wysiwyf/search_paths.hpp"

namespace wysiwyf::cli {

namespace {

// The templates: @NAME@ is the component type (snake_case), @CLASS@ its class (CamelCase).
const char* kCMakeLists = R"(# The @NAME@ component, built against an installed WYSIWYF (find_package(wysiwyf)):
#   cmake -S . -B build -DCMAKE_PREFIX_PATH=<wysiwyf prefix> && cmake --build build && ctest --test-dir build
cmake_minimum_required(VERSION 3.22)
project(@NAME@ LANGUAGES CXX)
set(CMAKE_CXX_STANDARD 17)
set(CMAKE_CXX_STANDARD_REQUIRED ON)
# A component runs in a 1 kHz loop: optimised, with debug information, unless asked otherwise.
if(NOT CMAKE_BUILD_TYPE AND NOT CMAKE_CONFIGURATION_TYPES)
  set(CMAKE_BUILD_TYPE RelWithDebInfo CACHE STRING "Build type" FORCE)
endif()

find_package(wysiwyf REQUIRED)
find_package(GTest REQUIRED)

# build/lib/wysiwyf/wysiwyf_@NAME@.so; `cmake --install build` puts it where wysiwyf looks.
wysiwyf_add_component(@NAME@ SOURCES @NAME@.cpp LINK wysiwyf::msgs)

# The test program sits in build/, so the Harness finds the component in build/lib/wysiwyf.
enable_testing()
add_executable(test_@NAME@ test_@NAME@.cpp)
target_link_libraries(test_@NAME@ PRIVATE wysiwyf::msgs GTest::gtest_main)
add_dependencies(test_@NAME@ component_@NAME@)
include(GoogleTest)
gtest_discover_tests(test_@NAME@)
)";

const char* kSource =
    R"(// @NAME@: scales a force/torque stream by a gain (a starting point: replace the body of tick()).
#include "wysiwyf/component.hpp"
#include "wysiwyf/msg_eigen.hpp"

namespace lab {

using namespace wysiwyf;

class @CLASS@ final : public Component {
 public:
  void configure(Context& ctx) override {
    ctx.summary("a wrench stream scaled by a gain");
    gain_ = ctx.param<double>("gain", 1.0, "factor applied to force and torque", Range{-1000, 1000});
    in_ = ctx.input<msg::WrenchStamped>("in", "the wrench to scale", Qos::reliable(64));
    out_ = ctx.output<msg::WrenchStamped>("out", "the scaled wrench, same frame and stamp");
  }

  void tick(Time) override {
    while (in_.take(sample_)) {
      const msgs::Vector6d w = msgs::to_vector6(sample_.wrench());
      if (!w.allFinite()) {
        reject(in_, "a non-finite force or torque");
        continue;
      }
      msgs::to_msg(gain_ * w, sample_.wrench());
      out_.write(sample_);
    }
  }

 private:
  double gain_ = 1.0;
  msg::WrenchStamped sample_;  // reused: no allocation per tick
  Input<msg::WrenchStamped> in_;
  Output<msg::WrenchStamped> out_;
};

}  // namespace lab

WYSIWYF_COMPONENT(lab::@CLASS@, "@NAME@")
)";

const char* kTest = R"(#include <gtest/gtest.h>

#include <limits>

#include "wysiwyf/harness.hpp"
#include "wysiwyf/msgs.hpp"

using namespace wysiwyf;

TEST(@CLASS@, ScalesTheWrenchAndRefusesANaN) {
  Harness h("@NAME@", "{gain: 2.5}");
  auto in = h.feed<msg::WrenchStamped>("in");
  auto out = h.watch<msg::WrenchStamped>("out");
  h.activate();

  msg::WrenchStamped w;
  w.header().stamp_ns(1'000'000);
  w.wrench().force().z(4.0);
  w.wrench().torque().x(-0.2);
  in.write(w);
  h.tick(Time{1'000'000});
  msg::WrenchStamped got;
  ASSERT_TRUE(out.take(got));
  EXPECT_DOUBLE_EQ(got.wrench().force().z(), 10.0);
  EXPECT_DOUBLE_EQ(got.wrench().torque().x(), -0.5);
  EXPECT_EQ(got.header().stamp_ns(), 1'000'000);

  w.wrench().force().x(std::numeric_limits<double>::quiet_NaN());
  in.write(w);
  h.tick(Time{2'000'000});
  EXPECT_FALSE(out.take(got));
  EXPECT_EQ(h.rejected("in"), 1u);
}

TEST(@CLASS@, RefusesAGainOutOfRange) {
  EXPECT_THROW(Harness("@NAME@", "{gain: 1e6}"), ConfigError);
}
)";

std::string camel_case(const std::string& name) {
  std::string out;
  bool up = true;
  for (char c : name) {
    if (c == '_') {
      up = true;
      continue;
    }
    out += up ? static_cast<char>(std::toupper(static_cast<unsigned char>(c))) : c;
    up = false;
  }
  return out;
}

std::string fill(std::string text, const std::string& name) {
  for (const auto& [key, value] : {std::pair<std::string, std::string>{"@NAME@", name}, {"@CLASS@", camel_case(name)}})
    for (std::size_t at; (at = text.find(key)) != std::string::npos;) text.replace(at, key.size(), value);
  return text;
}

}  // namespace

int cmd_new(Args args) {
  const auto what = args.take_front().value_or("");
  if (what != "component") throw UsageError("expected 'new component NAME [--dir DIR]'");
  const auto name = args.take_front();
  if (!name) throw UsageError("new component: expected a component type name, e.g. new component gesture_filter");
  if (!std::regex_match(*name, std::regex("^[a-z][a-z0-9_]*$")))
    throw UsageError("new component: found '" + *name +
                     "'; expected a type name of lower-case letters, digits and _, starting with a letter");
  const std::string dir = args.value("--dir").value_or(*name);
  if (!args.unknown_options().empty()) throw UsageError("unknown option " + args.unknown_options().front());
  namespace fs = std::filesystem;
  std::error_code ec;
  if (fs::exists(dir, ec) && !fs::is_empty(dir, ec)) {
    std::cerr << "wysiwyf new: " << dir << " exists and is not empty; nothing was written\n";
    return 1;
  }
  fs::create_directories(dir, ec);
  if (ec) {
    std::cerr << "wysiwyf new: cannot create " << dir << ": " << ec.message() << "\n";
    return 1;
  }
  const std::pair<std::string, const char*> files[] = {
      {"CMakeLists.txt", kCMakeLists}, {*name + ".cpp", kSource}, {"test_" + *name + ".cpp", kTest}};
  for (const auto& [file, text] : files) {
    std::ofstream out(fs::path(dir) / file);
    out << fill(text, *name);
    if (!out) {
      std::cerr << "wysiwyf new: cannot write " << (fs::path(dir) / file).string() << "\n";
      return 1;
    }
  }
  // The prefix this wysiwyf is installed in (its CMake package beside libwysiwyf_core.so).
  std::string prefix_option = " -DCMAKE_PREFIX_PATH=<the prefix wysiwyf is installed in>";
  const fs::path core = core_library_dir();
  if (!core.empty() && fs::exists(core / "cmake" / "wysiwyf" / "wysiwyfConfig.cmake", ec))
    prefix_option = " -DCMAKE_PREFIX_PATH=" + core.parent_path().string();
  std::cout << "wrote " << dir << "/{CMakeLists.txt, " << *name << ".cpp, test_" << *name << ".cpp}\n"
            << "build and test it against this wysiwyf:\n"
            << "  cmake -S " << dir << " -B " << dir << "/build" << prefix_option << " && cmake --build " << dir
            << "/build && ctest --test-dir " << dir << "/build\n";
  return 0;
}

}  // namespace wysiwyf::cli
