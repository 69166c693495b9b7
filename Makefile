# sol - reproduces the quantitative claims of "CryENGINE 3: Reaching the speed of light".
#
#   make reproduce   install/check Debian packages, build, run every experiment, regenerate
#                    results/ (and the paper)
#   make test        build and run the Criterion test suite
#   make bench       accuracy-vs-time benchmarks of every experiment (tables on stdout)
#   make sanitize    the test suite under AddressSanitizer + UndefinedBehaviorSanitizer (+ leaks)
#   make valgrind    the test suite under valgrind memcheck (slow; TEST_ARGS='--filter x/*')
#   make fuzz        every tests/fuzz/fuzz_*.c under libFuzzer for FUZZ_SECONDS each
#   make run-NAME    one experiment (NAME is a folder of experiments/); ARGS="--quick --out /tmp/x"
#                    passes arguments to the driver
#   make             the library and every experiment driver
#
# Layout is discovered: src/<module>/*.c (+ the Ceres shim *.cpp) form libsol.a, each
# experiments/<name>/ is one driver, tests/*.c form one Criterion binary. An experiment that links
# a peer library names it in experiments/<name>/build.mk as `<name>_LDLIBS := ...`.

BUILD ?= build
CC ?= cc
CXX ?= g++
CFLAGS ?= -O2 -g
CXXFLAGS ?= -O2 -g
LDFLAGS ?=

# Debian packages: what the tests need, and what reproducing everything needs (libsquish and
# NVIDIA Texture Tools are peers for side-by-side comparison; colobot-common-textures ships real
# game textures for the colour-texture experiments T1-T7).
TEST_PKGS := gcc g++ make pkg-config libcriterion-dev libceres-dev libgoogle-glog-dev libeigen3-dev \
             libopenexr-dev libpng-dev clang libclang-rt-14-dev libomp-14-dev valgrind libcjson-dev libassimp-dev assimp-testmodels
REPRODUCE_PKGS := $(TEST_PKGS) gnuplot-nox libsquish-dev libnvtt-dev colobot-common-textures texlive-latex-base \
                  texlive-latex-recommended texlive-fonts-recommended latexmk

# Reruns give identical files except timing values: gnuplot's PDFs get a fixed date (exp_plot) and
# the paper takes its date from SOURCE_DATE_EPOCH, the time of the last commit that changed what
# generates results/ (a commit of results/ alone does not move it). FORCE_SOURCE_DATE makes LaTeX's
# \today follow it too. `make compare-runs` lists what a rerun changed besides timings.
SOURCE_DATE_EPOCH ?= $(shell git log -1 --format=%ct -- src experiments paper Makefile 2>/dev/null || echo 0)
export SOURCE_DATE_EPOCH
export FORCE_SOURCE_DATE := 1

# All three can be narrowed on the command line while one module is being worked on, e.g.
# make BUILD=build/normals MODULES="core normals" TEST_SRC=tests/test_normals.c run-tests
# src/cli is the `sol` program, not a library module.
MODULES ?= $(filter-out cli,$(patsubst src/%/,%,$(wildcard src/*/)))
EXPERIMENTS ?= $(filter-out common,$(patsubst experiments/%/,%,$(wildcard experiments/*/)))
TEST_SRC ?= $(wildcard tests/*.c)

# pkg-config is asked lazily (=, not :=), so `make test` on a fresh machine first installs it.
EXR_CFLAGS = $(shell pkg-config --cflags OpenEXR 2>/dev/null)
PNG_CFLAGS = $(shell pkg-config --cflags libpng 2>/dev/null)
CPPFLAGS_ALL = $(addprefix -Isrc/,$(MODULES)) -Isrc/cli -Iexperiments/common $(EXR_CFLAGS) $(PNG_CFLAGS) \
               -I/usr/include/eigen3 -MMD -MP
WARNINGS := -Wall -Wextra -Wshadow -Wpointer-arith -Wstrict-prototypes -Wmissing-prototypes
C_STD := -std=c11 -D_DEFAULT_SOURCE -fopenmp  # _DEFAULT_SOURCE: M_PI, POSIX calls
# Link line from pkg-config: OpenEXR's .pc lists all of its libraries, sol uses only its C core
# (OpenEXRCore + the package's library suffix, e.g. -3_1), so that one is picked by name; Ceres
# ships no .pc file, so it is named directly.
EXR_LIBS = $(shell pkg-config --libs-only-L OpenEXR 2>/dev/null) \
           -lOpenEXRCore$(shell pkg-config --variable=libsuffix OpenEXR 2>/dev/null)
PNG_LIBS = $(shell pkg-config --libs libpng 2>/dev/null)
GLOG_LIBS = $(shell pkg-config --libs libglog 2>/dev/null)
CJSON_LIBS = $(shell pkg-config --libs libcjson 2>/dev/null)
ASSIMP_LIBS = $(shell pkg-config --libs assimp 2>/dev/null)
LDLIBS_ALL = $(PNG_LIBS) $(EXR_LIBS) $(CJSON_LIBS) $(ASSIMP_LIBS) -lceres $(GLOG_LIBS) -lgomp -lm

LIB_C := $(foreach m,$(MODULES),$(wildcard src/$(m)/*.c))
LIB_CXX := $(foreach m,$(MODULES),$(wildcard src/$(m)/*.cpp))
LIB_OBJ := $(LIB_C:%.c=$(BUILD)/%.o) $(LIB_CXX:%.cpp=$(BUILD)/%.o)
LIB := $(BUILD)/libsol.a
EXP_COMMON_OBJ := $(patsubst %.c,$(BUILD)/%.o,$(wildcard experiments/common/*.c))
TEST_OBJ := $(patsubst %.c,$(BUILD)/%.o,$(TEST_SRC))
TEST_BIN := $(BUILD)/tests/sol_tests
SOL_BIN := $(BUILD)/sol
SOL_BIN_OBJ := $(patsubst %.c,$(BUILD)/%.o,$(wildcard src/cli/*.c))

.PHONY: install shared run-examples compare-runs
.PHONY: all lib experiments test run-tests reproduce run-experiments claims-table paper paper-section bench \
        sanitize valgrind fuzz fuzz-smoke fuzz-build deps-test deps-reproduce clean $(EXPERIMENTS:%=run-%)

all: lib experiments $(SOL_BIN)

lib: $(LIB)

$(LIB): $(LIB_OBJ)
	@mkdir -p $(@D)
	rm -f $@
	ar rcs $@ $^

# ---- install: static + versioned shared library (PIC objects), headers under include/sol/ with
# the umbrella header sol/sol.h (generated from the module list), and sol.pc.
PREFIX ?= /usr/local
LIBDIR ?= $(PREFIX)/lib
INCLUDEDIR ?= $(PREFIX)/include
SOL_VERSION := $(shell sed -n 's/^\#define SOL_VERSION_STRING "\(.*\)"/\1/p' src/core/sol_core.h)
SOL_SOMAJOR := $(firstword $(subst ., ,$(SOL_VERSION)))
SHLIB := $(BUILD)/libsol.so.$(SOL_VERSION)
PIC_OBJ := $(LIB_OBJ:$(BUILD)/%=$(BUILD)/pic/%)
LIB_HEADERS := $(foreach m,$(MODULES),$(wildcard src/$(m)/sol_$(m).h))

shared: $(SHLIB)

$(SHLIB): $(PIC_OBJ)
	$(CXX) -shared -fopenmp $(LDFLAGS) -Wl,-soname,libsol.so.$(SOL_SOMAJOR) $^ -o $@ $(LDLIBS_ALL)

$(BUILD)/pic/src/%.o: src/%.c
	@mkdir -p $(@D)
	$(CC) $(C_STD) $(WARNINGS) $(CFLAGS) -fPIC $(CPPFLAGS_ALL) -c $< -o $@

$(BUILD)/pic/src/%.o: src/%.cpp
	@mkdir -p $(@D)
	$(CXX) -std=c++17 -Wall -Wextra $(CXXFLAGS) -fPIC $(CPPFLAGS_ALL) -c $< -o $@

# sol.pc is written by install for its PREFIX. Requires.private/Libs.private: what a static link
# needs (the shared library records its own dependencies). Libs has -lm: the headers' inline
# helpers (sol_angle3, sol_unorm_encode) call libm.
install: $(LIB) $(SHLIB)
	install -d $(DESTDIR)$(LIBDIR)/pkgconfig $(DESTDIR)$(INCLUDEDIR)/sol
	install -m 644 $(LIB) $(DESTDIR)$(LIBDIR)/libsol.a
	install -m 755 $(SHLIB) $(DESTDIR)$(LIBDIR)/libsol.so.$(SOL_VERSION)
	ln -sf libsol.so.$(SOL_VERSION) $(DESTDIR)$(LIBDIR)/libsol.so.$(SOL_SOMAJOR)
	ln -sf libsol.so.$(SOL_SOMAJOR) $(DESTDIR)$(LIBDIR)/libsol.so
	install -m 644 $(LIB_HEADERS) $(DESTDIR)$(INCLUDEDIR)/sol/
	{ echo '/* sol/sol.h - every public header of sol (generated by make install). */'; \
	  echo '#ifndef SOL_SOL_H'; echo '#define SOL_SOL_H'; \
	  for h in $(notdir $(LIB_HEADERS)); do echo "#include \"$$h\""; done; echo '#endif'; } \
	  > $(DESTDIR)$(INCLUDEDIR)/sol/sol.h
	printf '%s\n' 'prefix=$(PREFIX)' 'libdir=$(LIBDIR)' 'includedir=$(INCLUDEDIR)' '' 'Name: sol' \
	  'Description: reference implementations of CryENGINE 3 rendering techniques, and checks of an engine against them' \
	  'Version: $(SOL_VERSION)' 'Requires.private: libpng libglog libcjson assimp' \
	  'Libs: -L$${libdir} -lsol -lm' 'Libs.private: $(strip $(EXR_LIBS)) -lceres -lgomp -lstdc++ -lm' \
	  'Cflags: -I$${includedir}' > $(DESTDIR)$(LIBDIR)/pkgconfig/sol.pc

# examples/*.c built against the INSTALLED library (a temporary prefix inside build/) with
# pkg-config, then run: what a user of `make install` does. `make test` runs this.
EXAMPLE_PREFIX := $(abspath $(BUILD))/stage
run-examples: $(LIB) $(SHLIB)
	@rm -rf $(EXAMPLE_PREFIX)
	@$(MAKE) --no-print-directory PREFIX=$(EXAMPLE_PREFIX) install >/dev/null
	@for e in $(wildcard examples/*.c); do \
	  n=$$(basename $$e .c); \
	  $(CC) -std=c11 -Wall -Wextra -Werror $$e -o $(BUILD)/stage/$$n -Wl,-rpath,$(EXAMPLE_PREFIX)/lib \
	    $$(PKG_CONFIG_PATH=$(EXAMPLE_PREFIX)/lib/pkgconfig pkg-config --cflags --libs sol) || exit 1; \
	  $(BUILD)/stage/$$n >/dev/null || { echo "example $$n failed"; exit 1; }; echo "example $$n: ok"; \
	done

# The `sol` program: a thin front end over the library (src/cli/).
$(SOL_BIN): $(SOL_BIN_OBJ) $(LIB)
	$(CXX) -fopenmp $(LDFLAGS) $^ -o $@ $(LDLIBS_ALL)

$(BUILD)/src/%.o: src/%.c
	@mkdir -p $(@D)
	$(CC) $(C_STD) $(WARNINGS) $(CFLAGS) $(CPPFLAGS_ALL) -c $< -o $@

$(BUILD)/src/%.o: src/%.cpp
	@mkdir -p $(@D)
	$(CXX) -std=c++17 -Wall -Wextra $(CXXFLAGS) $(CPPFLAGS_ALL) -c $< -o $@

# Experiment drivers and tests: same C flags, but no -Wmissing-prototypes (Criterion's macros).
$(BUILD)/experiments/%.o: experiments/%.c
	@mkdir -p $(@D)
	$(CC) $(C_STD) -Wall -Wextra -Wshadow $(CFLAGS) $(CPPFLAGS_ALL) -c $< -o $@

$(BUILD)/experiments/%.o: experiments/%.cpp
	@mkdir -p $(@D)
	$(CXX) -std=c++17 -Wall -Wextra $(CXXFLAGS) $(CPPFLAGS_ALL) -c $< -o $@

$(BUILD)/tests/%.o: tests/%.c
	@mkdir -p $(@D)
	$(CC) $(C_STD) -Wall -Wextra $(CFLAGS) $(CPPFLAGS_ALL) -c $< -o $@

-include $(wildcard experiments/*/build.mk)

# One driver per experiment folder: build/experiments/<name>/<name>.
define experiment_rules
$(1)_OBJ := $$(patsubst %.c,$(BUILD)/%.o,$$(wildcard experiments/$(1)/*.c)) \
            $$(patsubst %.cpp,$(BUILD)/%.o,$$(wildcard experiments/$(1)/*.cpp))
$(BUILD)/experiments/$(1)/$(1): $$($(1)_OBJ) $(EXP_COMMON_OBJ) $(LIB)
	$(CXX) -fopenmp $(LDFLAGS) $$^ -o $$@ $$($(1)_LDLIBS) $(LDLIBS_ALL)
run-$(1): $(BUILD)/experiments/$(1)/$(1)
	@echo "== experiment $(1)"
	$(BUILD)/experiments/$(1)/$(1) $(ARGS)
endef
$(foreach e,$(EXPERIMENTS),$(eval $(call experiment_rules,$(e))))

experiments: $(foreach e,$(EXPERIMENTS),$(BUILD)/experiments/$(e)/$(e))

# The tests share the generator of issue 13's degenerate survey with the T8 driver's make bench.
TEST_SHARED_OBJ := $(BUILD)/experiments/t8_t14_3dc_encoders/degenerate_survey.o
$(TEST_BIN): $(TEST_OBJ) $(TEST_SHARED_OBJ) $(LIB)
	@mkdir -p $(@D)
	$(CXX) -fopenmp $(LDFLAGS) $^ -o $@ -lcriterion $(LDLIBS_ALL)

# The engine fixture of tests/test_check.c (a small engine with plantable bugs that `sol check`
# must flag); the test finds it and the `sol` program under $(BUILD).
ENGINE_FIXTURE := $(BUILD)/tests/engine_fixture
$(ENGINE_FIXTURE): $(BUILD)/tests/fixtures/engine_fixture.o $(LIB)
	$(CXX) -fopenmp $(LDFLAGS) $^ -o $@ $(LDLIBS_ALL)
$(BUILD)/tests/test_check.o: CPPFLAGS_ALL += -DSOL_TEST_BUILD_DIR='"$(BUILD)"'

# Installs what is missing when run as root; otherwise prints the exact apt line and stops.
define ensure_packages
@missing=$$(for p in $(1); do dpkg-query -W -f='$${Status}\n' $$p 2>/dev/null | grep -q 'ok installed' || echo $$p; done | tr '\n' ' ' | sed 's/ $$//'); \
if [ -n "$$missing" ]; then \
  if [ "$$(id -u)" = 0 ]; then \
    echo "installing missing Debian packages: $$missing"; \
    apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq $$missing || exit 1; \
  else \
    echo "sol needs these Debian packages. Run as root, or install them with:"; \
    echo "  sudo apt-get install $$missing"; \
    exit 1; \
  fi; \
fi
endef

deps-test:
	$(call ensure_packages,$(TEST_PKGS))

deps-reproduce:
	$(call ensure_packages,$(REPRODUCE_PKGS))

# Sub-makes re-read this file once the packages (and so pkg-config's answers) are there.
test: deps-test
	@$(MAKE) --no-print-directory run-tests
	@$(MAKE) --no-print-directory fuzz-smoke
	@$(MAKE) --no-print-directory run-examples

run-tests: $(TEST_BIN) $(SOL_BIN) $(ENGINE_FIXTURE)
	$(TEST_BIN)

# The build runs on every core (JOBS). The drivers run DRIVER_JOBS at a time, each with its OpenMP
# threads, the longest first, so that one driver's serial stretches (plots, tables, image writing)
# overlap another's parallel loops instead of leaving a core idle; -Otarget keeps each driver's
# output together. The results cannot depend on this: each driver writes only results/<name>/ and
# its numbers do not depend on the thread count (tests/test_determinism.c). LONGEST_FIRST is by
# measured CPU time; drivers not in it follow in folder order.
DRIVER_JOBS ?= 2
LONGEST_FIRST := scenes d15_ward_sg_fit d6_d7_s1_s5_normal_encodings t8_t14_3dc_encoders d3_d5_normal_cells \
                 d2_d14_d16_deferred_lobes s4_dfg_fit t1_t2_t4_t7_color_textures d18_taa m4_lut_grading
RUN_ORDER = $(foreach e,$(LONGEST_FIRST),$(filter $(e),$(EXPERIMENTS))) $(filter-out $(LONGEST_FIRST),$(EXPERIMENTS))

reproduce: deps-reproduce
	@$(MAKE) --no-print-directory -j$(JOBS) all
	@$(MAKE) --no-print-directory -j$(DRIVER_JOBS) -Otarget run-experiments
	@$(MAKE) --no-print-directory claims-table
	@$(MAKE) --no-print-directory paper

run-experiments: $(RUN_ORDER:%=run-%)

# Fails (naming the line) if a claim of experiments/claims_list.tsv lacks its experiment or its
# library entry point, so claim ID -> experiment -> function is one step.
claims-table:
	sh experiments/common/check_claims_list.sh experiments/claims_list.tsv
	awk -F'\t' -v fmt=md -f experiments/common/claims_table.awk experiments/claims_list.tsv \
	    $(wildcard results/*/claims.tsv) > results/CLAIMS.md
	awk -F'\t' -v fmt=tex -f experiments/common/claims_table.awk experiments/claims_list.tsv \
	    $(wildcard results/*/claims.tsv) > results/claims.tex

# The paper is built from results/ once paper/sol.tex exists; the PDF is copied into results/.
# results/numbers.tex gathers every driver's numbers.tex (exp_number) and the verdict counts of the
# claims table, so the prose's \solnum{key} come from the run; an undefined key fails the build.
paper:
	@if [ -f paper/sol.tex ]; then \
	  { cat $(wildcard results/*/numbers.tex) /dev/null; \
	    awk -F'\t' 'FNR > 1 && NF >= 5 { n++; c[$$5]++ } END { \
	      printf "\\solnumdef{claims-rows}{%d}\n", n; \
	      split("reproduced differs-explained not-reproduced", v, " "); \
	      for (i = 1; i <= 3; i++) printf "\\solnumdef{claims-%s}{%d}\n", v[i], c[v[i]] }' \
	      $(wildcard results/*/claims.tsv) /dev/null; \
	  } > results/numbers.tex; \
	  cd paper && latexmk -g -pdf -interaction=nonstopmode -halt-on-error -quiet sol.tex >/dev/null \
	    || { grep "undefined solnum key" sol.log | sed 's/^! Package sol Error: /paper: /; s/$$/ (no results\/*\/numbers.tex defines it: add exp_number to its driver and rerun it)/'; \
	         echo "paper: LaTeX failed, see paper/sol.log"; exit 1; }; \
	  cp sol.pdf ../results/sol.pdf; \
	fi

# One section alone (for checking it): build/paper-check/<SECTION>.pdf
paper-section:
	@[ -n "$(SECTION)" ] && [ -f paper/sections/$(SECTION).tex ] || { echo "usage: make paper-section SECTION=name, one of:" \
	  $(basename $(notdir $(wildcard paper/sections/*.tex))); exit 2; }
	@mkdir -p $(BUILD)/paper-check
	cd paper && pdflatex -interaction=nonstopmode -halt-on-error -output-directory=$(abspath $(BUILD))/paper-check \
	  -jobname=$(SECTION) "\def\solsection{$(SECTION)}\input{sol.tex}" >/dev/null \
	  || { echo "paper-section: LaTeX failed, see $(BUILD)/paper-check/$(SECTION).log"; exit 1; }
	@echo "built $(BUILD)/paper-check/$(SECTION).pdf"

# What a rerun changed besides timing values (exit 1 if anything else): A and B are two results
# trees, e.g. a copy of results/ from a first `make reproduce` and results/ after a second one.
# Without A, the results/ committed at HEAD (extracted under $(BUILD)/compare-head) is compared with
# B (default results/), so `make compare-runs` right after `make reproduce` checks the rerun.
compare-runs:
	@b="$(or $(B),results)"; a="$(A)"; \
	if [ -z "$$a" ]; then \
	  a=$(BUILD)/compare-head/results; rm -rf $(BUILD)/compare-head; mkdir -p $(BUILD)/compare-head; \
	  git archive HEAD results | tar -x -C $(BUILD)/compare-head || exit 2; \
	fi; \
	echo "compare-runs: $$a against $$b"; \
	sh experiments/common/compare_runs.sh "$$a" "$$b"

# The bench tables go to $(BUILD)/bench/<name>/ (and stdout), never into results/: results/ is
# written only by `make reproduce`, and a driver run with --bench writes smaller versions of some of
# its reproduce tables.
bench: deps-reproduce
	@$(MAKE) --no-print-directory experiments
	@mkdir -p $(BUILD)/bench
	@for e in $(EXPERIMENTS); do echo "## $$e"; $(BUILD)/experiments/$$e/$$e --bench --out $(BUILD)/bench || exit 1; done

# allocator_may_return_null: tests check that impossible allocations return SOL_ERR_NO_MEMORY.
# Criterion runs every test in a forked child and ignores the child's exit status once the test
# has reported, so LeakSanitizer's report at the child's exit (exit code 23) never failed the run:
# the log is kept and any sanitizer report in it fails the target.
sanitize: deps-test
	@$(MAKE) --no-print-directory BUILD=$(BUILD)/sanitize \
	  CFLAGS="-O1 -g -fsanitize=address,undefined -fno-sanitize-recover=undefined -fno-omit-frame-pointer" \
	  CXXFLAGS="-O1 -g -fsanitize=address,undefined -fno-omit-frame-pointer" \
	  LDFLAGS="-fsanitize=address,undefined" $(BUILD)/sanitize/tests/sol_tests $(BUILD)/sanitize/sol \
	  $(BUILD)/sanitize/tests/engine_fixture
	@log=$(BUILD)/sanitize/tests.log; \
	{ ASAN_OPTIONS=allocator_may_return_null=1:detect_leaks=1 $(BUILD)/sanitize/tests/sol_tests $(TEST_ARGS) 2>&1; \
	  echo $$? > $$log.rc; } | tee $$log; \
	if grep -q -E 'ERROR: (Leak|Address)Sanitizer|runtime error:' $$log; then \
	  echo "sanitize: sanitizer reports in $$log"; exit 1; fi; \
	exit $$(cat $$log.rc)

# Criterion's sandbox (BoxFort) forks and re-executes the test binary for each test, so memcheck
# must trace children; as above, their exit status is lost, so each process writes its own log
# and any error or definite/indirect leak in one fails the target.
VALGRIND_FLAGS := --trace-children=yes --child-silent-after-fork=yes --leak-check=full --errors-for-leak-kinds=definite,indirect --show-leak-kinds=definite,indirect \
                  --error-exitcode=1 --track-origins=no
valgrind: deps-test
	@$(MAKE) --no-print-directory $(TEST_BIN) $(SOL_BIN)
	@rm -rf $(BUILD)/valgrind && mkdir -p $(BUILD)/valgrind
	valgrind $(VALGRIND_FLAGS) --log-file=$(BUILD)/valgrind/vg.%p.log $(TEST_BIN) --jobs 1 $(TEST_ARGS); rc=$$?; \
	bad=$$(grep -l -E 'ERROR SUMMARY: [1-9]' $(BUILD)/valgrind/vg.*.log); \
	if [ -n "$$bad" ]; then echo "valgrind: errors in"; echo "$$bad"; exit 1; fi; \
	echo "valgrind: $$(ls $(BUILD)/valgrind | wc -l) processes, no errors"; exit $$rc

# Fuzzing (libFuzzer): every tests/fuzz/fuzz_<name>.c defines LLVMFuzzerTestOneInput and has its
# seeds in tests/fuzz/corpus/<name>/. The library's C sources are rebuilt with clang, ASan and
# UBSan in $(BUILD)/fuzz; each target runs FUZZ_SECONDS (make fuzz) or FUZZ_SMOKE_SECONDS (make
# fuzz-smoke, part of make test) from a scratch copy of its seeds, and any crash, leak, timeout or
# out-of-memory fails the target (the input is kept in $(BUILD)/fuzz/artifacts/).
# -Wno-pass-failed: at -O1 under the sanitizers clang cannot vectorize best_fit.c's omp simd loops;
# they stay scalar (the same bits, see that file), so the warning tells nothing about the fuzzed code.
FUZZ_SECONDS ?= 60
FUZZ_SMOKE_SECONDS ?= 10
FUZZ_TARGETS := $(patsubst tests/fuzz/fuzz_%.c,%,$(wildcard tests/fuzz/fuzz_*.c))
FUZZ_SAN := -fsanitize=address,undefined -fno-sanitize-recover=undefined -fno-omit-frame-pointer
FUZZ_LDLIBS = $(filter-out -lgomp,$(LDLIBS_ALL)) -lstdc++
FUZZ_FLAGS ?= -timeout=10 -rss_limit_mb=2048

fuzz-build: deps-test
	@$(MAKE) --no-print-directory BUILD=$(BUILD)/fuzz CC=clang CXX=clang++ LIB_CXX= \
	  CFLAGS="-O1 -g -Wno-pass-failed -fsanitize=fuzzer-no-link $(FUZZ_SAN)" $(BUILD)/fuzz/libsol.a
	@$(MAKE) --no-print-directory $(FUZZ_TARGETS:%=$(BUILD)/fuzz/bin/fuzz_%)

$(BUILD)/fuzz/bin/fuzz_%: tests/fuzz/fuzz_%.c $(BUILD)/fuzz/libsol.a
	@mkdir -p $(@D)
	clang $(C_STD) -Wall -Wextra -O1 -g -fsanitize=fuzzer $(FUZZ_SAN) $(CPPFLAGS_ALL) $< $(BUILD)/fuzz/libsol.a \
	  -o $@ $(FUZZ_LDLIBS)

define fuzz_run
	@mkdir -p $(BUILD)/fuzz/corpus/$(1) $(BUILD)/fuzz/artifacts
	@echo "== fuzz $(1): $(2) s"
	@$(BUILD)/fuzz/bin/fuzz_$(1) $(FUZZ_FLAGS) -max_total_time=$(2) -print_final_stats=1 \
	  -artifact_prefix=$(BUILD)/fuzz/artifacts/$(1)- $(BUILD)/fuzz/corpus/$(1) tests/fuzz/corpus/$(1) \
	  > $(BUILD)/fuzz/$(1).log 2>&1 || { tail -40 $(BUILD)/fuzz/$(1).log; echo "fuzz $(1): FAILED, see $(BUILD)/fuzz/$(1).log"; exit 1; }
	@grep -E 'stat::number_of_executed_units|Done [0-9]+ runs' $(BUILD)/fuzz/$(1).log | sed 's/^/   /'

endef

fuzz: fuzz-build
	$(foreach t,$(FUZZ_TARGETS),$(call fuzz_run,$(t),$(FUZZ_SECONDS)))

fuzz-smoke: fuzz-build
	$(foreach t,$(FUZZ_TARGETS),$(call fuzz_run,$(t),$(FUZZ_SMOKE_SECONDS)))

clean:
	rm -rf $(BUILD) paper/*.aux paper/*.log paper/*.fls paper/*.fdb_latexmk paper/*.out paper/*.bbl paper/*.blg \
	  paper/sol.pdf

-include $(shell find $(BUILD) -name '*.d' 2>/dev/null)
