# The simlab commands not covered elsewhere, run headless: build, list, --help everywhere, and the class
# benchmark on a tiny class.
# shellcheck source=../smoke/lib.sh
source "$(dirname "$0")/../smoke/lib.sh"

run_capture build "$SIMLAB" build apple "$SOURCE_DIR/solutions/apple/NewtonsApple.cpp" -o apple-built
check "simlab build makes the lab program from any student file" test "$(status_of build)" -eq 0 -a -x apple-built
run_capture built ./apple-built --quiet
check "and the program it made runs the file's simulation" grep -q '14.8 accurate digits' built.out
run_capture broken bash -c "echo 'int x = ;' >broken.cpp && '$SIMLAB' build apple broken.cpp -o never"
check "a file that does not compile is a non-zero exit with the compiler's message" \
  bash -c "test $(status_of broken) -eq 2 && grep -q 'error: expected' broken.err && test ! -e never"

run_capture list "$SIMLAB" list
check "simlab list shows the three assignments" test "$(grep -cE '^(apple|projectile|book) ' list.out)" -eq 3

for command in "" check grade build list "package student" "package gradescope" autograde; do
  run_capture help $SIMLAB $command --help
  check "simlab $command --help" test "$(status_of help)" -eq 0 -a -s help.out
done

# The object cache keeps under its cap ($SIMLAB_CACHE_MIB): the least recently used entries go first, down to 80 %.
mkdir -p cache/objects  # $SIMLAB_CACHE holds every cache; the objects' is objects/
for age in 3 2 1; do  # three old entries of 600 KiB each, used 3, 2 and 1 days ago: 1.8 MiB against a 1 MiB cap
  head -c 614400 /dev/zero >"cache/objects/old$age.o" && echo "int x;" >"cache/objects/old$age.cpp"
  touch -d "$age days ago" "cache/objects/old$age.o" "cache/objects/old$age.cpp"
done
run_capture trimmed env SIMLAB_CACHE="$PWD/cache" SIMLAB_CACHE_MIB=1 "$SIMLAB" check apple "$SOURCE_DIR/solutions/apple/NewtonsApple.cpp"
check "a cache over its cap loses its least recently used entries, whole, down to 80 % of the cap" \
  bash -c "test $(status_of trimmed) -eq 0 && ! test -e cache/objects/old3.o -o -e cache/objects/old3.cpp -o -e cache/objects/old2.o && test -e cache/objects/old1.o -a -e cache/objects/old1.cpp"
check "  and keeps the entry it has just made" bash -c "ls cache/objects/*.o | grep -qv old"
run_capture badcap env SIMLAB_CACHE="$PWD/cache" SIMLAB_CACHE_MIB=lots "$SIMLAB" check apple
check "a cap that is not a size is a one-line usage error" \
  bash -c "test $(status_of badcap) -eq 2 && grep -q 'SIMLAB_CACHE_MIB is .lots.: a size in MiB' badcap.err"

# --version on simlab and on every program a student or an instructor runs: the project's version, from CMake.
version=$(sed -n 's/^project(simlab VERSION \([0-9.]*\).*/\1/p' "$SOURCE_DIR/CMakeLists.txt")
run_capture version "$SIMLAB" --version
check "simlab --version says simlab $version" bash -c "test $(status_of version) -eq 0 && test \"\$(cat version.out)\" = 'simlab $version'"
for program in apple projectile book babyboot project apple-study; do
  run_capture version "$BIN_DIR/$program" --version
  check "$program --version names it and simlab $version" \
    bash -c "test $(status_of version) -eq 0 && grep -q '^[a-z-]* (simlab $version' version.out"
done

run_capture bench "$BIN_DIR/bench-grade-class" --students 2 --rounds 1 --jobs 1
check "the class benchmark runs and prints its ratio" grep -q 'simlab / floor = ' bench.out
finish
