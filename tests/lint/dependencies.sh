# Dependencies point one way. Each of the grader's modules includes only the modules below it (grader/CMakeLists.txt
# names the order); the protocol knows neither Simbody nor the course; the course's code includes nothing of the
# grader but the protocol's JSON forms (simlab/wire_types.h), and a lab's grading/ the harness and the probe too.
# Checked on every #include of every tracked source, so a new file is held to it as soon as it exists.
# shellcheck source=../smoke/lib.sh
source "$(dirname "$0")/../smoke/lib.sh"

python3 - "$SOURCE_DIR" >found.txt <<'PY'
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
PY
cat found.txt
check "every source was read" grep -qE '^[1-9][0-9]+ sources read' found.txt
check "no include points the wrong way" grep -q ' 0 wrong includes$' found.txt
finish
