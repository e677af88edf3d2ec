"""The viewer's window: Dear ImGui through ``imgui-bundle`` (hello_imgui on GLFW + OpenGL), the vc demo's own stack
in kind (SDL + ImGui there). Left: the panel generated from the scene's parameter specs
(:mod:`pywarp.viewer.panel`), the frame time and frames/s; right: the scene's image as an OpenGL texture
(``immvision.GlTexture``), shown 1:1 at the settings' size (scaled down to fit a smaller window; previews are
stretched to the same size). F1 shows the help overlay with the viewer's and the scene's key bindings.

The window only reads input, draws and picks up finished frames; :class:`pywarp.viewer.session.Session` holds the
state and renders on its own thread.
"""
from __future__ import annotations

import sys
import time

import numpy as np

from .controls import Binding, Input
from .panel import draw as draw_panel
from .session import Benchmark, Session

#: the panel's width (px)
PANEL_WIDTH = 470
#: the UI's frame-rate cap (frames/s): input, drawing and picking up frames; rendering runs on its own thread
UI_FPS_MAX = 60.0
#: while the render thread works, a UI frame waits up to this long (s) for its next frame: the UI then runs at the
#: rendering's pace (every UI frame costs CPU taken from the renderer: under Xvfb's software OpenGL, llvmpipe, ~13 ms a
#: frame at 640 x 360: the clear, the swap and ImGui ~5.5, the panel ~4, the image ~2.5; tools/window_cost.py)
UI_WAIT_S = 1.0 / 15.0
#: UI frames per second when nothing changes (hello_imgui's idling)
UI_FPS_IDLE = 10.0
#: the viewer's own bindings (help overlay)
VIEWER_BINDINGS = (Binding("Esc", "quit"), Binding("F1", "this help"), Binding("F12", "save a screenshot (PNG)"),
                   Binding("F5", "play / pause time (scenes with a time field)"))


def key_table(imgui) -> dict:
    """Key name (:mod:`pywarp.viewer.controls` docstring) -> ImGui keys."""
    K = imgui.Key
    t = {chr(c): [getattr(K, chr(c).lower())] for c in range(ord("A"), ord("Z") + 1)}
    for d in range(10):
        t[str(d)] = [getattr(K, f"_{d}"), getattr(K, f"keypad{d}")]
    t.update({"Up": [K.up_arrow], "Down": [K.down_arrow], "Left": [K.left_arrow], "Right": [K.right_arrow],
              "Space": [K.space], "Shift": [K.left_shift, K.right_shift], "Ctrl": [K.left_ctrl, K.right_ctrl],
              "Alt": [K.left_alt, K.right_alt], "Enter": [K.enter, K.keypad_enter], "Tab": [K.tab],
              "Backspace": [K.backspace], "PageUp": [K.page_up], "PageDown": [K.page_down], "Home": [K.home],
              "End": [K.end], "+": [K.equal, K.keypad_add], "-": [K.minus, K.keypad_subtract],
              "Escape": [K.escape]})
    for n in range(1, 13):
        t[f"F{n}"] = [getattr(K, f"f{n}")]
    return t


_GL = []  # [libGL through ctypes, or None where it cannot be loaded]


def _tex_sub_image(texture_id: int, img) -> bool:
    """Replace the pixels of the RGB texture ``texture_id`` (of ``img``'s size) with ``img`` (H x W x 3 uint8,
    C-contiguous) by ``glTexSubImage2D``; False where libGL cannot be called (then the caller re-creates the storage
    with ``GlTexture.update_from_image``, which costs about twice the CPU under llvmpipe: 1.6 against 0.8 ms at 640 x
    360)."""
    import ctypes
    import ctypes.util

    if not _GL:
        name = ctypes.util.find_library("GL") if sys.platform.startswith("linux") else None
        try:
            _GL.append(ctypes.CDLL(name) if name else None)
        except OSError:
            _GL.append(None)
    gl = _GL[0]
    if gl is None or img.ndim != 3 or img.shape[2] != 3 or img.dtype != np.uint8 or not img.flags.c_contiguous:
        return False
    texture_2d, rgb, unsigned_byte = 0x0DE1, 0x1907, 0x1401
    # rows packed tightly (alignment 1, no row length or skips), the unpack state restored after
    store = {0x0CF5: 1, 0x0CF2: 0, 0x0CF3: 0, 0x0CF4: 0}  # UNPACK_ALIGNMENT, _ROW_LENGTH, _SKIP_ROWS, _SKIP_PIXELS
    saved = {}
    for k in store:
        v = ctypes.c_int(0)
        gl.glGetIntegerv(k, ctypes.byref(v))
        saved[k] = v.value
    for k, v in store.items():
        gl.glPixelStorei(k, v)
    gl.glBindTexture(texture_2d, int(texture_id))
    gl.glTexSubImage2D(texture_2d, 0, 0, 0, img.shape[1], img.shape[0], rgb, unsigned_byte,
                       img.ctypes.data_as(ctypes.c_void_p))
    gl.glBindTexture(texture_2d, 0)
    for k, v in saved.items():
        gl.glPixelStorei(k, v)
    return True


class Window:
    """One viewer window on a session. ``run()`` returns when the user quits (Esc, closing the window), the script
    ends, or the benchmark is done."""

    def __init__(self, session: Session, *, benchmark: Benchmark | None = None, title: str | None = None,
                 window_screenshot=None, quit_after_script: bool = True, seconds: float | None = None):
        self.session = session
        self.benchmark = benchmark
        self.title = title or f"pywarp view {session.scene.name}"
        self.window_screenshot = window_screenshot
        self.quit_after_script = quit_after_script
        self.seconds = seconds
        self.t0 = None
        self.texture = None
        self.texture_shape = None
        self.panel_state: dict = {}
        self.last = None
        self.image_rect = None
        self.dragging = False
        self._keys = None
        self.result = None

    # --- input -----------------------------------------------------------------------------------------------------
    def _input(self, imgui, dt: float, image_hovered: bool) -> Input:
        io = imgui.get_io()
        if self._keys is None:
            self._keys = key_table(imgui)
        held, pressed = set(), set()
        if not io.want_text_input:
            for name, keys in self._keys.items():
                if any(imgui.is_key_down(k) for k in keys):
                    held.add(name)
                if any(imgui.is_key_pressed(k, False) for k in keys):
                    pressed.add(name)
        mouse = (0.0, 0.0)
        if imgui.is_mouse_clicked(0) and image_hovered:
            self.dragging = True
        if not imgui.is_mouse_down(0):
            self.dragging = False
        if self.dragging:
            mouse = (float(io.mouse_delta.x), float(io.mouse_delta.y))
        wheel = float(io.mouse_wheel) if image_hovered else 0.0
        return Input(dt=dt, held=frozenset(held), pressed=frozenset(pressed), mouse=mouse, wheel=wheel)

    # --- drawing ---------------------------------------------------------------------------------------------------
    def _upload(self, frame) -> None:
        from imgui_bundle import immvision

        img = frame.image
        if self.texture is None or self.texture_shape != img.shape:
            self.texture = immvision.GlTexture(img)
            self.texture_shape = img.shape
        elif not _tex_sub_image(self.texture.texture_id, img):
            self.texture.update_from_image(img)

    def _stats(self, imgui) -> None:
        s = self.session
        now = time.perf_counter()
        f = s.frame
        imgui.text(f"scene {s.scene.name}   {s.worker.status}")
        if f is not None:
            h, w = f.image.shape[:2]
            if f.full:
                kind = "refined"
            elif f.fresh != (w, h):  # the temporal reconstruction: the window's size, a fraction of it rendered
                kind = f"preview, 1/{round(w * h / max(1, f.fresh[0] * f.fresh[1]))} of the pixels rendered"
            else:
                kind = f"preview 1/{s.worker.scale:g}"
            imgui.text(f"frame {f.render_s * 1e3:7.1f} ms  {w}x{h} {kind}")
        imgui.text(f"scene {s.stats.fps(now):5.1f} frames/s   UI {imgui.get_io().framerate:5.1f} frames/s")
        if s.scene.time_field:
            c, s.time_playing = imgui.checkbox("play time (F5)", s.time_playing)
            imgui.same_line()
            imgui.set_next_item_width(120)
            _, s.time_scale = imgui.drag_float("x##timescale", s.time_scale, 1.0, 0.0, 1e4, "%.0f")
            if imgui.is_item_hovered():
                imgui.set_tooltip("simulated seconds per second while time plays")
        msg = s.error or s.worker.error or s.message
        if msg:
            imgui.text_wrapped(msg)
        imgui.text_disabled("F1 help   F12 screenshot   Esc quit")

    def _help(self, imgui) -> None:
        s = self.session
        if not s.show_help:
            return
        x, y, w, h = self.image_rect or (PANEL_WIDTH, 0, 640, 360)
        imgui.set_next_window_pos(imgui.ImVec2(x + 10, y + 10))
        imgui.set_next_window_bg_alpha(0.8)
        flags = (imgui.WindowFlags_.no_decoration.value | imgui.WindowFlags_.always_auto_resize.value
                 | imgui.WindowFlags_.no_saved_settings.value | imgui.WindowFlags_.no_focus_on_appearing.value
                 | imgui.WindowFlags_.no_nav.value)
        imgui.begin("help##overlay", None, flags)
        imgui.text(f"{s.scene.name}: {s.scene.description}")
        imgui.separator()
        for b in tuple(s.controls.bindings) + VIEWER_BINDINGS:
            imgui.text(f"{b.keys:<22}")
            imgui.same_line(190)
            imgui.text(b.help)
        imgui.separator()
        imgui.text_disabled("hover a panel setting for its unit, range, default and reason")
        imgui.end()

    def gui(self) -> None:
        from imgui_bundle import hello_imgui, imgui

        s = self.session
        if self.t0 is None:
            self._background()  # the theme is applied by now
        s.wait_frame(UI_WAIT_S)
        now = time.perf_counter()
        dt = 0.0 if self.last is None else now - self.last
        self.last = now
        vp = imgui.get_main_viewport()
        imgui.set_next_window_pos(vp.work_pos)
        imgui.set_next_window_size(vp.work_size)
        # no background quad over the whole window: the clear colour is its colour (:meth:`_background`); under a
        # software OpenGL (llvmpipe) the blended full-window quad cost ~6 of the window's ~19 ms of CPU a UI frame
        flags = (imgui.WindowFlags_.no_decoration.value | imgui.WindowFlags_.no_move.value
                 | imgui.WindowFlags_.no_saved_settings.value | imgui.WindowFlags_.no_bring_to_front_on_focus.value
                 | imgui.WindowFlags_.no_background.value)
        imgui.begin("pywarp view", None, flags)
        style = imgui.get_style()
        if style.window_border_size > 0:  # the window's frame, which the background pass drew (a few thin quads)
            p0, size = imgui.get_window_pos(), imgui.get_window_size()
            imgui.get_background_draw_list().add_rect(p0, imgui.ImVec2(p0.x + size.x, p0.y + size.y),
                                                      imgui.get_color_u32(imgui.Col_.border.value),
                                                      style.window_rounding, style.window_border_size)
        imgui.begin_child("panel", imgui.ImVec2(PANEL_WIDTH, 0), imgui.ChildFlags_.borders.value)
        self._stats(imgui)
        imgui.separator()
        imgui.push_item_width(-210)  # room for the labels (name [unit]) right of the widgets
        changes = draw_panel(imgui, s.settings, self.panel_state, exclude=s.exclude)
        imgui.pop_item_width()
        imgui.end_child()
        imgui.same_line()
        imgui.begin_child("image", imgui.ImVec2(0, 0), 0,
                          imgui.WindowFlags_.no_scrollbar.value | imgui.WindowFlags_.no_scroll_with_mouse.value)
        hovered = False
        frame = s.poll(now)
        if frame is not None:
            self._upload(frame)
        if self.texture is not None:
            avail = imgui.get_content_region_avail()
            st = s.settings
            w = getattr(st, "width", self.texture_shape[1])
            h = getattr(st, "height", self.texture_shape[0])
            k = min(1.0, avail.x / w, avail.y / h) if avail.x > 0 and avail.y > 0 else 1.0
            pos = imgui.get_cursor_screen_pos()
            imgui.image(imgui.ImTextureRef(self.texture.texture_id), imgui.ImVec2(int(w * k), int(h * k)))
            hovered = imgui.is_item_hovered()
            self.image_rect = (pos.x, pos.y, w * k, h * k)
        else:
            imgui.text(s.worker.status + " ...")
        imgui.end_child()
        imgui.end()
        self._help(imgui)
        inp = self._input(imgui, dt, hovered)
        if self.benchmark is not None:
            inp = Input(dt=dt, held=inp.held | self.benchmark.input(dt).held, pressed=inp.pressed)
        if changes:
            s.apply(changes)
        s.tick(inp)
        if self.benchmark is not None:
            self.benchmark.update(now)
            if self.benchmark.done:
                self.result = self.benchmark.result(window=True)
                s.quit = True
        if s.worker.error and s.script is not None:
            s.quit = True
        if self.quit_after_script and s.finished_script():
            s.quit = True
        if self.t0 is None:
            self.t0 = now
        if self.seconds is not None and now - self.t0 >= self.seconds:
            s.quit = True
        if s.quit:
            hello_imgui.get_runner_params().app_shall_exit = True
        elif s.worker.busy() or inp.held or inp.pressed or self.dragging or s.script is not None \
                or self.benchmark is not None or s.time_playing:
            hello_imgui.request_refresh()  # no idling while anything happens

    @staticmethod
    def _background() -> None:
        """The window's clear colour: the theme's window background as it looked blended over the (black) clear
        colour when the main ImGui window drew it, so the window looks as before without drawing it."""
        from imgui_bundle import hello_imgui, imgui

        c = imgui.get_style().color_(imgui.Col_.window_bg.value)
        hello_imgui.get_runner_params().imgui_window_params.background_color = \
            imgui.ImVec4(c.x * c.w, c.y * c.w, c.z * c.w, 1.0)

    def _release(self) -> None:
        # the texture is deleted while its OpenGL context exists (deleting it later would crash)
        self.texture = None
        self.texture_shape = None

    def run(self) -> None:
        from imgui_bundle import hello_imgui, immapp

        st = self.session.settings
        w = getattr(st, "width", 640)
        h = getattr(st, "height", 360)
        params = hello_imgui.RunnerParams()
        params.app_window_params.window_title = self.title
        params.app_window_params.window_geometry.size = (PANEL_WIDTH + min(w, 1600) + 24,
                                                         max(min(h, 1000) + 20, 420))
        params.imgui_window_params.default_imgui_window_type = \
            hello_imgui.DefaultImGuiWindowType.no_default_window
        params.fps_idling.enable_idling = True
        params.fps_idling.fps_idle = UI_FPS_IDLE
        params.fps_idling.vsync_to_monitor = False
        params.fps_idling.fps_max = UI_FPS_MAX
        params.ini_disable = True
        params.callbacks.show_gui = self.gui
        params.callbacks.before_exit = self._release
        try:
            immapp.run(params)
        except RuntimeError as exc:
            if "glfwInit" not in str(exc):
                raise
            import os

            raise ValueError(f"cannot open a window on display {os.environ.get('DISPLAY', '')!r} (GLFW could not "
                             f"start): run it under `xvfb-run -a`, or use --no-window") from None
        if self.window_screenshot is not None:
            from ..core.output import write_png

            shot = hello_imgui.final_app_window_screenshot()
            write_png(self.window_screenshot, shot[..., :3].copy())
