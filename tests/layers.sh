#!/bin/sh
# layers.sh: the library's include graph follows the layer order of src/README. A file under
# src/DIR/ may include headers of DIR and of the layers listed before DIR, never of one listed
# after it (which would make the layers a cycle, as scene.h <-> light.c once was). The order is
# read from src/README, its one place: the lines "  NAME/  ..." (and "  mcrt.h  ...") in order.
# Every directory of src/ must be listed there, and every listed one must exist.
# Run from the repository root; prints "ok ..." or "FAIL ..." per check, then "N passed, N failed".
passed=0
failed=0
check() {
    if [ "$2" = ok ]; then
        passed=$((passed + 1)); echo "ok $1"
    else
        failed=$((failed + 1)); echo "FAIL $1: $2"
    fi
}

# "NAME RANK" per layer, lowest first: mcrt.h is a layer of its own, as is each directory.
order=$(sed -n 's/^  \([a-z_][a-z_.]*\)\/\{0,1\}  .*/\1/p' src/README 2>/dev/null | awk '{ print $1, NR }')
if [ -z "$order" ]; then
    check "src/README lists the layers" "no lines '  NAME/  what it holds' found"
    echo "$passed passed, $failed failed"
    exit 1
fi
check "src/README lists the layers ($(echo "$order" | wc -l | tr -d ' '))" ok

# Directories of src/ and layers of src/README: the same set.
dirs=$(cd src && for d in */; do echo "${d%/}"; done)
unlisted=""
for d in $dirs; do
    echo "$order" | grep -q "^$d " || unlisted="$unlisted src/$d/"
done
missing=""
for l in $(echo "$order" | cut -d ' ' -f 1); do
    [ -e "src/$l" ] || missing="$missing $l"
done
if [ -n "$unlisted" ]; then check "every directory of src/ has a layer" "not in src/README:$unlisted"
else check "every directory of src/ has a layer" ok; fi
if [ -n "$missing" ]; then check "every layer of src/README exists" "no src/ entry for:$missing"
else check "every layer of src/README exists" ok; fi

# Every '#include "X"' of src/*/*.[ch]: X's layer (its directory, or X itself without one) must
# rank at most the including file's.
bad=$(grep -n '^[[:space:]]*#[[:space:]]*include[[:space:]]*"' src/*/*.c src/*/*.h |
    awk -v order="$order" '
        BEGIN { n = split(order, l, "\n"); for (i = 1; i <= n; i++) { split(l[i], f, " "); rank[f[1]] = f[2] } }
        {
            file = $0; sub(/:.*/, "", file)
            split(file, p, "/"); from = p[2]
            inc = $0; sub(/^[^"]*"/, "", inc); sub(/".*/, "", inc)
            to = inc; if (index(to, "/")) sub(/\/.*/, "", to)
            line = $0; sub(/^[^:]*:/, "", line); sub(/:.*/, "", line)
            if (!(to in rank)) print "    " file ":" line ": includes \"" inc "\", whose layer is not in src/README"
            else if (rank[to] > rank[from]) print "    " file ":" line ": " from "/ includes \"" inc "\" of the higher layer " to "/"
        }')
if [ -n "$bad" ]; then
    check "includes follow the layer order of src/README" "$(printf '\n%s' "$bad")"
else
    check "includes follow the layer order of src/README ($(grep -c '^[[:space:]]*#[[:space:]]*include[[:space:]]*"' src/*/*.c src/*/*.h | awk -F: '{ s += $2 } END { print s }') includes)" ok
fi
echo "$passed passed, $failed failed"
[ "$failed" -eq 0 ]
