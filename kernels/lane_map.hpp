#pragma once
// The lane map: one byte per metre of lane. 0 = free; otherwise 1 + the occupying vehicle's speed in
// quarter metres per second (floored, so a reader never overestimates a leader's speed). A vehicle marks
// every cell its body covers, from the cell of its rear bumper to the cell of its front bumper, continuing
// back over the lanes it came from when its body spans a lane boundary.
#include <math.h>
#include <stdint.h>
#include <string.h>
#if defined(__SSE2__) && !defined(__CUDA_ARCH__)
#include <emmintrin.h>
#endif

#include "kernels/hd.hpp"
#include "kernels/step_view.hpp"

namespace lpsim {

#ifndef __CUDA_ARCH__
static_assert(__BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__,
              "the lane-map scans read cells as little-endian words (as CUDA devices are)");
#endif

/// Bytes a host lane map must have readable after its last cell (zeros, never written): first_occupied
/// reads 64 cells from the start of a short range without looking at where the range ends.
constexpr uint32_t kLaneMapPadding = 64;

LPSIM_HD uint8_t encode_cell_speed(float v) {
  const float q = v * 4.0f;  // truncating a value clamped to [0, 254] is its floor
  return static_cast<uint8_t>(1 + (q < 0.0f ? 0 : (q > 254.0f ? 254 : static_cast<int>(q))));
}

LPSIM_HD float decode_cell_speed(uint8_t cell) { return static_cast<float>(cell - 1) * 0.25f; }

/// decode_cell_speed(encode_cell_speed(v)) == 0: the lane map shows a vehicle at speed v as standing (the
/// encoding floors v*4, and scaling by 4 is exact).
LPSIM_HD bool encodes_as_standing(float v) { return v * 4.0f < 1.0f; }

LPSIM_HD uint32_t lane_cells(const NetView& net, int32_t lane) { return net.lane_num_cells[lane]; }

/// Longest lane, in cells, the network builder accepts: with a look-ahead clamped to kMaxCellSpan, cell
/// arithmetic (front cell + 1 + reach) stays within int32.
constexpr uint32_t kMaxLaneCells = 1u << 30;
constexpr int32_t kMaxCellSpan = 1 << 29;

/// Whole cells in a non-negative distance of `metres` (floored), at most kMaxCellSpan: absurd vType
/// values or lane speeds make look-ahead distances that no integer holds (NaN gives the maximum too).
/// Any distance a network can hold converts exactly as a plain cast would.
LPSIM_HD int32_t metres_as_cells(float metres) {
  return metres < static_cast<float>(kMaxCellSpan) ? static_cast<int32_t>(metres) : kMaxCellSpan;
}

/// Cell index on a lane of a position (m from the lane start), clamped to the lane.
LPSIM_HD uint32_t cell_of(const NetView& net, int32_t lane, float pos) {
  const uint32_t n = lane_cells(net, lane);
  if (pos <= 0.0f) return 0;
  const uint32_t c = static_cast<uint32_t>(pos);
  return c >= n ? n - 1 : c;
}

#ifndef __CUDA_ARCH__
// Stores `n` (>= 1) copies of v from p with at most two (overlapping) word stores per size class instead of
// a store per cell: footprints are a few cells long, and a byte loop's exit is hard to predict. Only the
// cells of [p, p + n) are written, so vehicles filling neighbouring cells on other threads are unaffected.
inline void fill_bytes(uint8_t* p, uint32_t n, uint8_t v) {
  const uint64_t w = 0x0101010101010101ull * v;
  if (n >= 8) {
    for (; n > 16; n -= 8, p += 8) memcpy(p, &w, 8);
    memcpy(p, &w, 8);
    memcpy(p + n - 8, &w, 8);
  } else if (n >= 4) {
    memcpy(p, &w, 4);
    memcpy(p + n - 4, &w, 4);
  } else if (n >= 2) {
    memcpy(p, &w, 2);
    memcpy(p + n - 2, &w, 2);
  } else {
    *p = v;
  }
}
#endif

LPSIM_HD void fill_cells(uint8_t* map, const NetView& net, int32_t lane, uint32_t first, uint32_t last,
                         uint8_t v) {
  const uint32_t base = net.lane_cell_begin[lane];
  if (last < first) return;
#ifdef __CUDA_ARCH__
  for (uint32_t c = first; c <= last; ++c) map[base + c] = v;
#else
  fill_bytes(map + base + first, last - first + 1, v);
#endif
}

/// Calls cells(lane, first, last) for each lane a vehicle `length` metres long covers with footprint `fp`:
/// the cells [first, last] of that lane it covers.
#if defined(__CUDACC__)
#pragma nv_exec_check_disable  // host code (a part's border exchanges) calls it with host lambdas
#endif
template <class Cells>
LPSIM_HD_INLINED void for_each_footprint_piece(const NetView& net, const Footprint& fp, float length,
                                               Cells cells) {
  if (fp.lane < 0) return;
  const float rear = fp.pos - length;
  cells(fp.lane, cell_of(net, fp.lane, rear), cell_of(net, fp.lane, fp.pos));
  float remaining = -rear;  // body length still to place behind this lane's start
  const int32_t behind[2] = {fp.prev, fp.prev2};
  for (int k = 0; k < 2 && remaining > 0.0f && behind[k] >= 0; ++k) {
    const int32_t l = behind[k];
    const float len = net.lane_length[l];
    cells(l, cell_of(net, l, len - remaining), lane_cells(net, l) - 1);
    remaining -= len;
  }
}

/// Writes `value` into every cell of a footprint of a vehicle `length` metres long.
LPSIM_HD_INLINED void apply_footprint(uint8_t* map, const NetView& net, const Footprint& fp, float length,
                                      uint8_t value) {
  for_each_footprint_piece(net, fp, length, [&](int32_t lane, uint32_t first, uint32_t last) {
    fill_cells(map, net, lane, first, last, value);
  });
}

/// First occupied cell in [first, last] of a lane, or -1. On the host `map` needs kLaneMapPadding readable
/// bytes after its last cell.
LPSIM_HD_INLINED int32_t first_occupied(const uint8_t* map, const NetView& net, int32_t lane, int32_t first,
                                        int32_t last) {
  const uint8_t* cells = map + net.lane_cell_begin[lane];
  int32_t c = first;
#if defined(__SSE2__) && !defined(__CUDA_ARCH__)
  // Most scans (a leader within a look-ahead, the rest of a short lane) span at most 64 cells: one mask of
  // the 64 cells from `first`, cut to the range, without a loop whose exit depends on where the first
  // vehicle stands (a mispredicted branch on nearly every call).
  if (last - first < 64) {
    const int32_t n = last - first + 1 > 0 ? last - first + 1 : 0;  // cells in the range, 0 to 64
    const uint64_t range = n == 64 ? ~uint64_t{0} : (uint64_t{1} << n) - 1;
    const __m128i zero = _mm_setzero_si128();
    uint64_t free_cells = 0;
    for (int k = 0; k < 4; ++k) {
      const __m128i v = _mm_loadu_si128(reinterpret_cast<const __m128i*>(cells + first + 16 * k));
      free_cells |= static_cast<uint64_t>(static_cast<uint32_t>(_mm_movemask_epi8(_mm_cmpeq_epi8(v, zero))))
                    << (16 * k);
    }
    const uint64_t occupied = ~free_cells & range;
    return occupied != 0 ? first + static_cast<int32_t>(__builtin_ctzll(occupied)) : -1;
  }
#endif
  // Eight cells per test: look-ahead scans mostly cross empty cells. Little-endian (host and device), so
  // the lowest set byte of a word is the first cell in lane order.
#ifdef __CUDA_ARCH__
  // The device loads only aligned words (an unaligned one would be split into byte loads): single cells up
  // to the first word boundary, then whole words.
  for (; c <= last && (reinterpret_cast<uintptr_t>(cells + c) & 7u) != 0; ++c)
    if (cells[c] != 0) return c;
  for (; c + 7 <= last; c += 8) {
    const uint64_t word = *reinterpret_cast<const uint64_t*>(cells + c);
    if (word != 0) return c + ((__ffsll(static_cast<long long>(word)) - 1) >> 3);
  }
#else
  for (; c + 7 <= last; c += 8) {
    uint64_t word;
    memcpy(&word, cells + c, sizeof word);
    if (word != 0) return c + static_cast<int32_t>(__builtin_ctzll(word) >> 3);
  }
  // Fewer than 8 cells left: the word ending at `last` (inside the lane when it starts at cell 0 or later)
  // with the cells before c shifted out.
  if (c <= last && last >= 7) {
    uint64_t word;
    memcpy(&word, cells + last - 7, sizeof word);
    word >>= 8 * (c - (last - 7));
    return word != 0 ? c + static_cast<int32_t>(__builtin_ctzll(word) >> 3) : -1;
  }
#endif
  for (; c <= last; ++c)
    if (cells[c] != 0) return c;
  return -1;
}

/// Last occupied cell in [first, last] of a lane (scanning down from last), or -1.
LPSIM_HD int32_t last_occupied(const uint8_t* map, const NetView& net, int32_t lane, int32_t first,
                               int32_t last) {
  const uint8_t* cells = map + net.lane_cell_begin[lane];
  int32_t c = last;
  // The word of cells [c-7, c]: its highest set byte is the last occupied cell.
#ifdef __CUDA_ARCH__
  for (; c >= first && (reinterpret_cast<uintptr_t>(cells + c + 1) & 7u) != 0; --c)
    if (cells[c] != 0) return c;
  for (; c - 7 >= first; c -= 8) {
    const uint64_t word = *reinterpret_cast<const uint64_t*>(cells + c - 7);
    if (word != 0) return c - 7 + ((63 - __clzll(static_cast<long long>(word))) >> 3);
  }
#else
  for (; c - 7 >= first; c -= 8) {
    uint64_t word;
    memcpy(&word, cells + c - 7, sizeof word);
    if (word != 0) return c - 7 + static_cast<int32_t>((63 - __builtin_clzll(word)) >> 3);
  }
#endif
  for (; c >= first; --c)
    if (cells[c] != 0) return c;
  return -1;
}

}  // namespace lpsim
