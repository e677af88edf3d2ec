"""Figure rr-fig-2.2: the law of reflection and Snell's law at a flat air/water interface (rr-snell), with the share of
the light each ray carries from the Fresnel reflectance (rr-eq2, rr-eq3): (a) one ray from air into water as in the
text's schematic (n1 = 1, n2 = 1.33), (b) a fan of rays from air into water, (c) a fan from water into air, where the
rays beyond the critical angle are totally reflected. Every ray is computed, none drawn by hand.
Output: figures/rr/fig-2.2.png.
"""
# %% [markdown]
# A ray meeting the surface between two media splits in two. The reflected ray leaves at the angle it came in
# (theta_r = theta_i, law of reflection); the refracted ray bends towards the normal when it enters the denser
# medium, n1 sin(theta_i) = n2 sin(theta_t) (Snell's law). `pywarp.optics_snell(d, n, n1, n2)` returns both
# directions for a direction d and a normal n (vectors, no angles), and a flag for total internal reflection.
#
# How much light goes each way is the Fresnel reflectance, eqs. (2) and (3) of the text for the two polarisations;
# unpolarised light reflects their mean R = (R_s + R_p)/2 (`pywarp.optics_fresnel(cos_i, n1, n2)`, cosine forms,
# no 0/0 at normal incidence). In the drawings a ray's opacity is the share it carries: R for the reflected one,
# 1 - R for the refracted one. From air into water little is reflected until grazing incidence; from water into air
# everything is reflected beyond the critical angle arcsin(1/1.33) = 48.75 deg.

# %%
from __future__ import annotations

from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from matplotlib.patches import Arc  # noqa: E402

import pywarp  # noqa: E402

N_AIR, N_WATER = 1.0, 1.33
UP = np.array([0.0, 1.0, 0.0])  # the interface is the plane y = 0, air above, water below
AIR, WATER = "#f4f8fc", "#cfe6f7"


def incident(theta_deg, from_above=True):
    """Unit direction of a ray meeting the interface at theta from the normal, travelling left to right."""
    t = np.radians(theta_deg)
    return np.array([np.sin(t), -np.cos(t) if from_above else np.cos(t), 0.0])


def angle_to_normal(v):
    """Angle [deg] between a direction and the vertical (the normal's line)."""
    return float(np.degrees(np.arccos(min(abs(v[1]) / np.linalg.norm(v), 1.0))))


def media(ax, top, bottom, lim):
    ax.fill_between([-lim, lim], 0, lim, color=AIR if top == "air" else WATER, zorder=0)
    ax.fill_between([-lim, lim], -lim, 0, color=WATER if top == "air" else AIR, zorder=0)
    ax.axhline(0.0, color="C0", lw=1.5, zorder=1)
    ax.plot([0, 0], [-lim, lim], color="0.45", ls="--", lw=0.9, zorder=1)
    n_top, n_bot = (N_AIR, N_WATER) if top == "air" else (N_WATER, N_AIR)
    ax.text(-lim + 0.05, lim - 0.12, f"{top}, n = {n_top:g}", fontsize=10, va="top")
    ax.text(-lim + 0.05, -lim + 0.08, f"{bottom}, n = {n_bot:g}", fontsize=10)
    ax.set_xlim(-lim, lim)
    ax.set_ylim(-lim, lim)
    ax.set_aspect("equal")
    ax.set_xticks([])
    ax.set_yticks([])


def ray(ax, start, end, color, alpha, lw=2.0, arrow=True):
    if arrow:
        ax.annotate("", xy=end, xytext=start, arrowprops=dict(arrowstyle="-|>", color=color, lw=lw, alpha=alpha,
                                                              shrinkA=0, shrinkB=0), zorder=3)
    else:
        ax.plot(*np.stack([start, end]).T, color=color, lw=lw, alpha=alpha, zorder=3)


def single_ray(ax, theta_i):
    """(a): one ray from air into water, its reflection and refraction, the angles measured on the vectors."""
    media(ax, "air", "water", 1.25)
    d = incident(theta_i)
    t, r, tir = pywarp.optics_snell(d, UP, N_AIR, N_WATER)
    R, Rs, Rp = (float(x) for x in pywarp.optics_fresnel(np.cos(np.radians(theta_i)), N_AIR, N_WATER))
    ray(ax, -1.1 * d[:2], [0, 0], "k", 1.0, lw=2.4)
    ray(ax, [0, 0], 1.1 * r[:2], "C3", max(R, 0.25), lw=2.4)  # drawn at least 25 % opaque to stay visible
    ray(ax, [0, 0], 1.1 * t[:2], "C2", 1.0 - R, lw=2.4)
    th_i, th_r, th_t = angle_to_normal(d), angle_to_normal(r), angle_to_normal(t)
    for ang, base, col, lab, rad in ((th_i, 90.0, "k", "θ_i", 0.55), (th_r, 90.0 - th_r, "C3", "θ_r", 0.45),
                                     (th_t, 270.0, "C2", "θ_t", 0.55)):
        if base == 90.0:  # between the upward normal and the incident ray (on the left of the normal)
            ax.add_patch(Arc((0, 0), rad, rad, theta1=90.0, theta2=90.0 + ang, color=col, lw=1.2))
            mid = np.radians(90.0 + ang / 2)
        elif base == 270.0:  # between the downward normal and the refracted ray (right)
            ax.add_patch(Arc((0, 0), rad, rad, theta1=270.0, theta2=270.0 + ang, color=col, lw=1.2))
            mid = np.radians(270.0 + ang / 2)
        else:  # between the upward normal and the reflected ray (right)
            ax.add_patch(Arc((0, 0), rad, rad, theta1=90.0 - ang, theta2=90.0, color=col, lw=1.2))
            mid = np.radians(90.0 - ang / 2)
        ax.text(0.36 * np.cos(mid) * rad / 0.45 * 1.15, 0.36 * np.sin(mid) * rad / 0.45 * 1.15, lab, color=col,
                fontsize=10, ha="center", va="center")
    ax.text(-1.2, 0.72, "incident", fontsize=9)
    ax.text(0.72, 1.0, f"reflected\nR = {R:.3f}", fontsize=9, color="C3")
    ax.text(0.72, -0.75, f"refracted\n1 - R = {1 - R:.3f}", fontsize=9, color="C2")
    ax.text(-1.2, -0.42, f"θ_i = {th_i:.2f}°, θ_r = {th_r:.2f}°\nθ_t = {th_t:.2f}°\n"
            f"n1 sin θ_i = {N_AIR * np.sin(np.radians(th_i)):.4f}\nn2 sin θ_t = {N_WATER * np.sin(np.radians(th_t)):.4f}"
            f"\nR_s = {Rs:.4f}, R_p = {Rp:.4f}", fontsize=8.5, va="top")
    ax.set_title(f"(a) one ray, air -> water, θ_i = {theta_i:g}°\n(rr-snell; R from rr-eq2/rr-eq3)", fontsize=10)
    assert int(tir) == 0


def fan(ax, top, bottom, angles):
    """(b), (c): rays at many angles of incidence through one point; opacity = the share each carries."""
    lim = 1.25
    media(ax, top, bottom, lim)
    n1, n2 = (N_AIR, N_WATER) if top == "air" else (N_WATER, N_AIR)
    cmap = plt.get_cmap("viridis")
    for k, th in enumerate(angles):
        col = cmap(k / max(len(angles) - 1, 1))
        d = incident(th)
        t, r, tir = pywarp.optics_snell(d, UP, n1, n2)
        R = float(pywarp.optics_fresnel(np.cos(np.radians(th)), n1, n2)[0])
        ray(ax, -1.15 * d[:2], [0, 0], col, 0.9, lw=1.4, arrow=False)
        ray(ax, [0, 0], 1.15 * r[:2], col, max(R, 0.04), lw=1.4, arrow=False)
        if not tir:
            ray(ax, [0, 0], 1.15 * t[:2], col, max(1.0 - R, 0.04), lw=1.4, arrow=False)
    theta_c = np.degrees(np.arcsin(N_AIR / N_WATER))
    s_c, c_c = np.sin(np.radians(theta_c)), np.cos(np.radians(theta_c))
    if top == "air":
        ax.plot([0, 1.2 * s_c], [0, -1.2 * c_c], color="C3", ls=":", lw=1.4, zorder=4)
        ax.text(-1.2, -0.55, f"refracted rays stay within\nθ_c = {theta_c:.2f}° of the normal\n(dotted)", fontsize=9,
                color="C3")
        ax.set_title("(b) air -> water, θ_i = 0 ... 89°: every ray enters;\nreflection weak except at grazing "
                     "incidence", fontsize=10)
    else:
        ax.plot([0, -1.2 * s_c], [0, 1.2 * c_c], color="C3", ls=":", lw=1.4, zorder=4)
        ax.text(-1.2, -0.55, f"incident beyond θ_c = {theta_c:.2f}°\n(dotted): total internal\nreflection "
                "(optics_snell: tir = 1;\noptics_fresnel: R = 1)", fontsize=9, color="C3")
        ax.set_title("(c) water -> air, θ_i = 0 ... 89°: rays beyond the\ncritical angle are totally reflected",
                     fontsize=10)
    sm = plt.cm.ScalarMappable(cmap=cmap, norm=plt.Normalize(angles[0], angles[-1]))
    return sm


def main(out_dir, quick: bool = False) -> list[Path]:
    out_dir = Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    fig, axes = plt.subplots(1, 3, figsize=(16, 5.9), dpi=80 if quick else 120)
    single_ray(axes[0], 45.0)

    # %% [markdown]
    # The same two functions over all angles of incidence: from air, the refracted rays fill a cone of half-angle
    # 48.75 deg (the critical angle); from water, the rays beyond that angle cannot leave. Opacity shows the
    # Fresnel share: the reflected rays are faint until grazing incidence (air) or the critical angle (water).

    # %%
    angles = np.linspace(0.0, 89.0, 12 if quick else 24)
    fan(axes[1], "air", "water", angles)
    sm = fan(axes[2], "water", "air", angles)
    cb = fig.colorbar(sm, cax=fig.add_axes([0.945, 0.12, 0.012, 0.62]))
    cb.set_label("angle of incidence θ_i [deg]")
    fig.suptitle("Law of reflection and Snell's law (rr-snell), n_air = 1, n_water = 1.33; a ray's opacity is the "
                 "Fresnel share it carries (R reflected, 1 - R refracted)", fontsize=11)
    fig.subplots_adjust(left=0.01, right=0.93, top=0.84, bottom=0.02, wspace=0.05)
    out = out_dir / "fig-2.2.png"
    fig.savefig(out)
    plt.close(fig)
    return [out]


if __name__ == "__main__":
    from pywarp.tutorial import run_as_script

    run_as_script(main, __doc__, "figures/rr")
