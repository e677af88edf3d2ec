"""Figures oc-fig-5.11, oc-fig-5.12, oc-fig-5.15 and oc-fig-5.16: the cloud array rendered as a volume -- the noise
without filtering (5.11), filtered without the border fix (5.12, the border problem; cover 112 there), noise + filter +
larger array (5.15), and several clouds, scaled per axis, in one scene (5.16).

The arrays are the library's (pywarp.flight.clouds): oc-5.2.1 (size/8 -> size up-sampling with added noise), the
filter oc-5.2.2, border 'none' (oc-5.2.3), 'sin' (the rejected rounding oc-5.2.3.1, beside 5.12) and 'zero' (the
larger array, oc-5.2.3.2), per-axis scaling oc-5.2.3-scale. Figs. 5.11 and 5.12 use the cloud array's defaults (cover
128, sharpness 0.96 -- the text gives no values) and a small orthographic emission-absorption raymarch written in this
tutorial with NumPy (light from above through the volume, ambient term, blue-sky background). Figs. 5.15 and 5.16 use
the flight scene's cloud settings (FlightSettings: cover 50, sharpness 0.92, raw lattice noise, the falloff envelope
0.5 with its base at 0.35 -- the envelope is beyond the text, cclouds/voxel.h) and the flight scene's volume renderer
(pywarp.flight.volumes.render: the sun through each cloud's light volume, the Henyey-Greenstein phase, the generated
ground) -- the stand-in for SimVoleon, which the text displays them with. Outputs: figures/oc/fig-5.11.png,
figures/oc/fig-5.12.png, figures/oc/fig-5.15.png, figures/oc/fig-5.16.png.
"""
# %% [markdown]
# The noise array is a fog that fills its whole box (fig. 5.11). The exponential filter cuts a cloud out of it:
# voxels whose noise lies below `cover` (in 0..255 units) become transparent, the rest rise toward opaque the faster
# the smaller `sharpness` is. Without precautions the cloud is cut flat by the faces of the box (fig. 5.12): the
# border values of the coarse arrays survive every interpolation (fig. 5.13). Attenuating toward the faces with a
# sine removes the cut but leaves a rounded box (the author rejected it); keeping a zero border at every level lets
# the noise itself fall to zero on all sides. A falloff envelope (beyond the text: the noise lowered by 0.5 times the
# squared radius of the ellipsoid inscribed in the box) keeps the cloud well inside, so it takes a compact, rounded
# shape of its own (fig. 5.15). A larger `cover` gives
# *less* cloud -- the text's "how big a cloud we want" reads inverted.

# %%
from __future__ import annotations

from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from scipy import ndimage  # noqa: E402

from pywarp.flight.clouds import CloudArraySettings, cloud_volume, noise_volume, scale_volume  # noqa: E402
from pywarp.flight.settings import FlightSettings  # noqa: E402


def render_scene(volumes, width: int, height: int, eye, target, fov: float) -> np.ndarray:
    """The flight scene's volume renderer (pywarp.flight.volumes.render, its default look: sun 35 deg high at azimuth
    150 deg, the generated ground) of ``volumes`` = [(uint8 [z, y, x] with y up, origin, extent)], seen from ``eye``
    towards ``target`` [m] with a vertical field of view ``fov`` [deg]. uint8 sRGB."""
    import math

    from pywarp.flight import volumes as VS
    from pywarp.kernels import camera as CAM

    values = FlightSettings().c_values()
    vs = VS.VolumeSet([VS.PlacedVolume(v, o, e) for v, o, e in volumes])
    vs.compute_light(values)
    cam = CAM.camera_look_at(np.array(eye, float), np.array(target, float), (0.0, 1.0, 0.0), math.radians(fov),
                             width / height, 0.1, 1e5)
    return VS.render(vs, values, cam, width, height)


def render(vol, size=200, steps=160, tau=20.0, yaw=35.0, pitch=25.0, zoom=1.0, aspect=1.0):
    """Orthographic emission-absorption raymarch of a uint8 volume [z, y, x] (z up), NumPy; an image of ``size``
    rows and ``size * aspect`` columns framing the whole box (half its diagonal, over ``zoom``). ``tau``: optical
    depth of an opaque voxel run across the box's longest edge. The sun is straight above: the light reaching a voxel
    is exp(-optical depth from the top of the box). Sky gradient behind."""
    nz, ny, nx = vol.shape
    n = max(vol.shape)
    sig = vol.astype(np.float64) / 255.0 * tau / n
    lit = np.exp(-(np.cumsum(sig[::-1], axis=0)[::-1] - 0.5 * sig))
    cy, sy = np.cos(np.radians(yaw)), np.sin(np.radians(yaw))
    cp, sp = np.cos(np.radians(pitch)), np.sin(np.radians(pitch))
    fwd = np.array([cp * sy, cp * cy, -sp])
    right = np.array([cy, -sy, 0.0])
    up = np.cross(right, fwd)
    centre = np.array([nx, ny, nz]) / 2.0 - 0.5
    diag = float(np.sqrt(nx * nx + ny * ny + nz * nz))
    half = 0.5 * diag / zoom
    uu, vv = np.meshgrid(np.linspace(-half * aspect, half * aspect, int(round(size * aspect))),
                         np.linspace(half, -half, size))
    ts = np.linspace(-0.5 * diag, 0.5 * diag, steps)
    dt = ts[1] - ts[0]
    radiance, trans = np.zeros(uu.shape), np.ones(uu.shape)
    for t in ts:
        p = centre + uu[..., None] * right + vv[..., None] * up + t * fwd
        coords = np.stack([p[..., 2], p[..., 1], p[..., 0]])
        a = 1.0 - np.exp(-ndimage.map_coordinates(sig, coords, order=1, cval=0.0) * dt)
        light = ndimage.map_coordinates(lit, coords, order=1, cval=1.0)
        radiance += trans * a * (0.85 * light + 0.45)
        trans *= 1.0 - a
    h = np.linspace(0, 1, uu.shape[0])[:, None, None]
    sky = np.array([0.28, 0.48, 0.85]) * (1 - h) + np.array([0.72, 0.83, 0.96]) * h
    return np.clip(sky * trans[..., None] + np.minimum(radiance, 1.2)[..., None] * np.array([1.0, 0.99, 0.97]), 0, 1)


def _save(fig, path):
    fig.savefig(path)
    plt.close(fig)
    return path


def main(out_dir, quick: bool = False) -> list[Path]:
    out_dir = Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    size = 32 if quick else 64
    px, steps = (72, 48) if quick else (260, 200)
    dpi = 70 if quick else 110
    s = CloudArraySettings(size=size, seed=1)
    outs = []

    # %% [markdown]
    # Fig. 5.11: the noise before filtering, as opacities round(255 n), border 'none' -- the fog-filled box.

    # %%
    fog = np.round(noise_volume(s, border="none") * 255).astype(np.uint8)
    fig, ax = plt.subplots(figsize=(5, 5.3), dpi=dpi)
    ax.imshow(render(fog, px, steps, tau=6.0))
    ax.set_title("oc fig. 5.11: noise without filtering", fontsize=10)
    ax.axis("off")
    outs.append(_save(fig, out_dir / "fig-5.11.png"))

    # %% [markdown]
    # Fig. 5.12: filtered without the border fix: the cloud is cut by the box faces; next to it the rejected SIN
    # rounding (radius size/8): no cut faces, but the cloud keeps the box's rounded outline. A cover of 112 (instead
    # of the default 128) leaves more cloud, so that more of it meets the faces.

    # %%
    cut = cloud_volume(s, border="none", cover=112.0)
    rounded = cloud_volume(s, border="sin", cover=112.0)
    faces = np.concatenate([cut[0].ravel(), cut[-1].ravel(), cut[:, 0].ravel(), cut[:, -1].ravel(),
                            cut[:, :, 0].ravel(), cut[:, :, -1].ravel()])
    fig, axes = plt.subplots(1, 2, figsize=(10, 5.3), dpi=dpi)
    axes[0].imshow(render(cut, px, steps))
    axes[0].set_title(f"filtered, no border fix: {np.count_nonzero(faces)} face voxels > 0", fontsize=9)
    axes[1].imshow(render(rounded, px, steps))
    axes[1].set_title("rejected remedy: SIN rounding near the faces", fontsize=9)
    for ax in axes:
        ax.axis("off")
    fig.suptitle("oc fig. 5.12: noise with filtering -- the border problem", fontsize=11)
    fig.tight_layout()
    outs.append(_save(fig, out_dir / "fig-5.12.png"))

    # %% [markdown]
    # Fig. 5.15: noise + filter + larger array, with the flight scene's cloud settings (FlightSettings: cover 80,
    # sharpness 0.92, raw lattice noise, and the falloff envelope 0.2 -- beyond the text, ``cclouds/voxel.h``): every
    # face voxel is 0, the cloud ends inside its box, its outline is the noise's. The three interpolations of the
    # up-sampling side by side (the text: the cubic "differs only in small details" from the cosine), rendered by the
    # flight scene's volume renderer: sun light through the cloud's light volume and the Henyey-Greenstein phase (lit
    # tops, darker bases).

    # %%
    fs = FlightSettings()
    look = dict(cover=fs.cloud_cover, sharpness=fs.cloud_sharpness, smoothing=fs.cloud_smoothing,
                envelope=fs.cloud_envelope, envelope_base=fs.cloud_envelope_base)
    w, h = (96, 72) if quick else (400, 300)
    fig, axes = plt.subplots(1, 3, figsize=(3 * w / 100 + 0.3, h / 100 + 0.6), dpi=100)
    for ax, kind in zip(axes, ("linear", "cosine", "cubic")):
        cloud = cloud_volume(s, interpolation=kind, **look)
        assert cloud[0].max() == 0 and cloud[:, :, -1].max() == 0
        box = (-50.0, 0.0, -50.0), (100.0, 50.0, 100.0)
        ax.imshow(render_scene([(cloud, *box)], w, h, eye=(0.0, 28.0, 140.0), target=(0.0, 24.0, 0.0), fov=40.0))
        ax.set_title(f"{kind} up-sampling\n{np.count_nonzero(cloud) / cloud.size:.0%} of the voxels",
                     fontsize=6 if quick else 9)
        ax.axis("off")
    fig.suptitle("oc fig. 5.15: noise + filtering + larger array (+ envelope)", fontsize=7 if quick else 11)
    fig.tight_layout()
    outs.append(_save(fig, out_dir / "fig-5.15.png"))

    # %% [markdown]
    # Fig. 5.16: several clouds in one scene, each its own seed and per-axis scale (oc-5.2.3-scale: the uint8 array
    # is resampled, corners aligned, so the zero border stays zero), placed in boxes of their scaled shape (1 voxel =
    # 1.6 m) over the generated ground, rendered as in the flight scene.

    # %%
    layout = [(2, (1.6, 0.7, 1.3), (-190.0, 0.0)), (3, (1.1, 0.9, 1.1), (-10.0, -140.0)),
              (5, (1.3, 0.55, 1.0), (160.0, -10.0)), (7, (2.0, 0.8, 1.6), (-330.0, -600.0))]
    placed = []
    for seed, scale, (x, z) in layout:
        c = scale_volume(cloud_volume(s, seed=seed, **look), scale)  # (x, y, z) factors, y up
        ext = tuple(1.6 * n for n in c.shape[::-1])  # (x, y, z) metres: 1.6 m per voxel on every axis
        placed.append((c, (x - ext[0] / 2, 420.0, z - ext[2] / 2), ext))
    w, h = (160, 68) if quick else (960, 400)
    fig = plt.figure(figsize=(w / 100, h / 100 + 0.35), dpi=100)
    ax = fig.add_axes([0, 0, 1, h / (h + 35)])
    ax.imshow(render_scene(placed, w, h, eye=(0.0, 470.0, 330.0), target=(0.0, 440.0, -100.0), fov=50.0))
    ax.axis("off")
    label = "oc fig. 5.16: clouds in the scene, per-axis scaled (x, y, z): " + ", ".join(f"{sc}" for _, sc, _ in layout)
    if quick:  # a 160 px wide figure: the caption alone
        label = "oc fig. 5.16: scaled clouds"
    fig.text(0.5, 1 - 17 / (h + 35), label, ha="center", va="center", fontsize=7 if quick else 10)
    outs.append(_save(fig, out_dir / "fig-5.16.png"))
    return outs


if __name__ == "__main__":
    from pywarp.tutorial import run_as_script

    run_as_script(main, __doc__, "figures/oc")
