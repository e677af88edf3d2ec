"""The display transform every scene's 8-bit output goes through: an exposure in EV, then a tone curve.

A scene renders *display-linear* RGB (the float image :mod:`pywarp.core.linear` writes to ``.exr`` / ``.npy``, kept
scene-linear and unclipped there). Since the sky-driven lighting that image is HDR: sunlit cloud tops reach 1.5 and
more, and clamping them at 1 flattens their shape to white. Before the scene's own encoding (the sRGB OETF of the
cloudscape, none for the terrain and the rain, whose colours the texts give display-referred) and the 8-bit
quantisation, every PNG, GIF, MP4 and viewer frame is therefore

    y = T(2^EV * x)    per channel, x >= 0

with ``EV`` the scene's ``exposure_ev`` setting (``--exposure``; a per-scene default with its reason) and ``T`` its
``tonemap`` setting (``--tonemap``):

* ``"aces"`` (the default): the fit of the ACES filmic reference rendering transform by K. Narkowicz, "ACES Filmic
  Tone Mapping Curve" (2015, https://knarkowicz.wordpress.com/2016/01/06/aces-filmic-tone-mapping-curve/),
  T(x) = x (2.51 x + 0.03) / (x (2.43 x + 0.59) + 0.14), saturated to [0, 1]. T(0) = 0, T is increasing for x >= 0
  (its derivative's numerator (ad - bc) x^2 + 2ae x + be has positive coefficients), has a toe below ~0.1 and a
  shoulder that reaches 1 only at x = 7.24: a highlight 1.5x above white keeps its gradient instead of clipping.
  One curve per channel, as the fit is used in games: a very bright, saturated colour drifts towards white, as film
  does.
* ``"exponential"``: T(x) = 1 - exp(-x), the form of the vc thesis's own tone map (vc-4.5, C = 1 - exp(-k C_HDR),
  which the thesis applies to the Preetham sky only; here to the whole frame, k = 2^EV). Never reaches 1.
* ``"none"``: T(x) = x, then the encoding's clamp to [0, 1]: the output before the display transform existed, bit
  for bit at 0 EV (a multiplication by 2^0 = 1 is exact).

The transform is a vectorised NumPy function of the float frame (:func:`apply`): a few milliseconds at 640 x 360 on
one core, small beside the frame itself; the viewer shows the frames of ``render``, so the same transform.
"""
from __future__ import annotations

import numpy as np

from .params import param

#: The tone curves of the ``tonemap`` setting (see the module docstring).
TONEMAPS = ("aces", "exponential", "none")

#: Narkowicz's ACES fit, T(x) = x (A x + B) / (x (C x + D) + E).
ACES_A, ACES_B, ACES_C, ACES_D, ACES_E = 2.51, 0.03, 2.43, 0.59, 0.14

#: Range of the exposure (EV): 2^-10 .. 2^10, beyond anything a scene's float image needs.
EXPOSURE_RANGE = (-10.0, 10.0)


def exposure_param(default: float, reason: str, **extra):
    """The ``exposure_ev`` field of a scene's settings (``--exposure``), with the scene's default and its reason."""
    return param(default, unit="EV", lo=EXPOSURE_RANGE[0], hi=EXPOSURE_RANGE[1], group="display", cli="--exposure",
                 doc="exposure of the display transform: the float image is scaled by 2^EV before the tone curve "
                     "(8-bit outputs and the viewer only; .exr and .npy stay scene-linear)",
                 reason=reason, **extra)


def tonemap_param(default: str = "aces", reason: str = "", **extra):
    """The ``tonemap`` field of a scene's settings (``--tonemap``)."""
    return param(default, choices=TONEMAPS, group="display",
                 doc="tone curve of the display transform (pywarp.core.display): aces (Narkowicz 2015's fit of the "
                     "ACES filmic curve), exponential (1 - exp(-x), the form of the vc thesis's tone map vc-4.5), "
                     "none (clamp to [0, 1], the output before the display transform)",
                 reason=reason or "aces: highlights above 1 (sunlit cloud tops) keep their gradient instead of "
                                  "clipping to white; mid-tones keep their contrast", **extra)


def aces(x):
    """Narkowicz's ACES fit of ``x`` (any shape; float32 out), saturated to [0, 1]; negative inputs give 0. In place
    on two arrays of the image's size: a few milliseconds per 640 x 360 frame."""
    x = np.maximum(np.asarray(x, dtype=np.float32), np.float32(0.0))
    den = x * np.float32(ACES_C)
    den += np.float32(ACES_D)
    den *= x
    den += np.float32(ACES_E)
    num = x * np.float32(ACES_A)
    num += np.float32(ACES_B)
    num *= x
    num /= den
    return np.minimum(num, np.float32(1.0), out=num)


def exponential(x):
    """1 - exp(-x) of ``x`` (any shape; float32 out); negative inputs give 0."""
    y = np.maximum(np.asarray(x, dtype=np.float32), np.float32(0.0))
    np.negative(y, out=y)
    np.expm1(y, out=y)
    return np.negative(y, out=y)


def check(exposure_ev: float, tonemap: str) -> None:
    """ValueError naming the setting when ``exposure_ev`` or ``tonemap`` is out of its domain."""
    lo, hi = EXPOSURE_RANGE
    if not (isinstance(exposure_ev, (int, float)) and lo <= exposure_ev <= hi):
        raise ValueError(f"exposure_ev must be in [{lo:g}, {hi:g}], got {exposure_ev!r}")
    if tonemap not in TONEMAPS:
        raise ValueError(f"tonemap must be one of {', '.join(TONEMAPS)}, got {tonemap!r}")


def apply(rgb, exposure_ev: float = 0.0, tonemap: str = "aces") -> np.ndarray:
    """The display transform T(2^EV x) of a float image (float32 out, same shape): display-linear values for the
    scene's encoding, which clamps to [0, 1]. ``tonemap="none"`` at 0 EV returns the values unchanged. NaN and Inf
    stay non-finite (T(Inf) is NaN), so the encoders still refuse such an image."""
    check(exposure_ev, tonemap)
    x = np.asarray(rgb, dtype=np.float32)
    if exposure_ev != 0.0:
        x = x * np.float32(2.0 ** exposure_ev)
    if tonemap == "aces":
        return aces(x)
    if tonemap == "exponential":
        return exponential(x)
    return x


def apply_settings(rgb, settings) -> np.ndarray:
    """:func:`apply` with a scene's ``exposure_ev`` and ``tonemap`` settings."""
    return apply(rgb, settings.exposure_ev, settings.tonemap)


def srgb_oetf(c):
    """The sRGB encoding (IEC 61966-2-1) of linear values in [0, 1] (float32)."""
    c = np.asarray(c, dtype=np.float32)
    return np.where(c <= 0.0031308, 12.92 * c, 1.055 * np.power(c, 1.0 / 2.4) - 0.055).astype(np.float32)


def srgb_eotf(c):
    """The sRGB decoding (IEC 61966-2-1) of encoded values in [0, 1] (float32)."""
    c = np.asarray(c, dtype=np.float32)
    return np.where(c <= 0.04045, c / 12.92, np.power((c + 0.055) / 1.055, 2.4)).astype(np.float32)


def quantise(display, srgb: bool) -> np.ndarray:
    """uint8 of display values: clamp to [0, 1], the sRGB OETF when ``srgb`` (display-linear values), then
    int(v * 255 + 0.5)."""
    c = np.clip(np.asarray(display, dtype=np.float32), 0.0, 1.0)
    if srgb:
        c = srgb_oetf(c)
    return (c * 255.0 + 0.5).astype(np.uint8)


#: Samples of the composed curve of :func:`encode_encoded` over [0, 1], looked up at the nearest one: with 2^16 of
#: them a byte differs from the per-pixel evaluation only at a rounding edge, by one level (about 0.1 % of the bytes
#: of a uniformly random image); the per-pixel evaluation, with two powers, costs several times more.
ENCODED_CURVE_SAMPLES = 65536


def encode_encoded(rgb, exposure_ev: float, tonemap: str) -> np.ndarray:
    """uint8 of a scene whose float image is already display-encoded (the terrain's colours, which the text gives as
    displayed values), clamped to [0, 1]: decoded to linear light (sRGB EOTF), :func:`apply`, encoded again and
    quantised -- one curve of the value, tabulated as bytes (:data:`ENCODED_CURVE_SAMPLES`) and looked up.
    ``tonemap="none"`` at 0 EV is the plain clamp and quantisation of the values, as before the display transform.
    The caller checks that ``rgb`` is finite (a NaN has no byte)."""
    check(exposure_ev, tonemap)
    if tonemap == "none" and exposure_ev == 0.0:
        return quantise(rgb, srgb=False)
    v = np.linspace(0.0, 1.0, ENCODED_CURVE_SAMPLES, dtype=np.float32)
    table = quantise(apply(srgb_eotf(v), exposure_ev, tonemap), srgb=True)
    c = np.clip(np.asarray(rgb, dtype=np.float32), 0.0, 1.0)
    c *= np.float32(ENCODED_CURVE_SAMPLES - 1)
    c += np.float32(0.5)
    return table[c.astype(np.uint16)]


def luminance(img: np.ndarray) -> np.ndarray:
    """Rec. 709 luma of a uint8 sRGB picture (0..255, float64): what the benchmarks' SSIM is measured on."""
    return np.asarray(img, np.float64)[..., :3] @ np.array([0.2126, 0.7152, 0.0722])
