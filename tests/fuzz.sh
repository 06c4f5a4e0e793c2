#!/bin/sh
# fuzz.sh: the fuzzers' findings as regression tests in `make test`. Builds each libFuzzer harness
# (tests/fuzz/fuzz_*.c) with tests/fuzz/replay.c instead of libFuzzer, using $CC, $LDFLAGS and
# $LDLIBS (the image readers need libpng and OpenEXR's; so `make check` replays under
# ASan/UBSan), and runs it on its seed corpus and on every input
# that once crashed it (tests/fuzz/crash_<target>/). A crash, sanitizer report or nonzero exit
# fails. Run from the repository root after the build; $O is the build folder.
. tests/harness.sh.inc
CC=${CC:-cc}
TMPDIR=$tmp
export TMPDIR
for target in scene obj mtl image; do
    bin=$tmp/replay_$target
    if ! $CC -std=c99 -D_POSIX_C_SOURCE=200809L -O1 -g -Isrc $LDFLAGS -o "$bin" tests/fuzz/replay.c \
        "tests/fuzz/fuzz_$target.c" "$O/libmcrt.a" ${LDLIBS:--lpthread -lm} 2>"$tmp/err"; then
        fail "$target" "harness does not build"
        head -n 20 "$tmp/err"
        continue
    fi
    for dir in "tests/fuzz/corpus_$target" "tests/fuzz/crash_$target"; do
        [ -d "$dir" ] || continue
        set -- "$dir"/*
        [ -e "$1" ] || continue
        if "$bin" "$@" >"$tmp/out" 2>&1; then
            ok "$dir: $(tail -n 1 "$tmp/out")"
        else
            fail "$dir" "exit status $?"
            tail -n 30 "$tmp/out"
        fi
    done
done
finish
