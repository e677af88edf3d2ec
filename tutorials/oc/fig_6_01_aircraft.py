"""Figure oc-fig-6.1 in kind: the aircraft with its five height points A-E, and its attitude computed from them.

The text's plane is a 3DS model converted to Open Inventor (oc-6.1); none ships with the text, so the procedural
light aircraft of pywarp.equation("oc-6.1") (ccl_flight_aircraft: fuselage, low wing of 12 m span, tail, canopy)
stands in, drawn by the volume renderer of the flight scene (pywarp.flight.volumes.render, no clouds). The height
points (oc-6.1.1; their positions are not given: the catalogue's reading) are A = nose (0, 0, -3.75), B = tail
(0, 0, +3.75), C = left wing tip (-6, 0, 0), D = right wing tip (+6, 0, 0), E = centre of gravity (0, 0, 0) in the
model frame (x right, y up, z tail), projected with the camera. Left: level flight. Right: after the down arrow held
0.6 s and the right arrow 1.2 s (point rate 1 m/s: A and B moved +-0.6 m, C and D +-1.2 m); the attitude from the
heights, pitch = atan2(h_A - h_B, 7.5 m), roll = atan2(h_C - h_D, 12 m) (pywarp.equation("oc-6.1.1")), is printed
under the panel. Sun 35 deg high at azimuth 110 deg. Output: figures/oc/fig-6.1.png.
"""
# %% [markdown]
# The simulator does not model aerodynamics. Five points on the plane carry heights: the nose A, the tail B, the
# wing tips C and D, and the centre of gravity E, whose height is the altitude. The arrow keys raise or lower these
# points for as long as they are held, and the plane's tilt is computed from the height differences: nose against
# tail gives the pitch, left tip against right tip the roll. The plane then moves along its tilt -- it climbs when
# the nose is up (if it has speed) and turns towards the lower wing.

# %%
from __future__ import annotations

import math
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import pywarp  # noqa: E402
from pywarp.core.cbridge import VOLUME_PARAMS  # noqa: E402
from pywarp.kernels import camera as CAM  # noqa: E402
from pywarp.flight import model as F  # noqa: E402
from pywarp.kernels import volume as V  # noqa: E402
from pywarp.flight import volumes as VS  # noqa: E402
from pywarp.tutorial import fit_text  # noqa: E402

MODEL = F.FlightModel()
POINTS = {"A": (0.0, 0.0, -MODEL.length / 2), "B": (0.0, 0.0, MODEL.length / 2), "C": (-MODEL.span / 2, 0.0, 0.0),
          "D": (MODEL.span / 2, 0.0, 0.0), "E": (0.0, 0.0, 0.0)}
POS = np.array([0.0, 300.0, 0.0])
#: quick mode's label offsets (points) from each height point: the small image puts A, B, D and E within ~20 px of
#: each other, so the letters stand apart on leader lines (nose A below, tail B above right, wing tips outwards)
QUICK_LABEL_OFFSETS = {"A": (-6, -16), "B": (10, 14), "C": (12, -10), "D": (-14, 12), "E": (-2, 17)}


def panel(nose: float, wing: float, width: int, height: int):
    """Image, projected points and (pitch, roll) of the aircraft with the given height offsets of A/B and C/D."""
    h = POS[1]
    pitch, roll = pywarp.equation("oc-6.1.1")(h + nose, h - nose, h + wing, h - wing, MODEL.length, MODEL.span)
    pitch, roll = float(pitch), float(roll)
    f, r, u = F.axes(0.0, pitch, roll)
    values = VOLUME_PARAMS.defaults()
    values.update(sun=V.sun_direction(35.0, 110.0), aircraft=1, aircraft_position=tuple(POS), aircraft_forward=f,
                  aircraft_right=r, aircraft_up=u)
    eye = POS + np.array([-9.0, 6.5, -11.0])  # in front, to the left and above
    cam = CAM.camera_look_at(eye, POS, (0.0, 1.0, 0.0), math.radians(50.0), width / height, 0.1, 1e5)
    img = VS.render(VS.VolumeSet([]), values, cam, width, height)
    pts = {}
    for name, (x, y, z) in POINTS.items():
        w = POS + x * np.asarray(r) + y * np.asarray(u) - z * np.asarray(f)
        clip = np.asarray(cam.view_proj, dtype=np.float64) @ np.append(w, 1.0)
        ndc = clip[:3] / clip[3]
        pts[name] = ((ndc[0] + 1) / 2 * width, (1 - ndc[1]) / 2 * height, w[1])
    return img, pts, pitch, roll


def main(out_dir, quick: bool = False) -> list[Path]:
    out_dir = Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    w, h = (200, 140) if quick else (560, 400)
    cases = (("level flight", 0.0, 0.0), ("down arrow 0.6 s, right arrow 1.2 s", 0.6, 1.2))
    fig, axes = plt.subplots(1, 2, figsize=(2 * w / 100, h / 100 + 1.0), dpi=100)
    for ax, (title, nose, wing) in zip(axes, cases):
        img, pts, pitch, roll = panel(nose, wing, w, h)
        ax.imshow(img)
        heights = ""
        for name, (px, py, alt) in pts.items():
            ax.plot(px, py, "o", ms=4 if quick else 6, mfc="yellow", mec="black")
            if quick:  # the points lie a few pixels apart: each letter on a leader line, the heights in the caption
                ax.annotate(name, (px, py), xytext=QUICK_LABEL_OFFSETS[name], textcoords="offset points", fontsize=7,
                            ha="center", va="center", bbox=dict(boxstyle="round,pad=0.1", fc="white", alpha=0.8),
                            arrowprops=dict(arrowstyle="-", lw=0.6, color="black", shrinkA=0, shrinkB=2))
                heights += f", {name} {alt - POS[1]:+.1f}"
            else:
                ax.annotate(f"{name}  {alt - POS[1]:+.1f} m", (px, py), xytext=(6, -8), textcoords="offset points",
                            fontsize=8, color="black", bbox=dict(boxstyle="round,pad=0.15", fc="white", alpha=0.75))
        ax.set_title(title, fontsize=9)
        ax.set_xlabel((f"heights (m): {heights[2:]};  " if quick else "")
                      + f"pitch = atan2(h_A - h_B, {MODEL.length:g}) = {math.degrees(pitch):.1f} deg,  "
                      f"roll = atan2(h_C - h_D, {MODEL.span:g}) = {math.degrees(roll):.1f} deg", fontsize=8)
        ax.set_xticks([])
        ax.set_yticks([])
    fig.suptitle("aircraft with its height points (heights relative to E, the centre of gravity)", fontsize=9)
    fit_text(fig, tight_layout=True)  # the layout, with titles and labels that fit (legible in quick mode)
    path = out_dir / "fig-6.1.png"
    fig.savefig(path, dpi=100)
    plt.close(fig)
    return [path]


if __name__ == "__main__":
    from pywarp.tutorial import run_as_script

    run_as_script(main, __doc__, "figures/oc")
