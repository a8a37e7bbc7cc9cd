"""Reading a submission: what was handed in, made into plain modules, never run.

Above the sandbox (it uses its file reading and its list of importable libraries),
below the engine.

- :mod:`.submission` -- finding each lab's module in a folder, a file, a zip or a notebook;
- :mod:`.notebooks` and :mod:`.definitions` -- a notebook taken as its definitions,
  exactly as it runs top to bottom;
- :mod:`.reading` -- causes only the source shows (read with ``ast``);
- :mod:`.text` -- text from a submission made inert before it is shown.
"""
