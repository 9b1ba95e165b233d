# Bounds on the figures a validation script prints ("Figure: <name> = <value> ..." lines), for the
# quick validation tests. Source it and set figures=<the file the script's output went to>.
#   within <name> <lo> <hi>: lo <= value <= hi, else FAIL (a nan or a missing figure fails)
fail() { echo "FAIL: $*"; exit 1; }
figure() { sed -n "s/^Figure: $1 = \([^ ]*\).*/\1/p" "$figures"; }
within() {
    local name=$1 lo=$2 hi=$3 v
    v=$(figure "$name")
    awk -v v="$v" -v lo="$lo" -v hi="$hi" 'BEGIN { exit !(v != "" && v + 0 == v && v >= lo && v <= hi) }' \
        || fail "$name = '$v' outside [$lo, $hi]"
    echo "$name = $v in [$lo, $hi]"
}
