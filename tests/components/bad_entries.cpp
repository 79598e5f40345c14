// Broken component libraries for the loader tests; which one is built is chosen by a define.
#include "wysiwyf/component.hpp"

namespace {
class Nothing final : public wysiwyf::Component {
 public:
  void configure(wysiwyf::Context&) override {}
  void tick(wysiwyf::Time) override {}
};
}  // namespace

#if defined(WYSIWYF_TEST_WRONG_ABI)
extern "C" __attribute__((visibility("default"))) const wysiwyf::ComponentEntry* wysiwyf_component_entry() {
  static const wysiwyf::ComponentEntry e{999, WYSIWYF_BUILD_ID, "test_wrong_abi",
                                         [] { return static_cast<wysiwyf::Component*>(new Nothing()); },
                                         [](wysiwyf::Component* c) { delete c; }};
  return &e;
}
#elif defined(WYSIWYF_TEST_WRONG_BUILD)
extern "C" __attribute__((visibility("default"))) const wysiwyf::ComponentEntry* wysiwyf_component_entry() {
  static const wysiwyf::ComponentEntry e{wysiwyf::kAbiVersion, "0123456789abcdef", "test_wrong_build",
                                         [] { return static_cast<wysiwyf::Component*>(new Nothing()); },
                                         [](wysiwyf::Component* c) { delete c; }};
  return &e;
}
#elif defined(WYSIWYF_TEST_NO_ENTRY)
extern "C" __attribute__((visibility("default"))) int wysiwyf_not_an_entry() { return 42; }
#elif defined(WYSIWYF_TEST_UNRESOLVED)
extern "C" void wysiwyf_test_function_nobody_defines();
extern "C" __attribute__((visibility("default"))) const wysiwyf::ComponentEntry* wysiwyf_component_entry() {
  wysiwyf_test_function_nobody_defines();
  return nullptr;
}
#else
#error "define one of WYSIWYF_TEST_WRONG_ABI, _WRONG_BUILD, _NO_ENTRY, _UNRESOLVED"
#endif
