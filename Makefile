# mpmstab front door. `make` builds the tool, `make test` builds and runs the test suite, `make bench`
# the benchmarks. Every target first installs the Debian packages it needs if they are missing.

# The kernels' instruction-set ceiling: empty (every version, the CPU's best chosen at run time),
# avx2 or portable; each builds in its own folder, build-avx2 or build-portable, and gives the same
# results byte for byte (only the time moves): `make reproduce ISA=avx2`.
ISA        ?=
ifeq ($(filter-out avx2 portable,$(ISA)),)
else
$(error ISA must be empty, avx2 or portable, not '$(ISA)')
endif
BUILD_DIR  ?= build$(if $(ISA),-$(ISA))
BUILD_TYPE ?= Release
JOBS       ?= $(shell nproc 2>/dev/null || echo 2)
# CI builds treat compiler warnings as errors.
WERROR     ?= $(if $(CI),ON,OFF)

DEB_PACKAGES := cmake g++ make libeigen3-dev nlohmann-json3-dev libfmt-dev libcli11-dev libgtest-dev libgmock-dev \
                libbenchmark-dev gnuplot-nox fonts-dejavu-core clang-format bc util-linux clang-14 \
                libclang-rt-14-dev

# Every experiment is a spec in experiments/; `mpmstab list` prints them in the order they run
# (each after the experiments whose results its study reads), `mpmstab list --figures` those
# that draw a figure. No list of experiments is kept here. A spec's check_budget bounds the
# particle-steps of the cases make check reruns (default 2e7).
RESULTS     ?= results
MPMSTAB     := $(BUILD_DIR)/mpmstab
# The documents whose generated blocks the results write (mpmstab documents): only from results/,
# the committed results they describe; a tier run into another RESULTS folder leaves them as they
# are, so that no run elsewhere writes into the source tree.
DOCUMENTS   := README.md docs/theory.md docs/studies.md

FUZZ_SECONDS ?= 15
FUZZ_DIR     ?= build-fuzz

.PHONY: all build build-tests deps test test-cluster studies-cluster reproduce-cluster check bless fuzz bench bench-versions timings reproduce studies tier figures plots reports-unchanged format format-check clean help

all: build

help:
	@echo "make              install missing packages, configure and build the tool, $(BUILD_DIR)/mpmstab"
	@echo "make test         build and run the test suite (CTest), then make check, then make fuzz"
	@echo "make test-cluster  shard sweeps on a throwaway local Slurm cluster and with GNU parallel;"
	@echo "                   the merged reports must equal an unsharded run's, byte for byte"
	@echo "make studies-cluster NODES=1|2  make studies as one Slurm job array on a throwaway"
	@echo "                   local cluster of NODES nodes, JOBS tasks at once; results/ byte for"
	@echo "                   byte, the wall time into results/cluster_timings.json"
	@echo "                   (make reproduce-cluster: the paper tier)"
	@echo "make fuzz         fuzz the spec, results and cache readers, FUZZ_SECONDS (default 15) each"
	@echo "make check        rerun a fast subset of every experiment against reference/regression"
	@echo "make bless REASON=\"...\"  accept the current values as blessed, logged in BLESSED.md"
	@echo "make reproduce    regenerate the paper: Tables 1 and 2, Figs. 1-3, the comparison (results/)"
	@echo "make studies      regenerate every other study (cached cases are not rerun)"
	@echo "make reports-unchanged  re-render both tiers (from the cache when warm) and fail unless"
	@echo "                   every report, README.md and docs/ come out byte for byte as committed"
	@echo "make bench        run the step benchmark, write results/benchmark_step.json"
	@echo "make bench-versions  ns per particle-step of each kernel version this machine runs,"
	@echo "                   beside a lean loop compiled for the same instruction set"
	@echo "make timings      publish this machine's timings: results/timings.json, performance.md"
	@echo "make format       clang-format every source file in place"
	@echo "make deps         only install the missing Debian packages"
	@echo "ISA=avx2|portable  any target above with the kernels' instruction set capped (AVX2, or"
	@echo "                   the -march target only), built in build-avx2 or build-portable; the"
	@echo "                   same results byte for byte, another time"

# Install only what is missing; apt-get needs root (sudo is used when available).
deps:
	@missing=""; for p in $(DEB_PACKAGES); do \
	  dpkg-query -W -f='$${Status}' $$p 2>/dev/null | grep -q "ok installed" || missing="$$missing $$p"; \
	done; \
	if [ -n "$$missing" ]; then \
	  echo "Installing missing Debian packages:$$missing"; \
	  SUDO=""; [ "$$(id -u)" -ne 0 ] && SUDO="sudo"; \
	  $$SUDO apt-get update -qq && \
	  DEBIAN_FRONTEND=noninteractive $$SUDO apt-get install -y -qq --no-install-recommends $$missing; \
	fi

# A build folder made here is a fresh build: its start is noted, and `make` (the tool only) records
# how long it took (mpmstab build-time), from configuring to the linked tool. The record is a
# convenience: where it cannot be written build-time says so in one line (status 1) and `make`
# still succeeds.
$(BUILD_DIR)/CMakeCache.txt: CMakeLists.txt | deps
	@if [ ! -e $(BUILD_DIR)/CMakeCache.txt ]; then \
	  mkdir -p $(BUILD_DIR) && date +%s.%N > $(BUILD_DIR)/fresh-build-start; fi
	cmake -S . -B $(BUILD_DIR) -DCMAKE_BUILD_TYPE=$(BUILD_TYPE) -DMPMSTAB_WERROR=$(WERROR) -DMPMSTAB_ISA=$(ISA)

# `make` builds the tool only; the test programs (the suite, the kernels of every instruction
# set, the benchmark) are built by `make test` and `make bench`. What keeps a fresh build short is
# in CMakeLists.txt: the harness at -Og in unity groups, the solver exactly as its recorded flags
# say with a precompiled Eigen, and the layers compiled side by side.
build: deps $(BUILD_DIR)/CMakeCache.txt
	cmake -S . -B $(BUILD_DIR) -DMPMSTAB_WERROR=$(WERROR) -DMPMSTAB_ISA=$(ISA) > /dev/null
	@start=$$(cat $(BUILD_DIR)/fresh-build-start 2>/dev/null); rm -f $(BUILD_DIR)/fresh-build-start; \
	echo "cmake --build $(BUILD_DIR) -j $(JOBS) --target mpmstab"; \
	cmake --build $(BUILD_DIR) -j $(JOBS) --target mpmstab || exit $$?; \
	if [ -n "$$start" ]; then \
	  seconds=$$(echo "$$(date +%s.%N) - $$start" | bc); \
	  echo "make: a fresh build of the tool took $$(printf '%.1f' $$seconds) s"; \
	  $(MPMSTAB) build-time --seconds $$seconds --jobs $(JOBS) --out $(RESULTS) || [ $$? -eq 1 ]; \
	fi

# Everything: the tool and the test programs, in one build so that both cores stay busy.
build-tests: deps $(BUILD_DIR)/CMakeCache.txt
	@rm -f $(BUILD_DIR)/fresh-build-start  # the tool and the tests: not what `make` times
	cmake -S . -B $(BUILD_DIR) -DMPMSTAB_WERROR=$(WERROR) -DMPMSTAB_ISA=$(ISA) > /dev/null
	cmake --build $(BUILD_DIR) -j $(JOBS)

test: build-tests
	cd $(BUILD_DIR) && ctest --output-on-failure -j $(JOBS)
	@$(MAKE) --no-print-directory check
	@$(MAKE) --no-print-directory fuzz

# The cluster workflow end to end (tests/cluster/test_cluster.sh): installs slurm-wlm, munge and
# parallel if missing, starts a one-node Slurm cluster on localhost in a temporary folder, and
# compares the merged reports of sharded runs (Slurm job array, GNU parallel) with an unsharded run.
test-cluster: build
	MPMSTAB=$(MPMSTAB) tests/cluster/test_cluster.sh

# A whole tier as one Slurm job array (mpmstab slurm --tier) on a throwaway cluster of NODES slurmd
# nodes on this machine (tests/cluster/tier_cluster.sh): from an empty cache into a scratch folder
# (RESULTS_DIR, default a temporary one), every file must come out byte for byte as committed in
# results/; the wall time is then recorded in results/cluster_timings.json (make timings shows it
# in results/performance.md). JOBS array tasks run at once, on one node of JOBS CPUs or NODES nodes
# sharing them. make studies-cluster NODES=2 JOBS=2.
NODES  ?= 1
SHARDS ?= 8
studies-cluster: build
	MPMSTAB=$(MPMSTAB) TIER=studies NODES=$(NODES) JOBS=$(JOBS) SHARDS=$(SHARDS) RESULTS_DIR=$(RESULTS_DIR) \
	  tests/cluster/tier_cluster.sh

reproduce-cluster: build
	MPMSTAB=$(MPMSTAB) TIER=paper NODES=$(NODES) JOBS=$(JOBS) SHARDS=$(SHARDS) RESULTS_DIR=$(RESULTS_DIR) \
	  tests/cluster/tier_cluster.sh

# A bounded fuzz run, FUZZ_SECONDS each, of the three readers of outside text (libFuzzer, with
# address and UB sanitizers): the spec parser, the results reader and the cache reader. The
# committed corpora tests/fuzz/corpus*, the specs and tests/fuzz/seeds (a real results file and
# cache record) seed them, read only; new inputs that reach new code go to $(FUZZ_DIR)/corpus*,
# never into the source tree (copy one into tests/fuzz/corpus* by hand to keep it).
fuzz: deps
	@test -f $(FUZZ_DIR)/CMakeCache.txt || cmake -S . -B $(FUZZ_DIR) -DMPMSTAB_FUZZ=ON \
	  -DCMAKE_CXX_COMPILER=clang++-14 -DCMAKE_BUILD_TYPE=RelWithDebInfo -DMPMSTAB_ARCH= > /dev/null
	cmake --build $(FUZZ_DIR) -j $(JOBS) --target fuzz_spec fuzz_results fuzz_cache
	mkdir -p $(FUZZ_DIR)/corpus $(FUZZ_DIR)/corpus_results $(FUZZ_DIR)/corpus_cache
	$(FUZZ_DIR)/tests/fuzz/fuzz_spec -max_total_time=$(FUZZ_SECONDS) -max_len=4096 \
	  -dict=tests/fuzz/spec.dict -print_final_stats=1 $(FUZZ_DIR)/corpus tests/fuzz/corpus \
	  experiments
	$(FUZZ_DIR)/tests/fuzz/fuzz_results -max_total_time=$(FUZZ_SECONDS) -max_len=8192 \
	  -dict=tests/fuzz/spec.dict -print_final_stats=1 $(FUZZ_DIR)/corpus_results \
	  tests/fuzz/corpus_results tests/fuzz/seeds/results
	$(FUZZ_DIR)/tests/fuzz/fuzz_cache -max_total_time=$(FUZZ_SECONDS) -max_len=8192 \
	  -dict=tests/fuzz/spec.dict -print_final_stats=1 $(FUZZ_DIR)/corpus_cache \
	  tests/fuzz/corpus_cache tests/fuzz/seeds/cache

# The documents describe the committed results/, whatever RESULTS names.
check: build
	$(MPMSTAB) documents --check $(DOCUMENTS) --results results
	specs=$$($(MPMSTAB) list) && $(MPMSTAB) check $$specs --jobs $(JOBS) --results $(RESULTS)

# The reason reaches the program through the environment, never pasted into the shell line: no
# quote or $(...) in it can run a command.
bless: export MPMSTAB_BLESS_REASON = $(REASON)
bless: build
	specs=$$($(MPMSTAB) list) && \
	  $(MPMSTAB) bless $$specs --jobs $(JOBS) --results $(RESULTS) --reason "$$MPMSTAB_BLESS_REASON"

# Each kernel version this machine can run beside a lean loop compiled for the same instruction
# set (tests/bench_versions.sh): ns per particle-step per method, best of 3 interleaved runs; the
# table goes to the terminal and to $(BUILD_DIR)/bench_versions.md, nothing into the checkout.
bench-versions: build
	cmake --build $(BUILD_DIR) -j $(JOBS) --target bench_versions
	tests/bench_versions.sh $(BUILD_DIR)

# The step benchmark (Google Benchmark, 5 repetitions, medians used), pinned to one core.
bench: build
	cmake --build $(BUILD_DIR) -j $(JOBS) --target mpmstab_bench
	mkdir -p $(RESULTS)
	taskset -c 0 $(BUILD_DIR)/tests/mpmstab_bench --benchmark_repetitions=5 \
	  --benchmark_min_time=0.2 --benchmark_report_aggregates_only=true \
	  --benchmark_out=$(RESULTS)/benchmark_step.json.tmp --benchmark_out_format=json
	mv $(RESULTS)/benchmark_step.json.tmp $(RESULTS)/benchmark_step.json
	specs=$$($(MPMSTAB) list) && \
	  $(MPMSTAB) performance $$specs --bench $(RESULTS)/benchmark_step.json --out $(RESULTS)

# Two tiers, each whole (a spec's "tier"; mpmstab list --tier): `make reproduce` regenerates the
# paper (Tables 1 and 2, Figs. 1-3 with their variants, the peers study, and the comparison with
# the experiments it cites); `make studies` everything else, with the paper experiments its
# studies read. A paper experiment reads only paper experiments, so no report depends on which
# tier ran first. Each tier's cases go in one queue (mpmstab reproduce): only the cases whose key
# changed are computed, longest first on JOBS threads, and each experiment's reports are written
# as soon as it is complete; reports are rewritten only when their content changed, so a figure
# is redrawn only when its data or its script changed. The index (results/README.md) covers
# every experiment of both tiers.
reproduce: build
	@$(MAKE) --no-print-directory tier TIER=paper

studies: build
	@$(MAKE) --no-print-directory tier TIER=studies

# The tier named by TIER (paper or studies); reproduce and studies call it, and so does the render
# job of a tier run as a Slurm job array (mpmstab slurm --tier), with the cache the array filled.
tier:
	@start=$$(date +%s.%N); \
	specs=$$($(MPMSTAB) list --tier $(TIER)) || exit $$?; \
	$(MPMSTAB) reproduce $$specs --jobs $(JOBS) --out $(RESULTS) \
	  --label "make $(if $(filter paper,$(TIER)),reproduce,studies)" || exit $$?; \
	$(MAKE) --no-print-directory -j $(JOBS) plots FIGURES="$(FIGURE_NAMES)" || exit $$?; \
	all=$$($(MPMSTAB) list) || exit $$?; \
	$(MPMSTAB) index $$all --out $(RESULTS) || exit $$?; \
	if [ "$(RESULTS)" = results ]; then \
	  $(MPMSTAB) documents $(DOCUMENTS) --results $(RESULTS) || exit $$?; \
	else \
	  echo "make: $(DOCUMENTS) describe results/ and are left as they are (RESULTS=$(RESULTS))"; \
	fi; \
	echo "make $(if $(filter paper,$(TIER)),reproduce,studies): $$(echo "$$(date +%s.%N) - $$start" | bc | xargs printf '%.1f') s wall; reports in $(RESULTS)/README.md"

# Both tiers re-rendered into results/ (from the cache when it is warm: nothing is recomputed),
# every figure redrawn (its subtitle is code: a tier redraws a figure only when its data, its
# results or its script changed), then every committed report, figure and generated document
# compared byte for byte with the
# commit: a change of the code that moves no result passes; one that moves a byte fails, naming
# the files. Run it after every step of a refactoring.
reports-unchanged: build
	@$(MAKE) --no-print-directory tier TIER=paper RESULTS=results
	@$(MAKE) --no-print-directory tier TIER=studies RESULTS=results
	@for spec in $$($(MPMSTAB) list --figures); do $(MPMSTAB) plot $$spec --out results || exit 1; done
	$(MPMSTAB) documents --check $(DOCUMENTS) --results results
	@changed=$$(git status --porcelain --untracked-files=all -- results $(DOCUMENTS)); \
	if [ -n "$$changed" ]; then \
	  echo "make reports-unchanged: these files differ from the commit:" >&2; echo "$$changed" >&2; exit 1; \
	fi; echo "make reports-unchanged: every report of both tiers is byte for byte as committed"

# The machine's timings (results/cache/timings.json, written by every sweep and reproduce, not
# committed) published as results/timings.json with results/performance.md: the only way those two
# committed files change, so that a moved clock never shows as a moved result.
timings: build
	specs=$$($(MPMSTAB) list) && \
	  $(MPMSTAB) performance $$specs --bench $(RESULTS)/benchmark_step.json --out $(RESULTS)

# The figures of the experiments whose study draws one, each redrawn only when its data, its
# results (the subtitle reads them) or its script changed, JOBS at a time (each draws in a
# staging folder of its own). FIGURES (names) comes from mpmstab list --figures.
# (The tier calls plots itself: it runs where the tool is built, also in a Slurm job.)
FIGURE_NAMES = $$($(MPMSTAB) list --figures $(if $(TIER),--tier $(TIER)) | sed 's|.*/||; s|\.json$$||')
figures: build
	@$(MAKE) --no-print-directory -j $(JOBS) plots FIGURES="$(FIGURE_NAMES)"

plots: $(FIGURES:%=$(RESULTS)/%.png)

$(RESULTS)/%.png $(RESULTS)/%.svg &: $(RESULTS)/%_data.csv $(RESULTS)/%.json experiments/%.gp experiments/history.gp
	$(MPMSTAB) plot experiments/$*.json --out $(RESULTS)

SOURCES = $(shell git ls-files '*.cpp' '*.hpp' 2>/dev/null)

format:
	clang-format -i $(SOURCES)

format-check:
	clang-format --dry-run -Werror $(SOURCES)

clean:
	rm -rf $(BUILD_DIR)
