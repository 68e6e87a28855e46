# mk/sweep.mk: `make sweep`: the speed/accuracy sweep against the path tracer (issue 7, README "Performance").
# Runs `cumulo sweep` with its defaults into build/sweep/ (references cached in build/sweep/ref/), then copies the
# plot, the table, the presets and the CSV to docs/ (sweep_pareto.png, sweep.md, sweep_presets.txt, sweep_results.csv)
# for the README. Not part of `make check`. SWEEP_ARGS adds options (e.g. --quick).
SWEEP_DIR  ?= $(B)/sweep
SWEEP_ARGS ?=

sweep: deps-check $(B)/cumulo $(B)/cumulo-pt
	@command -v gnuplot >/dev/null 2>&1 || echo "sweep: gnuplot not found: no pareto.png will be drawn (install gnuplot-nox); the CSV and tables are still written"
	@start=$$(date +%s); \
	$(TEST_ENV) $(B)/cumulo sweep --out $(SWEEP_DIR) $(SWEEP_ARGS) || exit $$?; \
	echo "sweep: took $$(( $$(date +%s) - start )) s"
	cp $(SWEEP_DIR)/sweep.md docs/sweep.md
	cp $(SWEEP_DIR)/presets.txt docs/sweep_presets.txt
	cp $(SWEEP_DIR)/sweep.csv docs/sweep_results.csv
	@if [ -f $(SWEEP_DIR)/pareto.png ]; then cp $(SWEEP_DIR)/pareto.png docs/sweep_pareto.png && echo "sweep: docs/sweep.md and docs/sweep_pareto.png updated"; \
	else echo "sweep: docs/sweep.md updated; no $(SWEEP_DIR)/pareto.png (gnuplot missing?), docs/sweep_pareto.png left as it was"; fi
