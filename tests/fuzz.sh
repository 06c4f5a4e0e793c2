#!/bin/sh
# fuzz.sh: the fuzzers' findings as regression tests in `make test`. Builds each libFuzzer harness
# (tests/fuzz/fuzz_*.c) with tests/fuzz/replay.c instead of libFuzzer, using $CC and $LDFLAGS
# (so `make check` replays under ASan/UBSan), and runs it on its seed corpus and on every input
# that once crashed it (tests/fuzz/crash_<target>/). A crash, sanitizer report or nonzero exit
# fails. Run from the repository root after the build; $O is the build folder.
O=${O:-build}
CC=${CC:-cc}
passed=0
failed=0
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
TMPDIR=$tmp
export TMPDIR
for target in scene obj; do
    bin=$tmp/replay_$target
    if ! $CC -std=c99 -D_POSIX_C_SOURCE=200809L -O1 -g -Isrc $LDFLAGS -o "$bin" tests/fuzz/replay.c \
        "tests/fuzz/fuzz_$target.c" "$O/libmcrt.a" -lpthread -lm 2>"$tmp/err"; then
        echo "FAIL $target: harness does not build"
        head -n 20 "$tmp/err"
        failed=$((failed + 1))
        continue
    fi
    for dir in "tests/fuzz/corpus_$target" "tests/fuzz/crash_$target"; do
        [ -d "$dir" ] || continue
        set -- "$dir"/*
        [ -e "$1" ] || continue
        if "$bin" "$@" >"$tmp/out" 2>&1; then
            echo "ok $dir: $(tail -n 1 "$tmp/out")"
            passed=$((passed + 1))
        else
            echo "FAIL $dir: exit status $?"
            tail -n 30 "$tmp/out"
            failed=$((failed + 1))
        fi
    done
done
echo "$passed passed, $failed failed"
[ "$failed" -eq 0 ]
