/*
 * cclouds/hash.h -- the integer hash of the project: the PCG hash of Jarzynski & Olano (2020), used by the noise
 * lattices (Perlin permutations, Worley feature points) and by the per-pixel jitter of the raymarcher.
 *
 * uint32 arithmetic only (defined overflow in C, the same in Warp), no global state: the same input gives the same
 * bits on every platform, so C and Warp build identical lattices.
 */
#ifndef CCLOUDS_HASH_H
#define CCLOUDS_HASH_H

#include "cclouds/common.h"

#ifdef __cplusplus
extern "C" {
#endif

/* PCG hash of one uint32 (the RXS-M-XS output of a one-step PCG generator). Ref: vc-A1 (the "hash of the lattice
 * position" the thesis leaves unspecified); M. Jarzynski & M. Olano, "Hash Functions for GPU Rendering", JCGT 9(3),
 * 2020. v: any uint32 -> state s = v * 747796405 + 2891336453 (mod 2^32),
 * w = ((s >> ((s >> 28) + 4)) ^ s) * 277803737 (mod 2^32); returns (w >> 22) ^ w, any uint32. A bijection. */
CCL_API uint32_t ccl_hash_pcg(uint32_t v);

/* Uniform float in [0, 1) from the top 24 bits of a hash: (h >> 8) * 2^-24 (exact in float32). Ref: vc-A1 (random
 * values from the hash). h: any uint32 (usually a ccl_hash_pcg result); output in {0, 2^-24, ..., 1 - 2^-24}. */
CCL_API float ccl_hash_unit(uint32_t h);

#ifdef __cplusplus
}
#endif

#endif /* CCLOUDS_HASH_H */
