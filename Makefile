# Two commands do all set-up on a fresh machine:
#   make demo   -> builds uvfeat into .venv and runs `uvfeat demo` on the built-in Spot mesh
#   make test   -> builds uvfeat into .venv and runs every test (cargo test + pytest)
PYTHON ?= python3
VENV := .venv
BIN := $(VENV)/bin
DEMO_OUT ?= uvfeat-out/demo

PEERS_VENV := .venv-peers
PEERS_BIN := $(PEERS_VENV)/bin
PEERS_ARGS ?=
EXPERIMENTS_ARGS ?=

.PHONY: demo test test-rs test-py install install-test bench bench-noise bench-peers experiments clean

# The package's own dependencies come from pyproject.toml: `install` brings what uvfeat needs to
# run, `install-test` adds the extras the tests exercise (test, batch, video, view, bake).
TEST_EXTRAS := test,batch,video,view,bake

$(BIN)/python:
	$(PYTHON) -m venv $(VENV)

install: $(BIN)/python
	$(BIN)/python -m pip install -q --upgrade pip "maturin>=1.9.4,<2"
	VIRTUAL_ENV=$(abspath $(VENV)) $(BIN)/maturin develop --release -q

install-test: $(BIN)/python
	$(BIN)/python -m pip install -q --upgrade pip "maturin>=1.9.4,<2"
	VIRTUAL_ENV=$(abspath $(VENV)) $(BIN)/maturin develop --release -q --extras $(TEST_EXTRAS)

demo: install
	$(BIN)/uvfeat demo --out $(DEMO_OUT)

test-rs:
	cargo clippy --version >/dev/null 2>&1 || rustup component add clippy
	cargo clippy --workspace --all-targets -q -- -D warnings
	cargo test --workspace --exclude uvfeat-python

# One process per core, up to 4: the suite waits on subprocesses, clusters and one-thread Python
# as much as on the engine's parallel loops.
test-py: install-test
	$(BIN)/python -m pytest -q -n auto --maxprocesses 4 --dist worksteal tests

test: test-rs test-py

bench: install-test
	$(BIN)/python benches/bench_atlas.py
	$(BIN)/python benches/bench_features.py
	$(BIN)/python benches/bench_animate.py
	$(BIN)/python benches/bench_reference.py --exact

# Noise study of the integral and fit estimators (docs/NOISE.md); NOISE_ARGS=--quick for a subset.
NOISE_ARGS ?= --compute-resolution 256
bench-noise: install-test
	$(BIN)/python benches/bench_noise.py $(NOISE_ARGS)

# The paper's evaluation (DESIGN.md §5.2-§5.8) in one run, ~25-40 min on 2 cores: docs/EXPERIMENTS.md,
# docs/experiments/results.json and plots. EXPERIMENTS_ARGS=--quick for a smoke run (written to
# uvfeat-out/experiments-quick/), --only table1,radius, --resume, --report-only.
experiments: install-test
	$(BIN)/python benches/experiments.py $(EXPERIMENTS_ARGS)

# Peers benchmark (docs/PEERS.md): libigl, trimesh, pymeshlab, trueform in their own venv, next to
# a uvfeat wheel built from this tree. PEERS_ARGS=--quick for the 50K-face subset.
bench-peers: install-test
	test -x $(PEERS_BIN)/python || $(PYTHON) -m venv $(PEERS_VENV)
	$(PEERS_BIN)/python -m pip install -q --upgrade pip
	$(PEERS_BIN)/python -m pip install -q -r benches/peers/requirements.txt
	rm -rf target/peers-wheel
	$(BIN)/maturin build --release -q -o target/peers-wheel
	$(PEERS_BIN)/python -m pip install -q --force-reinstall --no-deps target/peers-wheel/uvfeat-*.whl
	$(PEERS_BIN)/python benches/peers/bench_peers.py $(PEERS_ARGS)

clean:
	rm -rf $(VENV) $(PEERS_VENV) target uvfeat-out
