// SPDX-License-Identifier: GPL-3.0-or-later
// What the readers that go through GDAL share (DemTerrain.cpp for rasters, GisVectorReader.cpp
// for vector data): GDAL's drivers registered once, its messages kept off stderr and turned
// into InputErrors by the caller, and owning handles for what GDAL allocates.
#pragma once

#include <cpl_error.h>
#include <gdal_priv.h>
#include <ogr_spatialref.h>

#include <mutex>
#include <string>

namespace urbanpvs::geometry::detail {

// GDAL reports errors through a global handler that prints to stderr; the readers report them
// themselves, as an InputError, so they are silenced while one works.
struct QuietGdal {
  QuietGdal() {
    static std::once_flag registered;
    std::call_once(registered, [] { GDALAllRegister(); });
    CPLPushErrorHandler(CPLQuietErrorHandler);
    CPLErrorReset();
  }
  ~QuietGdal() { CPLPopErrorHandler(); }
  QuietGdal(const QuietGdal&) = delete;
  QuietGdal& operator=(const QuietGdal&) = delete;
  /// GDAL's last message as ": message", or "" when it gave none.
  static std::string last() {
    const char* m = CPLGetLastErrorMsg();
    return m && *m ? std::string(": ") + m : std::string();
  }
};

struct DatasetCloser {
  void operator()(GDALDataset* d) const { GDALClose(GDALDataset::ToHandle(d)); }
};
struct TransformDeleter {
  void operator()(OGRCoordinateTransformation* t) const {
    OGRCoordinateTransformation::DestroyCT(t);
  }
};

/// Web Mercator (EPSG:3857, the web maps' system) and the other Mercators measure in "metres"
/// that are 1/cos(latitude) true metres: a city read in them is too large in plan, not in
/// height, so the readers never take them as metres.
inline bool is_mercator(const OGRSpatialReference& s) {
  const char* method = s.GetAttrValue("PROJECTION");
  if (method == nullptr) return false;
  const std::string m = method;
  return m.rfind("Mercator", 0) == 0 || m.find("Pseudo_Mercator") != std::string::npos;
}

/// "EPSG:25832" where the system names its authority, else its name.
inline std::string crs_name(const OGRSpatialReference& s) {
  const char* name = s.GetAuthorityName(nullptr);
  const char* code = s.GetAuthorityCode(nullptr);
  if (name && code) return std::string(name) + ":" + code;
  const char* n = s.GetName();
  return n ? n : "(unnamed)";
}

}  // namespace urbanpvs::geometry::detail
