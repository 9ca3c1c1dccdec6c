// SPDX-License-Identifier: GPL-3.0-or-later
#include "urbanpvs/preprocess/bake/BakeJournal.hpp"

#include <fcntl.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstring>

#include "Leb128.hpp"
#include "urbanpvs/preprocess/bake/BakeFingerprint.hpp"
#include "urbanpvs/preprocess/visibility/CellCounters.hpp"
#include "urbanpvs/runtime/Crc32c.hpp"

namespace urbanpvs::preprocess {
namespace {

using detail::put_varint;
using detail::VarintReader;

constexpr unsigned char kMagic[8] = {'U', 'P', 'V', 'S', 'J', 'R', 'N', 'L'};
constexpr std::uint32_t kCounterFieldCount = kCellCounterFields.size();
// Records are synced to disk this often, so a power loss costs at most these seconds of work
// (a kill -9 costs nothing: written records are in the kernel already).
constexpr std::int64_t kSyncIntervalNs = 5'000'000'000;

void put_u32(std::vector<unsigned char>& out, std::uint32_t v) {
  for (int i = 0; i < 4; ++i) out.push_back(static_cast<unsigned char>(v >> (8 * i)));
}
void put_u64(std::vector<unsigned char>& out, std::uint64_t v) {
  for (int i = 0; i < 8; ++i) out.push_back(static_cast<unsigned char>(v >> (8 * i)));
}
std::uint32_t get_u32(const unsigned char* p) {
  std::uint32_t v = 0;
  for (int i = 0; i < 4; ++i) v |= std::uint32_t{p[i]} << (8 * i);
  return v;
}
std::uint64_t get_u64(const unsigned char* p) {
  std::uint64_t v = 0;
  for (int i = 0; i < 8; ++i) v |= std::uint64_t{p[i]} << (8 * i);
  return v;
}

// Decodes one payload; false when it does not describe a cell of this bake.
bool decode_payload(const unsigned char* p, std::size_t n, const JournalIdentity& id,
                    JournalRecord& r) {
  VarintReader in(p, n);
  std::uint64_t v = 0;
  if (!in.next(v) || v >= id.cells) return false;
  r.cell = static_cast<std::uint32_t>(v);
  if (!in.next(v) || v != kCounterFieldCount) return false;
  for (const auto& field : kCellCounterFields)
    if (!in.next(r.counters.*(field.second))) return false;
  std::uint64_t size = 0;
  if (!in.next(size) || size > id.objects) return false;
  r.pvs.clear();
  r.pvs.reserve(static_cast<std::size_t>(size));
  std::uint64_t object = 0;
  for (std::uint64_t k = 0; k < size; ++k) {
    if (!in.next(v) || (k > 0 && v == 0)) return false;
    object += v;
    if (object >= id.objects) return false;
    r.pvs.push_back(static_cast<std::uint32_t>(object));
  }
  return in.at_end();
}

std::string errno_text() {
  return std::strerror(errno);
}

void write_all(int fd, const unsigned char* data, std::size_t size, const std::string& path) {
  while (size > 0) {
    const ssize_t n = ::write(fd, data, size);
    if (n < 0) {
      if (errno == EINTR) continue;
      throw JournalWriteError(path + ": cannot write the journal: " + errno_text());
    }
    data += n;
    size -= static_cast<std::size_t>(n);
  }
}

std::int64_t now_ns() {
  return std::chrono::duration_cast<std::chrono::nanoseconds>(
             std::chrono::steady_clock::now().time_since_epoch())
      .count();
}

}  // namespace

std::vector<unsigned char> encode_journal_header(const JournalIdentity& id) {
  std::vector<unsigned char> out(std::begin(kMagic), std::end(kMagic));
  put_u32(out, kJournalVersion);
  put_u32(out, kCounterFieldCount);
  put_u64(out, id.fingerprint);
  put_u32(out, id.cells);
  put_u32(out, id.objects);
  put_u32(out, static_cast<std::uint32_t>(kJournalHeaderSize));
  put_u32(out, runtime::crc32c(out.data(), out.size()));
  return out;
}

void encode_journal_record(const JournalRecord& r, std::vector<unsigned char>& out) {
  const std::size_t start = out.size();
  put_u32(out, 0);  // the payload size, patched below
  put_varint(out, r.cell);
  put_varint(out, kCounterFieldCount);
  for (const auto& field : kCellCounterFields) put_varint(out, r.counters.*(field.second));
  put_varint(out, r.pvs.size());
  std::uint32_t previous = 0;
  for (std::uint32_t object : r.pvs) {
    put_varint(out, object - previous);
    previous = object;
  }
  const auto payload = static_cast<std::uint32_t>(out.size() - start - 4);
  for (int i = 0; i < 4; ++i) out[start + i] = static_cast<unsigned char>(payload >> (8 * i));
  put_u32(out, runtime::crc32c(out.data() + start, out.size() - start));
}

JournalContents decode_journal(std::span<const unsigned char> bytes,
                               const JournalIdentity& expected, const std::string& name,
                               const JournalRecordSink& sink) {
  const unsigned char* p = bytes.data();
  if (bytes.size() < sizeof kMagic || std::memcmp(p, kMagic, sizeof kMagic) != 0)
    throw JournalMismatch(name + ": not an urbanpvs-preprocess journal");
  const std::uint32_t version = bytes.size() >= 12 ? get_u32(p + 8) : kJournalVersion;
  if (version != kJournalVersion)
    throw JournalMismatch(name + ": journal version " + std::to_string(version) +
                          ", this urbanpvs-preprocess reads version " +
                          std::to_string(kJournalVersion));
  if (bytes.size() < kJournalHeaderSize || get_u32(p + 36) != runtime::crc32c(p, 36))
    throw JournalMismatch(name + ": the journal's header is damaged");
  const JournalIdentity found{get_u64(p + 16), get_u32(p + 24), get_u32(p + 28)};
  if (get_u32(p + 12) != kCounterFieldCount || found.fingerprint != expected.fingerprint ||
      found.cells != expected.cells || found.objects != expected.objects)
    throw JournalMismatch(name + ": the journal belongs to other inputs or settings (fingerprint " +
                          hex64(found.fingerprint) + ", " + std::to_string(found.cells) +
                          " cells; this run: " + hex64(expected.fingerprint) + ", " +
                          std::to_string(expected.cells) + " cells)");

  JournalContents out;
  // A payload can hold no more than its varints: this bound rejects garbage sizes before any
  // allocation.
  const std::uint64_t max_payload =
      10 * (3 + kCounterFieldCount) + 5 * std::uint64_t{found.objects};
  std::size_t at = kJournalHeaderSize;
  JournalRecord record;
  while (bytes.size() - at >= 8) {
    const std::uint32_t n = get_u32(p + at);
    if (n > max_payload || bytes.size() - at - 8 < n) break;
    if (get_u32(p + at + 4 + n) != runtime::crc32c(p + at, 4 + std::size_t{n})) break;
    if (!decode_payload(p + at + 4, n, found, record)) break;
    if (sink) {
      sink(record);
    } else {
      out.records.push_back(std::move(record));
      record = {};
    }
    at += 8 + std::size_t{n};
  }
  out.valid_bytes = at;
  out.dropped_bytes = bytes.size() - at;
  return out;
}

BakeJournal::BakeJournal(std::string path, int fd)
    : path_(std::move(path)), fd_(fd), last_sync_ns_(now_ns()) {}

BakeJournal::~BakeJournal() {
  if (fd_ >= 0) ::close(fd_);
}

std::unique_ptr<BakeJournal> BakeJournal::create(const std::string& path,
                                                 const JournalIdentity& identity) {
  // Written beside the journal and renamed over it, so a journal on disk always has a whole
  // header, and a stale journal is replaced only once the new one is ready.
  const std::string temp = path + ".new";
  auto fail = [&](const std::string& what) {
    const std::string reason = errno_text();
    ::unlink(temp.c_str());
    return JournalWriteError(path + ": cannot " + what + " the journal: " + reason);
  };
  const int tfd = ::open(temp.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (tfd < 0) throw fail("create");
  const std::vector<unsigned char> header = encode_journal_header(identity);
  try {
    write_all(tfd, header.data(), header.size(), path);
  } catch (const JournalWriteError&) {
    ::close(tfd);
    ::unlink(temp.c_str());
    throw;
  }
  if (::fdatasync(tfd) != 0 || ::close(tfd) != 0) throw fail("write");
  if (::rename(temp.c_str(), path.c_str()) != 0) throw fail("create");
  const int fd = ::open(path.c_str(), O_WRONLY | O_APPEND | O_CLOEXEC);
  if (fd < 0) throw JournalWriteError(path + ": cannot open the journal: " + errno_text());
  return std::unique_ptr<BakeJournal>(new BakeJournal(path, fd));
}

std::unique_ptr<BakeJournal> BakeJournal::reopen(const std::string& path,
                                                 const JournalIdentity& identity,
                                                 JournalContents& contents,
                                                 const JournalRecordSink& sink) {
  const int fd = ::open(path.c_str(), O_RDWR | O_APPEND | O_CLOEXEC);
  if (fd < 0) throw JournalWriteError(path + ": cannot open the journal: " + errno_text());
  std::unique_ptr<BakeJournal> journal(new BakeJournal(path, fd));
  // Mapped, not read into memory: the journal of a city whose cells see thousands of objects
  // each takes gigabytes, and its records go on into the compact store one by one.
  struct stat st {};
  if (::fstat(fd, &st) != 0)
    throw JournalWriteError(path + ": cannot read the journal: " + errno_text());
  const auto size = static_cast<std::size_t>(st.st_size);
  void* mapped = size > 0 ? ::mmap(nullptr, size, PROT_READ, MAP_PRIVATE, fd, 0) : nullptr;
  if (mapped == MAP_FAILED)
    throw JournalWriteError(path + ": cannot read the journal: " + errno_text());
  struct Unmap {
    void* at;
    std::size_t size;
    ~Unmap() {
      if (at != nullptr) ::munmap(at, size);
    }
  } unmap{mapped, size};
  if (mapped != nullptr) ::madvise(mapped, size, MADV_SEQUENTIAL);
  contents =
      decode_journal({static_cast<const unsigned char*>(mapped), size}, identity, path, sink);
  // New records must follow the valid prefix directly, not a torn record.
  if (contents.dropped_bytes > 0 && ::ftruncate(fd, static_cast<off_t>(contents.valid_bytes)) != 0)
    throw JournalWriteError(path + ": cannot cut off the journal's torn end: " + errno_text());
  return journal;
}

void BakeJournal::append(const JournalRecord& record) {
  const std::lock_guard<std::mutex> lock(mutex_);
  buffer_.clear();
  encode_journal_record(record, buffer_);
  write_all(fd_, buffer_.data(), buffer_.size(), path_);
  const std::int64_t now = now_ns();
  if (now - last_sync_ns_ >= kSyncIntervalNs) {
    ::fdatasync(fd_);  // durability only; a failure here loses nothing a kill would not
    last_sync_ns_ = now;
  }
}

bool BakeJournal::remove() {
  const std::lock_guard<std::mutex> lock(mutex_);
  if (fd_ >= 0) ::close(fd_);
  fd_ = -1;
  return ::unlink(path_.c_str()) == 0;
}

}  // namespace urbanpvs::preprocess
