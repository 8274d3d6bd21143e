#!/usr/bin/env python3
"""Look through packages for any line of a hidden test or of a solution.

    package_secrets.py SOURCE_DIR PACKAGE...

A secret line is a line (trimmed, 25 characters or more) of an assignment's hidden tests (grading/hidden.cpp,
grading/trade-hidden.json) or of its solution (solutions/<id>/, but the worked example project, solutions/biosim/,
which students are given), and an example lab's (examples/<lab>/solution/ and grading/hidden*, but the template's) that no public file of the project holds as well (the starters, the contracts, the
handouts: a comment a starter shares with its solution is no secret). Every file of each PACKAGE (a folder) is read
as bytes, whatever its name, line by line, and each secret line found is printed with where it was found. Exit 1
if any was.
"""
import os
import subprocess
import sys

MIN_LENGTH = 25


def lines_of(path):
    try:
        with open(path, "rb") as f:
            data = f.read()
    except OSError:
        return set()
    out = set()
    for raw in data.split(b"\n"):
        line = raw.strip()
        if len(line) >= MIN_LENGTH:
            out.add(line)
    return out


def is_secret(relative):
    parts = relative.split("/")
    if parts[0] == "solutions" and len(parts) > 1 and parts[1] != "biosim":
        return True
    # An example lab's solution and hidden tests (examples/<lab>/), but the template's, which every author copies.
    if parts[0] == "examples" and len(parts) > 2 and parts[1] != "template":
        return parts[2] == "solution" or (parts[2] == "grading" and "hidden" in parts[-1])
    return parts[0] == "assignments" and len(parts) > 2 and "hidden" in parts[-1]


def is_instructors(relative):
    # Neither secret nor public: what only instructors get (the corpus holds solutions' lines in its edits).
    return relative.startswith(("tests/", ".ci/", "bench/")) or (
        relative.startswith("examples/") and "/corpus/" in relative)


def main():
    if len(sys.argv) < 3:
        print(__doc__.strip().splitlines()[2].strip(), file=sys.stderr)
        return 2
    source = sys.argv[1]
    files = subprocess.run(["git", "-C", source, "ls-files"], capture_output=True, text=True, check=True).stdout.split()
    secret, public = set(), set()
    origin = {}
    for relative in files:
        path = os.path.join(source, relative)
        if is_secret(relative):
            for line in lines_of(path):
                secret.add(line)
                origin.setdefault(line, relative)
        elif not is_instructors(relative):
            public |= lines_of(path)
    secret -= public
    if not secret or not any(o.startswith("assignments/") for o in origin.values()):
        print("package_secrets: no secret line to look for (or none of a hidden test)", file=sys.stderr)
        return 2
    found = 0
    for package in sys.argv[2:]:
        seen = 0
        for folder, _, names in os.walk(package):
            for name in names:
                path = os.path.join(folder, name)
                if os.path.islink(path) or not os.path.isfile(path):
                    continue
                for line in sorted(lines_of(path) & secret):
                    found += 1
                    seen += 1
                    print(f"{os.path.relpath(path, package)} in {package} holds a line of {origin[line]}: "
                          f"{line.decode(errors='replace')}")
        said = "no line" if seen == 0 else "1 line" if seen == 1 else f"{seen} lines"
        print(f"{package}: {said} of a hidden test or a solution ({len(secret)} looked for)")
    return 1 if found else 0


if __name__ == "__main__":
    sys.exit(main())
