// SPDX-License-Identifier: GPL-3.0-or-later
// One setting, written once: its key (the long option, the --config key, and with its unit the
// property stored in a .pvs file), unit, limits, help text and enum names. Its default is the
// member initializer of the options struct that holds it. Each stage publishes the table of its
// own options (read_settings, block_settings, view_cell_settings); every tool binds the tables
// it needs (SettingOptions.hpp), the bake composes them with its own (BakeSettings.hpp), and the
// stages check their options against the same table (check_limits), so a key, a limit or a
// help text exists in one place only.
#pragma once

#include <algorithm>
#include <charconv>
#include <cmath>
#include <functional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace urbanpvs::geometry {

/// Where a setting acts, in the order of the pipeline. Read, Occluders, Cells and Visibility
/// change the result: they are stored in the file and part of the journal's fingerprint.
enum class SettingStage { Read, Occluders, Cells, Visibility, Run };

enum class SettingKind {
  Number,   ///< a double, checked against [min, max]
  Integer,  ///< an integer, checked against [min, max]
  Flag,     ///< true / false (on the command line: present or not)
  Choice,   ///< one of `choices`
  Band,     ///< "MIN:MAX" in the unit, min <= MIN <= MAX <= max
  Path,     ///< a file name; in a --config file relative to the config
  Text,     ///< a name taken as given ("none": no name)
};

/// The shortest text that reads back to the same double: equal settings give equal text (and so
/// equal fingerprints), different ones different text.
inline std::string exact(double v) {
  char text[64];
  const auto result = std::to_chars(text, text + sizeof text, v);
  return std::string(text, result.ptr);
}

/// A setting of the options struct `Target`.
template <typename Target>
struct Setting {
  std::string key;   ///< "max-cell-edge": option --max-cell-edge, config key (or max_cell_edge)
  std::string unit;  ///< "m", "pixels" or "" (none)
  SettingStage stage = SettingStage::Run;
  SettingKind kind = SettingKind::Number;
  std::string help;
  double min = 0, max = 0;           ///< inclusive limits (Number, Integer, Band)
  std::vector<std::string> choices;  ///< Choice: names in the enum's order
  /// Text shown as the default when it is not the member's value ("all cores", "none").
  std::string default_text;
  /// A one-letter alias of the option ("q" for -q), or empty.
  std::string short_name;
  /// Path: the file must exist when the command line is read (an input, not an output).
  bool existing_file = false;
  /// A result setting newer than some files: the value those files were made with, read for a
  /// file that has no property for it (empty: such a file is refused).
  std::string value_before_it;
  /// The value as text: exact (the shortest text that reads back to the same double).
  std::function<std::string(const Target&)> get;
  /// Sets the value from text (as given on the command line or converted from JSON). Throws
  /// std::invalid_argument "--key ..." when the text does not parse or is out of the limits.
  std::function<void(Target&, const std::string&)> set;

  bool changes_result() const { return stage != SettingStage::Run; }
  /// The key of the file's property: "max_cell_edge_m".
  std::string property_key() const {
    std::string k = key;
    std::replace(k.begin(), k.end(), '-', '_');
    return unit == "m" ? k + "_m" : k;
  }
  /// "0.01 .. 1000 m", "cpu | osmesa", "" for flags and paths.
  std::string limits_text() const {
    switch (kind) {
      case SettingKind::Number:
      case SettingKind::Integer:
      case SettingKind::Band:
        return exact(min) + " .. " + exact(max) + (unit.empty() ? "" : " " + unit);
      case SettingKind::Choice: {
        std::string out;
        for (const std::string& c : choices) out += (out.empty() ? "" : " | ") + c;
        return out;
      }
      case SettingKind::Flag:
      case SettingKind::Path:
      case SettingKind::Text:
        break;
    }
    return "";
  }
  /// The default as the tables show it, with its unit: "18 m", "none".
  std::string default_shown(const Target& defaults) const {
    if (!default_text.empty()) return default_text;
    return get(defaults) + (unit.empty() ? "" : " " + unit);
  }
};

template <typename Target>
using SettingTable = std::vector<Setting<Target>>;

namespace setting_detail {

[[noreturn]] inline void refuse(const std::string& key, const std::string& what,
                                const std::string& text) {
  throw std::invalid_argument("--" + key + " " + what + ", got \"" + text + "\"");
}

inline double parse_number(const std::string& key, const std::string& text) {
  double v = 0;
  const char* end = text.data() + text.size();
  const auto [ptr, ec] = std::from_chars(text.data(), end, v);
  if (ec != std::errc() || ptr != end || !std::isfinite(v)) refuse(key, "expects a number", text);
  return v;
}

template <typename Target>
Setting<Target> base(std::string key, std::string unit, SettingStage stage, SettingKind kind,
                     std::string help, double min = 0, double max = 0) {
  Setting<Target> s;
  s.key = std::move(key);
  s.unit = std::move(unit);
  s.stage = stage;
  s.kind = kind;
  s.help = std::move(help);
  s.min = min;
  s.max = max;
  return s;
}

template <typename Target>
void check_limits(const Setting<Target>& s, double v, const std::string& text) {
  if (!(v >= s.min && v <= s.max)) refuse(s.key, "must be " + s.limits_text(), text);
}

}  // namespace setting_detail

// Builders, one per kind. `field` names the member that holds the value (and so its default).
template <typename Target>
Setting<Target> number_setting(std::string key, std::string unit, SettingStage stage, double min,
                               double max, std::string help,
                               std::function<double&(Target&)> field) {
  auto s = setting_detail::base<Target>(std::move(key), std::move(unit), stage, SettingKind::Number,
                                        std::move(help), min, max);
  s.get = [field](const Target& t) { return exact(field(const_cast<Target&>(t))); };
  s.set = [field, s](Target& t, const std::string& text) {
    const double v = setting_detail::parse_number(s.key, text);
    setting_detail::check_limits(s, v, text);
    field(t) = v;
  };
  return s;
}

template <typename Int, typename Target>
Setting<Target> integer_setting(std::string key, std::string unit, SettingStage stage, double min,
                                double max, std::string help, std::function<Int&(Target&)> field) {
  auto s = setting_detail::base<Target>(std::move(key), std::move(unit), stage,
                                        SettingKind::Integer, std::move(help), min, max);
  s.get = [field](const Target& t) { return std::to_string(field(const_cast<Target&>(t))); };
  s.set = [field, s](Target& t, const std::string& text) {
    const double v = setting_detail::parse_number(s.key, text);
    if (v != std::floor(v)) setting_detail::refuse(s.key, "expects an integer", text);
    setting_detail::check_limits(s, v, text);
    field(t) = static_cast<Int>(v);
  };
  return s;
}

template <typename Target>
Setting<Target> flag_setting(std::string key, SettingStage stage, std::string help,
                             std::function<bool&(Target&)> field) {
  auto s =
      setting_detail::base<Target>(std::move(key), "", stage, SettingKind::Flag, std::move(help));
  s.get = [field](const Target& t) { return field(const_cast<Target&>(t)) ? "true" : "false"; };
  s.set = [field, key = s.key](Target& t, const std::string& text) {
    if (text != "true" && text != "false")
      setting_detail::refuse(key, "expects true or false", text);
    field(t) = text == "true";
  };
  return s;
}

/// An enum whose values are 0, 1, ... in the order of `names`.
template <typename Enum, typename Target>
Setting<Target> choice_setting(std::string key, SettingStage stage, std::vector<std::string> names,
                               std::string help, std::function<Enum&(Target&)> field) {
  auto s =
      setting_detail::base<Target>(std::move(key), "", stage, SettingKind::Choice, std::move(help));
  s.choices = std::move(names);
  s.get = [field, names = s.choices](const Target& t) {
    return names.at(static_cast<std::size_t>(field(const_cast<Target&>(t))));
  };
  s.set = [field, s](Target& t, const std::string& text) {
    const auto it = std::find(s.choices.begin(), s.choices.end(), text);
    if (it == s.choices.end())
      setting_detail::refuse(s.key, "must be one of " + s.limits_text(), text);
    field(t) = static_cast<Enum>(it - s.choices.begin());
  };
  return s;
}

/// "MIN:MAX" into two members, min <= MIN <= MAX <= max.
template <typename Target>
Setting<Target> band_setting(std::string key, std::string unit, SettingStage stage, double min,
                             double max, std::string help, std::function<double&(Target&)> lo,
                             std::function<double&(Target&)> hi) {
  auto s = setting_detail::base<Target>(std::move(key), std::move(unit), stage, SettingKind::Band,
                                        std::move(help), min, max);
  s.get = [lo, hi](const Target& t) {
    return exact(lo(const_cast<Target&>(t))) + ":" + exact(hi(const_cast<Target&>(t)));
  };
  s.set = [lo, hi, s](Target& t, const std::string& text) {
    const auto colon = text.find(':');
    if (colon == std::string::npos)
      setting_detail::refuse(
          s.key, "expects MIN:MAX in " + (s.unit == "m" ? std::string("metres") : s.unit), text);
    const double a = setting_detail::parse_number(s.key, text.substr(0, colon));
    const double b = setting_detail::parse_number(s.key, text.substr(colon + 1));
    if (!(a >= s.min && a <= b && b <= s.max))
      setting_detail::refuse(s.key, "must be " + exact(s.min) + " <= MIN <= MAX <= " + exact(s.max),
                             text);
    lo(t) = a;
    hi(t) = b;
  };
  return s;
}

template <typename Target>
Setting<Target> path_setting(std::string key, SettingStage stage, std::string help,
                             std::function<std::string&(Target&)> field) {
  auto s =
      setting_detail::base<Target>(std::move(key), "", stage, SettingKind::Path, std::move(help));
  s.default_text = "none";
  s.get = [field](const Target& t) {
    const std::string& v = field(const_cast<Target&>(t));
    return v.empty() ? std::string("none") : v;
  };
  s.set = [field](Target& t, const std::string& text) { field(t) = text; };
  return s;
}

/// A name (an attribute, a tag): empty, shown and given as "none", when there is none.
template <typename Target>
Setting<Target> text_setting(std::string key, SettingStage stage, std::string help,
                             std::function<std::string&(Target&)> field) {
  auto s =
      setting_detail::base<Target>(std::move(key), "", stage, SettingKind::Text, std::move(help));
  s.get = [field](const Target& t) {
    const std::string& v = field(const_cast<Target&>(t));
    return v.empty() ? std::string("none") : v;
  };
  s.set = [field, key = s.key](Target& t, const std::string& text) {
    if (text.empty()) setting_detail::refuse(key, "expects a name (or none)", text);
    field(t) = text == "none" ? std::string() : text;
  };
  return s;
}

/// The same setting acting on the part of `Outer` that `part` selects: how a larger options
/// struct (the bake's request) takes over a stage's table instead of writing it again.
template <typename Outer, typename Inner>
Setting<Outer> lift(const Setting<Inner>& s, std::function<Inner&(Outer&)> part) {
  Setting<Outer> out;
  out.key = s.key;
  out.unit = s.unit;
  out.stage = s.stage;
  out.kind = s.kind;
  out.help = s.help;
  out.min = s.min;
  out.max = s.max;
  out.choices = s.choices;
  out.default_text = s.default_text;
  out.short_name = s.short_name;
  out.existing_file = s.existing_file;
  out.value_before_it = s.value_before_it;
  out.get = [get = s.get, part](const Outer& o) { return get(part(const_cast<Outer&>(o))); };
  out.set = [set = s.set, part](Outer& o, const std::string& text) { set(part(o), text); };
  return out;
}

/// Throws the table's std::invalid_argument ("--max-cell-edge must be 0.5 .. 10000 m, got ...")
/// for the first setting of `options` that is out of its limits: the stages' own checks of
/// options built in code, against the limits of the command line.
template <typename Target>
void check_limits(const SettingTable<Target>& table, const Target& options) {
  Target scratch = options;
  for (const Setting<Target>& s : table)
    if (s.kind != SettingKind::Path) s.set(scratch, s.get(options));
}

/// The setting with this key (underscores read as dashes); nullptr when there is none.
template <typename Target>
const Setting<Target>* find_setting(const SettingTable<Target>& table, std::string key) {
  std::replace(key.begin(), key.end(), '_', '-');
  for (const Setting<Target>& s : table)
    if (s.key == key) return &s;
  return nullptr;
}

}  // namespace urbanpvs::geometry
