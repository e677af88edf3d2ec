"""The `pywarp` command as a new user meets it: --version, bare `pywarp`, `python -m pywarp`, choices in --help, and
one error format (`pywarp <command>: error: --option ...`, one line, exit status 2, no traceback) for every bad value,
argparse's own errors included."""
from __future__ import annotations

import importlib
import subprocess
import sys

import pytest

import pywarp

cli_main = importlib.import_module("pywarp.cli.main")  # the module (pywarp.cli.main is also the function)


def _cli(*args, cwd):
    # cwd: never the repository root, where `python -m` would import the source folder instead of the package
    return subprocess.run([sys.executable, "-m", "pywarp", *args], capture_output=True, text=True, cwd=cwd,
                          timeout=300)


def _one_error_line(res, prefix):
    assert res.returncode == 2, (res.stdout, res.stderr)
    lines = res.stderr.strip().splitlines()
    assert len(lines) == 1, res.stderr
    assert "Traceback" not in res.stderr and "usage:" not in res.stderr
    assert lines[0].startswith(prefix), lines[0]
    return lines[0]


def test_version_is_the_package_version(tmp_path):
    res = _cli("--version", cwd=tmp_path)
    assert res.returncode == 0
    assert res.stdout.strip() == f"pywarp {pywarp.__version__}"


def test_bare_pywarp_prints_the_help_and_exits_0(tmp_path):
    res = _cli(cwd=tmp_path)
    assert res.returncode == 0 and res.stderr == ""
    assert res.stdout.startswith("usage: pywarp")
    for command in ("equations", "figures", "render", "animate", "bench"):
        assert command in res.stdout
    assert "Exit status" in res.stdout


def test_python_dash_m_is_the_console_script(tmp_path):
    res = _cli("--help", cwd=tmp_path)
    assert res.returncode == 0 and res.stdout.startswith("usage: pywarp")


@pytest.mark.parametrize("args,expected", [
    (["nosuch"], "pywarp: error: COMMAND must be one of equations, figures"),
    (["equations", "--seed", "xx"], "pywarp equations: error: --seed must be one of vc, pt, rr, oc, got 'xx'"),
    (["equations", "--format", "xml"],
     "pywarp equations: error: --format must be one of table, csv, markdown, json, got 'xml'"),
    (["equations", "--width", "wide"], "pywarp equations: error: --width must be an integer >= 0, got 'wide'"),
    (["equations", "--width", "-3"], "pywarp equations: error: --width must be an integer >= 0, got -3"),
    (["equations", "--format"], "pywarp equations: error: --format needs a value"),
    (["equations", "--bogus"], "pywarp equations: error: unknown argument: --bogus"),
    (["equations", "--missing", "--figures"], "pywarp equations: error: --figures cannot be used with --missing"),
    (["figures", "--seed", "zz"], "pywarp figures: error: --seed must be one of vc, pt, rr, oc, got 'zz'"),
    (["render", "--width", "abc"], "pywarp render: error: --width must be an integer, got 'abc'"),
    (["render", "--turbidity", "twelve"], "pywarp render: error: --turbidity must be a number, got 'twelve'"),
    (["render", "--width"], "pywarp render: error: --width needs a value"),
    (["render", "--out", "x.jpg"], "pywarp render: error: --out must end in .png"),
    (["render", "--out", "no-such-folder/x.png"], "pywarp render: error: --out: folder 'no-such-folder' does not"),
    (["animate", "--fps", "fast"], "pywarp animate: error: --fps must be a number, got 'fast'"),
    (["animate", "--out", "a.avi"], "pywarp animate: error: --out must be a video (.mp4 or .gif) or numbered frames "
                                    "such as frames/frame_%04d.png (.png, .exr, .npy), got 'a.avi'"),
    # no abbreviations: a prefix of an option is an unknown argument, named with the option it resembles
    (["render", "--wid", "64"], "pywarp render: error: unknown argument: --wid (did you mean --width?)"),
    (["render", "--widht", "64"], "pywarp render: error: unknown argument: --widht (did you mean --width?)"),
    (["equations", "--sed", "vc"], "pywarp equations: error: unknown argument: --sed vc (did you mean --seed?)"),
    (["equations", "--form", "csv"], "pywarp equations: error: unknown argument: --form csv (did you mean --format?)"),
    (["equations", "--seed", "cv"], "pywarp equations: error: --seed must be one of vc, pt, rr, oc, got 'cv'"),
    (["render", "clods"], "pywarp render: error: scene must be one of 'clouds', 'flight', 'rain', 'terrain', got "
                          "'clods' (did you mean clouds?)"),
    (["render", "--sky", "gradeint"], "pywarp render: error: --sky must be one of 'preetham', 'gradient', got "
                                      "'gradeint' (did you mean gradient?)"),
])
def test_every_bad_value_is_one_line_exit_2(tmp_path, args, expected):
    _one_error_line(_cli(*args, cwd=tmp_path), expected)
    assert list(tmp_path.iterdir()) == []


def test_usage_message_rewrites_argparse_wording():
    um = cli_main.usage_message
    assert um("argument --width: invalid int value: 'x'") == "--width must be an integer, got 'x'"
    assert um("argument --fps: invalid float value: 'x'") == "--fps must be a number, got 'x'"
    assert um("argument --seed: invalid choice: 'q' (choose from 'vc', 'pt')") == "--seed must be one of vc, pt, got 'q'"
    assert (um("argument --format: invalid choice: 'jsn' (choose from 'csv', 'json')")
            == "--format must be one of csv, json, got 'jsn' (did you mean json?)")
    assert um("the following arguments are required: name") == "missing argument: name"
    # a type function's own message already names the option: not repeated
    assert um("argument --width: --width must be >= 1, got 0") == "--width must be >= 1, got 0"
    assert "\n" not in um("argument --x: two\nlines")


def test_errors_raised_by_a_command_are_one_line_with_the_command_name(capsys, monkeypatch):
    def boom(args):
        raise ValueError("--thing must be\nfine, got 3")

    parser = cli_main.build_parser()
    monkeypatch.setattr(cli_main, "build_parser", lambda: parser)
    parser._commands.choices["figures"].set_defaults(run=boom)
    with pytest.raises(SystemExit) as exc:
        cli_main.main(["figures"])
    assert exc.value.code == 2
    assert capsys.readouterr().err == "pywarp figures: error: --thing must be fine, got 3\n"


def test_pywarp_debug_adds_the_traceback_and_keeps_the_exit_status(capsys, monkeypatch):
    def boom(args):
        raise ValueError("--thing must be fine, got 3")

    parser = cli_main.build_parser()
    monkeypatch.setattr(cli_main, "build_parser", lambda: parser)
    monkeypatch.setenv("PYWARP_DEBUG", "1")
    parser._commands.choices["figures"].set_defaults(run=boom)
    with pytest.raises(SystemExit) as exc:
        cli_main.main(["figures"])
    assert exc.value.code == 2
    err = capsys.readouterr().err
    assert "Traceback" in err and "in boom" in err
    assert err.endswith("pywarp figures: error: --thing must be fine, got 3\n")


def test_an_io_error_names_no_temporary_file_and_exits_1(capsys, monkeypatch):
    def boom(args):
        raise OSError(28, "No space left on device", "/x/.c.1234abcd.png.part")

    parser = cli_main.build_parser()
    monkeypatch.setattr(cli_main, "build_parser", lambda: parser)
    parser._commands.choices["figures"].set_defaults(run=boom)
    with pytest.raises(SystemExit) as exc:
        cli_main.main(["figures"])
    assert exc.value.code == 1
    err = capsys.readouterr().err
    assert err.startswith("pywarp figures: error: No space left on device") and err.count("\n") == 1


def test_help_shows_choices_never_str(tmp_path):
    for command in ("equations", "figures", "render", "animate"):
        res = _cli(command, "--help", cwd=tmp_path)
        assert res.returncode == 0, res.stderr
        assert " STR" not in res.stdout, (command, res.stdout)
    res = _cli("equations", "--help", cwd=tmp_path)
    assert "{table,csv,markdown,json}" in res.stdout and "{vc,pt,rr,oc}" in res.stdout


def test_figures_out_checked_before_any_work(tmp_path):
    blocker = tmp_path / "file"
    blocker.write_text("x")
    res = _cli("figures", "--out", str(blocker), "--only", "fig-2.14", cwd=tmp_path)
    _one_error_line(res, f"pywarp figures: error: --out: '{blocker}' is not a folder")
    res = _cli("figures", "--out", str(blocker / "sub"), "--only", "fig-2.14", cwd=tmp_path)
    _one_error_line(res, "pywarp figures: error: --out: cannot create folder")
    assert sorted(p.name for p in tmp_path.iterdir()) == ["file"]


def test_broken_pipe_is_quiet(tmp_path):
    p = subprocess.Popen([sys.executable, "-m", "pywarp", "equations"], stdout=subprocess.PIPE,
                         stderr=subprocess.PIPE, cwd=tmp_path)
    p.stdout.readline()
    p.stdout.close()  # the reader leaves, like `| head -1`
    err = p.stderr.read().decode()
    assert p.wait(timeout=300) == 0
    assert "Traceback" not in err and "BrokenPipe" not in err


def _scene_help(command, scene, tmp_path):
    res = _cli(command, *([scene] if scene else []), "--help", cwd=tmp_path)
    assert res.returncode == 0 and res.stderr == "", res.stderr
    return res.stdout


@pytest.mark.parametrize("command", ["render", "animate", "view"])
def test_scene_help_lists_that_scenes_options_and_defaults(tmp_path, command):
    """`pywarp <command> <scene> --help`: the scene's own options with its own defaults (size, --out), none of another
    scene's options; bare `--help` says that options depend on the scene and names the scenes."""
    from pywarp.cli.scene import view_defaults
    from pywarp.core.params import specs
    from pywarp.core.scenes import DEFAULT_SCENE, scenes

    every = {name: {p.option for p in specs(sc.settings) if p.option} for name, sc in scenes().items()}
    for name, sc in scenes().items():
        text = _scene_help(command, name, tmp_path)
        assert f"these are {name}'s" in " ".join(text.split())
        mine = every[name] - set(sc.command_exclude.get(command, ()))
        for other, opts in every.items():
            for opt in opts - every[name]:
                assert f"  {opt} " not in text, (name, other, opt)
        defaults = {p.name: p.default for p in specs(sc.settings)}
        defaults.update(view_defaults(sc) if command == "view" else {})
        defaults.update(sc.command_defaults.get(command, {}))
        if "width" in defaults:
            width = " ".join(text.split("--width INT", 2)[-1].split())  # the option's help, wrapped lines joined
            assert f"default: {defaults['width']}" in width.split("--height")[0], (name, width[:200])
        if command != "view":
            out = sc.outputs.get(command, f"{name}.png" if command == "render" else f"{name}.mp4")
            assert f"(default: {out})" in " ".join(text.split()), name
        assert any(o in text for o in mine)
    bare = " ".join(_scene_help(command, None, tmp_path).split())
    assert "Options depend on the scene" in bare and f"these are {DEFAULT_SCENE}'s (the default scene)" in bare
    others = bare.split("Other scenes:")[1].split("(")[0]
    assert sorted(n.strip(" ,") for n in others.split()) == sorted(n for n in scenes() if n != DEFAULT_SCENE)
