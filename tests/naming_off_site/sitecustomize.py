"""Run at start-up by a Python whose PYTHONPATH holds this folder (a test's ``grade.py``
subprocess): the grader's naming is off in that process (tests/naming_switch.py)."""

import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))   # tests/, for naming_switch
try:
    from naming_switch import turn_naming_off
finally:
    del sys.path[0]

turn_naming_off()
