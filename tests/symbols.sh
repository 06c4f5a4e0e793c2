#!/bin/sh
# libmcrt.a is linked into other people's programs: every symbol it defines must carry the
# public prefix mcrt_ or the internal prefix mc_, so that it cannot clash with theirs (sanitizer
# builds add their own __asan/__odr_asan symbols, which are not ours).
# And the command may use only the public header (and its own headers under src/cli/).
O=${O:-build}
passed=0
failed=0
check() {
    if [ "$2" = ok ]; then passed=$((passed + 1)); echo "ok $1"; else failed=$((failed + 1)); echo "FAIL $1: $2"; fi
}
bad=$(nm -g --defined-only "$O/libmcrt.a" 2>/dev/null | awk 'NF == 3 { print $3 }' | grep -v -E '^(mcrt_|mc_|__odr_asan|__asan|__ubsan|__tsan)' | sort -u)
if [ ! -f "$O/libmcrt.a" ]; then check "library symbols" "no $O/libmcrt.a"
elif [ -n "$bad" ]; then check "library symbols" "unprefixed: $(echo $bad)"
else check "library symbols" ok; fi
inc=$(grep -h '^#include "' src/cli/*.c src/cli/*.h | grep -v -E '"(mcrt|cli/[a-z_]+)\.h"')
if [ -n "$inc" ]; then check "command uses only mcrt.h" "$inc"; else check "command uses only mcrt.h" ok; fi
echo "$passed passed, $failed failed"
[ "$failed" -eq 0 ]
