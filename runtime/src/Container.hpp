// SPDX-License-Identifier: MIT
#pragma once

// The container around the sections: fixed header, section table, checksums (FORMAT.md,
// "Header" and "Section table"). Knows nothing about what the sections contain.

#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

#include "urbanpvs/runtime/PvsFile.hpp"

namespace urbanpvs::runtime::detail {

struct ContainerInfo {
  std::uint16_t major = 0;
  std::uint16_t minor = 0;
  std::uint32_t required_features = 0;
  std::vector<SectionInfo> sections;  ///< in file order (increasing id, contiguous)
};

/// Checks magic, version, sizes, header checksum, the section table (every section inside the
/// file, sections contiguous from the end of the header to the end of the file, ids strictly
/// increasing) and, when `verify_checksums`, every section's CRC32C. Allocates the table
/// (bounded by the buffer size); may throw std::bad_alloc.
Status read_container(const unsigned char* data, std::size_t size, bool verify_checksums,
                      ContainerInfo& info, LoadError& error);

/// A section to write: id and bytes. Ids must be strictly increasing.
using SectionBytes = std::pair<std::uint32_t, std::vector<unsigned char>>;

/// Header + table + sections, version `major`.`minor` with `required_features` set, checksums
/// filled in.
std::vector<std::byte> write_container(const std::vector<SectionBytes>& sections,
                                       std::uint16_t major, std::uint16_t minor,
                                       std::uint32_t required_features);

}  // namespace urbanpvs::runtime::detail
