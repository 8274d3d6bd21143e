# Dependencies point one way. Each of the grader's modules includes only the modules below it (grader/CMakeLists.txt
# names the order); the course library (assignments/support) is a layer that only the probe, the harness, the
# studies and the command include; the protocol knows neither Simbody nor the course; the course's code includes
# nothing of the grader but the protocol's JSON forms (simlab/wire_types.h), and a lab's grading/ the harness and
# the probe too. Checked on every #include of every tracked source (tests/lint/dependencies.py), so a new file is
# held to it as soon as it exists; and the check itself is tried on a tree with a wrong include of each kind.
# shellcheck source=../smoke/lib.sh
source "$(dirname "$0")/../smoke/lib.sh"

python3 "$SOURCE_DIR/tests/lint/dependencies.py" "$SOURCE_DIR" >found.txt
cat found.txt
check "every source was read" grep -qE '^[1-9][0-9]+ sources read' found.txt
check "no include points the wrong way" grep -q ' 0 wrong includes$' found.txt

# The lint, tried: a tree whose sources hold one wrong include of each kind, and right ones beside them.
mkdir -p tree && cd tree && git init -q
mkdir -p grader/rubric grader/isolation grader/harness grader/build assignments/support/include/simlab \
  assignments/apple/program
touch assignments/support/include/simlab/program.h assignments/support/include/simlab/reproducible_math.h
printf '#include "simlab/program.h"\n' >grader/rubric/wrong_support.cpp
printf '#include "simlab/program.h"\n#include "simlab/reproducible_math.h"\n' >grader/isolation/one_of_each.cpp
printf '#include "simlab/program.h"\n#include "simlab/harness/testing.h"\n' >grader/harness/right.cpp
printf '#include "simlab/grading/grade.h"\n' >grader/build/wrong_module.cpp
printf '#include "simlab/grading/grade.h"\n#include "simlab/program.h"\n' >assignments/apple/program/wrong_course.cpp
git add -A && cd ..
python3 "$SOURCE_DIR/tests/lint/dependencies.py" tree >tried.txt
sed 's/^/    /' tried.txt
check "the lint finds a module including the course library (rubric), and the sandbox's one header of it allowed" \
  bash -c "grep -q '^grader/rubric/wrong_support.cpp: includes simlab/program.h' tried.txt &&
    grep -q '^grader/isolation/one_of_each.cpp: includes simlab/program.h' tried.txt &&
    ! grep -q 'includes simlab/reproducible_math.h' tried.txt && ! grep -q '^grader/harness/right.cpp' tried.txt"
check "and a module including one above it, and the course's code including the grader" \
  bash -c "grep -q '^grader/build/wrong_module.cpp: includes simlab/grading/grade.h' tried.txt &&
    grep -q '^assignments/apple/program/wrong_course.cpp: includes simlab/grading/grade.h' tried.txt"
check "four wrong includes, no more (the course's code may include its library)" grep -q ' 4 wrong includes$' tried.txt
finish
