// SPDX-License-Identifier: GPL-3.0-or-later
// The checkpoint of a long bake: an append-only file (OUT.pvs.journal) of finished cells. Each
// record is written with one write() as its cell finishes, so a process killed at any moment
// (kill -9) leaves whole records and at most one torn record at the end; after a power loss the
// page cache may have lost the last few seconds, and a checksum per record finds a damaged
// tail. Resuming keeps the valid prefix, cuts off the rest and computes the missing cells; the
// output is assembled in cell order, so it is byte-identical to an uninterrupted run.
//
// Layout (little-endian):
//   header, 40 bytes: "UPVSJRNL", u32 version (1), u32 counter fields (14), u64 fingerprint,
//                     u32 cells, u32 objects, u32 header size (40), u32 CRC-32C of bytes 0..35
//   record:           u32 payload size n, payload[n], u32 CRC-32C of (size, payload)
//   payload:          LEB128 varints: cell, counter count, the counters (kCellCounterFields
//                     order), PVS size, first object index, then the gaps between indices
// The header is written to a temporary file and renamed into place, so it is never torn.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <mutex>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

#include "urbanpvs/preprocess/visibility/CellVisibility.hpp"

namespace urbanpvs::preprocess {

/// Which bake a journal belongs to; a journal is resumed only when all fields match.
struct JournalIdentity {
  std::uint64_t fingerprint = 0;  ///< bake_fingerprint() of inputs, settings and scene size
  std::uint32_t cells = 0;
  std::uint32_t objects = 0;
};

/// One finished cell.
struct JournalRecord {
  std::uint32_t cell = 0;
  std::vector<std::uint32_t> pvs;  ///< strictly increasing object indices
  CellCounters counters;
};

/// The journal cannot be created or written (disk full, no permission): an output error.
class JournalWriteError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// An existing journal that must not be resumed: not a journal, a damaged header, a newer
/// version, or one from other inputs or settings. what() names the file and the reason.
class JournalMismatch : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// The valid prefix of a journal's bytes.
struct JournalContents {
  /// In file order; a cell may repeat (identical records). Empty where a JournalRecordSink took
  /// them.
  std::vector<JournalRecord> records;
  std::uint64_t valid_bytes = 0;    ///< header plus the whole records with good checksums
  std::uint64_t dropped_bytes = 0;  ///< a torn or damaged tail after them
};

inline constexpr std::uint32_t kJournalVersion =
    4;  // 3: the far field's sweep counters; 4: narrow_sweeps
inline constexpr std::size_t kJournalHeaderSize = 40;

std::vector<unsigned char> encode_journal_header(const JournalIdentity& identity);
/// Appends the record's bytes to `out`. The PVS must be strictly increasing.
void encode_journal_record(const JournalRecord& record, std::vector<unsigned char>& out);

/// Takes each valid record as it is read, in file order, instead of JournalContents::records:
/// a journal of a city whose cells see every building would not fit in memory as records
/// (CompactPvsStore.hpp).
using JournalRecordSink = std::function<void(JournalRecord& record)>;

/// Reads the header and the valid records of a journal held in memory. Safe on any bytes: a
/// record whose checksum, size, cell or object indices are off ends the valid prefix. Throws
/// JournalMismatch (naming `name`) when the header is not that of `expected`. With a `sink`,
/// the records go to it and `records` stays empty.
JournalContents decode_journal(std::span<const unsigned char> bytes,
                               const JournalIdentity& expected, const std::string& name,
                               const JournalRecordSink& sink = {});

/// An open journal file. append() may be called from several threads.
class BakeJournal {
 public:
  /// A new, empty journal at `path`, replacing any file there. Throws JournalWriteError.
  static std::unique_ptr<BakeJournal> create(const std::string& path,
                                             const JournalIdentity& identity);
  /// Reopens the journal at `path` for appending: fills `contents` with its valid records and
  /// cuts the file back to them. Throws JournalMismatch (see decode_journal) or
  /// JournalWriteError; a missing file is a JournalWriteError too (check first).
  static std::unique_ptr<BakeJournal> reopen(const std::string& path,
                                             const JournalIdentity& identity,
                                             JournalContents& contents,
                                             const JournalRecordSink& sink = {});

  ~BakeJournal();
  BakeJournal(const BakeJournal&) = delete;
  BakeJournal& operator=(const BakeJournal&) = delete;

  /// Appends one record with a single write(). Throws JournalWriteError.
  void append(const JournalRecord& record);
  /// Closes and deletes the file once the output holds every cell. Returns false (and leaves
  /// the file) when it cannot be deleted.
  bool remove();
  const std::string& path() const { return path_; }

 private:
  BakeJournal(std::string path, int fd);
  std::string path_;
  int fd_ = -1;
  std::mutex mutex_;
  std::vector<unsigned char> buffer_;  ///< guarded by mutex_
  std::int64_t last_sync_ns_ = 0;      ///< guarded by mutex_
};

}  // namespace urbanpvs::preprocess
