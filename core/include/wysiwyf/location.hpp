#pragma once
// Where a configuration value came from: file:line:column, 1-based, for error messages.
#include <stdexcept>
#include <string>
#include <vector>

namespace wysiwyf {

struct Location {
  std::string file;
  int line = 0;             // 1-based; 0 when unknown
  int column = 0;           // 1-based; 0 when unknown
  std::string str() const;  // "file:line:column", or just "file"
};

// One problem found in a configuration, with where it is.
struct ConfigIssue {
  Location where;
  std::string message;
  std::string str() const { return where.str() + ": error: " + message; }
};

// A configuration that cannot run, with every problem found (not just the first).
class ConfigError : public std::runtime_error {
 public:
  explicit ConfigError(std::vector<ConfigIssue> issues);
  const std::vector<ConfigIssue>& issues() const { return issues_; }

 private:
  std::vector<ConfigIssue> issues_;
};

}  // namespace wysiwyf
