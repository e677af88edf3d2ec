"""Compare preview policies of the cloudscape's viewer on a fixed motion: the numbers quoted in
pywarp/clouds/controls.py and CloudscapeTechnique.reprojects.

    python tools/clouds_preview_eval.py [--altitude 6 --pitch -25] [--frames 40 --every 10] [--dump DIR]
                                        [--policy NAME=JSON ...]

The motion is the viewer benchmark's (``D`` + ``Left`` held, time playing at the viewer's 20x) in fixed steps of
1/30 s, so that it does not depend on the machine's speed. Each policy renders every frame at its preview size with
its settings changes (``{"size": [w, h], "changes": {...}, "preview": true}``; ``preview``: the technique's
:attr:`~pywarp.clouds.technique.CloudscapeTechnique.preview` flag, as the viewer sets it) and, every ``--every``
frames, the frame enlarged bilinearly to 640 x 360 (as the window shows it) is compared with the full render of the
same pose and time: SSIM on luminance (mean and minimum over the compared frames). The median frame time of each
policy is printed too; it is noisy on a shared machine: compare policies by ratios within one run. ``--dump``
writes each compared frame above its full render.
"""
from __future__ import annotations

import argparse
import dataclasses
import json
import os
import math
import time

import numpy as np

#: the default policies: the preview before (80 x 45 marched whole), the reprojected previews above the layer at the
#: sizes the viewer's adaptive scale picks, and the cheaper march of pywarp.clouds.controls
CHEAP = {"samples_min": 32, "samples_max": 64, "advanced": {"light_interp": 0.05, "exit_eps": 0.05}}
DEFAULT = {
    "whole-80x45": {"size": [80, 45]},
    "whole-80x45-cheap": {"size": [80, 45], "changes": CHEAP},
    "reproj-213x120": {"size": [213, 120], "changes": {"reprojection": True, **CHEAP}, "preview": True},
    "reproj-320x180": {"size": [320, 180], "changes": {"reprojection": True, **CHEAP}, "preview": True},
}
W, H = 640, 360
DT = 1.0 / 30.0


def pose_at(k: int, altitude: float, pitch: float):
    """The benchmark's motion after k steps: turning left at 60 deg/s while strafing right at 0.5 km/s."""
    from pywarp.core.pose import Pose

    x = z = 0.0
    for i in range(k):
        y = math.radians(-60.0 * DT * i)
        x += 0.5 * DT * math.cos(y)
        z += 0.5 * DT * math.sin(y)
    return Pose(x, altitude, z, -60.0 * DT * k, pitch, 60.0)


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--altitude", type=float, default=6.0)
    ap.add_argument("--pitch", type=float, default=-25.0)
    ap.add_argument("--frames", type=int, default=40)
    ap.add_argument("--every", type=int, default=10)
    ap.add_argument("--dump", default=None)
    ap.add_argument("--policy", action="append", default=[], metavar="NAME=JSON")
    a = ap.parse_args()
    if a.dump:
        os.makedirs(a.dump, exist_ok=True)
    if a.frames < 1 or not 1 <= a.every <= a.frames:
        ap.error("--frames must be >= 1 and --every in [1, frames]")
    policies = dict(DEFAULT) if not a.policy else {}
    for p in a.policy:
        name, _, text = p.partition("=")
        policies[name] = json.loads(text)

    from PIL import Image
    from skimage.metrics import structural_similarity

    from pywarp.clouds.settings import CloudscapeSettings
    from pywarp.clouds.technique import CloudscapeTechnique
    from pywarp.viewer.session import displayed, luminance

    base = CloudscapeSettings(width=W, height=H, camera_altitude_km=a.altitude, camera_pitch_deg=a.pitch)
    full = CloudscapeTechnique(base)
    refs: dict[int, np.ndarray] = {}

    def ref(k):
        if k not in refs:
            full.update(time_s=20.0 * DT * k)
            full.frame = 0
            refs[k] = np.asarray(full.render(pose_at(k, a.altitude, a.pitch), reprojection=False), np.uint8)
        return refs[k]

    for name, pol in policies.items():
        w, h = pol["size"]
        tech = CloudscapeTechnique(dataclasses.replace(base, width=w, height=h, **pol.get("changes", {})),
                                   textures=full.textures)
        tech.preview = bool(pol.get("preview", False))
        times, ssims = [], []
        for k in range(1, a.frames + 1):
            tech.update(time_s=20.0 * DT * k)
            t0 = time.perf_counter()
            img = np.asarray(tech.render(pose_at(k, a.altitude, a.pitch)), np.uint8)
            times.append(time.perf_counter() - t0)
            if k % a.every == 0:
                shown, r = displayed(img, W, H), ref(k)
                ssims.append(structural_similarity(luminance(shown), luminance(r), data_range=255.0))
                if a.dump:
                    Image.fromarray(np.concatenate([shown, r], 0)).save(f"{a.dump}/{name}-{k:03d}.png")
        print(f"{name}: {w}x{h}, frame {1e3 * np.median(times[3:] or times):.1f} ms median, "
              f"SSIM {np.mean(ssims):.4f} mean / {np.min(ssims):.4f} min", flush=True)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
