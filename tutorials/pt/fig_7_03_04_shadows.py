"""Figures pt-fig-7.3 and pt-fig-7.4: the landscape with hard shadows (Kod 7.6) and with soft shadows (Kod 7.7).

Equations: pt-code-7.6 (hard: t0 = 0.2, occluded or not), pt-code-7.7 (soft: t0 = 0.02, k = 4, penumbra from the
closest approach min k d / t), pt-7.1 (the shadow multiplies the diffuse term), pt-code-7.5 and pt-code-7.9 (the
terrain). The text's scene parameters are not given: the terrain scene's defaults with the sun from the right
(elevation 25 deg, azimuth 100 deg) so that the hills cast shadows across the view, stage 'atmosphere' (no water,
so that the lakes do not hide shadows). With k = 4, open flat ground is fully lit only for k sin(elevation) > 1 (the
shadow ray's clearance grows as t sin e), i.e. a sun above 14.5 deg: at 25 deg the penumbrae come from the hills
alone. Soft and hard shadows differ by a few grey levels on average, invisible at page size: fig-7.4 adds the
difference image |soft - hard| (x4) and, enlarged, the window where they differ most, hard beside soft.
Outputs: figures/pt/fig-7.3.png, figures/pt/fig-7.4.png.
"""
# %% [markdown]
# A shadow ray starts at the shaded point and marches towards the sun with the same vertical-gap steps as the view
# ray. The hard version only asks "did the ray hit the terrain?" (0 or 1). The soft version also remembers how close
# the ray came: the smallest k * gap / distance along the ray. A ray that skims a ridge at a small gap, close to the
# point, darkens it; one that passes far above does not -- a penumbra that widens with the distance to the occluder.

# %%
from __future__ import annotations

from dataclasses import replace
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from pywarp.terrain.settings import TerrainSettings  # noqa: E402
from pywarp.terrain.technique import TerrainTechnique  # noqa: E402

# shadow_min_step 0: the shadow rays step by the vertical gap as Kod 7.6 / 7.7 print it (the scene's default steps at
# least 1 unit, which changes the penumbrae by a few grey levels)
SCENE = dict(stage="atmosphere", sun_elevation_deg=25.0, sun_azimuth_deg=100.0, camera_pitch_deg=-12.0,
             shadow_min_step=0.0)


def _save(img, path, title):
    fig, ax = plt.subplots(figsize=(img.shape[1] / 100 + 0.2, img.shape[0] / 100 + 0.5))
    ax.imshow(img)
    ax.set_axis_off()
    ax.set_title(title)
    fig.savefig(path, dpi=100, bbox_inches="tight")
    plt.close(fig)


def main(out_dir, quick: bool = False) -> list[Path]:
    out_dir = Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    w, h = (128, 72) if quick else (800, 450)
    s = TerrainSettings(width=w, height=h, **SCENE)
    hard = TerrainTechnique(replace(s, shadows="hard")).render()
    soft = TerrainTechnique(replace(s, shadows="soft")).render()
    p3, p4 = out_dir / "fig-7.3.png", out_dir / "fig-7.4.png"
    _save(hard, p3, "hard shadows (Kod 7.6, t0 = 0.2)")
    _save_compared(soft, hard, p4)
    return [p3, p4]


def _penumbra_window(diff, wh):
    """(row, column) of the top-left corner of the wh = (height, width) window with the largest summed ``diff``."""
    c = np.pad(diff.cumsum(0).cumsum(1), ((1, 0), (1, 0)))
    h, w = wh
    sums = c[h:, w:] - c[:-h, w:] - c[h:, :-w] + c[:-h, :-w]
    return np.unravel_index(np.argmax(sums), sums.shape)


def _save_compared(soft, hard, path):
    """fig-7.4: the soft render, the difference |soft - hard| x 4 and the window where it is largest, enlarged."""
    diff = np.abs(soft.astype(int) - hard.astype(int)).max(axis=-1)
    h, w = soft.shape[:2]
    wh = (max(h // 5, 8), max(w // 5, 8))
    r, c = _penumbra_window(diff.astype(float), wh)
    fig = plt.figure(figsize=(12.0, 7.6))
    gs = fig.add_gridspec(2, 3, height_ratios=[1.0, 0.62], hspace=0.18, wspace=0.06, left=0.01, right=0.99,
                          top=0.93, bottom=0.01)
    ax = fig.add_subplot(gs[0, :2])
    ax.imshow(soft)
    ax.add_patch(plt.Rectangle((c - 0.5, r - 0.5), wh[1], wh[0], fill=False, ec="w", lw=1.5))
    ax.set_axis_off()
    ax.set_title("soft shadows (Kod 7.7, t0 = 0.02, k = 4); box: the window enlarged below")
    ax = fig.add_subplot(gs[0, 2])
    ax.imshow(np.minimum(diff * 4, 255), cmap="magma", vmin=0, vmax=255)
    ax.set_axis_off()
    ax.set_title(f"|soft − hard| × 4 (mean {diff.mean():.1f}, max {diff.max()} levels)", fontsize=10)
    for k, (img, name) in enumerate(((hard, "hard (7.3)"), (soft, "soft (7.4)"))):
        ax = fig.add_subplot(gs[1, k])
        ax.imshow(img[r:r + wh[0], c:c + wh[1]], interpolation="nearest")
        ax.set_axis_off()
        ax.set_title(f"{name}, enlarged: the penumbra", fontsize=10)
    ax = fig.add_subplot(gs[1, 2])
    ax.imshow(np.minimum(diff[r:r + wh[0], c:c + wh[1]] * 4, 255), cmap="magma", vmin=0, vmax=255,
              interpolation="nearest")
    ax.set_axis_off()
    ax.set_title("|soft − hard| × 4, enlarged", fontsize=10)
    fig.savefig(path, dpi=100)
    plt.close(fig)


if __name__ == "__main__":
    from pywarp.tutorial import run_as_script

    run_as_script(main, __doc__, "figures/pt")
