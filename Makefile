# mcrt: a Monte Carlo path tracer in C99.
#
#   make            build build/mcrt and build/libmcrt.a (with whichever image libraries are present)
#   make run        set up (installs Debian packages when root), build, render scenes/cornell.mcrt
#   make test       set up, build and run every test, JOBS at a time (default: the number of cores);
#                   the last line is "N passed, N failed, N skipped"
#   make check      the tests under AddressSanitizer + UndefinedBehaviorSanitizer (build-san/)
#   make tsan       a multi-threaded render of every scene under ThreadSanitizer (build-tsan/)
#   make fuzz       libFuzzer (clang) on the scene parser, the OBJ and MTL readers and the image readers, FUZZ_TIME s each (build-fuzz/)
#   make bench      BVH, path-tracer and photon-mapping throughput, mcrt-mpi's speed-up, and the
#                   efficiency against Mitsuba 3 (make bench-mitsuba alone; not a test)
#   make bench-error every sampler's error estimate against the truth on every scene, and the
#                   predicted time to an error against the time taken (minutes; not a test)
#   make crosscheck every exportable scene rendered by mcrt and Mitsuba 3, compared within their
#                   noise (needs pip install mitsuba; not part of make test)
#   make ref        regenerate the POV-Ray references in ref/ (needs povray; not part of make test)
#   make install    PREFIX=/usr/local, DESTDIR honoured
#   V=1             show full commands
#   WERROR=1        warnings are errors (as .ci/run builds; a plain make does not, so that a newer
#                   compiler's new warning does not stop a user's build)

CC      ?= cc
O       ?= build
PREFIX  ?= /usr/local
OPT     ?= -O2 -g
SETUP   ?= 1
WERROR  ?= 0

CSTD    = -std=c99 -D_POSIX_C_SOURCE=200809L
WARN    = -Wall -Wextra -Wpedantic -Wshadow -Wstrict-prototypes -Wmissing-prototypes \
          -Wold-style-definition -Wvla -Wformat=2 $(if $(filter 1,$(WERROR)),-Werror)
CFLAGS  += $(CSTD) $(WARN) $(OPT) -Isrc -MMD -MP
LDLIBS  = -lpthread -lm

# Optional image libraries, found by pkg-config. Their headers are seen only by src/io/.
PKG_CONFIG ?= pkg-config
HAVE_PNG := $(shell $(PKG_CONFIG) --exists libpng 2>/dev/null && echo 1)
HAVE_EXR := $(shell $(PKG_CONFIG) --exists OpenEXR 2>/dev/null && echo 1)
# MPI, for mcrt-mpi only (src/mpi/; the library never sees it): its compiler wrapper.
MPICC ?= mpicc
HAVE_MPI := $(shell command -v $(MPICC) >/dev/null 2>&1 && echo 1)
ifeq ($(HAVE_PNG),1)
IO_CFLAGS += -DMCRT_HAVE_PNG $(shell $(PKG_CONFIG) --cflags libpng)
IO_LIBS   += $(shell $(PKG_CONFIG) --libs libpng)
endif
ifeq ($(HAVE_EXR),1)
# OpenEXR's C headers are not -Wpedantic clean under C99: include them as system headers.
IO_CFLAGS += -DMCRT_HAVE_EXR $(shell $(PKG_CONFIG) --cflags-only-I OpenEXR | sed 's/-I/-isystem /g')
IO_LIBS   += $(filter -L% -lOpenEXRCore%,$(shell $(PKG_CONFIG) --libs OpenEXR))
endif
LDLIBS := $(IO_LIBS) $(LDLIBS)

# The configuration, recorded in $(O)/config.mk: the compiler, its flags and what pkg-config
# found. Every object and link depends on that file, so that a library installed since the last
# build (as by `make run` after `make`), or WERROR=1, rebuilds everything (seconds), and an
# unchanged configuration nothing. := fixes the text before target-specific flags (src/io/, bench)
# could vary it.
define CONFIG :=
CC = $(CC)
CFLAGS = $(CFLAGS)
LDFLAGS = $(LDFLAGS)
LDLIBS = $(LDLIBS)
HAVE_PNG = $(HAVE_PNG)
HAVE_EXR = $(HAVE_EXR)
HAVE_MPI = $(HAVE_MPI)
IO_CFLAGS = $(IO_CFLAGS)
endef

ifeq ($(V),1)
Q =
else
Q = @
endif

LIB_SRC  := $(filter-out src/cli/% src/mpi/%,$(wildcard src/*/*.c))
CLI_SRC  := $(wildcard src/cli/*.c)
LIB_OBJ  := $(LIB_SRC:%.c=$(O)/obj/%.o)
CLI_OBJ  := $(CLI_SRC:%.c=$(O)/obj/%.o)
UNIT_SRC := $(wildcard tests/unit/test_*.c)
BVH_VARIANTS := portable sse # test_bvh_VARIANT: see the rules below
NFOR_VARIANTS := sse # test_denoise_VARIANT
UNIT_BIN := $(UNIT_SRC:tests/unit/%.c=$(O)/tests/%) $(BVH_VARIANTS:%=$(O)/tests/test_bvh_%) \
            $(NFOR_VARIANTS:%=$(O)/tests/test_denoise_%)
TOOL_SRC := $(wildcard tests/tools/*.c)
TOOL_BIN := $(TOOL_SRC:tests/tools/%.c=$(O)/tests/%)

.PHONY: all run test test-build check tsan fuzz bench bench-mitsuba crosscheck bench-error bench-denoise denoise-figures install uninstall clean setup ref plots
all: $(O)/mcrt $(O)/libmcrt.a $(if $(HAVE_MPI),$(O)/mcrt-mpi)

# $(O)/config.mk, the CONFIG above, is written while this Makefile is read, and only when its text
# differs ($(call same,A,B): A and B are equal strings), so that only a change makes it newer than
# the objects. (A rule with a FORCE prerequisite would not do: make counts a target whose recipe
# ran as changed, and would rebuild everything every time.) It is written, and a missing library
# reported, only by a make that builds here: not by the make of `make run` or `make test`, which
# runs set-up (that may install the library) and then the build in a make of its own, nor by
# those of check, tsan and fuzz, which build in other folders.
CONFIG_MK = $(O)/config.mk
same = $(and $(findstring $(1),$(2)),$(findstring $(2),$(1)))
NO_BUILD_GOALS = run test check tsan fuzz setup clean uninstall
ifneq ($(filter-out $(NO_BUILD_GOALS),$(or $(MAKECMDGOALS),all)),)
ifeq ($(call same,$(file <$(CONFIG_MK)),$(CONFIG)),)
$(shell mkdir -p $(O))
$(file >$(CONFIG_MK),$(CONFIG))
endif
ifneq ($(HAVE_PNG),1)
$(info mcrt: libpng not found by pkg-config: building without PNG output (apt-get install pkgconf libpng-dev, then make again; make run and make test do it as root))
endif
ifneq ($(HAVE_MPI),1)
$(info mcrt: MPI not found ($(MPICC)): not building mcrt-mpi (apt-get install libopenmpi-dev openmpi-bin, then make again; make run and make test do it as root))
endif
ifneq ($(HAVE_EXR),1)
$(info mcrt: OpenEXR not found by pkg-config: building without EXR output (apt-get install pkgconf libopenexr-dev, then make again; make run and make test do it as root))
endif
endif

$(O)/obj/src/io/%.o: CFLAGS += $(IO_CFLAGS)
# The denoiser's loops run along rows of contiguous floats so that they vectorise; GCC's -O2
# vectorises only loops whose trip count it knows to be a multiple of the vector's width (its
# "very cheap" cost model), unless told to weigh each loop (compilers without the flag skip it).
# -fno-trapping-math lets it compute both sides of a select (NL-means skips a weight of 0 even
# for a value that is not finite): no result changes, as nothing reads the FP exception flags.
DENOISE_CFLAGS := $(shell $(CC) -Werror -fvect-cost-model=dynamic -x c -c /dev/null -o /dev/null \
                    2>/dev/null && echo -fvect-cost-model=dynamic) -fno-trapping-math
$(O)/obj/src/denoise/%.o: CFLAGS += $(DENOISE_CFLAGS)
$(O)/obj/%.o: %.c $(CONFIG_MK)
	@mkdir -p $(@D)
	@$(if $(Q),echo "  CC      $<")
	$(Q)$(CC) $(CFLAGS) -c $< -o $@

$(O)/libmcrt.a: $(LIB_OBJ)
	@$(if $(Q),echo "  AR      $@")
	$(Q)rm -f $@ && $(AR) rcs $@ $^

$(O)/mcrt: $(CLI_OBJ) $(O)/libmcrt.a $(CONFIG_MK)
	@$(if $(Q),echo "  LD      $@")
	$(Q)$(CC) $(CFLAGS) $(LDFLAGS) -o $@ $(CLI_OBJ) $(O)/libmcrt.a $(LDLIBS)

# mcrt-mpi: compiled and linked by MPI's wrapper, against the library like mcrt.
$(O)/obj/src/mpi/%.o: src/mpi/%.c $(CONFIG_MK)
	@mkdir -p $(@D)
	@$(if $(Q),echo "  MPICC   $<")
	$(Q)$(MPICC) $(CFLAGS) -c $< -o $@

MPI_OBJ := $(patsubst %.c,$(O)/obj/%.o,$(wildcard src/mpi/*.c)) $(O)/obj/src/cli/args.o
$(O)/mcrt-mpi: $(MPI_OBJ) $(O)/libmcrt.a $(CONFIG_MK)
	@$(if $(Q),echo "  LD      $@")
	$(Q)$(MPICC) $(CFLAGS) $(LDFLAGS) -o $@ $(MPI_OBJ) $(O)/libmcrt.a $(LDLIBS)

$(O)/tests/%: tests/unit/%.c tests/t.h tests/prim_util.h $(O)/libmcrt.a $(CONFIG_MK)
	@mkdir -p $(@D)
	@$(if $(Q),echo "  CC      $<")
	$(Q)$(CC) $(CFLAGS) -Itests -o $@ $< $(O)/libmcrt.a $(LDLIBS)

# The BVH tests again with the node tests the SIMD build does not use on this machine, each from
# src/geom/bvh.c linked ahead of the library: the portable C99 one, and SSE (which AVX machines
# pass over at run time).
BVH_VARIANT_FLAGS_portable = -DMCRT_BVH_PORTABLE
BVH_VARIANT_FLAGS_sse = -DMCRT_BVH_NO_AVX
$(BVH_VARIANTS:%=$(O)/obj/bvh_%.o): $(O)/obj/bvh_%.o: src/geom/bvh.c $(CONFIG_MK)
	@mkdir -p $(@D)
	@$(if $(Q),echo "  CC      $< ($*)")
	$(Q)$(CC) $(CFLAGS) $(BVH_VARIANT_FLAGS_$*) -c $< -o $@

$(BVH_VARIANTS:%=$(O)/tests/test_bvh_%): $(O)/tests/test_bvh_%: tests/unit/test_bvh.c tests/t.h tests/prim_util.h $(O)/obj/bvh_%.o $(O)/libmcrt.a $(CONFIG_MK)
	@mkdir -p $(@D)
	@$(if $(Q),echo "  CC      $< ($* BVH)")
	$(Q)$(CC) $(CFLAGS) -Itests -o $@ $< $(O)/obj/bvh_$*.o $(O)/libmcrt.a $(LDLIBS)

# The denoiser's tests again with its SSE2 copy, which AVX2 machines pass over at run time; they
# also write the result, which tests/denoise.sh compares with the AVX2 copy's (the same bits).
NFOR_VARIANT_FLAGS_sse = -DMCRT_NFOR_NO_AVX
$(NFOR_VARIANTS:%=$(O)/obj/nfor_%.o): $(O)/obj/nfor_%.o: src/denoise/nfor.c $(CONFIG_MK)
	@mkdir -p $(@D)
	@$(if $(Q),echo "  CC      $< ($*)")
	$(Q)$(CC) $(CFLAGS) $(NFOR_VARIANT_FLAGS_$*) -c $< -o $@

$(NFOR_VARIANTS:%=$(O)/tests/test_denoise_%): $(O)/tests/test_denoise_%: tests/unit/test_denoise.c tests/t.h $(O)/obj/nfor_%.o $(O)/libmcrt.a $(CONFIG_MK)
	@mkdir -p $(@D)
	@$(if $(Q),echo "  CC      $< ($* denoiser)")
	$(Q)$(CC) $(CFLAGS) -Itests -o $@ $< $(O)/obj/nfor_$*.o $(O)/libmcrt.a $(LDLIBS)

$(O)/tests/%: tests/tools/%.c $(O)/libmcrt.a $(CONFIG_MK)
	@mkdir -p $(@D)
	@$(if $(Q),echo "  CC      $<")
	$(Q)$(CC) $(CFLAGS) -Itests -o $@ $< $(O)/libmcrt.a $(LDLIBS)

# Set-up for a fresh Debian machine: install what the build and tests need when root, otherwise
# print the exact command and stop. SETUP=0 skips it (for machines that are not Debian).
# pkgconf finds the libraries; libpng-dev and libopenexr-dev are the PNG and EXR output; openexr
# has exrheader and exrmaketiled, which read back what mcrt writes; groff-base lints the manuals
# and man-db's man shows them (the README's `man -l`). The tests that need what is left out
# (python3, gnuplot) count as skipped. The README lists the same packages.
DEBS = pkgconf libpng-dev libopenexr-dev openexr groff-base man-db libopenmpi-dev openmpi-bin
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
	@O=$(O) CC="$(CC)" LDFLAGS="$(LDFLAGS)" LDLIBS="$(LDLIBS)" JOBS="$(JOBS)" sh tests/run.sh

test-build: all $(UNIT_BIN) $(TOOL_BIN)

# POV-Ray references (needs povray; never part of make test): ref/NAME.pov and ref/NAME.exr for
# every tests/pov/NAME.mcrt, rendered with the flags `mcrt pov` pins in each file. CASES=... limits.
ref: all $(O)/tests/exr_average
	@O=$(O) sh tests/tools/pov_ref.sh

# Every scene of scenes/, tests/crosscheck/ and bench-mitsuba's generated ones that `mcrt mitsuba`
# exports, rendered by mcrt and by Mitsuba 3 and compared within both renders' noise (needs
# `pip install mitsuba`; never part of make test). SPP, RENDERS, SHRINK, CASES=...: see tests/tools/crosscheck.sh.
crosscheck: all $(O)/tests/bench_scenes
	@mkdir -p $(O)/bench/scenes && $(O)/tests/bench_scenes $(O)/bench/scenes
	@O=$(O) sh tests/tools/crosscheck.sh

check:
	@$(MAKE) --no-print-directory O=build-san SETUP=0 \
	  OPT="-O1 -g -fsanitize=address,undefined -fno-omit-frame-pointer -fno-sanitize-recover=all" \
	  LDFLAGS="-fsanitize=address,undefined" test

# ThreadSanitizer: tests/stiff/tsan.sh renders every scene with 4 threads and runs test_tiles (the
# progress callback across threads) (TSan needs -O1+ and no ASan).
tsan:
	@$(MAKE) --no-print-directory O=build-tsan SETUP=0 OPT="-O1 -g -fsanitize=thread" \
	  LDFLAGS="-fsanitize=thread" all build-tsan/tests/test_tiles
	@O=build-tsan sh tests/stiff/tsan.sh

# libFuzzer harnesses (tests/fuzz/fuzz_*.c), run in parallel for FUZZ_TIME seconds each, starting
# from the seed corpus in tests/fuzz/corpus_*/; new inputs and crashes go to build-fuzz/.
# A crashing input belongs in tests/fuzz/crash_*/ (replayed by tests/fuzz.sh in make test).
FUZZ_TIME ?= 600
FUZZ_SAN   = -fsanitize=address,undefined -fno-sanitize-recover=all -fno-omit-frame-pointer
fuzz:
	@$(MAKE) --no-print-directory O=build-fuzz SETUP=0 CC=clang OPT="-O1 -g -fsanitize=fuzzer-no-link $(FUZZ_SAN)" \
	  LDFLAGS="$(FUZZ_SAN)" build-fuzz/fuzz/fuzz_scene build-fuzz/fuzz/fuzz_obj build-fuzz/fuzz/fuzz_mtl \
	  build-fuzz/fuzz/fuzz_image
	@mkdir -p build-fuzz/corpus_scene build-fuzz/corpus_obj build-fuzz/corpus_mtl build-fuzz/corpus_image
	build-fuzz/fuzz/fuzz_scene -max_total_time=$(FUZZ_TIME) -artifact_prefix=build-fuzz/scene- \
	  build-fuzz/corpus_scene tests/fuzz/corpus_scene > build-fuzz/fuzz_scene.log 2>&1 & p1=$$!; \
	build-fuzz/fuzz/fuzz_mtl -max_total_time=$(FUZZ_TIME) -artifact_prefix=build-fuzz/mtl- \
	  build-fuzz/corpus_mtl tests/fuzz/corpus_mtl > build-fuzz/fuzz_mtl.log 2>&1 & p3=$$!; \
	build-fuzz/fuzz/fuzz_image -max_total_time=$(FUZZ_TIME) -artifact_prefix=build-fuzz/image- \
	  build-fuzz/corpus_image tests/fuzz/corpus_image > build-fuzz/fuzz_image.log 2>&1 & p4=$$!; \
	build-fuzz/fuzz/fuzz_obj -max_total_time=$(FUZZ_TIME) -artifact_prefix=build-fuzz/obj- \
	  build-fuzz/corpus_obj tests/fuzz/corpus_obj > build-fuzz/fuzz_obj.log 2>&1; s2=$$?; \
	wait $$p1; s1=$$?; wait $$p3; s3=$$?; wait $$p4; s4=$$?; \
	tail -n 3 build-fuzz/fuzz_scene.log build-fuzz/fuzz_obj.log build-fuzz/fuzz_mtl.log \
	  build-fuzz/fuzz_image.log; \
	[ $$s1 = 0 ] && [ $$s2 = 0 ] && [ $$s3 = 0 ] && [ $$s4 = 0 ]

$(O)/fuzz/%: tests/fuzz/%.c $(O)/libmcrt.a $(CONFIG_MK)
	@mkdir -p $(@D)
	@$(if $(Q),echo "  CC      $<")
	$(Q)$(CC) $(CFLAGS) -fsanitize=fuzzer $(LDFLAGS) -o $@ $< $(O)/libmcrt.a $(LDLIBS)

# Debian's libembree-dev has no pkg-config file: when its header is there, the benchmark (only it;
# the library never links Embree) also traces every ray set with Embree 3 for comparison.
ifneq ($(wildcard /usr/include/embree3/rtcore.h),)
$(O)/tests/bench: CFLAGS += -DMCRT_HAVE_EMBREE
$(O)/tests/bench: LDLIBS += -lembree3
endif
bench: all $(O)/tests/bench $(O)/tests/bench_render $(O)/tests/bench_sppm $(O)/tests/bench_obj
	$(O)/tests/bench
	$(O)/tests/bench_obj
	$(O)/tests/bench_render
	$(O)/tests/bench_sppm
	MCRT=$(O)/mcrt sh tests/tools/mpi_bench.sh
	@$(MAKE) --no-print-directory bench-mitsuba

# The efficiency against Mitsuba 3 (issue 19) on four scenes: the Cornell box, scenes/glossy-floor
# (a small light beside a sky) and two that tests/tools/bench_scenes.c writes into $(O)/bench/scenes,
# too large for scenes/: 10,000 emitting triangles, and a 1,000,000-triangle terrain. Its
# references (1024 spp each, minutes) are kept in $(O)/bench.
BENCH_SCENES = scenes/cornell.mcrt scenes/glossy-floor.mcrt $(O)/bench/scenes/many-lights.mcrt \
               $(O)/bench/scenes/terrain.mcrt
bench-mitsuba: all $(O)/tests/bench_scenes
	@mkdir -p $(O)/bench/scenes && $(O)/tests/bench_scenes $(O)/bench/scenes
	@if command -v python3 >/dev/null 2>&1; then \
	  python3 tests/tools/mitsuba_bench.py $(O)/mcrt --cache $(O)/bench $(BENCH_SCENES:%=--scene %); \
	else echo "mitsuba_bench: no python3, so no efficiency ratio against Mitsuba 3 (then: pip install mitsuba)"; fi

# Estimated over true relMSE for every sampler at 16, 64 and 256 spp on every scene, and the
# predicted time to a target error against the time taken (issue 14).
bench-error: all
	MCRT=$(O)/mcrt sh tests/tools/error_bench.sh
	MCRT=$(O)/mcrt sh tests/tools/predict_bench.sh

# The denoiser's error reduction at 16 and 64 spp, its own error estimate and its time (issue 16).
bench-denoise: all $(O)/tests/exr_average
	MCRT=$(O)/mcrt EXR_AVERAGE=$(O)/tests/exr_average sh tests/tools/denoise_bench.sh

# The README's denoiser figures, its convergence plot and crops of scenes/cornell.mcrt, into
# $(O)/figures (tests/tools/denoise_figures.sh; the copies in docs/images come from it). Several
# minutes: the reference is a 4096 spp render. Not a test.
denoise-figures: all $(O)/tests/crops
	O=$(O) sh tests/tools/denoise_figures.sh

# Convergence plots (relMSE against seconds, three samplers) for every scene, into $(O)/plots:
# mcrt converge, gnuplot. Several minutes: each reference is a 256 spp render. Not a test.
plots: all
	mkdir -p $(O)/plots
	for s in scenes/*.mcrt; do \
	  $(O)/mcrt converge --quiet --spp 1,4,16 --compare sampler=random,stratified,sobol \
	    -o $(O)/plots $$s || exit 1; \
	done

install: all
	install -d $(DESTDIR)$(PREFIX)/bin $(DESTDIR)$(PREFIX)/lib/pkgconfig $(DESTDIR)$(PREFIX)/include \
	  $(DESTDIR)$(PREFIX)/share/man/man1 $(DESTDIR)$(PREFIX)/share/man/man3 $(DESTDIR)$(PREFIX)/share/man/man5
	install -m 755 $(O)/mcrt $(DESTDIR)$(PREFIX)/bin/mcrt
	$(if $(HAVE_MPI),install -m 755 $(O)/mcrt-mpi $(DESTDIR)$(PREFIX)/bin/mcrt-mpi)
	install -m 644 $(O)/libmcrt.a $(DESTDIR)$(PREFIX)/lib/libmcrt.a
	install -m 644 src/mcrt.h $(DESTDIR)$(PREFIX)/include/mcrt.h
	install -m 644 man/mcrt.1 $(DESTDIR)$(PREFIX)/share/man/man1/mcrt.1
	install -m 644 man/libmcrt.3 $(DESTDIR)$(PREFIX)/share/man/man3/libmcrt.3
	install -m 644 man/mcrt.5 $(DESTDIR)$(PREFIX)/share/man/man5/mcrt.5
	sed -e 's|@PREFIX@|$(PREFIX)|' -e 's|@VERSION@|$(shell sed -n 's/^#define MCRT_VERSION "\(.*\)"/\1/p' src/mcrt.h)|' \
	  -e 's|@LIBS_PRIVATE@|$(strip $(LDLIBS))|' \
	  src/mcrt.pc.in > $(DESTDIR)$(PREFIX)/lib/pkgconfig/mcrt.pc

uninstall:
	rm -f $(DESTDIR)$(PREFIX)/bin/mcrt $(DESTDIR)$(PREFIX)/bin/mcrt-mpi $(DESTDIR)$(PREFIX)/lib/libmcrt.a $(DESTDIR)$(PREFIX)/include/mcrt.h \
	  $(DESTDIR)$(PREFIX)/lib/pkgconfig/mcrt.pc $(DESTDIR)$(PREFIX)/share/man/man1/mcrt.1 \
	  $(DESTDIR)$(PREFIX)/share/man/man3/libmcrt.3 $(DESTDIR)$(PREFIX)/share/man/man5/mcrt.5

clean:
	rm -rf $(O) build-san build-tsan build-fuzz

-include $(LIB_OBJ:.o=.d) $(CLI_OBJ:.o=.d)
-include $(BVH_VARIANTS:%=$(O)/obj/bvh_%.d) $(NFOR_VARIANTS:%=$(O)/obj/nfor_%.d)
