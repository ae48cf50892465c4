#!/usr/bin/env python3
"""Self-test of ci/check_layers.py: small trees with one fault each, built in a temporary
folder, must each be reported, a clean one must pass, and so must the repository itself.

  python3 ci/tests/test_check_layers.py   (CTest: layering_self_test)
"""

from __future__ import annotations

import sys
import tempfile
import unittest
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent.parent))

import check_layers  # noqa: E402  (the module under test, found through the path above)

REPOSITORY = Path(__file__).resolve().parent.parent.parent

TABLES = {
    "": (
        ("src", (), "code"),
        ("datasets", ("src",), "code"),
        ("oracle", ("datasets",), "code"),
        ("reference", ("datasets",), "code"),
        ("validation", ("oracle", "reference"), "code"),
        ("apps", ("validation",), "code"),
        ("reports", (), "files only"),
    ),
}

RUNNER_CMAKE = """
phdslam_runner_layer(testing TEST_HELPERS LIBS nlohmann_json::nlohmann_json)
phdslam_runner_layer(io LIBS phdslam_datasets)
phdslam_runner_layer(registry DEPENDS io
                     LIBS phdslam_filters)
"""

CLEAN = {
    "src/core/types.h": "",
    "src/core/angles.h": '#include "src/core/types.h"\n',
    "datasets/scenario.h": '#include "src/core/types.h"\n',
    "datasets/scenario.cc": '#include "datasets/scenario.h"\n#include <vector>\n',
    "oracle/oracle.h": '#include "datasets/scenario.h"\n',
    "reference/smoother.h": '#include "datasets/scenario.h"\n',
    "validation/runner/CMakeLists.txt": RUNNER_CMAKE,
    "validation/runner/io/csv.h": "",
    "validation/runner/registry/table.h": '#include "validation/runner/io/csv.h"\n'
                                          '#include "oracle/oracle.h"\n'
                                          '#include "reference/smoother.h"\n',
    "validation/runner/registry/table_test.cc": '#include "validation/runner/testing/t.h"\n',
    "validation/runner/testing/t.h": "",
    "apps/main.cc": '#include "validation/runner/registry/table.h"\n#include "beside.h"\n',
    "apps/beside.h": "",
    "reports/render.py": "",
}


def problems_of(changes: dict[str, str | None]) -> list[str]:
    """check_layers' problems for the clean tree with `changes` (None removes a file)."""
    files = {**CLEAN, **changes}
    with tempfile.TemporaryDirectory() as directory:
        root = Path(directory)
        for relative, text in files.items():
            if text is None:
                continue
            (root / relative).parent.mkdir(parents=True, exist_ok=True)
            (root / relative).write_text(text)
        return check_layers.check(root, TABLES)


class CheckLayersTest(unittest.TestCase):
    def assertReported(self, changes: dict[str, str | None], *fragments: str) -> None:
        problems = problems_of(changes)
        self.assertTrue(problems, "no problem reported")
        text = "\n".join(problems)
        for fragment in fragments:
            self.assertIn(fragment, text)

    def test_clean_tree_passes(self) -> None:
        self.assertEqual(problems_of({}), [])

    def test_back_edge_between_top_level_folders(self) -> None:
        self.assertReported({"datasets/scenario.cc": '#include "datasets/scenario.h"\n\n'
                                                     '#include "validation/runner/io/csv.h"\n'},
                            "datasets/scenario.cc:3", "back-edge datasets -> validation",
                            "datasets/scenario.cc -> validation/runner/io/csv.h")

    def test_sibling_edge_reported_as_a_circle_when_both_ways(self) -> None:
        self.assertReported({"oracle/oracle.h": '#include "reference/smoother.h"\n',
                             "reference/smoother.h": '#include "oracle/oracle.h"\n'},
                            "back-edge oracle -> reference", "back-edge reference -> oracle",
                            "a circle of folders oracle, reference")

    def test_circle_of_files_inside_one_folder(self) -> None:
        # x.cc includes y.h, and y.h includes x.h: the unit x (x.h + x.cc) and y go round.
        self.assertReported({"reference/batch.h": "",
                             "reference/batch.cc": '#include "reference/batch.h"\n'
                                                   '#include "reference/start.h"\n',
                             "reference/start.h": '#include "reference/batch.h"\n'},
                            "a circle of files reference/batch, reference/start",
                            "reference/batch -> reference/start (reference/batch.cc:2)",
                            "reference/start -> reference/batch (reference/start.h:1)")

    def test_circle_of_folders_without_a_table(self) -> None:
        self.assertReported({"src/core/types.h": '#include "src/models/model.h"\n',
                             "src/models/model.h": '#include "src/core/angles.h"\n'},
                            "a circle of folders src/core, src/models")

    def test_back_edge_between_runner_layers_from_cmake(self) -> None:
        self.assertReported({"validation/runner/io/csv.h": '#include '
                                                           '"validation/runner/registry/x.h"\n',
                             "validation/runner/registry/x.h": ""},
                            "validation/runner/io/csv.h:1",
                            "back-edge validation/runner/io -> validation/runner/registry")

    def test_test_helpers_outside_a_test(self) -> None:
        self.assertReported({"validation/runner/registry/table.cc":
                             '#include "validation/runner/testing/t.h"\n'},
                            "validation/runner/registry/table.cc:1: includes the test helpers")

    def test_files_only_folder_is_never_included(self) -> None:
        self.assertReported({"reports/figure.h": "",
                             "apps/main.cc": '#include "reports/figure.h"\n'},
                            "apps/main.cc:1", "files-only folder 'reports'")

    def test_files_only_folder_includes_nothing(self) -> None:
        self.assertReported({"reports/figure.cc": '#include "datasets/scenario.h"\n'},
                            "reports/figure.cc:1", "the files-only folder 'reports' includes C++")

    def test_folder_that_is_not_a_layer(self) -> None:
        self.assertReported({"tools/x.cc": ""}, "tools/: a folder of C++ that is not a layer")
        self.assertReported({"validation/runner/other/x.h": ""},
                            "validation/runner/other/: a folder of C++ that is not a layer")

    def test_source_at_the_top_level_of_a_layered_folder(self) -> None:
        self.assertReported({"validation/runner/loose.cc": ""},
                            "validation/runner/loose.cc: a source file at the top level")

    def test_dependency_declared_later(self) -> None:
        _, problems = check_layers.layer_tables(Path("/nonexistent"),
                                                {"": (("high", ("low",), "code"),
                                                      ("low", (), "code"))})
        self.assertEqual(len(problems), 1)
        self.assertIn("'high' depends on 'low', which is not declared before it", problems[0])

    def test_runner_table_is_read_from_cmake(self) -> None:
        with tempfile.TemporaryDirectory() as directory:
            cmake = Path(directory, "validation/runner/CMakeLists.txt")
            cmake.parent.mkdir(parents=True)
            cmake.write_text(RUNNER_CMAKE)
            self.assertEqual(check_layers.runner_layers(Path(directory)),
                             (("testing", (), "test helpers"), ("io", (), "code"),
                              ("registry", ("io",), "code")))

    def test_repository_passes(self) -> None:
        self.assertEqual(check_layers.check(REPOSITORY), [])


if __name__ == "__main__":
    unittest.main()
