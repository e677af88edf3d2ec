/*
 * cclouds/raymarch.h -- (topic header; declarations are added as the catalogue entries are implemented).
 */
#ifndef CCLOUDS_RAYMARCH_H
#define CCLOUDS_RAYMARCH_H

#include "cclouds/common.h"

#ifdef __cplusplus
extern "C" {
#endif

#ifdef __cplusplus
}
#endif

#endif /* CCLOUDS_RAYMARCH_H */
