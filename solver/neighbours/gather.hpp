// Neighbour gathering: the one file of the solver with SIMD intrinsics.
//
// gather_neighbours() tests a contiguous range of candidate particles against a particle's
// kernel support and appends the hits to a list whose entries carry the wall flag in their top
// bit; fluid_within() does the same for a point's fluid candidates (mDBC's ghost nodes). A
// selection policy says which b a particle a may see: it is the boundary model's say in the pair
// loop (bc/dbc uses WallsSeeFluid) and one of the loop's three compile-time switches (kernel,
// viscosity, selection).
#pragma once

#include <immintrin.h>

#include <cstddef>
#include <cstdint>

#include "solver/state/types.hpp"

namespace swell {

// Neighbour lists are padded to a multiple of kPairLanes entries (2 kPairLanes = 16 floats for
// a float evaluator) so the evaluator's SIMD loop has no scalar remainder: 8 is the AVX-512
// width in doubles (what -march=native builds use
// here, -fopt-info-vec: "loop vectorized using 64 byte vectors") and a multiple of the AVX2
// width (4). The packing pass itself writes 8 entries at a time (AVX-512) or one (scalar).
inline constexpr std::uint32_t kPairLanes = 8;
// Neighbour-list entries carry the wall flag in their top bit (b | kWallBit for a wall b).
inline constexpr std::uint32_t kWallBit = 0x80000000u;

// Dynamic boundary conditions (Crespo et al. 2007): a fluid particle sees every particle in
// reach; a wall particle sees fluid only (wall-wall pairs do nothing) and gets continuity only,
// no density diffusion. Cells with no fluid within reach are skipped: their walls get zero
// rates.
struct WallsSeeFluid {
  static constexpr bool kWallSeesWalls = false;
  static constexpr bool kWallsDiffuse = false;
  static constexpr bool kSkipDryCells = true;
};

#if defined(__AVX512F__) && defined(__AVX512VL__) && defined(__AVX512BW__)
// The coordinates of the `count` (1..8) particles at p (D packed doubles each), split by axis:
// xb[d] lane l is particle l's coordinate d (lanes past count zero). Masked loads of the
// D x count consecutive doubles, then two-source permutes.
template <int D>
inline void load_axes8(const double* p, std::uint32_t count, __m512d xb[D]) {
  static_assert(D == 2 || D == 3, "the AVX-512 path handles 2D and 3D");
  const unsigned nd = count * D;  // doubles to read
  const auto part = [nd](unsigned from) {
    return nd >= from + 8 ? __mmask8(0xFF)
           : nd > from    ? __mmask8((1u << (nd - from)) - 1u)
                          : __mmask8(0);
  };
  const __m512d c0 = _mm512_maskz_loadu_pd(part(0), p), c1 = _mm512_maskz_loadu_pd(part(8), p + 8);
  if constexpr (D == 2) {
    xb[0] = _mm512_permutex2var_pd(c0, _mm512_setr_epi64(0, 2, 4, 6, 8, 10, 12, 14), c1);
    xb[1] = _mm512_permutex2var_pd(c0, _mm512_setr_epi64(1, 3, 5, 7, 9, 11, 13, 15), c1);
  } else {
    const __m512d c2 = _mm512_maskz_loadu_pd(part(16), p + 16);
    const __m512d tx = _mm512_permutex2var_pd(c0, _mm512_setr_epi64(0, 3, 6, 9, 12, 15, 0, 0), c1);
    const __m512d ty = _mm512_permutex2var_pd(c0, _mm512_setr_epi64(1, 4, 7, 10, 13, 0, 0, 0), c1);
    const __m512d tz = _mm512_permutex2var_pd(c0, _mm512_setr_epi64(2, 5, 8, 11, 14, 0, 0, 0), c1);
    xb[0] = _mm512_permutex2var_pd(tx, _mm512_setr_epi64(0, 1, 2, 3, 4, 5, 10, 13), c2);
    xb[1] = _mm512_permutex2var_pd(ty, _mm512_setr_epi64(0, 1, 2, 3, 4, 8, 11, 14), c2);
    xb[2] = _mm512_permutex2var_pd(tz, _mm512_setr_epi64(0, 1, 2, 3, 4, 9, 12, 15), c2);
  }
}
#endif

// Appends to nb[k...] the entries of the particles b in [b0, b1) within the kernel support of
// xa (b != a; which b per the selection policy) and returns the new count. P holds the
// positions (D doubles a particle), role the roles. nb must have room for (b1 - b0) + 8 more
// entries past k (16 for the float form below). The AVX-512 path tests 8 candidates at once and
// packs the hits with a register compress; the scalar path is the same test.
template <int D, class Select>
inline std::uint32_t gather_neighbours(const double* P, const Role* role, const double* xa,
                                       bool fluid_a, double support2, std::uint32_t b0,
                                       std::uint32_t b1, std::uint32_t* nb, std::uint32_t k) {
  std::uint32_t b = b0;
#if defined(__AVX512F__) && defined(__AVX512VL__) && defined(__AVX512BW__)
  static_assert(D == 2 || D == 3, "the AVX-512 path handles 2D and 3D");
  const __m512d s2 = _mm512_set1_pd(support2), tiny = _mm512_set1_pd(1e-18),
                zero = _mm512_setzero_pd();
  __m512d xav[D];
  for (int d = 0; d < D; ++d) xav[d] = _mm512_set1_pd(xa[d]);
  const __m256i lane = _mm256_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7);
  const __m256i wall_bit = _mm256_set1_epi32(static_cast<int>(kWallBit));
  const __m128i fluid_role = _mm_set1_epi8(static_cast<char>(Role::Fluid));
  for (; b < b1; b += 8) {
    const std::uint32_t left = b1 - b;
    const __mmask8 valid = left >= 8 ? __mmask8(0xFF) : __mmask8((1u << left) - 1u);
    __m512d xb[D];
    load_axes8<D>(P + static_cast<std::size_t>(b) * D, left >= 8 ? 8u : left, xb);
    __m512d r2 = zero;
    for (int d = 0; d < D; ++d) {
      const __m512d dx = _mm512_sub_pd(xav[d], xb[d]);
      r2 = _mm512_fmadd_pd(dx, dx, r2);
    }
    const __m128i kb = _mm_maskz_loadu_epi8(valid, role + b);
    const __mmask8 fluid_b = static_cast<__mmask8>(_mm_cmpeq_epi8_mask(kb, fluid_role));
    __mmask8 m =
        valid & _mm512_cmp_pd_mask(r2, s2, _CMP_LT_OQ) & _mm512_cmp_pd_mask(r2, tiny, _CMP_GT_OQ);
    if constexpr (!Select::kWallSeesWalls) {
      if (!fluid_a) m &= fluid_b;
    }
    __m256i idx = _mm256_add_epi32(_mm256_set1_epi32(static_cast<int>(b)), lane);
    idx = _mm256_mask_or_epi32(idx, static_cast<__mmask8>(~fluid_b), idx, wall_bit);
    _mm256_storeu_si256(reinterpret_cast<__m256i*>(nb + k), _mm256_maskz_compress_epi32(m, idx));
    k += static_cast<std::uint32_t>(__builtin_popcount(m));
  }
#else
  for (; b < b1; ++b) {
    double r2 = 0.0;
    for (int d = 0; d < D; ++d) {
      const double dx = xa[d] - P[b * D + d];
      r2 += dx * dx;
    }
    const bool fluid_b = role[b] == Role::Fluid;
    nb[k] = b | (fluid_b ? 0u : kWallBit);
    k += (r2 < support2) & (r2 > 1e-18) & (Select::kWallSeesWalls | fluid_a | fluid_b);
  }
#endif
  return k;
}

// Appends to out[n...] the fluid particles b of [b0, b1) with |x - x_b|^2 < s2 (P: D packed
// doubles a particle) and returns the new count; out needs room for b1 - b0 + 8 more entries.
// The candidates of a point that is no particle (mDBC's ghost nodes, bc/mdbc.hpp); the caller
// passes s2 with a margin and decides membership itself. AVX-512: 8 candidates at once, the
// hits packed with a register compress.
template <int D>
inline int fluid_within(const double* P, const Role* role, const double* x, double s2,
                        std::uint32_t b0, std::uint32_t b1, std::uint32_t* out, int n) {
  std::uint32_t b = b0;
#if defined(__AVX512F__) && defined(__AVX512VL__) && defined(__AVX512BW__)
  const __m512d s2v = _mm512_set1_pd(s2);
  __m512d xv[D];
  for (int d = 0; d < D; ++d) xv[d] = _mm512_set1_pd(x[d]);
  const __m256i lane = _mm256_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7);
  const __m128i fluid_role = _mm_set1_epi8(static_cast<char>(Role::Fluid));
  for (; b < b1; b += 8) {
    const std::uint32_t left = b1 - b;
    const __mmask8 valid = left >= 8 ? __mmask8(0xFF) : __mmask8((1u << left) - 1u);
    __m512d xb[D];
    load_axes8<D>(P + static_cast<std::size_t>(b) * D, left >= 8 ? 8u : left, xb);
    __m512d r2 = _mm512_setzero_pd();
    for (int d = 0; d < D; ++d) {
      const __m512d dx = _mm512_sub_pd(xv[d], xb[d]);
      r2 = _mm512_fmadd_pd(dx, dx, r2);
    }
    const __m128i kb = _mm_maskz_loadu_epi8(valid, role + b);
    const __mmask8 m = valid & static_cast<__mmask8>(_mm_cmpeq_epi8_mask(kb, fluid_role)) &
                       _mm512_cmp_pd_mask(r2, s2v, _CMP_LT_OQ);
    const __m256i idx = _mm256_add_epi32(_mm256_set1_epi32(static_cast<int>(b)), lane);
    _mm256_storeu_si256(reinterpret_cast<__m256i*>(out + n), _mm256_maskz_compress_epi32(m, idx));
    n += __builtin_popcount(m);
  }
#else
  for (; b < b1; ++b) {
    if (role[b] != Role::Fluid) continue;
    double r2 = 0.0;
    for (int d = 0; d < D; ++d) {
      const double dx = x[d] - P[static_cast<std::size_t>(b) * D + d];
      r2 += dx * dx;
    }
    if (r2 < s2) out[n++] = b;
  }
#endif
  return n;
}

// The float form of the test (issue #16: 16 candidates per AVX-512 instruction instead of 8),
// on a float copy of the positions taken relative to a fixed origin (the pair driver's
// NeighbourLists::pos). support2 must hold a margin for the copy's rounding: the test may then
// admit a few pairs just beyond the support, never drop one inside it, and the evaluator
// gives those pairs exactly zero (its own test on r_ab from the double positions decides).
// Every b with r2 < support2 in float is admitted, the particle itself and particles whose
// float copies coincide with it included (no lower cut: such a pair may be a real neighbour a
// few micrometres away far from the origin): the evaluator gives the self pair exactly zero,
// as it does the padding.
template <int D, class Select>
inline std::uint32_t gather_neighbours(const float* P, const Role* role, const float* xa,
                                       bool fluid_a, float support2, std::uint32_t b0,
                                       std::uint32_t b1, std::uint32_t* nb, std::uint32_t k) {
  std::uint32_t b = b0;
#if defined(__AVX512F__) && defined(__AVX512VL__) && defined(__AVX512BW__)
  static_assert(D == 2 || D == 3, "the AVX-512 path handles 2D and 3D");
  const __m512 s2 = _mm512_set1_ps(support2), zero = _mm512_setzero_ps();
  __m512 xav[D];
  for (int d = 0; d < D; ++d) xav[d] = _mm512_set1_ps(xa[d]);
  const __m512i lane = _mm512_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15);
  const __m512i wall_bit = _mm512_set1_epi32(static_cast<int>(kWallBit));
  const __m128i fluid_role = _mm_set1_epi8(static_cast<char>(Role::Fluid));
  for (; b < b1; b += 16) {
    const std::uint32_t left = b1 - b;
    const __mmask16 valid = left >= 16 ? __mmask16(0xFFFF) : __mmask16((1u << left) - 1u);
    // The 16 candidates' coordinates are D x 16 consecutive floats: load them (masked at the
    // end of the range) and split them by axis with two-source permutes.
    const float* p = P + static_cast<std::size_t>(b) * D;
    const unsigned nf = (left >= 16 ? 16u : left) * D;  // floats to read
    auto part = [nf](unsigned from) {
      return nf >= from + 16 ? __mmask16(0xFFFF)
             : nf > from     ? __mmask16((1u << (nf - from)) - 1u)
                             : __mmask16(0);
    };
    __m512 xb[D];
    const __m512 c0 = _mm512_maskz_loadu_ps(part(0), p),
                 c1 = _mm512_maskz_loadu_ps(part(16), p + 16);
    if constexpr (D == 2) {
      xb[0] = _mm512_permutex2var_ps(
          c0, _mm512_setr_epi32(0, 2, 4, 6, 8, 10, 12, 14, 16, 18, 20, 22, 24, 26, 28, 30), c1);
      xb[1] = _mm512_permutex2var_ps(
          c0, _mm512_setr_epi32(1, 3, 5, 7, 9, 11, 13, 15, 17, 19, 21, 23, 25, 27, 29, 31), c1);
    } else {
      // x: floats 0, 3, .., 45 of the 48; the first 11 (y: 11, z: 10) lie in c0 and c1.
      const __m512 c2 = _mm512_maskz_loadu_ps(part(32), p + 32);
      const __m512 tx = _mm512_permutex2var_ps(
          c0, _mm512_setr_epi32(0, 3, 6, 9, 12, 15, 18, 21, 24, 27, 30, 0, 0, 0, 0, 0), c1);
      const __m512 ty = _mm512_permutex2var_ps(
          c0, _mm512_setr_epi32(1, 4, 7, 10, 13, 16, 19, 22, 25, 28, 31, 0, 0, 0, 0, 0), c1);
      const __m512 tz = _mm512_permutex2var_ps(
          c0, _mm512_setr_epi32(2, 5, 8, 11, 14, 17, 20, 23, 26, 29, 0, 0, 0, 0, 0, 0), c1);
      xb[0] = _mm512_permutex2var_ps(
          tx, _mm512_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 17, 20, 23, 26, 29), c2);
      xb[1] = _mm512_permutex2var_ps(
          ty, _mm512_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 18, 21, 24, 27, 30), c2);
      xb[2] = _mm512_permutex2var_ps(
          tz, _mm512_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 16, 19, 22, 25, 28, 31), c2);
    }
    __m512 r2 = zero;
    for (int d = 0; d < D; ++d) {
      const __m512 dx = _mm512_sub_ps(xav[d], xb[d]);
      r2 = _mm512_fmadd_ps(dx, dx, r2);
    }
    const __m128i kb = _mm_maskz_loadu_epi8(valid, role + b);
    const __mmask16 fluid_b = _mm_cmpeq_epi8_mask(kb, fluid_role);
    __mmask16 m = valid & _mm512_cmp_ps_mask(r2, s2, _CMP_LT_OQ);
    if constexpr (!Select::kWallSeesWalls) {
      if (!fluid_a) m &= fluid_b;
    }
    __m512i idx = _mm512_add_epi32(_mm512_set1_epi32(static_cast<int>(b)), lane);
    idx = _mm512_mask_or_epi32(idx, static_cast<__mmask16>(~fluid_b), idx, wall_bit);
    _mm512_storeu_si512(nb + k, _mm512_maskz_compress_epi32(m, idx));
    k += static_cast<std::uint32_t>(__builtin_popcount(m));
  }
#else
  for (; b < b1; ++b) {
    float r2 = 0.0f;
    for (int d = 0; d < D; ++d) {
      const float dx = xa[d] - P[b * D + d];
      r2 += dx * dx;
    }
    const bool fluid_b = role[b] == Role::Fluid;
    nb[k] = b | (fluid_b ? 0u : kWallBit);
    k += (r2 < support2) & (Select::kWallSeesWalls | fluid_a | fluid_b);
  }
#endif
  return k;
}

#if defined(__AVX512F__)
// A 4 x 4 transpose of floats within each 128-bit block: out[i]'s element j of block k is
// in[j]'s element i of block k.
inline void transpose_blocks4(const __m512 in[4], __m512 out[4]) {
  const __m512d t0 = _mm512_castps_pd(_mm512_unpacklo_ps(in[0], in[1]));
  const __m512d t1 = _mm512_castps_pd(_mm512_unpackhi_ps(in[0], in[1]));
  const __m512d t2 = _mm512_castps_pd(_mm512_unpacklo_ps(in[2], in[3]));
  const __m512d t3 = _mm512_castps_pd(_mm512_unpackhi_ps(in[2], in[3]));
  out[0] = _mm512_castpd_ps(_mm512_unpacklo_pd(t0, t2));
  out[1] = _mm512_castpd_ps(_mm512_unpackhi_pd(t0, t2));
  out[2] = _mm512_castpd_ps(_mm512_unpacklo_pd(t1, t3));
  out[3] = _mm512_castpd_ps(_mm512_unpackhi_pd(t1, t3));
}

// 16 rows of 4 floats (row(j): neighbour j's, as a __m128) into 4 vectors of 16 lanes: out[i]
// lane j = row j's element i.
template <class Row>
inline void rows_to_lanes16(Row row, __m512 out[4]) {
  __m512 z[4];  // z_j's block k holds row 4k + j
  for (int j = 0; j < 4; ++j) {
    z[j] = _mm512_castps128_ps512(row(j));
    z[j] = _mm512_insertf32x4(z[j], row(4 + j), 1);
    z[j] = _mm512_insertf32x4(z[j], row(8 + j), 2);
    z[j] = _mm512_insertf32x4(z[j], row(12 + j), 3);
  }
  transpose_blocks4(z, out);
}
#endif

// The four sums of a float pair loop, each held as 16 lane partial sums (lane l has summed the
// pairs j = l, l + 16, ...), added up lane by lane in one fixed order: out[q] = ((0 + q[0]) +
// q[1]) + ... + q[15]. That is the order in which GCC finishes an `omp simd reduction(+)` of
// 16 float lanes, so the results are bit for bit those of the reduction it replaces; done as
// one 4-wide add per lane after a 4 x 4 transpose in each 128-bit block (8 shuffles, 16
// adds) instead of GCC's ~150 scalar stack loads and inserts (~12 % of the 2D pair loop's
// time). Arrays: 16 floats each, 64-byte aligned.
inline void sum_lanes_in_order(const float* q0, const float* q1, const float* q2, const float* q3,
                               float out[4]) {
#if defined(__AVX512F__)
  const __m512 in[4] = {_mm512_load_ps(q0), _mm512_load_ps(q1), _mm512_load_ps(q2),
                        _mm512_load_ps(q3)};
  // u_i, block k: (q0, q1, q2, q3) of lane 4k + i.
  __m512 u[4];
  transpose_blocks4(in, u);
  const __m512 u0 = u[0], u1 = u[1], u2 = u[2], u3 = u[3];
  __m128 acc = _mm_setzero_ps();
  acc = _mm_add_ps(acc, _mm512_castps512_ps128(u0));
  acc = _mm_add_ps(acc, _mm512_castps512_ps128(u1));
  acc = _mm_add_ps(acc, _mm512_castps512_ps128(u2));
  acc = _mm_add_ps(acc, _mm512_castps512_ps128(u3));
  acc = _mm_add_ps(acc, _mm512_extractf32x4_ps(u0, 1));
  acc = _mm_add_ps(acc, _mm512_extractf32x4_ps(u1, 1));
  acc = _mm_add_ps(acc, _mm512_extractf32x4_ps(u2, 1));
  acc = _mm_add_ps(acc, _mm512_extractf32x4_ps(u3, 1));
  acc = _mm_add_ps(acc, _mm512_extractf32x4_ps(u0, 2));
  acc = _mm_add_ps(acc, _mm512_extractf32x4_ps(u1, 2));
  acc = _mm_add_ps(acc, _mm512_extractf32x4_ps(u2, 2));
  acc = _mm_add_ps(acc, _mm512_extractf32x4_ps(u3, 2));
  acc = _mm_add_ps(acc, _mm512_extractf32x4_ps(u0, 3));
  acc = _mm_add_ps(acc, _mm512_extractf32x4_ps(u1, 3));
  acc = _mm_add_ps(acc, _mm512_extractf32x4_ps(u2, 3));
  acc = _mm_add_ps(acc, _mm512_extractf32x4_ps(u3, 3));
  _mm_storeu_ps(out, acc);
#else
  const float* q[4] = {q0, q1, q2, q3};
  for (int i = 0; i < 4; ++i) {
    float s = 0.0f;
    for (int l = 0; l < 16; ++l) s += q[i][l];
    out[i] = s;
  }
#endif
}

// Staging for a 2D float pair loop: the values of 16 neighbours (entries e[0..15], wall bit
// allowed) copied into lanes: x0, x1 (16 doubles each) from the positions P (2 doubles a
// particle) and r0..r3 (16 floats each) from rows R (4 floats a particle). On AVX-512 one
// 16-byte load a neighbour and each field's row, then in-block transposes; this CPU's gathers
// (and GCC's lane-by-lane loads, what it emits instead) cost several times more. Arrays 64-byte
// aligned.
inline void stage_rows_2d(const double* P, const float* R, const std::uint32_t* e, double* x0,
                          double* x1, float* r0, float* r1, float* r2, float* r3) {
#if defined(__AVX512F__)
  auto at = [e](int j) { return static_cast<std::size_t>(e[j] & ~kWallBit); };
  for (int h = 0; h < 2; ++h) {
    // z0's 128-bit blocks hold the positions of neighbours 8h + 0, 2, 4, 6; z1's 1, 3, 5, 7.
    const int o = 8 * h;
    auto row = [&](int j) { return _mm_castpd_ps(_mm_loadu_pd(P + 2 * at(o + j))); };
    __m512 z0 = _mm512_castps128_ps512(row(0)), z1 = _mm512_castps128_ps512(row(1));
    z0 = _mm512_insertf32x4(z0, row(2), 1);
    z1 = _mm512_insertf32x4(z1, row(3), 1);
    z0 = _mm512_insertf32x4(z0, row(4), 2);
    z1 = _mm512_insertf32x4(z1, row(5), 2);
    z0 = _mm512_insertf32x4(z0, row(6), 3);
    z1 = _mm512_insertf32x4(z1, row(7), 3);
    _mm512_store_pd(x0 + o, _mm512_unpacklo_pd(_mm512_castps_pd(z0), _mm512_castps_pd(z1)));
    _mm512_store_pd(x1 + o, _mm512_unpackhi_pd(_mm512_castps_pd(z0), _mm512_castps_pd(z1)));
  }
  __m512 q[4];
  rows_to_lanes16([&](int j) { return _mm_loadu_ps(R + 4 * at(j)); }, q);
  _mm512_store_ps(r0, q[0]);
  _mm512_store_ps(r1, q[1]);
  _mm512_store_ps(r2, q[2]);
  _mm512_store_ps(r3, q[3]);
#else
  for (int j = 0; j < 16; ++j) {
    const std::size_t b = e[j] & ~kWallBit;
    x0[j] = P[2 * b];
    x1[j] = P[2 * b + 1];
    r0[j] = R[4 * b];
    r1[j] = R[4 * b + 1];
    r2[j] = R[4 * b + 2];
    r3[j] = R[4 * b + 3];
  }
#endif
}

// Staging for a 3D float pair loop, with no copy of its own: positions x0..x2 (16 doubles
// each) from P (3 doubles a particle) and velocities v0..v2 (16 floats each) from U (3 floats
// a particle) by one masked load a neighbour and transposes; rho and P/rho^2 (rounded to
// float) by plain loads. Arrays 64-byte aligned.
inline void stage_rows_3d(const double* P, const float* U, const float* rho, const double* prs,
                          const std::uint32_t* e, double* x0, double* x1, double* x2, float* v0,
                          float* v1, float* v2, float* rh, float* pr) {
  auto at = [e](int j) { return static_cast<std::size_t>(e[j] & ~kWallBit); };
#if defined(__AVX512F__) && defined(__AVX512VL__)
  const __m512i lo = _mm512_setr_epi64(0, 1, 8, 9, 4, 5, 12, 13);
  const __m512i hi = _mm512_setr_epi64(2, 3, 10, 11, 6, 7, 14, 15);
  for (int h = 0; h < 2; ++h) {
    const int o = 8 * h;
    // z_j = (position of neighbour o + j | of o + j + 4), each (x, y, z, 0).
    auto pos = [&](int j) { return _mm256_maskz_loadu_pd(0x7, P + 3 * at(o + j)); };
    __m512d z[4];
    for (int j = 0; j < 4; ++j)
      z[j] = _mm512_insertf64x4(_mm512_castpd256_pd512(pos(j)), pos(j + 4), 1);
    // 128-bit blocks: t0 = (x0 x1 | z0 z1 | x4 x5 | z4 z5), t1 = (y0 y1 | 0 0 | y4 y5 | 0 0),
    // t2, t3 the same for neighbours 2, 3, 6, 7.
    const __m512d t0 = _mm512_unpacklo_pd(z[0], z[1]), t1 = _mm512_unpackhi_pd(z[0], z[1]);
    const __m512d t2 = _mm512_unpacklo_pd(z[2], z[3]), t3 = _mm512_unpackhi_pd(z[2], z[3]);
    _mm512_store_pd(x0 + o, _mm512_permutex2var_pd(t0, lo, t2));
    _mm512_store_pd(x1 + o, _mm512_permutex2var_pd(t1, lo, t3));
    _mm512_store_pd(x2 + o, _mm512_permutex2var_pd(t0, hi, t2));
  }
  // The velocities (x, y, z, 0) of the 16 neighbours, as rows.
  __m512 w[4];
  rows_to_lanes16([&](int j) { return _mm_maskz_loadu_ps(0x7, U + 3 * at(j)); }, w);
  _mm512_store_ps(v0, w[0]);
  _mm512_store_ps(v1, w[1]);
  _mm512_store_ps(v2, w[2]);
#else
  for (int j = 0; j < 16; ++j) {
    const std::size_t b = at(j);
    x0[j] = P[3 * b];
    x1[j] = P[3 * b + 1];
    x2[j] = P[3 * b + 2];
    v0[j] = U[3 * b];
    v1[j] = U[3 * b + 1];
    v2[j] = U[3 * b + 2];
  }
#endif
  for (int j = 0; j < 16; ++j) {
    const std::size_t b = at(j);
    rh[j] = rho[b];
    pr[j] = static_cast<float>(prs[b]);
  }
}

}  // namespace swell
