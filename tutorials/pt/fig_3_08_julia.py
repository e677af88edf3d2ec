"""Figure pt-fig-3.8: Julia sets for f(x) = x^5 + 0.544, f(x) = x^2 + 0.285 + 0.01i and f(x) = e^x - 0.65.

In kind: escape-time images of eq. 3.1 (pt-3.1) for the three maps of the caption (pt-u-julia,
pywarp.fractal_julia_example): |z| > 16 for the polynomials, Re z > 50 for the exponential map; 300 iterations (100 for
the exp map); members black, the others coloured by the smooth escape count on a cyclic, perceptually uniform palette
(twilight_shifted) -- three turns over the log of the count for the polynomials; for the exp map one turn per lap of its
orbits (below), with the super-logarithm as its smooth count and 3 x 3 start values a pixel (its hairs are thinner
than a pixel). Viewports, iteration counts and palette are not given in the text. Output: figures/pt/fig-3.8.png.
"""
# %% [markdown]
# Every pixel is a start value a_0 in the complex plane. Iterating a_{n+1} = f(a_n), the orbit either stays bounded
# (the pixel belongs to the filled Julia set, the text's "Julia set": black) or runs off to infinity; the step at which
# it is certainly gone colours the pixel. For z^d + c, |z| beyond max(|c|, 2^(1/(d-1))) proves escape. For e^z + c
# the modulus is no test -- e^z is small for Re z << 0 and periodic in Im z -- and orbits escape along the positive
# real direction, hence the test Re z > 50 (the next iterate is ~e^50).
#
# A smooth count for e^z + c. For z^d + c, n + 1 - log_d(ln|a_n| / ln R) is continuous: a start value that escapes one
# step later has an |a_n| one power of d larger. Here each step exponentiates (Re a_{n+1} ~ e^{Re a_n}), so the
# super-logarithm slog (the number of logarithms that bring x below 1, plus the rest: the inverse of tetration, taken
# linear between integers) takes the place of log_d ln: n + 1 - (slog(Re a_n) - slog(R)), with Re a_n in (R, e^R], is
# continuous where neighbouring start values escape one step apart. Everywhere else the escape count of e^z - 0.65
# jumps by a lap: the Julia set of this map is the whole plane (e^z - 0.65 is conjugate to 0.52 e^z, above 1/e), and
# where Re a_n passes R while cos(Im a_n) < 0 the next iterate is ~ -e^R, and the one after it is c itself, whose
# orbit starts again. Such a jump is the smooth count of c plus one, so a palette that turns once per lap is
# continuous across it as well: what is left are the hairs and the edges where an orbit leaves between the two.

# %%
from __future__ import annotations

from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import pywarp  # noqa: E402

VIEWS = {"x5": ((-1.25, 1.25), (-1.25, 1.25), 300, "f(x) = x^5 + 0.544"),
         "x2": ((-1.6, 1.6), (-1.2, 1.2), 300, "f(x) = x^2 + 0.285 + 0.01i"),
         "exp": ((-2.0, 4.5), (-3.5, 3.5), 100, "f(x) = e^x - 0.65")}
#: Start values a pixel of the exp panel, per side: its hairs and lap edges are thinner than a pixel, and 3 x 3
#: samples averaged in colour draw them without stair steps at the cost of 9 times its (few-step) iterations.
EXP_SUPERSAMPLE = 3
EXP_C = -0.65  # the constant of the exp map (pywarp.fractal_julia_example's "exp")
EXP_ESCAPE = 50.0  # its escape test Re z > R


def slog(x: np.ndarray) -> np.ndarray:
    """Super-logarithm, linear between integers: x - 1 on [0, 1] (clamped to -1 below 0), 1 + slog(ln x) above 1.
    slog(e^x) = slog(x) + 1 for every x > 0."""
    x = np.asarray(x, dtype=np.float64).copy()
    s = np.zeros_like(x)
    for _ in range(8):  # 8 logarithms bring any float64 below 1 (ln ln ln ln 1.8e308 < 1.0)
        big = x > 1.0
        s += big
        x = np.where(big, np.log(np.where(big, x, 1.0)), x)
    return s + np.clip(x, 0.0, 1.0) - 1.0


def exp_smooth_count(z0: np.ndarray, count: np.ndarray, max_iter: int) -> np.ndarray:
    """Smooth escape count count + 1 - (slog(Re a_count) - slog(R)) of e^z + c from start values ``z0`` (..., 2) and
    their escape ``count`` (the kernel's): the orbit re-run in float64 for ``count`` steps. Re a_count is clamped to
    (R, e^R], the values it takes after a step from Re a < R, so the fraction stays in [0, 1] where float32 and
    float64 orbits part (a chaotic orbit doubles its rounding error every step or so)."""
    z = z0[..., 0].astype(np.float64) + 1j * z0[..., 1].astype(np.float64)
    with np.errstate(over="ignore", invalid="ignore"):
        for k in range(int(count.max(initial=0))):
            go = count > k
            z = np.where(go, np.exp(np.where(go, z, 0.0)) + EXP_C, z)
    x = np.clip(np.nan_to_num(z.real, nan=EXP_ESCAPE), EXP_ESCAPE, np.exp(EXP_ESCAPE))
    smooth = count + 1.0 - (slog(x) - slog(EXP_ESCAPE))
    return np.where(count < max_iter, smooth, float(max_iter))


def exp_panel(xr, yr, n: int, ny: int, max_iter: int, cmap) -> tuple[np.ndarray, np.ndarray]:
    """The exp map's panel (ny, n, 3) and its escape counts at the 3 x 3 start values of each pixel."""
    ss = EXP_SUPERSAMPLE
    x = xr[0] + (np.arange(n * ss) + 0.5) / (n * ss) * (xr[1] - xr[0])
    y = yr[0] + (np.arange(ny * ss) + 0.5) / (ny * ss) * (yr[1] - yr[0])
    z0 = np.stack(np.meshgrid(x, y), -1).astype(np.float32)
    count, _ = pywarp.fractal_julia_example(z0, max_iter, example="exp")
    smooth = exp_smooth_count(z0, count, max_iter)
    c = np.array([[[EXP_C, 0.0]]], dtype=np.float32)
    lap = exp_smooth_count(c, pywarp.fractal_julia_example(c, max_iter, example="exp")[0], max_iter)[0, 0] + 1.0
    rgb = cmap(np.mod(smooth / lap, 1.0))[..., :3]
    rgb[count == max_iter] = 0.0
    return rgb.reshape(ny, ss, n, ss, 3).mean(axis=(1, 3)), count


def main(out_dir, quick: bool = False) -> list[Path]:
    out_dir = Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    n = 110 if quick else 420
    t = np.linspace(0.01, 30.0, 301)
    assert np.allclose(slog(np.exp(t)), slog(t) + 1.0)  # the property the smooth exp count rests on
    fig, axes = plt.subplots(1, 3, figsize=(15, 5.8), dpi=70 if quick else 100)
    cmap = plt.get_cmap("twilight_shifted")
    for ax, (example, (xr, yr, max_iter, title)) in zip(axes, VIEWS.items()):
        ny = int(round(n * (yr[1] - yr[0]) / (xr[1] - xr[0])))
        x = xr[0] + (np.arange(n) + 0.5) / n * (xr[1] - xr[0])
        y = yr[0] + (np.arange(ny) + 0.5) / ny * (yr[1] - yr[0])
        if example == "exp":  # one turn of the palette per lap of the orbits, 3 x 3 start values a pixel
            rgb, count = exp_panel(xr, yr, n, ny, max_iter, cmap)
        else:
            z0 = np.stack(np.meshgrid(x, y), -1).astype(np.float32)
            count, smooth = pywarp.fractal_julia_example(z0, max_iter, example=example)
            v = np.log1p(np.maximum(smooth, 0.0)) / np.log1p(max_iter)
            rgb = cmap(np.mod(3.0 * v, 1.0))[..., :3]
            rgb[count == max_iter] = 0.0
        ax.imshow(rgb, origin="lower", extent=(*xr, *yr), interpolation="nearest")
        ax.set_title(f"{title}\n{max_iter} iterations, {np.mean(count == max_iter) * 100:.1f} % bounded", fontsize=10)
        ax.set_xlabel("Re a0")
        ax.set_ylabel("Im a0")
    fig.suptitle("Julia sets (eq. 3.1, pt-3.1) of the three maps of Obrazok 3.8 (pt-u-julia): escape |z| > 16 "
                 "(polynomials), Re z > 50 (exp); colour = smooth escape count", fontsize=11)
    fig.subplots_adjust(left=0.045, right=0.99, bottom=0.1, top=0.83, wspace=0.22)
    out = out_dir / "fig-3.8.png"
    fig.savefig(out)
    plt.close(fig)
    return [out]


if __name__ == "__main__":
    from pywarp.tutorial import run_as_script

    run_as_script(main, __doc__, "figures/pt")
