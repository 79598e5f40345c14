// wysiwyf run / validate.
#include <unistd.h>

#include <cstdio>
#include <iomanip>
#include <iostream>

#include "cli.hpp"
#include "wysiwyf/real_time_readiness.hpp"
#include "wysiwyf/runtime.hpp"
#include "wysiwyf/validator.hpp"

namespace wysiwyf::cli {

namespace {

using Loaded = CheckedPipeline;

// Parses and validates; prints every problem of the file at once: the parser's and, for the
// components that parsed, the validator's, in the file's order, then the warnings; nullopt when
// the pipeline cannot run.
std::optional<Loaded> load_and_validate(Args& args, Loader& loader, std::string& process) {
  process = args.value("--process").value_or("");
  const auto sets = args.values("--set");
  const auto files = args.positional();
  if (files.size() != 1) throw UsageError("expected one pipeline file, found " + std::to_string(files.size()));
  Loaded loaded = check_pipeline(files[0], sets, loader, process);
  for (const auto& e : loaded.validation.errors) std::cerr << e.str() << "\n";
  for (const auto& w : loaded.validation.warnings) std::cerr << w.where.str() << ": warning: " << w.message << "\n";
  if (!loaded.validation.ok()) {
    std::cerr << loaded.validation.errors.size() << " error(s); nothing was started\n";
    return std::nullopt;
  }
  return loaded;
}

void print_report(const RunResult& r, bool real) {
  std::cout << std::fixed << std::setprecision(3) << "stopped: " << (r.ok ? r.stop_reason : "fault")
            << " at t=" << r.sim_time_ns * 1e-9 << " s after " << r.wall_seconds << " s wall\n";
  std::cout << std::left << std::setw(18) << "component" << std::setw(20) << "type" << std::right << std::setw(10)
            << "ticks" << std::setw(11) << "p50 us" << std::setw(11) << "p99 us" << std::setw(11) << "max us"
            << std::setw(13) << "run p99 us" << std::setw(13) << "run max us" << std::setw(10) << "overruns"
            << std::setw(9) << "dropped" << std::setw(10) << "rejected" << std::setw(10) << "warnings"
            << (real ? "   late p50 us   late p99 us" : "") << "  state\n";
  for (const auto& c : r.components) {
    std::cout << std::left << std::setw(18) << c.name << std::setw(20) << c.type << std::right << std::setw(10)
              << c.ticks << std::setprecision(1) << std::setw(11) << c.tick_p50_us << std::setw(11) << c.tick_p99_us
              << std::setw(11) << c.tick_max_us << std::setw(13) << c.run_tick_p99_us << std::setw(13)
              << c.run_tick_max_us << std::setw(10) << c.overruns << std::setw(9) << c.dropped_samples << std::setw(10)
              << c.rejected_samples << std::setw(10) << c.warnings;
    if (real) std::cout << std::setw(14) << c.late_p50_us << std::setw(14) << c.late_p99_us;
    std::cout << "  " << c.state << (c.state_reason.empty() ? "" : ": " + c.state_reason) << "\n";
  }
  for (const auto& line : r.dds_problems) std::cout << "dds: " << line << "\n";
  if (r.dds_samples_sent > 0)
    std::cout << "dds: " << r.dds_samples_sent << " samples sent to other processes in " << r.dds_publisher_wakes
              << " wakes of the publisher thread\n";
}

}  // namespace

int cmd_run(Args args) {
  const bool progress = args.flag("--progress");
  const bool no_progress = args.flag("--no-progress");
  const double start_after = number_option(args, "--start-after", 0, 0, 3600, "seconds from 0 to 3600");
  Loader loader;
  std::string process;
  auto loaded = load_and_validate(args, loader, process);
  if (!args.unknown_options().empty()) throw UsageError("unknown option " + args.unknown_options().front());
  if (!loaded) return 2;
  install_stop_signal_handlers();
  // On the real clock: what the pipeline asks of this machine, and what it gives.
  if (loaded->spec.clock_mode() == ClockMode::kReal)
    for (const auto& line : real_time_readiness(loaded->spec, process, read_machine_facts()))
      std::cerr << (line.warning ? "warning: " : "") << line.text << "\n";
  RunOptions options;
  options.process = process;
  options.start_after_s = start_after;
  options.one_writer_topics = loaded->validation.one_writer_topics;
  options.one_writer_participants = loaded->validation.one_writer_participants;
  options.unconnected_topics = loaded->validation.unconnected_topics;
  options.progress = progress || (!no_progress && isatty(STDERR_FILENO));
  Runtime runtime(loaded->spec, loader, options);
  const RunResult result = runtime.run();
  print_report(result, loaded->spec.clock_mode() == ClockMode::kReal);
  if (!result.ok) {
    std::cerr << "error: " << result.error << "\n";
    return 1;
  }
  // A run in which a component held or faulted did not do what it was asked: say which, fail.
  if (const ComponentReport* c = result.first_unhealthy()) {
    std::cerr << "error: component '" << c->name << "' (" << c->type << ") "
              << (c->state == "holding" ? "held" : "faulted") << " during the run"
              << (c->state_reason.empty() ? "" : ": " + c->state_reason) << "\n";
    return 1;
  }
  return 0;
}

int cmd_validate(Args args) {
  Loader loader;
  std::string process;
  auto loaded = load_and_validate(args, loader, process);
  const bool list = args.flag("--print-components");
  if (!args.unknown_options().empty()) throw UsageError("unknown option " + args.unknown_options().front());
  if (!loaded) return 2;
  const auto& spec = loaded->spec;
  if (list) {  // one name a line, for scripts
    for (const auto& c : spec.components) std::cout << c.name << "\n";
    return 0;
  }
  std::cout << spec.file << ": ok: pipeline '" << spec.name.value << "', " << spec.components.size()
            << " component(s), process group(s):";
  for (const auto& p : spec.processes()) std::cout << " " << p;
  std::cout << ", domain " << spec.domain_id() << ", " << (spec.clock_mode() == ClockMode::kSim ? "sim" : "real")
            << " clock\n";
  return 0;
}

}  // namespace wysiwyf::cli
