"""Figure rr-fig-3.6: maximum refraction in a raindrop and the field of view of a drop (rr-der-3.2.1), both variants:
the printed chain 90 -> 48 -> 6 -> 81 -> 75 deg giving FOVy = 150 deg (variant "thesis", the capture camera's
default) and the exact chain from the critical angle arcsin(1/1.33) = 48.75 deg giving 165.0 deg ("corrected");
rays traced with rr-snell. Output: figures/rr/fig-3.6.png.
"""
# %% [markdown]
# Which part of the scene can a drop show? A ray from the viewer that grazes the drop's edge (incidence 90 deg) is
# bent the most. Snell's law (rr-snell) sends it into the water at the critical angle theta_t = arcsin(1/1.33) from
# the normal; in a sphere the chord meets the far surface at the same angle, so the ray leaves tangentially again
# (90 deg), deviated by 180 - 2 theta_t = 82.49 deg. Both edges together: a field of view of 165.0 deg.
#
# The text rounds theta_t DOWN to 48 deg; then the exit normal is at 2*48 - 90 = 6 deg to the incoming ray, the exit
# angle arcsin(1.33 sin 48) = 81.26 is printed as 81, the deviation 81 - 6 = 75 deg, and the FOV 150 deg -- the value
# the application uses for its capture camera (spec error index item 7). `optics_drop_fov(n, variant=...)` returns
# both chains; the capture keeps 150 deg by default as the text's contract.

# %%
from __future__ import annotations

from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import pywarp  # noqa: E402

N = 1.33


def rot(v, deg):
    a = np.radians(deg)
    return np.array([np.cos(a) * v[0] - np.sin(a) * v[1], np.sin(a) * v[0] + np.cos(a) * v[1]])


def cross2(a, b):
    return a[0] * b[1] - a[1] * b[0]


def draw(ax, variant):
    fov, tt, e, x = (float(v) for v in pywarp.optics_drop_fov(N, variant=variant))
    t = np.linspace(0, 2 * np.pi, 300)
    ax.fill(np.cos(t), np.sin(t), color="#cfe6f7")
    ax.plot(np.cos(t), np.sin(t), color="C0", lw=1.5)
    P = np.array([0.0, 1.0])  # grazing entry at the top, the ray travels +x
    d = np.array([1.0, 0.0])
    # inside: theta_t from the inward normal (0, -1), bent forward (+x)
    tin = rot(np.array([0.0, -1.0]), tt)
    Q = P + (-2 * P @ tin) * tin
    # the exit direction makes `x` degrees with the outward normal Q, on the far side of it from the chord
    nq = Q / np.linalg.norm(Q)
    side = np.sign(cross2(nq, tin))
    out = rot(nq, side * x)
    ax.annotate("", xy=P, xytext=P - 1.2 * d, arrowprops=dict(arrowstyle="-|>", color="k", lw=1.5))
    ax.plot(*np.stack([P, Q]).T, color="C3", lw=1.8)
    ax.annotate("", xy=Q + 1.3 * out, xytext=Q, arrowprops=dict(arrowstyle="-|>", color="C3", lw=1.8))
    ax.plot(*np.stack([Q, Q + 1.25 * d]).T, color="k", ls=":", lw=1)  # the undeviated direction
    ax.plot(*np.stack([P - 0.35 * np.array([0, -1]), P + 0.6 * np.array([0, -1])]).T, color="0.5", ls="--", lw=0.8)
    ax.plot(*np.stack([Q - 0.4 * nq, Q + 0.5 * nq]).T, color="0.5", ls="--", lw=0.8)
    dev = np.degrees(np.arctan2(abs(cross2(d, out)), d @ out))
    ax.text(P[0] + 0.05, P[1] - 0.35, f"θ_t = {tt:.2f}°", fontsize=9, color="C3")
    ax.text(Q[0] + 0.08, Q[1] + 0.15, f"exit normal at {e:.2f}°\nto the incoming ray", fontsize=8)
    ax.text(Q[0] + 0.35, Q[1] - 0.75, f"exit at {x:.2f}° to the normal\ndeviation {x - e:.2f}°", fontsize=9,
            color="C3")
    ax.set_title(("(a) variant='thesis' (as printed)" if variant == "thesis" else "(b) variant='corrected' (exact)")
                 + f"\nFOV = 2 x {x - e:.2f}° = {fov:.2f}°")
    ax.set_aspect("equal")
    ax.set_xlim(-1.3, 2.6)
    ax.set_ylim(-1.9, 1.5)
    ax.axis("off")
    return dev


def main(out_dir, quick: bool = False) -> list[Path]:
    out_dir = Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    fig, axes = plt.subplots(1, 3, figsize=(16, 5.4), dpi=80 if quick else 120)
    draw(axes[0], "thesis")
    draw(axes[1], "corrected")

    # %% [markdown]
    # (c) The deviation of every ray through a spherical drop, traced with rr-snell (entry and exit refraction,
    # chord in between), against the impact parameter b: it grows monotonically to 82.49 deg at the rim, so the
    # exact FOV is twice that.

    # %%
    b = np.linspace(0.0, 1.0, 201 if quick else 2001)
    P = np.stack([b, np.sqrt(np.maximum(1 - b * b, 0.0)), np.zeros_like(b)], -1)
    Pn = np.stack([P[:, 0], -P[:, 1], P[:, 2]], -1)  # entry on the side facing the viewer (-y), ray along +y
    d = np.array([0.0, 1.0, 0.0])
    tin, _, _ = pywarp.optics_snell(d, Pn / np.linalg.norm(Pn, axis=1, keepdims=True), 1.0, N)
    s = -2 * np.sum(Pn * tin, -1, keepdims=True)
    Q = Pn + s * tin
    tout, _, tir = pywarp.optics_snell(tin, Q / np.linalg.norm(Q, axis=1, keepdims=True), N, 1.0)
    dev = np.degrees(np.arccos(np.clip(tout @ d, -1, 1)))
    ax = axes[2]
    ax.plot(b[tir == 0], dev[tir == 0], color="C0", lw=2, label="traced with rr-snell (float32)")
    ax.plot(b, np.degrees(2 * (np.arcsin(b) - np.arcsin(b / N))), color="k", ls=":", lw=1,
            label="2 (θ_i - θ_t), float64")
    ax.axhline(82.49, color="C3", ls="--", lw=1)
    ax.axhline(75.0, color="C1", ls="--", lw=1)
    ax.text(0.02, 83.5, "82.49° exact (FOV 165°)", color="C3", fontsize=9)
    ax.text(0.02, 71.0, "75° printed (FOV 150°)", color="C1", fontsize=9)
    ax.set_xlabel("impact parameter b (0 = centre, 1 = rim)")
    ax.set_ylabel("deviation [deg]")
    ax.set_title("(c) deviation through a sphere, n = 1.33")
    ax.set_xlim(0, 1)
    ax.set_ylim(0, 90)
    ax.grid(alpha=0.3)
    ax.legend(loc="center left", fontsize=9)
    fig.suptitle("Field of view of a drop (rr-der-3.2.1): the printed chain rounds 48.75° to 48° and gets 150°; "
                 "the exact chain gives 165°", fontsize=11)
    fig.tight_layout()
    out = out_dir / "fig-3.6.png"
    fig.savefig(out)
    plt.close(fig)
    return [out]


if __name__ == "__main__":
    from pywarp.tutorial import run_as_script

    run_as_script(main, __doc__, "figures/rr")
