# The layering of simlab's sources, checked on every #include of every tracked source of the tree given (its
# first argument): dependencies point one way (tests/lint/dependencies.sh says which). Prints each wrong include and
# a last line "N sources read, M wrong includes".
import os, re, subprocess, sys
root = sys.argv[1]
below = {  # a module -> the modules it may include besides itself
    "protocol": [], "rubric": [], "common": [],
    "isolation": ["common", "rubric"],
    "probe": ["protocol", "isolation"],
    "harness": ["protocol", "rubric", "probe"],
    "build": ["common", "rubric", "isolation"],
    "grading": ["common", "rubric", "isolation", "protocol", "build"],
    "writers": ["common", "rubric", "build", "grading"],
    "course": ["common", "rubric", "isolation", "protocol", "build", "grading", "writers"],
}
below["study"] = list(below["course"]) + ["course"]
below["cli"] = list(below) + ["study"]
modules = set(below)
# The course library (assignments/support/include/simlab/*.h: integrators, run settings, digits, the driver that
# calls a student's code, ...) is a layer of its own, below the grader's modules that talk to the course's code:
# the probe (which calls it), the harness (the judge's questions), the studies and the command. The rest of the
# grader - the sandbox, the build, grading, the writers, a class - knows nothing of Simbody or the labs; the
# sandbox takes one header of it, libm's reproducible versions, which every child's environment carries.
support_headers = set()
support_dir = os.path.join(root, "assignments/support/include/simlab")
if os.path.isdir(support_dir):
    support_headers = {name for name in os.listdir(support_dir) if name.endswith(".h")}
support_users = {"probe": None, "harness": None, "study": None, "cli": None, "isolation": {"reproducible_math.h"}}
include = re.compile(r'^\s*#\s*include\s*[<"]([^>"]+)[>"]', re.M)
files = subprocess.run(["git", "-C", root, "ls-files", "*.cpp", "*.h"], capture_output=True, text=True,
                       check=True).stdout.split()
said = 0
def wrong(path, name, why):
    global said
    said += 1
    print(f"{path}: includes {name}: {why}")
for path in files:
    text = open(os.path.join(root, path), encoding="utf-8", errors="replace").read()
    names = include.findall(text)
    parts = path.split("/")
    if parts[0] == "grader" and parts[1] in modules:
        me = parts[1]
        for name in names:
            m = re.match(r"simlab/([a-z_]+)/", name)
            if m and m.group(1) in modules and m.group(1) != me and m.group(1) not in below[me]:
                wrong(path, name, f"{me} may include only {', '.join(below[me]) or 'itself'}")
            if me == "protocol" and (name.lower().startswith("simbody") or (name.startswith("simlab/") and not name.startswith("simlab/protocol/"))):
                wrong(path, name, "the protocol knows neither Simbody nor the course")
            s = re.fullmatch(r"simlab/([A-Za-z0-9_]+\.h)", name)
            if s and s.group(1) in support_headers and me != "protocol":
                allowed = support_users.get(me, set())
                if allowed is not None and s.group(1) not in allowed:
                    users = ", ".join(sorted(m for m, a in support_users.items() if a is None))
                    wrong(path, name, f"the course library is included by {users} alone"
                          + (f" ({me}: {', '.join(sorted(allowed))})" if allowed else ""))
    elif parts[0] in ("assignments", "starter", "solutions", "examples"):
        # A lab's folder: assignments/<id>/ or examples/<id>/ (a lab of one's own, laid out the same way).
        lab_grading = parts[0] in ("assignments", "examples") and len(parts) > 2 and parts[2] == "grading"
        for name in names:
            m = re.match(r"simlab/([a-z_]+)/", name)
            if not m or m.group(1) not in modules:
                continue
            if lab_grading and m.group(1) in ("harness", "probe", "protocol"):
                continue
            if path == "assignments/support/include/simlab/wire_types.h" and m.group(1) == "protocol":
                continue
            wrong(path, name, "the course's code includes nothing of the grader")
print(f"{len(files)} sources read, {said} wrong includes")
