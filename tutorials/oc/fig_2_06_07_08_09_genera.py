"""Figures oc-fig-2.6, oc-fig-2.7, oc-fig-2.8 and oc-fig-2.9 (photographs of nimbostratus, stratocumulus, stratus and
cumulus), stand-ins rendered by the vc cloudscape from the same library -- a tie between the two texts.

The oc text shows photographs of the ten cloud genera (§2.1.2); the volumetric cloud layer of the vc thesis models
low clouds by a cloud type per ground position (0 stratus, 0.5 stratocumulus, 1 cumulus: the weather map's blue
channel, vc-A12, with the height gradients of vc-4.7), so four of the genera have a stand-in: stratus (type 0 under an
overcast: a thin uniform grey sheet with a flat base, precipitation 0.5), stratocumulus (type 0.5, coverage 0.7),
cumulus (type 1, coverage 0.3) and nimbostratus (type 1, the thick profile, under an overcast with precipitation 1: the
absorption of vc-2.31 grows with precipitation, so the layer is dark grey; the sun is put ahead, 28 deg up, inside
the view, and the layer hides it). Overcast: the weather map's coverage channel 1 on every texel
(:func:`overcast_textures`) -- at coverage 1 the map's own coverage is the raw noise, which leaves gaps and bright
breaks, not the uniform layer of these genera. The height gradients are the renderer's (clamped to [0, 1], figs vc-2.15 / vc-4.9): read as printed
(advanced={'gradient_clamp': 0}, as tutorials/vc/fig_2_02_cloud_types.py shows them) the cumulus profile does not
fall to 0 below the layer top, and the heaps become flat-sided towers up to 4 km whose walls, seen edge-on, are
speckled -- no photograph of a cumulus looks like that. The weather map's type spread is 0. Camera 0.3 km up looking 18 deg up, 55 deg field of view; sun 30 deg high at
azimuth 120 deg; seed 0; 480 x 270. The other genera are high or middle clouds, outside the vc layer
(pywarp/data/figure_status.json). Outputs: figures/oc/fig-2.6.png, figures/oc/fig-2.7.png, figures/oc/fig-2.8.png,
figures/oc/fig-2.9.png.
"""
# %% [markdown]
# The low genera differ in how much of the sky they cover and in their vertical profile: stratus is a thin uniform
# sheet, stratocumulus a lumpy layer of rolls and patches, cumulus separate heaps with flat bases, nimbostratus a
# thick dark layer that hides the sun. The vc renderer's weather map carries exactly these degrees of freedom --
# coverage, cloud type and precipitation -- so each genus is one setting of it.

# %%
from __future__ import annotations

from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

from pywarp.clouds import textures as T  # noqa: E402
from pywarp.clouds.cloudscape import CloudscapeSettings  # noqa: E402
from pywarp.clouds.technique import CloudscapeTechnique  # noqa: E402
from pywarp.tutorial import fit_text, one_type_textures  # noqa: E402

#: (file, title, cloudscape settings, overcast): an overcast genus has the weather map's coverage channel set to 1 on
#: every texel (:func:`overcast_textures`) -- a sheet without gaps; the others keep the map's noise.
GENERA = (("fig-2.6.png", "nimbostratus: overcast, type 1, precipitation 1, the sun (ahead) hidden",
           dict(cloud_type=1.0, coverage=1.0, precipitation=1.0, sun_azimuth_deg=0.0, sun_elevation_deg=28.0),
           True),
          ("fig-2.7.png", "stratocumulus (type 0.5, coverage 0.7)", dict(cloud_type=0.5, coverage=0.7), False),
          ("fig-2.8.png", "stratus: overcast, type 0, precipitation 0.5",
           dict(cloud_type=0.0, coverage=1.0, precipitation=0.5), True),
          ("fig-2.9.png", "cumulus (type 1, coverage 0.3)", dict(cloud_type=1.0, coverage=0.3), False))
SCENE = dict(precipitation=0.2, seed=0, sun_elevation_deg=30.0, sun_azimuth_deg=120.0, camera_altitude_km=0.3,
             camera_pitch_deg=18.0, fov_y_deg=55.0)
FULL = dict(width=480, height=270)
QUICK = dict(width=96, height=54, base_size=32, detail_size=16, curl_size=32, weather_size=64)


def overcast_textures(settings, generator):
    """:func:`pywarp.tutorial.one_type_textures` with the weather map's coverage (R) 1 on every texel: at coverage 1
    the map's R is the raw coverage noise (shape(n, 1) = n, ``cclouds/texgen.h``), which leaves thin patches and gaps
    -- broken cloud, not the uniform sheet of a stratus or nimbostratus. With R = 1 the base-shape noise passes
    unthresholded everywhere and the cloud type's height gradient alone shapes the layer: a flat base, no gaps."""
    import dataclasses

    from pywarp.clouds.cloudscape import RenderTextures

    s = settings
    tex = generator.textures(
        T.BaseShapeSettings(size=s.base_size, seed=s.seed), T.DetailShapeSettings(size=s.detail_size, seed=s.seed),
        T.CurlNoiseSettings(size=s.curl_size, seed=s.seed),
        T.WeatherMapSettings(size=s.weather_size, seed=s.seed, coverage=s.coverage, precipitation=s.precipitation,
                             cloud_type=s.cloud_type, cloud_type_variation=0.0))
    weather = tex.weather_map.copy()
    weather[..., 0] = 1.0
    return RenderTextures.from_textures(dataclasses.replace(tex, weather_map=weather), s.device)


def main(out_dir, quick: bool = False) -> list[Path]:
    out_dir = Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    gen = T.BasicTextureGenerator()
    written = []
    for name, title, genus, overcast in GENERA:
        s = CloudscapeSettings(**(QUICK if quick else FULL), **{**SCENE, **genus})
        textures = (overcast_textures if overcast else one_type_textures)(s, gen)
        img = CloudscapeTechnique(s, textures=textures).render()
        h, w = img.shape[:2]
        fig = plt.figure(figsize=(w / 100, h / 100 + 0.35), dpi=100)
        ax = fig.add_axes([0, 0, 1, h / (h + 35)])
        ax.imshow(img)
        ax.axis("off")
        fig.text(0.5, 1 - 17 / (h + 35), f"stand-in: {title}", ha="center", va="center", fontsize=8)
        fit_text(fig)  # a title wider than a small (quick) image: smaller, wrapped, its band taller
        path = out_dir / name
        fig.savefig(path, dpi=100)
        plt.close(fig)
        written.append(path)
    return written


if __name__ == "__main__":
    from pywarp.tutorial import run_as_script

    run_as_script(main, __doc__, "figures/oc")
