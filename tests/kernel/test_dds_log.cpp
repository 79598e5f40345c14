// Fast DDS's own log, once per kind of message: a flood of one message (a sample refused per
// sample) is said the first time and then at 10, 100, 1000 times, with its count.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "wysiwyf/dds_log.hpp"

namespace wysiwyf::test {

using eprosima::fastdds::dds::Log;

TEST(FastDdsLog, AMessageFloodIsSaidOnceThenCounted) {
  std::vector<std::string> said;
  dds::CountingLogConsumer consumer([&](const std::string& line) { said.push_back(line); });
  const Log::Entry refused{"Change payload size of '8388608' bytes is larger than the history payload size",
                           Log::Context{"DataReaderHistory.cpp", 120, "received_change", "RTPS_READER"},
                           Log::Kind::Error, "t"};
  const Log::Entry other{"Problem reserving CacheChange in reader",
                         Log::Context{"StatefulReader.cpp", 300, "process", "RTPS_MSG_IN"}, Log::Kind::Warning, "t"};
  for (int i = 0; i < 1500; ++i) consumer.Consume(refused);
  consumer.Consume(other);
  ASSERT_EQ(said.size(), 5u);  // 1, 10, 100, 1000, and the other message
  EXPECT_EQ(said[0],
            "[fastdds] ERROR RTPS_READER: Change payload size of '8388608' bytes is larger than the history payload "
            "size");
  EXPECT_EQ(said[1].rfind("[fastdds] ERROR RTPS_READER: 10 times so far", 0), 0u) << said[1];
  EXPECT_EQ(said[3].rfind("[fastdds] ERROR RTPS_READER: 1000 times so far", 0), 0u) << said[3];
  EXPECT_EQ(said[4], "[fastdds] warning RTPS_MSG_IN: Problem reserving CacheChange in reader");
}

}  // namespace wysiwyf::test
