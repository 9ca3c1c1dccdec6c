// SPDX-License-Identifier: GPL-3.0-or-later
// The run of urbanpvs-preprocess: read → scene → cells (parallel, journalled) → file.
#include "urbanpvs/preprocess/bake/PreprocessCommand.hpp"

#include <algorithm>
#include <charconv>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <map>
#include <system_error>
#include <utility>

#include "urbanpvs/geometry/cells/ViewCellRegion.hpp"
#include "urbanpvs/geometry/city/InputError.hpp"
#include "urbanpvs/geometry/occluders/RoofPlaneOccluders.hpp"
#include "urbanpvs/geometry/occluders/SolidOccluders.hpp"
#include "urbanpvs/geometry/occluders/TerrainOccluders.hpp"
#include "urbanpvs/preprocess/bake/BakeFingerprint.hpp"
#include "urbanpvs/preprocess/bake/BakeJournal.hpp"
#include "urbanpvs/preprocess/bake/BakeProgress.hpp"
#include "urbanpvs/preprocess/bake/BakeReport.hpp"
#include "urbanpvs/preprocess/bake/CompactPvsStore.hpp"
#include "urbanpvs/preprocess/bake/DistributedBake.hpp"
#include "urbanpvs/preprocess/bake/ParallelBake.hpp"
#include "urbanpvs/runtime/PvsWriter.hpp"

#ifndef URBANPVS_VERSION
#define URBANPVS_VERSION "unknown"
#endif

namespace urbanpvs::preprocess {
namespace {

namespace fs = std::filesystem;
constexpr const char* kPrefix = "urbanpvs-preprocess: ";

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// Failures with the exit code they end the run with.
struct Failure {
  int code;
  std::string message;
};

// Temporary files a killed run leaves behind: write_file_atomic's "OUT.tmp-<digits>" and the
// journal header's "OUT.journal.new". Nothing else writes these names.
void remove_stale_temporaries(const fs::path& output) {
  const fs::path dir = output.has_parent_path() ? output.parent_path() : fs::path(".");
  const std::string tmp_prefix = output.filename().string() + ".tmp-";
  std::error_code ec;
  for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
    const std::string name = it->path().filename().string();
    if (name.size() <= tmp_prefix.size() || name.compare(0, tmp_prefix.size(), tmp_prefix) != 0)
      continue;
    if (name.find_first_not_of("0123456789", tmp_prefix.size()) != std::string::npos) continue;
    std::error_code ignored;
    fs::remove(it->path(), ignored);
  }
  std::error_code ignored;
  fs::remove(output.string() + ".journal.new", ignored);
}

class Run {
 public:
  Run(const PreprocessRequest& request, const MpiJob& job)
      : request_(request),
        job_(job),
        quiet_(request.quiet || job.rank() != 0),
        style_(BakeProgress::style_for(stderr, quiet_)) {}

  int execute();

 private:
  template <typename... Args>
  void note(const char* format, Args... args) {
    if (quiet_) return;
    std::fprintf(stderr, "%s", kPrefix);
    std::fprintf(stderr, format, args...);
    std::fputc('\n', stderr);
  }
  void check_output_directory() const;
  void read_inputs();
  JournalIdentity identity_of(const BakeScene& scene) const;
  void check_same_scene_on_every_rank(const JournalIdentity& identity) const;
  void open_journal(const BakeScene& scene);
  void compute_cells(const BakeScene& scene);
  void write_output(const BakeScene& scene);

  const PreprocessRequest& request_;
  const MpiJob& job_;
  const bool quiet_;  // only rank 0 of a job speaks (errors excepted)
  const BakeProgress::Style style_;
  BakeOptions options_;
  geometry::City city_;
  std::uint64_t input_hash_ = 0;
  std::vector<std::pair<std::string, std::string>> settings_;
  std::unique_ptr<BakeJournal> journal_;
  CompactPvsStore pvs_;                 // per cell, filled in any order
  std::vector<CellCounters> counters_;  // per cell
  std::vector<std::uint32_t> missing_;  // cells to compute, ascending
  BakeReport report_;
};

void Run::check_output_directory() const {
  // Fail before hours of work, not after them.
  const fs::path output(request_.output);
  const fs::path dir = output.has_parent_path() ? output.parent_path() : fs::path(".");
  std::error_code ec;
  if (!fs::is_directory(dir, ec))
    throw Failure{kExitOutput,
                  request_.output + ": cannot write: " + dir.string() + " is not a directory"};
  if (fs::is_directory(output, ec))
    throw Failure{kExitOutput, request_.output + ": cannot write: it is a directory"};
  if (!request_.report_file.empty()) {
    const fs::path report(request_.report_file);
    const fs::path report_dir = report.has_parent_path() ? report.parent_path() : fs::path(".");
    if (!fs::is_directory(report_dir, ec))
      throw Failure{kExitOutput, request_.report_file + ": cannot write: " + report_dir.string() +
                                     " is not a directory"};
  }
}

void Run::read_inputs() {
  city_ = geometry::read_city(request_.inputs, request_.read);
  // The DEM is input too: a journal of one terrain must not resume under another.
  std::vector<std::string> hashed = request_.inputs;
  if (!request_.read.terrain_path.empty()) hashed.push_back(request_.read.terrain_path);
  input_hash_ = hash_input_files(hashed);
  report_.input_hash = input_hash_;
  std::uint64_t region_hash = 0;
  if (!request_.region_file.empty()) {
    options_.cells.region = geometry::read_region_file(request_.region_file, city_.frame);
    region_hash = hash_input_files({request_.region_file});
  }
  settings_ = result_settings(request_, region_hash);
  for (const std::string& path : hashed) {
    std::error_code ec;
    const auto size = fs::file_size(path, ec);
    report_.inputs.push_back({path, ec ? 0 : static_cast<std::uint64_t>(size)});
  }
}

JournalIdentity Run::identity_of(const BakeScene& scene) const {
  return {bake_fingerprint(input_hash_, settings_, scene.cell_count(), city_.objects.size()),
          static_cast<std::uint32_t>(scene.cell_count()),
          static_cast<std::uint32_t>(city_.objects.size())};
}

// Every rank reads the inputs and builds the scene itself (cheaper than sending it: see README,
// "Baking a metropolis"); a rank that read other files or settings would compute other cells.
void Run::check_same_scene_on_every_rank(const JournalIdentity& identity) const {
  const std::vector<unsigned char> mine = encode_journal_header(identity);
  if (job_.broadcast(mine) != mine)
    throw Failure{kExitUsage, "rank " + std::to_string(job_.rank()) +
                                  ": its inputs or settings differ from rank 0's (another file "
                                  "content, option or version)"};
}

void Run::open_journal(const BakeScene& scene) {
  const JournalIdentity identity = identity_of(scene);
  report_.fingerprint = identity.fingerprint;
  const std::string path = request_.output + ".journal";
  const std::size_t cells = scene.cell_count();
  pvs_ = CompactPvsStore(cells, static_cast<std::uint32_t>(city_.objects.size()));
  counters_.assign(cells, {});
  std::vector<char> have(cells, 0);
  std::error_code ec;
  if (request_.resume && fs::exists(path, ec)) {
    JournalContents contents;
    // Straight into the compact store: the records as vectors could take gigabytes.
    auto take = [&](JournalRecord& record) {
      if (have[record.cell]) return;
      have[record.cell] = 1;
      pvs_.store(record.cell, record.pvs);
      counters_[record.cell] = record.counters;
      ++report_.cells_from_journal;
    };
    try {
      journal_ = BakeJournal::reopen(path, identity, contents, take);
    } catch (const JournalMismatch& e) {
      throw Failure{kExitUsage,
                    std::string(e.what()) + "; delete it, or run without --resume to start over"};
    }
    note("resuming: %zu of %zu cells from %s%s", report_.cells_from_journal, cells, path.c_str(),
         contents.dropped_bytes > 0
             ? (" (dropped a torn end of " + std::to_string(contents.dropped_bytes) + " bytes)")
                   .c_str()
             : "");
  } else {
    if (request_.resume) note("no journal at %s: starting from the first cell", path.c_str());
    journal_ = BakeJournal::create(path, identity);
  }
  for (std::uint32_t c = 0; c < cells; ++c)
    if (!have[c]) missing_.push_back(c);
}

void Run::compute_cells(const BakeScene& scene) {
  BakeProgress progress(style_, scene.cell_count(), report_.cells_from_journal, stderr, kPrefix);
  ParallelBakeOptions parallel;
  parallel.threads = request_.threads;
  auto finished = [&](CellOutcome& outcome) {
    JournalRecord record{outcome.cell, std::move(outcome.pvs), outcome.counters};
    journal_->append(record);
    // Each cell has its own slot, written by exactly one thread: no lock needed.
    pvs_.store(outcome.cell, record.pvs);
    counters_[outcome.cell] = outcome.counters;
  };
  auto tick = [&](std::size_t done) { progress.update(done); };
  if (job_.distributed()) {
    report_.ranks = bake_cells_across_ranks(job_, scene, identity_of(scene), missing_, parallel,
                                            finished, tick);
  } else {
    bake_cells(scene, missing_, parallel, finished, tick);
  }
  progress.finish(missing_.size());
  report_.cells_computed = missing_.size();
}

void Run::write_output(const BakeScene& scene) {
  // settings_ (result_settings) is the tool's version, then bake_properties() as bake_city
  // stores them, then the reading options and the region; the inputs follow.
  std::vector<std::pair<std::string, std::string>> properties = settings_;
  std::string names;
  for (const std::string& path : request_.inputs)
    names += (names.empty() ? "" : "; ") + fs::path(path).filename().string();
  properties.emplace_back("inputs", names);
  properties.emplace_back("input_hash", hex64(input_hash_));
  for (std::uint32_t c = 0; c < scene.cell_count(); ++c) {
    report_.pvs_entries += pvs_.size(c);
    report_.pvs_max = std::max<std::uint64_t>(report_.pvs_max, pvs_.size(c));
    report_.counters += counters_[c];
  }
  const runtime::PvsBake bake = scene.pvs_file(pvs_, std::move(properties), input_hash_);
  std::vector<std::byte> bytes;
  try {
    runtime::EncodeOptions options;
    options.pvs_coding = request_.pvs_coding;
    bytes = runtime::encode(bake, options);
  } catch (const runtime::PvsWriteError& e) {
    throw Failure{kExitProcessing, request_.output + ": cannot encode: " + e.what()};
  }
  report_.output_bytes = bytes.size();
  try {
    runtime::write_file_atomic(request_.output, bytes);
  } catch (const runtime::FileWriteError& e) {
    throw Failure{kExitOutput, e.what()};
  }
}

int Run::execute() {
  using Clock = std::chrono::steady_clock;
  options_ = request_.bake;
  report_.tool = std::string("urbanpvs-preprocess ") + URBANPVS_VERSION;
  report_.output = request_.output;
  report_.threads = request_.threads;
  if (job_.rank() == 0) {
    check_output_directory();
    remove_stale_temporaries(request_.output);
  }

  auto start = Clock::now();
  read_inputs();
  report_.seconds.read = seconds_since(start);
  report_.objects = city_.objects.size();
  report_.repairs = city_.report.repairs;
  report_.non_occluding = city_.report.non_occluding;
  report_.warnings = city_.report.warnings;
  report_.multipolygons = city_.report.osm_multipolygons;
  report_.terrain = city_.report.terrain_note;
  note("read %zu objects from %zu files (%.2f s)", city_.objects.size(), request_.inputs.size(),
       report_.seconds.read);

  start = Clock::now();
  const BakeScene scene(city_, options_, request_.threads);
  report_.seconds.scene = seconds_since(start);
  report_.blocks = scene.blocks().size();
  report_.occluders = scene.occluders().size();
  // Occluders that stand on no block carry where they come from in Occluder::block.
  auto occluders_from = [&](std::uint32_t source) {
    return static_cast<std::size_t>(
        std::count_if(scene.occluders().begin(), scene.occluders().end(),
                      [source](const geometry::Occluder& o) { return o.block == source; }));
  };
  report_.terrain_occluders = occluders_from(geometry::kTerrainBlock);
  report_.roof_plane_occluders = occluders_from(geometry::kRoofPlaneBlock);
  report_.solid_occluders = occluders_from(geometry::kSolidBlock);
  report_.solids_shrunk = scene.solids_shrunk();
  report_.solids_declined = scene.solids_declined();
  report_.cells = scene.cell_count();
  report_.cell_area = scene.mesh().free_area;
  note("scene: %zu blocks, %zu occluders, %zu view cells (%.2f s)", report_.blocks,
       report_.occluders, report_.cells, report_.seconds.scene);

  if (job_.distributed()) check_same_scene_on_every_rank(identity_of(scene));
  if (job_.rank() != 0) {
    // The other ranks compute what rank 0 hands out; rank 0 alone keeps the journal and writes.
    bake_cells_across_ranks(job_, scene, identity_of(scene), {}, {request_.threads}, {}, {});
    return 0;
  }

  start = Clock::now();
  open_journal(scene);
  compute_cells(scene);
  report_.seconds.visibility = seconds_since(start);

  start = Clock::now();
  write_output(scene);
  report_.seconds.write = seconds_since(start);
  report_.settings = settings_;
  report_.peak_memory_bytes = peak_memory_bytes();
  if (!request_.report_file.empty()) {
    try {
      const std::string text = report_json(report_);
      runtime::write_file_atomic(request_.report_file, text);
    } catch (const runtime::FileWriteError& e) {
      // A run that fails leaves no output; the journal stays, so --resume only rewrites.
      std::error_code ignored;
      fs::remove(request_.output, ignored);
      throw Failure{kExitOutput, e.what()};
    }
  }
  if (!journal_->remove())
    std::fprintf(stderr, "%swarning: cannot delete %s\n", kPrefix, journal_->path().c_str());
  if (!quiet_) std::fputs(summary_text(report_).c_str(), stderr);
  return 0;
}

}  // namespace

std::vector<std::pair<std::string, std::string>> result_settings(const PreprocessRequest& r,
                                                                 std::uint64_t region_hash) {
  // The table's result settings (bake_properties first, as bake_city stores them, then the
  // reading options), and the region file by name and content.
  std::vector<std::pair<std::string, std::string>> out{
      {"tool", std::string("urbanpvs-preprocess ") + URBANPVS_VERSION}};
  for (auto& property : request_properties(r)) out.push_back(std::move(property));
  out.emplace_back("region",
                   r.region_file.empty() ? "none" : fs::path(r.region_file).filename().string());
  out.emplace_back("region_hash", r.region_file.empty() ? "none" : hex64(region_hash));
  return out;
}

int run_preprocess(const PreprocessRequest& request, const MpiJob& job) {
  // A rank that fails ends the whole job (MpiJob::abort): the others would wait for it forever.
  // Rank 0 writes the output only at the very end, by rename, so a failed job leaves none.
  const std::string prefix =
      std::string(kPrefix) + (job.distributed() ? "rank " + std::to_string(job.rank()) + ": " : "");
  auto fail = [&](int code, const char* message) {
    std::fprintf(stderr, "%s%s\n", prefix.c_str(), message);
    std::fflush(stderr);
    job.abort(code);
    return code;
  };
  try {
    return Run(request, job).execute();
  } catch (const Failure& f) {
    return fail(f.code, f.message.c_str());
  } catch (const geometry::InputError& e) {
    return fail(geometry::exit_code(e.problem()), e.what());
  } catch (const JournalWriteError& e) {
    return fail(kExitOutput, e.what());
  } catch (const std::bad_alloc&) {
    return fail(kExitProcessing, "out of memory");
  } catch (const std::exception& e) {
    return fail(kExitProcessing, e.what());
  }
}

}  // namespace urbanpvs::preprocess
