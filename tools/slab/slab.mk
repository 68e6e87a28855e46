# tools/slab: Monte Carlo slab transport (build/cumulo-slab), the model fitter, and their tests.
