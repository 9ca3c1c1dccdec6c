// SPDX-License-Identifier: MIT
#include "urbanpvs/runtime/Status.hpp"

#include "urbanpvs/runtime/Format.hpp"

namespace urbanpvs::runtime {

const char* status_message(Status status) noexcept {
  switch (status) {
    case Status::kOk:
      return "ok";
    case Status::kBadMagic:
      return "not a .pvs file (bad magic)";
    case Status::kUnsupportedVersion:
      return "unsupported major version";
    case Status::kUnsupportedFeature:
      return "file requires a feature this reader does not support";
    case Status::kTruncated:
      return "file is truncated";
    case Status::kTrailingBytes:
      return "unexpected bytes after the end of the file";
    case Status::kHeaderChecksumMismatch:
      return "header checksum mismatch";
    case Status::kSectionChecksumMismatch:
      return "section checksum mismatch";
    case Status::kMalformedHeader:
      return "malformed header or section table";
    case Status::kMissingSection:
      return "required section missing";
    case Status::kMalformedSection:
      return "malformed section";
    case Status::kOutOfRange:
      return "index out of range";
    case Status::kBufferTooSmall:
      return "buffer too small";
    case Status::kOutOfMemory:
      return "out of memory";
    case Status::kIoError:
      return "cannot read the file";
    case Status::kNotGeographic:
      return "the file's input was not geographic";
    case Status::kInvalidArgument:
      return "invalid argument";
    case Status::kNotExpanded:
      return "the file was not opened with its PVSs expanded";
  }
  return "unknown status";
}

namespace format {

const char* section_name(std::uint32_t id) noexcept {
  switch (static_cast<SectionId>(id)) {
    case SectionId::kMetadata:
      return "metadata";
    case SectionId::kObjects:
      return "objects";
    case SectionId::kCells:
      return "cells";
    case SectionId::kGrid:
      return "grid";
    case SectionId::kPvs:
      return "pvs";
    case SectionId::kPayloads:
      return "payloads";
  }
  return "unknown";
}

}  // namespace format
}  // namespace urbanpvs::runtime
