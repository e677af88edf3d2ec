"""The terrain scene (pt, chapters 6-9): the ray-marched fBm landscape of the procedural-texture demo.

``pywarp.terrain.settings.TerrainSettings`` (every parameter with its reason), ``pywarp.terrain.technique``
(``TerrainTechnique``: init / update / render / resize; ``render_image``; the C reference ``render_pixels_c``; the
camera path ``walk_path``), ``pywarp.terrain.evaluators`` (the NumPy-level heights and water normals, the evaluators
of ``terrain_shade`` / ``terrain_pixel``), ``pywarp.terrain.bench`` (Tabulka 7.1, 8.1, the bisection, supersampling,
the viewer preview). ``pywarp render|animate|bench terrain`` are built from ``pywarp.terrain.scene``.
"""
