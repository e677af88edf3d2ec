/* The PCG hash of the project. See cclouds/hash.h. */
#include "cclouds/hash.h"

uint32_t ccl_hash_pcg(uint32_t v)
{
    uint32_t state = v * 747796405u + 2891336453u;
    uint32_t word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
    return (word >> 22u) ^ word;
}

float ccl_hash_unit(uint32_t h)
{
    return (float)(h >> 8u) * (1.0f / 16777216.0f);
}
