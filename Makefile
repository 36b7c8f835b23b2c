# shlab — build, test, report.  See README.md.
#   make            build build/shlab, build/libshlab.a, build/libshlab.so
#   make check      build and run every test (unit tests with Check, CLI tests)
#   make check SANITIZE=1   the same, built with -fsanitize=address,undefined
#   make report     build, run every experiment, write reports/
#   make bench-count  instructions per rotation of every method (valgrind)
#   make probes     extract Blender's eight CC0 HDR world probes into data/probes/
#   make models     copy the real test meshes (assimp-testmodels) into data/models/
#   make report SCENES=full   also the scene experiments' full study (kept parts full/)
#   make report EXPERIMENTS="a b"   run only these experiments (docs/experiments.md)
#   make plots [EXPERIMENTS=...]    re-render the plots from the committed data
#   make install PREFIX=/usr/local
#   make deps       install missing Debian packages (as root) or print the command

PREFIX   ?= /usr/local
SANITIZE ?= 0
CC       ?= cc

ifeq ($(SANITIZE),1)
BUILD    ?= build/san
SANFLAGS := -fsanitize=address,undefined -fno-omit-frame-pointer -fno-sanitize-recover=undefined
OPT      := -O1 -g
else ifeq ($(SANITIZE),fuzz)
# make fuzz: clang's libFuzzer, with ASan/UBSan (Debian clang, libclang-rt-14-dev)
BUILD    ?= build/libfuzzer
SANFLAGS := -fsanitize=fuzzer-no-link,address,undefined -fno-omit-frame-pointer \
            -fno-sanitize-recover=undefined
OPT      := -O1 -g
CC       := clang
CXX      := clang++
else
BUILD    ?= build
SANFLAGS :=
OPT      := -O2 -g
endif

PKGS     := gsl OpenEXR jansson
# scenes (src/scene/): assimp and libpng by pkg-config, Embree 3 (no .pc file in Debian) by name
PKGS     += assimp libpng
PKG_CFLAGS = $(shell pkg-config --cflags $(PKGS) 2>/dev/null)
PKG_LIBS   = $(shell pkg-config --libs $(PKGS) 2>/dev/null)
CHECK_LIBS = $(shell pkg-config --libs check 2>/dev/null)

CFLAGS   += -std=c11 -D_DEFAULT_SOURCE -D_POSIX_C_SOURCE=200809L $(OPT) -Wall -Wextra \
            -Wno-unused-parameter -fPIC $(SANFLAGS) $(PKG_CFLAGS) -Isrc -MMD -MP
LDLIBS   += $(PKG_LIBS) -lembree3 -lpthread -lmpfr -lgmp -lstdc++ -lm
CXX      ?= c++
CXXFLAGS += -std=c++14 $(OPT) -Wall -Wextra -Wno-unused-parameter -fPIC $(SANFLAGS) $(PKG_CFLAGS) \
            -Isrc -MMD -MP

# src/ is grouped by concept, one folder each (README "Layout"): the library is
# every src/<concept>/*.c except src/cli/ (the command-line tool).
LIB_DIRS := core basis io project rotate taylor scale measure
LIB_DIRS += scene
LIB_SRC  := $(sort $(foreach d,$(LIB_DIRS),$(wildcard src/$(d)/*.c)))
# C++ sources of the library (io/exr_cxx.cpp: OpenEXR's C++ reader for DWAA/DWAB)
LIB_CXX  := $(sort $(foreach d,$(LIB_DIRS),$(wildcard src/$(d)/*.cpp)))
# src/lab/: the workbench around the library (timing engine, shards, the
# planner's timed choice): libshlab_lab.a, used by the tool, experiments and
# tests, not installed.
LAB_SRC  := $(sort $(wildcard src/lab/*.c))
LAB_OBJ  := $(LAB_SRC:src/%.c=$(BUILD)/obj/%.o)
LAB_LIB  := $(BUILD)/libshlab_lab.a
CLI_SRC  := $(sort $(wildcard src/cli/*.c))
TEST_SRC := $(sort $(wildcard tests/*/test_*.c))
# src/*/rot_*.c are precision-generic rotation kernels (rotate/rot_real.h):
# compiled once as double (x.o) and once as float (x_f.o, -DSH_REAL_FLOAT).
ROTK_SRC := $(sort $(foreach d,$(LIB_DIRS),$(wildcard src/$(d)/rot_*.c)))
LIB_OBJ  := $(LIB_SRC:src/%.c=$(BUILD)/obj/%.o) $(ROTK_SRC:src/%.c=$(BUILD)/obj/%_f.o) \
            $(LIB_CXX:src/%.cpp=$(BUILD)/obj/%.o)
# Loops marked `#pragma omp simd` in the kernels are vectorised at -O2
# (OpenMP's simd directive only: no OpenMP runtime is linked).
CFLAGS   += -fopenmp-simd
# The unrolled kernels (src/rotate/rot_fast.c, rot_simd.h) once more per
# instruction set on x86-64, each object with its own flags (chosen at run
# time by the plan: README "Rotation speed"): avx2, avx512 = one lane with
# AVX2 + FMA, or with AVX-512's 32 registers (fewer spills); sse2v/avx2v/
# avx512v = SIMD lanes of 16/32/64 bytes for batches.
# -ffp-contract=fast lets the compiler fuse a*b+c into FMA there (-std=c11
# alone turns contraction off, so the other objects never fuse).
ifneq ($(filter x86_64% amd64%,$(shell $(CC) -dumpmachine)),)
FAST_VARIANTS := avx2 avx512 sse2v avx2v avx512v
endif
FAST_FLAGS_avx2    := -DSHK_VARIANT=avx2 -mavx2 -mfma -ffp-contract=fast
FAST_FLAGS_avx512  := -DSHK_VARIANT=avx512 -mavx512f -mavx512vl -mfma -ffp-contract=fast
# (-Wno-psabi: the float objects hold the rotation's lanes in double, twice
# the native width, only in static functions, so no ABI is exposed.)
FAST_FLAGS_sse2v   := -DSHK_VARIANT=sse2v -DSHK_VBYTES=16 -Wno-psabi
FAST_FLAGS_avx2v   := -DSHK_VARIANT=avx2v -DSHK_VBYTES=32 -mavx2 -mfma -ffp-contract=fast -Wno-psabi
FAST_FLAGS_avx512v := -DSHK_VARIANT=avx512v -DSHK_VBYTES=64 -mavx512f -mfma -ffp-contract=fast -Wno-psabi
# rot_halfpi.c passes its 32-byte vector type between static functions only,
# so GCC's note on that ABI (-Wpsabi) concerns no interface: silenced.
$(BUILD)/obj/rotate/rot_halfpi.o $(BUILD)/obj/rotate/rot_halfpi_f.o: CFLAGS += -Wno-psabi
FAST_OBJ_D := $(FAST_VARIANTS:%=$(BUILD)/obj/rotate/rot_fast_%.o)
FAST_OBJ_F := $(FAST_VARIANTS:%=$(BUILD)/obj/rotate/rot_fast_%_f.o)
LIB_OBJ  += $(FAST_OBJ_D) $(FAST_OBJ_F)
ifeq ($(SANITIZE),fuzz)
# clang with UBSan takes most of an hour on the unrolled rotation kernels at
# -O1 (and seconds at -O0): they are built at -O0 for fuzzing
$(ROTK_SRC:src/%.c=$(BUILD)/obj/%.o) $(ROTK_SRC:src/%.c=$(BUILD)/obj/%_f.o) $(FAST_OBJ_D) $(FAST_OBJ_F): OPT := -O0 -g
endif
CLI_OBJ  := $(CLI_SRC:src/cli/%.c=$(BUILD)/obj/cli/%.o)
PUB_HDR  := src/shlab.h $(wildcard src/shlab/*.h)
# tests/<concept>/test_x.c (grouped like src/) -> $(BUILD)/tests/test_x
TEST_BIN := $(addprefix $(BUILD)/tests/,$(notdir $(TEST_SRC:.c=)))
vpath test_%.c $(sort $(dir $(TEST_SRC)))
# fuzz harnesses (tests/fuzz/fuzz_<h>.c); make check replays their corpora
FUZZ_HARNESS := exr fixture candidate coeffs light rotation mesh merge
FUZZ_REPLAY  := $(FUZZ_HARNESS:%=$(BUILD)/fuzz/replay_%)
REV      := $(shell git rev-parse --short=12 HEAD 2>/dev/null || echo unknown)$(shell git diff --quiet HEAD 2>/dev/null || echo -dirty)

# ---- sht: fast spherical harmonic transforms and the libsharp peer (begin) ----
# FFTW3 for the φ transforms, OpenMP across rings and m (src/project/sht*.c).
# The Legendre kernels (src/project/sht_kern.c) are compiled once more per x86
# instruction set; sht.c picks the widest one the CPU runs.  libsharp, when
# installed, is a peer (oracle in tests, yardstick in `shlab bench --peers`),
# linked into the CLI and its tests only, never into libshlab.
PKGS     += fftw3
CFLAGS   += -fopenmp
LDLIBS   += -fopenmp
.DEFAULT_GOAL := all
SHT_KFLAGS := -O3 -ffp-contract=fast
ifneq ($(filter x86_64%,$(shell $(CC) -dumpmachine)),)
CFLAGS   += -DSHLAB_SHT_X86
LIB_OBJ  += $(BUILD)/obj/project/sht_kern_avx2.o $(BUILD)/obj/project/sht_kern_avx512.o
endif
$(BUILD)/obj/project/sht_kern.o $(BUILD)/obj/project/sht.o: CFLAGS += -O3
$(BUILD)/obj/project/sht_kern_avx2.o: src/project/sht_kern.c
	@mkdir -p $(dir $@)
	$(CC) $(CFLAGS) $(SHT_KFLAGS) -mavx2 -mfma -DSHT_KERN_AVX2 -c $< -o $@
$(BUILD)/obj/project/sht_kern_avx512.o: src/project/sht_kern.c
	@mkdir -p $(dir $@)
	$(CC) $(CFLAGS) $(SHT_KFLAGS) -mavx512f -mfma -DSHT_KERN_AVX512 -c $< -o $@
# libsharp peer: src/measure/peers/peer_sharp.c (stubs that say so without libsharp)
HAVE_SHARP := $(shell pkg-config --exists libsharp 2>/dev/null && echo 1)
PEER_SHARP_OBJ := $(BUILD)/obj/measure/peers/peer_sharp.o
ifeq ($(HAVE_SHARP),1)
SHARP_CFLAGS := -DSHLAB_HAVE_SHARP $(shell pkg-config --cflags libsharp)
SHARP_LIBS := $(shell pkg-config --libs libsharp)
endif
$(PEER_SHARP_OBJ): CFLAGS += $(SHARP_CFLAGS)
CLI_OBJ  += $(PEER_SHARP_OBJ)
$(BUILD)/shlab: LDLIBS += $(SHARP_LIBS)
$(BUILD)/tests/test_sht_sharp: tests/project/test_sht_sharp.c tests/testutil.h $(PEER_SHARP_OBJ) $(LAB_LIB) $(BUILD)/libshlab.a
	@mkdir -p $(dir $@)
	$(CC) $(CFLAGS) -Itests -o $@ $< $(PEER_SHARP_OBJ) $(LAB_LIB) $(BUILD)/libshlab.a $(CHECK_LIBS) $(LDLIBS) $(SHARP_LIBS)
.PHONY: bench-peers
bench-peers:: all
	$(BUILD)/shlab bench --peers
# ---- sht (end) ----
# ---- shaders: Vulkan compute (src/lab/vk_compute.c, shader.c) ----
# With the Vulkan loader and shaderc (Debian: libvulkan-dev, libshaderc-dev;
# mesa-vulkan-drivers gives lavapipe, a CPU device), `verify --shader` and
# `bench --shader` run; without them they say so.  Only the lab (CLI, tests,
# experiments) uses them: linked as needed, libshlab never depends on them.
HAVE_VULKAN := $(shell pkg-config --exists vulkan shaderc 2>/dev/null && echo 1)
ifeq ($(HAVE_VULKAN),1)
$(BUILD)/obj/lab/vk_compute.o $(BUILD)/obj/lab/shader.o: CFLAGS += -DSHLAB_HAVE_VULKAN
# Debian's libshaderc.so.1 lacks its glslang dependency (and crashes when
# given the system's): the combined static archive is linked with glslang's
# and SPIRV-Tools' static libraries, where the shader code is used.
SHADERC_LIBS := -l:libshaderc_combined.a -Wl,--start-group -lglslang -lMachineIndependent -lGenericCodeGen \
  -lOSDependent -lOGLCompiler -lHLSL -lSPIRV -lSPIRV-Tools-opt -lSPIRV-Tools -Wl,--end-group
LDLIBS   += -Wl,--push-state,--as-needed $(SHADERC_LIBS) $(shell pkg-config --libs vulkan) -Wl,--pop-state
endif
# ---- shaders (end) ----

# Builds use every core: GNU make 4.3 honours a -j set here.  Only for the
# goals that build and test (a command line's own -j wins); `make report`
# stays serial, since its experiments time things.
ifeq ($(filter -j%,$(MAKEFLAGS)),)
ifeq ($(filter-out all check fuzz fuzz-build install,$(or $(MAKECMDGOALS),all)),)
MAKEFLAGS += -j$(shell nproc 2>/dev/null || echo 1)
endif
endif

.PHONY: all deps deps-quiet check report examples plots list-experiments experiments probes install clean man FORCE regen bench-count fuzz fuzz-build models
all: deps-quiet $(BUILD)/shlab $(BUILD)/libshlab.a $(BUILD)/libshlab.so

# ---- dependencies ---------------------------------------------------------
deps:
	@tools/deps.sh
deps-quiet:
	@tools/deps.sh --quiet

# ---- library and CLI --------------------------------------------------------
# Header dependencies come from the compiler (-MMD -MP, the .d files).
$(BUILD)/obj/%.o: src/%.c
	@mkdir -p $(dir $@)
	$(CC) $(CFLAGS) -c $< -o $@

$(BUILD)/obj/%.o: src/%.cpp
	@mkdir -p $(dir $@)
	$(CXX) $(CXXFLAGS) -c $< -o $@

$(BUILD)/obj/%_f.o: src/%.c
	@mkdir -p $(dir $@)
	$(CC) $(CFLAGS) -DSH_REAL_FLOAT -c $< -o $@

$(FAST_OBJ_D): $(BUILD)/obj/rotate/rot_fast_%.o: src/rotate/rot_fast.c
	@mkdir -p $(dir $@)
	$(CC) $(CFLAGS) $(FAST_FLAGS_$*) -c $< -o $@

$(FAST_OBJ_F): $(BUILD)/obj/rotate/rot_fast_%_f.o: src/rotate/rot_fast.c
	@mkdir -p $(dir $@)
	$(CC) $(CFLAGS) $(FAST_FLAGS_$*) -DSH_REAL_FLOAT -c $< -o $@

$(BUILD)/obj/cli/%.o: src/cli/%.c
	@mkdir -p $(dir $@)
	$(CC) $(CFLAGS) -DSHLAB_REVISION='"$(REV)"' -c $< -o $@

$(BUILD)/libshlab.a: $(LIB_OBJ)
	@rm -f $@
	ar rcs $@ $^

$(BUILD)/libshlab.so: $(LIB_OBJ)
	$(CC) -shared $(SANFLAGS) -Wl,-soname,libshlab.so.0 -o $@ $^ $(LDLIBS)

# the cost model's committed calibration as C (src/lab/cost_model.c)
COST_INC := $(BUILD)/gen/cost_table.inc
$(COST_INC): $(wildcard data/cost_model.tsv) tools/cost_table.awk
	@mkdir -p $(@D)
	@if [ -f data/cost_model.tsv ]; then awk -f tools/cost_table.awk data/cost_model.tsv; fi > $@.tmp && mv $@.tmp $@
$(BUILD)/obj/lab/cost_model.o: $(COST_INC)
$(BUILD)/obj/lab/cost_model.o: CFLAGS += -I$(BUILD)/gen

$(LAB_LIB): $(LAB_OBJ)
	@rm -f $@
	ar rcs $@ $^

$(BUILD)/shlab: $(CLI_OBJ) $(LAB_LIB) $(BUILD)/libshlab.a
	$(CC) $(SANFLAGS) -o $@ $(CLI_OBJ) $(LAB_LIB) $(BUILD)/libshlab.a $(LDLIBS)

# ---- tests ----------------------------------------------------------------
$(BUILD)/tests/%: %.c tests/testutil.h $(LAB_LIB) $(BUILD)/libshlab.a
	@mkdir -p $(dir $@)
	$(CC) $(CFLAGS) -Itests -o $@ $< $(TEST_EXTRA) $(LAB_LIB) $(BUILD)/libshlab.a $(CHECK_LIBS) $(LDLIBS)

# test_signal_cleanup exercises the CLI's signal handlers (src/cli/cli_output.c).
$(BUILD)/tests/test_signal_cleanup: $(BUILD)/libshlab_cli.a tests/fuzz/stubs.c
$(BUILD)/tests/test_signal_cleanup: TEST_EXTRA = $(BUILD)/libshlab_cli.a tests/fuzz/stubs.c
$(BUILD)/tests/test_cli_args: $(BUILD)/libshlab_cli.a tests/fuzz/stubs.c
$(BUILD)/tests/test_cli_args: TEST_EXTRA = $(BUILD)/libshlab_cli.a tests/fuzz/stubs.c

# The EXR tests write their files with OpenEXR's C++ library (tests/exr_writer.cpp).
EXR_WRITER_TESTS := $(BUILD)/tests/test_exr_layouts $(BUILD)/tests/test_exr_damage $(BUILD)/tests/test_ranges
$(EXR_WRITER_TESTS): $(BUILD)/tests/exr_writer.o
$(EXR_WRITER_TESTS): TEST_EXTRA = $(BUILD)/tests/exr_writer.o
$(BUILD)/tests/exr_writer.o: tests/exr_writer.cpp tests/exr_writer.h
	@mkdir -p $(dir $@)
	$(CXX) $(CXXFLAGS) -Itests -c $< -o $@

# TEST_JOBS: tests run at a time (tests/run.sh), one per core by default
TEST_JOBS ?= $(shell nproc 2>/dev/null || echo 1)
# Under the sanitizers the four longest numerical sweeps at the top of the
# promised ranges are left out: they run in the plain `make check`, and their
# code paths run under ASan/UBSan in the smaller tests (test_sht, test_rotator,
# test_exr, ...).  They were 730 s of the sanitizer run's 1380 s of tests.
SAN_SKIP  := test_ranges test_rot_halfpi test_exr_layouts test_sht_highband
# The generated shaders' numerics run on the Vulkan device (lavapipe's LLVM
# code, not instrumented) and take 150 s under ASan: the sanitizer run leaves
# out test_shaders_shlab.sh; test_shaders.sh still drives the host code
# (compilation, the sandboxed dispatch, the reader) under ASan/UBSan, on a
# shorter list (SANITIZE=1 in its environment: one language, one input).
SAN_SKIP_SCRIPTS := test_shaders_shlab.sh
ifeq ($(SANITIZE),1)
CHECK_BIN = $(filter-out $(addprefix $(BUILD)/tests/,$(SAN_SKIP)),$(TEST_BIN))
CHECK_SKIP_SCRIPTS = $(SAN_SKIP_SCRIPTS)
else
CHECK_BIN = $(TEST_BIN)
CHECK_SKIP_SCRIPTS =
endif
# Example plug-in kernels (shlab/kernel.h) for verify/bench --plugin
# (tests/cli/test_plugins.sh): self-contained, so built without libshlab.
PLUGIN_SO := $(BUILD)/tests/plugins/kernels.so
$(PLUGIN_SO): tests/plugins/kernels.c src/shlab/kernel.h
	@mkdir -p $(dir $@)
	$(CC) -std=c11 -D_DEFAULT_SOURCE -O2 -g -Wall -Wextra -fPIC -shared -Isrc -o $@ $< -lm

check: deps-quiet $(BUILD)/shlab $(CHECK_BIN) $(FUZZ_REPLAY) $(PLUGIN_SO)
	@SHLAB=$(BUILD)/shlab BUILD=$(BUILD) TEST_JOBS=$(TEST_JOBS) SKIP_SCRIPTS="$(CHECK_SKIP_SCRIPTS)" SANITIZE=$(SANITIZE) \
	  tests/run.sh $(CHECK_BIN)

# ---- fuzzing (tests/fuzz/README.md) -----------------------------------------
# One harness per input kind: tests/fuzz/fuzz_<h>.c.  make check links each to
# a corpus-replay main and replays tests/fuzz/corpus/<h>/ (tests/cli/
# test_fuzz_corpus.sh; with ASan/UBSan under SANITIZE=1).  make fuzz builds
# them with clang's libFuzzer and runs each for FUZZ_TIME seconds (0: no
# limit) or, with FUZZ_RUNS=N, until N executions, whichever comes first.
FUZZ_TIME    ?= 60
FUZZ_RUNS    ?=
CLI_LIB_OBJ  := $(filter-out $(BUILD)/obj/cli/main.o,$(CLI_OBJ))
FUZZ_SRC     := tests/fuzz/fuzz.h tests/fuzz/stubs.c

$(BUILD)/libshlab_cli.a: $(CLI_LIB_OBJ)
	@rm -f $@
	ar rcs $@ $^

$(BUILD)/fuzz/replay_%: tests/fuzz/fuzz_%.c tests/fuzz/replay.c $(FUZZ_SRC) $(BUILD)/libshlab_cli.a $(LAB_LIB) $(BUILD)/libshlab.a
	@mkdir -p $(dir $@)
	$(CC) $(CFLAGS) -o $@ $< tests/fuzz/replay.c tests/fuzz/stubs.c $(BUILD)/libshlab_cli.a \
	  $(LAB_LIB) $(BUILD)/libshlab.a $(LDLIBS)

$(BUILD)/fuzz/fuzz_%: tests/fuzz/fuzz_%.c $(FUZZ_SRC) $(BUILD)/libshlab_cli.a $(LAB_LIB) $(BUILD)/libshlab.a
	@mkdir -p $(dir $@)
	$(CC) $(CFLAGS) -fsanitize=fuzzer -fsanitize-link-c++-runtime -o $@ $< tests/fuzz/stubs.c $(BUILD)/libshlab_cli.a \
	  $(LAB_LIB) $(BUILD)/libshlab.a $(LDLIBS)

fuzz-build: $(FUZZ_HARNESS:%=$(BUILD)/fuzz/fuzz_%)

fuzz:
	@tools/deps.sh --fuzz --quiet
	@$(MAKE) --no-print-directory SANITIZE=fuzz fuzz-build
	@FUZZ_RUNS=$(FUZZ_RUNS) tests/fuzz/run.sh build/libfuzzer $(FUZZ_TIME) $(FUZZ_HARNESS)

# ---- generated code ---------------------------------------------------------
# src/rotate/rot_unrolled_gen.h is written by tools/gen_rot_unrolled.c (its
# banner records the command); `make regen` rewrites it, `make check` fails
# if it differs from what the generator writes (tests/cli/test_kernels.sh).
GEN_UNROLLED := $(BUILD)/tools/gen_rot_unrolled
$(GEN_UNROLLED): tools/gen_rot_unrolled.c $(BUILD)/libshlab.a
	@mkdir -p $(dir $@)
	$(CC) $(CFLAGS) -o $@ $< $(BUILD)/libshlab.a $(LDLIBS)

# The same generator writes shlab's compute shaders, data/shaders/rot_*.glsl
# and .hlsl (--shader), each with its command in its banner; `make check`
# compares them too (tests/cli/test_shader_gen.sh).
GEN_SHADERS := $(foreach m,zxzxz taylor1 taylor15 taylor2,$(foreach e,glsl hlsl,data/shaders/rot_$(m).$(e)))
regen: $(GEN_UNROLLED)
	$(GEN_UNROLLED) $$(sed -n 's|^ \*   build/tools/gen_rot_unrolled \(.*\) > src/rotate/rot_unrolled_gen.h$$|\1|p' src/rotate/rot_unrolled_gen.h) > $(BUILD)/rot_unrolled_gen.h
	mv $(BUILD)/rot_unrolled_gen.h src/rotate/rot_unrolled_gen.h
	@for f in $(GEN_SHADERS); do \
	  args=$$(sed -n "s|^//   build/tools/gen_rot_unrolled \(.*\) > $$f\$$|\1|p" $$f); \
	  [ -n "$$args" ] || { echo "regen: no command in the banner of $$f" >&2; exit 1; }; \
	  echo "$(GEN_UNROLLED) $$args > $$f"; \
	  $(GEN_UNROLLED) $$args > $(BUILD)/shader.tmp && mv $(BUILD)/shader.tmp $$f || exit 1; \
	done

check: $(GEN_UNROLLED)

# ---- experiments and report ----------------------------------------------
# One program per experiment: experiments/<name>/<name>.c → build/experiments/<name>
# → reports/<name>/*.dat → experiments/<name>/*.gp → reports/<name>/*.png
ALL_EXPERIMENTS := legendre_stability green_vector projection_convergence orthonormality cap_closed_form \
               probe_bands ringing scale_sparsity scale_smoothness scale_scenes taylor_deriv taylor_error \
               rotation_speed rotation_frontier rotation_stability rotation_conventions \
               rotation_extremes rotation_cost rotation_kernels \
               highband_peers sht_accuracy cost_model trade_atlas
# ---- scenes: experiments of src/scene/ -------------------
ALL_EXPERIMENTS += scene_transfer scene_shading
# ---- end scenes ---------------------------------------------------------------
# ---- cache: the radiance cache and shadow fields ----------
ALL_EXPERIMENTS += scene_cache scene_shadowfield
# ---- end cache ----------------------------------------------------------------
# `make report EXPERIMENTS="a b"` runs only these (docs/experiments.md); the
# report is still assembled from every experiment's fragments.
EXPERIMENTS ?= $(ALL_EXPERIMENTS)
ifneq ($(filter-out $(ALL_EXPERIMENTS),$(EXPERIMENTS)),)
$(error unknown experiment(s): $(filter-out $(ALL_EXPERIMENTS),$(EXPERIMENTS)) (make list-experiments names them))
endif
EXP_BIN := $(EXPERIMENTS:%=$(BUILD)/experiments/%)

$(BUILD)/experiments/%: experiments/%/*.c experiments/common/exp.c experiments/common/exp.h $(LAB_LIB) $(BUILD)/libshlab.a
	@mkdir -p $(dir $@)
	$(CC) $(CFLAGS) -Iexperiments/common -o $@ $(filter %.c,$^) $(LAB_LIB) $(BUILD)/libshlab.a $(LDLIBS)

# sht_accuracy compares with libsharp in-process (measure/peers/peer_sharp.o)
$(BUILD)/experiments/sht_accuracy: experiments/sht_accuracy/*.c experiments/common/exp.c experiments/common/exp.h \
    tests/legendre_truth.h $(PEER_SHARP_OBJ) $(LAB_LIB) $(BUILD)/libshlab.a
	@mkdir -p $(dir $@)
	$(CC) $(CFLAGS) -Iexperiments/common -o $@ $(filter %.c,$^) $(PEER_SHARP_OBJ) $(LAB_LIB) $(BUILD)/libshlab.a $(LDLIBS) $(SHARP_LIBS)

experiments: $(EXP_BIN)

# The report's revision stamp names the code, not the state of reports/: the
# last commit that changed code or data (experiments/common/code_rev.sh).
# SCENES=full: the scene experiments' full study too (their kept parts full/;
# needs `make probes` and `make models`; about an hour on 2 cores).
# cost_model writes the planner's calibration (data/cost_model.tsv), which
# is compiled in: it runs first, then everything is rebuilt with it.
REPORT_ENV = SCENES=$(SCENES) SHLAB=$(BUILD)/shlab BUILD=$(BUILD) ALL_EXPERIMENTS="$(ALL_EXPERIMENTS)" \
	  REV=$$(experiments/common/code_rev.sh)
report: all $(EXP_BIN)
	@if [ -n "$(filter cost_model,$(EXPERIMENTS))" ]; then \
	  $(REPORT_ENV) experiments/run_all.sh cost_model && \
	  $(MAKE) --no-print-directory all $(EXP_BIN); fi
	@$(REPORT_ENV) experiments/run_all.sh $(filter-out cost_model,$(EXPERIMENTS))
	@if [ -n "$(filter cost_model,$(EXPERIMENTS))" ]; then SHLAB=$(BUILD)/shlab tools/refresh_examples.sh docs/choosing.md; fi

# docs/choosing.md's console examples rewritten from their commands (checked
# by tests/cli/test_choosing_examples.sh)
examples: all
	@SHLAB=$(BUILD)/shlab tools/refresh_examples.sh docs/choosing.md

# Re-render the PNGs of EXPERIMENTS (default: all) from their committed data
# with gnuplot alone (no experiment runs), and reassemble the report.
plots:
	@ALL_EXPERIMENTS="$(ALL_EXPERIMENTS)" RENDER_ONLY=1 REV=$$(experiments/common/code_rev.sh) \
	  experiments/run_all.sh $(EXPERIMENTS)

list-experiments:
	@echo $(ALL_EXPERIMENTS)

# Instructions per rotated vector of every method, counted under valgrind's
# callgrind (independent of the machine's load; `shlab bench --instructions`).
bench-count: all
	$(BUILD)/shlab bench --instructions --order 2,3,4,5,6,8,10,12,16 --batch 3

probes:
	@tools/probes.sh data/probes

# ---- scenes (src/scene/, experiments/scene_*) ------------------------------
models:
	@tools/models.sh data/models

# ---- install ----------------------------------------------------------------
$(BUILD)/shlab.1: $(BUILD)/shlab tools/help2man.sh
	tools/help2man.sh $(BUILD)/shlab > $@

# the libraries libshlab links, for static linking (Libs.private; see the .pc.in)
PC_PRIVATE = $(shell pkg-config --static --libs gsl OpenEXR jansson fftw3 assimp libpng 2>/dev/null) -lembree3 -lpthread -lmpfr -lgmp -lstdc++ -lm -fopenmp
$(BUILD)/shlab.pc: tools/shlab.pc.in FORCE
	sed -e 's|@PREFIX@|$(PREFIX)|g' -e 's|@VERSION@|$(shell sed -n 's/^#define SHLAB_VERSION "\(.*\)"/\1/p' src/shlab.h)|g' \
	    -e 's|@PRIVATE_LIBS@|$(strip $(PC_PRIVATE))|g' $< > $@
FORCE:

install: all $(BUILD)/shlab.1 $(BUILD)/shlab.pc
	install -d $(DESTDIR)$(PREFIX)/bin $(DESTDIR)$(PREFIX)/lib/pkgconfig \
	  $(DESTDIR)$(PREFIX)/include/shlab $(DESTDIR)$(PREFIX)/share/man/man1
	install -m 755 $(BUILD)/shlab $(DESTDIR)$(PREFIX)/bin/shlab
	install -m 644 $(BUILD)/libshlab.a $(DESTDIR)$(PREFIX)/lib/libshlab.a
	install -m 755 $(BUILD)/libshlab.so $(DESTDIR)$(PREFIX)/lib/libshlab.so.0
	ln -sf libshlab.so.0 $(DESTDIR)$(PREFIX)/lib/libshlab.so
	install -m 644 src/shlab.h $(DESTDIR)$(PREFIX)/include/shlab.h
	install -m 644 $(wildcard src/shlab/*.h) $(DESTDIR)$(PREFIX)/include/shlab/
	install -m 644 $(BUILD)/shlab.pc $(DESTDIR)$(PREFIX)/lib/pkgconfig/shlab.pc
	install -m 644 $(BUILD)/shlab.1 $(DESTDIR)$(PREFIX)/share/man/man1/shlab.1
	install -d $(DESTDIR)$(PREFIX)/share/doc/shlab
	install -m 644 docs/CONVENTIONS.md docs/REFERENCES.md $(DESTDIR)$(PREFIX)/share/doc/shlab/
	@# run-time lookup of libshlab.so.0: shlab.pc's Libs carry an rpath (any PREFIX);
	@# a root install into /usr/local or /usr (directories the loader searches)
	@# also refreshes its cache, for programs linked without pkg-config
	@case "$(DESTDIR):$(PREFIX)" in :/usr/local|:/usr) [ "$$(id -u)" != 0 ] || ldconfig ;; esac

man: $(BUILD)/shlab.1

clean:
	rm -rf build

-include $(shell find $(BUILD) -name '*.d' 2>/dev/null)

# ---- peer: HEALPix C++ (begin peer_healpix block) --------------------------
# Oracle test and benchmark of the all-band rotation against HEALPix's
# rotate_alm (Debian libhealpix-cxx-dev, optional: `make deps` installs it).
# C++ stays here, at the edge: tests/peers/*.cc link libshlab.a.
CXX      ?= c++
HEALPIX_PC := $(shell pkg-config --exists healpix_cxx 2>/dev/null && echo yes)
PEER_HEALPIX_FLAGS = -std=c++17 $(OPT) -Wall $(SANFLAGS) -Isrc -Itests $(shell pkg-config --cflags healpix_cxx 2>/dev/null)
PEER_HEALPIX_LIBS  = $(BUILD)/libshlab.a $(shell pkg-config --libs healpix_cxx 2>/dev/null) $(CHECK_LIBS) $(LDLIBS)
.PHONY: bench-peers check-peer-healpix
ifeq ($(HEALPIX_PC),yes)
TEST_BIN += $(BUILD)/tests/test_peer_healpix
check: $(BUILD)/tests/test_peer_healpix
$(BUILD)/tests/test_peer_healpix: tests/peers/test_peer_healpix.cc tests/peers/peer_healpix.h tests/testutil.h $(BUILD)/libshlab.a
	@mkdir -p $(dir $@)
	$(CXX) $(PEER_HEALPIX_FLAGS) -o $@ $< $(PEER_HEALPIX_LIBS)
$(BUILD)/peers/peer_healpix_bench: tests/peers/peer_healpix_bench.cc tests/peers/peer_healpix.h $(BUILD)/libshlab.a
	@mkdir -p $(dir $@)
	$(CXX) $(PEER_HEALPIX_FLAGS) -o $@ $< $(PEER_HEALPIX_LIBS)
bench-peers:: $(BUILD)/peers/peer_healpix_bench
	$(BUILD)/peers/peer_healpix_bench $(PEER_ARGS)
# experiments/highband_peers runs it (peer_healpix_bench --tsv)
report: $(BUILD)/peers/peer_healpix_bench
else
check: check-peer-healpix
check-peer-healpix:
	@echo "test_peer_healpix: skipped: HEALPix C++ not found (pkg-config healpix_cxx; Debian libhealpix-cxx-dev, make deps)"
bench-peers::
	@echo "peer_healpix_bench: skipped: HEALPix C++ not found (pkg-config healpix_cxx; Debian libhealpix-cxx-dev, make deps)"
endif
# ---- end peer_healpix block --------------------------------------------------

# ---- python: the shlab package (begin python block) --------------------------
# python/shlab: ctypes over libshlab.so (docs/python.md); tests in python/tests
# (pytest), run by `make check` against this build's libshlab.so.
# PYTHON: Debian's interpreter, which has python3-numpy and python3-pytest (a
# python3 earlier on PATH, pyenv's say, may lack them); else python3 on PATH.
PYTHON ?= $(shell if [ -x /usr/bin/python3 ]; then echo /usr/bin/python3; else command -v python3 || echo python3; fi)
# `make install` puts the package in PY_SITE/shlab: for PREFIX=/usr/local (or
# /usr) a directory that interpreter searches (Debian's python3.11:
# /usr/local/lib/python3.11/dist-packages); for another PREFIX set
# PYTHONPATH=PREFIX/lib/python3.X/dist-packages (docs/python.md).  The
# package records PREFIX/lib (shlab/_install.py) to load libshlab.so.0 from.
PY_VERSION := $(shell $(PYTHON) -c 'import sys; print("%d.%d" % sys.version_info[:2])' 2>/dev/null || echo 3)
PY_SITE  ?= $(PREFIX)/lib/python$(PY_VERSION)/dist-packages
PY_SRC   := $(filter-out python/shlab/_install.py,$(wildcard python/shlab/*.py))
.PHONY: check-python install-python
check: check-python
install: install-python
ifeq ($(SANITIZE),1)
check-python:
	@echo "python tests: skipped under SANITIZE=1 (an ASan libshlab.so loads into python only with libasan in LD_PRELOAD; the plain make check runs them)"
else
check-python: $(BUILD)/libshlab.so $(BUILD)/shlab
	@if ! $(PYTHON) -c 'import numpy, pytest' 2>/dev/null; then \
	  echo "python tests: skipped: $(PYTHON) lacks numpy or pytest (Debian python3-numpy python3-pytest; make deps)"; \
	else SHLAB_LIBRARY=$(abspath $(BUILD))/libshlab.so SHLAB_BUILD=$(BUILD) PYTHON=$(PYTHON) \
	  $(PYTHON) -m pytest -q -p no:cacheprovider python/tests; fi
endif
install-python:
	install -d $(DESTDIR)$(PY_SITE)/shlab
	install -m 644 $(PY_SRC) $(DESTDIR)$(PY_SITE)/shlab/
	printf '"""Written by make install: the directory of libshlab.so.0."""\nLIBDIR = %s\n' "'$(PREFIX)/lib'" \
	  > $(DESTDIR)$(PY_SITE)/shlab/_install.py
# ---- end python block --------------------------------------------------------
