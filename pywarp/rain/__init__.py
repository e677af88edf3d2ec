"""Realistic rain of the rr text (scene ``rain``): settings, the technique (particles, capture, refraction shaders),
benchmarks."""
