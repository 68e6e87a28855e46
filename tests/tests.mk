# tests/tests.mk: every test of `make check`, one layout: tests/<part>/test_*.c (cmocka) and tests/<part>/test_*.sh
# (tests/lib.sh), all run by tests/run_tests.sh. Every test program is declared through one template.
TEST_CPPFLAGS := -Iinclude -Isrc/core -Isrc/gpu -I$(B)/gen/lib $(PLATFORM_CPPFLAGS) -Iapp -Itests/gpu -Itools/pathtrace \
                 -Itools/mie -Itools/slab
CFLAGS_TEST := $(CFLAGS_BASE) $(TEST_CPPFLAGS) $(CMOCKA_CFLAGS) $(LIB_CFLAGS) $(EGL_CFLAGS) $(OSMESA_CFLAGS)
$(eval $(call flags_rule,test,$(CC) $(CFLAGS_TEST)))

# $(call test_program,NAME,SOURCES (.c, then .o and .a in link order),EXTRA_CFLAGS,EXTRA_LIBS)
define test_program
$(B)/$(1): $(2) $(B)/flags/test | $(B)/gen/version.h
	@mkdir -p $$(@D)
	$$(CC) $$(CFLAGS_TEST) $(3) -o $$@ $$(filter %.c %.o %.a,$$^) $(4) $$(CMOCKA_LIBS) -lm -lpthread
CHECK_TESTS += $(B)/$(1)
endef

LIB   := $(B)/libcumulo.a
CORE  := $(B)/libcumulo-core.a
# What the image tests link to open a headless context (EGL surfaceless and OSMesa).
HEADLESS := tests/gpu/render_util.c app/session.c platform/display/egl_common.c platform/display/egl_surfaceless.c \
            platform/display/osmesa.c platform/display/headless_fbo.c
HEADLESS_LIBS := $(EGL_LIBS) $(OSMESA_LIBS) $(LIB_LIBS)

# core: the scene and its key table (docs included), phase tables, geometry and a C twin of the shader's per-sample maths.
$(eval $(call test_program,test_scene,tests/core/test_scene.c $(CORE),,$(LIB_LIBS)))
$(eval $(call test_program,test_phase,tests/core/test_phase.c $(CORE),,$(LIB_LIBS)))
$(eval $(call test_program,test_math,tests/core/test_math.c $(CORE),,$(LIB_LIBS)))
$(eval $(call test_program,test_keys,tests/core/test_keys.c $(CORE),,$(LIB_LIBS)))
CHECK_TESTS += tests/core/test_keys.sh
$(eval $(call test_program,test_tonemap,tests/core/test_tonemap.c $(CORE),,$(LIB_LIBS)))
# The sun from date, time and place (SPA) against published values, and the UTC parser on hostile text.
$(eval $(call test_program,test_solar,tests/core/test_solar.c $(CORE),,$(LIB_LIBS)))
# Generated cumulus layers: coverage, the size distribution's exponent, no overlap, determinism.
$(eval $(call test_program,test_layer,tests/core/test_layer.c $(CORE),,$(LIB_LIBS)))
# ms.mode = diffusion's solver against closed forms (slab energy and transmission, symmetry, warm start, extremes).
$(eval $(call test_program,test_ms_diffusion,tests/core/test_ms_diffusion.c $(CORE),,$(LIB_LIBS)))
# ms.lobe's table of lobe-only light against closed forms (HG's self-convolution, the scaled beam's energy), extremes.
$(eval $(call test_program,test_ms_lobe,tests/core/test_ms_lobe.c $(CORE),,$(LIB_LIBS)))
# quality.noise_baked's CPU twin against the fractal noise it stands in for.
$(eval $(call test_program,test_noise_baked,tests/core/test_noise_baked.c $(CORE),,$(LIB_LIBS)))
# The frame budget's controller (quality.target_fps) driven by frame costs of the test's own.
$(eval $(call test_program,test_budget,tests/core/test_budget.c $(CORE),,$(LIB_LIBS)))
# -Wno-pedantic: _Float16 is an ISO/IEC TS 18661-3 extension type, used only here to emulate mediump.
$(eval $(call test_program,test_precision,tests/core/test_precision.c,-Wno-pedantic,))

# gpu: renders through both headless back ends against references, closed forms and the CPU (test_sky: the sky pass
# against the CPU's Preetham model; test_temporal: the temporal grid against whole frames; test_composite: the
# one-pass composite of low-resolution clouds; test_impostor: clouds drawn from impostors against the full render;
# test_sun_bands: a creeping sun's maps made a band a frame against whole maps; test_ground_drift: the ground's
# shadow following clouds on the wind against whole renders; test_msd_frames: diffusion grids solved again over
# frames against the same solve in one; test_edge_refine: quality.edge_refine against full-resolution frames).
$(foreach t,render sunmap ms fallback field sky temporal composite impostor sun_bands ground_drift msd_frames \
  edge_refine,\
  $(eval $(call test_program,test_$(t),tests/gpu/test_$(t).c $(HEADLESS) $(LIB),,$(HEADLESS_LIBS))))
CHECK_TESTS += tests/gpu/test_ms_slab.sh tests/gpu/test_octaves_thin.sh tests/gpu/test_ms_diffusion.sh tests/gpu/test_ms_lobe.sh \
  tests/gpu/test_sun_planar.sh
# Where on screen a cloud can be (camera.c), against points of its bounds from random views: no GL.
$(eval $(call test_program,test_camera_rect,tests/gpu/test_camera_rect.c $(LIB),,$(LIB_LIBS)))
# Where the sky's grid may use larger cells (sky_grid.c), against the interpolation at every pixel: no GL.
$(eval $(call test_program,test_sky_plan,tests/gpu/test_sky_plan.c $(LIB),,$(LIB_LIBS)))
# How a ray is marched: the uniform method, Kol's boundary knots against the path tracer's transmittance, baked noise.
$(eval $(call test_program,test_march,tests/gpu/test_march.c $(HEADLESS) $(PT_OBJS) $(LIB),,$(HEADLESS_LIBS)))
# Issue 7's extremes matrix (it reads the temporal history and impostor images back with GLES itself).
$(eval $(call test_program,test_extremes,tests/gpu/test_extremes.c $(HEADLESS) $(LIB),,$(HEADLESS_LIBS) $(GLES_LIBS)))
# The extremes matrix of every key's range, through the GPU renderer and the path tracer.
$(eval $(call test_program,test_ranges,tests/gpu/test_ranges.c $(HEADLESS) $(PT_OBJS) $(LIB),,$(HEADLESS_LIBS)))
# embed: the test is the host, drawing with GLES itself (glvnd's libGLESv2 dispatches to the EGL context); the
# low-resolution clouds against its depth too (test_downsample).
$(foreach t,embed embed_state shadows downsample,\
  $(eval $(call test_program,test_$(t),tests/gpu/test_$(t).c tests/gpu/host_util.c $(HEADLESS) $(LIB),,\
    $(HEADLESS_LIBS) $(GLES_LIBS))))
CHECK_TESTS += tests/gpu/test_host_scene.sh
# The frame budget (quality.target_fps): the ladder walked with timer queries and the wall clock, a generous budget
# changing nothing, a host's own timer query (it draws GLES itself, like the embedding tests).
$(eval $(call test_program,test_frame_budget,tests/gpu/test_frame_budget.c $(HEADLESS) $(LIB),,$(HEADLESS_LIBS) \
  $(GLES_LIBS)))
# Pass timing (cu_renderer_set_profiling): the wall clock on llvmpipe, GPU timestamps forced on GLES and desktop GL,
# inside a host's own timer query (it draws GLES itself).
$(eval $(call test_program,test_profile,tests/gpu/test_profile.c $(HEADLESS) $(LIB),,$(HEADLESS_LIBS) $(GLES_LIBS)))
# A sky of many clouds: compositing, clear sky, wind, wrap-around, no pops over 10 minutes, a day without NaN (it
# draws into float framebuffers of its own, so it links GLES like the embedding tests).
$(eval $(call test_program,test_sky_field,tests/gpu/test_sky_field.c $(HEADLESS) $(LIB),,$(HEADLESS_LIBS) $(GLES_LIBS)))

# app: the cumulo program's command line.
CHECK_TESTS += tests/app/test_cli.sh tests/app/test_sky_cli.sh
CHECK_TESTS += tests/app/test_sun_cli.sh tests/app/test_sweep_methods.sh tests/app/test_sweep_fit.sh \
  tests/app/test_sweep_score.sh
# The sweep's cloud metrics (tools/sweep/metrics.c) on images whose answers are known; no GL.
$(eval $(call test_program,test_sweep_metrics,tests/sweep/test_sweep_metrics.c tools/sweep/metrics.c $(CORE),\
  -Itools/sweep,$(LIB_LIBS)))
# How the sweep picks presets (tools/sweep/choose.c) from made-up measurements: by the cloud's error, never flatter.
$(eval $(call test_program,test_sweep_choose,tests/sweep/test_sweep_choose.c tools/sweep/choose.c tools/sweep/knobs.c \
  $(CORE),-Itools/sweep,$(LIB_LIBS)))

# platform: decoders and parsers on recorded input, back ends against fakes of their kernel and libraries.
$(eval $(call test_program,test_quadrature,tests/platform/test_quadrature.c platform/input/quadrature.c,,))
$(eval $(call test_program,test_input,tests/platform/test_input.c platform/input/input.c \
  platform/input/stdin_input.c platform/input/sun_control.c platform/input/knob_speed.c,,))
# --clock: the knob's offset of the time of day and the time shown (cumulo run --clock end to end: test_run_clock.sh).
$(eval $(call test_program,test_clock,tests/platform/test_clock.c platform/input/clock_control.c \
  platform/input/knob_speed.c,,))
$(eval $(call test_program,test_evdev,tests/platform/test_evdev.c platform/input/evdev.c platform/input/input.c,,))
$(eval $(call test_program,test_drm_mode,tests/platform/test_drm_mode.c platform/display/drm_mode.c,,))
$(eval $(call test_program,test_evdev_dev,tests/platform/test_evdev_dev.c tests/platform/fake_dir.c platform/input/evdev.c \
  platform/input/input.c,,-Wl$(,)--wrap=open$(,)--wrap=ioctl$(,)--wrap=read$(,)--wrap=opendir$(,)--wrap=readdir$(,)--wrap=closedir))
ifeq ($(HAVE_DRM),1)
# drm.c against a fake Pi-like display stack (libdrm, GBM and EGL helpers defined in the test, /dev/dri faked).
$(eval $(call test_program,test_drm,tests/platform/test_drm.c tests/platform/fake_dir.c platform/display/drm.c platform/display/drm_probe.c platform/display/drm_mode.c,\
  $(DRM_CFLAGS),-Wl$(,)--wrap=open$(,)--wrap=stat$(,)--wrap=opendir$(,)--wrap=readdir$(,)--wrap=closedir))
endif
# gpio.c and one API's glue against a scripted fake of libgpiod, the same assertions for both: the v2 build finds the
# v2 API in tests/platform/gpiod_v2/gpiod.h, so it runs everywhere; the v1 build needs the v1 header (libgpiod 1.x).
GPIO_TEST_SRCS := tests/platform/test_gpio.c platform/input/gpio.c platform/input/gpio_errors.c platform/input/quadrature.c platform/input/input.c
$(eval $(call test_program,test_gpio_v2,$(GPIO_TEST_SRCS) platform/input/gpio_v2.c,-Itests/platform/gpiod_v2,))
ifeq ($(GPIO_API),1)
$(eval $(call test_program,test_gpio_v1,$(GPIO_TEST_SRCS) platform/input/gpio_v1.c,$(GPIO_CFLAGS),))
endif
# The input set with every input back end of this build, through the table in input_backend.c.
$(eval $(call test_program,test_input_set,tests/platform/test_input_set.c $(filter platform/input/%,$(INPUT_SRCS)),\
  $(GPIO_CFLAGS),$(GPIO_LIBS)))
CHECK_TESTS += tests/platform/test_run.sh tests/platform/test_run_clock.sh tests/platform/test_gpio_sim.sh \
               tests/platform/test_soak.sh

# sim: the host simulation protocols' decoders against host-side encoders, hostile datagrams included.
$(eval $(call test_program,test_cigi,tests/sim/test_cigi.c tests/sim/cigi_encode.c platform/sim/cigi.c,-Itests/sim,))
# Wireshark's CIGI dissector reads our datagrams and Start of Frame as meant (skips without tshark).
CHECK_TESTS += tests/sim/cigi_tshark_check.sh
check: $(B)/cigi_seeds
# ... FlightGear's and X-Plane's on recorded streams (tests/sim/data/) and hostile datagrams.
$(eval $(call test_program,test_fgfs,tests/sim/test_fgfs.c platform/sim/fgfs.c,,))
$(eval $(call test_program,test_xplane,tests/sim/test_xplane.c platform/sim/xplane.c,,))
# ig: `cumulo ig` end to end: a CIGI host of our own (tests/sim/cigi_host.c) drives it, Wireshark's dissector (tshark)
# decodes the exchange; recorded FlightGear and X-Plane streams replayed to it (tests/sim/sim_replay.c).
$(B)/cigi_host: tests/sim/cigi_host.c tests/sim/cigi_encode.c $(B)/flags/test
	$(CC) $(CFLAGS_TEST) -Itests/sim -o $@ tests/sim/cigi_host.c tests/sim/cigi_encode.c -lm
$(B)/png_diff: tests/sim/png_diff.c $(CORE) $(B)/flags/test
	$(CC) $(CFLAGS_TEST) -o $@ tests/sim/png_diff.c $(CORE) $(LIB_LIBS) -lm
$(B)/sim_replay: tests/sim/sim_replay.c $(B)/flags/test
	$(CC) $(CFLAGS_TEST) -o $@ tests/sim/sim_replay.c
check: $(B)/cigi_host $(B)/png_diff $(B)/sim_replay
CHECK_TESTS += tests/sim/test_ig_cigi.sh tests/sim/test_ig_fg_xplane.sh

# tools: the Mie solver, the slab Monte Carlo and fitter, the path tracer.
$(eval $(call test_program,test_mie,tests/mie/test_mie.c $(MIE_LIB_OBJS),,))
CHECK_TESTS += tests/mie/test_mie_cli.sh
$(eval $(call test_program,test_slab,tests/slab/test_slab.c $(B)/obj/tools/slab/slab.o $(B)/obj/tools/slab/slab_phase.o \
  $(B)/obj/tools/slab/fitlib.o,$(GSL_CFLAGS),$(GSL_LIBS)))
CHECK_TESTS += tests/slab/test_slab_cli.sh
$(eval $(call test_program,test_pathtrace,tests/pathtrace/test_pt.c $(PT_OBJS) $(CORE),,$(LIB_LIBS)))
$(eval $(call test_program,test_pt_limits,tests/pathtrace/test_pt_limits.c $(PT_OBJS) $(CORE),,$(LIB_LIBS)))
CHECK_TESTS += tests/pathtrace/test_pt_cli.sh

# build: configuration, install and an embedding program built against the installed copy (tests/build/).
CHECK_TESTS += $(wildcard tests/build/test_*.sh)

# A real FlightGear drives cumulo ig (its 1.8 GB of data keep it out of make check; FGCHECK_INSTALL=1 installs it).
fgcheck: all $(B)/sim_replay
	$(TEST_ENV) sh tests/run_tests.sh tests/sim/fgcheck.sh
.PHONY: fgcheck

# The long versions (larger images, finer sweeps, thick slabs): `make stress`.
stress: all $(B)/test_extremes $(B)/test_ranges $(B)/test_slab $(B)/test_sky_field
	$(TEST_ENV) CUMULO_STRESS=1 sh tests/run_tests.sh $(B)/test_extremes $(B)/test_ranges tests/slab/test_slab_stress.sh \
	  $(B)/test_sky_field

# Rewrites the reference images from the current renderer (EGL); look at them before committing.
refs: $(B)/test_render
	$(TEST_ENV) CUMULO_WRITE_REFS=1 CMOCKA_TEST_ABORT=0 $(B)/test_render
.PHONY: refs stress
