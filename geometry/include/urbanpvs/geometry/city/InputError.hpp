// SPDX-License-Identifier: GPL-3.0-or-later
// Errors in city input. Each names the file, the feature and the problem, and maps to a distinct
// process exit code so scripts can tell a broken file from a broken command line.
#pragma once

#include <stdexcept>
#include <string>

namespace urbanpvs::geometry {

enum class InputProblem {
  Unreadable = 10,       ///< cannot open or read the file
  InvalidJson = 11,      ///< syntax error (message has the byte offset)
  BadStructure = 12,     ///< valid JSON but not the expected CityJSON / GeoJSON shape
  UnknownCrs = 13,       ///< a reference system we cannot interpret
  InvalidGeometry = 14,  ///< self-intersecting or zero-area ring, < 3 points, NaN / infinite
  MissingHeight = 15,    ///< no height attribute and no default height given
  EmptyCity = 16,        ///< no building in the input
  UnsupportedFormat = 17,
  Implausible = 18,  ///< far outside what a city can be (a building 10 km tall)
  InvalidXml = 19,   ///< CityGML that is no well-formed XML (message has line and column)
};

/// The exit code a command returns for an InputError (distinct per problem).
inline int exit_code(InputProblem p) {
  return static_cast<int>(p);
}

const char* to_string(InputProblem p);

class InputError : public std::runtime_error {
 public:
  InputError(InputProblem problem, std::string file, std::string feature, const std::string& what);

  InputProblem problem() const { return problem_; }
  const std::string& file() const { return file_; }
  const std::string& feature() const { return feature_; }

 private:
  InputProblem problem_;
  std::string file_;
  std::string feature_;
};

}  // namespace urbanpvs::geometry
