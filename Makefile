# The two commands of the README's quick start: `make demo` and `make test`.
# Both create .venv, install the package (and, when run as root, the Debian
# packages it needs), then run their job.
PYTHON ?= python3
VENV   := .venv
BIN    := $(VENV)/bin
STAMP  := $(VENV)/.installed
DEBS   := libosmesa6 libegl1 libegl-mesa0 libgl1-mesa-dri espeak-ng

.PHONY: demo test test-all lint bench matrix partners dnf-vs-fsm learning setup debs clean wheel-check

setup: $(STAMP)

$(STAMP): pyproject.toml
	@$(MAKE) --no-print-directory debs
	$(PYTHON) -m venv $(VENV)
	$(BIN)/pip install --quiet --upgrade pip
	$(BIN)/pip install --quiet -e '.[test,lint]'
	@touch $(STAMP)

# Installs missing Debian packages when run as root; otherwise says what is missing.
debs:
	@missing=""; for p in $(DEBS); do dpkg -s $$p >/dev/null 2>&1 || missing="$$missing $$p"; done; \
	if [ -n "$$missing" ]; then \
	  if [ "$$(id -u)" = "0" ]; then apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq $$missing; \
	  else echo "note: missing Debian packages:$$missing (install them as root for rendering and speech)"; fi; \
	fi

# The main job: the seed's Fig. 3-4 storyline as one episode, to render/paper-fig3-4/video.mp4.
# `assistbot run` exits 1 when the person did not drink; the demo still shows what happened.
# vision: the robot sees through its head cameras; PERCEPTION=oracle reads ground truth (labelled as such).
PERCEPTION ?= vision
demo: $(STAMP)
	$(BIN)/assistbot run paper-fig3-4 --perception $(PERCEPTION) --force || [ $$? -eq 1 ]

# Each test file runs in one of $(TEST_WORKERS) worker processes (pytest-xdist); TEST_WORKERS=0 runs them in this one.
TEST_WORKERS ?= auto
test: $(STAMP)
	$(BIN)/python -m pytest -m "not slow" -q -n $(TEST_WORKERS) --dist loadfile

# The linter (ruff, configured in pyproject.toml) and the type check (mypy on fields/, task/, cognition/).
lint: $(STAMP)
	$(BIN)/ruff check src tests benchmarks examples
	$(BIN)/mypy

test-all: $(STAMP)
	$(BIN)/python -m pytest -q -n $(TEST_WORKERS) --dist loadfile

# The task space as a benchmark: 24 arrangements x 3 profiles x 3 seeds with vision (216 episodes,
# two workers; about 75 min on 2 cores: 24 min a seed), then its report. Resumes where it stopped.
WORKERS ?= 2
matrix: $(STAMP)
	$(BIN)/assistbot sweep scenarios/sweeps/matrix.yaml --workers $(WORKERS) --out render/sweeps/matrix
	$(BIN)/assistbot report render/sweeps/matrix

# People the robot has never met: 200 episodes of partners 1000-1099 of the population on the task space
# (scenarios/sweeps/partners.yaml), vision, two workers, then the report by partner attribute. Resumes.
partners: $(STAMP)
	$(BIN)/assistbot sweep scenarios/sweeps/partners.yaml --workers $(WORKERS) --out render/sweeps/partners
	$(BIN)/assistbot report render/sweeps/partners

# The field architecture against the state-machine baseline under degraded cues (scenarios/sweeps/dnf-vs-fsm/):
# one sweep per perturbation, 486 episodes in all, each reported per agent, then all of them side by side in
# render/sweeps/dnf-vs-fsm/overview/. About 2 h on 2 cores; resumes.
DNF_VS_FSM := $(wildcard scenarios/sweeps/dnf-vs-fsm/*.yaml)
dnf-vs-fsm: $(STAMP)
	@for f in $(DNF_VS_FSM); do \
	  $(BIN)/assistbot sweep $$f --workers $(WORKERS) --no-progress || exit $$?; \
	done
	$(BIN)/assistbot report $(patsubst scenarios/sweeps/%.yaml,render/sweeps/%,$(DNF_VS_FSM)) --by agent

# Learning from the user, into render/learn/: the default person (the seed's Fig. 3-4 and Fig. 5, ten episodes
# each learning in a row, each beside the same episode with the priors: learning changes nothing), then the
# partner with the swapped grips (scenarios/learning/swapped-pour-hws.yaml, five episodes from three seeds, and
# the seed's person there with the priors). Vision; 80 episodes, about 60 min on one core.
SWAPPED := scenarios/learning/swapped-pour-hws.yaml
learning: $(STAMP)
	$(BIN)/assistbot learn paper-fig3-4 --episodes 10 --compare --out render/learn/paper-fig3-4 --force
	$(BIN)/assistbot learn paper-fig5 --episodes 10 --compare --out render/learn/paper-fig5 --force
	@for s in 0 10 20; do \
	  $(BIN)/assistbot learn $(SWAPPED) --episodes 5 --compare --seed $$s --out render/learn/swapped-$$s --force || exit $$?; \
	done
	$(BIN)/assistbot learn $(SWAPPED) --set human.grip_convention=seed --episodes 5 --compare --out render/learn/seed-person --force

# The wheel as a user installs it: built, installed into a fresh venv, run from a temporary folder.
wheel-check:
	bash .ci/wheel-check

bench: $(STAMP)
	@for b in benchmarks/*.py; do echo "== $$b"; $(BIN)/python $$b || exit 1; done

clean:
	rm -rf $(VENV) render/* build *.egg-info src/*.egg-info
	touch render/.gitkeep
