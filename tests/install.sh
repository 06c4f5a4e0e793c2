#!/bin/sh
# install.sh: a staged install (make install DESTDIR=... PREFIX=/usr) puts every file in place
# with no DESTDIR baked into mcrt.pc; the README's embedding example builds against the installed
# files alone, through pkg-config with a sysroot, and prints a finite pixel; make uninstall
# removes everything. Run from the repository root after the build; $O is the build folder.
# Prints "ok ..." or "FAIL ..." per check, then "N passed, N failed".
O=${O:-build}
CC=${CC:-cc}
# The build's own link flags (make check links the library with the sanitizers).
LDFLAGS=${LDFLAGS:-}
PKG_CONFIG=${PKG_CONFIG:-pkg-config}
passed=0
failed=0
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
root=$tmp/root

ok() { echo "ok $*"; passed=$((passed + 1)); }
fail() { echo "FAIL $*"; failed=$((failed + 1)); }
note() { echo "  note: $*"; }
finish() {
    echo "$passed passed, $failed failed"
    [ "$failed" -eq 0 ]
    exit
}

# -o: install what the build made, as it was configured (say, with the sanitizers of make check),
# never rebuilding it because this make's flags differ from those recorded in $O/config.mk.
if make -s --no-print-directory -o "$O/config.mk" install O="$O" DESTDIR="$root" PREFIX=/usr \
    >"$tmp/make" 2>&1; then
    ok "make install DESTDIR=\$tmp PREFIX=/usr"
else
    fail "make install DESTDIR=\$tmp PREFIX=/usr:"
    sed 's/^/    /' "$tmp/make"
    finish
fi

missing=""
for f in bin/mcrt lib/libmcrt.a include/mcrt.h lib/pkgconfig/mcrt.pc \
    share/man/man1/mcrt.1 share/man/man3/libmcrt.3 share/man/man5/mcrt.5; do
    [ -s "$root/usr/$f" ] || missing="$missing $f"
done
if [ -z "$missing" ]; then ok "installed: bin, lib, include, pkgconfig and the three man pages"; else fail "not installed:$missing"; fi
if [ -x "$root/usr/bin/mcrt" ] && "$root/usr/bin/mcrt" --version >/dev/null 2>&1; then
    ok "the installed mcrt runs (--version)"
else
    fail "the installed mcrt does not run --version"
fi

pc=$root/usr/lib/pkgconfig/mcrt.pc
if [ ! -f "$pc" ]; then
    fail "no mcrt.pc"
    finish
fi
if grep -qF "$root" "$pc"; then
    fail "mcrt.pc has DESTDIR baked in:"
    grep -nF "$root" "$pc" | sed 's/^/    /'
elif grep -qx 'prefix=/usr' "$pc"; then
    ok "mcrt.pc: prefix=/usr, no DESTDIR"
else
    fail "mcrt.pc: no line prefix=/usr"
fi

# pkg-config as a cross or staged build uses it: the sysroot is prepended to -I and -L.
pkgc() { PKG_CONFIG_SYSROOT_DIR=$root PKG_CONFIG_PATH=$root/usr/lib/pkgconfig "$PKG_CONFIG" "$@"; }
if ! flags=$(pkgc --static --cflags --libs mcrt 2>"$tmp/pc.err"); then
    fail "pkg-config --static --cflags --libs mcrt:"
    sed 's/^/    /' "$tmp/pc.err"
    finish
fi
note "pkg-config --static --cflags --libs mcrt: $flags"
inc=$root/usr/include
lib=$root/usr/lib
case " $flags " in *" -I$inc "*) has_inc=1 ;; *) has_inc=0 ;; esac
case " $flags " in *" -L$lib "*) has_lib=1 ;; *) has_lib=0 ;; esac
case $has_inc$has_lib in
    11)
        ok "pkg-config with PKG_CONFIG_SYSROOT_DIR gives -I$inc and -L$lib" ;;
    *)
        # pkgconf drops -I/usr/include as a system folder before adding the sysroot; build the
        # paths from the .pc variables instead, which is what a packager would do.
        pinc=$(pkgc --variable=includedir mcrt)
        plib=$(pkgc --variable=libdir mcrt)
        case "$pinc" in "$root"/*) ;; *) pinc=$root$pinc ;; esac
        case "$plib" in "$root"/*) ;; *) plib=$root$plib ;; esac
        if [ "$pinc" = "$inc" ] && [ "$plib" = "$lib" ]; then
            ok "mcrt.pc variables give includedir $inc and libdir $lib"
            note "pkg-config's sysroot rewriting did not give both -I and -L: using -I/-L from includedir/libdir"
            flags="-I$pinc -L$plib $(pkgc --static --libs-only-l --libs-only-other mcrt)"
        else
            fail "mcrt.pc: includedir $pinc, libdir $plib; expected $inc and $lib"
            finish
        fi ;;
esac

awk '/^```c$/ { on = 1; next } on && /^```$/ { exit } on' README.md >"$tmp/embed.c"
if [ ! -s "$tmp/embed.c" ]; then
    fail "README.md has no \`\`\`c block"
    finish
fi
# shellcheck disable=SC2086 # $flags is a list of compiler arguments
if $CC -std=c99 -Wall -Wextra -Wpedantic -Werror -o "$tmp/embed" "$tmp/embed.c" $flags $LDFLAGS >"$tmp/cc" 2>&1; then
    ok "README example builds against the installed files (-std=c99 -Wall -Wextra -Wpedantic -Werror)"
else
    fail "README example does not build:"
    sed 's/^/    /' "$tmp/cc"
    finish
fi
# It must have used the installed header, not one elsewhere on the system.
# shellcheck disable=SC2086
if $CC -std=c99 -M "$tmp/embed.c" $flags 2>/dev/null | tr ' \\' '\n\n' | grep -qx "$inc/mcrt.h"; then
    ok "README example includes $inc/mcrt.h"
else
    fail "README example did not include the installed mcrt.h ($inc/mcrt.h)"
fi

if (cd "$tmp" && ./embed) >"$tmp/out" 2>&1; then
    out=$(cat "$tmp/out")
    # Three numbers in plain decimal or exponent form: "nan" and "inf" do not match.
    if printf '%s\n' "$out" | awk -F': ' '
        $1 == "centre pixel" { n = split($2, v, " "); good = n == 3
            for (i = 1; i <= n; i++) good = good && v[i] ~ /^[0-9]*\.?[0-9]+([eE][-+]?[0-9]+)?$/ }
        END { exit !good }'; then
        ok "README example runs and prints a finite, non-negative pixel ($out)"
    else
        fail "README example printed no finite pixel: $out"
    fi
else
    fail "README example exits with status $?:"
    sed 's/^/    /' "$tmp/out"
fi

if make -s --no-print-directory uninstall O="$O" DESTDIR="$root" PREFIX=/usr >"$tmp/make" 2>&1 &&
    [ -z "$(find "$root" -type f)" ]; then
    ok "make uninstall removes every installed file"
else
    fail "make uninstall left:"
    find "$root" -type f | sed 's/^/    /'
    sed 's/^/    /' "$tmp/make"
fi
finish
