"""Measures E, the Poisson ratio and the wave speed of each lattice (docs/model.md section 3)."""
