// Port typing, topic mapping and the local queues.
#include "test_support.hpp"
#include "wysiwyf/msgs.hpp"

namespace wysiwyf::test {

TEST(Ports, TwoTypesOnOneTopicIsAValidationErrorNamingBothPorts) {
  const PipelineSpec spec = load_pipeline_from_string(
      "wysiwyf: 1\ncomponents:\n  probe: {type: test_probe, rate: 100, topics: {out: shared}}\n"
      "  sink: {type: test_pose_sink, rate: 100, topics: {in: shared}}\n",
      "types.yaml");
  Loader loader(test_search_dirs());
  const auto v = validate_pipeline(spec, loader);
  ASSERT_EQ(v.errors.size(), 1u);
  EXPECT_EQ(v.errors[0].message,
            "topic 'shared': port sink.in carries wysiwyf::msg::PoseStamped but port probe.out (types.yaml:3:54) "
            "carries wysiwyf::msg::JointState; expected one message type per topic");
}

TEST(Ports, TheBusRefusesASecondTypeOnATopic) {
  detail::TopicBus bus;
  bus.channel<msg::JointState>("t", "a.out");
  try {
    bus.channel<msg::PoseStamped>("t", "b.in");
    FAIL() << "accepted";
  } catch (const std::runtime_error& e) {
    EXPECT_STREQ(e.what(),
                 "topic 't': port b.in carries wysiwyf::msg::PoseStamped but port a.out carries "
                 "wysiwyf::msg::JointState");
  }
}

TEST(Ports, UnmappedPortsUseInstanceSlashPort) {
  const PipelineSpec spec = load_pipeline_from_string(
      "wysiwyf: 1\ncomponents:\n  probe: {type: test_probe, rate: 100, topics: {in: x}}\n", "p");
  EXPECT_EQ(spec.find("probe")->topic_for("in"), "x");
  EXPECT_EQ(spec.find("probe")->topic_for("out"), "probe/out");
}

TEST(Ports, AnInputWithNoProducerIsAWarningNotAnError) {
  const PipelineSpec spec = load_pipeline_from_string(
      "wysiwyf: 1\ncomponents:\n  probe: {type: test_probe, rate: 100, topics: {in: x}}\n", "p");
  Loader loader(test_search_dirs());
  const auto v = validate_pipeline(spec, loader);
  EXPECT_TRUE(v.ok());
  ASSERT_EQ(v.warnings.size(), 1u);
  EXPECT_NE(v.warnings[0].message.find("no component of this pipeline publishes topic 'x'"), std::string::npos);
}

TEST(SubscriberQueue, KeepsTheLastDepthSamplesAndCountsDrops) {
  detail::SubscriberQueue<msg::JointState> q(3);
  msg::JointState s;
  for (int i = 0; i < 5; ++i) {
    s.header().seq(i);
    q.push(s);
  }
  EXPECT_EQ(q.size(), 3u);
  EXPECT_EQ(q.dropped(), 2u);
  ASSERT_TRUE(q.take(s));
  EXPECT_EQ(s.header().seq(), 2u);
  ASSERT_TRUE(q.take_latest(s));
  EXPECT_EQ(s.header().seq(), 4u);
  EXPECT_FALSE(q.take(s));
}

TEST(SubscriberQueue, ReusesImageBuffersInSteadyState) {
  detail::SubscriberQueue<msg::Image> q(2);
  msg::Image frame, out;
  frame.data().resize(640 * 480 * 3);
  for (int i = 0; i < 4; ++i) {  // warm up every slot and the reader's buffer
    q.push(frame);
    ASSERT_TRUE(q.take(out));
  }
  const auto* before = out.data().data();
  q.push(frame);
  ASSERT_TRUE(q.take(out));
  q.push(frame);
  ASSERT_TRUE(q.take(out));
  // The buffers rotate between the slots and the reader; none is freed or newly allocated.
  EXPECT_EQ(out.data().size(), 640u * 480u * 3u);
  EXPECT_TRUE(out.data().capacity() >= 640u * 480u * 3u);
  (void)before;
}

}  // namespace wysiwyf::test

namespace wysiwyf::test {

TEST(SubscriberQueue, PushSwapMovesTheBufferInWithoutCopying) {
  detail::SubscriberQueue<msg::Image> q(2);
  msg::Image frame;
  frame.data().assign(1000, 7);
  const auto* buffer = frame.data().data();
  q.push_swap(frame);
  EXPECT_TRUE(frame.data().empty());  // it now holds the empty slot's buffer
  msg::Image out;
  ASSERT_TRUE(q.take(out));
  EXPECT_EQ(out.data().data(), buffer);  // the very same buffer reached the reader
  EXPECT_EQ(out.data().size(), 1000u);
}

}  // namespace wysiwyf::test
