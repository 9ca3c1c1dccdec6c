// SPDX-License-Identifier: GPL-3.0-or-later
// urbanpvs-preprocess as library functions, so tests and other front ends can drive it: parse a
// command line (and a --config file) into a request, run the request to an exit code.
#pragma once

#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "urbanpvs/geometry/city/CityReader.hpp"
#include "urbanpvs/geometry/city/InputError.hpp"
#include "urbanpvs/preprocess/bake/BakeScene.hpp"
#include "urbanpvs/preprocess/bake/BakeSettings.hpp"
#include "urbanpvs/preprocess/bake/MpiJob.hpp"
#include "urbanpvs/runtime/ExitCodes.hpp"

namespace urbanpvs::preprocess {

/// The exit codes urbanpvs-preprocess uses besides 0, from the tools' one table
/// (urbanpvs/runtime/ExitCodes.hpp); input errors exit with geometry::exit_code() (10–19).
inline constexpr int kExitUsage = exit_code::kUsage;  ///< bad command line or config; journal
inline constexpr int kExitProcessing = exit_code::kProcessing;  ///< the bake itself failed
inline constexpr int kExitOutput = exit_code::kOutput;  ///< output, journal or report unwritable
static_assert(int(geometry::InputProblem::Unreadable) == exit_code::kCityInputFirst &&
              int(geometry::InputProblem::InvalidXml) == exit_code::kCityInputLast);

/// Parses urbanpvs-preprocess's command line, merging the --config file it names (the command
/// line wins). Returns the exit code when the program should stop here (0 after --help, 2 after
/// a usage error, whose message it has printed); nullopt when `request` is ready to run.
std::optional<int> parse_preprocess_command_line(int argc, const char* const* argv,
                                                 PreprocessRequest& request);

/// The settings that determine the result, as stored in the output's metadata properties and
/// hashed into the journal's fingerprint: tool version, every bake and reading option, and the
/// region file's name and hash (`region_hash`, 0 without a region).
std::vector<std::pair<std::string, std::string>> result_settings(const PreprocessRequest& request,
                                                                 std::uint64_t region_hash);

/// Runs the bake: read, scene, every cell's PVS (in parallel, journalled), write. Progress and
/// the summary go to standard error unless request.quiet; errors always do. Returns 0 or an exit
/// code; on failure no output (and no temporary file) is left, while the journal stays for
/// --resume. Run by every rank of an MPI `job` (see DistributedBake.hpp), only rank 0 keeps
/// the journal and writes; a failure on any rank ends the job with its exit code.
int run_preprocess(const PreprocessRequest& request, const MpiJob& job = MpiJob::single());

}  // namespace urbanpvs::preprocess
