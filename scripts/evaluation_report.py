"""Writing an evaluation report: the generated Markdown, then the hand-written reading of
its figures from a notes file beside it, when there is one."""

import os


def write_report(path, lines, notes_name):
    notes = os.path.join(os.path.dirname(os.path.abspath(path)), notes_name)
    if os.path.exists(notes):
        with open(notes) as f:
            lines = lines + [f.read()]
    with open(path, "w") as f:
        f.write("\n".join(lines))
