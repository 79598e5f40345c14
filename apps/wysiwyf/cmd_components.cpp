// wysiwyf components list | describe TYPE.
#include <iomanip>
#include <iostream>

#include "cli.hpp"
#include "wysiwyf/validator.hpp"

namespace wysiwyf::cli {

int cmd_components(Args args) {
  std::vector<std::string> pos;
  while (auto a = args.take_front()) pos.push_back(*a);
  if (!args.unknown_options().empty()) throw UsageError("unknown option " + args.unknown_options().front());
  Loader loader;
  if (pos.size() == 1 && pos[0] == "list") {
    int broken = 0;
    for (const auto& type : loader.known_types()) {
      try {
        const auto d = describe_component(loader, type);
        std::cout << std::left << std::setw(22) << type << " " << d.summary << "\n";
      } catch (const std::exception& e) {
        std::cout << std::left << std::setw(22) << type << " BROKEN: " << e.what() << "\n";
        ++broken;
      }
    }
    std::cout << "(search path:";
    for (const auto& d : loader.search_dirs()) std::cout << " " << d;
    std::cout << ")\n";
    return broken ? 1 : 0;
  }
  if (pos.size() == 2 && pos[0] == "describe") {
    ComponentDescription d;
    try {
      d = describe_component(loader, pos[1]);
    } catch (const std::exception& e) {
      std::cerr << "error: " << e.what() << "\n";
      return 2;
    }
    std::cout << d.type << ": " << d.summary << "\nlibrary: " << d.library << "\n\nparameters:\n";
    if (d.params.empty()) std::cout << "  (none)\n";
    for (const auto& p : d.params) {
      std::cout << "  " << p.name << " (" << to_string(p.type) << ", default " << p.default_value;
      if (p.length) std::cout << ", " << p.length->text();
      if (p.range) std::cout << ", range [" << p.range->min << ", " << p.range->max << "]";
      if (!p.choices.empty()) {
        std::cout << ", one of";
        for (const auto& c : p.choices) std::cout << " " << c;
      }
      std::cout << ")\n      " << p.description << "\n";
    }
    std::cout << "\nports:\n";
    if (d.ports.empty()) std::cout << "  (none)\n";
    for (const auto& p : d.ports) {
      std::cout << "  " << (p.direction == PortDirection::kInput ? "in  " : "out ") << p.name << " : " << p.type_name
                << " (" << to_string(p.qos.reliability) << ", depth " << p.qos.depth;
      if (p.qos.deadline_ns) std::cout << ", deadline " << p.qos.deadline_ns * 1e-6 << " ms";
      std::cout << ")\n      " << p.description << "\n";
    }
    return 0;
  }
  throw UsageError("expected 'components list' or 'components describe TYPE'");
}

}  // namespace wysiwyf::cli
