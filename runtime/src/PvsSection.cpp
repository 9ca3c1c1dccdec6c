// SPDX-License-Identifier: MIT
// The pvs section: per-cell offsets and payloads (FORMAT.md, "pvs"), and the writer's choice of
// encoding and diff reference for every cell.
#include <algorithm>
#include <deque>
#include <memory>

#include "Bits.hpp"
#include "ByteReader.hpp"
#include "ByteWriter.hpp"
#include "Sections.hpp"

namespace urbanpvs::runtime::detail {
namespace {

constexpr std::size_t kHeaderSize = 8;  // cell count u32, max chain u32
/// Coded (2.2): cell count, max chain, block shift, payload size, all u32.
constexpr std::size_t kCodedHeaderSize = 16;

/// Breadth-first order over the neighbour graph (components in index order), so a cell's
/// already-encoded neighbours — its best diff references — are close in space.
std::vector<std::uint32_t> processing_order(const std::vector<Neighbours>& neighbours) {
  const std::size_t n = neighbours.size();
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
      for (std::uint32_t nb : neighbours[c]) {
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
  PayloadPlanner(const PvsLists& lists, const std::vector<Neighbours>& neighbours,
                 const EncodeOptions& options, bool coded)
      : lists_(lists),
        neighbours_(neighbours),
        coded_(coded),
        max_chain_(std::min(options.max_diff_chain, format::kMaxDiffChain)),
        threshold_(options.diff_threshold),
        reference_(lists.size(), kNoCell),
        depth_(lists.size(), 0),
        done_(lists.size(), 0) {}

  std::vector<std::vector<unsigned char>> plan() {
    std::vector<std::vector<unsigned char>> payloads(lists_.size());
    std::uint32_t previous = kNoCell;
    for (std::uint32_t cell : processing_order(neighbours_)) {
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
    const std::vector<std::uint32_t>& mine = lists_.get(cell, mine_);
    encode_full(mine, coded_, full);
    if (max_chain_ == 0) return full;
    std::vector<unsigned char> best, diff;
    std::uint32_t best_reference = kNoCell;
    for (std::uint32_t candidate : candidates(cell, previous)) {
      if (depth_[candidate] >= max_chain_ || (coded_ && !coded_reference_fits(cell, candidate))) {
        continue;
      }
      encode_diff(cell, candidate, neighbours_[cell], lists_.get(candidate, theirs_), mine, coded_,
                  diff);
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
    const Neighbours& nbs = neighbours_[cell];
    for (std::uint32_t start : {nbs[0], nbs[1], nbs[2], previous}) {
      if (start == kNoCell || !done_[start]) continue;
      for (std::uint32_t c = start; c != kNoCell; c = reference_[c]) {
        if (std::find(out.begin(), out.end(), c) == out.end()) out.push_back(c);
      }
    }
    return out;
  }

  const PvsLists& lists_;
  std::vector<std::uint32_t> mine_, theirs_;  ///< lists from the bake's source
  const std::vector<Neighbours>& neighbours_;
  bool coded_;
  std::uint32_t max_chain_;
  double threshold_;
  std::vector<std::uint32_t> reference_;
  std::vector<std::uint32_t> depth_;
  std::vector<char> done_;
};

/// The load-time check of every cell's PVS, and the expansion, over the forest of diff
/// references: roots are the cells stored in full, children the diffs against a cell.
struct PvsValidation {
  PvsValidation(const PvsSection& s, std::uint32_t objects) : section(s), object_count(objects) {}

  const PvsSection& section;
  std::uint32_t object_count;
  std::vector<std::uint32_t> reference;  ///< per cell: its diff reference, or kNoCell
  /// Per cell: its diff fields as pass 1 read them (meaningful where reference is a cell), so
  /// pass 2 and the expansion do not parse them again.
  LargeVector<DiffHeader> diffs;
  std::vector<std::uint32_t>
      count;  ///< per cell: its PVS size, stored or derived (true after check_all)
  std::vector<std::uint32_t> first_child;  ///< cell_count + 1 offsets into `children`
  std::vector<std::uint32_t> children;
  std::size_t half = 1;                     ///< slots per level buffer (>= the largest PVS)
  std::unique_ptr<std::uint32_t[]> levels;  ///< (max_depth + 1) buffers of `half` slots
  std::uint32_t max_depth = 0;              ///< the declared bound on diff chains
  std::uint32_t deepest = 0;                ///< the longest chain met
  std::uint32_t visited = 0;                ///< cells checked

  void index_children() {
    const std::size_t n = reference.size();
    first_child.assign(n + 1, 0);
    for (std::uint32_t r : reference)
      if (r != kNoCell) ++first_child[r + 1];
    for (std::size_t c = 0; c < n; ++c) first_child[c + 1] += first_child[c];
    children.resize(first_child[n]);
    std::vector<std::uint32_t> fill(first_child.begin(), first_child.end() - 1);
    for (std::uint32_t c = 0; c < n; ++c)
      if (reference[c] != kNoCell) children[fill[reference[c]]++] = c;
  }

  bool has_children(std::uint32_t cell) const { return first_child[cell + 1] > first_child[cell]; }

  /// The counts of coded diffs, each its reference's - removed + added, top-down from the full
  /// cells. A cell not reached is on a cycle of references.
  bool derive_counts(const char*& detail) {
    std::vector<std::uint32_t> stack;
    std::size_t reached = 0;
    for (std::uint32_t root = 0; root < reference.size(); ++root) {
      if (reference[root] != kNoCell) continue;
      stack.push_back(root);
      while (!stack.empty()) {
        const std::uint32_t cell = stack.back();
        stack.pop_back();
        ++reached;
        for (std::uint32_t k = first_child[cell]; k < first_child[cell + 1]; ++k) {
          const std::uint32_t child = children[k];
          const std::uint32_t removed = diffs[child].removed, added = diffs[child].added;
          const std::uint64_t n = std::uint64_t{count[cell]} - removed + added;
          if (removed > count[cell] || n > object_count) {
            detail = "pvs: diff removes more than its reference holds or exceeds the objects";
            return false;
          }
          count[child] = static_cast<std::uint32_t>(n);
          stack.push_back(child);
        }
      }
    }
    if (reached != reference.size()) {
      detail = "pvs: bad diff reference chain";
      return false;
    }
    return true;
  }

  /// A decoded list: strictly increasing and below object_count.
  bool valid_list(const std::uint32_t* list, std::size_t n) const {
    for (std::size_t i = 1; i < n; ++i)
      if (list[i] <= list[i - 1]) return false;
    return n == 0 || list[n - 1] < object_count;
  }

  /// Checks the diffs against `cell` (its decoded list at `list`, at depth `level`): a leaf
  /// without building its list, a cell others refer to by building it one level down.
  bool check_children(std::uint32_t cell, const std::uint32_t* list, std::size_t n,
                      std::uint32_t level, const char*& detail) {
    if (first_child[cell + 1] > first_child[cell] && level + 1 > max_depth) {
      detail = "pvs: bad diff reference chain";
      return false;
    }
    const std::uint32_t last = first_child[cell + 1];
    for (std::uint32_t k = first_child[cell]; k < last; ++k) {
      // Siblings are scattered over the file: fetch the fields of the one after next and the
      // codes of the next while this one is checked (the loop is bound by those misses).
      if (k + 2 < last) {
        const std::uint32_t later = children[k + 2];
        URBANPVS_PREFETCH(&diffs[later]);
        URBANPVS_PREFETCH(&count[later]);
        URBANPVS_PREFETCH(&first_child[later]);
      }
      if (k + 1 < last) URBANPVS_PREFETCH(diffs[children[k + 1]].lists);
      const std::uint32_t child = children[k];
      ++visited;
      deepest = std::max(deepest, level + 1);
      const DiffHeader& diff = diffs[child];
      // A leaf is checked without building its list; the level below (unused: the leaf has
      // no children) holds its removed positions.
      std::uint32_t* next = levels.get() + (level + 1) * half;
      if (!has_children(child)) {
        if (!check_diff(diff, count[child], list, n, object_count, next, half)) {
          detail = "pvs: diff does not give an ascending list of its size in range";
          return false;
        }
        continue;
      }
      std::size_t m = 0;
      if (!merge_decoded(diff, list, n, next, half, m) || m != count[child]) {
        detail = "pvs: cell payload does not decode";
        return false;
      }
      if (!valid_list(next, m)) {
        detail = "pvs: decoded list not ascending or object index out of range";
        return false;
      }
      if (!check_children(child, next, m, level + 1, detail)) return false;
    }
    return true;
  }

  bool check_all(const char*& detail) {
    for (std::uint32_t cell = 0; cell < reference.size(); ++cell) {
      if (reference[cell] != kNoCell) continue;
      ++visited;
      std::size_t n = 0;
      if (decode_cell(section, cell, levels.get(), half, n) != Status::kOk) {
        detail = "pvs: cell payload does not decode";
        return false;
      }
      if (!valid_list(levels.get(), n)) {
        detail = "pvs: decoded list not ascending or object index out of range";
        return false;
      }
      if (!check_children(cell, levels.get(), n, 0, detail)) return false;
    }
    return true;
  }

  /// Every list decoded into its place in cell order: full cells from their payload, diffs
  /// from their reference's place (filled before them: parents first). Only after check_all.
  bool expand(PvsExpansion& e, const char*& detail) {
    const std::size_t n = reference.size();
    e.offsets.resize(n + 1);
    std::uint64_t at = 0;  // words; counts are at most object_count, so no overflow
    for (std::uint32_t c = 0; c < n; ++c) {
      e.offsets[c] = at + PvsExpansion::kHeaderWords;
      const std::uint64_t words = PvsExpansion::kHeaderWords + count[c];
      at += (words + PvsExpansion::kRecordWords - 1) / PvsExpansion::kRecordWords *
            PvsExpansion::kRecordWords;
    }
    e.offsets[n] = at;
    e.ids.assign(static_cast<std::size_t>(at), 0);  // the shapes are copied in by the loader
    for (std::uint32_t c = 0; c < n; ++c) {
      e.ids[static_cast<std::size_t>(e.offsets[c]) - 2] = c;
      e.ids[static_cast<std::size_t>(e.offsets[c]) - 1] = count[c];
    }
    for (std::uint32_t cell = 0; cell < n; ++cell) {
      if (reference[cell] != kNoCell) continue;
      std::size_t got = 0;
      if (decode_cell(section, cell, e.ids.data() + e.offsets[cell], size(e, cell), got) !=
              Status::kOk ||
          !expand_children(e, cell)) {
        detail = "pvs: cell payload does not decode";
        return false;
      }
    }
    return true;
  }

  static std::size_t size(const PvsExpansion& e, std::uint32_t cell) { return e.size(cell); }

  bool expand_children(PvsExpansion& e, std::uint32_t cell) {
    for (std::uint32_t k = first_child[cell]; k < first_child[cell + 1]; ++k) {
      const std::uint32_t child = children[k];
      std::size_t got = 0;
      if (!merge_decoded(diffs[child], e.ids.data() + e.offsets[cell], size(e, cell),
                         e.ids.data() + e.offsets[child], size(e, child), got) ||
          got != size(e, child) || !expand_children(e, child)) {
        return false;
      }
    }
    return true;
  }
};

}  // namespace

namespace {

/// The largest block shift whose blocks all keep their cells' starts within 65,535 bytes of the
/// block's first: fewer u32 starts, and shift 0 always fits.
std::uint32_t block_shift_for(const std::vector<std::uint64_t>& starts) {
  const std::size_t n = starts.size() - 1;  // starts[n] is the payload size
  for (std::uint32_t shift = kMaxBlockShift; shift > 0; --shift) {
    bool fits = true;
    for (std::size_t b = 0; fits && b < n; b += std::size_t{1} << shift) {
      const std::size_t last = std::min(n, b + (std::size_t{1} << shift)) - 1;
      fits = starts[last] - starts[b] <= 0xFFFF;
    }
    if (fits) return shift;
  }
  return 0;
}

}  // namespace

std::vector<unsigned char> write_pvs(const PvsLists& lists,
                                     const std::vector<Neighbours>& neighbours,
                                     const EncodeOptions& options, bool coded) {
  PayloadPlanner planner(lists, neighbours, options, coded);
  const std::vector<std::vector<unsigned char>> payloads = planner.plan();
  std::vector<std::uint64_t> starts(payloads.size() + 1, 0);
  for (std::size_t c = 0; c < payloads.size(); ++c) {
    starts[c + 1] = starts[c] + payloads[c].size();
    if (starts[c + 1] > UINT32_MAX) throw PvsWriteError("pvs: encoded PVS data exceeds 4 GiB");
  }
  ByteWriter w;
  w.u32(static_cast<std::uint32_t>(lists.size()));
  w.u32(planner.max_chain());
  if (coded) {
    const std::uint32_t shift = block_shift_for(starts);
    w.u32(shift);
    w.u32(static_cast<std::uint32_t>(starts.back()));
    const std::size_t block = std::size_t{1} << shift;
    for (std::size_t c = 0; c < payloads.size(); ++c) {
      const std::size_t first = c & ~(block - 1);
      if (c == first) {
        w.u32(static_cast<std::uint32_t>(starts[c]));
      } else {
        w.u16(static_cast<std::uint16_t>(starts[c] - starts[first]));
      }
    }
  } else {
    for (std::uint64_t start : starts) w.u32(static_cast<std::uint32_t>(start));
  }
  for (const auto& p : payloads) w.raw(p.data(), p.size());
  return std::move(w.bytes());
}

namespace {

/// The section header and index: fills `s` (but the payload check of every cell is
/// read_payload_header's) and `declared_chain`.
bool read_pvs_index(const SectionBytesView& in, std::uint32_t cell_count, bool coded, PvsSection& s,
                    std::uint32_t& declared_chain, const char*& detail) {
  ByteReader r(in.data, in.size);
  std::uint32_t count, shift = 0, payload_size = 0;
  std::uint64_t index_size;
  if (!r.u32(count) || !r.u32(declared_chain) || count != cell_count ||
      declared_chain > format::kMaxDiffChain ||
      (coded && (!r.u32(shift) || !r.u32(payload_size) || shift > kMaxBlockShift))) {
    detail = "pvs: bad header (cell count or chain length)";
    return false;
  }
  if (coded) {
    index_size = block_index_size(count, shift);
  } else if (!checked_mul(std::uint64_t{count} + 1, 4, index_size)) {
    index_size = UINT64_MAX;
  }
  if (index_size > r.remaining()) {
    detail = "pvs: bad header (cell count or chain length)";
    return false;
  }
  s.cell_count = count;
  s.coded = coded;
  s.block_shift = shift;
  s.offsets = in.data + (coded ? kCodedHeaderSize : kHeaderSize);
  s.payload = s.offsets + index_size;
  const std::uint64_t available = r.remaining() - index_size;
  s.payload_size = coded ? payload_size : load_u32(s.offsets + 4 * std::size_t{count});
  if ((count > 0 && cell_start(s, 0) != 0) || (!coded && load_u32(s.offsets) != 0) ||
      s.payload_size > available || (s.payload_size != available && !in.allow_extension)) {
    detail = "pvs: offsets do not match the section length";
    return false;
  }
  return true;
}

}  // namespace

bool read_pvs(const SectionBytesView& in, std::uint32_t cell_count, std::uint32_t object_count,
              bool coded, const Neighbours* neighbours, PvsView& out, PvsExpansion* expansion,
              const char*& detail) {
  PvsSection& s = out.section;
  std::uint32_t declared_chain = 0;
  if (!read_pvs_index(in, cell_count, coded, s, declared_chain, detail)) return false;
  s.object_count = object_count;
  s.neighbours = neighbours;
  const std::uint32_t count = s.cell_count;
  // Pass 1, in file order: each cell's header, size and reference, so pass 2 knows its scratch
  // size and the tree of references.
  out.max_pvs_size = 0;
  out.total_entries = 0;
  PvsValidation v(s, object_count);
  v.reference.resize(count);
  v.count.resize(count);
  v.diffs.resize(count);
  for (std::uint32_t cell = 0; cell < count; ++cell) {
    PayloadHeader header;
    DiffHeader diff;
    if (!read_payload_header(s, cell, header) || header.count > object_count ||
        (header.kind == format::PvsKind::kDiff && !read_diff_header(s, cell, header, diff))) {
      detail = "pvs: bad cell payload header";
      return false;
    }
    const bool is_diff = header.kind == format::PvsKind::kDiff;
    v.reference[cell] = is_diff ? diff.reference : kNoCell;
    v.count[cell] = header.count;
    if (is_diff) v.diffs[cell] = diff;
  }
  v.index_children();
  // A coded diff's count is derived from its reference's: from the full cells down.
  if (s.coded && !v.derive_counts(detail)) return false;
  for (std::uint32_t c : v.count) {
    out.max_pvs_size = std::max(out.max_pvs_size, c);
    out.total_entries += c;
  }
  // Pass 2: every cell once, from its full base down the tree of diffs that refer to it (each
  // full list decoded once, not once per cell that refers to it). A cell it does not reach is
  // on a cycle of references; one deeper than the declared bound is too far from its base.
  // After this the query functions can only meet data that decodes cleanly.
  v.half = std::max<std::size_t>(out.max_pvs_size, 1);
  v.max_depth = declared_chain;
  v.levels.reset(new std::uint32_t[(std::size_t{declared_chain} + 1) * v.half]);
  if (!v.check_all(detail)) return false;
  if (v.visited != count) {
    detail = "pvs: bad diff reference chain";
    return false;
  }
  out.max_chain = v.deepest;
  // Only now are the counts (and so their total) known to be true: allocate and fill.
  if (expansion != nullptr && !v.expand(*expansion, detail)) return false;
  return true;
}

}  // namespace urbanpvs::runtime::detail
