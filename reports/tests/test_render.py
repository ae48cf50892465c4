"""Headless Chromium renders the report without console errors into a non-blank screenshot, and
at 1280 px wide no part of the page reaches beyond the window (wide tables scroll in their box)."""

import os
import re
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


OVERFLOW_PROBE = """<script>
(function () {
  var width = window.innerWidth;
  var wide = [];
  var all = document.body.getElementsByTagName("*");
  for (var i = 0; i < all.length; i++) {
    var box = all[i].getBoundingClientRect();
    if (box.right > width + 0.5 && all[i].offsetParent !== null) {
      var inside = all[i].closest(".table-box");
      if (!inside || inside.getBoundingClientRect().right > width + 0.5) {
        wide.push(all[i].tagName + (all[i].className ? "." + all[i].className : ""));
      }
    }
  }
  var boxes = document.getElementsByClassName("table-box");
  var scrolling = 0;
  for (var j = 0; j < boxes.length; j++) {
    if (boxes[j].scrollWidth > boxes[j].clientWidth) { scrolling++; }
  }
  document.body.setAttribute("data-probe", [document.documentElement.scrollWidth, width,
      scrolling, wide.slice(0, 10).join(" ")].join("|"));
})();
</script>"""
"""Appended to a copy of the page (the report itself has no scripts): records the page's scroll
width, the window's width, how many table boxes scroll sideways and the first elements whose right
edge lies beyond the window outside a table box."""


def chromium_command(profile: Path, *arguments: str) -> list[str]:
    """Headless Chromium with no network activity of its own, a fresh profile and ``arguments``."""
    return [CHROMIUM, "--headless", "--no-sandbox", "--disable-gpu", "--disable-quic",
            "--no-first-run", "--disable-background-networking", "--disable-component-update",
            "--disable-sync", f"--user-data-dir={profile}", *arguments]


def page_overflow(page: Path, width: int, work: Path) -> tuple[int, int, int, str]:
    """(document scroll width, window width, table boxes that scroll, elements beyond the window)
    of ``page`` rendered ``width`` px wide."""
    probe = page.with_name("probe.html")
    probe.write_text(page.read_text(encoding="utf-8").replace("</body>",
                                                              OVERFLOW_PROBE + "</body>"),
                     encoding="utf-8")
    done = subprocess.run(
        chromium_command(work / "probe-profile", f"--window-size={width},900",
                         "--virtual-time-budget=5000", "--dump-dom", probe.as_uri()),
        capture_output=True, text=True, timeout=180, env={**os.environ, "HOME": str(work)})
    match = re.search(r'data-probe="(\d+)\|(\d+)\|(\d+)\|([^"]*)"', done.stdout)
    if match is None:
        raise AssertionError(f"the probe did not run: {done.stderr[-2000:]}")
    return int(match[1]), int(match[2]), int(match[3]), match[4]


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
            command = chromium_command(
                tmp_path / "profile", f"--screenshot={screenshot}", "--window-size=1400,4000",
                "--enable-logging=stderr", "--v=0", (out / "index.html").as_uri())
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

    def test_nothing_overflows_a_1280_px_window(self):
        """Wide tables (many metrics, long cells) scroll inside their box; the page does not."""
        with tempfile.TemporaryDirectory() as tmp:
            tmp_path = Path(tmp)
            deep = tmp_path / ("results-folder-with-a-long-name-" * 4) / "quick"
            results = make_results_folder(deep, FixtureSpec(
                groups=(("phd3", 1), ("phd3", 10), ("phd1", 10), ("odometry", 1)),
                nees=True, particles_file=True, scaling=True, parent_weights=True,
                da_rates=True, steps=30, steps_option=0))
            out = tmp_path / "report"
            build_report([results], out)
            scroll_width, width, scrolling, wide = page_overflow(out / "index.html", 1280,
                                                                 tmp_path)
            self.assertEqual(width, 1280)
            self.assertLessEqual(scroll_width, width, f"elements beyond the window: {wide}")
            self.assertEqual(wide, "")
            # the summary table (eight metrics with DA rates) is wider than the page: it scrolls
            self.assertGreaterEqual(scrolling, 1)


if __name__ == "__main__":
    unittest.main()
