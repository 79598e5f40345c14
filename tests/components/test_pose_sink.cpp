// Test component: reads PoseStamped on port "in" (a second message type for type-mismatch tests).
#include "wysiwyf/component.hpp"
#include "wysiwyf/msgs.hpp"

namespace {

class TestPoseSink final : public wysiwyf::Component {
 public:
  void configure(wysiwyf::Context& ctx) override {
    ctx.summary("kernel test: reads PoseStamped");
    in_ = ctx.input<wysiwyf::msg::PoseStamped>("in", "poses, ignored");
  }
  void tick(wysiwyf::Time) override {
    while (in_.take(pose_)) {
    }
  }

 private:
  wysiwyf::msg::PoseStamped pose_;
  wysiwyf::Input<wysiwyf::msg::PoseStamped> in_;
};

}  // namespace

WYSIWYF_COMPONENT(TestPoseSink, "test_pose_sink")
