# The dev container from nothing, as a student's laptop or GitHub Codespaces makes it: a Debian 12 made fresh by
# mmdebstrap from Debian's packages is the base, the student bundle's .devcontainer/Dockerfile is built on it by
# podman (chroot isolation: no daemon, no privileges a container withholds), and inside the image the bundle is set
# up by its own scripts/setup with no package installed by hand (install-deps finds every one already there) and
# self-checks the apple's reference to full visible marks, the sandbox saying which mode it runs in there. This is
# also the suite's proof, on a fresh machine, of the setup's package list. The objects the setup compiles come from
# the build's ccache where they are the same (below): the proof is the same, the minutes are not.
# shellcheck source=../smoke/lib.sh
source "$(dirname "$0")/../smoke/lib.sh"

if [[ $(id -u) -ne 0 ]] || ! command -v mmdebstrap >/dev/null || ! command -v podman >/dev/null; then
  echo "skipped: needs root, mmdebstrap and podman (scripts/install-deps installs them with the test tools)"
  exit 77
fi
tag=simlab-test-$$
base=localhost/$tag-base:latest dev=localhost/$tag-dev:latest checked=localhost/$tag-check:latest
cleanup() { podman rmi -f "$checked" "$dev" "$base" >/dev/null 2>&1; rm -rf "$work"; }
trap cleanup EXIT
seconds() { local start=$SECONDS; "$@"; local status=$?; echo "$((SECONDS - start))" >"$step.seconds"; return $status; }

step=base
seconds mmdebstrap --quiet --variant=apt --include=ca-certificates bookworm base.tar >base.log 2>&1
check "mmdebstrap makes a Debian 12 from Debian's packages ($(cat base.seconds) s)" test -s base.tar
[[ -s base.tar ]] || tail -5 base.log
podman import --quiet base.tar "$base" >/dev/null 2>>base.log
check "  which podman takes as an image" podman image exists "$base"
rm -f base.tar

run_capture package "$SIMLAB" package student -o bundle
check "the student bundle holds the dev container and VS Code's tasks" \
  test -f bundle/.devcontainer/devcontainer.json -a -f bundle/.devcontainer/Dockerfile -a -f bundle/.vscode/tasks.json \
  -a -f bundle/.dockerignore

step=image
seconds podman build --quiet --layers=false --isolation=chroot --build-arg BASE="$base" -t "$dev" \
  -f bundle/.devcontainer/Dockerfile bundle >image.log 2>&1
check "the dev container's image builds on it, every package from Debian ($(cat image.seconds) s)" \
  podman image exists "$dev"
podman image exists "$dev" || tail -20 image.log
size=$(podman image inspect --format '{{.Size}}' "$dev" 2>/dev/null || echo 0)
echo "    the image: $((size / 1000000)) MB"

# Inside, as the student: what the dev container runs on create (its onCreateCommand, limited to simlab and the
# apple's grader), then a self-check of the reference.
on_create=$(python3 -c 'import json,sys; print(json.load(open(sys.argv[1]))["onCreateCommand"])' \
  bundle/.devcontainer/devcontainer.json)
# (The bundle's .dockerignore keeps its dev container's build to the one file it takes: the bundle goes in as a
# folder of another context.)
mkdir context && mv bundle context/bundle
cp "$SOURCE_DIR/solutions/apple/NewtonsApple.cpp" context/bundle/reference-NewtonsApple.cpp
# The objects the bundle's build shares with the build under test come from that build's ccache (tests/smoke/lib.sh,
# shared_objects), lent to the check's stage read-only: the dev image itself has no ccache (it is the students' set
# of packages), so this stage alone installs it, and the test checks what that added. A hit leaves nothing unproved:
# in direct mode ccache takes an object only when every header its manifest names is there with the same bytes, and
# otherwise preprocesses, so a header of a package missing from the image fails the build as the compiler would
# (an object whose headers differ, another OpenSSL, is compiled anew); linking is never cached. Read-only, because
# the cache is the build's: a container's compiler and headers put nothing in it that the build would take later.
# A container whose compiler differs from the build's (another build of GCC) misses and compiles: slower, not wrong.
shared_objects /home/student/bundle
volume=() cache_env=""
echo "FROM $dev" >Containerfile
if [[ -n $shared_objects && -d $CCACHE_DIR ]]; then
  volume=(--volume "$CCACHE_DIR:/ccache:ro")
  cache_env="CCACHE_DIR=/ccache CCACHE_READONLY=1 CCACHE_TEMPDIR=/tmp/ccache CCACHE_STATSLOG=/tmp/ccache.log"
  cache_env+=" CCACHE_BASEDIR=$CCACHE_BASEDIR CCACHE_NOHASHDIR=1 CCACHE_SLOPPINESS=$CCACHE_SLOPPINESS"
  cache_env+=" SIMLAB_CMAKE_ARGS=$shared_objects"
  cat >>Containerfile <<'CONTAINERFILE'
USER root
RUN dpkg-query -W -f='${Package}\n' | sort >/tmp/packages \
 && apt-get update -qq && apt-get install -y -qq --no-install-recommends ccache >/dev/null \
 && rm -rf /var/lib/apt/lists/* \
 && echo "for the check alone: $(dpkg-query -W -f='${Package}\n' | sort | comm -13 /tmp/packages - | tr '\n' ' ')"
USER student
CONTAINERFILE
fi
cat >>Containerfile <<CONTAINERFILE
COPY --chown=student bundle /home/student/bundle
WORKDIR /home/student/bundle
RUN $cache_env SIMLAB_TARGETS="simlab apple_grader" $on_create 2>&1 && \\
    build/bin/simlab check apple reference-NewtonsApple.cpp 2>&1; status=\$?; \\
    if [ -f /tmp/ccache.log ]; then \\
      echo "ccache: \$(grep -cxE '(direct|preprocessed)_cache_hit' /tmp/ccache.log) objects from the build's cache, \$(grep -cx cache_miss /tmp/ccache.log) compiled"; \\
    fi; \\
    exit \$status
CONTAINERFILE
step=setup
seconds podman build --layers=false --isolation=chroot "${volume[@]}" -t "$checked" -f Containerfile context >setup.log 2>&1
check "inside it the bundle sets up with its own scripts/setup and checks the reference ($(cat setup.seconds) s)" \
  test -s setup.seconds -a "$(grep -c '^Score: ' setup.log)" -eq 1
grep -q '^Score: ' setup.log || tail -30 setup.log
check "  with no package to install: the image has them all" grep -q '^install-deps: all [0-9]* packages are installed' setup.log
check "  to full marks on the visible tests" grep -q '^Score: 76/76$' setup.log
check "  the sandbox saying which mode it runs in there" grep -qE '^  sandbox: (bubblewrap|Landlock|limits only)' setup.log
check "  and, when it is not bubblewrap, why not, in one line" \
  bash -c "grep -q '^  sandbox: bubblewrap' setup.log || grep -q 'bubblewrap cannot create namespaces here' setup.log"
grep -E '^  sandbox: ' setup.log | sed 's/^/   /'
if [[ ${#volume[@]} -gt 0 ]]; then
  # What ccache brings is its own program and the run-time libraries it links: no header, no tool a build could use.
  ccache_and_libraries() {
    local p; [[ -n $1 ]] || return 1
    for p in $1; do [[ $p == ccache || ($p == lib* && $p != *-dev) ]] || return 1; done
  }
  added=$(sed -n 's/^for the check alone: //p' setup.log)
  check "  the check's own stage adds ccache and libraries alone to the students' image (${added% })" \
    ccache_and_libraries "$added"
  grep '^ccache: ' setup.log | sed 's/^/    /'
else
  echo "    no ccache of the build's to lend: the setup compiled every object"
fi
finish
