# sol - reproduces the quantitative claims of "CryENGINE 3: Reaching the speed of light".
#
#   make reproduce   install/check Debian packages, build, run every experiment, regenerate
#                    results/ (and the paper)
#   make test        build and run the Criterion test suite
#   make bench       accuracy-vs-time benchmarks of every experiment (tables on stdout)
#   make sanitize    the test suite under AddressSanitizer + UndefinedBehaviorSanitizer
#   make run-NAME    one experiment (NAME is a folder of experiments/)
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
             libopenexr-dev libpng-dev libcjson-dev libassimp-dev assimp-testmodels
REPRODUCE_PKGS := $(TEST_PKGS) gnuplot-nox libsquish-dev libnvtt-dev colobot-common-textures texlive-latex-base \
                  texlive-latex-recommended texlive-fonts-recommended latexmk

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
LDLIBS_ALL := -lpng -lOpenEXRCore-3_1 -lcjson -lassimp -lceres -lglog -lgomp -lm

LIB_C := $(foreach m,$(MODULES),$(wildcard src/$(m)/*.c))
LIB_CXX := $(foreach m,$(MODULES),$(wildcard src/$(m)/*.cpp))
LIB_OBJ := $(LIB_C:%.c=$(BUILD)/%.o) $(LIB_CXX:%.cpp=$(BUILD)/%.o)
LIB := $(BUILD)/libsol.a
EXP_COMMON_OBJ := $(patsubst %.c,$(BUILD)/%.o,$(wildcard experiments/common/*.c))
TEST_OBJ := $(patsubst %.c,$(BUILD)/%.o,$(TEST_SRC))
TEST_BIN := $(BUILD)/tests/sol_tests
SOL_BIN := $(BUILD)/sol
SOL_BIN_OBJ := $(patsubst %.c,$(BUILD)/%.o,$(wildcard src/cli/*.c))

.PHONY: all lib experiments test run-tests reproduce run-experiments claims-table paper paper-section bench \
        sanitize deps-test deps-reproduce clean $(EXPERIMENTS:%=run-%)

all: lib experiments $(SOL_BIN)

lib: $(LIB)

$(LIB): $(LIB_OBJ)
	@mkdir -p $(@D)
	rm -f $@
	ar rcs $@ $^

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
	$(BUILD)/experiments/$(1)/$(1)
endef
$(foreach e,$(EXPERIMENTS),$(eval $(call experiment_rules,$(e))))

experiments: $(foreach e,$(EXPERIMENTS),$(BUILD)/experiments/$(e)/$(e))

$(TEST_BIN): $(TEST_OBJ) $(LIB)
	@mkdir -p $(@D)
	$(CXX) -fopenmp $(LDFLAGS) $^ -o $@ -lcriterion $(LDLIBS_ALL)

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

run-tests: $(TEST_BIN) $(SOL_BIN)
	$(TEST_BIN)

reproduce: deps-reproduce
	@$(MAKE) --no-print-directory all
	@$(MAKE) --no-print-directory run-experiments
	@$(MAKE) --no-print-directory claims-table
	@$(MAKE) --no-print-directory paper

run-experiments: $(EXPERIMENTS:%=run-%)

claims-table:
	awk -F'\t' -v fmt=md -f experiments/common/claims_table.awk experiments/claims_list.tsv \
	    $(wildcard results/*/claims.tsv) > results/CLAIMS.md
	awk -F'\t' -v fmt=tex -f experiments/common/claims_table.awk experiments/claims_list.tsv \
	    $(wildcard results/*/claims.tsv) > results/claims.tex

# The paper is built from results/ once paper/sol.tex exists; the PDF is copied into results/.
paper:
	@if [ -f paper/sol.tex ]; then \
	  cd paper && latexmk -pdf -interaction=nonstopmode -halt-on-error -quiet sol.tex >/dev/null \
	    || { echo "paper: LaTeX failed, see paper/sol.log"; exit 1; }; \
	  cp sol.pdf ../results/sol.pdf; \
	fi

# One section alone (for checking it): build/paper-check/<SECTION>.pdf
paper-section:
	@mkdir -p $(BUILD)/paper-check
	cd paper && pdflatex -interaction=nonstopmode -halt-on-error -output-directory=../$(BUILD)/paper-check \
	  -jobname=$(SECTION) "\def\solsection{$(SECTION)}\input{sol.tex}" >/dev/null \
	  || { echo "paper-section: LaTeX failed, see $(BUILD)/paper-check/$(SECTION).log"; exit 1; }
	@echo "built $(BUILD)/paper-check/$(SECTION).pdf"

bench: deps-reproduce
	@$(MAKE) --no-print-directory experiments
	@for e in $(EXPERIMENTS); do echo "## $$e"; $(BUILD)/experiments/$$e/$$e --bench || exit 1; done

# allocator_may_return_null: tests check that impossible allocations return SOL_ERR_NO_MEMORY.
sanitize: deps-test
	@ASAN_OPTIONS=allocator_may_return_null=1 $(MAKE) --no-print-directory BUILD=$(BUILD)/sanitize \
	  CFLAGS="-O1 -g -fsanitize=address,undefined -fno-sanitize-recover=undefined -fno-omit-frame-pointer" \
	  CXXFLAGS="-O1 -g -fsanitize=address,undefined -fno-omit-frame-pointer" \
	  LDFLAGS="-fsanitize=address,undefined" run-tests

clean:
	rm -rf $(BUILD) paper/*.aux paper/*.log paper/*.fls paper/*.fdb_latexmk paper/*.out paper/sol.pdf

-include $(shell find $(BUILD) -name '*.d' 2>/dev/null)
