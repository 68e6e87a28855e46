# tests/vm/vm.mk: `make vmcheck` runs the platform back ends against real kernel drivers in a small qemu VM (issue 8):
# vkms for DRM/KMS, gpio-sim for the GPIO knob, uinput for evdev knobs and keyboards. See tests/vm/README.md.
# Not part of `make check` (it needs qemu and ~5 minutes for the first kernel build); .ci/run runs it after.
VM_HELPERS := $(B)/vm/vm_kms $(B)/vm/vm_uinput

$(B)/vm/vm_kms: tests/vm/vm_kms.c
	@mkdir -p $(@D)
	$(CC) -std=c99 -Wall -Wextra $(WERROR) -O2 -g $(DRM_CFLAGS) $(LIB_CFLAGS) -o $@ $< $(DRM_LIBS) $(LIB_LIBS)

$(B)/vm/vm_uinput: tests/vm/vm_uinput.c
	@mkdir -p $(@D)
	$(CC) -std=c99 -Wall -Wextra $(WERROR) -O2 -g -o $@ $<

.PHONY: vmcheck vm-kernel vm-helpers vm-shell
vm-helpers: $(VM_HELPERS)

vm-kernel:
	@sh tests/vm/build-kernel.sh -j $(or $(VM_JOBS),2)

# VM_TESTS="drm gpio" runs only those guest scripts.
vmcheck: $(B)/cumulo $(VM_HELPERS)
	@sh tests/vm/vmcheck.sh $(VM_TESTS)
