#!/bin/sh
# pov_ref.sh: `make ref`. For every POV reference case tests/pov/NAME.mcrt, export ref/NAME.pov with
# `mcrt pov` and render ref/NAME.exr with POV-Ray using the flags the exporter pins on the file's
# second line ("// povray FLAGS": box-filter antialiasing, and for motion blur K clock frames,
# averaged here by exr_average). POV-Ray's EXR output is linear half float and is kept as written;
# the motion average is float. Records POV-Ray's version in ref/POVRAY_VERSION. Needs povray.
# Run from the repository root after the build; $O is the build folder; CASES limits the cases.
set -e
O=${O:-build}
POVRAY=${POVRAY:-povray}
command -v "$POVRAY" >/dev/null 2>&1 || { echo "pov_ref.sh: $POVRAY not found (apt-get install povray)" >&2; exit 1; }
mkdir -p ref
"$POVRAY" --version 2>&1 | grep -m1 '^POV-Ray' > ref/POVRAY_VERSION
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
for scene in ${CASES:-tests/pov/*.mcrt}; do
    name=$(basename "$scene" .mcrt)
    start=$(date +%s)
    "$O/mcrt" pov "$scene" -o "ref/$name.pov"
    flags=$(sed -n '2s|^// povray ||p' "ref/$name.pov")
    [ -n "$flags" ] || { echo "pov_ref.sh: ref/$name.pov has no '// povray' line" >&2; exit 1; }
    case "$flags" in
    *+KFF*)
        # shellcheck disable=SC2086
        "$POVRAY" -D +WT2 +I"ref/$name.pov" +O"$tmp/$name.exr" $flags >"$tmp/log" 2>&1 ||
            { cat "$tmp/log" >&2; exit 1; }
        "$O/tests/exr_average" "ref/$name.exr" "$tmp/$name"*.exr
        rm -f "$tmp/$name"*.exr ;;
    *)
        # shellcheck disable=SC2086
        "$POVRAY" -D +WT2 +I"ref/$name.pov" +O"ref/$name.exr" $flags >"$tmp/log" 2>&1 ||
            { cat "$tmp/log" >&2; exit 1; } ;;
    esac
    echo "ref/$name.exr: $flags ($(( $(date +%s) - start )) s)"
done
