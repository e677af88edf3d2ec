/*
 * cclouds/texgen.h -- (topic header; declarations are added as the catalogue entries are implemented).
 */
#ifndef CCLOUDS_TEXGEN_H
#define CCLOUDS_TEXGEN_H

#include "cclouds/common.h"

#ifdef __cplusplus
extern "C" {
#endif

#ifdef __cplusplus
}
#endif

#endif /* CCLOUDS_TEXGEN_H */
