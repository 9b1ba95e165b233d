#!/usr/bin/env bash
# The Debian package: cpack -G DEB in the build directory (output into a temporary directory)
# makes spindrift_<version>_<arch>.deb; its control fields name the runtime libraries the
# binaries link (the VTK libraries: package paraview), python3-paraview and bash-completion are
# recommended, not required, and it holds the solver, library, plugins, headers, CMake package,
# etc/, tutorials (input only) and the completion under /usr; its prerm removes the python caches
# a script run as root leaves in /usr/share/spindrift (tried on the package unpacked into a
# directory, DPKG_ROOT). Nothing is installed.
#   debPackage.sh <build dir> <version>
set -euo pipefail
build=$(cd "$1" && pwd) version=$2
fail() { echo "FAIL: $*"; exit 1; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
(cd "$build" && cpack -G DEB -B "$work") > "$work/cpack.log" 2>&1 || { cat "$work/cpack.log"; fail "cpack -G DEB"; }
arch=$(dpkg --print-architecture)
deb=$work/spindrift_${version}_${arch}.deb
[ -f "$deb" ] || fail "no spindrift_${version}_${arch}.deb: $(ls "$work")"
echo "$(basename "$deb"): $(du -h "$deb" | cut -f1)"

field() { dpkg-deb -f "$deb" "$1"; }
[ "$(field Package)" = spindrift ] || fail "Package: $(field Package)"
[ "$(field Version)" = "$version" ] || fail "Version: $(field Version)"
[ "$(field Architecture)" = "$arch" ] || fail "Architecture: $(field Architecture)"
depends=$(field Depends)
echo "Depends: $depends"
# the packages of what the solver, library and plugins link (ldd build/bin/spindrift)
needs() { tr -d ' ' <<< "$depends" | tr ',' '\n' | sed 's/(.*//' | grep -qxF "$1" || fail "Depends lacks $1"; }
for p in libc6 libstdc++6 libgcc-s1 libboost-program-options1.74.0 paraview; do needs "$p"; done
if ldd "$build/lib/libspindrift.so" | grep -q libgomp; then needs libgomp1; fi
recommends=$(field Recommends)
echo "Recommends: $recommends"
for p in python3-paraview python3-matplotlib bash-completion; do
    tr -d ' ' <<< "$recommends" | tr ',' '\n' | grep -qxF "$p" || fail "Recommends lacks $p"
    if tr -d ' ' <<< "$depends" | tr ',' '\n' | sed 's/(.*//' | grep -qxF "$p"; then fail "Depends has $p (only recommended)"; fi
done
dpkg-deb -I "$deb" postinst | grep -qw ldconfig || fail "postinst does not run ldconfig for /usr/lib/libspindrift.so"
# prerm on the unpacked package: the caches go, the package's own files stay
root=$work/root
dpkg-deb -x "$deb" "$root"
dpkg-deb -e "$deb" "$work/control"
[ -x "$work/control/prerm" ] || fail "no executable prerm"
mkdir -p "$root/usr/share/spindrift/etc/python/__pycache__" "$root/usr/share/spindrift/tutorials/damBreak2D/__pycache__"
touch "$root/usr/share/spindrift/etc/python/__pycache__/spindriftValidation.cpython-311.pyc"
DPKG_ROOT=$root "$work/control/prerm" remove || fail "prerm remove failed"
if find "$root/usr/share/spindrift" -name __pycache__ | grep -q .; then fail "prerm left a __pycache__"; fi
[ -f "$root/usr/share/spindrift/etc/python/spindriftValidation.py" ] || fail "prerm removed a file of the package"
# and a tutorial's script writes none there: RunFunctions keeps python from it (without it, the
# same import leaves a cache: the check can fail)
share=$root/usr/share/spindrift
importValidation='cd "$1/etc/python" && /usr/bin/python3 -c "import spindriftValidation"'
env -u PYTHONDONTWRITEBYTECODE bash -c ". \"\$1/etc/RunFunctions\" && $importValidation" _ "$share" \
    || fail "importing spindriftValidation from the package failed"
if [ -d "$share/etc/python/__pycache__" ]; then fail "a script run through RunFunctions left a __pycache__"; fi
env -u PYTHONDONTWRITEBYTECODE bash -c "$importValidation" _ "$share" || fail "importing spindriftValidation failed"
[ -d "$share/etc/python/__pycache__" ] || fail "the control import left no __pycache__ (the check above proves nothing)"

dpkg-deb -c "$deb" | awk '{ print $1, $6 }' > "$work/contents"
has() { grep -qE "^$1 \./usr/$2$" "$work/contents" || fail "the package lacks /usr/$2"; }
has -rwxr-xr-x bin/spindrift
has lrwxrwxrwx 'lib/libspindrift\.so\.[0-9]+\.[0-9]+'
has -rw-r--r-- "lib/libspindrift\.so\.$version"
has '-rw-r--r--' lib/spindrift/plugins/libspindrift_kernel_wendlandC2.so
has '-rw-r--r--' lib/spindrift/plugins/libspindrift_pressure_dfsph.so
has '-rw-r--r--' include/spindrift/Plugin.hpp
has '-rw-r--r--' lib/cmake/Spindrift/SpindriftConfig.cmake
has '-rw-r--r--' lib/cmake/Spindrift/SpindriftPlugin.cmake
has '-rw-r--r--' share/spindrift/etc/RunFunctions
has '-rw-r--r--' share/spindrift/etc/templates/functionObject/CMakeLists.txt
has -rwxr-xr-x share/spindrift/tutorials/damBreak2D/Allrun
has '-rw-r--r--' share/spindrift/tutorials/damBreak2D/system/controlDict
has '-rw-r--r--' share/bash-completion/completions/spindrift
if grep -E '\.pvd$|/log\.[^/]*$|/postProcessing/|/[0-9][0-9.eE+-]*/$' "$work/contents"; then
    fail "the package holds results of tutorial runs"
fi
if grep -vE " \./usr/" "$work/contents" | grep -vE " \./$"; then fail "files outside /usr"; fi
echo "Debian package: OK"
