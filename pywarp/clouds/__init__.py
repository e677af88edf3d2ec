"""The volumetric cloudscape of the vc thesis (scene ``clouds``): settings, textures, technique, benchmarks."""
