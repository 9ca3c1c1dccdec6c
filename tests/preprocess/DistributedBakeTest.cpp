// SPDX-License-Identifier: GPL-3.0-or-later
// How rank 0 cuts the cells into chunks (DistributedBake.hpp): every cell handed out once, no
// chunk larger than a few seconds of work, the last chunks small so that ranks finish together.
// The MPI protocol itself runs end to end in preprocess_mpi_bake (mpi_bake_test.sh).
#include <gtest/gtest.h>

#include "urbanpvs/preprocess/bake/DistributedBake.hpp"

using namespace urbanpvs::preprocess;

TEST(DistributedBake, ChunksCoverEveryCellOnceAndShrinkTowardsTheEnd) {
  for (int ranks : {2, 3, 16}) {
    for (unsigned threads : {1u, 4u}) {
      SCOPED_TRACE(std::to_string(ranks) + " ranks x " + std::to_string(threads) + " threads");
      const std::size_t cells = 100000;
      std::size_t remaining = cells, chunks = 0, last = 0;
      while (remaining > 0) {
        const std::size_t n = chunk_size(remaining, ranks, threads);
        ASSERT_GE(n, 1u);
        ASSERT_LE(n, remaining);
        ASSERT_LE(n, 32u * threads);
        // Never more than half a fair share of what is left: no rank is left with a long tail.
        if (remaining >= 2u * std::size_t(ranks)) {
          ASSERT_LE(n, remaining / (2 * ranks));
        }
        remaining -= n;
        last = n;
        ++chunks;
      }
      EXPECT_EQ(last, 1u);
      EXPECT_GE(chunks, cells / (32 * threads));
    }
  }
  EXPECT_EQ(chunk_size(0, 3, 1), 0u);
  EXPECT_EQ(chunk_size(5, 3, 1), 1u);
}
