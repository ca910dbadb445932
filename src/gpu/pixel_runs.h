// Runs of pixels that show the same patch: a hemicube image's neighbouring pixels mostly show
// one node (three in four continue a run on room402), so the reduction adds a run at once.
// The runs are found without a branch per pixel: each block of 64 pixels is compared with the
// pixels before it into a mask of run starts, whose set bits are then visited. Internal header.
#pragma once

#include <algorithm>
#include <bit>
#include <cstddef>
#include <cstdint>
#include <cstring>

namespace hemirad::gpu {

/// Calls run(first, count) for each maximal run of consecutive pixels of `rgba` (n RGBA float
/// pixels) with equal R, G and B (a patch ID, hemicube.h), in order.
template <class Run> void for_each_pixel_run(const float* rgba, std::size_t n, Run&& run) {
    std::size_t first = 0;
    for (std::size_t block = 0; block < n; block += 64) {
        const std::size_t end = std::min(n, block + 64);
        std::uint64_t starts = 0;
        for (std::size_t i = std::max<std::size_t>(block, 1); i < end; ++i) {
            // R and G as one 64-bit word, B as 32 bits: IDs are whole numbers, whose equal
            // values have equal bits (no -0, no NaN).
            std::uint64_t rg, rg_before;
            std::uint32_t b, b_before;
            std::memcpy(&rg, &rgba[4 * i], 8);
            std::memcpy(&rg_before, &rgba[4 * i - 4], 8);
            std::memcpy(&b, &rgba[4 * i + 2], 4);
            std::memcpy(&b_before, &rgba[4 * i - 2], 4);
            starts |= std::uint64_t((rg != rg_before) | (b != b_before)) << (i - block);
        }
        while (starts) {
            const std::size_t i = block + std::size_t(std::countr_zero(starts));
            starts &= starts - 1;
            run(first, i - first);
            first = i;
        }
    }
    if (n > 0) run(first, n - first);
}

/// Bit k set where the IDs a[k] and b[k] differ, for k < n (n <= 64): IDs are whole numbers,
/// whose equal values have equal bits (no -0, no NaN), compared as 32-bit words.
inline std::uint64_t unequal_ids(const float* a, const float* b, std::size_t n) {
    std::uint64_t mask = 0;
    for (std::size_t k = 0; k < n; ++k) {
        std::uint32_t x, y;
        std::memcpy(&x, a + k, 4);
        std::memcpy(&y, b + k, 4);
        mask |= std::uint64_t(x != y) << k;
    }
    return mask;
}

} // namespace hemirad::gpu
