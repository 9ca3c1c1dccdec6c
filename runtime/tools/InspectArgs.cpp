// SPDX-License-Identifier: MIT
// Command line of urbanpvs-inspect, parsed by hand (the tool links only the runtime).
#include <charconv>

#include "Inspect.hpp"

namespace urbanpvs::inspect {
namespace {

bool parse_index(const std::string& text, std::uint32_t& value) {
  const char* end = text.data() + text.size();
  const auto result = std::from_chars(text.data(), end, value);
  return !text.empty() && result.ec == std::errc() && result.ptr == end;
}

bool is_option(const std::string& arg) {
  return arg.size() > 1 && arg[0] == '-';
}

}  // namespace

std::string usage() {
  return R"(usage: urbanpvs-inspect FILE                 summary: version, settings, counts, PVS sizes, bytes
       urbanpvs-inspect FILE --cell N        one cell: geometry, neighbours, encoding, PVS with ids
       urbanpvs-inspect FILE --json          full dump as JSON (objects, cells, PVS, metadata)
       urbanpvs-inspect FILE --query [POINTS] [--geo]
                                             one JSON line per point "x y z" (input coordinates)
                                             read from POINTS or standard input ("-"); with --geo
                                             the points are "lon lat h" (WGS84, geographic files)
       urbanpvs-inspect FILE --svg OUT.svg [--cell N]
                                             top-down map: cells shaded by PVS size; with --cell
                                             the cell and its visible objects highlighted
       urbanpvs-inspect --help

Coordinates are reported in the input CRS (local + origin) for projected inputs, and in the
stored local east-north-up frame for geographic ones. Output files are written atomically.

exit codes (the same for every urbanpvs tool; README, "Exit codes"):
  0  success
  2  usage: bad or missing arguments
  3  bad value: cell out of range, unparsable query point, --geo on a non-geographic file
  4  internal error (out of memory)
  5  the output file cannot be written
  20 the input file cannot be read
  21 not a .pvs file (bad magic)
  22 unsupported format version or required feature (file newer than this tool)
  23 corrupt file: truncated, trailing bytes, checksum mismatch, malformed section
)";
}

bool parse_args(const std::vector<std::string>& args, Options& options, std::string& error) {
  options = Options{};
  std::vector<std::string> positional;
  for (std::size_t i = 0; i < args.size(); ++i) {
    const std::string& arg = args[i];
    auto value = [&](const char* what) -> const std::string* {
      if (i + 1 >= args.size() || is_option(args[i + 1])) {
        error = std::string(arg) + " needs " + what;
        return nullptr;
      }
      return &args[++i];
    };
    if (arg == "--help" || arg == "-h") {
      options.help = true;
    } else if (arg == "--json") {
      options.json = true;
    } else if (arg == "--geo") {
      options.geo = true;
    } else if (arg == "--cell") {
      const std::string* v = value("a cell index");
      std::uint32_t cell;
      if (v == nullptr) return false;
      if (!parse_index(*v, cell)) {
        error = "--cell needs a cell index, got '" + *v + "'";
        return false;
      }
      options.cell = cell;
    } else if (arg == "--svg") {
      const std::string* v = value("an output path");
      if (v == nullptr) return false;
      options.svg = *v;
    } else if (arg == "--query") {
      options.query = true;
    } else if (is_option(arg) && arg != "-") {
      error = "unknown option " + arg;
      return false;
    } else {
      positional.push_back(arg);
    }
  }
  // FILE, then (with --query) the optional POINTS file.
  if (!positional.empty()) options.file = positional[0];
  if (positional.size() == 2 && options.query) {
    options.points = positional[1];
  } else if (positional.size() >= 2) {
    error = "unexpected argument '" + positional[1] + "'";
    return false;
  }
  if (options.help) return true;
  if (options.file.empty()) {
    error = "missing FILE";
    return false;
  }
  const int modes = int{options.json} + int{options.query} + int{!options.svg.empty()};
  if (modes > 1) {
    error = "--json, --query and --svg cannot be combined";
    return false;
  }
  if (options.geo && !options.query) {
    error = "--geo only applies to --query";
    return false;
  }
  if (options.cell && (options.json || options.query)) {
    error = "--cell combines only with --svg";
    return false;
  }
  return true;
}

}  // namespace urbanpvs::inspect
