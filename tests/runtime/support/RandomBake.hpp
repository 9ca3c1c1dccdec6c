// SPDX-License-Identifier: MIT
#pragma once

// Random bakes for round-trip and point-location tests: a jittered triangle mesh with correct
// neighbour links, and PVSs with controllable density and neighbour coherence.

#include <cstdint>

#include "urbanpvs/runtime/PvsWriter.hpp"

namespace urbanpvs::test {

struct RandomBakeOptions {
  std::uint32_t nx = 4;          ///< mesh squares along x (two triangles each)
  std::uint32_t ny = 4;          ///< mesh squares along y
  double square = 10;            ///< square size (m)
  double jitter = 0.3;           ///< vertex jitter as a fraction of the square
  std::uint32_t objects = 60;    ///< object count
  std::uint32_t min_object = 0;  ///< PVS ids are drawn from [min_object, objects)
  double density = 0.2;          ///< expected fraction of objects visible per cell
  double coherence = 0.9;        ///< fraction of a parent cell's PVS a cell keeps
  bool neighbours = true;        ///< fill neighbour links (else all kNoCell)
  bool properties = true;        ///< add metadata properties
  bool payloads = false;         ///< give most objects a payload (key "mesh"): a 2.1 file
};

/// Deterministic for a given seed and options.
runtime::PvsBake random_mesh_bake(std::uint64_t seed, const RandomBakeOptions& options);

/// Cells that overlap each other at random (a "triangle soup"), for point-location tests.
runtime::PvsBake random_soup_bake(std::uint64_t seed, std::uint32_t cells, double extent);

}  // namespace urbanpvs::test
