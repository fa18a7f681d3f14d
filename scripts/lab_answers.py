#!/usr/bin/env python3
"""The labs' answer keys (docs/labs/NAME.answers.json), checked against the program or made anew.

Each key is a list of {"question", "command", "path", "value"}: `command` is a `lightcone`
command line as the lab's page shows it (run from the repository's root), `path` the place of
the answer in its JSON output (keys and list indices joined by dots: "pixel.0",
"black_hole.shadow_degrees"), `value` the number found there.

    scripts/lab_answers.py [--binary build/lightcone]          # check every key: exit 1 on a mismatch
    scripts/lab_answers.py --write [--binary build/lightcone]  # write each key's values anew

A value matches when it agrees to 1e-9 relative (1e-12 absolute near zero): an answer key quotes
six or more digits, and cannot drift from the program.
"""
import argparse
import glob
import json
import math
import os
import shlex
import subprocess
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
KEYS = os.path.join(ROOT, "docs", "labs", "*.answers.json")


def answer_of(entry, binary):
    """The number at the entry's path in its command's JSON output."""
    words = shlex.split(entry["command"])
    if not words or words[0] != "lightcone":
        raise ValueError(f"{entry['command']!r}: a command starts with `lightcone`")
    run = subprocess.run([binary] + words[1:], cwd=ROOT, capture_output=True, text=True)
    if run.returncode != 0:
        raise ValueError(f"{entry['command']!r} failed ({run.returncode}): {run.stderr.strip()}")
    value = json.loads(run.stdout)
    for step in entry["path"].split("."):
        value = value[int(step)] if isinstance(value, list) else value[step]
    if not isinstance(value, (int, float)) or isinstance(value, bool):
        raise ValueError(f"{entry['command']!r} at {entry['path']}: {value!r} is not a number")
    return value


def matches(found, expected):
    return math.isclose(found, expected, rel_tol=1e-9, abs_tol=1e-12)


def check(binary):
    """Every key's mismatches, as lines; none when every answer holds."""
    problems = []
    for path in sorted(glob.glob(KEYS)):
        with open(path) as f:
            for entry in json.load(f):
                found = answer_of(entry, binary)
                if not matches(found, entry["value"]):
                    problems.append(f"{os.path.relpath(path, ROOT)}: {entry['question']}: "
                                    f"{entry['command']} gives {found!r} at {entry['path']}, "
                                    f"the key says {entry['value']!r}")
    return problems


def write(binary):
    for path in sorted(glob.glob(KEYS)):
        with open(path) as f:
            entries = json.load(f)
        for entry in entries:
            entry["value"] = answer_of(entry, binary)
        with open(path, "w") as f:
            json.dump(entries, f, indent=2)
            f.write("\n")
        print(f"wrote {os.path.relpath(path, ROOT)} ({len(entries)} answers)")


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--binary", default=os.path.join(ROOT, "build", "lightcone"))
    parser.add_argument("--write", action="store_true", help="write each key's values anew")
    args = parser.parse_args()
    if args.write:
        write(args.binary)
        return 0
    problems = check(args.binary)
    for line in problems:
        print(line, file=sys.stderr)
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
