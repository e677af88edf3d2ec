/*
 * cclouds/noise.h -- (topic header; declarations are added as the catalogue entries are implemented).
 */
#ifndef CCLOUDS_NOISE_H
#define CCLOUDS_NOISE_H

#include "cclouds/common.h"

#ifdef __cplusplus
extern "C" {
#endif

#ifdef __cplusplus
}
#endif

#endif /* CCLOUDS_NOISE_H */
