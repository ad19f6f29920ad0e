# The two commands of the README: `make demo` and `make test`. Both set everything up from scratch.
PYTHON ?= python3
VENV := .venv
PY := $(VENV)/bin/python
export VIRTUAL_ENV := $(abspath $(VENV))

.PHONY: demo test develop rust-check rust-test cargo-test pytest py-test fuzz fuzz-short wheel-check docs bench clean

# The package's dependencies are pyproject.toml's: `maturin develop` installs them with the package and the
# extras of the README's commands (studies and pandas). It is always run with these same extras and the same
# environment, so that a build made by one goal serves every other; the extras the tests and the docs add are
# installed by pip alone (their lists read from pyproject.toml), without touching the build.
EXTRAS = studies,pandas
# Cargo's target directory (as maturin finds it) and the pyo3 configuration maturin writes there: the cargo
# commands below pass it too (PYO3_CONFIG_FILE), so that checking the bindings (clippy) runs pyo3's build
# script with maturin's inputs and leaves the extension's build fresh (else each rebuilds pyo3 and the bindings).
TARGET_DIR := $(abspath $(or $(CARGO_TARGET_DIR),target))
PYO3_ENV = PYO3_CONFIG_FILE="$$(ls -t $(TARGET_DIR)/maturin/pyo3-config-*.txt | head -n 1)"

$(VENV)/.deps: pyproject.toml
	@echo "setting up $(VENV) (pip and maturin; the packages masonry-dem needs come with the build)..."
	@$(PYTHON) -m venv $(VENV)
	@$(PY) -m pip install -q --upgrade pip
	@$(PY) -m pip install -q "maturin>=1.5,<2"
	@touch $@

# Release build of the extension, installed into .venv (python sources are linked, not copied) with its
# dependencies and $(EXTRAS) (a minute or two of pip the first time); run again only when a Rust source or
# a manifest changed (the stamp $(VENV)/.develop). pip lists every satisfied requirement while maturin
# installs the package: the log is kept in .venv/develop.log and shown only if the build fails.
RUST_SOURCES := $(shell find src python/src -name '*.rs' 2>/dev/null) Cargo.toml Cargo.lock python/Cargo.toml
$(VENV)/.develop: $(VENV)/.deps pyproject.toml $(wildcard $(RUST_SOURCES))
	@echo "building the extension (release; a few minutes the first time) with the extras $(EXTRAS)..."
	@$(VENV)/bin/maturin develop --release -q --extras $(EXTRAS) > $(VENV)/develop.log 2>&1 || { cat $(VENV)/develop.log; exit 1; }
	@touch $@

# The package's modules compiled once (an editable install is not compiled by pip, and with
# PYTHONDONTWRITEBYTECODE set Python would compile them at every import: tens of milliseconds)
$(VENV)/.pyc: $(VENV)/.develop $(shell find python/masonry_dem -name '*.py' 2>/dev/null)
	@$(PY) -m compileall -q python/masonry_dem > /dev/null
	@touch $@

develop: $(VENV)/.develop $(VENV)/.pyc

# An extra of pyproject.toml installed with pip alone: $(VENV)/.extra-test, $(VENV)/.extra-docs
$(VENV)/.extra-%: $(VENV)/.deps pyproject.toml
	@echo "installing the extra $* (pip)..."
	@$(PY) -c "import sys; t = __import__('tomllib' if sys.version_info >= (3, 11) else 'tomli'); \
		print('\n'.join(t.load(open('pyproject.toml', 'rb'))['project']['optional-dependencies'][sys.argv[1]]))" $* > $(VENV)/extra-$*.txt
	@$(PY) -m pip install -q -r $(VENV)/extra-$*.txt
	@touch $@

demo: develop
	$(VENV)/bin/masonry-dem demo --plot out/demo.png

# clippy on every crate and target and the crate's docs, warnings as errors, then the Rust tests. clippy and
# doc check the dependencies once between them (one profile, one set of features: no code generation);
# the tests reuse the extension's release build of the core and its dependencies (the same features:
# the bindings build the core with bench-internals, whose items' doctests run here too). After `develop`, whose pyo3
# configuration clippy reads (see PYO3_ENV). rust-check is all but running the tests (clippy, the docs, the
# tests' build); cargo-test runs them, built (for `test`, beside the fuzzer: it is given no MAKEFLAGS, whose
# jobserver cargo would try and fail to join).
CARGO_TEST = cargo test --release --features bench-internals
rust-check: develop
	$(PYO3_ENV) cargo clippy --release --workspace --all-targets --features masonry-dem/bench-internals -q -- -D warnings
	RUSTDOCFLAGS="-D warnings" cargo doc --release --no-deps -q -p masonry-dem
	$(CARGO_TEST) --no-run -q

rust-test: rust-check
	$(CARGO_TEST)

cargo-test:
	MAKEFLAGS= $(CARGO_TEST)

# pytest on every core (pytest-xdist; each test's files in its own temporary directory), an idle worker taking
# tests queued on the other (the long ones would otherwise end the run on one core)
PYTEST = $(PY) -m pytest -q -n auto --dist worksteal tests/python
py-test: develop $(VENV)/.extra-test
	$(PYTEST)
	$(MAKE) fuzz-short

# Fuzzing of the case-file reader and model building (tests/fuzz/fuzz_case.py, atheris). The corpus grows
# in out/fuzz-corpus (seeded with examples/); findings are written as out/fuzz/crash-* (or timeout-*, oom-*).
FUZZ_TIME ?= 600
FUZZ_FLAGS = -timeout=60 -rss_limit_mb=3072 -max_len=16384 -artifact_prefix=out/fuzz/
fuzz: develop $(VENV)/.extra-test
	mkdir -p out/fuzz out/fuzz-corpus
	$(PY) tests/fuzz/fuzz_case.py out/fuzz-corpus examples tests/fuzz/seeds $(FUZZ_FLAGS) -max_total_time=$(FUZZ_TIME) -print_final_stats=1

# 20 seconds, part of `make test`: a fresh corpus from examples/ only, so the run does not depend on earlier ones.
# The fuzzer's output goes to out/fuzz-short.log: its summary is printed, the end of the log if it finds something.
fuzz-short: develop $(VENV)/.extra-test
	@rm -rf out/fuzz-short-corpus && mkdir -p out/fuzz out/fuzz-short-corpus
	@echo "fuzzing the case-file reader and model building for 20 s (log: out/fuzz-short.log)..."
	@$(PY) tests/fuzz/fuzz_case.py out/fuzz-short-corpus examples tests/fuzz/seeds $(FUZZ_FLAGS) -max_total_time=20 -print_final_stats=1 > out/fuzz-short.log 2>&1 \
		|| { tail -n 60 out/fuzz-short.log; echo "the fuzzer found a failing input: see out/fuzz/ and out/fuzz-short.log"; exit 1; }
	@grep -E "^(Done|stat::number_of_executed_units|stat::new_units_added)" out/fuzz-short.log || true

# Every test: the Rust tests with the 20 s of fuzzing beside them, and pytest from when the fuzzer is done (it
# keeps a core of its own for its 20 s of the clock). cargo test runs its test binaries one after the other, most
# of them on one core: beside the fuzzer, then beside pytest, they share the two cores the tests alone would leave
# half idle (each one's output printed whole when it ends).
test: rust-check $(VENV)/.extra-test
	@$(MAKE) --no-print-directory -j2 --output-sync=target cargo-test fuzz-short pytest

pytest:
	$(PYTEST)

# The wheel a user would install, checked as a newcomer would use it: a portable (manylinux2014, glibc >= 2.17)
# wheel built with zig as the linker into out/wheels, installed with its dependencies alone into a fresh
# out/wheel-venv, and the demo and the validation run there from outside the repository, so that the
# installed package and its shipped examples are used, not the sources.
# (The notebooks run in make test's pytest, from the sources: tests/python/test_tutorial.py.)
WHEEL_VENV := out/wheel-venv
wheel-check: $(VENV)/.deps
	@$(PY) -m pip install -q "maturin[zig]>=1.5,<2"
	@rm -rf out/wheels $(WHEEL_VENV) && mkdir -p out/wheels
	@echo "building the portable wheel (release, zig; a few minutes the first time)..."
	@PATH="$(abspath $(VENV))/bin:$$PATH" $(VENV)/bin/maturin build --release --zig --compatibility manylinux2014 -o out/wheels > out/wheel-build.log 2>&1 \
		|| { tail -n 40 out/wheel-build.log; echo "the wheel build failed: see out/wheel-build.log"; exit 1; }
	@ls out/wheels/*.whl
	@ls out/wheels/*manylinux2014_x86_64*.whl > /dev/null 2>&1 || { echo "the wheel is not manylinux2014"; exit 1; }
	@$(PY) -c "import sys, zipfile; names = zipfile.ZipFile(sys.argv[1]).namelist(); \
		need = ['masonry_dem/examples/ferris-tinloi-wall1.toml', 'masonry_dem/examples/elcentro-1940-ns.csv', \
		'masonry_dem/examples/studies/wall1-fragility.toml']; missing = [n for n in need if n not in names]; \
		sys.exit(f'not in the wheel: {missing}' if missing else 0)" out/wheels/*.whl
	@echo "installing it into a fresh $(WHEEL_VENV)..."
	@$(PYTHON) -m venv $(WHEEL_VENV)
	@$(WHEEL_VENV)/bin/python -m pip install -q out/wheels/*.whl
	cd $(WHEEL_VENV) && VIRTUAL_ENV=$(abspath $(WHEEL_VENV)) bin/masonry-dem demo --plot ../wheel-demo.png
	cd $(WHEEL_VENV) && VIRTUAL_ENV=$(abspath $(WHEEL_VENV)) bin/masonry-dem validate --quiet

# The documentation site (mkdocs.yml: docs/*.md and the API reference from the docstrings) into out/site,
# warnings as errors. The extra `docs` (mkdocs-material, mkdocstrings) is installed by pip.
docs: develop $(VENV)/.extra-docs
	NO_MKDOCS_2_WARNING=1 $(VENV)/bin/mkdocs build --strict -d out/site

bench:
	cargo bench

clean:
	rm -rf $(VENV) target out
