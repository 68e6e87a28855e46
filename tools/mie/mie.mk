# tools/mie: the Lorenz-Mie solver (build/cumulo-mie) that makes data/mie_cloud.tbl. Its tests are in tests/mie/.
MIE_LIB_SRCS := tools/mie/mie.c tools/mie/water.c tools/mie/colour.c tools/mie/mietable.c tools/mie/mietable_grid.c \
                tools/mie/mietable_out.c tools/mie/resonance.c
MIE_LIB_OBJS := $(MIE_LIB_SRCS:%.c=$(B)/obj/%.o)
CFLAGS_TOOLS := $(CFLAGS_BASE) -Iinclude -Isrc/core -I$(B)/gen
$(eval $(call flags_rule,tools,$(CC) $(CFLAGS_TOOLS)))

$(B)/obj/tools/mie/%.o: tools/mie/%.c $(B)/flags/tools | $(B)/gen/version.h
	@mkdir -p $(dir $@)
	$(CC) $(CFLAGS_TOOLS) -c $< -o $@

$(B)/cumulo-mie: $(B)/obj/tools/mie/main.o $(MIE_LIB_OBJS)
	$(CC) $^ -o $@ -lm

ALL_BINS += $(B)/cumulo-mie

.PHONY: mie-table mie-plot mie-stress
# Regenerates the committed table (data/mie_cloud.md records the command and its checksum).
mie-table: $(B)/cumulo-mie
	$(B)/cumulo-mie --table data/mie_cloud.tbl
mie-plot:
	sh tools/mie/plot_phase.sh data/mie_cloud.tbl docs/mie_phase.png
# Full-table convergence (every angle, half dx and half the wavelength step must change nothing by 1e-4; ~3 CPU
# minutes), part of `make stress`.
mie-stress: $(B)/cumulo-mie
	$(TEST_ENV) sh tests/run_tests.sh tests/mie/mie_stress.sh
stress: mie-stress
