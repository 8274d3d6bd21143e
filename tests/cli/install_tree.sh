# cmake --install of the build, once, into $FIXTURES/install: what an installation writes is checked here - simlab,
# its manifest, its CMake package and the man page, with no folder of the build or the sources named and no
# precompiled header. The tests of an installation (cli/install, cli/authoring) copy this tree (cp -a) and work on
# their copy: the copy is a moved prefix, which simlab must grade from as from where it was installed.
# Usage: install_tree.sh BUILD_DIR
# shellcheck source=../smoke/lib.sh
source "$(dirname "$0")/../smoke/lib.sh"
build=$1
tree=$FIXTURES/install
rm -rf "$tree" && mkdir -p "$FIXTURES"

run_capture install cmake --install "$build" --prefix "$tree"
check "cmake --install writes simlab, its manifest and its CMake package" \
  test "$(status_of install)" -eq 0 -a -x "$tree/bin/simlab" -a -f "$tree/lib/simlab/simlab-build.json" \
       -a -f "$tree/lib/cmake/simlab/simlabConfig.cmake" -a -f "$tree/lib/cmake/simlab/simlabConfigVersion.cmake"
[[ $(status_of install) -eq 0 ]] || tail -n 20 install.err
if command -v help2man >/dev/null; then
  page=$tree/share/man/man1/simlab.1
  check "and the man page, made from simlab --help: its title and each command" \
    bash -c "grep -q '^\.TH SIMLAB \"1\"' $page && grep -qx check $page && grep -qx grade $page"
fi
check "the installed manifest names no folder of the build or of the sources" \
  bash -c "! grep -qF '$build' $tree/lib/simlab/simlab-build.json && ! grep -qF '\"$SOURCE_DIR/' $tree/lib/simlab/simlab-build.json"
check "and carries no precompiled header, which would name its headers by path" \
  bash -c "! ls $tree/lib/simlab/build/pch/*.pch >/dev/null 2>&1"
finish
