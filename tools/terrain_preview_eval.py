"""Compare preview policies of the terrain's viewer on a fixed motion: the numbers quoted in pywarp/core/temporal.py
(DEPTH_BLEND, DEPTH_REJECT, CUBIC_HISTORY) and for the terrain's preview mode (TerrainTechnique.preview_mode).

    python tools/terrain_preview_eval.py [--frames 60 --first 18 --every 6] [--dump DIR] [--policy NAME=JSON ...]

The motion is the viewer benchmark's (``W`` held: walking along the view at the controls' speed, time playing at the
viewer's 20x) in fixed steps of 1/30 s (``--fps``: another rate, e.g. the benchmark's on a loaded machine), so that it does not depend on the machine's speed. The motion starts from the
full render of its first pose (the viewer's refined frame before the keys are pressed). A policy is either
``{"scaled": [w, h]}`` -- the preview settings at w x h, enlarged bilinearly to 640 x 360 as the window shows it --
or ``{"factor": f, "depth": true, "water": true, "blend": b, "reject": r, "cubic": true, "sky": true, "clamped_cubic": true}`` -- the temporal
reconstruction of :mod:`pywarp.core.temporal` at 1/f^2 of the pixels per frame (``depth``: fed the terrain's depth;
``water``: and its water as changing; the rest the :class:`~pywarp.core.temporal.TemporalUpsampler` arguments,
defaults the module's); either may add ``"changes": {...}`` to the preview settings (e.g. ``{"quality": "full"}``). From frame ``--first`` on, every
``--every`` frames, the displayed 640 x 360 frame is compared with the full render of the same pose and time: SSIM
on luminance (mean and 5th percentile) and the mean CIEDE2000. The median CPU time of a frame (render + resolve, all
threads of the process) is printed too; it is noisy on a shared machine: compare policies by ratios within one run.
``--dump`` writes each compared frame above its full render.
"""
from __future__ import annotations

import argparse
import dataclasses
import json
import os
import time

import numpy as np

#: the default policies: the viewer's scaled preview at the size it picks on two cores, and the temporal
#: reconstruction at 1/4 and 1/16 of the pixels, without and with the depth's rejection
DEFAULT = {
    "scaled-213x120": {"scaled": [213, 120]},
    "temporal-f2-clamp": {"factor": 2, "depth": True, "reject": 0.0, "cubic": False},
    "temporal-f4-clamp": {"factor": 4, "depth": True, "reject": 0.0, "cubic": False},
    "temporal-f2-depth": {"factor": 2, "depth": True},
    "temporal-f4-depth": {"factor": 4, "depth": True},
}
W, H = 640, 360
DT = 1.0 / 30.0
#: the viewer's time scale (pywarp.viewer.session.Session's default)
TIME_SCALE = 20.0


def motion(base, frames: int, dt: float = DT) -> list:
    """The settings of frames 0..frames: the controls' step with ``W`` held, time advancing at the viewer's rate."""
    from pywarp.terrain.controls import TerrainControls
    from pywarp.viewer.controls import Input

    ctl = TerrainControls(base)
    s = base
    out = [s]
    for _ in range(frames):
        step = ctl.step(s, Input(dt=dt, held=frozenset({"W"})))
        s = dataclasses.replace(s, **step.changes, time_s=s.time_s + dt * TIME_SCALE)
        out.append(s)
    return out


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--frames", type=int, default=60)
    ap.add_argument("--first", type=int, default=18)
    ap.add_argument("--every", type=int, default=6)
    ap.add_argument("--dump", default=None)
    ap.add_argument("--fps", type=float, default=30.0, help="frames per second of the motion (its step)")
    ap.add_argument("--verbose", action="store_true", help="print each compared frame's SSIM")
    ap.add_argument("--policy", action="append", default=[], metavar="NAME=JSON")
    a = ap.parse_args()
    if a.dump:
        os.makedirs(a.dump, exist_ok=True)
    if a.frames < 1 or not 1 <= a.first <= a.frames or a.every < 1:
        ap.error("--frames must be >= 1, --first in [1, frames], --every >= 1")
    policies = dict(DEFAULT) if not a.policy else {}
    for p in a.policy:
        name, _, text = p.partition("=")
        policies[name] = json.loads(text)

    from PIL import Image
    from skimage.color import deltaE_ciede2000, rgb2lab
    from skimage.metrics import structural_similarity

    from pywarp.core import temporal as T
    from pywarp.core.pose import Pose
    from pywarp.terrain.settings import TerrainSettings
    from pywarp.terrain.technique import TerrainTechnique
    from pywarp.viewer.session import displayed, luminance, technique_camera

    base = TerrainSettings(width=W, height=H)
    if not a.fps > 0:
        ap.error("--fps must be > 0")
    states = motion(base, a.frames, 1.0 / a.fps)
    full = TerrainTechnique(base)
    refs: dict[int, np.ndarray] = {}

    def ref(k):
        if k not in refs:
            full.update(**{n: getattr(states[k], n) for n in ("camera_x", "camera_y", "camera_z", "time_s")})
            refs[k] = np.asarray(full.render(), np.uint8)
        return refs[k]

    start = ref(0)
    full.update(**{n: getattr(states[0], n) for n in ("camera_x", "camera_y", "camera_z", "time_s")})
    full.render()
    start_depth = full.depth()
    preview = {"quality": "preview", "preview_scale": 1}
    print(f"{'policy':<28} {'fresh':>9} {'CPU ms':>7} {'SSIM mean':>9} {'p5':>7} {'min':>7} {'dE00':>6}", flush=True)
    for name, pol in policies.items():
        tech = None
        up = None
        if "scaled" in pol:
            w, h = pol["scaled"]
        else:
            up = T.TemporalUpsampler(full.launcher, W, H, int(pol["factor"]), depth_blend=pol.get("blend"),
                                     depth_reject=pol.get("reject"), cubic=pol.get("cubic"),
                                     sky=pol.get("sky"), clamped_cubic=pol.get("clamped_cubic"))
            use_depth = bool(pol.get("depth", True))
            up.remember(start, technique_camera(full, Pose.from_settings(states[0])), key=None,
                        depth=start_depth if use_depth else None)
            w, h = W // up.factor, H // up.factor
        pv = {**preview, **pol.get("changes", {})}
        tech = TerrainTechnique(dataclasses.replace(base, width=w, height=h, **pv))
        cpu, ssims, des = [], [], []
        for k in range(1, a.frames + 1):
            s = dataclasses.replace(states[k], width=w, height=h, **pv)
            tech.update(**{n: getattr(s, n) for n in ("camera_x", "camera_y", "camera_z", "time_s")})
            c0 = time.process_time()
            if up is None:
                img = displayed(np.asarray(tech.render(), np.uint8), W, H)
            else:
                pose = tech.pose()
                lw, lh, jitter = up.plan()
                fresh = np.asarray(tech.render(tech.jitter(pose, jitter)), np.uint8)
                img = up.resolve(fresh, technique_camera(tech, pose), key=s.time_s,
                                 depth=tech.depth() if use_depth else None,
                                 changing=tech.changing() if use_depth and pol.get("water", True) else None)
            cpu.append(time.process_time() - c0)
            if k >= a.first and (k - a.first) % a.every == 0:
                r = ref(k)
                ssims.append(structural_similarity(luminance(img), luminance(r), data_range=255.0))
                if a.verbose:
                    print(f"  frame {k}: SSIM {ssims[-1]:.4f}", flush=True)
                des.append(float(np.mean(deltaE_ciede2000(rgb2lab(img / 255.0), rgb2lab(r / 255.0)))))
                if a.dump:
                    Image.fromarray(np.concatenate([img, r], 0)).save(f"{a.dump}/{name}-{k:03d}.png")
        print(f"{name:<28} {w:>4}x{h:<4} {1e3 * np.median(cpu[3:] or cpu):7.1f} {np.mean(ssims):9.4f} "
              f"{np.percentile(ssims, 5):7.4f} {np.min(ssims):7.4f} {np.mean(des):6.2f}", flush=True)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
