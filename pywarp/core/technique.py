"""The technique every scene renders with (vc-A33's design: init / update / render, plus resize), its common part.

A scene's technique subclasses :class:`Technique` and says what each invalidation rebuilds; the base keeps the
settings, the device and the order of the steps::

    class TerrainTechnique(Technique):
        settings_class = TerrainSettings

        def rebuild(self, stale, changed):       # what stale / changed settings make out of date
            self.params = ...
        def allocate(self, width, height):       # the frame buffers
            ...
        def render(self, pose=None, progress=None): ...

* ``Technique(settings)``: the settings (default: ``settings_class()``), the device (:meth:`use_device`), then
  :meth:`init`: :meth:`rebuild` of every invalidation its fields declare (:func:`invalidations`) and :meth:`resize`
  to the settings' size.
* ``update(**changes)``: the new settings; what the change invalidates comes from the settings' parameter specs
  (``param(..., invalidates="sky" | "textures" | "size" | "device")``, :meth:`pywarp.core.params.Settings.
  invalidated`): "device" switches the device first, :meth:`rebuild` gets the invalidations and the changed field
  names, "size" or "device" reallocate the frame buffers.
* ``resize(width, height)``: the settings' size and :meth:`allocate`.

``render(pose=None, progress=None)`` is the scene's own (:mod:`pywarp.core.scenes` says what it returns).
"""
from __future__ import annotations

import dataclasses
from dataclasses import replace

from .params import specs
from .runtime import launcher as shared_launcher


def invalidations(settings_class) -> frozenset:
    """Every invalidation the fields of a settings class declare (their specs' ``invalidates``, less "nothing"):
    what :meth:`Technique.init` rebuilds."""
    return frozenset(p.invalidates for p in specs(settings_class)) - {"nothing"}


class Technique:
    """The base of a scene's technique (see the module docstring). ``settings``, ``launcher`` (the tile-parallel
    launcher of the settings' device and threads), ``device``, ``frame`` (frames rendered)."""

    #: the scene's settings class (its default instance is the default settings)
    settings_class: type = None
    #: True: the viewer renders this scene's previews at the window's size with the controls' preview changes (the
    #: scene reconstructs what it must itself: rain's background); False: through pywarp.core.temporal
    previews_at_full_size: bool = False
    #: what the viewer shows while the view moves unless told (``pywarp view --previews``): "scaled" (the frame at a
    #: reduced size, enlarged) or "temporal" (the window's size through :mod:`pywarp.core.temporal`, 1/f^2 of the
    #: pixels rendered per frame); a scene whose reconstruction measures closer to the full render at the viewer's
    #: frame rate says "temporal" (the terrain, with its exact depth)
    preview_mode: str = "scaled"

    def __init__(self, settings=None):
        self.settings = settings if settings is not None else self.settings_class()
        self.frame = 0
        self.use_device()
        self.init()

    def use_device(self) -> None:
        """The launcher and device of the settings' ``device`` and ``threads`` (at construction and when a change
        invalidates "device")."""
        self.launcher = shared_launcher(self.settings.device, self.settings.threads)
        self.device = self.launcher.device

    def init(self) -> None:
        """Everything the first frame needs: :meth:`rebuild` of every invalidation and field, then the buffers."""
        self.rebuild(invalidations(type(self.settings)), {f.name for f in dataclasses.fields(self.settings)})
        self.resize(self.settings.width, self.settings.height)

    def rebuild(self, stale: set, changed: set) -> None:
        """Rebuild what the settings change made out of date: ``stale`` the invalidations (``"sky"``,
        ``"textures"``, ``"size"``, ``"device"``; every one at :meth:`init`), ``changed`` the names of the changed
        fields (every field at :meth:`init`). The new settings are ``self.settings``. Override."""

    def update(self, **changes) -> None:
        """Change settings (see the module docstring): only what the change invalidates is rebuilt."""
        old = self.settings
        new = replace(old, **changes)
        stale = self.invalidated(new, old)
        self.settings = new
        if "device" in stale:
            self.use_device()
        self.rebuild(stale, new.changed(old))
        if stale & {"size", "device"}:
            self.resize(new.width, new.height)

    def invalidated(self, new, old) -> set:
        """What a change from ``old`` to ``new`` settings invalidates: the specs' ``invalidates`` (override to add
        what a combination of fields means to this technique)."""
        return new.invalidated(old)

    def resize(self, width: int, height: int) -> None:
        """A new frame size: the settings' width and height, then :meth:`allocate`."""
        if (width, height) != (self.settings.width, self.settings.height):
            self.settings = replace(self.settings, width=width, height=height)
        self.allocate(width, height)

    def allocate(self, width: int, height: int) -> None:
        """The frame buffers of a width x height frame on ``self.device`` (override; default none)."""

    # --- what the viewer's temporal reconstruction asks of a scene (pywarp.core.temporal) -------------------------------
    def pose(self, pose=None):
        """The pose a ``render(pose)`` uses: ``pose``, or the settings' own (:meth:`Pose.from_settings`) where None.
        A scene whose camera is not a yaw and a pitch (the flight's chase camera) overrides it, and gives its
        camera as ``camera(pose)`` (:func:`pywarp.viewer.session.technique_camera`)."""
        from .pose import Pose

        return pose if pose is not None else Pose.from_settings(self.settings)

    def state(self):
        """What a frame depends on beyond the settings and the pose -- a simulation's state (rain's particles) -- as
        an opaque value for :meth:`restore`; None for a scene without one (the default). The viewer benchmark keeps
        it with each sampled frame, so the full render it compares with shows the same particles."""
        return None

    def restore(self, state) -> None:
        """Take a :meth:`state` of a technique of the same scene (the default: nothing to take)."""

    @staticmethod
    def jitter(pose, jitter_px: tuple):
        """``pose`` moved by a sub-pixel offset of the image (``jitter_px`` pixels; every pose class has the
        field)."""
        return replace(pose, jitter_px=(float(jitter_px[0]), float(jitter_px[1])))
