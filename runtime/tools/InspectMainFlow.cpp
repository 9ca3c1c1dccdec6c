// SPDX-License-Identifier: MIT
// urbanpvs-inspect: argument handling, loading with error reporting, dispatch to a command.
#include <fstream>
#include <iostream>
#include <new>

#include "Inspect.hpp"
#include "urbanpvs/runtime/Format.hpp"
#include "urbanpvs/runtime/PvsWriter.hpp"

namespace urbanpvs::inspect {
namespace {

using runtime::LoadError;
using runtime::Status;

int exit_code_for(Status status) {
  return exit_code::for_load(status);
}

/// "city.pvs: checksum mismatch in section 'pvs'" and the like.
std::string describe(const std::string& path, const LoadError& e) {
  const std::string section = std::string("'") + runtime::format::section_name(e.section_id) + "'";
  switch (e.status) {
    case Status::kIoError:
      return path + ": cannot read the file";
    case Status::kSectionChecksumMismatch:
      return path + ": checksum mismatch in section " + section;
    case Status::kMissingSection:
      return path + ": required section " + section + " missing";
    case Status::kMalformedSection:
      return path + ": malformed section " + section + " (" + e.detail + ")";
    case Status::kMalformedHeader:
      return path + ": malformed header (" + e.detail +
             (e.section_id != 0 ? ", section " + section : std::string()) + ")";
    default:
      return path + ": " + e.detail;
  }
}

int run_command(const Options& o, const runtime::PvsFile& file, std::istream& in, std::ostream& out,
                std::ostream& err) {
  std::string error;
  if (o.json) {
    write_json_dump(file, out);
  } else if (o.query) {
    if (o.geo && !file.frame().geographic) {
      err << "urbanpvs-inspect: " << o.file << ": --geo needs a file baked from geographic input\n";
      return kExitBadQuery;
    }
    std::ifstream points_file;
    std::istream* points = &in;
    if (!o.points.empty() && o.points != "-") {
      points_file.open(o.points);
      if (!points_file) {
        err << "urbanpvs-inspect: " << o.points << ": cannot read the points file\n";
        return kExitUnreadable;
      }
      points = &points_file;
    }
    const int code = run_queries(file, *points, o.geo, out, error);
    if (code != kExitOk) {
      err << "urbanpvs-inspect: " << (o.points.empty() ? "<stdin>" : o.points) << ": " << error
          << "\n";
      return code;
    }
  } else if (!o.svg.empty()) {
    try {
      const std::string svg = render_svg(file, o.cell);
      runtime::write_file_atomic(o.svg, svg);
    } catch (const runtime::FileWriteError& e) {
      err << "urbanpvs-inspect: " << e.what() << "\n";
      return kExitWriteFailed;
    }
  } else if (o.cell) {
    if (!write_cell_report(file, *o.cell, out, error)) {
      err << "urbanpvs-inspect: " << o.file << ": " << error << "\n";
      return kExitBadQuery;
    }
  } else {
    write_summary(file, o.file, out);
  }
  return kExitOk;
}

}  // namespace

int run(const std::vector<std::string>& args, std::istream& in, std::ostream& out,
        std::ostream& err) {
  try {
    Options o;
    std::string error;
    if (!parse_args(args, o, error)) {
      err << "urbanpvs-inspect: " << error << "\n\n" << usage();
      return kExitUsage;
    }
    if (o.help) {
      out << usage();
      return kExitOk;
    }
    runtime::PvsFile file;
    LoadError load_error;
    const Status status = runtime::PvsFile::open_file(o.file.c_str(), file, {}, &load_error);
    if (status != Status::kOk) {
      err << "urbanpvs-inspect: " << describe(o.file, load_error) << "\n";
      return exit_code_for(status);
    }
    if (o.cell && *o.cell >= file.cell_count()) {
      err << "urbanpvs-inspect: " << o.file << ": cell " << *o.cell
          << " out of range (the file has " << file.cell_count() << " cells)\n";
      return kExitBadQuery;
    }
    const int code = run_command(o, file, in, out, err);
    out.flush();
    if (code == kExitOk && !out) {
      err << "urbanpvs-inspect: cannot write the output\n";
      return kExitWriteFailed;
    }
    return code;
  } catch (const std::bad_alloc&) {
    err << "urbanpvs-inspect: out of memory\n";
    return kExitInternal;
  }
}

}  // namespace urbanpvs::inspect
