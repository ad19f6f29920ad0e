# The two commands of the README: `make demo` and `make test`. Both set everything up from scratch.
PYTHON ?= python3
VENV := .venv
PY := $(VENV)/bin/python
export VIRTUAL_ENV := $(abspath $(VENV))

.PHONY: demo test develop rust-test py-test bench clean

$(VENV)/.deps: pyproject.toml
	$(PYTHON) -m venv $(VENV)
	$(PY) -m pip install -q --upgrade pip
	$(PY) -m pip install -q "maturin>=1.5,<2" "numpy>=1.21" "matplotlib>=3.5" "tqdm>=4.60" "meshio>=5" "pytest>=7" "hypothesis>=6"
	touch $@

# Release build of the extension, installed into .venv (python sources are linked, not copied).
develop: $(VENV)/.deps
	$(VENV)/bin/maturin develop --release -q

demo: develop
	$(VENV)/bin/masonry-dem demo --plot out/demo.png

rust-test:
	cargo test --release

py-test: develop
	$(PY) -m pytest -q tests/python

test: rust-test py-test

bench:
	cargo bench

clean:
	rm -rf $(VENV) target out
