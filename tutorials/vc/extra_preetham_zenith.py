"""Extra figure vc-extra-preetham-zenith: Preetham's zenith luminance and chromaticity over the sun zenith angle.

Not a figure of the thesis: it plots the zenith values of the Preetham sky — luminance Y_z (vc-2.39) and
chromaticities x_z (vc-2.40) and y_z (vc-2.41) — over the sun zenith angle θ_s for several turbidities T, with both
readings of the zenith luminance (Preetham's 4.0453·T, the 'corrected' default, and 6.0453·T as printed in the
thesis, the 'thesis' variant), and marks the cataloguer's check values of spec/vc.md. Output:
figures/vc/extra-preetham-zenith.png.
"""
# %% [markdown]
# The Preetham sky is anchored at the zenith: the Perez formula only gives the shape of the sky (relative to the
# zenith), and three fitted formulas give the absolute zenith values as functions of the turbidity T and the sun
# zenith angle θ_s (0 = sun overhead, 90° = sun on the horizon):
#
#     Y_z = (4.0453·T − 4.9710)·tan χ − 0.2155·T + 2.4192,   χ = (4/9 − T/120)·(π − 2θ_s)      [kcd/m²]
#     x_z, y_z = [T² T 1] · M · [θ_s³ θ_s² θ_s 1]ᵀ                                              (3×4 matrices M)
#
# The thesis prints 6.0453 instead of Preetham's 4.0453 in Y_z. Both are drawn: solid = Preetham (corrected), dashed
# = as printed. The chromaticities have no erratum; they lie below the D65 white point (dotted), i.e. the zenith is
# bluish, and move towards (for T = 10 and a low sun, past) white as the haze grows. The black circles are the
# cataloguer's independent check values (spec/vc.md, computed outside this code); the curves must pass through them.

# %%
from __future__ import annotations

from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import pywarp  # noqa: E402

TURBIDITIES = (2.0, 3.0, 5.0, 8.0, 10.0)

# Check values of spec/vc.md (vc-2.39, vc-2.40, vc-2.41), "cataloguer-computed": (T, theta_s [deg]) -> value.
CHECK_Y = {(2.0, 0.0): (15.5007, 32.8266), (2.0, 30.0): (5.8867, 10.8855), (3.0, 60.0): (5.1392, 7.9583)}
CHECK_X = {(2.0, 0.0): 0.26674, (2.0, 30.0): 0.25142, (3.0, 60.0): 0.24493}
CHECK_YC = {(2.0, 0.0): 0.27720, (2.0, 30.0): 0.25592, (3.0, 60.0): 0.25257}


def main(out_dir, quick: bool = False) -> list[Path]:
    out_dir = out_dir if isinstance(out_dir, Path) else Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    n = 91 if quick else 361

    # %% [markdown]
    # Evaluate. pywarp.sky_preetham_zenith(T, θ_s) returns the xyY vector (x_z, y_z, Y_z) and broadcasts: a column of turbidities
    # against a row of angles gives the whole family of curves in one call. θ_s runs over [0, π/2]: the fits are made
    # for the sun above the horizon, and pywarp rejects a sun below it.

    # %%
    theta_s = np.linspace(0.0, np.float32(np.pi / 2), n, dtype=np.float32)
    T = np.array(TURBIDITIES, dtype=np.float32)[:, None]
    xz, yz, Yc = np.moveaxis(pywarp.sky_preetham_zenith(T, theta_s[None, :]), -1, 0)
    Yt = pywarp.sky_preetham_zenith(T, theta_s[None, :], variant="thesis")[..., 2]
    deg = np.degrees(theta_s)

    # %% [markdown]
    # Check the curves against the spec's values at the marked points (float32 evaluation vs 5-digit values: agreement
    # to a few units in the last printed digit).

    # %%
    pts_T = np.array([k[0] for k in CHECK_Y], dtype=np.float32)
    pts_t = np.radians(np.array([k[1] for k in CHECK_Y])).astype(np.float32)
    got_x, got_y, got_c = np.moveaxis(pywarp.sky_preetham_zenith(pts_T, pts_t), -1, 0)
    got_t = pywarp.sky_preetham_zenith(pts_T, pts_t, variant="thesis")[..., 2]
    want_c = np.array([v[0] for v in CHECK_Y.values()])
    want_t = np.array([v[1] for v in CHECK_Y.values()])
    assert np.allclose(got_c, want_c, rtol=0, atol=2e-4) and np.allclose(got_t, want_t, rtol=0, atol=2e-4)
    assert np.allclose(got_x, list(CHECK_X.values()), rtol=0, atol=2e-5)
    assert np.allclose(got_y, list(CHECK_YC.values()), rtol=0, atol=2e-5)

    # %%
    fig, axes = plt.subplots(1, 3, figsize=(15.0, 5.0), dpi=80 if quick else 130)
    colours = plt.cm.viridis(np.linspace(0.0, 0.85, len(TURBIDITIES)))
    ax = axes[0]
    for i, t in enumerate(TURBIDITIES):
        ax.plot(deg, Yc[i], color=colours[i], label=f"T = {t:g}")
        ax.plot(deg, Yt[i], color=colours[i], ls="--", lw=1.0)
    for (t, a), (vc, vt) in CHECK_Y.items():
        ax.plot([a, a], [vc, vt], "k", marker="o", ms=5, mfc="none", ls="none")
    ax.plot([], [], "k-", label="4.0453·T (Preetham, corrected)")
    ax.plot([], [], "k--", lw=1.0, label="6.0453·T (as printed, thesis)")
    ax.plot([], [], "ko", mfc="none", ls="none", label="spec check values")
    ax.set_yscale("log")
    ax.set_ylabel("Y_z [kcd/m²]")
    ax.set_title("zenith luminance Y_z (vc-2.39), log scale", fontsize=10)
    ax.legend(fontsize=7.5, loc="lower left", frameon=False, ncol=2)
    ax.set_ylim(0.1, 300.0)

    for ax, val, checks, name, eid, white in ((axes[1], xz, CHECK_X, "x_z", "vc-2.40", 0.3127),
                                              (axes[2], yz, CHECK_YC, "y_z", "vc-2.41", 0.3290)):
        ax.axhline(white, color="0.4", lw=0.8, ls=":")
        ax.text(1.0, white, f"D65 white {name[0]} = {white}", fontsize=7.5, color="0.3", va="bottom")
        for i, t in enumerate(TURBIDITIES):
            ax.plot(deg, val[i], color=colours[i], label=f"T = {t:g}")
        for (t, a), v in checks.items():
            ax.plot(a, v, "ko", ms=5, mfc="none")
        ax.set_ylabel(name)
        ax.set_title(f"zenith chromaticity {name} ({eid}), no erratum", fontsize=10)
        ax.legend(fontsize=7.5, frameon=False)
    for ax in axes:
        ax.set_xlabel("sun zenith angle θ_s [deg]  (0 = overhead, 90 = horizon)")
        ax.set_xlim(0.0, 90.0)
        ax.set_xticks(np.arange(0, 91, 15))
        ax.grid(alpha=0.3, which="both")
    fig.suptitle("Preetham zenith values over the sun zenith angle — solid: corrected, dashed: 6.0453·T as printed in "
                 "the thesis (Y_z only); circles: check values of spec/vc.md", fontsize=11)
    fig.subplots_adjust(left=0.05, right=0.99, top=0.86, bottom=0.13, wspace=0.25)
    out = out_dir / "extra-preetham-zenith.png"
    fig.savefig(out)
    plt.close(fig)
    return [out]


if __name__ == "__main__":
    from pywarp.tutorial import run_as_script

    run_as_script(main, __doc__, "figures/vc")
