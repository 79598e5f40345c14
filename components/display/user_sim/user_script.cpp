#include "user_script.hpp"

#include <sstream>
#include <stdexcept>

namespace wysiwyf::display {

namespace {

[[noreturn]] void fail(std::size_t line, const std::string& text, const std::string& what) {
  throw std::invalid_argument("script line " + std::to_string(line + 1) + " '" + text + "': " + what);
}

double number(std::istringstream& in, std::size_t line, const std::string& text, const char* what, bool positive) {
  double v = 0;
  if (!(in >> v)) fail(line, text, std::string("expected ") + what);
  if (positive && !(v > 0)) fail(line, text, std::string(what) + " must be positive");
  return v;
}

}  // namespace

std::vector<UserAction> parse_user_script(const std::vector<std::string>& lines, const haptics::Scene& scene) {
  std::vector<UserAction> actions;
  for (std::size_t i = 0; i < lines.size(); ++i) {
    const std::string& text = lines[i];
    std::istringstream in(text);
    std::string verb;
    in >> verb;
    UserAction a;
    if (verb == "reach") {
      a.kind = UserAction::Kind::kReach;
      std::string rest;
      std::getline(in, rest);
      rest.erase(0, rest.find_first_not_of(' '));
      // The longest feature name the rest starts with ("cube +x knob" before "cube +x").
      for (const auto& f : scene.features)
        if (rest.compare(0, f.name.size(), f.name) == 0 &&
            (rest.size() == f.name.size() || rest[f.name.size()] == ' ') &&
            (!a.feature || f.name.size() > a.feature->name.size()))
          a.feature = &f;
      if (!a.feature) {
        std::string known;
        for (const auto& f : scene.features) known += (known.empty() ? "" : ", ") + f.name;
        fail(i, text, "no feature of the scene is named so; expected one of " + (known.empty() ? "(none)" : known));
      }
      std::istringstream options(rest.substr(a.feature->name.size()));
      for (std::string key; options >> key;) {
        if (key == "at") {
          a.u = number(options, i, text, "at U V (m)", false);
          a.v = number(options, i, text, "at U V (m)", false);
        } else if (key == "speed") {
          a.speed = number(options, i, text, "speed V (m/s)", true);
          if (a.speed > 2.0) fail(i, text, "speed: people reach at up to 1.6 m/s (2.0 close in); expected at most 2");
        } else {
          fail(i, text, "unknown option '" + key + "'; expected at U V or speed V");
        }
      }
    } else if (verb == "push") {
      a.kind = UserAction::Kind::kPush;
      a.force = number(in, i, text, "push F T (N, s)", true);
      a.duration = number(in, i, text, "push F T (N, s)", true);
    } else if (verb == "drag") {
      a.kind = UserAction::Kind::kDrag;
      for (int k = 0; k < 3; ++k) a.vector[k] = number(in, i, text, "drag DX DY DZ T (m, s)", false);
      a.duration = number(in, i, text, "drag DX DY DZ T (m, s)", true);
    } else if (verb == "release") {
      a.kind = UserAction::Kind::kRelease;
      a.duration = number(in, i, text, "release T (s)", true);
    } else if (verb == "withdraw") {
      a.kind = UserAction::Kind::kWithdraw;
      a.distance = number(in, i, text, "withdraw D T (m, s)", true);
      a.duration = number(in, i, text, "withdraw D T (m, s)", true);
    } else if (verb == "move") {
      a.kind = UserAction::Kind::kMove;
      for (int k = 0; k < 3; ++k) a.vector[k] = number(in, i, text, "move X Y Z T (m, s)", false);
      a.duration = number(in, i, text, "move X Y Z T (m, s)", true);
    } else if (verb == "wait") {
      a.kind = UserAction::Kind::kWait;
      a.duration = number(in, i, text, "wait T (s)", true);
    } else {
      fail(i, text, "expected reach, push, drag, release, withdraw, move or wait");
    }
    std::string extra;
    if (verb != "reach" && in >> extra) fail(i, text, "unexpected '" + extra + "' at the end");
    actions.push_back(a);
  }
  return actions;
}

}  // namespace wysiwyf::display
