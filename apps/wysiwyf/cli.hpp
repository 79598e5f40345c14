#pragma once
// The `wysiwyf` command line: small argument helpers shared by the sub-commands.
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace wysiwyf::cli {

// Arguments after the sub-command, consumed as options are read.
class Args {
 public:
  explicit Args(std::vector<std::string> args) : args_(std::move(args)) {}
  // "--name value" (or "--name=value"); removes it. Repeated options: every value, in order.
  std::vector<std::string> values(const std::string& name);
  std::optional<std::string> value(const std::string& name);
  bool flag(const std::string& name);
  // The first argument if it is not an option (a sub-command or its operand); removes it.
  std::optional<std::string> take_front();
  // What is left that is not an option.
  std::vector<std::string> positional() const;
  // Options nobody asked for; call after reading every option.
  std::vector<std::string> unknown_options() const;

 private:
  std::vector<std::string> args_;
};

struct UsageError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// A number option "--name X", X within [min, max] (the whole text a number: "5s" is refused);
// `fallback` when it is absent. A bad one throws UsageError "NAME: found 'X'; expected EXPECTED".
double number_option(Args& args, const std::string& name, double fallback, double min, double max,
                     const std::string& expected);
// The same for a whole number.
long whole_option(Args& args, const std::string& name, long fallback, long min, long max, const std::string& expected);

int cmd_run(Args args);
int cmd_validate(Args args);
int cmd_components(Args args);
int cmd_topic(Args args);
int cmd_new(Args args);
int cmd_record(Args args);
int cmd_play(Args args);
int cmd_monitor(Args args);
int cmd_bridge(Args args);
int cmd_discovery_server(Args args);
int cmd_calibrate(Args args);

}  // namespace wysiwyf::cli
