// SPDX-License-Identifier: GPL-3.0-or-later
#include "urbanpvs/geometry/city/InputError.hpp"

namespace urbanpvs::geometry {

const char* to_string(InputProblem p) {
  switch (p) {
    case InputProblem::Unreadable:
      return "unreadable file";
    case InputProblem::InvalidJson:
      return "invalid JSON";
    case InputProblem::BadStructure:
      return "unexpected structure";
    case InputProblem::UnknownCrs:
      return "unknown coordinate reference system";
    case InputProblem::InvalidGeometry:
      return "invalid geometry";
    case InputProblem::MissingHeight:
      return "missing height";
    case InputProblem::EmptyCity:
      return "empty city";
    case InputProblem::UnsupportedFormat:
      return "unsupported format";
    case InputProblem::Implausible:
      return "implausible input";
    case InputProblem::InvalidXml:
      return "invalid XML";
  }
  return "input error";
}

static std::string compose(InputProblem p, const std::string& file, const std::string& feature,
                           const std::string& what) {
  std::string m = file;
  if (!feature.empty()) m += ": " + feature;
  m += ": ";
  m += to_string(p);
  if (!what.empty()) m += ": " + what;
  return m;
}

InputError::InputError(InputProblem problem, std::string file, std::string feature,
                       const std::string& what)
    : std::runtime_error(compose(problem, file, feature, what)),
      problem_(problem),
      file_(std::move(file)),
      feature_(std::move(feature)) {}

}  // namespace urbanpvs::geometry
