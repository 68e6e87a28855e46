# tools/slab: Monte Carlo slab transport (build/cumulo-slab), the model fitter (GSL) and the finite-cloud sphere
# study; all use GSL (special functions, the fitter's least squares) and are built when ./configure finds it.
# Tests are in tests/slab/.
SLAB_CFLAGS := $(CFLAGS_TOOLS) $(GSL_CFLAGS)

$(B)/obj/tools/slab/%.o: tools/slab/%.c $(B)/flags/tools | $(B)/gen/version.h
	@mkdir -p $(dir $@)
	$(CC) $(SLAB_CFLAGS) -c $< -o $@

$(B)/cumulo-slab: $(B)/obj/tools/slab/main.o $(B)/obj/tools/slab/slab.o $(B)/obj/tools/slab/slab_phase.o
	$(CC) $^ -o $@ $(GSL_LIBS) -lm -lpthread

$(B)/cumulo-slab-fit: $(B)/obj/tools/slab/fit.o $(B)/obj/tools/slab/fitlib.o
	$(CC) $^ -o $@ $(GSL_LIBS) -lm

# finite-cloud side study (README, "R and T vs thickness"): a sphere lit from the zenith
$(B)/cumulo-slab-sphere: $(B)/obj/tools/slab/sphere.o $(B)/obj/tools/slab/slab.o $(B)/obj/tools/slab/slab_phase.o
	$(CC) $^ -o $@ $(GSL_LIBS) -lm -lpthread

ifeq ($(HAVE_GSL),1)
ALL_BINS += $(B)/cumulo-slab $(B)/cumulo-slab-sphere $(B)/cumulo-slab-fit
endif

# Optional MPI build of the same source: only when mpicc exists (Open MPI's dev package is not installed here).
SLAB_MPICC := $(shell command -v mpicc 2>/dev/null)
ifneq ($(SLAB_MPICC),)
$(B)/obj/tools/slab/mpi/%.o: tools/slab/%.c
	@mkdir -p $(dir $@)
	$(SLAB_MPICC) $(SLAB_CFLAGS) -DCU_SLAB_MPI -c $< -o $@
$(B)/cumulo-slab-mpi: $(B)/obj/tools/slab/mpi/main.o $(B)/obj/tools/slab/mpi/slab.o $(B)/obj/tools/slab/mpi/slab_phase.o
	$(SLAB_MPICC) $(SLAB_CFLAGS) $^ -o $@ $(GSL_LIBS) -lm -lpthread
ALL_BINS += $(B)/cumulo-slab-mpi
endif
