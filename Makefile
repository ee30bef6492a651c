# The two commands of the README. Both set up a fresh machine first (scripts/setup.sh).
.PHONY: demo test setup validate

setup:
	scripts/setup.sh

# Runs a bundled scene end to end: writes out/flyer_plate/{summary.json,final.csv,snapshots.h5,snapshots.xdmf}.
demo: setup
	cargo run --release -p gsph -- run cases/flyer_plate.toml --out out/flyer_plate

# Runs the test suite (what CI runs).
test:
	scripts/test.sh

# Full-size validation runs and figures (not CI; about 90 minutes): out/validation/.
validate:
	scripts/validate.sh
