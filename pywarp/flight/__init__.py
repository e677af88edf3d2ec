"""The flight simulator of the oc text (scene ``flight``): value-noise cloud volumes (oc §5.2) rendered by the volume
renderer that stands in for SimVoleon, and the aircraft flown through and around them along a script of timed key
presses (oc §6). Settings, the default flight, the technique and the benchmarks."""
