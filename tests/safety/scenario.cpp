#include "scenario.hpp"

#include <array>
#include <cmath>
#include <cstdio>
#include <random>

namespace wysiwyf::safety {

namespace {

// Draws from the seed's stream; the arithmetic is ours (not a std:: distribution's) so a seed
// names the same scenario with any standard library.
class Draw {
 public:
  explicit Draw(std::uint64_t seed) : rng_(seed * 0x9E3779B97F4A7C15ull + 0x5EEDull) {}
  double uniform(double lo, double hi) { return lo + (hi - lo) * static_cast<double>(rng_() >> 11) * 0x1.0p-53; }
  bool chance(double p) { return uniform(0, 1) < p; }
  std::size_t index(std::size_t n) { return static_cast<std::size_t>(uniform(0, static_cast<double>(n))) % n; }

 private:
  std::mt19937_64 rng_;
};

std::string num(double v) {
  char b[32];
  std::snprintf(b, sizeof b, "%.3f", v);
  return b;
}

struct Feature {
  const char* name;
  std::array<double, 3> at;  // roughly where it is (the cube at rest), base frame, m
  bool face;                 // a face: a reach may aim off its centre
};

// The display demo's features (config/scenes/display_demo.yaml).
const std::array<Feature, 6> kFeatures = {{{"cube +x knob", {0.74, 0.0, 0.10}, false},
                                           {"cube +x face", {0.70, 0.0, 0.10}, true},
                                           {"cube +z face", {0.60, 0.0, 0.20}, true},
                                           {"cube +y face", {0.60, 0.10, 0.10}, true},
                                           {"cube -y face", {0.60, -0.10, 0.10}, true},
                                           {"cube +x+z edge", {0.70, 0.0, 0.20}, false}}};
constexpr std::array<double, 3> kHandStart = {1.1, 0.0, 0.2};  // user_sim's default

struct Writer {
  Draw& d;
  Scenario& s;
  std::array<double, 3> hand = kHandStart;

  // A minimum-jerk move at peak speed v (user_sim's move: peak 1.875 d / T).
  void move(const std::array<double, 3>& to, double v) {
    const double dist = std::hypot(to[0] - hand[0], to[1] - hand[1], to[2] - hand[2]);
    const double t = std::max(0.15, 1.875 * dist / v);
    s.script.push_back("move " + num(to[0]) + " " + num(to[1]) + " " + num(to[2]) + " " + num(t));
    hand = to;
  }
  void wait(double t) {
    if (t >= 0.005) s.script.push_back("wait " + num(t));  // (a shorter one is none: go on at once)
  }
  const Feature& reach(double v_lo, double v_hi) { return reach(kFeatures[d.index(kFeatures.size())], v_lo, v_hi); }
  const Feature& reach(const Feature& f, double v_lo, double v_hi) {
    std::string line = std::string("reach ") + f.name;
    if (f.face && d.chance(0.6)) line += " at " + num(d.uniform(-0.07, 0.07)) + " " + num(d.uniform(-0.07, 0.07));
    s.script.push_back(line + " speed " + num(d.uniform(v_lo, v_hi)));
    hand = f.at;
    return f;
  }
  void withdraw() {
    s.script.push_back("withdraw " + num(d.uniform(0.05, 0.2)) + " " + num(d.uniform(0.2, 0.8)));
    hand = {hand[0] + 0.1, hand[1], hand[2]};  // (roughly: most faces face +x or sideways)
  }
  // What the hand does once it has touched: a push, a drag, or only a touch.
  void after_touch() {
    switch (d.index(3)) {
      case 0:
        s.script.push_back("push " + num(d.uniform(2, 15)) + " " + num(d.uniform(0.2, 1.5)));
        s.script.push_back("release " + num(d.uniform(0.05, 0.5)));
        break;
      case 1:
        s.script.push_back("push " + num(d.uniform(3, 8)) + " 0.3");
        s.script.push_back("drag " + num(d.uniform(-0.08, 0.0)) + " " + num(d.uniform(-0.06, 0.06)) + " " +
                           num(d.uniform(-0.03, 0.03)) + " " + num(d.uniform(0.3, 1.5)));
        s.script.push_back("release " + num(d.uniform(0.05, 0.3)));
        break;
      default: s.script.push_back("release 0.1");
    }
    withdraw();
  }
  std::array<double, 3> point(double x0, double x1, double y0, double y1, double z0, double z1) {
    return {d.uniform(x0, x1), d.uniform(y0, y1), d.uniform(z0, z1)};
  }
};

void hand_faults(Draw& d, Scenario& s) {
  if (!d.chance(0.35)) return;
  std::string t, words;
  auto add = [&](const std::string& param, const std::string& what) {
    t += ", " + param;
    words += (words.empty() ? "" : ", ") + what;
  };
  if (d.chance(0.5)) {
    const double noise = d.uniform(0.002, 0.004);
    add("noise: " + num(noise), "noise " + num(noise * 1e3) + " mm");
  }
  if (d.chance(0.5)) {
    const double latency = d.uniform(0.01, 0.05);
    add("latency: " + num(latency), "latency " + num(latency * 1e3) + " ms");
  }
  if (d.chance(0.3)) {
    const double dropout = d.uniform(0.05, 0.5);
    add("dropout: " + num(dropout), "dropout " + num(dropout));
  }
  if (d.chance(0.3)) {
    const double from = d.uniform(0.5, 5), to = from + d.uniform(0.1, 1.5);
    add("outages: [" + num(from) + ", " + num(to) + "]", "outage " + num(from) + "-" + num(to) + " s");
  }
  if (d.chance(0.3)) {
    const double from = d.uniform(0.5, 5), to = from + d.uniform(0.05, 0.5);
    const double az = d.uniform(0, 2 * M_PI), el = d.uniform(-0.5 * M_PI, 0.5 * M_PI);
    const double dx = 0.1 * std::cos(el) * std::cos(az), dy = 0.1 * std::cos(el) * std::sin(az),
                 dz = 0.1 * std::sin(el);
    add("glitches: [" + num(from) + ", " + num(to) + ", " + num(dx) + ", " + num(dy) + ", " + num(dz) + "]",
        "10 cm glitch " + num(from) + "-" + num(to) + " s");
  }
  if (d.chance(0.2)) {
    const double from = d.uniform(0.5, 5), to = from + d.uniform(0.1, 1.0), age = d.uniform(0.05, 0.5);
    add("stale: [" + num(from) + ", " + num(to) + ", " + num(age) + "]",
        "stamps " + num(age * 1e3) + " ms stale " + num(from) + "-" + num(to) + " s");
  }
  s.tracker = "seed: " + std::to_string(s.seed % 1000000000ull) + t;
  s.faults = words;
}

}  // namespace

const std::vector<std::string>& scenario_kinds() {
  static const std::vector<std::string> kinds = {"reach", "change", "lunge", "rest", "switch", "hard_push"};
  return kinds;
}

Scenario make_scenario(std::uint64_t seed) {
  Scenario s;
  s.seed = seed;
  Draw d(seed);
  Writer w{d, s};
  // Reaches are the common case; each other kind comes about one time in eight.
  const double pick = d.uniform(0, 1);
  s.kind = pick < 0.375 ? "reach" : scenario_kinds()[1 + static_cast<std::size_t>((pick - 0.375) / 0.125) % 5];
  if (s.kind == "reach") {
    if (d.chance(0.7)) w.move(w.point(0.8, 1.15, -0.35, 0.35, 0.05, 0.40), d.uniform(0.3, 1.0));
    w.wait(d.uniform(0.0, 2.5));
    w.reach(0.3, 2.0);
    w.after_touch();
    if (d.chance(0.4)) {
      w.wait(d.uniform(0.0, 1.0));
      w.reach(0.3, 2.0);
      w.after_touch();
    }
  } else if (s.kind == "change") {
    w.wait(d.uniform(1.0, 2.5));
    const Feature& first = kFeatures[d.index(kFeatures.size())];
    const double part = d.uniform(0.4, 0.7);
    std::array<double, 3> mid;
    for (int i = 0; i < 3; ++i) mid[i] = w.hand[i] + part * (first.at[i] - w.hand[i]);
    w.move(mid, d.uniform(0.5, 1.6));
    w.reach(0.5, 1.8);
    w.after_touch();
  } else if (s.kind == "lunge") {
    w.wait(d.uniform(0.0, 2.5));
    if (d.chance(0.5)) w.reach(0.5, 1.5), w.withdraw();
    w.move(w.point(0.35, 0.75, -0.25, 0.25, 0.25, 0.55), d.uniform(1.0, 2.0));
    w.wait(d.uniform(0.0, 1.0));
    w.move({1.0, d.uniform(-0.2, 0.2), 0.25}, d.uniform(0.3, 1.0));
  } else if (s.kind == "rest") {
    w.move(w.point(0.72, 0.90, -0.20, 0.20, 0.15, 0.40), d.uniform(0.3, 0.8));
    w.wait(d.uniform(1.0, 3.0));
    w.reach(0.3, 1.5);
    w.after_touch();
  } else if (s.kind == "switch") {
    w.wait(d.uniform(1.5, 2.5));
    w.reach(kFeatures[d.index(2)], 0.5, 1.2);
    const int n = 2 + static_cast<int>(d.index(3));
    for (int i = 0; i < n; ++i) {
      s.script.push_back("push " + num(d.uniform(1.5, 3.5)) + " " + num(d.uniform(0.005, 0.06)));
      s.script.push_back("release " + num(d.uniform(0.01, 0.1)));
      if (d.chance(0.5)) w.wait(d.uniform(0.0, 0.15));
    }
    s.script.push_back("push 4 0.3");
    s.script.push_back("release 0.1");
    w.withdraw();
  } else {  // hard_push
    w.wait(d.uniform(1.5, 2.5));
    w.reach(kFeatures[d.index(2)], 0.6, 1.2);
    s.script.push_back("push " + num(d.uniform(20, 90)) + " " + num(d.uniform(0.3, 1.0)));
    s.script.push_back("release " + num(d.uniform(0.05, 0.3)));
    w.withdraw();
  }
  w.wait(0.3);
  hand_faults(d, s);
  return s;
}

}  // namespace wysiwyf::safety
