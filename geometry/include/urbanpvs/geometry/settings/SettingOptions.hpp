// SPDX-License-Identifier: GPL-3.0-or-later
// Settings tables (Setting.hpp) as CLI11 options: the one way every tool declares the options of
// a stage, so that urbanpvs-cityinfo, urbanpvs-cells, urbanpvs-validate and urbanpvs-preprocess
// read a city with the same options, spelled, limited and explained the same way. Values are
// kept as text until apply(), so that a tool can merge them with a --config file and check
// everything in one pass. Include only from programs that link CLI11.
#pragma once

#include <CLI/CLI.hpp>
#include <map>
#include <string>

#include "urbanpvs/geometry/settings/Setting.hpp"

namespace urbanpvs::geometry {

/// The placeholder of a setting's value in --help: M, N, PIXELS, MIN:MAX, FILE, a|b|c.
template <typename Target>
std::string option_type_name(const Setting<Target>& s) {
  switch (s.kind) {
    case SettingKind::Number:
      return s.unit == "m" ? "M" : "X";
    case SettingKind::Integer:
      return s.unit.empty() ? "N" : "PIXELS";
    case SettingKind::Choice: {
      std::string out;
      for (const std::string& c : s.choices) out += (out.empty() ? "" : "|") + c;
      return out;
    }
    case SettingKind::Band:
      return "MIN:MAX";
    case SettingKind::Path:
      return "FILE";
    case SettingKind::Text:
      return "NAME";
    case SettingKind::Flag:
      break;
  }
  return "";
}

/// The --help text: help, unit, limits and default.
template <typename Target>
std::string option_description(const Setting<Target>& s, const Target& defaults) {
  std::string text = s.help;
  if (!s.unit.empty()) text += ", in " + s.unit;
  // A flag that is on by default says so, and how to turn it off (SettingOptions).
  if (s.kind == SettingKind::Flag)
    return s.get(defaults) == "true" ? text + " [default: on; --no-" + s.key + ": off]" : text;
  if (const std::string limits = s.limits_text(); !limits.empty()) text += " (" + limits + ")";
  return text + " [default: " + (s.default_text.empty() ? s.get(defaults) : s.default_text) + "]";
}

/// The options of one settings table on one CLI::App.
template <typename Target>
class SettingOptions {
 public:
  /// Declares every setting of `table` (which must outlive this object) on `app`.
  SettingOptions(CLI::App& app, const SettingTable<Target>& table, const Target& defaults = {})
      : table_(table) {
    // CLI11 keeps pointers into texts_ and flags_: std::map nodes never move.
    for (const Setting<Target>& s : table_) {
      const std::string name =
          (s.short_name.empty() ? "" : "-" + s.short_name + ",") + "--" + s.key;
      if (s.kind == SettingKind::Flag) {
        // Present: on. A flag that is on by default also gets --no-KEY, so that the default can
        // be turned off without a --config file; giving both is a usage error.
        CLI::Option* on = app.add_flag(name, flags_[s.key], option_description(s, defaults));
        options_[s.key] = on;
        if (s.get(defaults) == "true") {
          const std::string off_help = "Turns --" + s.key + " off";
          CLI::Option* off = app.add_flag("--no-" + s.key, off_help);
          on->excludes(off);
          negations_[s.key] = off;
        }
        continue;
      }
      CLI::Option* o = app.add_option(name, texts_[s.key], option_description(s, defaults));
      o->type_name(option_type_name(s));
      if (s.existing_file) o->check(CLI::ExistingFile);
      options_[s.key] = o;
    }
  }

  SettingOptions(const SettingOptions&) = delete;
  SettingOptions& operator=(const SettingOptions&) = delete;

  /// After parsing: the given settings as (key, text), in the table's spelling.
  std::map<std::string, std::string> given() const {
    std::map<std::string, std::string> out;
    for (const Setting<Target>& s : table_) {
      if (const auto off = negations_.find(s.key); off != negations_.end() && off->second->count())
        out[s.key] = "false";
      if (options_.at(s.key)->count() == 0) continue;
      out[s.key] =
          s.kind == SettingKind::Flag ? (flags_.at(s.key) ? "true" : "false") : texts_.at(s.key);
    }
    return out;
  }

  /// Sets every given setting on `target`; throws the setting's std::invalid_argument.
  void apply(Target& target) const {
    for (const auto& [key, text] : given()) find_setting(table_, key)->set(target, text);
  }

 private:
  const SettingTable<Target>& table_;
  std::map<std::string, std::string> texts_;
  std::map<std::string, bool> flags_;
  std::map<std::string, CLI::Option*> options_;
  std::map<std::string, CLI::Option*> negations_;  ///< --no-KEY of the flags on by default
};

}  // namespace urbanpvs::geometry
