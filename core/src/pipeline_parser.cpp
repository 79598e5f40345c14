// Reads pipeline files: YAML syntax, the schema, include: and --set, with a file:line:column for
// every problem. Checks that need the component libraries are in pipeline_validator.cpp.
// Here the entry points, load_pipeline*; the Parser, and which file holds each of its parts, in pipeline_parser.hpp.
#include <filesystem>

#include "pipeline_parser.hpp"
#include "wysiwyf/config_files.hpp"
#include "wysiwyf/pipeline_spec.hpp"

namespace wysiwyf {

// --set layers and the merged checks, also over a file with problems: each is reported (a --set of a
// component that failed is not applied over it).
static void finish(detail::Parser& parser, PipelineSpec& spec, const std::vector<std::string>& overrides) {
  for (const auto& o : overrides) parser.apply_set(o, spec);
  detail::check_merged(spec, parser.issues, parser.failed_components);
}

// The pipeline file as given (absolute, or relative to the working directory), else the first
// folder of the config path that has it, as given or under pipelines/ (`wysiwyf run
// demo-sim.yaml` from an installed prefix, like an include); as given when none has it.
static std::string find_pipeline_file(const std::string& file) {
  std::error_code ec;
  if (std::filesystem::path(file).is_absolute() || std::filesystem::exists(file, ec)) return file;
  for (const std::string& relative : {file, "pipelines/" + file})
    if (const std::string found = find_in_config_dirs(relative); !found.empty()) return found;
  return file;
}

ParsedPipeline parse_pipeline(const std::string& given, const std::vector<std::string>& overrides) {
  const std::string file = find_pipeline_file(given);
  detail::Parser parser;
  ParsedPipeline parsed;
  parsed.spec.file = file;
  parser.parse_file(file, parsed.spec, Location{});
  finish(parser, parsed.spec, overrides);
  parsed.issues = std::move(parser.issues);
  parsed.failed_components = std::move(parser.failed_components);
  return parsed;
}

PipelineSpec load_pipeline(const std::string& given, const std::vector<std::string>& overrides) {
  ParsedPipeline parsed = parse_pipeline(given, overrides);
  if (!parsed.issues.empty()) throw ConfigError(parsed.issues);
  return std::move(parsed.spec);
}

PipelineSpec load_pipeline_from_string(const std::string& yaml, const std::string& file_name,
                                       const std::vector<std::string>& overrides) {
  detail::Parser parser;
  PipelineSpec spec;
  spec.file = file_name;
  parser.parse_text(yaml, file_name, spec);
  finish(parser, spec, overrides);
  if (!parser.issues.empty()) throw ConfigError(parser.issues);
  return spec;
}

}  // namespace wysiwyf
