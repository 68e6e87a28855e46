# tools/slab: Monte Carlo slab transport (build/cumulo-slab), the model fitter, and their tests.
SLAB_DIR := tools/slab
SLAB_OBJ := $(B)/obj/tools/slab
SLAB_CFLAGS := $(CFLAGS_COMMON) $(call pc_cflags,gsl)
SLAB_LIBS := $(call pc_libs,gsl) $(LDLIBS_COMMON)

$(SLAB_OBJ)/%.o: $(SLAB_DIR)/%.c
	@mkdir -p $(dir $@)
	$(CC) $(SLAB_CFLAGS) $(call pc_cflags,cmocka) -c $< -o $@

$(B)/cumulo-slab: $(SLAB_OBJ)/main.o $(SLAB_OBJ)/slab.o
	@mkdir -p $(dir $@)
	$(CC) $(SLAB_CFLAGS) $^ -o $@ $(SLAB_LIBS)

$(B)/cumulo-slab-fit: $(SLAB_OBJ)/fit.o $(SLAB_OBJ)/fitlib.o
	@mkdir -p $(dir $@)
	$(CC) $(SLAB_CFLAGS) $^ -o $@ $(SLAB_LIBS)

$(B)/test_slab: $(SLAB_OBJ)/test_slab.o $(SLAB_OBJ)/slab.o $(SLAB_OBJ)/fitlib.o
	@mkdir -p $(dir $@)
	$(CC) $(SLAB_CFLAGS) $^ -o $@ $(call pc_libs,cmocka) $(SLAB_LIBS)

# finite-cloud side study (README, "R and T vs thickness"): a sphere lit from the zenith
$(B)/cumulo-slab-sphere: $(SLAB_OBJ)/sphere.o $(SLAB_OBJ)/slab.o
	@mkdir -p $(dir $@)
	$(CC) $(SLAB_CFLAGS) $^ -o $@ $(SLAB_LIBS)

ALL_BINS += $(B)/cumulo-slab $(B)/cumulo-slab-fit $(B)/cumulo-slab-sphere
CHECK_TESTS += $(B)/test_slab $(SLAB_DIR)/test_slab_cli.sh

# Optional MPI build of the same source: only when mpicc exists (Open MPI's dev package is not installed here).
SLAB_MPICC := $(shell command -v mpicc 2>/dev/null)
ifneq ($(SLAB_MPICC),)
$(SLAB_OBJ)/mpi/%.o: $(SLAB_DIR)/%.c
	@mkdir -p $(dir $@)
	$(SLAB_MPICC) $(SLAB_CFLAGS) -DCU_SLAB_MPI -c $< -o $@

$(B)/cumulo-slab-mpi: $(SLAB_OBJ)/mpi/main.o $(SLAB_OBJ)/mpi/slab.o
	$(SLAB_MPICC) $(SLAB_CFLAGS) $^ -o $@ $(SLAB_LIBS)

ALL_BINS += $(B)/cumulo-slab-mpi
endif

# make stress: the long slab tests (T to 0.5 % for thick slabs; ~1-2 min on 2 cores). A prerequisite-only rule, so the
# stress recipe in tests/tests.mk is not overridden.
stress: slab-stress
slab-stress: $(B)/test_slab
	$(TEST_ENV) B=$(B) sh tests/run_tests.sh $(SLAB_DIR)/test_slab_stress.sh
.PHONY: slab-stress
