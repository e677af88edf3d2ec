"""Figures pt-fig-4.1 and pt-fig-4.2: SDF primitives (Kod 4.1) and operations (Kod 4.2), rendered by sphere tracing.

The demonstration scenes of pywarp.sdf_scene (pt-alg-4.1; primitives pt-code-4.1, operators pt-code-4.2) are sphere
traced per pixel (pt-alg-5.2, pywarp.sdf_sphere_trace: 256 steps, precision 1e-3, max_t 50) through the camera of
Kod 7.1 - 7.2, with normals by central differences (Kod 7.8, h = 0.002) and ambient + Lambert light (eq. 7.1,
L_a C_a = 0.18, L_d C_d = 0.85 times the object colour). Sizes, positions, colours and light are free in the text.
Output: figures/pt/fig-4.1.png, figures/pt/fig-4.2.png.
"""
# %% [markdown]
# A signed distance function tells every point of space how far the nearest surface is. A ray can therefore always
# advance by that distance without passing through anything (sphere tracing), and stops when the distance falls below
# a small precision. The surface normal is the gradient of the distance, estimated by central differences; the
# lighting is the demo's ambient + Lambert model.

# %%
from __future__ import annotations

from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import pywarp  # noqa: E402

LIGHT = np.array([-0.5, 0.8, -0.6]) / np.linalg.norm([-0.5, 0.8, -0.6])  # unit direction towards the light
AMBIENT, DIFFUSE = 0.18, 0.85  # L_a C_a and L_d C_d of eq. 7.1 (relative to the object colour)
H_NORMAL = 0.002  # Kod 7.8


def render(scene, width, height, cam, target, colour, zoom=1.0, light=LIGHT):
    """Sphere-trace ``scene`` through the Kod 7.2 camera; returns an RGB image (row 0 at the top)."""
    f = np.stack(np.meshgrid(np.arange(width) + 0.5, np.arange(height) + 0.5), -1)
    _, p, _ = pywarp.draw_coords(f, [width, height], aspect="x")  # Kod 7.1
    cam, target = np.asarray(cam, float), np.asarray(target, float)
    fwd = (target - cam) / np.linalg.norm(target - cam)           # Kod 7.2
    right = np.cross(fwd, [0.0, 1.0, 0.0])
    right /= np.linalg.norm(right)
    up = np.cross(right, fwd)
    rd = p[..., :1] * right + p[..., 1:] * up + zoom * fwd
    rd = (rd / np.linalg.norm(rd, axis=-1, keepdims=True)).astype(np.float32)
    t, _, hit = pywarp.sdf_sphere_trace(cam.astype(np.float32), rd, scene=scene)
    x = cam + t[..., None] * rd
    e = np.eye(3) * H_NORMAL
    n = np.stack([pywarp.sdf_scene(x + e[k], scene=scene) - pywarp.sdf_scene(x - e[k], scene=scene)
                  for k in range(3)], -1)
    n /= np.maximum(np.linalg.norm(n, axis=-1, keepdims=True), 1e-12)
    lambert = np.maximum(0.0, n @ np.asarray(light))
    shade = (AMBIENT + DIFFUSE * lambert)[..., None] * np.asarray(colour)
    sky = (0.93 - 0.25 * (0.5 + 0.5 * p[..., 1:])) * np.array([0.8, 0.87, 1.0])
    img = np.where(hit[..., None] == 1, shade, sky)
    return np.clip(img, 0, 1)[::-1]


def main(out_dir, quick: bool = False) -> list[Path]:
    out_dir = Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    s = 0.3 if quick else 1.0

    # %% [markdown]
    # Figure 4.1: the four primitives of Kod 4.1 side by side -- sphere, box, torus, ellipsoid (the last one's SDF is an
    # approximation, but a safe one: it never exceeds the true distance).

    # %%
    img = render("primitives", int(1100 * s), int(300 * s), [0.0, 3.0, 7.5], [0.0, 0.0, 0.0], (0.85, 0.55, 0.3), 3.3,
                 LIGHT * [1.0, 1.0, -1.0])  # camera on +z: light from its side
    fig, ax = plt.subplots(figsize=(11, 3.7), dpi=70 if quick else 100)
    ax.imshow(img, interpolation="nearest")
    ax.axis("off")
    ax.set_title("SDF primitives of Kod 4.1 (pt-code-4.1), sphere traced (pt-alg-5.2): sphere, box, torus, "
                 "ellipsoid (approximate SDF)", fontsize=10)
    fig.tight_layout()
    out1 = out_dir / "fig-4.1.png"
    fig.savefig(out1)
    plt.close(fig)

    # %% [markdown]
    # Figure 4.2: the operators of Kod 4.2 -- union, intersection and difference of a box and a sphere, the (printed)
    # modulo repetition, a sphere displaced by noise, and the printed smooth union (width 1) of an ellipsoid and a
    # sphere.

    # %%
    panels = [("union", "(a) union: box + sphere", (0.3, 0.6, 0.9)),
              ("intersection", "(b) intersection: box and sphere", (0.9, 0.5, 0.3)),
              ("subtraction", "(c) difference: box - sphere", (0.4, 0.8, 0.4)),
              ("repetition", "(d) modulo (printed repeat, c = 1.2)", (0.85, 0.75, 0.3)),
              ("displacement", "(e) sphere + 0.12 noise(3p)", (0.7, 0.45, 0.85)),
              ("smooth_union", "(f) smooth union (k = 1): ellipsoid, sphere", (0.9, 0.4, 0.5))]
    w = int(360 * s)
    fig, axes = plt.subplots(2, 3, figsize=(12, 8.4), dpi=70 if quick else 100)
    for ax, (scene, title, colour) in zip(axes.ravel(), panels):
        if scene == "repetition":
            img = render(scene, w, w, [0.1, 3.0, -0.2], [2.0, 0.0, 6.0], colour, 1.2)
        else:
            img = render(scene, w, w, [2.2, 2.4, -3.6], [0.0, 0.0, 0.0], colour, 1.8)
        ax.imshow(img, interpolation="nearest")
        ax.set_title(title, fontsize=10)
        ax.axis("off")
    fig.suptitle("SDF operations of Kod 4.2 (pt-code-4.2) on the scenes of pywarp.sdf_scene (pt-alg-4.1), sphere traced",
                 fontsize=11)
    fig.subplots_adjust(left=0.01, right=0.99, bottom=0.01, top=0.92, wspace=0.03, hspace=0.1)
    out2 = out_dir / "fig-4.2.png"
    fig.savefig(out2)
    plt.close(fig)
    return [out1, out2]


if __name__ == "__main__":
    from pywarp.tutorial import run_as_script

    run_as_script(main, __doc__, "figures/pt")
