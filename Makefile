# The two quick-start commands go through here so that a fresh machine gets
# the system packages the build needs (GNU m4 for GMP) before cargo runs.
.PHONY: deps report test

deps:
	@./scripts/ensure-deps.sh

# The main job: the quick error-analysis report, written to report/index.html.
report: deps
	cargo run --release -- report --quick --out report

# The test suite (release mode: the MPFR and property tests run much faster,
# and the build is shared with the benches and the CLI).
test: deps
	cargo test --release --all-features
