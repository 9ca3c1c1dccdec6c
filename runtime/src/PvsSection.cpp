// SPDX-License-Identifier: MIT
// The pvs section: per-cell offsets and payloads (FORMAT.md, "pvs"), and the writer's choice of
// encoding and diff reference for every cell.
#include <algorithm>
#include <deque>
#include <memory>

#include "ByteReader.hpp"
#include "ByteWriter.hpp"
#include "Sections.hpp"

namespace urbanpvs::runtime::detail {
namespace {

constexpr std::size_t kHeaderSize = 8;  // cell count u32, max chain u32

/// Breadth-first order over the neighbour graph (components in index order), so a cell's
/// already-encoded neighbours — its best diff references — are close in space.
std::vector<std::uint32_t> processing_order(const std::vector<CellRecord>& cells) {
  const std::size_t n = cells.size();
  std::vector<std::uint32_t> order;
  order.reserve(n);
  std::vector<char> seen(n, 0);
  std::deque<std::uint32_t> queue;
  for (std::size_t start = 0; start < n; ++start) {
    if (seen[start]) continue;
    seen[start] = 1;
    queue.push_back(static_cast<std::uint32_t>(start));
    while (!queue.empty()) {
      const std::uint32_t c = queue.front();
      queue.pop_front();
      order.push_back(c);
      for (std::uint32_t nb : cells[c].neighbours) {
        if (nb != kNoCell && !seen[nb]) {
          seen[nb] = 1;
          queue.push_back(nb);
        }
      }
    }
  }
  return order;
}

/// Greedy per-cell choice between the smallest full encoding and the smallest diff against an
/// already encoded nearby cell (an encoded neighbour, the previous cell, and their references),
/// keeping chains within max_chain. The threshold makes some cells full "keys" although a diff
/// would be slightly smaller, which keeps later diffs short.
class PayloadPlanner {
 public:
  PayloadPlanner(const std::vector<CellRecord>& cells, const EncodeOptions& options)
      : cells_(cells),
        max_chain_(std::min(options.max_diff_chain, format::kMaxDiffChain)),
        threshold_(options.diff_threshold),
        reference_(cells.size(), kNoCell),
        depth_(cells.size(), 0),
        done_(cells.size(), 0) {}

  std::vector<std::vector<unsigned char>> plan() {
    std::vector<std::vector<unsigned char>> payloads(cells_.size());
    std::uint32_t previous = kNoCell;
    for (std::uint32_t cell : processing_order(cells_)) {
      payloads[cell] = encode_cell(cell, previous);
      done_[cell] = 1;
      previous = cell;
    }
    return payloads;
  }

  std::uint32_t max_chain() const noexcept { return max_chain_; }

 private:
  std::vector<unsigned char> encode_cell(std::uint32_t cell, std::uint32_t previous) {
    std::vector<unsigned char> full;
    encode_full(cells_[cell].pvs, full);
    if (max_chain_ == 0) return full;
    std::vector<unsigned char> best, diff;
    std::uint32_t best_reference = kNoCell;
    for (std::uint32_t candidate : candidates(cell, previous)) {
      if (depth_[candidate] >= max_chain_) continue;
      encode_diff(cell, candidate, cells_[candidate].pvs, cells_[cell].pvs, diff);
      if (best_reference == kNoCell || diff.size() < best.size()) {
        best.swap(diff);
        best_reference = candidate;
      }
    }
    if (best_reference == kNoCell ||
        static_cast<double>(best.size()) > threshold_ * static_cast<double>(full.size())) {
      return full;
    }
    reference_[cell] = best_reference;
    depth_[cell] = depth_[best_reference] + 1;
    return best;
  }

  /// Encoded cells near `cell`, each followed by its chain of references; no duplicates, in a
  /// fixed order (so the output is deterministic).
  std::vector<std::uint32_t> candidates(std::uint32_t cell, std::uint32_t previous) const {
    std::vector<std::uint32_t> out;
    const auto& nbs = cells_[cell].neighbours;
    for (std::uint32_t start : {nbs[0], nbs[1], nbs[2], previous}) {
      if (start == kNoCell || !done_[start]) continue;
      for (std::uint32_t c = start; c != kNoCell; c = reference_[c]) {
        if (std::find(out.begin(), out.end(), c) == out.end()) out.push_back(c);
      }
    }
    return out;
  }

  const std::vector<CellRecord>& cells_;
  std::uint32_t max_chain_;
  double threshold_;
  std::vector<std::uint32_t> reference_;
  std::vector<std::uint32_t> depth_;
  std::vector<char> done_;
};

}  // namespace

std::vector<unsigned char> write_pvs(const std::vector<CellRecord>& cells,
                                     const EncodeOptions& options) {
  PayloadPlanner planner(cells, options);
  const std::vector<std::vector<unsigned char>> payloads = planner.plan();
  ByteWriter w;
  w.u32(static_cast<std::uint32_t>(cells.size()));
  w.u32(planner.max_chain());
  std::uint64_t offset = 0;
  w.u32(0);
  for (const auto& p : payloads) {
    offset += p.size();
    if (offset > UINT32_MAX) throw PvsWriteError("pvs: encoded PVS data exceeds 4 GiB");
    w.u32(static_cast<std::uint32_t>(offset));
  }
  for (const auto& p : payloads) w.raw(p.data(), p.size());
  return std::move(w.bytes());
}

bool read_pvs(const SectionBytesView& in, std::uint32_t cell_count, std::uint32_t object_count,
              PvsView& out, PvsExpansion* expansion, const char*& detail) {
  ByteReader r(in.data, in.size);
  std::uint32_t count, declared_chain;
  std::uint64_t offsets_size;
  if (!r.u32(count) || !r.u32(declared_chain) || count != cell_count ||
      declared_chain > format::kMaxDiffChain ||
      !checked_mul(std::uint64_t{count} + 1, 4, offsets_size) || offsets_size > r.remaining()) {
    detail = "pvs: bad header (cell count or chain length)";
    return false;
  }
  PvsSection& s = out.section;
  s.cell_count = count;
  s.object_count = object_count;
  s.offsets = in.data + kHeaderSize;
  s.payload = s.offsets + offsets_size;
  const std::uint64_t available = r.remaining() - offsets_size;
  s.payload_size = load_u32(s.offsets + 4 * std::size_t{count});
  if (load_u32(s.offsets) != 0 || s.payload_size > available ||
      (s.payload_size != available && !in.allow_extension)) {
    detail = "pvs: offsets do not match the section length";
    return false;
  }
  // Pass 1: headers, sizes and chains (cheap), so pass 2 knows its scratch size.
  out.max_pvs_size = 0;
  out.max_chain = 0;
  out.total_entries = 0;
  for (std::uint32_t cell = 0; cell < count; ++cell) {
    PayloadHeader header;
    Chain chain;
    if (!read_payload_header(s, cell, header) || header.count > object_count) {
      detail = "pvs: bad cell payload header";
      return false;
    }
    if (!resolve_chain(s, cell, chain) || chain.diff_steps > declared_chain) {
      detail = "pvs: bad diff reference chain";
      return false;
    }
    out.max_pvs_size = std::max(out.max_pvs_size, header.count);
    out.max_chain = std::max(out.max_chain, chain.diff_steps);
    out.total_entries += header.count;
  }
  // Pass 2: decode every cell once, exactly as lookups will, and check the result. After this
  // the query functions can only meet data that decodes cleanly.
  const std::size_t half = std::max<std::size_t>(out.max_pvs_size, 1);
  std::unique_ptr<std::uint32_t[]> scratch(new std::uint32_t[out.max_chain >= 2 ? 2 * half : half]);
  // No reserve from the headers' counts: they are only trusted once decoded.
  if (expansion != nullptr) expansion->offsets.assign(1, 0);
  for (std::uint32_t cell = 0; cell < count; ++cell) {
    std::size_t n = 0;
    if (decode_cell(s, cell, scratch.get(), half, n) != Status::kOk) {
      detail = "pvs: cell payload does not decode";
      return false;
    }
    for (std::size_t i = 0; i < n; ++i) {
      if (scratch[i] >= object_count || (i > 0 && scratch[i] <= scratch[i - 1])) {
        detail = "pvs: decoded list not ascending or object index out of range";
        return false;
      }
    }
    if (expansion != nullptr) {
      expansion->ids.insert(expansion->ids.end(), scratch.get(), scratch.get() + n);
      expansion->offsets.push_back(expansion->ids.size());
    }
  }
  return true;
}

}  // namespace urbanpvs::runtime::detail
