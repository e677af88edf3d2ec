/*
 * cclouds/cclouds.h -- umbrella header: includes every public header of the cclouds C99 core.
 * The order below is also the order in which the Python binding reads the headers.
 */
#ifndef CCLOUDS_CCLOUDS_H
#define CCLOUDS_CCLOUDS_H

#include "cclouds/common.h"
#include "cclouds/camera.h"
#include "cclouds/phase.h"
#include "cclouds/media.h"
#include "cclouds/hash.h"
#include "cclouds/interp.h"
#include "cclouds/noise.h"
#include "cclouds/texgen.h"
#include "cclouds/clouds.h"
#include "cclouds/raymarch.h"
#include "cclouds/colour.h"
#include "cclouds/sky.h"
#include "cclouds/reproj.h"
#include "cclouds/cloudscape.h"
#include "cclouds/optics.h"
#include "cclouds/rain.h"
#include "cclouds/draw.h"
#include "cclouds/fractal.h"
#include "cclouds/sdf.h"
#include "cclouds/terrain.h"
#include "cclouds/valuenoise.h"
#include "cclouds/voxel.h"
#include "cclouds/particles.h"
#include "cclouds/flight.h"
#include "cclouds/volume.h"

#endif /* CCLOUDS_CCLOUDS_H */
