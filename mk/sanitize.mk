# mk/sanitize.mk: the AddressSanitizer + UBSan build. `make check SANITIZE=1` compiles and links every object and
# program with the sanitizers (they sit in CC, so build/flags/* record them and switching SANITIZE rebuilds all) and
# runs make check's tests under them; `make sanitize` does that in a copy of the tree under $(B)/sanitize/, so the
# normal build is left as it is and the tests' build/ paths hold there (the copy has its own build/).
SANITIZE ?=
SAN_CFLAGS := -fsanitize=address,undefined -fno-omit-frame-pointer -fno-sanitize-recover=undefined
# Mesa is not instrumented and keeps allocations until exit: LeakSanitizer is told to ignore only its libraries
# (tests/sanitize/lsan.supp says why, entry by entry). The soak runs 4000 frames, not 10 000, with room for ASan's
# quarantine (freed blocks held back to catch a use after free), which grows the resident set by design: under the
# sanitizers LeakSanitizer checks leaks exactly, at exit, and make check keeps the 3 MB limit.
SAN_ASAN := detect_leaks=1:strict_string_checks=1:check_initialization_order=1:detect_stack_use_after_return=1
SAN_ENV  := CUMULO_SANITIZE=1 CUMULO_SOAK_FRAMES=4000 CUMULO_SOAK_RSS_KB=32768 ASAN_OPTIONS=$(SAN_ASAN) \
            LSAN_OPTIONS=suppressions=$(CURDIR)/tests/sanitize/lsan.supp:print_suppressions=0 \
            UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
ifeq ($(SANITIZE),1)
override CC := $(CC) $(SAN_CFLAGS)
TEST_ENV += $(SAN_ENV)
endif

# The copy holds what git tracks plus what it does not ignore (so uncommitted work is tested too), refreshed on each
# run with the sources' times kept, so a second run rebuilds only what changed. tests/build/test_build.sh is left out
# of the sanitized run: it rebuilds copies of the tree itself and links a program outside the tree, built without
# the sanitizers, against the installed library, which an instrumented library cannot serve. The VM tests
# (make vmcheck) are not part of make check, so they are not run here either.
SAN_TREE := $(B)/sanitize
.PHONY: sanitize
sanitize:
	@mkdir -p $(SAN_TREE)
	@find $(SAN_TREE) -mindepth 1 -maxdepth 1 ! -name build -exec rm -rf {} +
	@if git rev-parse >/dev/null 2>&1; then git ls-files -co --exclude-standard -z | \
	   xargs -0 tar -cf - --no-recursion; else tar --exclude=./build -cf - .; fi | tar -C $(SAN_TREE) -xf -
	@start=$$(date +%s); $(MAKE) -C $(SAN_TREE) --no-print-directory SANITIZE=1 check; rc=$$?; \
	  echo "sanitize: $$(( $$(date +%s) - start )) s"; exit $$rc
# tests/gpu/test_host_scene.sh is left out too: examples/host_scene opens its EGL display itself, as a host does, so
# cu_egl_keep_driver cannot keep Mesa's driver loaded there and the driver's 112-byte unload leak comes back from an
# "<unknown module>" that no suppression can name.
ifeq ($(SANITIZE),1)
CHECK_TESTS_RUN = $(filter-out tests/build/test_build.sh tests/gpu/test_host_scene.sh,$(CHECK_TESTS))
else
CHECK_TESTS_RUN = $(CHECK_TESTS)
endif
