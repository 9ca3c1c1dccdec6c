// SPDX-License-Identifier: GPL-3.0-or-later
// The journal of urbanpvs-preprocess: records survive any cut of the file (a kill -9 at any
// byte), damaged tails are dropped, foreign journals are refused, and a reopened journal
// continues right after its valid prefix.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <thread>

#include "urbanpvs/preprocess/bake/BakeFingerprint.hpp"
#include "urbanpvs/preprocess/bake/BakeJournal.hpp"
#include "urbanpvs/preprocess/bake/BakeProgress.hpp"

namespace urbanpvs::preprocess {
namespace {

namespace fs = std::filesystem;

const JournalIdentity kIdentity{0x1234'5678'9abc'def0ull, 100, 5000};

JournalRecord record(std::uint32_t cell) {
  JournalRecord r;
  r.cell = cell;
  for (std::uint32_t k = 0; k < cell % 7; ++k) r.pvs.push_back(k * 613 + cell);
  r.counters.cells = 1;
  r.counters.maps = cell;
  r.counters.pixels_written = 1ull << 40 | cell;
  return r;
}

std::vector<unsigned char> journal_bytes(const std::vector<std::uint32_t>& cells) {
  std::vector<unsigned char> bytes = encode_journal_header(kIdentity);
  for (std::uint32_t c : cells) encode_journal_record(record(c), bytes);
  return bytes;
}

void expect_same(const JournalRecord& a, const JournalRecord& b) {
  EXPECT_EQ(a.cell, b.cell);
  EXPECT_EQ(a.pvs, b.pvs);
  EXPECT_EQ(a.counters.maps, b.counters.maps);
  EXPECT_EQ(a.counters.pixels_written, b.counters.pixels_written);
}

std::vector<unsigned char> read_file(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), {}};
}

fs::path temp_dir(const std::string& name) {
  const fs::path dir =
      fs::temp_directory_path() / ("urbanpvs_journal_" + name + "_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

TEST(BakeJournal, RoundTrip) {
  const std::vector<std::uint32_t> cells = {5, 0, 99, 42, 7};
  const JournalContents c = decode_journal(journal_bytes(cells), kIdentity, "j");
  ASSERT_EQ(c.records.size(), cells.size());
  for (std::size_t i = 0; i < cells.size(); ++i) expect_same(c.records[i], record(cells[i]));
  EXPECT_EQ(c.dropped_bytes, 0u);
}

// A kill can cut the file anywhere after the (atomically written) header.
TEST(BakeJournal, EveryCutKeepsTheWholeRecords) {
  const std::vector<std::uint32_t> cells = {1, 2, 3, 4, 5, 6};
  const std::vector<unsigned char> full = journal_bytes(cells);
  std::vector<std::size_t> ends;  // where each record ends
  std::vector<unsigned char> grow = encode_journal_header(kIdentity);
  for (std::uint32_t c : cells) encode_journal_record(record(c), grow), ends.push_back(grow.size());
  for (std::size_t cut = kJournalHeaderSize; cut <= full.size(); ++cut) {
    const JournalContents c = decode_journal({full.data(), cut}, kIdentity, "j");
    const auto whole = std::size_t(std::upper_bound(ends.begin(), ends.end(), cut) - ends.begin());
    ASSERT_EQ(c.records.size(), whole) << "cut at " << cut;
    EXPECT_EQ(c.valid_bytes + c.dropped_bytes, cut);
  }
}

TEST(BakeJournal, DamagedRecordEndsTheValidPrefix) {
  std::vector<unsigned char> bytes = encode_journal_header(kIdentity);
  encode_journal_record(record(3), bytes);
  const std::size_t second = bytes.size();
  encode_journal_record(record(4), bytes);
  encode_journal_record(record(5), bytes);
  for (std::size_t at = second; at < bytes.size(); at += 3) {
    std::vector<unsigned char> damaged = bytes;
    damaged[at] ^= 0x5a;
    const JournalContents c = decode_journal(damaged, kIdentity, "j");
    ASSERT_GE(c.records.size(), 1u);
    EXPECT_EQ(c.records[0].cell, 3u);
    EXPECT_LT(c.records.size(), 3u) << "damage at byte " << at << " went unnoticed";
  }
  // Zeros, as a power loss can leave them, are no record either.
  std::vector<unsigned char> zeros = encode_journal_header(kIdentity);
  zeros.resize(zeros.size() + 64, 0);
  EXPECT_EQ(decode_journal(zeros, kIdentity, "j").records.size(), 0u);
}

TEST(BakeJournal, RecordsOfAnotherSceneSizeAreRejected) {
  // Same fingerprint claimed, but a cell index beyond the cell count: not a valid record.
  std::vector<unsigned char> bytes = encode_journal_header({1, 10, 10});
  encode_journal_record(record(11), bytes);
  EXPECT_EQ(decode_journal(bytes, {1, 10, 10}, "j").records.size(), 0u);
}

TEST(BakeJournal, ForeignJournalsAreRefused) {
  const std::vector<unsigned char> bytes = journal_bytes({1, 2});
  JournalIdentity other = kIdentity;
  other.fingerprint ^= 1;
  try {
    decode_journal(bytes, other, "out.pvs.journal");
    FAIL() << "a journal of other settings was accepted";
  } catch (const JournalMismatch& e) {
    EXPECT_NE(std::string(e.what()).find("out.pvs.journal"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("other inputs or settings"), std::string::npos)
        << e.what();
  }
  other = kIdentity;
  other.cells += 1;
  EXPECT_THROW(decode_journal(bytes, other, "j"), JournalMismatch);
  const std::string text = "{\"not\": \"a journal\"}";
  EXPECT_THROW(decode_journal({reinterpret_cast<const unsigned char*>(text.data()), text.size()},
                              kIdentity, "j"),
               JournalMismatch);
  std::vector<unsigned char> damaged = bytes;
  damaged[20] ^= 1;  // inside the fingerprint: the header checksum catches it
  EXPECT_THROW(decode_journal(damaged, kIdentity, "j"), JournalMismatch);
  EXPECT_THROW(decode_journal({bytes.data(), 20}, kIdentity, "j"), JournalMismatch);
}

TEST(BakeJournal, FileAppendReopenAndRemove) {
  const fs::path dir = temp_dir("file");
  const std::string path = (dir / "out.pvs.journal").string();
  {
    auto journal = BakeJournal::create(path, kIdentity);
    std::vector<std::thread> threads;
    for (std::uint32_t t = 0; t < 4; ++t)
      threads.emplace_back([&, t] {
        for (std::uint32_t c = t; c < 40; c += 4) journal->append(record(c));
      });
    for (std::thread& th : threads) th.join();
  }
  EXPECT_FALSE(fs::exists(path + ".new"));
  // A torn record at the end, as a kill in the middle of a write() leaves it.
  std::vector<unsigned char> torn;
  encode_journal_record(record(77), torn);
  {
    std::ofstream out(path, std::ios::binary | std::ios::app);
    out.write(reinterpret_cast<const char*>(torn.data()), std::streamsize(torn.size() / 2));
  }
  JournalContents contents;
  {
    auto journal = BakeJournal::reopen(path, kIdentity, contents);
    ASSERT_EQ(contents.records.size(), 40u);
    EXPECT_EQ(contents.dropped_bytes, torn.size() / 2);
    journal->append(record(50));
  }
  const JournalContents after = decode_journal(read_file(path), kIdentity, path);
  ASSERT_EQ(after.records.size(), 41u);
  expect_same(after.records.back(), record(50));
  EXPECT_EQ(after.dropped_bytes, 0u);
  std::vector<bool> seen(40);
  for (std::size_t i = 0; i < 40; ++i) seen[after.records[i].cell] = true;
  EXPECT_EQ(std::count(seen.begin(), seen.end(), true), 40);
  // A sink takes the same records in the same order, and none is kept.
  std::vector<JournalRecord> sunk;
  const JournalContents through_sink = decode_journal(read_file(path), kIdentity, path,
                                                      [&](JournalRecord& r) { sunk.push_back(r); });
  EXPECT_TRUE(through_sink.records.empty());
  EXPECT_EQ(through_sink.valid_bytes, after.valid_bytes);
  ASSERT_EQ(sunk.size(), after.records.size());
  for (std::size_t i = 0; i < sunk.size(); ++i) expect_same(sunk[i], after.records[i]);

  auto journal = BakeJournal::reopen(path, kIdentity, contents);
  EXPECT_TRUE(journal->remove());
  EXPECT_FALSE(fs::exists(path));
  // create() replaces whatever was there.
  { std::ofstream(path) << "junk"; }
  BakeJournal::create(path, kIdentity);
  EXPECT_EQ(decode_journal(read_file(path), kIdentity, path).valid_bytes, kJournalHeaderSize);
  fs::remove_all(dir);
}

TEST(BakeJournal, UnwritableDirectoryIsAWriteError) {
  EXPECT_THROW(BakeJournal::create("/nonexistent-dir/x.pvs.journal", kIdentity), JournalWriteError);
}

TEST(BakeFingerprint, SettingsCellsAndObjectsAllCount) {
  const std::vector<std::pair<std::string, std::string>> s = {{"epsilon_m", "1"},
                                                              {"pixel_m", "1.3"}};
  const std::uint64_t base = bake_fingerprint(7, s, 10, 20);
  EXPECT_EQ(base, bake_fingerprint(7, s, 10, 20));
  EXPECT_NE(base, bake_fingerprint(8, s, 10, 20));
  EXPECT_NE(base, bake_fingerprint(7, s, 11, 20));
  EXPECT_NE(base, bake_fingerprint(7, s, 10, 21));
  auto changed = s;
  changed[1].second = "1.2";
  EXPECT_NE(base, bake_fingerprint(7, changed, 10, 20));
  // Strings are length-prefixed: moving a character across a boundary changes the hash.
  EXPECT_NE(bake_fingerprint(7, {{"ab", "c"}}, 1, 1), bake_fingerprint(7, {{"a", "bc"}}, 1, 1));
  EXPECT_EQ(hex64(0xabcull), "0x0000000000000abc");
}

TEST(BakeFingerprint, InputHashIsOfTheBytes) {
  const fs::path dir = temp_dir("hash");
  { std::ofstream(dir / "a") << "hello"; }
  { std::ofstream(dir / "b") << "hello"; }
  { std::ofstream(dir / "c") << "hellO"; }
  EXPECT_EQ(hash_input_files({(dir / "a").string()}), hash_input_files({(dir / "b").string()}));
  EXPECT_NE(hash_input_files({(dir / "a").string()}), hash_input_files({(dir / "c").string()}));
  EXPECT_NE(hash_input_files({(dir / "a").string()}),
            hash_input_files({(dir / "a").string(), (dir / "b").string()}));
  EXPECT_ANY_THROW(hash_input_files({(dir / "missing").string()}));
  fs::remove_all(dir);
}

TEST(BakeProgress, DescribesDoneRateAndEta) {
  EXPECT_EQ(BakeProgress::describe(250, 1000, 50.0),
            "250/1000 cells (25.0 %), 50.0 cells/s, ETA 0:00:15");
  EXPECT_EQ(BakeProgress::describe(0, 1000, 0.0),
            "0/1000 cells (0.0 %), 0.0 cells/s, ETA --:--:--");
  EXPECT_EQ(BakeProgress::describe(1000, 1000, 0.0),
            "1000/1000 cells (100.0 %), 0.0 cells/s, ETA 0:00:00");
}

}  // namespace
}  // namespace urbanpvs::preprocess
