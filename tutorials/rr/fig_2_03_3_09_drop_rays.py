"""Figures rr-fig-2.3 and rr-fig-3.9: reflection and refraction of rays in a raindrop, and the directions of the rays
leaving it after 0, 1, 2 and 3 internal reflections -- a 2-D trace of parallel rays through a circle with n = 1.33,
every interface split by Snell (rr-snell) and Fresnel (rr-eq2, rr-eq3). Outputs: figures/rr/fig-2.3.png,
figures/rr/fig-3.9.png.
"""
# %% [markdown]
# A ray entering a drop is split at every surface: a Fresnel fraction R is reflected, 1 - R refracted (rr-eq2/3,
# unpolarised). Inside, the reflected part bounces on and leaks out a little at each hit. This trace follows parallel
# rays (light from the left) through a circular drop and records, for every exit, its direction and the energy it
# carries.
#
# Fig. 3.9 (the paper's fig. 10, which the text cites as "fig. 10") is the basis of the light model's A3 term: after
# no internal reflection the light goes on forward (the refraction the masks store); after one it comes back towards
# the source (the rainbow ray near 138 deg deviation); after two it leaves sideways near the rainbow's secondary
# angle; what leaves after internal reflections does so in the plane of incidence -- a vertical light plane gives
# vertical exits, the observation behind A3's horizontal dot product.

# %%
from __future__ import annotations

from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import pywarp  # noqa: E402

N = 1.33
MAX_INTERNAL = 3


def trace(b):
    """Parallel rays along +x at heights b through the unit circle. Returns per exit k = 0..3: points, directions,
    energies; and the internal chords (start, end, energy) for drawing."""
    b = np.asarray(b, np.float64)
    pos = np.stack([-np.sqrt(1 - b * b), b, np.zeros_like(b)], -1)
    d = np.array([1.0, 0.0, 0.0])
    nrm = pos / np.linalg.norm(pos, axis=1, keepdims=True)
    t, _, _ = pywarp.optics_snell(d, nrm, 1.0, N)
    w = 1.0 - pywarp.optics_fresnel(np.clip(np.abs(nrm @ d), 0, 1), 1.0, N)[0]
    exits, chords = [], []
    for _k in range(MAX_INTERNAL + 1):
        s = -2.0 * np.sum(pos * t, -1, keepdims=True)
        q = pos + s * t
        nq = q / np.linalg.norm(q, axis=1, keepdims=True)
        chords.append((pos.copy(), q.copy(), w.copy()))
        out, refl, tir = pywarp.optics_snell(t.astype(np.float32), nq.astype(np.float32), N, 1.0)
        R = pywarp.optics_fresnel(np.clip(np.abs(np.sum(t * nq, -1)), 0, 1), N, 1.0)[0]
        exits.append((q.copy(), out.astype(np.float64), w * (1.0 - R)))
        w = w * R
        pos, t = q, refl.astype(np.float64)
    return exits, chords


def main(out_dir, quick: bool = False) -> list[Path]:
    out_dir = Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    dpi = 80 if quick else 120
    colours = ["C0", "C3", "C2", "C4"]

    # %% [markdown]
    # Fig. 2.3: the paths of a few rays (line opacity ~ energy).

    # %%
    fig, ax = plt.subplots(figsize=(8, 7), dpi=dpi)
    c = np.linspace(0, 2 * np.pi, 300)
    ax.fill(np.cos(c), np.sin(c), color="#d6ebf8")
    ax.plot(np.cos(c), np.sin(c), color="C0", lw=1.5)
    b = np.array([0.2, 0.55, 0.86])
    exits, chords = trace(b)
    for i, bi in enumerate(b):
        ax.plot([-2.2, -np.sqrt(1 - bi * bi)], [bi, bi], color="k", lw=1.5)
        for (p0, p1, w) in chords:
            ax.plot([p0[i, 0], p1[i, 0]], [p0[i, 1], p1[i, 1]], color="C1", lw=1.3, alpha=float(np.clip(4 * w[i], 0.15, 1)))
        for k, (q, o, e) in enumerate(exits):
            ax.annotate("", xy=q[i, :2] + 1.0 * o[i, :2], xytext=q[i, :2],
                        arrowprops=dict(arrowstyle="-|>", color=colours[k], lw=1.4, alpha=float(np.clip(4 * e[i], 0.2, 1))))
        entry = np.array([-np.sqrt(1 - bi * bi), bi])
        R0 = float(pywarp.optics_fresnel(np.sqrt(1 - bi * bi), 1.0, N)[0])
        refl = pywarp.optics_snell([1.0, 0.0, 0.0], [entry[0], entry[1], 0.0], 1.0, N)[1]
        ax.annotate("", xy=entry + 0.7 * refl[:2], xytext=entry,
                    arrowprops=dict(arrowstyle="-|>", color="0.5", lw=1, alpha=float(np.clip(4 * R0, 0.2, 1))))
    for k in range(MAX_INTERNAL + 1):
        ax.plot([], [], color=colours[k], label=f"exit after {k} internal reflection{'s' if k != 1 else ''}")
    ax.plot([], [], color="0.5", label="external reflection")
    ax.plot([], [], color="C1", label="inside the drop")
    ax.set_aspect("equal")
    ax.set_xlim(-2.3, 2.3)
    ax.set_ylim(-2.3, 2.3)
    ax.axis("off")
    ax.legend(loc="lower left", fontsize=8)
    ax.set_title("Reflection and refraction of rays in a drop (n = 1.33; opacity ~ energy)")
    fig.tight_layout()
    out1 = out_dir / "fig-2.3.png"
    fig.savefig(out1)
    plt.close(fig)

    # %% [markdown]
    # Fig. 3.9: where the energy goes, per number of internal reflections -- a polar histogram of exit directions
    # (0 deg = straight on, 180 deg = back to the light), over rays spread uniformly across the drop.

    # %%
    b = np.linspace(-1, 1, 4001 if quick else 40001)[1:-1]
    exits, _ = trace(b)
    fig, axes = plt.subplots(1, 4, figsize=(16, 4.8), dpi=dpi, subplot_kw=dict(projection="polar"))
    bins = np.linspace(-np.pi, np.pi, 181)
    for k, (ax, (q, o, e)) in enumerate(zip(axes, exits)):
        ang = np.arctan2(o[:, 1], o[:, 0])
        h, _ = np.histogram(ang, bins=bins, weights=e / len(b) * 2)
        h = h / np.diff(bins)
        ax.bar(0.5 * (bins[:-1] + bins[1:]), h, width=np.diff(bins), color=colours[k], alpha=0.8)
        total = e.sum() / len(b) * 2 / 2
        ax.set_title(f"{k} internal reflection{'s' if k != 1 else ''}: {100 * total:.1f} % of the light", fontsize=10)
        ax.set_yticklabels([])
        ax.annotate("", xy=(0, 0.8 * h.max()), xytext=(np.pi, 0.8 * h.max()),
                    arrowprops=dict(arrowstyle="-|>", color="k", lw=0.8, alpha=0.4))
    fig.suptitle("Directions of rays leaving the drop (rr-fig-3.9): light from the left (arrow); 0° = straight on; "
                 "energy density per angle, Fresnel-weighted", fontsize=11)
    fig.tight_layout()
    out2 = out_dir / "fig-3.9.png"
    fig.savefig(out2)
    plt.close(fig)
    return [out1, out2]


if __name__ == "__main__":
    from pywarp.tutorial import run_as_script

    run_as_script(main, __doc__, "figures/rr")
