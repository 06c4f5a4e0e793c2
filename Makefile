# mcrt: a Monte Carlo path tracer in C99.
#
#   make            build build/mcrt and build/libmcrt.a (with whichever image libraries are present)
#   make run        set up (installs Debian packages when root), build, render scenes/cornell.mcrt
#   make test       set up, build and run every test; the last line is "N passed, N failed"
#   make check      the tests under AddressSanitizer + UndefinedBehaviorSanitizer (build-san/)
#   make bench      BVH and path-tracer throughput (not a test)
#   make install    PREFIX=/usr/local, DESTDIR honoured
#   V=1             show full commands

CC      ?= cc
O       ?= build
PREFIX  ?= /usr/local
OPT     ?= -O2 -g
SETUP   ?= 1

CSTD    = -std=c99 -D_POSIX_C_SOURCE=200809L
WARN    = -Wall -Wextra -Wpedantic -Wshadow -Wstrict-prototypes -Wmissing-prototypes \
          -Wold-style-definition -Wvla -Wformat=2
CFLAGS  += $(CSTD) $(WARN) $(OPT) -Isrc -MMD -MP
LDLIBS  = -lpthread -lm

# Optional image libraries, found by pkg-config. Their headers are seen only by src/io/.
PKG_CONFIG ?= pkg-config
HAVE_PNG := $(shell $(PKG_CONFIG) --exists libpng 2>/dev/null && echo 1)
HAVE_EXR := $(shell $(PKG_CONFIG) --exists OpenEXR 2>/dev/null && echo 1)
ifeq ($(HAVE_PNG),1)
IO_CFLAGS += -DMCRT_HAVE_PNG $(shell $(PKG_CONFIG) --cflags libpng)
IO_LIBS   += $(shell $(PKG_CONFIG) --libs libpng)
else
$(info mcrt: libpng not found by pkg-config: building without PNG (apt-get install libpng-dev))
endif
ifeq ($(HAVE_EXR),1)
# OpenEXR's C headers are not -Wpedantic clean under C99: include them as system headers.
IO_CFLAGS += -DMCRT_HAVE_EXR $(shell $(PKG_CONFIG) --cflags-only-I OpenEXR | sed 's/-I/-isystem /g')
IO_LIBS   += $(filter -L% -lOpenEXRCore%,$(shell $(PKG_CONFIG) --libs OpenEXR))
else
$(info mcrt: OpenEXR not found by pkg-config: building without EXR (apt-get install libopenexr-dev))
endif
LDLIBS := $(IO_LIBS) $(LDLIBS)

ifeq ($(V),1)
Q =
else
Q = @
endif

LIB_SRC  := $(filter-out src/cli/%,$(wildcard src/*/*.c))
CLI_SRC  := $(wildcard src/cli/*.c)
LIB_OBJ  := $(LIB_SRC:%.c=$(O)/obj/%.o)
CLI_OBJ  := $(CLI_SRC:%.c=$(O)/obj/%.o)
UNIT_SRC := $(wildcard tests/unit/test_*.c)
UNIT_BIN := $(UNIT_SRC:tests/unit/%.c=$(O)/tests/%)
TOOL_SRC := $(wildcard tests/tools/*.c)
TOOL_BIN := $(TOOL_SRC:tests/tools/%.c=$(O)/tests/%)

.PHONY: all run test check bench install uninstall clean setup
all: $(O)/mcrt $(O)/libmcrt.a

$(O)/obj/src/io/%.o: CFLAGS += $(IO_CFLAGS)
$(O)/obj/%.o: %.c
	@mkdir -p $(@D)
	@$(if $(Q),echo "  CC      $<")
	$(Q)$(CC) $(CFLAGS) -c $< -o $@

$(O)/libmcrt.a: $(LIB_OBJ)
	@$(if $(Q),echo "  AR      $@")
	$(Q)rm -f $@ && $(AR) rcs $@ $^

$(O)/mcrt: $(CLI_OBJ) $(O)/libmcrt.a
	@$(if $(Q),echo "  LD      $@")
	$(Q)$(CC) $(CFLAGS) $(LDFLAGS) -o $@ $(CLI_OBJ) $(O)/libmcrt.a $(LDLIBS)

$(O)/tests/%: tests/unit/%.c tests/t.h tests/prim_util.h $(O)/libmcrt.a
	@mkdir -p $(@D)
	@$(if $(Q),echo "  CC      $<")
	$(Q)$(CC) $(CFLAGS) -Itests -o $@ $< $(O)/libmcrt.a $(LDLIBS)

$(O)/tests/%: tests/tools/%.c $(O)/libmcrt.a
	@mkdir -p $(@D)
	@$(if $(Q),echo "  CC      $<")
	$(Q)$(CC) $(CFLAGS) -Itests -o $@ $< $(O)/libmcrt.a $(LDLIBS)

# Set-up for a fresh Debian machine: install what the build and tests need when root, otherwise
# print the exact command and stop. SETUP=0 skips it (for machines that are not Debian).
DEBS = pkgconf libpng-dev libopenexr-dev openexr groff-base
setup:
	@if [ "$(SETUP)" = 1 ] && command -v dpkg-query >/dev/null 2>&1; then \
	  missing=""; for p in $(DEBS); do \
	    dpkg-query -W -f='$${Status}' $$p 2>/dev/null | grep -q "ok installed" || missing="$$missing $$p"; \
	  done; \
	  if [ -n "$$missing" ]; then \
	    if [ "$$(id -u)" = 0 ]; then \
	      echo "mcrt: installing$$missing"; \
	      (apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq $$missing) >/dev/null \
	        || { echo "mcrt: apt-get install$$missing failed" >&2; exit 1; }; \
	    else \
	      echo "mcrt: missing Debian packages; run as root:  apt-get install$$missing" >&2; exit 1; \
	    fi; \
	  fi; \
	fi

# Recursive so that pkg-config is re-run after setup may have installed the libraries.
run: setup
	@$(MAKE) --no-print-directory all
	$(O)/mcrt scenes/cornell.mcrt -o cornell.png

test: setup
	@$(MAKE) --no-print-directory test-build
	@O=$(O) CC="$(CC)" LDFLAGS="$(LDFLAGS)" sh tests/run.sh

test-build: all $(UNIT_BIN) $(TOOL_BIN)

check:
	@$(MAKE) --no-print-directory O=build-san SETUP=0 \
	  OPT="-O1 -g -fsanitize=address,undefined -fno-omit-frame-pointer -fno-sanitize-recover=all" \
	  LDFLAGS="-fsanitize=address,undefined" test

bench: all $(O)/tests/bench $(O)/tests/bench_render
	$(O)/tests/bench
	$(O)/tests/bench_render

install: all
	install -d $(DESTDIR)$(PREFIX)/bin $(DESTDIR)$(PREFIX)/lib/pkgconfig $(DESTDIR)$(PREFIX)/include \
	  $(DESTDIR)$(PREFIX)/share/man/man1 $(DESTDIR)$(PREFIX)/share/man/man3 $(DESTDIR)$(PREFIX)/share/man/man5
	install -m 755 $(O)/mcrt $(DESTDIR)$(PREFIX)/bin/mcrt
	install -m 644 $(O)/libmcrt.a $(DESTDIR)$(PREFIX)/lib/libmcrt.a
	install -m 644 src/mcrt.h $(DESTDIR)$(PREFIX)/include/mcrt.h
	install -m 644 man/mcrt.1 $(DESTDIR)$(PREFIX)/share/man/man1/mcrt.1
	install -m 644 man/libmcrt.3 $(DESTDIR)$(PREFIX)/share/man/man3/libmcrt.3
	install -m 644 man/mcrt.5 $(DESTDIR)$(PREFIX)/share/man/man5/mcrt.5
	sed -e 's|@PREFIX@|$(PREFIX)|' -e 's|@VERSION@|$(shell sed -n 's/^#define MCRT_VERSION "\(.*\)"/\1/p' src/mcrt.h)|' \
	  -e 's|@LIBS_PRIVATE@|$(strip $(LDLIBS))|' \
	  src/mcrt.pc.in > $(DESTDIR)$(PREFIX)/lib/pkgconfig/mcrt.pc

uninstall:
	rm -f $(DESTDIR)$(PREFIX)/bin/mcrt $(DESTDIR)$(PREFIX)/lib/libmcrt.a $(DESTDIR)$(PREFIX)/include/mcrt.h \
	  $(DESTDIR)$(PREFIX)/lib/pkgconfig/mcrt.pc $(DESTDIR)$(PREFIX)/share/man/man1/mcrt.1 \
	  $(DESTDIR)$(PREFIX)/share/man/man3/libmcrt.3 $(DESTDIR)$(PREFIX)/share/man/man5/mcrt.5

clean:
	rm -rf $(O) build-san

-include $(LIB_OBJ:.o=.d) $(CLI_OBJ:.o=.d)
