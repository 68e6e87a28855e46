# tools/mie: the Lorenz-Mie solver (build/cumulo-mie) and its tests. Filled in by the Mie work.
