"""Extra figure vc-extra-phase-functions: the phase functions of the thesis in polar form.

Not a figure of the thesis: it draws the equations of §2.1.4 that the text gives without a plot — isotropic (vc-2.11),
Rayleigh (vc-2.12), Henyey–Greenstein (vc-2.13) for several g, and Schlick's approximation (vc-2.15) with
k = k(g) (vc-2.16) — plus the sign erratum of vc-2.15 ('thesis' variant). Output: figures/vc/extra-phase-functions.png.
"""
# %% [markdown]
# A phase function p(θ) says how much of the light that scatters at a point leaves at angle θ from its original
# direction. It is a probability density over the sphere, so it integrates to 1 (vc-2.8). In a polar plot, the
# radius in direction θ is p(θ): the incoming light travels from left to right, so forward scattering (θ = 0)
# points right.

# %%
from __future__ import annotations

from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import pywarp  # noqa: E402


def main(out_dir, quick: bool = False) -> list[Path]:
    out_dir = Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    n = 181 if quick else 721
    theta = np.linspace(0.0, 2.0 * np.pi, n)
    mu = np.cos(theta)

    # %% [markdown]
    # Left: isotropic and Rayleigh scattering. Rayleigh (small molecules, the blue sky) scatters as much backward as
    # forward, and half as much sideways.
    # Middle: Henyey–Greenstein. g is the mean cosine of the scattering angle; clouds scatter strongly forward
    # (g ≈ 0.8 for water droplets), which gives the bright "silver lining" when looking towards the sun.
    # Right: Schlick's cheaper lobe with k = 1.55 g − 0.55 g³ tracks HG closely. As printed in the thesis, the
    # denominator (1 + k cos θ)² turns the lobe backward for k > 0 (dashed): the 'thesis' variant.

    # %%
    fig, axes = plt.subplots(1, 3, subplot_kw={"projection": "polar"}, figsize=(13, 5.4), dpi=110 if quick else 150)
    ax = axes[0]
    ax.plot(theta, np.full_like(theta, pywarp.phase_isotropic()), label="isotropic (2.11)")
    ax.plot(theta, pywarp.phase_rayleigh(mu), label="Rayleigh (2.12)")
    ax.set_title("isotropic and Rayleigh [sr⁻¹]")

    ax = axes[1]
    for g in (0.0, 0.3, 0.5, 0.7):
        ax.plot(theta, pywarp.phase_hg(mu, g), label=f"HG g = {g}")
    ax.set_rscale("log")  # the forward peak grows as (1 + g)/(1 - g)^2: a log radius keeps every lobe visible
    ax.set_rlim(0.005, 2.0)
    ax.set_title("Henyey–Greenstein (2.13), log radius")

    ax = axes[2]
    g = 0.5
    k = float(pywarp.phase_schlick_k(g))
    ax.plot(theta, pywarp.phase_hg(mu, g), label=f"HG g = {g}")
    ax.plot(theta, pywarp.phase_schlick(mu, k), label=f"Schlick k(g) = {k:.3f}")
    ax.plot(theta, pywarp.phase_schlick(mu, k, variant="thesis"), "--", label="Schlick as printed (thesis)")
    ax.set_title("Schlick (2.15, 2.16) and its sign erratum")
    for ax in axes:
        ax.legend(loc="upper center", bbox_to_anchor=(0.5, -0.08), fontsize=8, ncol=2, frameon=False)
        ax.tick_params(labelsize=7)
        ax.title.set_position((0.5, 1.08))
    fig.suptitle("Phase functions [sr⁻¹]; light arrives from the left, θ = 0 (right) is forward scattering")
    fig.subplots_adjust(left=0.04, right=0.96, top=0.80, bottom=0.22, wspace=0.35)
    out = out_dir / "extra-phase-functions.png"
    fig.savefig(out)
    plt.close(fig)
    return [out]


if __name__ == "__main__":
    from pywarp.tutorial import run_as_script

    run_as_script(main, __doc__, "figures/vc")
