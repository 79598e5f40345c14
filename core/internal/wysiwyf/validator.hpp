#pragma once
// Checks a whole pipeline against the component libraries before anything starts: every
// component type exists, every parameter is declared, of the right type and in range, every
// topic mapping names a real port, ports sharing a topic carry one type, rates fit the clock.
#include <map>
#include <set>
#include <string>
#include <vector>

#include "wysiwyf/component_description.hpp"
#include "wysiwyf/loader.hpp"
#include "wysiwyf/pipeline_spec.hpp"
#include "wysiwyf/port.hpp"

namespace wysiwyf {

// Runs the type's configure() in describe mode: its parameters and ports with their defaults.
ComponentDescription describe_component(Loader& loader, const std::string& type);

struct ValidationResult {
  std::vector<ConfigIssue> errors;
  std::vector<ConfigIssue> warnings;
  std::map<std::string, ComponentDescription> described;  // by instance name
  // Topics that some port of the pipeline, in any process group, declares one-writer
  // (Qos::one_writer): every process's DDS endpoints on them must be exclusive (RunOptions).
  std::set<std::string> one_writer_topics;
  // One-writer topics that a component of this pipeline writes: the participant that alone may
  // write them ("<pipeline>/<process group>", as the kernel names its DDS participants).
  std::map<std::string, std::string> one_writer_participants;
  // Topics that only optional inputs the pipeline left unmapped read and no component writes:
  // left unconnected on purpose, so not on DDS either (nothing outside can write into them).
  std::set<std::string> unconnected_topics;
  bool ok() const { return errors.empty(); }
};

// `process` non-empty: also checks that the group exists.
ValidationResult validate_pipeline(const PipelineSpec& spec, Loader& loader, const std::string& process = "");

// A pipeline file, its includes and `--set`s, checked whole: every problem of the parser's and
// of validation's at once, in file order (line, column), errors only where they are not the
// knock-on of another (a component that did not parse is not validated). The spec is what
// parsed; it runs only if validation.ok().
struct CheckedPipeline {
  PipelineSpec spec;
  ValidationResult validation;
};
CheckedPipeline check_pipeline(const std::string& file, const std::vector<std::string>& overrides, Loader& loader,
                               const std::string& process = "");

// Levenshtein-closest of `candidates` to `word`, or "" when none is reasonably close.
std::string closest_name(const std::string& word, const std::vector<std::string>& candidates);

}  // namespace wysiwyf
