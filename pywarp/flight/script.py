"""The default scripted flight and the placement of the clouds along it.

A script is a list of ``(key, t_on, t_off)``: the key (up, down, left, right, w, s -- the control table of oc
§6.1.2) is held from ``t_on`` to ``t_off`` seconds. :func:`pywarp.flight.model.simulate` steps the flight model with
a fixed dt, so the same script always gives the same trajectory.
"""
from __future__ import annotations

import math

import numpy as np

#: The default flight (32 s, starting at 40 m/s heading -z just below the cloud level): full throttle, a climb into
#: the first cloud, level off inside it, a right turn out of it, a left turn around the clouds to the left, then
#: back to a shallow right bank and a gentle descent.
DEFAULT_SCRIPT = (
    ("w", 0.0, 3.0),          # to full speed (60 m/s)
    ("down", 1.0, 1.5),       # nose up: climb towards the first cloud
    ("up", 6.5, 7.0),         # level off inside it
    ("right", 9.0, 10.6),     # bank right, turn out of it
    ("left", 13.5, 15.1),     # level the wings
    ("left", 16.0, 18.0),     # bank left around the clouds on the left
    ("right", 23.0, 25.0),    # level the wings
    ("up", 26.0, 26.5),       # nose down: a gentle descent
    ("down", 29.5, 30.0),     # level off
)

#: draws of a cloud's position before it is placed even if its box still overlaps another (20: with the default 9
#: clouds a clear place is found within a few draws)
PLACEMENT_TRIES = 20

#: fixed simulation step [s]
DT = 1.0 / 60.0


def trajectory(settings, device: str | None = None):
    """The default script flown with the settings' flight model (:func:`pywarp.flight.model.simulate`)."""
    from .model import simulate

    return simulate(DEFAULT_SCRIPT, settings.flight_duration_s, dt=DT, start=settings.start_state(),
                    model=settings.flight_model(), device=device)


def _overlap(centre, extent, box) -> bool:
    """Whether the box of ``centre`` and ``extent`` intersects ``box`` = (origin, extent)."""
    o, e = box
    return all(abs(c - (oo + ee / 2)) < (x + ee) / 2 for c, x, oo, ee in zip(centre, extent, o, e))


def cloud_boxes(settings, traj) -> list[tuple[tuple, tuple]]:
    """(origin, extent) of every cloud box [m]: cloud 0 centred on the flight path at 22 %% of the flight and
    smaller (the aircraft flies through it in about 5 s), the others beside the path (alternately left and right,
    0.6 - 1.1 box widths from it, 0.2 - 1.4 widths ahead of a point of the path, drawn again while the box overlaps
    another), at the cloud altitude; sizes varied per cloud (+-25 %% wide, +-20 %% high). Deterministic per seed."""
    rng = np.random.default_rng(settings.seed)
    n = settings.cloud_count
    boxes = []
    pos = np.asarray(traj.position, dtype=np.float64)
    head = np.asarray(traj.heading, dtype=np.float64)
    dur = float(traj.time[-1])
    for k in range(n):
        w = settings.cloud_width_m * rng.uniform(0.75, 1.25)
        d = settings.cloud_width_m * rng.uniform(0.75, 1.25)
        h = settings.cloud_height_m * rng.uniform(0.8, 1.2)
        if k == 0:
            # smaller, so that the flight through it takes about 5 s
            w, d, h = 0.6 * w, 0.5 * d, 0.8 * h
            i = traj.at(0.22 * dur)
            centre = pos[i].copy()
        else:
            u = (k - 0.5) / max(n - 1, 1)
            i = traj.at(min(0.1 + 0.85 * u, 1.0) * dur)
            side = 1.0 if k % 2 else -1.0
            right = np.array([math.cos(head[i]), 0.0, math.sin(head[i])])
            ahead = np.array([math.sin(head[i]), 0.0, -math.cos(head[i])])
            # boxes that overlap are composited one after the other (cclouds/volume.h): a later box's cloud would be
            # cut by the earlier box's face. Draw again (at most PLACEMENT_TRIES times) until the box is clear of
            # the others
            for _ in range(PLACEMENT_TRIES):
                centre = (pos[i] + right * side * settings.cloud_width_m * rng.uniform(0.6, 1.1)
                          + ahead * settings.cloud_width_m * rng.uniform(0.2, 1.4))
                centre[1] = settings.cloud_altitude_m + rng.uniform(-0.15, 0.15) * settings.cloud_height_m
                if not any(_overlap(centre, (w, h, d), b) for b in boxes):
                    break
        extent = (w, h, d)
        origin = tuple(float(c - e / 2) for c, e in zip(centre, extent))
        boxes.append((origin, tuple(float(e) for e in extent)))
    return boxes
