// SPDX-License-Identifier: MIT
#pragma once

// What a PvsFile holds once validated: the bytes (owned or borrowed) and a view per section.

#include <cstddef>
#include <vector>

#include "Container.hpp"
#include "HugePages.hpp"
#include "LocateIndex.hpp"
#include "Sections.hpp"
#include "urbanpvs/runtime/GeodeticFrame.hpp"

namespace urbanpvs::runtime::detail {

struct PvsFileData {
  std::vector<std::byte> owned;  ///< open_owned: the caller's bytes, moved in
  LargeVector<std::byte> read;   ///< open_file: the file as read, on huge pages (HugePages.hpp)
  const unsigned char* data = nullptr;
  std::size_t size = 0;
  ContainerInfo container;
  MetadataView metadata;
  ObjectsView objects;
  CellTable cells;
  GridIndex grid;
  LocateIndex locate;  ///< the grid's lists as locate() reads them
  PvsView pvs;
  PayloadsView payloads;  ///< not present unless the file has a payloads section (2.1)
  PvsExpansion expanded;  ///< empty unless LoadOptions::expand_pvs
  std::size_t decode_buffer_size = 0;
  GeodeticFrame geodetic_frame{GeodeticOrigin{}};  ///< from the metadata, for geographic files
};

/// Validates `file.data[0, file.size)` and fills the views. Never throws: allocation failures
/// become kOutOfMemory.
Status load(PvsFileData& file, const LoadOptions& options, LoadError& error) noexcept;

}  // namespace urbanpvs::runtime::detail
