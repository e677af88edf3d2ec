"""Figures vc-fig-2.15 (gradients by cloud type) and vc-fig-4.9 (height gradients of clouds with formula 4.7).

Both figures plot the vertical density profiles of vc-4.7 (``pywarp.clouds_height_gradient``), blended over the weather map's
cloud type by vc-A16, as functions of the relative height h in the cloud layer (vc-A15). The remap inside them is
vc-2.27. The thesis does not say whether its remap clamps (spec vc-4.7 note), so both variants are drawn: unclamped as
printed (the default of ``clouds_height_gradient``, clamp=False) and each remap saturated to [0, 1] (clamp=True), with
the peak values the cataloguer computed in spec/vc.md annotated next to the values our function returns. The
cloudscape renderer uses the clamped gradient (``gradient_clamp = 1`` in ``ccl_cloudscape_params_default``,
cclouds/src/cloudscape.c; read from there when the figure is drawn): both figures mark it.

Outputs: figures/vc/fig-2.15.png (density over cloud type and height, the three named types marked) and
figures/vc/fig-4.9.png (the three profiles against h, with their formulas).
"""
# %% [markdown]
# A cloud layer is not equally dense at every height. Stratus is a thin sheet near the bottom of the layer,
# stratocumulus is a little taller, and cumulus towers up through most of it. The renderer encodes this with a
# height gradient D_v(h): the base cloud shape is multiplied by it (vc-2.29), so where D_v is 0 no cloud can form.
# Each gradient of formula 4.7 is the product of a rising ramp remap(h, a, b, 0, 1) and a falling ramp
# remap(h, c, d, 1, 0).
#
# The catch: remap (2.27) is a plain linear map. Outside its input range it keeps going, so the "ramps" are really
# straight lines and their product is a parabola that can climb far above 1 (cumulus reaches 2.18). If each remap is
# clamped to [0, 1] instead, the curves become the trapezoids one expects from the description. The thesis prints no
# clamp; the function follows the print by default and offers clamp=True. The renderer draws its clouds with the
# clamped gradient: unclamped, D_v reaches 2.18 and the coverage remap of vc-2.29 would then amplify density instead of
# thinning it (the reason given with ``ccl_cloudscape_params_default``).

# %%
from __future__ import annotations

from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import pywarp  # noqa: E402

# Cloud types of the weather map's blue channel (vc-A16) and the parameters of their two remaps in formula 4.7.
TYPES = (  # name, cloud_type, (a, b) rising remap, (c, d) falling remap
    ("cumulus", 1.0, (0.01, 0.30), (0.6, 0.95)),
    ("stratocumulus", 0.5, (0.01, 0.25), (0.3, 0.65)),
    ("stratus", 0.0, (0.01, 0.05), (0.0, 0.20)),
)
# The cataloguer's values (spec/vc.md, vc-4.7 notes): peak of the unclamped product and its height; the clamped
# description. Typed in from the spec, never computed here, so the figure shows any disagreement with the code.
SPEC_UNCLAMPED = {"cumulus": ("2.1764", 0.48), "stratocumulus": ("1.2190", 0.33), "stratus": ("1.1281", 0.105)}
SPEC_CLAMPED = {"cumulus": "1 on [0.30, 0.60]", "stratocumulus": "1 on [0.25, 0.30]", "stratus": "0.75 at h = 0.05"}


def renderer_clamp() -> bool:
    """Whether the cloudscape renderer clamps the gradient: ``gradient_clamp`` of ``ccl_cloudscape_params_default``."""
    from pywarp.clouds.cloudscape import CloudscapeSettings

    return bool(CloudscapeSettings().c_values()["gradient_clamp"])


def variants() -> tuple:
    """(clamp, label) of the two readings; the renderer's is named."""
    used = renderer_clamp()
    mark = lambda clamp: " — used by the renderer" if clamp == used else ""  # noqa: E731
    return ((False, "remap unclamped, as printed (function default)" + mark(False)),
            (True, "each remap clamped to [0, 1]" + mark(True)))


def _peak(h, d):
    """Largest value of a sampled profile and the mean height of the samples within 1e-6 of it (a plateau's middle)."""
    top = float(d.max())
    return top, float(h[d >= top - 1e-6].mean())


def fig_2_15(out_dir: Path, quick: bool) -> Path:
    # %% [markdown]
    # Figure 2.15: the density as an image over cloud type (horizontal) and height (vertical), the way the profiles
    # are used: the weather map's blue channel picks a column, the sample's relative height a row. Between the three
    # named types the gradients are blended linearly (vc-A16). The white contour is D_v = 1: inside it the printed
    # (unclamped) formula produces densities above 1, which the clamped variant caps.

    # %%
    n_h, n_t = (101, 51) if quick else (401, 201)
    h = np.linspace(0.0, 1.0, n_h, dtype=np.float32)
    cloud_type = np.linspace(0.0, 1.0, n_t, dtype=np.float32)
    fig, axes = plt.subplots(1, 2, figsize=(12, 5.6), dpi=90 if quick else 150, sharey=True)
    vmax = 2.2  # shared colour scale: the unclamped cumulus peak (2.18) fits, and the two panels compare directly
    used = renderer_clamp()
    for ax, (clamp, label) in zip(axes, variants()):
        d_v = pywarp.clouds_height_gradient(h[:, None], cloud_type[None, :], clamp=clamp)
        im = ax.imshow(d_v, origin="lower", extent=(0.0, 1.0, 0.0, 1.0), aspect="auto", cmap="cividis",
                       vmin=0.0, vmax=vmax, interpolation="bilinear")
        ax.contour(cloud_type, h, d_v, levels=[1.0], colors="white", linewidths=1.0)
        for name, t, _, _ in TYPES:
            ax.axvline(t, color="0.85", lw=0.8, ls=":")
            col = int(round(t * (n_t - 1)))
            top, h_top = _peak(h, d_v[:, col])
            if clamp:
                text = f"{name}\nspec: {SPEC_CLAMPED[name]}\npywarp: max {top:.4g} at h = {h_top:.3g}"
            else:
                sv, sh = SPEC_UNCLAMPED[name]
                text = f"{name}\nspec: max {sv} at h = {sh}\npywarp: max {top:.4f} at h = {h_top:.3g}"
            ax.plot([t], [h_top], "o", ms=6, mfc="white", mec="black", zorder=5)
            # fixed label boxes that cannot overlap: stratus left and cumulus right at mid height, stratocumulus top
            ha, xy_text = {0.0: ("left", (0.03, 0.62)), 0.5: ("center", (0.5, 0.87)), 1.0: ("right", (0.97, 0.62))}[t]
            ax.annotate(text, (t, h_top), xytext=xy_text, ha=ha, va="bottom", fontsize=7.5,
                        arrowprops={"arrowstyle": "-", "color": "white", "lw": 0.7},
                        bbox={"boxstyle": "round,pad=0.3", "fc": "white", "ec": "none", "alpha": 0.85})
        ax.set_xticks([0.0, 0.25, 0.5, 0.75, 1.0],
                      ["0\nstratus", "0.25", "0.5\nstratocumulus", "0.75", "1\ncumulus"])
        ax.set_xlabel("cloud type (weather map blue channel, vc-A16)")
        ax.set_title(label, fontsize=11, fontweight="bold" if clamp == used else "normal")
        if clamp == used:  # the renderer's gradient: a frame around its panel
            for spine in ax.spines.values():
                spine.set_edgecolor("C3")
                spine.set_linewidth(2.5)
    axes[0].set_ylabel("relative height h in the cloud layer (vc-A15)")
    fig.colorbar(im, cax=fig.add_axes((0.895, 0.17, 0.015, 0.72)), label="vertical density $D_v$ (vc-4.7)")
    fig.suptitle("Height gradients by cloud type (vc-4.7 blended by vc-A16); white contour: $D_v = 1$")
    fig.text(0.43, 0.045, "Difference: printed unclamped, remap extrapolates and the products exceed 1 "
             "(cumulus 2.18); clamped, every profile stays <= 1 and stratus peaks at only 0.75.",
             ha="center", fontsize=9)
    fig.text(0.43, 0.012, f"The renderer uses the {'clamped' if used else 'unclamped'} gradient (framed; "
             f"gradient_clamp = {int(used)} in ccl_cloudscape_params_default): unclamped, the coverage remap "
             "would amplify density.", ha="center", fontsize=9, color="C3")
    fig.subplots_adjust(left=0.06, right=0.87, top=0.89, bottom=0.19, wspace=0.14)
    out = out_dir / "fig-2.15.png"
    fig.savefig(out)
    plt.close(fig)
    return out


def fig_4_9(out_dir: Path, quick: bool) -> Path:
    # %% [markdown]
    # Figure 4.9: each profile against h with its formula. Solid: the printed, unclamped formula (the function's
    # default); dashed: the clamped variant, the one the renderer uses. The dotted line is density 1. The variants agree only where both ramps are inside
    # their input ranges at the same height: for stratus on [0.01, 0.05]. For the other two types the ramps do not
    # overlap, so at every height one of them is extrapolated beyond 1 and the printed curve lies above the clamped.

    # %%
    n = 201 if quick else 1001
    h = np.linspace(0.0, 1.0, n, dtype=np.float32)
    fig, axes = plt.subplots(1, 3, figsize=(14, 4.9), dpi=90 if quick else 150, sharey=True)
    styles = {False: {"ls": "-", "lw": 2.0}, True: {"ls": "--", "lw": 1.6}}
    for ax, (name, t, (a, b), (c, d)) in zip(axes, TYPES):
        for clamp, label in variants():
            d_v = pywarp.clouds_height_gradient(h, t, clamp=clamp)
            ax.plot(h, d_v, color="C0" if not clamp else "C3", label=label, **styles[clamp])
            top, h_top = _peak(h, d_v)
            ax.plot([h_top], [top], "o", color="C0" if not clamp else "C3", ms=5)
        sv, sh = SPEC_UNCLAMPED[name]
        ax.annotate(f"spec: max {sv} at h = {sh}", (sh, float(sv)), xytext=(0.72 if name == "cumulus" else 0.6, 2.25),
                    fontsize=8, ha="center", color="C0", arrowprops={"arrowstyle": "->", "color": "C0", "lw": 0.7})
        clamped_xy = {"cumulus": (0.45, 1.0), "stratocumulus": (0.275, 1.0), "stratus": (0.05, 0.75)}[name]
        text_xy = (0.45, 1.4) if name == "cumulus" else (0.62, 1.45)  # cumulus: inside its arc, clear of the curve
        ax.annotate(f"clamped, spec: {SPEC_CLAMPED[name]}", clamped_xy, xytext=text_xy, fontsize=8,
                    ha="center", color="C3", arrowprops={"arrowstyle": "->", "color": "C3", "lw": 0.7})
        ax.axhline(1.0, color="0.5", lw=0.7, ls=":")
        ax.set_title(f"{name} (cloud type {t:g})\n"
                     rf"$\max(0,\ \mathrm{{remap}}(h, {a}, {b}, 0, 1)\cdot\mathrm{{remap}}(h, {c}, {d}, 1, 0))$",
                     fontsize=10)
        ax.set_xlabel("relative height h")
        ax.set_xlim(0.0, 1.0)
        ax.set_ylim(-0.03, 2.45)
        ax.grid(alpha=0.25)
    axes[0].set_ylabel("vertical density $D_v$")
    handles, labels = axes[0].get_legend_handles_labels()
    fig.legend(handles, labels, loc="lower center", bbox_to_anchor=(0.5, 0.085), ncol=2, fontsize=9, frameon=False)
    fig.suptitle("Height gradients of clouds, formula 4.7 (pywarp.clouds_height_gradient); markers: maxima computed by "
                 "pywarp", fontsize=11)
    used = renderer_clamp()
    fig.text(0.5, 0.045, "Difference: solid = printed, unclamped remap (function default; peaks 2.1764, 1.2190, "
             "1.1281); dashed = each remap clamped to [0, 1] (plateaus at 1, stratus only 0.75).", ha="center",
             fontsize=9)
    fig.text(0.5, 0.012, f"The cloudscape renderer draws its clouds with the "
             f"{'dashed (clamped)' if used else 'solid (unclamped)'} profiles (gradient_clamp = {int(used)} in "
             "ccl_cloudscape_params_default).", ha="center", fontsize=9, color="C3")
    fig.subplots_adjust(left=0.05, right=0.99, top=0.80, bottom=0.27, wspace=0.1)
    out = out_dir / "fig-4.9.png"
    fig.savefig(out)
    plt.close(fig)
    return out


def main(out_dir, quick: bool = False) -> list[Path]:
    out_dir = Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    return [fig_2_15(out_dir, quick), fig_4_9(out_dir, quick)]


if __name__ == "__main__":
    from pywarp.tutorial import run_as_script

    run_as_script(main, __doc__, "figures/vc")
