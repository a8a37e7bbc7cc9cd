"""Hidden checks: only in the instructor's copy and the container, never in the student bundle."""
