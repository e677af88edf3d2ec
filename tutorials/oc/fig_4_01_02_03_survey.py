"""Figures oc-fig-4.1, oc-fig-4.2 and oc-fig-4.3 in kind: a cloud base built with metaballs, one textured ellipsoid,
and several ellipsoids joined -- two of the survey methods of the oc text (§4.2, §4.3), which it describes without
formulas or parameters.

Fig. 4.1 (oc-4.2): twelve metaball sources (centres, radii and strengths drawn from seed 3 in a flattened heap) summed
with the soft-object kernel of pywarp.equation("oc-4.2") on a 64^3 grid; the field thresholded at 0.35 with a ramp
of 0.35 gives the base shape (left); "covered by a fractal method" (the text) as the field's threshold displaced by
a fractal noise inside the sources' reach (right): density = clamp((field - 0.45 + 1.5 n) / 0.2, 0, 1) where field > 0,
with n a Perlin fBm (pywarp.equation("vc-2.21"), 4 octaves from 4 cells per box width, seed 3, in metres-isotropic box
coordinates, about [-0.7, 0.7]), so the noise piles turrets on the blob's edge, eats gullies into it and throws off
small fragments (the core, up to 3.2, stays solid). Fig. 4.2 (oc-4.3): one ellipsoid (semi-axes 0.42, 0.26, 0.34
of the box) with the texturing function 0.5 + n (clamped to [0, 1]; n the same fBm, 5 octaves from 4 cells per box
width, seed 5: Perlin-type noise, as the text's OpenGL version of Gardner's sums of sines) and Gardner's translucency
(pywarp.equation("oc-4.3"), T1 = 0.25, D = 0.25). Fig. 4.3 (oc-4.3): five such ellipsoids joined (the largest opacity
wins). Figs. 4.2 and 4.3 show the ellipsoids' outlines (their projections over the
empty scene) beside the textured result. Every volume is uint8 (0 .. 255) and rendered by the volume renderer of the
flight scene
(pywarp.flight.volumes.render: emission-absorption raymarch, light volume towards a sun 35 deg high at azimuth 110 deg,
from the right; optical depth 0.3 per voxel, so the texture's holes read as holes).
Outputs: figures/oc/fig-4.1.png, figures/oc/fig-4.2.png, figures/oc/fig-4.3.png.
"""
# %% [markdown]
# Before the project settles on procedural noise (§5), the text surveys other ways of modelling clouds. Two of them
# build a density field from simple primitives:
#
# * **metaballs** (§4.2): sources with a centre, a radius and a strength whose fields add up; a threshold on the sum
#   gives a blobby surface. The text notes that metaballs alone make poor clouds and are used for the *base shape*,
#   then covered by a fractal or a texture;
# * **textured ellipsoids** (§4.3, Gardner 1985): an ellipsoid whose opacity is a texturing function (sums of sines in
#   the original; Perlin-type noise in an OpenGL version) with a translucency that fades towards the ellipsoid's
#   surface, so the outline dissolves; several ellipsoids make one cloud.
#
# Neither comes with formulas in the text: the kernels used here are Wyvill's soft objects and Gardner's translucency.

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
from pywarp.kernels import volume as V  # noqa: E402
from pywarp.flight import volumes as VS  # noqa: E402
from pywarp.tutorial import fit_text  # noqa: E402

EXTENT = (100.0, 60.0, 100.0)  # box of every volume [m]; the camera looks at it from about 120 m
SQUASH = 0.6  # the box's height / width: box-unit y times this is isotropic in metres


def grid_points(n: int) -> np.ndarray:
    """Voxel centres of an n^3 grid in box units [0, 1], shape (n, n, n, 3) as (x, y, z), indexed [z, y, x]."""
    c = (np.arange(n, dtype=np.float32) + 0.5) / n
    z, y, x = np.meshgrid(c, c, c, indexing="ij")
    return np.stack([x, y, z], axis=-1)


def fbm(p: np.ndarray, cells: float, seed: int, octaves: int = 5) -> np.ndarray:
    """Perlin fBm (pywarp.equation("vc-2.21"), about [-0.7, 0.7]) at box-unit points p (..., 3), ``cells`` lattice
    cells per box width, y squeezed by SQUASH so that the features are round in metres."""
    q = (p * np.float32([1.0, SQUASH, 1.0])).reshape(-1, 3)
    n = pywarp.equation("vc-2.21")(q[:, 0], q[:, 1], q[:, 2], octaves, float(cells), seed)
    return np.asarray(n, np.float32).reshape(p.shape[:-1])


def to_u8(density: np.ndarray) -> np.ndarray:
    return np.clip(np.round(np.asarray(density, np.float64) * 255.0), 0, 255).astype(np.uint8)


# %% [markdown]
# **Metaballs.** Each source adds strength (1 - r^2/R^2)^3 inside its radius R; the sum is a smooth field. Where it
# exceeds a threshold there is cloud; a ramp above the threshold gives soft edges.

# %%
def metaball_field(n: int, seed: int = 3, count: int = 12) -> np.ndarray:
    rng = np.random.default_rng(seed)
    p = grid_points(n)
    field = np.zeros(p.shape[:3], np.float32)
    for _ in range(count):
        centre = np.array([rng.uniform(0.25, 0.75), rng.uniform(0.3, 0.5), rng.uniform(0.3, 0.7)], np.float32)
        radius = np.float32(rng.uniform(0.16, 0.28))
        strength = np.float32(rng.uniform(0.6, 1.0))
        # the box is flattened (60 m high, 100 m wide): distances in metres-like box units, y squeezed
        d = np.linalg.norm((p - centre) * np.float32([1.0, 0.6, 1.0]), axis=-1).astype(np.float32)
        field += pywarp.equation("oc-4.2")(d, radius, strength)
    return field


# %% [markdown]
# **Textured ellipsoids.** The opacity of Gardner's ellipsoid: with q = |p / radii|^2 and g = 1 - q,
# opacity = clamp((texture - T1 - D (1 - g)) / D, 0, 1). Near the centre the texture decides alone; towards the
# surface the texture must be ever larger to show, so the edge breaks up into the texture's pattern.

# %%
def ellipsoid_opacity(p: np.ndarray, centre, radii, texture: np.ndarray) -> np.ndarray:
    rel = (p - np.float32(centre)).reshape(-1, 3).astype(np.float32)
    op = pywarp.equation("oc-4.3")(rel, np.float32(radii), texture.reshape(-1), 0.25, 0.25)
    return np.asarray(op).reshape(p.shape[:3])


ORIGIN = (-EXTENT[0] / 2, 40.0, -EXTENT[2] / 2)  # the box's corner [m]


def camera(width: int, height: int):
    eye = np.array([0.0, 80.0, 118.0])
    return CAM.camera_look_at(eye, np.array([0.0, 68.0, 0.0]), (0.0, 1.0, 0.0), math.radians(45.0), width / height,
                              0.1, 1e5)


def render_volume(density: np.ndarray, width: int, height: int) -> np.ndarray:
    values = VOLUME_PARAMS.defaults()
    values["sky_zenith"], values["sky_horizon"] = (0.20, 0.38, 0.70), (0.55, 0.68, 0.86)
    # the sun from the right and a little behind, 35 deg high: lit right sides, shaded left and bottom; the ground's
    # noise cells of 30 m for a ground seen from 150 m
    values["sun"] = V.sun_direction(35.0, 110.0)
    values["field_size"] = 30.0
    values["tau_per_voxel"] = 0.3  # a little thinner than the flight scene's 0.35: holes and turrets read
    vs = VS.VolumeSet([VS.PlacedVolume(density, ORIGIN, EXTENT)])
    vs.compute_light(values)
    return VS.render(vs, values, camera(width, height), width, height)


def ellipse_outline(centre, radii, width: int, height: int) -> np.ndarray:
    """The outline of an ellipsoid (box units) in the image of :func:`camera`: the convex hull of its projected
    surface (the projection of an ellipsoid is convex), closed, pixel coordinates (k, 2)."""
    from scipy.spatial import ConvexHull

    th, ph = np.meshgrid(np.linspace(0, np.pi, 48), np.linspace(0, 2 * np.pi, 96), indexing="ij")
    unit = np.stack([np.sin(th) * np.cos(ph), np.cos(th), np.sin(th) * np.sin(ph)], axis=-1).reshape(-1, 3)
    world = np.float64(ORIGIN) + (np.float64(centre) + unit * np.float64(radii)) * np.float64(EXTENT)
    clip = np.c_[world, np.ones(len(world))] @ camera(width, height).view_proj.astype(np.float64).T
    ndc = clip[:, :2] / clip[:, 3:]
    px = np.stack([(ndc[:, 0] + 1) * 0.5 * width, (1 - ndc[:, 1]) * 0.5 * height], axis=-1)
    hull = px[ConvexHull(px).vertices]
    return np.vstack([hull, hull[:1]])


def save_with_outlines(background: np.ndarray, result: np.ndarray, ellipsoids, title: str, path: Path) -> Path:
    """Two panels: the ellipsoids' outlines over the empty scene (left) and the textured result (right)."""
    h, w = result.shape[:2]
    fig = plt.figure(figsize=(2 * w / 100, h / 100 + 0.35), dpi=100)
    for k, (img, label) in enumerate(((background, "the ellipsoids"), (result, "textured, Gardner translucency"))):
        ax = fig.add_axes([k * 0.5, 0, 0.5, h / (h + 35)])
        ax.imshow(img)
        if k == 0:
            for centre, radii in ellipsoids:
                o = ellipse_outline(centre, radii, w, h)
                ax.plot(o[:, 0], o[:, 1], color="white", lw=1.2)
        ax.text(6, 14, label, color="white", fontsize=8)
        ax.set_xlim(0, w)
        ax.set_ylim(h, 0)
        ax.axis("off")
    fig.text(0.5, 1 - 17 / (h + 35), title, ha="center", va="center", fontsize=9)
    fit_text(fig)  # a title wider than a small (quick) image: smaller, wrapped, its band taller
    fig.savefig(path, dpi=100)
    plt.close(fig)
    return path


def save(img: np.ndarray, title: str, path: Path) -> Path:
    h, w = img.shape[:2]
    fig = plt.figure(figsize=(w / 100, h / 100 + 0.35), dpi=100)
    ax = fig.add_axes([0, 0, 1, h / (h + 35)])
    ax.imshow(img)
    ax.axis("off")
    fig.text(0.5, 1 - 17 / (h + 35), title, ha="center", va="center", fontsize=9)
    fit_text(fig)  # a title wider than a small (quick) image: smaller, wrapped, its band taller
    fig.savefig(path, dpi=100)
    plt.close(fig)
    return path


def main(out_dir, quick: bool = False) -> list[Path]:
    out_dir = Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    n = 32 if quick else 64
    w, h = (160, 100) if quick else (480, 300)
    p = grid_points(n)
    written = []

    # fig 4.1: the metaball base, and the base covered by fractal noise (the threshold displaced by it)
    field = metaball_field(n)
    base = np.clip((field - 0.35) / 0.35, 0, 1)
    covered = np.where(field > 0, np.clip((field - 0.45 + 1.5 * fbm(p, 4.0, 3, 4)) / 0.2, 0, 1), 0.0)
    img = np.concatenate([render_volume(to_u8(base), w, h), render_volume(to_u8(covered), w, h)], axis=1)
    written.append(save(img, "metaball cloud base (12 sources, threshold 0.35)  |  the base covered by fractal noise",
                        out_dir / "fig-4.1.png"))

    # the texturing function of the ellipsoids: a high-contrast fBm in [0, 1]
    noise = np.clip(0.5 + 1.0 * fbm(p, 4.0, 5), 0.0, 1.0).astype(np.float32)

    # fig 4.2: one textured ellipsoid, its outline beside it
    empty = render_volume(np.zeros((n, n, n), np.uint8), w, h)
    single = [((0.5, 0.5, 0.5), (0.42, 0.26 / 0.6, 0.34))]
    one = ellipsoid_opacity(p, *single[0], noise)
    written.append(save_with_outlines(empty, render_volume(to_u8(one), w, h), single,
                                      "one ellipsoid: noise texture, Gardner translucency (T1 0.25, D 0.25)",
                                      out_dir / "fig-4.2.png"))

    # fig 4.3: several ellipsoids joined, their outlines beside them
    parts = [((0.5, 0.45, 0.5), (0.30, 0.30, 0.26)), ((0.28, 0.38, 0.52), (0.20, 0.22, 0.18)),
             ((0.72, 0.40, 0.46), (0.22, 0.25, 0.20)), ((0.45, 0.68, 0.48), (0.18, 0.25, 0.16)),
             ((0.62, 0.62, 0.58), (0.15, 0.22, 0.14))]
    parts = [(centre, (radii[0], radii[1] / 0.6, radii[2])) for centre, radii in parts]
    joined = np.zeros(p.shape[:3], np.float32)
    for centre, radii in parts:
        joined = np.maximum(joined, ellipsoid_opacity(p, centre, radii, noise))
    written.append(save_with_outlines(empty, render_volume(to_u8(joined), w, h), parts,
                                      "five textured ellipsoids joined (max of the opacities)",
                                      out_dir / "fig-4.3.png"))
    return written


if __name__ == "__main__":
    from pywarp.tutorial import run_as_script

    run_as_script(main, __doc__, "figures/oc")
