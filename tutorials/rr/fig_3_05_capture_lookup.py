"""Figure rr-fig-3.5: getting a drop pixel's colour from the captured texture, P_i -> P_o -> P_c (rr-alg-3.1.3),
computed: (a) side view of the viewer, one drop and the capture plane behind it, with the physical ray traced through
the drop (rr-snell) beside the shader's P_o and P_c (rain_refracted_uv on the mask texel of rr-alg-3.1.1); (b) the
150 deg capture (rr-alg-3.1.2) with P_o -> P_c for a grid of drop pixels; (c) the drop those pixels colour
(rr-alg-3.1, rain_shade_drop). Output: figures/rr/fig-3.5.png.
"""
# %% [markdown]
# The drop does not render the scene again. The scene is captured once per frame from the viewer with a very wide
# camera (150 deg, rr-alg-3.1.2), and that image is thought of as a plane behind the drops. For a drop pixel P_i the
# fragment shader
#
# 1. finds P_o, the capture pixel the viewer would see through P_i if the drop were air (the view direction,
#    projected by the capture camera);
# 2. reads the refraction vector e of P_i from the drop's mask (rr-alg-3.1.1: the direction in which the ray leaves
#    the drop, in the drop's frame: x right, y up, z along the view);
# 3. adds it in image space, P_c = P_o + (s_x e_x / e_z, -s_y e_y / e_z) (s = the capture's scale), and returns the
#    capture's colour at P_c. P_o itself is never shown.
#
# `pywarp.rain_refracted_uv(view_dir, exit_dir, tan_half_fov, aspect)` returns (P_c, P_o, valid). Panel (a) draws it
# to scale in a side view (the drop is enlarged: 1 unit radius 5 units away, the plane 12 units away) beside the
# physical path of the same ray, traced with `optics_snell` through a sphere. They differ a little because the mask
# is built for parallel view rays and the capture is taken from the viewer, not from the drop (the approximations the
# text accepts, rr-alg-3.2.2); for a real drop, millimetres across and metres away, the difference vanishes.

# %%
from __future__ import annotations

from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import pywarp  # noqa: E402
from pywarp.rain import drops  # noqa: E402
from pywarp.tutorial import billboard_frame, environment  # noqa: E402

N_WATER = 1.33
FOV_Y = 150.0  # the capture camera's FOVy: the text's contract (rr-der-3.2.1, variant 'thesis')
TAN_H = float(np.tan(np.radians(FOV_Y) / 2))
S_Y = 0.5 / TAN_H  # capture scale: uv per unit of tan (aspect 1)


def capture(size):
    """The viewer's wide-angle capture (rr-alg-3.1.2): size x size, FOVy 150 deg, row 0 at the top."""
    c = (np.arange(size) + 0.5) / size
    u, v = np.meshgrid(c, c)
    d = np.stack([(u - 0.5) / S_Y, (0.5 - v) / S_Y, -np.ones_like(u)], -1)
    return environment(d)


def side_view(ax, v_pix=0.55, D=5.0, R=1.0, L=12.0):
    """(a): the viewer at the origin looking right (depth = -z), one pixel row u = 0 of a drop straight ahead."""
    f = np.array([0.0, 0.0, -1.0])
    t_ar = np.tan(np.arcsin(R / D))  # the billboard spans the drop's angular radius
    C = D * f
    th = np.linspace(0, 2 * np.pi, 200)
    ax.fill(D + R * np.cos(th), R * np.sin(th), color="#cfe6f7", zorder=1)
    ax.plot(D + R * np.cos(th), R * np.sin(th), color="C0", lw=1.5, zorder=1)
    half = 4.2
    ax.plot([L, L], [-half, half], color="0.2", lw=3, zorder=1)
    # the capture's colours along the plane (u = 0.5 column), as the text's texture "placed behind the drops"
    ys = np.linspace(-half, half, 300)
    col = environment(np.stack([np.zeros_like(ys), ys / L, -np.ones_like(ys)], -1))
    ax.scatter(np.full_like(ys, L + 0.18), ys, c=col, s=14, marker="s", lw=0, zorder=2)
    ax.text(L + 0.45, half - 0.2, "capture plane\n(150° capture\nfrom the viewer)", fontsize=9, va="top")
    ax.plot(0, 0, "ko", ms=7, zorder=5)
    ax.text(-0.2, -0.45, "viewer", fontsize=10, ha="left")
    # the pixel's view direction and the physical path (perspective ray, sphere, rr-snell twice)
    d = np.array([0.0, v_pix * t_ar, -1.0])
    d /= np.linalg.norm(d)
    b = d @ C
    s = b - np.sqrt(b * b - (D * D - R * R))
    P = s * d
    t1, r1, _ = pywarp.optics_snell(d, (P - C) / R, 1.0, N_WATER)
    Q = P + (-2 * (P - C) @ t1) * t1
    t2, _, tir = pywarp.optics_snell(t1, (Q - C) / R, N_WATER, 1.0)
    hit = Q + ((-L - Q[2]) / t2[2]) * t2
    # the shader: mask texel at (0, v_pix), then P_o and P_c in capture uv, placed on the plane
    e, _, inside = pywarp.rain_mask_texel(0.0, v_pix, 1.0, method="sphere")
    pc, po, valid = pywarp.rain_refracted_uv(d, e, TAN_H, 1.0)
    y_o, y_c = L * (0.5 - po[1]) / S_Y, L * (0.5 - pc[1]) / S_Y
    assert int(inside) == 1 and int(valid) == 1 and int(tir) == 0

    def seg(a, b_, **kw):
        ax.plot([-a[2], -b_[2]], [a[1], b_[1]], **kw)

    seg(np.zeros(3), P, color="k", lw=2, zorder=4)
    seg(P, np.array([0, y_o, -L]), color="0.35", lw=1.3, ls="--", zorder=3)
    seg(P, Q, color="C3", lw=2, zorder=4)
    seg(Q, hit, color="C3", lw=2, zorder=4)
    seg(np.zeros(3), np.array([0, y_c, -L]), color="C2", lw=1.2, ls=":", zorder=3)
    ax.plot(-P[2], P[1], "o", color="k", ms=6, zorder=6)
    ax.plot(L, y_o, "o", color="0.35", ms=8, zorder=6)
    ax.plot(L, y_c, "o", color="C2", ms=8, zorder=6)
    ax.plot(L, hit[1], "x", color="C3", ms=9, mew=2, zorder=6)
    ax.annotate("", xy=(L - 0.25, y_c), xytext=(L - 0.25, y_o),
                arrowprops=dict(arrowstyle="-|>", color="C2", lw=2), zorder=6)
    ax.text(-P[2] - 0.25, P[1] + 0.25, "P_i", fontsize=11, ha="right")
    ax.text(L - 0.4, y_o + 0.25, "P_o (drop = air)", fontsize=10, ha="right", color="0.3")
    ax.text(L - 0.4, y_c - 0.1, "P_c = P_o + refraction\nvector (shader)", fontsize=10, ha="right", va="top",
            color="C2")
    ax.text(L - 0.4, hit[1] - 0.2, "physical ray's hit\n(traced, rr-snell)", fontsize=9, ha="right", va="top",
            color="C3")
    ax.text(-0.5, -half - 0.3, "green dotted: the viewer's line to P_c, parallel to the red exit ray -- the capture is\n"
            "seen from the viewer, not from the drop (parallax, accepted in rr-alg-3.2.2; it is a fixed offset of\n"
            "about one drop size, so it vanishes for millimetre drops in front of a distant scene)", fontsize=8.5,
            va="top")
    ax.set_title(f"(a) side view, pixel v = {v_pix} of a drop straight ahead (not to scale: drop enlarged)\n"
                 f"shader: P_o -> P_c along the plane; red: the ray traced through the sphere", fontsize=10)
    ax.set_xlim(-0.6, L + 2.6)
    ax.set_ylim(-half - 2.0, half + 0.3)
    ax.set_aspect("equal")
    ax.axis("off")


def main(out_dir, quick: bool = False) -> list[Path]:
    out_dir = Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    fig = plt.figure(figsize=(18, 6.4), dpi=80 if quick else 110)
    gs = fig.add_gridspec(1, 3, width_ratios=[1.35, 1.0, 1.0])
    side_view(fig.add_subplot(gs[0]))

    # %% [markdown]
    # (b) and (c): a drop a little right of and above the view centre, angular radius 0.2 rad (enlarged again, so
    # that its pixels can be marked; a 1 mm drop 2 m away has 0.0005 rad). Every P_o falls inside the drop's own small footprint on the capture (the
    # white circle); the refraction vectors spread the P_c over almost the whole 150 deg image, reversed: pixels at
    # the top of the drop fetch the ground, pixels at the bottom the sky -- the inverted wide-angle image a drop shows.

    # %%
    size = 128 if quick else 512
    cap = capture(size)
    f = np.array([0.12, 0.06, -1.0])
    f /= np.linalg.norm(f)
    ar = 0.2
    rt, up = billboard_frame(f)
    g = np.linspace(-0.75, 0.75, 5)
    uu, vv = [a.ravel() for a in np.meshgrid(g, g[::-1])]
    keep = uu ** 2 + vv ** 2 <= 0.8
    uu, vv = uu[keep], vv[keep]
    dirs = f + (rt * uu[:, None] + up * vv[:, None]) * np.tan(ar)
    dirs /= np.linalg.norm(dirs, axis=1, keepdims=True)
    e, _, inside = pywarp.rain_mask_texel(uu, vv, 1.0, method="sphere")
    pc, po, valid = pywarp.rain_refracted_uv(dirs, e, TAN_H, 1.0)
    cols = plt.get_cmap("turbo")(np.linspace(0.05, 0.95, len(uu)))
    axb = fig.add_subplot(gs[1])
    axb.imshow(cap, extent=(0, 1, 1, 0), interpolation="nearest")
    for k in range(len(uu)):
        if valid[k]:
            axb.annotate("", xy=pc[k], xytext=po[k], arrowprops=dict(arrowstyle="-|>", color=cols[k], lw=1.3,
                                                                     shrinkA=0, shrinkB=0))
            axb.plot(*pc[k], "o", color=cols[k], ms=6, mec="k", mew=0.6)
    c_o = pywarp.rain_refracted_uv(f, np.array([0.0, 0.0, 1.0]), TAN_H, 1.0)[1]  # the drop centre's P_o
    foot = np.tan(ar) * S_Y
    th = np.linspace(0, 2 * np.pi, 100)
    axb.plot(c_o[0] + foot * np.cos(th), c_o[1] + foot * np.sin(th), color="w", lw=2.0)
    axb.plot(po[valid == 1, 0], po[valid == 1, 1], "k.", ms=3)
    lo = np.minimum(pc[valid == 1].min(0), c_o - foot) - 0.04
    hi = np.maximum(pc[valid == 1].max(0), c_o + foot) + 0.04
    axb.set_xlim(lo[0], hi[0])
    axb.set_ylim(hi[1], lo[1])
    axb.set_xlabel("capture u")
    axb.set_ylabel("capture v (down)")
    axb.set_title("(b) the capture (150°, 512², centre part): arrows P_o -> P_c;\nevery P_o lies inside the drop's "
                  "footprint (white)",
                  fontsize=10)

    n_out = 96 if quick else 400
    mask = drops.drop_mask(128 if quick else 512, 1.0, method="sphere")
    drop = pywarp.rain_shade_drop(cap, mask, f, angular_radius=ar, out_size=n_out)
    axc = fig.add_subplot(gs[2])
    shown = np.where(drop[..., 3:] > 0, drop[..., :3], 0.15)
    axc.imshow(np.clip(shown, 0, 1), extent=(-1, 1, -1, 1), interpolation="nearest")
    for k in range(len(uu)):
        axc.plot(uu[k], vv[k], "o", color=cols[k], ms=8, mec="k", mew=0.8)
    axc.set_xlabel("billboard u")
    axc.set_ylabel("billboard v")
    axc.set_title("(c) the drop (rain_shade_drop): each P_i (dot)\ntakes the colour at its P_c in (b)", fontsize=10)
    fig.suptitle("Drop pixel colour from the captured scene, P_i -> P_o -> P_c (rr-alg-3.1.3; mask rr-alg-3.1.1, "
                 "capture rr-alg-3.1.2, n = 1.33)", fontsize=12)
    fig.subplots_adjust(left=0.01, right=0.99, top=0.84, bottom=0.08, wspace=0.15)
    out = out_dir / "fig-3.5.png"
    fig.savefig(out)
    plt.close(fig)
    return [out]


if __name__ == "__main__":
    from pywarp.tutorial import run_as_script

    run_as_script(main, __doc__, "figures/rr")
