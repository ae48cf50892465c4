"""Headless Chromium renders the report without console errors into a non-blank screenshot."""

import os
import shutil
import subprocess
import tempfile
import unittest
from pathlib import Path

from fixture import FixtureSpec, make_results_folder  # first: checks the interpreter
import numpy as np
from matplotlib import image as mpimg
from phdslam_reports.report import build_report


def find_chromium() -> str | None:
    """The Chromium program, if installed (Debian: apt-get install chromium)."""
    for name in ("chromium", "chromium-browser", "google-chrome"):
        path = shutil.which(name)
        if path:
            return path
    return None


CHROMIUM = find_chromium()
# The test command (ci/run-tests.sh) installs Chromium and sets this, so that a missing browser
# fails the run there instead of skipping the test.
REQUIRED = os.environ.get("PHDSLAM_REQUIRE_CHROMIUM") == "1"


class ChromiumPresenceTest(unittest.TestCase):
    def test_chromium_is_installed_where_required(self):
        if not REQUIRED:
            self.skipTest("PHDSLAM_REQUIRE_CHROMIUM is not 1")
        self.assertIsNotNone(CHROMIUM, "PHDSLAM_REQUIRE_CHROMIUM=1 but no chromium on PATH")


@unittest.skipIf(CHROMIUM is None, "chromium is not installed (apt-get install -y chromium, or "
                                   "ci/install-deps.sh --browser): render test skipped")
class RenderTest(unittest.TestCase):
    def test_report_renders_to_a_non_blank_screenshot(self):
        with tempfile.TemporaryDirectory() as tmp:
            tmp_path = Path(tmp)
            results = make_results_folder(tmp_path / "results", FixtureSpec(
                nees=True, particles_file=True, scaling=True, steps=30, steps_option=4000))
            out = tmp_path / "report"
            build_report([results], out)
            screenshot = tmp_path / "shot.png"
            command = [
                CHROMIUM, "--headless", "--no-sandbox", "--disable-gpu", "--disable-quic",
                "--no-first-run", "--disable-background-networking",
                "--disable-component-update", "--disable-sync",
                f"--user-data-dir={tmp_path / 'profile'}", f"--screenshot={screenshot}",
                "--window-size=1400,4000", "--enable-logging=stderr", "--v=0",
                (out / "index.html").as_uri(),
            ]
            done = subprocess.run(command, capture_output=True, text=True, timeout=180,
                                  env={**os.environ, "HOME": str(tmp_path)})
            log = done.stdout + done.stderr
            self.assertEqual(done.returncode, 0, log[-3000:])
            problems = [line for line in log.splitlines()
                        if "CONSOLE" in line or "Uncaught" in line or "net::ERR_" in line
                        or "Failed to load resource" in line]
            self.assertEqual(problems, [], "browser console errors")
            self.assertTrue(screenshot.is_file(), log[-3000:])
            pixels = mpimg.imread(screenshot)
            self.assertEqual(pixels.shape[:2], (4000, 1400))
            grey = pixels[..., :3].mean(axis=2)
            self.assertGreater(float(np.std(grey)), 0.05, "screenshot is blank")
            dark = float(np.mean(grey < 0.5))
            self.assertGreater(dark, 0.005, "no text or lines drawn")
            # the figures are drawn: some rows hold coloured (non-grey) pixels
            colour = np.max(pixels[..., :3], axis=2) - np.min(pixels[..., :3], axis=2)
            self.assertGreater(float(np.mean(colour > 0.2)), 0.001, "no coloured figure pixels")


if __name__ == "__main__":
    unittest.main()
