"""Figure rr-fig-3.10: influence of point lights on very large drops (rr-A1, rr-A2, rr-A3, rr-CF) -- external
reflection A1*A2, internal reflection A1*A3, their sum (each term on its own scale), and the final colour C_F over
the refracted background (rr-alg-3.1), for a spherical and a 4.5 mm Beard-Chuang drop with the normals of its exact mask. The text describes
this model but never implemented it. Output: figures/rr/fig-3.10.png.
"""
# %% [markdown]
# The light model of rr §3.2.4 adds, per point light, A1 (A2 + A3) to the refracted colour C_O times the ambient
# light: A1 = C_L DistFact (V_PE . V_N) is the most a light can change the pixel (normals facing the eye get more),
# A2 = max(0, V_PL . V_N) the external reflection back towards the light, A3 the light that leaves after internal
# reflections upward or downward (fig. 3.9). The text leaves DistFact open: here 1 / (1 + (d / r_half)^2) with
# r_half = 4 drop radii; and it gives no normal source (the masks hold refraction vectors): the normals come from
# the drop's shape, the entry normals of `drop_mask(..., normals=True)`.
#
# Two lights: a warm one up left in front of the drop, a cool one to the right and slightly behind it. The capture is
# a synthetic landscape (sky, hills, ground); any scene's capture works the same way.

# %%
from __future__ import annotations

from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import pywarp  # noqa: E402
from pywarp.rain import drops  # noqa: E402

LIGHTS = ((np.array([-2.5, 2.5, -3.0]), np.array([1.0, 0.75, 0.45])),
          (np.array([3.0, 0.5, 1.0]), np.array([0.45, 0.65, 1.0])))
R_HALF = 4.0
AMBIENT = np.array([0.75, 0.75, 0.8])


def landscape(h, w):
    """A synthetic capture: sky gradient, a sun, hills, ground with stripes (rows from the top)."""
    y, x = np.mgrid[0:h, 0:w] / np.array([h, w])[:, None, None]
    img = np.empty((h, w, 3), np.float32)
    sky = np.stack([0.35 + 0.4 * y, 0.55 + 0.3 * y, 0.95 - 0.1 * y], -1)
    img[:] = sky
    sun = (x - 0.7) ** 2 + (y - 0.25) ** 2 < 0.004
    img[sun] = (1.0, 0.95, 0.7)
    hill = y > 0.5 + 0.08 * np.sin(9 * x) + 0.04 * np.sin(23 * x)
    img[hill] = np.stack([0.2 + 0.1 * np.sin(40 * x), 0.45 + 0.1 * y, 0.2 * np.ones_like(x)], -1)[hill]
    ground = y > 0.75
    img[ground] = np.stack([0.55 + 0.15 * (np.sin(60 * x * y) > 0), 0.42 * np.ones_like(x), 0.3 * np.ones_like(x)],
                           -1)[ground]
    return img


def main(out_dir, quick: bool = False) -> list[Path]:
    out_dir = Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    size = 96 if quick else 320
    capture = landscape(128 if quick else 512, 128 if quick else 512)
    fig, axes = plt.subplots(2, 5, figsize=(17, 7.4), dpi=80 if quick else 110)
    for row, (label, method, a) in enumerate((("sphere", "sphere", 1.0), ("4.5 mm Beard-Chuang (exact mask)",
                                                                          "exact", 4.5))):
        mask, normals = drops.drop_mask(size, a, method=method, normals=True)
        inside = mask[..., 3] > 0

        # %% [markdown]
        # The refracted colour C_O of every drop pixel (rr-alg-3.1), a drop straight ahead, 150 deg capture.

        # %%
        c_o = pywarp.rain_shade_drop(capture, mask, [0.0, 0.0, -1.0], angular_radius=0.02, out_size=size)[..., :3]
        # pixel positions on the drop, in drop radii: the mask frame, z of the entry point from the normal's sphere
        j, i = np.meshgrid(np.arange(size), np.arange(size))
        u, v = 2 * (j + 0.5) / size - 1, 1 - 2 * (i + 0.5) / size
        p = np.stack([u, v, -np.sqrt(np.clip(1 - u * u - v * v, 0, 1))], -1)
        n = np.where(inside[..., None], normals, [0.0, 0.0, -1.0])
        n = n / np.linalg.norm(n, axis=-1, keepdims=True)
        eye = np.array([0.0, 0.0, -40.0])
        v_pe = (eye - p) / np.linalg.norm(eye - p, axis=-1, keepdims=True)
        ext, intl = np.zeros(p.shape), np.zeros(p.shape)
        for lpos, lcol in LIGHTS:
            d = lpos - p
            dist = np.linalg.norm(d, axis=-1)
            v_pl = d / dist[..., None]
            a1 = pywarp.rain_light_a1(lcol, dist, v_pe, n, R_HALF)
            ext += a1 * pywarp.rain_light_a2(v_pl, n)[..., None]
            intl += a1 * pywarp.rain_light_a3(v_pl, n)[..., None]
        (l1, c1), (l2, c2) = LIGHTS
        final = pywarp.rain_light_colour(c_o, AMBIENT, p, n, eye, l1, c1, l2, c2, R_HALF)
        panels = (("C_O (refraction only)", c_o), ("external: A1 A2", ext), ("internal: A1 A3", intl),
                  ("sum A1 (A2 + A3)", ext + intl), ("final C_F (rr-CF)", final))
        # %% [markdown]
        # The light terms are small beside C_O (the internal one ~1/10 of the external): each term panel is shown
        # with its own scale -- its brightest drop pixel (99.5th percentile) to white -- written under its title, so
        # that each term's shape is visible; C_O and C_F are shown as they are.

        # %%
        for k, (ax, (title, img)) in enumerate(zip(axes[row], panels)):
            scale = 1.0
            if 0 < k < len(panels) - 1:
                peak = np.percentile(img[inside].max(axis=-1), 99.5)
                scale = 1.0 / peak if peak > 0 else 1.0
                title = f"{title}   (shown x{scale:.3g})"
            shown = np.where(inside[..., None], np.clip(img * scale, 0, 1), 0.12)
            ax.imshow(shown, interpolation="nearest")
            ax.set_title(f"{title}\n{label}", fontsize=9)
            ax.axis("off")
    fig.suptitle("Light-drop interaction (rr-A1..A3, rr-CF; described by the text, implemented here): two point "
                 "lights, DistFact = 1/(1 + (d/r_half)^2), normals from the drop's shape; each light term on its own scale",
                 fontsize=11)
    fig.subplots_adjust(left=0.01, right=0.99, top=0.87, bottom=0.01, wspace=0.05, hspace=0.2)
    out = out_dir / "fig-3.10.png"
    fig.savefig(out)
    plt.close(fig)
    return [out]


if __name__ == "__main__":
    from pywarp.tutorial import run_as_script

    run_as_script(main, __doc__, "figures/rr")
