"""Figure vc-fig-4.14: reprojection artifact, (a) exact sampling, (b) averaged sampling (reproducible in kind).

Temporal reprojection (vc-A26) marches only one pixel of every 4 x 4 block per frame (the pixel chosen by vc-4.1; the
reduced buffer of vc-A22) and fills the other 15/16 from the previous frame: the ray of each pixel is intersected
with the inner sphere of the cloud layer (vc-A14), the hit point is projected with the previous camera and the
previous frame is read there, or, outside it, the reduced buffer is interpolated. The optional neighbourhood
averaging (vc-A27) reads an n x n box around the reprojected position instead. The clouds themselves are the full
pass of vc-A17, vc-A18, vc-A19, vc-A20, vc-A21 composited by vc-4.8 over the Preetham sky (vc-A29). Renderer:
pywarp.clouds.cloudscape with reprojection=True and reprojection_neighbourhood = 1 (exact sampling) or 3 (3 x 3 average),
with the thesis's reprojection_depth="inner_sphere" and reprojection_filter="bilinear" (the renderer's default
reprojects through the depth of what each pixel shows and samples with a clamped Catmull-Rom filter, which removes
these artifacts instead of averaging them away: cclouds/reproj.h).

Parameters (the thesis gives none): a camera 0.3 km up, 50° vertical field of view, looking 22° up, that turns by
0.5° per frame (yaw -8° -> +7.5°) while flying forward by 20 m per frame along -z (32 frames: two full 16-frame
refresh cycles); coverage 0.45, cloud type 0.75, sun 25° up at azimuth 110°, seed 0; jitter='none', so that the
reference differs from the reprojected frames only by the reprojection (the tilt jitter changes every frame). The
reference is a full render (every pixel marched) at the last pose. Image quality against it: SSIM and PSNR from
skimage.metrics (scikit-image, the test extra of the package) on the sRGB images, printed in the figure. 384x216 per
panel. Output: figures/vc/fig-4.14.png.
"""
# %% [markdown]
# Marching every pixel every frame is the expensive part of the renderer. Reprojection spreads the work over 16
# frames: each frame marches one pixel per 4 x 4 block, in a fixed order, and the other pixels are carried over from
# the previous frame. Because the camera moves, "carried over" means: find where this pixel's content was in the
# previous image. The clouds are a volume and the renderer does not know at which depth a pixel's colour came from,
# so the thesis assumes it came from the cloud base — the inner sphere of the layer. Wherever the real cloud is
# higher than that, the reprojected position is wrong by the parallax, and the error persists until the pixel's turn
# to be marched again comes up (up to 15 frames later). Resampling the previous frame at fractional positions every
# frame also blurs it a little each time.
#
# The thesis' remedy is to read the average of a neighbourhood instead of the single reprojected pixel: the sharp
# errors (ghost edges, the 4 x 4 pattern) are smoothed, at the price of blurred clouds, since the averaging repeats
# every frame for up to 15 frames.
#
# (With a still camera, exact sampling reproduces the full render exactly after 16 frames — every pixel has been
# marched once and nothing moved; we checked this while writing the tutorial. The 3 x 3 average blurs even then.)

# %%
from __future__ import annotations

from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from matplotlib.patches import Rectangle  # noqa: E402

from pywarp.clouds.cloudscape import CloudscapeSettings  # noqa: E402
from pywarp.clouds.technique import CloudscapeTechnique  # noqa: E402
from pywarp.core.pose import Pose  # noqa: E402

# the thesis's reprojection (the inner-sphere point, bilinear sampling), not the renderer's depth-aware default: this
# figure shows the thesis's artifacts
SCENE = dict(coverage=0.45, cloud_type=0.75, sun_elevation_deg=25.0, sun_azimuth_deg=110.0, seed=0, jitter="none",
             camera_altitude_km=0.3, fov_y_deg=50.0, camera_pitch_deg=22.0, reprojection_depth="inner_sphere",
             reprojection_filter="bilinear")
FULL = dict(width=384, height=216)
QUICK = dict(width=96, height=54, base_size=32, detail_size=16, curl_size=32, weather_size=64)
YAW_STEP_DEG = 0.5
FORWARD_STEP_KM = 0.02
CROP = (0.60, 0.58, 0.38, 0.32)  # x, y, w, h (fractions): the cumulus edges low on the right


def camera_path(frames: int, s: CloudscapeSettings) -> list[Pose]:
    """Turn by YAW_STEP_DEG and fly FORWARD_STEP_KM along -z per frame, ending at yaw 0 + (frames/2 - 1) steps."""
    return [Pose(0.0, s.camera_altitude_km, -FORWARD_STEP_KM * i, YAW_STEP_DEG * (i - frames // 2),
                       s.camera_pitch_deg, s.fov_y_deg) for i in range(frames)]


def quality(img: np.ndarray, ref: np.ndarray) -> tuple[float, float]:
    """(SSIM, PSNR in dB) of an sRGB uint8 image against the reference, both scaled to [0, 1]."""
    try:
        from skimage.metrics import peak_signal_noise_ratio, structural_similarity
    except ImportError as exc:  # scikit-image is in the package's test extra
        raise ImportError("fig 4.14 needs scikit-image for SSIM/PSNR: pip install scikit-image") from exc
    a, b = img.astype(np.float64) / 255.0, ref.astype(np.float64) / 255.0
    return (float(structural_similarity(a, b, channel_axis=2, data_range=1.0)),
            float(peak_signal_noise_ratio(b, a, data_range=1.0)))


def main(out_dir, quick: bool = False) -> list[Path]:
    out_dir = Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    size = QUICK if quick else FULL
    frames = 20 if quick else 32

    # %% [markdown]
    # The reference: one full render at the final pose. Then, for each neighbourhood size, a fresh technique with
    # reprojection on renders the whole camera path; its last frame is compared with the reference. All three share
    # the same textures.

    # %%
    base = CloudscapeSettings(**size, **SCENE)
    path = camera_path(frames, base)
    ref_tech = CloudscapeTechnique(base)
    reference = ref_tech.render(path[-1], reprojection=False)
    results = {}
    for n in (1, 3):
        s = CloudscapeSettings(**size, **SCENE, reprojection=True, reprojection_neighbourhood=n)
        tech = CloudscapeTechnique(s, textures=ref_tech.textures)
        for pose in path:
            img = tech.render(pose)
        results[n] = (img, *quality(img, reference))

    # %%
    h, w = reference.shape[:2]
    cx, cy, cw, ch = (int(round(f * m)) for f, m in zip(CROP, (w, h, w, h)))
    fig, axes = plt.subplots(3, 3, figsize=(13.0, 9.6), dpi=60 if quick else 100,
                             gridspec_kw=dict(height_ratios=[h / w, ch / cw, h / w]))
    columns = (("full render (every pixel marched)", reference, None),
               ("(a) exact sampling, n = 1", *results[1]),
               ("(b) averaged sampling, n = 3 (3×3 box)", *results[3]))
    for k, (title, img, *metrics) in enumerate(columns):
        ax = axes[0, k]
        ax.imshow(img, interpolation="nearest")
        ax.add_patch(Rectangle((cx - 0.5, cy - 0.5), cw, ch, fill=False, ec="red", lw=1.0))
        if metrics[0] is not None:
            title += f"\nSSIM {metrics[0]:.3f}, PSNR {metrics[1]:.1f} dB vs the full render"
        ax.set_title(title, fontsize=9)
        axes[1, k].imshow(img[cy:cy + ch, cx:cx + cw], interpolation="nearest")
        axes[1, k].set_title("red box enlarged" if k == 0 else "", fontsize=8)
        if k == 0:
            axes[2, k].text(0.5, 0.5, f"camera: {frames} frames,\n{YAW_STEP_DEG}° turn and "
                            f"{FORWARD_STEP_KM * 1000:.0f} m forward per frame;\nreprojection through the inner "
                            f"sphere (cloud base {base.layer_base_km:g} km)\n\nbelow (a), (b): |frame − full "
                            "render|,\nmean of R, G, B, ×8",
                            ha="center", va="center", fontsize=9, transform=axes[2, k].transAxes)
        else:
            diff = np.abs(img.astype(np.float64) - reference.astype(np.float64)).mean(axis=2)
            axes[2, k].imshow(np.clip(diff * 8.0, 0, 255), cmap="gray", vmin=0, vmax=255, interpolation="nearest")
            axes[2, k].set_title(f"mean |difference| {diff.mean():.1f} / 255", fontsize=9)
    for ax in axes.ravel():
        ax.set_axis_off()
    fig.suptitle("Fig 4.14 — reprojection artifact after a camera motion (vc-A26, vc-A27): (a) exact sampling, "
                 "(b) averaged sampling", fontsize=11)
    fig.subplots_adjust(left=0.01, right=0.99, top=0.89, bottom=0.01, wspace=0.03, hspace=0.16)
    out = out_dir / "fig-4.14.png"
    fig.savefig(out)
    plt.close(fig)
    print("fig 4.14: " + "; ".join(f"n = {n}: SSIM {r[1]:.4f}, PSNR {r[2]:.2f} dB" for n, r in results.items()))
    return [out]


if __name__ == "__main__":
    from pywarp.tutorial import run_as_script

    run_as_script(main, __doc__, "figures/vc")
