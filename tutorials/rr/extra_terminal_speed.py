"""Extra rr-extra-terminal-speed: terminal speed of raindrops (rr-tab-2.2): the 23 rows of Table 2.2, the documented
interpolation between them, the Stokes extension below 0.1 mm, the plateau, and the application's slow-down by 4.
Output: figures/rr/extra-terminal-speed.png.
"""
# %% [markdown]
# A falling drop accelerates until drag balances gravity; that terminal speed is reached within a few metres and is
# the speed at which rain hits the ground. Table 2.2 (Gunn & Kinzer 1949, via Rousseau et al.) lists it against the
# drop RADIUS: spherical drops up to 0.45 mm, flattened ones from 0.5 mm, levelling off at 9.23 m/s from 2.75 mm.
#
# `pywarp.rain_terminal_speed(radius_mm, slowdown)` interpolates linearly between the rows, extends below the first
# row with Stokes' law (v proportional to r^2, 0 at r = 0) and holds the plateau beyond the last; `slowdown` divides
# the speed (the application divides by 4, rr §5.2.2, so that the rain is watchable).

# %%
from __future__ import annotations

from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import pywarp  # noqa: E402
from pywarp.kernels import rain  # noqa: E402


def main(out_dir, quick: bool = False) -> list[Path]:
    out_dir = Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    r = np.linspace(0.0, 5.0, 201 if quick else 2001)
    v = pywarp.rain_terminal_speed(r)
    v4 = pywarp.rain_terminal_speed(r, rain.APP_SLOWDOWN)
    rows_r, rows_v = np.array(rain.SPEED_RADII), np.array(rain.SPEED_VALUES)

    fig, ax = plt.subplots(figsize=(9, 5.2), dpi=80 if quick else 120)
    ax.plot(r, v, color="C0", lw=2, label="rain_terminal_speed(r): linear between rows")
    ax.plot(r, v4, color="C1", lw=1.5, ls="--", label="slowdown = 4 (the application)")
    ax.plot(rows_r[:8], rows_v[:8], "o", color="C2", ms=5, label="Table 2.2, spherical drops")
    ax.plot(rows_r[8:], rows_v[8:], "s", color="C3", ms=5, label="Table 2.2, ellipsoidal drops")
    ax.axvspan(0, 0.1, color="0.9")
    ax.text(0.05, 5.2, "Stokes\nv ∝ r²", ha="center", fontsize=8)
    ax.axvspan(4.0, 5.0, color="0.93")
    ax.text(4.5, 7.5, "plateau\n(beyond the table)", ha="center", fontsize=8)
    ax.axvline(1.3, color="0.5", lw=0.8, ls=":")
    ax.text(1.33, 0.6, "1.3 mm: mean particle size (rr §5.2.2)", fontsize=8, color="0.35")
    ax.set_xlabel("drop radius r [mm]")
    ax.set_ylabel("terminal speed [m/s]")
    ax.set_xlim(0, 5)
    ax.set_ylim(0, 10)
    ax.grid(alpha=0.3)
    ax.legend(loc="lower right", fontsize=9)
    ax.set_title("Terminal speed of raindrops (rr-tab-2.2): 9.23 m/s from r = 2.75 mm")
    fig.tight_layout()
    out = out_dir / "extra-terminal-speed.png"
    fig.savefig(out)
    plt.close(fig)
    return [out]


if __name__ == "__main__":
    from pywarp.tutorial import run_as_script

    run_as_script(main, __doc__, "figures/rr")
