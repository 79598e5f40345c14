// `topic echo --field`: one field of a sample, by name and index, and what is said when the path
// is not there.
#include <gtest/gtest.h>

#include <stdexcept>

#include "yaml_field.hpp"

namespace wysiwyf::test {

const char* const kSample =
    "header:\n  stamp: 1500000000\n  frame_id: base\n"
    "name: [j1, j2, j3]\nposition: [0.1, -2.5e-05, 3]\n"
    "wrench:\n  force: {x: 1, y: 2, z: 3}\n";

TEST(EchoField, AMemberAnElementOrABlock) {
  EXPECT_EQ(cli::yaml_field(kSample, "header.stamp"), "1500000000\n");
  EXPECT_EQ(cli::yaml_field(kSample, "position.1"), "-2.5e-05\n");
  EXPECT_EQ(cli::yaml_field(kSample, "position[2]"), "3\n");
  EXPECT_EQ(cli::yaml_field(kSample, "wrench.force.z"), "3\n");
  const std::string force = cli::yaml_field(kSample, "wrench.force");
  EXPECT_NE(force.find("x: 1"), std::string::npos) << force;
  EXPECT_NE(force.find("z: 3"), std::string::npos) << force;
}

TEST(EchoField, APathThatIsNotThereSaysWhatIs) {
  const auto message = [](const std::string& path) {
    try {
      cli::yaml_field(kSample, path);
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  EXPECT_EQ(message("heder.stamp"),
            "--field heder.stamp: the sample has no field 'heder'; it has header, name, position, wrench "
            "(did you mean 'header'?)");
  EXPECT_EQ(message("position.3"),
            "--field position.3: 'position' is a list of 3; expected an index from 0 to 2, found '3'");
  EXPECT_EQ(message("position.x"),
            "--field position.x: 'position' is a list of 3; expected an index from 0 to 2, found 'x'");
  EXPECT_EQ(message("header.stamp.ns"), "--field header.stamp.ns: 'header.stamp' is a value, with no field 'ns'");
  EXPECT_EQ(message("."), "--field: found '.'; expected a field such as header.stamp");
}

}  // namespace wysiwyf::test
