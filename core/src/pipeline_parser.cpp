// Reads pipeline files: YAML syntax, the schema, include: and --set, with a file:line:column for
// every problem. Checks that need the component libraries are in pipeline_validator.cpp.
// Here the entry points, load_pipeline*; the Parser, and which file holds each of its parts, in pipeline_parser.hpp.
#include "pipeline_parser.hpp"
#include "wysiwyf/pipeline_spec.hpp"

namespace wysiwyf {

static PipelineSpec finish(detail::Parser& parser, PipelineSpec spec, const std::vector<std::string>& overrides) {
  if (parser.issues.empty())
    for (const auto& o : overrides) parser.apply_set(o, spec);
  if (parser.issues.empty()) detail::check_merged(spec, parser.issues);
  if (!parser.issues.empty()) throw ConfigError(parser.issues);
  return spec;
}

PipelineSpec load_pipeline(const std::string& file, const std::vector<std::string>& overrides) {
  detail::Parser parser;
  PipelineSpec spec;
  spec.file = file;
  parser.parse_file(file, spec, Location{});
  return finish(parser, std::move(spec), overrides);
}

PipelineSpec load_pipeline_from_string(const std::string& yaml, const std::string& file_name,
                                       const std::vector<std::string>& overrides) {
  detail::Parser parser;
  PipelineSpec spec;
  spec.file = file_name;
  parser.parse_text(yaml, file_name, spec);
  return finish(parser, std::move(spec), overrides);
}

}  // namespace wysiwyf
