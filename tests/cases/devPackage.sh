#!/usr/bin/env bash
# The development package used as a user would: installs this build into a temporary prefix
# (cmake --install), builds the kernel template outside the tree against it
# (find_package(Spindrift), spindrift_add_plugin named by the folder), and runs the installed
# solver with -dryRun on a copy of the installed hydrostaticTank2D that loads the template kernel
# through controlDict `libs`. The installed solver must use the installed library and find the
# installed plugins by itself (no SPINDRIFT_PLUGIN_PATH), never the build tree's.
#   devPackage.sh <build dir>
set -euo pipefail
build=$(cd "$1" && pwd)
fail() { echo "FAIL: $*"; exit 1; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
unset SPINDRIFT_DIR SPINDRIFT_PLUGIN_PATH SPINDRIFT_BIN
prefix=$work/prefix

cmake --install "$build" --prefix "$prefix" > "$work/install.log" || { cat "$work/install.log"; fail "cmake --install"; }
for f in bin/spindrift include/spindrift/Plugin.hpp include/spindrift/Kernel.hpp include/spindrift/NeighbourSearch.tpp \
         lib/cmake/Spindrift/SpindriftConfig.cmake lib/cmake/Spindrift/SpindriftConfigVersion.cmake \
         lib/cmake/Spindrift/SpindriftTargets.cmake lib/cmake/Spindrift/SpindriftPlugin.cmake \
         lib/spindrift/plugins/libspindrift_kernel_wendlandC2.so lib/spindrift/plugins/libspindrift_pressure_wcsph.so \
         share/spindrift/etc/RunFunctions share/spindrift/etc/bashrc share/spindrift/etc/templates/kernel/CMakeLists.txt \
         share/spindrift/tutorials/hydrostaticTank2D/system/controlDict share/bash-completion/completions/spindrift; do
    [ -e "$prefix/$f" ] || fail "cmake --install did not install $f"
done
[ -x "$prefix/share/spindrift/tutorials/damBreak2D/Allrun" ] || fail "the tutorials' scripts lost their executable bit"
soname=$(objdump -p "$prefix"/lib/libspindrift.so | awk '$1 == "SONAME" { print $2 }')
[[ "$soname" =~ ^libspindrift\.so\.[0-9]+\.[0-9]+$ ]] || fail "libspindrift.so has no versioned SONAME: '$soname'"
[ -f "$prefix/lib/$soname" ] || fail "$soname is not installed"
if grep -rlF "$build" "$prefix/lib/cmake" "$prefix/share/spindrift/etc"; then fail "the package refers to the build tree"; fi

# the kernel template outside the tree, named by its folder
cp -r "$prefix/share/spindrift/etc/templates/kernel" "$work/myKernel"
cmake -S "$work/myKernel" -B "$work/myKernel/build" -DCMAKE_PREFIX_PATH="$prefix" -DCMAKE_BUILD_TYPE=Release \
    > "$work/configure.log" 2>&1 || { cat "$work/configure.log"; fail "configuring the kernel template"; }
cmake --build "$work/myKernel/build" > "$work/build.log" 2>&1 || { cat "$work/build.log"; fail "building the kernel template"; }
plugin=$work/myKernel/build/libspindrift_kernel_myKernel.so
[ -f "$plugin" ] || fail "no $plugin: $(ls "$work/myKernel/build")"

# the installed solver, on a copy of the installed tutorial that loads it
. "$prefix/share/spindrift/etc/RunFunctions"
[ "$(command -v spindrift)" = "$prefix/bin/spindrift" ] || fail "RunFunctions put $(command -v spindrift) first on PATH"
core=$(ldd "$prefix/bin/spindrift" | awk '$1 == "'"$soname"'" { print $3 }')
[ "$(readlink -f "$core")" = "$(readlink -f "$prefix/lib/$soname")" ] || fail "the installed solver uses '$core'"
cloneCase "$prefix/share/spindrift/tutorials/hydrostaticTank2D" "$work/case"
sed -i "s|^application .*|&\nlibs            (\"$plugin\");|" "$work/case/system/controlDict"
sed -i 's/type        wendlandC2;/type        myKernel;/' "$work/case/system/sphSchemes"
grep -q "type        myKernel;" "$work/case/system/sphSchemes" || fail "could not select the template kernel"
"$prefix/bin/spindrift" -listModels kernel | grep -qw wendlandC2 || fail "the installed solver does not list its plugins"
out=$("$prefix/bin/spindrift" -case "$work/case" -dryRun -threads 1 2>&1) || { echo "$out"; fail "-dryRun"; }
echo "$out"
grep -q "Schemes   : kernel myKernel, pressure wcsph" <<< "$out" || fail "-dryRun does not use the template kernel"
grep -qxF "    $plugin" <<< "$out" || fail "-dryRun does not list the template plugin as loaded"
grep -qxF "    $prefix/lib/spindrift/plugins/libspindrift_pressure_wcsph.so" <<< "$out" \
    || fail "-dryRun did not load the installed wcsph plugin"
if grep -qF "$build" <<< "$out"; then fail "the installed solver loaded something from the build tree"; fi
[ -f "$work/case/0/fluid.vtp" ] || fail "-dryRun did not write 0/"
echo "development package: OK"
