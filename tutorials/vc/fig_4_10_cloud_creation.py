"""Figure vc-fig-4.10: visualization of cloud creation -- where clouds may form and the shape the noise gives them
(reproducible in kind).

The density at a sample point (vc-A17), step by step on a vertical slice through the cloud layer: the weather map's
coverage D_h (red channel, vc-A12) times the height gradient D_v of the local cloud type (vc-4.7 with the type blend
vc-A16, at the relative height vc-A15) restricts where clouds may exist; the base-shape texture gives B (vc-2.28);
coverage and profile are applied with B_D = remap(B D_v, C, 1, 0, 1) D_h (vc-2.29, remap vc-2.27, C := 1 - D_h as in
the renderer; panel (g) shows the literal reading C := D_h); the curl-displaced detail texture erodes the edges into
the final density (vc-2.30). Each step is computed
with the public registry functions (pywarp.clouds_relative_height, pywarp.clouds_height_gradient, pywarp.clouds_base_shape,
pywarp.clouds_coverage, pywarp.clouds_detail_erosion) on texture values read from the renderer's own textures
(pywarp.clouds.cloudscape.RenderTextures) with the renderer's world scales
(pywarp.clouds.settings.CloudscapeSettings.c_values), so the slice is the density the renderer marches (up to float32 rounding: the texture lookups here are NumPy float64 re-implementations
of the renderer's wrap-around bilinear / trilinear samplers). A render of the same clouds from above marks the slice.

Parameters (none are given in the thesis): the renderer's defaults (layer 1.5-4 km, texture sizes 128^3 / 32^3 /
128^2 / 512^2, its world scales of the textures -- read from pywarp.clouds.settings.CloudscapeSettings.c_values and
printed in the figure -- and clamped height gradients), coverage 0.45, cloud type 0.75, seed 0, sun 30° up at azimuth 120°; slice
z = -22 km, x = -20 .. 20 km; camera 12 km up at (0, -6) km looking 30° down along -z (60° vertical field of view),
640x360. The last slice row is not what the renderer does: it shows the same step with the threshold C := 1 - D_h,
the reading most other implementations use (spec vc-2.29 note 2), for contrast. Output: figures/vc/fig-4.10.png.
"""
# %% [markdown]
# How does the renderer decide where a cloud is? For every sample point p along a view ray (vc-A17):
#
# 1. The **weather map** is read at the point's ground position (x, z): red = coverage D_h (0: never a cloud here),
#    blue = cloud type. The relative height h in the layer (0 at the base, 1 at the top) gives the **height gradient**
#    D_v(h, type): stratus only low in the layer, cumulus through most of it. The product D_h·D_v is the envelope:
#    where it is 0 no cloud can exist, whatever the noise says.
# 2. The **base shape** B comes from the 128³ base texture (Perlin–Worley noise eroded by a Worley fBm, 2.28).
# 3. Profile and coverage are applied: B_D = remap(B·D_v, C, 1, 0, 1)·D_h (2.29). Everything of B·D_v below the
#    threshold C is cut away, the rest is stretched to [0, 1] and scaled by the coverage. The thesis does not define C;
#    the renderer uses C = D_h, the GPU Pro 7 form the thesis cites.
# 4. The **detail erosion** (2.30) subtracts the high-frequency detail texture (read at curl-displaced coordinates, so
#    the edges look wind-blown) from the edges: density C = remap(B_D, 0.2·M, 1, 0, 1).
#
# The slice makes one consequence of reading 3 with C = D_h visible: where the coverage is high the threshold is high
# too, and at D_h ≥ B·D_v everything is cut. The cores of the coverage blobs are empty; clouds grow only where
# 0 < D_h < B·D_v, in rings along the blob edges — exactly what the render from above shows.

# %%
from __future__ import annotations

from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import pywarp  # noqa: E402
from pywarp.clouds.cloudscape import CloudscapeSettings  # noqa: E402
from pywarp.clouds.technique import CloudscapeTechnique  # noqa: E402
from pywarp.core.pose import Pose  # noqa: E402

# the weather map's one periodic lookup (weather_detile off), so that the top view (a), the slices and the render
# (b) show the same clouds; the threshold C of vc-2.29 is the renderer's default reading, C := 1 - D_h
SCENE = dict(coverage=0.45, cloud_type=0.75, seed=0, sun_elevation_deg=30.0, sun_azimuth_deg=120.0,
             weather_detile=False, coverage_threshold="one_minus_coverage")
FULL = dict(width=640, height=360)
QUICK = dict(width=96, height=54, base_size=32, detail_size=16, curl_size=32, weather_size=64)
SLICE_Z_KM = -22.0
SLICE_X_KM = (-20.0, 20.0)
SLICE_Y_KM = (1.4, 4.1)  # altitudes shown: the layer (1.5-4 km) and a little outside it
MAP_HALF_KM = 24.0  # panel (a) shows x, z in [-24, 24] km
POSE = Pose(x=0.0, y=12.0, z=-6.0, yaw_deg=0.0, pitch_deg=-30.0, fov_y_deg=60.0)


# %% [markdown]
# The textures tile: a coordinate of 1 is one period, texel centres sit at (i + ½)/n, and indices wrap around. These
# two samplers reproduce the renderer's bilinear (weather map, curl) and trilinear (base, detail) lookups in NumPy.

# %%
def _axis(u: np.ndarray, n: int):
    x = u * n - 0.5  # texel centres at i + 0.5
    f = np.floor(x)
    i0 = f.astype(np.int64) % n
    return i0, (i0 + 1) % n, (x - f)[..., None]


def bilinear_wrap(tex: np.ndarray, u: np.ndarray, v: np.ndarray) -> np.ndarray:
    """tex[y, x, c] sampled at (u, v) with wrap-around."""
    n = tex.shape[0]
    x0, x1, tx = _axis(u, n)
    y0, y1, ty = _axis(v, n)
    return (tex[y0, x0] * (1 - tx) + tex[y0, x1] * tx) * (1 - ty) + (tex[y1, x0] * (1 - tx) + tex[y1, x1] * tx) * ty


def trilinear_wrap(tex: np.ndarray, u: np.ndarray, v: np.ndarray, w: np.ndarray) -> np.ndarray:
    """tex[z, y, x, c] sampled at (u, v, w) with wrap-around."""
    n = tex.shape[0]
    x0, x1, tx = _axis(u, n)
    y0, y1, ty = _axis(v, n)
    z0, z1, tz = _axis(w, n)

    def row(z, y):
        return tex[z, y, x0] * (1 - tx) + tex[z, y, x1] * tx

    return ((row(z0, y0) * (1 - ty) + row(z0, y1) * ty) * (1 - tz)
            + (row(z1, y0) * (1 - ty) + row(z1, y1) * ty) * tz)


def f32(a) -> np.ndarray:
    return np.asarray(a, dtype=np.float32)


def density_slice(tex, p: dict, nx: int, ny: int) -> dict:
    """Every stage of vc-A17 on the vertical slice z = SLICE_Z_KM (rows: altitude from top to bottom)."""
    x = np.linspace(*SLICE_X_KM, nx)
    y = np.linspace(*SLICE_Y_KM, ny)[::-1]
    X, Y = np.meshgrid(x, y)
    Z = np.full_like(X, SLICE_Z_KM)
    c = np.asarray(p["centre"], dtype=np.float64)
    radius = np.sqrt((X - c[0]) ** 2 + (Y - c[1]) ** 2 + (Z - c[2]) ** 2)
    h = pywarp.clouds_relative_height(f32(radius), p["r_inner"], p["r_outer"])  # vc-A15
    inside = (h >= 0.0) & (h <= 1.0)
    # weather map (vc-A12), planar projection: R coverage D_h, B cloud type
    wm = bilinear_wrap(tex.weather, (X + p["weather_offset"][0]) / p["weather_scale_km"],
                       (Z + p["weather_offset"][1]) / p["weather_scale_km"])
    d_h = f32(wm[..., 0])
    d_v = pywarp.clouds_height_gradient(f32(np.clip(h, 0.0, 1.0)), f32(wm[..., 2]), clamp=bool(p["gradient_clamp"]))
    # base shape (vc-2.28)
    s = p["base_scale_km"]
    bs = trilinear_wrap(tex.base, X / s, Y / s, Z / s)
    _, b = pywarp.clouds_base_shape(*(f32(bs[..., k]) for k in range(4)))
    # coverage and profile (vc-2.29): the renderer's C := 1 - D_h, and the literal reading C := D_h for contrast
    b_d = pywarp.clouds_coverage(b, d_v, d_h, 1.0 - d_h, clamp=True)
    b_d_alt = pywarp.clouds_coverage(b, d_v, d_h, d_h, clamp=True)
    # detail erosion (vc-2.30) at curl-displaced coordinates, h_rel of the displaced point
    cv = bilinear_wrap(tex.curl, X / p["curl_scale_km"], Z / p["curl_scale_km"])
    qx = X + cv[..., 0] * p["curl_strength_km"] + p["detail_offset"][0]
    qy = Y + p["detail_offset"][1]
    qz = Z + cv[..., 1] * p["curl_strength_km"] + p["detail_offset"][2]
    h_d = pywarp.clouds_relative_height(f32(np.sqrt((qx - c[0]) ** 2 + (qy - c[1]) ** 2 + (qz - c[2]) ** 2)),
                                        p["r_inner"], p["r_outer"])
    s = p["detail_scale_km"]
    dt = trilinear_wrap(tex.detail, qx / s, qy / s, qz / s)
    dens = pywarp.clouds_detail_erosion(b_d, *(f32(dt[..., k]) for k in range(3)), f32(np.clip(h_d, 0.0, 1.0)))
    # the renderer's early outs: nothing outside the layer or where the coverage is 0
    keep = inside & (d_h > 0.0)
    zero = np.float32(0.0)
    return {"x": x, "y": y, "inside": inside, "envelope": np.where(inside, d_h * d_v, zero),
            "B": np.where(inside, b, np.nan), "B_D": np.where(keep, b_d, zero), "C": np.where(keep, dens, zero),
            "B_D_alt": np.where(keep, b_d_alt, zero)}


def project(pose: Pose, width: int, height: int, pts: np.ndarray) -> np.ndarray:
    """Pixel (column, row) of world points (..., 3) for the renderer's pinhole camera (no roll, y up)."""
    f = pose.forward()
    r = np.cross(f, [0.0, 1.0, 0.0])
    r /= np.linalg.norm(r)
    u = np.cross(r, f)
    v = pts - np.array([pose.x, pose.y, pose.z])
    t = np.tan(np.radians(pose.fov_y_deg) / 2.0)
    zc = v @ f
    nx = (v @ r) / (zc * t * width / height)
    ny = (v @ u) / (zc * t)
    return np.stack([(nx + 1) / 2 * width - 0.5, (1 - ny) / 2 * height - 0.5], axis=-1)


def main(out_dir, quick: bool = False) -> list[Path]:
    out_dir = Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    settings = CloudscapeSettings(**(QUICK if quick else FULL), **SCENE)
    tech = CloudscapeTechnique(settings)
    p = settings.c_values()

    # %% [markdown]
    # The slice and the render use the same textures: the technique's (tech.textures) and its parameters.

    # %%
    sl = density_slice(tech.textures, p, *((200, 60) if quick else (900, 240)))
    image = tech.render(POSE)

    # %%
    fig = plt.figure(figsize=(14.0, 15.0), dpi=60 if quick else 100)
    gs = fig.add_gridspec(6, 2, height_ratios=[2.6, 1, 1, 1, 1, 1], width_ratios=[1.0, 1.78], left=0.06, right=0.93,
                          top=0.915, bottom=0.035, hspace=0.42, wspace=0.12)
    # (a) top view of the coverage around the origin (the weather map tiles the plane)
    ax = fig.add_subplot(gs[0, 0])
    g = np.linspace(-MAP_HALF_KM, MAP_HALF_KM, 129 if quick else 481)
    gx, gz = np.meshgrid(g, g)
    cov = bilinear_wrap(tech.textures.weather, (gx + p["weather_offset"][0]) / p["weather_scale_km"],
                        (gz + p["weather_offset"][1]) / p["weather_scale_km"])[..., 0]
    ax.imshow(cov, extent=(-MAP_HALF_KM, MAP_HALF_KM, MAP_HALF_KM, -MAP_HALF_KM), cmap="viridis", vmin=0.0,
              vmax=1.0, interpolation="nearest")
    ax.plot(SLICE_X_KM, [SLICE_Z_KM] * 2, "r-", lw=2)
    ax.plot([POSE.x], [POSE.z], "w^", ms=8)
    ax.annotate("camera", (POSE.x, POSE.z), (POSE.x + 2, POSE.z + 4), color="w", fontsize=8)
    ax.text(SLICE_X_KM[0], SLICE_Z_KM + 0.8, "slice", color="r", fontsize=9, va="top")
    ax.set_xlabel("x [km]")
    ax.set_ylabel("z [km]  (−z = view direction, up)")
    ax.set_title("(a) weather-map coverage D_h (red channel) seen from\n"
                 f"above (one map tile = {p['weather_scale_km']:g} km)", fontsize=10)
    # (b) render with the slice line
    ax = fig.add_subplot(gs[0, 1])
    ax.imshow(image, interpolation="nearest")
    h_img, w_img = image.shape[:2]
    for alt, style in ((settings.layer_base_km, "r--"), (settings.layer_top_km, "r-")):
        line = np.stack([np.linspace(*SLICE_X_KM, 50), np.full(50, alt), np.full(50, SLICE_Z_KM)], axis=-1)
        px = project(POSE, w_img, h_img, line)
        ax.plot(px[:, 0], px[:, 1], style, lw=1.2)
    ax.set_xlim(-0.5, w_img - 0.5)
    ax.set_ylim(h_img - 0.5, -0.5)
    ax.set_axis_off()
    ax.set_title("(b) render of the same clouds from 12 km (red: slice plane at the layer base - - and top —)",
                 fontsize=10)

    rows = (("(c) envelope D_h·D_v: coverage × height gradient (4.7) — where clouds may exist", "envelope", 1.0),
            ("(d) base shape B (2.28) from the 128³ base texture", "B", 1.0),
            ("(e) B_D = remap(B·D_v, 1 − D_h, 1, 0, 1)·D_h (2.29, C := 1 − D_h as in the renderer)", "B_D", None),
            ("(f) final density: detail erosion of B_D (2.30) — what the renderer marches", "C", None),
            ("(g) for contrast, not in the renderer: B_D with the literal reading C := D_h", "B_D_alt", None))
    extent = (SLICE_X_KM[0], SLICE_X_KM[1], SLICE_Y_KM[0], SLICE_Y_KM[1])
    for k, (title, key, vmax) in enumerate(rows):
        ax = fig.add_subplot(gs[1 + k, :])
        data = sl[key]
        top = vmax if vmax is not None else max(float(np.nanmax(data)), 1e-6)
        im = ax.imshow(data, extent=extent, aspect="auto", cmap="magma" if key != "B" else "gray", vmin=0.0,
                       vmax=top, interpolation="bilinear")
        ax.contour(sl["x"], sl["y"], sl["envelope"] > 0.0, levels=[0.5], colors="c", linewidths=0.6)
        ax.set_title(title, fontsize=10, loc="left")
        ax.set_ylabel("altitude [km]")
        cb = fig.colorbar(im, ax=ax, pad=0.01, fraction=0.03)
        cb.ax.tick_params(labelsize=7)
        if k == len(rows) - 1:
            ax.set_xlabel(f"x [km] along the slice z = {SLICE_Z_KM:g} km  (cyan: edge of the envelope D_h·D_v > 0)")
    fig.suptitle("Fig 4.10 — cloud creation (vc-A17): the weather map and height gradient restrict the positions, the "
                 "noise shapes them\n" + f"(world size of one texture tile: base {p['base_scale_km']:g} km, detail "
                 f"{p['detail_scale_km']:.3g} km, weather map {p['weather_scale_km']:g} km, curl "
                 f"{p['curl_scale_km']:g} km displacing the detail by up to {p['curl_strength_km']:.3g} km)",
                 fontsize=11)
    out = out_dir / "fig-4.10.png"
    fig.savefig(out)
    plt.close(fig)
    return [out]


if __name__ == "__main__":
    from pywarp.tutorial import run_as_script

    run_as_script(main, __doc__, "figures/vc")
