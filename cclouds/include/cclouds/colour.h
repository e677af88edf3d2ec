/*
 * cclouds/colour.h -- (topic header; declarations are added as the catalogue entries are implemented).
 */
#ifndef CCLOUDS_COLOUR_H
#define CCLOUDS_COLOUR_H

#include "cclouds/common.h"

#ifdef __cplusplus
extern "C" {
#endif

#ifdef __cplusplus
}
#endif

#endif /* CCLOUDS_COLOUR_H */
