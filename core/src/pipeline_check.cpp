// A pipeline file checked whole: the parser's problems and, for the components that parsed, the
// validator's, in one list (check_pipeline).
#include <algorithm>
#include <tuple>

#include "wysiwyf/validator.hpp"

namespace wysiwyf {

CheckedPipeline check_pipeline(const std::string& file, const std::vector<std::string>& overrides, Loader& loader,
                               const std::string& process) {
  ParsedPipeline parsed = parse_pipeline(file, overrides);
  CheckedPipeline checked;
  checked.spec = std::move(parsed.spec);
  if (parsed.issues.empty()) {
    checked.validation = validate_pipeline(checked.spec, loader, process);
    return checked;
  }
  // The components with problems of their own are left out of validation: what it would say of
  // them (a missing type, a rate) would be the knock-on of what the parser said.
  PipelineSpec parsed_part = checked.spec;
  auto& components = parsed_part.components;
  components.erase(std::remove_if(components.begin(), components.end(),
                                  [&](const ComponentSpec& c) { return parsed.failed_components.count(c.name) != 0; }),
                   components.end());
  checked.validation = validate_pipeline(parsed_part, loader, process);
  auto& errors = checked.validation.errors;
  errors.insert(errors.begin(), parsed.issues.begin(), parsed.issues.end());
  std::stable_sort(errors.begin(), errors.end(), [](const ConfigIssue& a, const ConfigIssue& b) {
    return std::tie(a.where.file, a.where.line, a.where.column) < std::tie(b.where.file, b.where.line, b.where.column);
  });
  return checked;
}

}  // namespace wysiwyf
