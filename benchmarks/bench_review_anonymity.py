"""What anonymous review costs per review screen: the student's forms, and redacting a long explanation.

A student with a three-part name, a group partner, an e-mail, LMS ids (about 300 forms of
their identities: cases, Unicode forms, accents, parts joined in every order); an
explanation of the longest length a report may have (``MAX_EXPLANATION_CHARS``), once
without any identity and once naming the student every few words. A benchmark, not a
test: it prints figures.

    python benchmarks/bench_review_anonymity.py
"""

from __future__ import annotations

import re
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from autograder.instructor.review.anonymity import Anonymiser, _whole  # noqa: E402
from autograder.loading.report import MAX_EXPLANATION_CHARS  # noqa: E402

STUDENT = {"student_id": "lukasz-s2231234", "display_name": "Jørgen Anders Łukasz",
           "origin": "lukaszjorgen_7654321_55_lab07_transformations.py",
           "lms": {"canvas_user_id": "7654321", "email": "jorgen.lukasz@uni.example", "sid": "s2231234"},
           "members": [{"name": "Jørgen Anders Łukasz", "sid": "s2231234", "email": "jorgen.lukasz@uni.example"},
                       {"name": "Ngozi Okoro", "sid": "s7777777", "email": "okoro@uni.example"}]}
TEXTS = {"no identity": "The warp leaves black corners because the inverse map samples outside the image. ",
         "named often": "Jørgen Łukasz (s2231234lab07, JØRGEN, jorgen.lukasz@uni.example) with Okoro. "}


def timed(call, repeat: int) -> float:
    start = time.perf_counter()
    for _ in range(repeat):
        call()
    return (time.perf_counter() - start) / repeat * 1000


def main():
    files = [f"report_{i}.md" for i in range(20)]
    hide = Anonymiser(STUDENT, files, "Student ABC123")
    print(f"forms of the identities   {len(hide._forms)}")
    print(f"Anonymiser built in       {timed(lambda: Anonymiser(STUDENT, files, 'Student ABC123'), 20):7.1f} ms")
    everything = re.compile("|".join(_whole(form) for form, _ in hide._forms), re.IGNORECASE)
    for name, sentence in TEXTS.items():
        text = (sentence * (MAX_EXPLANATION_CHARS // len(sentence) + 1))[:MAX_EXPLANATION_CHARS]
        print(f"{name:12} {len(text):,} chars: only the forms present {timed(lambda: hide.text(text), 10):7.1f} ms"
              f" | one alternation of all {timed(lambda: everything.sub('S', text), 2):7.1f} ms")


if __name__ == "__main__":
    main()
