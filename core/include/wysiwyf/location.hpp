#pragma once
/// @file
/// Where a configuration value came from: file:line:column, 1-based, for error messages.
#include <stdexcept>
#include <string>
#include <vector>

namespace wysiwyf {

/// Where a configuration value came from: file:line:column, 1-based, for error messages.
struct Location {
  std::string file;         ///< the file, as it was named
  int line = 0;             ///< 1-based; 0 when unknown
  int column = 0;           ///< 1-based; 0 when unknown
  std::string str() const;  ///< "file:line:column", or just "file"
};

/// One problem found in a configuration, with where it is.
struct ConfigIssue {
  Location where;       ///< where the value at fault is
  std::string message;  ///< what is wrong with it
  /// "file:line:column: error: message", as compilers print an error.
  std::string str() const { return where.str() + ": error: " + message; }
};

/// A configuration that cannot run, with every problem found (not just the first).
class ConfigError : public std::runtime_error {
 public:
  /// what() lists every issue, one a line.
  explicit ConfigError(std::vector<ConfigIssue> issues);
  /// Every problem found.
  const std::vector<ConfigIssue>& issues() const { return issues_; }

 private:
  std::vector<ConfigIssue> issues_;
};

}  // namespace wysiwyf
