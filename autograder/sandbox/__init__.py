"""The sandbox: where student code runs, and everything that crosses back from it.

The lowest layer: it knows nothing of labs or checks, only how to run a function
of a folder of modules in a confined worker and what to believe of the answer.

- :mod:`.supervisor` -- the grader's side: :class:`~autograder.sandbox.supervisor.Sandbox`
  starts a worker, sends one call at a time, turns whatever happens into a ``CallOutcome``;
- :mod:`.confine` and :mod:`.namespace_init` -- the worker's view of the system
  (namespaces, read-only mounts, a user of its own, cgroups), probed once per machine;
- :mod:`.worker`, :mod:`.transport`, :mod:`.beginner` -- what runs inside (copied into
  the scratch folder, never imported by the grader's process from there);
- :mod:`.evidence` -- what the kernel says about a worker, the only source of a fault's verdict;
- :mod:`.files` -- reading files someone else wrote (no link followed, every size capped);
- :mod:`.cache` -- the store of ground truth, which workers read and never write.
"""
