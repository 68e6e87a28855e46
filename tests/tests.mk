# tests/: unit tests (cmocka), image tests, physics and stability checks of the engine.
TEST_CFLAGS := $(CFLAGS_COMMON) $(call pc_cflags,cmocka) $(ENGINE_CFLAGS)
TEST_LIBS   := $(call pc_libs,cmocka) -lm

$(B)/test_scene: tests/test_scene.c $(B)/libcumulo.a
	$(CC) $(TEST_CFLAGS) -o $@ $< $(B)/libcumulo.a $(TEST_LIBS) -ldl
CHECK_TESTS += $(B)/test_scene

$(B)/test_phase: tests/test_phase.c $(B)/libcumulo.a
	$(CC) $(TEST_CFLAGS) -o $@ $< $(B)/libcumulo.a $(TEST_LIBS) -ldl
CHECK_TESTS += $(B)/test_phase

# -Wno-pedantic: _Float16 is an ISO/IEC TS 18661-3 extension type, used only here to emulate mediump.
$(B)/test_precision: tests/test_precision.c
	$(CC) $(TEST_CFLAGS) -Wno-pedantic -o $@ $< $(TEST_LIBS)
CHECK_TESTS += $(B)/test_precision

$(B)/test_math: tests/test_math.c $(B)/libcumulo.a
	$(CC) $(TEST_CFLAGS) -o $@ $< $(B)/libcumulo.a $(TEST_LIBS) -ldl
CHECK_TESTS += $(B)/test_math

HEADLESS_SRCS := platform/egl_common.c platform/egl_surfaceless.c platform/osmesa.c platform/headless_fbo.c
$(B)/test_render: tests/test_render.c tests/render_util.c $(HEADLESS_SRCS) $(B)/libcumulo.a $(B)/libcumulo_util.a
	$(CC) $(TEST_CFLAGS) $(call pc_cflags,egl osmesa) -o $@ tests/test_render.c tests/render_util.c $(HEADLESS_SRCS) \
	    $(B)/libcumulo.a $(B)/libcumulo_util.a $(call pc_libs,egl osmesa libpng) $(TEST_LIBS) -ldl
CHECK_TESTS += $(B)/test_render

$(B)/test_extremes: tests/test_extremes.c tests/render_util.c $(HEADLESS_SRCS) $(B)/libcumulo.a $(B)/libcumulo_util.a
	$(CC) $(TEST_CFLAGS) $(call pc_cflags,egl osmesa) -o $@ tests/test_extremes.c tests/render_util.c $(HEADLESS_SRCS) \
	    $(B)/libcumulo.a $(B)/libcumulo_util.a $(call pc_libs,egl osmesa libpng) $(TEST_LIBS) -ldl
CHECK_TESTS += $(B)/test_extremes

$(B)/test_sunmap: tests/test_sunmap.c tests/render_util.c $(HEADLESS_SRCS) $(B)/libcumulo.a $(B)/libcumulo_util.a
	$(CC) $(TEST_CFLAGS) $(call pc_cflags,egl osmesa) -o $@ tests/test_sunmap.c tests/render_util.c $(HEADLESS_SRCS) \
	    $(B)/libcumulo.a $(B)/libcumulo_util.a $(call pc_libs,egl osmesa libpng) $(TEST_LIBS) -ldl
CHECK_TESTS += $(B)/test_sunmap

# The long versions of the stability tests (larger images, finer sweeps).
stress: all $(B)/test_extremes
	$(TEST_ENV) CUMULO_STRESS=1 sh tests/run_tests.sh $(B)/test_extremes
.PHONY: stress

# Rewrites the reference images from the current renderer (EGL); look at them before committing.
refs: $(B)/test_render
	$(TEST_ENV) CUMULO_WRITE_REFS=1 CMOCKA_TEST_ABORT=0 $(B)/test_render
.PHONY: refs

CHECK_TESTS += tests/test_cli.sh

$(B)/test_ms: tests/test_ms.c tests/render_util.c $(HEADLESS_SRCS) $(B)/libcumulo.a $(B)/libcumulo_util.a
	$(CC) $(TEST_CFLAGS) $(call pc_cflags,egl osmesa) -o $@ tests/test_ms.c tests/render_util.c $(HEADLESS_SRCS) \
	    $(B)/libcumulo.a $(B)/libcumulo_util.a $(call pc_libs,egl osmesa libpng) $(TEST_LIBS) -ldl
CHECK_TESTS += $(B)/test_ms
CHECK_TESTS += tests/test_ms_slab.sh

$(B)/test_fallback: tests/test_fallback.c tests/render_util.c $(HEADLESS_SRCS) $(B)/libcumulo.a $(B)/libcumulo_util.a
	$(CC) $(TEST_CFLAGS) $(call pc_cflags,egl osmesa) -o $@ tests/test_fallback.c tests/render_util.c $(HEADLESS_SRCS) \
	    $(B)/libcumulo.a $(B)/libcumulo_util.a $(call pc_libs,egl osmesa libpng) $(TEST_LIBS) -ldl
CHECK_TESTS += $(B)/test_fallback
