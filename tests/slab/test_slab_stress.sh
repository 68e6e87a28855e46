#!/bin/sh
# make stress: the long slab tests (thin-T checks against adding-doubling, ~2 min CPU), build/test_slab with CUMULO_STRESS=1.
exec env CUMULO_STRESS=1 "${B:-build}/test_slab"
