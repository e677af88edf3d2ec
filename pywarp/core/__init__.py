"""The mechanisms every text builds on: the equation registry and its generated evaluation, the catalogue, parameter
specs, runtime (devices, tile-parallel launcher), the C binding, output files, caches and timing."""
