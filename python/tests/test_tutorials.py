"""The Python tutorials run as a user runs them, headless (no DISPLAY, matplotlib's Agg): exit status 0 (each exits
non-zero when its task did not converge) and the figures they promise, as PNG files."""
import os
import subprocess
import sys

from conftest import TUTORIALS

PNG = b"\x89PNG\r\n\x1a\n"


def run(script, *args):
    environment = dict(os.environ, MPLBACKEND="Agg")
    environment.pop("DISPLAY", None)
    result = subprocess.run([sys.executable, os.path.join(TUTORIALS, script), *args], capture_output=True, text=True,
                            env=environment, timeout=240)
    assert result.returncode == 0, f"{script} exited with {result.returncode}:\n{result.stdout}\n{result.stderr}"
    return result.stdout


def is_png(path):
    with open(path, "rb") as f:
        return f.read(8) == PNG and os.path.getsize(path) > 10000


def test_apriltag_tutorial(tmp_path):
    out = run("tutorial-projective-servo-apriltag.py", "--output", str(tmp_path / "end.png"))
    assert "acquisition done" in out and "After" in out
    assert is_png(tmp_path / "end.png")


def test_paper_figures_tutorial(tmp_path):
    out = run("tutorial-projective-paper-figures.py", "--output", str(tmp_path))
    assert "Servo: image error" in out
    for figure in ("fig2-features", "fig4-joints", "fig5-error"):
        assert is_png(tmp_path / f"projective-servo-{figure}.png")

