// SPDX-License-Identifier: MIT
#pragma once

// urbanpvs-inspect as a library: every command writes to streams, so tests run them directly
// and the executable is a one-line main.

#include <cstdint>
#include <iosfwd>
#include <optional>
#include <string>
#include <vector>

#include "urbanpvs/runtime/ExitCodes.hpp"
#include "urbanpvs/runtime/PvsFile.hpp"

namespace urbanpvs::inspect {

/// Exit codes: the tools' one table (urbanpvs/runtime/ExitCodes.hpp), by their inspect names.
enum ExitCode : int {
  kExitOk = exit_code::kOk,
  kExitInternal = exit_code::kProcessing,         ///< out of memory or another unexpected failure
  kExitUsage = exit_code::kUsage,                 ///< bad or missing command-line arguments
  kExitUnreadable = exit_code::kFileUnreadable,   ///< the input file cannot be read
  kExitNotPvs = exit_code::kNotPvs,               ///< not a .pvs file (bad magic)
  kExitUnsupported = exit_code::kPvsUnsupported,  ///< unsupported major version or feature
  kExitCorrupt = exit_code::kPvsCorrupt,  ///< truncated, trailing bytes, checksum, malformed
  kExitBadQuery = exit_code::kBadQuery,   ///< bad argument value: cell out of range, bad point
  kExitWriteFailed = exit_code::kOutput,  ///< the output file cannot be written
};

struct Options {
  std::string file;
  std::optional<std::uint32_t> cell;
  bool json = false;
  bool query = false;
  std::string points;  ///< --query input: a path, or "" / "-" for standard input
  bool geo = false;
  std::string svg;  ///< --svg output path
  bool help = false;
};

/// Parses argv[1..]; on failure returns false with a message in `error`.
bool parse_args(const std::vector<std::string>& args, Options& options, std::string& error);

/// The --help text.
std::string usage();

/// Runs the tool. `in` is standard input (for --query), `out`/`err` standard output/error.
int run(const std::vector<std::string>& args, std::istream& in, std::ostream& out,
        std::ostream& err);

/// The individual commands, over an open file.
void write_summary(const runtime::PvsFile& file, const std::string& name, std::ostream& out);
/// false (with a message) when the cell is out of range.
bool write_cell_report(const runtime::PvsFile& file, std::uint32_t cell, std::ostream& out,
                       std::string& error);
void write_json_dump(const runtime::PvsFile& file, std::ostream& out);
/// Reads points from `points` and writes one JSON line per point. Returns kExitOk or
/// kExitBadQuery (message in `error`, e.g. "line 3: expected three numbers").
int run_queries(const runtime::PvsFile& file, std::istream& points, bool geo, std::ostream& out,
                std::string& error);
/// The SVG map (optionally highlighting `cell`, which must be in range).
std::string render_svg(const runtime::PvsFile& file, std::optional<std::uint32_t> cell);

/// Whether coordinates are reported in the input CRS (projected input) or the local frame.
bool reports_input_coordinates(const runtime::PvsFile& file);
/// A local point in reported coordinates.
std::array<double, 3> reported(const runtime::PvsFile& file, double x, double y, double z);

}  // namespace urbanpvs::inspect
