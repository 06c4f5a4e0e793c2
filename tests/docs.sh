#!/bin/sh
# docs.sh: the manuals, README and scenes checked against the code. groff lints each page and man
# renders it; mcrt.5 names every block kind and key of the scene language (the specified ones and
# those in the parser's tables); mcrt.1 and `mcrt --help` name every option (and mcrt.1 every
# option --help shows); every integrator of the library's table is named by mcrt.1, mcrt.5,
# libmcrt.3 and mcrt.h; libmcrt.3 gives every function of src/mcrt.h with the header's exact
# prototype, every status code and struct field, and an example that compiles; versions agree;
# the README lists the set-up's Debian packages; every scene renders and the README lists it, and
# the generated model of scenes/vase.mcrt is what its generator makes; the
# Cornell box shows its red wall on the left.
# Run from the repository root after the build; $O is the build folder. Prints "ok ...", "FAIL ..."
# or "skip ..." per check, then "N passed, N failed" (", N skipped" when some were).
. tests/harness.sh.inc
CC=${CC:-cc}

# The lines of a page that define terms (.B, .BI, .BR, .SS, .TP ...), with font changes and
# escapes removed, so that `.BI \-\-spp " n"` reads `.BI --spp " n"`.
terms() {
    grep -E '^\.(B|BI|BR|IB|RB|SS|TP)( |$)' "$1" |
        sed -e 's/\\f[BIRP]//g' -e 's/\\f(..//g' -e 's/\\-/-/g' -e 's/\\[&%]//g' -e 's/\\(dq/"/g'
}

# Plain text of a page as man shows it on a UTF-8 terminal, without bold or underline (nofill
# lines are never broken).
render() { groff -man -Tutf8 -P-c -P-b -P-u "$1" 2>/dev/null; }

# has_word TEXT WORD: WORD occurs in TEXT delimited by anything but [-A-Za-z0-9_].
has_word() {
    printf '%s\n' "$1" | grep -qE -- "(^|[^-A-Za-z0-9_])$2([^-A-Za-z0-9_]|\$)"
}

# check_words WHAT TEXT WORD...: one check that every WORD occurs in TEXT.
check_words() {
    what=$1 text=$2 missing=""
    shift 2
    for w in "$@"; do
        has_word "$text" "$w" || missing="$missing $w"
    done
    if [ -z "$missing" ]; then ok "$what ($# names)"; else fail "$what: missing$missing"; fi
}

# ---- groff and man ----
for page in man/mcrt.1 man/mcrt.5 man/libmcrt.3; do
    if [ ! -f "$page" ]; then
        fail "$page is missing"
        continue
    fi
    if groff -man -ww -z "$page" >"$tmp/lint" 2>&1 && [ ! -s "$tmp/lint" ]; then
        ok "groff -man -ww -z $page: no warnings"
    else
        fail "groff -man -ww -z $page:"
        sed 's/^/    /' "$tmp/lint"
    fi
    if ! command -v man >/dev/null 2>&1; then
        skip "man -l $page renders" "man not installed (apt-get install man-db)"
    elif MANWIDTH=80 man -l "$page" >"$tmp/man.out" 2>"$tmp/man.err" && [ ! -s "$tmp/man.err" ] &&
        [ -s "$tmp/man.out" ]; then
        ok "man -l $page renders"
    else
        fail "man -l $page:"
        sed 's/^/    /' "$tmp/man.err"
    fi
done

# ---- mcrt.5 and mcrt.1: the names the code knows ----
# From the code's own tables, as tests/tools/words prints them: every block kind, key and keyword
# value of the scene language (the parser's tables) and every MTL statement must be in mcrt.5, and every sampler and image
# layer name (mcrt_names) in mcrt.1.
t5=$(terms man/mcrt.5)
words=$O/tests/words
if [ -x "$words" ] && "$words" >"$tmp/words" 2>&1 && grep -q '^block ' "$tmp/words"; then
    # shellcheck disable=SC2046 # word splitting of the lists is intended
    check_words "mcrt.5 documents every block kind, key and keyword value of the parser" "$t5" \
        $(awk '$1 == "block" || $1 == "key" || $1 == "value" { print $NF }' "$tmp/words" | sort -u)
    # shellcheck disable=SC2046
    check_words "mcrt.5 documents every MTL statement the reader knows" "$t5" \
        $(sed -n 's/^mtl //p' "$tmp/words" | sort -u)
    # shellcheck disable=SC2046
    check_words "mcrt.1 documents every sampler and image layer" "$(terms man/mcrt.1)" \
        $(sed -n 's/^\(sampler\|aov\) //p' "$tmp/words" | sort -u)
else
    fail "$words does not list the scene language's words (build the tests first)"
fi

# ---- mcrt.1 and --help: the options ----
options="-o --spp --threads --seed --integrator --stats --quiet --help --version"
t1=$(terms man/mcrt.1)
# shellcheck disable=SC2086
check_words "mcrt.1 documents every option" "$t1" $options
if [ -x "$MCRT" ]; then
    if "$MCRT" --help >"$tmp/help" 2>&1; then
        help=$(cat "$tmp/help")
        # shellcheck disable=SC2086
        check_words "mcrt --help shows every option" "$help" $options
        # The other way round: whatever --help offers, the manual explains.
        shown=$(grep -oE '(^|[][ 	,|])--?[a-z][-a-z]*' "$tmp/help" | sed 's/^[][ 	,|]*//' | sort -u)
        # shellcheck disable=SC2086
        check_words "mcrt.1 documents every option of mcrt --help" "$t1" $shown
    else
        fail "$MCRT --help exits with status $?"
    fi
else
    fail "$MCRT not built: cannot check --help and --version (run make first)"
fi

# ---- libmcrt.3: the API ----
# Every prototype of mcrt.h, one per line, blanks squeezed (declarations may span lines).
awk 'acc != "" { acc = acc " " $0; if (/;/) { print acc; acc = "" } next }
     /^[a-z][a-z_ *]*[ *]mcrt_[a-z_]+\(/ { if (/;/) print; else acc = $0 }' src/mcrt.h |
    sed -e 's/[[:space:]]\{1,\}/ /g' -e 's/( /(/g' >"$tmp/protos"
r3=$(render man/libmcrt.3)
flat3=$(printf '%s\n' "$r3" | tr '\n' ' ' | sed 's/[[:space:]]\{1,\}/ /g')
body3=$(printf '%s\n' "$r3" | sed -n '/^DESCRIPTION/,$p')
missing=""
n=0
while IFS= read -r p; do
    n=$((n + 1))
    case "$flat3" in
        *"$p"*) ;;
        *) missing="$missing
    $p" ;;
    esac
done <"$tmp/protos"
if [ "$n" -eq 0 ]; then
    fail "no prototypes found in src/mcrt.h"
elif [ -z "$missing" ]; then
    ok "libmcrt.3 SYNOPSIS has the prototype of every function in mcrt.h ($n)"
else
    fail "libmcrt.3 SYNOPSIS lacks or misstates these prototypes of mcrt.h:$missing"
fi
funcs=$(sed -e 's/(.*//' -e 's/.*[ *]//' "$tmp/protos")
# shellcheck disable=SC2086
check_words "libmcrt.3 describes every function" "$body3" $funcs
codes=$(grep -oE 'MCRT_[A-Z_]+' src/mcrt.h | grep -v '^MCRT_H$' | sort -u)
# shellcheck disable=SC2086
check_words "libmcrt.3 describes every status code and macro" "$body3" $codes
fields=$(awk '/^typedef struct mcrt_[a-z]+ \{/ { on = 1; next }
    /^\}/ { on = 0 }
    on {
        sub(/\/\*.*/, "")
        if (/\(\*/) { s = $0; sub(/.*\(\*/, "", s); sub(/\).*/, "", s); print s; next }
        if (!/;/) next
        s = $0; sub(/;.*/, "", s); n = split(s, a, ",")
        for (i = 1; i <= n; i++) { k = split(a[i], b, /[ \t*]+/); sub(/\[.*/, "", b[k]); print b[k] }
    }' src/mcrt.h)
# shellcheck disable=SC2086
check_words "libmcrt.3 describes every field of mcrt_options and mcrt_stats" "$body3" $fields

# ---- the integrators: every one of the library's table (mcrt --list integrator) is named by
# mcrt.1 (--integrator), mcrt.5 (integrator method), libmcrt.3 and mcrt.h's comment on the
# integrator option ----
if [ -x "$MCRT" ] && "$MCRT" --list integrator >"$tmp/integrators" 2>&1 && [ -s "$tmp/integrators" ]; then
    integrators=$(cut -f 1 "$tmp/integrators")
    # The comment above mcrt_options' integrator field, through the field's line.
    comment=$(awk '/^ *\/\*/ { c = "" } { c = c " " $0 } /const char \*integrator;/ { print c; exit }' src/mcrt.h)
    # shellcheck disable=SC2086
    check_words "mcrt.1 names every integrator" "$t1" $integrators
    # shellcheck disable=SC2086
    check_words "mcrt.5 names every integrator method" "$t5" $integrators
    # shellcheck disable=SC2086
    check_words "libmcrt.3 names every integrator" "$body3" $integrators
    # shellcheck disable=SC2086
    check_words "mcrt.h's comment on mcrt_options.integrator names every integrator" "$comment" $integrators
else
    fail "mcrt --list integrator lists nothing: $(head -n 1 "$tmp/integrators" 2>/dev/null)"
fi

# The EXAMPLES program, as a reader would copy it, compiles against the header.
printf '%s\n' "$r3" | awk '/^EXAMPLES/ { on = 1 } /^SEE ALSO/ { on = 0 }
    on && /^ *#include/ { code = 1 } on && /Build and run/ { code = 0 } code' |
    sed 's/^       //' >"$tmp/example.c"
if [ ! -s "$tmp/example.c" ]; then
    fail "libmcrt.3: no example program found under EXAMPLES"
elif LC_ALL=C grep -q '[^ -~]' "$tmp/example.c"; then
    fail "libmcrt.3: the example program is not plain ASCII (use \\- \\(aq \\e in roff):"
    LC_ALL=C grep -n '[^ -~]' "$tmp/example.c" | sed 's/^/    /'
elif $CC -std=c99 -Wall -Wextra -Wpedantic -Werror -Isrc -c "$tmp/example.c" -o "$tmp/example.o" \
    >"$tmp/cc" 2>&1; then
    ok "libmcrt.3: the example compiles (-std=c99 -Wall -Wextra -Wpedantic -Werror)"
else
    fail "libmcrt.3: the example does not compile:"
    sed 's/^/    /' "$tmp/cc"
fi

# ---- versions ----
version=$(sed -n 's/^#define MCRT_VERSION "\(.*\)"/\1/p' src/mcrt.h)
stale=""
for page in man/mcrt.1 man/mcrt.5 man/libmcrt.3; do
    grep -q "^\.TH .*\"mcrt $version\"" "$page" || stale="$stale $page"
done
if [ -z "$stale" ]; then ok "man pages are for mcrt $version"; else fail "not for mcrt $version:$stale"; fi
num=$(sed -n 's/^#define MCRT_VERSION_NUM \([0-9]*\)$/\1/p' src/mcrt.h)
want=$(echo "$version" | awk -F. '{ print $1 * 10000 + $2 * 100 + $3 }')
if [ -n "$num" ] && [ "$num" = "$want" ]; then
    ok "MCRT_VERSION_NUM $num is MCRT_VERSION $version"
else
    fail "MCRT_VERSION_NUM '$num' is not MCRT_VERSION $version (want $want)"
fi
if [ -x "$MCRT" ]; then
    if "$MCRT" --version 2>&1 | grep -qF "$version"; then
        ok "mcrt --version shows $version"
    else
        fail "mcrt --version does not show $version: $("$MCRT" --version 2>&1 | head -n 1)"
    fi
fi

# ---- README: the packages set-up installs (DEBS in the Makefile), listed as they are ----
debs=$(sed -n 's/^DEBS = //p' Makefile)
if [ -n "$debs" ] && tr '\n' ' ' <README.md | grep -qF "(\`$debs\`)"; then
    ok "README.md lists the set-up's packages: $debs"
else
    fail "README.md does not list the set-up's packages as (\`$debs\`)"
fi

# ---- scenes ----
for scene in scenes/*.mcrt; do
    name=$(basename "$scene" .mcrt)
    if grep -qF "scenes/$name.mcrt" README.md; then
        ok "README.md lists $scene"
    else
        fail "README.md does not list $scene"
    fi
    [ -x "$MCRT" ] || continue
    if "$MCRT" --quiet --spp 1 -o "$tmp/$name.pfm" "$scene" >"$tmp/run" 2>&1 && [ -s "$tmp/$name.pfm" ]; then
        ok "$scene renders"
    else
        fail "$scene does not render:"
        sed 's/^/    /' "$tmp/run"
    fi
done

# The files of scenes/vase.mcrt are what tests/tools/model_gen.c makes: the OBJ and MTL files
# byte for byte, the texture pixel for pixel (a PNG's bytes depend on the zlib that wrote it).
gen=$O/tests/model_gen
if [ -x "$gen" ] && mkdir "$tmp/model" && "$gen" "$tmp/model" && cmp -s "$tmp/model/vase.obj" scenes/vase.obj &&
    cmp -s "$tmp/model/vase.mtl" scenes/vase.mtl &&
    "$MCRT" diff --quiet --max-relmse 0 "$tmp/model/vase-glaze.png" scenes/vase-glaze.png; then
    ok "scenes/vase.obj, vase.mtl and vase-glaze.png are what model_gen makes"
else
    fail "scenes/vase.obj, vase.mtl and vase-glaze.png differ from what $gen makes"
fi

# The Cornell box's orientation: from the camera the red wall is on the left and the green one on
# the right, and they are lit (a light facing up would leave them black). Mean RGB of 5x5 pixels
# at mid-height, 40 pixels in from each side (on the side walls, clear of the blocks). Under the
# yellowish light (17 12 4), reflectances red 0.63/0.065 and green 0.14/0.45 give channel ratios
# of about 0.63*17/(0.065*12) = 14 (red R/G) and 0.45*12/(0.14*17) = 2.3 (green G/R); measured
# 13.9 and 2.2 at 4 spp. The thresholds 4 and 1.5 leave room for the noise of 25 pixels x 4
# samples; a mirrored image gives about 0.5 and 0.07.
if [ -x "$MCRT" ] && "$MCRT" --quiet --spp 4 -o "$tmp/cornell.pfm" scenes/cornell.mcrt >/dev/null 2>&1; then
    f=$tmp/cornell.pfm
    hdr=$(head -n 3 "$f" | wc -c)
    w=$(sed -n 2p "$f" | cut -d ' ' -f 1)
    h=$(sed -n 2p "$f" | cut -d ' ' -f 2)
    mean() { # mean R G B of the 5x5 pixels from column $1, row $2 (row 0 at the top)
        y=$2
        while [ "$y" -lt $(($2 + 5)) ]; do
            od -An -v -t f4 -j $((hdr + ((h - 1 - y) * w + $1) * 12)) -N 60 "$f"
            y=$((y + 1))
        done | tr -s ' \n' '\n\n' | grep . |
            awk '{ s[NR % 3] += $1 } END { printf "%g %g %g\n", s[1] / 25, s[2] / 25, s[0] / 25 }'
    }
    left=$(mean 40 254)
    right=$(mean $((w - 45)) 254)
    if echo "$left $right" | awk '{ exit !($1 > 0.02 && $1 > 4 * $2 && $5 > 0.02 && $5 > 1.5 * $4) }'; then
        ok "cornell.mcrt: red wall on the left (mean RGB $left), green on the right ($right)"
    else
        fail "cornell.mcrt: expected red on the left and green on the right, got left $left, right $right"
    fi
elif [ -x "$MCRT" ]; then
    fail "cornell.mcrt does not render to PFM"
fi

finish
