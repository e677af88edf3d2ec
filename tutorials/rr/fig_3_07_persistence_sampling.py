"""Figure rr-fig-3.7: sampling of one streak pixel under retinal persistence (rr-alg-3.2.3, rr-code-5.2.4), computed:
(a) one streak billboard and the drop at the 7 positions of its fall that the shader samples, over one pixel P; (b) the
refraction mask (rr-alg-3.1.1, a sphere) with the 7 texels P sees; (c) the 150 deg capture (rr-alg-3.1.2) with P_o and
the 7 refracted lookups P_c (rr-alg-3.1.3); (d) the 7 colours, their mean, the reduced alpha and the pixel -- equal to
the compositing pass (``pywarp.particles_composite``). Output: figures/rr/fig-3.7.png.
"""
# %% [markdown]
# While the eye keeps the image of a falling drop (60-90 ms), the drop moves down by L = speed x persistence. The
# streak billboard is the drop's quad stretched to cover that fall: 2 r wide, 2 r + L tall, the drop's mask stretched
# over it. The shader looks at the mask 7 times, shifted by i x tap_offset (i = -3 .. 3): the mask texel under the
# pixel when the drop was 3 steps above .. 3 steps below. `pywarp.particles_streak(speed, persistence, radius)`
# returns L and the tap offset (L / 6) / (2 r + L), so the 7 taps span the whole fall.
#
# Each tap that falls inside the drop refracts: the mask gives the exit direction (x, y, z), P_c = P_o + (x, -y) / z
# * 0.5 / tan(75 deg) in the capture. The pixel's colour is the mean of the taps that hit, its alpha the opacity times
# the share of taps that hit (the text's "reduced alpha", amount not given).

# %%
from __future__ import annotations

import math
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import pywarp  # noqa: E402
from pywarp.rain.drops import drop_mask  # noqa: E402
from pywarp.rain.settings import RainSettings  # noqa: E402
from pywarp.rain.technique import RainTechnique  # noqa: E402
from pywarp.tutorial import fit_text  # noqa: E402

W, H = 96, 120  # the view (pixels) around the streak
FOV_VIEW, FOV_CAP = math.radians(60.0), math.radians(150.0)
RADIUS, LENGTH_PX, PERSISTENCE = 9.0, 63.0, 0.075  # drop radius and fall (pixels), persistence time (s)


def main(out_dir, quick: bool = False) -> list[Path]:
    out_dir = Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    cap_size, mask_size = (128, 64) if quick else (512, 256)
    tech = RainTechnique(RainSettings(width=W, height=H, background="panorama", drops=0, capture_size=cap_size,
                                      camera_pitch_deg=-10.0, fov_y_deg=60.0))
    ins = tech.frame_inputs()
    bg, cap = ins["background"], ins["capture"]
    mask = np.asarray(drop_mask(mask_size, 1.0, method="sphere"))

    # %% [markdown]
    # The streak: the radius and the fall are in pixels here (the functions do not care about the unit).
    # %%
    length, tap = (float(v) for v in pywarp.particles_streak(LENGTH_PX / PERSISTENCE, PERSISTENCE, RADIUS))
    half = RADIUS + 0.5 * length
    cx, cy = W / 2, H / 2
    sprite = np.array([[cx, cy, RADIUS, half, tap, 1.0]], np.float32)
    frame = pywarp.particles_composite(bg, cap, mask, sprite, FOV_VIEW, FOV_CAP, streaks="thesis", opacity=1.0)

    px, py = int(cx) + 3, int(cy) + 6  # the pixel P
    mu = (px + 0.5 - cx) / (2 * RADIUS) + 0.5
    mv = (py + 0.5 - cy) / (2 * half) + 0.5
    ndc = np.array([2 * (px + 0.5) / W - 1, 1 - 2 * (py + 0.5) / H], np.float32)
    p_o = np.asarray(pywarp.particles_capture_uv(ndc, W / H, FOV_VIEW, FOV_CAP), np.float64)
    scale = 0.5 / math.tan(FOV_CAP / 2)
    taps = []
    for i in range(-3, 4):
        v = mv - i * tap
        inside = 0 <= v < 1 and 0 <= mu < 1
        t = mask[min(int(v * mask_size), mask_size - 1), min(int(mu * mask_size), mask_size - 1)] if inside else None
        if t is not None and t[3] > 0 and t[2] > 0:
            pc = p_o + scale * np.array([t[0] / t[2], -t[1] / t[2]])
            rgb = cap[min(int(pc[1] * cap_size), cap_size - 1), min(int(pc[0] * cap_size), cap_size - 1)]
            taps.append((i, v, pc, rgb))
        else:
            taps.append((i, v, None, None))
    hits = [t for t in taps if t[3] is not None]
    mean = np.mean([t[3] for t in hits], axis=0)
    alpha = len(hits) / 7
    pixel = bg[py, px] + (mean - bg[py, px]) * alpha
    assert np.allclose(pixel, frame[py, px], atol=1e-5), (pixel, frame[py, px])  # = the compositing pass

    fig, axes = plt.subplots(1, 4, figsize=(16, 4.8), dpi=70 if quick else 120,
                             gridspec_kw={"width_ratios": [1, 1.25, 1.25, 1.1]})
    # (a) the streak and the drop's 7 positions
    ax = axes[0]
    ax.imshow(np.clip(frame, 0, 1), interpolation="nearest", extent=(0, W, H, 0))
    tt = np.linspace(0, 2 * np.pi, 100)
    for i in range(-3, 4):
        # the stretched drop shifted by i tap offsets: its outline on screen
        yc = cy + i * tap * 2 * half
        ax.plot(cx + RADIUS * np.cos(tt), yc + half * np.sin(tt), lw=0.7, color=plt.cm.viridis((i + 3) / 6))
    ax.add_patch(plt.Rectangle((cx - RADIUS, cy - half), 2 * RADIUS, 2 * half, fill=False, ec="w", lw=1, ls="--"))
    ax.add_patch(plt.Rectangle((px, py), 1, 1, fill=False, ec="red", lw=1.5))
    ax.text(px + 2, py, "P", color="red", fontsize=10, va="center")
    ax.set_title(f"(a) streak billboard 2r x (2r + L): r = {RADIUS:g} px, L = {length:g} px,\n"
                 f"the drop at its 7 sampled positions (tap offset {tap:.4f})", fontsize=8)
    ax.axis("off")
    # (b) the mask with the taps of P
    ax = axes[1]
    with np.errstate(divide="ignore", invalid="ignore"):
        code = np.where((mask[..., 3:] > 0) & (mask[..., 2:3] > 0),
                        0.5 + 0.5 * np.concatenate([mask[..., :2] / mask[..., 2:3], mask[..., 3:] * 0.3], -1)
                        .clip(-1, 1), 0.1)
    ax.imshow(np.clip(code, 0, 1), extent=(0, 1, 1, 0))
    for i, v, pc, rgb in taps:
        ax.plot(mu, v, "o", ms=6, mfc=plt.cm.viridis((i + 3) / 6) if rgb is not None else "none",
                mec="w" if rgb is not None else "r")
        ax.text(mu + 0.03, v, f"i = {i:+d}" + ("" if rgb is not None else " (outside)"), color="w", fontsize=7,
                va="center")
    ax.set_title("(b) the mask (colour: x/z, y/z of the refraction vector)\nand the 7 texels under P: (u, v - i tap)",
                 fontsize=8)
    ax.set_xlabel("mask u")
    ax.set_ylabel("mask v (0 = top)")
    # (c) the capture, P_o and the P_c of the hits
    ax = axes[2]
    ax.imshow(np.clip(cap, 0, 1), extent=(0, 1, 1, 0))
    ax.plot(*p_o, "x", color="red", ms=9, mew=2)
    ax.text(p_o[0] + 0.01, p_o[1] - 0.012, "$P_o$", color="red", fontsize=11)
    for i, v, pc, rgb in hits:
        ax.plot(*pc, "o", ms=6, mfc=plt.cm.viridis((i + 3) / 6), mec="w")
        ax.annotate("", xy=pc, xytext=p_o, arrowprops=dict(arrowstyle="->", color="w", lw=0.6))
    ax.set_xlim(p_o[0] - 0.12, p_o[0] + 0.12)
    ax.set_ylim(p_o[1] + 0.12, p_o[1] - 0.12)
    ax.set_title("(c) the 150 deg capture around $P_o$ of P, the refracted lookups $P_c$ of the\nhits (the drop "
                 "shows the scene inverted: the top taps see the ground)", fontsize=8)
    ax.set_xlabel("capture u")
    ax.set_ylabel("capture v")
    # (d) the colours
    ax = axes[3]
    for k, (i, v, pc, rgb) in enumerate(taps):
        ax.add_patch(plt.Rectangle((0, 6 - k), 1, 0.85, color=np.clip(rgb, 0, 1) if rgb is not None else "w",
                                   ec="k", lw=0.5, hatch=None if rgb is not None else "//"))
        ax.text(1.1, 6.4 - k, f"i = {i:+d}" + ("" if rgb is not None else ": miss"), fontsize=8, va="center")
    for k, (c, label) in enumerate(((mean, f"mean of the {len(hits)} hits"), (bg[py, px], "background"),
                                    (pixel, f"pixel: alpha = {len(hits)}/7"))):
        ax.add_patch(plt.Rectangle((2.6, 5 - 2 * k), 1, 1.6, color=np.clip(c, 0, 1), ec="k", lw=0.5))
        ax.text(3.7, 5.8 - 2 * k, label, fontsize=8, va="center")
    ax.set_xlim(0, 6)
    ax.set_ylim(-0.5, 7.2)
    ax.axis("off")
    ax.set_title("(d) the 7 tap colours, their mean, the reduced alpha\n(= the compositing pass's pixel)", fontsize=8)
    fig.suptitle("Fig 3.7 — retinal persistence: sampling of one streak pixel (rr-alg-3.2.3, rr-code-5.2.4)",
                 fontsize=10)
    fit_text(fig, tight_layout=True)  # the layout, with titles and labels that fit (legible in quick mode)
    path = out_dir / "fig-3.7.png"
    fig.savefig(path)
    plt.close(fig)
    return [path]


if __name__ == "__main__":
    from pywarp.tutorial import run_as_script

    run_as_script(main, __doc__, "figures/rr")
