# shlab — build, test, report.  See README.md.
#   make            build build/shlab, build/libshlab.a, build/libshlab.so
#   make check      build and run every test (unit tests with Check, CLI tests)
#   make check SANITIZE=1   the same, built with -fsanitize=address,undefined
#   make report     build, run every experiment, write reports/
#   make probes     extract Blender's eight CC0 HDR world probes into data/probes/
#   make models     copy the real test meshes (assimp-testmodels) into data/models/
#   make install PREFIX=/usr/local
#   make deps       install missing Debian packages (as root) or print the command

PREFIX   ?= /usr/local
SANITIZE ?= 0
CC       ?= cc

ifeq ($(SANITIZE),1)
BUILD    ?= build/san
SANFLAGS := -fsanitize=address,undefined -fno-omit-frame-pointer -fno-sanitize-recover=undefined
OPT      := -O1 -g
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

# src/ is grouped by concept, one folder each (README "Layout"): the library is
# every src/<concept>/*.c except src/cli/ (the command-line tool).
LIB_DIRS := core basis io project rotate taylor scale measure
LIB_DIRS += scene
LIB_SRC  := $(sort $(foreach d,$(LIB_DIRS),$(wildcard src/$(d)/*.c)))
CLI_SRC  := $(sort $(wildcard src/cli/*.c))
TEST_SRC := $(sort $(wildcard tests/test_*.c))
# src/*/rot_*.c are precision-generic rotation kernels (rotate/rot_real.h):
# compiled once as double (x.o) and once as float (x_f.o, -DSH_REAL_FLOAT).
ROTK_SRC := $(sort $(foreach d,$(LIB_DIRS),$(wildcard src/$(d)/rot_*.c)))
LIB_OBJ  := $(LIB_SRC:src/%.c=$(BUILD)/obj/%.o) $(ROTK_SRC:src/%.c=$(BUILD)/obj/%_f.o)
CLI_OBJ  := $(CLI_SRC:src/cli/%.c=$(BUILD)/obj/cli/%.o)
PUB_HDR  := src/shlab.h $(wildcard src/shlab/*.h)
TEST_BIN := $(TEST_SRC:tests/%.c=$(BUILD)/tests/%)
REV      := $(shell git rev-parse --short=12 HEAD 2>/dev/null || echo unknown)$(shell git diff --quiet HEAD 2>/dev/null || echo -dirty)

.PHONY: all deps deps-quiet check report experiments probes models install clean man
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

$(BUILD)/obj/%_f.o: src/%.c
	@mkdir -p $(dir $@)
	$(CC) $(CFLAGS) -DSH_REAL_FLOAT -c $< -o $@

$(BUILD)/obj/cli/%.o: src/cli/%.c
	@mkdir -p $(dir $@)
	$(CC) $(CFLAGS) -DSHLAB_REVISION='"$(REV)"' -c $< -o $@

$(BUILD)/libshlab.a: $(LIB_OBJ)
	@rm -f $@
	ar rcs $@ $^

$(BUILD)/libshlab.so: $(LIB_OBJ)
	$(CC) -shared $(SANFLAGS) -Wl,-soname,libshlab.so.0 -o $@ $^ $(LDLIBS)

$(BUILD)/shlab: $(CLI_OBJ) $(BUILD)/libshlab.a
	$(CC) $(SANFLAGS) -o $@ $(CLI_OBJ) $(BUILD)/libshlab.a $(LDLIBS)

# ---- tests ----------------------------------------------------------------
$(BUILD)/tests/%: tests/%.c tests/testutil.h $(BUILD)/libshlab.a
	@mkdir -p $(dir $@)
	$(CC) $(CFLAGS) -o $@ $< $(BUILD)/libshlab.a $(CHECK_LIBS) $(LDLIBS)

check: deps-quiet $(BUILD)/shlab $(TEST_BIN)
	@SHLAB=$(BUILD)/shlab BUILD=$(BUILD) tests/run.sh $(TEST_BIN)

# ---- experiments and report ----------------------------------------------
# One program per experiment: experiments/<name>/<name>.c → build/experiments/<name>
# → reports/<name>/*.dat → experiments/<name>/*.gp → reports/<name>/*.png
EXPERIMENTS := legendre_stability green_vector projection_convergence orthonormality cap_closed_form \
               probe_bands ringing scale_sparsity scale_smoothness scale_scenes taylor_deriv taylor_error \
               rotation_speed rotation_frontier rotation_stability rotation_conventions \
               rotation_extremes rotation_cost
# ---- scenes: experiments of src/scene/ (helper `scenes`) -------------------
EXPERIMENTS += scene_transfer scene_shading
# ---- end scenes ---------------------------------------------------------------
# ---- cache: the radiance cache and shadow fields (helper `cache`) ----------
EXPERIMENTS += scene_cache scene_shadowfield
# ---- end cache ----------------------------------------------------------------
EXP_BIN := $(EXPERIMENTS:%=$(BUILD)/experiments/%)

$(BUILD)/experiments/%: experiments/%/*.c experiments/common/exp.c experiments/common/exp.h $(BUILD)/libshlab.a
	@mkdir -p $(dir $@)
	$(CC) $(CFLAGS) -Iexperiments/common -o $@ $(filter %.c,$^) $(BUILD)/libshlab.a $(LDLIBS)

experiments: $(EXP_BIN)

report: all $(EXP_BIN)
	@SHLAB=$(BUILD)/shlab BUILD=$(BUILD) REV=$(REV) experiments/run_all.sh $(EXPERIMENTS)

probes:
	@tools/probes.sh data/probes

# ---- scenes (src/scene/, experiments/scene_*) ------------------------------
models:
	@tools/models.sh data/models

# ---- install ----------------------------------------------------------------
$(BUILD)/shlab.1: $(BUILD)/shlab tools/help2man.sh
	tools/help2man.sh $(BUILD)/shlab > $@

$(BUILD)/shlab.pc: tools/shlab.pc.in
	sed -e 's|@PREFIX@|$(PREFIX)|g' -e 's|@VERSION@|$(shell sed -n 's/^#define SHLAB_VERSION "\(.*\)"/\1/p' src/shlab.h)|g' $< > $@

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

man: $(BUILD)/shlab.1

clean:
	rm -rf build

-include $(shell find $(BUILD) -name '*.d' 2>/dev/null)
