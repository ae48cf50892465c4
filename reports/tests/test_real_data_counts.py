"""Real data with a true map (mrclam): the report states what the steps are made of."""

import json
import tempfile
import unittest
from pathlib import Path

from fixture import FixtureSpec, make_results_folder
from phdslam_reports.report import build_report, counts_text

COUNTS = {"steps": 1459, "unscored_steps": 2, "landmark_detections": 2023,
          "other_robot_detections": 373, "unknown_barcode_detections": 3,
          "non_landmarks_dropped": False, "images_skipped": 0}


class RealDataCountsTest(unittest.TestCase):
    def test_sentence_names_every_count(self):
        text = counts_text(COUNTS)
        self.assertIn("1459 steps (2 without truth", text)
        self.assertIn("373 of other robots and 3 of unknown barcodes (kept as clutter)", text)
        self.assertNotIn("images", text)  # none skipped
        dropped = counts_text(dict(COUNTS, non_landmarks_dropped=True, images_skipped=4))
        self.assertIn("(dropped)", dropped)
        self.assertIn("4 images outside the commands or the truth left out", dropped)

    def test_folder_intro_states_the_counts(self):
        with tempfile.TemporaryDirectory() as tmp:
            root = Path(tmp)
            results = make_results_folder(root / "results", FixtureSpec(scenario="mrclam"))
            config_path = results / "config.json"
            config = json.loads(config_path.read_text(encoding="utf-8"))
            config["scenario"]["options"]["counts"] = COUNTS
            config_path.write_text(json.dumps(config), encoding="utf-8")
            build_report([results], root / "report")
            html = (root / "report" / "index.html").read_text(encoding="utf-8")
        self.assertIn("373 of other robots and 3 of unknown barcodes", html)


if __name__ == "__main__":
    unittest.main()
