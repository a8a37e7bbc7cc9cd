"""The lab sheet's own recipes get full marks, and its tools work in the grader.

``tests/submissions/lab_sheet/`` holds one module per lab written the way the
lab sheet says, line by line: the OpenCV functions it names (float32 points
where OpenCV wants them), NumPy where it says NumPy, and Matplotlib windows to
look at the results. Every lab module placed there must score full marks.
"""

from pathlib import Path

import numpy as np
import pytest

from autograder.engine.registry import REGISTRY, Lab, discover
from autograder.engine.runner import grade
from conftest import assert_full_marks, submission_from_source

LAB_SHEET = Path(__file__).parent / "submissions" / "lab_sheet"
LABS = sorted(lab.key for lab in discover().values() if (LAB_SHEET / f"{lab.module}.py").is_file())


@pytest.fixture(scope="module")
def lab_sheet_result():
    return grade(LAB_SHEET, LABS, pictures="none")


@pytest.mark.parametrize("lab", LABS)
def test_the_lab_sheets_recipes_score_full_marks(lab_sheet_result, lab):
    assert_full_marks(lab_sheet_result, lab)


@pytest.fixture
def plotting_lab():
    lab = Lab("lab97", module="toy_plots", title="Toy")
    ex1 = lab.exercise("ex1", "Plots", functions=["plot(values)"])

    @ex1.check("plot twice: each call starts with no figure open", points=1)
    def fresh_figures(t):
        for _ in range(2):
            backend, open_figures = t.call("plot", np.arange(5.0))
            if backend.lower() != "agg" or open_figures != 1:
                t.fail(f"backend {backend}, {open_figures} figures open")

    yield lab
    REGISTRY.pop("lab97")


def test_matplotlib_is_headless_and_figures_are_closed_after_each_call(plotting_lab, tmp_path):
    source = """
        import matplotlib
        matplotlib.use("TkAgg", force=False)   # a student's habit; ignored without a display
        import matplotlib.pyplot as plt

        def plot(values):
            plt.figure()
            plt.plot(values)
            plt.show()
            plt.pause(0.01)
            return matplotlib.get_backend(), len(plt.get_fignums())
        """
    result = grade(submission_from_source(tmp_path, "toy_plots", source), ["lab97"])
    [check] = result.exercises[0].checks
    assert check.passed, check.message
    assert "non-interactive" not in check.output and "non-GUI" not in check.output
