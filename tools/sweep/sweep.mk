# tools/sweep/sweep.mk: `cumulo-sweep`, the speed/accuracy sweep against the path tracer (README "Performance"), and
# `make sweep`, which runs it with its defaults into build/sweep/ (references cached in build/sweep/ref/) and copies
# the plot, the table, the presets and the CSV to docs/. Not part of `make check`. SWEEP_ARGS adds options.
# The sweep links the path tracer (tools/pathtrace/pt.o) and renders its references in-process.
SWEEP_SRCS := $(addprefix tools/sweep/,main.c options.c knobs.c reference.c metrics.c measure.c choose.c report.c \
              sweep.c methods.c fit.c score.c)
SWEEP_OBJS := $(SWEEP_SRCS:%.c=$(B)/obj/%.o)
CFLAGS_SWEEP := $(CFLAGS_BASE) -Iinclude -Isrc/core -Iapp -Itools/pathtrace $(PLATFORM_CPPFLAGS) -I$(B)/gen \
                $(LIB_CFLAGS)
$(eval $(call flags_rule,sweep,$(CC) $(CFLAGS_SWEEP)))

$(B)/obj/tools/sweep/%.o: tools/sweep/%.c $(B)/flags/sweep | $(B)/gen/version.h
	@mkdir -p $(dir $@)
	$(CC) $(CFLAGS_SWEEP) -c $< -o $@

# The reference cache key includes a checksum of the code that computes a reference: the path tracer's object and
# the core's (what build/cumulo-pt is made of, less its command line). Rewritten only when it changes.
SWEEP_PT_CODE := $(PT_OBJS) $(CORE_OBJS)
$(B)/gen/sweep_pt_code.h: $(SWEEP_PT_CODE)
	@mkdir -p $(@D)
	@printf '#define SW_PT_CODE "%s"\n' "$$(cat $(SWEEP_PT_CODE) | cksum | tr ' ' '-')" >$@.tmp; \
	  if cmp -s $@.tmp $@; then rm -f $@.tmp; else mv -f $@.tmp $@; fi
$(B)/obj/tools/sweep/reference.o: $(B)/gen/sweep_pt_code.h

SWEEP_LINK := $(SWEEP_OBJS) $(PT_OBJS) $(B)/obj/app/session.o $(B)/obj/app/options.o $(PLATFORM_OBJS) $(B)/libcumulo.a
$(B)/cumulo-sweep: $(SWEEP_LINK)
	$(CC) -o $@ $(SWEEP_LINK) $(PLATFORM_LIBS) $(LIB_LIBS) -lpthread
ALL_BINS += $(B)/cumulo-sweep

SWEEP_DIR  ?= $(B)/sweep
SWEEP_ARGS ?=
sweep: $(B)/cumulo-sweep
	@command -v gnuplot >/dev/null 2>&1 || echo "sweep: gnuplot not found: no pareto.png will be drawn (make deps-plots); the CSV and tables are still written"
	@start=$$(date +%s); \
	$(TEST_ENV) $(B)/cumulo-sweep --out $(SWEEP_DIR) $(SWEEP_ARGS) || exit $$?; \
	echo "sweep: took $$(( $$(date +%s) - start )) s"
	cp $(SWEEP_DIR)/sweep.md docs/sweep.md
	cp $(SWEEP_DIR)/presets.txt docs/sweep_presets.txt
	cp $(SWEEP_DIR)/sweep.csv docs/sweep_results.csv
	@if [ -f $(SWEEP_DIR)/pareto.png ]; then cp $(SWEEP_DIR)/pareto.png docs/sweep_pareto.png && echo "sweep: docs/sweep.md and docs/sweep_pareto.png updated"; \
	else echo "sweep: docs/sweep.md updated; no $(SWEEP_DIR)/pareto.png (gnuplot missing?), docs/sweep_pareto.png left as it was"; fi

# `make sweep-methods`: cumulo-sweep --methods (issue 14), Kol's method against the uniform ray march on the four
# views written for it (scenes/sweep_*_hg.scene: Henyey-Greenstein, a constant sky), time at 320x240 as the outside
# comparison measured it; copies the table, the CSV and the plot to docs/. Not part of `make check`.
METHODS_DIR  ?= $(B)/sweep-methods
METHODS_ARGS ?=
sweep-methods: $(B)/cumulo-sweep
	@start=$$(date +%s); \
	$(TEST_ENV) $(B)/cumulo-sweep --methods --out $(METHODS_DIR) --ref-dir $(SWEEP_DIR)/ref $(METHODS_ARGS) || exit $$?; \
	echo "sweep-methods: took $$(( $$(date +%s) - start )) s"
	sh scripts/methods_plot.sh $(METHODS_DIR) || true
	cp $(METHODS_DIR)/methods.md docs/methods.md
	cp $(METHODS_DIR)/methods.csv docs/methods.csv
	@if [ -f $(METHODS_DIR)/methods.png ]; then cp $(METHODS_DIR)/methods.png docs/methods.png; fi

# `make fit-octaves`: cumulo-sweep --fit-octaves (issue 14), the octave model of multiple scattering fitted to the path
# tracer on the training views in scenes/fit/ (about 10 min, references cached with the sweep's); copies the report
# to docs/ms_octaves_fit.md and the chosen keys to docs/ms_octaves_fit.txt, which src/core/scene_keys.c's defaults
# must match (tests/app/test_cli.sh). Not part of `make check`.
.PHONY: sweep-methods fit-octaves
FIT_DIR  ?= $(B)/fit-octaves
FIT_ARGS ?=
fit-octaves: $(B)/cumulo-sweep
	@start=$$(date +%s); \
	$(TEST_ENV) $(B)/cumulo-sweep --fit-octaves --out $(FIT_DIR) --ref-dir $(SWEEP_DIR)/ref $(FIT_ARGS) || exit $$?; \
	echo "fit-octaves: took $$(( $$(date +%s) - start )) s"
	cp $(FIT_DIR)/fit.md docs/ms_octaves_fit.md
	cp $(FIT_DIR)/fit.txt docs/ms_octaves_fit.txt
