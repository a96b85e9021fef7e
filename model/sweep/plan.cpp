// SPDX-License-Identifier: Apache-2.0
// A sweep's points (sweep.h): the swept keys from the --set arguments, the cross product
// of scenes and values, each point's resolved config and its fingerprint.
#include <algorithm>
#include <sstream>
#include <stdexcept>

#include "sweep/sweep.h"

namespace rastsim::sweep {

namespace {

Axis parse_axis(const std::string& arg) {
  const auto eq = arg.find('=');
  if (eq == std::string::npos || eq == 0 || eq + 1 == arg.size())
    throw std::runtime_error("--set " + arg + ": expected section.key=value[,value...]");
  Axis a{arg.substr(0, eq), {}};
  std::stringstream ss(arg.substr(eq + 1));
  for (std::string v; std::getline(ss, v, ',');)
    if (!v.empty()) a.values.push_back(v);
  return a;
}

// A sweep's --set arguments name each key once and each value of a key once: a key given
// twice (fixed then swept, or fixed twice) has no one meaning for the points, and a
// repeated value would run the same point twice under one CSV key.
void check_set_args(const std::vector<std::string>& set_args) {
  std::vector<std::pair<std::string, std::string>> seen;  // key, the --set that gave it
  for (const auto& s : set_args) {
    const Axis a = parse_axis(s);
    for (size_t i = 0; i < a.values.size(); ++i)
      for (size_t j = 0; j < i; ++j)
        if (a.values[i] == a.values[j])
          throw std::runtime_error("--set " + s + ": value " + a.values[i] + " of " + a.key +
                                   " is given twice (each point runs once)");
    for (const auto& [key, arg] : seen)
      if (key == a.key)
        throw std::runtime_error("--set " + s + ": " + a.key + " is already set by --set " + arg +
                                 " (give each key once: one value fixes it, several sweep it)");
    seen.emplace_back(a.key, s);
  }
}

}  // namespace

std::vector<Axis> split_axes(const std::vector<std::string>& set_args, std::vector<std::string>& fixed) {
  check_set_args(set_args);
  std::vector<Axis> axes;
  for (const auto& s : set_args) {
    Axis a = parse_axis(s);
    if (a.values.size() == 1) {
      fixed.push_back(a.key + "=" + a.values[0]);
      continue;
    }
    axes.push_back(std::move(a));
  }
  return axes;
}

std::vector<FixedSet> fixed_sets(const std::vector<std::string>& sets, const std::vector<Axis>& axes) {
  std::vector<FixedSet> fixed;
  for (const auto& s : sets) {
    const auto eq = s.find('=');
    const std::string key = s.substr(0, eq), value = eq == std::string::npos ? "" : s.substr(eq + 1);
    if (std::any_of(axes.begin(), axes.end(), [&](const Axis& a) { return a.key == key; })) continue;
    const auto it = std::find_if(fixed.begin(), fixed.end(), [&](const FixedSet& f) { return f.key == key; });
    if (it == fixed.end()) fixed.push_back({key, value});
    else it->value = value;
  }
  return fixed;
}

void validate_axes(const Config& cfg, const std::vector<Axis>& axes) {
  for (const auto& a : axes)
    for (const auto& v : a.values) {
      Config c = cfg;
      c.apply_override(a.key + "=" + v);
      c.validate();
    }
}

std::vector<Point> make_points(const std::vector<std::string>& scenes, const std::vector<Axis>& axes,
                               const BaseConfig& base, const std::string& level) {
  std::vector<Point> points;
  for (const auto& scene : scenes) {
    std::vector<size_t> idx(axes.size(), 0);
    for (;;) {
      Point p;
      p.scene = scene;
      for (size_t i = 0; i < axes.size(); ++i) p.values.push_back(axes[i].values[idx[i]]);
      p.config_hash = config_hash(point_config(p, axes, base));
      // --level cosim: the RTL's figures beside the SystemC model's (cmd_cosim.cpp).
      p.args = level == "cosim" ? std::vector<std::string>{"cosim", "--simulate-stats", "--scene", scene}
                                : std::vector<std::string>{"simulate", "--quiet", "--scene", scene};
      if (!base.path.empty()) p.args.insert(p.args.end(), {"--config", base.path});
      for (const auto& s : base.sets) p.args.insert(p.args.end(), {"--set", s});
      for (size_t i = 0; i < axes.size(); ++i) p.args.insert(p.args.end(), {"--set", axes[i].key + "=" + p.values[i]});
      points.push_back(std::move(p));
      size_t i = axes.size();
      while (i > 0 && ++idx[i - 1] == axes[i - 1].values.size()) idx[--i] = 0;
      if (i == 0) break;
    }
  }
  return points;
}

Config point_config(const Point& p, const std::vector<Axis>& axes, const BaseConfig& base) {
  Config c = base.resolved;
  for (size_t i = 0; i < axes.size(); ++i) c.apply_override(axes[i].key + "=" + p.values[i]);
  c.validate();
  return c;
}

std::string describe(const Point& p, const std::vector<Axis>& axes) {
  std::string s = "scene=" + p.scene;
  for (size_t i = 0; i < axes.size(); ++i) s += " " + axes[i].key + "=" + p.values[i];
  return s;
}

}  // namespace rastsim::sweep
