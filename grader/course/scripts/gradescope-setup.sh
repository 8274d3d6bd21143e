#!/usr/bin/env bash
# Gradescope runs this once, as root, to build the autograder image. Choose an Ubuntu 24.04 (or newer)
# base image: simlab needs CMake 3.25 and libtomlplusplus-dev.
# (simlab package gradescope writes it from grader/course/scripts/gradescope-setup.sh, its values in for the
# @...@ words.)
set -euo pipefail
targets=@TARGETS@  # what is built: simlab and this assignment's grader, or what a lab of one's own builds against
lab=@LAB@          # a lab of one's own, in this folder (empty: the course's own)
# The base image first, in one line, rather than a build that fails far down.
os_release=${SIMLAB_OS_RELEASE:-/etc/os-release}
ID=unknown VERSION_ID=0 PRETTY_NAME=unknown
# shellcheck disable=SC1090  # the image's own
[ -r "$os_release" ] && . "$os_release"
case "$ID" in
  ubuntu) minimum=24.04 ;;
  debian) minimum=12 ;;
  *) minimum="" ;;
esac
if [ -z "$minimum" ] || ! dpkg --compare-versions "$VERSION_ID" ge "$minimum"; then
  echo "simlab: the autograder's base image is $PRETTY_NAME: choose Ubuntu 24.04 (or newer) in the" \
       "autograder's settings (simlab needs CMake 3.25 and libtomlplusplus-dev)" >&2
  exit 1
fi
source_dir=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
SIMLAB_CMAKE_ARGS="-DBUILD_TESTING=OFF ${SIMLAB_CMAKE_ARGS:-}" SIMLAB_TARGETS="$targets" \
  "$source_dir/scripts/setup" --lean
if [[ -n $lab ]]; then
  "$source_dir/build/bin/simlab" assignment build "$source_dir/$lab"
fi
# simlab's places (the course, its build, the lab) closed to other users but what a test is lent, should neither
# bubblewrap nor Landlock run in Gradescope's container.
"$source_dir/scripts/lock-course" ${lab:+"$source_dir/$lab"}
