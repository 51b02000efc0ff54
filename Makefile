# Two commands do all set-up on a fresh machine:
#   make demo   -> builds uvfeat into .venv and runs `uvfeat demo` on the built-in Spot mesh
#   make test   -> builds uvfeat into .venv and runs every test (cargo test + pytest)
PYTHON ?= python3
VENV := .venv
BIN := $(VENV)/bin
DEMO_OUT ?= uvfeat-out/demo

.PHONY: demo test test-rs test-py install bench clean

$(BIN)/python:
	$(PYTHON) -m venv $(VENV)

install: $(BIN)/python
	$(BIN)/python -m pip install -q --upgrade pip
	$(BIN)/python -m pip install -q "maturin>=1.9.4,<2" numpy trimesh xatlas matplotlib pillow rich pygltflib pytest pygeodesic
	$(BIN)/maturin develop --release -q

demo: install
	$(BIN)/uvfeat demo --out $(DEMO_OUT)

test-rs:
	cargo test --workspace --exclude uvfeat-python

test-py: install
	$(BIN)/python -m pytest -q tests

test: test-rs test-py

bench: install
	$(BIN)/python benches/bench_atlas.py
	$(BIN)/python benches/bench_features.py
	$(BIN)/python benches/bench_animate.py
	$(BIN)/python benches/bench_reference.py --exact

clean:
	rm -rf $(VENV) target uvfeat-out
