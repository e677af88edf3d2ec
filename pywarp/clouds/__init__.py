"""The volumetric cloudscape of the vc thesis (scene ``clouds``): settings, textures, technique, benchmarks,
and the host side of the kernels' topics it renders with (reproj, raymarch, media, texgen, sky, noise)."""
