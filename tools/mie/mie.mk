# tools/mie: the Lorenz-Mie solver (build/cumulo-mie), its unit tests (build/test_mie) and CLI/table tests.

MIE_LIB_SRC := tools/mie/mie.c tools/mie/water.c tools/mie/colour.c tools/mie/mietable.c tools/mie/resonance.c
MIE_LIB_OBJ := $(MIE_LIB_SRC:%.c=$(B)/obj/%.o)
MIE_OBJ_DIR := $(B)/obj/tools/mie

$(MIE_OBJ_DIR)/%.o: tools/mie/%.c
	@mkdir -p $(dir $@)
	$(CC) $(CFLAGS_COMMON) -c $< -o $@

$(MIE_OBJ_DIR)/test_mie.o: tools/mie/test_mie.c
	@mkdir -p $(dir $@)
	$(CC) $(CFLAGS_COMMON) $(call pc_cflags,cmocka) -c $< -o $@

$(B)/cumulo-mie: $(MIE_OBJ_DIR)/main.o $(MIE_LIB_OBJ)
	@mkdir -p $(dir $@)
	$(CC) $^ -o $@ $(LDLIBS_COMMON)

# The unit tests read data/mie_cloud.tbl, so they also run against the committed table.
$(B)/test_mie: $(MIE_OBJ_DIR)/test_mie.o $(MIE_LIB_OBJ)
	@mkdir -p $(dir $@)
	$(CC) $^ -o $@ $(call pc_libs,cmocka) $(LDLIBS_COMMON)

ALL_BINS    += $(B)/cumulo-mie
# The shell test (bad arguments, output formats, regenerating data/mie_cloud.tbl) runs from the repository root.
CHECK_TESTS += $(B)/test_mie tools/mie/test_mie_cli.sh

.PHONY: mie-table mie-plot mie-stress
# Regenerates the committed table (data/mie_cloud.md records the command and its checksum).
mie-table: $(B)/cumulo-mie
	$(B)/cumulo-mie --table data/mie_cloud.tbl
mie-plot:
	sh tools/mie/plot_phase.sh data/mie_cloud.tbl docs/mie_phase.png
# Full-table convergence (every angle, half dx and half the wavelength step must change nothing by 1e-4; ~3 CPU
# minutes). Hooked into `make stress`, which tests/tests.mk defines.
mie-stress: $(B)/cumulo-mie
	sh tests/run_tests.sh tools/mie/mie_stress.sh
stress: mie-stress
