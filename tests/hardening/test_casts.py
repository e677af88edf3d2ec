"""Issue 31, the cast-before-clamp audit: every float -> integer conversion in cclouds/src and pywarp/kernels is bounded
before the cast, by construction or by a documented, checked domain (a float outside the integer's range, +-Inf or
NaN converted to an integer is undefined behaviour in C and in Warp's generated C++; findings N3 and N4 were two of
this family). Each site is listed here with the reason it is bounded; a new site fails the test until it is bounded
and listed.

C: the conversions are found by clang itself (-ast-dump=json, cast kind FloatingToIntegral: explicit casts and
implicit conversions alike). Warp: int(), wp.int32() and the like inside @wp.func / @wp.kernel functions whose
argument is a float by a small local inference (float parameters, float literals, wp.floor / wp.ceil and other float
functions, names assigned from those); a conversion of an integer is no float conversion. A site is keyed by its
file, function and the conversion's source text (not its line, which moves with unrelated edits)."""
from __future__ import annotations

import ast
import json
import shutil
import subprocess
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]

_CLAMPED = "clamped (NaN included) to a small range before the cast"
_FLOOR_INT = "floor_to_int: clamped to +-2^30 first, NaN mapped to the low end"
_BOUND_CELL = "bound_cell: the coordinate bounded to [-1, n] first (N3, N4), NaN returned before"
_TEXEL_DOMAIN = ("texture coordinate within |p size| < 2^23, checked by the sampler first (NaN outside); the "
                 "cloudscape check bounds every coordinate it produces below 2^23 texels")
_UNIT_UV = "a texture coordinate in [0, 1) (checked just before, or the loop's own pixel centres): index <= size"
_UV_VALID = ("a reprojected uv in [0, 1]^2 (the caller's valid flag) or the reduced buffer's clamped coordinate, "
             "plus the +-neighbourhood offsets: within the image +- a few pixels")
_RATIO_GUARD = "converted only where the ratio is below an int bound (the comparison is false for NaN and inf)"
_LOD = "lod in (0, levels - 1) here (NaN, <= 0 and >= levels - 1 return before)"
_LIGHT_STEPS = "grid diagonal (<= 1024 sqrt 3 voxels) / light_step_voxels (>= 0.05, checked): < 4e4"
_BRICK = "a sample position inside the grid box along [t_start, t_end] (the ray-box segment): within the grid"
_GROUND_NOISE = "floor of a coordinate clamped to +-2^23 first (fminf / fmaxf, wp.min / wp.max map NaN to the bound)"
_AXIS_MAP = "i (nc - 1) / (nf - 1) for 0 <= i < nf: in [0, nc - 1]"
_TO_U8 = "rounded value clamped to [0, 255] first, NaN mapped to 0"
_VALUENOISE = ("x, y, z in [0, CCL_VALUENOISE_MAX_COORD] (2^24) by the documented domain, refused outside it by the "
               "registry; NaN returned before")
_SPRITE = "a sprite's edge clamped to its tile +- 2 pixels first (binned sprites are not NaN: bin_sprites drops them)"
_ENCODE = "a finite channel (a non-finite one is counted and replaced by 0 first) clamped to [0, 1], then sRGB"
_PIXEL_U8 = ("clamped to [0, 1]; the pixel is finite on the checked domain (findings 5, 9, 11; fuzz_volume asserts "
             "a finite ccl_volume_pixel)")

#: (file, function, conversion text) -> why the value is within the integer's range before the cast
C_SITES = {
    ("cloudscape.c", "axis2", "(int32_t)fx"): _TEXEL_DOMAIN,
    ("cloudscape.c", "ground_noise", "(int32_t)fx"): _GROUND_NOISE,
    ("cloudscape.c", "ground_noise", "(int32_t)fz"): _GROUND_NOISE,
    ("cloudscape.c", "sample_mip", "(int)floorf(lod)"): _LOD,
    ("cloudscape.c", "ccl_cloudscape_march", "(int)need"): _RATIO_GUARD,
    ("cloudscape.c", "ccl_cloudscape_march", "(int)kf"): _RATIO_GUARD,
    ("cloudscape.c", "ccl_cloudscape_march", "(int)gf"): _RATIO_GUARD,
    ("noise.c", "floor_to_int", "(int32_t)f"): _FLOOR_INT,
    ("particles.c", "fetch", "(int)x0f"): _BOUND_CELL,
    ("particles.c", "fetch", "(int)y0f"): _BOUND_CELL,
    ("particles.c", "fetch", "(int)floorf(bound_cell(u * (float)size, size))"): _BOUND_CELL,
    ("particles.c", "fetch", "(int)floorf(bound_cell(v * (float)size, size))"): _BOUND_CELL,
    ("particles.c", "ccl_particles_tap", "(int)(mask_u * (float)mask_size)"): _UNIT_UV,
    ("particles.c", "ccl_particles_tap", "(int)(mask_v * (float)mask_size)"): _UNIT_UV,
    ("particles.c", "shade", "(int)(mu * (float)mask_size)"): _UNIT_UV,
    ("particles.c", "shade", "(int)(tv * (float)mask_size)"): _UNIT_UV,
    ("rain.c", "floor_clamped", "(int)floorf(x)"): _CLAMPED,
    ("rain.c", "ccl_rain_sample_capture", "(int)floorf(x)"): _CLAMPED,
    ("rain.c", "ccl_rain_sample_capture", "(int)floorf(y)"): _CLAMPED,
    ("rain.c", "ccl_rain_shade_drop", "(int)floorf((1.0f - v) * 0.5f * (float)mask_size)"): _UNIT_UV,
    ("rain.c", "ccl_rain_shade_drop", "(int)floorf((u + 1.0f) * 0.5f * (float)mask_size)"): _UNIT_UV,
    ("raymarch.c", "ccl_raymarch_view_sample_count", "(int)n"): _CLAMPED,
    ("reproj.c", "nearest_index", "(int)f"): _CLAMPED,
    ("reproj.c", "bilinear", "(int)x0f"): _UV_VALID,
    ("reproj.c", "bilinear", "(int)y0f"): _UV_VALID,
    ("reproj.c", "catmull_rom_add", "(int)x0f"): _UV_VALID,
    ("reproj.c", "catmull_rom_add", "(int)y0f"): _UV_VALID,
    ("reproj.c", "fallback_depth", "(int)x0f"): _UV_VALID,
    ("reproj.c", "fallback_depth", "(int)y0f"): _UV_VALID,
    ("texgen.c", "axis", "(int32_t)fx"): _TEXEL_DOMAIN,
    ("valuenoise.c", "ccl_valuenoise_interpolated", "(int32_t)flx"): _VALUENOISE,
    ("valuenoise.c", "ccl_valuenoise_interpolated", "(int32_t)fly"): _VALUENOISE,
    ("valuenoise.c", "ccl_valuenoise_interpolated", "(int32_t)flz"): _VALUENOISE,
    ("volume.c", "tri_setup", "(int)ix"): _BOUND_CELL,
    ("volume.c", "tri_setup", "(int)iy"): _BOUND_CELL,
    ("volume.c", "tri_setup", "(int)iz"): _BOUND_CELL,
    ("volume.c", "ccl_volume_light",
     "(int)ceilf(sqrtf((float)g.nx * (float)g.nx + (float)g.ny * (float)g.ny + (float)g.nz * (float)g.nz) / step)"):
        _LIGHT_STEPS,
    ("volume.c", "ccl_volume_pixel", "(int)steps"): _RATIO_GUARD,
    ("volume.c", "ccl_volume_pixel", "(int)floorf(v.x * (1.0f / (float)CCL_VOLUME_BRICK))"): _BRICK,
    ("volume.c", "ccl_volume_pixel", "(int)floorf(v.y * (1.0f / (float)CCL_VOLUME_BRICK))"): _BRICK,
    ("volume.c", "ccl_volume_pixel", "(int)floorf(v.z * (1.0f / (float)CCL_VOLUME_BRICK))"): _BRICK,
    ("volume.c", "ccl_volume_pixel", "(int)next"): _RATIO_GUARD,
    ("voxel.c", "axis_map", "(int32_t)pos"): _AXIS_MAP,
    ("voxel.c", "to_u8", "(uint8_t)(!(r >= 0.0f) ? 0.0f : (r > 255.0f ? 255.0f : r))"): _TO_U8,
}

WARP_SITES = {
    ('cloudscape.py', '_axis2', 'int(fx)'): _TEXEL_DOMAIN,
    ('cloudscape.py', '_ground_noise', 'int(fx)'): _GROUND_NOISE,
    ('cloudscape.py', '_ground_noise', 'int(fz)'): _GROUND_NOISE,
    ('cloudscape.py', '_empty_texels', 'int(wp.floor(x))'): _TEXEL_DOMAIN,
    ('cloudscape.py', '_empty_texels', 'int(wp.floor(y))'): _TEXEL_DOMAIN,
    ('cloudscape.py', 'cloudscape_march', 'int(gf)'): _RATIO_GUARD,
    ('cloudscape.py', 'cloudscape_march', 'int(kf)'): _RATIO_GUARD,
    ('cloudscape.py', 'cloudscape_march', 'int(need)'): _RATIO_GUARD,
    ('cloudscape.py', 'encode_kernel', 'int(v * 255.0 + 0.5)'): _ENCODE,
    ('cloudscape.py', 'sample_mip', 'int(l0)'): _LOD,
    ('noise.py', '_floor_to_int', 'int(g)'): _FLOOR_INT,
    ('particles.py', '_tap_packed', 'int(mask_u * float(mask_size))'): _UNIT_UV,
    ('particles.py', '_tap_packed', 'int(mask_v * float(mask_size))'): _UNIT_UV,
    ('particles.py', 'composite_tile_kernel', 'int(wp.floor(wp.clamp(sprites[j, 0] + sprites[j, 2], fx0, fx1)))'): _SPRITE,
    ('particles.py', 'composite_tile_kernel', 'int(wp.floor(wp.clamp(sprites[j, 0] - sprites[j, 2], fx0, fx1)))'): _SPRITE,
    ('particles.py', 'composite_tile_kernel', 'int(wp.floor(wp.clamp(sprites[j, 1] + sprites[j, 3], fy0, fy1)))'): _SPRITE,
    ('particles.py', 'composite_tile_kernel', 'int(wp.floor(wp.clamp(sprites[j, 1] - sprites[j, 3], fy0, fy1)))'): _SPRITE,
    ('particles.py', 'particles_fetch', 'int(wp.floor(bound_cell(u * float(size), size)))'): _BOUND_CELL,
    ('particles.py', 'particles_fetch', 'int(wp.floor(bound_cell(v * float(size), size)))'): _BOUND_CELL,
    ('particles.py', 'particles_fetch', 'int(x0f)'): _BOUND_CELL,
    ('particles.py', 'particles_fetch', 'int(y0f)'): _BOUND_CELL,
    ('particles.py', 'particles_tap', 'int(mask_u * float(mask_size))'): _UNIT_UV,
    ('particles.py', 'particles_tap', 'int(mask_v * float(mask_size))'): _UNIT_UV,
    ('rain.py', '_floor_clamped', 'int(wp.floor(xc))'): _CLAMPED,
    ('rain.py', 'rain_sample_capture', 'int(wp.floor(x))'): _CLAMPED,
    ('rain.py', 'rain_sample_capture', 'int(wp.floor(y))'): _CLAMPED,
    ('rain.py', 'rain_shade_pixel', 'int(wp.floor((1.0 - v) * 0.5 * float(ms)))'): _UNIT_UV,
    ('rain.py', 'rain_shade_pixel', 'int(wp.floor((u + 1.0) * 0.5 * float(ms)))'): _UNIT_UV,
    ('raymarch.py', 'raymarch_view_sample_count', 'int(n)'): _CLAMPED,
    ('reproj.py', '_bilinear', 'int(x0f)'): _UV_VALID,
    ('reproj.py', '_bilinear', 'int(y0f)'): _UV_VALID,
    ('reproj.py', '_catmull_rom_add', 'int(x0f)'): _UV_VALID,
    ('reproj.py', '_catmull_rom_add', 'int(y0f)'): _UV_VALID,
    ('reproj.py', '_fallback_depth', 'int(x0f)'): _UV_VALID,
    ('reproj.py', '_fallback_depth', 'int(y0f)'): _UV_VALID,
    ('reproj.py', '_nearest_index', 'int(f)'): _CLAMPED,
    ('texgen.py', '_axis_lo', 'int(fx)'): _TEXEL_DOMAIN,
    ('valuenoise.py', 'valuenoise_interpolated', 'int(flx)'): _VALUENOISE,
    ('valuenoise.py', 'valuenoise_interpolated', 'int(fly)'): _VALUENOISE,
    ('valuenoise.py', 'valuenoise_interpolated', 'int(flz)'): _VALUENOISE,
    ('volume.py', 'volume_light_voxel', 'int(wp.ceil(wp.sqrt(fnx * fnx + fny * fny + fnz * fnz) / step))'): _LIGHT_STEPS,
    ('volume.py', 'render_kernel', 'int(e * 255.0 + 0.5)'): _PIXEL_U8,
    ('volume.py', 'volume_pixel', 'int(ix)'): _BRICK,
    ('volume.py', 'volume_pixel', 'int(iy)'): _BRICK,
    ('volume.py', 'volume_pixel', 'int(iz)'): _BRICK,
    ('volume.py', 'volume_pixel', 'int(nxt)'): _RATIO_GUARD,
    ('volume.py', 'volume_pixel', 'int(steps)'): _RATIO_GUARD,
    ('volume.py', 'volume_pixel', 'int(wp.floor(v[0] * _INV_BRICK))'): _BRICK,
    ('volume.py', 'volume_pixel', 'int(wp.floor(v[1] * _INV_BRICK))'): _BRICK,
    ('volume.py', 'volume_pixel', 'int(wp.floor(v[2] * _INV_BRICK))'): _BRICK,
    ('volume.py', 'volume_sample', 'int(ix)'): _BOUND_CELL,
    ('volume.py', 'volume_sample', 'int(iy)'): _BOUND_CELL,
    ('volume.py', 'volume_sample', 'int(iz)'): _BOUND_CELL,
    ('voxel.py', '_axis_i0', 'int(pos)'): _AXIS_MAP,
    ('voxel.py', '_to_u8', 'int(r)'): _TO_U8,
}


def c_float_to_int_sites() -> set:
    """(file, function, source text) of every FloatingToIntegral cast in cclouds/src/*.c, from clang's AST."""
    clang = shutil.which("clang")
    if clang is None:
        pytest.skip("clang is not installed (the C audit reads clang's AST)")
    sites = set()
    for src in sorted((ROOT / "cclouds" / "src").glob("*.c")):
        res = subprocess.run([clang, "-fsyntax-only", "-std=c99", f"-I{ROOT / 'cclouds' / 'include'}",
                              f"-I{ROOT / 'cclouds' / 'src'}", "-DCCLOUDS_BUILDING", "-Xclang", "-ast-dump=json",
                              str(src)], capture_output=True, text=True)
        assert res.returncode == 0, res.stderr[-2000:]
        text = src.read_bytes()

        def walk(node, fn):
            if node.get("kind") == "FunctionDecl":
                fn = node.get("name")
            if node.get("castKind") == "FloatingToIntegral":
                b, e = node["range"]["begin"], node["range"]["end"]
                b, e = b.get("spellingLoc", b), e.get("spellingLoc", e)
                code = text[b["offset"]:e["offset"] + e.get("tokLen", 0)].decode()
                sites.add((src.name, fn, " ".join(code.split())))
            for child in node.get("inner", ()):
                walk(child, fn)

        walk(json.loads(res.stdout), None)
    return sites


#: functions whose result is a float whatever their arguments (wp.min, wp.max, wp.clamp, wp.abs, wp.where follow
#: their arguments, which the walk visits)
_FLOAT_FUNCS = {"floor", "ceil", "sqrt", "sin", "cos", "tan", "exp", "log", "pow", "round", "trunc", "length", "dot",
                "float", "float32", "bound_cell"}
#: builtins whose result has their arguments' type
_POLY = {"min", "max", "clamp", "abs", "where", "sign"}
_INT_TYPES = {"int", "int8", "int16", "int32", "int64", "uint8", "uint16", "uint32", "uint64"}


def _is_float(expr: ast.AST, floats: set) -> bool:
    """Whether ``expr`` is a float by the local inference: a float literal or name, a float function (wp.floor,
    float(), ...) of anything, arithmetic on a float operand, a subscript of a float array argument."""
    for n in _walk_values(expr):
        if isinstance(n, ast.Constant) and isinstance(n.value, float):
            return True
        if isinstance(n, ast.Name) and n.id in floats:
            return True
        if isinstance(n, ast.Call):
            f = n.func
            name = f.attr if isinstance(f, ast.Attribute) else (f.id if isinstance(f, ast.Name) else "")
            if name in _FLOAT_FUNCS:
                return True
    return False


def _walk_values(expr: ast.AST):
    """ast.walk that descends into the arguments of wp.min / max / clamp / abs / where only (an int() is an int, a
    user function's result has its own type) and into the array of a subscript, not its indices."""
    todo = [expr]
    while todo:
        n = todo.pop()
        yield n
        if isinstance(n, ast.Call):
            f = n.func
            name = f.attr if isinstance(f, ast.Attribute) else (f.id if isinstance(f, ast.Name) else "")
            if name not in _POLY:  # a float function is found at the call itself; other calls: their result type
                continue
            todo.extend(n.args)
            continue
        if isinstance(n, ast.Subscript):
            todo.append(n.value)
            continue
        todo.extend(ast.iter_child_nodes(n))


def _annotation_is_float(ann) -> bool:
    if ann is None:
        return False
    src = ast.unparse(ann)
    return src in ("float", "wp.float32", "wp.float64") or "dtype=float" in src or "dtype=wp.float32" in src


def warp_float_to_int_sites() -> set:
    sites = set()
    for path in sorted((ROOT / "pywarp" / "kernels").glob("*.py")):
        tree = ast.parse(path.read_text())
        for fn in ast.walk(tree):
            if not isinstance(fn, ast.FunctionDef):
                continue
            decos = [ast.unparse(d) for d in fn.decorator_list]
            if not any(d.startswith(("wp.func", "wp.kernel")) for d in decos):
                continue
            floats = {a.arg for a in fn.args.args if _annotation_is_float(a.annotation)}
            for _ in range(3):  # names assigned from float expressions, to a fixed point
                for n in ast.walk(fn):
                    if isinstance(n, (ast.Assign, ast.AnnAssign, ast.AugAssign)):
                        value = n.value
                        targets = n.targets if isinstance(n, ast.Assign) else [n.target]
                        if value is not None and _is_float(value, floats):
                            for t in targets:  # names only (not the indices of a subscript target)
                                for m in (t.elts if isinstance(t, ast.Tuple) else [t]):
                                    if isinstance(m, ast.Name):
                                        floats.add(m.id)
            for n in ast.walk(fn):
                if not (isinstance(n, ast.Call) and n.args):
                    continue
                f = n.func
                name = f.attr if isinstance(f, ast.Attribute) else (f.id if isinstance(f, ast.Name) else "")
                if name in _INT_TYPES and _is_float(n.args[0], floats):
                    sites.add((path.name, fn.name, ast.unparse(n)))
    return sites


def test_every_c_float_to_int_conversion_is_bounded_and_listed():
    found = c_float_to_int_sites()
    new = sorted(found - set(C_SITES))
    assert not new, ("float -> int conversions not in the audit (bound the value before the cast, then list the "
                     f"site with the reason): {new}")
    gone = sorted(set(C_SITES) - found)
    assert not gone, f"listed sites that no longer exist (remove them): {gone}"


def test_every_warp_float_to_int_conversion_is_bounded_and_listed():
    found = warp_float_to_int_sites()
    new = sorted(found - set(WARP_SITES))
    assert not new, ("float -> int conversions in Warp functions not in the audit (bound the value before the "
                     f"conversion, then list the site with the reason): {new}")
    gone = sorted(set(WARP_SITES) - found)
    assert not gone, f"listed sites that no longer exist (remove them): {gone}"


def test_the_warp_inference_tells_float_from_int_arguments():
    """The lint's inference: float parameters, float literals and functions, names assigned from them and the
    polymorphic builtins of floats are floats; int(), integer names and user functions' results are not."""
    def is_float(src, floats=("x",)):
        return _is_float(ast.parse(src).body[0].value, set(floats))

    assert is_float("wp.floor(n * 2)", ()) and is_float("x + 1") and is_float("wp.clamp(x, 0, 3)")
    assert is_float("a[i, 0] - 1.0", ()) and is_float("float(k) * m", ())
    assert not is_float("int(x) + 0") and not is_float("k + 1", ()) and not is_float("wp.max(k, 1)", ())
    assert not is_float("_floor_to_int(x)") and not is_float("a[wp.floor(x)]", ())
